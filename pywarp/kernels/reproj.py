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

Image-level kernels follow :class:`pywarp.core.runtime.TileLauncher`'s convention (first parameter ``row0: int``, launched
with ``dim=(rows, width)``).
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.registry import Arg, declare
from .camera import Camera, _check_camera, _check_size, camera_ray
from .raymarch import CloudLayer, raymarch_ray_sphere

REPROJ_BLOCK = 4
REPROJ_CYCLE = 16
#: Reprojected positions within this many pixels of a pixel centre are snapped to it: above the float32 round-off of
#: the reprojected position (<= 4.5e-4 px measured at 1920 x 1080, ~2e-3 px at 7680 wide), invisible as a shift.
SNAP_PX = 1.0 / 256.0
_SNAP = wp.constant(SNAP_PX)
#: vc-A27 default neighbourhood (n x n box of bilinear samples one pixel apart).
AVERAGE_NEIGHBOURHOOD = 3


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
def reproj_uv(inv_view_proj_rot: wp.mat44, eye: wp.vec3, prev_view_proj: wp.mat44, centre: wp.vec3, r_inner: float,
              x: int, y: int, width: int, height: int) -> tuple[int, float, float]:
    """vc-A26 step 2: (visible, u, v) of pixel (x, y) in the previous frame via the inner-sphere hit point."""
    m = prev_view_proj
    d = camera_ray(inv_view_proj_rot, x, y, width, height)
    t0, t1 = raymarch_ray_sphere(eye, d, centre, r_inner)
    t = t1
    if t0 > 0.0:
        t = t0
    u = wp.nan
    v = wp.nan
    ok = 0
    if t > 0.0:
        px = eye[0] + d[0] * t
        py = eye[1] + d[1] * t
        pz = eye[2] + d[2] * t
        cx = m[0][0] * px + m[0][1] * py + m[0][2] * pz + m[0][3]
        cy = m[1][0] * px + m[1][1] * py + m[1][2] * pz + m[1][3]
        cw = m[3][0] * px + m[3][1] * py + m[3][2] * pz + m[3][3]
        if cw > 0.0:
            u = (cx / cw) * 0.5 + 0.5
            v = 0.5 - (cy / cw) * 0.5
            if u >= 0.0 and u <= 1.0 and v >= 0.0 and v <= 1.0:
                ok = 1
    return ok, u, v


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
def reproject_pixel(current: wp.array3d(dtype=float), previous: wp.array3d(dtype=float),
                    reduced: wp.array3d(dtype=float), frame: int, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                    prev_view_proj: wp.mat44, centre: wp.vec3, r_inner: float, neighbourhood: int, history: int,
                    x: int, y: int, out: wp.array3d(dtype=float)):
    """vc-A26 / vc-A27 for one pixel: keep a pixel rendered this frame, else reproject it (n x n average) from the
    previous frame, else interpolate the reduced buffer."""
    height = current.shape[0]
    width = current.shape[1]
    channels = current.shape[2]
    if reproj_updated(x, y, frame) == 1:
        for ch in range(channels):
            out[y, x, ch] = current[y, x, ch]
        return
    valid = int(0)
    u = float(0.0)
    v = float(0.0)
    if history != 0:
        valid, u, v = reproj_uv(inv_view_proj_rot, eye, prev_view_proj, centre, r_inner, x, y, width, height)
    if valid == 1:
        xs = _snap(u * float(width) - 0.5)
        ys = _snap(v * float(height) - 0.5)
        half = neighbourhood / 2
        inv_n = 1.0 / float(neighbourhood * neighbourhood)
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


@wp.kernel
def reproject_frame_kernel(row0: int, current: wp.array3d(dtype=float), previous: wp.array3d(dtype=float),
                           reduced: wp.array3d(dtype=float), frame: int, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                           prev_view_proj: wp.mat44, centre: wp.vec3, r_inner: float, neighbourhood: int,
                           history: int, out: wp.array3d(dtype=float)):
    """vc-A26 over a frame (TileLauncher convention: pixel (row0 + i, j) of thread (i, j))."""
    i, j = wp.tid()
    reproject_pixel(current, previous, reduced, frame, inv_view_proj_rot, eye, prev_view_proj, centre, r_inner,
                    neighbourhood, history, j, row0 + i, out)


# --- the frame pass: custom evaluator -------------------------------------------------------------------------------

