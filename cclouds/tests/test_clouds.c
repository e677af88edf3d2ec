/* C unit tests of cclouds/clouds.h: closed forms of the density model (vc-2.28 .. 2.30), the cataloguer's check values
 * of vc-2.29 and vc-4.7 (peaks of the unclamped and clamped gradients), the lighting energy vc-2.31, type blending,
 * relative height (both variants), compositing, the density pipeline and NaN propagation. */
#include "cclouds/clouds.h"
#include "cclouds/phase.h"
#include "ccl_test.h"

/* Maximum of the height gradient over h = i / 100000 and where it is. */
static void gradient_peak(float cloud_type, int clamp, double *peak, double *where)
{
    int i;
    *peak = -1.0;
    *where = -1.0;
    for (i = 0; i <= 100000; ++i) {
        float h = (float)(i / 100000.0);
        float v = ccl_clouds_height_gradient(h, cloud_type, clamp);
        if ((double)v > *peak) {
            *peak = (double)v;
            *where = (double)h;
        }
    }
}

static void test_base_shape_closed_form(void)
{
    float l = -1.0f, b = -1.0f;
    ccl_clouds_base_shape(0.5f, 0.3f, 0.2f, 0.1f, &l, &b);
    CCL_CHECK_REL(l, 0.625 * 0.3 + 0.25 * 0.2 + 0.125 * 0.1, 1e-6);
    CCL_CHECK_REL(b, (0.5 - (double)l + 1.0) / (2.0 - (double)l), 1e-6);
    ccl_clouds_base_shape(1.0f, 1.0f, 1.0f, 1.0f, &l, &b); /* weights sum to 1 */
    CCL_CHECK_CLOSE(l, 1.0, 0.0);
    CCL_CHECK_CLOSE(b, 1.0, 0.0);
    ccl_clouds_base_shape(0.0f, 1.0f, 1.0f, 1.0f, &l, &b); /* the only zero of B */
    CCL_CHECK_CLOSE(b, 0.0, 0.0);
    ccl_clouds_base_shape(0.0f, 0.0f, 0.0f, 0.0f, &l, &b); /* lower bound (1 - L) / (2 - L) = 1/2 */
    CCL_CHECK_CLOSE(b, 0.5, 1e-7);
}

static void test_coverage_check_values(void)
{
    /* cataloguer: B = 0.8, C := D_h: 0.15 at 0.2, 0.30 at 0.5, 0.233 at 0.7, 0 at 0.8, negative above */
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.8f, 1.0f, 0.2f, 0.2f, 1), 0.15, 1e-6);
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.8f, 1.0f, 0.5f, 0.5f, 1), 0.30, 1e-6);
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.8f, 1.0f, 0.7f, 0.7f, 1), 0.7 / 3.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.8f, 1.0f, 0.8f, 0.8f, 1), 0.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.8f, 1.0f, 0.9f, 0.9f, 0), -0.9, 1e-5);
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.8f, 1.0f, 0.9f, 0.9f, 1), 0.0, 0.0);
    /* C = 1: empty remap range -> 0, finite in both clamp modes */
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.8f, 1.0f, 1.0f, 1.0f, 0), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_coverage(1.0f, 1.0f, 1.0f, 1.0f, 1), 0.0, 0.0);
    /* explicit threshold and vertical profile: remap(0.5 * 1.5, 0.25, 1, 0, 1) * 0.6 = 0.4 */
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.5f, 1.5f, 0.6f, 0.25f, 1), 0.4, 1e-6);
    /* C = 0: B_D = B D_v D_h */
    CCL_CHECK_CLOSE(ccl_clouds_coverage(0.5f, 0.8f, 0.5f, 0.0f, 1), 0.2, 1e-7);
}

static void test_detail_erosion(void)
{
    /* H = 0.625 + 0.25 + 0.125 = 1 at C = (1, 1, 1): M = 1 - h_rel */
    CCL_CHECK_CLOSE(ccl_clouds_detail_erosion(0.6f, 1.0f, 1.0f, 1.0f, 0.0f, CCL_DETAIL_FORMULA, 1), (0.6 - 0.2) / 0.8,
                    1e-6);
    CCL_CHECK_CLOSE(ccl_clouds_detail_erosion(0.6f, 1.0f, 1.0f, 1.0f, 1.0f, CCL_DETAIL_FORMULA, 1), 0.6, 1e-6);
    /* prose direction swaps the ends */
    CCL_CHECK_CLOSE(ccl_clouds_detail_erosion(0.6f, 1.0f, 1.0f, 1.0f, 0.0f, CCL_DETAIL_PROSE, 1), 0.6, 1e-6);
    CCL_CHECK_CLOSE(ccl_clouds_detail_erosion(0.6f, 1.0f, 1.0f, 1.0f, 1.0f, CCL_DETAIL_PROSE, 1), 0.5, 1e-6);
    /* M = 0.5 at h_rel = 0.5 for any H: C = (B_D - 0.1) / 0.9 */
    CCL_CHECK_CLOSE(ccl_clouds_detail_erosion(0.55f, 0.3f, 0.7f, 0.1f, 0.5f, CCL_DETAIL_FORMULA, 1), 0.5, 1e-6);
    /* below the threshold 0.2 M: negative unless clamped */
    CCL_CHECK(ccl_clouds_detail_erosion(0.1f, 1.0f, 1.0f, 1.0f, 0.0f, CCL_DETAIL_FORMULA, 0) < 0.0f);
    CCL_CHECK_CLOSE(ccl_clouds_detail_erosion(0.1f, 1.0f, 1.0f, 1.0f, 0.0f, CCL_DETAIL_FORMULA, 1), 0.0, 0.0);
}

