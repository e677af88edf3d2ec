"""Settings of the rain scene (rr), each field declared once with its parameter spec (:mod:`pywarp.core.params`).

The text (Rejdova 2009, after Rousseau et al. 2006) fixes the spawn box, the respawn level, the 4x slow-down, the
Gaussian sizes around 1.3 mm, the 512 x 512 mask and capture (our capture's default: 256, measured), the capture's
150 deg FOV and the 7 streak taps; every other value is ours, with its reason. This module imports neither Warp nor
the C library.
"""
from __future__ import annotations

from dataclasses import dataclass

from ..core.display import exposure_param, tonemap_param
from ..core.params import Settings, param

#: Drop shapes of Table 2.1 (a in mm), selected by the T key (rr-tab-A).
SHAPES = ("0.5", "1.0", "3.0", "4.5")
#: Mask methods (rr-alg-3.1.1; ccl_rain_mask_method order): sphere, the application's outline, the exact trace.
MASKS = ("sphere", "outline", "exact")
MODES = ("streaks", "drops")
#: Streak models of the compositing pass (``pywarp.kernels.particles.STREAKS``): the drop integrated over the
#: exposure (Garg & Nayar 2004), or the text's 7 taps over a rectangle (rr-code-5.2.4).
STREAK_MODELS = ("physical", "thesis")
FILTERS = ("nearest", "linear")
#: A built-in analytic background (sky gradient, horizon, checkered ground, coloured posts): fast, for tests and
#: figures. Any registered scene other than rain is a background too.
PANORAMA = "panorama"
#: The rain scene's own settings for a background scene, under ``background_options`` (which overrides them key by
#: key); a scene not named here has its own defaults.
#: terrain (the default background): the pt landscape under an overcast rain sky -- a dark grey sky under a lighter
#: grey cloud deck (its clouds smaller: a broken, low ceiling whose texture shows), no sun glow, light mostly ambient
#: (diffuse 0.45, ambient 0.55: no hard shadows under cloud), and haze: fog 0.006 (half the light gone at ln 2 / 0.006
#: = 115 units, the far hills grey).
#: clouds: an overcast, dark rain sky seen from 50 m; the ground three times the cloudscape's albedo (its default is
#: exposed for the sun above the clouds; under them the ground was near black) and in patches (ground_variation 0.8:
#: albedo 0.2 - 1.8 times its mean, fields and woods; a uniform ground seen from 50 m is a featureless plane).
#: A background's 8-bit image is the plain clamp of its colours (display transform ``none`` at 0 EV,
#: pywarp.core.display): the drops refract and the streaks composite display-encoded colours, and a display transform
#: belongs once at the end.
_PLAIN = {"tonemap": "none", "exposure_ev": 0.0}
BACKGROUND_OPTIONS = {
    "terrain": {"sky_colour": (0.42, 0.45, 0.49), "sun_colour": (0.0, 0.0, 0.0), "cloud_colour": (0.72, 0.74, 0.76),
                "cloud_scale": 60.0, "light_diffuse": 0.45, "light_ambient": 0.55, "fog_density": 0.006, **_PLAIN},
    "clouds": {"coverage": 0.75, "precipitation": 0.7, "camera_altitude_km": 0.05,
               "ground_albedo": (0.12, 0.14, 0.08), "ground_variation": 0.8, **_PLAIN},
}


def _check_background(obj, name, v):
    if v == PANORAMA:
        return
    from ..core.scenes import scenes

    names = [n for n in scenes() if n != "rain"]
    if v not in names:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, [PANORAMA] + names))}, got {v!r}")


def background_fields(background: str) -> set[str]:
    """Names of the settings fields of a background (none for the panorama)."""
    if background == PANORAMA:
        return set()
    import dataclasses

    from ..core.scenes import scene

    return {f.name for f in dataclasses.fields(scene(background).settings)}


def check_background_options(background: str, options: dict, name: str = "background_options") -> None:
    """A key of ``options`` that is no field of the background's settings is an error that names it and the
    background (checked against the scene the options are given for: a key is never dropped silently), with the
    closest field when one is close."""
    from ..core.params import did_you_mean

    fields = background_fields(background)
    unknown = sorted(set(options) - fields)
    if unknown:
        raise ValueError(f"{name} has no field(s) {unknown} in "
                         + ("the built-in panorama (it has no settings)" if background == PANORAMA
                            else f"scene {background!r}") + did_you_mean(unknown[0], sorted(fields)))


