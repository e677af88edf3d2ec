/*
 * cclouds/texgen.h -- the noise-texture generator of vc §2.3.3 / §4.3.1: the 128^3 base-shape texture (vc-A9), the
 * 32^3 detail texture (vc-A10), a generated 2-D curl-noise texture (vc-A11), a procedural 2-D weather map (vc-A12),
 * their settings (vc-A13), the gamma correction of generated noise (vc-4.6) and the wrap-around trilinear sampler the
 * renderer uses on these textures.
 *
 * Conventions shared by every function of this header:
 *   - Texel (ix, iy, iz) of a texture of edge `size` sits at the texture coordinate u = (ix + 0.5) / size (texel
 *     centres, as in OpenGL); the noise is evaluated at u times an integer frequency with the noise period equal to
 *     that frequency, so every texture is exactly periodic: texel(ix + size) == texel(ix) bit for bit (vc-A2, vc-A5).
 *     Sizes are powers of two so that u is exact in float32.
 *   - Memory layout: x fastest, then y, then z; channels interleaved: out[((iz * size + iy) * size + ix) * C + c]
 *     (C = 4 RGBA for the base shape and the weather map, 3 RGB for the detail texture, 2 for curl noise). This is the
 *     layout of a NumPy array of shape (size, size, size, C) indexed [iz, iy, ix, c].
 *   - The inverse-Worley layers of the base and detail textures: four layers W_j, j = 0..3, of inverse Euclidean
 *     Worley noise (ccl_noise_worley3, inverse) with worley_cells * 2^j cells per texture (the octave rule of vc-A6)
 *     and seed + j (the octave seeds of ccl_noise_fbm_worley3).
 *   - How four Worley frequencies fill three channels (vc-A9; the thesis leaves it open, spec §7 item 24) -- our
 *     choice, a sliding window over the layers, as in Hillaire's TileableVolumeNoise (the Electronic Arts code the
 *     thesis says it adopted): channel k = sum_{j = 0..2, k + j <= 3} w_j W_{k+j} / sum_{same j} w_j, so
 *     G = fBm(W0, W1, W2), B = fBm(W1, W2, W3), A = fBm(W2, W3) (renormalised). Increasing frequency from G to A, as
 *     eq 2.28 expects. The detail texture uses the same rule for R, G, B (vc-A10).
 *   - R of the base texture (vc-A8): P = clamp(0.5 fbm_perlin + 0.5, 0, 1) (Perlin fBm mapped from about [-1, 1] to
 *     [0, 1], not stated in the thesis), W = the G channel value (the lowest-frequency inverse-Worley fBm, as in
 *     Hillaire's code), R = ccl_noise_perlin_worley(P, W, combination), default CCL_PW_THESIS = remap(P, 0, 1, W, 1)^2.
 *   - Every channel is clamped to [0, 1] and then gamma-corrected with vc-4.6 (C^(1/gamma)); gamma = 1 is the
 *     identity.
 *   - Seeds: any uint32; the Perlin part uses the permutation table of `seed` (seed 0 = Ken Perlin's reference).
 */
#ifndef CCLOUDS_TEXGEN_H
#define CCLOUDS_TEXGEN_H

#include "cclouds/common.h"
#include "cclouds/noise.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Limits checked by the settings validation (the *_check functions). */
#define CCL_TEXGEN_MIN_SIZE 4          /* smallest texture edge */
#define CCL_TEXGEN_MAX_SIZE_3D 512     /* largest 3-D edge: 512^3 RGBA float32 = 2 GiB */
#define CCL_TEXGEN_MAX_SIZE_2D 8192    /* largest 2-D edge */
#define CCL_TEXGEN_MAX_OCTAVES 8       /* Perlin fBm octaves */
#define CCL_TEXGEN_MAX_LATTICE 4096    /* highest lattice frequency: frequency * 2^(octaves - 1), worley_cells * 8 */

