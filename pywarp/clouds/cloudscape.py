"""The volumetric cloudscape of the vc thesis on the CPU, the parts the technique (:mod:`pywarp.clouds.technique`) is
built from: the sky models of vc-A31, the textures as the renderer reads them (vc-A32), the per-frame lighting setup,
and the C reference of the same pixel (``ccl_cloudscape_pixel``, ``ccl_cloudscape_render``).

    from pywarp.clouds.cloudscape import RenderTextures, make_sky, render_pixels_c
    from pywarp.clouds.technique import CloudscapeTechnique, render_image
    img = render_image(CloudscapeSettings(width=640, height=360))      # uint8 (360, 640, 3)
    rgb = render_pixels_c(settings, textures, xs, ys)                   # the C reference at chosen pixels
"""
from __future__ import annotations

import math
import weakref
from abc import ABC, abstractmethod
from dataclasses import dataclass, field

import numpy as np
import warp as wp

from ..core.pose import Pose
from ..core.runtime import TileLauncher, init

init()

from ..kernels import camera as CAM  # noqa: E402
from ..kernels import cloudscape as K  # noqa: E402
from ..kernels import reproj as RP  # noqa: E402
from ..kernels import sky as S  # noqa: E402
from . import sky as SKY  # noqa: E402
from . import textures as T  # noqa: E402
from .settings import CLOUDSCAPE_PARAMS, SKIES, CloudscapeSettings  # noqa: E402,F401  (re-exported)


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
        self.gradient = SKY.gradient_params()
        self.preetham = S.Preetham()  # unused by the kernel for this kind


class PreethamSky(SkyModel):
    """vc-A29: the Preetham 1999 analytic daylight model, tone mapped (vc-4.5) or as radiance (units=physical)."""

    kind = K.SKY_PREETHAM

    def update(self, settings: CloudscapeSettings) -> None:
        # units='physical': the radiance k C_HDR instead of the tone map (K.SKY_PREETHAM_RADIANCE, cloudscape.h)
        self.kind = K.SKY_PREETHAM_RADIANCE if settings.units == "physical" else K.SKY_PREETHAM
        self.sun = settings.sun()
        theta_s = math.radians(90.0 - settings.sun_elevation_deg)
        self.preetham = SKY.preetham_params(settings.turbidity, min(theta_s, float(np.float32(math.pi / 2))),
                                          exposure=settings.sky_exposure, variant=settings.sky_variant)
        self.gradient = SKY.gradient_params()


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
        """The flat mip chain of the base or detail volume (level 0 first; :func:`mip_chain`);
        with ``half_base`` the base's chain of :meth:`level0`, every level rounded to float16 values."""
        half = half_base and name == "base"
        key = f"mips_{name}" + ("_half" if half else "")
        if key not in self._wp:
            chain = mip_chain(self.level0(name, half))
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
                t.__setattr__(name + "_levels", mip_levels(getattr(self, name).shape[0]))
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
            t.weather_empty = wp.array(weather_empty_distance(self.weather), dtype=wp.int32, device=self.device)
            t.empty_skip = 1
            t.selector_class = wp.array(selector_class(self.weather), dtype=wp.uint8, device=self.device)
            t.base_bound = base_shape_bound(chain)
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


def mip_levels(size: int) -> int:
    """Levels of the full mip chain of a power-of-two edge: size, size / 2, ..., 1."""
    return int(size).bit_length()


def mip_chain(tex: np.ndarray) -> np.ndarray:
    """The mip chain of a periodic RGBA volume ``tex[z, y, x, 4]`` (power-of-two edge) as one flat float32 (texels, 4)
    array, level 0 first; each texel of level k + 1 is the mean of its 8 children of level k, added in the order of
    ``ccl_cloudscape_mip3`` (x fastest, then y, then z), so C and NumPy agree bit for bit."""
    a = np.ascontiguousarray(tex, dtype=np.float32)
    n = a.shape[0]
    if a.ndim != 4 or a.shape[:3] != (n, n, n) or a.shape[3] != 4 or n < 1 or n & (n - 1):
        raise ValueError(f"mip_chain needs an (n, n, n, 4) volume with n a power of two, got {a.shape}")
    levels = [a.reshape(-1, 4)]
    while n > 1:
        s = a[0::2, 0::2, 0::2] + a[0::2, 0::2, 1::2]
        s = s + a[0::2, 1::2, 0::2]
        s = s + a[0::2, 1::2, 1::2]
        s = s + a[1::2, 0::2, 0::2]
        s = s + a[1::2, 0::2, 1::2]
        s = s + a[1::2, 1::2, 0::2]
        s = s + a[1::2, 1::2, 1::2]
        a = np.ascontiguousarray(s * np.float32(0.125), dtype=np.float32)
        n //= 2
        levels.append(a.reshape(-1, 4))
    return np.concatenate(levels, axis=0)


