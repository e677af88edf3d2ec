"""Sky models: turbidity (vc-2.33), CIE clear sky (vc-2.35), Perez (vc-2.36), CIE modified Perez and its erratum
(vc-2.37), normalisation (vc-2.38, vc-4.2), Preetham's fits with their check values and the 6.0453 erratum
(vc-2.39-2.44), the Preetham sky pipeline (vc-A29) and the gradient sky (vc-A28).

Independent references: the float64 formulas written out below with Preetham et al. 1999's coefficient tables
(appendix A.2), the cataloguer's check values of spec/vc.md, and colour-science for the colour conversions of the
chain. Float32 error bounds use u = 2^-24; libm's expf/cosf/tanf/acosf/powf are within 1 ulp (2u).
"""
from __future__ import annotations

import math

import colour
import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree, max_ulp_diff
from pywarp.core.binding import ffi, lib
from pywarp.clouds import sky as host_sky
from pywarp.kernels import sky as sky_mod

U = 2.0 ** -24
HALF_PI_F32 = float(np.float32(np.pi / 2))


def split(v):
    """The components of (..., 3) vectors as a tuple of arrays: (x, y, Y) or (R, G, B)."""
    return tuple(np.moveaxis(np.asarray(v), -1, 0))


def components(f):
    """A vector-valued entry (vc-A28, vc-A29) as a function returning the tuple of its components."""
    return lambda *args, **kw: split(f(*args, **kw))


def zenith_Yxy(f):
    """vc-2.39 (returns the xyY vector (x_z, y_z, Y_Z)) as a function returning (Y_Z, x_z, y_z)."""
    def call(*args, **kw):
        x, y, Y = split(f(*args, **kw))
        return Y, x, y
    return call


sky_preetham = components(pywarp.sky_preetham_colour)
sky_gradient = components(pywarp.sky_gradient_colour)
preetham_zenith = zenith_Yxy(pywarp.sky_preetham_zenith)

# --- float64 references: Preetham, Shirley & Smits 1999, appendix A.2 ------------------------------------------------
PEREZ_TABLE = {  # rows A..E: (coefficient of T, constant)
    "Y": np.array([[0.1787, -1.4630], [-0.3554, 0.4275], [-0.0227, 5.3251], [0.1206, -2.5771], [-0.0670, 0.3703]]),
    "x": np.array([[-0.0193, -0.2592], [-0.0665, 0.0008], [-0.0004, 0.2125], [-0.0641, -0.8989], [-0.0033, 0.0452]]),
    "y": np.array([[-0.0167, -0.2608], [-0.0950, 0.0092], [-0.0079, 0.2102], [-0.0441, -1.6537], [-0.0109, 0.0529]]),
}
ZENITH_X = np.array([[0.00166, -0.00375, 0.00209, 0.0], [-0.02903, 0.06377, -0.03202, 0.00394],
                     [0.11693, -0.21196, 0.06052, 0.25886]])
ZENITH_Y = np.array([[0.00275, -0.00610, 0.00317, 0.0], [-0.04214, 0.08970, -0.04153, 0.00516],
                     [0.15346, -0.26756, 0.06670, 0.26688]])
D65_LINDBLOOM = np.array([0.95047, 1.0, 1.08883])


def f32(a):
    return np.asarray(a, dtype=np.float32).astype(np.float64)


def coeffs64(T, ch):
    T = np.asarray(T, np.float64)
    return tuple(a * T + b for a, b in PEREZ_TABLE[ch])


def perez64_cg(ct, gamma, cg, A, B, C, D, E):
    ct = np.maximum(ct, 0.01)
    return (1 + A * np.exp(B / ct)) * (1 + C * np.exp(D * gamma) + E * cg * cg)


def perez64(theta, gamma, *c):
    return perez64_cg(np.cos(theta), gamma, np.cos(gamma), *c)


def zenith64(T, ts, k=4.0453):
    chi = (4 / 9 - T / 120) * (np.pi - 2 * ts)
    Yz = (k * T - 4.9710) * np.tan(chi) - 0.2155 * T + 2.4192
    tv = np.stack([np.asarray(T, float) ** 2, np.asarray(T, float), np.ones_like(np.asarray(T, float))], -1)
    thv = np.stack([ts ** 3, ts ** 2, ts, np.ones_like(ts)], -1)
    xz = np.einsum("...i,ij,...j->...", tv, ZENITH_X, thv)
    yz = np.einsum("...i,ij,...j->...", tv, ZENITH_Y, thv)
    return Yz, xz, yz


def perez_rel_bound(ct, gamma, cg, A, B, C, D, E, dgamma=0.0, dcg=0.0, cos_rounded=False):
    """First-order relative error bound of the float32 Perez evaluation (2.36) at float32-exact inputs.

    First factor 1 + A e^(B/ct): B/ct is rounded (u, plus 2u if ct came from cosf), e^ is within 2u, the product u,
    the sum u -- all relative to e1 = A e^(B/ct) except the last, divided by |1 + e1| (cancellation for A < 0).
    Second factor 1 + C e^(D g) + E cg^2: D g rounded (u |D g|), exp 2u, product u; cg^2 and E cg^2 3u (5u if cg
    came from cosf); two sums. dgamma / dcg: absolute errors of gamma and cos(gamma) handed in by the caller.
    """
    ctc = np.maximum(ct, 0.01)
    arg = np.abs(B / ctc) * (3 * U if cos_rounded else U)
    e1 = A * np.exp(B / ctc)
    f1 = 1 + e1
    rel1 = (np.abs(e1) * (arg + 3 * U) + U * np.abs(f1)) / np.abs(f1)
    e2 = C * np.exp(D * gamma)
    e3 = E * cg * cg
    f2 = 1 + e2 + e3
    abs2 = (np.abs(e2) * (U * np.abs(D * gamma) + 3 * U + np.abs(D) * dgamma)
            + np.abs(e3) * (5 * U if cos_rounded else 3 * U) + np.abs(2 * E * cg) * dcg + 2 * U * np.abs(f2))
    return rel1 + abs2 / np.abs(f2) + U


def sun64(elev_deg, az_deg):
    e, a = np.radians(elev_deg), np.radians(az_deg)
    return np.array([np.cos(e) * np.sin(a), np.sin(e), -np.cos(e) * np.cos(a)])


def lindbloom_matrix_from_colour():
    sp = colour.models.RGB_COLOURSPACE_sRGB
    return np.linalg.inv(colour.normalised_primary_matrix(sp.primaries, colour.XYZ_to_xy(D65_LINDBLOOM)))


def unit_dirs(rng, n):
    d = rng.normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


