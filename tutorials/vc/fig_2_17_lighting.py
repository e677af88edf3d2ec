"""Figure vc-fig-2.17 (photographs of lighting features), stand-in: renders isolating silver lining, powder darkening
and directional light.

The thesis shows reference photographs of the three effects its lighting model targets (reproducible: no). The
stand-in isolates each term of the cloud energy E = exp(-d a) HG(theta, g) (1 - exp(-2 d)) (vc-2.31; HG is vc-2.13,
the optical depth d towards the sun comes from the six cone samples of vc-A19, a from the precipitation, plus the
ambient term of vc-A20) in renders of the full cloud pass (vc-A17, vc-A21, vc-4.8; Preetham sky vc-A29), with the
thesis's constant lighting and powder term (lighting='thesis', powder=True) so that only the term under study
changes, and compares the renderer's dual-lobe phase (the sky lighting's silver-lining lobe, cclouds/cloudscape.h
"Lighting").
Renderer: pywarp.clouds.cloudscape. The plots evaluate pywarp.phase_hg, pywarp.clouds_energy and the renderer's
ccl_cloudscape_energy (multiple-scattering octaves).

Rows (the thesis gives no parameters; coverage 0.45, cloud type 0.75, seed 0, 400x225 per panel):
(1) silver lining -- camera 0.3 km up looking 15 deg up towards a sun 10 deg above the horizon (50 deg field of
view): one HG lobe with g = 0 (isotropic), g = 0.2 (the thesis lighting's default), and the dual lobe
0.7 HG(0.2) + 0.3 HG(0.8), the sky lighting's option (silver_weight; off by default): the narrow forward lobe
lights the cloud edges around the sun;
(2) powder darkening ("dark edges") -- sun 20 deg up behind the camera (azimuth 180 deg), camera looking 22 deg up:
vc-2.31 as printed (Beer x powder), the powder term off (powder=False: 1 - exp(-2 d) replaced by 1; the renderer's
default, measured closer to the path-traced reference by tools/tune_lighting.py) and the Beer term off (beer=False);
(3) directional light -- one cumulus seen from 1 km up (40 deg field of view), sun 15 deg up from the left (azimuth
-98 deg, at right angles to the view), from the right (+82 deg) and from behind the camera (172 deg): the side
facing the sun is bright, the far side is shadowed by the cloud itself (Beer's law on d). This row isolates Beer's
term: the powder term is off (its dark sunward rim would hide which side is lit) and the ambient light is half the
thesis's constants, so that the sun's term dominates (with both as default the same shading shows at lower
contrast, row 2's first panel).
Every panel averages 16 jittered frames (render_accumulated: no ray-jitter speckle in the distant clouds) and is shown
through the scene's display transform (-0.5 EV, ACES). The second output enlarges, for the silver lining and for the
powder term, the window of 1/3 x 1/3 of the panel where the two renders compared differ most: a sunlit edge.
Outputs: figures/vc/fig-2.17.png, figures/vc/fig-2.17-crops.png.
"""
# %% [markdown]
# The thesis lights every sample with one formula (2.31) and names three effects it should produce:
#
# * **silver lining** — the bright rim of a cloud seen against the sun. Droplets scatter mostly forward; the
#   Henyey–Greenstein phase function HG(θ, g) with g > 0 has a peak at θ = 0 (looking towards the sun), so thin
#   edges between the camera and the sun light up. With g = 0 (isotropic) the rim disappears; the thesis's mild
#   g = 0.2 shows a faint one. Real droplets have a much narrower forward peak: the renderer's sky lighting can add
#   a second lobe, (1 − w) HG(g) + w HG(0.8), here with w = 0.3, and the rims glow (off by default: the path-traced
#   reference, whose medium scatters by the one lobe g, is matched better without it).
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
from pywarp.clouds.cloudscape import CloudscapeSettings  # noqa: E402
from pywarp.clouds.settings import CLOUDSCAPE_PARAMS  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.core.pose import Pose  # noqa: E402

