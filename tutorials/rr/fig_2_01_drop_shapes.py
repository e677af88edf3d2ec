"""Figure rr-fig-2.1: Beard-Chuang drop shapes (rr-eq1, rr-tab-2.1): (a) radii 1 and 3 mm as tabulated, with
1.5, 2 and 2.5 mm drawn dashed from the interpolation option; (b)-(e) a = 0.5, 1, 3, 4.5 mm against the sphere of
radius a, with volume and axis ratio. Output: figures/rr/fig-2.1.png.
"""
# %% [markdown]
# Beard and Chuang (1987) describe the equilibrium shape of a falling raindrop by a cosine series of the polar angle
# theta, measured from the DOWNWARD vertical (theta = 0 is the bottom of the drop):
#
#     r(theta) = a (1 + sum_{n=0}^{10} C_n cos(n theta))          (rr-eq1)
#
# with the coefficients C_n of Table 2.1 (rr-tab-2.1) for four radii a = 0.5, 1, 3 and 4.5 mm. Surface tension pulls
# a drop toward a sphere, the air pressure below it flattens its bottom: small drops are nearly round, large drops
# look like a hamburger bun -- never like the tear of the popular picture (that is the streak of retinal
# persistence, fig. 3.7).
#
# The thesis's panel (a) also shows 1.5, 2 and 2.5 mm drops, for which Table 2.1 has no coefficients. The library
# refuses those radii unless asked for `interp="linear"` (each C_n linear in a between the rows): they are drawn
# dashed here, as an assumption, not as data.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.kernels import rain  # noqa: E402
from pywarp.rain import drops  # noqa: E402


def profile(a, n, interp="table"):
    """The meridian section (x, y) of the drop, y up: the curve r(theta) revolved to both sides."""
    theta = np.linspace(0.0, np.float32(np.pi), n)
    r = pywarp.rain_drop_radius(theta, a, interp=interp)
    x = np.concatenate([r * np.sin(theta), -(r * np.sin(theta))[::-1]])
    y = np.concatenate([-r * np.cos(theta), (-r * np.cos(theta))[::-1]])
    return x, y


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 91 if quick else 721

    # %% [markdown]
    # Volume and axis ratio (height / width) of each tabulated drop; a is the equal-volume radius (V = 4/3 pi a^3 to
    # 0.12 %).

    # %%
    radii = np.array(rain.SHAPE_RADII)
    volume = drops.drop_volume(radii)
    ratio = drops.drop_axis_ratio(radii)

    fig = plt.figure(figsize=(16, 6.6), dpi=80 if quick else 120)
    gs = fig.add_gridspec(2, 5, width_ratios=(1.2, 1.2, 1, 1, 1))
    ax = fig.add_subplot(gs[:, 0:2])
    for a, ls, interp in ((1.0, "-", "table"), (1.5, "--", "linear"), (2.0, "--", "linear"), (2.5, "--", "linear"),
                          (3.0, "-", "table")):
        x, y = profile(a, n, interp)
        ax.plot(x, y, ls=ls, lw=2 if ls == "-" else 1.2,
                label=f"R = {a:g} mm" + ("" if interp == "table" else " (interpolated C_n)"))
    ax.set_title("(a) radii 1-3 mm (dashed: not in Table 2.1)")
    ax.set_aspect("equal")
    ax.legend(fontsize=8, loc="upper right")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]  (up; theta = 0 points down)")
    ax.grid(alpha=0.3)
    ax.set_xlim(-4.2, 4.2)
    ax.set_ylim(-3.2, 3.6)
    for k, a in enumerate(radii):
        ax = fig.add_subplot(gs[k // 2, 2 + k % 2])
        x, y = profile(a, n)
        t = np.linspace(0, 2 * np.pi, 200)
        ax.plot(a * np.cos(t), a * np.sin(t), color="0.6", ls=":", lw=1, label="sphere of radius a")
        ax.fill(x, y, color="#9cc9ef", alpha=0.7)
        ax.plot(x, y, color="C0", lw=1.5, label="r(theta)")
        ax.plot([0], [0], "k+", ms=6)
        ax.set_aspect("equal")
        lim = 1.3 * a
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_title(f"({'bcde'[k]}) a = {a:g} mm: V / (4/3 pi a^3) = "
                     f"{volume[k] / (4 / 3 * np.pi * a ** 3):.4f},\naxis ratio h/w = {ratio[k]:.3f}", fontsize=9)
        ax.tick_params(labelsize=7)
        if k == 0:
            ax.legend(fontsize=7, loc="lower center")
    # 3-D views of the 1 and 4.5 mm drops from the axisymmetric surface
    for k, a in enumerate((1.0, 4.5)):
        ax = fig.add_subplot(gs[k, 4], projection="3d")
        th, ph = np.meshgrid(np.linspace(0, np.float32(np.pi), 24 if quick else 48),
                             np.linspace(0, 2 * np.pi, 32 if quick else 64))
        P, N = drops.drop_surface(th, ph, a)
        shade = np.clip(N @ np.array([0.4, 0.7, 0.6]) / np.linalg.norm([0.4, 0.7, 0.6]), 0, 1)
        ax.plot_surface(P[..., 0], P[..., 2], P[..., 1], facecolors=plt.cm.Blues(0.35 + 0.6 * shade), linewidth=0,
                        shade=False)
        ax.set_box_aspect((1, 1, 1))
        lim = 1.2 * a
        for s in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
            s(-lim, lim)
        ax.set_title(f"3-D surface, a = {a:g} mm", fontsize=9)
        ax.tick_params(labelsize=6)
        ax.view_init(elev=8, azim=-60)
    fig.suptitle("Beard-Chuang equilibrium drop shapes (rr-eq1 with Table 2.1): small drops are round, large drops "
                 "flatten at the bottom", fontsize=11)
    fig.subplots_adjust(left=0.05, right=0.99, top=0.87, bottom=0.08, wspace=0.3, hspace=0.42)
    out = out_dir / "fig-2.1.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
