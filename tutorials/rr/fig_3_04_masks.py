"""Figure rr-fig-3.4: precomputed refraction masks (rr-alg-3.1.1) and the 3-D drop: the text's sphere mask, the
application's flattened outline with sphere refraction, and -- beyond the text -- the exact Beard-Chuang drop traced
through both surfaces, side by side with their difference; for a = 3 mm (Table 2.1) and a = 1.5 mm (the text's
example radius, coefficients interpolated: an assumption). Output: figures/rr/fig-3.4.png.
"""
# %% [markdown]
# A drop on screen is a small billboard. For each of its pixels the shader needs two things: is the pixel inside the
# drop, and in which direction does the view ray leave the drop after refracting twice? Both are precomputed once,
# into a 512 x 512 mask: xyz = exit direction (x right, y up, z along the view), a = inside flag
# (`pywarp.rain.drops.drop_mask`). Here the direction is shown as colour, 0.5 + 0.5 (x, y, z).
#
# * **sphere** (the text): a spherical drop, two refractions at a sphere (rr-snell). The text calls the exact shape
#   "very expensive" and keeps the sphere even when a flattened drop is chosen.
# * **outline** (the application): the inside flag of the flattened Beard-Chuang outline, the sphere's refraction
#   stretched onto it (spec error index item 12).
# * **exact** (beyond the text): each ray marched to the Beard-Chuang surface, refracted, marched across the drop to
#   the far surface and refracted out; total internal reflections are followed (up to 3).
#
# The difference (d) is the angle between the exit directions of the outline and exact masks: for a 3 mm drop the
# flattened lens bends light quite differently from the sphere the text assumes.

# %%
from __future__ import annotations

import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from pywarp.kernels import rain  # noqa: E402
from pywarp.rain import drops  # noqa: E402

#: the figure prints the mask build times (measurements): not compared pixel for pixel
DETERMINISTIC = False


def colour(mask):
    """exit direction as colour on white; outside transparent-white."""
    rgb = 0.5 + 0.5 * mask[..., :3]
    return np.where(mask[..., 3:4] > 0, rgb, 1.0)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = 96 if quick else rain.MASK_SIZE
    rows = []
    for a, interp in ((3.0, "table"), (1.5, "linear")):
        masks, times = {}, {}
        for method in ("sphere", "outline", "exact"):
            t0 = time.perf_counter()
            masks[method] = drops.drop_mask(size, a, method=method, interp=interp)
            times[method] = time.perf_counter() - t0
        rows.append((a, interp, masks, times))

    fig = plt.figure(figsize=(17, 7.6), dpi=80 if quick else 110)
    gs = fig.add_gridspec(2, 5)
    for r, (a, interp, masks, times) in enumerate(rows):
        for c, method in enumerate(("sphere", "outline", "exact")):
            ax = fig.add_subplot(gs[r, c])
            ax.imshow(colour(masks[method]), extent=(-1, 1, -1, 1), interpolation="nearest")
            ax.set_title(f"({'abc'[c]}) {method}, a = {a:g} mm" + (" (interp.)" if interp == "linear" else ""),
                         fontsize=10)
            ax.set_xticks([])
            ax.set_yticks([])
        ex, ol = masks["exact"], masks["outline"]
        inside = ex[..., 3] > 0
        ang = np.degrees(np.arccos(np.clip(np.sum(ex[..., :3] * ol[..., :3], -1), -1, 1)))
        ang = np.where(inside, ang, np.nan)
        noexit = inside & (ex[..., 2] <= 0)
        ax = fig.add_subplot(gs[r, 3])
        im = ax.imshow(ang, extent=(-1, 1, -1, 1), cmap="magma", vmin=0, vmax=40, interpolation="nearest")
        ax.set_title(f"(d) exact vs outline [deg]\nmedian {np.nanmedian(ang):.1f}°, 95 % {np.nanpercentile(ang, 95):.1f}°,"
                     f" no exit {100 * noexit.sum() / inside.sum():.1f} %", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        fig.colorbar(im, ax=ax, fraction=0.046)
        ax = fig.add_subplot(gs[r, 4], projection="3d")
        th, ph = np.meshgrid(np.linspace(0, np.float32(np.pi), 24 if quick else 48),
                             np.linspace(0, 2 * np.pi, 32 if quick else 64))
        P, N = drops.drop_surface(th, ph, a, interp=interp)
        shade = np.clip(N @ np.array([0.4, 0.7, 0.6]) / np.linalg.norm([0.4, 0.7, 0.6]), 0, 1)
        ax.plot_surface(P[..., 0], P[..., 2], P[..., 1], facecolors=plt.cm.Blues(0.35 + 0.6 * shade), linewidth=0,
                        shade=False)
        lim = 1.2 * a
        for s in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
            s(-lim, lim)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=10, azim=-60)
        ax.tick_params(labelsize=6)
        ax.set_title(f"(e) 3-D drop, a = {a:g} mm\nmask build {size}²: sphere {times['sphere']:.2f} s, "
                     f"exact {times['exact']:.2f} s", fontsize=9)
    fig.suptitle("Refraction masks (rr-alg-3.1.1), colour = 0.5 + 0.5 x exit direction (x right, y up, z into the "
                 "scene): the text's sphere, the application's outline, the exact Beard-Chuang drop", fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.88, bottom=0.02, wspace=0.12, hspace=0.25)
    out = out_dir / "fig-3.4.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
