"""Escape-time fractals (pt §3.6) -- Warp twins of ``cclouds/fractal.h``.

Complex numbers are ``wp.vec2`` (x = real part, y = imaginary part): the registry's vector type, so one argument is
one complex number (NumPy arrays of shape ``(..., 2)``, ``ccl_vec2`` by value in C) and a whole plane of start values is
one array. Arithmetic in float32: (a + bi)(c + di) = (ac - bd) + (ad + bc)i, in the order of fractal.c.

* pt-3.1 :func:`fractal_julia`: a_0 = z0, a_{n+1} = f(a_n) for f = z^d + c (escape |z| > R) or e^z + c (escape
  Re z > R: e^z is 2 pi i-periodic and tiny for Re z << 0, so |z| is no escape test for it).
* pt-u-julia :func:`fractal_julia_example`: the three maps of Obrazok 3.8 with the escape tests that suit them.
* pt-3.2 :func:`fractal_quadratic`: z^2 - mu as printed (``variant="thesis"``) or the usual z^2 + c.
* pt-3.3 :func:`fractal_mandelbrot`: a_0 = 0, member while |a_n| <= 2.

Results: the escape count n (the index of the first iterate that fails the test; ``max_iter`` = no escape, taken as
a member) and a continuous ("smooth") count for colouring: n + 1 - log_d(ln|a_n| / ln R) for the polynomial maps,
n + 1 - clamp(ln(Re a_n) / R, 0, 1) for the exp map, ``max_iter`` for members. Both are arrays of the input's shape.
"""
from __future__ import annotations

import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import VARIANT, Arg, Option, declare
from . import VARIANT_THESIS

MAP_POLY = c_constant("CCL_FRACTAL_POLY", 0)
MAP_EXP = c_constant("CCL_FRACTAL_EXP", 1)
JULIA_X5 = c_constant("CCL_JULIA_X5", 0)
JULIA_X2 = c_constant("CCL_JULIA_X2", 1)
JULIA_EXP = c_constant("CCL_JULIA_EXP", 2)
MAPS = {"poly": MAP_POLY, "exp": MAP_EXP}
EXAMPLES = {"x5": JULIA_X5, "x2": JULIA_X2, "exp": JULIA_EXP}
#: The constants of Obrazok 3.8: f(x) = x^5 + 0.544, x^2 + 0.285 + 0.01i, e^x - 0.65.
EXAMPLE_MAPS = {"x5": ("poly", 5, (0.544, 0.0)), "x2": ("poly", 2, (0.285, 0.01)), "exp": ("exp", 1, (-0.65, 0.0))}
#: Escape radius of the polynomial examples: 2 already proves escape for both (R >= max(|c|, 2^(1/(d-1)))); 16 makes
#: the smooth count's log-log approximation (|a_n| ~ |a_{n-1}|^d) accurate, so the colour bands blend.
EXAMPLE_ESCAPE_POLY = 16.0
#: Escape threshold of the exp example, Re z > 50: the next iterate has modulus ~e^50, the one after overflows.
EXAMPLE_ESCAPE_EXP = 50.0
#: The Mandelbrot bailout of eq. 3.3: member while |a_n| <= 2.
MANDELBROT_ESCAPE = 2.0

MAP = Option("map", MAPS, "poly", "'poly': f(z) = z^power + c, escape |z| > escape; 'exp': f(z) = e^z + c, escape "
                                  "Re z > escape")
EXAMPLE = Option("example", EXAMPLES, "x2", "'x5': x^5 + 0.544; 'x2': x^2 + 0.285 + 0.01i; 'exp': e^x - 0.65")

_MAX_ITER = Arg("max_iter", "iteration limit (the text gives none; it sets the level of detail)", lo=1, hi=100000,
                dtype="int32", sample_range=(1.0, 300.0))
_Z = Arg("z0", "start value a_0 = the pixel's point of the complex plane (x = Re, y = Im)", lo=-1e6, hi=1e6,
         sample_range=(-2.0, 2.0))


