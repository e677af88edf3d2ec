"""A path-traced ground truth of the cloudscape: Monte Carlo light transport through the SAME density field, sun and
sky as the real-time renderer (:mod:`pywarp.kernels.cloudscape`), to measure the real-time lighting models against.

    from pywarp.clouds.reference import ReferenceRenderer
    r = ReferenceRenderer(CloudscapeSettings(width=160, height=90), spp=256, seed=0)
    linear = r.render(encode=False)       # display-linear float32 (h, w, 3), like CloudscapeTechnique.render
    r.stats["std_error"]                  # its Monte Carlo standard error (mean over pixels, linear units)

The medium
----------
Extinction ``sigma_t(x) = sigma rho(x)`` [1/km] with ``rho`` = :func:`pywarp.kernels.cloudscape.cloudscape_density`
**with detail** (the density of the view ray), ``sigma`` the scene's ``sigma_per_km``. Scattering ``omega sigma_t``,
absorption ``(1 - omega) sigma_t``, with ``omega`` the single-scattering albedo (:data:`DEFAULT_ALBEDO`).

*Phase function.* One physical phase function for every comparison, the settings' ``phase``: ``thesis`` --
Henyey-Greenstein with the scene's ``g`` (the settings' ``--phase-g``, 0.2 by default, or ``phase_g`` of
:class:`ReferenceRenderer`); ``mie`` -- the approximate Mie phase of cloud droplets of ``droplet_um``
(:func:`pywarp.kernels.phase.phase_mie`, vc-x-mie: HG + Draine, g ~ 0.87), sampled exactly (the lobe by its weight,
Draine's lobe by rejection from HG, :func:`sample_draine_cos`); with ``peak='truncated'`` (:data:`PEAKS`) the Mie
phase's forward peak is truncated (flattened inside a cone of a few degrees, the share it no longer scatters passed on
unscattered, the camera ray's single scattering with the full phase), a stated approximation whose pixels converge. Whatever the real-time model under test does (the
octave multiple scattering and the dual-lobe "silver lining" are approximations *of* transport in this medium, so
they are measured against it, not built into it). Reason: the error table must not mix the error of the transport
approximations with a change of the medium; with the scene's phase, "thesis" and "+sky light" (single lobe) are
compared against exactly the medium they claim to light.

*The density bound* (the constant majorant is ``sigma * DENSITY_BOUND``): with textures in [0, 1] (checked on the
host) and clamped height gradients (``gradient_clamp = 1``, the default; required here), ``rho <= 1``: the base
shape ``B = remap(C_R, L - 1, 1, 0, 1) = (C_R - L + 1) / (2 - L) <= 1`` for ``C_R <= 1``; ``D_v <= 1``; the
coverage ``D_h <= 1`` (the de-tiled lookup blends two lookups of the map); ``remap(B D_v, C, 1, 0, 1) D_h <= D_h``
for any threshold ``C < 1``; the detail erosion ``(B_D - a) / (1 - a)`` with ``a = 0.2 M in [0, 0.2]`` is
``<= B_D`` for ``B_D <= 1``. The kernel checks every density it evaluates against the majorant in use
(:func:`reference_density`) and counts violations: a render that exceeds the constant bound is refused.

Light
-----
* **Units** (the settings' ``units``): ``display`` (today's, kept so that old numbers reproduce) -- the real-time
  renderer's display-linear lights: the sun ``sun_intensity`` x the atmosphere's transmittance, the sky tone mapped
  (1 - exp(-k C_HDR)) and used as a radiance; ``physical`` -- radiances in kcd/m^2 times one exposure k (the settings'
  ``sky_exposure``): the Preetham sky k C_HDR (C_HDR is linear sRGB whose Y is the luminance in kcd/m^2, the unit of
  Preetham's zenith luminance, vc-2.39), the sun k x 127.5 klx x its transmittance through the sky's turbidity
  (cclouds/cloudscape.h, CCL_SKY_PREETHAM_RADIANCE). Light transport is linear, so k is the exposure of the
  finished image; the display transform (clamp and sRGB in :func:`encode_srgb`; a tone curve would replace it
  there) comes after.
* **Sun**: a directional (delta) light of irradiance ``p.sun_colour`` (the factor the real-time model multiplies by
  Beer x phase x powder) from the sky model's sun direction. Next-event estimation at every
  scattering vertex: ``beta * E_sun * p_HG(d . s) * T(x -> sun)``, ``T`` by ratio tracking through the layer (0 where
  the Earth blocks the sun).
* **Sky**: a path that leaves the layer without hitting the ground picks up the sky model's radiance
  :func:`pywarp.kernels.cloudscape.sky_colour` in its direction (the background the real-time model composites
  over). The air itself does not scatter: there is no aerial perspective in the reference (the sky model is a
  radiance at infinity, as for the real-time thesis model).
* **Ground**: the Earth sphere (radius ``r_earth``) is Lambertian with the settings' ``ground_albedo`` (the
  real-time renderer's sky lighting uses the same): next-event estimation to the sun
  ``beta * albedo / pi * E_sun * max(n . s, 0) * T`` and the path continues (cosine-weighted), so the sky and the
  clouds light the ground through the path.

The path
--------
Free-flight sampling by delta tracking (Woodcock) over the (up to two) intervals of the ray inside the spherical shell
of the layer, ending at the ground, with a piecewise-constant majorant: the ray is cut into chunks of
:data:`FINE_CHUNK_KM` (grouped by :data:`COARSE_CHUNKS`), and each chunk's majorant is ``sigma`` times a bound of the
density over the chunk's bounding box, from max pyramids of the weather map's coverage (both lookups of the de-tiled
map) and of the per-texel base shape (:func:`chunk_bound`: ``rho <= B_max + D_h,max - 1`` with the derivation above
and in :func:`majorant_grids`); chunks of clear air (bound 0) are skipped. Every density sample is checked against
its chunk's bound; a violation (a future change of the density function) redoes the render with the constant bound.
``majorant=False`` tracks with the constant ``sigma * DENSITY_BOUND`` throughout (same expectation, tested).
At most ``bounces`` scattering vertices (medium or ground) per path: every light contribution (sun by NEE at a
vertex, sky by escape after it) has been scattered at most ``bounces`` times; the path ends at vertex
``bounces + 1`` (the truncation is measured: :data:`DEFAULT_BOUNCES`). Transmittance estimates end with Russian
roulette below :data:`RR_TRANSMITTANCE` (unbiased).

Every loop is bounded by a validated parameter (a native launch cannot be interrupted): ``spp`` in [1, 65536],
``bounces`` in [1, 4096], ``max_steps`` tracking iterations per ray segment (default: twice the expected number
along the longest chord of the shell at the constant bound, so it is never reached in practice; a render that
reaches it is refused).

Determinism: the random numbers of sample ``s`` of pixel ``(x, y)`` come from a PCG stream seeded with
``hash(seed, x, y, s)`` alone, and each pixel sums its samples in order, so the image does not depend on the number of
threads, on the bands, or on how the samples are split into passes (which only exist for the progress bar and
Ctrl-C). Samples are accumulated in float64.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np
import warp as wp

from ..core.runtime import init, launcher as shared_launcher

init()

from ..kernels import camera as CAM  # noqa: E402
from ..kernels import cloudscape as K  # noqa: E402
from ..kernels.hash import hash_pcg  # noqa: E402
from ..kernels.phase import phase_hg, phase_mie, phase_mie_params  # noqa: E402
from ..kernels.raymarch import raymarch_ray_sphere  # noqa: E402
from ..kernels.sky import Preetham, SkyGradient  # noqa: E402
from ..core.binding import lib  # noqa: E402
from ..core.pose import Pose  # noqa: E402
from .cloudscape import RenderTextures  # noqa: E402
from .technique import CloudscapeTechnique  # noqa: E402
from .settings import CloudscapeSettings  # noqa: E402

#: Samples per pixel: at least 1; at most 2^16 (the noise then is 1/256 of one sample's; more is never needed for an
#: 8-bit image, and a bound keeps every launch finite).
SPP_RANGE = (1, 65536)
#: Scattering vertices per path (medium or ground): at most 4096. The clouds are optically thick (sigma 30/km,
#: extinction optical depths of tens to ~100 through a cloud, g = 0.2) and do not absorb, so light diffuses through
#: hundreds of scattering events before it leaves a cloud's core.
BOUNCES_RANGE = (1, 4096)
#: Default bounces: 1024. Measured on the benchmark's noon scene (80x45, 32 spp, frame mean with a standard error of
#: 0.0015): 16 -> 0.595, 64 -> 0.645, 256 -> 0.660, 1024 -> 0.662, 4096 -> 0.664; the time per path was the same
#: from 64 to 4096 (deep paths are rare), so the default keeps the truncation below the noise of the benchmark's
#: references (~0.3 % of the frame mean left beyond 1024).
DEFAULT_BOUNCES = 1024
#: Single-scattering albedo: 1.0. Cloud droplets at visible wavelengths absorb next to nothing (co-albedo ~1e-6 to
#: 1e-4 for 10 um droplets at 550 nm); the darkening of thick clouds is the light scattered away, which the path
#: tracer follows. (The real-time model's precipitation absorption is a model term, not a property of this medium.)
DEFAULT_ALBEDO = 1.0
#: The density bound of the majorant (derivation in the module docstring).
DENSITY_BOUND = 1.0
#: Transmittance below which ratio tracking plays Russian roulette (survive with probability T / 0.1 at T = 0.1):
#: unbiased; the light left below 10 % costs most of the steps of long grazing shadow rays.
RR_TRANSMITTANCE = 0.1
#: Tracking steps per ray segment: the largest ``max_steps`` accepted (2^22: a segment then costs at most ~1 s).
MAX_STEPS_LIMIT = 1 << 22
#: Length of the fine chunks of the local majorant along a ray: 0.25 km, ~5 texels of the base texture (47 m) and
#: 4 of the weather map (62.5 m) at the default scales, so that a chunk's bound comes from a small neighbourhood (a
#: pyramid level of 8 texels per cell). Measured at 96x54 on the default scene: 0.0625-0.5 km all within the noise of
#: a shared machine (0.24-0.45 s per spp), 1.5-2x faster than the constant majorant.
FINE_CHUNK_KM = 0.25
#: Fine chunks per coarse chunk (2 km): a coarse chunk with a zero bound (clear air) is skipped with one lookup.
COARSE_CHUNKS = 8
#: Added to the per-texel base shape of the majorant pyramid: the kernel interpolates and remaps in float32, a few
#: ulp (~1e-7) from the exact convex combination; 1e-5 is far above that and far below any density that matters.
B_MARGIN = 1e-5
#: Samples per pixel per launch: the unit of progress (and of Ctrl-C latency); the image does not depend on it.
PASS_SPP = 4

DENSITY_CLOUDSCAPE = 0
DENSITY_SLAB = 1
DENSITY_MODES = {"cloudscape": DENSITY_CLOUDSCAPE, "slab": DENSITY_SLAB}
PIXEL_FILTERS = ("box", "centre")
#: How the path tracer treats the forward peak of the Mie phase (``phase='mie'``): ``exact`` -- the full phase
#: (1 - w_D) HG(g_HG) + w_D Draine, unbiased; ``truncated`` -- the phase flattened inside a cone of ``peak_cut_deg``
#: about the forward direction to its value p_c at the cut, min(p, p_c) / (1 - f_c), and the share f_c it no longer
#: scatters passed on unscattered (delta-M scaling: extinction sigma (1 - omega f_c), albedo omega (1 - f_c) / (1 -
#: omega f_c); :func:`peak_cut`), with the camera ray's single scattering of the sun through the full phase (TMS,
#: Nakajima & Tanaka 1988: the aureole inside the cut where a pixel looks near the sun). Why: under ``exact`` a
#: path whose direction falls within the peak's half degree of the sun makes a next-event estimate of up to
#: ~1500/sr x the sun -- a quarter of the light of a sunlit cloud arrives in such rare events, so its pixels stay
#: speckled at thousands of paths (docs/lighting.rst); truncated, the largest estimate is p_c / (1 - f_c) ~ 8/sr at
#: the default cut. Its cost: the peak's spread inside the cut is not resolved -- invisible where the sun is high,
#: measurable where its light enters the cloud at a grazing angle (docs/lighting.rst); checked against ``exact`` in
#: tests/clouds/test_lighting_converged.py.
PEAKS = ("exact", "truncated")
#: The cut angle of ``truncated``: 3 deg. Inside it the phase is flattened to its value there, p_c = 4.7/sr at 15 um
#: (f_c = 0.40 of the scattering passes unscattered); the largest next-event estimate falls from ~1500/sr to p_c /
#: (1 - f_c) = 7.8/sr, a few times Draine's lobe, so the pixels converge (half-to-half CIEDE2000 ~0.5 at 4096
#: paths against 1-2.7 exact). Smaller cuts are closer to ``exact`` where the sun is low (docs/lighting.rst) and
#: noisier: at 1 deg the largest estimate is ~115/sr.
PEAK_CUT_DEG = 3.0
#: Cut angles accepted: [0.5, 5] deg (wider cuts flatten the phase's shoulder; f_c <= 0.48 there, for 5-50 um
#: droplets, keeps the sampler's acceptance >= 0.52).
PEAK_CUT_RANGE = (0.5, 5.0)

_INF = wp.constant(1.0e30)
_PI = wp.constant(3.14159265358979323846)

# the de-tiled weather lookup's second copy (pywarp.kernels.cloudscape.cloudscape_weather)
_WD_COS = wp.constant(float(K.WEATHER_DETILE["cos"]))
_WD_SIN = wp.constant(float(K.WEATHER_DETILE["sin"]))
_WD_SCALE_B = wp.constant(float(K.WEATHER_DETILE["scale_b"]))
_WD_SHIFT_U = wp.constant(float(K.WEATHER_DETILE["shift_u"]))
_WD_SHIFT_V = wp.constant(float(K.WEATHER_DETILE["shift_v"]))

# status of a traced segment
_ESCAPED = wp.constant(0)
_MEDIUM = wp.constant(1)
_GROUND = wp.constant(2)
_TRUNCATED = wp.constant(3)


@wp.struct
class ReferenceParams:
    """The path tracer's own parameters (validated by :class:`ReferenceRenderer`)."""

    seed: wp.uint32
    sample0: int          # first sample index of this pass
    samples: int          # samples of this pass
    albedo: float         # single-scattering albedo omega
    g: float              # HG asymmetry of the medium (phase = thesis)
    phase: int            # K.PHASE_THESIS (HG g) or K.PHASE_MIE (the approximate Mie phase of droplet_um)
    droplet_um: float
    bounces: int          # max scattering vertices per path
    max_steps: int        # tracking steps per ray segment
    rho_max: float        # density bound (majorant = sigma * rho_max)
    density_mode: int     # DENSITY_CLOUDSCAPE or DENSITY_SLAB (a test medium: constant density in the shell)
    slab_density: float
    ground_albedo: wp.vec3
    sky_on: int           # 0: a black sky (tests)
    box_filter: int       # 1: uniform over the pixel, 0: pixel centres
    rr_threshold: float
    peak_cut: int         # 1: the Mie phase's forward peak truncated (PEAKS, 'truncated')
    cut_value: float      # p_c = the Mie phase at theta_c [1/sr]
    cut_share: float      # f_c = the share of scattering inside the cone above p_c, passed unscattered
    ext_scale: float      # the extinction's factor: 1, or 1 - albedo f_c with peak_cut


