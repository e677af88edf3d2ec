"""The volumetric cloudscape of the vc thesis on the CPU: Preetham (or gradient) sky, cloud-layer raymarch, temporal
reprojection -- the render chain of vc-A30 built from the classes of vc-A31 (sky models), vc-A32 (texture generator)
and vc-A33 (visualization technique: init / update / render, plus resize).

    from pywarp.clouds.cloudscape import CloudscapeSettings, render_image
    img = render_image(CloudscapeSettings(width=640, height=360))      # uint8 (360, 640, 3)

One frame (``CloudscapeTechnique.render``):
  1. the sky model writes the background of every pixel (or, with reprojection, of one pixel per 4 x 4 block);
  2. the cloud kernel marches the cloud layer for the same pixels and composites over the background (vc-4.8);
  3. with reprojection, the other 15/16 of the pixels come from the previous frame (vc-A26) at the position found
     through the depth of what each pixel shows (the clouds' mean distance, kept in a depth buffer; the setting
     ``reprojection_depth``: "clouds", or the thesis's "inner_sphere" hit point) and sampled with the filter of
     ``reprojection_filter``, or from the reduced buffer;
  4. sRGB encoding, uint8.
Every stage is a Warp kernel launched as row bands on every core (:class:`pywarp.core.runtime.TileLauncher`). The same
pixel computation exists in C (``ccl_cloudscape_pixel``): :func:`render_pixels_c` runs it at chosen pixels.
"""
from __future__ import annotations

import math
import weakref
from abc import ABC, abstractmethod
from dataclasses import dataclass, field, replace

import numpy as np
import warp as wp

from ..core.runtime import TileLauncher, init, launcher as shared_launcher

init()

from ..kernels import camera as CAM  # noqa: E402
from ..kernels import cloudscape as K  # noqa: E402
from ..kernels import reproj as RP  # noqa: E402
from ..kernels import sky as S  # noqa: E402
from . import textures as T  # noqa: E402
from .settings import CLOUDSCAPE_PARAMS, SKIES, CloudscapeSettings  # noqa: E402,F401  (re-exported)



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

    def camera(self, width: int, height: int) -> CAM.Camera:
        """The vc-A25 camera matrices (``pywarp.kernels.camera.camera_look_at``)."""
        eye = np.array([self.x_km, self.altitude_km, self.z_km])
        return CAM.camera_look_at(eye, eye + self.forward(), (0.0, 1.0, 0.0), math.radians(self.fov_y_deg),
                                width / height, 0.01, 1000.0)


