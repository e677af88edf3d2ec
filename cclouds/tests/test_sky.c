/* C unit tests of cclouds/sky.h: turbidity (vc-2.33), CIE clear sky vs Perez (vc-2.35/2.36), the modified Perez
 * erratum (vc-2.37), zenith normalisation (vc-2.38, 4.2), the Preetham fits with their check values (vc-2.39-2.44),
 * the per-frame init and its validation, the Preetham and gradient sky per direction (vc-A29, vc-A28). */
#include "cclouds/sky.h"
#include "ccl_test.h"

#define PI_D 3.14159265358979323846
#define DEG(d) ((float)((d) * PI_D / 180.0))

static void test_turbidity_values(void)
{
    CCL_CHECK(ccl_turbidity(1.0f, 0.0f) == 1.0f); /* pure air */
    CCL_CHECK(ccl_turbidity(0.2f, 0.3f) == 2.5f);
    CCL_CHECK_REL(ccl_turbidity(0.1f, 0.9f), 10.0, 1e-6);
}

static void test_preetham_zenith_check_values_both_variants(void)
{
    /* spec vc-2.39..2.41 cataloguer check values (4.0453 corrected / 6.0453 as printed) */
    static const struct { double T, deg, Y, Y_thesis, x, y; } cases[] = {
        {2.0, 0.0, 15.5007, 32.8266, 0.26674, 0.27720},
        {2.0, 30.0, 5.8867, 10.8855, 0.25142, 0.25592},
        {3.0, 60.0, 5.1392, 7.9583, 0.24493, 0.25257},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        float Y, x, y, Yt, xt, yt;
        ccl_preetham_zenith((float)cases[i].T, DEG(cases[i].deg), CCL_VARIANT_CORRECTED, &Y, &x, &y);
        ccl_preetham_zenith((float)cases[i].T, DEG(cases[i].deg), CCL_VARIANT_THESIS, &Yt, &xt, &yt);
        CCL_CHECK_CLOSE(Y, cases[i].Y, 1e-4);
        CCL_CHECK_CLOSE(Yt, cases[i].Y_thesis, 1e-4);
        CCL_CHECK_CLOSE(x, cases[i].x, 1e-5);
        CCL_CHECK_CLOSE(y, cases[i].y, 1e-5);
        CCL_CHECK(x == xt && y == yt); /* the erratum only touches Y */
        CCL_CHECK(x == ccl_preetham_zenith_x((float)cases[i].T, DEG(cases[i].deg)));
        CCL_CHECK(y == ccl_preetham_zenith_y((float)cases[i].T, DEG(cases[i].deg)));
    }
}

static void test_preetham_perez_coefficients_at_T2(void)
{
    float A, B, C, D, E;
    ccl_preetham_perez_Y(2.0f, &A, &B, &C, &D, &E);
    CCL_CHECK_CLOSE(A, -1.1056, 1e-6); CCL_CHECK_CLOSE(B, -0.2833, 1e-6); CCL_CHECK_CLOSE(C, 5.2797, 1e-6);
    CCL_CHECK_CLOSE(D, -2.3359, 1e-6); CCL_CHECK_CLOSE(E, 0.2363, 1e-6);
    ccl_preetham_perez_x(2.0f, &A, &B, &C, &D, &E);
    CCL_CHECK_CLOSE(A, -0.2978, 1e-6); CCL_CHECK_CLOSE(B, -0.1322, 1e-6); CCL_CHECK_CLOSE(C, 0.2117, 1e-6);
    CCL_CHECK_CLOSE(D, -1.0271, 1e-6); CCL_CHECK_CLOSE(E, 0.0386, 1e-6);
    ccl_preetham_perez_y(2.0f, &A, &B, &C, &D, &E);
    CCL_CHECK_CLOSE(A, -0.2942, 1e-6); CCL_CHECK_CLOSE(B, -0.1808, 1e-6); CCL_CHECK_CLOSE(C, 0.1944, 1e-6);
    CCL_CHECK_CLOSE(D, -1.7419, 1e-6); CCL_CHECK_CLOSE(E, 0.0311, 1e-6);
}

static void test_perez_normalized_is_exact_at_zenith(void)
{
    float A, B, C, D, E, ts;
    int k;
    ccl_preetham_perez_Y(3.0f, &A, &B, &C, &D, &E);
    for (k = 0; k <= 9; ++k) {
        ts = DEG(10.0 * k);
        CCL_CHECK(ccl_perez_normalized(0.0f, ts, ts, 7.25f, A, B, C, D, E) == 7.25f);
        CCL_CHECK_REL(ccl_perez_zenith_factor(ts, 7.25f, A, B, C, D, E) * ccl_perez(0.0f, ts, A, B, C, D, E), 7.25,
                      3e-7);
    }
}