# --- medium -----------------------------------------------------------------------------------------------------------

@wp.struct
class MajorantGrids:
    """Max/min mip pyramids of the textures behind the density, for local majorants (:func:`chunk_bound`), built by
    :func:`majorant_grids`. Flat arrays, level 0 first, each level half the edge of the one before (periodic)."""

    weather_max: wp.array(dtype=float)    # max of the weather map's coverage (R) over each cell
    weather_size: int
    weather_levels: int
    base_max: wp.array(dtype=float)       # max of the per-texel base shape B (vc-2.28) of the base texture
    base_size: int
    base_levels: int
    fine_km: float                        # chunk lengths along the ray
    coarse_km: float
    enabled: int                          # 0: the constant majorant rho_max everywhere


@wp.func
def _level_fitting(lo0: int, hi0: int, lo1: int, hi1: int, lo2: int, hi2: int, levels: int) -> int:
    """The finest pyramid level whose cells cover the texel ranges [lo, hi] of every axis with at most 2 cells (the
    last level, a single cell, always does)."""
    k = int(0)
    for it in range(levels - 1):
        if (hi0 >> k) - (lo0 >> k) <= 1 and (hi1 >> k) - (lo1 >> k) <= 1 and (hi2 >> k) - (lo2 >> k) <= 1:
            break
        k = k + 1
    return k


