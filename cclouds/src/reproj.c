/* Temporal reprojection (vc §4.2.1, §4.4). See cclouds/reproj.h for the conventions and choices.
 * Every float32 expression is mirrored operation by operation in pywarp/kernels/reproj.py. */
#include "cclouds/reproj.h"
#include "internal.h"

/* Positions within 1/256 px of a pixel centre are snapped to it (see reproj.h). */
#define SNAP_PX 0.00390625f

static int mod16(int frame)
{
    return ((frame % CCL_REPROJ_CYCLE) + CCL_REPROJ_CYCLE) % CCL_REPROJ_CYCLE;
}

/* --- vc-4.1 ------------------------------------------------------------------------------------------------------ */

void ccl_reproj_pixel(int id_x, int id_y, int frame, int *out_x, int *out_y)
{
    int f = mod16(frame);
    CCL_REQUIRE(id_x >= 0 && id_y >= 0 && id_x <= CCL_REPROJ_MAX_ID && id_y <= CCL_REPROJ_MAX_ID);
    /* in unsigned arithmetic: outside the domain the result wraps instead of overflowing int (undefined) */
    *out_x = (int)(((unsigned)id_x * (unsigned)CCL_REPROJ_BLOCK + (unsigned)(f / 4)) & 0x7FFFFFFFu);
    *out_y = (int)(((unsigned)id_y * (unsigned)CCL_REPROJ_BLOCK + (unsigned)(f % 4)) & 0x7FFFFFFFu);
}

ccl_status ccl_reproj_grid(int width, int height, int *out_grid_w, int *out_grid_h)
{
    if (width < 1 || height < 1 || !out_grid_w || !out_grid_h) return CCL_EINVAL;
    *out_grid_w = (width - 1) / CCL_REPROJ_BLOCK + 1;
    *out_grid_h = (height - 1) / CCL_REPROJ_BLOCK + 1;
    return CCL_OK;
}

int ccl_reproj_updated(int x, int y, int frame)
{
    int f = mod16(frame);
    CCL_REQUIRE(x >= 0 && y >= 0);
    return (x % CCL_REPROJ_BLOCK == f / 4) && (y % CCL_REPROJ_BLOCK == f % 4);
}

/* --- vc-A22: reduced buffer mapping ------------------------------------------------------------------------------ */

/* reduced coordinate along one axis: (p - off) / 4 clamped to [0, floor((size - 1 - off) / 4)]; NaN if empty */
static float reduced_axis(int p, int off, int size)
{
    int last = size - 1 - off;
    float r, hi;
    if (last < 0) return NAN;
    hi = (float)(last / CCL_REPROJ_BLOCK);
    r = (float)(p - off) * 0.25f;
    if (r < 0.0f) r = 0.0f;
    if (r > hi) r = hi;
    return r;
}

void ccl_reproj_reduced_coord(int x, int y, int frame, int width, int height, float *out_rx, float *out_ry)
{
    int f = mod16(frame);
    *out_rx = reduced_axis(x, f / 4, width);
    *out_ry = reduced_axis(y, f % 4, height);
}

/* --- vc-A26: reprojection ---------------------------------------------------------------------------------------- */

int ccl_reproj_uv(const float inv_view_proj_rot[16], ccl_vec3 eye, const float prev_view_proj[16],
                        ccl_vec3 centre, float r_inner, int x, int y, int width, int height, float *out_u, float *out_v)
{
    const float *m = prev_view_proj;
    ccl_vec3 d = ccl_camera_ray(inv_view_proj_rot, x, y, width, height);
    float t0, t1, t, px, py, pz, cx, cy, cw, u, v;
    ccl_raymarch_ray_sphere(eye, d, centre, r_inner, &t0, &t1);
    t = (t0 > 0.0f) ? t0 : t1;
    if (!(t > 0.0f)) {
        *out_u = NAN;
        *out_v = NAN;
        return 0;
    }
    px = eye.x + d.x * t;
    py = eye.y + d.y * t;
    pz = eye.z + d.z * t;
    cx = m[0] * px + m[4] * py + m[8] * pz + m[12];
    cy = m[1] * px + m[5] * py + m[9] * pz + m[13];
    cw = m[3] * px + m[7] * py + m[11] * pz + m[15];
    if (!(cw > 0.0f)) {
        *out_u = NAN;
        *out_v = NAN;
        return 0;
    }
    u = (cx / cw) * 0.5f + 0.5f;
    v = 0.5f - (cy / cw) * 0.5f;
    *out_u = u;
    *out_v = v;
    return u >= 0.0f && u <= 1.0f && v >= 0.0f && v <= 1.0f;
}

static int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* bilinear lookup of channel ch of an image with row length w (pixels) at continuous position (xs, ys) (pixel (i, j)
 * centred at (i, j)), clamp-to-edge at column xmax and row ymax (the last texels that may be read) */
