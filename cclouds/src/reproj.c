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

/* nearest hit of the ray (eye, d) on the inner sphere in front of the camera (the far root from inside); NaN or <= 0:
 * none */
static float inner_sphere_t(ccl_vec3 eye, ccl_vec3 d, ccl_vec3 centre, float r_inner)
{
    float t0, t1;
    ccl_raymarch_ray_sphere(eye, d, centre, r_inner, &t0, &t1);
    return (t0 > 0.0f) ? t0 : t1;
}

/* uv of the point eye + d t in the camera m (clip = m (P, 1)); 0 and NaN uv when clip w <= 0 (or NaN) */
static int project(const float *m, ccl_vec3 eye, ccl_vec3 d, float t, float *out_u, float *out_v)
{
    float px = eye.x + d.x * t, py = eye.y + d.y * t, pz = eye.z + d.z * t;
    float cx = m[0] * px + m[4] * py + m[8] * pz + m[12];
    float cy = m[1] * px + m[5] * py + m[9] * pz + m[13];
    float cw = m[3] * px + m[7] * py + m[11] * pz + m[15];
    if (!(cw > 0.0f)) {
        *out_u = NAN;
        *out_v = NAN;
        return 0;
    }
    *out_u = (cx / cw) * 0.5f + 0.5f;
    *out_v = 0.5f - (cy / cw) * 0.5f;
    return 1;
}

static int inside_unit(float u, float v)
{
    return u >= 0.0f && u <= 1.0f && v >= 0.0f && v <= 1.0f;
}

int ccl_reproj_uv(const float inv_view_proj_rot[16], ccl_vec3 eye, const float prev_view_proj[16],
                        ccl_vec3 centre, float r_inner, int x, int y, int width, int height, float *out_u, float *out_v)
{
    ccl_vec3 d = ccl_camera_ray(inv_view_proj_rot, x, y, width, height);
    float t = inner_sphere_t(eye, d, centre, r_inner);
    if (!(t > 0.0f)) {
        *out_u = NAN;
        *out_v = NAN;
        return 0;
    }
    return project(prev_view_proj, eye, d, t, out_u, out_v) && inside_unit(*out_u, *out_v);
}

/* --- depth-aware reprojection (not in the thesis; see reproj.h) ------------------------------------------------- */

float ccl_reproj_surface_depth(float march_depth, ccl_vec3 eye, ccl_vec3 d, ccl_vec3 centre, float r_earth)
{
    float e0, e1;
    if (isnan(march_depth) || isnan(eye.x + eye.y + eye.z) || isnan(d.x + d.y + d.z)) return NAN;
    if (march_depth > 0.0f) return march_depth;
    ccl_raymarch_ray_sphere(eye, d, centre, r_earth, &e0, &e1);
    if (e0 > 0.0f) return e0; /* the ground ahead */
    return CCL_REPROJ_SKY_DEPTH_KM;
}

/* nearest pixel index along one axis of the continuous position p (pixel i centred at i), clamped to [0, n - 1]
 * in float before the conversion (p may be huge or NaN: NaN -> 0) */
static int nearest_index(float p, int n)
{
    float f = floorf(p + 0.5f);
    if (!(f >= 0.0f)) f = 0.0f;
    if (f > (float)(n - 1)) f = (float)(n - 1);
    return (int)f;
}

