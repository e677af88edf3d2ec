/* Value noise of the oc text (§5.1). See cclouds/valuenoise.h for the readings chosen where the text is silent.
 * Mirrored operation by operation in pywarp/kernels/valuenoise.py. */
#include "cclouds/valuenoise.h"
#include "cclouds/hash.h"
#include "internal.h"

#define PI_PRINTED 3.1415927f /* pi as printed in the cosine listing (oc-5.1.4.2); the same float32 as M_PI */

static float lattice_value(uint32_t h, int range)
{
    float u = ccl_hash_unit(h);
    return range == CCL_VALUENOISE_SIGNED ? 2.0f * u - 1.0f : u;
}

float ccl_valuenoise_lattice(int32_t x, int32_t y, int32_t z, uint32_t seed, int range)
{
    uint32_t hz = ccl_hash_pcg((uint32_t)z + seed);
    uint32_t hy = ccl_hash_pcg((uint32_t)y + hz);
    return lattice_value(ccl_hash_pcg((uint32_t)x + hy), range);
}

/* Per-axis weight of the binomial (Elias) kernel: 1/2 at the centre, 1/4 at the sides; 1 on an axis beyond dims
 * (half-width r = 0). */
static float elias_weight(int32_t d, int32_t r)
{
    return r == 0 ? 1.0f : (d == 0 ? 0.5f : 0.25f);
}

float ccl_valuenoise_smooth(int32_t x, int32_t y, int32_t z, uint32_t seed, int32_t dims, int smoothing, int range)
{
    int32_t r[3] = {1, 1, 1}; /* neighbourhood half-width per axis: 0 beyond dims */
    int32_t dx, dy, dz, count = 0;
    float sum = 0.0f;
    CCL_REQUIRE(dims >= 1 && dims <= 3);
    if (dims < 2) { y = 0; r[1] = 0; }
    if (dims < 3) { z = 0; r[2] = 0; }
    if (smoothing == CCL_VALUENOISE_SMOOTH_NONE)
        return ccl_valuenoise_lattice(x, y, z, seed, range);
    /* z outermost, x innermost: the partial hashes of z and y are shared by the points of a row */
    for (dz = -r[2]; dz <= r[2]; ++dz) {
        uint32_t hz = ccl_hash_pcg((uint32_t)z + (uint32_t)dz + seed);
        for (dy = -r[1]; dy <= r[1]; ++dy) {
            uint32_t hy = ccl_hash_pcg((uint32_t)y + (uint32_t)dy + hz);
            for (dx = -r[0]; dx <= r[0]; ++dx) {
                int32_t off = (dx != 0) + (dy != 0) + (dz != 0);
                float v;
                if (smoothing == CCL_VALUENOISE_SMOOTH_ELIAS) {
                    v = lattice_value(ccl_hash_pcg((uint32_t)x + (uint32_t)dx + hy), range);
                    sum += elias_weight(dx, r[0]) * elias_weight(dy, r[1]) * elias_weight(dz, r[2]) * v;
                } else if (off == 0 || (smoothing == CCL_VALUENOISE_SMOOTH_4 && off > 1)) {
                    continue; /* centre excluded; the 4-neighbourhood keeps the side (face) neighbours only */
                } else {
                    v = lattice_value(ccl_hash_pcg((uint32_t)x + (uint32_t)dx + hy), range);
                    sum += v;
                    ++count;
                }
            }
        }
    }
    if (smoothing == CCL_VALUENOISE_SMOOTH_ELIAS) return sum;
    return sum / (float)count;
}

/* a (1 - f) + b f rounds up to an ulp outside [min(a, b), max(a, b)] (1000.00006 for a = b = 1000 in the cosine
 * form, fuzz finding I1): such a result is the nearest end value (a NaN stays NaN) */
static float between(float r, float a, float b)
{
    const float lo = a < b ? a : b, hi = a < b ? b : a;
    return r < lo ? lo : (r > hi ? hi : r);
}

float ccl_valuenoise_linear(float a, float b, float x)
{
    return between(a * (1.0f - x) + b * x, a, b);
}

float ccl_valuenoise_cosine(float a, float b, float x)
{
    float ft = x * PI_PRINTED;
    float f = (1.0f - cosf(ft)) * 0.5f;
    return between(a * (1.0f - f) + b * f, a, b);
}

float ccl_valuenoise_cubic(float v0, float v1, float v2, float v3, float x)
{
    float p = (v3 - v2) - (v0 - v1);
    float q = (v0 - v1) - p;
    float r = v2 - v0;
    float s = v1;
    return p * x * x * x + q * x * x + r * x + s;
}

/* ---- separable interpolation of the smoothed lattice ------------------------------------------------------------- */

typedef struct {
    uint32_t seed;
    int32_t dims;
    int smoothing, interpolation, range;
} noise_params;

