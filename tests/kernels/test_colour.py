"""Colour conversions vc-2.32 (XYZ -> xy), vc-4.3 (xyY -> XYZ), vc-4.4 (XYZ -> linear sRGB, erratum -0.9392660),
vc-4.5 (tone map, sign erratum) and the sRGB encoding of the vc-A29 render chain.

colour-science is the independent oracle for every conversion. Float32 error bounds use u = 2^-24 (unit roundoff):
each correctly rounded +, -, *, / adds at most u relative error; libm's expf/powf are within 1 ulp (2u).
"""
from __future__ import annotations

import colour
import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree
from pywarp.clouds.sky import srgb_encode_array

U = 2.0 ** -24  # float32 unit roundoff
D65_LINDBLOOM = (0.95047, 1.0, 1.08883)


def f32(a):
    """The float32 value the kernels see, back in float64 (references are evaluated at the same inputs)."""
    return np.asarray(a, dtype=np.float32).astype(np.float64)


def lindbloom_matrix_from_colour():
    """XYZ -> linear sRGB built by colour-science from the sRGB primaries and Lindbloom's D65 white (0.95047, 1,
    1.08883): reproduces Lindbloom's 7-digit matrix (the corrected vc-4.4) to 4.6e-8."""
    sp = colour.models.RGB_COLOURSPACE_sRGB
    npm = colour.normalised_primary_matrix(sp.primaries, colour.XYZ_to_xy(np.array(D65_LINDBLOOM)))
    return np.linalg.inv(npm)



def v3(*c):
    """Stack components into (..., 3) vectors (broadcasting them first)."""
    return np.stack(np.broadcast_arrays(*(np.asarray(x, dtype=np.float64) for x in c)), axis=-1)


# --- vc-2.32 ----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.32")
def test_XYZ_to_xy_matches_colour_science(rng):
    XYZ = f32(rng.uniform(0.0, 100.0, (3000, 3)))
    x, y = np.moveaxis(pywarp.colour_XYZ_to_xy(XYZ), -1, 0)
    ref = colour.XYZ_to_xy(XYZ)
    # a sum of three non-negative terms (2 roundings, 2u) and one division (u): relative error <= 3u + O(u^2)
    np.testing.assert_allclose(x, ref[:, 0], rtol=3.001 * U, atol=0)
    np.testing.assert_allclose(y, ref[:, 1], rtol=3.001 * U, atol=0)


@pytest.mark.spec("vc-2.32")
def test_XYZ_to_xy_closed_forms():
    x, y = pywarp.colour_XYZ_to_xy(D65_LINDBLOOM)
    assert x == pytest.approx(0.312727, abs=1e-6) and y == pytest.approx(0.329023, abs=1e-6)  # D65 (Lindbloom)
    assert tuple(pywarp.colour_XYZ_to_xy([1.0, 1.0, 1.0])) == pytest.approx((1 / 3, 1 / 3), rel=1e-7)  # white E
    assert tuple(pywarp.colour_XYZ_to_xy([2.0, 0.0, 0.0])) == (1.0, 0.0)
    xy = pywarp.colour_XYZ_to_xy(v3(np.ones((2, 3)), 2.0, 3.0))  # shapes preserved, xy on the last axis
    assert xy.shape == (2, 3, 2) and np.all(xy[..., 0] == np.float32(1 / 6))


@pytest.mark.spec("vc-2.32", "vc-4.3")
def test_xy_and_xyY_round_trip(rng):
    XYZ = f32(rng.uniform(0.01, 50.0, (2000, 3)))
    x, y = np.moveaxis(pywarp.colour_XYZ_to_xy(XYZ), -1, 0)
    X, Y, Z = np.moveaxis(pywarp.colour_xyY_to_XYZ(v3(x, y, XYZ[:, 1])), -1, 0)
    np.testing.assert_array_equal(Y, XYZ[:, 1].astype(np.float32))  # Y passes through
    # x, y carry 3u each; X = x (Y / y) adds 2u: |dX| <= 8u X. Z = ((1 - x) - y)(Y / y): x, y's errors enter in
    # absolute terms 3u (x + y), the two subtractions u (1 - x) + u z, then y's 3u and 2 roundings on Z; with
    # Y / y = X + Y + Z = s:  |dZ| <= u s (3 (x + y) + (1 - x) + z) + 5u Z   (+ O(u^2))
    s = XYZ.sum(axis=1)
    x64, y64, z64 = XYZ[:, 0] / s, XYZ[:, 1] / s, XYZ[:, 2] / s
    np.testing.assert_allclose(X, XYZ[:, 0], rtol=8.001 * U, atol=0)
    bound = U * s * (3 * (x64 + y64) + (1 - x64) + z64) + 5 * U * XYZ[:, 2]
    assert np.all(np.abs(Z - XYZ[:, 2]) <= bound * (1 + 1e-6))


