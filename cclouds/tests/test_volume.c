/* C unit tests of cclouds/volume.h: trilinear voxel sampling, box intersection, the light volume, the pixel (empty
 * scene = background, opaque cloud hides it, lit side brighter), the survey extras oc-4.2 (metaball kernel) and
 * oc-4.3 (textured ellipsoid), bad input. */
#include "cclouds/flight.h"
#include "cclouds/volume.h"
#include "ccl_test.h"

#include <stdlib.h>

#define N 16
#define M (N / CCL_VOLUME_BRICK) /* bricks per axis */
static unsigned char ball[N * N * N];
static float ball_light[N * N * N];
static unsigned char empty[N * N * N];
static float empty_light[N * N * N];
static unsigned char all_bricks[(N / CCL_VOLUME_BRICK) * (N / CCL_VOLUME_BRICK) * (N / CCL_VOLUME_BRICK)]; /* skip distance 0 everywhere: no skipping */
static unsigned char ball_bricks[(N / CCL_VOLUME_BRICK) * (N / CCL_VOLUME_BRICK) * (N / CCL_VOLUME_BRICK)];

static void make_ball(void)
{
    int x, y, z;
    for (x = 0; x < (N / CCL_VOLUME_BRICK) * (N / CCL_VOLUME_BRICK) * (N / CCL_VOLUME_BRICK); ++x) all_bricks[x] = 0;
    for (z = 0; z < N; ++z)
        for (y = 0; y < N; ++y)
            for (x = 0; x < N; ++x) {
                float dx = (float)x + 0.5f - N / 2.0f, dy = (float)y + 0.5f - N / 2.0f, dz = (float)z + 0.5f - N / 2.0f;
                ball[(z * N + y) * N + x] = (dx * dx + dy * dy + dz * dz < 36.0f) ? 255 : 0;
                empty[(z * N + y) * N + x] = 0;
            }
}

static ccl_volume_grid grid_of(const unsigned char *d, const float *l, ccl_vec3 origin, ccl_vec3 extent)
{
    ccl_volume_grid g;
    g.density = d;
    g.light = l;
    g.skip = all_bricks;
    g.nx = g.ny = g.nz = N;
    g.origin = origin;
    g.extent = extent;
    return g;
}

static void test_volume_sample(void)
{
    unsigned char vox[8] = {0, 255, 0, 255, 0, 255, 0, 255}; /* 2^3, value = 255 x */
    /* at voxel centres the stored value, between them linear in x, clamped outside */
    CCL_CHECK_CLOSE(ccl_volume_sample(vox, 2, 2, 2, V(0.5f, 0.5f, 0.5f)), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_volume_sample(vox, 2, 2, 2, V(1.5f, 0.5f, 1.5f)), 1.0, 1e-7);
    CCL_CHECK_CLOSE(ccl_volume_sample(vox, 2, 2, 2, V(1.0f, 1.2f, 0.7f)), 0.5, 1e-7);
    CCL_CHECK_CLOSE(ccl_volume_sample(vox, 2, 2, 2, V(1.25f, 0.0f, 2.0f)), 0.75, 1e-7);
    CCL_CHECK_CLOSE(ccl_volume_sample(vox, 2, 2, 2, V(-5.0f, 9.0f, 0.5f)), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_volume_sample(vox, 2, 2, 2, V(7.0f, 0.5f, 0.5f)), 1.0, 1e-7);
}

static void test_volume_box(void)
{
    ccl_volume_grid g;
    float t0, t1;
    make_ball();
    g = grid_of(ball, ball_light, V(-10.0f, 0.0f, -10.0f), V(20.0f, 10.0f, 20.0f));
    CCL_CHECK(ccl_volume_box(&g, V(0.0f, 5.0f, 50.0f), V(0.0f, 0.0f, -1.0f), &t0, &t1));
    CCL_CHECK_CLOSE(t0, 40.0, 1e-4);
    CCL_CHECK_CLOSE(t1, 60.0, 1e-4);
    /* behind the eye: no hit; inside: t0 < 0 < t1 */
    CCL_CHECK(!ccl_volume_box(&g, V(0.0f, 5.0f, 50.0f), V(0.0f, 0.0f, 1.0f), &t0, &t1));
    CCL_CHECK(ccl_volume_box(&g, V(0.0f, 5.0f, 0.0f), V(1.0f, 0.0f, 0.0f), &t0, &t1) && t0 < 0.0f && t1 > 0.0f);
    CCL_CHECK_CLOSE(t1, 10.0, 1e-4);
    /* misses above */
    CCL_CHECK(!ccl_volume_box(&g, V(0.0f, 15.0f, 50.0f), V(0.0f, 0.0f, -1.0f), &t0, &t1));
}

