"""Temporal reprojection (vc §4.2.1, §4.4) -- Warp twins of ``cclouds/reproj.h``.

Eq 4.1 picks the one pixel of every 4 x 4 block a frame raymarches; the reduced buffer (ceil(W/4) x ceil(H/4),
vc-A22) holds those pixels; the reprojection pass (vc-A26) fills every other pixel from the previous frame through the
inner-sphere hit point and the previous view-projection, or from the reduced buffer when the point was not visible,
optionally averaging an n x n neighbourhood (vc-A27).

Images are float32 arrays (height, width, channels), y = 0 the top row; uv/NDC as in :mod:`pywarp.kernels.camera`.
Choices where the thesis is silent (the header comment of ``cclouds/reproj.h`` has the reasons):
  * frame f taken mod 16 (negative frames wrap too); (a, b) = (f div 4, f mod 4), column by column as in eq 4.1;
  * sizes not divisible by 4: grid ceil(W/4) x ceil(H/4), pixels outside the image skipped (:func:`reproj_grid`);
  * reduced-buffer fallback at the true positions of this frame's rendered pixels: ((x - a)/4, (y - b)/4), clamped to
    the texels written this frame;
  * bilinear lookup with clamp-to-edge at (u W - 0.5, v H - 0.5), snapped to a pixel centre within ``SNAP_PX``;
  * nearest inner-sphere hit in front of the camera; no hit, w <= 0 or uv outside [0, 1]^2 -> fallback;
  * ``history=False`` (first frame, camera cut, camera inside/above the layer) -> fallback for every pixel not
    rendered this frame.

Depth-aware reprojection (not in the thesis; the renderer's default, setting ``reprojection_depth="clouds"``): the
thesis reprojects every pixel through the inner sphere, so a cloud at another distance is fetched from the wrong place
of the previous frame (parallax) and the freshly marched pixel of each 4 x 4 block stands out as a dot grid while the
camera translates. :func:`reproj_uv_depth` finds the previous position through the depth of what the pixel shows
(:func:`reproj_surface_depth`, kept in a depth buffer; the sky far away) by a fixed-point iteration along the
current ray, and samples the previous frame with a clamped Catmull-Rom filter (repeated bilinear resampling blurs the
pixels carried for up to 15 frames); :func:`reproject_frame_depth_kernel` is the pass (checked and launched on
NumPy images by :func:`pywarp.clouds.reproj.reproj_frame_depth`). The choices (nearest previous depth, the
direction of the iterate from the previous eye, ``iterations=0`` = the thesis's point, the filter) and their reasons
are in ``cclouds/reproj.h``.

Image-level kernels follow :class:`pywarp.core.runtime.TileLauncher`'s convention (first parameter ``row0: int``, launched
with ``dim=(rows, width)``).
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.registry import Arg, declare
from .camera import Camera, _check_size, camera_ray
from .raymarch import CloudLayer, raymarch_ray_sphere

REPROJ_BLOCK = 4
REPROJ_CYCLE = 16
#: Reprojected positions within this many pixels of a pixel centre are snapped to it: above the float32 round-off of
#: the reprojected position (<= 4.5e-4 px measured at 1920 x 1080, ~2e-3 px at 7680 wide), invisible as a shift.
SNAP_PX = 1.0 / 256.0
_SNAP = wp.constant(SNAP_PX)
#: vc-A27 default neighbourhood (n x n box of bilinear samples one pixel apart).
AVERAGE_NEIGHBOURHOOD = 3
#: Fixed-point refinements of the depth-aware reprojection (CCL_REPROJ_DEPTH_ITERATIONS; the reason is in
#: cclouds/reproj.h) and the largest accepted number (CCL_REPROJ_MAX_DEPTH_ITERATIONS: bounds the work per pixel).
DEPTH_ITERATIONS = 2
MAX_DEPTH_ITERATIONS = 16
#: Depth of the sky in the depth buffer (CCL_REPROJ_SKY_DEPTH_KM): a 1 km camera step moves it by 1e-5 rad (0.02 px at
#: 1920 px over 60 deg), and float32 positions there keep 1e-7 rad of direction.
SKY_DEPTH_KM = 1.0e5
_SKY_DEPTH = wp.constant(SKY_DEPTH_KM)
#: Samplers of the previous frame (ccl_reproj_filter): the thesis's bilinear, or Catmull-Rom over 4 x 4 pixels clamped
#: to the 2 x 2 bilinear footprint (keeps the detail of pixels carried for up to 15 frames; reasons in reproj.h).
FILTERS = {"bilinear": 0, "catmull_rom": 1}
_CATMULL_ROM = wp.constant(1)


# --- vc-4.1 -----------------------------------------------------------------------------------------------------------

@wp.func
def _mod16(frame: int) -> int:
    return ((frame % 16) + 16) % 16


# the pixel index 4 id + 3 must fit in int32 (CCL_REPROJ_MAX_ID)
_ID_MAX = (2**31 - 1 - 3) // 4
#: Largest vc-A27 neighbourhood (CCL_REPROJ_MAX_NEIGHBOURHOOD): a 31 px box is a blur far wider than the 4 x 4 block
#: the reprojection fills (the thesis uses 3) and bounds the work per pixel (961 bilinear samples).
MAX_NEIGHBOURHOOD = 31


@declare("vc-4.1", c="ccl_reproj_pixel",
         args=(Arg("id_x", "thread index x (grid of ceil(W/4) columns)", lo=0, hi=_ID_MAX),
               Arg("id_y", "thread index y (grid of ceil(H/4) rows)", lo=0, hi=_ID_MAX),
               Arg("frame", "frame number (taken mod 16)")),
         outputs=("x", "y"),
         summary="reproj_pixel(id_x, id_y, frame) -> (x, y) int32: f = frame mod 16, a = floor(f/4), b = f mod 4, "
                 "(x, y) = (4 id_x + a, 4 id_y + b). Thread grid ceil(W/4) x ceil(H/4) (reproj_grid); threads whose "
                 "pixel lies outside the image are skipped.",
         references=("Barvir, Volumetric clouds, FIT BUT 2020, eq. 4.1",))
@wp.func
def reproj_pixel(id_x: int, id_y: int, frame: int) -> tuple[int, int]:
    """vc-4.1: (x, y) = (4 id_x + a, 4 id_y + b), a = floor(f / 4), b = f mod 4, f = frame mod 16."""
    f = _mod16(frame)
    return id_x * 4 + f / 4, id_y * 4 + f % 4


@wp.func
def reproj_updated(x: int, y: int, frame: int) -> int:
    """vc-4.1: 1 if pixel (x, y) is raymarched in this frame."""
    f = _mod16(frame)
    r = 0
    if x % 4 == f / 4 and y % 4 == f % 4:
        r = 1
    return r


def reproj_grid(width: int, height: int) -> tuple[int, int]:
    """Thread grid and reduced-buffer size (ceil(width / 4), ceil(height / 4)) (vc-4.1 bounds rule, vc-A22), the twin
    of ``ccl_reproj_grid``.

    Thread (i, j) renders pixel ``reproj_pixel(i, j, frame)`` and is skipped when that pixel lies outside the image;
    over 16 consecutive frames every pixel is then rendered exactly once.
    """
    w = _check_size(width, "width")
    h = _check_size(height, "height")
    return (w - 1) // REPROJ_BLOCK + 1, (h - 1) // REPROJ_BLOCK + 1


# --- vc-A22 -----------------------------------------------------------------------------------------------------------

@wp.func
def _reduced_axis(p: int, off: int, size: int) -> float:
    last = size - 1 - off
    r = wp.nan
    if last >= 0:
        hi = float(last / 4)
        r = float(p - off) * 0.25
        if r < 0.0:
            r = 0.0
        if r > hi:
            r = hi
    return r


def _check_reduced(**kw):
    x, y, w, h = (np.asarray(kw[n]) for n in ("x", "y", "width", "height"))
    if np.any(x >= w):
        raise ValueError(f"x must be < width, got x={np.max(x)}, width={np.min(w)}")
    if np.any(y >= h):
        raise ValueError(f"y must be < height, got y={np.max(y)}, height={np.min(h)}")


def _reduced_samples(rng, n):
    w, h = rng.integers(1, 4096, n), rng.integers(1, 4096, n)
    return {"x": rng.integers(0, w).astype(np.int32), "y": rng.integers(0, h).astype(np.int32),
            "width": w.astype(np.int32), "height": h.astype(np.int32)}


@declare("vc-A22", c="ccl_reproj_reduced_coord",
         args=(Arg("x", "pixel x (< width)", lo=0), Arg("y", "pixel y (< height)", lo=0),
               Arg("frame", "frame number (mod 16)"),
               # width, height >= 1 follow from 0 <= x < width, 0 <= y < height (the cross-argument check)
               Arg("width", "image width (> x)"), Arg("height", "image height (> y)")),
         outputs=("rx", "ry"), check=_check_reduced, samples=_reduced_samples,
         summary="Reduced (1/4 x 1/4) buffer coordinates of pixel (x, y) in frame f: ((x - a)/4, (y - b)/4) clamped to "
                 "the texels written this frame; equals the texel (x div 4, y div 4) the pixel writes when it is "
                 "rendered this frame; NaN when the frame renders no pixel in that direction (size < 4).",
         references=("Barvir, Volumetric clouds, FIT BUT 2020, §4.3.2 (reduced frame buffer)",))
@wp.func
def reproj_reduced_coord(x: int, y: int, frame: int, width: int, height: int) -> tuple[float, float]:
    """vc-A22: reduced-buffer coordinates ((x - a)/4, (y - b)/4) clamped to the texels written this frame."""
    f = _mod16(frame)
    return _reduced_axis(x, f / 4, width), _reduced_axis(y, f % 4, height)


# --- vc-A26 / vc-A27 --------------------------------------------------------------------------------------------------

@wp.func
def _inner_sphere_t(eye: wp.vec3, d: wp.vec3, centre: wp.vec3, r_inner: float) -> float:
    """Nearest inner-sphere hit in front of the camera (the far root from inside); NaN or <= 0: none."""
    t0, t1 = raymarch_ray_sphere(eye, d, centre, r_inner)
    t = t1
    if t0 > 0.0:
        t = t0
    return t


@wp.func
def _project(m: wp.mat44, eye: wp.vec3, d: wp.vec3, t: float) -> tuple[int, float, float]:
    """(1, u, v) of the point eye + d t in the camera m; (0, NaN, NaN) when clip w <= 0 (or NaN)."""
    px = eye[0] + d[0] * t
    py = eye[1] + d[1] * t
    pz = eye[2] + d[2] * t
    cx = m[0][0] * px + m[0][1] * py + m[0][2] * pz + m[0][3]
    cy = m[1][0] * px + m[1][1] * py + m[1][2] * pz + m[1][3]
    cw = m[3][0] * px + m[3][1] * py + m[3][2] * pz + m[3][3]
    ok = int(0)
    u = wp.nan
    v = wp.nan
    if cw > 0.0:
        ok = 1
        u = (cx / cw) * 0.5 + 0.5
        v = 0.5 - (cy / cw) * 0.5
    return ok, u, v


@wp.func
def _inside_unit(u: float, v: float) -> int:
    r = int(0)
    if u >= 0.0 and u <= 1.0 and v >= 0.0 and v <= 1.0:
        r = 1
    return r


@wp.func
def reproj_uv(inv_view_proj_rot: wp.mat44, eye: wp.vec3, prev_view_proj: wp.mat44, centre: wp.vec3, r_inner: float,
              x: int, y: int, width: int, height: int) -> tuple[int, float, float]:
    """vc-A26 step 2: (visible, u, v) of pixel (x, y) in the previous frame via the inner-sphere hit point."""
    d = camera_ray(inv_view_proj_rot, x, y, width, height)
    t = _inner_sphere_t(eye, d, centre, r_inner)
    u = wp.nan
    v = wp.nan
    ok = int(0)
    if t > 0.0:
        front, u, v = _project(prev_view_proj, eye, d, t)
        if front == 1:
            ok = _inside_unit(u, v)
    return ok, u, v


# --- depth-aware reprojection (not in the thesis; choices in cclouds/reproj.h) ----------------------------------------

@wp.func
def reproj_surface_depth(march_depth: float, eye: wp.vec3, d: wp.vec3, centre: wp.vec3, r_earth: float) -> float:
    """Twin of ``ccl_reproj_surface_depth``: the distance (km) along the unit ray d of what a pixel shows -- the
    march's mean cloud distance when > 0, else the ground ahead, else the sky (``SKY_DEPTH_KM``); NaN for NaN input."""
    if wp.isnan(march_depth) or wp.isnan(eye[0] + eye[1] + eye[2]) or wp.isnan(d[0] + d[1] + d[2]):
        return wp.nan
    if march_depth > 0.0:
        return march_depth
    e0, e1 = raymarch_ray_sphere(eye, d, centre, r_earth)
    if e0 > 0.0:
        return e0
    return _SKY_DEPTH


