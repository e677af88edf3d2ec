/* C unit tests of cclouds/terrain.h (pt chapters 7-9): closed forms, bounds and properties of the terrain demo. */
#include "cclouds/terrain.h"
#include "ccl_test.h"

#include <math.h>

static void test_terrain_pixel_position_ranges(void)
{
    ccl_vec2 p = ccl_terrain_pixel_position(320.0f, 240.0f, 640.0f, 480.0f);
    CCL_CHECK_CLOSE(p.x, 0.0, 0.0);
    CCL_CHECK_CLOSE(p.y, 0.0, 0.0);
    p = ccl_terrain_pixel_position(640.0f, 480.0f, 640.0f, 480.0f);
    CCL_CHECK_REL(p.x, 4.0 / 3.0, 1e-6);
    CCL_CHECK_CLOSE(p.y, 1.0, 0.0);
    p = ccl_terrain_pixel_position(0.0f, 0.0f, 1920.0f, 1080.0f);
    CCL_CHECK_REL(p.x, -16.0 / 9.0, 1e-6);
    CCL_CHECK_CLOSE(p.y, -1.0, 0.0);
}

/* Kod 7.9 (pt-code-7.9) is pt-alg-3.2 with the printed coefficients: ccl_noise_fbm_perlin2 */
static float fbm79(float x, float z, int32_t octaves)
{
    ccl_vec2 p;
    p.x = x;
    p.y = z;
    return ccl_noise_fbm_perlin2(p, octaves, 0u, 1.0f, 0.5f, 0.5f, 2.0f);
}

static void test_terrain_fbm_bound(void)
{
    int oct, i;
    for (oct = 1; oct <= 8; ++oct) {
        double bound = 2.0 * (1.0 - pow(0.5, oct));
        for (i = 0; i < 2000; ++i) {
            float x = -50.0f + 0.0731f * (float)i, z = 13.0f - 0.0419f * (float)i;
            CCL_CHECK(fabs((double)fbm79(x, z, oct)) <= bound);
        }
    }
    /* one octave at frequency 0.5 is the noise: 0 on the lattice (even coordinates) */
    CCL_CHECK_CLOSE(fbm79(4.0f, -6.0f, 1), 0.0, 0.0);
}

static void test_terrain_test_heightmap(void)
{
    CCL_CHECK_REL(ccl_terrain_height_perm(15.707963f, 15.707963f, 1, 1.0f, 1.0f, NULL, CCL_TERRAIN_TEST), 10.0, 1e-6);
    CCL_CHECK_CLOSE(ccl_terrain_height_perm(0.0f, 7.0f, 1, 1.0f, 1.0f, NULL, CCL_TERRAIN_TEST), 0.0, 0.0);
}

static void test_terrain_marches_find_the_same_surface(void)
{
    /* a ray from above down onto the test heightmap: fixed and dynamic marches agree within the fixed step */
    ccl_vec3 ro = V(3.0f, 20.0f, 5.0f), rd = ccl_vec3_normalize(V(0.3f, -0.5f, 0.8f));
    float tf, td, tb;
    int sf, sd, sb;
    int32_t hf = ccl_terrain_march_fixed(ro, rd, 200.0f, 0.05f, 0.01f, 1, 1.0f, 1.0f, 0u, CCL_TERRAIN_TEST, &tf, &sf);
    int32_t hd = ccl_terrain_march_dynamic(ro, rd, 200.0f, 0.01f, 1000, 1.0f, 1, 1.0f, 1.0f, 0u, CCL_TERRAIN_TEST,
                                           &td, &sd);
    int32_t hb = ccl_terrain_march_bisect(ro, rd, 200.0f, 0.01f, 1000, 1.0f, 0.25f, 8, 1, 1.0f, 1.0f, 0u,
                                          CCL_TERRAIN_TEST, &tb, &sb);
    CCL_CHECK(hf == 1 && hd == 1 && hb == 1);
    CCL_CHECK_CLOSE(tf, td, 0.05 / 0.5 + 0.05);
    CCL_CHECK_CLOSE(tb, td, 0.05);
    CCL_CHECK(sd < sf);
    /* a ray pointing up misses */
    rd = ccl_vec3_normalize(V(0.3f, 0.5f, 0.8f));
    CCL_CHECK(ccl_terrain_march_dynamic(ro, rd, 200.0f, 0.01f, 1000, 1.0f, 1, 1.0f, 1.0f, 0u, CCL_TERRAIN_TEST, &td,
                                        &sd) == 0);
    CCL_CHECK(td > 200.0f);
}

