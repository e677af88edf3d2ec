"""Noise-texture generator (vc §2.3.3, §4.3.1): gamma vc-4.6; base texture vc-A9 (with vc-A8), detail texture vc-A10,
curl-noise texture vc-A11, weather map vc-A12, settings vc-A13, the generator classes (vc-A32), the cache and the
wrap-around trilinear sampler.

Independent references: the textures recomputed in float64 from the noise primitives (pywarp's vc-A3/A6/2.21/A7/A8
entries, tested on their own in test_noise.py) with the formulas documented in cclouds/texgen.h; trilinear
interpolation written here in float64. Sizes are small (<= 32^3): the full 128^3 runs only in
pywarp.clouds.bench_textures.
"""
from __future__ import annotations

import inspect
import os
import re
from dataclasses import asdict, fields
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from helpers import assert_twins_agree

import pywarp
from pywarp.core import binding as _cclouds
from pywarp.clouds import texgen as TG
from pywarp.clouds import textures as T
from pywarp.kernels import texgen as K
from pywarp.kernels.noise import COMBINATIONS

EPS32 = float(np.finfo(np.float32).eps)

# C vs Warp tolerance (ulp) for the textures: both evaluate the same float32 expression tree in the same order (the
# Worley/Perlin hashing is integer arithmetic, sqrtf and the divisions are correctly rounded on both sides); only
# powf (gamma, vc-4.6) comes from two different libms, each within 1 ulp, plus the rounding of the result it feeds:
# 2 ulp. (Observed on x86-64: 0 ulp, bit-identical.)
TEXTURE_ULP = 2


def ulp_diff(a, b) -> int:
    """Largest distance in ulp between two float32 arrays; -0 and +0 are the same value."""
    a = (np.asarray(a, dtype=np.float32) + np.float32(0)).ravel().view(np.int32).astype(np.int64)
    b = (np.asarray(b, dtype=np.float32) + np.float32(0)).ravel().view(np.int32).astype(np.int64)
    return int(np.max(np.abs(a - b))) if a.size else 0


def texcoords(n):
    return (np.arange(n, dtype=np.float64) + 0.5) / n


def grid3(n):
    u = texcoords(n).astype(np.float32)
    z, y, x = np.meshgrid(u, u, u, indexing="ij")  # [iz, iy, ix]
    return x, y, z


def worley_layers_ref(x, y, z, cells, seed):
    """The four inverse-Worley layers of the header comment: cells * 2^j cells, seed + j, from the vc-A3 entry."""
    w3 = pywarp.equation("vc-A3")
    return [w3(x, y, z, cells * 2 ** j, seed + j, inverse=True).astype(np.float64) for j in range(4)]


def sliding_ref(layers, w):
    """channel k = sum_{j, k+j <= 3} w_j W_{k+j} / sum w_j (float64)."""
    w0, w1, w2 = w
    g = (w0 * layers[0] + w1 * layers[1] + w2 * layers[2]) / (w0 + w1 + w2)
    b = (w0 * layers[1] + w1 * layers[2] + w2 * layers[3]) / (w0 + w1 + w2)
    a = (w0 * layers[2] + w1 * layers[3]) / (w0 + w1)
    return [np.clip(c, 0, 1) for c in (g, b, a)]


def neighbour_roughness(a, axis):
    """Mean |difference| of neighbouring texels (periodic): larger for higher-frequency noise."""
    return float(np.mean(np.abs(a - np.roll(a, 1, axis=axis))))


# ---------------------------------------------------------------------------------------------------------------------
# vc-4.6 gamma
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-4.6")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_texgen_gamma_closed_form_and_float64_reference(impl, rng):
    gam = pywarp.equation("vc-4.6", impl=impl)
    assert gam(0.25, 0.5) == pytest.approx(0.0625, rel=2 * EPS32)
    assert gam(0.25, 2.0) == pytest.approx(0.5, rel=2 * EPS32)
    assert gam(0.0, 2.2) == 0.0 and gam(1.0, 2.2) == 1.0
    c = rng.uniform(0, 1, 3000).astype(np.float32)
    np.testing.assert_array_equal(gam(c, 1.0), c)  # gamma = 1 is the identity, exactly (pow(c, 1) == c)
    assert np.all(gam(c[c > 0], 2.2) > c[c > 0] * (1 - EPS32)) and np.all(gam(c, 0.5) <= c)  # > 1 brightens
    g = rng.uniform(0.2, 5.0, 3000).astype(np.float32)
    c = rng.uniform(1e-4, 1, 3000).astype(np.float32)
    c64, g64 = c.astype(np.float64), g.astype(np.float64)
    ref = c64 ** (1.0 / g64)
    # float32 evaluation: 1/gamma is rounded (relative error eps/2), which moves the result by |ln C| / gamma * eps/2
    # relatively; powf adds ~1 ulp: allowed eps * (2 + |ln c| / gamma)
    bound = EPS32 * (2.0 + np.abs(np.log(c64)) / g64)
    assert np.all(np.abs(gam(c, g) / ref - 1.0) <= bound)


@pytest.mark.spec("vc-4.6")
def test_texgen_gamma_c_and_warp_agree(rng):
    c = rng.uniform(0, 1, 4000).astype(np.float32)
    g = rng.uniform(0.1, 10, 4000).astype(np.float32)
    # powf of two libms, each within 1 ulp of the exact value of the same float32 arguments: <= 2 ulp apart
    assert_twins_agree("vc-4.6", c, g, ulp=2)


@pytest.mark.spec("vc-4.6")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_texgen_gamma_bad_input(impl):
    gam = pywarp.equation("vc-4.6", impl=impl)
    with pytest.raises(ValueError, match=r"^gamma must be in \(0, inf\), got 0\.0"):
        gam(0.5, 0.0)
    with pytest.raises(ValueError, match=r"^c must be in \[0, 1\], got 1\.5"):
        gam(1.5, 2.0)
    with pytest.raises(ValueError, match=r"^gamma must be finite"):
        gam(0.5, np.inf)


