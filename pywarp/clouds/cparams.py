"""The ``ccl_cloudscape_params`` values of a cloudscape's settings: one source of both the Warp struct and the C
struct, and the C check of those values (``ccl_cloudscape_check``)."""
from __future__ import annotations

import math

import numpy as np

from ..kernels import cloudscape as K

JITTERS = {"tilt": K.JITTER_TILT, "offset": K.JITTER_OFFSET, "none": K.JITTER_NONE}
COVERAGE_THRESHOLDS = {"coverage": 0, "one_minus_coverage": 1}
LIGHTINGS = {"thesis": K.LIGHTING_THESIS, "sky": K.LIGHTING_SKY}
MARCHES = {"fast": K.MARCH_FAST, "textbook": K.MARCH_TEXTBOOK}


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
        "early_exit": int(settings.early_exit), "exit_eps": p.exit_eps, "exit_fill": p.exit_fill,
        "light_interp": p.light_interp, "light_step_km": p.light_step_km,
        "light_cone_angle": p.light_cone_angle, "light_far_factor": p.light_far_factor,
        "light_detail": int(settings.light_detail), "jitter_mode": JITTERS[settings.jitter],
        "jitter_amount": p.jitter_amount, "gradient_clamp": p.gradient_clamp,
        "detail_direction": p.detail_direction, "ground_colour": tuple(p.ground_colour),
        "coverage_threshold": COVERAGE_THRESHOLDS[settings.coverage_threshold], "beer": int(settings.beer),
        "powder": int(settings.powder), "lod": int(settings.lod), "lod_bias": settings.lod_bias,
        "refine_step_km": settings.refine_step_km, "refine_max": settings.refine_max,
        "weather_detile": int(settings.weather_detile), "march": MARCHES[settings.march],
    }
    # lighting: 'thesis' is the thesis's model entirely (its constants, one octave, one HG lobe); 'sky' takes the
    # multiple-scattering and silver-lining settings
    thesis = settings.lighting == "thesis"
    v.update({
        "lighting": LIGHTINGS[settings.lighting], "sun_intensity": settings.sun_intensity,
        "turbidity": settings.turbidity, "ambient_bottom_ratio": p.ambient_bottom_ratio,
        "ambient_ground": tuple(p.ambient_ground), "ground_albedo": tuple(settings.ground_albedo),
        "aerial_km": settings.aerial_km, "aerial_height_km": settings.aerial_height_km, "ms_octaves": 1 if thesis else settings.ms_octaves, "ms_a": p.ms_a,
        "ms_b": p.ms_b, "ms_c": p.ms_c, "silver_g": settings.silver_g,
        "silver_weight": 0.0 if thesis else settings.silver_weight,
    })
    for name, value in settings.advanced.items():
        if name not in v or name in ("centre", "r_earth", "r_inner", "r_outer"):
            raise ValueError(f"advanced: unknown parameter {name!r}; known: {', '.join(sorted(v)[4:])}")
        if isinstance(v[name], tuple) != isinstance(value, (tuple, list)) or (
                isinstance(value, (tuple, list)) and len(value) != len(v[name])):
            raise ValueError(f"advanced: {name} must be like {v[name]!r}, got {value!r}")
        if isinstance(value, (tuple, list)):
            v[name] = tuple(_c_float(f"advanced: {name}", x) for x in value)
        elif isinstance(v[name], int):
            v[name] = _c_int(f"advanced: {name}", value)
        else:
            v[name] = _c_float(f"advanced: {name}", value)
    return v


_F32_MAX = float(np.finfo(np.float32).max)


def _c_int(name: str, value) -> int:
    """A value for a C ``int`` field, validated before any conversion (no bool, no 3.5, no OverflowError)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    if not -(2 ** 31) <= int(value) <= 2 ** 31 - 1:
        raise ValueError(f"{name} must be in [-2147483648, 2147483647] (int32), got {value!r}")
    return int(value)


def _c_float(name: str, value) -> float:
    """A value for a C ``float`` field: a finite number within the float32 range."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number, got {value!r}")
    x = float(value)
    if not math.isfinite(x) or abs(x) > _F32_MAX:
        raise ValueError(f"{name} must be finite and within the float32 range, got {value!r}")
    return x


