"""Figure vc-fig-2.7: types of Worley noise -- (a) classic (Euclidean F1), (b) Manhattan-Worley (L1 distance),
(c) inverse Worley (1 - F1).

Worley cellular noise (vc-A3) and its variants (vc-A4), all three from one call of pywarp.noise_worley3_variants;
8 cells per unit, seed 3, 256 x 256 pixels. The library's Worley noise is 3-D (the cloud textures are volumes), so
the panels are the slice z = 0.5625 (the middle of a layer of cells) of the unit cube; grid size, seed and resolution
are not stated in the thesis. A profile along one row (not in the thesis) shows the shape of the distance functions.
Output: figures/vc/fig-2.7.png.
"""
# %% [markdown]
# Worley noise scatters one random feature point in every cell of a grid and colours each point of space by its
# distance to the NEAREST feature point (F1). Only the own cell and its neighbours can hold the nearest point, so
# 27 cells are searched in 3-D. Distances are measured in cell units and clamped to [0, 1].
#
# * (a) classic: Euclidean distance sqrt(dx² + dy² + dz²) -- round dark spots at the feature points, bright ridges
#   where two points are equally far (the Voronoi cell borders).
# * (b) Manhattan: |dx| + |dy| + |dz| -- the spots become diamonds and the borders run at 45° and along the axes.
# * (c) inverse: 1 - F1 -- bright round blobs with dark creases between them: it looks like packed cauliflower
#   "billows", which is why the cloud textures of the thesis use inverse Worley noise.
#
# Because the feature points live in 3-D, a slice cuts most of them off-centre: not every cell has a black spot,
# the minimum of a cell is its point's distance to the slicing plane. The same off-plane distance |dz| makes the
# Manhattan distance exceed one cell more often: the library clamps F1 to 1 (beyond one cell the 27-cell search
# would no longer be exact, vc-A3), which gives the flat white patches of panel (b).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    cells, seed = 8, 3
    z = 4.5 / cells  # the middle of a layer of cells
    n = 96 if quick else 256
    u = (np.arange(n) + 0.5) / n  # pixel centres; the noise has period 1 on every axis
    x, y = np.meshgrid(u, u)

    # %% [markdown]
    # One library call gives all three variants (each equals pywarp.noise_worley3 with the matching `metric` and
    # `inverse` options).

    # %%
    classic, manhattan, inverse = pywarp.noise_worley3_variants(x, y, z, cells, seed)
    assert np.array_equal(manhattan, pywarp.noise_worley3(x, y, z, cells, seed, metric="manhattan"))

    fig = plt.figure(figsize=(13, 7.6), dpi=80 if quick else 110)
    gs = fig.add_gridspec(2, 3, height_ratios=(3.0, 1.25), hspace=0.32, wspace=0.12,
                          left=0.05, right=0.98, top=0.88, bottom=0.08)
    row = n * 5 // 8  # profile row
    panels = (("(a) classic Worley  F1 (Euclidean)", classic, "C0"),
              ("(b) Manhattan-Worley  F1 (|dx| + |dy| + |dz|)", manhattan, "C1"),
              ("(c) inverse Worley  1 - F1", inverse, "C2"))
    for j, (title, img, color) in enumerate(panels):
        ax = fig.add_subplot(gs[0, j])
        ax.imshow(img, cmap="gray", vmin=0.0, vmax=1.0, origin="lower", extent=(0, 1, 0, 1),
                  interpolation="nearest")
        ax.axhline(u[row], color=color, lw=1.2, ls="--")
        ax.set_title(title, fontsize=10)
        ax.set_xticks(np.linspace(0, 1, cells + 1))
        ax.set_yticks(np.linspace(0, 1, cells + 1))
        ax.set_xticklabels([])
        ax.set_yticklabels([])
        ax.grid(color="yellow", alpha=0.25, lw=0.6)  # the cell grid (one feature point per cell)

    # %% [markdown]
    # The profile along the dashed line: the Euclidean distance grows like a cone around each point (curved where
    # the line passes beside the point), the Manhattan distance like a pyramid (straight segments), and the inverse
    # is the classic profile upside down.

    # %%
    ax = fig.add_subplot(gs[1, :])
    for title, img, color in panels:
        ax.plot(u, img[row], color=color, lw=1.4, label=title.split("  ")[0])
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.22)
    ax.set_yticks(np.linspace(0, 1, 6))
    ax.set_xticks(np.linspace(0, 1, cells + 1))
    ax.grid(alpha=0.3)
    ax.set_xlabel(f"x (unit period; grid lines = the {cells} cells)")
    ax.set_ylabel("value")
    ax.legend(loc="upper center", ncol=3, fontsize=8.5, frameon=False)
    fig.suptitle(f"Worley noise (vc-A3, vc-A4): slice z = {z} of the 3-D noise, {cells} cells per unit, seed {seed}, "
                 f"{n}² px; the faint grid marks the cells;\n"
                 "F1 in cell units, clamped to 1 (the white plateaus of (b))",
                 fontsize=11)
    out = out_dir / "fig-2.7.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