/* Settings of the base-shape texture (vc-A9, vc-A13 "BaseShapeSettings"; the thesis gives no default values).
 * Defaults (ccl_texgen_base_shape_settings_default), with the reasons:
 *   size 128              -- vc-A9 (128^3 RGBA).
 *   seed 0                -- Perlin's reference permutation for the Perlin part.
 *   perlin_octaves 3      -- Hillaire's TileableVolumeNoise (the EA code adopted by the thesis) uses 3 octaves.
 *   perlin_frequency 8    -- Hillaire's base Perlin frequency; the top octave (32 cells) keeps 4 texels per cell.
 *   worley_cells 4        -- Hillaire's cell count; layers 4, 8, 16, 32: the finest layer still has 4 texels/cell.
 *   worley_weights 0.625, 0.25, 0.125 -- the only fBm weights the thesis prints (eq 2.28); Hillaire's as well.
 *   combination CCL_PW_THESIS -- the thesis' chosen combination remap(P, 0, 1, W, 1)^2 (vc-A8).
 *   gamma 1               -- no default in the text; 1 leaves the generated noise unchanged (vc-4.6). */
typedef struct ccl_base_shape_settings {
    int32_t size;                        /* texture edge, power of two in [4, 512] */
    uint32_t seed;                       /* any uint32 */
    int32_t perlin_octaves;              /* >= 1, <= 8 */
    int32_t perlin_frequency;            /* Perlin lattice cells per texture, >= 1; freq * 2^(octaves-1) <= 4096 */
    int32_t worley_cells;                /* cells per texture of layer W0, >= 1; worley_cells * 8 <= 4096 */
    float worley_weights[3];             /* fBm weights of the sliding window: finite, >= 0, weights[0] > 0 */
    ccl_perlin_worley_mode combination;  /* combination for the R channel (vc-A8) */
    float gamma;                         /* vc-4.6 exponent 1/gamma: finite, > 0 */
} ccl_base_shape_settings;

/* Settings of the detail texture (vc-A10, vc-A13 "DetailShapeSettings": fBm weights, base frequency, gamma).
 * Defaults: size 32 (vc-A10); seed 0; worley_cells 2 (Hillaire's detail texture: layers 2, 4, 8, 16, the finest
 * still 2 texels per cell); worley_weights 0.625, 0.25, 0.125 (eq 2.30's weights, Hillaire's); gamma 1 (identity). */
typedef struct ccl_detail_shape_settings {
    int32_t size;            /* power of two in [4, 512] */
    uint32_t seed;
    int32_t worley_cells;    /* >= 1; worley_cells * 8 <= 4096 */
    float worley_weights[3]; /* finite, >= 0, weights[0] > 0 */
    float gamma;             /* finite, > 0 */
} ccl_detail_shape_settings;

/* Settings of the 2-D curl-noise texture (vc-A11; the thesis ships a file, we generate it).
 * Texel value: ccl_noise_curl2 = (dpsi/dy, -dpsi/dx) of the stream function psi = Perlin noise (2-D reading (i) of
 * vc-A7, divergence-free), at (u, v) * frequency with period = frequency, in noise-lattice units (|v| up to ~2.5).
 * Defaults: size 128 (not given; 128^2 x 2 floats, a 4-texel-per-cell sampling of 32 cells is far finer than the
 * 4-cell default); seed 0; frequency 4 (a few swirls per texture, like the usual shipped curl textures);
 * fd_step 1/256 lattice units (CCL_NOISE_FD_STEP_INV, the noise module's default). */
typedef struct ccl_curl_noise_settings {
    int32_t size;      /* power of two in [4, 8192] */
    uint32_t seed;
    int32_t frequency; /* Perlin lattice cells per texture, in [1, 4096] */
    float fd_step;     /* central-difference step in lattice units, in (0, 0.25] */
} ccl_curl_noise_settings;

