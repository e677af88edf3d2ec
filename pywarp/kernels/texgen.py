"""Noise-texture generator (vc §2.3.3, §4.3.1) -- Warp twins of ``cclouds/texgen.h``.

* :func:`texgen_gamma` -- vc-4.6, ``C = C^(1/gamma)``.
* :func:`texgen_base_shape_texel` -- one texel of the 128^3 RGBA base-shape texture (vc-A9, vc-A8),
  :func:`texgen_detail_shape_texel` -- one texel of the 32^3 RGB detail texture (vc-A10),
  :func:`texgen_curl_noise_texel` -- one texel of the generated 2-D curl-noise texture (vc-A11),
  :func:`texgen_weather_map_texel` -- one texel of the procedural weather map (vc-A12),
  :func:`texgen_base_shape_settings_code` -- the settings validation of vc-A13 (the C
  ``ccl_texgen_base_shape_settings_check``).
* :func:`texgen_sample_trilinear_wrap` -- the renderer's trilinear sampler of a periodic power-of-two RGBA volume
  (``wp.array3d(dtype=wp.vec4)`` indexed ``[z, y, x]``) with bit-mask wrap, exactly shift-invariant.
* Tile kernels (first parameter ``row0``, launched through :class:`pywarp.core.runtime.TileLauncher`; for a 3-D texture
  row = z * size + y, so a 128^3 volume is 16384 rows x 128 columns).

The readings chosen where the thesis is silent are stated in the C header (``cclouds/texgen.h``) and repeated here:

* texel (ix, iy, iz) sits at u = (ix + 0.5) / size; noise is evaluated at u times an integer frequency with the noise
  period equal to that frequency, so every texture is exactly periodic (``texel(ix + size) == texel(ix)``);
* four inverse-Worley layers W_j (cells ``worley_cells * 2^j``, seed ``seed + j``) fill three channels by a sliding
  window (vc-A9's open mapping, spec §7 item 24; Hillaire's TileableVolumeNoise does the same):
  channel k = sum_{j, k+j <= 3} w_j W_{k+j} / sum w_j -> G = fBm(W0, W1, W2), B = fBm(W1, W2, W3), A = fBm(W2, W3);
* R = noise_perlin_worley(P, W = G, combination), P = clamp(0.5 fbm_perlin + 0.5, 0, 1) (vc-A8);
* every channel is clamped to [0, 1], then gamma-corrected (vc-4.6);
* weather map: R coverage, G precipitation (the spec's reading of the "blue twice" erratum), B cloud type, A = 0.

The whole-texture generation, the C settings structs and the NumPy evaluators are :mod:`pywarp.clouds.texgen`; the
generator classes, settings dataclasses and the cache are in :mod:`pywarp.clouds.textures`.
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.registry import Arg, declare
from .common import clamp01
from .noise import (COMBINATION, PW_AVERAGE, PW_THESIS, noise_curl2, noise_fbm_perlin3, noise_fbm_worley3,
                    noise_perlin_worley, noise_worley3, perm_array)

# Field order of the settings validation codes (1-based; 0 = valid), as checked by ccl_texgen_base_shape_settings_check.
BASE_SHAPE_FIELDS = ("size", "perlin_octaves", "perlin_frequency", "worley_cells", "worley_weights", "combination",
                     "gamma")
MIN_SIZE = 4  # CCL_TEXGEN_MIN_SIZE
MAX_SIZE_3D = 512  # CCL_TEXGEN_MAX_SIZE_3D
MAX_SIZE_2D = 8192  # CCL_TEXGEN_MAX_SIZE_2D
MAX_OCTAVES = 8  # CCL_TEXGEN_MAX_OCTAVES
MAX_LATTICE = 4096  # CCL_TEXGEN_MAX_LATTICE
_MIN_SIZE = wp.constant(MIN_SIZE)
_MAX_SIZE_3D = wp.constant(MAX_SIZE_3D)
_MAX_OCTAVES = wp.constant(MAX_OCTAVES)
_MAX_LATTICE = wp.constant(MAX_LATTICE)


# --- helpers (mirror the C statics of texgen.c) -----------------------------------------------------------------------

@wp.func
def _texcoord(i: int, size: int) -> float:
    """Centre of texel i: (i mod size + 0.5) / size (size a power of two). Reducing i first keeps u * frequency the
    same float for i and i + k size, so a single texel is exactly periodic for any frequency (as in C)."""
    return (float(i & (size - 1)) + 0.5) / float(size)


@wp.func
def _worley_layers(u: float, v: float, w: float, cells: int, seed: wp.uint32) -> wp.vec4:
    """The four inverse-Worley layers: cells * 2^j cells per texture, seed + j."""
    return wp.vec4(noise_worley3(u, v, w, cells, seed, 0, 1),
                   noise_worley3(u, v, w, cells * 2, seed + wp.uint32(1), 0, 1),
                   noise_worley3(u, v, w, cells * 4, seed + wp.uint32(2), 0, 1),
                   noise_worley3(u, v, w, cells * 8, seed + wp.uint32(3), 0, 1))


@wp.func
def _sliding_fbm(layers: wp.vec4, w0: float, w1: float, w2: float) -> wp.vec3:
    """channel k = sum_{j, k+j <= 3} w_j W_{k+j} / sum w_j, clamped to [0, 1] (same summation order as C)."""
    c0 = (w0 * layers[0] + w1 * layers[1] + w2 * layers[2]) / (w0 + w1 + w2)
    c1 = (w0 * layers[1] + w1 * layers[2] + w2 * layers[3]) / (w0 + w1 + w2)
    c2 = (w0 * layers[2] + w1 * layers[3]) / (w0 + w1)
    return wp.vec3(clamp01(c0), clamp01(c1), clamp01(c2))


@wp.func
def _perlin01(u: float, v: float, w: float, octaves: int, frequency: int, perm: wp.array(dtype=wp.int32),
              gain: float) -> float:
    """Perlin fBm mapped to [0, 1]: clamp(gain fbm + 0.5, 0, 1); period = frequency cells = one texture."""
    p = noise_fbm_perlin3(u, v, w, octaves, float(frequency), perm, frequency)
    return clamp01(gain * p + 0.5)


@wp.func
def _coverage_shape(n: float, c: float) -> float:
    """clamp(remap(n, 1 - c, 1, 0, 1), 0, 1) for c > 0, 0 for c <= 0."""
    if c <= 0.0:
        return 0.0
    return clamp01((n - (1.0 - c)) / c)


# --- argument domains, checks and samples of the declared entries --------------------------------------------------

_REF_SV = "A. Schneider & N. Vos, The real-time volumetric cloudscapes of Horizon: Zero Dawn, SIGGRAPH 2015 course"
_REF_GPU7 = "A. Schneider, Real-Time Volumetric Cloudscapes, GPU Pro 7, 2016"
_REF_HILLAIRE = "S. Hillaire, TileableVolumeNoise, https://github.com/sebh/TileableVolumeNoise, 2016"
_REF_BRIDSON = "R. Bridson, J. Hourihan & M. Nordenstam, Curl-Noise for Procedural Fluid Flow, SIGGRAPH 2007"

def _icoord(name):
    # any int32: the coordinate is reduced modulo size before the float conversion (exact for every frequency)
    return Arg(name, f"integer texel coordinate {name[-1]} (any int32: the texture is periodic)", lo=-2 ** 31,
               hi=2 ** 31 - 1, dtype="int32")


def _check_size_3d(size, **_):
    bad = ~is_pow2(size)
    if np.any(bad):
        raise ValueError(f"size must be a power of two in [{MIN_SIZE}, {MAX_SIZE_3D}], "
                         f"got {int(np.asarray(size)[bad].flat[0])}")


def _check_lattice(name, base, octaves):
    top = np.asarray(base, dtype=np.int64) * (2 ** (np.asarray(octaves, dtype=np.int64) - 1))
    if np.any(top > MAX_LATTICE):
        raise ValueError(f"{name} * 2^(octaves - 1) must be <= {MAX_LATTICE}, got {int(np.max(top))}")


def _check_base_texel(size, perlin_octaves, perlin_frequency, **_):
    _check_size_3d(size)
    _check_lattice("perlin_frequency", perlin_frequency, perlin_octaves)


_SIZE3 = Arg("size", f"texture edge, a power of two in [{MIN_SIZE}, {MAX_SIZE_3D}]", lo=MIN_SIZE, hi=MAX_SIZE_3D,
             dtype="int32")
_SEED = Arg("seed", "uint32 seed (Perlin: permutation of the seed, 0 = Perlin's reference; Worley layer j: seed + j)",
            lo=0, hi=4294967295, dtype="uint32")
_CELLS = Arg("worley_cells", "cells per texture of the lowest inverse-Worley layer (layers cells * 1, 2, 4, 8)", lo=1,
             hi=MAX_LATTICE // 8, dtype="int32")
_W0 = Arg("worley_w0", "fBm weight of the lowest layer in each channel's window (> 0)", lo=0.0, lo_open=True)
_W1 = Arg("worley_w1", "fBm weight of the second layer (>= 0)", lo=0.0)
_W2 = Arg("worley_w2", "fBm weight of the third layer (>= 0)", lo=0.0)
_GAMMA = Arg("gamma", "gamma of vc-4.6 (> 0; 1 = identity)", lo=0.0, lo_open=True)


def _texel_common(rng, n) -> dict:
    """Shared valid samples of the texel entries: power-of-two sizes, periodic coordinates, weights, gamma."""
    return {"ix": rng.integers(-300, 300, n).astype(np.int32), "iy": rng.integers(-300, 300, n).astype(np.int32),
            "iz": rng.integers(-300, 300, n).astype(np.int32),
            "size": (2 ** rng.integers(2, 10, n)).astype(np.int32),
            "seed": rng.integers(0, 3, n).astype(np.uint32),  # a few distinct seeds: one launch per seed
            "worley_cells": rng.integers(1, 9, n).astype(np.int32),
            "worley_w0": rng.uniform(0.1, 1.0, n).astype(np.float32),
            "worley_w1": rng.uniform(0.0, 1.0, n).astype(np.float32),
            "worley_w2": rng.uniform(0.0, 1.0, n).astype(np.float32),
            "gamma": rng.uniform(0.3, 3.0, n).astype(np.float32)}


def _base_texel_samples(rng, n):
    """Valid samples of vc-A9: perlin_frequency * 2^(perlin_octaves - 1) <= 4096. The first has one octave and a
    frequency <= 32, so every edge of perlin_octaves and perlin_frequency stays valid when set alone."""
    octaves = rng.integers(1, 5, n).astype(np.int32)
    octaves[0] = 1
    freq = rng.integers(1, 33, n).astype(np.int32)
    return {**_texel_common(rng, n), "perlin_octaves": octaves, "perlin_frequency": freq}


def _detail_texel_samples(rng, n):
    """Valid samples of vc-A10 (power-of-two sizes)."""
    c = _texel_common(rng, n)
    return {k: c[k] for k in ("ix", "iy", "iz", "size", "seed", "worley_cells", "worley_w0", "worley_w1",
                              "worley_w2", "gamma")}


@wp.struct
class SeedTables:
    """What the base-shape texel needs of its seed: the seed itself (Worley layers seed + j) and its Perlin
    permutation table (``noise.perm_array(seed)``), computed once per distinct seed by the evaluator."""

    seed: wp.uint32
    perm: wp.array(dtype=wp.int32)


def seed_tables(seed: int, device=None) -> SeedTables:
    """The :class:`SeedTables` of ``seed`` on ``device`` (the derived parameter of vc-A9)."""
    t = SeedTables()
    t.seed = wp.uint32(int(seed))
    t.perm = perm_array(int(seed), device)
    return t


# --- vc-4.6 -----------------------------------------------------------------------------------------------------------

# powf of two libms (glibc, Warp's runtime), each within 1 ulp of the exact value: <= 2 ulp apart (the default bound)
@declare("vc-4.6", c="ccl_texgen_gamma", args=(Arg("c", "generated noise value C", lo=0.0, hi=1.0), _GAMMA),
         outputs=("C",),
         summary="Gamma correction of generated noise, C = C^(1/gamma), applied to every channel of the base and "
                 "detail textures (a shaping step, not display gamma); gamma > 1 brightens, 1 is the identity (the "
                 "default of the settings: the thesis gives none).")
@wp.func
def texgen_gamma(c: float, gamma: float) -> float:
    """vc-4.6: gamma correction of generated noise, C = C^(1/gamma) (gamma > 0; 1 = identity, > 1 brightens)."""
    return wp.pow(c, 1.0 / gamma)


# --- texels -----------------------------------------------------------------------------------------------------------

@wp.func
def _base_shape_rgba(ix: int, iy: int, iz: int, size: int, seed: wp.uint32, perlin_octaves: int,
                     perlin_frequency: int, worley_cells: int, worley_w0: float, worley_w1: float, worley_w2: float,
                     gamma: float, combination: int, perm: wp.array(dtype=wp.int32)) -> wp.vec4:
    """vc-A9: RGBA texel (ix, iy, iz) of the base-shape texture; ``perm`` = the permutation table of ``seed``
    (``noise.perm_array(seed)``; the C twin builds it from the seed). The tile kernel calls this form."""
    u = _texcoord(ix, size)
    v = _texcoord(iy, size)
    w = _texcoord(iz, size)
    ch = _sliding_fbm(_worley_layers(u, v, w, worley_cells, seed), worley_w0, worley_w1, worley_w2)
    p = _perlin01(u, v, w, perlin_octaves, perlin_frequency, perm, 0.5)
    r = noise_perlin_worley(p, ch[0], combination)  # vc-A8
    return wp.vec4(texgen_gamma(clamp01(r), gamma), texgen_gamma(ch[0], gamma), texgen_gamma(ch[1], gamma),
                   texgen_gamma(ch[2], gamma))


@declare("vc-A9", c="ccl_texgen_base_shape_texel",
         args=(_icoord("ix"), _icoord("iy"), _icoord("iz"), _SIZE3, _SEED,
               Arg("perlin_octaves", "Perlin fBm octaves", lo=1, hi=MAX_OCTAVES, dtype="int32"),
               Arg("perlin_frequency", "Perlin lattice cells per texture (octave 0); period = frequency", lo=1,
                   hi=MAX_LATTICE, dtype="int32"),
               _CELLS, _W0, _W1, _W2, _GAMMA),
         options=(COMBINATION,), outputs=("R", "G", "B", "A"), check=_check_base_texel,
         derived={"tables": ("seed", seed_tables)}, samples=_base_texel_samples,
         summary="One texel (ix, iy, iz) of the base-shape texture (128^3 RGBA in the thesis), texture coordinate "
                 "(i + 0.5)/size. G, B, A: four inverse-Worley layers (cells worley_cells * 2^j, seed + j) mapped to "
                 "three channels by a sliding fBm window (G = W0..W2, B = W1..W3, A = W2..W3 renormalised; the thesis "
                 "leaves the mapping open). R: noise_perlin_worley(P, G, combination) with P = clamp(0.5 fBm_Perlin "
                 "+ 0.5) (vc-A8; default 'thesis' = remap(P, 0, 1, W, 1)^2). All channels clamped to [0, 1], then "
                 "gamma (vc-4.6). Exactly periodic: texel(i + size) == texel(i). Whole texture: "
                 "pywarp.clouds.textures (BasicTextureGenerator.base_shape, ccl_texgen_base_shape).",
         references=(_REF_SV, _REF_GPU7, _REF_HILLAIRE))
@wp.func
def texgen_base_shape_texel(ix: int, iy: int, iz: int, size: int, tables: SeedTables, perlin_octaves: int,
                            perlin_frequency: int, worley_cells: int, worley_w0: float, worley_w1: float,
                            worley_w2: float, gamma: float,
                            combination: int) -> tuple[float, float, float, float]:
    """vc-A9: (R, G, B, A) of texel (ix, iy, iz); ``tables`` = the seed and its permutation table."""
    t = _base_shape_rgba(ix, iy, iz, size, tables.seed, perlin_octaves, perlin_frequency, worley_cells, worley_w0,
                         worley_w1, worley_w2, gamma, combination, tables.perm)
    return t[0], t[1], t[2], t[3]


@wp.func
def _detail_shape_rgb(ix: int, iy: int, iz: int, size: int, seed: wp.uint32, worley_cells: int, worley_w0: float,
                      worley_w1: float, worley_w2: float, gamma: float) -> wp.vec3:
    """vc-A10: RGB texel of the detail texture (inverse-Worley fBm of increasing frequency); the tile kernel's form."""
    u = _texcoord(ix, size)
    v = _texcoord(iy, size)
    w = _texcoord(iz, size)
    ch = _sliding_fbm(_worley_layers(u, v, w, worley_cells, seed), worley_w0, worley_w1, worley_w2)
    return wp.vec3(texgen_gamma(ch[0], gamma), texgen_gamma(ch[1], gamma), texgen_gamma(ch[2], gamma))


