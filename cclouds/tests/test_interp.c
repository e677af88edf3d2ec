/* C unit tests of cclouds/interp.h: the fades against their closed forms (vc-2.19, vc-2.20), their boundary values,
 * symmetry and flatness at the ends, lerp and cosine interpolation (vc-A1), remap (vc-2.27), NaN propagation. */
#include "cclouds/interp.h"
#include "ccl_test.h"

#include <float.h>

static void test_fades_closed_form(void)
{
    float t;
    CCL_CHECK(ccl_interp_fade_cubic(0.0f) == 0.0f && ccl_interp_fade_cubic(1.0f) == 1.0f);
    CCL_CHECK(ccl_interp_fade_cubic(0.5f) == 0.5f);
    CCL_CHECK(ccl_interp_fade_quintic(0.0f) == 0.0f && ccl_interp_fade_quintic(1.0f) == 1.0f);
    CCL_CHECK(ccl_interp_fade_quintic(0.5f) == 0.5f);
    for (t = 0.0f; t <= 1.0f; t += 0.0625f) {
        double td = (double)t;
        CCL_CHECK_CLOSE(ccl_interp_fade_cubic(t), 3 * td * td - 2 * td * td * td, 4e-7);
        CCL_CHECK_CLOSE(ccl_interp_fade_quintic(t),
                        6 * td * td * td * td * td - 15 * td * td * td * td + 10 * td * td * td, 2e-6);
        /* symmetry f(1 - t) = 1 - f(t) */
        CCL_CHECK_CLOSE(ccl_interp_fade_cubic(1.0f - t), 1.0 - (double)ccl_interp_fade_cubic(t), 4e-7);
        CCL_CHECK_CLOSE(ccl_interp_fade_quintic(1.0f - t), 1.0 - (double)ccl_interp_fade_quintic(t), 2e-6);
    }
    /* cubic: f = 3 t^2 - 2 t^3 near 0 (f' = 0, f'' = 6); quintic: f = 10 t^3 - 15 t^4 + 6 t^5 (f' = f'' = 0); near 0
     * the Horner forms keep a relative error of <= 3 (cubic) and <= 7 (quintic) roundings of FLT_EPSILON / 2 */
    {
        const double d = (double)1e-3f;
        CCL_CHECK_REL(ccl_interp_fade_cubic(1e-3f), 3 * d * d - 2 * d * d * d, 2.0 * (double)FLT_EPSILON);
        CCL_CHECK_REL(ccl_interp_fade_quintic(1e-3f), 10 * d * d * d - 15 * d * d * d * d + 6 * d * d * d * d * d,
                      4.0 * (double)FLT_EPSILON);
    }
}

static void test_lerp_and_cosine(void)
{
    CCL_CHECK_CLOSE(ccl_interp_lerp(0.25f, 2.0f, 6.0f), 3.0, 0.0);
    CCL_CHECK(ccl_interp_lerp(0.0f, 2.0f, 6.0f) == 2.0f && ccl_interp_lerp(1.0f, 2.0f, 6.0f) == 6.0f);
    CCL_CHECK_CLOSE(ccl_interp_lerp(1.5f, 0.0f, 2.0f), 3.0, 0.0); /* extrapolates */
    CCL_CHECK(ccl_interp_cosine(0.0f, 2.0f, 6.0f) == 2.0f);
    CCL_CHECK_CLOSE(ccl_interp_cosine(0.5f, 0.0f, 1.0f), 0.5, 1e-7);
    CCL_CHECK_CLOSE(ccl_interp_cosine(1.0f, 2.0f, 6.0f), 6.0, 1e-6);
    /* (1 - cos(pi / 3)) / 2 = 1/4 */
    CCL_CHECK_CLOSE(ccl_interp_cosine(1.0f / 3.0f, 0.0f, 4.0f), 1.0, 1e-6);
}

static void test_remap(void)
{
    CCL_CHECK_CLOSE(ccl_interp_remap(0.0f, 0.0f, 1.0f, 2.0f, 4.0f), 2.0, 0.0);
    CCL_CHECK_CLOSE(ccl_interp_remap(1.0f, 0.0f, 1.0f, 2.0f, 4.0f), 4.0, 0.0);
    CCL_CHECK_CLOSE(ccl_interp_remap(2.0f, 0.0f, 1.0f, 2.0f, 4.0f), 6.0, 0.0);   /* unclamped */
    CCL_CHECK_CLOSE(ccl_interp_remap(0.25f, 0.0f, 1.0f, 1.0f, 0.0f), 0.75, 0.0); /* reversed */
    CCL_CHECK_CLOSE(ccl_interp_remap(-0.5f, -1.0f, 1.0f, 0.0f, 1.0f), 0.25, 0.0);
}

static void test_interp_nan_propagates(void)
{
    float nan = (float)NAN;
    CCL_CHECK(isnan(ccl_interp_fade_quintic(nan)) && isnan(ccl_interp_fade_cubic(nan)));
    CCL_CHECK(isnan(ccl_interp_lerp(nan, 0.0f, 1.0f)) && isnan(ccl_interp_cosine(nan, 0.0f, 1.0f)));
    CCL_CHECK(isnan(ccl_interp_lerp(0.5f, nan, 1.0f)) && isnan(ccl_interp_cosine(0.5f, 0.0f, nan)));
    CCL_CHECK(isnan(ccl_interp_remap(nan, 0.0f, 1.0f, 0.0f, 1.0f)));
}

int main(void)
{
    CCL_RUN(test_fades_closed_form);
    CCL_RUN(test_lerp_and_cosine);
    CCL_RUN(test_remap);
    CCL_RUN(test_interp_nan_propagates);
    return ccl_test_report();
}
