/* Fuzz harness: the element-wise functions of the ray-marched terrain (cclouds/terrain.h), written from the header
 * (issue 31); fuzz_terrain covers the parameter check and the whole shade. Contracts, within the documented domains:
 *   the height: |h| <= 10 for the test map, <= 2 height_scale for the fBm (amplitudes 1, 1/2, ..., |noise| <= 1);
 *   the marches (fixed, dynamic, bisection): hit 0 or 1, t finite, evaluations within their bounds, the fixed march's
 *     hit below the surface by the precision; shadows: hard 0 or 1, soft in [0, 1] and non-decreasing in k;
 *   the normal: unit, g.y within |g.y - 2h| <= 2 ulp(|p.y| + h + |H|) + ulp(2h) (finding I5's stated bound);
 *   fog in [0, 1]; sky finite with the glow at most the sun colour (N11); the clouds' colour between the colour and
 *   the cloud colour per channel (N12); the water weight in [0, 1] (I3); the wave normal unit; lighting >= 0. */
#include "cclouds/terrain.h"
#include "fuzz.h"
#include "fuzz_vec.h"


static ccl_vec3 fz_dir(fz_reader *r) {
    if (fz_u8(r) < 24) {
        static const ccl_vec3 axes[] = {{0.0f, -1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                        {0.577350318f, 0.577350318f, 0.577350318f}, {1.0f, 1e-38f, 0.0f},
                                        {0.0f, -1e-45f, 1.0f}};
        return axes[fz_u8(r) % 6];
    }
    ccl_vec3 d = v3(fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f));
    const float l = len3(d);
    if (!(l > 1e-3f)) return v3(0.0f, -1.0f, 0.0f);
    return v3(d.x / l, d.y / l, d.z / l);
}

static double ulp(double x) {
    const float f = (float)fabs(x);
    return (double)nextafterf(f, INFINITY) - (double)f;
}

typedef struct {
    int32_t octaves, heightmap;
    float height_scale, horizontal_scale;
    uint32_t seed;
    uint8_t perm[CCL_NOISE_PERM_SIZE];
} field;

static void fz_field_of(fz_reader *r, field *f) {
    f->heightmap = fz_range(r, 0, 1);
    f->octaves = fz_range(r, 1, fz_u8(r) < 200 ? 6 : 16);
    f->height_scale = fz_u8(r) < 200 ? fz_unit(r, 0.0f, 50.0f) : fz_unit(r, 0.0f, 1000.0f);
    f->horizontal_scale = fz_u8(r) < 200 ? fz_unit(r, 1.0f, 100.0f) : fz_unit(r, CCL_TERRAIN_MIN_SCALE, 1.0e4f);
    f->seed = fz_u32(r);
    ccl_noise_perm_table(f->seed, f->perm);
}

static float height_of(const field *f, float x, float z) {
    return ccl_terrain_height_perm(x, z, f->octaves, f->height_scale, f->horizontal_scale, f->perm, f->heightmap);
}

static void fuzz_height_and_normal(fz_reader *r) {
    field f;
    fz_field_of(r, &f);
    const float x = fz_u8(r) < 200 ? fz_unit(r, -500.0f, 500.0f) : fz_unit(r, -1.0e5f, 1.0e5f);
    const float z = fz_u8(r) < 200 ? fz_unit(r, -500.0f, 500.0f) : fz_unit(r, -1.0e5f, 1.0e5f);
    const float H = height_of(&f, x, z);
    const float bound = f.heightmap == CCL_TERRAIN_TEST ? 10.0f : 2.0f * f.height_scale;
    FZ_CHECK(isfinite(H) && fabsf(H) <= bound * (1.0f + 4.0f * EPS), "height %g beyond %g (map %d)", (double)H,
             (double)bound, f.heightmap);
    {
        const float h = fz_u8(r) < 128 ? 0.002f : fz_unit(r, 1e-4f, 1.0f);
        const ccl_vec3 p = v3(x, H + fz_unit(r, -2.0f, 2.0f), z);
        ccl_vec3 g;
        const ccl_vec3 n = ccl_terrain_normal(p, h, f.octaves, f.height_scale, f.horizontal_scale, f.seed, f.heightmap,
                                              &g);
        FZ_CHECK(fabsf(len3(n) - 1.0f) <= 1e-5f, "normal |n| = %g", (double)len3(n));
        const double b = 2.0 * ulp(fabs((double)p.y) + h + fabs((double)H)) + ulp(2.0 * h);
        FZ_CHECK(fabs((double)g.y - 2.0 * h) <= b, "g.y = %.9g, 2h = %.9g, bound %.3g (p.y %g H %g)", (double)g.y,
                 2.0 * h, b, (double)p.y, (double)H);
    }
}