@declare("vc-A10", c="ccl_texgen_detail_shape_texel",
         args=(_icoord("ix"), _icoord("iy"), _icoord("iz"), _SIZE3, _SEED, _CELLS, _W0, _W1, _W2, _GAMMA),
         outputs=("R", "G", "B"), check=lambda size, **_: _check_size_3d(size), samples=_detail_texel_samples,
         summary="One texel of the detail (erosion) texture (32^3 RGB in the thesis): R, G, B = inverse-Worley fBm "
                 "of increasing frequency by the same sliding window as vc-A9 (R = W0..W2, G = W1..W3, B = W2..W3), "
                 "clamped, gamma-corrected (vc-4.6). With weights 1, 1/2, 1/4 a channel equals noise_fbm_worley3 "
                 "(vc-A6) of three octaves. Whole texture: BasicTextureGenerator.detail_shape / "
                 "ccl_texgen_detail_shape.",
         references=(_REF_SV, _REF_HILLAIRE))
@wp.func
def texgen_detail_shape_texel(ix: int, iy: int, iz: int, size: int, seed: wp.uint32, worley_cells: int,
                              worley_w0: float, worley_w1: float, worley_w2: float,
                              gamma: float) -> tuple[float, float, float]:
    """vc-A10: (R, G, B) of texel (ix, iy, iz) of the detail texture."""
    t = _detail_shape_rgb(ix, iy, iz, size, seed, worley_cells, worley_w0, worley_w1, worley_w2, gamma)
    return t[0], t[1], t[2]


