"""The flight technique (init / update / render / resize, the scene interface of pywarp.core.scenes): cloud arrays
of the oc text (:func:`pywarp.flight.clouds.cloud_volume`) placed along a scripted flight, their light volumes, and
the volume renderer of :mod:`pywarp.kernels.volume` (row bands on every core through
:class:`pywarp.core.runtime.TileLauncher`) with the aircraft of :mod:`pywarp.kernels.flight`.

    from pywarp.flight.technique import FlightTechnique, FlightPose
    tech = FlightTechnique()                    # FlightSettings() defaults: 9 clouds of 64^3, 640 x 360
    img = tech.render(FlightPose(8.0))          # uint8 (360, 640, 3): the chase view 8 s into the flight
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import warp as wp

from ..core import display
from ..core.cbridge import VOLUME_PARAMS
from ..core.runtime import init
from ..core.technique import Technique

init()

from ..kernels import camera as CAM  # noqa: E402
from ..kernels.volume import render_linear_kernel  # noqa: E402
from . import model as F  # noqa: E402
from . import volumes as V  # noqa: E402
from . import script as S  # noqa: E402
from .settings import VIEWS, FlightSettings  # noqa: E402


@dataclass(frozen=True)
class AircraftState:
    """The aircraft at a moment: position (m, y up), heading, pitch and roll (rad), speed (m/s)."""

    position: tuple
    heading: float
    pitch: float
    roll: float
    speed: float


@dataclass(frozen=True)
class FlightPose:
    """A moment of the scripted flight and the camera that looks at it (``chase`` or ``cockpit``): the flight's
    camera is placed by the aircraft, not by a yaw and a pitch. ``aircraft``: the state to look at (the viewer's live
    flight, :class:`pywarp.flight.controls.FlightControls`; ``time_s`` is then the scripted moment it started from);
    None: the scripted aircraft at ``time_s``. ``jitter_px``: a sub-pixel offset of the image (pixels, as
    :class:`pywarp.core.pose.Pose`'s: the viewer's temporal reconstruction)."""

    time_s: float = 6.0
    view: str = "chase"
    aircraft: AircraftState | None = None
    jitter_px: tuple = (0.0, 0.0)

    def __post_init__(self):
        if isinstance(self.time_s, bool) or not isinstance(self.time_s, (int, float)) or not math.isfinite(
                self.time_s) or self.time_s < 0:
            raise ValueError(f"time_s must be a finite number >= 0, got {self.time_s!r}")
        if self.view not in VIEWS:
            raise ValueError(f"view must be one of {', '.join(map(repr, VIEWS))}, got {self.view!r}")


class FlightTechnique(Technique):
    """The flight scene's technique. ``volumes``: the placed cloud arrays with their light volumes
    (:class:`pywarp.flight.volumes.VolumeSet`); ``trajectory``: the scripted flight
    (:class:`pywarp.flight.model.Trajectory`)."""

    settings_class = FlightSettings

    def __init__(self, settings: FlightSettings | None = None, script=None):
        self.script = tuple(script) if script is not None else S.DEFAULT_SCRIPT
        super().__init__(settings)

    def rebuild(self, stale: set, changed: set) -> None:
        """What each change invalidates comes from the specs (``FlightSettings.INVALIDATES``): ``flight`` simulates
        the flight again and rebuilds the clouds placed along it, ``clouds`` the clouds, ``light`` (sun, light) the
        light volumes; a device switch all of them."""
        if stale & {"flight", "device"}:
            self._build_flight()
        if stale & {"flight", "clouds", "device"}:
            self._build_clouds()
        if stale & {"flight", "clouds", "device", "light"}:
            self.volumes.compute_light(self.settings.c_values(), launcher=self.launcher, needed_only=True)

    def _build_flight(self) -> None:
        s = self.settings
        self.trajectory = F.simulate(self.script, s.flight_duration_s, dt=S.DT, start=s.start_state(),
                                     model=s.flight_model(), device=self.device)

    def _build_clouds(self) -> None:
        from .clouds import cloud_volume

        s = self.settings
        boxes = S.cloud_boxes(s, self.trajectory)
        vols = [V.PlacedVolume(cloud_volume(s.cloud_array(k), device=self.device, launcher=self.launcher),
                               origin, extent) for k, (origin, extent) in enumerate(boxes)]
        self.volumes = V.VolumeSet(vols, device=self.device)

    def allocate(self, width: int, height: int) -> None:
        self._out = wp.zeros((height, width, 3), dtype=wp.uint8, device=self.device)

    # --- the aircraft and the camera -----------------------------------------------------------------------------
    def aircraft(self, time_s: float) -> AircraftState:
        """The aircraft at ``time_s`` (the last simulation step at or before it; the start state at 0)."""
        tr = self.trajectory
        if time_s < float(tr.time[0]) or len(tr.time) == 0:
            st = self.settings.start_state()
            return AircraftState(tuple(st.position), st.heading, 0.0, 0.0, st.speed)
        k = tr.at(time_s)
        return AircraftState(tuple(float(x) for x in tr.position[k]), float(tr.heading[k]), float(tr.pitch[k]),
                             float(tr.roll[k]), float(tr.speed[k]))

    def view(self, pose: FlightPose) -> tuple[CAM.Camera, dict]:
        """(camera, volume parameter values) of ``pose``."""
        s = self.settings
        a = pose.aircraft or self.aircraft(pose.time_s)
        f, r, u = F.axes(a.heading, a.pitch, a.roll)
        pos = np.asarray(a.position, dtype=np.float64)
        values = s.c_values()
        aspect = s.width / s.height
        fov = math.radians(s.fov_y_deg)
        if pose.view == "chase":
            # behind, beside and above the aircraft in the horizontal frame of its heading (a three-quarter view:
            # the bank and the pitch show as the tilt of the wings and the fuselage), looking past it a little ahead
            fh = np.array([math.sin(a.heading), 0.0, -math.cos(a.heading)])
            rh = np.array([math.cos(a.heading), 0.0, math.sin(a.heading)])
            eye = pos - fh * s.chase_distance_m + rh * s.chase_side_m + np.array([0.0, s.chase_height_m, 0.0])
            eye[1] = max(eye[1], 2.0)
            target = pos + fh * 10.0 + np.array([0.0, 1.0, 0.0])
            cam = CAM.camera_look_at(eye, target, (0.0, 1.0, 0.0), fov, aspect, 0.1, 1.0e5)
            values.update(aircraft=1, aircraft_position=tuple(pos), aircraft_forward=f, aircraft_right=r,
                          aircraft_up=u)
        else:
            # the pilot's eye above the cabin, looking along the nose; the horizon banks with the aircraft
            eye = pos + np.asarray(u) * 0.9 + np.asarray(f) * 1.4
            cam = CAM.camera_look_at(eye, eye + np.asarray(f) * 100.0, u, fov, aspect, 0.1, 1.0e5)
            values.update(aircraft=0)
        if pose.jitter_px != (0.0, 0.0):
            cam = cam.jittered(pose.jitter_px[0], pose.jitter_px[1], s.width, s.height)
        return cam, values

    def pose(self, pose: FlightPose | None = None) -> FlightPose:
        """The pose a ``render(pose)`` uses: ``pose``, or the settings' time and view."""
        return pose if pose is not None else FlightPose(self.settings.time_s, self.settings.view)

    def camera(self, pose: FlightPose | None = None) -> CAM.Camera:
        """The camera of ``pose`` without its jitter (:meth:`pywarp.core.technique.Technique.camera`)."""
        return self.view(replace(self.pose(pose), jitter_px=(0.0, 0.0)))[0]

    # --- render ---------------------------------------------------------------------------------------------------
    def render(self, pose: FlightPose | None = None, progress=None) -> np.ndarray:
        """One frame, uint8 sRGB (height, width, 3) through the display transform of the ``exposure_ev`` and
        ``tonemap`` settings (pywarp.core.display; ``none`` at 0 EV: the kernel's plain clamp and encoding). ``pose``
        (default: the settings' time and view); ``progress(fraction)`` per finished band."""
        s = self.settings
        pose = pose or FlightPose(s.time_s, s.view)
        cam, values = self.view(pose)
        grids, count, dens, light, occ = self.volumes.warp()
        h, w = s.height, s.width
        band_done = None if progress is None else (lambda n: progress(n / h))
        p = VOLUME_PARAMS.warp_struct(V.checked_params(values))
        args = [p, grids, count, dens, light, occ, cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), w, h]
        if s.tonemap == "none" and s.exposure_ev == 0.0:  # the plain clamp: encoded in the kernel
            self.launcher.launch(V.render_kernel, h, w, args, [self._out], progress=band_done)
            return self._out.numpy().copy()
        if getattr(self, "_linear", None) is None or self._linear.shape != (h, w, 3):
            self._linear = wp.zeros((h, w, 3), dtype=float, device=self.device)
        self.launcher.launch(render_linear_kernel, h, w, args, [self._linear], progress=band_done)
        lin = self._linear.numpy()
        if not np.all(np.isfinite(lin)):
            raise RuntimeError("the render produced non-finite pixels")
        return display.quantise(display.apply(lin, s.exposure_ev, s.tonemap), srgb=True)

    def render_pixels_c(self, xs, ys, pose: FlightPose | None = None) -> np.ndarray:
        """``ccl_volume_pixel`` (the C reference) at pixels (xs[k], ys[k]) of ``pose``: display-linear RGB (k, 3)."""
        s = self.settings
        cam, values = self.view(pose or FlightPose(s.time_s, s.view))
        return V.pixels_c(values, self.volumes, cam, xs, ys, s.width, s.height)

    def render_pixels_warp(self, xs, ys, pose: FlightPose | None = None) -> np.ndarray:
        """:func:`pywarp.kernels.volume.volume_pixel` at the same pixels (the Warp side of the comparison)."""
        s = self.settings
        cam, values = self.view(pose or FlightPose(s.time_s, s.view))
        return V.pixels_warp(values, self.volumes, cam, xs, ys, s.width, s.height)


def path_poses(frames: int, settings: FlightSettings, view: str) -> list[FlightPose]:
    """``frames`` moments spread evenly over the whole scripted flight (0 .. flight_duration_s)."""
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise ValueError(f"frames must be an integer >= 1, got {frames!r}")
    d = settings.flight_duration_s
    return [FlightPose(d * i / max(frames - 1, 1), view) for i in range(frames)]


def chase_path(frames: int, settings: FlightSettings) -> list[FlightPose]:
    """The ``chase`` camera path: :func:`path_poses` seen from behind, beside and above the aircraft (a three-quarter
    view)."""
    return path_poses(frames, settings, "chase")


def cockpit_path(frames: int, settings: FlightSettings) -> list[FlightPose]:
    """The ``cockpit`` camera path: :func:`path_poses` from the pilot's eye."""
    return path_poses(frames, settings, "cockpit")


def render_image(settings: FlightSettings | None = None, pose: FlightPose | None = None) -> np.ndarray:
    """One uint8 sRGB image of the flight scene."""
    return FlightTechnique(settings).render(pose)
