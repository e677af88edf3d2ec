"""Sky models (vc §2.5, §4.2) -- Warp twins of ``cclouds/sky.h``.

Angles are radians unless the name ends in ``_deg``: ``theta`` is the zenith angle of the view direction, ``gamma``
the angle between the view direction and the sun, ``theta_s`` the zenith angle of the sun. Directions are unit vectors
in a right-handed Y-up world; the sun direction from elevation e and azimuth a (degrees; azimuth 0 = -Z, the look
direction of a default OpenGL camera, 90 = +X) is ``(cos e sin a, sin e, -cos e cos a)``, so ``theta_s = 90 - e``.

Horizon and below: every Perez-type function evaluates ``cos(theta)`` as ``max(cos(theta), 0.01)`` -- the clamp of
Radiance's perezlum.cal/skybright.cal. For the Preetham coefficients of 2 <= T <= 10, exp(B / 0.01) < 2e-6, so rays at
and below the horizon get the horizon limit of the formula and B / cos(theta) never divides by zero (the thesis does
not say what it does there, vc-2.36 note).

For a renderer: :func:`pywarp.clouds.sky.preetham_params` and :func:`pywarp.clouds.sky.gradient_params` (the host
side) validate the per-frame parameters and return the Warp structs :class:`Preetham` / :class:`SkyGradient`; the
per-pixel functions are the ``@wp.func`` :func:`sky_preetham_rgb` (tone-mapped linear RGB, the thesis' frame-buffer
value), :func:`sky_preetham_hdr`, :func:`sky_preetham_xyY` and :func:`sky_gradient_rgb`, all allocation-free, with
the C twins ``ccl_sky_*``.
The registered entries of vc-A28 / vc-A29, :func:`sky_gradient_colour` and :func:`sky_preetham_colour`, are the
element-wise forms: one view direction (``wp.vec3``) and the sky parameters themselves per element, from which each
call derives the per-frame constants (cheap next to the per-pixel work of a NumPy call; a renderer uses the structs).
"""
from __future__ import annotations


import numpy as np
import warp as wp

from ..core.registry import VARIANT, Arg, Option, declare
from . import VARIANT_CORRECTED, VARIANT_THESIS
from .colour import (
    TONEMAP_EXPOSURE,
    colour_srgb_encode,
    colour_tonemap_exp,
    colour_xyY_to_XYZ,
    colour_XYZ_to_linear_srgb,
)

PI = wp.constant(3.14159265358979323846)
HALF_PI = wp.constant(1.57079632679489662)
DEG2RAD = wp.constant(0.0174532925199432958)
COS_THETA_MIN = wp.constant(0.01)  # horizon clamp of cos(theta), see the module docstring

#: Valid turbidity range of the Preetham fits (Preetham et al. 1999 fitted roughly T = 2..10; Zotti, Wilkie &
#: Purgathofer 2007 document the failures outside it, e.g. B_Y > 0 below T = 1.21).
TURBIDITY_RANGE = (2.0, 10.0)

HALF_PI_F32 = float(np.float32(np.pi / 2))  # float32(pi/2) > pi/2: accept it as the horizon
PI_F32 = float(np.float32(np.pi))

vec5 = wp.types.vector(length=5, dtype=wp.float32)


@wp.struct
class Preetham:
    """Per-frame constants of the Preetham sky (the C struct ``ccl_preetham``); build with
    :func:`pywarp.clouds.sky.preetham_params`."""

    perez_Y: vec5  # Perez A..E of the luminance Y (vc-2.42)
    perez_x: vec5  # of the chromaticity x (vc-2.43)
    perez_y: vec5  # of the chromaticity y (vc-2.44)
    zenith_Y: float  # Y_Z [kcd/m^2] (vc-2.39)
    zenith_x: float  # x_z (vc-2.40)
    zenith_y: float  # y_z (vc-2.41)
    factor_Y: float  # Y_Z / F_Y(0, theta_s) (vc-4.2)
    factor_x: float
    factor_y: float
    turbidity: float
    theta_s: float
    exposure: float  # tone-map k (vc-4.5)
    variant: int  # 0 corrected, 1 thesis: applies to vc-2.39, vc-4.4 and vc-4.5


@wp.struct
class SkyGradient:
    """Per-frame constants of the gradient sky (the C struct ``ccl_sky_gradient``); build with
    :func:`pywarp.clouds.sky.gradient_params`."""

    horizon: wp.vec3
    zenith: wp.vec3
    sun: wp.vec3
    sun_exponent: float


# --- Perez-type distributions --------------------------------------------------------------------------------------

@wp.func
def _clamp_cos_theta(cos_theta: float) -> float:
    ct = cos_theta
    if ct < COS_THETA_MIN:
        ct = COS_THETA_MIN
    return ct


