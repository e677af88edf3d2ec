"""The volumetric cloudscape of the vc thesis on the CPU: Preetham (or gradient) sky, cloud-layer raymarch, temporal
reprojection -- the render chain of vc-A30 built from the classes of vc-A31 (sky models), vc-A32 (texture generator)
and vc-A33 (visualization technique: init / update / render, plus resize).

    from pywarp.clouds.cloudscape import CloudscapeSettings, render_image
    img = render_image(CloudscapeSettings(width=640, height=360))      # uint8 (360, 640, 3)

One frame (``CloudscapeTechnique.render``):
  1. the sky model writes the background of every pixel (or, with reprojection, of one pixel per 4 x 4 block);
  2. the cloud kernel marches the cloud layer for the same pixels and composites over the background (vc-4.8);
  3. with reprojection, the other 15/16 of the pixels come from the previous frame through the inner-sphere hit
     point (vc-A26), or from the reduced buffer;
  4. sRGB encoding, uint8.
Every stage is a Warp kernel launched as row bands on every core (:class:`pywarp.core.runtime.TileLauncher`). The same
pixel computation exists in C (``ccl_cloudscape_pixel``): :func:`render_pixels_c` runs it at chosen pixels.
"""
from __future__ import annotations

import math
import weakref
from abc import ABC, abstractmethod
from dataclasses import asdict, dataclass, field, fields, replace

import numpy as np
import warp as wp

from ..core.runtime import TileLauncher, init, launcher as shared_launcher

init()

from ..kernels import cloudscape as K  # noqa: E402
from ..kernels import raymarch as R  # noqa: E402
from ..kernels import reproj as RP  # noqa: E402
from ..kernels import sky as S  # noqa: E402
from . import textures as T  # noqa: E402

SKIES = ("preetham", "gradient")
JITTERS = {"tilt": K.JITTER_TILT, "offset": K.JITTER_OFFSET, "none": K.JITTER_NONE}
COVERAGE_THRESHOLDS = {"coverage": 0, "one_minus_coverage": 1}


def _check(cond: bool, name: str, rng: str, value) -> None:
    if not cond:
        raise ValueError(f"{name} must be {rng}, got {value!r}")


def _finite(v) -> bool:
    return isinstance(v, (int, float, np.floating, np.integer)) and not isinstance(v, bool) and math.isfinite(v)


