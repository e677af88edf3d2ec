"""Figures vc-fig-4.16 and vc-fig-4.17: the thesis's measurements, re-measured on the machine that runs this script.

vc-fig-4.16 compares the cost of the sky models (vc-A28 gradient, vc-A29 Preetham) with reprojection off and on;
vc-fig-4.17 is the raymarching-optimisation ladder (vc-M4..M9): no optimisation, + adaptive sample count (vc-A18),
+ early termination (vc-A21), + temporal reprojection (vc-A26), each step including the previous ones, on the same
frame and camera. The thesis measured 1920x1080 on a GeForce GTX 860M (≈ 220 ms unoptimised, −20 %, −70 %, −97 %);
here the frame is 960x540 on the CPU (both cores, Warp tile-parallel), and the thesis's percentages stand beside ours.
As in the thesis, the reprojection bar is split into the raymarch (sky and clouds for one pixel of each 4x4 block)
and the reprojection pass; every step is measured REPEAT times (3), interleaved, and each repetition is drawn.
Outputs: figures/vc/fig-4.16.png, figures/vc/fig-4.17.png. The numbers are timings, so they differ from run to run
and from machine to machine (DETERMINISTIC = False: the figure-regression test does not compare these images).
"""
# %% [markdown]
# A performance chart is only meaningful for the machine it was measured on, so this tutorial measures instead of
# copying numbers. `pywarp.clouds.bench.measure_ladder` renders the same frame four times, switching the optimisations on
# one after the other; `pywarp.clouds.bench.measure_sky` times the sky stage alone. `pywarp bench cloudscape` prints the
# same numbers (and more) on the command line.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from pywarp.clouds.bench import machine, measure_ladder, measure_sky  # noqa: E402

DETERMINISTIC = False

# The thesis' numbers (spec §5, vc-M4..M9): time saved relative to the unoptimised cloud pass.
THESIS_CUT = {"unoptimised": 0.0, "adaptive_samples": 20.0, "early_exit": 70.0, "reprojection": 97.0}
LABELS = {"unoptimised": "no\noptimisation", "adaptive_samples": "+ 64..128 samples\nby ray elevation",
          "early_exit": "+ early\ntermination", "reprojection": "+ reprojection"}


