"""The cloudscape pixel (vc chapter 4) as Warp code -- the twin of ``cclouds/cloudscape.h``, operation by operation.

:class:`CloudscapeParams` mirrors ``ccl_cloudscape_params``; :func:`cloudscape_density`, :func:`cloudscape_march` and
:func:`cloudscape_pixel` mirror the C functions of the same names. The image kernels follow the
:class:`pywarp.core.runtime.TileLauncher` convention (first parameter ``row0``) so a frame runs on every core:

* :func:`sky_kernel` writes the sky model's colour into the frame buffer (the first stage of the render chain; with
  sky lighting the sky lifted to the horizon everywhere: the haze colour, which the cloud pass turns into the lit
  ground where the ray meets the Earth);
* :func:`clouds_kernel` marches the clouds of every pixel, or, with reprojection, of one pixel per 4 x 4 block
  (vc-4.1), composites them over the frame buffer (vc-4.8) and fills the reduced buffer (vc-A22);
* :func:`encode_kernel` clamps to [0, 1] and applies the sRGB encoding.

Frame buffers are ``wp.array3d(dtype=float)`` of shape (height, width, 3), row 0 at the top, display-linear RGB.
"""
from __future__ import annotations

from typing import Any

import warp as wp

from .clouds import (
    clouds_base_shape,
    clouds_composite,
    clouds_coverage,
    clouds_detail_erosion,
    clouds_relative_height,
    clouds_height_gradient,
)
from ..core.cbridge import c_constant
from ..core.registry import Arg, declare
from .colour import colour_srgb_encode
from .hash import hash_pcg, hash_unit
from .interp import interp_fade_cubic
from .phase import INV_4PI, MIE_D_RANGE, phase_hg, phase_mie, phase_mie_params
from .camera import camera_ray
from .raymarch import (
    raymarch_accumulate,
    raymarch_interval,
    raymarch_jitter,
    raymarch_layer_segment,
    raymarch_light_cone_kernel,
    raymarch_light_sample_position,
    raymarch_point,
    raymarch_ray_sphere,
    raymarch_view_sample_count,
)
from .reproj import reproj_pixel, reproj_surface_depth
from .sky import Preetham, SkyGradient, sky_gradient_rgb, sky_preetham_hdr, sky_preetham_rgb, sky_sun_attenuation
from .texgen import trilinear_axis, trilinear_lerp, trilinear_scale

SKY_GRADIENT = c_constant("CCL_SKY_GRADIENT", 0)
SKY_PREETHAM = c_constant("CCL_SKY_PREETHAM", 1)
SKY_PREETHAM_RADIANCE = c_constant("CCL_SKY_PREETHAM_RADIANCE", 2)  # physical units: k C_HDR (cloudscape.h)
PHASE_THESIS = c_constant("CCL_CLOUDSCAPE_PHASE_THESIS", 0)
PHASE_MIE = c_constant("CCL_CLOUDSCAPE_PHASE_MIE", 1)
#: The sun's illuminance above the atmosphere in klx (CCL_CLOUDSCAPE_SUN_KLX_X10 / 10; the reason is in cloudscape.h).
SUN_KLX_X10 = c_constant("CCL_CLOUDSCAPE_SUN_KLX_X10", 1275)
LIGHTING_THESIS = c_constant("CCL_LIGHTING_THESIS", 0)
LIGHTING_SKY = c_constant("CCL_LIGHTING_SKY", 1)
COVERAGE_SAME = c_constant("CCL_COVERAGE_SAME", 0)
COVERAGE_ONE_MINUS = c_constant("CCL_COVERAGE_ONE_MINUS", 1)
MAX_MS_OCTAVES = 8  # CCL_CLOUDSCAPE_MAX_MS_OCTAVES
COARSE_MAX_FACTOR = wp.constant(4)  # CCL_CLOUDSCAPE_COARSE_MAX_FACTOR (the reason is in cloudscape.h)
GROUP_SPAN = wp.constant(2.0)  # CCL_CLOUDSCAPE_GROUP_SPAN (the reason is in cloudscape.h)
GROUND_SHADOW_SAMPLES = wp.constant(12)  # CCL_CLOUDSCAPE_GROUND_SHADOW_SAMPLES
SKY_THETA_CELLS = wp.constant(8)  # CCL_CLOUDSCAPE_SKY_THETA_CELLS
SKY_PHI_CELLS = wp.constant(16)  # CCL_CLOUDSCAPE_SKY_PHI_CELLS
MARCH_FAST = c_constant("CCL_CLOUDSCAPE_MARCH_FAST", 0)  # cloudscape_march's own loop (the default)
MARCH_TEXTBOOK = c_constant("CCL_CLOUDSCAPE_MARCH_TEXTBOOK", 1)  # the thesis's loop: cloudscape_march_textbook


@wp.struct
class CloudscapeParams:
    """Twin of ``ccl_cloudscape_params`` (field meanings and defaults: ``cclouds/cloudscape.h`` / ``cloudscape.c``)."""

    centre: wp.vec3
    r_earth: float
    r_inner: float
    r_outer: float
    base_scale_km: float
    detail_scale_km: float
    weather_scale_km: float
    curl_scale_km: float
    curl_strength_km: float
    weather_offset: wp.vec2
    detail_offset: wp.vec3
    sigma: float
    sigma_light: float
    absorption_base: float
    absorption_precip: float
    g: float
    sun_colour: wp.vec3
    ambient_bottom: wp.vec3
    ambient_top: wp.vec3
    samples_min: int
    samples_max: int
    adaptive_samples: int
    early_exit: int
    exit_eps: float
    exit_fill: int
    light_interp: float
    light_step_km: float
    light_cone_angle: float
    light_far_factor: float
    light_detail: int
    jitter_mode: int
    jitter_amount: float
    gradient_clamp: int
    detail_direction: int
    ground_colour: wp.vec3
    coverage_threshold: int
    beer: int
    powder: int
    lighting: int
    sun_intensity: float
    turbidity: float
    ambient_bottom_ratio: float
    ambient_ground: wp.vec3
    ground_albedo: wp.vec3
    ground_variation: float
    aerial_km: float
    aerial_height_km: float
    ms_octaves: int
    ms_a: float
    ms_b: float
    ms_c: float
    silver_g: float
    silver_weight: float
    phase: int
    droplet_um: float
    ambient_ground_weight: float
    ms_depth: float
    ms_thin: float
    ms_view: float
    ms_view_trans: float
    ambient_aniso: float
    ms_slab: float
    ms_slab_mu: float
    ms_slab_far: float
    mie_delta: float
    lod: int
    lod_bias: float
    refine_step_km: float
    refine_max: int
    weather_detile: int
    march: int


@wp.func
def _axis2(x: float, mask: int):
    """Wrapped linear-interpolation axis, texel centres at i + 0.5 (twin of ``axis2`` in cloudscape.c)."""
    fx = wp.floor(x)
    f = x - fx
    i = int(fx)
    t = f - 0.5
    if f < 0.5:
        i = i - 1
        t = f + 0.5
    return i & mask, (i + 1) & mask, t


@wp.func
def sample_bilinear_wrap(tex: wp.array2d(dtype=wp.vec4), size_mask: int, u: float, v: float) -> wp.vec4:
    """Twin of ``ccl_cloudscape_sample_bilinear_wrap``: periodic 2-D RGBA ``tex[y, x]`` at texture coords (u, v)."""
    fsize = float(size_mask + 1)
    if not (wp.abs(u * fsize) < 8388608.0 and wp.abs(v * fsize) < 8388608.0):
        # outside the domain |uv * size| < 2^23 (or NaN): NaN, never an int() of such a value (as the C sampler)
        return wp.vec4(wp.nan, wp.nan, wp.nan, wp.nan)
    x0, x1, tx = _axis2(u * fsize, size_mask)
    y0, y1, ty = _axis2(v * fsize, size_mask)
    c00 = tex[y0, x0]
    c10 = tex[y0, x1]
    c01 = tex[y1, x0]
    c11 = tex[y1, x1]
    c0 = c00 + (c10 - c00) * tx
    c1 = c01 + (c11 - c01) * tx
    return c0 + (c1 - c0) * ty


#: Texels of margin: the bilinear footprint reaches 1 texel beyond the sample's texel, a step of at most delta texels
#: moves the texel by at most delta, and one texel more absorbs the rounding of the positions.
EMPTY_MARGIN = wp.constant(3)


@wp.struct
class CloudTextures:
    """Twin of ``ccl_cloud_textures``: base and detail as flat mip chains (level 0 first, then each half-size level
    down to 1^3, texel [z, y, x] of level k at ``mip_offset(size, k) + (z n_k + y) n_k + x``), curl and weather 2-D."""

    base: wp.array(dtype=wp.vec4)
    base_size: int
    base_levels: int  # mip levels present (1: level 0 only, no level of detail)
    # half_base = 1: the base chain is read from base_half (its texels' float16 values, the numbers the C renderer is
    # given with base_precision 'half'; half the memory, so that it stays in the cache) and base is not read
    base_half: wp.array(dtype=wp.vec4h)
    half_base: int
    detail: wp.array(dtype=wp.vec4)
    detail_size: int
    detail_levels: int
    curl: wp.array2d(dtype=wp.vec4)
    weather: wp.array2d(dtype=wp.vec4)
    # Warp only (an acceleration structure, no C twin: it changes no result): per weather texel, the Chebyshev
    # distance in texels to the nearest texel of coverage > 0 (:func:`pywarp.clouds.cloudscape.weather_empty_distance`);
    # 0 everywhere: no empty-space skipping. empty_skip = 0 switches off this and the two short cuts below (the frames
    # are the same)
    weather_empty: wp.array2d(dtype=wp.int32)
    empty_skip: int
    # Warp only, used with empty_skip: per cell of the weather map between texel centres (i, j)..(i + 1, j + 1),
    # 0 / 1 where the de-tiling's selector is certainly 0 / 1 there (:func:`pywarp.clouds.cloudscape.selector_class`),
    # else 2; a map of another size than the weather's: none
    selector_class: wp.array2d(dtype=wp.uint8)
    # Warp only, used with empty_skip: an upper bound of the base shape B of vc-2.28 over every sample of the base
    # chain (:func:`pywarp.clouds.cloudscape.base_shape_bound`); a sample with D_v * bound <= C (the coverage
    # threshold) has B_D = 0, whatever the base texture holds there, so its lookup is skipped. <= 0 (the default) or
    # NaN: no bound
    base_bound: float


