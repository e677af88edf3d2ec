"""Settings of the cloudscape scene (vc), each field declared once with its parameter spec (:mod:`pywarp.core.params`):
the noise-texture settings of vc-A13 (base shape, detail shape, curl noise, weather map) and
:class:`CloudscapeSettings`, every parameter of a render.

This module imports neither Warp nor the C library (the command line builds its options from it without starting
either). The constants below mirror the C headers; ``tests/clouds/test_settings.py`` pins them, and every default that
mirrors a C ``*_default()`` function, to the C values.

The weather map is declared once: :class:`WeatherMapSettings`. :class:`CloudscapeSettings` takes its ``coverage``,
``precipitation``, ``cloud_type``, ``cloud_type_variation``, the texture sizes and the seed from the texture settings'
specs (same domain, unit, doc and default) and builds the texture settings with :meth:`CloudscapeSettings.textures`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.cbridge import CStruct
from ..core.display import exposure_param, tonemap_param
from ..core.params import Settings, inherit, param

# cclouds/texgen.h limits (pinned to the C macros and pywarp.kernels.texgen by the tests)
MIN_SIZE = 4  # CCL_TEXGEN_MIN_SIZE
MAX_SIZE_3D = 512  # CCL_TEXGEN_MAX_SIZE_3D
MAX_SIZE_2D = 8192  # CCL_TEXGEN_MAX_SIZE_2D
MAX_OCTAVES = 8  # CCL_TEXGEN_MAX_OCTAVES
MAX_LATTICE = 4096  # CCL_TEXGEN_MAX_LATTICE
#: Perlin-Worley combinations of vc-A8, in the order of ccl_perlin_worley_mode (pywarp.kernels.noise.COMBINATIONS)
COMBINATION_NAMES = ("thesis", "gpu_pro_7", "hillaire", "product", "average")
#: cloud layer of vc-A14 (pywarp.kernels.raymarch, ccl_raymarch_cloud_layer_default)
EARTH_RADIUS_KM = 6371.0
LAYER_BASE_KM = 1.5
LAYER_TOP_KM = 4.0

#: Angles (azimuths, headings, wind direction) are taken in [-360, 360] degrees: every direction has a value there,
#: and larger magnitudes only lose float32 precision (at 1e300 the sine is NaN and the image black).
_ANGLE = dict(lo=-360.0, hi=360.0)
_ANGLE_DOC = "; in [-360, 360] (every direction has a value there; larger angles only lose precision)"
#: |time_s| <= 3 hours (see the time_s doc): at the highest wind speed (1000 km/h) the wind offsets then stay below
#: 4,500 km, and every texture coordinate below ccl_cloudscape_check's 2^23 texels at any texture size and the
#: default scales.
MAX_TIME_S = 10800.0
#: |camera x|, |camera z| <= 1000 km: the altitude is measured above the origin's ground, and 1000 km away the Earth
#: sphere (vc-A14) lies 78 km below that plane, so the "altitude" would no longer describe where the camera is;
#: float32 positions still resolve 6 cm there.
MAX_CAMERA_KM = 1000.0
_CAMERA_DOC = "; within 1000 km of the origin (the altitude is measured above the origin's ground)"

SKIES = ("preetham", "gradient")
JITTER_NAMES = ("tilt", "offset", "none")  # ccl_jitter_mode order
COVERAGE_THRESHOLD_NAMES = ("coverage", "one_minus_coverage")  # ccl_coverage_threshold order
LIGHTING_NAMES = ("thesis", "sky")  # ccl_lighting order
JITTER_ENUM = {"tilt": "CCL_JITTER_TILT", "offset": "CCL_JITTER_OFFSET", "none": "CCL_JITTER_NONE"}
COVERAGE_THRESHOLD_ENUM = {"coverage": "CCL_COVERAGE_SAME", "one_minus_coverage": "CCL_COVERAGE_ONE_MINUS"}
LIGHTING_ENUM = {"thesis": "CCL_LIGHTING_THESIS", "sky": "CCL_LIGHTING_SKY"}
REPROJECTION_DEPTHS = ("clouds", "inner_sphere")  # pywarp.kernels.reproj: DEPTH_ITERATIONS (2) / 0
BASE_PRECISIONS = ("half", "single")  # RenderTextures: how the renderer stores the base-shape texture
REPROJECTION_FILTERS = ("catmull_rom", "bilinear")  # pywarp.kernels.reproj.FILTERS (ccl_reproj_filter)
MAX_MS_OCTAVES = 8  # CCL_CLOUDSCAPE_MAX_MS_OCTAVES
PHASE_NAMES = ("thesis", "mie")  # ccl_cloudscape_phase order
PHASE_ENUM = {"thesis": "CCL_CLOUDSCAPE_PHASE_THESIS", "mie": "CCL_CLOUDSCAPE_PHASE_MIE"}
UNITS = ("display", "physical")  # the Preetham sky kind: CCL_SKY_PREETHAM / CCL_SKY_PREETHAM_RADIANCE
MARCH_NAMES = ("fast", "textbook")  # ccl_cloudscape_march_kind order
MARCH_ENUM = {"fast": "CCL_CLOUDSCAPE_MARCH_FAST", "textbook": "CCL_CLOUDSCAPE_MARCH_TEXTBOOK"}


#: The thesis's lighting (lighting='thesis'): one octave, one HG lobe and every later lighting term at its neutral
#: value, whatever the defaults (these are sky lighting's terms; the defaults turn them on) -- the one place that
#: sets them: :meth:`CloudscapeSettings.c_values`, before ``advanced`` (which may still set any of them, e.g. the
#: silver lobe of figure 2.17). The C leaves them to its caller (``ccl_cloudscape_light`` copies the thesis's
#: parameters unchanged); tests/clouds/test_default_lighting.py checks that none of the terms reaches a pixel.
THESIS_LIGHTING = dict(ms_octaves=1, silver_weight=0.0, ms_depth=0.0, ms_view=0.0, ms_slab=0.0, ambient_aniso=0.0,
                       ambient_ground_weight=0.0, mie_delta=0.0)


def _units_check(obj, name, v):
    """Physical units need the Preetham sky (the gradient sky has no units) and the sky lighting (the thesis's
    lighting has constant, display-linear lights)."""
    if v == "physical" and (obj.sky != "preetham" or obj.lighting != "sky"):
        raise ValueError(f"units='physical' needs sky='preetham' and lighting='sky', got sky={obj.sky!r}, "
                         f"lighting={obj.lighting!r}")


# --- checks shared by the texture settings ---------------------------------------------------------------------------

def _lattice(octaves_field: str | None, what: str = "octaves", layers: int = 4):
    """Lattice frequency of the lowest octave/layer: the highest, v * 2^(octaves - 1), must stay <= MAX_LATTICE."""
    def check(obj, name, v):
        octaves = getattr(obj, octaves_field) if octaves_field else layers
        if v * 2 ** (octaves - 1) > MAX_LATTICE:
            raise ValueError(f"{name} * 2^({what} - 1) must be <= {MAX_LATTICE}, got {v} * 2^{octaves - 1} = "
                             f"{v * 2 ** (octaves - 1)}")
    return check


def _weights(value, name):
    try:
        w = tuple(value)
    except TypeError:
        raise TypeError(f"{name} must be a sequence of 3 numbers, got {value!r}") from None
    if len(w) != 3:
        raise ValueError(f"{name} must hold 3 weights (lowest-frequency first), got {len(w)}")
    for v in w:
        if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, float, np.integer, np.floating)):
            raise TypeError(f"{name} must hold numbers, got {v!r}")
    w = tuple(float(v) for v in w)
    if not all(math.isfinite(v) and v >= 0.0 for v in w) or not w[0] > 0.0:
        raise ValueError(f"{name} must be finite and >= 0 with {name}[0] > 0 (every channel's window needs a "
                         f"positive weight sum), got {w}")
    return w


def _size(default: int, hi: int, reason: str, what: str = "texture"):
    return param(default, unit="texels", kind="int", lo=MIN_SIZE, hi=hi, pow2=True, invalidates="textures",
                 doc=f"edge of the {what}, a power of two", reason=reason)


def _seed(reason: str, doc: str = "seed of the noise (uint32); the same seed gives the same texture"):
    return param(0, kind="uint32", lo=0, hi=2 ** 32 - 1, invalidates="textures", doc=doc, reason=reason)


def _octaves(default: int, doc: str, reason: str):
    return param(default, kind="int", lo=1, hi=MAX_OCTAVES, invalidates="textures", doc=doc, reason=reason)


_WEIGHTS_REASON = ("(0.625, 0.25, 0.125): the only fBm weights the thesis prints (eq 2.28, 2.30), also "
                   "Hillaire's generator weights")
_GAMMA = dict(lo=0.0, lo_open=True, invalidates="textures", doc="gamma of vc-4.6, C^(1/gamma)",
              reason="1, the identity: the thesis gives no value")
_COMBINATION = dict(choices=COMBINATION_NAMES, invalidates="textures")


# --- texture settings (vc-A13) -----------------------------------------------------------------------------------------

@dataclass(frozen=True)
class BaseShapeSettings(Settings):
    """Settings of the base-shape texture (vc-A9, vc-A13 ``BaseShapeSettings``). The thesis names the parameters
    (Perlin octaves and frequency, Worley grid size, the weights of the Worley fBm, the Perlin-Worley combination,
    gamma) but gives no values; each default says where it comes from. Mirrors ``ccl_base_shape_settings``; fields are
    checked in the order of its C check."""

    INVALIDATES = Settings.INVALIDATES + ("textures",)  # the texture is regenerated

    size: int = _size(128, MAX_SIZE_3D, "128: the 128^3 of vc-A9")
    seed: int = _seed("0: the Perlin part then uses Ken Perlin's reference permutation")
    perlin_octaves: int = _octaves(3, "octaves of the Perlin fBm",
                                   "3: Hillaire's TileableVolumeNoise (the Electronic Arts code the thesis adopted)")
    perlin_frequency: int = param(8, unit="cells", kind="int", lo=1, hi=MAX_LATTICE, invalidates="textures",
                                  check=_lattice("perlin_octaves"),
                                  doc="Perlin lattice cells per texture (octave 0; also the period)",
                                  reason="8: Hillaire's value; the top octave (32 cells) keeps 4 texels per cell "
                                         "at 128^3")
    worley_cells: int = param(4, unit="cells", kind="int", lo=1, hi=MAX_LATTICE, invalidates="textures",
                              check=_lattice(None, "layers"),
                              doc="'Worley grid size': cells per texture of the lowest of the four inverse-Worley "
                                  "layers (cells x 1, 2, 4, 8)",
                              reason="4: Hillaire's cell count; the finest layer (32 cells) keeps 4 texels per cell "
                                     "at 128^3")
    worley_weights: tuple = param((0.625, 0.25, 0.125), convert=_weights, invalidates="textures",
                                  doc="weights of the Worley fBm window, lowest frequency first",
                                  reason=_WEIGHTS_REASON)
    combination: str = param("thesis", **_COMBINATION, doc="Perlin-Worley combination of the R channel (vc-A8)",
                             reason="'thesis': remap(P, 0, 1, W, 1)^2, the combination the thesis chose (4.3.1)")
    gamma: float = param(1.0, **_GAMMA)

    @property
    def shape(self) -> tuple:
        return (self.size, self.size, self.size, 4)


@dataclass(frozen=True)
class DetailShapeSettings(Settings):
    """Settings of the detail (erosion) texture (vc-A10, vc-A13 ``DetailShapeSettings``: fBm weights, base frequency,
    gamma; values not given in the thesis). Mirrors ``ccl_detail_shape_settings``."""

    INVALIDATES = Settings.INVALIDATES + ("textures",)  # the texture is regenerated

    size: int = _size(32, MAX_SIZE_3D, "32: the 32^3 of vc-A10")
    seed: int = _seed("0", "seed of the Worley feature points (layer j uses seed + j)")
    worley_cells: int = param(2, unit="cells", kind="int", lo=1, hi=MAX_LATTICE, invalidates="textures",
                              check=_lattice(None, "layers"),
                              doc="base frequency: cells per texture of the lowest layer (layers cells x 1, 2, 4, 8)",
                              reason="2: Hillaire's detail texture (layers 2, 4, 8, 16; the finest keeps 2 texels "
                                     "per cell at 32^3)")
    worley_weights: tuple = param((0.625, 0.25, 0.125), convert=_weights, invalidates="textures",
                                  doc="weights of the fBm layers, lowest first", reason=_WEIGHTS_REASON)
    gamma: float = param(1.0, **_GAMMA)

    @property
    def shape(self) -> tuple:
        return (self.size, self.size, self.size, 3)


@dataclass(frozen=True)
class CurlNoiseSettings(Settings):
    """Settings of the generated 2-D curl-noise texture (vc-A11; the thesis ships a file and states only that it holds
    curl noise of Perlin noise). Mirrors ``ccl_curl_noise_settings``."""

    INVALIDATES = Settings.INVALIDATES + ("textures",)  # the texture is regenerated

    size: int = _size(128, MAX_SIZE_2D, "128: not given; 128^2 x 2 floats samples the default 4 cells with 32 texels "
                                        "per cell, far finer than the swirls")
    seed: int = _seed("0: Perlin's reference permutation", "seed of the Perlin permutation")
    frequency: int = param(4, unit="cells", kind="int", lo=1, hi=MAX_LATTICE, invalidates="textures",
                           doc="Perlin lattice cells per texture (= the period)",
                           reason="4: a few swirls per tile, like the usual curl textures")
    fd_step: float = param(1.0 / 256.0, unit="lattice units", lo=0.0, hi=0.25, lo_open=True, invalidates="textures",
                           doc="central-difference step",
                           reason="1/256: the noise module's default (CCL_NOISE_FD_STEP_INV), a power of two so that "
                                  "p +- h is exact")

    @property
    def shape(self) -> tuple:
        return (self.size, self.size, 2)


_UNIT = dict(lo=0.0, hi=1.0, invalidates="textures", group="weather")


@dataclass(frozen=True)
class WeatherMapSettings(Settings):
    """Settings of the procedural weather map (vc-A12; the thesis ships a file). R = coverage, G = precipitation,
    B = cloud type, A = 0 (free). See ``cclouds/texgen.h`` for the formulas. The one declaration of the weather-map
    parameters: :class:`CloudscapeSettings` takes its weather fields from here. Fields are checked in the order of
    ``ccl_texgen_weather_map_settings_check``."""

    INVALIDATES = Settings.INVALIDATES + ("textures",)  # the texture is regenerated

    _validation_order = ("size", "seed", "perlin_octaves", "perlin_frequency", "perlin_contrast", "worley_octaves",
                         "worley_cells")

    size: int = _size(512, MAX_SIZE_2D, "512: not given; 4 MiB of float32 RGBA, finer than any cloud", "weather map")
    seed: int = _seed("0: Perlin's reference permutation for the coverage noise",
                      "seed: Perlin tables of seed (coverage), seed + 1 (precipitation), seed + 2 (type); Worley seed")
    perlin_frequency: int = param(4, unit="cells", kind="int", lo=1, hi=MAX_LATTICE, invalidates="textures",
                                  check=_lattice("perlin_octaves"), doc="Perlin lattice cells per map",
                                  reason="4: a few cloud systems per tile")
    perlin_octaves: int = _octaves(4, "Perlin fBm octaves", "4: ragged cloud-field edges down to 1/32 of the map")
    perlin_contrast: float = param(2.0, lo=0.0, lo_open=True, invalidates="textures",
                                   doc="gain of the Perlin fBm before clamping to [0, 1] (P = clamp(0.5 + contrast "
                                       "fbm))",
                                   reason="2: the fBm has a standard deviation of ~0.15 and |fbm| < 0.45, so 2 "
                                          "spreads it over ~[0.1, 0.9]; the covered fraction (R > 0) of the default "
                                          "map is then 0.24 / 0.61 / 0.91 at coverage 0.25 / 0.5 / 0.75")
    worley_octaves: int = _octaves(3, "Worley fBm octaves", "3: cells down to 1/16 of the map give clustered cumulus")
    worley_cells: int = param(4, unit="cells", kind="int", lo=1, hi=MAX_LATTICE, invalidates="textures",
                              check=_lattice("worley_octaves"), doc="Worley cells per map (octave 0)",
                              reason="4: the same scale as the Perlin blobs")
    combination: str = param("thesis", **_COMBINATION, doc="Perlin-Worley combination of the coverage noise (vc-A8)",
                             reason="'thesis', the thesis' cloud noise")
    coverage: float = param(0.5, **_UNIT, doc="weather-map coverage: 0 clear sky, 1 the raw noise everywhere",
                            reason="0.5: half of the noise range above the threshold, about 60 % of the sky covered")
    precipitation: float = param(0.2, **_UNIT, doc="weather-map precipitation (darker clouds through vc-2.31's a)",
                                 reason="0.2: mostly dry clouds, the fair-weather cumulus of the thesis' scenes")
    cloud_type: float = param(0.75, **_UNIT, doc="mean cloud type: 0 stratus, 0.5 stratocumulus, 1 cumulus",
                              reason="0.75: the low clouds the layer models (2.3.1), between stratocumulus and "
                                     "cumulus")
    cloud_type_variation: float = param(0.25, **_UNIT, doc="spread of the cloud type around its mean",
                                        reason="0.25: types from 0.5 to 1")

    @property
    def shape(self) -> tuple:
        return (self.size, self.size, 4)


TEXTURE_SETTINGS = {"base_shape": BaseShapeSettings, "detail_shape": DetailShapeSettings,
                    "curl_noise": CurlNoiseSettings, "weather_map": WeatherMapSettings}


# --- the render ------------------------------------------------------------------------------------------------------

def _layer_top_check(obj, name, v):
    if not v > obj.layer_base_km:
        raise ValueError(f"{name} must be > layer_base_km ({obj.layer_base_km:g} km), got {v!r}")


def _samples_max_check(obj, name, v):
    if v < obj.samples_min:
        raise ValueError(f"{name} must be in [samples_min ({obj.samples_min}), 4096], got {v!r}")


def _albedo_check(obj, name, v):
    if not all(0.0 <= x <= 1.0 for x in v):
        raise ValueError(f"{name} must hold 3 numbers in [0, 1], got {v!r}")


#: Largest sky_exposure of the thesis variant (CCL_CLOUDSCAPE_MAX_THESIS_EXPOSURE, reasons in cclouds/cloudscape.h):
#: the printed tone map 1 - exp(+k C) reached -inf at k = 5 and the composite made NaN pixels of it.
MAX_THESIS_EXPOSURE = 0.25


def _sky_exposure_check(obj, name, v):
    if obj.sky_variant == "thesis" and not v <= MAX_THESIS_EXPOSURE:
        raise ValueError(f"{name} must be in (0, {MAX_THESIS_EXPOSURE}] with sky_variant 'thesis' (its tone map "
                         f"1 - exp(+k C) overflows; ccl_cloudscape_check), got {v!r}")


def _advanced_check(obj, name, v):
    if v:
        obj.c_params()  # the C check of ccl_cloudscape_params, at the texture sizes


#: ``ccl_cloudscape_params`` (:mod:`pywarp.core.cbridge`). ``domains``: the valid values of the fields no setting
#: carries that ccl_cloudscape_check bounds by a plain range, as the check states them (for the error of an
#: ``advanced`` override); the other fields are bounded by the texture coordinates they produce.
CLOUDSCAPE_PARAMS = CStruct(
    "ccl_cloudscape_params", "ccl_cloudscape_check", "pywarp.kernels.cloudscape:CloudscapeParams",
    note=": texture coordinates must stay below 2^23 texels at the texture sizes",
    domains={
        "sigma": "> 0 and finite", "sigma_light": ">= 0 and finite", "absorption_base": ">= 0 and finite",
        "absorption_precip": ">= 0 and finite", "g": "in (-1, 1)", "sun_colour": ">= 0 and finite per channel",
        "ambient_bottom": ">= 0 and finite per channel", "ambient_top": ">= 0 and finite per channel",
        "ground_colour": ">= 0 and finite per channel", "samples_min": "in [1, samples_max]",
        "samples_max": "in [samples_min, 4096]", "exit_eps": "in (0, 1)", "exit_fill": "0 or 1",
        "light_interp": ">= 0 and finite", "light_step_km": "> 0 and finite",
        "light_cone_angle": "in [0, pi/2) rad",
        "light_far_factor": "in [1, 10^6] (CCL_CLOUDSCAPE_MAX_LIGHT_FAR_FACTOR), with light_far_factor x 5 x "
                            "light_step_km <= 10^6 km (CCL_CLOUDSCAPE_MAX_LIGHT_KM)",
        "jitter_mode": "0 (tilt), 1 (offset) or 2 (none)", "jitter_amount": ">= 0 and finite",
        "detail_direction": "0 or 1", "coverage_threshold": "0 or 1", "beer": "0 or 1", "powder": "0 or 1",
        "lighting": "0 (thesis) or 1 (sky)", "sun_intensity": ">= 0 and finite", "ambient_bottom_ratio": "in [0, 1]",
        "ambient_ground": ">= 0 and finite per channel", "ground_albedo": "in [0, 1] per channel",
        "ground_variation": "in [0, 1]",
        "aerial_km": ">= 0 and finite", "aerial_height_km": ">= 0 and finite",
        "ms_octaves": f"in [1, {MAX_MS_OCTAVES}]", "ms_a": "in [0, 1]", "ms_b": "in [0, 1]", "ms_c": "in [0, 1]",
        "silver_g": "in (-1, 1)", "silver_weight": "in [0, 1]", "phase": "0 (thesis) or 1 (mie)",
        "droplet_um": "in [5, 50]", "ambient_ground_weight": "in [0, 1]", "mie_delta": "in [0, 1]", "ms_depth": ">= 0 and finite",
        "ms_thin": "in [0, 1]", "ms_view": "in [0, 1000]", "ms_view_trans": "in [0.001, 1]", "ambient_aniso": "in [0, 1]", "ms_slab": "in [0, 1000]", "ms_slab_mu": "in [0, 4]", "ms_slab_far": "in [0, 1]", "lod": "0 or 1", "weather_detile": "0 or 1",
        "lod_bias": "in [-4, 4]", "refine_step_km": ">= 0 and finite", "refine_max": "in [1, 64]",
    })
#: the layer's fields: computed from the settings (earth_radius_km, layer_base_km, layer_top_km), never ``advanced``
_LAYER_FIELDS = ("centre", "r_earth", "r_inner", "r_outer")


_NOTHING = "nothing"


@dataclass(frozen=True)
class CloudscapeSettings(Settings):
    """Every parameter of a cloudscape render, with its unit, default and the reason for it. The thesis gives no
    values for any of them (spec vc-A36, "Not given"). Immutable: change with ``dataclasses.replace`` (validated) or
    :meth:`pywarp.clouds.technique.CloudscapeTechnique.update`. An invalid value raises ValueError (TypeError for a
    wrong type) naming the field, in the registry's wording."""

    #: ``textures``: the noise textures are regenerated; ``sky``: the sky model is rebuilt
    INVALIDATES = Settings.INVALIDATES + ("sky", "textures")

    width: int = param(960, unit="px", kind="int", lo=1, hi=8192, invalidates="size", group="image",
                       doc="image width", reason="960 x 540: a quarter of the thesis' Full HD, fast on a laptop CPU")
    height: int = param(540, unit="px", kind="int", lo=1, hi=8192, invalidates="size", group="image",
                        doc="image height", reason="960 x 540: a quarter of the thesis' Full HD")
    sky: str = param("preetham", choices=SKIES, invalidates="sky", group="sky",
                     doc="sky model: preetham (vc-A29) or gradient (vc-A28)",
                     reason="'preetham': the thesis' default sky")
    sun_elevation_deg: float = param(35.0, unit="deg", lo=0.0, hi=90.0, invalidates="sky", group="sky",
                                     cli="--sun-elevation",
                                     doc="sun elevation above the horizon (both skies: neither the Preetham model nor "
                                         "the gradient sky's lighting is defined for a sun below it)",
                                     reason="35: a mid-morning sun, the sky in view blue and the clouds lit from the "
                                            "side (sunlit tops, grey bases)")
    sun_azimuth_deg: float = param(150.0, unit="deg", **_ANGLE, invalidates="sky", group="sky",
                                   cli="--sun-azimuth",
                                   doc="sun azimuth, 0 = -z (straight ahead of the default camera), positive towards "
                                       "+x" + _ANGLE_DOC,
                                   reason="150: behind the viewer's right shoulder")
    turbidity: float = param(2.5, lo=2.0, hi=10.0, invalidates="sky", c="turbidity", group="sky",
                             doc="Preetham turbidity (the range of Preetham's fit)", reason="2.5: a clear day")
    sky_variant: str = param("corrected", choices=("corrected", "thesis"), invalidates="sky", group="sky",
                             doc="errata of the sky chain (vc-2.39, 4.4, 4.5)",
                             reason="'corrected': Preetham's published constants")
    units: str = param("display", choices=UNITS, invalidates="sky", group="sky", check=_units_check,
                       doc="display: the Preetham sky tone mapped, 1 - exp(-k C_HDR) (vc-4.5), and a sun of "
                           "sun_intensity; physical: radiances in kcd/m^2 times the one exposure k = sky_exposure -- "
                           "the sky k C_HDR (C_HDR's Y is luminance in kcd/m^2, vc-2.39) and the sun k x 127.5 klx x "
                           "the atmosphere's transmittance (cclouds/cloudscape.h); needs sky=preetham, lighting=sky",
                       reason="'display': the thesis's sky and the tuned exposure of its lighting")
    sky_exposure: float = param(0.05, lo=0.0, hi=10.0, lo_open=True, check=_sky_exposure_check, invalidates="sky",
                                group="sky", unit="1/(kcd/m^2)",
                                doc="exposure k of the Preetham tone map C = 1 - exp(-k C_HDR) (vc-4.5); C_HDR has "
                                    "the unit of Preetham's luminance fit, kcd/m^2 (the thesis gives none); at most "
                                    "0.25 with sky_variant 'thesis', whose printed 1 - exp(+k C_HDR) overflows",
                                reason="0.05: with the thesis' 0.03 the corrected sky is a dim slate grey-blue; 0.05, "
                                       "then the display transform (exposure_ev, tonemap), gives a T = 3 sky at a "
                                       "30-60 deg sun a blue zenith and a pale horizon (sRGB (109, 141, 179) and "
                                       "(160, 155, 161) at 35 deg) without saturating the sky around the sun "
                                       "(figures/vc/fig-4.6.png shows both)")
    coverage: float = inherit(WeatherMapSettings, "coverage")
    precipitation: float = inherit(WeatherMapSettings, "precipitation")
    cloud_type: float = inherit(WeatherMapSettings, "cloud_type")
    cloud_type_variation: float = inherit(WeatherMapSettings, "cloud_type_variation")
    coverage_threshold: str = param("one_minus_coverage", choices=COVERAGE_THRESHOLD_NAMES, c="coverage_threshold",
                                    c_enum=COVERAGE_THRESHOLD_ENUM, group="clouds",
                                    doc="reading of the undefined threshold C of vc-2.29: one_minus_coverage "
                                        "(C = 1 - D_h) or coverage (C = D_h, the literal reading: clouds survive only "
                                        "as rings around covered areas)",
                                    reason="one_minus_coverage: more coverage gives more cloud (ccl_cloudscape_"
                                           "params_default; see cclouds/cloudscape.c)")
    beer: bool = param(True, c="beer", group="clouds",
                       doc="Beer's-law term of the lighting energy vc-2.31 (off: replaced by 1)",
                       reason="on: the formula as printed (ccl_cloudscape_params_default)")
    powder: bool = param(False, c="powder", group="clouds",
                         doc="powder term of the lighting energy vc-2.31 (off: replaced by 1; "
                             "on: the formula as printed, the thesis's renderer)",
                         reason="off: measured against the path-traced reference (tools/tune_lighting.py), the mean "
                                "CIEDE2000 of three scenes falls from 13.4 to 9.0 and the dark rims along the clouds' "
                                "sunward edges (thin crease lines) go (ccl_cloudscape_params_default)")
    lod: bool = param(True, c="lod", group="clouds",
                      doc="level of detail: the base and detail noise sampled at the mip level of each sample's "
                          "footprint (the pixel's width at the sample; the light samples at least the light step); "
                          "off: full resolution everywhere, as the thesis",
                      reason="on: without it the steps and pixels near the horizon undersample 25-50 m texels and "
                             "the distant clouds turn into salt-and-pepper noise that changes every frame "
                             "(ccl_cloudscape_params_default)")
    lod_bias: float = param(0.0, lo=-4.0, hi=4.0, c="lod_bias", group="clouds",
                            doc="added to every mip level of the level of detail (> 0 blurs, < 0 sharpens)",
                            reason="0: one texel per footprint, the usual mip-mapping criterion")
    refine_step_km: float = param(0.1, unit="km", lo=0.0, hi=10.0, c="refine_step_km", group="clouds",
                                  doc="refinement: view steps longer than this are split into sub-steps of at most "
                                      "this length where a coarse base-shape test finds cloud; view steps already "
                                      "this short are grouped (up to refine_max steps, at most 2 x this long) and "
                                      "skipped where the coarse tests at both ends of the group find no cloud (0: "
                                      "off, the thesis)",
                                  reason="0.1 km: about three mean free paths of the default extinction in a "
                                         "typical cloud; near the horizon the view steps reach ~0.8 km, one step "
                                         "crossed a whole cloud and the pixel took the light of one random depth "
                                         "(the horizon's salt-and-pepper noise)")
    base_precision: str = param("half", choices=BASE_PRECISIONS, group="clouds",
                                doc="the base-shape texture's texels: half (rounded to float16 -- 2^-11 of their "
                                    "value -- and stored as half floats: 17 instead of 34 MB with its mip levels) "
                                    "or single (float32, as generated; the thesis's renderer). The C renderer reads "
                                    "the same rounded values",
                                reason="half: the 128^3 base texture no longer overflows the CPU's cache; measured "
                                       "(pywarp bench clouds speed) 5-9 % off a frame, and a random base lookup "
                                       "108 -> 38 ns; the frame changes by at most 1 level in about 1 % of pixels")
    weather_detile: bool = param(True, c="weather_detile", group="clouds",
                                 doc="the weather map does not tile visibly: blended with a rotated, scaled copy by "
                                     "the coverage of a much larger copy (ccl_cloudscape_weather); off: one periodic "
                                     "lookup, the thesis",
                                 reason="on: one 32 km map repeats visibly from a few km up")
    refine_max: int = param(8, lo=1, hi=64, c="refine_max", group="clouds",
                            doc="most sub-steps per view step of the refinement, and view steps per group of "
                                "short steps; with refinement on, no view "
                                "step is longer than refine_step_km x refine_max (a longer segment takes more steps, "
                                "at most 4 x samples_max: the coarse test would miss clouds between its points)",
                            reason="8: 0.8 km horizon steps down to 0.1 km; bounds the work per ray")
    seed: int = inherit(BaseShapeSettings, "seed", group="clouds",
                        doc="seed of every texture (uint32); the same seed gives the same image",
                        reason="0: Perlin's reference permutation")
    camera_altitude_km: float = param(0.3, unit="km", lo=0.0, hi=1000.0, group="camera", cli="--altitude",
                                      doc="camera altitude above the ground (the cloud layer: 1.5-4 km)",
                                      reason="0.3: below the layer, the cloud bases overhead")
    camera_x_km: float = param(0.0, unit="km", lo=-MAX_CAMERA_KM, hi=MAX_CAMERA_KM, group="camera",
                               cli="--camera-x",
                               doc="camera position x" + _CAMERA_DOC, reason="0: the origin")
    camera_z_km: float = param(0.0, unit="km", lo=-MAX_CAMERA_KM, hi=MAX_CAMERA_KM, group="camera",
                               cli="--camera-z",
                               doc="camera position z" + _CAMERA_DOC, reason="0: the origin")
    camera_yaw_deg: float = param(0.0, unit="deg", **_ANGLE, group="camera", cli="--yaw",
                                  doc="camera heading, 0 = -z, positive towards +x" + _ANGLE_DOC,
                                  reason="0: looking along -z")
    camera_pitch_deg: float = param(20.0, unit="deg", lo=-89.0, hi=89.0, group="camera", cli="--pitch",
                                    doc="camera pitch above the horizon",
                                    reason="20: the horizon near the bottom edge, the cloud bases overhead")
    fov_y_deg: float = param(60.0, unit="deg", lo=1.0, hi=170.0, group="camera", cli="--fov",
                             doc="vertical field of view", reason="60: a natural view")
    earth_radius_km: float = param(EARTH_RADIUS_KM, unit="km", lo=0.0, lo_open=True, group="cloud layer",
                                   cli="--earth-radius", doc="Earth radius (vc-A14)",
                                   reason="6371: the IUGG mean Earth radius rounded (pywarp.kernels.raymarch)")
    layer_base_km: float = param(LAYER_BASE_KM, unit="km", lo=0.0, group="cloud layer", cli="--layer-base",
                                 doc="altitude of the cloud layer's base (vc-A14)",
                                 reason="1.5: a typical condensation level of low clouds (pywarp.kernels.raymarch)")
    layer_top_km: float = param(LAYER_TOP_KM, unit="km", lo=0.0, lo_open=True, check=_layer_top_check,
                                group="cloud layer", cli="--layer-top",
                                doc="altitude of the cloud layer's top (vc-A14), > layer base",
                                reason="4: room for cumulus towers growing through the thesis' 2 km limit")
    wind_speed_kmh: float = param(30.0, unit="km/h", lo=0.0, hi=1000.0, group="wind", cli="--wind-speed",
                                  doc="wind speed; time moves the weather map and the detail noise (the detail at "
                                      "1.5x the speed, plus a slow rise: billowing)",
                                  reason="30: a fresh breeze, visible motion over seconds of a fly-through")
    wind_direction_deg: float = param(60.0, unit="deg", **_ANGLE, group="wind", cli="--wind-direction",
                                      doc="direction the wind blows towards, 0 = -z" + _ANGLE_DOC,
                                      reason="60: across the default view, so the motion is visible")
    time_s: float = param(0.0, unit="s", lo=-MAX_TIME_S, hi=MAX_TIME_S, group="wind", cli="--time",
                          doc="time: the wind moves the clouds. Within 3 hours either way: the model moves one "
                              "frozen cloud field with the wind, which stops making sense over longer spans (cumulus "
                              "form and dissolve within an hour), and 3 hours at the highest wind speed keep the "
                              "texture coordinates inside ccl_cloudscape_check's bound (2^23 texels)",
                          reason="0: the weather map as generated")
    adaptive_samples: bool = param(True, c="adaptive_samples", group="quality",
                                   doc="adaptive view-sample count, 64 at the zenith to 128 at the horizon (vc-A18)",
                                   reason="on: the thesis' optimisation (fig 4.17)")
    early_exit: bool = param(True, c="early_exit", group="quality", doc="early ray termination when opaque (vc-A21)",
                             reason="on: the thesis' optimisation (fig 4.17)")
    reprojection: bool = param(False, group="quality",
                               doc="temporal reprojection (vc-A26): one pixel per 4x4 block raymarched per frame",
                               reason="off: a single image has no previous frame")
    reprojection_neighbourhood: int = param(1, unit="px", kind="int", lo=1, hi=9, odd=True, group="quality",
                                            doc="vc-A27 neighbourhood averaging of reprojected pixels: 1 (exact "
                                                "sampling) or an odd n (n x n box)",
                                            reason="1: exact sampling, no blur")
    reprojection_depth: str = param("clouds", choices=REPROJECTION_DEPTHS, group="quality",
                                    doc="where a reprojected pixel's point is looked for in the previous frame: "
                                        "'clouds' (at the distance of what the pixel shows -- the clouds' mean "
                                        "distance from the march, else the ground, else the sky far away -- kept in "
                                        "a depth buffer and found by 2 fixed-point steps along the ray, "
                                        "pywarp.kernels.reproj.reproj_uv_depth) or 'inner_sphere' (the thesis, "
                                        "vc-A26: everything as if on the layer base)",
                                    reason="'clouds': through the inner sphere, clouds at other distances and the sky "
                                           "are fetched from the wrong place while the camera translates (parallax) "
                                           "and the freshly marched pixel of every 4x4 block shows as a dot grid")
    reprojection_filter: str = param("catmull_rom", choices=REPROJECTION_FILTERS, group="quality",
                                     doc="how the previous frame is sampled at a reprojected position: "
                                         "'catmull_rom' (cubic over 4x4 pixels, clamped to the range of the 2x2 "
                                         "the bilinear filter reads) or 'bilinear' (the thesis, vc-A26)",
                                     reason="'catmull_rom': a pixel is resampled up to 15 times before it is marched "
                                            "again; bilinear resampling blurs it every time, and the sharp fresh "
                                            "pixel of each 4x4 block then stands out as a dot grid")
    jitter: str = param("offset", choices=JITTER_NAMES, c="jitter_mode", c_enum=JITTER_ENUM, group="quality",
                        doc="ray jitter against banding (vc-A23): offset (the first sample's position along the "
                            "ray), tilt (the thesis: the ray's direction) or none",
                        reason="'offset': the thesis' tilt of up to 0.002 rad per axis moves the ray by more than a "
                               "pixel (0.0019 rad at 960x540), so far clouds changed from frame to frame (the "
                               "flickering horizon: 6.2 grey levels between frames against 0.77 with offset) and "
                               "near ones looked out of focus (ccl_cloudscape_params_default)")
    light_detail: bool = param(True, c="light_detail", group="quality",
                               doc="light samples with the detail erosion (off: the base shape only, cheaper)",
                               reason="on: the thesis' density (ccl_cloudscape_params_default)")
    march: str = param("fast", choices=MARCH_NAMES, c="march", c_enum=MARCH_ENUM, group="quality",
                       doc="the loop of the cloud march: fast (refinement of long steps, grouping and skipping of "
                           "empty ones, light interpolation, level of detail) or textbook (vc-A18..A21 as the thesis "
                           "prints the loop, ccl_cloudscape_march_textbook: for reading beside the text)",
                       reason="'fast': towards the horizon the textbook's view steps grow to hundreds of metres "
                              "(from inside the layer to kilometres) and each takes the light of one depth: noise "
                              "that changes every frame. Against a fine march (1024 samples, 0.1 km steps in "
                              "cloud; 320x180, below / inside the layer) the fast march is off by 7.4 / 6.0 levels "
                              "of 8 bits at the 99th percentile in 1.3 times the textbook's time, the textbook by "
                              "15 / 95, and with 8 times its samples by 4.1 / 5.8 in 3.7 times the fast march's "
                              "time (tutorials/vc/extra_textbook_march.py)")
    accumulate: int = param(1, unit="frames", kind="int", lo=1, hi=1024, group="quality",
                            doc="frames averaged into one still (pywarp render): each seen through the camera moved by "
                                "a sub-pixel offset of the R2 low-discrepancy sequence (pywarp.kernels.camera."
                                "subpixel_jitter; the first is the pixel centre) and with its own ray jitter (frame "
                                "counter), averaged in display-linear space and encoded once; no reprojection",
                            reason="1: one frame, the real-time image of the thesis; 16-64 remove the ray-jitter "
                                   "noise and the stair steps of a still (the noise falls as 1/sqrt(N)); at most 1024: "
                                   "the noise is then 1/32 of one frame's, below a grey level, and a 960x540 still "
                                   "already takes about 20 min on a 2-core CPU")
    exposure_ev: float = exposure_param(
        -0.5, reason="-0.5 EV: the ACES curve lifts mid-tones (T(0.34) = 0.48), and -0.5 EV brings the default "
                     "view's mean back to within 5 % of the clamped image's while its brightest cloud tops (1.54) map "
                     "to 0.82, not to white (480x270, 5.3 % of the clamped image's pixels have a channel at 255, none "
                     "with the transform)")
    tonemap: str = tonemap_param()
    base_size: int = inherit(BaseShapeSettings, "size", group="textures")
    detail_size: int = inherit(DetailShapeSettings, "size", group="textures")
    curl_size: int = inherit(CurlNoiseSettings, "size", group="textures")
    weather_size: int = inherit(WeatherMapSettings, "size", group="textures")
    g: float = param(0.2, lo=-1.0, hi=1.0, lo_open=True, hi_open=True, c="g", group="clouds", cli="--phase-g",
                     doc="Henyey-Greenstein asymmetry g of vc-2.31",
                     reason="0.2: ccl_cloudscape_params_default (see cclouds/cloudscape.c)")
    phase: str = param("thesis", choices=PHASE_NAMES, c="phase", c_enum=PHASE_ENUM, group="clouds",
                       doc="phase function of the clouds, in the real-time lighting and in the reference: thesis = "
                           "Henyey-Greenstein with --phase-g (vc-2.13; and the silver lobe); mie = the approximate "
                           "Mie phase of droplets of --droplet-um (Jendersie & d'Eon 2023, vc-x-mie)",
                       reason="'thesis': the thesis's single HG lobe, its images")
    droplet_um: float = param(15.0, unit="um", lo=5.0, hi=50.0, c="droplet_um", group="clouds",
                              doc="droplet diameter of the Mie phase (phase=mie), in the fit's range [5, 50] um",
                              reason="15: an effective radius of 7.5 um, in the 5-10 um of fair-weather cumulus "
                                     "(Miles, Verlinde & Clothiaux 2000, J. Atmos. Sci. 57:295); g = 0.87")
    sigma_per_km: float = param(30.0, unit="1/km", lo=0.0, hi=1000.0, lo_open=True, c="sigma", group="clouds",
                                cli="--sigma",
                                doc="extinction per unit density",
                                reason="30: ccl_cloudscape_params_default (see cclouds/cloudscape.c)")
    lighting: str = param("sky", choices=LIGHTING_NAMES[::-1], c="lighting", c_enum=LIGHTING_ENUM, group="lighting",
                          doc="sky: sun colour and ambient from the sky model (the sun's elevation through the "
                              "atmosphere, the sky's mean radiance), a lit ground with cloud shadows, aerial "
                              "perspective, multiple scattering and the silver-lining lobe; thesis: the thesis's "
                              "constant sun and ambient, flat ground, one octave, one HG lobe (its images exactly)",
                          reason="'sky': clouds take the colour of the light around them (a sunset lights them "
                                 "orange); ccl_cloudscape_params_default")
    sun_intensity: float = param(16.0, lo=0.0, hi=1000.0, c="sun_intensity", group="lighting",
                                 doc="sky lighting: sun irradiance above the atmosphere (display-linear units; the "
                                     "sun colour is this times the atmosphere's transmittance towards the sun)",
                                 reason="16: at the default sun (35 deg) the sun's red channel is ~12, the thesis "
                                        "constant's (ccl_cloudscape_params_default, see cclouds/cloudscape.c)")
    ground_albedo: tuple = param((0.04, 0.05, 0.03), lo=0.0, hi=1.0, check=_albedo_check, c="ground_albedo",
                                 group="lighting",
                                 doc="sky lighting: Lambertian albedo of the ground (RGB)",
                                 reason="(0.04, 0.05, 0.03): vegetation (0.1-0.2) scaled by the ~3.5 times too "
                                        "bright sun that exposes the dim clouds of vc-2.31, so the sunlit ground stays "
                                        "darker than the sky (ccl_cloudscape_params_default, see cclouds/cloudscape.c)")
    ground_variation: float = param(0.0, lo=0.0, hi=1.0, c="ground_variation", group="lighting",
                                    doc="sky lighting: relative albedo variation of the ground: patches of "
                                        "CCL_CLOUDSCAPE_GROUND_PATCH_KM = 125 m (and 4x smaller) from 1 - v to 1 + v "
                                        "times ground_albedo",
                                    reason="0: a uniform ground, the thesis's (seen from kilometres up it is a "
                                           "backdrop; the rain scene's view from 50 m sets 0.8)")
    aerial_km: float = param(30.0, unit="km", lo=0.0, hi=1e6, c="aerial_km", group="lighting", cli="--aerial",
                             doc="sky lighting: aerial-perspective e-folding distance L at the ground (0 = off): "
                                 "colour = C e^(-t/L) + horizon sky (1 - e^(-t/L)), t the path's length of "
                                 "ground-level air (see aerial_height_km)",
                             reason="30: a visual range of ~117 km (Koschmieder 3.912 x 30), a clear day; the "
                                    "horizon band of clouds fades into the sky (ccl_cloudscape_params_default)")
    aerial_height_km: float = param(2.0, unit="km", lo=0.0, hi=1e6, c="aerial_height_km", group="lighting",
                                    cli="--aerial-height",
                                    doc="sky lighting: scale height of the haze (its density falls as e^(-altitude "
                                        "/ H)); 0 = a homogeneous fog",
                                    reason="2: the haze is mostly aerosol in the lowest kilometres (scale heights "
                                           "1-2 km); a view from above sees the ground veiled, not fogged "
                                           "(ccl_cloudscape_params_default)")
    ambient_ground_weight: float = param(0.25, lo=0.0, hi=1.0, c="ambient_ground_weight", group="lighting",
                                         cli="--ambient-ground",
                                         doc="sky lighting: share w of the lit ground in the clouds' ambient, (1 - w) "
                                             "sky mean over the upper hemisphere + w ground radiance; 0.5 = the mean "
                                             "over all directions",
                                         reason="0.25: a quarter of the ambient from the lit ground below; "
                                                "chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst (ccl_cloudscape_params_default); 0 = the sky's mean alone")
    mie_delta: float = param(1.0, lo=0.0, hi=1.0, c="mie_delta", group="lighting", cli="--mie-delta",
                             doc="sky lighting with phase=mie: the share f of the Mie phase's forward HG lobe (the "
                                 "droplets' diffraction peak) that the lighting treats as unscattered light: "
                                 "extinction x (1 - f (1 - w_D)), the phase without that share (delta scaling, "
                                 "vc-x-mie-delta); 0 = off",
                             reason="1: the whole forward peak (extinction x w_D = 0.49 at 15 um, Draine's lobe "
                                    "as the phase); chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst; acts with phase=mie only")
    ms_depth: float = param(1.5, lo=0.0, hi=1e6, c="ms_depth", group="lighting", cli="--ms-depth",
                            doc="sky lighting: optical depth scale D of the multiple-scattering octaves' weight "
                                "t + (1 - t)(1 - exp(-d / D)), d the optical depth towards the sun, t = --ms-thin "
                                "(vc-x-ms-gain); 0 = off (weight 1)",
                            reason="1.5: the octaves reach 1 - 1/e of their weight at an optical depth of 1.5 "
                                   "towards the sun; chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst")
    ms_thin: float = param(0.2, lo=0.0, hi=1.0, c="ms_thin", group="lighting", cli="--ms-thin",
                           doc="sky lighting: the octaves' weight at d = 0 (see --ms-depth)",
                           reason="0.2: a fifth of the octaves where there is no cloud towards the sun; "
                                  "chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst; used when ms_depth > 0")
    ms_view: float = param(4.0, lo=0.0, hi=1000.0, c="ms_view", group="lighting", cli="--ms-view",
                           doc="sky lighting: the multiple-scattering octaves' weight by the depth into the cloud "
                               "along the view, 1 + k (1 - T), T the view transmittance in front of the sample "
                               "(vc-x-ms-view); 0 = off",
                           reason="4: the octaves up to 5 times deep in the cloud along the view; chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst")
    ms_view_trans: float = param(0.5, lo=0.001, hi=1.0, c="ms_view_trans", group="lighting", cli="--ms-view-trans",
                                 doc="sky lighting: the view transmittance T0 below which --ms-view's weight grows: "
                                     "1 + k max(1 - T / T0, 0)",
                                 reason="0.5: the weight grows once half the view's light is gone; chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst; used "
                                        "when ms_view > 0")
    ambient_aniso: float = param(0.6, lo=0.0, hi=1.0, c="ambient_aniso", group="lighting", cli="--ambient-aniso",
                                 doc="sky lighting: the ambient's weight by the view direction, 1 + alpha mu T, mu the "
                                     "cosine of the view with the local up (vc-x-ambient-aniso); 0 = off (isotropic)",
                                 reason="0.6: the ambient 60 % brighter looking up at the visible surface, 60 % "
                                        "darker looking down (a thin cloud's sky light, scattered by the droplets' "
                                        "forward-peaked phase, goes on down more than it comes back up); chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst")
    ms_slab: float = param(1.6, lo=0.0, hi=1000.0, c="ms_slab", group="lighting", cli="--ms-slab",
                           doc="sky lighting: gain k of the multiple-scattering octaves' weight by the sun's elevation "
                               "and the sample's place between the sun and the viewer, k max(mu0, 0)^p (1 - s r), mu0 "
                               "the sun's cosine with the local up, r = d / (d + tau_v) the optical depth towards the "
                               "sun over it plus that back to the eye (vc-x-ms-slab); 0 = off (weight 1)",
                           reason="1.6: removes the trend of the thick cloud's energy with the sun's elevation "
                                  "seen from below; chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst")
    ms_slab_mu: float = param(0.3, lo=0.0, hi=4.0, c="ms_slab_mu", group="lighting", cli="--ms-slab-mu",
                              doc="sky lighting: the exponent p of mu0 in --ms-slab's weight",
                              reason="0.3: a weaker fall with the sun's elevation than the 1 of the sun's flux "
                                     "through a horizontal cloud top (two-stream slab); chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst; used when ms_slab > 0")
    ms_slab_far: float = param(0.67, lo=0.0, hi=1.0, c="ms_slab_far", group="lighting", cli="--ms-slab-far",
                               doc="sky lighting: the share s of --ms-slab's weight lost where the sample is on the "
                                   "cloud's side away from the sun (r = 1)",
                               reason="0.67: two thirds of the weight lost on the side away from the sun; chosen against the path-traced references, issue 32's 'physical slab 2', docs/lighting.rst; used "
                                      "when ms_slab > 0")
    ms_octaves: int = param(4, kind="int", lo=1, hi=MAX_MS_OCTAVES, c="ms_octaves", group="lighting",
                            doc="sky lighting: multiple-scattering octaves (Wrenninge et al. 2013; 1 = single "
                                "scattering); octave i scales the optical depth and phase eccentricity by 0.5^i and "
                                "the contribution by 0.75^i (ms_a, ms_b, ms_c through `advanced`; ms_b 0.75 "
                                "chosen against the path-traced references, issue 32's 'physical slab 2', "
                                "docs/lighting.rst)",
                            reason="4 (ccl_cloudscape_params_default; measured with 0.5 per octave): against the "
                                   "path-traced reference (tools/tune_lighting.py, mean CIEDE2000 of three scenes): 1 "
                                   "octave 12.2, 2: 10.3, 3: 9.4, 4: 9.0, 8: 8.7 -- the fewest within 0.5 of the best")
    silver_g: float = param(0.8, lo=-1.0, hi=1.0, lo_open=True, hi_open=True, c="silver_g", group="lighting",
                            doc="sky lighting: asymmetry of the second Henyey-Greenstein lobe (silver lining)",
                            reason="0.8: a narrow forward lobe (ccl_cloudscape_params_default); used when "
                                   "silver_weight > 0")
    silver_weight: float = param(0.0, lo=0.0, hi=1.0, c="silver_weight", group="lighting",
                                 doc="sky lighting: weight w of the second lobe, phase = (1 - w) HG(g) + w "
                                     "HG(silver_g); 0 = one lobe",
                                 reason="0: measured against the path-traced reference (tools/tune_lighting.py): "
                                        "every weight raises the error in every scene (mean CIEDE2000 9.0 at 0, 9.3 "
                                        "at 0.15) -- the medium's phase function is one HG lobe; the lobe is an option")
    samples_min: int = param(64, kind="int", lo=1, hi=4096, c="samples_min", group="quality",
                             doc="view samples at the zenith (vc-A18)", reason="64: the thesis (vc-A18)")
    samples_max: int = param(128, kind="int", lo=1, hi=4096, check=_samples_max_check, c="samples_max", group="quality",
                             doc="view samples at the horizon (vc-A18), >= samples_min",
                             reason="128: the thesis (vc-A18)")
    # --- the path-traced ground truth (pywarp.clouds.reference; pywarp render clouds --reference) ---
    reference: bool = param(False, group="reference",
                            doc="render the path-traced ground truth of the same density field, sun and sky "
                                "(Monte Carlo, multiple scattering; pywarp.clouds.reference) instead of the "
                                "real-time image",
                            reason="off: the real-time renderer; the reference takes minutes per image")
    spp: int = param(64, kind="int", lo=1, hi=65536, group="reference",
                     doc="reference: paths per pixel (the noise falls as 1/sqrt(spp))",
                     reason="64: a recognisable image in about a minute at 320x180 on 2 cores; the benchmark's "
                            "references use 1024")
    reference_seed: int = param(0, kind="uint32", lo=0, hi=2 ** 32 - 1, group="reference",
                                doc="reference: seed of the path tracer's random numbers (the textures keep --seed); "
                                    "the same seed gives the same image on any number of threads",
                                reason="0: any value; independent seeds give independent noise")
    reference_bounces: int = param(1024, kind="int", lo=1, hi=4096, group="reference", cli="--bounces",
                                   doc="reference: scattering events per path at most (medium or ground)",
                                   reason="1024: pywarp.clouds.reference.DEFAULT_BOUNCES (the light still missing "
                                          "at 1024 is below the benchmark's noise; deeper paths are rare and cheap)")
    device: str = param("cpu", invalidates="device", group="runtime",
                        doc="Warp device: cpu, or cuda:N where present", reason="cpu: nothing requires a GPU")
    threads: int | None = param(None, kind="int", lo=1, hi=4096, optional=True, invalidates="device",
                                group="runtime", default_text="one per core",
                                doc="worker threads of the tile launcher",
                                reason="None: one per core (PYWARP_THREADS overrides)")
    advanced: dict = param({}, check=_advanced_check, cli=None,
                           doc="any other field of ccl_cloudscape_params by name (e.g. {'base_scale_km': 8.0, "
                               "'sun_colour': (30, 29, 27)}), checked by ccl_cloudscape_check",
                           reason="{}: the defaults and reasons of cclouds/cloudscape.c")

    # --- derived quantities ------------------------------------------------------------------------------------------
    def textures(self) -> dict:
        """The texture settings (vc-A13) of this render: kind -> settings."""
        return {"base_shape": BaseShapeSettings(size=self.base_size, seed=self.seed),
                "detail_shape": DetailShapeSettings(size=self.detail_size, seed=self.seed),
                "curl_noise": CurlNoiseSettings(size=self.curl_size, seed=self.seed),
                "weather_map": WeatherMapSettings(size=self.weather_size, seed=self.seed, coverage=self.coverage,
                                                  precipitation=self.precipitation, cloud_type=self.cloud_type,
                                                  cloud_type_variation=self.cloud_type_variation)}

    def half_base(self) -> bool:
        """True where the renderers read the base-shape texture as float16 values (``base_precision`` 'half'):
        the ``half_base`` argument of ``RenderTextures``, ``c_textures`` and ``majorant_grids``."""
        return self.base_precision == "half"

    def layer(self):
        """The cloud layer (vc-A14) as ``pywarp.kernels.raymarch.CloudLayer``."""
        from ..kernels import raymarch as R

        return R.CloudLayer(self.earth_radius_km, self.layer_base_km, self.layer_top_km)

    def sun(self) -> np.ndarray:
        """Unit vector towards the sun (``pywarp.kernels.sky.sun_direction``)."""
        from ..kernels import sky as S

        return S.sun_direction(self.sun_elevation_deg, self.sun_azimuth_deg)

    def wind_offsets(self) -> tuple[tuple[float, float], tuple[float, float, float]]:
        """(weather offset (x, z), detail offset (x, y, z)) in km after ``time_s`` seconds of wind."""
        dist = self.wind_speed_kmh * self.time_s / 3600.0
        a = math.radians(self.wind_direction_deg)
        dx, dz = math.sin(a), -math.cos(a)
        # the lookup moves against the wind so that the clouds move with it
        weather = (-dx * dist, -dz * dist)
        detail = (-1.5 * dx * dist, -0.1 * dist, -1.5 * dz * dist)
        return weather, detail

    # --- the C and Warp parameters (pywarp.core.cbridge) --------------------------------------------------------------
    def c_values(self) -> dict:
        """The ``ccl_cloudscape_params`` values of these settings: the C defaults, the fields the specs name, the
        layer, the wind offsets, ``sigma_light`` = ``sigma``, then the ``advanced`` overrides (unchecked)."""
        from ..core.cbridge import settings_values

        layer = self.layer()
        weather_off, detail_off = self.wind_offsets()
        v = CLOUDSCAPE_PARAMS.defaults()
        v.update(settings_values(self), centre=layer.centre, r_earth=layer.r_earth, r_inner=layer.r_inner,
                 r_outer=layer.r_outer, weather_offset=weather_off, detail_offset=detail_off,
                 sigma_light=self.sigma_per_km)
        if self.lighting == "thesis":  # the thesis's model entirely: one octave, one HG lobe, no later term
            v.update(THESIS_LIGHTING)
        for name, value in self.advanced.items():
            if name not in v or name in _LAYER_FIELDS:
                known = sorted(set(v) - set(_LAYER_FIELDS))
                raise ValueError(f"advanced: unknown parameter {name!r}; known: {', '.join(known)}")
            if isinstance(v[name], tuple) != isinstance(value, (tuple, list)) or (
                    isinstance(value, (tuple, list)) and len(value) != len(v[name])):
                raise ValueError(f"advanced: {name} must be like {v[name]!r}, got {value!r}")
            if isinstance(value, (tuple, list)):
                v[name] = tuple(_c_float(f"advanced: {name}", x) for x in value)
            elif isinstance(v[name], int):
                v[name] = _c_int(f"advanced: {name}", value)
            else:
                v[name] = _c_float(f"advanced: {name}", value)
        return v

    def c_params(self, values: dict | None = None):
        """The ``ccl_cloudscape_params`` (cffi) of :meth:`c_values` (or ``values``), checked by ccl_cloudscape_check
        at the settings' texture sizes (the texture-coordinate bound depends on them); ValueError names the first bad
        field."""
        from ..core.binding import ffi, lib

        f = ffi()
        dummy = np.zeros(4, dtype=np.float32)  # the check reads no texel: one dummy stands for every texture
        tex = f.new("ccl_cloud_textures *")
        for name, size in (("base", self.base_size), ("detail", self.detail_size), ("curl", self.curl_size),
                           ("weather", self.weather_size)):
            setattr(tex, name, f.cast("const float *", f.from_buffer("float[]", dummy)))
            setattr(tex, f"{name}_size", size)
        sky = f.new("ccl_cloudscape_sky *")  # a valid sky: the check of the sky is not the settings'
        sky.kind = lib().CCL_SKY_GRADIENT
        sky.sun[1] = 1.0
        return CLOUDSCAPE_PARAMS.checked(self.c_values() if values is None else values, tex, sky, settings=self,
                                         overrides=tuple(self.advanced))

    def warp_params(self):
        """The Warp ``CloudscapeParams`` of the checked :meth:`c_params` (before the per-sky lighting setup,
        ``pywarp.clouds.cloudscape.light_params``)."""
        return CLOUDSCAPE_PARAMS.warp_struct(self.c_params())


_F32_MAX = float(np.finfo(np.float32).max)


def _c_int(name: str, value) -> int:
    """A value for a C ``int`` field, validated before any conversion (no bool, no 3.5, no OverflowError)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    if not -(2 ** 31) <= int(value) <= 2 ** 31 - 1:
        raise ValueError(f"{name} must be in [-2147483648, 2147483647] (int32), got {value!r}")
    return int(value)


def _c_float(name: str, value) -> float:
    """A value for a C ``float`` field: a finite number within the float32 range."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number, got {value!r}")
    x = float(value)
    if not math.isfinite(x) or abs(x) > _F32_MAX:
        raise ValueError(f"{name} must be finite and within the float32 range, got {value!r}")
    return x
