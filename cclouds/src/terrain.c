/* The ray-marched procedural terrain demo of the pt text (see cclouds/terrain.h). Every function is mirrored
 * operation by operation by pywarp/kernels/terrain.py (float32, same order, comparisons written out so that NaN and
 * signed zeros behave alike). */
#include "cclouds/terrain.h"
#include "cclouds/camera.h"
#include "cclouds/interp.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "internal.h"

/* ---- small helpers (Warp: the same expressions) --------------------------------------------------------------- */

/* ro + rd t */
static ccl_vec3 along(ccl_vec3 ro, ccl_vec3 rd, float t)
{
    return v3(ro.x + rd.x * t, ro.y + rd.y * t, ro.z + rd.z * t);
}

/* GLSL smoothstep(a, b, x) for a < b */
static float smoothstep(float a, float b, float x)
{
    float s = clamp01((x - a) / (b - a));
    return s * s * (3.0f - 2.0f * s);
}

/* Kod 7.9 (pt-code-7.9) = pt-alg-3.2 with the printed A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2 */
static float fbm_perm(float x, float z, int32_t octaves, const uint8_t *perm)
{
    ccl_vec2 p;
    p.x = x;
    p.y = z;
    return ccl_noise_fbm_perlin2_perm(p, octaves, perm, 1.0f, 0.5f, 0.5f, 2.0f);
}

/* The heightmap of the element-wise functions and of the scene. */
typedef struct {
    int32_t octaves;
    float height_scale;
    float horizontal_scale;
    const uint8_t *perm;
    int32_t heightmap;
    float hmax; /* upper bound of the height (the slab's top), NO_SLAB: the printed loops (no clipping) */
    float precision_t; /* dynamic march: PRECISION grows by this per unit of t (0: as printed) */
} heightfield;

/* hmax of the element-wise functions (the printed listings): y - NO_SLAB > precision never holds */
#define NO_SLAB 3.0e38f

static float height(const heightfield *f, float x, float z)
{
    if (f->heightmap == CCL_TERRAIN_TEST) return 10.0f * sinf(0.1f * x) * sinf(0.1f * z);
    return f->height_scale * fbm_perm(x / f->horizontal_scale, z / f->horizontal_scale, f->octaves, f->perm);
}

/* Kod 7.5's map: the vertical gap between the point and the terrain */
static float map(const heightfield *f, ccl_vec3 q)
{
    return q.y - height(f, q.x, q.z);
}

static heightfield field_of(int32_t octaves, float height_scale, float horizontal_scale, const uint8_t *perm,
                            int32_t heightmap)
{
    heightfield f;
    f.octaves = octaves;
    f.height_scale = height_scale;
    f.horizontal_scale = horizontal_scale;
    f.perm = perm;
    f.heightmap = heightmap;
    f.hmax = NO_SLAB;
    f.precision_t = 0.0f;
    return f;
}

/* Start of a view ray: 0, or where a ray from above the slab (y > hmax + precision) comes down to its top -- no
 * point before it can be a hit (d >= y - hmax > precision there). */
static float slab_entry(const heightfield *f, ccl_vec3 ro, ccl_vec3 rd, float precision)
{
    float above = ro.y - f->hmax - precision;
    if (rd.y < 0.0f && above > 0.0f) return above / -rd.y;
    return 0.0f;
}

/* ---- the marches and shadows on a heightfield -------------------------------------------------------------------- */

/* pt-code-7.4 (Kod 7.4, the fixed step of §7.1.2): for (t = 0; t < MAX_T; t += STEP_SIZE) { point = ro + rd t;
 * hit when point.y - PRECISION < map(point) } with map the height h (q is the text's point). Beyond the text: the
 * break above the slab (f->hmax; NO_SLAB: as printed) and the cap of CCL_TERRAIN_MAX_FIXED_STEPS. */
static int32_t march_fixed(const heightfield *f, ccl_vec3 ro, ccl_vec3 rd, float max_t, float step_size,
                           float precision, float *out_t, int *out_steps)
{
    float t = 0.0f;
    int32_t steps = 0;
    while (t < max_t && steps < CCL_TERRAIN_MAX_FIXED_STEPS) {
        ccl_vec3 q = along(ro, rd, t);
        if (rd.y >= 0.0f && q.y - f->hmax > precision) break; /* above the slab, rising: no hit ahead */
        steps += 1;
        if (q.y - precision < height(f, q.x, q.z)) {
            *out_t = t;
            *out_steps = steps;
            return 1;
        }
        t += step_size;
    }
    *out_t = t;
    *out_steps = steps;
    return 0;
}

