"""Procedural noise (vc §2.3.2, §4.3.1) -- Warp twins of ``cclouds/noise.h``.

* The interpolants (vc-2.19, vc-2.20, lerp, cosine) and remap (vc-2.27) are in :mod:`pywarp.kernels.interp`, the PCG
  hash in :mod:`pywarp.kernels.hash`.
* Perlin gradient noise (vc-A1, vc-A2): with seed 0 it is Ken Perlin's 2002 "Improved Noise" reference implementation
  (ImprovedNoise.java) evaluated in float32. The Warp functions take the 512-entry permutation table as an
  ``wp.array(dtype=wp.int32)`` argument: build it once with :func:`perm_array` (``seed`` -> device array) or
  :func:`perm_table` (NumPy); the C library builds the identical table (``ccl_noise_perm_table``).
  ``period`` 0 = Perlin's lattice (repeats every 256 as a side effect of the table); ``period`` P >= 1 wraps the
  lattice coordinate modulo P before hashing, so ``f(p + P) == f(p)`` exactly.
* Worley noise (vc-A3, A4, A5): ``cells`` cells per unit, periodic with period 1 by construction; F1 in cell units
  clamped to [0, 1]; metric Euclidean or Manhattan; inverse = 1 - F1.
* fBm (vc-2.21, vc-A6): f_i = 2 f_{i-1}, w_i = w_{i-1} / 2, normalised by the sum of the weights. The terrain demo's
  unnormalised 2-D fBm (pt-alg-3.2, Kod 7.9: A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2) is noise_fbm_perlin2; the
  demo's noise (pt-alg-3.1) is the Perlin noise of vc-A1.
* Curl noise (vc-2.22 .. 2.26, vc-A7): central differences with step ``h`` (default 1/256), 2-D stream-function and
  3-D vector-potential readings.
* :func:`noise_perlin_worley` (vc-A8).

Every ``@wp.func`` mirrors the C function of the same name (minus ``ccl_``) operation by operation.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import VARIANT, Arg, Option, declare
from . import VARIANT_THESIS
from .hash import hash_pcg, hash_pcg_py
from .interp import interp_fade_cubic, interp_fade_quintic, interp_lerp, interp_remap

# --- constants ----------------------------------------------------------------------------------------------------

#: Ken Perlin's permutation (ImprovedNoise.java, 2002), the published table.
PERLIN_PERMUTATION = (
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225,
    140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148,
    247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122,
    60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54,
    65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169,
    200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64,
    52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212,
    207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213,
    119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9,
    129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104,
    218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241,
    81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157,
    184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93,
    222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180,
)

#: Default finite-difference step of the curl-noise functions (lattice units), CCL_NOISE_FD_STEP_INV = 256.
FD_STEP = 1.0 / 256.0
#: Offsets of the curl-noise vector potential psi = (N(p), N(p + O1), N(p + O2)) (lattice units).
CURL_OFFSET_1 = (100.25, -57.75, 33.5)
CURL_OFFSET_2 = (-41.5, 88.25, -119.75)

INTERP_QUINTIC = c_constant("CCL_INTERP_QUINTIC", 0)
INTERP_CUBIC = c_constant("CCL_INTERP_CUBIC", 1)
INTERP_LINEAR = c_constant("CCL_INTERP_LINEAR", 2)
INTERP_COSINE = c_constant("CCL_INTERP_COSINE", 3)
WORLEY_EUCLIDEAN = c_constant("CCL_WORLEY_EUCLIDEAN", 0)
WORLEY_MANHATTAN = c_constant("CCL_WORLEY_MANHATTAN", 1)
INTERP = {"quintic": INTERP_QUINTIC, "cubic": INTERP_CUBIC, "linear": INTERP_LINEAR, "cosine": INTERP_COSINE}
METRICS = {"euclidean": WORLEY_EUCLIDEAN, "manhattan": WORLEY_MANHATTAN}
PW_THESIS = c_constant("CCL_PW_THESIS", 0)
PW_GPU_PRO_7 = c_constant("CCL_PW_GPU_PRO_7", 1)
PW_HILLAIRE = c_constant("CCL_PW_HILLAIRE", 2)
PW_PRODUCT = c_constant("CCL_PW_PRODUCT", 3)
PW_AVERAGE = c_constant("CCL_PW_AVERAGE", 4)
COMBINATIONS = {"thesis": PW_THESIS, "gpu_pro_7": PW_GPU_PRO_7, "hillaire": PW_HILLAIRE, "product": PW_PRODUCT,
                "average": PW_AVERAGE}

_PI = wp.constant(3.14159265358979323846)
_FLOOR_LIM = wp.constant(1073741824.0)  # 2^30
_BIG = wp.constant(3.402823466e38)  # FLT_MAX
_OFF_SCALE = wp.constant(1.0 / 8388608.0)  # 2^-23
_O1X, _O1Y, _O1Z = (wp.constant(v) for v in CURL_OFFSET_1)
_O2X, _O2Y, _O2Z = (wp.constant(v) for v in CURL_OFFSET_2)

_U9 = wp.constant(wp.uint32(9))


# --- NumPy-side tables --------------------------------------------------------------------------------------------

@lru_cache(maxsize=64)
def _perm_tuple(seed: int) -> tuple:
    if seed == 0:
        base = list(PERLIN_PERMUTATION)
    else:
        base = list(range(256))
        key = hash_pcg_py(seed)
        for i in range(255, 0, -1):
            j = hash_pcg_py((key + i) & 0xFFFFFFFF) % (i + 1)
            base[i], base[j] = base[j], base[i]
    return tuple(base + base)


def _check_seed(seed) -> int:
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise TypeError(f"seed must be an integer, got {seed!r}")
    if not 0 <= int(seed) <= 0xFFFFFFFF:
        raise ValueError(f"seed must be in [0, 4294967295], got {seed!r}")
    return int(seed)


def perm_table(seed: int = 0) -> np.ndarray:
    """The 512-entry permutation table of ``seed`` (int32; ``ccl_noise_perm_table`` builds the same one).

    Seed 0 is Perlin's published table; other seeds shuffle the identity by Fisher-Yates, i = 255 .. 1,
    j = H(H(seed) + i) mod (i + 1), H = the PCG hash. Entries 256..511 repeat 0..255.
    """
    return np.array(_perm_tuple(_check_seed(seed)), dtype=np.int32)


_PERM_ARRAYS: dict = {}


def perm_array(seed: int = 0, device: str | None = None):
    """The permutation table of ``seed`` as a ``wp.array(dtype=wp.int32)`` on ``device`` (cached)."""
    from ..core.runtime import resolve_device

    dev = resolve_device(device)
    key = (_check_seed(seed), str(dev))
    arr = _PERM_ARRAYS.get(key)
    if arr is None:
        arr = wp.array(perm_table(key[0]), dtype=wp.int32, device=dev)
        if len(_PERM_ARRAYS) > 256:
            _PERM_ARRAYS.clear()
        _PERM_ARRAYS[key] = arr
    return arr


# --- lattice helpers -----------------------------------------------------------------------------------------------

@wp.func
def _floor_to_int(f: float) -> int:
    g = f
    if not (g >= -_FLOOR_LIM):
        g = -_FLOOR_LIM
    if g > _FLOOR_LIM:
        g = _FLOOR_LIM
    return int(g)


@wp.func
def _pmod(i: int, n: int) -> int:
    r = i % n
    if r < 0:
        r = r + n
    return r


@wp.func
def _wrap_lattice(i: int, period: int) -> int:
    if period > 0:
        return _pmod(i, period) & 255
    return i & 255


# --- argument domains and cross-argument checks --------------------------------------------------------------------

_COORD_LIM = float(2 ** 24)  # float32 keeps a fractional part below 2^24
#: Upper bound of frequency * 2^(octaves - 1) of noise_fbm_perlin3 (the C CCL_NOISE_FBM_MAX_FREQUENCY): 2^24 lattice
#: cells per unit, the position limit of the noise itself; keeps every octave's frequency finite (0 * Inf was NaN).
FBM_MAX_FREQUENCY = float(2 ** 24)
_CURL_LIM = float(2 ** 23)  # the curl potential adds offsets of up to ~120 lattice units


def _coord(name, doc, lim=_COORD_LIM):
    # open bounds: float32 keeps a fractional part only strictly below 2^24 (the C headers' |x| < 2^24)
    return Arg(name, doc, lo=-lim, hi=lim, lo_open=True, hi_open=True)


_X = _coord("x", "x coordinate (lattice units of the noise)")
_Y = _coord("y", "y coordinate")
_Z = _coord("z", "z coordinate")
_SEED = Arg("seed", "uint32 seed; 0 = Ken Perlin's reference permutation", lo=0, hi=4294967295, dtype="uint32",
            default=0)
_PERIOD = Arg("period", "0 = Perlin's lattice (repeats every 256), P >= 1 = periodic with integer period P",
              lo=0, hi=2 ** 30, dtype="int32", default=0)
_CELLS = Arg("cells", "Worley cells per unit period (the noise has period 1 on every axis)", lo=1, hi=2 ** 16,
             dtype="int32")
_WSEED = Arg("seed", "uint32 seed of the feature-point hash", lo=0, hi=4294967295, dtype="uint32", default=0)
_H = Arg("h", "central-difference step (lattice units)", lo=0.0, hi=0.25, lo_open=True, default=FD_STEP)
_CX, _CY, _CZ = (_coord(n, f"{n} coordinate (lattice units)", _CURL_LIM) for n in "xyz")

METRIC = Option("metric", METRICS, "euclidean", "distance: 'euclidean' (L2, classic) or 'manhattan' (L1)")
INVERSE = Option("inverse", {False: 0, True: 1}, False, "True: 1 - F1 (inverse Worley, used for clouds)")
COMBINATION = Option("combination", COMBINATIONS, "thesis",
                     "'thesis' remap(P,0,1,W,1)^2 (default, §4.3.1); 'gpu_pro_7' clamp(remap(P,W,1,0,1),0,1); "
                     "'hillaire' remap(P,0,1,W,1); 'product' P*W; 'average' (P+W)/2")


def _max_abs(x, y, z) -> np.ndarray:
    """max(|x|, |y|, |z|) element-wise in float64 (broadcast)."""
    return np.maximum(np.maximum(np.abs(x.astype(np.float64)), np.abs(y.astype(np.float64))),
                      np.abs(z.astype(np.float64)))


def _check_worley(x, y, z, cells, **_):
    scaled = _max_abs(x, y, z) * cells
    if np.any(scaled >= _COORD_LIM):
        raise ValueError(f"cells * |x|, |y|, |z| must be < 2^24 (float32 position precision), got {scaled.max():g}")


def _check_worley_bruteforce(x, y, z, cells, **_):
    if np.any(cells > 64):
        raise ValueError(f"cells must be in [1, 64] for the O(cells^3) brute force, got {int(cells.max())}")


def _check_fbm_perlin(x, y, z, octaves, frequency, seed, period, **_):
    top = 2.0 ** (octaves.astype(np.float64) - 1)
    if np.any(period * top > 2.0 ** 30):
        raise ValueError("period must satisfy period * 2^(octaves - 1) <= 2^30")
    if np.any(frequency.astype(np.float64) * top > FBM_MAX_FREQUENCY):
        raise ValueError(f"frequency * 2^(octaves - 1) must be <= 2^24 (CCL_NOISE_FBM_MAX_FREQUENCY), got "
                         f"{float(np.max(frequency.astype(np.float64) * top)):g}")
    if np.any(_max_abs(x, y, z) * frequency * top >= _COORD_LIM):
        raise ValueError("frequency * 2^(octaves - 1) * |x|, |y|, |z| must be < 2^24 (float32 position precision)")


def _check_fbm_worley(x, y, z, octaves, cells, **_):
    top = cells.astype(np.float64) * 2.0 ** (octaves.astype(np.float64) - 1)
    if np.any(top > 2.0 ** 16):
        raise ValueError("cells must satisfy cells * 2^(octaves - 1) <= 65536")
    if np.any(_max_abs(x, y, z) * top >= _COORD_LIM):
        raise ValueError("cells * 2^(octaves - 1) * |x|, |y|, |z| must be < 2^24 (float32 position precision)")


_PERLIN_REF = ("K. Perlin, Improving Noise, SIGGRAPH 2002 (reference code ImprovedNoise.java, "
               "https://mrl.cs.nyu.edu/~perlin/noise/)",
               "K. Perlin, An Image Synthesizer, SIGGRAPH 1985")
_WORLEY_REF = ("S. Worley, A Cellular Texture Basis Function, SIGGRAPH 1996",)
_PCG_REF = "M. Jarzynski & M. Olano, Hash Functions for GPU Rendering, JCGT 9(3), 2020 (PCG hash)"
_CURL_REF = ("R. Bridson, J. Hourihan & M. Nordenstam, Curl-Noise for Procedural Fluid Flow, SIGGRAPH 2007",)
_CURL_SUMMARY = ("Central differences with step h (default 1/256 lattice units) over float32 Perlin noise N "
                 "(seed, period as in vc-A1); potential psi = (N(p), N(p + o1), N(p + o2)), o1 = (100.25, -57.75, "
                 "33.5), o2 = (-41.5, 88.25, -119.75).")

#: The permutation table of a Perlin entry is computed from its ``seed`` argument: the Warp functions take the table
#: (``perm``), the C functions the seed; the evaluator launches once per distinct seed.
_PERM = {"perm": ("seed", perm_array)}


def _fbm_perlin_samples(rng, n):
    """Valid (x, y, z, octaves, frequency, period) for the contract tests: frequency * 2^(octaves - 1) * |p| < 2^24
    and period * 2^(octaves - 1) <= 2^30. The first sample has one octave, frequency 1/2 and |p| * frequency < 2, so
    every edge of x, y, z, octaves, frequency and period stays valid when set alone."""
    octaves = rng.integers(1, 9, n).astype(np.int32)
    octaves[0] = 1
    frequency = rng.uniform(0.5, 4.0, n).astype(np.float32)
    frequency[0] = 0.5  # x at its edge (just below 2^24) times the frequency stays below 2^24
    p = rng.uniform(-0.45, 0.45, (3, n)).astype(np.float32)
    return {"x": p[0], "y": p[1], "z": p[2], "octaves": octaves, "frequency": frequency,
            "seed": rng.integers(0, 3, n).astype(np.uint32), "period": rng.integers(0, 17, n).astype(np.int32)}


def _worley_samples(rng, n):
    """Valid (x, y, z, cells, seed): cells * |p| < 2^24. The first sample has one cell, so the edges of x, y, z (just
    below 2^24) stay valid when set alone."""
    cells = rng.integers(1, 17, n).astype(np.int32)
    cells[0] = 1
    p = rng.uniform(-3.0, 3.0, (3, n)).astype(np.float32)
    return {"x": p[0], "y": p[1], "z": p[2], "cells": cells,
            "seed": rng.integers(0, 2 ** 32, n, dtype=np.uint64).astype(np.uint32)}


def _fbm_worley_samples(rng, n):
    """Valid (x, y, z, octaves, cells, seed): cells * 2^(octaves - 1) <= 2^16. The first sample has one octave and
    one cell, so the edges octaves = 16 and cells = 65536 stay valid when set alone."""
    octaves = rng.integers(1, 5, n).astype(np.int32)
    cells = rng.integers(1, 9, n).astype(np.int32)
    octaves[0], cells[0] = 1, 1
    p = rng.uniform(-2.0, 2.0, (3, n)).astype(np.float32)
    return {"x": p[0], "y": p[1], "z": p[2], "octaves": octaves, "cells": cells,
            "seed": rng.integers(0, 2 ** 32, n, dtype=np.uint64).astype(np.uint32)}


# --- Perlin (vc-A1, vc-A2) -----------------------------------------------------------------------------------------

@wp.func
def _grad3(hash: int, x: float, y: float, z: float) -> float:
    """Perlin's grad(): the low 4 bits select one of the 12 cube-edge gradients."""
    h = hash & 15
    u = y
    if h < 8:
        u = x
    v = z
    if h < 4:
        v = y
    elif h == 12 or h == 14:
        v = x
    if (h & 1) != 0:
        u = -u
    if (h & 2) != 0:
        v = -v
    return u + v