@wp.func
def _nearest_index(p: float, n: int) -> int:
    f = wp.floor(p + 0.5)
    if not (f >= 0.0):
        f = 0.0
    if f > float(n - 1):
        f = float(n - 1)
    return int(f)


@wp.func
def reproj_uv_depth(inv_view_proj_rot: wp.mat44, eye: wp.vec3, prev_view_proj: wp.mat44, prev_eye: wp.vec3,
                    prev_depth: wp.array2d(dtype=float), centre: wp.vec3, r_inner: float, iterations: int, x: int,
                    y: int, width: int, height: int) -> tuple[int, float, float, float]:
    """Twin of ``ccl_reproj_uv_depth``: (visible, u, v, t) of pixel (x, y) in the previous frame through the depth
    of what it shows -- t from the inner sphere, then ``iterations`` times: X = eye + d t, uv = prev_view_proj X,
    Y = prev_eye + D (X - prev_eye)/|X - prev_eye| with D the previous depth at the nearest pixel of uv, t = |Y - eye|;
    uv of the final t. ``iterations = 0``: :func:`reproj_uv`'s point."""
    m = prev_view_proj
    d = camera_ray(inv_view_proj_rot, x, y, width, height)
    t = _inner_sphere_t(eye, d, centre, r_inner)
    # the iterate in the previous camera's clip space, linear in t: clip(eye + d t) = a + t b with a = M (eye, 1),
    # b = M (d, 0); the camera's step e = eye - prev_eye
    ax = m[0][0] * eye[0] + m[0][1] * eye[1] + m[0][2] * eye[2] + m[0][3]
    ay = m[1][0] * eye[0] + m[1][1] * eye[1] + m[1][2] * eye[2] + m[1][3]
    aw = m[3][0] * eye[0] + m[3][1] * eye[1] + m[3][2] * eye[2] + m[3][3]
    bx = m[0][0] * d[0] + m[0][1] * d[1] + m[0][2] * d[2]
    by = m[1][0] * d[0] + m[1][1] * d[1] + m[1][2] * d[2]
    bw = m[3][0] * d[0] + m[3][1] * d[1] + m[3][2] * d[2]
    ex = eye[0] - prev_eye[0]
    ey = eye[1] - prev_eye[1]
    ez = eye[2] - prev_eye[2]
    if not (t > 0.0):
        return int(0), wp.nan, wp.nan, wp.nan
    for k in range(iterations):
        cw = aw + t * bw
        if not (cw > 0.0):
            break
        u = ((ax + t * bx) / cw) * 0.5 + 0.5
        v = 0.5 - ((ay + t * by) / cw) * 0.5
        dp = prev_depth[_nearest_index(v * float(height) - 0.5, height), _nearest_index(u * float(width) - 0.5, width)]
        if not (dp > 0.0):
            break
        # q = X - prev_eye = d t + e; Y - eye = q dp / |q| - e; t = |Y - eye|
        qx = d[0] * t + ex
        qy = d[1] * t + ey
        qz = d[2] * t + ez
        lq = wp.sqrt(qx * qx + qy * qy + qz * qz)
        if not (lq > 0.0):
            break
        s = dp / lq
        yx = qx * s - ex
        yy = qy * s - ey
        yz = qz * s - ez
        tn = wp.sqrt(yx * yx + yy * yy + yz * yz)
        if not (tn > 0.0) or wp.isinf(tn):
            break
        t = tn
    # the final point as reproj_uv projects it (iterations = 0: its uv bit for bit)
    front, u, v = _project(prev_view_proj, eye, d, t)
    ok = int(0)
    if front == 1:
        ok = _inside_unit(u, v)
    return ok, u, v, t


