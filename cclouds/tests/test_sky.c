/* C unit tests of cclouds/sky.h: turbidity (vc-2.33), CIE clear sky vs Perez (vc-2.35/2.36), the modified Perez
 * erratum (vc-2.37), zenith normalisation (vc-2.38, 4.2), the Preetham fits with their check values (vc-2.39-2.44),
 * the per-frame init and its validation, the Preetham and gradient sky per direction (vc-A29, vc-A28). */
#include "cclouds/sky.h"
#include "ccl_test.h"

#define PI_D 3.14159265358979323846
#define DEG(d) ((float)((d) * PI_D / 180.0))

static void test_turbidity_values(void)
{
    CCL_CHECK(ccl_sky_turbidity(1.0f, 0.0f) == 1.0f); /* pure air */
    CCL_CHECK(ccl_sky_turbidity(0.2f, 0.3f) == 2.5f);
    CCL_CHECK_REL(ccl_sky_turbidity(0.1f, 0.9f), 10.0, 1e-6);
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
        const ccl_vec3 c = ccl_sky_preetham_zenith((float)cases[i].T, DEG(cases[i].deg), CCL_VARIANT_CORRECTED);
        const ccl_vec3 t = ccl_sky_preetham_zenith((float)cases[i].T, DEG(cases[i].deg), CCL_VARIANT_THESIS);
        const float x = c.x, y = c.y, Y = c.z, xt = t.x, yt = t.y, Yt = t.z;
        CCL_CHECK_CLOSE(Y, cases[i].Y, 1e-4);
        CCL_CHECK_CLOSE(Yt, cases[i].Y_thesis, 1e-4);
        CCL_CHECK_CLOSE(x, cases[i].x, 1e-5);
        CCL_CHECK_CLOSE(y, cases[i].y, 1e-5);
        CCL_CHECK(x == xt && y == yt); /* the erratum only touches Y */
        CCL_CHECK(x == ccl_sky_preetham_zenith_x((float)cases[i].T, DEG(cases[i].deg)));
        CCL_CHECK(y == ccl_sky_preetham_zenith_y((float)cases[i].T, DEG(cases[i].deg)));
    }
}

static void test_preetham_perez_coefficients_at_T2(void)
{
    float A, B, C, D, E;
    ccl_sky_preetham_perez_Y(2.0f, &A, &B, &C, &D, &E);
    CCL_CHECK_CLOSE(A, -1.1056, 1e-6); CCL_CHECK_CLOSE(B, -0.2833, 1e-6); CCL_CHECK_CLOSE(C, 5.2797, 1e-6);
    CCL_CHECK_CLOSE(D, -2.3359, 1e-6); CCL_CHECK_CLOSE(E, 0.2363, 1e-6);
    ccl_sky_preetham_perez_x(2.0f, &A, &B, &C, &D, &E);
    CCL_CHECK_CLOSE(A, -0.2978, 1e-6); CCL_CHECK_CLOSE(B, -0.1322, 1e-6); CCL_CHECK_CLOSE(C, 0.2117, 1e-6);
    CCL_CHECK_CLOSE(D, -1.0271, 1e-6); CCL_CHECK_CLOSE(E, 0.0386, 1e-6);
    ccl_sky_preetham_perez_y(2.0f, &A, &B, &C, &D, &E);
    CCL_CHECK_CLOSE(A, -0.2942, 1e-6); CCL_CHECK_CLOSE(B, -0.1808, 1e-6); CCL_CHECK_CLOSE(C, 0.1944, 1e-6);
    CCL_CHECK_CLOSE(D, -1.7419, 1e-6); CCL_CHECK_CLOSE(E, 0.0311, 1e-6);
}

static void test_perez_normalized_is_exact_at_zenith(void)
{
    float A, B, C, D, E, ts;
    int k;
    ccl_sky_preetham_perez_Y(3.0f, &A, &B, &C, &D, &E);
    for (k = 0; k <= 9; ++k) {
        ts = DEG(10.0 * k);
        CCL_CHECK(ccl_sky_perez_normalized(0.0f, ts, ts, 7.25f, A, B, C, D, E) == 7.25f);
        CCL_CHECK_REL(ccl_sky_perez_zenith_factor(ts, 7.25f, A, B, C, D, E) * ccl_sky_perez(0.0f, ts, A, B, C, D, E),
                      7.25, 3e-7);
    }
}

