"""The terrain demo's functions (pt ch. 7-9): closed forms and properties of the pixel transform, the marches, the
shadows, the normal, the octave policy, the fog (both variants), the sky, the clouds (both variants), the water
weight, and C vs Warp agreement on chosen inputs. Independent values are computed here in float64 NumPy."""
from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import assert_twins_agree

import pywarp
from pywarp.terrain import evaluators as TE

RNG = np.random.default_rng(20160617)


def unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def test_heightmap(x, z):
    return 10.0 * np.sin(0.1 * x) * np.sin(0.1 * z)


test_heightmap.__test__ = False  # a helper, not a test


# --- pt-code-7.1 ------------------------------------------------------------------------------------------------------

@pytest.mark.spec("pt-code-7.1", "pt-code-7.2")
def test_pixel_position_ranges_and_camera_agree_with_camera_ray():
    w, h = 640, 480
    p = pywarp.equation("pt-code-7.1")(np.array([0.5, w - 0.5, w / 2]), np.array([0.5, h - 0.5, h / 2]), w, h)
    np.testing.assert_allclose(p[0], [-(1 - 1 / w) * w / h, -(1 - 1 / h)], rtol=1e-6)
    np.testing.assert_allclose(p[1], [(1 - 1 / w) * w / h, 1 - 1 / h], rtol=1e-6)
    np.testing.assert_allclose(p[2], [0.0, 0.0], atol=0)
    # the pt-code-7.2 basis with p gives the rays of camera_ray (fov 90 deg); gl_FragCoord counts rows from the bottom
    eye, target = np.array([1.0, 5.0, 2.0]), np.array([4.0, 3.0, -6.0])
    cam = pywarp.kernels.camera.camera_look_at(eye, target, (0, 1, 0), math.pi / 2, w / h, 0.01, 1000.0)
    xs, ys = RNG.integers(0, w, 50), RNG.integers(0, h, 50)
    rd = pywarp.equation("pt-code-7.2")(xs, ys, w, h, cam)
    pp = pywarp.equation("pt-code-7.1")(xs + 0.5, (h - 1 - ys) + 0.5, float(w), float(h)).astype(np.float64)
    fwd = unit(target - eye)
    right = unit(np.cross(fwd, [0.0, 1.0, 0.0]))
    up = unit(np.cross(right, fwd))
    ref = unit(pp[:, :1] * right + pp[:, 1:] * up + fwd)
    np.testing.assert_allclose(rd, ref, atol=2e-6)


# --- pt-code-7.9 --------------------------------------------------------------------------------------------------------

def fbm79(x, z, octaves, **kw):
    """Kod 7.9 at (x, z): pt-code-7.9 is declared by pt-alg-3.2's function (p = (x, z), the printed defaults)."""
    return pywarp.equation("pt-code-7.9")(np.stack(np.broadcast_arrays(x, z), -1), octaves, **kw)


@pytest.mark.spec("pt-code-7.9", "pt-alg-3.1")
@pytest.mark.parametrize("octaves", [1, 2, 3, 4, 5, 6, 7, 8])
def test_fbm_bound_two_one_minus_half_power(octaves):
    x, z = RNG.uniform(-300, 300, (2, 20000))
    v = fbm79(x, z, octaves)
    assert np.max(np.abs(v)) <= 2.0 * (1.0 - 0.5 ** octaves)
    # the noise itself (one octave at frequency 0.5) is within [-1, 1]; measured about +-0.99 here
    if octaves == 1:
        assert 0.8 < np.max(np.abs(v)) <= 1.0


@pytest.mark.spec("pt-code-7.9")
def test_fbm_is_the_printed_sum_of_noise_octaves_and_agrees_with_pt_alg_3_2():
    x, z = RNG.uniform(-40, 40, (2, 200)).astype(np.float32)
    noise = pywarp.perlin2
    ref = np.zeros(200)
    for i in range(5):  # value += amplitude * noise(frequency * position), A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2
        f = np.float32(0.5 * 2 ** i)
        ref += 0.5 ** i * noise(f * x, f * z).astype(np.float64)
    np.testing.assert_allclose(fbm79(x, z, 5), ref, atol=1e-6)
    # one function answers both IDs, and the scene's heightmap is it: height = height_scale * fbm(x / hs, z / hs)
    from pywarp.core.registry import get
    assert get("pt-code-7.9") is get("pt-alg-3.2") and get("pt-code-7.9").c_symbol == "ccl_noise_fbm_perlin2"
    h = TE.height(x * 24.0, z * 24.0, 5, 1.0, 24.0, heightmap="fbm")
    np.testing.assert_array_equal(h, fbm79(np.float32(x * 24.0) / np.float32(24.0),
                                           np.float32(z * 24.0) / np.float32(24.0), 5))


