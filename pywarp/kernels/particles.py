"""The rain particle system and the drop/streak compositing of the rr text -- Warp twins of ``cclouds/particles.h``.

* rr-code-5.2.2 (:func:`particles_simulate`): drops spawned in a box around the camera (uniform position, size
  ``Gauss(1, 1.3, 8)`` in our reading: the mean of 8 uniforms on 1.3 +- 0.5 mm), falling at their terminal speed
  (Table 2.2) / 4, regenerated below y = -1, one particle added per frame up to the requested count (the printed
  decrement as ``variant="thesis"``: no particle is ever created), removal when the count drops, wind as an
  extension. Every draw is the PCG hash of (seed, index, generation, draw): deterministic per seed on any thread count.
* rr-alg-3.2.3 (:func:`particles_streak`): retinal persistence -> streak length = fall speed x persistence time and
  the shader's tap offset.
* rr-alg-3.1.2 (:func:`particles_capture_uv`): where the wide-angle capture (viewer's pose, FOVy 150 deg) shows the
  direction seen through a view pixel (P_o of rr-alg-3.1.3).
* rr-code-5.2.3 / rr-code-5.2.4 (:func:`particles_composite`): the refraction and retinal-persistence fragment
  shaders, their defects fixed, as one compositing pass over a frame (drops binned into screen tiles; one thread per
  pixel composites the drops of its tile far to near: multi-core, deterministic).

Conventions are those of the C header (camera-relative scene units, y up; images row 0 at the top; mask RGBA with
(x, y, z) the refracted direction in the billboard frame -- x right, y up, z away from the viewer -- and a the inside
flag).
"""
from __future__ import annotations

import math

import numpy as np
import warp as wp

from ..core.cbridge import PARTICLES_PARAMS, c_constant, read
from ..core.registry import VARIANT, Arg, Option, declare
from . import VARIANT_CORRECTED
from .hash import hash_pcg, hash_unit
from .rain import rain_light_colour, rain_terminal_speed

MAX_SIZE_SAMPLES = 64  # CCL_PARTICLES_MAX_SIZE_SAMPLES
STREAK_TAPS = 7  # CCL_PARTICLES_STREAK_TAPS
MAX_COUNT = 1000000  # CCL_PARTICLES_MAX_COUNT
NEAREST = c_constant("CCL_PARTICLES_NEAREST", 0)  # ccl_particles_filter
LINEAR = c_constant("CCL_PARTICLES_LINEAR", 1)
FILTERS = {"nearest": NEAREST, "linear": LINEAR}
SPRITE_FIELDS = ("cx", "cy", "radius", "half_height", "tap_offset", "depth")  # ccl_particles_sprite
_U3 = wp.constant(wp.uint32(3))
_U1 = wp.constant(wp.uint32(1))


@wp.struct
class ParticlesParams:
    """Warp twin of ``ccl_particles_params`` (field by field; built by :mod:`pywarp.core.cbridge`)."""

    box_min: wp.vec3
    box_max: wp.vec3
    respawn_y: float
    size_mean_mm: float
    size_spread_mm: float
    size_samples: int
    slowdown: float
    metres_per_unit: float
    wind: wp.vec3
    seed: wp.uint32


# --- rr-code-5.2.2: the particle system ---------------------------------------------------------------------------------

@wp.func
def particles_uniform(seed: wp.uint32, index: wp.uint32, generation: wp.uint32, k: wp.uint32) -> float:
    """Draw k of a particle in its generation, as ``ccl_particles_uniform``: [0, 1)."""
    key = hash_pcg(hash_pcg(hash_pcg(seed) ^ index) ^ generation)
    return hash_unit(hash_pcg(key + k))


@wp.func
def particles_gauss(seed: wp.uint32, index: wp.uint32, generation: wp.uint32, mean: float, spread: float,
                    samples: int) -> float:
    """Gauss(spread, mean, samples): the mean of ``samples`` uniforms on mean +- spread/2 (``ccl_particles_gauss``)."""
    n = wp.min(wp.max(samples, 1), MAX_SIZE_SAMPLES)
    s = float(0.0)
    for k in range(n):
        s = s + particles_uniform(seed, index, generation, _U3 + wp.uint32(k))
    return mean + spread * (s / float(n) - 0.5)


@wp.func
def particles_spawn(p: ParticlesParams, index: wp.uint32, generation: wp.uint32, warm: int):
    """GenerateNewParticle, as ``ccl_particles_spawn``: (position, radius mm, speed units/s)."""
    ux = particles_uniform(p.seed, index, generation, wp.uint32(0))
    uy = particles_uniform(p.seed, index, generation, _U1)
    uz = particles_uniform(p.seed, index, generation, wp.uint32(2))
    y0 = p.box_min[1]
    if warm != 0:
        y0 = p.respawn_y
    r = particles_gauss(p.seed, index, generation, p.size_mean_mm, p.size_spread_mm, p.size_samples)
    pos = wp.vec3(p.box_min[0] + (p.box_max[0] - p.box_min[0]) * ux, y0 + (p.box_max[1] - y0) * uy,
                  p.box_min[2] + (p.box_max[2] - p.box_min[2]) * uz)
    speed = rain_terminal_speed(r, p.slowdown) / p.metres_per_unit
    return pos, r, speed


