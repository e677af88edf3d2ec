/* Fuzz harness: the oc text's building blocks (cclouds/valuenoise.h, voxel.h, volume.h, flight.h), written from the
 * headers (issue 31). Contracts:
 *   value noise: lattice values in {0, ..., 1 - 2^-24} (unit) or [-1, 1 - 2^-23] (signed), the same for the same
 *     arguments; smoothed values within the range; the interpolated noise equals the smoothed value at lattice points
 *     (exactly for linear and cosine) and, like the octave sum, stays within the range for linear / cosine; the
 *     linear and cosine forms between their end values (finding I1); octave amplitudes in [0, 1];
 *   the voxel filter in [0, 255], non-decreasing in n, non-increasing in cover and in sharpness;
 *   the volume samplers: a uint8 grid sampled anywhere (infinite coordinates included) in [0, 1], a float grid
 *     within its values' range, NaN only for a NaN coordinate;
 *   the metaball between 0 and strength for any r >= 0 and R > 0 (N6); the textured ellipsoid in [0, 1];
 *   the aircraft SDF finite, a part in 0..3, 1-Lipschitz (a distance bound). */
#include "cclouds/flight.h"
#include "cclouds/valuenoise.h"
#include "cclouds/volume.h"
#include "cclouds/voxel.h"
#include "fuzz.h"
#include "fuzz_vec.h"

static int in_range(float v, int range) {
    return range == CCL_VALUENOISE_UNIT ? (v >= 0.0f && v <= 1.0f) : (v >= -1.0f && v <= 1.0f);
}

static void fuzz_valuenoise(fz_reader *r) {
    const uint32_t seed = fz_u32(r);
    const int range = fz_range(r, 0, 1), dims = fz_range(r, 1, 3), smoothing = fz_range(r, 0, 3);
    const int interp = fz_range(r, 0, 2);
    int32_t ix = fz_u8(r) < 200 ? fz_range(r, 0, 4096) : fz_i32(r), iy = fz_range(r, 0, 4096),
            iz = fz_range(r, 0, 4096);
    if (ix < 0) ix = -(ix + 1);
    const float lat = ccl_valuenoise_lattice(ix, iy, iz, seed, range);
    FZ_CHECK(lat == ccl_valuenoise_lattice(ix, iy, iz, seed, range), "lattice not deterministic");
    FZ_CHECK(range == CCL_VALUENOISE_UNIT ? (lat >= 0.0f && lat <= 1.0f - 5.9604645e-8f)
                                          : (lat >= -1.0f && lat <= 1.0f - EPS),
             "lattice %g (range %d)", (double)lat, range);
    if (ix <= 4096) {
        const float sm = ccl_valuenoise_smooth(ix, iy, iz, seed, dims, smoothing, range);
        FZ_CHECK(in_range(sm, range), "smooth %g (range %d)", (double)sm, range);
        /* at a lattice point the interpolation returns the smoothed value (linear and cosine exactly) */
        const float at = ccl_valuenoise_interpolated((float)ix, (float)iy, (float)iz, seed, dims, smoothing, interp,
                                                     range);
        if (interp != CCL_VALUENOISE_CUBIC)
            FZ_CHECK(at == sm, "interpolated %g at the lattice point, smoothed %g (interp %d)", (double)at,
                     (double)sm, interp);
        else
            FZ_CHECK(fabsf(at - sm) <= 8.0f * EPS, "cubic %g at the lattice point, smoothed %g", (double)at,
                     (double)sm);
    }
    {
        const float x = fz_unit(r, 0.0f, 4096.0f), y = fz_unit(r, 0.0f, 4096.0f), z = fz_unit(r, 0.0f, 4096.0f);
        const float v = ccl_valuenoise_interpolated(x, y, z, seed, dims, smoothing, interp, range);
        FZ_CHECK(isfinite(v), "interpolated not finite");
        if (interp != CCL_VALUENOISE_CUBIC) FZ_CHECK(in_range(v, range), "interpolated %g out of range", (double)v);
        const int octaves = fz_range(r, 1, CCL_VALUENOISE_MAX_OCTAVES), variant = fz_range(r, 0, 1);
        const float pers = fz_unit(r, 0.001f, 1.0f);
        const float xs = x / 2048.0f, ys = y / 2048.0f, zs = z / 2048.0f; /* 2^11 x [0, 2] stays in the domain */
        const float f = ccl_valuenoise_fbm(xs, ys, zs, seed, dims, octaves, pers, smoothing, interp, variant, range);
        FZ_CHECK(isfinite(f), "fbm not finite");
        if (interp != CCL_VALUENOISE_CUBIC)
            FZ_CHECK(range == CCL_VALUENOISE_UNIT ? (f >= 0.0f && f <= 1.0f + 4.0f * EPS)
                                                  : (f >= -1.0f - 4.0f * EPS && f <= 1.0f + 4.0f * EPS),
                     "fbm %g out of range", (double)f);
        const float a = ccl_valuenoise_amplitude(fz_range(r, 0, CCL_VALUENOISE_MAX_OCTAVES - 1), pers, variant);
        FZ_CHECK(a >= 0.0f && a <= 1.0f, "amplitude %g", (double)a);
    }
    {
        const float a = fz_u8(r) < 200 ? fz_unit(r, -1000.0f, 1000.0f) : fz_float(r);
        const float b = fz_u8(r) < 64 ? a : (fz_u8(r) < 200 ? fz_unit(r, -1000.0f, 1000.0f) : fz_float(r));
        const float t = fz_unit(r, 0.0f, 1.0f);
        if (isfinite(a) && isfinite(b) && fabsf(a) <= 1e37f && fabsf(b) <= 1e37f) {
            const float lo = fminf(a, b), hi = fmaxf(a, b), l = ccl_valuenoise_linear(a, b, t),
                        c = ccl_valuenoise_cosine(a, b, t);
            FZ_CHECK(l >= lo && l <= hi && c >= lo && c <= hi, "lerp(%.9g, %.9g, %.9g) = %.9g / cosine %.9g outside",
                     (double)a, (double)b, (double)t, (double)l, (double)c);
        }
    }
}

