"""Figure vc-fig-2.12: a weather map decomposed into its channels -- coverage (R), precipitation (G), cloud type (B)
-- next to the composite, plus (not in the thesis) the effect of the global coverage setting.

Stand-in: the thesis loads a pre-made weather-map file and gives no generation algorithm, so the map here is the
library's procedural one, pywarp.clouds.textures.BasicTextureGenerator().weather_map with the default WeatherMapSettings
(vc-A12: 512², seed 0; coverage from a tileable Perlin-Worley noise (vc-A8) thresholded by remap (vc-2.27),
precipitation and cloud type from independent Perlin fBm (vc-2.21)). Channel layout: the spec's reading of the
"blue named twice" erratum of the thesis (§3.2 gives blue to both precipitation and cloud type; we read
precipitation = green, A free). Output: figures/vc/fig-2.12.png.
"""
# %% [markdown]
# The weather map is a 2-D texture laid flat over the whole cloud layer (planar projection, scaled by a setting). It
# tells the shader, for every horizontal position, WHERE there are clouds and WHAT KIND:
#
# * R, coverage: 0 = clear sky, 1 = fully cloudy. The base-shape noise is cut by it (eq. 2.29), so its bright
#   patches become cloud fields.
# * G, precipitation: darker, denser rain clouds (it scales the extinction `a` of the lighting, eq. 2.31).
# * B, cloud type: 0 stratus (flat), 0.5 stratocumulus, 1 cumulus (tall); it picks the vertical density profile.
# * A: free (the thesis' conclusion suggests the cloud-base height for a future weather-map tool).
#
# The thesis ships a hand-made file; the library generates a map procedurally, so the image is a stand-in with the
# same channel meanings.

# %%
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LinearSegmentedColormap  # noqa: E402

from pywarp.clouds.textures import BasicTextureGenerator, WeatherMap, WeatherMapSettings  # noqa: E402

# one black -> colour ramp per channel, so each panel reads as "how much of this channel"; the blue ramp continues to
# a light blue so that the cloud types of the map (0.5 to 1) span a visible range of shades
RAMPS = {name: LinearSegmentedColormap.from_list(name, colours)
         for name, colours in (("red", ["black", "#ff2020"]), ("green", ["black", "#20e020"]),
                               ("blue", ["black", "#2040ff", "#c8dcff"]))}


