/* Fuzz harness: texture generation (cclouds/texgen.h). Settings decoded from the input (any int32 sizes, octaves,
 * frequencies, cells; NaN/Inf/huge weights and gammas; any enum value), checked, and generated when valid and small
 * (3-D edges <= 8, 2-D <= 16, so one input runs in milliseconds). Contract: the generator's status equals the
 * check's; a wrong out_len or a NULL buffer gives CCL_EINVAL and writes nothing; CCL_OK gives finite texels, in
 * [0, 1] for the base, detail and weather textures; the single-texel forms equal the whole texture's texel. */
#include "cclouds/texgen.h"
#include "fuzz.h"

#define SENTINEL 12345.0f

static int32_t fz_size(fz_reader *r) {
    /* mostly small powers of two, sometimes anything */
    static const int32_t sizes[] = {4, 8, 16, 2, 0, -4, 3, 6};
    uint8_t k = fz_u8(r);
    return k < 200 ? sizes[k % 8] : fz_i32(r);
}

static void untouched(const float *buf, size_t n) {
    for (size_t i = 0; i < n; ++i) FZ_CHECK(buf[i] == SENTINEL, "buffer written at %zu on an error", i);
}

static void run(fz_reader *r, ccl_status check, int32_t size, int dims, size_t channels, int limit, float lo,
                float hi, ccl_status (*gen)(const void *, float *, size_t), const void *s, float **out_buf,
                size_t *out_n) {
    *out_buf = NULL;
    *out_n = 0;
    int small = check == CCL_OK && size <= limit;
    size_t n = small ? (size_t)size * (size_t)size * (dims == 3 ? (size_t)size : 1) * channels : 16;
    float *buf = malloc((n + 4) * sizeof(float));
    for (size_t i = 0; i < n + 4; ++i) buf[i] = SENTINEL;
    uint8_t mode = fz_u8(r) % 4;
    if (mode == 0) {
        FZ_CHECK(gen(s, NULL, n) == CCL_EINVAL, "NULL output accepted");
    } else if (mode == 1 || !small) {
        /* a wrong length (the right one can't be allocated for big sizes, so big sizes always test this) */
        size_t bad = small ? n + (size_t)(fz_u8(r) % 3) + 1 : (size_t)(fz_u8(r) % 17);
        if (small && fz_bool(r)) bad = n - 1;
        FZ_CHECK(gen(s, buf, bad) == CCL_EINVAL, "wrong out_len %zu accepted (expected %zu)", bad, n);
        untouched(buf, n + 4);
    } else {
        ccl_status st = gen(s, buf, n);
        FZ_CHECK(st == check, "generator status %d != check status %d", (int)st, (int)check);
        FZ_CHECK(fz_all_finite(buf, n), "non-finite texel");
        if (lo <= hi) FZ_CHECK(fz_all_in(buf, n, lo, hi), "texel outside [%g, %g]", (double)lo, (double)hi);
        for (size_t i = n; i < n + 4; ++i) FZ_CHECK(buf[i] == SENTINEL, "write past out_len");
        *out_buf = buf;
        *out_n = n;
        return;
    }
    free(buf);
}

static ccl_status gen_base(const void *s, float *o, size_t n) { return ccl_texgen_base_shape(s, o, n); }
static ccl_status gen_detail(const void *s, float *o, size_t n) { return ccl_texgen_detail_shape(s, o, n); }
static ccl_status gen_curl(const void *s, float *o, size_t n) { return ccl_texgen_curl_noise(s, o, n); }
static ccl_status gen_weather(const void *s, float *o, size_t n) { return ccl_texgen_weather_map(s, o, n); }

/* The single-texel forms equal the texture's texel (ix & (size - 1), ...) bit for bit for every int32 coordinate and
 * every lattice frequency or cell count (README.md, finding 2: the coordinate is reduced modulo size first). */
static int32_t texel_coord(fz_reader *r) { return fz_i32(r); }

