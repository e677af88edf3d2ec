"""Extra figure vc-extra-reference: the real-time lighting models against a path-traced ground truth.

Not a figure of the thesis: it measures the renderer's lighting (the energy of vc-2.31 with the sun and ambient of
vc-A20, composited by vc-4.8 over the Preetham sky vc-A29) against a Monte Carlo path tracer of the same density
field (vc-A17 with detail), sun, sky and ground (pywarp.clouds.reference: delta tracking, multiple scattering,
next-event estimation towards the sun). Three scenes -- noon, a low sun, from above -- each as the reference and as
the real-time models "thesis" (constant sun and ambient), "+sky light" (sun and ambient from the sky model) and
"+multiple scattering" (the octaves; the silver-lining lobe is off by default, as tools/tune_lighting.py measured
it to raise the error); under each model its SSIM and mean CIEDE2000 against
the reference after the best single exposure scale (pywarp.clouds.bench_reference, the same numbers as
`pywarp bench clouds reference`). Output: figures/vc/extra-reference.png.
"""
# %% [markdown]
# A real-time cloud renderer approximates light transport: one march towards the viewer, a few light samples
# towards the sun, Beer's law and a "powder" term, an ambient constant. A path tracer solves the transport itself --
# every scattering event, the light bouncing between clouds, ground and sky -- at a thousand times the cost. Rendered
# from the same clouds, sun and sky, it is the picture the approximations aim for, and the distance to it is a number
# instead of "looks right".
#
# The reference images are exposed for display (the 99.5th percentile of their brightest channel is white: sunlit
# clouds are several times brighter than the blue sky). Each model's image is scaled by the single factor that fits
# it best to the reference (least squares on linear RGB) -- so the numbers measure the distribution of light, not its
# overall level -- then both are sRGB-encoded and compared: SSIM (1 = identical structure) and the mean CIEDE2000
# colour difference (about 1 = just noticeable, above ~5 clearly different colours). The noise floor is the same
# comparison between two independent halves of the reference's paths.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from pywarp.clouds.bench_reference import MAIN_MODELS, MODELS, SCENES, compare  # noqa: E402

# 64 paths per pixel: the figure's reference noise is printed on it (its standard error); `pywarp bench clouds
# reference` uses 1024 for the table of the note. 256 made this tutorial the slowest of the test suite (> 10 min).
FULL = dict(width=160, height=90, spp=64)
QUICK = dict(width=48, height=27, spp=8)
QUICK_TEXTURES = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    size = QUICK if quick else FULL

    # %% [markdown]
    # `compare` renders the reference of each scene (two halves of independent seeds) and each real-time model (a
    # still of 16 jittered frames, so that the renderer's own ray-jitter noise does not count as lighting error),
    # and returns the table and the display images.

    # %%
    result, images = compare(**size, settings=QUICK_TEXTURES if quick else None, progress=lambda msg: None)

    # %%
    columns = ["reference", *MAIN_MODELS]
    rows = list(SCENES)
    fig = plt.figure(figsize=(16.0, 9.4), dpi=60 if quick else 100)
    gs = fig.add_gridspec(len(rows), len(columns), left=0.06, right=0.99, top=0.9, bottom=0.2, wspace=0.04,
                          hspace=0.32)
    for r, scene in enumerate(rows):
        sc = next(s for s in result["scenes"] if s["scene"] == scene)
        models = {m["model"]: m for m in sc["models"]}
        for c, col in enumerate(columns):
            ax = fig.add_subplot(gs[r, c])
            ax.set_xticks([])
            ax.set_yticks([])
            if col in images[scene]:
                ax.imshow(images[scene][col], interpolation="nearest")
            if col == "reference":
                ax.set_title(f"path-traced reference, {result['spp']} spp\nstd. error {sc['std_error']:.3f} of "
                             f"white", fontsize=10)
                ax.set_ylabel(scene, fontsize=12)
            elif "skipped" in models[col]:
                ax.set_title(f"{col}\nskipped", fontsize=10)
            else:
                m = models[col]
                ax.set_title(f"{col}\nSSIM {m['ssim']:.3f}, ΔE2000 {m['delta_e']:.1f}", fontsize=10)

    # %% [markdown]
    # The table repeats the numbers with the noise floor of each scene: a model whose error is close to the floor is
    # as close to the reference as the reference's own noise allows at this sample count. The reference's air does
    # not scatter -- it has no aerial perspective -- so the column "+ms, haze off" (the last model without the haze)
    # shows how much of that model's error is the haze rather than the light on the clouds.

    # %%
    ax = fig.add_axes((0.02, 0.01, 0.97, 0.16))
    ax.axis("off")
    cells = []
    for sc in result["scenes"]:
        nf = sc["noise_floor"]
        row = [sc["scene"]]
        models = {m["model"]: m for m in sc["models"]}
        for name in MODELS:  # (the rows after them, e.g. the renderer's defaults, are the benchmark's)
            m = models[name]
            row.append("skipped" if "skipped" in m else f"{m['ssim']:.3f} / {m['delta_e']:.2f}")
        row.append(f"{nf['ssim']:.3f} / {nf['delta_e']:.2f}")
        cells.append(row)
    table = ax.table(cellText=cells, colLabels=["scene", *(f"{m}: SSIM / ΔE" for m in MODELS),
                                                "noise floor (half vs half)"], loc="center", cellLoc="center")
    table.auto_set_font_size(False)
    table.set_fontsize(9)
    table.scale(1.0, 1.5)
    w, h = result["size"]
    fig.suptitle(f"Real-time lighting models vs a path-traced ground truth of the same clouds, sun and sky ({w}x{h}; "
                 "each model at its best exposure scale)", fontsize=13)
    out = out_dir / "extra-reference.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
