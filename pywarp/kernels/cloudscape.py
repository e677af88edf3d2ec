"""The cloudscape pixel (vc chapter 4) as Warp code -- the twin of ``cclouds/cloudscape.h``, operation by operation.

:class:`CloudscapeParams` mirrors ``ccl_cloudscape_params``; :func:`cloudscape_density`, :func:`cloudscape_march` and
:func:`cloudscape_pixel` mirror the C functions of the same names. The image kernels follow the
:class:`pywarp.core.runtime.TileLauncher` convention (first parameter ``row0``) so a frame runs on every core:

* :func:`sky_kernel` writes the sky model's colour into the frame buffer (the first stage of the render chain);
* :func:`clouds_kernel` marches the clouds of every pixel, or, with reprojection, of one pixel per 4 x 4 block
  (vc-4.1), composites them over the frame buffer (vc-4.8) and fills the reduced buffer (vc-A22);
* :func:`encode_kernel` clamps to [0, 1] and applies the sRGB encoding.

Frame buffers are ``wp.array3d(dtype=float)`` of shape (height, width, 3), row 0 at the top, display-linear RGB.
"""
from __future__ import annotations

import warp as wp

from .clouds import (
    clouds_energy,
    clouds_base_shape,
    clouds_composite,
    clouds_coverage,
    clouds_detail_erosion,
    clouds_relative_height,
    clouds_height_gradient,
)
from .colour import colour_srgb_encode
from .phase import phase_hg
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
from .reproj import reproj_pixel
from .sky import Preetham, SkyGradient, sky_gradient_rgb, sky_preetham_rgb
from .texgen import texgen_sample_trilinear_wrap

SKY_GRADIENT = 0
SKY_PREETHAM = 1
JITTER_TILT = 0
JITTER_OFFSET = 1
JITTER_NONE = 2
LIGHTING_THESIS = 0  # ccl_lighting
LIGHTING_SKY = 1
MAX_MS_OCTAVES = 8  # CCL_CLOUDSCAPE_MAX_MS_OCTAVES


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
    aerial_km: float
    ms_octaves: int
    ms_a: float
    ms_b: float
    ms_c: float
    silver_g: float
    silver_weight: float


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


@wp.func
def cloudscape_density(p: CloudscapeParams, base: wp.array3d(dtype=wp.vec4), detail: wp.array3d(dtype=wp.vec4),
                       curl: wp.array2d(dtype=wp.vec4), weather: wp.array2d(dtype=wp.vec4), pos: wp.vec3,
                       with_detail: int):
    """vc-A17: (density, precipitation) at a world position; twin of ``ccl_cloudscape_density``."""
    c = p.centre
    r = wp.length(pos - c)
    h = clouds_relative_height(r, p.r_inner, p.r_outer, 0)
    density = float(0.0)
    precip = float(0.0)
    if h >= 0.0 and h <= 1.0:
        w = sample_bilinear_wrap(weather, weather.shape[0] - 1, (pos[0] + p.weather_offset[0]) / p.weather_scale_km,
                                 (pos[2] + p.weather_offset[1]) / p.weather_scale_km)
        precip = w[1]
        if w[0] > 0.0:
            d_v = clouds_height_gradient(h, w[2], p.gradient_clamp)
            if d_v > 0.0:
                bs = texgen_sample_trilinear_wrap(base, base.shape[0] - 1,
                                                  wp.vec3(pos[0] / p.base_scale_km, pos[1] / p.base_scale_km,
                                                          pos[2] / p.base_scale_km))
                l_fbm, b = clouds_base_shape(bs[0], bs[1], bs[2], bs[3])
                c_thr = 1.0 - w[0]
                if p.coverage_threshold == 0:
                    c_thr = w[0]
                b_d = clouds_coverage(b, d_v, w[0], c_thr, 1)
                if b_d > 0.0:
                    density = b_d
                    if with_detail != 0:
                        cv = sample_bilinear_wrap(curl, curl.shape[0] - 1, pos[0] / p.curl_scale_km,
                                                  pos[2] / p.curl_scale_km)
                        qx = pos[0] + cv[0] * p.curl_strength_km + p.detail_offset[0]
                        qy = pos[1] + p.detail_offset[1]
                        qz = pos[2] + cv[1] * p.curl_strength_km + p.detail_offset[2]
                        h_d = clouds_relative_height(wp.length(wp.vec3(qx, qy, qz) - c), p.r_inner, p.r_outer, 0)
                        h_d = wp.clamp(h_d, 0.0, 1.0)
                        dt = texgen_sample_trilinear_wrap(detail, detail.shape[0] - 1,
                                                          wp.vec3(qx / p.detail_scale_km, qy / p.detail_scale_km,
                                                                  qz / p.detail_scale_km))
                        density = clouds_detail_erosion(b_d, dt[0], dt[1], dt[2], h_d, p.detail_direction, 1)
    return density, precip