@wp.func
def perez_cg(cos_theta: float, gamma: float, cos_gamma: float, A: float, B: float, C: float, D: float,
             E: float) -> float:
    """vc-2.36 from cos(theta), gamma and cos(gamma) (cos(theta) clamped to >= 0.01)."""
    ct = _clamp_cos_theta(cos_theta)
    return (1.0 + A * wp.exp(B / ct)) * (1.0 + C * wp.exp(D * gamma) + E * cos_gamma * cos_gamma)


@wp.func
def _perez_vec(cos_theta: float, gamma: float, cos_gamma: float, c: vec5) -> float:
    return perez_cg(cos_theta, gamma, cos_gamma, c[0], c[1], c[2], c[3], c[4])


_THETA = Arg("theta", "zenith angle of the view direction [rad]; cos(theta) clamped to >= 0.01 at and below the "
             "horizon", lo=0.0, hi=PI_F32)
_GAMMA = Arg("gamma", "angle between the view direction and the sun [rad]", lo=0.0, hi=PI_F32)
_THETA_S = Arg("theta_s", "sun zenith angle [rad]; the Preetham model needs the sun above the horizon", lo=0.0,
               hi=HALF_PI_F32)
_TURBIDITY = Arg("turbidity", "atmospheric turbidity T of the Preetham fits", lo=TURBIDITY_RANGE[0],
                 hi=TURBIDITY_RANGE[1])
# Perez coefficients: any finite value is valid; the contract tests draw them from the range of the Preetham fits
# (|A..E| <= 6; exp(B / 0.01) overflows for B > 0.88, as the formula does)
#: Bound of the Perez coefficients (CCL_SKY_PEREZ_MAX_COEFFICIENT, reasons in cclouds/sky.h): A, C, E in [-1e6, 1e6],
#: B and D in [-1e6, 0], so both factors of F are finite (B = D = 0, C = E = -3.4e38 made 0 x -Inf = NaN).
PEREZ_MAX_COEFFICIENT = 1.0e6
_PEREZ = tuple(Arg(n, f"Perez coefficient {n}" + (" (<= 0: the luminance falls towards the horizon, the glow away from "
                                                   "the sun)" if n in "BD" else ""),
                   lo=-PEREZ_MAX_COEFFICIENT, hi=0.0 if n in "BD" else PEREZ_MAX_COEFFICIENT, sample_range=r)
               for n, r in zip("ABCDE", ((-2.0, 0.0), (-4.0, 0.0), (0.0, 6.0), (-3.0, 0.0), (-0.5, 0.5))))
_YZ = Arg("Y_z", "zenith value of the channel (Y_Z, or x_z / y_z for the chromaticities)")
_PREETHAM_REFS = ("Preetham, Shirley & Smits, A practical analytic model for daylight, SIGGRAPH 1999, appendix A.2",
                  "Zotti, Wilkie & Purgathofer, A critical review of the Preetham skylight model, WSCG 2007")


@declare("vc-2.33", c="ccl_sky_turbidity",
         args=(Arg("t_m", "optical thickness of the purely molecular atmosphere", lo=0.0, lo_open=True,
                   sample_range=(0.01, 10.0)),
               Arg("t_h", "optical thickness of the haze", lo=0.0)),
         outputs=("T",), summary="Turbidity T = (t_m + t_h) / t_m >= 1 (T = 1: pure air).",
         references=("McCartney, Optics of the Atmosphere, 1976", _PREETHAM_REFS[0]))
@wp.func
def sky_turbidity(t_m: float, t_h: float) -> float:
    """vc-2.33: T = (t_m + t_h) / t_m."""
    return (t_m + t_h) / t_m


@wp.func
def _cie_indicatrix(g: float) -> float:
    c = wp.cos(g)
    return 0.91 + 10.0 * wp.exp(-3.0 * g) + 0.45 * c * c


@declare("vc-2.35", c="ccl_sky_cie_clear",
         args=(_THETA, _GAMMA, _THETA_S, Arg("Y_z", "zenith luminance (any unit)")), outputs=("Y",),
         summary="CIE clear-sky luminance Y = Y_z (0.91 + 10 e^(-3 gamma) + 0.45 cos^2 gamma)(1 - e^(-0.32/cos "
                 "theta)) / ((0.91 + 10 e^(-3 theta_s) + 0.45 cos^2 theta_s)(1 - e^(-0.32))). Equals the Perez form "
                 "2.38 with A = -1, B = -0.32, C = 10/0.91, D = -3, E = 0.45/0.91.",
         references=("CIE 1973 standard clear sky (Kittler 1967)", "Radiance skybright.cal (G. Ward)"))
