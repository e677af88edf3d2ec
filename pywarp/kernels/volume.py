"""Volume rendering of uint8 cloud volumes in a sky -- Warp twins of ``cclouds/volume.h``, the stand-in for SimVoleon
(the Coin3D volume renderer of the oc text), and the survey extras metaballs (oc-4.2) and textured ellipsoids
(oc-4.3).

The pixel (``ccl_volume_pixel``, :func:`volume_pixel`): camera ray; the aircraft (sphere tracing of
:func:`pywarp.kernels.flight.flight_aircraft`), else the fogged ground, else the sky as background; the cloud grids in
the order of their entry distance, each marched in voxel space (emission-absorption, optical depth tau_per_voxel per
voxel length at density 255) with sun light from a precomputed light volume (:data:`light_kernel`, ``ccl_volume_light``:
transmittance towards the sun inside the cloud's own box), a Henyey-Greenstein phase and a height-graded ambient
term; aerial fog on each cloud by its entry distance. The full description is at the top of ``cclouds/volume.h``.

Data layout on the Warp side: every grid's voxels in one flat ``uint8`` array (``density``) and its light volume in
one flat ``float32`` array (``light``), each grid's part starting at ``VolumeGrid.offset``, voxel (x, y, z) of a grid
at ``offset + (z * ny + y) * nx + x`` (the C layout of an array of shape (nz, ny, nx)).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np
import warp as wp

from ..core.cbridge import VOLUME_PARAMS
from ..core.registry import Arg, declare
from .camera import camera_ray
from .colour import colour_srgb_encode
from .common import bound_cell, clamp01, mix3
from .flight import flight_aircraft
from .hash import hash_pcg, hash_unit
from .phase import phase_hg
from .valuenoise import valuenoise_fbm

BIG_T = wp.constant(3.0e38)
MAX_GRIDS = 16          # CCL_VOLUME_MAX_GRIDS
#: Largest colour component and sun_glow accepted (CCL_VOLUME_MAX_COLOUR, reasons in cclouds/volume.h): finite
#: colour x phase x glow products (FLT_MAX gave a NaN pixel).
MAX_COLOUR = 1.0e6
#: Box extents per axis in [1 / LENGTH_RANGE, LENGTH_RANGE] m (CCL_VOLUME_LENGTH_RANGE): a finite, non-zero voxel
#: scale and light direction (a denormal extent gave NaN light).
LENGTH_RANGE = 1.0e6
#: Largest optical depth per voxel (tau_per_voxel, light_tau_per_voxel) and step in voxels (step_voxels,
#: light_step_voxels) accepted (CCL_VOLUME_MAX_TAU, CCL_VOLUME_MAX_STEP): a finite optical depth per step (their
#: product overflowed to Inf, and Inf x a density of 0 gave NaN light).
MAX_TAU = 1.0e6
MAX_STEP = 1.0e6
AIRCRAFT_STEPS = wp.constant(64)  # CCL_VOLUME_AIRCRAFT_STEPS
AIRCRAFT_BOUND = wp.constant(6.3)
BRICK = 2  # CCL_VOLUME_BRICK
_BRICK_I = wp.constant(BRICK)
_BRICK_F = wp.constant(float(BRICK))
_INV_BRICK = wp.constant(1.0 / BRICK)
_Vgrid = wp.types.vector(length=MAX_GRIDS, dtype=wp.float32)  # per-grid values of one ray
FOUR_PI = wp.constant(float(np.float32(4.0) * np.float32(math.pi)))  # 4.0f * CCL_PI_F, folded as in C
_INV_255 = wp.constant(float(np.float32(1.0) / np.float32(255.0)))
_U65536 = wp.constant(wp.uint32(65536))
#: The generated ground (CCL_VOLUME_GROUND_*, reasons in cclouds/volume.h): octaves, period in lattice cells, seed.
GROUND_OCTAVES = 5
GROUND_PERIOD = 256
GROUND_SEED = 7
_GROUND_OCTAVES = wp.constant(GROUND_OCTAVES)
_GROUND_PERIOD = wp.constant(float(GROUND_PERIOD))
_GROUND_SEED = wp.constant(wp.uint32(GROUND_SEED))


@wp.struct
class VolumeGrid:
    """A grid placed in the world (``ccl_volume_grid`` without its pointers: ``offset`` into the flat arrays)."""

    origin: wp.vec3
    extent: wp.vec3
    nx: int
    ny: int
    nz: int
    offset: int
    boffset: int  # start of the grid's bricks in the flat skip-distance array


@wp.struct
class VolumeParams:
    """Mirror of ``ccl_volume_params`` (defaults and reasons: :class:`VolumeLook` and cclouds/src/volume.c)."""

    sun: wp.vec3
    sun_colour: wp.vec3
    ambient_top: wp.vec3
    ambient_bottom: wp.vec3
    sky_zenith: wp.vec3
    sky_horizon: wp.vec3
    ground_a: wp.vec3
    ground_b: wp.vec3
    sun_glow: float
    sun_glow_power: float
    field_size: float
    fog_distance: float
    tau_per_voxel: float
    light_tau_per_voxel: float
    step_voxels: float
    light_step_voxels: float
    exit_transmittance: float
    max_steps: int
    g: float
    jitter: int
    aircraft: int
    aircraft_position: wp.vec3
    aircraft_forward: wp.vec3
    aircraft_right: wp.vec3
    aircraft_up: wp.vec3
    aircraft_scale: float


def sun_direction(elevation_deg: float, azimuth_deg: float) -> tuple:
    """Unit vector towards the sun: azimuth 0 = -z, positive towards +x (the cloudscape's convention), float32
    operations as the C default."""
    e, a = np.float32(math.radians(elevation_deg)), np.float32(math.radians(azimuth_deg))
    ce, se, ca, sa = np.cos(e), np.sin(e), np.cos(a), np.sin(a)
    return (float(ce * sa), float(se), float(-(ce * ca)))


def checked_params(values: dict):
    """``values`` (``ccl_volume_params`` fields; the others the C defaults) checked by ``ccl_volume_check`` without
    grids (:mod:`pywarp.core.cbridge`): the cffi struct; ValueError naming the first bad field."""
    from ..core.binding import ffi

    return VOLUME_PARAMS.checked(values, ffi().NULL, 0)


# --- sampling -----------------------------------------------------------------------------------------------------------

@wp.func
def _tri_mix(fx: float, fy: float, fz: float, c000: float, c100: float, c010: float, c110: float, c001: float,
             c101: float, c011: float, c111: float) -> float:
    a = c000 + (c100 - c000) * fx
    b = c010 + (c110 - c010) * fx
    c = c001 + (c101 - c001) * fx
    d = c011 + (c111 - c011) * fx
    e = a + (b - a) * fy
    f = c + (d - c) * fy
    return e + (f - e) * fz


@wp.func
def _idx(offset: int, nx: int, ny: int, x: int, y: int, z: int) -> int:
    return offset + (z * ny + y) * nx + x


@wp.func
def volume_sample(values: wp.array(dtype=Any), offset: int, nx: int, ny: int, nz: int, v: wp.vec3,
                  scale: float) -> float:
    """Trilinear sample of a grid at voxel coordinates ``v`` (clamped to the edge voxels), times ``scale``; the grid's
    voxels start at ``offset`` of the flat array ``values``, each converted to float32 first (exactly). Twin of
    ``ccl_volume_sample`` (uint8 densities, ``scale`` = 1/255) and of ``ccl_volume_sample_float`` (float32 values,
    ``scale`` = 1, an exact product). Beyond the grid, infinities included, the edge voxels; a NaN component gives
    NaN (``bound_cell`` keeps every conversion to int within range)."""
    if not (v[0] == v[0] and v[1] == v[1] and v[2] == v[2]):
        return v[0] + v[1] + v[2]
    ux = bound_cell(v[0] - 0.5, nx)
    uy = bound_cell(v[1] - 0.5, ny)
    uz = bound_cell(v[2] - 0.5, nz)
    ix = wp.floor(ux)
    iy = wp.floor(uy)
    iz = wp.floor(uz)
    fx = ux - ix
    fy = uy - iy
    fz = uz - iz
    x0 = wp.clamp(int(ix), 0, nx - 1)
    x1 = wp.clamp(int(ix) + 1, 0, nx - 1)
    y0 = wp.clamp(int(iy), 0, ny - 1)
    y1 = wp.clamp(int(iy) + 1, 0, ny - 1)
    z0 = wp.clamp(int(iz), 0, nz - 1)
    z1 = wp.clamp(int(iz) + 1, 0, nz - 1)
    r = _tri_mix(fx, fy, fz,
                 float(values[_idx(offset, nx, ny, x0, y0, z0)]), float(values[_idx(offset, nx, ny, x1, y0, z0)]),
                 float(values[_idx(offset, nx, ny, x0, y1, z0)]), float(values[_idx(offset, nx, ny, x1, y1, z0)]),
                 float(values[_idx(offset, nx, ny, x0, y0, z1)]), float(values[_idx(offset, nx, ny, x1, y0, z1)]),
                 float(values[_idx(offset, nx, ny, x0, y1, z1)]), float(values[_idx(offset, nx, ny, x1, y1, z1)]))
    return r * scale


@wp.func
def _voxel_scale(g: VolumeGrid) -> wp.vec3:
    return wp.vec3(float(g.nx) / g.extent[0], float(g.ny) / g.extent[1], float(g.nz) / g.extent[2])


@wp.func
def _slab(o: float, d: float, n: float, t0: float, t1: float):
    a0 = t0
    a1 = t1
    ok = int(1)
    if d == 0.0:
        if not (o >= 0.0 and o <= n):
            ok = 0
    else:
        inv = 1.0 / d
        a = (0.0 - o) * inv
        b = (n - o) * inv
        if a > b:
            tmp = a
            a = b
            b = tmp
        if a > a0:
            a0 = a
        if b < a1:
            a1 = b
        if not (a0 <= a1):
            ok = 0
    return ok, a0, a1


@wp.func
def volume_box(g: VolumeGrid, eye: wp.vec3, d: wp.vec3):
    """Twin of ``ccl_volume_box``: (hit, t0, t1)."""
    sc = _voxel_scale(g)
    t0 = float(-BIG_T)
    t1 = float(BIG_T)
    ox = (eye[0] - g.origin[0]) * sc[0]
    oy = (eye[1] - g.origin[1]) * sc[1]
    oz = (eye[2] - g.origin[2]) * sc[2]
    hit = int(0)
    okx, t0, t1 = _slab(ox, d[0] * sc[0], float(g.nx), t0, t1)
    if okx != 0:
        oky, t0, t1 = _slab(oy, d[1] * sc[1], float(g.ny), t0, t1)
        if oky != 0:
            okz, t0, t1 = _slab(oz, d[2] * sc[2], float(g.nz), t0, t1)
            if okz != 0 and t1 > 0.0:
                hit = 1
    return hit, t0, t1


# --- the light volume ---------------------------------------------------------------------------------------------------

@wp.func
def volume_light_voxel(p: VolumeParams, g: VolumeGrid, density: wp.array(dtype=wp.uint8), i: int):
    """Transmittance towards the sun of voxel ``i`` of grid ``g`` (``ccl_volume_light``'s per-voxel march)."""
    nx = g.nx
    ny = g.ny
    nz = g.nz
    ix = i % nx
    iy = (i // nx) % ny
    iz = i // (nx * ny)
    sc = _voxel_scale(g)
    s_v = wp.vec3(p.sun[0] * sc[0], p.sun[1] * sc[1], p.sun[2] * sc[2])
    ln = wp.length(s_v)
    s_v = s_v * (1.0 / ln)
    step = p.light_step_voxels
    tau = p.light_tau_per_voxel * step
    fnx = float(nx)
    fny = float(ny)
    fnz = float(nz)
    max_k = int(wp.ceil(wp.sqrt(fnx * fnx + fny * fny + fnz * fnz) / step)) + 1
    c = wp.vec3(float(ix) + 0.5, float(iy) + 0.5, float(iz) + 0.5)
    total = float(0.0)
    for k in range(1, max_k + 1):
        q = c + s_v * (float(k) * step)
        if q[0] < 0.0 or q[1] < 0.0 or q[2] < 0.0 or q[0] > fnx or q[1] > fny or q[2] > fnz:
            break
        total = total + volume_sample(density, g.offset, nx, ny, nz, q, _INV_255)
    return wp.exp(-tau * total)


@wp.kernel
def light_kernel(p: VolumeParams, g: VolumeGrid, density: wp.array(dtype=wp.uint8),
                 # output: the grid's light volume (its own array, offset 0)
                 out: wp.array(dtype=float)):
    """Twin of ``ccl_volume_light``: one thread per voxel."""
    i = wp.tid()
    out[i] = volume_light_voxel(p, g, density, i)


@wp.kernel
def light_rows_kernel(row0: int, p: VolumeParams, g: VolumeGrid, density: wp.array(dtype=wp.uint8),
                      needed: wp.array(dtype=wp.uint8), needed_only: int,
                      # output: the grid's light volume (its own array, offset 0)
                      out: wp.array(dtype=float)):
    """:data:`light_kernel` as rows (z, y) x columns x of the grid, for the multi-core tile launcher
    (:class:`pywarp.core.runtime.TileLauncher`): the same voxels, each one thread's. ``needed_only`` != 0: voxels
    whose ``needed`` is 0 (none of their trilinear cells holds density: no ray reads them) are set to 1, not
    marched."""
    r, x = wp.tid()
    i = (row0 + r) * g.nx + x
    if needed_only != 0:
        if needed[i] == wp.uint8(0):
            out[i] = 1.0
            return
    out[i] = volume_light_voxel(p, g, density, i)


# --- background: sky, ground, aircraft ----------------------------------------------------------------------------------

@wp.func
def volume_sky(p: VolumeParams, d: wp.vec3) -> wp.vec3:
    """Twin of ``ccl_volume_sky``."""
    up = wp.where(d[1] > 0.0, d[1], 0.0)
    c = wp.dot(d, p.sun)
    # clamped to [0, 1] as in C: the dot of unit vectors may round above 1 (c^power overflowed for huge powers)
    c = wp.where(c > 0.0, wp.where(c < 1.0, c, 1.0), 0.0)
    glow = p.sun_glow * wp.pow(c, p.sun_glow_power)
    up = wp.sqrt(up)
    col = p.sky_horizon + (p.sky_zenith - p.sky_horizon) * up
    return col + p.sun_colour * glow


@wp.func
def _to_model(p: VolumeParams, w: wp.vec3) -> wp.vec3:
    return wp.vec3(wp.dot(w, p.aircraft_right), wp.dot(w, p.aircraft_up), -wp.dot(w, p.aircraft_forward))


@wp.func
def _aircraft_hit(p: VolumeParams, eye: wp.vec3, d: wp.vec3):
    """(t [world], part, model-frame hit point); t = BIG_T when missed."""
    inv = 1.0 / p.aircraft_scale
    o = _to_model(p, eye - p.aircraft_position) * inv
    dm = _to_model(p, d)
    b = wp.dot(o, dm)
    c = wp.dot(o, o) - AIRCRAFT_BOUND * AIRCRAFT_BOUND
    disc = b * b - c
    result = float(BIG_T)
    part_hit = int(0)
    q_hit = wp.vec3(0.0, 0.0, 0.0)
    if disc > 0.0:
        disc = wp.sqrt(disc)
        t = -b - disc
        t_far = -b + disc
        if t_far > 0.0:
            if t < 0.0:
                t = 0.0
            for k in range(AIRCRAFT_STEPS):
                q = o + dm * t
                dist, part = flight_aircraft(q)
                if dist < 0.002:
                    part_hit = part
                    q_hit = q
                    result = t * p.aircraft_scale
                    break
                t = t + dist
                if t > t_far:
                    break
    return result, part_hit, q_hit


@wp.func
def _aircraft_colour(p: VolumeParams, q: wp.vec3, part: int) -> wp.vec3:
    h = 0.01
    nx0, _a = flight_aircraft(wp.vec3(q[0] + h, q[1], q[2]))
    nx1, _b = flight_aircraft(wp.vec3(q[0] - h, q[1], q[2]))
    ny0, _c = flight_aircraft(wp.vec3(q[0], q[1] + h, q[2]))
    ny1, _d = flight_aircraft(wp.vec3(q[0], q[1] - h, q[2]))
    nz0, _e = flight_aircraft(wp.vec3(q[0], q[1], q[2] + h))
    nz1, _f = flight_aircraft(wp.vec3(q[0], q[1], q[2] - h))
    n = wp.normalize(wp.vec3(nx0 - nx1, ny0 - ny1, nz0 - nz1))
    nw = (p.aircraft_right * n[0] + p.aircraft_up * n[1]) + p.aircraft_forward * (-n[2])
    base = wp.vec3(0.08, 0.12, 0.2)
    if part == 0:
        base = wp.vec3(0.85, 0.85, 0.82)
    elif part == 1:
        base = wp.vec3(0.75, 0.12, 0.08)
    elif part == 2:
        base = wp.vec3(0.75, 0.12, 0.08)
    ndl = wp.dot(nw, p.sun)
    ndl = wp.where(ndl > 0.0, ndl, 0.0)
    up = 0.5 + 0.5 * nw[1]
    lit = p.sun_colour * ndl + (p.ambient_top * up + p.ambient_bottom * (1.0 - up))
    return wp.vec3(base[0] * lit[0], base[1] * lit[1], base[2] * lit[2])


@wp.func
def _ground_coord(g: float, field_size: float) -> float:
    u = g / field_size + 0.5 * _GROUND_PERIOD
    u = u - wp.floor(u / _GROUND_PERIOD) * _GROUND_PERIOD
    if u >= 0.0 and u < _GROUND_PERIOD:
        return u
    return 0.0


@wp.func
def _ground_fbm(x: float, z: float, seed: wp.uint32) -> float:
    # 2-D octave sum: raw lattice (smoothing 3), cosine (1), corrected persistence (0), unit range (0)
    return valuenoise_fbm(x, z, 0.0, seed, 2, _GROUND_OCTAVES, 0.5, 3, 1, 0, 0)


@wp.func
def volume_ground(p: VolumeParams, gx: float, gz: float) -> wp.vec3:
    """Twin of ``ccl_volume_ground``: the albedo of the generated ground at (gx, gz) [m] -- value-noise octave sums
    for meadows and fields (ground_a .. ground_b), forest and a river (the formulas in cclouds/volume.h)."""
    x = _ground_coord(gx, p.field_size)
    z = _ground_coord(gz, p.field_size)
    a = clamp01(2.5 * (_ground_fbm(x, z, _GROUND_SEED) - 0.5) + 0.5)
    b = clamp01(12.0 * (_ground_fbm(x, z, _GROUND_SEED + wp.uint32(1)) - 0.56))
    r = _ground_fbm(0.25 * x, 0.25 * z, _GROUND_SEED + wp.uint32(2)) - 0.5
    w = clamp01((0.012 - wp.abs(r)) / 0.004)
    alb = mix3(p.ground_a, p.ground_b, a)
    alb = mix3(alb, p.ground_a * 0.45, b)
    return mix3(alb, wp.vec3(0.06, 0.09, 0.12), w)


@wp.func
def volume_background(p: VolumeParams, eye: wp.vec3, d: wp.vec3):
    """Twin of ``ccl_volume_background``: (colour, aircraft distance or BIG_T)."""
    col = wp.vec3(0.0, 0.0, 0.0)
    t_out = float(BIG_T)
    done = int(0)
    if p.aircraft != 0:
        t_hit, part, q = _aircraft_hit(p, eye, d)
        if t_hit < BIG_T:
            t_out = t_hit
            col = _aircraft_colour(p, q, part)
            done = 1
    if done == 0:
        if d[1] < 0.0 and eye[1] > 0.0:
            t = -eye[1] / d[1]
            sun_up = wp.where(p.sun[1] > 0.0, p.sun[1], 0.0)
            alb = volume_ground(p, eye[0] + t * d[0], eye[2] + t * d[2])
            lit = p.sun_colour * sun_up + p.ambient_top
            col = wp.vec3(alb[0] * lit[0], alb[1] * lit[1], alb[2] * lit[2])
            f = wp.exp(-t / p.fog_distance)
            col = mix3(p.sky_horizon, col, f)
        else:
            col = volume_sky(p, d)
    return col, t_out


@wp.func
def _brick_exit(o: wp.vec3, d: wp.vec3, bx: int, by: int, bz: int, m: int) -> float:
    """Exit of the voxel-space ray from the cube of bricks b - (m - 1) .. b + m - 1 around brick (bx, by, bz)."""
    b = _BRICK_F
    r = float(m - 1)
    te = float(BIG_T)
    if d[0] != 0.0:
        plane = (float(bx) - r) * b
        if d[0] > 0.0:
            plane = (float(bx) + r + 1.0) * b
        t = (plane - o[0]) / d[0]
        te = wp.where(t < te, t, te)
    if d[1] != 0.0:
        plane = (float(by) - r) * b
        if d[1] > 0.0:
            plane = (float(by) + r + 1.0) * b
        t = (plane - o[1]) / d[1]
        te = wp.where(t < te, t, te)
    if d[2] != 0.0:
        plane = (float(bz) - r) * b
        if d[2] > 0.0:
            plane = (float(bz) + r + 1.0) * b
        t = (plane - o[2]) / d[2]
        te = wp.where(t < te, t, te)
    return te


# --- the pixel ----------------------------------------------------------------------------------------------------------

@wp.func
def volume_pixel(p: VolumeParams, grids: wp.array(dtype=VolumeGrid), count: int, density: wp.array(dtype=wp.uint8),
                 light: wp.array(dtype=float), skip: wp.array(dtype=wp.uint8), inv_view_proj_rot: wp.mat44,
                 eye: wp.vec3, x: int, y: int, width: int, height: int) -> wp.vec3:
    """Twin of ``ccl_volume_pixel``: the display-linear colour of pixel (x, y)."""
    d = camera_ray(inv_view_proj_rot, x, y, width, height)
    jitter = float(0.5)
    if p.jitter != 0:
        jitter = hash_unit(hash_pcg(wp.uint32(x) + _U65536 * wp.uint32(y)))
    total_t = float(1.0)
    bg, t_hit = volume_background(p, eye, d)
    total = wp.vec3(0.0, 0.0, 0.0)
    mu = wp.clamp(wp.dot(d, p.sun), -1.0, 1.0)
    phase = FOUR_PI * phase_hg(mu, p.g)
    last_t = float(-BIG_T)
    last_i = int(-1)
    # every box's entry and exit once (a miss: entry BIG_T, never chosen); then the grids in the order of entry
    box_t0 = _Vgrid()
    box_t1 = _Vgrid()
    box_hit = _Vgrid()
    for k in range(count):
        hit, t0, t1 = volume_box(grids[k], eye, d)
        box_t0[k] = t0
        box_t1[k] = t1
        box_hit[k] = float(hit)
    for k in range(count):
        best = int(-1)
        best_t0 = float(BIG_T)
        best_t1 = float(0.0)
        for i in range(count):
            if box_hit[i] == 0.0:
                continue
            t0 = box_t0[i]
            if t0 < last_t or (t0 == last_t and i <= last_i):
                continue
            if best < 0 or t0 < best_t0:
                best = i
                best_t0 = t0
                best_t1 = box_t1[i]
        if best < 0:
            break
        last_t = best_t0
        last_i = best
        g = grids[best]
        col = wp.vec3(0.0, 0.0, 0.0)
        trans = float(1.0)
        t_start = wp.where(best_t0 > 0.0, best_t0, 0.0)
        t_end = wp.where(best_t1 < t_hit, best_t1, t_hit)
        sc = _voxel_scale(g)
        o_v = wp.vec3((eye[0] - g.origin[0]) * sc[0], (eye[1] - g.origin[1]) * sc[1], (eye[2] - g.origin[2]) * sc[2])
        d_v = wp.vec3(d[0] * sc[0], d[1] * sc[1], d[2] * sc[2])
        dt = p.step_voxels / wp.length(d_v)
        a_step = p.tau_per_voxel * p.step_voxels
        n = int(0)
        if t_end > t_start:
            steps = wp.ceil((t_end - t_start) / dt)
            if steps < float(p.max_steps):
                n = int(steps)
            else:
                n = p.max_steps
        mx = (g.nx + _BRICK_I - 1) // _BRICK_I
        my = (g.ny + _BRICK_I - 1) // _BRICK_I
        mz = (g.nz + _BRICK_I - 1) // _BRICK_I
        s = int(0)
        while s < n:
            t = t_start + (float(s) + jitter) * dt
            if t > t_end:
                break
            v = o_v + d_v * t
            bx = wp.clamp(int(wp.floor(v[0] * _INV_BRICK)), 0, mx - 1)
            by = wp.clamp(int(wp.floor(v[1] * _INV_BRICK)), 0, my - 1)
            bz = wp.clamp(int(wp.floor(v[2] * _INV_BRICK)), 0, mz - 1)
            m = int(skip[g.boffset + (bz * my + by) * mx + bx])
            if m > 0:
                # an empty cube of bricks around: go to the first sample at or after its exit
                te = _brick_exit(o_v, d_v, bx, by, bz, m)
                nxt = wp.ceil((te - t_start) / dt - jitter)
                if nxt > float(s + 1):
                    if nxt < float(n):
                        s = int(nxt)
                    else:
                        s = n
                else:
                    s = s + 1
                continue
            s = s + 1
            # volume_sample of the density (scale 1/255) and of the light (scale 1) at v, sharing the weights
            ux = v[0] - 0.5
            uy = v[1] - 0.5
            uz = v[2] - 0.5
            ix = wp.floor(ux)
            iy = wp.floor(uy)
            iz = wp.floor(uz)
            fx = ux - ix
            fy = uy - iy
            fz = uz - iz
            x0 = wp.clamp(int(ix), 0, g.nx - 1)
            x1 = wp.clamp(int(ix) + 1, 0, g.nx - 1)
            y0 = wp.clamp(int(iy), 0, g.ny - 1)
            y1 = wp.clamp(int(iy) + 1, 0, g.ny - 1)
            z0 = wp.clamp(int(iz), 0, g.nz - 1)
            z1 = wp.clamp(int(iz) + 1, 0, g.nz - 1)
            i000 = g.offset + (z0 * g.ny + y0) * g.nx
            i010 = g.offset + (z0 * g.ny + y1) * g.nx
            i001 = g.offset + (z1 * g.ny + y0) * g.nx
            i011 = g.offset + (z1 * g.ny + y1) * g.nx
            rho = _tri_mix(fx, fy, fz, float(density[i000 + x0]), float(density[i000 + x1]),
                           float(density[i010 + x0]), float(density[i010 + x1]), float(density[i001 + x0]),
                           float(density[i001 + x1]), float(density[i011 + x0]), float(density[i011 + x1])) * _INV_255
            if rho <= 0.0:
                continue
            tl = _tri_mix(fx, fy, fz, light[i000 + x0], light[i000 + x1], light[i010 + x0], light[i010 + x1],
                          light[i001 + x0], light[i001 + x1], light[i011 + x0], light[i011 + x1])
            alpha = 1.0 - wp.exp(-a_step * rho)
            hfrac = wp.clamp(v[1] / float(g.ny), 0.0, 1.0)
            amb = mix3(p.ambient_bottom, p.ambient_top, hfrac)
            lc = p.sun_colour * (tl * phase) + amb
            col = col + lc * (trans * alpha)
            trans = trans * (1.0 - alpha)
            if trans < p.exit_transmittance:
                break
        fog = wp.exp(-t_start / p.fog_distance)
        col = col * fog + p.sky_horizon * ((1.0 - fog) * (1.0 - trans))
        total = total + col * total_t
        total_t = total_t * trans
        if total_t < p.exit_transmittance:
            break
    return wp.vec3(total[0] + total_t * bg[0], total[1] + total_t * bg[1], total[2] + total_t * bg[2])


# --- image kernels (TileLauncher convention) ----------------------------------------------------------------------------

@wp.kernel
def render_kernel(row0: int, p: VolumeParams, grids: wp.array(dtype=VolumeGrid), count: int,
                  density: wp.array(dtype=wp.uint8), light: wp.array(dtype=float),
                  skip: wp.array(dtype=wp.uint8), inv_view_proj_rot: wp.mat44, eye: wp.vec3, width: int,
                  height: int,
                  # output: sRGB uint8
                  out: wp.array3d(dtype=wp.uint8)):
    """One row band: the pixel, clamped to [0, 1], sRGB-encoded, rounded to uint8."""
    i, j = wp.tid()
    y = row0 + i
    c = volume_pixel(p, grids, count, density, light, skip, inv_view_proj_rot, eye, j, y, width, height)
    for ch in range(3):
        e = colour_srgb_encode(wp.clamp(c[ch], 0.0, 1.0))
        out[y, j, ch] = wp.uint8(int(e * 255.0 + 0.5))


@wp.kernel
def render_linear_kernel(row0: int, p: VolumeParams, grids: wp.array(dtype=VolumeGrid), count: int,
                         density: wp.array(dtype=wp.uint8), light: wp.array(dtype=float),
                         skip: wp.array(dtype=wp.uint8), inv_view_proj_rot: wp.mat44, eye: wp.vec3, width: int,
                         height: int,
                         # output: the display-linear pixel, unclamped (the display transform's input)
                         out: wp.array3d(dtype=float)):
    """One row band of :func:`volume_pixel` as float (pywarp.core.display encodes it)."""
    i, j = wp.tid()
    y = row0 + i
    c = volume_pixel(p, grids, count, density, light, skip, inv_view_proj_rot, eye, j, y, width, height)
    for ch in range(3):
        out[y, j, ch] = c[ch]


@wp.kernel
def pixels_kernel(p: VolumeParams, grids: wp.array(dtype=VolumeGrid), count: int, density: wp.array(dtype=wp.uint8),
                  light: wp.array(dtype=float), skip: wp.array(dtype=wp.uint8), inv_view_proj_rot: wp.mat44,
                  eye: wp.vec3, xs: wp.array(dtype=wp.int32), ys: wp.array(dtype=wp.int32), width: int, height: int,
                  out: wp.array2d(dtype=float)):
    """:func:`volume_pixel` at chosen pixels (the Warp side of the comparison with ``ccl_volume_pixel``)."""
    k = wp.tid()
    c = volume_pixel(p, grids, count, density, light, skip, inv_view_proj_rot, eye, xs[k], ys[k], width,
                     height)
    out[k, 0] = c[0]
    out[k, 1] = c[1]
    out[k, 2] = c[2]


# --- survey extras: metaballs (oc-4.2) and textured ellipsoids (oc-4.3) --------------------------------------------------

_METABALL_SQUARE_MIN = wp.constant(2.0 ** -60)  # the radii whose square is a normal float (METABALL_SQUARE_MIN, _MAX)
_METABALL_SQUARE_MAX = wp.constant(2.0 ** 60)


@declare("oc-4.2", c="ccl_volume_metaball",
         args=(Arg("distance", "distance from the source's centre", lo=0.0, sample_range=(0.0, 10.0)),
               Arg("radius", "the source's radius of influence R", lo=0.0, lo_open=True, sample_range=(0.1, 10.0)),
               Arg("strength", "the source's strength", sample_range=(-5.0, 5.0))),
         outputs=("field",),
         summary="Metaball field of one source (centre, radius, strength as the text lists them; the text gives no "
                 "field function, Wyvill's soft-object kernel stands in): strength (1 - r^2/R^2)^3 for r < R, else 0. "
                 "A cloud base is the thresholded sum over the sources (tutorials/oc/fig_4_01_metaballs.py).",
         references=("Kučera 2006, §4.2", "Wyvill, McPheeters & Wyvill, Data structure for soft objects, "
                                           "The Visual Computer 2(4), 1986"))
@wp.func
def volume_metaball(distance: float, radius: float, strength: float) -> float:
    """r >= R decides outside before any square; inside, r^2/R^2 where R^2 is a normal float, else (r/R)^2 (the
    squares of a radius beyond 2^+-60 under- or overflowed: 0/0, Inf/Inf). A NaN r gives NaN. As C."""
    r = 0.0 * strength
    if not (distance >= radius):
        q = float(0.0)
        if radius >= _METABALL_SQUARE_MIN and radius <= _METABALL_SQUARE_MAX:
            q = (distance * distance) / (radius * radius)
        else:
            q = (distance / radius) * (distance / radius)
        w = 1.0 - q
        r = strength * (w * w * w)
    return r


@declare("oc-4.3", c="ccl_volume_ellipsoid",
         args=(Arg("p", "point relative to the ellipsoid's centre", sample_range=(-5.0, 5.0)),
               Arg("radii", "semi-axes (each > 0)", lo=0.0, lo_open=True, sample_range=(0.5, 5.0)),
               Arg("texture", "texturing function at p (noise fBm) in [0, 1]", lo=0.0, hi=1.0),
               Arg("threshold", "Gardner's threshold T1", lo=0.0, hi=1.0),
               Arg("ramp", "Gardner's ramp D (> 0)", lo=0.0, lo_open=True, hi=1.0)),
         outputs=("opacity",),
         summary="Opacity of a textured ellipsoid (Gardner 1985 in kind; the text gives no formula): q = |p/radii|^2, "
                 "g = 1 - q, opacity = clamp((texture - T1 - D (1 - g)) / D, 0, 1): the texture decides, the edge is "
                 "eaten away towards the surface.",
         references=("Kučera 2006, §4.3", "Gardner, Visual simulation of clouds, SIGGRAPH 1985"))
@wp.func
def volume_ellipsoid(p: wp.vec3, radii: wp.vec3, texture: float, threshold: float, ramp: float) -> float:
    qx = p[0] / radii[0]
    qy = p[1] / radii[1]
    qz = p[2] / radii[2]
    q = qx * qx + qy * qy + qz * qz
    g = 1.0 - q
    o = (texture - threshold - ramp * (1.0 - g)) / ramp
    if o < 0.0:
        o = 0.0
    if o > 1.0:
        o = 1.0
    return o
