/*
 * cclouds/raymarch.h -- view-ray geometry of the cloudscape (vc §2.2, §4.2.1, §4.3.2): ray-sphere / ray-box
 * intersection, the cloud-layer segment, view-sample count, light-cone sample positions,
 * front-to-back accumulation with early termination, ray jitter, and the constants collected from the thesis.
 *
 * Conventions (all functions):
 *   - World frame: y is up. Lengths in kilometres (any unit works for the pure geometry; the documented defaults are
 *     km). The default planet has its centre at (0, -earth_radius, 0), so the ground under the origin is at y = 0 and
 *     a camera near the origin keeps float32 coordinates small.
 *   - Ray o + t d with |d| = 1 where a function says "unit d"; t is the distance along the ray. "No hit / no segment"
 *     is reported by a 0 return value AND by NaN in both distances, so `t_end > t_start` is false for a miss.
 *   - The camera and primary rays (vc-A25) are in cclouds/camera.h; the PCG hash of the jitter in cclouds/hash.h.
 *   - float32 throughout; every operation is mirrored in the same order by pywarp/kernels/raymarch.py.
 *   - Vectors in and out by value (ccl_vec3); several results: the first is the return value, the others go
 *     through trailing out-pointers.
 */
#ifndef CCLOUDS_RAYMARCH_H
#define CCLOUDS_RAYMARCH_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The three concentric spheres of vc-A14: the Earth and the inner (base) and outer (top) spheres of the cloud layer.
 * Radii in km, centre = (0, -r_earth, 0). */
typedef struct {
    ccl_vec3 centre;
    float r_earth;
    float r_inner;
    float r_outer;
} ccl_cloud_layer;

/* Constants collected from the thesis (vc-A36), read-only. Field names follow the spec table of vc-A36. */
typedef struct {
    int base_texture_size;             /* 128 (128^3 RGBA), §2.3.3 */
    int base_texture_channels;         /* 4 (RGBA) */
    int detail_texture_size;           /* 32 (32^3 RGB) */
    int detail_texture_channels;       /* 3 (RGB) */
    float low_freq_fbm_weights[3];     /* 0.625, 0.25, 0.125 (G, B, A of the base texture), 2.28 */
    float high_freq_fbm_weights[3];    /* 0.625, 0.25, 0.125 (R, G, B of the detail texture), 2.30 */
    float detail_erosion;              /* 0.2, 2.30 */
    float powder_factor;               /* 2, 2.31 */
    float schlick_fit[2];              /* 1.55, 0.55: k = 1.55 g - 0.55 g^3, 2.16 */
    float cloud_types[3];              /* 0 stratus, 0.5 stratocumulus, 1 cumulus, §2.3.3 */
    float gradient_cumulus[4];         /* 0.01, 0.30, 0.6, 0.95 (break points of 4.7) */
    float gradient_stratocumulus[4];   /* 0.01, 0.25, 0.3, 0.65 */
    float gradient_stratus[4];         /* 0.01, 0.05, 0.0, 0.20 */
    int view_samples_zenith;           /* 64, §4.3.2 */
    int view_samples_horizon;          /* 128 */
    int light_samples;                 /* 6, §2.3.4 */
    int light_samples_near;            /* 5 (+ 1 far) */
    float light_far_factor;            /* 3: the far light sample at ~3x the distance */
    int reprojection_block;            /* 4 (4 x 4 pixel blocks), §4.4 */
    int reprojection_cycle;            /* 16 frames */
    float tone_map_constant;           /* 0.03 (printed with a sign error, vc-4.5) */
    float cie_clear_sky_bcde[4];       /* B = -0.32, C = 10, D = -3, E = 0.45, §2.5.1 */
    float low_cloud_top_km;            /* 2: low clouds up to 2 km, §2.3.1 */
    float middle_cloud_base_km;        /* 2 */
    float middle_cloud_top_km;         /* 6 */
    float high_cloud_base_km;          /* 6 */
    float rayleigh_blue_nm;            /* 400 */
    float rayleigh_blue_vs_red;        /* 10 ("about ten times more", §2.5) */
    float rayleigh_red_nm;             /* 700 */
} ccl_vc_constant_table;

