"""Figure vc-fig-2.5: 2-D Perlin noise with four interpolants -- linear, cosine, the fade 3t^2 - 2t^3 (vc-2.19) and
Perlin's improved fade 6t^5 - 15t^4 + 10t^3 (vc-2.20).

Perlin gradient noise (vc-A1) on an 8 x 8 lattice, 256 x 256 pixels, seed 0 (Ken Perlin's 2002 permutation), evaluated
by the library with each interpolant (pywarp.clouds.noise.perlin2, the NumPy front end of ccl_noise_perlin2 /
noise_perlin2; the quintic panel equals pywarp.noise_perlin3(x, y, 0)). The thesis does not state the panels, lattice,
seed or resolution; two extra rows (not in the thesis) make the differences visible: the gradient magnitude and the
Laplacian of each image, by NumPy finite differences. Output: figures/vc/fig-2.5.png.
"""
# %% [markdown]
# Perlin noise gives every lattice point a pseudo-random gradient. Inside a cell, each corner contributes the dot
# product of its gradient with the vector from the corner to the point, and the four contributions are blended with
# weights w(t_x), w(t_y), where t is the position inside the cell. The blending curve w decides how smooth the result
# is across cell borders:
#
# * linear w = t: the noise is continuous, but its slope jumps at every cell border -- visible creases on a grid;
# * cosine w = (1 - cos pi t)/2 and the fade 3t^2 - 2t^3 (2.19): the slope is continuous (w'(0) = w'(1) = 0), but
#   the curvature still jumps;
# * the improved fade 6t^5 - 15t^4 + 10t^3 (2.20): slope and curvature are continuous (w'' = 0 at both ends too).
#
# In the noise itself (top row) the eye mostly sees the linear creases. The derivative rows show the rest: the
# gradient magnitude (middle) has sharp grid lines only for the linear blend; the Laplacian (bottom, the sum of the
# second derivatives, as used e.g. for normals and lighting of bumped surfaces) jumps along the lattice lines for every
# curve except the quintic one -- which is why Perlin introduced it in 2002.
#
# The flat black cell of the linear panel (x in [2, 3], y in [0, 1]) is not a bug: there the corners along each edge
# share their gradient component, and blending g t with g (t - 1) linearly cancels, (1 - t) g t + t g (t - 1) = 0.
# Any curve with w(t) != t leaves a small wave in the same cell.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds.noise import perlin2  # noqa: E402  (public NumPy helper: 2-D Perlin with a choice of interpolant)

PANELS = (("linear", "linear\nw = t"),
          ("cosine", "cosine\nw = (1 - cos πt)/2"),
          ("cubic", "fade (2.19)\nw = 3t² - 2t³"),
          ("quintic", "improved fade (2.20)\nw = 6t⁵ - 15t⁴ + 10t³"))


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    cells, seed = 8, 0
    n = 96 if quick else 256
    # pixel centres, in lattice units: x in [0, cells)
    u = (np.arange(n) + 0.5) * (cells / n)
    x, y = np.meshgrid(u, u)
    h = cells / n  # pixel size in lattice units (for the finite differences)

    # %% [markdown]
    # One call per interpolant; the quintic one is the library's standard Perlin noise (vc-A1), so it must equal the
    # z = 0 slice of the 3-D noise exactly.

    # %%
    images = {k: perlin2(x, y, seed=seed, interp=k) for k, _ in PANELS}
    assert np.array_equal(images["quintic"], pywarp.noise_perlin3(x, y, 0.0, seed))

    # %% [markdown]
    # Derivatives by central differences on the pixel grid (float64): the gradient magnitude |∇n| and the
    # Laplacian ∂²n/∂x² + ∂²n/∂y². They are computed on the image, so they are exact up to O(h²) within cells and
    # show each jump as a one-pixel line.

    # %%
    grads, laps = {}, {}
    for k, img in images.items():
        a = img.astype(np.float64)
        gy, gx = np.gradient(a, h)
        grads[k] = np.hypot(gx, gy)
        p = np.pad(a, 1, mode="edge")
        laps[k] = ((p[1:-1, 2:] + p[1:-1, :-2] + p[2:, 1:-1] + p[:-2, 1:-1] - 4.0 * a) / h**2)[1:-1, 1:-1]
    gmax = max(float(np.percentile(g, 99.5)) for g in grads.values())
    # the linear blend's Laplacian has delta-like spikes on the cell borders: scale by the three smooth curves and let
    # the linear panel saturate
    lmax = max(float(np.percentile(np.abs(laps[k]), 99.5)) for k in ("cosine", "cubic", "quintic"))

    fig, axes = plt.subplots(3, 4, figsize=(13, 10.2), dpi=80 if quick else 110)
    for j, (k, title) in enumerate(PANELS):
        ax = axes[0, j]
        im0 = ax.imshow(0.5 * images[k] + 0.5, cmap="gray", vmin=0.0, vmax=1.0, origin="lower",
                        extent=(0, cells, 0, cells), interpolation="nearest")
        ax.set_title(title, fontsize=10)
        im1 = axes[1, j].imshow(grads[k], cmap="magma", vmin=0.0, vmax=gmax, origin="lower",
                                extent=(0, cells, 0, cells), interpolation="nearest")
        im2 = axes[2, j].imshow(laps[k], cmap="RdBu_r", vmin=-lmax, vmax=lmax, origin="lower",
                                extent=(1 * h, cells - h, h, cells - h), interpolation="nearest")
        for ax in axes[:, j]:
            ax.set_xticks(range(0, cells + 1, 2))
            ax.set_yticks(range(0, cells + 1, 2))
            ax.tick_params(labelsize=7)
    fig.subplots_adjust(left=0.06, right=0.90, bottom=0.04, top=0.88, hspace=0.3, wspace=0.2)
    for row, (im, label) in enumerate(((im0, "noise  0.5 n + 0.5"), (im1, "gradient magnitude |∇n|"),
                                       (im2, "Laplacian ∇²n"))):
        axes[row, 0].set_ylabel(label, fontsize=10)
        fig.colorbar(im, ax=axes[row, :].tolist(), fraction=0.02, pad=0.01).ax.tick_params(labelsize=7)
    fig.suptitle(f"Perlin noise (vc-A1), {cells} x {cells} lattice cells, seed {seed}, {n}² px: the interpolant "
                 "decides the smoothness across cell borders\n(axes in lattice units; middle and bottom rows: "
                 "finite differences of the top row)", fontsize=11)
    out = out_dir / "fig-2.5.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
