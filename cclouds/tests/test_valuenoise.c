/* C unit tests of cclouds/valuenoise.h: the lattice hash (oc-5.1.2), the smoothing kernels against their weights
 * written out (oc-5.1.3), the printed interpolants (oc-5.1.4.1 - 5.1.4.3: end points, the cosine's check values, the
 * cubic's slope -- not Catmull-Rom), the separable interpolation (oc-5.1.4), both persistence schedules (oc-5.1.2.2)
 * and the octave sum (oc-5.1.1). */
#include "cclouds/valuenoise.h"
#include "cclouds/hash.h"
#include "ccl_test.h"

static void test_lattice(void)
{
    int32_t x;
    double sum = 0.0;
    for (x = 0; x < 4096; ++x) {
        float u = ccl_valuenoise_lattice(x, 7, 3, 42u, CCL_VALUENOISE_UNIT);
        float s = ccl_valuenoise_lattice(x, 7, 3, 42u, CCL_VALUENOISE_SIGNED);
        CCL_CHECK(u >= 0.0f && u < 1.0f);
        CCL_CHECK(s == 2.0f * u - 1.0f && s >= -1.0f && s < 1.0f);
        CCL_CHECK(u == ccl_valuenoise_lattice(x, 7, 3, 42u, CCL_VALUENOISE_UNIT)); /* deterministic */
        sum += (double)u;
    }
    CCL_CHECK_CLOSE(sum / 4096.0, 0.5, 0.02);
    /* the formula of the header */
    CCL_CHECK(ccl_valuenoise_lattice(5, 6, 7, 9u, CCL_VALUENOISE_UNIT)
              == ccl_hash_unit(ccl_hash_pcg(5u + ccl_hash_pcg(6u + ccl_hash_pcg(7u + 9u)))));
    CCL_CHECK(ccl_valuenoise_lattice(5, 6, 7, 9u, 0) != ccl_valuenoise_lattice(5, 6, 7, 10u, 0));
}

static double lat2(int32_t x, int32_t y)
{
    return (double)ccl_valuenoise_lattice(x, y, 0, 11u, CCL_VALUENOISE_UNIT);
}

static void test_smoothing_weights(void)
{
    int32_t x = 20, y = 30;
    double corners = lat2(x - 1, y - 1) + lat2(x + 1, y - 1) + lat2(x - 1, y + 1) + lat2(x + 1, y + 1);
    double sides = lat2(x - 1, y) + lat2(x + 1, y) + lat2(x, y - 1) + lat2(x, y + 1);
    double centre = lat2(x, y);
    /* Elias: corners/16 + sides/8 + centre/4 */
    CCL_CHECK_CLOSE(ccl_valuenoise_smooth(x, y, 99, 11u, 2, CCL_VALUENOISE_SMOOTH_ELIAS, 0),
                    corners / 16 + sides / 8 + centre / 4, 1e-6);
    CCL_CHECK_CLOSE(ccl_valuenoise_smooth(x, y, 99, 11u, 2, CCL_VALUENOISE_SMOOTH_4, 0), sides / 4, 1e-6);
    CCL_CHECK_CLOSE(ccl_valuenoise_smooth(x, y, 99, 11u, 2, CCL_VALUENOISE_SMOOTH_8, 0), (sides + corners) / 8, 1e-6);
    CCL_CHECK(ccl_valuenoise_smooth(x, y, 99, 11u, 2, CCL_VALUENOISE_SMOOTH_NONE, 0) == (float)centre);
    /* 1-D Elias: v/2 + (l + r)/4; y, z ignored */
    CCL_CHECK_CLOSE(ccl_valuenoise_smooth(x, 5, 5, 11u, 1, CCL_VALUENOISE_SMOOTH_ELIAS, 0),
                    lat2(x, 0) / 2 + (lat2(x - 1, 0) + lat2(x + 1, 0)) / 4, 1e-6);
    /* 3-D: the weights sum to 1 -- a constant field stays constant is not testable with a hash, so check bounds */
    {
        float v = ccl_valuenoise_smooth(3, 4, 5, 1u, 3, CCL_VALUENOISE_SMOOTH_ELIAS, CCL_VALUENOISE_SIGNED);
        CCL_CHECK(v >= -1.0f && v <= 1.0f);
    }
}

