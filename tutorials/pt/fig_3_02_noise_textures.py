"""Figure pt-fig-3.2 (textures from a book), stand-in: four textures built from the demo's fBm of Perlin noise.

Stand-in: the thesis shows material textures from Ebert et al. without recipes, so four textures in kind are built from
the demo's fBm (pt-alg-3.2, noise_fbm_perlin2 with the printed A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2) and simple colour
ramps: clouds, marble (Kod 3.2's combination, pt-code-3.2), wood rings and a height-coloured terrain map. Seeds, scales
and ramps are this tutorial's choices. Output: figures/pt/fig-3.2.png.
"""
# %% [markdown]
# Noise alone is a grey field. Textures come from what is done with it: a colour ramp (clouds), a sine whose phase
# is shifted by the noise (marble), the fractional part of a distance that the noise disturbs (wood), or a ramp of
# height colours (a map of a terrain).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402


def _ramp(v, stops, colours):
    v = np.clip(v, stops[0], stops[-1])
    return np.stack([np.interp(v, stops, [c[k] for c in colours]) for k in range(3)], -1)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 96 if quick else 320
    u = (np.arange(n) + 0.5) / n * 2 - 1
    X, Y = np.meshgrid(u, u)
    p = np.stack([X, Y], -1).astype(np.float32)

    clouds = pywarp.noise_fbm_perlin2(p * 4.0, 6, seed=1)
    sky = _ramp(0.5 + 0.5 * clouds, [0.0, 0.45, 0.75, 1.0],
                [(0.25, 0.45, 0.85), (0.45, 0.62, 0.92), (0.92, 0.94, 0.97), (1.0, 1.0, 1.0)])
    _, _, marble = pywarp.draw_marble(p, 5, seed=0)
    marble_rgb = _ramp(marble, [0.0, 0.15, 1.0], [(0.25, 0.22, 0.2), (0.6, 0.57, 0.52), (0.97, 0.96, 0.93)])
    ring = np.sqrt((X + 1.3) ** 2 + (Y + 0.2) ** 2) * 9.0 + 1.5 * pywarp.noise_fbm_perlin2(p * 3.0, 4, seed=2)
    grain = ring - np.floor(ring)
    wood = _ramp(grain ** 3, [0.0, 1.0], [(0.78, 0.55, 0.3), (0.45, 0.26, 0.1)])
    height = pywarp.noise_fbm_perlin2(p * 3.0, 7, seed=3)
    terrain = _ramp(height, [-1.0, -0.05, 0.0, 0.1, 0.5, 0.8, 1.2],
                    [(0.05, 0.15, 0.45), (0.2, 0.45, 0.75), (0.85, 0.8, 0.55), (0.3, 0.6, 0.25), (0.25, 0.4, 0.2),
                     (0.5, 0.45, 0.4), (0.97, 0.97, 0.97)])

    fig, axes = plt.subplots(1, 4, figsize=(14, 4.0), dpi=70 if quick else 100)
    for ax, img, title in zip(axes, (sky, marble_rgb, wood, terrain),
                              ("clouds: colour ramp of fBm(4p), 6 oct.", "marble: Kod 3.2 combination",
                               "wood: rings disturbed by fBm", "terrain map: height ramp, 7 oct.")):
        ax.imshow(img, origin="lower", interpolation="nearest")
        ax.set_title(title, fontsize=10)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle("Stand-in for pt-fig-3.2: textures from the demo's fBm (pt-alg-3.2) of Perlin noise (pt-alg-3.1)",
                 fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.02, top=0.85, wspace=0.05)
    out = out_dir / "fig-3.2.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