@wp.func
def _bilinear(img: wp.array3d(dtype=float), xmax: int, ymax: int, ch: int, xs: float, ys: float) -> float:
    x0f = wp.floor(xs)
    y0f = wp.floor(ys)
    fx = xs - x0f
    fy = ys - y0f
    x0 = wp.clamp(int(x0f), 0, xmax)
    x1 = wp.clamp(int(x0f) + 1, 0, xmax)
    y0 = wp.clamp(int(y0f), 0, ymax)
    y1 = wp.clamp(int(y0f) + 1, 0, ymax)
    p00 = img[y0, x0, ch]
    p10 = img[y0, x1, ch]
    p01 = img[y1, x0, ch]
    p11 = img[y1, x1, ch]
    return (p00 * (1.0 - fx) + p10 * fx) * (1.0 - fy) + (p01 * (1.0 - fx) + p11 * fx) * fy


@wp.func
def _snap(p: float) -> float:
    n = wp.floor(p + 0.5)
    r = p
    if wp.abs(p - n) <= _SNAP:
        r = n
    return r


@wp.func
def _catmull_rom_weights(t: float) -> wp.vec4:
    t2 = t * t
    t3 = t2 * t
    return wp.vec4(-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t,
                   0.5 * t3 - 0.5 * t2)