static void test_terrain_shadows(void)
{
    /* a point in the trough behind a crest of the test heightmap, the light grazing over the crest */
    ccl_vec3 ro = V(-15.707963f, -9.9f, 15.707963f), up = V(0.0f, 1.0f, 0.0f);
    ccl_vec3 low = ccl_vec3_normalize(V(1.0f, 0.05f, 0.0f));
    float k, prev = -1.0f;
    CCL_CHECK_CLOSE(ccl_terrain_shadow_hard(ro, up, 0.2f, 100.0f, 0.01f, 1000, 1, 1.0f, 1.0f, 0u, CCL_TERRAIN_TEST),
                    1.0, 0.0);
    CCL_CHECK_CLOSE(ccl_terrain_shadow_hard(ro, low, 0.2f, 100.0f, 0.01f, 1000, 1, 1.0f, 1.0f, 0u, CCL_TERRAIN_TEST),
                    0.0, 0.0);
    for (k = 0.5f; k <= 64.0f; k *= 2.0f) {
        ccl_vec3 mid = ccl_vec3_normalize(V(1.0f, 0.9f, 0.0f));
        float s = ccl_terrain_shadow_soft(ro, mid, 0.02f, k, 100.0f, 0.01f, 1000, 1, 1.0f, 1.0f, 0u, CCL_TERRAIN_TEST);
        CCL_CHECK(s >= 0.0f && s <= 1.0f);
        CCL_CHECK(s >= prev);
        prev = s;
    }
}

static void test_terrain_normal_y_is_2h(void)
{
    ccl_vec3 g;
    ccl_vec3 n = ccl_terrain_normal(V(0.5f, 0.0f, 0.25f), 0.002f, 6, 12.0f, 24.0f, 0u, CCL_TERRAIN_FBM, &g);
    float hgt = 12.0f * fbm79(0.5f / 24.0f, 0.25f / 24.0f, 6);
    /* (y + h - H) - (y - h - H) = 2h exactly in real arithmetic; each of the two differences rounds once at the
     * magnitude of |H| + h, so the float32 result is within 2 ulp of that magnitude */
    CCL_CHECK_CLOSE(g.y, 0.004, 2.0 * ldexp(1.0, ilogb(fabs((double)hgt) + 0.002) - 23));
    CCL_CHECK_CLOSE(ccl_vec3_length(n), 1.0, 1e-6);
    /* flat test heightmap at a crest: normal up */
    n = ccl_terrain_normal(V(15.707963f, 10.0f, 15.707963f), 0.002f, 1, 1.0f, 1.0f, 0u, CCL_TERRAIN_TEST, &g);
    CCL_CHECK_CLOSE(n.y, 1.0, 1e-5);
}

static void test_terrain_normal_octaves_policy(void)
{
    CCL_CHECK(ccl_terrain_normal_octaves(0.0f, 9, 4, 15.0f) == 9);
    CCL_CHECK(ccl_terrain_normal_octaves(15.0f, 9, 4, 15.0f) == 9);
    CCL_CHECK(ccl_terrain_normal_octaves(15.5f, 9, 4, 15.0f) == 8);
    CCL_CHECK(ccl_terrain_normal_octaves(60.5f, 9, 4, 15.0f) == 6);
    CCL_CHECK(ccl_terrain_normal_octaves(1e6f, 9, 4, 15.0f) == 4);
}

static void test_terrain_fog_variants(void)
{
    float rho = 0.01f;
    CCL_CHECK_CLOSE(ccl_terrain_fog(0.0f, rho, CCL_VARIANT_THESIS), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_terrain_fog(1.01f * 69.314718f, rho, CCL_VARIANT_THESIS), 1.0, 0.0);
    CCL_CHECK(ccl_terrain_fog(0.99f * 69.314718f, rho, CCL_VARIANT_THESIS) < 1.0f);
    CCL_CHECK_REL(ccl_terrain_fog(100.0f, rho, CCL_VARIANT_CORRECTED), 1.0 - exp(-1.0), 1e-6);
}

