"""The rain technique (rr-alg-4.1's classes, on the platform's init / update / render / resize design):

* the background (TERRAIN + SKYBOX of the application): any registered scene rendered through its own technique, or
  the built-in analytic :class:`Panorama`; rendered twice and cached -- the view at the output size and the
  wide-angle capture (FBOBJECT, rr-alg-3.1.2: the viewer's pose, FOVy 150 deg; 256 x 256 by default, the text's
  512 x 512 with ``--capture-size 512``);
* DROP: the refraction mask of the chosen shape (rr-alg-3.1.1, ``pywarp.kernels.rain``), built once per shape;
* RAIN PARTICLE: :class:`pywarp.rain.particles.ParticleSystem` (rr-code-5.2.2), advanced by the time field;
* SHADER + POST OBJECT: the particles projected to billboards (drops, or streaks, rr-alg-3.2.3) and composited over
  the view by the refraction / persistence shaders (rr-code-5.2.3 / 5.2.4) in one multi-core Warp pass over the
  screen tiles that hold drops;
* the light-drop model the text describes but never built (rr-A1..rr-A3, rr-CF): two point lights, off by default
  (settings ``light1_*``, ``light2_*``, ``light_ambient``, ``light_r_half``, ``light_variant``).

    from pywarp.rain.technique import RainTechnique
    from pywarp.rain.settings import RainSettings
    img = RainTechnique(RainSettings(background="panorama")).render()     # uint8 (360, 640, 3)
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..core import display
from ..core.pose import Pose
from ..core.runtime import init
from ..core.technique import Technique

init()

from . import particles as P  # noqa: E402
from .settings import PANORAMA, RainSettings, background_fields, check_background_options  # noqa: E402


# --- backgrounds ---------------------------------------------------------------------------------------------------------

class Panorama:
    """A built-in analytic background (display-encoded RGB in [0, 1]): a grey rain sky brightening to the horizon, a
    checkered ground plane 1.7 m below the eye (2 m squares) and a ring of coloured posts 40 m away -- enough structure
    to read the refraction (each drop shows it upside down). A function of the view direction only."""

    def render(self, pose: Pose, width: int, height: int, fov_y_deg: float) -> np.ndarray:
        s, u, f = pose.basis()
        t = math.tan(math.radians(fov_y_deg) / 2.0)
        xs = (2.0 * (np.arange(width) + 0.5) / width - 1.0) * t * width / height
        ys = (1.0 - 2.0 * (np.arange(height) + 0.5) / height) * t
        d = f[None, None, :] + xs[None, :, None] * s[None, None, :] + ys[:, None, None] * u[None, None, :]
        d /= np.linalg.norm(d, axis=-1, keepdims=True)
        return self.colour(d)

    @staticmethod
    def colour(d: np.ndarray) -> np.ndarray:
        dy = d[..., 1]
        sky_t = np.clip(dy, 0.0, 1.0)[..., None] ** 0.5
        sky = (1.0 - sky_t) * np.array([0.72, 0.75, 0.80]) + sky_t * np.array([0.38, 0.42, 0.50])
        with np.errstate(divide="ignore", invalid="ignore"):
            dist = np.where(dy < -1e-4, -1.7 / dy, np.inf)
        with np.errstate(invalid="ignore"):  # sky directions: inf * 0 -> NaN, never used (the sky is chosen)
            gx, gz = d[..., 0] * dist, d[..., 2] * dist
        with np.errstate(invalid="ignore"):
            check = ((np.floor(gx / 2.0) + np.floor(gz / 2.0)) % 2 == 0)[..., None]
        ground = np.where(check, np.array([0.22, 0.36, 0.16]), np.array([0.45, 0.40, 0.30]))
        fade = np.exp(-np.nan_to_num(dist, posinf=1e9) / 80.0)[..., None]
        ground = fade * ground + (1.0 - fade) * np.array([0.62, 0.64, 0.66])
        img = np.where((dy < -1e-4)[..., None], ground, sky)
        # posts: 12 vertical cylinders of radius 1.5 m at 40 m, from the ground to 8 m up
        az = np.arctan2(d[..., 0], -d[..., 2])
        k = np.round(az / (2 * np.pi / 12))
        off = np.abs(az - k * 2 * np.pi / 12) * 40.0
        horiz = np.sqrt(d[..., 0] ** 2 + d[..., 2] ** 2)
        with np.errstate(divide="ignore", invalid="ignore"):
            h = 40.0 * dy / horiz
        post = (off < 1.5) & (h > -1.7) & (h < 8.0)
        hues = np.array([[0.85, 0.20, 0.15], [0.95, 0.75, 0.15], [0.20, 0.45, 0.85], [0.90, 0.90, 0.90]])
        pc = hues[(k.astype(np.int64) % 4)]
        img = np.where(post[..., None], pc * (0.6 + 0.4 * (1.0 - off / 1.5))[..., None], img)
        return img.astype(np.float32)


class SceneBackground:
    """A registered scene as the background: its settings (``options``, then width, height, fov_y_deg,
    camera_yaw_deg, camera_pitch_deg where it has those fields) and its technique's ``render``."""

    def __init__(self, name: str, options: dict, device: str = "cpu", threads=None):
        from ..core.scenes import scene

        check_background_options(name, options, "options")
        self.scene = scene(name)
        fields = background_fields(name)
        base = dict(options)
        for k, v in (("device", device), ("threads", threads)):
            if k in fields:
                base[k] = v
        self.fields = fields
        self.base = self.scene.settings(**base)
        self._techniques: dict = {}

    def technique(self, pose: Pose, width: int, height: int, fov_y_deg: float):
        """The background scene's technique at this size, its settings following the pose's yaw and pitch."""
        changes = {k: v for k, v in (("width", width), ("height", height), ("fov_y_deg", fov_y_deg),
                                     ("camera_yaw_deg", pose.yaw_deg), ("camera_pitch_deg", pose.pitch_deg))
                   if k in self.fields}
        key = (width, height)
        tech = self._techniques.get(key)
        if tech is None:
            tech = self._techniques[key] = self.scene.technique(replace(self.base, **changes))
        else:
            tech.update(**changes)
        return tech

    def render(self, pose: Pose, width: int, height: int, fov_y_deg: float) -> np.ndarray:
        return self.technique(pose, width, height, fov_y_deg).render().astype(np.float32) / 255.0

    def render_reconstructed(self, pose: Pose, width: int, height: int, fov_y_deg: float, up) -> np.ndarray:
        """The view through the temporal reconstruction ``up`` (:class:`pywarp.core.temporal.TemporalUpsampler` of
        width x height): the background at full quality at its planned reduced size and sub-pixel phase, the rest
        the previous view reprojected without the clamp (a background is a function of the direction: the
        far-field reprojection is exact), so that a held direction converges to the full render after f^2 frames.
        The scene's own preview changes are not used: terrain's fewer octaves move its hills (measured SSIM 0.83
        against the full render at any size, 0.91 for the full quality at 1/16 of the pixels enlarged)."""
        from ..viewer.session import technique_camera

        lw, lh, jitter = up.plan()
        camera = technique_camera(self.technique(pose, width, height, fov_y_deg))  # the window picture's camera
        tech = self.technique(pose, lw, lh, fov_y_deg)
        fresh = np.asarray(tech.render(tech.jitter(tech.pose(None), jitter)), np.uint8)
        return up.resolve(fresh, camera, key=self.scene.name, clamp=False).astype(np.float32) / 255.0