@dataclass
class CloudscapeSettings:
    """Every parameter of a cloudscape render, with its unit and default. The thesis gives no values for any of
    them (spec vc-A36, "Not given"); each default says why it was chosen. ``validate()`` (called by every render)
    raises ValueError naming the field and its valid range."""

    #: Image size in pixels (default 960 x 540: a quarter of the thesis' Full HD, fast on a laptop CPU).
    width: int = 960
    height: int = 540
    #: Sky model: 'preetham' (the thesis' default, vc-A29) or 'gradient' (vc-A28).
    sky: str = "preetham"
    #: Sun elevation above the horizon and azimuth (degrees; azimuth 0 = -z, the default view direction).
    #: Default 35 deg, azimuth 150 deg: a mid-morning sun behind the viewer's right shoulder, so the sky in view is
    #: blue and the clouds are lit from the side (sunlit tops, grey bases).
    sun_elevation_deg: float = 35.0
    sun_azimuth_deg: float = 150.0
    #: Preetham turbidity in [2, 10] (the range of Preetham's fit). Default 2.5: a clear day.
    turbidity: float = 2.5
    #: Variant of the sky chain's errata (vc-2.39, 4.4, 4.5): 'corrected' or 'thesis'.
    sky_variant: str = "corrected"
    #: Exposure k of the Preetham tone map C = 1 - exp(-k C_HDR) (vc-4.5), > 0. Default 0.05: with the thesis'
    #: constant 0.03 and luminance in kcd/m^2 the corrected sky is a dim grey-blue; 0.05 gives a mid-blue zenith at
    #: T = 2.5 without saturating the sky around the sun (figures/vc/fig-4.6.png uses the thesis' 0.03).
    sky_exposure: float = 0.05
    #: Weather-map coverage in [0, 1] (fraction of the sky the cloud fields may occupy). Default 0.45.
    coverage: float = 0.45
    #: Weather-map precipitation in [0, 1] (darkens clouds through vc-2.31's a). Default 0.2.
    precipitation: float = 0.2
    #: Mean cloud type in [0, 1]: 0 stratus, 0.5 stratocumulus, 1 cumulus, and its spread across the weather map
    #: in [0, 1]. Defaults 0.75 and 0.25 (types 0.5 .. 1; pywarp.clouds.textures.WeatherMapSettings).
    cloud_type: float = 0.75
    cloud_type_variation: float = 0.25
    #: Reading of the undefined threshold C of vc-2.29: 'one_minus_coverage' (C = 1 - D_h, default: more coverage
    #: gives more cloud) or 'coverage' (C = D_h, the literal reading: clouds survive only where 0 < D_h < B D_v,
    #: as rings around covered areas). See cclouds/cloudscape.c.
    coverage_threshold: str = "one_minus_coverage"
    #: Terms of the lighting energy vc-2.31 (Beer's law, powder effect); switching one off replaces it by 1, to show
    #: what each contributes (fig 2.17). Default: both on, the formula as printed.
    beer: bool = True
    powder: bool = True
    #: Seed of every texture (uint32). The same seed gives the same image.
    seed: int = 0
    #: Camera position: altitude above the ground (km) and horizontal position (km); view: yaw (deg, 0 = -z,
    #: positive towards +x) and pitch (deg above the horizon); vertical field of view (deg).
    #: Default: 0.3 km above the ground, looking 20 deg up with a 60 deg field of view (the horizon near the bottom
    #: edge, the cloud bases overhead).
    camera_altitude_km: float = 0.3
    camera_x_km: float = 0.0
    camera_z_km: float = 0.0
    camera_yaw_deg: float = 0.0
    camera_pitch_deg: float = 20.0
    fov_y_deg: float = 60.0
    #: Cloud layer (vc-A14): Earth radius, base and top altitude (km). See pywarp.kernels.raymarch for the reasons.
    earth_radius_km: float = R.EARTH_RADIUS_KM
    layer_base_km: float = R.LAYER_BASE_KM
    layer_top_km: float = R.LAYER_TOP_KM
    #: Wind: speed (km/h) and the direction it blows towards (deg, 0 = -z); time (s) moves the weather map and the
    #: detail noise (detail at 1.5x the speed, plus a slow rise: billowing). Default 30 km/h, t = 0.
    wind_speed_kmh: float = 30.0
    wind_direction_deg: float = 60.0
    time_s: float = 0.0
    #: The optimisations of vc fig 4.17: adaptive view-sample count (vc-A18), early termination (vc-A21),
    #: temporal reprojection (vc-A26). Default: adaptive and early exit on, reprojection off (single images).
    adaptive_samples: bool = True
    early_exit: bool = True
    reprojection: bool = False
    #: vc-A27 neighbourhood averaging of reprojected pixels: 1 (exact sampling) or an odd n (n x n box). Default 1.
    reprojection_neighbourhood: int = 1
    #: Ray jitter against banding (vc-A23): 'tilt' (the thesis), 'offset', 'none'.
    jitter: str = "tilt"
    #: Light samples with the detail erosion (True, the thesis' density) or the base shape only (False: cheaper).
    light_detail: bool = True
    #: Texture sizes (powers of two): base 128^3 (vc-A9) and detail 32^3 (vc-A10) as in the thesis; curl 128^2 and
    #: weather 512^2 (not given; see pywarp.clouds.textures).
    base_size: int = 128
    detail_size: int = 32
    curl_size: int = 128
    weather_size: int = 512
    #: Henyey-Greenstein g of vc-2.31 and the extinction per unit density (1/km). See cclouds/cloudscape.c.
    g: float = 0.2
    sigma_per_km: float = 30.0
    #: View samples at the zenith / horizon (vc-A18: 64 / 128).
    samples_min: int = 64
    samples_max: int = 128
    #: Warp device ('cpu' or 'cuda:N') and worker threads (None: one per core).
    device: str = "cpu"
    threads: int | None = None
    #: Advanced: any other field of ``ccl_cloudscape_params`` by name (e.g. {"base_scale_km": 8.0,
    #: "sun_colour": (30, 29, 27)}); defaults and reasons in cclouds/cloudscape.c. Checked by ccl_cloudscape_check.
    advanced: dict = field(default_factory=dict)

    def validate(self) -> "CloudscapeSettings":
        for name in ("width", "height"):
            v = getattr(self, name)
            _check(isinstance(v, (int, np.integer)) and not isinstance(v, bool) and 1 <= v <= 8192, name,
                   "an integer in [1, 8192] pixels", v)
        _check(self.sky in SKIES, "sky", f"one of {', '.join(SKIES)}", self.sky)
        _check(_finite(self.sun_elevation_deg) and -90.0 <= self.sun_elevation_deg <= 90.0, "sun_elevation_deg",
               "in [-90, 90] degrees", self.sun_elevation_deg)
        if self.sky == "preetham":
            _check(self.sun_elevation_deg >= 0.0, "sun_elevation_deg",
                   "in [0, 90] degrees for the Preetham sky (the model is not defined for a sun below the horizon)",
                   self.sun_elevation_deg)
        _check(_finite(self.sun_azimuth_deg), "sun_azimuth_deg", "a finite angle in degrees", self.sun_azimuth_deg)
        _check(_finite(self.turbidity) and 2.0 <= self.turbidity <= 10.0, "turbidity",
               "in [2, 10] (the range of Preetham's fit)", self.turbidity)
        _check(self.sky_variant in ("corrected", "thesis"), "sky_variant", "'corrected' or 'thesis'", self.sky_variant)
        _check(_finite(self.sky_exposure) and 0.0 < self.sky_exposure <= 10.0, "sky_exposure", "in (0, 10]",
               self.sky_exposure)
        _check(self.coverage_threshold in COVERAGE_THRESHOLDS, "coverage_threshold",
               f"one of {', '.join(COVERAGE_THRESHOLDS)}", self.coverage_threshold)
        for name in ("coverage", "precipitation", "cloud_type", "cloud_type_variation"):
            v = getattr(self, name)
            _check(_finite(v) and 0.0 <= v <= 1.0, name, "in [0, 1]", v)
        _check(isinstance(self.seed, (int, np.integer)) and not isinstance(self.seed, bool)
               and 0 <= self.seed <= 0xFFFFFFFF, "seed", "an integer in [0, 2^32 - 1]", self.seed)
        _check(_finite(self.earth_radius_km) and self.earth_radius_km > 0, "earth_radius_km", "> 0 km",
               self.earth_radius_km)
        _check(_finite(self.layer_base_km) and self.layer_base_km >= 0, "layer_base_km", ">= 0 km", self.layer_base_km)
        _check(_finite(self.layer_top_km) and self.layer_top_km > self.layer_base_km, "layer_top_km",
               f"> layer_base_km ({self.layer_base_km} km)", self.layer_top_km)
        _check(_finite(self.camera_altitude_km) and -0.0 <= self.camera_altitude_km <= 1000.0, "camera_altitude_km",
               "in [0, 1000] km (above the ground)", self.camera_altitude_km)
        for name in ("camera_x_km", "camera_z_km", "camera_yaw_deg", "time_s", "wind_direction_deg"):
            _check(_finite(getattr(self, name)), name, "finite", getattr(self, name))
        _check(_finite(self.camera_pitch_deg) and -89.0 <= self.camera_pitch_deg <= 89.0, "camera_pitch_deg",
               "in [-89, 89] degrees", self.camera_pitch_deg)
        _check(_finite(self.fov_y_deg) and 1.0 <= self.fov_y_deg <= 170.0, "fov_y_deg", "in [1, 170] degrees",
               self.fov_y_deg)
        _check(_finite(self.wind_speed_kmh) and 0.0 <= self.wind_speed_kmh <= 1000.0, "wind_speed_kmh",
               "in [0, 1000] km/h", self.wind_speed_kmh)
        _check(_finite(self.reprojection_neighbourhood) and int(self.reprojection_neighbourhood) % 2 == 1
               and 1 <= self.reprojection_neighbourhood <= 9, "reprojection_neighbourhood", "an odd integer in [1, 9]",
               self.reprojection_neighbourhood)
        _check(self.jitter in JITTERS, "jitter", f"one of {', '.join(JITTERS)}", self.jitter)
        for name, lo, hi in (("base_size", 4, 512), ("detail_size", 4, 512), ("curl_size", 4, 8192),
                             ("weather_size", 4, 8192)):
            v = getattr(self, name)
            _check(isinstance(v, (int, np.integer)) and lo <= v <= hi and (v & (v - 1)) == 0, name,
                   f"a power of two in [{lo}, {hi}]", v)
        _check(_finite(self.g) and -1.0 < self.g < 1.0, "g", "in (-1, 1)", self.g)
        _check(_finite(self.sigma_per_km) and 0.0 < self.sigma_per_km <= 1000.0, "sigma_per_km", "in (0, 1000] 1/km",
               self.sigma_per_km)
        _check(isinstance(self.samples_min, (int, np.integer)) and 1 <= self.samples_min <= 4096, "samples_min",
               "an integer in [1, 4096]", self.samples_min)
        _check(isinstance(self.samples_max, (int, np.integer)) and self.samples_min <= self.samples_max <= 4096,
               "samples_max", f"an integer in [samples_min ({self.samples_min}), 4096]", self.samples_max)
        _check(self.threads is None or (isinstance(self.threads, int) and self.threads >= 1), "threads",
               "None or an integer >= 1", self.threads)
        _check(isinstance(self.advanced, dict), "advanced", "a dict", self.advanced)
        if self.advanced:
            _check_params(param_values(self))
        return self

    # --- derived quantities ------------------------------------------------------------------------------------------
    def layer(self) -> R.CloudLayer:
        return R.CloudLayer(self.earth_radius_km, self.layer_base_km, self.layer_top_km)

    def wind_offsets(self) -> tuple[tuple[float, float], tuple[float, float, float]]:
        """(weather offset (x, z), detail offset (x, y, z)) in km after ``time_s`` seconds of wind."""
        dist = self.wind_speed_kmh * self.time_s / 3600.0
        a = math.radians(self.wind_direction_deg)
        dx, dz = math.sin(a), -math.cos(a)
        # the lookup moves against the wind so that the clouds move with it
        weather = (-dx * dist, -dz * dist)
        detail = (-1.5 * dx * dist, -0.1 * dist, -1.5 * dz * dist)
        return weather, detail

    def sun(self) -> np.ndarray:
        return S.sun_direction(self.sun_elevation_deg, self.sun_azimuth_deg)


