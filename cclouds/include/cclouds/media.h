/*
 * cclouds/media.h -- light transport in participating media (vc §2.1, §2.2, §2.5): the loss and gain terms of the
 * radiative transfer equation, Beer-Lambert transmittance, the phase-function normalization check, optical thickness
 * and the raymarched volume-rendering sum.
 *
 * Conventions (all functions):
 *   - Coefficients sigma_a (absorption), sigma_s (scattering), sigma_t = sigma_a + sigma_s (extinction) are in
 *     inverse length [m^-1] (any length unit works if distances use the same one), >= 0.
 *   - Radiance L, L_e (emitted), L_i (in-scattered) in W m^-2 sr^-1 (or any consistent unit), >= 0; flux Phi in W.
 *   - Optical depth tau = int sigma_t dx is dimensionless, >= 0; transmittance T = exp(-tau) in (0, 1].
 *   - The *_derivative functions are right-hand sides dL/dx (or dPhi/dx) of the ordinary differential equations
 *     vc-2.1 .. 2.4, 2.9, 2.10 along the ray: x is the arc length along the direction of travel omega.
 *   - Sampled rays (vc-2.17, 2.18, 2.34): arrays of n samples of the coefficients at x_k = x + k dt omega,
 *     k = 0 .. n-1, with a uniform step dt; the path length is s = n dt. Integrals are left Riemann sums (the printed
 *     sum of vc-2.18 runs over t = 0 .. S-1), so they converge to the integrals at first order in dt. The optical
 *     depth to sample k is tau_k = sum_{j<k} sigma_t[j] dt and T(x, x_k) = exp(-tau_k).
 *   - Every coefficient, radiance, flux, sample and step dt is in [0, CCL_MEDIA_MAX_VALUE] (the functions with a
 *     status refuse others; optical depths may be any value >= 0).
 */
#ifndef CCLOUDS_MEDIA_H
#define CCLOUDS_MEDIA_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest coefficient, radiance, flux, sample or step accepted (10^9 in any unit): every product of two of them
 * (<= 10^18), each source term times dt (<= 2 x 10^27) and their sum over up to 2^31 samples stay finite, so no result
 * is Inf or NaN (samples or dt of ~1e25 gave Inf x 0 = NaN with status OK). A cloud's sigma is ~0.01-0.1 m^-1 and
 * the sun's radiance ~2 x 10^7 W m^-2 sr^-1. */
#define CCL_MEDIA_MAX_VALUE 1.0e9f

/* Radiance loss by absorption: dL/dx = -sigma_a L.
 * Ref: vc-2.1 (Pharr, Jakob & Humphreys, PBR 4th ed., §11.1.1). sigma_a -> sigma_a(x) >= 0; L -> L(x, omega) >= 0.
 * Output <= 0. Closed form of the ODE: L(s) = L(0) exp(-int_0^s sigma_a dx). NaN propagates. */
CCL_API float ccl_media_absorption_derivative(float sigma_a, float L);

/* Radiance loss by out-scattering: dL/dx = -sigma_s L.
 * Ref: vc-2.2. sigma_s -> sigma_s(x) >= 0 (printed without (x); read as spatially varying); L >= 0. Output <= 0. */
CCL_API float ccl_media_outscattering_derivative(float sigma_s, float L);

/* Radiance loss by extinction: dL/dx = -sigma_t L with sigma_t = sigma_a + sigma_s (the inline definition of vc-2.3).
 * Ref: vc-2.3. sigma_a, sigma_s >= 0; L >= 0. Evaluated as -(sigma_a + sigma_s) * L. Output <= 0; equals the sum of
 * vc-2.1 and vc-2.2 up to rounding. */
CCL_API float ccl_media_extinction_derivative(float sigma_a, float sigma_s, float L);

/* Beer-Lambert law in differential flux form: dPhi/dx = -sigma_t Phi.
 * Ref: vc-2.4. sigma_t -> sigma_t(x) >= 0 [m^-1]; phi -> Phi(x) >= 0 [W]. Output <= 0 [W m^-1]. */
CCL_API float ccl_media_flux_derivative(float sigma_t, float phi);

/* Flux leaving a slab: Phi_o = Phi_i exp(-int_0^l sigma_t dx).
 * Ref: vc-2.5. phi_i -> Phi_i >= 0; optical_depth -> int_0^l sigma_t(x) dx >= 0 (sigma_t l for a homogeneous slab of
 * thickness l; ccl_media_optical_thickness for a sampled one). Output in [0, Phi_i]. */
