/* Procedural noise, vc §2.3.2 and §4.3.1. See cclouds/noise.h for the conventions. */
#include "cclouds/noise.h"
#include "cclouds/hash.h"
#include "cclouds/interp.h"
#include "internal.h"

#include <float.h>

/* Ken Perlin's permutation (ImprovedNoise.java, 2002), the published table. */
#define CCL_PERLIN_PERMUTATION \
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, \
    140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, \
    247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32, \
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, \
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, \
    60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, \
    65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169, \
    200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64, \
    52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, \
    207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, \
    119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9, \
    129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104, \
    218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241, \
    81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, \
    184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, \
    222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180

/* p[256 + i] = p[i], as in the reference code. */
static const uint8_t ccl_perlin_p[CCL_NOISE_PERM_SIZE] = {CCL_PERLIN_PERMUTATION, CCL_PERLIN_PERMUTATION};

/* Large offsets of the curl-noise vector potential (lattice units; dyadic, so exactly representable). */
#define CCL_O1X 100.25f
#define CCL_O1Y (-57.75f)
#define CCL_O1Z 33.5f
#define CCL_O2X (-41.5f)
#define CCL_O2Y 88.25f
#define CCL_O2Z (-119.75f)

/* floor(v) as an int32, clamped to +-2^30 so that out-of-range values never reach an undefined conversion. */
static int32_t floor_to_int(float f)
{
    if (!(f >= -1073741824.0f)) f = -1073741824.0f; /* also maps NaN (callers reject NaN before) */
    if (f > 1073741824.0f) f = 1073741824.0f;
    return (int32_t)f;
}

/* Lattice coordinate wrapped for the table: i mod period (period >= 1), then & 255; period 0: i & 255 (Perlin). */
static int32_t wrap_lattice(int32_t i, int32_t period)
{
    int32_t r;
    if (period > 0) {
        r = i % period;
        if (r < 0) r += period;
        return (int32_t)((uint32_t)r & 255u);
    }
    return (int32_t)((uint32_t)i & 255u);
}

/* Non-negative i mod n (n >= 1). */
static int32_t pmod(int32_t i, int32_t n)
{
    int32_t r = i % n;
    if (r < 0) r += n;
    return r;
}

ccl_status ccl_noise_perm_table(uint32_t seed, uint8_t *out_perm)
{
    uint32_t key;
    int i;
    if (out_perm == NULL) return CCL_EINVAL;
    if (seed == 0u) {
        for (i = 0; i < CCL_NOISE_PERM_SIZE; ++i) out_perm[i] = ccl_perlin_p[i];
        return CCL_OK;
    }
    for (i = 0; i < 256; ++i) out_perm[i] = (uint8_t)i;
    key = ccl_hash_pcg(seed);
    for (i = 255; i >= 1; --i) {
        uint32_t j = ccl_hash_pcg(key + (uint32_t)i) % (uint32_t)(i + 1);
        uint8_t tmp = out_perm[i];
        out_perm[i] = out_perm[j];
        out_perm[j] = tmp;
    }
    for (i = 0; i < 256; ++i) out_perm[256 + i] = out_perm[i];
    return CCL_OK;
}

/* The table of a seed: the built-in one for seed 0, else built into buf. */
static const uint8_t *table_for(uint32_t seed, uint8_t *buf)
{
    if (seed == 0u) return ccl_perlin_p;
    ccl_noise_perm_table(seed, buf);
    return buf;
}

/* Perlin's grad(): the low 4 bits of the hash select one of the 12 cube-edge directions (4 repeated). */
static float grad3(int32_t hash, float x, float y, float z)
{
    int32_t h = hash & 15;
    float u = h < 8 ? x : y;
    float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}

static int all_finite3(float x, float y, float z)
{
    return isfinite(x) && isfinite(y) && isfinite(z);
}

