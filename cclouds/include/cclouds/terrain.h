/*
 * cclouds/terrain.h -- the ray-marched procedural terrain demo of the pt text (Drevicky 2016, chapters 6-9):
 * pixel transform (Kod 7.1), fixed-step and dynamic-step marching of a heightmap (Kod 7.4, 7.5) and the proposed
 * bisection refinement (ch. 9), hard and soft shadows (Kod 7.6, 7.7), Lambert + ambient light (eq 7.1), normals by
 * central differences (eq 7.2, Kod 7.8), the fBm heightmap (Kod 7.9) with a distance-dependent octave count (7.3),
 * exponential fog (eq 7.3), sky with a sun glow (Kod 7.10), 2-D fBm clouds moving with the wind (Kod 7.11), water
 * with a Fresnel-like weight (eq 7.4, 7.3.4), materials (Obrazok 7.10) and supersampling (7.1.6).
 *
 * Conventions:
 *   - World frame y up, arbitrary length unit ("units"); the demo's GLSL works in display RGB (no gamma): colours
 *     here are display values in [0, 1] (the shading may exceed 1; the pixel function clamps).
 *   - A heightmap is h(x, z); the marching distance ("map" of Kod 7.5) is the vertical gap y - h(x, z).
 *     CCL_TERRAIN_TEST is the text's test heightmap 10 sin(0.1 x) sin(0.1 z) (Kod 7.4); CCL_TERRAIN_FBM is
 *     height_scale * fbm(x / horizontal_scale, z / horizontal_scale, octaves) with the fBm of Kod 7.9.
 *   - The element-wise functions take the heightmap as (octaves, height_scale, horizontal_scale, seed, heightmap);
 *     for CCL_TERRAIN_TEST the first four are ignored. They build the Perlin table of `seed` on each call (~1 us);
 *     the scene-level functions (ccl_terrain_shade, ccl_terrain_pixel) use the table held in ccl_terrain_params.
 *   - The noise of the fBm (undefined in the text) is the 2-D Perlin noise of noise.h, ccl_noise_perlin2_perm with
 *     period 0 and the quintic fade: the z = 0 slice of Perlin's 2002 improved noise, |noise| <= 1 (a corner's
 *     gradient is a cube-edge vector of length sqrt(2), its 2-D part at most (1, 1); measured range on 10^6 samples
 *     about [-0.99, 0.99]), 0 at lattice points, repeating every 256 lattice units.
 *   - Every loop is bounded by an argument: max_steps, bisect_steps, or max_t / step_size (<= 10^6 by the domains).
 *   - pywarp/kernels/terrain.py mirrors every operation (float32, same order).
 */
#ifndef CCLOUDS_TERRAIN_H
#define CCLOUDS_TERRAIN_H

#include "cclouds/common.h"
#include "cclouds/noise.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Heightmaps. */
typedef enum ccl_terrain_heightmap {
    CCL_TERRAIN_TEST = 0, /* 10 sin(0.1 x) sin(0.1 z), the text's test heightmap (Kod 7.4, 7.5, Tabulka 7.1) */
    CCL_TERRAIN_FBM = 1   /* height_scale * fbm(x / horizontal_scale, z / horizontal_scale, octaves) (Kod 7.9) */
} ccl_terrain_heightmap;

/* Marching methods of the scene. */
typedef enum ccl_terrain_march_method {
    CCL_TERRAIN_MARCH_FIXED = 0,   /* Kod 7.4 */
    CCL_TERRAIN_MARCH_DYNAMIC = 1, /* Kod 7.5 (with the step scale of 7.1.3) */
    CCL_TERRAIN_MARCH_BISECT = 2   /* the refinement proposed in ch. 9 */
} ccl_terrain_march_method;

/* Shadow kinds of the scene. */
typedef enum ccl_terrain_shadow_kind {
    CCL_TERRAIN_SHADOWS_NONE = 0,
    CCL_TERRAIN_SHADOWS_HARD = 1, /* Kod 7.6 */
    CCL_TERRAIN_SHADOWS_SOFT = 2  /* Kod 7.7 */
} ccl_terrain_shadow_kind;

