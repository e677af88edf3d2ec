"""The vc renderer: Warp frame vs the scalar C reference at sampled pixels, no NaN/Inf anywhere (camera below, inside,
above the layer; both skies), determinism, temporal reprojection (static camera reproduces the full render; camera
inside/above falls back to full rendering), the optimisation ladder as work counts, bad input, and the CLI."""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from pywarp.clouds.cloudscape import CloudscapeSettings, render_frame_c, render_pixels_c, render_pixels_warp
from pywarp.clouds.technique import CloudscapeTechnique, flythrough_path
from pywarp.core.pose import Pose

SMALL = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)
SPEC = ("vc-A14", "vc-A17", "vc-A18", "vc-A19", "vc-A20", "vc-A21", "vc-A22", "vc-A24", "vc-A25", "vc-4.8")


def small(**kw) -> CloudscapeSettings:
    return CloudscapeSettings(**{"width": 96, "height": 54, **SMALL, **kw})


@pytest.fixture(scope="module")
def tech():
    return CloudscapeTechnique(small())


@pytest.mark.spec(*SPEC, "vc-A23", "vc-A28", "vc-A29", "vc-2.29", "vc-2.31")
@pytest.mark.parametrize("sky,jitter,extra", [
    ("preetham", "tilt", {}), ("gradient", "offset", {}),
    ("preetham", "none", dict(coverage_threshold="coverage", beer=False)),
    ("gradient", "tilt", dict(powder=False, light_detail=False, adaptive_samples=False)),
    # pitched up so far that every ray's view steps are short: the grouped march (tests/clouds/test_step_grouping.py)
    ("preetham", "offset", dict(camera_pitch_deg=45.0)),
    # the thesis's march: the early exit at 1/256 without its fill (tests/clouds/test_early_exit.py), every optical
    # depth towards the sun computed (tests/clouds/test_light_interp.py)
    ("gradient", "offset", dict(advanced={"exit_fill": 0, "exit_eps": 1.0 / 256.0, "light_interp": 0.0})),
    # the physical lighting model (docs/lighting.rst): physical units, the Mie phase delta-scaled, the octaves
    # weighted by the optical depth towards the sun
    ("preetham", "tilt", dict(units="physical", phase="mie", mie_delta=1.0, ms_depth=1.0, ms_thin=0.2,
                              aerial_km=0.0))])
def test_warp_pixels_match_c_reference(sky, jitter, extra):
    """300 sampled pixels of a 96x54 frame. Both sides evaluate the same float32 operations in the same order with
    the same libm (expf, powf, tanf); C is compiled without FMA contraction and Warp's CPU code does not contract
    either, so the results are expected bit-identical. The stated tolerance, 1e-5 absolute on values <= ~2, allows
    a few ulp of difference per operation accumulated over <= 128 march steps on another platform."""
    extra = {"camera_pitch_deg": 12.0, **extra}
    s = small(sky=sky, jitter=jitter, **extra)
    t = CloudscapeTechnique(s)
    rng = np.random.default_rng(7)
    xs, ys = rng.integers(0, s.width, 300), rng.integers(0, s.height, 300)
    w = render_pixels_warp(t, xs, ys)
    c = render_pixels_c(s, t.textures, xs, ys)
    assert np.all(np.isfinite(w)) and np.all(np.isfinite(c))
    np.testing.assert_allclose(w, c, rtol=0, atol=1e-5)
    # the sample must contain cloudy pixels, or the comparison would prove little
    clear = render_pixels_warp(CloudscapeTechnique(small(sky=sky, jitter=jitter, coverage=0.0, **extra)), xs, ys)
    assert np.mean(np.any(np.abs(w - clear) > 1e-3, axis=1)) > 0.2