@wp.func
def _catmull_rom_add(img: wp.array3d(dtype=float), xmax: int, ymax: int, xs: float, ys: float,
                     out: wp.array3d(dtype=float), y: int, x: int):
    """Catmull-Rom lookup of every channel at (xs, ys) (clamp-to-edge), each clamped to the range of the 2 x 2 pixels
    the bilinear lookup reads, added to out[y, x, :] (``catmull_rom_add`` in C)."""
    x0f = wp.floor(xs)
    y0f = wp.floor(ys)
    wx = _catmull_rom_weights(xs - x0f)
    wy = _catmull_rom_weights(ys - y0f)
    x0 = int(x0f)
    y0 = int(y0f)
    xi = wp.vec4i(wp.clamp(x0 - 1, 0, xmax), wp.clamp(x0, 0, xmax), wp.clamp(x0 + 1, 0, xmax),
                  wp.clamp(x0 + 2, 0, xmax))
    yi = wp.vec4i(wp.clamp(y0 - 1, 0, ymax), wp.clamp(y0, 0, ymax), wp.clamp(y0 + 1, 0, ymax),
                  wp.clamp(y0 + 2, 0, ymax))
    for ch in range(img.shape[2]):
        s = float(0.0)
        lo = float(wp.inf)
        hi = float(-wp.inf)
        for j in range(4):
            row = float(0.0)
            for i in range(4):
                val = img[yi[j], xi[i], ch]
                row = row + wx[i] * val
                if (i == 1 or i == 2) and (j == 1 or j == 2):
                    if val < lo:
                        lo = val
                    if val > hi:
                        hi = val
            s = s + wy[j] * row
        if s < lo:
            s = lo
        if s > hi:
            s = hi
        out[y, x, ch] = out[y, x, ch] + s


