"""Extra figure vc-extra-curl-texture: the generated 2-D curl-noise texture -- its magnitude with streamlines, the
Perlin stream function it comes from, its two channels, a 2 x 2 tiling and its divergence.

Not a figure of the thesis: the thesis loads its curl-noise texture from a file shipped with the library (vc-A11) and
only says it holds curl noise of Perlin noise; the library generates it with
pywarp.clouds.textures.BasicTextureGenerator().curl_noise and the default CurlNoiseSettings (128², Perlin noise of 4 cells
per texture, seed 0, central-difference step 1/256 cell). Construction: reading (i) of vc-A7, v = (∂ψ/∂y, −∂ψ/∂x)
for the stream function ψ = tileable Perlin noise (vc-A2, drawn with pywarp.noise_perlin3_tiled), which is
divergence-free (vc-2.25, the property of vc-2.26 as corrected). Output: figures/vc/extra-curl-texture.png.
"""
# %% [markdown]
# Curl noise is a swirling velocity field. The shader of the thesis uses it to push the sample positions of the
# detail texture around (eq. 2.30), which makes the cloud edges look torn by turbulent wind.
#
# The 2-D recipe (Bridson et al. 2007): take a smooth scalar noise ψ(x, y) -- here Perlin noise -- and rotate its
# gradient by 90°:  v = (∂ψ/∂y, −∂ψ/∂x). The velocity then runs ALONG the contour lines of ψ, never across them, so
# the flow swirls around the hills and valleys of the noise and has no sources or sinks: its divergence
# ∂v_x/∂x + ∂v_y/∂y = ∂²ψ/∂x∂y − ∂²ψ/∂y∂x is zero. That is what keeps the displaced texture from bunching up or
# thinning out.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds.textures import BasicTextureGenerator, CurlNoiseSettings  # noqa: E402


