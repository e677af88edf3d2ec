/* Noise-texture generator, vc §2.3.3 / §4.3.1. See cclouds/texgen.h for the conventions and the choices made. */
#include "cclouds/texgen.h"
#include "internal.h"

/* ---- small helpers (mirrored in pywarp/kernels/texgen.py) ------------------------------------------------------- */

/* Texture coordinate of the centre of texel i: (i mod size + 0.5) / size, exact for power-of-two sizes. i is always
 * reduced modulo size first (size is a power of two; the texture is periodic, so the texel is the same one): u then
 * lies in (0, 1) and u * frequency is the same float for i and i + k size, so the single-texel functions equal the
 * texture's texel bit for bit for any int32 coordinate and any frequency or cell count (not only powers of two). */
static float texcoord(int32_t i, int32_t size)
{
    i = (int32_t)((uint32_t)i & ((uint32_t)size - 1u));
    return ((float)i + 0.5f) / (float)size;
}

/* The four inverse-Worley layers: worley_cells * 2^j cells per texture, seed + j (vc-A6 octave rule). */
static void worley_layers(float u, float v, float w, int32_t cells, uint32_t seed, float layers[4])
{
    int32_t j;
    for (j = 0; j < 4; ++j)
        layers[j] = ccl_noise_worley3(u, v, w, cells * (1 << j), seed + (uint32_t)j, CCL_WORLEY_EUCLIDEAN, 1);
}

/* Sliding-window fBm: channel k = sum_{j, k+j <= 3} w_j W_{k+j} / sum w_j, clamped to [0, 1]. */
static void sliding_fbm(const float layers[4], float w0, float w1, float w2, float out[3])
{
    float wt[3];
    int32_t k, j;
    wt[0] = w0;
    wt[1] = w1;
    wt[2] = w2;
    for (k = 0; k < 3; ++k) {
        float num = 0.0f, den = 0.0f;
        for (j = 0; j < 3; ++j) {
            if (k + j <= 3) {
                num += wt[j] * layers[k + j];
                den += wt[j];
            }
        }
        out[k] = clamp01(num / den);
    }
}

/* Perlin fBm of the texture coordinate mapped to [0, 1]: clamp(gain fbm + 0.5, 0, 1); gain 0.5 maps [-1, 1] onto
 * [0, 1]. Period = frequency lattice cells, i.e. one texture. */
static float perlin01(float u, float v, float w, int32_t octaves, int32_t frequency, const uint8_t *perm, float gain)
{
    float p = ccl_noise_fbm_perlin3_perm(u, v, w, octaves, (float)frequency, perm, frequency);
    return clamp01(gain * p + 0.5f);
}

/* Global coverage remap of the weather map: clamp(remap(n, 1 - c, 1, 0, 1), 0, 1) for c > 0, 0 for c <= 0. */
static float coverage_shape(float n, float c)
{
    if (c <= 0.0f) return 0.0f;
    return clamp01((n - (1.0f - c)) / c);
}

static int is_pow2_in(int32_t v, int32_t lo, int32_t hi)
{
    return v >= lo && v <= hi && (v & (v - 1)) == 0;
}

static int in01(float v)
{
    return v >= 0.0f && v <= 1.0f; /* false for NaN */
}

/* lattice frequency * 2^(octaves - 1) within the limit (octaves already checked to be in [1, 8]) */
static int lattice_ok(int32_t base, int32_t octaves)
{
    return base >= 1 && (int64_t)base * ((int64_t)1 << (octaves - 1)) <= CCL_TEXGEN_MAX_LATTICE;
}

static int weights_ok(const float w[3])
{
    int i;
    for (i = 0; i < 3; ++i)
        if (!isfinite(w[i]) || w[i] < 0.0f) return 0;
    return w[0] > 0.0f;
}

static int gamma_ok(float g)
{
    return isfinite(g) && g > 0.0f;
}

static int mode_ok(ccl_perlin_worley_mode m)
{
    return (int)m >= (int)CCL_PW_THESIS && (int)m <= (int)CCL_PW_AVERAGE;
}

static ccl_status fail(const char **out_field, const char *name)
{
    if (out_field) *out_field = name;
    return name ? CCL_EINVAL : CCL_OK;
}

/* ---- gamma (vc-4.6) ---------------------------------------------------------------------------------------------- */

float ccl_texgen_gamma(float c, float gamma)
{
    CCL_REQUIRE(!(gamma <= 0.0f));
    /* vc-4.6: C = C^(1/gamma) */
    return powf(c, 1.0f / gamma);
}

