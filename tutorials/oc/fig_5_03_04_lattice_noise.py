"""Figures oc-fig-5.3 and oc-fig-5.4: the random number generator of value noise -- a deterministic function of
non-negative integers (oc-5.1.2) -- in 1-D (fig. 5.3: integer argument against the value) and in 2-D as a greyscale
image ("pure" noise, fig. 5.4).

pywarp.valuenoise_lattice: the project's PCG hash of the lattice point and the seed (the text gives no generator),
seed 1. The text states the range both as -1..1 and as 0..1 (erratum 2): fig. 5.3 shows both, [0, 1] being the
default (the cloud filter oc-5.2.2 multiplies by 255). Outputs: figures/oc/fig-5.3.png, figures/oc/fig-5.4.png.
"""
# %% [markdown]
# The core of value noise is a function that takes integers and returns a "random" number -- the same number every
# time it gets the same integers. Plotted against a 1-D integer argument (read as elapsed time) it is a row of
# unrelated values; in 2-D every pixel (x, y) gets its own value, the "scattered tea" of fig. 5.4. Smoothing
# (fig. 5.6) and interpolation (figs. 5.7 - 5.9) turn it into a continuous noise.

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
    x = np.arange(32)

    # %%
    unit = pywarp.valuenoise_lattice(x, 0, 0, 1)
    signed = pywarp.valuenoise_lattice(x, 0, 0, 1, value_range="signed")
    assert np.array_equal(signed, 2 * unit - 1)
    fig, axes = plt.subplots(1, 2, figsize=(12, 3.8), dpi=80 if quick else 120)
    for ax, v, lo, title in ((axes[0], unit, 0.0, "range [0, 1] (default)"),
                             (axes[1], signed, -1.0, "range [-1, 1] (value_range='signed')")):
        ax.vlines(x, lo if lo == 0 else 0, v, color="C0", lw=1.5)
        ax.plot(x, v, "o", color="C0", ms=5)
        ax.set_ylim(lo, 1)
        ax.axhline(0, color="0.5", lw=0.8)
        ax.set_xlabel("integer argument x (\"elapsed time\")")
        ax.set_ylabel("noise(x)")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3)
    fig.suptitle("oc fig. 5.3: random number generator -- the same x always gives the same value (seed 1)",
                 fontsize=11)
    fig.tight_layout()
    out1 = out_dir / "fig-5.3.png"
    fig.savefig(out1)
    plt.close(fig)

    # %% [markdown]
    # Fig. 5.4: every pixel gets the value of its own lattice point, shown as grey levels.

    # %%
    n = 96 if quick else 256
    yy, xx = np.mgrid[0:n, 0:n]
    img = pywarp.valuenoise_lattice(xx, yy, 0, 1)
    fig, ax = plt.subplots(figsize=(5.2, 5.6), dpi=80 if quick else 120)
    ax.imshow(img, cmap="gray", vmin=0, vmax=1, interpolation="nearest")
    ax.set_title(f"oc fig. 5.4: \"pure\" noise, {n} x {n}, one value per pixel", fontsize=10)
    ax.axis("off")
    fig.tight_layout()
    out2 = out_dir / "fig-5.4.png"
    fig.savefig(out2)
    plt.close(fig)
    return [out1, out2]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
