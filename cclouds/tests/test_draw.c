/* C unit tests of cclouds/draw.h and the pt fBm of noise.h: closed forms of pt-alg-3.3 / Kod 3.1 / Kod 3.2, the
 * nesting of the scalar domain warp, the fBm bound, butterfly symmetry. */
#include "cclouds/draw.h"
#include "cclouds/noise.h"
#include "ccl_test.h"

static void test_coords(void)
{
    ccl_vec2 p, polar, uv = ccl_draw_coords(V2(600.0f, 450.0f), V2(800.0f, 600.0f), CCL_DRAW_ASPECT_NONE, &p, &polar);
    CCL_CHECK(uv.x == 0.75f && uv.y == 0.75f && p.x == 0.5f && p.y == 0.5f);
    CCL_CHECK_CLOSE(polar.x, 0.70710678, 1e-6);
    CCL_CHECK_CLOSE(polar.y, 0.78539816, 1e-6);
    ccl_draw_coords(V2(800.0f, 300.0f), V2(800.0f, 600.0f), CCL_DRAW_ASPECT_X, &p, NULL);
    CCL_CHECK_CLOSE(p.x, 4.0 / 3.0, 1e-6);
}

static void test_curves(void)
{
    CCL_CHECK(ccl_draw_curves(V2(0.0f, 0.1f), 0.01f) == CCL_DRAW_RED);
    CCL_CHECK(ccl_draw_curves(V2(-0.9f + 0.63245553f, 0.0f), 0.01f) == CCL_DRAW_BLUE);
    CCL_CHECK(ccl_draw_curves(V2(0.0f, 0.0f), 0.01f) == CCL_DRAW_YELLOW);
    CCL_CHECK(ccl_draw_curves(V2(0.9f, -0.9f), 0.01f) == CCL_DRAW_BACKGROUND);
}

static void test_fbm_bound_and_marble(void)
{
    int i, oct;
    for (oct = 1; oct <= 8; ++oct) {
        double bound = 2.0 * (1.0 - pow(0.5, oct)), worst = 0.0;
        for (i = 0; i < 2000; ++i) {
            float v = ccl_noise_fbm_perlin2(V2(0.37f * (float)i - 300.0f, 0.113f * (float)i), oct, 0, 1.0f, 0.5f, 0.5f,
                                            2.0f);
            if (fabs((double)v) > worst) worst = fabs((double)v);
        }
        CCL_CHECK(worst <= bound);
    }
    {
        float f, comb, sine = ccl_draw_marble(V2(0.3f, -0.2f), 5, 0, &f, &comb);
        CCL_CHECK_CLOSE(sine, (1.0 + sin(50.0 * 0.3)) / 2.0, 1e-5);
        CCL_CHECK(f == ccl_noise_fbm_perlin2(V2(1.5f, -1.0f), 5, 0, 1.0f, 0.5f, 0.5f, 2.0f));
        CCL_CHECK(comb >= 0.0f && comb <= 1.0f);
    }
}

static void test_warp_nesting(void)
{
    ccl_vec2 p = V2(0.4f, -1.3f);
    float f0 = ccl_noise_fbm_perlin2(p, 4, 0, 1.0f, 0.5f, 0.5f, 2.0f);
    float f1 = ccl_noise_fbm_perlin2(V2(p.x + f0, p.y + f0), 4, 0, 1.0f, 0.5f, 0.5f, 2.0f);
    CCL_CHECK(ccl_draw_warp(p, 0, 4, 1.0f, 0, CCL_VARIANT_THESIS) == f0);
    CCL_CHECK(ccl_draw_warp(p, 1, 4, 1.0f, 0, CCL_VARIANT_THESIS) == f1);
    CCL_CHECK(ccl_draw_warp(p, 0, 4, 4.0f, 0, CCL_VARIANT_CORRECTED) == f0);
}

static void test_butterfly_symmetry(void)
{
    int i;
    for (i = 0; i < 50; ++i) {
        float x = -1.0f + 0.04f * (float)i, y = 0.3f - 0.02f * (float)i;
        ccl_vec3 a = ccl_draw_butterfly(V2(x, y), 0.0f), b = ccl_draw_butterfly(V2(-x, y), 0.0f);
        CCL_CHECK_CLOSE(a.x, b.x, 1e-6);
        CCL_CHECK_CLOSE(a.z, b.z, 1e-6);
    }
}

int main(void)
{
    CCL_RUN(test_coords);
    CCL_RUN(test_curves);
    CCL_RUN(test_fbm_bound_and_marble);
    CCL_RUN(test_warp_nesting);
    CCL_RUN(test_butterfly_symmetry);
    return ccl_test_report();
}
