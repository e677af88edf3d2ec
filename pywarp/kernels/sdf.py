"""Signed distance functions and ray marching (pt §4 - §5) -- Warp twins of ``cclouds/sdf.h``.

Sign convention (pt-alg-4.1): d(p) > 0 outside, < 0 inside, 0 on the surface. Points are ``wp.vec3``.

* pt-code-4.1 :func:`sdf_primitives`: sphere, box, torus, ellipsoid of Kod 4.1 at once (each also a ``@wp.func`` of
  its own: :func:`sdf_sphere`, :func:`sdf_box`, :func:`sdf_torus`, :func:`sdf_ellipsoid`). The ellipsoid is
  approximate (exact only for a sphere) but a distance bound.
* pt-code-4.2 :func:`sdf_operators`: union, intersection, subtraction, smooth union (width k; k = 1 is the printed
  smoothUnion) and repetition (``variant="thesis"``: mod(p, c) - c/2 as printed, copies at (k + 1/2) c;
  ``"corrected"``: the centred mod(p + c/2, c) - c/2).
* pt-alg-4.1 :func:`sdf_scene`: the demonstration scenes of Obrazok 4.1 / 4.2 (``SCENES``).
* pt-alg-5.1 :func:`sdf_ray_sphere`: ray tracing's analytic ray-sphere intersection.
* pt-alg-5.2 :func:`sdf_sphere_trace`: sphere tracing of a scene, bounded by ``max_steps``.
"""
from __future__ import annotations

import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import VARIANT, Arg, Option, declare
from . import VARIANT_THESIS
from .noise import _PERM, noise_perlin3

#: Demonstration scenes (layouts are this library's choice; the text gives none), see cclouds/sdf.h.
SCENE_PRIMITIVES = c_constant("CCL_SDF_SCENE_PRIMITIVES", 0)
SCENE_UNION = c_constant("CCL_SDF_SCENE_UNION", 1)
SCENE_INTERSECTION = c_constant("CCL_SDF_SCENE_INTERSECTION", 2)
SCENE_SUBTRACTION = c_constant("CCL_SDF_SCENE_SUBTRACTION", 3)
SCENE_REPETITION = c_constant("CCL_SDF_SCENE_REPETITION", 4)
SCENE_DISPLACEMENT = c_constant("CCL_SDF_SCENE_DISPLACEMENT", 5)
SCENE_SMOOTH_UNION = c_constant("CCL_SDF_SCENE_SMOOTH_UNION", 6)
SCENES = {"primitives": SCENE_PRIMITIVES, "union": SCENE_UNION, "intersection": SCENE_INTERSECTION,
          "subtraction": SCENE_SUBTRACTION, "repetition": SCENE_REPETITION, "displacement": SCENE_DISPLACEMENT,
          "smooth_union": SCENE_SMOOTH_UNION}
#: Displacement scene (Obrazok 4.2 e; amplitude and frequency not printed): d = (|p| - 1 - A N(F p)) / (1 + A F G),
#: with G = 4 a bound of |grad N| for Perlin's improved noise (lattice units^-1), so the scene stays a distance bound.
DISP_AMPLITUDE = 0.12
DISP_FREQUENCY = 3.0
DISP_GRAD_BOUND = 4.0
#: Sphere-tracing defaults (the text gives no values): 256 steps reach every surface of the demonstration scenes from
#: 10 units away except at grazing silhouettes; precision 1e-3 scene units is below a pixel at 10 units and 512 px;
#: max_t 50 is beyond every object of the scenes seen from their cameras.
MAX_STEPS = 256
PRECISION = 1e-3
MAX_T = 50.0

SCENE = Option("scene", SCENES, "primitives", "demonstration scene: " + ", ".join(map(repr, SCENES)))

_A = wp.constant(DISP_AMPLITUDE)
_F = wp.constant(DISP_FREQUENCY)
_G = wp.constant(DISP_GRAD_BOUND)

