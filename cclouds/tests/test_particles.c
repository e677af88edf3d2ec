/* C unit tests of cclouds/particles.h: spawn box and sizes, particle counts of both variants, determinism, streaks,
 * the capture lookup, the compositing of a uniform capture, the lit pixel's closed form. */
#include <math.h>
#include <string.h>

#include "cclouds/particles.h"
#include "ccl_test.h"

#define N 256

static void test_params_default_and_check(void)
{
    ccl_particles_params p;
    const char *field = NULL;
    ccl_particles_params_default(&p);
    CCL_CHECK(ccl_particles_params_check(&p, &field) == CCL_OK && field == NULL);
    CCL_CHECK_CLOSE(p.box_min.x, -1.0, 0.0);
    CCL_CHECK_CLOSE(p.box_max.y, 1.25, 0.0);
    CCL_CHECK_CLOSE(p.respawn_y, -1.0, 0.0);
    p.size_samples = 0;
    CCL_CHECK(ccl_particles_params_check(&p, &field) == CCL_EINVAL && strcmp(field, "size_samples") == 0);
    ccl_particles_params_default(&p);
    p.wind.y = 1.0f;
    CCL_CHECK(ccl_particles_params_check(&p, &field) == CCL_EINVAL && strcmp(field, "wind") == 0);
    ccl_particles_params_default(&p);
    p.respawn_y = 2.0f;
    CCL_CHECK(ccl_particles_params_check(&p, &field) == CCL_EINVAL && strcmp(field, "respawn_y") == 0);
}

static void test_spawn_in_box_and_sizes_bounded(void)
{
    ccl_particles_params p;
    uint32_t i;
    double sum = 0.0, sum2 = 0.0;
    ccl_particles_params_default(&p);
    for (i = 0; i < 4000; ++i) {
        ccl_vec3 pos;
        float r, v;
        ccl_particles_spawn(&p, i, 0u, 0, &pos, &r, &v);
        CCL_CHECK(pos.x >= -1.0f && pos.x < 1.0f && pos.y >= 1.0f && pos.y < 1.25f && pos.z >= -1.5f && pos.z < 1.5f);
        CCL_CHECK(r >= 0.8f && r < 1.8f);
        CCL_CHECK(v > 0.0f && v <= 9.23f / 4.0f);
        sum += (double)r;
        sum2 += (double)r * (double)r;
    }
    sum /= 4000.0;
    CCL_CHECK_CLOSE(sum, 1.3, 0.01);                                    /* mean */
    CCL_CHECK_CLOSE(sqrt(sum2 / 4000.0 - sum * sum), 1.0 / sqrt(96.0), 0.01); /* Irwin-Hall sigma */
}

static void test_speed_from_table(void)
{
    ccl_particles_params p;
    ccl_vec3 pos;
    float r, v;
    ccl_particles_params_default(&p);
    p.size_mean_mm = 1.0f;
    p.size_spread_mm = 0.0f;
    ccl_particles_spawn(&p, 7u, 0u, 0, &pos, &r, &v);
    CCL_CHECK_CLOSE(r, 1.0, 0.0);
    CCL_CHECK_CLOSE(v, 6.59 / 4.0, 1e-6); /* Table 2.2: 1.0 mm -> 6.59 m/s, slowed 4x */
}

static void test_counts_both_variants(void)
{
    static ccl_vec3 pos[N];
    static float rad[N], spd[N];
    static uint32_t gen[N];
    ccl_particles_params p;
    int count = 0;
    ccl_particles_params_default(&p);
    CCL_CHECK(ccl_particles_simulate(&p, 100, 1.0f / 60.0f, 30, 0, CCL_VARIANT_CORRECTED, N, pos, rad, spd, gen,
                                     &count) == CCL_OK);
    CCL_CHECK(count == 30); /* one particle per frame */
    CCL_CHECK(ccl_particles_simulate(&p, 100, 1.0f / 60.0f, 200, 0, CCL_VARIANT_CORRECTED, N, pos, rad, spd, gen,
                                     &count) == CCL_OK);
    CCL_CHECK(count == 100); /* up to the requested count */
    CCL_CHECK(ccl_particles_simulate(&p, 40, 1.0f / 60.0f, 1, 0, CCL_VARIANT_CORRECTED, N, pos, rad, spd, gen,
                                     &count) == CCL_OK);
    CCL_CHECK(count == 40); /* removal when the count drops */
    count = 0;
    CCL_CHECK(ccl_particles_simulate(&p, 100, 1.0f / 60.0f, 25, 0, CCL_VARIANT_THESIS, N, pos, rad, spd, gen,
                                     &count) == CCL_OK);
    CCL_CHECK(count == -25); /* the printed decrement: never a particle */
    count = 0;
    CCL_CHECK(ccl_particles_simulate(&p, 100, 1.0f / 60.0f, 0, 1, CCL_VARIANT_CORRECTED, N, pos, rad, spd, gen,
                                     &count) == CCL_OK);
    CCL_CHECK(count == 100); /* warm start */
    CCL_CHECK(ccl_particles_simulate(&p, 300, 1.0f / 60.0f, 1, 0, CCL_VARIANT_CORRECTED, N, pos, rad, spd, gen,
                                     &count) == CCL_EINVAL); /* requested > capacity */
}

