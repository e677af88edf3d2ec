/*
 * cclouds/draw.h -- drawing with formulas (pt §3.3 - §3.5): pixel coordinates, curves drawn from formulas, the sine /
 * fBm / marble textures, domain-warped noise and the animated-butterfly stand-in.
 *
 * Conventions: 2-D points are ccl_vec2 (x to the right, y up); "centred coordinates" p are those of pt-alg-3.3,
 * p = 2 uv - 1 in (-1, 1)^2 (x scaled by width/height when aspect correction is asked for). The fBm of every function
 * here is the unnormalised 2-D fBm of pt-alg-3.2 (ccl_noise_fbm_perlin2: A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2,
 * 2-D Perlin noise with seed `seed`); its octave count is a parameter because the text does not give it.
 */
#ifndef CCLOUDS_DRAW_H
#define CCLOUDS_DRAW_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Aspect handling of ccl_draw_coords. */
typedef enum ccl_draw_aspect {
    CCL_DRAW_ASPECT_NONE = 0, /* as pt-alg-3.3 / Kod 3.1: p in (-1, 1)^2, circles look elliptic in non-square windows */
    CCL_DRAW_ASPECT_X = 1     /* as Kod 7.1: p.x *= width / height, so one unit is the same length on both axes */
} ccl_draw_aspect;

/* Colour index of ccl_draw_curves (the draw order of Kod 3.1: later curves overwrite earlier ones). */
typedef enum ccl_draw_colour {
    CCL_DRAW_BACKGROUND = 0,
    CCL_DRAW_RED = 1,    /* y = 0.1 e^x */
    CCL_DRAW_BLUE = 2,   /* (x + 0.9)^2 + y^2 = 0.4 */
    CCL_DRAW_YELLOW = 3  /* x = 0.2 sin(15 y) */
} ccl_draw_colour;

/* Pixel position -> normalised, centred and polar coordinates. Ref: pt-alg-3.3 (Obrazok 3.4); aspect option as Kod 7.1.
 * frag: window position in pixels (pixel centres at i + 0.5, origin bottom-left), components in [-65536, 65536];
 * resolution: window size in pixels, components in [1, 65536]; aspect: ccl_draw_aspect.
 * Returns uv = frag / resolution ((0, 1)^2 inside the window); out_p = 2 uv - 1 (x times width/height with
 * CCL_DRAW_ASPECT_X); out_polar = (r, phi) = (|p|, atan2(p.y, p.x)), phi in [-pi, pi] (the text does not give the
 * polar formula). */
CCL_API ccl_vec2 ccl_draw_coords(ccl_vec2 frag, ccl_vec2 resolution, int aspect, ccl_vec2 *out_p,
                                 ccl_vec2 *out_polar);

/* The three curves of Kod 3.1 at centred point p: y = 0.1 e^x (red), (x + 0.9)^2 + y^2 - 0.4 = 0 (blue, circle of
 * radius sqrt(0.4) around (-0.9, 0)), x = 0.2 sin(15 y) (yellow). A point belongs to a curve when |residual| <
 * threshold (0.01 printed; in function-value units, so the line width varies with the slope); later tests overwrite
 * earlier ones (red, blue, yellow). Ref: pt-code-3.1. p components in [-16, 16]; threshold in (0, 1].
 * Returns a ccl_draw_colour. */
CCL_API int ccl_draw_curves(ccl_vec2 p, float threshold);

/* Sine, fBm and marble of Kod 3.2 at centred point p: fbm = fBm(5 p) (ccl_noise_fbm_perlin2 with `octaves` octaves,
 * seed `seed`), sine = (1 + sin(50 p.x)) / 2, combination = (1 + sin((p.x + fbm / 2) 50)) / 2.
 * Ref: pt-code-3.2. p components in [-1000, 1000]; octaves in [1, 12]. Returns sine in [0, 1]; out_fbm in
 * (-2, 2); out_combination in [0, 1]. */
CCL_API float ccl_draw_marble(ccl_vec2 p, int32_t octaves, uint32_t seed, float *out_fbm, float *out_combination);

/* Domain-warped fBm of Obrazok 3.3, depth levels of warping. Ref: pt-u-warp.
 * variant CCL_VARIANT_THESIS (the caption as printed, scalar offsets): q_0 = 0, q_{k+1} = fBm(p + s q_k (1, 1)),
 *   value = fBm(p + s q_depth (1, 1)): depth 0 = p(x), 1 = p(x + p(x)), 2 = p(x + p(x + p(x))) with s = 1.
 * variant CCL_VARIANT_CORRECTED (Quilez, "Domain Warping", vector offsets): q_0 = (0, 0),
 *   q_{k+1} = (fBm(p + s q_k + o_{2k}), fBm(p + s q_k + o_{2k+1})), value = fBm(p + s q_depth), with Quilez's offsets
 *   o = (0, 0), (5.2, 1.3), (1.7, 9.2), (8.3, 2.8) and his strength s = 4.
 * p components in [-1000, 1000]; depth in [0, 2]; octaves in [1, 12]; strength s in [0, 16]. Output in (-2, 2). */
CCL_API float ccl_draw_warp(ccl_vec2 p, int32_t depth, int32_t octaves, float strength, uint32_t seed,
                            ccl_variant variant);

/* The animated butterfly of pt §3.5 as a stand-in (the text gives no formula): two rectangles (span 1, length 1.2
 * along the body, the z axis) hinged on the body axis carry a wing texture drawn with formulas (two ellipses, black
 * border with white spots, veins radiating from the hinge, dark body strip). Hinge angle theta(t) = 1.0 sin(2 pi 1.5 t)
 * rad above the horizontal; the butterfly flies along c(t) = (0.6 sin(w t), 0.25 sin(2 w t), 0), w = 2 pi / 4 s; so
 * the animation repeats every 4 s. Camera at (0, 2, -3) looking at the origin, image plane at distance 1.5, world up
 * +y (the basis of Kod 7.2). Ref: pt-alg-3.5.
 * p: centred, aspect-corrected screen coordinates (Kod 7.1), components in [-4, 4]; time in seconds, [0, 3600].
 * Returns the RGB colour in [0, 1]^3 (wing texture shaded by 0.55 + 0.45 |n . rd|, else a sky gradient). */
CCL_API ccl_vec3 ccl_draw_butterfly(ccl_vec2 p, float time);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_DRAW_H */