@wp.func
def mip_offset(size: int, level: int) -> int:
    """Texels before mip level ``level`` of a flat chain whose level 0 is size^3 (a power of two <= 512): the sum
    of (size / 2^k)^3 over k < level, in closed form 8 (size^3 - m^3) / 7 with m = size / 2^level (exact in int32:
    8 x 512^3 < 2^31; no loop per lookup)."""
    m = size >> level
    return (8 * (size * size * size - m * m * m)) / 7


@wp.func
def sample_mip_level(tex: wp.array(dtype=Any), size: int, level: int, p: wp.vec3) -> wp.vec4:
    """Trilinear wrap sample of mip level ``level`` (twin of ``ccl_texgen_sample_trilinear_wrap`` on that level's
    texels; the same operations in the same order). ``tex``: a chain of ``wp.vec4`` or of ``wp.vec4h`` (each texel
    converted to float32 first, exactly)."""
    n = size >> level
    mask = n - 1
    base = mip_offset(size, level)
    x, y, z, ok = trilinear_scale(p, n)
    if not ok:
        return wp.vec4(wp.nan, wp.nan, wp.nan, wp.nan)
    x0, x1, tx = trilinear_axis(x, mask)
    y0, y1, ty = trilinear_axis(y, mask)
    z0, z1, tz = trilinear_axis(z, mask)
    y0 = y0 * n
    y1 = y1 * n
    z0 = z0 * n * n
    z1 = z1 * n * n
    return trilinear_lerp(wp.vec4(tex[base + z0 + y0 + x0]), wp.vec4(tex[base + z0 + y0 + x1]),
                          wp.vec4(tex[base + z0 + y1 + x0]), wp.vec4(tex[base + z0 + y1 + x1]),
                          wp.vec4(tex[base + z1 + y0 + x0]), wp.vec4(tex[base + z1 + y0 + x1]),
                          wp.vec4(tex[base + z1 + y1 + x0]), wp.vec4(tex[base + z1 + y1 + x1]), tx, ty, tz)


@wp.func
def sample_mip(tex: wp.array(dtype=Any), size: int, levels: int, lod: float, p: wp.vec3) -> wp.vec4:
    """Twin of ``sample_mip`` in cloudscape.c: level 0 for lod <= 0, else the blend of levels floor(lod) and
    floor(lod) + 1 by frac(lod) (the last level for lod >= levels - 1; level lod alone for a whole lod)."""
    if lod <= 0.0 or levels <= 1 or wp.isnan(lod):  # a NaN lod: level 0 (as in C), never an int() of NaN
        return sample_mip_level(tex, size, 0, p)
    top = float(levels - 1)
    if lod >= top:
        return sample_mip_level(tex, size, levels - 1, p)
    l0 = wp.floor(lod)
    f = lod - l0
    k = int(l0)
    a = sample_mip_level(tex, size, k, p)
    if f == 0.0:  # a whole level (the light samples'): one lookup
        return a
    b = sample_mip_level(tex, size, k + 1, p)
    return a + (b - a) * f


@wp.func
def cloudscape_lod(footprint_km: float, texel_km: float, bias: float) -> float:
    """Mip level of a sample whose footprint is ``footprint_km``: log2(footprint / texel) + bias (may be <= 0: level
    0). Twin of ``ccl_cloudscape_lod``."""
    if not (footprint_km > 0.0):
        return 0.0
    return wp.log2(footprint_km / texel_km) + bias


# the de-tiling of the weather map (CCL_WEATHER_DETILE_* in cclouds/cloudscape.h, where the reasons are)
WEATHER_DETILE = dict(cos=0.79863551, sin=0.60181502, scale_b=1.37, scale_m=5.3, shift_u=0.31, shift_v=0.57,
                      edge0=0.35, edge1=0.65)
_WD_COS = wp.constant(WEATHER_DETILE["cos"])
_WD_SIN = wp.constant(WEATHER_DETILE["sin"])
_WD_SCALE_B = wp.constant(WEATHER_DETILE["scale_b"])
_WD_SCALE_M = wp.constant(WEATHER_DETILE["scale_m"])
_WD_SHIFT_U = wp.constant(WEATHER_DETILE["shift_u"])
_WD_SHIFT_V = wp.constant(WEATHER_DETILE["shift_v"])
_WD_EDGE0 = wp.constant(WEATHER_DETILE["edge0"])
_WD_EDGE1 = wp.constant(WEATHER_DETILE["edge1"])


@wp.func
def _selector_certain(tex: CloudTextures, mask: int, u: float, v: float) -> float:
    """The de-tiling's blend weight at selector coordinates (u, v) where
    :func:`pywarp.clouds.cloudscape.selector_class` proves it (0 or 1, exactly what the lookup and smoothstep give
    there), else -1 (also outside the sampler's domain: the lookup decides, NaN included)."""
    fsize = float(mask + 1)
    if not (wp.abs(u * fsize) < 8388608.0 and wp.abs(v * fsize) < 8388608.0):
        return -1.0
    x0, x1, tx = _axis2(u * fsize, mask)
    y0, y1, ty = _axis2(v * fsize, mask)
    cls = int(tex.selector_class[y0, x0])
    if cls == 0:
        return 0.0
    if cls == 1:
        return 1.0
    return -1.0


@wp.func
def cloudscape_weather(p: CloudscapeParams, tex: CloudTextures, x: float, z: float) -> wp.vec4:
    """Twin of ``ccl_cloudscape_weather``: the weather map ``tex.weather`` at world (x, z) km with the wind, de-tiled
    when ``p.weather_detile``: blended with a rotated, scaled, shifted copy by the smoothstep of a much larger copy's
    coverage (Warp only: that selector is not looked up where ``tex.selector_class`` proves it 0 or 1)."""
    weather = tex.weather
    mask = weather.shape[0] - 1
    u = (x + p.weather_offset[0]) / p.weather_scale_km
    v = (z + p.weather_offset[1]) / p.weather_scale_km
    if p.weather_detile == 0:
        return sample_bilinear_wrap(weather, mask, u, v)
    c = _WD_COS
    s = _WD_SIN
    # the selector first: where it is 0 or 1 only one of the two maps is read
    su = (c * u + s * v) / _WD_SCALE_M + _WD_SHIFT_V
    sv = (c * v - s * u) / _WD_SCALE_M + _WD_SHIFT_U
    k = float(-1.0)
    if tex.empty_skip != 0 and tex.selector_class.shape[0] == mask + 1:
        k = _selector_certain(tex, mask, su, sv)
    if k < 0.0:
        m = sample_bilinear_wrap(weather, mask, su, sv)
        k = (m[0] - _WD_EDGE0) / (_WD_EDGE1 - _WD_EDGE0)
        k = interp_fade_cubic(wp.clamp(k, 0.0, 1.0))
    a = wp.vec4(0.0, 0.0, 0.0, 0.0)
    if not (k >= 1.0):
        a = sample_bilinear_wrap(weather, mask, u, v)
    if k == 0.0:  # (a NaN selector reads both and blends them: NaN, as the sampler outside its domain)
        return a
    b = sample_bilinear_wrap(weather, mask, (c * u - s * v) / _WD_SCALE_B + _WD_SHIFT_U,
                             (s * u + c * v) / _WD_SCALE_B + _WD_SHIFT_V)
    if k >= 1.0:
        return b
    return a + (b - a) * k


@wp.func
def _empty_texels(p: CloudscapeParams, tex: CloudTextures, u: float, v: float) -> int:
    """Distance of the weather texel of (u, v) in the empty-space map (0 outside the sampler's domain)."""
    size = tex.weather.shape[0]
    fsize = float(size)
    x = u * fsize
    y = v * fsize
    if not (wp.abs(x) < 8388608.0 and wp.abs(y) < 8388608.0):
        return 0
    return tex.weather_empty[int(wp.floor(y)) & (size - 1), int(wp.floor(x)) & (size - 1)]


@wp.func
def empty_until(p: CloudscapeParams, tex: CloudTextures, pos: wp.vec3, t: float, speed_h: float) -> float:
    """The ray distance up to which the density is certainly 0 (the weather map's coverage is 0 within the
    empty-space map's radius around ``pos``, horizontally: the ray moves ``speed_h`` km sideways per km), or -1 when
    ``pos`` itself is not certainly empty. Both maps of the de-tiling must be empty (the blend of two zeros is 0 for
    any selector). Warp only: it changes no result, only skips samples whose density is 0."""
    if tex.empty_skip == 0:
        return -1.0
    u = (pos[0] + p.weather_offset[0]) / p.weather_scale_km
    v = (pos[2] + p.weather_offset[1]) / p.weather_scale_km
    texel_km = p.weather_scale_km / float(tex.weather.shape[0])
    da = _empty_texels(p, tex, u, v) - EMPTY_MARGIN
    if da < 0:
        return -1.0
    r = float(da) * texel_km
    if p.weather_detile != 0:
        db = _empty_texels(p, tex, (_WD_COS * u - _WD_SIN * v) / _WD_SCALE_B + _WD_SHIFT_U,
                           (_WD_SIN * u + _WD_COS * v) / _WD_SCALE_B + _WD_SHIFT_V) - EMPTY_MARGIN
        if db < 0:
            return -1.0
        r = wp.min(r, float(db) * texel_km * _WD_SCALE_B)
    if speed_h * 1.0e6 <= r:
        return 1.0e30  # a (nearly) vertical ray stays in the empty column
    return t + r / speed_h