class _JitteredPose:
    """A camera pose seen through its camera moved by (dx_px, dy_px) pixels (:meth:`pywarp.kernels.camera.Camera.
    jittered`); every other attribute is the pose's (CloudscapeTechnique.render_accumulated)."""

    def __init__(self, pose: CameraPose, dx_px: float, dy_px: float):
        self._pose, self.dx_px, self.dy_px = pose, dx_px, dy_px

    def __getattr__(self, name):
        return getattr(self._pose, name)

    def camera(self, width: int, height: int) -> CAM.Camera:
        return self._pose.camera(width, height).jittered(self.dx_px, self.dy_px, width, height)


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

    def render(self, frame_buffer: wp.array, camera: CAM.Camera, frame: int, reprojection: bool,
               params: K.CloudscapeParams, launcher: TileLauncher) -> None:
        h, w = frame_buffer.shape[0], frame_buffer.shape[1]
        rows, cols = (RP.reproj_grid(w, h)[::-1]) if reprojection else (h, w)
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
        t = gen.textures(**settings.textures())
        return cls.from_textures(t, settings.device)

    def level0(self, name: str, half_base: bool = False) -> np.ndarray:
        """A texture (base, detail, curl, weather) as the renderers read it: with ``half_base`` the base's texels
        rounded to float16 values (:func:`half_values`; the C renderer reads these float32 values, Warp stores them as
        half floats, so both read the same numbers)."""
        if name != "base" or not half_base:
            return getattr(self, name)
        if "base_half" not in self._wp:
            self._wp["base_half"] = half_values(self.base, "base texture")
        return self._wp["base_half"]

    def mips(self, name: str, half_base: bool = False) -> np.ndarray:
        """The flat mip chain of the base or detail volume (level 0 first; :func:`pywarp.kernels.cloudscape.mip_chain`);
        with ``half_base`` the base's chain of :meth:`level0`, every level rounded to float16 values."""
        half = half_base and name == "base"
        key = f"mips_{name}" + ("_half" if half else "")
        if key not in self._wp:
            chain = K.mip_chain(self.level0(name, half))
            self._wp[key] = half_values(chain, "base texture") if half else chain
        return self._wp[key]

    def warp(self, half_base: bool = True) -> K.CloudTextures:
        """The :class:`pywarp.kernels.cloudscape.CloudTextures` the kernels read (built once per ``half_base``:
        the base chain as half floats, ``CloudscapeSettings.base_precision`` 'half', or as float32, 'single')."""
        key = "struct_half" if half_base else "struct"
        if key not in self._wp:
            t = K.CloudTextures()
            for name in ("base", "detail"):
                t.__setattr__(name + "_size", int(getattr(self, name).shape[0]))
                t.__setattr__(name + "_levels", K.mip_levels(getattr(self, name).shape[0]))
            t.detail = wp.array(self.mips("detail"), dtype=wp.vec4, device=self.device)
            chain = self.mips("base", half_base)
            if half_base:
                t.base_half = wp.array(chain.astype(np.float16), dtype=wp.vec4h, device=self.device)
                t.base = wp.zeros(1, dtype=wp.vec4, device=self.device)
            else:
                t.base = wp.array(chain, dtype=wp.vec4, device=self.device)
                t.base_half = wp.zeros(1, dtype=wp.vec4h, device=self.device)
            t.half_base = int(bool(half_base))
            t.curl = wp.array(self.curl, dtype=wp.vec4, device=self.device)
            t.weather = wp.array(self.weather, dtype=wp.vec4, device=self.device)
            t.weather_empty = wp.array(K.weather_empty_distance(self.weather), dtype=wp.int32, device=self.device)
            t.empty_skip = 1
            t.selector_class = wp.array(K.selector_class(self.weather), dtype=wp.uint8, device=self.device)
            t.base_bound = K.base_shape_bound(chain)
            self._wp[key] = t
        return self._wp[key]


#: Largest magnitude of a float16 (finite values beyond it would round to infinity)
HALF_MAX = 65504.0


def half_values(a: np.ndarray, what: str) -> np.ndarray:
    """float32 array of the float16 values nearest to ``a`` (round to nearest even; NaN and infinities kept). A finite
    value beyond +-HALF_MAX has no float16 value: ValueError naming ``what``."""
    a = np.asarray(a, dtype=np.float32)
    with np.errstate(invalid="ignore"):
        big = np.isfinite(a) & (np.abs(a) > HALF_MAX)
    if big.any():
        raise ValueError(f"{what}: a texel of {float(a[big].flat[0])!r} is beyond the float16 range "
                         f"+-{HALF_MAX:g}; use base_precision='single'")
    return a.astype(np.float16).astype(np.float32)


# --- the per-frame lighting setup ------------------------------------------------------------------------------------

#: The fields ccl_cloudscape_light / cloudscape_light fill from the sky model (sky lighting).
LIGHT_FIELDS = ("sun_colour", "ambient_top", "ambient_bottom", "ambient_ground")


def light_params(params: K.CloudscapeParams, sky: "SkyModel", device: str = "cpu") -> K.CloudscapeParams:
    """The per-frame lighting setup, twin of ``ccl_cloudscape_light``: with sky lighting, ``params`` with sun colour
    and ambients from ``sky`` (its kind, sun, Preetham and gradient constants), computed once by
    :func:`pywarp.kernels.cloudscape.cloudscape_light` (one thread, the same float32 operations as the C); the
    thesis's lighting returns ``params`` unchanged. Called when the settings or the sky change, not per frame.

    A user's own sky model (a :class:`SkyModel` whose ``kind`` is neither gradient nor Preetham) cannot be evaluated
    per direction by the kernel: its sun still sets the sun colour, and the ambient comes from the default gradient
    sky (vc-A28)."""
    if params.lighting != K.LIGHTING_SKY:
        return params
    kind = int(sky.kind)
    if kind not in (K.SKY_GRADIENT, K.SKY_PREETHAM):
        kind, preetham, gradient = K.SKY_GRADIENT, S.Preetham(), S.gradient_params()
    else:
        preetham, gradient = sky.preetham, sky.gradient
    out = wp.empty(1, dtype=K.CloudscapeParams, device=device)
    wp.launch(K.light_kernel, dim=1, inputs=[params, kind, wp.vec3(*np.asarray(sky.sun).tolist()), preetham,
                                             gradient], outputs=[out], device=device)
    rec = out.numpy()[0]
    for name in LIGHT_FIELDS:
        setattr(params, name, wp.vec3(*rec[name].tolist()))
    return params