static void test_cloud_energy(void)
{
    const double a = 0.5;
    double dstar = 0.5 * log(1.0 + 2.0 / a), best = -1.0, best_d = -1.0;
    int i;
    CCL_CHECK_CLOSE(ccl_clouds_energy(0.0f, 1.0f, 0.3f, 0.2f), 0.0, 0.0); /* E = 0 at d = 0 */
    {
        /* the closed form in double: e^{-d a} HG(mu, g) (1 - e^{-2d}) at the float32 inputs mu = 0.3f, g = 0.2f */
        const double mu = (double)0.3f, g = (double)0.2f;
        const double hg = (1.0 - g * g) / (4.0 * 3.14159265358979323846 * pow(1.0 + g * g - 2.0 * g * mu, 1.5));
        CCL_CHECK_REL(ccl_clouds_energy(1.0f, 0.5f, 0.3f, 0.2f), exp(-0.5) * hg * (1.0 - exp(-2.0)), 1e-6);
    }
    for (i = 1; i <= 4000; ++i) {
        double e = (double)ccl_clouds_energy((float)(i * 0.001), (float)a, 1.0f, 0.5f);
        if (e > best) {
            best = e;
            best_d = i * 0.001;
        }
    }
    CCL_CHECK_CLOSE(best_d, dstar, 2e-3); /* maximum of Beer * powder at d* = ln(1 + 2/a) / 2 */
}

static void test_height_gradient_spec_values(void)
{
    double peak, where;
    gradient_peak(1.0f, 0, &peak, &where);
    CCL_CHECK_CLOSE(peak, 2.1764, 1e-4);
    CCL_CHECK_CLOSE(where, 0.48, 1e-3);
    gradient_peak(0.5f, 0, &peak, &where);
    CCL_CHECK_CLOSE(peak, 1.2190, 1e-4);
    CCL_CHECK_CLOSE(where, 0.33, 1e-3);
    gradient_peak(0.0f, 0, &peak, &where);
    CCL_CHECK_CLOSE(peak, 1.1281, 1e-4);
    CCL_CHECK_CLOSE(where, 0.105, 1e-3);
    gradient_peak(0.0f, 1, &peak, &where);
    CCL_CHECK_CLOSE(peak, 0.75, 1e-6);
    CCL_CHECK_CLOSE(where, 0.05, 1e-5);
    /* clamped plateaus */
    CCL_CHECK_CLOSE(ccl_clouds_height_gradient(0.45f, 1.0f, 1), 1.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_height_gradient(0.27f, 0.5f, 1), 1.0, 0.0);
    /* support (0.01, 0.95) for every type */
    CCL_CHECK_CLOSE(ccl_clouds_height_gradient(0.005f, 1.0f, 0), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_height_gradient(0.97f, 1.0f, 0), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_height_gradient(0.7f, 0.5f, 0), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_height_gradient(0.25f, 0.0f, 0), 0.0, 0.0);
    /* type 0.25: the mean of stratus and stratocumulus */
    CCL_CHECK_REL(ccl_clouds_height_gradient(0.1f, 0.25f, 0),
                  0.5 * ((double)ccl_clouds_height_gradient(0.1f, 0.0f, 0) +
                         (double)ccl_clouds_height_gradient(0.1f, 0.5f, 0)),
                  1e-6);
}

static void test_type_blend_and_composite(void)
{
    CCL_CHECK_CLOSE(ccl_clouds_type_blend(0.1f, 0.3f, 0.9f, 0.0f), 0.1f, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_type_blend(0.1f, 0.3f, 0.9f, 0.5f), 0.3f, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_type_blend(0.1f, 0.3f, 0.9f, 1.0f), 0.9f, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_type_blend(0.1f, 0.3f, 0.9f, 0.75f), 0.6, 1e-7);
    CCL_CHECK_CLOSE(ccl_clouds_composite(0.5f, 0.0f, 0.2f), 0.7, 1e-7);
    CCL_CHECK_CLOSE(ccl_clouds_composite(0.5f, 1.0f, 0.2f), 0.2f, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_composite(0.5f, 0.5f, 0.2f), 0.45, 1e-7);
}

