"""The 3-D cloud array of the oc text (Kucera 2006, §5.2) -- Warp twins of ``cclouds/voxel.h``.

Public interface (stable; the flight scene renders what it returns)::

    from pywarp.kernels.voxel import CloudArraySettings, cloud_volume
    vol = cloud_volume(CloudArraySettings(size=64, seed=3))   # uint8 (64, 64, 64) indexed [z, y, x], 0..255
    vol = cloud_volume(size=64, seed=3, cover=110.0)          # the same with keyword overrides

* :class:`CloudArraySettings` -- every parameter with its default and the reason for it (the text gives no values).
* :func:`noise_volume` (oc-5.2.1) -- the noise array before filtering, float32 in [0, 1]: a size/8 array of value
  noise up-sampled level by level (x2) with new noise of lower amplitude added at each level; ``border`` picks the
  border handling: ``"zero"`` (default, the adopted larger array with zero borders, oc-5.2.3.2), ``"sin"`` (the
  rejected SIN rounding, oc-5.2.3.1, in our reading), ``"none"`` (the border problem, oc-5.2.3).
* :func:`voxel_filter` (oc-5.2.2) -- Elias's exponential cut-out, density = 255 (1 - sharpness^max(255 n - cover,
  0)); :func:`cloud_volume` -- noise + filter, uint8 0..255 (0 = invisible, 255 = opaque).
* :func:`voxel_sin_window` (oc-5.2.3.1) -- the SIN weight at a distance from the nearest face.
* :func:`scale_volume` (oc-5.2.3-scale) -- per-axis scaling by trilinear resampling (corners aligned: a zero border
  stays zero).
* :func:`bench_cloud_array` -- generation time by size and by interpolation (``pywarp bench flight``).

The build and every reading where the text is silent are stated in ``cclouds/voxel.h`` and repeated in
:class:`CloudArraySettings`. ``cover`` reads inverted in the text ("how big a cloud we want"): a larger cover
subtracts more and leaves LESS cloud -- it is a coverage threshold in 0..255 units.
"""
from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, replace

import numpy as np
import warp as wp

from ..core.params import Settings, param
from ..core.registry import Arg, Equation, declare
from .valuenoise import INTERPOLATIONS, SMOOTHINGS, interp_kind, octave_seed, valuenoise_linear, valuenoise_smooth

BORDERS = {"none": 0, "sin": 1, "zero": 2}  # CCL_VOXEL_BORDER_*
VARIANTS = {"corrected": 0, "thesis": 1}
MAX_LEVELS = 6  # CCL_VOXEL_MAX_LEVELS
MIN_BASE = 4  # CCL_VOXEL_MIN_BASE
MAX_SIZE = 256  # CCL_VOXEL_MAX_SIZE
MAX_SCALE_EDGE = 1024  # CCL_VOXEL_MAX_SCALE_EDGE
_BORDER_SIN = wp.constant(1)
_BORDER_ZERO = wp.constant(2)
_CUBIC = wp.constant(2)
_HALF_PI = wp.constant(1.57079637)

_REF_ELIAS = "H. Elias, Clouds tutorial (freespace.virgin.net/hugo.elias/models/m_clouds.htm), oc ref. [3]"


# --- settings ------------------------------------------------------------------------------------------------------------

def _check_size(obj, name, v):
    levels = obj.levels
    step = 2 ** (levels - 1)
    if v % step != 0 or v // step < MIN_BASE:
        raise ValueError(f"{name} must be a multiple of 2^(levels - 1) = {step} with {name} / {step} >= {MIN_BASE} "
                         f"(the level-0 array, size/8 for 4 levels), got {v}")


