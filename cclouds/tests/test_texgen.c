/* C unit tests of cclouds/texgen.h: gamma (vc-4.6), settings validation (vc-A13), the base (vc-A9) and detail
 * (vc-A10) textures rebuilt from the noise primitives, periodicity, the curl (vc-A11) and weather (vc-A12) textures,
 * and the wrap-around trilinear sampler against a double-precision reference. */
#include <stdlib.h>
#include <string.h>

#include "cclouds/texgen.h"
#include "ccl_test.h"

static const char *field_of_base(ccl_base_shape_settings s)
{
    const char *f = "unset";
    ccl_status st = ccl_texgen_base_shape_settings_check(&s, &f);
    return st == CCL_OK ? "" : f;
}

static void test_texgen_gamma_closed_form(void)
{
    CCL_CHECK_REL(ccl_texgen_gamma(0.25f, 0.5f), 0.0625, 1e-6);
    CCL_CHECK_REL(ccl_texgen_gamma(0.25f, 2.0f), 0.5, 1e-6);
    CCL_CHECK_REL(ccl_texgen_gamma(0.7f, 1.0f), 0.7f, 0.0); /* identity at gamma = 1 */
    CCL_CHECK(ccl_texgen_gamma(0.0f, 2.2f) == 0.0f);
    CCL_CHECK(ccl_texgen_gamma(1.0f, 2.2f) == 1.0f);
    CCL_CHECK(ccl_texgen_gamma(0.3f, 2.2f) > 0.3f); /* gamma > 1 brightens */
    CCL_CHECK(ccl_texgen_gamma(0.3f, 0.5f) < 0.3f);
    CCL_CHECK(isnan(ccl_texgen_gamma((float)NAN, 2.0f)));
}

