"""Figure oc-fig-5.6: converting raw noise to smoothed noise, then to the final resolution with bilinear
interpolation.

Raw 16 x 16 lattice noise (oc-5.1.2, seed 4) -> smoothed by neighbour averaging (oc-5.1.3) -> up-sampled to
256 x 256 by bilinear interpolation (oc-5.1.4, oc-5.1.4.1). The text does not say which neighbours are averaged
(erratum 4): row 1 uses Elias's weights (corners/16 + sides/8 + centre/4, the default), row 2 the plain mean of the
4 side neighbours and of all 8 neighbours, and the cosine-interpolated version (oc-5.1.4.2) for comparison.
Output: figures/oc/fig-5.6.png.
"""
# %% [markdown]
# Raw lattice noise has no relation between neighbouring values -- a jagged signal. Replacing each value by an
# average over its neighbourhood ties neighbours together (and lowers the contrast: an average of independent values
# spreads less). Interpolation then fills the pixels between the lattice points; bilinear interpolation shows the
# lattice as faint creases, the cosine curve hides them better.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.tutorial import fit_text  # noqa: E402


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    cells, size = 16, (64 if quick else 256)
    j, i = np.mgrid[0:cells, 0:cells]
    u = np.arange(size, dtype=np.float32) * np.float32(cells / size)
    xx, yy = np.meshgrid(u, u)

    # %% [markdown]
    # Lattice values at the 16 x 16 cells (shown enlarged, one flat square per value), their smoothed versions, and
    # the interpolated image at 256 x 256 -- evaluated by pywarp.valuenoise_interpolated at the pixel positions.

    # %%
    raw = pywarp.valuenoise_lattice(i, j, 0, 4)
    smooth = {k: pywarp.valuenoise_smooth(i, j, 0, 4, 2, smoothing=k) for k in ("elias", "4-neighbour",
                                                                                "8-neighbour")}
    bilinear = pywarp.valuenoise_interpolated(xx, yy, 0.0, 4, 2, smoothing="elias", interpolation="linear")
    cosine = pywarp.valuenoise_interpolated(xx, yy, 0.0, 4, 2, smoothing="elias", interpolation="cosine")
    # at the lattice points the interpolated image is the smoothed value
    step = size // cells
    assert np.array_equal(bilinear[::step, ::step], smooth["elias"])

    panels = [[(raw, "raw noise 16 x 16"), (smooth["elias"], "smoothed: Elias weights"),
               (bilinear, "bilinear -> 256 x 256")],
              [(smooth["4-neighbour"], "smoothed: mean of 4 sides"),
               (smooth["8-neighbour"], "smoothed: mean of 8 neighbours"),
               (cosine, "Elias + cosine -> 256 x 256")]]
    fig, axes = plt.subplots(2, 3, figsize=(11, 7.8), dpi=80 if quick else 110)
    for r in range(2):
        for c in range(3):
            img, title = panels[r][c]
            axes[r, c].imshow(img, cmap="gray", vmin=0, vmax=1, interpolation="nearest")
            axes[r, c].set_title(f"{title}  (std {img.std():.3f})", fontsize=9)
            axes[r, c].axis("off")
    fig.suptitle("oc fig. 5.6: raw noise -> smoothed noise -> final resolution (bilinear)", fontsize=11)
    fit_text(fig, tight_layout=True)  # the layout, with titles and labels that fit (legible in quick mode)
    out = out_dir / "fig-5.6.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