# --- vc-2.33 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.33")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_turbidity_closed_form_and_bad_input(impl, rng):
    f = pywarp.equation("vc-2.33", impl=impl)
    assert f(1.0, 0.0) == 1.0  # pure air
    assert f(0.2, 0.3) == 2.5
    tm, th = f32(rng.uniform(0.01, 1, 1000)), f32(rng.uniform(0, 5, 1000))
    np.testing.assert_allclose(f(tm, th), (tm + th) / tm, rtol=2.001 * U)  # a sum of positives and a division
    assert np.all(f(tm, th) >= 1)
    with pytest.raises(ValueError, match=r"^t_m must be in \(0, inf\), got 0\.0"):
        f(0.0, 1.0)
    with pytest.raises(ValueError, match=r"^t_h must be in \[0, inf\)"):
        f(1.0, -0.5)


# --- vc-2.35 / 2.36 / 2.37 / 2.38 / 4.2 ------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.35")
def test_cie_clear_sky_matches_float64(rng):
    n = 3000
    th, g, ts = f32(rng.uniform(0, np.pi / 2, n)), f32(rng.uniform(0, np.pi, n)), f32(rng.uniform(0, np.pi / 2, n))
    Yz = f32(rng.uniform(0.5, 30, n))
    out = pywarp.sky_cie_clear(th, g, ts, Yz)

    def f(x):
        return 0.91 + 10 * np.exp(-3 * x) + 0.45 * np.cos(x) ** 2

    ref = Yz * f(g) * (1 - np.exp(-0.32 / np.maximum(np.cos(th), 0.01))) / (f(ts) * (1 - np.exp(-0.32)))
    # f(x): sums of positive terms; each of 0.91f, 0.45f, 0.32f rounded (u), exp/cos 2u, ~8 roundings: <= 14u.
    # 1 - e^(-s): exp 2u plus the argument's 3u s, relative to 1 - e^(-s) >= 0.274 (s >= 0.32): <= 5u (3s e^-s +
    # 2e^-s + 1) / (1 - e^-s) <= 26u. Two f, two gradations, three roundings: 2*14 + 2*26 + 3 = 83u.
    np.testing.assert_allclose(out, ref, rtol=83 * U, atol=0)
    np.testing.assert_array_equal(pywarp.sky_cie_clear(0.0, ts, ts, Yz), Yz.astype(np.float32))  # zenith exact


@pytest.mark.spec("vc-2.35", "vc-2.36", "vc-2.38")
def test_cie_clear_sky_is_perez_with_A_minus_1_and_the_091_factor(rng):
    """The spec's derivation: 2.35 == Y_z F(theta, gamma)/F(0, theta_s) with A = -1, B = -0.32, C = 10/0.91, D = -3,
    E = 0.45/0.91; the text's C = 10, E = 0.45 differ by the 0.91 factor."""
    n = 2000
    th, g, ts = f32(rng.uniform(0, 1.5, n)), f32(rng.uniform(0, np.pi, n)), f32(rng.uniform(0, np.pi / 2, n))
    cie = pywarp.sky_cie_clear(th, g, ts, 1.0).astype(np.float64)
    exact = pywarp.sky_perez_normalized(th, g, ts, 1.0, -1.0, -0.32, 10 / 0.91, -3.0, 0.45 / 0.91).astype(np.float64)
    # both are float32 evaluations of the same function, each within 83u (previous test) of it
    np.testing.assert_allclose(exact, cie, rtol=2 * 83 * U)
    printed = pywarp.sky_perez_normalized(th, g, ts, 1.0, -1.0, -0.32, 10.0, -3.0, 0.45).astype(np.float64)

    def ratio(x):  # (1 + 10 e^-3x + .45 cos^2 x) / (0.91 + 10 e^-3x + .45 cos^2 x)
        e, c2 = 10 * np.exp(-3 * x), 0.45 * np.cos(x) ** 2
        return (1 + e + c2) / (0.91 + e + c2)

    np.testing.assert_allclose(printed / cie, ratio(g) / ratio(ts), rtol=4 * 83 * U)
    assert np.max(np.abs(printed / cie - 1)) > 0.05  # the printed C, E are measurably off (up to ~9 %)


@pytest.mark.spec("vc-2.36")
def test_perez_matches_float64_with_preetham_coefficients(rng):
    n = 4000
    T = f32(rng.uniform(2, 10, n))
    th, g = f32(rng.uniform(0, np.pi, n)), f32(rng.uniform(0, np.pi, n))
    for ch in "Yxy":
        c = tuple(f32(v) for v in pywarp.equation({"Y": "vc-2.42", "x": "vc-2.43", "y": "vc-2.44"}[ch])(T))
        out = pywarp.sky_perez(th, g, *c).astype(np.float64)
        ref = perez64(th, g, *c)
        bound = perez_rel_bound(np.cos(th), g, np.cos(g), *c, cos_rounded=True)
        assert np.all(np.abs(out - ref) <= bound * np.abs(ref) * (1 + 1e-6)), ch
        assert np.all(ref > 0)  # the Preetham distributions are positive on the whole sphere for 2 <= T <= 10


@pytest.mark.spec("vc-2.36")
def test_perez_horizon_clamp_and_closed_forms():
    A, B, C, D, E = -1.0, -0.32, 10.0, -3.0, 0.45
    theta = np.array([np.arccos(0.01), np.pi / 2, 2.0, np.pi], dtype=np.float32)
    v = pywarp.sky_perez(theta, 0.7, A, B, C, D, E)
    # at and below the horizon cos(theta) = 0.01 (Radiance perezlum.cal): finite, one value for a given gamma
    assert np.all(np.isfinite(v)) and np.all(v[1:] == v[1])
    assert v[1] == pytest.approx(perez64_cg(0.01, 0.7, np.cos(0.7), A, B, C, D, E), rel=64 * U)
    assert v[0] == pytest.approx(v[1], rel=1e-5)  # continuous at the clamp
    # A = 0: no gradation; C = E = 0: no circumsolar term
    assert pywarp.sky_perez(0.4, 1.0, 0.0, B, C, D, E) == pytest.approx(1 + C * np.exp(D) + E * np.cos(1.0) ** 2, rel=1e-6)
    assert pywarp.sky_perez(0.4, 1.0, A, B, 0.0, D, 0.0) == pytest.approx(1 + A * np.exp(B / np.cos(0.4)), rel=1e-6)


@pytest.mark.spec("vc-2.37")
def test_perez_cie_variants_pinned():
    """Erratum vc-2.37: the CIE indicatrix subtracts the constant exp(D pi/2) (exactly 1 at gamma = pi/2); the
    printed exp(D gamma pi/2) does not."""
    A, B, C, D, E = 0.0, -0.32, 10.0, -3.0, 0.45
    assert pywarp.sky_perez_cie(0.3, HALF_PI_F32, A, B, C, D, E) == pytest.approx(1.0, abs=1e-6)
    t = pywarp.sky_perez_cie(0.3, HALF_PI_F32, A, B, C, D, E, variant="thesis")
    assert t == pytest.approx(1 + 10 * (np.exp(-1.5 * np.pi) - np.exp(-0.75 * np.pi ** 2)), rel=1e-6)  # 1.0893
    # at gamma = 0 the two coincide only if exp(0) is subtracted: corrected 1 + 10 (1 - e^(-3 pi/2)) + 0.45
    assert pywarp.sky_perez_cie(0.0, 0.0, A, B, C, D, E) == pytest.approx(11.45 - 10 * np.exp(-1.5 * np.pi), rel=1e-6)
    assert pywarp.sky_perez_cie(0.0, 0.0, A, B, C, D, E, variant="thesis") == pytest.approx(1.45, rel=1e-6)


