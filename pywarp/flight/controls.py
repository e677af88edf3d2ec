"""The flight simulator's keys (oc §6.1.2: the arrows pitch and roll, W / S speed) as the viewer's controls
(:class:`pywarp.viewer.controls.Controls`; ``pywarp view flight``).

The aircraft is flown live by the flight model of :mod:`pywarp.kernels.flight` (``flight_step`` through
:func:`pywarp.flight.model.simulate`, the model of the settings: ``max_speed_mps``, ``point_rate_mps``,
``turn_rate``): the viewer's frame time advances the flight in fixed steps of :data:`pywarp.flight.script.DT` with
the keys held in that frame, so a script (fixed frame time) always flies the same path. The flight starts from the
scripted flight's state at the settings' ``time_s`` (the frame ``pywarp render flight`` shows) and goes back there
when ``time_s`` or the start fields change in the panel. The camera is the settings' ``view``: the chase camera
(behind, beside and above the aircraft: ``chase_distance_m``, ``chase_side_m``, ``chase_height_m``) or the
cockpit.

The aircraft state lives here, not in the settings: once it has flown, every step returns a
:class:`pywarp.flight.technique.FlightPose` that carries the aircraft (before, None: the settings' own camera, the
same aircraft). Preview frames (while the aircraft moves) take
``FlightSettings.preview()``'s ray step ``preview_step_voxels``; their resolution is the viewer's adaptive preview
scale (which replaces ``preview_scale``: it follows the measured frame time).
"""
from __future__ import annotations

import dataclasses
import math

from ..viewer.controls import Binding, Controls, Input, Step
from . import model as F
from . import script as S
from .technique import AircraftState, FlightPose

#: viewer key -> the flight model's key (cclouds/flight.h; oc §6.1.2's table)
KEYS = {"Up": "up", "Down": "down", "Left": "left", "Right": "right", "W": "w", "S": "s"}
#: the most simulation steps one viewer frame takes (a stalled frame does not fly minutes at once): 0.5 s
MAX_STEPS_PER_FRAME = 30


class FlightControls(Controls):
    """Arrows + W / S fly the aircraft (see the module docstring)."""

    bindings = (Binding("Up / Down", "nose down (descend) / nose up (climb): the nose point sinks / rises while held"),
                Binding("Left / Right", "bank left / right (turn): the wing points move while held"),
                Binding("W / S", "faster / slower (0 .. max_speed_mps)"))
    #: the benchmark banks left: a steady turn (the aircraft flies at its start speed)
    benchmark_keys = frozenset({"Left"})

    def __init__(self, settings):
        super().__init__(settings)
        self._start_key = None
        self.state: F.FlightState | None = None
        self.pitch = self.roll = 0.0
        self._acc = 0.0
        self.flown_s = 0.0
        self.flying = False  # flown since the session began (before that the settings' camera is the pose)

    @staticmethod
    def _key(settings):
        return (settings.time_s, settings.start_altitude_m, settings.start_speed_mps, settings.max_speed_mps,
                settings.point_rate_mps, settings.turn_rate, settings.flight_duration_s)

    def reset(self, settings) -> None:
        """The scripted flight's state at ``settings.time_s`` (as ``FlightTechnique.aircraft`` takes it)."""
        self._start_key = self._key(settings)
        self._acc = 0.0
        self.flown_s = 0.0
        model = settings.flight_model()
        if settings.time_s < S.DT:
            self.state = settings.start_state()
            self.pitch = self.roll = 0.0
            return
        tr = F.simulate(S.DEFAULT_SCRIPT, settings.flight_duration_s, dt=S.DT, start=settings.start_state(),
                        model=model)
        k = tr.at(settings.time_s)
        self.state = F.FlightState(tuple(float(x) for x in tr.position[k]), float(tr.heading[k]),
                                   float(tr.speed[k]), float(tr.nose_offset[k]), float(tr.wing_offset[k]))
        self.pitch, self.roll = float(tr.pitch[k]), float(tr.roll[k])

    def fly(self, settings, keys, steps: int) -> None:
        """``steps`` steps of :data:`pywarp.flight.script.DT` with ``keys`` (flight-model key names) held."""
        duration = steps * S.DT
        script = [(k, 0.0, duration + 1.0) for k in keys]
        tr = F.simulate(script, duration, dt=S.DT, start=self.state, model=settings.flight_model())
        self.state = F.FlightState(tuple(float(x) for x in tr.position[-1]), float(tr.heading[-1]),
                                   float(tr.speed[-1]), float(tr.nose_offset[-1]), float(tr.wing_offset[-1]))
        self.pitch, self.roll = float(tr.pitch[-1]), float(tr.roll[-1])
        self.flown_s += duration
        self.flying = True

    def aircraft(self) -> AircraftState:
        s = self.state
        return AircraftState(tuple(s.position), s.heading, self.pitch, self.roll, s.speed)

    def step(self, settings, inp: Input) -> Step:
        if self.state is None or self._key(settings) != self._start_key:
            self.reset(settings)
        keys = sorted(KEYS[k] for k in inp.held if k in KEYS)
        self._acc += max(0.0, float(inp.dt))
        steps = int(math.floor(self._acc / S.DT + 1e-9))
        self._acc -= steps * S.DT
        steps = min(steps, MAX_STEPS_PER_FRAME)
        before = self.state
        if steps and (keys or self.state.speed > 0.0):
            self.fly(settings, keys, steps)
        moving = self.state != before
        s = self.state
        msg = (f"speed {s.speed:.1f} m/s, altitude {s.position[1]:.0f} m, heading "
               f"{math.degrees(s.heading) % 360.0:.0f} deg, pitch {math.degrees(self.pitch):+.1f} deg, roll "
               f"{math.degrees(self.roll):+.1f} deg")
        # until the first flight step the aircraft is the scripted one at time_s: the settings' own camera (pose None,
        # so that the session's first frame is the one it asked for); then the flown aircraft, every step
        pose = FlightPose(settings.time_s, settings.view, self.aircraft()) if self.flying else None
        return Step(pose=pose, moving=moving, message=msg)

    def preview(self, settings) -> dict:
        p = settings.preview()
        return {f.name: getattr(p, f.name) for f in dataclasses.fields(p)
                if f.name not in ("width", "height") and getattr(p, f.name) != getattr(settings, f.name)}
