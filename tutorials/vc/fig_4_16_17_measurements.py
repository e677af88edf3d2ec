"""Figures vc-fig-4.16 and vc-fig-4.17: the thesis's measurements, re-measured on the machine that runs this script.

vc-fig-4.16 compares the cost of the sky models (vc-A28 gradient, vc-A29 Preetham) with reprojection off and on;
vc-fig-4.17 is the raymarching-optimisation ladder (vc-M4..M9): no optimisation, + adaptive sample count (vc-A18),
+ early termination (vc-A21), + temporal reprojection (vc-A26), each step including the previous ones, on the same
frame and camera. The thesis measured 1920x1080 on a GeForce GTX 860M (≈ 220 ms unoptimised, −20 %, −70 %, −97 %);
here the frame is 960x540 on the CPU (both cores, Warp tile-parallel), and the thesis's percentages stand beside ours.
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

from pywarp.clouds.bench import machine, measure_ladder, measure_sky  # noqa: E402

DETERMINISTIC = False

# The thesis' numbers (spec §5, vc-M4..M9): time saved relative to the unoptimised cloud pass.
THESIS_CUT = {"unoptimised": 0.0, "adaptive_samples": 20.0, "early_exit": 70.0, "reprojection": 97.0}
LABELS = {"unoptimised": "no optimisation", "adaptive_samples": "+ 64..128 samples\nby ray elevation",
          "early_exit": "+ early\ntermination", "reprojection": "+ reprojection"}


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    width, height, repeat = (160, 90, 1) if quick else (960, 540, 2)
    small = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64) if quick else {}
    tech, ladder = measure_ladder(width, height, repeat, **small)
    dense_cut = ladder.pop("dense_clouds_cut_percent")
    sky = measure_sky(tech, repeat)
    m = machine()
    where = f"{width}x{height}, {m['cores']} cores, {m['cpu']}"

    # %% [markdown]
    # Fig 4.17. Left: milliseconds per frame. Right: the time saved by each step relative to no optimisation,
    # ours next to the thesis's. The adaptive sample count saves what the horizon-to-zenith mix of the view allows;
    # early termination saves more when the clouds are dense (the thesis notes up to 85 % with denser clouds);
    # reprojection raymarches 1/16 of the pixels and adds a full-frame reprojection pass.
    # %%
    keys = list(ladder)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.6), dpi=100 if quick else 130)
    bars = a1.bar(range(len(keys)), [ladder[k] for k in keys], color=["#777", "#4a7ab5", "#2f9a6a", "#d08a2a"])
    for b, k in zip(bars, keys):
        a1.annotate(f"{ladder[k]:.0f} ms", (b.get_x() + b.get_width() / 2, b.get_height()), ha="center",
                    va="bottom", fontsize=9)
    a1.set_xticks(range(len(keys)), [LABELS[k] for k in keys], fontsize=8)
    a1.set_ylabel("ms per frame")
    a1.set_title(f"measured here ({where})", fontsize=9)
    ours = [100.0 * (1.0 - ladder[k] / ladder["unoptimised"]) for k in keys]
    x = range(len(keys))
    a2.bar([i - 0.2 for i in x], ours, width=0.4, label="measured here", color="#4a7ab5")
    a2.bar([i + 0.2 for i in x], [THESIS_CUT[k] for k in keys], width=0.4, label="thesis (GTX 860M, 1920x1080)",
           color="#bbb")
    for i, v in enumerate(ours):
        a2.annotate(f"{v:.0f} %", (i - 0.2, max(v, 0)), ha="center", va="bottom", fontsize=8)
    # vc-M7: the same frame with clouds twice as dense (twice the extinction): early termination saves more
    a2.bar([len(keys) - 0.2], [dense_cut], width=0.4, color="#2f9a6a")
    a2.bar([len(keys) + 0.2], [85.0], width=0.4, color="#bbb")
    a2.annotate(f"{dense_cut:.0f} %", (len(keys) - 0.2, max(dense_cut, 0)), ha="center", va="bottom", fontsize=8)
    a2.set_xticks(list(x) + [len(keys)], [LABELS[k] for k in keys] + ["early termination,\ndenser clouds (M7)"],
                  fontsize=8)
    a2.set_ylabel("time saved vs. no optimisation [%]")
    a2.set_ylim(0, 105)
    a2.legend(fontsize=8, loc="upper left")
    a2.set_title("cumulative saving, each step includes the previous ones", fontsize=9)
    fig.suptitle("Fig 4.17 — raymarching optimisations (vc-A18, vc-A21, vc-A26)")
    fig.tight_layout()
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
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="figures/vc")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    print(*main(args.out, quick=args.quick), sep="\n")
