/*
 * cclouds/optics.h -- geometric optics of a water drop (rr §2.2, §3.2.1; after Rousseau, Jolivet & Ghazanfarpour,
 * "Realistic real-time rain rendering", Computers & Graphics 30, 2006).
 *
 * Conventions (every function):
 *   - Directions are unit ccl_vec3. An incident direction d is the direction the light TRAVELS (towards the surface).
 *   - A surface normal n may point to either side: the functions orient it against d themselves.
 *   - n1 is the refractive index of the medium the light comes from, n2 that of the medium it enters
 *     (air 1, water 1.33 in the text, rr §3.2.1).
 *   - Angles of incidence are passed as cos_i = |cos theta_i| in [0, 1] (1 = normal incidence, 0 = grazing).
 *   - Total internal reflection (n1 > n2 beyond the critical angle arcsin(n2 / n1)) reflects everything: R = 1.
 */
#ifndef CCLOUDS_OPTICS_H
#define CCLOUDS_OPTICS_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Refractive index of water used by the text (rr §3.2.1), x 100 (an integer constant): 1.33. */
#define CCL_OPTICS_WATER_INDEX_X100 133

/* Law of reflection and Snell's law for a direction (vector in, vector out).
 *   n' = n oriented against d (dot(n', d) <= 0), cos_i = -dot(n', d), eta = n1 / n2,
 *   k = 1 - eta^2 (1 - cos_i^2);
 *   reflected r = d + 2 cos_i n'  (theta_r = theta_i);
 *   refracted t = eta d + (eta cos_i - sqrt(k)) n'  (n1 sin theta_i = n2 sin theta_t), a unit vector up to the
 *   conditioning of k: | |t| - 1 | <= 1e-5 + 8 eta^2 2^-23 for float unit d, n (k loses eta^2 ulps of cos_i^2:
 *   4e-6 for water, |t| = 0.72 at eta = 2000, where only rays within 5e-4 rad of the normal refract);
 *   k < 0: total internal reflection, t = (0, 0, 0) (the convention of GLSL/Cg refract) and *out_tir = 1.
 *   Where eta^2 overflows (n2 below ~5e-20 n1), an oblique ray is totally reflected and one along the normal
 *   (1 - cos_i^2 = 0) goes on unchanged, t = d: finite for every index in (0, 10].
 * Ref: rr-snell (Snell / law of reflection; rr §2.2 Obrazek 2.2). d -> incident direction (unit), n -> surface normal
 * (unit, either side), n1, n2 -> refractive indices in (0, 10]. Returns t; writes *out_r = r (unit) and *out_tir
 * (0 or 1). NaN propagates. */
CCL_API ccl_vec3 ccl_optics_snell(ccl_vec3 d, ccl_vec3 n, float n1, float n2, ccl_vec3 *out_r, int *out_tir);

/* Fresnel reflectance of unpolarised light in the cosine forms of eqs. (2), (3):
 *   cos_t = sqrt(1 - (n1/n2)^2 (1 - cos_i^2)),
 *   R_s = ((n1 cos_i - n2 cos_t) / (n1 cos_i + n2 cos_t))^2,
 *   R_p = ((n1 cos_t - n2 cos_i) / (n1 cos_t + n2 cos_i))^2,
 *   R = (R_s + R_p) / 2 (used but never written by the text; its "< 10 % below 67.5 deg" refers to it).
 * The cosine forms have no 0/0 at normal incidence (the printed sin/tan forms do). Beyond the critical angle
 * (radicand < 0) R_s = R_p = R = 1 (total internal reflection). The only remaining 0/0, grazing incidence exactly at
 * the critical angle (cos_i = cos_t = 0), is given its limit R_s = R_p = R = 1.
 * Ref: rr-eq2 (R_s), rr-eq3 (R_p) (Fresnel; Born & Wolf, Principles of Optics, §1.5). cos_i -> cos theta_i in [0, 1];
 * n1, n2 -> indices in (0, 10]. Returns R in [0, 1]; writes *out_rs = R_s and *out_rp = R_p, both in [0, 1].
 * Air -> water (1, 1.33): R(0 deg) = 0.0201, R(60 deg) = 0.0591, R(67.5 deg) = 0.1065. NaN propagates. */
CCL_API float ccl_optics_fresnel(float cos_i, float n1, float n2, float *out_rs, float *out_rp);

/* Field of view of a drop: the largest deviation of a ray refracted through a spherical drop (entry at grazing
 * incidence, no internal reflection), doubled. The chain of rr §3.2.1 (Obrazek 3.6), for the index n = n_water/n_air:
 *   theta_t = arcsin(1/n) (refraction angle at the grazing entry, from the normal),
 *   exit normal angle to the incoming ray  e = 90 - (180 - 2 theta_t) = 2 theta_t - 90,
 *   exit angle to that normal  x = arcsin(n sin theta_t),   deviation D = x - e,   FOV = 2 D.
 * variant CCL_VARIANT_CORRECTED: exact: x = 90, D = 180 - 2 theta_t, FOV = 360 - 4 arcsin(1/n) (165.0 deg for 1.33).
 * variant CCL_VARIANT_THESIS: as printed: every angle of the chain truncated to whole degrees (48.75 -> 48,
 *   81.26 -> 81), giving 48 -> 6 -> 81 -> 75 -> FOV 150 deg for 1.33 (spec error index item 7). The capture
 *   camera's FOVy defaults to this 150 deg, the text's contract.
 * Ref: rr-der-3.2.1. n -> relative index in [1, 2] (water/air 1.33). Returns the FOV in degrees; writes the chain:
 * *out_theta_t, *out_exit_normal, *out_exit (degrees). The FOV exceeds 180 deg for n > sqrt(2). */
CCL_API float ccl_optics_drop_fov(float n, ccl_variant variant, float *out_theta_t, float *out_exit_normal,
                                  float *out_exit);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_OPTICS_H */
