/* Fuzz harness: the reprojection pass ccl_reproj_frame (cclouds/reproj.h) on tiny frames (width, height in
 * [-2, 9], channels in [-1, 4]; buffers always big enough for the largest), arbitrary matrices, eye, sphere,
 * neighbourhood, history, any frame number; also ccl_reproj_grid with any int. Contract: CCL_EINVAL exactly for
 * the documented invalid arguments, out untouched then; CCL_OK: the pixels rendered this frame are copied bit for
 * bit from current, every output value is finite when the input buffers are finite. */
#include "cclouds/reproj.h"
#include "fuzz.h"

#define MAXW 9
#define MAXC 4
#define N (MAXW * MAXW * MAXC)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    int gw = -7, gh = -7;
    int32_t a = fz_i32(r), b = fz_i32(r);
    ccl_status gs = ccl_reproj_grid(a, b, &gw, &gh);
    FZ_CHECK((gs == CCL_OK) == (a >= 1 && b >= 1), "reproj_grid(%d, %d) = %d", a, b, (int)gs);
    if (gs == CCL_OK) FZ_CHECK(gw == (int)(((int64_t)a + 3) / 4) && gh == (int)(((int64_t)b + 3) / 4), "grid size");

    int width = fz_range(r, -2, MAXW), height = fz_range(r, -2, MAXW), channels = fz_range(r, -1, MAXC);
    int frame = fz_i32(r);
    float ivp[16], pvp[16];
    int camera = fz_u8(r) % 3;
    for (int i = 0; i < 16; ++i) {
        /* 0: arbitrary matrices; 1, 2: identity-like with fuzzed entries */
        ivp[i] = camera == 0 ? fz_float(r) : ((i % 5 == 0) ? 1.0f : 0.0f);
        pvp[i] = camera == 0 ? fz_float(r) : ((i % 5 == 0) ? 1.0f : 0.0f);
    }
    if (camera == 2) {
        ivp[fz_u8(r) % 16] = fz_float(r);
        pvp[fz_u8(r) % 16] = fz_float(r);
    }
    ccl_vec3 eye = {fz_float(r), fz_float(r), fz_float(r)};
    ccl_vec3 centre = {fz_float(r), fz_float(r), fz_float(r)};
    if (fz_bool(r)) { /* a plausible layer: camera near the top of a big sphere */
        eye.x = fz_unit(r, -5.0f, 5.0f);
        eye.y = fz_unit(r, 0.0f, 3.0f);
        eye.z = fz_unit(r, -5.0f, 5.0f);
        centre.x = 0.0f;
        centre.y = -6371.0f;
        centre.z = 0.0f;
    }
    float r_inner = fz_u8(r) < 128 ? 6372.5f : fz_float(r);
    int neighbourhood = fz_u8(r) < 128 ? (fz_bool(r) ? 1 : 3) : fz_i32(r);
    int history = fz_u8(r) < 200 ? fz_bool(r) : fz_i32(r);
    int alias = fz_u8(r) % 4; /* 0: out == current, 1: out == previous (invalid), 2, 3: separate */

    float *cur = malloc(N * sizeof(float)), *prev = malloc(N * sizeof(float)), *red = malloc(N * sizeof(float));
    float *out = malloc(N * sizeof(float)), *orig = malloc(N * sizeof(float));
    for (int i = 0; i < N; ++i) {
        cur[i] = fz_unit(r, -100.0f, 100.0f);
        prev[i] = fz_unit(r, -100.0f, 100.0f);
        red[i] = fz_unit(r, -100.0f, 100.0f);
        out[i] = 7777.0f;
    }
    float *dst = alias == 0 ? cur : (alias == 1 ? prev : out);
    memcpy(orig, cur, N * sizeof(float));
    float before[N];
    memcpy(before, dst, sizeof before);

    ccl_status st = ccl_reproj_frame(cur, prev, red, width, height, channels, frame, ivp, eye, pvp, centre, r_inner,
                                     neighbourhood, history, dst);
    int valid = width >= 1 && height >= 1 && channels >= 1 && neighbourhood >= 1 && (neighbourhood & 1) &&
                neighbourhood <= CCL_REPROJ_MAX_NEIGHBOURHOOD && r_inner > 0.0f && dst != prev;
    /* documented invalid arguments; other non-finite camera values are allowed (they only force the fallback) */
    if (!valid) FZ_CHECK(st == CCL_EINVAL, "invalid arguments accepted (w %d h %d c %d n %d r %g alias %d)", width,
                         height, channels, neighbourhood, (double)r_inner, alias);
    if (st != CCL_OK) {
        FZ_CHECK(memcmp(before, dst, sizeof before) == 0, "out written on an error");
    } else {
        FZ_CHECK(valid, "status OK for invalid input");
        size_t n = (size_t)width * (size_t)height * (size_t)channels;
        FZ_CHECK(fz_all_finite(dst, n), "non-finite output (finite buffers)");
        for (size_t i = 0; i < n; ++i)
            FZ_CHECK(fabsf(dst[i]) <= 100.001f, "output %.9g outside the range of the inputs (+- 100)", (double)dst[i]);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (ccl_reproj_updated(x, y, frame))
                    for (int c = 0; c < channels; ++c) {
                        size_t i = ((size_t)y * (size_t)width + (size_t)x) * (size_t)channels + (size_t)c;
                        FZ_CHECK(dst[i] == orig[i], "rendered pixel (%d, %d) not copied", x, y);
                    }
        if (dst != out) FZ_CHECK(out[0] == 7777.0f, "separate buffer touched");
    }
    free(cur);
    free(prev);
    free(red);
    free(out);
    free(orig);
    return 0;
}