/* pt-code-7.5 (Kod 7.5, the dynamic step of §7.1.3): for (i < MAX_STEPS) { point = ro + rd t; stepSize =
 * map(point), the vertical gap point.y - h; t += stepSize; hit when stepSize < PRECISION; miss when t > MAX_T }
 * (q is the text's point, d its stepSize). Beyond the text: step_scale (its remedy for overshooting, "for example to
 * half"; 1: as printed), the start and the break at the slab (f->hmax; NO_SLAB: as printed) and the precision growing
 * with t (f->precision_t; 0: as printed). */
static int32_t march_dynamic(const heightfield *f, ccl_vec3 ro, ccl_vec3 rd, float max_t, float precision,
                             int32_t max_steps, float step_scale, float *out_t, int *out_steps)
{
    float t = slab_entry(f, ro, rd, precision);
    int32_t i;
    for (i = 0; i < max_steps; ++i) {
        ccl_vec3 q = along(ro, rd, t);
        float eps = precision + f->precision_t * t; /* precision as printed for precision_t = 0 */
        float d;
        if (rd.y >= 0.0f && q.y - f->hmax > eps) { /* above the slab, rising: no hit ahead */
            *out_t = t;
            *out_steps = i;
            return 0;
        }
        d = map(f, q);
        t += step_scale * d;
        if (d < eps) {
            *out_t = t;
            *out_steps = i + 1;
            return 1;
        }
        if (t > max_t) {
            *out_t = t;
            *out_steps = i + 1;
            return 0;
        }
    }
    *out_t = t;
    *out_steps = max_steps;
    return 0;
}

static int32_t march_bisect(const heightfield *f, ccl_vec3 ro, ccl_vec3 rd, float max_t, float precision,
                            int32_t max_steps, float step_scale, float threshold, int32_t bisect_steps, float *out_t,
                            int *out_steps)
{
    float t = slab_entry(f, ro, rd, precision);
    int32_t steps = 0;
    int32_t i, k;
    for (i = 0; i < max_steps; ++i) {
        ccl_vec3 q = along(ro, rd, t);
        float d;
        if (rd.y >= 0.0f && q.y - f->hmax > precision) break; /* above the slab, rising: no hit ahead */
        d = map(f, q);
        steps += 1;
        if (d < precision) {
            *out_t = t;
            *out_steps = steps;
            return 1;
        }
        if (d < threshold) {
            float tb = t + threshold;
            float db = map(f, along(ro, rd, tb));
            steps += 1;
            if (db < precision) {
                float ta = t;
                for (k = 0; k < bisect_steps; ++k) {
                    float tm = 0.5f * (ta + tb);
                    float dm = map(f, along(ro, rd, tm));
                    steps += 1;
                    if (dm < precision) {
                        tb = tm;
                    } else {
                        ta = tm;
                    }
                }
                *out_t = tb;
                *out_steps = steps;
                return 1;
            }
            t = tb;
        } else {
            t += step_scale * d;
        }
        if (t > max_t) {
            *out_t = t;
            *out_steps = steps;
            return 0;
        }
    }
    *out_t = t;
    *out_steps = steps;
    return 0;
}

static float shadow_hard(const heightfield *f, ccl_vec3 ro, ccl_vec3 rd, float t0, float max_t, float precision,
                         int32_t max_steps, float min_step)
{
    float t = t0;
    int32_t i;
    for (i = 0; i < max_steps; ++i) {
        ccl_vec3 q = along(ro, rd, t);
        float d;
        if (rd.y >= 0.0f && q.y - f->hmax > precision) break; /* above the slab, rising: lit */
        d = map(f, q);
        if (d < precision) return 0.0f;
        if (t > max_t) break;
        t += d > min_step ? d : min_step; /* min_step 0: t += d (d >= precision > 0 here) */
    }
    return 1.0f;
}

static float shadow_soft(const heightfield *f, ccl_vec3 ro, ccl_vec3 rd, float t0, float k, float max_t,
                         float precision, int32_t max_steps, float min_step)
{
    float shadow = 1.0f;
    float t = t0;
    int32_t i;
    for (i = 0; i < max_steps; ++i) {
        ccl_vec3 q = along(ro, rd, t);
        float d, s;
        /* above the slab, rising: every later k d / t >= k (y - hmax) / t, which grows with t for an origin at or
         * below hmax; once that bound reaches the running minimum nothing ahead can lower it */
        if (rd.y >= 0.0f && ro.y <= f->hmax && q.y - f->hmax > precision && k * (q.y - f->hmax) / t >= shadow) break;
        d = map(f, q);
        if (d < precision) return 0.0f;
        if (t > max_t) break;
        s = k * d / t;
        if (s < shadow) shadow = s;
        t += d > min_step ? d : min_step; /* min_step 0: t += d (d >= precision > 0 here) */
    }
    return shadow;
}