@pytest.mark.spec("vc-2.32")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_XYZ_to_xy_bad_input(impl):
    f = pywarp.equation("vc-2.32", impl=impl)
    with pytest.raises(ValueError, match=r"^XYZ must have X \+ Y \+ Z > 0"):
        f([0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"^XYZ must have components >= 0, got -0\.1"):
        f([-0.1, 1.0, 1.0])
    with pytest.raises(ValueError, match=r"^XYZ must be finite"):
        f([1.0, 1.0, np.nan])
    with pytest.raises(ValueError, match=r"^XYZ must be an array of 3-vectors"):
        f([1.0, 1.0])


# --- vc-4.3 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-4.3")
def test_xyY_to_XYZ_matches_colour_science(rng):
    x = f32(rng.uniform(0.0, 0.7, 3000))
    y = f32(rng.uniform(0.01, 0.8, 3000))
    Y = f32(rng.uniform(0.0, 100.0, 3000))
    X_, Y_, Z_ = np.moveaxis(pywarp.colour_xyY_to_XYZ(v3(x, y, Y)), -1, 0)
    ref = colour.xyY_to_XYZ(np.stack([x, y, Y], axis=-1))
    k = Y / y
    # X = x * (Y / y): two roundings. Z = ((1 - x) - y) * (Y / y): the two subtractions err by u |1 - x| and
    # u |1 - x - y| in absolute terms, the division and product add 2u relative.
    np.testing.assert_allclose(X_, ref[:, 0], rtol=2 * U, atol=0)
    np.testing.assert_array_equal(Y_, ref[:, 1].astype(np.float32))
    bound = U * k * (np.abs(1 - x) + 3 * np.abs(1 - x - y))
    assert np.all(np.abs(Z_ - ref[:, 2]) <= bound)


@pytest.mark.spec("vc-4.3")
def test_xyY_to_XYZ_closed_form_white():
    # D65 chromaticity (0.3127, 0.3290) at Y = 1 -> (0.95046, 1, 1.08906) (IEC 61966-2-1 white)
    X, Y, Z = pywarp.colour_xyY_to_XYZ([0.3127, 0.3290, 1.0])
    assert (X, Y, Z) == pytest.approx((0.3127 / 0.3290, 1.0, (1 - 0.3127 - 0.3290) / 0.3290), rel=1e-6)


@pytest.mark.spec("vc-4.3")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_xyY_to_XYZ_bad_input(impl):
    f = pywarp.equation("vc-4.3", impl=impl)
    with pytest.raises(ValueError, match=r"^xyY must have its component y in \(0, 1\], got 0\.0"):
        f([0.3, 0.0, 1.0])
    with pytest.raises(ValueError, match=r"^xyY must have its component y in \(0, 1\]"):
        f(v3(0.3, [0.3, -0.2], 1.0))
    with pytest.raises(ValueError, match=r"^xyY must be finite"):
        f([0.3, np.nan, 1.0])
    with pytest.raises(ValueError, match=r"^xyY must have its component Y in \[0, inf\)"):
        f([0.3, 0.3, -1.0])
    with pytest.raises(ValueError, match=r"^xyY must have its component x in \[0, 1\]"):
        f([1.2, 0.3, 1.0])


# --- vc-4.4 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-4.4")
def test_XYZ_to_linear_srgb_matches_colour_science(rng):
    XYZ = f32(rng.uniform(0.0, 100.0, (3000, 3)))
    rgb = pywarp.colour_XYZ_to_linear_srgb(XYZ).astype(np.float64)
    M = lindbloom_matrix_from_colour()
    ref = XYZ @ M.T
    # each channel: three products and two sums (4u on sum |m_ij X_j|), each float32 entry rounded (u |m_ij|),
    # and Lindbloom's 7 digits vs colour's exact matrix (<= 4.6e-8 per entry)
    bound = 5 * U * (np.abs(XYZ) @ np.abs(M).T) + 4.6e-8 * np.abs(XYZ).sum(axis=1, keepdims=True)
    assert np.all(np.abs(rgb - ref) <= bound)
    # colour-science's own sRGB colourspace uses the IEC 61966-2-1 4-digit matrix: entries differ by <= 3.7e-4
    iec = colour.XYZ_to_RGB(XYZ, colour.models.RGB_COLOURSPACE_sRGB, apply_cctf_encoding=False)
    assert np.all(np.abs(rgb - iec) <= 3.7e-4 * XYZ.sum(axis=1, keepdims=True))


@pytest.mark.spec("vc-4.4")
def test_XYZ_to_linear_srgb_variants_white_point():
    """The erratum pinned: D65 white -> (1, 1, 1) with -0.9692660, G = 1.02851 with the printed -0.9392660."""
    r, g, b = pywarp.colour_XYZ_to_linear_srgb(D65_LINDBLOOM)
    assert (r, g, b) == pytest.approx((1.0, 1.0, 1.0), abs=2e-6)
    rt, gt, bt = pywarp.colour_XYZ_to_linear_srgb(D65_LINDBLOOM, variant="thesis")
    assert gt == pytest.approx(1.02851, abs=1e-5)
    assert gt - g == pytest.approx(0.03 * 0.95047, abs=2e-6)
    assert (rt, bt) == (r, b)  # only row 2 differs
    # unit X shows the (2, 1) entry itself
    assert pywarp.colour_XYZ_to_linear_srgb([1.0, 0.0, 0.0])[1] == np.float32(-0.9692660)
    assert pywarp.colour_XYZ_to_linear_srgb([1.0, 0.0, 0.0], variant="thesis")[1] == np.float32(-0.9392660)


@pytest.mark.spec("vc-4.4")
def test_XYZ_to_linear_srgb_primaries_map_to_unit_vectors():
    """colour-science's XYZ of the sRGB primaries (Lindbloom white) map to (1,0,0), (0,1,0), (0,0,1)."""
    sp = colour.models.RGB_COLOURSPACE_sRGB
    npm = colour.normalised_primary_matrix(sp.primaries, colour.XYZ_to_xy(np.array(D65_LINDBLOOM)))
    for k in range(3):
        out = pywarp.colour_XYZ_to_linear_srgb(npm[:, k])
        np.testing.assert_allclose(out, np.eye(3)[k], atol=3e-7)


@pytest.mark.spec("vc-4.4")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_XYZ_to_linear_srgb_bad_input(impl):
    f = pywarp.equation("vc-4.4", impl=impl)
    with pytest.raises(ValueError, match=r"^variant must be one of 'corrected', 'thesis'"):
        f([1.0, 1.0, 1.0], variant="lindbloom")
    with pytest.raises(ValueError, match=r"^XYZ must be finite"):
        f([1.0, np.nan, 1.0])


# --- vc-4.5 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-4.5")
def test_tonemap_exp_matches_float64_and_variants(rng):
    c = f32(rng.uniform(-5.0, 200.0, 3000))
    k = f32(rng.uniform(0.005, 0.2, 3000))
    for variant, sign in (("corrected", -1.0), ("thesis", 1.0)):
        out = pywarp.colour_tonemap_exp(c, k, variant=variant).astype(np.float64)
        e = np.exp(sign * k * c)
        # the argument's rounding (u |k c|) moves exp by e u |k c|; expf <= 1 ulp (2u e); the subtraction u |out|
        bound = e * U * np.abs(k * c) + 2 * U * e + U * np.abs(1 - e)
        assert np.all(np.abs(out - (1 - e)) <= bound * (1 + 1e-9)), variant
    assert pywarp.colour_tonemap_exp(100.0) == pytest.approx(1 - np.exp(-3.0), rel=1e-6)  # 0.950213
    assert pywarp.colour_tonemap_exp(100.0, variant="thesis") == pytest.approx(1 - np.exp(3.0), rel=1e-6)  # -19.0855


@pytest.mark.spec("vc-4.5")
def test_tonemap_exp_properties():
    c = np.linspace(0.0, 500.0, 5001)
    t = pywarp.colour_tonemap_exp(c)
    assert t[0] == 0.0 and np.all(np.diff(t) >= 0) and np.all((t >= 0) & (t <= 1))
    assert pywarp.colour_tonemap_exp(1e-3) == pytest.approx(0.03e-3, rel=1e-3)  # slope k at 0
    # as printed, 1 - exp(+0.03 C) <= 0 for every C >= 0: a black image after clamping (spec error index item 11)
    assert np.all(pywarp.colour_tonemap_exp(c, variant="thesis") <= 0)
    np.testing.assert_array_equal(pywarp.colour_tonemap_exp(c, variant="thesis"), pywarp.colour_tonemap_exp(-c))
    # exposure is a named parameter with the thesis' 0.03 as default
    assert pywarp.colour_tonemap_exp(10.0) == pywarp.colour_tonemap_exp(10.0, exposure=0.03)
    assert pywarp.colour_tonemap_exp(10.0, exposure=0.1) == pytest.approx(1 - np.exp(-1.0), rel=1e-6)


@pytest.mark.spec("vc-4.5")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_tonemap_exp_bad_input(impl):
    f = pywarp.equation("vc-4.5", impl=impl)
    with pytest.raises(ValueError, match=r"^exposure must be in \(0, inf\), got 0\.0"):
        f(1.0, exposure=0.0)
    with pytest.raises(ValueError, match=r"^exposure must be in \(0, inf\)"):
        f(1.0, exposure=-0.03)
    with pytest.raises(ValueError, match=r"^c_hdr must be finite"):
        f(np.nan)
    with pytest.raises(ValueError, match=r"^variant must be one of"):
        f(1.0, variant=1)


# --- sRGB encoding (IEC 61966-2-1), part of the vc-A29 render chain --------------------------------------------------

@pytest.mark.spec("vc-A29")
def test_srgb_encode_matches_colour_science(rng):
    c = f32(np.concatenate([rng.uniform(0.0, 1.0, 3000), rng.uniform(0.0, 0.004, 500), [0.0, 0.0031308, 1.0],
                            rng.uniform(-0.5, 0.0, 100), rng.uniform(1.0, 4.0, 100)]))
    v = srgb_encode_array(c).astype(np.float64)
    ref = colour.cctf_encoding(c, function="sRGB")
    # power segment: P = 1.055 c^(1/2.4) with 1/2.4 rounded to float32 (relative u, moving P by u |ln c| / 2.4),
    # powf <= 1 ulp (2u), the product u; then - 0.055 (u |v|). Linear segment: one product (u).
    P = 1.055 * np.abs(c) ** (1 / 2.4)
    bound = np.where(c <= 0.0031308, 2 * U * np.abs(ref), P * (3 * U + U * np.abs(np.log(np.maximum(c, 1e-30))) / 2.4)
                     + U * np.abs(ref))
    assert np.all(np.abs(v - ref) <= bound * (1 + 1e-9))
    assert srgb_encode_array(0.0) == 0.0 and srgb_encode_array(1.0) == pytest.approx(1.0, abs=1e-7)
    assert np.all(np.diff(srgb_encode_array(np.linspace(0, 1, 10001))) >= 0)  # monotonic across the joint


@pytest.mark.spec("vc-A29")
def test_srgb_encode_c_and_warp_agree_and_reject_nan(rng):
    c = rng.uniform(-0.1, 1.5, 3000)
    # the same float32 expression and the same libm powf on the CPU: measured bit-identical; 2 ulp allows one
    # differently rounded powf elsewhere
    w, cc = srgb_encode_array(c), srgb_encode_array(c, impl="c")
    assert w.shape == cc.shape and w.dtype == cc.dtype == np.float32
    assert np.max(np.abs(w.view(np.int32).astype(np.int64) - cc.view(np.int32).astype(np.int64))) <= 2
    with pytest.raises(ValueError, match=r"^c must be finite"):
        srgb_encode_array([0.5, np.nan])


# --- C vs Warp ----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.32", "vc-4.3", "vc-4.4", "vc-4.5")
def test_colour_c_and_warp_agree_on_random_inputs(rng):
    """C (gcc -std=c99: no FMA contraction) vs Warp (LLVM) on 3000 random inputs: at most 2 ulp apart. Both evaluate
    the same float32 expression tree; on the CPU Warp's exp/pow call the same libm as the C library, so the measured
    difference is 0 ulp -- 2 ulp allows one differently rounded libm call on another platform."""
    n = 3000
    X, Y, Z = rng.uniform(0.0, 100.0, (3, n))
    x, y, YY = rng.uniform(0.0, 0.6, n), rng.uniform(0.05, 0.6, n), rng.uniform(0.0, 50.0, n)
    c, k = rng.uniform(-5.0, 200.0, n), rng.uniform(0.001, 0.2, n)
    cases = [("vc-2.32", (v3(X, Y, Z),), {}), ("vc-4.3", (v3(x, y, YY),), {}),
             ("vc-4.4", (v3(X - 50, Y, Z),), {"variant": "corrected"}),
             ("vc-4.4", (v3(X, Y - 50, Z),), {"variant": "thesis"}),
             ("vc-4.5", (c, k), {"variant": "corrected"}), ("vc-4.5", (c, k), {"variant": "thesis"})]
    for cid, args, kw in cases:
        w, _ = assert_twins_agree(cid, *args, ulp=2, **kw)
        assert w[0].shape[0] == n, (cid, kw)