@dataclass(frozen=True)
class CloudArraySettings(Settings):
    """Settings of the cloud array (oc-5.2.1 - 5.2.3-scale); mirrors ``ccl_voxel_settings`` and is checked in the
    order of ``ccl_voxel_settings_check``. The text gives no values: each default says where it comes from."""

    _validation_order = ("levels", "size")
    INVALIDATES = Settings.INVALIDATES + ("textures",)  # the cloud array is regenerated

    size: int = param(64, unit="voxels", kind="int", lo=MIN_BASE, hi=MAX_SIZE, check=_check_size,
                      invalidates="textures", group="cloud array",
                      doc="edge of the cubic cloud array (a multiple of 2^(levels - 1))",
                      reason="64: the array name noise64 of the filter listing (oc-5.2.2) suggests 64^3")
    levels: int = param(4, kind="int", lo=1, hi=MAX_LEVELS, invalidates="textures", group="cloud array",
                        doc="number of arrays from the base to the full size (edge x2 per level)",
                        reason="4: size/8 -> size/4 -> size/2 -> size, the text's size/8 base (§5.2.1)")
    seed: int = param(0, kind="uint32", lo=0, hi=2 ** 32 - 1, invalidates="textures", group="cloud array",
                      doc="seed of the noise (uint32); the same seed gives the same volume",
                      reason="any; 0 is the reproducible default")
    persistence: float = param(0.5, lo=0.0, lo_open=True, hi=1.0, invalidates="textures", group="cloud array",
                               doc="amplitude ratio of successive levels (oc-5.1.2.2)",
                               reason="0.5: Elias's example value; the text says only 0-1 and that lower values "
                                      "look better (fig. 5.5)")
    interpolation: str = param("linear", choices=tuple(INTERPOLATIONS), invalidates="textures", group="cloud array",
                               doc="up-sampling interpolant: linear (trilinear), cosine, or the printed cubic",
                               reason="'linear': the 3-D analogue of the text's bilinear up-sampling, 'mainly used "
                                      "for real time' (§5.1.4.1)")
    smoothing: str = param("elias", choices=tuple(SMOOTHINGS), invalidates="textures", group="cloud array",
                           doc="smoothing of the noise added at each level (oc-5.1.3)",
                           reason="'elias': Elias's weights; with raw per-voxel noise the finest levels make a "
                                  "speckled 'popcorn' cloud, smoothed the clouds are compact")
    variant: str = param("corrected", choices=tuple(VARIANTS), invalidates="textures", group="cloud array",
                         doc="persistence schedule: 'corrected' p^l, 'thesis' the printed squaring p^(2^l)",
                         reason="'corrected': the reading of the cited tutorial (spec erratum 3)")
    border: str = param("zero", choices=tuple(BORDERS), invalidates="textures", group="cloud array",
                        doc="border handling: 'zero' = larger array with zero borders (oc-5.2.3.2), 'sin' = the "
                            "rejected SIN rounding (oc-5.2.3.1), 'none' = the border problem (oc-5.2.3)",
                        reason="'zero': the method the text adopts")
    sin_radius: float = param(0.125, unit="of the edge", lo=0.0, lo_open=True, hi=0.5, invalidates="textures",
                              group="cloud array", doc="radius of the SIN rounding as a fraction of the edge",
                              reason="0.125: one level-0 cell (size/8); the text gives no radius")
    cover: float = param(128.0, unit="0..255", lo=0.0, hi=255.0, invalidates="textures", group="cloud array",
                         doc="cloudCover: noise threshold in 0..255 units; a LARGER cover gives LESS cloud (the "
                             "text's 'how big a cloud we want' reads inverted)",
                         reason="128, the middle of the range: the smoothed noise spreads little around its mean "
                                "(about 0.4 x 255 with the zero border's fall-off), so 128 keeps the brightest 15-30 % "
                                "of the voxels -- one or a few compact clouds inside the box")
    sharpness: float = param(0.96, lo=0.0, hi=1.0, lo_open=True, hi_open=True, invalidates="textures",
                             group="cloud array",
                             doc="cloudSharpness in (0, 1): near 0 hard edges, near 1 soft, faint edges",
                             reason="0.96: half density 17 units above the cover -- soft but visible edges, of the "
                                    "order of Elias's values")

    @property
    def shape(self) -> tuple[int, int, int]:
        return (self.size, self.size, self.size)

    def level_sizes(self) -> list[int]:
        base = self.size >> (self.levels - 1)
        return [base << k for k in range(self.levels)]


