/* Fuzz harness: the optics of one raindrop and the particle system (cclouds/optics.h, rain.h, particles.h), written
 * from the headers (issue 31). Contracts:
 *   Snell: for unit d, n and indices in (0, 10], the refracted ray is unit or (0, 0, 0) with *out_tir = 1, the
 *     reflected ray unit; Fresnel R, R_s, R_p in [0, 1] for cos_i in [0, 1];
 *   the drop: r(theta) > 0 and <= ccl_rain_drop_extent for every theta, linear interpolation in [0.5, 4.5] mm; the
 *     surface normal unit; the terminal speed in [0, 9.23 / slowdown], non-decreasing in the radius (finding I4);
 *   mask texels: exit direction unit or zero, inside 0 or 1, normal unit or zero;
 *   refracted capture coordinates: finite where valid for exits with e.z >= 1e-6 and views with -c.z >= 1e-6;
 *     capture_uv finite for fov_capture >= CCL_PARTICLES_MIN_FOV_CAPTURE; the parallax of a point inside the
 *     background sphere finite (N7);
 *   particles: every parameter set ccl_particles_params_check accepts spawns inside the box (warm: y in
 *     [respawn_y, box_max.y]) with a finite radius and speed >= 0, and steps to finite positions with x, z in the
 *     box; the compositor's pixels are in [0, 1] for a background, capture and opacity in [0, 1]. */
#include "cclouds/optics.h"
#include "cclouds/particles.h"
#include "cclouds/rain.h"
#include "fuzz.h"
#include "fuzz_vec.h"


static ccl_vec3 fz_dir(fz_reader *r) {
    ccl_vec3 d = v3(fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f), fz_unit(r, -1.0f, 1.0f));
    float l = len3(d);
    if (fz_u8(r) < 16) { /* axis-aligned and diagonal directions: exact cancellations */
        static const ccl_vec3 axes[] = {{0.0f, 0.0f, 1.0f}, {0.0f, -1.0f, 0.0f}, {1.0f, 0.0f, 0.0f},
                                        {0.577350318f, 0.577350318f, 0.577350318f}};
        return axes[fz_u8(r) % 4];
    }
    if (!(l > 1e-3f)) return v3(0.0f, 0.0f, 1.0f);
    return v3(d.x / l, d.y / l, d.z / l);
}

static int unit_or_zero(ccl_vec3 v, float tol) {
    const float l = len3(v);
    return (v.x == 0.0f && v.y == 0.0f && v.z == 0.0f) || fabsf(l - 1.0f) <= tol;
}

static float fz_index(fz_reader *r) {
    float n = fz_u8(r) < 200 ? fz_unit(r, 1.0f, 2.0f) : fz_float(r);
    if (!(n > 0.0f && n <= 10.0f)) n = fz_unit(r, 1e-3f, 10.0f);
    return n > 0.0f ? n : 1.0f;
}

static void fuzz_snell_fresnel(fz_reader *r) {
    const ccl_vec3 d = fz_dir(r), n = fz_dir(r);
    const float n1 = fz_index(r), n2 = fz_index(r);
    ccl_vec3 refl;
    int tir = -1;
    const ccl_vec3 t = ccl_optics_snell(d, n, n1, n2, &refl, &tir);
    FZ_CHECK(tir == 0 || tir == 1, "tir %d", tir);
    FZ_CHECK(unit_or_zero(refl, 1e-5f) && len3(refl) > 0.5f, "reflected not unit: |r| = %g", (double)len3(refl));
    if (tir)
        FZ_CHECK(t.x == 0.0f && t.y == 0.0f && t.z == 0.0f, "tir with t = (%g %g %g)", (double)t.x, (double)t.y,
                 (double)t.z);
    else {
        /* unit up to the conditioning of k = 1 - eta^2 (1 - cos_i^2): eta^2 ulps of cos_i^2 (the header's bound) */
        const float eta = n1 / n2;
        FZ_CHECK(fabsf(len3(t) - 1.0f) <= 1e-5f + 8.0f * eta * eta * EPS, "refracted not unit: |t| = %g (n1 %g n2 %g)",
                 (double)len3(t), (double)n1, (double)n2);
    }
    {
        const float cos_i = fz_u8(r) < 32 ? (float)(fz_u8(r) % 2) : fz_unit(r, 0.0f, 1.0f);
        float rs = -1.0f, rp = -1.0f;
        const float R = ccl_optics_fresnel(cos_i, n1, n2, &rs, &rp);
        FZ_CHECK(R >= 0.0f && R <= 1.0f && rs >= 0.0f && rs <= 1.0f && rp >= 0.0f && rp <= 1.0f,
                 "fresnel(%g, %g, %g) = %g (%g, %g)", (double)cos_i, (double)n1, (double)n2, (double)R, (double)rs,
                 (double)rp);
    }
}

