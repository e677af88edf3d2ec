"""The viewer's controls of the terrain scene: the pt demo's own (spec/pt.md, controls table) -- the mouse looks
around, **W** walks forward, **Esc** quits (the viewer's). The text does not give the mapping; ours:

* left-button drag: yaw and pitch (``FREE_FLY_MOUSE_DEG`` per pixel, as every scene's mouse look), the pitch kept in
  the settings' domain [-89, 89] deg (the pt camera is undefined looking straight up or down);
* W (held): the eye moves along the view direction at :data:`WALK_SPEED` units per second -- the demo's camera
  moves where it looks -- never closer than :data:`CLEARANCE` above the marched ground or the water.

While the camera moves the viewer renders ``quality='preview'`` frames (:data:`pywarp.terrain.settings.PREVIEW` at
1/``preview_scale`` resolution) and the full frame once it stops.
"""
from __future__ import annotations

from ..core.pose import forward
from ..viewer.controls import FREE_FLY_MOUSE_DEG, Binding, Controls, Input, Step

#: walking speed (units per second): a brisk walk over hills ~50 units apart (the walk path's 3 units per frame at
#: ~3 frames/s)
WALK_SPEED = 8.0
#: the eye stays at least this high above the ground (marched octaves) or the water (units): a hiker's eye height
#: is ~5 units in this scene; 1.5 keeps the near terrain out of the near plane when walking down a slope
CLEARANCE = 1.5


class TerrainControls(Controls):
    """Mouse look + W, as the pt demo (see the module docstring)."""

    bindings = (Binding("mouse (left-drag)", "look around (yaw, pitch)"),
                Binding("W", "walk forward along the view"),
                Binding("Esc", "quit"))
    benchmark_keys = frozenset({"W"})  # a steady walk: every frame a new camera

    def __init__(self, settings):
        super().__init__(settings)
        self._ground = None

    def ground(self, settings, x: float, z: float) -> float:
        """max(terrain height at (x, z) with the marched octaves, water level) (units)."""
        if self._ground is None:
            from .technique import ground_height

            self._ground = ground_height
        return max(float(self._ground(settings, x, z)), settings.water_level)

    def step(self, settings, inp: Input) -> Step:
        s = settings
        dt = max(0.0, float(inp.dt))
        changes = {}
        yaw, pitch = s.camera_yaw_deg, s.camera_pitch_deg
        if inp.mouse[0] or inp.mouse[1]:
            yaw = yaw + inp.mouse[0] * FREE_FLY_MOUSE_DEG
            pitch = min(max(pitch - inp.mouse[1] * FREE_FLY_MOUSE_DEG, -89.0), 89.0)
            if yaw != s.camera_yaw_deg:
                changes["camera_yaw_deg"] = yaw
            if pitch != s.camera_pitch_deg:
                changes["camera_pitch_deg"] = pitch
        if "W" in inp.held and dt > 0.0:
            f = forward(yaw, pitch)
            d = WALK_SPEED * dt
            x = s.camera_x + d * f[0]
            z = s.camera_z + d * f[2]
            h = s.camera_y + d * f[1]
            h = max(h, self.ground(s, x, z) + CLEARANCE)
            changes.update(camera_x=x, camera_y=h, camera_z=z)
        return Step(changes=changes, moving=bool(changes),
                    message=f"({s.camera_x:.0f}, {s.camera_y:.0f}, {s.camera_z:.0f})")

    def preview(self, settings) -> dict:
        """The PREVIEW reductions at the size the viewer asks for (its temporal reconstruction renders 1/4 or 1/16 of
        the window's pixels itself)."""
        return {"quality": "preview", "preview_scale": 1}
