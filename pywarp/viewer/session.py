"""The viewer without its window: the render thread, the session state (settings, controls, camera, time), scripts,
screenshots, the frame counter and the benchmark. :mod:`pywarp.viewer.window` draws a session with Dear ImGui; a
session also runs headless (``pywarp view --no-window``, the tests).

Rendering runs on a thread of its own (:class:`RenderWorker`), one frame at a time, through the technique's
``update`` / ``render`` on the tile-parallel launcher; the UI thread only submits requests and picks up finished
frames, so the window stays responsive while a frame renders. While the view moves (keys held, a slider dragged, time
playing) the worker renders **previews**: the scene's settings at a reduced resolution (the scale adapts so that a
preview takes about :data:`PREVIEW_BUDGET_S`) with the controls' preview changes (clouds: their temporal reprojection
on, below the layer and above its top, and a cheaper march: :mod:`pywarp.clouds.controls`), enlarged by the window. Once nothing has changed for :data:`STILL_S` it renders the **refined** frame: the
settings as they are, full resolution, frame counter 0 -- the image ``pywarp render`` gives for the same settings. A
refined frame that a newer state makes stale is cancelled between bands.

``temporal=True`` (``pywarp view --previews temporal``) renders the previews at the window's resolution through the
temporal reconstruction of :mod:`pywarp.core.temporal` instead: 1/f^2 of the pixels per frame (f in 1, 2, 4 adapting
to the same budget), a sub-pixel phase each, the rest the previous picture reprojected and clamped (rain draws its
drops whole and reconstructs only its background). Without ``temporal`` (None) the technique's
:attr:`~pywarp.core.technique.Technique.preview_mode` decides: the terrain's is "temporal" (its exact depth keeps a
sharp history: tools/terrain_preview_eval.py), the other scenes' "scaled" -- measured with the viewer benchmark
(README, performance): on this 2-core CPU, at the frame rate the budget asks, their enlarged reduced frames are as
close to the full render (SSIM) and faster.
"""
from __future__ import annotations

import dataclasses
import json
import math
import os
import sys
import threading
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..core.display import luminance
from ..core.scenes import Scene
from .controls import Input, make_controls

#: a preview frame should take about this long (s): 1/30 s leaves room for the UI thread within the 20 frames/s target
PREVIEW_BUDGET_S = 1.0 / 30.0
#: the view counts as still (and is refined) after this long without a change (s)
STILL_S = 0.25
#: preview resolution divisors the worker chooses from (the full resolution divided by one of them)
PREVIEW_SCALES = (1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0)
#: the scale a session starts with (index into PREVIEW_SCALES): 640 x 360 -> 320 x 180
START_SCALE = 2
#: displayed frames the viewer benchmark compares with the full render of the same pose
QUALITY_SAMPLES = 8
#: the reduction factor the temporal previews start with (1/4 of the pixels rendered per frame)
START_FACTOR = 2
#: a temporal preview that takes more than this many budgets doubles the reduction factor at once (the frame at
#: twice the factor costs about a quarter: 2.5 budgets become ~0.6)
FACTOR_JUMP = 2.5
#: smallest preview width (px)
MIN_PREVIEW_WIDTH = 32
#: frame-rate targets (frames/s at 640 x 360 on two cores while moving), by scene: (without a window, with a window
#: under Xvfb, whose software OpenGL takes ~13 ms of CPU a UI frame: tools/window_cost.py); rain composites its drops
#: over its background
TARGET_FPS = {"clouds": (30.0, 24.0), "flight": (30.0, 24.0), "terrain": (30.0, 24.0), "rain": (20.0, 15.0)}
#: what is shown while moving against the full render of the same pose: (ssim_mean, ssim_p5) at least, every scene
TARGET_SSIM = (0.90, 0.80)
#: keys the viewer keeps for itself (the controls never see them)
VIEWER_KEYS = ("Escape", "F1", "F5", "F12")
#: the step of the session clock in scripted and benchmark runs (s): scripts are deterministic
SCRIPT_DT = 1.0 / 30.0


class Cancelled(Exception):
    """Raised from a render's progress callback to drop a frame that a newer request replaces."""


@dataclass(frozen=True)
class Frame:
    """A finished frame: uint8 (h, w, 3) ``image``, the state ``version`` it shows, ``full`` (refined) or a preview,
    its render time and a running ``index``."""

    image: np.ndarray
    version: int
    full: bool
    render_s: float
    index: int
    settings: Any = None
    fresh: tuple = (0, 0)      # (width, height) of what was rendered this frame (the rest reconstructed)
    source: Any = None         # the settings of the request (the window's size)
    pose: Any = None           # the pose of the request (None: the settings' own)
    state: Any = None          # the technique's simulation state after the frame (Technique.state)


