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
    float x, y;
    ccl_XYZ_to_xy((float)WX, (float)WY, (float)WZ, &x, &y);
    CCL_CHECK_REL(x, WX / (WX + WY + WZ), 2e-7); /* 0.312727 */
    CCL_CHECK_REL(y, WY / (WX + WY + WZ), 2e-7); /* 0.329023 */
    ccl_XYZ_to_xy(1.0f, 1.0f, 1.0f, &x, &y);     /* equal-energy white E */
    CCL_CHECK_REL(x, 1.0 / 3.0, 1e-7);
    CCL_CHECK_REL(y, 1.0 / 3.0, 1e-7);
    ccl_XYZ_to_xy(2.0f, 0.0f, 0.0f, &x, &y);
    CCL_CHECK(x == 1.0f && y == 0.0f);
}

static void test_xyY_to_XYZ_round_trip(void)
{
    static const float xyz[][3] = {{0.95047f, 1.0f, 1.08883f}, {0.2f, 0.5f, 0.1f}, {12.0f, 9.5f, 30.0f},
                                   {0.01f, 0.02f, 0.0f}};
    size_t i;
    for (i = 0; i < sizeof xyz / sizeof xyz[0]; ++i) {
        float x, y, X, Y, Z;
        ccl_XYZ_to_xy(xyz[i][0], xyz[i][1], xyz[i][2], &x, &y);
        ccl_xyY_to_XYZ(x, y, xyz[i][1], &X, &Y, &Z);
        CCL_CHECK_REL(X, xyz[i][0], 4e-7);
        CCL_CHECK(Y == xyz[i][1]);                                   /* Y passes through unchanged */
        CCL_CHECK_CLOSE(Z, xyz[i][2], 8e-7 * (xyz[i][0] + xyz[i][1] + xyz[i][2])); /* 1 - x - y cancels */
    }
}

static void test_XYZ_to_linear_srgb_white_point_both_variants(void)
{
    float r, g, b;
    ccl_XYZ_to_linear_srgb((float)WX, (float)WY, (float)WZ, CCL_VARIANT_CORRECTED, &r, &g, &b);
    CCL_CHECK_CLOSE(r, 1.0, 2e-6);
    CCL_CHECK_CLOSE(g, 1.0, 2e-6);
    CCL_CHECK_CLOSE(b, 1.0, 2e-6);
    ccl_XYZ_to_linear_srgb((float)WX, (float)WY, (float)WZ, CCL_VARIANT_THESIS, &r, &g, &b);
    CCL_CHECK_CLOSE(r, 1.0, 2e-6);
    CCL_CHECK_CLOSE(g, 1.0 + 0.03 * WX, 2e-6); /* 1.02851: the printed -0.9392660 adds 0.03 X to G */
    CCL_CHECK_CLOSE(g, 1.02851, 1e-5);
    CCL_CHECK_CLOSE(b, 1.0, 2e-6);
    /* columns of the matrix: unit X, Y, Z */
    ccl_XYZ_to_linear_srgb(1.0f, 0.0f, 0.0f, CCL_VARIANT_CORRECTED, &r, &g, &b);
    CCL_CHECK(r == 3.2404542f && g == -0.9692660f && b == 0.0556434f);
    ccl_XYZ_to_linear_srgb(1.0f, 0.0f, 0.0f, CCL_VARIANT_THESIS, &r, &g, &b);
    CCL_CHECK(r == 3.2404542f && g == -0.9392660f && b == 0.0556434f);
    ccl_XYZ_to_linear_srgb(0.0f, 1.0f, 0.0f, CCL_VARIANT_THESIS, &r, &g, &b);
    CCL_CHECK(r == -1.5371385f && g == 1.8760108f && b == -0.2040259f);
    ccl_XYZ_to_linear_srgb(0.0f, 0.0f, 1.0f, CCL_VARIANT_CORRECTED, &r, &g, &b);
    CCL_CHECK(r == -0.4985314f && g == 0.0415560f && b == 1.0572252f);
}

