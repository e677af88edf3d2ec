/* The scalar C reference of the cloudscape pixel; see cclouds/cloudscape.h for the algorithm. Every step calls the
 * catalogued functions of the other topics (raymarch, clouds, texgen, sky, colour), in the same order as
 * pywarp/kernels/cloudscape.py. */
#include "cclouds/cloudscape.h"

#include "cclouds/clouds.h"
#include "cclouds/colour.h"
#include "cclouds/phase.h"
#include "cclouds/texgen.h"
#include "internal.h"

#include <string.h>

/* Defaults. The thesis gives none of these values (spec vc-A36, "Not given"); each is our choice, with its reason:
 *   layer 6371 / 1.5 / 4 km   ccl_raymarch_cloud_layer_default (reasons in cclouds/raymarch.h).
 *   base_scale_km 6           one tile of the 128^3 base texture spans 6 km: its Worley cells (4 .. 32 per tile) then
 *                             make cloud cells of ~0.2-1.5 km, the size of fair-weather cumulus; 12 km looked like
 *                             soft blobs from the ground in our test renders.
 *   detail_scale_km 0.8       the 32^3 detail texture (2 .. 16 cells per tile) erodes edges at ~50-400 m.
 *   weather_scale_km 32       a weather-map tile covers 32 x 32 km: a few cloud fields in view before it repeats.
 *   curl_scale_km 8, curl_strength_km 0.2   turbulent swirls a few km wide that displace the detail by up to
 *                             200 m (the thesis gives neither; Schneider 2015 only shows the look).
 *   sigma = sigma_light 30/km a density-1 cloud has a mean free path of ~33 m; the densities of the default
 *                             textures are mostly 0.1-0.5, i.e. extinctions of 3-15/km inside the cloud and more at
 *                             the cores, the range of cumulus (20-100/km at liquid water contents of 0.2-1 g/m^3)
 *                             smoothed by the noise; lower values make the clouds look like veils.
 *   absorption a = 1 + 2 * precipitation: a = 1 is Beer's law on the light optical depth; rain clouds (weather-map
 *                             G = 1) darken three times faster, the effect vc-2.31 gives to precipitation.
 *   g 0.2                     the cloud-model default (pywarp.kernels.clouds): a mild forward lobe.
 *   sun_colour 12 (1, 0.96, 0.88)  the maximum of E = Beer x HG x powder is ~0.057 towards the sun (g = 0.2), so
 *                             the brightest silver lining reaches ~0.7 of display white and sunlit sides ~0.3-0.5;
 *                             slightly warm, as low sunlight is.
 *   ambient bottom (0.12, 0.14, 0.18), top (0.30, 0.34, 0.42)   bluish sky light, about a third of the sunlit
 *                             brightness, darker at the shadowed base: the bases stay grey-blue, not black.
 *   samples 64 .. 128, adaptive, early exit with eps 1/256, light cone 0.1 km / 15 deg / far 3, tilt jitter 0.002:
 *                             the thesis's counts and our raymarch defaults (cclouds/raymarch.h).
 *   light_detail 1            light samples use the full density (the thesis takes the density towards the sun;
 *                             it does not say that the light samples skip the detail).
 *   ground_colour (0.09, 0.10, 0.08)  a dark, slightly green-brown ground (albedo ~0.1 of vegetation and soil under
 *                             a display-linear sky of ~0.5-0.8): dark enough that cloud tops stand out from above.
 *   coverage_threshold CCL_COVERAGE_ONE_MINUS   the threshold C of vc-2.29 is undefined in the thesis. Read as
 *                             C := D_h (the spec's most plausible literal reading, pywarp.clouds_coverage's
 *                             default), coverage erodes cloud cores where D_h is high: clouds only survive where
 *                             0 < D_h < B D_v, as rings around the covered areas (figures/vc/fig-4.10.png shows it).
 *                             C := 1 - D_h (the form of many implementations) makes more coverage give more cloud.
 *                             The renderer defaults to 1 - D_h; CCL_COVERAGE_SAME renders the literal reading.
 *   beer 1, powder 1          both terms of vc-2.31 on (the formula as printed).
 *   gradient_clamp 1          the height gradients are clamped to [0, 1] in the renderer: unclamped, D_v peaks at
 *                             2.18 and the coverage remap then amplifies density instead of thinning it
 *                             (pywarp.kernels.clouds documents the effect); clamped, coverage is monotonic.
 * Lighting (see "Lighting" in cloudscape.h):
 *   lighting CCL_LIGHTING_SKY  sun and ambient follow the sky model (a sunset lights the clouds orange), the ground
 *                             is lit and shadowed by the clouds, distance fades into haze; CCL_LIGHTING_THESIS keeps
 *                             the constants above (the thesis's images).
 *   sun_intensity 16          at the default sun (35 deg up) and turbidity 2.5, ccl_sky_sun_attenuation is
 *                             (0.76, 0.65, 0.46), so the sun's red channel is 12.2 ~ the thesis constant's 12: the
 *                             default view keeps the exposure of the thesis lighting.
 *   turbidity 2.5             the Python settings' default (a clear day); they pass their turbidity here.
 *   ambient_bottom_ratio 0.4  the ratio of the thesis's constants above: ambient_bottom / ambient_top =
 *                             (0.40, 0.41, 0.43).
 *   ambient_ground            = ambient_top (unused in thesis mode; ccl_cloudscape_light overwrites it in sky mode).
 *   ground_albedo (0.06, 0.08, 0.05)  darker than the albedo of vegetation and soil (0.1-0.2): the energy of
 *                             vc-2.31 makes the clouds dim reflectors (a lit cloud top reaches ~0.15 of a white
 *                             Lambertian surface under the same sun), so a physical albedo would light the ground
 *                             almost as brightly as the clouds; at 0.06-0.08 the ground keeps the contrast of a
 *                             photograph (clouds several times brighter than the land).
 *   aerial_km 30              an extinction of 1/30 per km near the ground: Koschmieder's visual range 3.912 x 30 =
 *                             117 km, a clear day (turbidity 2-3); the horizon band of clouds (40-100 km away)
 *                             fades into the horizon sky, clouds a few km away keep their colour.
 *   ms_octaves 3, ms_a = ms_b = ms_c = 0.5   each octave halves the optical depth, the contribution and the phase
 *                             eccentricity (the octave form of Wrenninge et al. 2013 as Hillaire 2016 uses it, which
 *                             needs a <= b to conserve energy); 0.5 for all three is our choice; three octaves bring
 *                             the sum of the contributions to 1.75 (of 2 for infinitely many). PROVISIONAL: to be chosen by the
 *                             path-traced measurement (pywarp/clouds/reference.py).
 *   silver_g 0.8, silver_weight 0.3   a strong, narrow forward lobe for the silver lining next to the mild g = 0.2.
 *                             PROVISIONAL: to be chosen by the same measurement. */
