/*
 * cclouds/noise.h -- procedural noise of vc §2.3.2: Perlin gradient noise, Worley cellular noise, fBm, curl noise and
 * its vector operators, and the Perlin-Worley combinations of vc §4.3.1. The interpolants and remap (vc-2.19, vc-2.20,
 * vc-2.27) are in cclouds/interp.h, the PCG hash in cclouds/hash.h.
 *
 * Conventions shared by every function of this header:
 *   - Perlin noise with seed 0 is Ken Perlin's 2002 "Improved Noise" reference implementation (his Java class
 *     ImprovedNoise: the published 256-entry permutation, fade 6t^5 - 15t^4 + 10t^3, the 12 edge gradients selected by
 *     hash & 15, trilinear lerp), evaluated in float32. Other seeds use a permutation shuffled by Fisher-Yates driven
 *     by the PCG hash (ccl_noise_perm_table). Raw Perlin values lie in about [-1, 1] (not normalised).
 *   - Every Perlin function exists twice: `..._perm` takes a 512-entry permutation table (fast; fill it once with
 *     ccl_noise_perm_table) and the plain form takes a seed (seed 0 uses the built-in table at no cost, any other seed
 *     rebuilds the table on each call, ~1 us). The Warp twins take the table as an int32 array.
 *   - period: 0 = Perlin's reference lattice (which repeats every 256 units as a side effect of the 256-entry table);
 *     period P >= 1 wraps the integer lattice coordinate modulo P before hashing, so f(p + P e_i) == f(p) exactly
 *     whenever p + P is exactly representable in float32 (vc-A2).
 *   - Worley noise is periodic with period 1 on every axis by construction: `cells` cells per unit, one feature point
 *     per cell, cell indices wrapped modulo `cells` (vc-A5). Its value is the nearest-feature distance F1 measured in
 *     cell units (i.e. multiplied by `cells`) and clamped to [0, 1] (vc-A3).
 *   - Integer hashing is uint32 only (PCG hash of Jarzynski & Olano 2020); no global mutable state.
 *   - Non-finite coordinates give NaN.
 */
#ifndef CCLOUDS_NOISE_H
#define CCLOUDS_NOISE_H

#include "cclouds/common.h"
#include "cclouds/hash.h"
#include "cclouds/interp.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Number of entries of a permutation table (256 values repeated once, as in Perlin's p[]). */
#define CCL_NOISE_PERM_SIZE 512

/* Distance metric of Worley noise (vc-A4). */
typedef enum ccl_worley_metric {
    CCL_WORLEY_EUCLIDEAN = 0, /* L2 distance, classic Worley (vc-A3) */
    CCL_WORLEY_MANHATTAN = 1  /* L1 distance |dx| + |dy| + |dz| (vc-A4 "Manhattan-Worley") */
} ccl_worley_metric;

/* Interpolant of the 2-D Perlin noise used to reproduce vc-fig-2.5. */
typedef enum ccl_noise_interp {
    CCL_INTERP_QUINTIC = 0, /* 6t^5 - 15t^4 + 10t^3 (vc-2.20, Perlin 2002; the default) */
    CCL_INTERP_CUBIC = 1,   /* 3t^2 - 2t^3 (vc-2.19, Perlin 1985) */
    CCL_INTERP_LINEAR = 2,  /* t */
    CCL_INTERP_COSINE = 3   /* (1 - cos(pi t)) / 2 */
} ccl_noise_interp;

/* Perlin-Worley combinations of vc-A8 (P = Perlin fBm remapped to [0, 1], W = inverse Worley fBm in [0, 1]). */
typedef enum ccl_perlin_worley_mode {
    CCL_PW_THESIS = 0,    /* remap(P, 0, 1, W, 1)^2 = (W + P (1 - W))^2: the thesis default (§4.3.1) */
    CCL_PW_GPU_PRO_7 = 1, /* clamp(remap(P, W, 1, 0, 1), 0, 1) = clamp((P - W) / (1 - W)); 0 where W >= 1 */
    CCL_PW_HILLAIRE = 2,  /* remap(P, 0, 1, W, 1) = W + P (1 - W), unsquared (Hillaire's TileableVolumeNoise, 2016) */
    CCL_PW_PRODUCT = 3,   /* P * W */
    CCL_PW_AVERAGE = 4    /* (P + W) / 2 */
} ccl_perlin_worley_mode;

