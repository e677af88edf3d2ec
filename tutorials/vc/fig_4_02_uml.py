"""Figures vc-fig-4.2, vc-fig-4.3, vc-fig-4.5, vc-fig-4.7 and vc-fig-4.15 (class diagrams), stand-ins: the classes of
pywarp that play the parts of the thesis's classes, drawn from the code itself.

The thesis prints five UML class diagrams (the sky model and its program, the gradient and the Preetham sky models,
the noise-texture generator, the visualization technique); their content is only partly in its text (vc-A31, vc-A32,
vc-A33). These stand-ins are generated, not drawn by hand: the classes are read with ``inspect`` -- the base classes
give the inheritance arrows, the public methods defined in each class its operations (with their parameters; abstract
ones in italics), the dataclass fields or the attributes ``__init__``/``update`` set its attributes -- and laid out
with matplotlib, so they stay true when the code changes. What each shows against the thesis:

* fig-4.2 (SkyModel / SkyModelProgram): ``SkyModel`` (pywarp.clouds.cloudscape) is the thesis's base class; there is
  no separate program class -- the GLSL program becomes one Warp kernel (``sky_kernel``) launched through the
  ``TileLauncher``, which also takes the reprojection's thread count (the thesis's SkyModelProgram).
* fig-4.3 / fig-4.5: ``GradientSky`` and ``PreethamSky`` derive from ``SkyModel`` like GradientSkyModel and
  PreethamSkyModel; their model-specific uniforms (the thesis's update_implementation) are the Warp structs
  ``SkyGradient`` and ``Preetham`` that ``update`` computes.
* fig-4.7: the generator interface is ``TextureGenerator`` with the thesis's four methods (base_shape, detail_shape,
  curl_noise, weather_map, plus textures for all four); ``BasicTextureGenerator`` implements it and generates all four
  (the thesis loads curl noise and the weather map from files); the settings structs are dataclasses.
* fig-4.15: ``Technique`` has init / update / render (the thesis's draw) and resize (the thesis's second interface) in
  one class; the library has four techniques, one per scene, where the thesis has the clouds alone.

Outputs: figures/vc/fig-4.2.png, figures/vc/fig-4.3.png, figures/vc/fig-4.5.png, figures/vc/fig-4.7.png,
figures/vc/fig-4.15.png.
"""
# %% [markdown]
# A class box has three compartments: the name (italic for an abstract class), the attributes and the operations.
# An arrow with a hollow head points from a subclass to its base; a plain arrow with a label is a use (an
# attribute holding an instance, or a call).

# %%
from __future__ import annotations

import dataclasses
import inspect
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import FancyArrowPatch, Rectangle  # noqa: E402

from pywarp.clouds import cloudscape as CS  # noqa: E402
from pywarp.clouds import settings as CSET  # noqa: E402
from pywarp.clouds import textures as T  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.core.runtime import TileLauncher  # noqa: E402
from pywarp.core.technique import Technique  # noqa: E402
from pywarp.flight.technique import FlightTechnique  # noqa: E402
from pywarp.kernels import sky as SK  # noqa: E402
from pywarp.rain.technique import RainTechnique  # noqa: E402
from pywarp.terrain.technique import TerrainTechnique  # noqa: E402

FONT_PT = 7.5  # the size of the compartments' text
UNIT_IN = 0.5  # one diagram unit, in inches: every figure is drawn at this scale
LINE = FONT_PT * 1.5 / 72 / UNIT_IN  # height of one text line in diagram units
CHAR = FONT_PT * 0.62 / 72 / UNIT_IN  # width of one monospace character in diagram units


def _params(fn) -> str:
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):
        return "(...)"
    names = [p.name for p in sig.parameters.values() if p.name != "self"]
    return "(" + ", ".join(names) + ")"


def operations(cls, limit: int = 9) -> list[tuple[str, bool]]:
    """(signature, abstract) of the public methods ``cls`` itself defines, in source order."""
    out = []
    for name, member in cls.__dict__.items():
        if name.startswith("_") or not callable(member) or isinstance(member, type):
            continue
        fn = member.__func__ if isinstance(member, (classmethod, staticmethod)) else member
        out.append((f"+ {name}{_params(fn)}", getattr(fn, "__isabstractmethod__", False)))
    return out[:limit]


