/*
 * cclouds/valuenoise.h -- value noise on an integer lattice, the way Hugo Elias's tutorial and the oc text build it
 * (Kucera 2006, §5.1): a seeded lattice hash (oc-5.1.2), neighbour smoothing (oc-5.1.3), linear / cosine / cubic
 * interpolation exactly as printed (oc-5.1.4.1 - 5.1.4.3) in 1-D, 2-D and 3-D separable form (oc-5.1.4), and the
 * octave sum with persistence (oc-5.1.1, oc-5.1.2.1, oc-5.1.2.2). The text calls the result "Perlin noise"; it is
 * value noise (random values at lattice points), not Perlin's gradient noise (spec erratum 1).
 *
 * Readings where the text is silent (each a named option or a documented constant):
 *   hash      lattice(x, y, z, seed) = ccl_hash_unit(pcg(x + pcg(y + pcg(z + seed)))) in uint32 arithmetic (the
 *             project's PCG hash, hash.h); the text gives no generator. 1-D noise is the x axis (y = z = 0), 2-D the
 *             z = 0 plane: a function of "dims" ignores the coordinates beyond dims.
 *   range     [0, 1] (CCL_VALUENOISE_UNIT, the default: the cloud filter oc-5.2.2 multiplies by 255) or [-1, 1]
 *             (CCL_VALUENOISE_SIGNED, 2u - 1): the text states both (L326 vs L334, erratum 2). Exactly:
 *             unit {0, 2^-24, ..., 1 - 2^-24}, signed {-1, -1 + 2^-23, ..., 1 - 2^-23}.
 *   smoothing CCL_VALUENOISE_SMOOTH_ELIAS (default): Elias's weights corners/16 + sides/8 + centre/4 in 2-D, i.e. the
 *             binomial (1/4, 1/2, 1/4) per axis (1-D: centre/2 + sides/4; 3-D: corners/64 + edges/32 + faces/16 +
 *             centre/8); SMOOTH_4: the mean of the 4 side neighbours (1-D: 2, 3-D: 6 face neighbours), centre
 *             excluded ("average of the neighbours", §5.1.3); SMOOTH_8: the mean of the 8 neighbours (1-D: 2,
 *             3-D: 26); SMOOTH_NONE: the raw lattice value. The text names no neighbourhood (erratum 4).
 *   octaves   octave i samples the lattice at frequency 2^i (frequency 1 first, x2 each octave, §5.1.2.1) with the
 *             octave seed pcg(seed) + i (a different random lattice per octave, as in Elias's tutorial); amplitude
 *             p^i ('corrected') or the printed squaring p^(2^i) ('thesis', erratum 3); the sum is divided by the sum
 *             of the amplitudes so that it stays in the noise's range (the text gives no normalisation; the filter
 *             needs [0, 1]).
 *
 * Pure float32 functions in uint32 hashing; no state; C and the Warp twins (pywarp/kernels/valuenoise.py) compute the
 * same operations in the same order.
 */
#ifndef CCLOUDS_VALUENOISE_H
#define CCLOUDS_VALUENOISE_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Value range of the lattice values (oc-5.1.2). */
#define CCL_VALUENOISE_UNIT 0      /* [0, 1] (default) */
#define CCL_VALUENOISE_SIGNED 1    /* [-1, 1] */

/* Neighbour smoothing (oc-5.1.3). */
#define CCL_VALUENOISE_SMOOTH_ELIAS 0   /* binomial (1/4, 1/2, 1/4) per axis: Elias's corner/side/centre weights */
#define CCL_VALUENOISE_SMOOTH_4 1       /* mean of the side (face) neighbours, centre excluded */
#define CCL_VALUENOISE_SMOOTH_8 2       /* mean of all neighbours, centre excluded */
#define CCL_VALUENOISE_SMOOTH_NONE 3    /* raw lattice values */

/* Interpolation kinds (oc-5.1.4.1 - 5.1.4.3). */
#define CCL_VALUENOISE_LINEAR 0
#define CCL_VALUENOISE_COSINE 1
#define CCL_VALUENOISE_CUBIC 2

/* Limits: octave count of the sums; lattice coordinates of the element-wise functions. */
#define CCL_VALUENOISE_MAX_OCTAVES 12     /* 2^11 x the coordinate range stays exact in float32 */
#define CCL_VALUENOISE_MAX_COORD 4096     /* continuous coordinates in [0, 4096]: 4096 * 2^11 = 2^23 */

/* Lattice noise. Ref: oc-5.1.2 (§5.1.2; a deterministic function of non-negative integers). x, y, z -> lattice
 * point (integers >= 0; the hash wraps in uint32); seed -> any uint32; range -> CCL_VALUENOISE_UNIT (output
 * {0, ..., 1 - 2^-24}) or CCL_VALUENOISE_SIGNED (2u - 1, output [-1, 1 - 2^-23]). Same arguments, same value.
 * u = ccl_hash_unit(ccl_hash_pcg(x + ccl_hash_pcg(y + ccl_hash_pcg(z + seed)))), sums mod 2^32. */
CCL_API float ccl_valuenoise_lattice(int32_t x, int32_t y, int32_t z, uint32_t seed, int range);

/* Smoothed lattice noise: the weighted average of the lattice point's neighbourhood over the first dims axes.
 * Ref: oc-5.1.3 (§5.1.3; Elias's tutorial for the weights). x, y, z -> lattice point (>= 0; coordinates beyond dims
 * are ignored, taken as 0); seed -> any uint32; dims -> 1, 2 or 3; smoothing -> CCL_VALUENOISE_SMOOTH_*;
 * range -> as ccl_valuenoise_lattice. Output within the range of the lattice values (a convex combination). */
