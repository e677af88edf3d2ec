/* Volume rendering of uint8 cloud volumes (the SimVoleon stand-in of oc) and the survey extras oc-4.2 / oc-4.3.
 * See cclouds/volume.h for the pixel and the conventions. */
#include "cclouds/volume.h"
#include "cclouds/flight.h"
#include "cclouds/hash.h"
#include "cclouds/phase.h"
#include "internal.h"

#include <stddef.h>

#define BIG_T 3.0e38f

void ccl_volume_params_default(ccl_volume_params *out)
{
    if (out == NULL) return;
    /* sun 35 deg high behind the viewer's right shoulder of the default flight (heading -z): sunlit cloud sides */
    {
        /* elevation 35 deg, azimuth 150 deg (0 = -z, positive towards +x), as the cloudscape's default sun */
        float ce = 0.81915206f, se = 0.57357645f, ca = -0.8660254f, sa = 0.5f;
        out->sun = v3(ce * sa, se, -(ce * ca));
    }
    out->sun_colour = v3(1.0f, 0.96f, 0.88f);      /* warm white noon-ish sun; lit cloud tops reach white */
    out->ambient_top = v3(0.42f, 0.47f, 0.56f);    /* blue sky light from above */
    out->ambient_bottom = v3(0.22f, 0.24f, 0.29f); /* darker, the cloud's own shade at its base */
    out->sky_zenith = v3(0.16f, 0.33f, 0.65f);     /* deep blue zenith */
    out->sky_horizon = v3(0.62f, 0.72f, 0.85f);    /* pale horizon, also the fog colour */
    out->ground_a = v3(0.16f, 0.27f, 0.10f);       /* two greens / a field brown: a landscape seen from the air */
    out->ground_b = v3(0.36f, 0.33f, 0.18f);
    out->sun_glow = 0.6f;                          /* a visible glow when the view turns to the sun */
    out->sun_glow_power = 64.0f;                   /* a few degrees wide */
    out->field_size = 180.0f;                      /* fields of 180 m: motion cue at 60 m/s */
    out->fog_distance = 6000.0f;                   /* 6 km: a hazy summer day, the horizon dissolves */
    out->tau_per_voxel = 0.35f;                    /* a core of 255 is opaque after ~13 voxels, the edges stay soft */
    out->light_tau_per_voxel = 0.25f;              /* lighter than the view (forward scattering through the cloud) */
    out->step_voxels = 1.0f;                       /* one sample per voxel: no detail skipped */
    out->light_step_voxels = 1.0f;
    out->exit_transmittance = 0.01f;               /* 1 %: invisible behind */
    out->max_steps = 512;                          /* > the diagonal of a 256^3 box at one voxel per step */
    out->g = 0.3f;                                 /* mild forward scattering: silver lining towards the sun */
    out->jitter = 1;
    out->aircraft = 0;
    out->aircraft_position = v3(0.0f, 0.0f, 0.0f);
    out->aircraft_forward = v3(0.0f, 0.0f, -1.0f);
    out->aircraft_right = v3(1.0f, 0.0f, 0.0f);
    out->aircraft_up = v3(0.0f, 1.0f, 0.0f);
    out->aircraft_scale = 1.0f;
}

