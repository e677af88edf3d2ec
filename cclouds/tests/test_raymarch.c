/* C unit tests of cclouds/raymarch.h: closed forms of the intersections and the layer segment, sample counts, light
 * cone, accumulation, jitter, bounded marching, the constants, NaN and bad input. */
#include "cclouds/raymarch.h"
#include "ccl_test.h"

#define PI_D 3.14159265358979323846
#define R_E 6371.0

static void test_ray_sphere_closed_forms(void)
{
    float t0, t1;
    /* from the centre: +-r */
    CCL_CHECK(ccl_raymarch_ray_sphere(V(1, 2, 3), V(0, 0, 1), V(1, 2, 3), 2.5f, &t0, &t1) == 1);
    CCL_CHECK_CLOSE(t0, -2.5, 0.0);
    CCL_CHECK_CLOSE(t1, 2.5, 0.0);
    /* tangent: origin (-5, 1, 0), d = +x, unit sphere: a double root at 5 */
    CCL_CHECK(ccl_raymarch_ray_sphere(V(-5, 1, 0), V(1, 0, 0), V(0, 0, 0), 1.0f, &t0, &t1) == 1);
    CCL_CHECK_CLOSE(t0, 5.0, 0.0);
    CCL_CHECK_CLOSE(t1, 5.0, 0.0);
    /* outside, missing: closest approach 2 > 1 */
    CCL_CHECK(ccl_raymarch_ray_sphere(V(0, 2, -5), V(0, 0, 1), V(0, 0, 0), 1.0f, &t0, &t1) == 0);
    CCL_CHECK(isnan(t0) && isnan(t1));
    /* sphere behind the origin: both roots negative */
    CCL_CHECK(ccl_raymarch_ray_sphere(V(0, 0, 5), V(0, 0, 1), V(0, 0, 0), 1.0f, &t0, &t1) == 1);
    CCL_CHECK_CLOSE(t0, -6.0, 0.0);
    CCL_CHECK_CLOSE(t1, -4.0, 0.0);
    /* origin on the surface, ray along the tangent plane: q == 0 branch */
    CCL_CHECK(ccl_raymarch_ray_sphere(V(1, 0, 0), V(0, 1, 0), V(0, 0, 0), 1.0f, &t0, &t1) == 1);
    CCL_CHECK_CLOSE(t0, 0.0, 0.0);
    CCL_CHECK_CLOSE(t1, 0.0, 0.0);
}

static void test_ray_sphere_earth_scale(void)
{
    float t0, t1;
    ccl_vec3 c = V(0.0f, (float)-R_E, 0.0f);
    /* from the ground straight up: exactly 1.5 km to the layer base (|o - c| = R_E is exact in float32) */
    ccl_raymarch_ray_sphere(V(0, 0, 0), V(0, 1, 0), c, 6372.5f, &t0, &t1);
    CCL_CHECK_CLOSE(t1, 1.5, 0.0);
    CCL_CHECK_CLOSE(t0, -(2.0 * R_E + 1.5), 1e-3);
    /* horizontal: far root sqrt((R + h)^2 - R^2); float32 spacing of radii ~6e3 km is 4.9e-4 km, error <= 2 ulps */
    ccl_raymarch_ray_sphere(V(0, 0, 0), V(1, 0, 0), c, 6372.5f, &t0, &t1);
    CCL_CHECK_CLOSE(t1, sqrt(6372.5 * 6372.5 - R_E * R_E), 1e-3);
    CCL_CHECK_CLOSE(t0, -sqrt(6372.5 * 6372.5 - R_E * R_E), 1e-3);
}

static void test_ray_box(void)
{
    float t0, t1;
    CCL_CHECK(ccl_raymarch_ray_box(V(0, 0, -5), V(0, 0, 1), V(-1, -1, -1), V(1, 1, 1), &t0, &t1) == 1);
    CCL_CHECK_CLOSE(t0, 4.0, 0.0);
    CCL_CHECK_CLOSE(t1, 6.0, 0.0);
    /* parallel to the x slabs, outside them: miss */
    CCL_CHECK(ccl_raymarch_ray_box(V(2, 0, -5), V(0, 0, 1), V(-1, -1, -1), V(1, 1, 1), &t0, &t1) == 0);
    CCL_CHECK(isnan(t0) && isnan(t1));
    /* origin inside: entry behind */
    CCL_CHECK(ccl_raymarch_ray_box(V(0, 0, 0), V(0, 1, 0), V(-1, -2, -1), V(1, 3, 1), &t0, &t1) == 1);
    CCL_CHECK_CLOSE(t0, -2.0, 0.0);
    CCL_CHECK_CLOSE(t1, 3.0, 0.0);
    /* diagonal through the corner region */
    CCL_CHECK(ccl_raymarch_ray_box(V(-2, -2, 0), V(1, 1, 0), V(-1, -1, -1), V(1, 1, 1), &t0, &t1) == 1);
    CCL_CHECK_CLOSE(t0, 1.0, 0.0);
    CCL_CHECK_CLOSE(t1, 3.0, 0.0);
}