/* Build-up stages of Obrazok 7.10. */
typedef enum ccl_terrain_stage {
    CCL_TERRAIN_STAGE_HEIGHTMAP = 0,  /* (a) one material colour, lit */
    CCL_TERRAIN_STAGE_MATERIALS = 1,  /* (b) + colour gradient by height */
    CCL_TERRAIN_STAGE_ATMOSPHERE = 2, /* (c) + grass where the normal points up, clouds, fog */
    CCL_TERRAIN_STAGE_FINAL = 3       /* (d) + water */
} ccl_terrain_stage;

/* Smallest noise scale (units per noise unit) of horizontal_scale, cloud_scale and wave_scale: 1/64 (exact in
 * float32, like the smallest step_size), far below any use (defaults 24, 150, 2: finer noise only aliases) and large
 * enough that position / scale stays finite for every position the march reaches (1.02e-38 made x / horizontal_scale
 * Inf and the shade NaN). */
#define CCL_TERRAIN_MIN_SCALE 0.015625f

/* Upper bound of the iterations of the fixed-step march: max_t / step_size <= 10000 * 64 < 10^6. */
#define CCL_TERRAIN_MAX_FIXED_STEPS 1000000

/* Every parameter of a terrain frame (pywarp.terrain.settings declares each with its unit, default and reason).
 * Fill with ccl_terrain_params_default, change fields, then ccl_terrain_params_check (which also fills `perm`). */
