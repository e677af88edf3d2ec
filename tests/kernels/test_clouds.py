"""Cloud density and lighting model vc-2.28 .. 2.31, 4.7, 4.8, A15, A16, A17, A20: float64 NumPy re-derivations of the
printed formulas, the cataloguer's check values (coverage response of 2.29, gradient peaks of 4.7 with and without
clamping), properties (E = 0 at d = 0, maximum of Beer x powder, type interpolation, relative-height variants), the
chosen readings of the ambiguities, C vs Warp agreement and bad input."""
from __future__ import annotations

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree

EPS32 = float(np.finfo(np.float32).eps)


def f32(x):
    """The float32 rounding of x in float64: the exact input the functions under test receive."""
    return np.asarray(x, dtype=np.float32).astype(np.float64)


# --- float64 references, written from the spec (not from the code under test) ----------------------------------------

def remap64(v, o0, o1, n0, n1):
    return n0 + (v - o0) / (o1 - o0) * (n1 - n0)


def gradient64(h, cloud_type, clamp=False):
    """vc-4.7 with the vc-A16 piecewise-linear blend."""
    sat = (lambda x: np.clip(x, 0.0, 1.0)) if clamp else (lambda x: x)

    def profile(lo0, lo1, hi0, hi1):
        return np.maximum(0.0, sat(remap64(h, lo0, lo1, 0, 1)) * sat(remap64(h, hi0, hi1, 1, 0)))

    cu, sc, st = profile(0.01, 0.30, 0.6, 0.95), profile(0.01, 0.25, 0.3, 0.65), profile(0.01, 0.05, 0.0, 0.20)
    t = np.asarray(cloud_type, dtype=np.float64)
    low = st + (sc - st) * (2 * t)
    high = sc + (cu - sc) * (2 * t - 1)
    return np.where(t <= 0.5, low, high)


def hg64(mu, g):
    return (1 - g * g) / (4 * np.pi * (1 + g * g - 2 * g * mu) ** 1.5)