void ccl_cloudscape_params_default(ccl_cloudscape_params *out)
{
    static const float sun[3] = {12.0f, 11.52f, 10.56f};
    static const float amb_bottom[3] = {0.12f, 0.14f, 0.18f};
    static const float amb_top[3] = {0.30f, 0.34f, 0.42f};
    static const float ground[3] = {0.09f, 0.10f, 0.08f};
    static const float albedo[3] = {0.06f, 0.08f, 0.05f};
    CCL_REQUIRE(out != NULL);
    memset(out, 0, sizeof *out);
    ccl_raymarch_cloud_layer_default(&out->layer);
    out->base_scale_km = 6.0f;
    out->detail_scale_km = 0.8f;
    out->weather_scale_km = 32.0f;
    out->curl_scale_km = 8.0f;
    out->curl_strength_km = 0.2f;
    out->sigma = 30.0f;
    out->sigma_light = 30.0f;
    out->absorption_base = 1.0f;
    out->absorption_precip = 2.0f;
    out->g = 0.2f;
    memcpy(out->sun_colour, sun, sizeof sun);
    memcpy(out->ambient_bottom, amb_bottom, sizeof amb_bottom);
    memcpy(out->ambient_top, amb_top, sizeof amb_top);
    out->samples_min = 64;
    out->samples_max = 128;
    out->adaptive_samples = 1;
    out->early_exit = 1;
    out->exit_eps = 1.0f / 256.0f;
    out->light_step_km = 0.1f;
    out->light_cone_angle = 0.2617994f; /* 15 degrees */
    out->light_far_factor = 3.0f;
    out->light_detail = 1;
    out->jitter_mode = CCL_JITTER_TILT;
    out->jitter_amount = 0.002f;
    out->gradient_clamp = 1;
    out->detail_direction = CCL_DETAIL_FORMULA;
    memcpy(out->ground_colour, ground, sizeof ground);
    out->coverage_threshold = CCL_COVERAGE_ONE_MINUS;
    out->beer = 1;
    out->powder = 1;
    out->lighting = CCL_LIGHTING_SKY;
    out->sun_intensity = 16.0f;
    out->turbidity = 2.5f;
    out->ambient_bottom_ratio = 0.4f;
    memcpy(out->ambient_ground, amb_top, sizeof amb_top);
    memcpy(out->ground_albedo, albedo, sizeof albedo);
    out->aerial_km = 30.0f;
    out->ms_octaves = 3;
    out->ms_a = 0.5f;
    out->ms_b = 0.5f;
    out->ms_c = 0.5f;
    out->silver_g = 0.8f;
    out->silver_weight = 0.3f;
}

