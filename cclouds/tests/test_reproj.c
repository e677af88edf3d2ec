/* C unit tests of cclouds/reproj.h: eq 4.1 coverage (exactly once per 16 frames, also for sizes not divisible by 4),
 * the reduced-buffer mapping, and the reprojection pass (static camera returns the previous frame exactly, fallback
 * paths, bad input); the depth-aware pass (the thesis's settings give ccl_reproj_frame's colours, a plane of known
 * depth and a sideways step of whole pixels give the exact previous position, static camera with Catmull-Rom, bad
 * input). */
#include "cclouds/reproj.h"
#include "ccl_test.h"

#include <stdlib.h>
#include <string.h>

static void test_reprojection_pixel_order_and_wrap(void)
{
    int x, y;
    ccl_reproj_pixel(2, 3, 0, &x, &y);
    CCL_CHECK(x == 8 && y == 12);
    ccl_reproj_pixel(2, 3, 1, &x, &y); /* column by column: (a, b) = (0, 1) */
    CCL_CHECK(x == 8 && y == 13);
    ccl_reproj_pixel(2, 3, 4, &x, &y); /* (1, 0) */
    CCL_CHECK(x == 9 && y == 12);
    ccl_reproj_pixel(2, 3, 15, &x, &y);
    CCL_CHECK(x == 11 && y == 15);
    ccl_reproj_pixel(2, 3, 16 * 7 + 5, &x, &y); /* f wraps mod 16 */
    CCL_CHECK(x == 9 && y == 13);
    ccl_reproj_pixel(0, 0, -1, &x, &y); /* -1 == 15 (mod 16) */
    CCL_CHECK(x == 3 && y == 3);
}

/* every pixel of a W x H frame is written exactly once over 16 consecutive frames (threads outside skipped) */
static int coverage_ok(int w, int h, int first_frame)
{
    int gw, gh, f, i, j, x, y, ok = 1;
    int *count = (int *)calloc((size_t)w * (size_t)h, sizeof(int));
    if (!count || ccl_reproj_grid(w, h, &gw, &gh) != CCL_OK) {
        free(count);
        return 0;
    }
    for (f = first_frame; f < first_frame + 16; ++f)
        for (j = 0; j < gh; ++j)
            for (i = 0; i < gw; ++i) {
                ccl_reproj_pixel(i, j, f, &x, &y);
                if (x >= w || y >= h) continue; /* the bounds rule */
                count[y * w + x] += 1;
                if (!ccl_reproj_updated(x, y, f)) ok = 0;
            }
    for (i = 0; i < w * h; ++i)
        if (count[i] != 1) ok = 0;
    free(count);
    return ok;
}

static void test_reprojection_coverage_exactly_once(void)
{
    int gw, gh;
    CCL_CHECK(coverage_ok(16, 8, 0));
    CCL_CHECK(coverage_ok(10, 7, 0));
    CCL_CHECK(coverage_ok(10, 7, 37));
    CCL_CHECK(coverage_ok(1, 1, 0));
    CCL_CHECK(coverage_ok(5, 3, 3));
    CCL_CHECK(ccl_reproj_grid(10, 7, &gw, &gh) == CCL_OK && gw == 3 && gh == 2);
    CCL_CHECK(ccl_reproj_grid(8, 4, &gw, &gh) == CCL_OK && gw == 2 && gh == 1);
    CCL_CHECK(ccl_reproj_grid(0, 4, &gw, &gh) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_grid(4, -1, &gw, &gh) == CCL_EINVAL);
}