/* ---- settings (vc-A13) ------------------------------------------------------------------------------------------- */

ccl_base_shape_settings ccl_texgen_base_shape_settings_default(void)
{
    ccl_base_shape_settings s;
    s.size = 128;
    s.seed = 0u;
    s.perlin_octaves = 3;
    s.perlin_frequency = 8;
    s.worley_cells = 4;
    s.worley_weights[0] = 0.625f;
    s.worley_weights[1] = 0.25f;
    s.worley_weights[2] = 0.125f;
    s.combination = CCL_PW_THESIS;
    s.gamma = 1.0f;
    return s;
}

ccl_detail_shape_settings ccl_texgen_detail_shape_settings_default(void)
{
    ccl_detail_shape_settings s;
    s.size = 32;
    s.seed = 0u;
    s.worley_cells = 2;
    s.worley_weights[0] = 0.625f;
    s.worley_weights[1] = 0.25f;
    s.worley_weights[2] = 0.125f;
    s.gamma = 1.0f;
    return s;
}

ccl_curl_noise_settings ccl_texgen_curl_noise_settings_default(void)
{
    ccl_curl_noise_settings s;
    s.size = 128;
    s.seed = 0u;
    s.frequency = 4;
    s.fd_step = 1.0f / (float)CCL_NOISE_FD_STEP_INV;
    return s;
}

ccl_weather_map_settings ccl_texgen_weather_map_settings_default(void)
{
    ccl_weather_map_settings s;
    s.size = 512;
    s.seed = 0u;
    s.perlin_frequency = 4;
    s.perlin_octaves = 4;
    s.perlin_contrast = 2.0f;
    s.worley_cells = 4;
    s.worley_octaves = 3;
    s.combination = CCL_PW_THESIS;
    s.coverage = 0.5f;
    s.precipitation = 0.2f;
    s.cloud_type = 0.75f;
    s.cloud_type_variation = 0.25f;
    return s;
}

ccl_status ccl_texgen_base_shape_settings_check(const ccl_base_shape_settings *s, const char **out_field)
{
    if (!s) return fail(out_field, "s");
    if (!is_pow2_in(s->size, CCL_TEXGEN_MIN_SIZE, CCL_TEXGEN_MAX_SIZE_3D)) return fail(out_field, "size");
    if (s->perlin_octaves < 1 || s->perlin_octaves > CCL_TEXGEN_MAX_OCTAVES) return fail(out_field, "perlin_octaves");
    if (!lattice_ok(s->perlin_frequency, s->perlin_octaves)) return fail(out_field, "perlin_frequency");
    if (!lattice_ok(s->worley_cells, 4)) return fail(out_field, "worley_cells");
    if (!weights_ok(s->worley_weights)) return fail(out_field, "worley_weights");
    if (!mode_ok(s->combination)) return fail(out_field, "combination");
    if (!gamma_ok(s->gamma)) return fail(out_field, "gamma");
    return fail(out_field, NULL);
}

ccl_status ccl_texgen_detail_shape_settings_check(const ccl_detail_shape_settings *s, const char **out_field)
{
    if (!s) return fail(out_field, "s");
    if (!is_pow2_in(s->size, CCL_TEXGEN_MIN_SIZE, CCL_TEXGEN_MAX_SIZE_3D)) return fail(out_field, "size");
    if (!lattice_ok(s->worley_cells, 4)) return fail(out_field, "worley_cells");
    if (!weights_ok(s->worley_weights)) return fail(out_field, "worley_weights");
    if (!gamma_ok(s->gamma)) return fail(out_field, "gamma");
    return fail(out_field, NULL);
}

ccl_status ccl_texgen_curl_noise_settings_check(const ccl_curl_noise_settings *s, const char **out_field)
{
    if (!s) return fail(out_field, "s");
    if (!is_pow2_in(s->size, CCL_TEXGEN_MIN_SIZE, CCL_TEXGEN_MAX_SIZE_2D)) return fail(out_field, "size");
    if (!lattice_ok(s->frequency, 1)) return fail(out_field, "frequency");
    if (!(s->fd_step > 0.0f && s->fd_step <= 0.25f)) return fail(out_field, "fd_step");
    return fail(out_field, NULL);
}