# A whole texture from a settings object (not element-wise): custom evaluators through pywarp.clouds.textures.
@declare("vc-A11", c="ccl_texgen_curl_noise", name="texgen_curl_noise",
         make_warp="pywarp.clouds.texgen:curl_noise_warp", make_c="pywarp.clouds.texgen:curl_noise_c",
         outputs=("curl",),
         summary="The 2-D curl-noise texture, generated (the thesis loads a shipped file): texel (ix, iy) = "
                 "noise_curl2 = (dpsi/dy, -dpsi/dx) of Perlin noise psi at (u, v) * frequency with period = "
                 "frequency (vc-A7 reading (i), divergence-free, exactly tileable), 2 channels in noise-lattice "
                 "units. Call with a CurlNoiseSettings; returns float32 (size, size, 2) "
                 "indexed [iy, ix]. Warp: texgen_curl_noise_texel per texel.",
         references=(_REF_BRIDSON,))
@wp.func
def texgen_curl_noise_texel(ix: int, iy: int, size: int, frequency: int, fd_step: float,
                     perm: wp.array(dtype=wp.int32)) -> wp.vec2:
    """vc-A11: curl noise (dpsi/dy, -dpsi/dx) of Perlin noise psi at texel (ix, iy), noise-lattice units."""
    f = float(frequency)
    x = _texcoord(ix, size) * f
    y = _texcoord(iy, size) * f
    return noise_curl2(x, y, perm, frequency, fd_step)