@wp.func
def cloudscape_density_lod(p: CloudscapeParams, tex: CloudTextures, pos: wp.vec3, with_detail: int, lod_base: float,
                           lod_detail: float, footprint_km: float):
    """vc-A17 with a level of detail: (density, precipitation) at a world position with the base and detail textures
    sampled at mip levels ``lod_base`` / ``lod_detail`` (0: full resolution, the thesis); twin of
    ``ccl_cloudscape_density_lod``. At the detail texture's last level (its mean) the curl lookup is skipped: the
    detail no longer depends on the position.
    ``footprint_km`` > 0 (Warp only): the two levels are ``cloudscape_lod`` of that footprint, computed only where a
    lookup needs them (most samples have density 0 before the base lookup), and ``lod_base`` / ``lod_detail`` are
    not read -- the same levels the caller would compute, so the same density."""
    c = p.centre
    r = wp.length(pos - c)
    h = clouds_relative_height(r, p.r_inner, p.r_outer, 0)
    density = float(0.0)
    precip = float(0.0)
    if h >= 0.0 and h <= 1.0:
        w = cloudscape_weather(p, tex, pos[0], pos[2])
        precip = w[1]
        if w[0] > 0.0:
            d_v = clouds_height_gradient(h, w[2], p.gradient_clamp)
            c_thr = 1.0 - w[0]
            if p.coverage_threshold == COVERAGE_SAME:
                c_thr = w[0]
            # (Warp only) B <= base_bound everywhere: where D_v base_bound <= C, B D_v <= C and B_D = 0 (vc-2.29)
            # without the base lookup -- the same density, bit for bit (a NaN bound or C compares false: looked up)
            if tex.empty_skip != 0 and tex.base_bound > 0.0 and d_v * tex.base_bound <= c_thr:
                d_v = 0.0
            if d_v > 0.0:
                lb = lod_base
                if footprint_km > 0.0:
                    lb = cloudscape_lod(footprint_km, p.base_scale_km / float(tex.base_size), p.lod_bias)
                q_b = wp.vec3(pos[0] / p.base_scale_km, pos[1] / p.base_scale_km, pos[2] / p.base_scale_km)
                bs = wp.vec4()
                if tex.half_base != 0:
                    bs = sample_mip(tex.base_half, tex.base_size, tex.base_levels, lb, q_b)
                else:
                    bs = sample_mip(tex.base, tex.base_size, tex.base_levels, lb, q_b)
                l_fbm, b = clouds_base_shape(bs[0], bs[1], bs[2], bs[3])
                b_d = clouds_coverage(b, d_v, w[0], c_thr, 1)
                if b_d > 0.0:
                    density = b_d
                    if with_detail != 0:
                        ld = lod_detail
                        if footprint_km > 0.0:
                            ld = cloudscape_lod(footprint_km, p.detail_scale_km / float(tex.detail_size), p.lod_bias)
                        qx = pos[0] + p.detail_offset[0]
                        qy = pos[1] + p.detail_offset[1]
                        qz = pos[2] + p.detail_offset[2]
                        if ld < float(tex.detail_levels - 1):
                            cv = sample_bilinear_wrap(tex.curl, tex.curl.shape[0] - 1, pos[0] / p.curl_scale_km,
                                                      pos[2] / p.curl_scale_km)
                            qx = pos[0] + cv[0] * p.curl_strength_km + p.detail_offset[0]
                            qz = pos[2] + cv[1] * p.curl_strength_km + p.detail_offset[2]
                        h_d = clouds_relative_height(wp.length(wp.vec3(qx, qy, qz) - c), p.r_inner, p.r_outer, 0)
                        h_d = wp.clamp(h_d, 0.0, 1.0)
                        dt = sample_mip(tex.detail, tex.detail_size, tex.detail_levels, ld,
                                        wp.vec3(qx / p.detail_scale_km, qy / p.detail_scale_km,
                                                qz / p.detail_scale_km))
                        density = clouds_detail_erosion(b_d, dt[0], dt[1], dt[2], h_d, p.detail_direction, 1)
    return density, precip


@wp.func
def cloudscape_density(p: CloudscapeParams, tex: CloudTextures, pos: wp.vec3, with_detail: int):
    """vc-A17: (density, precipitation) at a world position at full resolution; twin of ``ccl_cloudscape_density``."""
    return cloudscape_density_lod(p, tex, pos, with_detail, 0.0, 0.0, 0.0)


@wp.func
def coarse_cloud(p: CloudscapeParams, tex: CloudTextures, eye: wp.vec3, d: wp.vec3, t: float, speed_h: float,
                 footprint_km: float):
    """The coarse test of the march (twin of ``coarse_cloud`` in cloudscape.c; the refinement's, once per long view
    step, and a group's, at each end): (1 where the base shape (no detail) at ray distance ``t`` has density > 0, at
    the mip level of ``footprint_km``, else 0; the ray distance up to which the density is certainly 0, from
    :func:`empty_until`, Warp only: where ``t`` is before it, no lookup). The detail only erodes, so 0 at a view
    sample's own footprint means that the view sample has density 0 too."""
    q = eye + d * t
    skip = empty_until(p, tex, q, t, speed_h)
    if t < skip:
        return int(0), skip
    fp = float(0.0)
    if p.lod != 0:
        fp = footprint_km  # (its mip level is computed in the density, only where the base is looked up)
    rho, precip = cloudscape_density_lod(p, tex, q, 0, 0.0, 0.0, fp)
    if rho > 0.0:
        return int(1), skip
    return int(0), skip


@wp.func
def light_depth(p: CloudscapeParams, tex: CloudTextures, pos: wp.vec3, to_sun: wp.vec3, t_i: float,
                pixel_angle: float) -> float:
    """vc-A19: the optical depth towards the sun of a lit sample at ``pos`` (ray distance ``t_i``) from 6 cone samples
    (twin of ``light_depth`` in cloudscape.c)."""
    lod_lb = float(0.0)
    lod_ld = float(0.0)
    if p.lod != 0:
        # the light samples at the nearest whole level: one lookup each instead of a blend of two (the optical depth
        # towards the sun is a sum of six samples, smooth where the view's colour is not)
        fl = wp.max(t_i * pixel_angle, p.light_step_km)
        lod_lb = wp.floor(cloudscape_lod(fl, p.base_scale_km / float(tex.base_size), p.lod_bias) + 0.5)
        lod_ld = wp.floor(cloudscape_lod(fl, p.detail_scale_km / float(tex.detail_size), p.lod_bias) + 0.5)
    d_light = float(0.0)
    for j in range(6):
        w = (p.light_far_factor - 1.0) * 5.0 * p.light_step_km
        if j < 5:
            w = p.light_step_km
        q = raymarch_light_sample_position(pos, to_sun, j, p.light_step_km, p.light_cone_angle,
                                           p.light_far_factor, raymarch_light_cone_kernel(j))
        if empty_until(p, tex, q, 0.0, 1.0) < 0.0:  # (else certainly 0: no lookup)
            rj, pj = cloudscape_density_lod(p, tex, q, p.light_detail, lod_lb, lod_ld, 0.0)
            d_light = d_light + w * rj
    return d_light * p.sigma_light


@declare("vc-x-ms-view", c="ccl_cloudscape_ms_view",
         args=(Arg("trans", "view transmittance in front of the sample", lo=0.0, hi=1.0),
               Arg("k", "growth of the weight; 0 = off", lo=0.0, hi=1.0e3),
               Arg("t0", "view transmittance below which the weight grows", lo=1.0e-3, hi=1.0)),
         outputs=("weight",),
         summary="Weight of the multiple-scattering octaves by the depth into the cloud along the view (beyond the "
                 "text): 1 + k max(1 - T / T0, 0), T the view transmittance in front of the sample; 1 when k = 0.",
         references=("Wrenninge, Kulla & Lundqvist, Oz: the great and volumetric, SIGGRAPH 2013 Talks",))
@wp.func
def cloudscape_ms_view(trans: float, k: float, t0: float) -> float:
    """Twin of ``ccl_cloudscape_ms_view`` (cloudscape.h)."""
    return 1.0 + k * wp.max(1.0 - trans / t0, 0.0)


@declare("vc-x-ms-slab", c="ccl_cloudscape_ms_slab",
         args=(Arg("mu0", "cosine of the direction to the sun with the local up", lo=-1.0, hi=1.0),
               Arg("d", "optical depth towards the sun", lo=0.0, hi=1.0e6),
               Arg("trans", "view transmittance in front of the sample", lo=0.0, hi=1.0),
               Arg("k", "gain of the weight; 0 = off", lo=0.0, hi=1.0e3),
               Arg("p", "exponent of mu0", lo=0.0, hi=4.0),
               Arg("s", "share lost on the side away from the sun", lo=0.0, hi=1.0)),
         outputs=("weight",),
         summary="Weight of the multiple-scattering octaves by the sun's elevation and the sample's place between "
                 "the sun and the viewer (beyond the text): k max(mu0, 0)^p (1 - s r), r = d / (d + tau_v), tau_v = "
                 "-ln max(T, 1e-30) the optical depth back to the eye (r = 0 where d + tau_v = 0): light scattered "
                 "many times comes from the sun's flux through the cloud's top and fades towards its far side; 1 "
                 "when k = 0.",
         references=("Wrenninge, Kulla & Lundqvist, Oz: the great and volumetric, SIGGRAPH 2013 Talks",
                     "Bohren & Clothiaux, Fundamentals of Atmospheric Radiation, Wiley 2006, ch. 6 (two-stream "
                     "theory of a cloud slab)"))
@wp.func
def cloudscape_ms_slab(mu0: float, d: float, trans: float, k: float, p: float, s: float) -> float:
    """Twin of ``ccl_cloudscape_ms_slab`` (cloudscape.h)."""
    if not (k > 0.0):
        return 1.0
    tau_v = -wp.log(wp.max(trans, 1.0e-30))
    r = float(0.0)
    if d + tau_v > 0.0:
        r = d / (d + tau_v)
    return k * wp.pow(wp.max(mu0, 0.0), p) * (1.0 - s * r)


