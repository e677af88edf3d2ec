"""View-ray geometry of the cloudscape (vc §2.2, §4.2.1, §4.3.2) -- Warp twins of ``cclouds/raymarch.h``.

Camera and ray generation (vc-A25), ray-sphere / ray-box intersection (vc-A14, vc-A35), the cloud-layer segment for
a camera below, inside or above the layer (vc-A14, vc-A24), the view-sample count (vc-A18), light samples in a cone
(vc-A19), front-to-back accumulation with early termination (vc-A21), ray jitter against banding (vc-A23), uniform
marching in a bounding volume (vc-A35) and the constants collected from the thesis (vc-A36).

Conventions (shared with the C header):
  * World frame y up, lengths in kilometres; the default planet centre is ``(0, -EARTH_RADIUS_KM, 0)`` so the ground
    under the origin is at y = 0 and float32 coordinates near the camera stay small.
  * Rays ``o + t d``; "no hit / no segment" is NaN in both distances (so ``t_end > t_start`` is false).
  * Matrices: ``wp.mat44`` in mathematical (row, column) indexing; the C code stores the same matrices column-major.
    Right-handed look-at view (the camera looks down -z), OpenGL perspective (NDC z in [-1, 1]).
  * Pixel ``(x, y)``, ``y = 0`` the top row; uv = ((x + 0.5)/W, (y + 0.5)/H); NDC = (2u - 1, 1 - 2v).
  * Every @wp.func performs the float32 operations of its C twin in the same order.

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

from ..core.registry import Arg, Equation, Option, register

# --- named defaults ---------------------------------------------------------------------------------------------------

EARTH_RADIUS_KM = 6371.0
LAYER_BASE_KM = 1.5
LAYER_TOP_KM = 4.0
VIEW_SAMPLES_ZENITH = 64
VIEW_SAMPLES_HORIZON = 128
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

JITTER_MODES = {"tilt": 0, "offset": 1, "none": 2}

# PCG hash constants (>= 2^31 must be typed uint32 explicitly)
_PCG_MUL = wp.constant(wp.uint32(747796405))
_PCG_INC = wp.constant(wp.uint32(2891336453))
_PCG_MUL2 = wp.constant(wp.uint32(277803737))


# --- vec3 helpers (same operation order as the static helpers of raymarch.c) ----------------------------------------

@wp.func
def _dot3(a: wp.vec3, b: wp.vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@wp.func
def _normalize3(a: wp.vec3) -> wp.vec3:
    l = wp.sqrt(_dot3(a, a))
    return wp.vec3(a[0] / l, a[1] / l, a[2] / l)


@wp.func
def _pcg_hash(v: wp.uint32) -> wp.uint32:
    state = v * _PCG_MUL + _PCG_INC
    word = ((state >> ((state >> wp.uint32(28)) + wp.uint32(4))) ^ state) * _PCG_MUL2
    return (word >> wp.uint32(22)) ^ word


@wp.func
def _jitter_seed(x: wp.uint32, y: wp.uint32, frame: wp.uint32) -> wp.uint32:
    return _pcg_hash(x + _pcg_hash(y + _pcg_hash(frame)))


@wp.func
def _hash_unit(h: wp.uint32) -> float:
    return float(h >> wp.uint32(8)) * (1.0 / 16777216.0)


# --- vc-A14: ray-sphere -----------------------------------------------------------------------------------------------

@wp.func
def ray_sphere(o: wp.vec3, d: wp.vec3, c: wp.vec3, r: float):
    """vc-A14: roots (t0 <= t1) of |o + t d - c| = r for unit d (Haines et al., Ray Tracing Gems 2019, robust form);
    (NaN, NaN) on a miss."""
    f = o - c
    b = _dot3(f, d)
    l = f - d * b
    ll = wp.sqrt(_dot3(l, l))
    disc = (r - ll) * (r + ll)
    t0 = wp.nan
    t1 = wp.nan
    if disc >= 0.0:
        s = wp.sqrt(disc)
        q = s - b
        if b >= 0.0:
            q = -(b + s)
        ff = wp.sqrt(_dot3(f, f))
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
def ray_box(o: wp.vec3, d: wp.vec3, bmin: wp.vec3, bmax: wp.vec3):
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

@wp.func
def layer_segment(o: wp.vec3, d: wp.vec3, c: wp.vec3, r_earth: float, r_inner: float, r_outer: float):
    """vc-A14 (camera below the layer) and vc-A24 (inside, above): (t_start, t_end) or (NaN, NaN)."""
    f = o - c
    rho = wp.sqrt(_dot3(f, f))
    ts = wp.nan
    te = wp.nan
    if rho < r_inner:
        e0, e1 = ray_sphere(o, d, c, r_earth)
        if not (e1 > 0.0):  # a miss gives NaN: not blocked
            i0, i1 = ray_sphere(o, d, c, r_inner)
            u0, u1 = ray_sphere(o, d, c, r_outer)
            ts = i1
            te = u1
    elif rho <= r_outer:
        ts = 0.0
        i0, i1 = ray_sphere(o, d, c, r_inner)
        if i0 > 0.0:
            te = i0
        else:
            u0, u1 = ray_sphere(o, d, c, r_outer)
            te = u1
    else:
        u0, u1 = ray_sphere(o, d, c, r_outer)
        if u1 > 0.0:
            ts = 0.0
            if u0 > 0.0:
                ts = u0
            te = u1
            i0, i1 = ray_sphere(o, d, c, r_inner)
            if i0 > 0.0:
                te = i0
    if not (te >= ts):
        ts = wp.nan
        te = wp.nan
    return ts, te


# --- vc-A18: view-sample count ----------------------------------------------------------------------------------------

@wp.func
def view_sample_count(dir_y: float, n_min: int, n_max: int) -> int:
    """vc-A18: N = floor(n_max + (n_min - n_max) |dir_y| + 0.5); |dir_y| > 1 counts as 1, NaN as 0."""
    ay = wp.abs(dir_y)
    if ay >= 1.0:
        ay = 1.0
    if wp.isnan(ay):
        ay = 0.0
    n = float(n_max) + float(n_min - n_max) * ay
    return int(wp.floor(n + 0.5))


# --- vc-A19: light-cone samples ---------------------------------------------------------------------------------------

@wp.func
def light_cone_kernel(i: int) -> wp.vec3:
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


@wp.func
def light_sample_position(p: wp.vec3, to_sun: wp.vec3, i: int, step: float, cone_angle: float, far_factor: float,
                          k: wp.vec3) -> wp.vec3:
    """vc-A19: p + s_i to_sun + (s_i tan(cone_angle)) k with s_i = (i + 1) step (i < 5), far_factor * 5 step (i = 5)."""
    s = far_factor * (5.0 * step)
    if i < 5:
        s = float(i + 1) * step
    radius = s * wp.tan(cone_angle)
    return (p + to_sun * s) + k * radius


# --- vc-A21: accumulation and early termination -----------------------------------------------------------------------

@wp.func
def march_accumulate(colour: wp.vec3, transmittance: float, sigma: float, rho: float, dt: float, light: wp.vec3,
                     eps: float):
    """vc-A21: tau = sigma rho dt; C += T (1 - e^-tau) L; T *= e^-tau. Returns (C, T, stop) with stop = 1 when
    1 - T >= 1 - eps."""
    tau = sigma * rho * dt
    e = wp.exp(-tau)
    w = transmittance * (1.0 - e)
    c = wp.vec3(colour[0] + w * light[0], colour[1] + w * light[1], colour[2] + w * light[2])
    t = transmittance * e
    stop = 0
    if (1.0 - t) >= (1.0 - eps):
        stop = 1
    return c, t, stop


# --- vc-A25: ray generation -------------------------------------------------------------------------------------------

@wp.func
def camera_ray(inv_view_proj_rot: wp.mat44, x: int, y: int, width: int, height: int) -> wp.vec3:
    """vc-A25: unit direction through the centre of pixel (x, y): uv -> NDC (z = 1) -> h = M (ndc, 1) with M the
    camera-relative inverse view-projection (``Camera.inv_view_proj_rot``) -> normalize(h.xyz)."""
    m = inv_view_proj_rot
    u = (float(x) + 0.5) / float(width)
    v = (float(y) + 0.5) / float(height)
    nx = 2.0 * u - 1.0
    ny = 1.0 - 2.0 * v
    hx = m[0][0] * nx + m[0][1] * ny + m[0][2] + m[0][3]
    hy = m[1][0] * nx + m[1][1] * ny + m[1][2] + m[1][3]
    hz = m[2][0] * nx + m[2][1] * ny + m[2][2] + m[2][3]
    return _normalize3(wp.vec3(hx, hy, hz))


# --- vc-A23: ray jitter -----------------------------------------------------------------------------------------------

@wp.func
def ray_jitter_tilt(d: wp.vec3, x: wp.uint32, y: wp.uint32, frame: wp.uint32, amount: float) -> wp.vec3:
    """vc-A23: normalize(d + amount r), r in [-1, 1)^3 from the PCG hash of (x, y, frame)."""
    seed = _jitter_seed(x, y, frame)
    rx = 2.0 * _hash_unit(_pcg_hash(seed + wp.uint32(0))) - 1.0
    ry = 2.0 * _hash_unit(_pcg_hash(seed + wp.uint32(1))) - 1.0
    rz = 2.0 * _hash_unit(_pcg_hash(seed + wp.uint32(2))) - 1.0
    return _normalize3(d + wp.vec3(rx, ry, rz) * amount)


@wp.func
def ray_jitter_offset(x: wp.uint32, y: wp.uint32, frame: wp.uint32) -> float:
    """vc-A23 (option): start offset in [0, 1) from the PCG hash of (x, y, frame)."""
    return _hash_unit(_pcg_hash(_jitter_seed(x, y, frame) + wp.uint32(3)))


# --- vc-A35: uniform march --------------------------------------------------------------------------------------------

@wp.func
def march_interval(t_near: float, t_far: float, n: int):
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
def march_point(o: wp.vec3, d: wp.vec3, t_start: float, dt: float, i: int, offset: float) -> wp.vec3:
    """vc-A35 / vc-2.18: o + (t_start + (i + offset) dt) d."""
    t = t_start + (float(i) + offset) * dt
    return o + d * t


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
def vc_constants() -> VcConstantTable:
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


def _f32(v) -> float:
    return float(np.float32(v))


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
    out[0] = vc_constants()


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
        p = lib().ccl_vc_constants()
        return _to_constants(lambda name: getattr(p, name))

    return call


# --- Python-side objects: cloud layer and camera ----------------------------------------------------------------------

def _finite_float(value, name: str) -> float:
    if isinstance(value, (bool, str, bytes)) or value is None:
        raise TypeError(f"{name} must be a number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {v}")
    return v


def _vec3_value(value, name: str) -> np.ndarray:
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a 3-vector of numbers, got {value!r}") from None
    if a.shape != (3,):
        raise ValueError(f"{name} must be a 3-vector, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {a.tolist()}")
    return a


@dataclass(frozen=True)
class CloudLayer:
    """The Earth sphere and the two spheres bounding the cloud layer (vc-A14), centre ``(0, -earth_radius, 0)``.

    Parameters (km): ``earth_radius`` (default 6371, IUGG mean radius), ``base_altitude`` (1.5) and ``top_altitude``
    (4.0) above the ground. Twin of ``ccl_cloud_layer_init``.
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


