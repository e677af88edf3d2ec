"""Figure oc-fig-5.1: 1-D "Perlin noise" -- noise functions of increasing frequency and decreasing amplitude, and their
sum ("Sum of Noise Functions = (Perlin Noise)").

Each octave i is the 1-D value noise of the text (oc-5.1.2 lattice hash, oc-5.1.3 smoothing with Elias's weights,
oc-5.1.4.2 cosine interpolation) at frequency 2^i (oc-5.1.2.1), weighted by its amplitude (oc-5.1.2.2); the bottom
panel is the normalised octave sum oc-5.1.1 (pywarp.valuenoise_fbm, 6 octaves, persistence 0.5, seed 3 -- the text
gives no values) for both persistence schedules: the corrected p^i and the printed squaring p^(2^i) (erratum 3).
Output: figures/oc/fig-5.1.png.
"""
# %% [markdown]
# Value noise in 1-D is a row of random numbers at the integers, joined by a smooth curve. An *octave* is one such
# curve; the next octave has twice the frequency (twice as many random values per unit) and, weighted by the
# *persistence*, a smaller amplitude. Summing the octaves gives a curve with large-scale shape and fine detail at
# once -- what the text (after Hugo Elias) calls "Perlin noise". (Perlin's own noise interpolates random
# *gradients*, not values; this is value noise.)
#
# The text prints the persistence update as `Persistence = persistence * Persistence`. Read literally with one
# variable it squares the weight every octave (p, p^2, p^4, ...) and the fine octaves vanish almost at once; the
# tutorial it follows means amplitude_i = p^i. The bottom panel shows both.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.kernels.valuenoise import octave_seed  # noqa: E402  (the seed of octave i: pcg(seed) + i)

SEED, OCTAVES, PERSISTENCE = 3, 6, 0.5


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    x = np.linspace(0.0, 8.0, 400 if quick else 2000, dtype=np.float32)

    # %% [markdown]
    # Octave i: the interpolated smoothed lattice (oc-5.1.4) at 2^i x with its own seed, times a_i. The sum divides by
    # sum a_i so that it stays in [0, 1] like one octave.

    # %%
    amps = pywarp.valuenoise_amplitude(np.arange(OCTAVES), PERSISTENCE)
    layers = [pywarp.valuenoise_interpolated(x * 2.0 ** i, 0.0, 0.0, octave_seed(SEED, i), 1,
                                             interpolation="cosine") for i in range(OCTAVES)]
    total = pywarp.valuenoise_fbm(x, 0.0, 0.0, SEED, 1, OCTAVES, PERSISTENCE, interpolation="cosine")
    thesis = pywarp.valuenoise_fbm(x, 0.0, 0.0, SEED, 1, OCTAVES, PERSISTENCE, interpolation="cosine",
                                   variant="thesis")
    ref = sum(a * v.astype(np.float64) for a, v in zip(amps, layers)) / amps.sum()
    assert np.allclose(total, ref, atol=1e-6)

    fig = plt.figure(figsize=(13, 7.5), dpi=80 if quick else 120)
    gs = fig.add_gridspec(3, OCTAVES // 2 if OCTAVES % 2 == 0 else OCTAVES, height_ratios=(1, 1, 1.4))
    for i in range(OCTAVES):
        ax = fig.add_subplot(gs[i // 3, i % 3])
        ax.plot(x, amps[i] * layers[i], color=f"C{i}", lw=1.2)
        ax.set_ylim(0, 1)
        ax.set_xlim(0, 8)
        ax.set_title(f"octave {i}: frequency {2 ** i}, amplitude {amps[i]:g}", fontsize=9)
        ax.tick_params(labelsize=7)
    ax = fig.add_subplot(gs[2, :])
    ax.plot(x, total, color="k", lw=1.4, label=f"sum, amplitude p^i (corrected), p = {PERSISTENCE}")
    ax.plot(x, thesis, color="C3", lw=1.1, ls="--", label="sum, amplitude p^(2^i) (the printed squaring)")
    ax.set_xlim(0, 8)
    ax.set_ylim(0, 1)
    ax.set_xlabel("x (lattice units of octave 0)")
    ax.legend(loc="upper right", fontsize=8, frameon=False)
    ax.set_title("Sum of noise functions = \"Perlin noise\" (normalised by the sum of the amplitudes)", fontsize=10)
    fig.suptitle("oc fig. 5.1: 1-D value noise, octaves and their sum (cosine interpolation, Elias smoothing, "
                 f"seed {SEED})", fontsize=11)
    fig.tight_layout()
    out = out_dir / "fig-5.1.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
