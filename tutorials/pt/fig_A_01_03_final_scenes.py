"""Figures pt-fig-A.1, pt-fig-A.2 and pt-fig-A.3: three frames of the finished demo (appendix A's screenshots).

The text's screenshots are frames of its final application; their cameras and parameters are not given, so these
are renders of our terrain scene with its final settings (pywarp.terrain.settings: every default with its reason)
from three viewpoints chosen to show what the demo shows: A.1 the scene's default view (``pywarp render terrain``),
A.2 a lake against the sun from its shore, A.3 a view from high above the hills with the sun behind the camera.

Equations: everything of the final scene -- pt-code-7.1/7.2 (pixel, camera ray), pt-alg-9-bisect (the dynamic
march of pt-code-7.5 at 0.8 of the step, refined by bisection; the text's halved dynamic step gives the same picture
within SSIM 0.996), pt-code-7.9 = pt-alg-3.2 (fBm terrain), pt-code-7.8 with pt-alg-7.3-lod (normals), pt-code-7.7
(soft shadows, steps of at least 1 unit), pt-7.1 (light), pt-alg-7.3-material (materials, grass), pt-code-7.10 (sky, sun glow), pt-code-7.11
(clouds), pt-alg-7.3.4 with pt-7.4 (water), pt-7.3 (fog, printed form). Outputs: figures/pt/fig-A.1.png,
figures/pt/fig-A.2.png, figures/pt/fig-A.3.png.
"""
# %% [markdown]
# The demo runs full screen; we render 960 x 540, the scene's default size. Each frame is the whole pipeline of
# chapter 7: the march finds the terrain (4 octaves), the normal adds detail near the camera (up to 9 octaves),
# soft shadows, grass on flat ground, lakes that mirror the sky and show the bottom near the shore, clouds moving
# with the wind (A.3 is 30 s later than A.1 and A.2) and the fog that hides MAX_T.
#
# To look around yourself: `pywarp view terrain` (mouse look + W, as the demo).

# %%
from __future__ import annotations

from pathlib import Path

from PIL import Image

from pywarp.terrain.settings import TerrainSettings
from pywarp.terrain.technique import TerrainTechnique, ground_height

#: the three viewpoints (settings changes against the final scene's defaults)
VIEWS = {
    "A.1": {},  # the scene's default camera: a ridge above a lake, hills, the sun's glow left of centre
    "A.2": {"camera_x": -45.0, "camera_z": 112.0, "camera_yaw_deg": -20.0, "camera_pitch_deg": -6.0},  # + height
    "A.3": {"camera_x": 60.0, "camera_y": 40.0, "camera_z": -70.0, "camera_yaw_deg": 160.0,
            "camera_pitch_deg": -18.0, "time_s": 30.0},
}
#: A.2's eye above the shore (units): the lake's level stays just below the horizon
EYE_HEIGHT = 4.0


def view_settings(name: str, width: int, height: int) -> TerrainSettings:
    changes = dict(VIEWS[name])
    if name == "A.2":
        s = TerrainSettings()
        ground = max(float(ground_height(s, changes["camera_x"], changes["camera_z"])), s.water_level)
        changes["camera_y"] = ground + EYE_HEIGHT
    return TerrainSettings(width=width, height=height, **changes)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    w, h = (96, 54) if quick else (960, 540)
    paths = []
    for name in VIEWS:
        img = TerrainTechnique(view_settings(name, w, h)).render()
        p = out_dir / f"fig-{name}.png"
        Image.fromarray(img).save(p)
        paths.append(p)
    return paths


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
