/* Fuzz harness: the reprojection pass ccl_reproj_frame (cclouds/reproj.h) on tiny frames (width, height in
 * [-2, 9], channels in [-1, 4]; buffers always big enough for the largest), arbitrary matrices, eye, sphere,
 * neighbourhood, history, any frame number; also ccl_reproj_grid with any int. Contract: CCL_EINVAL exactly for
 * the documented invalid arguments, out untouched then; CCL_OK: the pixels rendered this frame are copied bit for
 * bit from current, every output value is finite when the input buffers are finite.
 * Then the depth-aware pass ccl_reproj_frame_depth on the same frame with fuzzed depth buffers (clouds, the sky,
 * unknown 0 or negative), previous eye, filter, iterations and aliasing of the outputs: CCL_EINVAL exactly for the
 * documented invalid arguments, outputs untouched then; CCL_OK: rendered pixels (colour and depth) copied bit for
 * bit, colours finite and within the inputs' range (the Catmull-Rom filter is clamped to its bilinear footprint),
 * depths finite. */
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
    /* the depth-aware pass's own arguments, read before the (long) buffers so that short inputs reach them */
    ccl_vec3 prev_eye = {eye.x + fz_unit(r, -0.5f, 0.5f), eye.y + fz_unit(r, -0.5f, 0.5f),
                         eye.z + fz_unit(r, -0.5f, 0.5f)};
    if (fz_u8(r) < 16) prev_eye.x = fz_float(r);
    int filter = fz_u8(r) < 240 ? fz_bool(r) : fz_range(r, -2, 3);
    int iterations = fz_u8(r) < 240 ? fz_range(r, 0, 3) : fz_range(r, -2, CCL_REPROJ_MAX_DEPTH_ITERATIONS + 2);
    /* 0: out == current, out_depth == current_depth (allowed); 1: out_depth == previous_depth; 2: out ==
     * current_depth; 3: out_depth == current (invalid); 4, 5: separate */
    int alias_d = fz_u8(r) % 6;
    uint32_t depth_seed = fz_u32(r);

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

    /* --- the depth-aware pass ---------------------------------------------------------------------------------- */
    /* every buffer N floats: a depth buffer may be passed where a colour buffer goes (the aliasing cases) */
    float *dep = malloc(N * sizeof(float)), *pdep = malloc(N * sizeof(float));
    float *od = malloc(N * sizeof(float)), *odep_orig = malloc(N * sizeof(float));
    for (int i = 0; i < N; ++i) {
        /* depths from a hash of the index and a fuzzed seed: mostly clouds (0.01 .. 10 km), some sky, unknown (0)
         * and negative values */
        uint32_t h1 = ((uint32_t)i * 2654435761u) ^ depth_seed, h2 = (h1 ^ (h1 >> 15)) * 2246822519u;
        uint32_t k1 = h1 % 8u, k2 = (h2 >> 8) % 8u;
        float v1 = 0.01f + (float)((h2 >> 11) % 1000u) * 0.01f, v2 = 0.01f + (float)((h1 >> 13) % 1000u) * 0.01f;
        dep[i] = k1 < 5u ? v1 : (k1 == 5u ? CCL_REPROJ_SKY_DEPTH_KM : -v2);
        pdep[i] = k2 < 5u ? v2 : (k2 == 5u ? CCL_REPROJ_SKY_DEPTH_KM : (k2 == 6u ? 0.0f : -v1));
        od[i] = 5555.0f;
    }
    for (int i = 0; i < N; ++i) {
        cur[i] = orig[i];
        out[i] = 7777.0f;
    }
    memcpy(odep_orig, dep, N * sizeof(float));
    float *dst_c = alias_d == 0 ? cur : (alias_d == 2 ? dep : out);
    float *dst_d = alias_d == 0 ? dep : (alias_d == 1 ? pdep : (alias_d == 3 ? cur : od));
    float before_c[N], before_d[N];
    memcpy(before_c, dst_c, sizeof before_c);
    memcpy(before_d, dst_d, sizeof before_d);
    st = ccl_reproj_frame_depth(cur, dep, prev, pdep, red, width, height, channels, frame, ivp, eye, pvp, prev_eye,
                                centre, r_inner, neighbourhood, filter, iterations, history, dst_c, dst_d);
    int valid_d = width >= 1 && height >= 1 && channels >= 1 && neighbourhood >= 1 && (neighbourhood & 1) &&
                  neighbourhood <= CCL_REPROJ_MAX_NEIGHBOURHOOD && r_inner > 0.0f && (filter == 0 || filter == 1) &&
                  iterations >= 0 && iterations <= CCL_REPROJ_MAX_DEPTH_ITERATIONS && alias_d != 1 && alias_d != 2 &&
                  alias_d != 3;
    if (!valid_d)
        FZ_CHECK(st == CCL_EINVAL, "depth pass: invalid arguments accepted (filter %d iterations %d alias %d)", filter,
                 iterations, alias_d);
    if (st != CCL_OK) {
        FZ_CHECK(memcmp(before_c, dst_c, sizeof before_c) == 0, "depth pass: out written on an error");
        FZ_CHECK(memcmp(before_d, dst_d, sizeof before_d) == 0, "depth pass: out_depth written on an error");
    } else {
        FZ_CHECK(valid_d, "depth pass: status OK for invalid input");
        size_t n = (size_t)width * (size_t)height * (size_t)channels, np = (size_t)width * (size_t)height;
        FZ_CHECK(fz_all_finite(dst_c, n), "depth pass: non-finite colour (finite buffers)");
        FZ_CHECK(fz_all_finite(dst_d, np), "depth pass: non-finite depth (finite buffers)");
        for (size_t i = 0; i < n; ++i)
            FZ_CHECK(fabsf(dst_c[i]) <= 100.001f, "depth pass: colour %.9g outside the inputs' range (+- 100)",
                     (double)dst_c[i]);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (ccl_reproj_updated(x, y, frame)) {
                    size_t k = (size_t)y * (size_t)width + (size_t)x;
                    FZ_CHECK(dst_d[k] == odep_orig[k], "depth pass: rendered depth (%d, %d) not copied", x, y);
                    for (int c = 0; c < channels; ++c)
                        FZ_CHECK(dst_c[k * (size_t)channels + (size_t)c] == orig[k * (size_t)channels + (size_t)c],
                                 "depth pass: rendered pixel (%d, %d) not copied", x, y);
                }
    }
    free(dep);
    free(pdep);
    free(od);
    free(odep_orig);
    free(cur);
    free(prev);
    free(red);
    free(out);
    free(orig);
    return 0;
}
