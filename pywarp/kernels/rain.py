"""One raindrop (rr §2.1-3.2) -- Warp twins of ``cclouds/rain.h``: the Beard-Chuang shape, terminal speeds, refraction
masks, the drop pixel colour P_i -> P_o -> P_c, the capture-parallax error and the light-drop model.

Frames and units (see ``cclouds/rain.h`` for the full statement):

* **Drop frame**: y up (the fall axis); the Beard-Chuang angle ``theta`` is measured from the DOWNWARD vertical
  (0 = down, pi = up), ``phi`` the azimuth about y from +x towards +z; lengths in mm; ``a`` the radius of Table 2.1
  (0.5, 1.0, 3.0, 4.5 mm).
* **Mask frame** (rr-alg-3.1.1): x right, y up, z along the viewing direction (away from the viewer; the text's
  shaders keep texels with ``z > 0``). Texel (u, v) in [-1, 1]^2 is the point (u L, v L) of the drop's mid-plane,
  ``L = rain_drop_extent(a)`` (outline/exact) or ``a`` (sphere). Row i, column j of a size x size mask: u = 2 (j + 0.5) /
  size - 1, v = 1 - 2 (i + 0.5) / size. Camera space (OpenGL) of a billboard facing f: ``x r + y u + z f``,
  ``r = normalize(f x (0, 1, 0))``, ``u = r x f``.
* **Capture**: RGB float image, rows from the top, uv with v DOWN, perspective with vertical FOV ``fov_y``; edges
  clamped. The default FOV is the text's 150 deg (rr-der-3.2.1 as printed, :data:`CAPTURE_FOV_DEG`); the exact value
  for n = 1.33 is 165.0 deg (``optics_drop_fov(1.33)``).

Readings of what the text leaves open (each a named parameter):

* ``interp="table"`` (default) accepts only the four tabulated radii; ``interp="linear"`` interpolates each
  coefficient linearly in a between rows (a in [0.5, 4.5]) -- an assumption: the table has no 1.5-2.5 mm rows.
* Terminal speed: linear between the 23 rows of Table 2.2, Stokes ``0.72 (r / 0.1)^2`` below 0.1 mm, plateau 9.23 m/s
  from 4 mm; ``slowdown`` divides it (1 = physical, :data:`APP_SLOWDOWN` = 4 the application's).
* rr-A1's DistFact(d) = 1 / (1 + (d / r_half)^2) (inverse square with a finite core; ``r_half`` the distance at
  which a light has half its intensity).

Stable API used by the rain scene: :func:`rain_terminal_speed` (pywarp.rain_terminal_speed(radius_mm, slowdown)),
:func:`rain_drop_radius`, :func:`rain_drop_extent`, :func:`rain_mask_texel`, :func:`rain_refracted_uv`,
:func:`rain_sample_capture` and the light functions -- all ``@wp.func`` usable in kernels. The drop's shape on NumPy
arrays and the cached refraction mask (``drop_mask``) are :mod:`pywarp.rain.drops`.
"""
from __future__ import annotations

import math

import numpy as np
import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import VARIANT, Arg, Option, declare
from . import VARIANT_THESIS
from .optics import optics_snell

# --- constants ---------------------------------------------------------------------------------------------------------

#: Table 2.1 radii [mm] and coefficients c_n x 1e4 (rr-tab-2.1, Beard & Chuang 1987)
SHAPE_RADII = (0.5, 1.0, 3.0, 4.5)
SHAPE_TABLE = (
    (-28, -30, -83, -22, -3, 2, 1, 0, 0, 0, 0),
    (-134, -118, -385, -100, -5, 17, 6, -1, -3, -1, 1),
    (-843, -472, -2040, -240, 299, 168, -21, -73, -20, 25, 24),
    (-1328, -403, -2889, -106, 662, 153, -146, -111, 18, 81, 31),
)
#: Table 2.2: radius [mm] -> terminal speed [m/s] (rr-tab-2.2, Gunn & Kinzer 1949)
SPEED_RADII = (0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 2.75,
               3.0, 3.25, 3.5, 3.75, 4.0)
SPEED_VALUES = (0.72, 1.17, 1.62, 2.06, 2.47, 2.87, 3.27, 3.67, 4.0, 5.43, 6.59, 7.46, 8.1, 8.58, 8.91, 9.11, 9.2,
                9.23, 9.23, 9.23, 9.23, 9.23, 9.23)
#: the application divides the table's speeds by 4 (rr §5.2.2)
APP_SLOWDOWN = 4.0
#: the text's mask and capture resolution (rr §3.1.1, §3.1.2)
MASK_SIZE = 512
#: capture camera FOVy [deg]: the text's contract, the printed chain of rr-der-3.2.1 (the exact value is 165.0)
CAPTURE_FOV_DEG = 150.0
#: exact trace: internal reflections followed, march steps, bisection steps (C: CCL_RAIN_MASK_MAX_REFLECTIONS, ...)
MAX_REFLECTIONS = 3
TRACE_STEPS = 64
TRACE_BISECTIONS = 32

