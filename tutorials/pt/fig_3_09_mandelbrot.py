"""Figure pt-fig-3.9: the Mandelbrot set in the parameter plane mu.

Eq. 3.2 / 3.3 (pt-3.2, pt-3.3, pywarp.fractal_mandelbrot): a_0 = 0, a_{n+1} = a_n^2 - mu as printed (variant "thesis",
left) and the usual a_n^2 + c (variant "corrected", right), bailout |a_n| > 2 as printed, 500 iterations; members black,
the others coloured by the smooth count. The printed sign mirrors the set (mu = -c): antenna towards +2. Output:
figures/pt/fig-3.9.png.
"""
# %% [markdown]
# The Mandelbrot set collects the parameters whose Julia set is connected; equivalently (eq. 3.3) those for which the
# orbit of 0 stays within |a_n| <= 2. With the thesis's f(x) = x^2 - mu the set in the mu plane is the familiar one
# reflected through the imaginary axis, because x^2 - mu = x^2 + c with c = -mu and the set is symmetric about the real
# axis. Both are drawn on the same axes.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

MAX_ITER = 500  # not given; shows the filaments at this scale


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 140 if quick else 460
    xr, yr = (-2.4, 2.4), (-1.5, 1.5)
    ny = int(round(n * (yr[1] - yr[0]) / (xr[1] - xr[0])))
    x = xr[0] + (np.arange(n) + 0.5) / n * (xr[1] - xr[0])
    y = yr[0] + (np.arange(ny) + 0.5) / ny * (yr[1] - yr[0])
    mu = np.stack(np.meshgrid(x, y), -1).astype(np.float32)
    cmap = plt.get_cmap("inferno")
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.0), dpi=70 if quick else 100)
    for ax, variant, title in zip(axes, ("thesis", "corrected"),
                                  ("thesis: a_(n+1) = a_n^2 - mu (eq. 3.2 as printed)",
                                   "corrected: a_(n+1) = a_n^2 + c (usual convention)")):
        count, smooth = pywarp.fractal_mandelbrot(mu, MAX_ITER, variant=variant)
        v = np.sqrt(np.maximum(smooth, 0.0) / MAX_ITER)
        rgb = cmap(np.clip(v * 2.2, 0, 1))[..., :3]
        rgb[count == MAX_ITER] = 0.0
        ax.imshow(rgb, origin="lower", extent=(*xr, *yr), interpolation="nearest")
        ax.axvline(0, color="w", lw=0.4, alpha=0.5)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("Re mu" if variant == "thesis" else "Re c")
        ax.set_ylabel("Im")
    fig.suptitle(f"Mandelbrot set (pt-3.3), bailout |a_n| > 2, {MAX_ITER} iterations: the printed -mu sign mirrors "
                 "the set left-right (antenna towards +2)", fontsize=11)
    fig.tight_layout()
    out = out_dir / "fig-3.9.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