@wp.func
def sky_cie_clear(theta: float, gamma: float, theta_s: float, Y_z: float) -> float:
    """vc-2.35: CIE clear sky Y = Y_z f(gamma) phi(theta) / (f(theta_s) phi(0))."""
    num = _cie_indicatrix(gamma) * (1.0 - wp.exp(-0.32 / _clamp_cos_theta(wp.cos(theta))))
    den = _cie_indicatrix(theta_s) * (1.0 - wp.exp(-0.32))
    return (num / den) * Y_z


@declare("vc-2.36", c="ccl_sky_perez", args=(_THETA, _GAMMA, *_PEREZ), outputs=("F",),
         summary="Perez all-weather relative luminance F = (1 + A e^(B/cos theta))(1 + C e^(D gamma) + E cos^2 "
                 "gamma); cos(theta) is clamped to >= 0.01 (Radiance perezlum.cal) so horizon and below-horizon "
                 "directions get the horizon limit.",
         references=("Perez, Seals & Michalsky, All-weather model for sky luminance distribution, Solar Energy "
                     "50(3), 1993", "Radiance perezlum.cal (G. Ward)"))
@wp.func
def sky_perez(theta: float, gamma: float, A: float, B: float, C: float, D: float, E: float) -> float:
    """vc-2.36: F = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma)."""
    return perez_cg(wp.cos(theta), gamma, wp.cos(gamma), A, B, C, D, E)


@declare("vc-2.37", c="ccl_sky_perez_cie", args=(_THETA, _GAMMA, *_PEREZ), options=(VARIANT,), outputs=("F",),
         summary="CIE-adopted modified Perez function. variant='corrected': indicatrix 1 + C (e^(D gamma) - "
                 "e^(D pi/2)) + E cos^2 gamma (CIE standard general sky, exactly 1 at gamma = pi/2); "
                 "variant='thesis': e^(D gamma pi/2) as printed.",
         references=("CIE S 011/E:2003 Spatial distribution of daylight -- CIE standard general sky",
                     "Darula & Kittler, CIE general sky standard defining luminance distributions, 2002"))
@wp.func
def sky_perez_cie(theta: float, gamma: float, A: float, B: float, C: float, D: float, E: float,
                  variant: int) -> float:
    """vc-2.37: CIE modified Perez; corrected subtracts exp(D pi/2), variant 1 = exp(D gamma pi/2) as printed."""
    ct = _clamp_cos_theta(wp.cos(theta))
    cg = wp.cos(gamma)
    sub = wp.exp(D * HALF_PI)
    if variant == VARIANT_THESIS:
        sub = wp.exp(D * gamma * HALF_PI)
    return (1.0 + A * wp.exp(B / ct)) * (1.0 + C * (wp.exp(D * gamma) - sub) + E * cg * cg)


@declare("vc-4.2", c="ccl_sky_perez_zenith_factor", args=(_THETA_S, _YZ, *_PEREZ), outputs=("factor",),
         summary="Zenith normalisation Y_z / F(0, theta_s), precomputed per channel (Y, x and y, each with its own "
                 "A..E; the text writes it for Y only) and multiplied by F(theta, gamma) per pixel (= 2.38).",
         references=_PREETHAM_REFS[:1])
@wp.func
def sky_perez_zenith_factor(theta_s: float, Y_z: float, A: float, B: float, C: float, D: float, E: float) -> float:
    """vc-4.2: Y_z / F(0, theta_s)."""
    return Y_z / perez_cg(1.0, theta_s, wp.cos(theta_s), A, B, C, D, E)


@declare("vc-2.38", c="ccl_sky_perez_normalized", args=(_THETA, _GAMMA, _THETA_S, _YZ, *_PEREZ), outputs=("Y",),
         summary="Normalised distribution Y = F(theta, gamma) / F(0, theta_s) * Y_z; exactly Y_z at theta = 0, "
                 "gamma = theta_s.",
         references=_PREETHAM_REFS[:1])
@wp.func
def sky_perez_normalized(theta: float, gamma: float, theta_s: float, Y_z: float, A: float, B: float, C: float,
                         D: float, E: float) -> float:
    """vc-2.38: F(theta, gamma) / F(0, theta_s) * Y_z (exactly Y_z at theta = 0, gamma = theta_s)."""
    f = perez_cg(wp.cos(theta), gamma, wp.cos(gamma), A, B, C, D, E)
    f0 = perez_cg(1.0, theta_s, wp.cos(theta_s), A, B, C, D, E)
    return (f / f0) * Y_z


# --- Preetham fits -----------------------------------------------------------------------------------------------------