@pytest.mark.spec(*SPEC)
def test_whole_frame_warp_equals_c_render():
    s = small(width=48, height=27, tonemap="none", exposure_ev=0.0)  # the C reference encodes by the plain clamp
    t = CloudscapeTechnique(s)
    lin = t.render(reprojection=False, encode=False)
    warp_img = t.render(reprojection=False)
    c_img = render_frame_c(s, t.textures, frame=1)  # the second render above was frame 1
    # 1 level of 8 bits: the float frames agree to 1e-5 (test_warp_pixels_match_c_reference), which can carry a value
    # across a quantization boundary, and np.round (half to even) differs from the renderer's floor(x + 0.5) at ties
    np.testing.assert_allclose(np.round(c_img * 255.0).astype(int), warp_img.astype(int), atol=1)
    assert lin.shape == (27, 48, 3)


@pytest.mark.spec(*SPEC, "vc-A24")
@pytest.mark.parametrize("altitude,pitch", [(0.0, 5.0), (0.3, 30.0), (2.5, 0.0), (3.9, -20.0), (6.0, -30.0),
                                            (6.0, 40.0), (0.3, -60.0)])
@pytest.mark.parametrize("sky", ["preetham", "gradient"])
def test_images_are_finite_everywhere(tech, altitude, pitch, sky):
    s = small(sky=sky)
    t = CloudscapeTechnique(s, textures=tech.textures)
    lin = t.render(Pose(0.0, altitude, 0.0, 30.0, pitch, 60.0), reprojection=False, encode=False)
    assert np.all(np.isfinite(lin))
    assert lin.min() >= 0.0


@pytest.mark.spec(*SPEC)
def test_same_seed_same_image_and_other_seed_differs():
    a = CloudscapeTechnique(small(seed=3)).render(reprojection=False)
    b = CloudscapeTechnique(small(seed=3)).render(reprojection=False)
    c = CloudscapeTechnique(small(seed=4)).render(reprojection=False)
    np.testing.assert_array_equal(a, b)
    assert np.mean(np.abs(a.astype(int) - c.astype(int))) > 1.0


@pytest.mark.spec("vc-A26", "vc-4.1", "vc-A22")
def test_reprojection_static_camera_converges_to_full_render(tech):
    """With a static camera and no jitter, after 16 frames every pixel was raymarched once in its own frame and
    carried over exactly: the reprojected frame equals the full render."""
    s = small(jitter="none", reprojection=True)
    t = CloudscapeTechnique(s, textures=tech.textures)
    full = t.render(reprojection=False, encode=False)
    t2 = CloudscapeTechnique(s, textures=tech.textures)
    for _ in range(16):
        img = t2.render(reprojection=True, encode=False)
    np.testing.assert_array_equal(img, full)


@pytest.mark.spec("vc-A26", "vc-A24")
def test_reprojection_falls_back_to_full_render_inside_and_above_the_layer(tech):
    pose = Pose(0.0, 2.5, 0.0, 10.0, 5.0, 60.0)
    s = small(reprojection=True, jitter="none")
    a = CloudscapeTechnique(s, textures=tech.textures).render(pose, reprojection=True, encode=False)
    b = CloudscapeTechnique(s, textures=tech.textures).render(pose, reprojection=False, encode=False)
    np.testing.assert_array_equal(a, b)


@pytest.mark.spec("vc-A18", "vc-A21")
def test_optimisation_ladder_reduces_the_work(tech):
    """The ladder of fig 4.17 as work (samples marched), which is what the time follows: adaptive counts take fewer
    samples than 128 everywhere the ray leaves the horizon; early exit takes fewer still where clouds are dense."""
    counts = {}
    for name, kw in {"unoptimised": dict(adaptive_samples=False, early_exit=False),
                     "adaptive_samples": dict(adaptive_samples=True, early_exit=False),
                     "early_exit": dict(adaptive_samples=True, early_exit=True)}.items():
        # the thesis's march (no refinement: its sub-steps add samples where the coarse steps are long)
        t = CloudscapeTechnique(small(camera_pitch_deg=25.0, refine_step_km=0.0, **kw), textures=tech.textures)
        t.render(reprojection=False)
        counts[name] = t.samples_taken().astype(np.int64)
    assert counts["unoptimised"].max() == 128
    assert np.all(counts["adaptive_samples"] <= counts["unoptimised"])
    assert counts["adaptive_samples"].sum() < 0.9 * counts["unoptimised"].sum()
    assert np.all(counts["early_exit"] <= counts["adaptive_samples"])
    assert counts["early_exit"].sum() < counts["adaptive_samples"].sum()