@dataclass(frozen=True, eq=False)
class Camera:
    """Camera matrices (float32, mathematical row/column layout, ``m[row, col]``); see :func:`camera_look_at`.

    ``mat44(name)`` gives a ``wp.mat44`` for kernels, ``column_major(name)`` the float[16] layout of the C code.
    """

    eye: np.ndarray
    view: np.ndarray
    proj: np.ndarray
    view_proj: np.ndarray
    inv_view_proj: np.ndarray
    inv_view_proj_rot: np.ndarray  # inverse of proj @ (view without translation): clip -> direction from the eye

    def mat44(self, name: str = "inv_view_proj") -> wp.mat44:
        return wp.mat44(*getattr(self, name).ravel().tolist())

    def column_major(self, name: str = "inv_view_proj") -> np.ndarray:
        return np.ascontiguousarray(getattr(self, name).T.ravel(), dtype=np.float32)

    def eye_vec3(self) -> wp.vec3:
        return wp.vec3(*self.eye.tolist())


def camera_look_at(eye, target, up=(0.0, 1.0, 0.0), fov_y: float = math.radians(60.0), aspect: float = 16.0 / 9.0,
                   z_near: float = 0.01, z_far: float = 1000.0) -> Camera:
    """vc-A25 camera: right-handed look-at view (GLM ``lookAt``) and OpenGL perspective (GLM ``perspective``).

    ``fov_y`` vertical field of view in radians (0, pi); ``aspect`` = width / height; ``0 < z_near < z_far`` in km.
    The inputs are rounded to float32 first (as the C function receives them), the matrices, their product and the
    closed-form inverses ``inv(view) inv(proj)`` (and the same with the eye moved to the origin, ``inv_view_proj_rot``,
    the matrix ray generation uses) are computed in float64 and rounded once: the twin of ``ccl_camera_look_at``.
    Raises ValueError naming the parameter.
    """
    e = _vec3_value(eye, "eye").astype(np.float32).astype(np.float64)
    tg = _vec3_value(target, "target").astype(np.float32).astype(np.float64)
    u_in = _vec3_value(up, "up").astype(np.float32).astype(np.float64)
    fov = float(np.float32(_finite_float(fov_y, "fov_y")))
    asp = float(np.float32(_finite_float(aspect, "aspect")))
    zn = float(np.float32(_finite_float(z_near, "z_near")))
    zf = float(np.float32(_finite_float(z_far, "z_far")))
    if not 0.0 < fov < float(np.float32(math.pi)):
        raise ValueError(f"fov_y must be in (0, pi) radians, got {fov_y}")
    if not asp > 0.0:
        raise ValueError(f"aspect must be > 0, got {aspect}")
    if not zn > 0.0:
        raise ValueError(f"z_near must be > 0, got {z_near}")
    if not zf > zn:
        raise ValueError(f"z_far must be > z_near ({z_near}), got {z_far}")
    f = tg - e
    n = math.sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2])
    if not n > 0.0:
        raise ValueError("target must differ from eye")
    f = f / n
    nu = math.sqrt(u_in[0] * u_in[0] + u_in[1] * u_in[1] + u_in[2] * u_in[2])
    if not nu > 0.0:
        raise ValueError("up must be a non-zero vector")
    s = np.array([f[1] * u_in[2] - f[2] * u_in[1], f[2] * u_in[0] - f[0] * u_in[2], f[0] * u_in[1] - f[1] * u_in[0]])
    t = math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2])
    if not t > 1e-6 * nu:
        raise ValueError("up must not be parallel to the view direction (target - eye)")
    s = s / t
    u = np.array([s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]])
    view = np.zeros((4, 4))
    inv_view = np.zeros((4, 4))
    view[0, :3], view[1, :3], view[2, :3] = s, u, -f
    inv_view[:3, 0], inv_view[:3, 1], inv_view[:3, 2] = s, u, -f
    view[0, 3] = -(s[0] * e[0] + s[1] * e[1] + s[2] * e[2])
    view[1, 3] = -(u[0] * e[0] + u[1] * e[1] + u[2] * e[2])
    view[2, 3] = f[0] * e[0] + f[1] * e[1] + f[2] * e[2]
    view[3, 3] = 1.0
    inv_view[:3, 3] = e
    inv_view[3, 3] = 1.0
    th = math.tan(0.5 * fov)
    proj = np.zeros((4, 4))
    inv_proj = np.zeros((4, 4))
    proj[0, 0] = 1.0 / (asp * th)
    proj[1, 1] = 1.0 / th
    proj[2, 2] = -(zf + zn) / (zf - zn)
    proj[2, 3] = -(2.0 * zf * zn) / (zf - zn)
    proj[3, 2] = -1.0
    inv_proj[0, 0] = asp * th
    inv_proj[1, 1] = th
    inv_proj[2, 3] = -1.0
    inv_proj[3, 2] = (zn - zf) / (2.0 * zf * zn)
    inv_proj[3, 3] = (zf + zn) / (2.0 * zf * zn)
    inv_view_rot = inv_view.copy()
    inv_view_rot[:3, 3] = 0.0
    f32 = lambda m: np.ascontiguousarray(m, dtype=np.float32)  # noqa: E731
    return Camera(eye=f32(e), view=f32(view), proj=f32(proj), view_proj=f32(proj @ view),
                  inv_view_proj=f32(inv_view @ inv_proj), inv_view_proj_rot=f32(inv_view_rot @ inv_proj))


