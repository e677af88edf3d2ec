"""Figures oc-fig-4.4 and oc-fig-4.5: the voxel grid of the cellular-automaton clouds (oc-4.4) with its three Boolean
state variables hum, cld and act per cell, and the simulation process.

Fig. 4.4 (schematic) draws a 12 x 8 x 6 grid (front half cut away) whose cloud cells (cld = 1) are a hand-placed heap.
Fig. 4.5, "(a) simulation process": the automaton run over several steps with the transition rules of Dobashi et al.
2000 (after Nagel and Raschke), which the text cites but does not print -- BEYOND THE TEXT, in NumPy in this tutorial
only (no catalogued function: the text gives no equation for it to implement):

    hum' = hum & ~act,   cld' = cld | act,   act' = ~act & hum & f_act,
    f_act = act at (i +- 1, j, k), (i +- 2, j, k), (i, j +- 1, k), (i, j +- 2, k), (i, j, k - 1), (i, j, k - 2)
            (k up: activation spreads sideways and upwards),
    then cloud extinction and supply: cld' &= rnd > p_ext, hum' |= rnd < p_hum, act' |= rnd < p_act,

with the probabilities set by an ellipsoid, as Dobashi et al. control the cloud's shape: q the squared radius of the
ellipsoid (semi-axes 0.4, 0.3, 0.35 of the 64 x 32 x 32 grid, its centre a third of the way up), inside it
p_hum = 0.02 (1 - q), p_act = 0.002 (1 - q), p_ext = 0.1 q, outside p_hum = p_act = 0, p_ext = 1; at step 0 hum is set
in 40 % of the ellipsoid's cells and act in none (the supply starts it). The panels show steps 0, 4, 10, 20 and 40: a
vertical slice of the three bits (top) and the cloud seen through the grid (bottom: cld averaged over 3 x 3 x 3
neighbours, the continuous density the text mentions, then summed along the view). Seed 4; deterministic.
Outputs: figures/oc/fig-4.4.png, figures/oc/fig-4.5.png.
"""
# %% [markdown]
# In the cellular-automaton method the sky is a grid of cells, each holding three bits: **hum** (there is vapour),
# **act** (a phase transition may happen here) and **cld** (there is cloud). Rules applied to all cells at once move
# the bits from step to step -- vapour becomes activated, activated cells become cloud -- and because the states are
# bits, a whole row of cells is updated with a few bitwise operations. The text lists the variables but not the
# rules; fig. 4.5 runs the published rules of Dobashi et al. (marked as beyond the text). For rendering, the one-bit
# cloud is turned into a continuous density by averaging over neighbouring cells.

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


# %% [markdown]
# **The simulation process (beyond the text).** Dobashi et al.'s rules: vapour that is activated leaves hum, activated
# cells become cloud, and a humid cell becomes activated when an activated cell is near it (sideways, or below it: the
# rising air). Alone these rules only grow the cloud; the extension adds random extinction of cloud cells and random
# supply of vapour and activation, with probabilities that an ellipsoid sets, so the cloud forms, lives and decays
# inside it.

# %%
CA_SHAPE = (64, 32, 32)  # x, y (depth), z (up) cells of the simulation
CA_OFFSETS = ((1, 0, 0), (-1, 0, 0), (2, 0, 0), (-2, 0, 0), (0, 1, 0), (0, -1, 0), (0, 2, 0), (0, -2, 0), (0, 0, -1),
              (0, 0, -2))  # f_act: act at (i, j, k) + offset (k - 1, k - 2: below)


def shifted(a: np.ndarray, offset) -> np.ndarray:
    """a at (i, j, k) + offset, False beyond the grid."""
    out = np.zeros_like(a)
    src = tuple(slice(max(o, 0), n + min(o, 0)) for o, n in zip(offset, a.shape))
    dst = tuple(slice(max(-o, 0), n + min(-o, 0)) for o, n in zip(offset, a.shape))
    out[dst] = a[src]
    return out