@dataclass
class _Request:
    version: int
    settings: Any
    pose: Any
    full: bool

    @property
    def key(self):
        return (self.version, self.full)


def settings_diff(new, old) -> dict:
    """{field: new value} for the fields of two settings objects that differ."""
    return {f.name: getattr(new, f.name) for f in dataclasses.fields(new)
            if getattr(new, f.name) != getattr(old, f.name)}


def technique_camera(tech, pose=None):
    """The camera (:class:`pywarp.kernels.camera.Camera`, without the pose's jitter) that ``tech.render(pose)``
    looks through: the technique's own ``camera(pose)`` where it has one (flight's chase camera), else
    :func:`pywarp.kernels.camera.pose_camera` of its pose. The matrices depend on the aspect only, not the size."""
    own = getattr(tech, "camera", None)
    if own is not None:
        return own(pose)
    from ..kernels.camera import pose_camera

    p = dataclasses.replace(tech.pose(pose), jitter_px=(0.0, 0.0))
    return pose_camera(p, tech.settings.width, tech.settings.height)


class RenderWorker:
    """The render thread of a session (see the module docstring). ``submit`` a request, ``latest`` the newest frame.
    The technique is made on the thread, with the first request's settings (so the window opens at once)."""

    def __init__(self, scene: Scene, preview=None, budget_s: float = PREVIEW_BUDGET_S,
                 scale_index: int = START_SCALE, fixed_scale: bool = False, temporal: bool | None = None,
                 factor: int = START_FACTOR):
        self.scene = scene
        self._temporal_asked = None if temporal is None else bool(temporal)
        self.factor = int(factor)
        self._up = None  # the temporal reconstruction (pywarp.core.temporal, imported with the first preview)
        self.preview_changes = preview or (lambda s: {})
        self.budget_s = float(budget_s)
        self.scale_index = int(scale_index)
        self.fixed_scale = fixed_scale
        self.tech = None
        self.applied = None
        self.status = "starting"
        self.error = ""
        self.frames = 0
        self.cancelled = 0
        self._ema = None
        self._since_scale = 0
        self._req: _Request | None = None
        self._done_key = None
        self._latest: Frame | None = None
        self._cond = threading.Condition()
        self._stop = False
        self._thread = threading.Thread(target=self._run, name="pywarp-viewer-render", daemon=True)
        self._thread.start()

    # --- the UI side -------------------------------------------------------------------------------------------------
    def submit(self, version: int, settings, pose, full: bool) -> None:
        with self._cond:
            req = _Request(version, settings, pose, full)
            if self._req is None or self._req.key != req.key:
                self._req = req
                self._cond.notify_all()

    def latest(self) -> Frame | None:
        return self._latest

    def wait_frame(self, index: int, timeout: float) -> bool:
        """Wait (the GIL released) until a frame newer than ``index`` is out or ``timeout`` s pass; whether one is.
        The window paces itself by it: one UI frame per rendered frame while the worker is busy."""
        with self._cond:
            return self._cond.wait_for(lambda: self.frames != index or self._stop, timeout)

    def busy(self) -> bool:
        with self._cond:
            return self._req is not None and self._req.key != self._done_key

    def close(self, timeout: float = 30.0) -> None:
        with self._cond:
            self._stop = True
            self._cond.notify_all()
        self._thread.join(timeout)

    @property
    def temporal(self) -> bool:
        """Whether previews go through the temporal reconstruction: as asked (``pywarp view --previews``), else the
        technique's :attr:`~pywarp.core.technique.Technique.preview_mode` (False until the technique is made)."""
        if self._temporal_asked is not None:
            return self._temporal_asked
        return self.tech is not None and getattr(self.tech, "preview_mode", "scaled") == "temporal"

    @property
    def scale(self) -> float:
        return PREVIEW_SCALES[self.scale_index]

    # --- the thread --------------------------------------------------------------------------------------------------
    def _preview_settings(self, s):
        changes = dict(self.preview_changes(s))
        if hasattr(s, "width") and hasattr(s, "height"):
            sc = self.scale
            w = max(min(MIN_PREVIEW_WIDTH, s.width), int(round(s.width / sc)))
            h = max(1, int(round(w * s.height / s.width)))
            changes.update(width=w, height=h)
        return dataclasses.replace(s, **changes) if changes else s

    def _adapt(self, seconds: float) -> None:
        self._ema = seconds if self._ema is None else 0.6 * self._ema + 0.4 * seconds
        self._since_scale += 1
        if self.fixed_scale or self._since_scale < 3:
            return
        if self._ema > 1.25 * self.budget_s and self.scale_index < len(PREVIEW_SCALES) - 1:
            self.scale_index += 1
        elif (self._ema < 0.4 * self.budget_s and self.scale_index > 0):
            self.scale_index -= 1
        else:
            return
        self._since_scale, self._ema = 0, None

    def _run(self) -> None:
        while True:
            with self._cond:
                while not self._stop and (self._req is None or self._req.key == self._done_key):
                    self._cond.wait()
                if self._stop:
                    return
                req = self._req
            try:
                self._render(req)
            except Cancelled:
                self.cancelled += 1
            except Exception as exc:  # shown in the status line; the session goes on
                self.error = f"{type(exc).__name__}: {exc}"
                self.status = "error"
                if os.environ.get("PYWARP_DEBUG"):
                    traceback.print_exc()
                with self._cond:
                    self._done_key = req.key

    def _temporal(self, s) -> bool:
        """Whether previews of ``s`` go through the temporal reconstruction (the settings have a size)."""
        return self.temporal and hasattr(s, "width") and hasattr(s, "height")

    def _upsampler(self, s):
        from ..core import temporal as T

        up = self._up
        if up is None or (up.width, up.height) != (s.width, s.height) or up.launcher is not self.tech.launcher:
            up = self._up = T.TemporalUpsampler(self.tech.launcher, s.width, s.height, self.factor)
        if up.factor != T.factor_for(s.width, s.height, self.factor):
            up.set_factor(self.factor)
        return up

    def _depth(self) -> tuple:
        """The last frame's (depth, changing) where the technique gives them (:meth:`pywarp.core.temporal.
        TemporalUpsampler.resolve`'s arguments), else None each."""
        depth = getattr(self.tech, "depth", None)
        d = depth() if depth is not None else None
        changing = getattr(self.tech, "changing", None)
        return d, (changing(d) if changing is not None and d is not None else None)

    def _adapt_factor(self, seconds: float) -> None:
        """The reduction factor of the temporal previews: doubled when a preview takes over 1.25 budgets (at once when
        one takes over :data:`FACTOR_JUMP` budgets: the first preview of a motion at a factor far too small, e.g. the
        terrain's 1/4 of the pixels at ~4 budgets on two cores, is not repeated while the average catches up), halved
        when the frame it would give (about f^2/(f/2)^2 = 4 times the work) fits in 0.8 of one."""
        from ..core.temporal import VIEWER_FACTORS

        self._ema = seconds if self._ema is None else 0.6 * self._ema + 0.4 * seconds
        self._since_scale += 1
        if not self.fixed_scale and seconds > FACTOR_JUMP * self.budget_s and self.factor < VIEWER_FACTORS[-1]:
            self.factor *= 2
            self._since_scale, self._ema = 0, None
            return
        if self.fixed_scale or self._since_scale < 3:
            return
        if self._ema > 1.25 * self.budget_s and self.factor < VIEWER_FACTORS[-1]:
            self.factor *= 2
        elif self.factor > 1 and 4.0 * self._ema < 0.8 * self.budget_s:
            self.factor //= 2
        else:
            return
        self._since_scale, self._ema = 0, None

    @staticmethod
    def _key(s) -> dict:
        """What a picture depends on besides the camera and the size (the history's clamp is off while it stays)."""
        return {f.name: getattr(s, f.name) for f in dataclasses.fields(s) if f.name not in ("width", "height")}

    def _mark_preview(self, preview: bool) -> None:
        """Tell a technique with a ``preview`` attribute whether the next frame is a preview (the clouds reproject
        their previews above the layer too: :meth:`pywarp.clouds.technique.CloudscapeTechnique.reprojects`)."""
        if isinstance(getattr(self.tech, "preview", None), bool):
            self.tech.preview = preview

    def _render(self, req: _Request) -> None:
        own = self.tech is not None and self.tech.previews_at_full_size
        temporal = not req.full and self.tech is not None and self._temporal(req.settings) and not own
        if not req.full and own:
            target = dataclasses.replace(req.settings, **dict(self.preview_changes(req.settings)))
        elif temporal:
            up = self._upsampler(req.settings)
            lw, lh, jitter = up.plan()
            target = dataclasses.replace(req.settings, **dict(self.preview_changes(req.settings)), width=lw,
                                         height=lh)
        else:
            target = req.settings if req.full else self._preview_settings(req.settings)
        if self.tech is None:
            self.status = "initialising the technique (textures, kernels)"
            self.tech = self.scene.technique(target)
            self.applied = target
        else:
            changes = settings_diff(target, self.applied)
            if changes:
                stale = target.invalidated(self.applied) if hasattr(target, "invalidated") else set()
                if stale - {"size"}:
                    self.status = "recomputing " + ", ".join(sorted(stale - {"size"}))
                self.tech.update(**changes)
                self.applied = target
        self.status = "refining" if req.full else "preview"

        def progress(_fraction):
            if req.full and self._req is not None and self._req.key != req.key:
                raise Cancelled()

        self._mark_preview(not req.full)
        counted = req.full and isinstance(getattr(self.tech, "frame", None), int)
        saved = self.tech.frame if counted else None
        if counted:
            self.tech.frame = 0  # the refined frame is pywarp render's frame
        t0 = time.perf_counter()
        try:
            if temporal:
                pose = self.tech.pose(req.pose)
                fresh = np.asarray(self.tech.render(self.tech.jitter(pose, jitter), progress=progress), np.uint8)
                depth, changing = self._depth()  # the scene's per-pixel depth where it has one
                img = up.resolve(fresh, technique_camera(self.tech, pose), key=self._key(req.settings),
                                 depth=depth, changing=changing)
            else:
                img = self.tech.render(req.pose, progress=progress)
        finally:
            if counted:
                self.tech.frame = saved + 1
        dt = time.perf_counter() - t0
        img = np.ascontiguousarray(np.asarray(img, dtype=np.uint8))
        if temporal:
            self._adapt_factor(dt)
        elif not req.full:
            self._adapt(dt)
        elif self._temporal(req.settings) and img.shape[:2] == (req.settings.height, req.settings.width):
            # the refined frame is the next preview's history: the first frame of a new motion starts sharp
            self._upsampler(req.settings).remember(img, technique_camera(self.tech, req.pose),
                                                   key=self._key(req.settings), depth=self._depth()[0])
        self.frames += 1
        size = (img.shape[1], img.shape[0])
        fresh_size = (fresh.shape[1], fresh.shape[0]) if temporal else size
        self._latest = Frame(img, req.version, req.full, dt, self.frames, target, fresh_size, req.settings,
                             req.pose, self.tech.state())
        self.error = ""
        self.status = "refined" if req.full else "preview"
        with self._cond:
            self._done_key = req.key
            self._cond.notify_all()


