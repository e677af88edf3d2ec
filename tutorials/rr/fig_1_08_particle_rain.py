"""Figure rr-fig-1.8, stand-in: particle-system rain as games draw it (the text shows Call of Duty) -- classic white,
semi-transparent streaks of one colour -- beside the text's method, streaks that refract the scene (rr-code-5.2.4).

The game screenshot cannot be reproduced; the stand-in is our own render of the same idea. Both images use the same
particles (rr-code-5.2.2), the same streak length (rr-alg-3.2.3) and the same compositing pass
(``pywarp.equation("rr-code-5.2.3")``); the classic streaks are the billboard rectangles of the text's listing
(streaks='thesis') over a capture of one uniform light grey, the text's are the drops integrated over the persistence
time (streaks='physical': thin, tapered, the refracted scene).
Scene 2 of fig 6.3 (pt terrain, seed 7). Output: figures/rr/fig-1.8.png.
"""
# %% [markdown]
# Chapter 1 of the text surveys particle systems in games: rain is a cloud of textured quads, usually thin white
# streaks blended over the frame. They are cheap and read as rain, but their colour ignores the scene: over the bright
# sky they are too dark or invisible, over dark hills too bright. The refracting streaks of the text take their colour
# from the scene seen through the drop (an inverted wide-angle image), so they brighten over dark ground with the sky
# they refract and stay subtle elsewhere.

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

SCENE = dict(background="terrain", background_options={"seed": 7, "sun_elevation_deg": 35.0, "sun_azimuth_deg": 60.0},
             camera_yaw_deg=140.0, camera_pitch_deg=-6.0)
#: the classic streak: light grey, 35 % opaque (a typical additive/alpha rain texture; ours, not the text's)
CLASSIC_COLOUR = (0.85, 0.87, 0.9)
CLASSIC_OPACITY = 0.35


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = dict(width=192, height=108, capture_size=128, mask_size=128) if quick else dict(width=640, height=360)
    tech = RainTechnique(RainSettings(**size, **SCENE, drops=6000, time_s=2.0 / 0.05, seed=2, mode="streaks"))
    composite = pywarp.equation("rr-code-5.2.3")
    refracting = composite(**tech.frame_inputs())
    tech.update(streaks="thesis", billboard_scale=3.0)  # the thin billboard rectangles a game draws
    ins = tech.frame_inputs()
    grey = np.broadcast_to(np.asarray(CLASSIC_COLOUR, np.float32), ins["capture"].shape).copy()
    classic = composite(**{**ins, "capture": grey, "opacity": CLASSIC_OPACITY})

    fig, axes = plt.subplots(1, 2, figsize=(13, 4.0), dpi=70 if quick else 120)
    for ax, img, title in ((axes[0], classic, f"classic particle rain: one streak colour {CLASSIC_COLOUR}, "
                                              f"{CLASSIC_OPACITY:.0%} opaque"),
                           (axes[1], refracting, "the text's streaks: the refracted scene over the persistence "
                                                 "time (rr-code-5.2.4)")):
        ax.imshow(np.clip(img, 0, 1), interpolation="nearest")
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    fig.suptitle("Fig 1.8 stand-in — particle-system rain (the text shows a Call of Duty screenshot): 6000 drops",
                 fontsize=10)
    fig.tight_layout()
    path = out_dir / "fig-1.8.png"
    fig.savefig(path)
    plt.close(fig)
    return [path]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