static void fuzz_filter(fz_reader *r) {
    const float n = fz_unit(r, 0.0f, 1.0f), cover = fz_unit(r, 0.0f, 255.0f);
    const float s = fz_u8(r) < 200 ? fz_unit(r, 0.001f, 0.999f) : fz_unit(r, 1e-30f, 0.99999994f);
    const float dn = fz_unit(r, 0.0f, 0.01f), dc = fz_unit(r, 0.0f, 1.0f), ds = fz_unit(r, 0.0f, 0.01f);
    const float f = ccl_voxel_filter(n, cover, s);
    FZ_CHECK(f >= 0.0f && f <= 255.0f, "filter(%g, %g, %g) = %g", (double)n, (double)cover, (double)s, (double)f);
    if (n + dn <= 1.0f)
        FZ_CHECK(ccl_voxel_filter(n + dn, cover, s) >= f, "filter not increasing in n at %.9g", (double)n);
    if (cover + dc <= 255.0f)
        FZ_CHECK(ccl_voxel_filter(n, cover + dc, s) <= f, "filter not decreasing in cover at %.9g", (double)cover);
    if (s + ds < 1.0f)
        FZ_CHECK(ccl_voxel_filter(n, cover, s + ds) <= f, "filter not decreasing in sharpness at %.9g", (double)s);
}

static float fz_coord(fz_reader *r, int n) {
    const uint8_t k = fz_u8(r);
    if (k < 160) return fz_unit(r, -2.0f, (float)n + 2.0f);
    return fz_float(r); /* NaN, +-Inf, huge, tiny */
}

