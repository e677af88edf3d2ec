"""The ray-marched procedural terrain demo of the pt text (chapters 6-9) -- Warp twins of ``cclouds/terrain.h``.

Every ``@wp.func`` mirrors the C function of the same name (minus ``ccl_``) operation by operation (float32, same
order, comparisons written out), so that the Warp render and the C reference pixel agree bit for bit.

* Heightmaps: ``heightmap="test"`` is the text's 10 sin(0.1 x) sin(0.1 z) (Kod 7.4, 7.5, Tabulka 7.1);
  ``heightmap="fbm"`` is ``height_scale * fbm(x / horizontal_scale, z / horizontal_scale, octaves)`` with the fBm of
  Kod 7.9 (pt-code-7.9, declared with pt-alg-3.2 by :func:`pywarp.kernels.noise.noise_fbm_perlin2`: one
  function; A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2 as printed). The element-wise entries take the heightmap as
  ``(octaves, height_scale, horizontal_scale, seed, heightmap=...)``; the test heightmap ignores the first four.
* The noise of the fBm (undefined in the text) is :func:`pywarp.kernels.noise.noise_perlin2` (period 0, quintic
  fade): the z = 0 slice of Perlin's 2002 improved noise, ``|noise| <= 1`` (each corner's gradient has a 2-D part of
  at most (1, 1); measured about [-0.99, 0.99]), 0 at integer lattice points, repeating every 256 lattice units.
  Hence ``|fbm| <= 2 (1 - 0.5^octaves)``.
* The height slab (scene field ``slab``, on by default): the fBm's heights lie within +-hmax, hmax = height_scale
  2 (1 - 0.5^octaves) (10 for the test map), so the scene's view and shadow rays stop once they rise above
  hmax + PRECISION (the sky's rays after a few steps; the soft shadow once its bound k (y - hmax) / t reaches the
  running minimum) and start at that level when the camera is above it. Exact for a camera inside the slab (the
  same pixels bit for bit, tested); the element-wise entries are the printed listings (``_NO_SLAB``).
* Scene level: :class:`TerrainParams` (the twin of ``ccl_terrain_params``) and :func:`terrain_shade` (one ray,
  pt-code-7.3 with materials, water and atmosphere), :func:`terrain_pixel` (supersampled pixel, pt-alg-7.1.6) and
  the image kernel :data:`render_kernel` (row bands through :class:`pywarp.core.runtime.TileLauncher`).
* Host side: the NumPy-level ``height`` / ``water_normal`` and the evaluators of the two scene-level entries are
  :mod:`pywarp.terrain.evaluators`.
"""
from __future__ import annotations

import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import VARIANT, Arg, Option, declare
from .common import clamp01, mix3
from . import VARIANT_THESIS
from .interp import interp_fade_quintic, interp_lerp
from .noise import _floor_to_int, _grad3, noise_fbm_perlin2, noise_perlin2, perm_array, perm_table

HEIGHTMAP_TEST = c_constant("CCL_TERRAIN_TEST", 0)
HEIGHTMAP_FBM = c_constant("CCL_TERRAIN_FBM", 1)
MARCH_FIXED = c_constant("CCL_TERRAIN_MARCH_FIXED", 0)
MARCH_DYNAMIC = c_constant("CCL_TERRAIN_MARCH_DYNAMIC", 1)
MARCH_BISECT = c_constant("CCL_TERRAIN_MARCH_BISECT", 2)
SHADOWS_NONE = c_constant("CCL_TERRAIN_SHADOWS_NONE", 0)
SHADOWS_HARD = c_constant("CCL_TERRAIN_SHADOWS_HARD", 1)
SHADOWS_SOFT = c_constant("CCL_TERRAIN_SHADOWS_SOFT", 2)
STAGE_HEIGHTMAP = c_constant("CCL_TERRAIN_STAGE_HEIGHTMAP", 0)
STAGE_MATERIALS = c_constant("CCL_TERRAIN_STAGE_MATERIALS", 1)
STAGE_ATMOSPHERE = c_constant("CCL_TERRAIN_STAGE_ATMOSPHERE", 2)
STAGE_FINAL = c_constant("CCL_TERRAIN_STAGE_FINAL", 3)
HEIGHTMAPS = {"test": HEIGHTMAP_TEST, "fbm": HEIGHTMAP_FBM}
MARCH_METHODS = {"fixed": MARCH_FIXED, "dynamic": MARCH_DYNAMIC, "bisect": MARCH_BISECT}
SHADOW_KINDS = {"none": SHADOWS_NONE, "hard": SHADOWS_HARD, "soft": SHADOWS_SOFT}
STAGES = {"heightmap": STAGE_HEIGHTMAP, "materials": STAGE_MATERIALS, "atmosphere": STAGE_ATMOSPHERE,
          "final": STAGE_FINAL}
MAX_FIXED_STEPS = 1000000  # CCL_TERRAIN_MAX_FIXED_STEPS

_MAX_FIXED = wp.constant(MAX_FIXED_STEPS)
#: hmax of the element-wise functions (the printed listings): y - NO_SLAB > precision never holds (C: NO_SLAB)
_NO_SLAB = wp.constant(3.0e38)
# largest fBm coordinate of the clouds (C: CLOUD_COORD_MAX, FLT_MAX / 8): the top of their 4 octaves stays finite
_CLOUD_COORD_MAX = wp.constant(3.4028234663852886e38 / 8.0)

HEIGHTMAP = Option("heightmap", HEIGHTMAPS, "test",
                   "'test': 10 sin(0.1 x) sin(0.1 z), the text's test heightmap (default; octaves, height_scale, "
                   "horizontal_scale and seed are ignored); 'fbm': height_scale * fbm(x / horizontal_scale, "
                   "z / horizontal_scale, octaves) (Kod 7.9)")

_REF = ("M. Drevicky, Graficke demo vyuzivajuce proceduralne textury, FIT VUT Brno 2016 (spec/pt.md)",)
_IQ = "I. Quilez, Terrain raymarching / Free penumbra shadows for raymarching distance fields (iquilezles.org)"

# --- arguments --------------------------------------------------------------------------------------------------------

_RO = Arg("ro", "ray origin (units)", sample_range=(-30.0, 30.0))
_RD = Arg("rd", "unit ray direction", unit=True)
_MAX_T = Arg("max_t", "MAX_T: longest ray (units)", lo=0.0, hi=1.0e4, lo_open=True, default=400.0,
             sample_range=(1.0, 200.0))
_PRECISION = Arg("precision", "PRECISION: hit when the vertical gap falls below it (units)", lo=0.0, hi=10.0,
                 lo_open=True, default=0.01, sample_range=(0.001, 0.1))
_MAX_STEPS = Arg("max_steps", "MAX_STEPS: iteration cap", lo=1, hi=100000, default=300, sample_range=(1, 400))
_STEP_SCALE = Arg("step_scale", "factor on the dynamic step (1: Kod 7.5; 0.5: 'halve the step', 7.1.3)", lo=0.0,
                  hi=1.0, lo_open=True, default=1.0, sample_range=(0.3, 1.0))
_OCTAVES = Arg("octaves", "fBm octaves of the heightmap (fbm only)", lo=1, hi=16, default=4, sample_range=(1, 6))
_HEIGHT = Arg("height_scale", "height of the fBm heightmap (units; fbm only)", lo=0.0, hi=1000.0, default=12.0,
              sample_range=(1.0, 20.0))