@wp.func
def _zenith_Y(T: float, theta_s: float, variant: int) -> float:
    k = float(4.0453)
    if variant == VARIANT_THESIS:
        k = float(6.0453)
    chi = (4.0 / 9.0 - T / 120.0) * (PI - 2.0 * theta_s)
    return (k * T - 4.9710) * wp.tan(chi) - 0.2155 * T + 2.4192


@declare("vc-2.40", c="ccl_sky_preetham_zenith_x", args=(_TURBIDITY, _THETA_S), outputs=("x",),
         summary="Preetham zenith chromaticity x_z = [T^2 T 1] M_x [theta_s^3 theta_s^2 theta_s 1]^T.",
         references=_PREETHAM_REFS[:1])
@wp.func
def sky_preetham_zenith_x(turbidity: float, theta_s: float) -> float:
    """vc-2.40: x_z = [T^2 T 1] M_x [theta_s^3 theta_s^2 theta_s 1]^T."""
    T = turbidity
    t = theta_s
    t2 = t * t
    t3 = t2 * t
    r0 = 0.00166 * t3 - 0.00375 * t2 + 0.00209 * t
    r1 = -0.02903 * t3 + 0.06377 * t2 - 0.03202 * t + 0.00394
    r2 = 0.11693 * t3 - 0.21196 * t2 + 0.06052 * t + 0.25886
    return T * T * r0 + T * r1 + r2


@declare("vc-2.41", c="ccl_sky_preetham_zenith_y", args=(_TURBIDITY, _THETA_S), outputs=("y",),
         summary="Preetham zenith chromaticity y_z = [T^2 T 1] M_y [theta_s^3 theta_s^2 theta_s 1]^T.",
         references=_PREETHAM_REFS[:1])
@wp.func
def sky_preetham_zenith_y(turbidity: float, theta_s: float) -> float:
    """vc-2.41: y_z = [T^2 T 1] M_y [theta_s^3 theta_s^2 theta_s 1]^T."""
    T = turbidity
    t = theta_s
    t2 = t * t
    t3 = t2 * t
    r0 = 0.00275 * t3 - 0.00610 * t2 + 0.00317 * t
    r1 = -0.04214 * t3 + 0.08970 * t2 - 0.04153 * t + 0.00516
    r2 = 0.15346 * t3 - 0.26756 * t2 + 0.06670 * t + 0.26688
    return T * T * r0 + T * r1 + r2


@declare("vc-2.39", c="ccl_sky_preetham_zenith", args=(_TURBIDITY, _THETA_S), options=(VARIANT,), outputs=("xyY",),
         summary="Preetham zenith colour in xyY: chromaticities x_z, y_z (2.40, 2.41) and luminance Y_Z [kcd/m^2] "
                 "(2.39). variant='corrected': Y_Z = (4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192 (Preetham); "
                 "variant='thesis': 6.0453 T as printed. chi = (4/9 - T/120)(pi - 2 theta_s).",
         references=_PREETHAM_REFS)
@wp.func
def sky_preetham_zenith(turbidity: float, theta_s: float, variant: int) -> wp.vec3:
    """vc-2.39-2.41: (x_z, y_z, Y_Z [kcd/m^2]); variant 1 = 6.0453 T as printed instead of Preetham's 4.0453 T."""
    return wp.vec3(sky_preetham_zenith_x(turbidity, theta_s), sky_preetham_zenith_y(turbidity, theta_s),
                   _zenith_Y(turbidity, theta_s, variant))


_F5 = tuple[float, float, float, float, float]


@declare("vc-2.42", c="ccl_sky_preetham_perez_Y", args=(_TURBIDITY,), outputs=("A", "B", "C", "D", "E"),
         summary="Preetham's Perez coefficients A..E of the luminance Y, linear in the turbidity T.",
         references=_PREETHAM_REFS[:1])
@wp.func
def sky_preetham_perez_Y(turbidity: float) -> _F5:
    """vc-2.42: Perez A..E of the luminance Y."""
    T = turbidity
    return (0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771,
            -0.0670 * T + 0.3703)


@declare("vc-2.43", c="ccl_sky_preetham_perez_x", args=(_TURBIDITY,), outputs=("A", "B", "C", "D", "E"),
         summary="Preetham's Perez coefficients A..E of the chromaticity x, linear in the turbidity T.",
         references=_PREETHAM_REFS[:1])
@wp.func
def sky_preetham_perez_x(turbidity: float) -> _F5:
    """vc-2.43: Perez A..E of the chromaticity x."""
    T = turbidity
    return (-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989,
            -0.0033 * T + 0.0452)


@declare("vc-2.44", c="ccl_sky_preetham_perez_y", args=(_TURBIDITY,), outputs=("A", "B", "C", "D", "E"),
         summary="Preetham's Perez coefficients A..E of the chromaticity y, linear in the turbidity T.",
         references=_PREETHAM_REFS[:1])