/* Default finite-difference step of the curl-noise functions: 1/CCL_NOISE_FD_STEP_INV = 1/256 lattice units. A power
 * of two (p +- h is exact for dyadic p such as texel centres); it balances the O(h^2) truncation error (~3e-4 on the
 * gradient) against the O(eps / h) float32 cancellation error (~1e-4). */
#define CCL_NOISE_FD_STEP_INV 256

/* Upper bound of frequency * 2^(octaves - 1), the finest octave's lattice frequency, of ccl_noise_fbm_perlin3: 2^24
 * lattice cells per unit of p, the float32 position limit of the noise itself. Keeps every octave's frequency finite
 * (beyond FLT_MAX, f p at p = 0 was 0 * Inf = NaN) and is far above any use (the texture generator stays <= 4096). */
#define CCL_NOISE_FBM_MAX_FREQUENCY 16777216

/* ---- permutation tables ------------------------------------------------------------------------------------------ */

/* Fill out_perm[0..511] with the permutation table of `seed`: entries 0..255 are a permutation of 0..255 and
 * out_perm[256 + i] = out_perm[i]. Seed 0: Perlin's published table. Seed s != 0: the identity shuffled by
 * Fisher-Yates, i = 255 .. 1, j = ccl_hash_pcg(ccl_hash_pcg(s) + i) % (i + 1) (the modulo bias, < 2^-24, is
 * irrelevant here). Returns CCL_EINVAL if out_perm is NULL. */
CCL_API ccl_status ccl_noise_perm_table(uint32_t seed, uint8_t *out_perm);

/* ---- Perlin gradient noise (vc-A1, vc-A2) ------------------------------------------------------------------------ */

/* 3-D Perlin gradient noise with a permutation table. Ref: vc-A1 (Perlin 1985; Perlin 2002 "Improved Noise").
 * x, y, z: position in lattice units (|x| < 2^24 for a meaningful fractional part); perm: 512-entry table from
 * ccl_noise_perm_table; period: 0 (Perlin's lattice) or >= 1 (periodic with that period on every axis, vc-A2).
 * Output about [-1, 1]; exactly 0 at integer lattice points. */
CCL_API float ccl_noise_perlin3_perm(float x, float y, float z, const uint8_t *perm, int32_t period);

/* 3-D Perlin gradient noise for a seed; seed 0 = Ken Perlin's reference implementation. Ref: vc-A1.
 * See ccl_noise_perlin3_perm for the parameters. */
CCL_API float ccl_noise_perlin3(float x, float y, float z, uint32_t seed, int32_t period);

/* Seamless (tileable) 3-D Perlin noise: ccl_noise_perlin3 with a required period >= 1, so that
 * f(p + period e_i) == f(p). Ref: vc-A2 (lattice position reduced modulo the grid size before hashing). */
CCL_API float ccl_noise_perlin3_tiled(float x, float y, float z, int32_t period, uint32_t seed);

/* 2-D Perlin gradient noise: the 4-corner noise equal to perlin3(x, y, 0) with the quintic fade (bit for bit), with
 * a choice of interpolant for vc-fig-2.5. Ref: vc-A1 ("4 corners in 2-D"). interp: ccl_noise_interp. */
CCL_API float ccl_noise_perlin2_perm(float x, float y, const uint8_t *perm, int32_t period, ccl_noise_interp interp);

/* 2-D Perlin gradient noise for a seed. Ref: vc-A1. See ccl_noise_perlin2_perm. */
CCL_API float ccl_noise_perlin2(float x, float y, uint32_t seed, int32_t period, ccl_noise_interp interp);

