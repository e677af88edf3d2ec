"""Figure pt-fig-7.8: the vector that brings light reflected from the environment into the camera: l from the water
point to the camera, n the water normal, r_i the sought direction, angle theta_i (after Akenine-Moller et al.).

Equations: pt-alg-7.3.4 (r_i = 2 (n . l) n - l = reflect(rd, n), rd = -l), pt-7.4 (the weight |v . n|^kappa at the
same angle, annotated). A schematic with a tilted wave normal; the numbers are computed, not drawn by hand.
Output: figures/pt/fig-7.8.png.
"""
# %% [markdown]
# The camera sees the water point along rd = -l. The light that reaches it by reflection comes from the mirror
# direction r_i = 2 (n . l) n - l: the terrain scene looks up the sky and the clouds in that direction. With a wave
# normal tilted away from the vertical, r_i swings; the scene flips r_i above the horizon if a strong tilt sends it
# below.

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
    tilt = np.radians(8.0)
    n = np.array([np.sin(tilt), np.cos(tilt)])
    cam = np.array([-2.4, 1.5])
    l = cam / np.linalg.norm(cam)  # noqa: E741
    r = 2.0 * np.dot(n, l) * n - l
    theta = np.degrees(np.arccos(np.dot(n, l)))
    f = pywarp.equation("pt-7.4")(np.array([-l[0], -l[1], 0.0]), np.array([n[0], n[1], 0.0]), 3.0)
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    xs = np.linspace(-3, 3, 200)
    ax.fill_between(xs, -1.0, 0.04 * np.sin(6 * xs), color="#6fa8dc", alpha=0.6)
    ax.plot(xs, 0.04 * np.sin(6 * xs), color="#3d85c6")
    arrow = dict(arrowstyle="-|>", lw=2)
    for vec, name, col in ((n, "n", "k"), (l, "l", "tab:green"), (r, "r_i", "tab:red")):
        ax.annotate("", xy=1.6 * vec, xytext=(0, 0), arrowprops={**arrow, "color": col})
        ax.text(*(1.72 * vec), name, color=col, fontsize=13, ha="center")
    ax.plot(*cam, "ks", ms=10)
    ax.text(cam[0], cam[1] + 0.15, "camera", ha="center")
    ax.plot([0, cam[0]], [0, cam[1]], ":", color="tab:green")
    a0, a1 = np.degrees(np.arctan2(n[1], n[0])), np.degrees(np.arctan2(l[1], l[0]))
    arc = np.radians(np.linspace(a0, a1, 30))
    ax.plot(0.6 * np.cos(arc), 0.6 * np.sin(arc), color="0.3")
    ax.text(-0.55, 0.75, f"theta_i = {theta:.1f} deg", fontsize=10)
    ax.text(0.3, -0.6, f"r_i = 2 (n . l) n - l;  eq. 7.4 weight |v . n|^3 = {float(f):.3f}", fontsize=10)
    ax.set_xlim(-3, 3)
    ax.set_ylim(-1, 2.1)
    ax.set_aspect("equal")
    ax.set_axis_off()
    p = out_dir / "fig-7.8.png"
    fig.savefig(p, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return [p]



if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
