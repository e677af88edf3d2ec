/* Fuzz harness: the refraction mask ccl_rain_mask (cclouds/rain.h) with sizes in [-2, 8] (and huge ones, refused
 * before any write), arbitrary drop radius, deformation, index of refraction, interpolation and method values.
 * Contract: CCL_EINVAL for a size outside [1, 4096], deform outside [0, 1], n_water outside [1, 2] (NaN included),
 * an unknown method or a radius its interpolation does not cover, nothing written then; CCL_OK: every exit
 * direction is a unit vector or (0, 0, 0), inside is 0 or 1, every normal is unit or zero, all finite. */
#include "cclouds/rain.h"
#include "fuzz.h"

#define MAXS 8

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    int sz = fz_u8(r) < 240 ? fz_range(r, -2, MAXS) : fz_i32(r);
    float a = fz_u8(r) < 128 ? fz_unit(r, 0.4f, 4.6f) : fz_float(r);
    float deform = fz_u8(r) < 128 ? fz_unit(r, 0.0f, 1.0f) : fz_float(r);
    float n_water = fz_u8(r) < 128 ? fz_unit(r, 1.0f, 2.0f) : fz_float(r);
    int interp = fz_u8(r) < 230 ? fz_range(r, 0, 1) : fz_i32(r);
    int method = fz_u8(r) < 230 ? fz_range(r, 0, 2) : fz_i32(r);
    int with_normals = fz_bool(r);
    if (sz > MAXS && sz <= 4096) return 0; /* valid but too big for a quick run */
    float rgba[MAXS * MAXS * 4 + 1], normals[MAXS * MAXS * 3 + 1];
    for (size_t i = 0; i < sizeof rgba / sizeof rgba[0]; ++i) rgba[i] = 9.0f;
    for (size_t i = 0; i < sizeof normals / sizeof normals[0]; ++i) normals[i] = 9.0f;
    ccl_status st = ccl_rain_mask(sz, a, deform, n_water, (ccl_rain_interp)interp, (ccl_rain_mask_method)method, rgba,
                                  with_normals ? normals : NULL);
    int bad = sz < 1 || sz > 4096 || !(deform >= 0.0f && deform <= 1.0f) || !(n_water >= 1.0f && n_water <= 2.0f) ||
              method < 0 || method > 2;
    if (bad) FZ_CHECK(st == CCL_EINVAL, "invalid arguments accepted (size %d deform %g n %g method %d)", sz,
                      (double)deform, (double)n_water, method);
    if (st != CCL_OK) {
        for (size_t i = 0; i < sizeof rgba / sizeof rgba[0]; ++i) FZ_CHECK(rgba[i] == 9.0f, "written on an error");
        for (size_t i = 0; i < sizeof normals / sizeof normals[0]; ++i)
            FZ_CHECK(normals[i] == 9.0f, "normals written on an error");
        return 0;
    }
    size_t n = (size_t)sz * (size_t)sz;
    FZ_CHECK(fz_all_finite(rgba, n * 4), "mask not finite (size %d a %g deform %g n %g interp %d method %d)", sz,
             (double)a, (double)deform, (double)n_water, interp, method);
    for (size_t i = 0; i < n; ++i) {
        const float *e = rgba + 4 * i;
        float len = sqrtf(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        FZ_CHECK(len == 0.0f || fabsf(len - 1.0f) < 1e-4f, "exit direction of length %g", (double)len);
        FZ_CHECK(e[3] == 0.0f || e[3] == 1.0f, "inside = %g", (double)e[3]);
        if (with_normals) {
            const float *m = normals + 3 * i;
            float nl = sqrtf(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
            FZ_CHECK(isfinite(nl) && (nl == 0.0f || fabsf(nl - 1.0f) < 1e-4f), "normal of length %g", (double)nl);
        }
    }
    FZ_CHECK(rgba[n * 4] == 9.0f, "write past size^2 texels");
    return 0;
}