ccl_status ccl_texgen_weather_map_settings_check(const ccl_weather_map_settings *s, const char **out_field)
{
    if (!s) return fail(out_field, "s");
    if (!is_pow2_in(s->size, CCL_TEXGEN_MIN_SIZE, CCL_TEXGEN_MAX_SIZE_2D)) return fail(out_field, "size");
    if (s->perlin_octaves < 1 || s->perlin_octaves > CCL_TEXGEN_MAX_OCTAVES) return fail(out_field, "perlin_octaves");
    if (!lattice_ok(s->perlin_frequency, s->perlin_octaves)) return fail(out_field, "perlin_frequency");
    if (!(isfinite(s->perlin_contrast) && s->perlin_contrast > 0.0f)) return fail(out_field, "perlin_contrast");
    if (s->worley_octaves < 1 || s->worley_octaves > CCL_TEXGEN_MAX_OCTAVES) return fail(out_field, "worley_octaves");
    if (!lattice_ok(s->worley_cells, s->worley_octaves)) return fail(out_field, "worley_cells");
    if (!mode_ok(s->combination)) return fail(out_field, "combination");
    if (!in01(s->coverage)) return fail(out_field, "coverage");
    if (!in01(s->precipitation)) return fail(out_field, "precipitation");
    if (!in01(s->cloud_type)) return fail(out_field, "cloud_type");
    if (!in01(s->cloud_type_variation)) return fail(out_field, "cloud_type_variation");
    return fail(out_field, NULL);
}

/* ---- texels ------------------------------------------------------------------------------------------------------ */

static void base_texel(const ccl_base_shape_settings *s, const uint8_t *perm, int32_t ix, int32_t iy, int32_t iz,
                       float *out)
{
    float u = texcoord(ix, s->size), v = texcoord(iy, s->size), w = texcoord(iz, s->size);
    float layers[4], ch[3], p, r;
    worley_layers(u, v, w, s->worley_cells, s->seed, layers);
    sliding_fbm(layers, s->worley_weights[0], s->worley_weights[1], s->worley_weights[2], ch);
    p = perlin01(u, v, w, s->perlin_octaves, s->perlin_frequency, perm, 0.5f);
    r = ccl_noise_perlin_worley(p, ch[0], s->combination); /* vc-A8 */
    out[0] = ccl_texgen_gamma(clamp01(r), s->gamma);         /* vc-4.6 */
    out[1] = ccl_texgen_gamma(ch[0], s->gamma);
    out[2] = ccl_texgen_gamma(ch[1], s->gamma);
    out[3] = ccl_texgen_gamma(ch[2], s->gamma);
}

static void detail_texel(const ccl_detail_shape_settings *s, int32_t ix, int32_t iy, int32_t iz, float *out)
{
    float u = texcoord(ix, s->size), v = texcoord(iy, s->size), w = texcoord(iz, s->size);
    float layers[4], ch[3];
    worley_layers(u, v, w, s->worley_cells, s->seed, layers);
    sliding_fbm(layers, s->worley_weights[0], s->worley_weights[1], s->worley_weights[2], ch);
    out[0] = ccl_texgen_gamma(ch[0], s->gamma);
    out[1] = ccl_texgen_gamma(ch[1], s->gamma);
    out[2] = ccl_texgen_gamma(ch[2], s->gamma);
}

static void curl_texel(const ccl_curl_noise_settings *s, const uint8_t *perm, int32_t ix, int32_t iy, float *out)
{
    float f = (float)s->frequency;
    float x = texcoord(ix, s->size) * f, y = texcoord(iy, s->size) * f;
    ccl_vec2 v = ccl_noise_curl2_perm(x, y, perm, s->frequency, s->fd_step);
    out[0] = v.x;
    out[1] = v.y;
}

static void weather_texel(const ccl_weather_map_settings *s, const uint8_t *perm0, const uint8_t *perm1,
                          const uint8_t *perm2, int32_t ix, int32_t iy, float *out)
{
    float u = texcoord(ix, s->size), v = texcoord(iy, s->size);
    float p, wv, n, p2, p3;
    p = perlin01(u, v, 0.0f, s->perlin_octaves, s->perlin_frequency, perm0, s->perlin_contrast);
    wv = ccl_noise_fbm_worley3(u, v, 0.0f, s->worley_octaves, s->worley_cells, s->seed, CCL_WORLEY_EUCLIDEAN, 1);
    n = ccl_noise_perlin_worley(p, wv, s->combination);
    out[0] = coverage_shape(n, s->coverage);
    p2 = perlin01(u, v, 0.0f, s->perlin_octaves, s->perlin_frequency, perm1, s->perlin_contrast);
    out[1] = coverage_shape(p2, s->precipitation);
    p3 = perlin01(u, v, 0.0f, s->perlin_octaves, s->perlin_frequency, perm2, s->perlin_contrast);
    out[2] = clamp01(s->cloud_type + s->cloud_type_variation * (2.0f * p3 - 1.0f));
    out[3] = 0.0f;
}