@wp.func
def _cmul(a: wp.vec2, b: wp.vec2) -> wp.vec2:
    return wp.vec2(a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0])


@wp.func
def _cpow(z: wp.vec2, d: int) -> wp.vec2:
    r = z
    for _i in range(d - 1):
        r = _cmul(r, z)
    return r


@wp.func
def _log_abs(z: wp.vec2) -> float:
    a = wp.max(wp.abs(z[0]), wp.abs(z[1]))
    b = wp.min(wp.abs(z[0]), wp.abs(z[1]))
    q = b / a
    return wp.log(a) + 0.5 * wp.log(1.0 + q * q)


@wp.func
def _julia_iter(z0: wp.vec2, c: wp.vec2, power: int, max_iter: int, escape: float, map: int) -> tuple[int, float]:
    z = z0
    n = int(0)
    escaped = int(0)
    while n < max_iter:
        if map == MAP_EXP:
            if z[0] > escape:
                escaped = 1
                break
            e = wp.exp(z[0])
            nx = e * wp.cos(z[1]) + c[0]
            ny = e * wp.sin(z[1]) + c[1]
            z = wp.vec2(nx, ny)
        else:
            if z[0] * z[0] + z[1] * z[1] > escape * escape:
                escaped = 1
                break
            w = _cpow(z, power)
            z = wp.vec2(w[0] + c[0], w[1] + c[1])
        n += 1
    smooth = float(max_iter)
    if escaped == 1:
        if map == MAP_EXP:
            s = wp.log(z[0]) / escape
            s = wp.min(wp.max(s, 0.0), 1.0)
            smooth = float(n) + 1.0 - s
        else:
            smooth = float(n) + 1.0 - wp.log(_log_abs(z) / wp.log(escape)) / wp.log(float(power))
    return n, smooth


@declare("pt-3.1", c="ccl_fractal_julia",
         args=(_Z, Arg("c", "the map's constant (x = Re, y = Im)", lo=-100.0, hi=100.0, sample_range=(-1.0, 1.0)),
               Arg("power", "d of z^d + c (ignored by the exp map)", lo=2, hi=12, dtype="int32"),
               _MAX_ITER,
               Arg("escape", "R: |z| > R (poly) or Re z > R (exp); R >= max(|c|, 2^(1/(d-1))) proves escape for "
                             "z^d + c", lo=1.0, hi=64.0, lo_open=True, default=16.0)),
         options=(MAP,), outputs=("count", "smooth"),
         summary="Escape-time Julia iteration of eq. 3.1: a_0 = z0, a_{n+1} = f(a_n); count = first n whose a_n "
                 "fails the escape test (max_iter: bounded orbit, taken as a member of the filled Julia set -- the "
                 "text's 'Julia set'); smooth = n + 1 - log_d(ln|a_n| / ln R) (poly), n + 1 - clamp(ln(Re a_n) / R, "
                 "0, 1) (exp), max_iter for members.",
         references=("G. Julia, Memoire sur l'iteration des fonctions rationnelles, J. Math. Pures Appl. 1918",
                     "L. Vepstas, Renormalizing the Mandelbrot Escape, 1997 (smooth count)",
                     "R. L. Devaney, Julia sets and bifurcation diagrams for exponential maps, Bull. AMS 11, 1984"))
@wp.func
def fractal_julia(z0: wp.vec2, c: wp.vec2, power: int, max_iter: int, escape: float, map: int) -> tuple[int, float]:
    """pt-3.1: (escape count, smooth count) of z0 under z^power + c or e^z + c."""
    return _julia_iter(z0, c, power, max_iter, escape, map)


@declare("pt-u-julia", c="ccl_fractal_julia_example",
         args=(_Z, _MAX_ITER), options=(EXAMPLE,), outputs=("count", "smooth"),
         summary="The Julia sets of Obrazok 3.8 -- x^5 + 0.544, x^2 + 0.285 + 0.01i, e^x - 0.65 -- as pt-3.1 with "
                 "escape |z| > 16 for the polynomials (EXAMPLE_ESCAPE_POLY) and Re z > 50 for the exp map "
                 "(EXAMPLE_ESCAPE_EXP). The text calls e^x - 0.65 a rational function; it is transcendental.",
         references=("Wikimedia Commons, Julia set x^5+0.544, x^2+0.285+0.01i, e^x-0.65 (2011), the thesis's [2-4]",))
