"""View-ray geometry of the cloudscape (vc §2.2, §4.2.1, §4.3.2) -- Warp twins of ``cclouds/raymarch.h``.

Ray-sphere / ray-box intersection (vc-A14, vc-A35), the cloud-layer segment for a camera below, inside or above the
layer (vc-A14, vc-A24), the view-sample count (vc-A18), light samples in a cone (vc-A19), front-to-back accumulation
with early termination (vc-A21), ray jitter against banding (vc-A23), uniform marching in a bounding volume (vc-A35)
and the constants collected from the thesis (vc-A36). The camera and primary rays (vc-A25) are in
:mod:`pywarp.kernels.camera`, the PCG hash of the jitter in :mod:`pywarp.kernels.hash`.

Conventions (shared with the C header):
  * World frame y up, lengths in kilometres; the default planet centre is ``(0, -EARTH_RADIUS_KM, 0)`` so the ground
    under the origin is at y = 0 and float32 coordinates near the camera stay small.
  * Rays ``o + t d``; "no hit / no segment" is NaN in both distances (so ``t_end > t_start`` is false).
  * Positions, directions and colours are ``wp.vec3`` (NumPy ``(..., 3)`` arrays through the registry).
  * Every @wp.func performs the float32 operations of its C twin in the same order; the vector maths of
    ``cclouds/common.h`` is Warp's builtins (``wp.dot``, ``wp.length``, ``wp.normalize``, ``+ - *``).

Choices where the thesis gives no value (each a named parameter; see also the header comment of raymarch.h):
  * ``EARTH_RADIUS_KM = 6371``: IUGG mean Earth radius (6371.0088 km) rounded.
  * ``LAYER_BASE_KM = 1.5``, ``LAYER_TOP_KM = 4.0``: the thesis's layer is for low clouds (tops <= 2 km, §2.3.1); a
    base at a typical low-cloud condensation level and a top at 4 km leave room for cumulus towers growing through the
    2 km limit. Radii 6372.5 and 6375 km are exact in float32.
  * View samples ``N = round(mix(128, 64, |dir.y|))`` (vc-A18 does not state the law).
  * Light cone (vc-A19): ``LIGHT_STEP_KM = 0.1`` (5 near samples over 0.5 km, a cumulus core; the far one at
    1.5 km reaches a neighbouring cloud inside the 2.5 km layer), ``LIGHT_CONE_ANGLE = 15 deg`` (sideways spread ~1.3
    steps at the cone end), ``LIGHT_FAR_FACTOR = 3`` (the thesis), kernel ``LIGHT_CONE_KERNEL``.
  * Early termination (vc-A21): ``MARCH_EPS = 1/256``: stop when ``1 - T >= 1 - eps``.
  * Jitter (vc-A23): tilt by ``JITTER_AMOUNT = 0.002`` rad (about two pixel footprints of a 60 deg, 1080-row view),
    seeded by (x, y, frame) through the PCG hash (Jarzynski & Olano, JCGT 9(3), 2020); start-offset jitter optional.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import Arg, Option, declare
from .camera import _finite_float, _vec3_value
from .hash import hash_pcg, hash_unit

# --- named defaults ---------------------------------------------------------------------------------------------------

EARTH_RADIUS_KM = 6371.0
LAYER_BASE_KM = 1.5
LAYER_TOP_KM = 4.0
VIEW_SAMPLES_ZENITH = 64
VIEW_SAMPLES_HORIZON = 128
#: Largest n_max of raymarch_view_sample_count (CCL_RAYMARCH_MAX_VIEW_SAMPLES): far above the renderer's 4096, far
#: below 2^22, where n + 0.5 stops being exact in float32.
MAX_VIEW_SAMPLES = 65536
LIGHT_STEP_KM = 0.1
LIGHT_CONE_ANGLE = math.radians(15.0)
LIGHT_FAR_FACTOR = 3.0
MARCH_EPS = 1.0 / 256.0
JITTER_AMOUNT = 0.002

#: Six fixed pseudo-random unit vectors: u1 = pcg(2i)/2^32, u2 = pcg(2i+1)/2^32, z = 1 - 2 u1, phi = 2 pi u2,
#: k = (sqrt(1 - z^2) cos phi, sqrt(1 - z^2) sin phi, z) in float64, rounded to float32 (uniform on the sphere).
LIGHT_CONE_KERNEL = np.array([
    [-0.184916884, -0.288023561, 0.939599991],
    [-0.998808086, 0.0230856221, 0.0430054031],
    [-0.729488671, -0.0146079780, 0.683836877],
    [-0.464710385, 0.0182285905, -0.885275066],
    [-0.202527046, 0.584412575, 0.785776496],
    [-0.140362307, 0.982180178, 0.124982178],
], dtype=np.float32)
LIGHT_CONE_KERNEL.setflags(write=False)

_K = [wp.constant(wp.vec3(*map(float, k))) for k in LIGHT_CONE_KERNEL]
_K0, _K1, _K2, _K3, _K4, _K5 = _K

#: Jitter modes of :func:`raymarch_jitter` (``ccl_jitter_mode``).
JITTER_TILT = c_constant("CCL_JITTER_TILT", 0)
JITTER_OFFSET = c_constant("CCL_JITTER_OFFSET", 1)
JITTER_NONE = c_constant("CCL_JITTER_NONE", 2)
JITTER_MODES = {"tilt": JITTER_TILT, "offset": JITTER_OFFSET, "none": JITTER_NONE}


# --- Python-side objects: the cloud layer -----------------------------------------------------------------------------

def _f32(v) -> float:
    return float(np.float32(v))


@dataclass(frozen=True)
class CloudLayer:
    """The Earth sphere and the two spheres bounding the cloud layer (vc-A14), centre ``(0, -earth_radius, 0)``.

    Parameters (km): ``earth_radius`` (default 6371, IUGG mean radius), ``base_altitude`` (1.5) and ``top_altitude``
    (4.0) above the ground. Twin of ``ccl_raymarch_cloud_layer_init``.
    """

    earth_radius: float = EARTH_RADIUS_KM
    base_altitude: float = LAYER_BASE_KM
    top_altitude: float = LAYER_TOP_KM

    def __post_init__(self):
        er = _finite_float(self.earth_radius, "earth_radius")
        base = _finite_float(self.base_altitude, "base_altitude")
        top = _finite_float(self.top_altitude, "top_altitude")
        if er <= 0:
            raise ValueError(f"earth_radius must be > 0 km, got {er}")
        if base < 0:
            raise ValueError(f"base_altitude must be >= 0 km, got {base}")
        if not top > base:
            raise ValueError(f"top_altitude must be > base_altitude ({base}), got {top}")
        if not self.r_outer > self.r_inner:
            raise ValueError(f"top_altitude - base_altitude ({top - base}) is below the float32 resolution of the "
                             f"radius {er}")

    @property
    def centre(self) -> tuple:
        return (0.0, -_f32(self.earth_radius), 0.0)

    @property
    def r_earth(self) -> float:
        return _f32(self.earth_radius)

    @property
    def r_inner(self) -> float:
        return _f32(np.float32(self.earth_radius) + np.float32(self.base_altitude))

    @property
    def r_outer(self) -> float:
        return _f32(np.float32(self.earth_radius) + np.float32(self.top_altitude))

    def centre_vec3(self) -> wp.vec3:
        return wp.vec3(*self.centre)


_DEFAULT_LAYER = CloudLayer()
_ORIGIN = Arg("origin", "ray origin (km)", unit_name="km")
_DIRECTION = Arg("direction", "unit ray direction", unit=True)


# --- vc-A14: ray-sphere -----------------------------------------------------------------------------------------------

@declare("vc-A14", c="ccl_raymarch_ray_sphere",
         nonfinite="a ray that misses the sphere gives NaN distances (the documented miss)",
         args=(_ORIGIN, _DIRECTION, Arg("centre", "sphere centre (km)", unit_name="km"),
               Arg("radius", "sphere radius", lo=0.0, lo_open=True, unit_name="km")),
         outputs=("t_near", "t_far"),
         summary="Ray-sphere intersection distances t_near <= t_far along the unit direction (negative = behind the "
                 "origin); NaN where the ray misses. Used for the Earth and the two cloud-layer spheres (defaults: "
                 "Earth radius 6371 km, layer 1.5-4 km above the ground, centre (0, -6371, 0)).",
         references=("Haines, Guenther, Akenine-Moeller, Precision Improvements for Ray/Sphere Intersection, "
                     "Ray Tracing Gems, 2019",))
@wp.func
def raymarch_ray_sphere(origin: wp.vec3, direction: wp.vec3, centre: wp.vec3, radius: float) -> tuple[float, float]:
    """vc-A14: roots (t0 <= t1) of |o + t d - c| = r for unit d (Haines et al., Ray Tracing Gems 2019, robust form);
    (NaN, NaN) on a miss."""
    r = radius
    f = origin - centre
    b = wp.dot(f, direction)
    l = f - direction * b
    ll = wp.length(l)
    disc = (r - ll) * (r + ll)
    t0 = wp.nan
    t1 = wp.nan
    if disc >= 0.0:
        s = wp.sqrt(disc)
        q = s - b
        if b >= 0.0:
            q = -(b + s)
        ff = wp.length(f)
        cq = (ff - r) * (ff + r)
        ta = 0.0
        tb = 0.0
        if q != 0.0:
            ta = cq / q
            tb = q
        if ta < tb:
            t0 = ta
            t1 = tb
        else:
            t0 = tb
            t1 = ta
    return t0, t1


# --- vc-A35: ray-box --------------------------------------------------------------------------------------------------

@wp.func
def _slab(o: float, d: float, lo: float, hi: float, tn: float, tf: float):
    ok = 1
    if d == 0.0:
        if o < lo or o > hi:
            ok = 0
    else:
        ta = (lo - o) / d
        tb = (hi - o) / d
        if ta > tb:
            tmp = ta
            ta = tb
            tb = tmp
        if ta > tn:
            tn = ta
        if tb < tf:
            tf = tb
    return ok, tn, tf


@wp.func
def raymarch_ray_box(o: wp.vec3, d: wp.vec3, bmin: wp.vec3, bmax: wp.vec3) -> tuple[float, float]:
    """vc-A35: slab intersection with an axis-aligned box; (t0, t1) or (NaN, NaN)."""
    tn = -wp.inf
    tf = wp.inf
    check = o[0] + o[1] + o[2] + d[0] + d[1] + d[2] + bmin[0] + bmin[1] + bmin[2] + bmax[0] + bmax[1] + bmax[2]
    okx, tn, tf = _slab(o[0], d[0], bmin[0], bmax[0], tn, tf)
    oky, tn, tf = _slab(o[1], d[1], bmin[1], bmax[1], tn, tf)
    okz, tn, tf = _slab(o[2], d[2], bmin[2], bmax[2], tn, tf)
    t0 = wp.nan
    t1 = wp.nan
    if not wp.isnan(check) and okx == 1 and oky == 1 and okz == 1 and tn <= tf:
        t0 = tn
        t1 = tf
    return t0, t1


# --- vc-A14 / vc-A24: the cloud-layer segment -----------------------------------------------------------------------

def _check_layer(**kw):
    re, ri, ro = (np.asarray(kw[n]) for n in ("r_earth", "r_inner", "r_outer"))
    if np.any(ri < re):
        raise ValueError(f"r_inner must be >= r_earth, got r_inner={np.min(ri)}, r_earth={np.max(re)}")
    if np.any(ri >= ro):
        raise ValueError(f"r_inner must be < r_outer, got r_inner={np.max(ri)}, r_outer={np.min(ro)}")


def _layer_samples(rng, n):
    """Radii r_earth <= r_inner < r_outer (the layer 0-10 % of r_earth above it, 0.1-10 % thick)."""
    re = rng.uniform(1.0, 100.0, n)
    ri = re * (1.0 + rng.uniform(0.0, 0.1, n))
    ro = ri * (1.0 + rng.uniform(0.001, 0.1, n))
    return {"r_earth": re.astype(np.float32), "r_inner": ri.astype(np.float32), "r_outer": ro.astype(np.float32)}


@declare("vc-A24", c="ccl_raymarch_layer_segment",
         nonfinite="a ray without a segment in the layer gives NaN (the documented no-segment)",
         args=(_ORIGIN, _DIRECTION,
               Arg("centre", "planet centre (km)", default=(0.0, -EARTH_RADIUS_KM, 0.0), unit_name="km"),
               Arg("r_earth", "Earth radius", lo=0.0, lo_open=True, default=_DEFAULT_LAYER.r_earth, unit_name="km"),
               # r_inner and r_outer are bounded by r_earth <= r_inner < r_outer (the cross-argument check)
               Arg("r_inner", "cloud-layer base radius (>= r_earth)", default=_DEFAULT_LAYER.r_inner, unit_name="km"),
               Arg("r_outer", "cloud-layer top radius (> r_inner)", default=_DEFAULT_LAYER.r_outer, unit_name="km")),
         outputs=("t_start", "t_end"), check=_check_layer, samples=_layer_samples,
         summary="The raymarch interval through the cloud layer for a camera below (vc-A14: inner far root to outer "
                 "far root, nothing below the horizon), inside (camera to first exit) or above (outer entry to inner "
                 "entry or outer exit) the layer; NaN where the ray sees no cloud layer.",
         references=("Hillaire, Physically based sky, atmosphere and cloud rendering in Frostbite, SIGGRAPH 2016 "
                     "course",))
@wp.func
def raymarch_layer_segment(origin: wp.vec3, direction: wp.vec3, centre: wp.vec3, r_earth: float, r_inner: float,
                           r_outer: float) -> tuple[float, float]:
    """vc-A14 (camera below the layer) and vc-A24 (inside, above): (t_start, t_end) or (NaN, NaN)."""
    o = origin
    d = direction
    c = centre
    rho = wp.length(o - c)
    ts = wp.nan
    te = wp.nan
    if rho < r_inner:
        e0, e1 = raymarch_ray_sphere(o, d, c, r_earth)
        if not (e1 > 0.0):  # a miss gives NaN: not blocked
            i0, i1 = raymarch_ray_sphere(o, d, c, r_inner)
            u0, u1 = raymarch_ray_sphere(o, d, c, r_outer)
            ts = i1
            te = u1
    elif rho <= r_outer:
        ts = 0.0
        i0, i1 = raymarch_ray_sphere(o, d, c, r_inner)
        if i0 > 0.0:
            te = i0
        else:
            u0, u1 = raymarch_ray_sphere(o, d, c, r_outer)
            te = u1
    else:
        u0, u1 = raymarch_ray_sphere(o, d, c, r_outer)
        if u1 > 0.0:
            ts = 0.0
            if u0 > 0.0:
                ts = u0
            te = u1
            i0, i1 = raymarch_ray_sphere(o, d, c, r_inner)
            if i0 > 0.0:
                te = i0
    if not (te >= ts):
        ts = wp.nan
        te = wp.nan
    return ts, te


# --- vc-A18: view-sample count ----------------------------------------------------------------------------------------

def _check_counts(**kw):
    if np.any(np.asarray(kw["n_min"]) > np.asarray(kw["n_max"])):
        raise ValueError(f"n_min must be <= n_max, got n_min={np.max(kw['n_min'])}, n_max={np.min(kw['n_max'])}")


def _count_samples(rng, n):
    n_min = rng.integers(1, 129, n)
    return {"n_min": n_min.astype(np.int32), "n_max": (n_min + rng.integers(0, 129, n)).astype(np.int32)}


@declare("vc-A18", c="ccl_raymarch_view_sample_count",
         args=(Arg("dir_y", "y component of the unit view direction", lo=-1.0, hi=1.0),
               Arg("n_min", "samples at zenith/nadir (<= n_max <= MAX_VIEW_SAMPLES)", lo=1,
                   default=VIEW_SAMPLES_ZENITH),
               # bounded below by n_min >= 1 through the cross-argument check
               Arg("n_max", "samples at the horizon (>= n_min)", hi=MAX_VIEW_SAMPLES,
                   default=VIEW_SAMPLES_HORIZON)),
         outputs=("n",), check=_check_counts, samples=_count_samples,
         summary="View-ray sample count N = round(mix(n_max, n_min, |dir_y|)) (64 at zenith, 128 at the horizon; the "
                 "interpolation law is our choice), int32.",
         references=("Barvir, Volumetric clouds, FIT BUT 2020, §4.3.2 and §4.6",))
@wp.func
def raymarch_view_sample_count(dir_y: float, n_min: int, n_max: int) -> int:
    """vc-A18: N = floor(n_max + (n_min - n_max) |dir_y| + 0.5); |dir_y| > 1 counts as 1, NaN as 0."""
    ay = wp.abs(dir_y)
    if ay >= 1.0:
        ay = 1.0
    if wp.isnan(ay):
        ay = 0.0
    n = wp.floor(float(n_max) + float(n_min - n_max) * ay + 0.5)
    # the clamps of the C function (never an overflowing int() outside the domain)
    if not (n < float(n_max)):
        return n_max
    if n < float(n_min):
        return n_min
    return int(n)


# --- vc-A19: light-cone samples ---------------------------------------------------------------------------------------

@wp.func
def raymarch_light_cone_kernel(i: int) -> wp.vec3:
    """vc-A19: the default kernel vector i (wrapped mod 6), LIGHT_CONE_KERNEL[i]."""
    j = ((i % 6) + 6) % 6
    k = _K0
    if j == 1:
        k = _K1
    elif j == 2:
        k = _K2
    elif j == 3:
        k = _K3
    elif j == 4:
        k = _K4
    elif j == 5:
        k = _K5
    return k


@declare("vc-A19", c="ccl_raymarch_light_sample_position",
         args=(Arg("p", "view sample position (km)", unit_name="km"),
               Arg("to_sun", "unit direction towards the sun", unit=True),
               Arg("index", "light sample index i, 0..5 (5 = the far sample)", lo=0, hi=5),
               Arg("step", "axial step", lo=0.0, lo_open=True, sample_range=(0.01, 1.0), unit_name="km"),
               Arg("cone_angle", "cone half-angle", lo=0.0, hi=math.pi / 2, hi_open=True, unit_name="rad"),
               Arg("far_factor", "far sample distance / near cone length", lo=0.0, lo_open=True,
                   sample_range=(0.5, 5.0)),
               Arg("k", "kernel vector (unit; the default kernel is LIGHT_CONE_KERNEL[i])", unit=True)),
         outputs=("position",),
         summary="Position of light sample i (index) in a cone from p towards the sun: p + s_i to_sun + s_i "
                 "tan(cone_angle) k with s_i = (i+1) step for the 5 near samples and far_factor * 5 step for the 6th "
                 "(defaults: step LIGHT_STEP_KM, cone_angle LIGHT_CONE_ANGLE, far_factor LIGHT_FAR_FACTOR, "
                 "k = LIGHT_CONE_KERNEL[i]).",
         references=("Schneider & Vos, The real-time volumetric cloudscapes of Horizon Zero Dawn, SIGGRAPH 2015",
                     "Schneider, Real-time volumetric cloudscapes, GPU Pro 7, 2016"))
@wp.func
def raymarch_light_sample_position(p: wp.vec3, to_sun: wp.vec3, index: int, step: float, cone_angle: float,
                                   far_factor: float, k: wp.vec3) -> wp.vec3:
    """vc-A19: p + s_i to_sun + (s_i tan(cone_angle)) k with s_i = (i + 1) step (i = index < 5), far_factor * 5 step
    (i = 5)."""
    s = far_factor * (5.0 * step)
    if index < 5:
        s = float(index + 1) * step
    radius = s * wp.tan(cone_angle)
    return (p + to_sun * s) + k * radius


# --- vc-A21: accumulation and early termination -----------------------------------------------------------------------

@declare("vc-A21", c="ccl_raymarch_accumulate",
         args=(Arg("colour", "radiance accumulated so far", lo=0.0),
               Arg("transmittance", "view transmittance T so far", lo=0.0, hi=1.0),
               Arg("sigma", "extinction per unit density", lo=0.0, unit_name="1/km"),
               Arg("rho", "density at the sample", lo=0.0),
               Arg("dt", "step length", lo=0.0, unit_name="km"),
               Arg("light", "radiance of the sample", lo=0.0),
               Arg("eps", "early-termination threshold: stop when 1 - T >= 1 - eps", lo=0.0, hi=1.0,
                   default=MARCH_EPS)),
         outputs=("colour", "transmittance", "stop"),
         summary="One front-to-back step: tau = sigma rho dt, C += T (1 - e^-tau) L, T *= e^-tau; stop = 1 (int32) "
                 "when 1 - T >= 1 - eps (default eps = 1/256).",
         references=("Barvir, Volumetric clouds, FIT BUT 2020, §4.3.2",
                     "Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed., §11.2"))
@wp.func
def raymarch_accumulate(colour: wp.vec3, transmittance: float, sigma: float, rho: float, dt: float, light: wp.vec3,
                        eps: float) -> tuple[wp.vec3, float, int]:
    """vc-A21: tau = sigma rho dt; C += T (1 - e^-tau) L; T *= e^-tau. Returns (C, T, stop) with stop = 1 when
    1 - T >= 1 - eps."""
    tau = sigma * rho * dt
    e = wp.exp(-tau)
    w = transmittance * (1.0 - e)
    t = transmittance * e
    stop = 0
    if (1.0 - t) >= (1.0 - eps):
        stop = 1
    return colour + light * w, t, stop


# --- vc-A23: ray jitter -----------------------------------------------------------------------------------------------

@wp.func
def _jitter_seed(x: wp.uint32, y: wp.uint32, frame: wp.uint32) -> wp.uint32:
    return hash_pcg(x + hash_pcg(y + hash_pcg(frame)))


@wp.func
def raymarch_jitter_tilt(d: wp.vec3, x: wp.uint32, y: wp.uint32, frame: wp.uint32, amount: float) -> wp.vec3:
    """vc-A23: normalize(d + amount r), r in [-1, 1)^3 from the PCG hash of (x, y, frame)."""
    seed = _jitter_seed(x, y, frame)
    r = wp.vec3(2.0 * hash_unit(hash_pcg(seed + wp.uint32(0))) - 1.0,
                2.0 * hash_unit(hash_pcg(seed + wp.uint32(1))) - 1.0,
                2.0 * hash_unit(hash_pcg(seed + wp.uint32(2))) - 1.0)
    return wp.normalize(d + r * amount)


@wp.func
def raymarch_jitter_offset(x: wp.uint32, y: wp.uint32, frame: wp.uint32) -> float:
    """vc-A23 (option): start offset in [0, 1) from the PCG hash of (x, y, frame)."""
    return hash_unit(hash_pcg(_jitter_seed(x, y, frame) + wp.uint32(3)))


@declare("vc-A23", c="ccl_raymarch_jitter",
         args=(_DIRECTION,
               Arg("x", "pixel x", lo=0), Arg("y", "pixel y", lo=0), Arg("frame", "frame number", lo=0),
               Arg("amount", "tilt scale", lo=0.0, default=JITTER_AMOUNT, sample_range=(0.0, 0.1), unit_name="rad")),
         options=(Option("mode", JITTER_MODES, "tilt",
                         "'tilt' (default, the thesis): tilt the direction; 'offset': keep it and jitter the start "
                         "offset; 'none'"),),
         outputs=("direction", "offset"),
         summary="Ray jitter against banding, seeded by (x, y, frame) (uint32) through the PCG hash: mode 'tilt' "
                 "returns normalize(d + amount r), r in [-1, 1)^3, offset 0.5; mode 'offset' d and an offset in "
                 "[0, 1) for the first sample (t = t_start + (i + offset) dt); mode 'none' d and 0.5.",
         references=("Jarzynski & Olano, Hash Functions for GPU Rendering, JCGT 9(3), 2020",))
@wp.func
def raymarch_jitter(direction: wp.vec3, x: wp.uint32, y: wp.uint32, frame: wp.uint32, amount: float,
                    mode: int) -> tuple[wp.vec3, float]:
    """vc-A23: (direction to march, start offset) for a jitter mode (0 tilt, 1 offset, 2 none)."""
    d = direction
    offset = float(0.5)
    if mode == JITTER_TILT:
        d = raymarch_jitter_tilt(direction, x, y, frame, amount)
    elif mode == JITTER_OFFSET:
        offset = raymarch_jitter_offset(x, y, frame)
    return d, offset


# --- vc-A35: uniform march --------------------------------------------------------------------------------------------

@wp.func
def raymarch_interval(t_near: float, t_far: float, n: int) -> tuple[float, float]:
    """vc-A35: (t_start, dt) = (max(t_near, 0), (t_far - t_start) / n), or (NaN, NaN) for an empty/behind interval."""
    ts = wp.nan
    dt = wp.nan
    if t_far >= 0.0 and t_near <= t_far:
        ts = 0.0
        if t_near > 0.0:
            ts = t_near
        dt = (t_far - ts) / float(n)
    return ts, dt


@wp.func
def raymarch_point(o: wp.vec3, d: wp.vec3, t_start: float, dt: float, i: int, offset: float) -> wp.vec3:
    """vc-A35 / vc-2.18: o + (t_start + (i + offset) dt) d."""
    t = t_start + (float(i) + offset) * dt
    return o + d * t


@wp.func
def _march_fill(o: wp.vec3, d: wp.vec3, t0: float, t1: float, n: int, offset: float,
                out_points: wp.array2d(dtype=wp.vec3), row: int) -> float:
    ts, dt = raymarch_interval(t0, t1, n)
    for i in range(n):
        out_points[row, i] = raymarch_point(o, d, ts, dt, i, offset)
    return dt


@wp.func
def raymarch_sphere(o: wp.vec3, d: wp.vec3, c: wp.vec3, r: float, n: int, offset: float,
                    out_points: wp.array2d(dtype=wp.vec3), row: int) -> float:
    """vc-A35: n uniform steps through the sphere (c, r) in front of o (d any non-zero length, normalized):
    out_points[row, i] = raymarch_point(o, d, t_start, dt, i, offset); returns dt (NaN and NaN points on a miss)."""
    u = wp.normalize(d)
    t0, t1 = raymarch_ray_sphere(o, u, c, r)
    return _march_fill(o, u, t0, t1, n, offset, out_points, row)


@wp.func
def raymarch_box(o: wp.vec3, d: wp.vec3, bmin: wp.vec3, bmax: wp.vec3, n: int, offset: float,
                 out_points: wp.array2d(dtype=wp.vec3), row: int) -> float:
    """vc-A35: :func:`raymarch_sphere` for an axis-aligned box (bmin <= bmax)."""
    u = wp.normalize(d)
    t0, t1 = raymarch_ray_box(o, u, bmin, bmax)
    return _march_fill(o, u, t0, t1, n, offset, out_points, row)


@wp.kernel
def _march_volume_kernel(origins: wp.array(dtype=wp.vec3), dirs: wp.array(dtype=wp.vec3), kind: int, a: wp.vec3,
                         b: wp.vec3, radius: float, n: int, offset: float, points: wp.array2d(dtype=wp.vec3),
                         dts: wp.array(dtype=float)):
    r = wp.tid()
    if kind == 0:
        dts[r] = raymarch_sphere(origins[r], dirs[r], a, radius, n, offset, points, r)
    else:
        dts[r] = raymarch_box(origins[r], dirs[r], a, b, n, offset, points, r)


def _march_args(origin, direction, n, offset, name):
    o = np.asarray(origin, dtype=np.float64) if not isinstance(origin, str) else None
    d = np.asarray(direction, dtype=np.float64) if not isinstance(direction, str) else None
    for arr, nm in ((o, "origin"), (d, "direction")):
        if arr is None or arr.ndim == 0 or arr.shape[-1] != 3:
            raise ValueError(f"{nm} must be an array of 3-vectors (..., 3)")
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{nm} must be finite (no NaN or Inf)")
    try:
        shape = np.broadcast_shapes(o.shape[:-1], d.shape[:-1])
    except ValueError:
        raise ValueError(f"{name}(): origin{o.shape} and direction{d.shape} do not broadcast") from None
    if np.any(np.sum(d * d, axis=-1) == 0.0):
        raise ValueError("direction must be non-zero")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        raise TypeError(f"n must be an integer, got {n!r}")
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    off = _finite_float(offset, "offset")
    if not 0.0 <= off < 1.0:
        raise ValueError(f"offset must be in [0, 1), got {offset}")
    f32 = lambda v: np.ascontiguousarray(v, dtype=np.float32)  # noqa: E731
    return (f32(np.broadcast_to(o, (*shape, 3)).reshape(-1, 3)), f32(np.broadcast_to(d, (*shape, 3)).reshape(-1, 3)),
            shape, int(n), float(np.float32(off)))


def _sphere_args(centre, radius):
    a = _vec3_value(centre, "centre")
    r = _finite_float(radius, "radius")
    if r <= 0:
        raise ValueError(f"radius must be > 0, got {radius}")
    return np.float32(a), np.zeros(3, np.float32), float(np.float32(r))


def _box_args(box_min, box_max):
    a = _vec3_value(box_min, "box_min")
    b = _vec3_value(box_max, "box_max")
    if np.any(a > b):
        raise ValueError(f"box_min must be <= box_max component-wise, got {a.tolist()} and {b.tolist()}")
    return np.float32(a), np.float32(b), 0.0


def _march(kind, impl, device, o, d, shape, n, a, b, r, off):
    """n uniform steps of every ray through a sphere (kind 0: centre a, radius r) or a box (kind 1: a, b)."""
    if impl == "warp":
        from ..core.runtime import resolve_device

        dev = resolve_device(device)
        pts = wp.empty((o.shape[0], n), dtype=wp.vec3, device=dev)
        dts = wp.empty(o.shape[0], dtype=float, device=dev)
        if o.shape[0]:
            wp.launch(_march_volume_kernel, dim=o.shape[0],
                      inputs=[wp.array(o, dtype=wp.vec3, device=dev), wp.array(d, dtype=wp.vec3, device=dev), kind,
                              wp.vec3(*a.tolist()), wp.vec3(*b.tolist()), r, n, off], outputs=[pts, dts], device=dev)
        return pts.numpy().reshape(*shape, n, 3), dts.numpy().reshape(shape)
    from ..core.binding import ffi, lib

    F, L = ffi(), lib()
    pts_c = F.new("ccl_vec3[]", n)
    dt_c = F.new("float *")
    pts = np.empty((o.shape[0], n, 3), np.float32)
    dts = np.empty(o.shape[0], np.float32)
    for k in range(o.shape[0]):
        ok, dk = tuple(o[k].tolist()), tuple(d[k].tolist())
        if kind == 0:
            L.ccl_raymarch_sphere(ok, dk, tuple(a.tolist()), r, n, off, pts_c, dt_c)
        else:
            L.ccl_raymarch_box(ok, dk, tuple(a.tolist()), tuple(b.tolist()), n, off, pts_c, dt_c)
        pts[k] = np.frombuffer(F.buffer(pts_c), dtype=np.float32).reshape(n, 3)
        dts[k] = dt_c[0]
    return pts.reshape(*shape, n, 3), dts.reshape(shape)


def _sphere_evaluator(impl, device=None):
    def raymarch_sphere(origin, direction, centre, radius, n, offset=0.5):
        """Sample positions (..., n, 3) and step lengths (...) of n uniform steps through the sphere (centre,
        radius) in front of the origin (direction of any non-zero length); NaN where the ray misses (vc-A35)."""
        o, d, shape, n, off = _march_args(origin, direction, n, offset, "raymarch_sphere")
        a, b, r = _sphere_args(centre, radius)
        return _march(0, impl, device, o, d, shape, n, a, b, r, off)

    return raymarch_sphere


def march_box(origin, direction, box_min, box_max, n, offset=0.5, *, impl: str = "warp", device=None):
    """vc-A35 with an axis-aligned box (``ccl_raymarch_box``): sample positions (..., n, 3) and step lengths (...) of n
    uniform steps through the box in front of the origin (direction of any non-zero length); NaN where the ray
    misses. ``impl="c"`` evaluates the C function. The registered vc-A35 entry is the sphere, ``raymarch_sphere``
    (a box is not a catalogue entry of its own)."""
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    o, d, shape, n, off = _march_args(origin, direction, n, offset, "march_box")
    a, b, r = _box_args(box_min, box_max)
    return _march(1, impl, device, o, d, shape, n, a, b, r, off)


# Not element-wise: one ray gives n sample points, (..., n, 3); the same march through a box is march_box.
declare("vc-A35", c="ccl_raymarch_sphere", make_warp=lambda eq, device: _sphere_evaluator("warp", device),
        make_c=lambda eq: _sphere_evaluator("c"),
        summary="raymarch_sphere(origin, direction, centre, radius, n, offset=0.5) -> (points (..., n, 3), dt (...)): "
                "n uniform steps over the part of the ray in front of the origin inside a bounding sphere, sample i "
                "at t_start + (i + offset) dt; NaN where the ray misses. The same through an axis-aligned box "
                "(ccl_raymarch_box): pywarp.kernels.raymarch.march_box(..., impl='warp' | 'c').",
        references=("Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed., §11.3 (ray marching)",))(
    raymarch_sphere)


# --- vc-A36: constants ------------------------------------------------------------------------------------------------

@wp.struct
class VcConstantTable:
    """Warp twin of ``ccl_vc_constant_table`` (field by field)."""

    base_texture_size: int
    base_texture_channels: int
    detail_texture_size: int
    detail_texture_channels: int
    low_freq_fbm_weights: wp.vec3
    high_freq_fbm_weights: wp.vec3
    detail_erosion: float
    powder_factor: float
    schlick_fit: wp.vec2
    cloud_types: wp.vec3
    gradient_cumulus: wp.vec4
    gradient_stratocumulus: wp.vec4
    gradient_stratus: wp.vec4
    view_samples_zenith: int
    view_samples_horizon: int
    light_samples: int
    light_samples_near: int
    light_far_factor: float
    reprojection_block: int
    reprojection_cycle: int
    tone_map_constant: float
    cie_clear_sky_bcde: wp.vec4
    low_cloud_top_km: float
    middle_cloud_base_km: float
    middle_cloud_top_km: float
    high_cloud_base_km: float
    rayleigh_blue_nm: float
    rayleigh_blue_vs_red: float
    rayleigh_red_nm: float


@wp.func
def raymarch_vc_constants() -> VcConstantTable:
    """vc-A36: the constants collected from the thesis, usable inside kernels."""
    c = VcConstantTable()
    c.base_texture_size = 128
    c.base_texture_channels = 4
    c.detail_texture_size = 32
    c.detail_texture_channels = 3
    c.low_freq_fbm_weights = wp.vec3(0.625, 0.25, 0.125)
    c.high_freq_fbm_weights = wp.vec3(0.625, 0.25, 0.125)
    c.detail_erosion = 0.2
    c.powder_factor = 2.0
    c.schlick_fit = wp.vec2(1.55, 0.55)
    c.cloud_types = wp.vec3(0.0, 0.5, 1.0)
    c.gradient_cumulus = wp.vec4(0.01, 0.30, 0.6, 0.95)
    c.gradient_stratocumulus = wp.vec4(0.01, 0.25, 0.3, 0.65)
    c.gradient_stratus = wp.vec4(0.01, 0.05, 0.0, 0.20)
    c.view_samples_zenith = 64
    c.view_samples_horizon = 128
    c.light_samples = 6
    c.light_samples_near = 5
    c.light_far_factor = 3.0
    c.reprojection_block = 4
    c.reprojection_cycle = 16
    c.tone_map_constant = 0.03
    c.cie_clear_sky_bcde = wp.vec4(-0.32, 10.0, -3.0, 0.45)
    c.low_cloud_top_km = 2.0
    c.middle_cloud_base_km = 2.0
    c.middle_cloud_top_km = 6.0
    c.high_cloud_base_km = 6.0
    c.rayleigh_blue_nm = 400.0
    c.rayleigh_blue_vs_red = 10.0
    c.rayleigh_red_nm = 700.0
    return c


@dataclass(frozen=True)
class VcConstants:
    """The constants of vc-A36 (float32 values as stored by C and Warp; tuples for the weight/break-point lists)."""

    base_texture_size: int
    base_texture_channels: int
    detail_texture_size: int
    detail_texture_channels: int
    low_freq_fbm_weights: tuple
    high_freq_fbm_weights: tuple
    detail_erosion: float
    powder_factor: float
    schlick_fit: tuple
    cloud_types: tuple
    gradient_cumulus: tuple
    gradient_stratocumulus: tuple
    gradient_stratus: tuple
    view_samples_zenith: int
    view_samples_horizon: int
    light_samples: int
    light_samples_near: int
    light_far_factor: float
    reprojection_block: int
    reprojection_cycle: int
    tone_map_constant: float
    cie_clear_sky_bcde: tuple
    low_cloud_top_km: float
    middle_cloud_base_km: float
    middle_cloud_top_km: float
    high_cloud_base_km: float
    rayleigh_blue_nm: float
    rayleigh_blue_vs_red: float
    rayleigh_red_nm: float


def _to_constants(get) -> VcConstants:
    """Build VcConstants from ``get(name)`` returning a number or a sequence; floats rounded through float32."""
    out = {}
    for fd in fields(VcConstants):
        v = get(fd.name)
        if fd.type in ("int", int):
            out[fd.name] = int(v)
        elif fd.type in ("tuple", tuple):
            out[fd.name] = tuple(_f32(x) for x in v)
        else:
            out[fd.name] = _f32(v)
    return VcConstants(**out)


@wp.kernel
def _eval_vc_constants(out: wp.array(dtype=VcConstantTable)):
    out[0] = raymarch_vc_constants()


def _warp_vc_constants(eq, device):
    from ..core.runtime import resolve_device

    dev = resolve_device(device)

    def call():
        arr = wp.empty(1, dtype=VcConstantTable, device=dev)
        wp.launch(_eval_vc_constants, dim=1, inputs=[arr], device=dev)
        rec = arr.numpy()[0]
        return _to_constants(lambda name: rec[name])

    return call


def _c_vc_constants(eq):
    from ..core.binding import lib

    def call():
        p = lib().ccl_raymarch_vc_constants()
        return _to_constants(lambda name: getattr(p, name))

    return call


# Not element-wise: the result is a table of constants (a struct of scalars and short vectors), not an array.
declare("vc-A36", c="ccl_raymarch_vc_constants", make_warp=_warp_vc_constants, make_c=_c_vc_constants,
        summary="raymarch_vc_constants() -> VcConstants: the constants collected from the thesis (texture sizes, fBm "
                "weights, erosion, powder, Schlick fit, cloud types, gradient break points, sample counts, "
                "reprojection block and cycle, tone-map constant, CIE clear sky, cloud altitudes, Rayleigh ratio).",
        references=("Barvir, Volumetric clouds, FIT BUT 2020 (spec/vc.md vc-A36)",))(raymarch_vc_constants)