# --- camera -------------------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class CameraPose:
    """Camera position (km; y up, ground at y = 0 under the origin), yaw/pitch (deg) and vertical FOV (deg)."""

    x_km: float = 0.0
    altitude_km: float = 0.3
    z_km: float = 0.0
    yaw_deg: float = 0.0
    pitch_deg: float = 8.0
    fov_y_deg: float = 60.0

    @classmethod
    def from_settings(cls, s: CloudscapeSettings) -> "CameraPose":
        return cls(s.camera_x_km, s.camera_altitude_km, s.camera_z_km, s.camera_yaw_deg, s.camera_pitch_deg,
                   s.fov_y_deg)

    def forward(self) -> np.ndarray:
        y, p = math.radians(self.yaw_deg), math.radians(self.pitch_deg)
        return np.array([math.sin(y) * math.cos(p), math.sin(p), -math.cos(y) * math.cos(p)])

    def camera(self, width: int, height: int) -> R.Camera:
        """The vc-A25 camera matrices (``pywarp.kernels.raymarch.camera_look_at``)."""
        eye = np.array([self.x_km, self.altitude_km, self.z_km])
        return R.camera_look_at(eye, eye + self.forward(), (0.0, 1.0, 0.0), math.radians(self.fov_y_deg),
                                width / height, 0.01, 1000.0)


