"""The host side of the rr drop model (cclouds/rain.h): the Beard-Chuang drop's volume, axis ratio, extent and surface
on NumPy arrays (:func:`drop_volume`, :func:`drop_axis_ratio`, :func:`drop_extent`, :func:`drop_surface`), the
refraction mask of rr-alg-3.1.1 with its in-memory cache (:func:`drop_mask`), and the evaluators the registry names
for rr-alg-3.1 (one drop billboard). The equations and kernels are :mod:`pywarp.kernels.rain`.
"""
from __future__ import annotations

import math
import threading

import numpy as np
import warp as wp

from ..core.registry import Arg
from ..kernels.rain import (_A, _PI_F32, CAPTURE_FOV_DEG, FILTER, INTERP, MAPPING, MASK_SIZE, METHOD, _check_a,
                            mask_kernel, scalar_shape_kernel, shade_drop_kernel, surface_kernel)


def _shade_args(capture, mask, centre_dir, angular_radius, fov_y_deg, aspect, mapping, filter, out_size):
    cap = np.asarray(capture)
    if cap.ndim != 3 or cap.shape[2] != 3 or cap.shape[0] < 1 or cap.shape[1] < 1:
        raise ValueError(f"capture must be an (height, width, 3) RGB array, got shape {cap.shape}")
    cap = Arg("capture").check(cap)
    m = np.asarray(mask)
    if m.ndim != 3 or m.shape[2] != 4 or m.shape[0] != m.shape[1] or m.shape[0] < 1:
        raise ValueError(f"mask must be a (size, size, 4) array from drop_mask(), got shape {m.shape}")
    m = Arg("mask").check(m)
    c = Arg("centre_dir", unit=True, length=3).check(centre_dir)
    if c.shape != (3,) or not c[2] < 0.0:
        raise ValueError(f"centre_dir must be one unit 3-vector looking into the scene (z < 0), got {c.tolist()}")
    ar = float(Arg("angular_radius", lo=0.0, hi=0.5, lo_open=True).check(angular_radius))
    fov = float(Arg("fov_y_deg", lo=0.0, hi=179.0, lo_open=True).check(fov_y_deg))
    asp = float(Arg("aspect", lo=0.0, hi=100.0, lo_open=True).check(aspect))
    n = int(Arg("out_size", lo=1, hi=4096, dtype="int32").check(out_size))
    return (np.ascontiguousarray(cap, np.float32), np.ascontiguousarray(m, np.float32), c.astype(np.float32), ar,
            math.tan(math.radians(fov) / 2.0), asp, MAPPING.check(mapping), FILTER.check(filter), n)


_SHADE_DOC = """rain_shade_drop(capture, mask, centre_dir, angular_radius=0.01, fov_y_deg=150, aspect=1, mapping='offset',
filter='nearest', out_size=64) -> (out_size, out_size, 4) RGBA of one drop billboard (rr-alg-3.1): per pixel the
mask texel (nearest), outside alpha 0; inside the capture colour at P_c (rr-alg-3.1.3), alpha 1."""


def shade_drop_warp(eq, device):
    from ..core.runtime import launcher

    def rain_shade_drop(capture, mask, centre_dir, angular_radius=0.01, fov_y_deg=CAPTURE_FOV_DEG, aspect=1.0,
                        mapping="offset", filter="nearest", out_size=64):
        cap, m, c, ar, tan_h, asp, mp, fl, n = _shade_args(capture, mask, centre_dir, angular_radius, fov_y_deg,
                                                           aspect, mapping, filter, out_size)
        tl = launcher(device)
        out = wp.empty((n, n), dtype=wp.vec4, device=tl.device)
        tl.launch(shade_drop_kernel, n, n,
                  [wp.array(cap, dtype=wp.vec3, device=tl.device), wp.array(m, dtype=wp.vec4, device=tl.device),
                   wp.vec3(*c.tolist()), float(np.float32(math.tan(ar))), float(np.float32(tan_h)), asp, mp, fl],
                  [out])
        return out.numpy()

    rain_shade_drop.__doc__ = _SHADE_DOC
    return rain_shade_drop