static void test_cie_clear_sky_equals_perez_with_exact_coefficients(void)
{
    const float ts = DEG(35.0);
    int i, j;
    CCL_CHECK(ccl_cie_clear_sky(0.0f, ts, ts, 3.0f) == 3.0f);
    for (i = 0; i <= 8; ++i) {
        for (j = 0; j <= 18; ++j) {
            float th = DEG(10.0 * i), g = DEG(10.0 * j);
            double ref = ccl_perez_normalized(th, g, ts, 1.0f, -1.0f, -0.32f, 10.0f / 0.91f, -3.0f, 0.45f / 0.91f);
            CCL_CHECK_REL(ccl_cie_clear_sky(th, g, ts, 1.0f), ref, 2e-6);
        }
    }
}

static void test_perez_cie_variants(void)
{
    /* corrected: the indicatrix 1 + C (exp(D g) - exp(D pi/2)) + E cos^2 g is exactly 1 at g = pi/2 (A = 0) */
    CCL_CHECK_CLOSE(ccl_perez_cie(0.3f, (float)(PI_D / 2), 0.0f, -0.32f, 10.0f, -3.0f, 0.45f, CCL_VARIANT_CORRECTED),
                    1.0, 1e-6);
    /* as printed: exp(D g pi/2) = exp(-3 pi^2/4) at g = pi/2 */
    CCL_CHECK_CLOSE(ccl_perez_cie(0.3f, (float)(PI_D / 2), 0.0f, -0.32f, 10.0f, -3.0f, 0.45f, CCL_VARIANT_THESIS),
                    1.0 + 10.0 * (exp(-1.5 * PI_D) - exp(-0.75 * PI_D * PI_D)), 1e-5);
    /* 1 - 10 exp(-3 pi/2) = 0.91017: the origin of the 0.91 of the CIE clear sky 2.35 */
    CCL_CHECK_CLOSE(ccl_perez_cie(0.0f, 0.0f, 0.0f, 0.0f, 10.0f, -3.0f, 0.0f, CCL_VARIANT_CORRECTED),
                    11.0 - 10.0 * exp(-1.5 * PI_D), 2e-6);
}

static void test_perez_horizon_clamp(void)
{
    float A, B, C, D, E;
    ccl_preetham_perez_Y(4.0f, &A, &B, &C, &D, &E);
    /* every direction at or below the horizon evaluates cos(theta) = 0.01 */
    CCL_CHECK(ccl_perez(2.5f, 1.0f, A, B, C, D, E) == ccl_perez((float)(PI_D / 2), 1.0f, A, B, C, D, E));
    CCL_CHECK(isfinite(ccl_perez((float)PI_D, 1.0f, A, B, C, D, E)));
    CCL_CHECK_REL(ccl_perez((float)(PI_D / 2), 1.0f, A, B, C, D, E),
                  (1.0 + A * exp(B / 0.01)) * (1.0 + C * exp(D * 1.0) + E * cos(1.0) * cos(1.0)), 2e-6);
}