# --- sky models (vc-A31) --------------------------------------------------------------------------------------------------

class SkyModel(ABC):
    """A sky model writes the background colour (display-linear RGB) of the pixels a frame renders.

    Subclass it for your own sky: implement :meth:`update` (per-frame constants) and :meth:`render` (launch a kernel
    over the frame buffer; see :class:`GradientSky` for the pattern). The technique calls ``update`` when the
    settings change and ``render`` every frame."""

    kind: int = -1

    def __init__(self, settings: CloudscapeSettings):
        self.update(settings)

    @abstractmethod
    def update(self, settings: CloudscapeSettings) -> None:
        ...

    def render(self, frame_buffer: wp.array, camera: R.Camera, frame: int, reprojection: bool,
               params: K.CloudscapeParams, launcher: TileLauncher) -> None:
        h, w = frame_buffer.shape[0], frame_buffer.shape[1]
        rows, cols = (RP.reprojection_grid(w, h)[::-1]) if reprojection else (h, w)
        launcher.launch(K.sky_kernel, rows, cols,
                        [self.kind, wp.vec3(*self.sun.tolist()), self.preetham, self.gradient, params,
                         camera.mat44("inv_view_proj_rot"), camera.eye_vec3(), frame, int(reprojection)],
                        [frame_buffer])


class GradientSky(SkyModel):
    """vc-A28: light-to-dark blue by the view ray's y plus a sun glow (colours: pywarp.kernels.sky)."""

    kind = K.SKY_GRADIENT

    def update(self, settings: CloudscapeSettings) -> None:
        self.sun = settings.sun()
        self.gradient = S.gradient_params()
        self.preetham = S.Preetham()  # unused by the kernel for this kind


class PreethamSky(SkyModel):
    """vc-A29: the Preetham 1999 analytic daylight model, tone mapped (vc-4.5)."""

    kind = K.SKY_PREETHAM

    def update(self, settings: CloudscapeSettings) -> None:
        self.sun = settings.sun()
        theta_s = math.radians(90.0 - settings.sun_elevation_deg)
        self.preetham = S.preetham_params(settings.turbidity, min(theta_s, float(np.float32(math.pi / 2))),
                                          exposure=settings.sky_exposure, variant=settings.sky_variant)
        self.gradient = S.gradient_params()


def make_sky(settings: CloudscapeSettings) -> SkyModel:
    return PreethamSky(settings) if settings.sky == "preetham" else GradientSky(settings)


# --- textures (vc-A32) ----------------------------------------------------------------------------------------------------

