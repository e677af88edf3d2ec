/* The scalar C reference of the cloudscape pixel; see cclouds/cloudscape.h for the algorithm. Every step calls the
 * catalogued functions of the other topics (raymarch, clouds, texgen, sky, colour), in the same order as
 * pywarp/kernels/cloudscape.py. */
#include "cclouds/cloudscape.h"

#include "cclouds/clouds.h"
#include "cclouds/colour.h"
#include "cclouds/hash.h"
#include "cclouds/interp.h"
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
 *   samples 64 .. 128, adaptive, light cone 0.1 km / 15 deg / far 3:
 *                             the thesis's counts and our raymarch defaults (cclouds/raymarch.h).
 *   early exit at T <= exit_eps 1/64 with exit_fill 1   the thesis stops "once further samples cannot change the
 *                             colour" and gives no threshold. At the exit the rest of the ray still holds T of the
 *                             pixel's weight; exit_fill gives it the light of the last sample (the rest of an
 *                             opaque cloud is lit much like its last sample) instead of letting the background
 *                             show through it. Measured against the march without early exit on the default view
 *                             (240 x 135, linear levels of 8 bits; tests/clouds/test_early_exit.py): 1/256 without
 *                             the fill (the earlier default) changes pixels by 0.03 on average, at most 1.2; 1/64
 *                             with the fill by 0.045, at most 5.3, 99.9 % of them by at most 3.3; 1/64 without it by
 *                             0.13; 1/32 with it by 0.10, at most 11 (99.9 %: 7.2). The jitter changes the frame by
 *                             0.22, at most 8.8 (99.9 %: 5.1), from one frame to the next: 1/64 is the largest
 *                             threshold below that in all three. It takes 11 % fewer light estimates than 1/256
 *                             (5.24 instead of 5.87 per pixel, 320 x 180).
 *   light_interp 1/256        the six cone samples of vc-A19 are 40 % of a frame. In a cloud the lit samples are
 *                             consecutive view samples 0.1 km apart, and the optical depth towards the sun changes
 *                             little from one to the next: every second one may take the mean of its neighbours'.
 *                             Where that could show -- the neighbours' lights differ, and the sample weighs in the
 *                             pixel (with the exit's fill, a sample that ends the ray weighs the rest of it too) --
 *                             it computes its own: the product of its weight and the neighbours' largest channel
 *                             difference must be at most light_interp. Measured against 0 = off (240 x 135, linear
 *                             levels of 8 bits; tests/clouds/test_light_interp.py): 1/256 changes the default view
 *                             by 0.05 on average, at most 3.3 (the jitter: 0.20, at most 8.7), a low sun by 0.035, at
 *                             most 2.0 (jitter 0.07, 3.5), the view from above by 0.036, at most 3.4 (0.21, 16).
 *                             Larger thresholds stay below the jitter on average but not everywhere: 1/128 and 1/64
 *                             change a few low-sun pixels by 11-13 levels (a middle sample whose light path meets a
 *                             cloud its neighbours' miss). 1/256 computes 22 % fewer optical depths than 0 (4.09
 *                             instead of 5.24 per pixel, 320 x 180; 1/64: 3.43), and the error against the
 *                             path-traced reference does not grow.
 *   jitter offset (amount 0.002 for the tilt mode)   the first sample's position along the ray; the thesis's tilt
 *                             of up to 0.002 rad per axis moves the ray by more than a pixel (0.0019 rad at
 *                             960 x 540): far clouds changed from frame to frame (the flickering horizon) and near
 *                             ones looked out of focus.
 *   lod 1, lod_bias 0         level of detail (see ccl_cloudscape_lod): one texel per footprint, the usual mip-mapping
 *                             criterion; without it steps and pixels near the horizon undersample the 25-50 m texels.
 *   refine_step_km 0.1, refine_max 8   near the horizon the view steps reach ~0.8 km and one step crossed a whole
 *                             cloud: the pixel took the light of one random depth. 0.1 km is about three mean free
 *                             paths of the default extinction in a typical cloud; 8 sub-steps take 0.8 km to 0.1 km.
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
 *   beer 1, powder 0          Beer's term of vc-2.31 on, its powder term off (replaced by 1). Measured against the
 *                             path-traced reference (tools/tune_lighting.py, three scenes, 192 paths per pixel,
 *                             sky lighting with 4 octaves): with the powder term the mean CIEDE2000 is 13.4 and the
 *                             mean SSIM 0.646, without it 9.0 and 0.774. The term darkens every sample whose path
 *                             towards the sun is short -- a dark rim along each cloud's sunward edge, which shows as
 *                             thin dark crease lines where one cloud's edge lies over another. The thesis's renderer
 *                             (the formula as printed) sets powder = 1.
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
 *   ground_variation 0        a uniform ground, the thesis's (the rain scene sets 0.8 for its view from 50 m).
 *   ground_albedo (0.04, 0.05, 0.03)  a third of the albedo of vegetation and soil (0.1-0.2), for the exposure of
 *                             this renderer: the energy of vc-2.31 makes the clouds dim reflectors (a lit cloud top
 *                             reaches ~0.15 of a white Lambertian surface under the same sun), so the sun constant
 *                             that exposes the clouds is ~3.5 times brighter, relative to the display-linear sky,
 *                             than the real sun (100 klx against a ~6 kcd/m^2 zenith: a white surface ~5 times the
 *                             zenith sky; here 3.9 / 0.22 ~ 18 times). Scaled by that factor, the sunlit ground
 *                             stays darker than the zenith sky and the clouds stand out from it, as in a
 *                             photograph.
 *   aerial_km 30              an extinction of 1/30 per km near the ground: Koschmieder's visual range 3.912 x 30 =
 *                             117 km, a clear day (turbidity 2-3); the horizon band of clouds (40-100 km away)
 *                             fades into the horizon sky, clouds a few km away keep their colour.
 *   aerial_height_km 2        the haze that limits the visual range is mostly aerosol, held in the lowest kilometres
 *                             (aerosol scale heights 1-2 km; the air's own, Rayleigh, is 8 km): seen from 8 km up the
 *                             ground is then veiled, not lost in a homogeneous fog 8 km deep.
 *   ms_octaves 4, ms_a = ms_c = 0.5, ms_b 0.75   each octave halves the optical depth and the phase eccentricity
 *                             and keeps 0.75 of the contribution (the octave form of Wrenninge et al. 2013 as
 *                             Hillaire 2016 uses it, which needs a <= b to conserve energy). Four octaves were chosen
 *                             by measurement (tools/tune_lighting.py: mean CIEDE2000 against the path-traced reference
 *                             of three scenes, 192 paths per pixel; powder off, no second lobe, ms_b 0.5): 1 octave
 *                             12.16, 2: 10.26, 3: 9.43, 4: 9.04, 5: 8.85, 6: 8.77, 8: 8.70 -- four is the fewest
 *                             within 0.5 of the best (mean SSIM 0.774 against 0.776 for eight). ms_b 0.75 (with the
 *                             lighting terms below): chosen against the path-traced references in physical units
 *                             (tools/tune_lighting.py --physical, issue 32's model ``physical slab``,
 *                             docs/lighting.rst), together with the lighting terms below.
 *   silver_g 0.8, silver_weight 0   no second lobe: by the same measurement every weight raises the error in every
 *                             scene (4 octaves: w 0 9.04, 0.15 9.25, 0.3 with silver_g 0.8 9.71) -- the medium's
 *                             phase function is the one HG lobe g; the lobe stays an option (fig 2.17 shows it).
 *   ambient_ground_weight 0.25   a quarter of the clouds' ambient from the lit ground below, three quarters the sky's
 *                             mean over the upper hemisphere (0 is the sky's mean alone, 0.5 the mean over the whole
 *                             sphere of directions, the lower half the lit ground: the in-scattered light of an
 *                             isotropic phase for a cloud with nothing around it). Chosen against the path-traced
 *                             references, issue 32's ``physical slab 2``, docs/lighting.rst.
 *   phase CCL_CLOUDSCAPE_PHASE_THESIS, droplet_um 15   the thesis's HG lobe by default (its images); with
 *                             CCL_CLOUDSCAPE_PHASE_MIE the approximate Mie phase of 15 um droplets (effective radius
 *                             7.5 um, in the 5-10 um of fair-weather cumulus; g = 0.87). Octave i then takes c^i of
 *                             it and 1 - c^i of the isotropic phase: the mean cosine c^i g, as HG(c^i g) has.
 *   mie_delta 1, ms_depth 1.5, ms_thin 0.2, ms_view 4, ms_view_trans 0.5, ambient_aniso 0.6, ms_slab 1.6,
 *   ms_slab_mu 0.3, ms_slab_far 0.67   the lighting terms beyond the octaves (vc-x-mie-delta, vc-x-ms-gain,
 *                             vc-x-ms-view, vc-x-ambient-aniso, vc-x-ms-slab), with ambient_ground_weight 0.25 and
 *                             ms_b 0.75 above: chosen against the path-traced references, issue 32's ``physical
 *                             slab 2``, docs/lighting.rst (tools/tune_lighting.py --grid 5 against the converged
 *                             truncated-peak references: CIEDE2000 <= 3 and thick cloud within 0.90-1.10 of the
 *                             references' energy in every view). mie_delta acts with the Mie phase only: its forward HG lobe (share 1 - w_D)
 *                             goes on as unscattered light, extinction x w_D (0.49 at 15 um), Draine's lobe the
 *                             phase. The octaves i >= 1
 *                             are weighted by the optical depth d towards the sun, 0.2 + 0.8 (1 - exp(-d / 1.5)), by
 *                             the depth into the cloud along the view, 1 + 4 max(1 - T / 0.5, 0), and by the sun's
 *                             elevation and the sample's place between the sun and the viewer, 1.6 mu0^0.3 (1 - 0.67
 *                             r); the ambient by the view direction, 1 + 0.6 mu T. Off (the earlier images):
 *                             mie_delta 0, ms_depth 0, ms_view 0, ambient_aniso 0, ms_slab 0, ambient_ground_weight 0,
 *                             ms_b 0.5. Every one of these is a sky-lighting term: for the thesis's images
 *                             CCL_LIGHTING_THESIS takes them off, with ms_octaves 1 and silver_weight 0, as the caller's
 *                             choice (pywarp's settings: THESIS_LIGHTING in pywarp/clouds/settings.py; an explicit
 *                             change may still set any of them, e.g. the silver lobe under the thesis's lighting). */
void ccl_cloudscape_params_default(ccl_cloudscape_params *out)
{
    static const float sun[3] = {12.0f, 11.52f, 10.56f};
    static const float amb_bottom[3] = {0.12f, 0.14f, 0.18f};
    static const float amb_top[3] = {0.30f, 0.34f, 0.42f};
    static const float ground[3] = {0.09f, 0.10f, 0.08f};
    static const float albedo[3] = {0.04f, 0.05f, 0.03f};
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
    out->exit_eps = 1.0f / 64.0f;
    out->exit_fill = 1;
    out->light_interp = 1.0f / 256.0f;
    out->light_step_km = 0.1f;
    out->light_cone_angle = 0.2617994f; /* 15 degrees */
    out->light_far_factor = 3.0f;
    out->light_detail = 1;
    out->jitter_mode = CCL_JITTER_OFFSET;
    out->jitter_amount = 0.002f;
    out->gradient_clamp = 1;
    out->detail_direction = CCL_DETAIL_FORMULA;
    memcpy(out->ground_colour, ground, sizeof ground);
    out->coverage_threshold = CCL_COVERAGE_ONE_MINUS;
    out->beer = 1;
    out->powder = 0;
    out->lighting = CCL_LIGHTING_SKY;
    out->sun_intensity = 16.0f;
    out->turbidity = 2.5f;
    out->ambient_bottom_ratio = 0.4f;
    memcpy(out->ambient_ground, amb_top, sizeof amb_top);
    memcpy(out->ground_albedo, albedo, sizeof albedo);
    out->ground_variation = 0.0f;
    out->aerial_km = 30.0f;
    out->aerial_height_km = 2.0f;
    out->ms_octaves = 4;
    out->ms_a = 0.5f;
    out->ms_b = 0.75f;
    out->ms_c = 0.5f;
    out->silver_g = 0.8f;
    out->silver_weight = 0.0f;
    out->phase = CCL_CLOUDSCAPE_PHASE_THESIS;
    out->droplet_um = 15.0f;
    out->ambient_ground_weight = 0.25f;
    out->ms_depth = 1.5f;
    out->ms_thin = 0.2f;
    out->ms_view = 4.0f;
    out->ms_view_trans = 0.5f;
    out->ambient_aniso = 0.6f;
    out->ms_slab = 1.6f;
    out->ms_slab_mu = 0.3f;
    out->ms_slab_far = 0.67f;
    out->mie_delta = 1.0f;
    out->lod = 1;
    out->lod_bias = 0.0f;
    out->refine_step_km = 0.1f;
    out->refine_max = 8;
    out->weather_detile = 1;
    out->march = CCL_CLOUDSCAPE_MARCH_FAST;
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
    if (!(p->exit_fill == 0 || p->exit_fill == 1)) return bad(out_field, "exit_fill");
    if (!finite_nonneg(p->light_interp)) return bad(out_field, "light_interp");
    if (!finite_pos(p->light_step_km)) return bad(out_field, "light_step_km");
    if (!(p->light_cone_angle >= 0.0f && p->light_cone_angle < 1.5707963f)) return bad(out_field, "light_cone_angle");
    if (!(p->light_far_factor >= 1.0f && p->light_far_factor <= CCL_CLOUDSCAPE_MAX_LIGHT_FAR_FACTOR))
        return bad(out_field, "light_far_factor");
    if (!((double)p->light_far_factor * 5.0 * (double)p->light_step_km <= CCL_CLOUDSCAPE_MAX_LIGHT_KM))
        return bad(out_field, "light_far_factor");
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
    if (!(p->ground_variation >= 0.0f && p->ground_variation <= 1.0f)) return bad(out_field, "ground_variation");
    if (!finite_nonneg(p->aerial_km)) return bad(out_field, "aerial_km");
    if (!finite_nonneg(p->aerial_height_km)) return bad(out_field, "aerial_height_km");
    if (!(p->ms_octaves >= 1 && p->ms_octaves <= CCL_CLOUDSCAPE_MAX_MS_OCTAVES)) return bad(out_field, "ms_octaves");
    if (!(p->ms_a >= 0.0f && p->ms_a <= 1.0f)) return bad(out_field, "ms_a");
    if (!(p->ms_b >= 0.0f && p->ms_b <= 1.0f)) return bad(out_field, "ms_b");
    if (!(p->ms_c >= 0.0f && p->ms_c <= 1.0f)) return bad(out_field, "ms_c");
    if (!(p->silver_g > -1.0f && p->silver_g < 1.0f)) return bad(out_field, "silver_g");
    if (!(p->silver_weight >= 0.0f && p->silver_weight <= 1.0f)) return bad(out_field, "silver_weight");
    if (!(p->phase == CCL_CLOUDSCAPE_PHASE_THESIS || p->phase == CCL_CLOUDSCAPE_PHASE_MIE))
        return bad(out_field, "phase");
    if (!(p->droplet_um >= (float)CCL_PHASE_MIE_D_MIN && p->droplet_um <= (float)CCL_PHASE_MIE_D_MAX))
        return bad(out_field, "droplet_um");
    if (!(p->ambient_ground_weight >= 0.0f && p->ambient_ground_weight <= 1.0f))
        return bad(out_field, "ambient_ground_weight");
    if (!finite_nonneg(p->ms_depth)) return bad(out_field, "ms_depth");
    if (!(p->ms_thin >= 0.0f && p->ms_thin <= 1.0f)) return bad(out_field, "ms_thin");
    if (!(p->ms_view >= 0.0f && p->ms_view <= 1000.0f)) return bad(out_field, "ms_view");
    if (!(p->ms_view_trans >= 0.001f && p->ms_view_trans <= 1.0f)) return bad(out_field, "ms_view_trans");
    if (!(p->ambient_aniso >= 0.0f && p->ambient_aniso <= 1.0f)) return bad(out_field, "ambient_aniso");
    if (!(p->ms_slab >= 0.0f && p->ms_slab <= 1000.0f)) return bad(out_field, "ms_slab");
    if (!(p->ms_slab_mu >= 0.0f && p->ms_slab_mu <= 4.0f)) return bad(out_field, "ms_slab_mu");
    if (!(p->ms_slab_far >= 0.0f && p->ms_slab_far <= 1.0f)) return bad(out_field, "ms_slab_far");
    if (!(p->mie_delta >= 0.0f && p->mie_delta <= 1.0f)) return bad(out_field, "mie_delta");
    if (!(p->lod == 0 || p->lod == 1)) return bad(out_field, "lod");
    if (!(p->weather_detile == 0 || p->weather_detile == 1)) return bad(out_field, "weather_detile");
    if (!(p->lod_bias >= -4.0f && p->lod_bias <= 4.0f)) return bad(out_field, "lod_bias");
    if (!(p->refine_step_km >= 0.0f && p->refine_step_km < INFINITY)) return bad(out_field, "refine_step_km");
    if (!(p->refine_max >= 1 && p->refine_max <= 64)) return bad(out_field, "refine_max");
    if (!(p->march == CCL_CLOUDSCAPE_MARCH_FAST || p->march == CCL_CLOUDSCAPE_MARCH_TEXTBOOK))
        return bad(out_field, "march");
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
        /* the de-tiling's rotated lookups: |u'|, |v'| <= |u| + |v| + 1 (one period = weather_scale_km) */
        if (p->weather_detile &&
            !texcoord_ok(ex + ez, dabs(p->weather_offset[0]) + dabs(p->weather_offset[1]) + (double)p->weather_scale_km,
                         p->weather_scale_km, t->weather_size))
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
    if (!(sky->kind == CCL_SKY_GRADIENT || sky->kind == CCL_SKY_PREETHAM || sky->kind == CCL_SKY_PREETHAM_RADIANCE))
        return bad(out_field, "sky.kind");
    {
        /* | |sun| - 1 | <= 1e-3, the tolerance of the other unit-vector checks (registry UNIT_TOL); the march clamps
         * dot(d, sun) to [-1, 1], the domain of the phase function it feeds */
        const double s0 = (double)sky->sun[0], s1 = (double)sky->sun[1], s2 = (double)sky->sun[2];
        const double n = sqrt(s0 * s0 + s1 * s1 + s2 * s2);
        if (!(fabs(n - 1.0) <= 1e-3)) return bad(out_field, "sky.sun");
    }
    if (sky->kind == CCL_SKY_GRADIENT) {
        const ccl_sky_gradient *g = &sky->gradient;
        for (c = 0; c < 3; ++c)
            if (!(g->horizon[c] >= 0.0f && g->horizon[c] <= CCL_SKY_GRADIENT_MAX_COLOUR && g->zenith[c] >= 0.0f &&
                  g->zenith[c] <= CCL_SKY_GRADIENT_MAX_COLOUR && g->sun[c] >= 0.0f &&
                  g->sun[c] <= CCL_SKY_GRADIENT_MAX_COLOUR))
                return bad(out_field, "sky.gradient");
    } else if (sky->preetham.variant == CCL_VARIANT_THESIS &&
               !(sky->preetham.exposure > 0.0f && sky->preetham.exposure <= CCL_CLOUDSCAPE_MAX_THESIS_EXPOSURE)) {
        return bad(out_field, "sky.preetham.exposure");
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

static int mip_levels(int size)
{
    int n = 0;
    while (size > 0) {
        ++n;
        size >>= 1;
    }
    return n;
}

/* Level k of a mip chain: level 0 is tex itself, level k >= 1 lies in mips after the levels 1 .. k - 1. */
static const float *mip_level(const float *tex, const float *mips, int size, int k)
{
    size_t off = 0;
    int j;
    if (k == 0) return tex;
    for (j = 1; j < k; ++j) {
        const size_t n = (size_t)(size >> j);
        off += n * n * n;
    }
    return mips + off * 4u;
}

/* Trilinear wrap sample at a fractional mip level (twin of sample_mip in pywarp/kernels/cloudscape.py): level 0 for
 * lod <= 0 or without mips, the last level for lod >= levels - 1, else the blend of floor(lod) and floor(lod) + 1
 * (level lod alone for a whole lod). */
static void sample_mip(const float *tex, const float *mips, int size, float lod, ccl_vec3 p, float out[4])
{
    const int levels = mips != NULL ? mip_levels(size) : 1;
    float a[4], b[4], f;
    int k, c;
    if (!(lod > 0.0f) || levels <= 1) { /* a NaN lod too: level 0, never an int conversion of NaN */
        ccl_texgen_sample_trilinear_wrap(tex, size - 1, p.x, p.y, p.z, &out[0], &out[1], &out[2], &out[3]);
        return;
    }
    if (lod >= (float)(levels - 1)) {
        ccl_texgen_sample_trilinear_wrap(mip_level(tex, mips, size, levels - 1), (size >> (levels - 1)) - 1, p.x, p.y,
                                         p.z, &out[0], &out[1], &out[2], &out[3]);
        return;
    }
    f = lod - floorf(lod);
    k = (int)floorf(lod);
    ccl_texgen_sample_trilinear_wrap(mip_level(tex, mips, size, k), (size >> k) - 1, p.x, p.y, p.z, &a[0], &a[1],
                                     &a[2], &a[3]);
    if (f == 0.0f) { /* a whole level (the light samples'): one lookup */
        for (c = 0; c < 4; ++c) out[c] = a[c];
        return;
    }
    ccl_texgen_sample_trilinear_wrap(mip_level(tex, mips, size, k + 1), (size >> (k + 1)) - 1, p.x, p.y, p.z, &b[0],
                                     &b[1], &b[2], &b[3]);
    for (c = 0; c < 4; ++c) out[c] = a[c] + (b[c] - a[c]) * f;
}

float ccl_cloudscape_lod(float footprint_km, float texel_km, float bias)
{
    if (!(footprint_km > 0.0f)) return 0.0f;
    return log2f(footprint_km / texel_km) + bias;
}

size_t ccl_cloudscape_mip3_len(int size)
{
    size_t need = 0;
    int k;
    if (!is_pow2(size) || size > 4096) return 0;
    for (k = 1; (size >> k) > 0; ++k) need += (size_t)(size >> k) * (size_t)(size >> k) * (size_t)(size >> k) * 4u;
    return need;
}

ccl_status ccl_cloudscape_mip3(const float *tex, int size, float *out, size_t out_len)
{
    size_t n, x, y, z;
    const float *src = tex;
    float *dst = out;
    int c;
    if (tex == NULL || out == NULL || !is_pow2(size) || size > 4096) return CCL_EINVAL;
    if (out_len != ccl_cloudscape_mip3_len(size)) return CCL_EINVAL;
    for (n = (size_t)size; n > 1; n /= 2) {
        const size_t m = n / 2;
        for (z = 0; z < m; ++z)
            for (y = 0; y < m; ++y)
                for (x = 0; x < m; ++x)
                    for (c = 0; c < 4; ++c) {
#define T_(dz, dy, dx) src[(((2 * z + (dz)) * n + 2 * y + (dy)) * n + 2 * x + (dx)) * 4u + (size_t)c]
                        float s = T_(0, 0, 0) + T_(0, 0, 1);
                        s = s + T_(0, 1, 0);
                        s = s + T_(0, 1, 1);
                        s = s + T_(1, 0, 0);
                        s = s + T_(1, 0, 1);
                        s = s + T_(1, 1, 0);
                        s = s + T_(1, 1, 1);
#undef T_
                        dst[((z * m + y) * m + x) * 4u + (size_t)c] = s * 0.125f;
                    }
        src = dst;
        dst += m * m * m * 4u;
    }
    return CCL_OK;
}

float ccl_cloudscape_density(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 pos, int detail,
                             float *out_precipitation)
{
    return ccl_cloudscape_density_lod(p, t, pos, detail, 0.0f, 0.0f, out_precipitation);
}

void ccl_cloudscape_weather(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, float x_km, float z_km,
                            float *out_rgba)
{
    const float u = (x_km + p->weather_offset[0]) / p->weather_scale_km;
    const float v = (z_km + p->weather_offset[1]) / p->weather_scale_km;
    const float c = CCL_WEATHER_DETILE_COS, s = CCL_WEATHER_DETILE_SIN;
    float b[4], m[4], k;
    int i;
    if (!p->weather_detile) {
        ccl_cloudscape_sample_bilinear_wrap(t->weather, t->weather_size - 1, u, v, out_rgba);
        return;
    }
    /* the selector from the coverage of a much larger copy first: where it is 0 or 1 only one of the two maps is
     * read (the blend's value there: the map itself, or the rotated copy) */
    ccl_cloudscape_sample_bilinear_wrap(t->weather, t->weather_size - 1,
                                        (c * u + s * v) / CCL_WEATHER_DETILE_SCALE_M + CCL_WEATHER_DETILE_SHIFT_V,
                                        (c * v - s * u) / CCL_WEATHER_DETILE_SCALE_M + CCL_WEATHER_DETILE_SHIFT_U, m);
    k = (m[0] - CCL_WEATHER_DETILE_EDGE0) / (CCL_WEATHER_DETILE_EDGE1 - CCL_WEATHER_DETILE_EDGE0);
    k = ccl_interp_fade_cubic(k < 0.0f ? 0.0f : (k > 1.0f ? 1.0f : k));
    if (!(k >= 1.0f)) ccl_cloudscape_sample_bilinear_wrap(t->weather, t->weather_size - 1, u, v, out_rgba);
    if (k == 0.0f) return; /* (a NaN selector reads both and blends them: NaN, as the sampler outside its domain) */
    /* the map again, rotated, scaled and shifted */
    ccl_cloudscape_sample_bilinear_wrap(t->weather, t->weather_size - 1,
                                        (c * u - s * v) / CCL_WEATHER_DETILE_SCALE_B + CCL_WEATHER_DETILE_SHIFT_U,
                                        (s * u + c * v) / CCL_WEATHER_DETILE_SCALE_B + CCL_WEATHER_DETILE_SHIFT_V, b);
    if (k >= 1.0f) {
        for (i = 0; i < 4; ++i) out_rgba[i] = b[i];
        return;
    }
    for (i = 0; i < 4; ++i) out_rgba[i] = out_rgba[i] + (b[i] - out_rgba[i]) * k;
}

float ccl_cloudscape_density_lod(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 pos,
                                 int detail, float lod_base, float lod_detail, float *out_precipitation)
{
    const ccl_vec3 c = p->layer.centre;
    float r, h, w[4], base[4], curl[4], det[4], l_fbm, b, d_v, b_d, h_d;
    ccl_vec3 q;
    *out_precipitation = 0.0f;
    /* vc-A15: relative height in the layer */
    r = ccl_vec3_length(ccl_vec3_sub(pos, c));
    h = ccl_clouds_relative_height(r, p->layer.r_inner, p->layer.r_outer, CCL_VARIANT_CORRECTED);
    if (!(h >= 0.0f && h <= 1.0f)) return 0.0f;
    /* vc-A12: weather map, planar projection with wind (and the de-tiling, ccl_cloudscape_weather) */
    ccl_cloudscape_weather(p, t, pos.x, pos.z, w);
    *out_precipitation = w[1];
    if (!(w[0] > 0.0f)) return 0.0f;
    /* vc-4.7 / A16: vertical profile of the cloud type */
    d_v = ccl_clouds_height_gradient(h, w[2], p->gradient_clamp);
    if (!(d_v > 0.0f)) return 0.0f;
    /* vc-2.28: base shape */
    {
        ccl_vec3 u;
        u.x = pos.x / p->base_scale_km;
        u.y = pos.y / p->base_scale_km;
        u.z = pos.z / p->base_scale_km;
        sample_mip(t->base, t->base_mips, t->base_size, lod_base, u, base);
    }
    ccl_clouds_base_shape(base[0], base[1], base[2], base[3], &l_fbm, &b);
    /* vc-2.29: coverage with the threshold C read as 1 - D_h or D_h */
    b_d = ccl_clouds_coverage(b, d_v, w[0], p->coverage_threshold == CCL_COVERAGE_SAME ? w[0] : 1.0f - w[0], 1);
    if (!(b_d > 0.0f) || !detail) return b_d > 0.0f ? b_d : 0.0f;
    /* vc-2.30: detail erosion at curl-displaced coordinates */
    q.x = pos.x + p->detail_offset[0];
    q.y = pos.y + p->detail_offset[1];
    q.z = pos.z + p->detail_offset[2];
    if (lod_detail < (float)((t->detail_mips != NULL ? mip_levels(t->detail_size) : 1) - 1)) {
        /* the curl displacement (skipped at the detail's last level, the mean, which no position changes) */
        ccl_cloudscape_sample_bilinear_wrap(t->curl, t->curl_size - 1, pos.x / p->curl_scale_km,
                                            pos.z / p->curl_scale_km, curl);
        q.x = pos.x + curl[0] * p->curl_strength_km + p->detail_offset[0];
        q.z = pos.z + curl[1] * p->curl_strength_km + p->detail_offset[2];
    }
    h_d = ccl_clouds_relative_height(ccl_vec3_length(ccl_vec3_sub(q, c)), p->layer.r_inner, p->layer.r_outer,
                                     CCL_VARIANT_CORRECTED);
    h_d = h_d < 0.0f ? 0.0f : (h_d > 1.0f ? 1.0f : h_d);
    {
        ccl_vec3 u;
        u.x = q.x / p->detail_scale_km;
        u.y = q.y / p->detail_scale_km;
        u.z = q.z / p->detail_scale_km;
        sample_mip(t->detail, t->detail_mips, t->detail_size, lod_detail, u, det);
    }
    return ccl_clouds_detail_erosion(b_d, det[0], det[1], det[2], h_d, (ccl_detail_direction)p->detail_direction, 1);
}

/* --- lighting (see "Lighting" in cloudscape.h) ----------------------------------------------------------------- */

/* the parameters of ccl_phase_mie (the same float32 operations) */
static void mie_params(float d, float *g_hg, float *g_d, float *alpha, float *w_d)
{
    *g_hg = expf(-0.0990567f / (d - 1.67154f));
    *g_d = expf(-2.20679f / (d + 3.91029f) - 0.428934f);
    *alpha = expf(3.62489f - 8.29288f / (d + 5.52825f));
    *w_d = expf(-0.599085f / (d - 0.641583f) - 0.665888f);
}

float ccl_cloudscape_mie_delta_scale(float diameter_um, float f)
{
    float g_hg, g_d, alpha, w_d;
    CCL_REQUIRE(!(diameter_um < (float)CCL_PHASE_MIE_D_MIN || diameter_um > (float)CCL_PHASE_MIE_D_MAX));
    CCL_REQUIRE(!(f < 0.0f || f > 1.0f));
    mie_params(diameter_um, &g_hg, &g_d, &alpha, &w_d);
    return 1.0f - f * (1.0f - w_d);
}

float ccl_cloudscape_mie_delta_phase(float cos_theta, float diameter_um, float f)
{
    float g_hg, g_d, alpha, w_d, draine;
    CCL_REQUIRE(!(cos_theta < -1.0f || cos_theta > 1.0f));
    CCL_REQUIRE(!(diameter_um < (float)CCL_PHASE_MIE_D_MIN || diameter_um > (float)CCL_PHASE_MIE_D_MAX));
    CCL_REQUIRE(!(f < 0.0f || f > 1.0f));
    mie_params(diameter_um, &g_hg, &g_d, &alpha, &w_d);
    draine = ccl_phase_hg(cos_theta, g_d) * (1.0f + alpha * cos_theta * cos_theta) /
             (1.0f + alpha * (1.0f + 2.0f * g_d * g_d) / 3.0f);
    return ((1.0f - f) * (1.0f - w_d) * ccl_phase_hg(cos_theta, g_hg) + w_d * draine) / (1.0f - f * (1.0f - w_d));
}

float ccl_cloudscape_ms_gain(float d, float depth, float thin)
{
    CCL_REQUIRE(!(d < 0.0f) && !(depth < 0.0f) && !(thin < 0.0f || thin > 1.0f));
    if (!(depth > 0.0f)) return 1.0f;
    return thin + (1.0f - thin) * (1.0f - expf(-d / depth));
}

float ccl_cloudscape_ms_view(float trans, float k, float t0)
{
    CCL_REQUIRE(!(trans < 0.0f || trans > 1.0f) && !(k < 0.0f) && t0 > 0.0f);
    return 1.0f + k * fmaxf(1.0f - trans / t0, 0.0f);
}

float ccl_cloudscape_ms_slab(float mu0, float d, float trans, float k, float p, float s)
{
    float tau_v, r;
    CCL_REQUIRE(!(mu0 < -1.0f || mu0 > 1.0f) && !(d < 0.0f) && !(trans < 0.0f || trans > 1.0f) && !(k < 0.0f) &&
                !(p < 0.0f) && !(s < 0.0f || s > 1.0f));
    if (!(k > 0.0f)) return 1.0f;
    tau_v = -logf(fmaxf(trans, 1.0e-30f));
    r = d + tau_v > 0.0f ? d / (d + tau_v) : 0.0f;
    return k * powf(fmaxf(mu0, 0.0f), p) * (1.0f - s * r);
}

float ccl_cloudscape_ambient_aniso(float mu, float trans, float alpha)
{
    CCL_REQUIRE(!(mu < -1.0f || mu > 1.0f) && !(trans < 0.0f || trans > 1.0f) && !(alpha < 0.0f || alpha > 1.0f));
    return 1.0f + alpha * mu * trans;
}

float ccl_cloudscape_energy(const ccl_cloudscape_params *p, float d, float a, float cos_theta)
{
    /* octave i: contribution b^i, optical depth a^i d, eccentricities c^i g (Wrenninge et al. 2013, Hillaire 2016);
     * the i = 0 term is vc-2.31 in the operation order of ccl_clouds_energy: (beer * phase) * powder */
    float e = 0.0f, ai = 1.0f, bi = 1.0f, ci = 1.0f;
    const float mie = p->phase != CCL_CLOUDSCAPE_PHASE_MIE ? 0.0f
                      : p->mie_delta > 0.0f ? ccl_cloudscape_mie_delta_phase(cos_theta, p->droplet_um, p->mie_delta)
                                            : ccl_phase_mie(cos_theta, p->droplet_um);
    int i;
    const float gain = ccl_cloudscape_ms_gain(d, p->ms_depth, p->ms_thin);
    for (i = 0; i < p->ms_octaves; ++i) {
        const float di = d * ai;
        if (i == 1) bi *= gain; /* the octaves i >= 1 by the optical depth towards the sun (1 when ms_depth = 0) */
        const float beer = p->beer ? expf(-di * a) : 1.0f;
        const float powder = p->powder ? 1.0f - expf(-2.0f * di) : 1.0f;
        float phase;
        if (p->phase == CCL_CLOUDSCAPE_PHASE_MIE) {
            /* c^i of the Mie phase and 1 - c^i isotropic: the octave's mean cosine is c^i g, as with HG(c^i g) */
            phase = ci * mie + (1.0f - ci) * CCL_INV_4PI_F;
        } else {
            phase = ccl_phase_hg(cos_theta, p->g * ci);
            if (p->silver_weight > 0.0f) /* dual lobe: (1 - w) HG(g) + w HG(silver_g) */
                phase = (1.0f - p->silver_weight) * phase +
                        p->silver_weight * ccl_phase_hg(cos_theta, p->silver_g * ci);
        }
        e += bi * beer * phase * powder;
        ai *= p->ms_a;
        bi *= p->ms_b;
        ci *= p->ms_c;
    }
    return e;
}

/* value noise of the ground patches: lattice values in [0, 1) from the hash, smoothstep-interpolated; coordinates
 * bounded to +-2^23 cells before the cast (far beyond any ground point) */
static float ground_noise(float x, float z)
{
    const float lim = 8388608.0f;
    float fx = floorf(fminf(fmaxf(x, -lim), lim)), fz = floorf(fminf(fmaxf(z, -lim), lim));
    float u = fminf(fmaxf(x - fx, 0.0f), 1.0f), v = fminf(fmaxf(z - fz, 0.0f), 1.0f);
    uint32_t ix = (uint32_t)(int32_t)fx, iz = (uint32_t)(int32_t)fz;
    float a = ccl_hash_unit(ccl_hash_pcg(ccl_hash_pcg(ix) ^ iz));
    float b = ccl_hash_unit(ccl_hash_pcg(ccl_hash_pcg(ix + 1u) ^ iz));
    float c = ccl_hash_unit(ccl_hash_pcg(ccl_hash_pcg(ix) ^ (iz + 1u)));
    float d = ccl_hash_unit(ccl_hash_pcg(ccl_hash_pcg(ix + 1u) ^ (iz + 1u)));
    u = u * u * (3.0f - 2.0f * u);
    v = v * v * (3.0f - 2.0f * v);
    return (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v;
}

void ccl_cloudscape_ground(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 point,
                           ccl_vec3 to_sun, float *out_rgb, float *out_shadow)
{
    float patch = 1.0f;
    const ccl_cloud_layer *L = &p->layer;
    ccl_vec3 n = ccl_vec3_sub(point, L->centre);
    float a0, a1, b0, b1, cos_sun, shadow = 1.0f, k;
    int c;
    n = ccl_vec3_scale(n, 1.0f / ccl_vec3_length(n));
    cos_sun = ccl_vec3_dot(n, to_sun);
    cos_sun = cos_sun > 0.0f ? cos_sun : 0.0f;
    /* T_shadow: the ray towards the sun crosses the layer between the far roots of the inner and outer spheres */
    if (cos_sun > 0.0f && ccl_raymarch_ray_sphere(point, to_sun, L->centre, L->r_inner, &a0, &a1) &&
        ccl_raymarch_ray_sphere(point, to_sun, L->centre, L->r_outer, &b0, &b1)) {
        const float ts = a1 > 0.0f ? a1 : 0.0f;
        const float dt = (b1 - ts) / (float)CCL_CLOUDSCAPE_GROUND_SHADOW_SAMPLES;
        const float lod = p->lod ? ccl_cloudscape_lod(dt, p->base_scale_km / (float)t->base_size, p->lod_bias)
                                 : 0.0f;
        float od = 0.0f, pr;
        int i;
        if (dt > 0.0f) {
            for (i = 0; i < CCL_CLOUDSCAPE_GROUND_SHADOW_SAMPLES; ++i) {
                const ccl_vec3 q = ccl_raymarch_point(point, to_sun, ts, dt, i, 0.5f);
                od += ccl_cloudscape_density_lod(p, t, q, 0, lod, 0.0f, &pr);
            }
            shadow = expf(-p->sigma_light * (od * dt));
        }
    }
    /* Lambertian: albedo / pi x sun irradiance x cos, plus albedo x the cosine-weighted sky radiance */
    k = cos_sun * shadow * 0.318309886f; /* 1 / pi */
    if (p->ground_variation > 0.0f) {
        const float x = point.x / CCL_CLOUDSCAPE_GROUND_PATCH_KM, z = point.z / CCL_CLOUDSCAPE_GROUND_PATCH_KM;
        const float noise = (2.0f * ground_noise(x, z) + ground_noise(4.0f * x, 4.0f * z)) / 3.0f;
        patch = 1.0f + p->ground_variation * (2.0f * noise - 1.0f);
    }
    for (c = 0; c < 3; ++c)
        out_rgb[c] = p->ground_albedo[c] * patch * (p->sun_colour[c] * k + p->ambient_ground[c]);
    if (out_shadow) *out_shadow = shadow;
}

/* The sky model's display-linear colour of a unit direction. */
static ccl_vec3 sky_rgb(const ccl_cloudscape_sky *sky, ccl_vec3 d, ccl_vec3 sun)
{
    if (sky->kind == CCL_SKY_PREETHAM_RADIANCE) {
        /* k C_HDR with the out-of-gamut (negative) channels at 0, as the tone-mapped sky clips them */
        const ccl_vec3 c = ccl_sky_preetham_hdr(d, sun, &sky->preetham);
        const float k = sky->preetham.exposure;
        ccl_vec3 r;
        r.x = c.x < 0.0f ? 0.0f : k * c.x;
        r.y = c.y < 0.0f ? 0.0f : k * c.y;
        r.z = c.z < 0.0f ? 0.0f : k * c.z;
        return r;
    }
    return (sky->kind == CCL_SKY_PREETHAM) ? ccl_sky_preetham_rgb(d, sun, &sky->preetham)
                                           : ccl_sky_gradient_rgb(d, sun, &sky->gradient);
}

void ccl_cloudscape_light(const ccl_cloudscape_params *p, const ccl_cloudscape_sky *sky, ccl_cloudscape_params *out)
{
    ccl_cloudscape_params q = *p;
    if (p->lighting == CCL_LIGHTING_SKY) {
        const float dtheta = 1.5707963f / (float)CCL_CLOUDSCAPE_SKY_THETA_CELLS;
        const float dphi = 6.2831853f / (float)CCL_CLOUDSCAPE_SKY_PHI_CELLS;
        float cos_s = sky->sun[1], mean[3] = {0.0f, 0.0f, 0.0f}, cmean[3] = {0.0f, 0.0f, 0.0f}, wsum = 0.0f,
              csum = 0.0f, e_sun;
        ccl_vec3 sun, att;
        int i, j, c;
        sun.x = sky->sun[0];
        sun.y = sky->sun[1];
        sun.z = sky->sun[2];
        /* the sun through the atmosphere (Preetham et al. 1999 A.1) */
        cos_s = cos_s < 0.0f ? 0.0f : (cos_s > 1.0f ? 1.0f : cos_s);
        att = ccl_sky_sun_attenuation(acosf(cos_s), p->turbidity);
        /* physical units: the sun's illuminance above the atmosphere x the one exposure of the sky */
        e_sun = sky->kind == CCL_SKY_PREETHAM_RADIANCE
                    ? sky->preetham.exposure * ((float)CCL_CLOUDSCAPE_SUN_KLX_X10 * 0.1f) : p->sun_intensity;
        q.sun_colour[0] = e_sun * att.x;
        q.sun_colour[1] = e_sun * att.y;
        q.sun_colour[2] = e_sun * att.z;
        /* the sky's mean and cosine-weighted mean over the upper hemisphere, midpoint rule */
        for (i = 0; i < CCL_CLOUDSCAPE_SKY_THETA_CELLS; ++i) {
            const float theta = ((float)i + 0.5f) * dtheta, st = sinf(theta), ct = cosf(theta), wc = st * ct;
            for (j = 0; j < CCL_CLOUDSCAPE_SKY_PHI_CELLS; ++j) {
                const float phi = ((float)j + 0.5f) * dphi;
                ccl_vec3 d, s;
                float v[3];
                d.x = st * sinf(phi);
                d.y = ct;
                d.z = -st * cosf(phi);
                s = sky_rgb(sky, d, sun);
                v[0] = s.x > 0.0f ? s.x : 0.0f; /* out-of-gamut Preetham colours: no negative light */
                v[1] = s.y > 0.0f ? s.y : 0.0f;
                v[2] = s.z > 0.0f ? s.z : 0.0f;
                for (c = 0; c < 3; ++c) {
                    mean[c] += v[c] * st;
                    cmean[c] += v[c] * wc;
                }
                wsum += st;
                csum += wc;
            }
        }
        for (c = 0; c < 3; ++c) {
            /* the lower hemisphere's share: the unshadowed Lambertian ground under the sun and the sky */
            const float w = p->ambient_ground_weight;
            float ground;
            q.ambient_ground[c] = cmean[c] / csum;
            ground = p->ground_albedo[c] * (q.sun_colour[c] * (cos_s * 0.318309886f) + q.ambient_ground[c]);
            q.ambient_top[c] = (1.0f - w) * (mean[c] / wsum) + w * ground;
            q.ambient_bottom[c] = p->ambient_bottom_ratio * q.ambient_top[c];
        }
        if (p->phase == CCL_CLOUDSCAPE_PHASE_MIE && p->mie_delta > 0.0f) {
            /* delta scaling: the forward peak's share mie_delta goes on unscattered (ccl_cloudscape_mie_delta_scale) */
            const float scale = ccl_cloudscape_mie_delta_scale(p->droplet_um, p->mie_delta);
            q.sigma = p->sigma * scale;
            q.sigma_light = p->sigma_light * scale;
        }
    }
    *out = q;
}

/* The coarse test of the march (the refinement's, once per long view step, and a group's, at each end): 1 where the
 * base shape (no detail) at ray distance t_c has density > 0, at the mip level of footprint_km, else 0. The detail
 * only erodes, so 0 at a view sample's own footprint means that the view sample has density 0 too. */
static int coarse_cloud(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 eye, ccl_vec3 dir,
                        float t_c, float footprint_km)
{
    float lod = 0.0f, precip;
    if (p->lod) lod = ccl_cloudscape_lod(footprint_km, p->base_scale_km / (float)t->base_size, p->lod_bias);
    return ccl_cloudscape_density_lod(p, t, ccl_vec3_add(eye, ccl_vec3_scale(dir, t_c)), 0, lod, 0.0f, &precip) > 0.0f;
}

/* vc-A19: the optical depth towards the sun of a lit sample at pos (ray distance t_i) from 6 cone samples */
static float light_depth(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 pos, ccl_vec3 to_sun,
                         float t_i, float pixel_angle)
{
    float lod_lb = 0.0f, lod_ld = 0.0f, d_light = 0.0f;
    int j;
    if (p->lod) {
        /* the light samples at the nearest whole level: one lookup each instead of a blend of two (the optical depth
         * towards the sun is a sum of six samples, smooth where the view's colour is not) */
        const float fl = fmaxf(t_i * pixel_angle, p->light_step_km);
        lod_lb = floorf(ccl_cloudscape_lod(fl, p->base_scale_km / (float)t->base_size, p->lod_bias) + 0.5f);
        lod_ld = floorf(ccl_cloudscape_lod(fl, p->detail_scale_km / (float)t->detail_size, p->lod_bias) + 0.5f);
    }
    for (j = 0; j < 6; ++j) {
        float pj, w = j < 5 ? p->light_step_km : (p->light_far_factor - 1.0f) * 5.0f * p->light_step_km;
        ccl_vec3 q = ccl_raymarch_light_sample_position(pos, to_sun, j, p->light_step_km, p->light_cone_angle,
                                                        p->light_far_factor, ccl_raymarch_light_cone_kernel(j));
        d_light += w * ccl_cloudscape_density_lod(p, t, q, p->light_detail, lod_lb, lod_ld, &pj);
    }
    return d_light * p->sigma_light;
}

/* vc-2.31 + vc-A20: the light of a lit sample from its optical depth towards the sun (E of vc-2.31 with the
 * multiple-scattering octaves, dual-lobe phase, beer / powder flags) and the ambient by relative height; trans: the
 * view transmittance in front of the sample and view the view direction, for the octaves' weight by the depth into
 * the cloud (vc-x-ms-view) and the ambient's anisotropy (vc-x-ambient-aniso); to_sun for the octaves' weight by the
 * sun's elevation and the sample's place between the sun and the viewer (vc-x-ms-slab); all 1 at their defaults */
static ccl_vec3 sample_light(const ccl_cloudscape_params *p, float d_light, float precip, ccl_vec3 pos,
                             float cos_theta, float trans, ccl_vec3 view, ccl_vec3 to_sun)
{
    const ccl_cloud_layer *L = &p->layer;
    const float a = p->absorption_base + p->absorption_precip * precip;
    float e = ccl_cloudscape_energy(p, d_light, a, cos_theta);
    const ccl_vec3 rel = ccl_vec3_sub(pos, L->centre);
    const float h = ccl_clouds_relative_height(ccl_vec3_length(rel), L->r_inner, L->r_outer,
                                               CCL_VARIANT_CORRECTED);
    /* the ambient's anisotropy by the view direction and the octaves' weight by the depth into the cloud along the
     * view (vc-x-ambient-aniso, vc-x-ms-view; 1 at their defaults) */
    const float amb_w = p->ambient_aniso > 0.0f /* (off: no normalisation per sample) */
                            ? ccl_cloudscape_ambient_aniso(ccl_vec3_dot(view, ccl_vec3_normalize(rel)), trans,
                                                           p->ambient_aniso)
                            : 1.0f;
    ccl_vec3 light;
    if ((p->ms_view > 0.0f || p->ms_slab > 0.0f) && p->ms_octaves > 1) {
        /* the octaves i >= 1 (the whole energy less that of one octave) by the depth into the cloud and by the sun's
         * elevation and the sample's place between the sun and the viewer (vc-x-ms-slab) */
        ccl_cloudscape_params q = *p;
        float e1, w = 1.0f;
        q.ms_octaves = 1;
        e1 = ccl_cloudscape_energy(&q, d_light, a, cos_theta);
        if (p->ms_view > 0.0f) w = ccl_cloudscape_ms_view(trans, p->ms_view, p->ms_view_trans);
        if (p->ms_slab > 0.0f)
            w *= ccl_cloudscape_ms_slab(fminf(fmaxf(ccl_vec3_dot(to_sun, ccl_vec3_normalize(rel)), -1.0f), 1.0f),
                                        d_light, trans, p->ms_slab, p->ms_slab_mu, p->ms_slab_far);
        e = e1 + (e - e1) * w;
    }
    light.x = p->sun_colour[0] * e + amb_w * (p->ambient_bottom[0] + (p->ambient_top[0] - p->ambient_bottom[0]) * h);
    light.y = p->sun_colour[1] * e + amb_w * (p->ambient_bottom[1] + (p->ambient_top[1] - p->ambient_bottom[1]) * h);
    light.z = p->sun_colour[2] * e + amb_w * (p->ambient_bottom[2] + (p->ambient_top[2] - p->ambient_bottom[2]) * h);
    return light;
}

/* 1 where a sample of density rho and length dt ends the ray at transmittance trans: the stop flag of
 * ccl_raymarch_accumulate (vc-A21) for that sample (its colour does not matter: none is passed), with the early exit
 * on. Such a sample does not wait for the light interpolation: it gets its own optical depth at once, and the next
 * sample's, which the interpolation would need, is never computed (the ray stops there) */
static int ends_ray(const ccl_cloudscape_params *p, float trans, float rho, float dt)
{
    const ccl_vec3 zero = {0.0f, 0.0f, 0.0f};
    float t;
    int stop;
    (void)ccl_raymarch_accumulate(zero, trans, p->sigma, rho, dt, zero, p->exit_eps, &t, &stop);
    return p->early_exit && stop;
}

/* vc-A21 for one lit sample at ray distance t_i, front to back, and the early exit with its fill; 1 where the ray
 * stops */
static int march_sample(const ccl_cloudscape_params *p, float rho, float dt, ccl_vec3 light, float t_i,
                        ccl_vec3 *colour, float *trans, float *depth_w, float *depth_sum)
{
    const float t_before = *trans;
    int stop;
    *colour = ccl_raymarch_accumulate(*colour, t_before, p->sigma, rho, dt, light, p->exit_eps, trans, &stop);
    /* the sample's weight in the pixel, for the mean distance of the aerial perspective */
    *depth_w += t_before - *trans;
    *depth_sum += (t_before - *trans) * t_i;
    if (!(stop && p->early_exit)) return 0;
    if (p->exit_fill) {
        /* the rest of the ray's weight, T, takes the last sample's light (see exit_fill) */
        *colour = ccl_vec3_add(*colour, ccl_vec3_scale(light, *trans));
        *depth_w += *trans;
        *depth_sum += *trans * t_i;
        *trans = 0.0f;
    }
    return 1;
}

/* --- the textbook march (vc-A18..A21 as the thesis prints the loop, §4.3.2) -----------------------------------------
 * For reading beside the text: the same density (vc-A17), light (vc-2.31, vc-A20) and accumulation (vc-A21) as the
 * fast march below, in the thesis's loop. Its symbols: d the optical depth towards the sun, a the precipitation
 * coefficient and theta the angle of HG in E (vc-2.31); C the colour of the clouds (C_clouds of vc-4.8) and T the view
 * transmittance, O_D = 1 - T. */

/* vc-A19: the optical depth d towards the sun of the sample at pos: six pseudo-random samples q_j in a cone from pos
 * towards the sun, each further out and further to the side; five near ones (a light step apart), the sixth at
 * light_far_factor times their distance. Each density counts for the length w_j of the path it stands for. */
static float textbook_light_depth(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 pos,
                                  ccl_vec3 to_sun)
{
    float d = 0.0f, precip_j;
    int j;
    for (j = 0; j < 6; ++j) {
        const float w_j = j < 5 ? p->light_step_km : (p->light_far_factor - 1.0f) * 5.0f * p->light_step_km;
        const ccl_vec3 q_j = ccl_raymarch_light_sample_position(pos, to_sun, j, p->light_step_km,
                                                                p->light_cone_angle, p->light_far_factor,
                                                                ccl_raymarch_light_cone_kernel(j));
        d += w_j * ccl_cloudscape_density(p, t, q_j, p->light_detail, &precip_j);
    }
    return d * p->sigma_light;
}

void ccl_cloudscape_march_textbook(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 eye,
                                   ccl_vec3 dir, ccl_vec3 to_sun, float offset, float *out_rgb,
                                   float *out_transmittance, int *out_samples, float *out_depth_km)
{
    ccl_vec3 C = {0.0f, 0.0f, 0.0f};
    float T = 1.0f, t0, t1, t_start = 0.0f, dt = 0.0f, depth_w = 0.0f, depth_sum = 0.0f;
    /* theta of HG: |dir| and |to_sun| are 1 only to within rounding, keep cos(theta) in [-1, 1] */
    const float cos_theta = fminf(fmaxf(ccl_vec3_dot(dir, to_sun), -1.0f), 1.0f);
    int n = 0, i, taken = 0;
    /* vc-A14 / A24: the start and end points, where the ray crosses the layer; vc-A18: n samples between them, 64
     * towards the zenith .. 128 towards the horizon (or always samples_max) */
    if (ccl_raymarch_layer_segment(eye, dir, p->layer.centre, p->layer.r_earth, p->layer.r_inner, p->layer.r_outer,
                                   &t0, &t1)) {
        n = p->adaptive_samples ? ccl_raymarch_view_sample_count(dir.y, p->samples_min, p->samples_max)
                                : p->samples_max;
        if (!ccl_raymarch_interval(t0, t1, n, &t_start, &dt)) n = 0;
    }
    for (i = 0; i < n; ++i) {
        const float t_i = t_start + ((float)i + offset) * dt;
        const ccl_vec3 pos = ccl_raymarch_point(eye, dir, t_start, dt, i, offset);
        float precip, rho, d;
        ++taken;
        rho = ccl_cloudscape_density(p, t, pos, 1, &precip); /* vc-A17, full resolution */
        if (!(rho > 0.0f)) continue;
        d = textbook_light_depth(p, t, pos, to_sun); /* vc-A19: only where the density is non-zero */
        /* vc-2.31 + vc-A20: L = sun E(d, a, theta, g) + the ambient by relative height; vc-A21: C += T (1 -
         * exp(-sigma rho dt)) L, T *= exp(-sigma rho dt), and stop once O_D = 1 - T has reached its maximum */
        if (march_sample(p, rho, dt, sample_light(p, d, precip, pos, cos_theta, T, dir, to_sun), t_i, &C, &T,
                         &depth_w, &depth_sum))
            break;
    }
    out_rgb[0] = C.x;
    out_rgb[1] = C.y;
    out_rgb[2] = C.z;
    *out_transmittance = T;
    *out_samples = taken;
    if (out_depth_km) *out_depth_km = depth_w > 0.0f ? depth_sum / depth_w : 0.0f;
}

/* --- the fast march --------------------------------------------------------------------------------------------- */

void ccl_cloudscape_march(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 eye, ccl_vec3 dir,
                          ccl_vec3 to_sun, float offset, float pixel_angle, float *out_rgb, float *out_transmittance,
                          int *out_samples, float *out_depth_km)
{
    ccl_vec3 colour = {0.0f, 0.0f, 0.0f};
    float trans = 1.0f, t0, t1, t_start, dt, dt_view, cos_theta, depth_sum = 0.0f, depth_w = 0.0f;
    int n, i, k, m, sub, grp, prev_cloud = 0, next_cloud = -1, ahead = -1, taken = 0;
    /* light interpolation: the waiting sample, and the last lit sample whose optical depth was computed */
    int pend = 0, computed = 0;
    float pend_rho = 0.0f, pend_t = 0.0f, pend_precip = 0.0f, d_prev = 0.0f, t_prev = 0.0f;
    ccl_vec3 pend_pos = {0.0f, 0.0f, 0.0f}, light_prev = {0.0f, 0.0f, 0.0f};
    const ccl_cloud_layer *L = &p->layer;
    if (p->march == CCL_CLOUDSCAPE_MARCH_TEXTBOOK) {
        ccl_cloudscape_march_textbook(p, t, eye, dir, to_sun, offset, out_rgb, out_transmittance, out_samples,
                                      out_depth_km);
        return;
    }
    if (ccl_raymarch_layer_segment(eye, dir, L->centre, L->r_earth, L->r_inner, L->r_outer, &t0, &t1)) {
        n = p->adaptive_samples ? ccl_raymarch_view_sample_count(dir.y, p->samples_min, p->samples_max)
                                : p->samples_max;
        cos_theta = ccl_vec3_dot(dir, to_sun);
        /* |d| and |to_sun| are 1 only to within rounding (and the check's tolerance): keep the phase function's
         * argument in its domain [-1, 1] */
        cos_theta = cos_theta > 1.0f ? 1.0f : (cos_theta < -1.0f ? -1.0f : cos_theta);
        if (ccl_raymarch_interval(t0, t1, n, &t_start, &dt_view)) {
            /* no view step longer than refine_step_km x refine_max where refinement is on (the coarse test would
             * miss clouds between its points): more steps, at most CCL_CLOUDSCAPE_COARSE_MAX_FACTOR x samples_max */
            if (p->refine_step_km > 0.0f) {
                const float longest = p->refine_step_km * (float)p->refine_max;
                if (dt_view > longest) {
                    const float need = ceilf(dt_view * (float)n / longest);
                    const int most = CCL_CLOUDSCAPE_COARSE_MAX_FACTOR * p->samples_max;
                    const int n2 = need < (float)most ? (int)need : most;
                    if (n2 > n) {
                        n = n2;
                        ccl_raymarch_interval(t0, t1, n, &t_start, &dt_view);
                    }
                }
            }
            /* refinement: a view step longer than refine_step_km is split into k sub-steps where the coarse test
             * (base shape, no detail, at the step's own sample) finds cloud here or at the previous step; an empty
             * step costs that one lookup */
            k = 1;
            if (p->refine_step_km > 0.0f && dt_view > p->refine_step_km) {
                const float kf = ceilf(dt_view / p->refine_step_km);
                k = kf < (float)p->refine_max ? (int)kf : p->refine_max;
            }
            dt = dt_view / (float)k;
            /* grouping: where the view steps are already no longer than refine_step_km (k = 1), up to refine_max
             * of them, spanning at most CCL_CLOUDSCAPE_GROUP_SPAN x refine_step_km, share a coarse test at each end
             * of the group and are skipped together where both find no cloud */
            grp = 1;
            if (k == 1 && p->refine_step_km > 0.0f) {
                const float gf = floorf(CCL_CLOUDSCAPE_GROUP_SPAN * p->refine_step_km / dt_view);
                /* (also a zero-length segment: never an int conversion of inf) */
                if (gf >= (float)p->refine_max) grp = p->refine_max;
                else if (gf > 1.0f) grp = (int)gf;
            }
            m = 0;
            while (m < n * k) {
                float precip, rho, t_i, d_cur;
                ccl_vec3 pos, light;
                float lod_b = 0.0f, lod_d = 0.0f;
                i = m / k;
                sub = m - i * k;
                if (grp > 1 && m % grp == 0) {
                    /* k = 1: the group's first view sample is at t_g itself, with the same footprint */
                    const float t_g = t_start + ((float)m + offset) * dt_view;
                    const float t_n = t_start + ((float)(m + grp) + offset) * dt_view;
                    int here = next_cloud;
                    if (here < 0) {
                        here = coarse_cloud(p, t, eye, dir, t_g, t_g * pixel_angle);
                        ++taken;
                    }
                    next_cloud = coarse_cloud(p, t, eye, dir, t_n, t_n * pixel_angle);
                    ++taken;
                    if (!here && !next_cloud) {
                        m += grp;
                        continue;
                    }
                    if (!here) { /* the first view sample: density 0, as its coarse test found (counted, as skipped) */
                        ++m;
                        ++taken;
                        continue;
                    }
                }
                if (k > 1 && sub == 0) {
                    /* the step's coarse test (made ahead by the previous step), and the next step's: a cloud found
                     * there may begin within this step (its samples lie between the coarse points of the previous
                     * and the next step) */
                    const float t_c = t_start + ((float)i + offset) * dt_view;
                    const int cloud = ahead >= 0 ? ahead
                                                 : coarse_cloud(p, t, eye, dir, t_c, fmaxf(t_c * pixel_angle, dt_view));
                    ++taken;
                    ahead = 0;
                    if (i + 1 < n) {
                        const float t_a = t_start + ((float)(i + 1) + offset) * dt_view;
                        ahead = coarse_cloud(p, t, eye, dir, t_a, fmaxf(t_a * pixel_angle, dt_view));
                    }
                    if (!cloud && !prev_cloud && !ahead) {
                        m += k;
                        continue;
                    }
                    prev_cloud = cloud;
                }
                t_i = t_start + ((float)i + ((float)sub + offset) / (float)k) * dt_view;
                pos = ccl_vec3_add(eye, ccl_vec3_scale(dir, t_i));
                ++m;
                ++taken;
                if (p->lod) {
                    /* footprint of the sample: the pixel's width at its distance (the refinement keeps the steps
                     * short where there is cloud, so they need no blur along the ray) */
                    const float fp = t_i * pixel_angle;
                    lod_b = ccl_cloudscape_lod(fp, p->base_scale_km / (float)t->base_size, p->lod_bias);
                    lod_d = ccl_cloudscape_lod(fp, p->detail_scale_km / (float)t->detail_size, p->lod_bias);
                }
                rho = ccl_cloudscape_density_lod(p, t, pos, 1, lod_b, lod_d, &precip);
                if (!(rho > 0.0f)) continue;
                /* light interpolation (light_interp): the lit sample right after one whose optical depth towards the
                 * sun was computed waits for the next lit sample */
                if (p->light_interp > 0.0f && !pend && computed && t_i - t_prev <= 1.5f * dt &&
                    !ends_ray(p, trans, rho, dt)) {
                    pend = 1;
                    pend_rho = rho;
                    pend_t = t_i;
                    pend_precip = precip;
                    pend_pos = pos;
                    continue;
                }
                d_cur = light_depth(p, t, pos, to_sun, t_i, pixel_angle);
                light = sample_light(p, d_cur, precip, pos, cos_theta, trans, dir, to_sun);
                if (pend) {
                    /* the waiting sample: the mean of its neighbours' optical depths where it is the middle of three
                     * consecutive samples and its weight in the pixel times the largest difference of their lights
                     * is at most light_interp, else its own */
                    /* (it does not end the ray: a sample that would, by ends_ray, does not wait) */
                    const float w_p = trans * (1.0f - expf(-p->sigma * pend_rho * dt));
                    const float diff = fmaxf(fabsf(light.x - light_prev.x),
                                             fmaxf(fabsf(light.y - light_prev.y), fabsf(light.z - light_prev.z)));
                    float d_p = 0.5f * (d_prev + d_cur);
                    pend = 0;
                    if (t_i - pend_t > 1.5f * dt || w_p * diff > p->light_interp)
                        d_p = light_depth(p, t, pend_pos, to_sun, pend_t, pixel_angle);
                    if (march_sample(p, pend_rho, dt,
                                     sample_light(p, d_p, pend_precip, pend_pos, cos_theta, trans, dir, to_sun),
                                     pend_t, &colour, &trans, &depth_w, &depth_sum))
                        break;
                    /* this sample's light at the transmittance in front of it, now past the waiting sample (the
                     * terms that read it: vc-x-ms-view, vc-x-ms-slab, vc-x-ambient-aniso) */
                    if (p->ms_view > 0.0f || p->ms_slab > 0.0f || p->ambient_aniso > 0.0f)
                        light = sample_light(p, d_cur, precip, pos, cos_theta, trans, dir, to_sun);
                }
                computed = 1;
                d_prev = d_cur;
                light_prev = light;
                t_prev = t_i;
                if (march_sample(p, rho, dt, light, t_i, &colour, &trans, &depth_w, &depth_sum)) break;
            }
            if (pend) /* the ray ended with a sample waiting (a stop never leaves one) */
                march_sample(p, pend_rho, dt,
                             sample_light(p, light_depth(p, t, pend_pos, to_sun, pend_t, pixel_angle), pend_precip,
                                          pend_pos, cos_theta, trans, dir, to_sun),
                             pend_t, &colour, &trans, &depth_w, &depth_sum);
        }
    }
    out_rgb[0] = colour.x;
    out_rgb[1] = colour.y;
    out_rgb[2] = colour.z;
    *out_transmittance = trans;
    *out_samples = taken;
    if (out_depth_km) *out_depth_km = depth_w > 0.0f ? depth_sum / depth_w : 0.0f;
}

/* (d.x, max(d.y, 0), d.z) normalised, (0, 0, -1) at the nadir: the haze direction of the aerial perspective */
static ccl_vec3 lift_to_horizon(ccl_vec3 d)
{
    ccl_vec3 h = d;
    float len;
    if (h.y < 0.0f) h.y = 0.0f;
    len = ccl_vec3_length(h);
    if (!(len > 1e-6f)) {
        h.x = 0.0f;
        h.y = 0.0f;
        h.z = -1.0f;
        return h;
    }
    return ccl_vec3_scale(h, 1.0f / len);
}

/* t_air of the aerial perspective (see "Lighting" in cloudscape.h): the length of ground-level air with the optical
 * depth of the first t km of the ray, the haze thinning with altitude (scale height aerial_height_km; 0: t). */
static float aerial_air_km(const ccl_cloudscape_params *p, ccl_vec3 eye, ccl_vec3 d, float t)
{
    const float hs = p->aerial_height_km;
    ccl_vec3 r;
    float len, y0, u, x, a0, t_air;
    if (!(hs > 0.0f)) return t;
    r = ccl_vec3_sub(eye, p->layer.centre);
    len = ccl_vec3_length(r);
    y0 = len - p->layer.r_earth;
    y0 = y0 > 0.0f ? y0 : 0.0f;
    u = ccl_vec3_dot(d, r) / len; /* the ray's vertical component at the camera */
    x = u * t / hs;
    a0 = expf(-y0 / hs);
    if (fabsf(x) < 1e-3f)
        t_air = t * a0 * (1.0f - 0.5f * x);
    else
        t_air = (a0 - expf(-(y0 + u * t) / hs)) * (hs / u);
    return t_air < t ? t_air : t;
}

/* The pixel's coverage by the Earth (sky lighting's anti-aliased horizon): the ray's elevation above the horizon
 * seen from the eye, a = asin(d . up) + acos(r_earth / |eye - centre|) (the horizon dips below the horizontal), in
 * units of the pixel's angular size, box-filtered: clamp(0.5 - a / pixel_angle, 0, 1) -- 1 well below the horizon,
 * 0 well above, the covered fraction of a pixel the horizon crosses. Twin of horizon_coverage in
 * pywarp/kernels/cloudscape.py. */
static float horizon_coverage(const ccl_cloudscape_params *p, ccl_vec3 eye, ccl_vec3 d, float pixel_angle)
{
    const ccl_vec3 r = ccl_vec3_sub(eye, p->layer.centre);
    const float len = ccl_vec3_length(r);
    float s = ccl_vec3_dot(d, r) / len, q = p->layer.r_earth / len, a, cov;
    s = s > 1.0f ? 1.0f : (s < -1.0f ? -1.0f : s);
    q = q > 1.0f ? 1.0f : q;
    if (!(pixel_angle > 0.0f)) return s < 0.0f ? 1.0f : 0.0f;
    a = asinf(s) + acosf(q);
    cov = 0.5f - a / pixel_angle;
    return cov < 0.0f ? 0.0f : (cov > 1.0f ? 1.0f : cov);
}

/* Sky lighting's ground and aerial perspective (see "Lighting" in cloudscape.h): out = B T + C' with B the lit ground
 * faded by distance (ground) or the haze colour (sky), C' the clouds faded by their mean distance. B is anti-aliased
 * at the horizon: the haze + (ground - haze) x the pixel's coverage by the Earth (horizon_coverage), the ground of a
 * ray that passes above the Earth taken at the horizon's distance. */
static void sky_lit_composite(const ccl_cloudscape_params *p, const ccl_cloud_textures *t, ccl_vec3 eye, ccl_vec3 d,
                              ccl_vec3 sun, const float haze[3], int ground, float t_ground, const float cl[3],
                              float trans, float depth_km, float pixel_angle, float *out_rgb)
{
    float bg[3], f_g = 1.0f, f_c = 1.0f;
    const float cov = horizon_coverage(p, eye, d, pixel_angle);
    int c;
    if (!ground && cov > 0.0f) {
        /* a ray just above the horizon, in a pixel the horizon crosses: the ground at the horizon's distance */
        const float len = ccl_vec3_length(ccl_vec3_sub(eye, p->layer.centre));
        const float h2 = (len - p->layer.r_earth) * (len + p->layer.r_earth);
        t_ground = h2 > 0.0f ? sqrtf(h2) : 0.0f;
    }
    if (p->aerial_km > 0.0f) {
        f_g = expf(-aerial_air_km(p, eye, d, t_ground) / p->aerial_km);
        f_c = expf(-aerial_air_km(p, eye, d, depth_km) / p->aerial_km);
    }
    if (ground || cov > 0.0f) {
        ccl_cloudscape_ground(p, t, ccl_vec3_add(eye, ccl_vec3_scale(d, t_ground)), sun, bg, NULL);
        for (c = 0; c < 3; ++c) bg[c] = bg[c] * f_g + haze[c] * (1.0f - f_g);
        if (cov < 1.0f)
            for (c = 0; c < 3; ++c) bg[c] = haze[c] + (bg[c] - haze[c]) * cov;
    } else {
        for (c = 0; c < 3; ++c) bg[c] = haze[c];
    }
    for (c = 0; c < 3; ++c)
        out_rgb[c] = ccl_clouds_composite(bg[c], 1.0f - trans, cl[c] * f_c + haze[c] * ((1.0f - trans) * (1.0f - f_c)));
}

void ccl_cloudscape_pixel(const ccl_cloudscape_params *p, const ccl_cloud_textures *t,
                          const ccl_cloudscape_sky *sky, const ccl_camera *cam, int x, int y, int width, int height,
                          int frame, float *out_rgb)
{
    ccl_vec3 d = ccl_camera_ray(cam->inv_view_proj_rot, x, y, width, height), sun;
    float offset, bg[3], cl[3], trans, e0, e1, pixel_angle, depth, t_ground = 0.0f;
    int samples, c, ground = 0;
    d = ccl_raymarch_jitter(d, (uint32_t)x, (uint32_t)y, (uint32_t)frame, p->jitter_amount,
                            (ccl_jitter_mode)p->jitter_mode, &offset);
    sun.x = sky->sun[0];
    sun.y = sky->sun[1];
    sun.z = sky->sun[2];
    /* background: the ground where the ray hits the Earth ahead, else the sky model's colour */
    if (ccl_raymarch_ray_sphere(cam->eye, d, p->layer.centre, p->layer.r_earth, &e0, &e1) && e1 > 0.0f &&
        (e0 > 0.0f || ccl_vec3_dot(d, ccl_vec3_sub(cam->eye, p->layer.centre)) < 0.0f)) {
        /* the Earth ahead: entered in front of the camera, or (camera on the ground) the ray points downwards */
        ground = 1;
        t_ground = e0 > 0.0f ? e0 : 0.0f;
        bg[0] = p->ground_colour[0];
        bg[1] = p->ground_colour[1];
        bg[2] = p->ground_colour[2];
    } else {
        const ccl_vec3 s = sky_rgb(sky, d, sun);
        bg[0] = s.x;
        bg[1] = s.y;
        bg[2] = s.z;
    }
    /* the pixel's angular size, for the level of detail (twin of pixel_angle in pywarp/kernels/cloudscape.py) */
    pixel_angle = ccl_vec3_length(ccl_vec3_sub(ccl_camera_ray(cam->inv_view_proj_rot, x, y + 1, width, height),
                                               ccl_camera_ray(cam->inv_view_proj_rot, x, y, width, height)));
    ccl_cloudscape_march(p, t, cam->eye, d, sun, offset, pixel_angle, cl, &trans, &samples, &depth);
    if (p->lighting == CCL_LIGHTING_SKY) {
        /* the haze colour: the sky towards the horizon in the ray's azimuth */
        const ccl_vec3 h = sky_rgb(sky, lift_to_horizon(d), sun);
        const float haze[3] = {h.x, h.y, h.z};
        sky_lit_composite(p, t, cam->eye, d, sun, haze, ground, t_ground, cl, trans, depth, pixel_angle, out_rgb);
        return;
    }
    /* vc-4.8: C_f = B (1 - O_D) + C_clouds, O_D = 1 - T */
    for (c = 0; c < 3; ++c)
        out_rgb[c] = ccl_clouds_composite(bg[c], 1.0f - trans, cl[c]);
}

ccl_status ccl_cloudscape_render(const ccl_cloudscape_params *p, const ccl_cloud_textures *t,
                                 const ccl_cloudscape_sky *sky, const ccl_camera *cam, int width, int height,
                                 int frame, float *out_rgb, size_t out_len)
{
    int x, y, c;
    ccl_cloudscape_params lit;
    ccl_status st = ccl_cloudscape_check(p, t, sky, NULL);
    if (st != CCL_OK) return st;
    if (cam == NULL || out_rgb == NULL || width < 1 || height < 1 || frame < 0) return CCL_EINVAL;
    if (out_len != (size_t)width * (size_t)height * 3u) return CCL_EINVAL;
    ccl_cloudscape_light(p, sky, &lit); /* once per frame: sun and ambient from the sky model */
    p = &lit;
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
