"""Temporal reconstruction: a full-resolution picture while moving, from a fraction of its pixels per frame.

Every scene's viewer uses it (:class:`pywarp.viewer.session.RenderWorker`): while the view moves, a frame renders
1/f^2 of the window's pixels -- the scene at (width/f) x (height/f) with a sub-pixel camera offset, so that its pixel
(i, j) is exactly the window's pixel (f j + ox, f i + oy) -- and the phase (ox, oy) steps through the f x f pixels
of each block (Guerrilla's Nubis: 1/16 of the pixels per frame, Schneider 2015; checkerboard and TAA upsampling:
Karis 2014, Yang et al. 2020). :meth:`TemporalUpsampler.resolve` writes the window's picture:

* a pixel rendered this frame is that pixel of the full render (the same ray);
* any other pixel is the previous picture reprojected with the camera's motion (each window pixel's ray through the
  previous camera, as a point at infinity: exact for turning and for the distant cloudscape; where the camera
  translates near a surface the clamp below bounds the error), sampled bilinearly and clamped into the colour box of
  this frame's nearest fresh pixel and its four neighbours (Karis 2014's neighbourhood clamping on the fresh grid; the
  cross costs less than a 3 x 3 box and measured as good): history that disagrees with what the neighbourhood shows
  now -- a disocclusion, a moving object, changed lighting -- is pulled to it, so it cannot ghost -- and mixed with
  the interpolated fresh pixels (:data:`HISTORY_BLEND`);
* where the history falls outside the previous picture, or there is none, the fresh pixels interpolated bilinearly.

With the camera and the scene still, the clamp is off (the history is then exact) and after f^2 frames every pixel
has been rendered once: the picture is the full render. What a scene feeds the pass: its uint8 frame at the reduced
size rendered with the phase's ``jitter_px`` (:meth:`pywarp.core.technique.Technique.jitter`) and its camera
(:func:`pywarp.viewer.session.technique_camera`: the same matrices at any size of the same aspect). A scene may also feed
per-pixel depth (the distance along each fresh pixel's ray; the terrain's march does): each window pixel then takes
the depth of its nearest fresh pixel and its history from where that point was in the previous picture -- exact under
translation too (walking towards a hill), not only under turning.

With depth in this frame and the previous one (the picture keeps each pixel's depth as its history's), the history
of a surface is judged by geometry, not by colour (the clamp's 5-pixel cross of a 1/16 grid is wrong both ways on a
textured surface: it lets through what the cross happens to span and clips detail the cross missed):

* the point's distance from the previous eye must agree with the history's depths there (:data:`DEPTH_REJECT`), else
  the point was hidden (a disocclusion) -- tried for the pixel's own depth and then each of the four fresh pixels'
  around (at a silhouette the pixel may lie on either side);
* a kept history is sampled with Catmull-Rom (:data:`CUBIC_HISTORY`; bilinear resampling blurs it further every
  frame), from the history pixels of that surface only at an occluder's edge, and not mixed with the interpolation
  (:data:`DEPTH_BLEND`);
* a kept history that has been enlarged since its pixels were rendered (walking into a slope) loses sharpness
  (:data:`SHARPNESS_MIX`): each pixel carries it (1 rendered, divided by each frame's enlargement, measured per fresh
  cell), and where it falls to 1/f this frame's interpolation takes over -- else a stretched history smears;
* what the scene marks as ``changing`` (water: waves in time, reflections with the view) keeps the colour clamp
  above (its history sampled bilinearly, :data:`CLAMPED_CUBIC`); the far field (sky), smooth at the fresh pixels'
  spacing, is their interpolation while the camera moves (:data:`SKY_HISTORY`; else the colour clamp).

What a frame with depth costs (CPU of one 640 x 360 resolve at 1/16 of the pixels on the terrain's walk, the
enlargement pass included; median of 20 frames, the old and new passes interleaved in one process): 24.9 ms before,
18.4 ms now -- the sky's interpolation and the bilinear clamped history 5 ms of it; the history's depths read once
per candidate, its colour not where the interpolation replaces it, nor the interpolation where the history alone is
shown, the rest. Of the pass, the fresh grid's position, depth and colour for every window pixel are ~6 ms, a
surface's reprojection, depth test and Catmull-Rom sample ~8 ms (47 % of the pixels), the writes ~2.4 ms.

Measured on the terrain viewer benchmark's walk (``W`` held, time playing; tools/terrain_preview_eval.py, 640 x 360,
SSIM on luminance of the shown frame against the full render, mean / 5th percentile; CPU ms of a frame, one run on
a loaded 2-core machine). 2 s at 30 frames/s: the enlarged 213 x 120 frame 0.834 / 0.820 (65 ms); at 1/16 of the
pixels the colour clamp 0.808 / 0.795 (53 ms), with Catmull-Rom 0.812 / 0.800, the depth's rejection sampled
bilinearly 0.839 / 0.827, with Catmull-Rom but the water trusted 0.857 / 0.842, as here 0.868 / 0.856 (62 ms), the
interpolation mixed in at 0.1 0.821 / 0.809; at 1/4 of the pixels 0.933 / 0.922 (167 ms). The benchmark's whole
13 s at 28 frames/s (over a crest): 0.890 / 0.832 against the enlarged frame's 0.892 / 0.851 (the history moved
onto its own depth: 0.883 / 0.807; without the sharpness: 0.878 / 0.776). Measured again with the sky interpolated
while moving (:data:`SKY_HISTORY`) and the clamped history bilinear (:data:`CLAMPED_CUBIC`): the 2 s 0.867 / 0.855
(56 ms) against 0.868 / 0.856 (63 ms), the whole walk 0.894 / 0.840 against 0.894 / 0.839.
"""
from __future__ import annotations