/* ---- Worley cellular noise (vc-A3, vc-A4, vc-A5) ----------------------------------------------------------------- */

/* Feature point of lattice cell (ix, iy, iz) of a Worley lattice with `cells` cells per unit: the cell index is
 * wrapped modulo `cells` and hashed with the seed, h0 = H(wx + H(wy + H(wz + H(seed)))), h1 = H(h0), h2 = H(h1)
 * (H = ccl_hash_pcg); the offsets inside the cell are (h >> 9) / 2^23 in [0, 1). Returns the offsets o (cell units,
 * each in [0, 1)); the feature point lies at ((ix + o.x) / cells, ...) in noise coordinates.
 * Ref: vc-A3 step 1 (one feature point per cell). cells >= 1. */
CCL_API ccl_vec3 ccl_noise_worley_feature(int32_t ix, int32_t iy, int32_t iz, int32_t cells, uint32_t seed);

/* Worley (cellular) noise F1, periodic with period 1 on every axis. Ref: vc-A3 (Worley 1996), vc-A4 (metric,
 * inverse), vc-A5 (tileable).
 * x, y, z: position, period 1 (|x| * cells < 2^24); cells: cells per unit period, >= 1; seed: any uint32;
 * metric: CCL_WORLEY_EUCLIDEAN or CCL_WORLEY_MANHATTAN; inverse: 0 = F1, non-zero = 1 - F1.
 * F1 is the distance to the nearest feature point in cell units (x * cells), searched over the 27 neighbouring
 * cells, clamped to [0, 1]. The clamp makes the 27-cell search exact: a feature point two or more cells away along
 * some axis is at least 1 cell away in both metrics. Output [0, 1]; 0 (inverse: 1) at feature points. */
CCL_API float ccl_noise_worley3(float x, float y, float z, int32_t cells, uint32_t seed, ccl_worley_metric metric,
                                int inverse);

/* The three Worley variants of vc-fig-2.7 at one point: classic (Euclidean F1), Manhattan F1 and inverse
 * (1 - Euclidean F1), each equal to ccl_noise_worley3 with the corresponding options. Ref: vc-A4. */
CCL_API void ccl_noise_worley3_variants(float x, float y, float z, int32_t cells, uint32_t seed, float *out_classic,
                                        float *out_manhattan, float *out_inverse);

/* Tileable Worley noise by the literal construction of vc-A5: the unit cube holding cells^3 feature points (those
 * of ccl_noise_worley_feature) is surrounded by its 26 copies and every point tries all 27 placements of every
 * feature point; F1 = the smallest of the cells^3 * 27 distances, in cell units, clamped to [0, 1]. O(cells^3) per
 * call: a reference for ccl_noise_worley3 (which finds the same value with the wrapped 27-cell search), not for
 * texture generation. x, y, z in [0, 1) (other values are reduced modulo 1); cells in [1, 64]. Ref: vc-A5. */
CCL_API float ccl_noise_worley3_bruteforce(float x, float y, float z, int32_t cells, uint32_t seed,
                                           ccl_worley_metric metric, int inverse);

/* ---- fBm (vc-2.21, vc-A6) -------------------------------------------------------------------------------------- */

/* fBm of Perlin noise N_s(p) = sum_i w_i N(f_i p) / sum_i w_i, i = 0 .. octaves-1, with f_0 = frequency,
 * f_i = 2 f_{i-1}, w_0 = 1, w_i = w_{i-1} / 2 (vc-2.21 with the octave rules of vc-A6). Normalised by the sum of the
 * weights (2 - 2^(1 - octaves)), so the range equals that of one octave (about [-1, 1]).
 * octaves in [1, 24]; frequency > 0 (lattice cells per unit of p) with frequency * 2^(octaves - 1) <=
 * CCL_NOISE_FBM_MAX_FREQUENCY (asserted in debug builds); |p| * frequency * 2^(octaves - 1) < 2^24 for a meaningful
 * fractional part (finite, not NaN, below FLT_MAX); period: 0 or >= 1 = the period of octave 0 in its
 * lattice units, octave i uses period * 2^i (period * 2^(octaves-1) <= 2^30): the fBm then repeats every
 * period / frequency units of p (exactly when frequency is a power of two and p + period/frequency is exact). */