static ccl_vec3 normal(const heightfield *f, ccl_vec3 p, float h, ccl_vec3 *out_g)
{
    ccl_vec3 g;
    g.x = (p.y - height(f, p.x + h, p.z)) - (p.y - height(f, p.x - h, p.z));
    g.y = ((p.y + h) - height(f, p.x, p.z)) - ((p.y - h) - height(f, p.x, p.z));
    g.z = (p.y - height(f, p.x, p.z + h)) - (p.y - height(f, p.x, p.z - h));
    if (out_g != NULL) *out_g = g;
    return ccl_vec3_normalize(g);
}

/* ---- public element-wise functions ------------------------------------------------------------------------------- */

ccl_vec2 ccl_terrain_pixel_position(float frag_x, float frag_y, float width, float height_px)
{
    ccl_vec2 p;
    p.x = (frag_x / width) * 2.0f - 1.0f;
    p.y = (frag_y / height_px) * 2.0f - 1.0f;
    p.x = p.x * (width / height_px);
    return p;
}

float ccl_terrain_height_perm(float x, float z, int32_t octaves, float height_scale, float horizontal_scale,
                              const uint8_t *perm, int32_t heightmap)
{
    heightfield f = field_of(octaves, height_scale, horizontal_scale, perm, heightmap);
    return height(&f, x, z);
}

int32_t ccl_terrain_march_fixed(ccl_vec3 ro, ccl_vec3 rd, float max_t, float step_size, float precision,
                                int32_t octaves, float height_scale, float horizontal_scale, uint32_t seed,
                                int32_t heightmap, float *out_t, int *out_steps)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    heightfield f;
    CCL_REQUIRE(step_size > 0.0f);
    ccl_noise_perm_table(seed, perm);
    f = field_of(octaves, height_scale, horizontal_scale, perm, heightmap);
    return march_fixed(&f, ro, rd, max_t, step_size, precision, out_t, out_steps);
}

int32_t ccl_terrain_march_dynamic(ccl_vec3 ro, ccl_vec3 rd, float max_t, float precision, int32_t max_steps,
                                  float step_scale, int32_t octaves, float height_scale, float horizontal_scale,
                                  uint32_t seed, int32_t heightmap, float *out_t, int *out_steps)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    heightfield f;
    ccl_noise_perm_table(seed, perm);
    f = field_of(octaves, height_scale, horizontal_scale, perm, heightmap);
    return march_dynamic(&f, ro, rd, max_t, precision, max_steps, step_scale, out_t, out_steps);
}

int32_t ccl_terrain_march_bisect(ccl_vec3 ro, ccl_vec3 rd, float max_t, float precision, int32_t max_steps,
                                 float step_scale, float threshold, int32_t bisect_steps, int32_t octaves,
                                 float height_scale, float horizontal_scale, uint32_t seed, int32_t heightmap,
                                 float *out_t, int *out_steps)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    heightfield f;
    ccl_noise_perm_table(seed, perm);
    f = field_of(octaves, height_scale, horizontal_scale, perm, heightmap);
    return march_bisect(&f, ro, rd, max_t, precision, max_steps, step_scale, threshold, bisect_steps, out_t,
                        out_steps);
}

float ccl_terrain_shadow_hard(ccl_vec3 ro, ccl_vec3 rd, float t0, float max_t, float precision, int32_t max_steps,
                              int32_t octaves, float height_scale, float horizontal_scale, uint32_t seed,
                              int32_t heightmap)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    heightfield f;
    ccl_noise_perm_table(seed, perm);
    f = field_of(octaves, height_scale, horizontal_scale, perm, heightmap);
    return shadow_hard(&f, ro, rd, t0, max_t, precision, max_steps, 0.0f);
}

float ccl_terrain_shadow_soft(ccl_vec3 ro, ccl_vec3 rd, float t0, float k, float max_t, float precision,
                              int32_t max_steps, int32_t octaves, float height_scale, float horizontal_scale,
                              uint32_t seed, int32_t heightmap)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    heightfield f;
    ccl_noise_perm_table(seed, perm);
    f = field_of(octaves, height_scale, horizontal_scale, perm, heightmap);
    return shadow_soft(&f, ro, rd, t0, k, max_t, precision, max_steps, 0.0f);
}

ccl_vec3 ccl_terrain_lighting(ccl_vec3 n, ccl_vec3 l, float la, ccl_vec3 ca, float ld, ccl_vec3 cd, float shadow)
{
    float ndl = ccl_vec3_dot(n, l);
    float diffuse;
    if (ndl < 0.0f) ndl = 0.0f;
    diffuse = ld * ndl * shadow;
    return v3(ca.x * la + cd.x * diffuse, ca.y * la + cd.y * diffuse, ca.z * la + cd.z * diffuse);
}