# ---------------------------------------------------------------------------------------------------------------------
# vc-A9 base shape, vc-A10 detail shape
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A9", "vc-A8", "vc-4.6")
@pytest.mark.parametrize("combination", ["thesis", "gpu_pro_7", "hillaire"])
def test_base_shape_matches_composition_of_noise_primitives(combination):
    """Every texel of an 8^3 texture against the formulas of cclouds/texgen.h evaluated in float64 from the noise
    entries: G/B/A = sliding fBm of four inverse-Worley layers, R = Perlin-Worley of P and G, then gamma."""
    n, seed, w, gamma = 8, 5, (0.5, 0.3, 0.2), 1.6
    s = T.BaseShapeSettings(size=n, seed=seed, perlin_frequency=2, perlin_octaves=2, worley_cells=1,
                            worley_weights=w, combination=combination, gamma=gamma)
    x, y, z = grid3(n)
    g, b, a = sliding_ref(worley_layers_ref(x, y, z, 1, seed), w)
    p = np.clip(0.5 * pywarp.equation("vc-2.21")(x, y, z, 2, 2.0, seed, 2).astype(np.float64) + 0.5, 0, 1)
    if combination == "thesis":
        r = (g + p * (1 - g)) ** 2  # remap(P, 0, 1, W, 1)^2
    elif combination == "hillaire":
        r = g + p * (1 - g)
    else:
        r = np.clip((p - g) / (1 - g), 0, 1)
    ref = np.stack([np.clip(c, 0, 1) ** (1 / gamma) for c in (r, g, b, a)], axis=-1)
    for impl in ("warp", "c"):
        tex = T.generate("base_shape", s, impl=impl)
        assert tex.shape == (n, n, n, 4) and tex.dtype == np.float32
        # float32 sums of three weighted terms, one division, a square and powf vs float64: a few ulp of 1
        np.testing.assert_allclose(tex, ref, rtol=0, atol=8 * EPS32)


@pytest.mark.spec("vc-A10", "vc-4.6")
def test_detail_shape_matches_composition_and_worley_fbm():
    n, seed = 8, 11
    s = T.DetailShapeSettings(size=n, seed=seed, worley_cells=2, gamma=0.7)
    x, y, z = grid3(n)
    ref = np.stack([c ** (1 / 0.7) for c in sliding_ref(worley_layers_ref(x, y, z, 2, seed), s.worley_weights)],
                   axis=-1)
    for impl in ("warp", "c"):
        np.testing.assert_allclose(T.generate("detail_shape", s, impl=impl), ref, rtol=0, atol=8 * EPS32)
    # with the fBm weights 1, 1/2, 1/4 of vc-A6 a channel is the noise module's Worley fBm of three octaves
    halving = T.generate("detail_shape", T.DetailShapeSettings(size=n, seed=seed, worley_weights=(1, 0.5, 0.25)))
    fbm = pywarp.equation("vc-A6")
    np.testing.assert_allclose(halving[..., 0], fbm(x, y, z, 3, 2, seed, inverse=True), rtol=0, atol=2 * EPS32)
    np.testing.assert_allclose(halving[..., 1], fbm(x, y, z, 3, 4, seed + 1, inverse=True), rtol=0, atol=2 * EPS32)


@pytest.mark.spec("vc-A9", "vc-A10")
def test_base_and_detail_c_and_warp_agree_on_whole_textures():
    cases = [("base_shape", T.BaseShapeSettings(size=16)),
             ("base_shape", T.BaseShapeSettings(size=16, seed=4000000000, gamma=2.2, combination="average",
                                                perlin_frequency=4, worley_cells=2, worley_weights=(0.4, 0.4, 0.2))),
             ("detail_shape", T.DetailShapeSettings(size=16)),
             ("detail_shape", T.DetailShapeSettings(size=16, seed=77, gamma=0.45, worley_cells=1))]
    for kind, s in cases:
        w, c = T.generate(kind, s, impl="warp"), T.generate(kind, s, impl="c")
        assert w.shape == c.shape == s.shape
        assert ulp_diff(w, c) <= TEXTURE_ULP, (kind, s)


@pytest.mark.spec("vc-A9", "vc-A10")
def test_texel_entries_c_and_warp_agree(rng):
    """The texel entries on random texels, seeds (one permutation table per seed) and settings: the same float32
    expression tree; powf (gamma) of two libms: TEXTURE_ULP."""
    n = 200
    ix, iy, iz = rng.integers(-1000, 1000, (3, n))
    seed = rng.choice(np.array([0, 5, 4000000000], dtype=np.uint64), n).astype(np.uint32)
    size = 2 ** rng.integers(2, 7, n)
    octaves = rng.integers(1, 5, n)
    freq = rng.integers(1, 17, n)
    cells = rng.integers(1, 9, n)
    w0, w1, w2 = rng.uniform(0.1, 1.0, (3, n)).astype(np.float32)
    gamma = rng.uniform(0.4, 2.5, n).astype(np.float32)
    for combination in COMBINATIONS:
        assert_twins_agree("vc-A9", ix, iy, iz, size, seed, octaves, freq, cells, w0, w1, w2, gamma,
                           combination=combination, ulp=TEXTURE_ULP)
    assert_twins_agree("vc-A10", ix, iy, iz, size, seed, cells, w0, w1, w2, gamma, ulp=TEXTURE_ULP)


@pytest.mark.spec("vc-A9", "vc-A10")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_texel_entries_equal_whole_textures_and_are_exactly_periodic(impl, rng):
    """The element-wise entries give the texels of the whole texture, and texel(i + k size) == texel(i) bit for bit
    on every axis (the noise period equals the texture: tileable)."""
    n = 8
    base = T.BaseShapeSettings(size=n, seed=321, perlin_frequency=4, worley_cells=2, gamma=1.3)
    det = T.DetailShapeSettings(size=n, seed=9, gamma=0.8)
    tb, td = T.generate("base_shape", base, impl=impl), T.generate("detail_shape", det, impl=impl)
    ix, iy, iz = (rng.integers(0, n, 60) for _ in range(3))
    kx, ky, kz = (rng.integers(-3, 4, 60) for _ in range(3))
    bt = pywarp.equation("vc-A9", impl=impl)
    bargs = dict(size=n, seed=321, perlin_octaves=3, perlin_frequency=4, worley_cells=2, worley_w0=0.625,
                 worley_w1=0.25, worley_w2=0.125, gamma=1.3)
    r0 = np.stack(bt(ix, iy, iz, **bargs), axis=-1)
    np.testing.assert_array_equal(r0, tb[iz, iy, ix])
    np.testing.assert_array_equal(np.stack(bt(ix + kx * n, iy + ky * n, iz + kz * n, **bargs), axis=-1), r0)
    dt = pywarp.equation("vc-A10", impl=impl)
    dargs = dict(size=n, seed=9, worley_cells=2, worley_w0=0.625, worley_w1=0.25, worley_w2=0.125, gamma=0.8)
    d0 = np.stack(dt(ix, iy, iz, **dargs), axis=-1)
    np.testing.assert_array_equal(d0, td[iz, iy, ix])
    np.testing.assert_array_equal(np.stack(dt(ix - kx * n, iy + kz * n, iz - ky * n, **dargs), axis=-1), d0)