CCL_API float ccl_noise_fbm_perlin3_perm(float x, float y, float z, int32_t octaves, float frequency,
                                         const uint8_t *perm, int32_t period);

/* fBm of Perlin noise for a seed. Ref: vc-2.21, vc-A6. See ccl_noise_fbm_perlin3_perm. */
CCL_API float ccl_noise_fbm_perlin3(float x, float y, float z, int32_t octaves, float frequency, uint32_t seed,
                                    int32_t period);

/* Unnormalised 2-D fBm of the terrain demo: sum_i A0 g^i N(F0 lambda^i p), i = 0 .. octaves-1, with N = the 2-D Perlin
 * noise ccl_noise_perlin2_perm (quintic fade, period 0; the z = 0 slice of vc-A1), evaluated in the order of Kod 7.9:
 * value += amplitude * noise(frequency * p); amplitude *= gain; frequency *= lacunarity.
 * Ref: pt-alg-3.2 (fBm, printed A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2 of Kod 7.9). Unlike vc-2.21 it is NOT divided
 * by the sum of the weights: for noise in [-1, 1] and 0 <= gain <= 1, |fBm| <= A0 (1 - g^octaves) / (1 - g)
 * (2 (1 - 0.5^octaves) with the printed values).
 * p: position (|p| * frequency * lacunarity^(octaves-1) < 2^24); octaves in [1, 24]; perm from ccl_noise_perm_table;
 * amplitude A0 >= 0; frequency F0 > 0; gain in [0, 1]; lacunarity in [1, 4]. */
CCL_API float ccl_noise_fbm_perlin2_perm(ccl_vec2 p, int32_t octaves, const uint8_t *perm, float amplitude,
                                         float frequency, float gain, float lacunarity);

/* The 2-D fBm of pt-alg-3.2 for a seed (seed 0 = Perlin's table). Ref: pt-alg-3.2. See ccl_noise_fbm_perlin2_perm. */
CCL_API float ccl_noise_fbm_perlin2(ccl_vec2 p, int32_t octaves, uint32_t seed, float amplitude, float frequency,
                                    float gain, float lacunarity);

/* fBm of Worley noise: sum_i w_i W(p; cells * 2^i) / sum_i w_i with w_i = 2^-i (vc-2.21, vc-A6), periodic with
 * period 1. octaves in [1, 16]; cells >= 1 with cells * 2^(octaves-1) <= 2^16; metric and inverse as in
 * ccl_noise_worley3 (inverse applies per octave). Output [0, 1]. */
CCL_API float ccl_noise_fbm_worley3(float x, float y, float z, int32_t octaves, int32_t cells, uint32_t seed,
                                    ccl_worley_metric metric, int inverse);

/* ---- curl noise and its operators (vc-2.22 .. vc-2.26, vc-A7) ------------------------------------------------------
 * All derivatives are central differences with step h (default 1/CCL_NOISE_FD_STEP_INV = 1/256 lattice units):
 * d f / d x ~= (f(x + h) - f(x - h)) / ((x + h) - (x - h)) -- the denominator is the float32 spacing actually used.
 * The step actually used is max(h, 2^-20, |x| 2^-22): x + h and x - h stay distinct where h is below half an ulp of
 * x, and the quotients finite for every h in (0, 0.25] (the default step is unchanged below |x| = 2^14). Within one
 * step of FLT_MAX the point away from zero would overflow: it is x itself there (a one-sided difference), so every
 * finite coordinate gives a finite result (meaningful below |x| = 2^23, the Python registry's domain).
 * Base noise: 3-D Perlin noise N = perlin3(., seed, period). Vector potential of the 3-D reading:
 * psi(p) = (N(p), N(p + o1), N(p + o2)) with the large offsets o1 = (100.25, -57.75, 33.5),
 * o2 = (-41.5, 88.25, -119.75) (lattice units; non-integer so the three components are not lattice-aligned). */