static void test_volume_light(void)
{
    ccl_volume_params p;
    ccl_volume_grid g;
    int i;
    ccl_volume_params_default(&p);
    p.sun = V(0.0f, 1.0f, 0.0f);
    make_ball();
    g = grid_of(empty, empty_light, V(0.0f, 0.0f, 0.0f), V(16.0f, 16.0f, 16.0f));
    CCL_CHECK(ccl_volume_light(&p, &g, empty_light, N * N * N) == CCL_OK);
    for (i = 0; i < N * N * N; ++i) CCL_CHECK(empty_light[i] == 1.0f);
    g = grid_of(ball, ball_light, V(0.0f, 0.0f, 0.0f), V(16.0f, 16.0f, 16.0f));
    CCL_CHECK(ccl_volume_light(&p, &g, ball_light, N * N * N) == CCL_OK);
    /* sun from above: the bottom of the ball is darker than its top; above the ball full light */
    {
        float top = ball_light[(8 * N + 12) * N + 8], bottom = ball_light[(8 * N + 3) * N + 8];
        float above = ball_light[(8 * N + 15) * N + 8];
        CCL_CHECK(above == 1.0f);
        CCL_CHECK(bottom < top && top < 1.0f);
        /* the bottom voxel sees ~11 voxels of 255 above it: exp(-0.25 * 11) within the trilinear edges */
        CCL_CHECK(bottom < expf(-0.25f * 9.0f) && bottom > expf(-0.25f * 13.0f));
    }
    CCL_CHECK(ccl_volume_light(&p, &g, ball_light, 10) == CCL_EINVAL);
    p.light_step_voxels = 0.0f;
    CCL_CHECK(ccl_volume_light(&p, &g, ball_light, N * N * N) == CCL_EINVAL);
}

static void test_volume_pixel(void)
{
    ccl_volume_params p;
    ccl_volume_grid g;
    ccl_camera cam;
    float rgb[3], rgb2[3];
    ccl_vec3 bg;
    float t;
    const char *field = NULL;
    ccl_volume_params_default(&p);
    make_ball();
    g = grid_of(ball, ball_light, V(-40.0f, 60.0f, -240.0f), V(80.0f, 80.0f, 80.0f));
    CCL_CHECK(ccl_volume_light(&p, &g, ball_light, N * N * N) == CCL_OK);
    CCL_CHECK(ccl_volume_check(&p, &g, 1, &field) == CCL_OK);
    CCL_CHECK(ccl_camera_look_at(V(0.0f, 100.0f, 0.0f), V(0.0f, 100.0f, -1.0f), V(0.0f, 1.0f, 0.0f), 0.8f, 1.0f,
                                 0.1f, 1e5f, &cam) == CCL_OK);
    /* no grids: the background (the sky here) */
    ccl_volume_pixel(&p, &g, 0, &cam, 20, 20, 41, 41, rgb);
    bg = ccl_volume_background(&p, cam.eye, ccl_camera_ray(cam.inv_view_proj_rot, 20, 20, 41, 41), &t);
    CCL_CHECK(rgb[0] == bg.x && rgb[1] == bg.y && rgb[2] == bg.z);
    CCL_CHECK(t > 1e30f);
    /* the ball straight ahead: a dense cloud hides the sky, its colour is the cloud's */
    ccl_volume_pixel(&p, &g, 1, &cam, 20, 20, 41, 41, rgb);
    CCL_CHECK(fabsf(rgb[0] - bg.x) + fabsf(rgb[2] - bg.z) > 0.05f);
    /* a corner pixel misses the ball: the background */
    ccl_volume_pixel(&p, &g, 1, &cam, 0, 0, 41, 41, rgb2);
    bg = ccl_volume_background(&p, cam.eye, ccl_camera_ray(cam.inv_view_proj_rot, 0, 0, 41, 41), &t);
    CCL_CHECK(rgb2[0] == bg.x && rgb2[1] == bg.y && rgb2[2] == bg.z);
    /* an empty grid changes nothing */
    g.density = empty;
    ccl_volume_pixel(&p, &g, 1, &cam, 20, 20, 41, 41, rgb2);
    bg = ccl_volume_background(&p, cam.eye, ccl_camera_ray(cam.inv_view_proj_rot, 20, 20, 41, 41), &t);
    CCL_CHECK(rgb2[0] == bg.x && rgb2[1] == bg.y && rgb2[2] == bg.z);
    /* deterministic */
    g.density = ball;
    ccl_volume_pixel(&p, &g, 1, &cam, 20, 20, 41, 41, rgb2);
    CCL_CHECK(rgb[0] == rgb2[0] && rgb[1] == rgb2[1] && rgb[2] == rgb2[2]);
    /* empty-space skipping changes no pixel: the ball's occupancy (corner bricks empty) vs no skipping */
    CCL_CHECK(ccl_volume_occupancy(&g, ball_bricks, sizeof ball_bricks) == CCL_OK);
    {
        int x, y, empty_bricks = 0, i;
        for (i = 0; i < (int)sizeof ball_bricks; ++i) empty_bricks += ball_bricks[i] == 0;
        CCL_CHECK(empty_bricks > 0 && ball_bricks[(M / 2 * M + M / 2) * M + M / 2] == 1);
        /* the skip distances: 0 where occupied, >= 1 for the empty corner bricks, 1 next to an occupied one */
        CCL_CHECK(ccl_volume_skip(&g, ball_bricks, sizeof ball_bricks) == CCL_OK);
        CCL_CHECK(ball_bricks[0] >= 1 && ball_bricks[(M / 2 * M + M / 2) * M + M / 2] == 0);
        for (i = 0; i < (int)sizeof ball_bricks; ++i) CCL_CHECK(ball_bricks[i] < M);
        for (y = 0; y < 41; y += 3)
            for (x = 0; x < 41; x += 3) {
                g.skip = all_bricks;
                ccl_volume_pixel(&p, &g, 1, &cam, x, y, 41, 41, rgb);
                g.skip = ball_bricks;
                ccl_volume_pixel(&p, &g, 1, &cam, x, y, 41, 41, rgb2);
                CCL_CHECK(rgb[0] == rgb2[0] && rgb[1] == rgb2[1] && rgb[2] == rgb2[2]);
            }
        CCL_CHECK(ccl_volume_occupancy(&g, ball_bricks, 3) == CCL_EINVAL);
        CCL_CHECK(ccl_volume_skip(&g, ball_bricks, 3) == CCL_EINVAL);
    }
}

