"""Colour conversions (vc §2.4, §4.2.2) -- Warp twins of ``cclouds/colour.h``.

The chain of the Preetham sky (vc-A29)::

    xyY --(vc-4.3)--> XYZ --(vc-4.4)--> linear sRGB --(vc-4.5)--> tone-mapped linear RGB --(sRGB OETF)--> display

X, Y, Z are CIE 1931 tristimulus values (Y = luminance; the Preetham sky gives kcd/m^2), x, y CIE 1931 chromaticities,
linear sRGB has the Rec. 709 primaries and D65 white (0.95047, 1, 1.08883) -> (1, 1, 1). The thesis stops after the
tone map; :func:`srgb_encode` (IEC 61966-2-1) is the extra display step of the render chain, documented under vc-A29.

Errata (variant option, spec §7): vc-4.4 prints -0.9392660 for Lindbloom's -0.9692660 (D65 white -> G = 1.02851);
vc-4.5 prints 1 - exp(+0.03 C), which is <= 0 for C >= 0 -- corrected: 1 - exp(-k C) with the exposure k = 0.03 as a
named parameter.
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.registry import VARIANT, Arg, Equation, register

SRGB_LINEAR_LIMIT = wp.constant(0.0031308)  # IEC 61966-2-1: end of the linear segment (linear side)

#: Default exposure k of the tone map vc-4.5: the thesis' constant 0.03 (its sign corrected), for RGB in the unit of
#: the Preetham luminance (kcd/m^2): a zenith of 5-15 kcd/m^2 maps to 0.14-0.36 before the sRGB encoding.
TONEMAP_EXPOSURE = 0.03


@wp.func
def XYZ_to_xy(X: float, Y: float, Z: float):
    """vc-2.32: x = X / (X + Y + Z), y = Y / (X + Y + Z). Returns (x, y)."""
    s = X + Y + Z
    return X / s, Y / s


@wp.func
def xyY_to_XYZ(x: float, y: float, Y: float):
    """vc-4.3: X = x (Y / y), Y = Y, Z = (1 - x - y)(Y / y). Returns (X, Y, Z)."""
    k = Y / y
    return x * k, Y, (1.0 - x - y) * k


@wp.func
def XYZ_to_linear_srgb(X: float, Y: float, Z: float, variant: int):
    """vc-4.4: Lindbloom's XYZ -> linear sRGB (D65); variant 1 = -0.9392660 as printed. Returns (R, G, B)."""
    m10 = float(-0.9692660)
    if variant == 1:
        m10 = float(-0.9392660)
    r = 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z
    g = m10 * X + 1.8760108 * Y + 0.0415560 * Z
    b = 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z
    return r, g, b


@wp.func
def tonemap_exp(c_hdr: float, exposure: float, variant: int) -> float:
    """vc-4.5: 1 - exp(-k C_hdr); variant 1 = 1 - exp(+k C_hdr) as printed."""
    if variant == 1:
        return 1.0 - wp.exp(exposure * c_hdr)
    return 1.0 - wp.exp(-exposure * c_hdr)


@wp.func
def srgb_encode(c: float) -> float:
    """IEC 61966-2-1 sRGB encoding: 12.92 c below 0.0031308, else 1.055 c^(1/2.4) - 0.055 (part of vc-A29)."""
    if c <= SRGB_LINEAR_LIMIT:
        return 12.92 * c
    return 1.055 * wp.pow(c, 1.0 / 2.4) - 0.055


# --- element-wise evaluation kernels (inputs, options, then outputs) -------------------------------------------------

@wp.kernel
def _eval_XYZ_to_xy(X: wp.array(dtype=float), Y: wp.array(dtype=float), Z: wp.array(dtype=float),
                    out_x: wp.array(dtype=float), out_y: wp.array(dtype=float)):
    i = wp.tid()
    x, y = XYZ_to_xy(X[i], Y[i], Z[i])
    out_x[i] = x
    out_y[i] = y


@wp.kernel
def _eval_xyY_to_XYZ(x: wp.array(dtype=float), y: wp.array(dtype=float), Y: wp.array(dtype=float),
                     out_X: wp.array(dtype=float), out_Y: wp.array(dtype=float), out_Z: wp.array(dtype=float)):
    i = wp.tid()
    a, b, c = xyY_to_XYZ(x[i], y[i], Y[i])
    out_X[i] = a
    out_Y[i] = b
    out_Z[i] = c


@wp.kernel
def _eval_XYZ_to_linear_srgb(X: wp.array(dtype=float), Y: wp.array(dtype=float), Z: wp.array(dtype=float),
                             variant: int, out_R: wp.array(dtype=float), out_G: wp.array(dtype=float),
                             out_B: wp.array(dtype=float)):
    i = wp.tid()
    r, g, b = XYZ_to_linear_srgb(X[i], Y[i], Z[i], variant)
    out_R[i] = r
    out_G[i] = g
    out_B[i] = b


