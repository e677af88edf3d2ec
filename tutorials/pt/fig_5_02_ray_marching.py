"""Figure pt-fig-5.2: ray marching in the basic version (fixed steps) and with a variable step from an SDF.

A schematic computed with the library in the plane z = 0 of the "union" scene of pywarp.sdf_scene (pt-alg-4.1: box 0.7
and sphere 0.9): left, fixed steps of 0.35 tested for a sign change of the SDF; right, sphere tracing (pt-alg-5.2,
pywarp.sdf_sphere_trace), each step a circle of the SDF's radius -- the successive positions are the t of runs with
max_steps = 1, 2, 3, ... Output: figures/pt/fig-5.2.png.
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
TARGET = np.array([0.3, 0.8, 0.0])  # a ray that grazes the top of the sphere: many short steps


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 120 if quick else 400
    x, y = np.meshgrid(np.linspace(-4.6, 1.6, n), np.linspace(-1.6, 2.6, int(n * 4.2 / 6.2)))
    d = pywarp.sdf_scene(np.stack([x, y, np.zeros_like(x)], -1), scene="union")
    rd = (TARGET - RO) / np.linalg.norm(TARGET - RO)
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.2), dpi=70 if quick else 100)
    for ax in axes:
        ax.contourf(x, y, d, levels=[-10, 0], colors=["#7aa6d9"])
        ax.contour(x, y, d, levels=np.arange(0.5, 5, 0.5), colors="0.8", linewidths=0.6)
        ax.plot(*RO[:2], "ks", ms=8)
        ax.set_aspect("equal")
        ax.set_xlim(x.min(), x.max())
        ax.set_ylim(y.min(), y.max())
        ax.set_xticks([])
        ax.set_yticks([])

    # fixed steps: t = k STEP until the SDF changes sign
    ax = axes[0]
    k = 0
    while True:
        p = RO + k * STEP * rd
        inside = pywarp.sdf_scene(p, scene="union") < 0
        ax.plot(*p[:2], "o", color="r" if inside else "k", ms=4)
        if inside or k > 40:
            break
        k += 1
    ax.plot(*zip(RO[:2], p[:2]), "k-", lw=0.8)
    ax.set_title(f"basic ray marching: fixed step {STEP}, {k + 1} tests; hit known to within one step (red)",
                 fontsize=10)

    # sphere tracing: the position after each step, and the circle of radius d(p) around it
    ax = axes[1]
    t_prev = 0.0
    for steps in range(1, 30):
        t, used, hit = pywarp.sdf_sphere_trace(RO, rd, steps, 1e-3, 50.0, scene="union")
        p = RO + t_prev * rd
        r = float(pywarp.sdf_scene(p, scene="union"))
        ax.add_patch(plt.Circle(p[:2], r, fill=False, color="k", lw=0.7))
        ax.plot(*p[:2], "ko", ms=3)
        if hit:
            ax.plot(*(RO + t * rd)[:2], "ro", ms=5)
            break
        t_prev = float(t)
    ax.plot(*zip(RO[:2], (RO + t * rd)[:2]), "k-", lw=0.8)
    ax.set_title(f"sphere tracing (pt-alg-5.2): step = SDF distance, {int(used)} evaluations to precision 1e-3",
                 fontsize=10)
    fig.suptitle("Ray marching with fixed steps vs. variable steps from an SDF (slice z = 0 of the union scene; grey: "
                 "distance contours every 0.5)", fontsize=11)
    fig.tight_layout()
    out = out_dir / "fig-5.2.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
