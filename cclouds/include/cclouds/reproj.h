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
 *
 * Depth-aware reprojection (not in the thesis; the renderer's default, pywarp settings reprojection_depth = "clouds",
 * reprojection_filter = "catmull_rom"): the thesis reprojects every pixel through the inner sphere, as if every cloud
 * lay on the layer base and the sky were there too; a cloud at another distance, and the sky, are then fetched from
 * the wrong place of the previous frame (parallax) while the camera translates, the error grows with every frame a
 * pixel is carried, and the pixel marched fresh in each 4 x 4 block, which is right, stands out as a regular dot
 * grid. The depth-aware pass keeps a depth buffer (the distance from the eye, km, of what each pixel shows: the
 * march's transmittance-weighted mean distance of the cloud, else the ground, else the sky far away --
 * ccl_reproj_surface_depth) and finds where the pixel's point was seen in the previous frame by a fixed-point
 * iteration along the current ray (ccl_reproj_uv_depth):
 *   t = the inner-sphere distance; repeat `iterations` times: X = eye + d t, uv = prev_view_proj X,
 *   Y = prev_eye + D(uv) (X - prev_eye) / |X - prev_eye| (the point the previous frame saw in the direction of X,
 *   D = its depth at uv), t = |Y - eye|; finally uv = prev_view_proj (eye + d t).
 * Choices:
 *   - D is the NEAREST previous pixel's depth (clamped to the image while iterating; the final uv alone decides
 *     visibility): a bilinear depth invents, at every cloud edge, a distance between the cloud's and the sky's where
 *     no surface is (measured: more error above the horizon than with the nearest depth); with the nearest depth the
 *     iteration converges onto a point the previous frame showed (exactly onto it when that point projects to a
 *     pixel centre);
 *   - the previous pixel's depth is taken along the direction of X from prev_eye (not its own pixel-centre ray):
 *     then no inverse of the previous camera is needed, and where D is exact the fixed point is the exact hit;
 *   - a depth that is not > 0 (unknown), a projection behind the previous camera (w <= 0) or a degenerate step
 *     stops the iteration with the current t;
 *   - the sky (no cloud, no ground) is at CCL_REPROJ_SKY_DEPTH_KM: its colour depends on the direction only, so it
 *     must not move with the camera (through the inner sphere it drifted by about the camera step / the
 *     inner-sphere distance, in radians, every frame a pixel was carried);
 *   - iterations = 0 is the thesis's inner-sphere point exactly (ccl_reproj_uv); the reprojected pixel's depth is
 *     the final t (relative to the new eye), a fallback pixel's the bilinear interpolation of this frame's marched
 *     depths at the reduced-buffer position (like its colour), so the next frame has a depth everywhere;
 *   - the previous frame is sampled with the thesis's bilinear filter or (CCL_REPROJ_FILTER_CATMULL_ROM) the
 *     Catmull-Rom cubic over the 4 x 4 nearest pixels, clamped to the range of the 2 x 2 the bilinear filter reads
 *     (no overshoot at edges, which would grow frame after frame): a pixel is resampled up to 15 times before it is
 *     marched again, and each bilinear resampling at a fractional offset f blurs by a variance f (1 - f) px^2, so
 *     the carried pixels lose their detail and the fresh one stands out (measured on the steady forward path of
 *     tests/clouds/test_artefacts.py: even with the exact depths of full renders, a bilinear history leaves the fresh
 *     pixel 1.5x as far from its neighbours as another pixel; Catmull-Rom 1.2x).
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

/* Default number of fixed-point refinements of ccl_reproj_uv_depth. Measured (tests/kernels/test_reproj_depth.py: a
 * previous depth of 2 km everywhere, 640 x 360): a forward step of 20 m starts 3.8 px off at the inner sphere and is
 * 4e-4 px off after one refinement; a step of 200 m starts 36 px off, then 0.24 px and 0.002 px after two. Along the
 * forward path of tests/clouds/test_artefacts.py 1, 2 and 3 refinements give the same statistic (within 1 %); each
 * costs about 8 CPU-ms at 640 x 360 (13 % of the pass), so 2: converged for steps up to a tenth of the distance.
 * The largest accepted value bounds the work per pixel. */
#define CCL_REPROJ_DEPTH_ITERATIONS 2
#define CCL_REPROJ_MAX_DEPTH_ITERATIONS 16
/* Depth of the sky (km) in the depth buffer: far enough that a camera step of 1 km moves it by 1e-5 rad (0.02 px at
 * 1920 px over 60 deg), near enough that float32 positions there keep 1e-7 rad of direction (ulp 0.008 km). */