static void test_relative_height_variants(void)
{
    CCL_CHECK_CLOSE(ccl_clouds_relative_height(6401.0f, 6401.0f, 6403.0f, CCL_VARIANT_CORRECTED), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_relative_height(6403.0f, 6401.0f, 6403.0f, CCL_VARIANT_CORRECTED), 1.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_relative_height(6402.5f, 6401.0f, 6403.0f, CCL_VARIANT_CORRECTED), 0.75, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_relative_height(6401.0f, 6401.0f, 6403.0f, CCL_VARIANT_THESIS), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_relative_height(6403.0f, 6401.0f, 6403.0f, CCL_VARIANT_THESIS), -1.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_relative_height(6402.5f, 6401.0f, 6403.0f, CCL_VARIANT_THESIS), -0.75, 0.0);
}

static void test_density_pipeline_and_light(void)
{
    float l, b, d_v, b_d, expect;
    /* the pipeline equals its parts */
    d_v = ccl_clouds_height_gradient(0.4f, 1.0f, 0);
    ccl_clouds_base_shape(0.9f, 0.3f, 0.3f, 0.3f, &l, &b);
    b_d = ccl_clouds_coverage(b, d_v, 0.5f, 0.5f, 1);
    expect = ccl_clouds_detail_erosion(b_d, 0.2f, 0.2f, 0.2f, 0.4f, CCL_DETAIL_FORMULA, 1);
    CCL_CHECK(ccl_clouds_density(0.5f, 1.0f, 0.4f, 0.9f, 0.3f, 0.3f, 0.3f, 0.2f, 0.2f, 0.2f, 0.4f, 0.5f, 0, 1,
                                 CCL_DETAIL_FORMULA) == expect);
    CCL_CHECK(expect > 0.0f);
    /* no coverage, or outside the gradient's support: no cloud */
    CCL_CHECK_CLOSE(ccl_clouds_density(0.0f, 1.0f, 0.4f, 0.9f, 0.3f, 0.3f, 0.3f, 0.2f, 0.2f, 0.2f, 0.4f, 0.0f, 0, 1,
                                       CCL_DETAIL_FORMULA), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_density(0.5f, 1.0f, 0.98f, 0.9f, 0.3f, 0.3f, 0.3f, 0.2f, 0.2f, 0.2f, 0.98f, 0.5f, 0, 1,
                                       CCL_DETAIL_FORMULA), 0.0, 0.0);
    /* lighting: at d = 0 only the ambient term, interpolated by height */
    CCL_CHECK_CLOSE(ccl_clouds_sample_light(0.0f, 1.0f, 0.5f, 0.0f, 0.2f, 1.0f, 0.006f, 0.012f), 0.006f, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_sample_light(0.0f, 1.0f, 0.5f, 1.0f, 0.2f, 1.0f, 0.006f, 0.012f), 0.012f, 0.0);
    CCL_CHECK_CLOSE(ccl_clouds_sample_light(0.0f, 1.0f, 0.5f, 0.5f, 0.2f, 1.0f, 0.006f, 0.012f), 0.009, 1e-9);
    CCL_CHECK_REL(ccl_clouds_sample_light(0.7f, 1.0f, 0.5f, 0.5f, 0.2f, 3.0f, 0.0f, 0.0f),
                  3.0 * (double)ccl_clouds_energy(0.7f, 1.0f, 0.5f, 0.2f), 1e-6);
}

static void test_clouds_nan_propagates(void)
{
    float nan = (float)NAN, l, b;
    ccl_clouds_base_shape(nan, 0.5f, 0.5f, 0.5f, &l, &b);
    CCL_CHECK(isnan(b));
    CCL_CHECK(isnan(ccl_clouds_coverage(nan, 1.0f, 0.5f, 0.5f, 1)));
    CCL_CHECK(isnan(ccl_clouds_detail_erosion(nan, 0.5f, 0.5f, 0.5f, 0.5f, CCL_DETAIL_FORMULA, 1)));
    CCL_CHECK(isnan(ccl_clouds_energy(nan, 1.0f, 0.5f, 0.2f)));
    CCL_CHECK(isnan(ccl_clouds_height_gradient(nan, 0.5f, 1)));
    CCL_CHECK(isnan(ccl_clouds_type_blend(0.1f, 0.2f, 0.3f, nan)));
    CCL_CHECK(isnan(ccl_clouds_composite(nan, 0.5f, 0.1f)));
    CCL_CHECK(isnan(ccl_clouds_relative_height(nan, 1.0f, 2.0f, CCL_VARIANT_CORRECTED)));
    CCL_CHECK(isnan(ccl_clouds_sample_light(0.5f, 1.0f, 0.5f, nan, 0.2f, 1.0f, 0.1f, 0.2f)));
}

int main(void)
{
    CCL_RUN(test_base_shape_closed_form);
    CCL_RUN(test_coverage_check_values);
    CCL_RUN(test_detail_erosion);
    CCL_RUN(test_cloud_energy);
    CCL_RUN(test_height_gradient_spec_values);
    CCL_RUN(test_type_blend_and_composite);
    CCL_RUN(test_relative_height_variants);
    CCL_RUN(test_density_pipeline_and_light);
    CCL_RUN(test_clouds_nan_propagates);
    return ccl_test_report();
}