@wp.func
def _fill_pixel(current: wp.array3d(dtype=float), previous: wp.array3d(dtype=float), reduced: wp.array3d(dtype=float),
                frame: int, neighbourhood: int, filter: int, history: int, valid: int, u: float, v: float, x: int,
                y: int, out: wp.array3d(dtype=float)):
    """The colour of a pixel not rendered this frame: previous at (u, v) when valid (n x n samples of the filter),
    else the reduced buffer, else (no rendered pixel in that direction) previous / current as is (``fill_pixel`` in
    C)."""
    height = current.shape[0]
    width = current.shape[1]
    channels = current.shape[2]
    if valid == 1:
        xs = _snap(u * float(width) - 0.5)
        ys = _snap(v * float(height) - 0.5)
        half = neighbourhood / 2
        inv_n = 1.0 / float(neighbourhood * neighbourhood)
        if filter == _CATMULL_ROM:
            # the weights and indices once per sample, every channel summed in out
            for ch in range(channels):
                out[y, x, ch] = 0.0
            for j in range(-half, half + 1):
                for i in range(-half, half + 1):
                    _catmull_rom_add(previous, width - 1, height - 1, xs + float(i), ys + float(j), out, y, x)
            for ch in range(channels):
                out[y, x, ch] = out[y, x, ch] * inv_n
        else:
            for ch in range(channels):
                s = float(0.0)
                for j in range(-half, half + 1):
                    for i in range(-half, half + 1):
                        s = s + _bilinear(previous, width - 1, height - 1, ch, xs + float(i), ys + float(j))
                out[y, x, ch] = s * inv_n
    else:
        rx, ry = reproj_reduced_coord(x, y, frame, width, height)
        if wp.isnan(rx) or wp.isnan(ry):
            for ch in range(channels):
                if history != 0:
                    out[y, x, ch] = previous[y, x, ch]
                else:
                    out[y, x, ch] = current[y, x, ch]
        else:
            f = _mod16(frame)
            xmax = (width - 1 - f / 4) / 4
            ymax = (height - 1 - f % 4) / 4
            for ch in range(channels):
                out[y, x, ch] = _bilinear(reduced, xmax, ymax, ch, rx, ry)