def c_camera_look_at(eye, target, up=(0.0, 1.0, 0.0), fov_y: float = math.radians(60.0), aspect: float = 16.0 / 9.0,
                     z_near: float = 0.01, z_far: float = 1000.0) -> Camera:
    """The same camera built by the C function ``ccl_camera_look_at`` (for checking the two against each other)."""
    from ..core.binding import ffi, lib, status_error

    cam = ffi().new("ccl_camera *")
    st = lib().ccl_camera_look_at(tuple(map(float, eye)), tuple(map(float, target)), tuple(map(float, up)),
                                  float(fov_y), float(aspect), float(z_near), float(z_far), cam)
    status_error(st, "ccl_camera_look_at")

    def m(name):
        return np.frombuffer(ffi().buffer(getattr(cam, name)), dtype=np.float32).reshape(4, 4).T.copy()

    return Camera(eye=np.array([cam.eye.x, cam.eye.y, cam.eye.z], np.float32), view=m("view"), proj=m("proj"),
                  view_proj=m("view_proj"), inv_view_proj=m("inv_view_proj"),
                  inv_view_proj_rot=m("inv_view_proj_rot"))


# --- element-wise evaluation kernels (inputs, options, then outputs) --------------------------------------------------

@wp.kernel
def _eval_ray_sphere(ox: wp.array(dtype=float), oy: wp.array(dtype=float), oz: wp.array(dtype=float),
                     dx: wp.array(dtype=float), dy: wp.array(dtype=float), dz: wp.array(dtype=float),
                     cx: wp.array(dtype=float), cy: wp.array(dtype=float), cz: wp.array(dtype=float),
                     r: wp.array(dtype=float), t0: wp.array(dtype=float), t1: wp.array(dtype=float)):
    i = wp.tid()
    a, b = ray_sphere(wp.vec3(ox[i], oy[i], oz[i]), _normalize3(wp.vec3(dx[i], dy[i], dz[i])),
                      wp.vec3(cx[i], cy[i], cz[i]), r[i])
    t0[i] = a
    t1[i] = b