def make_background(s: RainSettings):
    if s.background == PANORAMA:
        return Panorama()
    return SceneBackground(s.background, s.background_values(), s.device, s.threads)


# --- the drop mask (DROP) ------------------------------------------------------------------------------------------------

_MASKS: dict = {}


def drop_mask(shape: str, method: str, size: int) -> tuple[np.ndarray, float, np.ndarray]:
    """The refraction mask (size, size, 4) of a Table 2.1 shape by ``method``, its half-size in units of a (the
    billboard of a drop of radius r is r L/a wide) and its entry normals (size, size, 3) (the light-drop model):
    ``pywarp.kernels.rain`` (rr-alg-3.1.1), cached."""
    key = (shape, method, size)
    if key not in _MASKS:
        _MASKS[key] = _build_mask(float(shape), method, size)
    return _MASKS[key]


def _build_mask(a: float, method: str, size: int) -> tuple[np.ndarray, float, np.ndarray]:
    from . import drops as R

    m, normals = R.drop_mask(size, a, method=method, normals=True)
    extent = 1.0 if method == "sphere" else float(np.asarray(R.drop_extent(a)).ravel()[0]) / a
    return np.ascontiguousarray(m, np.float32), extent, np.ascontiguousarray(normals, np.float32)


def sphere_mask(size: int, n_water: float = 1.33) -> np.ndarray:
    """A sphere's refraction mask in NumPy float64 (an independent check of ``pywarp.rain.drops.drop_mask``) (rays along +z through both surfaces; (0, 0, 0) where the exit
    is totally reflected), the encoding of ``ccl_rain_mask``: row 0 the top, (x, y, z) the exit direction (x right,
    y up, z away from the viewer), a the inside flag."""
    j = np.arange(size)
    u = 2.0 * (j + 0.5) / size - 1.0
    uu, vv = np.meshgrid(u, -u)
    r2 = uu * uu + vv * vv
    inside = r2 < 1.0
    zz = -np.sqrt(np.clip(1.0 - r2, 0.0, 1.0))
    n = np.stack([uu, vv, zz], -1)  # outward normal at the entry point (towards the viewer)
    d = np.array([0.0, 0.0, 1.0])

    def refract(d, n, eta):
        cos_i = -np.sum(d * n, -1, keepdims=True)
        k = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
        t = eta * d + (eta * cos_i - np.sqrt(np.clip(k, 0.0, None))) * n
        return t, k[..., 0]

    t1, _ = refract(np.broadcast_to(d, n.shape), n, 1.0 / n_water)
    p_exit = n - 2.0 * np.sum(n * t1, -1, keepdims=True) * t1  # second intersection of the chord
    t2, k2 = refract(t1, -p_exit, n_water)
    out = np.zeros((size, size, 4), np.float32)
    ok = inside & (k2 >= 0.0)
    out[..., :3] = np.where(ok[..., None], t2, 0.0)
    out[..., 3] = inside
    return out


