"""The viewer's controls of the clouds scene (``pywarp view clouds``): the vc demo's free-look camera -- the generic
free flight of :class:`pywarp.viewer.controls.FreeFlyControls` on the settings' camera (position in km, yaw, pitch)
-- with the preview frames (while the camera moves) rendered with temporal reprojection (vc-A26): one pixel in 16
marched per frame, the others reprojected from the previous frame, as the thesis's renderer runs at interactive
speed; the refined frame once the camera stops is the full render.
"""
from __future__ import annotations

from ..viewer.controls import FreeFlyControls


class CloudscapeControls(FreeFlyControls):
    """Free flight (W/S/A/D, E/Q, arrows or left-drag, Shift, +/-); reprojected preview frames."""

    def preview(self, settings) -> dict:
        return {"reprojection": True}