float ccl_noise_perlin3_perm(float x, float y, float z, const uint8_t *perm, int32_t period)
{
    float fx, fy, fz, u, v, w;
    int32_t x0, x1, y0, y1, z0, z1, a0, a1, b0, b1, aa, ab, ba, bb, aa1, ab1, ba1, bb1;
    CCL_REQUIRE(perm != NULL);
    CCL_REQUIRE(period >= 0);
    if (!all_finite3(x, y, z)) return NAN;
    fx = floorf(x);
    fy = floorf(y);
    fz = floorf(z);
    x0 = floor_to_int(fx);
    y0 = floor_to_int(fy);
    z0 = floor_to_int(fz);
    x1 = wrap_lattice(x0 + 1, period);
    y1 = wrap_lattice(y0 + 1, period);
    z1 = wrap_lattice(z0 + 1, period);
    x0 = wrap_lattice(x0, period);
    y0 = wrap_lattice(y0, period);
    z0 = wrap_lattice(z0, period);
    /* relative position in the cell (exact in float32) */
    x -= fx;
    y -= fy;
    z -= fz;
    u = ccl_interp_fade_quintic(x);
    v = ccl_interp_fade_quintic(y);
    w = ccl_interp_fade_quintic(z);
    /* hash of the 8 corners: p[p[p[i] + j] + k] */
    a0 = perm[x0] + y0;
    a1 = perm[x0] + y1;
    b0 = perm[x1] + y0;
    b1 = perm[x1] + y1;
    aa = perm[perm[a0] + z0];
    ab = perm[perm[a1] + z0];
    ba = perm[perm[b0] + z0];
    bb = perm[perm[b1] + z0];
    aa1 = perm[perm[a0] + z1];
    ab1 = perm[perm[a1] + z1];
    ba1 = perm[perm[b0] + z1];
    bb1 = perm[perm[b1] + z1];
    return ccl_interp_lerp(w,
        ccl_interp_lerp(v, ccl_interp_lerp(u, grad3(aa, x, y, z), grad3(ba, x - 1.0f, y, z)),
                          ccl_interp_lerp(u, grad3(ab, x, y - 1.0f, z), grad3(bb, x - 1.0f, y - 1.0f, z))),
        ccl_interp_lerp(v, ccl_interp_lerp(u, grad3(aa1, x, y, z - 1.0f), grad3(ba1, x - 1.0f, y, z - 1.0f)),
                          ccl_interp_lerp(u, grad3(ab1, x, y - 1.0f, z - 1.0f),
                                         grad3(bb1, x - 1.0f, y - 1.0f, z - 1.0f))));
}

float ccl_noise_perlin3(float x, float y, float z, uint32_t seed, int32_t period)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    return ccl_noise_perlin3_perm(x, y, z, table_for(seed, buf), period);
}

float ccl_noise_perlin3_tiled(float x, float y, float z, int32_t period, uint32_t seed)
{
    CCL_REQUIRE(period >= 1);
    return ccl_noise_perlin3(x, y, z, seed, period);
}

static float interp_weight(float t, ccl_noise_interp interp)
{
    switch (interp) {
    case CCL_INTERP_CUBIC: return ccl_interp_fade_cubic(t);
    case CCL_INTERP_LINEAR: return t;
    case CCL_INTERP_COSINE: return (1.0f - cosf(CCL_PI_F * t)) * 0.5f;
    case CCL_INTERP_QUINTIC: break;
    }
    return ccl_interp_fade_quintic(t);
}

