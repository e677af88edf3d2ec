"""Settings of the terrain scene (pt, chapters 6-9): every parameter of a frame, declared once with its parameter spec
(:mod:`pywarp.core.params`): unit, default, domain, doc and the reason for the default.

The text gives numbers only for the listings' constants (the shadow offsets 0.2 / 0.02, k = 4, h = 0.002, the fBm's
A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2, the sun power 80, the cloud octaves 4, kappa = 1, 3, 6, the 1/4/16 rays of
supersampling, the 1000-step cap of Obrazok 7.2); MAX_T, STEP_SIZE, PRECISION, MAX_STEPS, the colours, the fog
density, the water level and the heights are not given: each default below says why it was chosen. Fields that mirror
``ccl_terrain_params_default`` are pinned to the C values by ``tests/terrain/test_terrain_scene.py``. Each field that
reaches the pixel names its ``ccl_terrain_params`` field (``c=``): :meth:`TerrainSettings.c_params` builds and checks
the C struct from them (:mod:`pywarp.core.cbridge`), :meth:`TerrainSettings.warp_params` its Warp twin.

This module imports neither Warp nor the C library.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.cbridge import TERRAIN_PARAMS
from ..core.display import exposure_param, tonemap_param
from ..core.params import Settings, param

HEIGHTMAP_NAMES = ("fbm", "test")
MARCH_NAMES = ("dynamic", "fixed", "bisect")
SHADOW_NAMES = ("soft", "hard", "none")
STAGE_NAMES = ("final", "atmosphere", "materials", "heightmap")
VARIANT_NAMES = ("thesis", "corrected")
HEIGHTMAP_ENUM = {"test": "CCL_TERRAIN_TEST", "fbm": "CCL_TERRAIN_FBM"}
MARCH_ENUM = {"fixed": "CCL_TERRAIN_MARCH_FIXED", "dynamic": "CCL_TERRAIN_MARCH_DYNAMIC",
              "bisect": "CCL_TERRAIN_MARCH_BISECT"}
SHADOW_ENUM = {"none": "CCL_TERRAIN_SHADOWS_NONE", "hard": "CCL_TERRAIN_SHADOWS_HARD",
               "soft": "CCL_TERRAIN_SHADOWS_SOFT"}
STAGE_ENUM = {"heightmap": "CCL_TERRAIN_STAGE_HEIGHTMAP", "materials": "CCL_TERRAIN_STAGE_MATERIALS",
              "atmosphere": "CCL_TERRAIN_STAGE_ATMOSPHERE", "final": "CCL_TERRAIN_STAGE_FINAL"}
VARIANT_ENUM = {"corrected": "CCL_VARIANT_CORRECTED", "thesis": "CCL_VARIANT_THESIS"}
_C = "ccl_terrain_params_default"


def _rays_check(obj, name, v):
    m = math.isqrt(v)
    if m * m != v:
        raise ValueError(f"{name} must be a square number of rays (1, 4, 9, 16, ...; a regular m x m grid), got {v}")


def _octaves_min_check(obj, name, v):
    if v > obj.normal_octaves_max:
        raise ValueError(f"{name} must be in [1, normal_octaves_max ({obj.normal_octaves_max})], got {v}")


def _material_high_check(obj, name, v):
    if not v > obj.material_low:
        raise ValueError(f"{name} must be > material_low ({obj.material_low:g}), got {v!r}")


def _colour(default, doc, reason, group, c):
    return param(default, lo=0.0, hi=100.0, doc=doc, reason=reason, group=group, c=c)


@dataclass(frozen=True)
class TerrainSettings(Settings):
    """Every parameter of a terrain frame (see the module docstring). Immutable: change with ``dataclasses.replace``
    or :meth:`pywarp.terrain.technique.TerrainTechnique.update`; invalid values raise ValueError (TypeError for a
    wrong type) naming the field."""

    # --- image and camera -----------------------------------------------------------------------------------------------
    width: int = param(960, unit="px", kind="int", lo=1, hi=8192, invalidates="size", group="image",
                       doc="image width", reason="960 x 540: a quarter of Full HD, a few seconds on a laptop CPU")
    height: int = param(540, unit="px", kind="int", lo=1, hi=8192, invalidates="size", group="image",
                        doc="image height", reason="960 x 540: a quarter of Full HD")
    rays_per_pixel: int = param(1, kind="int", lo=1, hi=64, check=_rays_check, group="image",
                                doc="supersampling (7.1.6): rays per pixel on a regular m x m grid (1, 4, 16 in the "
                                    "text)",
                                reason="1: the final demo does not supersample (too slow, 7.1.6)")
    exposure_ev: float = exposure_param(
        -0.3, reason="-0.3 EV: the terrain's colours are display-encoded values clamped to 1 (the sun's disc); "
                     "decoded to linear light, the ACES curve at -0.3 EV keeps the default view's mean within 2 % "
                     "(R, G) of the clamped image's and the sun a bright disc without a channel at 255 (480x270: "
                     "3.7 % of the clamped image's pixels have one)")
    tonemap: str = tonemap_param()
    camera_x: float = param(-22.0, unit="units", lo=-1e5, hi=1e5, group="camera", doc="camera position x",
                            reason="-22: a ridge above a lake of the default terrain (seed 0), hills and water in "
                                   "view")
    camera_y: float = param(9.0, unit="units", lo=-1e4, hi=1e4, group="camera",
                            doc="camera height (absolute; the terrain spans about +-2 height_scale)",
                            reason="9: about 6 units above the ground at the default position, a hiker's view over "
                                   "the hills")
    camera_z: float = param(30.0, unit="units", lo=-1e5, hi=1e5, group="camera", doc="camera position z",
                            reason="30: see camera_x")
    camera_yaw_deg: float = param(0.0, unit="deg", group="camera", cli="--yaw",
                                  doc="camera heading, 0 = -z, positive towards +x",
                                  reason="0: looking along -z, towards the sun's side of the sky")
    camera_pitch_deg: float = param(-8.0, unit="deg", lo=-89.0, hi=89.0, group="camera", cli="--pitch",
                                    doc="camera pitch above the horizon (the pt camera is undefined looking "
                                        "straight up or down)",
                                    reason="-8: the horizon in the upper third, the hills in front")
    fov_y_deg: float = param(90.0, unit="deg", lo=1.0, hi=170.0, group="camera", cli="--fov",
                             doc="vertical field of view",
                             reason="90: the demo's camera (Kod 7.1-7.2: image plane at distance 1, half-height 1)")
    # --- sun --------------------------------------------------------------------------------------------------------------
    sun_elevation_deg: float = param(20.0, unit="deg", lo=0.5, hi=90.0, group="sun", cli="--sun-elevation",
                                     doc="sun elevation above the horizon",
                                     reason="20: a low afternoon sun with long shadows, the glow in view above the "
                                            "hills; above asin(1/k) = 14.5 deg so that the soft shadow (k = 4) leaves "
                                            "open flat ground lit (its clearance k d / t ~ k sin e)")
    sun_azimuth_deg: float = param(-30.0, unit="deg", group="sun", cli="--sun-azimuth",
                                   doc="sun azimuth, 0 = -z, positive towards +x",
                                   reason="-30: in view, left of centre, so the sun glow of Kod 7.10 shows")
    # --- heightmap ---------------------------------------------------------------------------------------------------
    heightmap: str = param("fbm", choices=HEIGHTMAP_NAMES, c="heightmap", c_enum=HEIGHTMAP_ENUM, group="heightmap",
                           doc="fbm: the demo's fBm landscape (Kod 7.9); test: 10 sin(0.1 x) sin(0.1 z) (Kod 7.4)",
                           reason="'fbm': the final demo")
    seed: int = param(0, kind="uint32", lo=0, hi=2 ** 32 - 1, c="seed", group="heightmap",
                      doc="Perlin seed of the fBm (terrain, clouds, waves)",
                      reason="0: Ken Perlin's reference permutation")
    march_octaves: int = param(4, kind="int", lo=1, hi=16, c="march_octaves", group="heightmap",
                               doc="fBm octaves of the marched surface and the shadows (few, 7.3)",
                               reason="4: hills and rocks (down to 1/8 of the largest features); more octaves cost "
                                      "every march step and add only what the normals already show (7.3)")
    height_scale: float = param(12.0, unit="units", lo=0.0, hi=1000.0, c="height_scale", group="heightmap",
                                doc="fBm amplitude: heights within +-2 height_scale",
                                reason="12: hills up to ~20 units over valleys ~50 units wide, slopes up to ~45 deg")
    horizontal_scale: float = param(24.0, unit="units", lo=0.015625, hi=1e4, c="horizontal_scale", group="heightmap",
                                    doc="units per fBm unit (the largest hills are 2 x this apart)",
                                    reason="24: with height_scale 12 the relief of rolling hills; a hiker's eye "
                                           "(~5 units) sees several ridges before the fog")
    # --- march ---------------------------------------------------------------------------------------------------------
    march: str = param("bisect", choices=MARCH_NAMES, c="march_method", c_enum=MARCH_ENUM, group="march",
                       doc="ray march: dynamic (Kod 7.5, the final demo's), fixed (Kod 7.4) or bisect (the refinement "
                           "of ch. 9)",
                       reason="'bisect': with step_scale 0.8 the refinement the text proposes takes 17 height "
                              "evaluations per pixel of the default view where Kod 7.5 at 0.5 takes 26, and finds the "
                              "same surface (SSIM 0.996, mean CIEDE2000 0.20 of the 640 x 360 image, shadow_min_step "
                              "1 included); 'dynamic' with step_scale 0.5 and shadow_min_step 0 is the final demo "
                              "(about 20x faster than fixed, Tabulka 7.1)")
    max_t: float = param(400.0, unit="units", lo=0.0, hi=1e4, lo_open=True, c="max_t", group="march",
                         doc="MAX_T: the longest view ray",
                         reason="400: about 8 hill spacings; the fog (full at 385) hides the cut-off, its purpose in "
                                "7.3.1")
    step_size: float = param(0.1, unit="units", lo=0.015625, hi=100.0, c="step_size", group="march",
                             doc="STEP_SIZE of the fixed march (Kod 7.4)",
                             reason="0.1: below a tenth of the smallest marched feature's height, so the naive march "
                                    "finds the same surface as the dynamic one (the error of a fixed step is up to "
                                    "one step)")
    precision: float = param(0.01, unit="units", lo=0.0, hi=10.0, lo_open=True, c="precision", group="march",
                             doc="PRECISION: hit when the vertical gap is smaller",
                             reason="0.01: a tenth of the fixed step and 1/1000 of a hill's height: invisible at "
                                    "every distance in view")
    max_steps: int = param(300, kind="int", lo=1, hi=100000, c="max_steps", group="march",
                           doc="MAX_STEPS of the dynamic march and the shadows",
                           reason="300: grazing rays over the default terrain hit within ~200 halved steps; the "
                                  "few that need more are far, under full fog")
    step_scale: float = param(0.8, lo=0.0, hi=1.0, lo_open=True, c="step_scale", group="march",
                              doc="factor on the dynamic step (1: Kod 7.5 as printed; 0.5: 'halve the step', 7.1.3)",
                              reason="0.8 with the bisect march: its bisection catches the small overshoots of the "
                                     "vertical gap (SSIM 0.996 against 0.5; 0.9: 0.980, 1: 0.950, holes in ridges); "
                                     "0.5: the text's remedy for the dynamic march")
    bisect_threshold: float = param(0.25, unit="units", lo=0.0, hi=100.0, lo_open=True, c="bisect_threshold",
                                    group="march",
                                    doc="bisect: step below which the march switches to threshold steps + "
                                        "bisection (ch. 9)",
                                    reason="0.25: 25 x PRECISION, where the dynamic march starts crawling; "
                                           "0.25 / 2^6 = 0.004 < PRECISION after the bisection")
    bisect_steps: int = param(6, kind="int", lo=0, hi=64, c="bisect_steps", group="march",
                              doc="bisect: halvings of the bracket",
                              reason="6: threshold / 2^6 = 0.004 units, below PRECISION (0.01)")
    slab: bool = param(True, c="slab", group="march",
                       doc="clip the view and shadow rays to the slab y <= bound + PRECISION that holds the terrain "
                           "(bound: height_scale 2 (1 - 0.5^march_octaves) for the fBm with |noise| <= 1, 10 for the "
                           "test map): rising rays above it stop (sky, lit), rays from above start at its top; off: "
                           "the printed loops, which march rising rays on to MAX_T",
                       reason="on: exact -- the same hits and shadows (bit for bit for a camera inside the slab; from "
                              "above, the march starts at the slab's top, the hit moves by less than PRECISION) for "
                              "~40 % fewer steps (the sky's rays stop after a few)")
    precision_per_unit: float = param(0.0, lo=0.0, hi=1.0, c="precision_per_unit", group="march",
                                      doc="dynamic march: hit when the vertical gap is below PRECISION + this x t "
                                          "(the pixel's footprint grows with t; not in the text)",
                                      reason="0: Kod 7.5's constant PRECISION (0.004, about half a pixel's "
                                             "footprint per unit of distance at 320 x 180, ends the crawl of grazing "
                                             "rays near the horizon, but moves the hits: SSIM 0.86 at 640 x 360)")
    # --- normals ------------------------------------------------------------------------------------------------------
    normal_h: float = param(0.002, unit="units", lo=0.0, hi=1.0, lo_open=True, c="normal_h", group="normals",
                            doc="central-difference step h (Kod 7.8)", reason="0.002: Kod 7.8")
    normal_octaves_max: int = param(9, kind="int", lo=1, hi=16, c="normal_octaves_max", group="normals",
                                    doc="fBm octaves of the normals near the camera (7.3: many)",
                                    reason="9: the finest octave (24/256 units ~ 0.1) is the size of a pixel at "
                                           "~lod_distance at 960 px")
    normal_octaves_min: int = param(4, kind="int", lo=1, hi=16, check=_octaves_min_check, c="normal_octaves_min",
                                    group="normals",
                                    doc="fBm octaves of the normals far away (at least the march's)",
                                    reason="4: the march's octaves, so a far normal still matches its surface")
    lod_distance: float = param(15.0, unit="units", lo=0.0, hi=1e4, lo_open=True, c="lod_distance", group="normals",
                                doc="distance up to which the normals use every octave; one octave less per "
                                    "doubling beyond (pt-alg-7.3-lod)",
                                reason="15: where a pixel at 960 x 540, fov 90 deg, is ~0.05 units, half the finest "
                                       "octave's feature: no aliasing of Obrazok 7.7")
    # --- shadows and light ---------------------------------------------------------------------------------------------
    shadows: str = param("soft", choices=SHADOW_NAMES, c="shadows", c_enum=SHADOW_ENUM, group="shadows",
                         doc="soft (Kod 7.7), hard (Kod 7.6) or none",
                         reason="'soft': the final demo")
    shadow_t0_hard: float = param(0.2, unit="units", lo=0.0, hi=100.0, c="shadow_t0_hard", group="shadows",
                                  doc="start offset of the hard shadow ray", reason="0.2: Kod 7.6")
    shadow_t0_soft: float = param(0.02, unit="units", lo=0.0, hi=100.0, lo_open=True, c="shadow_t0_soft",
                                  group="shadows",
                                  doc="start offset of the soft shadow ray", reason="0.02: Kod 7.7")
    shadow_k: float = param(4.0, lo=0.0, hi=1000.0, lo_open=True, c="shadow_k", group="shadows",
                            doc="softness factor k of Kod 7.7 (larger = harder)", reason="4: Kod 7.7")
    shadow_max_t: float = param(80.0, unit="units", lo=0.0, hi=1e4, lo_open=True, c="shadow_max_t", group="shadows",
                                doc="MAX_T of the shadow rays",
                                reason="80: a ray 14 deg up clears the highest hills (~+24) from the valley floor "
                                       "(~-24) within ~200 units only at grazing suns; 80 covers the shadows of the "
                                       "neighbouring hills, farther ones are under fog")
    shadow_bias: float = param(0.02, unit="units", lo=0.0, hi=10.0, c="shadow_bias", group="shadows",
                               doc="the shadow ray starts this far above the marched surface (not in the text)",
                               reason="0.02: 2 x PRECISION; the dynamic march stops up to PRECISION above or "
                                      "below the surface, and a shadow ray starting below it would shadow itself")
    shadow_min_step: float = param(1.0, unit="units", lo=0.0, hi=100.0, c="shadow_min_step", group="shadows",
                                   doc="smallest step of the shadow rays: t += max(d, this) (0: Kod 7.6/7.7's t += d "
                                       "as printed; not in the text): a ray grazing a slope no longer crawls",
                                   reason="1: the shadows cost ~1/4 less (640 x 360 default view) and the image "
                                          "changes by SSIM 0.9992, mean CIEDE2000 0.06 (2: 0.994); 0: the text's "
                                          "shadow march")
    light_ambient: float = param(0.35, lo=0.0, hi=100.0, c="light_ambient", group="light", doc="L_a of eq 7.1",
                                 reason="0.35: faces turned from the sun stay readable (the ambient term's purpose "
                                        "in 7.2)")
    light_diffuse: float = param(1.0, lo=0.0, hi=100.0, c="light_diffuse", group="light", doc="L_d of eq 7.1",
                                 reason="1: a lit face facing the sun shows its material colour plus ambient")
    # --- materials -----------------------------------------------------------------------------------------------------
    stage: str = param("final", choices=STAGE_NAMES, c="stage", c_enum=STAGE_ENUM, group="materials",
                       doc="build-up stage of Obrazok 7.10: heightmap (a), materials (b), atmosphere (c: grass, "
                           "clouds, fog), final (d: water)",
                       reason="'final': the finished demo")
    colour_rock: tuple = _colour((0.42, 0.38, 0.35), "rock colour (stage a; the top of the height gradient)",
                                 "a warm grey of weathered rock", "materials", c="colour_rock")
    colour_low: tuple = _colour((0.62, 0.55, 0.42), "colour of the low ground (sand, dirt)",
                                "the pale brown of dry soil and beach sand", "materials", c="colour_low")
    colour_grass: tuple = _colour((0.24, 0.40, 0.13), "grass colour", "a summer meadow green", "materials",
                                  c="colour_grass")
    material_low: float = param(-6.0, unit="units", lo=-1e4, hi=1e4, c="material_low", group="materials",
                                doc="height where the gradient leaves colour_low",
                                reason="-6: just above the water level (-5 minus a beach)")
    material_high: float = param(10.0, unit="units", lo=-1e4, hi=1e4, check=_material_high_check, c="material_high",
                                 group="materials",
                                 doc="height where the gradient reaches colour_rock",
                                 reason="10: the upper hills are rock")
    grass_min_normal_y: float = param(0.85, lo=0.0, hi=1.0, c="grass_min_normal_y", group="materials",
                                      doc="grass where the normal's y exceeds this (7.10 c)",
                                      reason="0.85: slopes under ~32 deg carry grass, steeper ones stay rock")
    grass_band: float = param(0.08, lo=0.0, hi=1.0, lo_open=True, c="grass_band", group="materials",
                              doc="width in n.y of the rock-grass transition",
                              reason="0.08: a soft edge, no aliasing at the grass line")
    # --- atmosphere ----------------------------------------------------------------------------------------------------
    fog: str = param("thesis", choices=VARIANT_NAMES, c="fog_variant", c_enum=VARIANT_ENUM, group="atmosphere",
                     doc="fog of eq 7.3: thesis min(e^(rho d) - 1, 1) as printed, or corrected 1 - e^(-rho d)",
                     reason="'thesis': the printed form reaches full fog at ln 2 / rho, so the terrain fades "
                            "completely into the sky before MAX_T -- what 7.3.1 wants it for")
    fog_density: float = param(0.0018, unit="1/units", lo=0.0, hi=100.0, lo_open=True, c="fog_density",
                               group="atmosphere",
                               doc="fog density rho",
                               reason="0.0018: full fog (printed form) at ln 2 / 0.0018 = 385 units, just inside "
                                      "MAX_T = 400")
    sky_colour: tuple = _colour((0.45, 0.62, 0.85), "skyColor of Kod 7.10", "a clear-day blue", "atmosphere",
                                c="sky_colour")
    sun_colour: tuple = _colour((1.0, 0.8, 0.55), "sunColor of Kod 7.10 (added to the sky, not clamped)",
                                "a warm low-sun glow", "atmosphere", c="sun_colour")
    sun_power: float = param(80.0, lo=0.0, hi=1e4, lo_open=True, c="sun_power", group="atmosphere",
                             doc="exponent of the sun glow (Kod 7.10)", reason="80: Kod 7.10 (half glow at 7.53 deg)")
    clouds: str = param("corrected", choices=VARIANT_NAMES, c="cloud_variant", c_enum=VARIANT_ENUM, group="atmosphere",
                        doc="clouds of Kod 7.11: corrected (none below the horizon) or thesis (as printed)",
                        reason="'corrected': the printed form puts clouds below the horizon (seen in the water's "
                               "reflections too)")
    cloud_height: float = param(250.0, unit="units", lo=-1e4, hi=1e4, c="cloud_height", group="atmosphere",
                                doc="cloudHeight: y of the cloud plane",
                                reason="250: ten times the highest hills, a cloud deck that stretches to the horizon")
    cloud_scale: float = param(150.0, unit="units", lo=0.015625, hi=1e6, c="cloud_scale", group="atmosphere",
                               doc="units per fBm unit of the cloud noise (Kod 7.11 has no scale: 1)",
                               reason="150: clouds ~300 units across, a few over the sky at cloud_height 250")
    wind_x: float = param(6.0, unit="units/s", lo=-1000.0, hi=1000.0, group="atmosphere",
                          doc="windSpeed x (Kod 7.11)", reason="6: a visible drift over a few seconds")
    wind_z: float = param(3.0, unit="units/s", lo=-1000.0, hi=1000.0, group="atmosphere",
                          doc="windSpeed z (Kod 7.11)", reason="3: across the view")
    time_s: float = param(0.0, unit="s", lo=0.0, hi=1e6, c="time", group="atmosphere", cli="--time",
                          doc="time: the wind moves the clouds, the waves move", reason="0: the start")
    cloud_colour: tuple = _colour((1.0, 1.0, 1.0), "cloudColor of Kod 7.11", "white fair-weather clouds",
                                  "atmosphere", c="cloud_colour")
    # --- water ----------------------------------------------------------------------------------------------------------
    water_level: float = param(-5.0, unit="units", lo=-1e4, hi=1e4, c="water_level", group="water",
                               doc="y of the water plane (7.3.4)",
                               reason="-5: lakes in the lower quarter of the fBm's range, some valleys flooded")
    water_kappa: float = param(3.0, lo=0.0, hi=100.0, lo_open=True, c="water_kappa", group="water",
                               doc="kappa of eq 7.4 (1, 3, 6 in Obrazok 7.9)",
                               reason="3: the middle value of Obrazok 7.9: the bottom shows near the shore, the sky "
                                      "farther out")
    wave_scale: float = param(2.0, unit="units", lo=0.015625, hi=1e4, c="wave_scale", group="water",
                              doc="size of the waves (units per noise unit)",
                              reason="2: ripples a fraction of a hiker's height")
    wave_strength: float = param(0.08, lo=0.0, hi=10.0, c="wave_strength", group="water",
                                 doc="slope amplitude of the wave normals",
                                 reason="0.08: a calm lake, reflections rippled but recognisable")
    water_tint: tuple = _colour((0.55, 0.75, 0.8), "factor on the underwater colour ((1, 1, 1): the text's plain "
                                                   "blend)", "a blue-green tint so shallow water reads as water",
                                "water", c="water_tint")
    # --- viewer preview -------------------------------------------------------------------------------------------------
    quality: str = param("full", choices=("full", "preview"), group="preview",
                         doc="full: the settings as they are; preview: the viewer's frames while the camera moves -- "
                             "the reductions of PREVIEW (pywarp.terrain.settings) rendered at 1/preview_scale of the "
                             "width and height and enlarged (nearest pixel)",
                         reason="'full': pywarp render; the viewer switches to 'preview' while moving and back to "
                                "'full' (refined frame) when the camera stops")
    preview_scale: int = param(2, kind="int", lo=1, hi=16, group="preview",
                               doc="resolution divisor of the preview (quality='preview'), on top of the viewer's own "
                                   "adaptive divisor",
                               reason="2: 640 x 360 previews at 320 x 180 (1/4 of the pixels); the viewer sets 1 "
                                      "and chooses the size itself (its adaptive divisor or the temporal "
                                      "reconstruction's)")
    # --- runtime -------------------------------------------------------------------------------------------------------
    device: str = param("cpu", invalidates="device", group="runtime",
                        doc="Warp device: cpu, or cuda:N where present", reason="cpu: nothing requires a GPU")
    threads: int | None = param(None, kind="int", lo=1, hi=4096, optional=True, invalidates="device",
                                group="runtime", default_text="one per core", doc="worker threads of the tile launcher",
                                reason="None: one per core (PYWARP_THREADS overrides)")

    # --- derived ----------------------------------------------------------------------------------------------------------
    def sun(self) -> tuple:
        """Unit vector towards the sun (azimuth 0 = -z, positive towards +x)."""
        e, a = math.radians(self.sun_elevation_deg), math.radians(self.sun_azimuth_deg)
        return (math.cos(e) * math.sin(a), math.sin(e), -math.cos(e) * math.cos(a))

    def c_values(self) -> dict:
        """The ``ccl_terrain_params`` values of these settings: the C defaults, the fields the specs name, and the
        sun direction, the wind (x, z) and the supersampling grid's rays per axis."""
        from ..core.cbridge import settings_values

        return {**TERRAIN_PARAMS.defaults(), **settings_values(self), "sun": self.sun(),
                "wind": (self.wind_x, self.wind_z), "samples_per_axis": math.isqrt(self.rays_per_pixel)}

    def c_params(self):
        """The ``ccl_terrain_params`` (cffi) of these settings, checked by ``ccl_terrain_params_check`` (which fills
        the Perlin table); ValueError names the first bad field."""
        return TERRAIN_PARAMS.checked(self.c_values(), settings=self)

    def warp_params(self):
        """The Warp ``TerrainParams`` of :meth:`c_params` (the same float32 values)."""
        return TERRAIN_PARAMS.warp_struct(self.c_params())