typedef struct ccl_terrain_params {
    /* heightmap */
    int32_t heightmap;         /* ccl_terrain_heightmap */
    uint32_t seed;             /* Perlin permutation seed of the fBm (0: Perlin's table) */
    int32_t march_octaves;     /* fBm octaves of the march and the shadows, [1, 16] */
    float height_scale;        /* units, [0, 1000] */
    float horizontal_scale;    /* units per fBm unit, [1/64, 10000] */
    /* marching */
    int32_t march_method;      /* ccl_terrain_march_method */
    float max_t;               /* MAX_T, (0, 10000] */
    float step_size;           /* STEP_SIZE of the fixed march, [1/64, 100] */
    float precision;           /* PRECISION, (0, 10] */
    int32_t max_steps;         /* MAX_STEPS, [1, 100000] */
    float step_scale;          /* factor on the dynamic step, (0, 1] (1: Kod 7.5, 0.5: "halve the step") */
    float bisect_threshold;    /* step below which the bisection starts, (0, 100] (ch. 9) */
    int32_t bisect_steps;      /* bisection iterations, [0, 64] */
    int32_t slab;              /* 1: the view and shadow rays are clipped to the slab y <= bound + precision that holds
                                * the terrain (bound: 10 for the test map, height_scale 2 (1 - 0.5^march_octaves) for
                                * the fBm, |noise| <= 1); exact (the same hits and shadows), 0: the printed loops */
    float precision_per_unit;  /* dynamic march: hit when d < precision + precision_per_unit t, [0, 1] (0: Kod 7.5) */
    /* normals */
    float normal_h;            /* central-difference step h, (0, 1] (Kod 7.8: 0.002) */
    int32_t normal_octaves_max;/* octaves of the normal near the camera, [1, 16] */
    int32_t normal_octaves_min;/* octaves far away, [1, normal_octaves_max] */
    float lod_distance;        /* distance up to which the normal has all its octaves, (0, 10000] */
    /* shadows and light */
    int32_t shadows;           /* ccl_terrain_shadow_kind */
    float shadow_t0_hard;      /* start offset of the hard shadow ray (Kod 7.6: 0.2), [0, 100] */
    float shadow_t0_soft;      /* start offset of the soft shadow ray (Kod 7.7: 0.02), (0, 100] */
    float shadow_k;            /* softness factor k (Kod 7.7: 4), (0, 1000] */
    float shadow_max_t;        /* MAX_T of the shadow rays, (0, 10000] */
    float shadow_bias;         /* lift of the shadow ray's origin above the terrain, [0, 10] */
    float shadow_min_step;     /* smallest step of the shadow rays, [0, 100]; 0: Kod 7.6/7.7's t += d as printed */
    ccl_vec3 sun;              /* unit direction towards the sun (light vector l of eq 7.1) */
    float light_ambient;       /* L_a, [0, 100] */
    float light_diffuse;       /* L_d, [0, 100] */
    /* materials (display RGB) */
    int32_t stage;             /* ccl_terrain_stage */
    ccl_vec3 colour_rock;      /* stage (a) colour and the high end of the height gradient */
    ccl_vec3 colour_low;       /* low end of the height gradient (sand, dirt) */
    ccl_vec3 colour_grass;     /* grass, where the normal points up */
    float material_low;        /* height where the gradient starts (colour_low below) */
    float material_high;       /* height where it ends (colour_rock above), > material_low */
    float grass_min_normal_y;  /* grass where n.y exceeds this, [0, 1] */
    float grass_band;          /* width of the grass transition in n.y, (0, 1] */
    /* atmosphere */
    int32_t fog_variant;       /* ccl_variant of eq 7.3 (CCL_VARIANT_THESIS: min(e^(rho d) - 1, 1)) */
    float fog_density;         /* rho, (0, 100] per unit */
    ccl_vec3 sky_colour;       /* skyColor of Kod 7.10 */
    ccl_vec3 sun_colour;       /* sunColor of Kod 7.10 */
    float sun_power;           /* exponent of the sun glow (Kod 7.10: 80), (0, 10000] */
    int32_t cloud_variant;     /* ccl_variant of Kod 7.11 (CCL_VARIANT_CORRECTED: no clouds below the horizon) */
    float cloud_height;        /* cloudHeight, units */
    float cloud_scale;         /* units per fBm unit of the cloud noise, [1/64, 1e6] */
    ccl_vec2 wind;             /* windSpeed (x, z), units per second */
    float time;                /* seconds, [0, 1e6] */
    ccl_vec3 cloud_colour;     /* cloudColor of Kod 7.11 */
    /* water */
    float water_level;         /* y of the water plane */
    float water_kappa;         /* kappa of eq 7.4, (0, 100] */
    float wave_scale;          /* units per noise unit of the wave normal, [1/64, 1e4] */
    float wave_strength;       /* slope amplitude of the waves, [0, 10] */
    ccl_vec3 water_tint;       /* factor on the underwater colour ((1, 1, 1): the text's plain blend) */
    /* image */
    int32_t samples_per_axis;  /* m: m x m regular sub-samples per pixel (7.1.6: 1, 4, 16 rays), [1, 8] */
    uint8_t perm[512];         /* Perlin table of `seed`, filled by ccl_terrain_params_check */
} ccl_terrain_params;

/* Defaults of the demo scene (every value and its reason: pywarp/terrain/settings.py, pinned by a test). */
CCL_API void ccl_terrain_params_default(ccl_terrain_params *out);

/* Check every field against its domain (NaN refused) and fill p->perm from p->seed. Returns CCL_OK, or CCL_EINVAL
 * with *out_field (when not NULL) naming the first invalid field. */
CCL_API ccl_status ccl_terrain_params_check(ccl_terrain_params *p, const char **out_field);

/* Pixel coordinate transform of the demo. Ref: pt-code-7.1. frag_x, frag_y -> gl_FragCoord.xy (pixel centre,
 * origin bottom-left, px), width, height -> iResolution (px, >= 1). p = (frag / res) * 2 - 1, then p.x *= width /
 * height: y in (-1, 1), x in (-aspect, aspect) for frag inside the window. */
CCL_API ccl_vec2 ccl_terrain_pixel_position(float frag_x, float frag_y, float width, float height);


