"""Phase functions (vc §2.1.4) -- Warp twins of ``cclouds/phase.h``.

Angle convention: ``cos_theta = dot(w_in, w_out)``, the cosine of the angle between the direction of travel before
and after scattering; ``+1`` is forward. In a camera raymarcher, ``cos_theta = dot(view_dir, to_sun)`` (vc-2.13).
"""
from __future__ import annotations

import warp as wp

from ..core.registry import VARIANT, Arg, declare
from . import VARIANT_THESIS

INV_4PI = wp.constant(0.0795774715459476679)  # 1 / (4 pi)


_COS = Arg("cos_theta", "cosine of the scattering angle, dot(w_in, w_out); +1 = forward", lo=-1.0, hi=1.0)


@declare("vc-2.11", c="ccl_phase_isotropic", outputs=("p",), summary="Isotropic phase function p = 1/(4 pi) [sr^-1].",
         references=("Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed., §11.3",))
@wp.func
def phase_isotropic() -> float:
    """vc-2.11: p = 1 / (4 pi)."""
    return INV_4PI


@declare("vc-2.12", c="ccl_phase_rayleigh", args=(_COS,), outputs=("p",),
         summary="Rayleigh phase function p = 3/(16 pi) (1 + cos^2 theta) [sr^-1].",
         references=("Chandrasekhar, Radiative Transfer, 1960",))
@wp.func
def phase_rayleigh(cos_theta: float) -> float:
    """vc-2.12: p = 1/(4 pi) * 3/4 * (1 + cos^2 theta)."""
    return INV_4PI * 0.75 * (1.0 + cos_theta * cos_theta)


@declare("vc-2.13", c="ccl_phase_hg",
         args=(_COS, Arg("g", "asymmetry parameter (mean cosine); > 0 forward", lo=-1.0, hi=1.0, lo_open=True,
                         hi_open=True)),
         outputs=("p",), summary="Henyey-Greenstein phase function [sr^-1].",
         references=("Henyey & Greenstein, Diffuse radiation in the galaxy, ApJ 93:70-83, 1941",))
@wp.func
def phase_hg(cos_theta: float, g: float) -> float:
    """vc-2.13: Henyey-Greenstein, p = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^(3/2)).

    The denominator is evaluated as (1 - g cos)^2 + g^2 (1 - cos)(1 + cos) and 1 - g^2 as (1 - g)(1 + g), without
    cancellation: finite on the whole open domain |g| < 1 (the plain form overflows at g = -0.999999, cos = -1)."""
    a = 1.0 - g * cos_theta
    denom = a * a + g * g * ((1.0 - cos_theta) * (1.0 + cos_theta))
    return INV_4PI * ((1.0 - g) * (1.0 + g)) / (denom * wp.sqrt(denom))


@declare("vc-2.15", c="ccl_phase_schlick",
         args=(_COS, Arg("k", "Schlick shape parameter; > 0 forward (corrected variant)", lo=-1.0, hi=1.0,
                         lo_open=True, hi_open=True)),
         options=(VARIANT,), outputs=("p",),
         summary="Schlick approximation of Henyey-Greenstein [sr^-1]. variant='corrected': (1 - k cos theta)^2, k > 0 "
                 "scatters forward; variant='thesis': (1 + k cos theta)^2 as printed, k > 0 scatters backward.",
         references=("Blasi, Le Saec & Schlick, A rendering algorithm for discrete volume density objects, "
                     "Computer Graphics Forum 12(3), 1993",
                     "Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed."))
@wp.func
def phase_schlick(cos_theta: float, k: float, variant: int) -> float:
    """vc-2.15: Schlick, p = (1 - k^2) / (4 pi (1 - k cos theta)^2); variant 1 = as printed, (1 + k cos theta)^2."""
    s = 1.0 - k * cos_theta
    if variant == VARIANT_THESIS:
        s = 1.0 + k * cos_theta
    return INV_4PI * (1.0 - k * k) / (s * s)


@declare("vc-2.16", c="ccl_phase_schlick_k", args=(Arg("g", "Henyey-Greenstein asymmetry parameter", lo=-1.0, hi=1.0),),
         outputs=("k",), summary="Schlick k from HG g: k = 1.55 g - 0.55 g^3. |k| exceeds 1 for 0.9381 < |g| < 1.",
         references=("Blasi, Le Saec & Schlick 1993",))
@wp.func
def phase_schlick_k(g: float) -> float:
    """vc-2.16: k = 1.55 g - 0.55 g^3."""
    return 1.55 * g - 0.55 * g * g * g


#: Droplet diameters [um] of the fit of :func:`phase_mie` (CCL_PHASE_MIE_D_MIN / _MAX): the range Jendersie & d'Eon
#: fitted and validated.
MIE_D_RANGE = (5.0, 50.0)


@wp.func
def phase_mie_params(diameter_um: float):
    """The parameters (g_HG, g_D, alpha, w_D) of the approximate Mie phase function for droplet diameter d [um]
    (Jendersie & d'Eon 2023, the fit for 5 <= d <= 50 um); the same float32 operations as ``ccl_phase_mie``."""
    d = diameter_um
    g_hg = wp.exp(-0.0990567 / (d - 1.67154))
    g_d = wp.exp(-2.20679 / (d + 3.91029) - 0.428934)
    alpha = wp.exp(3.62489 - 8.29288 / (d + 5.52825))
    w_d = wp.exp(-0.599085 / (d - 0.641583) - 0.665888)
    return g_hg, g_d, alpha, w_d


@wp.func
def phase_draine(cos_theta: float, g: float, alpha: float) -> float:
    """Draine's phase function (Draine 2003, eq. 4): HG(g) (1 + alpha cos^2) / (1 + alpha (1 + 2 g^2) / 3); the
    denominator is the mean of the numerator under HG(g), so it stays normalised. Helper of :func:`phase_mie`."""
    return phase_hg(cos_theta, g) * (1.0 + alpha * cos_theta * cos_theta) / (1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0)


@declare("vc-x-mie", c="ccl_phase_mie",
         args=(_COS, Arg("diameter_um", "droplet diameter d [um] of the fit", lo=MIE_D_RANGE[0], hi=MIE_D_RANGE[1])),
         outputs=("p",),
         summary="Approximate Mie phase function of cloud droplets [sr^-1] (beyond the text): (1 - w_D) HG(g_HG) + "
                 "w_D Draine(g_D, alpha), the four parameters fitted as functions of the droplet diameter d in "
                 "[5, 50] um.",
         references=("Jendersie & d'Eon, An Approximate Mie Scattering Function for Fog and Cloud Rendering, ACM "
                     "SIGGRAPH 2023 Talks, article 47",
                     "Draine, Scattering by interstellar dust grains. I., ApJ 598:1017-1025, 2003 (eq. 4)"))
@wp.func
def phase_mie(cos_theta: float, diameter_um: float) -> float:
    """vc-x-mie: (1 - w_D) HG(cos, g_HG) + w_D Draine(cos, g_D, alpha) with :func:`phase_mie_params` (d)."""
    g_hg, g_d, alpha, w_d = phase_mie_params(diameter_um)
    return (1.0 - w_d) * phase_hg(cos_theta, g_hg) + w_d * phase_draine(cos_theta, g_d, alpha)
