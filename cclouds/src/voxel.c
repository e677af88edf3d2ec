/* The 3-D cloud array of the oc text (§5.2). See cclouds/voxel.h for the build and the readings chosen.
 * Mirrored operation by operation in pywarp/kernels/voxel.py. */
#include "cclouds/voxel.h"
#include "cclouds/hash.h"
#include "cclouds/valuenoise.h"
#include "internal.h"

#include <stdlib.h>

#define HALF_PI_F 1.57079637f

ccl_voxel_settings ccl_voxel_settings_default(void)
{
    ccl_voxel_settings s;
    s.size = 64;
    s.levels = 4;
    s.seed = 0u;
    s.persistence = 0.5f;
    s.interpolation = CCL_VALUENOISE_LINEAR;
    s.smoothing = CCL_VALUENOISE_SMOOTH_ELIAS;
    s.variant = CCL_VARIANT_CORRECTED;
    s.border = CCL_VOXEL_BORDER_ZERO;
    s.sin_radius = 0.125f;
    s.cover = 128.0f;
    s.sharpness = 0.96f;
    s.envelope = 0.0f;
    s.envelope_base = 0.35f;
    return s;
}

static int finite_f(float v)
{
    return v == v && v - v == 0.0f;
}

ccl_status ccl_voxel_settings_check(const ccl_voxel_settings *s, const char **out_field)
{
    const char *bad = NULL;
    if (s == NULL) {
        bad = "s";
    } else if (s->levels < 1 || s->levels > CCL_VOXEL_MAX_LEVELS) {
        /* levels first: size is checked against it */
        bad = "levels";
    } else if (s->size < (CCL_VOXEL_MIN_BASE << (s->levels - 1)) || s->size > CCL_VOXEL_MAX_SIZE
               || (s->size & ((1 << (s->levels - 1)) - 1)) != 0) {
        bad = "size";
    } else if (!finite_f(s->persistence) || !(s->persistence > 0.0f && s->persistence <= 1.0f)) {
        bad = "persistence";
    } else if (s->interpolation < CCL_VALUENOISE_LINEAR || s->interpolation > CCL_VALUENOISE_CUBIC) {
        bad = "interpolation";
    } else if (s->smoothing < CCL_VALUENOISE_SMOOTH_ELIAS || s->smoothing > CCL_VALUENOISE_SMOOTH_NONE) {
        bad = "smoothing";
    } else if (s->variant != CCL_VARIANT_CORRECTED && s->variant != CCL_VARIANT_THESIS) {
        bad = "variant";
    } else if (s->border < CCL_VOXEL_BORDER_NONE || s->border > CCL_VOXEL_BORDER_ZERO) {
        bad = "border";
    } else if (!finite_f(s->sin_radius) || !(s->sin_radius > 0.0f && s->sin_radius <= 0.5f)) {
        bad = "sin_radius";
    } else if (!finite_f(s->cover) || !(s->cover >= 0.0f && s->cover <= 255.0f)) {
        bad = "cover";
    } else if (!finite_f(s->sharpness) || !(s->sharpness > 0.0f && s->sharpness < 1.0f)) {
        bad = "sharpness";
    } else if (!finite_f(s->envelope) || !(s->envelope >= 0.0f && s->envelope <= 1.0f)) {
        bad = "envelope";
    } else if (!finite_f(s->envelope_base) || !(s->envelope_base > 0.0f && s->envelope_base <= 1.0f)) {
        bad = "envelope_base";
    }
    if (out_field != NULL) *out_field = bad;
    return bad == NULL ? CCL_OK : CCL_EINVAL;
}

float ccl_voxel_filter(float n, float cover, float sharpness)
{
    float c = n * 255.0f - cover;
    CCL_REQUIRE(!(sharpness <= 0.0f || sharpness >= 1.0f));
    if (c < 0.0f) c = 0.0f;
    return 255.0f - powf(sharpness, c) * 255.0f;
}

float ccl_voxel_sin_window(int32_t d, float radius)
{
    float fd = (float)d;
    CCL_REQUIRE(d >= 0 && radius > 0.0f);
    if (fd >= radius) return 1.0f;
    return sinf(HALF_PI_F * (fd / radius));
}

float ccl_voxel_envelope(int32_t x, int32_t y, int32_t z, int32_t n, float base)
{
    float m, dx, dy, dz, c, u;
    CCL_REQUIRE(n >= 2 && base > 0.0f);
    m = (float)(n - 1);
    dx = (2.0f * (float)x - m) / m;
    dz = (2.0f * (float)z - m) / m;
    c = base / (1.0f + base);
    u = (float)y / m;
    dy = u >= c ? (u - c) / (1.0f - c) : (c - u) / c;
    return dx * dx + dy * dy + dz * dz;
}