# A whole texture from a settings object (not element-wise): custom evaluators through pywarp.clouds.textures.
@declare("vc-A12", c="ccl_texgen_weather_map", name="texgen_weather_map",
         make_warp="pywarp.clouds.texgen:weather_map_warp", make_c="pywarp.clouds.texgen:weather_map_c",
         outputs=("weather",),
         summary="Procedural weather map (the thesis loads a shipped file): R = coverage = clamp(remap(n, 1 - c, 1, "
                 "0, 1)) of a tileable Perlin-Worley noise n and the global coverage c; G = precipitation (the "
                 "spec's reading of the 'blue twice' erratum) from an independent Perlin fBm; B = cloud type = "
                 "cloud_type + cloud_type_variation (2 P - 1) clamped; A = 0 (free). Call with a WeatherMapSettings; "
                 "returns float32 (size, size, 4). Images: "
                 "pywarp.clouds.textures.WeatherMap.from_image. Warp: texgen_weather_map_texel per texel.",
         references=(_REF_SV, _REF_GPU7))
@wp.func
def texgen_weather_map_texel(ix: int, iy: int, size: int, seed: wp.uint32, perlin_frequency: int,
                             perlin_octaves: int, perlin_contrast: float, worley_cells: int, worley_octaves: int,
                             combination: int, coverage: float, precipitation: float, cloud_type: float,
                             cloud_type_variation: float, perm0: wp.array(dtype=wp.int32),
                             perm1: wp.array(dtype=wp.int32), perm2: wp.array(dtype=wp.int32)) -> wp.vec4:
    """vc-A12: (coverage, precipitation, cloud type, 0); perm0/1/2 = the tables of seed, seed + 1, seed + 2."""
    u = _texcoord(ix, size)
    v = _texcoord(iy, size)
    p = _perlin01(u, v, 0.0, perlin_octaves, perlin_frequency, perm0, perlin_contrast)
    wv = noise_fbm_worley3(u, v, 0.0, worley_octaves, worley_cells, seed, 0, 1)
    n = noise_perlin_worley(p, wv, combination)
    r = _coverage_shape(n, coverage)
    p2 = _perlin01(u, v, 0.0, perlin_octaves, perlin_frequency, perm1, perlin_contrast)
    g = _coverage_shape(p2, precipitation)
    p3 = _perlin01(u, v, 0.0, perlin_octaves, perlin_frequency, perm2, perlin_contrast)
    b = clamp01(cloud_type + cloud_type_variation * (2.0 * p3 - 1.0))
    return wp.vec4(r, g, b, 0.0)


