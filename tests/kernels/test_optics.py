"""Optics of a drop: Snell/reflection for vectors (rr-snell), Fresnel in the cosine forms (rr-eq2, rr-eq3) against
closed forms, the catalogue's check values and the printed sin/tan forms, the drop's field of view, both variants
(rr-der-3.2.1). Independent references: float64 evaluations of the textbook formulas written here."""
from __future__ import annotations

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree

N_W = 1.33


def _dirs(theta_deg):
    """Incident directions at theta from the normal +z, travelling down onto the plane z = 0."""
    t = np.radians(np.asarray(theta_deg, np.float64))
    return np.stack([np.sin(t), np.zeros_like(t), -np.cos(t)], -1)


@pytest.mark.spec("rr-snell")
def test_optics_snell_angles_match_snells_law():
    th = np.linspace(0.0, 89.0, 90)
    t, r, tir = pywarp.optics_snell(_dirs(th), [0.0, 0.0, 1.0], 1.0, N_W)
    assert not tir.any()
    sin_t = np.sin(np.radians(th)) / N_W  # n1 sin(theta_i) = n2 sin(theta_t)
    np.testing.assert_allclose(t[:, 0], sin_t, atol=2e-7)
    np.testing.assert_allclose(t[:, 2], -np.sqrt(1 - sin_t ** 2), atol=2e-7)
    np.testing.assert_allclose(np.linalg.norm(t, axis=-1), 1.0, atol=3e-7)
    # law of reflection: mirrored z, same tangential part
    np.testing.assert_allclose(r, _dirs(th) * [1, 1, -1], atol=3e-7)
    # the normal may be given on either side
    t2, r2, _ = pywarp.optics_snell(_dirs(th), [0.0, 0.0, -1.0], 1.0, N_W)
    np.testing.assert_array_equal(t2, t)
    np.testing.assert_array_equal(r2, r)


