"""Figure rr-fig-2.4 (photograph of a real drop refracting the scene), stand-in: drops rendered with rain_shade_drop.

Stand-in: the thesis shows a photograph (from Rousseau et al.: shutter 1/1000 s, white dots from the flash, a drop that
has just left a tap and is not yet at its equilibrium shape), which cannot be reproduced, so drops are rendered
refracting a synthetic scene the way the text does it: a 150 deg capture of the scene from the viewer (rr-alg-3.1.2),
refraction masks (rr-alg-3.1.1) and the per-pixel lookup P_i -> P_o -> P_c (rr-alg-3.1.3) of the fragment shader
(rr-code-5.2.3, defects fixed), all in `pywarp.rain_shade_drop` (rr-alg-3.1). The drops are a sphere (the text's
refraction) and Beard-Chuang drops of 3 and 4.5 mm traced exactly (rr-eq1, beyond the text); they are enlarged on
screen so that what they show can be seen. Not shown: the flash's highlights (reflection is neglected by the method,
rr-alg-3.2.2) and the drop's non-equilibrium shape. Output: figures/rr/fig-2.4.png.
"""
# %% [markdown]
# What the photograph shows: the scene seen through a drop is the background turned upside down and squeezed, a
# wide-angle image (the drop "sees" about 150-165 deg, rr-der-3.2.1). The text builds its whole drop shading on that
# observation, and this stand-in shows the result of that shading.
#
# The scene is a function of direction (`pywarp.tutorial.environment`: sky, sun, a mountain ridge, a chequered meadow
# with a road). It is rendered twice from the same eye (`pinhole_directions`): once as the viewer's image (50 deg
# FOVy) and once as the capture (150 deg, 512 x 512).
# Each drop is a billboard facing the viewer; `rain_shade_drop(capture, mask, centre_dir, angular_radius, ...)`
# returns its RGBA pixels, which are composited over the view at the directions they cover.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.rain import drops  # noqa: E402
from pywarp.tutorial import billboard_frame, environment, pinhole_directions  # noqa: E402

FOV_CAPTURE = 150.0  # the capture camera's FOVy: the text's contract (rr-der-3.2.1, variant 'thesis')
FOV_VIEW = 50.0  # the viewer's FOVy: a normal camera lens (the text does not give one)
# (label, mask method, radius a [mm], centre direction (camera space), angular radius [rad]); the angular radii are
# ~150x a real drop's (1 mm at 2 m: 0.0005 rad) so that the refracted image is visible
DROPS = (("sphere (the text)", "sphere", 1.0, (-0.26, 0.05, -1.0), 0.075),
         ("3 mm Beard-Chuang (exact)", "exact", 3.0, (0.02, -0.08, -1.0), 0.095),
         ("4.5 mm Beard-Chuang (exact)", "exact", 4.5, (0.28, 0.1, -1.0), 0.11))


def composite(img, dirs, drop_rgba, f, ar):
    """Paste a drop billboard over the view: each view pixel whose direction falls on the billboard takes the
    billboard pixel there (nearest), where the drop's alpha is set."""
    rt, up = billboard_frame(f)
    n = drop_rgba.shape[0]
    q = dirs / (dirs @ f)[..., None] - f
    u, v = q @ rt / np.tan(ar), q @ up / np.tan(ar)
    on = (np.abs(u) < 1) & (np.abs(v) < 1) & ((dirs @ f) > 0)
    j = np.clip(((u + 1) * 0.5 * n).astype(int), 0, n - 1)
    i = np.clip(((1 - v) * 0.5 * n).astype(int), 0, n - 1)
    px = drop_rgba[i, j]
    take = on & (px[..., 3] > 0)
    img[take] = px[take][:, :3]


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    h, w = (150, 240) if quick else (480, 768)
    cap_size = 128 if quick else 512
    mask_size = 64 if quick else 256
    dirs = pinhole_directions(w, h, FOV_VIEW)  # camera space: looking down -z, row 0 at the top
    view = environment(dirs)
    capture = environment(pinhole_directions(cap_size, cap_size, FOV_CAPTURE))

    # %% [markdown]
    # One mask per drop shape (cached), one billboard per drop. The billboard is rendered at about twice the pixels
    # it covers on screen, then composited.

    # %%
    px_per_tan = h / (2 * np.tan(np.radians(FOV_VIEW) / 2))
    composed = view.copy()
    closeups = []
    for label, method, a, f, ar in DROPS:
        f = np.asarray(f, float) / np.linalg.norm(f)
        mask = drops.drop_mask(mask_size, a, method=method)
        n = int(4 * np.tan(ar) * px_per_tan)
        rgba = pywarp.rain_shade_drop(capture, mask, f, angular_radius=ar, fov_y_deg=FOV_CAPTURE, out_size=n)
        composite(composed, dirs, rgba, f, ar)
        closeups.append((label, pywarp.rain_shade_drop(capture, mask, f, angular_radius=ar, fov_y_deg=FOV_CAPTURE,
                                                       out_size=96 if quick else 320)))
    fig = plt.figure(figsize=(17, 7.2), dpi=80 if quick else 110)
    gs = fig.add_gridspec(2, 4, width_ratios=[1.6, 1.6, 1.0, 1.0], height_ratios=[1, 1])
    ax = fig.add_subplot(gs[:, :2])
    ax.imshow(np.clip(composed, 0, 1), interpolation="nearest")
    ax.set_title("three drops in front of the scene (viewer: 50° FOVy; drops enlarged ~150x)", fontsize=10)
    ax.axis("off")
    for k, (label, rgba) in enumerate(closeups):
        axk = fig.add_subplot(gs[k // 2, 2 + k % 2])
        axk.imshow(np.clip(np.where(rgba[..., 3:] > 0, rgba[..., :3], 0.12), 0, 1), interpolation="nearest")
        axk.set_title(label, fontsize=10)
        axk.axis("off")
    axc = fig.add_subplot(gs[1, 3])
    axc.imshow(capture, interpolation="nearest")
    axc.set_title("the capture they refract\n(150° FOVy, 512², rr-alg-3.1.2)", fontsize=10)
    axc.axis("off")
    fig.suptitle("Stand-in for rr-fig-2.4 (a photograph): drops refracting the scene, rendered by the method "
                 "(rain_shade_drop: mask + P_i -> P_o -> P_c); the image in a drop is the scene turned upside "
                 "down and squeezed", fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.9, bottom=0.01, wspace=0.06, hspace=0.15)
    out = out_dir / "fig-2.4.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