#: Largest distance :func:`weather_empty_distance` records (texels): a skip of at most EMPTY_CAP - 3 weather texels
#: (2.3 km for the default 32 km map of 512 texels) -- longer skips would save little, the map costs EMPTY_CAP passes.
EMPTY_CAP = 40


def weather_empty_distance(weather: np.ndarray, cap: int = EMPTY_CAP) -> np.ndarray:
    """Empty-space map of a periodic weather map ``weather[y, x, 4]``: per texel the Chebyshev distance (texels, at
    most ``cap``) to the nearest texel whose coverage (R) is not <= 0, on the torus. A sample in texel T with distance
    D >= K.EMPTY_MARGIN has coverage exactly 0 (bilinear weights of four zero texels), and so has every point within
    D - K.EMPTY_MARGIN texels of it: the march skips those samples (their density is 0 in any case)."""
    cov = np.asarray(weather, dtype=np.float32)[..., 0]
    occupied = ~(cov <= 0.0)  # a NaN counts as occupied
    dist = np.zeros(cov.shape, dtype=np.int32)
    reach = occupied.copy()
    for _ in range(int(cap)):
        if reach.all():
            break
        dist += ~reach
        reach = reach | np.roll(reach, 1, 0) | np.roll(reach, -1, 0)
        reach = reach | np.roll(reach, 1, 1) | np.roll(reach, -1, 1)
    return dist


#: Relative and absolute margin of :func:`base_shape_bound` over the bound in exact arithmetic: the float32 trilinear
#: blend of a convex combination and the float32 remap of vc-2.28 may exceed it by a few ulps (~1e-7); the margin is
#: a hundred times that, and still skips nearly every sample the exact bound would (B_D > 0 needs B D_v > C).
BASE_BOUND_MARGIN = 1.0e-5


def base_shape_bound(chain: np.ndarray) -> float:
    """An upper bound of the base shape B = remap(C_R, L_FBM - 1, 1, 0, 1) of vc-2.28 at any sample of a base mip
    chain ``chain[texels, 4]`` (:func:`mip_chain`), or 0 (no bound) where none is proved.

    Every sample is a convex combination of texels (trilinear weights, the blend of two levels, levels that are means
    of level 0), so its C_R <= max C_R and its L_FBM (linear in the channels) >= min L_FBM. With C_R <= 1 and
    L_FBM < 2, B = (C_R + 1 - L) / (2 - L) rises with C_R and falls with L (dB/dL = (C_R - 1) / (2 - L)^2 <= 0), so
    B <= (max C_R + 1 - min L) / (2 - min L). Textures outside that domain (or with a NaN) get no bound."""
    a = np.asarray(chain, dtype=np.float64).reshape(-1, 4)
    if a.size == 0 or not np.isfinite(a).all():
        return 0.0
    r_max = float(a[:, 0].max())
    l_fbm = 0.625 * a[:, 1] + 0.25 * a[:, 2] + 0.125 * a[:, 3]
    l_min, l_max = float(l_fbm.min()), float(l_fbm.max())
    if not (r_max <= 1.0 and l_max < 2.0):
        return 0.0
    b = (r_max + 1.0 - l_min) / (2.0 - l_min)
    return float(max(b, 0.0) * (1.0 + BASE_BOUND_MARGIN) + BASE_BOUND_MARGIN)


#: Margin of :func:`selector_class` (coverage units): a float32 bilinear blend of four texels stays within this of
#: their range (its error is a few ulps of values <= 1, ~1e-7).
SELECTOR_MARGIN = 1.0e-6


