"""Drawing with formulas (pt §3.3 - §3.5) -- Warp twins of ``cclouds/draw.h``.

* pt-alg-3.3 :func:`draw_coords`: pixel -> uv -> centred p (aspect correction of Kod 7.1 as an option) -> polar.
* pt-code-3.1 :func:`draw_curves`: the three curves of Kod 3.1 with their 0.01 threshold (a colour index).
* pt-code-3.2 :func:`draw_marble`: sine, fBm and the marble combination of Kod 3.2.
* pt-u-warp :func:`draw_warp`: domain-warped fBm of Obrazok 3.3, the caption's scalar offsets (``variant="thesis"``)
  and Quilez's vector offsets (``variant="corrected"``).
* pt-alg-3.5 :func:`draw_butterfly`: the animated butterfly as a stand-in (two textured quads with a flapping hinge).

The fBm is the terrain demo's (pt-alg-3.2, :func:`pywarp.kernels.noise.noise_fbm_perlin2`, A0 = 1, F0 = 0.5, gain 0.5,
lacunarity 2); its octave count is a parameter because the text does not give it. Every ``@wp.func`` mirrors the C
function of the same name (minus ``ccl_``) operation by operation.
"""
from __future__ import annotations

import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import VARIANT, Arg, Option, declare
from . import VARIANT_THESIS
from .noise import _PERM, noise_fbm_perlin2

#: Colour indices of draw_curves (Kod 3.1 draw order: red, blue, yellow; later curves overwrite earlier ones).
CURVE_COLOURS = {0: "background", 1: "red", 2: "blue", 3: "yellow"}
#: Threshold of Kod 3.1 (function-value units, not pixels).
CURVE_THRESHOLD = 0.01
#: Default octave count of the Kod 3.2 / Obrazok 3.3 fBm (not printed): with fBm(5 p) on p in (-1, 1) the finest of 5
#: octaves has 5 * 0.5 * 2^4 = 40 lattice cells per unit, 6 pixels per cell in a 512-pixel window -- finer octaves
#: would alias.
DEFAULT_OCTAVES = 5
#: Quilez's offsets of the vector reading of domain warping (pt-u-warp, corrected), and his strength 4.
WARP_OFFSETS = ((0.0, 0.0), (5.2, 1.3), (1.7, 9.2), (8.3, 2.8))
WARP_STRENGTH_QUILEZ = 4.0
#: Butterfly (pt-alg-3.5 stand-in): the animation repeats every BUTTERFLY_PERIOD seconds (flight path 4 s, flaps at
#: 1.5 Hz: 6 beats per loop).
BUTTERFLY_PERIOD = 4.0

ASPECT_NONE = c_constant("CCL_DRAW_ASPECT_NONE", 0)
ASPECT_X = c_constant("CCL_DRAW_ASPECT_X", 1)
ASPECT = Option("aspect", {"none": ASPECT_NONE, "x": ASPECT_X}, "none",
                "'none': p = 2 uv - 1 as pt-alg-3.3 / Kod 3.1; 'x': p.x *= width / height as Kod 7.1")

_TWO_PI = wp.constant(6.28318530717958647692)
_O = [wp.constant(wp.vec2(*o)) for o in WARP_OFFSETS]
_O0, _O1, _O2, _O3 = _O


@declare("pt-alg-3.3", c="ccl_draw_coords",
         args=(Arg("frag", "window position in pixels (pixel centres at i + 0.5, origin bottom-left)", lo=-65536.0,
                   hi=65536.0, sample_range=(0.0, 2000.0)),
               Arg("resolution", "window size in pixels (800 x 600 in Obrazok 3.4)", lo=1.0, hi=65536.0,
                   sample_range=(1.0, 2000.0))),
         options=(ASPECT,), outputs=("uv", "p", "polar"),
         summary="uv = frag / resolution in (0, 1)^2 (origin bottom-left); p = 2 uv - 1 in (-1, 1)^2, origin at the "
                 "centre (aspect='x': p.x times width/height, Kod 7.1); polar = (|p|, atan2(p.y, p.x)) with phi in "
                 "[-pi, pi] (the text says polar coordinates can be derived but gives no formula).",
         references=("Drevicky, Graphics demo employing procedural textures (2016), §3.3, Obrazok 3.4",))
