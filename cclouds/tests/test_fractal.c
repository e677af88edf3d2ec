/* C unit tests of cclouds/fractal.h: known members and exact escape counts, the mirrored thesis sign. */
#include "cclouds/fractal.h"
#include "ccl_test.h"

static void test_mandelbrot(void)
{
    float s;
    CCL_CHECK(ccl_fractal_mandelbrot(V2(0.0f, 0.0f), 1000, 2.0f, CCL_VARIANT_CORRECTED, &s) == 1000 && s == 1000.0f);
    CCL_CHECK(ccl_fractal_mandelbrot(V2(-2.0f, 0.0f), 1000, 2.0f, CCL_VARIANT_CORRECTED, NULL) == 1000);
    CCL_CHECK(ccl_fractal_mandelbrot(V2(0.0f, 1.0f), 1000, 2.0f, CCL_VARIANT_CORRECTED, NULL) == 1000);
    CCL_CHECK(ccl_fractal_mandelbrot(V2(1.0f, 0.0f), 1000, 2.0f, CCL_VARIANT_CORRECTED, NULL) == 3);
    CCL_CHECK(ccl_fractal_mandelbrot(V2(1.0f, 1.0f), 1000, 2.0f, CCL_VARIANT_CORRECTED, NULL) == 2);
    /* printed x^2 - mu: the mirrored set */
    CCL_CHECK(ccl_fractal_mandelbrot(V2(2.0f, 0.0f), 1000, 2.0f, CCL_VARIANT_THESIS, NULL) == 1000);
    CCL_CHECK(ccl_fractal_mandelbrot(V2(-1.0f, 0.0f), 1000, 2.0f, CCL_VARIANT_THESIS, NULL) == 3);
    {
        ccl_vec2 f = ccl_fractal_quadratic(V2(1.0f, 2.0f), V2(0.5f, -1.0f), CCL_VARIANT_THESIS);
        CCL_CHECK(f.x == -3.5f && f.y == 5.0f);
    }
}

static void test_julia(void)
{
    float s;
    CCL_CHECK(ccl_fractal_julia(V2(0.5f, 0.0f), V2(0.0f, 0.0f), 2, 500, 16.0f, CCL_FRACTAL_POLY, NULL) == 500);
    CCL_CHECK(ccl_fractal_julia(V2(1.5f, 0.0f), V2(0.0f, 0.0f), 2, 500, 16.0f, CCL_FRACTAL_POLY, &s) == 3);
    CCL_CHECK_CLOSE(s, 3.5, 0.5); /* the smooth count lies in [n, n + 1] */
    CCL_CHECK(ccl_fractal_julia(V2(1.1f, 0.0f), V2(0.0f, 0.0f), 5, 500, 16.0f, CCL_FRACTAL_POLY, NULL) == 3);
    CCL_CHECK(ccl_fractal_julia(V2(0.0f, 0.0f), V2(-0.65f, 0.0f), 2, 100, 50.0f, CCL_FRACTAL_EXP, NULL) == 6);
    CCL_CHECK(ccl_fractal_julia_example(V2(0.0f, 0.0f), 100, CCL_JULIA_EXP, NULL) == 6);
}

int main(void)
{
    CCL_RUN(test_mandelbrot);
    CCL_RUN(test_julia);
    return ccl_test_report();
}