# --- vc-A13: settings validation (mirror of ccl_texgen_base_shape_settings_check) -----------------------------------

@wp.func
def _lattice_ok(base: int, octaves: int) -> int:
    if base < 1:
        return 0
    if base > (_MAX_LATTICE >> (octaves - 1)):
        return 0
    return 1


# A settings object (a struct in C), not element-wise values: custom evaluators. The Warp twin checks the fields in
# the order of the C check; pywarp.clouds.settings builds the settings dataclasses (vc-A13) and their defaults.
@declare("vc-A13", c="ccl_texgen_base_shape_settings_check", name="texgen_base_shape_settings_check",
         make_warp="pywarp.clouds.texgen:settings_check_warp", make_c="pywarp.clouds.texgen:settings_check_c",
         outputs=("field",),
         summary="Validation of the base-shape generator settings (BaseShapeSettings of vc-A13; the thesis gives no "
                 "values -- the documented defaults are in pywarp.clouds.settings and ccl_texgen_<kind>_settings_"
                 "default): texgen_base_shape_settings_check(settings) returns the name of the first invalid field "
                 "in the order of the C check, or None. Warp twin: texgen_base_shape_settings_code (0 = valid, else "
                 "1 + the index of the field). The detail, curl-noise and weather-map settings have their own C "
                 "checks ccl_texgen_<kind>_settings_check.")
