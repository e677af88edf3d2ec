/* One raindrop: Beard-Chuang shape, terminal speed, refraction masks, drop pixel colour, light-drop model (rr §2-3).
 * See cclouds/rain.h for the frames, units and readings. The Warp twins (pywarp/kernels/rain.py) perform the same
 * float32 operations in the same order. */
#include "cclouds/rain.h"
#include "cclouds/optics.h"
#include "internal.h"

/* Table 2.1: c_n x 1e4 for a = 0.5, 1.0, 3.0, 4.5 mm (rr-tab-2.1, Beard & Chuang 1987). */
static const float BC_A[CCL_RAIN_SHAPE_ROWS] = {0.5f, 1.0f, 3.0f, 4.5f};
static const float BC_C[CCL_RAIN_SHAPE_ROWS][CCL_RAIN_SHAPE_TERMS] = {
    {-28.0f, -30.0f, -83.0f, -22.0f, -3.0f, 2.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f},
    {-134.0f, -118.0f, -385.0f, -100.0f, -5.0f, 17.0f, 6.0f, -1.0f, -3.0f, -1.0f, 1.0f},
    {-843.0f, -472.0f, -2040.0f, -240.0f, 299.0f, 168.0f, -21.0f, -73.0f, -20.0f, 25.0f, 24.0f},
    {-1328.0f, -403.0f, -2889.0f, -106.0f, 662.0f, 153.0f, -146.0f, -111.0f, 18.0f, 81.0f, 31.0f}};

/* Table 2.2: radius [mm] -> terminal speed [m/s] (rr-tab-2.2, Gunn & Kinzer 1949). */
static const float TS_R[CCL_RAIN_SPEED_ROWS] = {0.1f, 0.15f, 0.2f, 0.25f, 0.3f, 0.35f, 0.4f, 0.45f, 0.5f, 0.75f, 1.0f,
                                                1.25f, 1.5f, 1.75f, 2.0f, 2.25f, 2.5f, 2.75f, 3.0f, 3.25f, 3.5f,
                                                3.75f, 4.0f};
static const float TS_V[CCL_RAIN_SPEED_ROWS] = {0.72f, 1.17f, 1.62f, 2.06f, 2.47f, 2.87f, 3.27f, 3.67f, 4.0f, 5.43f,
                                                6.59f, 7.46f, 8.1f, 8.58f, 8.91f, 9.11f, 9.2f, 9.23f, 9.23f, 9.23f,
                                                9.23f, 9.23f, 9.23f};

#define PI_F CCL_PI_F

static int interp_ok(float a, int interp)
{
    int k;
    if (interp == CCL_RAIN_INTERP_TABLE) {
        for (k = 0; k < CCL_RAIN_SHAPE_ROWS; ++k)
            if (a == BC_A[k]) return 1;
        return 0;
    }
    if (interp == CCL_RAIN_INTERP_LINEAR) return a >= 0.5f && a <= 4.5f;
    return 0;
}

float ccl_rain_drop_coefficient(int n, float a, ccl_rain_interp interp)
{
    int k;
    float w;
    CCL_REQUIRE(n >= 0 && n < CCL_RAIN_SHAPE_TERMS);
    if (n < 0 || n >= CCL_RAIN_SHAPE_TERMS || !interp_ok(a, (int)interp)) return NAN;
    if (interp == CCL_RAIN_INTERP_TABLE) {
        for (k = 0; k < CCL_RAIN_SHAPE_ROWS; ++k)
            if (a == BC_A[k]) return BC_C[k][n] * 1e-4f;
    }
    /* linear in a between the rows */
    k = 0;
    while (k < CCL_RAIN_SHAPE_ROWS - 2 && a >= BC_A[k + 1]) ++k;
    w = (a - BC_A[k]) / (BC_A[k + 1] - BC_A[k]);
    return BC_C[k][n] * 1e-4f * (1.0f - w) + BC_C[k + 1][n] * 1e-4f * w;
}

