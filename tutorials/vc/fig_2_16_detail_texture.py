"""Figure vc-fig-2.16: the texture for cloud details -- 2-D slices of the three channels of the 32³ detail (erosion)
texture, inverse-Worley fBm of increasing frequency in R, G and B.

The texture is made by the library's generator, pywarp.clouds.textures.BasicTextureGenerator with the default
DetailShapeSettings (vc-A10, vc-A13: 32³, seed 0, inverse-Worley layers of 2, 4, 8, 16 cells, fBm weights
0.625 / 0.25 / 0.125, gamma 1); the thesis states none of these values, so the slices match its figure in kind, not
texel for texel. Not in the thesis: the RGB composite, a 2 x 2 tiling (seamless), the gamma correction of vc-4.6
(generator with gamma 2, checked against pywarp.texgen_gamma) and a profile of one row of texels.
Output: figures/vc/fig-2.16.png.
"""
# %% [markdown]
# The base-shape texture gives the clouds their overall shape; the small detail texture (vc-A10) erodes their edges
# into wisps and billows (eq. 2.30). It is only 32 × 32 × 32 texels with three channels, because the shader tiles it
# many times across each cloud. Each channel is a fractional Brownian motion (fBm) of inverse Worley noise -- packed
# bright blobs -- and the frequency rises from R to G to B (layers of 2-8, 4-16 and 8-16 cells by the library's
# sliding window over four Worley layers). The shader mixes them as 0.625 R + 0.25 G + 0.125 B.
#
# With only 32 texels per edge, each texel is visible: the panels draw them as squares (nearest-neighbour); the
# renderer samples the volume trilinearly with wrap-around addressing, so the clouds never see these squares.

# %%
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds.textures import BasicTextureGenerator, DetailShapeSettings  # noqa: E402