/* Distance of index i from the nearer end of an axis of n cells. */
static int32_t face_distance(int32_t i, int32_t n)
{
    return i < n - 1 - i ? i : n - 1 - i;
}

/* ---- up-sampling (mirrored in voxel.py) ------------------------------------------------------------------------- */

/* Fine index i of an axis of nf cells -> lower coarse node i0 and weight t, corners aligned. */
static void axis_map(int32_t i, int32_t nf, int32_t nc, int32_t *i0, float *t)
{
    float pos = (float)(i * (nc - 1)) / (float)(nf - 1);
    int32_t k = (int32_t)pos;
    if (k > nc - 2) k = nc - 2;
    *i0 = k;
    *t = pos - (float)k;
}

static int32_t clampi(int32_t i, int32_t n)
{
    return i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
}

static float blend(int kind, float v0, float v1, float v2, float v3, float t)
{
    if (kind == CCL_VALUENOISE_CUBIC) return ccl_valuenoise_cubic(v0, v1, v2, v3, t);
    if (kind == CCL_VALUENOISE_COSINE) return ccl_valuenoise_cosine(v1, v2, t);
    return ccl_valuenoise_linear(v1, v2, t);
}

static float line_x(const float *src, int32_t nc, int32_t zi, int32_t yi, int32_t x0, float tx, int kind)
{
    const float *row = src + ((size_t)zi * (size_t)nc + (size_t)yi) * (size_t)nc;
    if (kind == CCL_VALUENOISE_CUBIC)
        return ccl_valuenoise_cubic(row[clampi(x0 - 1, nc)], row[x0], row[x0 + 1], row[clampi(x0 + 2, nc)], tx);
    return blend(kind, 0.0f, row[x0], row[x0 + 1], 0.0f, tx);
}

static float plane_xy(const float *src, int32_t nc, int32_t zi, int32_t y0, float ty, int32_t x0, float tx, int kind)
{
    float v0 = 0.0f, v3 = 0.0f;
    if (kind == CCL_VALUENOISE_CUBIC) {
        v0 = line_x(src, nc, zi, clampi(y0 - 1, nc), x0, tx, kind);
        v3 = line_x(src, nc, zi, clampi(y0 + 2, nc), x0, tx, kind);
    }
    return blend(kind, v0, line_x(src, nc, zi, y0, x0, tx, kind), line_x(src, nc, zi, y0 + 1, x0, tx, kind), v3, ty);
}

static float upsample(const float *src, int32_t nc, int32_t nf, int32_t x, int32_t y, int32_t z, int kind)
{
    int32_t x0, y0, z0;
    float tx, ty, tz, v0 = 0.0f, v3 = 0.0f;
    axis_map(x, nf, nc, &x0, &tx);
    axis_map(y, nf, nc, &y0, &ty);
    axis_map(z, nf, nc, &z0, &tz);
    if (kind == CCL_VALUENOISE_CUBIC) {
        v0 = plane_xy(src, nc, clampi(z0 - 1, nc), y0, ty, x0, tx, kind);
        v3 = plane_xy(src, nc, clampi(z0 + 2, nc), y0, ty, x0, tx, kind);
    }
    return blend(kind, v0, plane_xy(src, nc, z0, y0, ty, x0, tx, kind), plane_xy(src, nc, z0 + 1, y0, ty, x0, tx, kind),
                 v3, tz);
}

/* One level: cur[v] = U(prev)(v) + amp * N(v) (prev == NULL at level 0: amp * N(v)); with the zero border the
 * outermost layer stays 0. */
static void build_level(const ccl_voxel_settings *s, const float *prev, int32_t nc, float *cur, int32_t n,
                        float amp, uint32_t seed_l)
{
    int32_t x, y, z;
    int zero = s->border == CCL_VOXEL_BORDER_ZERO;
    for (z = 0; z < n; ++z)
        for (y = 0; y < n; ++y)
            for (x = 0; x < n; ++x) {
                size_t k = ((size_t)z * (size_t)n + (size_t)y) * (size_t)n + (size_t)x;
                float noise, v;
                if (zero && (x == 0 || y == 0 || z == 0 || x == n - 1 || y == n - 1 || z == n - 1)) {
                    cur[k] = 0.0f;
                    continue;
                }
                noise = ccl_valuenoise_smooth(x, y, z, seed_l, 3, s->smoothing, CCL_VALUENOISE_UNIT);
                v = prev == NULL ? 0.0f : upsample(prev, nc, n, x, y, z, s->interpolation);
                cur[k] = v + amp * noise;
            }
}