ccl_vec3 ccl_terrain_normal(ccl_vec3 p, float h, int32_t octaves, float height_scale, float horizontal_scale,
                            uint32_t seed, int32_t heightmap, ccl_vec3 *out_g)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    heightfield f;
    ccl_noise_perm_table(seed, perm);
    f = field_of(octaves, height_scale, horizontal_scale, perm, heightmap);
    return normal(&f, p, h, out_g);
}

int32_t ccl_terrain_normal_octaves(float t, int32_t octaves_max, int32_t octaves_min, float lod_distance)
{
    int32_t n = octaves_max;
    float d = lod_distance;
    while (n > octaves_min && t > d) {
        n -= 1;
        d = d * 2.0f;
    }
    return n;
}

float ccl_terrain_fog(float d, float rho, ccl_variant variant)
{
    float f;
    if (variant == CCL_VARIANT_THESIS) {
        f = expf(rho * d) - 1.0f;
        if (f > 1.0f) f = 1.0f;
        return f;
    }
    return 1.0f - expf(-(rho * d));
}

ccl_vec3 ccl_terrain_sky(ccl_vec3 rd, ccl_vec3 sun, ccl_vec3 sky_colour, ccl_vec3 sun_colour, float power)
{
    float sun_dot = ccl_vec3_dot(rd, sun);
    float g;
    if (!(sun_dot > 0.0f)) sun_dot = 0.0f;
    /* the dot of two unit vectors can round to 1 + 2^-23; its power then overflows for power above ~7e8: clamp to 1 */
    if (sun_dot > 1.0f) sun_dot = 1.0f;
    g = powf(sun_dot, power);
    return v3(sky_colour.x + sun_colour.x * g, sky_colour.y + sun_colour.y * g, sky_colour.z + sun_colour.z * g);
}

/* largest fBm coordinate of the clouds: the top one of their 4 octaves, 2^3 times it, stays finite */
#define CLOUD_COORD_MAX (FLT_MAX / 8.0f)

static ccl_vec3 clouds_perm(ccl_vec3 colour, ccl_vec3 ro, ccl_vec3 rd, float cloud_height, ccl_vec2 wind, float time,
                            float cloud_scale, ccl_vec3 cloud_colour, const uint8_t *perm, int32_t variant)
{
    float t, qx, qz, u, v, f, w;
    if (!(rd.y != 0.0f)) return colour;
    t = (cloud_height - ro.y) / rd.y;
    if (variant != CCL_VARIANT_THESIS && !(t > 0.0f)) return colour;
    /* a plane point beyond the floats (t overflows for |rd.y| below ~1e-36 |cloud_height - ro.y|, the fBm's top
     * octave coordinate 8 q.xz / cloud_scale soon after) has no fBm value: the weight f rd.y takes its limit there, 0,
     * as for rd.y == 0 (the fBm is bounded). NaN passes on. */
    if (isinf(t)) return colour;
    qx = ro.x + rd.x * t + wind.x * time;
    qz = ro.z + rd.z * t + wind.y * time;
    u = qx / cloud_scale;
    v = qz / cloud_scale;
    if (fabsf(u) > CLOUD_COORD_MAX || fabsf(v) > CLOUD_COORD_MAX) return colour;
    f = fbm_perm(u, v, 4, perm);
    w = clamp01(f * rd.y);
    return mix3(colour, cloud_colour, w);
}

ccl_vec3 ccl_terrain_clouds(ccl_vec3 colour, ccl_vec3 ro, ccl_vec3 rd, float cloud_height, ccl_vec2 wind, float time,
                            float cloud_scale, ccl_vec3 cloud_colour, uint32_t seed, ccl_variant variant)
{
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    ccl_noise_perm_table(seed, perm);
    return clouds_perm(colour, ro, rd, cloud_height, wind, time, cloud_scale, cloud_colour, perm, (int32_t)variant);
}

float ccl_terrain_water_weight(ccl_vec3 v, ccl_vec3 n, float kappa)
{
    /* |v . n| of unit vectors rounds up to 1 + 2^-22 (f = 1.0000236 for kappa 98.8, fuzz finding I3): at most 1 */
    const float c = fabsf(ccl_vec3_dot(v, n));
    return powf(c > 1.0f ? 1.0f : c, kappa);
}

ccl_vec3 ccl_terrain_water_normal_perm(float x, float z, float time, float wave_scale, float wave_strength,
                                       const uint8_t *perm)
{
    float u = x / wave_scale;
    float v = z / wave_scale;
    float a = ccl_noise_perlin2_perm(u + 0.5f * time, v - 0.3f * time, perm, 0, CCL_INTERP_QUINTIC) +
              0.5f * sinf(3.0f * u + 2.0f * time);
    float b = ccl_noise_perlin2_perm(u - 0.4f * time + 37.2f, v + 0.2f * time + 11.7f, perm, 0, CCL_INTERP_QUINTIC) +
              0.5f * sinf(3.0f * v + 1.7f * time);
    return ccl_vec3_normalize(v3(-(wave_strength * a), 1.0f, -(wave_strength * b)));
}

