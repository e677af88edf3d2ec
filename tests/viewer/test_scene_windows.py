"""The rain and flight scenes in a real window (Dear ImGui on our own Xvfb; skipped with the reason where there is
neither Xvfb nor a display): a script plays the texts' keys and a panel change; the screenshot matches the offline
render of the same camera and settings (SSIM >= 0.9), the keys moved what they say, the panel change changed the
image, and Esc exits 0 without a traceback."""
from __future__ import annotations

import json

import numpy as np
from PIL import Image

from pywarp.core import scenes as S


def ssim(a, b) -> float:
    from skimage.metrics import structural_similarity

    return structural_similarity(a, b, channel_axis=2, data_range=255)


def ok(proc):
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "Traceback" not in proc.stderr and "Segmentation" not in proc.stderr, proc.stderr[-3000:]


def settings_of(sc, path):
    side = json.loads(path.read_text())
    return side, sc.settings(**{k: (tuple(x) if isinstance(x, list) else x) for k, x in side["settings"].items()})


def test_rain_keys_and_panel_in_a_window(display, run_view, small_options, tmp_path):
    sc = S.scene("rain")
    script = tmp_path / "rain.json"
    script.write_text(json.dumps([
        {"t": 0.0, "key": "P"},                  # pause: the rain stands (time_s stays 0: the offline frame)
        {"t": 0.1, "key": "D"},                  # turn right 5 deg
        {"t": 0.2, "key": "Y"},                  # look up 5 deg
        {"t": 0.3, "key": "F"},                  # streaks -> drops
        {"t": 0.4, "key": "H"},                  # twice the drops
        {"t": 0.5, "screenshot": "a.png"},
        {"t": 0.6, "set": {"drops": 200}},       # a panel change
        {"t": 0.7, "screenshot": "b.png"},
        {"t": 0.8, "key": "Escape"}]))
    proc = run_view(["rain", *small_options(sc), "--background", "panorama", "--drops", "3000", "--pitch", "0",
                     "--script", str(script), "--state-out", "state.json"], tmp_path, display)
    ok(proc)
    st = json.loads((tmp_path / "state.json").read_text())["settings"]
    assert st["camera_yaw_deg"] == 5.0 and st["camera_pitch_deg"] == 5.0 and st["mode"] == "drops"
    assert st["drops"] == 200 and st["time_s"] == 0.0
    side, settings = settings_of(sc, tmp_path / "a.json")
    assert settings.drops == 6000 and settings.mode == "drops"
    a = np.asarray(Image.open(tmp_path / "a.png"))
    b = np.asarray(Image.open(tmp_path / "b.png"))
    assert ssim(a, sc.technique(settings).render()) >= 0.9
    assert np.mean(np.abs(a.astype(float) - b.astype(float))) > 0.5  # fewer drops changed the image


def test_flight_keys_and_panel_in_a_window(display, run_view, small_options, tmp_path):
    from pywarp.flight.technique import AircraftState, FlightPose

    sc = S.scene("flight")
    script = tmp_path / "fly.json"
    script.write_text(json.dumps([
        {"t": 0.0, "key": "Left", "hold": 1.0},   # bank left and turn
        {"t": 0.5, "key": "S", "hold": 0.5},      # slower
        {"t": 1.1, "screenshot": "a.png"},
        {"t": 1.2, "set": {"chase_distance_m": 60.0}},  # a panel change: the chase camera backs off
        {"t": 1.3, "screenshot": "b.png"},
        {"t": 1.4, "key": "Escape"}]))
    proc = run_view(["flight", *small_options(sc), "--cloud-count", "3", "--cloud-size", "32", "--time", "4",
                     "--script", str(script), "--state-out", "state.json"], tmp_path, display)
    ok(proc)
    side, settings = settings_of(sc, tmp_path / "a.json")
    pose = eval(side["pose"], {"FlightPose": FlightPose, "AircraftState": AircraftState})  # noqa: S307 (our own repr)
    tech = sc.technique(settings)
    start = tech.aircraft(4.0)
    a0 = pose.aircraft
    assert a0.roll < -0.05 and a0.heading < start.heading  # Left: banked and turned left
    assert a0.speed < start.speed  # S: slower
    a = np.asarray(Image.open(tmp_path / "a.png"))
    b = np.asarray(Image.open(tmp_path / "b.png"))
    assert ssim(a, tech.render(pose)) >= 0.9
    assert np.mean(np.abs(a.astype(float) - b.astype(float))) > 0.5
    assert json.loads((tmp_path / "state.json").read_text())["settings"]["chase_distance_m"] == 60.0
