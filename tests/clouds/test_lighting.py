"""The cloudscape's lighting from the sky model: the sun through the atmosphere (Preetham et al. 1999 appendix A.1),
ambient and ground light from the sky model (ccl_cloudscape_light), the lit and shadowed ground, aerial perspective,
multiple-scattering octaves and the dual-lobe phase -- C vs Warp, closed forms, properties of the images -- and the
thesis's constant lighting reproduced bit for bit."""
from __future__ import annotations

import math

import numpy as np
import pytest

from pywarp.kernels import sky as S

# --- the sun through the atmosphere ---------------------------------------------------------------------------------


def _attenuation_f64(theta_s, turbidity, lambda_um):
    """Preetham et al. 1999 appendix A.1 (Rayleigh + Angstrom terms) in float64, written from the paper."""
    m = 1.0 / (np.cos(theta_s) + 0.15 * (93.885 - np.degrees(theta_s)) ** -1.253)
    beta = 0.04608365822050 * turbidity - 0.04586025928522
    return m, np.exp(-0.008735 * lambda_um ** -4.08 * m) * np.exp(-beta * lambda_um ** -1.3 * m)


THETAS = np.float32(np.radians([0.0, 30.0, 55.0, 70.0, 80.0, 86.0, 87.0]))


@pytest.mark.parametrize("impl", ["warp", "c"])
@pytest.mark.parametrize("turbidity", [2.0, 2.5, 6.0, 10.0])
def test_sun_attenuation_closed_form(impl, turbidity):
    m, t = S.sun_attenuation(THETAS, turbidity, impl=impl)
    th = THETAS.astype(np.float64)
    for c, lam in enumerate(S.SUN_LAMBDA_UM):
        m_ref, t_ref = _attenuation_f64(th, turbidity, lam)
        # exp(-x), x <= 18 here: relative error x * rel_err(x), rel_err(x) <= ~3e-6 (see cclouds/tests/test_lighting.c)
        x = -np.log(t_ref)
        assert np.all(np.abs(t[:, c] - t_ref) <= (2e-5 + 3e-6 * x) * t_ref), (lam, t[:, c], t_ref)
        np.testing.assert_allclose(m, m_ref, rtol=1e-5)


def test_sun_attenuation_known_values():
    """The values quoted in cclouds/sky.h and cloudscape.c (T = 2.5): zenith, the default 35 deg sun, 4 deg."""
    _, t = S.sun_attenuation(np.float32(np.radians([0.0, 55.0, 86.0])), 2.5)
    np.testing.assert_allclose(t[0], (0.855, 0.778, 0.637), atol=1e-3)
    np.testing.assert_allclose(t[1], (0.762, 0.646, 0.457), atol=1e-3)
    np.testing.assert_allclose(t[2], (0.145, 0.045, 0.0039), atol=1e-3)
    # the default sun_intensity 16 gives the thesis constant's red channel of 12 at the default elevation
    assert abs(16.0 * t[1, 0] - 12.0) < 0.25


def test_sun_reddens_from_zenith_to_horizon():
    th = np.float32(np.linspace(0.0, np.pi / 2, 46))
    th[-1] = S.HALF_PI_F32
    _, t = S.sun_attenuation(th, 2.5)
    assert np.all(t[:, 0] >= t[:, 1]) and np.all(t[:, 1] >= t[:, 2]) and np.all(t > 0) and np.all(t <= 1)
    assert np.all(np.diff(t, axis=0) < 0)  # every channel dims as the sun sinks
    rb = t[:, 0] / t[:, 2]
    assert np.all(np.diff(rb) > 0)  # and the light reddens
    assert rb[0] < 1.4 and rb[-1] > 1e4


def test_sun_attenuation_c_equals_warp():
    """Bit for bit: the same float32 operations in the same order with the same libm (powf, expf, cosf)."""
    th = np.float32(np.linspace(0.0, S.HALF_PI_F32, 200))
    for T in (2.0, 3.7, 10.0):
        mw, tw = S.sun_attenuation(th, T)
        mc, tc = S.sun_attenuation(th, T, impl="c")
        np.testing.assert_array_equal(mw, mc)
        np.testing.assert_array_equal(tw, tc)


@pytest.mark.parametrize("theta_s,turbidity,match", [(-0.1, 2.5, "theta_s"), (1.6, 2.5, "theta_s"),
                                                     (float("nan"), 2.5, "theta_s"), (0.5, 1.9, "turbidity"),
                                                     (0.5, 10.5, "turbidity")])
def test_sun_attenuation_refuses_bad_input(theta_s, turbidity, match):
    with pytest.raises(ValueError, match=match):
        S.sun_attenuation(theta_s, turbidity)