@dataclass
class RenderTextures:
    """The four textures as the renderer reads them: float32 RGBA NumPy arrays with power-of-two edges (detail A = 0,
    curl BA = 0), the layout of ``ccl_cloud_textures``, and their Warp copies (``wp.vec4`` arrays)."""

    base: np.ndarray     # (n, n, n, 4)
    detail: np.ndarray   # (m, m, m, 4)
    curl: np.ndarray     # (k, k, 4)
    weather: np.ndarray  # (w, w, 4)
    device: str = "cpu"
    _wp: dict = field(default_factory=dict, repr=False)

    @staticmethod
    def _rgba(a: np.ndarray) -> np.ndarray:
        a = np.asarray(a, dtype=np.float32)
        if a.shape[-1] == 4:
            return np.ascontiguousarray(a)
        pad = np.zeros(a.shape[:-1] + (4 - a.shape[-1],), dtype=np.float32)
        return np.ascontiguousarray(np.concatenate([a, pad], axis=-1))

    @classmethod
    def from_textures(cls, t: T.CloudTextures, device: str = "cpu") -> "RenderTextures":
        """From the checked textures of a :class:`pywarp.clouds.textures.TextureGenerator`."""
        if t.weather_map.shape[0] != t.weather_map.shape[1]:
            raise ValueError(f"the renderer needs a square weather map, got {t.weather_map.shape[:2]}")
        return cls(cls._rgba(t.base_shape), cls._rgba(t.detail_shape), cls._rgba(t.curl_noise),
                   cls._rgba(t.weather_map), device)

    @classmethod
    def generate(cls, settings: CloudscapeSettings, generator: T.TextureGenerator | None = None) -> "RenderTextures":
        """Textures for ``settings`` from ``generator`` (default :class:`pywarp.clouds.textures.BasicTextureGenerator`, which
        caches them per settings in memory and on disk)."""
        gen = generator if generator is not None else T.BasicTextureGenerator(device=settings.device,
                                                                              workers=settings.threads)
        t = gen.textures(T.BaseShapeSettings(size=settings.base_size, seed=settings.seed),
                         T.DetailShapeSettings(size=settings.detail_size, seed=settings.seed),
                         T.CurlNoiseSettings(size=settings.curl_size, seed=settings.seed),
                         T.WeatherMapSettings(size=settings.weather_size, seed=settings.seed,
                                              coverage=settings.coverage, precipitation=settings.precipitation,
                                              cloud_type=settings.cloud_type,
                                              cloud_type_variation=settings.cloud_type_variation))
        return cls.from_textures(t, settings.device)

    def warp(self) -> tuple:
        if not self._wp:
            self._wp = {name: wp.array(getattr(self, name), dtype=wp.vec4, device=self.device)
                        for name in ("base", "detail", "curl", "weather")}
        d = self._wp
        return d["base"], d["detail"], d["curl"], d["weather"]


# --- parameters shared by Warp and C --------------------------------------------------------------------------------------

def param_values(settings: CloudscapeSettings) -> dict:
    """The ``ccl_cloudscape_params`` fields for ``settings`` (defaults of ``ccl_cloudscape_params_default`` for
    everything the settings do not expose), as Python values -- the one source of both the Warp struct and the C
    struct."""
    from ..core.binding import ffi, lib

    f = ffi()
    p = f.new("ccl_cloudscape_params *")
    lib().ccl_cloudscape_params_default(p)
    layer = settings.layer()
    weather_off, detail_off = settings.wind_offsets()
    v = {
        "centre": layer.centre, "r_earth": layer.r_earth, "r_inner": layer.r_inner, "r_outer": layer.r_outer,
        "base_scale_km": p.base_scale_km, "detail_scale_km": p.detail_scale_km,
        "weather_scale_km": p.weather_scale_km, "curl_scale_km": p.curl_scale_km,
        "curl_strength_km": p.curl_strength_km, "weather_offset": weather_off, "detail_offset": detail_off,
        "sigma": settings.sigma_per_km, "sigma_light": settings.sigma_per_km,
        "absorption_base": p.absorption_base, "absorption_precip": p.absorption_precip, "g": settings.g,
        "sun_colour": tuple(p.sun_colour), "ambient_bottom": tuple(p.ambient_bottom),
        "ambient_top": tuple(p.ambient_top), "samples_min": settings.samples_min,
        "samples_max": settings.samples_max, "adaptive_samples": int(settings.adaptive_samples),
        "early_exit": int(settings.early_exit), "exit_eps": p.exit_eps, "light_step_km": p.light_step_km,
        "light_cone_angle": p.light_cone_angle, "light_far_factor": p.light_far_factor,
        "light_detail": int(settings.light_detail), "jitter_mode": JITTERS[settings.jitter],
        "jitter_amount": p.jitter_amount, "gradient_clamp": p.gradient_clamp,
        "detail_direction": p.detail_direction, "ground_colour": tuple(p.ground_colour),
        "coverage_threshold": COVERAGE_THRESHOLDS[settings.coverage_threshold], "beer": int(settings.beer),
        "powder": int(settings.powder),
    }
    for name, value in settings.advanced.items():
        if name not in v or name in ("centre", "r_earth", "r_inner", "r_outer"):
            raise ValueError(f"advanced: unknown parameter {name!r}; known: {', '.join(sorted(v)[4:])}")
        if isinstance(v[name], tuple) != isinstance(value, (tuple, list)) or (
                isinstance(value, (tuple, list)) and len(value) != len(v[name])):
            raise ValueError(f"advanced: {name} must be like {v[name]!r}, got {value!r}")
        v[name] = tuple(value) if isinstance(value, (tuple, list)) else value
    return v


