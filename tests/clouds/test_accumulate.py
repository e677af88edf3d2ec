"""Noise-free stills: ``CloudscapeTechnique.render_accumulated`` / ``pywarp render clouds --accumulate N``.

N frames, each through the camera moved by a sub-pixel offset of the R2 sequence and with its own ray jitter, averaged
in display-linear space and encoded once. Checked: N = 1 is ``render`` bit for bit; the frame-to-frame noise of a
fixed camera falls with N; the offsets are a low-discrepancy sequence (properties of the points); the jittered camera
moves the image by the stated fraction of a pixel in the stated direction; bad N is refused, naming the option,
before any kernel runs; the same inputs give the same image."""
from __future__ import annotations

import importlib

import numpy as np
import pytest

from pywarp.clouds.cloudscape import CloudscapeSettings
from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.core.pose import Pose
import pywarp
from pywarp.kernels.camera import camera_look_at, subpixel_jitter

cli_main = importlib.import_module("pywarp.cli.main")

SMALL = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)
#: a low camera pitch puts the distant, noisy cloud band near the horizon into the frame
POSE = Pose(0.0, 0.3, 0.0, 0.0, 8.0, 60.0)


def small(**kw) -> CloudscapeSettings:
    return CloudscapeSettings(**{"width": 96, "height": 54, **SMALL, **kw})


@pytest.fixture(scope="module")
def textures():
    return CloudscapeTechnique(small()).textures


def fresh(textures, **kw) -> CloudscapeTechnique:
    return CloudscapeTechnique(small(**kw), textures=textures)


def test_render_accumulated_one_frame_is_render_bit_for_bit(textures):
    a = fresh(textures).render(POSE, reprojection=False)
    b = fresh(textures).render_accumulated(POSE, 1)
    assert a.dtype == b.dtype == np.uint8 and np.array_equal(a, b)
    lin_a = fresh(textures).render(POSE, reprojection=False, encode=False)
    lin_b = fresh(textures).render_accumulated(POSE, 1, encode=False)
    assert lin_b.dtype == np.float32 and np.array_equal(lin_a, lin_b)
    # the setting is the default n, and reprojection stays off even when the settings ask for it
    c = fresh(textures, accumulate=1, reprojection=True).render_accumulated(POSE)
    assert np.array_equal(a, c)


def test_accumulation_lowers_the_frame_to_frame_noise(textures):
    """Two accumulations of a fixed camera that differ only in their frame counters (0 and 1000: independent ray
    jitter, the same sub-pixel offsets) differ by the noise alone. With independent noise the mean absolute
    difference of an N-frame average falls as 1/sqrt(N) for Gaussian noise (1/4 at N = 16) and more slowly for
    sparse salt-and-pepper outliers (whose mean absolute value an average only spreads over more pixels); N = 16
    must at least halve it. The thesis's tilt jitter (the noisiest) makes the noise measurable at this small size;
    measured here: 0.32 (0.36 with the offset jitter, whose single frames differ 16 times less)."""
    t = fresh(textures, jitter="tilt")

    def noise(n):
        t.frame = 0
        a = t.render_accumulated(POSE, n, encode=False)
        t.frame = 1000
        b = t.render_accumulated(POSE, n, encode=False)
        return float(np.mean(np.abs(a - b)))

    one, sixteen = noise(1), noise(16)
    assert one > 1e-3  # the single frames are noisy, or the comparison would prove nothing
    assert sixteen / one < 0.5, (one, sixteen)


def test_render_accumulated_is_deterministic(textures):
    a = fresh(textures).render_accumulated(POSE, 3)
    b = fresh(textures).render_accumulated(POSE, 3)
    assert np.array_equal(a, b)
    # and it depends on the frame counter it starts from (each frame its own ray jitter)
    t = fresh(textures)
    t.frame = 7
    assert not np.array_equal(a, t.render_accumulated(POSE, 3))


