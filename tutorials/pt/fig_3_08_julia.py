"""Figure pt-fig-3.8: Julia sets for f(x) = x^5 + 0.544, f(x) = x^2 + 0.285 + 0.01i and f(x) = e^x - 0.65.

In kind: escape-time images of eq. 3.1 (pt-3.1) for the three maps of the caption (pt-u-julia,
pywarp.fractal_julia_example): |z| > 16 for the polynomials, Re z > 50 for the exponential map; 300 iterations (100 for
the exp map); members black, the others coloured by the smooth escape count -- three turns of a cyclic palette for
the polynomials; for the exp map, whose orbits escape within a few steps, one sweep of a sequential palette over the
counts present (over the cyclic palette one step more was a quarter turn: hard colour bands). The bands that remain
are the map's own: neighbouring start values between the "hairs" of e^z + c escape one step apart. Viewports, iteration counts and palette are
not given in the text. Output: figures/pt/fig-3.8.png.
"""
# %% [markdown]
# Every pixel is a start value a_0 in the complex plane. Iterating a_{n+1} = f(a_n), the orbit either stays bounded
# (the pixel belongs to the filled Julia set, the text's "Julia set": black) or runs off to infinity; the step at which
# it is certainly gone colours the pixel. For z^d + c, |z| beyond max(|c|, 2^(1/(d-1))) proves escape. For e^z + c
# the modulus is no test -- e^z is small for Re z << 0 and periodic in Im z -- and orbits escape along the positive
# real direction, hence the test Re z > 50 (the next iterate is ~e^50).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

VIEWS = {"x5": ((-1.25, 1.25), (-1.25, 1.25), 300, "f(x) = x^5 + 0.544"),
         "x2": ((-1.6, 1.6), (-1.2, 1.2), 300, "f(x) = x^2 + 0.285 + 0.01i"),
         "exp": ((-2.0, 4.5), (-3.5, 3.5), 100, "f(x) = e^x - 0.65")}


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 110 if quick else 420
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.8), dpi=70 if quick else 100)
    cmap = plt.get_cmap("twilight_shifted")
    for ax, (example, (xr, yr, max_iter, title)) in zip(axes, VIEWS.items()):
        ny = int(round(n * (yr[1] - yr[0]) / (xr[1] - xr[0])))
        x = xr[0] + (np.arange(n) + 0.5) / n * (xr[1] - xr[0])
        y = yr[0] + (np.arange(ny) + 0.5) / ny * (yr[1] - yr[0])
        z0 = np.stack(np.meshgrid(x, y), -1).astype(np.float32)
        count, smooth = pywarp.fractal_julia_example(z0, max_iter, example=example)
        if example == "exp":  # a few steps: one sweep of a sequential palette over the counts present
            esc = smooth[count < max_iter]
            lo, hi = np.percentile(esc, [0.5, 99.5]) if esc.size else (0.0, 1.0)
            rgb = plt.get_cmap("magma")(0.15 + 0.85 * np.clip((smooth - lo) / max(hi - lo, 1e-6), 0.0, 1.0))[..., :3]
        else:
            v = np.log1p(np.maximum(smooth, 0.0)) / np.log1p(max_iter)
            rgb = cmap(np.mod(3.0 * v, 1.0))[..., :3]
        rgb[count == max_iter] = 0.0
        ax.imshow(rgb, origin="lower", extent=(*xr, *yr), interpolation="nearest")
        ax.set_title(f"{title}\n{max_iter} iterations, {np.mean(count == max_iter) * 100:.1f} % bounded", fontsize=10)
        ax.set_xlabel("Re a0")
        ax.set_ylabel("Im a0")
    fig.suptitle("Julia sets (eq. 3.1, pt-3.1) of the three maps of Obrazok 3.8 (pt-u-julia): escape |z| > 16 "
                 "(polynomials), Re z > 50 (exp); colour = smooth escape count", fontsize=11)
    fig.subplots_adjust(left=0.045, right=0.99, bottom=0.1, top=0.83, wspace=0.22)
    out = out_dir / "fig-3.8.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