@wp.func
def draw_coords(frag: wp.vec2, resolution: wp.vec2, aspect: int) -> tuple[wp.vec2, wp.vec2, wp.vec2]:
    """pt-alg-3.3: (uv, p, polar) of a pixel position."""
    uv = wp.vec2(frag[0] / resolution[0], frag[1] / resolution[1])
    px = 2.0 * uv[0] - 1.0
    py = 2.0 * uv[1] - 1.0
    if aspect == ASPECT_X:
        px = px * (resolution[0] / resolution[1])
    return uv, wp.vec2(px, py), wp.vec2(wp.sqrt(px * px + py * py), wp.atan2(py, px))


@declare("pt-code-3.1", c="ccl_draw_curves",
         args=(Arg("p", "centred coordinates of pt-alg-3.3", lo=-16.0, hi=16.0),
               Arg("threshold", "line half-width in function-value units (0.01 printed)", lo=0.0, hi=1.0,
                   lo_open=True, default=CURVE_THRESHOLD)),
         outputs=("colour",),
         summary="Kod 3.1: 0 background, 1 red where |y - 0.1 e^x| < threshold, 2 blue where |(x + 0.9)^2 + y^2 - 0.4| "
                 "< threshold, 3 yellow where |x - 0.2 sin(15 y)| < threshold; later tests overwrite earlier ones. The "
                 "listing's slips (gl_fragCoord, p used before its declaration, undeclared colours) are corrected; "
                 "the background colour is the caller's.",
         references=("Drevicky (2016), Kod 3.1, Obrazok 3.5",))
@wp.func
def draw_curves(p: wp.vec2, threshold: float) -> int:
    """pt-code-3.1: colour index of the three curves at p."""
    colour = int(0)
    f1 = 0.1 * wp.exp(p[0])
    f2 = (p[0] + 0.9) * (p[0] + 0.9) + p[1] * p[1] - 0.4
    f3 = 0.2 * wp.sin(15.0 * p[1])
    if wp.abs(p[1] - f1) < threshold:
        colour = 1
    if wp.abs(f2) < threshold:
        colour = 2
    if wp.abs(p[0] - f3) < threshold:
        colour = 3
    return colour


@wp.func
def _fbm(p: wp.vec2, octaves: int, perm: wp.array(dtype=wp.int32)) -> float:
    return noise_fbm_perlin2(p, octaves, perm, 1.0, 0.5, 0.5, 2.0)


_OCTAVES = Arg("octaves", "fBm octaves (not printed; 5 resolves a 512-pixel window, DEFAULT_OCTAVES)", lo=1, hi=12,
               dtype="int32", default=DEFAULT_OCTAVES)
_SEED = Arg("seed", "uint32 seed of the Perlin table; 0 = Ken Perlin's", lo=0, hi=4294967295, dtype="uint32", default=0)
_PW = Arg("p", "centred coordinates of pt-alg-3.3", lo=-1000.0, hi=1000.0, sample_range=(-2.0, 2.0))


@declare("pt-code-3.2", c="ccl_draw_marble",
         args=(_PW, _OCTAVES, _SEED), outputs=("sine", "fbm", "combination"), derived=_PERM,
         summary="Kod 3.2: fbm = fBm(5 p) (pt-alg-3.2 with the printed coefficients; the listing's "
                 "fractionalBrownianMotion), sine = (1 + sin(50 p.x)) / 2, combination = (1 + sin((p.x + fbm / 2) "
                 "50)) / 2 -- vertical stripes, clouds and marble of Obrazok 3.6; sine and combination in [0, 1].",
         references=("Drevicky (2016), Kod 3.2, Obrazok 3.6 (after S. McCombs, Procedural Textures)",))