static int finite_pos(float v) { return v > 0.0f && v < INFINITY; }

/* The texture-coordinate bound of the check: every coordinate the density computes ((position + offset) / scale, in
 * texels) must stay below CCL_CLOUDSCAPE_MAX_TEXCOORD = 2^23, where float32 keeps no fraction to interpolate with
 * (the samplers return NaN from there on). Evaluated in double, so that the bound itself cannot overflow. */
static int texcoord_ok(double extent_km, double offset_km, float scale_km, int size)
{
    return (extent_km + offset_km) / (double)scale_km * (double)size < (double)CCL_CLOUDSCAPE_MAX_TEXCOORD;
}

static double dabs(float v) { return v < 0.0f ? -(double)v : (double)v; }
static int finite_nonneg(float v) { return v >= 0.0f && v < INFINITY; }
static int is_pow2(int n) { return n >= 1 && (n & (n - 1)) == 0; }

static ccl_status bad(const char **out_field, const char *name)
{
    if (out_field) *out_field = name;
    return CCL_EINVAL;
}

ccl_status ccl_cloudscape_check(const ccl_cloudscape_params *p, const ccl_cloud_textures *t,
                                const ccl_cloudscape_sky *sky, const char **out_field)
{
    int c;
    if (out_field) *out_field = NULL;
    if (p == NULL) return bad(out_field, "params");
    if (!(finite_pos(p->layer.r_earth) && p->layer.r_earth <= p->layer.r_inner && p->layer.r_inner < p->layer.r_outer
          && p->layer.r_outer < INFINITY))
        return bad(out_field, "layer");
    if (!finite_pos(p->base_scale_km)) return bad(out_field, "base_scale_km");
    if (!finite_pos(p->detail_scale_km)) return bad(out_field, "detail_scale_km");
    if (!finite_pos(p->weather_scale_km)) return bad(out_field, "weather_scale_km");
    if (!finite_pos(p->curl_scale_km)) return bad(out_field, "curl_scale_km");
    if (!finite_nonneg(p->curl_strength_km)) return bad(out_field, "curl_strength_km");
    if (!(fabsf(p->weather_offset[0]) < INFINITY && fabsf(p->weather_offset[1]) < INFINITY))
        return bad(out_field, "weather_offset");
    for (c = 0; c < 3; ++c)
        if (!(fabsf(p->detail_offset[c]) < INFINITY)) return bad(out_field, "detail_offset");
    if (!finite_pos(p->sigma)) return bad(out_field, "sigma");
    if (!finite_nonneg(p->sigma_light)) return bad(out_field, "sigma_light");
    if (!finite_nonneg(p->absorption_base)) return bad(out_field, "absorption_base");
    if (!finite_nonneg(p->absorption_precip)) return bad(out_field, "absorption_precip");
    if (!(p->g > -1.0f && p->g < 1.0f)) return bad(out_field, "g");
    for (c = 0; c < 3; ++c) {
        if (!finite_nonneg(p->sun_colour[c])) return bad(out_field, "sun_colour");
        if (!finite_nonneg(p->ambient_bottom[c])) return bad(out_field, "ambient_bottom");
        if (!finite_nonneg(p->ambient_top[c])) return bad(out_field, "ambient_top");
        if (!finite_nonneg(p->ground_colour[c])) return bad(out_field, "ground_colour");
    }
    if (!(p->samples_min >= 1 && p->samples_min <= p->samples_max)) return bad(out_field, "samples_min");
    if (!(p->samples_max <= 4096)) return bad(out_field, "samples_max");
    if (!(p->exit_eps > 0.0f && p->exit_eps < 1.0f)) return bad(out_field, "exit_eps");
    if (!finite_pos(p->light_step_km)) return bad(out_field, "light_step_km");
    if (!(p->light_cone_angle >= 0.0f && p->light_cone_angle < 1.5707963f)) return bad(out_field, "light_cone_angle");
    if (!(p->light_far_factor >= 1.0f && p->light_far_factor < INFINITY)) return bad(out_field, "light_far_factor");
    if (!(p->jitter_mode >= CCL_JITTER_TILT && p->jitter_mode <= CCL_JITTER_NONE)) return bad(out_field, "jitter_mode");
    if (!finite_nonneg(p->jitter_amount)) return bad(out_field, "jitter_amount");
    if (!(p->detail_direction == CCL_DETAIL_FORMULA || p->detail_direction == CCL_DETAIL_PROSE))
        return bad(out_field, "detail_direction");
    if (!(p->coverage_threshold == CCL_COVERAGE_SAME || p->coverage_threshold == CCL_COVERAGE_ONE_MINUS))
        return bad(out_field, "coverage_threshold");
    if (!(p->beer == 0 || p->beer == 1)) return bad(out_field, "beer");
    if (!(p->powder == 0 || p->powder == 1)) return bad(out_field, "powder");
    if (!(p->lighting == CCL_LIGHTING_THESIS || p->lighting == CCL_LIGHTING_SKY)) return bad(out_field, "lighting");
    if (!finite_nonneg(p->sun_intensity)) return bad(out_field, "sun_intensity");
    if (!(p->turbidity >= (float)CCL_PREETHAM_TURBIDITY_MIN && p->turbidity <= (float)CCL_PREETHAM_TURBIDITY_MAX))
        return bad(out_field, "turbidity");
    if (!(p->ambient_bottom_ratio >= 0.0f && p->ambient_bottom_ratio <= 1.0f))
        return bad(out_field, "ambient_bottom_ratio");
    for (c = 0; c < 3; ++c) {
        if (!finite_nonneg(p->ambient_ground[c])) return bad(out_field, "ambient_ground");
        if (!(p->ground_albedo[c] >= 0.0f && p->ground_albedo[c] <= 1.0f)) return bad(out_field, "ground_albedo");
    }
    if (!finite_nonneg(p->aerial_km)) return bad(out_field, "aerial_km");
    if (!(p->ms_octaves >= 1 && p->ms_octaves <= CCL_CLOUDSCAPE_MAX_MS_OCTAVES)) return bad(out_field, "ms_octaves");
    if (!(p->ms_a >= 0.0f && p->ms_a <= 1.0f)) return bad(out_field, "ms_a");
    if (!(p->ms_b >= 0.0f && p->ms_b <= 1.0f)) return bad(out_field, "ms_b");
    if (!(p->ms_c >= 0.0f && p->ms_c <= 1.0f)) return bad(out_field, "ms_c");
    if (!(p->silver_g > -1.0f && p->silver_g < 1.0f)) return bad(out_field, "silver_g");
    if (!(p->silver_weight >= 0.0f && p->silver_weight <= 1.0f)) return bad(out_field, "silver_weight");
    if (t == NULL) return bad(out_field, "textures");
    if (t->base == NULL || !is_pow2(t->base_size)) return bad(out_field, "base");
    if (t->detail == NULL || !is_pow2(t->detail_size)) return bad(out_field, "detail");
    if (t->curl == NULL || !is_pow2(t->curl_size)) return bad(out_field, "curl");
    if (t->weather == NULL || !is_pow2(t->weather_size)) return bad(out_field, "weather");
    {
        /* every position the density samples lies inside the outer sphere: |pos_i| <= |centre_i| + r_outer per
         * axis; the detail lookup adds the curl displacement (|curl| <= CCL_CLOUDSCAPE_MAX_CURL) and the offset */
        const double r = (double)p->layer.r_outer, ex = dabs(p->layer.centre.x) + r,
                     ey = dabs(p->layer.centre.y) + r, ez = dabs(p->layer.centre.z) + r;
        const double curl = (double)CCL_CLOUDSCAPE_MAX_CURL * (double)p->curl_strength_km;
        if (!(ex < (double)INFINITY && ey < (double)INFINITY && ez < (double)INFINITY)) return bad(out_field, "layer");
        if (!(texcoord_ok(ex, 0.0, p->base_scale_km, t->base_size) &&
              texcoord_ok(ey, 0.0, p->base_scale_km, t->base_size) &&
              texcoord_ok(ez, 0.0, p->base_scale_km, t->base_size)))
            return bad(out_field, "base_scale_km");
        if (!(texcoord_ok(ex, 0.0, p->curl_scale_km, t->curl_size) &&
              texcoord_ok(ez, 0.0, p->curl_scale_km, t->curl_size)))
            return bad(out_field, "curl_scale_km");
        if (!(texcoord_ok(ex, 0.0, p->weather_scale_km, t->weather_size) &&
              texcoord_ok(ez, 0.0, p->weather_scale_km, t->weather_size)))
            return bad(out_field, "weather_scale_km");
        if (!(texcoord_ok(ex, dabs(p->weather_offset[0]), p->weather_scale_km, t->weather_size) &&
              texcoord_ok(ez, dabs(p->weather_offset[1]), p->weather_scale_km, t->weather_size)))
            return bad(out_field, "weather_offset");
        if (!(texcoord_ok(ex, 0.0, p->detail_scale_km, t->detail_size) &&
              texcoord_ok(ey, 0.0, p->detail_scale_km, t->detail_size) &&
              texcoord_ok(ez, 0.0, p->detail_scale_km, t->detail_size)))
            return bad(out_field, "detail_scale_km");
        if (!(texcoord_ok(ex, curl, p->detail_scale_km, t->detail_size) &&
              texcoord_ok(ez, curl, p->detail_scale_km, t->detail_size)))
            return bad(out_field, "curl_strength_km");
        if (!(texcoord_ok(ex, curl + dabs(p->detail_offset[0]), p->detail_scale_km, t->detail_size) &&
              texcoord_ok(ey, dabs(p->detail_offset[1]), p->detail_scale_km, t->detail_size) &&
              texcoord_ok(ez, curl + dabs(p->detail_offset[2]), p->detail_scale_km, t->detail_size)))
            return bad(out_field, "detail_offset");
    }
    if (sky == NULL) return bad(out_field, "sky");
    if (!(sky->kind == CCL_SKY_GRADIENT || sky->kind == CCL_SKY_PREETHAM)) return bad(out_field, "sky.kind");
    {
        /* | |sun| - 1 | <= 1e-3, the tolerance of the other unit-vector checks (registry UNIT_TOL); the march clamps
         * dot(d, sun) to [-1, 1], the domain of the phase function it feeds */
        const double s0 = (double)sky->sun[0], s1 = (double)sky->sun[1], s2 = (double)sky->sun[2];
        const double n = sqrt(s0 * s0 + s1 * s1 + s2 * s2);
        if (!(fabs(n - 1.0) <= 1e-3)) return bad(out_field, "sky.sun");
    }
    return CCL_OK;
}

