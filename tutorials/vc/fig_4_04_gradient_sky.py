"""Figure vc-fig-4.4: the gradient atmosphere model — a blue gradient with the sun.

Reproduces the kind of image of thesis figure 4.4 with the gradient sky model (vc-A28): per view direction, a linear
interpolation between a light and a dark blue by the direction's Y component, plus a sun colour that grows with the
cosine of the angle between the view ray and the sun. The thesis states no colours, sun angles, field of view or
resolution, so every one of them is a choice here: pywarp's documented defaults for the colours and the sun lobe
(pywarp.kernels.sky.GRADIENT_DEFAULTS, listed in the registry entry of vc-A28), the sun 15° above the horizon straight
ahead, a 60° vertical-field-of-view camera, and an all-sky fisheye panel. View directions are built in NumPy here
(a pinhole camera and an equidistant fisheye). Output: figures/vc/fig-4.4.png.
"""
# %% [markdown]
# A sky model answers one question per pixel: "what colour do I see when I look in direction d?". The gradient model
# of the thesis is the simplest possible answer and serves as the example for user-written sky models:
#
#     colour(d) = lerp(horizon, zenith, clamp(d_y, 0, 1)) + sun · max(d · s, 0)^n
#
# where d_y is the "up" component of the unit view direction (0 at the horizon, 1 straight up), s is the unit
# direction towards the sun and n sets how tight the glow around the sun is. The thesis gives the sun position as two
# angles in degrees; pywarp uses elevation above the horizon and azimuth (0 = straight ahead, −Z, 90° = +X).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.tutorial import fisheye_directions, pinhole_directions, row_of_elevation  # noqa: E402

SUN_ELEVATION_DEG = 15.0
SUN_AZIMUTH_DEG = 0.0
FOV_Y_DEG = 60.0
PITCH_DEG = 25.0  # the camera looks 25° up: the horizon sits 5° above the lower edge of the 60° view


# %% [markdown]
# Directions, from `pywarp.tutorial`. A pinhole camera (`pinhole_directions`, the ray generation of vc-A25 without the
# matrices): the camera looks along f = (cos p sin a, sin p, −cos p cos a) — azimuth a, pitch p, Y up — and the ray
# through the image point (u, v) (both in [−1, 1], u to the right, v up) is f + u·tan(fov/2)·aspect·r +
# v·tan(fov/2)·up, normalised. Because the camera has no roll, the horizon (d_y = 0) projects to a horizontal line.
#
# The fisheye (`fisheye_directions`) is equidistant: the distance from the centre is proportional to the zenith angle
# (centre = zenith, rim = horizon). It shows the sky as seen looking up from below, azimuth 0 at the top, so azimuth
# 90° (+X) is on the LEFT, as in all-sky camera images.

