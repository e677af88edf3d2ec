"""The host side of the terrain topic (cclouds/terrain.h): the NumPy-level heightmap and water-normal helpers
(:func:`height`, :func:`water_normal`) and the evaluators the registry names for the scene-level entries
``terrain_shade`` (pt-code-7.3) and ``terrain_pixel`` (pt-alg-7.1.6), by the Warp kernels or the C functions. The
equations and the kernels are :mod:`pywarp.kernels.terrain`.
"""
from __future__ import annotations

import math

import numpy as np
import warp as wp

from ..core.binding import ffi, lib
from ..core.cbridge import TERRAIN_PARAMS
from ..core.registry import Arg
from ..core.runtime import resolve_device
from ..kernels import terrain as K
from ..kernels.camera import _camera_ray_args
from ..kernels.noise import _check_seed, perm_array, perm_table


def height(x, z, octaves: int = 4, height_scale: float = 12.0, horizontal_scale: float = 24.0, seed: int = 0,
           heightmap: str = "fbm", device: str | None = None) -> np.ndarray:
    """Terrain heights h(x, z) on NumPy arrays (the map of Kod 7.4 / Kod 7.9 heightmap); see terrain_height_perm."""
    if heightmap not in K.HEIGHTMAPS:
        raise ValueError(f"heightmap must be one of {', '.join(map(repr, K.HEIGHTMAPS))}, got {heightmap!r}")
    xa = Arg("x").check(x)
    za = Arg("z").check(z)
    o = K._OCTAVES.check(octaves)
    hs = K._HEIGHT.check(height_scale)
    hz = K._HSCALE.check(horizontal_scale)
    seed = _check_seed(seed)
    shape = np.broadcast_shapes(xa.shape, za.shape)
    xf = np.ascontiguousarray(np.broadcast_to(xa, shape).ravel())
    zf = np.ascontiguousarray(np.broadcast_to(za, shape).ravel())
    dev = resolve_device(device)
    out = wp.empty(xf.size, dtype=float, device=dev)
    if xf.size:
        wp.launch(K._height_kernel, dim=xf.size,
                  inputs=[wp.array(xf, dtype=float, device=dev), wp.array(zf, dtype=float, device=dev), int(o),
                          float(hs), float(hz), perm_array(seed, dev), K.HEIGHTMAPS[heightmap]], outputs=[out],
                  device=dev)
    return out.numpy().reshape(shape)


def water_normal(x, z, time: float = 0.0, wave_scale: float = 2.0, wave_strength: float = 0.08, seed: int = 0,
                 impl: str = "warp", device: str | None = None) -> np.ndarray:
    """Wave normals (..., 3) of the water plane (part of pt-alg-7.3.4); ``impl="c"`` evaluates
    ``ccl_terrain_water_normal_perm``."""
    xa = Arg("x").check(x)
    za = Arg("z").check(z)
    for name, v, lo in (("time", time, 0.0), ("wave_scale", wave_scale, K.MIN_SCALE),
                        ("wave_strength", wave_strength, 0.0)):
        if not math.isfinite(float(v)) or float(v) < lo:
            raise ValueError(f"{name} must be finite and >= {lo:g}, got {v!r}")
    seed = _check_seed(seed)
    shape = np.broadcast_shapes(xa.shape, za.shape)
    xf = np.ascontiguousarray(np.broadcast_to(xa, shape).ravel())
    zf = np.ascontiguousarray(np.broadcast_to(za, shape).ravel())
    if impl == "c":
        f = ffi()
        perm = f.new("uint8_t[512]", perm_table(seed).astype(np.uint8).tolist())
        out = np.empty((xf.size, 3), np.float32)
        for k in range(xf.size):
            n = lib().ccl_terrain_water_normal_perm(float(xf[k]), float(zf[k]), float(time), float(wave_scale),
                                                    float(wave_strength), perm)
            out[k] = (n.x, n.y, n.z)
        return out.reshape(shape + (3,))

    dev = resolve_device(device)
    res = wp.empty(xf.size, dtype=wp.vec3, device=dev)
    if xf.size:
        wp.launch(K._water_normal_kernel, dim=xf.size,
                  inputs=[wp.array(xf, dtype=float, device=dev), wp.array(zf, dtype=float, device=dev),
                          float(time), float(wave_scale), float(wave_strength), perm_array(seed, dev)],
                  outputs=[res], device=dev)
    return res.numpy().reshape(shape + (3,))


