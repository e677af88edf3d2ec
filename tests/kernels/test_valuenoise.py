"""Value noise of the oc text (§5.1): the lattice hash (oc-5.1.2), the smoothing kernels against their weights written
out in float64 (oc-5.1.3), the printed interpolants -- end points, the cosine's (a+b)/2 and 0.1464466, the cubic's
printed slope, which is not Catmull-Rom's (oc-5.1.4.1 - 5.1.4.3) --, the separable 2-D/3-D interpolation (oc-5.1.4),
both persistence schedules (oc-5.1.2.2), the octave sum and the 16 x 16 -> 256 x 256 layer procedure (oc-5.1.1,
oc-5.1.2.1, oc-4.5), C vs Warp, bad input."""
from __future__ import annotations

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree
from pywarp.kernels.hash import hash_pcg_py
from pywarp.flight.clouds import octave_image
from pywarp.kernels.valuenoise import INTERPOLATIONS, SMOOTHINGS, octave_seed

lattice = pywarp.equation("oc-5.1.2")
smooth = pywarp.equation("oc-5.1.3")
linear = pywarp.equation("oc-5.1.4.1")
cosine = pywarp.equation("oc-5.1.4.2")
cubic = pywarp.equation("oc-5.1.4.3")
interpolated = pywarp.equation("oc-5.1.4")
amplitude = pywarp.equation("oc-5.1.2.2")
fbm = pywarp.equation("oc-5.1.1")


def _lattice_py(x, y, z, seed):
    """The header's formula in Python integers (independent of the code under test)."""
    h = hash_pcg_py((x + hash_pcg_py((y + hash_pcg_py((z + seed) & 0xFFFFFFFF)) & 0xFFFFFFFF)) & 0xFFFFFFFF)
    return (h >> 8) / 2.0 ** 24


@pytest.mark.spec("oc-5.1.2")
def test_lattice_is_the_seeded_pcg_hash_in_both_ranges():
    rng = np.random.default_rng(1)
    x, y, z = (rng.integers(0, 100000, 300) for _ in range(3))
    u = lattice(x, y, z, 77)
    assert np.array_equal(u, np.array([_lattice_py(*p, 77) for p in zip(x, y, z)], np.float32))
    s = lattice(x, y, z, 77, value_range="signed")
    assert np.array_equal(s, 2.0 * u - 1.0)
    assert u.min() >= 0.0 and u.max() < 1.0 and s.min() >= -1.0 and s.max() < 1.0
    assert np.array_equal(lattice(x, y, z, 77), u)  # deterministic
    assert not np.array_equal(lattice(x, y, z, 78), u)  # the seed matters
    big = lattice(np.arange(20000), 3, 4, 5)
    assert big.mean() == pytest.approx(0.5, abs=0.01) and big.std() == pytest.approx(np.sqrt(1 / 12), abs=0.01)


def _lat(x, y, z, seed=11):
    return np.float64(lattice(x, y, z, seed))


@pytest.mark.spec("oc-5.1.3")
def test_smoothing_weights_written_out():
    x, y = 20, 30
    corners = sum(_lat(x + dx, y + dy, 0) for dx in (-1, 1) for dy in (-1, 1))
    sides = sum(_lat(x + dx, y + dy, 0) for dx, dy in ((-1, 0), (1, 0), (0, -1), (0, 1)))
    centre = _lat(x, y, 0)
    # Elias: corners/16 + sides/8 + centre/4; z is ignored in 2-D
    assert smooth(x, y, 99, 11, 2) == pytest.approx(corners / 16 + sides / 8 + centre / 4, abs=1e-6)
    assert smooth(x, y, 99, 11, 2, smoothing="4-neighbour") == pytest.approx(sides / 4, abs=1e-6)
    assert smooth(x, y, 99, 11, 2, smoothing="8-neighbour") == pytest.approx((sides + corners) / 8, abs=1e-6)
    assert smooth(x, y, 99, 11, 2, smoothing="none") == np.float32(centre)
    # 1-D: v/2 + (l + r)/4
    assert smooth(x, 5, 5, 11, 1) == pytest.approx(_lat(x, 0, 0) / 2 + (_lat(x - 1, 0, 0) + _lat(x + 1, 0, 0)) / 4,
                                                   abs=1e-6)
    # 3-D: binomial (1/4, 1/2, 1/4)^3 (corners/64 + edges/32 + faces/16 + centre/8), 6 faces, 26 neighbours
    z = 40
    w = {-1: 0.25, 0: 0.5, 1: 0.25}
    offs = [(dx, dy, dz) for dz in (-1, 0, 1) for dy in (-1, 0, 1) for dx in (-1, 0, 1)]
    vals = {o: _lat(x + o[0], y + o[1], z + o[2]) for o in offs}
    elias = sum(w[o[0]] * w[o[1]] * w[o[2]] * v for o, v in vals.items())
    faces = [v for o, v in vals.items() if sum(map(abs, o)) == 1]
    others = [v for o, v in vals.items() if o != (0, 0, 0)]
    assert smooth(x, y, z, 11, 3) == pytest.approx(elias, abs=1e-6)
    assert smooth(x, y, z, 11, 3, smoothing="4-neighbour") == pytest.approx(np.mean(faces), abs=1e-6)
    assert smooth(x, y, z, 11, 3, smoothing="8-neighbour") == pytest.approx(np.mean(others), abs=1e-6)


