/*
 * cclouds/reproj.h -- temporal reprojection (vc §4.2.1, §4.4): which pixel a thread renders in each frame (eq 4.1),
 * the reduced 1/4 x 1/4 buffer (vc-A22), and the reprojection pass that fills the pixels not rendered this frame
 * from the previous frame or, failing that, from the reduced buffer (vc-A26), with optional neighbourhood averaging
 * (vc-A27).
 *
 * Conventions: images are float32, row-major (height, width, channels), pixel (x, y) at index
 * (y * width + x) * channels + c, y = 0 the top row; uv and NDC as in cclouds/camera.h (uv = ((x + 0.5)/width,
 * (y + 0.5)/height), NDC y = 1 - 2v); matrices float[16] column-major.
 *
 * Choices where the thesis is silent (mirrored in pywarp/kernels/reproj.py):
 *   - frame f is taken mod 16 (mathematical modulo: negative frames wrap too); in cycle frame f the block offset is
 *     (a, b) = (f div 4, f mod 4) -- the column-by-column visiting order of eq 4.1;
 *   - sizes not divisible by 4: the thread grid is ceil(W/4) x ceil(H/4) (= the reduced buffer size); a thread whose
 *     pixel (4 id_x + a, 4 id_y + b) falls outside the image is skipped, so every pixel is still rendered exactly once
 *     per 16 frames;
 *   - the reduced buffer texel (i, j) holds the pixel (4i + a, 4j + b) rendered THIS frame, so the fallback lookup
 *     uses its true position: reduced coordinates ((x - a)/4, (y - b)/4), clamped to the texels whose pixel lies in
 *     the image (a plain uv lookup would shift the fallback by up to 1.5 px, differently in every frame of a cycle);
 *   - the reprojected sample is a bilinear lookup with clamp-to-edge at pixel position (u W - 0.5, v H - 0.5); a
 *     position within 1/256 px of a pixel centre is snapped to it, so a static camera returns the previous frame
 *     exactly instead of mixing in its neighbours through float32 round-off (measured <= 4.5e-4 px at 1920 x 1080;
 *     u has 24-bit resolution, so it grows with the width: ~2e-3 px at 7680); a 1/256 px shift is invisible;
 *   - the ray-sphere root: the nearest hit in front of the camera (the far root for a camera below the layer);
 *     no hit, a hit behind the previous camera (clip w <= 0) or uv outside [0, 1]^2 -> reduced-buffer fallback;
 *   - history = 0 (first frame, camera cut, camera inside/above the layer where vc-A24 says reprojection cannot be
 *     used) sends every non-rendered pixel to the fallback; if a frame renders no pixel at all in a row/column band
 *     (width or height < 4), the fallback keeps previous (history = 1) or current (history = 0) at the same pixel.
 */
#ifndef CCLOUDS_REPROJ_H
#define CCLOUDS_REPROJ_H

#include "cclouds/camera.h"
#include "cclouds/common.h"
#include "cclouds/raymarch.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Block size and cycle length of the reprojection (4 x 4 pixels, 16 frames). */
#define CCL_REPROJ_BLOCK 4
#define CCL_REPROJ_CYCLE 16

/* Largest thread index of ccl_reproj_pixel: 4 id + 3 must fit in an int. */
#define CCL_REPROJ_MAX_ID 536870911
/* Largest neighbourhood n of ccl_reproj_frame (n x n bilinear samples per pixel): 31 px is already a blur far wider
 * than the 4 x 4 block the reprojection fills (vc-A27 uses 3), and bounds the work per pixel (961 samples). */
#define CCL_REPROJ_MAX_NEIGHBOURHOOD 31

/* Pixel written by thread (id_x, id_y) in frame `frame` when reprojection is on.
 * Ref: vc-4.1: f = frame mod 16, a = floor(f / 4), b = f mod 4, (x, y) = (4 id_x + a, 4 id_y + b).
 * 0 <= id_x, id_y <= CCL_REPROJ_MAX_ID. The caller skips pixels outside the image (see ccl_reproj_grid). */
