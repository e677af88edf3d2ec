/* Fuzz harness: the flight scene's cloud volumes (cclouds/volume.h): ccl_volume_check, ccl_volume_light,
 * ccl_volume_occupancy, ccl_volume_skip and ccl_volume_pixel on tiny grids (edges in [-1, 4], buffers for 4^3),
 * default parameters with a few fields overwritten by decoded values. Contract: check gives CCL_OK or CCL_EINVAL
 * with a field name; light/occupancy/skip give CCL_EINVAL for a bad grid or length and write nothing then; after
 * CCL_OK the light volume is in [0, 1], occupancy in {0, 1}, skip distances consistent with occupancy, and a pixel
 * is finite. Steps below 1/64 voxel are skipped (each light ray takes diagonal / step samples). */
#include "cclouds/volume.h"
#include "fuzz.h"

#define P ccl_volume_params
static const fz_field fields[] = {
    FZ_V3(P, sun), FZ_V3(P, sun_colour), FZ_V3(P, ambient_top), FZ_F(P, ambient_bottom.y), FZ_F(P, sky_zenith.x),
    FZ_F(P, sky_horizon.z), FZ_F(P, ground_a.x), FZ_F(P, sun_glow), FZ_F(P, sun_glow_power), FZ_F(P, field_size),
    FZ_F(P, fog_distance), FZ_F(P, tau_per_voxel), FZ_F(P, light_tau_per_voxel), FZ_F(P, step_voxels),
    FZ_F(P, light_step_voxels), FZ_F(P, exit_transmittance), FZ_I(P, max_steps), FZ_F(P, g), FZ_I(P, jitter),
    FZ_I(P, aircraft), FZ_V3(P, aircraft_position), FZ_F(P, aircraft_forward.x), FZ_F(P, aircraft_up.y),
    FZ_F(P, aircraft_scale)};
#undef P