float ccl_noise_perlin2_perm(float x, float y, const uint8_t *perm, int32_t period, ccl_noise_interp interp)
{
    float fx, fy, u, v;
    int32_t x0, x1, y0, y1, z0;
    CCL_REQUIRE(perm != NULL);
    CCL_REQUIRE(period >= 0);
    if (!(isfinite(x) && isfinite(y))) return NAN;
    fx = floorf(x);
    fy = floorf(y);
    x0 = floor_to_int(fx);
    y0 = floor_to_int(fy);
    x1 = wrap_lattice(x0 + 1, period);
    y1 = wrap_lattice(y0 + 1, period);
    x0 = wrap_lattice(x0, period);
    y0 = wrap_lattice(y0, period);
    z0 = 0; /* the z = 0 slice of the 3-D lattice */
    x -= fx;
    y -= fy;
    u = interp_weight(x, interp);
    v = interp_weight(y, interp);
    return ccl_interp_lerp(v,
        ccl_interp_lerp(u, grad3(perm[perm[perm[x0] + y0] + z0], x, y, 0.0f),
                          grad3(perm[perm[perm[x1] + y0] + z0], x - 1.0f, y, 0.0f)),
        ccl_interp_lerp(u, grad3(perm[perm[perm[x0] + y1] + z0], x, y - 1.0f, 0.0f),
                          grad3(perm[perm[perm[x1] + y1] + z0], x - 1.0f, y - 1.0f, 0.0f)));
}

float ccl_noise_perlin2(float x, float y, uint32_t seed, int32_t period, ccl_noise_interp interp)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    return ccl_noise_perlin2_perm(x, y, table_for(seed, buf), period, interp);
}

/* ---- Worley ---------------------------------------------------------------------------------------------------- */

/* Feature offsets of a wrapped cell from its hash h0 = H(wx + H(wy + H(wz + H(seed)))): h1 = H(h0), h2 = H(h1);
 * 23-bit offsets k / 2^23 in [0, 1), so that d + offset (d in {-1, 0, 1}) is exact in float32. */
static void worley_offsets(uint32_t h0, float *ox, float *oy, float *oz)
{
    const float scale = 1.0f / 8388608.0f; /* 2^-23 */
    uint32_t h1 = ccl_hash_pcg(h0);
    uint32_t h2 = ccl_hash_pcg(h1);
    *ox = (float)(h0 >> 9u) * scale;
    *oy = (float)(h1 >> 9u) * scale;
    *oz = (float)(h2 >> 9u) * scale;
}

ccl_vec3 ccl_noise_worley_feature(int32_t ix, int32_t iy, int32_t iz, int32_t cells, uint32_t seed)
{
    ccl_vec3 o;
    CCL_REQUIRE(cells >= 1);
    if (cells < 1) cells = 1;
    worley_offsets(ccl_hash_pcg((uint32_t)pmod(ix, cells) +
                                ccl_hash_pcg((uint32_t)pmod(iy, cells) +
                                             ccl_hash_pcg((uint32_t)pmod(iz, cells) + ccl_hash_pcg(seed)))),
                   &o.x, &o.y, &o.z);
    return o;
}

float ccl_noise_worley3(float x, float y, float z, int32_t cells, uint32_t seed, ccl_worley_metric metric,
                        int inverse)
{
    float qx, qy, qz, fx, fy, fz, tx, ty, tz, best = FLT_MAX, f1;
    int32_t ix, iy, iz, dx, dy, dz, k;
    uint32_t wx[3], wy[3], wz[3];
    uint32_t hseed = ccl_hash_pcg(seed);
    CCL_REQUIRE(cells >= 1);
    if (cells < 1) cells = 1;
    if (!all_finite3(x, y, z)) return NAN;
    /* cell units: one feature point per unit cell */
    qx = x * (float)cells;
    qy = y * (float)cells;
    qz = z * (float)cells;
    fx = floorf(qx);
    fy = floorf(qy);
    fz = floorf(qz);
    ix = floor_to_int(fx);
    iy = floor_to_int(fy);
    iz = floor_to_int(fz);
    tx = qx - fx;
    ty = qy - fy;
    tz = qz - fz;
    for (k = 0; k < 3; ++k) { /* wrapped cell indices of the neighbours -1, 0, +1 */
        wx[k] = (uint32_t)pmod(ix + k - 1, cells);
        wy[k] = (uint32_t)pmod(iy + k - 1, cells);
        wz[k] = (uint32_t)pmod(iz + k - 1, cells);
    }
    for (dz = -1; dz <= 1; ++dz) {
        uint32_t hz = ccl_hash_pcg(wz[dz + 1] + hseed);
        for (dy = -1; dy <= 1; ++dy) {
            uint32_t hy = ccl_hash_pcg(wy[dy + 1] + hz);
            for (dx = -1; dx <= 1; ++dx) {
                float ox, oy, oz, ddx, ddy, ddz, d;
                worley_offsets(ccl_hash_pcg(wx[dx + 1] + hy), &ox, &oy, &oz);
                ddx = ((float)dx + ox) - tx;
                ddy = ((float)dy + oy) - ty;
                ddz = ((float)dz + oz) - tz;
                if (metric == CCL_WORLEY_MANHATTAN)
                    d = fabsf(ddx) + fabsf(ddy) + fabsf(ddz);
                else
                    d = ddx * ddx + ddy * ddy + ddz * ddz;
                if (d < best) best = d;
            }
        }
    }
    f1 = (metric == CCL_WORLEY_MANHATTAN) ? best : sqrtf(best);
    if (f1 > 1.0f) f1 = 1.0f;
    return inverse ? 1.0f - f1 : f1;
}