def test_render_accumulated_progress_covers_the_whole_accumulation(textures):
    seen = []
    fresh(textures).render_accumulated(POSE, 3, progress=seen.append)
    assert len(seen) >= 3 and all(0.0 < f <= 1.0 / 3.0 + 1e-12 for f in seen)
    assert sum(seen) == pytest.approx(1.0)


@pytest.mark.parametrize("n,exc", [(0, ValueError), (1025, ValueError), (-3, ValueError), (2.5, TypeError),
                                   (True, TypeError), ("4", TypeError)])
def test_bad_n_is_refused_before_any_kernel_runs(textures, monkeypatch, n, exc):
    t = fresh(textures)

    def no_kernels(*args, **kwargs):
        raise AssertionError("a frame was rendered")

    monkeypatch.setattr(t, "render", no_kernels)
    monkeypatch.setattr(t.launcher, "launch", no_kernels)
    with pytest.raises(exc, match="accumulate"):
        t.render_accumulated(POSE, n)
    with pytest.raises(exc, match="accumulate"):
        small(accumulate=n)


@pytest.mark.parametrize("value,message", [("0", "--accumulate must be in [1, 1024], got 0"),
                                           ("1025", "--accumulate must be in [1, 1024], got 1025"),
                                           ("x", "--accumulate must be an integer, got 'x'")])
def test_cli_bad_accumulate_is_one_line_naming_the_option(tmp_path, capsys, monkeypatch, value, message):
    def no_technique(*args, **kwargs):
        raise AssertionError("the technique was built")

    monkeypatch.setattr(CloudscapeTechnique, "__init__", no_technique)
    out = tmp_path / "x.png"
    with pytest.raises(SystemExit) as exc:
        cli_main.main(["render", "clouds", "--accumulate", value, "--out", str(out), "--no-progress"])
    assert exc.value.code == 2
    assert capsys.readouterr().err.strip() == f"pywarp render: error: {message}"
    assert not out.exists()


def test_cli_accumulate_writes_the_accumulated_still(tmp_path, textures, capsys):
    from PIL import Image

    out = tmp_path / "still.png"
    args = ["render", "clouds", "--width", "48", "--height", "27", "--pitch", "8", "--accumulate", "3", "--out",
            str(out), "--no-progress"] + [f"--{k.replace('_', '-')}={v}" for k, v in SMALL.items()]
    assert cli_main.main(args) == 0
    assert "3 frames accumulated" in capsys.readouterr().out
    t = CloudscapeTechnique(small(width=48, height=27, camera_pitch_deg=8.0), textures=textures)
    assert np.array_equal(np.asarray(Image.open(out).convert("RGB")), t.render_accumulated(None, 3))


def test_accumulate_is_an_option_of_render_only():
    from pywarp.cli.main import build_parser

    helps = {cmd: build_parser()._subparsers._group_actions[0].choices[cmd].format_help()
             for cmd in ("render", "animate", "view")}
    assert "--accumulate" in helps["render"]
    assert "--accumulate" not in helps["animate"] and "--accumulate" not in helps["view"]


# --- the jitter sequence and the jittered camera -------------------------------------------------------------------


def _l2_star_discrepancy(p: np.ndarray) -> float:
    """Warnock's closed form of the L2 star discrepancy of points p in [0, 1)^2."""
    n = len(p)
    x, y = p[:, 0], p[:, 1]
    t2 = np.sum((1.0 - x ** 2) * (1.0 - y ** 2)) / (2.0 * n)
    t3 = np.sum((1.0 - np.maximum(x[:, None], x[None, :])) * (1.0 - np.maximum(y[:, None], y[None, :]))) / n ** 2
    return float(np.sqrt(1.0 / 9.0 - t2 + t3))


