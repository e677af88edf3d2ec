"""The host side of the noise-texture generator (vc §2.3.3, §4.3.1; cclouds/texgen.h): whole textures from a settings
dataclass (:func:`generate`, the tile kernels of :mod:`pywarp.kernels.texgen` through a TileLauncher, or
``ccl_texgen_<kind>``), the C settings structs, the NumPy evaluators of the settings check and of the trilinear
sampler, and the evaluators the registry names for vc-A11, vc-A12 and vc-A13. :mod:`pywarp.clouds.textures` adds the
generator interface and the cache.
"""
from __future__ import annotations

import math
from dataclasses import asdict, is_dataclass

import numpy as np
import warp as wp

from ..core.registry import Equation
from ..kernels.noise import COMBINATIONS, perm_array
from ..kernels.texgen import (BASE_SHAPE_FIELDS, base_shape_kernel, curl_noise_kernel, detail_shape_kernel, is_pow2,
                              sample_kernel, settings_code_kernel, weather_map_kernel)


def _texture_call(kind: str, name: str, impl: str, device):
    """``fn(settings)`` with a settings object of ``kind`` (the dataclasses of :mod:`pywarp.clouds.settings`,
    validated when built) -> float32 array of ``settings.shape``: the evaluator of a whole-texture entry."""
    def call(settings):
        if not (is_dataclass(settings) and hasattr(settings, "shape")):
            raise TypeError(f"{name}(): settings must be a texture settings object "
                            f"(pywarp.clouds.settings), got {type(settings).__name__}")
        return generate(kind, settings, impl=impl, device=device)

    return call


def curl_noise_warp(eq: Equation, device=None):
    """The evaluator of vc-A11 (a whole texture, not element-wise) on Warp."""
    return _texture_call("curl_noise", "texgen_curl_noise", "warp", device)


def curl_noise_c(eq: Equation):
    """The C evaluator of vc-A11 (``ccl_texgen_curl_noise``)."""
    return _texture_call("curl_noise", "texgen_curl_noise", "c", None)


def weather_map_warp(eq: Equation, device=None):
    """The evaluator of vc-A12 (a whole texture, not element-wise) on Warp."""
    return _texture_call("weather_map", "texgen_weather_map", "warp", device)


def weather_map_c(eq: Equation):
    """The C evaluator of vc-A12 (``ccl_texgen_weather_map``)."""
    return _texture_call("weather_map", "texgen_weather_map", "c", None)


def _settings_check(impl: str, device):
    """``fn(settings)`` -> the name of the first invalid field of a base-shape settings object in the order of the C
    check, or None (vc-A13). The dataclass itself refuses invalid values when built, so this checks one built with
    ``dataclasses.replace`` or a look-alike (any object with the fields)."""
    def call(settings):
        v = {f: getattr(settings, f) for f in ("size", "perlin_octaves", "perlin_frequency", "worley_cells",
                                                "worley_weights", "combination", "gamma")}
        if impl == "c":
            from ..core.binding import ffi, lib

            out = ffi().new("const char **")
            st = settings_struct("base_shape", {**v, "seed": getattr(settings, "seed", 0)})
            if lib().ccl_texgen_base_shape_settings_check(st, out) == 0:
                return None
            return ffi().string(out[0]).decode()
        w0, w1, w2 = v["worley_weights"]
        comb = COMBINATIONS.get(v["combination"], -1) if isinstance(v["combination"], str) else -1
        code = int(base_shape_settings_codes(v["size"], v["perlin_octaves"], v["perlin_frequency"],
                                             v["worley_cells"], w0, w1, w2, comb, v["gamma"], device=device))
        return None if code == 0 else BASE_SHAPE_FIELDS[code - 1]

    return call


def settings_check_warp(eq: Equation, device=None):
    """The evaluator of vc-A13 (a settings object, not element-wise): :func:`base_shape_settings_codes` on Warp."""
    return _settings_check("warp", device)


def settings_check_c(eq: Equation):
    """The C evaluator of vc-A13 (``ccl_texgen_base_shape_settings_check``)."""
    return _settings_check("c", None)


