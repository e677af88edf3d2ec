/* Fuzz harness: the voxel cloud builders (cclouds/voxel.h): ccl_voxel_settings_check, ccl_voxel_noise,
 * ccl_voxel_cloud with any settings (built when valid and size <= 16) and ccl_voxel_scale with edges in [-1, 9].
 * Contract: check gives CCL_OK or CCL_EINVAL with a field name; the builders return the check's status (CCL_ERANGE
 * for a short buffer) and write nothing on an error; noise in [0, 1]; with the ZERO border every face voxel of the
 * cloud is 0; scale accepts exactly edges in [2, 1024] and keeps the values' range. */
#include "cclouds/voxel.h"
#include "fuzz.h"

#define S ccl_voxel_settings
static const fz_field fields[] = {FZ_I(S, size), FZ_I(S, levels), FZ_I(S, seed), FZ_F(S, persistence),
                                  FZ_I(S, interpolation), FZ_I(S, smoothing), FZ_I(S, variant), FZ_I(S, border),
                                  FZ_F(S, sin_radius), FZ_F(S, cover), FZ_F(S, sharpness)};
#undef S

#define MAXS 16
#define NV (MAXS * MAXS * MAXS)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    if (fz_bool(r)) {
        ccl_voxel_settings s = ccl_voxel_settings_default();
        s.levels = fz_range(r, 1, 3);
        s.size = (CCL_VOXEL_MIN_BASE << (s.levels - 1)) * fz_range(r, 1, 2);
        s.seed = fz_u32(r);
        s.border = fz_range(r, 0, 2);
        s.interpolation = fz_range(r, 0, 2);
        fz_mutate(r, &s, fields, sizeof fields / sizeof fields[0], 3);
        const char *field = "unset";
        ccl_status st = ccl_voxel_settings_check(&s, &field);
        FZ_CHECK((st == CCL_OK) == (field == NULL), "check status %d, field %s", (int)st, field ? field : "NULL");
        FZ_CHECK(ccl_voxel_settings_check(NULL, NULL) == CCL_EINVAL, "NULL settings accepted");
        int small = st == CCL_OK && s.size <= MAXS;
        size_t n = small ? (size_t)s.size * (size_t)s.size * (size_t)s.size : 8;
        float *noise = malloc((NV + 1) * sizeof(float));
        uint8_t *cloud = malloc(NV + 1);
        for (size_t i = 0; i <= NV; ++i) {
            noise[i] = -3.0f;
            cloud[i] = 201;
        }
        size_t len = small && fz_u8(r) < 220 ? n : (size_t)fz_range(r, 0, (int32_t)n);
        ccl_status ns = ccl_voxel_noise(&s, noise, len);
        ccl_status cs = ccl_voxel_cloud(&s, cloud, len);
        FZ_CHECK(ns == cs, "noise status %d != cloud status %d", (int)ns, (int)cs);
        if (st != CCL_OK) FZ_CHECK(ns == CCL_EINVAL, "invalid settings: status %d", (int)ns);
        if (ns == CCL_OK) {
            FZ_CHECK(small && len >= n, "accepted size %d, len %zu", s.size, len);
            FZ_CHECK(fz_all_in(noise, n, 0.0f, 1.0f), "noise outside [0, 1]");
            if (s.border == CCL_VOXEL_BORDER_ZERO) {
                int e = s.size;
                for (int z = 0; z < e; ++z)
                    for (int y = 0; y < e; ++y)
                        for (int x = 0; x < e; ++x)
                            if (x == 0 || y == 0 || z == 0 || x == e - 1 || y == e - 1 || z == e - 1)
                                FZ_CHECK(cloud[((size_t)z * e + y) * e + x] == 0, "face voxel not 0");
            }
            FZ_CHECK(len > n || (noise[n] == -3.0f && cloud[n] == 201), "write past size^3");
        } else {
            for (size_t i = 0; i <= NV; ++i) FZ_CHECK(noise[i] == -3.0f && cloud[i] == 201, "written on an error");
        }
        free(noise);
        free(cloud);
    } else {
        int32_t e[6];
        for (int i = 0; i < 6; ++i) e[i] = fz_u8(r) < 240 ? fz_range(r, -1, 9) : fz_i32(r);
        int ok = 1;
        for (int i = 0; i < 6; ++i) ok = ok && e[i] >= 2 && e[i] <= CCL_VOXEL_MAX_SCALE_EDGE;
        int fits = 1;
        for (int i = 0; i < 6; ++i) fits = fits && e[i] <= 9;
        uint8_t src[729], dst[730];
        uint8_t lo = 255, hi = 0;
        for (int i = 0; i < 729; ++i) {
            src[i] = fz_u8(r);
            if (fits && ok && i < e[0] * e[1] * e[2]) {
                lo = src[i] < lo ? src[i] : lo;
                hi = src[i] > hi ? src[i] : hi;
            }
        }
        memset(dst, 99, sizeof dst);
        if (!ok || fits) {
            ccl_status st = ccl_voxel_scale(src, e[0], e[1], e[2], dst, e[3], e[4], e[5]);
            FZ_CHECK((st == CCL_OK) == ok, "scale status %d for edges %d %d %d -> %d %d %d", (int)st, e[0], e[1],
                     e[2], e[3], e[4], e[5]);
            if (st == CCL_OK) {
                int m = e[3] * e[4] * e[5];
                for (int i = 0; i < m; ++i) FZ_CHECK(dst[i] >= lo && dst[i] <= hi, "scaled value outside the range");
                FZ_CHECK(m == 729 || dst[m] == 99, "write past the destination");
            } else {
                for (int i = 0; i < 730; ++i) FZ_CHECK(dst[i] == 99, "written on an error");
            }
            FZ_CHECK(ccl_voxel_scale(NULL, 2, 2, 2, dst, 2, 2, 2) == CCL_EINVAL, "NULL source accepted");
        }
    }
    return 0;
}
