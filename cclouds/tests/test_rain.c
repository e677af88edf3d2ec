/* C unit tests of cclouds/rain.h: the catalogue's r(theta) values (rr-eq1, rr-tab-2.1), interpolation options,
 * volume and axis ratio, terminal speeds (rr-tab-2.2), masks (rr-alg-3.1.1) against the analytic sphere, the
 * exact shape reducing to the sphere, capture lookups (rr-alg-3.1.3), bad input of the status functions. */
#include <stdlib.h>
#include "cclouds/rain.h"
#include "ccl_test.h"

#define PI_D 3.14159265358979323846

static void test_rain_drop_radius_catalogue_values(void)
{
    static const float a[4] = {0.5f, 1.0f, 3.0f, 4.5f};
    static const double r0[4] = {0.491850, 0.927700, 2.042100, 2.682900};
    static const double r90[4] = {0.502550, 1.023600, 3.441900, 5.560200};
    static const double r180[4] = {0.496850, 0.968300, 2.397300, 3.030300};
    int k;
    for (k = 0; k < 4; ++k) {
        CCL_CHECK_CLOSE(ccl_rain_drop_radius(0.0f, a[k], CCL_RAIN_INTERP_TABLE), r0[k], 2e-6 * (double)a[k]);
        CCL_CHECK_CLOSE(ccl_rain_drop_radius((float)(PI_D / 2), a[k], CCL_RAIN_INTERP_TABLE), r90[k],
                        4e-6 * (double)a[k]);
        CCL_CHECK_CLOSE(ccl_rain_drop_radius((float)PI_D, a[k], CCL_RAIN_INTERP_TABLE), r180[k], 4e-6 * (double)a[k]);
        /* the linear option reproduces the rows */
        CCL_CHECK(ccl_rain_drop_coefficient(2, a[k], CCL_RAIN_INTERP_LINEAR) ==
                  ccl_rain_drop_coefficient(2, a[k], CCL_RAIN_INTERP_TABLE));
    }
    CCL_CHECK(isnan(ccl_rain_drop_radius(0.0f, 2.0f, CCL_RAIN_INTERP_TABLE)));
    /* linear between 1 and 3 mm: C_2 at 2 mm is the mean of -385e-4 and -2040e-4 */
    CCL_CHECK_CLOSE(ccl_rain_drop_coefficient(2, 2.0f, CCL_RAIN_INTERP_LINEAR), -0.12125, 1e-7);
    CCL_CHECK(isnan(ccl_rain_drop_coefficient(0, 0.25f, CCL_RAIN_INTERP_LINEAR)));
}

static void test_rain_drop_surface_and_integrals(void)
{
    ccl_vec3 p, n;
    float v, ar;
    /* surface at theta = pi/2, phi = 0: on +x, normal close to +x */
    p = ccl_rain_drop_surface((float)(PI_D / 2), 0.0f, 1.0f, CCL_RAIN_INTERP_TABLE, &n);
    CCL_CHECK_CLOSE(p.x, 1.0236, 1e-5);
    CCL_CHECK_CLOSE(n.x * n.x + n.y * n.y + n.z * n.z, 1.0, 1e-6);
    p = ccl_rain_drop_surface(0.0f, 0.3f, 3.0f, CCL_RAIN_INTERP_TABLE, &n);
    CCL_CHECK_CLOSE(p.y, -2.0421, 1e-5);
    CCL_CHECK_CLOSE(n.y, -1.0, 1e-6);
    /* a is close to the equal-volume radius */
    v = ccl_rain_drop_volume(1.0f, CCL_RAIN_INTERP_TABLE);
    CCL_CHECK_REL(v, 4.0 / 3.0 * PI_D, 0.01);
    ar = ccl_rain_drop_axis_ratio(0.5f, CCL_RAIN_INTERP_TABLE);
    CCL_CHECK(ar < 1.0f && ar > 0.98f);
    CCL_CHECK(ccl_rain_drop_axis_ratio(4.5f, CCL_RAIN_INTERP_TABLE) < ccl_rain_drop_axis_ratio(3.0f, CCL_RAIN_INTERP_TABLE));
    CCL_CHECK(ccl_rain_drop_extent(4.5f, CCL_RAIN_INTERP_TABLE) >= 5.59818f); /* max r at theta = 1.497 */
    CCL_CHECK(ccl_rain_drop_extent(4.5f, CCL_RAIN_INTERP_TABLE) < 5.59818f + 0.0067f);
}

