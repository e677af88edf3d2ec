"""The aircraft of the oc flight simulator (§6) -- Warp twins of ``cclouds/flight.h``.

* :func:`flight_attitude` (oc-6.1.1): pitch and roll from the five height points A (nose), B (tail), C (left wing
  tip), D (right wing tip), E (centre of gravity = the altitude): ``pitch = atan2(h_A - h_B, length)``,
  ``roll = atan2(h_C - h_D, span)`` (roll > 0: right wing down).
* :func:`flight_step`: one step of the flight model driven by the six keys of the text's control table (arrows move
  the height points at ``point_rate`` while held, so the attitude change grows with how long a key is held; W/S change
  the speed within [0, max_speed]; the tilt gives the motion: climbing and turning only with speed).
* :func:`flight_aircraft` (oc-6.1): the signed distance to the procedural aircraft that stands in for the text's
  3DS model (no model ships with the text).
* :func:`simulate_kernel`: a script of timed key presses -> the trajectory, stepped with a fixed dt in one Warp thread
  (the same script gives the same trajectory); the host side (the model's defaults, the script, the C reference) is
  :mod:`pywarp.flight.model`.

Frames (as the C header): world y up, metres; heading 0 = towards -z, positive towards +x; model frame x = right
wing, y = up, z = tail (the nose points to -z).
"""
from __future__ import annotations

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
    """Mirror of ``ccl_flight_params`` (see :class:`pywarp.flight.model.FlightModel` for the defaults and their reasons)."""

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
def simulate_kernel(p: FlightParams, start: wp.vec3, heading0: float, speed0: float, nose0: float, wing0: float,
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