#define MAXN 4
#define VOX (MAXN * MAXN * MAXN)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    ccl_volume_params p;
    ccl_volume_params_default(&p);
    fz_mutate(r, &p, fields, sizeof fields / sizeof fields[0], 4);
    unsigned char density[VOX], skip[VOX], occ[VOX];
    float light[VOX + 1];
    for (int i = 0; i < VOX; ++i) density[i] = fz_u8(r) < 128 ? 0 : fz_u8(r);
    ccl_volume_grid g;
    memset(&g, 0, sizeof g);
    g.density = density;
    g.nx = fz_range(r, -1, MAXN);
    g.ny = fz_range(r, -1, MAXN);
    g.nz = fz_range(r, -1, MAXN);
    g.origin.x = fz_u8(r) < 200 ? fz_unit(r, -100.0f, 100.0f) : fz_float(r);
    g.origin.y = fz_unit(r, -100.0f, 100.0f);
    g.origin.z = fz_unit(r, -100.0f, 100.0f);
    g.extent.x = fz_u8(r) < 200 ? fz_unit(r, 1.0f, 100.0f) : fz_float(r);
    g.extent.y = fz_u8(r) < 230 ? fz_unit(r, 1.0f, 100.0f) : fz_float(r);
    g.extent.z = fz_unit(r, 1.0f, 100.0f);
    int count = fz_u8(r) < 230 ? 1 : fz_i32(r);
    int fast = p.light_step_voxels >= 1.0f / 64 && p.step_voxels >= 1.0f / 64 && p.max_steps <= 4096;

    const char *field = "unset";
    size_t n = g.nx > 0 && g.ny > 0 && g.nz > 0 ? (size_t)g.nx * (size_t)g.ny * (size_t)g.nz : 0;
    size_t nb = n ? (size_t)((g.nx + 1) / 2) * (size_t)((g.ny + 1) / 2) * (size_t)((g.nz + 1) / 2) : 0;
    if (!fast) return 0;
    for (int i = 0; i <= VOX; ++i) light[i] = -5.0f;
    size_t len = fz_u8(r) < 230 ? n : (size_t)fz_range(r, 0, VOX);
    ccl_status ls = ccl_volume_light(&p, &g, light, len);
    if (ls != CCL_OK) {
        for (int i = 0; i <= VOX; ++i) FZ_CHECK(light[i] == -5.0f, "light written on an error");
    } else {
        FZ_CHECK(len == n && n > 0, "light accepted length %zu of %zu", len, n);
        /* every accepted extent (README.md, finding 5: bounded to [1e-6, 1e6] m by the check) */
        for (size_t i = 0; i < n; ++i)
            FZ_CHECK(light[i] >= 0.0f && light[i] <= 1.0f, "light[%zu] = %g (grid %d %d %d, origin %g %g %g, extent %g %g %g)",
                     i, (double)light[i], g.nx, g.ny, g.nz, (double)g.origin.x, (double)g.origin.y,
                     (double)g.origin.z, (double)g.extent.x, (double)g.extent.y, (double)g.extent.z);
        FZ_CHECK(light[n] == -5.0f, "light written past out_len");
    }
    g.light = light;
    memset(occ, 77, sizeof occ);
    size_t blen = fz_u8(r) < 230 ? nb : (size_t)fz_range(r, 0, VOX);
    ccl_status os = ccl_volume_occupancy(&g, occ, blen);
    if (os == CCL_OK) {
        FZ_CHECK(blen == nb && nb > 0, "occupancy accepted length %zu of %zu", blen, nb);
        for (size_t i = 0; i < nb; ++i) FZ_CHECK(occ[i] <= 1, "occupancy %d", occ[i]);
        FZ_CHECK(ccl_volume_skip(&g, skip, blen) == CCL_OK, "skip refused what occupancy accepted");
        for (size_t i = 0; i < nb; ++i) FZ_CHECK((skip[i] == 0) == (occ[i] == 1), "skip/occupancy mismatch at %zu", i);
    } else {
        for (size_t i = 0; i < VOX; ++i) FZ_CHECK(occ[i] == 77, "occupancy written on an error");
    }
    if (ls == CCL_OK && os == CCL_OK) {
        g.skip = skip;
        ccl_volume_grid grids[CCL_VOLUME_MAX_GRIDS + 1]; /* a count the check accepts is covered */
        for (int i = 0; i <= CCL_VOLUME_MAX_GRIDS; ++i) grids[i] = g;
        ccl_status st = ccl_volume_check(&p, grids, count, &field);
        FZ_CHECK((st == CCL_OK) == (field == NULL), "check status %d, field %s", (int)st, field ? field : "NULL");
        if (st == CCL_OK) {
            FZ_CHECK(count >= 0 && count <= CCL_VOLUME_MAX_GRIDS, "count %d accepted", count);
            /* any accepted parameters (README.md, findings 5 and 9: the check bounds extents and colours) */
            if (count >= 1 && count <= 2) {
                ccl_camera cam;
                ccl_vec3 eye = {fz_unit(r, -150.0f, 150.0f), fz_unit(r, -150.0f, 150.0f), fz_unit(r, -150.0f, 150.0f)};
                ccl_vec3 target = {0.0f, 0.0f, 0.0f}, up = {0.0f, 1.0f, 0.0f};
                if (ccl_camera_look_at(eye, target, up, 1.0f, 1.5f, 0.1f, 1000.0f, &cam) == CCL_OK) {
                    float rgb[3];
                    ccl_volume_pixel(&p, grids, count, &cam, fz_range(r, 0, 15), fz_range(r, 0, 15), 16, 16, rgb);
                    if (!fz_all_finite(rgb, 3)) {
                        ccl_volume_params def;
                        ccl_volume_params_default(&def);
                        fz_print_changed(&p, &def, fields, sizeof fields / sizeof fields[0]);
                        fprintf(stderr, "  grid %d %d %d origin %g %g %g extent %g %g %g count %d eye %g %g %g\n",
                                g.nx, g.ny, g.nz, (double)g.origin.x, (double)g.origin.y, (double)g.origin.z,
                                (double)g.extent.x, (double)g.extent.y, (double)g.extent.z, count, (double)eye.x,
                                (double)eye.y, (double)eye.z);
                    }
                    FZ_CHECK(fz_all_finite(rgb, 3), "volume pixel not finite");
                }
            }
        }
    }
    return 0;
}
