/* Phase functions, vc §2.1.4. See cclouds/phase.h for the conventions. */
#include "cclouds/phase.h"
#include "internal.h"

float ccl_phase_isotropic(void)
{
    /* vc-2.11: p = 1 / (4 pi) */
    return CCL_INV_4PI_F;
}

float ccl_phase_rayleigh(float cos_theta)
{
    CCL_REQUIRE(!(cos_theta < -1.0f || cos_theta > 1.0f));
    /* vc-2.12: p = 1/(4 pi) * 3/4 * (1 + cos^2 theta) */
    return CCL_INV_4PI_F * 0.75f * (1.0f + cos_theta * cos_theta);
}

float ccl_phase_hg(float cos_theta, float g)
{
    float a, denom;
    CCL_REQUIRE(!(cos_theta < -1.0f || cos_theta > 1.0f));
    CCL_REQUIRE(!(g <= -1.0f || g >= 1.0f));
    /* vc-2.13: 1 + g^2 - 2 g cos theta written as (1 - g cos theta)^2 + g^2 (1 - cos theta)(1 + cos theta): a sum of
     * two non-negative terms without cancellation, so the denominator stays > 0 and accurate as |g| -> 1 (the plain
     * form rounds to 0 for g = -0.999999, cos theta = -1 and overflows); 1 - g^2 likewise as (1 - g)(1 + g). */
    a = 1.0f - g * cos_theta;
    denom = a * a + g * g * ((1.0f - cos_theta) * (1.0f + cos_theta));
    return CCL_INV_4PI_F * ((1.0f - g) * (1.0f + g)) / (denom * sqrtf(denom));
}

float ccl_phase_schlick(float cos_theta, float k, ccl_variant variant)
{
    float s;
    CCL_REQUIRE(!(cos_theta < -1.0f || cos_theta > 1.0f));
    CCL_REQUIRE(!(k <= -1.0f || k >= 1.0f));
    /* vc-2.15: corrected (1 - k cos theta)^2; as printed (1 + k cos theta)^2 */
    s = (variant == CCL_VARIANT_THESIS) ? 1.0f + k * cos_theta : 1.0f - k * cos_theta;
    return CCL_INV_4PI_F * (1.0f - k * k) / (s * s);
}

float ccl_phase_schlick_k(float g)
{
    /* vc-2.16: k = 1.55 g - 0.55 g^3 */
    return 1.55f * g - 0.55f * g * g * g;
}

/* Draine's phase function (Draine 2003, eq. 4): HG(g) x (1 + alpha cos^2 theta) / (1 + alpha (1 + 2 g^2) / 3); the
 * denominator is the mean of the numerator under HG(g) (<cos^2> = (1 + 2 g^2) / 3), so it stays normalised. */
static float phase_draine(float cos_theta, float g, float alpha)
{
    return ccl_phase_hg(cos_theta, g) * (1.0f + alpha * cos_theta * cos_theta) /
           (1.0f + alpha * (1.0f + 2.0f * g * g) / 3.0f);
}

float ccl_phase_mie(float cos_theta, float diameter_um)
{
    const float d = diameter_um;
    float g_hg, g_d, alpha, w_d;
    CCL_REQUIRE(!(cos_theta < -1.0f || cos_theta > 1.0f));
    CCL_REQUIRE(!(d < (float)CCL_PHASE_MIE_D_MIN || d > (float)CCL_PHASE_MIE_D_MAX));
    /* Jendersie & d'Eon 2023, the fit for 5 um <= d <= 50 um */
    g_hg = expf(-0.0990567f / (d - 1.67154f));
    g_d = expf(-2.20679f / (d + 3.91029f) - 0.428934f);
    alpha = expf(3.62489f - 8.29288f / (d + 5.52825f));
    w_d = expf(-0.599085f / (d - 0.641583f) - 0.665888f);
    return (1.0f - w_d) * ccl_phase_hg(cos_theta, g_hg) + w_d * phase_draine(cos_theta, g_d, alpha);
}