@pytest.mark.spec("rr-snell")
def test_optics_snell_round_trip_and_total_internal_reflection(rng):
    d = rng.normal(size=(500, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    n = np.array([0.0, 1.0, 0.0])
    t, _, tir = pywarp.optics_snell(d, n, 1.0, N_W)  # air -> water never reflects totally
    assert not tir.any()
    back, _, tir_b = pywarp.optics_snell(-t, n, N_W, 1.0)
    assert not tir_b.any()
    # the way back is ill-conditioned near grazing incidence: d theta_i / d theta_t = n cos(theta_t) / cos(theta_i),
    # so the float32 rounding of t (a few eps) grows by 1 / cos_i; allowed 2e-6 + 8 eps / cos_i
    cos_i = np.abs(d[:, 1:2])
    assert np.all(np.abs(back - (-d)) <= 2e-6 + 8 * np.finfo(np.float32).eps / cos_i)
    # water -> air beyond the critical angle arcsin(1/1.33) = 48.75 deg: total internal reflection, t = 0
    crit = np.degrees(np.arcsin(1 / N_W))
    th = np.array([crit - 0.05, crit + 0.05, 60.0, 89.0])
    t, r, tir = pywarp.optics_snell(-_dirs(th), [0.0, 0.0, 1.0], N_W, 1.0)
    np.testing.assert_array_equal(tir, [0, 1, 1, 1])
    np.testing.assert_array_equal(t[1:], 0.0)
    assert_twins_agree("rr-snell", d, n, 1.0, N_W)
    assert_twins_agree("rr-snell", -_dirs(th), [0.0, 0.0, 1.0], N_W, 1.0)


def _fresnel64(theta_i, n1, n2):
    """The printed sin/tan forms of eqs. (2), (3) in float64 (valid away from normal incidence and TIR)."""
    ti = np.radians(theta_i)
    tt = np.arcsin(n1 / n2 * np.sin(ti))
    rs = (np.sin(tt - ti) / np.sin(tt + ti)) ** 2
    rp = (np.tan(tt - ti) / np.tan(tt + ti)) ** 2
    return rs, rp


@pytest.mark.spec("rr-eq2", "rr-eq3")
def test_optics_fresnel_matches_printed_sin_tan_forms():
    th = np.linspace(1.0, 89.0, 89)
    R, rs, rp = pywarp.optics_fresnel(np.cos(np.radians(th)), 1.0, N_W)
    rs64, rp64 = _fresnel64(th, 1.0, N_W)
    np.testing.assert_allclose(rs, rs64, atol=2e-6)
    np.testing.assert_allclose(rp, rp64, atol=2e-6)
    np.testing.assert_allclose(R, 0.5 * (rs64 + rp64), atol=2e-6)
    assert_twins_agree("rr-eq2", np.cos(np.radians(th)), 1.0, N_W)
    assert_twins_agree("rr-eq3", np.cos(np.radians(th)), N_W, 1.0)


@pytest.mark.spec("rr-eq2", "rr-eq3")
def test_optics_fresnel_closed_forms_normal_brewster_grazing():
    for n1, n2 in ((1.0, N_W), (N_W, 1.0), (1.0, 1.5)):
        r0 = ((n2 - n1) / (n2 + n1)) ** 2  # normal incidence, no 0/0
        assert pywarp.optics_fresnel(1.0, n1, n2) == pytest.approx((r0, r0, r0), rel=1e-6)
    # Brewster's angle tan(theta_B) = n2 / n1: Rp = 0
    R, rs, rp = pywarp.optics_fresnel(np.cos(np.arctan(N_W)), 1.0, N_W)
    assert rp == pytest.approx(0.0, abs=1e-7) and rs > 0.03
    # grazing incidence reflects everything
    assert pywarp.optics_fresnel(0.0, 1.0, N_W) == pytest.approx((1.0, 1.0, 1.0), abs=1e-6)
    assert pywarp.optics_fresnel(1e-4, 1.0, N_W)[0] > 0.999
    # equal indices: nothing reflected; the only 0/0 left (grazing at the critical angle) is its limit 1
    assert pywarp.optics_fresnel(0.3, N_W, N_W) == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)
    assert pywarp.optics_fresnel(0.0, N_W, N_W) == (1.0, 1.0, 1.0)


@pytest.mark.spec("rr-eq2", "rr-eq3")
def test_optics_fresnel_catalogue_check_values_and_ten_percent_threshold():
    c = lambda deg: np.cos(np.radians(deg))  # noqa: E731
    assert pywarp.optics_fresnel(c(0.0), 1.0, N_W)[0] == pytest.approx(0.0201, abs=5e-5)
    assert pywarp.optics_fresnel(c(60.0), 1.0, N_W) == pytest.approx((0.0591, 0.1139, 0.0044), abs=5e-5)
    assert pywarp.optics_fresnel(c(67.5), 1.0, N_W) == pytest.approx((0.1065, 0.1837, 0.0293), abs=5e-5)
    assert pywarp.optics_fresnel(c(80.0), 1.0, N_W)[0] == pytest.approx(0.3469, abs=5e-5)
    # the text's "< 10 % below 67.5 deg" is approximate: the unpolarised R reaches 10 % at 66.76 deg
    th = np.linspace(60.0, 70.0, 10001)
    R = pywarp.optics_fresnel(c(th), 1.0, N_W)[0]
    assert th[np.argmax(R >= 0.1)] == pytest.approx(66.76, abs=0.01)


@pytest.mark.spec("rr-eq2", "rr-eq3")
def test_optics_fresnel_total_internal_reflection_and_reciprocity():
    crit = np.degrees(np.arcsin(1 / N_W))
    th = np.array([crit + 0.01, 55.0, 70.0, 90.0])
    R, rs, rp = pywarp.optics_fresnel(np.cos(np.radians(th)), N_W, 1.0)
    np.testing.assert_array_equal(R, 1.0)
    np.testing.assert_array_equal(rs, 1.0)
    np.testing.assert_array_equal(rp, 1.0)
    # Stokes reciprocity: the same reflectance from either side of the interface at conjugate angles
    ti = np.linspace(0.0, 80.0, 17)
    tt = np.degrees(np.arcsin(np.sin(np.radians(ti)) / N_W))
    a = pywarp.optics_fresnel(np.cos(np.radians(ti)), 1.0, N_W)
    b = pywarp.optics_fresnel(np.cos(np.radians(tt)), N_W, 1.0)
    for x, y in zip(a, b):
        np.testing.assert_allclose(x, y, atol=5e-6)


@pytest.mark.spec("rr-der-3.2.1")
def test_optics_drop_fov_printed_chain_is_150_thesis_variant():
    fov, tt, e, x = pywarp.optics_drop_fov(N_W, variant="thesis")
    assert (fov, tt, e, x) == (150.0, 48.0, 6.0, 81.0)  # 90 -> 48 -> 6 -> 81 -> 75 -> 150, as printed
    assert_twins_agree("rr-der-3.2.1", np.linspace(1.0, 2.0, 41), variant="thesis")


@pytest.mark.spec("rr-der-3.2.1")
def test_optics_drop_fov_exact_from_the_critical_angle():
    fov, tt, e, x = pywarp.optics_drop_fov(N_W)
    crit = np.degrees(np.arcsin(1 / N_W))
    assert tt == pytest.approx(crit, abs=2e-5) and tt == pytest.approx(48.75, abs=0.01)
    assert e == pytest.approx(7.51, abs=0.005) and x == 90.0
    assert fov == pytest.approx(165.0, abs=0.02)
    n = np.linspace(1.0, 2.0, 41)
    np.testing.assert_allclose(pywarp.optics_drop_fov(n)[0], 360 - 4 * np.degrees(np.arcsin(1 / n)), atol=1e-4)
    # the exact FOV is the largest deviation through a sphere, doubled: D(b) = 2 (theta_i - theta_t), b in [0, 1]
    b = np.linspace(0, 1, 100001)
    dev = 2 * (np.arcsin(b) - np.arcsin(b / N_W))
    assert 2 * np.degrees(dev.max()) == pytest.approx(fov, abs=0.01)
    assert_twins_agree("rr-der-3.2.1", n)