CCL_API float ccl_media_slab_flux(float phi_i, float optical_depth);

/* Transmittance from optical depth: T = Phi_o / Phi_i = exp(-tau).
 * Ref: vc-2.6. optical_depth -> tau = int_0^l sigma_t dx >= 0. Output in (0, 1] (0 once tau > ~103.3, float32
 * underflow). */
CCL_API float ccl_media_transmittance(float optical_depth);

/* Transmittance along two consecutive segments x -> x' -> x'' (x' on the straight segment from x to x'').
 * Ref: vc-2.7, spec error index item 1. t_a -> T(x, x'), t_b -> T(x', x''), both in [0, 1].
 * variant CCL_VARIANT_CORRECTED: T(x, x'') = T(x, x') * T(x', x'') (Beer-Lambert is multiplicative; the optical
 *   depths add). Output in [0, 1].
 * variant CCL_VARIANT_THESIS: the printed sum T(x, x') + T(x', x''), which exceeds 1 (0.8 + 0.8 = 1.6); kept only to
 *   reproduce the text. Output in [0, 2]. */
CCL_API float ccl_media_transmittance_compose(float t_a, float t_b, ccl_variant variant);

/* Integral of a tabulated, rotationally symmetric phase function over the sphere of directions (the normalization
 * check of vc-2.8): int_Omega p domega = 2 pi int_{-1}^{1} p(mu) dmu, by the composite Simpson rule.
 * Ref: vc-2.8. p -> p(mu_i) [sr^-1] at the n uniform nodes mu_i = -1 + 2 i / (n - 1), i = 0 .. n-1 (mu = cos theta,
 * theta the scattering angle); every phase function of vc-2.11 .. 2.15 depends on theta only.
 * Returns CCL_EINVAL (and leaves *out_integral untouched) if p or out_integral is NULL, n < 3, n is even, or a value
 * is negative or not finite. Output: the integral, 1 for a normalized phase function (Simpson is exact for cubic
 * polynomials in mu; error O(n^-4) for smooth p). Accumulated in float in node order. */
CCL_API ccl_status ccl_media_phase_integral(const float *p, int n, float *out_integral);

/* Asymmetry parameter (mean cosine) of a tabulated, rotationally symmetric phase function:
 * g = int_Omega p(omega_i) cos(theta) domega_i = 2 pi int_{-1}^{1} p(mu) mu dmu, composite Simpson on the nodes of
 * ccl_media_phase_integral. Ref: vc-2.14 (used to fit an HG lobe to a complex phase function). The same input rules
 * and CCL_EINVAL cases as ccl_media_phase_integral. Output in [-1, 1] for a normalized p: 0 for isotropic and
 * Rayleigh, g for Henyey-Greenstein. */
CCL_API ccl_status ccl_media_phase_asymmetry(const float *p, int n, float *out_g);

/* Radiance gain by emission and in-scattering: dL/dx = sigma_a L_e + sigma_s L_i.
 * Ref: vc-2.9. sigma_a, sigma_s >= 0 at x; L_e -> L_e(x, omega) >= 0; L_i -> L_i(x, omega) >= 0, the in-scattered
 * radiance int p L domega_i computed by the caller. Output >= 0. Evaluated as sigma_a * L_e + sigma_s * L_i. */
CCL_API float ccl_media_gain_derivative(float sigma_a, float sigma_s, float L_e, float L_i);

/* Right-hand side of the radiative transfer equation: dL/dx = sigma_a L_e + sigma_s L_i - sigma_t L,
 * sigma_t = sigma_a + sigma_s.
 * Ref: vc-2.10 (Pharr, Jakob & Humphreys, PBR 4th ed., §14.1). Arguments as in ccl_media_gain_derivative and
 * ccl_media_extinction_derivative. Evaluated as (sigma_a * L_e + sigma_s * L_i) - (sigma_a + sigma_s) * L.
 * Zero at the equilibrium radiance L = (sigma_a L_e + sigma_s L_i) / sigma_t. */
CCL_API float ccl_media_rte_derivative(float sigma_a, float sigma_s, float L_e, float L_i, float L);