/* ccl_raymarch_layer_segment with the layer L */
static int seg(ccl_vec3 o, ccl_vec3 d, const ccl_cloud_layer *L, float *ts, float *te)
{
    return ccl_raymarch_layer_segment(o, d, L->centre, L->r_earth, L->r_inner, L->r_outer, ts, te);
}

static void test_layer_segment_below_inside_above(void)
{
    ccl_cloud_layer L;
    float ts, te;
    const double ri = R_E + 1.5, ro = R_E + 4.0;
    ccl_raymarch_cloud_layer_default(&L);
    CCL_CHECK_CLOSE(L.r_earth, R_E, 0.0);
    CCL_CHECK_CLOSE(L.r_inner, ri, 0.0);
    CCL_CHECK_CLOSE(L.r_outer, ro, 0.0);
    CCL_CHECK_CLOSE(L.centre.y, -R_E, 0.0);
    /* below, zenith: [1.5, 4] */
    CCL_CHECK(seg(V(0, 0, 0), V(0, 1, 0), &L, &ts, &te) == 1);
    CCL_CHECK_CLOSE(ts, 1.5, 0.0);
    CCL_CHECK_CLOSE(te, 4.0, 0.0);
    /* below, horizon (camera 1 m up, horizontal): grazes the Earth? no: the Earth's far root is behind */
    CCL_CHECK(seg(V(0, 0.001f, 0), V(1, 0, 0), &L, &ts, &te));
    CCL_CHECK_CLOSE(ts, sqrt(ri * ri - (R_E + 0.001) * (R_E + 0.001)), 2e-3);
    CCL_CHECK_CLOSE(te, sqrt(ro * ro - (R_E + 0.001) * (R_E + 0.001)), 2e-3);
    /* below, looking down: the Earth blocks */
    CCL_CHECK(seg(V(0, 0.5f, 0), V(0, -1, 0), &L, &ts, &te) == 0);
    CCL_CHECK(isnan(ts) && isnan(te));
    /* underground camera: nothing */
    CCL_CHECK(seg(V(0, -1, 0), V(0, 1, 0), &L, &ts, &te) == 0);
    /* inside (2 km up): up -> [0, 2], down -> [0, 0.5] (leaves through the base) */
    CCL_CHECK(seg(V(0, 2, 0), V(0, 1, 0), &L, &ts, &te) == 1);
    CCL_CHECK_CLOSE(ts, 0.0, 0.0);
    CCL_CHECK_CLOSE(te, 2.0, 1e-3);
    CCL_CHECK(seg(V(0, 2, 0), V(0, -1, 0), &L, &ts, &te) == 1);
    CCL_CHECK_CLOSE(ts, 0.0, 0.0);
    CCL_CHECK_CLOSE(te, 0.5, 1e-3);
    /* inside, horizontal: misses the inner sphere -> outer far root */
    CCL_CHECK(seg(V(0, 2, 0), V(1, 0, 0), &L, &ts, &te) == 1);
    CCL_CHECK_CLOSE(te, sqrt(ro * ro - (R_E + 2) * (R_E + 2)), 2e-3);
    /* above (10 km): down -> [6, 8.5]; up -> nothing; horizontal -> misses the outer sphere */
    CCL_CHECK(seg(V(0, 10, 0), V(0, -1, 0), &L, &ts, &te) == 1);
    CCL_CHECK_CLOSE(ts, 6.0, 1e-3);
    CCL_CHECK_CLOSE(te, 8.5, 1e-3);
    CCL_CHECK(seg(V(0, 10, 0), V(0, 1, 0), &L, &ts, &te) == 0);
    CCL_CHECK(seg(V(0, 10, 0), V(1, 0, 0), &L, &ts, &te) == 0);
    /* NaN propagates */
    CCL_CHECK(seg(V(0, (float)NAN, 0), V(0, 1, 0), &L, &ts, &te) == 0);
    CCL_CHECK(isnan(ts) && isnan(te));
}