/* deform * C_n for n = 0..10 */
static void shape_coefs(float a, int interp, float deform, float *c)
{
    int n;
    for (n = 0; n < CCL_RAIN_SHAPE_TERMS; ++n) c[n] = deform * ccl_rain_drop_coefficient(n, a, (ccl_rain_interp)interp);
}

/* s = r / a = 1 + sum c_n cos(n theta) and ds = s'(theta) = -sum n c_n sin(n theta), from cos theta and sin theta
 * (cos/sin of n theta by the rotation recurrence) */
static float shape_eval(const float *c, float cos_t, float sin_t, float *ds)
{
    float cn = 1.0f, sn = 0.0f, s = 0.0f, d = 0.0f, cn1;
    int n;
    s = s + c[0] * cn;
    for (n = 1; n < CCL_RAIN_SHAPE_TERMS; ++n) {
        cn1 = cn * cos_t - sn * sin_t;
        sn = sn * cos_t + cn * sin_t;
        cn = cn1;
        s = s + c[n] * cn;
        d = d - (float)n * c[n] * sn;
    }
    *ds = d;
    return 1.0f + s;
}

float ccl_rain_drop_radius(float theta, float a, ccl_rain_interp interp)
{
    float c[CCL_RAIN_SHAPE_TERMS], ds;
    CCL_REQUIRE(!(theta < 0.0f || theta > PI_F));
    shape_coefs(a, (int)interp, 1.0f, c);
    return a * shape_eval(c, cosf(theta), sinf(theta), &ds);
}

/* outward unit normal of the shape s (per unit a) at cos/sin theta and azimuth cos/sin phi */
static ccl_vec3 shape_normal(float s, float ds, float cos_t, float sin_t, float cos_p, float sin_p)
{
    float nr = s * sin_t - ds * cos_t;
    float ny = -(s * cos_t + ds * sin_t);
    ccl_vec3 n;
    n.x = nr * cos_p;
    n.y = ny;
    n.z = nr * sin_p;
    return ccl_vec3_normalize(n);
}

ccl_vec3 ccl_rain_drop_surface(float theta, float phi, float a, ccl_rain_interp interp, ccl_vec3 *out_normal)
{
    float c[CCL_RAIN_SHAPE_TERMS], ds, s, r, ct, st, cp, sp;
    ccl_vec3 p;
    CCL_REQUIRE(!(theta < 0.0f || theta > PI_F));
    shape_coefs(a, (int)interp, 1.0f, c);
    ct = cosf(theta);
    st = sinf(theta);
    cp = cosf(phi);
    sp = sinf(phi);
    s = shape_eval(c, ct, st, &ds);
    r = a * s;
    p.x = r * st * cp;
    p.y = -r * ct;
    p.z = r * st * sp;
    *out_normal = shape_normal(s, ds, ct, st, cp, sp);
    return p;
}

#define VOLUME_INTERVALS 128
#define AXIS_SAMPLES 1024
#define EXTENT_SAMPLES 64

float ccl_rain_drop_volume(float a, ccl_rain_interp interp)
{
    float c[CCL_RAIN_SHAPE_TERMS], ds, h, th, s, w, acc = 0.0f;
    int k;
    shape_coefs(a, (int)interp, 1.0f, c);
    h = PI_F / (float)VOLUME_INTERVALS;
    for (k = 0; k <= VOLUME_INTERVALS; ++k) {
        th = (float)k * h;
        s = shape_eval(c, cosf(th), sinf(th), &ds);
        w = (k == 0 || k == VOLUME_INTERVALS) ? 1.0f : ((k % 2) ? 4.0f : 2.0f);
        acc = acc + w * (s * s * s * sinf(th));
    }
    /* (2 pi / 3) a^3 (h / 3) sum */
    return (2.0f * PI_F / 3.0f) * (h / 3.0f) * acc * (a * a * a);
}