def _check_params(values: dict) -> None:
    """Run ccl_cloudscape_check on the parameter values alone (dummy 1-texel textures, a valid sky)."""
    from ..core.binding import ffi, lib

    f, lb = ffi(), lib()
    dummy = np.zeros(4, dtype=np.float32)
    tex = f.new("ccl_cloud_textures *")
    for name in ("base", "detail", "curl", "weather"):
        setattr(tex, name, f.cast("const float *", f.from_buffer("float[]", dummy)))
        setattr(tex, f"{name}_size", 1)
    sky = f.new("ccl_cloudscape_sky *")
    sky.kind = lb.CCL_SKY_GRADIENT
    sky.sun[1] = 1.0
    out = f.new("const char **")
    if lb.ccl_cloudscape_check(c_params(values), tex, sky, out) != 0:
        name = f.string(out[0]).decode()
        raise ValueError(f"{name} is out of range (ccl_cloudscape_check), got {values.get(name)!r}")


def warp_params(values: dict) -> K.CloudscapeParams:
    s = K.CloudscapeParams()
    for name, v in values.items():
        t = K.CloudscapeParams.vars[name].type
        if t in (int, wp.int32):
            setattr(s, name, int(v))
        elif t in (float, wp.float32):
            setattr(s, name, float(v))
        else:
            setattr(s, name, t(*[float(x) for x in v]))
    return s


def c_params(values: dict):
    from ..core.binding import ffi

    p = ffi().new("ccl_cloudscape_params *")
    p.layer.centre.x, p.layer.centre.y, p.layer.centre.z = values["centre"]
    p.layer.r_earth, p.layer.r_inner, p.layer.r_outer = values["r_earth"], values["r_inner"], values["r_outer"]
    for name, v in values.items():
        if name in ("centre", "r_earth", "r_inner", "r_outer"):
            continue
        if isinstance(v, (tuple, list)):
            arr = getattr(p, name)
            for i, x in enumerate(v):
                arr[i] = x
        else:
            setattr(p, name, v)
    return p


# --- the technique (vc-A30, A33) ------------------------------------------------------------------------------------------

class CloudscapeTechnique:
    """The volumetric-clouds visualization technique: ``init`` (textures, sky), ``update`` (settings, time),
    ``render`` (one frame for a camera pose), ``resize``. Holds the frame buffers and the previous camera for the
    temporal reprojection (vc-A26)."""

    def __init__(self, settings: CloudscapeSettings | None = None, generator=None, sky: SkyModel | None = None,
                 textures: RenderTextures | None = None):
        self.settings = (settings or CloudscapeSettings()).validate()
        self.launcher = shared_launcher(self.settings.device, self.settings.threads)
        self.device = self.launcher.device
        self.generator = generator
        self.textures = textures
        self.sky = sky
        self.frame = 0
        self._prev_camera = None
        self._buffers = None
        self.init()

    # vc-A33: init / update / render, and the resize notification
    def init(self) -> None:
        if self.textures is None:
            self.textures = RenderTextures.generate(self.settings, self.generator)
        if self.sky is None:
            self.sky = make_sky(self.settings)
        self.params = warp_params(param_values(self.settings))
        self.resize(self.settings.width, self.settings.height)

    def update(self, **changes) -> None:
        """Change settings (e.g. ``time_s``, ``sun_elevation_deg``); textures are regenerated only when a texture
        setting changes."""
        old = self.settings
        new = replace(old, **changes).validate()
        tex_fields = ("seed", "coverage", "precipitation", "cloud_type", "cloud_type_variation", "base_size",
                      "detail_size", "curl_size", "weather_size")
        self.settings = new
        if any(getattr(old, f) != getattr(new, f) for f in tex_fields):
            self.textures = RenderTextures.generate(new, self.generator)
        if any(getattr(old, f) != getattr(new, f) for f in ("sky", "sun_elevation_deg", "sun_azimuth_deg",
                                                             "turbidity", "sky_variant", "sky_exposure")):
            if type(self.sky) in (GradientSky, PreethamSky):
                self.sky = make_sky(new)  # the sky kind may have changed
            else:
                self.sky.update(new)  # a user's own sky model
        self.params = warp_params(param_values(new))
        if (old.width, old.height) != (new.width, new.height):
            self.resize(new.width, new.height)

    def resize(self, width: int, height: int) -> None:
        self.settings.width, self.settings.height = int(width), int(height)
        self.settings.validate()
        gw, gh = RP.reprojection_grid(width, height)
        dev = self.device
        self._buffers = {
            "current": wp.zeros((height, width, 3), dtype=float, device=dev),
            "previous": wp.zeros((height, width, 3), dtype=float, device=dev),
            "out": wp.zeros((height, width, 3), dtype=float, device=dev),
            "reduced": wp.zeros((gh, gw, 3), dtype=float, device=dev),
            "samples": wp.zeros((height, width), dtype=wp.int32, device=dev),
            "encoded": wp.zeros((height, width, 3), dtype=float, device=dev),
        }
        self._prev_camera = None

    def camera_in_layer_or_above(self, pose: CameraPose) -> bool:
        return pose.altitude_km >= self.settings.layer_base_km

    def render(self, pose: CameraPose | None = None, reprojection: bool | None = None,
               encode: bool = True) -> np.ndarray:
        """Render one frame; returns uint8 sRGB (height, width, 3), or the display-linear float frame when
        ``encode=False``. Reprojection (default: the setting) falls back to a full render when the camera is inside
        or above the layer (vc-A24) and on the first frame."""
        s = self.settings
        pose = pose or CameraPose.from_settings(s)
        cam = pose.camera(s.width, s.height)
        reproj = s.reprojection if reprojection is None else bool(reprojection)
        if reproj and self.camera_in_layer_or_above(pose):
            reproj = False  # vc-A24: the view ray does not always hit the inner sphere
        b = self._buffers
        h, w = s.height, s.width
        layer = s.layer()
        base, detail, curl, weather = self.textures.warp()
        sun = wp.vec3(*self.sky.sun.tolist())
        target = b["current"] if reproj else b["out"]
        self.sky.render(target, cam, self.frame, reproj, self.params, self.launcher)
        rows, cols = (RP.reprojection_grid(w, h)[::-1]) if reproj else (h, w)
        self.launcher.launch(K.clouds_kernel, rows, cols,
                             [self.params, base, detail, curl, weather, sun, cam.mat44("inv_view_proj_rot"),
                              cam.eye_vec3(), self.frame, int(reproj)], [target, b["reduced"], b["samples"]])
        if reproj:
            history = int(self._prev_camera is not None)
            prev = self._prev_camera or cam
            self.launcher.launch(RP.reproject_frame_kernel, h, w,
                                 [b["current"], b["previous"], b["reduced"], self.frame,
                                  cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), prev.mat44("view_proj"),
                                  layer.centre_vec3(), layer.r_inner, int(s.reprojection_neighbourhood), history],
                                 [b["out"]])
        # the final frame becomes the previous one (ping-pong)
        b["previous"], b["out"] = b["out"], b["previous"]
        final = b["previous"]
        self._prev_camera = cam if reproj or s.reprojection else None
        self.frame += 1
        if not encode:
            return final.numpy().copy()
        self.launcher.launch(K.encode_kernel, h, w, [final], [b["encoded"]])
        out = b["encoded"].numpy()
        if not np.all(np.isfinite(out)):
            raise RuntimeError("the render produced non-finite pixels")
        return (out * 255.0 + 0.5).astype(np.uint8)

    def samples_taken(self) -> np.ndarray:
        """View samples marched per pixel in the last frame (pixels not rendered keep older counts)."""
        return self._buffers["samples"].numpy().copy()


