"""Figure pt-fig-3.6: textures of the sine function, fBm, and their combination (marble).

Kod 3.2 (pt-code-3.2, pywarp.draw_marble): sine = (1 + sin(50 p.x)) / 2, fbm = fBm(5 p) with the demo's fBm (pt-alg-3.2,
5 octaves -- the count is not printed), combination = (1 + sin((p.x + fbm / 2) 50)) / 2, on the centred coordinates of
pt-alg-3.3 in a 512 x 512 window. Output: figures/pt/fig-3.6.png.
"""
# %% [markdown]
# A sine of x alone gives straight stripes. Adding half the fBm to x before the sine shifts each stripe sideways by
# the noise, so the stripes meander like the veins of marble. The fBm itself is shown as grey levels 0.5 + fbm / 4.

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
    n = 128 if quick else 512
    f = np.arange(n) + 0.5
    frag = np.stack(np.meshgrid(f, f), -1)
    _, p, _ = pywarp.draw_coords(frag, [n, n])
    sine, fbm, comb = pywarp.draw_marble(p, 5)
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.7), dpi=70 if quick else 100)
    for ax, img, title in zip(axes, (sine, 0.5 + fbm / 4.0, comb),
                              ("sine = (1 + sin(50 p.x)) / 2", "fBm(5 p), 5 octaves (shown 0.5 + fbm/4)",
                               "combination = (1 + sin((p.x + fbm/2) 50)) / 2")):
        ax.imshow(img, origin="lower", cmap="gray", vmin=0, vmax=1, extent=(-1, 1, -1, 1))
        ax.set_title(title, fontsize=10)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle(f"Kod 3.2 (pt-code-3.2): sine, fBm and marble, {n} x {n}", fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.02, top=0.86, wspace=0.05)
    out = out_dir / "fig-3.6.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