#: pi rounded to float32 (3.1415927): the upper edge of theta, so that float32(pi) itself is accepted
_PI_F32 = float(np.float32(math.pi))
_N_TERMS = 11
_CoefVec = wp.types.vector(length=_N_TERMS, dtype=wp.float32)
_ShapeMat = wp.types.matrix(shape=(4, _N_TERMS), dtype=wp.float32)
_SpeedVec = wp.types.vector(length=23, dtype=wp.float32)
_BC_C = wp.constant(_ShapeMat(*[float(c) for row in SHAPE_TABLE for c in row]))
_BC_A = wp.constant(wp.vec4(*SHAPE_RADII))
_TS_R = wp.constant(_SpeedVec(*SPEED_RADII))
_TS_V = wp.constant(_SpeedVec(*SPEED_VALUES))
_PI = wp.constant(3.14159265358979323846)
_VOLUME_INTERVALS = wp.constant(128)
_AXIS_SAMPLES = wp.constant(1024)
_EXTENT_SAMPLES = wp.constant(64)
_STEPS = wp.constant(TRACE_STEPS)
_BISECT = wp.constant(TRACE_BISECTIONS)
_MAXREFL = wp.constant(MAX_REFLECTIONS)

INTERP_TABLE = c_constant("CCL_RAIN_INTERP_TABLE", 0)
INTERP_LINEAR = c_constant("CCL_RAIN_INTERP_LINEAR", 1)
MAPPING_OFFSET = c_constant("CCL_RAIN_MAPPING_OFFSET", 0)
MAPPING_PROJECT = c_constant("CCL_RAIN_MAPPING_PROJECT", 1)
INTERP = Option("interp", {"table": INTERP_TABLE, "linear": INTERP_LINEAR}, "table",
                "'table': only the tabulated radii a = 0.5, 1, 3, 4.5 mm; 'linear': coefficients linear in a between "
                "rows, a in [0.5, 4.5] (an assumption: Table 2.1 has no 1.5-2.5 mm rows)")
MASK_SPHERE = c_constant("CCL_RAIN_MASK_SPHERE", 0)
MASK_OUTLINE = c_constant("CCL_RAIN_MASK_OUTLINE", 1)
MASK_EXACT = c_constant("CCL_RAIN_MASK_EXACT", 2)
FILTER_NEAREST = c_constant("CCL_RAIN_FILTER_NEAREST", 0)
FILTER_LINEAR = c_constant("CCL_RAIN_FILTER_LINEAR", 1)
METHOD = Option("method", {"sphere": MASK_SPHERE, "outline": MASK_OUTLINE, "exact": MASK_EXACT}, "sphere",
                "'sphere': a spherical drop (the text's refraction); 'outline': the application -- Beard-Chuang "
                "outline, sphere refraction stretched onto it; 'exact': rays traced through both surfaces of the "
                "Beard-Chuang drop (beyond the text)")
MAPPING = Option("mapping", {"offset": MAPPING_OFFSET, "project": MAPPING_PROJECT}, "offset",
                 "'offset': the shader's P_c = P_o + refract.xy / refract.z (scaled to capture uv); 'project': the "
                 "exit direction rotated into camera space and projected (exact for any drop position)")
FILTER = Option("filter", {"nearest": FILTER_NEAREST, "linear": FILTER_LINEAR}, "nearest",
                "capture filtering: 'nearest' (rr §3.1.2: sufficient) or 'linear' (the FBO code's GL_LINEAR)")

_REFS_SHAPE = ("Beard & Chuang, A new model for the equilibrium shape of raindrops, J. Atmos. Sci. 44 (1987) "
               "1509-1520", "Rousseau, Jolivet & Ghazanfarpour, Realistic real-time rain rendering, Computers & "
               "Graphics 30 (2006) 507-518, Table 1")


def _is_row(a) -> np.ndarray:
    a = np.asarray(a, dtype=np.float32)
    return np.isin(a, np.asarray(SHAPE_RADII, dtype=np.float32))


def _check_a(a, interp="table", **_):
    if interp == "table" and not np.all(_is_row(a)):
        bad = np.asarray(a)[~_is_row(a)].flat[0]
        raise ValueError(f"a must be one of the tabulated radii {SHAPE_RADII} mm with interp='table' (Table 2.1 has "
                         f"no other rows), got {bad!r}; pass interp='linear' to interpolate the coefficients")


def _a_samples(rng, n):
    return {"a": rng.choice(np.asarray(SHAPE_RADII, np.float32), size=n)}


_A = Arg("a", "drop radius of Table 2.1 [mm]: 0.5, 1, 3 or 4.5 (interp='table'), [0.5, 4.5] (interp='linear')",
         lo=0.5, hi=4.5, unit_name="mm")


# --- drop shape --------------------------------------------------------------------------------------------------------

@wp.func
def _interp_ok(a: float, interp: int) -> int:
    if interp == INTERP_TABLE:
        for k in range(4):
            if a == _BC_A[k]:
                return 1
        return 0
    if interp == INTERP_LINEAR:
        if a >= 0.5 and a <= 4.5:
            return 1
    return 0


@declare("rr-tab-2.1", c="ccl_rain_drop_coefficient",
         args=(Arg("n", "index n of C_n", lo=0, hi=10), _A), options=(INTERP,), outputs=("C_n",),
         check=lambda n, a, interp: _check_a(a, interp), samples=lambda rng, n: {**_a_samples(rng, n),
                                                                                   "n": rng.integers(0, 11, n)},
         summary="Beard-Chuang shape coefficient C_n = (Table 2.1 entry) x 1e-4 for the drop radius a.",
         references=_REFS_SHAPE)
@wp.func
def rain_drop_coefficient(n: int, a: float, interp: int) -> float:
    """rr-tab-2.1: C_n of the row a (or linearly interpolated between rows with interp 1)."""
    if n < 0 or n > 10 or _interp_ok(a, interp) == 0:
        return wp.nan
    if interp == INTERP_TABLE:
        for k in range(4):
            if a == _BC_A[k]:
                return _BC_C[k, n] * 1e-4
    k = int(0)
    for _j in range(2):
        if k < 2 and a >= _BC_A[k + 1]:
            k = k + 1
    w = (a - _BC_A[k]) / (_BC_A[k + 1] - _BC_A[k])
    return _BC_C[k, n] * 1e-4 * (1.0 - w) + _BC_C[k + 1, n] * 1e-4 * w