static void test_texgen_settings_defaults_and_check(void)
{
    ccl_base_shape_settings b = ccl_texgen_base_shape_settings_default(), bad;
    ccl_detail_shape_settings d = ccl_texgen_detail_shape_settings_default();
    ccl_curl_noise_settings c = ccl_texgen_curl_noise_settings_default();
    ccl_weather_map_settings w = ccl_texgen_weather_map_settings_default();
    const char *f = "unset";
    CCL_CHECK(b.size == 128 && b.perlin_octaves == 3 && b.perlin_frequency == 8 && b.worley_cells == 4);
    CCL_CHECK(b.worley_weights[0] == 0.625f && b.worley_weights[1] == 0.25f && b.worley_weights[2] == 0.125f);
    CCL_CHECK(b.combination == CCL_PW_THESIS && b.gamma == 1.0f && b.seed == 0u);
    CCL_CHECK(d.size == 32 && d.worley_cells == 2 && d.gamma == 1.0f);
    CCL_CHECK(c.size == 128 && c.frequency == 4 && c.fd_step == 1.0f / 256.0f);
    CCL_CHECK(w.size == 512 && w.coverage == 0.5f && w.cloud_type == 0.75f);
    CCL_CHECK(ccl_texgen_base_shape_settings_check(&b, &f) == CCL_OK && f == NULL);
    CCL_CHECK(ccl_texgen_detail_shape_settings_check(&d, NULL) == CCL_OK);
    CCL_CHECK(ccl_texgen_curl_noise_settings_check(&c, NULL) == CCL_OK);
    CCL_CHECK(ccl_texgen_weather_map_settings_check(&w, NULL) == CCL_OK);
    CCL_CHECK(ccl_texgen_base_shape_settings_check(NULL, &f) == CCL_EINVAL && strcmp(f, "s") == 0);

    bad = b; bad.size = 96;
    CCL_CHECK(strcmp(field_of_base(bad), "size") == 0);
    bad = b; bad.size = 2;
    CCL_CHECK(strcmp(field_of_base(bad), "size") == 0);
    bad = b; bad.size = 1024;
    CCL_CHECK(strcmp(field_of_base(bad), "size") == 0);
    bad = b; bad.perlin_octaves = 0;
    CCL_CHECK(strcmp(field_of_base(bad), "perlin_octaves") == 0);
    bad = b; bad.perlin_frequency = 0;
    CCL_CHECK(strcmp(field_of_base(bad), "perlin_frequency") == 0);
    bad = b; bad.perlin_frequency = 1024; bad.perlin_octaves = 4; /* 1024 * 8 > 4096 */
    CCL_CHECK(strcmp(field_of_base(bad), "perlin_frequency") == 0);
    bad = b; bad.worley_cells = 513;
    CCL_CHECK(strcmp(field_of_base(bad), "worley_cells") == 0);
    bad = b; bad.worley_weights[1] = (float)NAN;
    CCL_CHECK(strcmp(field_of_base(bad), "worley_weights") == 0);
    bad = b; bad.worley_weights[2] = -0.1f;
    CCL_CHECK(strcmp(field_of_base(bad), "worley_weights") == 0);
    bad = b; bad.worley_weights[0] = 0.0f;
    CCL_CHECK(strcmp(field_of_base(bad), "worley_weights") == 0);
    bad = b; bad.combination = (ccl_perlin_worley_mode)7;
    CCL_CHECK(strcmp(field_of_base(bad), "combination") == 0);
    bad = b; bad.gamma = 0.0f;
    CCL_CHECK(strcmp(field_of_base(bad), "gamma") == 0);
    bad = b; bad.gamma = (float)INFINITY;
    CCL_CHECK(strcmp(field_of_base(bad), "gamma") == 0);

    c.fd_step = 0.0f;
    CCL_CHECK(ccl_texgen_curl_noise_settings_check(&c, &f) == CCL_EINVAL && strcmp(f, "fd_step") == 0);
    w.coverage = 1.5f;
    CCL_CHECK(ccl_texgen_weather_map_settings_check(&w, &f) == CCL_EINVAL && strcmp(f, "coverage") == 0);
    w = ccl_texgen_weather_map_settings_default();
    w.cloud_type = (float)NAN;
    CCL_CHECK(ccl_texgen_weather_map_settings_check(&w, &f) == CCL_EINVAL && strcmp(f, "cloud_type") == 0);
    d.gamma = -1.0f;
    CCL_CHECK(ccl_texgen_detail_shape_settings_check(&d, &f) == CCL_EINVAL && strcmp(f, "gamma") == 0);
}

static void test_texgen_whole_texture_rejects_bad_buffers(void)
{
    ccl_base_shape_settings b = ccl_texgen_base_shape_settings_default();
    ccl_detail_shape_settings d = ccl_texgen_detail_shape_settings_default();
    float buf[4 * 4 * 4 * 4];
    b.size = 4;
    d.size = 4;
    CCL_CHECK(ccl_texgen_base_shape(&b, buf, 4 * 4 * 4 * 4 - 1) == CCL_EINVAL);
    CCL_CHECK(ccl_texgen_base_shape(&b, NULL, 4 * 4 * 4 * 4) == CCL_EINVAL);
    CCL_CHECK(ccl_texgen_base_shape(NULL, buf, 4 * 4 * 4 * 4) == CCL_EINVAL);
    CCL_CHECK(ccl_texgen_detail_shape(&d, buf, 4 * 4 * 4 * 4) == CCL_EINVAL); /* RGB: 4^3 * 3 expected */
    b.gamma = -1.0f;
    memset(buf, 0, sizeof buf);
    CCL_CHECK(ccl_texgen_base_shape(&b, buf, 4 * 4 * 4 * 4) == CCL_EINVAL);
    CCL_CHECK(buf[0] == 0.0f); /* nothing written */
    b.gamma = 1.0f;
    CCL_CHECK(ccl_texgen_base_shape(&b, buf, 4 * 4 * 4 * 4) == CCL_OK);
    CCL_CHECK(ccl_texgen_detail_shape(&d, buf, 4 * 4 * 4 * 3) == CCL_OK);
}