static void test_rain_terminal_speed_table(void)
{
    CCL_CHECK_CLOSE(ccl_rain_terminal_speed(1.0f, 1.0f), 6.59, 1e-6);
    CCL_CHECK_CLOSE(ccl_rain_terminal_speed(0.45f, 1.0f), 3.67, 1e-6);
    CCL_CHECK_CLOSE(ccl_rain_terminal_speed(1.125f, 1.0f), 0.5 * (6.59 + 7.46), 1e-5);
    CCL_CHECK_CLOSE(ccl_rain_terminal_speed(8.0f, 1.0f), 9.23, 1e-6);
    CCL_CHECK_CLOSE(ccl_rain_terminal_speed(1.0f, 4.0f), 6.59 / 4.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_rain_terminal_speed(0.05f, 1.0f), 0.72 * 0.25, 1e-6);
    CCL_CHECK(ccl_rain_terminal_speed(0.0f, 1.0f) == 0.0f);
}

static void test_rain_mask_sphere_against_analytic(void)
{
    /* deviation of a ray through a sphere at impact parameter b: D = 2 (theta_i - theta_t), towards the axis */
    static const float us[4] = {0.0f, 0.3f, -0.6f, 0.2f}, vs[4] = {0.0f, 0.4f, 0.1f, -0.95f};
    int k, inside;
    for (k = 0; k < 4; ++k) {
        double b = sqrt((double)us[k] * (double)us[k] + (double)vs[k] * (double)vs[k]);
        double ti = asin(b), tt = asin(b / 1.33), dev = 2.0 * (ti - tt);
        ccl_vec3 n, e = ccl_rain_mask_texel(us[k], vs[k], 1.0f, 1.0f, 1.33f, CCL_RAIN_INTERP_TABLE,
                                            CCL_RAIN_MASK_SPHERE, &n, &inside);
        CCL_CHECK(inside == 1);
        CCL_CHECK_CLOSE(e.z, cos(dev), 2e-6);
        if (b > 0) {
            CCL_CHECK_CLOSE(e.x, -sin(dev) * (double)us[k] / b, 2e-6);
            CCL_CHECK_CLOSE(e.y, -sin(dev) * (double)vs[k] / b, 2e-6);
        }
    }
    {
        ccl_vec3 n, e = ccl_rain_mask_texel(0.8f, 0.7f, 1.0f, 1.0f, 1.33f, CCL_RAIN_INTERP_TABLE,
                                            CCL_RAIN_MASK_SPHERE, &n, &inside);
        CCL_CHECK(inside == 0 && e.x == 0.0f && e.z == 0.0f);
    }
}

static void test_rain_mask_exact_reduces_to_sphere(void)
{
    int k, i1, i2;
    for (k = 0; k < 20; ++k) {
        float u = -0.9f + 0.09f * (float)k, v = 0.5f - 0.04f * (float)k;
        ccl_vec3 n1, n2, e1, e2;
        if (u * u + v * v > 0.97f) continue;
        e1 = ccl_rain_mask_texel(u, v, 3.0f, 0.0f, 1.33f, CCL_RAIN_INTERP_TABLE, CCL_RAIN_MASK_EXACT, &n1, &i1);
        e2 = ccl_rain_mask_texel(u, v, 3.0f, 0.0f, 1.33f, CCL_RAIN_INTERP_TABLE, CCL_RAIN_MASK_SPHERE, &n2, &i2);
        CCL_CHECK(i1 == i2);
        CCL_CHECK_CLOSE(e1.x, e2.x, 2e-4);
        CCL_CHECK_CLOSE(e1.y, e2.y, 2e-4);
        CCL_CHECK_CLOSE(e1.z, e2.z, 2e-4);
    }
}

static void test_rain_mask_status(void)
{
    float *buf = (float *)malloc(16 * 16 * 4 * sizeof(float));
    CCL_CHECK(ccl_rain_mask(16, 1.0f, 1.0f, 1.33f, CCL_RAIN_INTERP_TABLE, CCL_RAIN_MASK_EXACT, buf, NULL) == CCL_OK);
    CCL_CHECK(buf[(8 * 16 + 8) * 4 + 3] == 1.0f && buf[3] == 0.0f);
    CCL_CHECK(ccl_rain_mask(16, 2.0f, 1.0f, 1.33f, CCL_RAIN_INTERP_TABLE, CCL_RAIN_MASK_EXACT, buf, NULL) ==
              CCL_EINVAL);
    CCL_CHECK(ccl_rain_mask(0, 1.0f, 1.0f, 1.33f, CCL_RAIN_INTERP_TABLE, CCL_RAIN_MASK_EXACT, buf, NULL) == CCL_EINVAL);
    CCL_CHECK(ccl_rain_mask(16, 1.0f, 1.0f, 0.5f, CCL_RAIN_INTERP_TABLE, CCL_RAIN_MASK_EXACT, buf, NULL) == CCL_EINVAL);
    free(buf);
}

