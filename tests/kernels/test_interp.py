"""Interpolants and remap (``cclouds/interp.h``): the fades vc-2.19/2.20 against their polynomials and end
derivatives, the linear and cosine curves of vc-fig-2.6, remap vc-2.27 (endpoints, reversed ranges, no clamping, a
float64 reference), C vs Warp agreement and bad input."""
from __future__ import annotations

import numpy as np
import pytest
from helpers import assert_twins_agree

import pywarp
from pywarp.core import binding as _cclouds
from pywarp.clouds import noise as host_noise

EPS32 = float(np.finfo(np.float32).eps)  # 2^-23


def f32(a):
    """Round to float32 and back (the inputs our float32 functions actually see)."""
    return np.asarray(a, dtype=np.float32).astype(np.float64)


# The quintic fade t^3 (t (6t - 15) + 10) in float32: the roundings of 6t, 6t - 15, t(...), + 10 are at most 2^-22,
# 2^-21, 2^-21, 2^-21 (magnitudes <= 6, 15, 15, 10), scaled by t^3 <= 1, plus the t^3 and final products
# (<= 10 * 2^-24): |error| <= 2.3e-6. The cubic t t (3 - 2t): <= 4 roundings at magnitude <= 3: 8 eps.
QUINTIC_ABS_TOL = 2.3e-6
CUBIC_ABS_TOL = 8 * EPS32


@pytest.mark.spec("vc-2.19", "vc-2.20")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_interp_fades_closed_forms_and_end_derivatives(impl):
    cubic, quintic = pywarp.equation("vc-2.19", impl=impl), pywarp.equation("vc-2.20", impl=impl)
    t = np.linspace(0.0, 1.0, 1025)
    td = f32(t)
    np.testing.assert_allclose(cubic(t), 3 * td ** 2 - 2 * td ** 3, rtol=0, atol=CUBIC_ABS_TOL)
    np.testing.assert_allclose(quintic(t), 6 * td ** 5 - 15 * td ** 4 + 10 * td ** 3, rtol=0, atol=QUINTIC_ABS_TOL)
    for f in (cubic, quintic):  # cataloguer's test values
        assert f(0.0) == 0.0 and f(0.5) == 0.5 and f(1.0) == 1.0
        assert np.all(np.diff(f(t).astype(np.float64)) >= 0)  # monotone
    # f'(0) = f'(1) = 0 for both; f''(0) = 6 (cubic) but 0 (quintic): f(d) = 3 d^2 - 2 d^3 vs 10 d^3 - 15 d^4 + 6 d^5
    # near 0, where the Horner forms t t (3 - 2t) and t^3 (t (6t - 15) + 10) keep a relative error of <= 3 (cubic)
    # and <= 7 (quintic) roundings, u = eps/2 each; near 1, f(1 - e) = 1 - f(e) (symmetry), so 1 - f(1 - e) is the
    # same small value up to the absolute bounds above (8 eps, 2.3e-6)
    d = float(np.float32(1e-3))
    assert cubic(d) == pytest.approx(3 * d ** 2 - 2 * d ** 3, rel=2 * EPS32)
    assert quintic(d) == pytest.approx(10 * d ** 3 - 15 * d ** 4 + 6 * d ** 5, rel=4 * EPS32)
    e = 1.0 - float(np.float32(1 - d))  # the distance to 1 of the float32 argument, exactly
    assert 1 - float(cubic(1 - d)) == pytest.approx(3 * e ** 2 - 2 * e ** 3, abs=CUBIC_ABS_TOL)
    e = 2.0 ** -5
    assert 1 - float(quintic(1 - np.float32(e))) == pytest.approx(10 * e ** 3 - 15 * e ** 4 + 6 * e ** 5,
                                                                  abs=QUINTIC_ABS_TOL)


@pytest.mark.spec("vc-A1", "vc-2.19", "vc-2.20")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_interp_interpolants_of_fig_2_6(impl):
    t = np.linspace(0, 1, 65)
    curves = host_noise.interpolants(t, impl=impl)
    td = f32(t)
    np.testing.assert_array_equal(curves["linear"], t.astype(np.float32))
    np.testing.assert_allclose(curves["cosine"], (1 - np.cos(np.pi * td)) / 2, atol=4 * EPS32)
    np.testing.assert_allclose(curves["cubic"], 3 * td ** 2 - 2 * td ** 3, atol=CUBIC_ABS_TOL)
    np.testing.assert_allclose(curves["quintic"], 6 * td ** 5 - 15 * td ** 4 + 10 * td ** 3, atol=QUINTIC_ABS_TOL)
    # cosine interpolation has zero slope at the ends like the fades; linear does not
    assert curves["cosine"][1] < 0.1 * t[1] and curves["linear"][1] == np.float32(t[1])