static int finite_f(float v) { return v == v && v - v == 0.0f; }
static int finite_v(ccl_vec3 v) { return finite_f(v.x) && finite_f(v.y) && finite_f(v.z); }
/* a colour: every component in [0, CCL_VOLUME_MAX_COLOUR] (finite products with the phase and the glow) */
static int colour_v(ccl_vec3 v)
{
    const float hi = (float)CCL_VOLUME_MAX_COLOUR;
    return finite_v(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f && v.x <= hi && v.y <= hi && v.z <= hi;
}
/* a length in [1 / CCL_VOLUME_LENGTH_RANGE, CCL_VOLUME_LENGTH_RANGE] metres */
static int length_f(float v)
{
    const float r = (float)CCL_VOLUME_LENGTH_RANGE;
    return finite_f(v) && v >= 1.0f / r && v <= r;
}
static int unit_v(ccl_vec3 v)
{
    float l = ccl_vec3_length(v);
    return finite_v(v) && fabsf(l - 1.0f) <= 1e-3f;
}

ccl_status ccl_volume_check(const ccl_volume_params *p, const ccl_volume_grid *grids, int count,
                            const char **out_field)
{
    const char *bad = NULL;
    int i;
    if (p == NULL) bad = "params";
    else if (!unit_v(p->sun)) bad = "sun";
    else if (!colour_v(p->sun_colour)) bad = "sun_colour";
    else if (!colour_v(p->ambient_top)) bad = "ambient_top";
    else if (!colour_v(p->ambient_bottom)) bad = "ambient_bottom";
    else if (!colour_v(p->sky_zenith)) bad = "sky_zenith";
    else if (!colour_v(p->sky_horizon)) bad = "sky_horizon";
    else if (!colour_v(p->ground_a)) bad = "ground_a";
    else if (!colour_v(p->ground_b)) bad = "ground_b";
    else if (!finite_f(p->sun_glow) || p->sun_glow < 0.0f || p->sun_glow > (float)CCL_VOLUME_MAX_COLOUR)
        bad = "sun_glow";
    else if (!finite_f(p->sun_glow_power) || !(p->sun_glow_power > 0.0f)) bad = "sun_glow_power";
    else if (!finite_f(p->field_size) || !(p->field_size > 0.0f)) bad = "field_size";
    else if (!finite_f(p->fog_distance) || !(p->fog_distance > 0.0f)) bad = "fog_distance";
    else if (!(p->tau_per_voxel >= 0.0f && p->tau_per_voxel <= (float)CCL_VOLUME_MAX_TAU)) bad = "tau_per_voxel";
    else if (!(p->light_tau_per_voxel >= 0.0f && p->light_tau_per_voxel <= (float)CCL_VOLUME_MAX_TAU))
        bad = "light_tau_per_voxel";
    else if (!(p->step_voxels >= 0.05f && p->step_voxels <= (float)CCL_VOLUME_MAX_STEP)) bad = "step_voxels";
    else if (!(p->light_step_voxels >= 0.05f && p->light_step_voxels <= (float)CCL_VOLUME_MAX_STEP))
        bad = "light_step_voxels";
    else if (!finite_f(p->exit_transmittance) || p->exit_transmittance < 0.0f || p->exit_transmittance >= 1.0f)
        bad = "exit_transmittance";
    else if (p->max_steps < 1 || p->max_steps > 100000) bad = "max_steps";
    else if (!finite_f(p->g) || !(p->g > -1.0f && p->g < 1.0f)) bad = "g";
    else if (p->aircraft && !finite_v(p->aircraft_position)) bad = "aircraft_position";
    else if (p->aircraft && !unit_v(p->aircraft_forward)) bad = "aircraft_forward";
    else if (p->aircraft && !unit_v(p->aircraft_right)) bad = "aircraft_right";
    else if (p->aircraft && !unit_v(p->aircraft_up)) bad = "aircraft_up";
    else if (p->aircraft && (!finite_f(p->aircraft_scale) || !(p->aircraft_scale > 0.0f))) bad = "aircraft_scale";
    else if (count < 0 || count > CCL_VOLUME_MAX_GRIDS || (count > 0 && grids == NULL)) bad = "count";
    for (i = 0; bad == NULL && i < count; ++i) {
        const ccl_volume_grid *gr = &grids[i];
        if (gr->density == NULL) bad = "density";
        else if (gr->light == NULL) bad = "light";
        else if (gr->skip == NULL) bad = "skip";
        else if (gr->nx < 1 || gr->ny < 1 || gr->nz < 1 || gr->nx > 4096 || gr->ny > 4096 || gr->nz > 4096)
            bad = "size";
        else if (!finite_v(gr->origin)) bad = "origin";
        else if (!length_f(gr->extent.x) || !length_f(gr->extent.y) || !length_f(gr->extent.z)) bad = "extent";
    }
    if (out_field != NULL) *out_field = bad;
    return bad == NULL ? CCL_OK : CCL_EINVAL;
}

static int clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

/* weights and clamped corner indices of a trilinear lookup at voxel-space v */
typedef struct {
    int x0, x1, y0, y1, z0, z1;
    float fx, fy, fz;
} tri_t;

static tri_t tri_setup(int nx, int ny, int nz, ccl_vec3 v)
{
    tri_t t;
    float ux = bound_cell(v.x - 0.5f, nx), uy = bound_cell(v.y - 0.5f, ny), uz = bound_cell(v.z - 0.5f, nz);
    float ix = floorf(ux), iy = floorf(uy), iz = floorf(uz);
    t.fx = ux - ix; t.fy = uy - iy; t.fz = uz - iz;
    t.x0 = clampi((int)ix, 0, nx - 1); t.x1 = clampi((int)ix + 1, 0, nx - 1);
    t.y0 = clampi((int)iy, 0, ny - 1); t.y1 = clampi((int)iy + 1, 0, ny - 1);
    t.z0 = clampi((int)iz, 0, nz - 1); t.z1 = clampi((int)iz + 1, 0, nz - 1);
    return t;
}

static float tri_mix(const tri_t *t, float c000, float c100, float c010, float c110, float c001, float c101,
                     float c011, float c111)
{
    float a = c000 + (c100 - c000) * t->fx;
    float b = c010 + (c110 - c010) * t->fx;
    float c = c001 + (c101 - c001) * t->fx;
    float d = c011 + (c111 - c011) * t->fx;
    float e = a + (b - a) * t->fy;
    float f = c + (d - c) * t->fy;
    return e + (f - e) * t->fz;
}

float ccl_volume_sample(const unsigned char *density, int nx, int ny, int nz, ccl_vec3 v)
{
    tri_t t;
    size_t sy = (size_t)nx, sz = (size_t)nx * (size_t)ny;
    if (!(v.x == v.x && v.y == v.y && v.z == v.z)) return v.x + v.y + v.z; /* NaN propagates */
    t = tri_setup(nx, ny, nz, v);
#define D_(X, Y, Z) ((float)density[(size_t)(Z) * sz + (size_t)(Y) * sy + (size_t)(X)])
    return tri_mix(&t, D_(t.x0, t.y0, t.z0), D_(t.x1, t.y0, t.z0), D_(t.x0, t.y1, t.z0), D_(t.x1, t.y1, t.z0),
                   D_(t.x0, t.y0, t.z1), D_(t.x1, t.y0, t.z1), D_(t.x0, t.y1, t.z1), D_(t.x1, t.y1, t.z1)) *
           (1.0f / 255.0f);
#undef D_
}

float ccl_volume_sample_float(const float *values, int nx, int ny, int nz, ccl_vec3 v)
{
    tri_t t;
    size_t sy = (size_t)nx, sz = (size_t)nx * (size_t)ny;
    if (!(v.x == v.x && v.y == v.y && v.z == v.z)) return v.x + v.y + v.z;
    t = tri_setup(nx, ny, nz, v);
#define F_(X, Y, Z) (values[(size_t)(Z) * sz + (size_t)(Y) * sy + (size_t)(X)])
    return tri_mix(&t, F_(t.x0, t.y0, t.z0), F_(t.x1, t.y0, t.z0), F_(t.x0, t.y1, t.z0), F_(t.x1, t.y1, t.z0),
                   F_(t.x0, t.y0, t.z1), F_(t.x1, t.y0, t.z1), F_(t.x0, t.y1, t.z1), F_(t.x1, t.y1, t.z1));
#undef F_
}

/* world -> voxel scale per axis */
static ccl_vec3 voxel_scale(const ccl_volume_grid *g)
{
    return v3((float)g->nx / g->extent.x, (float)g->ny / g->extent.y, (float)g->nz / g->extent.z);
}

/* slab test of o + t d against [0, n] on one axis; narrows [t0, t1]; returns 0 when empty */
static int slab(float o, float d, float n, float *t0, float *t1)
{
    if (d == 0.0f) return o >= 0.0f && o <= n;
    {
        float inv = 1.0f / d;
        float a = (0.0f - o) * inv, b = (n - o) * inv;
        if (a > b) { float tmp = a; a = b; b = tmp; }
        if (a > *t0) *t0 = a;
        if (b < *t1) *t1 = b;
    }
    return *t0 <= *t1;
}

int ccl_volume_box(const ccl_volume_grid *grid, ccl_vec3 eye, ccl_vec3 dir, float *out_t0, float *out_t1)
{
    ccl_vec3 sc = voxel_scale(grid);
    float t0 = -BIG_T, t1 = BIG_T;
    float ox = (eye.x - grid->origin.x) * sc.x, oy = (eye.y - grid->origin.y) * sc.y;
    float oz = (eye.z - grid->origin.z) * sc.z;
    int hit = slab(ox, dir.x * sc.x, (float)grid->nx, &t0, &t1) && slab(oy, dir.y * sc.y, (float)grid->ny, &t0, &t1)
              && slab(oz, dir.z * sc.z, (float)grid->nz, &t0, &t1) && t1 > 0.0f;
    if (out_t0 != NULL) *out_t0 = t0;
    if (out_t1 != NULL) *out_t1 = t1;
    return hit;
}

ccl_status ccl_volume_light(const ccl_volume_params *p, const ccl_volume_grid *grid, float *out_light,
                            size_t out_len)
{
    ccl_volume_grid g;
    ccl_vec3 sc, s_v;
    float len, step, tau;
    int ix, iy, iz, max_k;
    if (grid == NULL || out_light == NULL) return CCL_EINVAL;
    g = *grid;
    g.light = out_light; /* checked non-NULL only */
    g.skip = (const unsigned char *)out_light;
    if (ccl_volume_check(p, &g, 1, NULL) != CCL_OK) return CCL_EINVAL;
    if (out_len != (size_t)g.nx * (size_t)g.ny * (size_t)g.nz) return CCL_EINVAL;
    sc = voxel_scale(&g);
    s_v = v3(p->sun.x * sc.x, p->sun.y * sc.y, p->sun.z * sc.z);
    len = ccl_vec3_length(s_v);
    s_v = ccl_vec3_scale(s_v, 1.0f / len);
    step = p->light_step_voxels;
    tau = p->light_tau_per_voxel * step;
    /* the longest path through the box bounds the samples */
    max_k = (int)ceilf(sqrtf((float)g.nx * (float)g.nx + (float)g.ny * (float)g.ny + (float)g.nz * (float)g.nz) /
                       step) + 1;
    for (iz = 0; iz < g.nz; ++iz)
        for (iy = 0; iy < g.ny; ++iy)
            for (ix = 0; ix < g.nx; ++ix) {
                ccl_vec3 c = v3((float)ix + 0.5f, (float)iy + 0.5f, (float)iz + 0.5f);
                float sum = 0.0f;
                int k;
                for (k = 1; k <= max_k; ++k) {
                    ccl_vec3 q = ccl_vec3_add(c, ccl_vec3_scale(s_v, (float)k * step));
                    if (q.x < 0.0f || q.y < 0.0f || q.z < 0.0f || q.x > (float)g.nx || q.y > (float)g.ny ||
                        q.z > (float)g.nz)
                        break;
                    sum = sum + ccl_volume_sample(g.density, g.nx, g.ny, g.nz, q);
                }
                out_light[((size_t)iz * (size_t)g.ny + (size_t)iy) * (size_t)g.nx + (size_t)ix] = expf(-tau * sum);
            }
    return CCL_OK;
}

static int bricks(int n) { return (n + CCL_VOLUME_BRICK - 1) / CCL_VOLUME_BRICK; }

ccl_status ccl_volume_occupancy(const ccl_volume_grid *grid, unsigned char *out, size_t out_len)
{
    ccl_volume_params p;
    ccl_volume_grid g;
    int bx, by, bz, mx, my, mz;
    if (grid == NULL || out == NULL) return CCL_EINVAL;
    ccl_volume_params_default(&p);
    g = *grid;
    g.light = (const float *)(const void *)out;
    g.skip = out;
    if (ccl_volume_check(&p, &g, 1, NULL) != CCL_OK) return CCL_EINVAL;
    mx = bricks(g.nx); my = bricks(g.ny); mz = bricks(g.nz);
    if (out_len != (size_t)mx * (size_t)my * (size_t)mz) return CCL_EINVAL;
    for (bz = 0; bz < mz; ++bz)
        for (by = 0; by < my; ++by)
            for (bx = 0; bx < mx; ++bx) {
                const int e = CCL_VOLUME_BRICK;
                int x, y, z, any = 0;
                int x0 = clampi(bx * e - 1, 0, g.nx - 1), x1 = clampi(bx * e + e, 0, g.nx - 1);
                int y0 = clampi(by * e - 1, 0, g.ny - 1), y1 = clampi(by * e + e, 0, g.ny - 1);
                int z0 = clampi(bz * e - 1, 0, g.nz - 1), z1 = clampi(bz * e + e, 0, g.nz - 1);
                for (z = z0; z <= z1 && !any; ++z)
                    for (y = y0; y <= y1 && !any; ++y)
                        for (x = x0; x <= x1; ++x)
                            if (g.density[((size_t)z * (size_t)g.ny + (size_t)y) * (size_t)g.nx + (size_t)x] > 0) {
                                any = 1;
                                break;
                            }
                out[((size_t)bz * (size_t)my + (size_t)by) * (size_t)mx + (size_t)bx] = (unsigned char)any;
            }
    return CCL_OK;
}

ccl_status ccl_volume_skip(const ccl_volume_grid *grid, unsigned char *out, size_t out_len)
{
    ccl_status st;
    int mx, my, mz, m, changed;
    size_t i;
    if (grid == NULL || out == NULL) return CCL_EINVAL;
    st = ccl_volume_occupancy(grid, out, out_len);
    if (st != CCL_OK) return st;
    mx = bricks(grid->nx); my = bricks(grid->ny); mz = bricks(grid->nz);
    /* occupied -> 0, empty -> 255 (not reached yet); then distance m for the empty bricks next to distance m - 1 */
    for (i = 0; i < out_len; ++i) out[i] = out[i] ? 0 : 255;
    changed = 1;
    for (m = 1; m < 255 && changed; ++m) {
        int bx, by, bz;
        changed = 0;
        for (bz = 0; bz < mz; ++bz)
            for (by = 0; by < my; ++by)
                for (bx = 0; bx < mx; ++bx) {
                    int x, y, z, hit = 0;
                    unsigned char *c = &out[((size_t)bz * (size_t)my + (size_t)by) * (size_t)mx + (size_t)bx];
                    if (*c != 255) continue;
                    for (z = bz - 1; z <= bz + 1 && !hit; ++z)
                        for (y = by - 1; y <= by + 1 && !hit; ++y)
                            for (x = bx - 1; x <= bx + 1; ++x) {
                                if (x < 0 || y < 0 || z < 0 || x >= mx || y >= my || z >= mz) continue;
                                if (out[((size_t)z * (size_t)my + (size_t)y) * (size_t)mx + (size_t)x] == m - 1) {
                                    hit = 1;
                                    break;
                                }
                            }
                    if (hit) {
                        *c = (unsigned char)m;
                        changed = 1;
                    }
                }
    }
    return CCL_OK;
}

/* distance along the voxel-space ray o + t d to the exit of the cube of bricks (b - (m - 1)) .. (b + m - 1) per
 * axis around the brick (bx, by, bz) (m = 1: the brick itself) */
static float brick_exit(ccl_vec3 o, ccl_vec3 d, int bx, int by, int bz, int m)
{
    const float b = (float)CCL_VOLUME_BRICK;
    const float r = (float)(m - 1);
    float te = BIG_T;
    if (d.x != 0.0f) {
        float plane = d.x > 0.0f ? ((float)bx + r + 1.0f) * b : ((float)bx - r) * b;
        float t = (plane - o.x) / d.x;
        te = t < te ? t : te;
    }
    if (d.y != 0.0f) {
        float plane = d.y > 0.0f ? ((float)by + r + 1.0f) * b : ((float)by - r) * b;
        float t = (plane - o.y) / d.y;
        te = t < te ? t : te;
    }
    if (d.z != 0.0f) {
        float plane = d.z > 0.0f ? ((float)bz + r + 1.0f) * b : ((float)bz - r) * b;
        float t = (plane - o.z) / d.z;
        te = t < te ? t : te;
    }
    return te;
}

ccl_vec3 ccl_volume_sky(const ccl_volume_params *p, ccl_vec3 d)
{
    float up = d.y > 0.0f ? d.y : 0.0f;
    float c = ccl_vec3_dot(d, p->sun);
    float glow;
    ccl_vec3 col;
    /* clamped to [0, 1]: d . sun of unit vectors can round above 1, and c^power overflowed for huge powers */
    c = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
    glow = p->sun_glow * powf(c, p->sun_glow_power);
    up = sqrtf(up);
    col = ccl_vec3_add(p->sky_horizon, ccl_vec3_scale(ccl_vec3_sub(p->sky_zenith, p->sky_horizon), up));
    return ccl_vec3_add(col, ccl_vec3_scale(p->sun_colour, glow));
}

/* model-frame coordinates of a world point / direction */
static ccl_vec3 to_model(const ccl_volume_params *p, ccl_vec3 w)
{
    return v3(ccl_vec3_dot(w, p->aircraft_right), ccl_vec3_dot(w, p->aircraft_up),
              -ccl_vec3_dot(w, p->aircraft_forward));
}

/* bounding sphere of the model (radius in model metres): the wing tips at 6.0 m, the nose at 3.8 m */
#define AIRCRAFT_BOUND 6.3f

static float aircraft_hit(const ccl_volume_params *p, ccl_vec3 eye, ccl_vec3 d, int *out_part, ccl_vec3 *out_q)
{
    float inv = 1.0f / p->aircraft_scale;
    ccl_vec3 o = ccl_vec3_scale(to_model(p, ccl_vec3_sub(eye, p->aircraft_position)), inv);
    ccl_vec3 dm = to_model(p, d); /* unit: the axes are orthonormal */
    float b = ccl_vec3_dot(o, dm);
    float c = ccl_vec3_dot(o, o) - AIRCRAFT_BOUND * AIRCRAFT_BOUND;
    float disc = b * b - c, t, t_far;
    int k;
    if (disc <= 0.0f) return BIG_T;
    disc = sqrtf(disc);
    t = -b - disc;
    t_far = -b + disc;
    if (t_far <= 0.0f) return BIG_T;
    if (t < 0.0f) t = 0.0f;
    for (k = 0; k < CCL_VOLUME_AIRCRAFT_STEPS; ++k) {
        ccl_vec3 q = ccl_vec3_add(o, ccl_vec3_scale(dm, t));
        int part;
        float dist = ccl_flight_aircraft(q, &part);
        if (dist < 0.002f) {
            *out_part = part;
            *out_q = q;
            return t * p->aircraft_scale;
        }
        t = t + dist;
        if (t > t_far) break;
    }
    return BIG_T;
}

static ccl_vec3 aircraft_colour(const ccl_volume_params *p, ccl_vec3 q, int part)
{
    const float h = 0.01f;
    ccl_vec3 n, base, nw, lit;
    float ndl, up;
    n.x = ccl_flight_aircraft(v3(q.x + h, q.y, q.z), NULL) - ccl_flight_aircraft(v3(q.x - h, q.y, q.z), NULL);
    n.y = ccl_flight_aircraft(v3(q.x, q.y + h, q.z), NULL) - ccl_flight_aircraft(v3(q.x, q.y - h, q.z), NULL);
    n.z = ccl_flight_aircraft(v3(q.x, q.y, q.z + h), NULL) - ccl_flight_aircraft(v3(q.x, q.y, q.z - h), NULL);
    n = ccl_vec3_normalize(n);
    /* back to the world: x right, y up, z = -forward */
    nw = ccl_vec3_add(ccl_vec3_add(ccl_vec3_scale(p->aircraft_right, n.x), ccl_vec3_scale(p->aircraft_up, n.y)),
                      ccl_vec3_scale(p->aircraft_forward, -n.z));
    if (part == 0) base = v3(0.85f, 0.85f, 0.82f);      /* white fuselage */
    else if (part == 1) base = v3(0.75f, 0.12f, 0.08f); /* red wings */
    else if (part == 2) base = v3(0.75f, 0.12f, 0.08f); /* red tail */
    else base = v3(0.08f, 0.12f, 0.2f);                 /* dark canopy */
    ndl = ccl_vec3_dot(nw, p->sun);
    ndl = ndl > 0.0f ? ndl : 0.0f;
    up = 0.5f + 0.5f * nw.y;
    lit = ccl_vec3_add(ccl_vec3_scale(p->sun_colour, ndl),
                       ccl_vec3_add(ccl_vec3_scale(p->ambient_top, up), ccl_vec3_scale(p->ambient_bottom, 1.0f - up)));
    return v3(base.x * lit.x, base.y * lit.y, base.z * lit.z);
}

ccl_vec3 ccl_volume_background(const ccl_volume_params *p, ccl_vec3 eye, ccl_vec3 d, float *out_t)
{
    float t_hit = BIG_T;
    if (out_t != NULL) *out_t = BIG_T;
    if (p->aircraft) {
        int part = 0;
        ccl_vec3 q = v3(0.0f, 0.0f, 0.0f);
        t_hit = aircraft_hit(p, eye, d, &part, &q);
        if (t_hit < BIG_T) {
            if (out_t != NULL) *out_t = t_hit;
            return aircraft_colour(p, q, part);
        }
    }
    if (d.y < 0.0f && eye.y > 0.0f) {
        float t = -eye.y / d.y;
        float gx = eye.x + t * d.x, gz = eye.z + t * d.z;
        /* field cell, clamped so that the int conversion is defined for grazing rays (fogged out anyway) */
        float fx = floorf(gx / p->field_size), fz = floorf(gz / p->field_size);
        int cx, cz;
        fx = !(fx >= -1.0e9f) ? -1.0e9f : (fx > 1.0e9f ? 1.0e9f : fx); /* NaN (inf x 0 at d.x = 0): -1e9 */
        fz = !(fz >= -1.0e9f) ? -1.0e9f : (fz > 1.0e9f ? 1.0e9f : fz);
        cx = (int)fx;
        cz = (int)fz;
        uint32_t h = ccl_hash_pcg((uint32_t)cx * 73856093u ^ ccl_hash_pcg((uint32_t)cz));
        float u = ccl_hash_unit(h);
        float sun_up = p->sun.y > 0.0f ? p->sun.y : 0.0f;
        ccl_vec3 col = ccl_vec3_scale(mix3(p->ground_a, p->ground_b, u), 0.35f + 0.65f * sun_up);
        float f = expf(-t / p->fog_distance);
        return mix3(p->sky_horizon, col, f);
    }
    return ccl_volume_sky(p, d);
}

/* voxel-space ray of a grid */
static void grid_ray(const ccl_volume_grid *g, ccl_vec3 eye, ccl_vec3 d, ccl_vec3 *o_v, ccl_vec3 *d_v)
{
    ccl_vec3 sc = voxel_scale(g);
    *o_v = v3((eye.x - g->origin.x) * sc.x, (eye.y - g->origin.y) * sc.y, (eye.z - g->origin.z) * sc.z);
    *d_v = v3(d.x * sc.x, d.y * sc.y, d.z * sc.z);
}

void ccl_volume_pixel(const ccl_volume_params *p, const ccl_volume_grid *grids, int count, const ccl_camera *cam,
                      int x, int y, int width, int height, float *out_rgb)
{
    ccl_vec3 d = ccl_camera_ray(cam->inv_view_proj_rot, x, y, width, height);
    ccl_vec3 eye = cam->eye;
    float jitter = p->jitter ? ccl_hash_unit(ccl_hash_pcg((uint32_t)x + 65536u * (uint32_t)y)) : 0.5f;
    float t_hit, total_t = 1.0f;
    ccl_vec3 bg = ccl_volume_background(p, eye, d, &t_hit);
    ccl_vec3 total = v3(0.0f, 0.0f, 0.0f);
    float mu = ccl_vec3_dot(d, p->sun), phase;
    float last_t = -BIG_T;
    float box_t0[CCL_VOLUME_MAX_GRIDS], box_t1[CCL_VOLUME_MAX_GRIDS];
    int box_hit[CCL_VOLUME_MAX_GRIDS];
    int last_i = -1, k;
    mu = mu < -1.0f ? -1.0f : (mu > 1.0f ? 1.0f : mu); /* two unit vectors: |dot| may exceed 1 by an ulp */
    phase = 4.0f * CCL_PI_F * ccl_phase_hg(mu, p->g);
    /* every box's entry and exit once; then the grids in the order of their entry */
    for (k = 0; k < count; ++k) box_hit[k] = ccl_volume_box(&grids[k], eye, d, &box_t0[k], &box_t1[k]);
    for (k = 0; k < count; ++k) {
        /* the next grid along the ray: smallest entry after (last_t, last_i) */
        int best = -1, i;
        float best_t0 = BIG_T, best_t1 = 0.0f;
        for (i = 0; i < count; ++i) {
            float t0 = box_t0[i];
            if (!box_hit[i]) continue;
            if (t0 < last_t || (t0 == last_t && i <= last_i)) continue;
            if (best < 0 || t0 < best_t0) {
                best = i;
                best_t0 = t0;
                best_t1 = box_t1[i];
            }
        }
        if (best < 0) break;
        last_t = best_t0;
        last_i = best;
        {
            const ccl_volume_grid *g = &grids[best];
            ccl_vec3 o_v, d_v, col = v3(0.0f, 0.0f, 0.0f);
            float trans = 1.0f, t_start = best_t0 > 0.0f ? best_t0 : 0.0f;
            float t_end = best_t1 < t_hit ? best_t1 : t_hit;
            float dt, a_step, fog;
            int n, s, mx, my, mz;
            grid_ray(g, eye, d, &o_v, &d_v);
            dt = p->step_voxels / ccl_vec3_length(d_v);
            a_step = p->tau_per_voxel * p->step_voxels;
            n = 0;
            if (t_end > t_start) {
                float steps = ceilf((t_end - t_start) / dt);
                n = steps < (float)p->max_steps ? (int)steps : p->max_steps;
            }
            mx = bricks(g->nx); my = bricks(g->ny); mz = bricks(g->nz);
            s = 0;
            while (s < n) {
                float t = t_start + ((float)s + jitter) * dt;
                ccl_vec3 v;
                float rho, alpha, tl, hfrac;
                ccl_vec3 amb, light;
                int bx, by, bz, m;
                tri_t tri;
                if (t > t_end) break;
                v = ccl_vec3_add(o_v, ccl_vec3_scale(d_v, t));
                bx = clampi((int)floorf(v.x * (1.0f / (float)CCL_VOLUME_BRICK)), 0, mx - 1);
                by = clampi((int)floorf(v.y * (1.0f / (float)CCL_VOLUME_BRICK)), 0, my - 1);
                bz = clampi((int)floorf(v.z * (1.0f / (float)CCL_VOLUME_BRICK)), 0, mz - 1);
                m = g->skip[((size_t)bz * (size_t)my + (size_t)by) * (size_t)mx + (size_t)bx];
                if (m > 0) {
                    /* empty cube of bricks around: every sample inside it is 0; go to the first sample at or after
                       its exit */
                    float te = brick_exit(o_v, d_v, bx, by, bz, m);
                    float next = ceilf((te - t_start) / dt - jitter);
                    s = next > (float)(s + 1) ? (next < (float)n ? (int)next : n) : s + 1;
                    continue;
                }
                s = s + 1;
                /* ccl_volume_sample and ccl_volume_sample_float at v, sharing the weights */
                tri = tri_setup(g->nx, g->ny, g->nz, v);
                {
                    size_t sy = (size_t)g->nx, sz = (size_t)g->nx * (size_t)g->ny;
                    size_t i000 = (size_t)tri.z0 * sz + (size_t)tri.y0 * sy, i010 = (size_t)tri.z0 * sz + (size_t)tri.y1 * sy;
                    size_t i001 = (size_t)tri.z1 * sz + (size_t)tri.y0 * sy, i011 = (size_t)tri.z1 * sz + (size_t)tri.y1 * sy;
                    const unsigned char *dd = g->density;
                    const float *ll = g->light;
                    size_t x0 = (size_t)tri.x0, x1 = (size_t)tri.x1;
                    rho = tri_mix(&tri, (float)dd[i000 + x0], (float)dd[i000 + x1], (float)dd[i010 + x0],
                                  (float)dd[i010 + x1], (float)dd[i001 + x0], (float)dd[i001 + x1], (float)dd[i011 + x0],
                                  (float)dd[i011 + x1]) * (1.0f / 255.0f);
                    if (rho <= 0.0f) continue;
                    tl = tri_mix(&tri, ll[i000 + x0], ll[i000 + x1], ll[i010 + x0], ll[i010 + x1], ll[i001 + x0],
                                 ll[i001 + x1], ll[i011 + x0], ll[i011 + x1]);
                }
                alpha = 1.0f - expf(-a_step * rho);
                hfrac = v.y / (float)g->ny;
                hfrac = hfrac < 0.0f ? 0.0f : (hfrac > 1.0f ? 1.0f : hfrac);
                amb = mix3(p->ambient_bottom, p->ambient_top, hfrac);
                light = ccl_vec3_add(ccl_vec3_scale(p->sun_colour, tl * phase), amb);
                col = ccl_vec3_add(col, ccl_vec3_scale(light, trans * alpha));
                trans = trans * (1.0f - alpha);
                if (trans < p->exit_transmittance) break;
            }
            fog = expf(-t_start / p->fog_distance);
            col = ccl_vec3_add(ccl_vec3_scale(col, fog), ccl_vec3_scale(p->sky_horizon, (1.0f - fog) * (1.0f - trans)));
            total = ccl_vec3_add(total, ccl_vec3_scale(col, total_t));
            total_t = total_t * trans;
            if (total_t < p->exit_transmittance) break;
        }
    }
    out_rgb[0] = total.x + total_t * bg.x;
    out_rgb[1] = total.y + total_t * bg.y;
    out_rgb[2] = total.z + total_t * bg.z;
}

/* the radii whose square is a normal float (2^-60, 2^60) */
#define METABALL_SQUARE_MIN 8.67361737988403547e-19f
#define METABALL_SQUARE_MAX 1.152921504606846976e18f

float ccl_volume_metaball(float distance, float radius, float strength)
{
    float q, w;
    CCL_REQUIRE(!(distance < 0.0f) && !(radius <= 0.0f));
    /* oc-4.2 in kind: Wyvill, McPheeters & Wyvill 1986 soft objects, (1 - r^2/R^2)^3 inside R. r >= R decides
     * outside before any square (r^2/R^2 >= 1 there in float too); inside, r^2/R^2 where R^2 is a normal float, else
     * (r/R)^2: the squares of a radius beyond 2^+-60 under- or overflowed (0/0, Inf/Inf). A NaN r gives NaN. */
    if (distance >= radius) return 0.0f * strength;
    if (radius >= METABALL_SQUARE_MIN && radius <= METABALL_SQUARE_MAX) q = (distance * distance) / (radius * radius);
    else q = (distance / radius) * (distance / radius);
    w = 1.0f - q;
    return strength * (w * w * w);
}

float ccl_volume_ellipsoid(ccl_vec3 p, ccl_vec3 radii, float texture, float threshold, float ramp)
{
    float qx, qy, qz, q, g, o;
    CCL_REQUIRE(!(ramp <= 0.0f));
    /* oc-4.3 in kind: Gardner 1985's translucency with g = 1 - |p / radii|^2 */
    qx = p.x / radii.x;
    qy = p.y / radii.y;
    qz = p.z / radii.z;
    q = qx * qx + qy * qy + qz * qz;
    g = 1.0f - q;
    o = (texture - threshold - ramp * (1.0f - g)) / ramp;
    if (o < 0.0f) o = 0.0f;
    if (o > 1.0f) o = 1.0f;
    return o;
}
