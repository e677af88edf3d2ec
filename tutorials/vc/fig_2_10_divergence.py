"""Figure vc-fig-2.10: the divergence operator on three planar vector fields -- everything flows outward (div > 0),
everything converges (div < 0), balanced (div = 0) -- plus the divergence of curl noise.

The example fields are the catalogue's: F = (x, y) (div = +2), F = (-x, -y) (-2) and the rotation F = (-y, x) (0).
Their divergence (vc-2.25, summed over i = 1..n -- the printed i = 0 is an index error) is computed in this tutorial
with NumPy central differences: the library's divergence function (pywarp.noise_divergence3) takes Perlin noise as
its field, not an arbitrary one. The fourth panel (not in the thesis) is 2-D curl noise from the library,
pywarp.noise_curl2 (vc-A7), whose NumPy divergence vanishes -- the property vc-2.26 means (its printed formula says
"curl = 0" instead); the library's own residual pywarp.noise_curl_property (vc-2.26) of the 3-D curl noise
(pywarp.noise_curl3, eq. 2.23) is quoted too. Output: figures/vc/fig-2.10.png.
"""
# %% [markdown]
# The divergence measures how much a vector field spreads out from a point:
#
#     div F = dF_1/dx_1 + ... + dF_n/dx_n          (2.25; in the plane dF_x/dx + dF_y/dy)
#
# Picture the field as the velocity of a fluid. Around a point with div F > 0 more fluid leaves a small box than
# enters it -- a source; with div F < 0 more enters -- a sink; with div F = 0 inflow and outflow balance, the fluid
# is incompressible. A rotation (c) has no divergence at all, although its curl (fig 2.9) is not zero: curl and
# divergence measure independent things.
#
# Curl noise (d) is divergence-free by construction (the divergence of a curl is always zero): smoke and dust moved
# by it neither pile up nor thin out, which is why it looks like a real fluid flow.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

FIELDS = (("(a) F = (x, y): outflow, source", lambda x, y: (x, y)),
          ("(b) F = (-x, -y): inflow, sink", lambda x, y: (-x, -y)),
          ("(c) F = (-y, x): rotation, balanced", lambda x, y: (-y, x)))


def div_central(field, x, y, h=1e-3):
    """div F = dF_x/dx + dF_y/dy by central differences of the field function (float64)."""
    return ((field(x + h, y)[0] - field(x - h, y)[0]) + (field(x, y + h)[1] - field(x, y - h)[1])) / (2.0 * h)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 64 if quick else 200
    q = 11 if quick else 13
    fig, axes = plt.subplots(1, 4, figsize=(16, 4.9), dpi=80 if quick else 110)
    vlim = 3.0

    # %% [markdown]
    # The analytic fields on [-1, 1]²: background = the divergence by central differences, arrows = the field.

    # %%
    g = np.linspace(-1.0, 1.0, n)
    X, Y = np.meshgrid(g, g)
    a = np.linspace(-0.9, 0.9, q)
    AX, AY = np.meshgrid(a, a)
    for ax, (title, field) in zip(axes[:3], FIELDS):
        div = div_central(field, X, Y)
        im = ax.imshow(div, cmap="PuOr_r", vmin=-vlim, vmax=vlim, origin="lower", extent=(-1, 1, -1, 1))
        u, v = field(AX, AY)
        ax.quiver(AX, AY, u, v, color="k", angles="xy", pivot="middle", scale=14, width=0.005)
        ax.text(0.03, 0.03, f"div F = {float(np.mean(div)) + 0.0:+.2f}", transform=ax.transAxes, fontsize=9,
                bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))
        ax.set_title(title, fontsize=10)

    # %% [markdown]
    # Curl noise from the library: v = (dψ/dy, -dψ/dx) with the Perlin stream function ψ = N(x, y, 0), over 2 x 2
    # lattice cells. Its divergence by NumPy central differences of v (sampled with the same library function, with
    # the library's step h = 1/256) is zero up to float32 round-off, drawn on the same colour scale as (a)-(c).
    # (With a different outer step the two mixed differences sample different points and leave an O(h²)
    # truncation error instead: still tiny, but not round-off.)

    # %%
    ax = axes[3]
    L = 2.0
    h = 1.0 / 256.0  # the library's step: the two mixed differences then use the same four samples and cancel
    m = 64 if quick else 256  # a power of two: every sample x, x +- h, x +- 2h is exact in float32
    gn = (np.arange(m) + 0.5) * (L / m)
    NX, NY = np.meshgrid(gn, gn)

    def curl_noise(x, y):
        v = pywarp.noise_curl2(x, y).astype(np.float64)  # seed 0, h = 1/256 (defaults); shape (..., 2)
        return v[..., 0], v[..., 1]

    div = div_central(curl_noise, NX, NY, h=h)
    ax.imshow(div, cmap="PuOr_r", vmin=-vlim, vmax=vlim, origin="lower", extent=(0, L, 0, L))
    an = (np.arange(q) + 0.5) * (L / q)
    NAX, NAY = np.meshgrid(an, an)
    u, v = curl_noise(NAX, NAY)
    ax.quiver(NAX, NAY, u, v, color="k", angles="xy", pivot="middle", scale=12, width=0.005)
    # the library's own check of vc-2.26 on the 3-D curl noise (nested central differences, float32)
    res = pywarp.noise_curl_property(NX[::4, ::4], NY[::4, ::4], 0.5)
    ax.text(0.03, 0.03, f"NumPy: max |div v| = {np.abs(div).max():.1e}\n"
                        f"noise_curl_property (3-D): {np.abs(res).max():.1e}",
            transform=ax.transAxes, fontsize=8, bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))
    ax.set_title("(d) curl noise v = pywarp.noise_curl2 (vc-A7)\ndivergence-free (2.26, corrected)", fontsize=10)
    for ax in axes:
        ax.set_aspect("equal")
        ax.tick_params(labelsize=7)
    fig.subplots_adjust(left=0.03, right=0.92, bottom=0.08, top=0.80, wspace=0.15)
    cax = fig.add_axes((0.935, 0.12, 0.01, 0.62))
    fig.colorbar(im, cax=cax).set_label("div F = ∂F_x/∂x + ∂F_y/∂y", fontsize=9)
    fig.suptitle("Divergence operator (vc-2.25): arrows = the field, colour = its divergence by NumPy central "
                 "differences", fontsize=11)
    out = out_dir / "fig-2.10.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
