"""Extra rr-extra-rain-lights: the light-drop model the text describes but never built (rr-A1, rr-A2, rr-A3, rr-CF)
switched on in the rain scene -- two point lights near the viewer, drops and streaks, beside the same frames without
lights (the scene's default, as the text's application). Output: figures/rr/extra-rain-lights.png.
"""
# %% [markdown]
# Every refraction tap of the compositing pass can go through the light model: C_F = C_O C_amb + sum over the two
# lights of A1 (A2 + A3), with A1 = C_L DistFact (V_PE . N), DistFact = 1 / (1 + (d / r_half)^2) (the text leaves
# its form open), A2 = max(0, V_PL . N) the external reflection and A3 the internal reflections leaving up or down.
# The normal N is the entry normal of the drop's mask texel, turned from the billboard frame into the scene; the
# pixel position is the drop's centre (next to lights a metre away a drop is a point).
#
# In `RainSettings` the lights are `light1_pos`, `light1_colour`, `light2_pos`, `light2_colour` (camera-relative
# scene units; colour 0 = off, the default), `light_ambient` (C_amb), `light_r_half` and `light_variant` (rr-A1's
# clamp). Here: a warm lamp up and to the right, a cold one low on the left, both just beyond the nearest drops.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.rain.settings import RainSettings  # noqa: E402
from pywarp.rain.technique import RainTechnique  # noqa: E402

SCENE = dict(background="terrain", background_options={"seed": 7, "sun_elevation_deg": 35.0, "sun_azimuth_deg": 60.0},
             camera_yaw_deg=140.0, camera_pitch_deg=-6.0)
LIGHTS = dict(light1_colour=(1.0, 0.75, 0.4), light2_colour=(0.35, 0.55, 1.0))


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = dict(width=192, height=108, capture_size=128, mask_size=128) if quick else dict(width=640, height=360)
    tech = RainTechnique(RainSettings(**size, **SCENE, drops=3000, time_s=2.0 / 0.05, seed=5, mode="drops"))
    frames = {}
    for mode in ("drops", "streaks"):
        tech.update(mode=mode, light1_colour=(0.0, 0.0, 0.0), light2_colour=(0.0, 0.0, 0.0))
        frames[(mode, "off")] = tech.render()
        tech.update(**LIGHTS)
        frames[(mode, "on")] = tech.render()
    s = tech.settings
    fig, axes = plt.subplots(2, 2, figsize=(13, 7.6), dpi=70 if quick else 120)
    for (mode, state), ax in zip(frames, axes.ravel()):
        ax.imshow(frames[(mode, state)], interpolation="nearest")
        ax.set_title(f"{mode}, lights {state}" + (f": warm {s.light1_colour} at {s.light1_pos}, cold "
                                                    f"{s.light2_colour} at {s.light2_pos}" if state == "on" else
                                                    " (the scene's default, as the text's application)"),
                     fontsize=8)
        ax.axis("off")
    fig.suptitle(f"rr-A1..rr-CF in the rain scene: two point lights, DistFact half distance {s.light_r_half:g} m, "
                 f"C_amb = {s.light_ambient}", fontsize=10)
    fig.tight_layout()
    path = out_dir / "extra-rain-lights.png"
    fig.savefig(path)
    plt.close(fig)
    return [path]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