# %%
def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = out_dir if isinstance(out_dir, Path) else Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (240, 135) if quick else (960, 540)
    n_fish = 128 if quick else 400

    # %% [markdown]
    # Evaluate the model. pywarp.sky_gradient_colour takes any array of directions (..., 3) and returns their RGB
    # colours, shape (..., 3). The model itself writes linear RGB (what the thesis puts in the frame buffer); output='srgb' adds the
    # standard sRGB encoding a display expects (the thesis does not mention this step). The default colours are
    # defined so that their sRGB encodings are a light blue (0.84, 0.90, 0.97) and a medium blue (0.44, 0.62, 0.87).

    # %%
    view = pinhole_directions(w, h, FOV_Y_DEG, 0.0, PITCH_DEG)
    img = pywarp.sky_gradient_colour(view, SUN_ELEVATION_DEG, SUN_AZIMUTH_DEG, output="srgb")
    fish_d, inside = fisheye_directions(n_fish)
    fish = pywarp.sky_gradient_colour(fish_d, SUN_ELEVATION_DEG, SUN_AZIMUTH_DEG, output="srgb")
    fish[~inside] = 1.0  # white outside the horizon circle

    # %% [markdown]
    # A cross-section makes the two terms of the formula visible. Plotted against d_y = sin(elevation), the colour on
    # the side of the sky away from the sun (dashed; azimuth 180°, where d · s < 0 up to 75° elevation) is a straight
    # line from the horizon colour (d_y = 0) to the zenith colour (d_y = 1). Towards the sun (solid, azimuth 0°) the
    # sun term adds a peak whose width is set by n: half height at acos(0.5^(1/64)) = 8.4° from the sun for the
    # default n = 64. Linear values above 1 are shown as white. Below the horizon d_y is clamped to 0: the model has
    # no ground, it repeats the horizon colour.

    # %%
    elev = np.linspace(-12.0, 90.0, 205 if quick else 1021)
    e = np.radians(elev)
    towards = np.stack([np.zeros_like(e), np.sin(e), -np.cos(e)], axis=-1)  # azimuth 0, through the sun
    away = towards * np.array([1.0, 1.0, -1.0])  # azimuth 180
    prof_sun = np.moveaxis(pywarp.sky_gradient_colour(towards, SUN_ELEVATION_DEG, SUN_AZIMUTH_DEG), -1, 0)  # linear
    prof_away = np.moveaxis(pywarp.sky_gradient_colour(away, SUN_ELEVATION_DEG, SUN_AZIMUTH_DEG), -1, 0)

    # %%
    fig = plt.figure(figsize=(16.0, 5.0), dpi=80 if quick else 120)
    gs = fig.add_gridspec(1, 3, width_ratios=[16 / 9, 1.0, 1.05], wspace=0.22,
                          left=0.045, right=0.985, top=0.80, bottom=0.13)
    ax = fig.add_subplot(gs[0])
    ax.imshow(np.clip(img, 0.0, 1.0), interpolation="lanczos" if not quick else "nearest")
    ticks = np.array([0, 10, 20, 30, 40, 50])
    ax.set_yticks(row_of_elevation(ticks, h, FOV_Y_DEG, PITCH_DEG), [f"{t}°" for t in ticks])
    ax.set_xticks([])
    ax.set_ylabel("elevation (centre column)")
    hz = float(row_of_elevation(0.0, h, FOV_Y_DEG, PITCH_DEG))
    ax.axhline(hz, color="k", lw=0.6, ls=":", alpha=0.6)
    ax.text(w * 0.01, hz - h * 0.015, "horizon", fontsize=8, va="bottom", alpha=0.7)
    ax.set_title(f"camera view: vertical FOV {FOV_Y_DEG:.0f}°, looking {PITCH_DEG:.0f}° up towards the sun "
                 f"(elevation {SUN_ELEVATION_DEG:.0f}°)", fontsize=10)

    ax = fig.add_subplot(gs[1])
    ax.imshow(np.clip(fish, 0.0, 1.0), extent=(-1, 1, -1, 1), interpolation="lanczos" if not quick else "nearest")
    for zen in (30, 60):
        ax.add_patch(plt.Circle((0, 0), zen / 90.0, fill=False, lw=0.5, ls=":", color="k", alpha=0.5))
    ax.text(0, 1.04, "az 0° (−Z)", ha="center", va="bottom", fontsize=8)
    ax.text(-1.04, 0, "az 90°\n(+X)", ha="right", va="center", fontsize=8)
    ax.text(0.02, 60 / 90.0 - 0.02, "30°", fontsize=7, alpha=0.7, va="top")
    ax.text(0.02, 30 / 90.0 - 0.02, "60°", fontsize=7, alpha=0.7, va="top")
    ax.set_xlim(-1.35, 1.1)
    ax.set_ylim(-1.1, 1.2)
    ax.set_axis_off()
    ax.set_title("all-sky fisheye (equidistant, looking up),\nrings: elevation 30°, 60°", fontsize=10)

    ax = fig.add_subplot(gs[2])
    dy = np.sin(e)
    for k, (c, name) in enumerate(zip(("tab:red", "tab:green", "tab:blue"), "RGB")):
        ax.plot(dy, prof_sun[k], color=c, label=name)
        ax.plot(dy, prof_away[k], color=c, ls="--", lw=1.0)
    ax.axvline(np.sin(np.radians(SUN_ELEVATION_DEG)), color="orange", lw=0.8, ls=":")
    ax.text(np.sin(np.radians(SUN_ELEVATION_DEG)) + 0.01, 0.04, "sun", color="darkorange", fontsize=8)
    ax.axvline(0.0, color="k", lw=0.6, ls=":")
    ax.set_xlabel("d_y = sin(elevation)  (vertical through the sun)")
    ax.set_ylabel("linear RGB (as the model writes it)")
    ax.set_xlim(dy[0], 1.0)
    ax.set_ylim(0.0, 1.75)
    ax.grid(alpha=0.3)
    handles = ax.get_legend_handles_labels()[0] + [
        plt.Line2D([], [], color="k", label="towards the sun (az 0°)"),
        plt.Line2D([], [], color="k", ls="--", lw=1.0, label="away from it (az 180°)")]
    ax.legend(handles=handles, fontsize=7.5, loc="upper right", frameon=False)
    top = ax.secondary_xaxis("top", functions=(lambda x: np.degrees(np.arcsin(np.clip(x, -1, 1))),
                                               lambda d: np.sin(np.radians(d))))
    top.set_xticks([0, 15, 30, 45, 60, 90])
    top.tick_params(labelsize=8)
    top.set_xlabel("elevation [deg]", fontsize=8)
    ax.set_title("cross-section: a straight ramp in d_y plus the sun lobe", fontsize=10)

    fig.suptitle("Fig 4.4 — gradient sky model (vc-A28): lerp(light blue, dark blue, d_y) + sun·max(d·s, 0)^64 "
                 "(colours, sun and camera are pywarp's choices; the thesis states none)", fontsize=11)
    out = out_dir / "fig-4.4.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