# --- sprites (the vertex stage) ------------------------------------------------------------------------------------------

def sprites(state: dict, pose: Pose, width: int, height: int, s: RainSettings, extent: float,
            streaks: str, positions: bool = False):
    """Billboards (k, 6) (``pywarp.kernels.particles.SPRITE_FIELDS``) of the particles in view, far first: each
    drop's centre projected with the view camera, its billboard radius r L/a * billboard_scale on screen
    (``streaks='off'``); streaks (rr-alg-3.2.3) reach up by the fall during the persistence time
    (``particles_streak``), their taps spaced by its tap offset ('thesis'), their width the drop's projected diameter
    times streak_scale ('physical': sub-pixel widths are the compositor's fractional coverage). With
    ``positions=True`` also the drops' centres (k, 3) in the same order (the light-drop model)."""
    pos = np.asarray(state["pos"], np.float32).reshape(-1, 3)
    if not len(pos):
        empty = np.zeros((0, 6), np.float32)
        return (empty, np.zeros((0, 3), np.float32)) if positions else empty
    r_s, u_s, f_s = pose.basis()
    xc = pos @ r_s.astype(np.float32)
    yc = pos @ u_s.astype(np.float32)
    depth = pos @ f_s.astype(np.float32)
    focal = np.float32(0.5 * height / math.tan(math.radians(pose.fov_y_deg) / 2.0))
    scale = s.streak_scale if streaks == "physical" else s.billboard_scale
    radius_w = (state["radius_mm"] * np.float32(extent * 1e-3 / s.metres_per_unit * scale)).astype(np.float32)
    keep = depth > s.near_clip
    xc, yc, depth, radius_w, speed = xc[keep], yc[keep], depth[keep], radius_w[keep], state["speed"][keep]
    centres = pos[keep]
    cx = np.float32(0.5 * width) + focal * xc / depth
    cy = np.float32(0.5 * height) - focal * yc / depth
    rad = focal * radius_w / depth
    half = rad.copy()
    tap = np.zeros_like(rad)
    if streaks != "off":
        length, tap = P.particles_streak_np(speed, s.persistence_ms * 1e-3, radius_w)
        lpx = focal * length / depth
        cy = cy - 0.5 * lpx  # the trace lies above the drop: its earlier positions
        half = rad + 0.5 * lpx
    out = np.stack([cx, cy, rad, half, tap, depth], 1).astype(np.float32)
    on = (cx + half > 0) & (cx - half < width) & (cy + half > 0) & (cy - half < height) & (rad > 0)
    order = np.argsort(-out[on][:, 5], kind="stable")
    out = out[on][order]
    return (out, np.ascontiguousarray(centres[on][order])) if positions else out


