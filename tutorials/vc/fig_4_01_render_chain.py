"""Figure vc-fig-4.1: the rendering chain of the library, redrawn as a flow diagram (vc-A30).

A diagram, not a computation: sky model -> cloud raymarch -> optional reprojection, with the reprojection flag acting on
every stage (it selects the pixel index of vc-4.1 and launches 1/16 of the threads), and the inputs of the technique —
the noise textures from the generator, the camera and the settings. It is drawn from this implementation (the module
docstring of pywarp/clouds/technique.py and CloudscapeTechnique.render there) with the names of the pywarp pipeline: sky
models GradientSky (vc-A28) and PreethamSky (vc-A29), textures from BasicTextureGenerator (vc-A9, vc-A10, vc-A11,
vc-A12), the technique CloudscapeTechnique with init / update / render, the camera as Pose, the cloud density
and light of vc-A17 and vc-A20 composited by vc-4.8, and the temporal reprojection of vc-A26 and vc-A27.
Output: figures/vc/fig-4.1.png.
"""
# %% [markdown]
# One frame of the cloudscape is made in stages, each a full-screen pass that must finish before the next starts
# (the thesis puts memory barriers between its compute shaders):
#
# 1. the **sky model** paints the background: a cheap gradient or the analytic Preetham sky;
# 2. the **cloud raymarch** walks a ray per pixel through the cloud layer, accumulating density and light, and
#    composites the clouds over the sky (4.8);
# 3. optionally, **reprojection** fills in the pixels that were not raymarched this frame from the previous frame.
#
# The reprojection switch is not just the last stage: when it is on, *every* stage computes only one pixel of each
# 4x4 block per frame (formula 4.1 chooses which), so sky and clouds launch 1/16 of the threads, and the reprojection
# stage completes the other 15/16 from the previous frame, seen through the previous camera. The textures are made
# once by the generator when the technique is initialised; the camera changes every frame.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch  # noqa: E402

INPUT = {"fc": "#eef3f8", "ec": "#5d7fa3"}
STAGE = {"fc": "#fff4d6", "ec": "#b7860b"}
METHOD = {"fc": "#f4f4f4", "ec": "0.45"}
FLAG = {"fc": "#fde2e0", "ec": "#c0392b"}
FLAG_COLOUR = "#c0392b"


def _box(ax, x, y, w, h, title, body="", style=STAGE, title_size=10.5, body_size=8.5, lw=1.2):
    ax.add_patch(FancyBboxPatch((x, y), w, h, boxstyle="round,pad=0.02,rounding_size=0.15", lw=lw, zorder=2,
                                **style))
    if body:
        ax.text(x + w / 2, y + h - 0.14, title, ha="center", va="top", fontsize=title_size, fontweight="bold",
                zorder=3)
        ax.text(x + w / 2, y + h - 0.52, body, ha="center", va="top", fontsize=body_size, zorder=3, linespacing=1.35)
    else:
        ax.text(x + w / 2, y + h / 2, title, ha="center", va="center", fontsize=title_size, fontweight="bold",
                zorder=3)


