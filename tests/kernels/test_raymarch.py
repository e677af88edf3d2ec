"""View-ray geometry vc-A14, A18, A19, A21, A23, A24, A35, A36: closed forms, float64 references written here,
properties, C vs Warp agreement (assert_twins_agree) and bad input at the Python boundary."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest
from helpers import assert_twins_agree

import pywarp
from pywarp.clouds import raymarch as crm
from pywarp.kernels import raymarch as rm

EPS32 = float(np.finfo(np.float32).eps)
R_E, R_I, R_O = 6371.0, 6372.5, 6375.0
IMPLS = ["warp", "c"]


def unit32(v):
    """Unit vectors (..., 3) in float32, normalized in float64 and rounded once."""
    v = np.asarray(v, dtype=np.float64)
    return (v / np.linalg.norm(v, axis=-1, keepdims=True)).astype(np.float32)


def pcg(v: int) -> int:
    """PCG hash (Jarzynski & Olano 2020), written independently of the library."""
    s = (v * 747796405 + 2891336453) & 0xFFFFFFFF
    w = (((s >> ((s >> 28) + 4)) ^ s) * 277803737) & 0xFFFFFFFF
    return (w >> 22) ^ w


def roots64(o, d, c, r):
    """float64 quadratic-formula roots for unit d: (t0, t1, sqrt(disc)) with NaN on a miss."""
    f = o - c
    b = np.sum(f * d, axis=-1)
    disc = b * b - (np.sum(f * f, axis=-1) - r * r)
    s = np.sqrt(np.where(disc >= 0, disc, np.nan))
    return -b - s, -b + s, disc


# --- vc-A14: ray-sphere -----------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A14")
@pytest.mark.parametrize("impl", IMPLS)
def test_ray_sphere_closed_forms(impl):
    rs = pywarp.equation("vc-A14", impl=impl)
    assert rs((1, 2, 3), (0, 0, 1), (1, 2, 3), 2.5) == (-2.5, 2.5)  # from the centre: +-R
    assert rs((-5, 1, 0), (1, 0, 0), (0, 0, 0), 1.0) == (5.0, 5.0)  # tangent: double root
    t0, t1 = rs((0, 2, -5), (0, 0, 1), (0, 0, 0), 1.0)  # closest approach 2 > R: miss
    assert np.isnan(t0) and np.isnan(t1)
    assert rs((0, 0, 5), (0, 0, 1), (0, 0, 0), 1.0) == (-6.0, -4.0)  # sphere behind the origin
    assert rs((1, 0, 0), (0, 1, 0), (0, 0, 0), 1.0) == (0.0, 0.0)  # origin on the surface, tangent ray: q == 0
    # from the ground straight up to the layer base and top (|o - c| = 6371 is exact in float32)
    assert rs((0, 0, 0), (0, 1, 0), (0, -R_E, 0), R_I)[1] == 1.5
    assert rs((0, 0, 0), (0, 1, 0), (0, -R_E, 0), R_O)[1] == 4.0
    # horizontal from the ground: sqrt((R + h)^2 - R^2); radii near 6371 km have a float32 spacing of 4.9e-4 km
    for r in (R_I, R_O):
        assert rs((0, 0, 0), (1, 0, 0), (0, -R_E, 0), r)[1] == pytest.approx(math.sqrt(r * r - R_E * R_E), abs=1e-3)
    # vectors broadcast: one origin, two directions
    t0, t1 = rs((0, 0, -5), [(0, 0, 1), (0, 1, 0)], (0, 0, 0), 1.0)
    assert t0.shape == (2,) and (t0[0], t1[0]) == (4.0, 6.0) and np.isnan(t0[1])


@pytest.mark.spec("vc-A14")
def test_ray_sphere_matches_float64_reference(rng):
    n = 4000
    o = rng.uniform(-10, 10, (n, 3)).astype(np.float32)
    d = unit32(rng.normal(size=(n, 3)))
    c = rng.uniform(-3, 3, (n, 3)).astype(np.float32)
    r = rng.uniform(0.5, 8, n).astype(np.float32)
    t0, t1 = pywarp.raymarch_ray_sphere(o, d, c, r)
    o64, c64, r64 = o.astype(np.float64), c.astype(np.float64), r.astype(np.float64)
    d64 = d.astype(np.float64) / np.linalg.norm(d.astype(np.float64), axis=1, keepdims=True)
    e0, e1, disc = roots64(o64, d64, c64, r64)
    # hit/miss agrees wherever the discriminant is not within float32 round-off of zero
    clear = np.abs(disc) > 64 * EPS32 * (np.linalg.norm(o64 - c64, axis=1) + r64) ** 2
    assert np.array_equal(np.isnan(t0)[clear], np.isnan(e0)[clear])
    assert np.isnan(e0).sum() > 500 and (~np.isnan(e0)).sum() > 500  # both cases exercised
    # Away from tangency (disc >= 0.01 R^2) the robust form's error is a few roundings of the largest length
    # |o - c| + R, amplified by at most R / (2 sqrt(disc)) <= 5 through the square root: 16 eps (|o - c| + R).
    # (|d| - 1 <= 1 eps after rounding the unit vector to float32 adds at most eps |t| <= eps (|o - c| + R).)
    m = ~np.isnan(e0) & (disc >= 0.01 * r64 ** 2)
    scale = np.linalg.norm(o64 - c64, axis=1)[m] + r64[m]
    assert np.all(np.abs(t0[m] - e0[m]) <= 16 * EPS32 * scale)
    assert np.all(np.abs(t1[m] - e1[m]) <= 16 * EPS32 * scale)
    assert np.all(t0[~np.isnan(t0)] <= t1[~np.isnan(t0)])


# --- vc-A14 / vc-A24: layer segment -----------------------------------------------------------------------------------

@pytest.mark.spec("vc-A14", "vc-A24")
@pytest.mark.parametrize("impl", IMPLS)
def test_layer_segment_below_inside_above(impl):
    seg = pywarp.equation("vc-A24", impl=impl)
    up, down, side = (0, 1, 0), (0, -1, 0), (1, 0, 0)
    assert seg((0, 0, 0), up) == (1.5, 4.0)  # below, zenith (defaults: 6371 km, layer 1.5-4 km)
    assert all(np.isnan(seg((0, 0.5, 0), down)))  # below, looking down: the Earth blocks
    assert all(np.isnan(seg((0, -1, 0), up)))  # underground camera
    ts, te = seg((0, 2, 0), up)  # inside: camera to the top
    assert ts == 0.0 and te == pytest.approx(2.0, abs=1e-3)
    ts, te = seg((0, 2, 0), down)  # inside, looking down: leaves through the base
    assert ts == 0.0 and te == pytest.approx(0.5, abs=1e-3)
    ts, te = seg((0, 10, 0), down)  # above: enter the top, leave through the base
    assert (ts, te) == (pytest.approx(6.0, abs=1e-3), pytest.approx(8.5, abs=1e-3))
    assert all(np.isnan(seg((0, 10, 0), up)))  # above, looking up
    assert all(np.isnan(seg((0, 10, 0), side)))  # above, horizontal: passes over the layer
    # a custom layer: the same geometry scaled (Earth 1000, layer 1010-1020), camera on the ground
    assert seg((0, 0, 0), up, (0, -1000, 0), 1000, 1010, 1020) == (10.0, 20.0)


@pytest.mark.spec("vc-A14")
def test_layer_segment_horizon_is_the_earth_tangent():
    """From a camera at height h the Earth hides everything below the elevation -acos(R / (R + h)); above the
    horizontal the segment shrinks monotonically to the layer thickness at zenith."""
    h = 0.5
    horizon = -math.acos(R_E / (R_E + h))
    el = np.array([horizon - 2e-3, horizon + 2e-3, 0.0, 0.3, math.pi / 2])
    d = np.stack([np.cos(el), np.sin(el), np.zeros_like(el)], -1)
    ts, te = pywarp.raymarch_layer_segment((0, h, 0), d)
    assert np.isnan(ts[0]) and not np.isnan(ts[1])
    length = te[2:] - ts[2:]
    assert np.all(np.diff(length) < 0)
    assert length[-1] == pytest.approx(2.5, abs=1e-3)


@pytest.mark.spec("vc-A14", "vc-A24")
def test_layer_segment_matches_float64_reference(rng):
    n = 8000
    alt = rng.choice([0.01, 0.8, 2.0, 3.5, 6.0, 12.0], n) + rng.uniform(0, 0.3, n)
    xz = rng.uniform(-20, 20, (n, 2))
    o = np.stack([xz[:, 0], alt, xz[:, 1]], 1).astype(np.float32)
    d = unit32(rng.normal(size=(n, 3)))
    ts, te = pywarp.raymarch_layer_segment(o, d)
    # independent float64 selection rules
    o64 = o.astype(np.float64)
    d64 = d.astype(np.float64) / np.linalg.norm(d.astype(np.float64), axis=1, keepdims=True)
    c = np.array([0.0, -R_E, 0.0])
    rho = np.linalg.norm(o64 - c, axis=1)
    (e0, e1, de), (i0, i1, di), (u0, u1, du) = (roots64(o64, d64, c, r) for r in (R_E, R_I, R_O))
    below, inside, above = rho < R_I, (rho >= R_I) & (rho <= R_O), rho > R_O
    rs, re_ = np.full(n, np.nan), np.full(n, np.nan)
    m = below & ~(e1 > 0)
    rs[m], re_[m] = i1[m], u1[m]
    rs[inside] = 0.0
    re_[inside] = np.where(i0 > 0, i0, u1)[inside]
    m = above & (u1 > 0)
    rs[m], re_[m] = np.maximum(u0, 0)[m], np.where(i0 > 0, i0, u1)[m]
    for name, arr in (("below", below), ("inside", inside), ("above", above)):
        assert (arr & ~np.isnan(rs)).sum() > 200, name
    # decisions agree unless a discriminant or a deciding root is within float32 round-off (eps R^2, 1 m) of zero
    near = np.zeros(n, bool)
    for disc in (de, di, du):
        near |= np.abs(disc) < 64 * EPS32 * R_E ** 2
    for t in (e1, i0, u0, u1):
        near |= np.abs(np.nan_to_num(t, nan=1e9)) < 1e-3
    assert np.array_equal(np.isnan(ts)[~near], np.isnan(rs)[~near])
    # Error propagation: the radii and |o - c| carry float32 errors of order eps R, and a root moves by
    # delta(disc) / (2 sqrt(disc)) ~ eps R^2 / s, so |error| <= 4 eps (R^2 / s + R), s = sqrt(disc) of the sphere
    # that gave the root (measured <= 1.4 eps (R^2 / s + R)).
    ok = ~np.isnan(ts) & ~np.isnan(rs)
    s_start = np.sqrt(np.abs(np.where(below, di, du)))
    s_end = np.sqrt(np.abs(np.where(below, du, np.where(i0 > 0, di, du))))
    assert np.all(np.abs(ts - rs)[ok & ~inside] <= 4 * EPS32 * (R_E ** 2 / s_start + R_E)[ok & ~inside])
    assert np.all(ts[ok & inside] == 0.0)
    assert np.all(np.abs(te - re_)[ok] <= 4 * EPS32 * (R_E ** 2 / s_end + R_E)[ok])


@pytest.mark.spec("vc-A14")
def test_cloud_layer_defaults_and_validation():
    layer = rm.CloudLayer()
    assert (layer.r_earth, layer.r_inner, layer.r_outer) == (6371.0, 6372.5, 6375.0)
    assert layer.centre == (0.0, -6371.0, 0.0)
    with pytest.raises(ValueError, match=r"^earth_radius must be > 0"):
        rm.CloudLayer(earth_radius=-1.0)
    with pytest.raises(ValueError, match=r"^base_altitude must be >= 0"):
        rm.CloudLayer(base_altitude=-0.5)
    with pytest.raises(ValueError, match=r"^top_altitude must be > base_altitude"):
        rm.CloudLayer(base_altitude=4.0, top_altitude=4.0)
    with pytest.raises(ValueError, match=r"^top_altitude must be finite"):
        rm.CloudLayer(top_altitude=float("nan"))
    with pytest.raises(ValueError, match=r"^top_altitude - base_altitude \(.*\) is below the float32 resolution"):
        rm.CloudLayer(base_altitude=1.0, top_altitude=1.0001)


# --- vc-A18 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A18")
@pytest.mark.parametrize("impl", IMPLS)
def test_view_sample_count_horizon_zenith_and_law(impl):
    n = pywarp.equation("vc-A18", impl=impl)
    assert n(0.0) == 128 and n(1.0) == 64 and n(-1.0) == 64 and n(0.5) == 96
    y = np.linspace(-1, 1, 2001).astype(np.float32)
    got = n(y)
    assert got.dtype == np.int32
    ref = 128.0 - 64.0 * np.abs(y.astype(np.float64))
    clear = np.abs(ref - np.floor(ref) - 0.5) > 1e-4  # exact halves round up in both; skip float32 ties
    np.testing.assert_array_equal(got[clear], np.floor(ref[clear] + 0.5))
    assert np.all(np.diff(got[y >= 0]) <= 0) and np.all(np.diff(got[y <= 0]) >= 0)
    assert n(0.3, 32, 32) == 32 and n(0.5, 16, 48) == 32


# --- vc-A19 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A19")
def test_light_cone_kernel_is_the_documented_derivation():
    """The default kernel equals its derivation recomputed here: uniform points on the sphere from PCG(2i) and
    PCG(2i+1)."""
    for i in range(6):
        u1, u2 = pcg(2 * i) / 2 ** 32, pcg(2 * i + 1) / 2 ** 32
        z, phi = 1 - 2 * u1, 2 * math.pi * u2
        k = np.array([math.sqrt(1 - z * z) * math.cos(phi), math.sqrt(1 - z * z) * math.sin(phi), z])
        np.testing.assert_array_equal(rm.LIGHT_CONE_KERNEL[i], k.astype(np.float32))
    assert np.allclose(np.linalg.norm(rm.LIGHT_CONE_KERNEL.astype(np.float64), axis=1), 1.0, atol=1e-7)


@pytest.mark.spec("vc-A19")
@pytest.mark.parametrize("impl", IMPLS)
def test_light_sample_positions_in_a_cone(impl):
    pos = pywarp.equation("vc-A19", impl=impl)
    L = unit32([0.3, 0.8, -0.52]).astype(np.float64)
    p = np.array([1.0, 2.0, 3.0])
    i = np.arange(6)
    k = rm.LIGHT_CONE_KERNEL
    q = pos(p, L, i, rm.LIGHT_STEP_KM, rm.LIGHT_CONE_ANGLE, rm.LIGHT_FAR_FACTOR, k).astype(np.float64)
    s = np.where(i < 5, (i + 1) * 0.1, 3.0 * 0.5)  # 5 near samples, the 6th at 3x the near cone length
    # position - p - axial part = the sideways offset s_i tan(15 deg) k_i: increasing, and inside the cone's ball
    side = q - p - s[:, None] * L
    np.testing.assert_allclose(side, (s * math.tan(math.radians(15)))[:, None] * k, atol=4e-6)
    assert np.all(np.diff(np.linalg.norm(side, axis=1)) > 0)
    # zero cone angle: all six on the axis at s_i
    q = pos((0, 0, 0), L, i, 0.2, 0.0, 2.0, k)
    np.testing.assert_allclose(q, np.where(i < 5, (i + 1) * 0.2, 2.0)[:, None] * L, atol=1e-6)


# --- vc-A21 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A21", "vc-2.18")
def test_march_accumulate_constant_medium_closed_form():
    c = np.zeros(3, np.float32)
    t = np.float32(1.0)
    light = (1.0, 0.5, 0.25)
    for _ in range(20):
        c, t, stop = pywarp.raymarch_accumulate(c, t, 2.0, 0.5, 0.1, light)
    assert t == pytest.approx(math.exp(-2.0), rel=1e-5)  # T = exp(-sigma rho N dt)
    np.testing.assert_allclose(c, np.array(light) * (1 - math.exp(-2.0)), rtol=1e-5)  # C = L (1 - T)
    assert stop == 0


@pytest.mark.spec("vc-A21")
def test_march_accumulate_equals_back_to_front_compositing(rng):
    """Front-to-back accumulation equals the independent back-to-front 'over' recursion in float64."""
    n = 64
    sigma, dt = 1.3, 0.05
    rho = rng.uniform(0, 2, n)
    light = rng.uniform(0, 1, (n, 3))
    c, t = np.zeros(3, np.float32), np.float32(1.0)
    for k in range(n):
        c, t, _ = pywarp.raymarch_accumulate(c, t, sigma, rho[k], dt, light[k], 0.0)
    alpha = 1 - np.exp(-sigma * rho * dt)
    ref = np.zeros(3)
    for k in reversed(range(n)):
        ref = alpha[k] * light[k] + (1 - alpha[k]) * ref
    # 64 float32 steps, each adding a few roundings relative to the running sum: within 64 * 8 eps
    np.testing.assert_allclose(c, ref, rtol=64 * 8 * EPS32)
    assert t == pytest.approx(np.exp(-sigma * dt * rho.sum()), rel=64 * 4 * EPS32)


@pytest.mark.spec("vc-A21")
@pytest.mark.parametrize("impl", IMPLS)
def test_march_accumulate_early_termination_threshold(impl):
    acc = pywarp.equation("vc-A21", impl=impl)
    one = (1, 1, 1)
    # one step of optical depth tau from T = 1: stop iff 1 - e^-tau >= 1 - eps
    for tau, eps, stop in ((10.0, 1 / 256, 1), (5.0, 1 / 256, 0), (5.0, 0.01, 1), (math.log(256) + 1e-3, 1 / 256, 1)):
        assert acc((0, 0, 0), 1.0, tau, 1.0, 1.0, one, eps)[2] == stop, (tau, eps)
    # the default threshold is 1/256
    assert acc((0, 0, 0), 1.0, 5.0, 1.0, 1.0, one)[2] == 0
    assert acc((0, 0, 0), 1.0, 6.0, 1.0, 1.0, one)[2] == 1
    # rho = 0 leaves colour and transmittance untouched
    c, t, s = acc((0.1, 0.2, 0.3), 0.7, 5.0, 0.0, 1.0, one)
    np.testing.assert_array_equal(c, np.float32([0.1, 0.2, 0.3]))
    assert (t, s) == (np.float32(0.7), 0) and s.dtype == np.int32


# --- vc-A23 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A23")
@pytest.mark.parametrize("impl", IMPLS)
def test_ray_jitter_matches_independent_pcg(impl, rng):
    jit = pywarp.equation("vc-A23", impl=impl)
    x, y, f = rng.integers(0, 4096, 300), rng.integers(0, 4096, 300), rng.integers(0, 10000, 300)
    dn = unit32([0.2, 0.7, -0.5])
    d, off = jit(dn, x, y, f, 0.01)
    seeds = [pcg((int(a) + pcg((int(b) + pcg(int(c))) & 0xFFFFFFFF)) & 0xFFFFFFFF) for a, b, c in zip(x, y, f)]
    unit = lambda hh: (hh >> 8) / 2 ** 24  # noqa: E731
    r = np.array([[2 * unit(pcg((sd + k) & 0xFFFFFFFF)) - 1 for k in range(3)] for sd in seeds])
    ref = dn.astype(np.float64) + 0.01 * r
    ref /= np.linalg.norm(ref, axis=1, keepdims=True)
    np.testing.assert_allclose(d, ref, atol=8 * EPS32)
    assert np.all(off == 0.5)
    angle = np.arccos(np.clip(d @ dn.astype(np.float64), -1, 1))
    assert angle.max() <= math.sqrt(3) * 0.01 + 1e-6 and angle.min() > 0
    # the offset mode: the same hash chain, salt 3, exactly, and the direction unchanged
    d_off, off = jit(dn, x, y, f, mode="offset")
    np.testing.assert_array_equal(off, np.array([unit(pcg((sd + 3) & 0xFFFFFFFF)) for sd in seeds], np.float32))
    np.testing.assert_array_equal(d_off, np.broadcast_to(dn, (300, 3)))
    # deterministic, and 'none' leaves the direction
    assert np.array_equal(jit(dn, x, y, f, mode="offset")[1], off)
    nd, noff = jit(dn, x, y, f, mode="none")
    np.testing.assert_array_equal(nd, np.broadcast_to(dn, (300, 3)))
    assert np.all(noff == 0.5)
    # the whole uint32 range of the seed inputs
    d_big, _ = jit(dn, 2**32 - 1, 2**31 + 5, 2**32 - 2, 0.01)
    assert np.linalg.norm(d_big.astype(np.float64)) == pytest.approx(1.0, abs=2 * EPS32)


@pytest.mark.spec("vc-A23")
def test_ray_jitter_offsets_are_uniform():
    x, y = np.meshgrid(np.arange(128), np.arange(96))
    off = pywarp.raymarch_jitter((0, 0, 1), x.ravel(), y.ravel(), 7, mode="offset")[1]
    hist = np.histogram(off, bins=8, range=(0, 1))[0]
    # 12288 samples, 1536 per bin expected; 5 sigma of the binomial count is ~185
    assert np.all(np.abs(hist - 1536) < 185)
    assert off.min() >= 0.0 and off.max() < 1.0


# --- vc-A35 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A35", "vc-2.18")
@pytest.mark.parametrize("impl", IMPLS)
def test_march_volume_sphere_and_box(impl):
    mv = pywarp.equation("vc-A35", impl=impl)
    box = lambda *a, **k: crm.march_box(*a, impl=impl, **k)  # noqa: E731
    pts, dt = mv([0, 0, -5], [0, 0, 2], (0, 0, 0), 1.0, 4)  # any direction length: normalized
    np.testing.assert_array_equal(pts[:, 2], [-0.75, -0.25, 0.25, 0.75])
    assert dt == 0.5
    pts, dt = box([0, 0, -5], [0, 0, 1], (-1, -1, -1), (1, 1, 1), 4, offset=0.0)
    np.testing.assert_array_equal(pts[:, 2], [-1.0, -0.5, 0.0, 0.5])
    # origin inside: the march starts at the origin
    pts, dt = box([0, 0, 0], [0, 1, 0], (-1, -2, -1), (1, 3, 1), 5, offset=0.0)
    np.testing.assert_allclose(pts[:, 1], [0.0, 0.6, 1.2, 1.8, 2.4], rtol=2 * EPS32)  # dt = 3/5 rounded
    # misses and volumes behind the origin give NaN
    pts, dt = mv([[0, 3, -5], [0, 0, 5]], [0, 0, 1], (0, 0, 0), 1.0, 3)
    assert np.all(np.isnan(pts)) and np.all(np.isnan(dt))
    pts, dt = box([0, 3, -5], [0, 0, 1], (-1, -1, -1), (1, 1, 1), 3)
    assert np.all(np.isnan(pts)) and np.isnan(dt)


@pytest.mark.spec("vc-A35")
def test_march_volume_uniform_between_entry_and_exit(rng):
    o = rng.uniform(-4, 4, (400, 3))
    d = rng.normal(size=(400, 3))
    c, r, n = np.array([0.5, -0.2, 0.1]), 3.0, 16
    pts, dt = pywarp.raymarch_sphere(o, d, c, r, n)
    o64, d64 = o.astype(np.float32).astype(float), d.astype(np.float32).astype(float)
    d64 /= np.linalg.norm(d64, axis=1, keepdims=True)
    t0, t1, disc = roots64(o64, d64, c.astype(np.float32).astype(float), r)
    hit = ~np.isnan(t0) & (t1 >= 0)
    clear = np.abs(disc) > 0.01 * r * r  # away from tangency, where float32 round-off may flip hit / miss
    assert np.array_equal(hit[clear], ~np.isnan(dt)[clear]) and hit.sum() > 50
    ts = np.maximum(t0, 0)
    ref = o64[:, None, :] + (ts[:, None] + (np.arange(n) + 0.5)[None, :] * ((t1 - ts) / n)[:, None])[..., None] * \
        d64[:, None, :]
    m = hit & clear
    # |t| <= 12: the roots carry <= 16 eps (|o - c| + r) (see the ray-sphere test), the sample a few more roundings
    np.testing.assert_allclose(pts[m], ref[m], atol=32 * EPS32 * 12)
    assert np.all(np.linalg.norm(pts[~np.isnan(dt)] - c, axis=-1) <= r + 1e-5)  # every sample inside the sphere


# --- vc-A36 -----------------------------------------------------------------------------------------------------------

def spec_table_rows(root):
    text = (root / "spec" / "vc.md").read_text(encoding="utf-8")
    block = text.split("### vc-A36", 1)[1].split("\n### ", 1)[0].split("\n---", 1)[0]
    rows = {}
    for line in block.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 3 and cells[0] not in ("Constant", "---") and not cells[0].startswith("-"):
            rows[cells[0]] = cells[1]
    return rows


def numbers(cell):
    """The numbers of a spec cell in order; the Unicode minus counts as a sign, the en dash as a range separator."""
    cell = cell.replace("−", "-").replace("–", " ")
    return [float(v) for v in re.findall(r"(?<![\w.])-?\d+(?:\.\d+)?", cell)]


@pytest.mark.spec("vc-A36")
@pytest.mark.parametrize("impl", IMPLS)
def test_vc_constants_match_the_spec_table(impl, root):
    k = pywarp.equation("vc-A36", impl=impl)()
    assert isinstance(k, rm.VcConstants)
    rows = spec_table_rows(root)
    f32 = lambda v: [float(np.float32(x)) for x in v]  # noqa: E731
    expected = {
        "Base texture size": [k.base_texture_size] * 3,
        "Detail texture size": [k.detail_texture_size] * 3,
        "Low-freq fBm weights (G, B, A)": list(k.low_freq_fbm_weights),
        "High-freq fBm weights (R, G, B)": list(k.high_freq_fbm_weights),
        "Detail erosion factor": [k.detail_erosion],
        "Powder exponent factor": [k.powder_factor],
        "Schlick fit": list(k.schlick_fit),
        "Cloud types": list(k.cloud_types),
        "Height-gradient break points": [*k.gradient_cumulus, *k.gradient_stratocumulus, *k.gradient_stratus],
        "View samples": [k.view_samples_zenith, k.view_samples_horizon],
        "Light samples": [k.light_samples, k.light_samples_near, 1, k.light_far_factor],
        "Reprojection block / cycle": [k.reprojection_block, k.reprojection_block, k.reprojection_cycle],
        "Tone-map constant": [k.tone_map_constant],
        "CIE clear sky in Perez form": list(k.cie_clear_sky_bcde),
        "Cloud altitudes": [k.low_cloud_top_km, k.middle_cloud_base_km, k.middle_cloud_top_km, k.high_cloud_base_km],
    }
    for label, values in expected.items():
        assert label in rows, label
        assert f32(numbers(rows[label])[:len(values)]) == f32(values), label
    assert numbers(rows["Rayleigh blue vs red"])[:3] == [k.rayleigh_blue_nm, k.rayleigh_blue_vs_red,
                                                          k.rayleigh_red_nm]
    assert "(RGBA)" in rows["Base texture size"] and k.base_texture_channels == 4
    assert "(RGB)" in rows["Detail texture size"] and k.detail_texture_channels == 3
    # the table's last row names what the text does not give: our defaults for those live elsewhere (vc-A14 etc.)
    assert "Earth radius" in rows["Not given"]


@pytest.mark.spec("vc-A36")
def test_vc_constants_agree_with_the_named_defaults():
    k = pywarp.raymarch_vc_constants()
    assert (k.view_samples_zenith, k.view_samples_horizon) == (rm.VIEW_SAMPLES_ZENITH, rm.VIEW_SAMPLES_HORIZON)
    assert k.light_far_factor == rm.LIGHT_FAR_FACTOR and k.light_samples == len(rm.LIGHT_CONE_KERNEL)
    assert k.schlick_fit == (float(np.float32(1.55)), float(np.float32(0.55)))


@pytest.mark.spec("vc-A36")
def test_vc_constants_table_is_the_c_table():
    """VC_CONSTANTS, the one Python statement of vc-A36 (the Warp struct, its constructor and the host record are
    derived from it), holds the fields of ccl_vc_constant_table in the C order, with the C values (float32) and
    the C shapes (int, float, float[n] as an n-tuple)."""
    from pywarp.core.binding import ffi, lib

    ct = ffi().typeof("ccl_vc_constant_table")
    assert list(rm.VC_CONSTANTS) == [name for name, _ in ct.fields]
    c = lib().ccl_raymarch_vc_constants()
    for name, field in ct.fields:
        v = rm.VC_CONSTANTS[name]
        if field.type.kind == "array":
            assert isinstance(v, tuple) and len(v) == field.type.length, name
            assert [float(np.float32(x)) for x in v] == list(getattr(c, name)), name
        elif field.type.cname == "int":
            assert type(v) is int and v == getattr(c, name), name
        else:
            assert field.type.cname == "float" and type(v) is float, name
            assert float(np.float32(v)) == getattr(c, name), name
    assert list(rm.VcConstantTable.vars) == list(rm.VC_CONSTANTS)


# --- C vs Warp --------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A14", "vc-A18", "vc-A19", "vc-A21", "vc-A23", "vc-A24", "vc-A35")
def test_raymarch_c_and_warp_agree_on_random_inputs(rng):
    """C (gcc -std=c99, no contraction) vs Warp (clang, no contraction) on seeded random inputs of the cloudscape's
    scales, beyond the generic contract samples: within each entry's ulp bound (2), NaN in the same places, integers
    equal. Both evaluate the same float32 expression trees in the same order with correctly rounded sqrt; expf and
    tanf come from the same glibc in both builds (measured: 0 ulp everywhere)."""
    n = 1500
    o = rng.uniform(-10, 10, (n, 3)).astype(np.float32)
    d = unit32(rng.normal(size=(n, 3)))
    c = rng.uniform(-3, 3, (n, 3)).astype(np.float32)
    r = rng.uniform(0.5, 8, n).astype(np.float32)
    alt = rng.uniform(-0.5, 12, n).astype(np.float32)
    u = lambda *s: rng.uniform(0, 1, s).astype(np.float32)  # noqa: E731
    px = lambda: rng.integers(0, 5000, n)  # noqa: E731
    assert_twins_agree("vc-A14", o, d, c, r)
    assert_twins_agree("vc-A24", np.stack([o[:, 0], alt, o[:, 2]], 1), d)
    assert_twins_agree("vc-A18", rng.uniform(-1, 1, n).astype(np.float32), 64, 128)
    i = rng.integers(0, 6, n)
    assert_twins_agree("vc-A19", o, d, i, u(n) + 0.01, u(n) * 1.5, 1 + 2 * u(n), rm.LIGHT_CONE_KERNEL[i])
    assert_twins_agree("vc-A21", u(n, 3), u(n), 3 * u(n), 2 * u(n), u(n), u(n, 3), u(n) * 0.1)
    for mode in rm.JITTER_MODES:
        assert_twins_agree("vc-A23", d, px(), px(), rng.integers(0, 99, n), 0.02 * u(n), mode=mode)
    for kw in ({"centre": (0.5, 0, 0), "radius": 6.0}, {"box_min": (-5, -4, -3), "box_max": (3, 4, 5)}):
        if "centre" in kw:
            w = pywarp.equation("vc-A35")(o, d, kw["centre"], kw["radius"], 8)
            cc = pywarp.equation("vc-A35", impl="c")(o, d, kw["centre"], kw["radius"], 8)
        else:
            w = crm.march_box(o, d, kw["box_min"], kw["box_max"], 8)
            cc = crm.march_box(o, d, kw["box_min"], kw["box_max"], 8, impl="c")
        for a, b in zip(w, cc):  # the march is not element-wise: compare its arrays directly
            np.testing.assert_array_equal(np.isnan(a), np.isnan(b))
            assert np.array_equal(a[~np.isnan(a)], b[~np.isnan(b)]), kw


# --- bad input --------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A14", "vc-A18", "vc-A19", "vc-A21", "vc-A23", "vc-A24", "vc-A35")
@pytest.mark.parametrize("impl", IMPLS)
def test_raymarch_bad_input_raises_value_error_naming_parameter(impl):
    eq = lambda cid: pywarp.equation(cid, impl=impl)  # noqa: E731
    o, up = (0, 0, 0), (0, 1, 0)
    with pytest.raises(ValueError, match=r"^direction must have unit length"):
        eq("vc-A14")(o, (0, 0, 0), o, 1.0)
    with pytest.raises(ValueError, match=r"^direction must have unit length"):
        eq("vc-A14")(o, (0, 0, 7.0), o, 1.0)
    with pytest.raises(ValueError, match=r"^radius must be in \(0, 1e\+15\], got -1\.0"):
        eq("vc-A14")(o, up, o, -1.0)
    with pytest.raises(ValueError, match=r"^origin must be finite"):
        eq("vc-A14")((np.nan, 0, 0), up, o, 1.0)
    with pytest.raises(ValueError, match=r"^centre must be an array of 3-vectors"):
        eq("vc-A14")(o, up, (0, 0), 1.0)
    with pytest.raises(ValueError, match=r"^direction must have unit length"):
        eq("vc-A24")(o, [up, (0, 0, 0)])
    with pytest.raises(ValueError, match=r"^r_inner must be < r_outer"):
        eq("vc-A24")(o, up, r_inner=6375.0, r_outer=6375.0)
    with pytest.raises(ValueError, match=r"^r_inner must be >= r_earth"):
        eq("vc-A24")(o, up, r_earth=6373.0)
    with pytest.raises(ValueError, match=r"^r_earth must be in \(0, inf\)"):
        eq("vc-A24")(o, up, r_earth=-6371.0)
    with pytest.raises(ValueError, match=r"^dir_y must be in \[-1, 1\]"):
        eq("vc-A18")(1.5)
    with pytest.raises(ValueError, match=r"^n_min must be <= n_max"):
        eq("vc-A18")(0.5, 128, 64)
    with pytest.raises(ValueError, match=r"^n_min must be in \[1, inf\)"):
        eq("vc-A18")(0.5, 0, 64)
    k = rm.LIGHT_CONE_KERNEL[0]
    with pytest.raises(ValueError, match=r"^index must be in \[0, 5\]"):
        eq("vc-A19")(o, up, 6, 0.1, 0.2, 3.0, k)
    with pytest.raises(ValueError, match=r"^to_sun must have unit length"):
        eq("vc-A19")(o, (0, 0, 0), 0, 0.1, 0.2, 3.0, k)
    with pytest.raises(ValueError, match=r"^step must be in \(0, inf\)"):
        eq("vc-A19")(o, up, 0, 0.0, 0.2, 3.0, k)
    with pytest.raises(ValueError, match=r"^cone_angle must be in \[0, 1.5708\)"):
        eq("vc-A19")(o, up, 0, 0.1, math.pi / 2, 3.0, k)
    with pytest.raises(ValueError, match=r"^transmittance must be in \[0, 1\]"):
        eq("vc-A21")(o, 1.5, 1, 1, 1, (1, 1, 1))
    with pytest.raises(ValueError, match=r"^rho must be in \[0, inf\)"):
        eq("vc-A21")(o, 1.0, 1, -1, 1, (1, 1, 1))
    with pytest.raises(ValueError, match=r"^light must be .*components in \[0, inf\)"):
        eq("vc-A21")(o, 1.0, 1, 1, 1, (1, -1, 1))
    with pytest.raises(ValueError, match=r"^mode must be one of 'tilt', 'offset', 'none'"):
        eq("vc-A23")(up, 0, 0, 0, mode="shift")
    with pytest.raises(ValueError, match=r"^frame must be in \[0, 4294967295\]"):
        eq("vc-A23")(up, 0, 0, -1)
    with pytest.raises(ValueError, match=r"^direction must be non-zero"):
        eq("vc-A35")(o, o, o, 1.0, 4)
    with pytest.raises(ValueError, match=r"^radius must be > 0"):
        eq("vc-A35")(o, (0, 0, 1), o, -1.0, 4)
    with pytest.raises(ValueError, match=r"^n must be >= 1"):
        eq("vc-A35")(o, (0, 0, 1), o, 1.0, 0)
    with pytest.raises(ValueError, match=r"^offset must be in \[0, 1\)"):
        eq("vc-A35")(o, (0, 0, 1), o, 1.0, 4, offset=1.0)
    with pytest.raises(ValueError, match=r"^box_min must be <= box_max"):
        crm.march_box(o, (0, 0, 1), (1, 0, 0), (0, 1, 1), 4, impl=impl)