def _settings(settings, overrides) -> CloudArraySettings:
    if settings is None:
        settings = CloudArraySettings()
    elif not isinstance(settings, CloudArraySettings):
        raise TypeError(f"settings must be a CloudArraySettings, got {type(settings).__name__}")
    return replace(settings, **overrides) if overrides else settings


def settings_struct(s: CloudArraySettings):
    """A cffi ``ccl_voxel_settings *`` of ``s``."""
    from ..core.binding import ffi

    st = ffi().new("ccl_voxel_settings *")
    st.size, st.levels, st.seed = s.size, s.levels, s.seed
    st.persistence = s.persistence
    st.interpolation = INTERPOLATIONS[s.interpolation]
    st.smoothing = SMOOTHINGS[s.smoothing]
    st.variant = VARIANTS[s.variant]
    st.border = BORDERS[s.border]
    st.sin_radius, st.cover, st.sharpness = s.sin_radius, s.cover, s.sharpness
    return st


# --- evaluators of the whole-array entries (registered below) ------------------------------------------------------

def _cloud_make(impl):
    def factory(eq: Equation, device=None):
        def call(settings=None, **overrides):
            return cloud_volume(settings, impl=impl, device=device, **overrides)

        return call

    return factory if impl == "warp" else (lambda eq: factory(eq, None))


def _scale_make(impl):
    def factory(eq: Equation, device=None):
        def call(volume, scale):
            return scale_volume(volume, scale, impl=impl, device=device)

        return call

    return factory if impl == "warp" else (lambda eq: factory(eq, None))


# --- element-wise entries ------------------------------------------------------------------------------------------------

# powf of two libms (glibc, Warp's runtime), each within 1 ulp: <= 2 ulp apart in s^c, a few ulp of 255 after the
# subtraction where s^c is close to 1 (density near 0): bound 8 ulp
@declare("oc-5.2.2", c="ccl_voxel_filter",
         args=(Arg("n", "noise value in [0, 1]", lo=0.0, hi=1.0),
               Arg("cover", "cloudCover, threshold in 0..255 units (larger = LESS cloud)", lo=0.0, hi=255.0),
               Arg("sharpness", "cloudSharpness (near 0 hard, near 1 soft edges)", lo=0.0, hi=1.0, lo_open=True,
                   hi_open=True)),
         outputs=("density",), ulp=8,
         summary="Exponential cloud filter, as printed: c = n*255 - cover, c = max(c, 0), density = 255 - "
                 "sharpness^c * 255, in [0, 255]: 0 where 255 n <= cover, increasing in n, decreasing in cover and "
                 "in sharpness. The text's 'cloudCover: how big a cloud we want' reads inverted (a larger cover "
                 "gives less cloud); sharpness must lie in (0, 1) (1 gives 0 everywhere, > 1 negative density).",
         references=(_REF_ELIAS,))
@wp.func
def voxel_filter(n: float, cover: float, sharpness: float) -> float:
    """oc-5.2.2: 255 - sharpness^max(n*255 - cover, 0) * 255."""
    c = n * 255.0 - cover
    if c < 0.0:
        c = 0.0
    return 255.0 - wp.pow(sharpness, c) * 255.0


@declare("oc-5.2.3.1", c="ccl_voxel_sin_window",
         args=(Arg("d", "distance from the nearest face in voxels", lo=0, hi=4096, dtype="int32"),
               Arg("radius", "rounding radius in voxels", lo=0.0, lo_open=True, hi=4096.0)),
         outputs=("w",),
         summary="SIN rounding weight (rejected by the author, no formula printed; our reading of 'attenuate the "
                 "values coordinate by coordinate with SIN near the borders'): w = sin(pi/2 * d / radius) for "
                 "d < radius, else 1; the cloud array multiplies the three axes' weights. 0 on the faces, so the "
                 "cloud is no longer cut -- but it takes the rounded box's shape.")
@wp.func
def voxel_sin_window(d: int, radius: float) -> float:
    """oc-5.2.3.1: sin(pi/2 * (d / radius)) for d < radius, else 1."""
    fd = float(d)
    if fd >= radius:
        return 1.0
    return wp.sin(_HALF_PI * (fd / radius))


