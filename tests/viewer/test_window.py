"""The viewer in a real window (Dear ImGui, OpenGL) on a display server -- our own Xvfb, skipped with the reason
where neither Xvfb nor a display exists: every registered scene opens and Esc exits 0 without a traceback; a
scripted flight's screenshot matches the offline render of the same camera and settings (SSIM >= 0.9); the keys
moved the camera as they say; a panel change (coverage) changes the image; the image is really drawn in the window
(found in the window's own screenshot) and the window looks as before its background quad was dropped; real key
events (xdotool) drive the camera and quit."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time

import numpy as np
import pytest
from PIL import Image

from pywarp.core import scenes as S
from pywarp.viewer import controls as V

PANEL_WIDTH = 470  # pywarp.viewer.window.PANEL_WIDTH (not imported: it imports imgui-bundle)
#: the window's background and frame colours (sRGB) in a screenshot of the window as it was drawn with ImGui's own
#: full-window background (imgui-bundle 1.93's default theme)
WINDOW_BG = (30, 31, 33)
WINDOW_FRAME = (77, 78, 79)


def ssim(a, b) -> float:
    from skimage.metrics import structural_similarity

    return structural_similarity(a, b, channel_axis=2, data_range=255)


def ok(proc):
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "Traceback" not in proc.stderr and "Segmentation" not in proc.stderr, proc.stderr[-3000:]


def find(window: np.ndarray, image: np.ndarray) -> float:
    """Smallest mean abs difference of ``image`` placed anywhere right of the panel in ``window``."""
    h, w = image.shape[:2]
    best = np.inf
    win = window.astype(np.int16)
    img = image.astype(np.int16)
    for y in range(0, min(40, window.shape[0] - h + 1)):
        for x in range(PANEL_WIDTH - 10, min(PANEL_WIDTH + 40, window.shape[1] - w + 1)):
            best = min(best, float(np.mean(np.abs(win[y:y + h, x:x + w] - img))))
    return best


@pytest.mark.parametrize("name", list(S.scenes()))
def test_every_scene_opens_in_a_window_and_esc_quits(name, display, run_view, small_options, tmp_path):
    sc = S.scene(name)
    script = tmp_path / "s.json"
    script.write_text(json.dumps([{"t": 0.0, "key": "F1"}, {"t": 0.1, "screenshot": "shot.png"},
                                  {"t": 0.2, "key": "Escape"}]))
    proc = run_view([name, *small_options(sc), "--script", str(script), "--window-screenshot", "win.png",
                     "--state-out", "state.json"], tmp_path, display)
    ok(proc)
    state = json.loads((tmp_path / "state.json").read_text())
    assert state["scene"] == name and state["frames_shown"] >= 1 and not state["error"]
    shot = np.asarray(Image.open(tmp_path / "shot.png"))
    win = np.asarray(Image.open(tmp_path / "win.png"))[..., :3]
    assert shot.ndim == 3 and win.shape[1] > PANEL_WIDTH
    assert win.std() > 1.0  # the panel and the image were drawn


def test_clouds_script_screenshot_matches_the_offline_render(display, run_view, small_options, tmp_path):
    sc = S.scene("clouds")
    script = tmp_path / "fly.json"
    script.write_text(json.dumps([
        {"t": 0.0, "key": "W", "hold": 1.0},          # fly forward 0.5 km (yaw 0: along -z; pitch 20: climbing)
        {"t": 1.0, "key": "Right", "hold": 0.5},      # turn right 30 deg
        {"t": 1.6, "screenshot": "a.png"},
        {"t": 1.7, "set": {"coverage": 0.85}},        # a panel change
        {"t": 1.8, "screenshot": "b.png"},
        {"t": 1.9, "key": "Escape"}]))
    proc = run_view(["clouds", *small_options(sc), "--pitch", "20", "--script", str(script),
                     "--window-screenshot", "win.png", "--state-out", "state.json"], tmp_path, display)
    ok(proc)
    state = json.loads((tmp_path / "state.json").read_text())
    st = state["settings"]
    v = V.FREE_FLY_SPEED["km"]
    assert st["camera_z_km"] == pytest.approx(-v * np.cos(np.radians(20.0)), rel=1e-6)
    assert st["camera_altitude_km"] == pytest.approx(0.3 + v * np.sin(np.radians(20.0)), rel=1e-6)
    assert st["camera_yaw_deg"] == pytest.approx(0.5 * V.FREE_FLY_TURN_DEG_S, rel=1e-6)
    assert st["coverage"] == 0.85
    a = np.asarray(Image.open(tmp_path / "a.png"))
    b = np.asarray(Image.open(tmp_path / "b.png"))
    side = json.loads((tmp_path / "a.json").read_text())["settings"]
    settings = sc.settings(**{k: (tuple(x) if isinstance(x, list) else x) for k, x in side.items()})
    assert settings.camera_yaw_deg == pytest.approx(30.0) and settings.coverage == 0.5
    offline = sc.technique(settings).render()
    assert ssim(a, offline) >= 0.9
    assert np.mean(np.abs(a.astype(float) - b.astype(float))) > 1.0  # coverage changed the image
    win = np.asarray(Image.open(tmp_path / "win.png"))[..., :3]
    assert find(win, b) < 2.0  # the last frame is on screen, drawn 1:1 as a texture beside the panel
    # the window looks as it did when ImGui drew a background over all of it (colours read from a screenshot of
    # that version): the empty area below the image in the theme's window colour, a 1-px frame at the edges
    h, w = win.shape[:2]
    assert np.abs(win[h - 20:h - 4, w - 60:w - 4].astype(int) - WINDOW_BG).max() <= 2
    for edge in (win[h // 2, 0], win[h // 2, w - 1], win[0, w // 2], win[h - 1, w // 2]):
        assert np.abs(edge.astype(int) - WINDOW_FRAME).max() <= 2


@pytest.mark.skipif(shutil.which("xdotool") is None, reason="xdotool is not installed (apt-get install xdotool)")
def test_real_key_events_fly_the_camera_and_esc_exits_0(display, small_options, tmp_path):
    sc = S.scene("clouds")
    env = dict(os.environ, DISPLAY=display)
    env.pop("WAYLAND_DISPLAY", None)
    p = subprocess.Popen([sys.executable, "-m", "pywarp", "view", "clouds", *small_options(sc), "--pitch", "0",
                          "--state-out", "state.json"], cwd=tmp_path, env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    try:
        wid = ""
        t0 = time.time()
        while not wid and time.time() - t0 < 300 and p.poll() is None:
            time.sleep(0.5)
            wid = subprocess.run(["xdotool", "search", "--name", "pywarp view clouds"], env=env,
                                 capture_output=True, text=True).stdout.split()
            wid = wid[0] if wid else ""
        assert wid, "the window did not appear"
        time.sleep(2.0)
        x = lambda *a: subprocess.run(["xdotool", *a], env=env, check=True)  # noqa: E731
        x("windowfocus", "--sync", wid)
        x("keydown", "--window", wid, "w")
        time.sleep(1.0)
        x("keyup", "--window", wid, "w")
        time.sleep(0.5)
        x("key", "--window", wid, "Escape")
        out, err = p.communicate(timeout=120)
    finally:
        if p.poll() is None:
            p.kill()
            p.communicate()
    assert p.returncode == 0 and "Traceback" not in err, err[-3000:]
    st = json.loads((tmp_path / "state.json").read_text())["settings"]
    assert st["camera_z_km"] < -0.05 and st["camera_x_km"] == pytest.approx(0.0, abs=1e-9)  # W: forward, -z


TEXTURE_PROGRAM = r"""
import ctypes, ctypes.util, json
import numpy as np
from imgui_bundle import hello_imgui, immapp, immvision
from pywarp.viewer.window import _tex_sub_image