@pytest.mark.spec("oc-5.1.3")
def test_smoothing_reduces_the_spread():
    x = np.arange(1, 4001)
    raw = smooth(x, 7, 0, 3, 2, smoothing="none")
    for kind in ("elias", "4-neighbour", "8-neighbour"):
        s = smooth(x, 7, 0, 3, 2, smoothing=kind)
        assert s.std() < 0.6 * raw.std() and s.mean() == pytest.approx(0.5, abs=0.02)


@pytest.mark.spec("oc-5.1.4", "oc-5.1.4.1", "oc-5.1.4.2", "oc-5.1.4.3")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_interpolants_hit_their_end_points(impl):
    rng = np.random.default_rng(2)
    a = rng.uniform(-100, 100, 500).astype(np.float32)
    b = rng.uniform(-100, 100, 500).astype(np.float32)
    v0 = rng.uniform(-100, 100, 500).astype(np.float32)
    v3 = rng.uniform(-100, 100, 500).astype(np.float32)
    lin = pywarp.equation("oc-5.1.4.1", impl=impl)
    cos = pywarp.equation("oc-5.1.4.2", impl=impl)
    cub = pywarp.equation("oc-5.1.4.3", impl=impl)
    for f in (lin, cos):
        assert np.array_equal(f(a, b, 0.0), a) and np.array_equal(f(a, b, 1.0), b)  # exactly
    assert np.array_equal(cub(v0, a, b, v3, 0.0), a)
    # x = 1: P + Q + R + S = v2 up to the rounding of four sums of values of magnitude <= 400
    np.testing.assert_allclose(cub(v0, a, b, v3, 1.0), b, rtol=0, atol=400 * 4 * 2 ** -23)


@pytest.mark.spec("oc-5.1.4.1")
def test_printed_linear_is_exact_where_lerp_is_not():
    """Why oc-5.1.4.1 is its own function: interp_lerp's a + t (b - a) misses b at t = 1 for some floats."""
    from pywarp.core.binding import vectorize

    rng = np.random.default_rng(3)
    a = rng.uniform(0, 1, 2000).astype(np.float32)
    b = rng.uniform(0, 1, 2000).astype(np.float32)
    lerp = np.asarray(vectorize("ccl_interp_lerp")(np.float32(1.0), a, b), np.float32)
    assert np.any(lerp != b)
    assert np.array_equal(linear(a, b, 1.0), b)
    t = rng.uniform(0, 1, 2000).astype(np.float32)
    np.testing.assert_allclose(linear(a, b, t), a * (1.0 - t.astype(np.float64)) + b * t.astype(np.float64), atol=2e-7)


@pytest.mark.spec("oc-5.1.4.2")
def test_cosine_midpoint_and_check_value():
    a = np.float32([0.0, 0.1, -3.0, 10.0])
    b = np.float32([1.0, 0.7, 5.0, -10.0])
    np.testing.assert_allclose(cosine(a, b, 0.5), (a.astype(np.float64) + b) / 2, rtol=0, atol=1e-6)
    assert cosine(0.0, 1.0, 0.25) == pytest.approx(0.1464466, abs=1e-7)
    x = np.linspace(0, 1, 41)
    np.testing.assert_allclose(cosine(0.0, 1.0, x), (1 - np.cos(3.1415927 * x)) / 2, atol=2e-7)
    assert np.all(np.diff(cosine(0.0, 1.0, x)) > 0)