# --- the build (mirrors voxel.c) -----------------------------------------------------------------------------------------

@wp.func
def _axis_i0(i: int, nf: int, nc: int) -> int:
    pos = float(i * (nc - 1)) / float(nf - 1)
    k = int(pos)
    if k > nc - 2:
        k = nc - 2
    return k


@wp.func
def _axis_t(i: int, nf: int, nc: int, k: int) -> float:
    pos = float(i * (nc - 1)) / float(nf - 1)
    return pos - float(k)


@wp.func
def _clampi(i: int, n: int) -> int:
    if i < 0:
        return 0
    if i > n - 1:
        return n - 1
    return i


@wp.func
def _line_x(src: wp.array(dtype=float), nc: int, zi: int, yi: int, x0: int, tx: float, kind: int) -> float:
    row = (zi * nc + yi) * nc
    if kind == _CUBIC:
        return interp_kind(kind, src[row + _clampi(x0 - 1, nc)], src[row + x0], src[row + x0 + 1],
                           src[row + _clampi(x0 + 2, nc)], tx)
    return interp_kind(kind, 0.0, src[row + x0], src[row + x0 + 1], 0.0, tx)


@wp.func
def _plane_xy(src: wp.array(dtype=float), nc: int, zi: int, y0: int, ty: float, x0: int, tx: float,
              kind: int) -> float:
    v0 = float(0.0)
    v3 = float(0.0)
    if kind == _CUBIC:
        v0 = _line_x(src, nc, zi, _clampi(y0 - 1, nc), x0, tx, kind)
        v3 = _line_x(src, nc, zi, _clampi(y0 + 2, nc), x0, tx, kind)
    return interp_kind(kind, v0, _line_x(src, nc, zi, y0, x0, tx, kind), _line_x(src, nc, zi, y0 + 1, x0, tx, kind),
                       v3, ty)


@wp.func
def voxel_upsample(src: wp.array(dtype=float), nc: int, nf: int, x: int, y: int, z: int, kind: int) -> float:
    """Value at fine voxel (x, y, z) of edge nf of the coarse array ``src`` (edge nc, index (z nc + y) nc + x),
    separable x, y, z with the interpolant ``kind``, corners aligned (fine i -> coarse i (nc - 1) / (nf - 1)),
    end nodes of the cubic clamped. As the static ``upsample`` of voxel.c."""
    x0 = _axis_i0(x, nf, nc)
    y0 = _axis_i0(y, nf, nc)
    z0 = _axis_i0(z, nf, nc)
    tx = _axis_t(x, nf, nc, x0)
    ty = _axis_t(y, nf, nc, y0)
    tz = _axis_t(z, nf, nc, z0)
    v0 = float(0.0)
    v3 = float(0.0)
    if kind == _CUBIC:
        v0 = _plane_xy(src, nc, _clampi(z0 - 1, nc), y0, ty, x0, tx, kind)
        v3 = _plane_xy(src, nc, _clampi(z0 + 2, nc), y0, ty, x0, tx, kind)
    return interp_kind(kind, v0, _plane_xy(src, nc, z0, y0, ty, x0, tx, kind),
                       _plane_xy(src, nc, z0 + 1, y0, ty, x0, tx, kind), v3, tz)


# A whole volume from settings, not element-wise: custom evaluators (cloud_volume).
@declare("oc-5.2.1", "oc-5.2.3", "oc-5.2.3.2", c="ccl_voxel_cloud", name="voxel_cloud", make_warp=_cloud_make("warp"),
         make_c=_cloud_make("c"), outputs=("volume",),
         summary="The 3-D cloud array: a size/8 array of value noise up-sampled x2 level by level (trilinear by "
                 "default, cosine, or the printed cubic; corners aligned) with new noise of amplitude "
                 "persistence^l added at each level, normalised to [0, 1], cut out by the filter oc-5.2.2 and stored "
                 "as uint8 0..255 [z, y, x]. border='zero' (default): the larger array with zero borders -- the "
                 "outermost layer of every level stays 0, every outer-face voxel is 0 (oc-5.2.3.2); border='none' "
                 "reproduces the border problem (oc-5.2.3: the cloud is cut by the box); border='sin' the rejected "
                 "rounding (oc-5.2.3.1). Call with a CloudArraySettings and/or keyword overrides; the noise before "
                 "filtering: pywarp.kernels.voxel.noise_volume. Warp: voxel_upsample + valuenoise_smooth per voxel.",
         references=(_REF_ELIAS,))