void ccl_texgen_base_shape_texel(int32_t ix, int32_t iy, int32_t iz, int32_t size, uint32_t seed,
                                 int32_t perlin_octaves, int32_t perlin_frequency, int32_t worley_cells,
                                 float worley_w0, float worley_w1, float worley_w2, float gamma,
                                 ccl_perlin_worley_mode combination, float *out_r, float *out_g, float *out_b,
                                 float *out_a)
{
    ccl_base_shape_settings s;
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    float out[4];
    s.size = size;
    s.seed = seed;
    s.perlin_octaves = perlin_octaves;
    s.perlin_frequency = perlin_frequency;
    s.worley_cells = worley_cells;
    s.worley_weights[0] = worley_w0;
    s.worley_weights[1] = worley_w1;
    s.worley_weights[2] = worley_w2;
    s.combination = combination;
    s.gamma = gamma;
    CCL_REQUIRE(ccl_texgen_base_shape_settings_check(&s, NULL) == CCL_OK);
    CCL_REQUIRE(out_r != NULL && out_g != NULL && out_b != NULL && out_a != NULL);
    ccl_noise_perm_table(seed, perm);
    base_texel(&s, perm, ix, iy, iz, out);
    *out_r = out[0];
    *out_g = out[1];
    *out_b = out[2];
    *out_a = out[3];
}

void ccl_texgen_detail_shape_texel(int32_t ix, int32_t iy, int32_t iz, int32_t size, uint32_t seed,
                                   int32_t worley_cells, float worley_w0, float worley_w1, float worley_w2,
                                   float gamma, float *out_r, float *out_g, float *out_b)
{
    ccl_detail_shape_settings s;
    float out[3];
    s.size = size;
    s.seed = seed;
    s.worley_cells = worley_cells;
    s.worley_weights[0] = worley_w0;
    s.worley_weights[1] = worley_w1;
    s.worley_weights[2] = worley_w2;
    s.gamma = gamma;
    CCL_REQUIRE(ccl_texgen_detail_shape_settings_check(&s, NULL) == CCL_OK);
    CCL_REQUIRE(out_r != NULL && out_g != NULL && out_b != NULL);
    detail_texel(&s, ix, iy, iz, out);
    *out_r = out[0];
    *out_g = out[1];
    *out_b = out[2];
}

/* ---- whole textures ---------------------------------------------------------------------------------------------- */

ccl_status ccl_texgen_base_shape(const ccl_base_shape_settings *s, float *out_rgba, size_t out_len)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    size_t n;
    int32_t ix, iy, iz;
    float *o;
    if (!s || !out_rgba || ccl_texgen_base_shape_settings_check(s, NULL) != CCL_OK) return CCL_EINVAL;
    n = (size_t)s->size;
    if (out_len != n * n * n * 4u) return CCL_EINVAL;
    ccl_noise_perm_table(s->seed, perm);
    o = out_rgba;
    for (iz = 0; iz < s->size; ++iz)
        for (iy = 0; iy < s->size; ++iy)
            for (ix = 0; ix < s->size; ++ix, o += 4)
                base_texel(s, perm, ix, iy, iz, o);
    return CCL_OK;
}

ccl_status ccl_texgen_detail_shape(const ccl_detail_shape_settings *s, float *out_rgb, size_t out_len)
{
    size_t n;
    int32_t ix, iy, iz;
    float *o;
    if (!s || !out_rgb || ccl_texgen_detail_shape_settings_check(s, NULL) != CCL_OK) return CCL_EINVAL;
    n = (size_t)s->size;
    if (out_len != n * n * n * 3u) return CCL_EINVAL;
    o = out_rgb;
    for (iz = 0; iz < s->size; ++iz)
        for (iy = 0; iy < s->size; ++iy)
            for (ix = 0; ix < s->size; ++ix, o += 3)
                detail_texel(s, ix, iy, iz, o);
    return CCL_OK;
}

ccl_status ccl_texgen_curl_noise(const ccl_curl_noise_settings *s, float *out_xy, size_t out_len)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    size_t n;
    int32_t ix, iy;
    float *o;
    if (!s || !out_xy || ccl_texgen_curl_noise_settings_check(s, NULL) != CCL_OK) return CCL_EINVAL;
    n = (size_t)s->size;
    if (out_len != n * n * 2u) return CCL_EINVAL;
    ccl_noise_perm_table(s->seed, perm);
    o = out_xy;
    for (iy = 0; iy < s->size; ++iy)
        for (ix = 0; ix < s->size; ++ix, o += 2)
            curl_texel(s, perm, ix, iy, o);
    return CCL_OK;
}

