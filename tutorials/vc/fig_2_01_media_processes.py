"""Figure vc-fig-2.1: types of processes in participating media, with the radiance they produce along a ray.

Top: a schematic (drawn with matplotlib, no computation) of a ray through a medium and the four interactions of §2.1:
absorption (vc-2.1), out-scattering (vc-2.2), in-scattering and emission (vc-2.9), which together form the radiative
transfer equation (vc-2.10) with extinction sigma_t = sigma_a + sigma_s (vc-2.3) and transmittance (vc-2.6).
Bottom, a computational companion the thesis does not have: the radiance reaching the eye through a constant medium of
depth s, from the volume rendering equation (vc-2.17, ``pywarp.media_volume_render``) and its raymarching
approximation (vc-2.18, ``pywarp.media_raymarch``), switching the four terms on one after another, against the closed
form of the constant medium. Output: figures/vc/fig-2.1.png.
"""
# %% [markdown]
# Light that crosses a cloud, smoke or haze meets particles. Four things can happen at a particle, and each changes the
# radiance L carried along the ray:
#
# * **absorption** turns light into heat: L decreases by sigma_a L per unit length (2.1);
# * **out-scattering** deflects light out of the ray into other directions: L decreases by sigma_s L (2.2);
# * **in-scattering** deflects light arriving from elsewhere (here the sun) into the ray: L grows by sigma_s L_i (2.9);
# * **emission** (fire, hot gas) adds light: L grows by sigma_a L_e (2.9).
#
# The first two together are the extinction sigma_t = sigma_a + sigma_s; the sum of all four is the radiative transfer
# equation (2.10). In the schematic the width of the yellow beam is the radiance: it travels from the surface behind
# the medium to the eye, becoming thinner at the losses and thicker at the gains.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle, Ellipse, FancyArrowPatch, FancyBboxPatch, Rectangle  # noqa: E402

import pywarp  # noqa: E402

# Constant medium of the companion plot. The values are illustrative (the thesis gives none): coefficients of a
# light haze in units of 1/m, radiances in units of the background radiance.
SIGMA_A, SIGMA_S = 0.2, 0.3  # [1/m]
L_BG, L_I, L_E = 1.0, 0.5, 1.5  # background, in-scattered (sun via the phase function), emitted radiance
S_MAX = 10.0  # [m] deepest medium plotted

BEAM_Y = 2.2
EVENTS = (  # x position along the ray, beam half-width after the event (light travels right -> left)
    ("absorption", 10.6, 0.17),
    ("out-scattering", 8.2, 0.12),
    ("in-scattering", 5.8, 0.18),
    ("emission", 3.4, 0.25),
)


def _arrow(ax, start, end, color, lw=1.4, style="-|>", ms=10, z=6):
    ax.add_patch(FancyArrowPatch(start, end, arrowstyle=style, mutation_scale=ms, color=color, lw=lw, zorder=z))


