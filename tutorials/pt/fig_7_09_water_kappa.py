"""Figure pt-fig-7.9: reflection against refraction on the water surface at a constant camera angle for kappa = 1, 3
and 6 (eq. 7.4).

Equations: pt-7.4 (f = |v . n|^kappa: the weight of the underwater terrain against the reflected sky), pt-alg-7.3.4
(water plane, wave normal, reflection of sky and clouds), pt-code-7.10, pt-code-7.11. The water level and the wave
normal are not given: the terrain scene's (level -5, our noise + sine waves). Camera above the lake of the default
view, looking 30 deg down. Output: figures/pt/fig-7.9.png.
"""
# %% [markdown]
# Near the camera the view ray meets the water steeply (|v . n| near 1) and the bottom shows for every kappa; farther
# out the angle grows and the reflection takes over -- sooner for a larger kappa.

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
    w, h = (80, 60) if quick else (400, 300)
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.6))
    for ax, kappa in zip(axes, (1.0, 3.0, 6.0)):
        s = TerrainSettings(width=w, height=h, camera_x=-8.0, camera_y=4.0, camera_z=5.0, camera_yaw_deg=20.0,
                            camera_pitch_deg=-30.0, water_kappa=kappa)
        ax.imshow(TerrainTechnique(s).render())
        ax.set_title(f"kappa = {kappa:g}")
        ax.set_axis_off()
    p = out_dir / "fig-7.9.png"
    fig.savefig(p, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return [p]



if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/pt")