def _style(ax, extent=1):
    ax.set_xticks(np.linspace(0, extent, 2 * extent + 1))
    ax.set_yticks(np.linspace(0, extent, 2 * extent + 1))
    ax.tick_params(labelsize=7)
    ax.set_aspect("equal")


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)

    # %% [markdown]
    # Generate the texture: (size, size, 2) float32 indexed [y, x, component], in noise-lattice units (the change of
    # ψ per lattice cell). The texel (ix, iy) sits at the texture coordinate ((ix + 0.5)/size, (iy + 0.5)/size).

    # %%
    settings = CurlNoiseSettings(size=32) if quick else CurlNoiseSettings()
    curl = BasicTextureGenerator().curl_noise(settings)
    n, f, h = settings.size, settings.frequency, settings.fd_step
    vx, vy = curl[..., 0].astype(np.float64), curl[..., 1].astype(np.float64)
    speed = np.hypot(vx, vy)
    u = (np.arange(n) + 0.5) / n
    x, y = np.meshgrid(u, u)

    # %% [markdown]
    # The stream function: Perlin noise with `frequency` cells per texture and the same period, so it tiles. As a
    # check, central differences of ψ computed here in float64 (step h, the generator's fd_step) reproduce both
    # channels up to float32 round-off.

    # %%
    def psi_at(px, py):
        return pywarp.noise_perlin3_tiled(px * f, py * f, 0.0, f, settings.seed).astype(np.float64)

    psi = psi_at(x, y)
    dl = h / f  # h lattice units in texture coordinates
    vx_ref = (psi_at(x, y + dl) - psi_at(x, y - dl)) / (2.0 * h)
    vy_ref = -(psi_at(x + dl, y) - psi_at(x - dl, y)) / (2.0 * h)
    check = float(max(np.max(np.abs(vx_ref - vx)), np.max(np.abs(vy_ref - vy))))

    # %% [markdown]
    # The divergence and the curl (vorticity) of the texture itself, by central differences between neighbouring
    # texels with wrap-around (the texture is periodic). Texel spacing in lattice units: frequency / size.

    # %%
    d = f / n

    def ddx(a):
        return (np.roll(a, -1, axis=1) - np.roll(a, 1, axis=1)) / (2.0 * d)

    def ddy(a):
        return (np.roll(a, -1, axis=0) - np.roll(a, 1, axis=0)) / (2.0 * d)

    div = ddx(vx) + ddy(vy)
    vort = ddx(vy) - ddy(vx)
    ratio = float(np.sqrt(np.mean(div ** 2)) / np.sqrt(np.mean(vort ** 2)))

    fig = plt.figure(figsize=(14, 9.6), dpi=70 if quick else 100)
    gs = fig.add_gridspec(2, 3, hspace=0.28, wspace=0.30, left=0.04, right=0.96, top=0.89, bottom=0.05)
    ext = (0, 1, 0, 1)

    # %% [markdown]
    # (a) The speed |v| with streamlines: the flow circles in closed loops, fast where ψ is steep, still at the
    # centres of the eddies (the extrema of ψ) and at its saddle points.

    # %%
    ax = fig.add_subplot(gs[0, 0])
    im = ax.imshow(speed, cmap="magma", origin="lower", extent=ext, interpolation="bilinear")
    ax.streamplot(u, u, vx, vy, color="white", linewidth=0.6, density=1.4 if quick else 1.8, arrowsize=0.7)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_title("(a) speed |v| and streamlines", fontsize=10)
    _style(ax)
    fig.colorbar(im, ax=ax, fraction=0.046, pad=0.03).set_label("|v| (lattice units)", fontsize=8)

    # %% [markdown]
    # (b) The stream function ψ with its contour lines and the texture's vectors as arrows: every arrow is tangent to
    # a contour. The flow turns counter-clockwise around the hills of ψ (red) and clockwise around its valleys
    # (blue).

    # %%
    ax = fig.add_subplot(gs[0, 1])
    lim = float(np.max(np.abs(psi)))
    im = ax.imshow(psi, cmap="RdBu_r", vmin=-lim, vmax=lim, origin="lower", extent=ext, interpolation="bilinear")
    ax.contour(u, u, psi, levels=np.linspace(-lim, lim, 13), colors="k", linewidths=0.4, alpha=0.6)
    step = max(1, n // 24)
    sel = (slice(step // 2, None, step), slice(step // 2, None, step))
    ax.quiver(x[sel], y[sel], vx[sel], vy[sel], angles="xy", pivot="middle", color="k", width=0.004,
              scale=40)
    ax.set_title(f"(b) stream function ψ = Perlin noise ({f} cells)\narrows = texture vectors, tangent to contours",
                 fontsize=10)
    _style(ax)
    fig.colorbar(im, ax=ax, fraction=0.046, pad=0.03).set_label("ψ", fontsize=8)
    ax.text(0.02, 0.02, f"float64 central differences of ψ: max |Δ| = {check:.1e}", transform=ax.transAxes,
            fontsize=7.5, bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))

    # %% [markdown]
    # (c) What a texture file of this field would look like: the two signed channels mapped to red and green,
    # 0.5 + 0.5 v / max|v| (blue = 0), tiled 2 × 2. There are no seams at the dashed lines: ψ has a whole number of
    # Perlin cells per texture and wraps its lattice, so the curl wraps too.

    # %%
    ax = fig.add_subplot(gs[0, 2])
    vmax = float(np.max(np.abs(curl)))
    rg = np.zeros((n, n, 3))
    rg[..., 0] = 0.5 + 0.5 * vx / vmax
    rg[..., 1] = 0.5 + 0.5 * vy / vmax
    ax.imshow(np.tile(rg, (2, 2, 1)), origin="lower", extent=(0, 2, 0, 2), interpolation="nearest")
    ax.axvline(1.0, color="white", ls="--", lw=1.0)
    ax.axhline(1.0, color="white", ls="--", lw=1.0)
    ax.set_title("(c) encoded as R = v_x, G = v_y, tiled 2 × 2:\nno seams (dashed = tile borders)", fontsize=10)
    _style(ax, 2)

    # %% [markdown]
    # Bottom row: (d), (e) the two channels the texture stores, signed. (f) Divergence against vorticity along one
    # row of texels, both by central differences between texels. The vorticity curl_z = ∂v_y/∂x − ∂v_x/∂y = −∇²ψ
    # swings widely; the divergence stays on the zero line -- what is left of it is the truncation error of
    # the differences, a thousandth of the vorticity.

    # %%
    for j, (title, img) in enumerate((("(d) channel 0: v_x = ∂ψ/∂y", vx), ("(e) channel 1: v_y = −∂ψ/∂x", vy))):
        ax = fig.add_subplot(gs[1, j])
        im = ax.imshow(img, cmap="RdBu_r", vmin=-vmax, vmax=vmax, origin="lower", extent=ext,
                       interpolation="nearest")
        ax.set_title(title, fontsize=10)
        _style(ax)
        fig.colorbar(im, ax=ax, fraction=0.046, pad=0.03).set_label("lattice units", fontsize=8)
        ax.axhline(u[n // 2], color="k", ls="--", lw=0.8)  # the row of (f)
    ax = fig.add_subplot(gs[1, 2])
    pos = ax.get_position()
    ax.set_position((pos.x0 + 0.03, pos.y0, pos.width - 0.03, pos.height))  # room for the y label
    row = n // 2
    ax.plot(u, vort[row], color="tab:purple", lw=1.4, label="vorticity ∂v_y/∂x − ∂v_x/∂y")
    ax.plot(u, div[row], color="tab:orange", lw=1.8, label="divergence ∂v_x/∂x + ∂v_y/∂y")
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_xlim(0, 1)
    wlim = float(np.max(np.abs(vort)))
    ax.set_ylim(-1.15 * wlim, 1.45 * wlim)
    ax.grid(alpha=0.3)
    ax.set_xlabel(f"x (row y = {u[row]:.3f}, dashed in (d), (e))", fontsize=9)
    ax.set_ylabel("per lattice unit", fontsize=9)
    ax.tick_params(labelsize=7)
    ax.set_title("(f) divergence vs vorticity of the texture\n(central differences between texels)", fontsize=10)
    ax.legend(loc="upper left", fontsize=8, frameon=False)
    ax.text(0.02, 0.03, f"whole texture: RMS(div) / RMS(vorticity) = {ratio:.1e}\nmax |div| = "
            f"{np.max(np.abs(div)):.1e}, max |vorticity| = {wlim:.1f}", transform=ax.transAxes, fontsize=7.5,
            bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))

    fig.suptitle(f"Curl-noise texture (vc-A11), generated: default CurlNoiseSettings ({n}², {f} Perlin cells per "
                 f"texture, seed {settings.seed}, step h = 1/{round(1 / h)});\nv = (∂ψ/∂y, −∂ψ/∂x) of Perlin noise ψ "
                 "(vc-A7 reading (i)): a divergence-free, seamlessly tiling swirl field", fontsize=11)
    out = out_dir / "extra-curl-texture.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