def attributes(cls, limit: int = 8) -> list[str]:
    """The dataclass fields of ``cls`` (name: type), a Warp struct's fields, or the ``self.x`` its own methods set."""
    if dataclasses.is_dataclass(cls):
        fields = [f"{f.name}: {f.type if isinstance(f.type, str) else f.type.__name__}" for f in dataclasses.fields(cls)
                  if not f.name.startswith("_")]
    elif hasattr(cls, "vars") and isinstance(getattr(cls, "vars"), dict):  # a Warp struct
        fields = [f"{k}: " + (f"vec{v.type._length_}" if hasattr(v.type, "_length_") else
                              getattr(v.type, "__name__", str(v.type))) for k, v in cls.vars.items()]
    else:
        names = []
        for name in ("__init__", "update", "rebuild", "use_device"):
            fn = cls.__dict__.get(name)
            if fn is None:
                continue
            try:
                src = inspect.getsource(fn)
            except (OSError, TypeError):
                continue
            for tok in src.replace("(", " ").replace(",", " ").split():
                if tok.startswith("self.") and tok.count(".") == 1:
                    attr = tok[5:].rstrip(":=")
                    if attr.isidentifier() and not attr.startswith("_") and attr not in names and \
                            not callable(getattr(cls, attr, None)):
                        names.append(attr)
        fields = names
    if len(fields) > limit:
        fields = fields[:limit - 1] + [f"... ({len(fields) - limit + 1} more)"]
    return fields


def box(ax, cls, x, y, note: str = "", ops_limit: int = 9, attr_limit: int = 8, name: str | None = None):
    """Draw the class box of ``cls`` with its top-left corner at (x, y); returns (x0, y0, x1, y1)."""
    title = name or cls.__name__
    abstract = inspect.isabstract(cls) if isinstance(cls, type) else False
    attrs = attributes(cls, attr_limit) if isinstance(cls, type) or hasattr(cls, "vars") else []
    ops = operations(cls, ops_limit) if isinstance(cls, type) else []
    lines = [title] + ([f"«{note}»"] if note else [])
    width = max([len(s) * 1.25 for s in lines] + [len(s) for s in attrs + [o for o, _ in ops] + ["x" * 12]]) \
        * CHAR + 0.4
    h_name, h_attr, h_ops = len(lines) * LINE + 0.15, max(len(attrs), 1) * LINE + 0.1, max(len(ops), 1) * LINE + 0.1
    height = h_name + h_attr + h_ops
    y0 = y - height
    ax.add_patch(Rectangle((x, y0), width, height, fc="#fdf6e3", ec="k", lw=1.0))
    ax.plot([x, x + width], [y - h_name] * 2, "k-", lw=0.8)
    ax.plot([x, x + width], [y - h_name - h_attr] * 2, "k-", lw=0.8)
    ax.text(x + width / 2, y - 0.1 - LINE / 2, title, ha="center", va="center", fontsize=9, fontweight="bold",
            style="italic" if abstract else "normal")
    if note:
        ax.text(x + width / 2, y - 0.1 - 1.5 * LINE, f"«{note}»", ha="center", va="center", fontsize=7.5)
    for k, a in enumerate(attrs):
        ax.text(x + 0.15, y - h_name - 0.05 - (k + 0.5) * LINE, a, va="center", fontsize=7.5, family="monospace")
    for k, (o, is_abstract) in enumerate(ops):
        ax.text(x + 0.15, y - h_name - h_attr - 0.05 - (k + 0.5) * LINE, o, va="center", fontsize=7.5,
                family="monospace", style="italic" if is_abstract else "normal")
    return (x, y0, x + width, y)