static void test_interpolants(void)
{
    const float a = 0.1f, b = 0.7f;
    float x;
    /* end points exact (oc-5.1.4: x = 0 -> A, x = 1 -> B) */
    CCL_CHECK(ccl_valuenoise_linear(a, b, 0.0f) == a && ccl_valuenoise_linear(a, b, 1.0f) == b);
    CCL_CHECK(ccl_valuenoise_cosine(a, b, 0.0f) == a && ccl_valuenoise_cosine(a, b, 1.0f) == b);
    CCL_CHECK(ccl_valuenoise_cubic(0.3f, a, b, 0.2f, 0.0f) == a);
    CCL_CHECK_CLOSE(ccl_valuenoise_cubic(0.3f, a, b, 0.2f, 1.0f), b, 4e-7);
    /* cosine: (a + b)/2 at 1/2, the catalogue's check value */
    CCL_CHECK_CLOSE(ccl_valuenoise_cosine(a, b, 0.5f), 0.5 * ((double)a + (double)b), 6e-8);
    CCL_CHECK_CLOSE(ccl_valuenoise_cosine(0.0f, 1.0f, 0.25f), 0.1464466, 1e-7);
    for (x = 0.0f; x <= 1.0f; x += 0.125f)
        CCL_CHECK_CLOSE(ccl_valuenoise_cosine(0.0f, 1.0f, x), (1.0 - cos(3.1415927 * (double)x)) / 2.0, 2e-7);
    /* cubic: check values of the catalogue */
    CCL_CHECK_CLOSE(ccl_valuenoise_cubic(0.0f, 0.0f, 1.0f, 1.0f, 0.5f), 0.5, 0.0);
    for (x = 0.0f; x <= 1.0f; x += 0.125f)
        CCL_CHECK_CLOSE(ccl_valuenoise_cubic(0.0f, 1.0f, 0.0f, 1.0f, x),
                        (2.0 * (double)x - 3.0) * (double)x * (double)x + 1.0, 3e-7);
    /* the printed slope: v2 - v0 at 0, v3 - v1 at 1 (Catmull-Rom: half of that) */
    {
        const float v0 = 0.2f, v1 = 0.5f, v2 = 0.9f, v3 = 0.4f, h = 1.0f / 1024.0f;
        float c0 = ccl_valuenoise_cubic(v0, v1, v2, v3, 0.0f), ch = ccl_valuenoise_cubic(v0, v1, v2, v3, h);
        float c1 = ccl_valuenoise_cubic(v0, v1, v2, v3, 1.0f), c1h = ccl_valuenoise_cubic(v0, v1, v2, v3, 1.0f - h);
        double s0 = (double)((ch - c0) / h), s1 = (double)((c1 - c1h) / h);
        CCL_CHECK_CLOSE(s0, v2 - v0, 0.01);
        CCL_CHECK_CLOSE(s1, v3 - v1, 0.01);
        CCL_CHECK(fabs(s0 - 0.5 * (double)(v2 - v0)) > 0.3); /* not Catmull-Rom */
    }
}

static void test_interpolated(void)
{
    int k;
    for (k = 0; k < 3; ++k) {
        int dims = k + 1;
        /* at lattice points the interpolation returns the smoothed lattice value */
        CCL_CHECK(ccl_valuenoise_interpolated(12.0f, 7.0f, 3.0f, 5u, dims, 0, CCL_VALUENOISE_LINEAR, 0)
                  == ccl_valuenoise_smooth(12, 7, 3, 5u, dims, 0, 0));
        CCL_CHECK(ccl_valuenoise_interpolated(12.0f, 7.0f, 3.0f, 5u, dims, 0, CCL_VALUENOISE_COSINE, 0)
                  == ccl_valuenoise_smooth(12, 7, 3, 5u, dims, 0, 0));
        CCL_CHECK_CLOSE(ccl_valuenoise_interpolated(12.0f, 7.0f, 3.0f, 5u, dims, 0, CCL_VALUENOISE_CUBIC, 0),
                        ccl_valuenoise_smooth(12, 7, 3, 5u, dims, 0, 0), 1e-6);
    }
    /* 1-D linear between two nodes, written out */
    {
        float v1 = ccl_valuenoise_smooth(4, 0, 0, 5u, 1, 0, 0), v2 = ccl_valuenoise_smooth(5, 0, 0, 5u, 1, 0, 0);
        CCL_CHECK_CLOSE(ccl_valuenoise_interpolated(4.25f, 9.0f, 9.0f, 5u, 1, 0, 0, 0),
                        0.75 * (double)v1 + 0.25 * (double)v2, 1e-7);
    }
}

static void test_amplitudes_and_sum(void)
{
    int32_t i;
    double p = 0.6;
    for (i = 0; i < 6; ++i) {
        CCL_CHECK_CLOSE(ccl_valuenoise_amplitude(i, 0.6f, CCL_VARIANT_CORRECTED), pow(p, i), 1e-6);
        CCL_CHECK_CLOSE(ccl_valuenoise_amplitude(i, 0.6f, CCL_VARIANT_THESIS), pow(p, pow(2.0, i)), 1e-6);
    }
    CCL_CHECK(ccl_valuenoise_amplitude(0, 0.6f, CCL_VARIANT_CORRECTED) == 1.0f);
    CCL_CHECK(ccl_valuenoise_amplitude(0, 0.6f, CCL_VARIANT_THESIS) == 0.6f);
    /* one octave: the interpolated noise of the octave seed pcg(seed) + 0 */
    CCL_CHECK(ccl_valuenoise_fbm(3.3f, 1.7f, 0.0f, 8u, 2, 1, 0.5f, 0, 1, 0, 0)
              == ccl_valuenoise_interpolated(3.3f, 1.7f, 0.0f, ccl_hash_pcg(8u), 2, 0, 1, 0));
    /* normalised: stays in [0, 1] for linear */
    for (i = 0; i < 200; ++i) {
        float v = ccl_valuenoise_fbm(0.37f * (float)i, 0.11f * (float)i, 0.05f * (float)i, 3u, 3, 6, 0.5f, 0, 0, 0, 0);
        CCL_CHECK(v >= 0.0f && v <= 1.0f);
    }
}

int main(void)
{
    CCL_RUN(test_lattice);
    CCL_RUN(test_smoothing_weights);
    CCL_RUN(test_interpolants);
    CCL_RUN(test_interpolated);
    CCL_RUN(test_amplitudes_and_sum);
    return ccl_test_report();
}