@wp.func
def cloudscape_march(p: CloudscapeParams, base: wp.array3d(dtype=wp.vec4), detail: wp.array3d(dtype=wp.vec4),
                     curl: wp.array2d(dtype=wp.vec4), weather: wp.array2d(dtype=wp.vec4), eye: wp.vec3,
                     d: wp.vec3, to_sun: wp.vec3, offset: float):
    """One view ray: (cloud colour, transmittance, samples taken); twin of ``ccl_cloudscape_march``."""
    colour = wp.vec3(0.0, 0.0, 0.0)
    trans = float(1.0)
    taken = int(0)
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
        t_start, dt = raymarch_interval(t0, t1, n)
        if dt == dt:  # not NaN
            for i in range(n):
                pos = raymarch_point(eye, d, t_start, dt, i, offset)
                taken = taken + 1
                rho, precip = cloudscape_density(p, base, detail, curl, weather, pos, 1)
                if rho > 0.0:
                    # vc-A19: optical depth towards the sun from 6 cone samples
                    d_light = float(0.0)
                    for j in range(6):
                        w = (p.light_far_factor - 1.0) * 5.0 * p.light_step_km
                        if j < 5:
                            w = p.light_step_km
                        q = raymarch_light_sample_position(pos, to_sun, j, p.light_step_km, p.light_cone_angle,
                                                           p.light_far_factor, raymarch_light_cone_kernel(j))
                        rj, pj = cloudscape_density(p, base, detail, curl, weather, q, p.light_detail)
                        d_light = d_light + w * rj
                    d_light = d_light * p.sigma_light
                    # vc-2.31 + vc-A20
                    a = p.absorption_base + p.absorption_precip * precip
                    e = float(0.0)
                    if p.beer != 0 and p.powder != 0:
                        e = clouds_energy(d_light, a, cos_theta, p.g)
                    else:  # the same product with a term replaced by 1
                        beer = float(1.0)
                        if p.beer != 0:
                            beer = wp.exp(-d_light * a)
                        powder = float(1.0)
                        if p.powder != 0:
                            powder = 1.0 - wp.exp(-2.0 * d_light)
                        e = beer * phase_hg(cos_theta, p.g) * powder
                    h = clouds_relative_height(wp.length(pos - p.centre), p.r_inner, p.r_outer, 0)
                    light = wp.vec3(
                        p.sun_colour[0] * e + (p.ambient_bottom[0] + (p.ambient_top[0] - p.ambient_bottom[0]) * h),
                        p.sun_colour[1] * e + (p.ambient_bottom[1] + (p.ambient_top[1] - p.ambient_bottom[1]) * h),
                        p.sun_colour[2] * e + (p.ambient_bottom[2] + (p.ambient_top[2] - p.ambient_bottom[2]) * h))
                    # vc-A21
                    colour, trans, stop = raymarch_accumulate(colour, trans, p.sigma, rho, dt, light, p.exit_eps)
                    if stop != 0 and p.early_exit != 0:
                        break
    return colour, trans, taken


@wp.func
def pixel_ray(p: CloudscapeParams, inv_view_proj_rot: wp.mat44, x: int, y: int, width: int, height: int,
              frame: int):
    """vc-A25 + vc-A23: (direction, sample offset) of pixel (x, y) with the configured jitter."""
    d = camera_ray(inv_view_proj_rot, x, y, width, height)
    return raymarch_jitter(d, wp.uint32(x), wp.uint32(y), wp.uint32(frame), p.jitter_amount, p.jitter_mode)


@wp.func
def sky_colour(sky_kind: int, d: wp.vec3, sun: wp.vec3, preetham: Preetham, gradient: SkyGradient) -> wp.vec3:
    if sky_kind == 1:
        return sky_preetham_rgb(d, sun, preetham)
    return sky_gradient_rgb(d, sun, gradient)