@wp.func
def draw_marble(p: wp.vec2, octaves: int, perm: wp.array(dtype=wp.int32)) -> tuple[float, float, float]:
    """pt-code-3.2: (sine, fbm, combination)."""
    f = _fbm(wp.vec2(5.0 * p[0], 5.0 * p[1]), octaves, perm)
    sine = (1.0 + wp.sin(50.0 * p[0])) / 2.0
    combination = (1.0 + wp.sin((p[0] + f / 2.0) * 50.0)) / 2.0
    return sine, f, combination


@wp.func
def _warp_offset(i: int) -> wp.vec2:
    if i == 0:
        return _O0
    if i == 1:
        return _O1
    if i == 2:
        return _O2
    return _O3


@declare("pt-u-warp", c="ccl_draw_warp",
         args=(_PW, Arg("depth", "levels of warping: 0 p(x), 1 p(x + p(x)), 2 p(x + p(x + p(x)))", lo=0, hi=2,
                        dtype="int32"),
               _OCTAVES,
               Arg("strength", "s, scale of the offsets (1 as printed; Quilez uses 4, WARP_STRENGTH_QUILEZ)", lo=0.0,
                   hi=16.0, default=1.0),
               _SEED),
         options=(VARIANT,), outputs=("value",), derived=_PERM,
         summary="Domain warping of Obrazok 3.3. variant='thesis' (the caption, scalar offsets): q_0 = 0, "
                 "q_{k+1} = fBm(p + s q_k (1, 1)), value = fBm(p + s q_depth (1, 1)) -- the scalar p(x) added to "
                 "both components. variant='corrected' (Quilez, vector offsets): q_{k+1} = (fBm(p + s q_k + o_2k), "
                 "fBm(p + s q_k + o_2k+1)) with o = (0, 0), (5.2, 1.3), (1.7, 9.2), (8.3, 2.8). fBm = pt-alg-3.2 "
                 "with `octaves` octaves. Output in (-2, 2).",
         references=("I. Quilez, Domain Warping, https://iquilezles.org/articles/warp/ (2002)",
                     "Drevicky (2016), Obrazok 3.3"))
@wp.func
def draw_warp(p: wp.vec2, depth: int, octaves: int, strength: float, perm: wp.array(dtype=wp.int32),
              variant: int) -> float:
    """pt-u-warp: warped fBm, scalar (thesis) or vector (corrected) offsets."""
    qx = float(0.0)
    qy = float(0.0)
    d = wp.min(depth, 2)
    for k in range(d):
        bx = p[0] + strength * qx
        by = p[1] + strength * qy
        if variant == VARIANT_THESIS:
            q = _fbm(wp.vec2(bx, by), octaves, perm)
            qx = q
            qy = q
        else:
            oa = _warp_offset(2 * k)
            ob = _warp_offset(2 * k + 1)
            nx = _fbm(wp.vec2(bx + oa[0], by + oa[1]), octaves, perm)
            ny = _fbm(wp.vec2(bx + ob[0], by + ob[1]), octaves, perm)
            qx = nx
            qy = ny
    return _fbm(wp.vec2(p[0] + strength * qx, p[1] + strength * qy), octaves, perm)


# --- butterfly (pt-alg-3.5 stand-in) ---------------------------------------------------------------------------------

@wp.func
def _wing(s: float, v: float) -> tuple[int, wp.vec3]:
    """Wing texture drawn with formulas at (s, v) (span units from the hinge): (inside, colour)."""
    ef = ((s - 0.5) / 0.5) * ((s - 0.5) / 0.5) + ((v - 0.22) / 0.36) * ((v - 0.22) / 0.36)
    eh = ((s - 0.38) / 0.38) * ((s - 0.38) / 0.38) + ((v + 0.2) / 0.3) * ((v + 0.2) / 0.3)
    e = wp.min(ef, eh)
    phi = wp.atan2(v, s)
    c = wp.vec3(0.98, 0.55, 0.1)
    body = s < 0.06 and wp.abs(v) < 0.45
    if not (s >= 0.0) or (not (e < 1.0) and not body):
        return 0, c
    if wp.abs(wp.sin(12.0 * phi)) < 0.07:
        c = wp.vec3(0.15, 0.08, 0.02)
    if e > 0.72:
        c = wp.vec3(0.05, 0.04, 0.03)
    if e > 0.8 and e < 0.93 and wp.sin(40.0 * phi) > 0.6:
        c = wp.vec3(0.95, 0.95, 0.9)
    if body:
        c = wp.vec3(0.12, 0.09, 0.06)
    return 1, c