static float interp4(int kind, float v0, float v1, float v2, float v3, float t)
{
    if (kind == CCL_VALUENOISE_CUBIC) return ccl_valuenoise_cubic(v0, v1, v2, v3, t);
    if (kind == CCL_VALUENOISE_COSINE) return ccl_valuenoise_cosine(v1, v2, t);
    return ccl_valuenoise_linear(v1, v2, t);
}

/* Along x at lattice row (y, z): nodes ix - 1 .. ix + 2 (the outer two only for the cubic). */
static float line_x(const noise_params *np, int32_t ix, int32_t y, int32_t z, float fx)
{
    float v0 = 0.0f, v3 = 0.0f, v1, v2;
    if (np->interpolation == CCL_VALUENOISE_CUBIC) {
        v0 = ccl_valuenoise_smooth(ix - 1, y, z, np->seed, np->dims, np->smoothing, np->range);
        v3 = ccl_valuenoise_smooth(ix + 2, y, z, np->seed, np->dims, np->smoothing, np->range);
    }
    v1 = ccl_valuenoise_smooth(ix, y, z, np->seed, np->dims, np->smoothing, np->range);
    v2 = ccl_valuenoise_smooth(ix + 1, y, z, np->seed, np->dims, np->smoothing, np->range);
    return interp4(np->interpolation, v0, v1, v2, v3, fx);
}

static float plane_xy(const noise_params *np, int32_t ix, int32_t iy, int32_t z, float fx, float fy)
{
    float v0 = 0.0f, v3 = 0.0f, v1, v2;
    if (np->dims < 2) return line_x(np, ix, 0, 0, fx);
    if (np->interpolation == CCL_VALUENOISE_CUBIC) {
        v0 = line_x(np, ix, iy - 1, z, fx);
        v3 = line_x(np, ix, iy + 2, z, fx);
    }
    v1 = line_x(np, ix, iy, z, fx);
    v2 = line_x(np, ix, iy + 1, z, fx);
    return interp4(np->interpolation, v0, v1, v2, v3, fy);
}

static float volume_xyz(const noise_params *np, int32_t ix, int32_t iy, int32_t iz, float fx, float fy, float fz)
{
    float v0 = 0.0f, v3 = 0.0f, v1, v2;
    if (np->dims < 3) return plane_xy(np, ix, iy, 0, fx, fy);
    if (np->interpolation == CCL_VALUENOISE_CUBIC) {
        v0 = plane_xy(np, ix, iy, iz - 1, fx, fy);
        v3 = plane_xy(np, ix, iy, iz + 2, fx, fy);
    }
    v1 = plane_xy(np, ix, iy, iz, fx, fy);
    v2 = plane_xy(np, ix, iy, iz + 1, fx, fy);
    return interp4(np->interpolation, v0, v1, v2, v3, fz);
}

float ccl_valuenoise_interpolated(float x, float y, float z, uint32_t seed, int32_t dims, int smoothing,
                                  int interpolation, int range)
{
    noise_params np;
    float flx = floorf(x), fly = floorf(y), flz = floorf(z);
    CCL_REQUIRE(dims >= 1 && dims <= 3);
    np.seed = seed;
    np.dims = dims;
    np.smoothing = smoothing;
    np.interpolation = interpolation;
    np.range = range;
    if (x != x || y != y || z != z) return x + y + z; /* NaN propagates */
    return volume_xyz(&np, (int32_t)flx, (int32_t)fly, (int32_t)flz, x - flx, y - fly, z - flz);
}

float ccl_valuenoise_amplitude(int32_t octave, float persistence, int variant)
{
    float a = variant == CCL_VARIANT_THESIS ? persistence : 1.0f;
    int32_t i;
    CCL_REQUIRE(octave >= 0 && octave < CCL_VALUENOISE_MAX_OCTAVES);
    for (i = 0; i < octave && i < CCL_VALUENOISE_MAX_OCTAVES; ++i)
        a = variant == CCL_VARIANT_THESIS ? a * a : a * persistence;
    return a;
}

float ccl_valuenoise_fbm(float x, float y, float z, uint32_t seed, int32_t dims, int32_t octaves, float persistence,
                         int smoothing, int interpolation, int variant, int range)
{
    uint32_t base = ccl_hash_pcg(seed);
    float total = 0.0f, norm = 0.0f, freq = 1.0f;
    float a = variant == CCL_VARIANT_THESIS ? persistence : 1.0f;
    int32_t i;
    CCL_REQUIRE(octaves >= 1 && octaves <= CCL_VALUENOISE_MAX_OCTAVES);
    for (i = 0; i < octaves && i < CCL_VALUENOISE_MAX_OCTAVES; ++i) {
        total += a * ccl_valuenoise_interpolated(x * freq, y * freq, z * freq, base + (uint32_t)i, dims, smoothing,
                                                 interpolation, range);
        norm += a;
        freq *= 2.0f;
        a = variant == CCL_VARIANT_THESIS ? a * a : a * persistence;
    }
    return total / norm;
}