float ccl_rain_drop_axis_ratio(float a, ccl_rain_interp interp)
{
    float c[CCL_RAIN_SHAPE_TERMS], ds, th, wmax = 0.0f, height;
    int k;
    shape_coefs(a, (int)interp, 1.0f, c);
    for (k = 0; k <= AXIS_SAMPLES; ++k) {
        th = (float)k * (PI_F / (float)AXIS_SAMPLES);
        wmax = fmaxf(wmax, shape_eval(c, cosf(th), sinf(th), &ds) * sinf(th));
    }
    height = shape_eval(c, 1.0f, 0.0f, &ds) + shape_eval(c, -1.0f, 0.0f, &ds);
    return height / (2.0f * wmax);
}

/* the extent per unit a of the shape with coefficients c (see ccl_rain_drop_extent) */
static float shape_extent(const float *c)
{
    float ds, th, smax = 0.0f, bound = 0.0f, h = PI_F / (float)EXTENT_SAMPLES;
    int k, n;
    for (k = 0; k <= EXTENT_SAMPLES; ++k) {
        th = (float)k * h;
        smax = fmaxf(smax, shape_eval(c, cosf(th), sinf(th), &ds));
    }
    for (n = 1; n < CCL_RAIN_SHAPE_TERMS; ++n) bound = bound + (float)(n * n) * fabsf(c[n]);
    return smax + (h * h * 0.125f) * bound;
}

float ccl_rain_drop_extent(float a, ccl_rain_interp interp)
{
    float c[CCL_RAIN_SHAPE_TERMS];
    shape_coefs(a, (int)interp, 1.0f, c);
    return a * shape_extent(c);
}

float ccl_rain_terminal_speed(float radius_mm, float slowdown)
{
    int k;
    float r = radius_mm, v, w, q;
    CCL_REQUIRE(!(radius_mm < 0.0f || slowdown <= 0.0f));
    if (r < TS_R[0]) {
        q = r / TS_R[0]; /* Stokes: v proportional to r^2 */
        v = TS_V[0] * (q * q);
    } else if (r >= TS_R[CCL_RAIN_SPEED_ROWS - 1]) {
        v = TS_V[CCL_RAIN_SPEED_ROWS - 1];
    } else {
        k = 0;
        while (k < CCL_RAIN_SPEED_ROWS - 2 && r >= TS_R[k + 1]) ++k;
        w = (r - TS_R[k]) / (TS_R[k + 1] - TS_R[k]);
        /* V_k + w (V_k+1 - V_k): the difference is exact (Sterbenz: each row at most doubles the speed), so v is
         * non-decreasing in w and reaches V_k+1 at most; V_k (1 - w) + V_k+1 w, rounded twice, fell by an ulp as r
         * grew (fuzz finding I4) */
        v = TS_V[k] + w * (TS_V[k + 1] - TS_V[k]);
    }
    return v / slowdown;
}

/* --- masks ---------------------------------------------------------------------------------------------------------- */

/* implicit function of the drop (per unit a): |p| - s(theta(p)); <= 0 inside */
static float drop_f(const float *c, ccl_vec3 p)
{
    float r = ccl_vec3_length(p), rh, ds;
    if (r == 0.0f) return -1.0f;
    rh = sqrtf(p.x * p.x + p.z * p.z);
    return r - shape_eval(c, -p.y / r, rh / r, &ds);
}

static ccl_vec3 drop_normal(const float *c, ccl_vec3 p)
{
    float r = ccl_vec3_length(p), rh, ct, st, s, ds, cp = 1.0f, sp = 0.0f;
    if (r == 0.0f) return v3(0.0f, -1.0f, 0.0f);
    rh = sqrtf(p.x * p.x + p.z * p.z);
    ct = -p.y / r;
    st = rh / r;
    if (rh > 0.0f) {
        cp = p.x / rh;
        sp = p.z / rh;
    }
    s = shape_eval(c, ct, st, &ds);
    return shape_normal(s, ds, ct, st, cp, sp);
}