static void test_cloud_layer_init_rejects_bad_input(void)
{
    ccl_cloud_layer L;
    CCL_CHECK(ccl_raymarch_cloud_layer_init(6000.0f, 1.0f, 3.0f, &L) == CCL_OK);
    CCL_CHECK_CLOSE(L.r_inner, 6001.0, 0.0);
    CCL_CHECK(ccl_raymarch_cloud_layer_init(-1.0f, 1.0f, 3.0f, &L) == CCL_EINVAL);
    CCL_CHECK(ccl_raymarch_cloud_layer_init(6000.0f, -1.0f, 3.0f, &L) == CCL_EINVAL);
    CCL_CHECK(ccl_raymarch_cloud_layer_init(6000.0f, 3.0f, 3.0f, &L) == CCL_EINVAL);
    CCL_CHECK(ccl_raymarch_cloud_layer_init(6000.0f, 1.0f, (float)NAN, &L) == CCL_EINVAL);
    CCL_CHECK(ccl_raymarch_cloud_layer_init(6000.0f, 1.0f, 3.0f, NULL) == CCL_EINVAL);
}

static void test_view_sample_count(void)
{
    CCL_CHECK(ccl_raymarch_view_sample_count(0.0f, 64, 128) == 128);
    CCL_CHECK(ccl_raymarch_view_sample_count(1.0f, 64, 128) == 64);
    CCL_CHECK(ccl_raymarch_view_sample_count(-1.0f, 64, 128) == 64);
    CCL_CHECK(ccl_raymarch_view_sample_count(0.5f, 64, 128) == 96);
    CCL_CHECK(ccl_raymarch_view_sample_count(0.25f, 64, 128) == 112);
    CCL_CHECK(ccl_raymarch_view_sample_count(1.0f / 128.0f, 64, 128) == 128); /* 127.5 rounds up */
    CCL_CHECK(ccl_raymarch_view_sample_count(1.0000001f, 64, 128) == 64);
    CCL_CHECK(ccl_raymarch_view_sample_count((float)NAN, 64, 128) == 128);
    CCL_CHECK(ccl_raymarch_view_sample_count(0.3f, 7, 7) == 7);
}

static void test_light_cone_positions(void)
{
    const float step = 0.1f, angle = 0.2617994f, far = 3.0f;
    ccl_vec3 sun = V(0.6f, 0.8f, 0.0f), p = V(1, 2, 3);
    int i;
    double prev = 0.0;
    for (i = 0; i < 6; ++i) {
        ccl_vec3 k = ccl_raymarch_light_cone_kernel(i);
        ccl_vec3 q = ccl_raymarch_light_sample_position(p, sun, i, step, angle, far, k);
        double s = (i < 5) ? (i + 1) * 0.1 : 3.0 * 0.5;
        ccl_vec3 off = V((float)((double)(q.x - p.x) - s * (double)sun.x),
                         (float)((double)(q.y - p.y) - s * (double)sun.y),
                         (float)((double)(q.z - p.z) - s * (double)sun.z));
        CCL_CHECK_CLOSE(len3(k), 1.0, 1e-6);
        /* sideways offset s_i tan(angle): increases with i */
        CCL_CHECK_REL(len3(off), s * tan(0.2617994), 1e-4);
        CCL_CHECK(len3(off) > prev);
        prev = len3(off);
    }
    /* the far sample lies at 3x the near cone's length */
    {
        ccl_vec3 q = ccl_raymarch_light_sample_position(V(0, 0, 0), V(0, 1, 0), 5, 0.1f, 0.0f, 3.0f,
                                                        ccl_raymarch_light_cone_kernel(5));
        CCL_CHECK_CLOSE(q.y, 1.5, 1e-6);
        CCL_CHECK_CLOSE(q.x, 0.0, 0.0);
    }
    /* kernel wraps mod 6 and is deterministic */
    CCL_CHECK(ccl_raymarch_light_cone_kernel(7).x == ccl_raymarch_light_cone_kernel(1).x);
    CCL_CHECK(ccl_raymarch_light_cone_kernel(-1).z == ccl_raymarch_light_cone_kernel(5).z);
}