def inherit(ax, sub, base):
    """Arrow with a hollow head from the top of box ``sub`` to the bottom of box ``base``."""
    start = ((sub[0] + sub[2]) / 2, sub[3])
    end = ((base[0] + base[2]) / 2, base[1])
    ax.add_patch(FancyArrowPatch(start, end, arrowstyle="-|>,head_length=0.5,head_width=0.3", mutation_scale=14,
                                 fc="w", ec="k", lw=1.0))


def uses(ax, a, b, label, side="right"):
    """A dashed arrow from box ``a``'s side to box ``b``'s facing side, labelled beside its middle."""
    if side == "right":
        lo, hi = max(a[1], b[1]), min(a[3], b[3])  # the heights both boxes span: a horizontal arrow near the top
        ya, yb = (hi - 0.5, hi - 0.5) if hi - lo > 0.6 else ((a[1] + a[3]) / 2, (b[1] + b[3]) / 2)
        start, end = (a[2], ya), (b[0], yb)
        ax.text((start[0] + end[0]) / 2, (ya + yb) / 2 - 0.15, label, ha="center", va="top", fontsize=FONT_PT,
                bbox=dict(fc="w", ec="none", pad=1.0))
    else:
        start, end = ((a[0] + a[2]) / 2, a[1]), ((a[0] + a[2]) / 2, b[3])
        ax.text(start[0] + 0.2, (start[1] + end[1]) / 2, label, ha="left", va="center", fontsize=FONT_PT)
    ax.add_patch(FancyArrowPatch(start, end, arrowstyle="->", mutation_scale=12, ec="k", lw=0.9, ls="--"))


def _figure(title, xlim, ylim, dpi):
    """A figure whose axes show ``xlim`` x ``ylim`` diagram units at UNIT_IN inches each, 0.6 in above for the
    title."""
    w, h = (xlim[1] - xlim[0]) * UNIT_IN, (ylim[1] - ylim[0]) * UNIT_IN
    fig = plt.figure(figsize=(w, h + 0.6), dpi=dpi)
    ax = fig.add_axes([0.0, 0.0, 1.0, h / (h + 0.6)])
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_axis_off()
    fig.suptitle(title, fontsize=10, y=1.0 - 0.1 / (h + 0.6), va="top")
    return fig, ax


