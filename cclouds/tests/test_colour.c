/* C unit tests of cclouds/colour.h: chromaticity (vc-2.32), xyY -> XYZ (vc-4.3), XYZ -> linear sRGB with both
 * variants (vc-4.4), the tone map with both variants (vc-4.5), the sRGB encoding (IEC 61966-2-1), NaN propagation. */
#include "cclouds/colour.h"
#include "ccl_test.h"

/* D65 white of Lindbloom's matrix: XYZ (0.95047, 1, 1.08883) */
#define WX 0.95047
#define WY 1.0
#define WZ 1.08883

static void test_XYZ_to_xy_closed_form(void)
{
    ccl_vec2 xy = ccl_colour_XYZ_to_xy(V((float)WX, (float)WY, (float)WZ));
    CCL_CHECK_REL(xy.x, WX / (WX + WY + WZ), 2e-7); /* 0.312727 */
    CCL_CHECK_REL(xy.y, WY / (WX + WY + WZ), 2e-7); /* 0.329023 */
    xy = ccl_colour_XYZ_to_xy(V(1.0f, 1.0f, 1.0f)); /* equal-energy white E */
    CCL_CHECK_REL(xy.x, 1.0 / 3.0, 1e-7);
    CCL_CHECK_REL(xy.y, 1.0 / 3.0, 1e-7);
    xy = ccl_colour_XYZ_to_xy(V(2.0f, 0.0f, 0.0f));
    CCL_CHECK(xy.x == 1.0f && xy.y == 0.0f);
}

static void test_xyY_to_XYZ_round_trip(void)
{
    static const float xyz[][3] = {{0.95047f, 1.0f, 1.08883f}, {0.2f, 0.5f, 0.1f}, {12.0f, 9.5f, 30.0f},
                                   {0.01f, 0.02f, 0.0f}};
    size_t i;
    for (i = 0; i < sizeof xyz / sizeof xyz[0]; ++i) {
        ccl_vec2 xy = ccl_colour_XYZ_to_xy(V(xyz[i][0], xyz[i][1], xyz[i][2]));
        ccl_vec3 r = ccl_colour_xyY_to_XYZ(V(xy.x, xy.y, xyz[i][1]));
        CCL_CHECK_REL(r.x, xyz[i][0], 4e-7);
        CCL_CHECK(r.y == xyz[i][1]);                                   /* Y passes through unchanged */
        CCL_CHECK_CLOSE(r.z, xyz[i][2], 8e-7 * (double)(xyz[i][0] + xyz[i][1] + xyz[i][2])); /* 1 - x - y cancels */
    }
}

static void test_XYZ_to_linear_srgb_white_point_both_variants(void)
{
    ccl_vec3 c = ccl_colour_XYZ_to_linear_srgb(V((float)WX, (float)WY, (float)WZ), CCL_VARIANT_CORRECTED);
    CCL_CHECK_CLOSE(c.x, 1.0, 2e-6);
    CCL_CHECK_CLOSE(c.y, 1.0, 2e-6);
    CCL_CHECK_CLOSE(c.z, 1.0, 2e-6);
    c = ccl_colour_XYZ_to_linear_srgb(V((float)WX, (float)WY, (float)WZ), CCL_VARIANT_THESIS);
    CCL_CHECK_CLOSE(c.x, 1.0, 2e-6);
    CCL_CHECK_CLOSE(c.y, 1.0 + 0.03 * WX, 2e-6); /* 1.02851: the printed -0.9392660 adds 0.03 X to G */
    CCL_CHECK_CLOSE(c.y, 1.02851, 1e-5);
    CCL_CHECK_CLOSE(c.z, 1.0, 2e-6);
    /* columns of the matrix: unit X, Y, Z */
    c = ccl_colour_XYZ_to_linear_srgb(V(1.0f, 0.0f, 0.0f), CCL_VARIANT_CORRECTED);
    CCL_CHECK(c.x == 3.2404542f && c.y == -0.9692660f && c.z == 0.0556434f);
    c = ccl_colour_XYZ_to_linear_srgb(V(1.0f, 0.0f, 0.0f), CCL_VARIANT_THESIS);
    CCL_CHECK(c.x == 3.2404542f && c.y == -0.9392660f && c.z == 0.0556434f);
    c = ccl_colour_XYZ_to_linear_srgb(V(0.0f, 1.0f, 0.0f), CCL_VARIANT_THESIS);
    CCL_CHECK(c.x == -1.5371385f && c.y == 1.8760108f && c.z == -0.2040259f);
    c = ccl_colour_XYZ_to_linear_srgb(V(0.0f, 0.0f, 1.0f), CCL_VARIANT_CORRECTED);
    CCL_CHECK(c.x == -0.4985314f && c.y == 0.0415560f && c.z == 1.0572252f);
}

