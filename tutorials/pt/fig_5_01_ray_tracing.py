"""Figure pt-fig-5.1: the ray tracing algorithm -- view ray, nearest hit, shadow ray towards the light.

A schematic computed with the library's analytic ray-sphere intersection (pt-alg-5.1, pywarp.sdf_ray_sphere) in the
plane z = 0: rays from the camera through the pixels of an image plane, the nearest of two spheres for each, and a
shadow ray from each hit point to the light that is tested against the spheres the same way. Output:
figures/pt/fig-5.1.png.
"""
# %% [markdown]
# Ray tracing shoots one ray per pixel from the camera through the image plane and looks for the nearest object it
# intersects -- analytically, here with the quadratic of a ray and a sphere. From the hit point a secondary (shadow)
# ray goes to the light: if it meets an object first, the point is in shadow.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

SPHERES = [((6.0, 0.6, 0.0), 1.6), ((3.2, 3.2, 0.0), 0.8)]
LIGHT = np.array([-0.5, 6.0, 0.0])
CAMERA = np.array([-1.5, 1.0, 0.0])


def _nearest(ro, rd):
    ts = [pywarp.sdf_ray_sphere(ro, rd, c, r) for c, r in SPHERES]
    ts = [(t, k) for k, t in enumerate(ts) if t > 1e-4]
    return min(ts) if ts else (None, None)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(10, 6.4), dpi=70 if quick else 110)
    for (c, r), col in zip(SPHERES, ("#7aa6d9", "#d98a5b")):
        ax.add_patch(plt.Circle(c[:2], r, color=col, alpha=0.9))
    plane_x = 0.5
    ax.plot([plane_x, plane_x], [-1.0, 3.0], "k-", lw=3, alpha=0.4)
    ax.text(plane_x - 0.1, 3.15, "image plane", ha="center", fontsize=9)
    ax.plot(*CAMERA[:2], "ks", ms=9)
    ax.text(CAMERA[0], CAMERA[1] - 0.45, "camera", ha="center", fontsize=9)
    ax.plot(*LIGHT[:2], "o", color="gold", ms=16, mec="k")
    ax.text(LIGHT[0] + 0.35, LIGHT[1], "light", va="center", fontsize=9)
    for y in np.linspace(-0.8, 2.8, 9):
        rd = np.array([plane_x, y, 0.0]) - CAMERA
        rd /= np.linalg.norm(rd)
        t, k = _nearest(CAMERA, rd)
        if t is None:
            end = CAMERA + 9.5 * rd
            ax.plot(*zip(CAMERA[:2], end[:2]), color="0.6", lw=1, ls=":")
            continue
        hit = CAMERA + t * rd
        ax.plot(*zip(CAMERA[:2], hit[:2]), color="k", lw=1)
        ax.plot(*hit[:2], "k.", ms=7)
        sd = LIGHT - hit
        dist = np.linalg.norm(sd)
        sd /= dist
        ts, _ = _nearest(hit + 1e-3 * sd, sd)
        blocked = ts is not None and ts < dist
        end = hit + (ts if blocked else dist) * sd
        ax.plot(*zip(hit[:2], end[:2]), color="r" if blocked else "goldenrod", lw=1, ls="--")
        if blocked:
            ax.plot(*end[:2], "rx", ms=7)
    ax.plot([], [], "k-", label="view ray to the nearest hit (analytic, pt-alg-5.1)")
    ax.plot([], [], color="goldenrod", ls="--", label="shadow ray reaches the light: lit")
    ax.plot([], [], "r--", label="shadow ray blocked: in shadow")
    ax.plot([], [], color="0.6", ls=":", label="no hit: background")
    ax.legend(loc="lower right", fontsize=8)
    ax.set_xlim(-2.2, 9.0)
    ax.set_ylim(-1.8, 7.2)
    ax.set_aspect("equal")
    ax.set_title("Ray tracing (pt-alg-5.1): nearest analytic intersection per pixel, then a shadow ray to the light",
                 fontsize=10)
    ax.set_xticks([])
    ax.set_yticks([])
    fig.tight_layout()
    out = out_dir / "fig-5.1.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