static void test_reduced_coord(void)
{
    float rx, ry;
    int i, j, f, x, y;
    /* the pixel rendered by thread (i, j) maps to texel (i, j) exactly */
    for (f = 0; f < 16; ++f)
        for (j = 0; j < 2; ++j)
            for (i = 0; i < 3; ++i) {
                ccl_reproj_pixel(i, j, f, &x, &y);
                if (x >= 10 || y >= 7) continue;
                ccl_reproj_reduced_coord(x, y, f, 10, 7, &rx, &ry);
                CCL_CHECK(rx == (float)i && ry == (float)j);
            }
    /* in between: (x - a)/4; frame 5 -> (a, b) = (1, 1) */
    ccl_reproj_reduced_coord(3, 4, 5, 16, 16, &rx, &ry);
    CCL_CHECK(rx == 0.5f && ry == 0.75f);
    /* clamped to texels written this frame: 10 wide, a = 3 -> last texel floor((9 - 3)/4) = 1 */
    ccl_reproj_reduced_coord(9, 0, 12, 10, 7, &rx, &ry);
    CCL_CHECK(rx == 1.0f && ry == 0.0f);
    ccl_reproj_reduced_coord(0, 0, 5, 16, 16, &rx, &ry);
    CCL_CHECK(rx == 0.0f && ry == 0.0f);
    /* a 2-pixel-wide frame renders nothing in columns when a >= 2 */
    ccl_reproj_reduced_coord(0, 0, 8, 2, 8, &rx, &ry);
    CCL_CHECK(isnan(rx) && ry == 0.0f);
}

#define W 24
#define H 16
#define C 2

static void fill(float *img, int n, unsigned seed)
{
    int i;
    for (i = 0; i < n; ++i) {
        seed = seed * 1664525u + 1013904223u;
        img[i] = (float)(seed >> 8) / 16777216.0f;
    }
}

static void test_reproject_static_camera_exact(void)
{
    static float cur[H * W * C], prev[H * W * C], red[4 * 6 * C], out[H * W * C];
    ccl_camera cam;
    ccl_cloud_layer L;
    int x, y, ch, f, n_prev = 0;
    fill(cur, H * W * C, 1u);
    fill(prev, H * W * C, 2u);
    fill(red, 4 * 6 * C, 3u);
    ccl_raymarch_cloud_layer_default(&L);
    CCL_CHECK(ccl_camera_look_at(V(0.3f, 0.002f, -0.4f), V(0.8f, 0.5f, -1.2f), V(0, 1, 0), 1.1f, 1.5f, 0.01f, 1000.0f,
                                 &cam) == CCL_OK);
    for (f = 0; f < 16; f += 5) {
        CCL_CHECK(ccl_reproj_frame(cur, prev, red, W, H, C, f, cam.inv_view_proj_rot, cam.eye, cam.view_proj,
                                      L.centre, L.r_inner, 1, 1, out) == CCL_OK);
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x)
                for (ch = 0; ch < C; ++ch) {
                    int k = (y * W + x) * C + ch;
                    if (ccl_reproj_updated(x, y, f)) {
                        CCL_CHECK(out[k] == cur[k]);
                    } else {
                        CCL_CHECK(out[k] == prev[k]);
                        ++n_prev;
                    }
                }
    }
    CCL_CHECK(n_prev == 4 * (H * W - H * W / 16) * C);
}

