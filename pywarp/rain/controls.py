"""The rain application's keyboard (rr-tab-A, :data:`pywarp.rain.settings.CONTROLS`) as the viewer's controls
(:class:`pywarp.viewer.controls.Controls`; ``pywarp view rain``).

Keys (the table's): W / S step forward / back, Q / E move up / down, A / D turn left / right (5 deg), Y / C look up /
down (5 deg), P pauses / starts the simulation, F toggles drops / streaks, T selects the next drop shape of Table
2.1, G / H (and - / +) halve / double the number of drops, B / N make the drops 0.1 mm smaller / larger.

Choices the text leaves open (spec erratum 16: no step sizes; the application used the keyboard's auto-repeat):

* a key press is one step of the table; a key held repeats it at :data:`REPEAT_HZ` after :data:`REPEAT_DELAY_S`,
  as a keyboard's auto-repeat does;
* the rain box follows the eye (only the orientation matters to the drops), so W / S / Q / E move the camera of the
  background scene (its ``camera_x*`` / ``camera_y*`` or ``camera_altitude*`` / ``camera_z*`` fields in
  ``background_options``) by :func:`move_step` per step; the built-in panorama is a function of the view direction
  only, and they move nothing there (the status line says so);
* the simulation runs by itself in the viewer, as in the application: the controls advance ``time_s`` by the frame
  time (one rain second per second: ``time_s`` += dt / ``clock_rate``) unless it is paused (P) or the viewer's own
  time plays (F5, the benchmark), which advances ``time_s`` itself. P stops the controls' clock (the table names
  ``clock_rate`` = 0; setting it would rewind the particle system, whose time is ``time_s * clock_rate``);
* the preview frames (while the view moves) use a capture of :data:`PREVIEW_CAPTURE` px instead of 256 (the
  background is rendered twice per new pose: the view and the 150 deg capture; the capture costs per pixel too).
"""
from __future__ import annotations

import math

from ..core.params import specs
from ..core.pose import camera_fields
from ..viewer.controls import FREE_FLY_SPEED, Binding, Controls, Input, Step
from .settings import CONTROLS, MODES, PANORAMA, SHAPES

#: keyboard auto-repeat of a held key: first repeat after this long (s), then this many steps per second
REPEAT_DELAY_S = 0.25
REPEAT_HZ = 10.0
#: edge of the wide-angle capture in preview frames (px): the capture is seen only through the drops, a few pixels
#: each, and is rendered again at every new direction (a turn). 32: the default 640x360 frame with it against the
#: full one (capture 256), SSIM 0.997-0.998 on luminance, CIEDE2000 0.18-0.21 mean (64: 0.998, 16: 0.996), at a
#: quarter of 64's background pixels
PREVIEW_CAPTURE = 32
#: one W / S / Q / E step in seconds of the free-fly camera's speed (FREE_FLY_SPEED): 50 m over the clouds (km),
#: 2 m in a scene in metres
MOVE_STEP_S = 0.1
#: the most drops H gives (the spec's hi is 10^6; Table 6.2 measures up to 50 000)
MAX_DROPS = 1_000_000

_TABLE = {row["key"]: row for row in CONTROLS}


def move_step(unit: str) -> float:
    """One W / S / Q / E step in the background camera's position unit."""
    return FREE_FLY_SPEED.get(unit, 1.0) * MOVE_STEP_S