def parse_background_options(background: str, options: dict) -> dict:
    """``options`` with every string value of a non-string field parsed by that field's spec (the command line's
    ``--background-set KEY=VALUE`` gives strings; tuples as comma-separated numbers), errors naming
    ``--background-set KEY``."""
    if background == PANORAMA or not options:
        return dict(options)
    from ..core.params import specs
    from ..core.scenes import scene

    by_name = {p.name: p for p in specs(scene(background).settings)}
    out = {}
    for k, v in options.items():
        p = by_name.get(k)
        if isinstance(v, str) and p is not None and p.kind != "str":
            where = f"--background-set {k}"
            if p.kind == "floats":
                parts = v.split(",")
                if not all(_is_number(x) for x in parts):
                    raise ValueError(f"{where} must be comma-separated numbers, got {v!r}")
                v = p.validate([float(x) for x in parts], where)
            elif p.kind == "bool":
                low = v.strip().lower()
                if low not in ("true", "false", "1", "0", "yes", "no", "on", "off"):
                    raise ValueError(f"{where} must be true or false, got {v!r}")
                v = low in ("true", "1", "yes", "on")
            else:
                v = p.parse(v, where)
        out[k] = v
    return out


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _check_background_scale(obj, name, v):
    if v not in (1, 2, 4):
        raise ValueError(f"{name} must be 1, 2 or 4 (the reduction of the background's width and height), got {v}")


def _check_background_options(obj, name, v):
    check_background_options(obj.background, v, name)
    parse_background_options(obj.background, v)


def _check_size(obj, name, v):
    import numpy as np  # float32, as ccl_particles_params_check

    m, w = np.float32(obj.size_mm), np.float32(obj.size_spread_mm)
    if not (m - np.float32(0.5) * w >= np.float32(0.1) and m + np.float32(0.5) * w <= np.float32(4.5)):
        raise ValueError(f"{name} must keep size_mm +- size_spread_mm/2 within [0.1, 4.5] mm (Tables 2.1, 2.2), got "
                         f"{obj.size_mm:g} +- {obj.size_spread_mm:g}/2")


_G_IMAGE, _G_RAIN, _G_LOOK, _G_CAM, _G_BG, _G_RUN = "image", "rain", "drop look", "camera", "background", "runtime"
_G_LIGHT = "lights"


def _check_colour(obj, name, v):
    if any(c < 0.0 for c in v):
        raise ValueError(f"{name} must be >= 0 per channel, got {v!r}")