ccl_status ccl_texgen_weather_map(const ccl_weather_map_settings *s, float *out_rgba, size_t out_len)
{
    uint8_t perm0[CCL_NOISE_PERM_SIZE], perm1[CCL_NOISE_PERM_SIZE], perm2[CCL_NOISE_PERM_SIZE];
    size_t n;
    int32_t ix, iy;
    float *o;
    if (!s || !out_rgba || ccl_texgen_weather_map_settings_check(s, NULL) != CCL_OK) return CCL_EINVAL;
    n = (size_t)s->size;
    if (out_len != n * n * 4u) return CCL_EINVAL;
    ccl_noise_perm_table(s->seed, perm0);
    ccl_noise_perm_table(s->seed + 1u, perm1);
    ccl_noise_perm_table(s->seed + 2u, perm2);
    o = out_rgba;
    for (iy = 0; iy < s->size; ++iy)
        for (ix = 0; ix < s->size; ++ix, o += 4)
            weather_texel(s, perm0, perm1, perm2, ix, iy, o);
    return CCL_OK;
}

/* ---- sampling ---------------------------------------------------------------------------------------------------- */

/* Lower texel index (wrapped) and weight along one axis. x = p * size and t = x - floor(x) are exact; the half-texel
 * shift is applied to t alone, so the result depends on frac(p * size) and floor(p * size) mod size only. */
static void axis(float p, float fsize, uint32_t mask, uint32_t *i0, uint32_t *i1, float *t)
{
    float x = p * fsize;
    float fx = floorf(x);
    float f = x - fx;
    uint32_t i = (uint32_t)(int32_t)fx;
    if (f >= 0.5f) {
        f = f - 0.5f;
    } else {
        f = f + 0.5f;
        i = i - 1u;
    }
    *i0 = i & mask;
    *i1 = (i + 1u) & mask;
    *t = f;
}

void ccl_texgen_sample_trilinear_wrap(const float *tex, int32_t size_mask, float px, float py, float pz,
                                      float *out_r, float *out_g, float *out_b, float *out_a)
{
    uint32_t mask = (uint32_t)size_mask, x0, x1, y0, y1, z0, z1;
    size_t n = (size_t)mask + 1u;
    float fsize = (float)n, tx, ty, tz, res[4];
    int c;
    CCL_REQUIRE(tex != NULL && size_mask >= 0 && ((uint32_t)size_mask & ((uint32_t)size_mask + 1u)) == 0u);
    CCL_REQUIRE(out_r != NULL && out_g != NULL && out_b != NULL && out_a != NULL);
    if (!(fabsf(px * fsize) < 8388608.0f && fabsf(py * fsize) < 8388608.0f && fabsf(pz * fsize) < 8388608.0f)) {
        /* outside the domain |p * size| < 2^23 (or NaN): NaN, and no float -> int conversion of such a value */
        *out_r = *out_g = *out_b = *out_a = NAN;
        return;
    }
    axis(px, fsize, mask, &x0, &x1, &tx);
    axis(py, fsize, mask, &y0, &y1, &ty);
    axis(pz, fsize, mask, &z0, &z1, &tz);
    for (c = 0; c < 4; ++c) {
        float c000 = tex[((z0 * n + y0) * n + x0) * 4u + (size_t)c];
        float c100 = tex[((z0 * n + y0) * n + x1) * 4u + (size_t)c];
        float c010 = tex[((z0 * n + y1) * n + x0) * 4u + (size_t)c];
        float c110 = tex[((z0 * n + y1) * n + x1) * 4u + (size_t)c];
        float c001 = tex[((z1 * n + y0) * n + x0) * 4u + (size_t)c];
        float c101 = tex[((z1 * n + y0) * n + x1) * 4u + (size_t)c];
        float c011 = tex[((z1 * n + y1) * n + x0) * 4u + (size_t)c];
        float c111 = tex[((z1 * n + y1) * n + x1) * 4u + (size_t)c];
        /* lerp a + (b - a) t along x, then y, then z */
        float c00 = c000 + (c100 - c000) * tx;
        float c10 = c010 + (c110 - c010) * tx;
        float c01 = c001 + (c101 - c001) * tx;
        float c11 = c011 + (c111 - c011) * tx;
        float c0 = c00 + (c10 - c00) * ty;
        float c1 = c01 + (c11 - c01) * ty;
        res[c] = c0 + (c1 - c0) * tz;
    }
    *out_r = res[0];
    *out_g = res[1];
    *out_b = res[2];
    *out_a = res[3];
}