/* Axis of a wrapped linear interpolation, texel centres at i + 0.5 (the convention of the texgen sampler). */
static void axis2(float x, uint32_t mask, uint32_t *i0, uint32_t *i1, float *t)
{
    float fx = floorf(x), f = x - fx;
    int32_t i = (int32_t)fx;
    if (f < 0.5f) {
        i -= 1;
        *t = f + 0.5f;
    } else {
        *t = f - 0.5f;
    }
    *i0 = (uint32_t)i & mask;
    *i1 = (uint32_t)(i + 1) & mask;
}

void ccl_cloudscape_sample_bilinear_wrap(const float *tex, int size_mask, float u, float v, float *out_rgba)
{
    uint32_t mask = (uint32_t)size_mask, n = mask + 1u, x0, x1, y0, y1;
    float fsize = (float)n, tx, ty;
    int c;
    CCL_REQUIRE(tex != NULL && out_rgba != NULL && size_mask >= 0);
    if (!(fabsf(u * fsize) < 8388608.0f && fabsf(v * fsize) < 8388608.0f)) {
        /* outside the domain |uv * size| < 2^23 (or NaN): NaN, never a float -> int conversion of such a value */
        for (c = 0; c < 4; ++c) out_rgba[c] = NAN;
        return;
    }
    axis2(u * fsize, mask, &x0, &x1, &tx);
    axis2(v * fsize, mask, &y0, &y1, &ty);
    for (c = 0; c < 4; ++c) {
        float c00 = tex[((size_t)y0 * n + x0) * 4u + (size_t)c];
        float c10 = tex[((size_t)y0 * n + x1) * 4u + (size_t)c];
        float c01 = tex[((size_t)y1 * n + x0) * 4u + (size_t)c];
        float c11 = tex[((size_t)y1 * n + x1) * 4u + (size_t)c];
        float c0 = c00 + (c10 - c00) * tx;
        float c1 = c01 + (c11 - c01) * tx;
        out_rgba[c] = c0 + (c1 - c0) * ty;
    }
}

