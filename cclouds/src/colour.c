/* Colour conversions, vc §2.4 and §4.2.2. See cclouds/colour.h for the conventions. */
#include "cclouds/colour.h"
#include "internal.h"

void ccl_XYZ_to_xy(float X, float Y, float Z, float *out_x, float *out_y)
{
    float s;
    CCL_REQUIRE(out_x != NULL && out_y != NULL);
    /* vc-2.32: x = X / (X + Y + Z), y = Y / (X + Y + Z) */
    s = X + Y + Z;
    *out_x = X / s;
    *out_y = Y / s;
}

void ccl_xyY_to_XYZ(float x, float y, float Y, float *out_X, float *out_Y, float *out_Z)
{
    float k;
    CCL_REQUIRE(out_X != NULL && out_Y != NULL && out_Z != NULL);
    CCL_REQUIRE(!(y <= 0.0f));
    /* vc-4.3: X = x Y / y, Z = (1 - x - y) Y / y */
    k = Y / y;
    *out_X = x * k;
    *out_Y = Y;
    *out_Z = (1.0f - x - y) * k;
}

void ccl_XYZ_to_linear_srgb(float X, float Y, float Z, ccl_variant variant, float *out_R, float *out_G, float *out_B)
{
    /* vc-4.4, row 2 column 1: -0.9692660 (Lindbloom) or -0.9392660 as printed */
    const float m10 = (variant == CCL_VARIANT_THESIS) ? -0.9392660f : -0.9692660f;
    CCL_REQUIRE(out_R != NULL && out_G != NULL && out_B != NULL);
    *out_R = 3.2404542f * X - 1.5371385f * Y - 0.4985314f * Z;
    *out_G = m10 * X + 1.8760108f * Y + 0.0415560f * Z;
    *out_B = 0.0556434f * X - 0.2040259f * Y + 1.0572252f * Z;
}

float ccl_tonemap_exp(float c_hdr, float exposure, ccl_variant variant)
{
    CCL_REQUIRE(!(exposure <= 0.0f));
    /* vc-4.5: corrected 1 - exp(-k C); as printed 1 - exp(+k C) */
    if (variant == CCL_VARIANT_THESIS) return 1.0f - expf(exposure * c_hdr);
    return 1.0f - expf(-exposure * c_hdr);
}

float ccl_srgb_encode(float c)
{
    /* IEC 61966-2-1: linear segment below 0.0031308, 1.055 c^(1/2.4) - 0.055 above */
    if (c <= 0.0031308f) return 12.92f * c;
    return 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}