static void test_rain_refracted_uv_and_capture(void)
{
    ccl_vec3 c, e;
    ccl_vec2 po, pc, uv;
    int valid;
    float rgb[2 * 2 * 3] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3};
    ccl_vec3 col;
    c.x = 0.0f; c.y = 0.0f; c.z = -1.0f;
    e.x = 0.1f; e.y = 0.0f; e.z = 0.99498744f;
    pc = ccl_rain_refracted_uv(c, e, 1.0f, 1.0f, CCL_RAIN_MAPPING_OFFSET, &po, &valid);
    CCL_CHECK(valid == 1);
    CCL_CHECK_CLOSE(po.x, 0.5, 1e-7);
    CCL_CHECK_CLOSE(pc.x, 0.5 + 0.5 * 0.1 / 0.99498744, 1e-6);
    uv = ccl_rain_refracted_uv(c, e, 1.0f, 1.0f, CCL_RAIN_MAPPING_PROJECT, &po, &valid);
    CCL_CHECK_CLOSE(uv.x, pc.x, 1e-6);
    e.z = -0.5f;
    pc = ccl_rain_refracted_uv(c, e, 1.0f, 1.0f, CCL_RAIN_MAPPING_OFFSET, &po, &valid);
    CCL_CHECK(valid == 0);
    uv.x = 0.25f; uv.y = 0.75f; /* texel (1, 0) */
    col = ccl_rain_sample_capture(rgb, 2, 2, uv, CCL_RAIN_FILTER_NEAREST);
    CCL_CHECK(col.x == 2.0f);
    uv.x = 0.5f; uv.y = 0.5f; /* the middle: mean of the four */
    col = ccl_rain_sample_capture(rgb, 2, 2, uv, CCL_RAIN_FILTER_LINEAR);
    CCL_CHECK_CLOSE(col.x, 1.5, 1e-6);
    uv.x = 1e30f; uv.y = -1e30f;
    col = ccl_rain_sample_capture(rgb, 2, 2, uv, CCL_RAIN_FILTER_LINEAR);
    CCL_CHECK(col.x == 1.0f);
}

static void test_rain_light_terms(void)
{
    ccl_vec3 up, n, side, a1;
    up.x = 0.0f; up.y = 1.0f; up.z = 0.0f;
    n.x = 1.0f; n.y = 0.0f; n.z = 0.0f;
    side.x = -1.0f; side.y = 0.0f; side.z = 0.0f;
    CCL_CHECK(ccl_rain_light_a3(up, n) == 0.0f); /* vertical light: guarded */
    CCL_CHECK(ccl_rain_light_a3(side, n) == 0.0f); /* light straight behind: the ray passes along the normal */
    {   /* light behind and above at 60 deg, normal tilted up 30 deg: horizontal factor 1, V_PL.V_N = 0 -> 1 */
        ccl_vec3 l, m;
        l.x = -0.5f; l.y = 0.8660254f; l.z = 0.0f;
        m.x = 0.8660254f; m.y = 0.5f; m.z = 0.0f;
        CCL_CHECK_CLOSE(ccl_rain_light_a3(l, m), 1.0, 1e-6);
    }
    CCL_CHECK(ccl_rain_light_a2(side, n) == 0.0f);
    a1 = ccl_rain_light_a1(n, 2.0f, side, n, 2.0f, CCL_VARIANT_CORRECTED);
    CCL_CHECK(a1.x == 0.0f);
    a1 = ccl_rain_light_a1(n, 2.0f, side, n, 2.0f, CCL_VARIANT_THESIS);
    CCL_CHECK_CLOSE(a1.x, -0.5, 1e-7);
}

int main(void)
{
    CCL_RUN(test_rain_drop_radius_catalogue_values);
    CCL_RUN(test_rain_drop_surface_and_integrals);
    CCL_RUN(test_rain_terminal_speed_table);
    CCL_RUN(test_rain_mask_sphere_against_analytic);
    CCL_RUN(test_rain_mask_exact_reduces_to_sphere);
    CCL_RUN(test_rain_mask_status);
    CCL_RUN(test_rain_refracted_uv_and_capture);
    CCL_RUN(test_rain_light_terms);
    return ccl_test_report();
}
