"""The terrain scene (pt): the Warp render against the C reference pixel, the settings pinned to the C defaults, the
technique (update, resize), the image's content, the walk path and the command line."""
from __future__ import annotations

import dataclasses
import json
import subprocess
import sys

import numpy as np
import pytest

from pywarp.core.cbridge import TERRAIN_PARAMS, settings_values
from pywarp.core.pose import Pose
from pywarp.terrain.settings import PREVIEW, TEST_HEIGHTMAP, TerrainSettings
from pywarp.terrain.technique import (TerrainTechnique, render_pixels_c, render_pixels_warp, ground_height,
                                      walk_path)

SMALL = dict(width=96, height=54)


@pytest.fixture(scope="module")
def final_image():
    tech = TerrainTechnique(TerrainSettings(width=192, height=108))
    return tech.render(encode=False), tech.steps_taken()


@pytest.mark.spec("pt-alg-7.1.6", "pt-code-7.3", "pt-alg-7.3.4", "pt-alg-7.3-material")
@pytest.mark.parametrize("changes", [
    {},
    {"march": "bisect"},
    {"shadows": "hard", "fog": "corrected", "clouds": "thesis", "time_s": 7.5},
    {"rays_per_pixel": 4, "stage": "materials"},
    {"stage": "atmosphere", "seed": 5, "water_level": 0.0},
    dict(TEST_HEIGHTMAP, march="fixed", step_size=0.5),
    dict(TEST_HEIGHTMAP, march="fixed", step_size=0.5, slab=True, camera_y=30.0),
    {"camera_y": 40.0, "camera_pitch_deg": -30.0, "shadows": "hard"},
    {"slab": False, "march": "bisect"},
    dict(PREVIEW),
    {"precision_per_unit": 0.01, "camera_y": 30.0, "march": "dynamic"},
    {"march": "dynamic", "step_scale": 0.5, "shadow_min_step": 0.0},
    {"shadows": "hard", "shadow_min_step": 3.0},
], ids=["final", "bisect", "hard-thesis", "ss4-materials", "atmosphere-seed5", "test-fixed", "test-fixed-slab-above",
        "above-slab-hard", "no-slab-bisect", "preview", "precision-growth", "text-march-and-shadows",
        "hard-min-step"])
def test_warp_pixels_match_the_c_reference(changes):
    """The C reference pixel (ccl_terrain_pixel) and the Warp pixel perform the same float32 operations in the same
    order with the same libm calls: the results are expected bit-identical, and so are the step counts."""
    s = TerrainSettings(**SMALL, **changes)
    rng = np.random.default_rng(7)
    xs, ys = rng.integers(0, s.width, 24), rng.integers(0, s.height, 24)
    cw, sw = render_pixels_warp(s, xs, ys)
    cc, sc = render_pixels_c(s, xs, ys)
    np.testing.assert_array_equal(cw, cc)
    np.testing.assert_array_equal(sw, sc)


@pytest.mark.spec("pt-alg-7.1.6")
def test_the_frame_is_the_pixel_function():
    s = TerrainSettings(**SMALL)
    tech = TerrainTechnique(s)
    img = tech.render(encode=False)
    xs, ys = np.array([0, 13, 95, 50]), np.array([0, 40, 53, 20])
    cw, sw = render_pixels_warp(s, xs, ys)
    np.testing.assert_array_equal(img[ys, xs], cw)
    np.testing.assert_array_equal(tech.steps_taken()[ys, xs], sw)


def test_depth_is_the_distance_to_the_surface_the_pixel_shows():
    """The frame's depth (what the viewer's temporal reconstruction reprojects with): the point at that distance
    along each pixel's ray lies on the marched terrain (within PRECISION: Kod 7.5's hit test, the dynamic march) or
    on the water plane in front of it; the sky's pixels are -1; none for a supersampled frame."""
    from pywarp.kernels.camera import pose_camera

    s = TerrainSettings(**SMALL, march="dynamic", step_scale=0.5)
    tech = TerrainTechnique(s)
    tech.render()
    t = tech.depth().astype(np.float64)
    cam = pose_camera(Pose.from_settings(s), s.width, s.height)
    m = cam.inv_view_proj_rot.astype(np.float64)
    xs, ys = np.meshgrid(np.arange(s.width) + 0.5, np.arange(s.height) + 0.5)
    ndc = np.stack([2 * xs / s.width - 1, 1 - 2 * ys / s.height, np.ones_like(xs), np.ones_like(xs)], -1)
    d = (ndc @ m.T)[..., :3]
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    p = cam.eye.astype(np.float64) + d * t[..., None]
    sky, hit = t == -1.0, t > 0.0
    assert sky.any() and hit.any() and np.all(sky | hit)
    assert np.all(d[..., 1][sky & (d[..., 1] < -0.2)] > 1)  # no sky below the hills in front (a check that can fail)
    h = ground_height(s, p[..., 0][hit], p[..., 2][hit])
    water = np.abs(p[..., 1][hit] - s.water_level) < 1e-3
    land = np.abs(p[..., 1][hit] - h) < s.precision + 1e-3
    assert np.all(water | land), np.abs(p[..., 1][hit] - h)[~(water | land)].max()
    assert water.any() and land.mean() > 0.5
    tech.update(rays_per_pixel=4)
    tech.render()
    assert tech.depth() is None


