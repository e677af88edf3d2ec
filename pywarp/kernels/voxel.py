"""The 3-D cloud array of the oc text (Kucera 2006, §5.2) -- Warp twins of ``cclouds/voxel.h``.

* :func:`voxel_level_value` (oc-5.2.1) -- one voxel of a level of the noise array: the previous level up-sampled
  (x2, :func:`voxel_upsample`) plus new noise of lower amplitude; the level and finish kernels build the array,
  ``border`` picks the border handling: ``"zero"`` (default, the adopted larger array with zero borders, oc-5.2.3.2),
  ``"sin"`` (the rejected SIN rounding, oc-5.2.3.1, in our reading), ``"none"`` (the border problem, oc-5.2.3).
* :func:`voxel_filter` (oc-5.2.2) -- Elias's exponential cut-out, density = 255 (1 - sharpness^max(255 n - cover,
  0)).
* :func:`voxel_sin_window` (oc-5.2.3.1) -- the SIN weight at a distance from the nearest face.
* :func:`voxel_envelope` -- beyond the text: the squared radius of the ellipsoids of the falloff envelope
  (n - envelope q) that makes a compact cloud with no box face (``ccl_voxel_envelope``; the reasons in
  ``cclouds/voxel.h``).
* :func:`voxel_scale_sample` (oc-5.2.3-scale) -- per-axis scaling by trilinear resampling (corners aligned: a zero
  border stays zero).

The host side -- the settings (:class:`pywarp.flight.clouds.CloudArraySettings`), the builds
(:func:`pywarp.flight.clouds.cloud_volume`, ``noise_volume``, ``scale_volume``) and the generation benchmark -- is
:mod:`pywarp.flight.clouds`. The build and every reading where the text is silent are stated in ``cclouds/voxel.h``
and repeated in the settings.
"""
from __future__ import annotations

import warp as wp

from ..core.registry import Arg, declare
from .common import clamp01
from .valuenoise import interp_kind, valuenoise_linear, valuenoise_smooth

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


@wp.func
def voxel_envelope(x: int, y: int, z: int, n: int, base: float) -> float:
    """Twin of ``ccl_voxel_envelope``: q = dx^2 + dy^2 + dz^2 on the ellipsoids inscribed in the cube of edge n (y up,
    q = 1 on the inscribed one), their centre at height base / (1 + base) of the edge: the lower semi-axis is
    ``base`` times the upper, so the base falls off faster than the top."""
    m = float(n - 1)
    dx = (2.0 * float(x) - m) / m
    dz = (2.0 * float(z) - m) / m
    c = base / (1.0 + base)
    u = float(y) / m
    dy = float(0.0)
    if u >= c:
        dy = (u - c) / (1.0 - c)
    else:
        dy = (c - u) / c
    return dx * dx + dy * dy + dz * dz


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


# A whole volume from settings, not element-wise: custom evaluators (pywarp.flight.clouds.cloud_volume).
@declare("oc-5.2.1", "oc-5.2.3", "oc-5.2.3.2", c="ccl_voxel_cloud", name="voxel_cloud",
         make_warp="pywarp.flight.clouds:voxel_cloud_warp", make_c="pywarp.flight.clouds:voxel_cloud_c",
         outputs=("volume",),
         summary="The 3-D cloud array: a size/8 array of value noise up-sampled x2 level by level (trilinear by "
                 "default, cosine, or the printed cubic; corners aligned) with new noise of amplitude "
                 "persistence^l added at each level, normalised to [0, 1], cut out by the filter oc-5.2.2 and stored "
                 "as uint8 0..255 [z, y, x]. border='zero' (default): the larger array with zero borders -- the "
                 "outermost layer of every level stays 0, every outer-face voxel is 0 (oc-5.2.3.2); border='none' "
                 "reproduces the border problem (oc-5.2.3: the cloud is cut by the box); border='sin' the rejected "
                 "rounding (oc-5.2.3.1). Call with a CloudArraySettings and/or keyword overrides; the noise before "
                 "filtering: pywarp.flight.clouds.noise_volume. Warp: voxel_upsample + valuenoise_smooth per voxel.",
         references=(_REF_ELIAS,))
@wp.func
def voxel_level_value(prev: wp.array(dtype=float), nc: int, n: int, x: int, y: int, z: int, amp: float,
                      seed_l: wp.uint32, smoothing: int, interpolation: int) -> float:
    """One interior voxel of a level l > 0: U(prev)(x, y, z) + amp * N_l(x, y, z) (the level kernel's work)."""
    return voxel_upsample(prev, nc, n, x, y, z, interpolation) + amp * valuenoise_smooth(x, y, z, seed_l, 3,
                                                                                          smoothing, 0)


@wp.kernel
def level_kernel(row0: int, n: int, nc: int, first: int, amp: float, seed_l: wp.uint32, smoothing: int,
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
def _to_u8(d: float) -> wp.uint8:
    r = wp.floor(d + 0.5)
    if r < 0.0 or wp.isnan(r):  # NaN: 0 (as to_u8 in C), never an int() of NaN
        r = 0.0
    if r > 255.0:
        r = 255.0
    return wp.uint8(int(r))


@wp.kernel
def finish_kernel(row0: int, n: int, norm: float, border: int, radius: float, envelope: float, envelope_base: float,
                  cover: float, sharpness: float, filtered: int, raw: wp.array(dtype=float),
                  noise: wp.array(dtype=float), cloud: wp.array(dtype=wp.uint8)):
    # n = clamp(A / norm * SIN windows - envelope q, 0, 1); cloud = round(filter(n)) when filtered
    i, x = wp.tid()
    row = row0 + i
    z = row // n
    y = row - z * n
    k = row * n + x
    v = raw[k] / norm
    if border == _BORDER_SIN:
        v = v * voxel_sin_window(_face_distance(x, n), radius) * voxel_sin_window(_face_distance(y, n), radius) \
            * voxel_sin_window(_face_distance(z, n), radius)
    if envelope > 0.0:
        v = v - envelope * voxel_envelope(x, y, z, n, envelope_base)
    v = clamp01(v)
    noise[k] = v
    if filtered != 0:
        cloud[k] = _to_u8(voxel_filter(v, cover, sharpness))


# --- per-axis scaling ----------------------------------------------------------------------------------------------------

# A resampled volume, not element-wise: custom evaluators (pywarp.flight.clouds.scale_volume).
@declare("oc-5.2.3-scale", c="ccl_voxel_scale", name="voxel_scale",
         make_warp="pywarp.flight.clouds:voxel_scale_warp", make_c="pywarp.flight.clouds:voxel_scale_c",
         outputs=("volume",),
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
def scale_kernel(row0: int, nx: int, ny: int, nz: int, mx: int, my: int, mz: int, src: wp.array(dtype=wp.uint8),
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
