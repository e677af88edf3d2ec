"""Figure pt-fig-3.4: a pixel position in window space (800 x 600), normalised, then centred; polar coordinates.

pt-alg-3.3 (pywarp.draw_coords) applied to a sample pixel of the text's 800 x 600 window: uv = frag / resolution,
p = 2 uv - 1 (origin at the centre), (r, phi) = (|p|, atan2(p.y, p.x)); the aspect-corrected p of Kod 7.1 is shown as a
fourth frame. Output: figures/pt/fig-3.4.png.
"""
# %% [markdown]
# The fragment shader knows only its pixel's window position (origin bottom-left, in pixels). Dividing by the window
# size gives uv in (0, 1)^2 independent of the resolution; 2 uv - 1 moves the origin to the centre of the screen,
# the natural origin for drawing symmetric shapes; polar coordinates of p suit round ones.

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
    res = np.array([800.0, 600.0])
    frag = np.array([600.5, 450.5])  # the centre of pixel (600, 450)
    uv, p, polar = pywarp.draw_coords(frag, res)
    _, pa, _ = pywarp.draw_coords(frag, res, aspect="x")
    frames = [("window space (pixels)", (0, 800), (0, 600), frag, f"frag = ({frag[0]:g}, {frag[1]:g})"),
              ("normalised uv = frag / resolution", (0, 1), (0, 1), uv, f"uv = ({uv[0]:.4f}, {uv[1]:.4f})"),
              ("centred p = 2 uv - 1", (-1, 1), (-1, 1), p,
               f"p = ({p[0]:.4f}, {p[1]:.4f})\nr = {polar[0]:.4f}, phi = {np.degrees(polar[1]):.2f} deg"),
              ("aspect-corrected (Kod 7.1): p.x * 800/600", (-4 / 3, 4 / 3), (-1, 1), pa,
               f"p = ({pa[0]:.4f}, {pa[1]:.4f})")]
    fig, axes = plt.subplots(1, 4, figsize=(15, 3.9), dpi=70 if quick else 100)
    for ax, (title, xl, yl, pt, label) in zip(axes, frames):
        ax.add_patch(plt.Rectangle((xl[0], yl[0]), xl[1] - xl[0], yl[1] - yl[0], fill=False, lw=1.5))
        ax.plot([pt[0]], [pt[1]], "ro")
        ox, oy = (0.0, 0.0)
        ax.plot([ox], [oy], "ks", ms=5)
        ax.annotate("origin", (ox, oy), textcoords="offset points", xytext=(4, 4), fontsize=8)
        if title.startswith("centred"):
            ax.plot([0, pt[0]], [0, pt[1]], "r--", lw=1)
            t = np.linspace(0, polar[1], 30)
            ax.plot(0.25 * np.cos(t), 0.25 * np.sin(t), "r-", lw=1)
        ax.annotate(label, (pt[0], pt[1]), textcoords="offset points", xytext=(-95, 12), fontsize=8, color="r")
        ax.set_xlim(xl[0] - 0.08 * (xl[1] - xl[0]), xl[1] + 0.08 * (xl[1] - xl[0]))
        ax.set_ylim(yl[0] - 0.08 * (yl[1] - yl[0]), yl[1] + 0.08 * (yl[1] - yl[0]))
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=10)
    fig.suptitle("Pixel coordinates for drawing with formulas (pt-alg-3.3), window 800 x 600", fontsize=11)
    fig.tight_layout()
    out = out_dir / "fig-3.4.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