@declare("vc-A1", "pt-alg-3.1", c="ccl_noise_perlin3",
         args=(_X, _Y, _Z, _SEED, _PERIOD), outputs=("n",), derived=_PERM,
         summary="3-D Perlin gradient noise; seed 0 is Ken Perlin's 2002 ImprovedNoise reference exactly (his "
                 "permutation, 12 edge gradients via hash & 15, quintic fade 2.20, trilinear lerp), in float32; other "
                 "seeds use a Fisher-Yates permutation driven by the PCG hash (perm_table / ccl_noise_perm_table). "
                 "Output about [-1, 1], 0 at lattice points. period 0 = Perlin's lattice, period >= 1 = exactly "
                 "periodic (vc-A2). Also: 2-D noise ccl_noise_perlin2 / noise_perlin2 (= perlin3(x, y, 0), with a "
                 "choice of interpolant quintic/cubic/linear/cosine for vc-fig-2.5, NumPy helper pywarp.perlin2()), the "
                 "table-taking fast forms ccl_noise_perlin3_perm, and the interpolants ccl_interp_lerp, "
                 "ccl_interp_cosine (vc-fig-2.6). Warp functions take the permutation table (perm_array(seed)). "
                 "pt-alg-3.1: the terrain demo's undefined noise() is this noise (its 2-D slice z = 0, "
                 "noise_perlin2, inside the fBm of pt-alg-3.2). The text's steps (lattice, pseudo-random gradient per "
                 "corner, dot products with p - c, weights by distance) are these, except that Perlin's 12 edge "
                 "gradients have length sqrt(2), not 1 -- a fixed scale of the output. Range of the 2-D slice: [-1, 1] "
                 "(the sqrt(n)/2 |g| bound of n-D gradient noise, = 1 for n = 2, |g| = sqrt(2); measured max 0.997 "
                 "on a 24 x 24 grid in each of the 256^2 lattice cells), so the demo's fBm obeys "
                 "|fBm| <= 2 (1 - 0.5^octaves). 3-D: bound sqrt(3/2) = 1.22, measured max 0.995.",
         references=_PERLIN_REF + (_PCG_REF,))