def density64(cov, typ, h, br, bg, bb, ba, dr, dg, db, hd, thr, gradient_clamp=False, clamp=True, prose=False):
    d_v = gradient64(h, typ, gradient_clamp)
    l_fbm = 0.625 * bg + 0.25 * bb + 0.125 * ba
    b = remap64(br, l_fbm - 1, 1, 0, 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        b_d = np.where(thr >= 1, 0.0, remap64(b * d_v, thr, 1, 0, 1) * cov)
    if clamp:
        b_d = np.maximum(b_d, 0)
    hf = 0.625 * dr + 0.25 * dg + 0.125 * db
    if prose:
        hf = 1 - hf
    m = hf * (1 - hd) + (1 - hf) * hd
    c = remap64(b_d, 0.2 * m, 1, 0, 1)
    return np.maximum(c, 0) if clamp else c


# --- vc-2.28 ---------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.28", "vc-2.27")
def test_base_shape_closed_form_and_range(rng):
    cr, cg, cb, ca = (rng.uniform(0, 1, 2000) for _ in range(4))
    l_fbm, b = pywarp.clouds_base_shape(cr, cg, cb, ca)
    l64 = 0.625 * f32(cg) + 0.25 * f32(cb) + 0.125 * f32(ca)
    np.testing.assert_allclose(l_fbm, l64, rtol=3 * EPS32)
    # cataloguer: B = (C_R - L_FBM + 1) / (2 - L_FBM), in [(1 - L) / (2 - L), 1], never negative
    b64 = (f32(cr) - f32(l_fbm) + 1) / (2 - f32(l_fbm))
    np.testing.assert_allclose(b, b64, rtol=4 * EPS32)
    lo = (1 - f32(l_fbm)) / (2 - f32(l_fbm))
    assert np.all(b >= lo - 4 * EPS32) and np.all(b <= 1 + 4 * EPS32) and np.all(b >= 0)
    # weights 0.625 + 0.25 + 0.125 = 1; B = 0 only at L_FBM = 1 and C_R = 0; B = 1 at C_R = 1
    assert pywarp.clouds_base_shape(1.0, 1.0, 1.0, 1.0) == (1.0, 1.0)
    assert pywarp.clouds_base_shape(0.0, 1.0, 1.0, 1.0)[1] == 0.0
    assert pywarp.clouds_base_shape(0.0, 0.0, 0.0, 0.0)[1] == pytest.approx(0.5, rel=EPS32)
    np.testing.assert_allclose(pywarp.clouds_base_shape(1.0, cg, cb, ca)[1], 1.0, rtol=2 * EPS32)


# --- vc-2.29 ---------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.29")
def test_coverage_cataloguer_check_values_with_threshold_equal_to_coverage():
    """Spec note (2) of vc-2.29: with C = coverage, B = 0.8 gives 0.15 / 0.30 / 0.233 / 0 at D_h = 0.2 / 0.5 / 0.7 /
    0.8 and negative above -- the non-monotonic response of the reading C := D_h."""
    d_h = np.array([0.2, 0.5, 0.7, 0.8, 0.9])
    unclamped = pywarp.clouds_coverage(0.8, 1.0, d_h, d_h, clamp=False)
    np.testing.assert_allclose(unclamped, [0.15, 0.30, 0.7 / 3, 0.0, -0.9], atol=1e-6)
    clamped = pywarp.clouds_coverage(0.8, 1.0, d_h, d_h)  # clamp=True is the default
    np.testing.assert_allclose(clamped, [0.15, 0.30, 0.7 / 3, 0.0, 0.0], atol=1e-6)
    assert clamped[1] > clamped[2] > clamped[3]  # more coverage, less cloud: the non-monotonic reading
    # the threshold is an explicit argument (the C signature): C := D_h is asked for by passing the coverage twice
    np.testing.assert_array_equal(clamped, pywarp.clouds_coverage(0.8, 1.0, d_h, coverage_threshold=d_h))


@pytest.mark.spec("vc-2.29")
def test_coverage_division_by_zero_at_threshold_one_and_explicit_threshold(rng):
    # C = 1: the remap range [C, 1] is empty -> 0, finite in both clamp modes (no Inf/NaN)
    for clamp in (True, False):
        out = pywarp.clouds_coverage([0.0, 0.5, 1.0], [1.0, 2.0, 1.0], 1.0, 1.0, clamp=clamp)
        np.testing.assert_array_equal(out, 0.0)
    # explicit threshold against float64
    b, dv, dh = rng.uniform(0, 1, 1000), rng.uniform(0, 2.2, 1000), rng.uniform(0, 1, 1000)
    thr = rng.uniform(0, 0.95, 1000)
    got = pywarp.clouds_coverage(b, dv, dh, thr, clamp=False)
    ref = remap64(f32(b) * f32(dv), f32(thr), 1, 0, 1) * f32(dh)
    # a few roundings, amplified by the remap denominator 1 / (1 - C) <= 20 for the cancelling B D_v - C
    np.testing.assert_allclose(got, ref, rtol=8 * EPS32, atol=20 * 4 * EPS32 * 2.2)
    np.testing.assert_array_equal(pywarp.clouds_coverage(b, dv, dh, thr), np.maximum(got, 0))
    # C = 0 keeps the shape: B_D = B D_v D_h; "small clouds are lighter": B_D scales with D_h at a fixed threshold
    assert pywarp.clouds_coverage(0.5, 0.8, 0.5, 0.0) == pytest.approx(0.2, rel=2 * EPS32)
    assert pywarp.clouds_coverage(0.5, 1.5, 0.6, 0.25) == pytest.approx(0.4, rel=4 * EPS32)


# --- vc-2.30 ---------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.30")
def test_detail_erosion_formula_direction_and_float64(rng):
    bd, cr, cg, cb, hr = (rng.uniform(0, 1, 1000) for _ in range(5))
    hf = 0.625 * f32(cr) + 0.25 * f32(cg) + 0.125 * f32(cb)
    m = hf * (1 - f32(hr)) + (1 - hf) * f32(hr)
    ref = remap64(f32(bd), 0.2 * m, 1, 0, 1)
    got = pywarp.clouds_detail_erosion(bd, cr, cg, cb, hr, clamp=False)
    np.testing.assert_allclose(got, ref, rtol=8 * EPS32, atol=1e-7)  # denominator 1 - 0.2 M >= 0.8: well-conditioned
    np.testing.assert_array_equal(pywarp.clouds_detail_erosion(bd, cr, cg, cb, hr), np.maximum(got, 0))
    # as printed: at h_rel = 0 the threshold uses H_FBM, at h_rel = 1 it uses 1 - H_FBM (channels (1, 1, 1): H = 1)
    assert pywarp.clouds_detail_erosion(0.6, 1.0, 1.0, 1.0, 0.0) == pytest.approx((0.6 - 0.2) / 0.8, rel=2 * EPS32)
    assert pywarp.clouds_detail_erosion(0.6, 1.0, 1.0, 1.0, 1.0) == pytest.approx(0.6, rel=2 * EPS32)
    # M = 0.5 at mid height for any texture value: C = (B_D - 0.1) / 0.9
    np.testing.assert_allclose(pywarp.clouds_detail_erosion(0.55, cr, cg, cb, 0.5), 0.5, rtol=4 * EPS32)
    # below the threshold 0.2 M: negative as printed, 0 when clamped
    assert pywarp.clouds_detail_erosion(0.1, 1.0, 1.0, 1.0, 0.0, clamp=False) < 0
    assert pywarp.clouds_detail_erosion(0.1, 1.0, 1.0, 1.0, 0.0) == 0.0


@pytest.mark.spec("vc-2.30")
def test_detail_erosion_prose_direction_swaps_the_height_blend():
    """'prose': classic Worley low, inverse high for an inverse-Worley texture, i.e. M = (1 - H)(1 - h) + H h."""
    formula = pywarp.clouds_detail_erosion(0.6, 1.0, 1.0, 1.0, [0.0, 1.0])
    prose = pywarp.clouds_detail_erosion(0.6, 1.0, 1.0, 1.0, [0.0, 1.0], detail_direction="prose")
    np.testing.assert_allclose(prose, formula[::-1], rtol=2 * EPS32)
    h = np.linspace(0, 1, 11)
    ch = np.array([0.9, 0.4, 0.7])  # H = 0.7375; the complementary channels give 1 - H
    np.testing.assert_allclose(pywarp.clouds_detail_erosion(0.5, *ch, h, detail_direction="prose"),
                               pywarp.clouds_detail_erosion(0.5, *(1 - ch), h), rtol=4 * EPS32)


# --- vc-2.31 ---------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.31", "vc-2.13")
def test_cloud_energy_closed_form_and_zero_at_zero_thickness(rng):
    d, a = rng.uniform(0, 6, 2000), rng.uniform(0, 3, 2000)
    mu, g = rng.uniform(-1, 1, 2000), rng.uniform(-0.9, 0.9, 2000)
    ref = np.exp(-f32(d) * f32(a)) * hg64(f32(mu), f32(g)) * (1 - np.exp(-2 * f32(d)))
    got = pywarp.clouds_energy(d, a, mu, g)
    # HG's float32 error (cancellation in 1 + g^2 - 2 g mu, <= ~50 eps for |g| <= 0.9) dominates; the powder term
    # 1 - e^{-2d} loses relative precision for small d (absolute error ~eps)
    np.testing.assert_allclose(got, ref, rtol=100 * EPS32, atol=2 * EPS32 * hg64(f32(mu), f32(g)).max())
    # E = 0 at d = 0 for every angle, a and g (spec ambiguity item 19)
    np.testing.assert_array_equal(pywarp.clouds_energy(0.0, a, mu, g), 0.0)
    # silver lining: with g > 0 more energy towards the sun
    assert pywarp.clouds_energy(1.0, 1.0, 1.0, 0.5) > 5 * pywarp.clouds_energy(1.0, 1.0, -1.0, 0.5)
    # the default g (0.2, documented) is the argument's default
    assert pywarp.clouds_energy(1.0, 1.0, 0.3) == pywarp.clouds_energy(1.0, 1.0, 0.3, 0.2)


@pytest.mark.spec("vc-2.31")
@pytest.mark.parametrize("a", [0.25, 1.0, 4.0])
def test_cloud_energy_peaks_at_the_beer_powder_maximum(a):
    """d/dd [e^{-a d} (1 - e^{-2d})] = 0 at d* = ln(1 + 2/a) / 2 (dark edges, then Beer decay)."""
    d = np.linspace(0, 8, 80001)
    e = pywarp.clouds_energy(d, a, 0.0, 0.2)
    d_star = 0.5 * np.log(1 + 2 / a)
    assert d[np.argmax(e)] == pytest.approx(d_star, abs=2e-3)
    peak = np.exp(-a * d_star) * (1 - np.exp(-2 * d_star)) * hg64(0.0, 0.2)
    assert e.max() == pytest.approx(peak, rel=1e-5)
    # a = 0 (no precipitation): monotone, approaching HG from below
    e0 = pywarp.clouds_energy(d, 0.0, 0.0, 0.2)
    assert np.all(np.diff(e0) >= 0) and e0[-1] == pytest.approx(hg64(0.0, 0.2), rel=1e-6)


# --- vc-4.7, vc-A16 ------------------------------------------------------------------------------------------------

H_FINE = np.linspace(0.0, 1.0, 100001)


@pytest.mark.spec("vc-4.7", "vc-A16", "vc-2.27")
@pytest.mark.parametrize("cloud_type,peak,where", [(1.0, 2.1764, 0.48), (0.5, 1.2190, 0.33), (0.0, 1.1281, 0.105)])
def test_height_gradient_unclamped_peaks_match_the_catalogue(cloud_type, peak, where):
    g = pywarp.clouds_height_gradient(H_FINE, cloud_type)  # clamp=False is the default: remaps unclamped as printed
    assert g.max() == pytest.approx(peak, abs=1e-4)
    assert H_FINE[np.argmax(g)] == pytest.approx(where, abs=1e-3)


@pytest.mark.spec("vc-4.7", "vc-A16")
def test_height_gradient_clamped_profiles():
    st = pywarp.clouds_height_gradient(H_FINE, 0.0, clamp=True)
    assert st.max() == pytest.approx(0.75, abs=1e-6)  # cataloguer: the clamped stratus peaks at only 0.75
    assert H_FINE[np.argmax(st)] == pytest.approx(0.05, abs=1e-5)
    cu = pywarp.clouds_height_gradient(H_FINE, 1.0, clamp=True)
    sc = pywarp.clouds_height_gradient(H_FINE, 0.5, clamp=True)
    assert np.all(cu[(H_FINE >= 0.30) & (H_FINE <= 0.60)] == 1.0)  # cumulus plateau
    assert np.all(sc[(H_FINE >= 0.25) & (H_FINE <= 0.30)] == 1.0)  # stratocumulus plateau
    for g in (st, sc, cu):
        assert g.max() <= 1.0 and g.min() >= 0.0
    # non-zero support (0.01, 0.95) / (0.01, 0.65) / (0.01, 0.20), the same clamped or not
    for t, top in ((1.0, 0.95), (0.5, 0.65), (0.0, 0.20)):
        for clamp in (False, True):
            g = pywarp.clouds_height_gradient(H_FINE, t, clamp=clamp)
            inside = (H_FINE > 0.0101) & (H_FINE < top - 1e-4)
            assert np.all(g[inside] > 0) and np.all(g[(H_FINE <= 0.01) | (H_FINE >= top)] == 0), (t, clamp)


@pytest.mark.spec("vc-4.7", "vc-A16")
def test_height_gradient_matches_float64_reference(rng):
    h = rng.uniform(0, 1, 5000)
    t = np.concatenate([np.zeros(1000), np.full(1000, 0.5), np.ones(1000), rng.uniform(0, 1, 2000)])
    for clamp in (False, True):
        got = pywarp.clouds_height_gradient(h, t, clamp=clamp)
        ref = gradient64(f32(h), f32(t), clamp)
        # a few roundings of O(1) operands, amplified by the remap slopes (<= 1 / 0.04 for stratus) and the blend
        np.testing.assert_allclose(got, ref, rtol=0, atol=2e-5, err_msg=f"clamp={clamp}")


@pytest.mark.spec("vc-A16")
def test_type_blend_piecewise_linear_and_exact_at_the_nodes(rng):
    st, sc, cu = (rng.uniform(0, 2, 500) for _ in range(3))
    np.testing.assert_array_equal(pywarp.clouds_type_blend(st, sc, cu, 0.0), st.astype(np.float32))
    np.testing.assert_array_equal(pywarp.clouds_type_blend(st, sc, cu, 0.5), sc.astype(np.float32))
    np.testing.assert_array_equal(pywarp.clouds_type_blend(st, sc, cu, 1.0), cu.astype(np.float32))
    t = rng.uniform(0, 1, 500)
    ref = np.where(f32(t) <= 0.5, f32(st) + (f32(sc) - f32(st)) * 2 * f32(t),
                   f32(sc) + (f32(cu) - f32(sc)) * (2 * f32(t) - 1))
    np.testing.assert_allclose(pywarp.clouds_type_blend(st, sc, cu, t), ref, rtol=0, atol=8 * EPS32 * 2)
    # clouds_height_gradient blends the per-type gradients the same way: type 0.25 is the mean of stratus and
    # stratocumulus
    h = np.linspace(0, 1, 101)
    grad = pywarp.clouds_height_gradient
    np.testing.assert_allclose(grad(h, 0.25), 0.5 * (grad(h, 0.0) + grad(h, 0.5)), atol=4e-7)
    np.testing.assert_allclose(grad(h, 0.75), 0.5 * (grad(h, 0.5) + grad(h, 1.0)), atol=4e-7)


# --- vc-4.8, vc-A15 ------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-4.8")
def test_composite_limits_and_float64(rng):
    b, od, cc = rng.uniform(0, 2, 1000), rng.uniform(0, 1, 1000), rng.uniform(0, 1, 1000)
    np.testing.assert_allclose(pywarp.clouds_composite(b, od, cc), f32(b) * (1 - f32(od)) + f32(cc), rtol=4 * EPS32)
    # spec: O_D = 0 -> B + C_clouds (= B without clouds); O_D = 1 -> C_clouds
    np.testing.assert_array_equal(pywarp.clouds_composite(b, 0.0, 0.0), b.astype(np.float32))
    np.testing.assert_array_equal(pywarp.clouds_composite(b, 1.0, cc), cc.astype(np.float32))
    assert pywarp.clouds_composite(0.5, 0.5, 0.2) == pytest.approx(0.45, rel=EPS32)


@pytest.mark.spec("vc-A15")
def test_relative_height_variants():
    r_in, r_out = 6371.0 + 1.5, 6371.0 + 4.0  # km: a 2.5 km layer from 1.5 km above a 6371 km Earth
    r = np.array([r_in, r_in + 0.625, r_in + 1.25, r_out])
    h = pywarp.clouds_relative_height(r, r_in, r_out)
    # corrected: (r - R_inner) / (R_outer - R_inner): 0 at the inner sphere, 1 at the outer; float32 radii near 6.4e3
    # km carry ulp 4.9e-4 km, i.e. 2e-4 of the layer
    np.testing.assert_allclose(h, [0.0, 0.25, 0.5, 1.0], atol=4e-4)
    # thesis: the printed "subtract one" from the normalized distance to the outer sphere: d - 1 = -h in [-1, 0]
    thesis = pywarp.clouds_relative_height(r, r_in, r_out, variant="thesis")
    np.testing.assert_allclose(thesis, [0.0, -0.25, -0.5, -1.0], atol=4e-4)
    np.testing.assert_allclose(thesis, -h, atol=4e-4)
    assert pywarp.clouds_relative_height(2.5, 2.0, 4.0) == 0.25
    assert pywarp.clouds_relative_height(2.5, 2.0, 4.0, variant="thesis") == -0.25
    # outside the layer: linear extrapolation (the gradients are 0 there)
    assert pywarp.clouds_relative_height([1.0, 5.0], 2.0, 4.0).tolist() == [-0.5, 1.5]


# --- vc-A17, vc-A20 ------------------------------------------------------------------------------------------------

def _density_inputs(rng, n):
    u = [rng.uniform(0, 1, n) for _ in range(11)]
    u[2] = rng.uniform(0.0, 0.95, n)  # h: mostly inside the gradients' support
    return u


@pytest.mark.spec("vc-A17", "vc-2.28", "vc-2.29", "vc-2.30", "vc-4.7", "vc-A16")
def test_density_pipeline_matches_float64_reference(rng):
    args = _density_inputs(rng, 3000)
    thr = np.minimum(args[0], 0.95)  # keep the remap denominator 1 / (1 - C) <= 20
    for kw, opts in (({}, {}), ({"gradient_clamp": True}, {"gradient_clamp": True}),
                     ({"detail_direction": "prose"}, {"prose": True}),
                     ({"density_clamp": False}, {"clamp": False})):
        got = pywarp.clouds_density(*args, thr, **kw)
        ref = density64(*map(f32, args), f32(thr), **opts)
        # O(1) operands; the two remaps amplify rounding by <= 20 and <= 1.25, the gradient slopes by <= 25
        np.testing.assert_allclose(got, ref, rtol=0, atol=2e-4, err_msg=str(kw))
    assert np.mean(pywarp.clouds_density(*args, args[0]) > 0) > 0.05  # the test inputs do produce clouds


@pytest.mark.spec("vc-A17")
def test_density_pipeline_is_the_composition_of_its_parts(rng):
    cov, typ, h, br, bg, bb, ba, dr, dg, db, hd = _density_inputs(rng, 500)
    d_v = pywarp.clouds_height_gradient(h, typ)
    _, b = pywarp.clouds_base_shape(br, bg, bb, ba)
    b_d = pywarp.clouds_coverage(b, d_v, cov, cov)
    expected = pywarp.clouds_detail_erosion(b_d, dr, dg, db, hd)
    np.testing.assert_array_equal(pywarp.clouds_density(cov, typ, h, br, bg, bb, ba, dr, dg, db, hd, cov), expected)
    # no coverage, or a height outside every gradient's support: no cloud
    np.testing.assert_array_equal(pywarp.clouds_density(0.0, typ, h, br, bg, bb, ba, dr, dg, db, hd, 0.0), 0.0)
    np.testing.assert_array_equal(pywarp.clouds_density(cov, typ, 0.97, br, bg, bb, ba, dr, dg, db, hd, cov), 0.0)
    # the threshold C := D_h by keyword gives the same; an explicit other threshold changes the result
    same = pywarp.clouds_density(cov, typ, h, br, bg, bb, ba, dr, dg, db, hd, coverage_threshold=cov)
    np.testing.assert_array_equal(same, expected)
    # with B D_v <= 1 (clamped gradient) remap(x, C, 1, 0, 1) = (x - C)/(1 - C) <= x, and the erosion is monotone in
    # B_D: the threshold C = 0 keeps at least as much cloud everywhere. (With the unclamped gradient B D_v reaches
    # 2.18 and the remap amplifies it instead, so no such ordering holds.)
    lo = pywarp.clouds_density(cov, typ, h, br, bg, bb, ba, dr, dg, db, hd, 0.0, gradient_clamp=True)
    hi = pywarp.clouds_density(cov, typ, h, br, bg, bb, ba, dr, dg, db, hd, cov, gradient_clamp=True)
    assert np.all(lo >= hi) and np.sum(lo) > 1.5 * np.sum(hi)


@pytest.mark.spec("vc-A20", "vc-2.31")
def test_sample_light_ambient_by_height_and_defaults(rng):
    # at d = 0 the energy vanishes: only the ambient term, bottom colour at h = 0, top at h = 1 (defaults 0.006/0.012)
    np.testing.assert_allclose(pywarp.clouds_sample_light(0.0, 1.0, 0.5, [0.0, 0.5, 1.0]), [0.006, 0.009, 0.012],
                               rtol=2 * EPS32)
    assert pywarp.clouds_sample_light(0.0, 1.0, 0.5, 0.3, ambient_bottom=0.2, ambient_top=0.6) == \
        pytest.approx(0.32, rel=2 * EPS32)
    d, a, mu, h = rng.uniform(0, 4, 1000), rng.uniform(0, 2, 1000), rng.uniform(-1, 1, 1000), rng.uniform(0, 1, 1000)
    got = pywarp.clouds_sample_light(d, a, mu, h, 0.3, 2.5, 0.05, 0.1)
    ref = 2.5 * np.exp(-f32(d) * f32(a)) * hg64(f32(mu), f32(0.3)) * (1 - np.exp(-2 * f32(d))) \
        + f32(0.05) * (1 - f32(h)) + f32(0.1) * f32(h)
    np.testing.assert_allclose(got, ref, rtol=32 * EPS32, atol=2 * EPS32)
    # the direct term is vc-2.31 scaled by the sun
    np.testing.assert_allclose(pywarp.clouds_sample_light(d, a, mu, h, 0.3, 2.5, 0.0, 0.0),
                               2.5 * pywarp.clouds_energy(d, a, mu, 0.3), rtol=EPS32)
    # the documented defaults are the signature's defaults
    assert pywarp.clouds_sample_light(1.0, 1.0, 0.2, 0.4) == pywarp.clouds_sample_light(1.0, 1.0, 0.2, 0.4, 0.2, 1.0,
                                                                                         0.006, 0.012)


# --- C vs Warp, bad input ---------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.28", "vc-2.29", "vc-2.30", "vc-2.31", "vc-4.7", "vc-4.8", "vc-A15", "vc-A16", "vc-A17",
                  "vc-A20")