def shade_drop_c(eq):
    from ..core.binding import ffi, lib, status_error

    def rain_shade_drop(capture, mask, centre_dir, angular_radius=0.01, fov_y_deg=CAPTURE_FOV_DEG, aspect=1.0,
                        mapping="offset", filter="nearest", out_size=64):
        cap, m, c, ar, tan_h, asp, mp, fl, n = _shade_args(capture, mask, centre_dir, angular_radius, fov_y_deg,
                                                           aspect, mapping, filter, out_size)
        f = ffi()
        out = np.empty((n, n, 4), np.float32)
        cv = f.new("ccl_vec3 *", [float(x) for x in c])[0]
        st = lib().ccl_rain_shade_drop(f.from_buffer("float[]", cap), cap.shape[1], cap.shape[0],
                                       f.from_buffer("float[]", m), m.shape[0], cv, ar, float(np.float32(tan_h)), asp,
                                       mp, fl, n, f.from_buffer("float[]", out))
        status_error(st, "ccl_rain_shade_drop")
        return out

    rain_shade_drop.__doc__ = _SHADE_DOC
    return rain_shade_drop


def _impl(impl):
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return impl


def _shape_inputs(a, interp):
    k = INTERP.check(interp)
    arr = _A.check(a)
    _check_a(arr, interp)
    return np.ascontiguousarray(arr, np.float32), k


def _scalar_shape(which, cname, a, interp, impl, device):
    arr, k = _shape_inputs(a, interp)
    flat = arr.ravel()
    if _impl(impl) == "c":
        from ..core.binding import lib

        fn = getattr(lib(), cname)
        out = np.array([fn(float(x), k) for x in flat], np.float32)
    else:
        from ..core.runtime import resolve_device

        dev = resolve_device(device)
        o = wp.empty(flat.size, dtype=float, device=dev)
        if flat.size:
            wp.launch(scalar_shape_kernel, dim=flat.size, inputs=[which, wp.array(flat, dtype=float, device=dev), k],
                      outputs=[o], device=dev)
        out = o.numpy()
    out = out.reshape(arr.shape)
    return out[()] if out.ndim == 0 else out


def drop_volume(a, interp="table", impl="warp", device=None):
    """Volume [mm^3] of the Beard-Chuang drop of radius ``a`` (C: ccl_rain_drop_volume); close to 4/3 pi a^3."""
    return _scalar_shape(0, "ccl_rain_drop_volume", a, interp, impl, device)


def drop_axis_ratio(a, interp="table", impl="warp", device=None):
    """Axis ratio height / width of the drop of radius ``a`` (C: ccl_rain_drop_axis_ratio); 1 = sphere."""
    return _scalar_shape(1, "ccl_rain_drop_axis_ratio", a, interp, impl, device)


def drop_extent(a, interp="table", impl="warp", device=None):
    """Half-size L [mm] of the drop's mask and billboard (C: ccl_rain_drop_extent): a bound of max r(theta)."""
    return _scalar_shape(2, "ccl_rain_drop_extent", a, interp, impl, device)