float ccl_cloudscape_density(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 pos, int detail,
                             float *out_precipitation)
{
    const ccl_vec3 c = p->layer.centre;
    float r, h, w[4], base[4], curl[4], det[4], l_fbm, b, d_v, b_d, h_d;
    ccl_vec3 q;
    *out_precipitation = 0.0f;
    /* vc-A15: relative height in the layer */
    r = ccl_vec3_length(ccl_vec3_sub(pos, c));
    h = ccl_clouds_relative_height(r, p->layer.r_inner, p->layer.r_outer, CCL_VARIANT_CORRECTED);
    if (!(h >= 0.0f && h <= 1.0f)) return 0.0f;
    /* vc-A12: weather map, planar projection with wind */
    ccl_cloudscape_sample_bilinear_wrap(t->weather, t->weather_size - 1,
                                        (pos.x + p->weather_offset[0]) / p->weather_scale_km,
                                        (pos.z + p->weather_offset[1]) / p->weather_scale_km, w);
    *out_precipitation = w[1];
    if (!(w[0] > 0.0f)) return 0.0f;
    /* vc-4.7 / A16: vertical profile of the cloud type */
    d_v = ccl_clouds_height_gradient(h, w[2], p->gradient_clamp);
    if (!(d_v > 0.0f)) return 0.0f;
    /* vc-2.28: base shape */
    ccl_texgen_sample_trilinear_wrap(t->base, t->base_size - 1, pos.x / p->base_scale_km, pos.y / p->base_scale_km,
                                     pos.z / p->base_scale_km, &base[0], &base[1], &base[2], &base[3]);
    ccl_clouds_base_shape(base[0], base[1], base[2], base[3], &l_fbm, &b);
    /* vc-2.29: coverage with the threshold C read as 1 - D_h or D_h */
    b_d = ccl_clouds_coverage(b, d_v, w[0], p->coverage_threshold == CCL_COVERAGE_SAME ? w[0] : 1.0f - w[0], 1);
    if (!(b_d > 0.0f) || !detail) return b_d > 0.0f ? b_d : 0.0f;
    /* vc-2.30: detail erosion at curl-displaced coordinates */
    ccl_cloudscape_sample_bilinear_wrap(t->curl, t->curl_size - 1, pos.x / p->curl_scale_km,
                                        pos.z / p->curl_scale_km, curl);
    q.x = pos.x + curl[0] * p->curl_strength_km + p->detail_offset[0];
    q.y = pos.y + p->detail_offset[1];
    q.z = pos.z + curl[1] * p->curl_strength_km + p->detail_offset[2];
    h_d = ccl_clouds_relative_height(ccl_vec3_length(ccl_vec3_sub(q, c)), p->layer.r_inner, p->layer.r_outer,
                                     CCL_VARIANT_CORRECTED);
    h_d = h_d < 0.0f ? 0.0f : (h_d > 1.0f ? 1.0f : h_d);
    ccl_texgen_sample_trilinear_wrap(t->detail, t->detail_size - 1, q.x / p->detail_scale_km,
                                     q.y / p->detail_scale_km, q.z / p->detail_scale_km, &det[0], &det[1], &det[2],
                                     &det[3]);
    return ccl_clouds_detail_erosion(b_d, det[0], det[1], det[2], h_d, (ccl_detail_direction)p->detail_direction, 1);
}

