"""Interpolants and remap -- Warp twins of ``cclouds/interp.h``.

* Fade curves of Perlin noise: :func:`interp_fade_cubic` (vc-2.19, Perlin 1985) and :func:`interp_fade_quintic`
  (vc-2.20, Perlin 2002).
* :func:`interp_lerp` (Perlin's lerp, argument order (t, a, b)) and :func:`interp_cosine` (cosine interpolation),
  the curves vc-fig-2.6 compares the fades with; they have no catalogue ID of their own (vc-A1 step 3 names them
  without a formula), so they are helpers, not registry entries. :func:`pywarp.clouds.noise.interpolants` evaluates
  all four curves on NumPy arrays. The oc text's printed listings (oc-5.1.4.1 ``Linear_Interp(a, b, x) = a*(1-x) + b*x``, oc-5.1.4.2
  ``Cosine_Interp``) are the same functions in exact arithmetic but not in float32 -- the printed blend gives exactly
  b at x = 1, ``a + t(b - a)`` need not -- and take (a, b, x): they are their own entries,
  :func:`pywarp.kernels.valuenoise.valuenoise_linear` / ``valuenoise_cosine`` (with the printed cubic, oc-5.1.4.3).
* :func:`interp_remap` (vc-2.27), the linear range remap used by the cloud density model.
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.registry import Arg, declare

_PI = wp.constant(3.14159265358979323846)

_PERLIN_2002 = ("K. Perlin, Improving Noise, SIGGRAPH 2002 (reference code ImprovedNoise.java, "
                "https://mrl.cs.nyu.edu/~perlin/noise/)")
_PERLIN_1985 = "K. Perlin, An Image Synthesizer, SIGGRAPH 1985"
_T = Arg("t", "fractional position in a lattice cell", lo=0.0, hi=1.0)


@declare("vc-2.19", c="ccl_interp_fade_cubic", args=(_T,), outputs=("f",),
         summary="Fade (smoothstep) 3t^2 - 2t^3 = t*t*(3 - 2t); f(0)=0, f(1)=1, f'(0)=f'(1)=0. The linear (t) and "
                 "cosine ((1 - cos pi t)/2) interpolants it replaces are ccl_interp_lerp / ccl_interp_cosine "
                 "(Warp interp_lerp / interp_cosine), see vc-A1.",
         references=(_PERLIN_1985,))
@wp.func
def interp_fade_cubic(t: float) -> float:
    """vc-2.19: 3t^2 - 2t^3 as t*t*(3 - 2t)."""
    return t * t * (3.0 - 2.0 * t)


@declare("vc-2.20", c="ccl_interp_fade_quintic", args=(_T,), outputs=("f",),
         summary="Improved fade 6t^5 - 15t^4 + 10t^3 in Perlin's Horner form t*t*t*(t*(t*6 - 15) + 10); also f''=0 "
                 "at t = 0, 1. The thesis cites it as 'see formula [25]' (a citation printed for the equation "
                 "number).",
         references=(_PERLIN_2002,))
@wp.func
def interp_fade_quintic(t: float) -> float:
    """vc-2.20: 6t^5 - 15t^4 + 10t^3 in Perlin's Horner form; 1 where it rounds to 1 + 2^-23 (22,237 floats in
    [0.99536, 1), fuzz finding Q), as ``ccl_interp_fade_quintic``."""
    f = t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
    if f > 1.0:
        return 1.0
    return f


@wp.func
def interp_lerp(t: float, a: float, b: float) -> float:
    """Perlin's lerp: a + t (b - a), as ``ccl_interp_lerp``."""
    return a + t * (b - a)


@wp.func
def interp_cosine(t: float, a: float, b: float) -> float:
    """Cosine interpolation lerp((1 - cos(pi t)) / 2, a, b), as ``ccl_interp_cosine``."""
    s = (1.0 - wp.cos(_PI * t)) * 0.5
    return a + s * (b - a)


def _check_remap(v, o_min, o_max, n_min, n_max, **_):
    same = np.asarray(o_max == o_min)
    if np.any(same):
        bad = np.broadcast_to(o_max, same.shape)[same].flat[0]
        raise ValueError(f"o_max must differ from o_min (empty original range), got o_max = o_min = {bad!r}")


@declare("vc-2.27", c="ccl_interp_remap",
         args=(Arg("v", "value"), Arg("o_min", "start of the original range"),
               Arg("o_max", "end of the original range"), Arg("n_min", "start of the new range"),
               Arg("n_max", "end of the new range")),
         outputs=("r",), check=_check_remap,
         summary="remap(v, o_min, o_max, n_min, n_max) = n_min + (v - o_min)/(o_max - o_min) (n_max - n_min); "
                 "unclamped (extrapolates linearly), reversed ranges allowed, o_max != o_min.")
@wp.func
def interp_remap(v: float, o_min: float, o_max: float, n_min: float, n_max: float) -> float:
    """vc-2.27: n_min + (v - o_min) / (o_max - o_min) * (n_max - n_min), unclamped."""
    return n_min + (v - o_min) / (o_max - o_min) * (n_max - n_min)


@wp.kernel
def _lerp_cosine_curves(t: wp.array(dtype=float), lin: wp.array(dtype=float), cos: wp.array(dtype=float)):
    # the two helper curves of vc-fig-2.6 on [0, 1] (no registry entry, so no generated kernel)
    i = wp.tid()
    lin[i] = interp_lerp(t[i], 0.0, 1.0)
    cos[i] = interp_cosine(t[i], 0.0, 1.0)