_P = Arg("p", "point (scene units)", lo=-1e4, hi=1e4, sample_range=(-3.0, 3.0))


@wp.func
def sdf_sphere(p: wp.vec3, s: float) -> float:
    """Kod 4.1 sphere: |p| - s (exact)."""
    return wp.length(p) - s


@wp.func
def sdf_box(p: wp.vec3, b: wp.vec3) -> float:
    """Kod 4.1 box with half-extents b (exact)."""
    d = wp.vec3(wp.abs(p[0]) - b[0], wp.abs(p[1]) - b[1], wp.abs(p[2]) - b[2])
    inside = wp.min(wp.max(d[0], wp.max(d[1], d[2])), 0.0)
    return inside + wp.length(wp.vec3(wp.max(d[0], 0.0), wp.max(d[1], 0.0), wp.max(d[2], 0.0)))


@wp.func
def sdf_torus(p: wp.vec3, t: wp.vec2) -> float:
    """Kod 4.1 torus around the y axis: major radius t.x, minor t.y (exact)."""
    qx = wp.sqrt(p[0] * p[0] + p[2] * p[2]) - t[0]
    return wp.sqrt(qx * qx + p[1] * p[1]) - t[1]


@wp.func
def sdf_ellipsoid(p: wp.vec3, r: wp.vec3) -> float:
    """Kod 4.1 ellipsoid (|p / r| - 1) min(r): approximate, a distance bound."""
    return (wp.length(wp.vec3(p[0] / r[0], p[1] / r[1], p[2] / r[2])) - 1.0) * wp.min(wp.min(r[0], r[1]), r[2])


@declare("pt-code-4.1", c="ccl_sdf_primitives",
         args=(_P, Arg("s", "sphere radius", lo=0.0, hi=1e4, lo_open=True, default=1.0, sample_range=(0.1, 3.0)),
               Arg("b", "box half-extents", lo=0.0, hi=1e4, lo_open=True, default=(1.0, 1.0, 1.0),
                   sample_range=(0.1, 3.0)),
               Arg("t", "torus (major radius, minor radius)", lo=0.0, hi=1e4, lo_open=True, default=(1.0, 0.25),
                   sample_range=(0.1, 3.0)),
               Arg("r", "ellipsoid semi-axes", lo=0.0, hi=1e4, lo_open=True, default=(1.0, 0.6, 0.4),
                   sample_range=(0.1, 3.0))),
         outputs=("sphere", "box", "torus", "ellipsoid"),
         summary="The SDF primitives of Kod 4.1 (after Quilez) at p, centred at the origin: sphere |p| - s, box "
                 "min(max(d), 0) + |max(d, 0)| with d = |p| - b, torus |(|p.xz| - t.x, p.y)| - t.y (in the xz plane), "
                 "ellipsoid (|p / r| - 1) min(r). Sphere, box and torus are exact; the ellipsoid is APPROXIMATE (the "
                 "text does not say so): exact only for equal semi-axes, elsewhere a 1-Lipschitz bound (|d| <= true "
                 "distance, zero on the surface).",
         references=("I. Quilez, Distance functions, https://iquilezles.org/articles/distfunctions/",))
@wp.func
def sdf_primitives(p: wp.vec3, s: float, b: wp.vec3, t: wp.vec2, r: wp.vec3) -> tuple[float, float, float, float]:
    """pt-code-4.1: (sphere, box, torus, ellipsoid) distances of p."""
    return sdf_sphere(p, s), sdf_box(p, b), sdf_torus(p, t), sdf_ellipsoid(p, r)


@wp.func
def sdf_union(d1: float, d2: float) -> float:
    return wp.min(d1, d2)


@wp.func
def sdf_intersect(d1: float, d2: float) -> float:
    return wp.max(d1, d2)


@wp.func
def sdf_subtract(d1: float, d2: float) -> float:
    return wp.max(-d2, d1)