@wp.func
def noise_perlin3(x: float, y: float, z: float, perm: wp.array(dtype=wp.int32), period: int) -> float:
    """vc-A1: 3-D Perlin gradient noise (seed 0 table = Perlin's 2002 reference); period 0 or >= 1 (vc-A2)."""
    if not (wp.isfinite(x) and wp.isfinite(y) and wp.isfinite(z)):
        return wp.nan
    fx = wp.floor(x)
    fy = wp.floor(y)
    fz = wp.floor(z)
    ix = _floor_to_int(fx)
    iy = _floor_to_int(fy)
    iz = _floor_to_int(fz)
    x1 = _wrap_lattice(ix + 1, period)
    y1 = _wrap_lattice(iy + 1, period)
    z1 = _wrap_lattice(iz + 1, period)
    x0 = _wrap_lattice(ix, period)
    y0 = _wrap_lattice(iy, period)
    z0 = _wrap_lattice(iz, period)
    rx = x - fx
    ry = y - fy
    rz = z - fz
    u = interp_fade_quintic(rx)
    v = interp_fade_quintic(ry)
    w = interp_fade_quintic(rz)
    a0 = perm[x0] + y0
    a1 = perm[x0] + y1
    b0 = perm[x1] + y0
    b1 = perm[x1] + y1
    aa = perm[perm[a0] + z0]
    ab = perm[perm[a1] + z0]
    ba = perm[perm[b0] + z0]
    bb = perm[perm[b1] + z0]
    aa1 = perm[perm[a0] + z1]
    ab1 = perm[perm[a1] + z1]
    ba1 = perm[perm[b0] + z1]
    bb1 = perm[perm[b1] + z1]
    return interp_lerp(
        w,
        interp_lerp(v, interp_lerp(u, _grad3(aa, rx, ry, rz), _grad3(ba, rx - 1.0, ry, rz)),
                   interp_lerp(u, _grad3(ab, rx, ry - 1.0, rz), _grad3(bb, rx - 1.0, ry - 1.0, rz))),
        interp_lerp(v, interp_lerp(u, _grad3(aa1, rx, ry, rz - 1.0), _grad3(ba1, rx - 1.0, ry, rz - 1.0)),
                   interp_lerp(u, _grad3(ab1, rx, ry - 1.0, rz - 1.0), _grad3(bb1, rx - 1.0, ry - 1.0, rz - 1.0))))