def test_interp_lerp_and_cosine_c_functions():
    """ccl_interp_lerp / ccl_interp_cosine (helpers without a catalogue ID): endpoints, a closed form, extrapolation."""
    lib = _cclouds.lib()
    assert lib.ccl_interp_lerp(0.25, 2.0, 6.0) == 3.0
    assert lib.ccl_interp_lerp(0.0, 2.0, 6.0) == 2.0 and lib.ccl_interp_lerp(1.0, 2.0, 6.0) == 6.0
    assert lib.ccl_interp_lerp(1.5, 0.0, 2.0) == 3.0  # extrapolates
    assert lib.ccl_interp_cosine(0.0, 2.0, 6.0) == 2.0
    assert lib.ccl_interp_cosine(1.0 / 3.0, 0.0, 4.0) == pytest.approx(1.0, abs=4 * 4 * EPS32)  # (1 - cos(pi/3))/2
    assert lib.ccl_interp_cosine(0.5, 0.0, 1.0) == pytest.approx(0.5, abs=2 * EPS32)


@pytest.mark.spec("vc-2.27")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_interp_remap_endpoints_reversed_and_unclamped(impl, rng):
    remap = pywarp.equation("vc-2.27", impl=impl)
    assert remap(0.2, 0.2, 0.9, -1.0, 3.0) == -1.0
    assert remap(0.9, 0.2, 0.9, -1.0, 3.0) == pytest.approx(3.0, abs=4 * EPS32)
    assert remap(0.25, 0.0, 1.0, 1.0, 0.0) == 0.75  # reversed new range (as in 4.7)
    assert remap(2.0, 0.0, 1.0, 0.0, 10.0) == 20.0  # no clamping: linear extrapolation
    assert remap(-1.0, 0.0, 1.0, 0.0, 10.0) == -10.0
    assert remap(0.5, 1.0, 0.0, 0.0, 1.0) == 0.5  # reversed original range
    v, a, b, c, d = rng.uniform(-5, 5, (5, 2000)).astype(np.float32)
    b = np.where(np.abs(b - a) < 0.5, a + 1, b).astype(np.float32)
    ref = f32(c) + (f32(v) - f32(a)) / (f32(b) - f32(a)) * (f32(d) - f32(c))
    # four roundings, the quotient amplified by |v - a| / |b - a| <= 20: bound 4 eps (|ref| + 20 |d - c|)
    assert np.all(np.abs(remap(v, a, b, c, d) - ref) <= 4 * EPS32 * (np.abs(ref) + 20 * np.abs(d - c)))


@pytest.mark.spec("vc-2.27", "vc-2.19", "vc-2.20")
def test_interp_c_and_warp_agree(rng):
    """Identical float32 expressions without contraction: within the entries' 2 ulp (observed 0)."""
    t = rng.uniform(0, 1, 2000).astype(np.float32)
    assert_twins_agree("vc-2.19", t)
    assert_twins_agree("vc-2.20", t)
    assert_twins_agree("vc-2.27", t, 0.0, 1.0, 5.0, 2.0)
    # the two helper curves (no registry entry): the Warp kernel of interpolants() vs the C functions
    w, c = host_noise.interpolants(t), host_noise.interpolants(t, impl="c")
    np.testing.assert_array_equal(w["linear"], c["linear"])
    # cosf of glibc vs Warp's cos, each within 1 ulp of (1 - cos pi t) / 2's argument: 2 ulp of 1
    assert np.abs(w["cosine"].astype(np.float64) - c["cosine"]).max() <= 2 * EPS32


@pytest.mark.spec("vc-2.19", "vc-2.27")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_interp_bad_input_raises_value_error_naming_parameter(impl):
    with pytest.raises(ValueError, match=r"^t must be in \[0, 1\]"):
        pywarp.equation("vc-2.19", impl=impl)(1.5)
    with pytest.raises(ValueError, match=r"^t must be in \[0, 1\]"):
        host_noise.interpolants([0.5, -0.1], impl=impl)
    with pytest.raises(ValueError, match=r"^o_max must differ from o_min"):
        pywarp.equation("vc-2.27", impl=impl)(0.5, [0.0, 1.0], [1.0, 1.0], 0.0, 1.0)
    with pytest.raises(ValueError, match=r"^v must be finite"):
        pywarp.equation("vc-2.27", impl=impl)(np.nan, 0.0, 1.0, 0.0, 1.0)
    with pytest.raises(ValueError, match=r"^impl must be"):
        host_noise.interpolants(0.5, impl="numpy")


def test_interp_names_and_package_helpers():
    assert pywarp.interp_remap(0.5, 0.0, 1.0, 2.0, 4.0) == 3.0
    assert pywarp.interpolants is host_noise.interpolants