/* The base texture rebuilt from the noise primitives with the formulas of the header comment. */
static void test_texgen_base_shape_matches_noise_composition(void)
{
    ccl_base_shape_settings s = ccl_texgen_base_shape_settings_default();
    const int n = 8;
    float *tex = malloc(sizeof(float) * 8 * 8 * 8 * 4);
    int ix, iy, iz, bad_range = 0;
    double max_err = 0.0;
    s.size = n;
    s.seed = 7u;
    s.perlin_frequency = 2;
    s.worley_cells = 1;
    CCL_CHECK(tex != NULL);
    if (!tex) return;
    CCL_CHECK(ccl_texgen_base_shape(&s, tex, (size_t)n * (size_t)n * (size_t)n * 4) == CCL_OK);
    for (iz = 0; iz < n; ++iz)
        for (iy = 0; iy < n; ++iy)
            for (ix = 0; ix < n; ++ix) {
                const float *t = tex + (((size_t)iz * (size_t)n + (size_t)iy) * (size_t)n + (size_t)ix) * 4;
                double u = (ix + 0.5) / n, v = (iy + 0.5) / n, w = (iz + 0.5) / n, W[4], g, b, a, p, r;
                int j, c;
                for (j = 0; j < 4; ++j)
                    W[j] = (double)ccl_noise_worley3((float)u, (float)v, (float)w, 1 << j, 7u + (uint32_t)j,
                                                     CCL_WORLEY_EUCLIDEAN, 1);
                g = 0.625 * W[0] + 0.25 * W[1] + 0.125 * W[2];
                b = 0.625 * W[1] + 0.25 * W[2] + 0.125 * W[3];
                a = (0.625 * W[2] + 0.25 * W[3]) / 0.875;
                p = 0.5 * (double)ccl_noise_fbm_perlin3((float)u, (float)v, (float)w, 3, 2.0f, 7u, 2) + 0.5;
                p = p < 0 ? 0 : (p > 1 ? 1 : p);
                r = (g + p * (1.0 - g)) * (g + p * (1.0 - g)); /* remap(P, 0, 1, W, 1)^2 */
                max_err = fmax(max_err, fabs((double)t[0] - r));
                max_err = fmax(max_err, fabs((double)t[1] - g));
                max_err = fmax(max_err, fabs((double)t[2] - b));
                max_err = fmax(max_err, fabs((double)t[3] - a));
                for (c = 0; c < 4; ++c)
                    if (!(t[c] >= 0.0f && t[c] <= 1.0f)) ++bad_range;
            }
    /* float32 sums of three products in [0, 1] and one square vs double: a few ulp of 1 */
    CCL_CHECK(max_err < 1e-6);
    CCL_CHECK(bad_range == 0);
    free(tex);
}