def _schematic(ax, rng):
    # %% [markdown]
    # The schematic: the eye at x looks along omega into the medium; behind the medium lies a surface at x_s. The
    # radiance L(x_s, -omega) of the surface travels back towards the eye and is changed at each particle it passes.

    # %%
    ax.set_xlim(0.0, 14.2)
    ax.set_ylim(-0.05, 5.0)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.add_patch(FancyBboxPatch((2.3, 0.45), 9.6, 3.3, boxstyle="round,pad=0.05,rounding_size=1.2",
                                fc="#dfeaf5", ec="#7f9fbf", lw=1.0, zorder=0))
    ax.text(2.4, 3.85, "participating medium, extinction $\\sigma_t = \\sigma_a + \\sigma_s$ (2.3)", ha="left",
            va="bottom", fontsize=9, color="#40607f")
    px, py = rng.uniform(2.6, 11.6, 90), rng.uniform(0.7, 3.5, 90)
    keep = np.abs(py - BEAM_Y) > 0.35  # keep the beam itself clear of background particles
    ax.scatter(px[keep], py[keep], s=7, color="#9fb5cc", zorder=1)
    ax.add_patch(Rectangle((13.0, 0.9), 0.35, 2.6, fc="0.75", ec="0.35", hatch="////", zorder=2))
    ax.text(13.17, 3.65, "surface\n$x_s$", ha="center", va="bottom", fontsize=9)

    # The beam: half-width piecewise constant between the events, with short linear transitions.
    xs = [13.0]
    ws = [0.22]
    for _, x, w in EVENTS:
        xs += [x + 0.25, x - 0.25]
        ws += [ws[-1], w]
    xs += [1.35]
    ws += [ws[-1]]
    xs, ws = np.array(xs[::-1]), np.array(ws[::-1])
    ax.fill_between(xs, BEAM_Y - ws, BEAM_Y + ws, color="#f2c230", alpha=0.85, lw=0, zorder=3)
    for x in (12.3, 9.4, 7.0, 4.6, 2.2):
        _arrow(ax, (x + 0.25, BEAM_Y), (x - 0.25, BEAM_Y), "#8a6400", lw=1.2, ms=9)
    ax.text(12.3, BEAM_Y - 0.45, "$L(x_s, -\\omega)$", ha="center", va="top", fontsize=9)
    ax.text(1.5, BEAM_Y - 0.5, "$L(x, \\omega)$", ha="center", va="top", fontsize=9)

    # The eye and the view direction.
    ax.add_patch(Ellipse((0.85, BEAM_Y), 0.9, 0.5, fc="white", ec="black", lw=1.2, zorder=4))
    ax.add_patch(Circle((1.0, BEAM_Y), 0.15, fc="black", zorder=5))
    ax.text(0.85, BEAM_Y + 0.45, "eye $x$", ha="center", va="bottom", fontsize=9)
    _arrow(ax, (0.7, 1.25), (2.0, 1.25), "black", lw=1.0, ms=9)
    ax.text(1.35, 1.05, "view direction $\\omega$", ha="center", va="top", fontsize=8)

    labels = {
        "absorption": "absorption\n$-\\sigma_a L$ (2.1)",
        "out-scattering": "out-scattering\n$-\\sigma_s L$ (2.2)",
        "in-scattering": "in-scattering\n$+\\sigma_s L_i$ (2.9)",
        "emission": "emission\n$+\\sigma_a L_e$ (2.9)",
    }
    for name, x, _ in EVENTS:
        ax.text(x, 0.15, labels[name], ha="center", va="bottom", fontsize=9, fontweight="bold")
        ax.plot([x, x], [0.82, BEAM_Y - 0.3], color="0.55", lw=0.6, ls=":", zorder=2)
        if name == "absorption":
            ax.add_patch(Circle((x, BEAM_Y), 0.16, fc="#333333", zorder=7))
            t = np.linspace(0.0, 1.0, 60)
            for dx in (-0.25, 0.0, 0.25):  # wavy lines: the absorbed energy leaves as heat
                ax.plot(x + dx + 0.07 * np.sin(t * 6 * np.pi), BEAM_Y + 0.35 + 0.9 * t, color="#c0392b", lw=1.0,
                        zorder=6)
            ax.text(x, BEAM_Y + 1.35, "heat", ha="center", va="bottom", fontsize=8, color="#c0392b")
        elif name == "out-scattering":
            ax.add_patch(Circle((x, BEAM_Y), 0.14, fc="#5d7fa3", zorder=7))
            for ang in (50.0, 115.0, 160.0 + 90.0, 300.0):
                d = np.array([np.cos(np.radians(ang)), np.sin(np.radians(ang))])
                _arrow(ax, (x + 0.2 * d[0], BEAM_Y + 0.2 * d[1]), (x + 1.0 * d[0], BEAM_Y + 1.0 * d[1]),
                       "#d08a00", lw=1.3)
        elif name == "in-scattering":
            ax.add_patch(Circle((x, BEAM_Y), 0.14, fc="#5d7fa3", zorder=7))
            sun = np.array([x + 1.3, 4.55])
            ax.add_patch(Circle(tuple(sun), 0.28, fc="#ffcf33", ec="#d08a00", zorder=7))
            ax.text(sun[0] + 0.4, sun[1], "sun", ha="left", va="center", fontsize=8)
            d = np.array([x, BEAM_Y]) - sun
            d /= np.linalg.norm(d)
            for off in (-0.22, 0.0, 0.22):  # parallel rays from the sun converge on the particle's neighbourhood
                o = np.array([-d[1], d[0]]) * off
                _arrow(ax, tuple(sun + 0.4 * d + o), tuple(np.array([x, BEAM_Y]) - 0.25 * d + o * 0.3),
                       "#d08a00", lw=1.1, ms=8)
            ax.text(x - 0.3, 3.5, "$L_i$", ha="right", va="center", fontsize=9)
        else:  # emission
            ax.add_patch(Circle((x, BEAM_Y), 0.32, fc="#ffb347", alpha=0.45, lw=0, zorder=6))
            ax.add_patch(Circle((x, BEAM_Y), 0.15, fc="#e8590c", zorder=7))
            for ang in range(20, 360, 45):
                d = np.array([np.cos(np.radians(ang)), np.sin(np.radians(ang))])
                _arrow(ax, (x + 0.35 * d[0], BEAM_Y + 0.35 * d[1]), (x + 0.85 * d[0], BEAM_Y + 0.85 * d[1]),
                       "#e8590c", lw=1.0, ms=7)
            ax.text(x, BEAM_Y + 1.0, "$L_e$", ha="center", va="bottom", fontsize=9)
    ax.set_title("A ray through a participating medium: the beam width is the radiance carried towards the eye",
                 fontsize=11)