@wp.func
def texgen_base_shape_settings_code(size: int, perlin_octaves: int, perlin_frequency: int, worley_cells: int,
                                    worley_w0: float, worley_w1: float, worley_w2: float, combination: int,
                                    gamma: float) -> int:
    """vc-A13: 0 when the base-shape settings are valid, else 1 + the index of the first invalid field in
    BASE_SHAPE_FIELDS (the order of the C check)."""
    if size < _MIN_SIZE or size > _MAX_SIZE_3D or (size & (size - 1)) != 0:
        return 1
    if perlin_octaves < 1 or perlin_octaves > _MAX_OCTAVES:
        return 2
    if _lattice_ok(perlin_frequency, perlin_octaves) == 0:
        return 3
    if _lattice_ok(worley_cells, 4) == 0:
        return 4
    if not (wp.isfinite(worley_w0) and wp.isfinite(worley_w1) and wp.isfinite(worley_w2)):
        return 5
    if worley_w0 <= 0.0 or worley_w1 < 0.0 or worley_w2 < 0.0:
        return 5
    if combination < PW_THESIS or combination > PW_AVERAGE:
        return 6
    if not (wp.isfinite(gamma) and gamma > 0.0):
        return 7
    return 0


# --- sampler ----------------------------------------------------------------------------------------------------------