/* Ambiguity choices (mirrored as named constants in pywarp/kernels/raymarch.py):
 *   earth radius 6371 km        IUGG mean Earth radius R1 (6371.0088 km) rounded; the thesis gives no value (vc-A14).
 *   layer base 1.5 km, top 4 km the thesis's layer is for low clouds (tops <= 2 km, §2.3.1); a base at 1.5 km (a
 *                               typical low-cloud condensation level) and a top at 4 km leave room for cumulus towers
 *                               that grow through the 2 km low-cloud limit; 2.5 km thickness, float32 exact radii.
 *   view samples                N = round(mix(128, 64, |dir.y|)) = floor(128 + (64 - 128) |dir.y| + 0.5): 128 at the
 *                               horizon, 64 at zenith (and nadir); linear in |dir.y| (vc-A18 leaves the law open).
 *   light cone                  step 0.1 km (5 near samples span 0.5 km, a cumulus core; the far one at 1.5 km catches
 *                               a neighbouring cloud within the 2.5 km layer), half-angle 15 deg (0.2617994 rad:
 *                               sideways spread ~1.3 steps at the cone end), far factor 3 (the thesis), kernel
 *                               ccl_raymarch_light_cone_kernel.
 *   early termination           eps = 1/256: stop once 1 - T >= 1 - eps; what the remaining samples could still add is
 *                               below T <= 1/256 of the light, under one 8-bit step for radiance <= 1.
 *   jitter                      tilt (the thesis's reading, default) by up to amount * sqrt(3) rad, amount = 0.002 rad
 *                               (about 2 pixel footprints of a 60 deg / 1080-row view); the start-offset jitter is an
 *                               option. Seeded by (pixel x, pixel y, frame) through the PCG hash (Jarzynski & Olano,
 *                               JCGT 9(3), 2020).
 */

/* Largest coordinate (per component of the origin and the centre) and radius of ccl_raymarch_ray_sphere and
 * ccl_raymarch_layer_segment, in their length unit: |o - c| and the radii below ~3.5e15, so their squares (~1e31)
 * and the products of the closed form stay finite (an origin 1e19 away overflowed |o - c|^2 - r^2 to inf and the
 * layer segment ended at t = inf). 10^15 km is a hundred light years; the cloudscape works within 10^5 km. */
#define CCL_RAYMARCH_MAX_DISTANCE 1.0e15f

/* Ray-sphere intersection.
 * Ref: vc-A14 (cataloguer's closed form; numerically robust form after Haines et al., "Precision Improvements for
 * Ray/Sphere Intersection", Ray Tracing Gems, 2019). o -> ray origin, d -> unit direction, c -> sphere centre,
 * r -> radius (> 0); the components of o and c and r within CCL_RAYMARCH_MAX_DISTANCE. b = d.(o - c), l = (o - c) - b d, disc = r^2 - |l|^2 = (r - |l|)(r + |l|),
 * q = -b - sign(b) sqrt(disc), roots {cq/q, q} with cq = |o - c|^2 - r^2 = (|o - c| - r)(|o - c| + r).
 * Output: *out_t0 <= *out_t1 (may be negative: behind the origin), returns 1; on a miss both NaN, returns 0.
 * A tangent ray gives t0 == t1. NaN input propagates (returns 0). */
CCL_API int ccl_raymarch_ray_sphere(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r, float *out_t0, float *out_t1);

/* Ray-box (axis-aligned) intersection by slabs. Ref: vc-A35 (the bounding body of §2.2).
 * o -> origin, d -> direction (any non-zero length; t in units of |d|), bmin <= bmax -> box corners. Axes with
 * d == 0 accept the ray only when the origin lies between the slab planes. Output t0 <= t1 (either may be negative),
 * returns 1; miss: NaN, NaN, returns 0. */
CCL_API int ccl_raymarch_ray_box(ccl_vec3 o, ccl_vec3 d, ccl_vec3 bmin, ccl_vec3 bmax, float *out_t0,
                                 float *out_t1);

/* The part of the cloud layer a view ray marches through, for every camera position.
 * Ref: vc-A14 (camera below the layer), vc-A24 (inside, above). o -> camera position, d -> unit view direction,
 * c -> common centre, r_earth <= r_inner < r_outer -> radii (the components of o and c and the radii within
 * CCL_RAYMARCH_MAX_DISTANCE, see ccl_raymarch_ray_sphere: the segment is then finite). With rho = |o - c|:
 *   below  (rho < r_inner): no segment if the ray enters the Earth ahead (Earth far root > 0: below the horizon, also
 *          always for an underground camera); else [far root of inner, far root of outer].
 *   inside (r_inner <= rho <= r_outer): [0, first exit]: the inner sphere's near root if > 0, else the outer far root.
 *   above  (rho > r_outer): no segment unless the outer sphere is ahead; [outer near root, inner near root if the ray
 *          hits the inner sphere ahead (the Earth lies inside it), else outer far root].
 * Output 0 <= *out_t_start <= *out_t_end, returns 1; no segment: NaN, NaN, returns 0.
 * Accuracy: |o - c| and the radii are float32 numbers near 6371 km (spacing 4.9e-4 km); a root moves by about
 * eps R^2 / sqrt(disc), sub-metre for most rays and metres for grazing ones (tested: <= 4 eps (R^2 / s + R)). */
