"""The ``ccl_cloudscape_params`` values of a cloudscape's settings: one source of both the Warp struct and the C
struct, and the C check of those values (``ccl_cloudscape_check``)."""
from __future__ import annotations

import numpy as np

from ..kernels import cloudscape as K

JITTERS = {"tilt": K.JITTER_TILT, "offset": K.JITTER_OFFSET, "none": K.JITTER_NONE}
COVERAGE_THRESHOLDS = {"coverage": 0, "one_minus_coverage": 1}


def param_values(settings) -> dict:
    """The ``ccl_cloudscape_params`` fields for ``settings`` (defaults of ``ccl_cloudscape_params_default`` for
    everything the settings do not expose), as Python values -- the one source of both the Warp struct and the C
    struct."""
    from ..core.binding import ffi, lib

    f = ffi()
    p = f.new("ccl_cloudscape_params *")
    lib().ccl_cloudscape_params_default(p)
    layer = settings.layer()
    weather_off, detail_off = settings.wind_offsets()
    v = {
        "centre": layer.centre, "r_earth": layer.r_earth, "r_inner": layer.r_inner, "r_outer": layer.r_outer,
        "base_scale_km": p.base_scale_km, "detail_scale_km": p.detail_scale_km,
        "weather_scale_km": p.weather_scale_km, "curl_scale_km": p.curl_scale_km,
        "curl_strength_km": p.curl_strength_km, "weather_offset": weather_off, "detail_offset": detail_off,
        "sigma": settings.sigma_per_km, "sigma_light": settings.sigma_per_km,
        "absorption_base": p.absorption_base, "absorption_precip": p.absorption_precip, "g": settings.g,
        "sun_colour": tuple(p.sun_colour), "ambient_bottom": tuple(p.ambient_bottom),
        "ambient_top": tuple(p.ambient_top), "samples_min": settings.samples_min,
        "samples_max": settings.samples_max, "adaptive_samples": int(settings.adaptive_samples),
        "early_exit": int(settings.early_exit), "exit_eps": p.exit_eps, "light_step_km": p.light_step_km,
        "light_cone_angle": p.light_cone_angle, "light_far_factor": p.light_far_factor,
        "light_detail": int(settings.light_detail), "jitter_mode": JITTERS[settings.jitter],
        "jitter_amount": p.jitter_amount, "gradient_clamp": p.gradient_clamp,
        "detail_direction": p.detail_direction, "ground_colour": tuple(p.ground_colour),
        "coverage_threshold": COVERAGE_THRESHOLDS[settings.coverage_threshold], "beer": int(settings.beer),
        "powder": int(settings.powder),
    }
    for name, value in settings.advanced.items():
        if name not in v or name in ("centre", "r_earth", "r_inner", "r_outer"):
            raise ValueError(f"advanced: unknown parameter {name!r}; known: {', '.join(sorted(v)[4:])}")
        if isinstance(v[name], tuple) != isinstance(value, (tuple, list)) or (
                isinstance(value, (tuple, list)) and len(value) != len(v[name])):
            raise ValueError(f"advanced: {name} must be like {v[name]!r}, got {value!r}")
        v[name] = tuple(value) if isinstance(value, (tuple, list)) else value
    return v


def check_params(values: dict) -> None:
    """Run ccl_cloudscape_check on the parameter values alone (dummy 1-texel textures, a valid sky)."""
    from ..core.binding import ffi, lib

    f, lb = ffi(), lib()
    dummy = np.zeros(4, dtype=np.float32)
    tex = f.new("ccl_cloud_textures *")
    for name in ("base", "detail", "curl", "weather"):
        setattr(tex, name, f.cast("const float *", f.from_buffer("float[]", dummy)))
        setattr(tex, f"{name}_size", 1)
    sky = f.new("ccl_cloudscape_sky *")
    sky.kind = lb.CCL_SKY_GRADIENT
    sky.sun[1] = 1.0
    out = f.new("const char **")
    if lb.ccl_cloudscape_check(c_params(values), tex, sky, out) != 0:
        name = f.string(out[0]).decode()
        raise ValueError(f"{name} is out of range (ccl_cloudscape_check), got {values.get(name)!r}")


def c_params(values: dict):
    from ..core.binding import ffi

    p = ffi().new("ccl_cloudscape_params *")
    p.layer.centre.x, p.layer.centre.y, p.layer.centre.z = values["centre"]
    p.layer.r_earth, p.layer.r_inner, p.layer.r_outer = values["r_earth"], values["r_inner"], values["r_outer"]
    for name, v in values.items():
        if name in ("centre", "r_earth", "r_inner", "r_outer"):
            continue
        if isinstance(v, (tuple, list)):
            arr = getattr(p, name)
            for i, x in enumerate(v):
                arr[i] = x
        else:
            setattr(p, name, v)
    return p
