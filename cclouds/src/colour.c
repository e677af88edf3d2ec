/* Colour conversions, vc §2.4 and §4.2.2. See cclouds/colour.h for the conventions. */
#include "cclouds/colour.h"
#include "internal.h"

ccl_vec2 ccl_colour_XYZ_to_xy(ccl_vec3 XYZ)
{
    ccl_vec2 r;
    float s;
    /* vc-2.32: x = X / (X + Y + Z), y = Y / (X + Y + Z) */
    s = XYZ.x + XYZ.y + XYZ.z;
    r.x = XYZ.x / s;
    r.y = XYZ.y / s;
    return r;
}

ccl_vec3 ccl_colour_xyY_to_XYZ(ccl_vec3 xyY)
{
    ccl_vec3 r;
    float k;
    CCL_REQUIRE(!(xyY.y <= 0.0f));
    /* vc-4.3: X = x Y / y, Z = (1 - x - y) Y / y */
    k = xyY.z / xyY.y;
    r.x = xyY.x * k;
    r.y = xyY.z;
    r.z = (1.0f - xyY.x - xyY.y) * k;
    return r;
}

ccl_vec3 ccl_colour_XYZ_to_linear_srgb(ccl_vec3 XYZ, ccl_variant variant)
{
    /* vc-4.4, row 2 column 1: -0.9692660 (Lindbloom) or -0.9392660 as printed */
    const float m10 = (variant == CCL_VARIANT_THESIS) ? -0.9392660f : -0.9692660f;
    ccl_vec3 r;
    r.x = 3.2404542f * XYZ.x - 1.5371385f * XYZ.y - 0.4985314f * XYZ.z;
    r.y = m10 * XYZ.x + 1.8760108f * XYZ.y + 0.0415560f * XYZ.z;
    r.z = 0.0556434f * XYZ.x - 0.2040259f * XYZ.y + 1.0572252f * XYZ.z;
    return r;
}

float ccl_colour_tonemap_exp(float c_hdr, float exposure, ccl_variant variant)
{
    CCL_REQUIRE(!(exposure <= 0.0f));
    /* vc-4.5: corrected 1 - exp(-k C); as printed 1 - exp(+k C) */
    if (variant == CCL_VARIANT_THESIS) return 1.0f - expf(exposure * c_hdr);
    return 1.0f - expf(-exposure * c_hdr);
}

float ccl_colour_srgb_encode(float c)
{
    /* IEC 61966-2-1: linear segment below 0.0031308, 1.055 c^(1/2.4) - 0.055 above */
    if (c <= 0.0031308f) return 12.92f * c;
    return 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}
