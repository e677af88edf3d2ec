/* C unit tests of cclouds/sdf.h: exact primitive distances, operators, repeat variants, ray tracing vs sphere tracing. */
#include "cclouds/sdf.h"
#include "ccl_test.h"

static void test_primitives(void)
{
    ccl_vec2 t;
    t.x = 1.5f;
    t.y = 0.25f;
    CCL_CHECK_CLOSE(ccl_sdf_sphere(V(3.0f, 4.0f, 0.0f), 2.0f), 3.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_sdf_box(V(2.0f, 2.0f, 2.0f), V(1.0f, 1.0f, 1.0f)), sqrt(3.0), 1e-6);
    CCL_CHECK_CLOSE(ccl_sdf_box(V(0.5f, 0.0f, 0.0f), V(1.0f, 1.0f, 1.0f)), -0.5, 1e-6);
    CCL_CHECK_CLOSE(ccl_sdf_torus(V(0.0f, 0.0f, 0.0f), t), 1.25, 1e-6);
    CCL_CHECK_CLOSE(ccl_sdf_torus(V(1.5f, 0.0f, 0.0f), t), -0.25, 1e-6);
    CCL_CHECK_CLOSE(ccl_sdf_ellipsoid(V(2.0f, 0.0f, 0.0f), V(1.0f, 1.0f, 1.0f)), 1.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_sdf_ellipsoid(V(0.0f, 0.6f, 0.0f), V(1.0f, 0.6f, 0.4f)), 0.0, 1e-6);
}

static void test_operators(void)
{
    ccl_vec3 q;
    CCL_CHECK(ccl_sdf_union(1.0f, -2.0f) == -2.0f && ccl_sdf_intersect(1.0f, -2.0f) == 1.0f);
    CCL_CHECK(ccl_sdf_subtract(1.0f, -2.0f) == 2.0f);
    CCL_CHECK_CLOSE(ccl_sdf_smooth_union(0.3f, 0.3f, 1.0f), 0.05, 1e-6); /* d - k/4 where d1 = d2 */
    CCL_CHECK(ccl_sdf_smooth_union(0.0f, 3.0f, 1.0f) == 0.0f);          /* plain min outside the blend */
    q = ccl_sdf_repeat(V(1.0f, 1.5f, 2.0f), V(2.0f, 3.0f, 4.0f), CCL_VARIANT_THESIS);
    CCL_CHECK(q.x == 0.0f && q.y == 0.0f && q.z == 0.0f);
    q = ccl_sdf_repeat(V(2.0f, -3.0f, 8.0f), V(2.0f, 3.0f, 4.0f), CCL_VARIANT_CORRECTED);
    CCL_CHECK(q.x == 0.0f && q.y == 0.0f && q.z == 0.0f);
}

static void test_trace_vs_analytic(void)
{
    ccl_vec3 ro = V(-3.75f, 0.0f, -6.0f), rd = V(0.0f, 0.0f, 1.0f);
    int steps = 0, hit = 0;
    float t = ccl_sdf_sphere_trace(ro, rd, 256, 1e-4f, 50.0f, 0, CCL_SDF_SCENE_PRIMITIVES, &steps, &hit);
    float exact = ccl_sdf_ray_sphere(ro, rd, V(-3.75f, 0.0f, 0.0f), 0.8f);
    CCL_CHECK_CLOSE(exact, 5.2, 1e-6);
    CCL_CHECK(hit == 1 && steps >= 1 && t <= exact + 1e-5f && exact - t < 1e-4f);
    CCL_CHECK(ccl_sdf_ray_sphere(V(0.0f, 2.0f, -5.0f), rd, V(0.0f, 0.0f, 0.0f), 1.0f) == -1.0f);
    t = ccl_sdf_sphere_trace(V(0.0f, 5.0f, 0.0f), V(0.0f, 1.0f, 0.0f), 256, 1e-3f, 50.0f, 0, CCL_SDF_SCENE_UNION,
                             &steps, &hit);
    CCL_CHECK(hit == 0 && t > 50.0f);
}

int main(void)
{
    CCL_RUN(test_primitives);
    CCL_RUN(test_operators);
    CCL_RUN(test_trace_vs_analytic);
    return ccl_test_report();
}
