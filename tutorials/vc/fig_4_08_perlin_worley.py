"""Figure vc-fig-4.8: combinations of fBm Perlin noise P and inverse-Worley fBm W ("Perlin-Worley", vc-A8).

Every combination option of pywarp.noise_perlin_worley (vc-A8), as 2-D slices (z = 0.5) of 256 x 256 pixels:
'thesis' remap(P, 0, 1, W, 1)^2 (the thesis's default), 'gpu_pro_7' clamp(remap(P, W, 1, 0, 1)) (GPU Pro 7), and
three more that the library offers ('hillaire' remap(P, 0, 1, W, 1), 'product' P W, 'average' (P + W)/2). The thesis
names only the first two; its other panels are not listed, so those three are stand-ins. Inputs: P = fBm Perlin
(vc-2.21, pywarp.noise_fbm_perlin3: 3 octaves, frequency 8, period 8, seed 0) remapped from [-1, 1] to [0, 1] with
pywarp.interp_remap (vc-2.27); W = inverse-Worley fBm (vc-A6, pywarp.noise_fbm_worley3: 3 octaves, 4 cells, seed 0) --
the octave counts and frequencies of the base-shape texture defaults (the A9 texture, Hillaire's generator). Both are
periodic with period 1, so every panel tiles. Output: figures/vc/fig-4.8.png.
"""
# %% [markdown]
# The red channel of the base-shape texture is "Perlin-Worley" noise: Perlin fBm (soft, continuous blobs) combined
# with inverse-Worley fBm (billowy, cauliflower-like cells). Schneider's 2015 talk shows the result but not the
# formula, so the thesis tried several combinations and kept the one that looked closest:
#
# * thesis (default):  remap(P, 0, 1, W, 1)² = (W + P (1 - W))²  -- P is squeezed into [W, 1]: the Worley cells set
#   a floor, Perlin fills in between, and squaring darkens the low values again for contrast.
# * GPU Pro 7:  remap(P, W, 1, 0, 1) = (P - W)/(1 - W)  -- the Worley value is used as a threshold on P; most of the
#   image falls below it (clamped to 0) and only isolated bright Perlin peaks survive -- which is why "its result did
#   not resemble the 2015 texture".
# * hillaire:  remap(P, 0, 1, W, 1) -- the default without the square (Hillaire's TileableVolumeNoise): brighter,
#   lower contrast.
# * product P W and average (P + W)/2: the two simplest mixes, for comparison.
#
# The bottom-right plot follows one row of pixels through the inputs and the two named combinations.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

COMBOS = (("thesis", "thesis (default)\nremap(P, 0, 1, W, 1)²"),
          ("gpu_pro_7", "GPU Pro 7\nclamp(remap(P, W, 1, 0, 1))"),
          ("hillaire", "hillaire\nremap(P, 0, 1, W, 1)"),
          ("product", "product\nP · W"),
          ("average", "average\n(P + W) / 2"))


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    n = 96 if quick else 256
    z = 0.5
    u = (np.arange(n) + 0.5) / n  # texel centres of one period
    x, y = np.meshgrid(u, u)

    # %% [markdown]
    # The two inputs. Perlin fBm lies in about [-1, 1]; remap (2.27) takes it to [0, 1] (the clip only guards the
    # rare overshoot). The inverse-Worley fBm is already in [0, 1].

    # %%
    fbm = pywarp.noise_fbm_perlin3(x, y, z, 3, 8.0, 0, 8)  # octaves, frequency, seed, period
    P = np.clip(pywarp.interp_remap(fbm, -1.0, 1.0, 0.0, 1.0), 0.0, 1.0)
    W = pywarp.noise_fbm_worley3(x, y, z, 3, 4, 0, inverse=True)  # octaves, cells, seed

    # %% [markdown]
    # Every combination option of vc-A8, from the library.

    # %%
    out = {k: pywarp.noise_perlin_worley(P, W, combination=k) for k, _ in COMBOS}

    fig, axes = plt.subplots(2, 4, figsize=(15, 8.4), dpi=80 if quick else 110)
    panels = [("P: fBm Perlin → [0, 1]", P), ("W: inverse-Worley fBm", W)] + [(t, out[k]) for k, t in COMBOS]
    row = n * 3 // 8
    for ax, (title, img) in zip(axes.flat, panels):
        ax.imshow(img, cmap="gray", vmin=0.0, vmax=1.0, origin="lower", extent=(0, 1, 0, 1),
                  interpolation="nearest")
        ax.set_title(title, fontsize=10)
        ax.set_xticks([])
        ax.set_yticks([])
    for ax in axes.flat[:4]:
        ax.axhline(u[row], color="C1", lw=0.8, ls="--")
    for ax, (k, _) in zip(axes.flat[2:], COMBOS):
        if k == "thesis":
            ax.spines[:].set(color="C3", linewidth=3)
        m = float(out[k].mean())
        ax.text(0.02, 0.02, f"mean {m:.2f}", transform=ax.transAxes, fontsize=8,
                bbox=dict(facecolor="white", alpha=0.85, edgecolor="none"))

    ax = axes.flat[7]
    ax.plot(u, P[row], color="C0", lw=1.2, label="P")
    ax.plot(u, W[row], color="C2", lw=1.2, label="W")
    ax.plot(u, out["thesis"][row], color="C3", lw=2.0, label="thesis")
    ax.plot(u, out["gpu_pro_7"][row], color="k", lw=1.4, ls="--", label="GPU Pro 7")
    ax.set_xlim(0, 1)
    ax.set_ylim(-0.02, 1.25)
    ax.set_yticks(np.linspace(0, 1, 6))
    ax.set_box_aspect(1)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper center", ncol=4, fontsize=7.5, frameon=False, handlelength=1.5, columnspacing=1.0)
    ax.set_title("one row (dashed line)", fontsize=10)
    ax.tick_params(labelsize=7)
    fig.suptitle(f"Perlin-Worley combinations (vc-A8): slice z = {z}, {n}² px, grey scale [0, 1]; red frame = the "
                 "thesis's choice. The thesis names only 'thesis' and 'GPU Pro 7';\n'hillaire', 'product' and "
                 "'average' are the library's other options (stand-ins for the unlisted panels)", fontsize=11)
    fig.subplots_adjust(left=0.02, right=0.98, bottom=0.03, top=0.86, wspace=0.08, hspace=0.2)
    path = out_dir / "fig-4.8.png"
    fig.savefig(path)
    plt.close(fig)
    return [path]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