@wp.func
def _wrap(v: float, lo: float, hi: float) -> float:
    w = hi - lo
    out = v
    if out < lo:
        out = out + w
    if out >= hi:
        out = out - w
    return out


@wp.func
def particles_step(p: ParticlesParams, index: wp.uint32, dt: float, pos: wp.vec3, radius: float, speed: float,
                   generation: wp.uint32):
    """One frame of one particle, as ``ccl_particles_step``: (position, radius, speed, generation)."""
    q = pos
    r = radius
    v = speed
    g = generation
    if q[1] < p.respawn_y:
        g = g + _U1
        q, r, v = particles_spawn(p, index, g, 0)
    y = q[1] - dt * v
    x = _wrap(q[0] + dt * p.wind[0], p.box_min[0], p.box_max[0])
    z = _wrap(q[2] + dt * p.wind[2], p.box_min[2], p.box_max[2])
    return wp.vec3(x, y, z), r, v, g


@wp.kernel
def spawn_kernel(p: ParticlesParams, first: int, warm: int, pos: wp.array(dtype=wp.vec3),
                 radius: wp.array(dtype=float), speed: wp.array(dtype=float), generation: wp.array(dtype=wp.uint32)):
    """Spawn particles first + tid (generation 0)."""
    i = first + wp.tid()
    q, r, v = particles_spawn(p, wp.uint32(i), wp.uint32(0), warm)
    pos[i] = q
    radius[i] = r
    speed[i] = v
    generation[i] = wp.uint32(0)


@wp.kernel
def step_kernel(p: ParticlesParams, dt: float, pos: wp.array(dtype=wp.vec3), radius: wp.array(dtype=float),
                speed: wp.array(dtype=float), generation: wp.array(dtype=wp.uint32)):
    """One frame of every particle i < launch dim (``ccl_particles_step``)."""
    i = wp.tid()
    q, r, v, g = particles_step(p, wp.uint32(i), dt, pos[i], radius[i], speed[i], generation[i])
    pos[i] = q
    radius[i] = r
    speed[i] = v
    generation[i] = g


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


def _simulate_warp(eq, device):
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


def _simulate_c(eq):
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


@wp.func
def particles_simulate_frame(p: ParticlesParams, index: wp.uint32, dt: float, pos: wp.vec3, radius: float,
                             speed: float, generation: wp.uint32):
    """The per-particle body of SimulateParticleSystem (the registered twin of rr-code-5.2.2; see
    :class:`ParticleSystem` for the whole system)."""
    return particles_step(p, index, dt, pos, radius, speed, generation)


declare("rr-code-5.2.2", c="ccl_particles_simulate", name="particles_simulate",
        make_warp=_simulate_warp, make_c=_simulate_c,
        summary="particles_simulate(frames, requested, dt=1/60, capacity=None, warm=False, variant='corrected', "
                "**params) -> {pos, radius_mm, speed, generation, count}: SimulateParticleSystem run for `frames` "
                "frames. Spawn box X [-1, 1], Y [1, 1.25], Z [-1.5, 1.5] (camera-relative), regeneration below "
                "y = -1, radius Gauss(1, 1.3, 8) read as the mean of 8 uniforms on 1.3 +- 0.5 mm, speed = Table 2.2 / "
                "4, y -= dt speed. variant='corrected' adds one particle per frame up to `requested` and removes the "
                "surplus when it drops; 'thesis' keeps the printed decrement (count = -frames, no particle). "
                "params: fields of ccl_particles_params (wind = horizontal drift, our extension).",
        references=("Rousseau, Jolivet & Ghazanfarpour, Realistic real-time rain rendering, Computers & Graphics 30, "
                    "2006",))(particles_simulate_frame)


# --- rr-alg-3.2.3: retinal persistence -> streaks ---------------------------------------------------------------------

