"""Geometric optics of a water drop (rr §2.2, §3.2.1) -- Warp twins of ``cclouds/optics.h``.

Conventions: directions are unit vec3; an incident direction is the direction the light travels; a normal may point
to either side (the functions orient it against the incident direction); ``n1`` is the refractive index of the medium
the light comes from, ``n2`` of the one it enters (air 1, water 1.33 in the text); angles of incidence are passed as
``cos_i`` in [0, 1]. Total internal reflection reflects everything (R = 1) and refracts nothing (t = 0).
"""
from __future__ import annotations

import warp as wp

from ..core.registry import VARIANT, Arg, declare
from . import VARIANT_THESIS

#: refractive index of water used by the text (rr §3.2.1)
WATER_INDEX = 1.33
DEG_PER_RAD = wp.constant(57.2957795130823208768)
RAD_PER_DEG = wp.constant(0.0174532925199432957692)

_N1 = Arg("n1", "refractive index of the medium the light comes from (air 1)", lo=1e-3, hi=10.0)  # from 1e-3: no denormal index (n1 / n2 overflows)
_N2 = Arg("n2", "refractive index of the medium the light enters (water 1.33)", lo=1e-3, hi=10.0)


@declare("rr-snell", c="ccl_optics_snell",
         args=(Arg("d", "incident direction (unit; the direction the light travels)", unit=True),
               Arg("n", "surface normal (unit; either side)", unit=True), _N1, _N2),
         outputs=("t", "r", "tir"),
         summary="Law of reflection and Snell's law for a direction: r = d + 2 cos_i n', t = eta d + (eta cos_i - "
                 "sqrt(k)) n' (n' = n against d, eta = n1/n2, k = 1 - eta^2 (1 - cos_i^2)); total internal "
                 "reflection (k < 0): t = (0, 0, 0), tir = 1 (GLSL/Cg refract convention).",
         references=("Snell's law; Born & Wolf, Principles of Optics, §1.5",
                     "Rousseau, Jolivet & Ghazanfarpour, Computers & Graphics 30 (2006), §3"))
@wp.func
def optics_snell(d: wp.vec3, n: wp.vec3, n1: float, n2: float) -> tuple[wp.vec3, wp.vec3, int]:
    """rr-snell: refracted t (zero on TIR), reflected r, TIR flag. Where eta^2 overflows (n2 below ~5e-20 n1, outside
    the registry's domain; Inf x 0 at normal incidence) an oblique ray is totally reflected and one along the normal
    goes on, t = d, as C."""
    nn = n
    if wp.dot(n, d) > 0.0:
        nn = n * -1.0
    cos_i = -wp.dot(nn, d)
    r = d + nn * (2.0 * cos_i)
    eta = n1 / n2
    k = float(-1.0)
    if wp.isinf(eta * eta):
        if not (1.0 - cos_i * cos_i > 0.0):
            return d, r, 0
    else:
        k = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
    if k < 0.0:
        return wp.vec3(0.0, 0.0, 0.0), r, 1
    return d * eta + nn * (eta * cos_i - wp.sqrt(k)), r, 0


@declare("rr-eq2", "rr-eq3", c="ccl_optics_fresnel",
         args=(Arg("cos_i", "cosine of the angle of incidence (1 = normal, 0 = grazing)", lo=0.0, hi=1.0), _N1, _N2),
         outputs=("R", "Rs", "Rp"),
         summary="Fresnel reflectance in the cosine forms of eqs. (2), (3): Rs = ((n1 ci - n2 ct)/(n1 ci + n2 ct))^2, "
                 "Rp = ((n1 ct - n2 ci)/(n1 ct + n2 ci))^2, ct = sqrt(1 - (n1/n2)^2 (1 - ci^2)); R = (Rs + Rp)/2 "
                 "(unpolarised; used but not written by the text). No 0/0 at normal incidence; beyond the critical "
                 "angle R = Rs = Rp = 1 (total internal reflection); grazing at exactly the critical angle: the limit 1.",
         references=("Fresnel equations; Born & Wolf, Principles of Optics, §1.5.2",
                     "Rousseau, Jolivet & Ghazanfarpour 2006, eqs. (2), (3)"))
@wp.func
def optics_fresnel(cos_i: float, n1: float, n2: float) -> tuple[float, float, float]:
    """rr-eq2 / rr-eq3: unpolarised R, Rs, Rp."""
    eta = n1 / n2
    k = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
    if k < 0.0:
        return 1.0, 1.0, 1.0
    cos_t = wp.sqrt(k)
    a = n1 * cos_i - n2 * cos_t
    b = n1 * cos_i + n2 * cos_t
    rs = float(1.0)
    if b > 0.0:
        rs = (a / b) * (a / b)
    a = n1 * cos_t - n2 * cos_i
    b = n1 * cos_t + n2 * cos_i
    rp = float(1.0)
    if b > 0.0:
        rp = (a / b) * (a / b)
    return 0.5 * (rs + rp), rs, rp


@declare("rr-der-3.2.1", c="ccl_optics_drop_fov",
         args=(Arg("n", "relative refractive index water/air (1.33)", lo=1.0, hi=2.0),),
         options=(VARIANT,), outputs=("fov_deg", "theta_t_deg", "exit_normal_deg", "exit_deg"),
         summary="Field of view of a drop = twice the largest deviation through a sphere (grazing entry): theta_t = "
                 "arcsin(1/n), exit normal at 2 theta_t - 90 to the incoming ray, exit at arcsin(n sin theta_t) to "
                 "it, FOV = 2 (exit - exit normal). variant='corrected': exact, exit 90 deg, FOV = 360 - 4 "
                 "arcsin(1/n) = 165.0 deg for 1.33; variant='thesis': every angle truncated to whole degrees as "
                 "printed (48 -> 6 -> 81 -> 75), FOV 150 deg -- the capture camera's default FOVy (the text's "
                 "contract).",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §3.2.1 (Fig. 3.6 of the thesis)",))
@wp.func
def optics_drop_fov(n: float, variant: int) -> tuple[float, float, float, float]:
    """rr-der-3.2.1: (FOV, theta_t, exit normal, exit) in degrees."""
    theta_t = wp.asin(1.0 / n) * DEG_PER_RAD
    e = float(0.0)
    x = float(90.0)
    if variant == VARIANT_THESIS:
        theta_t = wp.floor(theta_t)
        e = 2.0 * theta_t - 90.0
        x = wp.floor(wp.asin(wp.min(n * wp.sin(theta_t * RAD_PER_DEG), 1.0)) * DEG_PER_RAD)
    else:
        e = 2.0 * theta_t - 90.0
    return 2.0 * (x - e), theta_t, e, x


__all__ = ["WATER_INDEX", "optics_snell", "optics_fresnel", "optics_drop_fov"]