def _style(ax):
    ax.set_xticks([0, 0.5, 1])
    ax.set_yticks([0, 0.5, 1])
    ax.tick_params(labelsize=7)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)

    # %% [markdown]
    # Generate the map (512² RGBA, about 0.3 s; cached). WeatherMap wraps the array and names its channels.

    # %%
    settings = WeatherMapSettings(size=128) if quick else WeatherMapSettings()
    gen = BasicTextureGenerator()
    wm = WeatherMap(gen.weather_map(settings))
    assert not np.any(wm.data[..., 3])  # A is free (0)

    fig = plt.figure(figsize=(15, 8.8), dpi=70 if quick else 100)
    gs = fig.add_gridspec(2, 4, hspace=0.26, wspace=0.28, left=0.03, right=0.965, top=0.90, bottom=0.10)
    ext = (0, 1, 0, 1)

    # %% [markdown]
    # Top row: (a) the composite as an RGB image -- the blue cast is the cloud type (0.5 to 1 everywhere), magenta
    # patches are cloud fields (red coverage + blue), cyan patches are precipitation (green + blue), white where both
    # meet. (b)-(d) each channel alone. The library draws the three channels from independent noises, so rain also
    # appears over clear sky: it only matters where the coverage is > 0 (a hand-painted map would align them).

    # %%
    ax = fig.add_subplot(gs[0, 0])
    ax.imshow(wm.data[..., :3], origin="lower", extent=ext, interpolation="nearest")
    ax.set_title("(a) composite RGB", fontsize=10)
    _style(ax)
    panels = (("(b) R  coverage", wm.coverage, "red", [0, 0.5, 1], ["0 clear", "0.5", "1 overcast"]),
              ("(c) G  precipitation", wm.precipitation, "green", [0, 0.5, 1], ["0 dry", "0.5", "1 rain"]),
              ("(d) B  cloud type", wm.cloud_type, "blue", [0, 0.5, 1], ["0 stratus", "0.5 stratocumulus",
                                                                         "1 cumulus"]))
    for j, (title, img, ramp, ticks, labels) in enumerate(panels):
        ax = fig.add_subplot(gs[0, j + 1])
        im = ax.imshow(img, cmap=RAMPS[ramp], vmin=0.0, vmax=1.0, origin="lower", extent=ext, interpolation="nearest")
        ax.set_title(f"{title}   (mean {img.mean():.2f})", fontsize=10)
        _style(ax)
        cb = fig.colorbar(im, ax=ax, fraction=0.046, pad=0.03, ticks=ticks)
        cb.ax.set_yticklabels(labels, fontsize=7, rotation=90, va="center")

    # %% [markdown]
    # Bottom row, not in the thesis: the global coverage setting c shifts the threshold of the coverage noise n,
    # R = clamp(remap(n, 1 - c, 1, 0, 1), 0, 1) (vc-2.27): c = 0.25 keeps only the strongest cloud fields, c = 0.75
    # covers most of the sky. The fraction of texels with R > 0 is printed under each panel.

    # %%
    for j, c in enumerate((0.25, 0.5, 0.75)):
        cov = gen.weather_map(replace(settings, coverage=c))[..., 0]
        ax = fig.add_subplot(gs[1, j])
        ax.imshow(cov, cmap=RAMPS["red"], vmin=0.0, vmax=1.0, origin="lower", extent=ext, interpolation="nearest")
        ax.set_title(f"({'efg'[j]}) R with coverage = {c:g}", fontsize=10)
        ax.set_xlabel(f"covered (R > 0): {np.mean(cov > 0.0):.0%} of the map", fontsize=9)
        _style(ax)

    # %% [markdown]
    # (h) The channel layout and the erratum: §3.2 of the thesis names "blue" twice, for precipitation and for cloud
    # type. One channel cannot hold both; by elimination, by the order "density, precipitation, type" of §2.3.3 and
    # by Schneider's Horizon Zero Dawn layout, precipitation is green and alpha is the free channel. The library
    # (and this figure) uses that reading; there is no "as printed" variant to draw.

    # %%
    ax = fig.add_subplot(gs[1, 3])
    ax.axis("off")
    rows = (("R", "coverage", "as printed (L449, §3.2)", "#d01010"),
            ("G", "precipitation", "our reading; §3.2 prints \"blue\"", "#10a010"),
            ("B", "cloud type", "as printed (L443, §3.2)", "#2040e0"),
            ("A", "free (= 0)", "conclusion: e.g. cloud-base height", "0.35"))
    ax.text(0.0, 0.97, "channel layout (vc-A12)", fontsize=11, weight="bold", va="top", transform=ax.transAxes)
    for i, (ch, what, src, colour) in enumerate(rows):
        yy = 0.80 - 0.15 * i
        ax.text(0.0, yy, ch, color=colour, fontsize=13, weight="bold", va="center", transform=ax.transAxes)
        ax.text(0.12, yy + 0.03, what, fontsize=10, va="center", transform=ax.transAxes)
        ax.text(0.12, yy - 0.035, src, fontsize=8, color="0.3", va="center", transform=ax.transAxes)
    ax.text(0.0, 0.12, "As printed (§3.2): blue = precipitation and\nblue = cloud type -- two quantities in one\n"
            "channel; G is the free one by elimination.", fontsize=8.5, va="top", transform=ax.transAxes,
            bbox=dict(facecolor="#fff3d0", edgecolor="#d0a040", boxstyle="round,pad=0.4"))

    fig.suptitle(f"Weather map (vc-A12), stand-in: the library's procedural {settings.size}² map (default "
                 f"WeatherMapSettings, seed {settings.seed}); the thesis loads a hand-made file.\nChannels in [0, 1], "
                 "each drawn black -> its colour; the map tiles and is projected flat over the cloud layer",
                 fontsize=11)
    fig.text(0.5, 0.015, "Erratum (spec §7 item 13): §3.2 of the thesis assigns \"blue\" to both precipitation and "
             "cloud type; shown here: precipitation = G, cloud type = B, A free.", ha="center", fontsize=9.5,
             style="italic")
    out = out_dir / "fig-2.12.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
