"""Value noise of the oc text (Kucera 2006, §5.1) -- Warp twins of ``cclouds/valuenoise.h``.

The text builds "Perlin noise" the way Hugo Elias's tutorial does: random values on an integer lattice, smoothed,
interpolated, summed over octaves with a persistence. That is value noise (spec erratum 1), not Perlin's gradient
noise (:mod:`pywarp.kernels.noise`).

* :func:`valuenoise_lattice` (oc-5.1.2) -- the seeded lattice hash, built on the project's PCG hash
  (:func:`pywarp.kernels.hash.hash_pcg`): ``hash_unit(pcg(x + pcg(y + pcg(z + seed))))``; range [0, 1] by default
  (the cloud filter multiplies by 255), [-1, 1] as ``value_range="signed"`` (the text states both, erratum 2).
  1-D noise is the x axis, 2-D the z = 0 plane.
* :func:`valuenoise_smooth` (oc-5.1.3) -- neighbour smoothing: ``"elias"`` (default: corners/16 + sides/8 +
  centre/4 in 2-D, the binomial (1/4, 1/2, 1/4) per axis in 1-D and 3-D), ``"4-neighbour"`` (mean of the side
  neighbours, 6 in 3-D), ``"8-neighbour"`` (mean of all neighbours, 26 in 3-D), ``"none"``. The text names no
  neighbourhood (erratum 4).
* :func:`valuenoise_linear`, :func:`valuenoise_cosine`, :func:`valuenoise_cubic` (oc-5.1.4.1 - 5.1.4.3) -- the
  printed listings, argument order (a, b, x). They are not :func:`pywarp.kernels.interp.interp_lerp` /
  ``interp_cosine``: the printed blend ``a(1 - x) + bx`` gives exactly b at x = 1 in float32, Perlin's
  ``a + t(b - a)`` need not. The cubic is NOT Catmull-Rom: its end slopes are v2 - v0 and v3 - v1, twice
  Catmull-Rom's.
* :func:`valuenoise_interpolated` (oc-5.1.4) -- the smoothed lattice interpolated at a continuous point, separable
  over 1, 2 or 3 axes (bilinear / trilinear for ``"linear"``; 4 nodes per axis for ``"cubic"``).
* :func:`valuenoise_amplitude` (oc-5.1.2.2) -- the persistence schedule: p^i (``"corrected"``) or the printed
  squaring p^(2^i) (``variant="thesis"``, erratum 3).
* :func:`valuenoise_fbm` (oc-5.1.1, oc-5.1.2.1, oc-4.5) -- the octave sum: frequency 2^i, octave seed
  ``pcg(seed) + i``, divided by the sum of the amplitudes (so it stays in the noise's range).
* :func:`octave_image` -- the text's 2-D procedure (16 x 16 -> 256 x 256: every layer bilinearly up-sampled to the
  final resolution, weighted, summed) on NumPy arrays, layers included.
"""
from __future__ import annotations

import warp as wp

from ..core.registry import VARIANT, Arg, Option, declare
from .hash import hash_pcg, hash_pcg_py, hash_unit

MAX_OCTAVES = 12  # CCL_VALUENOISE_MAX_OCTAVES
MAX_COORD = 4096  # CCL_VALUENOISE_MAX_COORD
MAX_LATTICE = 2 ** 24  # integer lattice coordinates of the element-wise entries
_MAX_OCTAVES = wp.constant(MAX_OCTAVES)
_PI_PRINTED = wp.constant(3.1415927)  # pi as printed in the cosine listing (the float32 nearest pi)

VALUE_RANGES = {"unit": 0, "signed": 1}  # CCL_VALUENOISE_UNIT / _SIGNED
SMOOTHINGS = {"elias": 0, "4-neighbour": 1, "8-neighbour": 2, "none": 3}  # CCL_VALUENOISE_SMOOTH_*
INTERPOLATIONS = {"linear": 0, "cosine": 1, "cubic": 2}  # CCL_VALUENOISE_LINEAR / COSINE / CUBIC
_SIGNED = wp.constant(1)
_ELIAS = wp.constant(0)
_SMOOTH_4 = wp.constant(1)
_SMOOTH_NONE = wp.constant(3)
_COSINE = wp.constant(1)
_CUBIC = wp.constant(2)
_THESIS = wp.constant(1)

VALUE_RANGE = Option("value_range", VALUE_RANGES, "unit",
                     "'unit' (default): lattice values in [0, 1] (what the cloud filter oc-5.2.2 expects, L334); "
                     "'signed': [-1, 1] as 2u - 1 (L326)")