static void test_texgen_texel_functions_match_whole_texture_and_are_periodic(void)
{
    ccl_base_shape_settings s = ccl_texgen_base_shape_settings_default();
    ccl_detail_shape_settings d = ccl_texgen_detail_shape_settings_default();
    float *tb = malloc(sizeof(float) * 8 * 8 * 8 * 4), *td = malloc(sizeof(float) * 8 * 8 * 8 * 3);
    int i, mismatches = 0, periodic_fail = 0;
    s.size = 8;
    s.seed = 12345u;
    s.perlin_frequency = 4;
    s.worley_cells = 2;
    s.gamma = 1.7f;
    d.size = 8;
    d.seed = 99u;
    d.gamma = 0.8f;
    CCL_CHECK(tb != NULL && td != NULL);
    if (!tb || !td) { free(tb); free(td); return; }
    CCL_CHECK(ccl_texgen_base_shape(&s, tb, 8 * 8 * 8 * 4) == CCL_OK);
    CCL_CHECK(ccl_texgen_detail_shape(&d, td, 8 * 8 * 8 * 3) == CCL_OK);
    for (i = 0; i < 8 * 8 * 8; i += 7) {
        int ix = i % 8, iy = (i / 8) % 8, iz = i / 64;
        float r, g, b, a, r2, g2, b2, a2;
        ccl_texgen_base_shape_texel(ix, iy, iz, 8, 12345u, 3, 4, 2, 0.625f, 0.25f, 0.125f, 1.7f, CCL_PW_THESIS,
                                    &r, &g, &b, &a);
        if (r != tb[i * 4] || g != tb[i * 4 + 1] || b != tb[i * 4 + 2] || a != tb[i * 4 + 3]) ++mismatches;
        /* periodic: texel (ix + 8, iy - 8, iz + 16) is texel (ix, iy, iz) bit for bit */
        ccl_texgen_base_shape_texel(ix + 8, iy - 8, iz + 16, 8, 12345u, 3, 4, 2, 0.625f, 0.25f, 0.125f, 1.7f,
                                    CCL_PW_THESIS, &r2, &g2, &b2, &a2);
        if (r2 != r || g2 != g || b2 != b || a2 != a) ++periodic_fail;
        ccl_texgen_detail_shape_texel(ix, iy, iz, 8, 99u, 2, 0.625f, 0.25f, 0.125f, 0.8f, &r, &g, &b);
        if (r != td[i * 3] || g != td[i * 3 + 1] || b != td[i * 3 + 2]) ++mismatches;
        ccl_texgen_detail_shape_texel(ix - 8, iy + 8, iz - 8, 8, 99u, 2, 0.625f, 0.25f, 0.125f, 0.8f, &r2, &g2, &b2);
        if (r2 != r || g2 != g || b2 != b) ++periodic_fail;
    }
    CCL_CHECK(mismatches == 0);
    CCL_CHECK(periodic_fail == 0);
    free(tb);
    free(td);
}

/* With weights 1, 1/2, 1/4 the G channel is the noise module's Worley fBm of three octaves (same layers, seeds). */
static void test_texgen_detail_channel_is_worley_fbm_for_halving_weights(void)
{
    int ix, iy, iz;
    double max_err = 0.0;
    for (iz = 0; iz < 4; ++iz)
        for (iy = 0; iy < 4; ++iy)
            for (ix = 0; ix < 4; ++ix) {
                float r, g, b;
                float u = ((float)ix + 0.5f) / 4.0f, v = ((float)iy + 0.5f) / 4.0f, w = ((float)iz + 0.5f) / 4.0f;
                ccl_texgen_detail_shape_texel(ix, iy, iz, 4, 3u, 2, 1.0f, 0.5f, 0.25f, 1.0f, &r, &g, &b);
                float wr = ccl_noise_fbm_worley3(u, v, w, 3, 2, 3u, CCL_WORLEY_EUCLIDEAN, 1);
                float wg = ccl_noise_fbm_worley3(u, v, w, 3, 4, 4u, CCL_WORLEY_EUCLIDEAN, 1);
                max_err = fmax(max_err, fabs((double)(r - wr)));
                max_err = fmax(max_err, fabs((double)(g - wg)));
            }
    CCL_CHECK(max_err <= 2.4e-7); /* same float32 sum, possibly a different rounding of the final division */
}