static void fuzz_marches(fz_reader *r) {
    field f;
    fz_field_of(r, &f);
    const ccl_vec3 ro = v3(fz_unit(r, -200.0f, 200.0f), fz_unit(r, -5.0f, 80.0f), fz_unit(r, -200.0f, 200.0f));
    const ccl_vec3 rd = fz_dir(r);
    const float max_t = fz_u8(r) < 200 ? fz_unit(r, 1.0f, 300.0f) : fz_unit(r, 1e-3f, 1.0e4f);
    const float precision = fz_u8(r) < 200 ? fz_unit(r, 1e-3f, 0.1f) : fz_unit(r, 1e-6f, 10.0f);
    const int32_t max_steps = fz_range(r, 1, 300);
    const float step_scale = fz_unit(r, 0.05f, 1.0f);
    float t = -1.0f;
    int steps = -1;
    int32_t hit;
    switch (fz_u8(r) % 3) {
    case 0: {
        /* few evaluations: the step at least max_t / 300 */
        float step = fz_unit(r, CCL_TERRAIN_MIN_SCALE, 100.0f);
        if (max_t / step > 300.0f) step = max_t / 300.0f;
        if (step > 100.0f) return;
        hit = ccl_terrain_march_fixed(ro, rd, max_t, step, precision, f.octaves, f.height_scale, f.horizontal_scale,
                                      f.seed, f.heightmap, &t, &steps);
        FZ_CHECK(steps >= 0 && steps <= CCL_TERRAIN_MAX_FIXED_STEPS, "fixed steps %d", steps);
        if (hit == 1) {
            const ccl_vec3 p = v3(ro.x + rd.x * t, ro.y + rd.y * t, ro.z + rd.z * t);
            FZ_CHECK(p.y - precision < height_of(&f, p.x, p.z) + 16.0f * EPS * (fabsf(p.y) + fabsf(ro.y) + t + 10.0f),
                     "fixed march hit above the surface at t %g", (double)t);
        }
        break;
    }
    case 1:
        hit = ccl_terrain_march_dynamic(ro, rd, max_t, precision, max_steps, step_scale, f.octaves, f.height_scale,
                                        f.horizontal_scale, f.seed, f.heightmap, &t, &steps);
        FZ_CHECK(steps >= 0 && steps <= max_steps, "dynamic steps %d of %d", steps, max_steps);
        break;
    default: {
        const float threshold = fz_unit(r, 1e-3f, 100.0f);
        const int32_t bis = fz_range(r, 0, 64);
        hit = ccl_terrain_march_bisect(ro, rd, max_t, precision, max_steps, step_scale, threshold, bis, f.octaves,
                                       f.height_scale, f.horizontal_scale, f.seed, f.heightmap, &t, &steps);
        FZ_CHECK(steps >= 0 && steps <= max_steps * 2 + bis + 2, "bisect steps %d", steps);
        break;
    }
    }
    FZ_CHECK((hit == 0 || hit == 1) && isfinite(t), "march hit %d t %g", hit, (double)t);
    {
        const float t0 = fz_unit(r, 0.01f, 1.0f), k = fz_unit(r, 0.01f, 1000.0f), k2 = k * fz_unit(r, 1.0f, 4.0f);
        const float hard = ccl_terrain_shadow_hard(ro, rd, t0, max_t, precision, max_steps, f.octaves, f.height_scale,
                                                   f.horizontal_scale, f.seed, f.heightmap);
        FZ_CHECK(hard == 0.0f || hard == 1.0f, "hard shadow %g", (double)hard);
        if (k2 <= 1000.0f) {
            const float s1 = ccl_terrain_shadow_soft(ro, rd, t0, k, max_t, precision, max_steps, f.octaves,
                                                     f.height_scale, f.horizontal_scale, f.seed, f.heightmap);
            const float s2 = ccl_terrain_shadow_soft(ro, rd, t0, k2, max_t, precision, max_steps, f.octaves,
                                                     f.height_scale, f.horizontal_scale, f.seed, f.heightmap);
            FZ_CHECK(s1 >= 0.0f && s1 <= 1.0f && s2 >= s1, "soft shadow %g (k %g), %g (k %g)", (double)s1, (double)k,
                     (double)s2, (double)k2);
        }
    }
}