# --- pt-code-7.4, 7.5, pt-alg-9-bisect --------------------------------------------------------------------------------------

def _rays(n):
    ro = np.column_stack([RNG.uniform(-50, 50, n), RNG.uniform(12, 25, n), RNG.uniform(-50, 50, n)])
    rd = unit(np.column_stack([RNG.uniform(-1, 1, n), RNG.uniform(-0.8, -0.15, n), RNG.uniform(-1, 1, n)]))
    return ro, rd


@pytest.mark.spec("pt-code-7.4", "pt-code-7.5", "pt-alg-9-bisect")
def test_fixed_dynamic_and_bisect_find_the_same_surface_on_the_test_heightmap():
    ro, rd = _rays(300)
    step, prec = 0.05, 0.01
    hf, tf, sf = pywarp.equation("pt-code-7.4")(ro, rd, 200.0, step, prec)
    hd, td, sd = pywarp.equation("pt-code-7.5")(ro, rd, 200.0, prec, 1000, 0.5)
    hb, tb, sb = pywarp.equation("pt-alg-9-bisect")(ro, rd, 200.0, prec, 1000, 0.5, 0.25, 8)
    both = (hf == 1) & (hd == 1) & (hb == 1)
    assert both.mean() > 0.95
    # the independent surface: the first crossing of y - h = 0 along the ray, found in float64 with a fine grid
    t = np.linspace(0, 200, 400001)
    for k in np.flatnonzero(both)[:60]:
        p = ro[k] + rd[k] * t[:, None]
        gap = p[:, 1] - test_heightmap(p[:, 0], p[:, 2])
        t_true = t[np.argmax(gap < 0.0)]
        # fixed step: the first sample at most PRECISION above the surface: up to one step after the crossing, or
        # (within PRECISION of it) slightly before; the float32 sum t += step drifts by < 1e-3 over 200 units
        assert t_true - 0.1 <= tf[k] <= t_true + step + 2e-3
        # dynamic and bisect stop within PRECISION of the surface: their t is within PRECISION / |slope| of it
        assert abs(td[k] - t_true) < 0.1 and abs(tb[k] - t_true) < 0.1
    assert np.mean(sd[both]) * 5 < np.mean(sf[both])


@pytest.mark.spec("pt-code-7.5")
def test_dynamic_march_misses_upward_rays_and_honours_max_steps():
    ro = np.array([0.0, 20.0, 0.0])
    hit, t, steps = pywarp.equation("pt-code-7.5")(ro, unit([0.2, 0.5, 0.3]), 200.0, 0.01, 1000)
    assert hit == 0 and t > 200.0
    hit, t, steps = pywarp.equation("pt-code-7.5")(ro, unit([1.0, -0.01, 0.0]), 200.0, 0.01, 3)
    assert steps == 3 and hit == 0


@pytest.mark.spec("pt-code-7.4", "pt-code-7.5", "pt-alg-9-bisect")
@pytest.mark.parametrize("heightmap", ["test", "fbm"])
def test_marches_c_and_warp_agree(heightmap):
    ro, rd = _rays(64)
    assert_twins_agree("pt-code-7.4", ro, rd, 150.0, 0.2, 0.01, heightmap=heightmap)
    assert_twins_agree("pt-code-7.5", ro, rd, 150.0, 0.01, 400, 0.5, heightmap=heightmap)
    assert_twins_agree("pt-alg-9-bisect", ro, rd, 150.0, 0.01, 400, 0.5, 0.3, 6, heightmap=heightmap)