@wp.func
def sky_preetham_perez_y(turbidity: float) -> _F5:
    """vc-2.44: Perez A..E of the chromaticity y."""
    T = turbidity
    return (-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537,
            -0.0109 * T + 0.0529)


# --- per-frame constants and per-direction sky functions ----------------------------------------------------------

@wp.func
def sky_sun_direction(elevation_deg: float, azimuth_deg: float) -> wp.vec3:
    """Unit direction towards the sun: (cos e sin a, sin e, -cos e cos a), Y up, azimuth 0 = -Z, 90 = +X."""
    e = elevation_deg * DEG2RAD
    a = azimuth_deg * DEG2RAD
    ce = wp.cos(e)
    return wp.vec3(ce * wp.sin(a), wp.sin(e), -ce * wp.cos(a))


@wp.func
def sky_preetham_init(turbidity: float, theta_s: float, exposure: float, variant: int) -> Preetham:
    """Per-frame constants (vc-A29 update): 2.42-2.44 -> 2.39-2.41 -> 4.2. No validation (see
    pywarp.clouds.sky.preetham_params)."""
    p = Preetham()
    A, B, C, D, E = sky_preetham_perez_Y(turbidity)
    p.perez_Y = vec5(A, B, C, D, E)
    A, B, C, D, E = sky_preetham_perez_x(turbidity)
    p.perez_x = vec5(A, B, C, D, E)
    A, B, C, D, E = sky_preetham_perez_y(turbidity)
    p.perez_y = vec5(A, B, C, D, E)
    z = sky_preetham_zenith(turbidity, theta_s, variant)
    zx = z[0]
    zy = z[1]
    zY = z[2]
    p.zenith_Y = zY
    p.zenith_x = zx
    p.zenith_y = zy
    cY = p.perez_Y
    cx = p.perez_x
    cy = p.perez_y
    p.factor_Y = sky_perez_zenith_factor(theta_s, zY, cY[0], cY[1], cY[2], cY[3], cY[4])
    p.factor_x = sky_perez_zenith_factor(theta_s, zx, cx[0], cx[1], cx[2], cx[3], cx[4])
    p.factor_y = sky_perez_zenith_factor(theta_s, zy, cy[0], cy[1], cy[2], cy[3], cy[4])
    p.turbidity = turbidity
    p.theta_s = theta_s
    p.exposure = exposure
    p.variant = variant
    return p


@wp.func
def sky_preetham_xyY(d: wp.vec3, sun: wp.vec3, p: Preetham) -> wp.vec3:
    """Preetham sky (vc-A29) in xyY for unit view direction d and unit sun direction: returns (x, y, Y)."""
    cos_g = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2]
    if cos_g > 1.0:
        cos_g = 1.0
    if cos_g < -1.0:
        cos_g = -1.0
    gamma = wp.acos(cos_g)
    x = p.factor_x * _perez_vec(d[1], gamma, cos_g, p.perez_x)
    y = p.factor_y * _perez_vec(d[1], gamma, cos_g, p.perez_y)
    Y = p.factor_Y * _perez_vec(d[1], gamma, cos_g, p.perez_Y)
    return wp.vec3(x, y, Y)


@wp.func
def sky_preetham_hdr(d: wp.vec3, sun: wp.vec3, p: Preetham) -> wp.vec3:
    """Preetham sky (vc-A29) as linear sRGB before the tone map: xyY -> XYZ (4.3) -> RGB (4.4)."""
    return colour_XYZ_to_linear_srgb(colour_xyY_to_XYZ(sky_preetham_xyY(d, sun, p)), p.variant)


@wp.func
def sky_preetham_rgb(d: wp.vec3, sun: wp.vec3, p: Preetham) -> wp.vec3:
    """Preetham sky (vc-A29) as the thesis writes it to the frame buffer: HDR RGB, tone map 4.5 per channel.
    Linear (apply colour_srgb_encode for display), not clamped. The corrected variant first clips a negative channel
    (a colour outside the sRGB gamut, e.g. the horizon's blue under a setting sun) to 0: 1 - exp(-k C) of a negative C
    is negative and reaches -Inf for a large exposure k (twin of ``ccl_sky_preetham_rgb``)."""
    c = sky_preetham_hdr(d, sun, p)
    if p.variant == VARIANT_CORRECTED:
        c = wp.vec3(wp.where(c[0] < 0.0, 0.0, c[0]), wp.where(c[1] < 0.0, 0.0, c[1]),
                    wp.where(c[2] < 0.0, 0.0, c[2]))  # (a NaN stays NaN)
    return wp.vec3(colour_tonemap_exp(c[0], p.exposure, p.variant), colour_tonemap_exp(c[1], p.exposure, p.variant),
                   colour_tonemap_exp(c[2], p.exposure, p.variant))