@pytest.mark.spec("oc-5.1.4.3")
def test_cubic_printed_slope_is_not_catmull_rom():
    v0, v1, v2, v3 = 0.2, 0.5, 0.9, 0.4
    h = 2.0 ** -10
    s0 = (np.float64(cubic(v0, v1, v2, v3, h)) - cubic(v0, v1, v2, v3, 0.0)) / h
    s1 = (np.float64(cubic(v0, v1, v2, v3, 1.0)) - cubic(v0, v1, v2, v3, 1.0 - h)) / h
    assert s0 == pytest.approx(v2 - v0, abs=0.01)  # the printed R = v2 - v0
    assert s1 == pytest.approx(v3 - v1, abs=0.01)  # 3P + 2Q + R = v3 - v1
    assert abs(s0 - (v2 - v0) / 2) > 0.3  # Catmull-Rom's slope is half of that
    # the catalogue's check values
    assert cubic(0, 0, 1, 1, 0.5) == 0.5
    x = np.linspace(0, 1, 33)
    np.testing.assert_allclose(cubic(0.0, 1.0, 0.0, 1.0, x), 2 * x ** 3 - 3 * x ** 2 + 1, atol=3e-7)
    # the polynomial itself, float64
    p = (v3 - v2) - (v0 - v1)
    q = (v0 - v1) - p
    np.testing.assert_allclose(cubic(v0, v1, v2, v3, x), p * x ** 3 + q * x ** 2 + (v2 - v0) * x + v1, atol=3e-7)
    # it overshoots its samples (unlike linear and cosine): (0, 1, 1, 0) -> -x^2 + x + 1, 1.25 at x = 1/2
    assert cubic(0.0, 1.0, 1.0, 0.0, 0.5) == 1.25


@pytest.mark.spec("oc-5.1.4")
@pytest.mark.parametrize("dims", [1, 2, 3])
def test_interpolation_is_separable_and_hits_the_lattice(dims):
    pts = np.array([[12.0, 7.0, 3.0], [0.0, 0.0, 0.0], [100.0, 5.0, 9.0]], np.float32)
    for kind in INTERPOLATIONS:
        v = interpolated(pts[:, 0], pts[:, 1], pts[:, 2], 5, dims, interpolation=kind)
        ref = smooth(pts[:, 0].astype(int), pts[:, 1].astype(int), pts[:, 2].astype(int), 5, dims)
        np.testing.assert_allclose(v, ref, atol=1e-6 if kind == "cubic" else 0)
    # bilinear / trilinear written out in float64 from the smoothed lattice
    x, y, z = 4.25, 9.5, 2.75
    s = lambda i, j, k: np.float64(smooth(i, j, k, 5, dims))  # noqa: E731
    if dims == 1:
        ref = 0.75 * s(4, 0, 0) + 0.25 * s(5, 0, 0)
    elif dims == 2:
        ref = 0.5 * (0.75 * s(4, 9, 0) + 0.25 * s(5, 9, 0)) + 0.5 * (0.75 * s(4, 10, 0) + 0.25 * s(5, 10, 0))
    else:
        ref = sum(wx * wy * wz * s(i, j, k) for i, wx in ((4, 0.75), (5, 0.25)) for j, wy in ((9, 0.5), (10, 0.5))
                  for k, wz in ((2, 0.25), (3, 0.75)))
    assert interpolated(x, y, z, 5, dims) == pytest.approx(ref, abs=1e-6)


@pytest.mark.spec("oc-5.1.2.2")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_persistence_schedules_of_both_variants(impl):
    amp = pywarp.equation("oc-5.1.2.2", impl=impl)
    i = np.arange(8)
    for p in (0.25, 0.5, 0.7, 1.0):
        pf = float(np.float32(p))
        np.testing.assert_allclose(amp(i, p), pf ** i.astype(np.float64), rtol=1e-6)  # corrected: p^i
        # printed: p^(2^i); each float32 squaring doubles the relative error so far and adds one rounding (2^i ulp
        # after i squarings); float32 underflows to 0 below ~1e-45
        np.testing.assert_allclose(amp(i, p, variant="thesis"), pf ** (2.0 ** i), rtol=2.0 ** (i.max() + 1 - 24),
                                   atol=1e-44)
    assert amp(0, 0.5) == 1.0 and amp(0, 0.5, variant="thesis") == 0.5
    assert amp(3, 0.5, variant="thesis") == 0.5 ** 8