import numpy as np
import warp as wp

#: the share of the fresh pixels' bilinear interpolation mixed into the clamped history while anything changes:
#: 0.35 measured against 0 on the viewer's motion at 1/16 of the pixels (SSIM against the full render, clouds 0.868 ->
#: 0.889, flight 0.933 -> 0.955): the sparse cross lets the history flicker, the interpolation steadies it
HISTORY_BLEND = 0.35
#: with depth (the frame and its history): the share of the fresh pixels' bilinear interpolation mixed into a history
#: kept by geometry (at least; the sharpness may ask more): 0 -- SSIM 0.868 against 0.821 at 0.1 (module docstring):
#: every share of the blurred interpolation stays in a moving picture, and what changes besides the motion (water,
#: sky) is colour-clamped instead
DEPTH_BLEND = 0.0
#: with depth: the history is kept where the point's distance from the previous eye and the history's own depths
#: there are within this ratio (else a disocclusion: the fresh interpolation). 1.5: 1.25 / 1.5 / 2 measured SSIM
#: 0.875 / 0.876 / 0.877 on the terrain's walk (before the sharpness; the depths interpolated between fresh pixels at
#: a grazing angle are ~10-20 % off, 1.1 rejected half the ground); a wall 2 units in front of ground 3-5 away
#: (tests) is still told apart
DEPTH_REJECT = 1.5
#: with depth: a kept history enlarged since its pixels were rendered (walking towards the ground) is worth less
#: than this frame's interpolation once its sharpness (1 when rendered, divided by the enlargement of every frame
#: since) falls to 1/f; from SHARPNESS_MIX / f down to 1/f the interpolation is mixed in linearly. 2: SSIM 0.883 /
#: 0.807 (mean / 5th percentile) against 0.882 / 0.791 at 1.25 on the terrain benchmark's whole walk at 28 frames/s
#: (tools/terrain_preview_eval.py --fps 28 --frames 364; measured while the history was still moved onto its depth)
SHARPNESS_MIX = wp.constant(2.0)
#: with depth: the history sampled with Catmull-Rom (Karis 2014; clamped into its four nearest pixels' box, no
#: ringing) rather than bilinearly, which blurs it further every frame: SSIM 0.868 against 0.839 on the terrain's walk
CUBIC_HISTORY = True
#: with depth, while the camera moves: whether the far field (sky) keeps its colour-clamped history; False: the
#: interpolation of the fresh pixels (a still camera keeps it: time playing, the clouds drift in a clamped history;
#: a still view converges through it). On the terrain benchmark's
#: whole walk (tools/terrain_preview_eval.py --fps 28 --frames 364) SSIM 0.8943 / 0.8397 (mean / 5th percentile)
#: against 0.8937 / 0.8390 with the history, 6 ms less CPU a frame of ~63 (the sky is ~43 % of the picture and smooth
#: at the fresh pixels' spacing; on the walk's first 2 s 0.8673 / 0.8554 against 0.8677 / 0.8559)
SKY_HISTORY = False
#: with depth: whether the colour-clamped history (the sky's where kept, the water's) is sampled with Catmull-Rom as a
#: surface's kept by its depth is (:data:`CUBIC_HISTORY`) rather than bilinearly: False -- the clamp into the fresh
#: pixels' box bounds it either way; SSIM 0.8943 / 0.8397 both on the whole walk, ~0.7 ms less CPU a frame
CLAMPED_CUBIC = False
#: with depth: the four fresh pixels around a window pixel whose depths are within this ratio of each other lie on
#: one smooth surface, and the pixel's depth is their bilinear interpolation (else the nearest one's: an edge).
#: 1.25: the ground seen at a grazing angle changes its depth by ~10-20 % per fresh pixel at 1/16 of the pixels;
#: a silhouette over a farther slope changes it by more
DEPTH_SMOOTH = wp.constant(1.25)
#: the reduction factors a reconstruction may use: 1/f^2 of the pixels are rendered per frame (f must divide both
#: sides); the viewer's own previews pick from the first three (:data:`VIEWER_FACTORS`), rain's background renders a
#: new direction at 8
FACTORS = (1, 2, 4, 8)
VIEWER_FACTORS = (1, 2, 4)


def phases(f: int) -> list[tuple[int, int]]:
    """The order in which the f x f pixels of a block are rendered: the ordered-dither (Bayer) order, so that any
    f^2/4 consecutive frames cover the block evenly (f = 2: (0,0), (1,1), (1,0), (0,1))."""
    if f == 1:
        return [(0, 0)]
    bayer = np.array([[0]])
    while bayer.shape[0] < f:
        n = bayer.shape[0]
        bayer = np.block([[4 * bayer, 4 * bayer + 2], [4 * bayer + 3, 4 * bayer + 1]])
        assert bayer.shape[0] == 2 * n
    order = sorted(((int(bayer[y, x]), x, y) for y in range(f) for x in range(f)))
    return [(x, y) for _, x, y in order]


def reprojection(camera, previous, width: int, height: int) -> np.ndarray:
    """The 3 x 3 homography (float64) that takes a window pixel (x, y, 1) of ``camera`` to the previous picture's
    pixel coordinates (homogeneous, the last component > 0 in front of the previous camera) of the same direction:
    the far-field reprojection. Pixel -> NDC (x + 0.5, y + 0.5 at the centre) -> direction through the camera's
    ``inv_view_proj_rot`` (vc-A25's ray, unnormalised) -> the previous ``view_proj`` (w = 0: a point at infinity)
    -> the previous pixel."""
    w, h = float(width), float(height)
    to_ndc = np.array([[2.0 / w, 0.0, 1.0 / w - 1.0], [0.0, -2.0 / h, 1.0 - 1.0 / h], [0.0, 0.0, 1.0]])
    m = np.asarray(camera.inv_view_proj_rot, np.float64)
    to_dir = np.column_stack([m[:3, 0], m[:3, 1], m[:3, 2] + m[:3, 3]])
    to_clip = np.asarray(previous.view_proj, np.float64)[[0, 1, 3]][:, :3]
    to_px = np.array([[w / 2.0, 0.0, w / 2.0 - 0.5], [0.0, -h / 2.0, h / 2.0 - 0.5], [0.0, 0.0, 1.0]])
    return to_px @ to_clip @ to_dir @ to_ndc