SMOOTHING = Option("smoothing", SMOOTHINGS, "elias",
                   "'elias' (default): corners/16 + sides/8 + centre/4 (binomial 1/4, 1/2, 1/4 per axis); "
                   "'4-neighbour': mean of the side neighbours (1-D 2, 3-D 6), centre excluded; '8-neighbour': mean "
                   "of all neighbours (1-D 2, 3-D 26); 'none': raw lattice values")
INTERPOLATION = Option("interpolation", INTERPOLATIONS, "linear",
                       "'linear' (default; bilinear / trilinear, as the text up-samples), 'cosine', 'cubic' (the "
                       "printed cubic, 4 nodes per axis)")
_REF_ELIAS = "H. Elias, Perlin Noise and Clouds tutorials (freespace.virgin.net/hugo.elias, c. 1998), oc ref. [3]"
_REF_PCG = "M. Jarzynski & M. Olano, Hash Functions for GPU Rendering, JCGT 9(3), 2020 (the lattice hash)"


# --- lattice and smoothing ---------------------------------------------------------------------------------------------

@wp.func
def _value(h: wp.uint32, value_range: int) -> float:
    u = hash_unit(h)
    if value_range == _SIGNED:
        return 2.0 * u - 1.0
    return u


def _icoord(name):
    return Arg(name, f"lattice coordinate {name} (integer >= 0; ignored beyond dims)", lo=0, hi=MAX_LATTICE,
               dtype="int32")


_SEED = Arg("seed", "uint32 seed; the same seed gives the same noise", lo=0, hi=2 ** 32 - 1, dtype="uint32")
_DIMS = Arg("dims", "dimension of the noise: 1 (x), 2 (x, y) or 3 (x, y, z)", lo=1, hi=3, dtype="int32")


@declare("oc-5.1.2", c="ccl_valuenoise_lattice", args=(_icoord("x"), _icoord("y"), _icoord("z"), _SEED),
         options=(VALUE_RANGE,), outputs=("n",),
         summary="Lattice noise: a deterministic pseudo-random value of non-negative integers, "
                 "hash_unit(pcg(x + pcg(y + pcg(z + seed)))) with the project's PCG hash (the text gives no "
                 "generator). 'unit': {0, 2^-24, ..., 1 - 2^-24}; 'signed': 2u - 1. 1-D noise is (x, 0, 0), 2-D "
                 "(x, y, 0).",
         references=(_REF_PCG, _REF_ELIAS))
@wp.func
def valuenoise_lattice(x: int, y: int, z: int, seed: wp.uint32, value_range: int) -> float:
    """oc-5.1.2: hash_unit(pcg(x + pcg(y + pcg(z + seed)))) (uint32 sums), or 2u - 1 for 'signed'."""
    hz = hash_pcg(wp.uint32(z) + seed)
    hy = hash_pcg(wp.uint32(y) + hz)
    return _value(hash_pcg(wp.uint32(x) + hy), value_range)


@wp.func
def _elias_weight(d: int, r: int) -> float:
    if r == 0:
        return 1.0
    if d == 0:
        return 0.5
    return 0.25


@declare("oc-5.1.3", c="ccl_valuenoise_smooth",
         args=(_icoord("x"), _icoord("y"), _icoord("z"), _SEED, _DIMS), options=(SMOOTHING, VALUE_RANGE),
         outputs=("n",),
         summary="Smoothed lattice noise: the weighted average of the lattice point's neighbourhood over the first "
                 "dims axes. 'elias' (default): Elias's corners/16 + sides/8 + centre/4 (2-D), i.e. the binomial "
                 "(1/4, 1/2, 1/4) per axis (1-D centre/2 + sides/4; 3-D corners/64 + edges/32 + faces/16 + "
                 "centre/8); '4-neighbour' / '8-neighbour': the plain mean of the side / all neighbours, centre "
                 "excluded ('the average of the neighbours', §5.1.3; 3-D: 6 / 26); 'none': the raw value. The text "
                 "names no neighbourhood.",
         references=(_REF_ELIAS,))
