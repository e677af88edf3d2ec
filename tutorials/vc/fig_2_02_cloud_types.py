"""Figure vc-fig-2.2 (photograph of low clouds), stand-in: renders of layers of stratus, stratocumulus and cumulus.

The thesis shows a photograph of low clouds (reproducible: no). The stand-in renders the cloud layer with a single
cloud type everywhere -- 0 (stratus), 0.5 (stratocumulus), 1 (cumulus), the values of the weather map's blue channel
(vc-A12, vc-A16) -- so that only the height gradient of vc-4.7 differs between the columns; the rest is the full
cloud pass (vc-A17 with vc-2.28, vc-2.29, vc-2.30; lighting vc-2.31, vc-A19, vc-A20; vc-A21; vc-4.8) over the
Preetham sky (vc-A29). Renderer: pywarp.clouds.cloudscape with textures from pywarp.clouds.textures.BasicTextureGenerator, because
the renderer's settings expose only the mean cloud type: the weather map is generated with cloud_type_variation = 0
(WeatherMapSettings) so the type is exactly 0, 0.5 or 1 everywhere.

Rows: (1) the renderer's defaults, whose height gradients clamp each remap of vc-4.7 to [0, 1]; (2) the gradients as
printed in the thesis (unclamped, advanced={'gradient_clamp': 0}); (3) the same as (2) seen from 5 km, 12° down.
Other parameters (the thesis gives none): coverage 0.5, precipitation 0.2, seed 0, sun 25° up at azimuth 110°, camera
0.3 km up looking 22° up with a 50° vertical field of view (rows 1-2); 400x225 per panel. The right-hand plot shows
the three height gradients (pywarp.clouds_height_gradient) in both readings. Every panel averages 8 jittered frames
(render_accumulated: no ray-jitter speckle) and is shown through the scene's display transform (-0.5 EV, ACES). The
vertical walls in the as-printed cumulus panels are that reading's: with D_v up to 2.18 the density is large
everywhere inside the coverage, and the layer ends at the coverage step of 2.29 in a wall. Output:
figures/vc/fig-2.2.png.
"""
# %% [markdown]
# Low clouds come in three families that the renderer distinguishes only by their vertical profile: **stratus**, a
# thin grey sheet near the bottom of the layer; **stratocumulus**, lumpy and a little taller; **cumulus**, towering
# heaps. The weather map stores a cloud type per ground position (blue channel: 0 stratus, 0.5 stratocumulus,
# 1 cumulus) and the height gradient D_v(h, type) of formula 4.7 multiplies the base shape (2.29): where D_v is 0 no
# cloud can exist.
#
# The clamped reading (the renderer's default) caps the stratus profile at 0.75 over a band only 0.2 of the layer
# thick, and then the coverage step of 2.29 (threshold C = D_h) removes almost all of it: the stratus sky of row 1 is
# nearly empty. Read as printed, the unclamped profiles are larger (the stratus peak is 1.13, the cumulus one 2.18),
# so the stratus sheet appears — and the cumulus and stratocumulus layers become much denser.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds import textures as T  # noqa: E402
from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.core.pose import Pose  # noqa: E402
from pywarp.tutorial import one_type_textures  # noqa: E402

TYPES = ((0.0, "stratus (type 0)"), (0.5, "stratocumulus (type 0.5)"), (1.0, "cumulus (type 1)"))
SCENE = dict(coverage=0.5, precipitation=0.2, seed=0, sun_elevation_deg=25.0, sun_azimuth_deg=110.0,
             camera_altitude_km=0.3, camera_pitch_deg=22.0, fov_y_deg=50.0)
FULL = dict(width=400, height=225)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)
ABOVE = Pose(x=0.0, y=5.0, z=0.0, yaw_deg=0.0, pitch_deg=-12.0, fov_y_deg=50.0)


# %% [markdown]
# The textures for one cloud type (`pywarp.tutorial.one_type_textures`): the same generator the renderer uses, with
# the weather map's type spread set to 0. The base, detail and curl textures do not depend on the type (they come from
# the cache after the first column).

ACCUMULATE = 8  # jittered frames per panel (full size): the ray-jitter noise falls to a third of one frame's


# %%
def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    gen = T.BasicTextureGenerator()
    rows = (("renderer default:\nclamped gradients", {}, None),
            ("gradients as printed\n(gradient_clamp 0)", {"gradient_clamp": 0}, None),
            ("as printed,\nseen from 5 km", {"gradient_clamp": 0}, ABOVE))
    images = []
    for _, advanced, pose in rows:
        row = []
        for cloud_type, _ in TYPES:
            s = CloudscapeSettings(**(QUICK if quick else FULL), **SCENE, cloud_type=cloud_type, advanced=advanced)
            tech = CloudscapeTechnique(s, textures=one_type_textures(s, gen))
            row.append(tech.render_accumulated(pose, 2 if quick else ACCUMULATE))
        images.append(row)

    # %% [markdown]
    # The profiles themselves, in both readings: pywarp.clouds_height_gradient(h, type, clamp=...).

    # %%
    h = np.linspace(0.0, 1.0, 101 if quick else 401, dtype=np.float32)
    fig = plt.figure(figsize=(16.0, 8.6), dpi=60 if quick else 100)
    gs = fig.add_gridspec(3, 3, left=0.035, right=0.79, top=0.9, bottom=0.06,
                          wspace=0.04, hspace=0.12)
    gs_plot = fig.add_gridspec(1, 1, left=0.835, right=0.99, top=0.9, bottom=0.06)
    for r, (label, _, _) in enumerate(rows):
        for c, (_, name) in enumerate(TYPES):
            ax = fig.add_subplot(gs[r, c])
            ax.imshow(images[r][c], interpolation="nearest")
            ax.set_xticks([])
            ax.set_yticks([])
            if r == 0:
                ax.set_title(name, fontsize=11)
            if c == 0:
                ax.set_ylabel(label, fontsize=9)
    ax = fig.add_subplot(gs_plot[0, 0])
    colours = ("tab:blue", "tab:orange", "tab:green")
    for (cloud_type, _), colour in zip(TYPES, colours):
        ax.plot(pywarp.clouds_height_gradient(h, cloud_type, clamp=True), h, color=colour)
        ax.plot(pywarp.clouds_height_gradient(h, cloud_type, clamp=False), h, "--", color=colour, lw=1.0)
    handles = [plt.Line2D([], [], color=c, label=n.split(" (")[0]) for (_, n), c in zip(TYPES, colours)]
    handles += [plt.Line2D([], [], color="k", label="clamped (renderer)"),
                plt.Line2D([], [], color="k", ls="--", lw=1.0, label="as printed")]
    ax.set_xlabel("height gradient D_v (4.7)")
    s0 = CloudscapeSettings()
    ax.set_ylabel(f"relative height h (0 = layer base {s0.layer_base_km:g} km, 1 = top {s0.layer_top_km:g} km)")
    ax.set_ylim(0.0, 1.0)
    ax.set_xlim(0.0, 2.6)
    ax.grid(alpha=0.3)
    ax.legend(handles=handles, fontsize=8, loc="upper right", frameon=False)
    fig.suptitle("Fig 2.2 stand-in (the thesis shows a photograph of low clouds): one cloud type everywhere, "
                 "coverage 0.5, sun 25° up; rows 1–2 from 0.3 km looking 22° up", fontsize=11)
    out = out_dir / "fig-2.2.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