rng = np.random.default_rng(7)
a = rng.integers(0, 256, (45, 81, 3), dtype=np.uint8)  # 81 x 3 bytes a row: not a multiple of 4
b = rng.integers(0, 256, (45, 81, 3), dtype=np.uint8)
out = {}

def gui():
    if out:
        return
    gl = ctypes.CDLL(ctypes.util.find_library("GL"))
    gl.glPixelStorei(0x0CF5, 4)  # UNPACK_ALIGNMENT left at GL's default by whoever ran before
    t = immvision.GlTexture(a)
    out["sub"] = _tex_sub_image(t.texture_id, b)
    back = np.zeros_like(b)
    gl.glBindTexture(0x0DE1, t.texture_id)
    gl.glPixelStorei(0x0D05, 1)  # PACK_ALIGNMENT: rows packed tightly
    gl.glGetTexImage(0x0DE1, 0, 0x1907, 0x1401, back.ctypes.data_as(ctypes.c_void_p))
    gl.glBindTexture(0x0DE1, 0)
    v = ctypes.c_int(0)
    gl.glGetIntegerv(0x0CF5, ctypes.byref(v))
    out.update(equal_b=bool((back == b).all()), equal_a=bool((back == a).all()), alignment_after=v.value)
    del t
    hello_imgui.get_runner_params().app_shall_exit = True

params = hello_imgui.RunnerParams()
params.callbacks.show_gui = gui
immapp.run(params)
print(json.dumps(out))
"""


def test_texture_update_in_place_replaces_every_pixel(display, tmp_path):
    """The window's cheaper upload (glTexSubImage2D into the existing texture) gives the new image exactly, rows of
    a width whose bytes are not a multiple of 4 included, and leaves the unpack alignment as it found it."""
    env = dict(os.environ, DISPLAY=display)
    env.pop("WAYLAND_DISPLAY", None)
    proc = subprocess.run([sys.executable, "-c", TEXTURE_PROGRAM], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=300)
    ok(proc)
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    assert out["sub"], "libGL could not be called: the window falls back to re-creating the texture"
    assert out["equal_b"] and not out["equal_a"]
    assert out["alignment_after"] == 4