@wp.func
def _texel_range(lo: float, hi: float, size: int):
    """Texels whose (bi/tri)linear footprint meets the texture coordinates [lo, hi] (in texture periods) of a texture
    of ``size`` texels (texel centres at i + 0.5): [floor(lo n - 0.5), floor(hi n - 0.5) + 1], widened by one texel
    on each side against the float32 rounding of the kernels' own coordinates."""
    n = float(size)
    return int(wp.floor(lo * n - 0.5)) - 1, int(wp.floor(hi * n - 0.5)) + 2


@wp.func
def weather_max_over(mj: MajorantGrids, x0: int, x1: int, z0: int, z1: int) -> float:
    """Max of the weather coverage over texels [x0, x1] x [z0, z1] (wrapped)."""
    k = _level_fitting(x0, x1, z0, z1, 0, 0, mj.weather_levels)
    off = int(0)
    n = mj.weather_size
    for i in range(k):
        off = off + n * n
        n = n / 2
    m = n - 1
    ax = (x0 >> k) & m
    bx = (x1 >> k) & m
    az = (z0 >> k) & m
    bz = (z1 >> k) & m
    return wp.max(wp.max(mj.weather_max[off + az * n + ax], mj.weather_max[off + az * n + bx]),
                  wp.max(mj.weather_max[off + bz * n + ax], mj.weather_max[off + bz * n + bx]))


@wp.func
def base_max_over(mj: MajorantGrids, x0: int, x1: int, y0: int, y1: int, z0: int, z1: int) -> float:
    """Max of the per-texel base shape B over texels [x0, x1] x [y0, y1] x [z0, z1] (wrapped)."""
    k = _level_fitting(x0, x1, y0, y1, z0, z1, mj.base_levels)
    off = int(0)
    n = mj.base_size
    for i in range(k):
        off = off + n * n * n
        n = n / 2
    m = n - 1
    b = float(0.0)
    for c in range(8):
        ix = (x0 >> k) & m
        if (c & 1) != 0:
            ix = (x1 >> k) & m
        iy = (y0 >> k) & m
        if (c & 2) != 0:
            iy = (y1 >> k) & m
        iz = (z0 >> k) & m
        if (c & 4) != 0:
            iz = (z1 >> k) & m
        b = wp.max(b, mj.base_max[off + (iz * n + iy) * n + ix])
    return b


@wp.func
def weather_bound(p: K.CloudscapeParams, mj: MajorantGrids, lo: wp.vec3, hi: wp.vec3) -> float:
    """The largest weather coverage D_h in the box [lo, hi] (km) as :func:`pywarp.kernels.cloudscape.cloudscape_weather`
    reads it: the map's lookup a, and with de-tiling the blend a + (b - a) k with k in [0, 1], at most max(a, b), so
    also the rotated, scaled copy b over the bounding box of the box's corners in its coordinates."""
    u0 = (lo[0] + p.weather_offset[0]) / p.weather_scale_km
    u1 = (hi[0] + p.weather_offset[0]) / p.weather_scale_km
    v0 = (lo[2] + p.weather_offset[1]) / p.weather_scale_km
    v1 = (hi[2] + p.weather_offset[1]) / p.weather_scale_km
    x0, x1 = _texel_range(u0, u1, mj.weather_size)
    z0, z1 = _texel_range(v0, v1, mj.weather_size)
    dh = weather_max_over(mj, x0, x1, z0, z1)
    if p.weather_detile != 0:
        bu0 = float(1.0e30)
        bu1 = float(-1.0e30)
        bv0 = float(1.0e30)
        bv1 = float(-1.0e30)
        for corner in range(4):
            u = u0
            if (corner & 1) != 0:
                u = u1
            v = v0
            if (corner & 2) != 0:
                v = v1
            bu = (_WD_COS * u - _WD_SIN * v) / _WD_SCALE_B + _WD_SHIFT_U
            bv = (_WD_SIN * u + _WD_COS * v) / _WD_SCALE_B + _WD_SHIFT_V
            bu0 = wp.min(bu0, bu)
            bu1 = wp.max(bu1, bu)
            bv0 = wp.min(bv0, bv)
            bv1 = wp.max(bv1, bv)
        x0, x1 = _texel_range(bu0, bu1, mj.weather_size)
        z0, z1 = _texel_range(bv0, bv1, mj.weather_size)
        dh = wp.max(dh, weather_max_over(mj, x0, x1, z0, z1))
    return dh


@wp.func
def chunk_bound(p: K.CloudscapeParams, r: ReferenceParams, mj: MajorantGrids, a: wp.vec3, b: wp.vec3) -> float:
    """An upper bound of the cloudscape density on the segment [a, b] (module docstring): with D_v <= 1 and the
    monotonic steps of vc-A17, rho <= B_D <= B_max + D_h,max - 1 (threshold C = 1 - D_h) or min(B_max, D_h,max)
    (C = D_h), where B_max is the largest per-texel base shape over the texels the trilinear lookups of the segment's
    bounding box can read, and D_h,max the largest weather coverage over its bilinear texels."""
    lo = wp.vec3(wp.min(a[0], b[0]), wp.min(a[1], b[1]), wp.min(a[2], b[2]))
    hi = wp.vec3(wp.max(a[0], b[0]), wp.max(a[1], b[1]), wp.max(a[2], b[2]))
    dh = weather_bound(p, mj, lo, hi)
    bound = float(0.0)
    if dh > 0.0:
        bx0, bx1 = _texel_range(lo[0] / p.base_scale_km, hi[0] / p.base_scale_km, mj.base_size)
        by0, by1 = _texel_range(lo[1] / p.base_scale_km, hi[1] / p.base_scale_km, mj.base_size)
        bz0, bz1 = _texel_range(lo[2] / p.base_scale_km, hi[2] / p.base_scale_km, mj.base_size)
        b_max = base_max_over(mj, bx0, bx1, by0, by1, bz0, bz1)
        if p.coverage_threshold == 0:
            bound = wp.min(b_max, dh)
        else:
            bound = b_max + dh - 1.0
    return wp.clamp(bound, 0.0, r.rho_max)


@wp.func
def reference_density(p: K.CloudscapeParams, r: ReferenceParams, tex: K.CloudTextures, pos: wp.vec3, bound: float,
                      flags: wp.array(dtype=wp.int32)) -> float:
    """The density the path tracer sees: the cloudscape's with detail (or the test slab's), with the majorant's bound
    ``rho <= bound`` asserted: a violation is counted in ``flags[0]`` (the render is refused)."""
    rho = float(0.0)
    if r.density_mode == DENSITY_SLAB:
        h = wp.length(pos - p.centre)
        if h >= p.r_inner and h <= p.r_outer:
            rho = r.slab_density
    else:
        rho, precip = K.cloudscape_density(p, tex, pos, 1)
    if not (rho <= bound):  # NaN too
        wp.atomic_add(flags, 0, 1)
    return rho