void ccl_noise_worley3_variants(float x, float y, float z, int32_t cells, uint32_t seed, float *out_classic,
                                float *out_manhattan, float *out_inverse)
{
    *out_classic = ccl_noise_worley3(x, y, z, cells, seed, CCL_WORLEY_EUCLIDEAN, 0);
    *out_manhattan = ccl_noise_worley3(x, y, z, cells, seed, CCL_WORLEY_MANHATTAN, 0);
    *out_inverse = ccl_noise_worley3(x, y, z, cells, seed, CCL_WORLEY_EUCLIDEAN, 1);
}

float ccl_noise_worley3_bruteforce(float x, float y, float z, int32_t cells, uint32_t seed, ccl_worley_metric metric,
                                   int inverse)
{
    float qx, qy, qz, best = FLT_MAX, f1;
    int32_t i, j, k, cx, cy, cz;
    CCL_REQUIRE(cells >= 1 && cells <= 64);
    if (cells < 1) cells = 1;
    if (cells > 64) cells = 64;
    if (!all_finite3(x, y, z)) return NAN;
    /* position in cell units inside the cube [0, cells)^3 */
    qx = (x - floorf(x)) * (float)cells;
    qy = (y - floorf(y)) * (float)cells;
    qz = (z - floorf(z)) * (float)cells;
    for (k = 0; k < cells; ++k)
        for (j = 0; j < cells; ++j)
            for (i = 0; i < cells; ++i) {
                ccl_vec3 o = ccl_noise_worley_feature(i, j, k, cells, seed);
                float ox = o.x, oy = o.y, oz = o.z;
                for (cz = -1; cz <= 1; ++cz)
                    for (cy = -1; cy <= 1; ++cy)
                        for (cx = -1; cx <= 1; ++cx) {
                            /* feature point (i + ox, ...) of the copy shifted by (cx, cy, cz) cubes */
                            float ddx = ((float)(i + cx * cells) + ox) - qx;
                            float ddy = ((float)(j + cy * cells) + oy) - qy;
                            float ddz = ((float)(k + cz * cells) + oz) - qz;
                            float d = (metric == CCL_WORLEY_MANHATTAN) ? fabsf(ddx) + fabsf(ddy) + fabsf(ddz)
                                                                       : ddx * ddx + ddy * ddy + ddz * ddz;
                            if (d < best) best = d;
                        }
            }
    f1 = (metric == CCL_WORLEY_MANHATTAN) ? best : sqrtf(best);
    if (f1 > 1.0f) f1 = 1.0f;
    return inverse ? 1.0f - f1 : f1;
}

/* ---- fBm ------------------------------------------------------------------------------------------------------- */