def test_flythrough_climbs_through_the_layer():
    s = CloudscapeSettings()
    poses = flythrough_path(30, s)
    alts = [p.y for p in poses]
    assert alts[0] == s.camera_altitude_km and alts[-1] > s.layer_top_km
    assert all(b >= a for a, b in zip(alts, alts[1:]))
    with pytest.raises(ValueError, match="frames must be >= 1"):
        flythrough_path(0, s)


def _cli(*args, cwd):
    # cwd: never the repository root, where `python -m` would import the source folder instead of the package
    return subprocess.run([sys.executable, "-m", "pywarp", *args], capture_output=True, text=True, cwd=cwd)


def test_cli_render_writes_png(tmp_path):
    out = tmp_path / "c.png"
    res = _cli("render", "--width", "64", "--height", "36", "--out", str(out), "--no-progress", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    from PIL import Image

    img = np.asarray(Image.open(out))
    assert img.shape == (36, 64, 3) and img.std() > 1.0
    # no --out: the scene's default file in the current folder (the README's `pywarp render`)
    res = _cli("render", "--width", "32", "--height", "18", "--no-progress", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert np.asarray(Image.open(tmp_path / "cloudscape.png")).shape == (18, 32, 3)


@pytest.mark.parametrize("args,message", [
    (["--width", "-5"], "pywarp render: error: --width must be in [1, 8192], got -5"),
    (["--width", "1.5"], "pywarp render: error: --width must be an integer, got '1.5'"),
    (["--turbidity", "12"], "pywarp render: error: --turbidity must be in [2, 10], got 12"),
    (["--turbidity", "abc"], "pywarp render: error: --turbidity must be a number, got 'abc'"),
    (["--sun-elevation", "-3"], "pywarp render: error: --sun-elevation must be in [0, 90], got -3"),
    (["--sky", "gradient", "--sun-elevation", "-3"], "pywarp render: error: --sun-elevation must be in [0, 90], got -3"),
    (["--sky", "hosek"], "pywarp render: error: --sky must be one of 'preetham', 'gradient', got 'hosek'"),
    (["--layer-top", "1"], "pywarp render: error: --layer-top must be > layer_base_km (1.5 km), got 1.0"),
    (["--device", "cuda:9"], "pywarp render: error: --device must be one of 'cpu'"),
    (["--out", "/nonexistent-dir/x.png"], "pywarp render: error: --out: folder '/nonexistent-dir' does not exist"),
    (["--out", "x.jpg"], "pywarp render: error: --out must end in .png"),
    (["nosuchscene"], "pywarp render: error: scene must be one of 'clouds'"),
])
def test_cli_render_bad_arguments_one_line_no_file(tmp_path, args, message):
    res = _cli("render", "--width", "32", "--height", "18", *args, cwd=tmp_path)
    assert res.returncode == 2
    assert res.stderr.strip().splitlines()[-1].startswith(message), res.stderr
    assert len(res.stderr.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []


def test_cli_animate_gif_and_bad_frames(tmp_path):
    out = tmp_path / "f.gif"
    res = _cli("animate", "--width", "48", "--height", "28", "--frames", "3", "--out", str(out), "--no-progress",
               cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    from PIL import Image

    with Image.open(out) as im:
        assert im.n_frames == 3
    for args, message in ((["--frames", "0"], "--frames must be in [1, 100000], got 0"),
                          (["--time-scale", "-1"], "--time-scale must be in [0, 1e+06], got -1"),
                          (["--fps", "0"], "--fps must be in [0.01, 240], got 0"),
                          (["--fps", "1e-6"], "--fps must be in [0.01, 240], got 1e-6"),
                          (["--path", "orbit"], "--path must be one of 'flythrough', got 'orbit'")):
        res = _cli("animate", *args, "--out", str(tmp_path / "g.gif"), cwd=tmp_path)
        assert res.returncode == 2 and res.stderr.strip() == "pywarp animate: error: " + message, res.stderr
    res = _cli("animate", "--width", "49", "--height", "28", "--out", str(tmp_path / "g.mp4"), cwd=tmp_path)
    assert res.returncode == 2 and "must be even for MP4" in res.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.gif"]


def test_cli_help_shows_units_ranges_choices_and_the_path_start(tmp_path):
    res = _cli("animate", "--help", cwd=tmp_path)
    assert res.returncode == 0
    text = " ".join(res.stdout.split())
    assert "STR" not in text
    assert "(--altitude, --pitch, --yaw, --camera-x, --camera-z) set the start of the path" in text
    for opt in ("--altitude", "--pitch", "--yaw"):
        i = text.index(opt + " FLOAT ")
        assert "the start of the camera path" in text[i:i + 300], opt
    assert "--time-scale FLOAT simulated seconds per video second" in text and "[0, 1e+06]" in text
    assert "default: 640" in text  # the animate frame width
    res = _cli("render", "--help", cwd=tmp_path)
    text = " ".join(res.stdout.split())
    assert "--turbidity FLOAT Preetham turbidity (the range of Preetham's fit); [2, 10]; default: 2.5" in text
    assert "--sky {preetham,gradient}" in text and "--sun-elevation FLOAT" in text and "[deg]; [0, 90]" in text
    assert "--reprojection" not in text  # one image has no previous frame


def test_cli_render_is_the_technique_render_pixel_for_pixel(tmp_path):
    """`pywarp render` with options = CloudscapeTechnique with the same settings (the renderer does not change)."""
    from PIL import Image

    out = tmp_path / "c.png"
    res = _cli("render", "clouds", "--width", "40", "--height", "24", "--sun-elevation", "8", "--coverage", "0.6",
               "--base-size", "32", "--detail-size", "16", "--curl-size", "32", "--weather-size", "64", "--out",
               str(out), "--no-progress", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    img = np.asarray(Image.open(out))
    ref = CloudscapeTechnique(small(width=40, height=24, sun_elevation_deg=8.0, coverage=0.6)).render(
        reprojection=False)
    np.testing.assert_array_equal(img, ref)


@pytest.mark.spec("vc-A28")
def test_gradient_sky_low_sun_renders_and_below_the_horizon_is_refused():
    """The gradient sky lights the clouds from the sun direction, which is not defined below the horizon: refused
    (the same domain as the Preetham sky); at the horizon it renders finite pixels."""
    lin = CloudscapeTechnique(small(sky="gradient", sun_elevation_deg=0.0)).render(reprojection=False, encode=False)
    assert np.all(np.isfinite(lin)) and lin.min() >= 0.0
    with pytest.raises(ValueError, match=r"^sun_elevation_deg must be in \[0, 90\], got -0\.5$"):
        small(sky="gradient", sun_elevation_deg=-0.5)


@pytest.mark.spec("vc-A14")
@pytest.mark.parametrize("altitude", [0.0, 0.3, 6.0])
def test_ground_below_the_horizon_sky_above(altitude):
    """Rays that hit the Earth sphere show the ground colour, the others the sky (also for a camera on the ground).
    No clouds (coverage 0), so nothing stands between the camera and the ground. The thesis's lighting: a flat
    ground colour (the sky lighting's lit ground: tests/clouds/test_lighting.py)."""
    s = small(sky="gradient", coverage=0.0, jitter="none", lighting="thesis")
    t = CloudscapeTechnique(s)
    lin = t.render(Pose(0.0, altitude, 0.0, 0.0, 0.0, 60.0), reprojection=False, encode=False)
    ground = np.array(t.params.ground_colour, dtype=np.float32)
    np.testing.assert_array_equal(lin[-1, s.width // 2], ground)  # bottom row looks 30 deg down
    assert np.abs(lin[0, s.width // 2] - ground).max() > 0.1  # top row looks 30 deg up: sky


@pytest.mark.spec("vc-2.31", "vc-A20")
def test_lighting_terms_switches_only_brighten(tech):
    """Replacing the powder or the Beer term of vc-2.31 by 1 can only raise the light of every sample (both terms
    are <= 1) while the opacity is unchanged, so every pixel gets at least as bright; and some clouds change. Every
    sample computes its own optical depth towards the sun (light_interp 0): where a sample interpolates depends on
    its neighbours' lights, so it could differ between the two models."""
    exact = dict(advanced={"light_interp": 0.0})
    s = small(sky="gradient", jitter="none", camera_pitch_deg=15.0, powder=True, **exact)  # vc-2.31 as printed
    on = CloudscapeTechnique(s, textures=tech.textures).render(reprojection=False, encode=False)
    for kw in (dict(powder=False), dict(beer=False, powder=True)):
        off = CloudscapeTechnique(small(sky="gradient", jitter="none", camera_pitch_deg=15.0, **kw, **exact),
                                  textures=tech.textures).render(reprojection=False, encode=False)
        assert np.all(off >= on)
        assert np.mean(off - on) > 1e-3


@pytest.mark.spec("vc-2.29")
def test_more_coverage_more_cloud_with_one_minus_threshold():
    """With C = 1 - D_h, the weather map's coverage raises the cloud amount monotonically (the difference to the
    clear sky grows); the literal reading C = D_h is the other option (see cclouds/cloudscape.c)."""
    clear = CloudscapeTechnique(small(coverage=0.0, jitter="none")).render(reprojection=False, encode=False)
    amount = []
    for c in (0.25, 0.5, 0.75):
        img = CloudscapeTechnique(small(coverage=c, jitter="none")).render(reprojection=False, encode=False)
        amount.append(float(np.mean(np.abs(img - clear))))
    assert amount[0] < amount[1] < amount[2]


import warp as wp  # noqa: E402

from pywarp.clouds.cloudscape import SkyModel  # noqa: E402


@wp.kernel
def _flat_sky_kernel(row0: int, colour: wp.vec3, frame_buffer: wp.array3d(dtype=float)):
    i, j = wp.tid()
    for ch in range(3):
        frame_buffer[row0 + i, j, ch] = colour[ch]


class FlatSky(SkyModel):
    """A user's own sky model: one colour everywhere (full frames only, for the test)."""

    kind = -1

    def update(self, settings):
        self.sun = settings.sun()
        self.colour = wp.vec3(0.2, 0.4, 0.8)

    def render(self, frame_buffer, camera, frame, reprojection, params, launcher):
        launcher.launch(_flat_sky_kernel, frame_buffer.shape[0], frame_buffer.shape[1], [self.colour],
                        [frame_buffer])


@pytest.mark.spec("vc-A28")
def test_a_user_defined_sky_model_is_used_as_background():
    s = small(coverage=0.0)  # no clouds: the frame is the sky model's output (and the ground)
    sky = FlatSky(s)
    t = CloudscapeTechnique(s, sky=sky)
    lin = t.render(reprojection=False, encode=False)
    np.testing.assert_allclose(lin[0], np.broadcast_to([0.2, 0.4, 0.8], lin[0].shape), rtol=0, atol=1e-7)
    t.update(time_s=5.0)  # settings changes keep the user's sky
    assert t.sky is sky