@wp.func
def _axis_lo(x: float) -> int:
    """Lower texel index (unwrapped) of x = p * size with texel centres at i + 0.5."""
    fx = wp.floor(x)
    i = int(fx)
    if x - fx < 0.5:
        i = i - 1
    return i


@wp.func
def _axis_t(x: float) -> float:
    """Weight of the upper texel: frac(x) - 0.5 or frac(x) + 0.5, from the exact frac(x) only."""
    fx = wp.floor(x)
    f = x - fx
    if f >= 0.5:
        return f - 0.5
    return f + 0.5


@wp.func
def trilinear_axis(x: float, size_mask: int):
    """One axis of the wrapped trilinear sampler: (lower index, upper index, weight of the upper) of x = p * size."""
    i = _axis_lo(x)
    return i & size_mask, (i + 1) & size_mask, _axis_t(x)


@wp.func
def trilinear_scale(p: wp.vec3, size: int):
    """p * size per axis and whether all three lie in the sampler's domain |p * size| < 2^23 (False for NaN too):
    outside it the samplers return NaN, never an int() of such a value (as the C sampler)."""
    fsize = float(size)
    x = p[0] * fsize
    y = p[1] * fsize
    z = p[2] * fsize
    ok = wp.abs(x) < 8388608.0 and wp.abs(y) < 8388608.0 and wp.abs(z) < 8388608.0
    return x, y, z, ok


@wp.func
def trilinear_lerp(c000: wp.vec4, c100: wp.vec4, c010: wp.vec4, c110: wp.vec4, c001: wp.vec4, c101: wp.vec4,
                   c011: wp.vec4, c111: wp.vec4, tx: float, ty: float, tz: float) -> wp.vec4:
    """The eight corners lerped along x, then y, then z (the order of ``ccl_texgen_sample_trilinear_wrap``)."""
    c00 = c000 + (c100 - c000) * tx
    c10 = c010 + (c110 - c010) * tx
    c01 = c001 + (c101 - c001) * tx
    c11 = c011 + (c111 - c011) * tx
    c0 = c00 + (c10 - c00) * ty
    c1 = c01 + (c11 - c01) * ty
    return c0 + (c1 - c0) * tz


@wp.func
def texgen_sample_trilinear_wrap(tex: wp.array3d(dtype=wp.vec4), size_mask: int, p: wp.vec3) -> wp.vec4:
    """Trilinear sample of the periodic RGBA volume ``tex[z, y, x]`` (edge size_mask + 1, a power of two) at texture
    coordinates p (1 = one period, texel centres at (i + 0.5) / size); indices wrap with ``& size_mask``. Like
    GL_REPEAT + GL_LINEAR; sampling p and p + 1 gives identical results (weights depend on frac(p * size) only)."""
    x, y, z, ok = trilinear_scale(p, size_mask + 1)
    if not ok:
        return wp.vec4(wp.nan, wp.nan, wp.nan, wp.nan)
    x0, x1, tx = trilinear_axis(x, size_mask)
    y0, y1, ty = trilinear_axis(y, size_mask)
    z0, z1, tz = trilinear_axis(z, size_mask)
    return trilinear_lerp(tex[z0, y0, x0], tex[z0, y0, x1], tex[z0, y1, x0], tex[z0, y1, x1], tex[z1, y0, x0],
                          tex[z1, y0, x1], tex[z1, y1, x0], tex[z1, y1, x1], tx, ty, tz)