@declare("vc-x-ambient-aniso", c="ccl_cloudscape_ambient_aniso",
         args=(Arg("mu", "cosine of the view direction with the local up", lo=-1.0, hi=1.0),
               Arg("trans", "view transmittance in front of the sample", lo=0.0, hi=1.0),
               Arg("alpha", "anisotropy; 0 = off", lo=0.0, hi=1.0)),
         outputs=("weight",),
         summary="Weight of the ambient by the view direction (beyond the text): 1 + alpha mu T: a forward-scattering "
                 "cloud sends the sky light from above on downwards, less back up; the weight fades with the view "
                 "transmittance T (deeper, the light is scattered many times and isotropic); 1 when alpha = 0.",
         references=("Henyey & Greenstein, Diffuse radiation in the galaxy, ApJ 93, 1941",))
@wp.func
def cloudscape_ambient_aniso(mu: float, trans: float, alpha: float) -> float:
    """Twin of ``ccl_cloudscape_ambient_aniso`` (cloudscape.h)."""
    return 1.0 + alpha * mu * trans


@wp.func
def sample_light(p: CloudscapeParams, d_light: float, precip: float, pos: wp.vec3, cos_theta: float, trans: float,
                 view: wp.vec3, to_sun: wp.vec3) -> wp.vec3:
    """vc-2.31 + vc-A20: the light of a lit sample from its optical depth towards the sun ``d_light`` (E of vc-2.31
    with the multiple-scattering octaves, dual-lobe phase, beer / powder flags) and the ambient by relative height
    (twin of ``sample_light`` in cloudscape.c). ``trans``: the view transmittance in front of the sample and ``view``
    the view direction, for the octaves' weight by the depth into the cloud (vc-x-ms-view) and the ambient's
    anisotropy (vc-x-ambient-aniso); ``to_sun`` for the octaves' weight by the sun's elevation and the sample's
    place between the sun and the viewer (vc-x-ms-slab); all off (weight 1) at their defaults."""
    a = p.absorption_base + p.absorption_precip * precip
    e = cloudscape_energy(p, d_light, a, cos_theta)
    amb_w = float(1.0)
    if p.ambient_aniso > 0.0:  # (off: no normalisation per sample)
        amb_w = cloudscape_ambient_aniso(wp.dot(view, wp.normalize(pos - p.centre)), trans, p.ambient_aniso)
    if (p.ms_view > 0.0 or p.ms_slab > 0.0) and p.ms_octaves > 1:
        q = p
        q.ms_octaves = 1
        e1 = cloudscape_energy(q, d_light, a, cos_theta)
        w = float(1.0)
        if p.ms_view > 0.0:
            w = cloudscape_ms_view(trans, p.ms_view, p.ms_view_trans)
        if p.ms_slab > 0.0:
            mu0 = wp.min(wp.max(wp.dot(to_sun, wp.normalize(pos - p.centre)), -1.0), 1.0)
            w = w * cloudscape_ms_slab(mu0, d_light, trans, p.ms_slab, p.ms_slab_mu, p.ms_slab_far)
        e = e1 + (e - e1) * w
    h = clouds_relative_height(wp.length(pos - p.centre), p.r_inner, p.r_outer, 0)
    return wp.vec3(
        p.sun_colour[0] * e + amb_w * (p.ambient_bottom[0] + (p.ambient_top[0] - p.ambient_bottom[0]) * h),
        p.sun_colour[1] * e + amb_w * (p.ambient_bottom[1] + (p.ambient_top[1] - p.ambient_bottom[1]) * h),
        p.sun_colour[2] * e + amb_w * (p.ambient_bottom[2] + (p.ambient_top[2] - p.ambient_bottom[2]) * h))


@wp.func
def ends_ray(p: CloudscapeParams, trans: float, rho: float, dt: float) -> int:
    """1 where a sample of density ``rho`` and length ``dt`` ends the ray at transmittance ``trans``: the stop flag of
    :func:`raymarch_accumulate` (vc-A21) for that sample (its colour does not matter: none is passed), with the early
    exit on (twin of ``ends_ray`` in cloudscape.c). Such a sample does not wait for the light interpolation: it gets
    its own optical depth at once, and the next sample's, which the interpolation would need, is never computed (the
    ray stops there)."""
    zero = wp.vec3(0.0, 0.0, 0.0)
    c, t, stop = raymarch_accumulate(zero, trans, p.sigma, rho, dt, zero, p.exit_eps)
    r = int(0)
    if p.early_exit != 0 and stop != 0:
        r = 1
    return r


@wp.func
def march_sample(p: CloudscapeParams, colour: wp.vec3, trans: float, depth_w: float, depth_sum: float, rho: float,
                 dt: float, light: wp.vec3, t_i: float):
    """vc-A21 for one lit sample at ray distance ``t_i``, and the early exit with its fill (twin of ``march_sample``
    in cloudscape.c): (colour, transmittance, depth weight, depth sum, 1 where the ray stops)."""
    t_before = trans
    c, t, stop = raymarch_accumulate(colour, trans, p.sigma, rho, dt, light, p.exit_eps)
    # the sample's weight in the pixel, for the mean distance of the aerial perspective
    dw = depth_w + (t_before - t)
    ds = depth_sum + (t_before - t) * t_i
    out = int(0)
    if stop != 0 and p.early_exit != 0:
        out = 1
        if p.exit_fill != 0:
            # the rest of the ray's weight, T, takes the last sample's light (exit_fill in the C)
            c = c + light * t
            dw = dw + t
            ds = ds + t * t_i
            t = 0.0
    return c, t, dw, ds, out


# --- the textbook march (vc-A18..A21 as the thesis prints the loop, §4.3.2) ------------------------------------------
# For reading beside the text: the same density (vc-A17), light (vc-2.31, vc-A20) and accumulation (vc-A21) as the fast
# march below, in the thesis's loop. Its symbols: d the optical depth towards the sun, a the precipitation coefficient
# and theta the angle of HG in E (vc-2.31); C the colour of the clouds (C_clouds of vc-4.8) and T the view
# transmittance, O_D = 1 - T.

@wp.func
def textbook_light_depth(p: CloudscapeParams, tex: CloudTextures, pos: wp.vec3, to_sun: wp.vec3) -> float:
    """vc-A19: the optical depth d towards the sun of the sample at ``pos``: six pseudo-random samples q_j in a cone
    from ``pos`` towards the sun, each further out and further to the side; five near ones (a light step apart), the
    sixth at light_far_factor times their distance. Each density counts for the length w_j of the path it stands for
    (twin of ``textbook_light_depth`` in cloudscape.c)."""
    d = float(0.0)
    for j in range(6):
        w_j = (p.light_far_factor - 1.0) * 5.0 * p.light_step_km
        if j < 5:
            w_j = p.light_step_km
        q_j = raymarch_light_sample_position(pos, to_sun, j, p.light_step_km, p.light_cone_angle,
                                             p.light_far_factor, raymarch_light_cone_kernel(j))
        rho_j, precip_j = cloudscape_density(p, tex, q_j, p.light_detail)
        d = d + w_j * rho_j
    return d * p.sigma_light


@wp.func
def cloudscape_march_textbook(p: CloudscapeParams, tex: CloudTextures, eye: wp.vec3, dir: wp.vec3, to_sun: wp.vec3,
                              offset: float):
    """The thesis's loop (vc-A18..A21): (C, T, samples taken, mean distance [km]) as :func:`cloudscape_march`,
    without refinement, grouping, light interpolation or level of detail; twin of ``ccl_cloudscape_march_textbook``."""
    C = wp.vec3(0.0, 0.0, 0.0)
    T = float(1.0)
    depth_w = float(0.0)
    depth_sum = float(0.0)
    taken = int(0)
    # theta of HG: |dir| and |to_sun| are 1 only to within rounding, keep cos(theta) in [-1, 1]
    cos_theta = wp.min(wp.max(wp.dot(dir, to_sun), -1.0), 1.0)
    # vc-A14 / A24: the start and end points, where the ray crosses the layer; vc-A18: n samples between them, 64
    # towards the zenith .. 128 towards the horizon (or always samples_max)
    t0, t1 = raymarch_layer_segment(eye, dir, p.centre, p.r_earth, p.r_inner, p.r_outer)
    n = p.samples_max
    if p.adaptive_samples != 0:
        n = raymarch_view_sample_count(dir[1], p.samples_min, p.samples_max)
    t_start, dt = raymarch_interval(t0, t1, n)
    if not (t1 >= t0 and dt == dt):  # no segment, or none in front of the eye (NaN)
        n = 0
    for i in range(n):
        t_i = t_start + (float(i) + offset) * dt
        pos = raymarch_point(eye, dir, t_start, dt, i, offset)
        taken = taken + 1
        rho, precip = cloudscape_density(p, tex, pos, 1)  # vc-A17, full resolution
        if rho > 0.0:
            d = textbook_light_depth(p, tex, pos, to_sun)  # vc-A19: only where the density is non-zero
            # vc-2.31 + vc-A20: L = sun E(d, a, theta, g) + the ambient by relative height; vc-A21: C += T (1 -
            # exp(-sigma rho dt)) L, T *= exp(-sigma rho dt), and stop once O_D = 1 - T has reached its maximum
            light = sample_light(p, d, precip, pos, cos_theta, T, dir, to_sun)
            C, T, depth_w, depth_sum, stop = march_sample(p, C, T, depth_w, depth_sum, rho, dt, light, t_i)
            if stop != 0:
                break
    depth = float(0.0)
    if depth_w > 0.0:
        depth = depth_sum / depth_w
    return C, T, taken, depth


# --- the fast march ---------------------------------------------------------------------------------------------------

