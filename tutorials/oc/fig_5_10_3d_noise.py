"""Figure oc-fig-5.10: creation of 3-D noise -- a size/8 array of random noise, interpolated up level by level with new
noise of lower amplitude added, until the full size.

The cloud array of oc-5.2.1 (pywarp.flight.clouds.noise_volume, 64^3, 4 levels 8 -> 16 -> 32 -> 64, trilinear
up-sampling, persistence 0.5 (oc-5.1.2.2), Elias smoothing (oc-5.1.3), zero border (oc-5.2.3.2), seed 1 -- the text
gives no values). Top row: the middle slice (z = size/2) of the array after each level; bottom row: the noise added
at that level, a_l N_l (pywarp.valuenoise_smooth). Output: figures/oc/fig-5.10.png.
"""
# %% [markdown]
# The cloud is a 3-D array of opacities. It starts as a small array (size/8 per axis) of random values -- the cloud's
# basic shape. Each step doubles the resolution by interpolation and adds new random values with a smaller
# amplitude, which put finer detail on the shape. Because each level of the pyramid uses the level seed of the octave
# sum (pcg(seed) + l), the array after level l is the same whatever the final size: a 4-level build of 64^3 passes
# through the 2-level build of 16^3.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.kernels.valuenoise import octave_seed  # noqa: E402
from pywarp.flight.clouds import CloudArraySettings, noise_volume  # noqa: E402

SEED = 1


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = 32 if quick else 64
    base = CloudArraySettings(size=size, seed=SEED)

    # %%
    stages, added = [], []
    for lvl, n in enumerate(base.level_sizes()):
        # the array after level l: the same build stopped at edge n (l + 1 levels), before the filter
        vol = noise_volume(base, size=n, levels=lvl + 1)
        stages.append(vol[n // 2])
        a = pywarp.valuenoise_amplitude(lvl, base.persistence)
        yy, xx = np.mgrid[0:n, 0:n]
        noise = a * pywarp.valuenoise_smooth(xx, yy, n // 2, octave_seed(SEED, lvl), 3)
        noise[[0, -1], :] = 0.0
        noise[:, [0, -1]] = 0.0  # the zero border of the larger array
        added.append(noise)

    fig, axes = plt.subplots(2, len(stages), figsize=(3.2 * len(stages), 6.6), dpi=80 if quick else 110)
    for lvl, (s, a) in enumerate(zip(stages, added)):
        n = s.shape[0]
        axes[0, lvl].imshow(s, cmap="gray", vmin=0, vmax=0.8, interpolation="nearest")
        axes[0, lvl].set_title(f"level {lvl}: {n}^3" + (" (size/8)" if lvl == 0 else " = interpolate x2 + noise"),
                               fontsize=9)
        axes[1, lvl].imshow(a, cmap="magma", vmin=0, vmax=1, interpolation="nearest")
        axes[1, lvl].set_title(f"noise added: amplitude {pywarp.valuenoise_amplitude(lvl, 0.5):g}", fontsize=9)
    for ax in axes.ravel():
        ax.axis("off")
    fig.suptitle(f"oc fig. 5.10: creation of 3-D noise, size/8 -> size ({size}^3), middle slice of each level",
                 fontsize=11)
    fig.tight_layout()
    out = out_dir / "fig-5.10.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