@pytest.mark.spec("vc-A9", "vc-A8")
def test_base_shape_ranges_statistics_and_frequency_order():
    """32^3 with the default layer scales halved (so that the 32 texels resolve them like 128 texels do the defaults):
    every channel in [0, 1] and not constant; texel-to-texel roughness grows from G to B to A (the "increasing
    frequency" of vc-A9, G lowest as eq 2.28's weights expect); R is tied to G: R >= G^2 for the thesis' combination
    (R = (G + P(1 - G))^2, P in [0, 1]) and strongly correlated with it."""
    tex = T.generate("base_shape", T.BaseShapeSettings(size=32, perlin_frequency=4, worley_cells=2))
    assert tex.min() >= 0.0 and tex.max() <= 1.0
    stds = tex.reshape(-1, 4).std(axis=0)
    assert np.all(stds > 0.05), stds
    rough = [np.mean([neighbour_roughness(tex[..., c], ax) for ax in range(3)]) for c in range(4)]
    assert rough[1] < rough[2] < rough[3], rough
    r, g = tex[..., 0].astype(np.float64), tex[..., 1].astype(np.float64)
    assert np.all(r >= g * g - 4 * EPS32)
    assert np.corrcoef(r.ravel(), g.ravel())[0, 1] > 0.5
    det = T.generate("detail_shape", T.DetailShapeSettings(size=32))
    assert det.min() >= 0.0 and det.max() <= 1.0 and np.all(det.reshape(-1, 3).std(axis=0) > 0.05)
    drough = [np.mean([neighbour_roughness(det[..., c], ax) for ax in range(3)]) for c in range(3)]
    assert drough[0] < drough[1] < drough[2], drough


@pytest.mark.spec("vc-A9", "vc-A10", "vc-A11", "vc-A12")
def test_generation_is_deterministic_and_seeded():
    for kind, cls in T.SETTINGS.items():
        size = 8 if kind.endswith("shape") else 16
        a = T.generate(kind, cls(size=size, seed=17))
        np.testing.assert_array_equal(a, T.generate(kind, cls(size=size, seed=17)))
        assert not np.array_equal(a, T.generate(kind, cls(size=size, seed=18))), kind


@pytest.mark.spec("vc-A9", "vc-A10")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_texel_entries_bad_input_raises_value_error_naming_parameter(impl):
    bt = pywarp.equation("vc-A9", impl=impl)
    ok = dict(size=8, seed=0, perlin_octaves=3, perlin_frequency=4, worley_cells=2, worley_w0=0.625, worley_w1=0.25,
              worley_w2=0.125, gamma=1.0)
    with pytest.raises(ValueError, match=r"^size must be a power of two in \[4, 512\], got 12"):
        bt(0, 0, 0, **{**ok, "size": 12})
    with pytest.raises(ValueError, match=r"^size must be in \[4, 512\]"):
        bt(0, 0, 0, **{**ok, "size": 1024})
    with pytest.raises(ValueError, match=r"^perlin_frequency \* 2\^\(octaves - 1\) must be <= 4096"):
        bt(0, 0, 0, **{**ok, "perlin_frequency": 2048})
    with pytest.raises(ValueError, match=r"^worley_w0 must be in \(0, inf\)"):
        bt(0, 0, 0, **{**ok, "worley_w0": 0.0})
    with pytest.raises(ValueError, match=r"^worley_w2 must be in \[0, inf\)"):
        bt(0, 0, 0, **{**ok, "worley_w2": -0.5})
    with pytest.raises(ValueError, match=r"^gamma must be finite"):
        bt(0, 0, 0, **{**ok, "gamma": np.nan})
    with pytest.raises(ValueError, match=r"^ix must hold integers"):
        bt(0.5, 0, 0, **ok)
    with pytest.raises(ValueError, match=r"^combination must be one of 'thesis'"):
        bt(0, 0, 0, **ok, combination="screen")
    with pytest.raises(ValueError, match=r"^seed must be in \[0, 4294967295\] \(uint32\)"):
        bt(0, 0, 0, **{**ok, "seed": -1})
    dt = pywarp.equation("vc-A10", impl=impl)
    with pytest.raises(ValueError, match=r"^size must be a power of two"):
        dt(0, 0, 0, size=6, seed=0, worley_cells=1, worley_w0=1, worley_w1=0, worley_w2=0, gamma=1)
    with pytest.raises(ValueError, match=r"^worley_cells must be in \[1, 512\]"):
        dt(0, 0, 0, size=8, seed=0, worley_cells=0, worley_w0=1, worley_w1=0, worley_w2=0, gamma=1)


# ---------------------------------------------------------------------------------------------------------------------
# tileability and the sampler
# ---------------------------------------------------------------------------------------------------------------------

def ref_trilinear(tex, p):
    """float64 GL_REPEAT + GL_LINEAR: x = p n - 0.5, i0 = floor(x), weights x - i0, indices mod n."""
    n = tex.shape[0]
    q = np.asarray(p, dtype=np.float64) * n - 0.5
    i0 = np.floor(q).astype(np.int64)
    t = q - i0
    out = np.zeros(q.shape[:-1] + (4,))
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                wgt = ((t[..., 0] if dx else 1 - t[..., 0]) * (t[..., 1] if dy else 1 - t[..., 1])
                       * (t[..., 2] if dz else 1 - t[..., 2]))
                out += wgt[..., None] * tex[(i0[..., 2] + dz) % n, (i0[..., 1] + dy) % n, (i0[..., 0] + dx) % n]
    return out


@pytest.mark.spec("vc-A9", "vc-A10")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_sample_trilinear_wrap_matches_float64_reference(impl, rng):
    n = 8
    tex = rng.uniform(0, 1, (n, n, n, 4)).astype(np.float32)
    p = rng.uniform(-3, 3, (2000, 3)).astype(np.float32)
    got = TG.sample_trilinear_wrap_np(tex, p, impl=impl)
    # float32: p * n is exact (n a power of two); the weight frac +- 0.5 is rounded once (<= eps/4); each of the 3
    # lerp levels a + (b - a) t on values in [0, 1] adds <= 1.5 ulp of 1: bound 6 eps
    np.testing.assert_allclose(got, ref_trilinear(tex, p), rtol=0, atol=6 * EPS32)
    # at texel centres the sample is the texel, exactly
    idx = rng.integers(0, n, (200, 3))
    centres = ((idx + 0.5) / n).astype(np.float32)
    np.testing.assert_array_equal(TG.sample_trilinear_wrap_np(tex, centres, impl=impl), tex[idx[:, 2], idx[:, 1],
                                                                                              idx[:, 0]])