@wp.func
def fractal_julia_example(z0: wp.vec2, max_iter: int, example: int) -> tuple[int, float]:
    """pt-u-julia: escape count of z0 for one of the three printed maps."""
    if example == JULIA_X5:
        return _julia_iter(z0, wp.vec2(0.544, 0.0), 5, max_iter, 16.0, 0)
    if example == JULIA_X2:
        return _julia_iter(z0, wp.vec2(0.285, 0.01), 2, max_iter, 16.0, 0)
    return _julia_iter(z0, wp.vec2(-0.65, 0.0), 1, max_iter, 50.0, 1)


@declare("pt-3.2", c="ccl_fractal_quadratic",
         args=(Arg("z", "the iterate (x = Re, y = Im)", lo=-1e6, hi=1e6, sample_range=(-2.0, 2.0)),
               Arg("mu", "the parameter = the pixel's point of the plane", lo=-1e6, hi=1e6,
                   sample_range=(-2.0, 2.0))),
         options=(VARIANT,), outputs=("f",),
         summary="Quadratic family of eq. 3.2. variant='thesis': f(z) = z^2 - mu as printed (the set of mu is the "
                 "usual Mandelbrot set mirrored, mu = -c: antenna towards +2); variant='corrected' (default): "
                 "z^2 + mu, the usual convention (mu = c).",
         references=("B. Mandelbrot, The Fractal Geometry of Nature, 1982",
                     "P. Alfeld, The Mandelbrot Set, Univ. of Utah, 1998 (the thesis's [7])"))
@wp.func
def fractal_quadratic(z: wp.vec2, mu: wp.vec2, variant: int) -> wp.vec2:
    """pt-3.2: z^2 - mu (thesis) or z^2 + mu (corrected)."""
    r = _cmul(z, z)
    if variant == VARIANT_THESIS:
        return wp.vec2(r[0] - mu[0], r[1] - mu[1])
    return wp.vec2(r[0] + mu[0], r[1] + mu[1])


@declare("pt-3.3", c="ccl_fractal_mandelbrot",
         args=(Arg("mu", "the parameter = the pixel's point of the plane (x = Re, y = Im)", lo=-1e6, hi=1e6,
                   sample_range=(-2.5, 2.5)),
               _MAX_ITER,
               Arg("escape", "bailout R: member while |a_n| <= R (2 printed; larger only smooths the colouring)",
                   lo=2.0, hi=256.0, default=MANDELBROT_ESCAPE)),
         options=(VARIANT,), outputs=("count", "smooth"),
         summary="Mandelbrot orbit of eq. 3.3: a_0 = 0, a_{n+1} = f(a_n) with f of pt-3.2 (variant='thesis' z^2 - mu, "
                 "'corrected' z^2 + mu); count = first n with |a_n| > escape (max_iter: member); smooth = n + 1 - "
                 "log2(ln|a_n| / ln R), max_iter for members.",
         references=("B. Mandelbrot, The Fractal Geometry of Nature, 1982",
                     "L. Vepstas, Renormalizing the Mandelbrot Escape, 1997"))
@wp.func
def fractal_mandelbrot(mu: wp.vec2, max_iter: int, escape: float, variant: int) -> tuple[int, float]:
    """pt-3.3: (escape count, smooth count) of the parameter mu."""
    a = wp.vec2(0.0, 0.0)
    n = int(0)
    escaped = int(0)
    while n < max_iter:
        if a[0] * a[0] + a[1] * a[1] > escape * escape:
            escaped = 1
            break
        a = fractal_quadratic(a, mu, variant)
        n += 1
    smooth = float(max_iter)
    if escaped == 1:
        smooth = float(n) + 1.0 - wp.log(_log_abs(a) / wp.log(escape)) / wp.log(2.0)
    return n, smooth