@pytest.mark.spec("vc-2.37", "vc-2.35")
def test_perez_cie_explains_the_091_of_the_cie_clear_sky(rng):
    """1 - 10 exp(-3 pi/2) = 0.91017: with the CIE clear-sky parameters the corrected 2.37 reproduces the (unnormalised)
    2.35 to within 0.00017 / 0.91 = 1.9e-4 -- the printed variant does not."""
    assert 1 - 10 * np.exp(-1.5 * np.pi) == pytest.approx(0.91017, abs=1e-5)
    th, g = f32(rng.uniform(0, 1.5, 2000)), f32(rng.uniform(0, np.pi, 2000))
    cie = (0.91 + 10 * np.exp(-3 * g) + 0.45 * np.cos(g) ** 2) * (1 - np.exp(-0.32 / np.cos(th)))
    corr = pywarp.sky_perez_cie(th, g, -1.0, -0.32, 10.0, -3.0, 0.45)
    thesis = pywarp.sky_perez_cie(th, g, -1.0, -0.32, 10.0, -3.0, 0.45, variant="thesis")
    assert np.max(np.abs(corr / cie - 1)) < 1.9e-4
    assert np.max(np.abs(thesis / cie - 1)) > 0.05


@pytest.mark.spec("vc-2.37")
def test_perez_cie_matches_float64_both_variants(rng):
    n = 3000
    th, g = f32(rng.uniform(0, np.pi, n)), f32(rng.uniform(0, np.pi, n))
    A, B, C, D, E = (f32(rng.uniform(lo, hi, n)) for lo, hi in ((-1.5, 1), (-1, -0.1), (0, 12), (-3, -0.5),
                                                                (-0.1, 0.5)))
    ct, cg = np.maximum(np.cos(th), 0.01), np.cos(g)
    for variant, sub in (("corrected", np.exp(D * np.pi / 2)), ("thesis", np.exp(D * g * np.pi / 2))):
        out = pywarp.sky_perez_cie(th, g, A, B, C, D, E, variant=variant).astype(np.float64)
        f1 = 1 + A * np.exp(B / ct)
        e2 = np.exp(D * g)
        f2 = 1 + C * (e2 - sub) + E * cg * cg
        ref = f1 * f2
        # as perez_rel_bound, with the subtracted exponential's own error (its argument holds up to 2 roundings and
        # pi/2 rounded to float32: 4u |arg|, exp 2u) entering the second factor in absolute terms
        b1 = perez_rel_bound(ct, g, cg, A, B, 0.0, D, 0.0, cos_rounded=True)
        abs2 = (np.abs(C) * (e2 * (np.abs(D * g) * U + 2 * U) + sub * (4 * U * np.abs(np.log(sub)) + 2 * U)
                             + 2 * U * np.abs(e2 - sub))
                + 5 * U * np.abs(E * cg * cg) + 2 * U * np.abs(f2))
        bound = (b1 + abs2 / np.abs(f2)) * np.abs(ref)
        assert np.all(np.abs(out - ref) <= bound * (1 + 1e-6)), variant


@pytest.mark.spec("vc-2.38", "vc-4.2")
def test_perez_normalized_exact_at_zenith_and_factor(rng):
    n = 2000
    T, ts, Yz = f32(rng.uniform(2, 10, n)), f32(rng.uniform(0, HALF_PI_F32, n)), f32(rng.uniform(0.1, 40, n))
    for cid in ("vc-2.42", "vc-2.43", "vc-2.44"):
        c = pywarp.equation(cid)(T)
        # Y(zenith) = Y_Z exactly: F(0, theta_s) / F(0, theta_s) == 1 in float32
        np.testing.assert_array_equal(pywarp.sky_perez_normalized(0.0, ts, ts, Yz, *c), Yz.astype(np.float32))
        # 4.2: factor = Y_z / F(0, theta_s) -- float64 reference with the perez bound for F(0, theta_s) plus 1 division
        fac = pywarp.sky_perez_zenith_factor(ts, Yz, *c).astype(np.float64)
        c64 = tuple(f32(v) for v in c)
        ref = Yz / perez64(0.0, ts, *c64)
        bound = perez_rel_bound(1.0, ts, np.cos(ts), *c64, cos_rounded=True) + U
        assert np.all(np.abs(fac - ref) <= bound * ref * (1 + 1e-6)), cid


@pytest.mark.spec("vc-2.38")
def test_perez_normalized_matches_float64(rng):
    n = 2000
    T = f32(rng.uniform(2, 10, n))
    th, g, ts = f32(rng.uniform(0, np.pi, n)), f32(rng.uniform(0, np.pi, n)), f32(rng.uniform(0, HALF_PI_F32, n))
    c = tuple(f32(v) for v in pywarp.sky_preetham_perez_Y(T))
    out = pywarp.sky_perez_normalized(th, g, ts, 5.0, *c).astype(np.float64)
    ref = perez64(th, g, *c) / perez64(0.0, ts, *c) * 5.0
    bound = (perez_rel_bound(np.cos(th), g, np.cos(g), *c, cos_rounded=True)
             + perez_rel_bound(1.0, ts, np.cos(ts), *c, cos_rounded=True) + 2 * U)
    assert np.all(np.abs(out - ref) <= bound * ref * (1 + 1e-6))


@pytest.mark.spec("vc-2.35", "vc-2.36", "vc-2.37", "vc-2.38", "vc-4.2")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_perez_family_bad_input(impl):
    perez = pywarp.equation("vc-2.36", impl=impl)
    with pytest.raises(ValueError, match=r"^theta must be in \[0, 3\.14159\]"):
        perez(-0.1, 0.5, -1, -0.3, 5, -2, 0.3)
    with pytest.raises(ValueError, match=r"^gamma must be in \[0, 3\.14159\]"):
        perez(0.1, 3.5, -1, -0.3, 5, -2, 0.3)
    with pytest.raises(ValueError, match=r"^B must be finite"):
        perez(0.1, 0.5, -1, np.nan, 5, -2, 0.3)
    with pytest.raises(ValueError, match=r"^theta_s must be in \[0, 1\.5708\], got 1\.6"):
        pywarp.equation("vc-2.38", impl=impl)(0.1, 0.5, 1.6, 1.0, -1, -0.3, 5, -2, 0.3)
    with pytest.raises(ValueError, match=r"^theta_s must be in"):
        pywarp.equation("vc-4.2", impl=impl)(-0.2, 1.0, -1, -0.3, 5, -2, 0.3)
    with pytest.raises(ValueError, match=r"^theta_s must be in"):
        pywarp.equation("vc-2.35", impl=impl)(0.1, 0.5, 2.0, 1.0)
    with pytest.raises(ValueError, match=r"^variant must be one of"):
        pywarp.equation("vc-2.37", impl=impl)(0.1, 0.5, -1, -0.3, 5, -2, 0.3, variant="cie")