/* Terrain height h(x, z) (units) of `heightmap` (ccl_terrain_heightmap); see the conventions. perm: 512-entry table
 * (ignored by CCL_TERRAIN_TEST). The map of Kod 7.4. */
CCL_API float ccl_terrain_height_perm(float x, float z, int32_t octaves, float height_scale, float horizontal_scale,
                                      const uint8_t *perm, int32_t heightmap);

/* Naive fixed-step ray march. Ref: pt-code-7.4: for (t = 0; t < max_t; t += step_size) hit when p.y - precision <
 * h(p.xz), p = ro + rd t. ro: ray origin; rd: unit direction; max_t in (0, 10000]; step_size in [1/64, 100];
 * precision in (0, 10]; heightmap as in the conventions. Returns hit (1/0); *out_t = t at the hit (max_t or beyond on
 * a miss); *out_steps = heights evaluated (<= CCL_TERRAIN_MAX_FIXED_STEPS). */
CCL_API int32_t ccl_terrain_march_fixed(ccl_vec3 ro, ccl_vec3 rd, float max_t, float step_size, float precision,
                                        int32_t octaves, float height_scale, float horizontal_scale, uint32_t seed,
                                        int32_t heightmap, float *out_t, int *out_steps);

/* Ray march with the dynamic step. Ref: pt-code-7.5 (map uses point.x, point.z: the printed p.x, p.z is a typo):
 * d = p.y - h(p.xz), t += step_scale d; hit when d < precision, miss when t > max_t or after max_steps.
 * step_scale in (0, 1]: 1 = as printed, 0.5 = the "halve the step" remedy against overshooting steep slopes (7.1.3).
 * max_steps in [1, 100000]. Outputs as ccl_terrain_march_fixed (t includes the last step, as printed). */
CCL_API int32_t ccl_terrain_march_dynamic(ccl_vec3 ro, ccl_vec3 rd, float max_t, float precision, int32_t max_steps,
                                          float step_scale, int32_t octaves, float height_scale,
                                          float horizontal_scale, uint32_t seed, int32_t heightmap, float *out_t,
                                          int *out_steps);

/* The refinement proposed in ch. 9 (not implemented in the text). Ref: pt-alg-9-bisect. March as
 * ccl_terrain_march_dynamic while d >= threshold; once d < threshold, step by the threshold instead of d (a floor on
 * the step: no crawl along a surface the ray runs parallel to), and when the end of such a step is below the surface
 * (d_b < precision) find the crossing in [t, t + threshold] by `bisect_steps` halvings (constant cost; error <=
 * threshold / 2^bisect_steps). threshold in (0, 100], bisect_steps in [0, 64]; other arguments as the dynamic march.
 * *out_steps counts every height evaluated (march + bisection). */
CCL_API int32_t ccl_terrain_march_bisect(ccl_vec3 ro, ccl_vec3 rd, float max_t, float precision, int32_t max_steps,
                                         float step_scale, float threshold, int32_t bisect_steps, int32_t octaves,
                                         float height_scale, float horizontal_scale, uint32_t seed,
                                         int32_t heightmap, float *out_t, int *out_steps);

/* Hard shadow. Ref: pt-code-7.6: t = t0; up to max_steps times: d = map(ro + rd t); d < precision -> 0 (occluded);
 * t > max_t -> stop; t += d. Returns 1 (lit) or 0. ro: shaded point; rd: unit direction to the light; t0 in [0, 100]
 * (Kod 7.6: 0.2); max_t in (0, 10000]; precision in (0, 10]; max_steps in [1, 100000]. */
CCL_API float ccl_terrain_shadow_hard(ccl_vec3 ro, ccl_vec3 rd, float t0, float max_t, float precision,
                                      int32_t max_steps, int32_t octaves, float height_scale, float horizontal_scale,
                                      uint32_t seed, int32_t heightmap);

/* Soft shadow (penumbra, Quilez). Ref: pt-code-7.7: as the hard shadow, and after each step shadow = min(shadow,
 * k d / t). t0 in (0, 100] (Kod 7.7: 0.02), k in (0, 1000] (Kod 7.7: 4; larger = harder). Returns a value in
 * [0, 1], non-decreasing in k. */