@wp.func
def _coefs(a: float, interp: int, deform: float) -> _CoefVec:
    c = _CoefVec()
    for n in range(11):
        c[n] = deform * rain_drop_coefficient(n, a, interp)
    return c


@wp.func
def _shape_eval(c: _CoefVec, cos_t: float, sin_t: float) -> tuple[float, float]:
    """(s, ds): s = r / a = 1 + sum c_n cos(n theta), ds = -sum n c_n sin(n theta) (rotation recurrence)."""
    cn = float(1.0)
    sn = float(0.0)
    s = float(0.0)
    d = float(0.0)
    s = s + c[0] * cn
    for n in range(1, 11):
        cn1 = cn * cos_t - sn * sin_t
        sn = sn * cos_t + cn * sin_t
        cn = cn1
        s = s + c[n] * cn
        d = d - float(n) * c[n] * sn
    return 1.0 + s, d


@declare("rr-eq1", c="ccl_rain_drop_radius",
         args=(Arg("theta", "angle from the downward vertical [rad] (0 = down, pi = up)", lo=0.0, hi=_PI_F32,
                   unit_name="rad"), _A),
         options=(INTERP,), outputs=("r",), check=lambda theta, a, interp: _check_a(a, interp), samples=_a_samples,
         summary="Beard-Chuang equilibrium drop shape r(theta) = a (1 + sum_{n=0}^{10} C_n cos(n theta)) [mm]; "
                 "theta = 0 points down. a = 1: r(0) = 0.9277, r(pi/2) = 1.0236, r(pi) = 0.9683.",
         references=_REFS_SHAPE)
@wp.func
def rain_drop_radius(theta: float, a: float, interp: int) -> float:
    """rr-eq1: r(theta) [mm]."""
    c = _coefs(a, interp, 1.0)
    s, ds = _shape_eval(c, wp.cos(theta), wp.sin(theta))
    return a * s


@wp.func
def _shape_normal(s: float, ds: float, cos_t: float, sin_t: float, cos_p: float, sin_p: float) -> wp.vec3:
    nr = s * sin_t - ds * cos_t
    ny = -(s * cos_t + ds * sin_t)
    return wp.normalize(wp.vec3(nr * cos_p, ny, nr * sin_p))


@wp.func
def rain_drop_surface(theta: float, phi: float, a: float, interp: int) -> tuple[wp.vec3, wp.vec3]:
    """Point [mm] and outward unit normal of the axisymmetric drop at (theta, phi) (rr-eq1, the 3-D surface)."""
    c = _coefs(a, interp, 1.0)
    ct = wp.cos(theta)
    st = wp.sin(theta)
    cp = wp.cos(phi)
    sp = wp.sin(phi)
    s, ds = _shape_eval(c, ct, st)
    r = a * s
    return wp.vec3(r * st * cp, -r * ct, r * st * sp), _shape_normal(s, ds, ct, st, cp, sp)


@wp.func
def rain_drop_volume(a: float, interp: int) -> float:
    """Volume [mm^3] = (2 pi / 3) int r^3 sin(theta) d theta (Simpson, 128 intervals)."""
    c = _coefs(a, interp, 1.0)
    h = _PI / float(_VOLUME_INTERVALS)
    acc = float(0.0)
    for k in range(_VOLUME_INTERVALS + 1):
        th = float(k) * h
        s, ds = _shape_eval(c, wp.cos(th), wp.sin(th))
        w = float(2.0)
        if k == 0 or k == _VOLUME_INTERVALS:
            w = 1.0
        elif k % 2 == 1:
            w = 4.0
        acc = acc + w * (s * s * s * wp.sin(th))
    return (2.0 * _PI / 3.0) * (h / 3.0) * acc * (a * a * a)


@wp.func
def rain_drop_axis_ratio(a: float, interp: int) -> float:
    """Height / width = (r(0) + r(pi)) / (2 max r sin theta) (1025 samples)."""
    c = _coefs(a, interp, 1.0)
    wmax = float(0.0)
    for k in range(_AXIS_SAMPLES + 1):
        th = float(k) * (_PI / float(_AXIS_SAMPLES))
        s, ds = _shape_eval(c, wp.cos(th), wp.sin(th))
        wmax = wp.max(wmax, s * wp.sin(th))
    s0, d0 = _shape_eval(c, 1.0, 0.0)
    s1, d1 = _shape_eval(c, -1.0, 0.0)
    return (s0 + s1) / (2.0 * wmax)


@wp.func
def _shape_extent(c: _CoefVec) -> float:
    h = _PI / float(_EXTENT_SAMPLES)
    smax = float(0.0)
    bound = float(0.0)
    for k in range(_EXTENT_SAMPLES + 1):
        th = float(k) * h
        s, ds = _shape_eval(c, wp.cos(th), wp.sin(th))
        smax = wp.max(smax, s)
    for n in range(1, 11):
        bound = bound + float(n * n) * wp.abs(c[n])
    return smax + (h * h * 0.125) * bound


@wp.func
def rain_drop_extent(a: float, interp: int) -> float:
    """Half-size L [mm] of the drop's mask and billboard: a bound of max r(theta), = a for a sphere."""
    return a * _shape_extent(_coefs(a, interp, 1.0))


# --- terminal speed ----------------------------------------------------------------------------------------------------