static void test_tonemap_exp_variants(void)
{
    CCL_CHECK(ccl_colour_tonemap_exp(0.0f, 0.03f, CCL_VARIANT_CORRECTED) == 0.0f);
    CCL_CHECK_REL(ccl_colour_tonemap_exp(100.0f, 0.03f, CCL_VARIANT_CORRECTED), 1.0 - exp(-3.0), 1e-6); /* 0.950213 */
    CCL_CHECK_REL(ccl_colour_tonemap_exp(10.0f, 0.1f, CCL_VARIANT_CORRECTED), 1.0 - exp(-1.0), 1e-6);
    CCL_CHECK(ccl_colour_tonemap_exp(1e4f, 0.03f, CCL_VARIANT_CORRECTED) == 1.0f); /* saturates, never exceeds 1 */
    /* as printed: 1 - exp(+k C) <= 0 for every C >= 0 */
    CCL_CHECK(ccl_colour_tonemap_exp(0.0f, 0.03f, CCL_VARIANT_THESIS) == 0.0f);
    CCL_CHECK_REL(ccl_colour_tonemap_exp(100.0f, 0.03f, CCL_VARIANT_THESIS), 1.0 - exp(3.0), 1e-6); /* -19.0855 */
    CCL_CHECK(ccl_colour_tonemap_exp(0.5f, 0.03f, CCL_VARIANT_THESIS) < 0.0f);
    /* the printed form is the corrected one at -C */
    CCL_CHECK(ccl_colour_tonemap_exp(7.0f, 0.03f, CCL_VARIANT_THESIS) ==
              ccl_colour_tonemap_exp(-7.0f, 0.03f, CCL_VARIANT_CORRECTED));
}

static void test_srgb_encode_values(void)
{
    CCL_CHECK(ccl_colour_srgb_encode(0.0f) == 0.0f);
    CCL_CHECK_CLOSE(ccl_colour_srgb_encode(1.0f), 1.0, 1e-7);
    CCL_CHECK_REL(ccl_colour_srgb_encode(0.0031308f), 12.92 * 0.0031308, 1e-6);
    /* the two segments meet at 0.0031308 to within 1e-7 (IEC 61966-2-1 constants) */
    CCL_CHECK_CLOSE(1.055 * pow(0.0031308, 1.0 / 2.4) - 0.055, 12.92 * 0.0031308, 1e-7);
    CCL_CHECK_REL(ccl_colour_srgb_encode(0.5f), 1.055 * pow(0.5, 1.0 / 2.4) - 0.055, 1e-6); /* 0.735357 */
    CCL_CHECK_REL(ccl_colour_srgb_encode(0.18f), 1.055 * pow(0.18, 1.0 / 2.4) - 0.055, 1e-6);
    CCL_CHECK_REL(ccl_colour_srgb_encode(-0.1f), -1.292, 1e-6);
}

static void test_colour_nan_propagates(void)
{
    float nan = (float)NAN;
    ccl_vec2 xy = ccl_colour_XYZ_to_xy(V(nan, 1.0f, 1.0f));
    ccl_vec3 c;
    CCL_CHECK(isnan(xy.x) && isnan(xy.y));
    c = ccl_colour_xyY_to_XYZ(V(0.3f, 0.3f, nan));
    CCL_CHECK(isnan(c.x) && isnan(c.y) && isnan(c.z));
    c = ccl_colour_XYZ_to_linear_srgb(V(nan, 0.0f, 0.0f), CCL_VARIANT_CORRECTED);
    CCL_CHECK(isnan(c.x) && isnan(c.y) && isnan(c.z));
    CCL_CHECK(isnan(ccl_colour_tonemap_exp(nan, 0.03f, CCL_VARIANT_CORRECTED)));
    CCL_CHECK(isnan(ccl_colour_tonemap_exp(nan, 0.03f, CCL_VARIANT_THESIS)));
    CCL_CHECK(isnan(ccl_colour_srgb_encode(nan)));
}

int main(void)
{
    CCL_RUN(test_XYZ_to_xy_closed_form);
    CCL_RUN(test_xyY_to_XYZ_round_trip);
    CCL_RUN(test_XYZ_to_linear_srgb_white_point_both_variants);
    CCL_RUN(test_tonemap_exp_variants);
    CCL_RUN(test_srgb_encode_values);
    CCL_RUN(test_colour_nan_propagates);
    return ccl_test_report();
}