def selector_class(weather: np.ndarray) -> np.ndarray:
    """Per cell (i, j) of a periodic weather map ``weather[y, x, 4]`` -- the square between the texel centres
    (j, i), (j, i + 1), (j + 1, i), (j + 1, i + 1), wrapped, which a bilinear lookup whose lower texel is (i, j)
    reads -- 0 where all four coverages (R) are <= edge0 - SELECTOR_MARGIN (the de-tiling's selector is certainly
    below edge0: blend weight exactly 0), 1 where all are >= edge1 + SELECTOR_MARGIN (weight exactly 1), else 2
    (NaN included)."""
    r = np.asarray(weather, dtype=np.float64)[..., 0]
    four = [r, np.roll(r, -1, 1), np.roll(r, -1, 0), np.roll(np.roll(r, -1, 0), -1, 1)]
    lo = K.WEATHER_DETILE["edge0"] - SELECTOR_MARGIN
    hi = K.WEATHER_DETILE["edge1"] + SELECTOR_MARGIN
    below = np.logical_and.reduce([c <= lo for c in four])
    above = np.logical_and.reduce([c >= hi for c in four])
    return np.where(below, 0, np.where(above, 1, 2)).astype(np.uint8)


# --- the per-frame lighting setup ------------------------------------------------------------------------------------

#: The fields ccl_cloudscape_light / cloudscape_light fill from the sky model (sky lighting).
LIGHT_FIELDS = ("sun_colour", "ambient_top", "ambient_bottom", "ambient_ground")
#: The extinctions ccl_cloudscape_light scales (delta scaling of the Mie phase, mie_delta > 0).
LIGHT_SCALARS = ("sigma", "sigma_light")


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
    if kind not in (K.SKY_GRADIENT, K.SKY_PREETHAM, K.SKY_PREETHAM_RADIANCE):
        kind, preetham, gradient = K.SKY_GRADIENT, S.Preetham(), SKY.gradient_params()
    else:
        preetham, gradient = sky.preetham, sky.gradient
    out = wp.empty(1, dtype=K.CloudscapeParams, device=device)
    wp.launch(K.light_kernel, dim=1, inputs=[params, kind, wp.vec3(*np.asarray(sky.sun).tolist()), preetham,
                                             gradient], outputs=[out], device=device)
    rec = out.numpy()[0]
    for name in LIGHT_FIELDS:
        setattr(params, name, wp.vec3(*rec[name].tolist()))
    for name in LIGHT_SCALARS:
        setattr(params, name, float(rec[name]))
    return params



# --- the C reference ------------------------------------------------------------------------------------------------------

def c_sky(settings: CloudscapeSettings):
    from ..core.binding import ffi, lib, status_error

    f, lb = ffi(), lib()
    sky = f.new("ccl_cloudscape_sky *")
    sun = settings.sun()
    sky.sun[0], sky.sun[1], sky.sun[2] = (float(x) for x in sun)
    if settings.sky == "preetham":
        sky.kind = lb.CCL_SKY_PREETHAM_RADIANCE if settings.units == "physical" else lb.CCL_SKY_PREETHAM
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


def render_pixels_c(settings: CloudscapeSettings, textures: RenderTextures, xs, ys, pose: Pose | None = None,
                    frame: int = 0) -> np.ndarray:
    """``ccl_cloudscape_pixel`` (the scalar C reference) at pixels (xs[k], ys[k]): display-linear RGB (k, 3)."""
    from ..core.binding import ffi, lib

    f, lb = ffi(), lib()
    s = settings
    pose = pose or Pose.from_settings(s)
    params = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    tex = c_textures(textures, s.half_base())
    sky = c_sky(s)
    cam = CAM.pose_camera(pose, s.width, s.height).to_c()
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


def render_pixels_warp(technique, xs, ys, pose: Pose | None = None,
                       frame: int = 0) -> np.ndarray:
    """:func:`pywarp.kernels.cloudscape.cloudscape_pixel` at pixels (xs[k], ys[k]) -- the Warp side of the comparison
    with :func:`render_pixels_c`."""
    s = technique.settings
    pose = pose or Pose.from_settings(s)
    cam = CAM.pose_camera(pose, s.width, s.height)
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


def render_frame_c(settings: CloudscapeSettings, textures: RenderTextures, pose: Pose | None = None,
                   frame: int = 0) -> np.ndarray:
    """A whole frame with the C reference ``ccl_cloudscape_render`` (one thread): sRGB floats (height, width, 3)."""
    from ..core.binding import ffi, lib, status_error

    f, lb = ffi(), lib()
    s = settings
    pose = pose or Pose.from_settings(s)
    params = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    tex = c_textures(textures, s.half_base())
    out = np.empty((s.height, s.width, 3), dtype=np.float32)
    status = lb.ccl_cloudscape_render(params, tex, c_sky(s), CAM.pose_camera(pose, s.width, s.height).to_c(), s.width,
                                      s.height, frame, f.from_buffer("float[]", out), out.size)
    status_error(status, "ccl_cloudscape_render")
    return out