float ccl_noise_fbm_perlin3_perm(float x, float y, float z, int32_t octaves, float frequency, const uint8_t *perm,
                                 int32_t period)
{
    float sum = 0.0f, wsum = 0.0f, amp = 1.0f, f = frequency;
    int32_t per = period, i;
    CCL_REQUIRE(octaves >= 1 && octaves <= 24);
    CCL_REQUIRE(frequency > 0.0f && ldexpf(frequency, octaves - 1) <= (float)CCL_NOISE_FBM_MAX_FREQUENCY);
    CCL_REQUIRE(period >= 0);
    for (i = 0; i < octaves; ++i) {
        sum += amp * ccl_noise_perlin3_perm(x * f, y * f, z * f, perm, per);
        wsum += amp;
        f *= 2.0f;
        amp *= 0.5f;
        if (per > 0 && per <= 0x3FFFFFFF) per *= 2; /* the precondition keeps period * 2^(octaves-1) <= 2^30 */
    }
    return sum / wsum;
}

float ccl_noise_fbm_perlin3(float x, float y, float z, int32_t octaves, float frequency, uint32_t seed,
                            int32_t period)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    return ccl_noise_fbm_perlin3_perm(x, y, z, octaves, frequency, table_for(seed, buf), period);
}

float ccl_noise_fbm_perlin2_perm(ccl_vec2 p, int32_t octaves, const uint8_t *perm, float amplitude, float frequency,
                                 float gain, float lacunarity)
{
    float value = 0.0f, amp = amplitude, f = frequency;
    int32_t i;
    CCL_REQUIRE(octaves >= 1 && octaves <= 24);
    CCL_REQUIRE(perm != NULL);
    for (i = 0; i < octaves; ++i) { /* Kod 7.9, operation by operation */
        value += amp * ccl_noise_perlin2_perm(f * p.x, f * p.y, perm, 0, CCL_INTERP_QUINTIC);
        amp *= gain;
        f *= lacunarity;
    }
    return value;
}

float ccl_noise_fbm_perlin2(ccl_vec2 p, int32_t octaves, uint32_t seed, float amplitude, float frequency, float gain,
                            float lacunarity)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    return ccl_noise_fbm_perlin2_perm(p, octaves, table_for(seed, buf), amplitude, frequency, gain, lacunarity);
}

float ccl_noise_fbm_worley3(float x, float y, float z, int32_t octaves, int32_t cells, uint32_t seed,
                            ccl_worley_metric metric, int inverse)
{
    float sum = 0.0f, wsum = 0.0f, amp = 1.0f;
    int32_t c = cells, i;
    CCL_REQUIRE(octaves >= 1 && octaves <= 16);
    CCL_REQUIRE(cells >= 1);
    for (i = 0; i < octaves; ++i) {
        /* octave i: cells * 2^i cells per unit, seed + i */
        sum += amp * ccl_noise_worley3(x, y, z, c, seed + (uint32_t)i, metric, inverse);
        wsum += amp;
        amp *= 0.5f;
        if (c <= 0x3FFFFFFF) c *= 2;
    }
    return sum / wsum;
}

/* ---- curl noise ------------------------------------------------------------------------------------------------ */

/* The finite-difference step actually used at coordinate c: max(h, 2^-20, |c| 2^-22). |c| 2^-22 is at least two
 * float32 ulps of c, so c + h and c - h stay distinct (and the difference quotient finite) even where h is below half
 * an ulp of c; 2^-20 keeps the round-off of the noise values (~6e-8) divided by the step (and, in the nested
 * differences of ccl_noise_curl_property, divided twice) finite. For the default h = 2^-8 neither takes over below
 * |c| = 2^14, beyond the texture generator's range. */
static float fd_step(float c, float h)
{
    const float hc = fabsf(c) * 2.384185791015625e-07f; /* 2^-22 */
    const float h_min = 9.5367431640625e-07f;            /* 2^-20 */
    if (h < h_min) h = h_min;
    return hc > h ? hc : h;
}