static void test_march_accumulate_constant_medium(void)
{
    /* N equal steps through a homogeneous medium: T = exp(-sigma rho N dt), C = L (1 - T) (closed form) */
    ccl_vec3 c = V(0, 0, 0), light = V(1.0f, 0.5f, 0.25f);
    float T = 1.0f;
    int i, stop = 0;
    for (i = 0; i < 20; ++i) c = ccl_raymarch_accumulate(c, T, 2.0f, 0.5f, 0.1f, light, 1.0f / 256.0f, &T, &stop);
    CCL_CHECK_REL(T, exp(-2.0), 1e-5);
    CCL_CHECK_REL(c.x, 1.0 - exp(-2.0), 1e-5);
    CCL_CHECK_REL(c.y, 0.5 * (1.0 - exp(-2.0)), 1e-5);
    CCL_CHECK(stop == 0);
    /* rho = 0 changes nothing */
    {
        float T0;
        ccl_vec3 c0 = ccl_raymarch_accumulate(V(0.1f, 0.2f, 0.3f), 0.7f, 5.0f, 0.0f, 1.0f, light, 0.01f, &T0, &stop);
        CCL_CHECK(c0.x == 0.1f && c0.y == 0.2f && c0.z == 0.3f && T0 == 0.7f && stop == 0);
    }
    /* termination: stop once 1 - T >= 1 - eps */
    {
        float T1;
        ccl_raymarch_accumulate(V(0, 0, 0), 1.0f, 1.0f, 1.0f, 10.0f, light, 1.0f / 256.0f, &T1, &stop);
        CCL_CHECK(stop == 1); /* e^-10 */
        ccl_raymarch_accumulate(V(0, 0, 0), 1.0f, 1.0f, 1.0f, 5.0f, light, 1.0f / 256.0f, &T1, &stop);
        CCL_CHECK(stop == 0); /* e^-5 > 1/256 */
        ccl_raymarch_accumulate(V(0, 0, 0), 1.0f, 1.0f, 1.0f, 5.0f, light, 0.01f, &T1, &stop);
        CCL_CHECK(stop == 1);
    }
}

static void test_ray_jitter(void)
{
    ccl_vec3 d = V(0.0f, 0.6f, -0.8f);
    ccl_vec3 a = ccl_raymarch_jitter_tilt(d, 10, 20, 3, 0.002f), b = ccl_raymarch_jitter_tilt(d, 10, 20, 3, 0.002f);
    ccl_vec3 e = ccl_raymarch_jitter_tilt(d, 11, 20, 3, 0.002f), g = ccl_raymarch_jitter_tilt(d, 10, 20, 4, 0.002f);
    double cosang;
    float o;
    CCL_CHECK(a.x == b.x && a.y == b.y && a.z == b.z); /* deterministic */
    CCL_CHECK(a.x != e.x || a.y != e.y);               /* depends on the pixel */
    CCL_CHECK(a.x != g.x || a.y != g.y);               /* and on the frame */
    CCL_CHECK_CLOSE(len3(a), 1.0, 2e-7);
    cosang = (double)(a.x * d.x + a.y * d.y + a.z * d.z);
    CCL_CHECK(acos(cosang > 1.0 ? 1.0 : cosang) <= sqrt(3.0) * 0.002 + 1e-6);
    /* zero amount: the direction itself */
    a = ccl_raymarch_jitter_tilt(d, 1, 2, 3, 0.0f);
    CCL_CHECK_CLOSE(a.y, 0.6, 1e-7);
    o = ccl_raymarch_jitter_offset(5, 6, 7);
    CCL_CHECK(o >= 0.0f && o < 1.0f);
    CCL_CHECK(o == ccl_raymarch_jitter_offset(5, 6, 7));
    /* one entry for the three modes */
    {
        float off;
        ccl_vec3 j = ccl_raymarch_jitter(d, 5, 6, 7, 0.002f, CCL_JITTER_OFFSET, &off);
        CCL_CHECK(j.x == d.x && j.y == d.y && j.z == d.z && off == o);
        j = ccl_raymarch_jitter(d, 5, 6, 7, 0.002f, CCL_JITTER_NONE, &off);
        CCL_CHECK(j.x == d.x && j.y == d.y && j.z == d.z && off == 0.5f);
        j = ccl_raymarch_jitter(d, 5, 6, 7, 0.002f, CCL_JITTER_TILT, &off);
        a = ccl_raymarch_jitter_tilt(d, 5, 6, 7, 0.002f);
        CCL_CHECK(j.x == a.x && j.y == a.y && j.z == a.z && off == 0.5f);
    }
}