#: Repetitions of every measurement (interleaved rounds); each one is drawn, the bars are their medians
REPEAT = 3
SPLIT_COLOURS = {"raymarch": "#d08a2a", "reprojection": "#8e5a9e", "other": "#c9c9c9"}
SPLIT_LABELS = {"raymarch": "raymarch (sky + clouds,\n1 pixel per 4x4 block)", "reprojection": "reprojection pass",
                "other": "sRGB encode, copies"}


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    width, height = (160, 90) if quick else (960, 540)
    small = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64) if quick else {}
    detail = {}
    tech, ladder = measure_ladder(width, height, REPEAT, detail=detail, **small)
    samples, split, dense = detail["samples"], detail["reprojection_split"], detail["dense_samples"]
    sky = measure_sky(tech, REPEAT)
    m = machine()
    where = f"{width}x{height}, {m['cores']} cores, {m['cpu']}"

    # %% [markdown]
    # Fig 4.17. Left: milliseconds per frame, the median of the repetitions (bars) and every repetition (dots).
    # The reprojection bar is stacked like the thesis's: the raymarch of one pixel per 4x4 block (the sky and the
    # cloud kernels), the full-frame reprojection pass, and the rest of the frame (sRGB encoding, the copy to the
    # host), each the median over the repetitions of its mean over a steady camera path. Right: the time saved by
    # each step relative to no optimisation, ours (whiskers: the spread over the repetitions) next to the
    # thesis's. The adaptive sample count saves what the horizon-to-zenith mix of the view allows; early
    # termination saves more when the clouds are dense (the thesis notes up to 85 % with denser clouds);
    # reprojection raymarches 1/16 of the pixels and adds a full-frame reprojection pass.
    # %%
    keys = list(samples)
    med = {k: float(np.median(v)) for k, v in samples.items()}
    fig = plt.figure(figsize=(14.5, 5.2), dpi=100 if quick else 130)
    grid = fig.add_gridspec(1, 3, width_ratios=(4.0, 1.25, 4.6), wspace=0.32)
    a1, a3, a2 = fig.add_subplot(grid[0]), fig.add_subplot(grid[1]), fig.add_subplot(grid[2])
    colours = {"unoptimised": "#777", "adaptive_samples": "#4a7ab5", "early_exit": "#2f9a6a"}

    def stacked(ax, i, width):
        bottom = 0.0
        for g, vals in split.items():
            h = float(np.median(vals))
            ax.bar(i, h, bottom=bottom, color=SPLIT_COLOURS[g], label=SPLIT_LABELS[g], width=width,
                   edgecolor="white", lw=0.6)
            bottom += h
        return bottom

    def dots(ax, x, values, label=None):
        ax.plot([x] * len(values), values, "o", ms=4, mfc="white", mec="black", mew=0.8, zorder=5, label=label)

    for i, k in enumerate(keys):
        if k == "reprojection":
            stacked(a1, i, 0.7)
        else:
            a1.bar(i, med[k], color=colours[k], width=0.7)
        dots(a1, i + 0.22, samples[k])
        a1.annotate(f"{med[k]:.0f} ms" if med[k] >= 10 else f"{med[k]:.1f} ms", (i, max(samples[k])),
                    xytext=(0, 4), textcoords="offset points", ha="center", va="bottom", fontsize=9)
    a1.set_xticks(range(len(keys)), [LABELS[k] for k in keys], fontsize=8)
    a1.set_ylabel("ms per frame")
    a1.set_ylim(0, 1.12 * max(max(v) for v in samples.values()))
    a1.set_title(f"measured here ({where})\nbars: median of {REPEAT} repetitions, dots: each", fontsize=9)

    # The reprojection bar enlarged: its parts (medians) and each repetition of the whole frame and of its parts.
    top = stacked(a3, 0, 0.55)
    dots(a3, -0.38, samples["reprojection"], "each repetition")
    bottom = 0.0
    for g, vals in split.items():
        h = float(np.median(vals))
        dots(a3, 0.0, np.asarray(vals) + bottom)  # each repetition of this part, on top of the parts below
        a3.annotate(f"{h:.1f}", (0.3, bottom + h / 2), ha="left", va="center", fontsize=8)
        bottom += h
    a3.set_xlim(-0.6, 0.9)
    a3.set_ylim(0, 1.45 * max(max(samples["reprojection"]), top))
    a3.set_xticks([0], ["+ reprojection\n(enlarged)"], fontsize=8)
    a3.set_ylabel("ms per frame")
    a3.legend(fontsize=7, loc="upper center", framealpha=0.95)
    a3.set_title("split as in the thesis", fontsize=9)

    def saved(v, ref):
        return 100.0 * (1.0 - v / ref)

    ref = med["unoptimised"]
    ours = [saved(med[k], ref) for k in keys]
    spread = [[saved(max(samples[k]), ref) for k in keys], [saved(min(samples[k]), ref) for k in keys]]
    x = np.arange(len(keys))
    a2.bar(x - 0.2, ours, width=0.4, label=f"measured here (median, whiskers: min-max of {REPEAT})",
           color="#4a7ab5", yerr=[np.subtract(ours, spread[0]), np.subtract(spread[1], ours)], capsize=3,
           error_kw={"lw": 1.0})
    a2.bar(x + 0.2, [THESIS_CUT[k] for k in keys], width=0.4, label="thesis (GTX 860M, 1920x1080)", color="#bbb")
    for i, v in enumerate(ours):
        a2.annotate(f"{v:.0f} %", (i - 0.2, max(spread[1][i], 0)), xytext=(0, 3), textcoords="offset points",
                    ha="center", va="bottom", fontsize=8)
    # vc-M7: the same frame with clouds twice as dense (twice the extinction): early termination saves more
    d_ref = float(np.median(dense["unoptimised"]))
    d_cuts = [saved(v, d_ref) for v in dense["early_exit"]]
    d_cut = saved(float(np.median(dense["early_exit"])), d_ref)
    n = len(keys)
    a2.bar([n - 0.2], [d_cut], width=0.4, color="#2f9a6a", yerr=[[d_cut - min(d_cuts)], [max(d_cuts) - d_cut]],
           capsize=3, error_kw={"lw": 1.0})
    a2.bar([n + 0.2], [85.0], width=0.4, color="#bbb")
    a2.annotate(f"{d_cut:.0f} %", (n - 0.2, max(max(d_cuts), 0)), xytext=(0, 3), textcoords="offset points",
                ha="center", va="bottom", fontsize=8)
    a2.set_xticks(list(x) + [n], [LABELS[k] for k in keys] + ["early termination,\ndenser clouds (M7)"],
                  fontsize=8)
    a2.set_ylabel("time saved vs. no optimisation [%]")
    lowest = min(min(spread[0]), min(d_cuts), 0.0)
    a2.set_ylim(min(0.0, lowest - 4.0), 122)
    a2.set_yticks(range(0 if lowest >= 0 else -20, 101, 20))
    a2.axhline(0.0, color="0.3", lw=0.8)
    a2.legend(fontsize=8, loc="upper left")
    a2.set_title("cumulative saving, each step includes the previous ones", fontsize=9)
    fig.suptitle("Fig 4.17 — raymarching optimisations (vc-A18, vc-A21, vc-A26)")
    fig.subplots_adjust(left=0.05, right=0.99, top=0.84, bottom=0.14)
    out17 = out_dir / "fig-4.17.png"
    fig.savefig(out17)
    plt.close(fig)

    # %% [markdown]
    # Fig 4.16. The sky stage alone. The Preetham sky evaluates three Perez functions, a colour conversion and a
    # tone map per pixel; the gradient sky one interpolation and a power. With reprojection only one pixel of each
    # 4x4 block is computed per frame. The thesis gives this chart without numbers.
    # %%
    fig, ax = plt.subplots(figsize=(7, 4.2), dpi=100 if quick else 130)
    kinds = list(sky)
    for j, (mode, colour) in enumerate((("full", "#4a7ab5"), ("reprojection", "#d08a2a"))):
        vals = [sky[k][mode] for k in kinds]
        bs = ax.bar([i + (j - 0.5) * 0.38 for i in range(len(kinds))], vals, width=0.38, color=colour,
                    label="every pixel" if mode == "full" else "reprojection (1/16 of the pixels)")
        for b, v in zip(bs, vals):
            ax.annotate(f"{v:.1f} ms", (b.get_x() + b.get_width() / 2, v), ha="center", va="bottom", fontsize=8)
    ax.set_xticks(range(len(kinds)), ["gradient (vc-A28)", "Preetham (vc-A29)"])
    ax.set_ylabel("ms per frame, sky stage only")
    ax.legend(fontsize=8)
    ax.set_title(f"Fig 4.16 — sky models ({where})", fontsize=9)
    fig.tight_layout()
    out16 = out_dir / "fig-4.16.png"
    fig.savefig(out16)
    plt.close(fig)
    return [out16, out17]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
