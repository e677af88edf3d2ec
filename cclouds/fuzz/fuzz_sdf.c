/* Fuzz harness: signed distance functions (cclouds/sdf.h), written from the header (issue 31).
 * Contract: the exact primitives (sphere, box, torus) and the ellipsoid are 1-Lipschitz and every demonstration
 * scene is a distance bound -- |d(p) - d(q)| <= |p - q| up to float rounding -- for points in [-1e4, 1e4]; the smooth
 * union is <= min(d1, d2); ccl_sdf_repeat lies in [-c/2, c/2) for every finite p and c in [2^-125, FLT_MAX], both
 * variants (finding N5); ccl_sdf_ray_sphere returns -1 or a t >= 0 on the sphere; a sphere-trace hit lies within the
 * precision of the surface, at most max_steps evaluations, t finite. */
#include "cclouds/sdf.h"
#include "fuzz.h"
#include "fuzz_vec.h"


/* a point in [-1e4, 1e4]^3: mostly near the scenes' objects, sometimes anywhere in the box */
static ccl_vec3 fz_point(fz_reader *r) {
    const float h = fz_u8(r) < 160 ? 6.0f : 1.0e4f;
    return v3(fz_unit(r, -h, h), fz_unit(r, -h, h), fz_unit(r, -h, h));
}

/* a finite float, any magnitude (raw bits or edge values; NaN and +-Inf replaced by 0) */
static float fz_finite(fz_reader *r) {
    float f = fz_float(r);
    return isfinite(f) ? f : 0.0f;
}

/* a positive size parameter: small sane values or edge values */
static float fz_size(fz_reader *r, float lo, float hi) {
    float f = fz_u8(r) < 200 ? fz_unit(r, lo, hi) : fabsf(fz_finite(r));
    return f > 0.0f ? f : lo;
}

static void check_lipschitz(const char *what, float dp, float dq, ccl_vec3 p, ccl_vec3 q, float scale) {
    const float dist = len3(v3(p.x - q.x, p.y - q.y, p.z - q.z));
    /* rounding: a few ulps of the magnitudes involved (points, sizes, distances) */
    const float tol = 16.0f * EPS * (len3(p) + len3(q) + fabsf(dp) + fabsf(dq) + scale + 1.0f);
    FZ_CHECK(isfinite(dp) && isfinite(dq), "%s not finite: %g %g", what, (double)dp, (double)dq);
    FZ_CHECK(fabsf(dp - dq) <= dist + tol, "%s not 1-Lipschitz: |%g - %g| > %g at p (%g %g %g) q (%g %g %g)", what,
             (double)dp, (double)dq, (double)dist, (double)p.x, (double)p.y, (double)p.z, (double)q.x, (double)q.y,
             (double)q.z);
}