@wp.func
def valuenoise_smooth(x: int, y: int, z: int, seed: wp.uint32, dims: int, smoothing: int,
                      value_range: int) -> float:
    """oc-5.1.3: neighbour smoothing of the lattice noise (loop order z, y, x as in C)."""
    xx = x
    yy = y
    zz = z
    ry = 1
    rz = 1
    if dims < 2:
        yy = 0
        ry = 0
    if dims < 3:
        zz = 0
        rz = 0
    if smoothing == _SMOOTH_NONE:
        return valuenoise_lattice(xx, yy, zz, seed, value_range)
    total = float(0.0)
    count = int(0)
    for dz in range(-rz, rz + 1):
        hz = hash_pcg(wp.uint32(zz) + wp.uint32(dz) + seed)
        for dy in range(-ry, ry + 1):
            hy = hash_pcg(wp.uint32(yy) + wp.uint32(dy) + hz)
            for dx in range(-1, 2):
                off = int(0)
                if dx != 0:
                    off += 1
                if dy != 0:
                    off += 1
                if dz != 0:
                    off += 1
                if smoothing == _ELIAS:
                    v = _value(hash_pcg(wp.uint32(xx) + wp.uint32(dx) + hy), value_range)
                    total += _elias_weight(dx, 1) * _elias_weight(dy, ry) * _elias_weight(dz, rz) * v
                elif off == 0 or (smoothing == _SMOOTH_4 and off > 1):
                    continue
                else:
                    v = _value(hash_pcg(wp.uint32(xx) + wp.uint32(dx) + hy), value_range)
                    total += v
                    count += 1
    if smoothing == _ELIAS:
        return total
    return total / float(count)


# --- the printed interpolants -------------------------------------------------------------------------------------------

_AB = (Arg("a", "value at x = 0 (A)"), Arg("b", "value at x = 1 (B)"))
_X = Arg("x", "position between the two values", lo=0.0, hi=1.0)


@wp.func
def _between(r: float, a: float, b: float) -> float:
    """r within [min(a, b), max(a, b)]: a (1 - f) + b f rounds up to an ulp outside (1000.00006 for a = b = 1000 in
    the cosine form, fuzz finding I1), such a result is the nearest end value; a NaN stays NaN (twin of ``between``,
    valuenoise.c)."""
    lo = b
    hi = a
    if a < b:
        lo = a
        hi = b
    if r < lo:
        return lo
    if r > hi:
        return hi
    return r


@declare("oc-5.1.4.1", c="ccl_valuenoise_linear", args=(*_AB, _X), outputs=("v",),
         summary="Linear_Interp(a, b, x) = a*(1-x) + b*x, as printed; exactly a at x = 0 and b at x = 1 (unlike "
                 "interp_lerp's a + x(b - a), which is the same function but need not give b exactly in float32).",
         references=(_REF_ELIAS,))
@wp.func
def valuenoise_linear(a: float, b: float, x: float) -> float:
    """oc-5.1.4.1: a*(1-x) + b*x, within [min(a, b), max(a, b)]."""
    return _between(a * (1.0 - x) + b * x, a, b)


@declare("oc-5.1.4.2", c="ccl_valuenoise_cosine", args=(*_AB, _X), outputs=("v",),
         summary="Cosine_Interp(a, b, x): ft = x * 3.1415927, f = (1 - cos(ft)) * .5, a*(1-f) + b*f, as printed "
                 "(pi written 3.1415927, the float32 nearest pi). a at 0, b at 1, (a+b)/2 at 1/2; (0, 1, 0.25) -> "
                 "0.1464466.",
         references=(_REF_ELIAS,))
@wp.func
def valuenoise_cosine(a: float, b: float, x: float) -> float:
    """oc-5.1.4.2: f = (1 - cos(3.1415927 x)) / 2; a(1 - f) + b f, within [min(a, b), max(a, b)]."""
    ft = x * _PI_PRINTED
    f = (1.0 - wp.cos(ft)) * 0.5
    return _between(a * (1.0 - f) + b * f, a, b)


@declare("oc-5.1.4.3", c="ccl_valuenoise_cubic",
         args=(Arg("v0", "the point before a"), Arg("v1", "a (value at x = 0)"), Arg("v2", "b (value at x = 1)"),
               Arg("v3", "the point after b"), _X),
         outputs=("v",),
         summary="Cubic(v0, v1, v2, v3, x) as printed: P = (v3 - v2) - (v0 - v1), Q = (v0 - v1) - P, R = v2 - v0, "
                 "S = v1, P x^3 + Q x^2 + R x + S (the printed 'Px3 + Qx2' lost its superscripts). v1 at x = 0, v2 at "
                 "x = 1 (up to rounding); slope v2 - v0 at 0 and v3 - v1 at 1: NOT Catmull-Rom (slope (v2 - v0)/2). "
                 "May overshoot its samples. 'Five values instead of three' counts x.",
         references=(_REF_ELIAS,))
