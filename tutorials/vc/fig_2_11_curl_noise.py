"""Figure vc-fig-2.11: curl noise with different bases -- (a) Perlin noise as a 2-D stream function, (b) Perlin noise
as a 3-D vector potential, (c) Worley noise as a 2-D stream function.

The thesis names neither the bases nor the construction (vc-A7 is ambiguous: the 2-D curl, eq. 2.24, of a 2-D field is
a scalar); the two standard readings of Bridson et al. (2007) are shown. (a) pywarp.noise_curl2 (vc-A7 reading (i)):
psi = N(x, y, 0), v = (dpsi/dy, -dpsi/dx). (b) pywarp.noise_curl3 (vc-2.23, reading (ii)): psi = (N(p), N(p + o1),
N(p + o2)) with large offsets, v = curl psi, slice z = 0.5. (c) the same 2-D construction with a Worley stream function
psi = F1 (pywarp.noise_worley3, vc-A3); the library has no Worley curl noise, so its derivatives are NumPy central
differences of library samples. Perlin seed 0, 4 x 4 lattice cells; Worley 4 x 4 cells, seed 2; central-difference
step 1/256 cell. The top row shows the base noises (pywarp.noise_perlin3, vc-A1, and the Worley F1).
Output: figures/vc/fig-2.11.png.
"""
# %% [markdown]
# Curl noise turns a scalar noise into a swirling velocity field that looks like fluid flow (smoke, wind).
# In 2-D, take a noise psi as a *stream function* and rotate its gradient by 90°:
#
#     v = (dpsi/dy, -dpsi/dx)
#
# The velocity is then tangent to the contour lines of psi (the flow circles around the bright and dark spots of the
# top row) and it is divergence-free: nothing piles up, as in an incompressible fluid (fig 2.10 (d)).
# In 3-D one needs three noises -- here the same Perlin noise at three far-apart offsets -- as a *vector potential*
# psi, and v = curl psi (2.23). Panel (b) shows a plane through that 3-D flow: the arrows show the in-plane part
# (vx, vy) and the colour the full speed including vz. The in-plane part alone can converge or spread where the flow
# leaves the plane, although the 3-D field is divergence-free.
#
# The base noise shapes the flow: smooth Perlin noise gives smooth eddies of every size; Worley noise (c), whose F1 is
# the distance to the nearest feature point, gives one vortex around every feature point with nearly constant speed,
# and shear lines where two cells meet (where the distance function has a kink). The speed is constant along each
# circle but differs from cell to cell: the feature points sit at different depths off the slicing plane, and the
# in-plane slope of the 3-D distance r is r_xy / r. Where F1 is clamped to 1 (far from every point) v = 0.

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
    L = 4  # cells shown (Perlin lattice cells / Worley cells)
    n = 64 if quick else 256  # image resolution
    ns = 48 if quick else 96  # streamline grid
    z3, worley_seed, worley_z = 0.5, 2, 0.4
    h = 1.0 / 256.0  # central-difference step, in cells

    def grid(m):
        g = (np.arange(m) + 0.5) * (L / m)
        return g, *np.meshgrid(g, g)

    # %% [markdown]
    # (a) and (b): the library's curl noise, on the image grid (speed) and on a coarser grid (streamlines).

    # %%
    def perlin2d(x, y):
        v = pywarp.noise_curl2(x, y)  # seed 0, h = 1/256 lattice units (defaults); shape (..., 2)
        return v[..., 0], v[..., 1]

    def perlin3d(x, y):
        v = pywarp.noise_curl3(x, y, z3)  # shape (..., 3)
        return v[..., 0], v[..., 1], v[..., 2]

    # %% [markdown]
    # (c): Worley noise as the stream function. Coordinates are in cells; the noise has period 1, so the library
    # is called at x / cells. v = (dpsi/dy, -dpsi/dx) by central differences (step 1/256 of a cell, float64
    # differences of the float32 samples).

    # %%
    def worley_psi(x, y):
        return pywarp.noise_worley3(np.asarray(x) / L, np.asarray(y) / L, worley_z, L, worley_seed).astype(np.float64)

    def worley2d(x, y):
        return ((worley_psi(x, y + h) - worley_psi(x, y - h)) / (2 * h),
                -(worley_psi(x + h, y) - worley_psi(x - h, y)) / (2 * h))

    g, X, Y = grid(n)
    gs_, SX, SY = grid(ns)
    bases = (
        ("(a) Perlin, 2-D stream function\npywarp.noise_curl2 (vc-A7)", pywarp.noise_perlin3(X, Y, 0.0), perlin2d,
         "ψ = N(x, y, 0)"),
        (f"(b) Perlin, 3-D vector potential, slice z = {z3}\npywarp.noise_curl3 (vc-2.23)",
         pywarp.noise_perlin3(X, Y, z3), perlin3d, "ψ_x = N(x, y, z) (1st of 3 components)"),
        ("(c) Worley F1, 2-D stream function\nNumPy differences of pywarp.noise_worley3", worley_psi(X, Y), worley2d,
         "ψ = F1(x, y)"),
    )
    fig, axes = plt.subplots(2, 3, figsize=(13.5, 9.6), dpi=80 if quick else 110)
    for j, (title, psi, field, psi_label) in enumerate(bases):
        ax = axes[0, j]
        im = ax.imshow(psi, cmap="gray", origin="lower", extent=(0, L, 0, L), interpolation="nearest")
        fig.colorbar(im, ax=ax, fraction=0.046, pad=0.02).ax.tick_params(labelsize=7)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel(f"base noise {psi_label}", fontsize=9)

        ax = axes[1, j]
        comps = [np.asarray(c, dtype=np.float64) for c in field(X, Y)]
        speed = np.sqrt(sum(c * c for c in comps))
        im = ax.imshow(speed, cmap="viridis", origin="lower", extent=(0, L, 0, L), interpolation="nearest",
                       vmin=0.0, vmax=float(np.percentile(speed, 99.5)))
        fig.colorbar(im, ax=ax, fraction=0.046, pad=0.02).ax.tick_params(labelsize=7)
        su, sv = (np.asarray(c, dtype=np.float64) for c in field(SX, SY)[:2])
        ax.streamplot(gs_, gs_, su, sv, color="white", linewidth=0.6, density=0.6 if quick else 1.6,
                      arrowsize=0.6)
        ax.set_xlim(0, L)
        ax.set_ylim(0, L)
        ax.set_xlabel("streamlines of (v_x, v_y); colour = |v|" + (" incl. v_z" if len(comps) == 3 else ""),
                      fontsize=9)
    for ax in axes.flat:
        ax.set_aspect("equal")
        ax.tick_params(labelsize=7)
    axes[0, 0].set_ylabel("base noise (potential)")
    axes[1, 0].set_ylabel("curl noise v")
    fig.suptitle(f"Curl noise with different bases (vc-A7, Bridson et al. 2007): {L} x {L} cells, {n}² px, "
                 "central differences with step 1/256 cell", fontsize=11)
    fig.subplots_adjust(left=0.05, right=0.97, bottom=0.05, top=0.90, wspace=0.18, hspace=0.22)
    out = out_dir / "fig-2.11.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
