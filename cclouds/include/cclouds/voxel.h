/*
 * cclouds/voxel.h -- the 3-D cloud array of the oc text (Kucera 2006, §5.2): a cubic array of opacities 0..255
 * built from a size/8 array of value noise by repeated up-sampling with added noise (oc-5.2.1), cut out by the
 * exponential cover/sharpness filter (oc-5.2.2), with the box-border problem (oc-5.2.3), the rejected SIN rounding
 * (oc-5.2.3.1) and the adopted zero-border "larger array" (oc-5.2.3.2), and per-axis scaling (oc-5.2.3-scale).
 *
 * The build (readings where the text is silent, spec erratum 7):
 *   levels    L = `levels` arrays of edge n_l = (size >> (L - 1)) << l, l = 0 .. L-1: the text's size/8 -> size is
 *             L = 4 (size/8, size/4, size/2, size).
 *   level 0   A_0[v] = a_0 N_0(v); level l > 0: A_l[v] = U(A_{l-1})(v) + a_l N_l(v), where N_l(v) =
 *             ccl_valuenoise_smooth(i, j, k, ccl_hash_pcg(seed) + l, 3, smoothing, CCL_VALUENOISE_UNIT) (the octave
 *             seeds of ccl_valuenoise_fbm: level l is octave l) and a_l = ccl_valuenoise_amplitude(l, persistence,
 *             variant) (the persistence schedule of oc-5.1.2.2 -- presumably what "new noise with lower amplitude"
 *             means).
 *   up-sample U: separable (x, then y, then z) with the chosen interpolant (linear = trilinear, the 3-D analogue of
 *             the text's bilinear; cosine; the printed cubic with clamped end nodes), corners aligned: fine index i
 *             of n_f maps to coarse position i (n_c - 1) / (n_f - 1), so the faces of each level map onto the faces
 *             of the one before.
 *   noise     n = clamp(A_{L-1} / sum_l a_l, 0, 1) (the cubic may overshoot), voxel (x, y, z) at index
 *             (z * size + y) * size + x.
 *   borders   CCL_VOXEL_BORDER_NONE: noise everywhere -- the border problem of oc-5.2.3, the cloud is cut by the box;
 *             CCL_VOXEL_BORDER_SIN: the rejected rounding of oc-5.2.3.1, n *= w(x) w(y) w(z) with
 *             w = ccl_voxel_sin_window(min(i, size - 1 - i), sin_radius * size) (our reading of "attenuate coordinate by
 *             coordinate with SIN near the borders": the cloud is no longer cut, but it takes the box's rounded
 *             shape -- why the author rejected it);
 *             CCL_VOXEL_BORDER_ZERO (default): the larger array of oc-5.2.3.2 -- the outermost cell layer of every
 *             level is 0 and never filled (neither by the up-sampling nor by the added noise), so every level can
 *             interpolate toward zero on all sides; the array of edge `size` is the cloud's interior (size - 2)
 *             plus the zero border (the text does not give the border width: one cell per level).
 *   envelope  (beyond the text) n = n - envelope * q(x, y, z), q = ccl_voxel_envelope(x, y, z, size,
 *             envelope_base): the squared radius of the ellipsoids inscribed in the box (1 on the inscribed one, up to
 *             3 in the corners), their centre lowered so that the base falls off faster than the top; after the border
 *             handling, before the clamp. envelope = 0 (default): the text's array as printed. The zero border only
 *             stops the noise at the faces: a cloud that fills its box still shows the box's flat faces. The falloff
 *             subtracts little in the core, where the noise and the cover decide the outline (lumps the size of the
 *             noise's features), and ever more towards the faces, so the cloud is compact and ends well inside its
 *             box with no face to show: a lumpy top and a flatter base (Gardner's textured ellipsoids, oc-4.3, in
 *             the text's pipeline). Subtracted, not multiplied: a weight in [0, 1] times the noise moves the
 *             outline with the weight's steep slope, not with the noise, and every cloud became the same ellipsoid.
 *   filter    density = ccl_voxel_filter(n, cover, sharpness), stored as uint8 round(density).
 *   scaling   the cloud is scaled per axis by resampling the uint8 array (ccl_voxel_scale), corners aligned, so a
 *             zero border stays zero; a renderer may scale its box instead (what a SoScale node does in Coin3D).
 */