/* from pos on the surface, along dir (into the drop): the next surface point; *out_n its outward normal.
 * sphere != 0: the unit sphere, analytically; else the shape c, marched inside the bounding sphere of radius ext. */
static ccl_vec3 exit_hit(int sphere, const float *c, float ext, ccl_vec3 pos, ccl_vec3 dir, ccl_vec3 *out_n)
{
    float b, cc, smax, lo, hi, mid, s;
    int k, found = 0;
    ccl_vec3 q;
    if (sphere) {
        s = -2.0f * ccl_vec3_dot(pos, dir);
        q = ccl_vec3_add(pos, ccl_vec3_scale(dir, s));
        *out_n = ccl_vec3_normalize(q);
        return q;
    }
    b = ccl_vec3_dot(pos, dir);
    cc = ccl_vec3_dot(pos, pos) - ext * ext;
    smax = -b + sqrtf(fmaxf(b * b - cc, 0.0f));
    lo = 0.0f;
    hi = smax;
    for (k = 1; k <= CCL_RAIN_TRACE_STEPS; ++k) {
        s = smax * ((float)k / (float)CCL_RAIN_TRACE_STEPS);
        if (!found) {
            if (drop_f(c, ccl_vec3_add(pos, ccl_vec3_scale(dir, s))) > 0.0f) {
                hi = s;
                found = 1;
            } else {
                lo = s;
            }
        }
    }
    for (k = 0; k < CCL_RAIN_TRACE_BISECTIONS; ++k) {
        mid = 0.5f * (lo + hi);
        if (drop_f(c, ccl_vec3_add(pos, ccl_vec3_scale(dir, mid))) > 0.0f) hi = mid;
        else lo = mid;
    }
    q = ccl_vec3_add(pos, ccl_vec3_scale(dir, 0.5f * (lo + hi)));
    *out_n = drop_normal(c, q);
    return q;
}

ccl_vec3 ccl_rain_mask_texel(float u, float v, float a, float deform, float n_water, ccl_rain_interp interp,
                             ccl_rain_mask_method method, ccl_vec3 *out_normal, int *out_inside)
{
    float c[CCL_RAIN_SHAPE_TERMS], ext = 1.0f, x, y, rho, s, ds, h, lo, hi, mid, z;
    int k, sphere, tir, done = 0;
    ccl_vec3 zero = v3(0.0f, 0.0f, 0.0f), d = v3(0.0f, 0.0f, 1.0f), p, nrm, dir, q, nq, out, r, e = zero;
    *out_normal = zero;
    *out_inside = 0;
    sphere = (method != CCL_RAIN_MASK_EXACT);
    if (method == CCL_RAIN_MASK_SPHERE) {
        x = u;
        y = v;
        if (x * x + y * y > 1.0f) return zero;
    } else {
        shape_coefs(a, (int)interp, deform, c);
        ext = shape_extent(c);
        x = u * ext;
        y = v * ext;
        rho = sqrtf(x * x + y * y);
        s = 1.0f;
        if (rho > 0.0f) s = shape_eval(c, -y / rho, fabsf(x) / rho, &ds);
        if (rho > s) return zero; /* outside the outline (the drop's mid-plane section) */
        if (method == CCL_RAIN_MASK_OUTLINE) {
            x = x / s; /* stretch the outline onto the unit sphere */
            y = y / s;
        }
    }
    *out_inside = 1;
    if (sphere) {
        p = v3(x, y, -sqrtf(fmaxf(1.0f - x * x - y * y, 0.0f)));
        nrm = ccl_vec3_normalize(p);
    } else {
        /* entry: first sign change of the implicit function from the bounding sphere to the mid-plane (inside) */
        h = sqrtf(fmaxf(ext * ext - (x * x + y * y), 0.0f));
        lo = -h;
        hi = 0.0f;
        for (k = 1; k <= CCL_RAIN_TRACE_STEPS; ++k) {
            z = -h + h * ((float)k / (float)CCL_RAIN_TRACE_STEPS);
            if (!done) {
                if (drop_f(c, v3(x, y, z)) <= 0.0f) {
                    hi = z;
                    done = 1;
                } else {
                    lo = z;
                }
            }
        }
        for (k = 0; k < CCL_RAIN_TRACE_BISECTIONS; ++k) {
            mid = 0.5f * (lo + hi);
            if (drop_f(c, v3(x, y, mid)) <= 0.0f) hi = mid;
            else lo = mid;
        }
        p = v3(x, y, 0.5f * (lo + hi));
        nrm = drop_normal(c, p);
        done = 0;
    }
    *out_normal = nrm;
    dir = ccl_optics_snell(d, nrm, 1.0f, n_water, &r, &tir);
    for (k = 0; k <= CCL_RAIN_MASK_MAX_REFLECTIONS; ++k) {
        if (!done) {
            q = exit_hit(sphere, c, ext, p, dir, &nq);
            out = ccl_optics_snell(dir, nq, n_water, 1.0f, &r, &tir);
            if (tir && sphere) {
                /* a sphere reflects nothing totally (the exit angle equals the entry's refraction angle); at the rim
                 * rounding can push k = 1 - eta^2 sin^2 below 0: leave tangentially, the limit k -> 0 */
                out = ccl_vec3_normalize(ccl_vec3_sub(dir, ccl_vec3_scale(nq, ccl_vec3_dot(dir, nq))));
                tir = 0;
            }
            if (!tir) {
                e = out;
                done = 1;
            } else {
                p = q;
                dir = r;
            }
        }
    }
    return e;
}