@wp.func
def cloudscape_march(p: CloudscapeParams, tex: CloudTextures, eye: wp.vec3, d: wp.vec3, to_sun: wp.vec3,
                     offset: float, pixel_angle: float):
    """One view ray: (cloud colour, transmittance, samples taken, mean distance [km]); twin of
    ``ccl_cloudscape_march`` (the mean distance: the transmittance-weighted mean distance of the samples, 0 where
    nothing was accumulated, for the aerial perspective).
    ``pixel_angle``: the angle between neighbouring pixels' rays (rad), for the level of detail.
    ``p.march`` selects the loop: MARCH_FAST, this one; MARCH_TEXTBOOK, :func:`cloudscape_march_textbook`."""
    if p.march == MARCH_TEXTBOOK:
        tb_colour, tb_trans, tb_taken, tb_depth = cloudscape_march_textbook(p, tex, eye, d, to_sun, offset)
        return tb_colour, tb_trans, tb_taken, tb_depth
    colour = wp.vec3(0.0, 0.0, 0.0)
    trans = float(1.0)
    taken = int(0)
    depth_sum = float(0.0)
    depth_w = float(0.0)
    t0, t1 = raymarch_layer_segment(eye, d, p.centre, p.r_earth, p.r_inner, p.r_outer)
    if t1 >= t0:
        n = p.samples_max
        if p.adaptive_samples != 0:
            n = raymarch_view_sample_count(d[1], p.samples_min, p.samples_max)
        cos_theta = wp.dot(d, to_sun)
        # |d| and |to_sun| are 1 only to within rounding: keep the phase function's argument in [-1, 1] (as the C)
        if cos_theta > 1.0:
            cos_theta = 1.0
        elif cos_theta < -1.0:
            cos_theta = -1.0
        t_start, dt_view = raymarch_interval(t0, t1, n)
        if p.refine_step_km > 0.0 and dt_view > p.refine_step_km * float(p.refine_max):
            # no view step longer than refine_step_km x refine_max (the coarse test would miss clouds between its
            # points): more steps, at most COARSE_MAX_FACTOR x samples_max (CCL_CLOUDSCAPE_COARSE_MAX_FACTOR)
            need = wp.ceil(dt_view * float(n) / (p.refine_step_km * float(p.refine_max)))
            most = COARSE_MAX_FACTOR * p.samples_max
            n2 = most
            if need < float(most):
                n2 = int(need)
            if n2 > n:
                n = n2
                t_start, dt_view = raymarch_interval(t0, t1, n)
        if dt_view == dt_view:  # not NaN
            # refinement: a view step longer than refine_step_km is split into k sub-steps where the coarse test
            # finds cloud (here or at the previous step); empty steps cost one base-shape lookup
            k = int(1)
            if p.refine_step_km > 0.0 and dt_view > p.refine_step_km:
                kf = wp.ceil(dt_view / p.refine_step_km)
                k = p.refine_max
                if kf < float(p.refine_max):  # never an int() of a huge or infinite ratio
                    k = int(kf)
            dt = dt_view / float(k)
            # grouping: where the view steps are already no longer than refine_step_km (k = 1), up to refine_max of
            # them, spanning at most GROUP_SPAN x refine_step_km, share a coarse test at each end of the group and
            # are skipped together where both find no cloud
            grp = int(1)
            if k == 1 and p.refine_step_km > 0.0:
                gf = wp.floor(GROUP_SPAN * p.refine_step_km / dt_view)
                if gf >= float(p.refine_max):  # (also a zero-length segment: never an int() of inf)
                    grp = p.refine_max
                elif gf > 1.0:
                    grp = int(gf)
            next_cloud = int(-1)  # the coarse test at the start of the next group, once made
            prev_cloud = int(0)
            ahead = int(-1)  # the refinement's coarse test of the next step, once made
            c_skip = float(-1.0)  # the coarse tests' empty space: up to c_skip from the last test's point
            # empty-space skipping (Warp only, no change of any result): samples before skip_end have density 0
            skip_end = float(-1.0)
            speed_h = wp.sqrt(d[0] * d[0] + d[2] * d[2])
            # light interpolation: the waiting sample, the last lit sample whose optical depth was computed
            pend = int(0)
            pend_rho = float(0.0)
            pend_t = float(0.0)
            pend_precip = float(0.0)
            pend_pos = wp.vec3(0.0, 0.0, 0.0)
            computed = int(0)
            d_prev = float(0.0)
            light_prev = wp.vec3(0.0, 0.0, 0.0)
            t_prev = float(0.0)
            stop = int(0)
            m = int(0)
            while m < n * k:
                i = m / k
                sub = m - i * k
                if grp > 1 and m % grp == 0:
                    # k = 1: the group's first view sample is at t_g itself, with the same footprint (the tests' own
                    # empty-space distances are not kept: the one at the group's end lies ahead of its samples)
                    t_g = t_start + (float(m) + offset) * dt_view
                    t_n = t_start + (float(m + grp) + offset) * dt_view
                    here = next_cloud
                    if here < 0:
                        here, skip_g = coarse_cloud(p, tex, eye, d, t_g, speed_h, t_g * pixel_angle)
                        taken = taken + 1
                    next_cloud, skip_n = coarse_cloud(p, tex, eye, d, t_n, speed_h, t_n * pixel_angle)
                    taken = taken + 1
                    if here == 0 and next_cloud == 0:
                        m = m + grp
                        continue
                    if here == 0:  # the first view sample: density 0, as its coarse test found (counted, as skipped)
                        m = m + 1
                        taken = taken + 1
                        continue
                if k > 1 and sub == 0:
                    # the step's coarse test (made ahead by the previous step), and the next step's: a cloud found
                    # there may begin within this step (its samples lie between the coarse points of the previous
                    # and the next step). The tests' empty-space distances (c_skip) hold from their own points on,
                    # so they skip later tests, not this step's samples before its point
                    t_c = t_start + (float(i) + offset) * dt_view
                    taken = taken + 1
                    cloud = ahead
                    if cloud < 0:
                        cloud = int(0)
                        if t_c >= c_skip:
                            cloud, c_skip = coarse_cloud(p, tex, eye, d, t_c, speed_h,
                                                         wp.max(t_c * pixel_angle, dt_view))
                    ahead = int(0)
                    if i + 1 < n:
                        t_a = t_start + (float(i + 1) + offset) * dt_view
                        if t_a >= c_skip:
                            ahead, c_skip = coarse_cloud(p, tex, eye, d, t_a, speed_h,
                                                         wp.max(t_a * pixel_angle, dt_view))
                    if cloud == 0 and prev_cloud == 0 and ahead == 0:
                        m = m + k
                        continue
                    prev_cloud = cloud
                t_i = t_start + (float(i) + (float(sub) + offset) / float(k)) * dt_view
                pos = eye + d * t_i
                m = m + 1
                taken = taken + 1
                if t_i < skip_end:
                    continue
                skip_end = empty_until(p, tex, pos, t_i, speed_h)
                if t_i < skip_end:
                    continue
                fp = float(0.0)
                if p.lod != 0:
                    # footprint of the sample: the pixel's width at its distance (the refinement keeps the steps
                    # short where there is cloud, so they need no blur along the ray); its mip levels are computed
                    # in the density only where it looks up a texture (cloudscape_lod(fp) is 0 for fp <= 0)
                    fp = t_i * pixel_angle
                rho, precip = cloudscape_density_lod(p, tex, pos, 1, 0.0, 0.0, fp)
                if rho > 0.0:
                    # light interpolation (light_interp in the C): the lit sample right after one whose optical depth
                    # towards the sun was computed waits for the next lit sample
                    if p.light_interp > 0.0 and pend == 0 and computed != 0 and t_i - t_prev <= 1.5 * dt and \
                            ends_ray(p, trans, rho, dt) == 0:
                        pend = 1
                        pend_rho = rho
                        pend_t = t_i
                        pend_precip = precip
                        pend_pos = pos
                        continue
                    d_cur = light_depth(p, tex, pos, to_sun, t_i, pixel_angle)
                    light = sample_light(p, d_cur, precip, pos, cos_theta, trans, d, to_sun)
                    if pend != 0:
                        # the waiting sample: the mean of its neighbours' optical depths where it is the middle of
                        # three consecutive samples and its weight in the pixel times the largest difference of
                        # their lights is at most light_interp, else its own
                        pend = 0
                        # (it does not end the ray: a sample that would, by ends_ray, does not wait)
                        w_p = trans * (1.0 - wp.exp(-p.sigma * pend_rho * dt))
                        diff = wp.max(wp.abs(light[0] - light_prev[0]),
                                      wp.max(wp.abs(light[1] - light_prev[1]), wp.abs(light[2] - light_prev[2])))
                        d_p = 0.5 * (d_prev + d_cur)
                        if t_i - pend_t > 1.5 * dt or w_p * diff > p.light_interp:
                            d_p = light_depth(p, tex, pend_pos, to_sun, pend_t, pixel_angle)
                        colour, trans, depth_w, depth_sum, stop = march_sample(
                            p, colour, trans, depth_w, depth_sum, pend_rho, dt,
                            sample_light(p, d_p, pend_precip, pend_pos, cos_theta, trans, d, to_sun), pend_t)
                        if stop != 0:
                            break
                        # this sample's light at the transmittance in front of it, now past the waiting sample (the
                        # terms that read it: vc-x-ms-view, vc-x-ms-slab, vc-x-ambient-aniso)
                        if p.ms_view > 0.0 or p.ms_slab > 0.0 or p.ambient_aniso > 0.0:
                            light = sample_light(p, d_cur, precip, pos, cos_theta, trans, d, to_sun)
                    computed = 1
                    d_prev = d_cur
                    light_prev = light
                    t_prev = t_i
                    colour, trans, depth_w, depth_sum, stop = march_sample(p, colour, trans, depth_w, depth_sum, rho,
                                                                           dt, light, t_i)
                    if stop != 0:
                        break
            if pend != 0:  # the ray ended with a sample waiting (a stop never leaves one)
                d_p = light_depth(p, tex, pend_pos, to_sun, pend_t, pixel_angle)
                colour, trans, depth_w, depth_sum, stop = march_sample(
                    p, colour, trans, depth_w, depth_sum, pend_rho, dt,
                    sample_light(p, d_p, pend_precip, pend_pos, cos_theta, trans, d, to_sun), pend_t)
    depth = float(0.0)
    if depth_w > 0.0:
        depth = depth_sum / depth_w
    return colour, trans, taken, depth