#: Smallest slowdown (divisor of the terminal speed) accepted, 1/64 (exact in float32): speeds up to 64 times the
#: physical ones; a tiny divisor (1e-45) overflowed the speed to inf (ccl_rain_terminal_speed and
#: ccl_particles_params_check alike).
MIN_SLOWDOWN = 0.015625


@declare("rr-tab-2.2", c="ccl_rain_terminal_speed",
         args=(Arg("radius_mm", "drop radius [mm] (Table 2.2 is indexed by radius)", lo=0.0, hi=10.0, unit_name="mm"),
               Arg("slowdown", "divisor of the speed: 1 physical, 4 the application's (rr §5.2.2)", lo=MIN_SLOWDOWN,
                   hi=1000.0, default=1.0)),
         outputs=("speed",),
         summary="Terminal speed [m/s] / slowdown from Table 2.2 (23 rows): linear between rows, Stokes "
                 "0.72 (r/0.1)^2 below 0.1 mm, plateau 9.23 m/s from 4 mm (reached at 2.75 mm).",
         references=("Gunn & Kinzer, The terminal velocity of fall for water droplets in stagnant air, J. Meteorol. "
                     "6 (1949) 243-248", "Rousseau, Jolivet & Ghazanfarpour 2006, Table 2"))
@wp.func
def rain_terminal_speed(radius_mm: float, slowdown: float) -> float:
    """rr-tab-2.2: terminal speed [m/s] divided by ``slowdown``."""
    r = radius_mm
    v = float(0.0)
    if r < _TS_R[0]:
        q = r / _TS_R[0]
        v = _TS_V[0] * (q * q)
    elif r >= _TS_R[22]:
        v = _TS_V[22]
    else:
        k = int(0)
        for _j in range(21):
            if k < 21 and r >= _TS_R[k + 1]:
                k = k + 1
        w = (r - _TS_R[k]) / (_TS_R[k + 1] - _TS_R[k])
        # V_k + w (V_k+1 - V_k), the difference exact: non-decreasing in the radius (as ccl_rain_terminal_speed)
        v = _TS_V[k] + w * (_TS_V[k + 1] - _TS_V[k])
    return v / slowdown


# --- refraction masks --------------------------------------------------------------------------------------------------

@wp.func
def _drop_f(c: _CoefVec, p: wp.vec3) -> float:
    r = wp.length(p)
    if r == 0.0:
        return -1.0
    rh = wp.sqrt(p[0] * p[0] + p[2] * p[2])
    s, ds = _shape_eval(c, -p[1] / r, rh / r)
    return r - s


@wp.func
def _drop_normal(c: _CoefVec, p: wp.vec3) -> wp.vec3:
    r = wp.length(p)
    if r == 0.0:
        return wp.vec3(0.0, -1.0, 0.0)
    rh = wp.sqrt(p[0] * p[0] + p[2] * p[2])
    ct = -p[1] / r
    st = rh / r
    cp = float(1.0)
    sp = float(0.0)
    if rh > 0.0:
        cp = p[0] / rh
        sp = p[2] / rh
    s, ds = _shape_eval(c, ct, st)
    return _shape_normal(s, ds, ct, st, cp, sp)


@wp.func
def _exit_hit(sphere: int, c: _CoefVec, ext: float, pos: wp.vec3, dir: wp.vec3) -> tuple[wp.vec3, wp.vec3]:
    if sphere != 0:
        s = -2.0 * wp.dot(pos, dir)
        q = pos + dir * s
        return q, wp.normalize(q)
    b = wp.dot(pos, dir)
    cc = wp.dot(pos, pos) - ext * ext
    smax = -b + wp.sqrt(wp.max(b * b - cc, 0.0))
    lo = float(0.0)
    hi = smax
    found = int(0)
    for k in range(1, _STEPS + 1):
        s = smax * (float(k) / float(_STEPS))
        if found == 0:
            if _drop_f(c, pos + dir * s) > 0.0:
                hi = s
                found = 1
            else:
                lo = s
    for _k in range(_BISECT):
        mid = 0.5 * (lo + hi)
        if _drop_f(c, pos + dir * mid) > 0.0:
            hi = mid
        else:
            lo = mid
    q = pos + dir * (0.5 * (lo + hi))
    return q, _drop_normal(c, q)


def _mask_samples(rng, n):
    return {**_a_samples(rng, n), "u": rng.uniform(-1, 1, n).astype(np.float32),
            "v": rng.uniform(-1, 1, n).astype(np.float32)}