#: Smallest noise scale (units per noise unit) of horizontal_scale, cloud_scale and wave_scale (the C
#: CCL_TERRAIN_MIN_SCALE): finer noise only aliases, and position / scale stays finite (1.02e-38 gave a NaN shade).
MIN_SCALE = 0.015625  # 1/64, exact in float32
_HSCALE = Arg("horizontal_scale", "units per fBm unit (fbm only)", lo=MIN_SCALE, hi=1.0e4, default=24.0,
              sample_range=(5.0, 50.0))
_SEED = Arg("seed", "Perlin seed of the fBm (uint32; 0 = Perlin's table; fbm only)", lo=0, hi=4294967295,
            dtype="uint32", default=0)
_FIELD = (_OCTAVES, _HEIGHT, _HSCALE, _SEED)
_PERM = {"perm": ("seed", perm_array)}
_COLOUR = dict(lo=0.0, hi=100.0)


# --- helpers (the static functions of terrain.c) ------------------------------------------------------------------------

@wp.func
def _smoothstep(a: float, b: float, x: float) -> float:
    s = clamp01((x - a) / (b - a))
    return s * s * (3.0 - 2.0 * s)


@wp.func
def _along(ro: wp.vec3, rd: wp.vec3, t: float) -> wp.vec3:
    return wp.vec3(ro[0] + rd[0] * t, ro[1] + rd[1] * t, ro[2] + rd[2] * t)


@wp.func
def _normalize(a: wp.vec3) -> wp.vec3:
    """ccl_vec3_normalize: a / |a|, the zero vector for |a| = 0."""
    lng = wp.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    if lng == 0.0:
        return wp.vec3(0.0, 0.0, 0.0)
    return wp.vec3(a[0] / lng, a[1] / lng, a[2] / lng)