static void test_preetham_init_validates(void)
{
    ccl_preetham p, q;
    q.turbidity = -1.0f;
    CCL_CHECK(ccl_preetham_init(3.0f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    CCL_CHECK(ccl_preetham_init(2.0f, 0.0f, 0.03f, CCL_VARIANT_THESIS, &p) == CCL_OK);
    CCL_CHECK(ccl_preetham_init(10.0f, (float)(PI_D / 2), 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    CCL_CHECK(ccl_preetham_init(1.99f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_preetham_init(10.01f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_preetham_init((float)NAN, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_preetham_init(3.0f, 1.58f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL); /* sun below */
    CCL_CHECK(ccl_preetham_init(3.0f, -0.01f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_preetham_init(3.0f, (float)NAN, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_preetham_init(3.0f, 0.5f, 0.0f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_preetham_init(3.0f, 0.5f, (float)INFINITY, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_preetham_init(3.0f, 0.5f, 0.03f, (ccl_variant)7, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_preetham_init(3.0f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, NULL) == CCL_EINVAL);
    CCL_CHECK(q.turbidity == -1.0f); /* untouched on error */
}

static void test_preetham_sky_zenith_and_horizon(void)
{
    ccl_preetham p;
    float sx, sy, sz, x, y, Y, zY, zx, zy, r, g, b, r2, g2, b2;
    ccl_sky_sun_direction(40.0f, 30.0f, &sx, &sy, &sz);
    CCL_CHECK(ccl_preetham_init(3.0f, DEG(50.0), 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    ccl_preetham_zenith(3.0f, DEG(50.0), CCL_VARIANT_CORRECTED, &zY, &zx, &zy);
    CCL_CHECK(p.zenith_Y == zY && p.zenith_x == zx && p.zenith_y == zy);
    /* looking straight up gives the zenith values (gamma = acos(s_y) ~ theta_s: a few ulp of acos/cos) */
    ccl_sky_preetham_xyY(0.0f, 1.0f, 0.0f, sx, sy, sz, &p, &x, &y, &Y);
    CCL_CHECK_REL(Y, zY, 2e-6);
    CCL_CHECK_REL(x, zx, 2e-6);
    CCL_CHECK_REL(y, zy, 2e-6);
    /* below the horizon cos(theta) is clamped to 0.01: two directions below the horizon with the same angle to the
     * sun (sun at the zenith, both at d . s = -0.6) give the same, finite, in-range colour */
    CCL_CHECK(ccl_preetham_init(3.0f, 0.0f, 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    ccl_sky_preetham_rgb(0.8f, -0.6f, 0.0f, 0.0f, 1.0f, 0.0f, &p, &r, &g, &b);
    ccl_sky_preetham_rgb(0.0f, -0.6f, 0.8f, 0.0f, 1.0f, 0.0f, &p, &r2, &g2, &b2);
    CCL_CHECK(r == r2 && g == g2 && b == b2);
    CCL_CHECK(isfinite(r) && r > 0.0f && g > 0.0f && b > 0.0f && r < 1.0f && g < 1.0f && b < 1.0f);
    /* the thesis variant of the whole chain: tone map 1 - exp(+kC) <= 0 everywhere */
    CCL_CHECK(ccl_preetham_init(3.0f, DEG(50.0), 0.03f, CCL_VARIANT_THESIS, &p) == CCL_OK);
    ccl_sky_preetham_rgb(0.0f, 1.0f, 0.0f, sx, sy, sz, &p, &r, &g, &b);
    CCL_CHECK(r < 0.0f && g < 0.0f && b < 0.0f);
}

static void test_sun_direction(void)
{
    float x, y, z;
    ccl_sky_sun_direction(0.0f, 0.0f, &x, &y, &z);
    CCL_CHECK(x == 0.0f && y == 0.0f && z == -1.0f);
    ccl_sky_sun_direction(0.0f, 90.0f, &x, &y, &z);
    CCL_CHECK_CLOSE(x, 1.0, 1e-7); CCL_CHECK_CLOSE(y, 0.0, 1e-7); CCL_CHECK_CLOSE(z, 0.0, 1e-7);
    ccl_sky_sun_direction(90.0f, 123.0f, &x, &y, &z);
    CCL_CHECK_CLOSE(x, 0.0, 1e-7); CCL_CHECK(y == 1.0f); CCL_CHECK_CLOSE(z, 0.0, 1e-7);
    ccl_sky_sun_direction(30.0f, 45.0f, &x, &y, &z);
    CCL_CHECK_CLOSE(x, cos(PI_D / 6) * sin(PI_D / 4), 1e-7);
    CCL_CHECK_CLOSE(y, 0.5, 1e-7);
    CCL_CHECK_CLOSE(z, -cos(PI_D / 6) * cos(PI_D / 4), 1e-7);
    CCL_CHECK_CLOSE(x * x + y * y + z * z, 1.0, 3e-7);
}

static void test_gradient_sky(void)
{
    ccl_sky_gradient g, bad;
    float r, gg, b, sx, sy, sz;
    ccl_sky_gradient_defaults(&g);
    bad.sun_exponent = -5.0f;
    ccl_sky_sun_direction(10.0f, 0.0f, &sx, &sy, &sz);
    /* zenith: the dark blue plus a negligible sun term (cos 80 deg ^ 64 < 1e-48) */
    ccl_sky_gradient_rgb(0.0f, 1.0f, 0.0f, sx, sy, sz, &g, &r, &gg, &b);
    CCL_CHECK_CLOSE(r, g.zenith[0], 1e-7);
    CCL_CHECK_CLOSE(gg, g.zenith[1], 1e-7);
    CCL_CHECK_CLOSE(b, g.zenith[2], 1e-7);
    /* horizon and below, facing away from the sun: the light blue */
    ccl_sky_gradient_rgb(0.0f, -0.6f, 0.8f, sx, sy, sz, &g, &r, &gg, &b);
    CCL_CHECK(r == g.horizon[0] && gg == g.horizon[1] && b == g.horizon[2]);
    /* at the sun the full sun colour is added */
    ccl_sky_gradient_rgb(sx, sy, sz, sx, sy, sz, &g, &r, &gg, &b);
    CCL_CHECK_CLOSE(r, g.horizon[0] + sy * (g.zenith[0] - g.horizon[0]) + g.sun[0], 1e-5);
    CCL_CHECK_CLOSE(b, g.horizon[2] + sy * (g.zenith[2] - g.horizon[2]) + g.sun[2], 1e-5);
    /* half the sun colour at cos(gamma) = 0.5^(1/64): gamma = 8.42 deg */
    CCL_CHECK_CLOSE(acos(pow(0.5, 1.0 / 64.0)) * 180.0 / PI_D, 8.42, 5e-3);
    CCL_CHECK(ccl_sky_gradient_init(0.5f, 0.6f, 0.9f, 0.1f, 0.2f, 0.6f, 1.0f, 1.0f, 1.0f, 32.0f, &g) == CCL_OK);
    CCL_CHECK(g.sun_exponent == 32.0f && g.zenith[2] == 0.6f);
    CCL_CHECK(ccl_sky_gradient_init(0.5f, 0.6f, 0.9f, 0.1f, 0.2f, 0.6f, 1.0f, 1.0f, 1.0f, 0.0f, &bad) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_gradient_init(-0.1f, 0.6f, 0.9f, 0.1f, 0.2f, 0.6f, 1.0f, 1.0f, 1.0f, 8.0f, &bad) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_gradient_init(0.5f, 0.6f, 0.9f, 0.1f, 0.2f, (float)NAN, 1.0f, 1.0f, 1.0f, 8.0f, &bad) ==
              CCL_EINVAL);
    CCL_CHECK(ccl_sky_gradient_init(0.5f, 0.6f, 0.9f, 0.1f, 0.2f, 0.6f, 1.0f, 1.0f, 1.0f, 8.0f, NULL) == CCL_EINVAL);
    CCL_CHECK(bad.sun_exponent == -5.0f);
}

static void test_sky_nan_propagates(void)
{
    float nan = (float)NAN, r, g, b;
    ccl_preetham p;
    CCL_CHECK(isnan(ccl_perez(nan, 0.5f, -1.0f, -0.3f, 5.0f, -2.0f, 0.3f)));
    CCL_CHECK(isnan(ccl_perez(0.5f, 0.5f, -1.0f, nan, 5.0f, -2.0f, 0.3f)));
    CCL_CHECK(isnan(ccl_cie_clear_sky(nan, 0.5f, 0.5f, 1.0f)));
    CCL_CHECK(isnan(ccl_perez_cie(0.5f, nan, -1.0f, -0.3f, 5.0f, -2.0f, 0.3f, CCL_VARIANT_CORRECTED)));
    CCL_CHECK(isnan(ccl_preetham_zenith_x(nan, 0.5f)));
    CCL_CHECK(isnan(ccl_turbidity(nan, 0.5f)));
    CCL_CHECK(ccl_preetham_init(3.0f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    ccl_sky_preetham_rgb(nan, 0.5f, 0.5f, 0.0f, 1.0f, 0.0f, &p, &r, &g, &b);
    CCL_CHECK(isnan(r) && isnan(g) && isnan(b));
}

int main(void)
{
    CCL_RUN(test_turbidity_values);
    CCL_RUN(test_preetham_zenith_check_values_both_variants);
    CCL_RUN(test_preetham_perez_coefficients_at_T2);
    CCL_RUN(test_perez_normalized_is_exact_at_zenith);
    CCL_RUN(test_cie_clear_sky_equals_perez_with_exact_coefficients);
    CCL_RUN(test_perez_cie_variants);
    CCL_RUN(test_perez_horizon_clamp);
    CCL_RUN(test_preetham_init_validates);
    CCL_RUN(test_preetham_sky_zenith_and_horizon);
    CCL_RUN(test_sun_direction);
    CCL_RUN(test_gradient_sky);
    CCL_RUN(test_sky_nan_propagates);
    return ccl_test_report();
}
