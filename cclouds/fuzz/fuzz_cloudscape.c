/* Fuzz harness: ccl_cloudscape_check, ccl_cloudscape_pixel and ccl_cloudscape_render (cclouds/cloudscape.h).
 * Default parameters with a few fields overwritten by decoded values (NaN, Inf, huge, any int), tiny textures
 * (edges 4 or 8 with values in [0, 1], or invalid edges -1, 0, 3 with a buffer of 8^3 RGBA so that an accepted
 * invalid edge could not read out of bounds unseen by the check), a gradient or Preetham sky with a fuzzed sun and
 * a look-at camera; the sky's gradient colours and Preetham exposure fuzzed too (findings N1, N2: the check bounds
 * a gradient colour by CCL_SKY_GRADIENT_MAX_COLOUR and the thesis variant's exposure). Contract: check gives CCL_OK or CCL_EINVAL with a field name; after CCL_OK one pixel is finite
 * and >= 0, and a 1..3 x 1..3 render gives CCL_OK with values in [0, 1]; render returns CCL_EINVAL exactly when the
 * check fails, a size is < 1, frame < 0 or out_len is wrong. Views with more than 2 x 256 samples per ray are skipped to keep
 * one input within milliseconds. */
#include "cclouds/cloudscape.h"
#include "fuzz.h"

#define P ccl_cloudscape_params
static const fz_field fields[] = {
    FZ_V3(P, layer.centre), FZ_F(P, layer.r_earth), FZ_F(P, layer.r_inner), FZ_F(P, layer.r_outer),
    FZ_F(P, base_scale_km), FZ_F(P, detail_scale_km), FZ_F(P, weather_scale_km), FZ_F(P, curl_scale_km),
    FZ_F(P, curl_strength_km), FZ_F(P, weather_offset[0]), FZ_F(P, weather_offset[1]), FZ_F(P, detail_offset[0]),
    FZ_F(P, detail_offset[1]), FZ_F(P, detail_offset[2]), FZ_F(P, sigma), FZ_F(P, sigma_light),
    FZ_F(P, absorption_base), FZ_F(P, absorption_precip), FZ_F(P, g), FZ_F(P, sun_colour[0]), FZ_F(P, sun_colour[2]),
    FZ_F(P, ambient_bottom[1]), FZ_F(P, ambient_top[0]), FZ_I(P, samples_min), FZ_I(P, samples_max),
    FZ_I(P, adaptive_samples), FZ_I(P, early_exit), FZ_F(P, exit_eps), FZ_F(P, light_step_km),
    FZ_F(P, light_cone_angle), FZ_F(P, light_far_factor), FZ_I(P, light_detail), FZ_I(P, jitter_mode),
    FZ_F(P, jitter_amount), FZ_I(P, gradient_clamp), FZ_I(P, detail_direction), FZ_F(P, ground_colour[1]),
    FZ_I(P, coverage_threshold), FZ_I(P, beer), FZ_I(P, powder), FZ_I(P, exit_fill), FZ_F(P, light_interp)};
#undef P

