/* C unit tests of cclouds/camera.h: the look-at and perspective matrices, primary rays through pixel centres (the
 * camera of vc-A25 and pt-code-7.2), bad input. */
#include "cclouds/camera.h"
#include "ccl_test.h"

#include <string.h>

static void test_camera_look_at_and_rays(void)
{
    ccl_camera cam;
    int r, c, k;
    const float fov = 1.0f;
    /* eye at the origin looking down -z, up +y: the view matrix is the identity */
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), fov, 2.0f, 0.01f, 1000.0f, &cam) == CCL_OK);
    for (r = 0; r < 4; ++r)
        for (c = 0; c < 4; ++c) CCL_CHECK_CLOSE(cam.view[c * 4 + r], r == c ? 1.0 : 0.0, 0.0);
    /* projection entries (GLM perspective) */
    CCL_CHECK_REL(cam.proj[5], 1.0 / tan(0.5), 1e-6);
    CCL_CHECK_REL(cam.proj[0], 1.0 / (2.0 * tan(0.5)), 1e-6);
    CCL_CHECK_CLOSE(cam.proj[11], -1.0, 0.0);
    /* a general camera: inv_view_proj * view_proj == I to float32 accuracy */
    CCL_CHECK(ccl_camera_look_at(V(3, 0.5f, 7), V(2, 0.6f, 6), V(0, 1, 0), fov, 1.5f, 0.01f, 100.0f, &cam) == CCL_OK);
    for (r = 0; r < 4; ++r)
        for (c = 0; c < 4; ++c) {
            double s = 0.0;
            for (k = 0; k < 4; ++k) s += (double)cam.inv_view_proj[k * 4 + r] * (double)cam.view_proj[c * 4 + k];
            CCL_CHECK_CLOSE(s, r == c ? 1.0 : 0.0, 2e-4);
        }
    /* the centre pixel of an odd-size image looks along target - eye; its neighbours are one pixel angle away */
    {
        ccl_vec3 d = ccl_camera_ray(cam.inv_view_proj_rot, 50, 50, 101, 101);
        double fx = -1.0 / sqrt(2.01), fy = 0.1 / sqrt(2.01), fz = -1.0 / sqrt(2.01);
        CCL_CHECK_CLOSE(d.x, fx, 2e-7);
        CCL_CHECK_CLOSE(d.y, fy, 2e-7);
        CCL_CHECK_CLOSE(d.z, fz, 2e-7);
        CCL_CHECK_CLOSE(len3(d), 1.0, 2e-7);
    }
    /* the top-left corner of the image plane: angle to the axis atan(tan(fov/2) * hypot(aspect, 1)) at the corner */
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), fov, 1.0f, 0.01f, 1000.0f, &cam) == CCL_OK);
    {
        /* pixel (0, 0) of a 2x2 image has NDC (-0.5, 0.5) */
        ccl_vec3 d = ccl_camera_ray(cam.inv_view_proj_rot, 0, 0, 2, 2);
        double t = tan(0.5), n = sqrt(0.25 * t * t * 2.0 + 1.0);
        CCL_CHECK_CLOSE(d.x, -0.5 * t / n, 2e-7);
        CCL_CHECK_CLOSE(d.y, 0.5 * t / n, 2e-7);
        CCL_CHECK_CLOSE(d.z, -1.0 / n, 2e-7);
    }
}

static void test_camera_rejects_bad_input(void)
{
    ccl_camera cam;
    memset(&cam, 0, sizeof cam);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, 0), V(0, 1, 0), 1.0f, 1.0f, 0.1f, 10.0f, &cam) == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 1, 0), V(0, 1, 0), 1.0f, 1.0f, 0.1f, 10.0f, &cam) == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 0, 0), 1.0f, 1.0f, 0.1f, 10.0f, &cam) == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), 0.0f, 1.0f, 0.1f, 10.0f, &cam) == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), 3.2f, 1.0f, 0.1f, 10.0f, &cam) == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), 1.0f, 0.0f, 0.1f, 10.0f, &cam) == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), 1.0f, 1.0f, 0.0f, 10.0f, &cam) == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), 1.0f, 1.0f, 1.0f, 1.0f, &cam) == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V((float)NAN, 0, 0), V(0, 0, -1), V(0, 1, 0), 1.0f, 1.0f, 0.1f, 10.0f, &cam)
              == CCL_EINVAL);
    CCL_CHECK(ccl_camera_look_at(V(0, 0, 0), V(0, 0, -1), V(0, 1, 0), 1.0f, 1.0f, 0.1f, 10.0f, NULL) == CCL_EINVAL);
    CCL_CHECK(cam.view[0] == 0.0f); /* untouched on failure */
}

static void test_camera_ray_is_the_pt_camera(void)
{
    /* pt-code-7.2 with fov_y = pi/2 and up = +y: rd = normalize(p.x right + p.y up + forward), p = (NDC x * aspect,
     * NDC y); right = normalize(forward x (0, 1, 0)), up = normalize(right x forward). Computed here in double. */
    const double eye[3] = {1.0, 2.0, 3.0}, target[3] = {4.0, 2.5, -1.0};
    const int w = 8, h = 5;
    double f[3], r[3], u[3], n;
    ccl_camera cam;
    int x, y, i;
    for (i = 0; i < 3; ++i) f[i] = target[i] - eye[i];
    n = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (i = 0; i < 3; ++i) f[i] /= n;
    r[0] = -f[2]; /* f x (0, 1, 0) = (-f.z, 0, f.x) */
    r[1] = 0.0;
    r[2] = f[0];
    n = sqrt(r[0] * r[0] + r[2] * r[2]);
    r[0] /= n;
    r[2] /= n;
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    CCL_CHECK(ccl_camera_look_at(V(1, 2, 3), V(4, 2.5f, -1), V(0, 1, 0), 1.5707964f, (float)w / (float)h, 0.01f,
                                 1000.0f, &cam) == CCL_OK);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            /* gl_FragCoord has its origin at the bottom-left: row y from the top is h - 1 - y from the bottom */
            double px = ((x + 0.5) / w * 2.0 - 1.0) * ((double)w / h), py = (h - 1 - y + 0.5) / h * 2.0 - 1.0;
            double rd[3];
            ccl_vec3 d = ccl_camera_ray(cam.inv_view_proj_rot, x, y, w, h);
            for (i = 0; i < 3; ++i) rd[i] = px * r[i] + py * u[i] + f[i];
            n = sqrt(rd[0] * rd[0] + rd[1] * rd[1] + rd[2] * rd[2]);
            /* float32 matrix entries and a few roundings per component */
            CCL_CHECK_CLOSE(d.x, rd[0] / n, 1e-6);
            CCL_CHECK_CLOSE(d.y, rd[1] / n, 1e-6);
            CCL_CHECK_CLOSE(d.z, rd[2] / n, 1e-6);
        }
}

int main(void)
{
    CCL_RUN(test_camera_look_at_and_rays);
    CCL_RUN(test_camera_rejects_bad_input);
    CCL_RUN(test_camera_ray_is_the_pt_camera);
    return ccl_test_report();
}