@wp.func
def valuenoise_cubic(v0: float, v1: float, v2: float, v3: float, x: float) -> float:
    """oc-5.1.4.3: the printed cubic, evaluated P*x*x*x + Q*x*x + R*x + S."""
    p = (v3 - v2) - (v0 - v1)
    q = (v0 - v1) - p
    r = v2 - v0
    s = v1
    return p * x * x * x + q * x * x + r * x + s


@wp.func
def interp_kind(kind: int, v0: float, v1: float, v2: float, v3: float, t: float) -> float:
    """The interpolant of ``kind`` (INTERPOLATIONS) on nodes v0..v3 (linear and cosine use v1, v2 only)."""
    if kind == _CUBIC:
        return valuenoise_cubic(v0, v1, v2, v3, t)
    if kind == _COSINE:
        return valuenoise_cosine(v1, v2, t)
    return valuenoise_linear(v1, v2, t)


# --- separable interpolation of the smoothed lattice --------------------------------------------------------------------

@wp.func
def _line_x(ix: int, y: int, z: int, fx: float, seed: wp.uint32, dims: int, smoothing: int, interpolation: int,
            value_range: int) -> float:
    v0 = float(0.0)
    v3 = float(0.0)
    if interpolation == _CUBIC:
        v0 = valuenoise_smooth(ix - 1, y, z, seed, dims, smoothing, value_range)
        v3 = valuenoise_smooth(ix + 2, y, z, seed, dims, smoothing, value_range)
    v1 = valuenoise_smooth(ix, y, z, seed, dims, smoothing, value_range)
    v2 = valuenoise_smooth(ix + 1, y, z, seed, dims, smoothing, value_range)
    return interp_kind(interpolation, v0, v1, v2, v3, fx)


@wp.func
def _plane_xy(ix: int, iy: int, z: int, fx: float, fy: float, seed: wp.uint32, dims: int, smoothing: int,
              interpolation: int, value_range: int) -> float:
    if dims < 2:
        return _line_x(ix, 0, 0, fx, seed, dims, smoothing, interpolation, value_range)
    v0 = float(0.0)
    v3 = float(0.0)
    if interpolation == _CUBIC:
        v0 = _line_x(ix, iy - 1, z, fx, seed, dims, smoothing, interpolation, value_range)
        v3 = _line_x(ix, iy + 2, z, fx, seed, dims, smoothing, interpolation, value_range)
    v1 = _line_x(ix, iy, z, fx, seed, dims, smoothing, interpolation, value_range)
    v2 = _line_x(ix, iy + 1, z, fx, seed, dims, smoothing, interpolation, value_range)
    return interp_kind(interpolation, v0, v1, v2, v3, fy)


_FCOORD = lambda name: Arg(name, f"coordinate {name} in lattice units (ignored beyond dims)", lo=0.0,  # noqa: E731
                           hi=float(MAX_COORD), sample_range=(0.0, 64.0))


@declare("oc-5.1.4", c="ccl_valuenoise_interpolated",
         args=(_FCOORD("x"), _FCOORD("y"), _FCOORD("z"), _SEED, _DIMS),
         options=(SMOOTHING, INTERPOLATION, VALUE_RANGE), outputs=("n",),
         summary="Interpolated smoothed noise at a continuous point: the 1-D interpolant (x = 0 -> A, x = 1 -> B) "
                 "applied per axis, x then y then z, over the first dims axes -- linear gives bilinear / trilinear "
                 "(2 x 2 / 2 x 2 x 2 nodes), cosine the same nodes, cubic 4 nodes per axis (4, 16, 64 smoothed "
                 "values). Equals valuenoise_smooth at lattice points.",
         references=(_REF_ELIAS,))
@wp.func
def valuenoise_interpolated(x: float, y: float, z: float, seed: wp.uint32, dims: int, smoothing: int,
                            interpolation: int, value_range: int) -> float:
    """oc-5.1.4: separable interpolation of valuenoise_smooth at (x, y, z)."""
    flx = wp.floor(x)
    fly = wp.floor(y)
    flz = wp.floor(z)
    ix = int(flx)
    iy = int(fly)
    iz = int(flz)
    fx = x - flx
    fy = y - fly
    fz = z - flz
    if dims < 3:
        return _plane_xy(ix, iy, 0, fx, fy, seed, dims, smoothing, interpolation, value_range)
    v0 = float(0.0)
    v3 = float(0.0)
    if interpolation == _CUBIC:
        v0 = _plane_xy(ix, iy, iz - 1, fx, fy, seed, dims, smoothing, interpolation, value_range)
        v3 = _plane_xy(ix, iy, iz + 2, fx, fy, seed, dims, smoothing, interpolation, value_range)
    v1 = _plane_xy(ix, iy, iz, fx, fy, seed, dims, smoothing, interpolation, value_range)
    v2 = _plane_xy(ix, iy, iz + 1, fx, fy, seed, dims, smoothing, interpolation, value_range)
    return interp_kind(interpolation, v0, v1, v2, v3, fz)