# --- scripts ---------------------------------------------------------------------------------------------------------------

@dataclass
class Script:
    """Timed key presses and settings changes, read from JSON: a list of events, each with ``t`` (s, on the
    session clock) and one of

    * ``"key": NAME`` with optional ``"hold": SECONDS`` -- pressed at t and held for ``hold`` (0: one press);
    * ``"set": {field: value}`` -- panel changes (validated like the panel's);
    * ``"mouse": [dx, dy]`` -- a left-button drag over the image (pixels) in that frame;
    * ``"screenshot": PATH`` -- the refined frame of the state at t, written as PNG (with a JSON of the settings);
    * ``"quit": true`` -- the same as the Escape key.

    The session clock advances by :data:`SCRIPT_DT` per frame and stops while a screenshot waits for its refined
    frame, so the same script and seed give the same screenshots."""

    events: list

    @classmethod
    def load(cls, path) -> "Script":
        try:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
        except OSError as exc:
            raise ValueError(f"--script: cannot read {str(path)!r}: {exc.strerror}") from None
        except json.JSONDecodeError as exc:
            raise ValueError(f"--script: {str(path)!r} is not JSON: {exc}") from None
        return cls.parse(data)

    @classmethod
    def parse(cls, data) -> "Script":
        if not isinstance(data, list):
            raise ValueError("--script must hold a JSON list of events")
        events = []
        for i, e in enumerate(data):
            if not isinstance(e, dict) or not isinstance(e.get("t"), (int, float)) or not math.isfinite(e["t"]) \
                    or e["t"] < 0:
                raise ValueError(f"--script: event {i} needs a time 't' >= 0 (seconds), got {e!r}")
            kinds = [k for k in ("key", "set", "mouse", "screenshot", "quit") if k in e]
            if len(kinds) != 1:
                raise ValueError(f"--script: event {i} needs exactly one of key, set, mouse, screenshot, quit; "
                                 f"got {e!r}")
            if "hold" in e and (not isinstance(e["hold"], (int, float)) or e["hold"] < 0):
                raise ValueError(f"--script: event {i}: hold must be >= 0 seconds, got {e['hold']!r}")
            if "set" in e and not isinstance(e["set"], dict):
                raise ValueError(f"--script: event {i}: set must be an object of field: value")
            events.append(dict(e))
        events.sort(key=lambda e: e["t"])
        return cls(events)

    @property
    def end(self) -> float:
        return max((e["t"] + e.get("hold", 0.0) for e in self.events), default=0.0)

    def at(self, t0: float, t1: float):
        """Events of the frame covering session time [t0, t1): (pressed, held, mouse, sets, screenshots, quit)."""
        pressed, held, sets, shots = set(), set(), {}, []
        mouse = [0.0, 0.0]
        quit_ = False
        eps = 1e-9
        for e in self.events:
            t = e["t"]
            starts = t0 - eps <= t < t1 - eps
            if "key" in e:
                hold = float(e.get("hold", 0.0))
                if starts:
                    pressed.add(e["key"])
                if starts or (t - eps <= t0 < t + hold - eps):
                    held.add(e["key"])
            elif starts:
                if "set" in e:
                    sets.update(e["set"])
                elif "mouse" in e:
                    mouse[0] += float(e["mouse"][0])
                    mouse[1] += float(e["mouse"][1])
                elif "screenshot" in e:
                    shots.append(e["screenshot"])
                elif e.get("quit"):
                    quit_ = True
        return frozenset(pressed), frozenset(held), tuple(mouse), sets, shots, quit_


