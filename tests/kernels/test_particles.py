"""Topic tests of pywarp.kernels.particles and its host side pywarp.rain.particles (rr-code-5.2.2, rr-alg-3.2.3,
rr-alg-3.1.2, rr-code-5.2.3/5.2.4): particle counts of both variants, determinism, spawn box and sizes, terminal speeds
from Table 2.2, frame-rate independence, streak geometry, the capture lookup, the compositing (uniform capture, Warp
tiles vs the C reference)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import assert_twins_agree

import pywarp
from pywarp.rain import particles as P

sim_w = pywarp.equation("rr-code-5.2.2")
sim_c = pywarp.equation("rr-code-5.2.2", impl="c")


@pytest.mark.spec("rr-code-5.2.2")
def test_counts_corrected_grow_one_per_frame_and_shrink_at_once():
    assert sim_w(30, 100)["count"] == 30
    assert sim_w(200, 100)["count"] == 100
    ps = P.ParticleSystem(100)
    for _ in range(50):
        ps.step(100, 1 / 60)
    ps.step(20, 1 / 60)
    assert ps.count == 20 and len(ps.state()["pos"]) == 20


@pytest.mark.spec("rr-code-5.2.2")
def test_counts_thesis_decrement_never_creates_a_particle():
    for impl in (sim_w, sim_c):
        r = impl(25, 100, variant="thesis")
        assert r["count"] == -25 and len(r["pos"]) == 0
        r = impl(25, 100, warm=True, variant="thesis")
        assert r["count"] == -25 and len(r["pos"]) == 0


@pytest.mark.spec("rr-code-5.2.2")
@pytest.mark.parametrize("kw", [dict(), dict(warm=True, seed=7), dict(warm=True, wind=(0.8, 0.0, -0.3), seed=3)])
def test_warp_and_c_agree_bit_for_bit_and_rerun_is_identical(kw):
    a = sim_w(150, 80, 1 / 30, **kw)
    b = sim_w(150, 80, 1 / 30, **kw)
    c = sim_c(150, 80, 1 / 30, **kw)
    for k in ("pos", "radius_mm", "speed", "generation"):
        np.testing.assert_array_equal(a[k], b[k])
        np.testing.assert_array_equal(a[k], c[k])
    assert a["generation"].max() > 0  # drops fell below -1 and were regenerated


@pytest.mark.spec("rr-code-5.2.2")
def test_spawn_box_and_gauss_reading():
    r = sim_w(0, 20000, warm=True, capacity=20000)
    pos, rad = r["pos"], r["radius_mm"]
    assert np.all((pos[:, 0] >= -1) & (pos[:, 0] < 1) & (pos[:, 2] >= -1.5) & (pos[:, 2] < 1.5))
    assert np.all((pos[:, 1] >= -1) & (pos[:, 1] < 1.25))  # warm: between the respawn level and the box top
    # Gauss(1, 1.3, 8): mean of 8 uniforms on [0.8, 1.8): mean 1.3, sigma 1/sqrt(96), ~68 % within one sigma
    assert rad.min() >= 0.8 and rad.max() < 1.8
    assert abs(rad.mean() - 1.3) < 0.003
    assert abs(rad.std() - 1 / math.sqrt(96)) < 0.003
    assert 0.64 < np.mean(np.abs(rad - 1.3) < 1 / math.sqrt(96)) < 0.72
    cold = sim_w(1, 1)["pos"]  # a new particle starts in the box Y in [1, 1.25], then falls one frame
    assert 1.25 > cold[0, 1] > 1.0 - 9.23 / 4 / 60


@pytest.mark.spec("rr-code-5.2.2", "rr-tab-2.2")
@pytest.mark.parametrize("radius,speed", [(0.5, 4.0), (1.0, 6.59), (2.0, 8.91), (3.0, 9.23)])
def test_speed_is_table_2_2_slowed_four_times(radius, speed):
    r = sim_w(0, 3, warm=True, size_mean_mm=radius, size_spread_mm=0.0)
    np.testing.assert_allclose(r["radius_mm"], radius)
    np.testing.assert_allclose(r["speed"], speed / 4, rtol=1e-6)


@pytest.mark.spec("rr-code-5.2.2")
def test_frame_rate_independence():
    kw = dict(size_mean_mm=1.0, size_spread_mm=0.0, box_min=(-1, 1.0, -1.5), box_max=(1, 1.25, 1.5))
    a = sim_w(30, 1, 1 / 30, **kw)
    b = sim_w(60, 1, 1 / 60, **kw)  # the particle is created on frame 1 and falls frames - 1 ... frames steps
    y0 = sim_w(1, 1, 0.0, **kw)["pos"][0, 1]
    v = 6.59 / 4
    assert a["pos"][0, 1] == pytest.approx(y0 - 30 * v / 30, abs=1e-5)
    assert b["pos"][0, 1] == pytest.approx(y0 - 60 * v / 60, abs=1e-5)


@pytest.mark.spec("rr-code-5.2.2")
def test_wind_wraps_in_the_box_and_bad_input_is_refused():
    r = sim_w(200, 50, 1 / 30, warm=True, wind=(3.0, 0.0, -2.0))
    assert np.all((r["pos"][:, 0] >= -1) & (r["pos"][:, 0] < 1) & (r["pos"][:, 2] >= -1.5) & (r["pos"][:, 2] < 1.5))
    with pytest.raises(ValueError, match="wind"):
        sim_w(1, 1, wind=(0.0, 1.0, 0.0))
    with pytest.raises(ValueError, match="size_samples"):
        sim_c(1, 1, size_samples=0)
    with pytest.raises(ValueError, match="capacity"):
        sim_w(1, 10, capacity=5)
    with pytest.raises(ValueError, match="dt"):
        sim_c(1, 1, dt=2.0)


@pytest.mark.spec("rr-alg-3.2.3", "rr-code-5.2.4")
def test_streak_length_and_tap_offset():
    length, off = pywarp.equation("rr-alg-3.2.3")(1.8, 0.075, 0.01)
    assert length == pytest.approx(0.135, rel=1e-6)  # fall during the persistence time
    assert off == pytest.approx((0.135 / 6) / (0.02 + 0.135), rel=1e-6)  # taps -3..3 span the fall
    assert_twins_agree("rr-alg-3.2.3", np.linspace(0, 3, 11), np.array([0.06, 0.09])[:, None], 0.013)


@pytest.mark.spec("rr-alg-3.1.2")
def test_capture_uv_against_the_capture_camera():
    fv, fc = math.radians(60), math.radians(150)
    uv = pywarp.equation("rr-alg-3.1.2")(np.array([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]), 16 / 9, fv, fc)
    np.testing.assert_allclose(uv[0], [0.5, 0.5])
    t = math.tan(math.radians(30)) / math.tan(math.radians(75))
    np.testing.assert_allclose(uv[1], [0.5, 0.5 - 0.5 * t], rtol=1e-6)  # the top of the view, 30 deg up
    np.testing.assert_allclose(uv[2], [0.5 + 0.5 * 16 / 9 * t, 0.5], rtol=1e-6)
    # a 150 deg capture sees the whole 60 deg view well inside its frame
    rng = np.random.default_rng(1)
    ndc = rng.uniform(-1, 1, (200, 2))
    assert_twins_agree("rr-alg-3.1.2", ndc, 16 / 9, fv, fc)


def _scene(rng, h=24, w=40, n=12, streaks="off"):
    bg = rng.uniform(0, 1, (h, w, 3)).astype(np.float32)
    cap = rng.uniform(0, 1, (32, 32, 3)).astype(np.float32)
    from pywarp.rain.technique import sphere_mask

    mask = sphere_mask(16)
    cx = rng.uniform(-3, w + 3, n)
    cy = rng.uniform(-3, h + 3, n)
    r = rng.uniform(1.5, 6, n)
    half = r + (rng.uniform(0, 10, n) if streaks != "off" else 0)
    tap = (half - r) * 2 / 6 / (2 * half) if streaks != "off" else np.zeros(n)
    sp = np.stack([cx, cy, r, half, tap, rng.uniform(0.5, 2, n)], 1).astype(np.float32)
    return bg, cap, mask, sp[np.argsort(-sp[:, 5], kind="stable")]


@pytest.mark.spec("rr-code-5.2.3", "rr-code-5.2.4")
@pytest.mark.parametrize("streaks", ["off", "thesis", "physical"])
@pytest.mark.parametrize("filt", ["nearest", "linear"])
def test_composite_warp_tiles_match_the_c_reference(rng, streaks, filt):
    bg, cap, mask, sp = _scene(rng, streaks=streaks)
    kw = dict(fov_view=math.radians(60), fov_capture=math.radians(150), streaks=streaks, filter=filt, opacity=0.8)
    w = pywarp.equation("rr-code-5.2.3")(bg, cap, mask, sp, **kw)
    c = pywarp.equation("rr-code-5.2.3", impl="c")(bg, cap, mask, sp, **kw)
    assert np.abs(w - c).max() <= 1e-6
    assert np.abs(w - bg).max() > 0.05  # drops were drawn
    ys, xs = np.nonzero(np.any(w != bg, axis=2))
    pw = P.composite_pixels(bg, cap, mask, sp, xs, ys, **kw)
    pc = P.composite_pixels(bg, cap, mask, sp, xs, ys, impl="c", **kw)
    np.testing.assert_array_equal(pw, pc)
    np.testing.assert_allclose(pw, w[ys, xs], atol=1e-6)


@pytest.mark.spec("rr-code-5.2.4")
def test_streak_average_of_a_uniform_capture_is_that_colour(rng):
    bg, cap, mask, sp = _scene(rng, streaks="thesis")
    colour = np.array([0.2, 0.5, 0.7], np.float32)
    cap[:] = colour
    bg[:] = colour
    out = P.composite(bg, cap, mask, sp, math.radians(60), streaks="thesis", opacity=0.5)
    np.testing.assert_allclose(out, bg, atol=1e-6)
    bg[:] = 0.0  # over black: colour * alpha, alpha = 0.5 hits / 7 <= 0.5
    out = P.composite(bg, cap, mask, sp[:1], math.radians(60), streaks="thesis", opacity=0.5)
    a = out[..., 1] / colour[1]
    assert a.max() <= 0.5 + 1e-6 and a.max() > 0.2
    assert set(np.round(a[a > 0] * 14).astype(int)) <= set(range(1, 8))  # multiples of 0.5/7


@pytest.mark.spec("rr-code-5.2.3")
def test_composite_refuses_bad_input(rng):
    bg, cap, mask, sp = _scene(rng)
    f = pywarp.equation("rr-code-5.2.3")
    with pytest.raises(ValueError, match="mask"):
        f(bg, cap, mask[..., :3], sp, math.radians(60))
    with pytest.raises(ValueError, match="filter"):
        f(bg, cap, mask, sp, math.radians(60), filter="cubic")
    with pytest.raises(ValueError, match="fov_capture"):
        f(bg, cap, mask, sp, math.radians(60), math.radians(181))
    bad = sp.copy()
    bad[0, 2] = 0
    with pytest.raises(ValueError, match="radius"):
        pywarp.equation("rr-code-5.2.3", impl="c")(bg, cap, mask, bad, math.radians(60))


# --- the frame pass: binning, tiles, packed mask (the images must not depend on them) -------------------------------

def test_binning_lists_every_sprite_of_a_tile_in_order(rng):
    _, _, _, sp = _scene(rng, h=50, w=70, n=40, streaks="thesis")
    for tile in (1, 5, 8, 16):
        start, items, tiles_x = P.bin_sprites(sp, 70, 50, tile)
        tiles_y = -(-50 // tile)
        assert start.shape == (tiles_x * tiles_y + 1,) and start[0] == 0 and start[-1] == len(items)
        assert np.all(np.diff(start) >= 0)
        for t in range(tiles_x * tiles_y):
            tx, ty = t % tiles_x, t // tiles_x
            # brute force: the sprites whose box (1 px margin) meets the tile, in array order
            want = [j for j, s in enumerate(sp)
                    if s[0] + s[2] >= 0 and s[0] - s[2] <= 70 and s[1] + s[3] >= 0 and s[1] - s[3] <= 50
                    and min(max(math.floor(s[0] - s[2] - 1) // tile, 0), tiles_x - 1) <= tx
                    <= min(max(math.floor(s[0] + s[2] + 1) // tile, 0), tiles_x - 1)
                    and min(max(math.floor(s[1] - s[3] - 1) // tile, 0), tiles_y - 1) <= ty
                    <= min(max(math.floor(s[1] + s[3] + 1) // tile, 0), tiles_y - 1)]
            assert items[start[t]:start[t + 1]].tolist() == want
    start, items, _ = P.bin_sprites(np.zeros((0, 6), np.float32), 70, 50, 8)
    assert len(items) == 0 and not start.any()


@pytest.mark.spec("rr-code-5.2.3", "rr-code-5.2.4")
@pytest.mark.parametrize("streaks", ["off", "thesis", "physical"])
def test_frame_does_not_depend_on_the_tile_size_or_kernel(rng, streaks):
    bg, cap, mask, sp = _scene(rng, h=37, w=53, n=30, streaks=streaks)
    kw = dict(fov_view=math.radians(60), streaks=streaks, filter="linear", opacity=0.7)
    frames = [P.composite(bg, cap, mask, sp, tile=t, per_tile=pt, **kw) for t in (1, 4, 8, 16, 64)
              for pt in (False, True)]
    frames.append(P.composite_pixels(bg, cap, mask, sp, *np.meshgrid(np.arange(53), np.arange(37)), **kw)
                  .reshape(37, 53, 3))  # every sprite tested per pixel, no tiles
    for f in frames[1:]:
        np.testing.assert_array_equal(f, frames[0])
    np.testing.assert_array_equal(P.composite(bg, cap, mask, sp[:0], **kw), bg)  # no sprite: the background
    far = sp.copy()
    far[:, 0] += 1000.0  # every sprite off screen
    np.testing.assert_array_equal(P.composite(bg, cap, mask, far, **kw), bg)


def test_packed_mask_holds_the_shader_quotients_column_major(rng):
    from pywarp.rain.technique import sphere_mask

    m = sphere_mask(16)
    q = P.pack_mask(m).reshape(16, 16, 2)  # [column, row]
    ok = (m[..., 3] > 0) & (m[..., 2] > 0)
    for my in range(16):
        for mx in range(16):
            if ok[my, mx]:
                assert q[mx, my, 0] == np.float32(m[my, mx, 0]) / np.float32(m[my, mx, 2])
                assert q[mx, my, 1] == np.float32(m[my, mx, 1]) / np.float32(m[my, mx, 2])
            else:
                assert np.isnan(q[mx, my]).all()
    nrm = rng.normal(size=(16, 16, 3)).astype(np.float32)
    np.testing.assert_array_equal(P.pack_normals(nrm).reshape(16, 16, 3), nrm.transpose(1, 0, 2))


# --- the light-drop model in the frame (rr-A1..rr-CF) --------------------------------------------------------------

def _lit_inputs(rng, streaks):
    from pywarp.rain import drops as R

    bg, cap, _, sp = _scene(rng, h=30, w=48, n=25, streaks=streaks)
    mask, normals = R.drop_mask(32, 1.0, method="sphere", normals=True)
    pos = np.stack([rng.uniform(-1, 1, len(sp)), rng.uniform(-1, 1, len(sp)), -sp[:, 5]], 1).astype(np.float32)
    lights = dict(l1=(0.5, 0.4, -1.6), c_l1=(1.0, 0.8, 0.5), l2=(-0.7, -0.2, -1.0), c_l2=(0.3, 0.5, 1.0),
                  ambient=(0.9, 1.0, 1.1), r_half=1.0, right=(1.0, 0.0, 0.0), up=(0.0, 1.0, 0.0),
                  forward=(0.0, 0.0, -1.0))
    return bg, cap, np.asarray(mask), sp, pos, np.asarray(normals), lights


@pytest.mark.spec("rr-CF", "rr-A1", "rr-A2", "rr-A3")
@pytest.mark.parametrize("streaks", ["off", "thesis", "physical"])
@pytest.mark.parametrize("variant", ["corrected", "thesis"])
def test_lit_frame_matches_the_c_reference(rng, streaks, variant):
    bg, cap, mask, sp, pos, normals, lights = _lit_inputs(rng, streaks)
    lights["variant"] = variant
    kw = dict(fov_view=math.radians(60), streaks=streaks, filter="nearest", opacity=0.8)
    lit = P.composite(bg, cap, mask, sp, lights=lights, positions=pos, normals=normals, **kw)
    unlit = P.composite(bg, cap, mask, sp, **kw)
    ys, xs = np.nonzero(np.any(unlit != bg, axis=2))
    assert len(ys) > 50
    c = P.composite_pixels(bg, cap, mask, sp, xs, ys, lights=lights, positions=pos, normals=normals, impl="c", **kw)
    np.testing.assert_allclose(lit[ys, xs], c, rtol=1e-6, atol=1e-6)
    np.testing.assert_array_equal(P.composite(bg, cap, mask, sp, lights=lights, positions=pos, normals=normals,
                                              per_tile=False, **kw), lit)  # thread per pixel = thread per tile
    assert np.abs(lit - unlit).max() > 0.05  # the lights show
    np.testing.assert_array_equal(lit[unlit == bg], bg[unlit == bg])  # nothing outside the drops


@pytest.mark.spec("rr-CF")
def test_lights_off_give_the_unlit_frame_and_ambient_scales_it(rng):
    bg, cap, mask, sp, pos, normals, lights = _lit_inputs(rng, "off")
    kw = dict(fov_view=math.radians(60), opacity=1.0)
    unlit = P.composite(bg, cap, mask, sp, **kw)
    off = dict(lights, c_l1=(0, 0, 0), c_l2=(0, 0, 0), ambient=(1, 1, 1))
    np.testing.assert_array_equal(P.composite(bg, cap, mask, sp, lights=off, **kw), unlit)  # no positions needed
    cap[:] = 0.5
    flat = P.composite(bg, cap, mask, sp, **kw)
    dim = P.composite(bg, cap, mask, sp, lights=dict(off, ambient=(0.5, 1.0, 2.0)), positions=pos, normals=normals,
                      **kw)
    drop = flat[..., 0] == 0.5  # opaque drop pixels show the uniform capture ...
    assert drop.sum() > 50
    np.testing.assert_allclose(dim[drop], np.broadcast_to([0.25, 0.5, 1.0], dim[drop].shape), rtol=1e-6)  # x C_amb


def test_lights_refuse_bad_input(rng):
    bg, cap, mask, sp, pos, normals, lights = _lit_inputs(rng, "off")
    kw = dict(fov_view=math.radians(60))
    with pytest.raises(ValueError, match="c_l1"):
        P.composite(bg, cap, mask, sp, lights=dict(lights, c_l1=(-1, 0, 0)), positions=pos, normals=normals, **kw)
    with pytest.raises(ValueError, match="r_half"):
        P.composite(bg, cap, mask, sp, lights=dict(lights, r_half=0.0), positions=pos, normals=normals, **kw)
    with pytest.raises(ValueError, match="positions"):
        P.composite(bg, cap, mask, sp, lights=lights, positions=pos[:3], normals=normals, **kw)
    with pytest.raises(ValueError, match="normals"):
        P.composite(bg, cap, mask, sp, lights=lights, positions=pos, normals=normals[:4], **kw)
    with pytest.raises(ValueError, match="forward"):
        P.composite(bg, cap, mask, sp, lights=dict(lights, forward=(0, 0, 2)), positions=pos, normals=normals, **kw)
    with pytest.raises(ValueError, match="unknown light"):
        P.composite(bg, cap, mask, sp, lights=dict(lights, colour=1), positions=pos, normals=normals, **kw)