@wp.func
def reproject_pixel(current: wp.array3d(dtype=float), previous: wp.array3d(dtype=float),
                    reduced: wp.array3d(dtype=float), frame: int, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                    prev_view_proj: wp.mat44, centre: wp.vec3, r_inner: float, neighbourhood: int, history: int,
                    x: int, y: int, out: wp.array3d(dtype=float)):
    """vc-A26 / vc-A27 for one pixel: keep a pixel rendered this frame, else reproject it (n x n average) from the
    previous frame, else interpolate the reduced buffer."""
    if reproj_updated(x, y, frame) == 1:
        for ch in range(current.shape[2]):
            out[y, x, ch] = current[y, x, ch]
        return
    valid = int(0)
    u = float(0.0)
    v = float(0.0)
    if history != 0:
        valid, u, v = reproj_uv(inv_view_proj_rot, eye, prev_view_proj, centre, r_inner, x, y, current.shape[1],
                                current.shape[0])
    _fill_pixel(current, previous, reduced, frame, neighbourhood, 0, history, valid, u, v, x, y, out)


@wp.func
def _fallback_depth(current_depth: wp.array2d(dtype=float), previous_depth: wp.array2d(dtype=float), frame: int,
                    history: int, x: int, y: int) -> float:
    """The depth of a fallback pixel (``fallback_depth`` in C): this frame's rendered depths (pixel (4i + a, 4j + b)
    holds reduced texel (i, j)) interpolated bilinearly at the reduced-buffer position."""
    height = current_depth.shape[0]
    width = current_depth.shape[1]
    rx, ry = reproj_reduced_coord(x, y, frame, width, height)
    if wp.isnan(rx) or wp.isnan(ry):
        if history != 0:
            return previous_depth[y, x]
        return current_depth[y, x]
    f = _mod16(frame)
    a = f / 4
    b = f % 4
    xmax = (width - 1 - a) / 4
    ymax = (height - 1 - b) / 4
    x0f = wp.floor(rx)
    y0f = wp.floor(ry)
    fx = rx - x0f
    fy = ry - y0f
    x0 = wp.clamp(int(x0f), 0, xmax)
    x1 = wp.clamp(int(x0f) + 1, 0, xmax)
    y0 = wp.clamp(int(y0f), 0, ymax)
    y1 = wp.clamp(int(y0f) + 1, 0, ymax)
    p00 = current_depth[4 * y0 + b, 4 * x0 + a]
    p10 = current_depth[4 * y0 + b, 4 * x1 + a]
    p01 = current_depth[4 * y1 + b, 4 * x0 + a]
    p11 = current_depth[4 * y1 + b, 4 * x1 + a]
    return (p00 * (1.0 - fx) + p10 * fx) * (1.0 - fy) + (p01 * (1.0 - fx) + p11 * fx) * fy