def test_clouds_c_and_warp_agree_on_random_inputs(rng):
    """C and Warp evaluate the same float32 expression trees (+ - * / correctly rounded, gcc -std=c99 does not contract
    into FMA, Warp's CPU backend measured bit-identical). Allowed: the entries' 2 ulp, to tolerate a backend that
    contracts a*b + c, or 1e-6 absolute for results that cancel to ~0 in remap (B D_v - C) or in the powder term:
    one ulp of an O(1) operand (6e-8) amplified at most 1 / (1 - 0.95) = 20 by the remap denominators used here."""
    n = 1500

    def u(lo=0.0, hi=1.0):
        return rng.uniform(lo, hi, n).astype(np.float32)

    d_h, cov = u(0, 0.95), u(0, 0.95)

    cases = [
        ("vc-2.28", (u(), u(), u(), u()), {}),
        ("vc-2.29", (u(), u(0, 2.2), u(), u(0, 0.95)), {"clamp": False}),
        ("vc-2.29", (u(), u(0, 2.2), d_h, d_h), {}),
        ("vc-2.30", (u(-1, 1), u(), u(), u(), u()), {"clamp": False}),
        ("vc-2.30", (u(-1, 1), u(), u(), u(), u()), {"detail_direction": "prose"}),
        ("vc-2.31", (u(0, 5), u(0, 3), u(-1, 1), u(-0.95, 0.95)), {}),
        ("vc-4.7", (u(), u()), {}),
        ("vc-4.7", (u(), u()), {"clamp": True}),
        ("vc-4.8", (u(0, 2), u(), u()), {}),
        ("vc-A15", (u(6372, 6376), 6372.5, 6375.0), {}),
        ("vc-A15", (u(6372, 6376), 6372.5, 6375.0), {"variant": "thesis"}),
        ("vc-A16", (u(0, 2), u(0, 2), u(0, 2), u()), {}),
        ("vc-A17", (cov, *(u() for _ in range(10)), cov), {}),
        ("vc-A17", (*(u() for _ in range(11)), u(0, 0.95)),
         {"gradient_clamp": True, "density_clamp": False, "detail_direction": "prose"}),
        ("vc-A20", (u(0, 5), u(0, 3), u(-1, 1), u(), u(-0.9, 0.9), u(0, 3), u(0, 0.1), u(0, 0.1)), {}),
    ]
    for cid, args, kw in cases:
        assert_twins_agree(cid, *args, atol=0.0 if cid == "vc-2.28" else 1e-6, **kw)


