"""The viewer's input: how keys, the mouse and time move a scene's camera or change its settings (``pywarp view
<scene>``, :mod:`pywarp.viewer`). Importing this module imports neither ImGui, Warp nor the C library: a scene
package's ``controls.py`` subclasses :class:`Controls` without them.

Every registered scene opens in the viewer with no extra declaration: the side panel is generated from the settings'
parameter specs, and a change goes through ``technique.update(**changes)`` (so only what it invalidates is
recomputed). How keys, the mouse and time move the camera or change settings is the scene's **controls**, declared
by two optional fields of :class:`pywarp.core.scenes.Scene`:

* ``controls``: a factory ``controls(settings) -> Controls``: the :class:`Controls` subclass of the scene package's
  ``controls.py``, named as ``"module:Class"`` (imported when the viewer opens the scene, :func:`make_controls`).
  None: :class:`FreeFlyControls`, the generic free-fly camera (below);
* ``command_defaults["view"]``: settings defaults of the viewer (default: ``width=640, height=360`` where the
  settings have those fields).

A :class:`Controls` object is made once per viewer session and then, once per window frame (about 60 per second,
on the UI thread; keep it cheap), ``step(settings, inp)`` is called with the current settings and an :class:`Input`:
``dt`` (seconds since the last frame; fixed in scripted runs, so that a script is deterministic), ``held`` (names of
the keys held now), ``pressed`` (keys pressed since the last frame, once per press), ``mouse`` (pointer motion in
pixels since the last frame while the left button drags over the image) and ``wheel``. It returns a :class:`Step`:

* ``changes``: settings fields to change (e.g. the camera position, ``mode="drops"``, ``drops=...``); they are
  validated by the settings (an invalid value is reported in the status line and dropped) and applied with
  ``technique.update``;
* ``pose``: the pose passed to ``technique.render(pose)``; None renders the camera of the settings (where the camera
  lives in the settings, as for ``clouds``). A scene whose camera is a state of its own (the flight model's chase
  camera) keeps that state in its Controls object and returns the pose every step;
* ``moving``: True while the view changes continuously (the viewer then renders at reduced resolution and refines
  to full quality once it stops; any settings change counts as moving too);
* ``message``: a short status text (e.g. ``"paused"``, ``"speed 0.5 km/s"``).

Further members: ``bindings`` (a tuple of :class:`Binding`: keys and what they do, shown in the help overlay, F1),
``benchmark_keys`` (keys held during ``pywarp view <scene> --benchmark SECONDS``, a steady motion whose frame rate
is measured) and ``preview(settings) -> dict`` (settings changes for the reduced-resolution frames while moving, e.g.
clouds' temporal reprojection). Key names: ``"A"`` .. ``"Z"``, ``"0"`` .. ``"9"``, ``"Up"``, ``"Down"``, ``"Left"``,
``"Right"``, ``"Space"``, ``"Shift"``, ``"Ctrl"``, ``"Alt"``, ``"Enter"``, ``"Tab"``, ``"Backspace"``,
``"PageUp"``, ``"PageDown"``, ``"Home"``, ``"End"``, ``"+"``, ``"-"``, ``"F2"`` .. ``"F11"``. The viewer keeps
``Escape`` (quit), ``F1`` (help overlay), ``F5`` (play/pause time) and ``F12`` (screenshot) for itself. A scene's
controls, e.g. the rain table::

    class RainControls(Controls):
        bindings = (Binding("F", "drops / streaks"), Binding("G / H", "fewer / more drops"), ...)

        def step(self, settings, inp):
            changes = {}
            if "F" in inp.pressed:
                changes["mode"] = MODES[(MODES.index(settings.mode) + 1) % len(MODES)]
            if "H" in inp.pressed:
                changes["drops"] = min(max(1, settings.drops * 2), MAX_DROPS)
            ...
            return Step(changes=changes, moving=bool(changes))

    register(Scene(name="rain", ..., controls="pywarp.rain.controls:RainControls"))

A scene may subclass :class:`FreeFlyControls` to keep the free flight and add keys (call ``super().step`` and merge).

**The free-fly default** finds the camera in the settings by field names (:func:`pywarp.core.pose.camera_fields`,
as :meth:`pywarp.core.pose.Pose.from_settings` does): ``camera_x*``, ``camera_y*`` or
``camera_altitude*``, ``camera_z*`` (position; unit from the spec: ``km``, ``m``), ``camera_yaw*`` (deg; 0 looks
along -z, positive towards +x) and ``camera_pitch*`` (deg, up positive). W/S fly forward/back along the view, A/D
strafe, E/Q (or Space/C) rise/sink, the arrows and a left-button drag look around, Shift flies 10x faster, +/- and
the wheel halve/double the speed. The yaw wraps to [-180, 180) deg; every value is clamped to its spec's domain (e.g.
the pitch to [-89, 89] deg, the altitude to >= 0). A scene without such fields still opens: the default then moves
nothing and the panel changes the image.

**Techniques in the viewer**: the viewer renders on its own thread, one frame at a time, through the technique's
``update`` / ``render``; ``render(pose, progress=...)``'s progress callback may raise to cancel a frame that a newer
one replaces (the technique must stay usable: the next ``render`` draws a whole frame again). A temporal technique
exposes its frame counter as ``frame``; the viewer renders its refined frames with ``frame = 0``, so that they equal
``pywarp render`` of the same settings (the screenshot test relies on it).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..core.params import specs
from ..core.pose import camera_fields, forward


@dataclass(frozen=True)
class Binding:
    """One line of the viewer's help overlay: the keys (as the user reads them, e.g. ``"W / S"``) and what they do."""

    keys: str
    help: str


