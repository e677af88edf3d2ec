/*
 * cclouds/clouds.h -- the cloud density and lighting model (vc §2.3.3, §2.3.4, §4.3.2; after Schneider & Vos,
 * "The real-time volumetric cloudscapes of Horizon: Zero Dawn", SIGGRAPH 2015, and Schneider, GPU Pro 7, 2016).
 *
 * Every function is a pure scalar function of already-sampled texture and weather-map values, so the renderer's
 * pixel kernel (Warp) and its C reference call the same code per raymarch sample. remap is vc-2.27
 * (ccl_interp_remap in cclouds/interp.h): linear, NOT clamped.
 *
 * Readings chosen where the thesis is ambiguous (spec §7):
 *   - vc-2.29: the threshold C is undefined; it is an explicit argument coverage_threshold, and the reading the spec
 *     recommends is C := D_h (pass the weather-map coverage itself). At C >= 1 the remap range [C, 1] is
 *     empty (division by zero): the result is defined as 0 (the limit of the clamped value for B < 1: the cloud is
 *     fully eroded). Negative results (B < C) are clamped to 0 when clamp != 0 (default on in Python).
 *   - vc-2.30: the direction of the height blend is configurable (ccl_detail_direction); the default follows the
 *     printed formula. Negative results are clamped to 0 when clamp != 0.
 *   - vc-4.7: remap unclamped by default (the printed max(0, .) is only needed when the remaps are not saturated, so
 *     the formula as printed implies unclamped remaps; peaks 2.1764 / 1.2190 / 1.1281); clamp != 0 saturates each
 *     remap to [0, 1] (plateaus of 1; stratus peaks at 0.75).
 *   - vc-A15: relative height from the distance r = |p - c| to the Earth's centre; the corrected variant is
 *     h = (r - R_inner) / (R_outer - R_inner), the thesis variant the printed d - 1 = -h.
 *   - vc-A16: piecewise-linear blend of the three profiles over the cloud type (0 stratus, 0.5 stratocumulus,
 *     1 cumulus).
 *   - vc-A12: precipitation enters only the lighting (a of vc-2.31), not the density.
 */
#ifndef CCLOUDS_CLOUDS_H
#define CCLOUDS_CLOUDS_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Direction of the height blend of the detail noise in vc-2.30 (spec ambiguity item 17). */
typedef enum ccl_detail_direction {
    CCL_DETAIL_FORMULA = 0, /* as printed: M = H (1 - h_rel) + (1 - H) h_rel (H at the base, 1 - H at the top) */
    CCL_DETAIL_PROSE = 1    /* as the prose says for an inverse-Worley texture: M = (1 - H)(1 - h_rel) + H h_rel */
} ccl_detail_direction;

/* Base cloud shape from the four channels of the 128^3 base texture:
 *   L_FBM = 0.625 C_G + 0.25 C_B + 0.125 C_A,  B = remap(C_R, L_FBM - 1, 1, 0, 1) = (C_R - L_FBM + 1) / (2 - L_FBM).
 * Ref: vc-2.28 (Schneider, GPU Pro 7, 2016). c_r -> C_R (Perlin-Worley), c_g, c_b, c_a -> C_G, C_B, C_A (Worley fBm
 * of increasing frequency), all in [0, 1]. Writes *out_l_fbm = L_FBM in [0, 1] and *out_b = B in
 * [(1 - L_FBM) / (2 - L_FBM), 1] (never negative; 0 only at L_FBM = 1, C_R = 0). NaN propagates. */
CCL_API void ccl_clouds_base_shape(float c_r, float c_g, float c_b, float c_a, float *out_l_fbm, float *out_b);

/* Vertical profile and horizontal coverage applied to the base shape:
 *   B' = B D_v,  B_D = remap(B', C, 1, 0, 1) D_h = (B' - C) / (1 - C) D_h.
 * Ref: vc-2.29 (spec ambiguity item 16). b -> B of vc-2.28 (>= 0); d_v -> D_v, the height gradient of vc-4.7 (>= 0,
 * up to 2.18 unclamped); d_h -> D_h, the weather-map coverage in [0, 1]; coverage_threshold -> C in [0, 1] (pass
 * d_h for the recommended reading C := D_h). C >= 1 gives 0. clamp != 0: results < 0 become 0.
 * Output: B_D (>= 0 when clamped). With C = D_h the response to coverage is non-monotonic (B = 0.8: 0.15 at D_h = 0.2,
 * 0.30 at 0.5, 0.233 at 0.7, 0 at 0.8). NaN propagates. */