def _rays(ro, rd):
    ro = Arg("ro", length=3).check(ro)
    rd = Arg("rd", length=3, unit=True).check(rd)
    try:
        shape = np.broadcast_shapes(ro.shape[:-1], rd.shape[:-1])
    except ValueError:
        raise ValueError(f"terrain_shade(): the shapes of ro{ro.shape} and rd{rd.shape} do not broadcast") from None
    return (np.ascontiguousarray(np.broadcast_to(ro, shape + (3,)).reshape(-1, 3)),
            np.ascontiguousarray(np.broadcast_to(rd, shape + (3,)).reshape(-1, 3)), shape)


def shade_warp(eq, device):
    dev = resolve_device(device)

    def terrain_shade(ro, rd, params: dict | None = None):
        """Colours (..., 3) (unclamped) and view-march steps (...) of rays (ro, rd) (pt-code-7.3)."""
        ros, rds, shape = _rays(ro, rd)
        c = TERRAIN_PARAMS.checked(dict(params or {}))
        p, seed = TERRAIN_PARAMS.warp_struct(c), int(c.seed)
        n = ros.shape[0]
        out = wp.empty(n, dtype=wp.vec3, device=dev)
        steps = wp.empty(n, dtype=wp.int32, device=dev)
        if n:
            wp.launch(K._shade_kernel, dim=n,
                      inputs=[p, perm_array(seed, dev), wp.array(ros, dtype=wp.vec3, device=dev),
                              wp.array(rds, dtype=wp.vec3, device=dev)],
                      outputs=[out, steps], device=dev)
        return out.numpy().reshape(shape + (3,)), steps.numpy().reshape(shape)

    return terrain_shade


def shade_c(eq):
    def terrain_shade(ro, rd, params: dict | None = None):
        """Colours (..., 3) and view-march steps of rays (ro, rd) by ccl_terrain_shade."""
        ros, rds, shape = _rays(ro, rd)
        c = TERRAIN_PARAMS.checked(dict(params or {}))
        f = ffi()
        st = f.new("int *")
        out = np.empty((ros.shape[0], 3), np.float32)
        steps = np.empty(ros.shape[0], np.int32)
        for k in range(ros.shape[0]):
            col = lib().ccl_terrain_shade(c, tuple(map(float, ros[k])), tuple(map(float, rds[k])), st)
            out[k] = (col.x, col.y, col.z)
            steps[k] = st[0]
        return out.reshape(shape + (3,)), steps.reshape(shape)

    return terrain_shade


def pixel_warp(eq, device):
    dev = resolve_device(device)

    def terrain_pixel(x, y, width, height, camera, params: dict | None = None):
        """Pixel colours (..., 3) in [0, 1] and summed view-march steps at pixels (x, y) (pt-alg-7.1.6)."""
        xs, ys, shape, width, height, camera = _camera_ray_args(x, y, width, height, camera)
        c = TERRAIN_PARAMS.checked(dict(params or {}))
        p, seed = TERRAIN_PARAMS.warp_struct(c), int(c.seed)
        out = wp.empty(xs.size, dtype=wp.vec3, device=dev)
        steps = wp.empty(xs.size, dtype=wp.int32, device=dev)
        if xs.size:
            wp.launch(K._pixels_kernel, dim=xs.size,
                      inputs=[p, perm_array(seed, dev), camera.mat44("inv_view_proj_rot"), camera.eye_vec3(),
                              wp.array(xs, dtype=wp.int32, device=dev), wp.array(ys, dtype=wp.int32, device=dev),
                              width, height], outputs=[out, steps], device=dev)
        return out.numpy().reshape(shape + (3,)), steps.numpy().reshape(shape)

    return terrain_pixel


def pixel_c(eq):
    def terrain_pixel(x, y, width, height, camera, params: dict | None = None):
        """Pixel colours (..., 3) and summed steps by the C reference ccl_terrain_pixel."""
        xs, ys, shape, width, height, camera = _camera_ray_args(x, y, width, height, camera)
        c = TERRAIN_PARAMS.checked(dict(params or {}))
        f = ffi()
        m = f.new("float[16]", camera.column_major("inv_view_proj_rot").tolist())
        eye = tuple(float(v) for v in camera.eye)
        rgb = f.new("float[3]")
        st = f.new("int *")
        out = np.empty((xs.size, 3), np.float32)
        steps = np.empty(xs.size, np.int32)
        for k in range(xs.size):
            lib().ccl_terrain_pixel(c, m, eye, int(xs[k]), int(ys[k]), width, height, rgb, st)
            out[k] = rgb[0], rgb[1], rgb[2]
            steps[k] = st[0]
        return out.reshape(shape + (3,)), steps.reshape(shape)

    return terrain_pixel