def _style(ax, extent=1):
    ax.set_xticks(np.linspace(0, extent, 2 * extent + 1))
    ax.set_yticks(np.linspace(0, extent, 2 * extent + 1))
    ax.tick_params(labelsize=7)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)

    # %% [markdown]
    # Generate the texture (a few hundredths of a second: 32³ texels, cached on disk). It is small already, so quick
    # mode only lowers the image resolution.

    # %%
    settings = DetailShapeSettings()
    gen = BasicTextureGenerator()
    detail = gen.detail_shape(settings)  # (32, 32, 32, 3) float32 indexed [z, y, x, channel]
    n = settings.size
    iz = n // 2
    sl = detail[iz]  # (y, x, 3): the slice z = (iz + 0.5) / n
    z = (iz + 0.5) / n

    fig = plt.figure(figsize=(14, 8.6), dpi=70 if quick else 100)
    gs = fig.add_gridspec(2, 4, hspace=0.30, wspace=0.12, left=0.03, right=0.975, top=0.88, bottom=0.06)
    c0 = settings.worley_cells
    titles = (f"(a) R  inverse-Worley fBm\nlayers {c0}, {2 * c0}, {4 * c0} cells",
              f"(b) G  inverse-Worley fBm\nlayers {2 * c0}, {4 * c0}, {8 * c0} cells",
              f"(c) B  inverse-Worley fBm\nlayers {4 * c0}, {8 * c0} cells")
    row = n // 2
    yrow = (row + 0.5) / n
    for c in range(3):
        ax = fig.add_subplot(gs[0, c])
        ax.imshow(sl[..., c], cmap="gray", vmin=0.0, vmax=1.0, origin="lower", extent=(0, 1, 0, 1),
                  interpolation="nearest")
        ax.set_title(titles[c], fontsize=10)
        ax.text(0.02, 0.02, f"mean {sl[..., c].mean():.2f}", transform=ax.transAxes, fontsize=8,
                bbox=dict(facecolor="white", alpha=0.8, edgecolor="none"))
        ax.plot([0.0], [yrow], ls="none", marker=">", ms=7, color="tab:orange", clip_on=False)  # row of (g)
        ax.plot([1.0], [yrow], ls="none", marker="<", ms=7, color="tab:orange", clip_on=False)
        _style(ax)

    # %% [markdown]
    # (d) The three channels at once, as the GPU stores them (R, G, B of one texel): bright where all three noises
    # are high, coloured where only one is.

    # %%
    ax = fig.add_subplot(gs[0, 3])
    ax.imshow(sl, vmin=0.0, vmax=1.0, origin="lower", extent=(0, 1, 0, 1), interpolation="nearest")
    ax.set_title("(d) composite RGB\n(the texture as stored)", fontsize=10)
    _style(ax)

    # %% [markdown]
    # Bottom row. (e) Four copies of the composite: no seam at the dashed lines -- each Worley layer has a whole
    # number of cells per texture and wraps its cells, so texel 32 is texel 0 again. (f) The gamma correction of
    # vc-4.6, C^(1/γ), is one of the detail settings: γ = 2 lifts the dark creases and thins the contrast. The
    # generator run with gamma=2 equals pywarp.texgen_gamma applied to the γ = 1 texture. (g) One row of texels per
    # channel: R changes slowly, B fastest.

    # %%
    ax = fig.add_subplot(gs[1, 0])
    ax.imshow(np.tile(sl, (2, 2, 1)), vmin=0.0, vmax=1.0, origin="lower", extent=(0, 2, 0, 2),
              interpolation="nearest")
    ax.axvline(1.0, color="white", ls="--", lw=1.0)
    ax.axhline(1.0, color="white", ls="--", lw=1.0)
    ax.set_title("(e) composite tiled 2 × 2: no seams\n(dashed = tile borders)", fontsize=10)
    _style(ax, 2)

    gamma = 2.0
    sl_g = gen.detail_shape(replace(settings, gamma=gamma))[iz]
    err = float(np.max(np.abs(pywarp.texgen_gamma(sl[..., 0], gamma) - sl_g[..., 0])))
    ax = fig.add_subplot(gs[1, 1])
    ax.imshow(sl_g[..., 0], cmap="gray", vmin=0.0, vmax=1.0, origin="lower", extent=(0, 1, 0, 1),
              interpolation="nearest")
    ax.set_title(f"(f) R with gamma = {gamma:g} (vc-4.6)\nC^(1/γ): brighter, less contrast", fontsize=10)
    ax.text(0.02, 0.02, f"vs pywarp.texgen_gamma(R, {gamma:g}): max |Δ| = {err:.1e}", transform=ax.transAxes,
            fontsize=8, bbox=dict(facecolor="white", alpha=0.8, edgecolor="none"))
    _style(ax)

    ax = fig.add_subplot(gs[1, 2:])
    pos = ax.get_position()
    ax.set_position((pos.x0 + 0.035, pos.y0, pos.width - 0.035, pos.height))  # room for the y label
    u = (np.arange(n) + 0.5) / n
    for c, (name, color) in enumerate((("R", "tab:red"), ("G", "tab:green"), ("B", "tab:blue"))):
        ax.plot(u, sl[row, :, c], color=color, lw=1.3, marker="o", ms=2.5, label=name)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.15)
    ax.grid(alpha=0.3)
    ax.set_xlabel(f"x (texture coordinate; row y = {yrow:.3f} of the slice, arrowheads in (a)-(c); dots = texels)")
    ax.set_ylabel("value")
    ax.set_title("(g) one row of texels: R → G → B rise in frequency", fontsize=10)
    ax.legend(loc="upper center", ncol=3, fontsize=9, frameon=False)

    fig.suptitle(f"Detail texture (vc-A10): slice z = {z:.3f} of the {n}³ RGB volume, default DetailShapeSettings "
                 f"(seed {settings.seed}, gamma {settings.gamma:g});\nvalues in [0, 1], black = 0, white = 1; "
                 "each square is one texel", fontsize=11)
    out = out_dir / "fig-2.16.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