@wp.func
def shell_intervals(o: wp.vec3, d: wp.vec3, p: K.CloudscapeParams, check_ground: int):
    """The ray o + t d (t > 0, unit d) inside the layer's shell r_inner <= |x - c| <= r_outer, before the ground:
    (a0, b0, a1, b1, t_ground), two intervals (empty when a > b) and the distance to the Earth sphere (1e30: none).
    ``check_ground`` 0 for a ray leaving the ground (the Earth is convex: it cannot hit it again)."""
    c = p.centre
    a0 = float(1.0)
    b0 = float(0.0)
    a1 = float(1.0)
    b1 = float(0.0)
    tg = float(_INF)
    if check_ground != 0:
        e0, e1 = raymarch_ray_sphere(o, d, c, p.r_earth)
        if e0 > 0.0:  # NaN on a miss: no hit
            tg = e0
    u0, u1 = raymarch_ray_sphere(o, d, c, p.r_outer)
    if u1 > 0.0:
        a0 = wp.max(u0, 0.0)
        b0 = u1
        i0, i1 = raymarch_ray_sphere(o, d, c, p.r_inner)
        if i1 > 0.0 and i0 < u1:  # the inner sphere cuts the chord
            b0 = wp.min(u1, i0)
            a1 = wp.max(i1, 0.0)
            b1 = u1
        b0 = wp.min(b0, tg)
        b1 = wp.min(b1, tg)
    return a0, b0, a1, b1, tg


@wp.func
def track(p: K.CloudscapeParams, r: ReferenceParams, tex: K.CloudTextures, mj: MajorantGrids, o: wp.vec3,
          d: wp.vec3, check_ground: int, ratio: int, ext: float, state: wp.uint32, flags: wp.array(dtype=wp.int32)):
    """Tracking along o + t d through the layer with a piecewise-constant majorant: coarse chunks (``coarse_km``)
    whose bound is 0 are skipped whole, the others are cut into fine chunks (``fine_km``) tracked with
    ``sigma * chunk_bound`` (or ``sigma * rho_max`` everywhere when the grids are off).

    ``ratio`` 0 -- delta tracking (free-flight sampling): status _MEDIUM (a real collision at t), _GROUND (the Earth
    at t), _ESCAPED (left the layer for the sky) or _TRUNCATED (``max_steps`` reached: counted in flags[1]);
    ``ratio`` 1 -- ratio tracking: the transmittance T to infinity (0 where the Earth blocks the ray), with Russian
    roulette below ``rr_threshold``; ``ratio`` 2 -- the same, the transmittance of the clouds up to the Earth (the
    ground does not block: the view's cloud optical depth, :meth:`ReferenceRenderer.view_optical_depth`).

    ``ext``: the factor of the extinction (1: the cloud's; ``r.ext_scale``: the medium the paths see, scaled under
    peak='truncated'). ``max_steps`` bounds the iterations: every chunk bound and every tentative collision is one.
    Returns (status, t, T, state)."""
    a0, b0, a1, b1, tg = shell_intervals(o, d, p, check_ground)
    status = int(_ESCAPED)
    t_out = float(0.0)
    T = float(1.0)
    if ratio == 1 and tg < _INF:
        T = 0.0
    seg = int(0)
    lo = a0
    hi = b0
    if not (lo <= hi):
        seg = 1
        lo = a1
        hi = b1
    if T > 0.0 and lo <= hi:
        t = lo
        coarse_end = t
        fine_end = t
        bound = float(0.0)
        sigma_maj = float(0.0)
        inside = int(0)
        done = int(0)
        for k in range(r.max_steps):
            if inside == 0:
                # the next chunk with a positive bound
                if t >= hi:
                    if seg == 0 and a1 <= b1:
                        seg = 1
                        t = a1
                        hi = b1
                        coarse_end = t
                        continue
                    done = 1
                    break
                if mj.enabled == 0:
                    bound = r.rho_max
                    fine_end = hi
                else:
                    if t >= coarse_end:
                        coarse_end = wp.min(t + mj.coarse_km, hi)
                        if chunk_bound(p, r, mj, o + d * t, o + d * coarse_end) <= 0.0:
                            t = coarse_end
                            continue
                    fine_end = wp.min(t + mj.fine_km, coarse_end)
                    bound = chunk_bound(p, r, mj, o + d * t, o + d * fine_end)
                    if bound <= 0.0:
                        t = fine_end
                        continue
                sigma_maj = p.sigma * ext * bound
                inside = 1
            else:
                tn = t - wp.log(1.0 - wp.randf(state)) / sigma_maj
                if tn >= fine_end:
                    t = fine_end  # memoryless: the exponential restarts in the next chunk
                    inside = 0
                    continue
                t = tn
                rho = reference_density(p, r, tex, o + d * t, bound, flags)
                if ratio == 0:
                    if wp.randf(state) * bound < rho:
                        status = _MEDIUM
                        t_out = t
                        done = 1
                        break
                else:
                    T = T * (1.0 - rho / bound)
                    if T < r.rr_threshold:
                        if wp.randf(state) * r.rr_threshold < T:
                            T = r.rr_threshold
                        else:
                            T = 0.0
                            done = 1
                            break
        if done == 0:
            wp.atomic_add(flags, 1, 1)
            status = _TRUNCATED
            T = 0.0
    if ratio == 0 and status == _ESCAPED and tg < _INF:
        status = _GROUND
        t_out = tg
    return status, t_out, T, state


# --- sampling ---------------------------------------------------------------------------------------------------------

@wp.func
def _basis(n: wp.vec3):
    """Orthonormal tangents of unit n (Duff et al. 2017, 'Building an orthonormal basis, revisited')."""
    sign = float(1.0)
    if n[2] < 0.0:
        sign = -1.0
    a = -1.0 / (sign + n[2])
    b = n[0] * n[1] * a
    t1 = wp.vec3(1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0])
    t2 = wp.vec3(b, sign + n[1] * n[1] * a, -n[1])
    return t1, t2


@wp.func
def sample_hg_cos(g: float, u: float) -> float:
    """cos(theta) of a Henyey-Greenstein direction relative to the propagation direction (inverse CDF):
    cos = (1 + g^2 - ((1 - g^2) / (1 - g + 2 g u))^2) / (2 g); u = 0 -> -1, u = 1 -> +1; uniform for |g| < 1e-3."""
    if wp.abs(g) < 1.0e-3:
        return 1.0 - 2.0 * u
    s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u)
    return wp.clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0)


@wp.func
def around(axis: wp.vec3, cos_theta: float, phi: float) -> wp.vec3:
    """The unit direction at angle theta from unit ``axis``, azimuth phi."""
    t1, t2 = _basis(axis)
    sin_theta = wp.sqrt(wp.max(0.0, 1.0 - cos_theta * cos_theta))
    return wp.normalize(axis * cos_theta + t1 * (sin_theta * wp.cos(phi)) + t2 * (sin_theta * wp.sin(phi)))


@wp.func
def sample_hg(d: wp.vec3, g: float, state: wp.uint32):
    """A new propagation direction after scattering from propagation direction d: (direction, state)."""
    u1 = wp.randf(state)
    u2 = wp.randf(state)
    return around(d, sample_hg_cos(g, u1), 2.0 * _PI * u2), state


#: Most proposals of the truncated Mie phase's rejection sampler (peak 'truncated', :func:`sample_phase`): a proposal
#: from the full phase is accepted with probability min(1, p_c / p), on average 1 - f_c >= 0.52 (f_c <= 0.48 for
#: cuts up to 5 deg, :data:`PEAK_CUT_RANGE`), so all 256 fail with probability < 2^-256 -- never -- and the loop is
#: finite.
TRUNCATED_TRIES = wp.constant(256)


#: Most proposals of the rejection sampler of Draine's lobe (:func:`sample_draine_cos`): the acceptance probability
#: is at least 1/3 (the mean of (1 + alpha mu^2) / (1 + alpha) under HG(g) is (1 + alpha (1 + 2 g^2) / 3) / (1 + alpha)
#: >= 1/3), so all 256 fail with probability <= (2/3)^256 ~ 1e-45 -- never in any image -- and the bound keeps the
#: loop finite.
DRAINE_TRIES = wp.constant(256)