static void fuzz_primitives(fz_reader *r) {
    ccl_vec3 p = fz_point(r), q;
    const float step = fz_u8(r) < 128 ? fz_unit(r, 0.0f, 0.01f) : fz_unit(r, 0.0f, 2.0f);
    const float s = fz_size(r, 0.01f, 10.0f);
    const ccl_vec3 b = v3(fz_size(r, 0.01f, 10.0f), fz_size(r, 0.01f, 10.0f), fz_size(r, 0.01f, 10.0f));
    const ccl_vec3 e = v3(fz_size(r, 0.01f, 10.0f), fz_size(r, 0.01f, 10.0f), fz_size(r, 0.01f, 10.0f));
    ccl_vec2 t;
    t.x = fz_u8(r) < 16 ? 0.0f : fz_size(r, 0.01f, 10.0f);
    t.y = fz_size(r, 0.01f, 10.0f);
    q = v3(p.x + step * fz_unit(r, -1.0f, 1.0f), p.y + step * fz_unit(r, -1.0f, 1.0f),
           p.z + step * fz_unit(r, -1.0f, 1.0f));
    if (!(s <= 1e6f && b.x <= 1e6f && b.y <= 1e6f && b.z <= 1e6f && e.x <= 1e6f && e.y <= 1e6f && e.z <= 1e6f &&
          t.x <= 1e6f && t.y <= 1e6f && e.x >= 1e-6f && e.y >= 1e-6f && e.z >= 1e-6f))
        return; /* sizes: sane magnitudes (the ellipsoid divides by them) */
    check_lipschitz("sphere", ccl_sdf_sphere(p, s), ccl_sdf_sphere(q, s), p, q, s);
    check_lipschitz("box", ccl_sdf_box(p, b), ccl_sdf_box(q, b), p, q, b.x + b.y + b.z);
    check_lipschitz("torus", ccl_sdf_torus(p, t), ccl_sdf_torus(q, t), p, q, t.x + t.y);
    /* the ellipsoid's rounding grows with the axis ratio: tolerance in units of the largest semi-axis */
    {
        const float emax = fmaxf(e.x, fmaxf(e.y, e.z)), emin = fminf(e.x, fminf(e.y, e.z));
        check_lipschitz("ellipsoid", ccl_sdf_ellipsoid(p, e), ccl_sdf_ellipsoid(q, e), p, q,
                        emax + (len3(p) + len3(q)) * emax / emin);
    }
    {
        const float d1 = fz_unit(r, -10.0f, 10.0f), d2 = fz_unit(r, -10.0f, 10.0f), k = fz_size(r, 0.01f, 4.0f);
        const float su = ccl_sdf_smooth_union(d1, d2, k);
        FZ_CHECK(su <= fminf(d1, d2) + 4.0f * EPS * (fabsf(d1) + fabsf(d2) + k),
                 "smooth union %g above min(%g, %g) (k %g)", (double)su, (double)d1, (double)d2, (double)k);
    }
}

static void fuzz_repeat(fz_reader *r) {
    ccl_vec3 p = v3(fz_finite(r), fz_finite(r), fz_finite(r)), c;
    const int variant = fz_bool(r);
    float cc[3];
    for (int i = 0; i < 3; ++i) {
        float v = fabsf(fz_finite(r));
        if (fz_u8(r) < 128) v = fz_unit(r, 0.001f, 10.0f);
        cc[i] = v < 2.350988702e-38f ? 2.350988702e-38f : v; /* 2^-125 */
    }
    c = v3(cc[0], cc[1], cc[2]);
    ccl_vec3 q = ccl_sdf_repeat(p, c, (ccl_variant)variant);
    const float out[3] = {q.x, q.y, q.z}, in[3] = {p.x, p.y, p.z};
    for (int i = 0; i < 3; ++i)
        FZ_CHECK(out[i] >= -0.5f * cc[i] && out[i] < 0.5f * cc[i], "repeat(%.9g, %.9g, variant %d) = %.9g not in [-c/2, c/2)",
                 (double)in[i], (double)cc[i], variant, (double)out[i]);
}

static void fuzz_scene(fz_reader *r) {
    const int scene = fz_range(r, 0, 6);
    const uint32_t seed = fz_u32(r);
    ccl_vec3 p = fz_point(r), q;
    const float step = fz_u8(r) < 128 ? fz_unit(r, 0.0f, 0.01f) : fz_unit(r, 0.0f, 2.0f);
    q = v3(p.x + step * fz_unit(r, -1.0f, 1.0f), p.y + step * fz_unit(r, -1.0f, 1.0f),
           p.z + step * fz_unit(r, -1.0f, 1.0f));
    if (!(fabsf(q.x) <= 1e4f && fabsf(q.y) <= 1e4f && fabsf(q.z) <= 1e4f)) return;
    /* the scenes' objects are a few units big; their ellipsoids have axis ratios of 2 at most */
    check_lipschitz("scene", ccl_sdf_scene(p, seed, scene), ccl_sdf_scene(q, seed, scene), p, q,
                    4.0f * (len3(p) + len3(q)) + 8.0f);
}

