/* Participating media, vc §2.1, §2.2, §2.5. See cclouds/media.h for the conventions. */
#include "cclouds/media.h"
#include "internal.h"

#include <float.h>

#define CCL_2PI_F 6.28318530717958647692f

/* A finite value >= 0 (false for NaN and +-Inf). */
static int nonneg_finite(float v)
{
    return v >= 0.0f && v <= CCL_MEDIA_MAX_VALUE;
}

/* Every sample of a[0 .. n-1] is in [0, CCL_MEDIA_MAX_VALUE]. */
static int samples_ok(const float *a, int n)
{
    int k;
    for (k = 0; k < n; ++k) {
        if (!nonneg_finite(a[k])) return 0;
    }
    return 1;
}

float ccl_media_absorption_derivative(float sigma_a, float L)
{
    /* vc-2.1: dL/dx = -sigma_a L */
    return -sigma_a * L;
}

float ccl_media_outscattering_derivative(float sigma_s, float L)
{
    /* vc-2.2: dL/dx = -sigma_s L */
    return -sigma_s * L;
}

float ccl_media_extinction_derivative(float sigma_a, float sigma_s, float L)
{
    /* vc-2.3: dL/dx = -sigma_t L, sigma_t = sigma_a + sigma_s */
    return -(sigma_a + sigma_s) * L;
}

float ccl_media_flux_derivative(float sigma_t, float phi)
{
    /* vc-2.4: dPhi/dx = -sigma_t Phi */
    return -sigma_t * phi;
}

float ccl_media_slab_flux(float phi_i, float optical_depth)
{
    CCL_REQUIRE(!(optical_depth < 0.0f));
    /* vc-2.5: Phi_o = Phi_i exp(-tau) */
    return phi_i * expf(-optical_depth);
}

float ccl_media_transmittance(float optical_depth)
{
    CCL_REQUIRE(!(optical_depth < 0.0f));
    /* vc-2.6: T = exp(-tau) */
    return expf(-optical_depth);
}

float ccl_media_transmittance_compose(float t_a, float t_b, ccl_variant variant)
{
    CCL_REQUIRE(!(t_a < 0.0f || t_a > 1.0f || t_b < 0.0f || t_b > 1.0f));
    /* vc-2.7: corrected T(x,x') T(x',x''); as printed T(x,x') + T(x',x'') */
    return (variant == CCL_VARIANT_THESIS) ? t_a + t_b : t_a * t_b;
}

ccl_status ccl_media_phase_integral(const float *p, int n, float *out_integral)
{
    float s, h;
    int i;
    if (p == NULL || out_integral == NULL || n < 3 || n % 2 == 0 || !samples_ok(p, n)) return CCL_EINVAL;
    /* vc-2.8: 2 pi int_{-1}^{1} p(mu) dmu, composite Simpson: h/3 (p_0 + 4 p_1 + 2 p_2 + ... + 4 p_{n-2} + p_{n-1}) */
    s = p[0] + p[n - 1];
    for (i = 1; i < n - 1; ++i) {
        s += ((i % 2) ? 4.0f : 2.0f) * p[i];
    }
    h = 2.0f / (float)(n - 1);
    *out_integral = CCL_2PI_F * s * h / 3.0f;
    return CCL_OK;
}

ccl_status ccl_media_phase_asymmetry(const float *p, int n, float *out_g)
{
    float s, h;
    int i;
    if (p == NULL || out_g == NULL || n < 3 || n % 2 == 0 || !samples_ok(p, n)) return CCL_EINVAL;
    /* vc-2.14: g = 2 pi int_{-1}^{1} p(mu) mu dmu, the same Simpson rule as vc-2.8 on the nodes mu_i */
    h = 2.0f / (float)(n - 1);
    s = -p[0] + p[n - 1];
    for (i = 1; i < n - 1; ++i) {
        float mu = -1.0f + (float)i * h;
        s += ((i % 2) ? 4.0f : 2.0f) * (p[i] * mu);
    }
    *out_g = CCL_2PI_F * s * h / 3.0f;
    return CCL_OK;
}