/* The two abscissae c + s and c - s of the central difference at c, s = fd_step(c, h). Within s of FLT_MAX the
 * point away from zero overflows to Inf: it is then c itself (a one-sided difference over the spacing actually used),
 * so every finite coordinate gives a finite quotient. Unchanged wherever c + s is finite. */
static void fd_points(float c, float h, float *out_plus, float *out_minus)
{
    const float s = fd_step(c, h);
    float cp = c + s, cm = c - s;
    if (isinf(cp)) cp = c;
    if (isinf(cm)) cm = c;
    *out_plus = cp;
    *out_minus = cm;
}

/* Central difference of perlin3 along `axis` (0, 1, 2) at (x, y, z). */
static float dnoise(const uint8_t *perm, int32_t period, float x, float y, float z, int axis, float h)
{
    float xp = x, yp = y, zp = z, xm = x, ym = y, zm = z, d;
    if (axis == 0) {
        fd_points(x, h, &xp, &xm);
        d = xp - xm;
    } else if (axis == 1) {
        fd_points(y, h, &yp, &ym);
        d = yp - ym;
    } else {
        fd_points(z, h, &zp, &zm);
        d = zp - zm;
    }
    return (ccl_noise_perlin3_perm(xp, yp, zp, perm, period) - ccl_noise_perlin3_perm(xm, ym, zm, perm, period)) / d;
}

ccl_vec3 ccl_noise_curl3_perm(float x, float y, float z, const uint8_t *perm, int32_t period, float h)
{
    ccl_vec3 v;
    /* psi = (N(p), N(q1), N(q2)), q1 = p + o1, q2 = p + o2; v = nabla x psi (vc-2.23) */
    float q1x = x + CCL_O1X, q1y = y + CCL_O1Y, q1z = z + CCL_O1Z;
    float q2x = x + CCL_O2X, q2y = y + CCL_O2Y, q2z = z + CCL_O2Z;
    CCL_REQUIRE(h > 0.0f);
    v.x = dnoise(perm, period, q2x, q2y, q2z, 1, h) - dnoise(perm, period, q1x, q1y, q1z, 2, h);
    v.y = dnoise(perm, period, x, y, z, 2, h) - dnoise(perm, period, q2x, q2y, q2z, 0, h);
    v.z = dnoise(perm, period, q1x, q1y, q1z, 0, h) - dnoise(perm, period, x, y, z, 1, h);
    return v;
}

ccl_vec3 ccl_noise_curl3(float x, float y, float z, uint32_t seed, int32_t period, float h)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    return ccl_noise_curl3_perm(x, y, z, table_for(seed, buf), period, h);
}

ccl_vec3 ccl_noise_gradient3(float x, float y, float z, uint32_t seed, int32_t period, float h)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    const uint8_t *perm = table_for(seed, buf);
    ccl_vec3 g;
    CCL_REQUIRE(h > 0.0f);
    g.x = dnoise(perm, period, x, y, z, 0, h);
    g.y = dnoise(perm, period, x, y, z, 1, h);
    g.z = dnoise(perm, period, x, y, z, 2, h);
    return g;
}

float ccl_noise_rot2(float x, float y, uint32_t seed, int32_t period, float h)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    const uint8_t *perm = table_for(seed, buf);
    const float z = 0.0f;
    float q1x = x + CCL_O1X, q1y = y + CCL_O1Y, q1z = z + CCL_O1Z;
    CCL_REQUIRE(h > 0.0f);
    /* vc-2.24: dF_y/dx - dF_x/dy with F = (N(p), N(p + o1)) */
    return dnoise(perm, period, q1x, q1y, q1z, 0, h) - dnoise(perm, period, x, y, z, 1, h);
}

