/*
 * cclouds/fractal.h -- escape-time fractals of pt §3.6: Julia sets (eq. 3.1, Obrazok 3.8) and the Mandelbrot set
 * (eq. 3.2, 3.3, Obrazok 3.9).
 *
 * Complex numbers are ccl_vec2 with x = real part, y = imaginary part (the registry's vector type: one argument per
 * complex number, passed by value in C and as wp.vec2 in Warp). Arithmetic in float32, in the order written in
 * fractal.c: (a + bi)(c + di) = (ac - bd) + (ad + bc)i.
 *
 * Escape counts: the iteration a_0, a_1 = f(a_0), ... stops at the first a_n that fails the escape test; the count is
 * that n (0 .. max_iter - 1), or max_iter when no iterate a_0 .. a_{max_iter-1} escaped (the point is taken as a member of
 * the set: an approximation whose detail grows with max_iter, as the text says). Smooth (continuous) counts:
 *   polynomial maps z^d + c, escape |a_n| > R: smooth = n + 1 - log_d(ln|a_n| / ln R), about [n, n + 1) (the usual
 *     normalised iteration count, Vepstas 1997; exact in the limit of large R, where |a_n| ~ |a_{n-1}|^d);
 *   exponential map e^z + c, escape Re(a_n) > R: smooth = n + 1 - clamp(ln(Re a_n) / R, 0, 1) (a_n ~ e^{a_{n-1}}, so
 *     ln Re a_n ~ Re a_{n-1} <= R: continuous across the escape step);
 *   members: smooth = max_iter.
 */
#ifndef CCLOUDS_FRACTAL_H
#define CCLOUDS_FRACTAL_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Map family of ccl_fractal_julia. */
typedef enum ccl_fractal_map {
    CCL_FRACTAL_POLY = 0, /* f(z) = z^power + c, escape |z| > escape */
    CCL_FRACTAL_EXP = 1   /* f(z) = e^z + c, escape Re(z) > escape (|z| is no test for e^z: e^z is periodic in Im z and
                             small for Re z << 0, so orbits escape along the positive real direction) */
} ccl_fractal_map;

/* The three Julia sets of Obrazok 3.8 (pt-u-julia). */
typedef enum ccl_fractal_example {
    CCL_JULIA_X5 = 0,  /* f(x) = x^5 + 0.544 */
    CCL_JULIA_X2 = 1,  /* f(x) = x^2 + 0.285 + 0.01i */
    CCL_JULIA_EXP = 2  /* f(x) = e^x - 0.65 */
} ccl_fractal_example;

/* Escape-time Julia iteration a_0 = z0, a_{n+1} = f(a_n) (eq. 3.1). Ref: pt-3.1.
 * z0: start value = the pixel's point of the complex plane, components in [-1e6, 1e6]; c: the map's constant,
 * components in [-100, 100]; power: d of z^d + c, in [2, 12] (ignored by the exp map); max_iter in [1, 100000];
 * escape: R in (1, 64] (polynomial map: any R >= max(|c|, 2^(1/(d-1))) proves escape; exp map: e^R stays finite in
 * float32 and Re z > R makes the next iterate ~e^R); map: ccl_fractal_map.
 * Returns the escape count n in [0, max_iter]; out_smooth: the continuous count (see the header comment). */
CCL_API int32_t ccl_fractal_julia(ccl_vec2 z0, ccl_vec2 c, int32_t power, int32_t max_iter, float escape, int map,
                                  float *out_smooth);

/* The Julia sets of Obrazok 3.8 with escape tests that suit each: x^5 + 0.544 and x^2 + 0.285 + 0.01i with |z| > 16
 * (2 already proves escape for both; 16 makes the smooth count's log-log approximation accurate), e^x - 0.65 with
 * Re(z) > 50. Ref: pt-u-julia (pt-3.1). z0 components in [-1e6, 1e6]; max_iter in [1, 100000];
 * example: ccl_fractal_example. Returns the escape count; out_smooth the continuous count. */
CCL_API int32_t ccl_fractal_julia_example(ccl_vec2 z0, int32_t max_iter, int example, float *out_smooth);

/* One step of the quadratic family of eq. 3.2. Ref: pt-3.2.
 * variant CCL_VARIANT_THESIS: f(z) = z^2 - mu as printed (the set in the mu plane is the usual Mandelbrot set
 *   mirrored, mu = -c: antenna towards +2);
 * variant CCL_VARIANT_CORRECTED: f(z) = z^2 + mu, the usual convention (mu = c).
 * z, mu components in [-1e6, 1e6]. Returns f(z). */
CCL_API ccl_vec2 ccl_fractal_quadratic(ccl_vec2 z, ccl_vec2 mu, ccl_variant variant);

/* Mandelbrot orbit and membership test (eq. 3.3): a_0 = 0, a_{n+1} = f(a_n) with f of ccl_fractal_quadratic; mu is a
 * member while |a_n| <= escape (2 printed) for every computed n. Ref: pt-3.3 (pt-3.2).
 * mu components in [-1e6, 1e6]; max_iter in [1, 100000]; escape in [2, 256] (2 printed; a larger R only smooths the
 * continuous count: |a_n| > 2 already proves escape). Returns the escape count in [0, max_iter] (max_iter = member);
 * out_smooth the continuous count. */
CCL_API int32_t ccl_fractal_mandelbrot(ccl_vec2 mu, int32_t max_iter, float escape, ccl_variant variant,
                                       float *out_smooth);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_FRACTAL_H */
