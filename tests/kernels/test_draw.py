"""Drawing with formulas (pt §3.1 - §3.5): the demo's noise (pt-alg-3.1) and fBm (pt-alg-3.2), pixel coordinates
(pt-alg-3.3), the curves of Kod 3.1, the textures of Kod 3.2, domain warping in both readings (pt-u-warp) and the
butterfly stand-in (pt-alg-3.5): closed forms, independent values, C vs Warp agreement."""
from __future__ import annotations

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree


# --- pt-alg-3.1: the noise of the demo ---------------------------------------------------------------------------------

@pytest.mark.spec("pt-alg-3.1")
def test_demo_noise_is_vc_perlin_with_range_within_one(rng):
    xy = rng.uniform(-300.0, 300.0, (2, 200000)).astype(np.float32)
    n2 = pywarp.perlin2(xy[0], xy[1])
    # the 2-D noise of the demo is the z = 0 slice of vc-A1, bit for bit
    assert np.array_equal(n2, pywarp.noise_perlin3(xy[0], xy[1], 0.0))
    # range: the sqrt(n)/2 |g| bound of gradient noise is 1 for n = 2, |g| = sqrt(2)
    assert np.abs(n2).max() <= 1.0 and np.abs(n2).max() > 0.9
    # the bound is reached at a cell centre whose four corners carry the diagonal gradient pointing at it:
    # (+-1, +-1) . (+-1/2, +-1/2) = 1 at every corner, so the value is 1 whatever the weights
    lattice = np.arange(-4, 5, dtype=np.float32)
    assert np.all(pywarp.perlin2(lattice, lattice[::-1]) == 0.0)  # zero at lattice points
    assert pywarp.equation("pt-alg-3.1") is not None and pywarp.equation("pt-alg-3.1").equation.id == "vc-A1"


# --- pt-alg-3.2: the demo's fBm -----------------------------------------------------------------------------------------

@pytest.mark.spec("pt-alg-3.2")
@pytest.mark.parametrize("octaves", range(1, 9))
def test_fbm_bound_two_times_one_minus_half_power(octaves, rng):
    p = rng.uniform(-40.0, 40.0, (50000, 2)).astype(np.float32)
    v = pywarp.noise_fbm_perlin2(p, octaves)
    bound = 2.0 * (1.0 - 0.5 ** octaves)  # 1, 1.5, 1.75, ... for |noise| <= 1 (spec pt-code-7.9 note)
    assert np.abs(v).max() <= bound
    assert np.abs(v).max() > 0.5 * bound  # a real range


@pytest.mark.spec("pt-alg-3.2")
def test_fbm_is_the_printed_sum_of_octaves(rng):
    """Independent value: sum_i A0 g^i N(F0 lambda^i p) in float64 from the noise entry, octave by octave."""
    p = rng.uniform(-20.0, 20.0, (4000, 2)).astype(np.float32)
    for a0, f0, g, lac, n in ((1.0, 0.5, 0.5, 2.0, 6), (2.5, 1.25, 0.35, 2.5, 4), (1.0, 0.5, 0.5, 2.0, 1)):
        ref = np.zeros(len(p))
        amp, f = np.float32(a0), np.float32(f0)
        for _ in range(n):
            ref += float(amp) * pywarp.perlin2(f * p[:, 0], f * p[:, 1]).astype(np.float64)
            amp, f = np.float32(amp * np.float32(g)), np.float32(f * np.float32(lac))
        got = pywarp.noise_fbm_perlin2(p, n, amplitude=a0, frequency=f0, gain=g, lacunarity=lac)
        np.testing.assert_allclose(got, ref, atol=4e-6 * a0 * n)
    # the printed defaults are A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2 (Kod 7.9)
    assert np.array_equal(pywarp.noise_fbm_perlin2(p, 5),
                          pywarp.noise_fbm_perlin2(p, 5, 0, 1.0, 0.5, 0.5, 2.0))
    assert_twins_agree("pt-alg-3.2", p[:300], 7, seed=3)


@pytest.mark.spec("pt-alg-3.2")
def test_fbm_refuses_positions_beyond_float32_precision():
    with pytest.raises(ValueError, match=r"\bp\b"):
        pywarp.noise_fbm_perlin2([1e6, 0.0], 24)
    with pytest.raises(ValueError, match=r"\bgain\b"):
        pywarp.noise_fbm_perlin2([1.0, 0.0], 3, gain=1.5)