def render_image(settings: CloudscapeSettings | None = None, pose: CameraPose | None = None) -> np.ndarray:
    """One uint8 sRGB image (height, width, 3) of the cloudscape."""
    return CloudscapeTechnique(settings).render(pose, reprojection=False)


# --- the C reference ------------------------------------------------------------------------------------------------------

def c_sky(settings: CloudscapeSettings):
    from ..core.binding import ffi, lib, status_error

    f, lb = ffi(), lib()
    sky = f.new("ccl_cloudscape_sky *")
    sun = settings.sun()
    sky.sun[0], sky.sun[1], sky.sun[2] = (float(x) for x in sun)
    if settings.sky == "preetham":
        sky.kind = lb.CCL_SKY_PREETHAM
        theta_s = min(math.radians(90.0 - settings.sun_elevation_deg), float(np.float32(math.pi / 2)))
        status_error(lb.ccl_preetham_init(settings.turbidity, theta_s, settings.sky_exposure,
                                          0 if settings.sky_variant == "corrected" else 1, f.addressof(sky.preetham)),
                     "ccl_preetham_init")
    else:
        sky.kind = lb.CCL_SKY_GRADIENT
        lb.ccl_sky_gradient_defaults(f.addressof(sky.gradient))
    return sky


def c_textures(textures: RenderTextures):
    """A ``ccl_cloud_textures`` pointing into the NumPy arrays of ``textures`` (which must outlive it: the cffi
    object keeps a reference to each buffer)."""
    from ..core.binding import ffi

    f = ffi()
    tex = f.new("ccl_cloud_textures *")
    buffers = []
    for name in ("base", "detail", "curl", "weather"):
        arr = getattr(textures, name)
        buf = f.from_buffer("float[]", arr)
        buffers.append(buf)
        setattr(tex, name, f.cast("const float *", buf))
        setattr(tex, f"{name}_size", arr.shape[0])
    _KEEP_ALIVE[tex] = buffers
    return tex


_KEEP_ALIVE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # cffi struct -> the buffers it points into