@wp.func
def sample_draine_cos(g: float, alpha: float, state: wp.uint32):
    """cos(theta) of Draine's phase function HG(g) (1 + alpha mu^2) / (1 + alpha (1 + 2 g^2) / 3) (Draine 2003), by
    rejection: propose mu from HG(g), accept with probability (1 + alpha mu^2) / (1 + alpha) (the ratio of the target
    to the proposal, up to the constant, is at most 1 + alpha at mu = +-1). Exact (module docstring of the bound).
    Returns (mu, state)."""
    mu = float(1.0)
    for k in range(DRAINE_TRIES):
        mu = sample_hg_cos(g, wp.randf(state))
        if wp.randf(state) * (1.0 + alpha) <= 1.0 + alpha * mu * mu:
            break
    return mu, state


@wp.func
def sample_phase(d: wp.vec3, r: ReferenceParams, state: wp.uint32):
    """A new propagation direction from the medium's phase function: HG(r.g), or the approximate Mie phase
    (1 - w_D) HG(g_HG) + w_D Draine(g_D, alpha) by picking the lobe with probability w_D (vc-x-mie). (dir, state)."""
    cos_t = float(0.0)
    if r.phase == K.PHASE_MIE:
        g_hg, g_d, alpha, w_d = phase_mie_params(r.droplet_um)
        for k in range(TRUNCATED_TRIES):
            if wp.randf(state) < w_d:
                cos_t, state = sample_draine_cos(g_d, alpha, state)
            else:
                cos_t = sample_hg_cos(g_hg, wp.randf(state))
            # the truncated phase (peak 'truncated'): min(p, p_c) by rejection from p, accepted with min(1, p_c / p)
            if r.peak_cut == 0:
                break
            if wp.randf(state) * phase_mie(cos_t, r.droplet_um) <= r.cut_value:
                break
    else:
        cos_t = sample_hg_cos(r.g, wp.randf(state))
    return around(d, cos_t, 2.0 * _PI * wp.randf(state)), state


@wp.func
def phase_value(cos_theta: float, r: ReferenceParams) -> float:
    """The medium's phase function at cos_theta [1/sr] (next-event estimation); with peak 'truncated' the Mie phase
    flattened to its value p_c at the cut inside the cut's cone, renormalised: min(p, p_c) / (1 - f_c)."""
    if r.phase == K.PHASE_MIE and r.peak_cut != 0:
        return wp.min(phase_mie(cos_theta, r.droplet_um), r.cut_value) / (1.0 - r.cut_share)
    if r.phase == K.PHASE_MIE:
        return phase_mie(cos_theta, r.droplet_um)
    return phase_hg(cos_theta, r.g)


@wp.func
def sample_cosine(n: wp.vec3, state: wp.uint32):
    """A cosine-weighted direction about unit n (pdf cos / pi): (direction, state)."""
    u1 = wp.randf(state)
    u2 = wp.randf(state)
    return around(n, wp.sqrt(1.0 - u1), 2.0 * _PI * u2), state


@wp.func
def sample_seed(seed: wp.uint32, x: int, y: int, sample: int) -> wp.uint32:
    """The RNG state of sample ``sample`` of pixel (x, y): a function of these four numbers only."""
    return hash_pcg(seed ^ hash_pcg(wp.uint32(x) + hash_pcg(wp.uint32(y) + hash_pcg(wp.uint32(sample)))))


@wp.func
def pixel_direction(m: wp.mat44, fx: float, fy: float, width: int, height: int) -> wp.vec3:
    """The view direction through image point (fx, fy) in pixels (row 0 at the top): vc-A25's mapping
    (:func:`pywarp.kernels.camera.camera_ray` at ``fx = x + 0.5``), at any point of the pixel."""
    nx = 2.0 * fx / float(width) - 1.0
    ny = 1.0 - 2.0 * fy / float(height)
    hx = m[0][0] * nx + m[0][1] * ny + m[0][2] + m[0][3]
    hy = m[1][0] * nx + m[1][1] * ny + m[1][2] + m[1][3]
    hz = m[2][0] * nx + m[2][1] * ny + m[2][2] + m[2][3]
    return wp.normalize(wp.vec3(hx, hy, hz))


# --- one path ---------------------------------------------------------------------------------------------------------

@wp.func
def trace_path(p: K.CloudscapeParams, r: ReferenceParams, tex: K.CloudTextures, mj: MajorantGrids, sky_kind: int,
               sun: wp.vec3, preetham: Preetham,
               gradient: SkyGradient, eye: wp.vec3, d0: wp.vec3, state: wp.uint32,
               flags: wp.array(dtype=wp.int32)):
    """Radiance along the camera ray (eye, d0): (L, state). See the module docstring."""
    L = wp.vec3(0.0, 0.0, 0.0)
    beta = wp.vec3(1.0, 1.0, 1.0)
    o = eye
    d = d0
    check_ground = int(1)
    for k in range(r.bounces + 1):
        status, t, T0, state = track(p, r, tex, mj, o, d, check_ground, 0, r.ext_scale, state, flags)
        if status == _ESCAPED:
            if r.sky_on != 0:
                L = L + wp.cw_mul(beta, K.sky_colour(sky_kind, d, sun, preetham, gradient))
            break
        if status == _TRUNCATED or k == r.bounces:
            break  # vertex bounces + 1: not allowed
        x = o + d * t
        if status == _MEDIUM:
            beta = beta * r.albedo
            cos_s = wp.clamp(wp.dot(d, sun), -1.0, 1.0)
            st, t_s, T, state = track(p, r, tex, mj, x, sun, 1, 1, r.ext_scale, state, flags)
            pv = phase_value(cos_s, r)
            if k == 0 and r.peak_cut != 0:
                # TMS (Nakajima & Tanaka 1988): the camera ray's single scattering with the full phase over the
                # truncation's 1 - f_c (the scaled medium's attenuation kept): the aureole within the cut where the
                # view looks near the sun; the same value as min(p, p_c) / (1 - f_c) outside the cone. Deterministic
                # per pixel, so no fireflies.
                pv = phase_mie(cos_s, r.droplet_um) / (1.0 - r.cut_share)
            L = L + wp.cw_mul(beta, p.sun_colour) * (pv * T)
            d, state = sample_phase(d, r, state)
            check_ground = 1
        else:  # the ground: Lambertian
            n = wp.normalize(x - p.centre)
            cos_n = wp.dot(n, sun)
            if cos_n > 0.0:
                st, t_s, T, state = track(p, r, tex, mj, x, sun, 0, 1, r.ext_scale, state, flags)
                L = L + wp.cw_mul(wp.cw_mul(beta, r.ground_albedo), p.sun_colour) * (cos_n * T / _PI)
            beta = wp.cw_mul(beta, r.ground_albedo)
            d, state = sample_cosine(n, state)
            check_ground = 0
        o = x
    return L, state


@wp.kernel
def reference_kernel(row0: int, p: K.CloudscapeParams, r: ReferenceParams, tex: K.CloudTextures,
                     mj: MajorantGrids, sky_kind: int, sun: wp.vec3, preetham: Preetham,
                     gradient: SkyGradient, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                     # outputs
                     accum: wp.array3d(dtype=wp.float64), accum_sq: wp.array3d(dtype=wp.float64),
                     flags: wp.array(dtype=wp.int32)):
    """``r.samples`` paths per pixel (samples ``r.sample0 ...``), each added to ``accum`` and its square to
    ``accum_sq`` in sample order, in float64 (so the sums do not depend on how the samples are split into launches;
    TileLauncher convention: row bands)."""
    i, j = wp.tid()
    height = accum.shape[0]
    width = accum.shape[1]
    y = row0 + i
    x = j
    for s in range(r.samples):
        state = sample_seed(r.seed, x, y, r.sample0 + s)
        jx = float(0.5)
        jy = float(0.5)
        if r.box_filter != 0:
            jx = wp.randf(state)
            jy = wp.randf(state)
        d = pixel_direction(inv_view_proj_rot, float(x) + jx, float(y) + jy, width, height)
        L, state = trace_path(p, r, tex, mj, sky_kind, sun, preetham, gradient, eye, d, state,
                              flags)
        for ch in range(3):
            v = wp.float64(L[ch])
            accum[y, x, ch] = accum[y, x, ch] + v
            accum_sq[y, x, ch] = accum_sq[y, x, ch] + v * v


