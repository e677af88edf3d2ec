"""Figures rr-fig-6.10, rr-fig-6.11 and rr-fig-6.12 (in kind): the user's settings of the application (rr-tab-A) on
one scene -- the drop size (B/N keys, 6.10), the drop shape of Table 2.1 (T key, 6.11: a = 0.5, 1.0, 3.0, 4.5 mm,
rr-eq1 outlines in the rr-alg-3.1.1 masks) and the number of drops (G/H keys, 6.12).

Scene 1 of fig 6.3 (the pt terrain) behind the rain of the scene `rain`; drops (rr-code-5.2.3) for size and shape,
where the drop itself must be seen, streaks (rr-code-5.2.4) for the count. Each panel has an enlarged inset (for
size and shape around the nearest drop).
Outputs: figures/rr/fig-6.10.png, figures/rr/fig-6.11.png, figures/rr/fig-6.12.png.
"""
# %% [markdown]
# The keys of the application change three fields of `RainSettings`: `size_mm` (the mean radius of the particle
# sizes, Gauss(1, 1.3, 8) in our reading), `shape` (which Table 2.1 drop the mask's outline comes from) and `drops`.
# `RainTechnique.update(...)` applies them without re-rendering the background: the view and the capture stay cached,
# a new shape rebuilds the mask, a new size respawns the particles (same seed: the same positions). A new count shows
# what a fresh technique with that many drops would: a lower one keeps the first drops, a higher one respawns the
# system at the current time.
#
# As in the application, the shape changes the OUTLINE only ("outline" mask: the Beard-Chuang silhouette, a sphere's
# refraction -- spec erratum 12); `mask="exact"` traces the rays through the true shape instead.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402

from pywarp.rain.settings import SHAPES, RainSettings  # noqa: E402
from pywarp.rain.technique import RainTechnique  # noqa: E402

SCENE = dict(background="terrain", background_options={}, camera_yaw_deg=0.0, camera_pitch_deg=-4.0)
SIZES = ((0.5, 0.6), (1.3, 1.0), (2.5, 1.0))  # (size_mm, size_spread_mm): radii in size +- spread / 2
COUNTS = (500, 3000, 12000)


def panel(ax, img, title, zoom):
    ax.imshow(img, interpolation="nearest")
    ax.set_title(title, fontsize=9)
    ax.axis("off")
    y0, y1, x0, x1 = zoom
    ins = ax.inset_axes([0.52, 0.02, 0.46, 0.5])
    ins.imshow(img[y0:y1, x0:x1], interpolation="nearest")
    ins.set_xticks([])
    ins.set_yticks([])
    for s in ins.spines.values():
        s.set_color("yellow")
    ax.indicate_inset([x0, y0, x1 - x0, y1 - y0], ins, edgecolor="yellow", alpha=0.9)


def near_drop(tech):
    """Screen centre (x, y) of the nearest drop in view (the sprites are sorted far first)."""
    sp = tech.frame_inputs()["sprites"]
    return float(sp[-1, 0]), float(sp[-1, 1])


def row(images, titles, path, suptitle, quick, centre, cols=None):
    h, w = images[0].shape[:2]
    zh, zw = h // 6, w // 6  # the inset shows a sixth of the frame, enlarged
    x0 = int(min(max(centre[0] - zw / 2, 0), w - zw))
    y0 = int(min(max(centre[1] - zh / 2, 0), h - zh))
    zoom = (y0, y0 + zh, x0, x0 + zw)
    cols = cols or len(images)
    rows = -(-len(images) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 3.2 * rows), dpi=70 if quick else 130, squeeze=False)
    for ax, img, t in zip(axes.ravel(), images, titles):
        panel(ax, img, t, zoom)
    fig.suptitle(suptitle, fontsize=10)
    height = 3.2 * rows  # inches; room for the title and the panels' titles (tight_layout misplaces the insets')
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=1.0 - 0.55 / height, wspace=0.03, hspace=0.16)
    fig.savefig(path)
    plt.close(fig)


def enlarged_drop(tech, radius: int) -> np.ndarray:
    """One drop of the technique's current mask, ``radius`` px, composited in the middle of its frame: the square
    crop around it (uint8)."""
    ins = tech.frame_inputs()
    h, w = ins["background"].shape[:2]
    cx, cy = w / 2, h / 2
    sp = np.array([[cx, cy, radius, radius, 0.0, 1.0]], np.float32)
    frame = pywarp.particles_composite(ins["background"], ins["capture"], ins["mask"], sp, ins["fov_view"],
                                       ins["fov_capture"], filter=ins["filter"], opacity=1.0)
    r = int(radius * 1.25)
    crop = frame[int(cy) - r:int(cy) + r, int(cx) - r:int(cx) + r]
    return (np.clip(crop, 0, 1) * 255 + 0.5).astype(np.uint8)