float ccl_media_gain_derivative(float sigma_a, float sigma_s, float L_e, float L_i)
{
    /* vc-2.9: dL/dx = sigma_a L_e + sigma_s L_i */
    return sigma_a * L_e + sigma_s * L_i;
}

float ccl_media_rte_derivative(float sigma_a, float sigma_s, float L_e, float L_i, float L)
{
    /* vc-2.10: dL/dx = sigma_a L_e + sigma_s L_i - sigma_t L */
    return (sigma_a * L_e + sigma_s * L_i) - (sigma_a + sigma_s) * L;
}

ccl_status ccl_media_volume_render(const float *sigma_a, const float *sigma_s, const float *L_e, const float *L_i,
                                   int n, float dt, float L_bg, ccl_variant variant, float *out_L)
{
    float tau = 0.0f, L = 0.0f;
    int k;
    if (out_L == NULL || n < 0 || !nonneg_finite(dt) || !nonneg_finite(L_bg)) return CCL_EINVAL;
    if (n > 0) {
        if (sigma_a == NULL || sigma_s == NULL || L_e == NULL || L_i == NULL) return CCL_EINVAL;
        if (!samples_ok(sigma_a, n) || !samples_ok(sigma_s, n) || !samples_ok(L_e, n) || !samples_ok(L_i, n)) {
            return CCL_EINVAL;
        }
    }
    /* vc-2.17, left Riemann sum; the thesis variant evaluates sigma_a, L_e, L_i at x (sample 0) as printed */
    for (k = 0; k < n; ++k) {
        int j = (variant == CCL_VARIANT_THESIS) ? 0 : k;
        float source = sigma_a[j] * L_e[j] + sigma_s[k] * L_i[j];
        L += expf(-tau) * source * dt;
        tau += (sigma_a[k] + sigma_s[k]) * dt;
    }
    *out_L = expf(-tau) * L_bg + L;
    return CCL_OK;
}

ccl_status ccl_media_raymarch(const float *sigma_t, const float *sigma_s, const float *L_i, int n, float dt,
                              float L_bg, ccl_variant variant, float *out_L)
{
    float tau = 0.0f, L = 0.0f;
    int k;
    if (out_L == NULL || n < 0 || !nonneg_finite(dt) || !nonneg_finite(L_bg)) return CCL_EINVAL;
    if (n > 0) {
        if (sigma_t == NULL || sigma_s == NULL || L_i == NULL) return CCL_EINVAL;
        if (!samples_ok(sigma_t, n) || !samples_ok(sigma_s, n) || !samples_ok(L_i, n)) return CCL_EINVAL;
        for (k = 0; k < n; ++k) {
            if (sigma_s[k] > sigma_t[k]) return CCL_EINVAL;
        }
    }
    /* vc-2.18: T(x, x_s) L_bg + sum_k T(x, x_k) sigma_s(x_k) L_i(x_k) dt; the thesis variant takes L_i at x */
    for (k = 0; k < n; ++k) {
        int j = (variant == CCL_VARIANT_THESIS) ? 0 : k;
        L += expf(-tau) * sigma_s[k] * L_i[j] * dt;
        tau += sigma_t[k] * dt;
    }
    *out_L = expf(-tau) * L_bg + L;
    return CCL_OK;
}

ccl_status ccl_media_optical_thickness(const float *sigma, int n, float dt, float *out_tau)
{
    float tau = 0.0f;
    int k;
    if (out_tau == NULL || n < 0 || !nonneg_finite(dt)) return CCL_EINVAL;
    if (n > 0 && (sigma == NULL || !samples_ok(sigma, n))) return CCL_EINVAL;
    /* vc-2.34: tau = int_0^s sigma dx, left Riemann sum */
    for (k = 0; k < n; ++k) {
        tau += sigma[k] * dt;
    }
    *out_tau = tau;
    return CCL_OK;
}