void ccl_cloudscape_march(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 eye, ccl_vec3 dir,
                          ccl_vec3 to_sun, float offset, float *out_rgb, float *out_transmittance, int *out_samples)
{
    ccl_vec3 colour = {0.0f, 0.0f, 0.0f};
    float trans = 1.0f, t0, t1, t_start, dt, cos_theta;
    int n, i, j, taken = 0;
    const ccl_cloud_layer *L = &p->layer;
    if (ccl_raymarch_layer_segment(eye, dir, L->centre, L->r_earth, L->r_inner, L->r_outer, &t0, &t1)) {
        n = p->adaptive_samples ? ccl_raymarch_view_sample_count(dir.y, p->samples_min, p->samples_max)
                                : p->samples_max;
        cos_theta = ccl_vec3_dot(dir, to_sun);
        /* |d| and |to_sun| are 1 only to within rounding (and the check's tolerance): keep the phase function's
         * argument in its domain [-1, 1] */
        cos_theta = cos_theta > 1.0f ? 1.0f : (cos_theta < -1.0f ? -1.0f : cos_theta);
        if (ccl_raymarch_interval(t0, t1, n, &t_start, &dt)) {
            for (i = 0; i < n; ++i) {
                float precip, rho, h, d_light = 0.0f, a, e;
                int stop;
                ccl_vec3 pos = ccl_raymarch_point(eye, dir, t_start, dt, i, offset), light;
                ++taken;
                rho = ccl_cloudscape_density(p, t, pos, 1, &precip);
                if (!(rho > 0.0f)) continue;
                /* vc-A19: optical depth towards the sun from 6 cone samples */
                for (j = 0; j < 6; ++j) {
                    float pj, w = j < 5 ? p->light_step_km : (p->light_far_factor - 1.0f) * 5.0f * p->light_step_km;
                    ccl_vec3 q = ccl_raymarch_light_sample_position(pos, to_sun, j, p->light_step_km,
                                                                    p->light_cone_angle, p->light_far_factor,
                                                                    ccl_raymarch_light_cone_kernel(j));
                    d_light += w * ccl_cloudscape_density(p, t, q, p->light_detail, &pj);
                }
                d_light *= p->sigma_light;
                /* vc-2.31 + vc-A20: sun energy and ambient by relative height, per channel */
                a = p->absorption_base + p->absorption_precip * precip;
                if (p->beer && p->powder)
                    e = ccl_clouds_energy(d_light, a, cos_theta, p->g);
                else /* the same product with a term replaced by 1 */
                    e = (p->beer ? expf(-d_light * a) : 1.0f) * ccl_phase_hg(cos_theta, p->g) *
                        (p->powder ? 1.0f - expf(-2.0f * d_light) : 1.0f);
                h = ccl_clouds_relative_height(ccl_vec3_length(ccl_vec3_sub(pos, L->centre)),
                                               L->r_inner, L->r_outer, CCL_VARIANT_CORRECTED);
                light.x = p->sun_colour[0] * e + (p->ambient_bottom[0] + (p->ambient_top[0] - p->ambient_bottom[0]) * h);
                light.y = p->sun_colour[1] * e + (p->ambient_bottom[1] + (p->ambient_top[1] - p->ambient_bottom[1]) * h);
                light.z = p->sun_colour[2] * e + (p->ambient_bottom[2] + (p->ambient_top[2] - p->ambient_bottom[2]) * h);
                /* vc-A21: front-to-back accumulation, early termination */
                colour = ccl_raymarch_accumulate(colour, trans, p->sigma, rho, dt, light, p->exit_eps, &trans, &stop);
                if (stop && p->early_exit) break;
            }
        }
    }
    out_rgb[0] = colour.x;
    out_rgb[1] = colour.y;
    out_rgb[2] = colour.z;
    *out_transmittance = trans;
    *out_samples = taken;
}