static ccl_vec3 fz_unit_dir(fz_reader *r) {
    ccl_vec3 d = v3(fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f));
    float l = len3(d);
    if (!(l > 1e-3f)) return v3(0.0f, 0.0f, 1.0f);
    return v3(d.x / l, d.y / l, d.z / l);
}

static void fuzz_trace(fz_reader *r) {
    const int scene = fz_range(r, 0, 6), max_steps = fz_range(r, 1, 300);
    const uint32_t seed = fz_u32(r);
    const ccl_vec3 ro = fz_point(r), rd = fz_unit_dir(r);
    const float precision = fz_u8(r) < 200 ? fz_unit(r, 1e-4f, 0.1f) : fz_unit(r, 1e-6f, 1.0f);
    const float max_t = fz_u8(r) < 200 ? fz_unit(r, 1.0f, 100.0f) : fz_unit(r, 1e-3f, 1e5f);
    int steps = -1, hit = -1;
    const float t = ccl_sdf_sphere_trace(ro, rd, max_steps, precision, max_t, seed, scene, &steps, &hit);
    FZ_CHECK(steps >= 0 && steps <= max_steps && (hit == 0 || hit == 1), "steps %d (max %d), hit %d", steps, max_steps,
             hit);
    FZ_CHECK(isfinite(t) && t >= 0.0f, "trace t = %g", (double)t);
    if (hit) {
        const ccl_vec3 p = v3(ro.x + t * rd.x, ro.y + t * rd.y, ro.z + t * rd.z);
        if (fabsf(p.x) <= 1e4f && fabsf(p.y) <= 1e4f && fabsf(p.z) <= 1e4f) {
            const float d = ccl_sdf_scene(p, seed, scene);
            FZ_CHECK(d < precision + 16.0f * EPS * (len3(ro) + t + 8.0f),
                     "hit off the surface: scene %d d %g >= precision %g (t %g)", scene, (double)d, (double)precision,
                     (double)t);
        }
    }
}

static void fuzz_ray_sphere(fz_reader *r) {
    const ccl_vec3 ro = fz_point(r), rd = fz_unit_dir(r), c = fz_point(r);
    float radius = fz_u8(r) < 200 ? fz_unit(r, 1e-3f, 100.0f) : fabsf(fz_finite(r));
    if (!(radius > 0.0f)) radius = 1.0f;
    const float t = ccl_sdf_ray_sphere(ro, rd, c, radius);
    FZ_CHECK(t == -1.0f || (t >= 0.0f && isfinite(t)), "ray_sphere t = %g (radius %g)", (double)t, (double)radius);
    if (t >= 0.0f && radius <= 1e6f) {
        const ccl_vec3 p = v3(ro.x + t * rd.x - c.x, ro.y + t * rd.y - c.y, ro.z + t * rd.z - c.z);
        /* the printed closed form subtracts b^2 - |oc|^2 + radius^2: its rounding, ~eps |oc|^2, moves the root by
         * up to ~sqrt(eps) |oc| (a small sphere far away: pt-alg-5.1 as printed, not the robust form of vc-A14) */
        const ccl_vec3 oc = v3(ro.x - c.x, ro.y - c.y, ro.z - c.z);
        const float tol = 64.0f * EPS * (len3(ro) + len3(c) + t + radius) + 4.0f * sqrtf(EPS) * (len3(oc) + radius);
        FZ_CHECK(fabsf(len3(p) - radius) <= tol, "ray_sphere hit |p - c| = %g, radius %g (t %g)", (double)len3(p),
                 (double)radius, (double)t);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    switch (fz_u8(r) % 5) {
    case 0: fuzz_primitives(r); break;
    case 1: fuzz_repeat(r); break;
    case 2: fuzz_scene(r); break;
    case 3: fuzz_trace(r); break;
    default: fuzz_ray_sphere(r); break;
    }
    return 0;
}