@wp.func
def pixel_ray(p: CloudscapeParams, inv_view_proj_rot: wp.mat44, x: int, y: int, width: int, height: int,
              frame: int):
    """vc-A25 + vc-A23: (direction, sample offset) of pixel (x, y) with the configured jitter."""
    d = camera_ray(inv_view_proj_rot, x, y, width, height)
    return raymarch_jitter(d, wp.uint32(x), wp.uint32(y), wp.uint32(frame), p.jitter_amount, p.jitter_mode)


@wp.func
def pixel_angle(inv_view_proj_rot: wp.mat44, x: int, y: int, width: int, height: int) -> float:
    """The angle (rad, as the chord of unit vectors) between the rays of pixels (x, y) and (x, y + 1): the angular
    size of the pixel, for the level of detail. Twin of the same step in ``ccl_cloudscape_pixel``."""
    return wp.length(camera_ray(inv_view_proj_rot, x, y + 1, width, height)
                     - camera_ray(inv_view_proj_rot, x, y, width, height))


@wp.func
def sky_colour(sky_kind: int, d: wp.vec3, sun: wp.vec3, preetham: Preetham, gradient: SkyGradient) -> wp.vec3:
    """Twin of ``sky_rgb`` in cloudscape.c: the sky model's display-linear colour of unit direction d (physical units,
    SKY_PREETHAM_RADIANCE: k C_HDR with negative channels at 0)."""
    if sky_kind == SKY_PREETHAM_RADIANCE:
        c = sky_preetham_hdr(d, sun, preetham)
        k = preetham.exposure
        return wp.vec3(wp.where(c[0] < 0.0, 0.0, k * c[0]), wp.where(c[1] < 0.0, 0.0, k * c[1]),
                       wp.where(c[2] < 0.0, 0.0, k * c[2]))
    if sky_kind == SKY_PREETHAM:
        return sky_preetham_rgb(d, sun, preetham)
    return sky_gradient_rgb(d, sun, gradient)


# --- lighting (see "Lighting" in cclouds/cloudscape.h) ----------------------------------------------------------------

_MIE_D = Arg("diameter_um", "droplet diameter d [um] of the Mie fit", lo=MIE_D_RANGE[0], hi=MIE_D_RANGE[1])
_DELTA_F = Arg("f", "share of the forward HG lobe treated as unscattered", lo=0.0, hi=1.0)
_DELTA_REFS = ("Joseph, Wiscombe & Weinman, The delta-Eddington approximation for radiative flux transfer, J. Atmos. "
               "Sci. 33:2452-2459, 1976",
               "Wiscombe, The delta-M method, J. Atmos. Sci. 34:1408-1422, 1977",
               "Jendersie & d'Eon, An Approximate Mie Scattering Function for Fog and Cloud Rendering, ACM SIGGRAPH "
               "2023 Talks, article 47")


@declare("vc-x-mie-delta-scale", c="ccl_cloudscape_mie_delta_scale", args=(_MIE_D, _DELTA_F), outputs=("s",),
         summary="Delta scaling of the approximate Mie phase (beyond the text): the extinction factor s = 1 - f (1 - "
                 "w_D) when a share f of the forward HG lobe is treated as unscattered light.",
         references=_DELTA_REFS)
@wp.func
def cloudscape_mie_delta_scale(diameter_um: float, f: float) -> float:
    """Twin of ``ccl_cloudscape_mie_delta_scale``: s = 1 - f (1 - w_D(d)) (cloudscape.h, "Delta scaling")."""
    g_hg, g_d, alpha, w_d = phase_mie_params(diameter_um)
    return 1.0 - f * (1.0 - w_d)


@declare("vc-x-mie-delta", c="ccl_cloudscape_mie_delta_phase",
         args=(Arg("cos_theta", "cosine of the scattering angle; +1 = forward", lo=-1.0, hi=1.0), _MIE_D, _DELTA_F),
         outputs=("p",),
         summary="Delta-scaled approximate Mie phase [sr^-1] (beyond the text): ((1 - f)(1 - w_D) HG(g_HG) + w_D "
                 "Draine(g_D, alpha)) / (1 - f (1 - w_D)), the phase left when a share f of the forward HG lobe is "
                 "treated as unscattered.",
         references=_DELTA_REFS)
@wp.func
def cloudscape_mie_delta_phase(cos_theta: float, diameter_um: float, f: float) -> float:
    """Twin of ``ccl_cloudscape_mie_delta_phase`` (cloudscape.h, "Delta scaling")."""
    g_hg, g_d, alpha, w_d = phase_mie_params(diameter_um)
    draine = phase_hg(cos_theta, g_d) * (1.0 + alpha * cos_theta * cos_theta) / (
        1.0 + alpha * (1.0 + 2.0 * g_d * g_d) / 3.0)
    return ((1.0 - f) * (1.0 - w_d) * phase_hg(cos_theta, g_hg) + w_d * draine) / (1.0 - f * (1.0 - w_d))


@declare("vc-x-ms-gain", c="ccl_cloudscape_ms_gain",
         args=(Arg("d", "optical depth towards the sun", lo=0.0, hi=1.0e6),
               Arg("depth", "optical depth scale D of the gain; 0 = off", lo=0.0, hi=1.0e6),
               Arg("thin", "gain at d = 0", lo=0.0, hi=1.0)),
         outputs=("gain",),
         summary="Weight of the multiple-scattering octaves by the optical depth towards the sun (beyond the text): "
                 "t + (1 - t)(1 - exp(-d / D)); 1 when D = 0.",
         references=("Wrenninge, Kulla & Lundqvist, Oz: the great and volumetric, SIGGRAPH 2013 Talks",
                     "Hillaire, Physically based sky, atmosphere and cloud rendering in Frostbite, SIGGRAPH 2016"))
@wp.func
def cloudscape_ms_gain(d: float, depth: float, thin: float) -> float:
    """Twin of ``ccl_cloudscape_ms_gain`` (cloudscape.h)."""
    if not (depth > 0.0):
        return 1.0
    return thin + (1.0 - thin) * (1.0 - wp.exp(-d / depth))


@wp.func
def cloudscape_energy(p: CloudscapeParams, d: float, a: float, cos_theta: float) -> float:
    """Twin of ``ccl_cloudscape_energy``: the sun energy of a sample, sum over i < ms_octaves of ms_b^i beer(ms_a^i d)
    phase_i powder(ms_a^i d) with the dual-lobe phase (1 - w) HG(ms_c^i g) + w HG(ms_c^i silver_g) (Wrenninge et al.
    2013, Hillaire 2016); one octave and w = 0 is vc-2.31 (``clouds_energy``) bit for bit."""
    e = float(0.0)
    ai = float(1.0)
    bi = float(1.0)
    ci = float(1.0)
    mie = float(0.0)
    if p.phase == PHASE_MIE:
        if p.mie_delta > 0.0:
            mie = cloudscape_mie_delta_phase(cos_theta, p.droplet_um, p.mie_delta)
        else:
            mie = phase_mie(cos_theta, p.droplet_um)
    gain = cloudscape_ms_gain(d, p.ms_depth, p.ms_thin)
    for i in range(p.ms_octaves):
        di = d * ai
        if i == 1:
            bi = bi * gain  # the octaves i >= 1 by the optical depth towards the sun (1 when ms_depth = 0)
        beer = float(1.0)
        if p.beer != 0:
            beer = wp.exp(-di * a)
        powder = float(1.0)
        if p.powder != 0:
            powder = 1.0 - wp.exp(-2.0 * di)
        phase = float(0.0)
        if p.phase == PHASE_MIE:
            # c^i of the Mie phase and 1 - c^i isotropic: the octave's mean cosine is c^i g, as with HG(c^i g)
            phase = ci * mie + (1.0 - ci) * INV_4PI
        else:
            phase = phase_hg(cos_theta, p.g * ci)
            if p.silver_weight > 0.0:  # dual lobe: (1 - w) HG(g) + w HG(silver_g)
                phase = (1.0 - p.silver_weight) * phase + p.silver_weight * phase_hg(cos_theta, p.silver_g * ci)
        e = e + bi * beer * phase * powder
        ai = ai * p.ms_a
        bi = bi * p.ms_b
        ci = ci * p.ms_c
    return e


GROUND_PATCH_KM = 0.125  # CCL_CLOUDSCAPE_GROUND_PATCH_KM


