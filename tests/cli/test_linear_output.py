"""Linear image output: `pywarp render --out x.exr|x.npy` (display-linear float RGB before the sRGB encoding), numbered
frames from `pywarp animate --out frames/frame_%04d.png|.exr`, the refusal for a scene without the linear hook, and
no partial file after Ctrl-C."""
from __future__ import annotations

import importlib
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from pywarp.core import linear as L
from pywarp.core import scenes as SC

cli_main = importlib.import_module("pywarp.cli.main")

SIZE = ["--width", "48", "--height", "28"]


def _run(*argv):
    """Run the command in this process; its exit status (0, or SystemExit's code for an error)."""
    try:
        return cli_main.main(list(argv))
    except SystemExit as exc:
        return exc.code


def _srgb_encode(x):
    """The IEC 61966-2-1 sRGB encoding in float64 (independent of pywarp's colour_srgb_encode)."""
    x = np.clip(np.asarray(x, dtype=np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


@pytest.fixture(scope="module")
def clouds_outputs(tmp_path_factory):
    d = tmp_path_factory.mktemp("linear")
    for name in ("a.png", "a.npy", "a.exr", "f.exr", "d.png"):
        extra = {"f.exr": ["--exr-precision", "float"], "a.png": ["--tonemap", "none", "--exposure", "0"]}
        assert _run("render", *SIZE, "--out", str(d / name), "--no-progress", *extra.get(name, [])) == 0
    return d


def test_npy_is_float32_display_linear_rgb_and_the_png_is_its_srgb_encoding(clouds_outputs):
    lin = np.load(clouds_outputs / "a.npy")
    assert lin.dtype == np.float32 and lin.shape == (28, 48, 3)
    assert np.isfinite(lin).all()
    from PIL import Image

    png = np.asarray(Image.open(clouds_outputs / "a.png").convert("RGB")).astype(int)
    want = np.floor(_srgb_encode(lin) * 255.0 + 0.5).astype(int)
    assert np.abs(png - want).max() <= 1  # float32 kernel vs float64 formula: one level at a rounding edge
    # linear, not encoded: the encoding brightens every mid-tone
    mid = (lin > 0.05) & (lin < 0.8)
    assert mid.any() and np.all(png[mid] / 255.0 > lin[mid])


def test_the_default_png_is_the_display_transform_of_the_npy(clouds_outputs):
    """The default PNG: 2^-0.5 (the clouds' exposure_ev), Narkowicz's ACES fit, the sRGB encoding -- the .npy stays
    unclipped (the default view holds values above 1)."""
    from PIL import Image

    lin = np.load(clouds_outputs / "a.npy").astype(np.float64)
    assert lin.max() > 1.0
    x = lin * 2.0 ** -0.5
    aces = np.clip(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)
    want = np.floor(_srgb_encode(aces) * 255.0 + 0.5).astype(int)
    png = np.asarray(Image.open(clouds_outputs / "d.png").convert("RGB")).astype(int)
    assert np.abs(png - want).max() <= 1
    assert not (png == 255).any()


def test_exr_float_holds_the_npy_exactly_and_half_within_half_precision(clouds_outputs):
    lin = np.load(clouds_outputs / "a.npy")
    f = L.read_exr(clouds_outputs / "f.exr")
    assert f.dtype == np.float32 and np.array_equal(f, lin)
    h = L.read_exr(clouds_outputs / "a.exr")
    assert h.dtype == np.float16 and h.shape == lin.shape
    assert np.array_equal(h, lin.astype(np.float16))


def test_writers_refuse_non_finite_pixels_and_leave_nothing(tmp_path):
    img = np.ones((4, 5, 3), np.float32)
    img[2, 3, 1] = np.nan
    for name in ("x.npy", "x.exr"):
        with pytest.raises(RuntimeError, match="non-finite"):
            L.write_image(tmp_path / name, img)
    big = np.full((2, 2, 3), 1e6, np.float32)
    with pytest.raises(RuntimeError, match="half-float range"):
        L.write_exr(tmp_path / "big.exr", big)
    L.write_exr(tmp_path / "big.exr", big, precision="float")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.exr"]


class _NoLinear:
    def __init__(self, settings):
        self.settings = settings

    def render(self, pose=None, progress=None):
        return np.zeros((self.settings.height, self.settings.width, 3), np.uint8)


@pytest.fixture
def scene_without_linear():
    from dataclasses import dataclass

    from pywarp.core.params import Settings, param

    @dataclass(frozen=True)
    class TinySettings(Settings):
        width: int = param(8, unit="px", kind="int", lo=1, hi=64, doc="frame width", reason="tiny")
        height: int = param(6, unit="px", kind="int", lo=1, hi=64, doc="frame height", reason="tiny")

    SC.scenes()
    sc = SC.register(SC.Scene(name="tinytest", description="a scene without linear output", settings=TinySettings,
                              technique=_NoLinear,
                              paths={"still": SC.CameraPath("still", "no motion", lambda n, s: [None] * n)},
                              default_path="still"))
    yield sc
    with SC._lock:
        SC._scenes.pop("tinytest", None)


@pytest.mark.parametrize("out", ["x.npy", "x.exr"])
def test_a_scene_without_the_hook_is_refused_with_a_clear_error(tmp_path, capsys, scene_without_linear, out):
    assert _run("render", "tinytest", "--out", str(tmp_path / out), "--no-progress") == 2
    err = capsys.readouterr().err.strip()
    assert err == ("pywarp render: error: --out: scene 'tinytest' writes 8-bit images only, not the linear (.exr, "
                   ".npy) image of a scene such as 'clouds'; use .png")
    assert list(tmp_path.iterdir()) == []
    assert _run("animate", "tinytest", "--frames", "2", "--out", str(tmp_path / "f_%03d.exr"), "--no-progress") == 2
    assert "writes 8-bit images only" in capsys.readouterr().err
    assert not any(tmp_path.rglob("*.exr"))
    # its PNG frames work
    assert _run("animate", "tinytest", "--frames", "2", "--out", str(tmp_path / "f_%03d.png"), "--no-progress") == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f_000.png", "f_001.png"]


def test_animate_numbered_frames_are_the_frames_of_the_path_in_order(tmp_path):
    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.clouds.settings import CloudscapeSettings
    from PIL import Image

    args = ["--frames", "3", "--width", "32", "--height", "18", "--no-progress"]
    assert _run("animate", *args, "--out", str(tmp_path / "png" / "frame_%04d.png")) == 0
    assert _run("animate", *args, "--out", str(tmp_path / "exr" / "frame_%04d.exr"),
                "--exr-precision", "float") == 0
    assert sorted(p.name for p in (tmp_path / "png").iterdir()) == [f"frame_{i:04d}.png" for i in range(3)]
    assert sorted(p.name for p in (tmp_path / "exr").iterdir()) == [f"frame_{i:04d}.exr" for i in range(3)]
    # the same frames rendered here: animate's defaults (reprojection on), the path's poses, the wind time advancing
    sc = SC.scene("clouds")
    settings = CloudscapeSettings(**{**sc.command_defaults["animate"], "width": 32, "height": 18})
    poses = sc.path().poses(3, settings)
    tech = CloudscapeTechnique(settings)
    lin_tech = CloudscapeTechnique(settings)
    for i, pose in enumerate(poses):
        t = settings.time_s + i / 24.0 * 20.0
        tech.update(time_s=t)
        lin_tech.update(time_s=t)
        png = np.asarray(Image.open(tmp_path / "png" / f"frame_{i:04d}.png"))
        assert np.array_equal(png, tech.render(pose)), i
        assert np.array_equal(L.read_exr(tmp_path / "exr" / f"frame_{i:04d}.exr"), lin_tech.render_linear(pose)), i


@pytest.mark.parametrize("out,message", [
    ("frames/f_%d_%d.png", "--out must hold one frame number field"),
    ("f_%s.png", "--out must hold one frame number field"),
    ("f_%04d.jpg", "--out: numbered frames must end in .png or .exr or .npy"),
    ("f.png", "--out: frames need a numbered path such as frames/frame_%04d.png"),
    ("f.exr", "--out: frames need a numbered path such as frames/frame_%04d.exr"),
    ("d%02d/f_%04d.png", "--out: the frame number field must be in the file name"),
])
def test_animate_bad_frame_patterns_name_the_option(tmp_path, capsys, out, message):
    assert _run("animate", "--frames", "2", "--out", str(tmp_path / out), "--no-progress") == 2
    assert message in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_render_refuses_other_suffixes(tmp_path, capsys):
    assert _run("render", "--out", str(tmp_path / "x.tiff"), "--no-progress") == 2
    assert "--out must end in .png or .exr or .npy" in capsys.readouterr().err


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_during_exr_frames_leaves_only_complete_frames(tmp_path):
    folder = tmp_path / "frames"
    p = subprocess.Popen([sys.executable, "-m", "pywarp", "animate", "--width", "64", "--height", "36", "--frames",
                          "5000", "--out", str(folder / "f_%04d.exr"), "--no-progress"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path)
    try:
        deadline = time.monotonic() + 240
        while time.monotonic() < deadline and p.poll() is None:
            if folder.is_dir() and len(list(folder.glob("f_*.exr"))) >= 2:
                break
            time.sleep(0.05)
        assert p.poll() is None, p.communicate()
        p.send_signal(signal.SIGINT)
        _, stderr = p.communicate(timeout=120)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    assert p.returncode == 130, stderr
    assert stderr.strip().splitlines() == ["pywarp: interrupted"]
    names = sorted(f.name for f in folder.iterdir())
    assert names == [f"f_{i:04d}.exr" for i in range(len(names))]  # no hidden .part file, no gap
    for name in names:  # every frame left is complete
        img = L.read_exr(folder / name)
        assert img.shape == (36, 64, 3) and np.isfinite(img).all()
