"""Figure pt-fig-7.7: the fBm terrain with 1 to 8 octaves, seen from fairly far above the surface; aliasing appears at
the higher octave counts.

Equations: pt-code-7.9 (fBm, A0 = 1, F0 = 0.5, gain 0.5, lacunarity 2), pt-code-7.5 (march), pt-code-7.8 (normals),
pt-7.1 (light). Each panel uses n octaves for the marched surface and for the normals alike, with no distance rule
(pt-alg-7.3-lod switched off: normal_octaves_min = normal_octaves_max = n), so the aliasing the text describes shows.
Camera 70 units above the mean level looking 35 deg down; materials (b) and soft shadows; the text's camera and colours
are not given. Output: figures/pt/fig-7.7.png.
"""
# %% [markdown]
# Every octave doubles the frequency and halves the amplitude: octave 1 gives the hills, octaves 2-4 the rocks,
# octave 8 "stones" of 24 / 2^7 / 2 ~ 0.1 units. From 70 units away a pixel covers ~0.2 units, so octaves 7-8 are
# finer than a pixel: one ray per pixel samples them at random-looking phases (aliasing, the sparkle on the right
# panels). The terrain scene therefore lowers the normals' octave count with distance (pt-alg-7.3-lod).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.terrain.settings import TerrainSettings  # noqa: E402
from pywarp.terrain.technique import TerrainTechnique  # noqa: E402


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (64, 36) if quick else (320, 180)
    fig, axes = plt.subplots(3, 3, figsize=(12, 7.4))
    for k, ax in enumerate(axes.ravel()):
        ax.set_axis_off()
        if k >= 8:
            continue
        n = k + 1
        s = TerrainSettings(width=w, height=h, stage="materials", camera_y=70.0, camera_pitch_deg=-35.0,
                            march_octaves=n, normal_octaves_max=n, normal_octaves_min=n, max_steps=400)
        ax.imshow(TerrainTechnique(s).render())
        ax.set_title(f"{n} octave{'s' if n > 1 else ''}", fontsize=10)
    p = out_dir / "fig-7.7.png"
    fig.savefig(p, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return [p]



if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
