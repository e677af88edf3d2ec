"""Figure rr-fig-3.1: the double cone of Wang and Wade (the text's reference [2], MS Flight Simulator 2004) -- a
schematic: a double cone centred on the viewer carries scrolling rain-streak textures; for a moving viewer the cone
is tilted along the relative velocity of the rain, so the streaks fall towards the viewer. Output:
figures/rr/fig-3.1.png.
"""
# %% [markdown]
# Before the particle method of the text, the review chapter describes the cheapest way to draw rain around a camera:
# two cones joined at their bases, the viewer at the centre, textured with rain streaks that scroll down the surface
# (Wang & Wade 2004). Nothing of the scene is refracted: the textures are drawn over the frame. The text rejects it for
# its lack of interaction with the scene -- the motivation for refracting particles (rr-alg-3.1).
#
# Panel (a): the cone for a viewer at rest, the rain falling vertically. Panel (b): a viewer moving at v through rain
# falling at w: the cone's axis is tilted along w - v, the rain's velocity relative to the viewer, so its streaks meet
# the viewer at the right angle.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from pywarp.tutorial import fit_text  # noqa: E402

R, HC = 1.0, 1.4  # cone radius at the viewer's height and half height (apex to base)


def cone_axes(tilt_deg):
    """Rotation about the x axis by the tilt (the cone axis leans towards -y)."""
    t = np.radians(tilt_deg)
    return np.array([[1, 0, 0], [0, np.cos(t), -np.sin(t)], [0, np.sin(t), np.cos(t)]])


def draw(ax, tilt_deg, title, rng, quick):
    rot = cone_axes(tilt_deg)
    n = 24 if quick else 48
    th = np.linspace(0, 2 * np.pi, n)
    z = np.linspace(-HC, HC, n)
    tt, zz = np.meshgrid(th, z)
    rr = R * (1 - np.abs(zz) / HC)
    pts = np.stack([rr * np.cos(tt), rr * np.sin(tt), zz], -1) @ rot.T
    ax.plot_surface(pts[..., 0], pts[..., 1], pts[..., 2], color="#9cc3e6", alpha=0.18, linewidth=0.2,
                    edgecolor="#5a8fc0")
    # streaks of the texture: short segments along the cone's generatrices, scrolling down
    for _ in range(90 if quick else 260):
        a = rng.uniform(0, 2 * np.pi)
        z0 = rng.uniform(-HC + 0.1, HC - 0.1)
        z1 = z0 - 0.18
        seg = np.array([[R * (1 - abs(zz_) / HC) * np.cos(a), R * (1 - abs(zz_) / HC) * np.sin(a), zz_]
                        for zz_ in (z0, z1)]) @ rot.T
        ax.plot(*seg.T, color="#2d5f8f", lw=0.8, alpha=0.8)
    ax.scatter([0], [0], [0], color="red", s=40, depthshade=False)
    ax.text(0.05, 0.05, 0.08, "viewer", color="red", fontsize=9)
    # the view direction
    ax.quiver(0, 0, 0, 0, 1.3, 0, color="red", arrow_length_ratio=0.15, lw=1.2)
    # the fall direction relative to the viewer (along the axis, downward)
    axis = rot @ np.array([0, 0, -1.0])
    ax.quiver(*(rot @ np.array([0, 0, HC + 0.35])), *(axis * 0.7), color="k", arrow_length_ratio=0.2, lw=1.5)
    ax.set_title(title, fontsize=9)
    ax.set_xlim(-1.2, 1.2)
    ax.set_ylim(-1.2, 1.2)
    ax.set_zlim(-1.6, 1.9)
    ax.set_box_aspect((1, 1, 1.45))
    ax.view_init(elev=14, azim=-60)
    ax.set_axis_off()


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(3)
    fig = plt.figure(figsize=(11, 6.2), dpi=70 if quick else 120)
    draw(fig.add_subplot(1, 2, 1, projection="3d"), 0.0,
         "(a) viewer at rest: the streak textures scroll straight down", rng, quick)
    draw(fig.add_subplot(1, 2, 2, projection="3d"), -30.0,  # the top leans forward: the rain comes from ahead
         "(b) viewer moving forward: the cone tilted along the\nrain's velocity relative to the viewer (here 30 deg)",
         rng, quick)
    fig.suptitle("Fig 3.1 — the double cone of Wang & Wade [2] (schematic): textured cones around the viewer, no "
                 "refraction of the scene", fontsize=10)
    fit_text(fig, tight_layout=True)  # the layout, with titles and labels that fit (legible in quick mode)
    path = out_dir / "fig-3.1.png"
    fig.savefig(path)
    plt.close(fig)
    return [path]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