# --- octaves and persistence --------------------------------------------------------------------------------------------

@declare("oc-5.1.2.2", c="ccl_valuenoise_amplitude",
         args=(Arg("octave", "octave index i (0 = the first, lowest frequency)", lo=0, hi=MAX_OCTAVES - 1,
                   dtype="int32"),
               Arg("persistence", "persistence p", lo=0.0, hi=1.0)),
         options=(VARIANT,), outputs=("amplitude",),
         summary="Amplitude of octave i. 'corrected' (default): p^i (Elias: amplitude = amplitude * persistence, "
                 "1 for the first octave); 'thesis': the printed 'Persistence = persistence * Persistence' read "
                 "literally with one variable, p^(2^i) = p, p^2, p^4, p^8, ... Repeated multiplication (no pow).",
         references=(_REF_ELIAS,))
@wp.func
def valuenoise_amplitude(octave: int, persistence: float, variant: int) -> float:
    """oc-5.1.2.2: p^i ('corrected') or p^(2^i) ('thesis') by repeated multiplication."""
    a = float(1.0)
    if variant == _THESIS:
        a = persistence
    n = wp.min(octave, _MAX_OCTAVES)
    for _i in range(n):
        if variant == _THESIS:
            a = a * a
        else:
            a = a * persistence
    return a


@declare("oc-5.1.1", "oc-5.1.2.1", "oc-4.5", c="ccl_valuenoise_fbm",
         args=(_FCOORD("x"), _FCOORD("y"), _FCOORD("z"), _SEED, _DIMS,
               Arg("octaves", "number of octaves ('generally 6 is enough', §5.1.2.1)", lo=1, hi=MAX_OCTAVES,
                   dtype="int32", default=6),
               Arg("persistence", "persistence p (0 excluded: every 'thesis' amplitude would be 0)", lo=0.0,
                   lo_open=True, hi=1.0, default=0.5)),
         options=(SMOOTHING, INTERPOLATION, VARIANT, VALUE_RANGE), outputs=("n",),
         summary="Octave sum ('Perlin noise' of the text; value-noise fBm): sum_i a_i N_i(2^i p) / sum_i a_i, "
                 "i < octaves, N_i = valuenoise_interpolated with octave seed pcg(seed) + i, a_i = "
                 "valuenoise_amplitude(i, persistence, variant); frequency 1 first, x2 per octave (§5.1.2.1); "
                 "normalised by the amplitude sum so the result stays in the noise's range. Defaults: 6 octaves "
                 "(§5.1.2.1), persistence 0.5 (Elias's example; the text gives none). oc-4.5: the procedural noise "
                 "of the survey is this pipeline.",
         references=(_REF_ELIAS,))
@wp.func
def valuenoise_fbm(x: float, y: float, z: float, seed: wp.uint32, dims: int, octaves: int, persistence: float,
                   smoothing: int, interpolation: int, variant: int, value_range: int) -> float:
    """oc-5.1.1: normalised octave sum of valuenoise_interpolated."""
    base = hash_pcg(seed)
    total = float(0.0)
    norm = float(0.0)
    freq = float(1.0)
    a = float(1.0)
    if variant == _THESIS:
        a = persistence
    n = wp.min(octaves, _MAX_OCTAVES)
    for i in range(n):
        total += a * valuenoise_interpolated(x * freq, y * freq, z * freq, base + wp.uint32(i), dims, smoothing,
                                             interpolation, value_range)
        norm += a
        freq *= 2.0
        if variant == _THESIS:
            a = a * a
        else:
            a = a * persistence
    return total / norm


# --- NumPy helpers -------------------------------------------------------------------------------------------------------

def octave_seed(seed: int, octave: int) -> int:
    """The seed of octave (or cloud-array level) ``octave``: ``ccl_hash_pcg(seed) + octave`` (mod 2^32)."""
    return (hash_pcg_py(int(seed) & 0xFFFFFFFF) + int(octave)) & 0xFFFFFFFF