ccl_status ccl_rain_mask(int size, float a, float deform, float n_water, ccl_rain_interp interp,
                         ccl_rain_mask_method method, float *out_rgba, float *out_normals)
{
    int i, j, inside;
    size_t o;
    float u, v;
    ccl_vec3 e, n;
    if (out_rgba == NULL || size < 1 || size > 4096) return CCL_EINVAL;
    if (!(deform >= 0.0f && deform <= 1.0f) || !(n_water >= 1.0f && n_water <= 2.0f)) return CCL_EINVAL;
    if (method != CCL_RAIN_MASK_SPHERE && method != CCL_RAIN_MASK_OUTLINE && method != CCL_RAIN_MASK_EXACT)
        return CCL_EINVAL;
    if (method != CCL_RAIN_MASK_SPHERE && !interp_ok(a, (int)interp)) return CCL_EINVAL;
    for (i = 0; i < size; ++i) {
        v = 1.0f - 2.0f * ((float)i + 0.5f) / (float)size;
        for (j = 0; j < size; ++j) {
            u = 2.0f * ((float)j + 0.5f) / (float)size - 1.0f;
            e = ccl_rain_mask_texel(u, v, a, deform, n_water, interp, method, &n, &inside);
            o = (size_t)i * (size_t)size + (size_t)j;
            out_rgba[o * 4 + 0] = e.x;
            out_rgba[o * 4 + 1] = e.y;
            out_rgba[o * 4 + 2] = e.z;
            out_rgba[o * 4 + 3] = (float)inside;
            if (out_normals != NULL) {
                out_normals[o * 3 + 0] = n.x;
                out_normals[o * 3 + 1] = n.y;
                out_normals[o * 3 + 2] = n.z;
            }
        }
    }
    return CCL_OK;
}

/* --- drop pixel colour ---------------------------------------------------------------------------------------------- */