@dataclass(frozen=True)
class RainSettings(Settings):
    """Every parameter of a rain frame, with its unit, default and the reason for it. Immutable: change with
    ``dataclasses.replace`` or :meth:`pywarp.rain.technique.RainTechnique.update`."""

    #: ``background``: the background scene is rebuilt (and its frames cached again); ``mask``: the refraction mask
    #: is computed again; ``particles``: the particle system starts again
    INVALIDATES = Settings.INVALIDATES + ("background", "mask", "particles")

    width: int = param(640, unit="px", kind="int", lo=1, hi=8192, invalidates="size", group=_G_IMAGE,
                       doc="image width", reason="640 x 360: the issue's benchmark frame")
    height: int = param(360, unit="px", kind="int", lo=1, hi=8192, invalidates="size", group=_G_IMAGE,
                        doc="image height", reason="640 x 360: the issue's benchmark frame")
    mode: str = param("streaks", choices=MODES, group=_G_RAIN,
                      doc="drops (rr-code-5.2.3) or retinal-persistence streaks (rr-code-5.2.4); the F key",
                      reason="streaks: the text's final rain (figs 6.4, 6.6, 6.8)")
    drops: int = param(3000, kind="int", lo=0, hi=1000000, group=_G_RAIN, cli="--drops",
                       doc="requested number of drops (G/H keys)",
                       reason="3000: heavy rain at 640 x 360 that still lets the background through; Table 6.2 "
                              "measures 0 - 50 000")
    shape: str = param("1.0", choices=SHAPES, invalidates="mask", group=_G_RAIN,
                       doc="drop shape: the Table 2.1 radius a (mm) whose Beard-Chuang outline the mask takes (T key)",
                       reason="1.0: the typical drop of the text's §3.1 (1 mm radius ~ 10 px)")
    mask: str = param("outline", choices=MASKS, invalidates="mask", group=_G_RAIN,
                      doc="refraction mask: sphere, outline (the application: the shape's outline, a sphere's "
                          "refraction) or exact (rays traced through the Beard-Chuang drop)",
                      reason="outline: what the application did (rr-alg-3.1.1, spec erratum 12)")
    size_mm: float = param(1.3, unit="mm", lo=0.1, hi=4.5, c="size_mean_mm", invalidates="particles", group=_G_RAIN,
                           cli="--size",
                           doc="mean drop radius of the particle sizes, Gauss(1, 1.3, 8)'s 1.3 (B/N keys)",
                           reason="1.3: the text's mean size (rr-code-5.2.2), read as a radius (Table 2.2 is indexed "
                                  "by radius)")
    size_spread_mm: float = param(1.0, unit="mm", lo=0.0, hi=4.4, check=_check_size, c="size_spread_mm",
                                  invalidates="particles", group=_G_RAIN, cli="--size-spread",
                                  doc="Gauss(1, 1.3, 8)'s 1, read as the width of the averaged uniforms: radii in "
                                      "size +- spread/2, standard deviation spread / sqrt(12 samples)",
                                  reason="1: the printed argument; with 8 samples sigma = 0.10 mm, so ~68 % of the "
                                         "drops are within 0.1 mm of 1.3 mm (the text's ~66 %)")
    size_samples: int = param(8, kind="int", lo=1, hi=64, c="size_samples", invalidates="particles", group=_G_RAIN,
                              doc="Gauss(1, 1.3, 8)'s 8, read as the number of uniforms averaged (Irwin-Hall)",
                              reason="8: the printed argument")
    slowdown: float = param(4.0, lo=0.015625, hi=1000.0, c="slowdown", invalidates="particles", group=_G_RAIN,
                            doc="terminal speeds of Table 2.2 divided by this", reason="4: the application's")
    metres_per_unit: float = param(1.0, unit="m", lo=0.001, hi=1000.0, c="metres_per_unit",
                                   invalidates="particles", group=_G_RAIN,
                                   doc="one scene unit in metres (speeds in m/s become units/s; a millimetre at "
                                       "least, within ccl_particles_params_check's bound)",
                                   reason="1: not given (spec erratum 17); the 2 x 0.25 x 3 box is then a few metres "
                                          "around the viewer")
    wind_x: float = param(0.0, unit="m/s", lo=-50.0, hi=50.0, invalidates="particles", group=_G_RAIN, cli="--wind-x",
                          doc="horizontal wind along x (our extension; drops drift and wrap in the box)",
                          reason="0: the text has no wind")
    wind_z: float = param(0.0, unit="m/s", lo=-50.0, hi=50.0, invalidates="particles", group=_G_RAIN, cli="--wind-z",
                          doc="horizontal wind along z (our extension)", reason="0: the text has no wind")
    warm_start: bool = param(True, invalidates="particles", group=_G_RAIN,
                             doc="start with every requested drop in the air (off: one drop added per frame, as the "
                                 "listing)",
                             reason="on: a single image shows the requested count (the listing needs `drops` frames "
                                    "to fill the box)")
    variant: str = param("corrected", choices=("corrected", "thesis"), invalidates="particles", group=_G_RAIN,
                         doc="particle counter of rr-code-5.2.2: corrected (+1 per frame) or thesis (the printed "
                             "decrement: no drop is ever created)",
                         reason="corrected: the listing's evident intent")
    seed: int = param(0, kind="uint32", lo=0, hi=2 ** 32 - 1, c="seed", invalidates="particles", group=_G_RAIN,
                      doc="seed of every particle draw; the same seed gives the same rain", reason="0")
    time_s: float = param(0.0, unit="s", lo=0.0, hi=1e6, group=_G_RAIN, cli="--time",
                          doc="simulated time since the start (animate advances it; dt = its change, scaled by "
                              "clock_rate)",
                          reason="0: the first frame")
    clock_rate: float = param(0.05, lo=0.0, hi=100.0, group=_G_RAIN,
                              doc="rain seconds per second of the time field",
                              reason="0.05: `pywarp animate` advances the time by --time-scale (default 20) "
                                     "seconds per video second; 0.05 makes that real time")
    frame_dt: float = param(1.0 / 30.0, unit="s", lo=1e-4, hi=0.1, group=_G_RAIN,
                            doc="largest simulation step (a longer time change is simulated in steps of this)",
                            reason="1/30: the frame time of a 30 fps application")
    persistence_ms: float = param(75.0, unit="ms", lo=60.0, hi=90.0, group=_G_LOOK,
                                  doc="retinal persistence: the streak is the fall during this time (rr-alg-3.2.3)",
                                  reason="75: the middle of the text's 60 - 90 ms")
    billboard_scale: float = param(8.0, lo=0.1, hi=1000.0, group=_G_LOOK,
                                   doc="drop billboards drawn this many times their true size",
                                   reason="8: a 1.3 mm drop 1 m away is 0.4 px at true size at 360 px and 60 deg; "
                                          "the text's drops are ~10 px (§3.1); 8x gives ~3 px there and ~10 px at "
                                          "0.3 m")
    opacity: float = param(1.0, lo=0.0, hi=1.0, group=_G_LOOK,
                           doc="opacity of a drop pixel (mode drops)",
                           reason="1: the shader writes the refracted colour (alpha 1 from the mask)")
    streaks: str = param("physical", choices=STREAK_MODELS, group=_G_LOOK,
                         doc="streak model (mode streaks): physical (the drop's disc integrated over the persistence "
                             "time with a raised-cosine weight: thin, tapered, opacity = the share of the time a drop "
                             "covers a pixel, Garg & Nayar 2004) or thesis (rr-code-5.2.4: 7 mask taps stretched "
                             "over a rectangle, streak_opacity)",
                         reason="physical: the text's intent (the refracted scene smeared over the retinal "
                                "persistence) without its sampling showing; thesis keeps the listing")
    streak_scale: float = param(8.0, lo=0.1, hi=1000.0, group=_G_LOOK,
                                doc="physical streaks: the drop's diameter drawn this many times its true size (the "
                                    "streak's width, and with it its opacity 2 r / L, scale with it)",
                                reason="8, billboard_scale's: the streak is the drop the drops mode draws (F), moved "
                                       "over the persistence time. At true size a 1.3 mm drop 1 m away is 0.8 px "
                                       "wide and its streak 1.8 % opaque on average (Garg & Nayar's faint streaks: "
                                       "none shows against an overcast sky); 8x gives 6.5 px and 15 % (30 % at the "
                                       "middle) there, 2 - 3 px for the drops 2 - 3 m away: streaks that read as rain "
                                       "over the sky without hiding the scene (4x and 6x were invisible at 480 x 270)")
    streak_opacity: float = param(0.5, lo=0.0, hi=1.0, group=_G_LOOK,
                                  doc="thesis streaks: opacity of a streak pixel whose 7 taps all hit (fewer hits: "
                                      "proportionally less) -- the text's reduced alpha, amount not given",
                                  reason="0.5: streaks stay see-through where they cross (fig 3.8 uses opaque "
                                         "streaks: 1)")
    near_clip: float = param(0.5, unit="units", lo=0.01, hi=10.0, group=_G_LOOK,
                             doc="drops nearer than this to the eye (along the view) are not drawn",
                             reason="0.5: nearer drops would cover tens of pixels and hide the scene")
    filter: str = param("nearest", choices=FILTERS, group=_G_LOOK,
                        doc="capture filtering: nearest (rr-alg-3.1.2) or linear (rr-code-5.2.1-c's GL_LINEAR)",
                        reason="nearest: the text says it suffices")
    capture_size: int = param(256, unit="px", kind="int", lo=16, hi=4096, invalidates="size", group=_G_LOOK,
                              doc="edge of the square wide-angle capture (the text's: 512, rr-alg-3.1.2)",
                              reason="256: a drop is a few pixels wide, so each of its pixels spans some 40 texels "
                                     "of a 256 px capture of 150 deg already; measured at 640x360 over the default "
                                     "terrain, the still differs from 512's by SSIM 0.999 and CIEDE2000 0.13 mean "
                                     "(1.3 at the 99th percentile), and the capture costs a quarter of the background "
                                     "pixels (the still ~1.6x faster)")
    capture_fov_deg: float = param(150.0, unit="deg", lo=1.0, hi=170.0, group=_G_LOOK, cli="--capture-fov",
                                   doc="vertical FOV of the capture camera (rr-der-3.2.1)",
                                   reason="150: the text's contract (the exact drop FOV is 165 deg, rr-der-3.2.1)")
    mask_size: int = param(512, unit="px", kind="int", lo=8, hi=4096, invalidates="mask", group=_G_LOOK,
                           doc="edge of the refraction mask", reason="512: the text's (rr-alg-3.1.1)")
    light1_pos: tuple = param((0.5, 0.45, -1.6), unit="units", length=3, group=_G_LIGHT,
                              doc="position of point light 1 (rr-A1..rr-CF), camera-relative scene units (x right, y "
                                  "up, -z ahead at yaw 0; the eye at the origin, like the rain box)",
                              reason="up and to the right, just beyond the drops (the box reaches z = -1.5): a lamp "
                                     "close enough for rr-A1's DistFact to matter")
    light1_colour: tuple = param((0.0, 0.0, 0.0), length=3, check=_check_colour, group=_G_LIGHT,
                                 doc="colour C_L of light 1 (RGB >= 0; 0 = off)",
                                 reason="off: the text's application has no lights (rr-A1..rr-CF are its future "
                                        "extension); a warm lamp is e.g. (1.0, 0.8, 0.5)")
    light2_pos: tuple = param((-0.7, -0.2, -1.0), unit="units", length=3, group=_G_LIGHT,
                              doc="position of point light 2 (rr-CF's second light)",
                              reason="low on the left, so that the two lights hit the drops from opposite sides")
    light2_colour: tuple = param((0.0, 0.0, 0.0), length=3, check=_check_colour, group=_G_LIGHT,
                                 doc="colour C_L of light 2 (RGB >= 0; 0 = off)", reason="off, as light 1")
    light_ambient: tuple = param((1.0, 1.0, 1.0), length=3, check=_check_colour, group=_G_LIGHT,
                                 doc="C_amb of rr-CF: the refracted colour is multiplied by it",
                                 reason="1: the refracted scene keeps its colour (the capture is already lit)")
    light_r_half: float = param(1.0, unit="units", lo=0.0, lo_open=True, hi=1000.0, group=_G_LIGHT,
                                doc="rr-A1's DistFact = 1 / (1 + (d / r_half)^2): the distance at which a light has "
                                    "half its intensity",
                                reason="1 (1 m): the text gives no form; nearby lights (a lamp a metre or two away) "
                                       "light the drops, far ones fade like an inverse square")
    light_variant: str = param("corrected", choices=("corrected", "thesis"), group=_G_LIGHT,
                               doc="rr-A1: corrected (V_PE . V_N clamped at 0) or thesis (unclamped, as printed)",
                               reason="corrected: a normal facing away from the eye gets no light")
    camera_yaw_deg: float = param(0.0, unit="deg", lo=-360.0, hi=360.0, group=_G_CAM, cli="--yaw",
                                  doc="camera heading, 0 = -z (passed to the background scene)",
                                  reason="0: looking along -z")
    camera_pitch_deg: float = param(2.0, unit="deg", lo=-89.0, hi=89.0, group=_G_CAM, cli="--pitch",
                                    doc="camera pitch (passed to the background scene)",
                                    reason="2: the horizon across the frame, so drops show sky and ground upside down")
    fov_y_deg: float = param(60.0, unit="deg", lo=1.0, hi=170.0, group=_G_CAM, cli="--fov",
                             doc="vertical field of view of the view", reason="60: a natural view")
    background: str = param("terrain", check=_check_background, invalidates="background", group=_G_BG,
                            doc="background: 'panorama' (built-in analytic sky and ground) or any registered scene "
                                "(its settings' width, height, fov_y_deg, camera_yaw_deg and camera_pitch_deg are set "
                                "from ours)",
                            reason="terrain: the pt landscape under an overcast sky (BACKGROUND_OPTIONS) -- the "
                                   "ground the text's scenes 2 and 3 have, for the drops to refract")
    background_options: dict = param({}, cli="--background-set", check=_check_background_options,
                                     invalidates="background", group=_G_BG,
                                     doc="settings of the background scene by name, over the rain scene's own for "
                                         "that scene (BACKGROUND_OPTIONS: the terrain overcast, the clouds overcast "
                                         "from 50 m); on the command line KEY=VALUE (tuples as 0.5,0.5,0.6); a name "
                                         "that is no field of the background's settings is an error",
                                     reason="empty: every background with the rain scene's settings for it, or its "
                                            "own defaults")
    background_scale: int = param(1, kind="int", lo=1, hi=4, check=_check_background_scale, group=_G_BG,
                                  doc="the background view rendered at 1/background_scale of the width and height "
                                      "per frame, a sub-pixel phase each time, the window's picture reconstructed "
                                      "over frames (pywarp.core.temporal: exact while the view only turns, as the "
                                      "background's camera does); 1 renders it whole",
                                  reason="1: pywarp render's full background; the viewer sets 4 while the view "
                                         "moves (a sixteenth of the background's pixels per frame: measured 7 "
                                         "frames/s against 3.5 with 2 over the terrain, the same SSIM)")
    particles_scale: int = param(1, kind="int", lo=1, hi=2, group=_G_BG,
                                 doc="the drops composited at 1/particles_scale of the width and height over the "
                                     "view averaged down, their change to it enlarged bilinearly and added to the "
                                     "full view (2 only where both sides are even; else 1)",
                                 reason="1: pywarp render's drops, every pixel; the viewer sets 2 while the view "
                                        "moves (the compositing pass at a quarter of the pixels: measured 36 ms of "
                                        "CPU a 640x360 frame at 1)")
    exposure_ev: float = exposure_param(0.0, reason="0 EV: the frame's values are already displayed ones (below)")
    tonemap: str = tonemap_param(
        "none", reason="none: the frame is the background's display-encoded image (its own transform the plain "
                       "clamp, BACKGROUND_OPTIONS) with the drops composited over it, so no value exceeds 1 (no pixel "
                       "of the README image has a channel at 255) and the clamp keeps every colour; aces or "
                       "exponential at an exposure apply the shared display transform (pywarp.core.display) to it")
    device: str = param("cpu", invalidates="device", group=_G_RUN, doc="Warp device: cpu, or cuda:N where present",
                        reason="cpu: nothing requires a GPU")
    threads: int | None = param(None, kind="int", lo=1, hi=4096, optional=True, invalidates="device", group=_G_RUN,
                                default_text="one per core", doc="worker threads of the tile launcher",
                                reason="None: one per core (PYWARP_THREADS overrides)")

    def background_values(self) -> dict:
        """The settings of the background scene: ``BACKGROUND_OPTIONS`` of this background, then
        ``background_options``."""
        return {**BACKGROUND_OPTIONS.get(self.background, {}),
                **parse_background_options(self.background, self.background_options)}

    def light_values(self) -> dict:
        """The lights of these settings as ``pywarp.kernels.particles.LIGHT_DEFAULTS`` fields (without the view
        basis, which the technique adds)."""
        return dict(l1=self.light1_pos, c_l1=self.light1_colour, l2=self.light2_pos, c_l2=self.light2_colour,
                    ambient=self.light_ambient, r_half=self.light_r_half, variant=self.light_variant)

    def c_values(self) -> dict:
        """The ``ccl_particles_params`` values of these settings (:mod:`pywarp.core.cbridge`): the C defaults, the
        fields the specs name and the wind in scene units per second."""
        from ..core.cbridge import PARTICLES_PARAMS, settings_values

        return {**PARTICLES_PARAMS.defaults(), **settings_values(self),
                "wind": (self.wind_x / self.metres_per_unit, 0.0, self.wind_z / self.metres_per_unit)}