def test_subpixel_jitter_starts_at_the_pixel_centre_and_stays_in_the_pixel():
    o = subpixel_jitter(1024)
    assert o.shape == (1024, 2) and np.array_equal(o[0], [0.0, 0.0])
    assert np.all(o >= -0.5) and np.all(o < 0.5)
    assert len({tuple(r) for r in o}) == 1024
    assert np.array_equal(subpixel_jitter(16), o[:16])  # a prefix of one sequence: n frames reuse n - 1's offsets


def test_subpixel_jitter_is_low_discrepancy():
    """Two properties that random points do not have. (1) Packing: every prefix of the R2 sequence keeps its points
    at least ~0.55 / sqrt(n) apart on the torus (Roberts 2018; measured minimum over n <= 1024: 0.549 / sqrt(n),
    bound 0.5); uniform random points come as close as ~0.05-0.1 / sqrt(n). (2) The L2 star discrepancy falls
    nearly as log(n) / n (fitted exponent -0.89 over n = 64..1024), random points only as n^-1/2: the bound -0.75
    lies between, and at n = 1024 the discrepancy is below a quarter of that of random points (measured 0.13)."""
    p = subpixel_jitter(1024) + 0.5
    d = np.abs(p[:, None, :] - p[None, :, :])
    d = np.sqrt(np.sum(np.minimum(d, 1.0 - d) ** 2, axis=-1))
    np.fill_diagonal(d, np.inf)
    worst = min(d[:n, :n].min() * np.sqrt(n) for n in range(2, 1025))
    assert worst >= 0.5, worst
    ns = np.array([64, 128, 256, 512, 1024])
    disc = np.array([_l2_star_discrepancy(p[:n]) for n in ns])
    slope = np.polyfit(np.log(ns), np.log(disc), 1)[0]
    assert slope < -0.75, slope
    rng = np.random.default_rng(20201)
    random_disc = np.mean([_l2_star_discrepancy(rng.random((1024, 2))) for _ in range(10)])
    assert disc[-1] < 0.25 * random_disc, (disc[-1], random_disc)


@pytest.mark.parametrize("dx,dy,to", [(1.0, 0.0, (1, 0)), (0.0, 1.0, (0, 1)), (-2.0, 3.0, (-2, 3))])
def test_jittered_camera_moves_the_sample_point_by_the_offset(dx, dy, to):
    """Whole-pixel offsets make the exact check: pixel (x, y) of the jittered camera sees what pixel (x + dx,
    y + dy) of the camera sees (y down). float32 matrices: directions agree to a few ulp of 1."""
    w, h = 64, 36
    cam = camera_look_at((0.1, 0.3, -0.2), (0.5, 0.6, -1.0), fov_y=1.0, aspect=w / h)
    jit = cam.jittered(dx, dy, w, h)
    xs, ys = np.meshgrid(np.arange(8, 40), np.arange(6, 30))
    got = pywarp.camera_ray(xs, ys, w, h, jit)
    want = pywarp.camera_ray(xs + to[0], ys + to[1], w, h, cam)
    np.testing.assert_allclose(got, want, rtol=0, atol=2e-6)
    # sub-pixel offsets add up: two half offsets are the whole one
    halves = cam.jittered(0.5 * dx, 0.5 * dy, w, h).jittered(0.5 * dx, 0.5 * dy, w, h)
    np.testing.assert_allclose(pywarp.camera_ray(xs, ys, w, h, halves), want, rtol=0, atol=2e-6)


def test_jittered_camera_without_offset_is_the_camera():
    cam = camera_look_at((0.0, 0.3, 0.0), (0.0, 0.5, -1.0))
    j = cam.jittered(0.0, 0.0, 96, 54)
    for name in ("eye", "view", "proj", "view_proj", "inv_view_proj", "inv_view_proj_rot"):
        assert np.array_equal(getattr(cam, name), getattr(j, name)), name
    with pytest.raises(ValueError, match="dx_px"):
        cam.jittered(float("nan"), 0.0, 96, 54)
    with pytest.raises(ValueError, match="width"):
        cam.jittered(0.1, 0.0, 0, 54)
