"""Figure pt-fig-3.3: textures from modifications of the noise domain, f(x) = p(x), p(x + p(x)), p(x + p(x + p(x))).

Both readings of the caption (pt-u-warp): the scalar offset as printed (variant "thesis": p(x) added to both
coordinates) and Quilez's vector offsets (variant "corrected", strength 4), after basic Perlin noise (pt-alg-3.1) and its
fBm (pt-alg-3.2, 6 octaves). Scale, octaves and colours are not given in the text: p on (-3, 3)^2, one colour map for
all panels. Output: figures/pt/fig-3.3.png.
"""
# %% [markdown]
# Domain warping evaluates the noise not at x but at a point moved by the noise itself. The caption writes the offset
# as p(x): a single number, so literally the point moves along the diagonal (1, 1) only -- the "thesis" row. Quilez,
# whom the caption cites, moves the point by a 2-D vector made of two differently offset fBm evaluations (and scales
# it by 4), which bends the pattern in every direction -- the "corrected" row.

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
    n, octaves = (80 if quick else 256), 6
    u = ((np.arange(n) + 0.5) / n * 2 - 1) * 3.0
    p = np.stack(np.meshgrid(u, u), -1).astype(np.float32)
    basic = pywarp.perlin2(p[..., 0], p[..., 1])
    rows = {}
    for variant, strength in (("thesis", 1.0), ("corrected", 4.0)):
        rows[variant] = [pywarp.draw_warp(p, d, octaves, strength, variant=variant) for d in range(3)]
    fig, axes = plt.subplots(2, 4, figsize=(14, 7.4), dpi=70 if quick else 100)
    titles = ("f = p(x) (fBm)", "f = p(x + p(x))", "f = p(x + p(x + p(x)))")
    for r, (variant, label) in enumerate((("thesis", "scalar offset as printed, s = 1"),
                                          ("corrected", "Quilez's vector offsets, s = 4"))):
        ax = axes[r, 0]
        if r == 0:
            ax.imshow(basic, origin="lower", cmap="magma", vmin=-1, vmax=1)
            ax.set_title("1. basic Perlin noise", fontsize=10)
        else:
            ax.axis("off")
            ax.text(0.0, 0.5, "variant = 'corrected':\nvector offsets\nq = (fBm(x), fBm(x + (5.2, 1.3)))\n"
                    "f = fBm(x + 4 q), ...", fontsize=10, va="center")
        for k in range(3):
            ax = axes[r, k + 1]
            ax.imshow(rows[variant][k], origin="lower", cmap="magma", vmin=-1.6, vmax=1.6)
            ax.set_title(f"{k + 2}. {titles[k]}\n{variant}: {label}", fontsize=9)
        for ax in axes[r]:
            ax.set_xticks([])
            ax.set_yticks([])
    fig.suptitle("Domain warping (pt-u-warp) of the demo's fBm (pt-alg-3.2, 6 octaves), p in (-3, 3)^2. Top: the caption "
                 "read literally (p(x) is a number, added to both coordinates);\nbottom: Quilez's domain warping that the "
                 "caption cites (2-D offsets): the printed formula only shears the pattern along the diagonal.",
                 fontsize=10)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.02, top=0.86, wspace=0.05, hspace=0.22)
    out = out_dir / "fig-3.3.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
