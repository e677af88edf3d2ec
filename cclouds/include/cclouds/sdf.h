/*
 * cclouds/sdf.h -- signed distance functions of pt §4 and the two ways of finding a ray's first surface of pt §5:
 * primitives (Kod 4.1), operators (Kod 4.2), the demonstration scenes of Obrazok 4.1 / 4.2, analytic ray-sphere
 * intersection (ray tracing) and sphere tracing (ray marching with the SDF value as the step).
 *
 * Sign convention (pt-alg-4.1): d(p) > 0 outside, < 0 inside, = 0 on the surface. Points and directions are ccl_vec3
 * (scene units; world up +y). GLSL's mod(x, y) is x - y floor(x / y); mix(a, b, h) is a (1 - h) + b h.
 */
#ifndef CCLOUDS_SDF_H
#define CCLOUDS_SDF_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Demonstration scenes of ccl_sdf_scene (positions and sizes are this library's choice; the text gives none). */
typedef enum ccl_sdf_scene_id {
    CCL_SDF_SCENE_PRIMITIVES = 0,   /* Obrazok 4.1: sphere s = 0.8 at (-3.75, 0, 0), box b = (0.7, 0.7, 0.7) at
                                       (-1.25, 0, 0), torus t = (0.7, 0.25) at (1.25, 0, 0), ellipsoid r = (0.9, 0.6,
                                       0.45) at (3.75, 0, 0) */
    CCL_SDF_SCENE_UNION = 1,        /* Obrazok 4.2 (a): box b = (0.7, 0.7, 0.7) union sphere s = 0.9, both at 0 */
    CCL_SDF_SCENE_INTERSECTION = 2, /* (b): the same box intersected with the same sphere */
    CCL_SDF_SCENE_SUBTRACTION = 3,  /* (c): box minus sphere */
    CCL_SDF_SCENE_REPETITION = 4,   /* (d): sphere s = 0.35 repeated by the printed repeat (thesis variant) with
                                       period c = (1.2, 1.2, 1.2) in x and z (y kept): copies at ((i + 1/2) 1.2, 0,
                                       (k + 1/2) 1.2) */
    CCL_SDF_SCENE_DISPLACEMENT = 5, /* (e): sphere s = 1 displaced by 0.12 perlin3(3 p) (noise of `seed`), divided by
                                       the Lipschitz bound 1 + 0.12 * 3 * 4 = 2.44 so that it stays a distance bound */
    CCL_SDF_SCENE_SMOOTH_UNION = 6  /* (f): printed smooth union (k = 1) of ellipsoid r = (1.0, 0.5, 0.6) at
                                       (-0.5, 0, 0) and sphere s = 0.6 at (0.7, 0.15, 0) */
} ccl_sdf_scene_id;

/* Sphere of radius s at the origin: |p| - s. Exact. Ref: pt-code-4.1. s > 0. */
CCL_API float ccl_sdf_sphere(ccl_vec3 p, float s);

/* Axis-aligned box with half-extents b at the origin: min(max(d.x, d.y, d.z), 0) + |max(d, 0)|, d = |p| - b. Exact.
 * Ref: pt-code-4.1. b components > 0. */
CCL_API float ccl_sdf_box(ccl_vec3 p, ccl_vec3 b);

/* Torus around the y axis in the xz plane, major radius t.x, minor radius t.y: |(|p.xz| - t.x, p.y)| - t.y. Exact.
 * Ref: pt-code-4.1. t.x >= 0, t.y > 0. */
CCL_API float ccl_sdf_torus(ccl_vec3 p, ccl_vec2 t);

/* Ellipsoid with semi-axes r at the origin: (|p / r| - 1) min(r.x, r.y, r.z). APPROXIMATE (the text does not say so):
 * exact only for a sphere (r.x = r.y = r.z); zero exactly on the surface, the right sign everywhere, and never larger
 * than the true distance in magnitude (the function is 1-Lipschitz), so sphere tracing stays safe. Ref: pt-code-4.1.
 * r components > 0. */
CCL_API float ccl_sdf_ellipsoid(ccl_vec3 p, ccl_vec3 r);

/* The four primitives of Kod 4.1 at one point, each with its own size (the entry pt-code-4.1). */
CCL_API void ccl_sdf_primitives(ccl_vec3 p, float s, ccl_vec3 b, ccl_vec2 t, ccl_vec3 r, float *out_sphere,
                                float *out_box, float *out_torus, float *out_ellipsoid);