# --- vc-2.39 .. 2.44 -------------------------------------------------------------------------------------------------

SPEC_CHECK = [  # spec/vc.md vc-2.39..2.41: (T, theta_s deg, Y_Z 4.0453, Y_Z 6.0453, x_z, y_z)
    (2.0, 0.0, 15.5007, 32.8266, 0.26674, 0.27720),
    (2.0, 30.0, 5.8867, 10.8855, 0.25142, 0.25592),
    (3.0, 60.0, 5.1392, 7.9583, 0.24493, 0.25257),
]


@pytest.mark.spec("vc-2.39", "vc-2.40", "vc-2.41")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_preetham_zenith_spec_check_values_both_variants(impl):
    zen = zenith_Yxy(pywarp.equation("vc-2.39", impl=impl))
    for T, deg, Yc, Yt, xz, yz in SPEC_CHECK:
        ts = math.radians(deg)
        Y, x, y = zen(T, ts)
        Y_t, x_t, y_t = zen(T, ts, variant="thesis")
        # printed to 4 (Y) and 5 (x, y) decimals: half a unit of the last digit plus a few float32 ulp
        assert Y == pytest.approx(Yc, abs=5e-5 + 8 * U * Yc)
        assert Y_t == pytest.approx(Yt, abs=5e-5 + 8 * U * Yt)
        assert x == pytest.approx(xz, abs=5e-6 + 8 * U) and y == pytest.approx(yz, abs=5e-6 + 8 * U)
        assert (x_t, y_t) == (x, y)  # the erratum touches Y only
        assert pywarp.equation("vc-2.40", impl=impl)(T, ts) == x
        assert pywarp.equation("vc-2.41", impl=impl)(T, ts) == y


@pytest.mark.spec("vc-2.39")
def test_preetham_zenith_luminance_matches_float64_both_variants(rng):
    n = 3000
    T, ts = f32(rng.uniform(2, 10, n)), f32(rng.uniform(0, HALF_PI_F32, n))
    bounds = {}
    for variant, k in (("corrected", 4.0453), ("thesis", 6.0453)):
        Y = preetham_zenith(T, ts, variant=variant)[0].astype(np.float64)
        ref = zenith64(T, ts, k)[0]
        chi = (4 / 9 - T / 120) * (np.pi - 2 * ts)
        a, tn = k * T - 4.9710, np.tan(chi)
        # chi: 4/9, T/120, the difference, pi_f - 2 ts (abs u pi + pi_f's own 0.5u pi) and the product: 4u |chi| +
        # 1.5u pi (4/9 - T/120) absolute; tan amplifies by 1 + tan^2, tanf adds 2u. Then a = kT - 4.971 (k rounded:
        # 3u), the product, and the final sums (cancelling at T = 10, theta_s = pi/2 where Y_Z = 0.264).
        dchi = 4 * U * np.abs(chi) + 1.5 * U * np.pi * (4 / 9 - T / 120)
        dtan = (1 + tn ** 2) * dchi + 2 * U * np.abs(tn)
        dY = np.abs(a) * dtan + 4 * U * np.abs(a * tn) + 3 * U * (np.abs(a * tn) + 0.2155 * T + 2.4192)
        assert np.all(np.abs(Y - ref) <= dY * (1 + 1e-6)), variant
        bounds[variant] = dY
    # the printed 6.0453 adds exactly 2 T tan(chi): each variant within its bound above of the float64 value
    Yc, Yt = (preetham_zenith(T, ts, variant=v)[0].astype(np.float64) for v in ("corrected", "thesis"))
    chi = (4 / 9 - T / 120) * (np.pi - 2 * ts)
    assert np.all(np.abs((Yt - Yc) - 2 * T * np.tan(chi)) <= (bounds["corrected"] + bounds["thesis"]) * (1 + 1e-6))
    assert np.all(Yc > 0)  # positive for the sun above the horizon over the valid turbidity range


@pytest.mark.spec("vc-2.40", "vc-2.41")
def test_preetham_zenith_chromaticity_matches_float64(rng):
    n = 3000
    T, ts = f32(rng.uniform(2, 10, n)), f32(rng.uniform(0, HALF_PI_F32, n))
    _, xr, yr = zenith64(T, ts)
    tv = np.stack([T ** 2, T, np.ones_like(T)], -1)
    thv = np.stack([ts ** 3, ts ** 2, ts, np.ones_like(ts)], -1)
    for name, M, ref in (("vc-2.40", ZENITH_X, xr), ("vc-2.41", ZENITH_Y, yr)):
        out = pywarp.equation(name)(T, ts).astype(np.float64)
        # every monomial T^i c_ij theta^j passes through <= 8 roundings (powers, coefficient, products, sums)
        mag = np.einsum("...i,ij,...j->...", tv, np.abs(M), thv)
        assert np.all(np.abs(out - ref) <= 8 * U * mag), name
        assert np.all((out > 0.2) & (out < 0.35))  # bluish-white chromaticities


@pytest.mark.spec("vc-2.42", "vc-2.43", "vc-2.44")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_preetham_perez_coefficients_match_table(impl, rng):
    T = f32(np.concatenate([[2.0, 10.0], rng.uniform(2, 10, 500)]))
    for cid, ch in (("vc-2.42", "Y"), ("vc-2.43", "x"), ("vc-2.44", "y")):
        out = pywarp.equation(cid, impl=impl)(T)
        for k, (a, b) in enumerate(PEREZ_TABLE[ch]):
            ref = a * T + b
            # a, b rounded to float32 (u each), a T and the sum rounded: u (2 |a T| + |b| + |ref|)
            assert np.all(np.abs(out[k] - ref) <= U * (2 * np.abs(a * T) + np.abs(b) + np.abs(ref))), (ch, k)
        # B < 0 over the valid range: exp(B / 0.01) < 2e-6, so the horizon clamp returns the horizon limit
        assert np.all(out[1] < 0) and np.all(np.exp(out[1].astype(np.float64) / 0.01) < 2e-6)
    Y = pywarp.equation("vc-2.42", impl=impl)(2.0)
    assert Y == pytest.approx((-1.1056, -0.2833, 5.2797, -2.3359, 0.2363), abs=1e-6)