/* Settings of the procedural weather map (vc-A12; the thesis ships a file, we generate it). Channels:
 * R = coverage, G = precipitation, B = cloud type, A = 0 (free; the thesis' conclusion reserves it for a future
 * cloud-base height). The spec's reading of the "blue twice" erratum (spec §7 item 13): precipitation is green.
 *   n  = ccl_noise_perlin_worley(P, W, combination) on the slice z = 0, with P = clamp(0.5 + perlin_contrast *
 *        fbm_perlin(seed), 0, 1) and W = ccl_noise_fbm_worley3(inverse, worley_octaves, worley_cells, seed);
 *   R  = shape(n, coverage), shape(n, c) = clamp((n - (1 - c)) / c, 0, 1) for c > 0, 0 for c = 0 (a global coverage
 *        remap(n, 1 - c, 1, 0, 1): c = 0 clear sky, c = 1 the raw noise; non-decreasing in c);
 *   G  = shape(P2, precipitation), P2 = P of the permutation of seed + 1;
 *   B  = clamp(cloud_type + cloud_type_variation (2 P3 - 1), 0, 1), P3 = P of the permutation of seed + 2.
 * Defaults, with the reasons: size 512 (not given; 512^2 RGBA float32 = 4 MiB, finer than any cloud at the usual
 * projection scales); seed 0; perlin_frequency 4 and perlin_octaves 4 (a few cloud systems per map with ragged
 * edges); perlin_contrast 2 (4-octave Perlin fBm has a standard deviation of about 0.15 and |fbm| < 0.45: a gain of
 * 2 spreads it over about [0.1, 0.9]; measured on the default map, the fraction of texels with R > 0 is 0.24 / 0.61 /
 * 0.91 at coverage 0.25 / 0.5 / 0.75, i.e. coverage reads as "fraction of the sky covered"; with the plain
 * 0.5 fbm + 0.5 mapping it is 0.08 / 0.66 / 0.98); worley_cells 4, worley_octaves 3 (cells of the same scale as
 * the Perlin blobs: clustered cumulus);
 * combination CCL_PW_THESIS (the combination the thesis chose for its cloud noise); coverage 0.5 (half of the noise
 * range above the threshold); precipitation 0.2 (mostly dry clouds: the thesis' scenes are fair-weather cumulus);
 * cloud_type 0.75 and cloud_type_variation 0.25 (types between stratocumulus 0.5 and cumulus 1, the low clouds the
 * cloud layer models, §2.3.1). */
typedef struct ccl_weather_map_settings {
    int32_t size;                 /* power of two in [4, 8192] (square map) */
    uint32_t seed;
    int32_t perlin_frequency;     /* >= 1; perlin_frequency * 2^(perlin_octaves-1) <= 4096 */
    int32_t perlin_octaves;       /* in [1, 8] */
    float perlin_contrast;        /* gain of the Perlin fBm before clamping to [0, 1]: finite, > 0 */
    int32_t worley_cells;         /* >= 1; worley_cells * 2^(worley_octaves-1) <= 4096 */
    int32_t worley_octaves;       /* in [1, 8] */
    ccl_perlin_worley_mode combination;
    float coverage;               /* [0, 1] */
    float precipitation;          /* [0, 1] */
    float cloud_type;             /* [0, 1]: 0 stratus, 0.5 stratocumulus, 1 cumulus */
    float cloud_type_variation;   /* [0, 1] */
} ccl_weather_map_settings;

/* ---- gamma correction (vc-4.6) ---------------------------------------------------------------------------------- */

/* Gamma correction of generated noise C = C^(1/gamma). Ref: vc-4.6 (§4.3.1). c -> C, a texture value in [0, 1];
 * gamma -> gamma > 0 (gamma > 1 brightens, < 1 darkens, 1 is the identity). Output [0, 1]. NaN propagates.
 * Evaluated as powf(c, 1.0f / gamma). */
CCL_API float ccl_texgen_gamma(float c, float gamma);

/* ---- settings (vc-A13) ------------------------------------------------------------------------------------------- */

/* Documented defaults (see the struct comments for the reasons). Ref: vc-A13. */
CCL_API ccl_base_shape_settings ccl_texgen_base_shape_settings_default(void);
CCL_API ccl_detail_shape_settings ccl_texgen_detail_shape_settings_default(void);
CCL_API ccl_curl_noise_settings ccl_texgen_curl_noise_settings_default(void);
CCL_API ccl_weather_map_settings ccl_texgen_weather_map_settings_default(void);

/* Validate settings: CCL_OK, or CCL_EINVAL with *out_field = the name of the first invalid field (the C struct field
 * name, e.g. "size", "worley_weights", "gamma"); *out_field = NULL when valid. s == NULL gives CCL_EINVAL and "s".
 * out_field may be NULL. Ref: vc-A13. */