static void test_texgen_curl_noise_is_divergence_free_and_tileable(void)
{
    ccl_curl_noise_settings s = ccl_texgen_curl_noise_settings_default();
    const int n = 32;
    float *t = malloc(sizeof(float) * 32 * 32 * 2);
    int ix, iy;
    double div_sum = 0.0, grad_sum = 0.0, seam = 0.0, interior = 0.0;
    s.size = n;
    s.frequency = 2;
    CCL_CHECK(t != NULL);
    if (!t) return;
    CCL_CHECK(ccl_texgen_curl_noise(&s, t, (size_t)n * (size_t)n * 2) == CCL_OK);
    for (iy = 0; iy < n; ++iy)
        for (ix = 0; ix < n; ++ix) {
            int xp = (ix + 1) % n, xm = (ix + n - 1) % n, yp = (iy + 1) % n, ym = (iy + n - 1) % n;
            double dvx = (double)(t[(iy * n + xp) * 2] - t[(iy * n + xm) * 2]);
            double dvy = (double)(t[(yp * n + ix) * 2 + 1] - t[(ym * n + ix) * 2 + 1]);
            double dvx_dy = (double)(t[(yp * n + ix) * 2] - t[(ym * n + ix) * 2]);
            div_sum += fabs(dvx + dvy);
            grad_sum += fabs(dvx) + fabs(dvx_dy);
            if (ix == n - 1) seam = fmax(seam, fabs((double)(t[(iy * n) * 2] - t[(iy * n + ix) * 2])));
            else interior = fmax(interior, fabs((double)(t[(iy * n + ix + 1) * 2] - t[(iy * n + ix) * 2])));
        }
    /* discrete divergence (texel central differences of a smooth divergence-free field): O(h^2), far below the
     * derivatives themselves */
    CCL_CHECK(div_sum < 0.05 * grad_sum);
    CCL_CHECK(seam <= interior); /* the wrap-around step is an ordinary neighbour step */
    free(t);
}

static void test_texgen_weather_map_channels(void)
{
    ccl_weather_map_settings s = ccl_texgen_weather_map_settings_default();
    const int n = 32;
    float *t = malloc(sizeof(float) * 32 * 32 * 4), *t2 = malloc(sizeof(float) * 32 * 32 * 4);
    int i, bad = 0, monotone_fail = 0;
    double mean_lo = 0.0, mean_hi = 0.0;
    CCL_CHECK(t != NULL && t2 != NULL);
    if (!t || !t2) { free(t); free(t2); return; }
    s.size = n;
    s.coverage = 0.0f;
    CCL_CHECK(ccl_texgen_weather_map(&s, t, (size_t)n * (size_t)n * 4) == CCL_OK);
    for (i = 0; i < n * n; ++i)
        if (t[i * 4] != 0.0f || t[i * 4 + 3] != 0.0f) ++bad; /* coverage 0 = clear sky; alpha free (0) */
    CCL_CHECK(bad == 0);
    s.coverage = 0.4f;
    CCL_CHECK(ccl_texgen_weather_map(&s, t, (size_t)n * (size_t)n * 4) == CCL_OK);
    s.coverage = 0.7f;
    CCL_CHECK(ccl_texgen_weather_map(&s, t2, (size_t)n * (size_t)n * 4) == CCL_OK);
    for (i = 0; i < n * n; ++i) {
        int c;
        for (c = 0; c < 4; ++c)
            if (!(t2[i * 4 + c] >= 0.0f && t2[i * 4 + c] <= 1.0f)) ++bad;
        if (t2[i * 4] < t[i * 4]) ++monotone_fail;
        mean_lo += (double)t[i * 4];
        mean_hi += (double)t2[i * 4];
        /* B in [cloud_type - variation, cloud_type + variation] */
        if (t2[i * 4 + 2] < 0.5f || t2[i * 4 + 2] > 1.0f) ++bad;
        if (t2[i * 4 + 1] != t[i * 4 + 1] || t2[i * 4 + 2] != t[i * 4 + 2]) ++bad; /* coverage touches R only */
    }
    CCL_CHECK(bad == 0);
    CCL_CHECK(monotone_fail == 0);
    CCL_CHECK(mean_hi > mean_lo);
    free(t);
    free(t2);
}

