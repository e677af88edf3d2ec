/* Signed distance functions, ray tracing and sphere tracing, pt §4 - §5. See cclouds/sdf.h. */
#include "cclouds/sdf.h"
#include "cclouds/noise.h"
#include "internal.h"

#include <math.h>

float ccl_sdf_sphere(ccl_vec3 p, float s)
{
    return ccl_vec3_length(p) - s;
}

float ccl_sdf_box(ccl_vec3 p, ccl_vec3 b)
{
    ccl_vec3 d = v3(fabsf(p.x) - b.x, fabsf(p.y) - b.y, fabsf(p.z) - b.z);
    float inside = fminf(fmaxf(d.x, fmaxf(d.y, d.z)), 0.0f);
    return inside + ccl_vec3_length(v3(fmaxf(d.x, 0.0f), fmaxf(d.y, 0.0f), fmaxf(d.z, 0.0f)));
}

float ccl_sdf_torus(ccl_vec3 p, ccl_vec2 t)
{
    float qx = sqrtf(p.x * p.x + p.z * p.z) - t.x;
    return sqrtf(qx * qx + p.y * p.y) - t.y;
}

float ccl_sdf_ellipsoid(ccl_vec3 p, ccl_vec3 r)
{
    return (ccl_vec3_length(v3(p.x / r.x, p.y / r.y, p.z / r.z)) - 1.0f) * fminf(fminf(r.x, r.y), r.z);
}

void ccl_sdf_primitives(ccl_vec3 p, float s, ccl_vec3 b, ccl_vec2 t, ccl_vec3 r, float *out_sphere, float *out_box,
                        float *out_torus, float *out_ellipsoid)
{
    if (out_sphere) *out_sphere = ccl_sdf_sphere(p, s);
    if (out_box) *out_box = ccl_sdf_box(p, b);
    if (out_torus) *out_torus = ccl_sdf_torus(p, t);
    if (out_ellipsoid) *out_ellipsoid = ccl_sdf_ellipsoid(p, r);
}

float ccl_sdf_union(float d1, float d2)
{
    return fminf(d1, d2);
}

float ccl_sdf_intersect(float d1, float d2)
{
    return fmaxf(d1, d2);
}

float ccl_sdf_subtract(float d1, float d2)
{
    return fmaxf(-d2, d1);
}

float ccl_sdf_smooth_union(float d1, float d2, float k)
{
    float h = 0.5f + 0.5f * (d1 - d2) / k;
    CCL_REQUIRE(k > 0.0f);
    h = fminf(fmaxf(h, 0.0f), 1.0f);
    return d1 * (1.0f - h) + d2 * h - k * h * (1.0f - h);
}

/* One axis of the repeat, in [-c/2, c/2) for every finite x and c in [2^-125, FLT_MAX] (c/2 exact and normal).
 * GLSL's x - c floor(x / c) rounded twice: the quotient's rounding put the result a period off for |x| / c of ~1e5
 * and more, and x - c (-1) = c for a tiny negative x gave c/2 (fuzz finding N5). fmodf's remainder r is exact, |r| < c,
 * with the sign of x; the shifts by c below are exact too (Sterbenz), so the corrected form is the exact centred
 * remainder. The thesis form r + c/2 for r < 0 rounds up to c/2 when |r| is below half an ulp of c/2: the float below
 * c/2 (c/2 (1 - 2^-24)) is then the nearest value inside the interval. */
static float repeat_axis(float x, float c, ccl_variant variant)
{
    const float h = 0.5f * c, r = fmodf(x, c);
    if (variant != CCL_VARIANT_THESIS) return r >= h ? r - c : (r < -h ? r + c : r); /* mod(x + c/2, c) - c/2 */
    if (r >= 0.0f) return r - h;                                                      /* mod(x, c) - c/2 */
    return r + h < h ? r + h : h * 0.99999994f;
}

ccl_vec3 ccl_sdf_repeat(ccl_vec3 p, ccl_vec3 c, ccl_variant variant)
{
    return v3(repeat_axis(p.x, c.x, variant), repeat_axis(p.y, c.y, variant), repeat_axis(p.z, c.z, variant));
}

void ccl_sdf_operators(float d1, float d2, float k, ccl_vec3 p, ccl_vec3 c, ccl_variant variant, float *out_union,
                       float *out_intersection, float *out_subtraction, float *out_smooth_union,
                       ccl_vec3 *out_repeat)
{
    if (out_union) *out_union = ccl_sdf_union(d1, d2);
    if (out_intersection) *out_intersection = ccl_sdf_intersect(d1, d2);
    if (out_subtraction) *out_subtraction = ccl_sdf_subtract(d1, d2);
    if (out_smooth_union) *out_smooth_union = ccl_sdf_smooth_union(d1, d2, k);
    if (out_repeat) *out_repeat = ccl_sdf_repeat(p, c, variant);
}

/* ---- demonstration scenes ------------------------------------------------------------------------------------- */

/* Displacement of scene 5: amplitude, noise frequency and the bound of |grad perlin3| used for the Lipschitz factor
 * (the gradient of Perlin's improved noise stays below 4 lattice units^-1). */
