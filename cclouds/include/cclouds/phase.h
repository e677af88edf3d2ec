/*
 * cclouds/phase.h -- phase functions of participating media (vc §2.1.4).
 *
 * Angle convention (all functions): cos_theta = dot(w_in, w_out), the cosine of the angle between the direction the
 * light travels before scattering and after it. cos_theta = +1 is "straight on" (forward scattering). In a camera
 * raymarcher this is dot(view ray direction, direction towards the sun) -- the convention of vc-2.13. Phase functions
 * are in sr^-1 and integrate to 1 over the sphere (vc-2.8).
 */
#ifndef CCLOUDS_PHASE_H
#define CCLOUDS_PHASE_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Isotropic phase function p = 1 / (4 pi).
 * Ref: vc-2.11. Output: 1/(4 pi) ~= 0.0795775 sr^-1. */
CCL_API float ccl_phase_isotropic(void);

/* Rayleigh phase function p = 3 / (16 pi) * (1 + cos^2 theta).
 * Ref: vc-2.12 (Rayleigh; Chandrasekhar 1960). cos_theta -> cos(theta), domain [-1, 1].
 * Output: [3/(16 pi), 3/(8 pi)] sr^-1. NaN propagates. */
CCL_API float ccl_phase_rayleigh(float cos_theta);

/* Henyey-Greenstein phase function p = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^(3/2)).
 * Ref: vc-2.13 (Henyey & Greenstein 1941). cos_theta -> cos(theta) in [-1, 1]; g -> g, mean cosine, in (-1, 1);
 * g > 0 scatters forward (peak at cos_theta = +1). Output > 0 sr^-1. NaN propagates. */
CCL_API float ccl_phase_hg(float cos_theta, float g);

/* Schlick's approximation of Henyey-Greenstein p = (1 - k^2) / (4 pi (1 - k cos theta)^2).
 * Ref: vc-2.15 (Blasi, Le Saec & Schlick 1993). cos_theta in [-1, 1]; k in (-1, 1).
 * variant CCL_VARIANT_CORRECTED: denominator (1 - k cos theta)^2, k > 0 forward, like HG with g > 0.
 * variant CCL_VARIANT_THESIS: denominator (1 + k cos theta)^2 as printed in vc-2.15, which makes k > 0 BACKWARD
 * scattering under the angle convention of vc-2.13 (spec error index item 2). Output > 0 sr^-1. */
CCL_API float ccl_phase_schlick(float cos_theta, float k, ccl_variant variant);

/* Schlick parameter k from the Henyey-Greenstein g: k = 1.55 g - 0.55 g^3.
 * Ref: vc-2.16. g in [-1, 1]. Note: |k| > 1 for 0.9381 < |g| < 1 (max |k| ~= 1.0015), where 2.15 turns negative;
 * callers that feed k into ccl_phase_schlick should keep |g| <= 0.938. */
CCL_API float ccl_phase_schlick_k(float g);

/* The approximate Mie phase function of cloud and fog droplets (beyond the text: the thesis's clouds use one HG lobe):
 *   p = (1 - w_D) HG(cos_theta, g_HG) + w_D Draine(cos_theta, g_D, alpha),
 *   Draine(cos_theta, g, alpha) = HG(cos_theta, g) (1 + alpha cos^2 theta) / (1 + alpha (1 + 2 g^2) / 3),
 * with the parameters fitted to Lorenz-Mie theory over droplet diameters d in [5, 50] um:
 *   g_HG = exp(-0.0990567 / (d - 1.67154)),  g_D = exp(-2.20679 / (d + 3.91029) - 0.428934),
 *   alpha = exp(3.62489 - 8.29288 / (d + 5.52825)),  w_D = exp(-0.599085 / (d - 0.641583) - 0.665888).
 * Ref: vc-x-mie; Jendersie & d'Eon 2023, "An Approximate Mie Scattering Function for Fog and Cloud Rendering", ACM
 * SIGGRAPH 2023 Talks, article 47; Draine 2003, ApJ 598:1017 (eq. 4). cos_theta in [-1, 1]; diameter_um -> d, the
 * droplet diameter in micrometres, in [CCL_PHASE_MIE_D_MIN, CCL_PHASE_MIE_D_MAX]. Output > 0 sr^-1, integrates to 1
 * over the sphere. NaN propagates. */
#define CCL_PHASE_MIE_D_MIN 5
#define CCL_PHASE_MIE_D_MAX 50
CCL_API float ccl_phase_mie(float cos_theta, float diameter_um);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_PHASE_H */
