"""The host side of the temporal reprojection (vc §4.2.1, §4.4; cclouds/reproj.h): the checked whole-frame passes on
NumPy images -- the thesis's pass (the evaluators the registry names for vc-A26/vc-A27) and the depth-aware pass
(:func:`reproj_frame_depth`) -- on Warp through a TileLauncher or in C, and the per-pixel depth lookups for tests and
figures (:func:`reproj_uv_depth_at`, :func:`surface_depth`). The equations and kernels are
:mod:`pywarp.kernels.reproj`.
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..kernels.camera import _check_camera
from ..kernels.raymarch import CloudLayer
from ..kernels.reproj import (DEPTH_ITERATIONS, FILTERS, MAX_DEPTH_ITERATIONS, MAX_NEIGHBOURHOOD, REPROJ_BLOCK,
                              reproject_frame_depth_kernel, reproject_frame_kernel, surface_depth_kernel,
                              uv_depth_kernel)


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



def _frame_evaluator(impl: str, device=None):
    def reproject_frame(current, previous, reduced, frame, camera, prev_camera, layer=None,
                        neighbourhood=1, history=True):
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


def frame_warp(eq, device=None):
    """The evaluator of vc-A26/vc-A27 (whole images in and out, not element-wise) on Warp."""
    return _frame_evaluator("warp", device)


def frame_c(eq):
    """The C evaluator of vc-A26/vc-A27 (``ccl_reproj_frame``)."""
    return _frame_evaluator("c")



def _depth(value, name: str, shape: tuple) -> np.ndarray:
    if isinstance(value, (str, bytes)) or value is None:
        raise TypeError(f"{name} must be a float array (height, width), got {value!r}")
    a = np.asarray(value)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must be numeric, got dtype {a.dtype}")
    if a.shape != shape:
        raise ValueError(f"{name} must have shape (height, width) = {shape}, got {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32)



def _iterations(value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"iterations must be an integer in [0, {MAX_DEPTH_ITERATIONS}], got {value!r}")
    if not 0 <= value <= MAX_DEPTH_ITERATIONS:
        raise ValueError(f"iterations must be in [0, {MAX_DEPTH_ITERATIONS}], got {value}")
    return int(value)



def reproj_frame_depth(current, depth, previous, previous_depth, reduced, frame, camera, prev_camera, layer=None,
                       neighbourhood: int = 1, filter: str = "catmull_rom", iterations: int = DEPTH_ITERATIONS,
                       history: bool = True, impl: str = "warp", device=None):
    """The depth-aware reprojection pass (twin of ``ccl_reproj_frame_depth``): pixels not rendered this frame come from
    the previous frame at the position found through the depth of what they show
    (:func:`pywarp.kernels.reproj.reproj_uv_depth`), else from the reduced buffer, as :func:`pywarp.reproj_frame`
    (vc-A26/A27) otherwise.

    current (H, W[, C]), previous, reduced, frame, camera, prev_camera, layer, neighbourhood, history: as
    ``reproj_frame``; depth (H, W): this frame's depths (km from camera.eye;
    :func:`pywarp.kernels.reproj.reproj_surface_depth`) of the pixels rendered this frame; previous_depth (H, W): the
    previous frame's final depths (km from prev_camera.eye; a value not > 0 is unknown); filter: the sampler of the
    previous frame, "catmull_rom" or "bilinear" (the thesis's, :data:`pywarp.kernels.reproj.FILTERS`); iterations:
    fixed-point refinements in [0, MAX_DEPTH_ITERATIONS] (0 with "bilinear": the thesis's inner-sphere point, the
    colours of ``reproj_frame`` bit for bit); impl: "warp" or "c". Returns (frame, depth): float32, the shapes of
    current and depth (the depth of every pixel, km from camera.eye). Everything is checked before any kernel runs.
    """
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    lay = CloudLayer() if layer is None else layer
    cur, prev, red, f, n, hist, squeeze = _frame_args(current, previous, reduced, frame, camera, prev_camera, lay,
                                                      neighbourhood, history)
    h, w, c = cur.shape
    dep = _depth(depth, "depth", (h, w))
    pdep = _depth(previous_depth, "previous_depth", (h, w))
    its = _iterations(iterations)
    if not isinstance(filter, str) or filter not in FILTERS:
        raise ValueError(f"filter must be one of {', '.join(map(repr, FILTERS))}, got {filter!r}")
    flt = FILTERS[filter]
    for cam, name in ((camera, "camera"), (prev_camera, "prev_camera")):
        if not np.all(np.isfinite(cam.eye)):
            raise ValueError(f"{name}.eye must be finite")
    if impl == "warp":
        from ..core.runtime import launcher

        tl = launcher(device)
        dev = tl.device
        out = wp.empty((h, w, c), dtype=float, device=dev)
        out_d = wp.empty((h, w), dtype=float, device=dev)
        tl.launch(reproject_frame_depth_kernel, h, w,
                  inputs=[wp.array(cur, dtype=float, device=dev), wp.array(dep, dtype=float, device=dev),
                          wp.array(prev, dtype=float, device=dev), wp.array(pdep, dtype=float, device=dev),
                          wp.array(red, dtype=float, device=dev), f, camera.mat44("inv_view_proj_rot"),
                          camera.eye_vec3(), prev_camera.mat44("view_proj"), prev_camera.eye_vec3(),
                          lay.centre_vec3(), lay.r_inner, n, flt, its, hist],
                  outputs=[out, out_d])
        res, res_d = out.numpy(), out_d.numpy()
    else:
        from ..core.binding import ffi, lib, status_error

        F = ffi()
        res = np.empty_like(cur)
        res_d = np.empty_like(dep)
        st = lib().ccl_reproj_frame_depth(
            F.from_buffer("float[]", cur), F.from_buffer("float[]", dep), F.from_buffer("float[]", prev),
            F.from_buffer("float[]", pdep), F.from_buffer("float[]", red), w, h, c, f,
            F.new("float[16]", camera.column_major("inv_view_proj_rot").tolist()), tuple(camera.eye.tolist()),
            F.new("float[16]", prev_camera.column_major("view_proj").tolist()), tuple(prev_camera.eye.tolist()),
            lay.centre, lay.r_inner, n, flt, its, hist, F.from_buffer("float[]", res), F.from_buffer("float[]", res_d))
        status_error(st, "ccl_reproj_frame_depth")
    return (res[:, :, 0] if squeeze else res), res_d



def reproj_uv_depth_at(x, y, camera, prev_camera, previous_depth, layer=None, iterations: int = DEPTH_ITERATIONS,
                       impl: str = "warp"):
    """:func:`pywarp.kernels.reproj.reproj_uv_depth` (``ccl_reproj_uv_depth``) at pixels (x, y) of a frame the size of
    ``previous_depth`` (H, W): (visible int32, u, v, t float32), arrays of the shape of x and y (for tests and
    figures)."""
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    lay = CloudLayer() if layer is None else layer
    _check_camera(camera, "camera")
    _check_camera(prev_camera, "prev_camera")
    pd = np.asarray(previous_depth)
    if pd.ndim != 2 or pd.shape[0] < 1 or pd.shape[1] < 1:
        raise ValueError(f"previous_depth must have shape (height, width), got {pd.shape}")
    h, w = pd.shape
    pdep = _depth(pd, "previous_depth", (h, w))
    its = _iterations(iterations)
    xs, ys = np.broadcast_arrays(np.asarray(x), np.asarray(y))
    shape = xs.shape
    xs, ys = xs.astype(np.int32).ravel(), ys.astype(np.int32).ravel()
    if np.any((xs < 0) | (xs >= w) | (ys < 0) | (ys >= h)):
        raise ValueError(f"x, y must be pixels of the {w}x{h} frame of previous_depth")
    if impl == "warp":
        n = xs.size
        outs = [wp.empty(n, dtype=wp.int32), wp.empty(n, dtype=float), wp.empty(n, dtype=float),
                wp.empty(n, dtype=float)]
        if n:
            wp.launch(uv_depth_kernel, dim=n,
                      inputs=[wp.array(xs, dtype=wp.int32), wp.array(ys, dtype=wp.int32), w, h,
                              camera.mat44("inv_view_proj_rot"), camera.eye_vec3(), prev_camera.mat44("view_proj"),
                              prev_camera.eye_vec3(), wp.array(pdep, dtype=float), lay.centre_vec3(), lay.r_inner,
                              its], outputs=outs)
        res = [o.numpy() for o in outs]
    else:
        from ..core.binding import ffi, lib

        F = ffi()
        ivp = F.new("float[16]", camera.column_major("inv_view_proj_rot").tolist())
        pvp = F.new("float[16]", prev_camera.column_major("view_proj").tolist())
        pbuf = F.from_buffer("float[]", pdep)
        pu, pv, pt = F.new("float[1]"), F.new("float[1]"), F.new("float[1]")
        res = [np.empty(xs.size, np.int32)] + [np.empty(xs.size, np.float32) for _ in range(3)]
        fn = lib().ccl_reproj_uv_depth
        eye, peye = tuple(camera.eye.tolist()), tuple(prev_camera.eye.tolist())
        for k in range(xs.size):
            res[0][k] = fn(ivp, eye, pvp, peye, pbuf, lay.centre, lay.r_inner, its, int(xs[k]), int(ys[k]), w, h,
                           pu, pv, pt)
            res[1][k], res[2][k], res[3][k] = pu[0], pv[0], pt[0]
    return tuple(r.reshape(shape) for r in res)



def surface_depth(march_depth, eye, d, layer=None, impl: str = "warp") -> np.ndarray:
    """:func:`pywarp.kernels.reproj.reproj_surface_depth` (``ccl_reproj_surface_depth``) element-wise: march depths
    (...,) and unit rays d (..., 3) from one eye (3,); float32 (...,)."""
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    lay = CloudLayer() if layer is None else layer
    md = np.asarray(march_depth, np.float32)
    dd = np.asarray(d, np.float32)
    if dd.shape[-1:] != (3,):
        raise ValueError(f"d must have shape (..., 3), got {dd.shape}")
    md, _ = np.broadcast_arrays(md, dd[..., 0])
    shape = md.shape
    md, dd = np.ascontiguousarray(md.ravel()), np.ascontiguousarray(dd.reshape(-1, 3))
    e = np.asarray(eye, np.float32).reshape(3)
    if impl == "warp":
        out = wp.empty(md.size, dtype=float)
        if md.size:
            wp.launch(surface_depth_kernel, dim=md.size,
                      inputs=[wp.array(md, dtype=float), wp.vec3(*e.tolist()), wp.array(dd, dtype=wp.vec3),
                              lay.centre_vec3(), lay.r_earth], outputs=[out])
        return out.numpy().reshape(shape)
    from ..core.binding import lib

    fn = lib().ccl_reproj_surface_depth
    ev = tuple(e.tolist())
    return np.array([fn(float(md[k]), ev, tuple(dd[k].tolist()), lay.centre, lay.r_earth)
                     for k in range(md.size)], np.float32).reshape(shape)