static void test_reproject_fallback_and_history(void)
{
    static float cur[H * W * C], prev[H * W * C], red[4 * 6 * C], out[H * W * C];
    ccl_camera cam, prev_cam;
    ccl_cloud_layer L;
    int x, y, k;
    fill(cur, H * W * C, 4u);
    fill(prev, H * W * C, 5u);
    /* a reduced buffer linear in the texel coordinates: bilinear interpolation reproduces it exactly */
    for (y = 0; y < 4; ++y)
        for (x = 0; x < 6; ++x) {
            red[(y * 6 + x) * C] = (float)x;
            red[(y * 6 + x) * C + 1] = (float)y;
        }
    ccl_raymarch_cloud_layer_default(&L);
    CCL_CHECK(ccl_camera_look_at(V(0, 0.002f, 0), V(0, 0.4f, -1), V(0, 1, 0), 1.0f, 1.5f, 0.01f, 1000.0f, &cam)
              == CCL_OK);
    /* history off: every pixel not rendered in frame 5 (a = b = 1) comes from the reduced buffer at
     * ((x - 1)/4, (y - 1)/4) clamped to [0, 5] x [0, 3] */
    CCL_CHECK(ccl_reproj_frame(cur, prev, red, W, H, C, 5, cam.inv_view_proj_rot, cam.eye, cam.view_proj, L.centre,
                                  L.r_inner, 1, 0, out) == CCL_OK);
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            k = (y * W + x) * C;
            if (ccl_reproj_updated(x, y, 5)) continue;
            {
                double ex = (x - 1) / 4.0, ey = (y - 1) / 4.0;
                ex = ex < 0 ? 0 : (ex > 5 ? 5 : ex);
                ey = ey < 0 ? 0 : (ey > 3 ? 3 : ey);
                CCL_CHECK_CLOSE(out[k], ex, 1e-6);
                CCL_CHECK_CLOSE(out[k + 1], ey, 1e-6);
            }
        }
    /* the previous camera looked the opposite way: nothing was visible -> the same fallback with history on */
    CCL_CHECK(ccl_camera_look_at(V(0, 0.002f, 0), V(0, 0.4f, 1), V(0, 1, 0), 1.0f, 1.5f, 0.01f, 1000.0f, &prev_cam)
              == CCL_OK);
    CCL_CHECK(ccl_reproj_frame(cur, prev, red, W, H, C, 5, cam.inv_view_proj_rot, cam.eye, prev_cam.view_proj,
                                  L.centre, L.r_inner, 1, 1, out) == CCL_OK);
    k = (4 * W + 7) * C; /* pixel (7, 4): not rendered in frame 5 */
    CCL_CHECK_CLOSE(out[k], 1.5, 1e-6);
    CCL_CHECK_CLOSE(out[k + 1], 0.75, 1e-6);
    /* out may alias current */
    memcpy(out, cur, sizeof cur);
    CCL_CHECK(ccl_reproj_frame(out, prev, red, W, H, C, 5, cam.inv_view_proj_rot, cam.eye, cam.view_proj, L.centre,
                                  L.r_inner, 3, 1, out) == CCL_OK);
    CCL_CHECK(out[(5 * W + 5) * C] == cur[(5 * W + 5) * C]);
}

static void test_reproject_rejects_bad_input(void)
{
    static float cur[H * W * C], prev[H * W * C], red[4 * 6 * C], out[H * W * C];
    ccl_camera cam;
    ccl_vec3 c = V(0, -6371, 0);
    ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), 1.0f, 1.0f, 0.01f, 100.0f, &cam);
    out[0] = 42.0f;
    CCL_CHECK(ccl_reproj_frame(cur, prev, red, 0, H, C, 0, cam.inv_view_proj_rot, cam.eye, cam.view_proj, c,
                                  6372.5f, 1, 1, out) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame(cur, prev, red, W, H, 0, 0, cam.inv_view_proj_rot, cam.eye, cam.view_proj, c,
                                  6372.5f, 1, 1, out) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame(cur, prev, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye, cam.view_proj, c,
                                  6372.5f, 2, 1, out) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame(cur, prev, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye, cam.view_proj, c,
                                  -1.0f, 1, 1, out) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame(cur, prev, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye, cam.view_proj, c,
                                  6372.5f, 1, 1, prev) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame(NULL, prev, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye, cam.view_proj, c,
                                  6372.5f, 1, 1, out) == CCL_EINVAL);
    CCL_CHECK(out[0] == 42.0f);
}

static void test_reprojection_uv_static_is_pixel_centre(void)
{
    ccl_camera cam;
    ccl_cloud_layer L;
    float u, v;
    int x, y;
    ccl_raymarch_cloud_layer_default(&L);
    ccl_camera_look_at(V(3, 0.5f, 7), V(2, 0.6f, 6), V(0, 1, 0), 1.2f, 16.0f / 9.0f, 0.01f, 1000.0f, &cam);
    for (y = 0; y < 1080; y += 97)
        for (x = 0; x < 1920; x += 131) {
            CCL_CHECK(ccl_reproj_uv(cam.inv_view_proj_rot, cam.eye, cam.view_proj, L.centre, L.r_inner, x, y,
                                          1920, 1080, &u, &v) == 1);
            /* float32 round trip: <= 4.5e-4 px measured; u has 24-bit resolution (1.1e-4 px per ulp here) */
            CCL_CHECK_CLOSE((double)u * 1920.0 - 0.5, x, 1e-3);
            CCL_CHECK_CLOSE((double)v * 1080.0 - 0.5, y, 1e-3);
        }
}