@pytest.mark.spec("vc-A9", "vc-A10")
def test_sample_trilinear_wrap_c_and_warp_agree_and_are_shift_invariant(rng):
    """Sampling at p and p + 1 (texture units) is identical bit for bit, on every axis and in both implementations:
    the weights depend only on frac(p * size), computed exactly."""
    tex = T.generate("base_shape", T.BaseShapeSettings(size=16, perlin_frequency=4, worley_cells=2))
    p1 = rng.uniform(1, 2, (1500, 3)).astype(np.float32)  # in [1, 2): p1 - 1 and p1 - 3 are exact
    p0 = p1 - np.float32(1)
    pm = p1 - np.float32(3)
    w1 = TG.sample_trilinear_wrap_np(tex, p1)
    np.testing.assert_array_equal(w1, TG.sample_trilinear_wrap_np(tex, p0))
    np.testing.assert_array_equal(w1, TG.sample_trilinear_wrap_np(tex, pm))
    mixed = np.stack([p0[:, 0], p1[:, 1], pm[:, 2]], axis=1)
    np.testing.assert_array_equal(w1, TG.sample_trilinear_wrap_np(tex, mixed))
    c1 = TG.sample_trilinear_wrap_np(tex, p1, impl="c")
    np.testing.assert_array_equal(c1, TG.sample_trilinear_wrap_np(tex, p0, impl="c"))
    # same float32 lerps in the same order: bit-identical up to operation contraction (allow 2 ulp)
    assert ulp_diff(w1, c1) <= 2


def seam_ratio(a, axis) -> float:
    """Mean squared step across the tile border / mean squared interior step (lag-1 variogram) along ``axis``."""
    a = np.asarray(a, dtype=np.float64)
    inner = np.diff(a, axis=axis)
    border = np.take(a, [0], axis=axis) - np.take(a, [-1], axis=axis)
    return float(np.mean(border ** 2) / np.mean(inner ** 2))


def seamless(a, axis) -> bool:
    """The border step is an ordinary step: its mean square is within 1.5x of the interior's. Without tiling it is
    the step between two far-apart (nearly independent) values, 2 var, against the interior 2 var (1 - rho_1): at
    least 2x for any field whose lag-1 correlation rho_1 is >= 0, and typically much more for smooth noise."""
    return seam_ratio(a, axis) <= 1.5


@pytest.mark.spec("vc-A9", "vc-A10", "vc-A11", "vc-A12")
def test_textures_tile_without_seams():
    base = T.generate("base_shape", T.BaseShapeSettings(size=32))
    det = T.generate("detail_shape", T.DetailShapeSettings(size=32))
    curl = T.generate("curl_noise", T.CurlNoiseSettings(size=64))
    weather = T.generate("weather_map", T.WeatherMapSettings(size=64))
    for c in range(4):
        assert all(seamless(base[..., c], ax) for ax in range(3)), c
    for c in range(3):
        assert all(seamless(det[..., c], ax) for ax in range(3)), c
    for c in range(2):
        assert all(seamless(curl[..., c], ax) for ax in range(2)), c
    for c in (0, 2):  # G (precipitation 0.2) is mostly 0 at this size, A is constant 0
        assert all(seamless(weather[..., c], ax) for ax in range(2)), c
    # the criterion has teeth: the same Perlin fBm with Perlin's own lattice (period 0, not matched to the tile)
    # and a Worley noise at 1.3x the tile frequency both fail it (observed ratios 3.0 and 5.8)
    x, y, z = grid3(32)
    perlin = pywarp.equation("vc-2.21")(x, y, z, 3, 8.0, 0, 0)
    worley = pywarp.equation("vc-A3")(x * np.float32(1.3), y, z, 4, 0, inverse=True)
    assert not seamless(perlin, 2) and not seamless(perlin, 0) and not seamless(worley, 2)


# ---------------------------------------------------------------------------------------------------------------------
# vc-A11 curl noise
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A11", "vc-A7")
def test_curl_noise_texture_is_curl_of_perlin_and_divergence_free():
    s = T.CurlNoiseSettings(size=32, seed=3, frequency=2)
    u = texcoords(32).astype(np.float32)
    y, x = np.meshgrid(u, u, indexing="ij")
    f = np.float32(2)
    vx, vy = np.moveaxis(pywarp.equation("vc-A7")(x * f, y * f, 3, 2, s.fd_step), -1, 0)
    for impl in ("warp", "c"):
        tex = pywarp.equation("vc-A11", impl=impl)(s)
        assert tex.shape == (32, 32, 2)
        np.testing.assert_array_equal(tex[..., 0], vx)  # the same float32 computation, composed
        np.testing.assert_array_equal(tex[..., 1], vy)
    # tileable: the noise one texture further on (u + 1, v - 2) is the texture itself, bit for bit
    sx, sy = np.moveaxis(pywarp.equation("vc-A7")((x + np.float32(1)) * f, (y - np.float32(2)) * f, 3, 2, s.fd_step),
                         -1, 0)
    np.testing.assert_array_equal(sx, vx)
    np.testing.assert_array_equal(sy, vy)
    # discrete divergence on the texel grid (central differences, periodic): the field is the curl of a smooth
    # stream function, so it is O(h^2) -- tiny against the derivatives themselves
    d_vx_dx = (np.roll(tex[..., 0], -1, 1) - np.roll(tex[..., 0], 1, 1)).astype(np.float64)
    d_vy_dy = (np.roll(tex[..., 1], -1, 0) - np.roll(tex[..., 1], 1, 0)).astype(np.float64)
    assert np.mean(np.abs(d_vx_dx + d_vy_dy)) < 0.05 * np.mean(np.abs(d_vx_dx))
    # a non-trivial, signed field
    assert tex.std() > 0.2 and tex.min() < 0 < tex.max()


@pytest.mark.spec("vc-A11")
def test_curl_noise_c_and_warp_agree_and_bad_settings():
    for s in (T.CurlNoiseSettings(size=64), T.CurlNoiseSettings(size=32, seed=99, frequency=8, fd_step=0.01)):
        assert ulp_diff(T.generate("curl_noise", s), T.generate("curl_noise", s, impl="c")) <= TEXTURE_ULP
    for impl in ("warp", "c"):
        fn = pywarp.equation("vc-A11", impl=impl)
        np.testing.assert_array_equal(fn(T.CurlNoiseSettings(16, 4)),
                                      T.generate("curl_noise", T.CurlNoiseSettings(16, 4)))
        with pytest.raises(TypeError, match=r"settings must be a texture settings object"):
            fn({"size": 16})
    # bad settings are refused when the settings object is built, before any generator runs
    with pytest.raises(ValueError, match=r"^fd_step must be in \(0, 0\.25\], got 0\.5"):
        T.CurlNoiseSettings(size=16, fd_step=0.5)
    with pytest.raises(ValueError, match=r"^size must be a power of two in \[4, 8192\], got 48"):
        T.CurlNoiseSettings(size=48)


