"""Figures pt-fig-7.1 and pt-fig-7.2: the test heightmap 10 sin(0.1 x) sin(0.1 z) rendered by naive fixed-step ray
marching, and the steps per pixel of the naive march (Kod 7.4) against the dynamic step (Kod 7.5), capped at 1000, on a
log scale, the rays that hit the terrain and the sky rays (which a naive march runs to the cap) counted apart.

Equations: pt-code-7.4, pt-code-7.5 (the marches), pt-code-7.1/7.2 (rays), pt-7.1 and pt-code-7.8 (light as in 7.2).
The text gives no camera, light, colours, MAX_T or STEP_SIZE: the scene's TEST_HEIGHTMAP settings are used (camera 15
units above the mean level looking 20 deg down along the diagonal, MAX_T 200, STEP_SIZE 0.1, PRECISION 0.01,
MAX_STEPS 1000). Outputs: figures/pt/fig-7.1.png, figures/pt/fig-7.2.png.
"""
# %% [markdown]
# The naive march of Kod 7.4 walks every ray in equal steps until the point is below the terrain (or within PRECISION
# above it). Its cost is the ray length divided by STEP_SIZE: a ray into the sky takes MAX_T / STEP_SIZE = 2000 steps.
# The dynamic march of Kod 7.5 steps by the vertical gap y - h(x, z) instead: large steps high above the terrain,
# small ones near it. Both find the same surface (the image difference is printed below); the step counts show why
# Tabulka 7.1 measures ~20x.

# %%
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

from pywarp.core import display  # noqa: E402
from pywarp.terrain.settings import TEST_HEIGHTMAP, TerrainSettings  # noqa: E402
from pywarp.terrain.technique import TerrainTechnique  # noqa: E402

CAP = 1000  # Obrazok 7.2 caps the step count at 1000


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (128, 96) if quick else (640, 480)
    s = TerrainSettings(width=w, height=h, **TEST_HEIGHTMAP)
    fixed = TerrainTechnique(replace(s, march="fixed"))
    colours_fixed = fixed.render(encode=False)
    steps_fixed = fixed.steps_taken()
    dynamic = TerrainTechnique(replace(s, march="dynamic"))
    colours_dynamic = dynamic.render(encode=False)
    steps_dynamic = dynamic.steps_taken()
    img_fixed, img_dynamic = (display.encode_encoded(c, s.exposure_ev, s.tonemap)
                              for c in (colours_fixed, colours_dynamic))
    # a ray that hits nothing returns the sky colour of the heightmap stage (the top row looks into the sky)
    sky = np.all(colours_dynamic == colours_dynamic[0, 0], axis=-1) & np.all(colours_fixed == colours_fixed[0, 0],
                                                                                axis=-1)

    # %% Obrazok 7.1: the naive render
    fig, ax = plt.subplots(figsize=(6.4, 5.2))
    ax.imshow(img_fixed)
    ax.set_axis_off()
    ax.set_title("10 sin(0.1x) sin(0.1z), naive fixed-step march (Kod 7.4), Lambert + ambient")
    p1 = out_dir / "fig-7.1.png"
    fig.savefig(p1, dpi=100, bbox_inches="tight")
    plt.close(fig)

    # %% Obrazok 7.2: steps per pixel on one log scale; the rays that hit the terrain and the sky rays counted apart
    # (a sky ray of the naive march runs to the 1000-step cap, a sky ray of the dynamic one leaves through MAX_T in a
    # few long steps: the mean over all pixels hides both)
    diff = np.abs(img_fixed.astype(int) - img_dynamic.astype(int)).max(axis=-1)
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.6))
    norm = LogNorm(vmin=1, vmax=CAP)
    for ax, steps, name in ((axes[0], steps_fixed, "naive (7.1.2)"), (axes[1], steps_dynamic, "dynamic step (7.1.3)")):
        capped = np.minimum(steps, CAP)
        im = ax.imshow(np.maximum(capped, 1), cmap="inferno", norm=norm)
        ax.set_title(f"{name}\nterrain rays: mean {capped[~sky].mean():.0f} steps\nsky rays ({sky.mean() * 100:.0f} % "
                     f"of the pixels): mean {capped[sky].mean():.0f} steps", fontsize=11)
        ax.set_axis_off()
    fig.colorbar(im, ax=axes, fraction=0.025, label="steps per pixel (log scale, capped at 1000)")
    fig.suptitle(f"ray-march steps per pixel; the images differ by <= 2/255 in {np.mean(diff <= 2) * 100:.1f} % of "
                 "pixels (silhouettes move by up to one fixed step)")
    p2 = out_dir / "fig-7.2.png"
    fig.savefig(p2, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return [p1, p2]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