# --- the technique -------------------------------------------------------------------------------------------------------

#: frames a reconstructed background view is refined while the view keeps its direction (background_scale > 1):
#: 16 = the 4 x 4 phases of the viewer's reduction, after which every pixel of the view has been rendered once (each
#: costs a background frame at 1/16 of the pixels; the rain's turns come 10 times a second while a key is held)
BACKGROUND_REFINE_FRAMES = 16
#: a view of a new direction (background_scale > 1) samples this many times more sparsely than its refinements (a
#: 5 deg turn of the viewer's benchmark exposes 35 of 640 columns: the rest is the turned previous view). Measured on
#: the benchmark (640x360, 2 cores, idle, the terrain background at its ~2x cheaper still): 1 gives 26.1 frames/s
#: without a window and 13.2-14.8 under Xvfb, SSIM 0.94 / 0.92 (mean / p5); 2 gives 27.3 and 20.8 frames/s, SSIM
#: 0.88-0.89 / 0.83-0.85. 1: the quality target (SSIM 0.90 / 0.80) and the frame rate without a window, 1-2 frames/s
#: short of 15 under Xvfb (whose software OpenGL then took a core's 20-30 ms a frame; ~13 ms since the window
#: stopped drawing its full-window background: tools/window_cost.py)
NEW_DIRECTION_FACTOR = 1
#: a reconstructed view is refined at most every this many frames (background_scale > 1): the frames between show the
#: drops over the view as it is (the drops move every frame; a refinement costs a background frame at 1/16 of the
#: pixels, ~4 drop frames' CPU time). A new direction is always rendered. 3: measured on the benchmark's turn, 22
#: frames/s against 16 with 2 at the same SSIM (0.887 / 0.885)
BACKGROUND_REFINE_EVERY = 3