# ---------------------------------------------------------------------------------------------------------------------
# vc-A12 weather map
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A12", "vc-A8")
def test_weather_map_matches_composition_of_noise_primitives():
    n, seed = 16, 6
    s = T.WeatherMapSettings(size=n, seed=seed, coverage=0.6, precipitation=0.3, cloud_type=0.4,
                             cloud_type_variation=0.5)
    u = texcoords(n).astype(np.float32)
    fbm = pywarp.equation("vc-2.21")

    def reference(dx, dy):  # the formulas of cclouds/texgen.h from the noise primitives, shifted by whole tiles
        y, x = np.meshgrid(u + np.float32(dy), u + np.float32(dx), indexing="ij")
        z = np.zeros_like(x)

        def perlin01(sd):
            return np.clip(0.5 + 2.0 * fbm(x, y, z, 4, 4.0, sd, 4).astype(np.float64), 0, 1)

        wv = pywarp.equation("vc-A6")(x, y, z, 3, 4, seed, inverse=True).astype(np.float64)
        p = perlin01(seed)
        nz = (wv + p * (1 - wv)) ** 2
        return np.stack([np.clip((nz - 0.4) / 0.6, 0, 1), np.clip((perlin01(seed + 1) - 0.7) / 0.3, 0, 1),
                         np.clip(0.4 + 0.5 * (2 * perlin01(seed + 2) - 1), 0, 1), np.zeros_like(nz)], axis=-1)

    ref = reference(0, 0)
    for impl in ("warp", "c"):
        tex = pywarp.equation("vc-A12", impl=impl)(s)
        # the coverage remap divides by c = 0.6 and the contrast multiplies by 2: ~10 float32 roundings of O(1) values
        np.testing.assert_allclose(tex, ref, rtol=0, atol=16 * EPS32)
    # tileable: the map continues periodically beyond its border (the primitives are exactly periodic)
    np.testing.assert_array_equal(reference(1, -1), ref)


@pytest.mark.spec("vc-A12")
def test_weather_map_channels_coverage_and_c_warp_agreement():
    base = dict(size=64, seed=2)
    maps = {c: T.generate("weather_map", T.WeatherMapSettings(**base, coverage=c)) for c in (0.0, 0.25, 0.5, 0.75,
                                                                                            1.0)}
    for m in maps.values():
        assert m.shape == (64, 64, 4) and m.min() >= 0 and m.max() <= 1
        np.testing.assert_array_equal(m[..., 3], 0.0)  # A: free
        np.testing.assert_array_equal(m[..., 1:3], maps[0.5][..., 1:3])  # coverage changes R only
    assert np.all(maps[0.0][..., 0] == 0.0)  # coverage 0: clear sky
    fracs = [float(np.mean(maps[c][..., 0] > 0)) for c in (0.25, 0.5, 0.75, 1.0)]
    for lo, hi in zip((0.0, 0.25, 0.5, 0.75), (0.25, 0.5, 0.75, 1.0)):
        assert np.all(maps[hi][..., 0] >= maps[lo][..., 0])  # non-decreasing in the coverage, texel by texel
    assert fracs == sorted(fracs) and fracs[0] < 0.5 < fracs[2] and fracs[3] == 1.0, fracs
    # B within cloud_type +- variation; G: precipitation 0 -> dry everywhere
    m = T.generate("weather_map", T.WeatherMapSettings(**base, cloud_type=0.3, cloud_type_variation=0.2,
                                                       precipitation=0.0))
    assert m[..., 2].min() >= 0.1 - 1e-7 and m[..., 2].max() <= 0.5 + 1e-7 and m[..., 2].std() > 0.02
    assert np.all(m[..., 1] == 0.0)
    for s in (T.WeatherMapSettings(size=64), T.WeatherMapSettings(size=32, seed=4294967295, combination="product",
                                                                  coverage=0.9, perlin_contrast=1.0)):
        assert ulp_diff(T.generate("weather_map", s), T.generate("weather_map", s, impl="c")) <= TEXTURE_ULP


def _png(path, arr, mode):
    from PIL import Image

    Image.fromarray(arr, mode=mode).save(path)
    return path


@pytest.mark.spec("vc-A12")
def test_weather_map_from_image_loads_and_validates(tmp_path, rng):
    rgba = rng.integers(0, 256, (8, 16, 4), dtype=np.uint8)
    wm = T.WeatherMap.from_image(_png(tmp_path / "w.png", rgba, "RGBA"))
    assert wm.data.shape == (8, 16, 4) and wm.data.dtype == np.float32
    np.testing.assert_array_equal(wm.data, rgba.astype(np.float32) / np.float32(255))
    np.testing.assert_array_equal(wm.coverage, wm.data[..., 0])
    np.testing.assert_array_equal(wm.precipitation, wm.data[..., 1])
    np.testing.assert_array_equal(wm.cloud_type, wm.data[..., 2])
    rgb = rng.integers(0, 256, (4, 4, 3), dtype=np.uint8)
    wm3 = T.WeatherMap.from_image(_png(tmp_path / "w3.png", rgb, "RGB"))
    np.testing.assert_array_equal(wm3.data[..., :3], rgb / np.float32(255))
    np.testing.assert_array_equal(wm3.data[..., 3], 0.0)
    with pytest.raises(ValueError, match=r"^mode of the weather map image must be 'RGB' or 'RGBA'.*got 'L'"):
        T.WeatherMap.from_image(_png(tmp_path / "gray.png", rgb[..., 0], "L"))
    with pytest.raises(ValueError, match=r"^size of the weather map image must be powers of two .* got 12x8"):
        T.WeatherMap.from_image(_png(tmp_path / "odd.png", rng.integers(0, 256, (8, 12, 3), dtype=np.uint8), "RGB"))
    with pytest.raises(ValueError, match=r"^size of the weather map image must be powers of two .* got 2x2"):
        T.WeatherMap.from_image(_png(tmp_path / "tiny.png", rgb[:2, :2], "RGB"))
    with pytest.raises(FileNotFoundError, match="weather map image not found"):
        T.WeatherMap.from_image(tmp_path / "missing.png")
    (tmp_path / "junk.png").write_bytes(b"not an image at all")
    with pytest.raises(ValueError, match=r"^path '.*junk\.png' is not an image Pillow can read"):
        T.WeatherMap.from_image(tmp_path / "junk.png")
    # round trip through to_image (8-bit) and use in the generator instead of the procedural map
    gen_map = T.WeatherMap(T.generate("weather_map", T.WeatherMapSettings(size=16)))
    gen_map.to_image(tmp_path / "gen.png")
    back = T.WeatherMap.from_image(tmp_path / "gen.png")
    np.testing.assert_allclose(back.data, gen_map.data, rtol=0, atol=0.5 / 255 + 1e-7)
    gen = T.BasicTextureGenerator(cache=False, weather_image=tmp_path / "gen.png")
    np.testing.assert_array_equal(gen.weather_map(), back.data)
    with pytest.raises(ValueError, match="settings cannot be combined with weather_image"):
        gen.weather_map(T.WeatherMapSettings(size=16))
    with pytest.raises(ValueError, match=r"^data must hold finite values in \[0, 1\]"):
        T.WeatherMap(np.full((4, 4, 4), 1.5, np.float32))


