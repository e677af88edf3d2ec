"""The viewer's controls of the clouds scene (``pywarp view clouds``): the vc demo's free-look camera -- the generic
free flight of :class:`pywarp.viewer.controls.FreeFlyControls` on the settings' camera (position in km, yaw, pitch)
-- with the preview frames (while the camera moves) rendered with temporal reprojection (vc-A26): one pixel in 16
marched per frame, the others reprojected from the previous frame, as the thesis's renderer runs at interactive
speed (below the layer, and above its top: :meth:`pywarp.clouds.technique.CloudscapeTechnique.reprojects`), and a
cheaper march (:data:`PREVIEW_MARCH`); the refined frame once the camera stops is the full render.
"""
from __future__ import annotations

from ..viewer.controls import FreeFlyControls

#: the view samples of a preview's march: at most (samples_min, samples_max) = (32, 64) instead of the default
#: (64, 128) -- the refinement of long steps keeps the clouds' detail (the steps that find cloud are split anyway)
PREVIEW_SAMPLES = (32, 64)
#: ``advanced`` parameters of a preview's march (a user's own ``advanced`` values win): the light of a view sample
#: interpolated between its neighbours when their lights differ by at most 0.05 (light_interp, default 1/256), and
#: the march stopped once the transmittance is below 0.05 (exit_eps, default 1/64; the early exit's fill keeps the
#: pixel's brightness). Measured with PREVIEW_SAMPLES at 107 x 60, enlarged, against the full 640 x 360 render
#: (SSIM on luminance): from 6 km looking 25 deg down 0.9071 against 0.9073 in 0.7-0.8 of the frame time, inside the
#: layer (2.5 km) 0.9811 against 0.9812 in 0.5-0.6 of it
PREVIEW_MARCH = {"light_interp": 0.05, "exit_eps": 0.05}


class CloudscapeControls(FreeFlyControls):
    """Free flight (W/S/A/D, E/Q, arrows or left-drag, Shift, +/-); reprojected preview frames with a cheaper
    march."""

    def preview(self, settings) -> dict:
        lo = min(settings.samples_min, PREVIEW_SAMPLES[0])
        hi = max(lo, min(settings.samples_max, PREVIEW_SAMPLES[1]))
        return {"reprojection": True, "samples_min": lo, "samples_max": hi,
                "advanced": {**PREVIEW_MARCH, **settings.advanced}}