CCL_API ccl_status ccl_texgen_base_shape_settings_check(const ccl_base_shape_settings *s, const char **out_field);
CCL_API ccl_status ccl_texgen_detail_shape_settings_check(const ccl_detail_shape_settings *s, const char **out_field);
CCL_API ccl_status ccl_texgen_curl_noise_settings_check(const ccl_curl_noise_settings *s, const char **out_field);
CCL_API ccl_status ccl_texgen_weather_map_settings_check(const ccl_weather_map_settings *s, const char **out_field);

/* ---- single texels (element-wise forms) -------------------------------------------------------------------------- */

/* One texel (ix, iy, iz) of the base-shape texture (vc-A9, vc-A8, vc-4.6); the arguments are the fields of
 * ccl_base_shape_settings (see there and the header comment). Integer coordinates may be any int32 (the texture is
 * periodic: i is reduced modulo size first, so texel i + k size equals texel i bit for bit for every frequency). Rebuilds the permutation table of `seed` on each call (~1 us): the whole-texture function builds it once.
 * Writes R, G, B, A in [0, 1]. Domain: as ccl_texgen_base_shape_settings_check (asserted in debug builds). */
CCL_API void ccl_texgen_base_shape_texel(int32_t ix, int32_t iy, int32_t iz, int32_t size, uint32_t seed,
                                         int32_t perlin_octaves, int32_t perlin_frequency, int32_t worley_cells,
                                         float worley_w0, float worley_w1, float worley_w2, float gamma,
                                         ccl_perlin_worley_mode combination, float *out_r, float *out_g,
                                         float *out_b, float *out_a);

/* One texel of the detail texture (vc-A10, vc-4.6): R, G, B in [0, 1]. Arguments: the ccl_detail_shape_settings
 * fields. */
CCL_API void ccl_texgen_detail_shape_texel(int32_t ix, int32_t iy, int32_t iz, int32_t size, uint32_t seed,
                                           int32_t worley_cells, float worley_w0, float worley_w1, float worley_w2,
                                           float gamma, float *out_r, float *out_g, float *out_b);

/* ---- whole textures ---------------------------------------------------------------------------------------------- */

/* Base-shape texture, size^3 RGBA (vc-A9). out_rgba: out_len == size^3 * 4 floats. Single thread.
 * Returns CCL_EINVAL for invalid settings, a NULL pointer or a wrong out_len (nothing written). */
CCL_API ccl_status ccl_texgen_base_shape(const ccl_base_shape_settings *s, float *out_rgba, size_t out_len);

/* Detail texture, size^3 RGB (vc-A10). out_len == size^3 * 3. */
CCL_API ccl_status ccl_texgen_detail_shape(const ccl_detail_shape_settings *s, float *out_rgb, size_t out_len);

/* Curl-noise texture, size^2 x 2 (vc-A11): (vx, vy) per texel, layout [iy][ix][c]. out_len == size^2 * 2. */
CCL_API ccl_status ccl_texgen_curl_noise(const ccl_curl_noise_settings *s, float *out_xy, size_t out_len);

/* Weather map, size^2 RGBA (vc-A12): layout [iy][ix][c]. out_len == size^2 * 4. */
CCL_API ccl_status ccl_texgen_weather_map(const ccl_weather_map_settings *s, float *out_rgba, size_t out_len);

/* ---- sampling -------------------------------------------------------------------------------------------------- */

/* Trilinear sample of a periodic RGBA volume, the renderer's hand-written replacement of a GL_REPEAT + GL_LINEAR 3-D
 * texture (used on the textures above). tex: (size_mask + 1)^3 RGBA floats in the layout above; size_mask = size - 1
 * with size a power of two (indices wrap with & size_mask); (px, py, pz): texture coordinates, 1 = one texture period,
 * texel centres at (i + 0.5) / size. Shift-invariant bit for bit: sampling p and p + 1 (both exact) gives the same
 * result. Weights depend only on frac(p * size), computed exactly. Domain |p * size| < 2^23 on every axis; outside it (or
 * for a NaN coordinate) R, G, B, A are NaN. Writes R, G, B, A. */
CCL_API void ccl_texgen_sample_trilinear_wrap(const float *tex, int32_t size_mask, float px, float py, float pz,
                                              float *out_r, float *out_g, float *out_b, float *out_a);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_TEXGEN_H */