@wp.kernel
def view_transmittance_kernel(row0: int, p: K.CloudscapeParams, r: ReferenceParams, tex: K.CloudTextures,
                              mj: MajorantGrids, inv_view_proj_rot: wp.mat44, eye: wp.vec3,
                              # outputs
                              out: wp.array2d(dtype=float), flags: wp.array(dtype=wp.int32)):
    """The clouds' transmittance along each pixel-centre view ray up to the ground: the mean of ``r.samples`` ratio
    tracking estimates (unbiased; TileLauncher convention)."""
    i, j = wp.tid()
    height = out.shape[0]
    width = out.shape[1]
    y = row0 + i
    d = pixel_direction(inv_view_proj_rot, float(j) + 0.5, float(y) + 0.5, width, height)
    acc = float(0.0)
    for s in range(r.samples):
        state = sample_seed(r.seed, j, y, r.sample0 + s)
        st, t, T, state = track(p, r, tex, mj, eye, d, 1, 2, 1.0, state, flags)
        acc = acc + T
    out[y, j] = acc / float(r.samples)


@wp.kernel
def hg_samples_kernel(g: float, seed: wp.uint32, out: wp.array(dtype=float)):
    """cos(theta) of HG samples about +z (for the sampler's tests)."""
    i = wp.tid()
    state = sample_seed(seed, i, 0, 0)
    d, state = sample_hg(wp.vec3(0.0, 0.0, 1.0), g, state)
    out[i] = d[2]


@wp.kernel
def phase_samples_kernel(r: ReferenceParams, seed: wp.uint32, out: wp.array(dtype=float)):
    """cos(theta) of samples of the medium's phase function about +z (for the sampler's tests)."""
    i = wp.tid()
    state = sample_seed(seed, i, 0, 0)
    d, state = sample_phase(wp.vec3(0.0, 0.0, 1.0), r, state)
    out[i] = d[2]


# --- host side --------------------------------------------------------------------------------------------------------

def peak_cut(droplet_um: float, cut_deg: float) -> tuple[float, float, float]:
    """(cos theta_c, p_c, f_c) of the truncated Mie phase min(p, p_c) / (1 - f_c) (peak 'truncated', :data:`PEAKS`):
    p_c the phase at the cut angle (float32, ``ccl_phase_mie``, as the kernel evaluates it) and f_c = 2 pi
    int_{cos theta_c}^1 (p - p_c) dmu, the share of the scattering above p_c (the phase falls monotonically from the
    forward direction past the cut, tested; trapezoids over 20001 angles in float64: the peak is ~0.4 deg wide, the
    step cut / 20000 <= 0.00025 deg)."""
    c = lib()
    cos_c = float(np.float32(math.cos(math.radians(cut_deg))))
    p_c = float(c.ccl_phase_mie(cos_c, droplet_um))
    theta = np.linspace(0.0, math.radians(cut_deg), 20001)
    p = np.array([c.ccl_phase_mie(float(np.float32(math.cos(t))), droplet_um) for t in theta], dtype=np.float64)
    y = np.maximum(p - p_c, 0.0) * np.sin(theta)
    f = 2.0 * math.pi * float(np.sum((y[1:] + y[:-1]) * np.diff(theta)) / 2.0)
    return cos_c, p_c, float(f)


def _int_in(name: str, value, lo: int, hi: int) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an integer in [{lo}, {hi}], got {value!r}")
    if not lo <= int(value) <= hi:
        raise ValueError(f"{name} must be in [{lo}, {hi}], got {value!r}")
    return int(value)


def _float_in(name: str, value, lo: float, hi: float) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number in [{lo:g}, {hi:g}], got {value!r}")
    v = float(value)
    if not (math.isfinite(v) and lo <= v <= hi):
        raise ValueError(f"{name} must be in [{lo:g}, {hi:g}], got {value!r}")
    return v


def longest_chord_km(settings: CloudscapeSettings) -> float:
    """The longest path of one ray inside the layer's shell: the chord tangent to the inner sphere,
    2 sqrt(r_outer^2 - r_inner^2)."""
    layer = settings.layer()
    return 2.0 * math.sqrt(float(layer.r_outer) ** 2 - float(layer.r_inner) ** 2)


def default_max_steps(settings: CloudscapeSettings, rho_max: float = DENSITY_BOUND, fine_km: float = None) -> int:
    """Twice the expected number of tracking iterations along the longest chord (majorant events at the bound
    ``rho_max`` everywhere, plus one per fine and coarse chunk), plus 1024: a segment never reaches it in practice
    (Poisson: the mean plus > 100 standard deviations at the default layer)."""
    fine = FINE_CHUNK_KM if fine_km is None else fine_km
    length = longest_chord_km(settings)
    mu = settings.sigma_per_km * rho_max * length + length / fine * (1.0 + 1.0 / COARSE_CHUNKS) + 2.0
    return int(math.ceil(2.0 * mu)) + 1024


def _pyramid(level0: np.ndarray, reduce) -> np.ndarray:
    """The periodic max (or min) mip pyramid of a square or cubic power-of-two array, flattened, level 0 first:
    each cell of level k + 1 reduces its 2^d children of level k."""
    levels = [np.ascontiguousarray(level0, dtype=np.float32)]
    a = levels[0]
    while a.shape[0] > 1:
        parts = [a[tuple(slice(o, None, 2) for o in offs)] for offs in np.ndindex(*(2,) * a.ndim)]
        a = reduce.reduce(np.stack(parts), axis=0)
        levels.append(np.ascontiguousarray(a, dtype=np.float32))
    return levels


def majorant_grids(textures: RenderTextures, enabled: bool = True, fine_km: float = None,
                   coarse_km: float = None, device: str = "cpu", half_base: bool = True) -> MajorantGrids:
    """The :class:`MajorantGrids` of ``textures``: periodic max pyramids of the weather coverage and of the per-texel
    base shape B = (R - L + 1) / (2 - L), L = 0.625 G + 0.25 B + 0.125 A (vc-2.28), of the base's texels as the
    kernels read them (``half_base``: rounded to float16 values, ``RenderTextures.level0``).

    Why the per-texel B bounds B at any point: the trilinear lookup interpolates the channels, so (R, L) at a point
    is a convex combination of the 8 texels' (R, L); B is a linear-fractional function of (R, L) with a positive
    denominator (L <= 1), hence quasilinear (Boyd & Vandenberghe 2004, 3.4.1), and its value at a convex combination
    is at most the largest value at the texels. :data:`B_MARGIN` covers the float32 rounding of the kernel's
    interpolation and remap."""
    w = np.asarray(textures.weather[..., 0], dtype=np.float32)
    base = np.asarray(textures.level0("base", half_base), dtype=np.float64)
    lfbm = 0.625 * base[..., 1] + 0.25 * base[..., 2] + 0.125 * base[..., 3]
    b_texel = (base[..., 0] - lfbm + 1.0) / (2.0 - lfbm) + B_MARGIN
    wl = _pyramid(w, np.maximum)
    bl = _pyramid(b_texel.astype(np.float32), np.maximum)
    mj = MajorantGrids()
    mj.weather_max = wp.array(np.concatenate([a.ravel() for a in wl]), dtype=float, device=device)
    mj.weather_size = int(w.shape[0])
    mj.weather_levels = len(wl)
    mj.base_max = wp.array(np.concatenate([a.ravel() for a in bl]), dtype=float, device=device)
    mj.base_size = int(base.shape[0])
    mj.base_levels = len(bl)
    fine = FINE_CHUNK_KM if fine_km is None else float(fine_km)
    mj.fine_km = fine
    mj.coarse_km = fine * COARSE_CHUNKS if coarse_km is None else float(coarse_km)
    mj.enabled = int(bool(enabled))
    return mj