def test_the_hashed_table_gives_the_same_fbm():
    """The scene's table (hashed_perm_array: the permutation and the 2-D lattice hashes) gives fbm_perm bit for bit
    what the plain permutation gives -- negative, large (near the 2^24 limit of the fraction) and non-finite
    coordinates included -- and its first 512 entries are the permutation (every other reader of perm)."""
    import warp as wp

    from pywarp.kernels import terrain as K
    from pywarp.kernels.noise import perm_array, perm_table

    @wp.kernel
    def fbm_kernel(x: wp.array(dtype=float), z: wp.array(dtype=float), perm: wp.array(dtype=wp.int32),
                   out: wp.array(dtype=float)):
        i = wp.tid()
        out[i] = K.fbm_perm(x[i], z[i], 1 + i % 9, perm)

    rng = np.random.default_rng(3)
    x = np.concatenate([rng.uniform(-300, 300, 4000), rng.uniform(-2.0 ** 22, 2.0 ** 22, 500), [np.inf, np.nan, 0.0,
                                                                                               -1.0, 255.5]])
    z = np.concatenate([rng.uniform(-300, 300, 4000), rng.uniform(-2.0 ** 22, 2.0 ** 22, 500), [0.0, 1.0, np.nan,
                                                                                               -256.0, 1e-30]])
    for seed in (0, 5):
        outs = []
        for perm in (perm_array(seed, "cpu"), K.hashed_perm_array(seed, "cpu")):
            out = wp.zeros(x.size, dtype=float, device="cpu")
            wp.launch(fbm_kernel, x.size, [wp.array(x.astype(np.float32), dtype=float, device="cpu"),
                                           wp.array(z.astype(np.float32), dtype=float, device="cpu"), perm, out],
                      device="cpu")
            outs.append(out.numpy())
        np.testing.assert_array_equal(outs[0], outs[1])
        assert np.isnan(outs[0][-5:-2]).all() and np.isfinite(outs[0][:-5]).all()
        np.testing.assert_array_equal(K.hashed_perm_array(seed, "cpu").numpy()[:512], perm_table(seed))


def test_settings_defaults_are_the_c_defaults():
    s = TerrainSettings()
    c = TERRAIN_PARAMS.defaults()
    mine = settings_values(s)
    computed = {"sun", "wind", "samples_per_axis"}  # from the settings' angles, wind_x/_z, rays_per_pixel
    assert set(c) - {"perm"} == set(mine) | computed  # every C field but the Perlin table comes from the settings
    mine.update({k: v for k, v in s.c_values().items() if k in computed})
    for name, v in c.items():
        if name in ("sun", "seed", "perm"):
            continue  # the sun comes from the settings' elevation and azimuth
        got = mine[name]
        if isinstance(v, tuple):
            np.testing.assert_allclose(np.float32(got), np.float32(v), err_msg=name)
        else:
            assert np.float32(got) == np.float32(v), name


def test_bad_settings_name_the_field():
    with pytest.raises(ValueError, match="max_steps"):
        TerrainSettings(max_steps=0)
    with pytest.raises(ValueError, match="rays_per_pixel"):
        TerrainSettings(rays_per_pixel=3)
    with pytest.raises(ValueError, match="normal_octaves_min"):
        TerrainSettings(normal_octaves_max=3, normal_octaves_min=4)
    with pytest.raises(ValueError, match="material_high"):
        TerrainSettings(material_low=5.0, material_high=5.0)
    with pytest.raises(ValueError, match="fog"):
        TerrainSettings(fog="sometimes")
    with pytest.raises(ValueError, match="precision"):
        TERRAIN_PARAMS.checked({"precision": float("nan")})