/* Trilinear reference in double with the usual floor(p * size - 0.5) formulation. */
static double ref_trilinear(const float *tex, int n, double px, double py, double pz, int c)
{
    double x = px * n - 0.5, y = py * n - 0.5, z = pz * n - 0.5;
    double fx = floor(x), fy = floor(y), fz = floor(z), tx = x - fx, ty = y - fy, tz = z - fz, acc = 0.0;
    int dx, dy, dz;
    for (dz = 0; dz < 2; ++dz)
        for (dy = 0; dy < 2; ++dy)
            for (dx = 0; dx < 2; ++dx) {
                int ix = (((int)fx + dx) % n + n) % n, iy = (((int)fy + dy) % n + n) % n;
                int iz = (((int)fz + dz) % n + n) % n;
                double wgt = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) * (dz ? tz : 1 - tz);
                size_t at = (((size_t)iz * (size_t)n + (size_t)iy) * (size_t)n + (size_t)ix) * 4 + (size_t)c;
                acc += wgt * (double)tex[at];
            }
    return acc;
}

static void test_texgen_sample_trilinear_wrap(void)
{
    const int n = 8;
    float tex[8 * 8 * 8 * 4];
    int i, exact_fail = 0, shift_fail = 0;
    double max_err = 0.0;
    uint32_t state = 12345u;
    for (i = 0; i < n * n * n * 4; ++i) {
        state = ccl_hash_pcg(state);
        tex[i] = (float)(state >> 8) / 16777216.0f;
    }
    /* at a texel centre the sample is the texel */
    for (i = 0; i < n * n * n; i += 5) {
        int ix = i % n, iy = (i / n) % n, iz = i / (n * n);
        float r, g, b, a;
        ccl_texgen_sample_trilinear_wrap(tex, n - 1, ((float)ix + 0.5f) / (float)n, ((float)iy + 0.5f) / (float)n,
                                         ((float)iz + 0.5f) / (float)n, &r, &g, &b, &a);
        if (r != tex[i * 4] || g != tex[i * 4 + 1] || b != tex[i * 4 + 2] || a != tex[i * 4 + 3]) ++exact_fail;
    }
    CCL_CHECK(exact_fail == 0);
    for (i = 0; i < 500; ++i) {
        float p[3], o[4], o2[4];
        int k;
        for (k = 0; k < 3; ++k) {
            state = ccl_hash_pcg(state);
            p[k] = 1.0f + (float)(state >> 8) / 16777216.0f; /* [1, 2): p - 1 is exact */
        }
        ccl_texgen_sample_trilinear_wrap(tex, n - 1, p[0], p[1], p[2], &o[0], &o[1], &o[2], &o[3]);
        ccl_texgen_sample_trilinear_wrap(tex, n - 1, p[0] - 1.0f, p[1] - 1.0f, p[2] - 3.0f, &o2[0], &o2[1], &o2[2],
                                         &o2[3]);
        for (k = 0; k < 4; ++k) {
            if (o[k] != o2[k]) ++shift_fail;
            double ref = ref_trilinear(tex, n, (double)p[0], (double)p[1], (double)p[2], k);
            max_err = fmax(max_err, fabs((double)o[k] - ref));
        }
    }
    CCL_CHECK(shift_fail == 0);
    /* 7 float32 lerps of values in [0, 1] with weights rounded once: a few ulp of 1 */
    CCL_CHECK(max_err < 1e-6);
}

int main(void)
{
    CCL_RUN(test_texgen_gamma_closed_form);
    CCL_RUN(test_texgen_settings_defaults_and_check);
    CCL_RUN(test_texgen_whole_texture_rejects_bad_buffers);
    CCL_RUN(test_texgen_base_shape_matches_noise_composition);
    CCL_RUN(test_texgen_texel_functions_match_whole_texture_and_are_periodic);
    CCL_RUN(test_texgen_detail_channel_is_worley_fbm_for_halving_weights);
    CCL_RUN(test_texgen_curl_noise_is_divergence_free_and_tileable);
    CCL_RUN(test_texgen_weather_map_channels);
    CCL_RUN(test_texgen_sample_trilinear_wrap);
    return ccl_test_report();
}
