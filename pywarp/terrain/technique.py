"""The terrain technique (pt-alg-6 in our terms): the demo's one full-screen fragment shader becomes one Warp image
kernel launched as row bands on every core; the CPU side holds the camera and the settings.

    from pywarp.terrain.technique import render_image
    img = render_image(TerrainSettings(width=640, height=360))      # uint8 (360, 640, 3)

One frame (``TerrainTechnique.render``): per pixel, m x m sub-sample rays (pt-code-7.1/7.2: the camera of
:mod:`pywarp.kernels.camera`, fov 90 deg), each shaded by ``terrain_shade`` (pt-code-7.3: march, normal, materials,
shadow, light, water, clouds, fog), averaged and clamped (pt-alg-7.1.6); colours are display values (the demo's
GLSL writes them without gamma). The same pixel exists in C (``ccl_terrain_pixel``): :func:`render_pixels_c`.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import warp as wp

from ..core import display
from ..core.pose import Pose
from ..core.registry import equation
from ..core.runtime import init
from ..core.technique import Technique

init()

from ..kernels import camera as CAM  # noqa: E402
from ..kernels import terrain as K  # noqa: E402
from . import evaluators as E  # noqa: E402
from .settings import PREVIEW, TerrainSettings  # noqa: E402


def effective(settings: TerrainSettings) -> TerrainSettings:
    """The settings a frame is rendered with: ``settings`` itself for quality 'full'; for 'preview' the reductions
    of :data:`pywarp.terrain.settings.PREVIEW` at 1/preview_scale of the width and height (rounded up). The last
    answer is kept for the same (frozen) settings object: a viewer frame asks four times, and each new settings
    object validates every field."""
    s = settings
    if s.quality != "preview":
        return s
    global _EFFECTIVE_LAST
    last = _EFFECTIVE_LAST  # one tuple, read and replaced whole (the viewer's threads may both ask)
    if last[0] is s and last[1] == PREVIEW:
        return last[2]
    k = s.preview_scale
    e = replace(s, **PREVIEW, width=-(-s.width // k), height=-(-s.height // k))
    _EFFECTIVE_LAST = (s, dict(PREVIEW), e)
    return e


#: (settings, PREVIEW as it was, effective settings) of the last call of :func:`effective` with a preview
_EFFECTIVE_LAST: tuple = (None, None, None)


#: a depth's point within this share of (1 + its distance) of the water plane shows the water
#: (:meth:`TerrainTechnique.changing`): the plane's hit is analytic, so only float32 rounding (~1e-6 of the
#: distance) and the march's precision near the shore separate them
WATER_TOLERANCE = 1e-3


class TerrainTechnique(Technique):
    """``init`` (parameters, Perlin table, buffers), ``update(**changes)``, ``render(pose)``, ``resize``."""

    settings_class = TerrainSettings
    #: the viewer's previews through the temporal reconstruction, fed the march's depth and the water
    #: (:meth:`depth`, :meth:`changing`): at 1/16 of the pixels per frame, on the viewer benchmark's walk
    #: (tools/terrain_preview_eval.py), SSIM 0.868 / 0.856 (mean / 5th percentile) against the full render where the
    #: enlarged 213 x 120 frame of the same CPU gives 0.834 / 0.820 (over the whole 13 s, a crest included, 0.890 /
    #: 0.832 against 0.892 / 0.851); it costs the 640 x 360 resolve on top (~18 ms of CPU a frame besides the
    #: 160 x 90 render's ~35: fewer frames/s; the sky, ~43 % of the picture, is interpolated while moving)
    preview_mode = "temporal"

    def invalidated(self, new: TerrainSettings, old: TerrainSettings) -> set:
        """The specs' invalidations, and "size" when the quality or the preview scale changes (the preview frame has
        its own size)."""
        stale = new.invalidated(old)
        if (new.quality, new.preview_scale) != (old.quality, old.preview_scale):
            stale.add("size")
        return stale

    def rebuild(self, stale: set, changed: set) -> None:
        """Every change is a new parameter struct (checked by ccl_terrain_params_check) and Perlin table."""
        s = self.settings
        self.params = effective(s).warp_params()
        self.perm = K.hashed_perm_array(s.seed, self.device)

    def allocate(self, width: int, height: int) -> None:
        e = effective(self.settings)
        self._buffers = {"out": wp.zeros((e.height, e.width, 3), dtype=float, device=self.device),
                         "steps": wp.zeros((e.height, e.width), dtype=wp.int32, device=self.device),
                         "depth": wp.zeros((e.height, e.width), dtype=float, device=self.device)}

    def render(self, pose: Pose | None = None, progress=None, encode: bool = True) -> np.ndarray:
        """One frame: uint8 (height, width, 3) through the display transform of the ``exposure_ev`` and ``tonemap``
        settings (:func:`pywarp.core.display.encode_encoded`: the colours are display-encoded), or the float colours
        in [0, 1] when ``encode=False``. ``progress`` is called with fractions of the frame (summing to 1) as row bands finish."""
        full = self.settings
        s = effective(full)
        pose = pose or Pose.from_settings(full)
        cam = CAM.pose_camera(pose, s.width, s.height)
        self._last_camera = cam
        b = self._buffers
        band_done = None if progress is None else (lambda n, total=s.height: progress(n / total))
        self.launcher.launch(K.render_kernel, s.height, s.width,
                             [self.params, self.perm, cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), s.width,
                              s.height], [b["out"], b["steps"], b["depth"]], progress=band_done)
        self.frame += 1
        img = b["out"].numpy()
        if not np.all(np.isfinite(img)):
            raise RuntimeError("the render produced non-finite pixels")
        if (s.width, s.height) != (full.width, full.height):  # the preview: enlarge (nearest pixel)
            k = full.preview_scale
            img = np.repeat(np.repeat(img, k, axis=0), k, axis=1)[:full.height, :full.width]
        if not encode:
            return img.copy()
        return display.encode_encoded(img, full.exposure_ev, full.tonemap)

    def depth(self) -> np.ndarray | None:
        """Distance along each pixel's centre ray to the surface it shows in the last frame (float32, the rendered
        size; -1 for the sky), as the temporal reconstruction reprojects with (:mod:`pywarp.core.temporal`); None
        for a supersampled or enlarged preview frame."""
        full = self.settings
        s = effective(full)
        if s.rays_per_pixel != 1 or (s.width, s.height) != (full.width, full.height):
            return None
        return self._buffers["depth"].numpy().copy()

    def changing(self, depth: np.ndarray | None = None) -> np.ndarray | None:
        """Where the last frame shows the water (bool, :meth:`depth`'s size; None where it has none): its waves move
        with time and its reflection with the view, so the temporal reconstruction colour-clamps its history there
        rather than trusting it by depth (``depth``: :meth:`depth`'s answer where the caller has it already). A pixel
        is water where its depth's point lies on the water plane (within
        :data:`WATER_TOLERANCE` of its distance; the shore's terrain at that height counts too, harmlessly)."""
        d = self.depth() if depth is None else depth
        if d is None:
            return None
        cam = self._last_camera
        h, w = d.shape
        m = np.asarray(cam.inv_view_proj_rot, np.float64)
        nx = 2.0 * (np.arange(w) + 0.5) / w - 1.0
        ny = 1.0 - 2.0 * (np.arange(h) + 0.5) / h
        ray = (m[:3, 0, None, None] * nx[None, None, :] + m[:3, 1, None, None] * ny[None, :, None]
               + (m[:3, 2] + m[:3, 3])[:, None, None])
        dy = ray[1] / np.linalg.norm(ray, axis=0)
        y = float(np.asarray(cam.eye)[1]) + dy * d
        return (d > 0.0) & (np.abs(y - self.settings.water_level) <= WATER_TOLERANCE * (1.0 + d))

    def steps_taken(self) -> np.ndarray:
        """View-march height evaluations per pixel of the last frame (summed over the sub-samples)."""
        return self._buffers["steps"].numpy().copy()


def render_image(settings: TerrainSettings | None = None, pose: Pose | None = None) -> np.ndarray:
    """One uint8 image (height, width, 3) of the terrain."""
    return TerrainTechnique(settings).render(pose)


def render_pixels_c(settings: TerrainSettings, xs, ys, pose: Pose | None = None) -> tuple:
    """The C reference ``ccl_terrain_pixel`` at pixels (xs[k], ys[k]): (colours (k, 3) in [0, 1], steps (k,))."""
    s = settings
    pose = pose or Pose.from_settings(s)
    return equation("pt-alg-7.1.6", impl="c")(np.asarray(xs), np.asarray(ys), s.width, s.height, CAM.pose_camera(pose, s.width, s.height),
                                 s.c_values())


def render_pixels_warp(settings: TerrainSettings, xs, ys, pose: Pose | None = None) -> tuple:
    """The Warp ``terrain_pixel`` at pixels (xs[k], ys[k]) -- the other side of :func:`render_pixels_c`."""
    s = settings
    pose = pose or Pose.from_settings(s)
    return equation("pt-alg-7.1.6", device=s.device)(np.asarray(xs), np.asarray(ys), s.width, s.height,
                                              CAM.pose_camera(pose, s.width, s.height), s.c_values())


def ground_height(settings: TerrainSettings, x, z, octaves: int | None = None) -> np.ndarray:
    """Terrain height at (x, z) with the settings' heightmap (default: the marched octaves)."""
    s = settings
    return E.height(x, z, octaves or s.march_octaves, s.height_scale, s.horizontal_scale, s.seed, s.heightmap,
                    s.device)


def walk_path(frames: int, settings: TerrainSettings) -> list[Pose]:
    """The camera path of ``pywarp animate terrain`` (a scripted walk standing in for the demo's mouse + W): from
    the settings' camera, 3 units per frame along the heading, the heading swinging +-20 deg (one slow S-curve),
    the eye kept at its start height above max(ground, water) -- the ground smoothed over 12 units so that the
    camera glides over small bumps -- and the pitch of the settings."""
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise ValueError(f"frames must be an integer >= 1, got {frames!r}")
    s = settings
    step = 3.0
    yaw0 = s.camera_yaw_deg
    xs, zs, yaws = [s.camera_x], [s.camera_z], []
    for i in range(frames):
        u = i / max(frames - 1, 1)
        yaw = yaw0 + 20.0 * math.sin(2.0 * math.pi * u)
        yaws.append(yaw)
        if i < frames - 1:
            a = math.radians(yaw)
            xs.append(xs[-1] + step * math.sin(a))
            zs.append(zs[-1] - step * math.cos(a))
    xs_a, zs_a = np.array(xs), np.array(zs)
    # ground under the camera, smoothed over +-6 units along and across the path
    offs = np.linspace(-6.0, 6.0, 5)
    gx = xs_a[:, None, None] + offs[None, :, None]
    gz = zs_a[:, None, None] + offs[None, None, :]
    ground = ground_height(s, gx, gz).reshape(frames, -1).mean(axis=1)
    ground = np.maximum(ground, s.water_level)
    clearance = s.camera_y - max(float(ground[0]), s.water_level)
    clearance = max(clearance, 2.0)
    return [Pose(float(xs_a[i]), float(ground[i] + clearance), float(zs_a[i]), yaws[i], s.camera_pitch_deg,
                 s.fov_y_deg) for i in range(frames)]