static void test_tonemap_exp_variants(void)
{
    CCL_CHECK(ccl_tonemap_exp(0.0f, 0.03f, CCL_VARIANT_CORRECTED) == 0.0f);
    CCL_CHECK_REL(ccl_tonemap_exp(100.0f, 0.03f, CCL_VARIANT_CORRECTED), 1.0 - exp(-3.0), 1e-6); /* 0.950213 */
    CCL_CHECK_REL(ccl_tonemap_exp(10.0f, 0.1f, CCL_VARIANT_CORRECTED), 1.0 - exp(-1.0), 1e-6);
    CCL_CHECK(ccl_tonemap_exp(1e4f, 0.03f, CCL_VARIANT_CORRECTED) == 1.0f); /* saturates, never exceeds 1 */
    /* as printed: 1 - exp(+k C) <= 0 for every C >= 0 */
    CCL_CHECK(ccl_tonemap_exp(0.0f, 0.03f, CCL_VARIANT_THESIS) == 0.0f);
    CCL_CHECK_REL(ccl_tonemap_exp(100.0f, 0.03f, CCL_VARIANT_THESIS), 1.0 - exp(3.0), 1e-6); /* -19.0855 */
    CCL_CHECK(ccl_tonemap_exp(0.5f, 0.03f, CCL_VARIANT_THESIS) < 0.0f);
    /* the printed form is the corrected one at -C */
    CCL_CHECK(ccl_tonemap_exp(7.0f, 0.03f, CCL_VARIANT_THESIS) == ccl_tonemap_exp(-7.0f, 0.03f, CCL_VARIANT_CORRECTED));
}

static void test_srgb_encode_values(void)
{
    CCL_CHECK(ccl_srgb_encode(0.0f) == 0.0f);
    CCL_CHECK_CLOSE(ccl_srgb_encode(1.0f), 1.0, 1e-7);
    CCL_CHECK_REL(ccl_srgb_encode(0.0031308f), 12.92 * 0.0031308, 1e-6);
    /* the two segments meet at 0.0031308 to within 1e-7 (IEC 61966-2-1 constants) */
    CCL_CHECK_CLOSE(1.055 * pow(0.0031308, 1.0 / 2.4) - 0.055, 12.92 * 0.0031308, 1e-7);
    CCL_CHECK_REL(ccl_srgb_encode(0.5f), 1.055 * pow(0.5, 1.0 / 2.4) - 0.055, 1e-6); /* 0.735357 */
    CCL_CHECK_REL(ccl_srgb_encode(0.18f), 1.055 * pow(0.18, 1.0 / 2.4) - 0.055, 1e-6);
    CCL_CHECK_REL(ccl_srgb_encode(-0.1f), -1.292, 1e-6);
}

static void test_colour_nan_propagates(void)
{
    float nan = (float)NAN, a, b, c;
    ccl_XYZ_to_xy(nan, 1.0f, 1.0f, &a, &b);
    CCL_CHECK(isnan(a) && isnan(b));
    ccl_xyY_to_XYZ(0.3f, 0.3f, nan, &a, &b, &c);
    CCL_CHECK(isnan(a) && isnan(b) && isnan(c));
    ccl_XYZ_to_linear_srgb(nan, 0.0f, 0.0f, CCL_VARIANT_CORRECTED, &a, &b, &c);
    CCL_CHECK(isnan(a) && isnan(b) && isnan(c));
    CCL_CHECK(isnan(ccl_tonemap_exp(nan, 0.03f, CCL_VARIANT_CORRECTED)));
    CCL_CHECK(isnan(ccl_tonemap_exp(nan, 0.03f, CCL_VARIANT_THESIS)));
    CCL_CHECK(isnan(ccl_srgb_encode(nan)));
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