@wp.func
def reproject_pixel_depth(current: wp.array3d(dtype=float), current_depth: wp.array2d(dtype=float),
                          previous: wp.array3d(dtype=float), previous_depth: wp.array2d(dtype=float),
                          reduced: wp.array3d(dtype=float), frame: int, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                          prev_view_proj: wp.mat44, prev_eye: wp.vec3, centre: wp.vec3, r_inner: float,
                          neighbourhood: int, filter: int, iterations: int, history: int, x: int, y: int,
                          out: wp.array3d(dtype=float), out_depth: wp.array2d(dtype=float)):
    """One pixel of ``ccl_reproj_frame_depth``: keep a pixel rendered this frame (colour and depth), else reproject
    it through its depth (:func:`reproj_uv_depth`), else the reduced-buffer fallback; its depth relative to eye."""
    if reproj_updated(x, y, frame) == 1:
        for ch in range(current.shape[2]):
            out[y, x, ch] = current[y, x, ch]
        out_depth[y, x] = current_depth[y, x]
        return
    valid = int(0)
    u = float(0.0)
    v = float(0.0)
    t = float(0.0)
    if history != 0:
        valid, u, v, t = reproj_uv_depth(inv_view_proj_rot, eye, prev_view_proj, prev_eye, previous_depth, centre,
                                         r_inner, iterations, x, y, current.shape[1], current.shape[0])
    _fill_pixel(current, previous, reduced, frame, neighbourhood, filter, history, valid, u, v, x, y, out)
    if valid == 1 and not wp.isinf(t):
        out_depth[y, x] = t
    else:
        out_depth[y, x] = _fallback_depth(current_depth, previous_depth, frame, history, x, y)


@wp.kernel
def reproject_frame_kernel(row0: int, current: wp.array3d(dtype=float), previous: wp.array3d(dtype=float),
                           reduced: wp.array3d(dtype=float), frame: int, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                           prev_view_proj: wp.mat44, centre: wp.vec3, r_inner: float, neighbourhood: int,
                           history: int, out: wp.array3d(dtype=float)):
    """vc-A26 over a frame (TileLauncher convention: pixel (row0 + i, j) of thread (i, j))."""
    i, j = wp.tid()
    reproject_pixel(current, previous, reduced, frame, inv_view_proj_rot, eye, prev_view_proj, centre, r_inner,
                    neighbourhood, history, j, row0 + i, out)


