"""Figure pt-fig-5.2: ray marching in the basic version (fixed steps) and with a variable step from an SDF.

A schematic computed with the library in the plane z = 0 of the "union" scene of pywarp.sdf_scene (pt-alg-4.1: box 0.7
and sphere 0.9): left, fixed steps of 0.35 tested for a sign change of the SDF; right, sphere tracing (pt-alg-5.2,
pywarp.sdf_sphere_trace), each step a circle of the SDF's radius -- the successive positions are the t of runs with
max_steps = 1, 2, 3, ... Top: a ray aimed at the sphere; bottom: a ray grazing its top, 0.03 above it, along which
sphere tracing creeps in ever shorter steps (the cost of silhouettes) while the fixed march steps on regardless.
Output: figures/pt/fig-5.2.png.
"""
# %% [markdown]
# The basic ray marcher advances by a constant step and checks after each step whether it is inside the surface: small
# steps are slow, large ones can jump over thin objects and the hit is only known to within a step. With a signed
# distance function the step can be the distance to the nearest surface -- a sphere that certainly contains no
# surface -- so the ray takes long steps in empty space and short ones near the surface.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

STEP = 0.35  # fixed step of the basic march (scene units)
RO = np.array([-4.2, 1.9, 0.0])
TARGET = np.array([0.3, 0.8, 0.0])  # a ray aimed at the top of the sphere: it hits
#: A grazing ray: slightly downwards, passing 0.03 above the sphere's top (radius 0.9) and above the box's corners --
#: sphere tracing creeps along the silhouette in ever shorter steps, then leaves; the fixed march just steps on.
RO_GRAZE = np.array([-4.2, 1.269, 0.0])
DIR_GRAZE = np.array([1.0, -0.08, 0.0])


def _fixed(ax, ro, rd):
    """Fixed steps: t = k STEP until the SDF changes sign (or 26 steps)."""
    k = 0
    while True:
        p = ro + k * STEP * rd
        inside = pywarp.sdf_scene(p, scene="union") < 0
        ax.plot(*p[:2], "o", color="r" if inside else "k", ms=4)
        if inside or k >= 25:
            break
        k += 1
    ax.plot(*zip(ro[:2], p[:2]), "k-", lw=0.8)
    return k + 1, bool(inside)


def _sphere_trace(ax, ro, rd):
    """Sphere tracing: the position after each step, and the circle of radius d(p) around it."""
    t_prev = 0.0
    for steps in range(1, 60):
        t, used, hit = pywarp.sdf_sphere_trace(ro, rd, steps, 1e-3, 6.0, scene="union")
        p = ro + t_prev * rd
        r = float(pywarp.sdf_scene(p, scene="union"))
        ax.add_patch(plt.Circle(p[:2], r, fill=False, color="k", lw=0.7))
        ax.plot(*p[:2], "ko", ms=3)
        if hit:
            ax.plot(*(ro + t * rd)[:2], "ro", ms=5)
            break
        if t >= 6.0 or float(t) == t_prev:
            break
        t_prev = float(t)
    ax.plot(*zip(ro[:2], (ro + t * rd)[:2]), "k-", lw=0.8)
    return int(used), bool(hit)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 120 if quick else 400
    x, y = np.meshgrid(np.linspace(-4.6, 1.6, n), np.linspace(-1.6, 2.6, int(n * 4.2 / 6.2)))
    d = pywarp.sdf_scene(np.stack([x, y, np.zeros_like(x)], -1), scene="union")
    rays = (("aimed at the sphere", RO, (TARGET - RO) / np.linalg.norm(TARGET - RO)),
            ("grazing the sphere's top", RO_GRAZE, DIR_GRAZE / np.linalg.norm(DIR_GRAZE)))
    fig, axes = plt.subplots(2, 2, figsize=(14, 9.6), dpi=70 if quick else 100)
    for ax in axes.ravel():
        ax.contourf(x, y, d, levels=[-10, 0], colors=["#7aa6d9"])
        ax.contour(x, y, d, levels=np.arange(0.5, 5, 0.5), colors="0.8", linewidths=0.6)
        ax.set_aspect("equal")
        ax.set_xlim(x.min(), x.max())
        ax.set_ylim(y.min(), y.max())
        ax.set_xticks([])
        ax.set_yticks([])
    for row, (name, ro, rd) in enumerate(rays):
        for ax in axes[row]:
            ax.plot(*ro[:2], "ks", ms=8)
        tests, hit = _fixed(axes[row, 0], ro, rd)
        axes[row, 0].set_title(f"{name}: fixed step {STEP}, {tests} tests, "
                               + ("hit known to within one step (red)" if hit else "no hit"), fontsize=10)
        used, hit = _sphere_trace(axes[row, 1], ro, rd)
        axes[row, 1].set_title(f"{name}: sphere tracing (pt-alg-5.2), {used} evaluations, "
                               + ("hit to precision 1e-3 (red)" if hit else "no hit up to t = 6"), fontsize=10)
    fig.suptitle("Ray marching with fixed steps vs. variable steps from an SDF (slice z = 0 of the union scene; grey: "
                 "distance contours every 0.5)", fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=0.92, wspace=0.03, hspace=0.1)
    out = out_dir / "fig-5.2.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