ccl_status ccl_voxel_noise(const ccl_voxel_settings *s, float *out, size_t out_len)
{
    int32_t n, base, l, x, y, z, nc = 0;
    float *prev = NULL, *cur = NULL, norm = 0.0f, radius;
    uint32_t seed0;
    if (ccl_voxel_settings_check(s, NULL) != CCL_OK || out == NULL) return CCL_EINVAL;
    n = s->size;
    if (out_len < (size_t)n * (size_t)n * (size_t)n) return CCL_ERANGE;
    base = n >> (s->levels - 1);
    seed0 = ccl_hash_pcg(s->seed);
    for (l = 0; l < s->levels; ++l) {
        int32_t nl = base << l;
        float amp = ccl_valuenoise_amplitude(l, s->persistence, s->variant);
        /* the last level is built in out itself */
        cur = l == s->levels - 1 ? out : (float *)malloc((size_t)nl * (size_t)nl * (size_t)nl * sizeof(float));
        if (cur == NULL) {
            free(prev);
            return CCL_ENOMEM;
        }
        build_level(s, prev, nc, cur, nl, amp, seed0 + (uint32_t)l);
        norm += amp;
        free(prev);
        prev = l == s->levels - 1 ? NULL : cur;
        nc = nl;
    }
    radius = s->sin_radius * (float)n;
    for (z = 0; z < n; ++z)
        for (y = 0; y < n; ++y)
            for (x = 0; x < n; ++x) {
                size_t k = ((size_t)z * (size_t)n + (size_t)y) * (size_t)n + (size_t)x;
                float v = out[k] / norm;
                if (s->border == CCL_VOXEL_BORDER_SIN)
                    v = v * ccl_voxel_sin_window(face_distance(x, n), radius)
                        * ccl_voxel_sin_window(face_distance(y, n), radius)
                        * ccl_voxel_sin_window(face_distance(z, n), radius);
                if (s->envelope > 0.0f) v = v - s->envelope * ccl_voxel_envelope(x, y, z, n, s->envelope_base);
                out[k] = clamp01(v);
            }
    return CCL_OK;
}

static uint8_t to_u8(float d)
{
    float r = floorf(d + 0.5f);
    return (uint8_t)(!(r >= 0.0f) ? 0.0f : (r > 255.0f ? 255.0f : r)); /* NaN: 0, never a cast of NaN */
}

ccl_status ccl_voxel_cloud(const ccl_voxel_settings *s, uint8_t *out, size_t out_len)
{
    size_t total, k;
    float *noise;
    ccl_status st;
    if (ccl_voxel_settings_check(s, NULL) != CCL_OK || out == NULL) return CCL_EINVAL;
    total = (size_t)s->size * (size_t)s->size * (size_t)s->size;
    if (out_len < total) return CCL_ERANGE;
    noise = (float *)malloc(total * sizeof(float));
    if (noise == NULL) return CCL_ENOMEM;
    st = ccl_voxel_noise(s, noise, total);
    if (st == CCL_OK)
        for (k = 0; k < total; ++k) out[k] = to_u8(ccl_voxel_filter(noise[k], s->cover, s->sharpness));
    free(noise);
    return st;
}

ccl_status ccl_voxel_scale(const uint8_t *src, int32_t nx, int32_t ny, int32_t nz, uint8_t *dst, int32_t mx,
                           int32_t my, int32_t mz)
{
    int32_t x, y, z;
    if (src == NULL || dst == NULL) return CCL_EINVAL;
    if (nx < 2 || ny < 2 || nz < 2 || mx < 2 || my < 2 || mz < 2 || nx > CCL_VOXEL_MAX_SCALE_EDGE
        || ny > CCL_VOXEL_MAX_SCALE_EDGE || nz > CCL_VOXEL_MAX_SCALE_EDGE || mx > CCL_VOXEL_MAX_SCALE_EDGE
        || my > CCL_VOXEL_MAX_SCALE_EDGE || mz > CCL_VOXEL_MAX_SCALE_EDGE)
        return CCL_EINVAL;
    for (z = 0; z < mz; ++z) {
        int32_t z0;
        float tz;
        axis_map(z, mz, nz, &z0, &tz);
        for (y = 0; y < my; ++y) {
            int32_t y0;
            float ty;
            axis_map(y, my, ny, &y0, &ty);
            for (x = 0; x < mx; ++x) {
                int32_t x0, b, c;
                float tx, p[2];
                axis_map(x, mx, nx, &x0, &tx);
                for (c = 0; c < 2; ++c) {
                    float r[2];
                    for (b = 0; b < 2; ++b) {
                        const uint8_t *row = src + ((size_t)(z0 + c) * (size_t)ny + (size_t)(y0 + b)) * (size_t)nx;
                        r[b] = ccl_valuenoise_linear((float)row[x0], (float)row[x0 + 1], tx);
                    }
                    p[c] = ccl_valuenoise_linear(r[0], r[1], ty);
                }
                dst[((size_t)z * (size_t)my + (size_t)y) * (size_t)mx + (size_t)x]
                    = to_u8(ccl_valuenoise_linear(p[0], p[1], tz));
            }
        }
    }
    return CCL_OK;
}
