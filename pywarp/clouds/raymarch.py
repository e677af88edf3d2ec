"""The host side of the raymarch topic (cclouds/raymarch.h): the uniform march through a bounding volume (vc-A35) on
NumPy rays -- through a sphere (the evaluators the registry names for vc-A35) or an axis-aligned box (:func:`march_box`)
by the Warp kernel or the C functions -- and the evaluators of the vc-A36 constants table
(:class:`pywarp.kernels.raymarch.VcConstants` from the Warp struct or the C struct). The equations, the table and the
kernels are :mod:`pywarp.kernels.raymarch`.
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..kernels.camera import _finite_float, _vec3_value
from ..kernels.raymarch import (VC_CONSTANTS, VcConstants, VcConstantTable, _f32, march_volume_kernel,
                               vc_constants_kernel)


def _march_args(origin, direction, n, offset, name):
    o = np.asarray(origin, dtype=np.float64) if not isinstance(origin, str) else None
    d = np.asarray(direction, dtype=np.float64) if not isinstance(direction, str) else None
    for arr, nm in ((o, "origin"), (d, "direction")):
        if arr is None or arr.ndim == 0 or arr.shape[-1] != 3:
            raise ValueError(f"{nm} must be an array of 3-vectors (..., 3)")
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{nm} must be finite (no NaN or Inf)")
    try:
        shape = np.broadcast_shapes(o.shape[:-1], d.shape[:-1])
    except ValueError:
        raise ValueError(f"{name}(): origin{o.shape} and direction{d.shape} do not broadcast") from None
    if np.any(np.sum(d * d, axis=-1) == 0.0):
        raise ValueError("direction must be non-zero")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        raise TypeError(f"n must be an integer, got {n!r}")
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    off = _finite_float(offset, "offset")
    if not 0.0 <= off < 1.0:
        raise ValueError(f"offset must be in [0, 1), got {offset}")
    f32 = lambda v: np.ascontiguousarray(v, dtype=np.float32)  # noqa: E731
    return (f32(np.broadcast_to(o, (*shape, 3)).reshape(-1, 3)), f32(np.broadcast_to(d, (*shape, 3)).reshape(-1, 3)),
            shape, int(n), float(np.float32(off)))


def _sphere_args(centre, radius):
    a = _vec3_value(centre, "centre")
    r = _finite_float(radius, "radius")
    if r <= 0:
        raise ValueError(f"radius must be > 0, got {radius}")
    return np.float32(a), np.zeros(3, np.float32), float(np.float32(r))


def _box_args(box_min, box_max):
    a = _vec3_value(box_min, "box_min")
    b = _vec3_value(box_max, "box_max")
    if np.any(a > b):
        raise ValueError(f"box_min must be <= box_max component-wise, got {a.tolist()} and {b.tolist()}")
    return np.float32(a), np.float32(b), 0.0


def _march(kind, impl, device, o, d, shape, n, a, b, r, off):
    """n uniform steps of every ray through a sphere (kind 0: centre a, radius r) or a box (kind 1: a, b)."""
    if impl == "warp":
        from ..core.runtime import resolve_device

        dev = resolve_device(device)
        pts = wp.empty((o.shape[0], n), dtype=wp.vec3, device=dev)
        dts = wp.empty(o.shape[0], dtype=float, device=dev)
        if o.shape[0]:
            wp.launch(march_volume_kernel, dim=o.shape[0],
                      inputs=[wp.array(o, dtype=wp.vec3, device=dev), wp.array(d, dtype=wp.vec3, device=dev), kind,
                              wp.vec3(*a.tolist()), wp.vec3(*b.tolist()), r, n, off], outputs=[pts, dts], device=dev)
        return pts.numpy().reshape(*shape, n, 3), dts.numpy().reshape(shape)
    from ..core.binding import ffi, lib

    F, L = ffi(), lib()
    pts_c = F.new("ccl_vec3[]", n)
    dt_c = F.new("float *")
    pts = np.empty((o.shape[0], n, 3), np.float32)
    dts = np.empty(o.shape[0], np.float32)
    for k in range(o.shape[0]):
        ok, dk = tuple(o[k].tolist()), tuple(d[k].tolist())
        if kind == 0:
            L.ccl_raymarch_sphere(ok, dk, tuple(a.tolist()), r, n, off, pts_c, dt_c)
        else:
            L.ccl_raymarch_box(ok, dk, tuple(a.tolist()), tuple(b.tolist()), n, off, pts_c, dt_c)
        pts[k] = np.frombuffer(F.buffer(pts_c), dtype=np.float32).reshape(n, 3)
        dts[k] = dt_c[0]
    return pts.reshape(*shape, n, 3), dts.reshape(shape)


def _sphere_evaluator(impl, device=None):
    def raymarch_sphere(origin, direction, centre, radius, n, offset=0.5):
        """Sample positions (..., n, 3) and step lengths (...) of n uniform steps through the sphere (centre,
        radius) in front of the origin (direction of any non-zero length); NaN where the ray misses (vc-A35)."""
        o, d, shape, n, off = _march_args(origin, direction, n, offset, "raymarch_sphere")
        a, b, r = _sphere_args(centre, radius)
        return _march(0, impl, device, o, d, shape, n, a, b, r, off)

    return raymarch_sphere


def march_box(origin, direction, box_min, box_max, n, offset=0.5, *, impl: str = "warp", device=None):
    """vc-A35 with an axis-aligned box (``ccl_raymarch_box``): sample positions (..., n, 3) and step lengths (...) of n
    uniform steps through the box in front of the origin (direction of any non-zero length); NaN where the ray
    misses. ``impl="c"`` evaluates the C function. The registered vc-A35 entry is the sphere, ``raymarch_sphere``
    (a box is not a catalogue entry of its own)."""
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    o, d, shape, n, off = _march_args(origin, direction, n, offset, "march_box")
    a, b, r = _box_args(box_min, box_max)
    return _march(1, impl, device, o, d, shape, n, a, b, r, off)


def sphere_warp(eq, device=None):
    """The evaluator of vc-A35 (n sample points per ray, not element-wise) on Warp."""
    return _sphere_evaluator("warp", device)


def sphere_c(eq):
    """The C evaluator of vc-A35 (``ccl_raymarch_sphere``)."""
    return _sphere_evaluator("c")


def _to_constants(get) -> VcConstants:
    """Build VcConstants from ``get(name)`` returning a number or a sequence; floats rounded through float32."""
    out = {}
    for name, v in VC_CONSTANTS.items():
        x = get(name)
        out[name] = tuple(_f32(c) for c in x) if isinstance(v, tuple) else int(x) if isinstance(v, int) else _f32(x)
    return VcConstants(**out)


def constants_warp(eq, device=None):
    """The evaluator of vc-A36 (a table, not an array) on Warp: the constants as a kernel reads them."""
    from ..core.runtime import resolve_device

    dev = resolve_device(device)

    def call():
        arr = wp.empty(1, dtype=VcConstantTable, device=dev)
        wp.launch(vc_constants_kernel, dim=1, inputs=[arr], device=dev)
        rec = arr.numpy()[0]
        return _to_constants(lambda name: rec[name])

    return call


def constants_c(eq):
    """The C evaluator of vc-A36 (``ccl_raymarch_vc_constants``)."""
    from ..core.binding import lib

    def call():
        p = lib().ccl_raymarch_vc_constants()
        return _to_constants(lambda name: getattr(p, name))

    return call
