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

import linecache
import math
from dataclasses import dataclass, make_dataclass

import numpy as np
import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import Arg, Option, declare
from .camera import _finite_float
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
#: Largest coordinate and radius of the ray-sphere and layer-segment entries (CCL_RAYMARCH_MAX_DISTANCE, reasons in
#: cclouds/raymarch.h): |o - c|^2 - r^2 overflowed for an origin 1e19 away and the layer segment ended at inf.
MAX_DISTANCE = 1.0e15
_ORIGIN = Arg("origin", "ray origin (km)", lo=-MAX_DISTANCE, hi=MAX_DISTANCE, unit_name="km")
_DIRECTION = Arg("direction", "unit ray direction", unit=True)


# --- vc-A14: ray-sphere -----------------------------------------------------------------------------------------------

@declare("vc-A14", c="ccl_raymarch_ray_sphere",
         nonfinite="a ray that misses the sphere gives NaN distances (the documented miss)",
         args=(_ORIGIN, _DIRECTION, Arg("centre", "sphere centre (km)", lo=-MAX_DISTANCE, hi=MAX_DISTANCE,
                                        unit_name="km"),
               Arg("radius", "sphere radius", lo=0.0, lo_open=True, hi=MAX_DISTANCE, unit_name="km")),
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
               Arg("centre", "planet centre (km)", lo=-MAX_DISTANCE, hi=MAX_DISTANCE,
                   default=(0.0, -EARTH_RADIUS_KM, 0.0), unit_name="km"),
               Arg("r_earth", "Earth radius", lo=0.0, lo_open=True, default=_DEFAULT_LAYER.r_earth, unit_name="km"),
               # r_inner is bounded by r_earth <= r_inner < r_outer (the cross-argument check)
               Arg("r_inner", "cloud-layer base radius (>= r_earth)", default=_DEFAULT_LAYER.r_inner, unit_name="km"),
               Arg("r_outer", "cloud-layer top radius (> r_inner)", hi=MAX_DISTANCE, default=_DEFAULT_LAYER.r_outer,
                   unit_name="km")),
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
def march_volume_kernel(origins: wp.array(dtype=wp.vec3), dirs: wp.array(dtype=wp.vec3), kind: int, a: wp.vec3,
                        b: wp.vec3, radius: float, n: int, offset: float, points: wp.array2d(dtype=wp.vec3),
                        dts: wp.array(dtype=float)):
    r = wp.tid()
    if kind == 0:
        dts[r] = raymarch_sphere(origins[r], dirs[r], a, radius, n, offset, points, r)
    else:
        dts[r] = raymarch_box(origins[r], dirs[r], a, b, n, offset, points, r)


# Not element-wise: one ray gives n sample points, (..., n, 3); the same march through a box is
# pywarp.clouds.raymarch.march_box.
declare("vc-A35", c="ccl_raymarch_sphere", make_warp="pywarp.clouds.raymarch:sphere_warp",
        make_c="pywarp.clouds.raymarch:sphere_c",
        summary="raymarch_sphere(origin, direction, centre, radius, n, offset=0.5) -> (points (..., n, 3), dt (...)): "
                "n uniform steps over the part of the ray in front of the origin inside a bounding sphere, sample i "
                "at t_start + (i + offset) dt; NaN where the ray misses. The same through an axis-aligned box "
                "(ccl_raymarch_box): pywarp.clouds.raymarch.march_box(..., impl='warp' | 'c').",
        references=("Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed., §11.3 (ray marching)",))(
    raymarch_sphere)


# --- vc-A36: constants ------------------------------------------------------------------------------------------------