# --- the session -------------------------------------------------------------------------------------------------------------

@dataclass
class _Shot:
    path: Path
    version: int
    done: bool = False


@dataclass
class Stats:
    """The frame counter: frames shown (new frames picked up by the UI), their times, and the UI's own frames."""

    shown: list = field(default_factory=list)  # (wall time, render_s, full, width, height, fresh width, fresh height)
    ui_frames: int = 0

    def fps(self, now: float, window: float = 1.0) -> float:
        n = sum(1 for t, *_ in self.shown if t > now - window)
        return n / window


class Session:
    """A viewer session on ``scene`` with ``settings`` (see the module docstring). The UI calls :meth:`tick` once per
    window frame with the input, then :meth:`poll` for a new frame to show."""

    def __init__(self, scene: Scene, settings, *, script: Script | None = None, exclude=(),
                 budget_s: float = PREVIEW_BUDGET_S, still_s: float = STILL_S, screenshot_dir=".",
                 scale_index: int = START_SCALE, fixed_scale: bool = False, time_scale: float = 20.0,
                 temporal: bool | None = None):
        self.scene = scene
        self.settings = settings
        self.controls = make_controls(scene, settings)
        self.exclude = tuple(exclude)
        self.script = script
        self.still_s = float(still_s)
        self.screenshot_dir = Path(screenshot_dir)
        self.time_playing = False
        self.time_scale = float(time_scale)
        self.version = 0
        self.pose = None
        self.clock = 0.0
        self.last_change = -math.inf
        self.message = ""
        self.error = ""
        self.show_help = False
        self.quit = False
        self.shots: list[_Shot] = []
        self.shots_written: list[Path] = []
        self.stats = Stats()
        self._shown_index = 0
        self._frame: Frame | None = None
        self.worker = RenderWorker(scene, self.controls.preview, budget_s, scale_index, fixed_scale, temporal)
        self._submit(full=True)

    # --- state changes -----------------------------------------------------------------------------------------------
    def apply(self, changes: dict) -> bool:
        """Change settings (validated by the settings class); an invalid change is dropped and reported in
        ``error``. Returns whether anything changed."""
        if not changes:
            return False
        try:
            new = dataclasses.replace(self.settings, **changes)
        except (TypeError, ValueError) as exc:
            self.error = str(exc)
            return False
        if not settings_diff(new, self.settings):
            return False
        self.settings = new
        self.error = ""
        self.version += 1
        self.last_change = self.clock
        return True

    def screenshot(self, path=None) -> Path:
        """Save the refined frame of the current state as PNG (when it is ready; :meth:`poll` writes it)."""
        if path is None:
            n = len(self.shots) + 1
            path = self.screenshot_dir / f"pywarp-{self.scene.name}-{n:03d}.png"
        shot = _Shot(Path(path), self.version)
        self.shots.append(shot)
        return shot.path

    @property
    def waiting(self) -> bool:
        """A screenshot waits for its refined frame."""
        return any(not s.done for s in self.shots)

    def _viewer_keys(self, pressed) -> None:
        if "Escape" in pressed:
            self.quit = True
        if "F1" in pressed:
            self.show_help = not self.show_help
        if "F5" in pressed and self.scene.time_field:
            self.time_playing = not self.time_playing
        if "F12" in pressed:
            self.screenshot()

    def tick(self, inp: Input) -> None:
        """One window frame: script events, the viewer's keys, the controls, time; then the render request."""
        self.stats.ui_frames += 1
        sets, shots = {}, []
        if self.script is not None:
            if self.waiting:  # the script's clock stops until the screenshot is written
                self._write_ready_shots()
                if self.waiting:
                    self._submit(full=True)
                    return
            dt = SCRIPT_DT
            pressed, held, mouse, sets, shots, quit_ = self.script.at(self.clock, self.clock + dt)
            inp = Input(dt=dt, held=held | inp.held, pressed=pressed | inp.pressed,
                        mouse=(mouse[0] + inp.mouse[0], mouse[1] + inp.mouse[1]), wheel=inp.wheel)
            if quit_:
                self.quit = True
        self._viewer_keys(inp.pressed)
        if sets:
            self.apply(sets)
        ctl = Input(dt=inp.dt, held=frozenset(k for k in inp.held if k not in VIEWER_KEYS),
                    pressed=frozenset(k for k in inp.pressed if k not in VIEWER_KEYS), mouse=inp.mouse,
                    wheel=inp.wheel)
        step = self.controls.step(self.settings, ctl)
        self.message = step.message
        if step.changes:
            self.apply(step.changes)
        if step.pose is not None and step.pose != self.pose:
            self.pose = step.pose
            self.version += 1
            self.last_change = self.clock
        if self.time_playing and self.scene.time_field:
            tf = self.scene.time_field
            self.apply({tf: getattr(self.settings, tf) + inp.dt * self.time_scale})
        for path in shots:
            self.screenshot(path)
        self.clock += inp.dt
        moving = step.moving or (self.clock - self.last_change) < self.still_s
        self._submit(full=not moving or self.waiting)

    def _write_ready_shots(self) -> None:
        """Write the screenshots whose refined frame is already there (it may have arrived, and been shown, before
        the screenshot was asked for: then no new frame comes and :meth:`poll` would wait for ever)."""
        f = self.worker.latest()
        if f is not None and f.full:
            for s in self.shots:
                if not s.done and s.version == f.version:
                    self._write(s, f)

    def _submit(self, full: bool) -> None:
        latest = self.worker.latest()
        if latest is not None and latest.full and latest.version == self.version:
            full = True  # refined already: no preview of the same state
        self.worker.submit(self.version, self.settings, self.pose, full)

    def poll(self, now: float | None = None) -> Frame | None:
        """The newest frame if it is new since the last poll (counted by the frame counter), else None. Writes the
        screenshots whose refined frame has arrived."""
        f = self.worker.latest()
        if f is None or f.index == self._shown_index:
            return None
        self._shown_index = f.index
        self._frame = f
        now = time.perf_counter() if now is None else now
        self.stats.shown.append((now, f.render_s, f.full, f.image.shape[1], f.image.shape[0], *f.fresh))
        if f.full:
            for s in self.shots:
                if not s.done and s.version == f.version:
                    self._write(s, f)
        return f

    @property
    def frame(self) -> Frame | None:
        return self._frame

    def wait_frame(self, timeout: float) -> None:
        """Wait up to ``timeout`` s for a frame newer than the one shown, if the worker is rendering one."""
        if self.worker.busy():
            self.worker.wait_frame(self._shown_index, timeout)

    def _write(self, shot: _Shot, f: Frame) -> None:
        from ..core.output import write_png

        shot.path.parent.mkdir(parents=True, exist_ok=True)
        write_png(shot.path, f.image)
        state = {"scene": self.scene.name, "clock_s": round(self.clock, 6),
                 "settings": {k: v for k, v in dataclasses.asdict(f.settings).items()},
                 "pose": None if self.pose is None else repr(self.pose)}
        shot.path.with_suffix(".json").write_text(json.dumps(state, indent=1, default=repr) + "\n",
                                                 encoding="utf-8")
        shot.done = True
        self.shots_written.append(shot.path)
        self.message = f"saved {shot.path}"
        print(f"pywarp view: saved {shot.path}", file=sys.stderr, flush=True)

    def finished_script(self) -> bool:
        return self.script is not None and self.clock >= self.script.end and not self.waiting \
            and not self.worker.busy()

    def close(self) -> None:
        self.worker.close()

    def state(self) -> dict:
        """The session's state (the settings and the frame counter) as JSON-serialisable values."""
        return {"scene": self.scene.name, "clock_s": round(self.clock, 6), "version": self.version,
                "settings": json.loads(json.dumps(dataclasses.asdict(self.settings), default=repr)),
                "frames_shown": len(self.stats.shown), "ui_frames": self.stats.ui_frames,
                "screenshots": [str(p) for p in self.shots_written], "error": self.error or self.worker.error}