int ccl_reproj_uv_depth(const float inv_view_proj_rot[16], ccl_vec3 eye, const float prev_view_proj[16],
                        ccl_vec3 prev_eye, const float *prev_depth, ccl_vec3 centre, float r_inner, int iterations,
                        int x, int y, int width, int height, float *out_u, float *out_v, float *out_t)
{
    const float *m = prev_view_proj;
    ccl_vec3 d = ccl_camera_ray(inv_view_proj_rot, x, y, width, height);
    float t = inner_sphere_t(eye, d, centre, r_inner);
    /* the iterate in the previous camera's clip space, linear in t: clip(eye + d t) = a + t b with a = M (eye, 1),
     * b = M (d, 0); the camera's step e = eye - prev_eye */
    float ax = m[0] * eye.x + m[4] * eye.y + m[8] * eye.z + m[12];
    float ay = m[1] * eye.x + m[5] * eye.y + m[9] * eye.z + m[13];
    float aw = m[3] * eye.x + m[7] * eye.y + m[11] * eye.z + m[15];
    float bx = m[0] * d.x + m[4] * d.y + m[8] * d.z;
    float by = m[1] * d.x + m[5] * d.y + m[9] * d.z;
    float bw = m[3] * d.x + m[7] * d.y + m[11] * d.z;
    float ex = eye.x - prev_eye.x, ey = eye.y - prev_eye.y, ez = eye.z - prev_eye.z;
    int k;
    CCL_REQUIRE(iterations >= 0 && iterations <= CCL_REPROJ_MAX_DEPTH_ITERATIONS && prev_depth);
    if (!(t > 0.0f)) {
        *out_u = NAN;
        *out_v = NAN;
        *out_t = NAN;
        return 0;
    }
    for (k = 0; k < iterations; ++k) {
        float cw = aw + t * bw, u, v, dp, qx, qy, qz, lq, s, yx, yy, yz, tn;
        if (!(cw > 0.0f)) break; /* behind the previous camera */
        u = ((ax + t * bx) / cw) * 0.5f + 0.5f;
        v = 0.5f - ((ay + t * by) / cw) * 0.5f;
        /* the depth the previous frame stored at the nearest pixel of uv (clamped to the image) */
        dp = prev_depth[(size_t)nearest_index(v * (float)height - 0.5f, height) * (size_t)width +
                        (size_t)nearest_index(u * (float)width - 0.5f, width)];
        if (!(dp > 0.0f)) break; /* unknown (or NaN) */
        /* q = X - prev_eye = d t + e; Y - eye = prev_eye + dp q / |q| - eye = q dp / |q| - e; t = |Y - eye| */
        qx = d.x * t + ex;
        qy = d.y * t + ey;
        qz = d.z * t + ez;
        lq = sqrtf(qx * qx + qy * qy + qz * qz);
        if (!(lq > 0.0f)) break;
        s = dp / lq;
        yx = qx * s - ex;
        yy = qy * s - ey;
        yz = qz * s - ez;
        tn = sqrtf(yx * yx + yy * yy + yz * yz);
        if (!(tn > 0.0f) || isinf(tn)) break;
        t = tn;
    }
    *out_t = t;
    /* the final point as ccl_reproj_uv projects it (iterations = 0: its uv bit for bit) */
    return project(prev_view_proj, eye, d, t, out_u, out_v) && inside_unit(*out_u, *out_v);
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

/* Catmull-Rom weights of the 4 taps at offsets -1, 0, 1, 2 for the fraction t in [0, 1) */
static void catmull_rom_weights(float t, float w[4])
{
    float t2 = t * t, t3 = t2 * t;
    w[0] = -0.5f * t3 + t2 - 0.5f * t;
    w[1] = 1.5f * t3 - 2.5f * t2 + 1.0f;
    w[2] = -1.5f * t3 + 2.0f * t2 + 0.5f * t;
    w[3] = 0.5f * t3 - 0.5f * t2;
}

/* Catmull-Rom lookup of every channel at (xs, ys) (clamp-to-edge as bilinear), each clamped to the range of the 2 x 2
 * pixels the bilinear lookup reads (the filter sharpens, it never overshoots), added to acc[0 .. channels - 1] */
static void catmull_rom_add(const float *img, int w, int xmax, int ymax, int channels, float xs, float ys, float *acc)
{
    float x0f = floorf(xs), y0f = floorf(ys), wx[4], wy[4];
    int x0 = (int)x0f, y0 = (int)y0f, xi[4], yi[4], i, j, ch;
    catmull_rom_weights(xs - x0f, wx);
    catmull_rom_weights(ys - y0f, wy);
    for (i = 0; i < 4; ++i) {
        xi[i] = clampi(x0 - 1 + i, 0, xmax);
        yi[i] = clampi(y0 - 1 + i, 0, ymax);
    }
    for (ch = 0; ch < channels; ++ch) {
        float sum = 0.0f, lo = INFINITY, hi = -INFINITY;
        for (j = 0; j < 4; ++j) {
            float row = 0.0f;
            for (i = 0; i < 4; ++i) {
                float val = img[at(xi[i], yi[j], w, channels, ch)];
                row = row + wx[i] * val;
                if ((i == 1 || i == 2) && (j == 1 || j == 2)) {
                    if (val < lo) lo = val;
                    if (val > hi) hi = val;
                }
            }
            sum = sum + wy[j] * row;
        }
        if (sum < lo) sum = lo;
        if (sum > hi) sum = hi;
        acc[ch] = acc[ch] + sum;
    }
}

static float snap(float p)
{
    float n = floorf(p + 0.5f);
    return (fabsf(p - n) <= SNAP_PX) ? n : p;
}

/* the colour of a pixel not rendered this frame: the previous frame at (u, v) when valid (n x n bilinear samples),
 * else the reduced buffer (vc-A26 step 3), else (no rendered pixel in that direction) previous / current as is */
static void fill_pixel(const float *current, const float *previous, const float *reduced, int width, int height,
                       int channels, int frame, int neighbourhood, int filter, int history, int valid, float u, float v,
                       int x, int y, float *out)
{
    size_t base = at(x, y, width, channels, 0);
    int ch, i, j, half = neighbourhood / 2;
    if (valid) {
        float xs = snap(u * (float)width - 0.5f), ys = snap(v * (float)height - 0.5f);
        float inv_n = 1.0f / (float)(neighbourhood * neighbourhood);
        if (filter == CCL_REPROJ_FILTER_CATMULL_ROM) {
            /* the weights and indices once per sample, every channel summed in out */
            for (ch = 0; ch < channels; ++ch) out[base + (size_t)ch] = 0.0f;
            for (j = -half; j <= half; ++j)
                for (i = -half; i <= half; ++i)
                    catmull_rom_add(previous, width, width - 1, height - 1, channels, xs + (float)i, ys + (float)j,
                                    out + base);
            for (ch = 0; ch < channels; ++ch) out[base + (size_t)ch] = out[base + (size_t)ch] * inv_n;
        } else {
            for (ch = 0; ch < channels; ++ch) {
                float sum = 0.0f;
                for (j = -half; j <= half; ++j)
                    for (i = -half; i <= half; ++i)
                        sum = sum + bilinear(previous, width, width - 1, height - 1, channels, ch, xs + (float)i,
                                             ys + (float)j);
                out[base + (size_t)ch] = sum * inv_n;
            }
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

static void reproject_pixel(const float *current, const float *previous, const float *reduced, int width, int height,
                            int channels, int frame, const float inv_view_proj_rot[16], ccl_vec3 eye,
                            const float prev_view_proj[16], ccl_vec3 centre, float r_inner, int neighbourhood,
                            int history, int x, int y, float *out)
{
    size_t base = at(x, y, width, channels, 0);
    int ch, valid = 0;
    float u = 0.0f, v = 0.0f;
    if (ccl_reproj_updated(x, y, frame)) {
        for (ch = 0; ch < channels; ++ch) out[base + (size_t)ch] = current[base + (size_t)ch];
        return;
    }
    if (history)
        valid = ccl_reproj_uv(inv_view_proj_rot, eye, prev_view_proj, centre, r_inner, x, y, width, height, &u,
                                    &v);
    fill_pixel(current, previous, reduced, width, height, channels, frame, neighbourhood, CCL_REPROJ_FILTER_BILINEAR,
               history, valid, u, v, x, y, out);
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

/* the depth of a fallback pixel: the bilinear interpolation of this frame's rendered depths (pixel (4i + a, 4j + b)
 * of current_depth holds reduced texel (i, j)) at the reduced-buffer position, as the colour; no rendered pixel in
 * that direction: previous_depth (history) or current_depth at the same pixel */
static float fallback_depth(const float *current_depth, const float *previous_depth, int width, int height, int frame,
                            int history, int x, int y)
{
    float rx, ry, x0f, y0f, fx, fy, p00, p10, p01, p11;
    int f = mod16(frame), a = f / 4, b = f % 4, x0, x1, y0, y1, xmax, ymax;
    ccl_reproj_reduced_coord(x, y, frame, width, height, &rx, &ry);
    if (isnan(rx) || isnan(ry)) return (history ? previous_depth : current_depth)[at(x, y, width, 1, 0)];
    xmax = (width - 1 - a) / CCL_REPROJ_BLOCK;
    ymax = (height - 1 - b) / CCL_REPROJ_BLOCK;
    x0f = floorf(rx);
    y0f = floorf(ry);
    fx = rx - x0f;
    fy = ry - y0f;
    x0 = clampi((int)x0f, 0, xmax);
    x1 = clampi((int)x0f + 1, 0, xmax);
    y0 = clampi((int)y0f, 0, ymax);
    y1 = clampi((int)y0f + 1, 0, ymax);
    p00 = current_depth[at(CCL_REPROJ_BLOCK * x0 + a, CCL_REPROJ_BLOCK * y0 + b, width, 1, 0)];
    p10 = current_depth[at(CCL_REPROJ_BLOCK * x1 + a, CCL_REPROJ_BLOCK * y0 + b, width, 1, 0)];
    p01 = current_depth[at(CCL_REPROJ_BLOCK * x0 + a, CCL_REPROJ_BLOCK * y1 + b, width, 1, 0)];
    p11 = current_depth[at(CCL_REPROJ_BLOCK * x1 + a, CCL_REPROJ_BLOCK * y1 + b, width, 1, 0)];
    return (p00 * (1.0f - fx) + p10 * fx) * (1.0f - fy) + (p01 * (1.0f - fx) + p11 * fx) * fy;
}

ccl_status ccl_reproj_frame_depth(const float *current, const float *current_depth, const float *previous,
                                  const float *previous_depth, const float *reduced, int width, int height,
                                  int channels, int frame, const float inv_view_proj_rot[16], ccl_vec3 eye,
                                  const float prev_view_proj[16], ccl_vec3 prev_eye, ccl_vec3 centre, float r_inner,
                                  int neighbourhood, int filter, int iterations, int history, float *out,
                                  float *out_depth)
{
    int x, y;
    if (!current || !current_depth || !previous || !previous_depth || !reduced || !inv_view_proj_rot ||
        !prev_view_proj || !out || !out_depth)
        return CCL_EINVAL;
    /* written buffers: out may be current, out_depth may be current_depth (a rendered pixel keeps its value and the
     * fallback reads only rendered pixels); nothing else written may be read */
    if (out == previous || out == previous_depth || out == current_depth || out == reduced || out == out_depth ||
        out_depth == previous || out_depth == previous_depth || out_depth == current || out_depth == reduced)
        return CCL_EINVAL;
    if (width < 1 || height < 1 || channels < 1 || neighbourhood < 1 || neighbourhood % 2 == 0 ||
        neighbourhood > CCL_REPROJ_MAX_NEIGHBOURHOOD || !(r_inner > 0.0f) || iterations < 0 ||
        iterations > CCL_REPROJ_MAX_DEPTH_ITERATIONS ||
        (filter != CCL_REPROJ_FILTER_BILINEAR && filter != CCL_REPROJ_FILTER_CATMULL_ROM))
        return CCL_EINVAL;
    for (y = 0; y < height; ++y)
        for (x = 0; x < width; ++x) {
            size_t k = at(x, y, width, 1, 0);
            int valid = 0;
            float u = 0.0f, v = 0.0f, t = 0.0f;
            if (ccl_reproj_updated(x, y, frame)) {
                size_t base = at(x, y, width, channels, 0);
                int ch;
                for (ch = 0; ch < channels; ++ch) out[base + (size_t)ch] = current[base + (size_t)ch];
                out_depth[k] = current_depth[k];
                continue;
            }
            if (history)
                valid = ccl_reproj_uv_depth(inv_view_proj_rot, eye, prev_view_proj, prev_eye, previous_depth, centre,
                                            r_inner, iterations, x, y, width, height, &u, &v, &t);
            fill_pixel(current, previous, reduced, width, height, channels, frame, neighbourhood, filter, history,
                       valid, u, v, x, y, out);
            /* a reprojected point at an infinite distance (only through a degenerate previous projection) keeps the
             * fallback's depth: the depth buffer stays finite */
            out_depth[k] = (valid && !isinf(t)) ? t
                                                : fallback_depth(current_depth, previous_depth, width, height, frame,
                                                                 history, x, y);
        }
    return CCL_OK;
}