/* ---- the scene ----------------------------------------------------------------------------------------------------- */

void ccl_terrain_params_default(ccl_terrain_params *out)
{
    ccl_terrain_params p;
    if (out == NULL) return;
    memset(&p, 0, sizeof p);
    p.heightmap = CCL_TERRAIN_FBM;
    p.seed = 0u;
    p.march_octaves = 4;
    p.height_scale = 12.0f;
    p.horizontal_scale = 24.0f;
    p.march_method = CCL_TERRAIN_MARCH_BISECT;
    p.max_t = 400.0f;
    p.step_size = 0.1f;
    p.precision = 0.01f;
    p.max_steps = 300;
    p.step_scale = 0.8f;
    p.bisect_threshold = 0.25f;
    p.bisect_steps = 6;
    p.slab = 1;
    p.precision_per_unit = 0.0f;
    p.normal_h = 0.002f;
    p.normal_octaves_max = 9;
    p.normal_octaves_min = 4;
    p.lod_distance = 15.0f;
    p.shadows = CCL_TERRAIN_SHADOWS_SOFT;
    p.shadow_t0_hard = 0.2f;
    p.shadow_t0_soft = 0.02f;
    p.shadow_k = 4.0f;
    p.shadow_max_t = 80.0f;
    p.shadow_bias = 0.02f;
    p.shadow_min_step = 1.0f;
    p.sun = v3(0.0f, 1.0f, 0.0f); /* overwritten by the settings (elevation, azimuth) */
    p.light_ambient = 0.35f;
    p.light_diffuse = 1.0f;
    p.stage = CCL_TERRAIN_STAGE_FINAL;
    p.colour_rock = v3(0.42f, 0.38f, 0.35f);
    p.colour_low = v3(0.62f, 0.55f, 0.42f);
    p.colour_grass = v3(0.24f, 0.40f, 0.13f);
    p.material_low = -6.0f;
    p.material_high = 10.0f;
    p.grass_min_normal_y = 0.85f;
    p.grass_band = 0.08f;
    p.fog_variant = CCL_VARIANT_THESIS;
    p.fog_density = 0.0018f;
    p.sky_colour = v3(0.45f, 0.62f, 0.85f);
    p.sun_colour = v3(1.0f, 0.8f, 0.55f);
    p.sun_power = 80.0f;
    p.cloud_variant = CCL_VARIANT_CORRECTED;
    p.cloud_height = 250.0f;
    p.cloud_scale = 150.0f;
    p.wind.x = 6.0f;
    p.wind.y = 3.0f;
    p.time = 0.0f;
    p.cloud_colour = v3(1.0f, 1.0f, 1.0f);
    p.water_level = -5.0f;
    p.water_kappa = 3.0f;
    p.wave_scale = 2.0f;
    p.wave_strength = 0.08f;
    p.water_tint = v3(0.55f, 0.75f, 0.8f);
    p.samples_per_axis = 1;
    ccl_noise_perm_table(p.seed, p.perm);
    *out = p;
}

static int in_range(float v, float lo, float hi)
{
    return v >= lo && v <= hi;
}

