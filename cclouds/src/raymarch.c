/* View-ray geometry of the cloudscape (vc §2.2, §4.2.1, §4.3.2). See cclouds/raymarch.h for the conventions.
 * Every float32 expression here is mirrored operation by operation in pywarp/kernels/raymarch.py. */
#include "cclouds/raymarch.h"
#include "internal.h"

#include <float.h>

/* --- vec3 helpers (static: the public header has no inline functions) -------------------------------------------- */

static ccl_vec3 v3(float x, float y, float z)
{
    ccl_vec3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}

static ccl_vec3 v3_add(ccl_vec3 a, ccl_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static ccl_vec3 v3_sub(ccl_vec3 a, ccl_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static ccl_vec3 v3_scale(ccl_vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static float v3_dot(ccl_vec3 a, ccl_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

static ccl_vec3 v3_normalize(ccl_vec3 a)
{
    float l = sqrtf(v3_dot(a, a));
    return v3(a.x / l, a.y / l, a.z / l);
}

/* --- PCG hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020) ---------------------------- */

static uint32_t pcg_hash(uint32_t v)
{
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/* Seed of pixel (x, y) in frame `frame`: pcg(x + pcg(y + pcg(frame))). */
static uint32_t jitter_seed(uint32_t x, uint32_t y, uint32_t frame)
{
    return pcg_hash(x + pcg_hash(y + pcg_hash(frame)));
}

/* Uniform float in [0, 1) from the top 24 bits of a hash (exact in float32). */
static float hash_unit(uint32_t h)
{
    return (float)(h >> 8u) * (1.0f / 16777216.0f);
}

static void write_nan2(float *a, float *b)
{
    *a = NAN;
    *b = NAN;
}

/* --- vc-A14: ray-sphere ------------------------------------------------------------------------------------------ */

int ccl_ray_sphere(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r, float *out_t0, float *out_t1)
{
    ccl_vec3 f, l;
    float b, ll, disc, s, q, ff, cq, ta, tb;
    CCL_REQUIRE(!(r <= 0.0f));
    f = v3_sub(o, c);
    b = v3_dot(f, d);
    l = v3_sub(f, v3_scale(d, b)); /* closest-approach vector: |l| = distance of the line from c */
    ll = sqrtf(v3_dot(l, l));
    disc = (r - ll) * (r + ll);
    if (!(disc >= 0.0f)) { /* miss, or NaN input */
        write_nan2(out_t0, out_t1);
        return 0;
    }
    s = sqrtf(disc);
    q = (b >= 0.0f) ? -(b + s) : s - b; /* -b - sign(b) s: no cancellation */
    ff = sqrtf(v3_dot(f, f));
    cq = (ff - r) * (ff + r); /* |f|^2 - r^2 without cancelling two squares */
    if (q == 0.0f) {          /* b == 0 and disc == 0: the origin is the tangent point */
        ta = 0.0f;
        tb = 0.0f;
    } else {
        ta = cq / q;
        tb = q;
    }
    *out_t0 = (ta < tb) ? ta : tb;
    *out_t1 = (ta < tb) ? tb : ta;
    return 1;
}

int ccl_ray_sphere_flat(float ox, float oy, float oz, float dx, float dy, float dz, float cx, float cy, float cz,
                        float r, float *out_t0, float *out_t1)
{
    return ccl_ray_sphere(v3(ox, oy, oz), v3_normalize(v3(dx, dy, dz)), v3(cx, cy, cz), r, out_t0, out_t1);
}

/* --- vc-A35: ray-box (slabs) ------------------------------------------------------------------------------------- */

static int slab(float o, float d, float lo, float hi, float *tn, float *tf)
{
    float ta, tb, tmp;
    if (d == 0.0f) return !(o < lo || o > hi);
    ta = (lo - o) / d;
    tb = (hi - o) / d;
    if (ta > tb) {
        tmp = ta;
        ta = tb;
        tb = tmp;
    }
    if (ta > *tn) *tn = ta;
    if (tb < *tf) *tf = tb;
    return 1;
}

int ccl_ray_box(ccl_vec3 o, ccl_vec3 d, ccl_vec3 bmin, ccl_vec3 bmax, float *out_t0, float *out_t1)
{
    float tn = -INFINITY, tf = INFINITY;
    float check = o.x + o.y + o.z + d.x + d.y + d.z + bmin.x + bmin.y + bmin.z + bmax.x + bmax.y + bmax.z;
    if (isnan(check) || !slab(o.x, d.x, bmin.x, bmax.x, &tn, &tf) || !slab(o.y, d.y, bmin.y, bmax.y, &tn, &tf)
        || !slab(o.z, d.z, bmin.z, bmax.z, &tn, &tf) || !(tn <= tf)) {
        write_nan2(out_t0, out_t1);
        return 0;
    }
    *out_t0 = tn;
    *out_t1 = tf;
    return 1;
}

/* --- vc-A14 / vc-A24: the cloud-layer segment -------------------------------------------------------------------- */

int ccl_layer_segment(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r_earth, float r_inner, float r_outer,
                      float *out_t_start, float *out_t_end)
{
    ccl_vec3 f = v3_sub(o, c);
    float rho = sqrtf(v3_dot(f, f));
    float t0, t1, ts, te;
    CCL_REQUIRE(!(r_earth <= 0.0f || r_inner < r_earth || r_outer <= r_inner));
    if (rho < r_inner) {
        /* below the layer (vc-A14): the Earth blocks every ray whose far root lies ahead */
        if (ccl_ray_sphere(o, d, c, r_earth, &t0, &t1) && t1 > 0.0f) {
            write_nan2(out_t_start, out_t_end);
            return 0;
        }
        ccl_ray_sphere(o, d, c, r_inner, &t0, &t1);
        ts = t1;
        ccl_ray_sphere(o, d, c, r_outer, &t0, &t1);
        te = t1;
    } else if (rho <= r_outer) {
        /* inside the layer (vc-A24): from the camera to the first exit */
        ts = 0.0f;
        if (ccl_ray_sphere(o, d, c, r_inner, &t0, &t1) && t0 > 0.0f) {
            te = t0;
        } else {
            ccl_ray_sphere(o, d, c, r_outer, &t0, &t1);
            te = t1;
        }
    } else {
        /* above the layer (vc-A24): enter the outer sphere, leave through the inner one (the Earth is inside it) */
        if (!ccl_ray_sphere(o, d, c, r_outer, &t0, &t1) || !(t1 > 0.0f)) {
            write_nan2(out_t_start, out_t_end);
            return 0;
        }
        ts = (t0 > 0.0f) ? t0 : 0.0f;
        te = t1;
        if (ccl_ray_sphere(o, d, c, r_inner, &t0, &t1) && t0 > 0.0f) te = t0;
    }
    if (!(te >= ts)) { /* NaN input or a numerically empty interval */
        write_nan2(out_t_start, out_t_end);
        return 0;
    }
    *out_t_start = ts;
    *out_t_end = te;
    return 1;
}

int ccl_layer_segment_flat(float ox, float oy, float oz, float dx, float dy, float dz, float cx, float cy, float cz,
                           float r_earth, float r_inner, float r_outer, float *out_t_start, float *out_t_end)
{
    return ccl_layer_segment(v3(ox, oy, oz), v3_normalize(v3(dx, dy, dz)), v3(cx, cy, cz), r_earth, r_inner, r_outer,
                             out_t_start, out_t_end);
}

void ccl_cloud_layer_default(ccl_cloud_layer *out)
{
    ccl_status st = ccl_cloud_layer_init(6371.0f, 1.5f, 4.0f, out);
    (void)st;
    CCL_REQUIRE(st == CCL_OK);
}

ccl_status ccl_cloud_layer_init(float earth_radius, float base_altitude, float top_altitude, ccl_cloud_layer *out)
{
    if (!out || !isfinite(earth_radius) || !isfinite(base_altitude) || !isfinite(top_altitude) || earth_radius <= 0.0f
        || base_altitude < 0.0f || !(top_altitude > base_altitude))
        return CCL_EINVAL;
    out->centre = v3(0.0f, -earth_radius, 0.0f);
    out->r_earth = earth_radius;
    out->r_inner = earth_radius + base_altitude;
    out->r_outer = earth_radius + top_altitude;
    if (!(out->r_outer > out->r_inner)) return CCL_EINVAL; /* altitudes below the float32 resolution of the radius */
    return CCL_OK;
}

/* --- vc-A18: view-sample count ----------------------------------------------------------------------------------- */

int ccl_view_sample_count(float dir_y, int n_min, int n_max)
{
    float ay = fabsf(dir_y);
    float n;
    CCL_REQUIRE(n_min >= 1 && n_min <= n_max);
    if (!(ay < 1.0f)) ay = (ay >= 1.0f) ? 1.0f : 0.0f; /* |y| > 1 from rounding -> 1; NaN -> 0 (n_max samples) */
    n = (float)n_max + (float)(n_min - n_max) * ay;
    return (int)floorf(n + 0.5f);
}

/* --- vc-A19: light-cone samples ---------------------------------------------------------------------------------- */

/* Six unit vectors, uniform on the sphere: u1 = pcg(2i) / 2^32, u2 = pcg(2i + 1) / 2^32, z = 1 - 2 u1,
 * phi = 2 pi u2, k = (sqrt(1 - z^2) cos phi, sqrt(1 - z^2) sin phi, z), evaluated in double, rounded to float. */
static const float light_cone_kernel[6][3] = {
    {-0.184916884f, -0.288023561f, 0.939599991f},
    {-0.998808086f, 0.0230856221f, 0.0430054031f},
    {-0.729488671f, -0.0146079780f, 0.683836877f},
    {-0.464710385f, 0.0182285905f, -0.885275066f},
    {-0.202527046f, 0.584412575f, 0.785776496f},
    {-0.140362307f, 0.982180178f, 0.124982178f},
};

ccl_vec3 ccl_light_cone_kernel(int i)
{
    int j = ((i % 6) + 6) % 6;
    return v3(light_cone_kernel[j][0], light_cone_kernel[j][1], light_cone_kernel[j][2]);
}

ccl_vec3 ccl_light_sample_position(ccl_vec3 p, ccl_vec3 to_sun, int i, float step, float cone_angle,
                                   float far_factor, ccl_vec3 k)
{
    float s, radius;
    CCL_REQUIRE(i >= 0 && i <= 5);
    CCL_REQUIRE(!(step <= 0.0f) && !(cone_angle < 0.0f));
    s = (i < 5) ? (float)(i + 1) * step : far_factor * (5.0f * step);
    radius = s * tanf(cone_angle);
    return v3_add(v3_add(p, v3_scale(to_sun, s)), v3_scale(k, radius));
}

void ccl_light_sample_offset_flat(int i, float sx, float sy, float sz, float step, float cone_angle, float far_factor,
                                  float *out_x, float *out_y, float *out_z)
{
    ccl_vec3 r = ccl_light_sample_position(v3(0.0f, 0.0f, 0.0f), v3_normalize(v3(sx, sy, sz)), i, step, cone_angle,
                                           far_factor, ccl_light_cone_kernel(i));
    *out_x = r.x;
    *out_y = r.y;
    *out_z = r.z;
}

/* --- vc-A21: accumulation and early termination ------------------------------------------------------------------ */

int ccl_march_accumulate(ccl_vec3 *colour, float *transmittance, float sigma, float rho, float dt, ccl_vec3 light,
                         float eps)
{
    float tau = sigma * rho * dt;
    float e = expf(-tau);
    float w = *transmittance * (1.0f - e);
    colour->x = colour->x + w * light.x;
    colour->y = colour->y + w * light.y;
    colour->z = colour->z + w * light.z;
    *transmittance = *transmittance * e;
    return (1.0f - *transmittance) >= (1.0f - eps);
}

void ccl_march_accumulate_flat(float cr, float cg, float cb, float transmittance, float sigma, float rho, float dt,
                               float lr, float lg, float lb, float eps, float *out_r, float *out_g, float *out_b,
                               float *out_transmittance, float *out_stop)
{
    ccl_vec3 c = v3(cr, cg, cb);
    float t = transmittance;
    int stop = ccl_march_accumulate(&c, &t, sigma, rho, dt, v3(lr, lg, lb), eps);
    *out_r = c.x;
    *out_g = c.y;
    *out_b = c.z;
    *out_transmittance = t;
    *out_stop = stop ? 1.0f : 0.0f;
}

/* --- vc-A25: camera and ray generation --------------------------------------------------------------------------- */

/* column-major store of a row-major double matrix */
static void store_cm(float dst[16], double m[4][4])
{
    int r, c;
    for (c = 0; c < 4; ++c)
        for (r = 0; r < 4; ++r) dst[c * 4 + r] = (float)m[r][c];
}

static void matmul4(double out[4][4], double a[4][4], double b[4][4])
{
    int r, c, k;
    for (r = 0; r < 4; ++r)
        for (c = 0; c < 4; ++c) {
            double s = 0.0;
            for (k = 0; k < 4; ++k) s += a[r][k] * b[k][c];
            out[r][c] = s;
        }
}

ccl_status ccl_camera_look_at(ccl_vec3 eye, ccl_vec3 target, ccl_vec3 up, float fov_y, float aspect, float z_near,
                              float z_far, ccl_camera *out)
{
    double f[3], s[3], u[3], upd[3], n, t;
    double view[4][4], proj[4][4], inv_view[4][4], inv_proj[4][4], vp[4][4], ivp[4][4], ivpr[4][4];
    const float in[] = {eye.x, eye.y, eye.z, target.x, target.y, target.z, up.x, up.y, up.z, fov_y, aspect, z_near,
                        z_far};
    size_t i;
    int r, c;
    if (!out) return CCL_EINVAL;
    for (i = 0; i < sizeof in / sizeof in[0]; ++i)
        if (!isfinite(in[i])) return CCL_EINVAL;
    if (!(fov_y > 0.0f && fov_y < CCL_PI_F) || !(aspect > 0.0f) || !(z_near > 0.0f) || !(z_far > z_near))
        return CCL_EINVAL;
    /* forward f = normalize(target - eye) */
    f[0] = (double)target.x - eye.x;
    f[1] = (double)target.y - eye.y;
    f[2] = (double)target.z - eye.z;
    n = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(n > 0.0)) return CCL_EINVAL;
    for (i = 0; i < 3; ++i) f[i] /= n;
    upd[0] = up.x;
    upd[1] = up.y;
    upd[2] = up.z;
    n = sqrt(upd[0] * upd[0] + upd[1] * upd[1] + upd[2] * upd[2]);
    if (!(n > 0.0)) return CCL_EINVAL;
    /* side s = normalize(f x up); |f x up/|up|| = sin(angle): reject up within ~1e-6 rad of the view direction */
    s[0] = f[1] * upd[2] - f[2] * upd[1];
    s[1] = f[2] * upd[0] - f[0] * upd[2];
    s[2] = f[0] * upd[1] - f[1] * upd[0];
    t = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    if (!(t > 1e-6 * n)) return CCL_EINVAL;
    for (i = 0; i < 3; ++i) s[i] /= t;
    /* true up u = s x f */
    u[0] = s[1] * f[2] - s[2] * f[1];
    u[1] = s[2] * f[0] - s[0] * f[2];
    u[2] = s[0] * f[1] - s[1] * f[0];

    for (r = 0; r < 4; ++r)
        for (c = 0; c < 4; ++c) view[r][c] = proj[r][c] = inv_view[r][c] = inv_proj[r][c] = 0.0;
    for (c = 0; c < 3; ++c) {
        view[0][c] = s[c];
        view[1][c] = u[c];
        view[2][c] = -f[c];
        inv_view[c][0] = s[c];
        inv_view[c][1] = u[c];
        inv_view[c][2] = -f[c];
    }
    view[0][3] = -(s[0] * eye.x + s[1] * eye.y + s[2] * eye.z);
    view[1][3] = -(u[0] * eye.x + u[1] * eye.y + u[2] * eye.z);
    view[2][3] = f[0] * eye.x + f[1] * eye.y + f[2] * eye.z;
    view[3][3] = 1.0;
    inv_view[0][3] = eye.x;
    inv_view[1][3] = eye.y;
    inv_view[2][3] = eye.z;
    inv_view[3][3] = 1.0;

    t = tan(0.5 * (double)fov_y);
    proj[0][0] = 1.0 / ((double)aspect * t);
    proj[1][1] = 1.0 / t;
    proj[2][2] = -((double)z_far + z_near) / ((double)z_far - z_near);
    proj[2][3] = -(2.0 * z_far * z_near) / ((double)z_far - z_near);
    proj[3][2] = -1.0;
    inv_proj[0][0] = (double)aspect * t;
    inv_proj[1][1] = t;
    inv_proj[2][3] = -1.0;
    inv_proj[3][2] = ((double)z_near - z_far) / (2.0 * z_far * z_near);
    inv_proj[3][3] = ((double)z_far + z_near) / (2.0 * z_far * z_near);

    matmul4(vp, proj, view);
    matmul4(ivp, inv_view, inv_proj);
    inv_view[0][3] = inv_view[1][3] = inv_view[2][3] = 0.0; /* the camera moved to the origin */
    matmul4(ivpr, inv_view, inv_proj);
    out->eye = eye;
    store_cm(out->view, view);
    store_cm(out->proj, proj);
    store_cm(out->view_proj, vp);
    store_cm(out->inv_view_proj, ivp);
    store_cm(out->inv_view_proj_rot, ivpr);
    return CCL_OK;
}

ccl_vec3 ccl_camera_ray(const float inv_view_proj_rot[16], int x, int y, int width, int height)
{
    const float *m = inv_view_proj_rot;
    float u, v, nx, ny, hx, hy, hz;
    CCL_REQUIRE(width >= 1 && height >= 1);
    u = ((float)x + 0.5f) / (float)width;
    v = ((float)y + 0.5f) / (float)height;
    nx = 2.0f * u - 1.0f;
    ny = 1.0f - 2.0f * v;
    /* h = M (nx, ny, 1, 1), the far-plane point relative to the eye times w > 0; m[c * 4 + r] = M[r][c] */
    hx = m[0] * nx + m[4] * ny + m[8] + m[12];
    hy = m[1] * nx + m[5] * ny + m[9] + m[13];
    hz = m[2] * nx + m[6] * ny + m[10] + m[14];
    return v3_normalize(v3(hx, hy, hz));
}

/* --- vc-A23: ray jitter ------------------------------------------------------------------------------------------ */

ccl_vec3 ccl_ray_jitter_tilt(ccl_vec3 d, uint32_t x, uint32_t y, uint32_t frame, float amount)
{
    uint32_t seed = jitter_seed(x, y, frame);
    float rx = 2.0f * hash_unit(pcg_hash(seed + 0u)) - 1.0f;
    float ry = 2.0f * hash_unit(pcg_hash(seed + 1u)) - 1.0f;
    float rz = 2.0f * hash_unit(pcg_hash(seed + 2u)) - 1.0f;
    CCL_REQUIRE(!(amount < 0.0f));
    return v3_normalize(v3_add(d, v3_scale(v3(rx, ry, rz), amount)));
}

float ccl_ray_jitter_offset(uint32_t x, uint32_t y, uint32_t frame)
{
    return hash_unit(pcg_hash(jitter_seed(x, y, frame) + 3u));
}

void ccl_ray_jitter_flat(float dx, float dy, float dz, int x, int y, int frame, float amount, int mode,
                         float *out_dx, float *out_dy, float *out_dz, float *out_offset)
{
    ccl_vec3 d = v3_normalize(v3(dx, dy, dz));
    float offset = 0.5f;
    if (mode == CCL_JITTER_TILT)
        d = ccl_ray_jitter_tilt(d, (uint32_t)x, (uint32_t)y, (uint32_t)frame, amount);
    else if (mode == CCL_JITTER_OFFSET)
        offset = ccl_ray_jitter_offset((uint32_t)x, (uint32_t)y, (uint32_t)frame);
    *out_dx = d.x;
    *out_dy = d.y;
    *out_dz = d.z;
    *out_offset = offset;
}

/* --- vc-A35: uniform march in a bounding volume ------------------------------------------------------------------ */

int ccl_march_interval(float t_near, float t_far, int n, float *out_t_start, float *out_dt)
{
    float ts;
    CCL_REQUIRE(n >= 1);
    if (!(t_far >= 0.0f) || !(t_near <= t_far)) {
        write_nan2(out_t_start, out_dt);
        return 0;
    }
    ts = (t_near > 0.0f) ? t_near : 0.0f;
    *out_t_start = ts;
    *out_dt = (t_far - ts) / (float)n;
    return 1;
}

ccl_vec3 ccl_march_point(ccl_vec3 o, ccl_vec3 d, float t_start, float dt, int i, float offset)
{
    float t = t_start + ((float)i + offset) * dt;
    return v3_add(o, v3_scale(d, t));
}

static int march_fill(ccl_vec3 o, ccl_vec3 d, float t0, float t1, int n, float offset, ccl_vec3 *out_points,
                      float *out_dt)
{
    float ts, dt;
    int i, hit = ccl_march_interval(t0, t1, n, &ts, &dt);
    for (i = 0; i < n; ++i) out_points[i] = ccl_march_point(o, d, ts, dt, i, offset);
    *out_dt = dt;
    return hit;
}

int ccl_march_sphere(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r, int n, float offset, ccl_vec3 *out_points,
                     float *out_dt)
{
    float t0, t1;
    ccl_vec3 u = v3_normalize(d);
    ccl_ray_sphere(o, u, c, r, &t0, &t1);
    return march_fill(o, u, t0, t1, n, offset, out_points, out_dt);
}

int ccl_march_box(ccl_vec3 o, ccl_vec3 d, ccl_vec3 bmin, ccl_vec3 bmax, int n, float offset, ccl_vec3 *out_points,
                  float *out_dt)
{
    float t0, t1;
    ccl_vec3 u = v3_normalize(d);
    ccl_ray_box(o, u, bmin, bmax, &t0, &t1);
    return march_fill(o, u, t0, t1, n, offset, out_points, out_dt);
}

/* --- vc-A36: constants ------------------------------------------------------------------------------------------- */

static const ccl_vc_constant_table vc_constants = {
    128, 4, 32, 3,
    {0.625f, 0.25f, 0.125f},
    {0.625f, 0.25f, 0.125f},
    0.2f,
    2.0f,
    {1.55f, 0.55f},
    {0.0f, 0.5f, 1.0f},
    {0.01f, 0.30f, 0.6f, 0.95f},
    {0.01f, 0.25f, 0.3f, 0.65f},
    {0.01f, 0.05f, 0.0f, 0.20f},
    64, 128,
    6, 5, 3.0f,
    4, 16,
    0.03f,
    {-0.32f, 10.0f, -3.0f, 0.45f},
    2.0f, 2.0f, 6.0f, 6.0f,
    400.0f, 10.0f, 700.0f,
};

const ccl_vc_constant_table *ccl_vc_constants(void)
{
    return &vc_constants;
}