static void test_reproject_depth_thesis_settings_equal_frame(void)
{
    static float cur[H * W * C], prev[H * W * C], red[4 * 6 * C], out[H * W * C], ref[H * W * C];
    static float dep[H * W], pdep[H * W], od[H * W];
    ccl_camera cam, pcam;
    ccl_cloud_layer L;
    int i, f;
    fill(cur, H * W * C, 4u);
    fill(prev, H * W * C, 5u);
    fill(red, 4 * 6 * C, 6u);
    fill(dep, H * W, 7u);
    fill(pdep, H * W, 8u);
    for (i = 0; i < H * W; ++i) pdep[i] = 0.5f + 4.0f * pdep[i];
    ccl_raymarch_cloud_layer_default(&L);
    ccl_camera_look_at(V(0.2f, 0.3f, 0.1f), V(0.5f, 0.7f, -0.9f), V(0, 1, 0), 1.2f, 1.5f, 0.01f, 1000.0f, &cam);
    ccl_camera_look_at(V(0.23f, 0.3f, 0.13f), V(0.53f, 0.71f, -0.87f), V(0, 1, 0), 1.2f, 1.5f, 0.01f, 1000.0f,
                       &pcam);
    for (f = 0; f < 16; f += 7) {
        CCL_CHECK(ccl_reproj_frame(cur, prev, red, W, H, C, f, cam.inv_view_proj_rot, cam.eye, pcam.view_proj,
                                   L.centre, L.r_inner, 1, 1, ref) == CCL_OK);
        CCL_CHECK(ccl_reproj_frame_depth(cur, dep, prev, pdep, red, W, H, C, f, cam.inv_view_proj_rot, cam.eye,
                                         pcam.view_proj, pcam.eye, L.centre, L.r_inner, 1, CCL_REPROJ_FILTER_BILINEAR,
                                         0, 1, out, od) == CCL_OK);
        CCL_CHECK(memcmp(out, ref, sizeof out) == 0);
    }
    /* a static camera with the Catmull-Rom filter: the previous frame exactly, its depths to rounding */
    CCL_CHECK(ccl_reproj_frame_depth(cur, dep, prev, pdep, red, W, H, C, 3, cam.inv_view_proj_rot, cam.eye,
                                     cam.view_proj, cam.eye, L.centre, L.r_inner, 1, CCL_REPROJ_FILTER_CATMULL_ROM,
                                     CCL_REPROJ_DEPTH_ITERATIONS, 1, out, od) == CCL_OK);
    for (i = 0; i < H * W; ++i) {
        int x = i % W, y = i / W;
        if (ccl_reproj_updated(x, y, 3)) {
            CCL_CHECK(od[i] == dep[i] && out[i * C] == cur[i * C]);
        } else {
            CCL_CHECK(out[i * C] == prev[i * C] && out[i * C + 1] == prev[i * C + 1]);
            CCL_CHECK_REL(od[i], pdep[i], 1e-6);
        }
    }
}

/* a plane facing the camera 2 km away, the previous depth buffer its exact distance along each pixel's ray, and a
 * sideways step of exactly k pixels at that distance: pixel (x, y) was at (x + k, y) in the previous frame */
