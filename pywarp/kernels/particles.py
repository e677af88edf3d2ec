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

from ..core.cbridge import c_constant
from ..core.registry import VARIANT, Arg, declare
from .common import bound_cell
from .hash import hash_pcg, hash_unit
from .rain import rain_light_colour, rain_terminal_speed

MAX_SIZE_SAMPLES = 64  # CCL_PARTICLES_MAX_SIZE_SAMPLES
STREAK_TAPS = 7  # CCL_PARTICLES_STREAK_TAPS
STREAK_SAMPLES = 8  # CCL_PARTICLES_STREAK_SAMPLES
MIN_STREAK_PX = 0.015625  # CCL_PARTICLES_MIN_STREAK_PX
DROPS = c_constant("CCL_PARTICLES_DROPS", 0)  # ccl_particles_streaks
STREAKS_THESIS = c_constant("CCL_PARTICLES_STREAKS_THESIS", 1)
STREAKS_PHYSICAL = c_constant("CCL_PARTICLES_STREAKS_PHYSICAL", 2)
#: the ``streaks`` argument of the compositing pass by name
STREAKS = {"off": 0, "thesis": 1, "physical": 2}
_TWO_PI = wp.constant(2.0 * math.pi)  # 2.0f * CCL_PI_F
MAX_COUNT = 1000000  # CCL_PARTICLES_MAX_COUNT
NEAREST = c_constant("CCL_PARTICLES_NEAREST", 0)  # ccl_particles_filter
LINEAR = c_constant("CCL_PARTICLES_LINEAR", 1)
FILTERS = {"nearest": NEAREST, "linear": LINEAR}
SPRITE_FIELDS = ("cx", "cy", "radius", "half_height", "tap_offset", "depth")  # ccl_particles_sprite
_U3 = wp.constant(wp.uint32(3))
_U1 = wp.constant(wp.uint32(1))


# CCL_PARTICLES_MAX_EXTENT, CCL_PARTICLES_MIN_METRES_PER_UNIT (checked by ccl_particles_params_check): a larger box
# makes its widths overflow, a smaller scene unit the fall speed
MAX_EXTENT = 1048576.0
MIN_METRES_PER_UNIT = 0.0009765625


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


@wp.func
def particles_simulate_frame(p: ParticlesParams, index: wp.uint32, dt: float, pos: wp.vec3, radius: float,
                             speed: float, generation: wp.uint32):
    """The per-particle body of SimulateParticleSystem (the registered twin of rr-code-5.2.2; see
    :class:`pywarp.rain.particles.ParticleSystem` for the whole system)."""
    return particles_step(p, index, dt, pos, radius, speed, generation)