def shapes_figure(frames, drops, path, quick):
    """Fig 6.11: the frames of the four shapes in a row, each with its drop enlarged below it."""
    fig, axes = plt.subplots(2, len(frames), figsize=(4.6 * len(frames), 6.4), dpi=70 if quick else 130,
                             gridspec_kw=dict(height_ratios=(1.0, 1.35)))
    for k, (a, img, drop) in enumerate(zip(SHAPES, frames, drops)):
        axes[0, k].imshow(img, interpolation="nearest")
        axes[0, k].set_title(f"shape a = {a} mm (Table 2.1): 3000 drops", fontsize=9)
        axes[1, k].imshow(drop, interpolation="nearest")
        axes[1, k].set_title(f"one drop of shape {a} mm, enlarged", fontsize=9)
        for ax in axes[:, k]:
            ax.axis("off")
    fig.suptitle("Fig 6.11 (in kind) — the drop shapes (T key): Beard-Chuang outlines, sphere refraction as the "
                 "application; the 0.5 and 1 mm drops nearly round, the 3 and 4.5 mm drops flat-bottomed", fontsize=10)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.88, bottom=0.01, wspace=0.04, hspace=0.12)
    fig.savefig(path)
    plt.close(fig)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    # full size: the text's 512 px capture (the scene's default is 256): fig 6.11 enlarges one drop to 72 px, where
    # a coarser capture would show its texels
    size = (dict(width=192, height=108, capture_size=128, mask_size=128) if quick
            else dict(width=640, height=360, capture_size=512))
    tech = RainTechnique(RainSettings(**size, **SCENE, drops=3000, time_s=2.0 / 0.05, seed=4, mode="drops"))

    # %% [markdown]
    # Fig 6.10: the mean drop radius 0.5, 1.3 (the text's mean) and 2.5 mm. Larger drops are larger billboards AND
    # fall faster (Table 2.2 / 4), so they also spread further in 2 s.
    # %%
    imgs = []
    for s_mm, spread in SIZES:
        tech.update(size_mm=s_mm, size_spread_mm=spread)
        imgs.append(tech.render())
        if s_mm == 1.3:
            centre = near_drop(tech)
    p10 = out_dir / "fig-6.10.png"
    row(imgs, [f"size {s:g} mm (radii {s - w / 2:g} - {s + w / 2:g} mm)" for s, w in SIZES], p10,
        "Fig 6.10 (in kind) — changing the drop size (B/N): refracting drops, 3000 drops", quick, centre)

    # %% [markdown]
    # Fig 6.11: the four shapes of Table 2.1 (drop radius unchanged: Gauss(1, 1.3, 8); only the mask changes). The
    # 0.5 and 1 mm drops are nearly round, the 3 and 4.5 mm drops flat-bottomed (rr-eq1: r(0) < r(pi)). At ~8 px a
    # drop's outline is hard to tell apart, so each frame has an enlarged drop under it: the same compositing pass
    # (``pywarp.particles_composite``) with one billboard of 72 px radius in the middle of the frame, over the frame's
    # own background and capture -- the mask of that shape, as the frame's drops have it.
    # %%
    tech.update(size_mm=1.3, size_spread_mm=1.0)
    imgs, big = [], []
    for shape in SHAPES:
        tech.update(shape=shape)
        imgs.append(tech.render())
        big.append(enlarged_drop(tech, 24 if quick else 72))
    p11 = out_dir / "fig-6.11.png"
    shapes_figure(imgs, big, p11, quick)

    # %% [markdown]
    # Fig 6.12: 500, 3000 and 12 000 drops in the final (streak) mode. The physical streaks are faint (their alpha is
    # the exposure, a tenth or so), so a second row shows what the rain adds to the background, |frame - background|
    # x 8: the streaks in view, to count.
    # %%
    tech.update(shape="1.0", mode="streaks")
    imgs = []
    for n in COUNTS:
        tech.update(drops=n)
        imgs.append(tech.render())
    tech.update(drops=0)
    bg = tech.render().astype(np.int16)
    diffs = [np.repeat(np.clip(np.abs(i.astype(np.int16) - bg).max(axis=2, keepdims=True) * 8, 0, 255), 3, axis=2)
             .astype(np.uint8) for i in imgs]
    p12 = out_dir / "fig-6.12.png"
    row(imgs + diffs, [f"{n} drops" for n in COUNTS] + [f"{n} drops: |frame - background| x 8" for n in COUNTS],
        p12, "Fig 6.12 (in kind) — changing the number of drops (G/H): retinal-persistence streaks", quick,
        (0.3 * imgs[0].shape[1], 0.3 * imgs[0].shape[0]), cols=3)
    return [p10, p11, p12]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
