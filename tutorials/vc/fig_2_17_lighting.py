"""Figure vc-fig-2.17 (photographs of lighting features), stand-in: renders isolating silver lining, powder darkening
and directional light.

The thesis shows reference photographs of the three effects its lighting model targets (reproducible: no). The
stand-in isolates each term of the cloud energy E = exp(-d a) HG(theta, g) (1 - exp(-2 d)) (vc-2.31; HG is vc-2.13,
the optical depth d towards the sun comes from the six cone samples of vc-A19, a from the precipitation, plus the
ambient term of vc-A20) in renders of the full cloud pass (vc-A17, vc-A21, vc-4.8; Preetham sky vc-A29).
Renderer: pywarp.clouds.cloudscape. The plots evaluate pywarp.phase_hg and pywarp.clouds_energy.

Rows (the thesis gives no parameters; coverage 0.45, cloud type 0.75, seed 0, 400x225 per panel, 50° field of view):
(1) silver lining -- camera 0.3 km up looking 15° up towards a sun 10° above the horizon, g = 0 / 0.2 (the default) /
0.4: the forward lobe of Henyey-Greenstein lights the cloud edges around the sun;
(2) powder darkening ("dark edges") -- sun 20° up behind the camera (azimuth 180°), camera looking 22° up:
the default (Beer x powder), the powder term switched off, and the Beer term switched off. The renderer has no switch
for the powder term, so "powder off" is emulated with `advanced`: sigma_light x 50 and absorption_base,
absorption_precip / 50 leave exp(-d a) unchanged while 1 - exp(-2 d) becomes 1 - exp(-100 d) ~ 1 (exact except where
d < ~0.03). "Beer off" is absorption_base = absorption_precip = 0 (a = 0).
(3) directional light -- seen from 5 km (12° down), sun 12° up from the left (azimuth -90°), from the right (+90°) and
from behind the camera (180°): the sides facing the sun are bright, the far sides are shadowed by the cloud itself
(Beer's law on d).
Output: figures/vc/fig-2.17.png.
"""
# %% [markdown]
# The thesis lights every sample with one formula (2.31) and names three effects it should produce:
#
# * **silver lining** — the bright rim of a cloud seen against the sun. Droplets scatter mostly forward; the
#   Henyey–Greenstein phase function HG(θ, g) with g > 0 has a peak at θ = 0 (looking towards the sun), so thin
#   edges between the camera and the sun light up. With g = 0 (isotropic) the rim disappears.
# * **dark edges (powder effect)** — with the sun behind the viewer, the outermost parts of a cumulus look darker
#   than the parts just inside: a point at the very surface has little cloud around it to scatter light towards the
#   viewer. The thesis models it with the factor 1 − exp(−2d), which is 0 at d = 0 and goes to 1 inside.
# * **directional lighting** — the side of a cloud facing the sun is bright, the far side dark: Beer's law exp(−d·a)
#   on the optical depth d between the sample and the sun.
#
# Each row below changes one thing and keeps the rest fixed.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402

import pywarp  # noqa: E402
from pywarp.clouds.cloudscape import CameraPose, CloudscapeSettings, CloudscapeTechnique, param_values  # noqa: E402

