"""Figure vc-fig-2.8: fBm of noises -- (a) Worley, (b) inverse Worley, (c) Perlin.

Fractional Brownian motion (vc-2.21) with the octave rules of vc-A6 (f_i = 2 f_{i-1}, w_i = w_{i-1} / 2, normalised by
the sum of the weights): pywarp.noise_fbm_worley3 (classic and inverse, 4 cells per unit at octave 0, seed 5) and
pywarp.noise_fbm_perlin3 (frequency 4, seed 0), 5 octaves, slice z = 0.3 of the 3-D noises, 256 x 256 pixels. The
thesis states neither the octave count nor the base frequency. The top row (not in the thesis) shows octave 0 alone
for comparison. Output: figures/vc/fig-2.8.png.
"""
# %% [markdown]
# One noise octave has one characteristic feature size: the cell size of Worley noise, the lattice spacing of
# Perlin noise. Natural shapes such as clouds have detail at many scales at once. fBm (2.21) sums copies of the same
# noise, each at twice the frequency and half the weight of the previous one:
#
#     N_s(x) = sum_i w_i N(f_i x),   f_i = 2 f_(i-1),   w_i = w_(i-1) / 2
#
# Each copy is an "octave". The coarse octave keeps the large-scale shape (compare with the top row), the finer ones
# add progressively weaker detail. Dividing by the sum of the weights keeps the result in the range of one octave;
# averaging independent octaves also pulls the values towards the middle, so the fBm has less contrast (see the
# colour bars; each image is stretched to its own range). fBm of inverse Worley noise gives the soft, billowy
# shapes of cumulus clouds -- the detail and base textures of the thesis are built from it.

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
    n = 96 if quick else 256
    octaves, cells, worley_seed = 5, 4, 5
    frequency, perlin_seed, z = 4.0, 0, 0.3
    u = (np.arange(n) + 0.5) / n  # pixel centres in [0, 1]
    x, y = np.meshgrid(u, u)

    # %% [markdown]
    # The library evaluates the whole sum per pixel (Warp, CPU). Worley fBm: octave i has cells 2^i cells per unit
    # and seed + i; Perlin fBm: octave i has frequency 2^i frequency. Perlin values are shown as 0.5 n + 0.5.

    # %%
    def rows(k):
        worley = pywarp.noise_fbm_worley3(x, y, z, k, cells, worley_seed)
        inverse = pywarp.noise_fbm_worley3(x, y, z, k, cells, worley_seed, inverse=True)
        perlin = 0.5 * pywarp.noise_fbm_perlin3(x, y, z, k, frequency, perlin_seed) + 0.5
        return worley, inverse, perlin

    single, fbm = rows(1), rows(octaves)
    # one octave of the fBm is the plain noise
    assert np.array_equal(single[0], pywarp.noise_worley3(x, y, z, cells, worley_seed))

    titles = ("(a) Worley", "(b) inverse Worley", "(c) Perlin")
    fig, axes = plt.subplots(2, 3, figsize=(13, 8.8), dpi=80 if quick else 110)
    for i, (row, label) in enumerate(((single, "octave 0 alone"), (fbm, f"fBm, {octaves} octaves (2.21)"))):
        for j, img in enumerate(row):
            ax = axes[i, j]
            im = ax.imshow(img, cmap="gray", vmin=float(img.min()), vmax=float(img.max()), origin="lower",
                           extent=(0, 1, 0, 1), interpolation="nearest")
            fig.colorbar(im, ax=ax, fraction=0.046, pad=0.02).ax.tick_params(labelsize=7)
            ax.set_title(f"{titles[j]}: {label}", fontsize=10)
            ax.set_xticks([])
            ax.set_yticks([])
    fig.suptitle(f"fBm of noises (vc-2.21, vc-A6): f_i = 2 f_(i-1), w_i = w_(i-1)/2, divided by Σ w_i; "
                 f"slice z = {z}, {n}² px\nWorley: {cells} cells per unit at octave 0, seed {worley_seed}; "
                 f"Perlin: frequency {frequency:g}, seed {perlin_seed}; each image stretched to its own range",
                 fontsize=11)
    fig.subplots_adjust(left=0.02, right=0.97, bottom=0.02, top=0.88, wspace=0.12, hspace=0.14)
    out = out_dir / "fig-2.8.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