@wp.func
def voxel_level_value(prev: wp.array(dtype=float), nc: int, n: int, x: int, y: int, z: int, amp: float,
                      seed_l: wp.uint32, smoothing: int, interpolation: int) -> float:
    """One interior voxel of a level l > 0: U(prev)(x, y, z) + amp * N_l(x, y, z) (the level kernel's work)."""
    return voxel_upsample(prev, nc, n, x, y, z, interpolation) + amp * valuenoise_smooth(x, y, z, seed_l, 3,
                                                                                          smoothing, 0)


@wp.kernel
def _level_kernel(row0: int, n: int, nc: int, first: int, amp: float, seed_l: wp.uint32, smoothing: int,
                  interpolation: int, border: int, prev: wp.array(dtype=float), cur: wp.array(dtype=float)):
    # one level: cur = U(prev) + amp * N (first level: amp * N); row = z * n + y
    i, x = wp.tid()
    row = row0 + i
    z = row // n
    y = row - z * n
    k = row * n + x
    if border == _BORDER_ZERO and (x == 0 or y == 0 or z == 0 or x == n - 1 or y == n - 1 or z == n - 1):
        cur[k] = 0.0
        return
    if first != 0:
        cur[k] = 0.0 + amp * valuenoise_smooth(x, y, z, seed_l, 3, smoothing, 0)
    else:
        cur[k] = voxel_level_value(prev, nc, n, x, y, z, amp, seed_l, smoothing, interpolation)


@wp.func
def _face_distance(i: int, n: int) -> int:
    if i < n - 1 - i:
        return i
    return n - 1 - i


@wp.func
def _clamp01(v: float) -> float:
    if v < 0.0:
        return 0.0
    if v > 1.0:
        return 1.0
    return v


@wp.func
def _to_u8(d: float) -> wp.uint8:
    r = wp.floor(d + 0.5)
    if r < 0.0:
        r = 0.0
    if r > 255.0:
        r = 255.0
    return wp.uint8(int(r))


@wp.kernel
def _finish_kernel(row0: int, n: int, norm: float, border: int, radius: float, cover: float, sharpness: float,
                   filtered: int, raw: wp.array(dtype=float), noise: wp.array(dtype=float),
                   cloud: wp.array(dtype=wp.uint8)):
    # n = clamp(A / norm * SIN windows, 0, 1); cloud = round(filter(n)) when filtered
    i, x = wp.tid()
    row = row0 + i
    z = row // n
    y = row - z * n
    k = row * n + x
    v = raw[k] / norm
    if border == _BORDER_SIN:
        v = v * voxel_sin_window(_face_distance(x, n), radius) * voxel_sin_window(_face_distance(y, n), radius) \
            * voxel_sin_window(_face_distance(z, n), radius)
    v = _clamp01(v)
    noise[k] = v
    if filtered != 0:
        cloud[k] = _to_u8(voxel_filter(v, cover, sharpness))