# ---------------------------------------------------------------------------------------------------------------------
# vc-A13 settings
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A13")
def test_settings_defaults_are_documented_and_equal_the_c_defaults():
    lib = _cclouds.lib()
    for kind, cls in T.SETTINGS.items():
        c = getattr(lib, f"ccl_texgen_{kind}_settings_default")()
        for fl in fields(cls):
            # every field states its default and why: a parameter spec with a reason (pywarp.core.params), or, in a
            # plain dataclass, a preceding "#:" comment that says "Default"
            if "param" in fl.metadata:
                assert fl.metadata["param"].reason.strip(), (cls.__name__, fl.name)
            else:
                src = inspect.getsource(inspect.getmodule(cls))
                m = re.search(rf"((?:\n\s*#:[^\n]*)+)\n\s*{fl.name}: [^=]+= ",
                              src[src.index(f"class {cls.__name__}"):])
                assert m and "Default" in m.group(1), (cls.__name__, fl.name)
            py = getattr(cls(), fl.name)
            cv = getattr(c, fl.name)
            if fl.name == "worley_weights":
                assert tuple(cv) == pytest.approx(py, rel=1e-7)
            elif fl.name == "combination":
                assert cv == COMBINATIONS[py]
            else:
                assert cv == pytest.approx(py, rel=1e-7), (kind, fl.name)
    assert T.BaseShapeSettings().shape == (128, 128, 128, 4) and T.DetailShapeSettings().shape == (32, 32, 32, 3)


BAD_SETTINGS = [
    ("base_shape", {"size": 100}, r"size must be a power of two in \[4, 512\], got 100"),
    ("base_shape", {"size": 2}, r"size must be a power of two"),
    ("base_shape", {"perlin_octaves": 0}, r"perlin_octaves must be in \[1, 8\], got 0"),
    ("base_shape", {"perlin_frequency": 2048, "perlin_octaves": 3}, r"perlin_frequency \* 2\^\(octaves - 1\) must "
                                                                    r"be <= 4096, got 2048 \* 2\^2 = 8192"),
    ("base_shape", {"worley_cells": 1000}, r"worley_cells \* 2\^\(layers - 1\) must be <= 4096, got 1000"),
    ("base_shape", {"worley_weights": (0.0, 1.0, 1.0)}, r"worley_weights must be finite and >= 0 with"),
    ("base_shape", {"worley_weights": (1.0, float("nan"), 1.0)}, r"worley_weights must be finite"),
    ("base_shape", {"worley_weights": (1.0, 1.0)}, r"worley_weights must hold 3 weights"),
    ("base_shape", {"combination": "max"}, r"combination must be one of 'thesis'"),
    ("base_shape", {"gamma": 0.0}, r"gamma must be in \(0, inf\), got 0\.0"),
    ("base_shape", {"gamma": float("inf")}, r"gamma must be finite"),
    ("base_shape", {"seed": -1}, r"seed must be in \[0, 4294967295\], got -1"),
    ("detail_shape", {"size": 1024}, r"size must be a power of two in \[4, 512\]"),
    ("detail_shape", {"worley_cells": 0}, r"worley_cells must be in \[1, 4096\], got 0"),
    ("detail_shape", {"gamma": -2.0}, r"gamma must be in \(0, inf\), got -2\.0"),
    ("curl_noise", {"frequency": 0}, r"frequency must be in \[1, 4096\], got 0"),
    ("curl_noise", {"fd_step": 0.3}, r"fd_step must be in \(0, 0\.25\], got 0\.3"),
    ("weather_map", {"coverage": 1.2}, r"coverage must be in \[0, 1\], got 1\.2"),
    ("weather_map", {"precipitation": -0.1}, r"precipitation must be in \[0, 1\], got -0\.1"),
    ("weather_map", {"cloud_type": float("nan")}, r"cloud_type must be finite"),
    ("weather_map", {"cloud_type_variation": 2.0}, r"cloud_type_variation must be in \[0, 1\]"),
    ("weather_map", {"perlin_contrast": 0.0}, r"perlin_contrast must be in \(0, inf\), got 0\.0"),
    ("weather_map", {"worley_octaves": 9}, r"worley_octaves must be in \[1, 8\]"),
    ("weather_map", {"size": 16384}, r"size must be a power of two in \[4, 8192\]"),
]


@pytest.mark.spec("vc-A13")
@pytest.mark.parametrize("kind,bad,msg", BAD_SETTINGS)
def test_settings_validation_names_the_field(kind, bad, msg):
    field = next(iter(bad))
    with pytest.raises(ValueError, match="^" + msg):
        T.SETTINGS[kind](**bad)
    with pytest.raises(ValueError, match="^" + msg):
        T.texture_settings(kind, **bad)
    if (kind == "base_shape" and field in K.BASE_SHAPE_FIELDS and field != "combination"
            and len(bad.get("worley_weights", (0, 0, 0))) == 3):
        # the vc-A13 entry checks a look-alike settings object (not validated when built): C and Warp name the field
        look_alike = SimpleNamespace(**{**asdict(T.BaseShapeSettings()), **bad})
        assert pywarp.equation("vc-A13")(look_alike) == field
        assert pywarp.equation("vc-A13", impl="c")(look_alike) == field
    # the C check names the same field
    with pytest.raises(ValueError, match=rf"^{field} "):
        T.texture_settings(kind, impl="c", **bad)