def _mat44(m) -> wp.mat44:
    return wp.mat44(*np.asarray(m, np.float32).ravel().tolist())


def factor_for(width: int, height: int, wanted: int) -> int:
    """The largest factor of :data:`FACTORS` up to ``wanted`` that divides both sides (1 always does)."""
    return max(f for f in FACTORS if f <= wanted and width % f == 0 and height % f == 0)


@wp.func
def pixel_ray(x: int, y: int, width: int, height: int, inv_view_proj_rot: wp.mat44) -> wp.vec3:
    """The unit ray through window pixel (x, y)'s centre (vc-A25's ray through ``inv_view_proj_rot``)."""
    nx = 2.0 * (float(x) + 0.5) / float(width) - 1.0
    ny = 1.0 - 2.0 * (float(y) + 0.5) / float(height)
    m = inv_view_proj_rot
    return wp.normalize(wp.vec3(m[0][0] * nx + m[0][1] * ny + m[0][2] + m[0][3],
                                m[1][0] * nx + m[1][1] * ny + m[1][2] + m[1][3],
                                m[2][0] * nx + m[2][1] * ny + m[2][2] + m[2][3]))


@wp.func
def project_point(p: wp.vec3, view_proj: wp.mat44, width: int, height: int) -> wp.vec3:
    """The pixel (homogeneous: (x w, y w, w), w > 0 in front of the camera) of world point ``p`` through
    ``view_proj``."""
    c = view_proj * wp.vec4(p[0], p[1], p[2], 1.0)
    w = float(width)
    h = float(height)
    return wp.vec3(c[0] * w * 0.5 + c[3] * (w * 0.5 - 0.5), -c[1] * h * 0.5 + c[3] * (h * 0.5 - 0.5), c[3])


@wp.func
def depth_reprojection(x: int, y: int, t: float, width: int, height: int, inv_view_proj_rot: wp.mat44,
                       eye: wp.vec3, prev_view_proj: wp.mat44) -> wp.vec3:
    """The previous picture's pixel (homogeneous: (x w, y w, w), w > 0 in front of the previous camera) of the point
    at distance ``t`` along window pixel (x, y)'s unit ray (vc-A25's ray through ``inv_view_proj_rot`` from ``eye``):
    the reprojection with depth, exact under translation too."""
    d = pixel_ray(x, y, width, height, inv_view_proj_rot)
    return project_point(eye + d * t, prev_view_proj, width, height)


@wp.func
def catmull_rom(t: float) -> wp.vec4:
    """The Catmull-Rom weights of the four taps at -1, 0, 1, 2 for a sample at ``t`` in [0, 1] past tap 0 (they sum
    to 1 and reproduce linear functions exactly)."""
    t2 = t * t
    t3 = t2 * t
    return wp.vec4(-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t,
                   0.5 * t3 - 0.5 * t2)


@wp.func
def history_cell(px: float, py: float, width: int, height: int):
    """The history pixel (x0, y0) at the top left of pixel coordinates (px, py), clamped so that x0 + 1 and y0 + 1 lie
    in the picture, and the bilinear weights (ta, tb) of x0 + 1 and y0 + 1: (x0, y0, ta, tb)."""
    cx = wp.clamp(px, 0.0, float(width - 1))
    cy = wp.clamp(py, 0.0, float(height - 1))
    x0 = wp.max(wp.min(int(cx), width - 2), 0)
    y0 = wp.max(wp.min(int(cy), height - 2), 0)
    return x0, y0, wp.clamp(cx - float(x0), 0.0, 1.0), wp.clamp(cy - float(y0), 0.0, 1.0)


@wp.func
def sample_history(hist: wp.array(dtype=wp.vec3, ndim=2), px: float, py: float, width: int, height: int,
                   cubic: int) -> wp.vec3:
    """The history at pixel coordinates (px, py) (inside the picture): bilinear, or with ``cubic`` Catmull-Rom over
    the 4 x 4 pixels around it clamped into the box of the four nearest (no ringing past them; Karis 2014)."""
    x0, y0, ta, tb = history_cell(px, py, width, height)
    c00 = hist[y0, x0]
    c10 = hist[y0, x0 + 1]
    c01 = hist[y0 + 1, x0]
    c11 = hist[y0 + 1, x0 + 1]
    if cubic == 0:
        return (c00 * (1.0 - ta) + c10 * ta) * (1.0 - tb) + (c01 * (1.0 - ta) + c11 * ta) * tb
    wx = catmull_rom(ta)
    wy = catmull_rom(tb)
    # the four columns clamped once (x0 - 1 and x0 + 2 may fall off the picture; x0 and x0 + 1 never do)
    xa = wp.max(x0 - 1, 0)
    xd = wp.min(x0 + 2, width - 1)
    acc = wp.vec3(0.0, 0.0, 0.0)
    for j in range(4):
        yy = wp.clamp(y0 - 1 + j, 0, height - 1)
        row = hist[yy, xa] * wx[0]
        row = row + hist[yy, x0] * wx[1]
        row = row + hist[yy, x0 + 1] * wx[2]
        row = row + hist[yy, xd] * wx[3]
        acc = acc + row * wy[j]
    lo = wp.min(wp.min(c00, c10), wp.min(c01, c11))
    hi = wp.max(wp.max(c00, c10), wp.max(c01, c11))
    return wp.min(wp.max(acc, lo), hi)


