"""Figures rr-fig-6.15 and rr-fig-6.16 (in kind): the final rain simulation placed in scene 2 (6.15) and in the third
scene (6.16), as three successive frames 1/30 s apart -- the retinal-persistence streaks (rr-code-5.2.4, rr-alg-3.2.3)
of the particle system (rr-code-5.2.2) falling over the cached background.

Scene 2 is the pt terrain (seed 7), scene 3 the vc cloudscape, as in fig 6.3, here with other views and heavier rain
(6000 drops). Outputs: figures/rr/fig-6.15.png, figures/rr/fig-6.16.png.
"""
# %% [markdown]
# `pywarp animate rain` renders such frames as a video; here three of them stand side by side. The settings' time
# field advances by `frame_dt / clock_rate` per frame (one 1/30 s step of the particles); the background is not
# re-rendered, so a frame costs the particle step, the projection and the compositing pass only.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.rain.settings import RainSettings  # noqa: E402
from pywarp.rain.technique import RainTechnique  # noqa: E402

VIEWS = {
    "6.15": ("scene 2: pt terrain, seed 7",
             dict(background="terrain", background_options={"seed": 7, "sun_elevation_deg": 35.0,
                                                             "sun_azimuth_deg": 60.0},
                  camera_yaw_deg=200.0, camera_pitch_deg=-3.0)),
    "6.16": ("scene 3: vc cloudscape from 50 m", dict(background="clouds", camera_yaw_deg=90.0,
                                                      camera_pitch_deg=8.0)),
}
QUICK_CLOUDS = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = dict(width=192, height=108, capture_size=128, mask_size=128) if quick else dict(width=640, height=360)
    written = []
    for fig_id, (name, scene) in VIEWS.items():
        if quick and scene["background"] == "clouds":
            scene = dict(scene, background_options={**RainSettings().background_options, **QUICK_CLOUDS})
        s = RainSettings(**size, **scene, drops=6000, time_s=2.0 / 0.05, seed=11, mode="streaks")
        tech = RainTechnique(s)
        frames = []
        for k in range(3):
            tech.update(time_s=s.time_s + k * s.frame_dt / s.clock_rate)
            frames.append(tech.render())
        fig, axes = plt.subplots(1, 3, figsize=(15, 3.2), dpi=70 if quick else 128)
        for k, (ax, img) in enumerate(zip(axes, frames)):
            ax.imshow(img, interpolation="nearest")
            ax.set_title(f"frame {k}: t = 2 s + {1000 * k * s.frame_dt:.0f} ms", fontsize=9)
            ax.axis("off")
        fig.suptitle(f"Fig {fig_id} (in kind) — the final rain simulation in {name}: 6000 drops, streaks of "
                     f"{s.persistence_ms:g} ms persistence", fontsize=10)
        fig.tight_layout()
        path = out_dir / f"fig-{fig_id}.png"
        fig.savefig(path)
        plt.close(fig)
        written.append(path)
    return written


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