CCL_API float ccl_valuenoise_smooth(int32_t x, int32_t y, int32_t z, uint32_t seed, int32_t dims, int smoothing,
                                    int range);

/* Linear interpolation, as printed: a (1 - x) + b x. Ref: oc-5.1.4.1 (and the definition oc-5.1.4: x = 0 -> a,
 * x = 1 -> b). a, b -> the end values (any finite float); x -> position in [0, 1]. Exactly a at x = 0 and b at x = 1
 * (a + x (b - a), ccl_interp_lerp, need not give exactly b at x = 1 in float32: hence its own function). Output
 * between a and b: where the sum rounds an ulp outside (a = b = 1000), the nearest of the two. */
CCL_API float ccl_valuenoise_linear(float a, float b, float x);

/* Cosine interpolation, as printed: ft = x * 3.1415927, f = (1 - cos(ft)) * .5, a (1 - f) + b f. Ref: oc-5.1.4.2.
 * a, b -> the end values; x -> [0, 1]. Exactly a at x = 0, b at x = 1, (a + b)/2 at x = 1/2 (up to one rounding);
 * (0, 1, 0.25) -> 0.1464466. Output between a and b (as ccl_valuenoise_linear: the nearest of the two where the
 * sum rounds an ulp outside them). */
CCL_API float ccl_valuenoise_cosine(float a, float b, float x);

/* Cubic interpolation, as printed: P = (v3 - v2) - (v0 - v1), Q = (v0 - v1) - P, R = v2 - v0, S = v1;
 * P x^3 + Q x^2 + R x + S (evaluated P*x*x*x + Q*x*x + R*x + S). Ref: oc-5.1.4.3. v0 -> the point before a,
 * v1 -> a, v2 -> b, v3 -> the point after b; x -> [0, 1] between v1 and v2. Gives v1 at x = 0 and v2 at x = 1 (up to
 * rounding); the slopes are v2 - v0 at x = 0 and v3 - v1 at x = 1 -- twice Catmull-Rom's (v2 - v0)/2: this is NOT
 * Catmull-Rom. It may overshoot the range of its samples. */
CCL_API float ccl_valuenoise_cubic(float v0, float v1, float v2, float v3, float x);

/* Interpolated smoothed noise at a continuous point, separable over the first dims axes (x, then y, then z): linear
 * (bi-/trilinear), cosine, or cubic (4 nodes per axis: 4, 16, 64 smoothed values). Ref: oc-5.1.4 (interpolation
 * between lattice values; the 2-D and 3-D forms apply the 1-D interpolant per axis). x, y, z -> point in lattice
 * units, [0, CCL_VALUENOISE_MAX_COORD] (beyond dims ignored); seed, dims, smoothing, range -> as ccl_valuenoise_smooth;
 * interpolation -> CCL_VALUENOISE_LINEAR / COSINE / CUBIC. Equals ccl_valuenoise_smooth at lattice points (cubic: up
 * to rounding). Linear/cosine stay within the range; cubic may overshoot it. */
CCL_API float ccl_valuenoise_interpolated(float x, float y, float z, uint32_t seed, int32_t dims, int smoothing,
                                          int interpolation, int range);

/* Amplitude of octave i. Ref: oc-5.1.2.2 (persistence, the printed listing
 * "Frequency = frequency * 2; Persistence = persistence * Persistence"). octave -> i in [0, CCL_VALUENOISE_MAX_OCTAVES);
 * persistence -> p in [0, 1]; variant -> CCL_VARIANT_CORRECTED: p^i (Elias's amplitude *= persistence; 1 for i = 0),
 * CCL_VARIANT_THESIS: the printed single-variable update read literally, p^(2^i) = p, p^2, p^4, p^8, ... Computed by
 * repeated multiplication (no powf), output in [0, 1]. */
CCL_API float ccl_valuenoise_amplitude(int32_t octave, float persistence, int variant);

/* Octave sum ("Perlin noise" of the text): sum_i a_i N_i(2^i x, 2^i y, 2^i z) / sum_i a_i over i < octaves, N_i =
 * ccl_valuenoise_interpolated with the octave seed ccl_hash_pcg(seed) + i, a_i = ccl_valuenoise_amplitude(i, p,
 * variant). Ref: oc-5.1.1 (summed octaves), oc-5.1.2.1 (frequency 1, x2 per octave, 6 octaves generally enough),
 * oc-5.1.2.2 (persistence), oc-4.5 (procedural noise: the survey's method the project implements).
 * x, y, z -> point in [0, CCL_VALUENOISE_MAX_COORD] (beyond dims ignored); seed -> any uint32; dims -> 1..3;
 * octaves -> [1, CCL_VALUENOISE_MAX_OCTAVES]; persistence -> (0, 1] (0 would weight every 'thesis' octave 0);
 * smoothing, interpolation, range -> as ccl_valuenoise_interpolated; variant -> as ccl_valuenoise_amplitude.
 * Output within the range of the noise for linear/cosine (cubic may overshoot). */
CCL_API float ccl_valuenoise_fbm(float x, float y, float z, uint32_t seed, int32_t dims, int32_t octaves,
                                 float persistence, int smoothing, int interpolation, int variant, int range);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_VALUENOISE_H */
