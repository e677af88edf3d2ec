"""Figure vc-fig-5.1: result of the visualization technique -- the final clouds over the Preetham sky (reproducible in
kind).

One frame of the complete technique (vc-A30, classes vc-A31, vc-A32, vc-A33): Preetham sky (vc-A29: vc-2.36,
vc-2.38, vc-2.39, vc-2.40, vc-2.41, vc-2.42, vc-2.43, vc-2.44, vc-4.2, vc-4.3, vc-4.4, vc-4.5), cloud layer raymarch
(vc-A14, vc-A18) with the density of vc-A17 (vc-4.7, vc-2.28, vc-2.29, vc-2.30), cone light samples (vc-A19),
lighting vc-2.31 with the ambient term (vc-A20), front-to-back accumulation with early exit (vc-A21), the tilt jitter
(vc-A23) and the composite vc-4.8. Renderer: pywarp.clouds.cloudscape (render_image).

The thesis states no parameters; these were chosen by eye among a few dozen trial renders of the public settings
(sun elevation / azimuth, coverage, cloud type, camera pitch / yaw, seed): a morning sun 20° above the horizon at
azimuth 35° (in view, to the right, so that the forward-scattering lobe of vc-2.31 lights the cloud edges around it;
at 10° the Preetham zenith is a dim 3 kcd/m² and the sky a grey-blue),
coverage 0.5, cloud type 0.9 (mostly cumulus), camera 0.3 km above the ground looking 23° up (the horizon just above
the bottom edge) with a 50° vertical field of view, seed 0; everything else is the renderer's default (layer
1.5-4 km, turbidity 2.5, g = 0.2, 64-128 view samples, the display transform of pywarp.core.display: -0.5 EV and
the ACES curve, so the sunlit tops, up to 1.9 in display-linear units, keep their shading instead of clipping to
white). 640x360 (about 2 s on two cores). Known limits that show:
the thin noisy band at the horizon (distant clouds thinner than a pixel, no level of detail) and the soft look of the
cloud bases overhead. Output: figures/vc/fig-5.1.png.
"""
# %% [markdown]
# This is the whole technique in one call. `render_image(settings)` builds a `CloudscapeTechnique` — generate (or load
# from the cache) the four noise textures, set up the sky model — and renders one frame without reprojection. Every
# parameter is a field of `CloudscapeSettings` with a documented default; the values below are the ones that differ
# from the defaults.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.technique import render_image  # noqa: E402

SCENE = dict(sun_elevation_deg=20.0, sun_azimuth_deg=35.0, coverage=0.5, cloud_type=0.9, camera_altitude_km=0.3,
             camera_pitch_deg=23.0, camera_yaw_deg=0.0, fov_y_deg=50.0, seed=0)
FULL = dict(width=640, height=360)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)

    # %%
    settings = CloudscapeSettings(**(QUICK if quick else FULL), **SCENE)
    image = render_image(settings)

    # %% [markdown]
    # What to look for: the cloud edges around the sun are brighter than the sunlit sides away from it (silver lining:
    # the Henyey–Greenstein lobe, g = 0.2); thick cores are darker than thin edges seen against the sun (Beer's law on
    # the optical depth towards the sun); the bases overhead are lit only by the ambient term and stay blue-grey.

    # %%
    h, w = image.shape[:2]
    width = max(w / 100 + 0.2, 6.6)  # at least 6.6 in: the quick mode's small render keeps a readable title
    height = (width - 0.2) * h / w + 0.9
    fig = plt.figure(figsize=(width, height), dpi=100)
    ax = fig.add_axes([0.1 / width, 0.1 / height, (width - 0.2) / width, (height - 0.9) / height])
    ax.imshow(image, interpolation="nearest")
    ax.set_axis_off()
    fig.suptitle("Fig 5.1 — result of the technique: clouds over the Preetham sky\n(sun 20° up, azimuth 35°; coverage "
                 "0.5; cloud type 0.9;\ncamera 0.3 km up, pitch 23°; display −0.5 EV, ACES curve)", fontsize=9, y=0.995)
    out = out_dir / "fig-5.1.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