static void fuzz_drop(fz_reader *r) {
    const int table = fz_u8(r) < 64;
    static const float rows[] = {0.5f, 1.0f, 3.0f, 4.5f};
    const float a = table ? rows[fz_u8(r) % 4] : fz_unit(r, 0.5f, 4.5f);
    const ccl_rain_interp interp = table ? CCL_RAIN_INTERP_TABLE : CCL_RAIN_INTERP_LINEAR;
    const float theta = fz_u8(r) < 32 ? (fz_bool(r) ? 0.0f : 3.14159265f) : fz_unit(r, 0.0f, 3.14159265f);
    const float rad = ccl_rain_drop_radius(theta, a, interp), ext = ccl_rain_drop_extent(a, interp);
    ccl_vec3 nrm;
    const ccl_vec3 p = ccl_rain_drop_surface(theta, fz_unit(r, -7.0f, 7.0f), a, interp, &nrm);
    FZ_CHECK(rad > 0.0f && isfinite(rad) && rad <= ext, "r(%g) = %g, extent %g (a %g)", (double)theta, (double)rad,
             (double)ext, (double)a);
    FZ_CHECK(fabsf(len3(p) - rad) <= 8.0f * EPS * rad && fabsf(len3(nrm) - 1.0f) <= 1e-5f,
             "surface |p| %g vs r %g, |n| %g", (double)len3(p), (double)rad, (double)len3(nrm));
    {
        const float slow = fz_u8(r) < 128 ? fz_unit(r, 0.015625f, 8.0f) : fz_unit(r, 0.015625f, 1000.0f);
        const float r0 = fz_u8(r) < 200 ? fz_unit(r, 0.0f, 4.5f) : fz_unit(r, 0.0f, 10.0f);
        uint32_t bits;
        memcpy(&bits, &r0, sizeof bits);
        bits += 1u + (fz_u8(r) % 4); /* a few floats up */
        float r1;
        memcpy(&r1, &bits, sizeof r1);
        const float v0 = ccl_rain_terminal_speed(r0, slow), v1 = ccl_rain_terminal_speed(r1, slow);
        FZ_CHECK(v0 >= 0.0f && v0 <= 9.23f / slow * (1.0f + 2.0f * EPS), "speed(%g) = %g", (double)r0, (double)v0);
        FZ_CHECK(v1 >= v0, "terminal speed not monotone: v(%.9g) = %.9g > v(%.9g) = %.9g (slowdown %g)", (double)r0,
                 (double)v0, (double)r1, (double)v1, (double)slow);
    }
    {
        const float u = fz_unit(r, -1.0f, 1.0f), v = fz_unit(r, -1.0f, 1.0f);
        const float deform = fz_unit(r, 0.0f, 1.0f), n_water = fz_unit(r, 1.0f, 2.0f);
        const int method = fz_range(r, 0, 2);
        ccl_vec3 nm;
        int inside = -1;
        const ccl_vec3 e = ccl_rain_mask_texel(u, v, a, deform, n_water, interp, (ccl_rain_mask_method)method, &nm,
                                               &inside);
        FZ_CHECK((inside == 0 || inside == 1) && unit_or_zero(e, 1e-4f) && unit_or_zero(nm, 1e-4f),
                 "mask texel (%g, %g) method %d: e |%g| n |%g| inside %d", (double)u, (double)v, method,
                 (double)len3(e), (double)len3(nm), inside);
    }
}