SCENE = dict(coverage=0.45, cloud_type=0.75, seed=0, fov_y_deg=50.0, lighting="thesis", powder=True)
FULL = dict(width=400, height=225)
QUICK = dict(width=96, height=54, base_size=32, detail_size=16, curl_size=32, weather_size=64)
BELOW_TO_SUN = Pose(0.0, 0.3, 0.0, 0.0, 15.0, 50.0)
BELOW_AWAY = Pose(0.0, 0.3, 0.0, 0.0, 22.0, 50.0)
CUMULUS = Pose(0.0, 1.0, 0.0, -8.0, 9.0, 40.0)
SILVER = {"silver_g": 0.8, "silver_weight": 0.3}  # the option shown (the default is one lobe: silver_weight 0)
AMBIENT_SCALE = 0.5  # row 3: the ambient constants x 1/2, so that the sun's term dominates
ACCUMULATE = 16  # jittered frames per panel (full size): the ray-jitter noise falls to 1/4 of one frame's


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = QUICK if quick else FULL
    p = CloudscapeSettings(lighting="thesis").c_values()  # the thesis lighting's constants
    dim = {name: tuple(AMBIENT_SCALE * v for v in p[name]) for name in ("ambient_bottom", "ambient_top")}
    rows = (
        ("silver lining", BELOW_TO_SUN, dict(sun_elevation_deg=10.0, sun_azimuth_deg=0.0),
         (("one lobe, g = 0 (isotropic)", dict(g=0.0)), ("one lobe, g = 0.2 (thesis)", dict(g=0.2)),
          ("0.7 HG(0.2) + 0.3 HG(0.8) (option)", dict(g=0.2, advanced=SILVER)))),
        ("dark edges (powder)", BELOW_AWAY, dict(sun_elevation_deg=20.0, sun_azimuth_deg=180.0),
         (("Beer × powder (vc-2.31)", {}), ("powder off (renderer default)", dict(powder=False)),
          ("Beer off: powder only", dict(beer=False)))),
        ("directional light", CUMULUS, dict(sun_elevation_deg=15.0, advanced=dim, powder=False),
         (("sun from the left", dict(sun_azimuth_deg=-98.0)), ("sun from the right", dict(sun_azimuth_deg=82.0)),
          ("sun behind the camera", dict(sun_azimuth_deg=172.0)))),
    )

    # %% [markdown]
    # One technique renders everything that shares textures; `update(**changes)` swaps the lighting settings without
    # regenerating the textures (they depend only on seed, coverage, precipitation, cloud type and sizes).

    # %%
    tech = CloudscapeTechnique(CloudscapeSettings(**size, **SCENE))
    base_settings = tech.settings
    reset = {f: getattr(base_settings, f) for f in ("g", "sun_azimuth_deg", "advanced", "beer", "powder")}
    images = []
    for _, pose, common, panels in rows:
        row = []
        for _, changes in panels:
            tech.update(**{**reset, **common, **changes})
            row.append(tech.render_accumulated(pose, 2 if quick else ACCUMULATE))
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
    # The plots: (1) the phase functions of the three renders — the silver lining is the forward peak at θ = 0, 24x
    # higher for the dual lobe than for g = 0.2; (2) the three factors of 2.31 against the optical depth d towards the
    # sun (a = 1.4, the renderer's a = 1 + 2·precipitation at precipitation 0.2): powder rises from 0, Beer falls from
    # 1, their product peaks at d = ln(3)/2 ≈ 0.55 for a = 1 — the edges (small d) are dark, a thin layer just inside
    # is brightest; (3) the energy E with HG at θ = 90° (side light): the shadowed side (large d) is dark; the
    # renderer's multiple-scattering octaves (sky lighting: octave i with d·0.5^i, contribution 0.75^i, the octaves
    # i >= 1 weighted by 0.2 + 0.8 (1 - exp(-d / 1.5)): the defaults) lift the deep, shadowed parts.

    # %%
    theta = np.linspace(0.0, np.pi, 361)
    ax = fig.add_subplot(gp[0, 0])
    for g in (0.0, 0.2):
        ax.semilogy(np.degrees(theta), pywarp.phase_hg(np.cos(theta), g), label=f"HG(θ, {g})")
    dual = (1.0 - SILVER["silver_weight"]) * pywarp.phase_hg(np.cos(theta), 0.2) + \
        SILVER["silver_weight"] * pywarp.phase_hg(np.cos(theta), SILVER["silver_g"])
    ax.semilogy(np.degrees(theta), dual, label="0.7 HG(θ, 0.2) + 0.3 HG(θ, 0.8)")
    ax.set_xlabel("scattering angle θ [deg] (0 = towards the sun)", fontsize=8)
    ax.set_ylabel("phase [sr⁻¹]", fontsize=8)
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.legend(fontsize=8, frameon=False)
    ax.set_title("phase functions (2.13, dual lobe)", fontsize=10)
    ax.tick_params(labelsize=7)

    d = np.linspace(0.0, 4.0, 401)
    a = 1.4
    ax = fig.add_subplot(gp[1, 0])
    ax.plot(d, np.exp(-d * a), label="Beer exp(−d·a)")
    ax.plot(d, 1.0 - np.exp(-2.0 * d), label="powder 1 − exp(−2d)")
    ax.plot(d, np.exp(-d * a) * (1.0 - np.exp(-2.0 * d)), "k", label="product")
    ax.set_xlabel("optical depth towards the sun d", fontsize=8)
    ax.legend(fontsize=7, frameon=False)
    ax.set_title(f"terms of 2.31 (a = {a})", fontsize=10)
    ax.tick_params(labelsize=7)

    ax = fig.add_subplot(gp[2, 0])
    ax.plot(d, pywarp.clouds_energy(d, 1.0, 0.0, 0.2), label="E(d) of 2.31 (1 octave), a = 1")
    ax.plot(d, pywarp.clouds_energy(d, 3.0, 0.0, 0.2), label="E(d) of 2.31, a = 3 (rain)")
    ax.plot(d, _energy_octaves(d, 1.0, 4), "--", label="4 octaves (sky lighting), a = 1")
    ax.set_xlabel("optical depth towards the sun d", fontsize=8)
    ax.set_ylabel("E [sr⁻¹] (θ = 90°, g = 0.2)", fontsize=8)
    ax.legend(fontsize=7, frameon=False)
    ax.set_title("energy E (2.31; ccl_cloudscape_energy)", fontsize=10)
    ax.tick_params(labelsize=7)

    fig.suptitle("Fig 2.17 stand-in (the thesis shows photographs): the three lighting effects of eq. 2.31, one "
                 "term changed per panel", fontsize=12)
    out = out_dir / "fig-2.17.png"
    fig.savefig(out)
    plt.close(fig)

    # %% [markdown]
    # At page size the silver lining and the powder term are thin features along the cloud edges. The crops enlarge
    # the window where each pair of renders differs most: with the second lobe the edges towards the sun glow; with
    # the powder term the sunlit rim is darker than the cloud just inside it (the "dark edges"), without it the rim
    # is the brightest part.

    # %%
    pairs = (("silver lining", images[0][1], images[0][2], "one lobe, g = 0.2", "+ 0.3 HG(0.8) lobe"),
             ("powder", images[1][1], images[1][0], "powder off", "powder on (vc-2.31)"))
    fig, axes = plt.subplots(2, 3, figsize=(15.0, 7.4), dpi=60 if quick else 100)
    for r, (label, a, b, name_a, name_b) in enumerate(pairs):
        diff = np.abs(a.astype(int) - b.astype(int)).sum(axis=-1)
        h, w = diff.shape
        wh = (max(h // 3, 8), max(w // 3, 8))
        y, x = _window_of_largest(diff.astype(float), wh)
        crop = (slice(y, y + wh[0]), slice(x, x + wh[1]))
        for c, (img, name) in enumerate(((a, name_a), (b, name_b))):
            axes[r, c].imshow(img[crop], interpolation="nearest")
            axes[r, c].set_title(f"{label}: {name}", fontsize=10)
        axes[r, 2].imshow(a, interpolation="nearest")
        axes[r, 2].add_patch(plt.Rectangle((x - 0.5, y - 0.5), wh[1], wh[0], fill=False, ec="r", lw=1.5))
        axes[r, 2].set_title(f"where the crops are ({name_a})", fontsize=10)
        for ax in axes[r]:
            ax.set_axis_off()
    fig.suptitle("Fig 2.17 stand-in, enlarged: the sunlit edges where the silver-lining lobe and the powder term "
                 "change the image most", fontsize=12)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.9, bottom=0.01, wspace=0.04, hspace=0.14)
    crops = out_dir / "fig-2.17-crops.png"
    fig.savefig(crops)
    plt.close(fig)
    return [out, crops]


def _window_of_largest(diff, wh):
    """(row, column) of the top-left corner of the wh = (height, width) window with the largest summed ``diff``."""
    c = np.pad(diff.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    h, w = wh
    sums = c[h:, w:] - c[:-h, w:] - c[h:, :-w] + c[:-h, :-w]
    return np.unravel_index(np.argmax(sums), sums.shape)


def _energy_octaves(d: np.ndarray, a: float, octaves: int) -> np.ndarray:
    """The renderer's energy (ccl_cloudscape_energy, C) at cos(theta) = 0 with one HG lobe, g = 0.2 and ``octaves``
    multiple-scattering octaves of the default factors, the powder term on (vc-2.31 as printed)."""
    from pywarp.core.binding import lib

    s = CloudscapeSettings(ms_octaves=octaves, silver_weight=0.0, g=0.2, powder=True)
    p = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    return np.array([lib().ccl_cloudscape_energy(p, float(x), a, 0.0) for x in d])


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