@wp.func
def sky_gradient_rgb(d: wp.vec3, sun: wp.vec3, g: SkyGradient) -> wp.vec3:
    """Gradient sky (vc-A28): lerp(horizon, zenith, clamp(d_y, 0, 1)) + sun * max(d . sun, 0)^sun_exponent."""
    t = d[1]
    if t < 0.0:
        t = 0.0
    if t > 1.0:
        t = 1.0
    c = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2]
    # The dot of two unit vectors can round to 1 + 2^-23; c^n then overflows for n above ~7e8: clamp to [0, 1].
    if c < 0.0:
        c = 0.0
    if c > 1.0:
        c = 1.0
    s = wp.pow(c, g.sun_exponent)
    return wp.vec3(g.horizon[0] + t * (g.zenith[0] - g.horizon[0]) + g.sun[0] * s,
                   g.horizon[1] + t * (g.zenith[1] - g.horizon[1]) + g.sun[1] * s,
                   g.horizon[2] + t * (g.zenith[2] - g.horizon[2]) + g.sun[2] * s)


@wp.func
def _normalize3(d: wp.vec3) -> wp.vec3:
    """d / |d| with the operations of the C twin."""
    length = wp.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
    return wp.vec3(d[0] / length, d[1] / length, d[2] / length)


@wp.func
def _srgb_encode3(c: wp.vec3) -> wp.vec3:
    return wp.vec3(colour_srgb_encode(c[0]), colour_srgb_encode(c[1]), colour_srgb_encode(c[2]))


_DIRECTION = Arg("direction", "view direction, Y up (any non-zero length; normalised here)", nonzero=True,
                 sample_range=(-1.0, 1.0))
_SUN_ELEV_PREETHAM = Arg("sun_elevation_deg", "sun elevation above the horizon [deg]; the Preetham model needs the "
                         "sun above the horizon (theta_s = 90 - elevation <= 90 deg)", lo=0.0, hi=90.0)
_SUN_ELEV = Arg("sun_elevation_deg", "sun elevation above the horizon [deg]", lo=-90.0, hi=90.0)
_SUN_AZ = Arg("sun_azimuth_deg", "sun azimuth [deg], 0 = -Z (ahead of a default OpenGL camera), 90 = +X",
              default=0.0, sample_range=(-360.0, 360.0))
_EXPOSURE = Arg("exposure", "tone-map exposure k of vc-4.5 (> 0); 0.03 = the thesis' constant", lo=0.0,
                lo_open=True, default=TONEMAP_EXPOSURE, sample_range=(0.001, 1.0))
_OUTPUT_PREETHAM = Option("output", {"tonemapped": 0, "hdr": 1, "xyY": 2, "srgb": 3}, "tonemapped",
                          "'tonemapped' (default): the thesis' frame-buffer value, linear RGB after the tone map 4.5; "
                          "'hdr': linear sRGB before the tone map (4.4); 'xyY': the Perez stage, (x, y, Y); "
                          "'srgb': tonemapped and sRGB-encoded (IEC 61966-2-1) for display")
_OUTPUT_GRADIENT = Option("output", {"linear": 0, "srgb": 1}, "linear",
                          "'linear' (default): the colour as the thesis writes it; 'srgb': sRGB-encoded for display")

#: Defaults of the gradient sky (vc-A28; the thesis names only "a light and a dark shade of blue" and "a sun colour").
#: Linear RGB, the same space as the tone-mapped Preetham output, so the two models are interchangeable in the render
#: chain. Horizon: light sky blue, sRGB-encoded (0.84, 0.90, 0.97); zenith: medium-dark blue, sRGB (0.44, 0.62, 0.87);
#: sun: warm white; exponent 64: the glow falls to half at 8.4 deg from the sun (cos^64 = 0.5), a visible halo at
#: camera fields of view of 45-90 deg (a disc of the true 0.27 deg radius would need n ~ 10^5 and vanish between
#: pixels).
GRADIENT_DEFAULTS = {
    "horizon_colour": (0.66, 0.78, 0.94),
    "zenith_colour": (0.16, 0.34, 0.72),
    "sun_colour": (1.0, 0.9, 0.7),
    "sun_exponent": 64.0,
}