@declare("vc-A2", c="ccl_noise_perlin3_tiled",
         args=(_X, _Y, _Z, Arg("period", "integer period on every axis (lattice units)", lo=1, hi=2 ** 30,
                               dtype="int32"), _SEED),
         outputs=("n",), derived=_PERM,
         summary="Seamless Perlin noise: noise_perlin3 with a required period P >= 1; the lattice coordinate is "
                 "reduced modulo P before hashing, so f(p + P e_i) == f(p) exactly when p + P is representable in "
                 "float32.",
         references=_PERLIN_REF[:1])
@wp.func
def noise_perlin3_tiled(x: float, y: float, z: float, period: int, perm: wp.array(dtype=wp.int32)) -> float:
    """vc-A2: noise_perlin3 with a required period >= 1."""
    return noise_perlin3(x, y, z, perm, period)


@wp.func
def _interp_weight(t: float, interp: int) -> float:
    if interp == INTERP_CUBIC:
        return interp_fade_cubic(t)
    if interp == INTERP_LINEAR:
        return t
    if interp == INTERP_COSINE:
        return (1.0 - wp.cos(_PI * t)) * 0.5
    return interp_fade_quintic(t)


@wp.func
def noise_perlin2(x: float, y: float, perm: wp.array(dtype=wp.int32), period: int, interp: int) -> float:
    """vc-A1 in 2-D: equal to noise_perlin3(x, y, 0) for interp 0 (quintic); 1 cubic, 2 linear, 3 cosine."""
    if not (wp.isfinite(x) and wp.isfinite(y)):
        return wp.nan
    fx = wp.floor(x)
    fy = wp.floor(y)
    ix = _floor_to_int(fx)
    iy = _floor_to_int(fy)
    x1 = _wrap_lattice(ix + 1, period)
    y1 = _wrap_lattice(iy + 1, period)
    x0 = _wrap_lattice(ix, period)
    y0 = _wrap_lattice(iy, period)
    z0 = 0
    rx = x - fx
    ry = y - fy
    u = _interp_weight(rx, interp)
    v = _interp_weight(ry, interp)
    return interp_lerp(
        v,
        interp_lerp(u, _grad3(perm[perm[perm[x0] + y0] + z0], rx, ry, 0.0),
                   _grad3(perm[perm[perm[x1] + y0] + z0], rx - 1.0, ry, 0.0)),
        interp_lerp(u, _grad3(perm[perm[perm[x0] + y1] + z0], rx, ry - 1.0, 0.0),
                   _grad3(perm[perm[perm[x1] + y1] + z0], rx - 1.0, ry - 1.0, 0.0)))


# --- Worley (vc-A3, vc-A4, vc-A5) ----------------------------------------------------------------------------------

@wp.func
def _worley_offsets(h0: wp.uint32) -> wp.vec3:
    h1 = hash_pcg(h0)
    h2 = hash_pcg(h1)
    return wp.vec3(float(h0 >> _U9) * _OFF_SCALE, float(h1 >> _U9) * _OFF_SCALE, float(h2 >> _U9) * _OFF_SCALE)


@wp.func
def noise_worley_feature(ix: int, iy: int, iz: int, cells: int, seed: wp.uint32) -> wp.vec3:
    """Feature-point offset (cell units, [0, 1)^3) of cell (ix, iy, iz), indices wrapped modulo ``cells``."""
    c = wp.max(cells, 1)
    h0 = hash_pcg(wp.uint32(_pmod(ix, c)) + hash_pcg(wp.uint32(_pmod(iy, c)) +
                                                        hash_pcg(wp.uint32(_pmod(iz, c)) + hash_pcg(seed))))
    return _worley_offsets(h0)


@declare("vc-A3", c="ccl_noise_worley3",
         args=(_X, _Y, _Z, _CELLS, _WSEED), options=(METRIC, INVERSE), outputs=("f1",), check=_check_worley,
         samples=_worley_samples,
         summary="Worley (cellular) noise F1, periodic with period 1 on every axis (cells per unit = cells; cell "
                 "indices wrapped modulo cells, vc-A5). One feature point per cell from the PCG hash of the wrapped "
                 "cell index and the seed (ccl_noise_worley_feature / noise_worley_feature); the 27 neighbouring cells "
                 "are searched. F1 = distance in cell units clamped to [0, 1] (the clamp makes the 27-cell search "
                 "exact). metric='manhattan' gives L1 distances and inverse=True gives 1 - F1 (vc-A4).",
         references=_WORLEY_REF + (_PCG_REF,))
