"""Figure oc-fig-2.1.1-u (unnumbered, §2.1.1): the nine stages of a cumulus's life, drawn as a schematic from the
text's list -- a diagram, no equation.

The text lists the stages (warm air at the ground; a bubble detaches and rises; an updraft, which breaks off if the
warm-air supply is small; a haze at the condensation level; irregular droplets growing and merging; sharp edges, the
highest and whitest where the updraft is strongest, the darkest base; growth while the supply lasts, then decay;
outlines dissolving, the cloud breaking apart; dissolving from the top in descending air). Each panel draws one stage
with matplotlib primitives: the ground, the condensation level (dashed), warm air (orange), the updraft or the
descending air (arrows), and the cloud as overlapping grey-and-white ellipses (a darker base from stage 6). The
shapes are hand-placed; nothing is simulated. Output: figures/oc/fig-2.1.1-u.png.
"""
# %% [markdown]
# A cumulus forms only by thermal convection (§2.1.1): the sun heats moist air at the ground, a bubble of it
# detaches and rises, cools as it expands, and where it reaches the dew point -- the condensation level -- its vapour
# condenses into the droplets that make the cloud. The cloud lives as long as the warm air keeps coming, then
# decays. The nine panels follow the text's list.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Ellipse, FancyArrow  # noqa: E402

BASE = 0.55  # the condensation level (axes units: ground 0, top 1)

STAGES = (
    "1. warm air accumulates\nat the ground",
    "2. the warm air detaches\nand rises",
    "3. an updraft forms (with a small\nsupply it breaks off: no cloud)",
    "4. at the condensation level\na fine haze forms",
    "5. irregular droplets form,\ngrow and merge",
    "6. sharp edges; highest, whitest over the\nstrongest updraft; the base darkest",
    "7. the cloud grows while the warm\nair lasts, then starts to decay",
    "8. the outlines dissolve, the\ncloud breaks apart",
    "9. in descending air the cloud\ndissolves from the top",
)

# the cloud of each stage: (x, y, width, height, grey) ellipses; y is the centre height
PUFFS = {
    4: [(0.5, BASE + 0.03, 0.22, 0.05, 0.93)],
    5: [(0.42, BASE + 0.05, 0.10, 0.08, 0.95), (0.55, BASE + 0.07, 0.12, 0.10, 0.95),
        (0.64, BASE + 0.04, 0.07, 0.06, 0.95)],
    6: [(0.5, BASE + 0.06, 0.34, 0.12, 0.62), (0.42, BASE + 0.14, 0.20, 0.16, 0.97),
        (0.56, BASE + 0.2, 0.22, 0.22, 1.0), (0.5, BASE + 0.3, 0.16, 0.16, 1.0)],
    7: [(0.5, BASE + 0.07, 0.44, 0.14, 0.55), (0.38, BASE + 0.16, 0.24, 0.2, 0.95),
        (0.6, BASE + 0.2, 0.28, 0.26, 1.0), (0.5, BASE + 0.33, 0.22, 0.2, 1.0), (0.52, BASE + 0.41, 0.14, 0.1, 0.98)],
    8: [(0.33, BASE + 0.08, 0.16, 0.1, 0.8), (0.52, BASE + 0.14, 0.18, 0.14, 0.88),
        (0.68, BASE + 0.1, 0.12, 0.1, 0.85), (0.47, BASE + 0.27, 0.12, 0.1, 0.9)],
    9: [(0.42, BASE + 0.06, 0.14, 0.06, 0.85), (0.58, BASE + 0.07, 0.12, 0.05, 0.85)],
}


def draw_stage(ax, k: int) -> None:
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_facecolor((0.72, 0.84, 0.96))
    ax.add_patch(plt.Rectangle((0, 0), 1, 0.08, color=(0.45, 0.55, 0.3)))
    ax.axhline(BASE, color=(0.3, 0.3, 0.5), ls="--", lw=0.8)
    warm = (0.95, 0.55, 0.2)
    if k == 1:
        ax.add_patch(Ellipse((0.5, 0.11), 0.5, 0.07, color=warm, alpha=0.7))
    if k == 2:
        ax.add_patch(Ellipse((0.5, 0.1), 0.35, 0.04, color=warm, alpha=0.5))
        ax.add_patch(Ellipse((0.5, 0.25), 0.16, 0.12, color=warm, alpha=0.75))
    if 3 <= k <= 7:
        strength = {3: 0.35, 4: 0.42, 5: 0.45, 6: 0.5, 7: 0.5}[k]
        for x, s in ((0.5, 1.0), (0.42, 0.7), (0.58, 0.7)):
            ax.add_patch(FancyArrow(x, 0.1, 0, strength * s, width=0.012, head_width=0.04, head_length=0.04,
                                    color=warm, alpha=0.85))
        ax.add_patch(Ellipse((0.5, 0.1), 0.3 if k < 7 else 0.18, 0.035, color=warm, alpha=0.6))
    if k == 3:
        ax.text(0.5, 0.52, "x", color="red", ha="center", fontsize=9)
        ax.text(0.5, 0.6, "weak supply: breaks off", ha="center", fontsize=6, color=(0.5, 0.1, 0.1))
    if k == 9:
        for x in (0.35, 0.5, 0.65):
            ax.add_patch(FancyArrow(x, 0.85, 0, -0.22, width=0.01, head_width=0.035, head_length=0.035,
                                    color=(0.3, 0.4, 0.7), alpha=0.8))
    for x, y, w, h, g in PUFFS.get(k, []):
        ax.add_patch(Ellipse((x, y), w, h, color=(g, g, g), alpha=0.55 if k in (4, 8, 9) else 0.95))
    if k == 6:
        ax.text(0.86, BASE - 0.05, "dark\nbase", fontsize=6, ha="center", va="top")
    ax.text(0.02, BASE + 0.015, "condensation level", fontsize=5.5, color=(0.3, 0.3, 0.5))
    ax.set_title(STAGES[k - 1], fontsize=7.5)
    ax.set_xticks([])
    ax.set_yticks([])


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(3, 3, figsize=(9.6, 8.4), dpi=60 if quick else 100)
    for k, ax in enumerate(axes.ravel(), start=1):
        draw_stage(ax, k)
    fig.suptitle("oc fig. 2.1.1 (unnumbered): stages of a cumulus, a schematic of the text's list", fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    out = out_dir / "fig-2.1.1-u.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/oc")