@wp.func
def _dot(a: wp.vec3, b: wp.vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


#: length of a plain permutation table (perm_table); the scene's table (hashed_perm_array) is longer
_PERM_LEN = wp.constant(512)
_HASHED_PERM: dict = {}


def hashed_perm_array(seed: int = 0, device: str | None = None):
    """The scene's Perlin table: the 512 entries of ``perm_table(seed)`` followed by the 256 x 256 lattice hashes
    perm[perm[perm[x] + y]] of the 2-D noise (z = 0), so that a corner's gradient costs one lookup instead of three.
    Every function that reads ``perm`` reads the same first 512 entries; ``fbm_perm`` takes its hashes from the rest
    (the same values: the same noise, bit for bit; ~1.3x faster per octave on a CPU). Cached per seed and device."""
    import numpy as np

    from ..core.runtime import resolve_device

    dev = resolve_device(device)
    key = (int(seed), str(dev))
    arr = _HASHED_PERM.get(key)
    if arr is None:
        p = perm_table(seed).astype(np.int64)
        hashes = p[p[p[:256, None] + np.arange(256)[None, :]]]
        arr = wp.array(np.concatenate([p, hashes.ravel()]).astype(np.int32), dtype=wp.int32, device=dev)
        if len(_HASHED_PERM) > 64:
            _HASHED_PERM.clear()
        _HASHED_PERM[key] = arr
    return arr


@wp.func
def _perlin2_hashed(x: float, y: float, perm: wp.array(dtype=wp.int32)) -> float:
    """noise_perlin2(x, y, perm, period 0, quintic) with the corners' hashes from hashed_perm_array's 2-D table:
    the same operations on the same values."""
    if not (wp.isfinite(x) and wp.isfinite(y)):
        return wp.nan
    fx = wp.floor(x)
    fy = wp.floor(y)
    ix = _floor_to_int(fx)
    iy = _floor_to_int(fy)
    x1 = (ix + 1) & 255
    y1 = (iy + 1) & 255
    x0 = ix & 255
    y0 = iy & 255
    rx = x - fx
    ry = y - fy
    u = interp_fade_quintic(rx)
    v = interp_fade_quintic(ry)
    return interp_lerp(
        v,
        interp_lerp(u, _grad3(perm[_PERM_LEN + x0 * 256 + y0], rx, ry, 0.0),
                    _grad3(perm[_PERM_LEN + x1 * 256 + y0], rx - 1.0, ry, 0.0)),
        interp_lerp(u, _grad3(perm[_PERM_LEN + x0 * 256 + y1], rx, ry - 1.0, 0.0),
                    _grad3(perm[_PERM_LEN + x1 * 256 + y1], rx - 1.0, ry - 1.0, 0.0)))


@wp.func
def fbm_perm(x: float, z: float, octaves: int, perm: wp.array(dtype=wp.int32)) -> float:
    """Kod 7.9 (pt-code-7.9) = pt-alg-3.2 with the printed A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2: one function,
    noise_fbm_perlin2 (C: ccl_noise_fbm_perlin2_perm), which declares both IDs. With the scene's table
    (hashed_perm_array) the same sum, each octave's corner hashes looked up once (_perlin2_hashed)."""
    if perm.shape[0] > _PERM_LEN:
        value = float(0.0)
        amp = float(1.0)
        f = float(0.5)
        for _i in range(octaves):
            value += amp * _perlin2_hashed(f * x, f * z, perm)
            amp *= 0.5
            f *= 2.0
        return value
    return noise_fbm_perlin2(wp.vec2(x, z), octaves, perm, 1.0, 0.5, 0.5, 2.0)


@wp.func
def terrain_height_perm(x: float, z: float, octaves: int, height_scale: float, horizontal_scale: float,
                        perm: wp.array(dtype=wp.int32), heightmap: int) -> float:
    """Terrain height h(x, z) (units) of ``heightmap`` (0 test, 1 fbm): the map of Kod 7.4."""
    if heightmap == HEIGHTMAP_TEST:
        return 10.0 * wp.sin(0.1 * x) * wp.sin(0.1 * z)
    return height_scale * fbm_perm(x / horizontal_scale, z / horizontal_scale, octaves, perm)


@wp.func
def _map(q: wp.vec3, octaves: int, height_scale: float, horizontal_scale: float, perm: wp.array(dtype=wp.int32),
         heightmap: int) -> float:
    return q[1] - terrain_height_perm(q[0], q[2], octaves, height_scale, horizontal_scale, perm, heightmap)


# --- pt-code-7.1: pixel coordinates ------------------------------------------------------------------------------------

@declare("pt-code-7.1", c="ccl_terrain_pixel_position",
         args=(Arg("frag_x", "gl_FragCoord.x: pixel centre, from the left (px)", sample_range=(0.0, 1920.0)),
               Arg("frag_y", "gl_FragCoord.y: pixel centre, from the bottom (px)", sample_range=(0.0, 1080.0)),
               Arg("width", "iResolution.x (px)", lo=1.0, hi=1.0e5, sample_range=(1.0, 2000.0)),
               Arg("height", "iResolution.y (px)", lo=1.0, hi=1.0e5, sample_range=(1.0, 2000.0))),
         outputs=("p",),
         summary="Kod 7.1: p = (frag / resolution) * 2 - 1, then p.x *= width / height: y in (-1, 1), x in (-aspect, "
                 "aspect) inside the window. With pt-code-7.2 (camera_ray, fov 90 deg) it gives the demo's rays.",
         references=_REF)
@wp.func
def terrain_pixel_position(frag_x: float, frag_y: float, width: float, height: float) -> wp.vec2:
    px = (frag_x / width) * 2.0 - 1.0
    py = (frag_y / height) * 2.0 - 1.0
    px = px * (width / height)
    return wp.vec2(px, py)


# --- pt-code-7.4, 7.5, pt-alg-9-bisect: marching --------------------------------------------------------------------

@declare("pt-code-7.4", c="ccl_terrain_march_fixed",
         args=(_RO, _RD, _MAX_T,
               Arg("step_size", "STEP_SIZE: constant step (units)", lo=0.015625, hi=100.0, default=0.1,
                   sample_range=(0.05, 2.0)),
               _PRECISION) + _FIELD,
         options=(HEIGHTMAP,), outputs=("hit", "t", "steps"), derived=_PERM,
         summary="Kod 7.4: for (t = 0; t < max_t; t += step_size) hit when p.y - precision < h(p.xz), p = ro + rd t. "
                 "Returns hit (1/0), t (at the hit; >= max_t on a miss) and the heights evaluated (<= max_t / "
                 "step_size + 1 <= 10^6).",
         references=_REF + (_IQ,))
@wp.func
def terrain_march_fixed(ro: wp.vec3, rd: wp.vec3, max_t: float, step_size: float, precision: float, octaves: int,
                        height_scale: float, horizontal_scale: float, perm: wp.array(dtype=wp.int32),
                        heightmap: int) -> tuple[int, float, int]:
    return _march_fixed(ro, rd, max_t, step_size, precision, octaves, height_scale, horizontal_scale, perm, heightmap,
                        _NO_SLAB)


@wp.func
def _slab_entry(ro: wp.vec3, rd: wp.vec3, precision: float, hmax: float) -> float:
    """Start of a view ray: 0, or where a ray from above the slab (y > hmax + precision) comes down to its top (no
    point before it can be a hit: d >= y - hmax > precision there). C: slab_entry."""
    above = ro[1] - hmax - precision
    if rd[1] < 0.0 and above > 0.0:
        return above / (-rd[1])
    return 0.0


@wp.func
def _march_fixed(ro: wp.vec3, rd: wp.vec3, max_t: float, step_size: float, precision: float, octaves: int,
                 height_scale: float, horizontal_scale: float, perm: wp.array(dtype=wp.int32), heightmap: int,
                 hmax: float) -> tuple[int, float, int]:
    """Kod 7.4 (the fixed step of §7.1.2: for t = 0 while t < MAX_T, t += STEP_SIZE, hit when point.y - PRECISION <
    map(point), map the height; ``q`` is the text's point) clipped to the slab y <= hmax + precision (hmax =
    _NO_SLAB: as printed), at most _MAX_FIXED steps. C: march_fixed."""
    t = float(0.0)
    steps = int(0)
    while t < max_t and steps < _MAX_FIXED:
        q = _along(ro, rd, t)
        if rd[1] >= 0.0 and q[1] - hmax > precision:
            break
        steps += 1
        if q[1] - precision < terrain_height_perm(q[0], q[2], octaves, height_scale, horizontal_scale, perm,
                                                  heightmap):
            return 1, t, steps
        t += step_size
    return 0, t, steps


@declare("pt-code-7.5", c="ccl_terrain_march_dynamic",
         args=(_RO, _RD, _MAX_T, _PRECISION, _MAX_STEPS, _STEP_SCALE) + _FIELD,
         options=(HEIGHTMAP,), outputs=("hit", "t", "steps"), derived=_PERM,
         summary="Kod 7.5 (map with point.x, point.z; the printed p.x, p.z is a typo): d = p.y - h(p.xz), t += "
                 "step_scale d; hit when d < precision, miss when t > max_t or after max_steps. t includes the last "
                 "step, as printed. step_scale 0.5 is the text's remedy for overshooting steep slopes (the vertical "
                 "gap is not a safe distance).",
         references=_REF + (_IQ,))
@wp.func
def terrain_march_dynamic(ro: wp.vec3, rd: wp.vec3, max_t: float, precision: float, max_steps: int,
                          step_scale: float, octaves: int, height_scale: float, horizontal_scale: float,
                          perm: wp.array(dtype=wp.int32), heightmap: int) -> tuple[int, float, int]:
    return _march_dynamic(ro, rd, max_t, precision, max_steps, step_scale, octaves, height_scale, horizontal_scale,
                          perm, heightmap, _NO_SLAB, 0.0)


@wp.func
def _march_dynamic(ro: wp.vec3, rd: wp.vec3, max_t: float, precision: float, max_steps: int, step_scale: float,
                   octaves: int, height_scale: float, horizontal_scale: float, perm: wp.array(dtype=wp.int32),
                   heightmap: int, hmax: float, precision_t: float) -> tuple[int, float, int]:
    """Kod 7.5 (the dynamic step of §7.1.3: stepSize = map(point), the vertical gap point.y - h; t += stepSize; hit
    when stepSize < PRECISION, miss when t > MAX_T; ``q`` is the text's point, ``d`` its stepSize) with t += step_scale
    d (the text's remedy for overshooting; 1: as printed), clipped to the slab y <= hmax + precision (hmax = _NO_SLAB:
    as printed), the hit test d < precision + precision_t t (precision_t = 0: as printed). C: march_dynamic."""
    t = _slab_entry(ro, rd, precision, hmax)
    for i in range(max_steps):
        q = _along(ro, rd, t)
        eps = precision + precision_t * t
        if rd[1] >= 0.0 and q[1] - hmax > eps:
            return 0, t, i
        d = _map(q, octaves, height_scale, horizontal_scale, perm, heightmap)
        t += step_scale * d
        if d < eps:
            return 1, t, i + 1
        if t > max_t:
            return 0, t, i + 1
    return 0, t, max_steps


@declare("pt-alg-9-bisect", c="ccl_terrain_march_bisect",
         args=(_RO, _RD, _MAX_T, _PRECISION, _MAX_STEPS, _STEP_SCALE,
               Arg("threshold", "step below which the bisection phase starts (units)", lo=0.0, hi=100.0,
                   lo_open=True, default=0.25, sample_range=(0.05, 2.0)),
               Arg("bisect_steps", "halvings of the bracket", lo=0, hi=64, default=6, sample_range=(0, 12)))
              + _FIELD,
         options=(HEIGHTMAP,), outputs=("hit", "t", "steps"), derived=_PERM,
         summary="The refinement proposed in ch. 9 (not implemented in the text): the dynamic march while d >= "
                 "threshold; below it, steps of `threshold` (a floor on the step: no crawl along a surface the ray "
                 "runs parallel to), and once such a step ends below the surface (d < precision) the crossing in "
                 "[t, t + threshold] is found by bisect_steps halvings (constant cost, error <= threshold / "
                 "2^bisect_steps). steps counts every height evaluated.",
         references=_REF)
@wp.func
def terrain_march_bisect(ro: wp.vec3, rd: wp.vec3, max_t: float, precision: float, max_steps: int, step_scale: float,
                         threshold: float, bisect_steps: int, octaves: int, height_scale: float,
                         horizontal_scale: float, perm: wp.array(dtype=wp.int32),
                         heightmap: int) -> tuple[int, float, int]:
    return _march_bisect(ro, rd, max_t, precision, max_steps, step_scale, threshold, bisect_steps, octaves,
                         height_scale, horizontal_scale, perm, heightmap, _NO_SLAB)


@wp.func
def _march_bisect(ro: wp.vec3, rd: wp.vec3, max_t: float, precision: float, max_steps: int, step_scale: float,
                  threshold: float, bisect_steps: int, octaves: int, height_scale: float, horizontal_scale: float,
                  perm: wp.array(dtype=wp.int32), heightmap: int, hmax: float) -> tuple[int, float, int]:
    """pt-alg-9-bisect clipped to the slab y <= hmax + precision (hmax = _NO_SLAB: no clipping). C: march_bisect."""
    t = _slab_entry(ro, rd, precision, hmax)
    steps = int(0)
    for _i in range(max_steps):
        q = _along(ro, rd, t)
        if rd[1] >= 0.0 and q[1] - hmax > precision:
            break
        d = _map(q, octaves, height_scale, horizontal_scale, perm, heightmap)
        steps += 1
        if d < precision:
            return 1, t, steps
        if d < threshold:
            tb = t + threshold
            db = _map(_along(ro, rd, tb), octaves, height_scale, horizontal_scale, perm, heightmap)
            steps += 1
            if db < precision:
                ta = t
                for _k in range(bisect_steps):
                    tm = 0.5 * (ta + tb)
                    dm = _map(_along(ro, rd, tm), octaves, height_scale, horizontal_scale, perm, heightmap)
                    steps += 1
                    if dm < precision:
                        tb = tm
                    else:
                        ta = tm
                return 1, tb, steps
            t = tb
        else:
            t += step_scale * d
        if t > max_t:
            return 0, t, steps
    return 0, t, steps


# --- pt-code-7.6, 7.7: shadows -------------------------------------------------------------------------------------------

_SH_MAX_T = Arg("max_t", "MAX_T of the shadow ray (units)", lo=0.0, hi=1.0e4, lo_open=True, default=80.0,
                sample_range=(1.0, 100.0))


@declare("pt-code-7.6", c="ccl_terrain_shadow_hard",
         args=(Arg("ro", "the shaded point (units)", sample_range=(-30.0, 30.0)),
               Arg("rd", "unit direction towards the light", unit=True),
               Arg("t0", "start offset (Kod 7.6: 0.2)", lo=0.0, hi=100.0, default=0.2, sample_range=(0.0, 1.0)),
               _SH_MAX_T, _PRECISION, _MAX_STEPS) + _FIELD,
         options=(HEIGHTMAP,), outputs=("shadow",), derived=_PERM,
         summary="Kod 7.6: t = t0; up to max_steps times d = map(ro + rd t): d < precision -> 0 (occluded), t > max_t "
                 "-> stop, t += d. Returns 1 (lit) or 0. t0 must be positive enough to leave the surface (the text's "
                 "0.2; its prose says 'close to zero' and Kod 7.7 uses 0.02).",
         references=_REF)
@wp.func
def terrain_shadow_hard(ro: wp.vec3, rd: wp.vec3, t0: float, max_t: float, precision: float, max_steps: int,
                        octaves: int, height_scale: float, horizontal_scale: float, perm: wp.array(dtype=wp.int32),
                        heightmap: int) -> float:
    return _shadow_hard(ro, rd, t0, max_t, precision, max_steps, octaves, height_scale, horizontal_scale, perm,
                        heightmap, _NO_SLAB, 0.0)


@wp.func
def _shadow_hard(ro: wp.vec3, rd: wp.vec3, t0: float, max_t: float, precision: float, max_steps: int, octaves: int,
                 height_scale: float, horizontal_scale: float, perm: wp.array(dtype=wp.int32), heightmap: int,
                 hmax: float, min_step: float) -> float:
    """Kod 7.6, lit as soon as the rising ray leaves the slab (hmax = _NO_SLAB: as printed), steps of at least
    min_step (0: t += d as printed). C: shadow_hard."""
    t = float(t0)
    for _i in range(max_steps):
        q = _along(ro, rd, t)
        if rd[1] >= 0.0 and q[1] - hmax > precision:
            break
        d = _map(q, octaves, height_scale, horizontal_scale, perm, heightmap)
        if d < precision:
            return 0.0
        if t > max_t:
            break
        if d > min_step:
            t += d
        else:
            t += min_step
    return 1.0


@declare("pt-code-7.7", c="ccl_terrain_shadow_soft",
         args=(Arg("ro", "the shaded point (units)", sample_range=(-30.0, 30.0)),
               Arg("rd", "unit direction towards the light", unit=True),
               Arg("t0", "start offset (Kod 7.7: 0.02)", lo=0.0, hi=100.0, lo_open=True, default=0.02,
                   sample_range=(0.01, 1.0)),
               Arg("k", "softness factor (Kod 7.7: 4; larger = harder)", lo=0.0, hi=1000.0, lo_open=True, default=4.0,
                   sample_range=(0.5, 32.0)),
               _SH_MAX_T, _PRECISION, _MAX_STEPS) + _FIELD,
         options=(HEIGHTMAP,), outputs=("shadow",), derived=_PERM,
         summary="Kod 7.7 (Quilez's penumbra): as the hard shadow, and after each step shadow = min(shadow, k d / t). "
                 "Output in [0, 1] and non-decreasing in k (the path of the ray does not depend on k).",
         references=_REF + (_IQ,))
@wp.func
def terrain_shadow_soft(ro: wp.vec3, rd: wp.vec3, t0: float, k: float, max_t: float, precision: float,
                        max_steps: int, octaves: int, height_scale: float, horizontal_scale: float,
                        perm: wp.array(dtype=wp.int32), heightmap: int) -> float:
    return _shadow_soft(ro, rd, t0, k, max_t, precision, max_steps, octaves, height_scale, horizontal_scale, perm,
                        heightmap, _NO_SLAB, 0.0)


@wp.func
def _shadow_soft(ro: wp.vec3, rd: wp.vec3, t0: float, k: float, max_t: float, precision: float, max_steps: int,
                 octaves: int, height_scale: float, horizontal_scale: float, perm: wp.array(dtype=wp.int32),
                 heightmap: int, hmax: float, min_step: float) -> float:
    """Kod 7.7 with the slab's exact early exit (hmax = _NO_SLAB: as printed) and steps of at least min_step (0:
    t += d as printed). C: shadow_soft. Above the slab and
    rising, every later k d / t >= k (y - hmax) / t, which grows with t for an origin at or below hmax; once that
    bound reaches the running minimum nothing ahead can lower it."""
    shadow = float(1.0)
    t = float(t0)
    for _i in range(max_steps):
        q = _along(ro, rd, t)
        if rd[1] >= 0.0 and ro[1] <= hmax and q[1] - hmax > precision and k * (q[1] - hmax) / t >= shadow:
            break
        d = _map(q, octaves, height_scale, horizontal_scale, perm, heightmap)
        if d < precision:
            return 0.0
        if t > max_t:
            break
        s = k * d / t
        if s < shadow:
            shadow = s
        if d > min_step:
            t += d
        else:
            t += min_step
    return shadow


# --- pt-7.1 lighting, pt-7.2 / pt-code-7.8 normals, pt-alg-7.3-lod --------------------------------------------------------

@declare("pt-7.1", c="ccl_terrain_lighting",
         args=(Arg("n", "unit surface normal", unit=True), Arg("l", "unit vector towards the light", unit=True),
               Arg("la", "L_a: ambient light intensity", lo=0.0, hi=100.0, sample_range=(0.0, 2.0)),
               Arg("ca", "C_a: ambient colour of the object (RGB)", lo=0.0, hi=1.0),
               Arg("ld", "L_d: diffuse light intensity", lo=0.0, hi=100.0, sample_range=(0.0, 2.0)),
               Arg("cd", "C_d: diffuse colour of the object (RGB)", lo=0.0, hi=1.0),
               Arg("shadow", "shadow factor (Kod 7.6/7.7), 1 = lit", lo=0.0, hi=1.0, default=1.0)),
         outputs=("i",),
         summary="eq 7.1: I = L_a C_a + L_d C_d max(0, n.l), the diffuse term multiplied by the shadow factor (the "
                 "text does not say how the shadow enters; this is the usual choice). RGB >= 0, not clamped.",
         references=_REF + ("J. H. Lambert, Photometria, 1760",))
@wp.func
def terrain_lighting(n: wp.vec3, l: wp.vec3, la: float, ca: wp.vec3, ld: float, cd: wp.vec3,  # noqa: E741
                     shadow: float) -> wp.vec3:
    ndl = _dot(n, l)
    if ndl < 0.0:
        ndl = 0.0
    diffuse = ld * ndl * shadow
    return wp.vec3(ca[0] * la + cd[0] * diffuse, ca[1] * la + cd[1] * diffuse, ca[2] * la + cd[2] * diffuse)


@wp.func
def _normal(p: wp.vec3, h: float, octaves: int, height_scale: float, horizontal_scale: float,
            perm: wp.array(dtype=wp.int32), heightmap: int) -> tuple[wp.vec3, wp.vec3]:
    hc = terrain_height_perm(p[0], p[2], octaves, height_scale, horizontal_scale, perm, heightmap)
    gx = (p[1] - terrain_height_perm(p[0] + h, p[2], octaves, height_scale, horizontal_scale, perm, heightmap)) - (
        p[1] - terrain_height_perm(p[0] - h, p[2], octaves, height_scale, horizontal_scale, perm, heightmap))
    gy = ((p[1] + h) - hc) - ((p[1] - h) - hc)
    gz = (p[1] - terrain_height_perm(p[0], p[2] + h, octaves, height_scale, horizontal_scale, perm, heightmap)) - (
        p[1] - terrain_height_perm(p[0], p[2] - h, octaves, height_scale, horizontal_scale, perm, heightmap))
    g = wp.vec3(gx, gy, gz)
    return _normalize(g), g


@declare("pt-code-7.8", "pt-7.2", c="ccl_terrain_normal",
         args=(Arg("p", "point on (or near) the terrain (units)", sample_range=(-30.0, 30.0)),
               Arg("h", "central-difference step (Kod 7.8: 0.002)", lo=0.0, hi=1.0, lo_open=True, default=0.002,
                   sample_range=(0.0005, 0.01))) + _FIELD,
         options=(HEIGHTMAP,), outputs=("n", "g"), derived=_PERM,
         summary="Kod 7.8 / eq 7.2: g = (map(p + h x) - map(p - h x), map(p + h y) - map(p - h y), map(p + h z) - "
                 "map(p - h z)) with map = y - h(x, z) (so g = 2h (-h_x, 1, -h_z) to first order); n = normalize(g). "
                 "Outputs n and g (the missing division by 2h does not matter after normalising; g.y = 2h up to five "
                 "roundings: |g.y - 2h| <= 2 ulp(|p.y| + h + |H|) + ulp(2h), H the height at (p.x, p.z)). The scene "
                 "evaluates it with more octaves than the march (7.3).",
         references=_REF)
@wp.func
def terrain_normal(p: wp.vec3, h: float, octaves: int, height_scale: float, horizontal_scale: float,
                   perm: wp.array(dtype=wp.int32), heightmap: int) -> tuple[wp.vec3, wp.vec3]:
    return _normal(p, h, octaves, height_scale, horizontal_scale, perm, heightmap)


@declare("pt-alg-7.3-lod", c="ccl_terrain_normal_octaves",
         args=(Arg("t", "distance along the view ray (units)", lo=0.0, sample_range=(0.0, 500.0)),
               Arg("octaves_max", "octaves near the camera", lo=1, hi=16),
               Arg("octaves_min", "octaves far away (octaves_max when octaves_min >= octaves_max)", lo=1, hi=16),
               Arg("lod_distance", "distance up to which all octaves are kept (units)", lo=0.0, hi=1.0e4,
                   lo_open=True, sample_range=(1.0, 50.0))),
         outputs=("octaves",),
         summary="Octave count of the normals at distance t (the text gives no rule): octaves_max up to lod_distance, "
                 "one less per doubling of the distance beyond it (an octave's detail halves per octave, and the "
                 "pixel footprint doubles per doubling of t), never below octaves_min. Exact (products by 2 only).",
         references=_REF)
@wp.func
def terrain_normal_octaves(t: float, octaves_max: int, octaves_min: int, lod_distance: float) -> int:
    n = int(octaves_max)
    d = float(lod_distance)
    while n > octaves_min and t > d:
        n -= 1
        d = d * 2.0
    return n


# --- pt-7.3 fog, pt-code-7.10 sky, pt-code-7.11 clouds ---------------------------------------------------------------------

@declare("pt-7.3", c="ccl_terrain_fog",
         args=(Arg("d", "distance from the camera (units)", lo=0.0, sample_range=(0.0, 1000.0)),
               Arg("rho", "fog density (per unit)", lo=0.0, hi=100.0, lo_open=True, sample_range=(1e-4, 0.05))),
         options=(VARIANT,), outputs=("f",),
         summary="Fog weight in [0, 1]: variant 'thesis' f = min(e^(rho d) - 1, 1) as printed (f = 1 exactly for "
                 "d >= ln 2 / rho, with a kink there), 'corrected' the conventional f = 1 - e^(-rho d). The scene "
                 "blends colour + (sky - colour) f.",
         references=_REF)
@wp.func
def terrain_fog(d: float, rho: float, variant: int) -> float:
    if variant == VARIANT_THESIS:
        f = wp.exp(rho * d) - 1.0
        if f > 1.0:
            f = 1.0
        return f
    return 1.0 - wp.exp(-(rho * d))


@declare("pt-code-7.10", c="ccl_terrain_sky",
         args=(_RD, Arg("sun", "unit direction towards the sun (not a position)", unit=True),
               Arg("sky_colour", "skyColor (RGB)", **_COLOUR, sample_range=(0.0, 1.0)),
               Arg("sun_colour", "sunColor (RGB)", **_COLOUR, sample_range=(0.0, 1.0)),
               Arg("power", "exponent of the glow (Kod 7.10: 80)", lo=0.0, hi=1.0e4, lo_open=True, default=80.0,
                   sample_range=(1.0, 200.0))),
         outputs=("colour",),
         summary="Kod 7.10: sky_colour + max(rd.sun, 0)^power sun_colour, not clamped. With power 80 the glow halves "
                 "at acos(0.5^(1/80)) = 7.53 deg from the sun and falls to 1 % at 19.25 deg.",
         references=_REF)
@wp.func
def terrain_sky(rd: wp.vec3, sun: wp.vec3, sky_colour: wp.vec3, sun_colour: wp.vec3, power: float) -> wp.vec3:
    sun_dot = _dot(rd, sun)
    if not (sun_dot > 0.0):
        sun_dot = 0.0
    # the dot of two unit vectors can round to 1 + 2^-23; its power then overflows for power above ~7e8: clamp to 1
    if sun_dot > 1.0:
        sun_dot = 1.0
    g = wp.pow(sun_dot, power)
    return wp.vec3(sky_colour[0] + sun_colour[0] * g, sky_colour[1] + sun_colour[1] * g,
                   sky_colour[2] + sun_colour[2] * g)


@wp.func
def clouds_perm(colour: wp.vec3, ro: wp.vec3, rd: wp.vec3, cloud_height: float, wind: wp.vec2, time: float,
                cloud_scale: float, cloud_colour: wp.vec3, perm: wp.array(dtype=wp.int32), variant: int) -> wp.vec3:
    if not (rd[1] != 0.0):
        return colour
    t = (cloud_height - ro[1]) / rd[1]
    if variant != VARIANT_THESIS and not (t > 0.0):
        return colour
    # a plane point beyond the floats (t, or the fBm's top octave coordinate 8 q.xz / cloud_scale) has no fBm value:
    # the weight f rd.y takes its limit there, 0, as for rd.y = 0 (the fBm is bounded); NaN passes on. As C.
    if wp.isinf(t):
        return colour
    qx = ro[0] + rd[0] * t + wind[0] * time
    qz = ro[2] + rd[2] * t + wind[1] * time
    u = qx / cloud_scale
    v = qz / cloud_scale
    if wp.abs(u) > _CLOUD_COORD_MAX or wp.abs(v) > _CLOUD_COORD_MAX:
        return colour
    f = fbm_perm(u, v, 4, perm)
    w = clamp01(f * rd[1])
    return mix3(colour, cloud_colour, w)


@declare("pt-code-7.11", c="ccl_terrain_clouds",
         args=(Arg("colour", "colour behind the clouds (RGB)", **_COLOUR, sample_range=(0.0, 1.0)),
               Arg("ro", "ray origin (units)", sample_range=(-50.0, 50.0)), _RD,
               Arg("cloud_height", "cloudHeight: y of the cloud plane (units)", sample_range=(60.0, 500.0)),
               Arg("wind", "windSpeed (x, z) (units/s)", sample_range=(-10.0, 10.0)),
               Arg("time", "time (s)", lo=0.0, hi=1.0e6, default=0.0, sample_range=(0.0, 100.0)),
               Arg("cloud_scale", "units per fBm unit (1: the listing, which has no scale)", lo=MIN_SCALE, hi=1.0e6,
                   default=1.0, sample_range=(1.0, 300.0)),
               Arg("cloud_colour", "cloudColor (RGB)", **_COLOUR, default=(1.0, 1.0, 1.0), sample_range=(0.0, 1.0)),
               _SEED),
         options=(VARIANT,), outputs=("colour",), derived=_PERM,
         summary="Kod 7.11: q = ro + rd (cloud_height - ro.y) / rd.y, q.xz += wind time, w = clamp(fbm(q.xz / "
                 "cloud_scale, 4) rd.y, 0, 1), colour + (cloud_colour - colour) w. 'thesis': as printed, also below "
                 "the horizon (spurious clouds where the fBm is negative; rd.y = 0 leaves the colour, the limit of "
                 "w); 'corrected' (default): clouds only where the plane lies ahead (t > 0), none below the horizon "
                 "for a camera under the clouds.",
         references=_REF)
@wp.func
def terrain_clouds(colour: wp.vec3, ro: wp.vec3, rd: wp.vec3, cloud_height: float, wind: wp.vec2, time: float,
                   cloud_scale: float, cloud_colour: wp.vec3, perm: wp.array(dtype=wp.int32), variant: int) -> wp.vec3:
    return clouds_perm(colour, ro, rd, cloud_height, wind, time, cloud_scale, cloud_colour, perm, variant)


# --- pt-7.4 and the water of pt-alg-7.3.4 ------------------------------------------------------------------------------

@declare("pt-7.4", c="ccl_terrain_water_weight",
         args=(Arg("v", "unit view direction", unit=True), Arg("n", "unit water normal", unit=True),
               Arg("kappa", "exponent (Obrazok 7.9: 1, 3, 6)", lo=0.0, hi=100.0, lo_open=True, default=3.0,
                   sample_range=(0.5, 10.0))),
         outputs=("f",),
         summary="eq 7.4: f = |v.n|^kappa in [0, 1], the weight of the underwater terrain against the reflection: 1 "
                 "looking straight down (every kappa), -> 0 at grazing angles; a lower kappa keeps the bottom "
                 "visible at more oblique angles. An empirical curve after Fresnel, not Fresnel's reflectance.",
         references=_REF + ("T. Akenine-Moller, E. Haines, N. Hoffman, Real-Time Rendering, 3rd ed., 2008",))
@wp.func
def terrain_water_weight(v: wp.vec3, n: wp.vec3, kappa: float) -> float:
    c = wp.abs(_dot(v, n))
    if c > 1.0:  # |v . n| of unit vectors rounds up to 1 + 2^-22 (as ccl_terrain_water_weight)
        c = 1.0
    return wp.pow(c, kappa)


@wp.func
def terrain_water_normal_perm(x: float, z: float, time: float, wave_scale: float, wave_strength: float,
                              perm: wp.array(dtype=wp.int32)) -> wp.vec3:
    """Wave normal of the water plane (ours; the text gives none): a, b = noise + 0.5 sin, n = normalize(-s a, 1,
    -s b); see ccl_terrain_water_normal_perm."""
    u = x / wave_scale
    v = z / wave_scale
    a = noise_perlin2(u + 0.5 * time, v - 0.3 * time, perm, 0, 0) + 0.5 * wp.sin(3.0 * u + 2.0 * time)
    b = noise_perlin2(u - 0.4 * time + 37.2, v + 0.2 * time + 11.7, perm, 0, 0) + 0.5 * wp.sin(3.0 * v + 1.7 * time)
    return _normalize(wp.vec3(-(wave_strength * a), 1.0, -(wave_strength * b)))


# --- the scene: parameters, shading, pixels ---------------------------------------------------------------------------------

@wp.struct
class TerrainParams:
    """The twin of ``ccl_terrain_params`` (the permutation table is passed separately as ``perm``)."""

    heightmap: int
    seed: wp.uint32
    march_octaves: int
    height_scale: float
    horizontal_scale: float
    march_method: int
    max_t: float
    step_size: float
    precision: float
    max_steps: int
    step_scale: float
    bisect_threshold: float
    bisect_steps: int
    slab: int
    precision_per_unit: float
    normal_h: float
    normal_octaves_max: int
    normal_octaves_min: int
    lod_distance: float
    shadows: int
    shadow_t0_hard: float
    shadow_t0_soft: float
    shadow_k: float
    shadow_max_t: float
    shadow_bias: float
    shadow_min_step: float
    sun: wp.vec3
    light_ambient: float
    light_diffuse: float
    stage: int
    colour_rock: wp.vec3
    colour_low: wp.vec3
    colour_grass: wp.vec3
    material_low: float
    material_high: float
    grass_min_normal_y: float
    grass_band: float
    fog_variant: int
    fog_density: float
    sky_colour: wp.vec3
    sun_colour: wp.vec3
    sun_power: float
    cloud_variant: int
    cloud_height: float
    cloud_scale: float
    wind: wp.vec2
    time: float
    cloud_colour: wp.vec3
    water_level: float
    water_kappa: float
    wave_scale: float
    wave_strength: float
    water_tint: wp.vec3
    samples_per_axis: int


@wp.func
def _hmax(p: TerrainParams) -> float:
    """The slab's hmax: the bound of the marched height (|fbm| <= 2 (1 - 0.5^octaves) for |noise| <= 1; 10 for the
    test map), _NO_SLAB when p.slab is 0. C: march_field."""
    if p.slab == 0:
        return _NO_SLAB
    bound = float(0.0)
    a = float(1.0)
    for _i in range(p.march_octaves):
        bound += a
        a *= 0.5
    if p.heightmap == HEIGHTMAP_TEST:
        return 10.0
    return p.height_scale * bound


@wp.func
def _terrain_colour(p: TerrainParams, perm: wp.array(dtype=wp.int32), pos: wp.vec3, t: float) -> wp.vec3:
    octn = terrain_normal_octaves(t, p.normal_octaves_max, p.normal_octaves_min, p.lod_distance)
    n, _g = _normal(pos, p.normal_h, octn, p.height_scale, p.horizontal_scale, perm, p.heightmap)
    c = p.colour_rock
    if p.stage >= STAGE_MATERIALS:
        c = mix3(p.colour_low, p.colour_rock, _smoothstep(p.material_low, p.material_high, pos[1]))
    if p.stage >= STAGE_ATMOSPHERE:
        c = mix3(c, p.colour_grass, _smoothstep(p.grass_min_normal_y, p.grass_min_normal_y + p.grass_band, n[1]))
    shadow = float(1.0)
    if p.shadows != SHADOWS_NONE:
        origin = wp.vec3(pos[0], terrain_height_perm(pos[0], pos[2], p.march_octaves, p.height_scale,
                                                     p.horizontal_scale, perm, p.heightmap) + p.shadow_bias, pos[2])
        if p.shadows == SHADOWS_HARD:
            shadow = _shadow_hard(origin, p.sun, p.shadow_t0_hard, p.shadow_max_t, p.precision, p.max_steps,
                                  p.march_octaves, p.height_scale, p.horizontal_scale, perm, p.heightmap, _hmax(p),
                                  p.shadow_min_step)
        else:
            shadow = _shadow_soft(origin, p.sun, p.shadow_t0_soft, p.shadow_k, p.shadow_max_t, p.precision,
                                  p.max_steps, p.march_octaves, p.height_scale, p.horizontal_scale, perm,
                                  p.heightmap, _hmax(p), p.shadow_min_step)
    return terrain_lighting(n, p.sun, p.light_ambient, c, p.light_diffuse, c, shadow)


@wp.func
def terrain_shade(p: TerrainParams, perm: wp.array(dtype=wp.int32), ro: wp.vec3, rd: wp.vec3) -> tuple[wp.vec3, int]:
    """pt-code-7.3 with everything of ch. 7 (twin of ccl_terrain_shade): unclamped colour and the view-march steps."""
    colour, steps, _dist = _shade_dist(p, perm, ro, rd)
    return colour, steps


@wp.func
def _shade_dist(p: TerrainParams, perm: wp.array(dtype=wp.int32), ro: wp.vec3,
                rd: wp.vec3) -> tuple[wp.vec3, int, float]:
    """terrain_shade, and the distance along the ray to the surface the pixel shows (the terrain's t, or the water
    plane's in front of it; -1 for the sky): the depth the viewer's temporal reconstruction reprojects with."""
    hit = int(0)
    t = float(0.0)
    steps = int(0)
    hmax = _hmax(p)
    if p.march_method == MARCH_FIXED:
        hit, t, steps = _march_fixed(ro, rd, p.max_t, p.step_size, p.precision, p.march_octaves, p.height_scale,
                                     p.horizontal_scale, perm, p.heightmap, hmax)
    elif p.march_method == MARCH_BISECT:
        hit, t, steps = _march_bisect(ro, rd, p.max_t, p.precision, p.max_steps, p.step_scale, p.bisect_threshold,
                                      p.bisect_steps, p.march_octaves, p.height_scale, p.horizontal_scale, perm,
                                      p.heightmap, hmax)
    else:
        hit, t, steps = _march_dynamic(ro, rd, p.max_t, p.precision, p.max_steps, p.step_scale, p.march_octaves,
                                       p.height_scale, p.horizontal_scale, perm, p.heightmap, hmax,
                                       p.precision_per_unit)
    sky = terrain_sky(rd, p.sun, p.sky_colour, p.sun_colour, p.sun_power)
    background = sky
    if p.stage >= STAGE_ATMOSPHERE:
        background = clouds_perm(sky, ro, rd, p.cloud_height, p.wind, p.time, p.cloud_scale, p.cloud_colour, perm,
                                 p.cloud_variant)
    if hit == 0:
        return background, steps, -1.0
    pos = _along(ro, rd, t)
    colour = _terrain_colour(p, perm, pos, t)
    dist = t
    if p.stage >= STAGE_FINAL and pos[1] < p.water_level and rd[1] < 0.0 and ro[1] > p.water_level:
        tw = (p.water_level - ro[1]) / rd[1]
        wpos = _along(ro, rd, tw)
        n = terrain_water_normal_perm(wpos[0], wpos[2], p.time, p.wave_scale, p.wave_strength, perm)
        rdn = 2.0 * _dot(rd, n)
        ry = rd[1] - n[1] * rdn
        if ry < 0.0:
            ry = -ry
        r = wp.vec3(rd[0] - n[0] * rdn, ry, rd[2] - n[2] * rdn)
        reflected = terrain_sky(r, p.sun, p.sky_colour, p.sun_colour, p.sun_power)
        reflected = clouds_perm(reflected, wpos, r, p.cloud_height, p.wind, p.time, p.cloud_scale, p.cloud_colour,
                                perm, p.cloud_variant)
        f = terrain_water_weight(rd, n, p.water_kappa)
        under = wp.vec3(colour[0] * p.water_tint[0], colour[1] * p.water_tint[1], colour[2] * p.water_tint[2])
        colour = mix3(reflected, under, f)
        dist = tw
    if p.stage >= STAGE_ATMOSPHERE:
        colour = mix3(colour, sky, terrain_fog(dist, p.fog_density, p.fog_variant))
    return colour, steps, dist


@wp.func
def terrain_pixel(p: TerrainParams, perm: wp.array(dtype=wp.int32), inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                  x: int, y: int, width: int, height: int) -> tuple[wp.vec3, int]:
    """pt-alg-7.1.6 (twin of ccl_terrain_pixel): mean of m x m regular sub-sample shades, each clamped to [0, 1];
    the rays are camera_ray's (pt-code-7.2) with the sub-pixel offset ((i + 0.5) / m, (j + 0.5) / m)."""
    m = inv_view_proj_rot
    nn = p.samples_per_axis
    steps = int(0)
    ax = float(0.0)
    ay = float(0.0)
    az = float(0.0)
    for j in range(nn):
        for i in range(nn):
            ox = (float(i) + 0.5) / float(nn)
            oy = (float(j) + 0.5) / float(nn)
            u = (float(x) + ox) / float(width)
            v = (float(y) + oy) / float(height)
            nx = 2.0 * u - 1.0
            ny = 1.0 - 2.0 * v
            rd = _normalize(wp.vec3(m[0][0] * nx + m[0][1] * ny + m[0][2] + m[0][3],
                                    m[1][0] * nx + m[1][1] * ny + m[1][2] + m[1][3],
                                    m[2][0] * nx + m[2][1] * ny + m[2][2] + m[2][3]))
            c, s = terrain_shade(p, perm, eye, rd)
            steps += s
            ax += clamp01(c[0])
            ay += clamp01(c[1])
            az += clamp01(c[2])
    inv = float(nn * nn)
    return wp.vec3(ax / inv, ay / inv, az / inv), steps


@wp.func
def _pixel_depth(p: TerrainParams, perm: wp.array(dtype=wp.int32), inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                 x: int, y: int, width: int, height: int) -> tuple[wp.vec3, int, float]:
    """terrain_pixel with one ray (samples_per_axis 1: the same operations) and the distance of _shade_dist."""
    m = inv_view_proj_rot
    u = (float(x) + 0.5) / float(width)
    v = (float(y) + 0.5) / float(height)
    nx = 2.0 * u - 1.0
    ny = 1.0 - 2.0 * v
    rd = _normalize(wp.vec3(m[0][0] * nx + m[0][1] * ny + m[0][2] + m[0][3],
                            m[1][0] * nx + m[1][1] * ny + m[1][2] + m[1][3],
                            m[2][0] * nx + m[2][1] * ny + m[2][2] + m[2][3]))
    c, s, dist = _shade_dist(p, perm, eye, rd)
    return wp.vec3(clamp01(c[0]), clamp01(c[1]), clamp01(c[2])), s, dist


@wp.kernel
def render_kernel(row0: int, p: TerrainParams, perm: wp.array(dtype=wp.int32), inv_view_proj_rot: wp.mat44,
                  eye: wp.vec3, width: int, height: int, out: wp.array3d(dtype=float),
                  steps: wp.array2d(dtype=wp.int32), depth: wp.array2d(dtype=float)):
    """The image: terrain_pixel per pixel; ``depth`` the distance along the pixel's centre ray to the surface it
    shows (-1: the sky), written for one ray per pixel (-1 everywhere when supersampled)."""
    i, j = wp.tid()
    y = row0 + i
    c = wp.vec3(0.0, 0.0, 0.0)
    s = int(0)
    dist = float(-1.0)
    if p.samples_per_axis == 1:
        c, s, dist = _pixel_depth(p, perm, inv_view_proj_rot, eye, j, y, width, height)
    else:
        c, s = terrain_pixel(p, perm, inv_view_proj_rot, eye, j, y, width, height)
    out[y, j, 0] = c[0]
    out[y, j, 1] = c[1]
    out[y, j, 2] = c[2]
    steps[y, j] = s
    depth[y, j] = dist


@wp.kernel
def _shade_kernel(p: TerrainParams, perm: wp.array(dtype=wp.int32), ro: wp.array(dtype=wp.vec3),
                  rd: wp.array(dtype=wp.vec3), out: wp.array(dtype=wp.vec3), steps: wp.array(dtype=wp.int32)):
    k = wp.tid()
    c, s = terrain_shade(p, perm, ro[k], rd[k])
    out[k] = c
    steps[k] = s


@wp.kernel
def _pixels_kernel(p: TerrainParams, perm: wp.array(dtype=wp.int32), inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                   xs: wp.array(dtype=wp.int32), ys: wp.array(dtype=wp.int32), width: int, height: int,
                   out: wp.array(dtype=wp.vec3), steps: wp.array(dtype=wp.int32)):
    k = wp.tid()
    c, s = terrain_pixel(p, perm, inv_view_proj_rot, eye, xs[k], ys[k], width, height)
    out[k] = c
    steps[k] = s


@wp.kernel
def _height_kernel(x: wp.array(dtype=float), z: wp.array(dtype=float), octaves: int, height_scale: float,
                   horizontal_scale: float, perm: wp.array(dtype=wp.int32), heightmap: int,
                   out: wp.array(dtype=float)):
    k = wp.tid()
    out[k] = terrain_height_perm(x[k], z[k], octaves, height_scale, horizontal_scale, perm, heightmap)


@wp.kernel
def _water_normal_kernel(x: wp.array(dtype=float), z: wp.array(dtype=float), time: float, wave_scale: float,
                         wave_strength: float, perm: wp.array(dtype=wp.int32), out: wp.array(dtype=wp.vec3)):
    k = wp.tid()
    out[k] = terrain_water_normal_perm(x[k], z[k], time, wave_scale, wave_strength, perm)


# Not element-wise: the scene parameters (ccl_terrain_params, ~50 fields and the Perlin table) are a struct argument
# shared by every ray.
declare("pt-code-7.3", "pt-alg-7.3.4", "pt-alg-7.3-material", c="ccl_terrain_shade",
        make_warp="pywarp.terrain.evaluators:shade_warp", make_c="pywarp.terrain.evaluators:shade_c",
        summary="terrain_shade(ro, rd, params) -> (colour (..., 3), steps): the demo's top-level shading (Kod 7.3; "
                "castRay returns its t, as the note fixes the 2-argument call) with everything of ch. 7: march "
                "(fixed / dynamic / bisect), normal with distance-dependent octaves, materials by height and grass "
                "by normal (Obrazok 7.10 stages heightmap, materials, atmosphere, final), shadow, eq 7.1 light, "
                "water (7.3.4: the plane y = water_level in front of underwater terrain, wave normal from noise + "
                "sines, reflection of sky + clouds only, mix(reflection, tint * underwater colour, eq 7.4)), clouds "
                "and fog. params: a dict of ccl_terrain_params fields (pywarp.terrain.TerrainSettings.c_values()).",
        references=_REF)(terrain_shade)

# Not element-wise: the scene parameters and the camera (ccl_camera) are struct arguments shared by every pixel.
declare("pt-alg-7.1.6", c="ccl_terrain_pixel", make_warp="pywarp.terrain.evaluators:pixel_warp",
        make_c="pywarp.terrain.evaluators:pixel_c",
        summary="terrain_pixel(x, y, width, height, camera, params) -> (rgb (..., 3), steps): the C reference pixel "
                "of the terrain scene. Supersampling (7.1.6): the mean of m x m regular sub-sample shades (m = "
                "samples_per_axis: 1, 2, 4 for the text's 1, 4, 16 rays) at offsets ((i + 0.5) / m, (j + 0.5) / m), "
                "each clamped to [0, 1]; the rays are camera_ray's (pt-code-7.2, fov 90 deg), exactly for m = 1.",
        references=_REF)(terrain_pixel)


__all__ = ["HEIGHTMAPS", "MARCH_METHODS", "SHADOW_KINDS", "STAGES", "TerrainParams",
           "fbm_perm", "hashed_perm_array", "render_kernel", "terrain_clouds", "terrain_fog",
           "terrain_height_perm", "terrain_lighting", "terrain_march_bisect", "terrain_march_dynamic",
           "terrain_march_fixed", "terrain_normal", "terrain_normal_octaves", "terrain_pixel",
           "terrain_pixel_position", "terrain_shade", "terrain_shadow_hard", "terrain_shadow_soft", "terrain_sky",
           "terrain_water_normal_perm", "terrain_water_weight"]
