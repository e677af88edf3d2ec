/* Fuzz harness: the terrain parameters (cclouds/terrain.h): ccl_terrain_params_check on the defaults with a few
 * fields overwritten by decoded values, then one ray through ccl_terrain_shade when the parameters are valid and
 * cheap (at most 256 march and bisection steps, 8 octaves). Contract: CCL_OK or CCL_EINVAL with a field name;
 * CCL_OK fills perm with Perlin's table of the seed and gives a finite colour for any finite unit ray. */
#include "cclouds/noise.h"
#include "cclouds/terrain.h"
#include "fuzz.h"

#define P ccl_terrain_params
static const fz_field fields[] = {
    FZ_I(P, heightmap), FZ_I(P, seed), FZ_I(P, march_octaves), FZ_F(P, height_scale), FZ_F(P, horizontal_scale),
    FZ_I(P, march_method), FZ_F(P, max_t), FZ_F(P, step_size), FZ_F(P, precision), FZ_I(P, max_steps),
    FZ_F(P, step_scale), FZ_F(P, bisect_threshold), FZ_I(P, bisect_steps), FZ_I(P, slab), FZ_F(P, precision_per_unit),
    FZ_F(P, normal_h), FZ_I(P, normal_octaves_max), FZ_I(P, normal_octaves_min), FZ_F(P, lod_distance),
    FZ_I(P, shadows), FZ_F(P, shadow_t0_hard), FZ_F(P, shadow_t0_soft), FZ_F(P, shadow_k), FZ_F(P, shadow_max_t),
    FZ_F(P, shadow_bias), FZ_F(P, shadow_min_step), FZ_V3(P, sun), FZ_F(P, light_ambient), FZ_F(P, light_diffuse),
    FZ_I(P, stage),
    FZ_F(P, colour_rock.x), FZ_F(P, colour_low.y), FZ_F(P, colour_grass.z), FZ_F(P, material_low),
    FZ_F(P, material_high), FZ_F(P, grass_min_normal_y), FZ_F(P, grass_band), FZ_I(P, fog_variant),
    FZ_F(P, fog_density), FZ_F(P, sky_colour.x), FZ_F(P, sun_colour.y), FZ_F(P, sun_power), FZ_I(P, cloud_variant),
    FZ_F(P, cloud_height), FZ_F(P, cloud_scale), FZ_F(P, wind.x), FZ_F(P, time), FZ_F(P, cloud_colour.z),
    FZ_F(P, water_level), FZ_F(P, water_kappa), FZ_F(P, wave_scale), FZ_F(P, wave_strength), FZ_F(P, water_tint.x),
    FZ_I(P, samples_per_axis)};
#undef P

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    ccl_terrain_params p;
    ccl_terrain_params_default(&p);
    p.max_steps = fz_range(r, 1, 256);
    p.march_octaves = fz_range(r, 1, 8);
    fz_mutate(r, &p, fields, sizeof fields / sizeof fields[0], 5);
    const char *field = "unset";
    ccl_status st = ccl_terrain_params_check(&p, &field);
    FZ_CHECK(st == CCL_OK || st == CCL_EINVAL, "status %d", (int)st);
    /* terrain.h documents *out_field for CCL_EINVAL only (texgen.h and voxel.h also set NULL on CCL_OK) */
    if (st != CCL_OK) FZ_CHECK(field != NULL && strcmp(field, "unset") != 0, "CCL_EINVAL without a field name");
    FZ_CHECK(ccl_terrain_params_check(NULL, NULL) == CCL_EINVAL, "NULL params accepted");
    if (st != CCL_OK) return 0;
    uint8_t perm[CCL_NOISE_PERM_SIZE];
    ccl_noise_perm_table(p.seed, perm);
    FZ_CHECK(memcmp(perm, p.perm, sizeof perm) == 0, "perm is not the table of the seed");
    double fixed_steps = (double)p.max_t / (double)p.step_size;
    int cheap = p.max_steps <= 256 && p.bisect_steps <= 16 && p.march_octaves <= 8 && p.normal_octaves_max <= 8 &&
                fixed_steps <= 256.0 && p.samples_per_axis <= 2;
    if (!cheap) return 0;
    ccl_vec3 ro = {fz_unit(r, -100.0f, 100.0f), fz_unit(r, 0.0f, 50.0f), fz_unit(r, -100.0f, 100.0f)};
    ccl_vec3 rd3 = {fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f)};
    if (ccl_vec3_length(rd3) < 1e-3f) rd3.z = -1.0f;
    rd3 = ccl_vec3_normalize(rd3);
    int steps = -1;
    ccl_vec3 c = ccl_terrain_shade(&p, ro, rd3, &steps);
    if (!(isfinite(c.x) && isfinite(c.y) && isfinite(c.z))) {
        ccl_terrain_params def;
        ccl_terrain_params_default(&def);
        fz_print_changed(&p, &def, fields, sizeof fields / sizeof fields[0]);
        fprintf(stderr, "  ro %.9g %.9g %.9g rd %.9g %.9g %.9g -> %g %g %g\n", (double)ro.x, (double)ro.y,
                (double)ro.z, (double)rd3.x, (double)rd3.y, (double)rd3.z, (double)c.x, (double)c.y, (double)c.z);
    }
    FZ_CHECK(isfinite(c.x) && isfinite(c.y) && isfinite(c.z), "shade not finite");
    FZ_CHECK(steps >= 0, "steps %d", steps);
    return 0;
}
