"""The host side of the rain particle system and of the drop compositor (rr-code-5.2.2, rr-code-5.2.3/5.2.4): the
state arrays and the count of :class:`ParticleSystem`, the NumPy-level compositing passes (:func:`composite` over a
frame, :func:`composite_pixels` at chosen pixels, the C reference), their checks, the screen-tile binning and the
packed mask, and the evaluators the registry names for rr-code-5.2.2 and rr-code-5.2.3/5.2.4. The equations and
kernels they launch are :mod:`pywarp.kernels.particles`.
"""
from __future__ import annotations

import math

import numpy as np
import warp as wp

from ..core.cbridge import PARTICLES_PARAMS, read
from ..core.registry import VARIANT, Arg
from ..kernels import VARIANT_CORRECTED
from ..kernels.particles import (_FOV, _FOV_CAPTURE, FILTERS, MAX_COUNT, STREAKS, ParticlesLights, c_lights, check_lights,
                                 composite_kernel, composite_tile_kernel, light_params, lights_on,
                                 pixels_kernel, spawn_kernel, step_kernel, uv_ratio_kernel)


class ParticleSystem:
    """SimulateParticleSystem (rr-code-5.2.2) on the Warp device: state arrays of ``capacity`` particles and the
    count. ``step(requested, dt)`` runs one frame (the count logic on the host, as the listing's scalar code; the
    particles in one kernel launch). ``variant='thesis'`` keeps the printed decrement (the count goes negative and no
    particle is ever simulated). ``warm=True`` starts the (corrected) system full, as if it had been falling for a
    while (ours: the text grows the system one particle per frame)."""

    def __init__(self, capacity: int, device: str = "cpu", variant: str = "corrected", **values):
        if isinstance(capacity, bool) or not isinstance(capacity, (int, np.integer)) or not 0 <= capacity <= MAX_COUNT:
            raise ValueError(f"capacity must be an integer in [0, {MAX_COUNT}], got {capacity!r}")
        self.variant = VARIANT.check(variant)
        c = PARTICLES_PARAMS.checked(values)  # ccl_particles_params_check (pywarp.core.cbridge)
        self.values = read(c)
        self.params = PARTICLES_PARAMS.warp_struct(c)
        self.capacity = int(capacity)
        self.device = device
        n = max(self.capacity, 1)
        self.pos = wp.zeros(n, dtype=wp.vec3, device=device)
        self.radius = wp.zeros(n, dtype=float, device=device)
        self.speed = wp.zeros(n, dtype=float, device=device)
        self.generation = wp.zeros(n, dtype=wp.uint32, device=device)
        self.count = 0

    def _check_requested(self, requested: int) -> int:
        if isinstance(requested, bool) or not isinstance(requested, (int, np.integer)) \
                or not 0 <= requested <= self.capacity:
            raise ValueError(f"requested must be an integer in [0, capacity = {self.capacity}], got {requested!r}")
        return int(requested)

    def _check_dt(self, dt: float) -> float:
        dt = float(dt)
        if not (0.0 <= dt <= 1.0):
            raise ValueError(f"dt must be in [0, 1] s, got {dt!r}")
        w, lo, hi = self.values["wind"], self.values["box_min"], self.values["box_max"]
        for k, axis in ((0, "x"), (2, "z")):
            if abs(np.float32(w[k])) * np.float32(dt) > np.float32(hi[k]) - np.float32(lo[k]):
                raise ValueError(f"dt must keep |wind {axis}| dt within the box width, got dt = {dt!r} at wind "
                                 f"{w[k]!r}")
        return dt

    def fill(self, requested: int) -> None:
        """Warm start (corrected variant, empty system): ``requested`` particles spawned with y uniform between the
        respawn level and the box top."""
        requested = self._check_requested(requested)
        if self.variant == VARIANT_CORRECTED and self.count == 0 and requested:
            wp.launch(spawn_kernel, dim=requested, inputs=[self.params, 0, 1],
                      outputs=[self.pos, self.radius, self.speed, self.generation], device=self.device)
            self.count = requested

    def step(self, requested: int, dt: float) -> None:
        """One frame of SimulateParticleSystem."""
        requested = self._check_requested(requested)
        dt = self._check_dt(dt)
        if self.variant == VARIANT_CORRECTED:
            if self.count > requested:
                self.count = requested
            if self.count < requested:
                wp.launch(spawn_kernel, dim=1, inputs=[self.params, self.count, 0],
                          outputs=[self.pos, self.radius, self.speed, self.generation], device=self.device)
                self.count += 1
        elif self.count < requested:
            if 0 <= self.count < self.capacity:
                wp.launch(spawn_kernel, dim=1, inputs=[self.params, self.count, 0],
                          outputs=[self.pos, self.radius, self.speed, self.generation], device=self.device)
            if self.count > -MAX_COUNT:
                self.count -= 1
        n = max(self.count, 0)
        if n:
            wp.launch(step_kernel, dim=n, inputs=[self.params, float(np.float32(dt))],
                      outputs=[self.pos, self.radius, self.speed, self.generation], device=self.device)

    def state(self) -> dict:
        """The simulated particles (i < count) as NumPy arrays: pos (n, 3), radius_mm, speed, generation."""
        n = max(self.count, 0)
        return {"pos": self.pos.numpy()[:n].copy(), "radius_mm": self.radius.numpy()[:n].copy(),
                "speed": self.speed.numpy()[:n].copy(), "generation": self.generation.numpy()[:n].copy(),
                "count": self.count}