@pytest.mark.spec("vc-2.39", "vc-2.40", "vc-2.41", "vc-2.42")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_preetham_fits_bad_input(impl):
    zen = zenith_Yxy(pywarp.equation("vc-2.39", impl=impl))
    with pytest.raises(ValueError, match=r"^turbidity must be in \[2, 10\], got 1\.5"):
        zen(1.5, 0.3)
    with pytest.raises(ValueError, match=r"^turbidity must be in \[2, 10\]"):
        zen([3.0, 12.0], 0.3)
    with pytest.raises(ValueError, match=r"^turbidity must be finite"):
        zen(np.nan, 0.3)
    with pytest.raises(ValueError, match=r"^theta_s must be in \[0, 1\.5708\], got 1\.7"):
        zen(3.0, 1.7)  # sun below the horizon
    with pytest.raises(ValueError, match=r"^theta_s must be finite"):
        pywarp.equation("vc-2.40", impl=impl)(3.0, np.inf)
    with pytest.raises(ValueError, match=r"^turbidity must be in"):
        pywarp.equation("vc-2.42", impl=impl)(0.5)
    # the horizon itself (theta_s = pi/2, also as float32) is valid
    assert np.isfinite(zen(3.0, np.pi / 2)[0]) and np.isfinite(zen(3.0, np.float32(np.pi / 2))[0])


# --- vc-A29: the Preetham sky pipeline -------------------------------------------------------------------------------

def sky_xyY64(d, sun, T, ts, k=4.0453):
    """Float64 Preetham sky in xyY at float32-exact direction and sun vectors."""
    cg = np.clip(d @ sun, -1, 1)
    g = np.arccos(cg)
    out = []
    for ch, z in zip("xyY", (zenith64(T, ts, k)[1], zenith64(T, ts, k)[2], zenith64(T, ts, k)[0])):
        c = coeffs64(np.float32(T), ch)
        c = tuple(f32(v) for v in c)
        out.append(z * perez64_cg(d[:, 1], g, cg, *c) / perez64(0.0, ts, *c))
    return np.stack(out, -1), g, cg


@pytest.mark.spec("vc-A29", "vc-2.38", "vc-4.2", "vc-2.39")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_sky_preetham_zenith_gives_zenith_values(impl):
    """Looking straight up returns (x_z, y_z, Y_z): 4.2 applied to all three channels. With the sun at the zenith the
    spec's check value Y_Z(T = 2, theta_s = 0) = 15.5007 / 32.8266 (thesis) appears in the sky itself."""
    sky = components(pywarp.equation("vc-A29", impl=impl))
    for T in (2.0, 5.0, 10.0):
        for elev in (0.0, 10.0, 35.0, 60.0):
            ts = np.float32(math.radians(90 - elev))
            x, y, Y = sky([0.0, 1.0, 0.0], T, elev, 17.0, output="xyY")
            Yz, xz, yz = preetham_zenith(T, ts)
            # gamma = acos(sun_y) instead of theta_s: |d gamma| <= 3u / sin(theta_s) <= 6u for theta_s >= 30 deg,
            # |d ln F / d gamma| <= 3; plus the factor's and F's roundings (~10u): 28u
            for a, b in ((x, xz), (y, yz), (Y, Yz)):
                assert a == pytest.approx(b, rel=28 * U), (T, elev)
    Y_c = sky([0.0, 1.0, 0.0], 2.0, 90.0, output="xyY")[2]
    Y_t = sky([0.0, 1.0, 0.0], 2.0, 90.0, output="xyY", variant="thesis")[2]
    assert Y_c == pytest.approx(15.5007, abs=1e-4) and Y_t == pytest.approx(32.8266, abs=1e-4)


@pytest.mark.spec("vc-A29", "vc-2.36", "vc-2.38", "vc-4.2")
def test_sky_preetham_xyY_matches_float64(rng):
    d = f32(unit_dirs(rng, 3000)).astype(np.float32)
    for T, elev, az in ((2.0, 5.0, 0.0), (4.5, 40.0, 130.0), (10.0, 75.0, -60.0)):
        x, y, Y = sky_preetham(d, T, elev, az, output="xyY")
        sun = sky_mod.sun_direction(elev, az).astype(np.float64)
        ts = float(np.float32(math.radians(90 - elev)))
        ref, g, cg = sky_xyY64(d.astype(np.float64), sun, T, ts)
        keep = g > math.radians(1.0)  # acos is ill-conditioned at the sun: |d gamma| ~ sqrt(u) there
        # |d cos gamma| <= 3u (float32 dot product of unit vectors), |d gamma| <= 3u / sin(gamma) + 2u gamma (acosf);
        # F(theta, gamma) and F(0, theta_s) by perez_rel_bound, the zenith value by the previous tests (<= 20u),
        # the factor division and the product: 2u
        dcg = 3 * U
        dg = dcg / np.sin(g) + 2 * U * g
        for k, (out, ch) in enumerate(zip((x, y, Y), "xyY")):
            c = tuple(f32(v) for v in coeffs64(np.float32(T), ch))
            bound = (perez_rel_bound(d[:, 1].astype(np.float64), g, cg, *c, dgamma=dg, dcg=dcg)
                     + perez_rel_bound(1.0, ts, np.cos(ts), *c, cos_rounded=True) + 22 * U)
            err = np.abs(out.astype(np.float64) - ref[:, k]) / ref[:, k]
            assert np.all(err[keep] <= bound[keep]), (T, elev, ch)
            assert np.all(err <= 0.02)  # even within 1 degree of the sun


@pytest.mark.spec("vc-A29", "vc-4.3", "vc-4.4", "vc-4.5")
@pytest.mark.parametrize("variant", ["corrected", "thesis"])
def test_sky_preetham_stages_compose_exactly(rng, variant):
    """hdr = 4.4(4.3(xyY)), tonemapped = 4.5(hdr), srgb = sRGB(tonemapped): the same float32 functions, bit for bit."""
    from pywarp.clouds.sky import srgb_encode_array

    d = unit_dirs(rng, 1000)
    args = (d, 3.3, 28.0, 75.0)
    x, y, Y = sky_preetham(*args, output="xyY", variant=variant)
    hdr = sky_preetham(*args, output="hdr", variant=variant)
    tm = sky_preetham(*args, variant=variant)
    srgb = sky_preetham(*args, output="srgb", variant=variant)
    ref_hdr = split(pywarp.colour_XYZ_to_linear_srgb(pywarp.colour_xyY_to_XYZ(np.stack([x, y, Y], -1)),
                                                     variant=variant))
    for a, b in zip(hdr, ref_hdr):
        np.testing.assert_array_equal(a, b)
    for a, b, c in zip(tm, hdr, srgb):
        np.testing.assert_array_equal(a, pywarp.colour_tonemap_exp(b, 0.03, variant=variant))
        np.testing.assert_array_equal(c, srgb_encode_array(a))


