"""The host side of the volume renderer (cclouds/volume.h) that draws the flight scene: cloud volumes placed in boxes
(:class:`PlacedVolume`), their brick occupancy and skip distances, the set of grids as the kernels read it
(:class:`VolumeSet`: flat arrays, light volumes) and as C reads it (:func:`c_grids`), and the frame and pixel passes
(:func:`render`, :func:`pixels_warp`, :func:`pixels_c`). The equations and kernels are :mod:`pywarp.kernels.volume`.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import warp as wp

from ..core.cbridge import VOLUME_PARAMS
from ..kernels.volume import (BRICK, LENGTH_RANGE, MAX_GRIDS, VolumeGrid, checked_params, light_kernel,
                              light_rows_kernel, pixels_kernel, render_kernel)


@dataclass
class PlacedVolume:
    """A uint8 volume (shape (nz, ny, nx), C order) placed in a box from ``origin`` with size ``extent`` [m]."""

    density: np.ndarray
    origin: tuple
    extent: tuple

    def __post_init__(self):
        a = np.asarray(self.density)
        if a.dtype != np.uint8 or a.ndim != 3 or min(a.shape) < 1:
            raise ValueError(f"density must be a non-empty uint8 array of shape (nz, ny, nx), got {a.dtype} "
                             f"{a.shape}")
        self.density = np.ascontiguousarray(a)
        for name in ("origin", "extent"):
            v = np.asarray(getattr(self, name), dtype=np.float64)
            if v.shape != (3,) or not np.all(np.isfinite(v)):
                raise ValueError(f"{name} must be 3 finite numbers, got {getattr(self, name)!r}")
            setattr(self, name, tuple(float(x) for x in v))
        if min(self.extent) < 1.0 / LENGTH_RANGE or max(self.extent) > LENGTH_RANGE:
            raise ValueError(f"extent must be in [{1.0 / LENGTH_RANGE:g}, {LENGTH_RANGE:g}] m on every axis, got "
                             f"{self.extent}")


def grown(density: np.ndarray) -> np.ndarray:
    """The voxels (bool, shape of ``density``) that are > 0 or have a 26-neighbour > 0: the corners of every
    trilinear cell holding some density -- the only voxels whose light a ray reads (it reads light where the sampled
    density is > 0)."""
    d = np.asarray(density) > 0
    for ax in range(3):  # grown by one voxel along each axis in turn (the box dilation is separable)
        g = d.copy()
        lo, hi = [slice(None)] * 3, [slice(None)] * 3
        lo[ax], hi[ax] = slice(1, None), slice(None, -1)
        g[tuple(lo)] |= d[tuple(hi)]
        g[tuple(hi)] |= d[tuple(lo)]
        d = g
    return d


def occupancy(density: np.ndarray) -> np.ndarray:
    """Brick occupancy of a uint8 volume (nz, ny, nx), as ``ccl_volume_occupancy``: brick b of BRICK^3 voxels is 1
    when any voxel of indices B b - 1 .. B b + B (B = BRICK, clamped) is > 0 -- every voxel a trilinear sample
    inside it can touch."""
    d = grown(density)
    # brick b holds voxels B b .. B b + B - 1 of the grown volume (padded with empty voxels to whole bricks)
    shape = tuple(-(-n // BRICK) for n in d.shape)
    pad = np.zeros(tuple(n * BRICK for n in shape), bool)
    pad[:d.shape[0], :d.shape[1], :d.shape[2]] = d
    bricks = pad.reshape(shape[0], BRICK, shape[1], BRICK, shape[2], BRICK)
    return bricks.any(axis=(1, 3, 5)).astype(np.uint8)


def skip_distance(density: np.ndarray) -> np.ndarray:
    """Skip distances of a uint8 volume (nz, ny, nx), as ``ccl_volume_skip``: 0 for an occupied brick
    (:func:`occupancy`), else min(255, the Chebyshev distance in bricks to the nearest occupied brick) (255 when none
    is occupied) -- every brick within distance m - 1 of a brick of distance m is empty, so a ray may jump to the exit
    of that cube. Repeated 26-neighbour dilation, as the C function."""
    occ = occupancy(density) > 0
    out = np.where(occ, 0, 255).astype(np.uint8)
    reached = occ.copy()
    for m in range(1, 255):
        if reached.all() or not reached.any():
            break
        grown = reached.copy()
        for ax in range(3):  # the cube dilation is separable: a 3-wide max along each axis in turn
            g = grown.copy()
            sl_a, sl_b = [slice(None)] * 3, [slice(None)] * 3
            sl_a[ax], sl_b[ax] = slice(1, None), slice(None, -1)
            g[tuple(sl_a)] |= grown[tuple(sl_b)]
            g[tuple(sl_b)] |= grown[tuple(sl_a)]
            grown = g
        out[grown & ~reached] = m
        reached = grown
    return out


@dataclass
class VolumeSet:
    """Grids and their light volumes as the kernels read them (flat arrays + :class:`pywarp.kernels.volume.VolumeGrid`
    records)."""

    volumes: list
    light: list = field(default_factory=list)  # float32 arrays of the volumes' shapes
    device: str = "cpu"
    #: largest skip distance the kernels see (1..255): 1 jumps one empty brick at a time, the renderer before the
    #: skip distances (kept so that a benchmark can measure the two in one run; the pixels are the same)
    skip_cap: int = 255
    _wp: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        if len(self.volumes) > MAX_GRIDS:
            raise ValueError(f"at most {MAX_GRIDS} volumes, got {len(self.volumes)}")
        if isinstance(self.skip_cap, bool) or not isinstance(self.skip_cap, int) or not 1 <= self.skip_cap <= 255:
            raise ValueError(f"skip_cap must be an integer in [1, 255], got {self.skip_cap!r}")

    def set_skip_cap(self, cap: int) -> None:
        """Change :attr:`skip_cap` (validated); the kernels' arrays are rebuilt on the next :meth:`warp`."""
        if isinstance(cap, bool) or not isinstance(cap, int) or not 1 <= cap <= 255:
            raise ValueError(f"skip_cap must be an integer in [1, 255], got {cap!r}")
        self.skip_cap = cap
        self._wp = {}

    def records(self) -> list:
        out, offset, boffset = [], 0, 0
        for v in self.volumes:
            nz, ny, nx = v.density.shape
            g = VolumeGrid()
            g.origin = wp.vec3(*v.origin)
            g.extent = wp.vec3(*v.extent)
            g.nx, g.ny, g.nz, g.offset, g.boffset = nx, ny, nz, offset, boffset
            out.append(g)
            offset += v.density.size
            boffset += -(-nz // BRICK) * -(-ny // BRICK) * -(-nx // BRICK)
        return out

    def compute_light(self, values: dict, launcher=None, needed_only: bool = False) -> None:
        """The light volume of every grid (Warp, one thread per voxel); ``values`` validated first. With
        ``launcher`` (a :class:`pywarp.core.runtime.TileLauncher`) the grid's rows are shared out among its workers
        (the same values). ``needed_only``: only the voxels a ray reads (:func:`grown`: about a third of a cloud's
        box) are marched, the others set to 1 (never read: the same pixels; ``ccl_volume_light`` computes all)."""
        p = VOLUME_PARAMS.warp_struct(checked_params(values))
        self.light = []
        for v, rec in zip(self.volumes, self.records()):
            rec.offset = 0
            d = wp.array(v.density.ravel(), dtype=wp.uint8, device=self.device)
            out = wp.empty(v.density.size, dtype=float, device=self.device)
            nz, ny, nx = v.density.shape
            need = np.ones(1, np.uint8) if not needed_only else grown(v.density).astype(np.uint8).ravel()
            need = wp.array(need, dtype=wp.uint8, device=self.device)
            if launcher is None and not needed_only:
                wp.launch(light_kernel, dim=v.density.size, inputs=[p, rec, d], outputs=[out], device=self.device)
            elif launcher is None:
                wp.launch(light_rows_kernel, dim=(nz * ny, nx), inputs=[0, p, rec, d, need, 1], outputs=[out],
                          device=self.device)
            else:  # rows (z, y) shared out among the launcher's workers: the same voxels
                launcher.launch(light_rows_kernel, nz * ny, nx, [p, rec, d, need, int(needed_only)], [out])
            self.light.append(out.numpy().reshape(v.density.shape))
        self._wp = {}

    def warp(self):
        """(grids, count, density, light, skip) for the kernels (skip: :func:`skip_distance` of every grid)."""
        if not self._wp:
            recs = self.records()
            n = len(recs)
            dens = np.concatenate([v.density.ravel() for v in self.volumes]) if n else np.zeros(1, np.uint8)
            light = (np.concatenate([np.asarray(l, np.float32).ravel() for l in self.light]) if n
                     else np.zeros(1, np.float32))
            occ = (np.concatenate([np.minimum(skip_distance(v.density), self.skip_cap).ravel()
                                   for v in self.volumes]) if n else np.zeros(1, np.uint8))
            grids = wp.array(recs if n else [VolumeGrid()], dtype=VolumeGrid, device=self.device)
            self._wp = {"grids": grids, "count": n,
                        "density": wp.array(dens, dtype=wp.uint8, device=self.device),
                        "light": wp.array(light, dtype=float, device=self.device),
                        "skip": wp.array(occ, dtype=wp.uint8, device=self.device)}
        w = self._wp
        return w["grids"], w["count"], w["density"], w["light"], w["skip"]


def c_grids(vset: VolumeSet):
    """``ccl_volume_grid[count]`` pointing into the NumPy arrays of ``vset`` (kept alive with the returned tuple)."""
    from ..core.binding import ffi

    f = ffi()
    n = len(vset.volumes)
    arr = f.new("ccl_volume_grid[]", max(n, 1))
    keep = []
    for k, v in enumerate(vset.volumes):
        d = np.ascontiguousarray(v.density)
        lt = np.ascontiguousarray(np.asarray(vset.light[k], dtype=np.float32))
        oc = np.ascontiguousarray(skip_distance(d))
        bd, bl = f.from_buffer("unsigned char[]", d), f.from_buffer("float[]", lt)
        bo = f.from_buffer("unsigned char[]", oc)
        keep += [d, lt, oc, bd, bl, bo]
        arr[k].density = f.cast("const unsigned char *", bd)
        arr[k].light = f.cast("const float *", bl)
        arr[k].skip = f.cast("const unsigned char *", bo)
        arr[k].nz, arr[k].ny, arr[k].nx = d.shape
        arr[k].origin.x, arr[k].origin.y, arr[k].origin.z = v.origin
        arr[k].extent.x, arr[k].extent.y, arr[k].extent.z = v.extent
    return arr, keep


def light_c(values: dict, volume: PlacedVolume) -> np.ndarray:
    """``ccl_volume_light`` of one volume (the C reference of :meth:`VolumeSet.compute_light`)."""
    from ..core.binding import ffi, lib, status_error

    f, lb = ffi(), lib()
    vs = VolumeSet([volume], [np.zeros(volume.density.shape, np.float32)])
    arr, keep = c_grids(vs)
    out = np.empty(volume.density.shape, np.float32)
    status_error(lb.ccl_volume_light(VOLUME_PARAMS.to_c(values), arr, f.from_buffer("float[]", out), out.size),
                 "ccl_volume_light")
    del keep
    return out


def pixels_c(values: dict, vset: VolumeSet, camera, xs, ys, width: int, height: int) -> np.ndarray:
    """``ccl_volume_pixel`` at pixels (xs[k], ys[k]): display-linear RGB (k, 3)."""
    from ..core.binding import ffi, lib

    f, lb = ffi(), lib()
    params = VOLUME_PARAMS.to_c(values)
    arr, keep = c_grids(vset)
    fld = f.new("const char **")
    if lb.ccl_volume_check(params, arr, len(vset.volumes), fld) != 0:
        raise ValueError(f"ccl_volume_check rejected {f.string(fld[0]).decode()}")
    cam = camera.to_c()
    out = np.empty((len(xs), 3), np.float32)
    rgb = f.new("float[3]")
    for k, (x, y) in enumerate(zip(xs, ys)):
        lb.ccl_volume_pixel(params, arr, len(vset.volumes), cam, int(x), int(y), width, height, rgb)
        out[k] = rgb[0], rgb[1], rgb[2]
    del keep
    return out


def pixels_warp(values: dict, vset: VolumeSet, camera, xs, ys, width: int, height: int,
                device: str | None = None) -> np.ndarray:
    """:func:`pywarp.kernels.volume.volume_pixel` at pixels (xs[k], ys[k]): display-linear RGB (k, 3)."""
    grids, count, dens, light, occ = vset.warp()
    dev = vset.device
    xa = wp.array(np.asarray(xs, np.int32), dtype=wp.int32, device=dev)
    ya = wp.array(np.asarray(ys, np.int32), dtype=wp.int32, device=dev)
    out = wp.zeros((len(xs), 3), dtype=float, device=dev)
    wp.launch(pixels_kernel, dim=len(xs), inputs=[VOLUME_PARAMS.warp_struct(values), grids, count, dens, light, occ,
                                                  camera.mat44("inv_view_proj_rot"), camera.eye_vec3(), xa, ya,
                                                  width, height], outputs=[out], device=dev)
    return out.numpy()


def render(vset: VolumeSet, values: dict, camera, width: int, height: int, launcher=None) -> np.ndarray:
    """A whole frame of ``vset`` (light volumes computed) seen by ``camera`` (:func:`pywarp.kernels.camera.
    camera_look_at`): uint8 sRGB (height, width, 3), row bands on every core (``launcher``: default the process-wide
    :class:`pywarp.core.runtime.TileLauncher` of the set's device)."""
    from ..core.runtime import launcher as shared_launcher

    p = VOLUME_PARAMS.warp_struct(checked_params(values))
    for name, v in (("width", width), ("height", height)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not 1 <= v <= 16384:
            raise ValueError(f"{name} must be an integer in [1, 16384], got {v!r}")
    if len(vset.light) != len(vset.volumes):
        raise ValueError("the light volumes are missing: call vset.compute_light(values) first")
    lau = launcher or shared_launcher(vset.device)
    grids, count, dens, light, occ = vset.warp()
    out = wp.zeros((height, width, 3), dtype=wp.uint8, device=vset.device)
    lau.launch(render_kernel, height, width,
               [p, grids, count, dens, light, occ, camera.mat44("inv_view_proj_rot"),
                camera.eye_vec3(), int(width), int(height)], [out])
    return out.numpy()