@pytest.mark.spec("vc-2.28", "vc-2.29", "vc-2.30", "vc-2.31", "vc-4.7", "vc-4.8", "vc-A15", "vc-A16", "vc-A17",
                  "vc-A20")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_clouds_bad_input_raises_value_error_naming_parameter(impl):
    eq = lambda cid: pywarp.equation(cid, impl=impl)  # noqa: E731
    with pytest.raises(ValueError, match=r"^C_A must be in \[0, 1\], got 1\.5"):
        eq("vc-2.28")(0.5, 0.5, 0.5, 1.5)
    with pytest.raises(ValueError, match=r"^D_h must be in \[0, 1\]"):
        eq("vc-2.29")(0.5, 1.0, -0.1, 0.5)
    with pytest.raises(ValueError, match=r"^coverage_threshold must be in \[0, 1\], got 1\.2"):
        eq("vc-2.29")(0.5, 1.0, 0.5, 1.2)
    with pytest.raises(ValueError, match=r"^clamp must be one of True, False, got 'yes'"):
        eq("vc-2.29")(0.5, 1.0, 0.5, 0.5, clamp="yes")
    with pytest.raises(TypeError, match=r"clouds_coverage\(\): missing a required argument: 'coverage_threshold'"):
        eq("vc-2.29")(0.5, 1.0, 0.5)
    with pytest.raises(ValueError, match=r"^detail_direction must be one of 'formula', 'prose', got 'up'"):
        eq("vc-2.30")(0.5, 0.5, 0.5, 0.5, 0.5, detail_direction="up")
    with pytest.raises(ValueError, match=r"^h_rel must be in \[0, 1\]"):
        eq("vc-2.30")(0.5, 0.5, 0.5, 0.5, 1.5)
    with pytest.raises(ValueError, match=r"^d must be in \[0, inf\)"):
        eq("vc-2.31")(-1.0, 1.0, 0.5, 0.2)
    with pytest.raises(ValueError, match=r"^g must be in \(-1, 1\), got 1\.0"):
        eq("vc-2.31")(1.0, 1.0, 0.5, 1.0)
    with pytest.raises(ValueError, match=r"^cos_theta must be finite"):
        eq("vc-2.31")(1.0, 1.0, np.nan, 0.2)
    with pytest.raises(ValueError, match=r"^cloud_type must be in \[0, 1\]"):
        eq("vc-4.7")(0.5, 1.1)
    with pytest.raises(ValueError, match=r"^h must be finite"):
        eq("vc-4.7")(np.inf, 0.5)
    with pytest.raises(ValueError, match=r"^O_D must be in \[0, 1\]"):
        eq("vc-4.8")(0.5, 1.5, 0.1)
    with pytest.raises(ValueError, match=r"^r_outer must be > r_inner, got r_inner = 2\.0, r_outer = 2\.0"):
        eq("vc-A15")(1.0, 2.0, 2.0)
    with pytest.raises(ValueError, match=r"^r_inner must be in \(0, inf\)"):
        eq("vc-A15")(1.0, 0.0, 2.0)
    with pytest.raises(ValueError, match=r"^d_cumulus must be in \[0, inf\)"):
        eq("vc-A16")(0.1, 0.1, -0.1, 0.5)
    with pytest.raises(ValueError, match=r"^h_detail must be in \[0, 1\]"):
        eq("vc-A17")(*([0.5] * 10), 2.0, 0.5)
    with pytest.raises(TypeError, match=r"clouds_density\(\): missing a required argument: 'h_detail'"):
        eq("vc-A17")(*([0.5] * 10))
    with pytest.raises(ValueError, match=r"^ambient_top must be in \[0, inf\)"):
        eq("vc-A20")(1.0, 1.0, 0.5, 0.5, ambient_top=-0.1)
    with pytest.raises(ValueError, match=r"^sun_intensity must be finite"):
        eq("vc-A20")(1.0, 1.0, 0.5, 0.5, sun_intensity=np.inf)