# --- headless run and the benchmark -----------------------------------------------------------------------------------

def run_headless(session: Session, *, seconds: float | None = None, ui_hz: float = 60.0,
                 timeout: float = 600.0) -> None:
    """Drive a session without a window at ``ui_hz`` frames per second: until its script ends (and its screenshots
    are written), ``seconds`` of wall time pass, or Escape/quit."""
    t_start = time.perf_counter()
    last = t_start
    period = 1.0 / ui_hz
    while not session.quit:
        now = time.perf_counter()
        if now - t_start > timeout:
            raise TimeoutError(f"the viewer session did not finish within {timeout:g} s")
        session.tick(Input(dt=now - last))
        last = now
        session.poll()
        if session.worker.error and session.script is not None:
            raise RuntimeError(session.worker.error)
        if session.script is not None and session.finished_script():
            break
        if seconds is not None and now - t_start >= seconds:
            break
        time.sleep(max(0.0, period - (time.perf_counter() - now)))


class Benchmark:
    """The viewer's benchmark mode (``pywarp view SCENE --benchmark SECONDS``): the controls' ``benchmark_keys`` are
    held (a steady camera motion), time plays where the scene has a time field (clouds: the wind), and the frame
    counter counts the frames shown during ``seconds`` after a warm-up (the technique made, the kernels compiled, the
    preview scale settled). Driven by the window or headless."""

    def __init__(self, session: Session, seconds: float, warmup_s: float = 3.0, dump=None,
                 samples: int = QUALITY_SAMPLES):
        self.session = session
        if session.scene.time_field:
            session.time_playing = True
        self.seconds = float(seconds)
        self.warmup_s = float(warmup_s)
        self.dump = None if dump is None else Path(dump)
        self.n_samples = int(samples)
        self.samples: list[dict] = []
        self.t_start = None
        self.t_measure = None
        self.done = False
        self.n0 = 0

    def input(self, dt: float) -> Input:
        return Input(dt=dt, held=frozenset(self.session.controls.benchmark_keys))

    def update(self, now: float) -> None:
        """Call once per UI frame after ``poll``."""
        s = self.session
        if self.t_start is None:
            if s.frame is not None:  # the first frame: the technique exists
                self.t_start = now
            return
        if self.t_measure is None and now - self.t_start >= self.warmup_s:
            self.t_measure = now
            self.n0 = len(s.stats.shown)
            self.ui0 = s.stats.ui_frames
            self.v0 = s.version
        if self.t_measure is not None and self.n_samples and len(self.samples) < self.n_samples:
            # the displayed frame at evenly spaced moments of the measurement (a frame shown while moving)
            due = self.t_measure + (len(self.samples) + 0.5) * self.seconds / self.n_samples
            f = s.frame
            if now >= due and f is not None and not f.full and f.source is not None:
                self.samples.append({"frame": f, "clock_s": s.clock})
        if self.t_measure is not None and now - self.t_measure >= self.seconds:
            self.done = True
            self.t_end = now

    def result(self, window: bool) -> dict:
        s = self.session
        shown = s.stats.shown[self.n0:]
        shown = [x for x in shown if x[0] <= self.t_end]
        elapsed = self.t_end - self.t_measure
        render = np.array([x[1] for x in shown]) if shown else np.array([math.nan])
        sizes = {}
        for x in shown:
            sizes[f"{x[3]}x{x[4]}"] = sizes.get(f"{x[3]}x{x[4]}", 0) + 1
        fps = len(shown) / elapsed if elapsed > 0 else 0.0
        target = TARGET_FPS.get(s.scene.name)
        target = None if target is None else target[1 if window else 0]
        st = s.settings
        window_px = max(1, (getattr(st, "width", 1) or 1) * (getattr(st, "height", 1) or 1))
        fresh = [x[5] * x[6] / window_px for x in shown if not x[2]]
        internal = {}
        for x in shown:
            if not x[2]:
                internal[f"{x[5]}x{x[6]}"] = internal.get(f"{x[5]}x{x[6]}", 0) + 1
        s.worker.close()  # no frame renders while the samples are compared with the full render
        quality = compare_samples(s.scene, self.samples, self.dump)
        return {
            "benchmark": "view", "scene": s.scene.name, "window": window,
            "width": getattr(st, "width", None), "height": getattr(st, "height", None),
            "seconds": round(elapsed, 3), "frames": len(shown), "fps": round(fps, 2),
            "frame_ms_mean": round(float(np.mean(render)) * 1e3, 2),
            "frame_ms_p95": round(float(np.percentile(render, 95)) * 1e3, 2),
            "ui_fps": round((s.stats.ui_frames - self.ui0) / elapsed, 1) if elapsed > 0 else 0.0,
            "preview_sizes": sizes, "preview_scale": s.worker.scale,
            "keys": sorted(s.controls.benchmark_keys), "time_playing": s.time_playing,
            "moved": s.version != self.v0, "cores": os.cpu_count(),
            "target_fps": target, "meets_target": None if target is None else fps >= target,
            "internal_sizes": internal, "fresh_fraction": round(float(np.mean(fresh)), 4) if fresh else None,
            "temporal": s.worker.temporal, **quality,
            "target_ssim": list(TARGET_SSIM),
            "meets_quality": (quality["ssim_mean"] >= TARGET_SSIM[0] and quality["ssim_p5"] >= TARGET_SSIM[1])
            if quality.get("ssim_mean") is not None else None,
        }


