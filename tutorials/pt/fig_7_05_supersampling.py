"""Figure pt-fig-7.5: the landscape without anti-aliasing, with 4 and with 16 rays per pixel, distant hilltops
magnified with nearest-neighbour scaling.

Equations: pt-alg-7.1.6 (supersampling: the mean of m x m regular sub-samples at ((i + 0.5) / m, (j + 0.5) / m) of the
pixel, m = 1, 2, 4), pt-code-7.1/7.2 (one ray per sub-sample), pt-code-7.3 (shading). Scene: the terrain scene's
defaults (its camera, sun and materials; the text's are not given). The crop (a 48 x 27 pixel window on the far
ridges) is magnified 4x without interpolation, as in the text. Output: figures/pt/fig-7.5.png.
"""
# %% [markdown]
# One ray per pixel samples the image at the pixel centres only; thin bright ridge lines and the grass/rock edges far
# away fall between centres and flicker into stair steps. Averaging a regular 2 x 2 or 4 x 4 grid of rays inside each
# pixel approximates the pixel's area integral. The cost grows with the number of rays (`pywarp bench terrain
# supersampling`), which is why the demo does not use it.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from pywarp.terrain.settings import TerrainSettings  # noqa: E402
from pywarp.terrain.technique import TerrainTechnique  # noqa: E402


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (96, 54) if quick else (384, 216)
    images = {rays: TerrainTechnique(TerrainSettings(width=w, height=h, rays_per_pixel=rays)).render()
              for rays in (1, 4, 16)}
    # a window on the far ridges just below the horizon, right of the sun
    cw, ch = w // 8, h // 8
    x0, y0 = int(w * 0.62), int(h * 0.42)
    fig, axes = plt.subplots(2, 3, figsize=(13, 6.2), gridspec_kw={"height_ratios": [1, 1]})
    for k, (rays, img) in enumerate(images.items()):
        axes[0, k].imshow(img)
        axes[0, k].add_patch(plt.Rectangle((x0 - 0.5, y0 - 0.5), cw, ch, fill=False, ec="red", lw=1))
        axes[0, k].set_title(f"{rays} ray{'s' if rays > 1 else ''} per pixel")
        crop = img[y0:y0 + ch, x0:x0 + cw]
        axes[1, k].imshow(np.repeat(np.repeat(crop, 4, axis=0), 4, axis=1), interpolation="nearest")
        axes[1, k].set_title("far ridges, 4x nearest neighbour")
    for ax in axes.ravel():
        ax.set_axis_off()
    p = out_dir / "fig-7.5.png"
    fig.savefig(p, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return [p]



if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