@wp.func
def vec4_of(c: wp.vec3, w: float) -> wp.vec4:
    return wp.vec4(c[0], c[1], c[2], w)


@wp.func
def agrees(hd: float, dist: float, reject: float) -> bool:
    """Whether a history pixel's depth ``hd`` (<= 0: far field) and a point's distance ``dist`` from the previous
    eye are within the ratio ``reject`` of each other: the history saw that point's surface."""
    return hd > 0.0 and dist <= hd * reject and hd <= dist * reject


@wp.func
def sample_surface(hist: wp.array(dtype=wp.vec3, ndim=2), hist_depth: wp.array(dtype=float, ndim=2), px: float,
                   py: float, dist: float, reject: float, width: int, height: int, cubic: int) -> wp.vec4:
    """The history at (px, py) of a point at distance ``dist`` from the previous eye: :func:`sample_history` where
    the four pixels around all show that surface (their depths within ``reject`` of ``dist``), else the bilinear
    weights of those that do, renormalised -- at the edge of an occluder the history does not mix the occluder in;
    the last component 0 where none does (rejected)."""
    x0, y0, ta, tb = history_cell(px, py, width, height)
    a00 = agrees(hist_depth[y0, x0], dist, reject)
    a10 = agrees(hist_depth[y0, x0 + 1], dist, reject)
    a01 = agrees(hist_depth[y0 + 1, x0], dist, reject)
    a11 = agrees(hist_depth[y0 + 1, x0 + 1], dist, reject)
    if a00 and a10 and a01 and a11:  # the common case: no colour read twice
        return vec4_of(sample_history(hist, px, py, width, height, cubic), 1.0)
    acc = wp.vec3(0.0, 0.0, 0.0)
    wsum = float(0.0)
    for j in range(2):
        for i in range(2):
            if agrees(hist_depth[y0 + j, x0 + i], dist, reject):
                w = wp.where(i == 0, 1.0 - ta, ta) * wp.where(j == 0, 1.0 - tb, tb)
                acc = acc + hist[y0 + j, x0 + i] * w
                wsum = wsum + w
    if wsum <= 1.0e-6:
        return wp.vec4(0.0, 0.0, 0.0, 0.0)  # none of them: rejected
    return vec4_of(acc / wsum, 1.0)


@wp.func
def surface_seen(hist_depth: wp.array(dtype=float, ndim=2), px: float, py: float, dist: float, reject: float,
                 width: int, height: int) -> bool:
    """Whether :func:`sample_surface` keeps the history at (px, py) for a point at distance ``dist`` (any of the four
    pixels around with weight shows that surface), without reading a colour."""
    x0, y0, ta, tb = history_cell(px, py, width, height)
    wsum = float(0.0)
    for j in range(2):
        for i in range(2):
            if agrees(hist_depth[y0 + j, x0 + i], dist, reject):
                wsum = wsum + wp.where(i == 0, 1.0 - ta, ta) * wp.where(j == 0, 1.0 - tb, tb)
    return wsum > 1.0e-6


@wp.func
def history_candidate(x: int, y: int, tc: float, d: wp.vec3, g: wp.mat33, eye: wp.vec3, prev_eye: wp.vec3,
                      prev_view_proj: wp.mat44, hist_depth: wp.array(dtype=float, ndim=2), reject: float, width: int,
                      height: int) -> wp.vec4:
    """Whether the previous picture saw the point at distance ``tc`` along window pixel (x, y)'s unit ray ``d``
    (``tc`` <= 0: the far field, seen where the history's depth is far too): (px, py, t, 1) with the point's pixel
    in the previous picture, where its distance from the previous eye lies within ``reject`` of the range of the
    depth of one of the four history pixels around it with weight (:func:`surface_seen`; which pixels agree,
    :func:`sample_surface` picks), else (.., .., .., 0). (Moving the point along the ray onto the history's own depth measured worse: SSIM 0.883
    against 0.890 on the terrain's walk -- the history's depths between fresh pixels are estimates, and the error
    fed back into the next frame's history.)"""
    no = wp.vec4(0.0, 0.0, tc, 0.0)
    q = g * wp.vec3(float(x), float(y), 1.0)
    if tc > 0.0:
        q = project_point(eye + d * tc, prev_view_proj, width, height)
    if q[2] <= 0.0:
        return no
    px = q[0] / q[2]
    py = q[1] / q[2]
    if px < -0.5 or py < -0.5 or px > float(width) - 0.5 or py > float(height) - 0.5:
        return no
    if tc <= 0.0:
        if hist_depth[wp.clamp(int(py + 0.5), 0, height - 1), wp.clamp(int(px + 0.5), 0, width - 1)] <= 0.0:
            return wp.vec4(px, py, tc, 1.0)
        return no
    e = eye - prev_eye
    dist = wp.length(e + d * tc)  # the point's distance from the previous eye
    if not surface_seen(hist_depth, px, py, dist, reject, width, height):  # no history pixel around saw it
        return no
    return wp.vec4(px, py, tc, 1.0)


@wp.func
def bilerp(fresh: wp.array(dtype=wp.vec3, ndim=2), i0: int, i1: int, j0: int, j1: int, a: float,
           b: float) -> wp.vec3:
    """The fresh pixels' bilinear interpolation at (i0 + a, j0 + b) of their grid (i1, j1 the next column and row):
    computed where a window pixel uses it (a surface's kept history does not)."""
    return (fresh[j0, i0] * (1.0 - a) + fresh[j0, i1] * a) * (1.0 - b) + (fresh[j1, i0] * (1.0 - a)
                                                                       + fresh[j1, i1] * a) * b


