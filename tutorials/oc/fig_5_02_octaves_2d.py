"""Figure oc-fig-5.2: "Perlin noise" in a 2-D array -- layers from 16 x 16 to 256 x 256, each up-sampled bilinearly
to the final resolution, and their sum.

The text's procedure (oc-5.1.1): start with a 16 x 16 image, double the frequency (oc-5.1.2.1) and the resolution up
to 256 x 256 (16, 32, 64, 128, 256: 5 layers), interpolate every layer to 256 x 256 with bilinear interpolation
(oc-5.1.4, oc-5.1.4.1), weight by the persistence (oc-5.1.2.2, p = 0.5 -- the text gives none) and sum.
pywarp.flight.clouds.octave_image does exactly this with the lattice noise of oc-5.1.2 smoothed by Elias's
weights (oc-5.1.3), seed 7. The last panel is the printed persistence squaring (erratum 3). Output:
figures/oc/fig-5.2.png.
"""
# %% [markdown]
# In 2-D the text builds the octaves as images: a coarse 16 x 16 image of smoothed random values gives the basic
# shape, each further layer has twice the resolution and adds finer detail. Every layer is brought to the final
# 256 x 256 by bilinear interpolation -- one lattice cell of the 16 x 16 layer covers 16 x 16 pixels, so the first
# layer is a soft blur, the last one changes from pixel to pixel -- and the layers are summed with weights p^i.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.flight.clouds import octave_image  # noqa: E402  (the 2-D layer procedure of §5.1.1)
from pywarp.tutorial import fit_text  # noqa: E402


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size, base = (64, 4) if quick else (256, 16)  # quick: the same 5 layers at a quarter of the size

    # %% [markdown]
    # The layers (unweighted, each in [0, 1]) and their weighted sum, normalised by the sum of the weights.

    # %%
    layers, amps, total = octave_image(size=size, base=base, octaves=5, persistence=0.5, seed=7)
    _, _, thesis = octave_image(size=size, base=base, octaves=5, persistence=0.5, seed=7, variant="thesis")
    # the sum is the octave sum oc-5.1.1 at the pixel's lattice coordinate
    px = np.arange(size, dtype=np.float32) * np.float32(base) / np.float32(size)
    xx, yy = np.meshgrid(px, px)
    assert np.allclose(total, pywarp.valuenoise_fbm(xx, yy, 0.0, 7, 2, 5, 0.5), atol=1e-6)

    fig, axes = plt.subplots(2, 4, figsize=(13, 7), dpi=80 if quick else 110)
    panels = [(lay, f"layer {i}: {base * 2 ** i} x {base * 2 ** i} -> {size} x {size}, weight {a:g}")
              for i, (lay, a) in enumerate(zip(layers, amps))]
    panels += [(total, "sum (weights p^i, p = 0.5)"), (thesis, "sum, printed squaring p^(2^i)")]
    for ax, (img, title) in zip(axes.ravel(), panels):
        ax.imshow(img, cmap="gray", vmin=0, vmax=1, interpolation="nearest")
        ax.set_title(title, fontsize=8.5)
    for ax in axes.ravel():
        ax.axis("off")
    fig.suptitle("oc fig. 5.2: \"Perlin noise\" in a 2-D array: bilinearly up-sampled layers and their sum", fontsize=11)
    fit_text(fig, tight_layout=True)  # the layout, with titles and labels that fit (legible in quick mode)
    out = out_dir / "fig-5.2.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
