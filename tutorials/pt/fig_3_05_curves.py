"""Figure pt-fig-3.5: the curves y = 0.1 e^x, x = 0.2 sin(15 y) and (x + 0.9)^2 + y^2 = 0.4 drawn from formulas.

Kod 3.1 (pt-code-3.1, pywarp.draw_curves) per pixel of an 800 x 600 window with the printed threshold 0.01, on the
coordinates of pt-alg-3.3 (pywarp.draw_coords) as printed (left: no aspect correction, the circle is an ellipse) and with
the aspect correction of Kod 7.1 (right). Background colour not given: dark grey. Output: figures/pt/fig-3.5.png.
"""
# %% [markdown]
# Each pixel tests whether it lies on a curve: |residual| < 0.01. The residual is in function-value units, so the
# lines are not of constant width: the exponential is thin where it is flat, the circle is wider where its implicit
# function changes slowly (near the centre), and the sine is thinnest where it is steep.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

PALETTE = np.array([[0.12, 0.12, 0.14], [0.9, 0.15, 0.1], [0.15, 0.35, 0.95], [0.98, 0.85, 0.1]])


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (200, 150) if quick else (800, 600)
    fx, fy = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    frag = np.stack([fx, fy], -1)
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.6), dpi=70 if quick else 100)
    for ax, aspect, title in zip(axes, ("none", "x"), ("as printed (no aspect correction)",
                                                       "with the aspect correction of Kod 7.1")):
        _, p, _ = pywarp.draw_coords(frag, [w, h], aspect=aspect)
        colour = pywarp.draw_curves(p, 0.01)
        ext = (p[..., 0].min(), p[..., 0].max(), -1, 1)
        ax.imshow(PALETTE[colour], origin="lower", extent=ext, interpolation="nearest")
        ax.set_title(f"Kod 3.1 {title}, {w} x {h}, threshold 0.01", fontsize=10)
        ax.set_xlabel("p.x")
        ax.set_ylabel("p.y")
    fig.suptitle("red y = 0.1 e^x, blue (x + 0.9)^2 + y^2 = 0.4, yellow x = 0.2 sin(15 y) (pt-code-3.1)", fontsize=11)
    fig.tight_layout()
    out = out_dir / "fig-3.5.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