static int vec_finite(ccl_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static int colour_ok(ccl_vec3 c)
{
    return in_range(c.x, 0.0f, 100.0f) && in_range(c.y, 0.0f, 100.0f) && in_range(c.z, 0.0f, 100.0f);
}

ccl_status ccl_terrain_params_check(ccl_terrain_params *p, const char **out_field)
{
    const char *bad = NULL;
    if (p == NULL) {
        if (out_field != NULL) *out_field = "params";
        return CCL_EINVAL;
    }
#define CCL_TERRAIN_BAD(cond, name) if (bad == NULL && (cond)) bad = name
    CCL_TERRAIN_BAD(p->heightmap != CCL_TERRAIN_TEST && p->heightmap != CCL_TERRAIN_FBM, "heightmap");
    CCL_TERRAIN_BAD(p->march_octaves < 1 || p->march_octaves > 16, "march_octaves");
    CCL_TERRAIN_BAD(!in_range(p->height_scale, 0.0f, 1000.0f), "height_scale");
    /* the three noise scales (units per noise unit) >= CCL_TERRAIN_MIN_SCALE: a tiny one (1.02e-38) overflowed
     * x / scale to Inf and the shade to NaN */
    CCL_TERRAIN_BAD(!in_range(p->horizontal_scale, CCL_TERRAIN_MIN_SCALE, 10000.0f), "horizontal_scale");
    CCL_TERRAIN_BAD(p->march_method < 0 || p->march_method > 2, "march_method");
    CCL_TERRAIN_BAD(!(p->max_t > 0.0f && p->max_t <= 10000.0f), "max_t");
    CCL_TERRAIN_BAD(!in_range(p->step_size, 0.015625f, 100.0f), "step_size");
    CCL_TERRAIN_BAD(!(p->precision > 0.0f && p->precision <= 10.0f), "precision");
    CCL_TERRAIN_BAD(p->max_steps < 1 || p->max_steps > 100000, "max_steps");
    CCL_TERRAIN_BAD(!(p->step_scale > 0.0f && p->step_scale <= 1.0f), "step_scale");
    CCL_TERRAIN_BAD(!(p->bisect_threshold > 0.0f && p->bisect_threshold <= 100.0f), "bisect_threshold");
    CCL_TERRAIN_BAD(p->bisect_steps < 0 || p->bisect_steps > 64, "bisect_steps");
    CCL_TERRAIN_BAD(p->slab != 0 && p->slab != 1, "slab");
    CCL_TERRAIN_BAD(!(p->precision_per_unit >= 0.0f && p->precision_per_unit <= 1.0f), "precision_per_unit");
    CCL_TERRAIN_BAD(!(p->normal_h > 0.0f && p->normal_h <= 1.0f), "normal_h");
    CCL_TERRAIN_BAD(p->normal_octaves_max < 1 || p->normal_octaves_max > 16, "normal_octaves_max");
    CCL_TERRAIN_BAD(p->normal_octaves_min < 1 || p->normal_octaves_min > p->normal_octaves_max,
                    "normal_octaves_min");
    CCL_TERRAIN_BAD(!(p->lod_distance > 0.0f && p->lod_distance <= 10000.0f), "lod_distance");
    CCL_TERRAIN_BAD(p->shadows < 0 || p->shadows > 2, "shadows");
    CCL_TERRAIN_BAD(!in_range(p->shadow_t0_hard, 0.0f, 100.0f), "shadow_t0_hard");
    CCL_TERRAIN_BAD(!(p->shadow_t0_soft > 0.0f && p->shadow_t0_soft <= 100.0f), "shadow_t0_soft");
    CCL_TERRAIN_BAD(!(p->shadow_k > 0.0f && p->shadow_k <= 1000.0f), "shadow_k");
    CCL_TERRAIN_BAD(!(p->shadow_max_t > 0.0f && p->shadow_max_t <= 10000.0f), "shadow_max_t");
    CCL_TERRAIN_BAD(!in_range(p->shadow_bias, 0.0f, 10.0f), "shadow_bias");
    CCL_TERRAIN_BAD(!in_range(p->shadow_min_step, 0.0f, 100.0f), "shadow_min_step");
    CCL_TERRAIN_BAD(!vec_finite(p->sun) || fabsf(ccl_vec3_length(p->sun) - 1.0f) > 1e-3f, "sun");
    CCL_TERRAIN_BAD(!in_range(p->light_ambient, 0.0f, 100.0f), "light_ambient");
    CCL_TERRAIN_BAD(!in_range(p->light_diffuse, 0.0f, 100.0f), "light_diffuse");
    CCL_TERRAIN_BAD(p->stage < 0 || p->stage > 3, "stage");
    CCL_TERRAIN_BAD(!colour_ok(p->colour_rock), "colour_rock");
    CCL_TERRAIN_BAD(!colour_ok(p->colour_low), "colour_low");
    CCL_TERRAIN_BAD(!colour_ok(p->colour_grass), "colour_grass");
    CCL_TERRAIN_BAD(!in_range(p->material_low, -10000.0f, 10000.0f), "material_low");
    CCL_TERRAIN_BAD(!(p->material_high > p->material_low && p->material_high <= 10000.0f), "material_high");
    CCL_TERRAIN_BAD(!in_range(p->grass_min_normal_y, 0.0f, 1.0f), "grass_min_normal_y");
    CCL_TERRAIN_BAD(!(p->grass_band > 0.0f && p->grass_band <= 1.0f), "grass_band");
    CCL_TERRAIN_BAD(p->fog_variant != CCL_VARIANT_CORRECTED && p->fog_variant != CCL_VARIANT_THESIS, "fog_variant");
    CCL_TERRAIN_BAD(!(p->fog_density > 0.0f && p->fog_density <= 100.0f), "fog_density");
    CCL_TERRAIN_BAD(!colour_ok(p->sky_colour), "sky_colour");
    CCL_TERRAIN_BAD(!colour_ok(p->sun_colour), "sun_colour");
    CCL_TERRAIN_BAD(!(p->sun_power > 0.0f && p->sun_power <= 10000.0f), "sun_power");
    CCL_TERRAIN_BAD(p->cloud_variant != CCL_VARIANT_CORRECTED && p->cloud_variant != CCL_VARIANT_THESIS,
                    "cloud_variant");
    CCL_TERRAIN_BAD(!in_range(p->cloud_height, -10000.0f, 10000.0f), "cloud_height");
    CCL_TERRAIN_BAD(!in_range(p->cloud_scale, CCL_TERRAIN_MIN_SCALE, 1e6f), "cloud_scale");
    CCL_TERRAIN_BAD(!in_range(p->wind.x, -1000.0f, 1000.0f) || !in_range(p->wind.y, -1000.0f, 1000.0f), "wind");
    CCL_TERRAIN_BAD(!in_range(p->time, 0.0f, 1e6f), "time");
    CCL_TERRAIN_BAD(!colour_ok(p->cloud_colour), "cloud_colour");
    CCL_TERRAIN_BAD(!in_range(p->water_level, -10000.0f, 10000.0f), "water_level");
    CCL_TERRAIN_BAD(!(p->water_kappa > 0.0f && p->water_kappa <= 100.0f), "water_kappa");
    CCL_TERRAIN_BAD(!in_range(p->wave_scale, CCL_TERRAIN_MIN_SCALE, 1e4f), "wave_scale");
    CCL_TERRAIN_BAD(!in_range(p->wave_strength, 0.0f, 10.0f), "wave_strength");
    CCL_TERRAIN_BAD(!colour_ok(p->water_tint), "water_tint");
    CCL_TERRAIN_BAD(p->samples_per_axis < 1 || p->samples_per_axis > 8, "samples_per_axis");
#undef CCL_TERRAIN_BAD
    if (bad != NULL) {
        if (out_field != NULL) *out_field = bad;
        return CCL_EINVAL;
    }
    ccl_noise_perm_table(p->seed, p->perm);
    return CCL_OK;
}

static heightfield march_field(const ccl_terrain_params *p)
{
    heightfield f = field_of(p->march_octaves, p->height_scale, p->horizontal_scale, p->perm, p->heightmap);
    if (p->slab) {
        /* |fbm| <= sum_i 0.5^i = 2 (1 - 0.5^octaves) for |noise| <= 1 (exact in float: a sum of powers of 2) */
        float bound = 0.0f, a = 1.0f;
        int32_t i;
        for (i = 0; i < p->march_octaves; ++i) {
            bound += a;
            a *= 0.5f;
        }
        f.hmax = p->heightmap == CCL_TERRAIN_TEST ? 10.0f : p->height_scale * bound;
    }
    f.precision_t = p->precision_per_unit;
    return f;
}

/* the lit terrain colour at the hit point pos, t along the view ray (stages a-c; pt-alg-7.3-material) */
static ccl_vec3 terrain_colour(const ccl_terrain_params *p, ccl_vec3 pos, float t)
{
    heightfield fm = march_field(p);
    heightfield fn = fm;
    ccl_vec3 n, c, origin;
    float shadow = 1.0f;
    fn.octaves = ccl_terrain_normal_octaves(t, p->normal_octaves_max, p->normal_octaves_min, p->lod_distance);
    n = normal(&fn, pos, p->normal_h, NULL);
    c = p->colour_rock;
    if (p->stage >= CCL_TERRAIN_STAGE_MATERIALS) {
        c = mix3(p->colour_low, p->colour_rock, smoothstep(p->material_low, p->material_high, pos.y));
    }
    if (p->stage >= CCL_TERRAIN_STAGE_ATMOSPHERE) {
        c = mix3(c, p->colour_grass, smoothstep(p->grass_min_normal_y, p->grass_min_normal_y + p->grass_band, n.y));
    }
    if (p->shadows != CCL_TERRAIN_SHADOWS_NONE) {
        origin = v3(pos.x, height(&fm, pos.x, pos.z) + p->shadow_bias, pos.z);
        if (p->shadows == CCL_TERRAIN_SHADOWS_HARD) {
            shadow = shadow_hard(&fm, origin, p->sun, p->shadow_t0_hard, p->shadow_max_t, p->precision,
                                 p->max_steps, p->shadow_min_step);
        } else {
            shadow = shadow_soft(&fm, origin, p->sun, p->shadow_t0_soft, p->shadow_k, p->shadow_max_t,
                                 p->precision, p->max_steps, p->shadow_min_step);
        }
    }
    return ccl_terrain_lighting(n, p->sun, p->light_ambient, c, p->light_diffuse, c, shadow);
}

ccl_vec3 ccl_terrain_shade(const ccl_terrain_params *p, ccl_vec3 ro, ccl_vec3 rd, int *out_steps)
{
    heightfield fm = march_field(p);
    float t = 0.0f, dist;
    int steps = 0;
    int32_t hit;
    ccl_vec3 sky, background, colour, pos;
    if (p->march_method == CCL_TERRAIN_MARCH_FIXED) {
        hit = march_fixed(&fm, ro, rd, p->max_t, p->step_size, p->precision, &t, &steps);
    } else if (p->march_method == CCL_TERRAIN_MARCH_BISECT) {
        hit = march_bisect(&fm, ro, rd, p->max_t, p->precision, p->max_steps, p->step_scale, p->bisect_threshold,
                           p->bisect_steps, &t, &steps);
    } else {
        hit = march_dynamic(&fm, ro, rd, p->max_t, p->precision, p->max_steps, p->step_scale, &t, &steps);
    }
    if (out_steps != NULL) *out_steps = steps;
    sky = ccl_terrain_sky(rd, p->sun, p->sky_colour, p->sun_colour, p->sun_power);
    background = sky;
    if (p->stage >= CCL_TERRAIN_STAGE_ATMOSPHERE) {
        background = clouds_perm(sky, ro, rd, p->cloud_height, p->wind, p->time, p->cloud_scale, p->cloud_colour,
                                 p->perm, p->cloud_variant);
    }
    if (!hit) return background;
    pos = along(ro, rd, t);
    colour = terrain_colour(p, pos, t);
    dist = t;
    if (p->stage >= CCL_TERRAIN_STAGE_FINAL && pos.y < p->water_level && rd.y < 0.0f && ro.y > p->water_level) {
        /* pt-alg-7.3.4: the water plane in front of the underwater terrain */
        float tw = (p->water_level - ro.y) / rd.y;
        ccl_vec3 wpos = along(ro, rd, tw);
        ccl_vec3 n = ccl_terrain_water_normal_perm(wpos.x, wpos.z, p->time, p->wave_scale, p->wave_strength, p->perm);
        float rdn = 2.0f * ccl_vec3_dot(rd, n);
        ccl_vec3 r = v3(rd.x - n.x * rdn, rd.y - n.y * rdn, rd.z - n.z * rdn);
        ccl_vec3 reflected, under;
        float f;
        if (r.y < 0.0f) r.y = -r.y; /* a wave normal tilted past the view ray: keep the reflection in the sky */
        reflected = ccl_terrain_sky(r, p->sun, p->sky_colour, p->sun_colour, p->sun_power);
        reflected = clouds_perm(reflected, wpos, r, p->cloud_height, p->wind, p->time, p->cloud_scale,
                                p->cloud_colour, p->perm, p->cloud_variant);
        f = ccl_terrain_water_weight(rd, n, p->water_kappa);
        under = v3(colour.x * p->water_tint.x, colour.y * p->water_tint.y, colour.z * p->water_tint.z);
        colour = mix3(reflected, under, f);
        dist = tw;
    }
    if (p->stage >= CCL_TERRAIN_STAGE_ATMOSPHERE) {
        colour = mix3(colour, sky, ccl_terrain_fog(dist, p->fog_density, (ccl_variant)p->fog_variant));
    }
    return colour;
}

void ccl_terrain_pixel(const ccl_terrain_params *p, const float inv_view_proj_rot[16], ccl_vec3 eye, int x, int y,
                       int width, int height_px, float *out_rgb, int *out_steps)
{
    const float *m = inv_view_proj_rot;
    int32_t n = p->samples_per_axis;
    int32_t i, j, steps = 0;
    float ax = 0.0f, ay = 0.0f, az = 0.0f, inv;
    for (j = 0; j < n; ++j) {
        for (i = 0; i < n; ++i) {
            /* ccl_camera_ray with the sub-pixel offset ((i + 0.5) / n, (j + 0.5) / n) instead of (0.5, 0.5) */
            float ox = ((float)i + 0.5f) / (float)n;
            float oy = ((float)j + 0.5f) / (float)n;
            float u = ((float)x + ox) / (float)width;
            float v = ((float)y + oy) / (float)height_px;
            float nx = 2.0f * u - 1.0f;
            float ny = 1.0f - 2.0f * v;
            ccl_vec3 rd = ccl_vec3_normalize(v3(m[0] * nx + m[4] * ny + m[8] + m[12],
                                                m[1] * nx + m[5] * ny + m[9] + m[13],
                                                m[2] * nx + m[6] * ny + m[10] + m[14]));
            int s = 0;
            ccl_vec3 c = ccl_terrain_shade(p, eye, rd, &s);
            steps += s;
            ax += clamp01(c.x);
            ay += clamp01(c.y);
            az += clamp01(c.z);
        }
    }
    inv = (float)(n * n);
    out_rgb[0] = ax / inv;
    out_rgb[1] = ay / inv;
    out_rgb[2] = az / inv;
    if (out_steps != NULL) *out_steps = steps;
}