#: vc-A36, the constants collected from the thesis, stated once (the reasons are in ``ccl_vc_constant_table``,
#: cclouds/raymarch.h): field -> an int, a float, or a tuple of 2-4 floats, in the order of the C struct. The Warp
#: struct :class:`VcConstantTable`, its kernel-side constructor :func:`raymarch_vc_constants`, the host record
#: :class:`VcConstants` and the evaluators (pywarp.clouds.raymarch) are derived from this table;
#: tests/kernels/test_raymarch.py pins it to ``ccl_raymarch_vc_constants`` field by field.
VC_CONSTANTS = {
    "base_texture_size": 128, "base_texture_channels": 4, "detail_texture_size": 32, "detail_texture_channels": 3,
    "low_freq_fbm_weights": (0.625, 0.25, 0.125), "high_freq_fbm_weights": (0.625, 0.25, 0.125),
    "detail_erosion": 0.2, "powder_factor": 2.0, "schlick_fit": (1.55, 0.55), "cloud_types": (0.0, 0.5, 1.0),
    "gradient_cumulus": (0.01, 0.30, 0.6, 0.95), "gradient_stratocumulus": (0.01, 0.25, 0.3, 0.65),
    "gradient_stratus": (0.01, 0.05, 0.0, 0.20), "view_samples_zenith": 64, "view_samples_horizon": 128,
    "light_samples": 6, "light_samples_near": 5, "light_far_factor": 3.0, "reprojection_block": 4,
    "reprojection_cycle": 16, "tone_map_constant": 0.03, "cie_clear_sky_bcde": (-0.32, 10.0, -3.0, 0.45),
    "low_cloud_top_km": 2.0, "middle_cloud_base_km": 2.0, "middle_cloud_top_km": 6.0, "high_cloud_base_km": 6.0,
    "rayleigh_blue_nm": 400.0, "rayleigh_blue_vs_red": 10.0, "rayleigh_red_nm": 700.0,
}
_VC_TYPES = {int: ("int", int, int), float: ("float", float, float), 2: ("wp.vec2", wp.vec2, tuple),
             3: ("wp.vec3", wp.vec3, tuple), 4: ("wp.vec4", wp.vec4, tuple)}


def _vc_field(value) -> tuple[str, type, type]:
    """(Warp type as written in a kernel, Warp type, host type) of a :data:`VC_CONSTANTS` value."""
    return _VC_TYPES[len(value) if isinstance(value, tuple) else type(value)]


def _vc_constants_func():
    """:func:`raymarch_vc_constants` written from the table: one assignment per field, as a kernel would state it
    (generated like the registry's evaluation kernels, with its source in linecache for Warp's code generator)."""
    body = ["def raymarch_vc_constants() -> VcConstantTable:",
            '    """vc-A36: the constants collected from the thesis, usable inside kernels."""',
            "    c = VcConstantTable()"]
    for name, v in VC_CONSTANTS.items():
        wtype = _vc_field(v)[0]
        value = f"{wtype}({', '.join(map(repr, v))})" if isinstance(v, tuple) else repr(v)
        body.append(f"    c.{name} = {value}")
    body.append("    return c")
    src = "\n".join(body) + "\n"
    filename = f"<pywarp generated {__name__}.raymarch_vc_constants>"
    linecache.cache[filename] = (len(src), None, src.splitlines(True), filename)
    ns = {"wp": wp, "VcConstantTable": VcConstantTable, "__name__": __name__}
    exec(compile(src, filename, "exec"), ns)
    return wp.func(ns["raymarch_vc_constants"])


VcConstantTable = wp.struct(type("VcConstantTable", (), {
    "__doc__": "Warp twin of ``ccl_vc_constant_table`` (field by field, from :data:`VC_CONSTANTS`).",
    "__module__": __name__, "__qualname__": "VcConstantTable",
    "__annotations__": {name: _vc_field(v)[1] for name, v in VC_CONSTANTS.items()}}))
raymarch_vc_constants = _vc_constants_func()

VcConstants = make_dataclass("VcConstants", [(name, _vc_field(v)[2]) for name, v in VC_CONSTANTS.items()],
                             frozen=True, namespace={
                                 "__module__": __name__,
                                 "__doc__": "The constants of vc-A36 (float32 values as stored by C and Warp; tuples "
                                            "for the weight/break-point lists)."})


@wp.kernel
def vc_constants_kernel(out: wp.array(dtype=VcConstantTable)):
    out[0] = raymarch_vc_constants()


# Not element-wise: the result is a table of constants (a struct of scalars and short vectors), not an array.
declare("vc-A36", c="ccl_raymarch_vc_constants", make_warp="pywarp.clouds.raymarch:constants_warp",
        make_c="pywarp.clouds.raymarch:constants_c",
        summary="raymarch_vc_constants() -> VcConstants: the constants collected from the thesis (texture sizes, fBm "
                "weights, erosion, powder, Schlick fit, cloud types, gradient break points, sample counts, "
                "reprojection block and cycle, tone-map constant, CIE clear sky, cloud altitudes, Rayleigh ratio).",
        references=("Barvir, Volumetric clouds, FIT BUT 2020 (spec/vc.md vc-A36)",))(raymarch_vc_constants)