def _build_warp(s: CloudArraySettings, filtered: bool, device, launcher):
    from ..core.runtime import launcher as shared_launcher

    lau = launcher if launcher is not None else shared_launcher(device)
    dev = lau.device
    sizes = s.level_sizes()
    prev, nc, norm = wp.zeros(1, dtype=float, device=dev), 1, np.float32(0.0)
    amp = np.float32(1.0) if s.variant == "corrected" else np.float32(s.persistence)
    for lvl, nl in enumerate(sizes):
        cur = wp.empty(nl ** 3, dtype=float, device=dev)
        lau.launch(_level_kernel, nl * nl, nl,
                   [nl, nc, int(lvl == 0), float(amp), wp.uint32(octave_seed(s.seed, lvl)), SMOOTHINGS[s.smoothing],
                    INTERPOLATIONS[s.interpolation], BORDERS[s.border], prev], [cur])
        norm = np.float32(norm + amp)
        amp = np.float32(amp * amp) if s.variant == "thesis" else np.float32(amp * np.float32(s.persistence))
        prev, nc = cur, nl
    n = s.size
    noise = wp.empty(n ** 3, dtype=float, device=dev)
    cloud = wp.empty(n ** 3 if filtered else 1, dtype=wp.uint8, device=dev)
    lau.launch(_finish_kernel, n * n, n,
               [n, float(norm), BORDERS[s.border], float(np.float32(s.sin_radius) * np.float32(n)), s.cover,
                s.sharpness, int(filtered), prev], [noise, cloud])
    if filtered:
        return np.array(cloud.numpy(), copy=True).reshape(s.shape)
    return np.array(noise.numpy(), dtype=np.float32, copy=True).reshape(s.shape)


def _build_c(s: CloudArraySettings, filtered: bool):
    from ..core.binding import ffi, lib, status_error

    st = settings_struct(s)
    if filtered:
        out = np.empty(s.shape, dtype=np.uint8)
        status_error(lib().ccl_voxel_cloud(st, ffi().from_buffer("uint8_t[]", out), out.size), "ccl_voxel_cloud")
    else:
        out = np.empty(s.shape, dtype=np.float32)
        status_error(lib().ccl_voxel_noise(st, ffi().from_buffer("float[]", out), out.size), "ccl_voxel_noise")
    return out


def noise_volume(settings: CloudArraySettings | None = None, impl: str = "warp", device: str | None = None,
                 launcher=None, **overrides) -> np.ndarray:
    """The noise array before filtering (fig. 5.11's "nebula"): float32 (size, size, size) in [0, 1] indexed
    [z, y, x]. ``settings`` (default :class:`CloudArraySettings`) with keyword ``overrides`` of its fields;
    ``impl="warp"``: row bands through ``launcher`` (default the process-wide TileLauncher of ``device``);
    ``impl="c"``: ``ccl_voxel_noise``, one thread. Ref: oc-5.2.1, oc-5.2.3, oc-5.2.3.1, oc-5.2.3.2."""
    s = _settings(settings, overrides)
    if impl == "c":
        return _build_c(s, False)
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return _build_warp(s, False, device, launcher)


def cloud_volume(settings: CloudArraySettings | None = None, impl: str = "warp", device: str | None = None,
                 launcher=None, **overrides) -> np.ndarray:
    """The cloud array: :func:`noise_volume` cut out by :func:`voxel_filter` (cover, sharpness), uint8
    (size, size, size) indexed [z, y, x], 0 = invisible .. 255 = fully opaque. With ``border="zero"`` (default) every
    voxel of the six outer faces is 0. Same arguments as :func:`noise_volume`; the same settings give the same
    volume (any thread count). Ref: oc-5.2.1, oc-5.2.2, oc-5.2.3.2."""
    s = _settings(settings, overrides)
    if impl == "c":
        return _build_c(s, True)
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return _build_warp(s, True, device, launcher)


# --- per-axis scaling ----------------------------------------------------------------------------------------------------

# A resampled volume, not element-wise: custom evaluators (scale_volume).
@declare("oc-5.2.3-scale", c="ccl_voxel_scale", name="voxel_scale", make_warp=_scale_make("warp"),
         make_c=_scale_make("c"), outputs=("volume",),
         summary="Per-axis scaling of the cloud array: voxel_scale(volume, (sx, sy, sz)) resamples the uint8 array "
                 "to round(n * s) voxels per axis, trilinear with corners aligned (faces map onto faces: a zero "
                 "border stays zero), e.g. (1.5, 1.5, 0.6) for a wide, flat cloud. A renderer may scale its box "
                 "instead. The text gives no factors.",
         references=(_REF_ELIAS,))
