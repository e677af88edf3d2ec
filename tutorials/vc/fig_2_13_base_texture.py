"""Figure vc-fig-2.13: the texture for the base cloud shape -- 2-D slices of the four channels of the 128³ base-shape
texture (R Perlin-Worley, G/B/A inverse-Worley fBm of increasing frequency) and a 2 x 2 tiling that shows it is
seamless.

The texture is made by the library's generator, pywarp.clouds.textures.BasicTextureGenerator with the default
BaseShapeSettings (vc-A9, vc-A13: 128³, seed 0, Perlin 3 octaves from 8 cells, inverse-Worley layers of 4, 8, 16,
32 cells with the fBm weights 0.625 / 0.25 / 0.125, combination 'thesis', gamma 1 of vc-4.6 = identity); the thesis
states none of these values, so the slices match its figure in kind, not texel for texel. The R channel is rebuilt
from its ingredients with pywarp.noise_fbm_perlin3 (vc-2.21) and pywarp.noise_perlin_worley (vc-A8) as a check.
Output: figures/vc/fig-2.13.png.
"""
# %% [markdown]
# The clouds of the thesis are carved out of a few tiling noise volumes. The biggest one, the base-shape texture
# (vc-A9), is a 128 × 128 × 128 RGBA volume; each channel is a different noise:
#
# * R, "Perlin-Worley": a Perlin fBm P (soft, wispy) combined with an inverse-Worley fBm W (round, billowy cells)
#   as R = remap(P, 0, 1, W, 1)² = (W + P (1 − W))² (vc-A8, the combination the thesis chose). Where W is high
#   (inside a billow) R stays high; between the billows the Perlin noise shows through.
# * G, B, A: inverse-Worley fBm with rising frequency (the library fills them from four Worley layers of 4, 8, 16
#   and 32 cells by a sliding window: G = layers 1-3, B = layers 2-4, A = layers 3-4).
#
# The shader (eq. 2.28) uses R as the low-frequency cloud shape and erodes it with 0.625 G + 0.25 B + 0.125 A.
# Here we cut the volume at its middle depth and show each channel in grey.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds.textures import BaseShapeSettings, BasicTextureGenerator  # noqa: E402


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)

    # %% [markdown]
    # Generate the texture (about 1 s for 128³ on the CPU with Warp, tile-parallel; the result is cached on disk, so
    # later runs just load it). Quick mode uses a 32³ texture with the same noise frequencies.

    # %%
    settings = BaseShapeSettings(size=32) if quick else BaseShapeSettings()
    base = BasicTextureGenerator().base_shape(settings)  # (n, n, n, 4) float32 indexed [z, y, x, channel]
    n = settings.size
    iz = n // 2
    sl = base[iz]  # (y, x, 4): the slice z = (iz + 0.5) / n

    # %% [markdown]
    # The R channel from its ingredients: the Perlin fBm mapped to [0, 1], P = clamp(0.5 fbm + 0.5, 0, 1), with the
    # period equal to the frequency so that it tiles, and W = the G channel. The library's R equals
    # pywarp.noise_perlin_worley(P, W) exactly.

    # %%
    u = (np.arange(n) + 0.5) / n  # texel centres
    x, y = np.meshgrid(u, u)
    z = (iz + 0.5) / n
    f = settings.perlin_frequency
    fbm = pywarp.noise_fbm_perlin3(x, y, z, settings.perlin_octaves, float(f), settings.seed, f)
    p = np.clip(0.5 * fbm + 0.5, 0.0, 1.0).astype(np.float32)
    r_check = pywarp.noise_perlin_worley(p, sl[..., 1], combination=settings.combination)
    err = float(np.max(np.abs(r_check - sl[..., 0])))

    fig = plt.figure(figsize=(14, 8.6), dpi=70 if quick else 100)
    gs = fig.add_gridspec(2, 4, height_ratios=(1.0, 1.0), hspace=0.30, wspace=0.12,
                          left=0.03, right=0.975, top=0.88, bottom=0.06)
    cells = settings.worley_cells
    titles = ("(a) R  Perlin-Worley\nremap(P, 0, 1, W, 1)², W = G",
              f"(b) G  inverse-Worley fBm\nlayers {cells}, {2 * cells}, {4 * cells} cells",
              f"(c) B  inverse-Worley fBm\nlayers {2 * cells}, {4 * cells}, {8 * cells} cells",
              f"(d) A  inverse-Worley fBm\nlayers {4 * cells}, {8 * cells} cells")
    for c in range(4):
        ax = fig.add_subplot(gs[0, c])
        ax.imshow(sl[..., c], cmap="gray", vmin=0.0, vmax=1.0, origin="lower", extent=(0, 1, 0, 1),
                  interpolation="nearest")
        ax.set_title(titles[c], fontsize=10)
        ax.text(0.02, 0.02, f"mean {sl[..., c].mean():.2f}", transform=ax.transAxes, fontsize=8,
                bbox=dict(facecolor="white", alpha=0.8, edgecolor="none"))
        ax.set_xticks([0, 0.5, 1])
        ax.set_yticks([0, 0.5, 1])
        ax.tick_params(labelsize=7)
        yrow = (n // 2 + 0.5) / n  # the row of the profile (g), marked by two arrowheads at the edges
        ax.plot([0.0], [yrow], ls="none", marker=">", ms=7, color="tab:orange", clip_on=False)
        ax.plot([1.0], [yrow], ls="none", marker="<", ms=7, color="tab:orange", clip_on=False)

    # %% [markdown]
    # Bottom row. (e) The Perlin ingredient P alone: smooth, without cells. (f) Four copies of the R slice side by
    # side: there is no visible seam at the dashed lines, because every noise is evaluated with a period equal to its
    # number of cells (the texel at x + 1 equals the texel at x exactly). The renderer relies on this: it samples the
    # texture with wrap-around addressing far beyond [0, 1]. (g) One row of texels of every channel: G, B and A
    # wiggle faster and faster -- the increasing frequency that the erosion of eq. 2.28 needs.

    # %%
    ax = fig.add_subplot(gs[1, 0])
    ax.imshow(p, cmap="gray", vmin=0.0, vmax=1.0, origin="lower", extent=(0, 1, 0, 1), interpolation="nearest")
    ax.set_title(f"(e) ingredient P: Perlin fBm, {settings.perlin_octaves} octaves\nfrom {f} cells, mapped to [0, 1]",
                 fontsize=10)
    ax.text(0.02, 0.02, f"R rebuilt from P and G: max |Δ| = {err:.1e}", transform=ax.transAxes, fontsize=8,
            bbox=dict(facecolor="white", alpha=0.8, edgecolor="none"))
    ax.set_xticks([0, 0.5, 1])
    ax.set_yticks([0, 0.5, 1])
    ax.tick_params(labelsize=7)

    ax = fig.add_subplot(gs[1, 1])
    ax.imshow(np.tile(sl[..., 0], (2, 2)), cmap="gray", vmin=0.0, vmax=1.0, origin="lower", extent=(0, 2, 0, 2),
              interpolation="nearest")
    ax.axvline(1.0, color="tab:orange", ls="--", lw=1.0)
    ax.axhline(1.0, color="tab:orange", ls="--", lw=1.0)
    ax.set_title("(f) R tiled 2 × 2: no seams\n(dashed = tile borders)", fontsize=10)
    ax.set_xticks([0, 1, 2])
    ax.set_yticks([0, 1, 2])
    ax.tick_params(labelsize=7)

    ax = fig.add_subplot(gs[1, 2:])
    pos = ax.get_position()
    ax.set_position((pos.x0 + 0.035, pos.y0, pos.width - 0.035, pos.height))  # room for the y label
    row = n // 2
    for c, (name, color) in enumerate((("R", "tab:red"), ("G", "tab:green"), ("B", "tab:blue"), ("A", "0.3"))):
        ax.plot(u, sl[row, :, c], color=color, lw=1.3, label=name)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.15)
    ax.grid(alpha=0.3)
    ax.set_xlabel(f"x (texture coordinate; row y = {(row + 0.5) / n:.3f} of the slice, arrowheads in (a)-(d))")
    ax.set_ylabel("value")
    ax.set_title("(g) one row of texels: G → B → A rise in frequency", fontsize=10)
    ax.legend(loc="upper center", ncol=4, fontsize=9, frameon=False)

    fig.suptitle(f"Base-shape texture (vc-A9): slice z = {z:.3f} of the {n}³ RGBA volume, default BaseShapeSettings "
                 f"(seed {settings.seed}, gamma {settings.gamma:g});\nvalues in [0, 1] shown in grey, black = 0, "
                 "white = 1; every channel tiles with period 1", fontsize=11)
    out = out_dir / "fig-2.13.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