static float maybe_float(fz_reader *r, float def) { return fz_u8(r) < 160 ? def : fz_float(r); }
static int32_t maybe_i32(fz_reader *r, int32_t def) { return fz_u8(r) < 160 ? def : fz_i32(r); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    const char *field = "unset";
    float *buf = NULL;
    size_t n = 0;
    switch (fz_u8(r) % 4) {
    case 0: {
        ccl_base_shape_settings s = ccl_texgen_base_shape_settings_default();
        s.size = fz_size(r);
        s.seed = fz_u32(r);
        s.perlin_octaves = maybe_i32(r, fz_range(r, 1, 3));
        s.perlin_frequency = maybe_i32(r, fz_range(r, 1, 8));
        s.worley_cells = maybe_i32(r, fz_range(r, 1, 4));
        for (int i = 0; i < 3; ++i) s.worley_weights[i] = maybe_float(r, s.worley_weights[i]);
        s.combination = (ccl_perlin_worley_mode)maybe_i32(r, fz_range(r, 0, 4));
        s.gamma = maybe_float(r, fz_unit(r, 0.25f, 4.0f));
        ccl_status check = ccl_texgen_base_shape_settings_check(&s, &field);
        FZ_CHECK((check == CCL_OK) == (field == NULL), "status %d but field %s", (int)check, field ? field : "NULL");
        run(r, check, s.size, 3, 4, 8, 0.0f, 1.0f, gen_base, &s, &buf, &n);
        if (buf) {
            int32_t ix = texel_coord(r), iy = texel_coord(r), iz = texel_coord(r);
            float t[4];
            ccl_texgen_base_shape_texel(ix, iy, iz, s.size, s.seed, s.perlin_octaves, s.perlin_frequency,
                                        s.worley_cells, s.worley_weights[0], s.worley_weights[1], s.worley_weights[2],
                                        s.gamma, s.combination, &t[0], &t[1], &t[2], &t[3]);
            uint32_t m = (uint32_t)s.size - 1u;
            size_t at = ((((size_t)((uint32_t)iz & m) * (size_t)s.size) + ((uint32_t)iy & m)) * (size_t)s.size +
                         ((uint32_t)ix & m)) * 4;
            FZ_CHECK(memcmp(t, buf + at, sizeof t) == 0,
                     "texel (%d, %d, %d) differs from the texture: size %d seed %u octaves %d frequency %d cells %d "
                     "weights %g %g %g combination %d gamma %g: %.9g %.9g %.9g %.9g vs %.9g %.9g %.9g %.9g",
                     ix, iy, iz, s.size, s.seed, s.perlin_octaves, s.perlin_frequency, s.worley_cells,
                     (double)s.worley_weights[0], (double)s.worley_weights[1], (double)s.worley_weights[2],
                     (int)s.combination, (double)s.gamma, (double)t[0], (double)t[1], (double)t[2], (double)t[3],
                     (double)buf[at], (double)buf[at + 1], (double)buf[at + 2], (double)buf[at + 3]);
        }
        break;
    }
    case 1: {
        ccl_detail_shape_settings s = ccl_texgen_detail_shape_settings_default();
        s.size = fz_size(r);
        s.seed = fz_u32(r);
        s.worley_cells = maybe_i32(r, fz_range(r, 1, 4));
        for (int i = 0; i < 3; ++i) s.worley_weights[i] = maybe_float(r, s.worley_weights[i]);
        s.gamma = maybe_float(r, fz_unit(r, 0.25f, 4.0f));
        ccl_status check = ccl_texgen_detail_shape_settings_check(&s, &field);
        FZ_CHECK((check == CCL_OK) == (field == NULL), "status %d but field %s", (int)check, field ? field : "NULL");
        run(r, check, s.size, 3, 3, 8, 0.0f, 1.0f, gen_detail, &s, &buf, &n);
        if (buf) {
            int32_t ix = texel_coord(r), iy = texel_coord(r), iz = texel_coord(r);
            float t[3];
            ccl_texgen_detail_shape_texel(ix, iy, iz, s.size, s.seed, s.worley_cells, s.worley_weights[0],
                                          s.worley_weights[1], s.worley_weights[2], s.gamma, &t[0], &t[1], &t[2]);
            uint32_t m = (uint32_t)s.size - 1u;
            size_t at = ((((size_t)((uint32_t)iz & m) * (size_t)s.size) + ((uint32_t)iy & m)) * (size_t)s.size +
                         ((uint32_t)ix & m)) * 3;
            FZ_CHECK(memcmp(t, buf + at, sizeof t) == 0, "texel (%d, %d, %d) differs from the texture", ix, iy, iz);
        }
        break;
    }
    case 2: {
        ccl_curl_noise_settings s = ccl_texgen_curl_noise_settings_default();
        s.size = fz_size(r);
        s.seed = fz_u32(r);
        s.frequency = maybe_i32(r, fz_range(r, 1, 8));
        s.fd_step = maybe_float(r, s.fd_step);
        ccl_status check = ccl_texgen_curl_noise_settings_check(&s, &field);
        FZ_CHECK((check == CCL_OK) == (field == NULL), "status %d but field %s", (int)check, field ? field : "NULL");
        run(r, check, s.size, 2, 2, 16, 1.0f, 0.0f, gen_curl, &s, &buf, &n);
        break;
    }
    default: {
        ccl_weather_map_settings s = ccl_texgen_weather_map_settings_default();
        s.size = fz_size(r);
        s.seed = fz_u32(r);
        s.perlin_frequency = maybe_i32(r, fz_range(r, 1, 8));
        s.perlin_octaves = maybe_i32(r, fz_range(r, 1, 4));
        s.perlin_contrast = maybe_float(r, s.perlin_contrast);
        s.worley_cells = maybe_i32(r, fz_range(r, 1, 8));
        s.worley_octaves = maybe_i32(r, fz_range(r, 1, 3));
        s.combination = (ccl_perlin_worley_mode)maybe_i32(r, fz_range(r, 0, 4));
        s.coverage = maybe_float(r, fz_unit(r, 0.0f, 1.0f));
        s.precipitation = maybe_float(r, fz_unit(r, 0.0f, 1.0f));
        s.cloud_type = maybe_float(r, fz_unit(r, 0.0f, 1.0f));
        s.cloud_type_variation = maybe_float(r, fz_unit(r, 0.0f, 1.0f));
        ccl_status check = ccl_texgen_weather_map_settings_check(&s, &field);
        FZ_CHECK((check == CCL_OK) == (field == NULL), "status %d but field %s", (int)check, field ? field : "NULL");
        run(r, check, s.size, 2, 4, 16, 0.0f, 1.0f, gen_weather, &s, &buf, &n);
        break;
    }
    }
    free(buf);
    /* NULL settings */
    FZ_CHECK(ccl_texgen_base_shape_settings_check(NULL, &field) == CCL_EINVAL && field && !strcmp(field, "s"),
             "NULL settings accepted");
    return 0;
}