# --- tile kernels (row0 first; TileLauncher) ------------------------------------------------------------------------

@wp.kernel
def base_shape_kernel(row0: int, size: int, seed: wp.uint32, perlin_octaves: int, perlin_frequency: int,
                      worley_cells: int, worley_w0: float, worley_w1: float, worley_w2: float, gamma: float,
                      combination: int, perm: wp.array(dtype=wp.int32), out: wp.array3d(dtype=wp.vec4)):
    i, j = wp.tid()
    row = row0 + i
    iz = row // size
    iy = row - iz * size
    out[iz, iy, j] = _base_shape_rgba(j, iy, iz, size, seed, perlin_octaves, perlin_frequency, worley_cells,
                                      worley_w0, worley_w1, worley_w2, gamma, combination, perm)


@wp.kernel
def detail_shape_kernel(row0: int, size: int, seed: wp.uint32, worley_cells: int, worley_w0: float,
                        worley_w1: float, worley_w2: float, gamma: float, out: wp.array3d(dtype=wp.vec3)):
    i, j = wp.tid()
    row = row0 + i
    iz = row // size
    iy = row - iz * size
    out[iz, iy, j] = _detail_shape_rgb(j, iy, iz, size, seed, worley_cells, worley_w0, worley_w1, worley_w2, gamma)


@wp.kernel
def curl_noise_kernel(row0: int, size: int, frequency: int, fd_step: float, perm: wp.array(dtype=wp.int32),
                      out: wp.array2d(dtype=wp.vec2)):
    i, j = wp.tid()
    iy = row0 + i
    out[iy, j] = texgen_curl_noise_texel(j, iy, size, frequency, fd_step, perm)


@wp.kernel
def weather_map_kernel(row0: int, size: int, seed: wp.uint32, perlin_frequency: int, perlin_octaves: int,
                       perlin_contrast: float, worley_cells: int, worley_octaves: int, combination: int,
                       coverage: float, precipitation: float, cloud_type: float, cloud_type_variation: float,
                       perm0: wp.array(dtype=wp.int32), perm1: wp.array(dtype=wp.int32),
                       perm2: wp.array(dtype=wp.int32), out: wp.array2d(dtype=wp.vec4)):
    i, j = wp.tid()
    iy = row0 + i
    out[iy, j] = texgen_weather_map_texel(j, iy, size, seed, perlin_frequency, perlin_octaves, perlin_contrast,
                                   worley_cells, worley_octaves, combination, coverage, precipitation, cloud_type,
                                   cloud_type_variation, perm0, perm1, perm2)


@wp.kernel
def sample_kernel(tex: wp.array3d(dtype=wp.vec4), size_mask: int, p: wp.array(dtype=wp.vec3),
                  out: wp.array(dtype=wp.vec4)):
    i = wp.tid()
    out[i] = texgen_sample_trilinear_wrap(tex, size_mask, p[i])


@wp.kernel
def settings_code_kernel(size: wp.array(dtype=wp.int32), perlin_octaves: wp.array(dtype=wp.int32),
                         perlin_frequency: wp.array(dtype=wp.int32), worley_cells: wp.array(dtype=wp.int32),
                         worley_w0: wp.array(dtype=float), worley_w1: wp.array(dtype=float),
                         worley_w2: wp.array(dtype=float), combination: wp.array(dtype=wp.int32),
                         gamma: wp.array(dtype=float), out: wp.array(dtype=wp.int32)):
    # the settings check over arrays of settings, for base_shape_settings_codes (vc-A13 is not element-wise)
    i = wp.tid()
    out[i] = texgen_base_shape_settings_code(size[i], perlin_octaves[i], perlin_frequency[i], worley_cells[i],
                                             worley_w0[i], worley_w1[i], worley_w2[i], combination[i], gamma[i])


# --- argument check of the size entries ------------------------------------------------------------------------------

def is_pow2(n) -> np.ndarray:
    n = np.asarray(n, dtype=np.int64)
    return (n > 0) & ((n & (n - 1)) == 0)