@wp.func
def sdf_smooth_union(d1: float, d2: float, k: float) -> float:
    """Polynomial smooth union of width k; k = 1 is Kod 4.2's smoothUnion."""
    h = 0.5 + 0.5 * (d1 - d2) / k
    h = wp.min(wp.max(h, 0.0), 1.0)
    return d1 * (1.0 - h) + d2 * h - k * h * (1.0 - h)


@wp.func
def _repeat_axis(x: float, c: float, variant: int) -> float:
    """One axis of the repeat in [-c/2, c/2) for every finite x (twin of ``repeat_axis``, sdf.c): wp.mod is fmodf,
    the exact remainder; the corrected form shifts it by c (exact), the thesis form takes the float below c/2 where
    r + c/2 rounds up to c/2 (fuzz finding N5: GLSL's x - c floor(x / c) left the interval)."""
    h = 0.5 * c
    r = wp.mod(x, c)
    if variant != VARIANT_THESIS:
        if r >= h:
            return r - c
        if r < -h:
            return r + c
        return r
    if r >= 0.0:
        return r - h
    if r + h < h:
        return r + h
    return h * 0.99999994


@wp.func
def sdf_repeat(p: wp.vec3, c: wp.vec3, variant: int) -> wp.vec3:
    """Kod 4.2 repeat: thesis mod(p, c) - c/2; corrected mod(p + c/2, c) - c/2; in [-c/2, c/2) per axis."""
    return wp.vec3(_repeat_axis(p[0], c[0], variant), _repeat_axis(p[1], c[1], variant),
                   _repeat_axis(p[2], c[2], variant))


@declare("pt-code-4.2", c="ccl_sdf_operators",
         args=(Arg("d1", "distance to object 1", lo=-1e6, hi=1e6, sample_range=(-3.0, 3.0)),
               Arg("d2", "distance to object 2", lo=-1e6, hi=1e6, sample_range=(-3.0, 3.0)),
               Arg("k", "smooth-union width (1 = the printed smoothUnion)", lo=0.0, hi=1e3, lo_open=True, default=1.0,
                   sample_range=(0.05, 4.0)),
               Arg("p", "point to repeat", lo=-1e4, hi=1e4, default=(0.0, 0.0, 0.0), sample_range=(-10.0, 10.0)),
               Arg("c", "repetition period per axis (>= 2^-125: c/2 a normal float)", lo=2.0 ** -125, hi=1e4,
                   default=(1.0, 1.0, 1.0),
                   sample_range=(0.1, 4.0))),
         options=(VARIANT,), outputs=("union", "intersection", "subtraction", "smooth_union", "repeat"),
         summary="The operators of Kod 4.2: union min(d1, d2) (named opUnion in GLSL, where union is reserved), "
                 "intersection max(d1, d2), subtraction max(-d2, d1) (object 1 minus object 2), smooth union "
                 "h = clamp(0.5 + 0.5 (d1 - d2) / k, 0, 1), mix(d1, d2, h) - k h (1 - h) (k = 1: the printed "
                 "fixed width; = Quilez's smin(d2, d1, k)), and repeat: variant='thesis' mod(p, c) - c/2 as printed "
                 "(copies at (k + 1/2) c), 'corrected' mod(p + c/2, c) - c/2 (copies at k c).",
         references=("I. Quilez, Distance functions, https://iquilezles.org/articles/distfunctions/",
                     "I. Quilez, Smooth minimum, https://iquilezles.org/articles/smin/"))
@wp.func
def sdf_operators(d1: float, d2: float, k: float, p: wp.vec3, c: wp.vec3,
                  variant: int) -> tuple[float, float, float, float, wp.vec3]:
    """pt-code-4.2: (union, intersection, subtraction, smooth union, repeated point)."""
    return (sdf_union(d1, d2), sdf_intersect(d1, d2), sdf_subtract(d1, d2), sdf_smooth_union(d1, d2, k),
            sdf_repeat(p, c, variant))


