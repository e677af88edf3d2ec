"""The host side of the oc flight model (§6): the parameters with their defaults (:class:`FlightModel`), a state
(:class:`FlightState`), a scripted flight (:func:`key_mask`) flown by the Warp kernel (:func:`simulate`) or by the C
reference (:func:`simulate_c`) into a :class:`Trajectory`, and the body axes on the host (:func:`axes`). The equations
and the kernel are :mod:`pywarp.kernels.flight`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
import warp as wp

from ..kernels.flight import KEYS, FlightParams, simulate_kernel


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
    """The keys held during each step of ``duration`` seconds: ``script`` is a sequence of ``(key, t_on, t_off)`` (key a
    name of :data:`pywarp.kernels.flight.KEYS` or a bit, times in seconds); step k (from t = k dt to (k + 1) dt) holds
    the keys with ``t_on <= k dt < t_off``. Validated: ValueError naming the bad entry."""
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
    wp.launch(simulate_kernel, dim=1,
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