#: The viewer's preview (quality='preview'): what it reduces against the final scene (same camera, same terrain, the
#: same look at a reduced size): the march at 0.9 of the step, at most 120 steps. Measured on the viewer benchmark's
#: eight poses against the full 640 x 360 render (SSIM of the enlarged frame): the final look at 107 x 60 gives 0.80
#: (160 x 90: 0.86) for ~1.5x the CPU of the former reductions (3 march octaves, 6 normal octaves, no shadows, a
#: shorter and coarser march, denser fog: 0.65 at any size -- another surface, no shadows); without the shadows 0.72,
#: with the normal octaves' distance rule scaled to the preview's pixel 0.73 (the fine normals' grass pattern is
#: what the full render shows); these two reductions change nothing visible (0.802 either way) for ~5 % less.
PREVIEW = dict(step_scale=0.9, max_steps=120)

#: Settings of the test heightmap of Kod 7.4 / 7.5 (Obrazok 7.1-7.2, Tabulka 7.1): the egg-crate terrain lit as in
#: 7.2, no shadows, no atmosphere, the printed loops (no slab: Tabulka 7.1 and Obrazok 7.2 count their steps); the
#: camera 15 units above the mean level looking down along the diagonal.
TEST_HEIGHTMAP = dict(heightmap="test", march="dynamic", stage="heightmap", shadows="none", slab=False, max_t=200.0,
                      step_size=0.1, max_steps=1000, step_scale=1.0, camera_x=0.0, camera_y=15.0, camera_z=0.0,
                      camera_yaw_deg=45.0, camera_pitch_deg=-20.0, sun_elevation_deg=40.0, sun_azimuth_deg=120.0)
