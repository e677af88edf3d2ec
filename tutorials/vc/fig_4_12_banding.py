"""Figure vc-fig-4.12: the discretization artifact, (a) without filter, (b) with filter (reproducible in kind).

A thick cloud layer marched with few samples shows banding: neighbouring view rays take their samples at almost the
same distances, so the sampled density jumps in steps that line up across the image (the Riemann sum vc-2.18 of the
raymarch vc-A35 with the sample count of vc-A18 and the accumulation of vc-A21). The thesis' filter tilts every ray by
a small pseudo-random angle (vc-A23, "tilt"); pywarp also offers a random start offset within the first step
("offset"). Renderer: pywarp.clouds.cloudscape.

Parameters (the thesis gives none; chosen so that the artifact is obvious): the layer top raised from 4 to 12 km
(layer_top_km; the base stays at 1.5 km), samples_min = 12 and samples_max = 16 instead of 64 / 128, cumulus
(cloud_type 1.0), coverage 0.45, sun at elevation 25°, azimuth 110°, camera 0.3 km up looking 25° up with a 60°
field of view, Preetham sky, seed 0. Panels: (a) jitter='none'; (b) jitter='tilt' with the renderer's default tilt of
0.002 rad (the thesis' filter; the amount is not given); (c) jitter='tilt' with 0.02 rad (advanced={'jitter_amount':
0.02}); (d) jitter='offset'; (e) the renderer's own fix, its defaults: the offset jitter, the refinement of view steps
longer than refine_step_km where a coarse test finds cloud, and the level of detail. The enlarged crops are
nearest-neighbour x3. 480x270 per panel.
Output: figures/vc/fig-4.12.png.
"""
# %% [markdown]
# A raymarch replaces the integral along a view ray by a sum over N samples at distances t_0 + (i + ½)·Δt. With a
# thick layer and a small N the steps Δt are hundreds of metres long. Two neighbouring pixels look in almost the same
# direction, so they sample the clouds at almost the same points: where a cloud boundary falls between two sample
# shells, the whole region of the image that "sees" that boundary jumps by one sample at once. The result is a stack
# of contour-like bands that follow the shells of constant distance — the artifact of thesis figure 4.12a.
#
# The filter makes neighbouring rays sample different points. The thesis tilts each ray slightly in a pseudo-random
# direction. A tilt only moves the samples sideways, by (tilt angle × distance), and barely changes where along the
# ray they fall, so it has to be large enough to move them by a good part of a band; with the default 0.002 rad it is
# about 10 m at 5 km and the bands stay. A random offset of the first sample along the ray (a fraction
# of Δt, different per pixel) breaks the bands directly. Both turn the bands into fine noise, which the eye (and the
# temporal reprojection) tolerates far better.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402

SCENE = dict(layer_top_km=12.0, samples_min=12, samples_max=16, cloud_type=1.0, coverage=0.45, sun_elevation_deg=25.0,
             sun_azimuth_deg=110.0, camera_altitude_km=0.3, camera_pitch_deg=25.0, fov_y_deg=60.0, seed=0,
             # the thesis's march: no refinement of long steps, no level of detail (the renderer's defaults remove
             # the bands by splitting long steps where there is cloud; this figure shows the artefact and its filters)
             refine_step_km=0.0, lod=False)
FULL = dict(width=480, height=270)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)
PANELS = (("(a) no filter (jitter='none')", dict(jitter="none")),
          ("(b) tilt filter, 0.002 rad (the thesis's)", dict(jitter="tilt")),
          ("(c) tilt filter, 0.02 rad", dict(jitter="tilt", advanced={"jitter_amount": 0.02})),
          ("(d) random start offset", dict(jitter="offset")),
          ("(e) the renderer's defaults: offset,\nrefinement of long steps, level of detail", "defaults"))
CROP = (0.66, 0.36, 0.30, 0.34)  # x, y, width, height as fractions of the frame: the tower on the right


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = QUICK if quick else FULL

    # %% [markdown]
    # One technique per panel; the textures are generated once and shared (they do not depend on the jitter).

    # %%
    first = CloudscapeTechnique(CloudscapeSettings(**size, **SCENE, **PANELS[0][1]))
    images = [first.render()]
    thesis_march = ("refine_step_km", "lod")
    for _, changes in PANELS[1:]:
        if changes == "defaults":  # the same scene with the renderer's march (jitter, refinement, lod: defaults)
            s = CloudscapeSettings(**size, **{k: v for k, v in SCENE.items() if k not in thesis_march})
        else:
            s = CloudscapeSettings(**size, **SCENE, **changes)
        images.append(CloudscapeTechnique(s, textures=first.textures).render())

    # %%
    h, w = images[0].shape[:2]
    cx, cy, cw, ch = (int(round(f * n)) for f, n in zip(CROP, (w, h, w, h)))
    fig, axes = plt.subplots(2, len(PANELS), figsize=(21.0, 6.9), dpi=100 if not quick else 60,
                             gridspec_kw=dict(height_ratios=[h / w, ch / cw]))
    for k, ((title, _), img) in enumerate(zip(PANELS, images)):
        ax = axes[0, k]
        ax.imshow(img, interpolation="nearest")
        ax.add_patch(Rectangle((cx - 0.5, cy - 0.5), cw, ch, fill=False, ec="red", lw=1.2))
        ax.set_title(title, fontsize=10)
        ax.set_axis_off()
        ax = axes[1, k]
        ax.imshow(img[cy:cy + ch, cx:cx + cw], interpolation="nearest")
        ax.set_title("red box enlarged ×3" if k == 0 else "", fontsize=8)
        ax.set_axis_off()
    fig.suptitle("Fig 4.12 — discretization artifact of a thick layer (1.5–12 km) marched with 12–16 samples: "
                 "(a) without filter, (b)–(d) with filters (vc-A23)", fontsize=11)
    fig.text(0.5, 0.012, "The thesis's tilt (b) moves the samples only sideways (~10 m at 5 km) and leaves the bands; a "
             "10x larger tilt (c) or a random start offset along the ray (d) turns them into per-pixel noise;\nthe "
             "renderer's defaults (e) -- the offset jitter with long view steps split where there is cloud "
             "(refine_step_km) -- remove both.", ha="center", fontsize=9)
    fig.subplots_adjust(left=0.005, right=0.995, top=0.86, bottom=0.08, wspace=0.02, hspace=0.12)
    out = out_dir / "fig-4.12.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