static void test_march_interval_and_points(void)
{
    float ts, dt;
    ccl_vec3 pts[4];
    int i;
    CCL_CHECK(ccl_raymarch_interval(-2.0f, 6.0f, 4, &ts, &dt) == 1); /* origin inside: start at 0 */
    CCL_CHECK_CLOSE(ts, 0.0, 0.0);
    CCL_CHECK_CLOSE(dt, 1.5, 0.0);
    CCL_CHECK(ccl_raymarch_interval(-6.0f, -2.0f, 4, &ts, &dt) == 0); /* behind */
    CCL_CHECK(isnan(ts) && isnan(dt));
    CCL_CHECK(ccl_raymarch_interval((float)NAN, 1.0f, 4, &ts, &dt) == 0);
    /* sphere of radius 1 at the origin from z = -5: midpoints -0.75, -0.25, 0.25, 0.75 */
    CCL_CHECK(ccl_raymarch_sphere(V(0, 0, -5), V(0, 0, 2), V(0, 0, 0), 1.0f, 4, 0.5f, pts, &dt) == 1);
    CCL_CHECK_CLOSE(dt, 0.5, 0.0);
    for (i = 0; i < 4; ++i) CCL_CHECK_CLOSE(pts[i].z, -0.75 + 0.5 * i, 1e-6);
    CCL_CHECK(ccl_raymarch_box(V(0, 0, -5), V(0, 0, 1), V(-1, -1, -1), V(1, 1, 1), 4, 0.0f, pts, &dt) == 1);
    CCL_CHECK_CLOSE(pts[0].z, -1.0, 0.0);
    CCL_CHECK_CLOSE(pts[3].z, 0.5, 0.0);
    CCL_CHECK(ccl_raymarch_sphere(V(0, 3, -5), V(0, 0, 1), V(0, 0, 0), 1.0f, 4, 0.5f, pts, &dt) == 0);
    CCL_CHECK(isnan(pts[2].x) && isnan(dt));
}

static void test_vc_constants(void)
{
    const ccl_vc_constant_table *k = ccl_raymarch_vc_constants();
    CCL_CHECK(k != NULL);
    CCL_CHECK(k->base_texture_size == 128 && k->detail_texture_size == 32);
    CCL_CHECK(k->view_samples_zenith == 64 && k->view_samples_horizon == 128);
    CCL_CHECK(k->light_samples == 6 && k->light_samples_near == 5);
    CCL_CHECK(k->reprojection_block == 4 && k->reprojection_cycle == 16);
    CCL_CHECK(k->low_freq_fbm_weights[0] == 0.625f && k->high_freq_fbm_weights[2] == 0.125f);
    CCL_CHECK(k->gradient_stratus[2] == 0.0f && k->gradient_cumulus[3] == 0.95f);
    CCL_CHECK(k->cie_clear_sky_bcde[0] == -0.32f && k->cie_clear_sky_bcde[3] == 0.45f);
    CCL_CHECK(k->tone_map_constant == 0.03f && k->detail_erosion == 0.2f && k->powder_factor == 2.0f);
}

static void test_nan_propagates(void)
{
    float t0, t1, nan = (float)NAN;
    CCL_CHECK(ccl_raymarch_ray_sphere(V(nan, 0, 0), V(0, 0, 1), V(0, 0, 0), 1.0f, &t0, &t1) == 0 && isnan(t0));
    CCL_CHECK(ccl_raymarch_ray_box(V(0, 0, -5), V(0, nan, 1), V(-1, -1, -1), V(1, 1, 1), &t0, &t1) == 0 && isnan(t1));
    {
        float T;
        int stop;
        ccl_vec3 c = ccl_raymarch_accumulate(V(0, 0, 0), 1.0f, 1.0f, nan, 1.0f, V(1, 1, 1), 0.01f, &T, &stop);
        CCL_CHECK(isnan(c.x) && isnan(T) && stop == 0);
    }
}

int main(void)
{
    CCL_RUN(test_ray_sphere_closed_forms);
    CCL_RUN(test_ray_sphere_earth_scale);
    CCL_RUN(test_ray_box);
    CCL_RUN(test_layer_segment_below_inside_above);
    CCL_RUN(test_cloud_layer_init_rejects_bad_input);
    CCL_RUN(test_view_sample_count);
    CCL_RUN(test_light_cone_positions);
    CCL_RUN(test_march_accumulate_constant_medium);
    CCL_RUN(test_ray_jitter);
    CCL_RUN(test_march_interval_and_points);
    CCL_RUN(test_vc_constants);
    CCL_RUN(test_nan_propagates);
    return ccl_test_report();
}