@pytest.mark.spec("vc-A29", "vc-4.3", "vc-4.4", "vc-4.5")
def test_sky_preetham_end_to_end_matches_colour_science(rng):
    """Float64 Preetham xyY -> colour.xyY_to_XYZ -> XYZ -> linear sRGB (colour's matrix) -> 1 - exp(-0.03 C) ->
    colour.cctf_encoding, against the srgb output, the error bound propagated stage by stage."""
    d = f32(unit_dirs(rng, 2000)).astype(np.float32)
    T, elev, az = 3.0, 35.0, 20.0
    out = np.stack(sky_preetham(d, T, elev, az, output="srgb"), -1).astype(np.float64)
    sun = sky_mod.sun_direction(elev, az).astype(np.float64)
    ts = float(np.float32(math.radians(90 - elev)))
    xyY, g, cg = sky_xyY64(d.astype(np.float64), sun, T, ts)
    keep = g > math.radians(1.0)
    XYZ = colour.xyY_to_XYZ(xyY)
    M = lindbloom_matrix_from_colour()
    hdr = XYZ @ M.T
    tm = 1 - np.exp(-0.03 * hdr)
    ref = colour.cctf_encoding(tm, function="sRGB")
    # relative error of x, y, Y: as the previous test, bounded here by its worst case over the kept samples
    dg = 3 * U / np.sin(g) + 2 * U * g
    eps = max(np.max((perez_rel_bound(d[:, 1].astype(np.float64), g, cg, *tuple(f32(v) for v in coeffs64(T, ch)),
                                      dgamma=dg, dcg=3 * U)
                      + perez_rel_bound(1.0, ts, np.cos(ts), *tuple(f32(v) for v in coeffs64(T, ch)),
                                        cos_rounded=True) + 22 * U)[keep]) for ch in "xyY")
    # X = x Y / y and Z = (1 - x - y) Y / y: 3 eps + 4u relative (Z's subtraction: |1 - x - y| >= 0.4 here, so
    # x, y's errors grow by at most (x + y) / z < 1.5); the matrix row: 5u on sum |m X| (test_colour)
    absM = np.abs(M)
    d_xyz = (4.5 * eps + 6 * U) * np.abs(XYZ)
    d_hdr = d_xyz @ absM.T + 5 * U * (np.abs(XYZ) @ absM.T) + 4.6e-8 * np.abs(XYZ).sum(-1, keepdims=True)
    d_tm = 0.03 * np.exp(-0.03 * hdr) * d_hdr + 4 * U  # 1 - e^-kC: slope k e^-kC, plus expf and the subtraction
    slope = np.where(tm <= 0.0031308, 12.92, 1.055 / 2.4 * np.maximum(tm, 0.0031308) ** (1 / 2.4 - 1))
    d_srgb = slope * d_tm + 4 * U
    assert np.all(np.abs(out - ref)[keep] <= d_srgb[keep])
    assert np.all((out > 0) & (out < 1))  # the corrected chain maps the valid sky into the display range


@pytest.mark.spec("vc-A29", "vc-2.39", "vc-4.4", "vc-4.5")
def test_sky_preetham_thesis_variant_pinned():
    """variant='thesis' applies all three printed errata: 6.0453 (Y scaled by Y_Z^thesis / Y_Z), the green-cast
    matrix and the tone map sign (<= 0 everywhere: a black frame after clamping)."""
    d = np.array([[0.0, 1.0, 0.0], [0.6, 0.3, -0.74], [0.2, -0.3, 0.9]])
    args = (d, 3.0, 30.0, 0.0)
    xc, yc, Yc = sky_preetham(*args, output="xyY")
    xt, yt, Yt = sky_preetham(*args, output="xyY", variant="thesis")
    np.testing.assert_array_equal(xt, xc)
    np.testing.assert_array_equal(yt, yc)
    ts = math.radians(60.0)
    ratio = zenith64(3.0, ts, 6.0453)[0] / zenith64(3.0, ts)[0]  # 7.9583 / 5.1392
    np.testing.assert_allclose(Yt / Yc, ratio, rtol=1e-5)
    # concrete values: the zenith luminance of the spec's check case (T = 3, theta_s = 60 deg)
    assert Yc[0] == pytest.approx(5.1392, abs=1e-4) and Yt[0] == pytest.approx(7.9583, abs=1e-4)
    Xt, _, Zt = split(pywarp.colour_xyY_to_XYZ(np.stack([xt, yt, Yt], -1)))
    hdr_t = sky_preetham(*args, output="hdr", variant="thesis")
    g_corr_matrix = pywarp.colour_XYZ_to_linear_srgb(np.stack([Xt, Yt, Zt], -1))[..., 1]
    np.testing.assert_allclose(hdr_t[1] - g_corr_matrix, 0.03 * Xt, rtol=1e-4)  # -0.9392660 + 0.9692660 = 0.03
    tm_t = sky_preetham(*args, variant="thesis")
    assert all(np.all(c < 0) for c in tm_t)
    tm_c = sky_preetham(*args)
    assert all(np.all((c > 0) & (c < 1)) for c in tm_c)


@pytest.mark.spec("vc-A29", "vc-2.36")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_sky_preetham_below_horizon_is_the_horizon_limit(impl):
    """Sun at the zenith: two below-horizon directions with the same angle to the sun give the same colour, equal to
    the float64 Perez value at cos(theta) = 0.01; below-horizon colours are finite and in the display range."""
    sky = components(pywarp.equation("vc-A29", impl=impl))
    d = np.array([[0.8, -0.6, 0.0], [0.0, -0.6, 0.8], [-0.48, -0.6, -0.64]])
    x, y, Y = sky(d, 4.0, 90.0, output="xyY")
    assert np.all(x == x[0]) and np.all(y == y[0]) and np.all(Y == Y[0])
    g = np.arccos(-0.6)
    c = tuple(f32(v) for v in coeffs64(4.0, "Y"))
    ref = zenith64(4.0, 0.0)[0] * perez64_cg(0.01, g, -0.6, *c) / perez64(0.0, 0.0, *c)
    assert Y[0] == pytest.approx(ref, rel=1e-5)
    below = unit_dirs(np.random.default_rng(5), 500)
    below[:, 1] = -np.abs(below[:, 1])
    rgb = sky(below, 6.0, 20.0, output="srgb")
    assert all(np.all(np.isfinite(c) & (c > 0) & (c < 1)) for c in rgb)