@declare("rr-alg-3.2.3", c="ccl_particles_streak",
         args=(Arg("speed", "fall speed of the drop (scene units per second)", lo=0.0, sample_range=(0.0, 10.0)),
               Arg("persistence_s", "fade time of the retinal image (s); the text: 0.06 - 0.09", lo=0.0, hi=1.0),
               Arg("radius", "billboard radius of the drop (scene units)", lo=0.0, lo_open=True,
                   sample_range=(1e-3, 1.0))),
         outputs=("length", "tap_offset"),
         summary="Streak of a falling drop: length L = speed persistence_s (the fall while the retinal image fades; "
                 "the particle becomes a streak billboard 2 radius wide and 2 radius + L tall, the mask stretched over "
                 "it) and the tap offset (texelOffset) of rr-code-5.2.4, (L / 6) / (2 radius + L) in mask units, so "
                 "that the 7 taps (i = -3 .. 3) span the whole fall.",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §3.5.3 (retinal persistence)",))
@wp.func
def particles_streak(speed: float, persistence_s: float, radius: float) -> tuple[float, float]:
    length = speed * persistence_s
    return length, (length / 6.0) / (2.0 * radius + length)


def particles_streak_np(speed, persistence_s, radius):
    """:func:`particles_streak` on NumPy arrays (the same float32 operations), for the per-frame vertex stage."""
    sp = np.asarray(speed, np.float32)
    length = sp * np.float32(persistence_s)
    return length, (length / np.float32(6.0)) / (np.float32(2.0) * np.asarray(radius, np.float32) + length)


# --- rr-alg-3.1.2: the capture lookup ---------------------------------------------------------------------------------

_FOV = dict(lo=0.0, hi=float(np.float32(math.pi)), lo_open=True, hi_open=True)


@declare("rr-alg-3.1.2", c="ccl_particles_capture_uv",
         args=(Arg("ndc", "normalised device coordinates of the point in the view, (-1, -1) bottom-left",
                   sample_range=(-1.0, 1.0)),
               Arg("aspect", "view width / height", lo=0.0, lo_open=True, sample_range=(0.25, 4.0)),
               Arg("fov_view", "vertical field of view of the view camera (rad)", **_FOV, sample_range=(0.1, 2.5)),
               Arg("fov_capture", "vertical field of view of the square capture (rad); the text: 150 deg",
                   **_FOV, sample_range=(1.0, 3.0))),
         outputs=("uv",),
         summary="The capture camera (viewer's position and orientation, perspective, FOVy 150 deg, 512 x 512): "
                 "texture coordinates (u, v; v = 0 the top row) of the direction seen through a view point -- P_o of "
                 "rr-alg-3.1.3. u = 0.5 + 0.5 ndc.x aspect t, v = 0.5 - 0.5 ndc.y t, t = tan(fov_view/2) / "
                 "tan(fov_capture/2). The capture itself is a render of the background scene with that camera "
                 "(pywarp.rain.capture).",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §4.1",))
@wp.func
def particles_capture_uv(ndc: wp.vec2, aspect: float, fov_view: float, fov_capture: float) -> wp.vec2:
    ratio = wp.tan(0.5 * fov_view) / wp.tan(0.5 * fov_capture)
    return wp.vec2(0.5 + 0.5 * (ndc[0] * aspect * ratio), 0.5 - 0.5 * (ndc[1] * ratio))


# --- rr-code-5.2.3 / rr-code-5.2.4: the fragment shaders ----------------------------------------------------------------

@wp.func
def _texel(img: wp.array(dtype=float), size: int, x: int, y: int) -> wp.vec3:
    i = 3 * (wp.clamp(y, 0, size - 1) * size + wp.clamp(x, 0, size - 1))
    return wp.vec3(img[i], img[i + 1], img[i + 2])


@wp.func
def particles_fetch(img: wp.array(dtype=float), size: int, u: float, v: float, filt: int) -> wp.vec3:
    """Capture fetch at (u, v), clamped to the edge: nearest (0) or bilinear (1), as the C ``fetch``."""
    if filt == LINEAR:
        fx = u * float(size) - 0.5
        fy = v * float(size) - 0.5
        x0f = wp.floor(fx)
        y0f = wp.floor(fy)
        ax = fx - x0f
        ay = fy - y0f
        x0 = int(x0f)
        y0 = int(y0f)
        a = _texel(img, size, x0, y0)
        b = _texel(img, size, x0 + 1, y0)
        c = _texel(img, size, x0, y0 + 1)
        d = _texel(img, size, x0 + 1, y0 + 1)
        top = wp.vec3(a[0] + (b[0] - a[0]) * ax, a[1] + (b[1] - a[1]) * ax, a[2] + (b[2] - a[2]) * ax)
        bot = wp.vec3(c[0] + (d[0] - c[0]) * ax, c[1] + (d[1] - c[1]) * ax, c[2] + (d[2] - c[2]) * ax)
        return wp.vec3(top[0] + (bot[0] - top[0]) * ay, top[1] + (bot[1] - top[1]) * ay,
                       top[2] + (bot[2] - top[2]) * ay)
    return _texel(img, size, int(wp.floor(u * float(size))), int(wp.floor(v * float(size))))


@wp.func
def particles_tap(mask: wp.array(dtype=float), mask_size: int, capture: wp.array(dtype=float), capture_size: int,
                  mask_u: float, mask_v: float, p_o: wp.vec2, scale: float, filt: int):
    """One tap of the refraction shader, as ``ccl_particles_tap``: (hit 0/1, rgb)."""
    rgb = wp.vec3(0.0, 0.0, 0.0)
    hit = int(0)
    if mask_u >= 0.0 and mask_u < 1.0 and mask_v >= 0.0 and mask_v < 1.0:
        mx = wp.clamp(int(mask_u * float(mask_size)), 0, mask_size - 1)
        my = wp.clamp(int(mask_v * float(mask_size)), 0, mask_size - 1)
        m = 4 * (my * mask_size + mx)
        if mask[m + 3] > 0.0 and mask[m + 2] > 0.0:
            uc = p_o[0] + scale * (mask[m] / mask[m + 2])
            vc = p_o[1] - scale * (mask[m + 1] / mask[m + 2])
            rgb = particles_fetch(capture, capture_size, uc, vc, filt)
            hit = 1
    return hit, rgb


@wp.func
def particles_shade_sprite(c: wp.vec3, sprites: wp.array2d(dtype=float), j: int, mask: wp.array(dtype=float),
                           mask_size: int, capture: wp.array(dtype=float), capture_size: int, px: float, py: float,
                           p_o: wp.vec2, scale: float, filt: int, streaks: int, opacity: float) -> wp.vec3:
    """Sprite j composited over colour c at pixel centre (px, py) (the loop body of ``ccl_particles_shade_pixel``)."""
    dx = px - sprites[j, 0]
    dy = py - sprites[j, 1]
    radius = sprites[j, 2]
    out = c
    if wp.abs(dx) < radius and wp.abs(dy) < sprites[j, 3]:
        mu = dx / (2.0 * radius) + 0.5
        mv = dy / (2.0 * sprites[j, 3]) + 0.5
        lo = int(0)
        hi = int(0)
        if streaks != 0:
            lo = -(STREAK_TAPS // 2)
            hi = STREAK_TAPS // 2
        s = wp.vec3(0.0, 0.0, 0.0)
        hits = int(0)
        for i in range(lo, hi + 1):
            h, rgb = particles_tap(mask, mask_size, capture, capture_size, mu, mv - float(i) * sprites[j, 4], p_o,
                                   scale, filt)
            if h != 0:
                s = wp.vec3(s[0] + rgb[0], s[1] + rgb[1], s[2] + rgb[2])
                hits = hits + 1
        if hits > 0:
            alpha = opacity
            if streaks != 0:
                alpha = opacity * (float(hits) / float(STREAK_TAPS))
            out = wp.vec3(c[0] + (s[0] / float(hits) - c[0]) * alpha, c[1] + (s[1] / float(hits) - c[1]) * alpha,
                          c[2] + (s[2] / float(hits) - c[2]) * alpha)
    return out


# --- the light-drop model in the compositing pass (rr-A1..rr-A3, rr-CF; the text never implemented it) --------------

@wp.struct
class ParticlesLights:
    """Warp twin of ``ccl_particles_lights`` (field by field; see :func:`light_params`)."""

    l1: wp.vec3
    c_l1: wp.vec3
    l2: wp.vec3
    c_l2: wp.vec3
    ambient: wp.vec3
    r_half: float
    variant: int
    right: wp.vec3
    up: wp.vec3
    forward: wp.vec3


#: Lights of the compositing pass (``ccl_particles_lights``): positions in camera-relative scene units (y up, the eye
#: at the origin), colours RGB (0 = off), the view basis that turns mask normals into that frame. Off by default:
#: the text's application has no lights (rr-A1..rr-CF are its "possible future extension").
LIGHT_DEFAULTS = dict(l1=(0.0, 0.0, 0.0), c_l1=(0.0, 0.0, 0.0), l2=(0.0, 0.0, 0.0), c_l2=(0.0, 0.0, 0.0),
                      ambient=(1.0, 1.0, 1.0), r_half=1.0, variant="corrected", right=(1.0, 0.0, 0.0),
                      up=(0.0, 1.0, 0.0), forward=(0.0, 0.0, -1.0))


def check_lights(values: dict) -> dict:
    """``values`` (fields of :data:`LIGHT_DEFAULTS`, missing ones defaulted) checked; ValueError naming the field."""
    unknown = set(values) - set(LIGHT_DEFAULTS)
    if unknown:
        raise ValueError(f"unknown light parameter(s) {sorted(unknown)}; known: {sorted(LIGHT_DEFAULTS)}")
    v = {**LIGHT_DEFAULTS, **values}
    for name in ("l1", "c_l1", "l2", "c_l2", "ambient", "right", "up", "forward"):
        a = np.asarray(v[name], np.float64)
        if a.shape != (3,) or not np.all(np.isfinite(a)) or np.any(np.abs(a) > 1e30):
            raise ValueError(f"{name} must be 3 finite numbers, got {v[name]!r}")
        if name in ("c_l1", "c_l2", "ambient") and np.any(a < 0):
            raise ValueError(f"{name} must be >= 0 per channel, got {v[name]!r}")
        if name in ("right", "up", "forward") and abs(np.linalg.norm(a) - 1.0) > 1e-3:
            raise ValueError(f"{name} must be a unit vector, got {v[name]!r}")
        v[name] = tuple(float(x) for x in a)
    r = v["r_half"]
    if isinstance(r, bool) or not isinstance(r, (int, float, np.integer, np.floating)) or not (
            math.isfinite(r) and 0.0 < r <= 1e30):
        raise ValueError(f"r_half must be > 0, got {r!r}")
    v["r_half"] = float(r)
    var = v["variant"]
    v["variant"] = var if isinstance(var, int) and not isinstance(var, bool) and var in (0, 1) else \
        VARIANT.check(var)  # idempotent: a checked dict (variant 0/1) passes again
    return v


def lights_on(v: dict) -> bool:
    """Whether checked light values change any colour (a light with a colour, or an ambient other than 1)."""
    return any(v["c_l1"]) or any(v["c_l2"]) or tuple(v["ambient"]) != (1.0, 1.0, 1.0)


def light_params(**values) -> ParticlesLights:
    """A checked :class:`ParticlesLights`."""
    v = check_lights(values)
    L = ParticlesLights()
    for k in ("l1", "c_l1", "l2", "c_l2", "ambient", "right", "up", "forward"):
        setattr(L, k, wp.vec3(*v[k]))
    L.r_half = v["r_half"]
    L.variant = int(v["variant"])
    return L


def c_lights(**values):
    """The same lights as a cffi ``ccl_particles_lights *``."""
    from ..core.binding import ffi

    v = check_lights(values)
    c = ffi().new("ccl_particles_lights *")
    for k in ("l1", "c_l1", "l2", "c_l2", "ambient", "right", "up", "forward"):
        vec = getattr(c, k)
        vec.x, vec.y, vec.z = v[k]
    c.r_half = v["r_half"]
    c.variant = int(v["variant"])
    return c


@wp.func
def _light_tap(L: ParticlesLights, p: wp.vec3, normals: wp.array(dtype=float), t: int, c_o: wp.vec3) -> wp.vec3:
    """C_F of one tap (``light_tap`` of particles.c): the texel's entry normal (packed, :func:`pack_normals`) turned
    into the scene frame, then rr-CF with the eye at the origin."""
    nx = normals[3 * t]
    ny = normals[3 * t + 1]
    nz = normals[3 * t + 2]
    n = wp.vec3(nx * L.right[0] + ny * L.up[0] + nz * L.forward[0],
                nx * L.right[1] + ny * L.up[1] + nz * L.forward[1],
                nx * L.right[2] + ny * L.up[2] + nz * L.forward[2])
    return rain_light_colour(c_o, L.ambient, p, n, wp.vec3(0.0, 0.0, 0.0), L.l1, L.c_l1, L.l2, L.c_l2, L.r_half,
                             L.variant)


@wp.func
def _tap_packed(offsets: wp.array(dtype=float), mask_size: int, capture: wp.array(dtype=float), capture_size: int,
                mask_u: float, mask_v: float, p_o: wp.vec2, scale: float, filt: int):
    """:func:`particles_tap` on the packed mask of :func:`pack_mask` (the same values, x/z and y/z read instead of
    divided; NaN where the texel has no ray)."""
    rgb = wp.vec3(0.0, 0.0, 0.0)
    hit = int(0)
    t = int(0)
    if mask_u >= 0.0 and mask_u < 1.0 and mask_v >= 0.0 and mask_v < 1.0:
        mx = wp.clamp(int(mask_u * float(mask_size)), 0, mask_size - 1)
        my = wp.clamp(int(mask_v * float(mask_size)), 0, mask_size - 1)
        t = mx * mask_size + my
        qx = offsets[2 * t]
        if qx == qx:
            uc = p_o[0] + scale * qx
            vc = p_o[1] - scale * offsets[2 * t + 1]
            rgb = particles_fetch(capture, capture_size, uc, vc, filt)
            hit = 1
    return hit, rgb, t


@wp.func
def _shade_sprite_packed(c: wp.vec3, sprites: wp.array2d(dtype=float), j: int, offsets: wp.array(dtype=float),
                         mask_size: int, capture: wp.array(dtype=float), capture_size: int, px: float, py: float,
                         p_o: wp.vec2, scale: float, filt: int, streaks: int, opacity: float, lit: int,
                         positions: wp.array(dtype=wp.vec3), normals: wp.array(dtype=float),
                         L: ParticlesLights) -> wp.vec3:
    """:func:`particles_shade_sprite` with :func:`_tap_packed` (the frame kernel's form; the same operations); with
    ``lit`` every hit's colour goes through :func:`_light_tap` (``ccl_particles_shade_pixel_lit``)."""
    dx = px - sprites[j, 0]
    dy = py - sprites[j, 1]
    radius = sprites[j, 2]
    out = c
    if wp.abs(dx) < radius and wp.abs(dy) < sprites[j, 3]:
        mu = dx / (2.0 * radius) + 0.5
        mv = dy / (2.0 * sprites[j, 3]) + 0.5
        lo = int(0)
        hi = int(0)
        if streaks != 0:
            lo = -(STREAK_TAPS // 2)
            hi = STREAK_TAPS // 2
        s = wp.vec3(0.0, 0.0, 0.0)
        hits = int(0)
        for i in range(lo, hi + 1):
            h, rgb, t = _tap_packed(offsets, mask_size, capture, capture_size, mu, mv - float(i) * sprites[j, 4],
                                    p_o, scale, filt)
            if h != 0 and lit != 0:
                rgb = _light_tap(L, positions[j], normals, t, rgb)
            if h != 0:
                s = wp.vec3(s[0] + rgb[0], s[1] + rgb[1], s[2] + rgb[2])
                hits = hits + 1
        if hits > 0:
            alpha = opacity
            if streaks != 0:
                alpha = opacity * (float(hits) / float(STREAK_TAPS))
            out = wp.vec3(c[0] + (s[0] / float(hits) - c[0]) * alpha, c[1] + (s[1] / float(hits) - c[1]) * alpha,
                          c[2] + (s[2] / float(hits) - c[2]) * alpha)
    return out


def pack_mask(mask: np.ndarray) -> np.ndarray:
    """The refraction mask (n, n, 4) as the frame kernel reads it: per texel (x / z, y / z) in float32 (the quotients
    the shader forms), NaN where the texel is outside the drop or has no ray (a <= 0 or z <= 0), stored COLUMN-major
    (texel (row my, column mx) at 2 (mx n + my)): a streak's taps walk down one mask column, so they share cache lines
    (the row-major RGBA mask made every tap a cache miss). Half the memory, no division per tap, the same values."""
    m = np.asarray(mask, np.float32)
    ok = (m[..., 3] > 0) & (m[..., 2] > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.stack([np.where(ok, m[..., 0] / m[..., 2], np.float32(np.nan)),
                      np.where(ok, m[..., 1] / m[..., 2], np.float32(np.nan))], -1).astype(np.float32)
    return np.ascontiguousarray(q.transpose(1, 0, 2)).reshape(-1)


def pack_normals(normals: np.ndarray) -> np.ndarray:
    """The mask's entry normals (n, n, 3) column-major like :func:`pack_mask` (texel (my, mx) at 3 (mx n + my))."""
    return np.ascontiguousarray(np.asarray(normals, np.float32).transpose(1, 0, 2)).reshape(-1)


@wp.func
def particles_pixel_uv(x: int, y: int, width: int, height: int, fov_view: float, fov_capture: float) -> wp.vec2:
    """P_o of pixel (x, y): its centre's NDC through :func:`particles_capture_uv`."""
    ndc = wp.vec2(2.0 * ((float(x) + 0.5) / float(width)) - 1.0, 1.0 - 2.0 * ((float(y) + 0.5) / float(height)))
    return particles_capture_uv(ndc, float(width) / float(height), fov_view, fov_capture)


@wp.func
def particles_uv_ratio(fov_view: float, fov_capture: float) -> float:
    """tan(fov_view/2) / tan(fov_capture/2): the factor of :func:`particles_capture_uv`, the same float32 operations."""
    return wp.tan(0.5 * fov_view) / wp.tan(0.5 * fov_capture)


@wp.kernel
def uv_ratio_kernel(fov_view: float, fov_capture: float, out: wp.array(dtype=float)):
    """The frame's capture ratio, once (the pixels then need no tangent: 2 tan per pixel were a third of an empty
    frame's time)."""
    out[0] = particles_uv_ratio(fov_view, fov_capture)


@wp.kernel
def composite_kernel(row0: int, active: wp.array(dtype=int), background: wp.array3d(dtype=float),
                     sprites: wp.array2d(dtype=float), tile_start: wp.array(dtype=int), tile_items: wp.array(dtype=int),
                     tile: int, tiles_x: int, offsets: wp.array(dtype=float), mask_size: int,
                     capture: wp.array(dtype=float), capture_size: int, ratio: wp.array(dtype=float), scale: float,
                     filt: int, streaks: int, opacity: float, lit: int, positions: wp.array(dtype=wp.vec3),
                     normals: wp.array(dtype=float), L: ParticlesLights, out: wp.array3d(dtype=float)):
    """The rain frame over the screen tiles that hold sprites (TileLauncher bands of ``active``, one thread per pixel
    of a tile; ``out`` holds the background already, the other tiles are not touched): per pixel, the background then
    the sprites of its tile, far to near (rr-code-5.2.3 / rr-code-5.2.4). The same operations as
    ``ccl_particles_shade_pixel`` with P_o of ``ccl_particles_capture_uv`` (its ratio computed once per frame by
    :func:`uv_ratio_kernel` with the same expression)."""
    i, k = wp.tid()
    t = active[row0 + i]
    x = (t % tiles_x) * tile + k % tile
    y = (t // tiles_x) * tile + k // tile
    h = background.shape[0]
    w = background.shape[1]
    if x < w and y < h:
        c = wp.vec3(background[y, x, 0], background[y, x, 1], background[y, x, 2])
        ndc = wp.vec2(2.0 * ((float(x) + 0.5) / float(w)) - 1.0, 1.0 - 2.0 * ((float(y) + 0.5) / float(h)))
        aspect = float(w) / float(h)
        r = ratio[0]
        p_o = wp.vec2(0.5 + 0.5 * (ndc[0] * aspect * r), 0.5 - 0.5 * (ndc[1] * r))
        px = float(x) + 0.5
        py = float(y) + 0.5
        for j in range(tile_start[t], tile_start[t + 1]):
            c = _shade_sprite_packed(c, sprites, tile_items[j], offsets, mask_size, capture, capture_size, px, py,
                                     p_o, scale, filt, streaks, opacity, lit, positions, normals, L)
        out[y, x, 0] = c[0]
        out[y, x, 1] = c[1]
        out[y, x, 2] = c[2]


@wp.kernel
def composite_tile_kernel(row0: int, active: wp.array(dtype=int), background: wp.array3d(dtype=float),
                          sprites: wp.array2d(dtype=float), tile_start: wp.array(dtype=int),
                          tile_items: wp.array(dtype=int), tile: int, tiles_x: int, offsets: wp.array(dtype=float),
                          mask_size: int, capture: wp.array(dtype=float), capture_size: int,
                          ratio: wp.array(dtype=float), scale: float, filt: int, streaks: int, opacity: float,
                          lit: int, positions: wp.array(dtype=wp.vec3), normals: wp.array(dtype=float),
                          L: ParticlesLights, out: wp.array3d(dtype=float)):
    """The rain frame, one thread per screen tile that holds sprites (TileLauncher bands of ``active``; ``out`` holds
    the background already): the tile's sprites far to near, each composited over the pixels of the tile its box
    covers (``out`` is the running colour). Per pixel the same operations in the same order as
    :func:`composite_kernel` and ``ccl_particles_shade_pixel``; sprite by sprite, the taps of one drop follow each
    other, so its mask column stays in cache."""
    i, _z = wp.tid()
    t = active[row0 + i]
    h = background.shape[0]
    w = background.shape[1]
    x0 = (t % tiles_x) * tile
    y0 = (t // tiles_x) * tile
    x1 = wp.min(x0 + tile, w) - 1
    y1 = wp.min(y0 + tile, h) - 1
    aspect = float(w) / float(h)
    r = ratio[0]
    for k in range(tile_start[t], tile_start[t + 1]):
        j = tile_items[k]
        # the pixels whose centre may lie in the box (the exact test is the shader's)
        xa = wp.max(x0, int(wp.floor(sprites[j, 0] - sprites[j, 2])) - 1)
        xb = wp.min(x1, int(wp.floor(sprites[j, 0] + sprites[j, 2])) + 1)
        ya = wp.max(y0, int(wp.floor(sprites[j, 1] - sprites[j, 3])) - 1)
        yb = wp.min(y1, int(wp.floor(sprites[j, 1] + sprites[j, 3])) + 1)
        for x in range(xa, xb + 1):  # down the columns: the mask is column-major
            for y in range(ya, yb + 1):
                ndc = wp.vec2(2.0 * ((float(x) + 0.5) / float(w)) - 1.0, 1.0 - 2.0 * ((float(y) + 0.5) / float(h)))
                p_o = wp.vec2(0.5 + 0.5 * (ndc[0] * aspect * r), 0.5 - 0.5 * (ndc[1] * r))
                c = wp.vec3(out[y, x, 0], out[y, x, 1], out[y, x, 2])
                c = _shade_sprite_packed(c, sprites, j, offsets, mask_size, capture, capture_size, float(x) + 0.5,
                                         float(y) + 0.5, p_o, scale, filt, streaks, opacity, lit, positions, normals,
                                         L)
                out[y, x, 0] = c[0]
                out[y, x, 1] = c[1]
                out[y, x, 2] = c[2]


@wp.kernel
def pixels_kernel(background: wp.array3d(dtype=float), sprites: wp.array2d(dtype=float), n: int,
                  mask: wp.array(dtype=float), mask_size: int, capture: wp.array(dtype=float), capture_size: int,
                  fov_view: float, fov_capture: float, scale: float, filt: int, streaks: int, opacity: float,
                  xs: wp.array(dtype=int), ys: wp.array(dtype=int), out: wp.array2d(dtype=float)):
    """Chosen pixels with every sprite tested (no tiles): the per-pixel twin of ``ccl_particles_shade_pixel``."""
    k = wp.tid()
    x = xs[k]
    y = ys[k]
    h = background.shape[0]
    w = background.shape[1]
    c = wp.vec3(background[y, x, 0], background[y, x, 1], background[y, x, 2])
    p_o = particles_pixel_uv(x, y, w, h, fov_view, fov_capture)
    for j in range(n):
        c = particles_shade_sprite(c, sprites, j, mask, mask_size, capture, capture_size, float(x) + 0.5,
                                   float(y) + 0.5, p_o, scale, filt, streaks, opacity)
    out[k, 0] = c[0]
    out[k, 1] = c[1]
    out[k, 2] = c[2]


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
    fc = Arg("fov_capture", **_FOV).check(fov_capture).item()
    if not isinstance(streaks, (bool, np.bool_)):
        raise TypeError(f"streaks must be True or False, got {streaks!r}")
    if filter not in FILTERS:
        raise ValueError(f"filter must be one of {', '.join(map(repr, FILTERS))}, got {filter!r}")
    op = Arg("opacity", lo=0.0, hi=1.0).check(opacity).item()
    return bg, cap, m, sp, float(fv), float(fc), int(bool(streaks)), FILTERS[filter], float(op)


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


def composite(background, capture, mask, sprites, fov_view, fov_capture=math.radians(150.0), streaks=False,
              filter="nearest", opacity=1.0, *, lights: dict | None = None, positions=None, normals=None,
              device=None, launcher=None, tile: int | None = None, cache: dict | None = None,
              per_tile: bool | None = None) -> np.ndarray:
    """rr-code-5.2.3 / rr-code-5.2.4 over a whole frame on the Warp device: ``background`` (H, W, 3), the ``capture``
    (n, n, 3), the drop ``mask`` (m, m, 4), ``sprites`` (k, 6) in compositing order (far first; columns
    :data:`SPRITE_FIELDS`). Returns the frame (H, W, 3) float32.

    The sprites are binned into ``tile`` x ``tile`` screen tiles (:func:`bin_sprites`); the frame starts as a copy
    of the background and only the tiles that hold a sprite are shaded, in TileLauncher bands of those tiles, so an
    empty frame costs a copy. ``per_tile`` (default: on the CPU) runs one thread per tile
    (:func:`composite_tile_kernel`, ``tile`` default :data:`TILE`), else one per pixel (:func:`composite_kernel`,
    default :data:`TILE_PIXEL`); every choice gives the same pixels, bit for bit. ``cache``: a dict the caller keeps between frames; unchanged
    background, capture and mask arrays (the same NumPy objects) are neither checked nor copied to the device again.

    ``lights``: the light-drop model (rr-A1..rr-CF, ``ccl_particles_shade_pixel_lit``) -- a dict of the fields of
    :data:`LIGHT_DEFAULTS`; then ``positions`` (k, 3) (each sprite's drop centre, camera-relative scene units) and
    ``normals`` (the mask's (m, m, 3) entry normals, ``pywarp.kernels.rain.drop_mask(..., normals=True)``) are
    required. Lights that change nothing (no colour, ambient 1) skip the model: the unlit frame, bit for bit."""
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
                     streaks=False, filter="nearest", opacity=1.0, *, lights: dict | None = None, positions=None,
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


def _composite_warp(eq, device):
    # not element-wise: a whole frame (every pixel composites the drops whose billboard covers it)
    def particles_composite(background, capture, mask, sprites, fov_view, fov_capture=math.radians(150.0),
                            streaks=False, filter="nearest", opacity=1.0):
        return composite(background, capture, mask, sprites, fov_view, fov_capture, streaks, filter, opacity,
                         device=device)

    return particles_composite


def _composite_c(eq):
    # not element-wise: the C reference shades every pixel of the frame (ccl_particles_composite)
    def particles_composite(background, capture, mask, sprites, fov_view, fov_capture=math.radians(150.0),
                            streaks=False, filter="nearest", opacity=1.0):
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


declare("rr-code-5.2.3", "rr-code-5.2.4", c="ccl_particles_composite", name="particles_composite",
        make_warp=_composite_warp, make_c=_composite_c,
        summary="particles_composite(background, capture, mask, sprites, fov_view, fov_capture=150 deg, "
                "streaks=False, filter='nearest', opacity=1) -> frame: the refraction fragment shader (rr-code-5.2.3) "
                "on every drop billboard, or with streaks=True the retinal-persistence shader (rr-code-5.2.4: 7 mask "
                "taps i = -3 .. 3 shifted by i tap_offset, averaged, alpha reduced to the share of taps that hit), "
                "composited far to near over the background. Per tap: the mask texel (inside flag a, refraction "
                "vector xyz), P_o = the pixel's capture coordinate (rr-alg-3.1.2), P_c = P_o + (x, -y) / z * 0.5 / "
                "tan(fov_capture/2), the capture at P_c. The listings' defects (undeclared count, extra brace, no "
                "output, int*float, no averaging or alpha) are fixed.",
        references=("Rousseau, Jolivet & Ghazanfarpour 2006, §4 (refraction), §3.5.3 (retinal persistence)",))(
    particles_shade_sprite)


__all__ = ["ParticlesParams", "ParticleSystem", "composite",
           "ParticlesLights", "LIGHT_DEFAULTS", "check_lights", "lights_on", "light_params", "c_lights", "pack_mask",
           "pack_normals", "TILE", "TILE_PIXEL",
           "composite_pixels", "bin_sprites", "capture_scale", "FILTERS", "SPRITE_FIELDS", "STREAK_TAPS"]
