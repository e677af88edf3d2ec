"""Figures oc-fig-4.4 and oc-fig-4.5, schematic only: the voxel grid of the cellular-automaton clouds (oc-4.4) and its
three Boolean state variables hum, cld and act per cell.

The text describes the method (Dobashi et al. 2000) without its transition rules, so the automaton is not simulated:
fig. 4.4 draws a 12 x 8 x 6 grid (front half cut away) whose cloud cells (cld = 1) are a hand-placed heap, fig. 4.5 draws one horizontal
slice of the three state variables side by side and, for the continuous density the text mentions, the cld slice
smoothed by averaging each cell with its neighbours (a 3 x 3 box, our choice; Dobashi et al. use a weighted
average over a larger neighbourhood). The layouts are seeded (seed 4) and deterministic.
Outputs: figures/oc/fig-4.4.png, figures/oc/fig-4.5.png.
"""
# %% [markdown]
# In the cellular-automaton method the sky is a grid of cells, each holding three bits: **hum** (there is vapour),
# **act** (a phase transition may happen here) and **cld** (there is cloud). Rules applied to all cells at once move
# the bits from step to step -- vapour becomes activated, activated cells become cloud -- and because the states are
# bits, a whole row of cells is updated with a few bitwise operations. The text lists the variables but not the
# rules, so these figures show the data structure, not a simulation. For rendering, the one-bit cloud is turned into
# a continuous density by averaging over neighbouring cells.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SHAPE = (12, 8, 6)  # x, y (depth), z (up) cells


def states(seed: int = 4):
    """Hand-placed hum / act / cld bits: a heap of cloud over a wider layer of humid cells."""
    rng = np.random.default_rng(seed)
    x, y, z = np.meshgrid(*(np.arange(n) for n in SHAPE), indexing="ij")
    r = np.sqrt(((x - 5.5) / 4.0) ** 2 + ((y - 3.5) / 3.0) ** 2 + (z / 4.5) ** 2)
    cld = (r < 1.0) & (rng.random(SHAPE) < 0.85)
    hum = (r < 1.5) & ~cld & (rng.random(SHAPE) < 0.7)
    act = hum & (r < 1.25) & (rng.random(SHAPE) < 0.5)
    return hum, act, cld


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    hum, act, cld = states()
    dpi = 60 if quick else 100

    fig = plt.figure(figsize=(6.4, 4.8), dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    colours = np.empty(SHAPE, dtype=object)
    colours[hum] = "#9ecae180"
    colours[act] = "#fdae6b90"
    colours[cld] = "#f7f7f7ff"
    cut = np.zeros(SHAPE, bool)
    cut[:, 4:, :] = True  # the back half only: a cut-away that shows the cloud cells inside
    ax.voxels((hum | act | cld) & cut, facecolors=colours, edgecolor="#55555560", linewidth=0.3)
    ax.set_box_aspect(SHAPE)
    ax.set_title("cellular automaton: cells of the voxel grid, front half cut away\n(white: cld = 1, orange: act = 1, blue: hum = 1)",
                 fontsize=9)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("height")
    p44 = out_dir / "fig-4.4.png"
    fig.savefig(p44, dpi=dpi)
    plt.close(fig)

    k = 1  # the slice one cell above the ground
    padded = np.pad(cld[:, :, k].astype(float), 1)
    smooth = sum(padded[1 + i:padded.shape[0] - 1 + i, 1 + j:padded.shape[1] - 1 + j]
                 for i in (-1, 0, 1) for j in (-1, 0, 1)) / 9.0
    fig, axes = plt.subplots(1, 4, figsize=(11, 3.2), dpi=dpi)
    for ax, (name, a, cmap) in zip(axes, (("hum (humidity)", hum, "Blues"), ("act (phase transition possible)", act,
                                                                            "Oranges"),
                                          ("cld (cloud)", cld, "Greys_r"))):
        ax.imshow(a[:, :, k].T, cmap=cmap, vmin=0, vmax=1.4 if cmap != "Greys_r" else 1, origin="lower")
        ax.set_title(f"{name}: one bit per cell", fontsize=8)
        for (i, j), v in np.ndenumerate(a[:, :, k]):
            ax.text(i, j, int(v), ha="center", va="center", fontsize=6, color="red" if cmap == "Greys_r" else "k")
        ax.set_xticks([])
        ax.set_yticks([])
    axes[3].imshow(smooth.T, cmap="Greys_r", vmin=0, vmax=1, origin="lower")
    axes[3].set_title("continuous density: cld averaged\nover 3 x 3 neighbours", fontsize=8)
    axes[3].set_xticks([])
    axes[3].set_yticks([])
    fig.suptitle("one slice of the automaton's state (the transition rules hum -> act -> cld are not given in the "
                 "text: not simulated)", fontsize=9)
    fig.tight_layout()
    p45 = out_dir / "fig-4.5.png"
    fig.savefig(p45, dpi=dpi)
    plt.close(fig)
    return [p44, p45]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