SCENE = dict(coverage=0.45, cloud_type=0.75, seed=0, fov_y_deg=50.0)
FULL = dict(width=400, height=225)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)
POWDER_OFF_K = 50.0  # sigma_light x K, absorption / K: Beer unchanged, powder 1 - exp(-2 K d) ~ 1
BELOW_TO_SUN = CameraPose(0.0, 0.3, 0.0, 0.0, 15.0, 50.0)
BELOW_AWAY = CameraPose(0.0, 0.3, 0.0, 0.0, 22.0, 50.0)
ABOVE = CameraPose(0.0, 5.0, 0.0, 0.0, -12.0, 50.0)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = QUICK if quick else FULL
    p = param_values(CloudscapeSettings())  # the renderer's defaults of sigma_light and the absorption a
    powder_off = {"sigma_light": p["sigma_light"] * POWDER_OFF_K,
                  "absorption_base": p["absorption_base"] / POWDER_OFF_K,
                  "absorption_precip": p["absorption_precip"] / POWDER_OFF_K}
    beer_off = {"absorption_base": 0.0, "absorption_precip": 0.0}
    rows = (
        ("silver lining", BELOW_TO_SUN, dict(sun_elevation_deg=10.0, sun_azimuth_deg=0.0),
         (("g = 0 (isotropic)", dict(g=0.0)), ("g = 0.2 (default)", dict(g=0.2)), ("g = 0.4", dict(g=0.4)))),
        ("dark edges (powder)", BELOW_AWAY, dict(sun_elevation_deg=20.0, sun_azimuth_deg=180.0),
         (("Beer × powder (default)", {}), ("powder off (emulated)", dict(advanced=powder_off)),
          ("Beer off (a = 0): powder only", dict(advanced=beer_off)))),
        ("directional light", ABOVE, dict(sun_elevation_deg=12.0),
         (("sun from the left (az −90°)", dict(sun_azimuth_deg=-90.0)),
          ("sun from the right (az +90°)", dict(sun_azimuth_deg=90.0)),
          ("sun behind the camera (az 180°)", dict(sun_azimuth_deg=180.0)))),
    )

    # %% [markdown]
    # One technique renders everything that shares textures; `update(**changes)` swaps the lighting settings without
    # regenerating the textures (they depend only on seed, coverage, precipitation, cloud type and sizes).

    # %%
    tech = CloudscapeTechnique(CloudscapeSettings(**size, **SCENE))
    base_settings = tech.settings
    images = []
    for _, pose, common, panels in rows:
        row = []
        for _, changes in panels:
            tech.update(**{**{f: getattr(base_settings, f) for f in ("g", "sun_azimuth_deg", "advanced")},
                           **common, **changes})
            row.append(tech.render(pose))
        images.append(row)

    # %%
    fig = plt.figure(figsize=(17.0, 9.6), dpi=60 if quick else 100)
    gs = fig.add_gridspec(3, 3, left=0.03, right=0.75, top=0.92, bottom=0.06, wspace=0.05, hspace=0.22)
    gp = fig.add_gridspec(3, 1, left=0.80, right=0.99, top=0.92, bottom=0.06, hspace=0.55)
    for r, (label, _, _, panels) in enumerate(rows):
        for c, (title, _) in enumerate(panels):
            ax = fig.add_subplot(gs[r, c])
            ax.imshow(images[r][c], interpolation="nearest")
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_title(title, fontsize=10)
            if c == 0:
                ax.set_ylabel(label, fontsize=11)

    # %% [markdown]
    # The plots: (1) the phase function HG(θ, g) of the three renders — the silver lining is the forward peak at
    # θ = 0; (2) the three factors of 2.31 against the optical depth d towards the sun (a = 1.4, the renderer's
    # a = 1 + 2·precipitation at precipitation 0.2): powder rises from 0, Beer falls from 1, their product peaks at
    # d = ln(3)/2 ≈ 0.55 for a = 1 — the edges (small d) are dark, a thin layer just inside is brightest;
    # (3) the energy E with HG at θ = 90° (side light) for a = 1 and a = 3 (rain): the shadowed side (large d) is dark.

    # %%
    theta = np.linspace(0.0, np.pi, 361)
    ax = fig.add_subplot(gp[0, 0])
    for g in (0.0, 0.2, 0.4):
        ax.semilogy(np.degrees(theta), pywarp.phase_hg(np.cos(theta), g), label=f"g = {g}")
    ax.set_xlabel("scattering angle θ [deg] (0 = towards the sun)", fontsize=8)
    ax.set_ylabel("HG(θ, g) [sr⁻¹]", fontsize=8)
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.legend(fontsize=8, frameon=False)
    ax.set_title("phase function (2.13)", fontsize=10)
    ax.tick_params(labelsize=7)

    d = np.linspace(0.0, 4.0, 401)
    a = 1.4
    ax = fig.add_subplot(gp[1, 0])
    ax.plot(d, np.exp(-d * a), label="Beer exp(−d·a)")
    ax.plot(d, 1.0 - np.exp(-2.0 * d), label="powder 1 − exp(−2d)")
    ax.plot(d, np.exp(-d * a) * (1.0 - np.exp(-2.0 * d)), "k", label="product")
    ax.plot(d, 1.0 - np.exp(-2.0 * POWDER_OFF_K * d), ":", color="tab:orange", label="powder 'off' (emulated)")
    ax.set_xlabel("optical depth towards the sun d", fontsize=8)
    ax.legend(fontsize=7, frameon=False)
    ax.set_title(f"terms of 2.31 (a = {a})", fontsize=10)
    ax.tick_params(labelsize=7)

    ax = fig.add_subplot(gp[2, 0])
    for a_ in (1.0, 3.0):
        ax.plot(d, pywarp.clouds_energy(d, a_, 0.0, 0.2), label=f"E(d), a = {a_:g}, θ = 90°, g = 0.2")
    ax.set_xlabel("optical depth towards the sun d", fontsize=8)
    ax.set_ylabel("E [sr⁻¹]", fontsize=8)
    ax.legend(fontsize=7, frameon=False)
    ax.set_title("energy E (2.31, pywarp.clouds_energy)", fontsize=10)
    ax.tick_params(labelsize=7)

    fig.suptitle("Fig 2.17 stand-in (the thesis shows photographs): the three lighting effects of eq. 2.31, one "
                 "term changed per panel", fontsize=12)
    out = out_dir / "fig-2.17.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="figures/vc")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    print(*main(args.out, quick=args.quick), sep="\n")