#ifndef CCLOUDS_VOXEL_H
#define CCLOUDS_VOXEL_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Border handling (oc-5.2.3, 5.2.3.1, 5.2.3.2). */
#define CCL_VOXEL_BORDER_NONE 0
#define CCL_VOXEL_BORDER_SIN 1
#define CCL_VOXEL_BORDER_ZERO 2

#define CCL_VOXEL_MAX_LEVELS 6      /* size/32 -> size */
#define CCL_VOXEL_MIN_BASE 4        /* edge of the level-0 array: 2 interior cells inside a zero border */
#define CCL_VOXEL_MAX_SIZE 256      /* 256^3 floats = 64 MiB per level buffer */
#define CCL_VOXEL_MAX_SCALE_EDGE 1024 /* largest edge of a scaled volume */

/* Settings of the cloud array. The text gives no values (spec §4: "no value given"); the defaults and why:
 *   size 64             -- the array name noise64 of the filter listing (oc-5.2.2) suggests 64^3.
 *   levels 4            -- size/8 -> size (§5.2.1): 8^3, 16^3, 32^3, 64^3.
 *   seed 0              -- any; the same seed gives the same volume.
 *   persistence 0.5     -- Elias's example value; the text only says 0-1 and that lower values look better (5.5).
 *   interpolation LINEAR-- trilinear, the 3-D analogue of the bilinear up-sampling of §5.1.1; "mainly used for
 *                          real-time computation" (§5.1.4.1).
 *   smoothing ELIAS     -- Elias's weights (oc-5.1.3) on the noise added at each level: with raw per-voxel noise
 *                          the finest levels make a speckled "popcorn" cloud; smoothed, the clouds are compact.
 *   variant CORRECTED   -- amplitude persistence^l (CCL_VARIANT_THESIS: the printed squaring).
 *   border ZERO         -- the method the text adopts (oc-5.2.3.2).
 *   sin_radius 0.125    -- radius of the SIN rounding as a fraction of the edge: one level-0 cell (size/8).
 *   cover 128           -- threshold in 0..255 units, the middle of the range: smoothed noise spreads little
 *                          around its mean (about 0.4 x 255 with the zero border's fall-off), so 128 keeps the
 *                          brightest 15-30 % of the voxels -- one or a few compact clouds inside the box.
 *   sharpness 0.96      -- soft but visible edges: 255 (1 - 0.96^c) reaches half density at c = 17 units above the
 *                          cover (Elias's tutorial uses values of this order).
 *   envelope 0          -- the text's array as printed (the flight scene asks for 0.5).
 *   envelope_base 0.35  -- lower semi-axis of the ellipsoids over the upper one: the base falls off about three
 *                          times as fast as the top (a fair-weather cumulus: a flat base at the condensation level
 *                          under a dome). */
typedef struct ccl_voxel_settings {
    int32_t size;           /* edge in voxels, [CCL_VOXEL_MIN_BASE << (levels - 1), CCL_VOXEL_MAX_SIZE], a multiple
                               of 2^(levels - 1) */
    int32_t levels;         /* [1, CCL_VOXEL_MAX_LEVELS] */
    uint32_t seed;          /* any uint32 */
    float persistence;      /* (0, 1] */
    int32_t interpolation;  /* CCL_VALUENOISE_LINEAR / COSINE / CUBIC */
    int32_t smoothing;      /* CCL_VALUENOISE_SMOOTH_* */
    int32_t variant;        /* CCL_VARIANT_CORRECTED / CCL_VARIANT_THESIS (persistence schedule) */
    int32_t border;         /* CCL_VOXEL_BORDER_* */
    float sin_radius;       /* (0, 0.5], fraction of the edge (used by CCL_VOXEL_BORDER_SIN only) */
    float cover;            /* [0, 255] */
    float sharpness;        /* (0, 1) */
    float envelope;         /* [0, 1], noise subtracted on the inscribed ellipsoid (0: none) */
    float envelope_base;    /* (0, 1], lower over upper semi-axis of the ellipsoids */
} ccl_voxel_settings;

/* The documented defaults above. Ref: oc-5.2.1. */
CCL_API ccl_voxel_settings ccl_voxel_settings_default(void);

/* Validate settings: CCL_OK, or CCL_EINVAL with *out_field = the name of the first invalid field in the order of the
 * struct ("size" also when size is not a multiple of 2^(levels - 1) or its level-0 edge is below CCL_VOXEL_MIN_BASE);
 * *out_field = NULL when valid. s == NULL gives CCL_EINVAL and "s". out_field may be NULL. Ref: oc-5.2.1. */
