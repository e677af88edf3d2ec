"""Figure vc-fig-4.13: camera movement outside the inner bounding sphere -- views from inside and above the cloud layer
(reproducible in kind).

The thesis extends the raymarch so that the camera may enter the cloud layer and fly above it (vc-A24): inside the
layer the march starts at the camera and ends where the ray first leaves the layer (inner or outer sphere); above it
the march starts where the ray enters the outer sphere and ends at the inner sphere or the ground. The layer spheres
and their intersections are vc-A14 (pywarp.raymarch_ray_sphere, pywarp.raymarch_layer_segment); everything else is
the full cloud pass (vc-A17, vc-A18, vc-A19, vc-A20, vc-A21, vc-A22, vc-2.31, vc-4.8) over the Preetham sky (vc-A29).
Renderer: pywarp.clouds.cloudscape.

Parameters (none are given in the thesis): the renderer's default layer (base 1.5 km, top 4 km, Earth radius
6371 km), coverage 0.6 (more clouds around the camera inside the layer), cloud type 0.75, seed 0, sun 25° up at
azimuth 120°, 60° vertical field of view, 480x270 per panel. Cameras: (a) inside the layer at 2.5 km, placed
automatically at the texel nearest to the origin whose surroundings (a square of +-0.8 km) have zero weather-map
coverage, so that the camera itself is in clear air (weather map read from the technique's textures), looking 3° down
towards +x (yaw 90°, the sun's side); (b) 0.5 km above the layer top, looking 10° down; (c) 8 km up, looking 25° down.
Panel (d) draws the march segments of the three centre rays, heights to scale.
Output: figures/vc/fig-4.13.png.
"""
# %% [markdown]
# Below the clouds, every view ray that goes up crosses the whole layer: it enters through the inner sphere (the cloud
# base) and leaves through the outer sphere (the cloud tops). Once the camera is inside the layer or above it, the
# segment to march is different (vc-A24):
#
# * inside: from the camera (t = 0) to where the ray first leaves the layer — downwards through the inner sphere,
#   upwards or sideways through the outer sphere;
# * above: from where the ray enters the outer sphere to where it reaches the inner sphere (or misses it and leaves
#   the layer again through the outer sphere near the horizon).
#
# The temporal reprojection of the thesis cannot be used there, because it reprojects through the inner sphere and a
# camera above the layer looking up never meets it (the renderer switches reprojection off by itself).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.core.pose import Pose  # noqa: E402

SCENE = dict(coverage=0.6, cloud_type=0.75, seed=0, sun_elevation_deg=25.0, sun_azimuth_deg=120.0, fov_y_deg=60.0)
FULL = dict(width=480, height=270)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)
CLEAR_HALF_KM = 0.8  # the camera inside the layer needs clear air around it: no coverage within +-0.8 km


# %% [markdown]
# Where to put the camera inside the layer? If the weather map has coverage at the camera's (x, z), the camera may be
# inside a cloud and see only grey. The weather map (red channel = coverage) tiles the ground plane with a period of
# `weather_scale_km`; we look for the texel nearest to the origin whose whole neighbourhood is clear, with a box sum
# over the wrapped map (an integral image), and put the camera there.