#define DISP_AMPLITUDE 0.12f
#define DISP_FREQUENCY 3.0f
#define DISP_GRAD_BOUND 4.0f

static float scene_eval(ccl_vec3 p, const uint8_t *perm, int scene)
{
    const ccl_vec3 cube = v3(0.7f, 0.7f, 0.7f);
    switch (scene) {
    case CCL_SDF_SCENE_PRIMITIVES: {
        float d = ccl_sdf_sphere(v3(p.x + 3.75f, p.y, p.z), 0.8f);
        ccl_vec2 t;
        t.x = 0.7f;
        t.y = 0.25f;
        d = ccl_sdf_union(d, ccl_sdf_box(v3(p.x + 1.25f, p.y, p.z), cube));
        d = ccl_sdf_union(d, ccl_sdf_torus(v3(p.x - 1.25f, p.y, p.z), t));
        return ccl_sdf_union(d, ccl_sdf_ellipsoid(v3(p.x - 3.75f, p.y, p.z), v3(0.9f, 0.6f, 0.45f)));
    }
    case CCL_SDF_SCENE_UNION:
        return ccl_sdf_union(ccl_sdf_box(p, cube), ccl_sdf_sphere(p, 0.9f));
    case CCL_SDF_SCENE_INTERSECTION:
        return ccl_sdf_intersect(ccl_sdf_box(p, cube), ccl_sdf_sphere(p, 0.9f));
    case CCL_SDF_SCENE_SUBTRACTION:
        return ccl_sdf_subtract(ccl_sdf_box(p, cube), ccl_sdf_sphere(p, 0.9f));
    case CCL_SDF_SCENE_REPETITION: {
        ccl_vec3 q = ccl_sdf_repeat(p, v3(1.2f, 1.2f, 1.2f), CCL_VARIANT_THESIS);
        q.y = p.y;
        return ccl_sdf_sphere(q, 0.35f);
    }
    case CCL_SDF_SCENE_DISPLACEMENT: {
        float n = ccl_noise_perlin3_perm(DISP_FREQUENCY * p.x, DISP_FREQUENCY * p.y, DISP_FREQUENCY * p.z, perm, 0);
        return (ccl_sdf_sphere(p, 1.0f) - DISP_AMPLITUDE * n) /
               (1.0f + DISP_AMPLITUDE * DISP_FREQUENCY * DISP_GRAD_BOUND);
    }
    default:
        return ccl_sdf_smooth_union(ccl_sdf_ellipsoid(v3(p.x + 0.5f, p.y, p.z), v3(1.0f, 0.5f, 0.6f)),
                                    ccl_sdf_sphere(v3(p.x - 0.7f, p.y - 0.15f, p.z), 0.6f), 1.0f);
    }
}

float ccl_sdf_scene(ccl_vec3 p, uint32_t seed, int scene)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    ccl_noise_perm_table(seed, perm);
    return scene_eval(p, perm, scene);
}

/* the largest radius whose square is a finite float with room for |oc|^2 (2^60) */
#define RAY_SPHERE_SQUARE_MAX 1.152921504606846976e18f

float ccl_sdf_ray_sphere(ccl_vec3 ro, ccl_vec3 rd, ccl_vec3 centre, float radius)
{
    ccl_vec3 oc = ccl_vec3_sub(ro, centre);
    float k = 1.0f, b, c, disc, s, t0, t1;
    CCL_REQUIRE(radius > 0.0f);
    /* t scales with the sphere: a radius whose square overflows (Inf - Inf: an infinite t) is divided out, the unit
     * sphere in units of radius, and t scaled back; any other radius is used as it is */
    if (radius > RAY_SPHERE_SQUARE_MAX) {
        k = radius;
        oc.x /= k;
        oc.y /= k;
        oc.z /= k;
        radius = 1.0f;
    }
    b = ccl_vec3_dot(oc, rd);
    c = ccl_vec3_dot(oc, oc) - radius * radius;
    disc = b * b - c;
    if (disc < 0.0f) return -1.0f;
    s = sqrtf(disc);
    t0 = -b - s;
    t1 = -b + s;
    if (t0 >= 0.0f) return k * t0;
    if (t1 >= 0.0f) return k * t1;
    return -1.0f;
}

float ccl_sdf_sphere_trace(ccl_vec3 ro, ccl_vec3 rd, int32_t max_steps, float precision, float max_t, uint32_t seed,
                           int scene, int *out_steps, int *out_hit)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    float t = 0.0f;
    int32_t i;
    int steps = 0, hit = 0;
    CCL_REQUIRE(max_steps >= 1);
    CCL_REQUIRE(precision > 0.0f);
    ccl_noise_perm_table(seed, perm);
    for (i = 0; i < max_steps; ++i) {
        float d = scene_eval(ccl_vec3_add(ro, ccl_vec3_scale(rd, t)), perm, scene);
        steps = i + 1;
        if (d < precision) {
            hit = 1;
            break;
        }
        t += d;
        if (t > max_t) break;
    }
    if (out_steps) *out_steps = steps;
    if (out_hit) *out_hit = hit;
    return t;
}