static void fuzz_capture(fz_reader *r) {
    const ccl_vec3 c = fz_dir(r), e = fz_dir(r);
    const float thf = fz_u8(r) < 128 ? fz_unit(r, 0.015625f, 4.0f) : fz_unit(r, 0.015625f, 100.0f);
    const float aspect = fz_u8(r) < 128 ? fz_unit(r, 0.5f, 2.5f) : fz_unit(r, 0.015625f, 100.0f);
    const int mapping = fz_range(r, 0, 1);
    ccl_vec2 p_o;
    int valid = -1;
    const ccl_vec2 p_c = ccl_rain_refracted_uv(c, e, thf, aspect, (ccl_rain_mapping)mapping, &p_o, &valid);
    FZ_CHECK(valid == 0 || valid == 1, "valid %d", valid);
    if (valid && e.z >= 1e-6f && -c.z >= 1e-6f && mapping == 0)
        FZ_CHECK(isfinite(p_c.x) && isfinite(p_c.y) && isfinite(p_o.x) && isfinite(p_o.y),
                 "refracted uv not finite: (%g %g) (%g %g)", (double)p_c.x, (double)p_c.y, (double)p_o.x,
                 (double)p_o.y);
    {
        ccl_vec2 ndc;
        ndc.x = fz_unit(r, -1.0f, 1.0f);
        ndc.y = fz_unit(r, -1.0f, 1.0f);
        const float fov_view = fz_unit(r, 0.01f, 3.1f), fov_cap = fz_unit(r, CCL_PARTICLES_MIN_FOV_CAPTURE, 3.14159f);
        const ccl_vec2 uv = ccl_particles_capture_uv(ndc, fz_unit(r, 0.1f, 10.0f), fov_view, fov_cap);
        FZ_CHECK(isfinite(uv.x) && isfinite(uv.y), "capture_uv (%g %g) fov %g %g", (double)uv.x, (double)uv.y,
                 (double)fov_view, (double)fov_cap);
    }
    {
        float R = fz_float(r);
        if (!(R > 0.0f && R < INFINITY)) R = 1.0f;
        const float f = fz_unit(r, 0.0f, 0.999f);
        const ccl_vec3 p = v3(R * f * e.x, R * f * e.y, R * f * e.z);
        /* inside the sphere, decided in double (|p|^2 underflows in float for denormal components) */
        if ((double)p.x * p.x + (double)p.y * p.y + (double)p.z * p.z < (double)R * R) {
            const float ang = ccl_rain_capture_parallax(p, fz_dir(r), R);
            FZ_CHECK(isfinite(ang), "parallax NaN for |p| %g < R %g", (double)len3(p), (double)R);
        }
    }
}

static const fz_field PARTICLE_FIELDS[] = {
    FZ_V3(ccl_particles_params, box_min),     FZ_V3(ccl_particles_params, box_max),
    FZ_F(ccl_particles_params, respawn_y),    FZ_F(ccl_particles_params, size_mean_mm),
    FZ_F(ccl_particles_params, size_spread_mm), FZ_I(ccl_particles_params, size_samples),
    FZ_F(ccl_particles_params, slowdown),     FZ_F(ccl_particles_params, metres_per_unit),
    FZ_V3(ccl_particles_params, wind),        FZ_I(ccl_particles_params, seed),
};

static void fuzz_particles(fz_reader *r) {
    ccl_particles_params p;
    const char *field = NULL;
    ccl_particles_params_default(&p);
    fz_mutate(r, &p, PARTICLE_FIELDS, sizeof PARTICLE_FIELDS / sizeof PARTICLE_FIELDS[0], 4);
    if (ccl_particles_params_check(&p, &field) != CCL_OK) {
        FZ_CHECK(field != NULL, "refusal without a field");
        return;
    }
    const uint32_t index = fz_u32(r), gen = fz_u32(r);
    const int warm = fz_bool(r);
    ccl_vec3 pos;
    float radius, speed;
    ccl_particles_spawn(&p, index, gen, warm, &pos, &radius, &speed);
    const float ylo = warm ? p.respawn_y : p.box_min.y;
    FZ_CHECK(pos.x >= p.box_min.x && pos.x <= p.box_max.x && pos.y >= ylo && pos.y <= p.box_max.y &&
                 pos.z >= p.box_min.z && pos.z <= p.box_max.z,
             "spawned outside the box: (%g %g %g)", (double)pos.x, (double)pos.y, (double)pos.z);
    FZ_CHECK(isfinite(radius) && isfinite(speed) && speed >= 0.0f, "radius %g speed %g", (double)radius,
             (double)speed);
    {
        /* dt within the documented bound: |wind| dt <= the box width */
        float dt = fz_unit(r, 0.0f, 1.0f);
        const float wx = p.box_max.x - p.box_min.x, wz = p.box_max.z - p.box_min.z;
        if (fabsf(p.wind.x) * dt > wx) dt = wx / fabsf(p.wind.x);
        if (fabsf(p.wind.z) * dt > wz) dt = fminf(dt, wz / fabsf(p.wind.z));
        uint32_t g = gen;
        for (int k = 0; k < 3; ++k) ccl_particles_step(&p, index, dt, &pos, &radius, &speed, &g);
        FZ_CHECK(isfinite(pos.x) && isfinite(pos.y) && isfinite(pos.z) && isfinite(speed),
                 "stepped particle not finite: (%g %g %g) speed %g", (double)pos.x, (double)pos.y, (double)pos.z,
                 (double)speed);
        FZ_CHECK(pos.x >= p.box_min.x && pos.x <= p.box_max.x && pos.z >= p.box_min.z && pos.z <= p.box_max.z,
                 "stepped out of the box in x/z: (%g %g %g)", (double)pos.x, (double)pos.y, (double)pos.z);
    }
}