static void test_cie_clear_sky_equals_perez_with_exact_coefficients(void)
{
    const float ts = DEG(35.0);
    int i, j;
    CCL_CHECK(ccl_sky_cie_clear(0.0f, ts, ts, 3.0f) == 3.0f);
    for (i = 0; i <= 8; ++i) {
        for (j = 0; j <= 18; ++j) {
            float th = DEG(10.0 * i), g = DEG(10.0 * j);
            double ref = (double)ccl_sky_perez_normalized(th, g, ts, 1.0f, -1.0f, -0.32f, 10.0f / 0.91f, -3.0f,
                                                          0.45f / 0.91f);
            CCL_CHECK_REL(ccl_sky_cie_clear(th, g, ts, 1.0f), ref, 2e-6);
        }
    }
}

static void test_perez_cie_variants(void)
{
    /* corrected: the indicatrix 1 + C (exp(D g) - exp(D pi/2)) + E cos^2 g is exactly 1 at g = pi/2 (A = 0) */
    CCL_CHECK_CLOSE(
        ccl_sky_perez_cie(0.3f, (float)(PI_D / 2), 0.0f, -0.32f, 10.0f, -3.0f, 0.45f, CCL_VARIANT_CORRECTED), 1.0,
        1e-6);
    /* as printed: exp(D g pi/2) = exp(-3 pi^2/4) at g = pi/2 */
    CCL_CHECK_CLOSE(ccl_sky_perez_cie(0.3f, (float)(PI_D / 2), 0.0f, -0.32f, 10.0f, -3.0f, 0.45f, CCL_VARIANT_THESIS),
                    1.0 + 10.0 * (exp(-1.5 * PI_D) - exp(-0.75 * PI_D * PI_D)), 1e-5);
    /* 1 - 10 exp(-3 pi/2) = 0.91017: the origin of the 0.91 of the CIE clear sky 2.35 */
    CCL_CHECK_CLOSE(ccl_sky_perez_cie(0.0f, 0.0f, 0.0f, 0.0f, 10.0f, -3.0f, 0.0f, CCL_VARIANT_CORRECTED),
                    11.0 - 10.0 * exp(-1.5 * PI_D), 2e-6);
}

static void test_perez_horizon_clamp(void)
{
    float A, B, C, D, E;
    ccl_sky_preetham_perez_Y(4.0f, &A, &B, &C, &D, &E);
    /* every direction at or below the horizon evaluates cos(theta) = 0.01 */
    CCL_CHECK(ccl_sky_perez(2.5f, 1.0f, A, B, C, D, E) == ccl_sky_perez((float)(PI_D / 2), 1.0f, A, B, C, D, E));
    CCL_CHECK(isfinite(ccl_sky_perez((float)PI_D, 1.0f, A, B, C, D, E)));
    CCL_CHECK_REL(ccl_sky_perez((float)(PI_D / 2), 1.0f, A, B, C, D, E),
                  (1.0 + (double)A * exp((double)B / 0.01)) *
                      (1.0 + (double)C * exp((double)D * 1.0) + (double)E * cos(1.0) * cos(1.0)), 2e-6);
}