# %%
def clear_spot(coverage: np.ndarray, scale_km: float, half_km: float) -> tuple[float, float]:
    """World (x, z) in km of the texel nearest to the origin with zero coverage within +-half_km (square)."""
    n = coverage.shape[0]
    r = max(1, int(round(half_km / scale_km * n)))
    covered = (coverage > 0.0).astype(np.int64)
    padded = np.pad(covered, r, mode="wrap")
    integral = np.pad(padded.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    k = 2 * r + 1
    box = integral[k:, k:] - integral[:-k, k:] - integral[k:, :-k] + integral[:-k, :-k]  # (n, n) window sums
    centres = (np.arange(n) + 0.5) / n * scale_km
    centres = (centres + scale_km / 2) % scale_km - scale_km / 2  # wrap to [-scale/2, scale/2)
    xx, zz = np.meshgrid(centres, centres)  # weather map rows are z, columns x
    dist = np.where(box == 0, np.hypot(xx, zz), np.inf)
    i = np.unravel_index(np.argmin(dist), dist.shape)
    if not np.isfinite(dist[i]):
        raise RuntimeError("the weather map has no clear spot of that size")
    return float(xx[i]), float(zz[i])


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    settings = CloudscapeSettings(**(QUICK if quick else FULL), **SCENE)
    tech = CloudscapeTechnique(settings)
    p = settings.c_values()
    x_in, z_in = clear_spot(tech.textures.weather[..., 0], p["weather_scale_km"], CLEAR_HALF_KM)
    top = settings.layer_top_km
    poses = (("(a) inside the layer", Pose(x_in, 2.5, z_in, 90.0, -3.0, settings.fov_y_deg)),
             ("(b) just above the layer top", Pose(0.0, top + 0.5, 0.0, 0.0, -10.0, settings.fov_y_deg)),
             ("(c) high above the layer", Pose(0.0, 8.0, 0.0, 0.0, -25.0, settings.fov_y_deg)))

    # %% [markdown]
    # The same technique renders all three views; only the camera pose changes. A pose is position (km) + yaw, pitch
    # and field of view.

    # %%
    images = [tech.render(pose) for _, pose in poses]

    # %% [markdown]
    # Panel (d): the march segment of the central ray of each camera, from pywarp.raymarch_layer_segment (vc-A24) — the
    # same function the renderer calls per pixel. Heights are to scale; horizontal distances are compressed (the
    # segment of the camera inside the layer looking 3° down is tens of km long).

    # %%
    c = p["centre"]
    segments = []
    for _, pose in poses:
        d = pose.forward()
        d32 = d.astype(np.float32)  # the unit direction in float32, normalized as the renderer's rays are
        d32 = d32 / np.sqrt(d32[0] * d32[0] + d32[1] * d32[1] + d32[2] * d32[2])
        t0, t1 = pywarp.raymarch_layer_segment((pose.x, pose.y, pose.z), d32, c, p["r_earth"],
                                               p["r_inner"], p["r_outer"])
        segments.append((pose, d, float(t0), float(t1)))

    # %%
    fig = plt.figure(figsize=(13.2, 8.0), dpi=60 if quick else 100)
    gs = fig.add_gridspec(2, 2, left=0.01, right=0.99, top=0.91, bottom=0.04, wspace=0.06, hspace=0.16)
    for k, ((title, pose), img) in enumerate(zip(poses, images)):
        ax = fig.add_subplot(gs[k // 2, k % 2])
        ax.imshow(img, interpolation="nearest")
        ax.set_title(f"{title}: altitude {pose.y:.1f} km, pitch {pose.pitch_deg:+.0f}°", fontsize=10)
        ax.set_axis_off()
    ax = fig.add_subplot(gs[1, 1])
    base, top_km = settings.layer_base_km, settings.layer_top_km
    ax.axhspan(base, top_km, color="0.85", zorder=0)
    ax.text(0.98, base + 0.15, f"cloud layer {base:g}–{top_km:g} km", transform=ax.get_yaxis_transform(),
            ha="right", va="bottom", fontsize=8)
    ax.axhline(0.0, color="saddlebrown", lw=2)
    colours = ("tab:blue", "tab:orange", "tab:green")
    for k, ((pose, d, t0, t1), colour) in enumerate(zip(segments, colours)):
        x0 = 1.0 + 1.2 * k  # each camera drawn at its own place on a compressed horizontal axis
        hdist = np.hypot(d[0], d[2])
        squash = 0.12  # horizontal km drawn per km of distance
        ax.plot([x0], [pose.y], "o", color=colour)
        tt = np.array([0.0, t1 * 1.05])
        ax.plot(x0 + tt * hdist * squash, pose.y + tt * d[1], ":", color=colour, lw=1)
        seg = np.array([t0, t1])
        ax.plot(x0 + seg * hdist * squash, pose.y + seg * d[1], "-", color=colour, lw=3,
                label=f"{'abc'[k]}: march t = {t0:.1f} … {t1:.1f} km")
    ax.set_xlim(0.5, 6.5)
    ax.set_ylim(-0.3, 9.0)
    ax.set_xticks([])
    ax.set_ylabel("altitude [km]")
    ax.legend(fontsize=8, loc="upper right", frameon=False)
    ax.set_title("(d) march segments of the centre rays (pywarp.layer_segment); horizontal axis compressed",
                 fontsize=10)
    fig.suptitle("Fig 4.13 — camera inside and above the cloud layer (vc-A24); reprojection is off in these "
                 "positions", fontsize=11)
    out = out_dir / "fig-4.13.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