#define W 6
#define H 5
#define MS 4
#define CS 4

static void fuzz_composite(fz_reader *r) {
    float bg[W * H * 3], mask[MS * MS * 4], cap[CS * CS * 3], out[W * H * 3];
    ccl_particles_sprite sp[3];
    for (int i = 0; i < W * H * 3; ++i) bg[i] = fz_unit(r, 0.0f, 1.0f);
    for (int i = 0; i < CS * CS * 3; ++i) cap[i] = fz_unit(r, 0.0f, 1.0f);
    for (int i = 0; i < MS * MS; ++i) {
        /* exit directions: unit-ish with z > 0 mostly, or anything (the tap reads e.x / e.z) */
        mask[4 * i + 0] = fz_u8(r) < 200 ? fz_unit(r, -1.0f, 1.0f) : fz_float(r);
        mask[4 * i + 1] = fz_u8(r) < 200 ? fz_unit(r, -1.0f, 1.0f) : fz_float(r);
        mask[4 * i + 2] = fz_u8(r) < 200 ? fz_unit(r, 0.0f, 1.0f) : fz_float(r);
        mask[4 * i + 3] = (float)(fz_u8(r) % 2);
    }
    const int n = fz_range(r, 0, 3);
    for (int j = 0; j < n; ++j) {
        sp[j].cx = fz_u8(r) < 200 ? fz_unit(r, -2.0f, W + 2.0f) : fz_float(r);
        sp[j].cy = fz_u8(r) < 200 ? fz_unit(r, -2.0f, H + 2.0f) : fz_float(r);
        sp[j].radius = fz_u8(r) < 200 ? fz_unit(r, 0.1f, 4.0f) : fabsf(fz_float(r));
        sp[j].half_height = sp[j].radius * (fz_u8(r) < 128 ? 1.0f : fz_unit(r, 1.0f, 4.0f));
        sp[j].tap_offset = fz_unit(r, 0.0f, 0.16f);
        sp[j].depth = fz_unit(r, 0.1f, 10.0f);
    }
    const float fov_view = fz_unit(r, 0.1f, 3.0f), fov_cap = fz_unit(r, CCL_PARTICLES_MIN_FOV_CAPTURE, 3.14f);
    const int filter = fz_range(r, 0, 1), streaks = fz_bool(r);
    const float opacity = fz_unit(r, 0.0f, 1.0f);
    const ccl_status st = ccl_particles_composite(bg, W, H, sp, n, mask, MS, cap, CS, fov_view, fov_cap, filter,
                                                  streaks, opacity, out);
    int bad = 0;
    for (int j = 0; j < n; ++j) bad |= !(sp[j].radius > 0.0f) || !(sp[j].half_height >= sp[j].radius);
    FZ_CHECK((st == CCL_OK) == !bad, "composite status %d for sprites valid %d", (int)st, !bad);
    if (st == CCL_OK) {
        for (int i = 0; i < W * H * 3; ++i)
            FZ_CHECK(out[i] >= 0.0f && out[i] <= 1.0f, "composite pixel %d = %g", i, (double)out[i]);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    fz_reader rd = fz_init(data, size);
    fz_reader *r = &rd;
    switch (fz_u8(r) % 5) {
    case 0: fuzz_snell_fresnel(r); break;
    case 1: fuzz_drop(r); break;
    case 2: fuzz_capture(r); break;
    case 3: fuzz_particles(r); break;
    default: fuzz_composite(r); break;
    }
    return 0;
}