/* Volume rendering equation along one sampled ray (emission and single scattering), as a left Riemann sum:
 *   L = T(x, x_s) L_bg + sum_{k=0}^{n-1} T(x, x_k) (sigma_a[k] L_e[k] + sigma_s[k] L_i[k]) dt,
 *   T(x, x_k) = exp(-sum_{j<k} (sigma_a[j] + sigma_s[j]) dt),
 *   T(x, x_s) = exp(-sum_{j<n} (sigma_a[j] + sigma_s[j]) dt).
 * Ref: vc-2.17 (spec error index item 4; Pharr, Jakob & Humphreys, PBR 4th ed., §14.1.2). sigma_a, sigma_s, L_e, L_i
 * -> arrays of n samples >= 0 at x_k = x + k dt omega; dt -> step length >= 0; L_bg -> L(x_s), the radiance of the
 * surface (background) behind the medium >= 0; the path length is s = n dt. Direction convention: omega points from
 * the eye into the medium, L_e and L_i are the radiances travelling back towards the eye (the sign mix of the text
 * is resolved this way).
 * variant CCL_VARIANT_CORRECTED: every integrand at the sample x_k (the physically right form).
 * variant CCL_VARIANT_THESIS: sigma_a, L_e and L_i at x as printed, i.e. sigma_a[0], L_e[0], L_i[0] for every k;
 *   sigma_s and the transmittance still use x_k.
 * Returns CCL_EINVAL (out_L untouched) if out_L is NULL, n < 0, an array is NULL while n > 0, dt or L_bg is negative
 * or not finite, or a sample is negative or not finite. n = 0 gives L = L_bg. First-order accurate in dt. */
CCL_API ccl_status ccl_media_volume_render(const float *sigma_a, const float *sigma_s, const float *L_e,
                                           const float *L_i, int n, float dt, float L_bg, ccl_variant variant,
                                           float *out_L);

/* Raymarching approximation of the volume rendering equation without emission (the printed Riemann sum):
 *   L = T(x, x_s) L_bg + sum_{k=0}^{n-1} T(x, x_k) sigma_s[k] L_i[k] dt,  T(x, x_k) = exp(-sum_{j<k} sigma_t[j] dt).
 * Ref: vc-2.18 (spec error index item 4). sigma_t, sigma_s, L_i -> arrays of n samples >= 0 with
 * sigma_s[k] <= sigma_t[k] (sigma_t = sigma_a + sigma_s); n -> S, the number of samples; dt -> Delta t >= 0;
 * L_bg -> L(x_s) >= 0.
 * variant CCL_VARIANT_CORRECTED: L_i at the sample x_k. variant CCL_VARIANT_THESIS: L_i(x, omega) at x as printed,
 * i.e. L_i[0] for every k.
 * Returns CCL_EINVAL (out_L untouched) for NULL pointers (arrays only when n > 0), n < 0, negative or non-finite dt,
 * L_bg or samples, or sigma_s[k] > sigma_t[k]. Accumulation order (mirrored by the Warp twin): for k = 0 .. n-1,
 * L += exp(-tau) * sigma_s[k] * L_i[k] * dt, then tau += sigma_t[k] * dt; finally L = exp(-tau) * L_bg + L. */
CCL_API ccl_status ccl_media_raymarch(const float *sigma_t, const float *sigma_s, const float *L_i, int n, float dt,
                                      float L_bg, ccl_variant variant, float *out_L);

/* Optical thickness of a sampled path: tau = int_0^s sigma dx ~= sum_{k=0}^{n-1} sigma[k] dt (left Riemann sum,
 * accumulated as tau += sigma[k] * dt in sample order, exactly like the optical depth inside ccl_media_raymarch).
 * Ref: vc-2.34. sigma -> the coefficient samples >= 0 at x_k = x + k dt omega; dt >= 0; s = n dt.
 * The text integrates sigma_s (exact only for a non-absorbing medium, spec ambiguity item 28); the general definition
 * integrates sigma_t. The function integrates whichever coefficient it is given: pass sigma_t for the optical depth
 * of Beer-Lambert (vc-2.5, 2.6), sigma_s to reproduce the printed formula.
 * Returns CCL_EINVAL (out_tau untouched) for NULL pointers (sigma only when n > 0), n < 0, negative or non-finite dt
 * or samples. Output >= 0. */
CCL_API ccl_status ccl_media_optical_thickness(const float *sigma, int n, float dt, float *out_tau);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_MEDIA_H */