CCL_API float ccl_terrain_shadow_soft(ccl_vec3 ro, ccl_vec3 rd, float t0, float k, float max_t, float precision,
                                      int32_t max_steps, int32_t octaves, float height_scale, float horizontal_scale,
                                      uint32_t seed, int32_t heightmap);

/* Ambient + Lambert light. Ref: pt-7.1: I = L_a C_a + L_d C_d max(0, n.l) shadow (the shadow factor multiplies
 * the diffuse term: the text does not say, this is the usual choice). n, l: unit vectors; la, ld >= 0 intensities;
 * ca, cd: colours (RGB, [0, 1]); shadow in [0, 1]. Returns RGB >= 0. */
CCL_API ccl_vec3 ccl_terrain_lighting(ccl_vec3 n, ccl_vec3 l, float la, ccl_vec3 ca, float ld, ccl_vec3 cd,
                                      float shadow);

/* Normal by central differences. Ref: pt-code-7.8, pt-7.2: g = (map(p + h x) - map(p - h x), map(p + h y) -
 * map(p - h y), map(p + h z) - map(p - h z)) with map = y - h(x, z) and `octaves` octaves; returns normalize(g),
 * and g itself (not divided by 2h) through out_g when not NULL. g.y = 2h up to five roundings (p.y +- h, the two
 * map values, their difference): |g.y - 2h| <= 2 ulp(|p.y| + h + |H|) + ulp(2h), H the height at (p.x, p.z) and
 * ulp(x) the float spacing at x (0.00402832 for h = 0.002 at p.y ~ 957: within 1.2e-4 of 2h there).
 * h in (0, 1] (Kod 7.8: 0.002). */
CCL_API ccl_vec3 ccl_terrain_normal(ccl_vec3 p, float h, int32_t octaves, float height_scale, float horizontal_scale,
                                    uint32_t seed, int32_t heightmap, ccl_vec3 *out_g);

/* Octave count of the normal at distance t. Ref: pt-alg-7.3-lod (the text gives no rule): octaves_max up to
 * lod_distance, one octave less per doubling of the distance beyond it (an octave's detail halves in size, and so
 * does the pixel footprint's resolution of it, per doubling of t), never below octaves_min. t >= 0 (units);
 * 1 <= octaves_min <= octaves_max <= 16; lod_distance > 0. Exact (multiplications by 2 only). */
CCL_API int32_t ccl_terrain_normal_octaves(float t, int32_t octaves_max, int32_t octaves_min, float lod_distance);

/* Fog weight. Ref: pt-7.3. variant CCL_VARIANT_THESIS: f = min(e^(rho d) - 1, 1) as printed (f = 1 exactly for
 * d >= ln 2 / rho); CCL_VARIANT_CORRECTED: the conventional f = 1 - e^(-rho d). d >= 0 (units), rho > 0 (per unit).
 * Output in [0, 1]. The scene blends colour + (sky - colour) f. */
CCL_API float ccl_terrain_fog(float d, float rho, ccl_variant variant);

/* Sky with the sun. Ref: pt-code-7.10: sky_colour + max(rd.sun, 0)^power sun_colour. rd, sun: unit vectors (sun:
 * the direction towards the sun, not a position); power > 0 (Kod 7.10: 80; the glow halves at acos(0.5^(1/80)) =
 * 7.53 deg). rd.sun is taken in [0, 1] (two unit vectors' dot can round to 1 + 2^-23, whose power overflowed for
 * power above ~7e8); the colour is not clamped. */
CCL_API ccl_vec3 ccl_terrain_sky(ccl_vec3 rd, ccl_vec3 sun, ccl_vec3 sky_colour, ccl_vec3 sun_colour, float power);

