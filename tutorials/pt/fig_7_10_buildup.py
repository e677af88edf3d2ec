"""Figure pt-fig-7.10: building up the terrain: (a) heightmap only, (b) materials by a colour gradient, (c) clouds,
fog and grass where the normal points up, (d) the final environment with water.

Equations: pt-alg-7.3-material (the four stages), pt-code-7.9, pt-code-7.5, pt-code-7.8, pt-7.1, pt-code-7.7 (soft
shadows in every stage), pt-7.3 (fog, printed form), pt-code-7.10, pt-code-7.11, pt-alg-7.3.4, pt-7.4. Colours,
thresholds and gradient heights are not given: the terrain scene's defaults (pywarp.terrain.settings, each with its
reason). Output: figures/pt/fig-7.10.png.
"""
# %% [markdown]
# (a) one rock colour, lit; (b) colour_low below material_low blending to colour_rock above material_high;
# (c) grass where n.y > 0.85 (a soft band of 0.08), the clouds of Kod 7.11 and the fog of eq. 7.3 towards the sky
# colour; (d) the water plane at y = -5 in front of the underwater terrain.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.terrain.settings import TerrainSettings  # noqa: E402
from pywarp.terrain.technique import TerrainTechnique  # noqa: E402

STAGES = (("heightmap", "(a) heightmap only"), ("materials", "(b) materials by height"),
          ("atmosphere", "(c) + grass, clouds, fog"), ("final", "(d) + water"))


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (96, 54) if quick else (480, 270)
    fig, axes = plt.subplots(2, 2, figsize=(10.5, 6.4))
    for ax, (stage, title) in zip(axes.ravel(), STAGES):
        ax.imshow(TerrainTechnique(TerrainSettings(width=w, height=h, stage=stage)).render())
        ax.set_title(title)
        ax.set_axis_off()
    p = out_dir / "fig-7.10.png"
    fig.savefig(p, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return [p]



if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