@wp.func
def noise_worley3(x: float, y: float, z: float, cells: int, seed: wp.uint32, metric: int, inverse: int) -> float:
    """vc-A3/A4/A5: Worley F1 (cell units, clamped to [0, 1]), period 1; metric 0 = Euclidean, 1 = Manhattan."""
    c = wp.max(cells, 1)
    if not (wp.isfinite(x) and wp.isfinite(y) and wp.isfinite(z)):
        return wp.nan
    hseed = hash_pcg(seed)
    qx = x * float(c)
    qy = y * float(c)
    qz = z * float(c)
    fx = wp.floor(qx)
    fy = wp.floor(qy)
    fz = wp.floor(qz)
    ix = _floor_to_int(fx)
    iy = _floor_to_int(fy)
    iz = _floor_to_int(fz)
    tx = qx - fx
    ty = qy - fy
    tz = qz - fz
    best = _BIG
    for dz in range(-1, 2):
        hz = hash_pcg(wp.uint32(_pmod(iz + dz, c)) + hseed)
        for dy in range(-1, 2):
            hy = hash_pcg(wp.uint32(_pmod(iy + dy, c)) + hz)
            for dx in range(-1, 2):
                o = _worley_offsets(hash_pcg(wp.uint32(_pmod(ix + dx, c)) + hy))
                ddx = (float(dx) + o[0]) - tx
                ddy = (float(dy) + o[1]) - ty
                ddz = (float(dz) + o[2]) - tz
                d = float(0.0)
                if metric == WORLEY_MANHATTAN:
                    d = wp.abs(ddx) + wp.abs(ddy) + wp.abs(ddz)
                else:
                    d = ddx * ddx + ddy * ddy + ddz * ddz
                if d < best:
                    best = d
    f1 = best
    if metric != WORLEY_MANHATTAN:
        f1 = wp.sqrt(best)
    if f1 > 1.0:
        f1 = 1.0
    if inverse != 0:
        return 1.0 - f1
    return f1


@declare("vc-A4", c="ccl_noise_worley3_variants",
         args=(_X, _Y, _Z, _CELLS, _WSEED), outputs=("classic", "manhattan", "inverse"),
         check=_check_worley, samples=_worley_samples,
         summary="The three Worley variants of vc-fig-2.7 at once: classic (Euclidean F1), Manhattan (L1) F1 and "
                 "inverse 1 - F1; each equals noise_worley3 (vc-A3) with the matching metric/inverse options.",
         references=_WORLEY_REF)
@wp.func
def noise_worley3_variants(x: float, y: float, z: float, cells: int,
                           seed: wp.uint32) -> tuple[float, float, float]:
    """vc-A4: (classic, Manhattan, inverse) Worley at one point, the three panels of vc-fig-2.7."""
    return (noise_worley3(x, y, z, cells, seed, 0, 0), noise_worley3(x, y, z, cells, seed, 1, 0),
            noise_worley3(x, y, z, cells, seed, 0, 1))


@declare("vc-A5", c="ccl_noise_worley3_bruteforce",
         # samples: O(cells^3) per point, so the contract tests draw small lattices (the edge 64 is still checked)
         args=(_X, _Y, _Z, Arg("cells", "cells per unit period", lo=1, hi=64, dtype="int32", sample_range=(1, 4)),
               _WSEED),
         options=(METRIC, INVERSE), outputs=("f1",), check=_check_worley_bruteforce,
         summary="Tileable Worley noise by the literal construction of vc-A5: the cube of cells^3 feature points is "
                 "surrounded by its copies and every point tries all 27 placements of every feature point (O(cells^3) "
                 "per point). A reference: noise_worley3 (vc-A3) gives the same value with the wrapped 27-cell search "
                 "and is the function to use; it is periodic with period 1 by construction.",
         references=_WORLEY_REF)
@wp.func
def noise_worley3_bruteforce(x: float, y: float, z: float, cells: int, seed: wp.uint32, metric: int,
                             inverse: int) -> float:
    """vc-A5 literally: every feature point of the cube in all 27 placements of the surrounding copies."""
    c = wp.clamp(cells, 1, 64)
    if not (wp.isfinite(x) and wp.isfinite(y) and wp.isfinite(z)):
        return wp.nan
    qx = (x - wp.floor(x)) * float(c)
    qy = (y - wp.floor(y)) * float(c)
    qz = (z - wp.floor(z)) * float(c)
    best = _BIG
    for k in range(c):
        for j in range(c):
            for i in range(c):
                o = noise_worley_feature(i, j, k, c, seed)
                for cz in range(-1, 2):
                    for cy in range(-1, 2):
                        for cx in range(-1, 2):
                            ddx = (float(i + cx * c) + o[0]) - qx
                            ddy = (float(j + cy * c) + o[1]) - qy
                            ddz = (float(k + cz * c) + o[2]) - qz
                            d = float(0.0)
                            if metric == WORLEY_MANHATTAN:
                                d = wp.abs(ddx) + wp.abs(ddy) + wp.abs(ddz)
                            else:
                                d = ddx * ddx + ddy * ddy + ddz * ddz
                            if d < best:
                                best = d
    f1 = best
    if metric != WORLEY_MANHATTAN:
        f1 = wp.sqrt(best)
    if f1 > 1.0:
        f1 = 1.0
    if inverse != 0:
        return 1.0 - f1
    return f1


# --- fBm (vc-2.21, vc-A6) ------------------------------------------------------------------------------------------

@declare("vc-2.21", c="ccl_noise_fbm_perlin3",
         args=(_X, _Y, _Z, Arg("octaves", "number of octaves", lo=1, hi=24, dtype="int32"),
               Arg("frequency", "f_0, lattice cells per unit of x; frequency * 2^(octaves - 1) <= 2^24", lo=0.0,
                   hi=FBM_MAX_FREQUENCY, lo_open=True),
               _SEED, Arg("period", "0, or the integer period of octave 0 in its lattice units (octave i: period 2^i); "
                                    "the fBm repeats every period/frequency", lo=0, hi=2 ** 30, dtype="int32",
                          default=0)),
         outputs=("n",), derived=_PERM, check=_check_fbm_perlin, samples=_fbm_perlin_samples,
         summary="fBm N_s(p) = sum_i w_i N(f_i p) / sum_i w_i of Perlin noise with the octave rules of vc-A6 "
                 "(f_0 = frequency, f_i = 2 f_{i-1}, w_0 = 1, w_i = w_{i-1}/2), normalised by the sum of the weights "
                 "so the range stays that of one octave. The Worley counterpart is noise_fbm_worley3 (vc-A6).",
         references=_PERLIN_REF[:1])
