"""Figures rr-fig-6.3, rr-fig-6.4, rr-fig-6.5, rr-fig-6.6, rr-fig-6.7, rr-fig-6.8 and rr-fig-6.9 (in kind): the three
tested scenes without rain (6.3), with the final rain simulation -- retinal-persistence streaks, rr-code-5.2.4 (6.4,
6.6, 6.8) -- and with the particle system shown as refracting drops, rr-code-5.2.3 (6.5, 6.7, 6.9).

The application's scenes were a Terragen terrain under skybox textures, which are not available; ours are renders of
the platform's own scenes behind the rain: scene 1 and 2 the terrain of the pt text (two heightmap seeds and views),
scene 3 the vc cloudscape seen from 50 m. The rain is the scene `rain` (rr-code-5.2.2 particles, rr-alg-3.1.2 capture,
rr-alg-3.1.1 masks) with its defaults: 3000 drops of Gauss(1, 1.3, 8) mm, the 1 mm outline mask, 150 deg capture.
Outputs: figures/rr/fig-6.3.png, figures/rr/fig-6.4.png, figures/rr/fig-6.5.png, figures/rr/fig-6.6.png,
figures/rr/fig-6.7.png, figures/rr/fig-6.8.png, figures/rr/fig-6.9.png.
"""
# %% [markdown]
# Chapter 6 of the text shows each tested scene twice: once with "the final rain simulation" and once with "the
# particle-system simulation". We read the pair as the two display modes of the application (the F key): streaks,
# the final look with retinal persistence, and drops, each particle a refracting billboard. A scene is rendered once
# (the view and the 150 deg capture are cached by the technique); switching the mode re-composites only the rain.
#
# `RainTechnique(settings).render()` returns the frame; `update(mode=...)` changes the display mode. The background
# is any registered scene: its camera follows the rain settings' yaw, pitch and field of view.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.rain.settings import RainSettings  # noqa: E402
from pywarp.rain.technique import RainTechnique  # noqa: E402
from pywarp.tutorial import fit_text  # noqa: E402

#: The three tested scenes (our stand-ins for the text's three Terragen scenes).
SCENES = {
    1: dict(background="terrain", background_options={}, camera_yaw_deg=0.0, camera_pitch_deg=-4.0),
    2: dict(background="terrain", background_options={"seed": 7, "sun_elevation_deg": 35.0, "sun_azimuth_deg": 60.0},
            camera_yaw_deg=140.0, camera_pitch_deg=-6.0),
    3: dict(background="clouds", camera_pitch_deg=4.0),
}
NAMES = {1: "scene 1: terrain (pt), lake view", 2: "scene 2: terrain (pt), seed 7, hills",
         3: "scene 3: vc cloudscape from 50 m"}
QUICK_CLOUDS = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)
#: figure numbers: scene -> (final rain = streaks, particle system = drops)
FIGS = {1: ("6.4", "6.5"), 2: ("6.6", "6.7"), 3: ("6.8", "6.9")}


def save_frame(img, path, title):
    h, w = img.shape[:2]
    fig = plt.figure(figsize=(w / 100, (h + 28) / 100), dpi=100)
    ax = fig.add_axes([0, 0, 1, h / (h + 28)])
    ax.imshow(img, interpolation="nearest")
    ax.axis("off")
    fig.text(0.5, 1 - 14 / (h + 28), title, ha="center", va="center", fontsize=9)
    fit_text(fig)  # a title wider than a small (quick) frame: smaller, wrapped, its band taller
    fig.savefig(path)
    plt.close(fig)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = dict(width=192, height=108, capture_size=128, mask_size=128) if quick else dict(width=960, height=540)
    written = []
    empty = {}
    for k, scene in SCENES.items():
        # %% [markdown]
        # One technique per scene: rain at t = 2 s (the particles fall 2 s from a full box; seed 1).
        # %%
        if quick and scene["background"] == "clouds":  # small noise textures: seconds instead of tens
            scene = dict(scene, background_options={**RainSettings().background_options, **QUICK_CLOUDS})
        tech = RainTechnique(RainSettings(**size, **scene, drops=3000, time_s=2.0 / 0.05, seed=1, mode="streaks"))
        streaks = tech.render()
        tech.update(mode="drops")
        drops = tech.render()
        tech.update(drops=0)
        empty[k] = tech.render()
        final, particles = FIGS[k]
        for fig_id, img, what in ((final, streaks, "final rain simulation: streaks (rr-code-5.2.4)"),
                                  (particles, drops, "particle system: refracting drops (rr-code-5.2.3)")):
            path = out_dir / f"fig-{fig_id}.png"
            save_frame(img, path, f"Fig {fig_id} (in kind) — {NAMES[k]}, 3000 drops, {what}")
            written.append(path)

    # %% [markdown]
    # Fig 6.3: the same three views without rain (drops = 0: the frame is the cached background).
    # %%
    fig, axes = plt.subplots(1, 3, figsize=(15, 3.3), dpi=70 if quick else 110)
    for ax, (k, img) in zip(axes, empty.items()):
        ax.imshow(img)
        ax.set_title(NAMES[k], fontsize=9)
        ax.axis("off")
    fig.suptitle("Fig 6.3 (in kind) — the tested scenes without rain (our backgrounds for the text's Terragen scenes)",
                 fontsize=10)
    fig.tight_layout()
    path = out_dir / "fig-6.3.png"
    fig.savefig(path)
    plt.close(fig)
    return [path] + written


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