static void test_volume_ground_and_aircraft(void)
{
    ccl_volume_params p;
    ccl_vec3 f, r, u, c, d;
    float t;
    ccl_volume_params_default(&p);
    /* looking down: the ground; looking up: the sky with a brighter zenith blue */
    c = ccl_volume_background(&p, V(0.0f, 100.0f, 0.0f), V(0.0f, -1.0f, 0.0f), &t);
    CCL_CHECK(c.y > c.z); /* green-brown, not blue */
    {
        /* the generated ground: Lambert under the sun and the sky, fogged; its albedo varies within a noise cell
         * (value noise, not fields of one colour) and between cells, and stays within [0, 1] */
        ccl_vec3 a = ccl_volume_ground(&p, 0.0f, 0.0f);
        float fog = expf(-100.0f / p.fog_distance), x, lo = 1.0f, hi = 0.0f, step = 0.0f, prev = a.y;
        CCL_CHECK_CLOSE(c.y, p.sky_horizon.y + (a.y * (p.sun_colour.y * p.sun.y + p.ambient_top.y)
                                                - p.sky_horizon.y) * fog, 1e-5);
        for (x = 5.0f; x < 1800.0f; x += 5.0f) {
            ccl_vec3 g = ccl_volume_ground(&p, x, 37.0f);
            CCL_CHECK(g.x >= 0.0f && g.x <= 1.0f && g.y >= 0.0f && g.y <= 1.0f && g.z >= 0.0f && g.z <= 1.0f);
            lo = g.y < lo ? g.y : lo;
            hi = g.y > hi ? g.y : hi;
            step += fabsf(g.y - prev) > 1e-6f;
            prev = g.y;
        }
        CCL_CHECK(hi - lo > 0.1f && step > 300.0f);
    }
    c = ccl_volume_background(&p, V(0.0f, 100.0f, 0.0f), V(0.0f, 1.0f, 0.0f), &t);
    CCL_CHECK_CLOSE(c.z, p.sky_zenith.z + p.sun_colour.z * p.sun_glow * powf(p.sun.y, p.sun_glow_power), 1e-6);
    /* the aircraft 50 m ahead is hit at 50 m minus the wing's half chord... its top surface seen from above */
    ccl_flight_axes(0.0f, 0.0f, 0.0f, &f, &r, &u);
    p.aircraft = 1;
    p.aircraft_position = V(0.0f, 100.0f, -50.0f);
    p.aircraft_forward = f;
    p.aircraft_right = r;
    p.aircraft_up = u;
    d = V(0.0f, 0.0f, -1.0f);
    c = ccl_volume_background(&p, V(0.0f, 100.0f, 0.0f), d, &t);
    /* looking at the tail cone along the axis: the first surface is the tail boom's end near z_model = 3.75 */
    CCL_CHECK(t > 45.0f && t < 50.0f);
    CCL_CHECK(c.x >= 0.0f && c.x < 1.5f);
    /* missing it */
    c = ccl_volume_background(&p, V(0.0f, 100.0f, 0.0f), V(0.0f, 0.6f, -0.8f), &t);
    CCL_CHECK(t > 1e30f);
}