@declare("vc-A29", c="ccl_sky_preetham_colour",
         nonfinite="variant='thesis' (the printed tone-map sign of vc-4.5) overflows to -inf for bright skies",
         args=(_DIRECTION, _TURBIDITY, _SUN_ELEV_PREETHAM, _SUN_AZ, _EXPOSURE),
         options=(VARIANT, _OUTPUT_PREETHAM), outputs=("colour",),
         summary="Preetham sky per view direction: theta = acos(d_y), gamma = angle to the sun -> Perez 2.36 for Y, "
                 "x, y x the zenith factors 4.2 (= 2.38) -> xyY -> XYZ (4.3) -> linear sRGB (4.4) -> tone map (4.5). "
                 "variant applies to all three errata (2.39 6.0453, 4.4 -0.9392660, 4.5 sign). Below-horizon "
                 "directions: cos(theta) clamped to 0.01 (horizon limit). output='srgb' adds the IEC 61966-2-1 sRGB "
                 "encoding (colour_srgb_encode), the display step of the render chain. Element-wise: the per-frame "
                 "constants are derived per call; a renderer uses @wp.func sky_preetham_rgb(d, sun, Preetham) with "
                 "pywarp.clouds.sky.preetham_params(...) / ccl_sky_preetham_rgb with ccl_sky_preetham_init(...).",
         references=(*_PREETHAM_REFS, "IEC 61966-2-1:1999 (sRGB transfer function)"))
@wp.func
def sky_preetham_colour(direction: wp.vec3, turbidity: float, sun_elevation_deg: float, sun_azimuth_deg: float,
                        exposure: float, variant: int, output: int) -> wp.vec3:
    """vc-A29 for one direction: per-frame constants from the parameters, then the per-pixel chain."""
    theta_s = (90.0 - sun_elevation_deg) * DEG2RAD
    p = sky_preetham_init(turbidity, theta_s, exposure, variant)
    sun = sky_sun_direction(sun_elevation_deg, sun_azimuth_deg)
    d = _normalize3(direction)
    if output == 2:
        return sky_preetham_xyY(d, sun, p)
    if output == 1:
        return sky_preetham_hdr(d, sun, p)
    if output == 3:
        return _srgb_encode3(sky_preetham_rgb(d, sun, p))
    return sky_preetham_rgb(d, sun, p)


#: Largest colour component of the gradient sky (CCL_SKY_GRADIENT_MAX_COLOUR, reasons in cclouds/sky.h): the
#: cloudscape's sky lighting sums the sky over a hemisphere, and a horizon of 1e37 overflowed those sums (NaN pixels).
GRADIENT_MAX_COLOUR = 1.0e6


def _colour_arg(name, doc):
    return Arg(name, f"{doc} (linear RGB, components in [0, 1e6]), default {GRADIENT_DEFAULTS[name]}", lo=0.0,
               hi=GRADIENT_MAX_COLOUR, default=GRADIENT_DEFAULTS[name], sample_range=(0.0, 2.0))


@declare("vc-A28", c="ccl_sky_gradient_colour",
         args=(_DIRECTION, _SUN_ELEV, _SUN_AZ, _colour_arg("horizon_colour", "colour at and below the horizon"),
               _colour_arg("zenith_colour", "colour at the zenith"),
               _colour_arg("sun_colour", "colour added at the sun"),
               Arg("sun_exponent", "n of max(cos gamma, 0)^n; default 64 = half intensity at 8.4 deg", lo=0.0,
                   lo_open=True, default=GRADIENT_DEFAULTS["sun_exponent"], sample_range=(1.0, 256.0))),
         options=(_OUTPUT_GRADIENT,), outputs=("colour",),
         summary="Gradient sky: lerp(horizon_colour, zenith_colour, clamp(d_y, 0, 1)) + sun_colour max(d . s, 0)^n, "
                 "the sun direction s from its elevation and azimuth in degrees. The thesis gives no colours: the "
                 "defaults (pywarp.kernels.sky.GRADIENT_DEFAULTS) are a light and a medium-dark blue in the "
                 "tone-mapped linear space of the Preetham sky, a warm white sun and n = 64. Element-wise; a renderer "
                 "uses @wp.func sky_gradient_rgb(d, sun, SkyGradient) / ccl_sky_gradient_rgb.",
         references=("Spec vc-A28 (thesis §4.2.1)",))
@wp.func
def sky_gradient_colour(direction: wp.vec3, sun_elevation_deg: float, sun_azimuth_deg: float,
                        horizon_colour: wp.vec3, zenith_colour: wp.vec3, sun_colour: wp.vec3, sun_exponent: float,
                        output: int) -> wp.vec3:
    """vc-A28 for one direction, from the sky parameters."""
    g = SkyGradient()
    g.horizon = horizon_colour
    g.zenith = zenith_colour
    g.sun = sun_colour
    g.sun_exponent = sun_exponent
    c = sky_gradient_rgb(_normalize3(direction), sky_sun_direction(sun_elevation_deg, sun_azimuth_deg), g)
    if output == 1:
        return _srgb_encode3(c)
    return c


# --- the kernels of the host-side struct builders (pywarp.clouds.sky) and the unit sun vector -----------------------