@declare("pt-alg-3.5", c="ccl_draw_butterfly",
         args=(Arg("p", "centred, aspect-corrected screen coordinates (Kod 7.1)", lo=-4.0, hi=4.0),
               Arg("time", "seconds; the animation repeats every 4 s (BUTTERFLY_PERIOD)", lo=0.0, hi=3600.0)),
         outputs=("rgb",),
         summary="Stand-in for the butterfly of pt §3.5 (no formula given): two rectangles (span 1, length 1.2 along "
                 "the body = z axis) hinged on the body axis, hinge angle theta(t) = 1.0 sin(2 pi 1.5 t) rad, flying "
                 "along c(t) = (0.6 sin(w t), 0.25 sin(2 w t), 0), w = 2 pi / 4 s, seen from (0, 2, -3) towards the "
                 "origin (Kod 7.2 basis, image plane at 1.5). Each ray is intersected with both wing planes; the "
                 "nearest hit inside the wing texture (two ellipses, veins, black border, white spots, body strip) is "
                 "shaded by 0.55 + 0.45 |n . rd|, else a sky gradient. RGB in [0, 1].",
         references=("I. Quilez, Drawing, Sculpting and Animating Nature with Maths, ICM 2006 (the thesis's [18])",))
@wp.func
def draw_butterfly(p: wp.vec2, time: float) -> wp.vec3:
    """pt-alg-3.5: colour of the butterfly frame at screen point p and time t."""
    cam = wp.vec3(0.0, 2.0, -3.0)
    target = wp.vec3(0.0, 0.0, 0.0)
    world_up = wp.vec3(0.0, 1.0, 0.0)
    focal = float(1.5)
    span = float(1.0)
    half_length = float(0.6)
    omega = _TWO_PI / 4.0
    flap = _TWO_PI * 1.5
    theta_max = float(1.0)
    fwd = wp.normalize(target - cam)
    right = wp.normalize(wp.cross(fwd, world_up))
    up = wp.normalize(wp.cross(right, fwd))
    rd = wp.normalize(right * p[0] + up * p[1] + fwd * focal)
    centre = wp.vec3(0.6 * wp.sin(omega * time), 0.25 * wp.sin(2.0 * omega * time), 0.0)
    theta = theta_max * wp.sin(flap * time)
    ct = wp.cos(theta)
    st = wp.sin(theta)
    yb = 0.5 + 0.5 * p[1]
    best = float(wp.inf)
    yb = wp.min(wp.max(yb, 0.0), 1.0)
    colour = wp.vec3(0.55 + 0.25 * yb, 0.75 + 0.15 * yb, 0.95)
    for side in range(2):
        k = float(2 * side - 1)
        d = wp.vec3(k * ct, st, 0.0)
        n = wp.vec3(st, -k * ct, 0.0)
        denom = wp.dot(rd, n)
        if wp.abs(denom) >= 1.0e-6:
            t = wp.dot(centre - cam, n) / denom
            if t > 0.0 and t < best:
                q = (cam + rd * t) - centre
                u = wp.dot(q, d)
                v = q[2]
                if u >= 0.0 and u <= span and wp.abs(v) <= half_length:
                    inside, c = _wing(u / span, v / span)
                    if inside == 1:
                        best = t
                        colour = c * (0.55 + 0.45 * wp.abs(denom))
    return colour