CCL_API float ccl_clouds_coverage(float b, float d_v, float d_h, float coverage_threshold, int clamp);

/* Detail erosion with the 32^3 detail texture:
 *   H_FBM = 0.625 C_R + 0.25 C_G + 0.125 C_B,  M = H_FBM (1 - h_rel) + (1 - H_FBM) h_rel,
 *   C = remap(B_D, 0.2 M, 1, 0, 1) = (B_D - 0.2 M) / (1 - 0.2 M).
 * Ref: vc-2.30 (spec ambiguity item 17). b_d -> B_D of vc-2.29; c_r, c_g, c_b -> the detail channels in [0, 1]
 * sampled at the curl-displaced point; h_rel -> the relative height of that point in [0, 1];
 * detail_direction: ccl_detail_direction (CCL_DETAIL_PROSE replaces H_FBM by 1 - H_FBM); clamp != 0: C < 0 becomes 0.
 * The remap denominator 1 - 0.2 M is >= 0.8: never singular. Output: the final density C. NaN propagates. */
CCL_API float ccl_clouds_detail_erosion(float b_d, float c_r, float c_g, float c_b, float h_rel,
                                        ccl_detail_direction detail_direction, int clamp);

/* Cloud lighting energy, exactly as printed: E = exp(-d a) HG(theta, g) (1 - exp(-2 d)).
 * Ref: vc-2.31 (Schneider & Vos 2015). d -> optical thickness towards the light (>= 0, from the cone samples of
 * vc-A19); a -> precipitation (extinction) coefficient >= 0; cos_theta -> cos(theta), theta the angle between the
 * view ray and the direction to the light, in [-1, 1] (convention of vc-2.13, ccl_phase_hg); g -> HG asymmetry in
 * (-1, 1). Output [0, HG) sr^-1; E = 0 at d = 0 (spec ambiguity item 19: the lit surface itself gets no energy); for
 * a > 0 the maximum over d is at d* = ln(1 + 2 / a) / 2. NaN propagates. */
CCL_API float ccl_clouds_energy(float d, float a, float cos_theta, float g);

/* Piecewise-linear blend of the three vertical profiles by cloud type:
 *   t in [0, 0.5]: lerp(D_stratus, D_stratocumulus, 2 t);  t in (0.5, 1]: lerp(D_stratocumulus, D_cumulus, 2 t - 1),
 * with lerp(a, b, s) = a (1 - s) + b s (exact at s = 0 and s = 1).
 * Ref: vc-A16. d_stratus, d_stratocumulus, d_cumulus -> the profile values at one height (>= 0);
 * cloud_type -> t in [0, 1] (0 stratus, 0.5 stratocumulus, 1 cumulus; weather-map blue). NaN propagates. */
CCL_API float ccl_clouds_type_blend(float d_stratus, float d_stratocumulus, float d_cumulus, float cloud_type);

/* Height (vertical density) gradient D_v of vc-4.7 for a cloud type:
 *   cumulus       = max(0, remap(h, 0.01, 0.30, 0, 1) remap(h, 0.60, 0.95, 1, 0)),
 *   stratocumulus = max(0, remap(h, 0.01, 0.25, 0, 1) remap(h, 0.30, 0.65, 1, 0)),
 *   stratus       = max(0, remap(h, 0.01, 0.05, 0, 1) remap(h, 0.00, 0.20, 1, 0)),
 * blended over cloud_type by ccl_clouds_type_blend (vc-A16).
 * Ref: vc-4.7 (spec ambiguity item 18), vc-A16. h -> relative height in the layer in [0, 1] (vc-A15);
 * cloud_type in [0, 1]; clamp = 0: remaps unclamped as printed (cumulus peaks 2.1764 at h = 0.48, stratocumulus
 * 1.2190 at 0.33, stratus 1.1281 at 0.105); clamp != 0: each remap saturated to [0, 1] (peaks 1, 1, and 0.75 for
 * stratus at h = 0.05). Output >= 0; 0 outside (0.01, 0.95) for every type. NaN propagates. */