def main(out_dir, quick: bool = False) -> list[Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    dpi = 60 if quick else 100
    written = []

    def save(fig, name):
        """Fit the figure to the boxes drawn (UNIT_IN inches per unit both ways, 0.6 in for the title), then save."""
        ax = fig.axes[0]
        x1 = max(p.get_x() + p.get_width() for p in ax.patches if isinstance(p, Rectangle)) + 0.3
        y0 = min(p.get_y() for p in ax.patches if isinstance(p, Rectangle)) - 0.3
        y1 = ax.get_ylim()[1]
        w, h = x1 * UNIT_IN, (y1 - y0) * UNIT_IN
        title_w = fig.texts[0].get_window_extent(fig.canvas.get_renderer()).width / fig.dpi + 0.4
        w = max(w, title_w)
        fig.set_size_inches(w, h + 0.6)
        ax.set_position([0.0, 0.0, x1 * UNIT_IN / w, h / (h + 0.6)])
        ax.set_xlim(0.0, x1)
        ax.set_ylim(y0, y1)
        fig.texts[0].set_y(1.0 - 0.1 / (h + 0.6))
        out = out_dir / name
        fig.savefig(out)
        plt.close(fig)
        written.append(out)

    # %% [markdown]
    # fig 4.2: the sky model and what runs its program.

    # %%
    fig, ax = _figure("Fig 4.2 stand-in — the sky model (vc-A31): SkyModel, and a Warp kernel launched through the\n"
                      "TileLauncher in place of SkyModelProgram", (0, 30), (0, 11), dpi)
    tech = box(ax, CloudscapeTechnique, 0.3, 10.6, ops_limit=5, attr_limit=6)
    sky = box(ax, CS.SkyModel, tech[2] + 2.0, 10.6, note="abstract")
    launcher = box(ax, TileLauncher, sky[2] + 4.5, 10.6, ops_limit=4, attr_limit=5)
    uses(ax, tech, sky, "sky")
    uses(ax, sky, launcher, "render():\nlaunch(sky_kernel)")
    grad = box(ax, CS.GradientSky, sky[0] - 1.0, 4.6, ops_limit=3, attr_limit=4)
    pree = box(ax, CS.PreethamSky, grad[2] + 3.0, 4.6, ops_limit=3, attr_limit=4)
    inherit(ax, grad, sky)
    inherit(ax, pree, sky)
    save(fig, "fig-4.2.png")

    # %% [markdown]
    # fig 4.3 and fig 4.5: each model with the per-frame struct its update() computes (the thesis's uniforms).

    # %%
    for fig_name, cls, struct, text in (
            ("fig-4.3.png", CS.GradientSky, SK.SkyGradient, "Fig 4.3 stand-in — the gradient sky model (vc-A28): "
                                                            "GradientSky and its per-frame struct SkyGradient"),
            ("fig-4.5.png", CS.PreethamSky, SK.Preetham, "Fig 4.5 stand-in — the Preetham sky model (vc-A29): "
                                                         "PreethamSky and its per-frame struct Preetham")):
        fig, ax = _figure(text, (0, 26), (0, 12), dpi)
        base = box(ax, CS.SkyModel, 0.5, 11.4, note="abstract")
        model = box(ax, cls, 0.8, 6.4, ops_limit=3, attr_limit=4)
        inherit(ax, model, base)
        st = box(ax, struct, max(base[2], model[2]) + 4.0, 11.4, note="Warp struct", attr_limit=20,
                 name=struct.__name__)
        uses(ax, model, st, "update() computes")
        save(fig, fig_name)

    # %% [markdown]
    # fig 4.7: the noise-texture generator, its implementation and the settings of each texture.

    # %%
    fig, ax = _figure("Fig 4.7 stand-in — the noise-texture generator (vc-A32): the interface, its implementation "
                      "and the settings structs", (0, 36), (0, 18), dpi)
    gen = box(ax, T.TextureGenerator, 0.3, 17.4, note="abstract", ops_limit=6)
    basic = box(ax, T.BasicTextureGenerator, 0.3, 10.0, ops_limit=6, attr_limit=4)
    inherit(ax, basic, gen)
    cache = box(ax, T.TextureCache, 0.3, 3.6, ops_limit=3, attr_limit=3)
    uses(ax, basic, cache, "cache", side="down")
    x = max(gen[2], basic[2]) + 4.0
    tops = []
    for k, cls in enumerate((CSET.BaseShapeSettings, CSET.DetailShapeSettings, CSET.CurlNoiseSettings,
                              CSET.WeatherMapSettings)):
        b = box(ax, cls, x if k % 2 == 0 else tops[-1][2] + 1.0, 17.4 - (k // 2) * 6.6, note="dataclass",
                ops_limit=2, attr_limit=6)
        tops.append(b)
    uses(ax, gen, tops[0], "settings of\neach texture")
    out = box(ax, T.CloudTextures, x, 4.0, note="dataclass", ops_limit=2, attr_limit=4)
    uses(ax, basic, out, "textures() returns")
    save(fig, "fig-4.7.png")

    # %% [markdown]
    # fig 4.15: the technique interface and the techniques of the four scenes.

    # %%
    fig, ax = _figure("Fig 4.15 stand-in — the visualization technique (vc-A33): init / update / render and resize "
                      "in one base class; one technique per scene", (0, 40), (0, 15), dpi)
    base = box(ax, Technique, 14.0, 14.6, ops_limit=9, attr_limit=5)
    subs = []
    x = 0.3
    for cls in (CloudscapeTechnique, TerrainTechnique, RainTechnique, FlightTechnique):
        subs.append(box(ax, cls, x, 6.4, ops_limit=5, attr_limit=3))
        x = subs[-1][2] + 0.8
    for s in subs:
        inherit(ax, s, base)
    save(fig, "fig-4.15.png")
    return written


if __name__ == "__main__":
    from pywarp.tutorial import run_as_script

    run_as_script(main, __doc__, "figures/vc")
