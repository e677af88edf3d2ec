"""Colour conversions (vc §2.4, §4.2.2) -- Warp twins of ``cclouds/colour.h``.

The chain of the Preetham sky (vc-A29)::

    xyY --(vc-4.3)--> XYZ --(vc-4.4)--> linear sRGB --(vc-4.5)--> tone-mapped linear RGB --(sRGB OETF)--> display

X, Y, Z are CIE 1931 tristimulus values (Y = luminance; the Preetham sky gives kcd/m^2), x, y CIE 1931 chromaticities,
linear sRGB has the Rec. 709 primaries and D65 white (0.95047, 1, 1.08883) -> (1, 1, 1). The thesis stops after the
tone map; :func:`colour_srgb_encode` (IEC 61966-2-1) is the extra display step of the render chain, documented
under vc-A29.

Errata (variant option, spec §7): vc-4.4 prints -0.9392660 for Lindbloom's -0.9692660 (D65 white -> G = 1.02851);
vc-4.5 prints 1 - exp(+0.03 C), which is <= 0 for C >= 0 -- corrected: 1 - exp(-k C) with the exposure k = 0.03 as a
named parameter.

Triples are vectors: XYZ, xyY and RGB are ``wp.vec3`` (NumPy ``(..., 3)``, C ``ccl_vec3``), the chromaticity xy a
``wp.vec2``. The tone map and the sRGB encoding work on one channel.
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.registry import VARIANT, Arg, declare
from . import VARIANT_THESIS

SRGB_LINEAR_LIMIT = wp.constant(0.0031308)  # IEC 61966-2-1: end of the linear segment (linear side)

#: Default exposure k of the tone map vc-4.5: the thesis' constant 0.03 (its sign corrected), for RGB in the unit of
#: the Preetham luminance (kcd/m^2): a zenith of 5-15 kcd/m^2 maps to 0.14-0.36 before the sRGB encoding.
TONEMAP_EXPOSURE = 0.03


def _check_XYZ_chromaticity(XYZ):
    a = np.asarray(XYZ, np.float64)
    if np.any(a < 0):
        raise ValueError(f"XYZ must have components >= 0, got {a[a < 0].flat[0]!r}")
    s = a.sum(axis=-1)
    if np.any(s <= 0):
        raise ValueError(f"XYZ must have X + Y + Z > 0 (chromaticity is undefined for black), got {np.min(s)!r}")


def _samples_XYZ(rng, n):
    return {"XYZ": rng.uniform(0.01, 100.0, (n, 3)).astype(np.float32)}


@declare("vc-2.32", c="ccl_colour_XYZ_to_xy",
         args=(Arg("XYZ", "CIE 1931 tristimulus values (X, Y, Z), components >= 0 with X + Y + Z > 0 (checked)"),),
         outputs=("xy",), check=_check_XYZ_chromaticity, samples=_samples_XYZ,
         summary="CIE xy chromaticity x = X/(X+Y+Z), y = Y/(X+Y+Z); X + Y + Z must be > 0.",
         references=("CIE 015:2018 Colorimetry, 4th ed.", "colour-science: colour.XYZ_to_xy"))
@wp.func
def colour_XYZ_to_xy(XYZ: wp.vec3) -> wp.vec2:
    """vc-2.32: x = X / (X + Y + Z), y = Y / (X + Y + Z). Returns (x, y)."""
    s = XYZ[0] + XYZ[1] + XYZ[2]
    return wp.vec2(XYZ[0] / s, XYZ[1] / s)


def _check_xyY(xyY):
    a = np.asarray(xyY, np.float64)
    x, y, Y = a[..., 0], a[..., 1], a[..., 2]
    for name, v, ok, dom in (("x", x, (x >= 0) & (x <= 1), "[0, 1]"), ("y", y, (y > 0) & (y <= 1), "(0, 1]"),
                             ("Y", Y, Y >= 0, "[0, inf)")):
        if not np.all(ok):
            raise ValueError(f"xyY must have its component {name} in {dom}, got {v[~ok].flat[0]!r}")


def _samples_xyY(rng, n):
    return {"xyY": np.stack([rng.uniform(0.0, 1.0, n), rng.uniform(0.01, 1.0, n), rng.uniform(0.0, 100.0, n)],
                            axis=-1).astype(np.float32)}


@declare("vc-4.3", c="ccl_colour_xyY_to_XYZ",
         args=(Arg("xyY", "(x, y, Y): CIE 1931 chromaticity x in [0, 1], y in (0, 1] and luminance Y >= 0 (any unit; "
                          "X, Z come out in the same unit) (checked)"),),
         outputs=("XYZ",), check=_check_xyY, samples=_samples_xyY,
         summary="CIE xyY -> XYZ: X = x Y/y, Y = Y, Z = (1 - x - y) Y/y (requires y > 0). Inverse of vc-2.32.",
         references=("CIE 015:2018 Colorimetry", "colour-science: colour.xyY_to_XYZ"))
@wp.func
def colour_xyY_to_XYZ(xyY: wp.vec3) -> wp.vec3:
    """vc-4.3: X = x (Y / y), Y = Y, Z = (1 - x - y)(Y / y). Returns (X, Y, Z)."""
    k = xyY[2] / xyY[1]
    return wp.vec3(xyY[0] * k, xyY[2], (1.0 - xyY[0] - xyY[1]) * k)


@declare("vc-4.4", c="ccl_colour_XYZ_to_linear_srgb",
         args=(Arg("XYZ", "CIE 1931 tristimulus values (X, Y, Z)", sample_range=(-10.0, 100.0)),),
         options=(VARIANT,), outputs=("RGB",),
         summary="CIE XYZ -> linear sRGB (D65), Lindbloom's matrix. variant='corrected': row 2 column 1 = "
                 "-0.9692660, D65 white (0.95047, 1, 1.08883) -> (1, 1, 1); variant='thesis': -0.9392660 as printed, "
                 "the same white -> G = 1.02851 (green cast). Output unbounded (negative = out of gamut).",
         references=("IEC 61966-2-1:1999 (sRGB)", "B. Lindbloom, RGB/XYZ Matrices, brucelindbloom.com",
                     "colour-science: colour.XYZ_to_RGB, colour.normalised_primary_matrix"))
@wp.func
def colour_XYZ_to_linear_srgb(XYZ: wp.vec3, variant: int) -> wp.vec3:
    """vc-4.4: Lindbloom's XYZ -> linear sRGB (D65); variant 1 = -0.9392660 as printed. Returns (R, G, B)."""
    m10 = float(-0.9692660)
    if variant == VARIANT_THESIS:
        m10 = float(-0.9392660)
    X = XYZ[0]
    Y = XYZ[1]
    Z = XYZ[2]
    r = 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z
    g = m10 * X + 1.8760108 * Y + 0.0415560 * Z
    b = 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z
    return wp.vec3(r, g, b)