static void test_volume_metaball(void)
{
    CCL_CHECK_CLOSE(ccl_volume_metaball(0.0f, 2.0f, 3.0f), 3.0, 0.0);
    CCL_CHECK_CLOSE(ccl_volume_metaball(2.0f, 2.0f, 3.0f), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_volume_metaball(5.0f, 2.0f, 3.0f), 0.0, 0.0);
    /* independent value: r = R/2: (3/4)^3 */
    CCL_CHECK_REL(ccl_volume_metaball(1.0f, 2.0f, 1.0f), 27.0 / 64.0, 1e-6);
    /* monotone decreasing in r */
    CCL_CHECK(ccl_volume_metaball(0.5f, 2.0f, 1.0f) > ccl_volume_metaball(0.6f, 2.0f, 1.0f));
}

static void test_volume_ellipsoid(void)
{
    ccl_vec3 radii = V(4.0f, 2.0f, 3.0f);
    /* centre: (texture - t1) / d; on the surface it needs texture > t1 + d to be seen */
    CCL_CHECK_REL(ccl_volume_ellipsoid(V(0, 0, 0), radii, 0.6f, 0.2f, 0.8f), 0.5, 1e-6);
    CCL_CHECK_CLOSE(ccl_volume_ellipsoid(V(4.0f, 0, 0), radii, 0.9f, 0.2f, 0.8f), 0.0, 0.0);
    CCL_CHECK_CLOSE(ccl_volume_ellipsoid(V(0, 2.0f, 0), radii, 1.0f, 0.0f, 0.5f), 1.0, 0.0);
    CCL_CHECK_CLOSE(ccl_volume_ellipsoid(V(0, 0, 9.0f), radii, 1.0f, 0.0f, 0.5f), 0.0, 0.0);
    /* monotone: more texture, more opacity; further out, less */
    CCL_CHECK(ccl_volume_ellipsoid(V(1, 1, 1), radii, 0.7f, 0.2f, 0.8f) >
              ccl_volume_ellipsoid(V(1, 1, 1), radii, 0.6f, 0.2f, 0.8f));
    CCL_CHECK(ccl_volume_ellipsoid(V(1, 1, 1), radii, 0.7f, 0.2f, 0.8f) >
              ccl_volume_ellipsoid(V(2, 1, 1), radii, 0.7f, 0.2f, 0.8f));
}

static void test_volume_check(void)
{
    ccl_volume_params p;
    ccl_volume_grid g;
    const char *field = NULL;
    ccl_volume_params_default(&p);
    g = grid_of(ball, ball_light, V(0, 0, 0), V(1, 1, 1));
    CCL_CHECK(ccl_volume_check(&p, &g, 1, &field) == CCL_OK);
    g.extent.y = 0.0f;
    CCL_CHECK(ccl_volume_check(&p, &g, 1, &field) == CCL_EINVAL && field[0] == 'e');
    g.extent.y = 1.0f;
    CCL_CHECK(ccl_volume_check(&p, &g, CCL_VOLUME_MAX_GRIDS + 1, &field) == CCL_EINVAL);
    p.sun = V(0.0f, 2.0f, 0.0f);
    CCL_CHECK(ccl_volume_check(&p, &g, 1, &field) == CCL_EINVAL && field[0] == 's');
    ccl_volume_params_default(&p);
    p.g = 1.0f;
    CCL_CHECK(ccl_volume_check(&p, &g, 1, &field) == CCL_EINVAL && field[0] == 'g');
}

int main(void)
{
    CCL_RUN(test_volume_sample);
    CCL_RUN(test_volume_box);
    CCL_RUN(test_volume_light);
    CCL_RUN(test_volume_pixel);
    CCL_RUN(test_volume_ground_and_aircraft);
    CCL_RUN(test_volume_metaball);
    CCL_RUN(test_volume_ellipsoid);
    CCL_RUN(test_volume_check);
    return ccl_test_report();
}
