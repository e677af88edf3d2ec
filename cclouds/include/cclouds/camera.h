/*
 * cclouds/camera.h -- the look-at + perspective camera and primary-ray generation shared by every scene: the
 * cloudscape (vc-A25) and the ray-marched terrain demo (pt-code-7.2, the same camera; see ccl_camera_ray).
 *
 * Conventions:
 *   - World frame: y is up; any length unit (the cloudscape uses km).
 *   - Matrices are float[16] in COLUMN-MAJOR order (OpenGL/GLM): element (row r, column c) is m[c * 4 + r].
 *     Right-handed look-at view matrix (the camera looks down -z in view space) and an OpenGL perspective
 *     projection with NDC z in [-1, 1].
 *   - Pixels: (x, y) integer indices, y = 0 is the TOP row (NumPy/PNG order); the pixel centre has
 *     uv = ((x + 0.5) / width, (y + 0.5) / height) and NDC = (2u - 1, 1 - 2v).
 *   - float32 results; pywarp/kernels/camera.py mirrors every operation (camera_look_at, camera_ray).
 */
#ifndef CCLOUDS_CAMERA_H
#define CCLOUDS_CAMERA_H

#include "cclouds/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Camera matrices, all float32 column-major (see the conventions above). Built by ccl_camera_look_at; the products
 * and the inverse are computed in double and rounded once. */
typedef struct {
    ccl_vec3 eye;              /* camera position (world) */
    float view[16];            /* world -> view (look-at) */
    float proj[16];            /* view -> clip (perspective, vertical field of view) */
    float view_proj[16];       /* proj * view: world -> clip */
    float inv_view_proj[16];   /* inverse of view_proj: clip -> world */
    float inv_view_proj_rot[16]; /* inverse of proj * (view without its translation): clip -> direction from the
                                    eye; what ccl_camera_ray uses (see there) */
} ccl_camera;

/* Camera from eye, target and up vectors (GLM lookAt, right-handed) and a perspective projection (GLM perspective,
 * OpenGL NDC). Ref: vc-A25, pt-code-7.2. eye -> camera position, target -> point looked at (!= eye), up -> world up
 * (not parallel to target - eye; pt-code-7.2 fixes (0, 1, 0)), fov_y -> vertical field of view (rad, (0, pi);
 * pt-code-7.2: pi/2), aspect -> width / height (> 0), 0 < z_near < z_far (world units).
 * Basis: f = normalize(target - eye), s = normalize(f x up), u = s x f; view rows s, u, -f.
 * Returns CCL_EINVAL (out untouched) for a non-finite input, eye == target, up parallel to the view direction
 * (within ~1e-6 rad), a parameter outside its range, or a matrix entry beyond the float32 range (an eye near
 * FLT_MAX, aspect tan(fov_y / 2) or 1 / z_near above it); CCL_OK otherwise, every matrix entry finite. */
CCL_API ccl_status ccl_camera_look_at(ccl_vec3 eye, ccl_vec3 target, ccl_vec3 up, float fov_y, float aspect,
                                      float z_near, float z_far, ccl_camera *out);

/* Unit view direction through the centre of pixel (x, y) of a width x height image.
 * Ref: vc-A25, pt-code-7.2: pixel -> uv = ((x + 0.5)/width, (y + 0.5)/height) -> NDC (2u - 1, 1 - 2v, z = 1) ->
 * h = inv_view_proj_rot (ndc, 1) -> d = normalize(h.xyz). inv_view_proj_rot is the inverse view-projection of the
 * camera moved to the origin (ccl_camera.inv_view_proj_rot): h.xyz = R (x aspect tan(fov/2), y tan(fov/2), -1)
 * exactly, and w = 1/z_far > 0 only scales it, so it is not divided out. This is pt-code-7.2's
 * rd = normalize(p.x right + p.y up + forward) with p = (NDC x * aspect, NDC y) and tan(fov/2) = 1.
 * Why not the full inverse: its float32 entries mix the eye translation (~50 |eye| for z_near = 0.01) with the
 * far-plane w (1/z_far), and the direction p/w - eye cancels them: measured 0.037 px error at 1920 x 1080 with the
 * eye 7.6 km from the origin, against < 1e-3 px here, independent of the eye position.
 * 0 <= x < width, 0 <= y < height. Output: unit vector (float32, |d| = 1 within a few ulp). */
CCL_API ccl_vec3 ccl_camera_ray(const float inv_view_proj_rot[16], int x, int y, int width, int height);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_CAMERA_H */
