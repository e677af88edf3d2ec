"""Figure vc-fig-2.14: visualization of the remap function (vc-2.27) applied to trigonometric functions.

The thesis does not give its functions; this uses the catalogue's example: v = sin x, o_min = 0.3 sin(8x) - 0.3,
result remap(v, o_min, 1, 0, 1), evaluated with pywarp.interp_remap (unclamped, as catalogued). Panel (c), not in the
thesis, uses a non-negative o_min = 0.3 sin(8x) + 0.3 instead: the erosion of eq. 2.30 rather than the outward push of
eq. 2.28. Output: figures/vc/fig-2.14.png.
"""
# %% [markdown]
# remap (2.27) maps a value v linearly from an old range [o_min, o_max] to a new range [n_min, n_max]:
#
#     remap(v, o_min, o_max, n_min, n_max) = n_min + (v - o_min) / (o_max - o_min) * (n_max - n_min)
#
# The cloud shader uses it with a *varying* old range to carve detail into a shape (2.28, 2.30): the old minimum
# o_min comes from a high-frequency noise. Here the "shape" is v = sin x and the "noise" is o_min = 0.3 sin 8x - 0.3
# (between -0.6 and 0). With o_max = n_max = 1 and n_min = 0:
#
#     remap(v, o_min, 1, 0, 1) = (v - o_min) / (1 - o_min)
#
# At the top of the shape (v = 1) the result stays 1 whatever o_min is, and the result reaches 0 exactly where
# v = o_min. In between, the wiggle of o_min shows through with a weight that grows as v falls: the large-scale form
# is kept, and the fine modulation acts mostly on its low parts -- in a cloud, on the soft edges, not the dense core.
#
# The sign of o_min decides the direction. With o_min <= 0 (the example, panel b) the result is never below v: the
# detail pushes the shape outward, as 2.28 does with o_min = L_FBM - 1 (the base shape "dilated" by the Worley fBm).
# With o_min >= 0 (panel c, not in the thesis, o_min = 0.3 sin 8x + 0.3) the result is never above v: the detail
# eats into the shape, the erosion of 2.30. The formula is not clamped: where v < o_min the result goes below 0
# (shaded); a density is cut off there.

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
    n = 401 if quick else 2001
    x = np.linspace(0.0, 2.0 * np.pi, n)
    v = np.sin(x)
    o_min = 0.3 * np.sin(8.0 * x) - 0.3

    # %% [markdown]
    # The remap itself, by the library (Warp, float32, unclamped).

    # %%
    r = pywarp.interp_remap(v, o_min, 1.0, 0.0, 1.0)

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), dpi=90 if quick else 130)
    ax = axes[0]
    ax.plot(x, v, color="C0", lw=2, label="v = sin x  (the shape)")
    ax.plot(x, o_min, color="C1", lw=1.3, label="o_min = 0.3 sin 8x - 0.3  (the detail)")
    ax.axhline(1.0, color="C2", lw=1.2, ls="--", label="o_max = 1")
    ax.set_title("(a) the inputs")

    ax = axes[1]
    ax.plot(x, v, color="C0", lw=1.2, ls="--", label="v = sin x")
    ax.plot(x, r, color="C3", lw=2, label="remap(v, o_min, 1, 0, 1)")
    ax.fill_between(x, r, 0.0, where=r < 0.0, color="C3", alpha=0.25, label="< 0: cut off as a density")
    ax.set_title("(b) o_min ≤ 0: the detail pushes out (like 2.28)")

    # %% [markdown]
    # (c) The same with a non-negative o_min: erosion.

    # %%
    ax = axes[2]
    o_ero = 0.3 * np.sin(8.0 * x) + 0.3
    r_ero = pywarp.interp_remap(v, o_ero, 1.0, 0.0, 1.0)
    ax.plot(x, v, color="C0", lw=1.2, ls="--", label="v = sin x")
    ax.plot(x, o_ero, color="C1", lw=1.0, alpha=0.8, label="o_min = 0.3 sin 8x + 0.3")
    ax.plot(x, r_ero, color="C4", lw=2, label="remap(v, o_min, 1, 0, 1)")
    ax.fill_between(x, r_ero, 0.0, where=r_ero < 0.0, color="C4", alpha=0.25, label="< 0: cut off as a density")
    ax.set_title("(c) o_min ≥ 0: the detail erodes (like 2.30)")
    ax.text(1.5 * np.pi, -1.18, f"(continues to {r_ero.min():.1f})", ha="center", fontsize=8, color="C4",
            bbox=dict(facecolor="white", alpha=0.9, edgecolor="none", pad=1.5))
    for ax in axes:
        ax.axhline(0.0, color="0.5", lw=0.8)
        ax.set_xlim(0.0, 2.0 * np.pi)
        ax.set_ylim(-1.25, 1.45)
        ax.set_xticks(np.arange(0, 2.01, 0.5) * np.pi)
        ax.set_xticklabels(["0", "π/2", "π", "3π/2", "2π"])
        ax.set_xlabel("x")
        ax.grid(alpha=0.3)
        ax.legend(loc="lower left", fontsize=8, frameon=True, framealpha=0.9)
    fig.suptitle("remap (vc-2.27) applied to trigonometric functions: the shape keeps its peak, the high-frequency "
                 "o_min reshapes its lower parts", fontsize=11)
    fig.subplots_adjust(left=0.04, right=0.99, bottom=0.13, top=0.86, wspace=0.15)
    out = out_dir / "fig-2.14.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