ccl_vec2 ccl_rain_refracted_uv(ccl_vec3 view_dir, ccl_vec3 exit_dir, float tan_half_fov, float aspect,
                               ccl_rain_mapping mapping, ccl_vec2 *out_p_o, int *out_valid)
{
    float sx = 0.5f / (tan_half_fov * aspect), sy = 0.5f / tan_half_fov, len;
    ccl_vec2 po, pc;
    ccl_vec3 f = view_dir, up = v3(0.0f, 1.0f, 0.0f), rt, uu, w;
    po.x = 0.0f;
    po.y = 0.0f;
    pc = po;
    *out_p_o = po;
    *out_valid = 0;
    if (!(f.z < 0.0f) || !(exit_dir.z > 0.0f)) return pc;
    po.x = 0.5f + sx * (f.x / -f.z);
    po.y = 0.5f - sy * (f.y / -f.z);
    if (mapping == CCL_RAIN_MAPPING_OFFSET) {
        /* the shader: P_c = P_o + refract.xy / refract.z, in capture uv (v down) */
        pc.x = po.x + sx * (exit_dir.x / exit_dir.z);
        pc.y = po.y - sy * (exit_dir.y / exit_dir.z);
    } else {
        rt = ccl_vec3_cross(f, up);
        len = ccl_vec3_length(rt);
        rt = (len > 1e-6f) ? ccl_vec3_scale(rt, 1.0f / len) : v3(1.0f, 0.0f, 0.0f);
        uu = ccl_vec3_cross(rt, f);
        w = ccl_vec3_add(ccl_vec3_add(ccl_vec3_scale(rt, exit_dir.x), ccl_vec3_scale(uu, exit_dir.y)),
                         ccl_vec3_scale(f, exit_dir.z));
        if (!(w.z < 0.0f)) return pc;
        pc.x = 0.5f + sx * (w.x / -w.z);
        pc.y = 0.5f - sy * (w.y / -w.z);
    }
    *out_p_o = po;
    *out_valid = 1;
    return pc;
}

static int clampi(int i, int lo, int hi)
{
    return i < lo ? lo : (i > hi ? hi : i);
}

/* floor of x clamped to [lo, hi], safe for any float */
static int floor_clamped(float x, int lo, int hi)
{
    x = fminf(fmaxf(x, (float)lo - 1.0f), (float)hi + 1.0f);
    return clampi((int)floorf(x), lo, hi);
}

static ccl_vec3 texel(const float *rgb, int width, int i, int j)
{
    const float *t = rgb + ((size_t)i * (size_t)width + (size_t)j) * 3;
    return v3(t[0], t[1], t[2]);
}

ccl_vec3 ccl_rain_sample_capture(const float *rgb, int width, int height, ccl_vec2 uv, ccl_rain_filter filter)
{
    float x, y, fx, fy;
    int j0, i0, j1, i1;
    ccl_vec3 a, b, top, bot;
    if (filter == CCL_RAIN_FILTER_NEAREST) {
        return texel(rgb, width, floor_clamped(uv.y * (float)height, 0, height - 1),
                     floor_clamped(uv.x * (float)width, 0, width - 1));
    }
    x = fminf(fmaxf(uv.x * (float)width - 0.5f, -1.0f), (float)width);
    y = fminf(fmaxf(uv.y * (float)height - 0.5f, -1.0f), (float)height);
    fx = x - floorf(x);
    fy = y - floorf(y);
    j0 = clampi((int)floorf(x), 0, width - 1);
    j1 = clampi((int)floorf(x) + 1, 0, width - 1);
    i0 = clampi((int)floorf(y), 0, height - 1);
    i1 = clampi((int)floorf(y) + 1, 0, height - 1);
    a = texel(rgb, width, i0, j0);
    b = texel(rgb, width, i0, j1);
    top = ccl_vec3_add(ccl_vec3_scale(a, 1.0f - fx), ccl_vec3_scale(b, fx));
    a = texel(rgb, width, i1, j0);
    b = texel(rgb, width, i1, j1);
    bot = ccl_vec3_add(ccl_vec3_scale(a, 1.0f - fx), ccl_vec3_scale(b, fx));
    return ccl_vec3_add(ccl_vec3_scale(top, 1.0f - fy), ccl_vec3_scale(bot, fy));
}

