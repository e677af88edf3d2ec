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
# The scene is a function of direction (sky, sun, a mountain ridge, a chequered meadow with a road). It is rendered
# twice from the same eye: once as the viewer's image (50 deg FOVy) and once as the capture (150 deg, 512 x 512).
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

FOV_CAPTURE = 150.0  # the capture camera's FOVy: the text's contract (rr-der-3.2.1, variant 'thesis')
FOV_VIEW = 50.0  # the viewer's FOVy: a normal camera lens (the text does not give one)
# (label, mask method, radius a [mm], centre direction (camera space), angular radius [rad]); the angular radii are
# ~150x a real drop's (1 mm at 2 m: 0.0005 rad) so that the refracted image is visible
DROPS = (("sphere (the text)", "sphere", 1.0, (-0.26, 0.05, -1.0), 0.075),
         ("3 mm Beard-Chuang (exact)", "exact", 3.0, (0.02, -0.08, -1.0), 0.095),
         ("4.5 mm Beard-Chuang (exact)", "exact", 4.5, (0.28, 0.1, -1.0), 0.11))


def environment(d):
    """The scene around the viewer as a function of direction (camera space, x right, y up, looking down -z): sky
    gradient, sun, a mountain ridge on the horizon, a chequered meadow 1.6 m below the eye, haze with distance."""
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    up = np.clip(y, 0, 1)[..., None]
    rgb = (1 - np.sqrt(up)) * np.array([0.86, 0.9, 0.96]) + np.sqrt(up) * np.array([0.22, 0.42, 0.85])
    sun = np.array([-0.45, 0.45, -1.0]) / np.linalg.norm([-0.45, 0.45, -1.0])
    rgb = rgb + np.clip((d @ sun - 0.996) / 0.002, 0, 1)[..., None] * np.array([1.2, 1.0, 0.6])
    az = np.arctan2(x, -z)
    ridge = (y >= 0) & (y < 0.07 + 0.05 * np.sin(3 * az + 0.5) + 0.025 * np.sin(11 * az))
    rgb = np.where(ridge[..., None], np.array([0.42, 0.45, 0.58]), rgb)
    below = y < 0
    dist = 1.6 / np.maximum(-y, 1e-4)
    gx, gz = x * dist, z * dist
    cell = (np.floor(gx / 2.0) + np.floor(gz / 2.0)) % 2
    grass = np.where(cell[..., None] > 0, np.array([0.22, 0.5, 0.16]), np.array([0.62, 0.52, 0.22]))
    road = np.abs(gx) < 1.2
    grass = np.where(road[..., None], np.array([0.3, 0.3, 0.32]), grass)
    haze = 1 - np.exp(-dist / 60.0)
    ground = (1 - haze[..., None]) * grass + haze[..., None] * np.array([0.8, 0.84, 0.9])
    rgb = np.where(below[..., None], ground, rgb)
    return np.clip(rgb, 0, 1).astype(np.float32)


def render_view(h, w, fov_deg):
    """Pixel directions and the scene of a pinhole camera looking down -z (row 0 at the top)."""
    t = np.tan(np.radians(fov_deg) / 2)
    ys = (1 - 2 * (np.arange(h) + 0.5) / h) * t
    xs = (2 * (np.arange(w) + 0.5) / w - 1) * t * w / h
    X, Y = np.meshgrid(xs, ys)
    d = np.stack([X, Y, -np.ones_like(X)], -1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    return d, environment(d)


def billboard_frame(f):
    """Right and up vectors of a billboard facing the viewer in direction f (the drop's mask frame)."""
    rt = np.cross(f, [0.0, 1.0, 0.0])
    rt /= np.linalg.norm(rt)
    return rt, np.cross(rt, f)


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
    dirs, view = render_view(h, w, FOV_VIEW)
    cdirs, capture = render_view(cap_size, cap_size, FOV_CAPTURE)

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
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="figures/rr")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    print(*main(args.out, quick=args.quick), sep="\n")