static void test_terrain_sky_glow_halves_at_7_53_deg(void)
{
    double a = acos(pow(0.5, 1.0 / 80.0));
    ccl_vec3 sun = V(0.0f, 0.0f, -1.0f), black = V(0.0f, 0.0f, 0.0f), white = V(1.0f, 1.0f, 1.0f);
    ccl_vec3 c = ccl_terrain_sky(V((float)sin(a), 0.0f, -(float)cos(a)), sun, black, white, 80.0f);
    CCL_CHECK_REL(a * 180.0 / 3.14159265358979, 7.53, 1e-3);
    CCL_CHECK_CLOSE(c.x, 0.5, 1e-4);
    c = ccl_terrain_sky(sun, sun, black, white, 80.0f);
    CCL_CHECK_CLOSE(c.y, 1.0, 0.0);
}

static void test_terrain_clouds_variants_below_the_horizon(void)
{
    ccl_vec3 sky = V(0.4f, 0.6f, 0.9f), white = V(1.0f, 1.0f, 1.0f), ro = V(0.0f, 0.0f, 0.0f);
    ccl_vec2 wind;
    int i, spurious = 0;
    wind.x = 1.0f;
    wind.y = 0.0f;
    for (i = 0; i < 200; ++i) {
        ccl_vec3 rd = ccl_vec3_normalize(V(0.01f * (float)i, -0.5f, 1.0f));
        ccl_vec3 c = ccl_terrain_clouds(sky, ro, rd, 100.0f, wind, 3.0f, 10.0f, white, 0u, CCL_VARIANT_CORRECTED);
        ccl_vec3 t = ccl_terrain_clouds(sky, ro, rd, 100.0f, wind, 3.0f, 10.0f, white, 0u, CCL_VARIANT_THESIS);
        CCL_CHECK(c.x == sky.x && c.y == sky.y && c.z == sky.z);
        if (t.x != sky.x) spurious++;
    }
    CCL_CHECK(spurious > 0);
}

static void test_terrain_water_weight_normal_incidence(void)
{
    ccl_vec3 n = V(0.0f, 1.0f, 0.0f), down = V(0.0f, -1.0f, 0.0f);
    CCL_CHECK_CLOSE(ccl_terrain_water_weight(down, n, 1.0f), 1.0, 0.0);
    CCL_CHECK_CLOSE(ccl_terrain_water_weight(down, n, 6.0f), 1.0, 0.0);
    CCL_CHECK_REL(ccl_terrain_water_weight(ccl_vec3_normalize(V(1.0f, -1.0f, 0.0f)), n, 3.0f),
                  pow(sqrt(0.5), 3.0), 1e-6);
}

static void test_terrain_params_and_pixel(void)
{
    ccl_terrain_params p;
    const char *field = NULL;
    float m[16] = {0};
    float rgb[3];
    int steps;
    ccl_terrain_params_default(&p);
    CCL_CHECK(ccl_terrain_params_check(&p, &field) == CCL_OK);
    p.max_steps = 0;
    CCL_CHECK(ccl_terrain_params_check(&p, &field) == CCL_EINVAL);
    CCL_CHECK(field != NULL && field[0] == 'm');
    ccl_terrain_params_default(&p);
    p.precision = NAN;
    CCL_CHECK(ccl_terrain_params_check(&p, &field) == CCL_EINVAL);
    ccl_terrain_params_default(&p);
    /* identity-like camera looking down -z: inverse of the rotation-free projection, fov 90 deg, aspect 1 */
    m[0] = 1.0f;
    m[5] = 1.0f;
    m[10] = 0.0f;
    m[14] = -1.0f; /* h.z = -1 for every pixel (m[c * 4 + r]) */
    ccl_terrain_pixel(&p, m, V(0.0f, 30.0f, 0.0f), 0, 7, 8, 8, rgb, &steps);
    CCL_CHECK(rgb[0] >= 0.0f && rgb[0] <= 1.0f && steps >= 1);
}

int main(void)
{
    CCL_RUN(test_terrain_pixel_position_ranges);
    CCL_RUN(test_terrain_fbm_bound);
    CCL_RUN(test_terrain_test_heightmap);
    CCL_RUN(test_terrain_marches_find_the_same_surface);
    CCL_RUN(test_terrain_shadows);
    CCL_RUN(test_terrain_normal_y_is_2h);
    CCL_RUN(test_terrain_normal_octaves_policy);
    CCL_RUN(test_terrain_fog_variants);
    CCL_RUN(test_terrain_sky_glow_halves_at_7_53_deg);
    CCL_RUN(test_terrain_clouds_variants_below_the_horizon);
    CCL_RUN(test_terrain_water_weight_normal_incidence);
    CCL_RUN(test_terrain_params_and_pixel);
    return ccl_test_report();
}
