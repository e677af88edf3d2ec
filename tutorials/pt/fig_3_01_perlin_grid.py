"""Figure pt-fig-3.1: the 2-D lattice of Perlin noise with a gradient vector at every corner.

The demo's noise (pt-alg-3.1 = vc-A1, 2-D slice z = 0, seed 0 = Ken Perlin's table) over a 6 x 4 patch of lattice cells;
the arrows are the corner gradients, read off the noise itself: at a lattice point the fade weights have zero slope,
so the noise gradient there is exactly the (x, y) part of the corner's gradient vector (one of Perlin's 12 edge
vectors). Grid size and seed are free in the text. Output: figures/pt/fig-3.1.png.
"""
# %% [markdown]
# Perlin noise puts a pseudo-random gradient vector on every corner of a square lattice. At a point p inside a cell,
# each of the four corners c contributes the dot product g_c . (p - c): a little tilted plane through the corner. The
# four planes are blended with weights that depend on the distance of p from each corner (the quintic fade), so the
# noise is zero at every corner and rises or falls away from it in the direction of its gradient.

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
    nx, ny, res = 6, 4, (24 if quick else 64)
    x0, y0 = 3.0, 5.0  # which patch of the lattice (free)
    xs = x0 + (np.arange(nx * res) + 0.5) / res
    ys = y0 + (np.arange(ny * res) + 0.5) / res
    X, Y = np.meshgrid(xs, ys)
    noise = pywarp.perlin2(X.astype(np.float32), Y.astype(np.float32))

    # %% [markdown]
    # The gradient at each corner by central differences of the noise (h = 1/256 lattice units): exact up to the
    # O(h^2) curvature of the fade, well below the width of an arrow.

    # %%
    cx, cy = np.meshgrid(np.arange(x0, x0 + nx + 1), np.arange(y0, y0 + ny + 1))
    h = np.float32(1.0 / 256.0)
    c32x, c32y = cx.astype(np.float32), cy.astype(np.float32)
    gx = (pywarp.perlin2(c32x + h, c32y) - pywarp.perlin2(c32x - h, c32y)) / (2 * h)
    gy = (pywarp.perlin2(c32x, c32y + h) - pywarp.perlin2(c32x, c32y - h)) / (2 * h)
    assert np.all(np.isin(np.round(gx), [-1, 0, 1])) and np.all(np.isin(np.round(gy), [-1, 0, 1]))

    fig, ax = plt.subplots(figsize=(9, 6.4), dpi=70 if quick else 110)
    im = ax.imshow(noise, origin="lower", extent=(x0, x0 + nx, y0, y0 + ny), cmap="RdBu_r", vmin=-1, vmax=1)
    for k in range(nx + 1):
        ax.axvline(x0 + k, color="k", lw=0.8)
    for k in range(ny + 1):
        ax.axhline(y0 + k, color="k", lw=0.8)
    ax.quiver(cx, cy, gx, gy, angles="xy", scale_units="xy", scale=2.2, width=0.006, color="k", zorder=3)
    ax.plot(cx, cy, "ko", ms=4)
    fig.colorbar(im, ax=ax, fraction=0.03, pad=0.02, label="noise value")
    ax.set_title("Perlin noise lattice (pt-alg-3.1 = vc-A1, z = 0 slice, seed 0): a gradient at every corner\n"
                 "arrows = (x, y) part of Perlin's edge gradients, drawn at half length; noise is 0 at every corner",
                 fontsize=10)
    ax.set_xlabel("x (lattice units)")
    ax.set_ylabel("y (lattice units)")
    fig.tight_layout()
    out = out_dir / "fig-3.1.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