# --- pt-alg-3.3: pixel coordinates -------------------------------------------------------------------------------------

@pytest.mark.spec("pt-alg-3.3")
def test_coords_of_obrazok_3_4_window():
    res = np.array([800.0, 600.0])
    frag = np.array([[400.0, 300.0], [0.0, 0.0], [800.0, 600.0], [600.0, 450.0]])
    uv, p, polar = pywarp.draw_coords(frag, res)
    np.testing.assert_array_equal(uv, [[0.5, 0.5], [0, 0], [1, 1], [0.75, 0.75]])
    np.testing.assert_array_equal(p, [[0, 0], [-1, -1], [1, 1], [0.5, 0.5]])
    np.testing.assert_allclose(polar[3], [np.sqrt(0.5), np.pi / 4], rtol=1e-6)
    np.testing.assert_allclose(polar[1], [np.sqrt(2), -3 * np.pi / 4], rtol=1e-6)
    # aspect correction (Kod 7.1): x in (-4/3, 4/3), y unchanged
    _, pa, _ = pywarp.draw_coords(frag, res, aspect="x")
    np.testing.assert_allclose(pa[:, 0], p[:, 0] * 800.0 / 600.0, rtol=1e-6)
    np.testing.assert_array_equal(pa[:, 1], p[:, 1])
    assert_twins_agree("pt-alg-3.3", frag, res, aspect="x")


# --- pt-code-3.1: the three curves ---------------------------------------------------------------------------------------

@pytest.mark.spec("pt-code-3.1")
def test_curves_points_on_each_curve_and_draw_order():
    y = 0.5
    pts = np.array([[0.0, 0.1],                          # y = 0.1 e^0: red
                    [-0.9 + np.sqrt(0.4), 0.0],          # on the circle: blue
                    [0.2 * np.sin(15 * y), y],           # x = 0.2 sin(15 y): yellow
                    [0.9, -0.9]], dtype=np.float32)      # nothing
    np.testing.assert_array_equal(pywarp.draw_curves(pts), [1, 2, 3, 0])
    # the threshold is in function-value units: residual 0.009 drawn, 0.011 not
    assert pywarp.draw_curves([0.0, 0.1 + 0.009]) == 1 and pywarp.draw_curves([0.0, 0.1 + 0.011]) == 0
    # draw order: where the red curve meets the circle, blue (drawn later) wins; float64 root of
    # (x + 0.9)^2 + (0.1 e^x)^2 = 0.4 by bisection on [-0.5, 0]
    lo, hi = -0.5, 0.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if (mid + 0.9) ** 2 + (0.1 * np.exp(mid)) ** 2 < 0.4 else (lo, mid)
    assert pywarp.draw_curves([lo, 0.1 * np.exp(lo)]) == 2
    # where the yellow curve crosses y = 0 (x = 0) it overwrites nothing but the background
    assert pywarp.draw_curves([0.0, 0.0]) == 3
    grid = np.stack(np.meshgrid(np.linspace(-1, 1, 97), np.linspace(-1, 1, 61)), -1)
    assert_twins_agree("pt-code-3.1", grid, 0.01)


# --- pt-code-3.2: sine, fBm, marble ----------------------------------------------------------------------------------------

@pytest.mark.spec("pt-code-3.2")
def test_marble_closed_forms(rng):
    p = rng.uniform(-1.0, 1.0, (5000, 2)).astype(np.float32)
    sine, fbm, comb = pywarp.draw_marble(p, 5)
    np.testing.assert_allclose(sine, (1 + np.sin(50.0 * p[:, 0].astype(np.float64))) / 2, atol=2e-6)
    # the fBm is pt-alg-3.2 at 5 p with the printed coefficients
    np.testing.assert_array_equal(fbm, pywarp.noise_fbm_perlin2(np.float32(5.0) * p, 5))
    ref = (1 + np.sin((p[:, 0].astype(np.float64) + fbm / 2.0) * 50.0)) / 2
    np.testing.assert_allclose(comb, ref, atol=3e-5)  # sin of |arg| <= 150 in float32: a few 1e-6 per rounding
    assert sine.min() >= 0 and sine.max() <= 1 and comb.min() >= 0 and comb.max() <= 1
    assert_twins_agree("pt-code-3.2", p[:400], 6, seed=2)