static void test_fall_respawn_and_determinism(void)
{
    static ccl_vec3 a[N], b[N];
    static float ra[N], sa[N], rb[N], sb[N];
    static uint32_t ga[N], gb[N];
    ccl_particles_params p;
    int ca = 0, cb = 0, i, respawned = 0;
    ccl_particles_params_default(&p);
    p.seed = 42u;
    ccl_particles_simulate(&p, 64, 1.0f / 30.0f, 0, 1, CCL_VARIANT_CORRECTED, N, a, ra, sa, ga, &ca);
    ccl_particles_simulate(&p, 64, 1.0f / 30.0f, 0, 1, CCL_VARIANT_CORRECTED, N, b, rb, sb, gb, &cb);
    ccl_particles_simulate(&p, 64, 1.0f / 30.0f, 120, 0, CCL_VARIANT_CORRECTED, N, a, ra, sa, ga, &ca);
    ccl_particles_simulate(&p, 64, 1.0f / 30.0f, 120, 0, CCL_VARIANT_CORRECTED, N, b, rb, sb, gb, &cb);
    CCL_CHECK(memcmp(a, b, sizeof(ccl_vec3) * 64) == 0 && memcmp(ga, gb, sizeof(uint32_t) * 64) == 0);
    for (i = 0; i < 64; ++i) {
        CCL_CHECK(a[i].y >= -1.0f - 9.23f / 4.0f / 30.0f && a[i].y < 1.25f);
        respawned += ga[i] > 0u;
    }
    CCL_CHECK(respawned > 0); /* 4 s at >= 0.9 m/s: every drop fell through the 2.25 units at least once */
}

static void test_streak(void)
{
    float off, len = ccl_particles_streak(2.0f, 0.075f, 0.01f, &off);
    CCL_CHECK_CLOSE(len, 0.15, 1e-7);
    CCL_CHECK_CLOSE(off, (0.15 / 6.0) / (0.02 + 0.15), 1e-7);
    len = ccl_particles_streak(0.0f, 0.075f, 0.01f, &off);
    CCL_CHECK(len == 0.0f && off == 0.0f);
}

static void test_capture_uv(void)
{
    ccl_vec2 ndc = {0.0f, 0.0f}, uv;
    float fv = 1.0471976f, fc = 2.6179939f; /* 60 and 150 deg */
    uv = ccl_particles_capture_uv(ndc, 16.0f / 9.0f, fv, fc);
    CCL_CHECK_CLOSE(uv.x, 0.5, 0.0);
    CCL_CHECK_CLOSE(uv.y, 0.5, 0.0);
    ndc.y = 1.0f; /* the top edge of the view: 30 deg up */
    uv = ccl_particles_capture_uv(ndc, 16.0f / 9.0f, fv, fc);
    CCL_CHECK_CLOSE(uv.y, 0.5 - 0.5 * tan(30.0 * 3.14159265358979 / 180.0) / tan(75.0 * 3.14159265358979 / 180.0),
                    1e-6);
}

static void test_uniform_capture_gives_its_colour(void)
{
    static float mask[8 * 8 * 4], capture[4 * 4 * 3];
    ccl_particles_sprite s = {10.0f, 10.0f, 4.0f, 12.0f, 0.1f, 1.0f};
    ccl_vec2 p_o = {0.5f, 0.5f};
    ccl_vec3 bg = {0.25f, 0.5f, 0.75f}, c;
    int i;
    for (i = 0; i < 8 * 8; ++i) {
        mask[4 * i] = 0.1f;
        mask[4 * i + 1] = -0.2f;
        mask[4 * i + 2] = 0.9f;
        mask[4 * i + 3] = 1.0f;
    }
    for (i = 0; i < 4 * 4 * 3; i += 3) {
        capture[i] = 0.25f;
        capture[i + 1] = 0.5f;
        capture[i + 2] = 0.75f;
    }
    /* the streak average of a uniform background is that background, whatever the alpha */
    c = ccl_particles_shade_pixel(&s, 1, mask, 8, capture, 4, 10, 10, p_o, 0.13f, CCL_PARTICLES_LINEAR, 1, 0.5f, bg);
    CCL_CHECK_CLOSE(c.x, 0.25, 1e-7);
    CCL_CHECK_CLOSE(c.y, 0.5, 1e-7);
    CCL_CHECK_CLOSE(c.z, 0.75, 1e-7);
    bg.x = 0.0f;
    c = ccl_particles_shade_pixel(&s, 1, mask, 8, capture, 4, 10, 10, p_o, 0.13f, CCL_PARTICLES_NEAREST, 0, 1.0f, bg);
    CCL_CHECK_CLOSE(c.x, 0.25, 1e-7); /* a drop pixel is the capture's colour */
    c = ccl_particles_shade_pixel(&s, 1, mask, 8, capture, 4, 30, 10, p_o, 0.13f, CCL_PARTICLES_NEAREST, 0, 1.0f, bg);
    CCL_CHECK_CLOSE(c.x, 0.0, 0.0); /* outside the billboard: the background */
}