class RainControls(Controls):
    """rr-tab-A on the rain settings (see the module docstring)."""

    bindings = tuple(Binding(k, f"{_TABLE[a]['action']} / {_TABLE[b]['action']}") for k, a, b in (
        ("W / S", "W", "S"), ("Q / E", "Q", "E"), ("A / D", "A", "D"), ("Y / C", "Y", "C"),
        ("G / H", "G", "H"), ("B / N", "B", "N"))) + (Binding("- / +", "fewer / more drops (as G / H)"),) + tuple(
        Binding(k, _TABLE[k]["action"]) for k in ("P", "F", "T"))
    #: the benchmark turns right (A / D's 5 deg steps at the key repeat): a new background pose every step
    benchmark_keys = frozenset({"D"})
    STEP_KEYS = ("W", "S", "Q", "E", "A", "D", "Y", "C", "G", "H", "B", "N", "-", "+")

    def __init__(self, settings):
        super().__init__(settings)
        self.paused = False
        self._acc: dict = {}
        self._time_seen = None

    # --- helpers --------------------------------------------------------------------------------------------------
    def _count(self, key: str, inp: Input) -> int:
        """Steps of ``key`` this frame: 1 on a press, then the auto-repeat while held."""
        if key in inp.pressed:
            self._acc[key] = -REPEAT_DELAY_S
            return 1
        if key not in inp.held:
            self._acc.pop(key, None)
            return 0
        acc = self._acc.get(key, 0.0) + max(0.0, float(inp.dt))
        n = 0
        period = 1.0 / REPEAT_HZ
        while acc >= period:
            acc -= period
            n += 1
        self._acc[key] = acc
        return n

    @staticmethod
    def background_fields(settings) -> tuple[dict, dict]:
        """(fields by role, specs by role) of the background scene's camera position (empty for the panorama)."""
        if settings.background == PANORAMA:
            return {}, {}
        from ..core.scenes import scene

        cls = scene(settings.background).settings
        found = {r: n for r, n in camera_fields(cls).items() if r in ("x", "y", "z")}
        by_name = {p.name: p for p in specs(cls)}
        return found, {r: by_name[n] for r, n in found.items()}

    def _move(self, settings, fwd: int, up: int) -> tuple[dict, str]:
        """background_options with the background camera moved ``fwd`` steps along the level view and ``up``
        steps up (from where the background's camera is: the options, the rain scene's own for that scene, or the
        scene's default); the status text."""
        fields, sp = self.background_fields(settings)
        if not fields:
            return {}, "W/S/Q/E move a scene background's camera; the panorama has no position"
        from ..core.scenes import scene

        base = scene(settings.background).settings()
        opts = dict(settings.background_options)
        at = settings.background_values()
        unit = next(iter(sp.values())).unit
        d = move_step(unit)
        yaw = math.radians(settings.camera_yaw_deg)
        delta = {"x": d * fwd * math.sin(yaw), "y": d * up, "z": -d * fwd * math.cos(yaw)}
        for role, name in fields.items():
            if not delta[role]:
                continue
            v = float(at.get(name, getattr(base, name))) + delta[role]
            p = sp[role]
            v = min(max(v, -math.inf if p.lo is None else p.lo), math.inf if p.hi is None else p.hi)
            opts[name] = round(v, 9)
        if opts == dict(settings.background_options):
            return {}, ""
        return {"background_options": opts}, ""

    # --- the step -------------------------------------------------------------------------------------------------
    def step(self, settings, inp: Input) -> Step:
        changes: dict = {}
        note = ""
        n = {k: self._count(k, inp) for k in self.STEP_KEYS}
        for k in set(inp.pressed) - set(self.STEP_KEYS):
            self._acc.pop(k, None)
        # look: A / D turn (heading wraps to [-180, 180)), Y / C pitch within the spec's [-89, 89]
        dyaw = (n["D"] - n["A"]) * float(_TABLE["D"]["change"])
        if dyaw:
            changes["camera_yaw_deg"] = (settings.camera_yaw_deg + dyaw + 180.0) % 360.0 - 180.0
        dpitch = (n["Y"] - n["C"]) * float(_TABLE["Y"]["change"])
        if dpitch:
            p = min(max(settings.camera_pitch_deg + dpitch, -89.0), 89.0)
            if p != settings.camera_pitch_deg:
                changes["camera_pitch_deg"] = p
        # move: W / S along the level view, Q up / E down (the background's camera)
        fwd, up = n["W"] - n["S"], n["Q"] - n["E"]
        if fwd or up:
            moved, note = self._move(settings, fwd, up)
            changes.update(moved)
        # toggles on a press
        if "P" in inp.pressed:
            self.paused = not self.paused
        if "F" in inp.pressed:
            changes["mode"] = MODES[(MODES.index(settings.mode) + 1) % len(MODES)]
        if "T" in inp.pressed:
            changes["shape"] = SHAPES[(SHAPES.index(settings.shape) + 1) % len(SHAPES)]
        # G / H (- / +, the viewer's usual keys for more and less): count x 0.5 / x 2
        drops = settings.drops
        for _ in range(n["G"] + n["-"]):
            drops = drops // 2
        for _ in range(n["H"] + n["+"]):
            drops = min(max(1, drops * 2), MAX_DROPS)
        if drops != settings.drops:
            changes["drops"] = drops
        # B / N: size -+ 0.1 mm, kept where size +- spread/2 stays within [0.1, 4.5] mm (Tables 2.1, 2.2)
        ds = (n["N"] - n["B"]) * float(_TABLE["N"]["change"])
        if ds:
            half = 0.5 * settings.size_spread_mm
            lo, hi = math.ceil((0.1 + half) * 1e6) / 1e6, math.floor((4.5 - half) * 1e6) / 1e6
            size = min(max(round(settings.size_mm + ds, 6), lo), hi)
            if size != settings.size_mm:
                changes["size_mm"] = size
            else:
                note = f"drop size at its limit ({settings.size_mm:g} mm +- {half:g})"
        # the simulation clock
        t = settings.time_s
        external = self._time_seen is not None and t != self._time_seen  # F5 time, a script or the panel moved it
        if not self.paused and not external and settings.clock_rate > 0 and inp.dt > 0:
            changes["time_s"] = t + float(inp.dt) / settings.clock_rate
        self._time_seen = changes.get("time_s", t)
        look = {k: v for k, v in changes.items() if k != "time_s"}
        s = dict(mode=changes.get("mode", settings.mode), drops=changes.get("drops", settings.drops),
                 shape=changes.get("shape", settings.shape), size=changes.get("size_mm", settings.size_mm))
        msg = (f"{s['mode']}, {s['drops']} drops, shape {s['shape']} mm, size {s['size']:g} mm"
               f"{', paused' if self.paused else ''}{'; ' + note if note else ''}")
        return Step(changes=changes, moving=bool(look), message=msg)

    def preview(self, settings) -> dict:
        """A small capture, the background reconstructed from a sixteenth of its pixels per frame and the drops
        composited at half the width and height over it (the viewer renders rain previews at the window's size)."""
        return {"capture_size": min(settings.capture_size, PREVIEW_CAPTURE), "background_scale": 4,
                "particles_scale": 2}