def drop_surface(theta, phi, a, interp="table", impl="warp", device=None):
    """Points [mm] and outward unit normals (..., 3) of the axisymmetric Beard-Chuang drop at (theta, phi)
    (rr-eq1 revolved about the vertical; C: ccl_rain_drop_surface)."""
    th = Arg("theta", lo=0.0, hi=_PI_F32).check(theta)
    ph = Arg("phi").check(phi)
    arr, k = _shape_inputs(a, interp)
    shape = np.broadcast_shapes(th.shape, ph.shape, arr.shape)
    th, ph, aa = (np.ascontiguousarray(np.broadcast_to(x, shape).ravel(), np.float32) for x in (th, ph, arr))
    if _impl(impl) == "c":
        from ..core.binding import ffi, lib

        nptr = ffi().new("ccl_vec3 *")
        P = np.empty((th.size, 3), np.float32)
        N = np.empty((th.size, 3), np.float32)
        for i in range(th.size):
            p = lib().ccl_rain_drop_surface(float(th[i]), float(ph[i]), float(aa[i]), k, nptr)
            P[i] = (p.x, p.y, p.z)
            N[i] = (nptr.x, nptr.y, nptr.z)
    else:
        from ..core.runtime import resolve_device

        dev = resolve_device(device)
        op = wp.empty(th.size, dtype=wp.vec3, device=dev)
        on = wp.empty(th.size, dtype=wp.vec3, device=dev)
        if th.size:
            wp.launch(surface_kernel, dim=th.size, inputs=[wp.array(th, dtype=float, device=dev),
                                                          wp.array(ph, dtype=float, device=dev),
                                                          wp.array(aa, dtype=float, device=dev), k],
                      outputs=[op, on], device=dev)
        P, N = op.numpy(), on.numpy()
    return P.reshape(shape + (3,)), N.reshape(shape + (3,))


_MASK_CACHE: dict = {}


_MASK_LOCK = threading.Lock()


_MASK_CACHE_MAX = 16


def drop_mask(size=MASK_SIZE, a=1.0, method="sphere", interp="table", deform=1.0, n_water=1.33, normals=False,
              impl="warp", device=None):
    """The size x size refraction mask of rr-alg-3.1.1: float32 (size, size, 4) = (exit x, y, z, inside) per texel
    (row 0 at the top, mask frame of :mod:`pywarp.kernels.rain`); with ``normals=True`` also the (size, size, 3)
    entry normals. ``method``: 'sphere' (the text), 'outline' (the application's flattened outline with sphere
    refraction), 'exact' (traced through the Beard-Chuang drop). Cached in memory per arguments (the last 16); the
    returned arrays are read-only. ``impl='c'`` computes it with ccl_rain_mask."""
    size = int(Arg("size", lo=1, hi=4096, dtype="int32").check(size))
    m = METHOD.check(method)
    k = INTERP.check(interp)
    a_f = float(_A.check(a))
    if m != 0:
        _check_a(np.float32(a_f), interp)
    d_f = float(Arg("deform", lo=0.0, hi=1.0).check(deform))
    n_f = float(Arg("n_water", lo=1.0, hi=2.0).check(n_water))
    _impl(impl)
    key = (size, float(np.float32(a_f)), m, k, float(np.float32(d_f)), float(np.float32(n_f)), impl,
           device if impl == "warp" else None)
    with _MASK_LOCK:
        hit = _MASK_CACHE.get(key)
    if hit is None:
        if impl == "c":
            from ..core.binding import ffi, lib, status_error

            f = ffi()
            rgba = np.empty((size, size, 4), np.float32)
            nrm = np.empty((size, size, 3), np.float32)
            st = lib().ccl_rain_mask(size, a_f, d_f, n_f, k, m, f.from_buffer("float[]", rgba),
                                     f.from_buffer("float[]", nrm))
            status_error(st, "ccl_rain_mask")
        else:
            from ..core.runtime import launcher

            tl = launcher(device)
            o = wp.empty((size, size), dtype=wp.vec4, device=tl.device)
            on = wp.empty((size, size), dtype=wp.vec3, device=tl.device)
            tl.launch(mask_kernel, size, size, [a_f, d_f, n_f, k, m], [o, on])
            rgba, nrm = o.numpy(), on.numpy()
        rgba.setflags(write=False)
        nrm.setflags(write=False)
        hit = (rgba, nrm)
        with _MASK_LOCK:
            if len(_MASK_CACHE) >= _MASK_CACHE_MAX:
                _MASK_CACHE.pop(next(iter(_MASK_CACHE)))
            _MASK_CACHE[key] = hit
    return hit if normals else hit[0]
