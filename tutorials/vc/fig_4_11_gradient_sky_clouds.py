"""Figure vc-fig-4.11: the final cloud over the gradient atmosphere model (reproducible in kind).

The whole cloud pass of the thesis rendered over the gradient sky (vc-A28) instead of the Preetham sky: per pixel the
sky colour B is written first, then the view ray is marched through the cloud layer (vc-A14, vc-A24, vc-A18), the
density of every sample is built from the weather map and the noise textures (vc-A17: vc-4.7, vc-2.28, vc-2.29,
vc-2.30), lit by six cone samples towards the sun (vc-A19) with the energy of vc-2.31 plus the height-dependent
ambient term (vc-A20), accumulated front to back (vc-A21) and composited over the sky with C_f = B (1 - O_D) +
C_clouds (vc-4.8, vc-A22). Renderer: pywarp.clouds.cloudscape (CloudscapeSettings, CloudscapeTechnique).

The thesis gives no parameters for this figure; the ones chosen here: sky='gradient' (pywarp's default colours),
sun 20° above the horizon at azimuth 30° (in view, so the sun lobe of the gradient model shows through the gaps),
camera 0.3 km above the ground looking 20° up with a 50° vertical field of view, weather-map coverage 0.45, mean
cloud type 0.75, precipitation 0.2, seed 0; every other setting is the renderer's documented default (layer 1.5-4 km,
64-128 view samples, g = 0.2, tilt jitter). Left panel: the same view with coverage 0 (no clouds), i.e. the sky
model's own output. 640x360 per panel (about 1 s each on two cores).
Output: figures/vc/fig-4.11.png.
"""
# %% [markdown]
# The renderer builds a frame in stages. The sky model runs first and writes the background colour of every pixel.
# The cloud stage then marches each view ray through the cloud layer and blends what it found over that background:
#
#     C_f = B · (1 − O_D) + C_clouds                     (vc-4.8)
#
# where O_D = 1 − T is the opacity accumulated along the ray (T: view transmittance) and C_clouds the light scattered
# towards the camera, already weighted by the transmittance in front of each sample. Where there is no cloud O_D = 0
# and the sky shows unchanged; behind thick cloud O_D → 1 and the sky disappears.
#
# The gradient sky is the thesis' simplest sky model: a blend from a light to a dark blue by the height of the view
# direction, plus a glow around the sun. It has no ground: below the horizon it repeats the horizon colour.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402

SCENE = dict(sky="gradient", sun_elevation_deg=20.0, sun_azimuth_deg=30.0, camera_altitude_km=0.3,
             camera_pitch_deg=20.0, fov_y_deg=50.0, coverage=0.45, cloud_type=0.75, precipitation=0.2, seed=0)
FULL = dict(width=640, height=360)
# quick mode: a tiny frame and small textures (the look differs; it only checks that the tutorial runs)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)


def render(quick: bool, **changes):
    s = CloudscapeSettings(**(QUICK if quick else FULL), **{**SCENE, **changes})
    return CloudscapeTechnique(s).render()


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)

    # %% [markdown]
    # Two renders of the same view: coverage 0 gives an empty weather map, so every pixel keeps the sky colour; with
    # coverage 0.45 the clouds are composited over exactly that sky.

    # %%
    sky_only = render(quick, coverage=0.0)
    clouds = render(quick)

    # %%
    h, w = clouds.shape[:2]
    width = max(2 * w / 100 + 0.4, 12.0)  # at least 12 in: the quick mode's small renders keep a readable title
    fig, axes = plt.subplots(1, 2, figsize=(width, (width - 0.4) / 2 * h / w + 0.9), dpi=100)
    for ax, img, title in ((axes[0], sky_only, "(a) gradient sky model alone (coverage 0)"),
                           (axes[1], clouds, "(b) clouds composited over it, C_f = B(1 − O_D) + C_clouds")):
        ax.imshow(img, interpolation="nearest")
        ax.set_title(title, fontsize=9)
        ax.set_axis_off()
    fig.suptitle("Fig 4.11 — final clouds with the gradient atmosphere model (sun 20° up at azimuth 30°, coverage "
                 "0.45, cloud type 0.75; parameters are pywarp's choices)", fontsize=9)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.84, bottom=0.02, wspace=0.03)
    out = out_dir / "fig-4.11.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