@pytest.mark.spec("pt-code-7.3", "pt-alg-7.3.4", "pt-7.3", "pt-code-7.10", "pt-code-7.11")
def test_final_image_has_sky_terrain_water_and_the_sun(final_image):
    img, steps = final_image
    assert np.all(np.isfinite(img)) and img.min() >= 0.0 and img.max() <= 1.0
    s = TerrainSettings(width=192, height=108)
    top = img[:8].reshape(-1, 3).mean(0)
    assert top[2] > top[0]  # blue sky at the top
    assert steps[:8].mean() < steps[-8:].mean()  # sky rays leave early, ground rays march
    # the sun glow: the brightest pixel lies towards the sun (left half, upper half)
    lum = img.mean(-1)
    y, x = np.unravel_index(np.argmax(lum), lum.shape)
    assert x < s.width // 2 and y < s.height // 2 and lum[y, x] > 0.95
    # water in view: stage 'final' differs from 'atmosphere' only where there is water
    no_water = TerrainTechnique(dataclasses.replace(s, stage="atmosphere")).render(encode=False)
    wet = np.any(np.abs(img - no_water) > 1e-6, axis=-1)
    assert 0.02 < wet.mean() < 0.6
    assert not wet[:20].any()  # no water in the sky


@pytest.mark.spec("pt-code-7.6", "pt-code-7.7")
def test_shadows_darken_and_soft_shadows_lie_between_none_and_hard():
    base = TerrainSettings(**SMALL, stage="materials")
    imgs = {k: TerrainTechnique(dataclasses.replace(base, shadows=k)).render(encode=False).mean()
            for k in ("none", "soft", "hard")}
    assert imgs["hard"] < imgs["none"] and imgs["soft"] < imgs["none"]


def test_same_seed_same_image_other_seed_differs():
    s = TerrainSettings(**SMALL)
    a = TerrainTechnique(s).render()
    b = TerrainTechnique(s).render()
    c = TerrainTechnique(dataclasses.replace(s, seed=3)).render()
    assert np.array_equal(a, b) and not np.array_equal(a, c)


def test_update_and_resize():
    tech = TerrainTechnique(TerrainSettings(**SMALL))
    a = tech.render()
    tech.update(time_s=30.0)  # clouds and waves move
    b = tech.render()
    assert a.shape == b.shape and not np.array_equal(a, b)
    tech.resize(40, 30)
    assert tech.render().shape == (30, 40, 3)
    with pytest.raises(ValueError, match="step_scale"):
        tech.update(step_scale=0.0)


def test_walk_path_stays_above_ground_and_water():
    s = TerrainSettings()
    poses = walk_path(30, s)
    assert len(poses) == 30 and isinstance(poses[0], Pose)
    xs = np.array([p.x for p in poses])
    zs = np.array([p.z for p in poses])
    ys = np.array([p.y for p in poses])
    ground = np.maximum(ground_height(s, xs, zs), s.water_level)
    assert np.all(ys - ground > 1.0)
    assert np.hypot(xs[-1] - xs[0], zs[-1] - zs[0]) > 40.0
    with pytest.raises(ValueError, match="frames"):
        walk_path(0, s)


def _cli(*args, timeout=240):
    return subprocess.run([sys.executable, "-m", "pywarp", *args], capture_output=True, text=True, timeout=timeout)


def test_cli_render_animate_and_bad_option(tmp_path):
    out = tmp_path / "t.png"
    r = _cli("render", "terrain", "--width", "64", "--height", "36", "--out", str(out), "--no-progress")
    assert r.returncode == 0, r.stderr
    assert out.exists() and "scene terrain" in r.stdout
    gif = tmp_path / "w.gif"
    r = _cli("animate", "terrain", "--frames", "3", "--width", "32", "--height", "18", "--out", str(gif),
             "--no-progress")
    assert r.returncode == 0, r.stderr
    assert gif.exists() and "path walk" in r.stdout
    r = _cli("render", "terrain", "--max-steps", "0", "--out", str(tmp_path / "x.png"), "--no-progress")
    assert r.returncode == 2 and "--max-steps" in r.stderr and not (tmp_path / "x.png").exists()


