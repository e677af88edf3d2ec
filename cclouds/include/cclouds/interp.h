/*
 * cclouds/interp.h -- interpolants and remap shared by every topic: the fade curves of Perlin noise (vc-2.19,
 * vc-2.20), linear and cosine interpolation (vc-A1 step 3, vc-fig-2.6) and the linear range remap of vc-2.27.
 *
 * Pure float32 functions; NaN inputs propagate.
 */
#ifndef CCLOUDS_INTERP_H
#define CCLOUDS_INTERP_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fade (smoothstep) 3t^2 - 2t^3, evaluated as t*t*(3 - 2t). Ref: vc-2.19 (Perlin 1985).
 * t: fractional position in a lattice cell, domain [0, 1]; output [0, 1]; f'(0) = f'(1) = 0. */
CCL_API float ccl_interp_fade_cubic(float t);

/* Improved fade 6t^5 - 15t^4 + 10t^3, evaluated as Perlin's t*t*t*(t*(t*6 - 15) + 10), taken as 1 where that
 * rounds above 1 (1 + 2^-23 for 22,237 floats t in [0.99536, 1)). Ref: vc-2.20 (Perlin, "Improving Noise",
 * SIGGRAPH 2002). t in [0, 1]; output [0, 1] (checked for every float t); f' = f'' = 0 at t = 0 and t = 1. */
CCL_API float ccl_interp_fade_quintic(float t);

/* Linear interpolation a + t (b - a) (Perlin's lerp, argument order (t, a, b)). Ref: vc-A1 step 3.
 * t: weight, usually [0, 1] (other values extrapolate); a, b: the values at t = 0 and t = 1, any finite float. */
CCL_API float ccl_interp_lerp(float t, float a, float b);

/* Cosine interpolation: lerp((1 - cos(pi t)) / 2, a, b). Ref: vc-A1 step 3 ("cosine interpolation looks best";
 * the formula is not printed in the thesis -- the usual form is used), vc-fig-2.6. t in [0, 1]; a, b any finite
 * float; output between a and b. */
CCL_API float ccl_interp_cosine(float t, float a, float b);

/* remap(v, o_min, o_max, n_min, n_max) = n_min + (v - o_min) / (o_max - o_min) * (n_max - n_min). Ref: vc-2.27.
 * No clamping: values outside [o_min, o_max] extrapolate linearly; reversed ranges allowed; o_max != o_min
 * (o_max == o_min gives +-Inf or NaN). Units: those of the ranges. */
CCL_API float ccl_interp_remap(float v, float o_min, float o_max, float n_min, float n_max);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_INTERP_H */