@dataclass(frozen=True)
class Input:
    """The input of one viewer frame: ``dt`` seconds since the last one, key names ``held`` now and ``pressed`` since
    the last frame, ``mouse`` motion (dx, dy) in pixels while the left button drags over the image, ``wheel`` steps."""

    dt: float = 0.0
    held: frozenset = frozenset()
    pressed: frozenset = frozenset()
    mouse: tuple = (0.0, 0.0)
    wheel: float = 0.0


@dataclass(frozen=True)
class Step:
    """What one :meth:`Controls.step` did: settings ``changes``, the ``pose`` to render (None: the settings' camera),
    whether the view is ``moving`` and a status ``message``."""

    changes: dict = field(default_factory=dict)
    pose: Any = None
    moving: bool = False
    message: str = ""


class Controls:
    """Base of a scene's viewer controls (see the module docstring). Override :meth:`step`; set ``bindings`` (help
    overlay) and ``benchmark_keys`` (the benchmark's motion); override :meth:`preview` for cheaper preview frames."""

    bindings: tuple = ()
    benchmark_keys: frozenset = frozenset()

    def __init__(self, settings):
        self.settings_class = type(settings)

    def step(self, settings, inp: Input) -> Step:
        return Step()

    def preview(self, settings) -> dict:
        """Settings changes for the reduced-resolution frames rendered while the view moves (default: none)."""
        return {}


#: speed of the free-fly camera per unit of its position fields (units per second), 10x with Shift
FREE_FLY_SPEED = {"km": 0.5, "m": 20.0, "cm": 200.0, "mm": 2000.0}
#: look rates of the free-fly camera: arrows (deg/s) and mouse drag (deg per pixel)
FREE_FLY_TURN_DEG_S = 60.0
FREE_FLY_MOUSE_DEG = 0.2


class FreeFlyControls(Controls):
    """The generic free-fly camera on the settings' camera fields (see the module docstring): the vc demo's
    free-look camera (position plus yaw/pitch, moved along its own axes)."""

    bindings = (Binding("W / S", "fly forward / back along the view"),
                Binding("A / D", "strafe left / right"),
                Binding("E / Q (Space / C)", "rise / sink"),
                Binding("arrows, left-drag", "look around (yaw, pitch)"),
                Binding("Shift", "10x faster"),
                Binding("+ / - (wheel)", "double / halve the speed"))
    benchmark_keys = frozenset({"D", "Left"})  # strafe while turning: a circle at constant altitude

    def __init__(self, settings, fields: dict | None = None, speed: float | None = None):
        super().__init__(settings)
        self.fields = camera_fields(type(settings)) if fields is None else dict(fields)
        by_name = {p.name: p for p in specs(type(settings))}
        self._specs = {role: by_name[name] for role, name in self.fields.items()}
        unit = next((self._specs[r].unit for r in ("x", "y", "z") if r in self._specs), "")
        self.unit = unit
        self.speed = float(speed) if speed is not None else FREE_FLY_SPEED.get(unit, 1.0)

    def _get(self, settings, role, default=0.0):
        return float(getattr(settings, self.fields[role])) if role in self.fields else default

    def _clamp(self, role, v):
        p = self._specs[role]
        lo = -math.inf if p.lo is None else p.lo
        hi = math.inf if p.hi is None else p.hi
        return min(max(v, lo), hi)

    def step(self, settings, inp: Input) -> Step:
        held, dt = inp.held, max(0.0, float(inp.dt))
        for k in inp.pressed:
            if k == "+":
                self.speed *= 2.0
            elif k == "-":
                self.speed *= 0.5
        if inp.wheel:
            self.speed *= 2.0 ** float(inp.wheel)
        yaw, pitch = self._get(settings, "yaw"), self._get(settings, "pitch")
        dyaw = (("Right" in held) - ("Left" in held)) * FREE_FLY_TURN_DEG_S * dt + inp.mouse[0] * FREE_FLY_MOUSE_DEG
        dpitch = (("Up" in held) - ("Down" in held)) * FREE_FLY_TURN_DEG_S * dt - inp.mouse[1] * FREE_FLY_MOUSE_DEG
        fwd = ("W" in held) - ("S" in held)
        side = ("D" in held) - ("A" in held)
        up = (("E" in held) or ("Space" in held)) - (("Q" in held) or ("C" in held))
        new = {}
        if "yaw" in self.fields and dyaw:
            new["yaw"] = self._clamp("yaw", (yaw + dyaw + 180.0) % 360.0 - 180.0)  # a heading: wrapped
        if "pitch" in self.fields and dpitch:
            new["pitch"] = self._clamp("pitch", pitch + dpitch)
        if fwd or side or up:
            f = forward(yaw, pitch)
            y = math.radians(yaw)
            r = (math.cos(y), 0.0, math.sin(y))
            d = self.speed * (10.0 if "Shift" in held else 1.0) * dt
            move = [d * (fwd * f[i] + side * r[i]) for i in range(3)]
            move[1] += d * up
            for i, role in enumerate(("x", "y", "z")):
                if role in self.fields and move[i]:
                    new[role] = self._clamp(role, self._get(settings, role) + move[i])
        changes = {self.fields[role]: v for role, v in new.items() if v != self._get(settings, role)}
        return Step(changes=changes, moving=bool(changes),
                    message=f"speed {self.speed:g} {self.unit or 'units'}/s" if self.fields else "")


def make_controls(scene, settings) -> Controls:
    """The viewer's controls of ``scene`` for ``settings``: the scene's own (``Scene.controls``), or the free-fly
    default."""
    factory = scene.controls or FreeFlyControls
    c = factory(settings)
    if not isinstance(c, Controls):
        raise TypeError(f"controls of scene {scene.name!r} must be a Controls, got {type(c).__name__}")
    return c