@pytest.mark.spec("pt-alg-9-bisect")
def test_bisect_caps_the_crawl_of_grazing_rays():
    # rays skimming just above the crests of the test heightmap: the dynamic step crawls, the bisection does not
    n = 200
    ro = np.column_stack([np.full(n, -40.0), np.full(n, 10.3), RNG.uniform(10, 20, n)])
    rd = unit(np.column_stack([np.ones(n), RNG.uniform(-0.004, 0.0, n), np.zeros(n)]))
    _, _, sd = pywarp.equation("pt-code-7.5")(ro, rd, 200.0, 0.01, 100000)
    _, _, sb = pywarp.equation("pt-alg-9-bisect")(ro, rd, 200.0, 0.01, 100000, 1.0, 0.25, 6)
    assert sb.mean() < sd.mean()


# --- pt-code-7.6, 7.7 --------------------------------------------------------------------------------------------------------

@pytest.mark.spec("pt-code-7.6", "pt-code-7.7")
def test_shadows_lit_occluded_in_unit_range_and_soft_monotone_in_k():
    trough = np.array([-15.707963, -9.9, 15.707963])
    assert pywarp.equation("pt-code-7.6")(trough, [0.0, 1.0, 0.0]) == 1.0
    assert pywarp.equation("pt-code-7.6")(trough, unit([1.0, 0.05, 0.0])) == 0.0
    ro = np.column_stack([RNG.uniform(-30, 30, 400), np.zeros(400), RNG.uniform(-30, 30, 400)])
    ro[:, 1] = test_heightmap(ro[:, 0], ro[:, 2]) + 0.05
    l = unit(np.column_stack([RNG.uniform(-1, 1, 400), RNG.uniform(0.05, 1, 400), RNG.uniform(-1, 1, 400)]))  # noqa
    prev = None
    for k in (0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 64.0):
        s = pywarp.equation("pt-code-7.7")(ro, l, 0.02, k)
        assert np.all((s >= 0.0) & (s <= 1.0))
        if prev is not None:
            assert np.all(s >= prev)
        prev = s
    hard = pywarp.equation("pt-code-7.6")(ro, l, 0.02)
    assert np.all(prev[hard == 0.0] == 0.0)  # occluded by the hard test -> 0 for every k (same path, same hit)
    assert 0.05 < np.mean(hard == 0.0) < 0.95


@pytest.mark.spec("pt-code-7.6", "pt-code-7.7")
def test_shadows_c_and_warp_agree():
    ro = np.column_stack([RNG.uniform(-30, 30, 64), RNG.uniform(-2, 20, 64), RNG.uniform(-30, 30, 64)])
    l = unit(np.column_stack([RNG.uniform(-1, 1, 64), RNG.uniform(0.05, 1, 64), RNG.uniform(-1, 1, 64)]))  # noqa
    for hm in ("test", "fbm"):
        assert_twins_agree("pt-code-7.6", ro, l, 0.2, heightmap=hm)
        assert_twins_agree("pt-code-7.7", ro, l, 0.02, 4.0, heightmap=hm)


# --- pt-7.1, pt-7.2, pt-code-7.8, pt-alg-7.3-lod -----------------------------------------------------------------------------