CCL_API void ccl_reproj_pixel(int id_x, int id_y, int frame, int *out_x, int *out_y);

/* Thread grid (= reduced buffer) size for a width x height image: ceil(width / 4) x ceil(height / 4).
 * Ref: vc-4.1 (bounds rule), vc-A22. Returns CCL_EINVAL if width < 1 or height < 1. */
CCL_API ccl_status ccl_reproj_grid(int width, int height, int *out_grid_w, int *out_grid_h);

/* 1 if pixel (x, y) is raymarched in frame `frame` ((x mod 4, y mod 4) == (a, b) of eq 4.1), else 0. Ref: vc-4.1. */
CCL_API int ccl_reproj_updated(int x, int y, int frame);

/* Continuous coordinates in the reduced buffer (texel units, texel (i, j) at (i, j)) of pixel (x, y) in frame
 * `frame`: ((x - a)/4, (y - b)/4), clamped to [0, floor((width - 1 - a)/4)] x [0, floor((height - 1 - b)/4)], the
 * texels written this frame. For the pixel rendered by thread (i, j) this is exactly (i, j), the texel it writes.
 * NaN in a coordinate when this frame renders no pixel in that direction (width - 1 < a, or height - 1 < b).
 * Ref: vc-A22 (reduced buffer mapping), vc-A26 step 3. 0 <= x < width, 0 <= y < height. */
CCL_API void ccl_reproj_reduced_coord(int x, int y, int frame, int width, int height, float *out_rx, float *out_ry);

/* Where pixel (x, y) of the current frame was in the previous frame.
 * Ref: vc-A26 step 2: ray from eye through the pixel (ccl_camera_ray with inv_view_proj_rot) -> nearest hit in front
 * of the camera on the inner sphere (centre, r_inner) -> P -> clip = prev_view_proj (P, 1) -> NDC -> uv.
 * Returns 1 if the point was visible (clip w > 0 and uv in [0, 1]^2); otherwise 0. *out_u, *out_v hold the uv when
 * the point projects (w > 0, even outside [0, 1]) and NaN when the ray misses the sphere or w <= 0. */
CCL_API int ccl_reproj_uv(const float inv_view_proj_rot[16], ccl_vec3 eye, const float prev_view_proj[16],
                                ccl_vec3 centre, float r_inner, int x, int y, int width, int height, float *out_u,
                                float *out_v);

/* The reprojection pass over a frame.
 * Ref: vc-A26 (temporal reprojection), vc-A27 (neighbourhood averaging).
 * current  -> this frame's buffer (height, width, channels): the pixels rendered this frame (ccl_reproj_updated)
 *             are taken from it unchanged;
 * previous -> the previous frame's final buffer (height, width, channels);
 * reduced  -> this frame's reduced buffer (ceil(height/4), ceil(width/4), channels);
 * frame, inv_view_proj_rot, eye -> current frame number and camera (ccl_camera.inv_view_proj_rot, .eye);
 * prev_view_proj -> the previous frame's camera (ccl_camera.view_proj);
 * centre, r_inner -> the inner sphere of the cloud layer;
 * neighbourhood -> odd n in [1, CCL_REPROJ_MAX_NEIGHBOURHOOD]: the reprojected value is the mean of n x n bilinear samples one pixel apart centred on
 *                  the reprojected position (1 = exact sampling, fig 4.14a; 3 = the vc-A27 default, fig 4.14b);
 * history -> 1 to use the previous frame, 0 to use only the reduced fallback (see the choices above);
 * out      -> (height, width, channels); may be the same array as current, never previous.
 * Returns CCL_EINVAL (out untouched) for NULL pointers, sizes < 1, an even, non-positive or too large neighbourhood,
 * r_inner <= 0 or NaN, or out == previous. */
CCL_API ccl_status ccl_reproj_frame(const float *current, const float *previous, const float *reduced, int width,
                                       int height, int channels, int frame, const float inv_view_proj_rot[16],
                                       ccl_vec3 eye, const float prev_view_proj[16], ccl_vec3 centre, float r_inner,
                                       int neighbourhood, int history, float *out);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_REPROJ_H */