@pytest.mark.spec("vc-A29")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_sky_preetham_bad_input(impl):
    sky = components(pywarp.equation("vc-A29", impl=impl))
    d = [[0.0, 1.0, 0.0]]
    with pytest.raises(ValueError, match=r"^turbidity must be in \[2, 10\], got 1\.0"):
        sky(d, 1.0, 30.0)
    with pytest.raises(ValueError, match=r"^turbidity must be in \[2, 10\], got 10\.5"):
        sky(d, 10.5, 30.0)
    with pytest.raises(ValueError, match=r"^turbidity must be finite"):
        sky(d, np.nan, 30.0)
    # the sky parameters are element-wise arguments like the direction: they broadcast (one sky per element)
    assert sky(d, [3.0, 4.0], 30.0)[0].shape == (2,)
    with pytest.raises(ValueError, match=r"^sun_elevation_deg must be in \[0, 90\], got -5"):
        sky(d, 3.0, -5.0)  # sun below the horizon: theta_s > pi/2 is invalid for Preetham
    with pytest.raises(ValueError, match=r"^direction must be finite"):
        sky([[0.0, np.nan, 1.0]], 3.0, 30.0)
    with pytest.raises(ValueError, match=r"^direction must be a non-zero vector"):
        sky([[0.0, 0.0, 0.0]], 3.0, 30.0)
    with pytest.raises(ValueError, match=r"^direction must be an array of 3-vectors, shape \(\.\.\., 3\)"):
        sky([[0.0, 1.0]], 3.0, 30.0)
    with pytest.raises(ValueError, match=r"^exposure must be in \(0, inf\)"):
        sky(d, 3.0, 30.0, exposure=0.0)
    with pytest.raises(ValueError, match=r"^sun_azimuth_deg must be finite"):
        sky(d, 3.0, 30.0, np.inf)
    with pytest.raises(ValueError, match=r"^output must be one of"):
        sky(d, 3.0, 30.0, output="rgb8")
    with pytest.raises(ValueError, match=r"^variant must be one of"):
        sky(d, 3.0, 30.0, variant="printed")


@pytest.mark.spec("vc-A29")
def test_sky_preetham_shapes_and_exposure():
    d = np.zeros((4, 5, 3))
    d[..., 1] = 1.0
    r, g, b = sky_preetham(d, 3.0, 30.0)
    assert r.shape == (4, 5) and r.dtype == np.float32
    assert sky_preetham(np.zeros((0, 3)), 3.0, 30.0)[0].shape == (0,)
    hdr = sky_preetham([0.3, 0.5, 0.2], 3.0, 30.0, output="hdr")
    tm = sky_preetham([0.3, 0.5, 0.2], 3.0, 30.0, exposure=0.1)
    np.testing.assert_allclose(tm, 1 - np.exp(-0.1 * np.array(hdr, np.float64)), rtol=1e-6)


@pytest.mark.spec("vc-A29")
def test_preetham_params_struct_matches_c_init(rng):
    """The Warp per-frame struct (preetham_params) equals the C ccl_sky_preetham_init field by field (<= 2 ulp; measured
    0), and both validate: turbidity in [2, 10], theta_s in [0, pi/2]."""
    f, lb = ffi(), lib()
    for T, ts, v in ((2.0, 0.0, "corrected"), (6.5, 1.2, "thesis"), (10.0, HALF_PI_F32, "corrected")):
        p = host_sky.preetham_params(T, ts, 0.03, v)
        c = f.new("ccl_preetham *")
        assert lb.ccl_sky_preetham_init(T, ts, 0.03, {"corrected": 0, "thesis": 1}[v], c) == 0
        for name in ("perez_Y", "perez_x", "perez_y"):
            assert max_ulp_diff(np.array(getattr(p, name)), np.array(list(getattr(c, name)))) <= 2, name
        for name in ("zenith_Y", "zenith_x", "zenith_y", "factor_Y", "factor_x", "factor_y", "turbidity", "theta_s",
                     "exposure"):
            assert max_ulp_diff(getattr(p, name), getattr(c, name)) <= 2, name
        assert p.variant == c.variant
    with pytest.raises(ValueError, match=r"^theta_s must be in \[0, 1\.5708\]"):
        host_sky.preetham_params(3.0, 1.6)
    with pytest.raises(ValueError, match=r"^turbidity must be in \[2, 10\]"):
        host_sky.preetham_params(1.9, 0.5)
    with pytest.raises(ValueError, match=r"^exposure must be in"):
        host_sky.preetham_params(3.0, 0.5, exposure=-1.0)
    c = f.new("ccl_preetham *")
    assert lb.ccl_sky_preetham_init(3.0, 1.6, 0.03, 0, c) == lb.CCL_EINVAL
    assert lb.ccl_sky_preetham_init(11.0, 0.5, 0.03, 0, c) == lb.CCL_EINVAL


# --- vc-A28: gradient sky ---------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A28")
def test_sky_gradient_matches_float64(rng):
    d = f32(unit_dirs(rng, 3000)).astype(np.float32)
    kw = dict(horizon_colour=(0.7, 0.8, 0.95), zenith_colour=(0.1, 0.3, 0.7), sun_colour=(1.0, 0.9, 0.6),
              sun_exponent=32.0)
    out = np.stack(sky_gradient(d, 25.0, 40.0, **kw), -1).astype(np.float64)
    sun = sky_mod.sun_direction(25.0, 40.0).astype(np.float64)
    dd = d.astype(np.float64)
    h, z, s = (f32(kw[k]) for k in ("horizon_colour", "zenith_colour", "sun_colour"))
    t = np.clip(dd[:, 1], 0, 1)[:, None]
    c = np.maximum(dd @ sun, 0)[:, None]
    ref = h + t * (z - h) + s * c ** 32
    # lerp: z - h, the product and the sum (3u on |h| + |t (z - h)|); the sun term: c carries 3u absolute (dot
    # product), c^32 then 32 * 3u / c relative, powf 2u, the product and the last sum u
    bound = 3 * U * (np.abs(h) + np.abs(t * (z - h))) + s * c ** 32 * (96 * U / np.maximum(c, 1e-30) + 4 * U) \
        + U * np.abs(ref)
    assert np.all(np.abs(out - ref) <= bound * (1 + 1e-6))


