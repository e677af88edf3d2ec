/* The look-at + perspective camera and primary rays (vc-A25, pt-code-7.2). See cclouds/camera.h for the
 * conventions. pywarp/kernels/camera.py mirrors camera_look_at (float64, rounded once) and camera_ray (float32, the
 * same operations in the same order). */
#include "cclouds/camera.h"

#include <float.h>
#include <math.h>
#include "internal.h"

/* column-major store of a row-major double matrix */
static void store_cm(float dst[16], double m[4][4])
{
    int r, c;
    for (c = 0; c < 4; ++c)
        for (r = 0; r < 4; ++r) dst[c * 4 + r] = (float)m[r][c];
}

/* 1 when every entry of m rounds to a finite float (|x| <= FLT_MAX; NaN fails) */
static int fits_float(double m[4][4])
{
    int r, c;
    for (r = 0; r < 4; ++r)
        for (c = 0; c < 4; ++c)
            if (!(fabs(m[r][c]) <= (double)FLT_MAX)) return 0;
    return 1;
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
    f[0] = (double)target.x - (double)eye.x;
    f[1] = (double)target.y - (double)eye.y;
    f[2] = (double)target.z - (double)eye.z;
    n = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(n > 0.0)) return CCL_EINVAL;
    for (i = 0; i < 3; ++i) f[i] /= n;
    upd[0] = (double)up.x;
    upd[1] = (double)up.y;
    upd[2] = (double)up.z;
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
    view[0][3] = -(s[0] * (double)eye.x + s[1] * (double)eye.y + s[2] * (double)eye.z);
    view[1][3] = -(u[0] * (double)eye.x + u[1] * (double)eye.y + u[2] * (double)eye.z);
    view[2][3] = f[0] * (double)eye.x + f[1] * (double)eye.y + f[2] * (double)eye.z;
    view[3][3] = 1.0;
    inv_view[0][3] = (double)eye.x;
    inv_view[1][3] = (double)eye.y;
    inv_view[2][3] = (double)eye.z;
    inv_view[3][3] = 1.0;

    t = tan(0.5 * (double)fov_y);
    proj[0][0] = 1.0 / ((double)aspect * t);
    proj[1][1] = 1.0 / t;
    proj[2][2] = -((double)z_far + (double)z_near) / ((double)z_far - (double)z_near);
    proj[2][3] = -(2.0 * (double)z_far * (double)z_near) / ((double)z_far - (double)z_near);
    proj[3][2] = -1.0;
    inv_proj[0][0] = (double)aspect * t;
    inv_proj[1][1] = t;
    inv_proj[2][3] = -1.0;
    inv_proj[3][2] = ((double)z_near - (double)z_far) / (2.0 * (double)z_far * (double)z_near);
    inv_proj[3][3] = ((double)z_far + (double)z_near) / (2.0 * (double)z_far * (double)z_near);

    matmul4(vp, proj, view);
    matmul4(ivp, inv_view, inv_proj);
    inv_view[0][3] = inv_view[1][3] = inv_view[2][3] = 0.0; /* the camera moved to the origin */
    matmul4(ivpr, inv_view, inv_proj);
    /* an eye near FLT_MAX, aspect tan(fov_y / 2) or 1 / z_near beyond it: an entry overflows float32 (C9) */
    if (!(fits_float(view) && fits_float(proj) && fits_float(vp) && fits_float(ivp) && fits_float(ivpr)))
        return CCL_EINVAL;
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
    ccl_vec3 h;
    CCL_REQUIRE(width >= 1 && height >= 1);
    u = ((float)x + 0.5f) / (float)width;
    v = ((float)y + 0.5f) / (float)height;
    nx = 2.0f * u - 1.0f;
    ny = 1.0f - 2.0f * v;
    /* h = M (nx, ny, 1, 1), the far-plane point relative to the eye times w > 0; m[c * 4 + r] = M[r][c] */
    hx = m[0] * nx + m[4] * ny + m[8] + m[12];
    hy = m[1] * nx + m[5] * ny + m[9] + m[13];
    hz = m[2] * nx + m[6] * ny + m[10] + m[14];
    h.x = hx;
    h.y = hy;
    h.z = hz;
    return ccl_vec3_normalize(h);
}