CCL_API float ccl_clouds_height_gradient(float h, float cloud_type, int clamp);

/* Clouds composited over the sky: C_f = B (1 - O_D) + C_clouds (per colour channel).
 * Ref: vc-4.8 (spec ambiguity item 22). b -> B, the background (sky) colour >= 0; o_d -> O_D, the opacity of the
 * clouds along the view ray in [0, 1] (= 1 - view transmittance); c_clouds -> C_clouds, the accumulated cloud colour
 * (premultiplied by opacity) >= 0. Output >= 0. NaN propagates. */
CCL_API float ccl_clouds_composite(float b, float o_d, float c_clouds);

/* Relative height of a sample in the cloud layer between two concentric spheres (centre c).
 * Ref: vc-A15 (spec error index item 12). r -> |p - c|, the distance of the sample p from the Earth's centre;
 * r_inner, r_outer -> the radii of the inner and outer bounding spheres, 0 < r_inner < r_outer (same unit as r; in
 * float32 use km, or metres relative to a small origin: ulp(6.4e6 m) = 0.5 m).
 * variant CCL_VARIANT_CORRECTED: h = (r - r_inner) / (r_outer - r_inner): 0 on the inner sphere, 1 on the outer.
 * variant CCL_VARIANT_THESIS: the printed "subtract one": d - 1 with d = (r_outer - r) / (r_outer - r_inner) the
 *   normalized distance to the nearest point of the outer sphere; = -h, in [-1, 0] inside the layer.
 * Outside the layer both extrapolate linearly. NaN propagates. */
CCL_API float ccl_clouds_relative_height(float r, float r_inner, float r_outer, ccl_variant variant);

/* Cloud density at one raymarch sample (the pipeline of vc-A17):
 * D_v = ccl_clouds_height_gradient(h, type, gradient_clamp); (L_FBM, B) = ccl_clouds_base_shape(base);
 * B_D = ccl_clouds_coverage(B, D_v, coverage, coverage_threshold, density_clamp);
 * C = ccl_clouds_detail_erosion(B_D, detail, h_detail, detail_direction, density_clamp).
 * Ref: vc-A17 (vc-2.28, 2.29, 2.30, 4.7, A16). coverage -> D_h (weather map red) in [0, 1]; cloud_type -> weather
 * map blue in [0, 1]; h -> relative height of the sample (vc-A15) in [0, 1]; base_r .. base_a -> base texture RGBA at
 * the sample; detail_r .. detail_b -> detail texture RGB at the curl-displaced sample; h_detail -> relative height of
 * the displaced point in [0, 1]; coverage_threshold -> C of vc-2.29 (pass coverage for C := D_h); gradient_clamp,
 * density_clamp: flags as in ccl_clouds_height_gradient and ccl_clouds_coverage; detail_direction:
 * ccl_detail_direction.
 * Output: the density C (>= 0 when density_clamp != 0). Not specified by the text and left to the caller: texture
 * scales, curl displacement, wind, the "Perlin-Worley intensity" parameter. NaN propagates. */
CCL_API float ccl_clouds_density(float coverage, float cloud_type, float h, float base_r, float base_g, float base_b,
                                 float base_a, float detail_r, float detail_g, float detail_b, float h_detail,
                                 float coverage_threshold, int gradient_clamp, int density_clamp,
                                 ccl_detail_direction detail_direction);

/* Light scattered towards the eye at one sample, one colour channel (vc-A20):
 *   L = sun_intensity E(d, a, cos_theta, g) + ambient(h),
 *   ambient(h) = ambient_bottom (1 - t) + ambient_top t,  t = clamp(h, 0, 1).
 * Ref: vc-A20, vc-2.31. d, a, cos_theta, g as in ccl_clouds_energy; h -> relative height of the sample (vc-A15);
 * sun_intensity -> the sun's irradiance in this channel (>= 0); ambient_bottom, ambient_top -> the ambient radiance at
 * the base and the top of the layer (>= 0). The thesis gives no values; the Python defaults (documented there) are
 * g = 0.2, sun_intensity = 1, ambient_bottom = 0.006, ambient_top = 0.012. Output >= 0. NaN propagates. */
CCL_API float ccl_clouds_sample_light(float d, float a, float cos_theta, float h, float g, float sun_intensity,
                                      float ambient_bottom, float ambient_top);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_CLOUDS_H */