static void test_reproject_depth_plane_sideways_step_is_exact(void)
{
    enum { PW = 64, PH = 36 };
    static float pdep[PH * PW];
    const float fov = 1.0f, z_plane = 2.0f;
    const int k = 3;
    ccl_camera cam, pcam;
    ccl_cloud_layer L;
    double px_km = 2.0 * (double)z_plane * tan(0.5 * (double)fov) * ((double)PW / (double)PH) / (double)PW;
    float step = (float)((double)k * px_km), u, v, t;
    int x, y, n = 0;
    ccl_raymarch_cloud_layer_default(&L);
    ccl_camera_look_at(V(0, 0.3f, 0), V(0, 0.3f, -1), V(0, 1, 0), fov, (float)PW / (float)PH, 0.01f, 1000.0f, &pcam);
    ccl_camera_look_at(V(step, 0.3f, 0), V(step, 0.3f, -1), V(0, 1, 0), fov, (float)PW / (float)PH, 0.01f, 1000.0f,
                       &cam);
    for (y = 0; y < PH; ++y)
        for (x = 0; x < PW; ++x) {
            ccl_vec3 d = ccl_camera_ray(pcam.inv_view_proj_rot, x, y, PW, PH);
            pdep[y * PW + x] = (float)((double)z_plane / -(double)d.z);
        }
    for (y = 0; y < PH; ++y)
        for (x = 0; x + k < PW; ++x) {
            CCL_CHECK(ccl_reproj_uv_depth(cam.inv_view_proj_rot, cam.eye, pcam.view_proj, pcam.eye, pdep, L.centre,
                                          L.r_inner, CCL_REPROJ_DEPTH_ITERATIONS, x, y, PW, PH, &u, &v, &t) == 1);
            /* float32 round-off of the camera constants and the projection: ~1e-4 px */
            CCL_CHECK_CLOSE((double)u * PW - 0.5, x + k, 1e-3);
            CCL_CHECK_CLOSE((double)v * PH - 0.5, y, 1e-3);
            /* the thesis's point (the layer base, 100+ km along these rays) is off by nearly k pixels */
            CCL_CHECK(ccl_reproj_uv_depth(cam.inv_view_proj_rot, cam.eye, pcam.view_proj, pcam.eye, pdep, L.centre,
                                          L.r_inner, 0, x, y, PW, PH, &u, &v, &t) == 1);
            if (fabs((double)u * PW - 0.5 - (x + k)) > 0.9 * k) ++n;
        }
    CCL_CHECK(n > PH * (PW - k) / 2);
}

static void test_reproject_depth_rejects_bad_input(void)
{
    static float cur[H * W * C], prev[H * W * C], red[4 * 6 * C], out[H * W * C], dep[H * W], pdep[H * W],
        od[H * W];
    ccl_camera cam;
    ccl_vec3 c = V(0, -6371, 0);
    ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), 1.0f, 1.0f, 0.01f, 100.0f, &cam);
    out[0] = 42.0f;
    od[0] = 43.0f;
    CCL_CHECK(ccl_reproj_frame_depth(cur, dep, prev, pdep, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye,
                                     cam.view_proj, cam.eye, c, 6372.5f, 1, 2, 2, 1, out, od) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame_depth(cur, dep, prev, pdep, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye,
                                     cam.view_proj, cam.eye, c, 6372.5f, 1, 1, CCL_REPROJ_MAX_DEPTH_ITERATIONS + 1, 1,
                                     out, od) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame_depth(cur, dep, prev, pdep, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye,
                                     cam.view_proj, cam.eye, c, 6372.5f, 1, 1, -1, 1, out, od) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame_depth(cur, NULL, prev, pdep, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye,
                                     cam.view_proj, cam.eye, c, 6372.5f, 1, 1, 2, 1, out, od) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame_depth(cur, dep, prev, pdep, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye,
                                     cam.view_proj, cam.eye, c, 6372.5f, 1, 1, 2, 1, out, pdep) == CCL_EINVAL);
    CCL_CHECK(ccl_reproj_frame_depth(cur, dep, prev, pdep, red, W, H, C, 0, cam.inv_view_proj_rot, cam.eye,
                                     cam.view_proj, cam.eye, c, 6372.5f, 1, 1, 2, 1, od, od) == CCL_EINVAL);
    CCL_CHECK(out[0] == 42.0f && od[0] == 43.0f);
}

int main(void)
{
    CCL_RUN(test_reprojection_pixel_order_and_wrap);
    CCL_RUN(test_reprojection_coverage_exactly_once);
    CCL_RUN(test_reduced_coord);
    CCL_RUN(test_reproject_static_camera_exact);
    CCL_RUN(test_reproject_fallback_and_history);
    CCL_RUN(test_reproject_rejects_bad_input);
    CCL_RUN(test_reprojection_uv_static_is_pixel_centre);
    CCL_RUN(test_reproject_depth_thesis_settings_equal_frame);
    CCL_RUN(test_reproject_depth_plane_sideways_step_is_exact);
    CCL_RUN(test_reproject_depth_rejects_bad_input);
    return ccl_test_report();
}
