/* Cloud density and lighting model, vc §2.3.3, §2.3.4, §4.3.2. See cclouds/clouds.h for the readings chosen. */
#include "cclouds/clouds.h"
#include "cclouds/noise.h"
#include "cclouds/phase.h"
#include "internal.h"

/* max(0, x); NaN propagates */
static float nonneg(float x)
{
    return x < 0.0f ? 0.0f : x;
}

/* a (1 - s) + b s: exact at s = 0 and s = 1 */
static float lerp(float a, float b, float s)
{
    return a * (1.0f - s) + b * s;
}

void ccl_clouds_base_shape(float c_r, float c_g, float c_b, float c_a, float *out_l_fbm, float *out_b)
{
    float l_fbm;
    CCL_REQUIRE(out_l_fbm != NULL && out_b != NULL);
    /* vc-2.28 */
    l_fbm = 0.625f * c_g + 0.25f * c_b + 0.125f * c_a;
    *out_l_fbm = l_fbm;
    *out_b = ccl_interp_remap(c_r, l_fbm - 1.0f, 1.0f, 0.0f, 1.0f);
}

float ccl_clouds_coverage(float b, float d_v, float d_h, float coverage_threshold, int clamp)
{
    float b_d;
    CCL_REQUIRE(!(coverage_threshold < 0.0f || coverage_threshold > 1.0f));
    /* vc-2.29: B = B D_v; B_D = remap(B, C, 1, 0, 1) D_h. The range [C, 1] is empty at C >= 1: fully eroded. */
    if (coverage_threshold >= 1.0f) return 0.0f;
    b_d = ccl_interp_remap(b * d_v, coverage_threshold, 1.0f, 0.0f, 1.0f) * d_h;
    return clamp ? nonneg(b_d) : b_d;
}

float ccl_clouds_detail_erosion(float b_d, float c_r, float c_g, float c_b, float h_rel,
                                ccl_detail_direction detail_direction, int clamp)
{
    float h_fbm, m, c;
    /* vc-2.30 */
    h_fbm = 0.625f * c_r + 0.25f * c_g + 0.125f * c_b;
    if (detail_direction == CCL_DETAIL_PROSE) h_fbm = 1.0f - h_fbm;
    m = h_fbm * (1.0f - h_rel) + (1.0f - h_fbm) * h_rel;
    c = ccl_interp_remap(b_d, 0.2f * m, 1.0f, 0.0f, 1.0f);
    return clamp ? nonneg(c) : c;
}

float ccl_clouds_energy(float d, float a, float cos_theta, float g)
{
    CCL_REQUIRE(!(d < 0.0f || a < 0.0f));
    /* vc-2.31: Beer * HG * powder */
    return expf(-d * a) * ccl_phase_hg(cos_theta, g) * (1.0f - expf(-2.0f * d));
}

float ccl_clouds_type_blend(float d_stratus, float d_stratocumulus, float d_cumulus, float cloud_type)
{
    CCL_REQUIRE(!(cloud_type < 0.0f || cloud_type > 1.0f));
    /* vc-A16: 0 stratus, 0.5 stratocumulus, 1 cumulus, piecewise linear in between */
    if (cloud_type <= 0.5f) return lerp(d_stratus, d_stratocumulus, 2.0f * cloud_type);
    return lerp(d_stratocumulus, d_cumulus, 2.0f * cloud_type - 1.0f);
}

/* One profile of vc-4.7: max(0, remap(h, lo0, lo1, 0, 1) remap(h, hi0, hi1, 1, 0)), remaps optionally saturated. */
static float height_profile(float h, float lo0, float lo1, float hi0, float hi1, int clamp)
{
    float up = ccl_interp_remap(h, lo0, lo1, 0.0f, 1.0f);
    float down = ccl_interp_remap(h, hi0, hi1, 1.0f, 0.0f);
    if (clamp) {
        up = clamp01(up);
        down = clamp01(down);
    }
    return nonneg(up * down);
}

float ccl_clouds_height_gradient(float h, float cloud_type, int clamp)
{
    float st, sc, cu;
    /* vc-4.7 */
    cu = height_profile(h, 0.01f, 0.30f, 0.6f, 0.95f, clamp);
    sc = height_profile(h, 0.01f, 0.25f, 0.3f, 0.65f, clamp);
    st = height_profile(h, 0.01f, 0.05f, 0.0f, 0.20f, clamp);
    return ccl_clouds_type_blend(st, sc, cu, cloud_type);
}

float ccl_clouds_composite(float b, float o_d, float c_clouds)
{
    CCL_REQUIRE(!(o_d < 0.0f || o_d > 1.0f));
    /* vc-4.8 */
    return b * (1.0f - o_d) + c_clouds;
}

float ccl_clouds_relative_height(float r, float r_inner, float r_outer, ccl_variant variant)
{
    float thickness = r_outer - r_inner;
    CCL_REQUIRE(!(thickness <= 0.0f));
    /* vc-A15: the printed reading subtracts one from the normalized distance to the outer sphere */
    if (variant == CCL_VARIANT_THESIS) return (r_outer - r) / thickness - 1.0f;
    return (r - r_inner) / thickness;
}

float ccl_clouds_density(float coverage, float cloud_type, float h, float base_r, float base_g, float base_b,
                         float base_a, float detail_r, float detail_g, float detail_b, float h_detail,
                         float coverage_threshold, int gradient_clamp, int density_clamp,
                         ccl_detail_direction detail_direction)
{
    float d_v, l_fbm, b, b_d;
    /* vc-A17 */
    d_v = ccl_clouds_height_gradient(h, cloud_type, gradient_clamp);
    ccl_clouds_base_shape(base_r, base_g, base_b, base_a, &l_fbm, &b);
    b_d = ccl_clouds_coverage(b, d_v, coverage, coverage_threshold, density_clamp);
    return ccl_clouds_detail_erosion(b_d, detail_r, detail_g, detail_b, h_detail, detail_direction, density_clamp);
}

float ccl_clouds_sample_light(float d, float a, float cos_theta, float h, float g, float sun_intensity,
                              float ambient_bottom, float ambient_top)
{
    /* vc-A20: direct light (vc-2.31) + ambient interpolated by relative height */
    float ambient = lerp(ambient_bottom, ambient_top, clamp01(h));
    return sun_intensity * ccl_clouds_energy(d, a, cos_theta, g) + ambient;
}