@wp.func
def voxel_scale_sample(src: wp.array(dtype=wp.uint8), nx: int, ny: int, x0: int, y0: int, z0: int, tx: float,
                       ty: float, tz: float) -> float:
    """Trilinear sample of the uint8 array ``src`` (index (z ny + y) nx + x) in cell (x0, y0, z0) at weights
    (tx, ty, tz), each axis blended as valuenoise_linear (the scale kernel inlines the same operations)."""
    r00 = valuenoise_linear(float(src[(z0 * ny + y0) * nx + x0]), float(src[(z0 * ny + y0) * nx + x0 + 1]), tx)
    r01 = valuenoise_linear(float(src[(z0 * ny + y0 + 1) * nx + x0]), float(src[(z0 * ny + y0 + 1) * nx + x0 + 1]),
                            tx)
    r10 = valuenoise_linear(float(src[((z0 + 1) * ny + y0) * nx + x0]),
                            float(src[((z0 + 1) * ny + y0) * nx + x0 + 1]), tx)
    r11 = valuenoise_linear(float(src[((z0 + 1) * ny + y0 + 1) * nx + x0]),
                            float(src[((z0 + 1) * ny + y0 + 1) * nx + x0 + 1]), tx)
    return valuenoise_linear(valuenoise_linear(r00, r01, ty), valuenoise_linear(r10, r11, ty), tz)


@wp.kernel
def _scale_kernel(row0: int, nx: int, ny: int, nz: int, mx: int, my: int, mz: int, src: wp.array(dtype=wp.uint8),
                  dst: wp.array(dtype=wp.uint8)):
    i, x = wp.tid()
    row = row0 + i
    z = row // my
    y = row - z * my
    z0 = _axis_i0(z, mz, nz)
    y0 = _axis_i0(y, my, ny)
    x0 = _axis_i0(x, mx, nx)
    v = voxel_scale_sample(src, nx, ny, x0, y0, z0, _axis_t(x, mx, nx, x0), _axis_t(y, my, ny, y0),
                           _axis_t(z, mz, nz, z0))
    dst[(z * my + y) * mx + x] = _to_u8(v)


def scaled_shape(shape, scale) -> tuple[int, int, int]:
    """Edges of a volume of ``shape`` (z, y, x) scaled by ``scale`` = (sx, sy, sz) per axis: round(n * s) >= 2."""
    sx, sy, sz = scale
    nz, ny, nx = shape
    return (max(2, int(round(nz * sz))), max(2, int(round(ny * sy))), max(2, int(round(nx * sx))))


def scale_volume(volume, scale, impl: str = "warp", device: str | None = None, launcher=None) -> np.ndarray:
    """Per-axis scaling of a uint8 cloud array (oc-5.2.3-scale): ``volume`` (nz, ny, nx) indexed [z, y, x],
    ``scale`` = (sx, sy, sz) factors > 0 (e.g. (1.5, 1.5, 0.6) for a wide, flat cloud). Trilinear resampling with
    corners aligned (a face maps onto a face, so a zero border stays zero), rounded to uint8. Returns uint8 of
    :func:`scaled_shape`. ``impl="c"``: ``ccl_voxel_scale``."""
    vol = np.asarray(volume)
    if vol.dtype != np.uint8 or vol.ndim != 3:
        raise ValueError(f"volume must be a 3-D uint8 array, got {vol.dtype} of shape {vol.shape}")
    if any(n < 2 or n > MAX_SCALE_EDGE for n in vol.shape):
        raise ValueError(f"volume edges must be in [2, {MAX_SCALE_EDGE}], got {vol.shape}")
    try:
        sc = tuple(float(v) for v in scale)
    except TypeError:
        raise TypeError(f"scale must be a sequence of 3 numbers, got {scale!r}") from None
    if len(sc) != 3 or not all(math.isfinite(v) and v > 0.0 for v in sc):
        raise ValueError(f"scale must hold 3 finite factors > 0 (x, y, z), got {scale!r}")
    mz, my, mx = scaled_shape(vol.shape, sc)
    if max(mz, my, mx) > MAX_SCALE_EDGE:
        raise ValueError(f"scale gives edges {(mz, my, mx)}, above {MAX_SCALE_EDGE}")
    nz, ny, nx = vol.shape
    src = np.ascontiguousarray(vol)
    if impl == "c":
        from ..core.binding import ffi, lib, status_error

        out = np.empty((mz, my, mx), dtype=np.uint8)
        status_error(lib().ccl_voxel_scale(ffi().from_buffer("uint8_t[]", src), nx, ny, nz,
                                           ffi().from_buffer("uint8_t[]", out), mx, my, mz), "ccl_voxel_scale")
        return out
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    from ..core.runtime import launcher as shared_launcher

    lau = launcher if launcher is not None else shared_launcher(device)
    dst = wp.empty(mz * my * mx, dtype=wp.uint8, device=lau.device)
    lau.launch(_scale_kernel, mz * my, mx,
               [nx, ny, nz, mx, my, mz, wp.array(src.ravel(), dtype=wp.uint8, device=lau.device)], [dst])
    return np.array(dst.numpy(), copy=True).reshape(mz, my, mx)