@wp.func
def noise_fbm_perlin3(x: float, y: float, z: float, octaves: int, frequency: float, perm: wp.array(dtype=wp.int32),
                      period: int) -> float:
    """vc-2.21/A6: sum_i 2^-i N(2^i f p) / sum_i 2^-i; octave i uses period * 2^i."""
    total = float(0.0)
    wsum = float(0.0)
    amp = float(1.0)
    f = frequency
    per = period
    for _i in range(octaves):
        total += amp * noise_perlin3(x * f, y * f, z * f, perm, per)
        wsum += amp
        f *= 2.0
        amp *= 0.5
        if per > 0 and per <= 0x3FFFFFFF:
            per *= 2
    return total / wsum


def _check_fbm_perlin2(p, octaves, frequency, lacunarity, **_):
    top = frequency.astype(np.float64) * lacunarity.astype(np.float64) ** (octaves.astype(np.float64) - 1)
    reach = np.max(np.abs(p.astype(np.float64)), axis=-1) * top
    if np.any(reach >= _COORD_LIM):
        raise ValueError("p: |p| * frequency * lacunarity^(octaves - 1) must be < 2^24 (float32 position precision), "
                         f"got {reach.max():g}")


def _fbm_perlin2_samples(rng, n):
    """Valid (p, octaves, seed, amplitude, frequency, gain, lacunarity): |p| frequency lacunarity^(octaves-1) < 2^24.
    The first sample has one octave, frequency 1/2 and |p| < 1, so each edge of p, octaves, frequency and lacunarity
    stays valid when set alone."""
    octaves = rng.integers(1, 11, n).astype(np.int32)
    octaves[0] = 1
    frequency = rng.uniform(0.1, 4.0, n).astype(np.float32)
    frequency[0] = 0.5
    lacunarity = rng.uniform(1.0, 3.0, n).astype(np.float32)
    lacunarity[0] = 2.0
    p = rng.uniform(-50.0, 50.0, (n, 2)).astype(np.float32)
    p[0] = (0.3, -0.7)
    return {"p": p, "octaves": octaves, "seed": rng.integers(0, 3, n).astype(np.uint32),
            "amplitude": rng.uniform(0.0, 4.0, n).astype(np.float32), "frequency": frequency,
            "gain": rng.uniform(0.0, 1.0, n).astype(np.float32), "lacunarity": lacunarity}


@declare("pt-alg-3.2", "pt-code-7.9", c="ccl_noise_fbm_perlin2",
         args=(Arg("p", "2-D position (the terrain's (x, z) in Kod 7.9)", lo=-_COORD_LIM, hi=_COORD_LIM, lo_open=True,
                   hi_open=True, sample_range=(-50.0, 50.0)),
               Arg("octaves", "number of octaves N", lo=1, hi=24, dtype="int32"),
               _SEED,
               Arg("amplitude", "A0, amplitude of octave 0 (1.0 printed)", lo=0.0, hi=1e6, default=1.0),
               Arg("frequency", "F0, frequency of octave 0 (0.5 printed)", lo=0.0, hi=1e4, lo_open=True, default=0.5),
               Arg("gain", "g, amplitude ratio of successive octaves (0.5 printed)", lo=0.0, hi=1.0, default=0.5),
               Arg("lacunarity", "lambda, frequency ratio of successive octaves (2.0 printed)", lo=1.0, hi=4.0,
                   default=2.0)),
         outputs=("value",), derived=_PERM, check=_check_fbm_perlin2, samples=_fbm_perlin2_samples,
         summary="The terrain demo's fBm (pt §3.2, Kod 7.9): sum_i A0 g^i N(F0 lambda^i p), i = 0 .. N-1, NOT "
                 "normalised (unlike vc-2.21), in the operation order of Kod 7.9; N = 2-D Perlin noise "
                 "(noise_perlin2, the z = 0 slice of vc-A1 = pt-alg-3.1). Defaults are the printed A0 = 1, F0 = 0.5, "
                 "g = 0.5, lambda = 2; for |N| <= 1, |fBm| <= A0 (1 - g^N) / (1 - g) = 2 (1 - 0.5^N) printed. "
                 "pt-code-7.9 (Kod 7.9, the terrain's fBm) is this function with the defaults (p = (x, z)); the "
                 "terrain scene calls it.",
         references=_PERLIN_REF[:1] + ("F. K. Musgrave, in Ebert et al., Texturing & Modeling, 3rd ed., 2003 "
                                       "(fBm: gain and lacunarity)",))
@wp.func
def noise_fbm_perlin2(p: wp.vec2, octaves: int, perm: wp.array(dtype=wp.int32), amplitude: float, frequency: float,
                      gain: float, lacunarity: float) -> float:
    """pt-alg-3.2: value += amplitude * noise(frequency * p); amplitude *= gain; frequency *= lacunarity."""
    value = float(0.0)
    amp = amplitude
    f = frequency
    for _i in range(octaves):
        value += amp * noise_perlin2(f * p[0], f * p[1], perm, 0, 0)
        amp *= gain
        f *= lacunarity
    return value


@declare("vc-A6", c="ccl_noise_fbm_worley3",
         args=(_X, _Y, _Z, Arg("octaves", "number of octaves", lo=1, hi=16, dtype="int32"),
               Arg("cells", "cells per unit of octave 0 (octave i: cells 2^i)", lo=1, hi=2 ** 16, dtype="int32"),
               _WSEED),
         options=(METRIC, INVERSE), outputs=("n",), check=_check_fbm_worley, samples=_fbm_worley_samples,
         summary="fBm of Worley noise with the vc-A6 octave rules: octave i = noise_worley3 with cells 2^i cells per "
                 "unit and seed + i, weight 2^-i; divided by the sum of the weights, so the result is in [0, 1] and "
                 "periodic with period 1. inverse applies per octave (fBm of inverse Worley, the cloud textures). "
                 "The Perlin counterpart is noise_fbm_perlin3 (vc-2.21).",
         references=_WORLEY_REF)
@wp.func
def noise_fbm_worley3(x: float, y: float, z: float, octaves: int, cells: int, seed: wp.uint32, metric: int,
                      inverse: int) -> float:
    """vc-2.21/A6: sum_i 2^-i W(p; cells 2^i, seed + i) / sum_i 2^-i, period 1."""
    total = float(0.0)
    wsum = float(0.0)
    amp = float(1.0)
    c = cells
    for i in range(octaves):
        total += amp * noise_worley3(x, y, z, c, seed + wp.uint32(i), metric, inverse)
        wsum += amp
        amp *= 0.5
        if c <= 0x3FFFFFFF:
            c *= 2
    return total / wsum