@wp.kernel
def _eval_tonemap_exp(c_hdr: wp.array(dtype=float), exposure: wp.array(dtype=float), variant: int,
                      out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = tonemap_exp(c_hdr[i], exposure[i], variant)


@wp.kernel
def _eval_srgb_encode(c: wp.array(dtype=float), out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = srgb_encode(c[i])


def srgb_encode_array(c, impl: str = "warp", device: str | None = None) -> np.ndarray:
    """Element-wise sRGB encoding (IEC 61966-2-1) of a NumPy array -- the display step of the vc-A29 chain, which has
    no catalogue ID of its own. ``impl="c"`` evaluates ``ccl_srgb_encode``. ``c`` must be finite."""
    from ..core.registry import Equation as _Eq, _c_eval, _warp_eval

    eq = _Eq("vc-A29", "srgb_encode", "ccl_srgb_encode", srgb_encode, _eval_srgb_encode,
             args=(Arg("c", "linear channel value"),), outputs=("V",))
    return (_c_eval(eq) if impl == "c" else _warp_eval(eq, device))(c)


# --- registry ---------------------------------------------------------------------------------------------------------

def _check_xyz_sum(X, Y, Z):
    s = np.asarray(X, np.float64) + np.asarray(Y, np.float64) + np.asarray(Z, np.float64)
    if np.any(s <= 0):
        raise ValueError(f"X + Y + Z must be > 0 (chromaticity is undefined for black), got {np.min(s)!r}")


_NONNEG = dict(lo=0.0)

register(Equation(
    "vc-2.32", "XYZ_to_xy", "ccl_XYZ_to_xy", XYZ_to_xy, _eval_XYZ_to_xy,
    args=(Arg("X", "CIE 1931 tristimulus X", **_NONNEG), Arg("Y", "CIE 1931 tristimulus Y (luminance)", **_NONNEG),
          Arg("Z", "CIE 1931 tristimulus Z", **_NONNEG)),
    outputs=("x", "y"), check=_check_xyz_sum,
    summary="CIE xy chromaticity x = X/(X+Y+Z), y = Y/(X+Y+Z); X + Y + Z must be > 0.",
    references=("CIE 015:2018 Colorimetry, 4th ed.", "colour-science: colour.XYZ_to_xy")))

register(Equation(
    "vc-4.3", "xyY_to_XYZ", "ccl_xyY_to_XYZ", xyY_to_XYZ, _eval_xyY_to_XYZ,
    args=(Arg("x", "CIE 1931 chromaticity x", lo=0.0, hi=1.0),
          Arg("y", "CIE 1931 chromaticity y, > 0", lo=0.0, hi=1.0, lo_open=True),
          Arg("Y", "luminance (any unit; X, Z come out in the same unit)", lo=0.0)),
    outputs=("X", "Y", "Z"),
    summary="CIE xyY -> XYZ: X = x Y/y, Y = Y, Z = (1 - x - y) Y/y (requires y > 0). Inverse of vc-2.32.",
    references=("CIE 015:2018 Colorimetry", "colour-science: colour.xyY_to_XYZ")))

register(Equation(
    "vc-4.4", "XYZ_to_linear_srgb", "ccl_XYZ_to_linear_srgb", XYZ_to_linear_srgb, _eval_XYZ_to_linear_srgb,
    args=(Arg("X", "CIE 1931 tristimulus X"), Arg("Y", "CIE 1931 tristimulus Y"), Arg("Z", "CIE 1931 tristimulus Z")),
    options=(VARIANT,), outputs=("R", "G", "B"),
    summary="CIE XYZ -> linear sRGB (D65), Lindbloom's matrix. variant='corrected': row 2 column 1 = -0.9692660, "
            "D65 white (0.95047, 1, 1.08883) -> (1, 1, 1); variant='thesis': -0.9392660 as printed, the same white "
            "-> G = 1.02851 (green cast). Output unbounded (negative = out of gamut).",
    references=("IEC 61966-2-1:1999 (sRGB)", "B. Lindbloom, RGB/XYZ Matrices, brucelindbloom.com",
                "colour-science: colour.XYZ_to_RGB, colour.normalised_primary_matrix")))

register(Equation(
    "vc-4.5", "tonemap_exp", "ccl_tonemap_exp", tonemap_exp, _eval_tonemap_exp,
    args=(Arg("c_hdr", "linear HDR channel value (RGB from vc-4.4)"),
          Arg("exposure", "exposure k > 0; 0.03 = the thesis' constant, for RGB in kcd/m^2", lo=0.0, lo_open=True,
              default=TONEMAP_EXPOSURE)),
    options=(VARIANT,), outputs=("C",),
    summary="Exponential tone map. variant='corrected': C = 1 - exp(-k C_hdr), [0, inf) -> [0, 1); "
            "variant='thesis': C = 1 - exp(+k C_hdr) as printed, <= 0 for C_hdr >= 0 (black after clamping).",
    references=("Spec vc §7 item 11 (sign of the printed formula)",)))