@wp.kernel
def _k_preetham_init(turbidity: float, theta_s: float, exposure: float, variant: int,
                     out: wp.array(dtype=Preetham)):
    # builds the struct of pywarp.clouds.sky.preetham_params (a struct-valued helper, not a registry entry)
    out[0] = sky_preetham_init(turbidity, theta_s, exposure, variant)


@wp.kernel
def _k_sun_direction(elevation_deg: float, azimuth_deg: float, out: wp.array(dtype=wp.vec3)):
    # one sun vector for sun_direction (a helper, not a registry entry)
    out[0] = sky_sun_direction(elevation_deg, azimuth_deg)


def _scalar(arg: Arg, value) -> float:
    a = arg.check(value)
    if a.ndim != 0:
        raise ValueError(f"{arg.name} must be a scalar (a per-frame constant), got an array of shape {a.shape}")
    return float(a)


def sun_direction(elevation_deg, azimuth_deg=0.0, impl: str = "warp", device: str | None = None) -> np.ndarray:
    """The unit sun direction (float32 array of 3) of ``sky_sun_direction`` / ``ccl_sky_sun_direction``."""
    e = _scalar(_SUN_ELEV, elevation_deg)
    a = _scalar(_SUN_AZ, azimuth_deg)
    if impl == "c":
        from ..core.binding import lib

        s = lib().ccl_sky_sun_direction(e, a)
        return np.array([s.x, s.y, s.z], dtype=np.float32)
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    from ..core.runtime import resolve_device

    dev = resolve_device(device)
    out = wp.empty(1, dtype=wp.vec3, device=dev)
    wp.launch(_k_sun_direction, dim=1, inputs=[e, a], outputs=[out], device=dev)
    return out.numpy()[0].astype(np.float32)


# --- the sun through the atmosphere (Preetham et al. 1999, appendix A.1; twins of ccl_sky_relative_air_mass and
# ccl_sky_sun_attenuation, see cclouds/sky.h: Rayleigh and Angstrom aerosol terms at three wavelengths, the ozone,
# water-vapour and mixed-gas bands omitted) ------------------------------------------------------------------------

#: Wavelengths [micrometres] of the R, G, B channels of sky_sun_attenuation (CCL_SKY_SUN_LAMBDA_*_UM).
SUN_LAMBDA_UM = (0.680, 0.550, 0.440)
_SUN_LAMBDA_R = wp.constant(0.680)
_SUN_LAMBDA_G = wp.constant(0.550)
_SUN_LAMBDA_B = wp.constant(0.440)


@wp.func
def sky_relative_air_mass(theta_s: float) -> float:
    """Kasten's relative air mass as Preetham's appendix A.1: 1 / (cos theta_s + 0.15 (93.885 - theta_s_deg)^-1.253).
    theta_s [rad] in [0, pi/2]; 0.9995 at the zenith, ~36.5 at the horizon."""
    return 1.0 / (wp.cos(theta_s) + 0.15 * wp.pow(93.885 - theta_s * 57.2957795, -1.253))


@wp.func
def _sun_transmittance(lambda_um: float, m: float, beta: float) -> float:
    rayleigh = wp.exp(-(0.008735 * wp.pow(lambda_um, -4.08)) * m)
    aerosol = wp.exp(-(beta * wp.pow(lambda_um, -1.3)) * m)
    return rayleigh * aerosol


@wp.func
def sky_sun_attenuation(theta_s: float, turbidity: float) -> wp.vec3:
    """Transmittance towards the sun at 0.680 / 0.550 / 0.440 um: exp(-0.008735 lambda^-4.08 m) exp(-beta lambda^-1.3
    m), beta = 0.04608365822050 T - 0.04586025928522 (Preetham et al. 1999 appendix A.1). theta_s in [0, pi/2],
    turbidity in [2, 10]."""
    m = sky_relative_air_mass(theta_s)
    beta = 0.04608365822050 * turbidity - 0.04586025928522  # Angstrom turbidity, alpha = 1.3
    return wp.vec3(_sun_transmittance(_SUN_LAMBDA_R, m, beta), _sun_transmittance(_SUN_LAMBDA_G, m, beta),
                   _sun_transmittance(_SUN_LAMBDA_B, m, beta))


@wp.kernel
def _k_sun_attenuation(theta_s: wp.array(dtype=float), turbidity: wp.array(dtype=float),
                       out_m: wp.array(dtype=float), out_t: wp.array(dtype=wp.vec3)):
    # element-wise kernel of pywarp.clouds.sky.sun_attenuation (no catalogue ID: Preetham's appendix, not the thesis)
    i = wp.tid()
    out_m[i] = sky_relative_air_mass(theta_s[i])
    out_t[i] = sky_sun_attenuation(theta_s[i], turbidity[i])