def displayed(img: np.ndarray, width: int, height: int) -> np.ndarray:
    """The picture as the window shows it at width x height: enlarged bilinearly (the texture's filter) where it is
    smaller."""
    if img.shape[:2] == (height, width):
        return img
    from PIL import Image

    return np.asarray(Image.fromarray(img).resize((width, height), Image.BILINEAR))


def render_args(scene: str, settings) -> list[str]:
    """``pywarp render`` arguments that give ``settings`` (the options of the fields that differ from the
    defaults)."""
    from ..core.params import specs

    args = ["pywarp", "render", scene]
    for p in specs(type(settings)):
        v = getattr(settings, p.name)
        if p.option is None or v == p.default or v is None:
            continue
        if p.kind == "bool":
            args.append(p.option if v else "--no-" + p.option[2:])
        else:
            args += [p.option, repr(v) if isinstance(v, float) else str(v)]
    return args


def compare_samples(scene: Scene, samples: list[dict], dump=None) -> dict:
    """The quality of the frames shown while moving: each sampled frame against the full render of the same
    settings and pose (a new technique: what ``pywarp render`` gives), SSIM on luminance (scikit-image, 7 x 7
    Gaussian-free window) and the mean CIEDE2000 (on sRGB -> CIELAB). ``ssim_p5`` is the 5th percentile of the
    per-frame SSIMs. ``dump``: a folder for each sample's shown frame, the full render and a JSON of its settings,
    pose and the ``pywarp render`` command."""
    keys = {"quality_samples": len(samples), "ssim_mean": None, "ssim_p5": None, "ciede2000_mean": None}
    if not samples:
        return keys
    from skimage.color import deltaE_ciede2000, rgb2lab
    from skimage.metrics import structural_similarity

    if dump is not None:
        Path(dump).mkdir(parents=True, exist_ok=True)
    ssims, des = [], []
    for k, smp in enumerate(samples):
        f = smp["frame"]
        st = f.source
        # a technique of its own, as pywarp render makes, with the shown frame's simulation state (rain's particles:
        # the same drops, rendered with the full settings)
        tech = scene.technique(st)
        if f.state is not None:
            tech.restore(f.state)
        full = np.asarray(tech.render(f.pose), np.uint8)
        shown = displayed(f.image, full.shape[1], full.shape[0])
        ssims.append(float(structural_similarity(luminance(shown), luminance(full), data_range=255.0)))
        des.append(float(np.mean(deltaE_ciede2000(rgb2lab(shown / 255.0), rgb2lab(full / 255.0)))))
        if dump is not None:
            from ..core.output import write_png

            stem = Path(dump) / f"{scene.name}-{k:02d}"
            write_png(stem.with_name(stem.name + "-shown.png"), shown)
            write_png(stem.with_name(stem.name + "-full.png"), full)
            pose = None if f.pose is None else {k2: v for k2, v in dataclasses.asdict(f.pose).items()}
            info = {"scene": scene.name, "clock_s": round(smp["clock_s"], 6), "ssim": ssims[-1],
                    "ciede2000_mean": des[-1], "fresh": list(f.fresh), "pose": pose,
                    "settings": dataclasses.asdict(st), "render": render_args(scene.name, st)}
            stem.with_suffix(".json").write_text(json.dumps(info, indent=1, default=repr) + "\n", encoding="utf-8")
    keys.update(ssim_mean=round(float(np.mean(ssims)), 4), ssim_p5=round(float(np.percentile(ssims, 5)), 4),
                ciede2000_mean=round(float(np.mean(des)), 3))
    return keys