static void test_preetham_init_validates(void)
{
    ccl_preetham p, q;
    q.turbidity = -1.0f;
    CCL_CHECK(ccl_sky_preetham_init(3.0f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    CCL_CHECK(ccl_sky_preetham_init(2.0f, 0.0f, 0.03f, CCL_VARIANT_THESIS, &p) == CCL_OK);
    CCL_CHECK(ccl_sky_preetham_init(10.0f, (float)(PI_D / 2), 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    CCL_CHECK(ccl_sky_preetham_init(1.99f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_preetham_init(10.01f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_preetham_init((float)NAN, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_preetham_init(3.0f, 1.58f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL); /* sun below */
    CCL_CHECK(ccl_sky_preetham_init(3.0f, -0.01f, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_preetham_init(3.0f, (float)NAN, 0.03f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_preetham_init(3.0f, 0.5f, 0.0f, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_preetham_init(3.0f, 0.5f, (float)INFINITY, CCL_VARIANT_CORRECTED, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_preetham_init(3.0f, 0.5f, 0.03f, (ccl_variant)7, &q) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_preetham_init(3.0f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, NULL) == CCL_EINVAL);
    CCL_CHECK(q.turbidity == -1.0f); /* untouched on error */
}

static void test_preetham_sky_zenith_and_horizon(void)
{
    ccl_preetham p;
    const ccl_vec3 sun = ccl_sky_sun_direction(40.0f, 30.0f), up = V(0.0f, 1.0f, 0.0f);
    ccl_vec3 z, c, c2;
    CCL_CHECK(ccl_sky_preetham_init(3.0f, DEG(50.0), 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    z = ccl_sky_preetham_zenith(3.0f, DEG(50.0), CCL_VARIANT_CORRECTED);
    CCL_CHECK(p.zenith_Y == z.z && p.zenith_x == z.x && p.zenith_y == z.y);
    /* looking straight up gives the zenith values (gamma = acos(s_y) ~ theta_s: a few ulp of acos/cos) */
    c = ccl_sky_preetham_xyY(up, sun, &p);
    CCL_CHECK_REL(c.z, z.z, 2e-6);
    CCL_CHECK_REL(c.x, z.x, 2e-6);
    CCL_CHECK_REL(c.y, z.y, 2e-6);
    /* the element-wise form gives the same as init + per-pixel (theta_s = 90 - 40 deg in float) */
    c2 = ccl_sky_preetham_colour(V(0.0f, 2.0f, 0.0f), 3.0f, 40.0f, 30.0f, 0.03f, CCL_VARIANT_CORRECTED,
                                 CCL_SKY_PREETHAM_XYY);
    CCL_CHECK_REL(c2.z, z.z, 2e-6);
    CCL_CHECK_REL(c2.x, z.x, 2e-6);
    /* below the horizon cos(theta) is clamped to 0.01: two directions below the horizon with the same angle to the
     * sun (sun at the zenith, both at d . s = -0.6) give the same, finite, in-range colour */
    CCL_CHECK(ccl_sky_preetham_init(3.0f, 0.0f, 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    c = ccl_sky_preetham_rgb(V(0.8f, -0.6f, 0.0f), up, &p);
    c2 = ccl_sky_preetham_rgb(V(0.0f, -0.6f, 0.8f), up, &p);
    CCL_CHECK(c.x == c2.x && c.y == c2.y && c.z == c2.z);
    CCL_CHECK(isfinite(c.x) && c.x > 0.0f && c.y > 0.0f && c.z > 0.0f && c.x < 1.0f && c.y < 1.0f && c.z < 1.0f);
    /* the thesis variant of the whole chain: tone map 1 - exp(+kC) <= 0 everywhere */
    CCL_CHECK(ccl_sky_preetham_init(3.0f, DEG(50.0), 0.03f, CCL_VARIANT_THESIS, &p) == CCL_OK);
    c = ccl_sky_preetham_rgb(up, sun, &p);
    CCL_CHECK(c.x < 0.0f && c.y < 0.0f && c.z < 0.0f);
}

static void test_sun_direction(void)
{
    ccl_vec3 s = ccl_sky_sun_direction(0.0f, 0.0f);
    CCL_CHECK(s.x == 0.0f && s.y == 0.0f && s.z == -1.0f);
    s = ccl_sky_sun_direction(0.0f, 90.0f);
    CCL_CHECK_CLOSE(s.x, 1.0, 1e-7); CCL_CHECK_CLOSE(s.y, 0.0, 1e-7); CCL_CHECK_CLOSE(s.z, 0.0, 1e-7);
    s = ccl_sky_sun_direction(90.0f, 123.0f);
    CCL_CHECK_CLOSE(s.x, 0.0, 1e-7); CCL_CHECK(s.y == 1.0f); CCL_CHECK_CLOSE(s.z, 0.0, 1e-7);
    s = ccl_sky_sun_direction(30.0f, 45.0f);
    CCL_CHECK_CLOSE(s.x, cos(PI_D / 6) * sin(PI_D / 4), 1e-7);
    CCL_CHECK_CLOSE(s.y, 0.5, 1e-7);
    CCL_CHECK_CLOSE(s.z, -cos(PI_D / 6) * cos(PI_D / 4), 1e-7);
    CCL_CHECK_CLOSE(s.x * s.x + s.y * s.y + s.z * s.z, 1.0, 3e-7);
}

static void test_gradient_sky(void)
{
    ccl_sky_gradient g, bad;
    const ccl_vec3 sun = ccl_sky_sun_direction(10.0f, 0.0f);
    const ccl_vec3 h = V(0.5f, 0.6f, 0.9f), z = V(0.1f, 0.2f, 0.6f), s = V(1.0f, 1.0f, 1.0f);
    ccl_vec3 c;
    ccl_sky_gradient_defaults(&g);
    bad.sun_exponent = -5.0f;
    /* zenith: the dark blue plus a negligible sun term (cos 80 deg ^ 64 < 1e-48) */
    c = ccl_sky_gradient_rgb(V(0.0f, 1.0f, 0.0f), sun, &g);
    CCL_CHECK_CLOSE(c.x, g.zenith[0], 1e-7);
    CCL_CHECK_CLOSE(c.y, g.zenith[1], 1e-7);
    CCL_CHECK_CLOSE(c.z, g.zenith[2], 1e-7);
    /* horizon and below, facing away from the sun: the light blue */
    c = ccl_sky_gradient_rgb(V(0.0f, -0.6f, 0.8f), sun, &g);
    CCL_CHECK(c.x == g.horizon[0] && c.y == g.horizon[1] && c.z == g.horizon[2]);
    /* at the sun the full sun colour is added */
    c = ccl_sky_gradient_rgb(sun, sun, &g);
    CCL_CHECK_CLOSE(c.x, g.horizon[0] + sun.y * (g.zenith[0] - g.horizon[0]) + g.sun[0], 1e-5);
    CCL_CHECK_CLOSE(c.z, g.horizon[2] + sun.y * (g.zenith[2] - g.horizon[2]) + g.sun[2], 1e-5);
    /* the element-wise form with the default colours: the same colour for a non-normalised direction */
    c = ccl_sky_gradient_colour(V(0.0f, 3.0f, 0.0f), 10.0f, 0.0f, V(0.66f, 0.78f, 0.94f),
                                V(0.16f, 0.34f, 0.72f), V(1.0f, 0.9f, 0.7f), 64.0f, CCL_SKY_GRADIENT_LINEAR);
    CCL_CHECK_CLOSE(c.x, g.zenith[0], 1e-7);
    CCL_CHECK_CLOSE(c.z, g.zenith[2], 1e-7);
    /* half the sun colour at cos(gamma) = 0.5^(1/64): gamma = 8.42 deg */
    CCL_CHECK_CLOSE(acos(pow(0.5, 1.0 / 64.0)) * 180.0 / PI_D, 8.42, 5e-3);
    CCL_CHECK(ccl_sky_gradient_init(h, z, s, 32.0f, &g) == CCL_OK);
    CCL_CHECK(g.sun_exponent == 32.0f && g.zenith[2] == 0.6f);
    CCL_CHECK(ccl_sky_gradient_init(h, z, s, 0.0f, &bad) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_gradient_init(V(-0.1f, 0.6f, 0.9f), z, s, 8.0f, &bad) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_gradient_init(h, V(0.1f, 0.2f, (float)NAN), s, 8.0f, &bad) == CCL_EINVAL);
    CCL_CHECK(ccl_sky_gradient_init(h, z, s, 8.0f, NULL) == CCL_EINVAL);
    CCL_CHECK(bad.sun_exponent == -5.0f);
}

static void test_sky_nan_propagates(void)
{
    float nan = (float)NAN;
    ccl_preetham p;
    ccl_vec3 c;
    CCL_CHECK(isnan(ccl_sky_perez(nan, 0.5f, -1.0f, -0.3f, 5.0f, -2.0f, 0.3f)));
    CCL_CHECK(isnan(ccl_sky_perez(0.5f, 0.5f, -1.0f, nan, 5.0f, -2.0f, 0.3f)));
    CCL_CHECK(isnan(ccl_sky_cie_clear(nan, 0.5f, 0.5f, 1.0f)));
    CCL_CHECK(isnan(ccl_sky_perez_cie(0.5f, nan, -1.0f, -0.3f, 5.0f, -2.0f, 0.3f, CCL_VARIANT_CORRECTED)));
    CCL_CHECK(isnan(ccl_sky_preetham_zenith_x(nan, 0.5f)));
    CCL_CHECK(isnan(ccl_sky_turbidity(nan, 0.5f)));
    CCL_CHECK(ccl_sky_preetham_init(3.0f, 0.5f, 0.03f, CCL_VARIANT_CORRECTED, &p) == CCL_OK);
    c = ccl_sky_preetham_rgb(V(nan, 0.5f, 0.5f), V(0.0f, 1.0f, 0.0f), &p);
    CCL_CHECK(isnan(c.x) && isnan(c.y) && isnan(c.z));
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