#define CCL_REPROJ_SKY_DEPTH_KM 1.0e5f

/* How ccl_reproj_frame_depth samples the previous frame (see the choices above). */
typedef enum {
    CCL_REPROJ_FILTER_BILINEAR = 0,   /* the thesis (vc-A26) */
    CCL_REPROJ_FILTER_CATMULL_ROM = 1 /* Catmull-Rom over 4 x 4 pixels, clamped to the 2 x 2 bilinear footprint */
} ccl_reproj_filter;

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

/* The depth a pixel keeps for the depth-aware reprojection: the distance (km) from the eye along the unit ray d of
 * what it shows: march_depth (ccl_cloudscape_march's transmittance-weighted mean distance of the cloud) when > 0, else
 * the Earth sphere (centre, r_earth) entered ahead of the camera (t0 > 0), else the sky, CCL_REPROJ_SKY_DEPTH_KM.
 * Not in the thesis (see the depth-aware choices above). r_earth > 0. Output > 0; NaN for a NaN march_depth, eye
 * or d. */
CCL_API float ccl_reproj_surface_depth(float march_depth, ccl_vec3 eye, ccl_vec3 d, ccl_vec3 centre, float r_earth);

/* Where pixel (x, y) of the current frame was in the previous frame, through the depth of what it shows.
 * Not in the thesis: the fixed-point iteration on the depth described above (iterations = 0: ccl_reproj_uv).
 * prev_depth -> the previous frame's depth buffer (height, width), km from prev_eye (a value not > 0: unknown);
 * prev_eye -> the previous camera's eye (ccl_camera.eye); the other arguments as ccl_reproj_uv;
 * 0 <= iterations <= CCL_REPROJ_MAX_DEPTH_ITERATIONS (CCL_REPROJ_DEPTH_ITERATIONS by default).
 * Returns 1 if the point was visible (clip w > 0 and uv in [0, 1]^2), else 0. *out_u, *out_v as ccl_reproj_uv;
 * *out_t: the point's distance from eye along the ray (km), NaN when the ray misses the inner sphere. */
CCL_API int ccl_reproj_uv_depth(const float inv_view_proj_rot[16], ccl_vec3 eye, const float prev_view_proj[16],
                                ccl_vec3 prev_eye, const float *prev_depth, ccl_vec3 centre, float r_inner,
                                int iterations, int x, int y, int width, int height, float *out_u, float *out_v,
                                float *out_t);

/* The depth-aware reprojection pass over a frame (the renderer's default; iterations = 0 with the bilinear filter:
 * ccl_reproj_frame's colours, bit for bit, plus the depths).
 * current_depth -> this frame's depth buffer (height, width): the depths (ccl_reproj_surface_depth) of the pixels
 *                  rendered this frame (the others are not read);
 * previous_depth -> the previous frame's final depth buffer (height, width), km from prev_eye;
 * prev_eye -> the previous camera's eye; filter -> a ccl_reproj_filter, the sampler of the previous frame (each of
 *             the n x n samples of the neighbourhood); iterations -> 0 .. CCL_REPROJ_MAX_DEPTH_ITERATIONS;
 * out_depth -> (height, width): the depth of every pixel relative to eye (rendered: current_depth; reprojected: the
 *              converged distance; fallback, or a reprojected point at an infinite distance (a degenerate previous
 *              projection): the bilinear interpolation of this frame's rendered depths at the reduced-buffer
 *              position; no rendered pixel in that direction: previous_depth (history) or current_depth at the
 *              same pixel);
 * the other arguments as ccl_reproj_frame. out may be current and out_depth may be current_depth; no other buffer
 * written may be one that is read.
 * Returns CCL_EINVAL (out, out_depth untouched) for what ccl_reproj_frame rejects, a NULL depth buffer, an unknown
 * filter, iterations outside [0, CCL_REPROJ_MAX_DEPTH_ITERATIONS], or a written buffer that is also read (other
 * than the two above). */
CCL_API ccl_status ccl_reproj_frame_depth(const float *current, const float *current_depth, const float *previous,
                                          const float *previous_depth, const float *reduced, int width, int height,
                                          int channels, int frame, const float inv_view_proj_rot[16], ccl_vec3 eye,
                                          const float prev_view_proj[16], ccl_vec3 prev_eye, ccl_vec3 centre,
                                          float r_inner, int neighbourhood, int filter, int iterations, int history,
                                          float *out, float *out_depth);

#ifdef __cplusplus
}
#endif

#endif /* CCLOUDS_REPROJ_H */