# --- curl noise (vc-2.22 .. vc-2.26, vc-A7) ------------------------------------------------------------------------

@wp.func
def _fd_step(c: float, h: float) -> float:
    """The step actually used at coordinate c: max(h, 2^-20, |c| 2^-22) (two float32 ulps of c at least, so c +- h
    stay distinct where h is below half an ulp; 2^-20 keeps round-off / step finite, also nested; the C fd_step)."""
    hc = wp.abs(c) * 2.384185791015625e-07
    hh = h
    if hh < 9.5367431640625e-07:
        hh = 9.5367431640625e-07
    if hc > hh:
        return hc
    return hh


@wp.func
def _fd_points(c: float, h: float) -> wp.vec2:
    """The abscissae (c + s, c - s), s = _fd_step(c, h); the one overflowing to Inf (within s of FLT_MAX) is c itself:
    a one-sided difference, finite for every finite c (the C fd_points)."""
    s = _fd_step(c, h)
    cp = c + s
    cm = c - s
    if wp.isinf(cp):
        cp = c
    if wp.isinf(cm):
        cm = c
    return wp.vec2(cp, cm)


@wp.func
def _dnoise(perm: wp.array(dtype=wp.int32), period: int, x: float, y: float, z: float, axis_: int, h_: float) -> float:
    """Central difference of noise_perlin3 along ``axis`` with the float spacing actually used."""
    axis = axis_
    c = z
    if axis == 0:
        c = x
    elif axis == 1:
        c = y
    pm = _fd_points(c, h_)
    xp = x
    yp = y
    zp = z
    xm = x
    ym = y
    zm = z
    d = float(0.0)
    if axis == 0:
        xp = pm[0]
        xm = pm[1]
        d = xp - xm
    elif axis == 1:
        yp = pm[0]
        ym = pm[1]
        d = yp - ym
    else:
        zp = pm[0]
        zm = pm[1]
        d = zp - zm
    return (noise_perlin3(xp, yp, zp, perm, period) - noise_perlin3(xm, ym, zm, perm, period)) / d


@declare("vc-2.22", c="ccl_noise_gradient3",
         args=(_CX, _CY, _CZ, _SEED, _PERIOD, _H), outputs=("gradient",), derived=_PERM,
         summary="Nabla operator applied to Perlin noise: (dN/dx, dN/dy, dN/dz). " + _CURL_SUMMARY,
         references=_CURL_REF)
@wp.func
def noise_gradient3(x: float, y: float, z: float, perm: wp.array(dtype=wp.int32), period: int, h: float) -> wp.vec3:
    """vc-2.22: nabla N of Perlin noise by central differences."""
    return wp.vec3(_dnoise(perm, period, x, y, z, 0, h), _dnoise(perm, period, x, y, z, 1, h),
                   _dnoise(perm, period, x, y, z, 2, h))


@declare("vc-2.23", c="ccl_noise_curl3",
         args=(_CX, _CY, _CZ, _SEED, _PERIOD, _H), outputs=("v",), derived=_PERM,
         summary="3-D curl noise v = nabla x psi (2.23) of the offset Perlin vector potential -- reading (ii) of "
                 "vc-A7; divergence-free. Table form ccl_noise_curl3_perm. " + _CURL_SUMMARY,
         references=_CURL_REF)
@wp.func
def noise_curl3(x: float, y: float, z: float, perm: wp.array(dtype=wp.int32), period: int, h: float) -> wp.vec3:
    """vc-2.23 / vc-A7 (ii): v = nabla x psi, psi = (N(p), N(p + o1), N(p + o2))."""
    q1x = x + _O1X
    q1y = y + _O1Y
    q1z = z + _O1Z
    q2x = x + _O2X
    q2y = y + _O2Y
    q2z = z + _O2Z
    vx = _dnoise(perm, period, q2x, q2y, q2z, 1, h) - _dnoise(perm, period, q1x, q1y, q1z, 2, h)
    vy = _dnoise(perm, period, x, y, z, 2, h) - _dnoise(perm, period, q2x, q2y, q2z, 0, h)
    vz = _dnoise(perm, period, q1x, q1y, q1z, 0, h) - _dnoise(perm, period, x, y, z, 1, h)
    return wp.vec3(vx, vy, vz)


@declare("vc-2.24", c="ccl_noise_rot2",
         args=(_CX, _CY, _SEED, _PERIOD, _H), outputs=("rot",), derived=_PERM,
         summary="2-D curl (scalar) dF_y/dx - dF_x/dy of the planar noise field F = (N(p), N(p + o1)), p = (x, y, 0): "
                 "the literal reading of the thesis (two offset evaluations, then the curl) -- a scalar, not a 2-D "
                 "field (vc-A7 ambiguity). Equals the z component of noise_curl3 at z = 0. " + _CURL_SUMMARY,
         references=_CURL_REF)
@wp.func
def noise_rot2(x: float, y: float, perm: wp.array(dtype=wp.int32), period: int, h: float) -> float:
    """vc-2.24: dF_y/dx - dF_x/dy of F = (N(p), N(p + o1)), p = (x, y, 0)."""
    z = float(0.0)
    q1x = x + _O1X
    q1y = y + _O1Y
    q1z = z + _O1Z
    return _dnoise(perm, period, q1x, q1y, q1z, 0, h) - _dnoise(perm, period, x, y, z, 1, h)


@declare("vc-2.25", c="ccl_noise_divergence3",
         args=(_CX, _CY, _CZ, _SEED, _PERIOD, _H), outputs=("div",), derived=_PERM,
         summary="Divergence (sum over i = 1..3; the printed i = 0 is an index error) of the offset Perlin potential "
                 "psi itself -- not zero in general, unlike its curl (vc-2.26). " + _CURL_SUMMARY,
         references=_CURL_REF)
@wp.func
def noise_divergence3(x: float, y: float, z: float, perm: wp.array(dtype=wp.int32), period: int, h: float) -> float:
    """vc-2.25: nabla . psi of the offset Perlin potential."""
    q1x = x + _O1X
    q1y = y + _O1Y
    q1z = z + _O1Z
    q2x = x + _O2X
    q2y = y + _O2Y
    q2z = z + _O2Z
    return (_dnoise(perm, period, x, y, z, 0, h) + _dnoise(perm, period, q1x, q1y, q1z, 1, h)) + \
        _dnoise(perm, period, q2x, q2y, q2z, 2, h)


