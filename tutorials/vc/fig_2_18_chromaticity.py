"""Figure vc-fig-2.18 (comparison of colour models), stand-in: the CIE 1931 chromaticity diagram with the sky's colours.

The thesis shows the chromaticity diagram of CIE RGB and CIE XYZ with XYZ's imaginary primaries; the diagram needs the
CIE 1931 colour-matching data, which the thesis does not contain (spec: reproducible only with external data). This
stand-in draws it with colour-science (``colour.plotting``; **requires the package colour-science**, import name
``colour``): the spectral locus, the sRGB gamut our renderer outputs (vc-4.4), the CIE RGB gamut, the triangle of the
XYZ primaries, and the chromaticities of the Preetham sky computed by pywarp — the zenith x_z, y_z (vc-2.39, vc-2.40, vc-2.41,
``pywarp.sky_preetham_zenith``) over sun elevations and turbidities, and every direction of one whole sky (vc-A29,
``pywarp.sky_preetham_colour(output="xyY")``) — with the chromaticity coordinates of vc-2.32. The errata of vc-2.39 change
only the luminance Y, not x and y, so this figure has no 'thesis' variant. Output: figures/vc/fig-2.18.png.
"""
# %% [markdown]
# Colours that differ only in brightness share a point of this diagram: (x, y) = (X, Y) / (X + Y + Z) (2.32). The
# horseshoe is the spectral locus, the colours of single wavelengths; every visible colour lies inside it. A display
# mixes three primaries and can show only the triangle between them: sRGB (the output of the renderer) covers a
# modest part. CIE RGB, the 1931 primaries of real monochromatic lights at 700, 546.1 and 435.8 nm, has corners on the
# locus. XYZ chose three *imaginary* primaries at (1, 0), (0, 1) and (0, 0) — outside the locus, they are not real
# colours — so that every visible colour has non-negative X, Y, Z and Y alone is the luminance.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

import pywarp  # noqa: E402

try:
    import colour  # noqa: E402
    import colour.plotting  # noqa: E402
except ImportError as exc:  # pragma: no cover - colour-science is installed in the project's environment
    raise ModuleNotFoundError("fig_2_18_chromaticity.py needs the package 'colour-science' (import name 'colour') "
                              "for the CIE 1931 data and diagram: pip install colour-science") from exc

TURBIDITIES = (2.0, 3.0, 4.0, 6.0, 8.0, 10.0)  # the Preetham fits' range is T = 2..10
ELEVATION_MARKS = (0.0, 15.0, 30.0, 60.0, 90.0)  # sun elevations [deg] marked on each curve
DOME_T, DOME_ELEVATION = 3.0, 30.0  # the one whole sky shown (clear day, afternoon sun)
ZOOM = (0.215, 0.375, 0.215, 0.385)  # x0, x1, y0, y1 of the right panel


