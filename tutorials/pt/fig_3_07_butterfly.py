"""Figure pt-fig-3.7 (Quilez's butterfly), stand-in: a wing texture drawn with formulas on two flapping rectangles.

Stand-in: the thesis shows Quilez's butterfly without its formulas, so pt-alg-3.5 (pywarp.draw_butterfly) draws one: two
textured quads hinged on the body axis, hinge angle 1.0 sin(2 pi 1.5 t) rad, flying a figure-of-eight that repeats every
4 s. A strip of 8 frames over one wing beat, and (full size only) the whole 4 s loop as an animated GIF at 20 frames/s,
480 x 360; the view is enlarged 1.7 times and every pixel averages 3 x 3 samples (antialiased).
Output: figures/pt/fig-3.7.png (and fig-3.7.gif).
"""
# %% [markdown]
# The wings are flat rectangles; everything that looks like a butterfly is the texture, drawn with formulas in the
# wing's own coordinates: two ellipses (fore- and hindwing), a black border (the ellipse equation above 0.72), white
# spots (a sine of the angle around the hinge inside the border), veins radiating from the hinge, a dark body strip.
# Each pixel intersects its camera ray with both wing planes and keeps the nearest hit inside the texture.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

FPS = 20  # GIF frame rate; 80 frames = the 4 s loop of the animation
ZOOM = 1.7  # the view of pt-alg-3.5's coordinates, enlarged: the figure-of-eight still stays inside the frame
SUPERSAMPLING = 3  # 3 x 3 samples per pixel, box-filtered: the wing pattern antialiased, not a few aliased dots


def _frame(w, h, t):
    """One frame, (h, w, 3) in [0, 1]: pt-alg-3.5 at SUPERSAMPLING^2 points per pixel, averaged."""
    k = SUPERSAMPLING
    f = np.stack(np.meshgrid((np.arange(w * k) + 0.5) / k, (np.arange(h * k) + 0.5) / k), -1)
    _, p, _ = pywarp.draw_coords(f, [w, h], aspect="x")
    rgb = np.clip(pywarp.draw_butterfly(p / ZOOM, t), 0, 1)[::-1]  # row 0 at the top for images
    return rgb.reshape(h, k, w, k, 3).mean(axis=(1, 3))


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (120, 90) if quick else (480, 360)
    beat = 1.0 / 1.5
    times = np.arange(8) * beat / 8 + 0.3
    fig, axes = plt.subplots(2, 4, figsize=(16, 6.6), dpi=70 if quick else 100)
    for ax, t in zip(axes.ravel(), times):
        ax.imshow(_frame(w, h, t), interpolation="lanczos" if not quick else "nearest")
        ax.set_title(f"t = {t:.3f} s", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle("Stand-in for pt-fig-3.7: pt-alg-3.5, one wing beat (1/1.5 s) in 8 frames; the animation loops "
                 "every 4 s", fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.02, top=0.88, wspace=0.04, hspace=0.16)
    out = out_dir / "fig-3.7.png"
    fig.savefig(out)
    plt.close(fig)
    written = [out]
    if not quick:
        from PIL import Image

        frames = [Image.fromarray((_frame(w, h, k / FPS) * 255 + 0.5).astype(np.uint8)) for k in range(4 * FPS)]
        gif = out_dir / "fig-3.7.gif"
        frames[0].save(gif, save_all=True, append_images=frames[1:], duration=1000 // FPS, loop=0)
        written.append(gif)
    return written


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