#: The valid values of the ``ccl_cloudscape_check`` fields checked against a plain range (as the check states them);
#: the other fields are bounded by the texture coordinates they produce. For the error message only.
FIELD_RANGES = {
    "sigma": "> 0 and finite", "sigma_light": ">= 0 and finite", "absorption_base": ">= 0 and finite",
    "absorption_precip": ">= 0 and finite", "g": "in (-1, 1)", "sun_colour": ">= 0 and finite per channel",
    "ambient_bottom": ">= 0 and finite per channel", "ambient_top": ">= 0 and finite per channel",
    "ground_colour": ">= 0 and finite per channel", "samples_min": "in [1, samples_max]",
    "samples_max": "in [samples_min, 4096]", "exit_eps": "in (0, 1)", "exit_fill": "0 or 1",
    "light_interp": ">= 0 and finite", "light_step_km": "> 0 and finite",
    "light_cone_angle": "in [0, pi/2) rad",
    "light_far_factor": "in [1, 10^6] (CCL_CLOUDSCAPE_MAX_LIGHT_FAR_FACTOR), with light_far_factor x 5 x "
                        "light_step_km <= 10^6 km (CCL_CLOUDSCAPE_MAX_LIGHT_KM)",
    "jitter_mode": "0 (tilt), 1 (offset) or 2 (none)", "jitter_amount": ">= 0 and finite",
    "detail_direction": "0 or 1", "coverage_threshold": "0 or 1", "beer": "0 or 1", "powder": "0 or 1",
    "lighting": "0 (thesis) or 1 (sky)", "sun_intensity": ">= 0 and finite", "ambient_bottom_ratio": "in [0, 1]",
    "ambient_ground": ">= 0 and finite per channel", "ground_albedo": "in [0, 1] per channel",
    "aerial_km": ">= 0 and finite", "aerial_height_km": ">= 0 and finite",
    "ms_octaves": f"in [1, {K.MAX_MS_OCTAVES}]", "ms_a": "in [0, 1]", "ms_b": "in [0, 1]", "ms_c": "in [0, 1]",
    "silver_g": "in (-1, 1)", "silver_weight": "in [0, 1]", "lod": "0 or 1", "weather_detile": "0 or 1",
    "lod_bias": "in [-4, 4]", "refine_step_km": ">= 0 and finite", "refine_max": "in [1, 64]",
}


def check_params(values: dict, sizes: dict | None = None) -> None:
    """Run ccl_cloudscape_check on the parameter values (a valid sky; textures of edge ``sizes[name]`` for name in
    base, detail, curl, weather, default 1: the check bounds the texture coordinates, which grow with the edge, and
    reads no texel, so a 4-float dummy stands for every texture). Raises ValueError naming the first bad field."""
    from ..core.binding import ffi, lib

    f, lb = ffi(), lib()
    dummy = np.zeros(4, dtype=np.float32)
    tex = f.new("ccl_cloud_textures *")
    for name in ("base", "detail", "curl", "weather"):
        setattr(tex, name, f.cast("const float *", f.from_buffer("float[]", dummy)))
        setattr(tex, f"{name}_size", int((sizes or {}).get(name, 1)))
    sky = f.new("ccl_cloudscape_sky *")
    sky.kind = lb.CCL_SKY_GRADIENT
    sky.sun[1] = 1.0
    out = f.new("const char **")
    if lb.ccl_cloudscape_check(c_params(values), tex, sky, out) != 0:
        name = f.string(out[0]).decode()
        shown = values.get(name, values.get(name.split(".")[0]))
        if name in FIELD_RANGES:
            raise ValueError(f"{name} is out of range: it must be {FIELD_RANGES[name]} (ccl_cloudscape_check), "
                             f"got {shown!r}")
        raise ValueError(f"{name} is out of range (ccl_cloudscape_check: with the texture sizes "
                         f"{dict(sizes or {})}, texture coordinates must stay below 2^23 texels), got {shown!r}")


def texture_sizes(settings) -> dict:
    """The texture edges of ``settings`` by ``ccl_cloud_textures`` field name."""
    return {"base": settings.base_size, "detail": settings.detail_size, "curl": settings.curl_size,
            "weather": settings.weather_size}


def checked_values(settings) -> dict:
    """:func:`param_values` of ``settings``, checked by ccl_cloudscape_check at the settings' texture sizes (the
    texture-coordinate bound depends on them); ValueError names the first bad field."""
    values = param_values(settings)
    check_params(values, texture_sizes(settings))
    return values


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