class ReferenceRenderer:
    """The path tracer for a cloudscape's settings (module docstring). Parameters are validated here, before any
    kernel runs; ValueError/TypeError name the parameter and its range.

    ``spp``, ``seed``, ``bounces``: default from the settings (``spp``, ``reference_seed``, ``reference_bounces``)
    where they have them, else 64, 0, :data:`DEFAULT_BOUNCES`. ``albedo``: single-scattering albedo in [0, 1].
    ``phase_g``: HG g of the medium (default the settings' ``g``). ``max_steps``: tracking steps per ray segment
    (default :func:`default_max_steps`). ``pixel_filter``: 'box' (the pixel's area, the image's ground truth) or
    'centre' (pixel centres, as the real-time renderer samples). ``density``: 'cloudscape' or 'slab' (a test medium:
    ``slab_density`` everywhere in the shell). ``sky``: False for a black sky (tests). ``ground_albedo``: RGB in
    [0, 1] (default: the settings' ``ground_albedo``, the real-time renderer's). ``majorant``: local majorants from
    the texture pyramids (False: the constant ``sigma * DENSITY_BOUND``; the same image in expectation, slower)."""

    technique_kind = "reference"

    def __init__(self, settings: CloudscapeSettings | None = None, textures: RenderTextures | None = None, *,
                 spp: int | None = None, seed: int | None = None, bounces: int | None = None,
                 albedo: float = DEFAULT_ALBEDO, phase_g: float | None = None, max_steps: int | None = None,
                 pixel_filter: str = "box", density: str = "cloudscape", slab_density: float = 0.5,
                 sky: bool = True, ground_albedo=None, majorant: bool = True, threads: int | None = None,
                 peak: str = "exact", peak_cut_deg: float = PEAK_CUT_DEG):
        self._arguments = dict(spp=spp, seed=seed, bounces=bounces, albedo=albedo, phase_g=phase_g,
                               max_steps=max_steps, pixel_filter=pixel_filter, density=density,
                               slab_density=slab_density, sky=sky, ground_albedo=ground_albedo, majorant=majorant,
                               threads=threads, peak=peak, peak_cut_deg=peak_cut_deg)
        self.settings = settings or CloudscapeSettings()
        s = self.settings
        if getattr(s, "accumulate", 1) != 1:
            raise ValueError(f"accumulate must be 1 with the reference (it averages its spp paths per pixel "
                             f"instead), got {s.accumulate}")
        self.spp = _int_in("spp", spp if spp is not None else getattr(s, "spp", 64), *SPP_RANGE)
        self.seed = _int_in("seed", seed if seed is not None else getattr(s, "reference_seed", 0), 0, 2 ** 32 - 1)
        self.bounces = _int_in("bounces", bounces if bounces is not None
                               else getattr(s, "reference_bounces", DEFAULT_BOUNCES), *BOUNCES_RANGE)
        self.albedo = _float_in("albedo", albedo, 0.0, 1.0)
        self.g = _float_in("phase_g", s.g if phase_g is None else phase_g, -0.999, 0.999)
        self.phase = s.phase
        self.droplet_um = float(s.droplet_um)
        if peak not in PEAKS:
            raise ValueError(f"peak must be one of {', '.join(map(repr, PEAKS))}, got {peak!r}")
        if peak == "truncated" and self.phase != "mie":
            raise ValueError(f"peak='truncated' needs the Mie phase (phase 'mie'; its forward peak is what is "
                             f"truncated), got phase {self.phase!r}")
        self.peak = peak
        self.peak_cut_deg = _float_in("peak_cut_deg", peak_cut_deg, *PEAK_CUT_RANGE)
        self.cut = peak_cut(self.droplet_um, self.peak_cut_deg) if peak == "truncated" else None
        if pixel_filter not in PIXEL_FILTERS:
            raise ValueError(f"pixel_filter must be one of {', '.join(map(repr, PIXEL_FILTERS))}, got "
                             f"{pixel_filter!r}")
        self.pixel_filter = pixel_filter
        if density not in DENSITY_MODES:
            raise ValueError(f"density must be one of {', '.join(map(repr, DENSITY_MODES))}, got {density!r}")
        self.density = density
        self.slab_density = _float_in("slab_density", slab_density, 0.0, DENSITY_BOUND)
        self.sky_on = bool(sky)
        self.values = s.c_values()
        s.c_params(self.values)  # ccl_cloudscape_check at the texture sizes
        if int(self.values["gradient_clamp"]) != 1:
            raise ValueError("gradient_clamp must be 1 for the reference (the density bound of the majorant needs "
                             f"clamped height gradients), got {self.values['gradient_clamp']!r}")
        ga = self.values["ground_albedo"] if ground_albedo is None else ground_albedo
        try:
            ga = tuple(ga)
        except TypeError:
            raise TypeError(f"ground_albedo must be 3 numbers in [0, 1], got {ga!r}") from None
        if len(ga) != 3:
            raise ValueError(f"ground_albedo must be 3 numbers in [0, 1], got {ga!r}")
        self.ground_albedo = tuple(_float_in("ground_albedo", v, 0.0, 1.0) for v in ga)
        needed = default_max_steps(s)
        self.max_steps = _int_in("max_steps", needed if max_steps is None else max_steps, 1, MAX_STEPS_LIMIT)
        if self.max_steps < needed - 1024:
            raise ValueError(f"max_steps must be >= {needed - 1024} (twice the expected tracking steps along the "
                             f"longest chord of the layer, {longest_chord_km(s):.1f} km at sigma "
                             f"{s.sigma_per_km:g}/km), got {self.max_steps}")
        self.launcher = shared_launcher(s.device, s.threads if threads is None else threads)
        self.device = self.launcher.device
        self.textures = textures if textures is not None else RenderTextures.generate(s)
        for name in ("base", "detail", "weather"):  # the curl texture only displaces the detail lookup
            a = getattr(self.textures, name)
            if not (np.all(np.isfinite(a)) and a.min() >= 0.0 and a.max() <= 1.0):
                raise ValueError(f"textures: {name} must hold values in [0, 1] (the density bound of the majorant "
                                 f"needs them), got [{a.min()!r}, {a.max()!r}]")
        self.majorant = bool(majorant)
        self.grids = majorant_grids(self.textures, enabled=self.majorant and density == "cloudscape",
                                    device=self.device, half_base=s.half_base())
        # the sun, sky and medium exactly as the real-time technique sets them up for these settings (its
        # parameters, including any per-frame light set-up from the sky model, and its sky model)
        # (the medium itself: a lighting model's delta scaling of the Mie phase, mie_delta, is no part of it)
        medium = replace(s, mie_delta=0.0, advanced={k: v for k, v in s.advanced.items() if k != "mie_delta"})
        rt = CloudscapeTechnique(medium, textures=self.textures)
        self.params = rt.params
        self.sky = rt.sky
        self.stats: dict = {}

    # the scene technique protocol (pywarp.core.scenes): update / render / resize
    def update(self, **changes) -> None:
        """Change settings (validated); the textures are kept unless a texture setting changed. The constructor's
        own arguments stay (those left at None follow the new settings)."""
        new = replace(self.settings, **changes)
        textures = self.textures if "textures" not in new.invalidated(self.settings) else None
        self.__init__(new, textures, **self._arguments)

    def resize(self, width: int, height: int) -> None:
        self.update(width=width, height=height)

    def _reference_params(self, sample0: int, samples: int) -> ReferenceParams:
        r = ReferenceParams()
        r.seed = wp.uint32(self.seed)
        r.sample0 = int(sample0)
        r.samples = int(samples)
        r.albedo = self.albedo
        r.g = self.g
        r.phase = K.PHASE_MIE if self.phase == "mie" else K.PHASE_THESIS
        r.droplet_um = self.droplet_um
        r.bounces = self.bounces
        r.max_steps = self.max_steps
        r.rho_max = DENSITY_BOUND
        r.density_mode = DENSITY_MODES[self.density]
        r.slab_density = self.slab_density
        r.ground_albedo = wp.vec3(*self.ground_albedo)
        r.sky_on = int(self.sky_on)
        r.box_filter = int(self.pixel_filter == "box")
        r.rr_threshold = RR_TRANSMITTANCE
        r.peak_cut = int(self.peak == "truncated")
        r.ext_scale = 1.0
        r.cut_value, r.cut_share = 0.0, 0.0
        if self.cut is not None:
            # delta-M scaling of the share f_c passed unscattered: extinction sigma (1 - omega f_c), single-scattering
            # albedo omega (1 - f_c) / (1 - omega f_c)
            r.cut_value, r.cut_share = self.cut[1], self.cut[2]
            r.ext_scale = 1.0 - self.albedo * self.cut[2]
            r.albedo = self.albedo * (1.0 - self.cut[2]) / r.ext_scale
        return r

    def render(self, pose: Pose | None = None, encode: bool = True, progress=None):
        """The path-traced frame: uint8 sRGB (height, width, 3), or display-linear float32 with ``encode=False``
        (the mean of ``spp`` paths per pixel). ``progress(fraction)`` as passes of PASS_SPP samples finish (the
        fractions add up to 1). Sets :attr:`stats`: spp, seconds, std_error (per-pixel Monte Carlo standard error
        of the linear image, mean over pixels and channels; NaN at spp = 1), std_error_max, std_error_image and
        majorant ('local', or 'constant' with the reason).

        The local majorant's bound is checked at every density sample; should a change of the density function
        ever break it, the samples are redone with the constant bound (warned, ``stats['majorant']`` says why), so
        the image stays unbiased."""
        s = self.settings
        pose = pose or Pose.from_settings(s)
        cam = CAM.pose_camera(pose, s.width, s.height)
        h, w = s.height, s.width
        tex = self.textures.warp(s.half_base())
        sun = wp.vec3(*self.sky.sun.tolist())
        inputs = [self.sky.kind, sun, self.sky.preetham, self.sky.gradient, cam.mat44("inv_view_proj_rot"),
                  cam.eye_vec3()]
        reported = [0.0]

        def report(total: float) -> None:  # fractions of the frame, never more than 1 in all (also after a redo)
            if progress is not None and total > reported[0]:
                progress(total - reported[0])
                reported[0] = total

        t0 = time.perf_counter()
        grids = self.grids
        majorant = "local" if grids.enabled else "constant"
        while True:
            accum = wp.zeros((h, w, 3), dtype=wp.float64, device=self.device)
            accum_sq = wp.zeros((h, w, 3), dtype=wp.float64, device=self.device)
            flags = wp.zeros(2, dtype=wp.int32, device=self.device)
            done = 0
            violated = 0
            while done < self.spp:
                n = min(PASS_SPP, self.spp - done)
                base_fraction = done / self.spp
                rows_done = [0]

                def band_done(rows, n=n, base_fraction=base_fraction, rows_done=rows_done):
                    rows_done[0] += rows
                    report(base_fraction + rows_done[0] / h * n / self.spp)

                self.launcher.launch(reference_kernel, h, w,
                                     [self.params, self._reference_params(done, n), tex, grids, *inputs],
                                     [accum, accum_sq, flags], progress=band_done)
                done += n
                violated = int(flags.numpy()[0])
                if violated:
                    break
            if violated and grids.enabled:
                import warnings

                majorant = (f"constant (the local bound was exceeded at {violated} density samples: the density "
                            "function changed; update chunk_bound)")
                warnings.warn(f"reference: {majorant}; redoing the samples with the constant majorant",
                              RuntimeWarning, stacklevel=2)
                grids = majorant_grids(self.textures, enabled=False, device=self.device,
                                       half_base=s.half_base())
                continue
            break
        seconds = time.perf_counter() - t0
        f = flags.numpy()
        if f[0] > 0:
            raise RuntimeError(f"the density exceeded its bound {DENSITY_BOUND} at {int(f[0])} samples (the majorant "
                               "would be wrong); nothing is written")
        if f[1] > 0:
            raise RuntimeError(f"{int(f[1])} ray segments reached max_steps = {self.max_steps}; raise max_steps")
        n = float(self.spp)
        mean = accum.numpy() / n
        var = np.maximum(accum_sq.numpy() / n - mean * mean, 0.0) * (n / max(n - 1.0, 1.0))
        se = np.sqrt(var / n) if self.spp > 1 else np.full_like(mean, np.nan)  # one path: no variance estimate
        self.stats = {"spp": self.spp, "seed": self.seed, "bounces": self.bounces, "seconds": seconds,
                      "seconds_per_spp": seconds / n, "std_error": float(se.mean()),
                      "std_error_max": float(se.max()), "std_error_image": se.astype(np.float32),
                      "majorant": majorant}
        linear = mean.astype(np.float32)
        if not np.all(np.isfinite(linear)):
            raise RuntimeError("the reference produced non-finite pixels; nothing is written")
        if not encode:
            return linear
        return encode_srgb(linear, self.launcher)

    def view_optical_depth(self, pose: Pose | None = None, samples: int = 64) -> np.ndarray:
        """The clouds' optical depth tau = -ln T along each pixel-centre view ray up to the ground (float32 (height,
        width); inf where every estimate was 0): T the mean of ``samples`` ratio-tracking estimates (unbiased for T;
        at T = e^-3 and 64 samples its relative standard error is ~0.1). The pixel classes of
        ``pywarp bench clouds reference`` (clear, thin, thick) come from it."""
        s = self.settings
        samples = _int_in("samples", samples, 1, SPP_RANGE[1])
        pose = pose or Pose.from_settings(s)
        cam = CAM.pose_camera(pose, s.width, s.height)
        out = wp.zeros((s.height, s.width), dtype=float, device=self.device)
        flags = wp.zeros(2, dtype=wp.int32, device=self.device)
        self.launcher.launch(view_transmittance_kernel, s.height, s.width,
                             [self.params, self._reference_params(0, samples), self.textures.warp(s.half_base()),
                              self.grids, cam.mat44("inv_view_proj_rot"), cam.eye_vec3()], [out, flags])
        f = flags.numpy()
        if f[0] > 0 or f[1] > 0:
            raise RuntimeError(f"view_optical_depth: {int(f[0])} densities above the bound, {int(f[1])} segments at "
                               "max_steps; nothing is returned")
        with np.errstate(divide="ignore"):
            return (-np.log(out.numpy().astype(np.float64))).astype(np.float32)

    def render_linear(self, pose: Pose | None = None, progress=None) -> np.ndarray:
        """The linear-image hook (:mod:`pywarp.core.linear`)."""
        return self.render(pose, encode=False, progress=progress)


def encode_srgb(linear: np.ndarray, launcher=None) -> np.ndarray:
    """The real-time renderer's display step (``encode_kernel``: clamp to [0, 1], sRGB) on a linear frame: uint8."""
    lau = launcher or shared_launcher()
    a = wp.array(np.ascontiguousarray(linear, dtype=np.float32), dtype=float, device=lau.device)
    out = wp.zeros(a.shape, dtype=wp.uint8, device=lau.device)
    lau.launch(K.encode_kernel, a.shape[0], a.shape[1], [a], [out, wp.zeros(1, dtype=wp.int32, device=lau.device)])
    return out.numpy()


def render_reference(settings: CloudscapeSettings | None = None, pose: Pose | None = None, encode: bool = True,
                     **kwargs):
    """One path-traced frame (see :class:`ReferenceRenderer` for ``kwargs``)."""
    return ReferenceRenderer(settings, **kwargs).render(pose, encode=encode)