# --- the technique (vc-A30, A33) ------------------------------------------------------------------------------------------

class CloudscapeTechnique:
    """The volumetric-clouds visualization technique: ``init`` (textures, sky), ``update`` (settings, time),
    ``render`` (one frame for a camera pose), ``resize``. Holds the frame buffers and the previous camera for the
    temporal reprojection (vc-A26)."""

    def __init__(self, settings: CloudscapeSettings | None = None, generator=None, sky: SkyModel | None = None,
                 textures: RenderTextures | None = None):
        self.settings = settings or CloudscapeSettings()
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
        self.params = light_params(self.settings.warp_params(), self.sky, self.device)
        self.resize(self.settings.width, self.settings.height)

    def update(self, **changes) -> None:
        """Change settings (e.g. ``time_s``, ``sun_elevation_deg``); the settings' specs say what each change
        invalidates: textures are regenerated only when a texture setting changes, the sky only when a sky setting
        does, the buffers when the size does."""
        old = self.settings
        new = replace(old, **changes)
        stale = new.invalidated(old)
        self.settings = new
        if "device" in stale:
            self.launcher = shared_launcher(new.device, new.threads)
            self.device = self.launcher.device
        if "textures" in stale or ("device" in stale and self.textures.device != self.device):
            self.textures = RenderTextures.generate(new, self.generator)
        if "sky" in stale:
            if type(self.sky) in (GradientSky, PreethamSky):
                self.sky = make_sky(new)  # the sky kind may have changed
            else:
                self.sky.update(new)  # a user's own sky model
        self.params = light_params(new.warp_params(), self.sky, self.device)
        if stale & {"size", "device"}:
            self.resize(new.width, new.height)

    def resize(self, width: int, height: int) -> None:
        if (width, height) != (self.settings.width, self.settings.height):
            self.settings = replace(self.settings, width=width, height=height)
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
            "non_finite": wp.zeros(1, dtype=wp.int32, device=dev),
        }
        self._prev_camera = None

    def camera_in_layer_or_above(self, pose: CameraPose) -> bool:
        return pose.altitude_km >= self.settings.layer_base_km

    def render(self, pose: CameraPose | None = None, reprojection: bool | None = None,
               encode: bool = True, progress=None) -> np.ndarray:
        """Render one frame; returns uint8 sRGB (height, width, 3), or the display-linear float frame when
        ``encode=False``. Reprojection (default: the setting) falls back to a full render when the camera is inside
        or above the layer (vc-A24) and on the first frame. ``progress``: optional callable, called with a fraction
        of the frame (the fractions add up to 1) as each band of the cloud pass -- nearly all of the time --
        finishes."""
        s = self.settings
        pose = pose or CameraPose.from_settings(s)
        cam = pose.camera(s.width, s.height)
        reproj = s.reprojection if reprojection is None else bool(reprojection)
        if reproj and self.camera_in_layer_or_above(pose):
            reproj = False  # vc-A24: the view ray does not always hit the inner sphere
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
        """uint8 sRGB of a display-linear frame on the device (encode_kernel: clamp, encode, quantise); a frame with
        a non-finite pixel raises instead (the encoding's clamp would make a NaN a black pixel: never a NaN image,
        not even a black one)."""
        b = self._buffers
        b["non_finite"].zero_()
        self.launcher.launch(K.encode_kernel, self.settings.height, self.settings.width, [linear],
                             [b["encoded"], b["non_finite"]])
        if int(b["non_finite"].numpy()[0]) != 0:
            _finite(linear.numpy())  # raises, naming the first such pixel
        return b["encoded"].numpy().copy()

    def render_linear(self, pose: CameraPose | None = None, progress=None) -> np.ndarray:
        """The linear-image hook (:mod:`pywarp.core.linear`): one frame exactly as :meth:`render` (same frame
        counter and reprojection history), returned as display-linear float32 RGB (height, width, 3) before the
        clamp and the sRGB encoding of ``render``'s uint8 image."""
        return np.asarray(self.render(pose, encode=False, progress=progress), dtype=np.float32)

    def render_accumulated(self, pose: CameraPose | None = None, n: int | None = None, progress=None,
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
        pose = pose or CameraPose.from_settings(s)
        offsets = CAM.subpixel_jitter(n)
        total = None
        for k, (dx, dy) in enumerate(offsets):
            step = None if progress is None else (lambda f: progress(f / n))
            view = pose if k == 0 else _JitteredPose(pose, float(dx), float(dy))
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
        status_error(lb.ccl_sky_preetham_init(settings.turbidity, theta_s, settings.sky_exposure,
                                          0 if settings.sky_variant == "corrected" else 1, f.addressof(sky.preetham)),
                     "ccl_sky_preetham_init")
    else:
        sky.kind = lb.CCL_SKY_GRADIENT
        lb.ccl_sky_gradient_defaults(f.addressof(sky.gradient))
    return sky


def c_textures(textures: RenderTextures, half_base: bool = True):
    """A ``ccl_cloud_textures`` pointing into the NumPy arrays of ``textures`` (which must outlive it: the cffi
    object keeps a reference to each buffer); ``half_base``: the base's texels rounded to float16 values, the numbers
    the Warp renderer reads with ``base_precision`` 'half'."""
    from ..core.binding import ffi

    f = ffi()
    tex = f.new("ccl_cloud_textures *")
    buffers = []
    for name in ("base", "detail", "curl", "weather"):
        arr = textures.level0(name, half_base)
        buf = f.from_buffer("float[]", arr)
        buffers.append(buf)
        setattr(tex, name, f.cast("const float *", buf))
        setattr(tex, f"{name}_size", arr.shape[0])
    for name in ("base", "detail"):
        n = getattr(textures, name).shape[0]
        chain = textures.mips(name, half_base)
        if n > 1:  # levels 1.. of the same chain the Warp kernels read
            buf = f.from_buffer("float[]", chain[n ** 3:])
            buffers.append(buf)
            setattr(tex, f"{name}_mips", f.cast("const float *", buf))
    _KEEP_ALIVE[tex] = buffers
    return tex


_KEEP_ALIVE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # cffi struct -> the buffers it points into


def c_camera(cam: CAM.Camera):
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
    s = settings
    pose = pose or CameraPose.from_settings(s)
    params = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    tex = c_textures(textures, s.half_base())
    sky = c_sky(s)
    cam = c_camera(pose.camera(s.width, s.height))
    field_ = f.new("const char **")
    if lb.ccl_cloudscape_check(params, tex, sky, field_) != 0:
        raise ValueError(f"ccl_cloudscape_check rejected {f.string(field_[0]).decode()}")
    lb.ccl_cloudscape_light(params, sky, params)  # once, as ccl_cloudscape_render does (sky lighting)
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
    tex = technique.textures.warp(s.half_base())
    dev = technique.device
    xa = wp.array(np.asarray(xs, dtype=np.int32), dtype=wp.int32, device=dev)
    ya = wp.array(np.asarray(ys, dtype=np.int32), dtype=wp.int32, device=dev)
    out = wp.zeros((len(xs), 3), dtype=float, device=dev)
    sky = technique.sky
    wp.launch(K.pixels_kernel, dim=len(xs),
              inputs=[technique.params, tex, sky.kind, wp.vec3(*sky.sun.tolist()),
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
    s = settings
    pose = pose or CameraPose.from_settings(s)
    params = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    tex = c_textures(textures, s.half_base())
    out = np.empty((s.height, s.width, 3), dtype=np.float32)
    status = lb.ccl_cloudscape_render(params, tex, c_sky(s), c_camera(pose.camera(s.width, s.height)), s.width,
                                      s.height, frame, f.from_buffer("float[]", out), out.size)
    status_error(status, "ccl_cloudscape_render")
    return out
