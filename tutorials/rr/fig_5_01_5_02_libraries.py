"""Figures rr-fig-5.1 and rr-fig-5.2: the libraries the application is built on (§5.1) -- how GLUT sits in an
application between it, OpenGL and the window system (5.1), and the layering of OpenGL, GLU and GLUT (5.2), drawn in
kind from the text's description of each library. Outputs: figures/rr/fig-5.1.png, figures/rr/fig-5.2.png.
"""
# %% [markdown]
# The text takes both figures from its sources ([10], [11]: Tišnovský's root.cz series on GLUT and GLU); our copy has
# their captions only, so they are drawn here from what §5.1 says of each library:
#
# * OpenGL (§5.1.1): independent of the operating system, the graphics driver and the window manager, so it has no
#   functions for windows, a GUI or events -- those come from the window system or a library above it;
# * GLUT (§5.1.2): a system-independent interface for windows and a simple GUI (keyboard, mouse, bitmap and vector
#   fonts; no buttons or sliders), with C's basic types only;
# * GLU (§5.1.3): tessellators, evaluators (points on parametric surfaces), quadrics (spheres, cylinders, cones,
#   discs) and display-list helpers, on top of OpenGL;
# * GLEW (§5.1.4): the extensions and newer OpenGL versions on every platform.
#
# The application (C++, §5) calls all of them; GLUT calls OpenGL and the window system (WGL on Windows, GLX under X).

# %%
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch  # noqa: E402

BLUE, ORANGE, GREEN, GREY = "#dbe8f7", "#fde6cf", "#dff2dc", "#ececec"


def box(ax, x, y, w, h, title, text="", fc=BLUE, size=11):
    ax.add_patch(FancyBboxPatch((x, y), w, h, boxstyle="round,pad=0.004,rounding_size=0.012", fc=fc, ec="#34495e",
                                lw=1.3))
    ax.text(x + w / 2, y + h - 0.03 if text else y + h / 2, title, ha="center", va="center", fontsize=size,
            weight="bold", color="#1b2a3a")
    if text:
        ax.text(x + w / 2, y + h / 2 - 0.018, text, ha="center", va="center", fontsize=8.2, color="#333333")


def arrow(ax, p0, p1, label="", both=False):
    ax.add_patch(FancyArrowPatch(p0, p1, arrowstyle="<|-|>" if both else "-|>", mutation_scale=13, color="#444444",
                                 lw=1.2))
    if label:
        ax.text((p0[0] + p1[0]) / 2 + 0.01, (p0[1] + p1[1]) / 2, label, fontsize=8, color="#444444", va="center")


def fig_5_1(path: Path, dpi: int) -> None:
    """GLUT in an application: the application's callbacks and GLUT's event loop over the window system."""
    fig, ax = plt.subplots(figsize=(11, 8.5), dpi=dpi)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.axis("off")
    box(ax, 0.08, 0.78, 0.84, 0.14, "application (C++)",
        "initialises GLUT, registers its callbacks (display, reshape, keyboard, idle),\n"
        "draws the scene with OpenGL / GLU calls, then enters glutMainLoop()", fc=ORANGE)
    box(ax, 0.08, 0.50, 0.40, 0.18, "GLUT",
        "windows, keyboard, mouse,\nbitmap / vector fonts, the event loop:\ncalls the application's callbacks")
    box(ax, 0.54, 0.50, 0.38, 0.18, "OpenGL  (+ GLU, GLEW)",
        "drawing only: no windows,\nno GUI, no events")
    box(ax, 0.08, 0.26, 0.84, 0.13, "window system interface: WGL (Windows), GLX (X Window)",
        "creates the OpenGL context of a window, swaps its buffers", fc=GREEN)
    box(ax, 0.08, 0.05, 0.40, 0.12, "window system / OS", "Win32, X Window: windows, input events", fc=GREY)
    box(ax, 0.54, 0.05, 0.38, 0.12, "graphics driver + hardware", "", fc=GREY)
    arrow(ax, (0.16, 0.78), (0.16, 0.68), "glutInit, glutCreateWindow,\nglut*Func(callback)")
    arrow(ax, (0.42, 0.68), (0.42, 0.78), "callbacks")
    arrow(ax, (0.73, 0.78), (0.73, 0.68), "gl* / glu* calls")
    arrow(ax, (0.48, 0.59), (0.54, 0.59))
    arrow(ax, (0.28, 0.50), (0.28, 0.39), "context, swap", both=True)
    arrow(ax, (0.73, 0.50), (0.73, 0.39))
    arrow(ax, (0.28, 0.26), (0.28, 0.17), "events", both=True)
    arrow(ax, (0.73, 0.26), (0.73, 0.17), "commands")
    ax.text(0.5, 0.975, "Fig 5.1 (in kind) — integration of GLUT in an application (rr §5.1.2)", ha="center",
            va="top", fontsize=12)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.99, bottom=0.01)
    fig.savefig(path)
    plt.close(fig)


def fig_5_2(path: Path, dpi: int) -> None:
    """The layering of OpenGL, GLU and GLUT: each library uses the ones below it; the application may call any."""
    fig, ax = plt.subplots(figsize=(11, 7.5), dpi=dpi)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.axis("off")
    box(ax, 0.06, 0.80, 0.88, 0.10, "application program", fc=ORANGE)
    box(ax, 0.06, 0.56, 0.28, 0.16, "GLUT", "windows, simple GUI,\nkeyboard, mouse, fonts")
    box(ax, 0.38, 0.56, 0.26, 0.16, "GLU", "tessellators, evaluators,\nquadrics, display lists")
    box(ax, 0.68, 0.56, 0.20, 0.16, "GLEW", "extensions, newer\nOpenGL versions")
    box(ax, 0.06, 0.32, 0.28, 0.14, "WGL / GLX", "+ Win32 / Xlib", fc=GREEN)
    box(ax, 0.38, 0.32, 0.56, 0.14, "OpenGL (GL)", "independent of the OS, the driver and the window manager")
    box(ax, 0.06, 0.08, 0.88, 0.14, "graphics driver, hardware, frame buffer", fc=GREY)
    for x in (0.20, 0.51, 0.78):
        arrow(ax, (x, 0.80), (x, 0.72))
    arrow(ax, (0.91, 0.80), (0.91, 0.46), "gl*")
    arrow(ax, (0.20, 0.56), (0.20, 0.46))
    arrow(ax, (0.30, 0.56), (0.45, 0.46))
    arrow(ax, (0.51, 0.56), (0.51, 0.46))
    arrow(ax, (0.75, 0.56), (0.75, 0.46))
    arrow(ax, (0.20, 0.32), (0.20, 0.22))
    arrow(ax, (0.66, 0.32), (0.66, 0.22))
    ax.text(0.5, 0.975, "Fig 5.2 (in kind) — relationship between the OpenGL, GLU and GLUT libraries (rr §5.1)",
            ha="center", va="top", fontsize=12)
    fig.subplots_adjust(left=0.01, right=0.99, top=0.99, bottom=0.01)
    fig.savefig(path)
    plt.close(fig)


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    dpi = 60 if quick else 110
    p1, p2 = out_dir / "fig-5.1.png", out_dir / "fig-5.2.png"
    fig_5_1(p1, dpi)
    fig_5_2(p2, dpi)
    return [p1, p2]


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/rr")