@wp.func
def background(p: CloudscapeParams, sky_kind: int, eye: wp.vec3, d: wp.vec3, sun: wp.vec3, preetham: Preetham,
               gradient: SkyGradient) -> wp.vec3:
    """Twin of the background step of ``ccl_cloudscape_pixel``: the ground colour where the ray hits the Earth
    sphere ahead, else the sky model's colour."""
    e0, e1 = raymarch_ray_sphere(eye, d, p.centre, p.r_earth)
    if e1 > 0.0:
        down = wp.dot(d, eye - p.centre)
        if e0 > 0.0 or down < 0.0:  # entered ahead, or (camera on the ground) pointing downwards
            return p.ground_colour
    return sky_colour(sky_kind, d, sun, preetham, gradient)


@wp.func
def cloudscape_pixel(p: CloudscapeParams, base: wp.array3d(dtype=wp.vec4), detail: wp.array3d(dtype=wp.vec4),
                     curl: wp.array2d(dtype=wp.vec4), weather: wp.array2d(dtype=wp.vec4), sky_kind: int,
                     sun: wp.vec3, preetham: Preetham, gradient: SkyGradient, inv_view_proj_rot: wp.mat44,
                     eye: wp.vec3, x: int, y: int, width: int, height: int, frame: int) -> wp.vec3:
    """Twin of ``ccl_cloudscape_pixel``: the display-linear colour of one pixel (sky, clouds, composite)."""
    d, offset = pixel_ray(p, inv_view_proj_rot, x, y, width, height, frame)
    bg = background(p, sky_kind, eye, d, sun, preetham, gradient)
    cl, trans, taken = cloudscape_march(p, base, detail, curl, weather, eye, d, sun, offset)
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
def clouds_kernel(row0: int, p: CloudscapeParams, base: wp.array3d(dtype=wp.vec4),
                  detail: wp.array3d(dtype=wp.vec4), curl: wp.array2d(dtype=wp.vec4),
                  weather: wp.array2d(dtype=wp.vec4), sun: wp.vec3, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                  frame: int, reprojection: int,
                  # outputs
                  frame_buffer: wp.array3d(dtype=float), reduced: wp.array3d(dtype=float),
                  samples: wp.array2d(dtype=wp.int32)):
    """Stage 2 (vc-A14..A22): clouds over the sky already in ``frame_buffer`` (vc-4.8); with reprojection the thread
    grid is the 4 x 4 block grid and the reduced buffer receives this frame's pixels (vc-A22)."""
    i, j = wp.tid()
    height = frame_buffer.shape[0]
    width = frame_buffer.shape[1]
    x = j
    y = row0 + i
    if reprojection != 0:
        x, y = reproj_pixel(j, row0 + i, frame)
    if x < width and y < height:
        d, offset = pixel_ray(p, inv_view_proj_rot, x, y, width, height, frame)
        cl, trans, taken = cloudscape_march(p, base, detail, curl, weather, eye, d, sun, offset)
        o_d = 1.0 - trans
        for ch in range(3):
            v = clouds_composite(frame_buffer[y, x, ch], o_d, cl[ch])
            frame_buffer[y, x, ch] = v
            if reprojection != 0:
                reduced[row0 + i, j, ch] = v
        samples[y, x] = taken


@wp.kernel
def encode_kernel(row0: int, frame_buffer: wp.array3d(dtype=float),
                  # outputs
                  out: wp.array3d(dtype=float)):
    """Clamp to [0, 1] and sRGB-encode (the display step of vc-A29)."""
    i, j = wp.tid()
    y = row0 + i
    for ch in range(3):
        out[y, j, ch] = colour_srgb_encode(wp.clamp(frame_buffer[y, j, ch], 0.0, 1.0))


@wp.kernel
def pixels_kernel(p: CloudscapeParams, base: wp.array3d(dtype=wp.vec4), detail: wp.array3d(dtype=wp.vec4),
                  curl: wp.array2d(dtype=wp.vec4), weather: wp.array2d(dtype=wp.vec4), sky_kind: int, sun: wp.vec3,
                  preetham: Preetham, gradient: SkyGradient, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                  xs: wp.array(dtype=wp.int32), ys: wp.array(dtype=wp.int32), width: int, height: int, frame: int,
                  # outputs
                  out: wp.array2d(dtype=float)):
    """:func:`cloudscape_pixel` at a list of pixels (for comparisons with the C reference)."""
    k = wp.tid()
    c = cloudscape_pixel(p, base, detail, curl, weather, sky_kind, sun, preetham, gradient, inv_view_proj_rot, eye,
                         xs[k], ys[k], width, height, frame)
    out[k, 0] = c[0]
    out[k, 1] = c[1]
    out[k, 2] = c[2]