def test_cli_bench_supersampling_json():
    r = _cli("bench", "terrain", "supersampling", "--width", "24", "--height", "16", "--json")
    assert r.returncode == 0, r.stderr
    res = json.loads(r.stdout.strip().splitlines()[-1])
    assert [row["rays_per_pixel"] for row in res["rows"]] == [1, 4, 16]
    assert res["rows"][2]["cost_ratio"] > 2.0


@pytest.mark.spec("pt-code-7.5", "pt-code-7.7", "pt-alg-9-bisect")
@pytest.mark.parametrize("changes", [{}, {"march": "bisect", "shadows": "hard"}, {"camera_pitch_deg": 10.0},
                                     dict(TEST_HEIGHTMAP, slab=True, march="dynamic", camera_y=8.0)],
                         ids=["final", "bisect-hard", "looking-up", "test-map"])
def test_the_slab_changes_no_pixel_for_a_camera_inside_it(changes):
    """The slab (rising rays above bound + PRECISION stop, the soft shadow stops once its bound k (y - hmax) / t
    reaches the running minimum) is exact: the same image bit for bit, with fewer steps."""
    on = TerrainTechnique(TerrainSettings(**SMALL, **changes))
    img_on = on.render(encode=False)
    off = TerrainTechnique(TerrainSettings(**SMALL, **dict(changes, slab=False)))
    img_off = off.render(encode=False)
    np.testing.assert_array_equal(img_on, img_off)
    assert on.steps_taken().sum() < off.steps_taken().sum()


def test_the_slab_from_above_moves_hits_by_less_than_precision():
    """A camera above the slab starts its rays at the slab's top: the march's step sequence changes, the hits move
    along the ray by less than PRECISION (Kod 7.5's hit test: the dynamic march), so the image stays within a few
    display levels (and far fewer steps)."""
    changes = {"camera_y": 60.0, "camera_pitch_deg": -35.0, "shadows": "none", "march": "dynamic", "step_scale": 0.5}
    on = TerrainTechnique(TerrainSettings(**SMALL, **changes))
    off = TerrainTechnique(TerrainSettings(**SMALL, **dict(changes, slab=False)))
    a, b = on.render(encode=False), off.render(encode=False)
    assert np.abs(a - b).max() < 8.0 / 255.0
    assert np.abs(a - b).mean() < 0.5 / 255.0
    assert on.steps_taken().mean() < 0.8 * off.steps_taken().mean()


def test_preview_quality_is_the_reduced_frame_enlarged():
    s = TerrainSettings(width=64, height=35, quality="preview", preview_scale=2)
    tech = TerrainTechnique(s)
    img = tech.render(encode=False)
    assert img.shape == (35, 64, 3)
    small = TerrainTechnique(TerrainSettings(width=32, height=18, **PREVIEW)).render(encode=False)
    np.testing.assert_array_equal(img, np.repeat(np.repeat(small, 2, 0), 2, 1)[:35])
    tech.update(quality="full")  # back to the refined frame: full size, the settings as they are
    np.testing.assert_array_equal(tech.render(encode=False),
                                  TerrainTechnique(TerrainSettings(width=64, height=35)).render(encode=False))


def test_controls_mouse_look_and_w_walk_forward_above_the_ground():
    from pywarp.core.scenes import scene
    from pywarp.viewer.controls import Input, make_controls
    from pywarp.terrain.controls import CLEARANCE, WALK_SPEED, TerrainControls

    s = TerrainSettings(**SMALL)
    c = make_controls(scene("terrain"), s)
    assert isinstance(c, TerrainControls) and c.benchmark_keys == {"W"}
    assert c.preview(s) == {"quality": "preview", "preview_scale": 1}
    step = c.step(s, Input(dt=0.5, held=frozenset({"W"})))
    assert step.moving
    # yaw 0 looks along -z, pitch -8 deg: half a second of W moves 4 units along the view (or stays above ground)
    assert step.changes["camera_z"] == pytest.approx(s.camera_z - 0.5 * WALK_SPEED * np.cos(np.radians(-8.0)))
    assert step.changes["camera_x"] == pytest.approx(s.camera_x)
    step = c.step(s, Input(dt=0.1, mouse=(50.0, -20.0)))
    assert step.changes["camera_yaw_deg"] == pytest.approx(10.0)  # 0.2 deg per pixel, right turns towards +x
    assert step.changes["camera_pitch_deg"] == pytest.approx(-4.0)  # dragging up looks up
    assert "camera_x" not in step.changes
    assert not c.step(s, Input(dt=0.1, held=frozenset({"S", "A", "Up"}))).changes  # only the demo's keys
    # walking down into a hill: the eye stays CLEARANCE above the ground
    low = dataclasses.replace(s, camera_pitch_deg=-80.0, camera_y=float(ground_height(s, s.camera_x, s.camera_z)) + 1.6)
    for _ in range(20):
        ch = c.step(low, Input(dt=0.25, held=frozenset({"W"}))).changes
        low = dataclasses.replace(low, **ch)
        g = max(float(ground_height(low, low.camera_x, low.camera_z)), low.water_level)
        assert low.camera_y >= g + CLEARANCE - 1e-4


