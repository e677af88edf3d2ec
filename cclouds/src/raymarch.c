/* View-ray geometry of the cloudscape (vc §2.2, §4.2.1, §4.3.2). See cclouds/raymarch.h for the conventions.
 * Every float32 expression here is mirrored operation by operation in pywarp/kernels/raymarch.py; the vector maths
 * is common.h's (Warp's builtins), the hash hash.h's. */
#include "cclouds/raymarch.h"
#include "cclouds/hash.h"
#include "internal.h"

#include <float.h>

/* Seed of pixel (x, y) in frame `frame`: pcg(x + pcg(y + pcg(frame))) (vc-A23). */
static uint32_t jitter_seed(uint32_t x, uint32_t y, uint32_t frame)
{
    return ccl_hash_pcg(x + ccl_hash_pcg(y + ccl_hash_pcg(frame)));
}

static void write_nan2(float *a, float *b)
{
    *a = NAN;
    *b = NAN;
}

/* --- vc-A14: ray-sphere ------------------------------------------------------------------------------------------ */

int ccl_raymarch_ray_sphere(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r, float *out_t0, float *out_t1)
{
    ccl_vec3 f, l;
    float b, ll, disc, s, q, ff, cq, ta, tb;
    CCL_REQUIRE(!(r <= 0.0f));
    f = ccl_vec3_sub(o, c);
    b = ccl_vec3_dot(f, d);
    l = ccl_vec3_sub(f, ccl_vec3_scale(d, b)); /* closest-approach vector: |l| = distance of the line from c */
    ll = ccl_vec3_length(l);
    disc = (r - ll) * (r + ll);
    if (!(disc >= 0.0f)) { /* miss, or NaN input */
        write_nan2(out_t0, out_t1);
        return 0;
    }
    s = sqrtf(disc);
    q = (b >= 0.0f) ? -(b + s) : s - b; /* -b - sign(b) s: no cancellation */
    ff = ccl_vec3_length(f);
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

int ccl_raymarch_ray_box(ccl_vec3 o, ccl_vec3 d, ccl_vec3 bmin, ccl_vec3 bmax, float *out_t0, float *out_t1)
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

int ccl_raymarch_layer_segment(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r_earth, float r_inner, float r_outer,
                      float *out_t_start, float *out_t_end)
{
    ccl_vec3 f = ccl_vec3_sub(o, c);
    float rho = ccl_vec3_length(f);
    float t0, t1, ts, te;
    CCL_REQUIRE(!(r_earth <= 0.0f || r_inner < r_earth || r_outer <= r_inner));
    if (rho < r_inner) {
        /* below the layer (vc-A14): the Earth blocks every ray whose far root lies ahead */
        if (ccl_raymarch_ray_sphere(o, d, c, r_earth, &t0, &t1) && t1 > 0.0f) {
            write_nan2(out_t_start, out_t_end);
            return 0;
        }
        ccl_raymarch_ray_sphere(o, d, c, r_inner, &t0, &t1);
        ts = t1;
        ccl_raymarch_ray_sphere(o, d, c, r_outer, &t0, &t1);
        te = t1;
    } else if (rho <= r_outer) {
        /* inside the layer (vc-A24): from the camera to the first exit */
        ts = 0.0f;
        if (ccl_raymarch_ray_sphere(o, d, c, r_inner, &t0, &t1) && t0 > 0.0f) {
            te = t0;
        } else {
            ccl_raymarch_ray_sphere(o, d, c, r_outer, &t0, &t1);
            te = t1;
        }
    } else {
        /* above the layer (vc-A24): enter the outer sphere, leave through the inner one (the Earth is inside it) */
        if (!ccl_raymarch_ray_sphere(o, d, c, r_outer, &t0, &t1) || !(t1 > 0.0f)) {
            write_nan2(out_t_start, out_t_end);
            return 0;
        }
        ts = (t0 > 0.0f) ? t0 : 0.0f;
        te = t1;
        if (ccl_raymarch_ray_sphere(o, d, c, r_inner, &t0, &t1) && t0 > 0.0f) te = t0;
    }
    if (!(te >= ts)) { /* NaN input or a numerically empty interval */
        write_nan2(out_t_start, out_t_end);
        return 0;
    }
    *out_t_start = ts;
    *out_t_end = te;
    return 1;
}

void ccl_raymarch_cloud_layer_default(ccl_cloud_layer *out)
{
    ccl_status st = ccl_raymarch_cloud_layer_init(6371.0f, 1.5f, 4.0f, out);
    (void)st;
    CCL_REQUIRE(st == CCL_OK);
}

ccl_status ccl_raymarch_cloud_layer_init(float earth_radius, float base_altitude, float top_altitude,
                                         ccl_cloud_layer *out)
{
    if (!out || !isfinite(earth_radius) || !isfinite(base_altitude) || !isfinite(top_altitude) || earth_radius <= 0.0f
        || base_altitude < 0.0f || !(top_altitude > base_altitude))
        return CCL_EINVAL;
    out->centre.x = 0.0f;
    out->centre.y = -earth_radius;
    out->centre.z = 0.0f;
    out->r_earth = earth_radius;
    out->r_inner = earth_radius + base_altitude;
    out->r_outer = earth_radius + top_altitude;
    if (!(out->r_outer > out->r_inner)) return CCL_EINVAL; /* altitudes below the float32 resolution of the radius */
    return CCL_OK;
}

/* --- vc-A18: view-sample count ----------------------------------------------------------------------------------- */

int ccl_raymarch_view_sample_count(float dir_y, int n_min, int n_max)
{
    float ay = fabsf(dir_y);
    float n;
    CCL_REQUIRE(n_min >= 1 && n_min <= n_max && n_max <= CCL_RAYMARCH_MAX_VIEW_SAMPLES);
    if (!(ay < 1.0f)) ay = (ay >= 1.0f) ? 1.0f : 0.0f; /* |y| > 1 from rounding -> 1; NaN -> 0 (n_max samples) */
    n = floorf((float)n_max + (float)(n_min - n_max) * ay + 0.5f);
    /* in [n_min, n_max] on the domain; the clamps keep a count beyond it (n_max near INT_MAX rounds up to 2^31 in
     * float32) from reaching an overflowing float -> int conversion */
    if (!(n < (float)n_max)) return n_max;
    if (n < (float)n_min) return n_min;
    return (int)n;
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

ccl_vec3 ccl_raymarch_light_cone_kernel(int i)
{
    int j = ((i % 6) + 6) % 6;
    ccl_vec3 k;
    k.x = light_cone_kernel[j][0];
    k.y = light_cone_kernel[j][1];
    k.z = light_cone_kernel[j][2];
    return k;
}

ccl_vec3 ccl_raymarch_light_sample_position(ccl_vec3 p, ccl_vec3 to_sun, int i, float step, float cone_angle,
                                            float far_factor, ccl_vec3 k)
{
    float s, radius;
    CCL_REQUIRE(i >= 0 && i <= 5);
    CCL_REQUIRE(!(step <= 0.0f) && !(cone_angle < 0.0f));
    s = (i < 5) ? (float)(i + 1) * step : far_factor * (5.0f * step);
    radius = s * tanf(cone_angle);
    return ccl_vec3_add(ccl_vec3_add(p, ccl_vec3_scale(to_sun, s)), ccl_vec3_scale(k, radius));
}

/* --- vc-A21: accumulation and early termination ------------------------------------------------------------------ */

ccl_vec3 ccl_raymarch_accumulate(ccl_vec3 colour, float transmittance, float sigma, float rho, float dt,
                                 ccl_vec3 light, float eps, float *out_transmittance, int *out_stop)
{
    float tau = sigma * rho * dt;
    float e = expf(-tau);
    float w = transmittance * (1.0f - e);
    float t = transmittance * e;
    *out_transmittance = t;
    *out_stop = (1.0f - t) >= (1.0f - eps);
    return ccl_vec3_add(colour, ccl_vec3_scale(light, w));
}

/* --- vc-A23: ray jitter ------------------------------------------------------------------------------------------ */

ccl_vec3 ccl_raymarch_jitter_tilt(ccl_vec3 d, uint32_t x, uint32_t y, uint32_t frame, float amount)
{
    uint32_t seed = jitter_seed(x, y, frame);
    ccl_vec3 r;
    CCL_REQUIRE(!(amount < 0.0f));
    r.x = 2.0f * ccl_hash_unit(ccl_hash_pcg(seed + 0u)) - 1.0f;
    r.y = 2.0f * ccl_hash_unit(ccl_hash_pcg(seed + 1u)) - 1.0f;
    r.z = 2.0f * ccl_hash_unit(ccl_hash_pcg(seed + 2u)) - 1.0f;
    return ccl_vec3_normalize(ccl_vec3_add(d, ccl_vec3_scale(r, amount)));
}

float ccl_raymarch_jitter_offset(uint32_t x, uint32_t y, uint32_t frame)
{
    return ccl_hash_unit(ccl_hash_pcg(jitter_seed(x, y, frame) + 3u));
}

ccl_vec3 ccl_raymarch_jitter(ccl_vec3 d, uint32_t x, uint32_t y, uint32_t frame, float amount, ccl_jitter_mode mode,
                             float *out_offset)
{
    *out_offset = 0.5f;
    if (mode == CCL_JITTER_TILT) return ccl_raymarch_jitter_tilt(d, x, y, frame, amount);
    if (mode == CCL_JITTER_OFFSET) *out_offset = ccl_raymarch_jitter_offset(x, y, frame);
    return d;
}

/* --- vc-A35: uniform march in a bounding volume ------------------------------------------------------------------ */

int ccl_raymarch_interval(float t_near, float t_far, int n, float *out_t_start, float *out_dt)
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

ccl_vec3 ccl_raymarch_point(ccl_vec3 o, ccl_vec3 d, float t_start, float dt, int i, float offset)
{
    float t = t_start + ((float)i + offset) * dt;
    return ccl_vec3_add(o, ccl_vec3_scale(d, t));
}

static int march_fill(ccl_vec3 o, ccl_vec3 d, float t0, float t1, int n, float offset, ccl_vec3 *out_points,
                      float *out_dt)
{
    float ts, dt;
    int i, hit = ccl_raymarch_interval(t0, t1, n, &ts, &dt);
    for (i = 0; i < n; ++i) out_points[i] = ccl_raymarch_point(o, d, ts, dt, i, offset);
    *out_dt = dt;
    return hit;
}

int ccl_raymarch_sphere(ccl_vec3 o, ccl_vec3 d, ccl_vec3 c, float r, int n, float offset, ccl_vec3 *out_points,
                     float *out_dt)
{
    float t0, t1;
    ccl_vec3 u = ccl_vec3_normalize(d);
    ccl_raymarch_ray_sphere(o, u, c, r, &t0, &t1);
    return march_fill(o, u, t0, t1, n, offset, out_points, out_dt);
}

int ccl_raymarch_box(ccl_vec3 o, ccl_vec3 d, ccl_vec3 bmin, ccl_vec3 bmax, int n, float offset, ccl_vec3 *out_points,
                  float *out_dt)
{
    float t0, t1;
    ccl_vec3 u = ccl_vec3_normalize(d);
    ccl_raymarch_ray_box(o, u, bmin, bmax, &t0, &t1);
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

const ccl_vc_constant_table *ccl_raymarch_vc_constants(void)
{
    return &vc_constants;
}