@declare("vc-2.26", c="ccl_noise_curl_property",
         args=(_CX, _CY, _CZ, _SEED, _PERIOD, _H), options=(VARIANT,), outputs=("residual",),
         derived=_PERM,
         summary="Residual of the property claimed for curl noise v = noise_curl3 (nested central differences, same "
                 "h). variant='corrected': nabla . v, the divergence-free property meant (~0 up to float32 round-off); "
                 "variant='thesis': |nabla x v| for the printed 'nabla x F = 0', which does not hold (spec error 7). "
                 + _CURL_SUMMARY,
         references=_CURL_REF)
@wp.func
def noise_curl_property(x: float, y: float, z: float, perm: wp.array(dtype=wp.int32), period: int, h: float,
                        variant: int) -> float:
    """vc-2.26 residual: variant 0 = nabla . v (~0, the property meant), 1 = |nabla x v| (as printed, not 0)."""
    # axis x
    pm0 = _fd_points(x, h)
    px = pm0[0]
    mx = pm0[1]
    d0 = px - mx
    vp = noise_curl3(px, y, z, perm, period, h)
    vm = noise_curl3(mx, y, z, perm, period, h)
    j00 = (vp[0] - vm[0]) / d0
    j10 = (vp[1] - vm[1]) / d0
    j20 = (vp[2] - vm[2]) / d0
    # axis y
    pm1 = _fd_points(y, h)
    py = pm1[0]
    my = pm1[1]
    d1 = py - my
    vp = noise_curl3(x, py, z, perm, period, h)
    vm = noise_curl3(x, my, z, perm, period, h)
    j01 = (vp[0] - vm[0]) / d1
    j11 = (vp[1] - vm[1]) / d1
    j21 = (vp[2] - vm[2]) / d1
    # axis z
    pm2 = _fd_points(z, h)
    pz = pm2[0]
    mz = pm2[1]
    d2 = pz - mz
    vp = noise_curl3(x, y, pz, perm, period, h)
    vm = noise_curl3(x, y, mz, perm, period, h)
    j02 = (vp[0] - vm[0]) / d2
    j12 = (vp[1] - vm[1]) / d2
    j22 = (vp[2] - vm[2]) / d2
    if variant == VARIANT_THESIS:
        cx = j21 - j12
        cy = j02 - j20
        cz = j10 - j01
        return wp.sqrt(cx * cx + cy * cy + cz * cz)
    return (j00 + j11) + j22


@declare("vc-A7", c="ccl_noise_curl2",
         args=(_CX, _CY, _SEED, _PERIOD, _H), outputs=("v",), derived=_PERM,
         summary="Curl noise, reading (i): 2-D stream function psi = N(x, y, 0), v = (dpsi/dy, -dpsi/dx) -- tangent to "
                 "the level sets of psi and divergence-free. Reading (ii), the 3-D vector potential with large "
                 "offsets, is noise_curl3 (vc-2.23). Table form ccl_noise_curl2_perm. " + _CURL_SUMMARY,
         references=_CURL_REF)
@wp.func
def noise_curl2(x: float, y: float, perm: wp.array(dtype=wp.int32), period: int, h: float) -> wp.vec2:
    """vc-A7 (i): v = (dpsi/dy, -dpsi/dx), psi = N(x, y, 0)."""
    return wp.vec2(_dnoise(perm, period, x, y, 0.0, 1, h), -_dnoise(perm, period, x, y, 0.0, 0, h))


# --- Perlin-Worley (vc-A8) ---------------------------------------------------------------------------------------

@declare("vc-A8", c="ccl_noise_perlin_worley",
         args=(Arg("p", "fBm Perlin remapped to [0, 1]", lo=0.0, hi=1.0),
               Arg("w", "inverse-Worley fBm in [0, 1]", lo=0.0, hi=1.0)),
         options=(COMBINATION,), outputs=("pw",),
         summary="Perlin-Worley combination for the base texture's R channel. 'thesis' (default, §4.3.1): "
                 "remap(P, 0, 1, W, 1)^2 = (W + P(1 - W))^2, in [W^2, 1]; 'gpu_pro_7': clamp(remap(P, W, 1, 0, 1), 0, "
                 "1) = clamp((P - W)/(1 - W)), 0 where W = 1 (the limit for P < 1); 'hillaire': remap(P, 0, 1, W, 1), "
                 "the unsquared form of Hillaire's TileableVolumeNoise; 'product': P W (Perlin masked by Worley); "
                 "'average': (P + W)/2. The thesis names only the first two (fig 4.8).",
         references=("A. Schneider, The real-time volumetric cloudscapes of Horizon: Zero Dawn, SIGGRAPH 2015",
                     "A. Schneider, Real-Time Volumetric Cloudscapes, GPU Pro 7, 2016",
                     "S. Hillaire, TileableVolumeNoise, https://github.com/sebh/TileableVolumeNoise, 2016"))
@wp.func
def noise_perlin_worley(p: float, w: float, combination: int) -> float:
    """vc-A8: 0 thesis remap(P,0,1,W,1)^2, 1 gpu_pro_7 clamp(remap(P,W,1,0,1)), 2 hillaire remap(P,0,1,W,1),
    3 product P W, 4 average (P + W)/2."""
    if combination == PW_GPU_PRO_7:
        if w >= 1.0:
            return 0.0
        r = interp_remap(p, w, 1.0, 0.0, 1.0)
        if r < 0.0:
            return 0.0
        if r > 1.0:
            return 1.0
        return r
    if combination == PW_HILLAIRE:
        return interp_remap(p, 0.0, 1.0, w, 1.0)
    if combination == PW_PRODUCT:
        return p * w
    if combination == PW_AVERAGE:
        return (p + w) * 0.5
    r = interp_remap(p, 0.0, 1.0, w, 1.0)
    return r * r


# --- NumPy helpers for functions without their own catalogue ID ------------------------------------------------------

@wp.kernel
def _perlin2_kernel(x: wp.array(dtype=float), y: wp.array(dtype=float), period: int, interp: int,
                    perm: wp.array(dtype=wp.int32), out: wp.array(dtype=float)):
    # noise_perlin2 has no catalogue ID of its own (the 2-D form of vc-A1 for vc-fig-2.5): evaluated by
    # pywarp.clouds.noise.perlin2()
    i = wp.tid()
    out[i] = noise_perlin2(x[i], y[i], perm, period, interp)