CCL_API int ccl_raymarch_layer_segment(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r_earth, float r_inner,
                                       float r_outer, float *out_t_start, float *out_t_end);

/* Default cloud layer: Earth radius 6371 km, base 1.5 km and top 4 km above the ground (see the choices above). */
CCL_API void ccl_raymarch_cloud_layer_default(ccl_cloud_layer *out);

/* Cloud layer from an Earth radius and the base/top altitudes above the ground (km); centre (0, -earth_radius, 0).
 * Returns CCL_EINVAL (out untouched) unless 0 < earth_radius, 0 <= base_altitude < top_altitude, all finite. */
CCL_API ccl_status ccl_raymarch_cloud_layer_init(float earth_radius, float base_altitude, float top_altitude,
                                                 ccl_cloud_layer *out);

/* Largest n_max of ccl_raymarch_view_sample_count: 2^16, far above the renderer's 4096 and far below 2^22, up to
 * which n + 0.5 is exact in float32 (so the rounding never leaves [n_min, n_max]). */
#define CCL_RAYMARCH_MAX_VIEW_SAMPLES 65536

/* Number of view samples N = round(mix(n_max, n_min, |dir_y|)) = floor(n_max + (n_min - n_max) |dir_y| + 0.5).
 * Ref: vc-A18 (64 at zenith ... 128 at the horizon; the law is our choice). dir_y -> y component of the unit view
 * direction in [-1, 1]; 1 <= n_min <= n_max <= CCL_RAYMARCH_MAX_VIEW_SAMPLES (thesis: 64, 128). Output in
 * [n_min, n_max]; n_max at the horizon. */
CCL_API int ccl_raymarch_view_sample_count(float dir_y, int n_min, int n_max);

/* Default light-cone kernel vector i (0..5): six fixed pseudo-random unit vectors (uniform on the sphere, drawn with
 * the PCG hash of 2i and 2i + 1; see pywarp/kernels/raymarch.py LIGHT_CONE_KERNEL for the derivation).
 * Ref: vc-A19. i outside 0..5 is wrapped mod 6. */
CCL_API ccl_vec3 ccl_raymarch_light_cone_kernel(int i);

/* Position of light sample i (0..5) in a cone from p towards the sun.
 * Ref: vc-A19 (Schneider & Vos 2015; GPU Pro 7, "Real-time volumetric cloudscapes", 2016). p -> view sample,
 * to_sun -> unit direction towards the sun, step -> axial step (km, > 0), cone_angle -> half-angle (rad, [0, pi/2)),
 * far_factor -> the far sample's distance relative to the near cone's length, k -> kernel vector (unit).
 * Axial distance s_i = (i + 1) step for the 5 near samples (i < 5), s_5 = far_factor * 5 step;
 * position = p + s_i to_sun + (s_i tan(cone_angle)) k: the sideways offset grows with s_i (increasing offsets).
 * Output: world position. */
CCL_API ccl_vec3 ccl_raymarch_light_sample_position(ccl_vec3 p, ccl_vec3 to_sun, int i, float step,
                                                    float cone_angle, float far_factor, ccl_vec3 k);

/* One front-to-back accumulation step. Ref: vc-A21 (cataloguer's standard form), vc-2.18.
 * colour -> radiance accumulated so far, transmittance -> view transmittance T so far ([0, 1]), sigma -> extinction
 * per unit density (1/km, >= 0), rho -> density (>= 0), dt -> step length (km, >= 0), light -> radiance of the
 * sample, eps -> termination threshold ([0, 1], default 1/256, see above).
 * tau = (sigma rho) dt, e = exp(-tau); returns colour + (T (1 - e)) light; *out_transmittance = T e;
 * *out_stop = 1 when the march may stop (1 - T e >= 1 - eps), else 0. */
CCL_API ccl_vec3 ccl_raymarch_accumulate(ccl_vec3 colour, float transmittance, float sigma, float rho, float dt,
                                         ccl_vec3 light, float eps, float *out_transmittance, int *out_stop);