static void fuzz_samplers(fz_reader *r) {
    const int nx = fz_range(r, 1, 4), ny = fz_range(r, 1, 4), nz = fz_range(r, 1, 4);
    unsigned char dens[64];
    float vals[64], lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < nx * ny * nz; ++i) {
        dens[i] = fz_u8(r);
        vals[i] = fz_unit(r, -1000.0f, 1000.0f);
        lo = fminf(lo, vals[i]);
        hi = fmaxf(hi, vals[i]);
    }
    ccl_vec3 v;
    v.x = fz_coord(r, nx);
    v.y = fz_coord(r, ny);
    v.z = fz_coord(r, nz);
    const int nan_in = isnan(v.x) || isnan(v.y) || isnan(v.z);
    const float s = ccl_volume_sample(dens, nx, ny, nz, v), f = ccl_volume_sample_float(vals, nx, ny, nz, v);
    if (nan_in) {
        FZ_CHECK(isnan(s) && isnan(f), "NaN coordinate gave %g %g", (double)s, (double)f);
        return;
    }
    FZ_CHECK(s >= 0.0f && s <= 1.0f, "sample %g at (%g %g %g)", (double)s, (double)v.x, (double)v.y, (double)v.z);
    FZ_CHECK(f >= lo - 1e-3f && f <= hi + 1e-3f, "float sample %g outside [%g, %g] at (%g %g %g)", (double)f,
             (double)lo, (double)hi, (double)v.x, (double)v.y, (double)v.z);
}

static void fuzz_fields(fz_reader *r) {
    {
        float d = fabsf(fz_float(r)), R = fabsf(fz_float(r)), st = fz_float(r);
        if (!(R > 0.0f)) R = 1.0f;
        if (isnan(d)) d = 0.0f;
        if (!isfinite(st)) st = 1.0f;
        const float m = ccl_volume_metaball(d, R, st);
        FZ_CHECK(isfinite(m) && m >= fminf(0.0f, st) && m <= fmaxf(0.0f, st), "metaball(%g, %g, %g) = %g", (double)d,
                 (double)R, (double)st, (double)m);
    }
    {
        ccl_vec3 p, radii;
        p.x = fz_unit(r, -10.0f, 10.0f);
        p.y = fz_unit(r, -10.0f, 10.0f);
        p.z = fz_unit(r, -10.0f, 10.0f);
        radii.x = fz_unit(r, 0.01f, 10.0f);
        radii.y = fz_unit(r, 0.01f, 10.0f);
        radii.z = fz_unit(r, 0.01f, 10.0f);
        const float o = ccl_volume_ellipsoid(p, radii, fz_unit(r, 0.0f, 1.0f), fz_unit(r, -1.0f, 1.0f),
                                             fz_unit(r, 0.001f, 1.0f));
        FZ_CHECK(o >= 0.0f && o <= 1.0f, "ellipsoid opacity %g", (double)o);
    }
    {
        ccl_vec3 p, q;
        const float h = fz_u8(r) < 200 ? 10.0f : 1.0e4f, step = fz_unit(r, 0.0f, 1.0f);
        int part = -1, part2 = -1;
        p.x = fz_unit(r, -h, h);
        p.y = fz_unit(r, -h, h);
        p.z = fz_unit(r, -h, h);
        q.x = p.x + step * fz_unit(r, -1.0f, 1.0f);
        q.y = p.y + step * fz_unit(r, -1.0f, 1.0f);
        q.z = p.z + step * fz_unit(r, -1.0f, 1.0f);
        const float dp = ccl_flight_aircraft(p, &part), dq = ccl_flight_aircraft(q, &part2);
        const float dist = sqrtf((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) + (p.z - q.z) * (p.z - q.z));
        const float mag = fabsf(p.x) + fabsf(p.y) + fabsf(p.z) + 12.0f;
        FZ_CHECK(isfinite(dp) && part >= 0 && part <= 3, "aircraft %g part %d", (double)dp, part);
        FZ_CHECK(fabsf(dp - dq) <= dist + 32.0f * EPS * mag, "aircraft not 1-Lipschitz: |%g - %g| > %g", (double)dp,
                 (double)dq, (double)dist);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    switch (fz_u8(r) % 4) {
    case 0: fuzz_valuenoise(r); break;
    case 1: fuzz_filter(r); break;
    case 2: fuzz_samplers(r); break;
    default: fuzz_fields(r); break;
    }
    return 0;
}