ccl_status ccl_rain_shade_drop(const float *capture, int cap_w, int cap_h, const float *mask, int mask_size,
                               ccl_vec3 centre_dir, float angular_radius, float tan_half_fov, float aspect,
                               ccl_rain_mapping mapping, ccl_rain_filter filter, int out_size, float *out_rgba)
{
    int i, j, mi, mj, valid;
    size_t o, m;
    float u, v, t, len;
    ccl_vec3 f = centre_dir, up = v3(0.0f, 1.0f, 0.0f), rt, uu, dir, e, col;
    ccl_vec2 pc, po;
    if (capture == NULL || mask == NULL || out_rgba == NULL) return CCL_EINVAL;
    if (cap_w < 1 || cap_h < 1 || mask_size < 1 || out_size < 1 || out_size > 4096) return CCL_EINVAL;
    if (!(angular_radius > 0.0f && angular_radius <= 0.5f) || !(tan_half_fov > 0.0f && tan_half_fov <= 100.0f) ||
        !(aspect > 0.0f && aspect <= 100.0f) || !(centre_dir.z < 0.0f))
        return CCL_EINVAL;
    rt = ccl_vec3_cross(f, up);
    len = ccl_vec3_length(rt);
    rt = (len > 1e-6f) ? ccl_vec3_scale(rt, 1.0f / len) : v3(1.0f, 0.0f, 0.0f);
    uu = ccl_vec3_cross(rt, f);
    t = tanf(angular_radius);
    for (i = 0; i < out_size; ++i) {
        for (j = 0; j < out_size; ++j) {
            o = ((size_t)i * (size_t)out_size + (size_t)j) * 4;
            u = 2.0f * ((float)j + 0.5f) / (float)out_size - 1.0f;
            v = 1.0f - 2.0f * ((float)i + 0.5f) / (float)out_size;
            mi = clampi((int)floorf((1.0f - v) * 0.5f * (float)mask_size), 0, mask_size - 1);
            mj = clampi((int)floorf((u + 1.0f) * 0.5f * (float)mask_size), 0, mask_size - 1);
            m = ((size_t)mi * (size_t)mask_size + (size_t)mj) * 4;
            out_rgba[o + 0] = 0.0f;
            out_rgba[o + 1] = 0.0f;
            out_rgba[o + 2] = 0.0f;
            out_rgba[o + 3] = 0.0f;
            if (!(mask[m + 3] > 0.0f)) continue;
            out_rgba[o + 3] = 1.0f;
            e = v3(mask[m + 0], mask[m + 1], mask[m + 2]);
            dir = ccl_vec3_normalize(ccl_vec3_add(f, ccl_vec3_scale(ccl_vec3_add(ccl_vec3_scale(rt, u),
                                                                                 ccl_vec3_scale(uu, v)), t)));
            pc = ccl_rain_refracted_uv(dir, e, tan_half_fov, aspect, mapping, &po, &valid);
            if (!valid) continue;
            col = ccl_rain_sample_capture(capture, cap_w, cap_h, pc, filter);
            out_rgba[o + 0] = col.x;
            out_rgba[o + 1] = col.y;
            out_rgba[o + 2] = col.z;
        }
    }
    return CCL_OK;
}

/* the radii whose square is a normal float (2^-60, 2^60) */
#define PARALLAX_SQUARE_MIN 8.67361737988403547e-19f
#define PARALLAX_SQUARE_MAX 1.152921504606846976e18f