def _image(value, name: str) -> np.ndarray:
    if isinstance(value, (str, bytes)) or value is None:
        raise TypeError(f"{name} must be a float array (height, width, channels), got {value!r}")
    a = np.asarray(value)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must be numeric, got dtype {a.dtype}")
    if a.ndim == 2:
        a = a[:, :, None]
    if a.ndim != 3:
        raise ValueError(f"{name} must have shape (height, width) or (height, width, channels), got {a.shape}")
    if a.shape[0] < 1 or a.shape[1] < 1 or a.shape[2] < 1:
        raise ValueError(f"{name}: frame size must be at least 1x1 with >= 1 channel, got shape {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32)


def _frame_args(current, previous, reduced, frame, camera, prev_camera, layer, neighbourhood, history):
    cur = _image(current, "current")
    squeeze = np.asarray(current).ndim == 2
    prev = _image(previous, "previous")
    red = _image(reduced, "reduced")
    h, w, c = cur.shape
    if prev.shape != cur.shape:
        raise ValueError(f"previous must have the shape of current {cur.shape}, got {prev.shape}")
    rw, rh = (w - 1) // REPROJ_BLOCK + 1, (h - 1) // REPROJ_BLOCK + 1
    if red.shape != (rh, rw, c):
        raise ValueError(f"reduced must have shape (ceil(H/4), ceil(W/4), channels) = {(rh, rw, c)}, got {red.shape}")
    if isinstance(frame, bool) or not isinstance(frame, (int, np.integer)):
        raise TypeError(f"frame must be an integer, got {frame!r}")
    if not -(2**31) <= int(frame) < 2**31:
        raise ValueError(f"frame must fit in int32, got {frame}")
    _check_camera(camera, "camera")
    _check_camera(prev_camera, "prev_camera")
    if not isinstance(layer, CloudLayer):
        raise TypeError(f"layer must be a CloudLayer, got {type(layer).__name__}")
    if isinstance(neighbourhood, bool) or not isinstance(neighbourhood, (int, np.integer)):
        raise TypeError(f"neighbourhood must be an odd integer >= 1, got {neighbourhood!r}")
    if neighbourhood < 1 or neighbourhood % 2 == 0 or neighbourhood > MAX_NEIGHBOURHOOD:
        raise ValueError(f"neighbourhood must be an odd integer in [1, {MAX_NEIGHBOURHOOD}], got {neighbourhood}")
    if not isinstance(history, (bool, np.bool_)):
        raise TypeError(f"history must be True or False, got {history!r}")
    for cam, name in ((camera, "camera"), (prev_camera, "prev_camera")):
        for m in ("inv_view_proj_rot", "view_proj"):
            if not np.all(np.isfinite(getattr(cam, m))):
                raise ValueError(f"{name}.{m} must be finite")
    return cur, prev, red, int(frame), int(neighbourhood), int(bool(history)), squeeze


def _make_frame_evaluator(default_neighbourhood: int, impl: str, device=None):
    def reproject_frame(current, previous, reduced, frame, camera, prev_camera, layer=None,
                        neighbourhood=default_neighbourhood, history=True):
        """vc-A26 / vc-A27: the reprojection pass over a frame.

        current (H, W[, C]): this frame's buffer (pixels rendered this frame are kept); previous: the previous frame's
        final buffer; reduced (ceil(H/4), ceil(W/4)[, C]): this frame's reduced buffer; frame: frame number; camera /
        prev_camera: Camera of this and the previous frame; layer: CloudLayer (default CloudLayer()); neighbourhood:
        odd n, the n x n average of vc-A27 (1 = exact sampling); history: False -> reduced-buffer fallback only.
        Returns the new frame, float32, the shape of current.
        """
        lay = CloudLayer() if layer is None else layer
        cur, prev, red, f, n, hist, squeeze = _frame_args(current, previous, reduced, frame, camera, prev_camera, lay,
                                                          neighbourhood, history)
        h, w, c = cur.shape
        if impl == "warp":
            from ..core.runtime import launcher

            tl = launcher(device)
            dev = tl.device
            out = wp.empty((h, w, c), dtype=float, device=dev)
            tl.launch(reproject_frame_kernel, h, w,
                      inputs=[wp.array(cur, dtype=float, device=dev), wp.array(prev, dtype=float, device=dev),
                              wp.array(red, dtype=float, device=dev), f, camera.mat44("inv_view_proj_rot"),
                              camera.eye_vec3(), prev_camera.mat44("view_proj"), lay.centre_vec3(),
                              lay.r_inner, n, hist],
                      outputs=[out])
            res = out.numpy()
        else:
            from ..core.binding import ffi, lib, status_error

            F = ffi()
            res = np.empty_like(cur)
            st = lib().ccl_reproj_frame(
                F.from_buffer("float[]", cur), F.from_buffer("float[]", prev), F.from_buffer("float[]", red), w, h, c,
                f, F.new("float[16]", camera.column_major("inv_view_proj_rot").tolist()), tuple(camera.eye.tolist()),
                F.new("float[16]", prev_camera.column_major("view_proj").tolist()), lay.centre, lay.r_inner, n, hist,
                F.from_buffer("float[]", res))
            status_error(st, "ccl_reproj_frame")
        return res[:, :, 0] if squeeze else res

    return reproject_frame


# Not element-wise: whole images in and out (each pixel reads a neighbourhood of the previous frame and the reduced
# buffer), and the cameras are struct arguments. vc-A27 is the same pass with neighbourhood > 1 (3 in the thesis's
# figure 4.14b, AVERAGE_NEIGHBOURHOOD).
declare("vc-A26", "vc-A27", c="ccl_reproj_frame", name="reproj_frame",
        make_warp=lambda eq, device: _make_frame_evaluator(1, "warp", device),
        make_c=lambda eq: _make_frame_evaluator(1, "c"),
        summary="reproj_frame(current, previous, reduced, frame, camera, prev_camera, layer=CloudLayer(), "
                "neighbourhood=1, history=True): pixels not rendered this frame are reprojected through the "
                "inner-sphere hit point into the previous frame (bilinear) when visible there, else interpolated from "
                "the reduced buffer. vc-A27 (neighbourhood averaging): neighbourhood = n > 1 (odd) takes the mean of "
                "an n x n box of bilinear samples one pixel apart (AVERAGE_NEIGHBOURHOOD = 3, fig 4.14b), trading "
                "detail for fewer reprojection artifacts.",
        references=("Schneider & Vos, The real-time volumetric cloudscapes of Horizon Zero Dawn, SIGGRAPH 2015",
                    "Barvir, Volumetric clouds, FIT BUT 2020, §4.4, fig. 4.14"))(reproject_pixel)


__all__ = ["Camera", "CloudLayer", "reproj_grid", "REPROJ_BLOCK", "REPROJ_CYCLE", "SNAP_PX",
           "AVERAGE_NEIGHBOURHOOD"]