def _diagram(ax, **kwargs):
    colour.plotting.plot_RGB_colourspaces_in_chromaticity_diagram_CIE1931(
        ["sRGB", "CIE RGB"], axes=ax, show=False, show_whitepoints=False, title=None,
        plot_kwargs=[{"color": "black", "linewidth": 1.6}, {"color": "#6a3d9a", "linewidth": 1.2, "linestyle": "--"}],
        legend=False, **kwargs)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)

    # %% [markdown]
    # The Preetham zenith chromaticity: a cubic polynomial in the sun's zenith angle and a quadratic in the turbidity
    # T (2.40, 2.41). Clear skies (T = 2) are the bluest; as haze grows the zenith moves towards white. For a given
    # turbidity the zenith is bluest with the sun at a middle elevation (about 30° for T = 2) and whiter both for a
    # low sun and for a sun near the zenith. All of it lies in a small region below and left of the D65 white point of
    # sRGB: the right panel zooms in, with the CIE daylight locus (the colours of daylight of a given correlated
    # colour temperature) for reference. The sky is bluer than 6500 K daylight: a clear zenith (T = 2, 3) sits between
    # about 9 000 and 29 000 K. The faint grey dots are the x, y of every view direction of one sky (T = 3, sun at
    # 30°), from the same Perez distribution the renderer evaluates per pixel; the tail towards yellow-white is the
    # circumsolar region.

    # %%
    n_el = 46 if quick else 181
    elevation = np.linspace(0.0, 90.0, n_el, dtype=np.float32)
    theta_s = np.radians(90.0 - elevation).astype(np.float32)
    theta_s = np.clip(theta_s, 0.0, np.float32(np.pi / 2))  # float32(pi/2) is the horizon, accepted by the Arg
    curves = {}
    for t in TURBIDITIES:
        x, y, _ = np.moveaxis(pywarp.sky_preetham_zenith(np.full_like(theta_s, t), theta_s), -1, 0)
        curves[t] = (x, y)
    n_dir = 40 if quick else 120  # dome directions per axis (azimuth x elevation above the horizon)
    az = np.radians(np.linspace(0.0, 360.0, 2 * n_dir, endpoint=False))
    el = np.radians(np.linspace(0.5, 89.5, n_dir))
    A, E = np.meshgrid(az, el)
    dirs = np.stack([np.cos(E) * np.sin(A), np.sin(E), -np.cos(E) * np.cos(A)], axis=-1).astype(np.float32)
    dome_x, dome_y, _ = np.moveaxis(pywarp.sky_preetham_colour(dirs.reshape(-1, 3), DOME_T, DOME_ELEVATION,
                                                               output="xyY"), -1, 0)

    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(14, 6.8), dpi=80 if quick else 130,
                                   gridspec_kw={"width_ratios": [1.0, 1.15]})
    _diagram(ax0)
    ax0.plot([1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 0.0], color="#b15928", lw=1.2, ls=":", clip_on=False)
    for (px, py), name, off in (((1.0, 0.0), "X", (-0.02, 0.02)), ((0.0, 1.0), "Y", (0.015, -0.02)),
                                ((0.0, 0.0), "Z", (0.015, 0.015))):
        ax0.plot([px], [py], "s", color="#b15928", ms=6, clip_on=False, zorder=10)
        ax0.text(px + off[0], py + off[1], name, color="#b15928", fontsize=10, fontweight="bold",
                 ha="right" if px > 0.5 else "left", va="bottom" if py < 0.5 else "top")
    d65 = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]
    ax0.plot(*d65, "o", mfc="white", mec="black", ms=6, zorder=10)
    for t, (x, y) in curves.items():
        ax0.plot(x, y, color="#1f78b4", lw=1.0)
    ax0.add_patch(Rectangle((ZOOM[0], ZOOM[2]), ZOOM[1] - ZOOM[0], ZOOM[3] - ZOOM[2], fill=False, ec="#1f78b4",
                            lw=1.0))
    ax0.set_xlim(-0.08, 1.04)
    ax0.set_ylim(-0.04, 1.04)
    ax0.set_aspect("equal")
    ax0.set_title("CIE 1931 chromaticity diagram (colour-science)", fontsize=11)
    handles = [plt.Line2D([], [], color="black", lw=1.6, label="sRGB gamut (renderer output)"),
               plt.Line2D([], [], color="#6a3d9a", lw=1.2, ls="--", label="CIE RGB gamut (real primaries)"),
               plt.Line2D([], [], color="#b15928", lw=1.2, ls=":", marker="s", ms=5,
                          label="XYZ primaries (imaginary)"),
               plt.Line2D([], [], color="black", marker="o", mfc="white", ls="none", label="D65 white point"),
               plt.Line2D([], [], color="#1f78b4", lw=1.0, label="Preetham zenith (right: zoom)")]
    ax0.legend(handles=handles, loc="upper right", fontsize=8.5, framealpha=0.9)

    # %% [markdown]
    # Right panel: the zoom. Each curve is one turbidity, traced from the sun on the horizon to the sun at the zenith;
    # the markers are the sun elevations listed in the legend.

    # %%
    _diagram(ax1, show_diagram_colours=False)  # a white background keeps the curves readable
    ax1.scatter(dome_x, dome_y, s=2, color="0.55", alpha=0.2, lw=0, zorder=3,
                label=f"whole sky, T = {DOME_T:g}, sun {DOME_ELEVATION:g}° (vc-A29)")
    cct = np.array([5000.0, 8000.0, 10000.0, 15000.0, 25000.0])  # 6500 K is the D65 point
    locus = colour.temperature.CCT_to_xy_CIE_D(np.linspace(4000.0, 25000.0, 200))
    ax1.plot(locus[:, 0], locus[:, 1], color="0.3", lw=1.0, ls="-.", label="CIE daylight locus")
    for k, (lx, ly) in zip(cct, colour.temperature.CCT_to_xy_CIE_D(cct)):
        ax1.plot([lx], [ly], "|", color="0.3", ms=8, mew=1.2)
        ax1.text(lx + 0.002, ly - 0.004, f"{k / 1000:g} kK", fontsize=7.5, color="0.3", ha="left", va="top")
    cmap = plt.get_cmap("viridis")
    marks = [int(np.argmin(np.abs(elevation - e))) for e in ELEVATION_MARKS]
    symbols = ("v", "s", "o", "D", "^")
    for i, (t, (x, y)) in enumerate(curves.items()):
        c = cmap(i / (len(TURBIDITIES) - 1))
        ax1.plot(x, y, color=c, lw=1.8, label=f"zenith, T = {t:g}", zorder=5)
        for j, sym in zip(marks, symbols):
            ax1.plot([x[j]], [y[j]], sym, color=c, mec="black", mew=0.5, ms=5.5, zorder=6)
    for e, sym in zip(ELEVATION_MARKS, symbols):
        ax1.plot([], [], sym, color="white", mec="black", ms=5.5, ls="none", label=f"sun elevation {e:g}°")
    ax1.plot(*d65, "o", mfc="white", mec="black", ms=7, zorder=10)
    ax1.text(d65[0] + 0.003, d65[1] + 0.002, "D65", fontsize=8.5, ha="left", va="bottom")
    ax1.set_xlim(ZOOM[0], ZOOM[1])
    ax1.set_ylim(ZOOM[2], ZOOM[3])
    ax1.set_aspect("equal")
    ax1.set_title("Preetham sky chromaticities (pywarp.sky_preetham_zenith, 2.40/2.41)", fontsize=11)
    ax1.legend(loc="center left", bbox_to_anchor=(1.02, 0.5), fontsize=8, frameon=False, markerscale=1.2)
    fig.suptitle("Colour models: the visible colours (spectral locus), the sRGB and CIE RGB gamuts, the imaginary XYZ "
                 "primaries, and the colours of the Preetham sky", fontsize=11.5)
    fig.subplots_adjust(left=0.04, right=0.83, top=0.9, bottom=0.07, wspace=0.12)
    out = out_dir / "fig-2.18.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