_C_TYPES = {"base_shape": "ccl_base_shape_settings", "detail_shape": "ccl_detail_shape_settings",
            "curl_noise": "ccl_curl_noise_settings", "weather_map": "ccl_weather_map_settings"}


def settings_struct(kind: str, values: dict):
    """A cffi ``ccl_<kind>_settings *`` holding ``values`` (dataclass field -> value), without Python validation:
    a value that does not fit its C type raises ValueError/TypeError naming the field."""
    from ..core.binding import ffi

    f = ffi()
    st = f.new(f"{_C_TYPES[kind]} *")
    for name, v in values.items():
        try:
            if name == "worley_weights":
                w = list(v)
                if len(w) != 3:
                    raise ValueError(f"worley_weights must hold 3 weights, got {len(w)}")
                for i in range(3):
                    st.worley_weights[i] = w[i]
            elif name == "combination":
                if v not in COMBINATIONS:
                    raise ValueError(f"combination must be one of {', '.join(map(repr, COMBINATIONS))}, got {v!r}")
                st.combination = COMBINATIONS[v]
            else:
                setattr(st, name, v)
        except OverflowError:
            raise ValueError(f"{name} is out of range of its C type, got {v!r}") from None
        except TypeError as exc:
            raise TypeError(f"{name}: {exc}") from None
    return st


def generate(kind: str, s, impl: str = "warp", device: str | None = None, launcher=None) -> np.ndarray:
    """Texture ``kind`` ('base_shape', 'detail_shape', 'curl_noise', 'weather_map') of the settings dataclass ``s``
    (validated when it was built; pywarp.clouds.settings) as a new float32 array of ``s.shape``. ``impl="warp"``:
    the tile kernels through ``launcher`` (default the process-wide TileLauncher of ``device``: row bands on every
    core); ``impl="c"``: ``ccl_texgen_<kind>``, one thread. pywarp.clouds.textures adds the generator interface and
    the cache."""
    if kind not in _C_TYPES:
        raise ValueError(f"kind must be one of {', '.join(map(repr, _C_TYPES))}, got {kind!r}")
    if impl == "c":
        return _generate_c(kind, s)
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return _generate_warp(kind, s, device, launcher)


def _generate_c(kind: str, s) -> np.ndarray:
    from ..core.binding import ffi, lib, status_error

    st = settings_struct(kind, asdict(s))
    out = np.empty(s.shape, dtype=np.float32)
    status = getattr(lib(), f"ccl_texgen_{kind}")(st, ffi().from_buffer("float[]", out), out.size)
    status_error(status, f"ccl_texgen_{kind}")
    return out


def _generate_warp(kind: str, s, device, launcher) -> np.ndarray:
    from ..core.runtime import launcher as shared_launcher

    lau = launcher if launcher is not None else shared_launcher(device)
    dev = lau.device
    n = s.size
    if kind == "base_shape":
        w0, w1, w2 = s.worley_weights
        out = wp.empty((n, n, n), dtype=wp.vec4, device=dev)
        lau.launch(base_shape_kernel, n * n, n,
                   [n, s.seed, s.perlin_octaves, s.perlin_frequency, s.worley_cells, w0, w1, w2, s.gamma,
                    COMBINATIONS[s.combination], perm_array(s.seed, dev)], [out])
    elif kind == "detail_shape":
        w0, w1, w2 = s.worley_weights
        out = wp.empty((n, n, n), dtype=wp.vec3, device=dev)
        lau.launch(detail_shape_kernel, n * n, n, [n, s.seed, s.worley_cells, w0, w1, w2, s.gamma], [out])
    elif kind == "curl_noise":
        out = wp.empty((n, n), dtype=wp.vec2, device=dev)
        lau.launch(curl_noise_kernel, n, n, [n, s.frequency, s.fd_step, perm_array(s.seed, dev)], [out])
    else:
        out = wp.empty((n, n), dtype=wp.vec4, device=dev)
        seeds = [(s.seed + i) & 0xFFFFFFFF for i in range(3)]
        lau.launch(weather_map_kernel, n, n,
                   [n, s.seed, s.perlin_frequency, s.perlin_octaves, s.perlin_contrast, s.worley_cells,
                    s.worley_octaves, COMBINATIONS[s.combination], s.coverage, s.precipitation, s.cloud_type,
                    s.cloud_type_variation, *(perm_array(x, dev) for x in seeds)], [out])
    return np.array(out.numpy(), dtype=np.float32, copy=True).reshape(s.shape)