@pytest.mark.spec("pt-7.1")
def test_lighting_closed_form_and_shadow_on_the_diffuse_term():
    n = unit(RNG.normal(size=(100, 3)))
    l = unit(RNG.normal(size=(100, 3)))  # noqa: E741
    ca, cd = RNG.uniform(0, 1, (2, 100, 3))
    la, ld, sh = 0.3, 1.2, RNG.uniform(0, 1, 100)
    ref = la * ca + ld * cd * (np.maximum(0.0, np.sum(n * l, -1)) * sh)[:, None]
    np.testing.assert_allclose(pywarp.equation("pt-7.1")(n, l, la, ca, ld, cd, sh), ref, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(pywarp.equation("pt-7.1")(n, l, la, ca, ld, cd, 0.0), la * ca, rtol=1e-6)


@pytest.mark.spec("pt-code-7.8", "pt-7.2")
def test_normal_gradient_y_is_2h_and_matches_the_analytic_gradient():
    p = np.column_stack([RNG.uniform(-60, 60, 200), RNG.uniform(-5, 5, 200), RNG.uniform(-60, 60, 200)])
    h = 0.002
    n, g = pywarp.equation("pt-code-7.8")(p, h)
    # g.y = (y + h - H) - (y - h - H) = 2h; two roundings at the magnitude of |y| + |H| + h (<= 16: 2 ulp = 2.4e-6)
    np.testing.assert_allclose(g[:, 1], 2 * h, atol=2 * 2.0 ** -23 * 16)
    # normal of y = 10 sin(0.1x) sin(0.1z): (-h_x, 1, -h_z) normalised
    hx = np.cos(0.1 * p[:, 0]) * np.sin(0.1 * p[:, 2])
    hz = np.sin(0.1 * p[:, 0]) * np.cos(0.1 * p[:, 2])
    ref = unit(np.column_stack([-hx, np.ones(200), -hz]))
    # central differences of a float32 height (ulp(10) ~ 1e-6) over 2h = 0.004: ~5e-4 in the gradient
    np.testing.assert_allclose(n, ref, atol=2e-3)
    np.testing.assert_allclose(np.linalg.norm(n, axis=-1), 1.0, atol=1e-6)
    assert_twins_agree("pt-code-7.8", p, h, heightmap="fbm")
    assert_twins_agree("pt-code-7.8", p, h, heightmap="test")


@pytest.mark.spec("pt-alg-7.3-lod")
def test_normal_octaves_one_less_per_doubling_of_distance():
    f = pywarp.equation("pt-alg-7.3-lod")
    t = np.array([0.0, 10.0, 10.0001, 20.0, 20.001, 40.001, 80.001, 1e5])
    np.testing.assert_array_equal(f(t, 9, 4, 10.0), [9, 9, 8, 8, 7, 6, 5, 4])
    assert f(1e9, 6, 8, 10.0) == 6  # octaves_min >= octaves_max: octaves_max
    t = RNG.uniform(0, 1000, 500)
    assert np.all(np.diff(f(np.sort(t), 10, 2, 7.0)) <= 0)
    assert_twins_agree("pt-alg-7.3-lod", t, 10, 2, 7.0)


# --- pt-7.3, pt-code-7.10, pt-code-7.11, pt-7.4 -----------------------------------------------------------------------------

@pytest.mark.spec("pt-7.3")
def test_fog_printed_form_reaches_one_at_ln2_over_rho_and_conventional_form():
    fog = pywarp.equation("pt-7.3")
    for rho in (0.001, 0.01, 0.3):
        d_full = math.log(2.0) / rho
        d = np.array([0.0, 0.5 * d_full, 0.999 * d_full, 1.001 * d_full, 10 * d_full])
        th = fog(d, rho, variant="thesis")
        np.testing.assert_allclose(th[:3], np.exp(rho * d[:3]) - 1.0, rtol=2e-5, atol=1e-7)
        assert th[2] < 1.0 and th[3] == 1.0 and th[4] == 1.0
        np.testing.assert_allclose(fog(d, rho), 1.0 - np.exp(-rho * d), rtol=2e-5, atol=1e-7)
    assert_twins_agree("pt-7.3", RNG.uniform(0, 1000, 100), 0.003, variant="thesis")
    assert_twins_agree("pt-7.3", RNG.uniform(0, 1000, 100), 0.003, variant="corrected")


@pytest.mark.spec("pt-code-7.10")
def test_sky_glow_halves_at_7_53_degrees_and_is_power_80():
    sun = np.array([0.0, 0.0, -1.0])
    a_half = math.acos(0.5 ** (1 / 80))
    assert math.degrees(a_half) == pytest.approx(7.53, abs=0.005)
    a = np.radians([0.0, 2.0, math.degrees(a_half), 19.25, 90.0, 120.0])
    rd = np.column_stack([np.sin(a), np.zeros_like(a), -np.cos(a)])
    c = pywarp.equation("pt-code-7.10")(rd, sun, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
    np.testing.assert_allclose(c[:, 0], np.maximum(np.cos(a), 0.0) ** 80, rtol=1e-4, atol=1e-7)
    assert c[2, 0] == pytest.approx(0.5, abs=1e-4)
    assert c[3, 0] == pytest.approx(0.01, abs=2e-4)
    assert np.all(c[4:] == 0.0)


@pytest.mark.spec("pt-code-7.11")
def test_clouds_no_clouds_below_the_horizon_corrected_spurious_thesis():
    n = 500
    rd = unit(np.column_stack([RNG.uniform(-1, 1, n), RNG.uniform(-1, -0.05, n), RNG.uniform(-1, 1, n)]))
    sky = np.array([0.4, 0.6, 0.9])
    args = (sky, np.zeros(3), rd, 100.0, (2.0, 1.0), 5.0, 30.0, (1.0, 1.0, 1.0))
    corr = pywarp.equation("pt-code-7.11")(*args)
    thesis = pywarp.equation("pt-code-7.11")(*args, variant="thesis")
    np.testing.assert_array_equal(corr, np.broadcast_to(sky.astype(np.float32), corr.shape))
    assert np.mean(np.any(thesis != sky.astype(np.float32), axis=-1)) > 0.2  # fBm < 0 times rd.y < 0 -> clouds
    # above the horizon: w = clamp(fbm(q / scale, 4) rd.y, 0, 1) with q the plane point moved by the wind
    up = unit(np.column_stack([RNG.uniform(-1, 1, n), RNG.uniform(0.05, 1, n), RNG.uniform(-1, 1, n)]))
    c = pywarp.equation("pt-code-7.11")(sky, np.zeros(3), up, 100.0, (2.0, 1.0), 5.0, 30.0, (1.0, 1.0, 1.0))
    t = 100.0 / up[:, 1]
    qx = (up[:, 0] * t + 10.0) / 30.0
    qz = (up[:, 2] * t + 5.0) / 30.0
    w = np.clip(fbm79(qx, qz, 4) * up[:, 1], 0, 1)
    np.testing.assert_allclose(c, sky + (1.0 - sky) * w[:, None], atol=1e-4)
    for v in ("thesis", "corrected"):
        assert_twins_agree("pt-code-7.11", sky, np.array([3.0, 2.0, -1.0]), np.concatenate([rd, up]), 100.0,
                           (2.0, 1.0), 5.0, 30.0, (1.0, 1.0, 1.0), variant=v)


@pytest.mark.spec("pt-7.4")
@pytest.mark.parametrize("kappa", [0.5, 1.0, 3.0, 6.0])
def test_water_weight_one_at_normal_incidence_and_decreasing_with_angle(kappa):
    n = np.array([0.0, 1.0, 0.0])
    f = pywarp.equation("pt-7.4")
    assert f([0.0, -1.0, 0.0], n, kappa) == 1.0
    a = np.radians(np.linspace(0, 89, 50))
    v = np.column_stack([np.sin(a), -np.cos(a), np.zeros_like(a)])
    w = f(v, n, kappa)
    np.testing.assert_allclose(w, np.cos(a) ** kappa, rtol=2e-5, atol=1e-7)
    assert np.all(np.diff(w) < 0)


@pytest.mark.spec("pt-7.4")
def test_lower_kappa_keeps_the_bottom_visible_at_oblique_angles():
    v, n = unit([1.0, -1.0, 0.0]), np.array([0.0, 1.0, 0.0])
    w = [pywarp.equation("pt-7.4")(v, n, k) for k in (1.0, 3.0, 6.0)]
    assert w[0] > w[1] > w[2]


@pytest.mark.spec("pt-alg-7.3.4")
def test_water_normal_c_and_warp_agree_unit_and_tilted_by_the_strength():
    x, z = RNG.uniform(-100, 100, (2, 300))
    wn = TE.water_normal(x, z, 3.5, 2.0, 0.08)
    cn = TE.water_normal(x, z, 3.5, 2.0, 0.08, impl="c")
    np.testing.assert_array_equal(wn, cn)
    np.testing.assert_allclose(np.linalg.norm(wn, axis=-1), 1.0, atol=1e-6)
    assert np.all(wn[:, 1] > 0.98)  # strength 0.08, |a|, |b| <= 1.5: tilt below 10 deg
    flat = TE.water_normal(x, z, 3.5, 2.0, 0.0)
    np.testing.assert_array_equal(flat, np.broadcast_to(np.float32([0, 1, 0]), flat.shape))


# --- bad input ------------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("cid, args, name", [
    ("pt-code-7.5", ([0, 1, 0], [0, -1, 0], 0.0), "max_t"),
    ("pt-code-7.5", ([0, 1, 0], [0, -2, 0]), "rd"),
    ("pt-code-7.4", ([0, 1, 0], [0, -1, 0], 100.0, 0.001), "step_size"),
    ("pt-7.3", (-1.0, 0.1), "d"),
    ("pt-7.4", ([0, -1, 0], [0, 1, 0], 0.0), "kappa"),
    ("pt-code-7.9", ((1.0, 2.0), 0), "octaves"),
])
def test_bad_input_refused_naming_the_argument(cid, args, name):
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        pywarp.equation(cid)(*args)