@wp.func
def _scene(p: wp.vec3, perm: wp.array(dtype=wp.int32), scene: int) -> float:
    cube = wp.vec3(0.7, 0.7, 0.7)
    if scene == SCENE_PRIMITIVES:
        d = sdf_sphere(wp.vec3(p[0] + 3.75, p[1], p[2]), 0.8)
        d = sdf_union(d, sdf_box(wp.vec3(p[0] + 1.25, p[1], p[2]), cube))
        d = sdf_union(d, sdf_torus(wp.vec3(p[0] - 1.25, p[1], p[2]), wp.vec2(0.7, 0.25)))
        return sdf_union(d, sdf_ellipsoid(wp.vec3(p[0] - 3.75, p[1], p[2]), wp.vec3(0.9, 0.6, 0.45)))
    if scene == SCENE_UNION:
        return sdf_union(sdf_box(p, cube), sdf_sphere(p, 0.9))
    if scene == SCENE_INTERSECTION:
        return sdf_intersect(sdf_box(p, cube), sdf_sphere(p, 0.9))
    if scene == SCENE_SUBTRACTION:
        return sdf_subtract(sdf_box(p, cube), sdf_sphere(p, 0.9))
    if scene == SCENE_REPETITION:
        q = sdf_repeat(p, wp.vec3(1.2, 1.2, 1.2), 1)
        return sdf_sphere(wp.vec3(q[0], p[1], q[2]), 0.35)
    if scene == SCENE_DISPLACEMENT:
        n = noise_perlin3(_F * p[0], _F * p[1], _F * p[2], perm, 0)
        return (sdf_sphere(p, 1.0) - _A * n) / (1.0 + _A * _F * _G)
    return sdf_smooth_union(sdf_ellipsoid(wp.vec3(p[0] + 0.5, p[1], p[2]), wp.vec3(1.0, 0.5, 0.6)),
                            sdf_sphere(wp.vec3(p[0] - 0.7, p[1] - 0.15, p[2]), 0.6), 1.0)


_SEED = Arg("seed", "uint32 Perlin seed of the displacement scene (0 = Ken Perlin's table)", lo=0, hi=4294967295,
            dtype="uint32", default=0)


@declare("pt-alg-4.1", c="ccl_sdf_scene",
         args=(_P, _SEED), options=(SCENE,), outputs=("d",), derived=_PERM,
         summary="Signed distance (bound) of the demonstration scenes built from Kod 4.1 / 4.2: > 0 outside, < 0 "
                 "inside, 0 on the surface (pt-alg-4.1). 'primitives' (Obrazok 4.1: sphere, box, torus, ellipsoid "
                 "along x), 'union' / 'intersection' / 'subtraction' (Obrazok 4.2 a-c: box 0.7 and sphere 0.9 at the "
                 "origin; box minus sphere), 'repetition' (d: sphere 0.35 repeated with the printed repeat, period 1.2 "
                 "in x and z), 'displacement' (e: unit sphere displaced by 0.12 perlin3(3 p), divided by its "
                 "Lipschitz bound 2.44), 'smooth_union' (f: printed smoothUnion of an ellipsoid and a sphere).",
         references=("J. C. Hart, Sphere tracing, The Visual Computer 12, 1996",
                     "I. Quilez, Distance functions, https://iquilezles.org/articles/distfunctions/"))
@wp.func
def sdf_scene(p: wp.vec3, perm: wp.array(dtype=wp.int32), scene: int) -> float:
    """pt-alg-4.1: signed distance of a demonstration scene at p."""
    return _scene(p, perm, scene)


_RAY_SPHERE_SQUARE_MAX = wp.constant(2.0 ** 60)  # the largest radius squared as it is (C: RAY_SPHERE_SQUARE_MAX)