def test_precision_growing_with_distance_ends_the_march_earlier_and_zero_is_the_printed_test():
    """precision_per_unit c: the dynamic march hits when d < PRECISION + c t -- fewer steps for grazing rays, the
    hits at most c t higher; c = 0 is Kod 7.5."""
    dynamic = dict(SMALL, march="dynamic", step_scale=0.5)
    base = TerrainTechnique(TerrainSettings(**dynamic))
    grow = TerrainTechnique(TerrainSettings(**dynamic, precision_per_unit=0.004))
    a, b = base.render(encode=False), grow.render(encode=False)
    assert grow.steps_taken().sum() < base.steps_taken().sum()
    assert np.abs(a - b).mean() < 0.05 and not np.array_equal(a, b)
    zero = TerrainTechnique(TerrainSettings(**dynamic, precision_per_unit=0.0)).render(encode=False)
    np.testing.assert_array_equal(zero, a)


def test_changing_marks_the_water_and_the_viewer_prefers_temporal_previews():
    """TerrainTechnique.changing (what the temporal reconstruction colour-clamps rather than trusts by depth): true
    exactly at the pixels whose depth's point lies on the water plane -- found here from the ray geometry of the
    camera, not from the method -- false on the land above it and the sky; the technique asks the viewer for
    temporal previews; none for a supersampled frame."""
    from pywarp.kernels.camera import pose_camera
    from pywarp.terrain.technique import WATER_TOLERANCE

    s = TerrainSettings(**SMALL)
    tech = TerrainTechnique(s)
    assert tech.preview_mode == "temporal"
    tech.render()
    t = tech.depth().astype(np.float64)
    chg = tech.changing()
    assert chg.shape == t.shape and chg.dtype == bool
    cam = pose_camera(Pose.from_settings(s), s.width, s.height)
    m = cam.inv_view_proj_rot.astype(np.float64)
    xs, ys = np.meshgrid(np.arange(s.width) + 0.5, np.arange(s.height) + 0.5)
    ndc = np.stack([2 * xs / s.width - 1, 1 - 2 * ys / s.height, np.ones_like(xs), np.ones_like(xs)], -1)
    d = (ndc @ m.T)[..., :3]
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    y = cam.eye[1] + d[..., 1] * t
    water = (t > 0) & (np.abs(y - s.water_level) < 1e-3)
    land = (t > 0) & (y > s.water_level + 0.05 * (1 + t))
    assert water.sum() > 20 and land.sum() > 20
    assert np.all(chg[water]) and not np.any(chg[land]) and not np.any(chg[t < 0])
    assert np.all(np.abs(y[chg] - s.water_level) <= WATER_TOLERANCE * (1 + t[chg]) + 1e-6)
    tech.update(rays_per_pixel=4)
    tech.render()
    assert tech.changing() is None


def test_the_viewer_takes_the_techniques_preview_mode_unless_told():
    """The viewer's render thread previews through the temporal reconstruction where the technique asks for it
    (the terrain does) and `pywarp view --previews scaled|temporal` was not given; given, it wins."""
    from types import SimpleNamespace

    from pywarp.core import scenes as S
    from pywarp.viewer.session import RenderWorker

    sc = S.scene("terrain")
    for asked, expected in ((None, True), (False, False), (True, True)):
        worker = RenderWorker(sc, temporal=asked)
        try:
            assert worker.temporal == (asked is True)  # before the technique exists: only what was asked
            worker.tech = SimpleNamespace(preview_mode=TerrainTechnique.preview_mode)
            assert worker.temporal == expected
            worker.tech = SimpleNamespace(preview_mode="scaled")
            assert worker.temporal == (asked is True)
        finally:
            worker.tech = None
            worker.close()