declare("rr-code-5.2.2", c="ccl_particles_simulate", name="particles_simulate",
        make_warp="pywarp.rain.particles:simulate_warp", make_c="pywarp.rain.particles:simulate_c",
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


# --- rr-alg-3.1.2: the capture lookup ---------------------------------------------------------------------------------

_FOV = dict(lo=0.0, hi=float(np.float32(math.pi)), lo_open=True, hi_open=True)
# CCL_PARTICLES_MIN_FOV_CAPTURE: a narrower capture makes tan(fov_capture/2) underflow and the coordinates overflow
MIN_FOV_CAPTURE = 0.015625
_FOV_CAPTURE = dict(_FOV, lo=MIN_FOV_CAPTURE, lo_open=False)


@declare("rr-alg-3.1.2", c="ccl_particles_capture_uv",
         args=(Arg("ndc", "normalised device coordinates of the point in the view, (-1, -1) bottom-left",
                   sample_range=(-1.0, 1.0)),
               Arg("aspect", "view width / height", lo=0.0, lo_open=True, sample_range=(0.25, 4.0)),
               Arg("fov_view", "vertical field of view of the view camera (rad)", **_FOV, sample_range=(0.1, 2.5)),
               Arg("fov_capture", "vertical field of view of the square capture (rad); the text: 150 deg",
                   **_FOV_CAPTURE, sample_range=(1.0, 3.0))),
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


# --- physical streaks: the drop's disc integrated over the exposure (Garg & Nayar 2004) -------------------------------

@wp.func
def _exposure_w2(s: float) -> float:
    """Second integral of the exposure weight 1 - cos(2 pi s) on [0, 1] (``exposure_w2`` of particles.c)."""
    k = _TWO_PI
    out = float(0.0)
    if s >= 1.0:
        out = s - 0.5
    elif s > 0.0:
        out = 0.5 * s * s + (wp.cos(k * s) - 1.0) / (k * k)
    return out


@wp.func
def _exposure_w2_end(s: float) -> float:
    """``_exposure_w2(s) - (s - 1/2)`` without the cancellation (``exposure_w2_end``)."""
    k = _TWO_PI
    t = 1.0 - s
    out = float(0.0)
    if s < 1.0:
        out = 0.5 * t * t + (wp.cos(k * t) - 1.0) / (k * k)
    return out


@wp.func
def _sinc(x: float) -> float:
    out = float(1.0)
    if wp.abs(x) >= 1e-4:
        out = wp.sin(x) / x
    return out


@wp.func
def _chord_integral(u: float, r: float) -> float:
    """int_0^u 2 sqrt(r^2 - t^2) dt (``chord_integral``)."""
    q = u / r
    if q > 1.0:
        q = 1.0
    if q < -1.0:
        q = -1.0
    return r * r * (q * wp.sqrt(wp.max(1.0 - q * q, 0.0)) + wp.asin(q))


@wp.func
def particles_streak_cover(cx: float, cy: float, radius: float, half_height: float, px: float, py: float):
    """(alpha, mask u, half chord): the exposure of the pixel centred at (px, py) to the physical streak of a sprite,
    as ``ccl_particles_streak_cover`` (the model and its reference are in :func:`particles_composite`'s summary)."""
    k = _TWO_PI
    travel = 2.0 * (half_height - radius)
    length = wp.max(travel, MIN_STREAK_PX)
    head = cy + 0.5 * travel
    dx = px - cx
    lo = wp.max(dx - 0.5, -radius)
    hi = wp.min(dx + 0.5, radius)
    alpha = float(0.0)
    mu = float(0.5)
    h = float(0.0)
    if hi > lo:
        cover = hi - lo
        h = 0.5 * (_chord_integral(hi, radius) - _chord_integral(lo, radius)) / cover
        mu = 0.5 * (lo + hi) / (2.0 * radius) + 0.5
        a = 1.0 + (py - head) / length
        e = 0.5 / length
        d = h / length
        if a + e + d <= 0.0 or a - e - d >= 1.0:
            alpha = 0.0
        elif a - e - d >= 0.0 and a + e + d <= 1.0:
            alpha = cover * (2.0 * h / length) * (1.0 - _sinc(k * e) * _sinc(k * d) * wp.cos(k * a))
        elif a - e - d >= 0.0:
            alpha = cover * length * (_exposure_w2_end(a + e + d) - _exposure_w2_end(a - e + d)
                                      - _exposure_w2_end(a + e - d) + _exposure_w2_end(a - e - d))
        else:
            alpha = cover * length * (_exposure_w2(a + e + d) - _exposure_w2(a - e + d) - _exposure_w2(a + e - d)
                                      + _exposure_w2(a - e - d))
        alpha = wp.min(wp.max(alpha, 0.0), 1.0)
    return alpha, mu, h


@wp.func
def _sample_v(i: int, h: float, radius: float) -> float:
    """Mask v of colour sample i of a physical streak pixel: evenly across the chord (-h, h)."""
    return 0.5 + h * ((2.0 * float(i) + 1.0) / float(STREAK_SAMPLES) - 1.0) / (2.0 * radius)


# --- rr-code-5.2.3 / rr-code-5.2.4: the fragment shaders ----------------------------------------------------------------

@wp.func
def _texel(img: wp.array(dtype=float), size: int, x: int, y: int) -> wp.vec3:
    i = 3 * (wp.clamp(y, 0, size - 1) * size + wp.clamp(x, 0, size - 1))
    return wp.vec3(img[i], img[i + 1], img[i + 2])


@wp.func
def particles_fetch(img: wp.array(dtype=float), size: int, u: float, v: float, filt: int) -> wp.vec3:
    """Capture fetch at (u, v), clamped to the edge: nearest (0) or bilinear (1), as the C ``fetch``; any non-NaN
    (u, v) beyond the capture reads its edge texels, a NaN gives NaN."""
    if not (u == u and v == v):
        return wp.vec3(u + v, u + v, u + v)
    if filt == LINEAR:
        fx = bound_cell(u * float(size) - 0.5, size)
        fy = bound_cell(v * float(size) - 0.5, size)
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
    return _texel(img, size, int(wp.floor(bound_cell(u * float(size), size))),
                  int(wp.floor(bound_cell(v * float(size), size))))


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
            qx = mask[m] / mask[m + 2]
            qy = mask[m + 1] / mask[m + 2]
            if qx == qx and qy == qy:  # a NaN exit direction (or 0/0, Inf/Inf): the texel has no ray
                uc = p_o[0] + scale * qx
                vc = p_o[1] - scale * qy
                rgb = particles_fetch(capture, capture_size, uc, vc, filt)
                hit = 1
    return hit, rgb


@wp.func
def _sprite_taps(sprites: wp.array2d(dtype=float), j: int, px: float, py: float, streaks: int):
    """Where the taps of sprite j lie at pixel centre (px, py) (the geometry of the loop body of
    ``ccl_particles_shade_pixel``): (lo, hi, mu, w, cover), taps i = lo..hi at mask (mu, :func:`_tap_v`); none (hi <
    lo) when the pixel misses the sprite. Physical streaks: STREAK_SAMPLES colour samples across the chord of
    half-length w = h, ``cover`` the streak's coverage of the pixel; otherwise one tap at mask v = w (STREAK_TAPS
    along the streak with ``streaks`` on) and cover 1."""
    dx = px - sprites[j, 0]
    dy = py - sprites[j, 1]
    radius = sprites[j, 2]
    lo = int(0)
    hi = int(-1)
    mu = float(0.0)
    w = float(0.0)
    cover = float(1.0)
    if streaks == STREAKS_PHYSICAL:
        if wp.abs(dx) < radius + 0.5 and wp.abs(dy) < sprites[j, 3] + 0.5:
            alpha, mu_s, hc = particles_streak_cover(sprites[j, 0], sprites[j, 1], radius, sprites[j, 3], px, py)
            if alpha > 0.0:
                hi = STREAK_SAMPLES - 1
                mu = mu_s
                w = hc
                cover = alpha
    elif wp.abs(dx) < radius and wp.abs(dy) < sprites[j, 3]:
        mu = dx / (2.0 * radius) + 0.5
        w = dy / (2.0 * sprites[j, 3]) + 0.5
        hi = 0
        if streaks != 0:
            lo = -(STREAK_TAPS // 2)
            hi = STREAK_TAPS // 2
    return lo, hi, mu, w, cover


@wp.func
def _tap_v(sprites: wp.array2d(dtype=float), j: int, streaks: int, i: int, w: float) -> float:
    """Mask v of tap i of :func:`_sprite_taps`."""
    if streaks == STREAKS_PHYSICAL:
        return _sample_v(i, w, sprites[j, 2])
    return w - float(i) * sprites[j, 4]


@wp.func
def _sprite_over(c: wp.vec3, s: wp.vec3, hits: int, streaks: int, cover: float, opacity: float) -> wp.vec3:
    """The mean colour of a sprite's ``hits`` taps (their sum ``s``) over colour c: with the opacity times the
    streak's coverage (physical streaks), times the share of taps that hit (``streaks`` on), or the opacity."""
    if hits == 0:
        return c
    a = opacity
    if streaks == STREAKS_PHYSICAL:
        a = opacity * cover
    elif streaks != 0:
        a = opacity * (float(hits) / float(STREAK_TAPS))
    return wp.vec3(c[0] + (s[0] / float(hits) - c[0]) * a, c[1] + (s[1] / float(hits) - c[1]) * a,
                   c[2] + (s[2] / float(hits) - c[2]) * a)


@wp.func
def particles_shade_sprite(c: wp.vec3, sprites: wp.array2d(dtype=float), j: int, mask: wp.array(dtype=float),
                           mask_size: int, capture: wp.array(dtype=float), capture_size: int, px: float, py: float,
                           p_o: wp.vec2, scale: float, filt: int, streaks: int, opacity: float) -> wp.vec3:
    """Sprite j composited over colour c at pixel centre (px, py) (the loop body of ``ccl_particles_shade_pixel``)."""
    lo, hi, mu, w, cover = _sprite_taps(sprites, j, px, py, streaks)
    s = wp.vec3(0.0, 0.0, 0.0)
    hits = int(0)
    for i in range(lo, hi + 1):
        h, rgb = particles_tap(mask, mask_size, capture, capture_size, mu, _tap_v(sprites, j, streaks, i, w), p_o,
                               scale, filt)
        if h != 0:
            s = wp.vec3(s[0] + rgb[0], s[1] + rgb[1], s[2] + rgb[2])
            hits = hits + 1
    return _sprite_over(c, s, hits, streaks, cover, opacity)


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
    """C_F of one tap (``light_tap`` of particles.c): the texel's entry normal (packed, :func:`pywarp.rain.particles.pack_normals`) turned
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
    """:func:`particles_tap` on the packed mask of :func:`pywarp.rain.particles.pack_mask` (the same values, x/z and y/z read instead of
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
    lo, hi, mu, w, cover = _sprite_taps(sprites, j, px, py, streaks)
    s = wp.vec3(0.0, 0.0, 0.0)
    hits = int(0)
    for i in range(lo, hi + 1):
        h, rgb, t = _tap_packed(offsets, mask_size, capture, capture_size, mu, _tap_v(sprites, j, streaks, i, w), p_o,
                                scale, filt)
        if h != 0 and lit != 0:
            rgb = _light_tap(L, positions[j], normals, t, rgb)
        if h != 0:
            s = wp.vec3(s[0] + rgb[0], s[1] + rgb[1], s[2] + rgb[2])
            hits = hits + 1
    return _sprite_over(c, s, hits, streaks, cover, opacity)


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
        # the pixels whose centre may lie in the box (the exact test is the shader's); the edges are taken within
        # the tile +- 2 pixels before the int() (a huge or infinite sprite; binned sprites are not NaN), which keeps
        # xa..xb and ya..yb as they were
        fx0 = float(x0) - 2.0
        fx1 = float(x1) + 2.0
        fy0 = float(y0) - 2.0
        fy1 = float(y1) + 2.0
        xa = wp.max(x0, int(wp.floor(wp.clamp(sprites[j, 0] - sprites[j, 2], fx0, fx1))) - 1)
        xb = wp.min(x1, int(wp.floor(wp.clamp(sprites[j, 0] + sprites[j, 2], fx0, fx1))) + 1)
        ya = wp.max(y0, int(wp.floor(wp.clamp(sprites[j, 1] - sprites[j, 3], fy0, fy1))) - 1)
        yb = wp.min(y1, int(wp.floor(wp.clamp(sprites[j, 1] + sprites[j, 3], fy0, fy1))) + 1)
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


declare("rr-code-5.2.3", "rr-code-5.2.4", c="ccl_particles_composite", name="particles_composite",
        make_warp="pywarp.rain.particles:composite_warp",
        make_c="pywarp.rain.particles:composite_c",
        summary="particles_composite(background, capture, mask, sprites, fov_view, fov_capture=150 deg, "
                "streaks='off', filter='nearest', opacity=1) -> frame: the refraction fragment shader (rr-code-5.2.3) "
                "on every drop billboard; streaks='thesis' the retinal-persistence shader as listed (rr-code-5.2.4: 7 "
                "mask taps i = -3 .. 3 shifted by i tap_offset, averaged, alpha reduced to the share of taps that "
                "hit); streaks='physical' the drop's disc (the sprite's radius) integrated over the persistence time "
                "T in closed form: alpha = opacity (1/T) int w(t) cov(t) dt, cov the share of the pixel the disc "
                "covers, w = 1 - cos(2 pi t / T) (mean 1: the image builds up and fades, so the ends taper), so a "
                "streak's alphas sum to pi r^2 and its middle is ~ 2 r / L opaque -- the time a drop covers a pixel "
                "over the exposure (Garg & Nayar 2004: < 1.2 ms of a 1/30 s frame, faint streaks); colour the mean "
                "of 8 refraction taps down the mask column across the chord the pixel sees (fixed in the drop: no "
                "pattern along the streak). Composited far to near over the background. Per tap: the mask texel (inside flag a, refraction "
                "vector xyz), P_o = the pixel's capture coordinate (rr-alg-3.1.2), P_c = P_o + (x, -y) / z * 0.5 / "
                "tan(fov_capture/2), the capture at P_c. The listings' defects (undeclared count, extra brace, no "
                "output, int*float, no averaging or alpha) are fixed.",
        references=("Rousseau, Jolivet & Ghazanfarpour 2006, §4 (refraction), §3.5.3 (retinal persistence)",
                    "Garg & Nayar, Detection and removal of rain from videos, CVPR 2004 (exposure of a streak)"))(
    particles_shade_sprite)


__all__ = ["ParticlesParams", "ParticlesLights", "LIGHT_DEFAULTS",
           "check_lights", "lights_on", "light_params", "c_lights", "FILTERS", "SPRITE_FIELDS", "STREAK_TAPS"]