#: rr-tab-A: the controls of the application (Appendix A.1), as data: key -> (action, the settings field it changes,
#: how). The viewer binds them; step sizes are not given by the text (spec erratum 16), ours are here.
CONTROLS = (
    {"key": "W", "action": "step forward", "field": None, "change": "camera forward"},
    {"key": "S", "action": "step backward", "field": None, "change": "camera backward"},
    {"key": "A", "action": "turn left", "field": "camera_yaw_deg", "change": -5.0},
    {"key": "D", "action": "turn right", "field": "camera_yaw_deg", "change": +5.0},
    {"key": "Q", "action": "move up", "field": None, "change": "camera up"},
    {"key": "E", "action": "move down", "field": None, "change": "camera down"},
    {"key": "Y", "action": "look up", "field": "camera_pitch_deg", "change": +5.0},
    {"key": "C", "action": "look down", "field": "camera_pitch_deg", "change": -5.0},
    {"key": "P", "action": "pause / start the simulation", "field": "clock_rate", "change": "toggle 0"},
    {"key": "F", "action": "toggle drops / streaks", "field": "mode", "change": "cycle"},
    {"key": "T", "action": "select the drop shape (Table 2.1)", "field": "shape", "change": "cycle"},
    {"key": "G", "action": "decrease the number of drops", "field": "drops", "change": "x 0.5"},
    {"key": "H", "action": "increase the number of drops", "field": "drops", "change": "x 2"},
    {"key": "B", "action": "decrease the drop size", "field": "size_mm", "change": -0.1},
    {"key": "N", "action": "increase the drop size", "field": "size_mm", "change": +0.1},
)