/* Gradient nabla N = (dN/dx, dN/dy, dN/dz) of Perlin noise by central differences, returned as a vector (lattice
 * units^-1). Ref: vc-2.22. x, y, z: position (lattice units); seed, period as ccl_noise_perlin3; h in (0, 0.25]. */
CCL_API ccl_vec3 ccl_noise_gradient3(float x, float y, float z, uint32_t seed, int32_t period, float h);

/* Curl noise, 3-D reading: v = nabla x psi (vc-2.23) of the offset Perlin potential psi (see above), returned as a
 * vector (components of the order of 1-5). Ref: vc-2.23, vc-A7 reading (ii) (Bridson, Hourihan & Nordenstam 2007).
 * Divergence-free (vc-2.26). x, y, z: position (lattice units); seed (or the table perm), period as
 * ccl_noise_perlin3; h in (0, 0.25]. */
CCL_API ccl_vec3 ccl_noise_curl3_perm(float x, float y, float z, const uint8_t *perm, int32_t period, float h);
CCL_API ccl_vec3 ccl_noise_curl3(float x, float y, float z, uint32_t seed, int32_t period, float h);

/* 2-D curl (scalar circulation density) dF_y/dx - dF_x/dy of the planar noise field F = (N(p), N(p + o1)),
 * p = (x, y, 0) -- the literal reading of the thesis' "evaluate twice with a large offset, take the curl", which
 * yields a scalar (vc-A7 ambiguity). Equal to the z component of ccl_noise_curl3 at z = 0. Ref: vc-2.24. */
CCL_API float ccl_noise_rot2(float x, float y, uint32_t seed, int32_t period, float h);

/* Divergence nabla . psi = dpsi_x/dx + dpsi_y/dy + dpsi_z/dz of the offset Perlin potential psi (not zero in
 * general; contrast with vc-2.26). Ref: vc-2.25 (sum over i = 1..n; the printed i = 0 is an index error). */
CCL_API float ccl_noise_divergence3(float x, float y, float z, uint32_t seed, int32_t period, float h);

/* Residual of the property claimed for curl noise, v = ccl_noise_curl3 (nested central differences, same h).
 * Ref: vc-2.26. variant CCL_VARIANT_CORRECTED: nabla . v (div of a curl, ~0 up to float32 round-off: the property
 * meant); CCL_VARIANT_THESIS: |nabla x v| (the printed "nabla x F = 0", which does NOT hold: of the order of the
 * second derivatives of the noise). */
CCL_API float ccl_noise_curl_property(float x, float y, float z, uint32_t seed, int32_t period, float h,
                                      ccl_variant variant);

/* Curl noise, 2-D reading: v = (dpsi/dy, -dpsi/dx) of the stream function psi = perlin3(x, y, 0), returned as a
 * 2-vector. Tangent to the level sets of psi and divergence-free. Ref: vc-A7 reading (i) (Bridson et al. 2007, 2-D).
 * x, y: position (lattice units); seed (or the table perm), period as ccl_noise_perlin3; h in (0, 0.25]. */
CCL_API ccl_vec2 ccl_noise_curl2_perm(float x, float y, const uint8_t *perm, int32_t period, float h);
CCL_API ccl_vec2 ccl_noise_curl2(float x, float y, uint32_t seed, int32_t period, float h);

/* ---- Perlin-Worley combination (vc-A8) ------------------------------------------------------------------------- */

/* Combination of fBm Perlin P and inverse-Worley fBm W, both in [0, 1], for the R channel of the base texture.
 * Ref: vc-A8. combination: ccl_perlin_worley_mode (see the enum). Output [0, 1] for inputs in [0, 1]. */
CCL_API float ccl_noise_perlin_worley(float p, float w, ccl_perlin_worley_mode combination);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_NOISE_H */
