"""Figure oc-fig-5.5: different noises for different input parameters -- 2-D octave sums for several persistences and
octave counts, with both persistence schedules.

pywarp.valuenoise_fbm (oc-5.1.1, oc-5.1.2.1, oc-5.1.2.2) over 2-D value noise (oc-5.1.2, Elias smoothing oc-5.1.3,
cosine interpolation oc-5.1.4.2), 4 lattice cells across the image at octave 0, seed 2 (the text gives no parameter
values). Row 1: persistence 0.25 - 1 with amplitude p^i (corrected); row 2: the same with the printed squaring
p^(2^i) (erratum 3); row 3: 1, 2, 4 and 6 octaves at p = 0.5. Output: figures/oc/fig-5.5.png.
"""
# %% [markdown]
# The persistence is the ratio of the amplitudes of successive octaves. At p = 1 every octave counts as much as the
# first and the fine octaves drown the shape in grain; lowering it -- the text's observation -- leaves the large
# shape with a little detail on top. The number of octaves decides how fine the finest detail is ("generally 6 is
# enough"). With the printed listing (the weight squared every octave) the detail fades after two or three octaves
# whatever the persistence: compare rows 1 and 2.

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
    n = 64 if quick else 192
    u = np.arange(n, dtype=np.float32) * np.float32(4.0 / n)
    xx, yy = np.meshgrid(u, u)

    # %%
    def noise(octaves, p, variant="corrected"):
        return pywarp.valuenoise_fbm(xx, yy, 0.0, 2, 2, octaves, p, interpolation="cosine", variant=variant)

    rows = [[(noise(6, p), f"p = {p}, 6 octaves") for p in (0.25, 0.5, 0.75, 1.0)],
            [(noise(6, p, "thesis"), f"p = {p}, printed p^(2^i)") for p in (0.25, 0.5, 0.75, 1.0)],
            [(noise(k, 0.5), f"p = 0.5, {k} octave{'s' if k > 1 else ''}") for k in (1, 2, 4, 6)]]
    fig, axes = plt.subplots(3, 4, figsize=(12, 9.6), dpi=80 if quick else 110)
    for r, row in enumerate(rows):
        for c, (img, title) in enumerate(row):
            ax = axes[r, c]
            lo, hi = float(img.min()), float(img.max())
            ax.imshow((img - lo) / max(hi - lo, 1e-6), cmap="gray", vmin=0, vmax=1)
            ax.set_title(title, fontsize=9)
            ax.axis("off")
    fig.text(0.01, 0.80, "amplitude p^i", rotation=90, fontsize=10, va="center")
    fig.text(0.01, 0.50, "as printed: p^(2^i)", rotation=90, fontsize=10, va="center")
    fig.text(0.01, 0.18, "octave count", rotation=90, fontsize=10, va="center")
    fig.suptitle("oc fig. 5.5: noises for different persistence and octave counts (each image stretched to its "
                 "range)", fontsize=11)
    fig.tight_layout(rect=(0.02, 0, 1, 0.965))  # the top 3.5 % for the suptitle: clear of the first row's titles
    out = out_dir / "fig-5.5.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
