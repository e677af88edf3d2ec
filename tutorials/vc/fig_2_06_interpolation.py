"""Figure vc-fig-2.6: comparison of the interpolation curves of Perlin noise -- linear t, cosine (1 - cos pi t)/2,
the fade 3t^2 - 2t^3 (vc-2.19) and the improved fade 6t^5 - 15t^4 + 10t^3 (vc-2.20) on t in [0, 1].

The fades are pywarp.interp_fade_cubic and pywarp.interp_fade_quintic; the linear and cosine curves are the library's
interp_lerp / interp_cosine (pywarp.clouds.noise.interpolants; the thesis does not write the cosine formula, the
catalogue's reading (1 - cos pi t)/2 is used). Extra panels (not in the thesis): the first and second derivatives of
each curve by NumPy central differences, which show the smoothness property each curve buys (vc-A1).
Output: figures/vc/fig-2.6.png.
"""
# %% [markdown]
# Perlin noise blends the contributions of the cell corners with a weight w(t) that goes from 0 at one corner
# (t = 0) to 1 at the other (t = 1). The shape of w decides how the noise behaves where two cells meet:
#
# * w(t) = t is the plain linear blend. Its slope is 1 at both ends, so neighbouring cells meet with a kink.
# * The cosine curve and the fade 3t^2 - 2t^3 (2.19, "smoothstep") both start and end with slope 0 -- the noise is
#   smooth (C1) across cell borders. The fade is a cheap polynomial that replaces the trigonometric function; the
#   two curves are almost indistinguishable.
# * Perlin's improved fade 6t^5 - 15t^4 + 10t^3 (2.20) also has zero curvature (second derivative) at both ends,
#   so the noise is C2: its second derivatives, which show up in bump-mapped lighting, no longer jump at the lattice.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds.noise import interpolants  # noqa: E402  (public NumPy helper: the four curves of this figure)

STYLE = {"linear": ("linear  t", "C0", "-"),
         "cosine": ("cosine  (1 - cos πt)/2", "C1", "--"),
         "cubic": ("fade  3t² - 2t³  (2.19)", "C2", "-"),
         "quintic": ("improved fade  6t⁵ - 15t⁴ + 10t³  (2.20)", "C3", "-")}


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 101 if quick else 201  # coarse enough that the float32 round-off stays invisible in w''
    t = np.linspace(0.0, 1.0, n)

    # %% [markdown]
    # The curves, evaluated by the library (Warp twins, float32). The two fades are the registered equations
    # vc-2.19 and vc-2.20; `interpolants` returns them together with the linear and cosine blends.

    # %%
    curves = interpolants(t)
    assert np.array_equal(curves["cubic"], pywarp.interp_fade_cubic(t))
    assert np.array_equal(curves["quintic"], pywarp.interp_fade_quintic(t))

    # %% [markdown]
    # Derivatives by central differences (float64 on the float32 samples, one-sided at the ends): exact enough to
    # read off w'(0), w'(1), w''(0), w''(1). The grey dots mark the values the smoothness argument needs: slope 0 at
    # the ends for C1, curvature 0 at the ends for C2.

    # %%
    dt = t[1] - t[0]
    d1 = {k: np.gradient(v.astype(np.float64), dt, edge_order=2) for k, v in curves.items()}
    d2 = {k: np.gradient(v, dt, edge_order=2) for k, v in d1.items()}

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.8), dpi=90 if quick else 130)
    for k, (label, color, ls) in STYLE.items():
        for ax, data in zip(axes, (curves[k], d1[k], d2[k])):
            ax.plot(t, data, color=color, ls=ls, lw=1.8, label=label)
    axes[0].set_title("w(t): the interpolation curves")
    axes[0].set_ylabel("weight of the far corner")
    axes[1].set_title("w'(t): slope (0 at both ends -> C1 noise)")
    axes[2].set_title("w''(t): curvature (0 at both ends -> C2 noise)")
    for ax in axes[1:]:
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.plot([0, 1], [0, 0], "o", color="0.4", ms=5, zorder=5)
    axes[2].set_ylim(-7.5, 7.5)
    for ax in axes:
        ax.set_xlabel("t (position inside the cell)")
        ax.set_xlim(0.0, 1.0)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper left", fontsize=8.5, frameon=False)
    fig.suptitle("Interpolation curves of Perlin noise (vc-fig-2.6) and their derivatives "
                 "(middle and right: central differences, not in the thesis)", fontsize=11)
    fig.subplots_adjust(left=0.05, right=0.98, bottom=0.12, top=0.85, wspace=0.22)
    out = out_dir / "fig-2.6.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