@pytest.mark.spec("vc-A28")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_sky_gradient_properties_and_defaults(impl):
    sky = components(pywarp.equation("vc-A28", impl=impl))
    D = sky_mod.GRADIENT_DEFAULTS
    h, z, s = (np.array(D[k], np.float32) for k in ("horizon_colour", "zenith_colour", "sun_colour"))
    # zenith with the sun at 10 deg: the dark blue (cos(80 deg)^64 underflows)
    np.testing.assert_allclose(np.array(sky([0, 1, 0], 10.0)), z, atol=1e-7)
    # at and below the horizon, facing away from the sun: the light blue exactly
    for dy in (0.0, -0.3, -1.0):
        np.testing.assert_array_equal(np.array(sky([0.0, dy, 1.0], 10.0)), h)
    # the sun term: full colour at the sun, half at acos(0.5^(1/64)) = 8.42 deg
    e = 10.0
    at_sun = np.array(sky(sky_mod.sun_direction(e, 0.0), e), np.float64)
    t = np.sin(np.radians(e))
    ref = h + t * (z - h) + s
    # d . s of a float32 unit vector with itself is 1 within 3u, raised to the 64th power: 192u on the sun term
    assert np.all(np.abs(at_sun - ref) <= s * (192 + 4) * U + 3 * U * ref)
    half = math.degrees(math.acos(0.5 ** (1 / 64)))
    assert half == pytest.approx(8.42, abs=5e-3)
    off = sky_mod.sun_direction(e + half, 0.0)
    base = h + np.sin(np.radians(e + half)) * (z - h)
    # c = d . s carries the float32 rounding of both directions (2u) and of the dot product (3u), raised to the 64th
    # power: 64 * 5u / c = 324u; powf and the product 4u; the lerp's 3u on |h| + |t (z - h)| <= 1 relative to
    # 0.5 s >= 0.35: 9u. Allowed 340u = 2.0e-5 (observed 1.4e-7)
    np.testing.assert_allclose(np.array(sky(off, e), np.float64) - base, 0.5 * s, rtol=340 * U)
    # monotonic from the horizon to the zenith when the sun is behind the viewer's hemisphere
    ys = np.linspace(0, 1, 50)
    dirs = np.stack([np.zeros(50), ys, np.sqrt(1 - ys ** 2)], -1)
    b = sky(dirs, 20.0, 180.0 + 90.0)[2]
    assert np.all(np.diff(b) <= 0)  # blue channel falls from 0.94 to 0.72
    # the C defaults are the documented Python defaults
    g = ffi().new("ccl_sky_gradient *")
    lib().ccl_sky_gradient_defaults(g)
    np.testing.assert_array_equal(np.array(list(g.horizon)), h)
    np.testing.assert_array_equal(np.array(list(g.zenith)), z)
    np.testing.assert_array_equal(np.array(list(g.sun)), s)
    assert g.sun_exponent == D["sun_exponent"]


@pytest.mark.spec("vc-A28")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_sky_gradient_bad_input(impl):
    sky = components(pywarp.equation("vc-A28", impl=impl))
    d = [0.0, 1.0, 0.0]
    with pytest.raises(ValueError,
                       match=r"^horizon_colour must be in 3-vector, components in \[0, 1e\+06\], got -0\.1"):
        sky(d, 10.0, horizon_colour=(-0.1, 0.5, 0.5))
    with pytest.raises(ValueError, match=r"^zenith_colour must be an array of 3-vectors"):
        sky(d, 10.0, zenith_colour=(0.1, 0.5))
    with pytest.raises(ValueError, match=r"^sun_colour must be finite"):
        sky(d, 10.0, sun_colour=(np.nan, 0.5, 0.5))
    with pytest.raises(ValueError, match=r"^sun_exponent must be in \(0, inf\)"):
        sky(d, 10.0, sun_exponent=0.0)
    with pytest.raises(ValueError, match=r"^sun_elevation_deg must be in \[-90, 90\]"):
        sky(d, 91.0)
    with pytest.raises(ValueError, match=r"^direction must be a non-zero vector"):
        sky([0.0, 0.0, 0.0], 10.0)
    with pytest.raises(ValueError, match=r"^output must be one of 'linear', 'srgb'"):
        sky(d, 10.0, output="hdr")


@pytest.mark.spec("vc-A28", "vc-A29")
def test_sun_direction_closed_form_and_c_agreement(rng):
    for e, a in ((0.0, 0.0), (0.0, 90.0), (90.0, 33.0), (30.0, 45.0), (-20.0, 200.0)):
        w = sky_mod.sun_direction(e, a)
        c = sky_mod.sun_direction(e, a, impl="c")
        np.testing.assert_allclose(w, sun64(e, a), atol=2e-7)
        assert max_ulp_diff(w, c) <= 2
        assert np.linalg.norm(w.astype(np.float64)) == pytest.approx(1.0, abs=3e-7)
    np.testing.assert_array_equal(sky_mod.sun_direction(0.0, 0.0), [0.0, 0.0, -1.0])  # azimuth 0 = -Z
    with pytest.raises(ValueError, match=r"^sun_elevation_deg must be in \[-90, 90\]"):
        sky_mod.sun_direction(-91.0)


# --- C vs Warp --------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.33", "vc-2.35", "vc-2.36", "vc-2.37", "vc-2.38", "vc-4.2", "vc-2.39", "vc-2.40", "vc-2.41",
                  "vc-2.42", "vc-2.43", "vc-2.44")
def test_sky_functions_c_and_warp_agree_on_random_inputs(rng):
    """C (gcc -std=c99, no FMA contraction) vs Warp (LLVM) on 2000 random inputs per function: at most 2 ulp apart.
    Both evaluate the same float32 expression tree; on the CPU Warp's exp/cos/tan/acos/pow call the same libm as the
    C library, so the measured difference is 0 ulp for every function -- 2 ulp allows one differently rounded libm
    call on another platform."""
    n = 2000
    T = rng.uniform(2, 10, n)
    th, g, ts = rng.uniform(0, np.pi, n), rng.uniform(0, np.pi, n), rng.uniform(0, np.pi / 2, n)
    Yz = rng.uniform(0.1, 30, n)
    c = pywarp.sky_preetham_perez_Y(T)
    cases = [("vc-2.33", (rng.uniform(0.01, 1, n), rng.uniform(0, 3, n)), {}),
             ("vc-2.35", (th, g, ts, Yz), {}), ("vc-2.36", (th, g, *c), {}),
             ("vc-2.37", (th, g, *c), {"variant": "corrected"}), ("vc-2.37", (th, g, *c), {"variant": "thesis"}),
             ("vc-2.38", (th, g, ts, Yz, *c), {}), ("vc-4.2", (ts, Yz, *c), {}),
             ("vc-2.39", (T, ts), {"variant": "corrected"}), ("vc-2.39", (T, ts), {"variant": "thesis"}),
             ("vc-2.40", (T, ts), {}), ("vc-2.41", (T, ts), {}),
             ("vc-2.42", (T,), {}), ("vc-2.43", (T,), {}), ("vc-2.44", (T,), {})]
    for cid, args, kw in cases:
        w, _ = assert_twins_agree(cid, *args, ulp=2, **kw)
        assert w[0].shape[0] == n, (cid, kw)


@pytest.mark.spec("vc-A28", "vc-A29")
def test_sky_models_c_and_warp_agree_on_random_directions(rng):
    """The per-pixel sky functions, C vs Warp, every output stage and both variants, on 1000 random directions (a
    third below the horizon): at most 2 ulp (measured 0), for the reason of the previous test."""
    d = unit_dirs(rng, 1000)
    for kw in ({"output": "xyY"}, {"output": "hdr"}, {}, {"output": "srgb"}, {"variant": "thesis"},
               {"variant": "thesis", "output": "hdr"}):
        assert_twins_agree("vc-A29", d, 3.7, 35.0, 20.0, ulp=2, **kw)
    for kw in ({}, {"output": "srgb"}, {"sun_exponent": 7.5, "zenith_colour": (0.0, 0.1, 0.5)}):
        assert_twins_agree("vc-A28", d, -10.0, 300.0, ulp=2, **kw)