static float *texture(fz_reader *r, int *edge, int dims) {
    static const int edges[] = {4, 8, 4, 8, 4, -1, 0, 3};
    *edge = edges[fz_u8(r) % 8];
    size_t n = (size_t)8 * 8 * (dims == 3 ? 8 : 1) * 4;
    float *t = malloc(n * sizeof(float));
    uint32_t h = fz_u32(r) | 1u;
    for (size_t i = 0; i < n; ++i) { /* xorshift values in [0, 1] */
        h ^= h << 13;
        h ^= h >> 17;
        h ^= h << 5;
        t[i] = (float)(h >> 8) / 16777215.0f;
    }
    return t;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    ccl_cloudscape_params p;
    ccl_cloudscape_params_default(&p);
    /* small sample counts by default (speed) */
    p.samples_min = fz_range(r, 1, 16);
    p.samples_max = p.samples_min + fz_range(r, 0, 16);
    fz_mutate(r, &p, fields, sizeof fields / sizeof fields[0], 4);

    ccl_cloud_textures t;
    memset(&t, 0, sizeof t);
    float *base = texture(r, &t.base_size, 3), *detail = texture(r, &t.detail_size, 3);
    float *curl = texture(r, &t.curl_size, 2), *weather = texture(r, &t.weather_size, 2);
    t.base = base;
    t.detail = detail;
    t.curl = curl;
    t.weather = weather;
    if (fz_u8(r) == 255) t.weather = NULL;
    /* mip chains for the level of detail, when the edges allow them */
    float *base_mips = NULL, *detail_mips = NULL;
    if (fz_u8(r) & 1u) {
        size_t nb = ccl_cloudscape_mip3_len(t.base_size), nd = ccl_cloudscape_mip3_len(t.detail_size);
        if (nb > 0 && nd > 0) {
            base_mips = malloc(nb * sizeof(float));
            detail_mips = malloc(nd * sizeof(float));
            assert(base_mips && detail_mips);
            assert(ccl_cloudscape_mip3(base, t.base_size, base_mips, nb) == CCL_OK);
            assert(ccl_cloudscape_mip3(detail, t.detail_size, detail_mips, nd) == CCL_OK);
            t.base_mips = base_mips;
            t.detail_mips = detail_mips;
        }
    }

    ccl_cloudscape_sky sky;
    memset(&sky, 0, sizeof sky);
    sky.kind = fz_u8(r) < 250 ? (int)(fz_u8(r) % 2) : fz_i32(r);
    float elev = fz_u8(r) < 200 ? fz_unit(r, 0.0f, 90.0f) : fz_unit(r, -90.0f, 90.0f); /* asserted domain */
    float az = fz_unit(r, -360.0f, 360.0f);
    ccl_vec3 s = ccl_sky_sun_direction(elev, az);
    sky.sun[0] = s.x;
    sky.sun[1] = s.y;
    sky.sun[2] = s.z;
    if (fz_u8(r) < 16) sky.sun[fz_u8(r) % 3] = fz_float(r);
    ccl_sky_gradient_defaults(&sky.gradient);
    if (fz_u8(r) < 32) { /* a fuzzed gradient colour: the check bounds them (finding N2) */
        float *cols = fz_bool(r) ? sky.gradient.horizon : (fz_bool(r) ? sky.gradient.zenith : sky.gradient.sun);
        cols[fz_u8(r) % 3] = fz_u8(r) < 64 ? CCL_SKY_GRADIENT_MAX_COLOUR : fz_float(r);
    }
    {
        /* the exposure: the documented 0.1, any value of the init's domain (> 0), or the thesis bound (N1) */
        const uint8_t k = fz_u8(r);
        const float exposure = k < 160 ? 0.1f : (k < 200 ? CCL_CLOUDSCAPE_MAX_THESIS_EXPOSURE : fz_unit(r, 0.0f, 10.0f));
        if (ccl_sky_preetham_init(fz_unit(r, 2.0f, 10.0f), (90.0f - fz_unit(r, 0.0f, 90.0f)) * 0.017453292f, exposure,
                                  (ccl_variant)(fz_u8(r) % 2), &sky.preetham) != CCL_OK)
            ccl_sky_preetham_init(2.5f, 0.5f, 0.1f, CCL_VARIANT_CORRECTED, &sky.preetham);
    }

    const char *field = "unset";
    ccl_status st = ccl_cloudscape_check(&p, &t, &sky, &field);
    FZ_CHECK(st == CCL_OK || st == CCL_EINVAL, "check status %d", (int)st);
    FZ_CHECK((st == CCL_OK) == (field == NULL), "status %d, field %s", (int)st, field ? field : "NULL");
    if (st == CCL_OK) {
        FZ_CHECK(t.base_size == 4 || t.base_size == 8, "base_size %d accepted", t.base_size);
        FZ_CHECK(t.detail_size == 4 || t.detail_size == 8, "detail_size %d accepted", t.detail_size);
        FZ_CHECK(t.curl_size == 4 || t.curl_size == 8, "curl_size %d accepted", t.curl_size);
        FZ_CHECK(t.weather_size == 4 || t.weather_size == 8, "weather_size %d accepted", t.weather_size);
        FZ_CHECK(t.weather != NULL, "NULL texture accepted");
    }
    FZ_CHECK(ccl_cloudscape_check(NULL, &t, &sky, NULL) == CCL_EINVAL, "NULL params accepted");

    ccl_camera cam;
    ccl_vec3 eye = {fz_unit(r, -10.0f, 10.0f), fz_u8(r) < 200 ? fz_unit(r, 0.0f, 6.0f) : fz_float(r),
                    fz_unit(r, -10.0f, 10.0f)};
    ccl_vec3 target = {eye.x + fz_unit(r, -1.0f, 1.0f), eye.y + fz_unit(r, -1.0f, 1.0f),
                       eye.z + fz_unit(r, -1.0f, 1.0f)};
    ccl_vec3 up = {0.0f, 1.0f, 0.0f};
    int have_cam = ccl_camera_look_at(eye, target, up, fz_unit(r, 0.1f, 3.0f), fz_unit(r, 0.25f, 4.0f), 0.01f,
                                      100.0f, &cam) == CCL_OK;
    int width = fz_range(r, -1, 3), height = fz_range(r, -1, 3), frame = fz_i32(r);
    int heavy = p.samples_max > 256;
    if (have_cam && st == CCL_OK && !heavy) {
        float rgb[3];
        ccl_cloudscape_pixel(&p, &t, &sky, &cam, fz_range(r, 0, 63), fz_range(r, 0, 63), 64, 64, frame, rgb);
        FZ_CHECK(fz_all_finite(rgb, 3), "pixel not finite");
    }
    if (have_cam && !heavy) {
        float out[3 * 3 * 3 + 1];
        out[27] = 4242.0f;
        size_t n = width > 0 && height > 0 ? (size_t)width * (size_t)height * 3 : 0;
        size_t len = fz_u8(r) < 230 ? n : (size_t)fz_range(r, 0, 27);
        ccl_status rs = ccl_cloudscape_render(&p, &t, &sky, &cam, width, height, frame, out, len);
        int valid = st == CCL_OK && width >= 1 && height >= 1 && frame >= 0 && len == n;
        FZ_CHECK((rs == CCL_OK) == valid, "render status %d (check %d, %d x %d, len %zu of %zu)", (int)rs, (int)st,
                 width, height, len, n);
        if (rs == CCL_OK) FZ_CHECK(fz_all_in(out, n, 0.0f, 1.0f), "render value outside [0, 1]");
        FZ_CHECK(out[27] == 4242.0f, "render wrote past out_len");
    }
    free(base);
    free(detail);
    free(curl);
    free(weather);
    free(base_mips);
    free(detail_mips);
    return 0;
}