@wp.func
def _ground_noise(x: float, z: float) -> float:
    """Value noise of the ground patches (``ground_noise`` of cloudscape.c)."""
    lim = 8388608.0
    fx = wp.floor(wp.min(wp.max(x, -lim), lim))
    fz = wp.floor(wp.min(wp.max(z, -lim), lim))
    u = wp.min(wp.max(x - fx, 0.0), 1.0)
    v = wp.min(wp.max(z - fz, 0.0), 1.0)
    ix = wp.uint32(int(fx))
    iz = wp.uint32(int(fz))
    one = wp.uint32(1)
    a = hash_unit(hash_pcg(hash_pcg(ix) ^ iz))
    b = hash_unit(hash_pcg(hash_pcg(ix + one) ^ iz))
    c = hash_unit(hash_pcg(hash_pcg(ix) ^ (iz + one)))
    d = hash_unit(hash_pcg(hash_pcg(ix + one) ^ (iz + one)))
    u = u * u * (3.0 - 2.0 * u)
    v = v * v * (3.0 - 2.0 * v)
    return (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v


@wp.func
def cloudscape_ground(p: CloudscapeParams, tex: CloudTextures, point: wp.vec3, to_sun: wp.vec3):
    """Twin of ``ccl_cloudscape_ground``: (radiance, T_shadow) of the ground at ``point``: ground_albedo (sun_colour
    max(n . s, 0) T_shadow / pi + ambient_ground), T_shadow from GROUND_SHADOW_SAMPLES base-shape density samples on
    the ray towards the sun through the layer."""
    n = point - p.centre
    n = n * (1.0 / wp.length(n))
    cos_sun = wp.dot(n, to_sun)
    if not (cos_sun > 0.0):
        cos_sun = 0.0
    shadow = float(1.0)
    if cos_sun > 0.0:
        a0, a1 = raymarch_ray_sphere(point, to_sun, p.centre, p.r_inner)
        b0, b1 = raymarch_ray_sphere(point, to_sun, p.centre, p.r_outer)
        if a1 == a1 and b1 == b1:  # both hit (not NaN)
            ts = float(0.0)
            if a1 > 0.0:
                ts = a1
            dt = (b1 - ts) / float(GROUND_SHADOW_SAMPLES)
            lod = float(0.0)
            if p.lod != 0:
                lod = cloudscape_lod(dt, p.base_scale_km / float(tex.base_size), p.lod_bias)
            od = float(0.0)
            if dt > 0.0:
                for i in range(GROUND_SHADOW_SAMPLES):
                    q = raymarch_point(point, to_sun, ts, dt, i, 0.5)
                    rho, pr = cloudscape_density_lod(p, tex, q, 0, lod, 0.0, 0.0)
                    od = od + rho
                shadow = wp.exp(-p.sigma_light * (od * dt))
    k = cos_sun * shadow * 0.318309886  # 1 / pi
    patch = float(1.0)
    if p.ground_variation > 0.0:
        x = point[0] / GROUND_PATCH_KM
        z = point[2] / GROUND_PATCH_KM
        noise = (2.0 * _ground_noise(x, z) + _ground_noise(4.0 * x, 4.0 * z)) / 3.0
        patch = 1.0 + p.ground_variation * (2.0 * noise - 1.0)
    return wp.vec3(p.ground_albedo[0] * patch * (p.sun_colour[0] * k + p.ambient_ground[0]),
                   p.ground_albedo[1] * patch * (p.sun_colour[1] * k + p.ambient_ground[1]),
                   p.ground_albedo[2] * patch * (p.sun_colour[2] * k + p.ambient_ground[2])), shadow


@wp.func
def cloudscape_light(p: CloudscapeParams, sky_kind: int, sun: wp.vec3, preetham: Preetham,
                     gradient: SkyGradient) -> CloudscapeParams:
    """Twin of ``ccl_cloudscape_light``: ``p`` with sun_colour, ambient_top / _bottom / _ground from the sky model
    (sky lighting), unchanged for the thesis's lighting."""
    q = p
    if p.lighting == LIGHTING_SKY:
        dtheta = 1.5707963 / float(SKY_THETA_CELLS)
        dphi = 6.2831853 / float(SKY_PHI_CELLS)
        cos_s = wp.clamp(sun[1], 0.0, 1.0)
        att = sky_sun_attenuation(wp.acos(cos_s), p.turbidity)
        # physical units: the sun's illuminance above the atmosphere x the one exposure of the sky
        e_sun = p.sun_intensity
        if sky_kind == SKY_PREETHAM_RADIANCE:
            e_sun = preetham.exposure * (float(SUN_KLX_X10) * 0.1)
        q.sun_colour = wp.vec3(e_sun * att[0], e_sun * att[1], e_sun * att[2])
        mean = wp.vec3(0.0, 0.0, 0.0)
        cmean = wp.vec3(0.0, 0.0, 0.0)
        wsum = float(0.0)
        csum = float(0.0)
        for i in range(SKY_THETA_CELLS):
            theta = (float(i) + 0.5) * dtheta
            st = wp.sin(theta)
            ct = wp.cos(theta)
            wc = st * ct
            for j in range(SKY_PHI_CELLS):
                phi = (float(j) + 0.5) * dphi
                s = sky_colour(sky_kind, wp.vec3(st * wp.sin(phi), ct, -st * wp.cos(phi)), sun, preetham, gradient)
                v = wp.vec3(wp.max(s[0], 0.0), wp.max(s[1], 0.0), wp.max(s[2], 0.0))
                mean = wp.vec3(mean[0] + v[0] * st, mean[1] + v[1] * st, mean[2] + v[2] * st)
                cmean = wp.vec3(cmean[0] + v[0] * wc, cmean[1] + v[1] * wc, cmean[2] + v[2] * wc)
                wsum = wsum + st
                csum = csum + wc
        # the lower hemisphere's share: the unshadowed Lambertian ground under the sun and the sky
        w = p.ambient_ground_weight
        amb_g = wp.vec3(cmean[0] / csum, cmean[1] / csum, cmean[2] / csum)
        k = cos_s * 0.318309886
        sc = q.sun_colour
        top = wp.vec3((1.0 - w) * (mean[0] / wsum) + w * (p.ground_albedo[0] * (sc[0] * k + amb_g[0])),
                      (1.0 - w) * (mean[1] / wsum) + w * (p.ground_albedo[1] * (sc[1] * k + amb_g[1])),
                      (1.0 - w) * (mean[2] / wsum) + w * (p.ground_albedo[2] * (sc[2] * k + amb_g[2])))
        q.ambient_top = top
        q.ambient_bottom = wp.vec3(p.ambient_bottom_ratio * top[0], p.ambient_bottom_ratio * top[1],
                                   p.ambient_bottom_ratio * top[2])
        q.ambient_ground = amb_g
        if p.phase == PHASE_MIE and p.mie_delta > 0.0:
            # delta scaling: the forward peak's share mie_delta goes on unscattered (cloudscape_mie_delta_scale)
            scale = cloudscape_mie_delta_scale(p.droplet_um, p.mie_delta)
            q.sigma = p.sigma * scale
            q.sigma_light = p.sigma_light * scale
    return q


@wp.func
def lift_to_horizon(d: wp.vec3) -> wp.vec3:
    """(d.x, max(d.y, 0), d.z) normalised, (0, 0, -1) at the nadir: the haze direction of the aerial perspective."""
    h = wp.vec3(d[0], wp.max(d[1], 0.0), d[2])
    ln = wp.length(h)
    if not (ln > 1.0e-6):
        return wp.vec3(0.0, 0.0, -1.0)
    return h * (1.0 / ln)


@wp.func
def ground_hit(p: CloudscapeParams, eye: wp.vec3, d: wp.vec3):
    """(1, distance) where the ray meets the Earth sphere ahead (entered in front of the camera, or from the ground
    pointing downwards: distance 0), else (0, 0): the test of ``ccl_cloudscape_pixel``."""
    e0, e1 = raymarch_ray_sphere(eye, d, p.centre, p.r_earth)
    if e1 > 0.0:
        if e0 > 0.0:
            return int(1), e0
        if wp.dot(d, eye - p.centre) < 0.0:
            return int(1), float(0.0)
    return int(0), float(0.0)


@wp.func
def aerial_air_km(p: CloudscapeParams, eye: wp.vec3, d: wp.vec3, t: float) -> float:
    """t_air of the aerial perspective (twin of ``aerial_air_km`` in cloudscape.c): the length of ground-level air
    with the optical depth of the first ``t`` km of the ray, the haze thinning with altitude (scale height
    ``aerial_height_km``; 0: ``t``)."""
    hs = p.aerial_height_km
    if not (hs > 0.0):
        return t
    r = eye - p.centre
    ln = wp.length(r)
    y0 = ln - p.r_earth
    if not (y0 > 0.0):
        y0 = 0.0
    u = wp.dot(d, r) / ln  # the ray's vertical component at the camera
    x = u * t / hs
    a0 = wp.exp(-y0 / hs)
    t_air = float(0.0)
    if wp.abs(x) < 1.0e-3:
        t_air = t * a0 * (1.0 - 0.5 * x)
    else:
        t_air = (a0 - wp.exp(-(y0 + u * t) / hs)) * (hs / u)
    if t_air < t:
        return t_air
    return t


@wp.func
def horizon_coverage(p: CloudscapeParams, eye: wp.vec3, d: wp.vec3, pixel_angle: float) -> float:
    """The pixel's coverage by the Earth (twin of ``horizon_coverage`` in cloudscape.c): the ray's elevation above the
    horizon seen from the eye, a = asin(d . up) + acos(r_earth / |eye - centre|), over the pixel's angular size,
    box-filtered: clamp(0.5 - a / pixel_angle, 0, 1)."""
    r = eye - p.centre
    ln = wp.length(r)
    s = wp.dot(d, r) / ln
    q = p.r_earth / ln
    if s > 1.0:
        s = 1.0
    elif s < -1.0:
        s = -1.0
    if q > 1.0:
        q = 1.0
    if not (pixel_angle > 0.0):
        if s < 0.0:
            return 1.0
        return 0.0
    a = wp.asin(s) + wp.acos(q)
    cov = 0.5 - a / pixel_angle
    if cov < 0.0:
        return 0.0
    if cov > 1.0:
        return 1.0
    return cov


@wp.func
def sky_lit_composite(p: CloudscapeParams, tex: CloudTextures, eye: wp.vec3, d: wp.vec3, sun: wp.vec3,
                      haze: wp.vec3, cl: wp.vec3, trans: float, depth: float, pixel_angle: float) -> wp.vec3:
    """Sky lighting's ground and aerial perspective (twin of ``sky_lit_composite`` in cloudscape.c): B T + C' with B
    the lit ground faded by its distance (ground) or the haze colour (sky), C' the clouds faded by their mean
    distance. B is anti-aliased at the horizon: haze + (ground - haze) x the pixel's coverage by the Earth
    (:func:`horizon_coverage`), the ground of a ray that passes above the Earth taken at the horizon's distance."""
    ground, t_ground = ground_hit(p, eye, d)
    cov = horizon_coverage(p, eye, d, pixel_angle)
    if ground == 0 and cov > 0.0:
        ln = wp.length(eye - p.centre)
        h2 = (ln - p.r_earth) * (ln + p.r_earth)
        t_ground = float(0.0)
        if h2 > 0.0:
            t_ground = wp.sqrt(h2)
    f_g = float(1.0)
    f_c = float(1.0)
    if p.aerial_km > 0.0:
        f_g = wp.exp(-aerial_air_km(p, eye, d, t_ground) / p.aerial_km)
        f_c = wp.exp(-aerial_air_km(p, eye, d, depth) / p.aerial_km)
    bg = haze
    if ground != 0 or cov > 0.0:
        g, shadow = cloudscape_ground(p, tex, eye + d * t_ground, sun)
        bg = wp.vec3(g[0] * f_g + haze[0] * (1.0 - f_g), g[1] * f_g + haze[1] * (1.0 - f_g),
                     g[2] * f_g + haze[2] * (1.0 - f_g))
        if cov < 1.0:
            bg = wp.vec3(haze[0] + (bg[0] - haze[0]) * cov, haze[1] + (bg[1] - haze[1]) * cov,
                         haze[2] + (bg[2] - haze[2]) * cov)
    o_d = 1.0 - trans
    return wp.vec3(clouds_composite(bg[0], o_d, cl[0] * f_c + haze[0] * (o_d * (1.0 - f_c))),
                   clouds_composite(bg[1], o_d, cl[1] * f_c + haze[1] * (o_d * (1.0 - f_c))),
                   clouds_composite(bg[2], o_d, cl[2] * f_c + haze[2] * (o_d * (1.0 - f_c))))


@wp.func
def background(p: CloudscapeParams, sky_kind: int, eye: wp.vec3, d: wp.vec3, sun: wp.vec3, preetham: Preetham,
               gradient: SkyGradient) -> wp.vec3:
    """Twin of the background step of ``ccl_cloudscape_pixel``: the ground colour where the ray hits the Earth
    sphere ahead, else the sky model's colour. With sky lighting: the sky model's colour of the ray lifted to the
    horizon for every ray (the haze colour, which the cloud pass turns into the lit ground where the ray meets
    the Earth)."""
    if p.lighting == LIGHTING_SKY:
        return sky_colour(sky_kind, lift_to_horizon(d), sun, preetham, gradient)
    e0, e1 = raymarch_ray_sphere(eye, d, p.centre, p.r_earth)
    if e1 > 0.0:
        down = wp.dot(d, eye - p.centre)
        if e0 > 0.0 or down < 0.0:  # entered ahead, or (camera on the ground) pointing downwards
            return p.ground_colour
    return sky_colour(sky_kind, d, sun, preetham, gradient)


@wp.func
def cloudscape_pixel(p: CloudscapeParams, tex: CloudTextures, sky_kind: int,
                     sun: wp.vec3, preetham: Preetham, gradient: SkyGradient, inv_view_proj_rot: wp.mat44,
                     eye: wp.vec3, x: int, y: int, width: int, height: int, frame: int) -> wp.vec3:
    """Twin of ``ccl_cloudscape_pixel``: the display-linear colour of one pixel (sky, clouds, composite)."""
    d, offset = pixel_ray(p, inv_view_proj_rot, x, y, width, height, frame)
    bg = background(p, sky_kind, eye, d, sun, preetham, gradient)
    pa = pixel_angle(inv_view_proj_rot, x, y, width, height)
    cl, trans, taken, depth = cloudscape_march(p, tex, eye, d, sun, offset, pa)
    if p.lighting == LIGHTING_SKY:  # bg is the haze colour
        return sky_lit_composite(p, tex, eye, d, sun, bg, cl, trans, depth, pa)
    o_d = 1.0 - trans
    return wp.vec3(clouds_composite(bg[0], o_d, cl[0]), clouds_composite(bg[1], o_d, cl[1]),
                   clouds_composite(bg[2], o_d, cl[2]))


# --- image kernels (TileLauncher convention) --------------------------------------------------------------------------

@wp.kernel
def sky_kernel(row0: int, sky_kind: int, sun: wp.vec3, preetham: Preetham, gradient: SkyGradient,
               p: CloudscapeParams, inv_view_proj_rot: wp.mat44, eye: wp.vec3, frame: int, reprojection: int,
               # outputs
               frame_buffer: wp.array3d(dtype=float)):
    """Stage 1 (vc-A28 / A29): the background of every pixel (sky model, or the ground where the ray hits the
    Earth), or of this frame's pixel of each 4 x 4 block."""
    i, j = wp.tid()
    height = frame_buffer.shape[0]
    width = frame_buffer.shape[1]
    x = j
    y = row0 + i
    if reprojection != 0:
        x, y = reproj_pixel(j, row0 + i, frame)
    if x < width and y < height:
        d, offset = pixel_ray(p, inv_view_proj_rot, x, y, width, height, frame)
        c = background(p, sky_kind, eye, d, sun, preetham, gradient)
        frame_buffer[y, x, 0] = c[0]
        frame_buffer[y, x, 1] = c[1]
        frame_buffer[y, x, 2] = c[2]


@wp.kernel
def clouds_kernel(row0: int, p: CloudscapeParams, tex: CloudTextures, sun: wp.vec3, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                  frame: int, reprojection: int,
                  # outputs
                  frame_buffer: wp.array3d(dtype=float), reduced: wp.array3d(dtype=float),
                  samples: wp.array2d(dtype=wp.int32), depth_buffer: wp.array2d(dtype=float)):
    """Stage 2 (vc-A14..A22): clouds over the sky already in ``frame_buffer`` (vc-4.8); with reprojection the thread
    grid is the 4 x 4 block grid and the reduced buffer receives this frame's pixels (vc-A22). ``depth_buffer``
    receives the distance (km) of what each marched pixel shows, for the depth-aware reprojection
    (:func:`pywarp.kernels.reproj.reproj_surface_depth`: the clouds' mean distance, else the ground, else the sky far
    away)."""
    i, j = wp.tid()
    height = frame_buffer.shape[0]
    width = frame_buffer.shape[1]
    x = j
    y = row0 + i
    if reprojection != 0:
        x, y = reproj_pixel(j, row0 + i, frame)
    if x < width and y < height:
        d, offset = pixel_ray(p, inv_view_proj_rot, x, y, width, height, frame)
        pa = pixel_angle(inv_view_proj_rot, x, y, width, height)
        cl, trans, taken, depth = cloudscape_march(p, tex, eye, d, sun, offset, pa)
        o_d = 1.0 - trans
        if p.lighting == LIGHTING_SKY:
            # the sky pass wrote the haze colour (the sky lifted to the horizon): ground, aerial perspective
            haze = wp.vec3(frame_buffer[y, x, 0], frame_buffer[y, x, 1], frame_buffer[y, x, 2])
            c = sky_lit_composite(p, tex, eye, d, sun, haze, cl, trans, depth, pa)
            for ch in range(3):
                frame_buffer[y, x, ch] = c[ch]
                if reprojection != 0:
                    reduced[row0 + i, j, ch] = c[ch]
        else:
            for ch in range(3):
                v = clouds_composite(frame_buffer[y, x, ch], o_d, cl[ch])
                frame_buffer[y, x, ch] = v
                if reprojection != 0:
                    reduced[row0 + i, j, ch] = v
        samples[y, x] = taken
        depth_buffer[y, x] = reproj_surface_depth(depth, eye, d, p.centre, p.r_earth)


@wp.kernel
def light_kernel(p: CloudscapeParams, sky_kind: int, sun: wp.vec3, preetham: Preetham, gradient: SkyGradient,
                 # outputs
                 out: wp.array(dtype=CloudscapeParams)):
    """The per-frame lighting setup :func:`cloudscape_light` (one thread)."""
    out[0] = cloudscape_light(p, sky_kind, sun, preetham, gradient)


@wp.kernel
def encode_kernel(row0: int, frame_buffer: wp.array3d(dtype=float),
                  # outputs
                  out: wp.array3d(dtype=wp.uint8), non_finite: wp.array(dtype=wp.int32)):
    """Clamp to [0, 1], sRGB-encode (the display step of vc-A29) and quantise to 8 bits, int(v * 255 + 0.5) in
    float32; counts the pixels with a non-finite channel in ``non_finite[0]`` (their bytes are meaningless: the
    caller raises)."""
    i, j = wp.tid()
    y = row0 + i
    ok = int(1)
    for ch in range(3):
        c = frame_buffer[y, j, ch]
        if not wp.isfinite(c):
            ok = 0
            c = 0.0
        v = colour_srgb_encode(wp.clamp(c, 0.0, 1.0))
        out[y, j, ch] = wp.uint8(int(v * 255.0 + 0.5))
    if ok == 0:
        wp.atomic_add(non_finite, 0, 1)


@wp.kernel
def pixels_kernel(p: CloudscapeParams, tex: CloudTextures, sky_kind: int, sun: wp.vec3,
                  preetham: Preetham, gradient: SkyGradient, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                  xs: wp.array(dtype=wp.int32), ys: wp.array(dtype=wp.int32), width: int, height: int, frame: int,
                  # outputs
                  out: wp.array2d(dtype=float)):
    """:func:`cloudscape_pixel` at a list of pixels (for comparisons with the C reference)."""
    k = wp.tid()
    c = cloudscape_pixel(p, tex, sky_kind, sun, preetham, gradient, inv_view_proj_rot, eye,
                         xs[k], ys[k], width, height, frame)
    out[k, 0] = c[0]
    out[k, 1] = c[1]
    out[k, 2] = c[2]


@wp.kernel
def weather_points_kernel(p: CloudscapeParams, tex: CloudTextures, points: wp.array(dtype=wp.vec3),
                          # outputs
                          out: wp.array(dtype=wp.vec4)):
    """:func:`cloudscape_weather` at a list of world points (x, z used; for comparisons with the C reference)."""
    k = wp.tid()
    out[k] = cloudscape_weather(p, tex, points[k][0], points[k][2])