def report(result: dict) -> str:
    tgt = result["target_fps"]
    verdict = "" if tgt is None else f" (target >= {tgt:g}: {'met' if result['meets_target'] else 'NOT met'})"
    if result.get("meets_quality") is not None:
        verdict += (f", SSIM {result['ssim_mean']:.3f} mean / {result['ssim_p5']:.3f} p5 (target >= "
                    f"{result['target_ssim'][0]:g} / {result['target_ssim'][1]:g}: "
                    f"{'met' if result['meets_quality'] else 'NOT met'})")
    return (f"pywarp view {result['scene']} --benchmark: {result['fps']:.1f} frames/s{verdict} over "
            f"{result['seconds']:.1f} s while moving ({'+'.join(result['keys']) or 'no keys'}"
            f"{', time playing' if result['time_playing'] else ''}), "
            f"{result['width']}x{result['height']} window, previews {result['preview_sizes']}, "
            f"render {result['frame_ms_mean']:.1f} ms mean / {result['frame_ms_p95']:.1f} ms p95, "
            f"UI {result['ui_fps']:.0f} frames/s, {result['cores']} cores"
            f"{'' if result['moved'] else ' -- NOTHING MOVED: the controls ignored the benchmark keys'}"
            f"{'' if result['window'] else ', no window'}")


def run_benchmark_headless(session: Session, seconds: float, warmup_s: float = 3.0, ui_hz: float = 60.0,
                           dump=None) -> dict:
    b = Benchmark(session, seconds, warmup_s, dump=dump)
    period = 1.0 / ui_hz
    last = time.perf_counter()
    while not b.done:
        now = time.perf_counter()
        session.tick(b.input(now - last))
        last = now
        session.poll(now)
        b.update(now)
        if session.worker.error:
            raise RuntimeError(session.worker.error)
        time.sleep(max(0.0, period - (time.perf_counter() - now)))
    return b.result(window=False)