@pytest.mark.spec("vc-A13")
def test_settings_types_and_kinds():
    with pytest.raises(TypeError, match=r"^size must be an integer, got 128\.0"):
        T.BaseShapeSettings(size=128.0)
    with pytest.raises(TypeError, match=r"^gamma must be a number, got '2'"):
        T.DetailShapeSettings(gamma="2")
    with pytest.raises(TypeError, match=r"^perlin_octaves must be an integer, got True"):
        T.BaseShapeSettings(perlin_octaves=True)
    with pytest.raises(ValueError, match=r"^kind must be one of 'base_shape'"):
        T.texture_settings("sky")
    with pytest.raises(TypeError, match="unexpected keyword argument 'octaves'"):
        T.BaseShapeSettings(octaves=3)
    s = T.BaseShapeSettings(worley_weights=[1, 0.5, 0.25], seed=np.uint32(7), gamma=np.float32(2))
    assert s.worley_weights == (1.0, 0.5, 0.25) and type(s.seed) is int and type(s.gamma) is float
    assert T.texture_settings("curl_noise", size=64) == T.CurlNoiseSettings(size=64)
    for impl in ("warp", "c"):
        assert pywarp.equation("vc-A13", impl=impl)(T.BaseShapeSettings()) is None  # the defaults are valid
    assert T.texture_settings("weather_map", impl="c", coverage=0.3) == T.WeatherMapSettings(coverage=0.3)
    with pytest.raises(AttributeError):
        s.size = 64  # frozen


@pytest.mark.spec("vc-A13")
def test_settings_validation_python_c_and_warp_agree_on_random_settings(rng):
    """The first invalid field is the same for the Python dataclass, the C check and the Warp twin
    (base_shape_settings_code), over random settings of which about half are invalid."""
    ffi, lib = _cclouds.ffi(), _cclouds.lib()
    n = 400
    cols = dict(size=rng.choice([2, 4, 8, 12, 64, 128, 512, 1024], n),
                perlin_octaves=rng.integers(-1, 11, n), perlin_frequency=rng.integers(-2, 1100, n),
                worley_cells=rng.integers(-1, 600, n),
                w0=rng.choice([0.0, 0.3, 1.0, -1.0, np.nan], n, p=[0.1, 0.4, 0.4, 0.05, 0.05]),
                w1=rng.choice([0.0, 0.5, -0.5, np.inf], n, p=[0.3, 0.6, 0.05, 0.05]),
                w2=rng.choice([0.0, 0.25, -0.1], n, p=[0.3, 0.65, 0.05]),
                combination=rng.integers(0, 7, n), gamma=rng.choice([1.0, 2.2, 0.0, -1.0, np.inf], n,
                                                                      p=[0.4, 0.4, 0.1, 0.05, 0.05]))
    codes = TG.base_shape_settings_codes(cols["size"], cols["perlin_octaves"], cols["perlin_frequency"],
                                        cols["worley_cells"], cols["w0"], cols["w1"], cols["w2"], cols["combination"],
                                        cols["gamma"])
    names = list(COMBINATIONS)
    n_invalid = 0
    for i in range(n):
        st = ffi.new("ccl_base_shape_settings *")
        st.size, st.perlin_octaves = int(cols["size"][i]), int(cols["perlin_octaves"][i])
        st.perlin_frequency, st.worley_cells = int(cols["perlin_frequency"][i]), int(cols["worley_cells"][i])
        st.worley_weights = [float(cols["w0"][i]), float(cols["w1"][i]), float(cols["w2"][i])]
        st.combination, st.gamma = int(cols["combination"][i]), float(cols["gamma"][i])
        out = ffi.new("const char **")
        c_field = ffi.string(out[0]).decode() if lib.ccl_texgen_base_shape_settings_check(st, out) else None
        comb = int(cols["combination"][i])
        kw = dict(size=int(cols["size"][i]), perlin_octaves=int(cols["perlin_octaves"][i]),
                  perlin_frequency=int(cols["perlin_frequency"][i]), worley_cells=int(cols["worley_cells"][i]),
                  worley_weights=(cols["w0"][i], cols["w1"][i], cols["w2"][i]),
                  combination=names[comb] if 0 <= comb < len(names) else f"mode{comb}", gamma=cols["gamma"][i])
        try:
            T.BaseShapeSettings(**kw)
            py_field = None
        except ValueError as exc:
            py_field = re.match(r"(\w+) ", str(exc)).group(1)
        warp_field = None if codes[i] == 0 else K.BASE_SHAPE_FIELDS[codes[i] - 1]
        assert py_field == c_field == warp_field, (kw, py_field, c_field, warp_field)
        if i < 60 and 0 <= comb < len(names):  # the vc-A13 entry on the same values (a few: one launch each)
            entry = pywarp.equation("vc-A13", impl="c" if i % 2 else "warp")
            assert entry(SimpleNamespace(**kw)) == c_field, (kw, c_field)
        n_invalid += c_field is not None
    assert 0.3 * n < n_invalid < 0.95 * n


# ---------------------------------------------------------------------------------------------------------------------
# generator classes (vc-A32) and the cache
# ---------------------------------------------------------------------------------------------------------------------

SMALL = dict(base_shape=T.BaseShapeSettings(size=8), detail_shape=T.DetailShapeSettings(size=8),
             curl_noise=T.CurlNoiseSettings(size=16), weather_map=T.WeatherMapSettings(size=16))


@pytest.mark.spec("vc-A9", "vc-A10", "vc-A11", "vc-A12", "vc-A32")
def test_generator_interface_and_user_generator(tmp_path):
    with pytest.raises(TypeError, match="abstract"):
        T.TextureGenerator()

    class Flat(T.TextureGenerator):  # a user's own generator: only the four methods
        def base_shape(self, settings=None):
            return np.full((4, 4, 4, 4), 0.5, np.float32)

        def detail_shape(self, settings=None):
            return np.zeros((4, 4, 4, 3), np.float32)

        def curl_noise(self, settings=None):
            return np.zeros((4, 4, 2), np.float32)

        def weather_map(self, settings=None):
            return np.ones((4, 8, 4), np.float32)

    tex = Flat().textures()
    assert isinstance(tex, T.CloudTextures)

    class Broken(Flat):
        def base_shape(self, settings=None):
            return np.full((4, 4, 4, 4), 1.5, np.float32)

    with pytest.raises(ValueError, match=r"^base_shape values must be in \[0, 1\]"):
        Broken().textures()
    with pytest.raises(ValueError, match=r"^detail_shape must have shape \(n, n, n, 3\)"):
        T.CloudTextures(tex.base_shape, np.zeros((4, 4, 6, 3), np.float32), tex.curl_noise, tex.weather_map)

    for impl in ("warp", "c"):
        gen = T.BasicTextureGenerator(impl=impl, cache=T.TextureCache(tmp_path / impl))
        got = gen.textures(**SMALL)
        for kind, s in SMALL.items():
            arr = getattr(got, kind)
            assert arr.shape == s.shape
            np.testing.assert_array_equal(arr, T.generate(kind, s, impl=impl))
        with pytest.raises(TypeError, match="settings must be a BaseShapeSettings"):
            gen.base_shape(T.DetailShapeSettings(size=8))
    with pytest.raises(ValueError, match="impl must be 'warp' or 'c'"):
        T.BasicTextureGenerator(impl="cuda")