@pytest.mark.spec("oc-5.1.1", "oc-5.1.2.1", "oc-5.1.2.2", "oc-4.5")
def test_octave_sum_written_out():
    x, y = np.float32(3.3), np.float32(1.7)
    for variant in ("corrected", "thesis"):
        p = 0.6
        amps = [np.float64(amplitude(i, p, variant=variant)) for i in range(4)]
        layers = [np.float64(interpolated(x * 2 ** i, y * 2 ** i, 0.0, octave_seed(8, i), 2)) for i in range(4)]
        ref = sum(a * v for a, v in zip(amps, layers)) / sum(amps)
        assert fbm(x, y, 0.0, 8, 2, 4, p, variant=variant) == pytest.approx(ref, abs=1e-6)
    assert octave_seed(8, 2) == (hash_pcg_py(8) + 2) & 0xFFFFFFFF
    # the default is 6 octaves (§5.1.2.1: 'generally 6 is enough')
    assert fbm(x, y, 0.0, 8, 2) == fbm(x, y, 0.0, 8, 2, 6, 0.5)
    # normalised: linear and cosine stay in [0, 1] (or [-1, 1])
    rng = np.random.default_rng(4)
    pts = rng.uniform(0, 50, (3, 2000)).astype(np.float32)
    for kind in ("linear", "cosine"):
        v = fbm(*pts, 1, 3, 6, 0.5, interpolation=kind)
        assert v.min() >= 0.0 and v.max() <= 1.0
        v = fbm(*pts, 1, 3, 6, 0.5, interpolation=kind, value_range="signed")
        assert v.min() >= -1.0 and v.max() <= 1.0 and v.min() < 0.0


@pytest.mark.spec("oc-5.1.1", "oc-5.1.2.2")
def test_thesis_schedule_fades_the_detail_faster():
    """The printed squaring weights octave 3 by p^8 instead of p^3: the sum is smoother (less high-frequency energy)."""
    x = np.linspace(0, 8, 4001, dtype=np.float32)
    corr = fbm(x, 0.0, 0.0, 2, 1, 6, 0.6)
    thesis = fbm(x, 0.0, 0.0, 2, 1, 6, 0.6, variant="thesis")
    assert np.abs(np.diff(thesis, 2)).mean() < 0.5 * np.abs(np.diff(corr, 2)).mean()


@pytest.mark.spec("oc-5.1.1")
def test_octave_image_16_to_256_equals_the_octave_sum():
    layers, amps, total = octave_image(size=64, base=4, octaves=5, seed=3)  # 4 -> 64, the text's 16 -> 256 / 4
    assert [lay.shape for lay in layers] == [(64, 64)] * 5 and len(amps) == 5
    px = np.arange(64, dtype=np.float32) * np.float32(4) / np.float32(64)
    xx, yy = np.meshgrid(px, px)
    np.testing.assert_allclose(total, fbm(xx, yy, 0.0, 3, 2, 5, 0.5), atol=2e-7)
    # layer i has base * 2^i cells per edge: the last layer changes from pixel to pixel, the first is smooth
    assert np.abs(np.diff(layers[0], axis=1)).mean() < np.abs(np.diff(layers[-1], axis=1)).mean() / 4
    with pytest.raises(ValueError, match="octaves"):
        octave_image(octaves=0)


@pytest.mark.spec("oc-5.1.2", "oc-5.1.3", "oc-5.1.4", "oc-5.1.1")
def test_c_and_warp_agree_for_every_option():
    rng = np.random.default_rng(5)
    ix = [rng.integers(0, 5000, 64) for _ in range(3)]
    fx = [rng.uniform(0, 40, 64).astype(np.float32) for _ in range(3)]
    for r in ("unit", "signed"):
        assert_twins_agree("oc-5.1.2", *ix, 9, value_range=r)
        for dims in (1, 2, 3):
            for sm in SMOOTHINGS:
                assert_twins_agree("oc-5.1.3", *ix, 9, dims, smoothing=sm, value_range=r)
            for kind in INTERPOLATIONS:
                assert_twins_agree("oc-5.1.4", *fx, 9, dims, interpolation=kind, value_range=r)
    for variant in ("corrected", "thesis"):
        assert_twins_agree("oc-5.1.1", *fx, 9, 3, 6, 0.5, interpolation="cubic", variant=variant)
    assert_twins_agree("oc-5.1.4.3", *(rng.uniform(-1, 1, 64).astype(np.float32) for _ in range(4)),
                       rng.uniform(0, 1, 64).astype(np.float32))


@pytest.mark.spec("oc-5.1.1", "oc-5.1.3")
def test_bad_input_is_refused_naming_the_parameter():
    with pytest.raises(ValueError, match="persistence"):
        fbm(1.0, 1.0, 1.0, 0, 3, 6, 0.0)  # 0 would weight every 'thesis' octave 0
    with pytest.raises(ValueError, match="dims"):
        smooth(1, 1, 1, 0, 4)
    with pytest.raises(ValueError, match="octaves"):
        fbm(1.0, 1.0, 1.0, 0, 3, 13, 0.5)
    with pytest.raises(ValueError, match="x"):
        lattice(-1, 0, 0, 0)  # the text's lattice takes non-negative integers
    with pytest.raises(ValueError, match="smoothing"):
        smooth(1, 1, 1, 0, 2, smoothing="gauss")
    with pytest.raises(ValueError, match="interpolation"):
        interpolated(1.0, 1.0, 1.0, 0, 2, interpolation="catmull-rom")
