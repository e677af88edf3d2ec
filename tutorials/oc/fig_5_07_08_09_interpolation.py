"""Figures oc-fig-5.7, oc-fig-5.8 and oc-fig-5.9: linear, cosine and cubic interpolation between random samples.

The three printed listings: Linear_Interp a(1 - x) + bx (oc-5.1.4.1), Cosine_Interp with pi written 3.1415927
(oc-5.1.4.2) and the cubic P x^3 + Q x^2 + R x + S through v0, v1 = a, v2 = b, v3 (oc-5.1.4.3), each applied between
consecutive samples (oc-5.1.4: x = 0 -> A, x = 1 -> B) of 10 lattice values of seed 6 (oc-5.1.2). Fig. 5.9 labels
v0..v3 of one interval and draws Catmull-Rom for comparison: the printed cubic's slope at a is v2 - v0, twice
Catmull-Rom's (v2 - v0)/2, so it swings wider. Outputs: figures/oc/fig-5.7.png, figures/oc/fig-5.8.png,
figures/oc/fig-5.9.png.
"""
# %% [markdown]
# Interpolation returns a value between A and B from a position x in [0, 1]. The linear blend joins the samples with
# straight segments (kinks at every sample); the cosine blend eases in and out, so the curve is flat at every
# sample; the cubic uses two more samples, the one before A and the one after B, and passes through the samples
# with a continuous slope. The text calls it very smooth but too expensive for real time -- the benchmark
# `pywarp bench flight` measures that claim. Its slope at A is v2 - v0, twice Catmull-Rom's: it is not the
# Catmull-Rom spline, and it overshoots more.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

SEED, N = 6, 10


def _curves(kind, v, t):
    """The interpolant ``kind`` between samples k and k+1 at the positions k + t, k = 0 .. N-2 (end samples
    repeated as v0 / v3 at the ends)."""
    k = np.arange(N - 1)[:, None]
    x = np.broadcast_to(t, (N - 1, t.size))
    a, b = v[k], v[k + 1]
    if kind == "linear":
        y = pywarp.valuenoise_linear(a, b, x)
    elif kind == "cosine":
        y = pywarp.valuenoise_cosine(a, b, x)
    else:
        v0, v3 = v[np.maximum(k - 1, 0)], v[np.minimum(k + 2, N - 1)]
        y = pywarp.valuenoise_cubic(v0, a, b, v3, x)
    return (k + x).ravel(), np.asarray(y).ravel()


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    t = np.linspace(0.0, 1.0, 25 if quick else 101, dtype=np.float32)
    v = pywarp.valuenoise_lattice(np.arange(N), 0, 0, SEED)
    outs = []

    # %%
    for fig_no, kind, title in ((7, "linear", "linear interpolation: a(1 - x) + b x"),
                                (8, "cosine", "cosine interpolation: f = (1 - cos(3.1415927 x)) / 2"),
                                (9, "cubic", "cubic interpolation: P x^3 + Q x^2 + R x + S")):
        fig, ax = plt.subplots(figsize=(9, 4.2), dpi=80 if quick else 120)
        xs, ys = _curves(kind, v, t)
        ax.plot(xs, ys, color="C0", lw=1.8, label=kind)
        if kind == "cubic":
            # Catmull-Rom through the same samples (slope (v2 - v0)/2), float64 -- for comparison only
            k = np.arange(N - 1)[:, None]
            v0, v1, v2, v3 = (v[np.clip(k + d, 0, N - 1)].astype(np.float64) for d in (-1, 0, 1, 2))
            tt = t.astype(np.float64)
            cr = 0.5 * ((2 * v1) + (-v0 + v2) * tt + (2 * v0 - 5 * v1 + 4 * v2 - v3) * tt ** 2
                        + (-v0 + 3 * v1 - 3 * v2 + v3) * tt ** 3)
            ax.plot((k + tt).ravel(), cr.ravel(), color="C3", lw=1.1, ls="--", label="Catmull-Rom (not the text's)")
            j = 4  # label one interval
            for d, name in zip((-1, 0, 1, 2), ("v0", "v1 = a", "v2 = b", "v3")):
                ax.annotate(name, (j + d, v[j + d]), textcoords="offset points", xytext=(6, 8), fontsize=9)
            ax.axvspan(j, j + 1, color="0.9", zorder=0)
        ax.plot(np.arange(N), v, "o", color="k", ms=5, label="lattice values", zorder=5)
        ax.set_xlabel("x (lattice units)")
        ax.set_ylabel("value")
        ax.set_xlim(-0.2, N - 0.8)
        ax.grid(alpha=0.3)
        ax.legend(loc="lower right", fontsize=8, frameon=False)
        ax.set_title(f"oc fig. 5.{fig_no}: {title}", fontsize=10)
        fig.tight_layout()
        out = out_dir / f"fig-5.{fig_no}.png"
        fig.savefig(out)
        plt.close(fig)
        outs.append(out)
    return outs


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