@pytest.mark.spec("vc-A9", "vc-A13")
def test_cache_hit_returns_identical_data(tmp_path):
    cache = T.TextureCache(tmp_path)
    gen = T.BasicTextureGenerator(cache=cache)
    s = T.BaseShapeSettings(size=8, seed=5)
    first = gen.base_shape(s)
    assert cache.stats == {"memory_hits": 0, "disk_hits": 0, "misses": 1, "corrupt": 0}
    assert not first.flags.writeable  # the cached array cannot be modified by a caller
    again = gen.base_shape(T.BaseShapeSettings(size=8, seed=5))  # an equal settings object
    assert again is first and cache.stats["memory_hits"] == 1
    entries = list((tmp_path / "textures").glob("base_shape-*.pwtex"))
    assert len(entries) == 1
    # a new process (new cache object, same directory): served from disk, bit-identical
    cache2 = T.TextureCache(tmp_path)
    disk = T.BasicTextureGenerator(cache=cache2).base_shape(s)
    assert cache2.stats["disk_hits"] == 1 and cache2.stats["misses"] == 0
    np.testing.assert_array_equal(disk, first)
    np.testing.assert_array_equal(disk, T.generate("base_shape", s))
    # other settings, implementation or kind: other keys
    keys = {T.TextureCache.key("base_shape", s, "warp", "cpu"),
            T.TextureCache.key("base_shape", T.BaseShapeSettings(size=8, seed=6), "warp", "cpu"),
            T.TextureCache.key("base_shape", s, "c", "cpu"),
            T.TextureCache.key("base_shape", T.BaseShapeSettings(size=8, seed=5, gamma=1.5), "warp", "cpu")}
    assert len(keys) == 4
    assert T.TextureCache.key("base_shape", s, "warp", "cpu") == T.TextureCache.key("base_shape", s, "warp", "cpu")
    # no caching at all
    assert T.BasicTextureGenerator(cache=False).base_shape(s) is not first


@pytest.mark.spec("vc-A9")
@pytest.mark.parametrize("damage", ["flip_byte", "truncate", "bad_header", "wrong_shape"])
def test_cache_corrupt_entry_is_detected_and_regenerated(tmp_path, damage):
    s = T.DetailShapeSettings(size=8, seed=1)
    good = T.BasicTextureGenerator(cache=T.TextureCache(tmp_path)).detail_shape(s)
    (entry,) = (tmp_path / "textures").glob("detail_shape-*.pwtex")
    data = bytearray(entry.read_bytes())
    if damage == "flip_byte":
        data[-5] ^= 0xFF
    elif damage == "truncate":
        data = data[: len(data) // 2]
    elif damage == "bad_header":
        data[:8] = b"GARBAGE!"
    else:  # a well-formed entry of another texture written under this key
        import hashlib
        import io

        buf = io.BytesIO()
        np.save(buf, np.zeros((4, 4, 4, 3), np.float32))
        payload = buf.getvalue()
        data = bytearray(b"PWTEX01\n" + hashlib.sha256(payload).digest() + payload)
    entry.write_bytes(bytes(data))
    cache = T.TextureCache(tmp_path)
    with pytest.warns(T.TextureCacheWarning, match="corrupt texture cache entry"):
        again = T.BasicTextureGenerator(cache=cache).detail_shape(s)
    assert cache.stats["corrupt"] == 1 and cache.stats["misses"] == 1
    np.testing.assert_array_equal(again, good)
    # the entry was rewritten: a fresh cache reads it without complaint
    cache3 = T.TextureCache(tmp_path)
    np.testing.assert_array_equal(T.BasicTextureGenerator(cache=cache3).detail_shape(s), good)
    assert cache3.stats["disk_hits"] == 1 and cache3.stats["corrupt"] == 0


@pytest.mark.spec("vc-A9")
def test_cache_writes_are_atomic(tmp_path, monkeypatch):
    s = T.DetailShapeSettings(size=4)
    tdir = tmp_path / "textures"
    T.generate("detail_shape", s)  # load the Warp module first: Warp's own kernel cache must not see the patch

    def interrupted(*a, **k):
        raise KeyboardInterrupt  # the run is interrupted between writing the temporary file and publishing it

    monkeypatch.setattr(os, "replace", interrupted)
    with pytest.raises(KeyboardInterrupt):
        T.BasicTextureGenerator(cache=T.TextureCache(tmp_path)).detail_shape(s)
    assert list(tdir.iterdir()) == []  # neither a partial entry nor a stray temporary file
    monkeypatch.setattr(os, "replace", lambda *a, **k: (_ for _ in ()).throw(OSError(28, "No space left")))
    with pytest.warns(T.TextureCacheWarning, match="could not write the texture cache entry"):
        arr = T.BasicTextureGenerator(cache=T.TextureCache(tmp_path)).detail_shape(s)
    assert arr.shape == (4, 4, 4, 3) and list(tdir.iterdir()) == []
    monkeypatch.undo()
    T.BasicTextureGenerator(cache=T.TextureCache(tmp_path)).detail_shape(s)
    assert [p.suffix for p in tdir.iterdir()] == [".pwtex"]


@pytest.mark.spec("vc-A9")
def test_cache_directory_from_environment(monkeypatch, tmp_path):
    monkeypatch.delenv("PYWARP_CACHE_DIR", raising=False)
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    assert T.cache_dir() == Path.home() / ".cache" / "pywarp"
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert T.cache_dir() == tmp_path / "xdg" / "pywarp"
    monkeypatch.setenv("PYWARP_CACHE_DIR", str(tmp_path / "mine"))
    assert T.cache_dir() == tmp_path / "mine"
    cache = T.TextureCache()
    T.BasicTextureGenerator(cache=cache).curl_noise(T.CurlNoiseSettings(size=4))
    assert len(list((tmp_path / "mine" / "textures").glob("curl_noise-*.pwtex"))) == 1


@pytest.mark.spec("vc-A9")
def test_cache_memory_budget_drops_least_recently_used(tmp_path):
    cache = T.TextureCache(tmp_path, disk=False, max_memory_bytes=3 * 8 ** 3 * 4 * 4)
    gen = T.BasicTextureGenerator(cache=cache)
    arrs = [gen.base_shape(T.BaseShapeSettings(size=8, seed=k)) for k in range(4)]
    assert cache.stats["misses"] == 4 and len(cache._mem) == 3
    assert gen.base_shape(T.BaseShapeSettings(size=8, seed=3)) is arrs[3]
    gen.base_shape(T.BaseShapeSettings(size=8, seed=0))  # dropped: generated again
    assert cache.stats["misses"] == 5 and not list(tmp_path.iterdir())