void ccl_cloudscape_pixel(const ccl_cloudscape_params *p, const ccl_cloud_textures *t,
                          const ccl_cloudscape_sky *sky, const ccl_camera *cam, int x, int y, int width, int height,
                          int frame, float *out_rgb)
{
    ccl_vec3 d = ccl_camera_ray(cam->inv_view_proj_rot, x, y, width, height), sun;
    float offset, bg[3], cl[3], trans, e0, e1;
    int samples, c;
    d = ccl_raymarch_jitter(d, (uint32_t)x, (uint32_t)y, (uint32_t)frame, p->jitter_amount,
                            (ccl_jitter_mode)p->jitter_mode, &offset);
    sun.x = sky->sun[0];
    sun.y = sky->sun[1];
    sun.z = sky->sun[2];
    /* background: the ground where the ray hits the Earth ahead, else the sky model's colour */
    if (ccl_raymarch_ray_sphere(cam->eye, d, p->layer.centre, p->layer.r_earth, &e0, &e1) && e1 > 0.0f &&
        (e0 > 0.0f || ccl_vec3_dot(d, ccl_vec3_sub(cam->eye, p->layer.centre)) < 0.0f)) {
        /* the Earth ahead: entered in front of the camera, or (camera on the ground) the ray points downwards */
        bg[0] = p->ground_colour[0];
        bg[1] = p->ground_colour[1];
        bg[2] = p->ground_colour[2];
    } else {
        const ccl_vec3 s = (sky->kind == CCL_SKY_PREETHAM) ? ccl_sky_preetham_rgb(d, sun, &sky->preetham)
                                                           : ccl_sky_gradient_rgb(d, sun, &sky->gradient);
        bg[0] = s.x;
        bg[1] = s.y;
        bg[2] = s.z;
    }
    ccl_cloudscape_march(p, t, cam->eye, d, sun, offset, cl, &trans, &samples);
    /* vc-4.8: C_f = B (1 - O_D) + C_clouds, O_D = 1 - T */
    for (c = 0; c < 3; ++c)
        out_rgb[c] = ccl_clouds_composite(bg[c], 1.0f - trans, cl[c]);
}

ccl_status ccl_cloudscape_render(const ccl_cloudscape_params *p, const ccl_cloud_textures *t,
                                 const ccl_cloudscape_sky *sky, const ccl_camera *cam, int width, int height,
                                 int frame, float *out_rgb, size_t out_len)
{
    int x, y, c;
    ccl_status st = ccl_cloudscape_check(p, t, sky, NULL);
    if (st != CCL_OK) return st;
    if (cam == NULL || out_rgb == NULL || width < 1 || height < 1 || frame < 0) return CCL_EINVAL;
    if (out_len != (size_t)width * (size_t)height * 3u) return CCL_EINVAL;
    for (y = 0; y < height; ++y) {
        for (x = 0; x < width; ++x) {
            float rgb[3];
            float *o = out_rgb + ((size_t)y * (size_t)width + (size_t)x) * 3u;
            ccl_cloudscape_pixel(p, t, sky, cam, x, y, width, height, frame, rgb);
            for (c = 0; c < 3; ++c)
                o[c] = ccl_colour_srgb_encode(rgb[c] < 0.0f ? 0.0f : (rgb[c] > 1.0f ? 1.0f : rgb[c]));
        }
    }
    return CCL_OK;
}