class RainTechnique(Technique):
    """Rain over a background scene: ``init`` (background, mask, particles), ``update`` (settings, time),
    ``render`` (one frame), ``resize``. The background view and capture are cached per pose and size (a still camera
    pays for them once)."""

    settings_class = RainSettings
    #: the viewer renders rain's previews at the window's size in either preview mode (the drops drawn whole every
    #: frame, at half size; the background reconstructed at full quality, ``background_scale``): measured on the
    #: benchmark's turn, SSIM against the full render 0.82 / 0.76 (the picture at 1/64 of the pixels enlarged, the
    #: terrain at its preview quality) -> 0.94 / 0.92 (NEW_DIRECTION_FACTOR)
    previews_at_full_size = True

    def __init__(self, settings: RainSettings | None = None):
        self._cache: dict = {}
        self._device_cache: dict = {}
        super().__init__(settings)

    def rebuild(self, stale: set, changed: set) -> None:
        """What each change invalidates comes from the specs (``RainSettings.INVALIDATES``): ``background`` the
        background scene, ``mask`` the drop mask, ``particles`` the particle system; a device switch all three.

        ``drops`` is handled here, so that the particles in view are those of a fresh technique with the new count
        (the G / H keys, fig 6.12): each particle's draws depend on its index and generation only, so a lower count
        keeps the first ``drops`` particles (:meth:`_advance` drops the rest at once), which ARE the fresh system's;
        a higher count respawns the system (warm, when ``warm_start``) and re-advances it to the current time -- the
        particles past the old count were never simulated (or stopped when the count was lowered)."""
        s = self.settings
        if stale & {"background", "device"}:
            self.background = make_background(s)
            self._cache.clear()
        if stale & {"mask", "device"}:
            self.mask, self.extent, self.normals = drop_mask(s.shape, s.mask, s.mask_size)
        if stale & {"particles", "device"} or ("drops" in changed and s.drops > self.system.count):
            self._reset_particles()

    def state(self) -> dict:
        """The particles (the system's arrays and count) and the simulated time."""
        sy = self.system
        return {"t": self.t, "count": sy.count,
                "arrays": {n: getattr(sy, n).numpy().copy() for n in ("pos", "radius", "speed", "generation")}}

    def restore(self, state: dict) -> None:
        """Continue from another rain technique's :meth:`state` (same particle settings)."""
        import warp as wp

        sy = self.system
        for n, a in state["arrays"].items():
            setattr(sy, n, wp.array(a, dtype=getattr(sy, n).dtype, device=self.device))
        sy.capacity = len(state["arrays"]["pos"])
        sy.count = state["count"]
        self.t = state["t"]

    def _reset_particles(self) -> None:
        s = self.settings
        self.system = P.ParticleSystem(max(s.drops, 1), device=self.device, variant=s.variant,
                                       **s.c_values())
        if s.warm_start:
            self.system.fill(s.drops)
        self.t = 0.0

    def _advance(self) -> None:
        s = self.settings
        target = s.time_s * s.clock_rate
        if target < self.t - 1e-9:
            self._reset_particles()
        steps = 0
        while self.t < target - 1e-9 and steps < 100000:
            dt = min(s.frame_dt, target - self.t)
            self.system.step(s.drops, dt)
            self.t += dt
            steps += 1
        if self.system.count > s.drops:  # a lowered count (G key) takes effect at once
            self.system.step(s.drops, 0.0)

    def images(self, pose: Pose) -> tuple[np.ndarray, np.ndarray]:
        """(view, capture) of the background for ``pose``: display-encoded RGB float32. Each is cached by what it
        depends on -- the direction and the field of view, not the position: a background is seen from its own
        place, turned with the view -- so a camera that moves without turning pays for neither. With
        ``background_scale`` > 1 a view not yet cached comes from the temporal reconstruction (full quality, 1/f^2
        of the pixels at f = 4 x :data:`NEW_DIRECTION_FACTOR`, the previous view turned with the camera) and is
        refined by another reconstructed frame (1/16 of the pixels) every
        :data:`BACKGROUND_REFINE_EVERY` calls while the direction stays, :data:`BACKGROUND_REFINE_FRAMES` times (then
        it is the full render); a full view cached for the same direction is used as it is."""
        s = self.settings
        look = (pose.yaw_deg, pose.pitch_deg)
        vkey = (look, pose.fov_y_deg, s.width, s.height)
        ckey = (look, s.capture_fov_deg, s.capture_size)
        view = self._cache.get(("view", vkey))  # (image, exact, reconstructed frames)
        self._idle_calls = getattr(self, "_idle_calls", 0) + 1  # calls since the view was last rendered
        refine = view is not None and not view[1] and (s.background_scale == 1 or (
            view[2] < BACKGROUND_REFINE_FRAMES and self._idle_calls >= BACKGROUND_REFINE_EVERY))
        if view is None or refine:
            self._idle_calls = 0
            scene_bg = isinstance(self.background, SceneBackground)
            if s.background_scale > 1 and scene_bg:  # a new direction, or the same one refined by another frame
                # a new direction at half the sampling again (NEW_DIRECTION_FACTOR): most of it is the turned history
                up = self._upsampler(s.width, s.height, s.background_scale * (NEW_DIRECTION_FACTOR if view is None
                                                                             else 1))
                img = self.background.render_reconstructed(pose, s.width, s.height, pose.fov_y_deg, up)
                view = (img, False, 1 if view is None else view[2] + 1)
            else:
                view = (self.background.render(pose, s.width, s.height, pose.fov_y_deg), True, 0)
                if scene_bg:  # the next reconstructed view starts from it
                    from ..viewer.session import technique_camera

                    cam = technique_camera(self.background.technique(pose, s.width, s.height, pose.fov_y_deg))
                    self._upsampler(s.width, s.height, 2).remember(
                        (np.clip(view[0], 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8), cam,
                        key=self.background.scene.name)
            self._cache = {k: v for k, v in self._cache.items() if k[0] != "view"}
            self._cache[("view", vkey)] = (np.ascontiguousarray(view[0], np.float32), view[1], view[2])
            view = self._cache[("view", vkey)]
        capture = self._cache.get(("capture", ckey))
        if capture is None:
            capture = np.ascontiguousarray(self.background.render(replace(pose, fov_y_deg=s.capture_fov_deg),
                                                                  s.capture_size, s.capture_size,
                                                                  s.capture_fov_deg), np.float32)
            self._cache = {k: v for k, v in self._cache.items() if k[0] != "capture"}
            self._cache[("capture", ckey)] = capture
        return view[0], capture

    def _upsampler(self, width: int, height: int, factor: int):
        """The background's temporal reconstruction (one per view size; ``factor`` the reduction asked now)."""
        from ..core.temporal import TemporalUpsampler

        up = getattr(self, "_up", None)
        if up is None or (up.width, up.height) != (width, height):
            up = self._up = TemporalUpsampler(self.launcher, width, height, factor)
        elif up.factor != factor:
            up.set_factor(factor)
        return up

    def particles_factor(self) -> int:
        """The reduction the drops are composited at: ``particles_scale`` where it divides both sides, else 1."""
        k = self.settings.particles_scale
        return k if self.settings.width % k == 0 and self.settings.height % k == 0 else 1

    def frame_inputs(self, pose: Pose | None = None, factor: int = 1) -> dict:
        """Everything the compositing pass takes for the current state (for tests and the C comparison); ``factor``
        > 1: at 1/factor of the width and height, the view averaged over factor x factor blocks."""
        s = self.settings
        pose = pose or Pose.from_settings(s)
        self._advance()
        view, capture = self.images(pose)
        self._view = view  # the full view of this frame (render adds the drops' change to it)
        if factor > 1:  # averaged once per view (the same array while the view is cached)
            small = getattr(self, "_small_view", None)
            if small is None or small[0] is not view or small[1] != factor:
                h, w = view.shape[:2]
                small = self._small_view = (view, factor, np.ascontiguousarray(
                    view.reshape(h // factor, factor, w // factor, factor, 3).mean((1, 3)), np.float32))
            view = small[2]
        lights = dict(s.light_values())
        lit = P.lights_on(P.check_lights(lights))
        streaks = s.streaks if s.mode == "streaks" else "off"
        out = sprites(self.system.state(), pose, s.width // factor, s.height // factor, s, self.extent, streaks,
                      positions=lit)
        sp = out[0] if lit else out
        ins = dict(background=view, capture=capture, mask=self.mask, sprites=sp,
                   fov_view=math.radians(pose.fov_y_deg), fov_capture=math.radians(s.capture_fov_deg),
                   streaks=streaks, filter=s.filter,
                   opacity={"off": s.opacity, "thesis": s.streak_opacity, "physical": 1.0}[streaks])
        if lit:  # the light-drop model (rr-A1..rr-CF): off unless a light has a colour or the ambient is not 1
            r, u, f = pose.basis()
            lights.update(right=tuple(r), up=tuple(u), forward=tuple(f))
            ins.update(lights=lights, positions=out[1], normals=self.normals)
        return ins

    def render(self, pose: Pose | None = None, progress=None, encode: bool = True) -> np.ndarray:
        """One frame: uint8 (height, width, 3) through the display transform of the ``exposure_ev`` and ``tonemap``
        settings (:func:`pywarp.core.display.encode_encoded`: the colours are display-encoded), or the float frame
        with ``encode=False``."""
        k = self.particles_factor()
        ins = self.frame_inputs(pose, k)
        out = P.composite(**ins, launcher=self.launcher, cache=self._device_cache)
        if k > 1:  # the drops' change to the reduced view, enlarged, over the full view
            out = self._view + enlarge2(out - ins["background"])
        if progress is not None:
            progress(1.0)
        if not encode:
            return out
        return display.encode_encoded(out, self.settings.exposure_ev, self.settings.tonemap)


def enlarge2(a: np.ndarray) -> np.ndarray:
    """(h, w, c) -> (2 h, 2 w, c) bilinearly (pixel centres aligned: output pixel 2 i + d, d in {0, 1}, samples the
    input at i - 1/4 + d/2; the edges clamped), float32."""
    a = np.asarray(a, np.float32)
    for axis in (0, 1):
        n = a.shape[axis]
        p = np.concatenate([a.take([0], axis), a, a.take([n - 1], axis)], axis)
        mid = p.take(range(1, n + 1), axis)
        even = 0.75 * mid + 0.25 * p.take(range(0, n), axis)
        odd = 0.75 * mid + 0.25 * p.take(range(2, n + 2), axis)
        a = np.stack([even, odd], axis + 1).reshape(a.shape[:axis] + (2 * n,) + a.shape[axis + 1:])
    return a.astype(np.float32)


def render_image(settings: RainSettings | None = None, pose: Pose | None = None) -> np.ndarray:
    """One uint8 image of rain."""
    return RainTechnique(settings).render(pose)


def still_path(frames: int, settings: RainSettings) -> list:
    """The camera of the settings for every frame (the rain falls; the cached background is rendered once)."""
    if frames < 1:
        raise ValueError(f"frames must be >= 1, got {frames}")
    return [Pose.from_settings(settings)] * frames