def base_shape_settings_codes(size, perlin_octaves, perlin_frequency, worley_cells, worley_w0, worley_w1, worley_w2,
                              combination, gamma, device=None) -> np.ndarray:
    """Evaluate :func:`pywarp.kernels.texgen.texgen_base_shape_settings_code` on NumPy arrays (no validation: any
    values; int32/float32)."""
    from ..core.runtime import resolve_device

    dev = resolve_device(device)
    ints = [np.asarray(v, dtype=np.int32) for v in (size, perlin_octaves, perlin_frequency, worley_cells)]
    flts = [np.asarray(v, dtype=np.float32) for v in (worley_w0, worley_w1, worley_w2)]
    comb, gam = np.asarray(combination, dtype=np.int32), np.asarray(gamma, dtype=np.float32)
    shape = np.broadcast_shapes(*(a.shape for a in (*ints, *flts, comb, gam)))
    flat = [np.ascontiguousarray(np.broadcast_to(a, shape).ravel()) for a in (*ints, *flts, comb, gam)]
    n = int(math.prod(shape))
    out = wp.zeros(max(n, 1), dtype=wp.int32, device=dev)
    if n:
        wp.launch(settings_code_kernel, dim=n, inputs=[wp.array(a, device=dev) for a in flat],
                  outputs=[out], device=dev)
    return out.numpy()[:n].reshape(shape)


def sample_trilinear_wrap_np(tex, p, impl: str = "warp", device=None) -> np.ndarray:
    """Sample an RGBA volume ``tex`` of shape (n, n, n, 4) (n a power of two, indexed [z, y, x, c]) at texture
    coordinates ``p`` of shape (..., 3) with :func:`pywarp.kernels.texgen.texgen_sample_trilinear_wrap`
    (``impl="warp"``) or ``ccl_texgen_sample_trilinear_wrap`` (``impl="c"``). Returns float32 (..., 4)."""
    tex = np.ascontiguousarray(tex, dtype=np.float32)
    if tex.ndim != 4 or tex.shape[3] != 4 or not (tex.shape[0] == tex.shape[1] == tex.shape[2]):
        raise ValueError(f"tex must have shape (n, n, n, 4), got {tex.shape}")
    n = tex.shape[0]
    if not is_pow2(n):
        raise ValueError(f"tex size must be a power of two, got {n}")
    p = np.asarray(p, dtype=np.float32)
    if p.shape[-1:] != (3,):
        raise ValueError(f"p must have shape (..., 3), got {p.shape}")
    if not np.all(np.isfinite(p)) or np.any(np.abs(p.astype(np.float64)) * n >= 2.0 ** 23):
        raise ValueError("p must be finite with |p| * size < 2^23")
    flat = np.ascontiguousarray(p.reshape(-1, 3))
    if impl == "c":
        from ..core.binding import ffi, lib

        f, lb = ffi(), lib()
        buf = f.from_buffer("float[]", tex)
        outs = f.new("float[4]")
        res = np.empty((flat.shape[0], 4), dtype=np.float32)
        for k, (x, y, z) in enumerate(flat.tolist()):
            lb.ccl_texgen_sample_trilinear_wrap(buf, n - 1, x, y, z, outs, outs + 1, outs + 2, outs + 3)
            res[k] = (outs[0], outs[1], outs[2], outs[3])
    elif impl == "warp":
        from ..core.runtime import resolve_device

        dev = resolve_device(device)
        t = wp.array(tex, dtype=wp.vec4, device=dev)
        out = wp.empty(max(flat.shape[0], 1), dtype=wp.vec4, device=dev)
        if flat.shape[0]:
            wp.launch(sample_kernel, dim=flat.shape[0], inputs=[t, n - 1, wp.array(flat, dtype=wp.vec3, device=dev)],
                      outputs=[out], device=dev)
        res = out.numpy()[:flat.shape[0]]
    else:
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return res.reshape(p.shape[:-1] + (4,))
