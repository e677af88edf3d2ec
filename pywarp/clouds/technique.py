"""The cloudscape technique (vc-A30's render chain, vc-A33's init / update / render, plus resize): Preetham (or
gradient) sky, cloud-layer raymarch, temporal reprojection, on the textures and sky models of
:mod:`pywarp.clouds.cloudscape`.

    from pywarp.clouds.settings import CloudscapeSettings
    from pywarp.clouds.technique import CloudscapeTechnique, render_image
    from pywarp.core.pose import Pose
    img = render_image(CloudscapeSettings(width=640, height=360))      # uint8 (360, 640, 3)
    img = CloudscapeTechnique().render(Pose(y=0.3, pitch_deg=10))      # the camera 300 m up, looking 10 deg up

One frame (``CloudscapeTechnique.render``):
  1. the sky model writes the background of every pixel (or, with reprojection, of one pixel per 4 x 4 block);
  2. the cloud kernel marches the cloud layer for the same pixels and composites over the background (vc-4.8);
  3. with reprojection, the other 15/16 of the pixels come from the previous frame (vc-A26) at the position found
     through the depth of what each pixel shows (the clouds' mean distance, kept in a depth buffer; the setting
     ``reprojection_depth``: "clouds", or the thesis's "inner_sphere" hit point) and sampled with the filter of
     ``reprojection_filter``, or from the reduced buffer;
  4. sRGB encoding, uint8.
Every stage is a Warp kernel launched as row bands on every core (:class:`pywarp.core.runtime.TileLauncher`). The same
pixel computation exists in C (``ccl_cloudscape_pixel``): :func:`pywarp.clouds.cloudscape.render_pixels_c` runs it at
chosen pixels. The camera is a :class:`pywarp.core.pose.Pose` (position in km).
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import warp as wp

from ..core import display
from ..core.pose import Pose
from ..core.runtime import init
from ..core.technique import Technique

init()

from ..kernels import camera as CAM  # noqa: E402
from ..kernels import cloudscape as K  # noqa: E402
from ..kernels import reproj as RP  # noqa: E402
from .cloudscape import GradientSky, PreethamSky, RenderTextures, SkyModel, light_params, make_sky  # noqa: E402
from .settings import CloudscapeSettings  # noqa: E402


class CloudscapeTechnique(Technique):
    """The volumetric-clouds visualization technique: ``init`` (textures, sky), ``update`` (settings, time),
    ``render`` (one frame for a camera pose), ``resize``. Holds the frame buffers and the previous camera for the
    temporal reprojection (vc-A26)."""

    settings_class = CloudscapeSettings
    #: True while the viewer renders a preview frame (:class:`pywarp.viewer.session.RenderWorker` sets it; ``pywarp
    #: render`` and the stills never do): with reprojection on and the depth-aware reprojection
    #: (``reprojection_depth="clouds"``), a camera above the layer top reprojects too instead of marching every pixel
    #: (see :meth:`reprojects`)
    preview: bool = False

    def __init__(self, settings: CloudscapeSettings | None = None, generator=None, sky: SkyModel | None = None,
                 textures: RenderTextures | None = None):
        self.generator = generator
        self.textures = textures
        self.sky = sky
        self._prev_camera = None
        super().__init__(settings)

    # vc-A33: init / update / render, and the resize notification
    def init(self) -> None:
        """The textures and the sky (those passed to the constructor are kept), the parameters, the buffers."""
        if self.textures is None:
            self.textures = RenderTextures.generate(self.settings, self.generator)
        if self.sky is None:
            self.sky = make_sky(self.settings)
        self.rebuild(set(), set())
        self.resize(self.settings.width, self.settings.height)

    def rebuild(self, stale: set, changed: set) -> None:
        """Textures are regenerated only when a texture setting changes (or the device, unless they are on the new
        one already), the sky only when a sky setting does; every change is a new parameter struct."""
        s = self.settings
        if "textures" in stale or ("device" in stale and self.textures.device != self.device):
            self.textures = RenderTextures.generate(s, self.generator)
        if "sky" in stale:
            if type(self.sky) in (GradientSky, PreethamSky):
                self.sky = make_sky(s)  # the sky kind may have changed
            else:
                self.sky.update(s)  # a user's own sky model
        self.params = light_params(s.warp_params(), self.sky, self.device)

    def allocate(self, width: int, height: int) -> None:
        gw, gh = RP.reproj_grid(width, height)
        dev = self.device
        self._buffers = {
            "current": wp.zeros((height, width, 3), dtype=float, device=dev),
            "previous": wp.zeros((height, width, 3), dtype=float, device=dev),
            "out": wp.zeros((height, width, 3), dtype=float, device=dev),
            "reduced": wp.zeros((gh, gw, 3), dtype=float, device=dev),
            "samples": wp.zeros((height, width), dtype=wp.int32, device=dev),
            # distances (km) of what each pixel shows, for the depth-aware reprojection: this frame's marched pixels,
            # the previous frame's and this frame's final depths (ping-pong like the colour)
            "depth": wp.zeros((height, width), dtype=float, device=dev),
            "prev_depth": wp.zeros((height, width), dtype=float, device=dev),
            "out_depth": wp.zeros((height, width), dtype=float, device=dev),
            "encoded": wp.zeros((height, width, 3), dtype=wp.uint8, device=dev),
            "display": wp.zeros((height, width, 3), dtype=float, device=dev),
            "non_finite": wp.zeros(1, dtype=wp.int32, device=dev),
        }
        self._prev_camera = None

    def camera_in_layer_or_above(self, pose: Pose) -> bool:
        return pose.y >= self.settings.layer_base_km

    def reprojects(self, pose: Pose, wanted: bool) -> bool:
        """Whether a frame with reprojection ``wanted`` reprojects at ``pose``. The thesis's rule (vc-A24): not
        inside or above the layer, where the view ray does not always hit the inner sphere that its reprojection goes
        through. A :attr:`preview` above the layer top is the exception when the reprojection is depth-aware: each
        pixel's point is found from the depth of what it shows (the clouds' or the ground's distance, refined from
        the inner sphere's hit), which from above is as good as from below; the rays that miss the inner sphere (the
        sky over the horizon) take the reduced buffer. Measured on the viewer's motion from 6 km looking 25 deg down
        (SSIM against the full render, 640 x 360): 320 x 180 reprojected (80 x 45 marched per frame) 0.916 against
        0.877 for 80 x 45 marched whole and enlarged, at about 1.3 times its frame time. Inside the layer the rays
        looking up miss the inner sphere and would all take the reduced buffer: the full march stays."""
        if not wanted or not self.camera_in_layer_or_above(pose):
            return bool(wanted)
        return self.preview and self.settings.reprojection_depth == "clouds" and pose.y > self.settings.layer_top_km

    def render(self, pose: Pose | None = None, reprojection: bool | None = None,
               encode: bool = True, progress=None) -> np.ndarray:
        """Render one frame; returns uint8 sRGB (height, width, 3), or the display-linear float frame when
        ``encode=False``. Reprojection (default: the setting) falls back to a full render when the camera is inside
        or above the layer (vc-A24; above it, previews excepted: :meth:`reprojects`) and on the first frame. ``progress``: optional callable, called with a fraction
        of the frame (the fractions add up to 1) as each band of the cloud pass -- nearly all of the time --
        finishes."""
        s = self.settings
        pose = pose or Pose.from_settings(s)
        cam = CAM.pose_camera(pose, s.width, s.height)
        reproj = self.reprojects(pose, s.reprojection if reprojection is None else bool(reprojection))
        b = self._buffers
        h, w = s.height, s.width
        layer = s.layer()
        tex = self.textures.warp(s.half_base())
        sun = wp.vec3(*self.sky.sun.tolist())
        target = b["current"] if reproj else b["out"]
        depth_target = b["depth"] if reproj else b["out_depth"]
        self.sky.render(target, cam, self.frame, reproj, self.params, self.launcher)
        rows, cols = (RP.reproj_grid(w, h)[::-1]) if reproj else (h, w)
        band_done = None if progress is None else (lambda n, total=rows: progress(n / total))
        self.launcher.launch(K.clouds_kernel, rows, cols,
                             [self.params, tex, sun, cam.mat44("inv_view_proj_rot"),
                              cam.eye_vec3(), self.frame, int(reproj)],
                             [target, b["reduced"], b["samples"], depth_target], progress=band_done)
        if reproj:
            history = int(self._prev_camera is not None)
            prev = self._prev_camera or cam
            # depth-aware (cclouds/reproj.h): the fixed-point iteration on the depth; 0 iterations and the bilinear
            # filter = the thesis's inner-sphere point and sampling (the colours of RP.reproject_frame_kernel), the
            # depths still carried
            iterations = RP.DEPTH_ITERATIONS if s.reprojection_depth == "clouds" else 0
            flt = RP.FILTERS[s.reprojection_filter]
            self.launcher.launch(RP.reproject_frame_depth_kernel, h, w,
                                 [b["current"], b["depth"], b["previous"], b["prev_depth"], b["reduced"], self.frame,
                                  cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), prev.mat44("view_proj"),
                                  prev.eye_vec3(), layer.centre_vec3(), layer.r_inner,
                                  int(s.reprojection_neighbourhood), flt, iterations, history],
                                 [b["out"], b["out_depth"]])
        # the final frame becomes the previous one (ping-pong)
        b["previous"], b["out"] = b["out"], b["previous"]
        b["prev_depth"], b["out_depth"] = b["out_depth"], b["prev_depth"]
        final = b["previous"]
        self._prev_camera = cam if reproj or s.reprojection else None
        self.frame += 1
        if not encode:
            return _finite(final.numpy().copy())
        return self._encode(final)

    def _encode(self, linear: wp.array) -> np.ndarray:
        """uint8 sRGB of a display-linear frame on the device: the display transform of the ``exposure_ev`` and
        ``tonemap`` settings (:func:`pywarp.core.display.apply`; skipped for ``none`` at 0 EV, which it would leave
        unchanged), then encode_kernel (clamp, encode, quantise); a frame with
        a non-finite pixel raises instead (the encoding's clamp would make a NaN a black pixel: never a NaN image,
        not even a black one)."""
        b = self._buffers
        b["non_finite"].zero_()
        s = self.settings
        if (s.tonemap, s.exposure_ev) != ("none", 0.0):  # the display transform (pywarp.core.display), on the host
            b["display"].assign(display.apply(linear.numpy(), s.exposure_ev, s.tonemap))
            linear = b["display"]
        self.launcher.launch(K.encode_kernel, s.height, s.width, [linear], [b["encoded"], b["non_finite"]])
        if int(b["non_finite"].numpy()[0]) != 0:
            _finite(linear.numpy())  # raises, naming the first such pixel
        return b["encoded"].numpy().copy()

    def render_linear(self, pose: Pose | None = None, progress=None) -> np.ndarray:
        """The linear-image hook (:mod:`pywarp.core.linear`): one frame exactly as :meth:`render` (same frame
        counter and reprojection history), returned as display-linear float32 RGB (height, width, 3) before the
        clamp and the sRGB encoding of ``render``'s uint8 image."""
        return np.asarray(self.render(pose, encode=False, progress=progress), dtype=np.float32)

    def render_accumulated(self, pose: Pose | None = None, n: int | None = None, progress=None,
                           encode: bool = True) -> np.ndarray:
        """A still without noise: the average of ``n`` full frames (default: the ``accumulate`` setting) in
        display-linear space, encoded once (uint8 sRGB like :meth:`render`; ``encode=False``: display-linear
        float32). Frame k looks through the camera moved by the sub-pixel offset k of the R2 sequence
        (:func:`pywarp.kernels.camera.subpixel_jitter`, offset 0 = the pixel centre; a box filter over the pixel:
        anti-aliased edges) and uses its own frame counter (``self.frame`` + k: a new ray jitter, vc-A23), so both
        the aliasing and the jitter noise average out (the noise falls as 1/sqrt(n)). No reprojection. n = 1 is
        :meth:`render` without reprojection, bit for bit. ``progress``: fractions of the whole accumulation (they add
        up to 1). ``n`` is checked (1..1024) before any kernel runs."""
        from ..core.params import specs

        spec = next(p for p in specs(CloudscapeSettings) if p.name == "accumulate")
        n = spec.validate(self.settings.accumulate if n is None else n, "accumulate")
        s = self.settings
        pose = pose or Pose.from_settings(s)
        offsets = CAM.subpixel_jitter(n)
        total = None
        for k, (dx, dy) in enumerate(offsets):
            step = None if progress is None else (lambda f: progress(f / n))
            view = pose if k == 0 else replace(pose, jitter_px=(float(dx), float(dy)))
            frame = self.render(view, reprojection=False, encode=False, progress=step)
            total = frame.astype(np.float64) if total is None else total + frame
        self._prev_camera = None  # a jittered camera is no history for a later reprojected frame
        linear = (total / n).astype(np.float32)
        if not encode:
            return linear
        b = self._buffers
        b["previous"].assign(linear)
        return self._encode(b["previous"])

    def samples_taken(self) -> np.ndarray:
        """View samples marched per pixel in the last frame (pixels not rendered keep older counts)."""
        return self._buffers["samples"].numpy().copy()


def _finite(linear: np.ndarray) -> np.ndarray:
    """``linear`` (height, width, 3) when every channel is finite; else a RuntimeError naming the first bad pixel."""
    bad = ~np.all(np.isfinite(linear), axis=2)
    if bad.any():
        ys, xs = np.nonzero(bad)
        raise RuntimeError(f"the render produced {len(ys)} non-finite pixels (first at x={xs[0]}, y={ys[0]}); "
                           "nothing is written")
    return linear


def render_image(settings: CloudscapeSettings | None = None, pose: Pose | None = None) -> np.ndarray:
    """One uint8 sRGB image (height, width, 3) of the cloudscape."""
    return CloudscapeTechnique(settings).render(pose, reprojection=False)


def flythrough_path(frames: int, settings: CloudscapeSettings) -> list[Pose]:
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
        poses.append(Pose(s.camera_x_km + math.sin(yaw) * dist, alt, s.camera_z_km - math.cos(yaw) * dist,
                                s.camera_yaw_deg, pitch, s.fov_y_deg))
    return poses