/* 2-D fBm clouds. Ref: pt-code-7.11: q = ro + rd (cloud_height - ro.y) / rd.y, q.xz += wind time, w = clamp(fbm(q.xz
 * / cloud_scale, 4 octaves) rd.y, 0, 1), colour + (cloud_colour - colour) w. cloud_scale = 1 is the listing (which
 * has no scale). variant CCL_VARIANT_THESIS: as printed, also for rd.y < 0 (spurious clouds below the horizon where
 * the fBm is negative; rd.y == 0 gives the colour unchanged, the limit of the weight); CCL_VARIANT_CORRECTED: clouds
 * only where the plane lies ahead of the ray (t = (cloud_height - ro.y) / rd.y > 0). Where t or the fBm's top
 * octave coordinate 8 q.xz / cloud_scale overflows the floats (for a ray near the horizon: |rd.y| below ~1e-37
 * |cloud_height - ro.y| / cloud_scale), the plane point has no fBm value: the colour unchanged, the limit of the
 * weight as for rd.y == 0.
 * rd: unit; seed: Perlin seed; time >= 0 (s); wind: (x, z) units/s. */
CCL_API ccl_vec3 ccl_terrain_clouds(ccl_vec3 colour, ccl_vec3 ro, ccl_vec3 rd, float cloud_height, ccl_vec2 wind,
                                    float time, float cloud_scale, ccl_vec3 cloud_colour, uint32_t seed,
                                    ccl_variant variant);

/* Fresnel-like refraction weight. Ref: pt-7.4: f = |v.n|^kappa; v: unit view direction, n: unit water normal,
 * kappa > 0 (Obrazok 7.9: 1, 3, 6). f in [0, 1]: 1 looking straight down (the bottom shows), -> 0 at grazing angles
 * (only the reflection). */
CCL_API float ccl_terrain_water_weight(ccl_vec3 v, ccl_vec3 n, float kappa);

/* Wave normal of the water plane (the text: "noise and trigonometric functions", no formula; ours): with
 * (u, v) = (x, z) / wave_scale, s = wave_strength,
 * a = perlin2(u + 0.5 t, v - 0.3 t) + 0.5 sin(3 u + 2 t), b = perlin2(u - 0.4 t + 37.2, v + 0.2 t + 11.7) +
 * 0.5 sin(3 v + 1.7 t), n = normalize(-s a, 1, -s b). Part of pt-alg-7.3.4. */
CCL_API ccl_vec3 ccl_terrain_water_normal_perm(float x, float z, float time, float wave_scale, float wave_strength,
                                               const uint8_t *perm);

/* Shade one ray: the demo's top-level shading with everything of ch. 7. Ref: pt-code-7.3 (castRay with its t, as
 * the note fixes the 2-argument call), pt-alg-7.3-material (stages (a)-(d)), pt-alg-7.3.4 (water: plane hit, wave
 * normal, reflection of sky + clouds only, mix(reflection, tint * underwater terrain, f) with f of eq 7.4).
 * p: checked params; ro, rd (unit). Returns the unclamped colour; *out_steps = height evaluations of the view march
 * (not the shadow). */
CCL_API ccl_vec3 ccl_terrain_shade(const ccl_terrain_params *p, ccl_vec3 ro, ccl_vec3 rd, int *out_steps);

/* One pixel: mean of the shades of m x m regular sub-samples at offsets ((i + 0.5) / m, (j + 0.5) / m) inside the
 * pixel (m = samples_per_axis; 7.1.6: 1, 4 or 16 rays), each ray built as ccl_camera_ray (m = 1: exactly it), then
 * clamped to [0, 1]. Ref: pt-alg-7.1.6. inv_view_proj_rot: ccl_camera.inv_view_proj_rot; eye: camera position;
 * 0 <= x < width, 0 <= y < height (y = 0 the top row). out_rgb[3]; *out_steps: summed view-march evaluations. */
CCL_API void ccl_terrain_pixel(const ccl_terrain_params *p, const float inv_view_proj_rot[16], ccl_vec3 eye, int x,
                               int y, int width, int height, float *out_rgb, int *out_steps);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_TERRAIN_H */