@declare("pt-alg-5.1", c="ccl_sdf_ray_sphere",
         args=(Arg("ro", "ray origin", lo=-1e4, hi=1e4, sample_range=(-5.0, 5.0)),
               Arg("rd", "unit ray direction", unit=True),
               Arg("centre", "sphere centre", lo=-1e4, hi=1e4, sample_range=(-2.0, 2.0)),
               Arg("radius", "sphere radius", lo=0.0, hi=1e4, lo_open=True, sample_range=(0.1, 3.0))),
         outputs=("t",),
         summary="Ray tracing's analytic step (pt §5.1): the nearest t >= 0 with |ro + t rd - centre| = radius "
                 "(t = -b -+ sqrt(b^2 - |oc|^2 + radius^2), b = oc . rd, oc = ro - centre); the exit point when ro is "
                 "inside; -1 when the ray misses. Shadow rays are the same test from the hit point towards the light.",
         references=("P. Shirley & S. Marschner, Fundamentals of Computer Graphics, 3rd ed., 2009, §4.4",))
@wp.func
def sdf_ray_sphere(ro: wp.vec3, rd: wp.vec3, centre: wp.vec3, radius: float) -> float:
    """pt-alg-5.1: nearest non-negative ray parameter of the sphere, or -1. t scales with the sphere: a radius whose
    square overflows (an infinite t) is divided out, the unit sphere in units of radius and t scaled back, as C."""
    oc = ro - centre
    k = float(1.0)
    r = radius
    if radius > _RAY_SPHERE_SQUARE_MAX:
        k = radius
        oc = wp.vec3(oc[0] / k, oc[1] / k, oc[2] / k)
        r = 1.0
    b = wp.dot(oc, rd)
    c = wp.dot(oc, oc) - r * r
    disc = b * b - c
    if disc < 0.0:
        return -1.0
    s = wp.sqrt(disc)
    t0 = -b - s
    t1 = -b + s
    if t0 >= 0.0:
        return k * t0
    if t1 >= 0.0:
        return k * t1
    return -1.0


@declare("pt-alg-5.2", c="ccl_sdf_sphere_trace",
         args=(Arg("ro", "ray origin", lo=-1e4, hi=1e4, sample_range=(-6.0, 6.0)),
               Arg("rd", "unit ray direction", unit=True),
               Arg("max_steps", "loop bound: at most this many scene evaluations (MAX_STEPS)", lo=1, hi=100000,
                   dtype="int32", default=MAX_STEPS, sample_range=(1.0, 400.0)),
               Arg("precision", "hit when the distance falls below it (PRECISION)", lo=0.0, hi=1.0, lo_open=True,
                   default=PRECISION, sample_range=(1e-4, 0.1)),
               Arg("max_t", "miss when t exceeds it (MAX_T)", lo=0.0, hi=1e5, lo_open=True, default=MAX_T,
                   sample_range=(1.0, 60.0)),
               _SEED),
         options=(SCENE,), outputs=("t", "steps", "hit"), derived=_PERM,
         summary="Sphere tracing (pt §5.2, Hart 1996): t = 0; at most max_steps times: d = scene(ro + t rd); hit when "
                 "d < precision; t += d; miss when t > max_t. Returns t (the hit distance when hit = 1), the number "
                 "of scene evaluations and hit (0: miss or max_steps ran out). The step is the distance to the "
                 "nearest surface, so the ray never passes through one when the scene is a distance bound (every "
                 "scene of sdf_scene is).",
         references=("J. C. Hart, Sphere tracing, The Visual Computer 12, 1996",
                     "B. Keinert et al., Enhanced Sphere Tracing, STAG 2014 (the thesis's [12])"))
@wp.func
def sdf_sphere_trace(ro: wp.vec3, rd: wp.vec3, max_steps: int, precision: float, max_t: float,
                     perm: wp.array(dtype=wp.int32), scene: int) -> tuple[float, int, int]:
    """pt-alg-5.2: (t, steps, hit) of the ray ro + t rd against a demonstration scene."""
    t = float(0.0)
    steps = int(0)
    hit = int(0)
    i = int(0)
    while i < max_steps:
        d = _scene(ro + rd * t, perm, scene)
        steps = i + 1
        if d < precision:
            hit = 1
            break
        t += d
        if t > max_t:
            break
        i += 1
    return t, steps, hit
