"""Figure rr-fig-3.8 (in kind): the retinal-persistence method (rr-alg-3.2.3, rr-code-5.2.4: every streak pixel the
refracted scene averaged over the fall) beside streaks of one static colour, both at the same coverage and alpha, the
static colour matched to the persistence streaks in the top-right corner.

Scene 1 of fig 6.3 (pt terrain) behind the rain of the scene `rain`; the static streaks are the same compositing pass
(``pywarp.equation("rr-code-5.2.3")``) over a capture of one uniform colour, so both images have the same streaks,
the same coverage and the same alpha; only the colour source differs. Output: figures/rr/fig-3.8.png.
"""
# %% [markdown]
# The text argues for persistence streaks with this comparison: a static streak colour tuned to look right in one
# part of the image (the top-right corner, sky) is wrong elsewhere (the bottom-left corner, ground and water), while
# the refracted colour follows the scene everywhere -- the drop shows an inverted wide-angle image of the scene, and
# its streak averages that image along the fall.
#
# The text's streaks are opaque here; ours (streaks='physical') take their alpha from the exposure -- a few % for a
# drop at its size -- so that the colours can be compared the drops are drawn 12 times their size
# (`streak_scale = 12`): streaks 20 - 45 % opaque. To match the top-right corner we take the colour c of the
# persistence streaks there: each streak pixel is bg + alpha (c - bg), alpha from the same pass over black with a
# white capture; c is the least-squares fit over the corner's streak pixels.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.rain.settings import RainSettings  # noqa: E402
from pywarp.rain.technique import RainTechnique  # noqa: E402

SCENE = dict(background="terrain", background_options={}, camera_yaw_deg=0.0, camera_pitch_deg=-4.0)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = dict(width=192, height=108, capture_size=128, mask_size=128) if quick else dict(width=640, height=360)
    tech = RainTechnique(RainSettings(**size, **SCENE, drops=4000, time_s=2.0 / 0.05, seed=8, mode="streaks",
                                      streak_scale=12.0))
    ins = tech.frame_inputs()
    composite = pywarp.equation("rr-code-5.2.3")  # the compositing pass (rr-code-5.2.3 / 5.2.4)
    persistence = composite(**ins)
    bg = ins["background"]
    h, w = bg.shape[:2]

    # %% [markdown]
    # The static colour: the streaks' own colour in the top-right quarter, fitted from frame = bg + alpha (c - bg).
    # %%
    alpha = composite(**{**ins, "background": np.zeros_like(bg), "capture": np.ones_like(ins["capture"])})[..., 1]
    tr = (slice(0, h // 2), slice(w // 2, w))
    a = alpha[tr][..., None]
    colour = ((a * (persistence[tr] - bg[tr] * (1.0 - a))).sum(axis=(0, 1)) / (a * a).sum()).astype(np.float32)
    uniform = np.broadcast_to(colour, ins["capture"].shape).copy()
    static = composite(**{**ins, "capture": uniform})

    def show(ax, img, title):
        ax.imshow(np.clip(img, 0, 1), interpolation="nearest")
        ax.set_title(title, fontsize=9)
        ax.axis("off")
        for (y0, x0), name in (((0, w // 2), "top right"), ((h // 2, 0), "bottom left")):
            ax.add_patch(plt.Rectangle((x0, y0), w // 2 - 1, h // 2 - 1, fill=False, ec="yellow", lw=0.8, ls="--"))
            ax.text(x0 + 4, y0 + 4, name, color="yellow", fontsize=7, va="top")

    fig = plt.figure(figsize=(13, 6.2), dpi=70 if quick else 120)
    gs = fig.add_gridspec(2, 4, height_ratios=[2.2, 1])
    show(fig.add_subplot(gs[0, :2]), persistence, "persistence method (rr-code-5.2.4): the refracted scene over the fall")
    show(fig.add_subplot(gs[0, 2:]), static,
         f"static streak colour ({colour[0]:.2f}, {colour[1]:.2f}, {colour[2]:.2f}) = the left image's "
         "top-right streak colour")
    # enlarged corners: top right alike, bottom left different
    cy, cx = h // 5, w // 5
    crops = ((slice(h // 8, h // 8 + cy), slice(w - w // 8 - cx, w - w // 8)),
             (slice(h - h // 8 - cy, h - h // 8), slice(w // 8, w // 8 + cx)))
    for k, (img, label) in enumerate(((persistence, "persistence"), (static, "static"))):
        for m, (crop, corner) in enumerate(zip(crops, ("top right", "bottom left"))):
            ax = fig.add_subplot(gs[1, 2 * m + k])
            ax.imshow(np.clip(img[crop], 0, 1), interpolation="nearest")
            ax.set_title(f"{corner}, {label}", fontsize=8)
            ax.axis("off")
    fig.suptitle("Fig 3.8 (in kind) — retinal persistence vs a static streak colour, drops 12x: alike where the "
                 "colour was matched (top right), different elsewhere (bottom left)", fontsize=10)
    fig.tight_layout()
    path = out_dir / "fig-3.8.png"
    fig.savefig(path)
    plt.close(fig)
    return [path]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