float ccl_rain_capture_parallax(ccl_vec3 p, ccl_vec3 e, float R)
{
    float pp, pe, s;
    ccl_vec3 q;
    CCL_REQUIRE(!(R <= 0.0f));
    /* the angle does not depend on the scale: a radius whose square under- or overflows (0 or Inf: NaN below) is
     * divided out, p / R and R = 1; any other radius is used as it is */
    if (!(R >= PARALLAX_SQUARE_MIN && R <= PARALLAX_SQUARE_MAX)) {
        p.x /= R;
        p.y /= R;
        p.z /= R;
        R = 1.0f;
    }
    pp = ccl_vec3_dot(p, p);
    if (!(pp < R * R)) return NAN; /* the drop is not inside the background sphere */
    pe = ccl_vec3_dot(p, e);
    s = -pe + sqrtf(fmaxf(pe * pe - pp + R * R, 0.0f));
    q = ccl_vec3_add(p, ccl_vec3_scale(e, s));
    return atan2f(ccl_vec3_length(ccl_vec3_cross(e, q)), ccl_vec3_dot(e, q));
}

/* --- light-drop interaction ----------------------------------------------------------------------------------------- */

ccl_vec3 ccl_rain_light_a1(ccl_vec3 c_l, float dist, ccl_vec3 v_pe, ccl_vec3 v_n, float r_half, ccl_variant variant)
{
    float q = dist / r_half, dist_fact = 1.0f / (1.0f + q * q), cosv = ccl_vec3_dot(v_pe, v_n);
    CCL_REQUIRE(!(r_half <= 0.0f || dist < 0.0f));
    if (variant != CCL_VARIANT_THESIS) cosv = fmaxf(cosv, 0.0f);
    return ccl_vec3_scale(c_l, dist_fact * cosv);
}

float ccl_rain_light_a2(ccl_vec3 v_pl, ccl_vec3 v_n)
{
    /* the dot of two unit vectors rounds up to 1 + 2^-22 (0.577350318 (1, 1, 1), fuzz finding I2): at most 1 */
    const float a = fmaxf(0.0f, ccl_vec3_dot(v_pl, v_n));
    return a > 1.0f ? 1.0f : a;
}

float ccl_rain_light_a3(ccl_vec3 v_pl, ccl_vec3 v_n)
{
    float lh = sqrtf(v_pl.x * v_pl.x + v_pl.z * v_pl.z), nh = sqrtf(v_n.x * v_n.x + v_n.z * v_n.z), horiz = 0.0f;
    if (lh >= 1e-6f && nh >= 1e-6f) horiz = -((v_pl.x / lh) * (v_n.x / nh) + (v_pl.z / lh) * (v_n.z / nh));
    return fmaxf(0.0f, horiz * (1.0f - (-ccl_vec3_dot(v_pl, v_n))));
}

static ccl_vec3 one_light(ccl_vec3 p, ccl_vec3 n, ccl_vec3 v_pe, ccl_vec3 l, ccl_vec3 c_l, float r_half,
                          ccl_variant variant)
{
    ccl_vec3 d = ccl_vec3_sub(l, p), v_pl, a1;
    float dist = ccl_vec3_length(d);
    v_pl = ccl_vec3_normalize(d);
    a1 = ccl_rain_light_a1(c_l, dist, v_pe, n, r_half, variant);
    return ccl_vec3_scale(a1, ccl_rain_light_a2(v_pl, n) + ccl_rain_light_a3(v_pl, n));
}

ccl_vec3 ccl_rain_light_colour(ccl_vec3 c_o, ccl_vec3 c_amb, ccl_vec3 p, ccl_vec3 n, ccl_vec3 eye, ccl_vec3 l1,
                               ccl_vec3 c_l1, ccl_vec3 l2, ccl_vec3 c_l2, float r_half, ccl_variant variant)
{
    ccl_vec3 v_pe = ccl_vec3_normalize(ccl_vec3_sub(eye, p)), base;
    base = v3(c_o.x * c_amb.x, c_o.y * c_amb.y, c_o.z * c_amb.z);
    base = ccl_vec3_add(base, one_light(p, n, v_pe, l1, c_l1, r_half, variant));
    return ccl_vec3_add(base, one_light(p, n, v_pe, l2, c_l2, r_half, variant));
}