float ccl_noise_divergence3(float x, float y, float z, uint32_t seed, int32_t period, float h)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    const uint8_t *perm = table_for(seed, buf);
    float q1x = x + CCL_O1X, q1y = y + CCL_O1Y, q1z = z + CCL_O1Z;
    float q2x = x + CCL_O2X, q2y = y + CCL_O2Y, q2z = z + CCL_O2Z;
    CCL_REQUIRE(h > 0.0f);
    /* vc-2.25, i = 1..3 */
    return dnoise(perm, period, x, y, z, 0, h) + dnoise(perm, period, q1x, q1y, q1z, 1, h) +
           dnoise(perm, period, q2x, q2y, q2z, 2, h);
}

float ccl_noise_curl_property(float x, float y, float z, uint32_t seed, int32_t period, float h,
                              ccl_variant variant)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    const uint8_t *perm = table_for(seed, buf);
    float jac[3][3]; /* jac[j][i] = d v_j / d x_i */
    float cx, cy, cz;
    int i;
    CCL_REQUIRE(h > 0.0f);
    for (i = 0; i < 3; ++i) {
        float px = x, py = y, pz = z, mx = x, my = y, mz = z, d;
        ccl_vec3 vp, vm;
        if (i == 0) {
            fd_points(x, h, &px, &mx);
            d = px - mx;
        } else if (i == 1) {
            fd_points(y, h, &py, &my);
            d = py - my;
        } else {
            fd_points(z, h, &pz, &mz);
            d = pz - mz;
        }
        vp = ccl_noise_curl3_perm(px, py, pz, perm, period, h);
        vm = ccl_noise_curl3_perm(mx, my, mz, perm, period, h);
        jac[0][i] = (vp.x - vm.x) / d;
        jac[1][i] = (vp.y - vm.y) / d;
        jac[2][i] = (vp.z - vm.z) / d;
    }
    if (variant == CCL_VARIANT_THESIS) {
        /* the printed nabla x F = 0, with F = v */
        cx = jac[2][1] - jac[1][2];
        cy = jac[0][2] - jac[2][0];
        cz = jac[1][0] - jac[0][1];
        return sqrtf(cx * cx + cy * cy + cz * cz);
    }
    return jac[0][0] + jac[1][1] + jac[2][2];
}

ccl_vec2 ccl_noise_curl2_perm(float x, float y, const uint8_t *perm, int32_t period, float h)
{
    /* stream function psi = N(x, y, 0); v = (dpsi/dy, -dpsi/dx) */
    ccl_vec2 v;
    CCL_REQUIRE(h > 0.0f);
    v.x = dnoise(perm, period, x, y, 0.0f, 1, h);
    v.y = -dnoise(perm, period, x, y, 0.0f, 0, h);
    return v;
}

ccl_vec2 ccl_noise_curl2(float x, float y, uint32_t seed, int32_t period, float h)
{
    uint8_t buf[CCL_NOISE_PERM_SIZE];
    return ccl_noise_curl2_perm(x, y, table_for(seed, buf), period, h);
}

/* ---- Perlin-Worley ----------------------------------------------------------------------------------- */

float ccl_noise_perlin_worley(float p, float w, ccl_perlin_worley_mode combination)
{
    float r;
    switch (combination) {
    case CCL_PW_GPU_PRO_7:
        if (w >= 1.0f) return 0.0f; /* (P - W) / (1 - W) is undefined at W = 1: the clamped limit for P < 1 */
        r = ccl_interp_remap(p, w, 1.0f, 0.0f, 1.0f);
        return r < 0.0f ? 0.0f : (r > 1.0f ? 1.0f : r);
    case CCL_PW_HILLAIRE:
        return ccl_interp_remap(p, 0.0f, 1.0f, w, 1.0f);
    case CCL_PW_PRODUCT:
        return p * w;
    case CCL_PW_AVERAGE:
        return (p + w) * 0.5f;
    case CCL_PW_THESIS:
        break;
    }
    r = ccl_interp_remap(p, 0.0f, 1.0f, w, 1.0f);
    return r * r;
}