static void test_lit_pixel_closed_form(void)
{
    /* one drop at p = (0, 0, -1) straight ahead, every normal facing the eye (mask frame (0, 0, -1) -> scene (0, 0, 1)
     * with forward = -z), light 1 behind the eye at (0, 0, 1): dist 2, V_PE = V_PL = V_N, A1 = C_L / (1 + (2/2)^2) =
     * C_L / 2, A2 = 1, A3 = max(0, -1 * 2) = 0; C_F = C_O C_amb + C_L / 2 */
    static float mask[8 * 8 * 4], normals[8 * 8 * 3], capture[4 * 4 * 3];
    ccl_particles_sprite s = {10.0f, 10.0f, 4.0f, 4.0f, 0.0f, 1.0f};
    ccl_vec3 pos = {0.0f, 0.0f, -1.0f};
    ccl_particles_lights L;
    ccl_vec2 p_o = {0.5f, 0.5f};
    ccl_vec3 bg = {0.0f, 0.0f, 0.0f}, c, u;
    int i;
    for (i = 0; i < 8 * 8; ++i) {
        mask[4 * i] = 0.1f;
        mask[4 * i + 1] = -0.2f;
        mask[4 * i + 2] = 0.9f;
        mask[4 * i + 3] = 1.0f;
        normals[3 * i] = 0.0f;
        normals[3 * i + 1] = 0.0f;
        normals[3 * i + 2] = -1.0f;
    }
    for (i = 0; i < 4 * 4 * 3; i += 3) {
        capture[i] = 0.25f;
        capture[i + 1] = 0.5f;
        capture[i + 2] = 0.75f;
    }
    memset(&L, 0, sizeof L);
    L.ambient.x = L.ambient.y = L.ambient.z = 1.0f;
    L.r_half = 2.0f;
    L.variant = CCL_VARIANT_CORRECTED;
    L.right.x = 1.0f;
    L.up.y = 1.0f;
    L.forward.z = -1.0f;
    /* lights off, ambient 1: the unlit colour */
    c = ccl_particles_shade_pixel_lit(&s, &pos, 1, mask, normals, 8, capture, 4, 10, 10, p_o, 0.13f,
                                      CCL_PARTICLES_NEAREST, 0, 1.0f, &L, bg);
    u = ccl_particles_shade_pixel(&s, 1, mask, 8, capture, 4, 10, 10, p_o, 0.13f, CCL_PARTICLES_NEAREST, 0, 1.0f, bg);
    CCL_CHECK(c.x == u.x && c.y == u.y && c.z == u.z);
    L.l1.z = 1.0f;
    L.c_l1.x = L.c_l1.y = L.c_l1.z = 0.2f;
    c = ccl_particles_shade_pixel_lit(&s, &pos, 1, mask, normals, 8, capture, 4, 10, 10, p_o, 0.13f,
                                      CCL_PARTICLES_NEAREST, 0, 1.0f, &L, bg);
    CCL_CHECK_CLOSE(c.x, 0.35, 1e-6);
    CCL_CHECK_CLOSE(c.y, 0.6, 1e-6);
    CCL_CHECK_CLOSE(c.z, 0.85, 1e-6);
    /* ambient scales the refracted colour */
    L.c_l1.x = L.c_l1.y = L.c_l1.z = 0.0f;
    L.ambient.y = 0.5f;
    c = ccl_particles_shade_pixel_lit(&s, &pos, 1, mask, normals, 8, capture, 4, 10, 10, p_o, 0.13f,
                                      CCL_PARTICLES_NEAREST, 0, 1.0f, &L, bg);
    CCL_CHECK_CLOSE(c.y, 0.25, 1e-7);
    /* NULL lights: the unlit pixel */
    c = ccl_particles_shade_pixel_lit(&s, &pos, 1, mask, normals, 8, capture, 4, 10, 10, p_o, 0.13f,
                                      CCL_PARTICLES_NEAREST, 0, 1.0f, NULL, bg);
    CCL_CHECK(c.y == u.y);
}

int main(void)
{
    CCL_RUN(test_params_default_and_check);
    CCL_RUN(test_spawn_in_box_and_sizes_bounded);
    CCL_RUN(test_speed_from_table);
    CCL_RUN(test_counts_both_variants);
    CCL_RUN(test_fall_respawn_and_determinism);
    CCL_RUN(test_streak);
    CCL_RUN(test_capture_uv);
    CCL_RUN(test_uniform_capture_gives_its_colour);
    CCL_RUN(test_lit_pixel_closed_form);
    return ccl_test_report();
}