def probabilities():
    """(p_hum, p_act, p_ext) per cell from the ellipsoid (see the module docstring)."""
    x, y, z = np.meshgrid(*((np.arange(n) + 0.5) / n for n in CA_SHAPE), indexing="ij")
    q = ((x - 0.5) / 0.4) ** 2 + ((y - 0.5) / 0.3) ** 2 + ((z - 0.35) / 0.35) ** 2
    inside = q < 1.0
    return (np.where(inside, 0.02 * (1 - q), 0.0), np.where(inside, 0.002 * (1 - q), 0.0),
            np.where(inside, 0.1 * q, 1.0))


def simulate(steps, seed: int = 4):
    """The automaton's (hum, act, cld) at each of ``steps`` (increasing): Dobashi et al.'s rules with extinction."""
    rng = np.random.default_rng(seed)
    p_hum, p_act, p_ext = probabilities()
    hum = (rng.random(CA_SHAPE) < 0.4) & (p_ext < 1.0)
    act = np.zeros(CA_SHAPE, bool)
    cld = np.zeros(CA_SHAPE, bool)
    out = []
    for t in range(max(steps) + 1):
        if t in steps:
            out.append((hum.copy(), act.copy(), cld.copy()))
        f_act = np.zeros(CA_SHAPE, bool)
        for o in CA_OFFSETS:
            f_act |= shifted(act, o)
        hum, cld, act = hum & ~act, cld | act, ~act & hum & f_act
        cld &= rng.random(CA_SHAPE) > p_ext
        hum |= rng.random(CA_SHAPE) < p_hum
        act |= rng.random(CA_SHAPE) < p_act
    return out


def seen(cld: np.ndarray) -> np.ndarray:
    """The cloud seen along y: cld averaged over 3 x 3 x 3 neighbours (the continuous density), summed along y as an
    optical depth, 1 - exp(-depth) (x, z)."""
    smooth = sum(shifted(cld.astype(float), (i, j, k)) for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1))
    return 1.0 - np.exp(-0.15 * (smooth / 27.0).sum(axis=1))


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

    # fig. 4.5: the simulation process (Dobashi et al. 2000; beyond the text)
    steps = (0, 4, 10, 20, 40)
    frames = simulate(steps)
    fig, axes = plt.subplots(2, len(steps), figsize=(12, 3.8), dpi=dpi)
    for c, (t, (hum_t, act_t, cld_t)) in enumerate(zip(steps, frames)):
        j = CA_SHAPE[1] // 2  # the vertical slice through the middle
        rgb = np.zeros((CA_SHAPE[2], CA_SHAPE[0], 3))
        rgb[hum_t[:, j, :].T] = (0.35, 0.55, 0.85)
        rgb[act_t[:, j, :].T] = (0.95, 0.55, 0.15)
        rgb[cld_t[:, j, :].T] = (0.97, 0.97, 0.97)
        axes[0, c].imshow(rgb, origin="lower", interpolation="nearest")
        axes[0, c].set_title(f"step {t}: {int(cld_t.sum())} cloud cells", fontsize=8)
        axes[1, c].imshow(seen(cld_t).T, cmap="Greys_r", vmin=0, vmax=1, origin="lower")
        for ax in axes[:, c]:
            ax.set_xticks([])
            ax.set_yticks([])
    axes[0, 0].set_ylabel("slice: cld white,\nact orange, hum blue", fontsize=8)
    axes[1, 0].set_ylabel("cloud seen through\nthe grid (smoothed cld)", fontsize=8)
    fig.suptitle("(a) simulation process: Dobashi et al. 2000's transition rules with extinction (beyond the text: "
                 "it cites them, does not print them)", fontsize=9)
    fig.tight_layout()
    p45 = out_dir / "fig-4.5.png"
    fig.savefig(p45, dpi=dpi)
    plt.close(fig)
    return [p44, p45]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
