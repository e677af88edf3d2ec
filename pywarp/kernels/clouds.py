"""Cloud density and lighting model (vc §2.3.3, §2.3.4, §4.3.2) -- Warp twins of ``cclouds/clouds.h``.

Every function is a pure scalar function of already-sampled texture and weather-map values, so the renderer's pixel
kernel calls them per raymarch sample. ``remap`` is vc-2.27 (``pywarp.kernels.interp.interp_remap``), linear and
unclamped; the phase function is ``phase_hg`` (vc-2.13).

Readings chosen where the thesis is ambiguous (spec §7; the C header says the same):

* vc-2.29: the threshold ``C`` is undefined -> the required argument ``coverage_threshold``; pass the coverage
  ``D_h`` itself for ``C := D_h`` (the reading the spec recommends and GPU Pro 7's form), ``1 - D_h`` for the other
  reading the renderer offers. (It used to default to ``D_h``; a default that depends on another argument cannot be
  declared element-wise, and the explicit argument is what the C function takes.) At ``C >= 1`` the remap range
  [C, 1] is empty (division by zero): the result is 0 (fully eroded; the clamped limit for B < 1). Option ``clamp``
  (default True) clamps negative densities (B < C) to 0.
* vc-2.30: option ``detail_direction``: ``"formula"`` (default, as printed, M = H (1 - h) + (1 - H) h) or ``"prose"``
  (M = (1 - H)(1 - h) + H h: classic Worley low, inverse high for an inverse-Worley texture). Option ``clamp``.
* vc-4.7: option ``clamp`` default **False**: the printed ``max(0, .)`` only matters when the remaps are unclamped
  (a product of two saturated remaps is never negative), so the formula as printed implies unclamped remaps; the
  peaks are then 2.1764 (cumulus, h = 0.48), 1.2190 (stratocumulus, 0.33), 1.1281 (stratus, 0.105). ``clamp=True``
  saturates each remap to [0, 1] (plateaus at 1; stratus peaks at 0.75 at h = 0.05).
* vc-A15: from the distance ``r = |p - c|`` to the Earth's centre; ``variant="corrected"`` gives
  h = (r - R_inner)/(R_outer - R_inner), ``"thesis"`` the printed d - 1 = -h.
* vc-A16: piecewise-linear blend of the three profiles over the cloud type (0 stratus, 0.5 stratocumulus, 1 cumulus).
* vc-A17: precipitation enters only the lighting (``a`` of vc-2.31), not the density.
* vc-A20 defaults (the thesis gives none): ``g = 0.2`` -- a mild forward lobe that gives the silver lining towards the
  sun while a single-scattering model without a multiple-scattering term keeps the far side visible (water droplets
  have g ~ 0.85; pass it to get it); ``sun_intensity = 1`` -- radiances are in units of the sun's irradiance, the
  renderer applies its exposure; ``ambient_top = 0.012`` ~ 0.15 / (4 pi): clear-sky diffuse irradiance is roughly
  15 % of the direct sun's, scattered isotropically (1 / (4 pi)); ``ambient_bottom = 0.006``: half of it, the base of
  a cloud faces the darker ground and is shadowed by the cloud above (darker bases, brighter tops as in Schneider &
  Vos 2015 and the thesis' fig. 4.11).
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.cbridge import c_constant
from ..core.registry import VARIANT, Arg, Option, declare
from .common import clamp01
from . import VARIANT_THESIS
from .interp import interp_remap
from .phase import phase_hg

#: ``ccl_detail_direction``: M as the formula vc-2.30 prints it, or as the prose describes it
DETAIL_FORMULA = c_constant("CCL_DETAIL_FORMULA", 0)
DETAIL_PROSE = c_constant("CCL_DETAIL_PROSE", 1)

DEFAULT_G = 0.2
DEFAULT_SUN_INTENSITY = 1.0
DEFAULT_AMBIENT_TOP = 0.012
DEFAULT_AMBIENT_BOTTOM = 0.006


# --- helpers (NaN propagates, like the C statics) ---------------------------------------------------------------------

@wp.func
def _nonneg(x: float) -> float:
    if x < 0.0:
        return 0.0
    return x


@wp.func
def _lerp_exact(a: float, b: float, s: float) -> float:
    """a (1 - s) + b s: exact at s = 0 and s = 1."""
    return a * (1.0 - s) + b * s


# --- twins (element-wise; the evaluation kernels are generated) -------------------------------------------------------

_REF_SV = "Schneider & Vos, The real-time volumetric cloudscapes of Horizon: Zero Dawn, SIGGRAPH 2015 course"
_REF_GPU7 = "Schneider, Real-time volumetric cloudscapes, GPU Pro 7, 2016"


def _unit(name, doc):
    return Arg(name, doc + ", in [0, 1]", lo=0.0, hi=1.0)


_CLAMP_DENSITY = Option("clamp", {True: 1, False: 0}, True,
                        "True (default): negative densities are clamped to 0 (not stated in the text); "
                        "False: as printed")
_DETAIL_DIRECTION = Option("detail_direction", {"formula": 0, "prose": 1}, "formula",
                           "'formula' (default): M = H (1 - h_rel) + (1 - H) h_rel as printed; 'prose': "
                           "M = (1 - H)(1 - h_rel) + H h_rel, classic Worley at the base for an inverse-Worley texture")
_CLAMP_GRADIENT_DOC = ("False (default): remaps unclamped as printed (the printed max(0, .) implies it; peaks 2.1764, "
                       "1.2190, 1.1281); True: each remap saturated to [0, 1] (stratus peaks at 0.75)")
_COVERAGE_THRESHOLD = Arg("coverage_threshold", "C of vc-2.29, undefined in the text: pass the coverage D_h for the "
                          "recommended reading C := D_h, 1 - D_h for the other; 1 erodes everything", lo=0.0, hi=1.0)
_G = Arg("g", f"HG asymmetry parameter; default {DEFAULT_G} (not given in the text, see the module docstring)",
         lo=-1.0, hi=1.0, lo_open=True, hi_open=True, default=DEFAULT_G)
_COS = Arg("cos_theta", "cosine of the angle between the view ray and the direction to the light (+1 = towards the "
           "sun, forward scattering)", lo=-1.0, hi=1.0)
_D = Arg("d", "optical thickness towards the light (vc-A19) >= 0", lo=0.0)
_A = Arg("a", "precipitation (extinction) coefficient of the Beer term >= 0", lo=0.0)


@declare("vc-2.28", c="ccl_clouds_base_shape",
         args=(_unit("C_R", "base texture red: Perlin-Worley"),
               _unit("C_G", "base texture green: Worley fBm, low freq."),
               _unit("C_B", "base texture blue: Worley fBm"),
               _unit("C_A", "base texture alpha: Worley fBm, high freq.")),
         outputs=("L_FBM", "B"),
         summary="Base cloud shape: L_FBM = 0.625 C_G + 0.25 C_B + 0.125 C_A, B = remap(C_R, L_FBM - 1, 1, 0, 1).",
         references=(_REF_GPU7,))
@wp.func
def clouds_base_shape(C_R: float, C_G: float, C_B: float, C_A: float) -> tuple[float, float]:
    """vc-2.28: returns (L_FBM, B), L_FBM = 0.625 C_G + 0.25 C_B + 0.125 C_A, B = remap(C_R, L_FBM - 1, 1, 0, 1)."""
    l_fbm = 0.625 * C_G + 0.25 * C_B + 0.125 * C_A
    return l_fbm, interp_remap(C_R, l_fbm - 1.0, 1.0, 0.0, 1.0)


@declare("vc-2.29", c="ccl_clouds_coverage",
         args=(Arg("B", "base shape of vc-2.28 >= 0", lo=0.0),
               Arg("D_v", "vertical density: height gradient of vc-4.7 >= 0", lo=0.0),
               _unit("D_h", "horizontal density: weather-map coverage (red)"), _COVERAGE_THRESHOLD),
         options=(_CLAMP_DENSITY,), outputs=("B_D",),
         summary="Vertical profile and coverage: B_D = remap(B D_v, C, 1, 0, 1) D_h with C = coverage_threshold "
                 "(pass D_h for the recommended C := D_h); 0 at C = 1; negatives clamped to 0 unless clamp=False.",
         references=(_REF_GPU7,))
@wp.func
def clouds_coverage(B: float, D_v: float, D_h: float, coverage_threshold: float, clamp: int) -> float:
    """vc-2.29: B_D = remap(B D_v, C, 1, 0, 1) D_h; 0 at C >= 1; clamp != 0 clamps negatives to 0."""
    if coverage_threshold >= 1.0:
        return 0.0
    b_d = interp_remap(B * D_v, coverage_threshold, 1.0, 0.0, 1.0) * D_h
    if clamp != 0:
        return _nonneg(b_d)
    return b_d


@declare("vc-2.30", c="ccl_clouds_detail_erosion",
         args=(Arg("B_D", "base shape with coverage, vc-2.29 (may be negative when not clamped)"),
               _unit("C_R", "detail texture red"), _unit("C_G", "detail texture green"),
               _unit("C_B", "detail texture blue"),
               _unit("h_rel", "relative height of the curl-displaced sample point")),
         options=(_DETAIL_DIRECTION, _CLAMP_DENSITY), outputs=("C",),
         summary="Detail erosion: H = 0.625 C_R + 0.25 C_G + 0.125 C_B, M = H (1 - h_rel) + (1 - H) h_rel, "
                 "C = remap(B_D, 0.2 M, 1, 0, 1).",
         references=(_REF_GPU7,))
@wp.func
def clouds_detail_erosion(B_D: float, C_R: float, C_G: float, C_B: float, h_rel: float, detail_direction: int,
                          clamp: int) -> float:
    """vc-2.30: H = 0.625 C_R + 0.25 C_G + 0.125 C_B, M = H (1 - h) + (1 - H) h, C = remap(B_D, 0.2 M, 1, 0, 1);
    detail_direction 1 replaces H by 1 - H; clamp != 0 clamps negatives to 0."""
    h_fbm = 0.625 * C_R + 0.25 * C_G + 0.125 * C_B
    if detail_direction == DETAIL_PROSE:
        h_fbm = 1.0 - h_fbm
    m = h_fbm * (1.0 - h_rel) + (1.0 - h_fbm) * h_rel
    c = interp_remap(B_D, 0.2 * m, 1.0, 0.0, 1.0)
    if clamp != 0:
        return _nonneg(c)
    return c


@declare("vc-2.31", c="ccl_clouds_energy", args=(_D, _A, _COS, _G), outputs=("E",),
         summary="Cloud lighting energy as printed: E = exp(-d a) HG(theta, g) (1 - exp(-2 d)) [sr^-1]; 0 at d = 0.",
         references=(_REF_SV,))
@wp.func
def clouds_energy(d: float, a: float, cos_theta: float, g: float) -> float:
    """vc-2.31: E = exp(-d a) HG(theta, g) (1 - exp(-2 d))."""
    return wp.exp(-d * a) * phase_hg(cos_theta, g) * (1.0 - wp.exp(-2.0 * d))


@declare("vc-A16", c="ccl_clouds_type_blend",
         args=(Arg("d_stratus", "stratus profile value >= 0", lo=0.0),
               Arg("d_stratocumulus", "stratocumulus profile value >= 0", lo=0.0),
               Arg("d_cumulus", "cumulus profile value >= 0", lo=0.0),
               _unit("cloud_type", "0 stratus, 0.5 stratocumulus, 1 cumulus")),
         outputs=("D_v",),
         summary="Cloud type -> vertical profile: piecewise-linear blend stratus (0) -> stratocumulus (0.5) -> "
                 "cumulus (1).")
@wp.func
def clouds_type_blend(d_stratus: float, d_stratocumulus: float, d_cumulus: float, cloud_type: float) -> float:
    """vc-A16: piecewise-linear blend, 0 stratus, 0.5 stratocumulus, 1 cumulus."""
    if cloud_type <= 0.5:
        return _lerp_exact(d_stratus, d_stratocumulus, 2.0 * cloud_type)
    return _lerp_exact(d_stratocumulus, d_cumulus, 2.0 * cloud_type - 1.0)


@wp.func
def _height_profile(h: float, lo0: float, lo1: float, hi0: float, hi1: float, clamp: int) -> float:
    up = interp_remap(h, lo0, lo1, 0.0, 1.0)
    down = interp_remap(h, hi0, hi1, 1.0, 0.0)
    if clamp != 0:
        up = clamp01(up)
        down = clamp01(down)
    return _nonneg(up * down)


@declare("vc-4.7", c="ccl_clouds_height_gradient",
         args=(_unit("h", "relative height in the cloud layer (vc-A15)"),
               _unit("cloud_type", "0 stratus, 0.5 stratocumulus, 1 cumulus, blended in between (vc-A16)")),
         options=(Option("clamp", {True: 1, False: 0}, False, _CLAMP_GRADIENT_DOC),), outputs=("D_v",),
         summary="Height (vertical density) gradient of the cloud types, blended by type (vc-A16).",
         references=(_REF_GPU7,))
@wp.func
def clouds_height_gradient(h: float, cloud_type: float, clamp: int) -> float:
    """vc-4.7 + vc-A16: the height gradient of the three cloud types, blended by type."""
    cu = _height_profile(h, 0.01, 0.30, 0.6, 0.95, clamp)
    sc = _height_profile(h, 0.01, 0.25, 0.3, 0.65, clamp)
    st = _height_profile(h, 0.01, 0.05, 0.0, 0.20, clamp)
    return clouds_type_blend(st, sc, cu, cloud_type)


@declare("vc-4.8", c="ccl_clouds_composite",
         args=(Arg("B", "background (sky) colour channel >= 0", lo=0.0),
               _unit("O_D", "cloud opacity along the view ray (1 - view transmittance)"),
               Arg("C_clouds", "accumulated cloud colour channel (premultiplied by opacity) >= 0", lo=0.0)),
         outputs=("C_f",), summary="Clouds over the sky, one colour channel: C_f = B (1 - O_D) + C_clouds.")
@wp.func
def clouds_composite(B: float, O_D: float, C_clouds: float) -> float:
    """vc-4.8: C_f = B (1 - O_D) + C_clouds."""
    return B * (1.0 - O_D) + C_clouds


def _check_radii(r_inner, r_outer, **_):
    bad = np.broadcast_to(r_inner >= r_outer, np.broadcast_shapes(np.shape(r_inner), np.shape(r_outer)))
    if np.any(bad):
        ri = np.broadcast_to(r_inner, bad.shape)[bad].flat[0].item()
        ro = np.broadcast_to(r_outer, bad.shape)[bad].flat[0].item()
        raise ValueError(f"r_outer must be > r_inner, got r_inner = {ri!r}, r_outer = {ro!r}")


def _radii_samples(rng, n):
    """Valid (r, r_inner, r_outer) for the contract tests: a layer [r_inner, r_outer] and r around it."""
    r_inner = rng.uniform(1.0, 100.0, n)
    r_outer = r_inner + rng.uniform(0.1, 20.0, n)
    return {"r": rng.uniform(0.0, 130.0, n), "r_inner": r_inner, "r_outer": r_outer}


@declare("vc-A15", c="ccl_clouds_relative_height",
         args=(Arg("r", "distance |p - c| of the sample from the Earth's centre (any length unit) >= 0", lo=0.0),
               Arg("r_inner", "radius of the inner bounding sphere > 0", lo=0.0, lo_open=True),
               # > 0 through r_outer > r_inner (the check); no bound of its own, whose edge would contradict it
               Arg("r_outer", "radius of the outer bounding sphere > r_inner")),
         options=(VARIANT,), outputs=("h",), check=_check_radii, samples=_radii_samples,
         summary="Relative height in the cloud layer. variant='corrected': (r - R_inner)/(R_outer - R_inner), 0 at "
                 "the inner sphere, 1 at the outer; variant='thesis': the printed 'subtract one', d - 1 = -h in "
                 "[-1, 0].")
@wp.func
def clouds_relative_height(r: float, r_inner: float, r_outer: float, variant: int) -> float:
    """vc-A15: (r - R_inner) / (R_outer - R_inner); variant 1 = the printed (R_outer - r)/(R_outer - R_inner) - 1."""
    thickness = r_outer - r_inner
    if variant == VARIANT_THESIS:
        return (r_outer - r) / thickness - 1.0
    return (r - r_inner) / thickness


@declare("vc-A17", c="ccl_clouds_density",
         args=(_unit("coverage", "weather-map coverage D_h (red)"),
               _unit("cloud_type", "weather-map cloud type (blue)"),
               _unit("h", "relative height of the sample (vc-A15)"),
               _unit("base_r", "base texture red"), _unit("base_g", "base texture green"),
               _unit("base_b", "base texture blue"), _unit("base_a", "base texture alpha"),
               _unit("detail_r", "detail texture red at the curl-displaced point"),
               _unit("detail_g", "detail texture green"), _unit("detail_b", "detail texture blue"),
               _unit("h_detail", "relative height of the curl-displaced point"), _COVERAGE_THRESHOLD),
         options=(Option("gradient_clamp", {True: 1, False: 0}, False, "clamp of clouds_height_gradient (vc-4.7); "
                         + _CLAMP_GRADIENT_DOC),
                  Option("density_clamp", {True: 1, False: 0}, True, "clamp of vc-2.29 and vc-2.30: "
                         + _CLAMP_DENSITY.doc),
                  _DETAIL_DIRECTION),
         outputs=("density",),
         summary="Cloud density at a raymarch sample from the sampled weather and texture values: height gradient "
                 "(4.7, A16) -> base shape (2.28) -> coverage (2.29, C = coverage_threshold; pass coverage for "
                 "C := D_h) -> detail erosion (2.30).",
         references=(_REF_GPU7,))
@wp.func
def clouds_density(coverage: float, cloud_type: float, h: float, base_r: float, base_g: float, base_b: float,
                   base_a: float, detail_r: float, detail_g: float, detail_b: float, h_detail: float,
                   coverage_threshold: float, gradient_clamp: int, density_clamp: int, detail_direction: int) -> float:
    """vc-A17: height gradient (4.7, A16) -> base shape (2.28) -> coverage (2.29) -> detail erosion (2.30)."""
    d_v = clouds_height_gradient(h, cloud_type, gradient_clamp)
    l_fbm, b = clouds_base_shape(base_r, base_g, base_b, base_a)
    b_d = clouds_coverage(b, d_v, coverage, coverage_threshold, density_clamp)
    return clouds_detail_erosion(b_d, detail_r, detail_g, detail_b, h_detail, detail_direction, density_clamp)


@declare("vc-A20", c="ccl_clouds_sample_light",
         args=(_D, _A, _COS, _unit("h", "relative height of the sample (ambient interpolation; clamped to [0, 1])"), _G,
               Arg("sun_intensity", f"sun irradiance in this channel >= 0; default {DEFAULT_SUN_INTENSITY}", lo=0.0,
                   default=DEFAULT_SUN_INTENSITY),
               Arg("ambient_bottom", f"ambient radiance at the layer base >= 0; default {DEFAULT_AMBIENT_BOTTOM}",
                   lo=0.0, default=DEFAULT_AMBIENT_BOTTOM),
               Arg("ambient_top", f"ambient radiance at the layer top >= 0; default {DEFAULT_AMBIENT_TOP}", lo=0.0,
                   default=DEFAULT_AMBIENT_TOP)),
         outputs=("L",),
         summary="Per-sample lighting, one colour channel: sun_intensity * clouds_energy(d, a, cos_theta, g) + "
                 "ambient interpolated between ambient_bottom (h = 0) and ambient_top (h = 1). Defaults (the text "
                 "gives none): g = 0.2, a mild forward lobe (silver lining without a black far side in a "
                 "single-scattering model); sun_intensity = 1, radiances in units of the sun's irradiance; "
                 "ambient_top = 0.012 ~ 0.15 / (4 pi), clear-sky diffuse irradiance ~15 % of the direct sun scattered "
                 "isotropically; ambient_bottom = 0.006, half: the base faces the ground and is shadowed by the "
                 "cloud above.",
         references=(_REF_SV,))
@wp.func
def clouds_sample_light(d: float, a: float, cos_theta: float, h: float, g: float, sun_intensity: float,
                        ambient_bottom: float, ambient_top: float) -> float:
    """vc-A20: sun_intensity E(d, a, cos_theta, g) + lerp(ambient_bottom, ambient_top, clamp(h, 0, 1))."""
    ambient = _lerp_exact(ambient_bottom, ambient_top, clamp01(h))
    return sun_intensity * clouds_energy(d, a, cos_theta, g) + ambient