# --- pt-u-warp: domain warping, both readings -------------------------------------------------------------------------

@pytest.mark.spec("pt-u-warp")
def test_warp_scalar_reading_is_the_printed_nesting(rng):
    p = rng.uniform(-2.0, 2.0, (3000, 2)).astype(np.float32)

    def fbm(q):
        return pywarp.noise_fbm_perlin2(q, 4)

    f0 = fbm(p)
    f1 = fbm(p + f0[:, None])                      # p(x + p(x)), the scalar added to both components
    f2 = fbm(p + f1[:, None])                      # p(x + p(x + p(x)))
    for depth, ref in enumerate((f0, f1, f2)):
        np.testing.assert_array_equal(pywarp.draw_warp(p, depth, 4, variant="thesis"), ref)
    assert_twins_agree("pt-u-warp", p[:200], 2, 4, 1.0, variant="thesis")


@pytest.mark.spec("pt-u-warp")
def test_warp_vector_reading_is_quilez(rng):
    p = rng.uniform(-2.0, 2.0, (3000, 2)).astype(np.float32)
    s = np.float32(4.0)

    def fbm(q):
        return pywarp.noise_fbm_perlin2(q, 4)

    o = np.array([[0.0, 0.0], [5.2, 1.3], [1.7, 9.2], [8.3, 2.8]], dtype=np.float32)
    q = np.stack([fbm(p + o[0]), fbm(p + o[1])], -1)
    r = np.stack([fbm(p + s * q + o[2]), fbm(p + s * q + o[3])], -1)
    np.testing.assert_array_equal(pywarp.draw_warp(p, 1, 4, 4.0, variant="corrected"), fbm(p + s * q))
    np.testing.assert_array_equal(pywarp.draw_warp(p, 2, 4, 4.0, variant="corrected"), fbm(p + s * r))
    # depth 0 and strength 0 are the plain fBm in both readings; the readings differ otherwise
    for v in ("thesis", "corrected"):
        np.testing.assert_array_equal(pywarp.draw_warp(p, 0, 4, variant=v), fbm(p))
        np.testing.assert_array_equal(pywarp.draw_warp(p, 2, 4, 0.0, variant=v), fbm(p))
    assert not np.allclose(pywarp.draw_warp(p, 1, 4, variant="thesis"), pywarp.draw_warp(p, 1, 4, variant="corrected"))
    assert_twins_agree("pt-u-warp", p[:200], 2, 5, 4.0, seed=7, variant="corrected")


# --- pt-alg-3.5: the butterfly stand-in -------------------------------------------------------------------------------

def _screen(n=64):
    u = (np.arange(n) + 0.5) / n * 2 - 1
    return np.stack(np.meshgrid(u * 1.2, u[::-1] * 0.9), -1).astype(np.float32)


@pytest.mark.spec("pt-alg-3.5")
def test_butterfly_symmetric_when_centred_and_periodic():
    p = _screen()
    img0 = pywarp.draw_butterfly(p, 0.0)
    sky = pywarp.draw_butterfly(np.array([[-1.19, 0.89]], np.float32), 0.0)
    # at t = 0 the butterfly is at the origin, wings flat, the camera on the yz plane: a mirror-symmetric image
    np.testing.assert_allclose(img0, img0[:, ::-1], atol=1e-6)
    wing = np.any(np.abs(img0 - img0[:1, :1]) > 0.2, axis=-1)
    assert 0.03 < wing.mean() < 0.6, wing.mean()  # the wings cover part of the frame
    assert img0.min() >= 0 and img0.max() <= 1 and sky.shape == (1, 3)
    # the flight repeats every 4 s (6 wing beats at 1.5 Hz): frames 4 s apart agree except at a few edge pixels
    a, b = pywarp.draw_butterfly(p, 0.7), pywarp.draw_butterfly(p, 4.7)
    assert np.mean(np.any(np.abs(a - b) > 1e-3, axis=-1)) < 0.01
    # and the wings move: a quarter beat later the frame differs
    assert np.mean(np.any(np.abs(pywarp.draw_butterfly(p, 0.7 + 1 / 6) - a) > 1e-3, axis=-1)) > 0.02
    assert_twins_agree("pt-alg-3.5", p[::4, ::4], 1.3)
