"""Figure vc-fig-2.9: the curl (rotation) operator on three planar vector fields -- clockwise rotation (curl_z < 0),
counter-clockwise rotation (curl_z > 0) and no rotation (curl_z = 0) -- plus the same operator on a noise field.

The three example fields are the catalogue's: F = (y, -x) (curl_z = -2), F = (-y, x) (+2) and a constant field (0).
Their curl (vc-2.23, z component = the 2-D curl vc-2.24) is computed in this tutorial with NumPy central differences:
the library's curl functions take Perlin noise as their field, not an arbitrary one. The fourth panel (not in the
thesis) is the library's pywarp.noise_rot2 (vc-2.24) of the planar Perlin field F = (N(p), N(p + o1)) of vc-A7,
checked against NumPy central differences of F sampled with pywarp.noise_perlin3 (vc-A1).
Output: figures/vc/fig-2.9.png.
"""
# %% [markdown]
# The curl measures how much a vector field rotates around a point. For a field in the plane (no z component) the
# curl (2.23) points along z and only its z component survives:
#
#     curl_z F = dF_y/dx - dF_x/dy          (the 2-D curl, 2.24)
#
# Think of a tiny paddle wheel dropped into the flow: curl_z > 0 turns it counter-clockwise (the curl vector points
# out of the page, right-hand rule), curl_z < 0 turns it clockwise (into the page), and a uniform flow only carries it
# along without turning it (curl_z = 0). Curl noise (fig 2.11) is built from exactly these derivatives.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.kernels.noise import CURL_OFFSET_1  # noqa: E402  (public constant: the offset o1 of vc-A7's potential)

# the example fields of the catalogue (vc-fig-2.9)
FIELDS = (("(a) F = (y, -x): clockwise", lambda x, y: (y, -x)),
          ("(b) F = (-y, x): counter-clockwise", lambda x, y: (-y, x)),
          ("(c) F = (1, 0.5): uniform, no rotation", lambda x, y: (np.ones_like(x), 0.5 * np.ones_like(y))))


def curl_z_central(field, x, y, h=1e-3):
    """curl_z = dF_y/dx - dF_x/dy by central differences of the field function (float64)."""
    dfy_dx = (field(x + h, y)[1] - field(x - h, y)[1]) / (2.0 * h)
    dfx_dy = (field(x, y + h)[0] - field(x, y - h)[0]) / (2.0 * h)
    return dfy_dx - dfx_dy


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 64 if quick else 200  # background resolution
    q = 11 if quick else 13  # arrows per side
    fig, axes = plt.subplots(1, 4, figsize=(16, 4.9), dpi=80 if quick else 110)
    vlim = 3.0

    # %% [markdown]
    # The analytic fields on [-1, 1]²: background = the curl by central differences, arrows = the field.

    # %%
    g = np.linspace(-1.0, 1.0, n)
    X, Y = np.meshgrid(g, g)
    a = np.linspace(-0.9, 0.9, q)
    AX, AY = np.meshgrid(a, a)
    for ax, (title, field) in zip(axes[:3], FIELDS):
        curl = curl_z_central(field, X, Y)
        im = ax.imshow(curl, cmap="RdBu_r", vmin=-vlim, vmax=vlim, origin="lower", extent=(-1, 1, -1, 1))
        u, v = field(AX, AY)
        ax.quiver(AX, AY, u, v, color="k", angles="xy", pivot="middle", scale=14, width=0.005)
        c = float(np.mean(curl))
        sign = "⊙ out of the page" if c > 0.5 else ("⊗ into the page" if c < -0.5 else "no rotation")
        ax.text(0.03, 0.03, f"curl_z = {c:+.2f}\n{sign}", transform=ax.transAxes, fontsize=9,
                bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))
        ax.set_title(title, fontsize=10)

    # %% [markdown]
    # The fourth panel is the library's 2-D curl of a noise field: the planar field F = (N(p), N(p + o1)) made of two
    # Perlin evaluations with a large offset o1 (the literal reading of the thesis' curl-noise recipe, vc-A7), and its
    # curl from pywarp.noise_rot2. The curl of a noise field changes sign from place to place: red eddies turn
    # counter-clockwise, blue ones clockwise. As a check, NumPy central differences of F (sampled with
    # pywarp.noise_perlin3, same step h = 1/256) give the same curl up to float32 round-off.

    # %%
    ax = axes[3]
    L = 2.0  # lattice cells shown
    gn = (np.arange(n) + 0.5) * (L / n)
    NX, NY = np.meshgrid(gn, gn)
    rot = pywarp.noise_rot2(NX, NY)  # seed 0, h = 1/256 lattice units (defaults)
    o1x, o1y, o1z = CURL_OFFSET_1

    def noise_field(x, y):
        return (pywarp.noise_perlin3(x, y, 0.0).astype(np.float64),
                pywarp.noise_perlin3(x + o1x, y + o1y, o1z).astype(np.float64))

    check = curl_z_central(noise_field, NX, NY, h=1.0 / 256.0)  # the library's default step
    err = float(np.max(np.abs(check - rot)))
    im = ax.imshow(rot, cmap="RdBu_r", vmin=-vlim, vmax=vlim, origin="lower", extent=(0, L, 0, L))
    an = (np.arange(q) + 0.5) * (L / q)
    NAX, NAY = np.meshgrid(an, an)
    fu, fv = noise_field(NAX, NAY)
    ax.quiver(NAX, NAY, fu, fv, color="k", angles="xy", pivot="middle", scale=6, width=0.005)
    ax.text(0.03, 0.03, f"NumPy check: max |Δ| = {err:.1e}", transform=ax.transAxes, fontsize=8,
            bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))
    ax.set_title("(d) noise field F = (N(p), N(p + o1))\ncurl by pywarp.noise_rot2 (vc-2.24)", fontsize=10)
    for ax in axes:
        ax.set_aspect("equal")
        ax.tick_params(labelsize=7)
    fig.subplots_adjust(left=0.03, right=0.92, bottom=0.08, top=0.80, wspace=0.15)
    cax = fig.add_axes((0.935, 0.12, 0.01, 0.62))
    fig.colorbar(im, cax=cax).set_label("curl_z = ∂F_y/∂x - ∂F_x/∂y", fontsize=9)
    fig.suptitle("Curl operator (vc-2.23, vc-2.24): arrows = the field, colour = its curl; (a)-(c) curl by NumPy "
                 "central differences, (d) by the library", fontsize=11)
    out = out_dir / "fig-2.9.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