# --- registry entries of the whole-array functions (not element-wise: a volume from settings) --------------------------

# --- benchmark -----------------------------------------------------------------------------------------------------------

def bench_cloud_array(sizes=(32, 64, 128), interpolations=("linear", "cosine", "cubic"), repeats: int = 3,
                      impl: str = "warp", device: str | None = None, settings: CloudArraySettings | None = None,
                      c_reference: bool = False) -> dict:
    """Cloud-array generation time (:func:`cloud_volume`, noise + filter) by size and by interpolation, the best of
    ``repeats`` runs after one warm-up (Warp compiles on first use). Returns a JSON-ready dict::

        {"unit": "ms", "impl": ..., "device": ..., "workers": ..., "repeats": ...,
         "cloud_array_ms": {"linear": {"32": ms, "64": ms, "128": ms}, "cosine": {...}, "cubic": {...}},
         "cubic_over_linear": {"32": ratio, ...},
         "c_ms": {...}  # only with c_reference=True: the single-threaded C reference, same layout
        }

    The text claims cubic interpolation is "unusable in real time" (§5.1.4.3) without measuring it; this measures
    it. ``settings``: the other parameters (default :class:`CloudArraySettings`)."""
    from ..core.runtime import launcher as shared_launcher

    if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
        raise ValueError(f"repeats must be an integer >= 1, got {repeats!r}")
    for it in interpolations:
        if it not in INTERPOLATIONS:
            raise ValueError(f"interpolations must be among {', '.join(map(repr, INTERPOLATIONS))}, got {it!r}")
    base = settings if settings is not None else CloudArraySettings()
    cases = [(it, int(n), replace(base, size=int(n), interpolation=it)) for it in interpolations for n in sizes]

    def timed(fn):
        fn()  # warm-up (compilation, allocation)
        best = math.inf
        for _ in range(repeats):
            t0 = time.perf_counter()
            fn()
            best = min(best, time.perf_counter() - t0)
        return best * 1e3

    lau = shared_launcher(device) if impl == "warp" else None
    res: dict = {"unit": "ms", "impl": impl, "repeats": repeats, "settings": asdict(base),
                 "cloud_array_ms": {it: {} for it in interpolations}}
    if lau is not None:
        res["device"], res["workers"] = lau.device, lau.workers
    for it, n, s in cases:
        res["cloud_array_ms"][it][str(n)] = timed(lambda s=s: cloud_volume(s, impl=impl, launcher=lau))
    if "linear" in interpolations and "cubic" in interpolations:
        res["cubic_over_linear"] = {k: res["cloud_array_ms"]["cubic"][k] / res["cloud_array_ms"]["linear"][k]
                                    for k in res["cloud_array_ms"]["linear"]}
    if c_reference:
        res["c_ms"] = {it: {} for it in interpolations}
        for it, n, s in cases:
            res["c_ms"][it][str(n)] = timed(lambda s=s: cloud_volume(s, impl="c"))
    return res