def c_camera(cam: R.Camera):
    from ..core.binding import ffi

    c = ffi().new("ccl_camera *")
    c.eye.x, c.eye.y, c.eye.z = (float(v) for v in cam.eye)
    for name in ("view", "proj", "view_proj", "inv_view_proj", "inv_view_proj_rot"):
        arr = getattr(c, name)
        for i, v in enumerate(cam.column_major(name)):
            arr[i] = float(v)
    return c


def render_pixels_c(settings: CloudscapeSettings, textures: RenderTextures, xs, ys, pose: CameraPose | None = None,
                    frame: int = 0) -> np.ndarray:
    """``ccl_cloudscape_pixel`` (the scalar C reference) at pixels (xs[k], ys[k]): display-linear RGB (k, 3)."""
    from ..core.binding import ffi, lib

    f, lb = ffi(), lib()
    s = settings.validate()
    pose = pose or CameraPose.from_settings(s)
    params = c_params(param_values(s))
    tex = c_textures(textures)
    sky = c_sky(s)
    cam = c_camera(pose.camera(s.width, s.height))
    field_ = f.new("const char **")
    if lb.ccl_cloudscape_check(params, tex, sky, field_) != 0:
        raise ValueError(f"ccl_cloudscape_check rejected {f.string(field_[0]).decode()}")
    out = np.empty((len(xs), 3), dtype=np.float32)
    rgb = f.new("float[3]")
    for k, (x, y) in enumerate(zip(xs, ys)):
        lb.ccl_cloudscape_pixel(params, tex, sky, cam, int(x), int(y), s.width, s.height, frame, rgb)
        out[k] = rgb[0], rgb[1], rgb[2]
    return out


def render_pixels_warp(technique: CloudscapeTechnique, xs, ys, pose: CameraPose | None = None,
                       frame: int = 0) -> np.ndarray:
    """:func:`pywarp.kernels.cloudscape.cloudscape_pixel` at pixels (xs[k], ys[k]) -- the Warp side of the comparison
    with :func:`render_pixels_c`."""
    s = technique.settings
    pose = pose or CameraPose.from_settings(s)
    cam = pose.camera(s.width, s.height)
    base, detail, curl, weather = technique.textures.warp()
    dev = technique.device
    xa = wp.array(np.asarray(xs, dtype=np.int32), dtype=wp.int32, device=dev)
    ya = wp.array(np.asarray(ys, dtype=np.int32), dtype=wp.int32, device=dev)
    out = wp.zeros((len(xs), 3), dtype=float, device=dev)
    sky = technique.sky
    wp.launch(K.pixels_kernel, dim=len(xs),
              inputs=[technique.params, base, detail, curl, weather, sky.kind, wp.vec3(*sky.sun.tolist()),
                      sky.preetham, sky.gradient, cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), xa, ya, s.width,
                      s.height, frame], outputs=[out], device=dev)
    return out.numpy()


def flythrough_path(frames: int, settings: CloudscapeSettings) -> list[CameraPose]:
    """The camera path of ``pywarp animate``: a climb from ``settings.camera_altitude_km`` below the layer, through
    it, to 1.5 km above its top, flying forward along the camera heading at 600 km/h-equivalent per frame step; the
    pitch eases from looking up (below) to looking slightly down (above) so that the cloud tops come into view."""
    if frames < 1:
        raise ValueError(f"frames must be >= 1, got {frames}")
    s = settings
    start = s.camera_altitude_km
    end = max(s.layer_top_km + 1.5, start)
    poses = []
    yaw = math.radians(s.camera_yaw_deg)
    for i in range(frames):
        u = i / max(frames - 1, 1)
        ease = 0.5 - 0.5 * math.cos(math.pi * u)
        alt = start + (end - start) * ease
        dist = 12.0 * u  # km flown forward
        pitch = s.camera_pitch_deg + (-12.0 - s.camera_pitch_deg) * ease
        poses.append(CameraPose(s.camera_x_km + math.sin(yaw) * dist, alt, s.camera_z_km - math.cos(yaw) * dist,
                                s.camera_yaw_deg, pitch, s.fov_y_deg))
    return poses


def render_frame_c(settings: CloudscapeSettings, textures: RenderTextures, pose: CameraPose | None = None,
                   frame: int = 0) -> np.ndarray:
    """A whole frame with the C reference ``ccl_cloudscape_render`` (one thread): sRGB floats (height, width, 3)."""
    from ..core.binding import ffi, lib, status_error

    f, lb = ffi(), lib()
    s = settings.validate()
    pose = pose or CameraPose.from_settings(s)
    params = c_params(param_values(s))
    tex = c_textures(textures)
    out = np.empty((s.height, s.width, 3), dtype=np.float32)
    status = lb.ccl_cloudscape_render(params, tex, c_sky(s), c_camera(pose.camera(s.width, s.height)), s.width,
                                      s.height, frame, f.from_buffer("float[]", out), out.size)
    status_error(status, "ccl_cloudscape_render")
    return out
