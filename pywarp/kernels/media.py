"""Participating media (vc §2.1, §2.2, §2.5) -- Warp twins of ``cclouds/media.h``.

Conventions: coefficients ``sigma_a`` (absorption), ``sigma_s`` (scattering), ``sigma_t = sigma_a + sigma_s``
(extinction) in inverse length, >= 0; radiances ``L``, ``L_e``, ``L_i`` >= 0; optical depth ``tau`` dimensionless.
The ``*_derivative`` functions are the right-hand sides dL/dx of the ODEs vc-2.1 .. 2.4, 2.9, 2.10 along the ray.

Sampled rays (vc-2.8, 2.17, 2.18, 2.34) are not element-wise: their Warp twins take 2-D arrays ``[rays, samples]``
and a row index, march one ray per thread, and are evaluated through the custom evaluators of
:mod:`pywarp.clouds.media` (``make_warp``/``make_c``): sample arrays of shape ``(..., n)`` give one result per ray,
shape ``(...)``. Integrals are left Riemann sums over the samples ``x_k = x + k dt omega``, ``k = 0 .. n-1`` (first
order in ``dt``).
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.registry import VARIANT, Arg, declare
from . import VARIANT_THESIS

TWO_PI = wp.constant(6.28318530717958647692)  # 2 pi
#: Largest coefficient, radiance, flux, sample or step (CCL_MEDIA_MAX_VALUE, reasons in cclouds/media.h): products,
#: source terms times dt and their sums over any number of samples stay finite (~1e25 gave Inf x 0 = NaN).
MAX_VALUE = 1.0e9


# --- scalar twins (element-wise; the evaluation kernels are generated) ---------------------------------------------

_REFS_PBR = ("Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed., ch. 11 and 14",)


def _coef(name, doc):
    return Arg(name, doc + " [m^-1], in [0, 1e9]", lo=0.0, hi=MAX_VALUE)


_SIGMA_A = _coef("sigma_a", "absorption coefficient sigma_a(x)")
_SIGMA_S = _coef("sigma_s", "scattering coefficient sigma_s(x)")
_SIGMA_T = _coef("sigma_t", "extinction coefficient sigma_t(x) = sigma_a + sigma_s")
_L = Arg("L", "radiance L(x, omega) >= 0", lo=0.0, hi=MAX_VALUE)
_L_E = Arg("L_e", "emitted radiance L_e(x, omega) >= 0", lo=0.0, hi=MAX_VALUE)
_L_I = Arg("L_i", "in-scattered radiance L_i(x, omega) = int p L domega_i >= 0", lo=0.0, hi=MAX_VALUE)
_TAU = Arg("optical_depth", "optical depth tau = int_0^l sigma_t dx (dimensionless) >= 0", lo=0.0)


@declare("vc-2.1", c="ccl_media_absorption_derivative", args=(_SIGMA_A, _L), outputs=("dL_dx",),
         summary="Radiance loss by absorption, the ODE right-hand side dL/dx = -sigma_a L.", references=_REFS_PBR)
@wp.func
def media_absorption_derivative(sigma_a: float, L: float) -> float:
    """vc-2.1: dL/dx = -sigma_a L."""
    return -sigma_a * L


@declare("vc-2.2", c="ccl_media_outscattering_derivative", args=(_SIGMA_S, _L), outputs=("dL_dx",),
         summary="Radiance loss by out-scattering, dL/dx = -sigma_s L (sigma_s read as sigma_s(x)).",
         references=_REFS_PBR)
@wp.func
def media_outscattering_derivative(sigma_s: float, L: float) -> float:
    """vc-2.2: dL/dx = -sigma_s L."""
    return -sigma_s * L


@declare("vc-2.3", c="ccl_media_extinction_derivative", args=(_SIGMA_A, _SIGMA_S, _L), outputs=("dL_dx",),
         summary="Radiance loss by extinction, dL/dx = -sigma_t L with sigma_t = sigma_a + sigma_s.",
         references=_REFS_PBR)
@wp.func
def media_extinction_derivative(sigma_a: float, sigma_s: float, L: float) -> float:
    """vc-2.3: dL/dx = -sigma_t L with sigma_t = sigma_a + sigma_s."""
    return -(sigma_a + sigma_s) * L


@declare("vc-2.4", c="ccl_media_flux_derivative",
         args=(_SIGMA_T, Arg("phi", "radiant flux Phi(x) [W] >= 0", lo=0.0, hi=MAX_VALUE)), outputs=("dphi_dx",),
         summary="Beer-Lambert law in differential flux form, dPhi/dx = -sigma_t Phi.", references=_REFS_PBR)
@wp.func
def media_flux_derivative(sigma_t: float, phi: float) -> float:
    """vc-2.4: dPhi/dx = -sigma_t Phi (Beer-Lambert, differential form)."""
    return -sigma_t * phi


@declare("vc-2.5", c="ccl_media_slab_flux",
         args=(Arg("phi_i", "flux entering the slab Phi_i [W] >= 0", lo=0.0, hi=MAX_VALUE), _TAU), outputs=("phi_o",),
         summary="Flux leaving a slab, Phi_o = Phi_i exp(-tau); tau = sigma_t l for a homogeneous slab of thickness "
                 "l, media_optical_thickness (vc-2.34) of sigma_t for a sampled one.", references=_REFS_PBR)
@wp.func
def media_slab_flux(phi_i: float, optical_depth: float) -> float:
    """vc-2.5: Phi_o = Phi_i exp(-tau), tau = int_0^l sigma_t dx."""
    return phi_i * wp.exp(-optical_depth)


@declare("vc-2.6", c="ccl_media_transmittance", args=(_TAU,), outputs=("T",),
         summary="Beer-Lambert transmittance T = exp(-tau), in (0, 1].", references=_REFS_PBR)
@wp.func
def media_transmittance(optical_depth: float) -> float:
    """vc-2.6: T = exp(-tau)."""
    return wp.exp(-optical_depth)


@declare("vc-2.7", c="ccl_media_transmittance_compose",
         args=(Arg("t_a", "T(x, x'), transmittance of the first segment", lo=0.0, hi=1.0),
               Arg("t_b", "T(x', x''), transmittance of the second segment (x' between x and x'')", lo=0.0, hi=1.0)),
         options=(VARIANT,), outputs=("T",),
         summary="Transmittance of two consecutive segments. variant='corrected': the product T(x,x') T(x',x'') "
                 "(optical depths add); variant='thesis': the printed sum, which exceeds 1 (0.8 + 0.8 = 1.6).",
         references=_REFS_PBR)
@wp.func
def media_transmittance_compose(t_a: float, t_b: float, variant: int) -> float:
    """vc-2.7: T(x, x'') = T(x, x') T(x', x''); variant 1 = the printed sum T(x, x') + T(x', x'')."""
    if variant == VARIANT_THESIS:
        return t_a + t_b
    return t_a * t_b


@declare("vc-2.9", c="ccl_media_gain_derivative", args=(_SIGMA_A, _SIGMA_S, _L_E, _L_I), outputs=("dL_dx",),
         summary="Radiance gain by emission and in-scattering, dL/dx = sigma_a L_e + sigma_s L_i (L_i given).",
         references=_REFS_PBR)
@wp.func
def media_gain_derivative(sigma_a: float, sigma_s: float, L_e: float, L_i: float) -> float:
    """vc-2.9: dL/dx = sigma_a L_e + sigma_s L_i."""
    return sigma_a * L_e + sigma_s * L_i


@declare("vc-2.10", c="ccl_media_rte_derivative", args=(_SIGMA_A, _SIGMA_S, _L_E, _L_I, _L), outputs=("dL_dx",),
         summary="Radiative transfer equation, dL/dx = sigma_a L_e + sigma_s L_i - (sigma_a + sigma_s) L "
                 "(L_i given).", references=_REFS_PBR)
@wp.func
def media_rte_derivative(sigma_a: float, sigma_s: float, L_e: float, L_i: float, L: float) -> float:
    """vc-2.10: dL/dx = sigma_a L_e + sigma_s L_i - (sigma_a + sigma_s) L."""
    return (sigma_a * L_e + sigma_s * L_i) - (sigma_a + sigma_s) * L


# --- the sampled-ray entries' calling convention (their evaluators: pywarp.clouds.media) ------------------------------
# Calling convention: the registered ``args`` are the sample arrays (shape (..., n), broadcast together) followed by
# the per-ray arguments (broadcast to (...)); the Warp kernel takes them as 2-D / 1-D arrays in that order, then the
# options, then the output; the C function takes (sample pointers..., n, per-ray scalars..., options..., out pointer).

def _check_phase_nodes(n, **_):
    if n < 3 or n % 2 == 0:
        raise ValueError(f"p must hold an odd number >= 3 of samples along its last axis (Simpson nodes), got {n}")


def _check_raymarch(sigma_t, sigma_s, **_):
    bad = sigma_s > sigma_t
    if np.any(bad):
        r, k = np.argwhere(bad)[0]
        raise ValueError(f"sigma_s must be <= sigma_t (sigma_t = sigma_a + sigma_s), got sigma_s = "
                         f"{sigma_s[r, k].item()!r} > sigma_t = {sigma_t[r, k].item()!r} at sample {k}")


_DT = Arg("dt", "step length Delta t between samples (path length s = n dt) >= 0", lo=0.0, hi=MAX_VALUE)
_L_BG = Arg("L_bg", "radiance of the surface behind the medium L(x_s) >= 0", lo=0.0, hi=MAX_VALUE)
_SAMPLES = "samples along the ray on the last axis, in [0, 1e9]"
_P_NODES = Arg("p", "phase function p(mu) [sr^-1] >= 0 at the n (odd, >= 3) uniform nodes mu_i = -1 + 2 i/(n-1) on "
                    "the last axis", lo=0.0, hi=MAX_VALUE)
# The sampled-ray entries below are not element-wise (a sum over the sample axis of each ray): their evaluators are
# pywarp.clouds.media's.
_ROWS = {"make_warp": "pywarp.clouds.media:rows_warp", "make_c": "pywarp.clouds.media:rows_c"}


# --- sampled-ray twins (one row of a [rays, samples] array) -----------------------------------------------------------

@declare("vc-2.8", c="ccl_media_phase_integral", args=(_P_NODES,), outputs=("integral",),
         check=_check_phase_nodes, extra={"n_sample_args": 1}, **_ROWS,
         summary="Normalization check of a rotationally symmetric phase function: int_sphere p domega = 2 pi "
                 "int_{-1}^1 p(mu) dmu by composite Simpson on tabulated values; 1 for a normalized phase function.",
         references=_REFS_PBR)
@wp.func
def media_phase_integral(p: wp.array2d(dtype=float), row: int) -> float:
    """vc-2.8: 2 pi int_{-1}^{1} p(mu) dmu by composite Simpson over the n (odd) uniform nodes of row ``row``."""
    n = p.shape[1]
    s = p[row, 0] + p[row, n - 1]
    for i in range(1, n - 1):
        w = float(2.0)
        if i % 2 == 1:
            w = 4.0
        s = s + w * p[row, i]
    h = 2.0 / float(n - 1)
    return TWO_PI * s * h / 3.0


@declare("vc-2.14", c="ccl_media_phase_asymmetry", args=(_P_NODES,), outputs=("g",),
         check=_check_phase_nodes, extra={"n_sample_args": 1}, **_ROWS,
         summary="Asymmetry parameter (mean cosine) g = int p cos(theta) domega of a tabulated phase function, by the "
                 "Simpson rule of vc-2.8; fits an HG lobe (vc-2.13) to a complex phase function.",
         references=_REFS_PBR + ("Henyey & Greenstein, ApJ 93:70-83, 1941",))
@wp.func
def media_phase_asymmetry(p: wp.array2d(dtype=float), row: int) -> float:
    """vc-2.14: g = 2 pi int_{-1}^{1} p(mu) mu dmu, the Simpson rule of :func:`media_phase_integral`."""
    n = p.shape[1]
    h = 2.0 / float(n - 1)
    s = -p[row, 0] + p[row, n - 1]
    for i in range(1, n - 1):
        w = float(2.0)
        if i % 2 == 1:
            w = 4.0
        mu = -1.0 + float(i) * h
        s = s + w * (p[row, i] * mu)
    return TWO_PI * s * h / 3.0


@declare("vc-2.17", c="ccl_media_volume_render",
         args=(Arg("sigma_a", "absorption coefficient, " + _SAMPLES, lo=0.0, hi=MAX_VALUE),
               Arg("sigma_s", "scattering coefficient, " + _SAMPLES, lo=0.0, hi=MAX_VALUE),
               Arg("L_e", "emitted radiance, " + _SAMPLES, lo=0.0, hi=MAX_VALUE),
               Arg("L_i", "in-scattered radiance, " + _SAMPLES, lo=0.0, hi=MAX_VALUE), _DT, _L_BG),
         options=(VARIANT,), outputs=("L",), extra={"n_sample_args": 4}, **_ROWS,
         summary="Volume rendering equation (emission + single scattering) along sampled rays, left Riemann sum: "
                 "T(x,x_s) L_bg + sum_k T(x,x_k) (sigma_a L_e + sigma_s L_i)(x_k) dt with sigma_t = sigma_a + "
                 "sigma_s. variant='corrected': integrands at x_k; variant='thesis': sigma_a, L_e, L_i at x "
                 "(sample 0) as printed.",
         references=_REFS_PBR + ("Max, Optical models for direct volume rendering, IEEE TVCG 1(2), 1995",))
@wp.func
def media_volume_render(sigma_a: wp.array2d(dtype=float), sigma_s: wp.array2d(dtype=float),
                        L_e: wp.array2d(dtype=float), L_i: wp.array2d(dtype=float), row: int, dt: float,
                        L_bg: float, variant: int) -> float:
    """vc-2.17: T(x, x_s) L_bg + sum_k T(x, x_k) (sigma_a L_e + sigma_s L_i)(x_k) dt; variant 1 takes sigma_a, L_e,
    L_i at x (sample 0) as printed."""
    n = sigma_a.shape[1]
    tau = float(0.0)
    L = float(0.0)
    for k in range(n):
        j = k
        if variant == VARIANT_THESIS:
            j = 0
        source = sigma_a[row, j] * L_e[row, j] + sigma_s[row, k] * L_i[row, j]
        L = L + wp.exp(-tau) * source * dt
        tau = tau + (sigma_a[row, k] + sigma_s[row, k]) * dt
    return wp.exp(-tau) * L_bg + L


@declare("vc-2.18", c="ccl_media_raymarch",
         args=(Arg("sigma_t", "extinction coefficient, " + _SAMPLES, lo=0.0, hi=MAX_VALUE),
               Arg("sigma_s", "scattering coefficient (<= sigma_t), " + _SAMPLES, lo=0.0, hi=MAX_VALUE),
               Arg("L_i", "in-scattered radiance, " + _SAMPLES, lo=0.0, hi=MAX_VALUE), _DT, _L_BG),
         options=(VARIANT,), outputs=("L",), check=_check_raymarch, extra={"n_sample_args": 3}, **_ROWS,
         summary="Raymarching approximation (Riemann sum, no emission): T(x,x_s) L_bg + sum_k T(x,x_k) sigma_s(x_k) "
                 "L_i(x_k) dt. variant='corrected': L_i at x_k; variant='thesis': L_i at x (sample 0) as printed.",
         references=_REFS_PBR)
@wp.func
def media_raymarch(sigma_t: wp.array2d(dtype=float), sigma_s: wp.array2d(dtype=float), L_i: wp.array2d(dtype=float),
                   row: int, dt: float, L_bg: float, variant: int) -> float:
    """vc-2.18: T(x, x_s) L_bg + sum_k T(x, x_k) sigma_s(x_k) L_i(x_k) dt; variant 1 takes L_i at x as printed."""
    n = sigma_t.shape[1]
    tau = float(0.0)
    L = float(0.0)
    for k in range(n):
        j = k
        if variant == VARIANT_THESIS:
            j = 0
        L = L + wp.exp(-tau) * sigma_s[row, k] * L_i[row, j] * dt
        tau = tau + sigma_t[row, k] * dt
    return wp.exp(-tau) * L_bg + L


@declare("vc-2.34", c="ccl_media_optical_thickness",
         args=(Arg("sigma", "attenuation coefficient to integrate (sigma_t for Beer-Lambert; the text prints "
                            "sigma_s), " + _SAMPLES, lo=0.0, hi=MAX_VALUE), _DT),
         outputs=("tau",), extra={"n_sample_args": 1}, **_ROWS,
         summary="Optical thickness of a sampled path, tau = sum_k sigma(x_k) dt (left Riemann sum of int_0^s sigma "
                 "dx). The text integrates sigma_s; the general definition sigma_t: pass the coefficient you mean.",
         references=_REFS_PBR)
@wp.func
def media_optical_thickness(sigma: wp.array2d(dtype=float), row: int, dt: float) -> float:
    """vc-2.34: tau = sum_k sigma(x_k) dt (left Riemann sum of int_0^s sigma dx)."""
    tau = float(0.0)
    for k in range(sigma.shape[1]):
        tau = tau + sigma[row, k] * dt
    return tau


# --- per-ray kernels: 2-D sample arrays, then 1-D per-ray arrays, then options, then outputs --------------------------

@wp.kernel
def _rows_media_phase_integral(p: wp.array2d(dtype=float), out: wp.array(dtype=float)):
    r = wp.tid()
    out[r] = media_phase_integral(p, r)


@wp.kernel
def _rows_media_phase_asymmetry(p: wp.array2d(dtype=float), out: wp.array(dtype=float)):
    r = wp.tid()
    out[r] = media_phase_asymmetry(p, r)


@wp.kernel
def _rows_media_volume_render(sigma_a: wp.array2d(dtype=float), sigma_s: wp.array2d(dtype=float),
                              L_e: wp.array2d(dtype=float), L_i: wp.array2d(dtype=float), dt: wp.array(dtype=float),
                              L_bg: wp.array(dtype=float), variant: int, out: wp.array(dtype=float)):
    r = wp.tid()
    out[r] = media_volume_render(sigma_a, sigma_s, L_e, L_i, r, dt[r], L_bg[r], variant)


@wp.kernel
def _rows_media_raymarch(sigma_t: wp.array2d(dtype=float), sigma_s: wp.array2d(dtype=float),
                         L_i: wp.array2d(dtype=float), dt: wp.array(dtype=float), L_bg: wp.array(dtype=float),
                         variant: int, out: wp.array(dtype=float)):
    r = wp.tid()
    out[r] = media_raymarch(sigma_t, sigma_s, L_i, r, dt[r], L_bg[r], variant)


@wp.kernel
def _rows_media_optical_thickness(sigma: wp.array2d(dtype=float), dt: wp.array(dtype=float),
                                  out: wp.array(dtype=float)):
    r = wp.tid()
    out[r] = media_optical_thickness(sigma, r, dt[r])