CCL_API ccl_status ccl_voxel_settings_check(const ccl_voxel_settings *s, const char **out_field);

/* Exponential cloud filter, as printed: c = n * 255 - cover, c = max(c, 0), density = 255 - sharpness^c * 255.
 * Ref: oc-5.2.2 (Elias's cloud filter). n -> the noise value in [0, 1]; cover -> cloudCover, a threshold in 0..255
 * units; sharpness -> cloudSharpness in (0, 1) (1 gives 0 everywhere, > 1 negative densities: refused). Output
 * density in [0, 255]: 0 wherever n * 255 <= cover; increasing in n, DECREASING in cover (a larger "how big a cloud
 * we want" gives less cloud: the text's label reads inverted, erratum 6 -- read cover as a coverage threshold) and
 * decreasing in sharpness (near 0: hard edges, near 1: soft, faint edges). Evaluated as 255.0f - powf(s, c) * 255.0f. */
CCL_API float ccl_voxel_filter(float n, float cover, float sharpness);

/* SIN rounding weight at distance d (in voxels) from the nearest face: w = sin(pi/2 * (d / radius)) for d < radius,
 * else 1. Ref: oc-5.2.3.1 (rejected by the author; no formula printed -- this is our reading). In the cloud array
 * d = min(i, size - 1 - i) per axis and the weights of the three axes multiply. d -> [0, 4096] voxels;
 * radius -> (0, 4096] voxels. Output [0, 1], 0 on a face (d = 0). pi/2 = 1.57079637f. */
CCL_API float ccl_voxel_sin_window(int32_t d, float radius);

/* Squared radius of the envelope's ellipsoids at voxel (x, y, z) of a cubic array of edge n (y up): with m = n - 1,
 * dx = (2x - m) / m, dz = (2z - m) / m, the centre at height c = base / (1 + base) (fraction of the edge),
 * u = y / m, dy = (u - c) / (1 - c) above the centre, (c - u) / c below; q = dx^2 + dy^2 + dz^2. 0 at the centre,
 * 1 on the ellipsoid inscribed in the box, at most 3 (a corner); continuous. Ref: the envelope of the cloud array
 * (beyond the text; oc-4.3 in kind). x, y, z -> [0, n - 1]; n -> [2, 4096]; base -> (0, 1]. */
CCL_API float ccl_voxel_envelope(int32_t x, int32_t y, int32_t z, int32_t n, float base);

/* The noise array before filtering (the "nebula" of fig. 5.11): float32 in [0, 1], size^3 values indexed
 * (z * size + y) * size + x, built as described at the top of this header (border handling included).
 * Ref: oc-5.2.1, oc-5.2.3, oc-5.2.3.1, oc-5.2.3.2. CCL_EINVAL for invalid settings, CCL_ERANGE if out_len < size^3,
 * CCL_ENOMEM if the level buffers cannot be allocated. Single-threaded. */
CCL_API ccl_status ccl_voxel_noise(const ccl_voxel_settings *s, float *out, size_t out_len);

/* The cloud array: ccl_voxel_noise, then ccl_voxel_filter per voxel, stored as uint8 round(density) (0 = invisible,
 * 255 = fully opaque, §5.2.1). Ref: oc-5.2.1, oc-5.2.2, oc-5.2.3.2. Same layout and errors as ccl_voxel_noise. With
 * CCL_VOXEL_BORDER_ZERO every voxel of the six outer faces is 0. */
CCL_API ccl_status ccl_voxel_cloud(const ccl_voxel_settings *s, uint8_t *out, size_t out_len);

/* Per-axis scaling by resampling: dst (mx, my, mz) from src (nx, ny, nz), both indexed (z * ny + y) * nx + x,
 * trilinear with corners aligned (dst index i samples src position i (n - 1) / (m - 1); a face maps onto a face),
 * each axis blended as ccl_valuenoise_linear, rounded to uint8. Ref: oc-5.2.3-scale (the factor per axis is m / n).
 * Edges in [2, CCL_VOXEL_MAX_SCALE_EDGE]; CCL_EINVAL for NULL pointers or edges out of range. */
CCL_API ccl_status ccl_voxel_scale(const uint8_t *src, int32_t nx, int32_t ny, int32_t nz, uint8_t *dst, int32_t mx,
                                   int32_t my, int32_t mz);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_VOXEL_H */