def _companion(ax, quick):
    # %% [markdown]
    # The companion plot answers "what do these terms do to a whole ray?". Take a medium of constant coefficients and
    # depth s and evaluate the volume rendering equation (2.17) for growing s, switching the terms on one at a time:
    #
    # * without a medium the background arrives unchanged;
    # * absorption alone dims it as exp(-sigma_a s); adding out-scattering dims it faster, exp(-sigma_t s)
    #   (Beer–Lambert, 2.6);
    # * in-scattering adds light that converges to sigma_s L_i / sigma_t for a deep medium: far enough in, the
    #   background is forgotten and the medium shows only its own scattered light — this is why a thick cloud has its
    #   own brightness whatever lies behind it;
    # * emission raises that limit by sigma_a L_e / sigma_t.
    #
    # Thin black dashes are the closed form of the constant medium,
    # L = L_bg exp(-sigma_t s) + (sigma_a L_e + sigma_s L_i)(1 - exp(-sigma_t s)) / sigma_t. The library sums the
    # integral with n steps (a left Riemann sum), which overestimates the gain terms by about sigma_t dt / 2 relative
    # (0.25 % for the deepest ray here, 1024 steps of 1 cm); the gap is below the line width. The circles are the
    # raymarching sum 2.18 (no emission term) for the in-scattering case; it coincides with 2.17.

    # %%
    n = 128 if quick else 1024  # samples per ray
    n_s = 41 if quick else 201  # ray depths
    s = np.linspace(0.0, S_MAX, n_s, dtype=np.float32)
    dt = s / n

    def full(v):
        return np.full((n_s, n), v, dtype=np.float32)

    cases = (  # label, sigma_a, sigma_s, L_e, L_i, colour
        ("no medium", 0.0, 0.0, 0.0, 0.0, "0.65"),
        ("absorption only", SIGMA_A, 0.0, 0.0, 0.0, "#333333"),
        ("+ out-scattering (extinction)", SIGMA_A, SIGMA_S, 0.0, 0.0, "#5d7fa3"),
        ("+ in-scattering", SIGMA_A, SIGMA_S, 0.0, L_I, "#d08a00"),
        ("+ emission (all four terms)", SIGMA_A, SIGMA_S, L_E, L_I, "#e8590c"),
    )
    s64 = s.astype(np.float64)
    for label, sa, ss, le, li, colour in cases:
        L = pywarp.media_volume_render(full(sa), full(ss), full(le), full(li), dt, L_BG)
        ax.plot(s, L, color=colour, lw=2.2, label=f"{label}: 2.17")
        st = sa + ss
        if st > 0.0:  # closed form of the constant medium, float64
            closed = L_BG * np.exp(-st * s64) + (sa * le + ss * li) * (1.0 - np.exp(-st * s64)) / st
        else:
            closed = np.full_like(s64, L_BG)
        ax.plot(s64, closed, color="black", lw=0.8, ls=(0, (4, 3)))
    every = max(1, n_s // 20)
    L18 = pywarp.media_raymarch(full(SIGMA_A + SIGMA_S), full(SIGMA_S), full(L_I), dt, L_BG)
    ax.plot(s[::every], L18[::every], "o", ms=5, mfc="none", mec="black", label="+ in-scattering: raymarch 2.18")
    ax.plot([], [], color="black", lw=0.8, ls=(0, (4, 3)), label="closed form (float64)")
    for limit, text in ((SIGMA_S * L_I / (SIGMA_A + SIGMA_S), "$\\sigma_s L_i / \\sigma_t$"),
                        ((SIGMA_A * L_E + SIGMA_S * L_I) / (SIGMA_A + SIGMA_S),
                         "$(\\sigma_a L_e + \\sigma_s L_i) / \\sigma_t$")):
        ax.axhline(limit, color="0.6", lw=0.6, ls=":")
        ax.text(S_MAX - 0.1, limit - 0.015, text, ha="right", va="top", fontsize=9, color="0.35")
    ax.set_xlim(0.0, S_MAX)
    ax.set_ylim(0.0, 1.08)
    ax.set_xlabel("depth s of the medium along the ray [m]")
    ax.set_ylabel("radiance at the eye $L(x, \\omega)$ / $L_{bg}$")
    ax.set_title(f"Constant medium: $\\sigma_a$ = {SIGMA_A}, $\\sigma_s$ = {SIGMA_S} m$^{{-1}}$, "
                 f"$L_i$ = {L_I}, $L_e$ = {L_E} (pywarp.media_volume_render, {n} steps per ray)", fontsize=10)
    ax.legend(loc="center right", bbox_to_anchor=(1.0, 0.6), fontsize=8.5, framealpha=0.9)
    ax.grid(alpha=0.25)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(21)  # particle positions of the schematic
    fig, (ax0, ax1) = plt.subplots(2, 1, figsize=(13, 10.5), dpi=80 if quick else 130,
                                   gridspec_kw={"height_ratios": [1.25, 1.0]})
    _schematic(ax0, rng)
    _companion(ax1, quick)
    fig.subplots_adjust(left=0.07, right=0.97, top=0.96, bottom=0.06, hspace=0.12)
    ax0.set_position((0.02, 0.47, 0.96, 0.5))  # the schematic uses the full width
    out = out_dir / "fig-2.1.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