/* Jitter modes of ccl_raymarch_jitter (vc-A23). */
typedef enum {
    CCL_JITTER_TILT = 0,    /* tilt the direction (the thesis, default) */
    CCL_JITTER_OFFSET = 1,  /* keep the direction, jitter the start offset of the first sample */
    CCL_JITTER_NONE = 2     /* neither: direction unchanged, offset 0.5 (sample at segment midpoints) */
} ccl_jitter_mode;

/* Direction tilted by a pseudo-random amount: normalize(d + amount * r), r in [-1, 1)^3 from the PCG hash of
 * (x, y, frame): seed = pcg(x + pcg(y + pcg(frame))), r_k = 2 ccl_hash_unit(pcg(seed + k)) - 1, k = 0, 1, 2.
 * Ref: vc-A23. d -> unit direction, amount -> tilt scale (rad, >= 0; the tilt angle is at most about
 * sqrt(3) amount). Deterministic: the same (x, y, frame) gives the same direction. */
CCL_API ccl_vec3 ccl_raymarch_jitter_tilt(ccl_vec3 d, uint32_t x, uint32_t y, uint32_t frame, float amount);

/* Pseudo-random start offset in [0, 1) (in units of the step, see ccl_raymarch_point) from the PCG hash of
 * (x, y, frame): ccl_hash_unit(pcg(seed + 3)) with the seed of ccl_raymarch_jitter_tilt. Ref: vc-A23 (the
 * alternative to tilting). */
CCL_API float ccl_raymarch_jitter_offset(uint32_t x, uint32_t y, uint32_t frame);

/* The jitter of pixel (x, y) in frame `frame` for a jitter mode: CCL_JITTER_TILT -> ccl_raymarch_jitter_tilt(d, ...),
 * offset 0.5; CCL_JITTER_OFFSET -> d unchanged, offset ccl_raymarch_jitter_offset(x, y, frame); CCL_JITTER_NONE ->
 * d unchanged, offset 0.5. Ref: vc-A23. d -> unit view direction, amount -> tilt scale (rad, >= 0).
 * Returns the direction to march; *out_offset = the start offset in [0, 1). */
CCL_API ccl_vec3 ccl_raymarch_jitter(ccl_vec3 d, uint32_t x, uint32_t y, uint32_t frame, float amount,
                                     ccl_jitter_mode mode, float *out_offset);

/* Uniform march over an intersection interval: clamps the interval to the part in front of the origin,
 * t_start = max(t_near, 0), dt = (t_far - t_start) / n. Ref: vc-A35, vc-2.18 (S = n uniform steps).
 * Returns 0 (NaN, NaN) when the interval is empty, lies behind the origin or is NaN; n >= 1. */
CCL_API int ccl_raymarch_interval(float t_near, float t_far, int n, float *out_t_start, float *out_dt);

/* Sample i of a uniform march: o + (t_start + (i + offset) dt) d; offset in [0, 1) (0.5 = segment midpoints).
 * Ref: vc-A35, vc-2.18 (x_t = x + t dt w). */
CCL_API ccl_vec3 ccl_raymarch_point(ccl_vec3 o, ccl_vec3 d, float t_start, float dt, int i, float offset);

/* n uniform steps through a bounding sphere (centre c, radius r > 0) in front of the origin: d any non-zero length
 * (normalized here), [t_near, t_far] from ccl_raymarch_ray_sphere -> ccl_raymarch_interval -> out_points[i] =
 * ccl_raymarch_point(o, d, t_start, dt, i, offset) for i = 0..n-1 (out_points holds n vectors). Ref: vc-A35.
 * Returns 1; on a miss 0 with every point and *out_dt NaN. */
CCL_API int ccl_raymarch_sphere(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r, int n, float offset,
                                ccl_vec3 *out_points, float *out_dt);

/* ccl_raymarch_sphere for an axis-aligned box (bmin <= bmax), intersected by ccl_raymarch_ray_box. Ref: vc-A35. */
CCL_API int ccl_raymarch_box(ccl_vec3 o, ccl_vec3 d, ccl_vec3 bmin, ccl_vec3 bmax, int n, float offset,
                             ccl_vec3 *out_points, float *out_dt);

/* The constants collected from the thesis (vc-A36); never NULL, static storage, read-only. */
CCL_API const ccl_vc_constant_table *ccl_raymarch_vc_constants(void);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_RAYMARCH_H */