/* element (x, y, ch) of an image with row length w: every index is >= 0 here (clamped or looped from 0) */
static size_t at(int x, int y, int w, int channels, int ch)
{
    return ((size_t)y * (size_t)w + (size_t)x) * (size_t)channels + (size_t)ch;
}

static float bilinear(const float *img, int w, int xmax, int ymax, int channels, int ch, float xs, float ys)
{
    float x0f = floorf(xs), y0f = floorf(ys);
    float fx = xs - x0f, fy = ys - y0f;
    int x0 = clampi((int)x0f, 0, xmax), x1 = clampi((int)x0f + 1, 0, xmax);
    int y0 = clampi((int)y0f, 0, ymax), y1 = clampi((int)y0f + 1, 0, ymax);
    float p00 = img[at(x0, y0, w, channels, ch)];
    float p10 = img[at(x1, y0, w, channels, ch)];
    float p01 = img[at(x0, y1, w, channels, ch)];
    float p11 = img[at(x1, y1, w, channels, ch)];
    return (p00 * (1.0f - fx) + p10 * fx) * (1.0f - fy) + (p01 * (1.0f - fx) + p11 * fx) * fy;
}

static float snap(float p)
{
    float n = floorf(p + 0.5f);
    return (fabsf(p - n) <= SNAP_PX) ? n : p;
}

static void reproject_pixel(const float *current, const float *previous, const float *reduced, int width, int height,
                            int channels, int frame, const float inv_view_proj_rot[16], ccl_vec3 eye,
                            const float prev_view_proj[16], ccl_vec3 centre, float r_inner, int neighbourhood,
                            int history, int x, int y, float *out)
{
    size_t base = at(x, y, width, channels, 0);
    int ch, i, j, valid = 0, half = neighbourhood / 2;
    float u = 0.0f, v = 0.0f;
    if (ccl_reproj_updated(x, y, frame)) {
        for (ch = 0; ch < channels; ++ch) out[base + (size_t)ch] = current[base + (size_t)ch];
        return;
    }
    if (history)
        valid = ccl_reproj_uv(inv_view_proj_rot, eye, prev_view_proj, centre, r_inner, x, y, width, height, &u,
                                    &v);
    if (valid) {
        float xs = snap(u * (float)width - 0.5f), ys = snap(v * (float)height - 0.5f);
        float inv_n = 1.0f / (float)(neighbourhood * neighbourhood);
        for (ch = 0; ch < channels; ++ch) {
            float sum = 0.0f;
            for (j = -half; j <= half; ++j)
                for (i = -half; i <= half; ++i)
                    sum = sum + bilinear(previous, width, width - 1, height - 1, channels, ch, xs + (float)i,
                                         ys + (float)j);
            out[base + (size_t)ch] = sum * inv_n;
        }
    } else {
        float rx, ry;
        ccl_reproj_reduced_coord(x, y, frame, width, height, &rx, &ry);
        if (isnan(rx) || isnan(ry)) {
            const float *keep = history ? previous : current;
            for (ch = 0; ch < channels; ++ch) out[base + (size_t)ch] = keep[base + (size_t)ch];
        } else {
            /* row length of the reduced buffer ceil(width / 4); read only texels written this frame */
            int rw = (width - 1) / CCL_REPROJ_BLOCK + 1;
            int f = mod16(frame);
            int xmax = (width - 1 - f / 4) / CCL_REPROJ_BLOCK, ymax = (height - 1 - f % 4) / CCL_REPROJ_BLOCK;
            for (ch = 0; ch < channels; ++ch)
                out[base + (size_t)ch] = bilinear(reduced, rw, xmax, ymax, channels, ch, rx, ry);
        }
    }
}

ccl_status ccl_reproj_frame(const float *current, const float *previous, const float *reduced, int width,
                               int height, int channels, int frame, const float inv_view_proj_rot[16], ccl_vec3 eye,
                               const float prev_view_proj[16], ccl_vec3 centre, float r_inner, int neighbourhood,
                               int history, float *out)
{
    int x, y;
    if (!current || !previous || !reduced || !inv_view_proj_rot || !prev_view_proj || !out || out == previous)
        return CCL_EINVAL;
    if (width < 1 || height < 1 || channels < 1 || neighbourhood < 1 || neighbourhood % 2 == 0 ||
        neighbourhood > CCL_REPROJ_MAX_NEIGHBOURHOOD || !(r_inner > 0.0f))
        return CCL_EINVAL;
    for (y = 0; y < height; ++y)
        for (x = 0; x < width; ++x)
            reproject_pixel(current, previous, reduced, width, height, channels, frame, inv_view_proj_rot, eye,
                            prev_view_proj, centre, r_inner, neighbourhood, history, x, y, out);
    return CCL_OK;
}
