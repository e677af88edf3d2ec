"""The aircraft of the oc flight simulator (§6) -- Warp twins of ``cclouds/flight.h``.

* :func:`flight_attitude` (oc-6.1.1): pitch and roll from the five height points A (nose), B (tail), C (left wing
  tip), D (right wing tip), E (centre of gravity = the altitude): ``pitch = atan2(h_A - h_B, length)``,
  ``roll = atan2(h_C - h_D, span)`` (roll > 0: right wing down).
* :func:`flight_step`: one step of the flight model driven by the six keys of the text's control table (arrows move
  the height points at ``point_rate`` while held, so the attitude change grows with how long a key is held; W/S change
  the speed within [0, max_speed]; the tilt gives the motion: climbing and turning only with speed).
* :func:`flight_aircraft` (oc-6.1): the signed distance to the procedural aircraft that stands in for the text's
  3DS model (no model ships with the text).
* :func:`simulate`: a script of timed key presses -> the trajectory, stepped with a fixed dt in one Warp thread
  (the same script gives the same trajectory); :func:`simulate_c` does the same with ``ccl_flight_step``.

Frames (as the C header): world y up, metres; heading 0 = towards -z, positive towards +x; model frame x = right
wing, y = up, z = tail (the nose points to -z).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
import warp as wp

from ..core.registry import Arg, declare

# key bits (cclouds/flight.h)
KEY_UP = 1      # up arrow: descend
KEY_DOWN = 2    # down arrow: climb
KEY_LEFT = 4    # left arrow: turn left
KEY_RIGHT = 8   # right arrow: turn right
KEY_W = 16      # faster
KEY_S = 32      # slower
KEYS = {"up": KEY_UP, "down": KEY_DOWN, "left": KEY_LEFT, "right": KEY_RIGHT, "w": KEY_W, "s": KEY_S}

_KUP = wp.constant(KEY_UP)
_KDOWN = wp.constant(KEY_DOWN)
_KLEFT = wp.constant(KEY_LEFT)
_KRIGHT = wp.constant(KEY_RIGHT)
_KW = wp.constant(KEY_W)
_KS = wp.constant(KEY_S)


@wp.struct
class FlightParams:
    """Mirror of ``ccl_flight_params`` (see :class:`FlightModel` for the defaults and their reasons)."""

    length: float
    span: float
    point_rate: float
    max_pitch: float
    max_roll: float
    level_rate: float
    max_speed: float
    acceleration: float
    turn_rate: float
    min_altitude: float


@dataclass(frozen=True)
class FlightModel:
    """The parameters of the flight model with the defaults of ``ccl_flight_params_default`` (the text gives none of
    these values; reasons in cclouds/src/flight.c and the flight settings)."""

    length: float = 7.5
    span: float = 12.0
    point_rate: float = 1.0
    max_pitch: float = 0.5
    max_roll: float = 0.8
    level_rate: float = 0.0
    max_speed: float = 60.0
    acceleration: float = 8.0
    turn_rate: float = 0.8
    min_altitude: float = 5.0

    def __post_init__(self):
        half_pi = float(np.float32(math.pi / 2))
        for f in fields(self):
            v = getattr(self, f.name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"{f.name} must be a finite number, got {v!r}")
        for name in ("length", "span", "max_speed"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be in (0, inf), got {getattr(self, name)!r}")
        for name in ("point_rate", "level_rate", "acceleration", "turn_rate"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"{name} must be in [0, inf), got {getattr(self, name)!r}")
        for name in ("max_pitch", "max_roll"):
            if not 0 < getattr(self, name) < half_pi:
                raise ValueError(f"{name} must be in (0, pi/2), got {getattr(self, name)!r}")

    def warp(self) -> FlightParams:
        s = FlightParams()
        for f in fields(self):
            setattr(s, f.name, float(getattr(self, f.name)))
        return s

    def c(self):
        from ..core.binding import ffi

        p = ffi().new("ccl_flight_params *")
        for f in fields(self):
            setattr(p, f.name, float(getattr(self, f.name)))
        return p


# --- oc-6.1.1: attitude from the height points -----------------------------------------------------------------------

_H = dict(sample_range=(-50.0, 50.0))


@declare("oc-6.1.1", c="ccl_flight_attitude",
         args=(Arg("h_a", "height of A, the nose [m]", **_H), Arg("h_b", "height of B, the tail [m]", **_H),
               Arg("h_c", "height of C, the left wing tip [m]", **_H),
               Arg("h_d", "height of D, the right wing tip [m]", **_H),
               Arg("length", "distance nose-tail |AB| [m]", lo=0.0, lo_open=True, sample_range=(0.5, 50.0)),
               Arg("span", "distance of the wing tips |CD| [m]", lo=0.0, lo_open=True, sample_range=(0.5, 50.0))),
         outputs=("pitch", "roll"),
         summary="Aircraft attitude from its height points: pitch = atan2(h_A - h_B, length) (> 0 nose up), "
                 "roll = atan2(h_C - h_D, span) (> 0 right wing down) [rad]; E (the altitude) does not enter.",
         references=("Kučera 2006, §6.1.1 (the formula is the catalogue's reading: the text says only that the tilt "
                     "is computed from the height differences)",))
@wp.func
def flight_attitude(h_a: float, h_b: float, h_c: float, h_d: float, length: float,
                    span: float) -> tuple[float, float]:
    roll = wp.atan2(h_c - h_d, span)
    return wp.atan2(h_a - h_b, length), roll


@wp.func
def flight_axes(heading: float, pitch: float, roll: float):
    """Twin of ``ccl_flight_axes``: (forward, right, up)."""
    sh = wp.sin(heading)
    ch = wp.cos(heading)
    sp = wp.sin(pitch)
    cp = wp.cos(pitch)
    sr = wp.sin(roll)
    cr = wp.cos(roll)
    f = wp.vec3(sh * cp, sp, -(ch * cp))
    r0 = wp.vec3(ch, 0.0, sh)
    u0 = wp.cross(r0, f)
    r = r0 * cr - u0 * sr
    u = r0 * sr + u0 * cr
    return f, r, u


def axes(heading: float, pitch: float, roll: float) -> tuple[tuple, tuple, tuple]:
    """Body axes (forward, right, up) of ``ccl_flight_axes`` on the host, in float32 NumPy operations (for placing
    the aircraft in a scene). Angles in radians."""
    f32 = np.float32
    sh, ch = np.sin(f32(heading)), np.cos(f32(heading))
    sp, cp = np.sin(f32(pitch)), np.cos(f32(pitch))
    sr, cr = np.sin(f32(roll)), np.cos(f32(roll))
    f = np.array([sh * cp, sp, -(ch * cp)], dtype=f32)
    r0 = np.array([ch, f32(0.0), sh], dtype=f32)
    u0 = np.cross(r0, f).astype(f32)
    r = (r0 * cr - u0 * sr).astype(f32)
    u = (r0 * sr + u0 * cr).astype(f32)
    return tuple(map(float, f)), tuple(map(float, r)), tuple(map(float, u))


@wp.func
def _move_offset(offset: float, up_key: int, down_key: int, rate: float, level: float, dt: float,
                 limit: float) -> float:
    o = offset
    if up_key != 0 and down_key == 0:
        o = o + rate * dt
    elif down_key != 0 and up_key == 0:
        o = o - rate * dt
    elif up_key == 0 and down_key == 0 and level > 0.0:
        step = level * dt
        if o > step:
            o = o - step
        elif o < -step:
            o = o + step
        else:
            o = 0.0
    if o > limit:
        o = limit
    if o < -limit:
        o = -limit
    return o


@wp.func
def flight_step(p: FlightParams, position: wp.vec3, heading: float, speed: float, nose_offset: float,
                wing_offset: float, keys: int, dt: float):
    """Twin of ``ccl_flight_step``: (position, heading, speed, nose_offset, wing_offset) after one step."""
    pitch_limit = 0.5 * p.length * wp.tan(p.max_pitch)
    roll_limit = 0.5 * p.span * wp.tan(p.max_roll)
    nose = _move_offset(nose_offset, keys & _KDOWN, keys & _KUP, p.point_rate, p.level_rate, dt, pitch_limit)
    wing = _move_offset(wing_offset, keys & _KRIGHT, keys & _KLEFT, p.point_rate, p.level_rate, dt, roll_limit)
    v = speed
    if (keys & _KW) != 0 and (keys & _KS) == 0:
        v = v + p.acceleration * dt
    if (keys & _KS) != 0 and (keys & _KW) == 0:
        v = v - p.acceleration * dt
    if v > p.max_speed:
        v = p.max_speed
    if v < 0.0:
        v = 0.0
    h_e = position[1]
    pitch, roll = flight_attitude(h_e + nose, h_e - nose, h_e + wing, h_e - wing, p.length, p.span)
    turn = p.turn_rate * wp.sin(roll) * (v / p.max_speed)
    psi = heading + turn * dt
    f = wp.vec3(wp.sin(psi) * wp.cos(pitch), wp.sin(pitch), -(wp.cos(psi) * wp.cos(pitch)))
    pos = position + f * (v * dt)
    if pos[1] < p.min_altitude:
        pos = wp.vec3(pos[0], p.min_altitude, pos[2])
    return pos, psi, v, nose, wing


# --- oc-6.1: the procedural aircraft ------------------------------------------------------------------------------------

@wp.func
def _capsule(p: wp.vec3, a: wp.vec3, b: wp.vec3, r: float) -> float:
    pa = p - a
    ba = b - a
    h = wp.dot(pa, ba) / wp.dot(ba, ba)
    if h < 0.0:
        h = 0.0
    if h > 1.0:
        h = 1.0
    return wp.length(pa - ba * h) - r


@wp.func
def _round_box(p: wp.vec3, c: wp.vec3, e: wp.vec3, r: float) -> float:
    qx = wp.abs(p[0] - c[0]) - e[0] + r
    qy = wp.abs(p[1] - c[1]) - e[1] + r
    qz = wp.abs(p[2] - c[2]) - e[2] + r
    qp = wp.vec3(wp.where(qx > 0.0, qx, 0.0), wp.where(qy > 0.0, qy, 0.0), wp.where(qz > 0.0, qz, 0.0))
    inner = wp.where(qx > qy, qx, qy)
    inner = wp.where(inner > qz, inner, qz)
    if inner > 0.0:
        inner = 0.0
    return wp.length(qp) + inner - r


@declare("oc-6.1", c="ccl_flight_aircraft",
         args=(Arg("p", "point in the model frame (x right wing, y up, z tail) [m]", sample_range=(-8.0, 8.0)),),
         outputs=("distance", "part"),
         summary="Signed distance [m] to the procedural light aircraft that stands in for the text's 3DS model "
                 "(3DS -> Open Inventor with 3DS2IV; no model ships with the text), and the nearest part: 0 "
                 "fuselage, 1 wings, 2 tail surfaces, 3 canopy. Span 12 m, nose to tail 7.5 m (the height points "
                 "A-D of oc-6.1.1 at its nose, tail and wing tips).",
         references=("Kučera 2006, §6.1 (the model import) and Obrázek 6.1",
                     "Quilez, distance functions (capsule, rounded box)"))
@wp.func
def flight_aircraft(p: wp.vec3) -> tuple[float, int]:
    part = int(0)
    d = _capsule(p, wp.vec3(0.0, 0.0, -3.2), wp.vec3(0.0, 0.0, 1.2), 0.55)
    e = _capsule(p, wp.vec3(0.0, 0.05, 1.2), wp.vec3(0.0, 0.3, 3.5), 0.25)
    if e < d:
        d = e
    e = _capsule(p, wp.vec3(0.0, 0.0, -3.6), wp.vec3(0.0, 0.0, -3.55), 0.2)
    if e < d:
        d = e
    e = _round_box(p, wp.vec3(0.0, -0.25, -0.9), wp.vec3(6.0, 0.07, 0.8), 0.06)
    if e < d:
        d = e
        part = 1
    e = _round_box(p, wp.vec3(0.0, 0.3, 3.3), wp.vec3(2.0, 0.05, 0.45), 0.04)
    if e < d:
        d = e
        part = 2
    e = _round_box(p, wp.vec3(0.0, 0.95, 3.35), wp.vec3(0.06, 0.7, 0.45), 0.05)
    if e < d:
        d = e
        part = 2
    e = _capsule(p, wp.vec3(0.0, 0.42, -1.9), wp.vec3(0.0, 0.42, -0.9), 0.38)
    if e < d:
        d = e
        part = 3
    return d, part


# --- scripted flights ---------------------------------------------------------------------------------------------------

@wp.kernel
def _simulate_kernel(p: FlightParams, start: wp.vec3, heading0: float, speed0: float, nose0: float, wing0: float,
                     keys: wp.array(dtype=wp.int32), dt: float, n: int,
                     # outputs: the state after each step
                     pos: wp.array(dtype=wp.vec3), heading: wp.array(dtype=float), speed: wp.array(dtype=float),
                     nose: wp.array(dtype=float), wing: wp.array(dtype=float)):
    x = start
    psi = heading0
    v = speed0
    a = nose0
    b = wing0
    for k in range(n):
        x, psi, v, a, b = flight_step(p, x, psi, v, a, b, keys[k], dt)
        pos[k] = x
        heading[k] = psi
        speed[k] = v
        nose[k] = a
        wing[k] = b


@dataclass(frozen=True)
class FlightState:
    """A state of the aircraft (``ccl_flight_state``)."""

    position: tuple = (0.0, 300.0, 0.0)
    heading: float = 0.0
    speed: float = 0.0
    nose_offset: float = 0.0
    wing_offset: float = 0.0


@dataclass(frozen=True)
class Trajectory:
    """States after each step of a scripted flight: ``time[k] = (k + 1) dt``; ``pitch`` and ``roll`` from the
    height points (oc-6.1.1)."""

    time: np.ndarray
    position: np.ndarray  # (n, 3)
    heading: np.ndarray
    speed: np.ndarray
    nose_offset: np.ndarray
    wing_offset: np.ndarray
    pitch: np.ndarray
    roll: np.ndarray
    keys: np.ndarray

    def at(self, t: float) -> int:
        """Index of the last step at or before time ``t`` (0 before the first)."""
        dt = float(self.time[0])
        return int(min(max(round(t / dt) - 1, 0), len(self.time) - 1))


#: the most steps a simulation takes (bounds the kernel's loop)
MAX_STEPS = 10_000_000


def key_mask(script, duration: float, dt: float) -> np.ndarray:
    """The keys held during each step of ``duration`` seconds: ``script`` is a sequence of ``(key, t_on, t_off)``
    (key a name of :data:`KEYS` or a bit, times in seconds); step k (from t = k dt to (k + 1) dt) holds the keys
    with ``t_on <= k dt < t_off``. Validated: ValueError naming the bad entry."""
    if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be in (0, inf), got {dt!r}")
    if not (isinstance(duration, (int, float)) and math.isfinite(duration) and duration >= 0):
        raise ValueError(f"duration must be in [0, inf), got {duration!r}")
    n = int(round(duration / dt))
    if n > MAX_STEPS:
        raise ValueError(f"duration / dt must be at most {MAX_STEPS} steps, got {n}")
    t = np.arange(n, dtype=np.float64) * dt
    mask = np.zeros(n, dtype=np.int32)
    for i, item in enumerate(script):
        try:
            key, on, off = item
        except (TypeError, ValueError):
            raise ValueError(f"script[{i}] must be (key, t_on, t_off), got {item!r}") from None
        bit = KEYS.get(key.lower()) if isinstance(key, str) else key
        if bit not in KEYS.values():
            raise ValueError(f"script[{i}]: key must be one of {', '.join(KEYS)}, got {key!r}")
        for name, v in (("t_on", on), ("t_off", off)):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"script[{i}]: {name} must be a finite number, got {v!r}")
        if off < on:
            raise ValueError(f"script[{i}]: t_off must be >= t_on, got {off!r} < {on!r}")
        mask[(t >= on) & (t < off)] |= bit
    return mask


def _finish(model: FlightModel, dt: float, keys, pos, heading, speed, nose, wing) -> Trajectory:
    from ..core.registry import equation

    n = len(keys)
    if n:
        h = pos[:, 1]
        pitch, roll = equation("oc-6.1.1")(h + nose, h - nose, h + wing, h - wing, model.length, model.span)
    else:
        pitch = roll = np.zeros(0, np.float32)
    return Trajectory(np.arange(1, n + 1) * dt, pos, heading, speed, nose, wing, np.asarray(pitch),
                      np.asarray(roll), keys)


def _check_state(state: FlightState, model: FlightModel) -> FlightState:
    pos = np.asarray(state.position, dtype=np.float64)
    if pos.shape != (3,) or not np.all(np.isfinite(pos)):
        raise ValueError(f"start position must be 3 finite numbers, got {state.position!r}")
    for name in ("heading", "speed", "nose_offset", "wing_offset"):
        v = getattr(state, name)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"start {name} must be a finite number, got {v!r}")
    if not 0 <= state.speed <= model.max_speed:
        raise ValueError(f"start speed must be in [0, max_speed = {model.max_speed:g}], got {state.speed!r}")
    return state


def simulate(script, duration: float, dt: float = 1.0 / 60.0, start: FlightState | None = None,
             model: FlightModel | None = None, device: str | None = None) -> Trajectory:
    """Fly ``script`` (see :func:`key_mask`) for ``duration`` seconds with the fixed step ``dt`` (Warp, one thread:
    the flight is sequential). The same script gives the same trajectory."""
    from ..core.runtime import resolve_device

    model = model or FlightModel()
    start = _check_state(start or FlightState(), model)
    keys = key_mask(script, duration, dt)
    n = len(keys)
    dev = resolve_device(device)
    outs = [wp.zeros(max(n, 1), dtype=wp.vec3, device=dev)] + [wp.zeros(max(n, 1), dtype=float, device=dev)
                                                               for _ in range(4)]
    wp.launch(_simulate_kernel, dim=1,
              inputs=[model.warp(), wp.vec3(*[float(x) for x in start.position]), float(start.heading),
                      float(start.speed), float(start.nose_offset), float(start.wing_offset),
                      wp.array(keys if n else np.zeros(1, np.int32), dtype=wp.int32, device=dev), float(dt), n],
              outputs=outs, device=dev)
    pos, heading, speed, nose, wing = (o.numpy()[:n] for o in outs)
    return _finish(model, dt, keys, pos, heading, speed, nose, wing)


def simulate_c(script, duration: float, dt: float = 1.0 / 60.0, start: FlightState | None = None,
               model: FlightModel | None = None) -> Trajectory:
    """:func:`simulate` with the C reference ``ccl_flight_step``."""
    from ..core.binding import ffi, lib, status_error

    f, lb = ffi(), lib()
    model = model or FlightModel()
    start = _check_state(start or FlightState(), model)
    keys = key_mask(script, duration, dt)
    params = model.c()
    field = f.new("const char **")
    status_error(lb.ccl_flight_check(params, field), "ccl_flight_check")
    s = f.new("ccl_flight_state *")
    s.position.x, s.position.y, s.position.z = (float(x) for x in start.position)
    s.heading, s.speed, s.nose_offset, s.wing_offset = (float(start.heading), float(start.speed),
                                                        float(start.nose_offset), float(start.wing_offset))
    n = len(keys)
    pos = np.empty((n, 3), np.float32)
    other = np.empty((n, 4), np.float32)
    for k in range(n):
        lb.ccl_flight_step(params, s, int(keys[k]), float(dt), s)
        pos[k] = s.position.x, s.position.y, s.position.z
        other[k] = s.heading, s.speed, s.nose_offset, s.wing_offset
    return _finish(model, dt, keys, pos, other[:, 0].copy(), other[:, 1].copy(), other[:, 2].copy(),
                   other[:, 3].copy())