# The exact trace bisects the surface to float precision; a 1-ulp difference of cos/sin between libm and Warp can
# move the hit point by a few ulp and the exit direction by a few ulp times the conditioning of the two refractions
# (observed <= 40 ulp on the contract samples, up to ~1e-5 absolute next to the rim where the exit direction's
# derivative grows without bound).
@declare("rr-alg-3.1.1", c="ccl_rain_mask_texel",
         args=(Arg("u", "mask coordinate, right", lo=-1.0, hi=1.0), Arg("v", "mask coordinate, up", lo=-1.0, hi=1.0),
               _A, Arg("deform", "scale of every C_n (0 = sphere, 1 = Beard-Chuang)", lo=0.0, hi=1.0, default=1.0),
               Arg("n_water", "relative refractive index of the drop (1.33)", lo=1.0, hi=2.0, default=1.33)),
         options=(INTERP, METHOD), outputs=("exit_dir", "normal", "inside"),
         check=lambda u, v, a, deform, n_water, interp, method: _check_a(a, interp), samples=_mask_samples,
         ulp=64,
         summary="Refraction-mask texel: the direction (mask frame: x right, y up, z along the view) in which the "
                 "view ray through (u, v) leaves the drop, the outward normal at its entry point and the inside "
                 "flag; (0, 0, 0) outside or when no exit is found after 3 internal reflections.",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §4.1 (refraction masks)",) + _REFS_SHAPE)
@wp.func
def rain_mask_texel(u: float, v: float, a: float, deform: float, n_water: float, interp: int,
                    method: int) -> tuple[wp.vec3, wp.vec3, int]:
    """rr-alg-3.1.1: (exit direction, entry normal, inside)."""
    zero = wp.vec3(0.0, 0.0, 0.0)
    c = _CoefVec()
    ext = float(1.0)
    x = u
    y = v
    sphere = int(1)
    if method == MASK_EXACT:
        sphere = 0
    if method == MASK_SPHERE:
        if x * x + y * y > 1.0:
            return zero, zero, 0
    else:
        c = _coefs(a, interp, deform)
        ext = _shape_extent(c)
        x = u * ext
        y = v * ext
        rho = wp.sqrt(x * x + y * y)
        s = float(1.0)
        if rho > 0.0:
            s, ds = _shape_eval(c, -y / rho, wp.abs(x) / rho)
        if rho > s:
            return zero, zero, 0
        if method == MASK_OUTLINE:
            x = x / s
            y = y / s
    p = wp.vec3(0.0, 0.0, 0.0)
    nrm = wp.vec3(0.0, 0.0, 0.0)
    if sphere != 0:
        p = wp.vec3(x, y, -wp.sqrt(wp.max(1.0 - x * x - y * y, 0.0)))
        nrm = wp.normalize(p)
    else:
        h = wp.sqrt(wp.max(ext * ext - (x * x + y * y), 0.0))
        lo = -h
        hi = float(0.0)
        found = int(0)
        for k in range(1, _STEPS + 1):
            z = -h + h * (float(k) / float(_STEPS))
            if found == 0:
                if _drop_f(c, wp.vec3(x, y, z)) <= 0.0:
                    hi = z
                    found = 1
                else:
                    lo = z
        for _k in range(_BISECT):
            mid = 0.5 * (lo + hi)
            if _drop_f(c, wp.vec3(x, y, mid)) <= 0.0:
                hi = mid
            else:
                lo = mid
        p = wp.vec3(x, y, 0.5 * (lo + hi))
        nrm = _drop_normal(c, p)
    d = wp.vec3(0.0, 0.0, 1.0)
    dir, r0, tir0 = optics_snell(d, nrm, 1.0, n_water)
    e = zero
    done = int(0)
    for _k in range(_MAXREFL + 1):
        if done == 0:
            q, nq = _exit_hit(sphere, c, ext, p, dir)
            out, r, tir = optics_snell(dir, nq, n_water, 1.0)
            if tir != 0 and sphere != 0:
                # a sphere reflects nothing totally; at the rim rounding can make k < 0: leave tangentially
                out = wp.normalize(dir - nq * wp.dot(dir, nq))
                tir = 0
            if tir == 0:
                e = out
                done = 1
            else:
                p = q
                dir = r
    return e, nrm, 1


# --- drop pixel colour -------------------------------------------------------------------------------------------------

@wp.func
def _billboard_frame(f: wp.vec3) -> tuple[wp.vec3, wp.vec3]:
    rt = wp.cross(f, wp.vec3(0.0, 1.0, 0.0))
    ln = wp.length(rt)
    if ln > 1e-6:
        rt = rt * (1.0 / ln)
    else:
        rt = wp.vec3(1.0, 0.0, 0.0)
    return rt, wp.cross(rt, f)


#: Smallest tan_half_fov and aspect of rr-alg-3.1.3, 1/64 (exact in float32; a 1.8 deg capture, a 1:64 frame): the uv
#: scales s_x = 0.5 / (tan_half_fov aspect) <= 2048, s_y <= 32 stay finite (1e-45 overflowed P_o and P_c to +-inf).
MIN_PROJECTION = 0.015625
_TAN = Arg("tan_half_fov", "tan(fov_y / 2) of the capture camera (150 deg: 3.7321)", lo=MIN_PROJECTION, hi=100.0)
_ASPECT = Arg("aspect", "capture width / height", lo=MIN_PROJECTION, hi=100.0, default=1.0)


@declare("rr-alg-3.1.3", c="ccl_rain_refracted_uv",
         args=(Arg("view_dir", "unit direction eye -> P_i (camera space, OpenGL: looking down -z)", unit=True),
               Arg("exit_dir", "mask texel: exit direction in the mask frame", lo=-1.0, hi=1.0), _TAN, _ASPECT),
         options=(MAPPING,), outputs=("P_c", "P_o", "valid"),
         nonfinite="a direction at 90 deg to the view axis projects to infinity: where exit_dir.z > 0 (or -view_dir.z "
                   "> 0, or w.z < 0 for 'project') is below ~1e-38 of its other components, e.x / e.z overflows and "
                   "P_c (P_o) is +-inf, NaN where two such infinities cancel (the capture sampler clamps to the border)",
         summary="P_i -> P_o -> P_c: P_o = capture uv of the undeviated view direction, (0.5 + s_x c.x/(-c.z), "
                 "0.5 - s_y c.y/(-c.z)), s_x = 0.5/(tan_half_fov aspect), s_y = 0.5/tan_half_fov; 'offset': P_c = "
                 "P_o + (s_x e.x/e.z, -s_y e.y/e.z) (the shader); 'project': the exit direction in camera space "
                 "projected. valid = 0 (and P_c = P_o = 0) where e.z <= 0 or a direction points backwards.",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §4.2 (Fig. 6)",))
@wp.func
def rain_refracted_uv(view_dir: wp.vec3, exit_dir: wp.vec3, tan_half_fov: float, aspect: float,
                      mapping: int) -> tuple[wp.vec2, wp.vec2, int]:
    """rr-alg-3.1.3: (P_c, P_o, valid)."""
    sx = 0.5 / (tan_half_fov * aspect)
    sy = 0.5 / tan_half_fov
    f = view_dir
    zero = wp.vec2(0.0, 0.0)
    if not (f[2] < 0.0) or not (exit_dir[2] > 0.0):
        return zero, zero, 0
    po = wp.vec2(0.5 + sx * (f[0] / -f[2]), 0.5 - sy * (f[1] / -f[2]))
    pc = zero
    if mapping == MAPPING_OFFSET:
        pc = wp.vec2(po[0] + sx * (exit_dir[0] / exit_dir[2]), po[1] - sy * (exit_dir[1] / exit_dir[2]))
    else:
        rt, uu = _billboard_frame(f)
        w = rt * exit_dir[0] + uu * exit_dir[1] + f * exit_dir[2]
        if not (w[2] < 0.0):
            return zero, zero, 0
        pc = wp.vec2(0.5 + sx * (w[0] / -w[2]), 0.5 - sy * (w[1] / -w[2]))
    return pc, po, 1


@wp.func
def _floor_clamped(x: float, lo: int, hi: int) -> int:
    xc = wp.min(wp.max(x, float(lo) - 1.0), float(hi) + 1.0)
    return wp.clamp(int(wp.floor(xc)), lo, hi)


@wp.func
def rain_sample_capture(rgb: wp.array2d(dtype=wp.vec3), uv: wp.vec2, filter: int) -> wp.vec3:
    """Capture colour at uv (v down), nearest or bilinear (texel centres at (j + 0.5)/width), edges clamped."""
    height = rgb.shape[0]
    width = rgb.shape[1]
    if filter == FILTER_NEAREST:
        return rgb[_floor_clamped(uv[1] * float(height), 0, height - 1),
                   _floor_clamped(uv[0] * float(width), 0, width - 1)]
    x = wp.min(wp.max(uv[0] * float(width) - 0.5, -1.0), float(width))
    y = wp.min(wp.max(uv[1] * float(height) - 0.5, -1.0), float(height))
    fx = x - wp.floor(x)
    fy = y - wp.floor(y)
    j0 = wp.clamp(int(wp.floor(x)), 0, width - 1)
    j1 = wp.clamp(int(wp.floor(x)) + 1, 0, width - 1)
    i0 = wp.clamp(int(wp.floor(y)), 0, height - 1)
    i1 = wp.clamp(int(wp.floor(y)) + 1, 0, height - 1)
    top = rgb[i0, j0] * (1.0 - fx) + rgb[i0, j1] * fx
    bot = rgb[i1, j0] * (1.0 - fx) + rgb[i1, j1] * fx
    return top * (1.0 - fy) + bot * fy


@wp.func
def rain_shade_pixel(capture: wp.array2d(dtype=wp.vec3), mask: wp.array2d(dtype=wp.vec4), f: wp.vec3, rt: wp.vec3,
                     uu: wp.vec3, t: float, u: float, v: float, tan_half_fov: float, aspect: float, mapping: int,
                     filter: int) -> wp.vec4:
    """rr-alg-3.1 for one billboard pixel (u, v) of a drop facing f (frame rt, uu, tan of its angular radius t):
    mask lookup (nearest), outside -> 0; inside -> the capture colour at P_c, alpha 1 (black where no ray exits)."""
    ms = mask.shape[0]
    mi = wp.clamp(int(wp.floor((1.0 - v) * 0.5 * float(ms))), 0, ms - 1)
    mj = wp.clamp(int(wp.floor((u + 1.0) * 0.5 * float(ms))), 0, ms - 1)
    m = mask[mi, mj]
    if not (m[3] > 0.0):
        return wp.vec4(0.0, 0.0, 0.0, 0.0)
    dir = wp.normalize(f + (rt * u + uu * v) * t)
    pc, po, valid = rain_refracted_uv(dir, wp.vec3(m[0], m[1], m[2]), tan_half_fov, aspect, mapping)
    if valid == 0:
        return wp.vec4(0.0, 0.0, 0.0, 1.0)
    col = rain_sample_capture(capture, pc, filter)
    return wp.vec4(col[0], col[1], col[2], 1.0)


@wp.kernel
def shade_drop_kernel(row0: int, capture: wp.array2d(dtype=wp.vec3), mask: wp.array2d(dtype=wp.vec4), f: wp.vec3,
                      t: float, tan_half_fov: float, aspect: float, mapping: int, filter: int,
                      out: wp.array2d(dtype=wp.vec4)):
    i0, j = wp.tid()
    i = row0 + i0
    n = out.shape[0]
    u = 2.0 * (float(j) + 0.5) / float(n) - 1.0
    v = 1.0 - 2.0 * (float(i) + 0.5) / float(n)
    rt, uu = _billboard_frame(f)
    out[i, j] = rain_shade_pixel(capture, mask, f, rt, uu, t, u, v, tan_half_fov, aspect, mapping, filter)


# Not element-wise: the capture and the mask are whole textures shared by every pixel of the billboard.
@declare("rr-alg-3.1", c="ccl_rain_shade_drop", make_warp="pywarp.rain.drops:shade_drop_warp",
         make_c="pywarp.rain.drops:shade_drop_c",
         summary="One drop billboard: mask lookup (inside flag, refraction vector), P_o of the undeviated view "
                 "direction, P_c = P_o + refraction, capture colour at P_c (nearest or linear); see rain_shade_pixel "
                 "for the per-pixel @wp.func used by the rain scene.",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §4",))
@wp.func
def rain_shade_drop(capture: wp.array2d(dtype=wp.vec3), mask: wp.array2d(dtype=wp.vec4), f: wp.vec3, t: float,
                    tan_half_fov: float, aspect: float, mapping: int, filter: int, u: float, v: float) -> wp.vec4:
    """rr-alg-3.1 for the billboard pixel (u, v) of a drop seen in direction f (angular radius atan(t))."""
    rt, uu = _billboard_frame(f)
    return rain_shade_pixel(capture, mask, f, rt, uu, t, u, v, tan_half_fov, aspect, mapping, filter)


def _parallax_samples(rng, n):
    d = rng.normal(size=(n, 3))
    p = d / np.linalg.norm(d, axis=1, keepdims=True) * rng.uniform(0.0, 5.0, (n, 1))
    e = rng.normal(size=(n, 3))
    return {"p": p.astype(np.float32), "e": (e / np.linalg.norm(e, axis=1, keepdims=True)).astype(np.float32),
            "R": rng.uniform(6.0, 1000.0, n).astype(np.float32)}


_PARALLAX_SQUARE_MIN = wp.constant(2.0 ** -60)  # the radii whose square is a normal float (C: PARALLAX_SQUARE_MIN)
_PARALLAX_SQUARE_MAX = wp.constant(2.0 ** 60)


@declare("rr-alg-3.2.2", c="ccl_rain_capture_parallax",
         args=(Arg("p", "drop position relative to the viewer", sample_range=(-5.0, 5.0)),
               Arg("e", "unit direction leaving the drop", unit=True),
               Arg("R", "radius of the background sphere around the viewer", lo=0.0, lo_open=True)),
         outputs=("angle",), samples=_parallax_samples,
         summary="The accepted approximation of one capture from the viewer, measured: the angle [rad] between the "
                 "exit direction e and the direction from the viewer to the background point the drop at p really "
                 "sees (background: sphere of radius R around the viewer); ~ |p| sin(p, e) / R. NaN where |p| >= R "
                 "(the drop is not inside the background).",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §4.3",))
@wp.func
def rain_capture_parallax(p: wp.vec3, e: wp.vec3, R: float) -> float:
    """rr-alg-3.2.2: angular error [rad] of the single viewer-centred capture. The angle does not depend on the
    scale: a radius whose square under- or overflows (0 or Inf: NaN) is divided out, p / R and R = 1, as C."""
    pr = p
    r = R
    if not (R >= _PARALLAX_SQUARE_MIN and R <= _PARALLAX_SQUARE_MAX):
        pr = wp.vec3(p[0] / R, p[1] / R, p[2] / R)
        r = 1.0
    pp = wp.dot(pr, pr)
    if not (pp < r * r):
        return wp.nan
    pe = wp.dot(pr, e)
    s = -pe + wp.sqrt(wp.max(pe * pe - pp + r * r, 0.0))
    q = pr + e * s
    return wp.atan2(wp.length(wp.cross(e, q)), wp.dot(e, q))


# --- light-drop interaction --------------------------------------------------------------------------------------------

_RHALF = Arg("r_half", "DistFact half-intensity distance (DistFact = 1 / (1 + (d / r_half)^2))", lo=0.0, lo_open=True,
             sample_range=(0.1, 10.0))
_COLOUR = dict(lo=0.0, sample_range=(0.0, 2.0))
_VN = Arg("v_n", "unit drop normal at the pixel (drop frame, y up)", unit=True)
_VPL = Arg("v_pl", "unit direction pixel -> light", unit=True)


@declare("rr-A1", c="ccl_rain_light_a1",
         args=(Arg("c_l", "light colour C_L (RGB)", **_COLOUR),
               Arg("dist", "pixel-light distance", lo=0.0, sample_range=(0.0, 10.0)),
               Arg("v_pe", "unit direction pixel -> eye", unit=True), _VN, _RHALF),
         options=(VARIANT,), outputs=("A1",),
         summary="A1 = C_L DistFact (V_PE . V_N), DistFact = 1/(1 + (dist/r_half)^2). variant='corrected': the dot "
                 "product clamped at 0; 'thesis': unclamped as printed.",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §5",))
@wp.func
def rain_light_a1(c_l: wp.vec3, dist: float, v_pe: wp.vec3, v_n: wp.vec3, r_half: float, variant: int) -> wp.vec3:
    """rr-A1: the largest colour change of the pixel by one light."""
    q = dist / r_half
    dist_fact = 1.0 / (1.0 + q * q)
    cosv = wp.dot(v_pe, v_n)
    if variant != VARIANT_THESIS:
        cosv = wp.max(cosv, 0.0)
    return c_l * (dist_fact * cosv)


@declare("rr-A2", c="ccl_rain_light_a2", args=(_VPL, _VN), outputs=("A2",),
         summary="A2 = max(0, V_PL . V_N): external reflection back towards the light, in [0, 1].",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §5",))
@wp.func
def rain_light_a2(v_pl: wp.vec3, v_n: wp.vec3) -> float:
    """rr-A2, at most 1 where the dot of unit vectors rounds above it (as ccl_rain_light_a2)."""
    return wp.min(wp.max(0.0, wp.dot(v_pl, v_n)), 1.0)


@declare("rr-A3", c="ccl_rain_light_a3", args=(_VPL, _VN), outputs=("A3",),
         summary="A3 = max(0, (-V_PL2D . V_N2D)(1 - (-V_PL . V_N))): internal reflections leaving up or down; 2-D = "
                 "horizontal (x, z) projection, normalised; a projection shorter than 1e-6 (vertical vector) makes "
                 "the horizontal factor 0. Range [0, 2).",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §5",))
@wp.func
def rain_light_a3(v_pl: wp.vec3, v_n: wp.vec3) -> float:
    """rr-A3 with the guard for vertical vectors."""
    lh = wp.sqrt(v_pl[0] * v_pl[0] + v_pl[2] * v_pl[2])
    nh = wp.sqrt(v_n[0] * v_n[0] + v_n[2] * v_n[2])
    horiz = float(0.0)
    if lh >= 1e-6 and nh >= 1e-6:
        horiz = -((v_pl[0] / lh) * (v_n[0] / nh) + (v_pl[2] / lh) * (v_n[2] / nh))
    return wp.max(0.0, horiz * (1.0 - (-wp.dot(v_pl, v_n))))


@wp.func
def _one_light(p: wp.vec3, n: wp.vec3, v_pe: wp.vec3, l: wp.vec3, c_l: wp.vec3, r_half: float,
               variant: int) -> wp.vec3:
    d = l - p
    dist = wp.length(d)
    v_pl = wp.normalize(d)
    a1 = rain_light_a1(c_l, dist, v_pe, n, r_half, variant)
    return a1 * (rain_light_a2(v_pl, n) + rain_light_a3(v_pl, n))


_POS = dict(sample_range=(-10.0, 10.0))


@declare("rr-CF", c="ccl_rain_light_colour",
         args=(Arg("c_o", "refracted colour C_O from the capture", **_COLOUR),
               Arg("c_amb", "ambient light colour C_amb", **_COLOUR),
               Arg("p", "pixel position on the drop (drop frame, y up)", **_POS),
               Arg("n", "unit normal at p", unit=True), Arg("eye", "eye position", **_POS),
               Arg("l1", "position of light 1", **_POS), Arg("c_l1", "colour of light 1 (0 = off)", **_COLOUR),
               Arg("l2", "position of light 2", **_POS), Arg("c_l2", "colour of light 2 (0 = off)", **_COLOUR),
               _RHALF),
         options=(VARIANT,), outputs=("C_F",),
         summary="C_F = C_O C_amb + sum over two point lights of A1 (A2 + A3) (component-wise; no clamp), with "
                 "V_PE, V_PL and the distances from the positions. variant as rr-A1.",
         references=("Rousseau, Jolivet & Ghazanfarpour 2006, §5",))
@wp.func
def rain_light_colour(c_o: wp.vec3, c_amb: wp.vec3, p: wp.vec3, n: wp.vec3, eye: wp.vec3, l1: wp.vec3,
                      c_l1: wp.vec3, l2: wp.vec3, c_l2: wp.vec3, r_half: float, variant: int) -> wp.vec3:
    """rr-CF: the final drop pixel colour with two point lights."""
    v_pe = wp.normalize(eye - p)
    base = wp.vec3(c_o[0] * c_amb[0], c_o[1] * c_amb[1], c_o[2] * c_amb[2])
    base = base + _one_light(p, n, v_pe, l1, c_l1, r_half, variant)
    return base + _one_light(p, n, v_pe, l2, c_l2, r_half, variant)


# --- whole-shape helpers (not catalogue entries: evaluators of the unregistered shape functions) ----------------------

@wp.kernel
def scalar_shape_kernel(which: int, a: wp.array(dtype=float), interp: int, out: wp.array(dtype=float)):
    i = wp.tid()
    if which == 0:
        out[i] = rain_drop_volume(a[i], interp)
    elif which == 1:
        out[i] = rain_drop_axis_ratio(a[i], interp)
    else:
        out[i] = rain_drop_extent(a[i], interp)


@wp.kernel
def surface_kernel(theta: wp.array(dtype=float), phi: wp.array(dtype=float), a: wp.array(dtype=float), interp: int,
                   out_p: wp.array(dtype=wp.vec3), out_n: wp.array(dtype=wp.vec3)):
    i = wp.tid()
    p, n = rain_drop_surface(theta[i], phi[i], a[i], interp)
    out_p[i] = p
    out_n[i] = n


@wp.kernel
def mask_kernel(row0: int, a: float, deform: float, n_water: float, interp: int, method: int,
                out: wp.array2d(dtype=wp.vec4), out_n: wp.array2d(dtype=wp.vec3)):
    i0, j = wp.tid()
    i = row0 + i0
    size = out.shape[0]
    v = 1.0 - 2.0 * (float(i) + 0.5) / float(size)
    u = 2.0 * (float(j) + 0.5) / float(size) - 1.0
    e, n, inside = rain_mask_texel(u, v, a, deform, n_water, interp, method)
    out[i, j] = wp.vec4(e[0], e[1], e[2], float(inside))
    out_n[i, j] = n


__all__ = ["SHAPE_RADII", "SHAPE_TABLE", "SPEED_RADII", "SPEED_VALUES", "APP_SLOWDOWN", "MASK_SIZE", "CAPTURE_FOV_DEG",
           "INTERP", "METHOD", "MAPPING", "FILTER",
           "rain_drop_coefficient", "rain_drop_radius", "rain_drop_surface", "rain_drop_volume", "rain_drop_axis_ratio",
           "rain_drop_extent", "rain_terminal_speed", "rain_mask_texel", "rain_refracted_uv", "rain_sample_capture",
           "rain_shade_pixel", "rain_shade_drop", "rain_capture_parallax", "rain_light_a1", "rain_light_a2",
           "rain_light_a3", "rain_light_colour"]