/* Union min(d1, d2) (Kod 4.2 `union`, a reserved word in GLSL). Ref: pt-code-4.2. */
CCL_API float ccl_sdf_union(float d1, float d2);

/* Intersection max(d1, d2). Ref: pt-code-4.2. */
CCL_API float ccl_sdf_intersect(float d1, float d2);

/* Subtraction max(-d2, d1): object 1 with object 2 carved out. Ref: pt-code-4.2. */
CCL_API float ccl_sdf_subtract(float d1, float d2);

/* Polynomial smooth union with blend width k: h = clamp(0.5 + 0.5 (d1 - d2) / k, 0, 1),
 * mix(d1, d2, h) - k h (1 - h). k = 1 is Kod 4.2's smoothUnion exactly (its fixed width of 1 scene unit); the general k
 * is Quilez's smin with the arguments swapped. Ref: pt-code-4.2. k > 0. Output <= min(d1, d2). */
CCL_API float ccl_sdf_smooth_union(float d1, float d2, float k);

/* Domain repetition with period c (in [2^-125, FLT_MAX] per axis: c/2 a normal float).
 * variant CCL_VARIANT_THESIS: mod(p, c) - c/2 as printed: an object modelled at the origin appears at (k + 1/2) c;
 * variant CCL_VARIANT_CORRECTED: mod(p + c/2, c) - c/2, the centred form: copies at k c.
 * Output components in [-c/2, c/2) for every finite p: the remainder is exact (fmodf), the corrected form exactly
 * the centred remainder, the thesis form exact but where it rounds up to c/2 (the float below c/2 instead). NaN or
 * infinite p gives NaN. Ref: pt-code-4.2. */
CCL_API ccl_vec3 ccl_sdf_repeat(ccl_vec3 p, ccl_vec3 c, ccl_variant variant);

/* The five operators of Kod 4.2 at once (the entry pt-code-4.2): union, intersection, subtraction and smooth union of
 * (d1, d2) with width k, and the repeated point of p with period c. */
CCL_API void ccl_sdf_operators(float d1, float d2, float k, ccl_vec3 p, ccl_vec3 c, ccl_variant variant,
                               float *out_union, float *out_intersection, float *out_subtraction,
                               float *out_smooth_union, ccl_vec3 *out_repeat);

/* Signed distance (bound) of a demonstration scene at p. Ref: pt-alg-4.1 (SDF definition: > 0 outside, < 0 inside,
 * 0 on the surface; scenes built with Kod 4.1 / 4.2). p components in [-1e4, 1e4]; seed: the Perlin table of the
 * displacement scene (0 = Perlin's); scene: ccl_sdf_scene_id. Every scene is a distance bound (|d| <= true distance),
 * so it can be sphere traced. */
CCL_API float ccl_sdf_scene(ccl_vec3 p, uint32_t seed, int scene);

/* Ray tracing's core step: nearest intersection of the ray ro + t rd (rd unit) with the sphere |x - centre| = radius,
 * solved analytically (t = -b -+ sqrt(b^2 - |oc|^2 + radius^2), b = oc . rd, oc = ro - centre). Ref: pt-alg-5.1.
 * ro, centre components in [-1e4, 1e4]; radius > 0 (above 2^60, where radius^2 overflows, the unit sphere is solved
 * in units of radius and t scaled back: finite for every float radius). Returns the smallest t >= 0 (the exit point
 * when ro is inside), or -1 when the ray misses. */
CCL_API float ccl_sdf_ray_sphere(ccl_vec3 ro, ccl_vec3 rd, ccl_vec3 centre, float radius);

/* Sphere tracing of a demonstration scene (ray marching with the distance as the step): t = 0; repeat at most
 * max_steps times: d = scene(ro + t rd); if d < precision the ray hit the surface; t += d; stop (miss) when t > max_t.
 * Ref: pt-alg-5.2. ro components in [-1e4, 1e4]; rd unit; max_steps in [1, 100000] (the loop bound); precision in
 * (0, 1]; max_t in (0, 1e5]; seed, scene as ccl_sdf_scene. Returns t (the hit distance when *out_hit = 1);
 * *out_steps = number of scene evaluations; *out_hit = 1 on a hit, 0 on a miss or when max_steps ran out. */
CCL_API float ccl_sdf_sphere_trace(ccl_vec3 ro, ccl_vec3 rd, int32_t max_steps, float precision, float max_t,
                                   uint32_t seed, int scene, int *out_steps, int *out_hit);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_SDF_H */
