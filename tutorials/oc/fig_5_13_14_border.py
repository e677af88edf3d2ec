"""Figures oc-fig-5.13 and oc-fig-5.14: why the filtered cloud shows the edges of its box, and the larger array that
removes them.

Fig. 5.13 (oc-5.2.3): one row of pixels up-sampled 4 -> 8 -> 16 -> 32 by linear interpolation with corners aligned
(the up-sampling of the cloud array, oc-5.2.1; oc-5.1.4.1 as the blend): the random border pixel "1" is carried
toward the interior, and the end of the row keeps a non-zero value -- nothing lies beyond it to interpolate toward.
With a zero border cell (the larger array, oc-5.2.3.2) the row falls to 0 at both ends. Fig. 5.14 (oc-5.2.3.2): the
scheme on the middle slices of a real build (pywarp.flight.clouds.noise_volume, 32^3, 4 levels, seed 5): the border
cells of every level (outlined) stay 0 and are never filled, neither by interpolation nor by the added noise.
Outputs: figures/oc/fig-5.13.png, figures/oc/fig-5.14.png.
"""
# %% [markdown]
# Interpolation refines the array toward its interior, but at the edge of the array there is nothing to interpolate
# toward: the outermost value of the coarse array lands on the outermost voxel of every finer array. A random,
# non-zero border value therefore survives to the full resolution and -- after the filter -- the cloud is cut flat by
# the faces of its box (fig. 5.12). The remedy the text adopts is to keep a border of zeros at every level: the
# array is larger than the cloud, and the cloud can fall off to zero on every side (fig. 5.15).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.flight.clouds import CloudArraySettings, noise_volume  # noqa: E402


def _upsample_row(row, n):
    """Corner-aligned linear up-sampling of a row to n samples, blended with the printed Linear_Interp."""
    m = row.size
    pos = np.arange(n) * (m - 1) / (n - 1)
    i0 = np.minimum(pos.astype(int), m - 2)
    return np.asarray(pywarp.valuenoise_linear(row[i0], row[i0 + 1], (pos - i0).astype(np.float32)))


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)

    # %% [markdown]
    # Fig. 5.13: a row of 4 random pixels (lattice noise, seed 2), pixel 1 at the left border; up-sampled three times.
    # Without a border the left end keeps pixel 1's value; with a zero border cell the interior is the same noise and
    # the ends are 0.

    # %%
    raw = pywarp.valuenoise_lattice(np.arange(6), 0, 0, 2).astype(np.float32)
    raw[0] = 0.9  # pixel "1": a bright random value at the border
    bordered = raw.copy()
    bordered[[0, -1]] = 0.0  # the larger array: noise only inside, the border cells stay 0
    fig, axes = plt.subplots(2, 1, figsize=(11, 5.6), dpi=80 if quick else 120)
    for ax, row, title in ((axes[0], raw, "no border: pixel 1 stays on the edge of the array"),
                           (axes[1], bordered, "zero border cells at both ends (larger array): the row falls to 0")):
        rows = [row]
        for _ in range(3):
            rows.append(_upsample_row(rows[-1], 2 * rows[-1].size))
        for k, r in enumerate(rows):
            x = np.linspace(0, 1, r.size)
            off = 1.2 * (len(rows) - 1 - k)
            ax.plot(x, r + off, "-o", ms=6 - k, lw=1, color=f"C{k}", label=f"{r.size} pixels")
            ax.axhline(off, color="0.8", lw=0.6)
        if row is raw:
            ax.annotate("1", (0, rows[0][0] + 3.6), textcoords="offset points", xytext=(-14, -4), fontsize=12,
                        color="C3")
        ax.set_yticks([])
        ax.set_xlabel("position along the row (0 = border)")
        ax.set_title(title, fontsize=10)
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8, frameon=False)
    fig.suptitle("oc fig. 5.13: interpolation on a row of pixels -- the border pixel propagates inward", fontsize=11)
    fig.tight_layout()
    out1 = out_dir / "fig-5.13.png"
    fig.savefig(out1)
    plt.close(fig)

    # %% [markdown]
    # Fig. 5.14: the middle slice of each level of a 32^3 zero-border build; the outlined frame is the border, 0 at
    # every level.

    # %%
    s = CloudArraySettings(size=32, seed=5)
    fig, axes = plt.subplots(1, 4, figsize=(13, 3.8), dpi=80 if quick else 110)
    for lvl, (ax, n) in enumerate(zip(axes, s.level_sizes())):
        sl = noise_volume(s, size=n, levels=lvl + 1)[n // 2]
        assert np.all(sl[[0, -1], :] == 0) and np.all(sl[:, [0, -1]] == 0)
        ax.imshow(sl, cmap="gray", vmin=0, vmax=0.8, interpolation="nearest")
        ax.add_patch(plt.Rectangle((-0.5, -0.5), n, n, fill=False, ec="C3", lw=2.5))
        ax.add_patch(plt.Rectangle((0.5, 0.5), n - 2, n - 2, fill=False, ec="C3", lw=1, ls="--"))
        ax.set_title(f"level {lvl}: {n} x {n}, border = 0", fontsize=9)
        ax.axis("off")
    fig.suptitle("oc fig. 5.14: removing the edges with a larger array (border cells 0 at every level, outlined)",
                 fontsize=11)
    fig.tight_layout()
    out2 = out_dir / "fig-5.14.png"
    fig.savefig(out2)
    plt.close(fig)
    return [out1, out2]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
