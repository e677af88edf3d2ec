"""Settings of the ``flight`` scene: every value the oc text does not give is a parameter with its unit, default and
the reason for it (the text gives none of them: spec oc-6.1.1 "Not given", §4 "no value given")."""
from __future__ import annotations

from dataclasses import dataclass

from ..core.display import exposure_param, tonemap_param
from ..core.params import Settings, param

VIEWS = ("chase", "cockpit")


def _time_check(obj, name, v):
    if v > obj.flight_duration_s:
        raise ValueError(f"{name} must be in [0, flight_duration_s ({obj.flight_duration_s:g} s)], got {v!r}")


def _size_check(obj, name, v):
    if v % 8 != 0:
        raise ValueError(f"{name} must be a multiple of 8 (the size/8 base array of oc-5.2.1, at least 4 cells), "
                         f"got {v!r}")


@dataclass(frozen=True)
class FlightSettings(Settings):
    """Every parameter of the flight scene. Immutable: change with ``dataclasses.replace`` (validated) or
    :meth:`pywarp.flight.technique.FlightTechnique.update`."""

    #: ``clouds``: the cloud arrays are rebuilt (and their light); ``flight``: the scripted flight is simulated again
    #: (the clouds are placed along it: they and their light follow); ``light``: the light volumes are recomputed
    INVALIDATES = Settings.INVALIDATES + ("clouds", "flight", "light")

    _validation_order = ("flight_duration_s",)

    # --- image ---
    width: int = param(640, unit="px", kind="int", lo=16, hi=8192, invalidates="size", group="image",
                       doc="image width",
                       reason="640 x 360: the text runs smoothly 'only at lower resolutions' (§7); the benchmark size")
    height: int = param(360, unit="px", kind="int", lo=16, hi=8192, invalidates="size", group="image",
                        doc="image height", reason="640 x 360 (16:9)")
    # --- the clouds (oc-5.2) ---
    seed: int = param(0, kind="uint32", lo=0, hi=2 ** 32 - 1, invalidates="clouds", group="clouds",
                      doc="seed of the cloud arrays and of their placement; the same seed gives the same flight "
                          "images", reason="0: any; reproducible")
    cloud_count: int = param(9, kind="int", lo=1, hi=16, invalidates="clouds", group="clouds",
                             doc="number of cloud volumes (the first is on the flight path, the others beside and "
                                 "ahead of it)",
                             reason="9: one to fly through, others to fly around and in view during the turns")
    cloud_size: int = param(64, unit="voxels", kind="int", lo=32, hi=256, check=_size_check, invalidates="clouds",
                            group="clouds", cli="--cloud-size", doc="edge of each cloud array (oc-5.2.1)",
                            reason="64: the noise64 of the filter listing (oc-5.2.2)")
    # the fields below mirror pywarp.flight.clouds.CloudArraySettings (cover, sharpness, persistence, interpolation,
    # smoothing, envelope, envelope_base), declared here so that registering the scene imports no Warp (tests/flight
    # check they agree)
    cloud_cover: float = param(50.0, unit="0..255", lo=0.0, hi=255.0, invalidates="clouds", group="clouds",
                               cli="--cloud-cover",
                               doc="cloudCover of the filter (oc-5.2.2): a LARGER cover gives LESS cloud",
                               reason="50: with the envelope (cloud_envelope) the noise makes cloud where it exceeds "
                                      "50 + 128 q (q the envelope's squared radius): a compact cloud of about a fifth "
                                      "of its box; the cloud array's own 128 (without the envelope) left sparse "
                                      "wisps")
    cloud_sharpness: float = param(0.92, lo=0.0, hi=1.0, lo_open=True, hi_open=True, invalidates="clouds",
                                   group="clouds", cli="--cloud-sharpness",
                                   doc="cloudSharpness of the filter (oc-5.2.2) in (0, 1): near 0 hard edges",
                                   reason="0.92: half density 8 units above the cover -- a readable outline, still "
                                          "soft (the cloud array's 0.96 gave a haze at this cover)")
    cloud_persistence: float = param(0.5, lo=0.0, lo_open=True, hi=1.0, invalidates="clouds", group="clouds",
                                     cli="--cloud-persistence", doc="persistence of the cloud array (oc-5.1.2.2)",
                                     reason="0.5: the cloud array's default (Elias's value)")
    cloud_interpolation: str = param("linear", choices=("linear", "cosine", "cubic"), invalidates="clouds",
                                     group="clouds", cli="--cloud-interpolation",
                                     doc="up-sampling interpolant of the cloud array (oc-5.1.4)",
                                     reason="'linear': the cloud array's default (trilinear, 'for real time')")
    cloud_smoothing: str = param("none", choices=("elias", "4-neighbour", "8-neighbour", "none"),
                                 invalidates="clouds", group="clouds", cli="--cloud-smoothing",
                                 doc="smoothing of the noise added at each level (oc-5.1.3)",
                                 reason="'none': inside the envelope the raw lattice's finer levels give the lumpy, "
                                        "cauliflower outline of a cumulus; Elias's smoothing (the cloud array's "
                                        "default) rounds every cloud into the same soft blob")
    cloud_envelope: float = param(0.5, unit="noise", lo=0.0, hi=1.0, invalidates="clouds", group="clouds",
                                  cli="--cloud-envelope",
                                  doc="falloff envelope of the cloud array (beyond the text): noise minus this times "
                                      "the squared radius of the ellipsoids inscribed in the box; 0 = the text's "
                                      "array as printed (the cloud fills its box and shows its faces)",
                                  reason="0.5: about 7 standard deviations of the raw-lattice noise (0.07) at the "
                                         "inscribed ellipsoid -- every cloud ends inside it, rounded; in the core "
                                         "(q < 0.2) the threshold moves by less than 1.5 of them, so the noise draws "
                                         "the lumps. 0.2 left flat, box-like sides (the zero border's falloff is "
                                         "separable per axis)")
    cloud_envelope_base: float = param(0.35, lo=0.0, lo_open=True, hi=1.0, invalidates="clouds", group="clouds",
                                       doc="lower semi-axis of the envelope's ellipsoids over the upper one",
                                       reason="0.35: the base falls off three times as fast as the top: a flat base "
                                              "under a dome (the cloud array's default)")
    cloud_width_m: float = param(700.0, unit="m", lo=10.0, hi=20000.0, invalidates="clouds", group="clouds",
                                 doc="horizontal size of a cloud's box (oc-5.2.3-scale: the per-axis scale), varied "
                                     "by up to +-25 %% per cloud",
                                 reason="700: a fair-weather cumulus, about 12 s of flight at full speed")
    cloud_height_m: float = param(320.0, unit="m", lo=10.0, hi=20000.0, invalidates="clouds", group="clouds",
                                  doc="vertical size of a cloud's box (oc-5.2.3-scale), varied by up to +-20 %%",
                                  reason="320: flattened to about half the width, as fair-weather cumulus are")
    cloud_altitude_m: float = param(600.0, unit="m", lo=0.0, hi=20000.0, invalidates="clouds", group="clouds",
                                    doc="altitude of the clouds' centres beside the path",
                                    reason="600: low clouds (the low level: up to 2 km, §2.1.2), the flight level")
    # --- lighting (volume.h) ---
    sun_elevation_deg: float = param(35.0, unit="deg", lo=1.0, hi=90.0, invalidates="light", group="lighting",
                                     cli="--sun-elevation", doc="sun elevation",
                                     reason="35: a mid-morning sun, sunlit cloud sides and shaded bases")
    sun_azimuth_deg: float = param(150.0, unit="deg", invalidates="light", group="lighting", cli="--sun-azimuth",
                                   doc="sun azimuth, 0 = -z (the start heading), positive towards +x",
                                   reason="150: behind the aircraft's right: the clouds ahead are lit from the front")
    tau_per_voxel: float = param(0.35, lo=0.0, hi=50.0, c="tau_per_voxel", group="lighting", cli="--tau",
                                 doc="optical depth of one voxel length at density 255 along the view",
                                 reason="0.35: a core of 255 is opaque after about 13 voxels, the edges stay soft "
                                        "(ccl_volume_params_default)")
    light_tau_per_voxel: float = param(0.25, lo=0.0, hi=50.0, invalidates="light", c="light_tau_per_voxel",
                                       group="lighting", cli="--light-tau",
                                       doc="optical depth per voxel towards the sun (the light volume)",
                                       reason="0.25: less than the view's, for the light scattered forward through "
                                              "the cloud (ccl_volume_params_default)")
    g: float = param(0.3, lo=-1.0, hi=1.0, lo_open=True, hi_open=True, c="g", group="lighting", cli="--phase-g",
                     doc="Henyey-Greenstein asymmetry of the cloud's phase function",
                     reason="0.3: mild forward scattering, bright edges towards the sun (ccl_volume_params_default)")
    fog_distance_m: float = param(6000.0, unit="m", lo=1.0, hi=1e7, c="fog_distance", group="lighting",
                                  cli="--fog-distance",
                                  doc="e-folding distance of the aerial fog", reason="6000: a hazy summer day")
    # --- quality ---
    step_voxels: float = param(1.0, unit="voxels", lo=0.05, hi=16.0, c="step_voxels", group="quality", cli="--step",
                               doc="view-ray step in voxel lengths",
                               reason="1: one sample per voxel, no detail skipped (ccl_volume_params_default)")
    light_step_voxels: float = param(1.0, unit="voxels", lo=0.05, hi=16.0, invalidates="light", c="light_step_voxels",
                                     group="quality",
                                     cli="--light-step", doc="light-ray step of the light volume in voxel lengths",
                                     reason="1: one sample per voxel (ccl_volume_params_default)")
    preview_scale: float = param(0.5, lo=0.05, hi=1.0, group="quality", cli="--preview-scale",
                                 doc="resolution factor of a preview frame (width and height times this) while the "
                                     "view moves, e.g. in the viewer (FlightSettings.preview)",
                                 reason="0.5: the full 640 x 360 frame does not reach the >= 15-20 frames/s aim on two "
                                        "cores (pywarp bench flight frame: the march through the soft 64^3 clouds, "
                                        "whose boxes are about 40 % occupied, costs per pixel); a quarter of the "
                                        "pixels "
                                        "does, and the text itself runs smoothly 'only at lower resolutions' (§7)")
    preview_step_voxels: float = param(2.0, unit="voxels", lo=0.05, hi=16.0, group="quality",
                                       cli="--preview-step",
                                       doc="view-ray step of a preview frame (FlightSettings.preview)",
                                       reason="2: half the samples of the refined frame; the opacity per step follows "
                                              "the step (alpha = 1 - exp(-tau rho step)), so the clouds keep their "
                                              "density, and the jittered start hides the coarser slicing in motion")
    # --- the flight (oc-6.1.1) ---
    flight_duration_s: float = param(32.0, unit="s", lo=1.0, hi=3600.0, invalidates="flight", group="flight",
                                     cli="--duration", doc="length of the scripted flight (animate spreads its "
                                                           "frames over it)",
                                     reason="32: the default script (pywarp.flight.script): a bank, a climb through "
                                            "the first cloud, turns around the others")
    time_s: float = param(10.0, unit="s", lo=0.0, check=_time_check, group="flight", cli="--time",
                          doc="moment of the flight that `render` shows",
                          reason="10: the aircraft banking right out of the first cloud, the next clouds ahead and "
                                 "beside it (the README picture)")
    start_altitude_m: float = param(560.0, unit="m", lo=10.0, hi=20000.0, invalidates="flight", group="flight",
                                    cli="--start-altitude", doc="altitude of the aircraft at t = 0",
                                    reason="560: just below the cloud level; the script's climb enters the first "
                                           "cloud")
    start_speed_mps: float = param(40.0, unit="m/s", lo=0.0, hi=1000.0, invalidates="flight", group="flight",
                                   cli="--start-speed", doc="speed at t = 0 (<= max speed)",
                                   reason="40: cruising; W brings it to the maximum")
    max_speed_mps: float = param(60.0, unit="m/s", lo=0.0, lo_open=True, hi=1000.0, invalidates="flight",
                                 group="flight", cli="--max-speed", doc="the 'defined maximum' speed of W (§6.1.2)",
                                 reason="60 m/s = 216 km/h: a light aircraft (ccl_flight_params_default)")
    point_rate_mps: float = param(1.0, unit="m/s", lo=0.0, hi=100.0, invalidates="flight", group="flight",
                                  cli="--point-rate",
                                  doc="rise/sink speed of a height point while its arrow key is held (oc-6.1.1)",
                                  reason="1: a 1 s press tilts the nose by 15 deg (ccl_flight_params_default)")
    turn_rate: float = param(0.8, unit="rad/s", lo=0.0, hi=10.0, invalidates="flight", group="flight",
                             cli="--turn-rate", doc="heading rate at 90 deg bank and full speed",
                             reason="0.8: at 30 deg bank a full circle in 16 s (ccl_flight_params_default)")
    # --- camera ---
    view: str = param("chase", choices=VIEWS, group="camera",
                      doc="camera of `render`: chase (behind, beside and above the aircraft) or cockpit (at the "
                          "pilot's eye, banking with the aircraft; the aircraft itself is not drawn)",
                      reason="'chase': shows the aircraft and its attitude in the clouds")
    chase_distance_m: float = param(20.0, unit="m", lo=1.0, hi=10000.0, group="camera", cli="--chase-distance",
                                    doc="distance of the chase camera behind the aircraft (along its heading)",
                                    reason="20: with the side offset the aircraft (12 m span) fills about a third "
                                           "of the width, the clouds ahead stay in view")
    chase_side_m: float = param(14.0, unit="m", lo=-10000.0, hi=10000.0, group="camera", cli="--chase-side",
                                doc="offset of the chase camera to the aircraft's right (negative: left)",
                                reason="14: a three-quarter view from behind, 35 deg off the tail -- wings, tail "
                                       "and fuselage all read and the bank shows as a tilt of the wings (0: "
                                       "straight behind, a flat 'T')")
    chase_height_m: float = param(6.0, unit="m", lo=-1000.0, hi=1000.0, group="camera", cli="--chase-height",
                                  doc="height of the chase camera above the aircraft",
                                  reason="6: looking slightly down onto the wings")
    fov_y_deg: float = param(60.0, unit="deg", lo=1.0, hi=170.0, group="camera", cli="--fov",
                             doc="vertical field of view", reason="60: a natural view")
    exposure_ev: float = exposure_param(
        -0.5, reason="-0.5 EV: with the ACES curve the default view's mean stays within 3.5 % (R, G, B) of the clamped "
                     "image's and no channel reaches 255 (480x270: 0.02 % of the clamped image's pixels have one)")
    tonemap: str = tonemap_param()
    device: str = param("cpu", invalidates="device", group="runtime",
                        doc="Warp device: cpu, or cuda:N where present", reason="cpu: nothing requires a GPU")
    threads: int | None = param(None, kind="int", lo=1, hi=4096, optional=True, invalidates="device",
                                group="runtime", default_text="one per core",
                                doc="worker threads of the tile launcher",
                                reason="None: one per core (PYWARP_THREADS overrides)")

    def _check(self) -> None:
        if self.start_speed_mps > self.max_speed_mps:
            raise ValueError(f"start_speed_mps must be in [0, max_speed_mps ({self.max_speed_mps:g})], "
                             f"got {self.start_speed_mps!r}")

    def cloud_array(self, k: int):
        """The cloud-array settings (``pywarp.flight.clouds.CloudArraySettings``) of cloud ``k``, its seed derived
        from the scene's."""
        from .clouds import CloudArraySettings

        return CloudArraySettings(size=self.cloud_size, seed=(self.seed * 7919 + 104729 * k) % 2 ** 32,
                                  cover=self.cloud_cover, sharpness=self.cloud_sharpness,
                                  persistence=self.cloud_persistence, interpolation=self.cloud_interpolation,
                                  smoothing=self.cloud_smoothing, envelope=self.cloud_envelope,
                                  envelope_base=self.cloud_envelope_base)

    def preview(self) -> "FlightSettings":
        """The settings of a preview frame while the view moves: width and height times ``preview_scale`` (at least
        16 px, the aspect kept), ``step_voxels`` = ``preview_step_voxels``; everything else unchanged."""
        import dataclasses

        w = max(16, int(round(self.width * self.preview_scale)))
        h = max(16, int(round(self.height * self.preview_scale)))
        return dataclasses.replace(self, width=w, height=h, step_voxels=self.preview_step_voxels)

    def c_values(self) -> dict:
        """The ``ccl_volume_params`` values of this scene (:mod:`pywarp.core.cbridge`): the C defaults, the fields
        the specs name and the sun direction (the aircraft's fields are the view's)."""
        from ..core.cbridge import VOLUME_PARAMS, settings_values
        from ..kernels import volume as V

        return {**VOLUME_PARAMS.defaults(), **settings_values(self),
                "sun": V.sun_direction(self.sun_elevation_deg, self.sun_azimuth_deg)}

    def flight_model(self):
        from .model import FlightModel

        return FlightModel(max_speed=self.max_speed_mps, point_rate=self.point_rate_mps, turn_rate=self.turn_rate)

    def start_state(self):
        from .model import FlightState

        return FlightState(position=(0.0, self.start_altitude_m, 0.0), heading=0.0, speed=self.start_speed_mps)


