/*
 * cclouds/colour.h -- colour conversions of the sky pipeline (vc §2.4, §4.2.2): CIE XYZ <-> xyY, XYZ -> linear sRGB,
 * the exponential tone map and the sRGB transfer function.
 *
 * Conventions: X, Y, Z are CIE 1931 tristimulus values (Y = luminance, any positive scale -- the Preetham sky gives
 * kcd/m^2); x, y are CIE 1931 chromaticities; linear sRGB has the sRGB/Rec. 709 primaries and the D65 white point
 * (0.95047, 1, 1.08883) -> (1, 1, 1). The chain used by the Preetham sky (vc-A29) is
 *   xyY --(vc-4.3)--> XYZ --(vc-4.4)--> linear sRGB --(vc-4.5)--> tone-mapped linear RGB --(sRGB OETF)--> display.
 * The thesis stops after the tone map (it writes linear values to the frame buffer); the sRGB encoding
 * (IEC 61966-2-1) is the extra step that turns them into display values for an 8-bit image (documented under vc-A29).
 */
#ifndef CCLOUDS_COLOUR_H
#define CCLOUDS_COLOUR_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* CIE xy chromaticity of a tristimulus value: x = X / (X + Y + Z), y = Y / (X + Y + Z).
 * Ref: vc-2.32 (CIE 1931). XYZ -> (X, Y, Z), components >= 0 with X + Y + Z > 0 (undefined for a zero sum: the
 * result is NaN). Output (x, y), in [0, 1] for non-negative input. NaN propagates. */
CCL_API ccl_vec2 ccl_colour_XYZ_to_xy(ccl_vec3 XYZ);

/* CIE xyY -> XYZ: X = x * (Y / y), Y = Y, Z = (1 - x - y) * (Y / y).
 * Ref: vc-4.3. xyY -> (x, y, Y): chromaticity x, y with y > 0 (y = 0 divides by zero: Inf/NaN) and luminance
 * Y >= 0, any unit (the output has the unit of Y). Output (X, Y, Z). The inverse of ccl_colour_XYZ_to_xy for
 * Y > 0. */
CCL_API ccl_vec3 ccl_colour_xyY_to_XYZ(ccl_vec3 xyY);

/* CIE XYZ -> linear sRGB (D65) by the 3x3 matrix of vc-4.4 (Lindbloom's XYZ -> sRGB matrix, 7 digits).
 * Ref: vc-4.4; IEC 61966-2-1:1999; B. Lindbloom, "RGB/XYZ matrices". XYZ -> (X, Y, Z), any finite values.
 * variant CCL_VARIANT_CORRECTED: row 2, column 1 is -0.9692660 (Lindbloom): D65 white (0.95047, 1, 1.08883) maps to
 * (1.0000, 1.0000, 1.0000) within 1e-6. variant CCL_VARIANT_THESIS: -0.9392660 as printed (spec error index item 10):
 * the same white maps to G = 1.02851, a ~2.9 % green cast. All other entries are identical in both variants.
 * Output: linear (R, G, B) (unbounded: out-of-gamut colours give negative components). */
CCL_API ccl_vec3 ccl_colour_XYZ_to_linear_srgb(ccl_vec3 XYZ, ccl_variant variant);

/* Exponential tone map of one HDR channel: C = 1 - exp(-k C_hdr).
 * Ref: vc-4.5. c_hdr -> C_HDR, linear HDR value (any finite value; >= 0 for in-gamut colours); exposure -> k > 0
 * (the thesis' constant is 0.03, applied to RGB in the unit of the Preetham luminance, kcd/m^2).
 * variant CCL_VARIANT_CORRECTED: 1 - exp(-k C_hdr), maps [0, inf) onto [0, 1), monotonic, slope k at 0.
 * variant CCL_VARIANT_THESIS: 1 - exp(+k C_hdr) as printed (spec error index item 11): <= 0 for every C_hdr >= 0,
 * i.e. a black image once clamped to [0, 1]. NaN propagates. */
CCL_API float ccl_colour_tonemap_exp(float c_hdr, float exposure, ccl_variant variant);

/* sRGB encoding (opto-electronic transfer function) of one linear channel:
 * V = 12.92 c for c <= 0.0031308, V = 1.055 c^(1/2.4) - 0.055 otherwise.
 * Ref: IEC 61966-2-1:1999 (part of the vc-A29 render chain: applied after the tone map for 8-bit display; the
 * thesis does not mention it -- see vc-4.4 note). c any finite value: negative input stays on the linear segment
 * (as colour-science's eotf_inverse_sRGB), input above 1 follows the power segment. [0, 1] maps onto [0, 1].
 * NaN propagates. */
CCL_API float ccl_colour_srgb_encode(float c);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_COLOUR_H */