def _simulate_args(frames, requested, dt, capacity, warm, variant):
    for name, v in (("frames", frames), ("requested", requested)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
            raise ValueError(f"{name} must be an integer >= 0, got {v!r}")
    if capacity is None:
        capacity = requested
    if isinstance(capacity, bool) or not isinstance(capacity, (int, np.integer)) or not requested <= capacity <= MAX_COUNT:
        raise ValueError(f"capacity must be an integer in [requested, {MAX_COUNT}], got {capacity!r}")
    if not isinstance(warm, (bool, np.bool_)):
        raise TypeError(f"warm must be True or False, got {warm!r}")
    if isinstance(dt, bool) or not isinstance(dt, (int, float, np.integer, np.floating)):
        raise TypeError(f"dt must be a number, got {dt!r}")
    return int(frames), int(requested), float(dt), int(capacity), bool(warm), VARIANT.check(variant)


def simulate_warp(eq, device):
    # not element-wise: a stateful system (the count grows by one per frame; particles respawn) run for n frames
    def particles_simulate(frames, requested, dt=1.0 / 60.0, capacity=None, warm=False, variant="corrected",
                           **values):
        frames, requested, dt, capacity, warm, v = _simulate_args(frames, requested, dt, capacity, warm, variant)
        ps = ParticleSystem(capacity, device=device or "cpu", variant=variant, **values)
        if warm:
            ps.fill(requested)
        for _ in range(frames):
            ps.step(requested, dt)
        return ps.state()

    return particles_simulate


def simulate_c(eq):
    # not element-wise: the C function runs the whole system for n frames over caller-owned arrays
    def particles_simulate(frames, requested, dt=1.0 / 60.0, capacity=None, warm=False, variant="corrected",
                           **values):
        from ..core.binding import ffi, lib, status_error

        frames, requested, dt, capacity, warm, v = _simulate_args(frames, requested, dt, capacity, warm, variant)
        ParticleSystem(0, variant=variant, **values)._check_dt(dt)  # the same ValueErrors as the Warp side
        f = ffi()
        n = max(capacity, 1)
        pos = np.zeros((n, 3), np.float32)
        radius = np.zeros(n, np.float32)
        speed = np.zeros(n, np.float32)
        gen = np.zeros(n, np.uint32)
        count = f.new("int *", 0)
        st = lib().ccl_particles_simulate(PARTICLES_PARAMS.checked(values), requested, dt, frames, int(warm), v,
                                          capacity,
                                          f.cast("ccl_vec3 *", f.from_buffer("float[]", pos)),
                                          f.from_buffer("float[]", radius), f.from_buffer("float[]", speed),
                                          f.from_buffer("uint32_t[]", gen), count)
        status_error(st, "ccl_particles_simulate")
        k = max(count[0], 0)
        return {"pos": pos[:k].copy(), "radius_mm": radius[:k].copy(), "speed": speed[:k].copy(),
                "generation": gen[:k].copy(), "count": int(count[0])}

    return particles_simulate


def particles_streak_np(speed, persistence_s, radius):
    """:func:`pywarp.kernels.particles.particles_streak` on NumPy arrays (the same float32 operations), for the
    per-frame vertex stage."""
    sp = np.asarray(speed, np.float32)
    length = sp * np.float32(persistence_s)
    return length, (length / np.float32(6.0)) / (np.float32(2.0) * np.asarray(radius, np.float32) + length)


def pack_mask(mask: np.ndarray) -> np.ndarray:
    """The refraction mask (n, n, 4) as the frame kernel reads it: per texel (x / z, y / z) in float32 (the quotients
    the shader forms), NaN where the texel is outside the drop or has no ray (a <= 0, z <= 0, or a NaN
    quotient), stored COLUMN-major
    (texel (row my, column mx) at 2 (mx n + my)): a streak's taps walk down one mask column, so they share cache lines
    (the row-major RGBA mask made every tap a cache miss). Half the memory, no division per tap, the same values."""
    m = np.asarray(mask, np.float32)
    ok = (m[..., 3] > 0) & (m[..., 2] > 0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        qx, qy = m[..., 0] / m[..., 2], m[..., 1] / m[..., 2]
    ok &= ~(np.isnan(qx) | np.isnan(qy))  # a NaN exit direction: no ray (as ccl_particles_tap)
    q = np.stack([np.where(ok, qx, np.float32(np.nan)), np.where(ok, qy, np.float32(np.nan))], -1).astype(np.float32)
    return np.ascontiguousarray(q.transpose(1, 0, 2)).reshape(-1)


def pack_normals(normals: np.ndarray) -> np.ndarray:
    """The mask's entry normals (n, n, 3) column-major like :func:`pack_mask` (texel (my, mx) at 3 (mx n + my))."""
    return np.ascontiguousarray(np.asarray(normals, np.float32).transpose(1, 0, 2)).reshape(-1)


def capture_scale(fov_capture: float) -> float:
    """Offset scale of the refraction vector in capture texture units, 0.5 / tan(fov_capture / 2) (float32): a drop in
    the centre of the view then samples its refracted direction exactly."""
    return float(np.float32(0.5) / np.tan(np.float32(0.5) * np.float32(fov_capture)))


def bin_sprites(sprites: np.ndarray, width: int, height: int, tile: int = 8) -> tuple[np.ndarray, np.ndarray, int]:
    """Screen-tile lists of the sprites (a conservative bounding box per sprite, one pixel of margin): (tile_start
    (tiles + 1,), tile_items, tiles_x); within a tile the sprites keep their order (far first). Vectorised NumPy: the
    (sprite, tile) pairs are generated sprite by sprite and stably sorted by tile (a counting sort's result)."""
    tiles_x = -(-width // tile)
    tiles_y = -(-height // tile)
    ntiles = tiles_x * tiles_y
    s = np.asarray(sprites, np.float32).reshape(-1, 6)
    empty = np.zeros(ntiles + 1, np.int32), np.zeros(0, np.int32), tiles_x
    if not len(s):
        return empty
    on = ((s[:, 0] + s[:, 2] >= 0) & (s[:, 0] - s[:, 2] <= width) & (s[:, 1] + s[:, 3] >= 0)
          & (s[:, 1] - s[:, 3] <= height))
    idx = np.nonzero(on)[0]
    if not len(idx):
        return empty
    s = s[idx]
    x0 = np.clip(np.floor((s[:, 0] - s[:, 2]) - np.float32(1.0)) // tile, 0, tiles_x - 1).astype(np.int64)
    x1 = np.clip(np.floor((s[:, 0] + s[:, 2]) + np.float32(1.0)) // tile, 0, tiles_x - 1).astype(np.int64)
    y0 = np.clip(np.floor((s[:, 1] - s[:, 3]) - np.float32(1.0)) // tile, 0, tiles_y - 1).astype(np.int64)
    y1 = np.clip(np.floor((s[:, 1] + s[:, 3]) + np.float32(1.0)) // tile, 0, tiles_y - 1).astype(np.int64)
    nx = x1 - x0 + 1
    per = nx * (y1 - y0 + 1)
    total = int(per.sum())
    first = np.repeat(np.cumsum(per) - per, per)
    k = np.arange(total, dtype=np.int64) - first
    nxr = np.repeat(nx, per)
    t = (np.repeat(y0, per) + k // nxr) * tiles_x + np.repeat(x0, per) + k % nxr
    order = np.argsort(t, kind="stable")  # by tile; within a tile the generation order = sprite order
    items = np.repeat(idx.astype(np.int32), per)[order]
    start = np.zeros(ntiles + 1, np.int64)
    start[1:] = np.cumsum(np.bincount(t, minlength=ntiles))
    return start.astype(np.int32), items, tiles_x


def _composite_args(background, capture, mask, sprites, fov_view, fov_capture, streaks, filter, opacity,
                    checked: dict | None = None):
    """The checked inputs of the compositing pass. ``checked``: a dict the caller keeps between frames; a background,
    capture or mask array that is the same object as one already found finite is not scanned again (the rain
    technique passes its own cached images every frame)."""
    bg = np.ascontiguousarray(background, np.float32)
    if bg.ndim != 3 or bg.shape[2] != 3 or bg.shape[0] < 1 or bg.shape[1] < 1:
        raise ValueError(f"background must be an (height, width, 3) image, got shape {np.shape(background)}")
    cap = np.ascontiguousarray(capture, np.float32)
    if cap.ndim != 3 or cap.shape[2] != 3 or cap.shape[0] != cap.shape[1] or cap.shape[0] < 1:
        raise ValueError(f"capture must be a square (n, n, 3) image, got shape {np.shape(capture)}")
    m = np.ascontiguousarray(mask, np.float32)
    if m.ndim != 3 or m.shape[2] != 4 or m.shape[0] != m.shape[1] or m.shape[0] < 1:
        raise ValueError(f"mask must be a square (n, n, 4) RGBA texture, got shape {np.shape(mask)}")
    sp = np.ascontiguousarray(np.asarray(sprites, np.float32).reshape(-1, 6))
    if len(sp) > MAX_COUNT:
        raise ValueError(f"sprites must hold at most {MAX_COUNT} sprites, got {len(sp)}")
    for name, a in (("background", bg), ("capture", cap), ("mask", m), ("sprites", sp)):
        if checked is not None and name != "sprites" and checked.get(name) is a:
            continue
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name} must be finite (no NaN or Inf)")
        if checked is not None and name != "sprites":
            checked[name] = a
    if len(sp) and not np.all(sp[:, 2] > 0):
        raise ValueError("sprites radius (column 2) must be > 0")
    if len(sp) and not np.all(sp[:, 3] >= sp[:, 2]):
        raise ValueError("sprites half_height (column 3) must be >= radius (column 2)")
    fv = Arg("fov_view", **_FOV).check(fov_view).item()
    fc = Arg("fov_capture", **_FOV_CAPTURE).check(fov_capture).item()
    if not isinstance(streaks, str) or streaks not in STREAKS:
        raise ValueError(f"streaks must be one of {', '.join(map(repr, STREAKS))}, got {streaks!r}")
    if filter not in FILTERS:
        raise ValueError(f"filter must be one of {', '.join(map(repr, FILTERS))}, got {filter!r}")
    op = Arg("opacity", lo=0.0, hi=1.0).check(opacity).item()
    return bg, cap, m, sp, float(fv), float(fc), STREAKS[streaks], FILTERS[filter], float(op)


#: The frame pass on the CPU: one thread per screen tile of TILE x TILE pixels that composites the tile's drops one
#: after the other (a drop's taps then follow each other in time and its mask column stays in cache: 3-4x faster
#: than a thread per pixel for 10 000 streaks); 24-64 px tiles measure the same, 32 keeps 240 tiles in a 640 x 360
#: frame for the worker bands. On a GPU a thread per pixel (TILE_PIXEL-px tiles: fewer sprite tests per pixel).
TILE = 32


TILE_PIXEL = 8


def _light_args(lights, positions, normals, sp, m):
    """(checked light values or None when they change nothing, positions (k, 3), normals (n, n, 3))."""
    if lights is None:
        return None, None, None
    if not isinstance(lights, dict):
        raise TypeError(f"lights must be a dict of ccl_particles_lights fields, got {type(lights).__name__}")
    v = check_lights(lights)
    if not lights_on(v):
        return None, None, None
    pos = np.ascontiguousarray(np.asarray(positions if positions is not None else np.zeros((0, 3)), np.float32))
    if pos.shape != (len(sp), 3) or not np.all(np.isfinite(pos)):
        raise ValueError(f"positions must be ({len(sp)}, 3) finite drop centres (one per sprite), got shape "
                         f"{pos.shape}")
    nrm = np.ascontiguousarray(np.asarray(normals if normals is not None else np.zeros((0, 0, 3)), np.float32))
    if nrm.shape != m.shape[:2] + (3,) or not np.all(np.isfinite(nrm)):
        raise ValueError(f"normals must be the mask's ({m.shape[0]}, {m.shape[1]}, 3) finite entry normals, got "
                         f"shape {nrm.shape}")
    return v, pos, nrm


def composite(background, capture, mask, sprites, fov_view, fov_capture=math.radians(150.0), streaks="off",
              filter="nearest", opacity=1.0, *, lights: dict | None = None, positions=None, normals=None,
              device=None, launcher=None, tile: int | None = None, cache: dict | None = None,
              per_tile: bool | None = None) -> np.ndarray:
    """rr-code-5.2.3 / rr-code-5.2.4 over a whole frame on the Warp device: ``background`` (H, W, 3), the ``capture``
    (n, n, 3), the drop ``mask`` (m, m, 4), ``sprites`` (k, 6) in compositing order (far first; columns
    :data:`pywarp.kernels.particles.SPRITE_FIELDS`). Returns the frame (H, W, 3) float32.

    The sprites are binned into ``tile`` x ``tile`` screen tiles (:func:`bin_sprites`); the frame starts as a copy of
    the background and only the tiles that hold a sprite are shaded, in TileLauncher bands of those tiles, so an empty
    frame costs a copy. ``per_tile`` (default: on the CPU) runs one thread per tile
    (:func:`pywarp.kernels.particles.composite_tile_kernel`, ``tile`` default :data:`TILE`), else one per pixel
    (:func:`pywarp.kernels.particles.composite_kernel`, default :data:`TILE_PIXEL`); every choice gives the same pixels,
    bit for bit. ``cache``: a dict the caller keeps between frames; unchanged background, capture and mask arrays (the
    same NumPy objects) are neither checked nor copied to the device again.

    ``lights``: the light-drop model (rr-A1..rr-CF, ``ccl_particles_shade_pixel_lit``) -- a dict of the fields of
    :data:`pywarp.kernels.particles.LIGHT_DEFAULTS`; then ``positions`` (k, 3) (each sprite's drop centre,
    camera-relative scene units) and ``normals`` (the mask's (m, m, 3) entry normals, ``pywarp.rain.drops.drop_mask(...,
    normals=True)``) are required. Lights that change nothing (no colour, ambient 1) skip the model: the unlit frame,
    bit for bit."""
    from ..core.runtime import launcher as shared_launcher

    checked = None if cache is None else cache.setdefault("checked", {})
    bg, cap, m, sp, fv, fc, st, filt, op = _composite_args(background, capture, mask, sprites, fov_view,
                                                           fov_capture, streaks, filter, opacity, checked)
    lv, pos, nrm = _light_args(lights, positions, normals, sp, m)
    lau = launcher or shared_launcher(device)
    dev = lau.device
    cpu = dev.startswith("cpu")
    per_tile = cpu if per_tile is None else bool(per_tile)
    tile = int(Arg("tile", lo=1, hi=256, dtype="int32").check((TILE if per_tile else TILE_PIXEL) if tile is None
                                                                else tile))
    h, w = bg.shape[:2]
    start, items, tiles_x = bin_sprites(sp, w, h, tile)
    active = np.nonzero(start[1:] > start[:-1])[0].astype(np.int32)
    if not len(active):
        return bg.copy()

    def on_device(a, dtype=float):
        # CPU: the NumPy memory itself (no copy); the caller keeps ``a`` alive until the launch returns
        return wp.array(a, dtype=dtype, device=dev, copy=not cpu)

    def cached(name, a):
        hit = None if cache is None else cache.get(name)
        if hit is not None and hit[0] is a and hit[1].device == wp.get_device(dev):
            return hit[1]
        flat = (pack_mask(a) if name == "mask" else pack_normals(a) if name == "normals"
                else a if name == "background" else a.reshape(-1))
        arr = on_device(flat)  # on the CPU the Warp array keeps the NumPy memory it aliases alive
        if cache is not None:
            cache[name] = (a, arr)
        return arr

    frame = bg.copy()
    out = on_device(frame)
    ratio = wp.empty(1, dtype=float, device=dev)
    wp.launch(uv_ratio_kernel, dim=1, inputs=[fv, fc], outputs=[ratio], device=dev)
    lau.launch(composite_tile_kernel if per_tile else composite_kernel, len(active), 1 if per_tile else tile * tile,
               [on_device(active, int), cached("background", bg), on_device(sp), on_device(start, int),
                on_device(items, int), tile, tiles_x, cached("mask", m), m.shape[0], cached("capture", cap),
                cap.shape[0], ratio, capture_scale(fc), filt, st, op, int(lv is not None),
                on_device(pos, wp.vec3) if lv is not None else wp.zeros(1, dtype=wp.vec3, device=dev),
                cached("normals", nrm) if lv is not None else wp.zeros(3, dtype=float, device=dev),
                light_params(**lv) if lv is not None else ParticlesLights()], [out])
    return frame if cpu else out.numpy()


def composite_pixels(background, capture, mask, sprites, xs, ys, fov_view, fov_capture=math.radians(150.0),
                     streaks="off", filter="nearest", opacity=1.0, *, lights: dict | None = None, positions=None,
                     normals=None, impl="warp", device=None) -> np.ndarray:
    """The composited colour at pixels (xs[k], ys[k]), every sprite tested (no tiles): (k, 3) float32.
    ``impl='c'``: ``ccl_particles_shade_pixel`` (the C reference), with ``lights`` (as :func:`composite`)
    ``ccl_particles_shade_pixel_lit``; the Warp form here has no lights (the frame kernel has)."""
    bg, cap, m, sp, fv, fc, st, filt, op = _composite_args(background, capture, mask, sprites, fov_view,
                                                           fov_capture, streaks, filter, opacity)
    lv, pos, nrm = _light_args(lights, positions, normals, sp, m)
    h, w = bg.shape[:2]
    xs = np.asarray(xs, np.int32).ravel()
    ys = np.asarray(ys, np.int32).ravel()
    if xs.shape != ys.shape:
        raise ValueError(f"xs and ys must have the same length, got {xs.shape} and {ys.shape}")
    if np.any((xs < 0) | (xs >= w)) or np.any((ys < 0) | (ys >= h)):
        raise ValueError(f"pixels must lie in the {w} x {h} image")
    scale = capture_scale(fc)
    if impl == "c":
        from ..core.binding import ffi, lib

        f, lb = ffi(), lib()
        spp = f.cast("ccl_particles_sprite *", f.from_buffer("float[]", sp)) if len(sp) else f.NULL
        mp = f.cast("const float *", f.from_buffer("float[]", m))
        cp = f.cast("const float *", f.from_buffer("float[]", cap))
        if lv is not None:
            pp = f.cast("ccl_vec3 *", f.from_buffer("float[]", pos)) if len(pos) else f.NULL
            np_ = f.cast("const float *", f.from_buffer("float[]", nrm))
            lc = c_lights(**lv)
        out = np.empty((len(xs), 3), np.float32)
        aspect = float(np.float32(w) / np.float32(h))
        for k, (x, y) in enumerate(zip(xs.tolist(), ys.tolist())):
            ndc = (float(np.float32(2.0) * ((np.float32(x) + np.float32(0.5)) / np.float32(w)) - np.float32(1.0)),
                   float(np.float32(1.0) - np.float32(2.0) * ((np.float32(y) + np.float32(0.5)) / np.float32(h))))
            p_o = lb.ccl_particles_capture_uv(ndc, aspect, fv, fc)
            if lv is None:
                c = lb.ccl_particles_shade_pixel(spp, len(sp), mp, m.shape[0], cp, cap.shape[0], x, y, p_o, scale,
                                                 filt, st, op, tuple(float(v) for v in bg[y, x]))
            else:
                c = lb.ccl_particles_shade_pixel_lit(spp, pp, len(sp), mp, np_, m.shape[0], cp, cap.shape[0], x, y,
                                                     p_o, scale, filt, st, op, lc, tuple(float(v) for v in bg[y, x]))
            out[k] = c.x, c.y, c.z
        return out
    if lv is not None:
        raise ValueError("lights: the per-pixel Warp form has none; use impl='c' or composite()")
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    from ..core.runtime import resolve_device

    dev = resolve_device(device)
    out = wp.zeros((len(xs), 3), dtype=float, device=dev)
    if len(xs):
        wp.launch(pixels_kernel, dim=len(xs),
                  inputs=[wp.array(bg, dtype=float, device=dev),
                          wp.array(sp if len(sp) else np.zeros((1, 6), np.float32), dtype=float, device=dev), len(sp),
                          wp.array(m.ravel(), dtype=float, device=dev), m.shape[0],
                          wp.array(cap.ravel(), dtype=float, device=dev), cap.shape[0], fv, fc, scale, filt, st, op,
                          wp.array(xs, dtype=int, device=dev), wp.array(ys, dtype=int, device=dev)],
                  outputs=[out], device=dev)
    return out.numpy()


def composite_warp(eq, device):
    # not element-wise: a whole frame (every pixel composites the drops whose billboard covers it)
    def particles_composite(background, capture, mask, sprites, fov_view, fov_capture=math.radians(150.0),
                            streaks="off", filter="nearest", opacity=1.0):
        return composite(background, capture, mask, sprites, fov_view, fov_capture, streaks, filter, opacity,
                         device=device)

    return particles_composite


def composite_c(eq):
    # not element-wise: the C reference shades every pixel of the frame (ccl_particles_composite)
    def particles_composite(background, capture, mask, sprites, fov_view, fov_capture=math.radians(150.0),
                            streaks="off", filter="nearest", opacity=1.0):
        from ..core.binding import ffi, lib, status_error

        bg, cap, m, sp, fv, fc, st, filt, op = _composite_args(background, capture, mask, sprites, fov_view,
                                                               fov_capture, streaks, filter, opacity)
        f = ffi()
        out = np.empty_like(bg)
        spp = f.cast("ccl_particles_sprite *", f.from_buffer("float[]", sp)) if len(sp) else f.NULL
        status_error(lib().ccl_particles_composite(
            f.from_buffer("float[]", bg), bg.shape[1], bg.shape[0], spp, len(sp), f.from_buffer("float[]", m),
            m.shape[0], f.from_buffer("float[]", cap), cap.shape[0], fv, fc, filt, st, op,
            f.from_buffer("float[]", out)), "ccl_particles_composite")
        return out

    return particles_composite
