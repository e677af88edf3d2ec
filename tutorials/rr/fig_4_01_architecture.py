"""Figure rr-fig-4.1: the basic block diagram of the application (rr-alg-4.1) -- the text's ten classes, each drawn
with the part of pywarp's rain scene that does its work, and the flow of one frame between them. Output:
figures/rr/fig-4.1.png.
"""
# %% [markdown]
# The text names ten classes (§4.1) but draws no edges we can read (the figure is not in our copy; spec rr-fig-4.1:
# "edges not described in text"). The edges here are the calls of one frame as §4.1 describes them: RUNTIME sets up
# GLUT and draws the skybox, the terrain and the particle system; FBOBJECT renders skybox and terrain into the
# 512 x 512 texture; DROP renders the drop model into the refraction texture; RAIN PARTICLE moves the drops; SHADER
# runs the refraction on every particle; POST OBJECT draws the result. TGA and IMAGE load the Terragen textures.
#
# Under each class: where pywarp does that work. A background scene (the pt terrain by default) replaces Terragen's
# model, skybox and textures; the capture is a render of that scene, not a texture pass; the shaders are one Warp
# compositing kernel.

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch  # noqa: E402

#: class -> (centre x, centre y, what it does in the text, where pywarp does it)
BLOCKS = {
    "RUNTIME": (0.50, 0.88, "GLUT set-up, callbacks, camera,\nkeyboard; draws the whole scene",
                "pywarp render | view rain\nRainTechnique (rain/technique.py),\nRainControls (rain/controls.py)"),
    "SKYBOX": (0.13, 0.62, "loads and draws the skybox", "the background scene's sky\n(SceneBackground)"),
    "TERRAIN": (0.37, 0.62, "loads the Terragen model\nand textures",
                "the background scene: terrain\n(default), clouds, flight, panorama"),
    "RAIN PARTICLE": (0.63, 0.62, "N drops, Gaussian sizes, fall,\nrespawn at the top",
                      "ParticleSystem (rain/particles.py)\nrr-code-5.2.2 kernels"),
    "DROP": (0.87, 0.62, "drop model of the chosen shape\nrendered to the refraction texture",
             "drop_mask (rain/drops.py)\nrr-alg-3.1.1, Table 2.1 shapes"),
    "TGA": (0.13, 0.12, "reads TGA headers and data", "(none: no image files)"),
    "IMAGE": (0.13, 0.36, "image from Tga's data", "(none: the scenes are\nrendered, not loaded)"),
    "FBOBJECT": (0.40, 0.36, "renders skybox + terrain into\na 512 x 512 texture",
                 "RainTechnique.images(): the\n150 deg capture, cached per pose"),
    "SHADER": (0.70, 0.36, "compiles and links the\nrefraction / streak shaders",
               "particles_composite: Warp kernel\n(kernels/particles.py), rr-code-5.2.3/4"),
    "POST OBJECT": (0.55, 0.12, "draws the resulting texture", "composite() -> frame -> PNG / window"),
}
#: (from, to, label) -- the flow of one frame
EDGES = (("RUNTIME", "SKYBOX", "draw"), ("RUNTIME", "TERRAIN", "draw"), ("RUNTIME", "RAIN PARTICLE", "step"),
         ("RUNTIME", "DROP", "shape"), ("TGA", "IMAGE", "data"), ("IMAGE", "TERRAIN", "textures"),
         ("SKYBOX", "FBOBJECT", "render"), ("TERRAIN", "FBOBJECT", "render"), ("FBOBJECT", "SHADER", "capture"),
         ("RAIN PARTICLE", "SHADER", "billboards"), ("DROP", "SHADER", "mask"), ("SHADER", "POST OBJECT", "frame"))
W, H = 0.21, 0.16


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(15, 9.5), dpi=60 if quick else 110)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.axis("off")
    for name, (x, y, text_role, ours) in BLOCKS.items():
        ax.add_patch(FancyBboxPatch((x - W / 2, y - H / 2), W, H, boxstyle="round,pad=0.005,rounding_size=0.01",
                                    fc="#eef3fa", ec="#3b5b8c", lw=1.4))
        ax.text(x, y + H / 2 - 0.022, name, ha="center", va="center", fontsize=11, weight="bold", color="#1d3557")
        ax.text(x, y + 0.012, text_role, ha="center", va="center", fontsize=8, color="#333333")
        ax.text(x, y - H / 2 + 0.036, ours, ha="center", va="center", fontsize=7.5, color="#8a3b12",
                family="monospace")
    for a, b, label in EDGES:
        xa, ya = BLOCKS[a][:2]
        xb, yb = BLOCKS[b][:2]
        # from the edge of box a towards box b (the arrow ends at b's edge)
        def edge(x0, y0, x1, y1):
            dx, dy = x1 - x0, y1 - y0
            s = min(W / 2 / abs(dx) if dx else 1e9, H / 2 / abs(dy) if dy else 1e9)
            return x0 + dx * s, y0 + dy * s
        p0 = edge(xa, ya, xb, yb)
        p1 = edge(xb, yb, xa, ya)
        ax.add_patch(FancyArrowPatch(p0, p1, arrowstyle="-|>", mutation_scale=14, color="#555555", lw=1.1))
        ax.text(p0[0] + 0.4 * (p1[0] - p0[0]), p0[1] + 0.4 * (p1[1] - p0[1]), label, fontsize=7.5, ha="center", va="center",
                color="#555555", bbox=dict(fc="white", ec="none", pad=0.5))
    ax.text(0.01, 0.985, "black: the class's role in the text (§4.1)    brown: where pywarp's rain scene does it",
            fontsize=9, va="top")
    fig.suptitle("Fig 4.1 (in kind) — basic block diagram of the application (rr-alg-4.1), with pywarp's rain scene",
                 fontsize=12)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.94, bottom=0.01)
    out = out_dir / "fig-4.1.png"
    fig.savefig(out)
    plt.close(fig)
    return [out]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