static void fuzz_atmosphere(fz_reader *r) {
    {
        const float d = fz_u8(r) < 200 ? fz_unit(r, 0.0f, 1.0e4f) : fabsf(fz_float(r));
        const float rho = fz_u8(r) < 200 ? fz_unit(r, 1e-5f, 1.0f) : fabsf(fz_float(r));
        if (isfinite(d) && rho > 0.0f && isfinite(rho)) {
            const int variant = fz_range(r, 0, 1);
            const float fog = ccl_terrain_fog(d, rho, (ccl_variant)variant);
            FZ_CHECK(fog >= 0.0f && fog <= 1.0f, "fog(%g, %g, %d) = %g", (double)d, (double)rho, variant, (double)fog);
        }
    }
    const ccl_vec3 rd = fz_dir(r), sun = fz_u8(r) < 32 ? rd : fz_dir(r);
    const ccl_vec3 sky = v3(fz_unit(r, 0.0f, 1.0f), fz_unit(r, 0.0f, 1.0f), fz_unit(r, 0.0f, 1.0f));
    const ccl_vec3 sc = v3(fz_unit(r, 0.0f, 2.0f), fz_unit(r, 0.0f, 2.0f), fz_unit(r, 0.0f, 2.0f));
    {
        float power = fz_u8(r) < 200 ? fz_unit(r, 0.5f, 200.0f) : fabsf(fz_float(r));
        if (!(power > 0.0f && isfinite(power))) power = 80.0f;
        const ccl_vec3 c = ccl_terrain_sky(rd, sun, sky, sc, power);
        FZ_CHECK(c.x >= sky.x && c.x <= sky.x + sc.x && c.y >= sky.y && c.y <= sky.y + sc.y && c.z >= sky.z &&
                     c.z <= sky.z + sc.z,
                 "sky (%g %g %g) beyond sky + sun (power %g)", (double)c.x, (double)c.y, (double)c.z, (double)power);
    }
    {
        const ccl_vec3 ro = v3(fz_unit(r, -1e3f, 1e3f), fz_unit(r, -10.0f, 100.0f), fz_unit(r, -1e3f, 1e3f));
        ccl_vec2 wind;
        wind.x = fz_unit(r, -10.0f, 10.0f);
        wind.y = fz_unit(r, -10.0f, 10.0f);
        const float ch = fz_unit(r, -100.0f, 500.0f), time = fz_unit(r, 0.0f, 1000.0f);
        const float cs = fz_u8(r) < 200 ? fz_unit(r, 1.0f, 200.0f) : fz_unit(r, CCL_TERRAIN_MIN_SCALE, 1.0e4f);
        const int variant = fz_range(r, 0, 1);
        const ccl_vec3 c = ccl_terrain_clouds(sky, ro, rd, ch, wind, time, cs, sc, fz_u32(r), (ccl_variant)variant);
        const float got[3] = {c.x, c.y, c.z}, a[3] = {sky.x, sky.y, sky.z}, b[3] = {sc.x, sc.y, sc.z};
        for (int i = 0; i < 3; ++i)
            FZ_CHECK(got[i] >= fminf(a[i], b[i]) - 4.0f * EPS && got[i] <= fmaxf(a[i], b[i]) + 4.0f * EPS,
                     "clouds channel %d = %g outside [%g, %g] (rd.y %g)", i, (double)got[i], (double)a[i],
                     (double)b[i], (double)rd.y);
    }
    {
        const float kappa = fz_unit(r, 0.01f, 100.0f);
        const float w = ccl_terrain_water_weight(rd, fz_u8(r) < 64 ? rd : sun, kappa);
        FZ_CHECK(w >= 0.0f && w <= 1.0f, "water weight %.9g (kappa %g)", (double)w, (double)kappa);
        uint8_t perm[CCL_NOISE_PERM_SIZE];
        ccl_noise_perm_table(fz_u32(r), perm);
        const ccl_vec3 n = ccl_terrain_water_normal_perm(fz_unit(r, -1e4f, 1e4f), fz_unit(r, -1e4f, 1e4f),
                                                         fz_unit(r, 0.0f, 1e3f),
                                                         fz_unit(r, CCL_TERRAIN_MIN_SCALE, 100.0f),
                                                         fz_unit(r, 0.0f, 10.0f), perm);
        FZ_CHECK(fabsf(len3(n) - 1.0f) <= 1e-5f, "wave normal |n| = %g", (double)len3(n));
        const ccl_vec3 l = ccl_terrain_lighting(rd, sun, fz_unit(r, 0.0f, 2.0f), sky, fz_unit(r, 0.0f, 2.0f), sc,
                                                fz_unit(r, 0.0f, 1.0f));
        FZ_CHECK(l.x >= 0.0f && l.y >= 0.0f && l.z >= 0.0f && isfinite(l.x + l.y + l.z), "lighting (%g %g %g)",
                 (double)l.x, (double)l.y, (double)l.z);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    switch (fz_u8(r) % 3) {
    case 0: fuzz_height_and_normal(r); break;
    case 1: fuzz_marches(r); break;
    default: fuzz_atmosphere(r); break;
    }
    return 0;
}