@wp.func
def resolve_pixel_depth(fresh: wp.array(dtype=wp.vec3, ndim=2), hist: wp.array(dtype=wp.vec3, ndim=2), f: int,
                        ox: int, oy: int, has_hist: int, clamp: int, g: wp.mat33, width: int, height: int, x: int,
                        y: int, depth: wp.array(dtype=float, ndim=2), has_depth: int, inv_view_proj_rot: wp.mat44,
                        eye: wp.vec3, prev_view_proj: wp.mat44, hist_depth: wp.array(dtype=float, ndim=2),
                        reject: float, prev_eye: wp.vec3, blend: float, cubic: int,
                        changing: wp.array(dtype=wp.uint8, ndim=2), has_changing: int,
                        clamp_blend: float, hist_res: wp.array(dtype=float, ndim=2),
                        enlarge: wp.array(dtype=float, ndim=2), sky: int,
                        clamped_cubic: int) -> tuple[wp.vec3, float, float]:
    """One pixel of the window's picture (see the module docstring) and the depth it shows (-1: far field): with
    ``has_depth`` the history is found through the depth of the nearest fresh pixel (``depth[j, i]``, distance along
    the ray; < 0: far field); with ``reject`` > 0 too (the history has its depth, ``hist_depth``) the history is kept
    only where its depth agrees with the reprojected point's (:data:`DEPTH_REJECT`), and not colour-clamped -- except
    where the nearest fresh pixel shows the far field or a surface whose colour changes with time or the view
    (``changing[j, i]`` != 0, e.g. water's waves), which keep the colour clamp."""
    lh = fresh.shape[0]
    lw = fresh.shape[1]
    dx = x - ox
    dy = y - oy
    m = f - 1  # f is a power of two (FACTORS): the remainder is a mask, the quotient a product with 1/f (exact)
    if dx >= 0 and dy >= 0 and (dx & m) == 0 and (dy & m) == 0:
        c = fresh[dy // f, dx // f]
        t_own = -1.0
        if has_depth != 0:
            t_own = depth[dy // f, dx // f]
        return c, t_own, 1.0
    # this pixel in the fresh grid: bilinear weights, and the nearest fresh pixel (the centre of the clamp's cross)
    inv_f = 1.0 / float(f)
    u = wp.clamp(float(dx) * inv_f, 0.0, float(lw - 1))
    v = wp.clamp(float(dy) * inv_f, 0.0, float(lh - 1))
    i0 = wp.min(int(u), lw - 1)
    j0 = wp.min(int(v), lh - 1)
    i1 = wp.min(i0 + 1, lw - 1)
    j1 = wp.min(j0 + 1, lh - 1)
    a = u - float(i0)
    b = v - float(j0)
    ci = wp.min(int(u + 0.5), lw - 1)
    cj = wp.min(int(v + 0.5), lh - 1)
    t = -1.0
    t00 = -1.0
    t10 = -1.0
    t01 = -1.0
    t11 = -1.0
    if has_depth != 0:
        # the depth of the nearest fresh pixel; on a smooth surface (the four around within DEPTH_SMOOTH of each
        # other) their bilinear interpolation, which follows a plane's depth between the fresh pixels
        t = depth[cj, ci]
        t00 = depth[j0, i0]
        t10 = depth[j0, i1]
        t01 = depth[j1, i0]
        t11 = depth[j1, i1]
        tlo = wp.min(wp.min(t00, t10), wp.min(t01, t11))
        thi = wp.max(wp.max(t00, t10), wp.max(t01, t11))
        if tlo > 0.0 and thi <= tlo * DEPTH_SMOOTH:
            t = (t00 * (1.0 - a) + t10 * a) * (1.0 - b) + (t01 * (1.0 - a) + t11 * a) * b
    if has_hist == 0:
        return bilerp(fresh, i0, i1, j0, j1, a, b), t, 1.0 / float(f)
    steady = int(1)  # the nearest fresh pixel shows a surface whose colour only the motion changes
    if has_changing != 0:
        if changing[cj, ci] != wp.uint8(0):
            steady = 0
    if has_depth != 0 and reject > 0.0 and t > 0.0 and steady != 0:
        # geometric rejection: the candidates are this pixel's depth, then each of the four fresh pixels' around
        # (at a silhouette the pixel may lie on either side); the first whose point the history saw (its depth there
        # within the ratio ``reject``) is kept, refined onto the history's own surface
        d = pixel_ray(x, y, width, height, inv_view_proj_rot)
        found = wp.vec4(0.0, 0.0, 0.0, 0.0)
        for k in range(5):
            tc = t
            if k == 1:
                tc = t00
            elif k == 2:
                tc = t10
            elif k == 3:
                tc = t01
            elif k == 4:
                tc = t11
            if found[3] == 0.0 and (k == 0 or tc != t):
                cand = history_candidate(x, y, tc, d, g, eye, prev_eye, prev_view_proj, hist_depth, reject, width,
                                         height)
                if cand[3] != 0.0:
                    found = cand
        if found[3] != 0.0:
            tk = found[2]
            # the history's sharpness at the point (1: rendered there; 1/f: the interpolation's), lost as the point
            # comes nearer (its picture enlarged by the previous distance over this one); below SHARPNESS_MIX / f the
            # interpolation of this frame's fresh pixels takes over, wholly at 1/f
            rh = hist_res[wp.clamp(int(found[1] + 0.5), 0, height - 1), wp.clamp(int(found[0] + 0.5), 0, width - 1)]
            grow = enlarge[cj, ci]  # the fresh cell's enlargement; else the distances' ratio (size ~ 1/distance)
            if grow <= 0.0:
                grow = wp.length(eye - prev_eye + d * tk) / wp.max(tk, 1.0e-6)
            res = wp.min(1.0, rh / wp.max(grow, 1.0e-6))
            w = wp.max(wp.clamp((SHARPNESS_MIX - res * float(f)) / (SHARPNESS_MIX - 1.0), 0.0, 1.0), blend)
            if w >= 1.0:  # the interpolation wholly: the history's colour is not needed (most of the cost)
                return bilerp(fresh, i0, i1, j0, j1, a, b), tk, 1.0 / float(f)
            hs = wp.vec3(0.0, 0.0, 0.0)
            if tk > 0.0:
                hs4 = sample_surface(hist, hist_depth, found[0], found[1], wp.length(eye - prev_eye + d * tk), reject,
                                     width, height, cubic)
                hs = wp.vec3(hs4[0], hs4[1], hs4[2])
            else:
                hs = sample_history(hist, found[0], found[1], width, height, cubic)
            h = hs
            if w > 0.0:  # (else the history alone: the interpolation is not computed)
                h = hs + (bilerp(fresh, i0, i1, j0, j1, a, b) - hs) * w
            return h, tk, res + (1.0 / float(f) - res) * w
        return bilerp(fresh, i0, i1, j0, j1, a, b), t, 1.0 / float(f)
    hcubic = cubic
    if has_depth != 0 and clamp != 0:  # a frame with depth, while anything changes: the colour-clamped history
        if sky == 0 and t <= 0.0:  # the far field: the interpolation
            return bilerp(fresh, i0, i1, j0, j1, a, b), t, 1.0 / float(f)
        hcubic = clamped_cubic
    q = g * wp.vec3(float(x), float(y), 1.0)
    if has_depth != 0 and t > 0.0:
        q = depth_reprojection(x, y, t, width, height, inv_view_proj_rot, eye, prev_view_proj)
    if q[2] <= 0.0:  # the point was behind the previous camera
        return bilerp(fresh, i0, i1, j0, j1, a, b), t, 1.0 / float(f)
    px = q[0] / q[2]
    py = q[1] / q[2]
    if px < -0.5 or py < -0.5 or px > float(width) - 0.5 or py > float(height) - 0.5:  # off the previous picture
        return bilerp(fresh, i0, i1, j0, j1, a, b), t, 1.0 / float(f)
    h = sample_history(hist, px, py, width, height, hcubic)
    if clamp != 0:
        xa = wp.max(ci - 1, 0)
        xb = wp.min(ci + 1, lw - 1)
        ya = wp.max(cj - 1, 0)
        yb = wp.min(cj + 1, lh - 1)
        s1 = fresh[ya, ci]
        s3 = fresh[cj, xa]
        s4 = fresh[cj, ci]
        s5 = fresh[cj, xb]
        s7 = fresh[yb, ci]
        lo = wp.min(wp.min(wp.min(s1, s3), wp.min(s4, s5)), s7)
        hi = wp.max(wp.max(wp.max(s1, s3), wp.max(s4, s5)), s7)
        h = wp.min(wp.max(h, lo), hi)
        h = h + (bilerp(fresh, i0, i1, j0, j1, a, b) - h) * clamp_blend
        return h, t, 1.0 / float(f)
    # unclamped (a still view): the history as it is, and its sharpness with it
    return h, t, hist_res[wp.clamp(int(py + 0.5), 0, height - 1), wp.clamp(int(px + 0.5), 0, width - 1)]


@wp.kernel
def enlargement_kernel(row0: int, depth: wp.array(dtype=float, ndim=2), f: int, ox: int, oy: int, width: int,
                       height: int, inv_view_proj_rot: wp.mat44, eye: wp.vec3, prev_view_proj: wp.mat44,
                       out: wp.array(dtype=float, ndim=2)):
    """How much the picture of each fresh pixel's surface has been enlarged since the previous frame (linear: the
    square root of f^2 over the area its cell -- it and its right and lower neighbours -- covered in the previous
    picture); -1 where the three do not lie on one smooth surface in front of both cameras (an edge, the sky)."""
    i, j = wp.tid()
    jj = row0 + i
    lh = depth.shape[0]
    lw = depth.shape[1]
    ja = wp.min(jj, lh - 2)
    ia = wp.min(j, lw - 2)
    t0 = depth[ja, ia]
    t1 = depth[ja, ia + 1]
    t2 = depth[ja + 1, ia]
    lo = wp.min(wp.min(t0, t1), t2)
    hi = wp.max(wp.max(t0, t1), t2)
    m = float(-1.0)
    if lo > 0.0 and hi <= lo * DEPTH_SMOOTH:
        x0 = f * ia + ox
        y0 = f * ja + oy
        q0 = depth_reprojection(x0, y0, t0, width, height, inv_view_proj_rot, eye, prev_view_proj)
        q1 = depth_reprojection(x0 + f, y0, t1, width, height, inv_view_proj_rot, eye, prev_view_proj)
        q2 = depth_reprojection(x0, y0 + f, t2, width, height, inv_view_proj_rot, eye, prev_view_proj)
        if q0[2] > 0.0 and q1[2] > 0.0 and q2[2] > 0.0:
            ax = q1[0] / q1[2] - q0[0] / q0[2]
            ay = q1[1] / q1[2] - q0[1] / q0[2]
            bx = q2[0] / q2[2] - q0[0] / q0[2]
            by = q2[1] / q2[2] - q0[1] / q0[2]
            area = wp.abs(ax * by - ay * bx)
            if area > 1.0e-6:
                m = wp.sqrt(float(f * f) / area)
    out[jj, j] = m


@wp.kernel
def resolve_kernel(row0: int, fresh: wp.array(dtype=wp.vec3, ndim=2), hist: wp.array(dtype=wp.vec3, ndim=2),
                   f: int, ox: int, oy: int, has_hist: int, clamp: int, g: wp.mat33, width: int, height: int,
                   depth: wp.array(dtype=float, ndim=2), has_depth: int, inv_view_proj_rot: wp.mat44,
                   eye: wp.vec3, prev_view_proj: wp.mat44, hist_depth: wp.array(dtype=float, ndim=2),
                   reject: float, prev_eye: wp.vec3, blend: float, cubic: int,
                   changing: wp.array(dtype=wp.uint8, ndim=2), has_changing: int, clamp_blend: float,
                   hist_res: wp.array(dtype=float, ndim=2), enlarge: wp.array(dtype=float, ndim=2), sky: int,
                   clamped_cubic: int, out: wp.array(dtype=wp.vec3, ndim=2), out_depth: wp.array(dtype=float, ndim=2),
                   out_res: wp.array(dtype=float, ndim=2),
                   shown: wp.array(dtype=wp.uint8, ndim=3)):
    i, x = wp.tid()
    y = row0 + i
    c, r, res = resolve_pixel_depth(fresh, hist, f, ox, oy, has_hist, clamp, g, width, height, x, y, depth, has_depth,
                            inv_view_proj_rot, eye, prev_view_proj, hist_depth, reject, prev_eye, blend, cubic,
                            changing, has_changing, clamp_blend, hist_res, enlarge, sky,
                            clamped_cubic)
    out[y, x] = c
    out_depth[y, x] = r
    out_res[y, x] = res
    for k in range(3):
        shown[y, x, k] = wp.uint8(int(wp.clamp(c[k], 0.0, 255.0) + 0.5))


class TemporalUpsampler:
    """The reconstruction of one viewer (see the module docstring): ``plan`` says what the next frame renders,
    ``resolve`` turns that render into the window's picture and keeps it as the next frame's history.

    ``width`` x ``height`` the window's picture; ``factor`` the wanted reduction (:func:`factor_for` picks the
    largest that divides both sides). The policy where the frames come with depth (``resolve(..., depth=)``):
    ``depth_blend`` (:data:`DEPTH_BLEND`), ``depth_reject`` (:data:`DEPTH_REJECT`; 0: the colour clamp instead, as
    without depth) and ``cubic`` (:data:`CUBIC_HISTORY`); without depth the history is sampled bilinearly, clamped
    and blended with :data:`HISTORY_BLEND`."""

    def __init__(self, launcher, width: int, height: int, factor: int = 2, depth_blend: float | None = None,
                 depth_reject: float | None = None, cubic: bool | None = None, sky: bool | None = None,
                 clamped_cubic: bool | None = None):
        self.launcher = launcher
        self.device = launcher.device
        self.width, self.height = int(width), int(height)
        self.depth_blend = float(DEPTH_BLEND if depth_blend is None else depth_blend)
        self.depth_reject = float(DEPTH_REJECT if depth_reject is None else depth_reject)
        self.cubic = bool(CUBIC_HISTORY if cubic is None else cubic)
        self.sky = bool(SKY_HISTORY if sky is None else sky)
        self.clamped_cubic = bool(CLAMPED_CUBIC if clamped_cubic is None else clamped_cubic)
        if not 0.0 <= self.depth_blend <= 1.0:
            raise ValueError(f"depth_blend must be in [0, 1], got {self.depth_blend}")
        if not (self.depth_reject == 0.0 or self.depth_reject >= 1.0):
            raise ValueError(f"depth_reject must be 0 (off) or >= 1, got {self.depth_reject}")
        self.set_factor(factor)
        self.count = 0
        self._hist = wp.zeros((self.height, self.width), dtype=wp.vec3, device=self.device)
        self._out = wp.zeros((self.height, self.width), dtype=wp.vec3, device=self.device)
        self._hdepth = wp.zeros((self.height, self.width), dtype=float, device=self.device)
        self._odepth = wp.zeros((self.height, self.width), dtype=float, device=self.device)
        # each pixel's sharpness: 1 rendered, 1/f interpolated, less for a history enlarged since it was rendered
        self._hres = wp.ones((self.height, self.width), dtype=float, device=self.device)
        self._ores = wp.ones((self.height, self.width), dtype=float, device=self.device)
        self._hdepth_ok = False  # whether the history has its depth (the frame before came with depth)
        self._shown = wp.zeros((self.height, self.width, 3), dtype=wp.uint8, device=self.device)
        self._no_changing = wp.zeros((1, 1), dtype=wp.uint8, device=self.device)  # unread
        self._no_depth = wp.zeros((1, 1), dtype=float, device=self.device)  # unread
        self._prev_cam = None
        self._prev_key = None

    def set_factor(self, factor: int) -> None:
        self.factor = factor_for(self.width, self.height, int(factor))
        self._phases = phases(self.factor)

    def reset(self) -> None:
        """Forget the history (the next frame is interpolated from its own pixels)."""
        self._prev_cam = None
        self._prev_key = None
        self._hdepth_ok = False

    def remember(self, image: np.ndarray, camera, key=None, depth: np.ndarray | None = None) -> None:
        """Take a full-resolution picture (uint8, e.g. the viewer's refined frame) as the history, with its depth
        where it has one (float, the same size; as ``resolve``'s)."""
        if image.shape[:2] != (self.height, self.width):
            raise ValueError(f"image must be {self.width}x{self.height}, got {image.shape[1]}x{image.shape[0]}")
        self._hist = wp.array(np.ascontiguousarray(image[..., :3], dtype=np.float32), dtype=wp.vec3,
                              device=self.device)
        self._hdepth_ok = depth is not None
        if depth is not None:
            self._hdepth = self._depth_array(depth, self.width, self.height)
            self._hres = wp.ones((self.height, self.width), dtype=float, device=self.device)
        self._prev_cam = camera
        self._prev_key = key

    def _depth_array(self, depth, w: int, h: int):
        depth = np.asarray(depth, np.float32)
        if depth.shape != (h, w):
            raise ValueError(f"depth must be {w}x{h}, got {'x'.join(str(n) for n in depth.shape[::-1])}")
        return wp.array(np.where(np.isfinite(depth), depth, -1.0).astype(np.float32), dtype=float,
                        device=self.device)

    def plan(self) -> tuple[int, int, tuple[float, float]]:
        """(width, height, jitter_px) of the next frame's render: the reduced size and the sub-pixel offset (in the
        reduced image's pixels) that puts its pixel (i, j) on the window's pixel (f i + ox, f j + oy)."""
        f = self.factor
        ox, oy = self._phases[self.count % len(self._phases)]
        return self.width // f, self.height // f, ((ox + 0.5) / f - 0.5, (oy + 0.5) / f - 0.5)

    def resolve(self, fresh: np.ndarray, camera, key=None, depth: np.ndarray | None = None,
                clamp: bool | None = None, changing: np.ndarray | None = None) -> np.ndarray:
        """The window's picture (uint8, height x width x 3) from ``fresh`` (the planned render, uint8) and the
        frame's ``camera`` (:class:`pywarp.kernels.camera.Camera` without the jitter, any size of this aspect).
        ``key``: what the picture depends on besides the camera (the scene's settings other than its size); the
        clamp is off while the key and the camera stay the same. ``depth``: optional, ``fresh``'s size, each pixel's
        distance along its (jittered) unit ray from the camera's eye to the surface it shows (< 0 or not finite:
        far, e.g. the sky); with it the history is reprojected through the depth, exact under translation as well
        as turning (without it: the far-field homography), and where the previous frame had depth too it is kept
        or rejected by its depth (``depth_reject``) instead of the colour clamp. ``clamp=False``: off whatever
        moves -- for a picture that is a function of the view direction only (a background seen from its own
        place, as rain's), where the far-field reprojection is exact and the clamp would only blur the history.
        ``changing``: optional with ``depth``, ``fresh``'s size, true where the surface's colour changes with time or
        the view direction beyond the motion (water's waves and reflections): there the history is colour-clamped
        as without the depth's rejection."""
        f = self.factor
        ox, oy = self._phases[self.count % len(self._phases)]
        lw, lh = self.width // f, self.height // f
        if fresh.shape[:2] != (lh, lw):
            raise ValueError(f"fresh must be {lw}x{lh} (the planned size), got {fresh.shape[1]}x{fresh.shape[0]}")
        src = wp.array(np.ascontiguousarray(fresh[..., :3], dtype=np.float32), dtype=wp.vec3, device=self.device)
        has_hist = self._prev_cam is not None
        same_camera = has_hist and all(
            np.array_equal(getattr(camera, n), getattr(self._prev_cam, n)) for n in ("view_proj", "inv_view_proj"))
        still = same_camera and key == self._prev_key
        prev = self._prev_cam if has_hist else camera
        g = reprojection(camera, prev, self.width, self.height)
        if depth is not None:
            if np.shape(depth) != (lh, lw):
                raise ValueError(f"depth must be {lw}x{lh} (the planned size), got "
                                 f"{'x'.join(str(n) for n in np.shape(depth)[::-1])}")
            dep = self._depth_array(depth, lw, lh)
        else:
            dep = self._no_depth  # unread
        if changing is not None:
            if depth is None or np.shape(changing) != (lh, lw):
                raise ValueError(f"changing must come with depth and be {lw}x{lh} (the planned size), got "
                                 f"{'x'.join(str(n) for n in np.shape(changing)[::-1])}")
            chg = wp.array(np.ascontiguousarray(np.asarray(changing, bool), dtype=np.uint8), dtype=wp.uint8,
                           device=self.device)
        else:
            chg = self._no_changing
        with_depth = depth is not None and self._hdepth_ok and has_hist
        reject = self.depth_reject if with_depth and not still else 0.0
        if reject > 0.0:
            grow = wp.empty((lh, lw), dtype=float, device=self.device)
            self.launcher.launch(enlargement_kernel, lh, lw,
                                 [dep, f, ox, oy, self.width, self.height, _mat44(camera.inv_view_proj_rot),
                                  wp.vec3(*np.asarray(camera.eye, np.float32).tolist()), _mat44(prev.view_proj)],
                                 [grow])
        else:
            grow = self._no_depth  # unread
        self.launcher.launch(resolve_kernel, self.height, self.width,
                             [src, self._hist, f, ox, oy, int(has_hist),
                              int(not still if clamp is None else clamp),
                              wp.mat33(*g.astype(np.float32).ravel().tolist()), self.width, self.height,
                              dep, int(depth is not None), _mat44(camera.inv_view_proj_rot),
                              wp.vec3(*np.asarray(camera.eye, np.float32).tolist()), _mat44(prev.view_proj),
                              self._hdepth, float(reject), wp.vec3(*np.asarray(prev.eye, np.float32).tolist()),
                              float(self.depth_blend), int(self.cubic and depth is not None), chg,
                              int(changing is not None), float(HISTORY_BLEND), self._hres, grow,
                              int(self.sky or same_camera), int(self.cubic and self.clamped_cubic and depth is not None)],
                             [self._out, self._odepth, self._ores, self._shown])
        self._hist, self._out = self._out, self._hist
        self._hdepth, self._odepth = self._odepth, self._hdepth
        self._hres, self._ores = self._ores, self._hres
        self._hdepth_ok = depth is not None
        self._prev_cam, self._prev_key = camera, key
        self.count += 1
        return self._shown.numpy().copy()