def _arrow(ax, a, b, color="0.2", ls="-", lw=1.4, text=None, text_xy=None, rad=0.0, size=8.0):
    ax.add_patch(FancyArrowPatch(a, b, arrowstyle="-|>", mutation_scale=13, color=color, lw=lw, ls=ls, zorder=4,
                                 connectionstyle=f"arc3,rad={rad}", shrinkA=0, shrinkB=0))
    if text:
        x, y = text_xy if text_xy else ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
        ax.text(x, y, text, ha="center", va="center", fontsize=size, color=color, zorder=5,
                bbox={"fc": "white", "ec": "none", "pad": 1.0})


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(15, 9.6), dpi=80 if quick else 130)
    ax.set_xlim(0.0, 16.0)
    ax.set_ylim(0.0, 10.2)
    ax.axis("off")

    # %% [markdown]
    # Top row: the inputs. Middle: the technique and its three methods. Bottom: the passes of render(), left to
    # right, with the reprojection flag (red) reaching into each of them and the previous frame fed back into the
    # reprojection.

    # %%
    _box(ax, 0.2, 8.4, 4.3, 1.4, "CloudscapeSettings",
         "layer radii, coverage, step counts,\nsky model choice, exposure,\nreprojection flag", INPUT)
    _box(ax, 5.0, 8.4, 6.0, 1.4, "BasicTextureGenerator",
         "base_shape 128³ RGBA (vc-A9), detail_shape 32³ RGB (vc-A10),\ncurl_noise 2-D (vc-A11), weather_map 2-D "
         "(vc-A12)\ngenerated once per texture settings, cached", INPUT)
    _box(ax, 11.5, 8.4, 4.3, 1.4, "Pose (frame n)",
         "position and orientation → view and\nprojection matrices of the frame", INPUT)

    # The technique container and its methods.
    ax.add_patch(FancyBboxPatch((0.2, 0.25), 15.6, 7.35, boxstyle="round,pad=0.02,rounding_size=0.25", fc="white",
                                ec="0.25", lw=1.6, zorder=1))
    ax.text(0.45, 7.38, "CloudscapeTechnique", ha="left", va="top", fontsize=13, fontweight="bold")
    _box(ax, 0.5, 5.6, 4.6, 1.0, "init()", "textures, sky model (GradientSky | PreethamSky),\nframe buffers and "
         "the reduced ¼×¼ buffer", METHOD, title_size=9.5, body_size=8)
    _box(ax, 5.7, 5.6, 4.6, 1.0, "update(**changes)", "new settings (time, sun, ...); textures are\nregenerated "
         "only if a texture setting changed", METHOD, title_size=9.5, body_size=8)
    _box(ax, 10.9, 5.6, 4.6, 1.0, "render(pose, reprojection) → image",
         "passes 1–3, sRGB encode; frame counter n,\nf = n mod 16 (vc-4.1); keeps the camera", METHOD,
         title_size=9.5, body_size=8)
    _arrow(ax, (2.35, 8.4), (2.35, 6.65))  # settings -> init
    _arrow(ax, (6.5, 8.4), (3.6, 6.65), text="textures", text_xy=(5.6, 7.95))  # generator -> init
    _arrow(ax, (13.65, 8.4), (13.65, 6.65), text="camera", text_xy=(13.65, 7.95))  # camera -> render

    # The passes of render(), grouped, with the reprojection flag on top of them.
    ax.add_patch(FancyBboxPatch((0.4, 1.7), 15.2, 3.5, boxstyle="round,pad=0.02,rounding_size=0.15", fc="none",
                                ec="0.55", lw=1.0, ls="--", zorder=1))
    ax.text(15.45, 4.95, "passes of render(),\nrun in order (the\nthesis: memory\nbarriers)", ha="right", va="top",
            fontsize=8,
            color="0.35", style="italic")
    _arrow(ax, (13.2, 5.6), (13.2, 5.24), color="0.2")  # render() runs the passes
    ax.add_patch(FancyBboxPatch((0.5, 4.35), 12.6, 0.65, boxstyle="round,pad=0.02,rounding_size=0.12", lw=1.2,
                                zorder=2, **FLAG))
    ax.text(6.8, 4.675, "reprojection flag (settings.reprojection, or render(reprojection=...); off with the camera "
            "in or above the layer, vc-A24)\non: each pass computes 1 pixel per 4×4 block (index of vc-4.1), 1/16 "
            "of the threads; off: 1 thread per pixel", ha="center", va="center", fontsize=8.5, color=FLAG_COLOUR,
            zorder=3, linespacing=1.4)
    _arrow(ax, (1.0, 8.4), (1.0, 5.0), color=FLAG_COLOUR, ls="--", lw=1.1)  # settings -> flag

    y0, h = 1.95, 1.9
    stages = (
        (0.6, 3.4, "1  Sky model", "GradientSky (vc-A28) or\nPreethamSky (vc-A29: Perez 2.36,\n"
                                   "zenith 2.39–2.41, xyY → RGB 4.3–4.5)"),
        (4.9, 3.8, "2  Cloud raymarch", "ray ∩ cloud layer spheres, 64–128\nsamples: density vc-A17 (2.28–2.30,\n"
                                        "4.7), 6 light samples, energy 2.31,\ncomposite over the sky 4.8"),
        (9.7, 3.4, "3  Reprojection", "optional (vc-A26, vc-A27): the other\n15/16 of the pixels from the previous\n"
                                      "frame via the previous camera,\nelse from the reduced buffer"),
        (13.8, 1.7, "Display", "sRGB encode,\nuint8 → PNG,\nGIF, MP4\n(pywarp.core.output)"),
    )
    for x, w, title, body in stages:
        _box(ax, x, y0, w, h, title, body, STAGE if title != "Display" else METHOD, body_size=8.3)
    for (xa, wa, *_), (xb, *_) in zip(stages[:-1], stages[1:]):
        _arrow(ax, (xa + wa, y0 + h / 2), (xb, y0 + h / 2))
    for x_mid, label in ((4.45, "back-\nground"), (9.2, "frame"), (13.45, "image")):
        ax.text(x_mid, y0 + h / 2 - 0.12, label, ha="center", va="top", fontsize=7.5, color="0.3")
    for x, w, *_ in stages[:3]:
        _arrow(ax, (x + w / 2, 4.35), (x + w / 2, y0 + h), color=FLAG_COLOUR, ls="--", lw=1.1)

    # Feedback: the finished frame and this frame's camera are kept for the next frame's reprojection.
    _box(ax, 9.7, 0.5, 3.4, 0.8, "previous frame + previous camera", style={"fc": "#eaf5ea", "ec": "#2e7d32"},
         title_size=8.5)
    _arrow(ax, (12.8, y0), (12.4, 1.3), color="#2e7d32")
    ax.text(12.75, 1.5, "kept for frame n+1", ha="left", va="center", fontsize=7.5, color="#2e7d32")
    _arrow(ax, (10.5, 1.3), (10.5, y0), color="#2e7d32")
    ax.text(5.2, 0.9, "sky and clouds need no history: only the reprojection reads the previous frame",
            ha="center", va="center", fontsize=8, color="0.35", style="italic")

    fig.suptitle("Rendering chain of the cloudscape (one frame), redrawn from pywarp/clouds/technique.py "
                 "(CloudscapeTechnique.render)",
                 fontsize=12, y=0.985)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.95, bottom=0.01)
    out = out_dir / "fig-4.1.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