@declare("vc-4.5", c="ccl_colour_tonemap_exp",
         nonfinite="variant='thesis' (the printed sign, 1 - exp(+k C)) overflows to -inf for k C > 88.7",
         args=(Arg("c_hdr", "linear HDR channel value (RGB from vc-4.4)", sample_range=(-10.0, 100.0)),
               Arg("exposure", "exposure k > 0; 0.03 = the thesis' constant, for RGB in kcd/m^2", lo=0.0,
                   lo_open=True, default=TONEMAP_EXPOSURE, sample_range=(0.001, 1.0))),
         options=(VARIANT,), outputs=("C",),
         summary="Exponential tone map of one channel. variant='corrected': C = 1 - exp(-k C_hdr), [0, inf) -> "
                 "[0, 1); variant='thesis': C = 1 - exp(+k C_hdr) as printed, <= 0 for C_hdr >= 0 (black after "
                 "clamping).",
         references=("Spec vc §7 item 11 (sign of the printed formula)",))
@wp.func
def colour_tonemap_exp(c_hdr: float, exposure: float, variant: int) -> float:
    """vc-4.5: 1 - exp(-k C_hdr); variant 1 = 1 - exp(+k C_hdr) as printed."""
    if variant == VARIANT_THESIS:
        return 1.0 - wp.exp(exposure * c_hdr)
    return 1.0 - wp.exp(-exposure * c_hdr)


@wp.func
def colour_srgb_encode(c: float) -> float:
    """IEC 61966-2-1 sRGB encoding: 12.92 c below 0.0031308, else 1.055 c^(1/2.4) - 0.055 (part of vc-A29; no
    catalogue ID of its own, so not a registry entry: :func:`pywarp.clouds.sky.srgb_encode_array` evaluates it on
    arrays)."""
    if c <= SRGB_LINEAR_LIMIT:
        return 12.92 * c
    return 1.055 * wp.pow(c, 1.0 / 2.4) - 0.055


@wp.kernel
def _srgb_encode_kernel(c: wp.array(dtype=float), out: wp.array(dtype=float)):
    # the array form of colour_srgb_encode for pywarp.clouds.sky.srgb_encode_array (a helper without a catalogue ID, not an entry)
    i = wp.tid()
    out[i] = colour_srgb_encode(c[i])
