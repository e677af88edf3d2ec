"""Figure pt-fig-7.6: the light intensity depends on the angle between the surface normal and the direction to the
light (Lambert's cosine law), drawn as a diagram with the curve of eq. 7.1.

Equations: pt-7.1 (I = L_a C_a + L_d C_d max(0, n.l); evaluated with pywarp for the plotted curve, L_a = 0.35, L_d = 1
and a white material, the terrain scene's defaults). Output: figures/pt/fig-7.6.png.
"""
# %% [markdown]
# A beam of light of fixed width spreads over a larger area of the surface the more the surface is tilted away from
# it: the irradiance, and the diffuse brightness, fall as cos(theta) = n . l. Faces turned away (n . l < 0) receive no
# direct light and keep only the ambient term.

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
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    # the diagram: a surface and three beams of the same width arriving at 0, 45 and 70 deg from the normal
    ax.plot([-3.2, 5.6], [0, 0], color="0.3", lw=3)
    for th, col, cx in ((0.0, "tab:orange", -2.0), (45.0, "tab:red", 0.9), (70.0, "tab:purple", 3.9)):
        t = np.radians(th)
        d = np.array([-np.sin(t), np.cos(t)])  # towards the light
        spread = 0.5 / np.cos(t)
        for s_ in (-0.5, 0.5):
            foot = cx + s_ * spread
            ax.plot([foot, foot + 1.8 * d[0]], [0, 1.8 * d[1]], color=col, lw=1.2)
        ax.plot([cx - spread / 2, cx + spread / 2], [0.03, 0.03], color=col, lw=6, solid_capstyle="butt")
        ax.annotate("", xy=(cx, 1.0), xytext=(cx, 0), arrowprops=dict(arrowstyle="-|>", color="k", lw=1.5))
        ax.text(cx + 0.08, 0.85, "n", fontsize=11)
        ax.text(cx, -0.12, f"theta = {th:.0f} deg\narea x {1 / np.cos(t):.2f}", color=col, fontsize=9, ha="center", va="top")
    ax.set_xlim(-3.4, 5.8)
    ax.set_ylim(-0.6, 2.1)
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title("a beam lights 1/cos(theta) times the area")
    # the curve of eq 7.1
    th = np.radians(np.linspace(-180, 180, 361 if not quick else 73))
    n = np.broadcast_to([0.0, 1.0, 0.0], (th.size, 3))
    l = np.column_stack([np.sin(th), np.cos(th), np.zeros_like(th)])  # noqa: E741
    white = np.ones(3)
    i = pywarp.equation("pt-7.1")(n, l, 0.35, white, 1.0, white)
    i_shadow = pywarp.equation("pt-7.1")(n, l, 0.35, white, 1.0, white, 0.0)
    ax2.plot(np.degrees(th), i[:, 0], label="I = L_a C_a + L_d C_d max(0, n.l)  (L_a 0.35, L_d 1)")
    ax2.plot(np.degrees(th), i_shadow[:, 0], "--", label="in shadow: the ambient term only")
    ax2.set_xlabel("angle between n and l (deg)")
    ax2.set_ylabel("intensity")
    ax2.legend(fontsize=8, loc="upper right")
    ax2.set_ylim(0.0, 1.8)
    ax2.set_title("eq. 7.1 for a white material")
    p = out_dir / "fig-7.6.png"
    fig.savefig(p, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return [p]



if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