@wp.kernel
def _eval_layer_segment(ox: wp.array(dtype=float), oy: wp.array(dtype=float), oz: wp.array(dtype=float),
                        dx: wp.array(dtype=float), dy: wp.array(dtype=float), dz: wp.array(dtype=float),
                        cx: wp.array(dtype=float), cy: wp.array(dtype=float), cz: wp.array(dtype=float),
                        r_earth: wp.array(dtype=float), r_inner: wp.array(dtype=float),
                        r_outer: wp.array(dtype=float), t_start: wp.array(dtype=float),
                        t_end: wp.array(dtype=float)):
    i = wp.tid()
    a, b = layer_segment(wp.vec3(ox[i], oy[i], oz[i]), _normalize3(wp.vec3(dx[i], dy[i], dz[i])),
                         wp.vec3(cx[i], cy[i], cz[i]), r_earth[i], r_inner[i], r_outer[i])
    t_start[i] = a
    t_end[i] = b


@wp.kernel
def _eval_view_sample_count(dir_y: wp.array(dtype=float), n_min: wp.array(dtype=wp.int32),
                            n_max: wp.array(dtype=wp.int32), out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = float(view_sample_count(dir_y[i], n_min[i], n_max[i]))


@wp.kernel
def _eval_light_sample_offset(idx: wp.array(dtype=wp.int32), sx: wp.array(dtype=float), sy: wp.array(dtype=float),
                              sz: wp.array(dtype=float), step: wp.array(dtype=float),
                              cone_angle: wp.array(dtype=float), far_factor: wp.array(dtype=float),
                              out_x: wp.array(dtype=float), out_y: wp.array(dtype=float),
                              out_z: wp.array(dtype=float)):
    i = wp.tid()
    p = light_sample_position(wp.vec3(0.0, 0.0, 0.0), _normalize3(wp.vec3(sx[i], sy[i], sz[i])), idx[i], step[i],
                              cone_angle[i], far_factor[i], light_cone_kernel(idx[i]))
    out_x[i] = p[0]
    out_y[i] = p[1]
    out_z[i] = p[2]


@wp.kernel
def _eval_march_accumulate(cr: wp.array(dtype=float), cg: wp.array(dtype=float), cb: wp.array(dtype=float),
                           transmittance: wp.array(dtype=float), sigma: wp.array(dtype=float),
                           rho: wp.array(dtype=float), dt: wp.array(dtype=float), lr: wp.array(dtype=float),
                           lg: wp.array(dtype=float), lb: wp.array(dtype=float), eps: wp.array(dtype=float),
                           out_r: wp.array(dtype=float), out_g: wp.array(dtype=float), out_b: wp.array(dtype=float),
                           out_t: wp.array(dtype=float), out_stop: wp.array(dtype=float)):
    i = wp.tid()
    c, t, stop = march_accumulate(wp.vec3(cr[i], cg[i], cb[i]), transmittance[i], sigma[i], rho[i], dt[i],
                                  wp.vec3(lr[i], lg[i], lb[i]), eps[i])
    out_r[i] = c[0]
    out_g[i] = c[1]
    out_b[i] = c[2]
    out_t[i] = t
    out_stop[i] = float(stop)


@wp.kernel
def _eval_ray_jitter(dx: wp.array(dtype=float), dy: wp.array(dtype=float), dz: wp.array(dtype=float),
                     x: wp.array(dtype=wp.int32), y: wp.array(dtype=wp.int32), frame: wp.array(dtype=wp.int32),
                     amount: wp.array(dtype=float), mode: int, out_dx: wp.array(dtype=float),
                     out_dy: wp.array(dtype=float), out_dz: wp.array(dtype=float), out_offset: wp.array(dtype=float)):
    i = wp.tid()
    d = _normalize3(wp.vec3(dx[i], dy[i], dz[i]))
    offset = 0.5
    if mode == 0:
        d = ray_jitter_tilt(d, wp.uint32(x[i]), wp.uint32(y[i]), wp.uint32(frame[i]), amount[i])
    elif mode == 1:
        offset = ray_jitter_offset(wp.uint32(x[i]), wp.uint32(y[i]), wp.uint32(frame[i]))
    out_dx[i] = d[0]
    out_dy[i] = d[1]
    out_dz[i] = d[2]
    out_offset[i] = offset


@wp.kernel
def _camera_ray_kernel(xs: wp.array(dtype=wp.int32), ys: wp.array(dtype=wp.int32), width: int, height: int,
                       inv_view_proj_rot: wp.mat44, out: wp.array(dtype=wp.vec3)):
    i = wp.tid()
    out[i] = camera_ray(inv_view_proj_rot, xs[i], ys[i], width, height)


@wp.kernel
def _march_volume_kernel(origins: wp.array(dtype=wp.vec3), dirs: wp.array(dtype=wp.vec3), kind: int, a: wp.vec3,
                         b: wp.vec3, radius: float, n: int, offset: float, points: wp.array2d(dtype=wp.vec3),
                         dts: wp.array(dtype=float)):
    r = wp.tid()
    o = origins[r]
    d = _normalize3(dirs[r])
    t0 = float(0.0)
    t1 = float(0.0)
    if kind == 0:
        t0, t1 = ray_sphere(o, d, a, radius)
    else:
        t0, t1 = ray_box(o, d, a, b)
    ts, dt = march_interval(t0, t1, n)
    for i in range(n):
        points[r, i] = march_point(o, d, ts, dt, i, offset)
    dts[r] = dt


# --- custom evaluators (vc-A25 camera rays, vc-A35 bounded march) -----------------------------------------------------

def _int_array(value, name: str, lo: int | None = None) -> np.ndarray:
    return Arg(name, lo=lo, dtype="int32").check(value)


def _check_camera(camera, name: str = "camera") -> Camera:
    if not isinstance(camera, Camera):
        raise TypeError(f"{name} must be a pywarp.kernels.raymarch.Camera (see camera_look_at), got "
                        f"{type(camera).__name__}")
    return camera


def _check_size(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    if value < 1:
        raise ValueError(f"{name} must be >= 1, got {value}")
    return int(value)


def _camera_ray_args(x, y, width, height, camera):
    width = _check_size(width, "width")
    height = _check_size(height, "height")
    camera = _check_camera(camera)
    xa = _int_array(x, "x", lo=0)
    ya = _int_array(y, "y", lo=0)
    if np.any(xa >= width):
        raise ValueError(f"x must be in [0, width - 1] = [0, {width - 1}], got {xa[xa >= width].flat[0]}")
    if np.any(ya >= height):
        raise ValueError(f"y must be in [0, height - 1] = [0, {height - 1}], got {ya[ya >= height].flat[0]}")
    try:
        shape = np.broadcast_shapes(xa.shape, ya.shape)
    except ValueError:
        raise ValueError(f"camera_ray(): the shapes of x{xa.shape} and y{ya.shape} do not broadcast") from None
    return (np.ascontiguousarray(np.broadcast_to(xa, shape).ravel()),
            np.ascontiguousarray(np.broadcast_to(ya, shape).ravel()), shape, width, height, camera)


def _warp_camera_ray(eq, device):
    from ..core.runtime import resolve_device

    dev = resolve_device(device)

    def camera_ray(x, y, width, height, camera):
        """Unit view directions (..., 3) through pixel centres (x, y) of a width x height image (vc-A25)."""
        xs, ys, shape, width, height, camera = _camera_ray_args(x, y, width, height, camera)
        out = wp.empty(xs.size, dtype=wp.vec3, device=dev)
        if xs.size:
            wp.launch(_camera_ray_kernel, dim=xs.size, inputs=[wp.array(xs, dtype=wp.int32, device=dev),
                                                              wp.array(ys, dtype=wp.int32, device=dev), width, height,
                                                              camera.mat44("inv_view_proj_rot")],
                      outputs=[out], device=dev)
        return out.numpy().reshape(*shape, 3)

    return camera_ray


def _c_camera_ray(eq):
    from ..core.binding import ffi, lib

    def camera_ray(x, y, width, height, camera):
        """Unit view directions (..., 3) through pixel centres (x, y) of a width x height image (vc-A25), C."""
        xs, ys, shape, width, height, camera = _camera_ray_args(x, y, width, height, camera)
        m = ffi().new("float[16]", camera.column_major("inv_view_proj_rot").tolist())
        out = np.empty((xs.size, 3), np.float32)
        fn = lib().ccl_camera_ray
        for k in range(xs.size):
            d = fn(m, int(xs[k]), int(ys[k]), width, height)
            out[k] = (d.x, d.y, d.z)
        return out.reshape(*shape, 3)

    return camera_ray


def _march_volume_args(origin, direction, n, centre, radius, box_min, box_max, offset):
    o = np.asarray(origin, dtype=np.float64) if not isinstance(origin, str) else None
    d = np.asarray(direction, dtype=np.float64) if not isinstance(direction, str) else None
    for arr, name in ((o, "origin"), (d, "direction")):
        if arr is None or arr.ndim == 0 or arr.shape[-1] != 3:
            raise ValueError(f"{name} must be an array of 3-vectors (..., 3)")
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{name} must be finite (no NaN or Inf)")
    try:
        shape = np.broadcast_shapes(o.shape[:-1], d.shape[:-1])
    except ValueError:
        raise ValueError(f"march_volume(): origin{o.shape} and direction{d.shape} do not broadcast") from None
    if np.any(np.sum(d * d, axis=-1) == 0.0):
        raise ValueError("direction must be non-zero")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        raise TypeError(f"n must be an integer, got {n!r}")
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    off = _finite_float(offset, "offset")
    if not 0.0 <= off < 1.0:
        raise ValueError(f"offset must be in [0, 1), got {offset}")
    sphere = centre is not None or radius is not None
    box = box_min is not None or box_max is not None
    if sphere == box:
        raise ValueError("give either centre and radius (a bounding sphere) or box_min and box_max (a box)")
    if sphere:
        if centre is None or radius is None:
            raise ValueError("a bounding sphere needs both centre and radius")
        a = _vec3_value(centre, "centre")
        r = _finite_float(radius, "radius")
        if r <= 0:
            raise ValueError(f"radius must be > 0, got {radius}")
        b = np.zeros(3)
        kind = 0
    else:
        if box_min is None or box_max is None:
            raise ValueError("a box needs both box_min and box_max")
        a = _vec3_value(box_min, "box_min")
        b = _vec3_value(box_max, "box_max")
        if np.any(a > b):
            raise ValueError(f"box_min must be <= box_max component-wise, got {a.tolist()} and {b.tolist()}")
        r = 0.0
        kind = 1
    f32 = lambda v: np.ascontiguousarray(v, dtype=np.float32)  # noqa: E731
    o = f32(np.broadcast_to(o, (*shape, 3)).reshape(-1, 3))
    d = f32(np.broadcast_to(d, (*shape, 3)).reshape(-1, 3))
    return o, d, shape, int(n), kind, f32(a), f32(b), float(np.float32(r)), float(np.float32(off))


def _warp_march_volume(eq, device):
    from ..core.runtime import resolve_device

    dev = resolve_device(device)

    def march_volume(origin, direction, n, centre=None, radius=None, box_min=None, box_max=None, offset=0.5):
        """Sample positions (..., n, 3) and step lengths (...) of n uniform steps through a bounding sphere
        (centre, radius) or box (box_min, box_max) in front of the origin; NaN where the ray misses (vc-A35)."""
        o, d, shape, n, kind, a, b, r, off = _march_volume_args(origin, direction, n, centre, radius, box_min,
                                                                 box_max, offset)
        pts = wp.empty((o.shape[0], n), dtype=wp.vec3, device=dev)
        dts = wp.empty(o.shape[0], dtype=float, device=dev)
        if o.shape[0]:
            wp.launch(_march_volume_kernel, dim=o.shape[0],
                      inputs=[wp.array(o, dtype=wp.vec3, device=dev), wp.array(d, dtype=wp.vec3, device=dev), kind,
                              wp.vec3(*a.tolist()), wp.vec3(*b.tolist()), r, n, off], outputs=[pts, dts], device=dev)
        return pts.numpy().reshape(*shape, n, 3), dts.numpy().reshape(shape)

    return march_volume


def _c_march_volume(eq):
    from ..core.binding import ffi, lib

    def march_volume(origin, direction, n, centre=None, radius=None, box_min=None, box_max=None, offset=0.5):
        """C twin of the vc-A35 evaluator (ccl_march_sphere / ccl_march_box)."""
        o, d, shape, n, kind, a, b, r, off = _march_volume_args(origin, direction, n, centre, radius, box_min,
                                                                 box_max, offset)
        F, L = ffi(), lib()
        pts_c = F.new("ccl_vec3[]", n)
        dt_c = F.new("float *")
        pts = np.empty((o.shape[0], n, 3), np.float32)
        dts = np.empty(o.shape[0], np.float32)
        for k in range(o.shape[0]):
            ok, dk = tuple(o[k].tolist()), tuple(d[k].tolist())
            if kind == 0:
                L.ccl_march_sphere(ok, dk, tuple(a.tolist()), r, n, off, pts_c, dt_c)
            else:
                L.ccl_march_box(ok, dk, tuple(a.tolist()), tuple(b.tolist()), n, off, pts_c, dt_c)
            pts[k] = np.frombuffer(F.buffer(pts_c), dtype=np.float32).reshape(n, 3)
            dts[k] = dt_c[0]
        return pts.reshape(*shape, n, 3), dts.reshape(shape)

    return march_volume


# --- registry ---------------------------------------------------------------------------------------------------------

def _nonzero_direction(prefix: str, names=("dx", "dy", "dz")):
    def check(**kw):
        x, y, z = (np.asarray(kw[n], dtype=np.float64) for n in names)
        if np.any(x * x + y * y + z * z == 0.0):
            raise ValueError(f"{prefix} ({', '.join(names)}) must be non-zero")
    return check


def _check_layer(**kw):
    _nonzero_direction("direction")(**kw)
    re, ri, ro = (np.asarray(kw[n]) for n in ("r_earth", "r_inner", "r_outer"))
    if np.any(ri < re):
        raise ValueError(f"r_inner must be >= r_earth, got r_inner={np.min(ri)}, r_earth={np.max(re)}")
    if np.any(ri >= ro):
        raise ValueError(f"r_inner must be < r_outer, got r_inner={np.max(ri)}, r_outer={np.min(ro)}")


def _check_counts(**kw):
    if np.any(np.asarray(kw["n_min"]) > np.asarray(kw["n_max"])):
        raise ValueError(f"n_min must be <= n_max, got n_min={np.max(kw['n_min'])}, n_max={np.min(kw['n_max'])}")


_F = dict(dtype="float32")
_O = tuple(Arg(n, "ray origin component (km)") for n in ("ox", "oy", "oz"))
_D = tuple(Arg(n, "ray direction component (any non-zero length; normalized)") for n in ("dx", "dy", "dz"))
_DEFAULT_LAYER = CloudLayer()

register(Equation(
    "vc-A14", "ray_sphere", "ccl_ray_sphere_flat", ray_sphere, _eval_ray_sphere,
    args=(*_O, *_D, Arg("cx", "sphere centre x"), Arg("cy", "sphere centre y"), Arg("cz", "sphere centre z"),
          Arg("radius", "sphere radius (> 0)", lo=0.0, lo_open=True)),
    outputs=("t_near", "t_far"), check=_nonzero_direction("direction"),
    summary="Ray-sphere intersection distances t_near <= t_far along the normalized direction (negative = behind "
            "the origin); NaN where the ray misses. Used for the Earth and the two cloud-layer spheres (defaults: "
            "Earth radius 6371 km, layer 1.5-4 km above the ground, centre (0, -6371, 0)).",
    references=("Haines, Guenther, Akenine-Moeller, Precision Improvements for Ray/Sphere Intersection, "
                "Ray Tracing Gems, 2019",)))

register(Equation(
    "vc-A24", "layer_segment", "ccl_layer_segment_flat", layer_segment, _eval_layer_segment,
    args=(*_O, *_D,
          Arg("cx", "planet centre x (km)", default=0.0), Arg("cy", "planet centre y (km)", default=-EARTH_RADIUS_KM),
          Arg("cz", "planet centre z (km)", default=0.0),
          Arg("r_earth", "Earth radius (km)", lo=0.0, lo_open=True, default=_DEFAULT_LAYER.r_earth),
          Arg("r_inner", "cloud-layer base radius (km)", lo=0.0, lo_open=True, default=_DEFAULT_LAYER.r_inner),
          Arg("r_outer", "cloud-layer top radius (km)", lo=0.0, lo_open=True, default=_DEFAULT_LAYER.r_outer)),
    outputs=("t_start", "t_end"), check=_check_layer,
    summary="The raymarch interval through the cloud layer for a camera below (vc-A14: inner far root to outer far "
            "root, nothing below the horizon), inside (camera to first exit) or above (outer entry to inner entry "
            "or outer exit) the layer; NaN where the ray sees no cloud layer.",
    references=("Hillaire, Physically based sky, atmosphere and cloud rendering in Frostbite, SIGGRAPH 2016 course",)))

register(Equation(
    "vc-A18", "view_sample_count", "ccl_view_sample_count", view_sample_count, _eval_view_sample_count,
    args=(Arg("dir_y", "y component of the unit view direction", lo=-1.0, hi=1.0),
          Arg("n_min", "samples at zenith/nadir", lo=1, dtype="int32", default=VIEW_SAMPLES_ZENITH),
          Arg("n_max", "samples at the horizon", lo=1, dtype="int32", default=VIEW_SAMPLES_HORIZON)),
    outputs=("n",), check=_check_counts,
    summary="View-ray sample count N = round(mix(n_max, n_min, |dir_y|)) (64 at zenith, 128 at the horizon; the "
            "interpolation law is our choice). Returned as float32 holding an integer.",
    references=("Barvir, Volumetric clouds, FIT BUT 2020, §4.3.2 and §4.6",)))

register(Equation(
    "vc-A19", "light_sample_offset", "ccl_light_sample_offset_flat", light_sample_position, _eval_light_sample_offset,
    args=(Arg("i", "light sample index 0..5 (5 = the far sample)", lo=0, hi=5, dtype="int32"),
          Arg("sx", "direction to the sun x (any non-zero length)"), Arg("sy", "direction to the sun y"),
          Arg("sz", "direction to the sun z"),
          Arg("step", "axial step (km)", lo=0.0, lo_open=True, default=LIGHT_STEP_KM),
          Arg("cone_angle", "cone half-angle (rad)", lo=0.0, hi=math.pi / 2, hi_open=True, default=LIGHT_CONE_ANGLE),
          Arg("far_factor", "far sample distance / near cone length", lo=0.0, lo_open=True,
              default=LIGHT_FAR_FACTOR)),
    outputs=("x", "y", "z"), check=_nonzero_direction("sun direction", ("sx", "sy", "sz")),
    summary="Offset of light sample i from the view sample: s_i to_sun + s_i tan(cone_angle) k_i with s_i = (i+1) "
            "step for the 5 near samples and far_factor * 5 step for the 6th; k_i = LIGHT_CONE_KERNEL[i].",
    references=("Schneider & Vos, The real-time volumetric cloudscapes of Horizon Zero Dawn, SIGGRAPH 2015",
                "Schneider, Real-time volumetric cloudscapes, GPU Pro 7, 2016")))

register(Equation(
    "vc-A21", "march_accumulate", "ccl_march_accumulate_flat", march_accumulate, _eval_march_accumulate,
    args=(Arg("cr", "accumulated colour r"), Arg("cg", "accumulated colour g"), Arg("cb", "accumulated colour b"),
          Arg("transmittance", "view transmittance T so far", lo=0.0, hi=1.0),
          Arg("sigma", "extinction per unit density (1/km)", lo=0.0),
          Arg("rho", "density at the sample", lo=0.0), Arg("dt", "step length (km)", lo=0.0),
          Arg("lr", "sample radiance r", lo=0.0), Arg("lg", "sample radiance g", lo=0.0),
          Arg("lb", "sample radiance b", lo=0.0),
          Arg("eps", "early-termination threshold: stop when 1 - T >= 1 - eps", lo=0.0, hi=1.0, default=MARCH_EPS)),
    outputs=("r", "g", "b", "transmittance", "stop"),
    summary="One front-to-back step: tau = sigma rho dt, C += T (1 - e^-tau) L, T *= e^-tau; stop = 1.0 when "
            "1 - T >= 1 - eps (default eps = 1/256).",
    references=("Barvir, Volumetric clouds, FIT BUT 2020, §4.3.2",
                "Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed., §11.2")))

register(Equation(
    "vc-A23", "ray_jitter", "ccl_ray_jitter_flat", ray_jitter_tilt, _eval_ray_jitter,
    args=(*_D, Arg("x", "pixel x", lo=0, dtype="int32"), Arg("y", "pixel y", lo=0, dtype="int32"),
          Arg("frame", "frame number", lo=0, dtype="int32"),
          Arg("amount", "tilt scale (rad)", lo=0.0, default=JITTER_AMOUNT)),
    options=(Option("mode", JITTER_MODES, "tilt",
                    "'tilt' (default, the thesis): tilt the direction; 'offset': keep it and jitter the start "
                    "offset; 'none'"),),
    outputs=("dx", "dy", "dz", "offset"), check=_nonzero_direction("direction"),
    summary="Ray jitter against banding, seeded by (x, y, frame) through the PCG hash: mode 'tilt' returns "
            "normalize(d + amount r), r in [-1, 1)^3, offset 0.5; mode 'offset' the normalized d and an offset in "
            "[0, 1) for the first sample (t = t_start + (i + offset) dt); mode 'none' d and 0.5.",
    references=("Jarzynski & Olano, Hash Functions for GPU Rendering, JCGT 9(3), 2020",)))

register(Equation(
    "vc-A25", "camera_ray", "ccl_camera_ray", camera_ray, _camera_ray_kernel,
    make_warp=_warp_camera_ray, make_c=_c_camera_ray,
    summary="camera_ray(x, y, width, height, camera) -> unit directions (..., 3) through pixel centres: "
            "uv = ((x+0.5)/W, (y+0.5)/H), NDC = (2u-1, 1-2v, 1), h = inverse view-projection of the camera moved to "
            "the origin times (NDC, 1), d = normalize(h.xyz). camera from camera_look_at (GLM lookAt + perspective, "
            "float32 matrices).",
    references=("GLM lookAt / perspective (OpenGL conventions)",)))

register(Equation(
    "vc-A35", "march_volume", "ccl_march_sphere", march_point, _march_volume_kernel,
    make_warp=_warp_march_volume, make_c=_c_march_volume,
    summary="march_volume(origin, direction, n, centre=, radius= | box_min=, box_max=, offset=0.5) -> (points "
            "(..., n, 3), dt (...)): n uniform steps over the part of the ray in front of the origin inside a "
            "bounding sphere or axis-aligned box, sample i at t_start + (i + offset) dt; NaN where the ray misses.",
    references=("Pharr, Jakob & Humphreys, Physically Based Rendering, 4th ed., §11.3 (ray marching)",)))

register(Equation(
    "vc-A36", "vc_constants", "ccl_vc_constants", vc_constants, _eval_vc_constants,
    make_warp=_warp_vc_constants, make_c=_c_vc_constants,
    summary="vc_constants() -> VcConstants: the constants collected from the thesis (texture sizes, fBm weights, "
            "erosion, powder, Schlick fit, cloud types, gradient break points, sample counts, reprojection block and "
            "cycle, tone-map constant, CIE clear sky, cloud altitudes, Rayleigh ratio).",
    references=("Barvir, Volumetric clouds, FIT BUT 2020 (spec/vc.md vc-A36)",)))