@wp.kernel
def reproject_frame_depth_kernel(row0: int, current: wp.array3d(dtype=float), current_depth: wp.array2d(dtype=float),
                                 previous: wp.array3d(dtype=float), previous_depth: wp.array2d(dtype=float),
                                 reduced: wp.array3d(dtype=float), frame: int, inv_view_proj_rot: wp.mat44,
                                 eye: wp.vec3, prev_view_proj: wp.mat44, prev_eye: wp.vec3, centre: wp.vec3,
                                 r_inner: float, neighbourhood: int, filter: int, iterations: int, history: int,
                                 # outputs
                                 out: wp.array3d(dtype=float), out_depth: wp.array2d(dtype=float)):
    """The depth-aware pass over a frame (``ccl_reproj_frame_depth``; TileLauncher convention)."""
    i, j = wp.tid()
    reproject_pixel_depth(current, current_depth, previous, previous_depth, reduced, frame, inv_view_proj_rot, eye,
                          prev_view_proj, prev_eye, centre, r_inner, neighbourhood, filter, iterations, history, j,
                          row0 + i, out, out_depth)


# --- the frame pass (its evaluators are pywarp.clouds.reproj's) -------------------------------------------------------

# Not element-wise: whole images in and out (each pixel reads a neighbourhood of the previous frame and the reduced
# buffer), and the cameras are struct arguments. vc-A27 is the same pass with neighbourhood > 1 (3 in the thesis's
# figure 4.14b, AVERAGE_NEIGHBOURHOOD).
declare("vc-A26", "vc-A27", c="ccl_reproj_frame", name="reproj_frame",
        make_warp="pywarp.clouds.reproj:frame_warp", make_c="pywarp.clouds.reproj:frame_c",
        summary="reproj_frame(current, previous, reduced, frame, camera, prev_camera, layer=CloudLayer(), "
                "neighbourhood=1, history=True): pixels not rendered this frame are reprojected through the "
                "inner-sphere hit point into the previous frame (bilinear) when visible there, else interpolated from "
                "the reduced buffer. vc-A27 (neighbourhood averaging): neighbourhood = n > 1 (odd) takes the mean of "
                "an n x n box of bilinear samples one pixel apart (AVERAGE_NEIGHBOURHOOD = 3, fig 4.14b), trading "
                "detail for fewer reprojection artifacts.",
        references=("Schneider & Vos, The real-time volumetric cloudscapes of Horizon Zero Dawn, SIGGRAPH 2015",
                    "Barvir, Volumetric clouds, FIT BUT 2020, §4.4, fig. 4.14"))(reproject_pixel)


# --- the depth lookups at chosen pixels (pywarp.clouds.reproj launches them) ------------------------------------------

@wp.kernel
def uv_depth_kernel(xs: wp.array(dtype=wp.int32), ys: wp.array(dtype=wp.int32), width: int, height: int,
                    inv_view_proj_rot: wp.mat44, eye: wp.vec3, prev_view_proj: wp.mat44, prev_eye: wp.vec3,
                    prev_depth: wp.array2d(dtype=float), centre: wp.vec3, r_inner: float, iterations: int,
                    # outputs
                    ok: wp.array(dtype=wp.int32), u: wp.array(dtype=float), v: wp.array(dtype=float),
                    t: wp.array(dtype=float)):
    k = wp.tid()
    a, b, c, e = reproj_uv_depth(inv_view_proj_rot, eye, prev_view_proj, prev_eye, prev_depth, centre, r_inner,
                                 iterations, xs[k], ys[k], width, height)
    ok[k] = a
    u[k] = b
    v[k] = c
    t[k] = e


@wp.kernel
def surface_depth_kernel(march_depth: wp.array(dtype=float), eye: wp.vec3, d: wp.array(dtype=wp.vec3),
                         centre: wp.vec3, r_earth: float,
                         # outputs
                         out: wp.array(dtype=float)):
    k = wp.tid()
    out[k] = reproj_surface_depth(march_depth[k], eye, d[k], centre, r_earth)


__all__ = ["Camera", "CloudLayer", "reproj_grid", "REPROJ_BLOCK", "REPROJ_CYCLE", "SNAP_PX",
           "AVERAGE_NEIGHBOURHOOD", "DEPTH_ITERATIONS", "MAX_DEPTH_ITERATIONS", "SKY_DEPTH_KM", "FILTERS"]
