"""Camera rays and stand-in scenes for the tutorials (and your own notebooks): NumPy in float64, but for the textures.

The figures of the texts often need the view directions of a simple camera -- to evaluate a sky model per pixel, to
place a drop on the screen -- or a scene to look at where the text shows a photograph. These are not equations of the
texts (the scenes' cameras are ``pywarp.kernels.camera``), so they live here, once, instead of in each tutorial:

* :func:`pinhole_directions`: the unit rays through the pixel centres of a pinhole camera turned by azimuth and pitch
  (Y up, azimuth 0 looking down -Z, row 0 at the top): the ray generation of vc-A25 without the matrices;
* :func:`fisheye_directions`: an equidistant all-sky fisheye, seen looking up from below;
* :func:`row_of_elevation`: where the pinhole image shows a given elevation (to draw the horizon or the sun's height);
* :func:`billboard_frame`: the right and up vectors of a billboard facing the viewer (a rain drop's mask frame);
* :func:`environment`: a stand-in scene as a function of direction (sky, sun, a mountain ridge, a chequered meadow with
  a road, haze), the backdrop the rain tutorials refract through their drops;
* :func:`one_type_textures`: the cloudscape's textures with one cloud type over the whole weather map, the stand-in
  scene of the cloud-genus figures (this one renders with Warp);
* :func:`run_as_script`: the command line every tutorial has (``--out``, ``--quick``) when it runs as a script;
* :func:`text_problems` and :func:`checking_legibility`: the text of a figure (titles, axis labels, tick labels, the
  suptitle, figure texts, labels placed in an axes) inside the figure and not overlapping, checked where the tutorials save their figures.
* :func:`fit_text`: what the tutorials call instead of ``tight_layout`` (or before saving a figure laid out by hand),
  so that their titles and labels pass that check at any size: too-wide text shrunk to :data:`MIN_FONT_PT`, then
  wrapped; the layout corrected where ``tight_layout`` misses an overlap; a figure whose text fits left as it was.

Example::

    from pywarp.tutorial import environment, pinhole_directions
    d = pinhole_directions(320, 180, 50.0)           # (180, 320, 3), looking down -Z
    rgb = environment(d)                             # (180, 320, 3) float32 in [0, 1]
"""
from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

import numpy as np

__all__ = ["pinhole_directions", "fisheye_directions", "row_of_elevation", "billboard_frame", "environment",
           "one_type_textures", "run_as_script", "text_problems", "checking_legibility", "fit_text"]


def pinhole_directions(width: int, height: int, fov_y_deg: float, azimuth_deg: float = 0.0,
                       pitch_deg: float = 0.0) -> np.ndarray:
    """Unit view directions (height, width, 3) through the pixel centres of a pinhole camera (row 0 = top).

    The camera looks along f = (cos p sin a, sin p, -cos p cos a) -- azimuth a (0: -Z, 90 deg: +X), pitch p (up > 0),
    Y up -- and the ray through the image point (u, v) (both in [-1, 1], u to the right, v up) is
    f + u tan(fov/2) aspect r + v tan(fov/2) up, normalised. The camera has no roll, so the horizon (d_y = 0) projects
    to a horizontal line."""
    t = np.tan(np.radians(fov_y_deg) / 2.0)
    u = ((np.arange(width) + 0.5) / width * 2.0 - 1.0) * t * width / height
    v = (1.0 - (np.arange(height) + 0.5) / height * 2.0) * t
    uu, vv = np.meshgrid(u, v)
    a, p = np.radians(azimuth_deg), np.radians(pitch_deg)
    fwd = np.array([np.cos(p) * np.sin(a), np.sin(p), -np.cos(p) * np.cos(a)])
    right = np.array([np.cos(a), 0.0, np.sin(a)])
    up = np.cross(right, fwd)
    d = fwd + uu[..., None] * right + vv[..., None] * up
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def fisheye_directions(size: int) -> tuple[np.ndarray, np.ndarray]:
    """Equidistant all-sky fisheye: unit directions (size, size, 3) and the mask of pixels inside the horizon circle.

    The distance from the centre is proportional to the zenith angle (centre = zenith, rim = horizon). The sky is seen
    looking up from below, azimuth 0 (-Z) at the top, so azimuth 90 deg (+X) is on the LEFT, as in all-sky camera
    images. Pixels outside the circle get the direction of the rim."""
    c = (np.arange(size) + 0.5) / size * 2.0 - 1.0
    uu, vv = np.meshgrid(c, -c)  # v up
    r = np.hypot(uu, vv)
    zen = np.minimum(r, 1.0) * (np.pi / 2.0)  # zenith angle
    az = np.arctan2(-uu, vv)  # top = azimuth 0, left = azimuth 90 (looking up from below)
    d = np.stack([np.sin(zen) * np.sin(az), np.cos(zen), -np.sin(zen) * np.cos(az)], axis=-1)
    return d, r <= 1.0


def row_of_elevation(elev_deg, height: int, fov_y_deg: float, pitch_deg: float):
    """Fractional pixel row (0 = centre of the top row) at which the centre column of :func:`pinhole_directions`'
    camera sees the elevation ``elev_deg`` (scalar or array): the inverse of its v for that column."""
    v = np.tan(np.radians(np.asarray(elev_deg) - pitch_deg)) / np.tan(np.radians(fov_y_deg) / 2.0)
    return (1.0 - v) / 2.0 * height - 0.5


def billboard_frame(f) -> tuple[np.ndarray, np.ndarray]:
    """Right and up unit vectors of a billboard facing the viewer in direction ``f`` (unit, not vertical): right =
    f x Y (horizontal), up = right x f. The frame of a rain drop's mask (x right, y up, z along the view)."""
    rt = np.cross(f, [0.0, 1.0, 0.0])
    rt /= np.linalg.norm(rt)
    return rt, np.cross(rt, f)


def environment(d) -> np.ndarray:
    """A stand-in scene around the viewer as a function of direction ``d`` (..., 3), any length (camera space: x
    right, y up, looking down -z): a sky gradient, a sun, a mountain ridge on the horizon, a chequered meadow 1.6 m
    below the eye with a road along -z, and haze with distance. Returns float32 RGB in [0, 1], shape (..., 3).

    The rain tutorials show what a drop refracts with it where the text shows a photograph of a real scene; it is
    detailed enough (edges, a bright sun, colours above and below the horizon) that the upside-down, squeezed image a
    drop shows can be read."""
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    up = np.clip(y, 0, 1)[..., None]
    rgb = (1 - np.sqrt(up)) * np.array([0.86, 0.9, 0.96]) + np.sqrt(up) * np.array([0.22, 0.42, 0.85])
    sun = np.array([-0.45, 0.45, -1.0]) / np.linalg.norm([-0.45, 0.45, -1.0])
    rgb = rgb + np.clip((d @ sun - 0.996) / 0.002, 0, 1)[..., None] * np.array([1.2, 1.0, 0.6])
    az = np.arctan2(x, -z)
    ridge = (y >= 0) & (y < 0.07 + 0.05 * np.sin(3 * az + 0.5) + 0.025 * np.sin(11 * az))
    rgb = np.where(ridge[..., None], np.array([0.42, 0.45, 0.58]), rgb)
    below = y < 0
    dist = 1.6 / np.maximum(-y, 1e-4)
    gx, gz = x * dist, z * dist
    cell = (np.floor(gx / 2.0) + np.floor(gz / 2.0)) % 2
    grass = np.where(cell[..., None] > 0, np.array([0.22, 0.5, 0.16]), np.array([0.62, 0.52, 0.22]))
    road = np.abs(gx) < 1.2
    grass = np.where(road[..., None], np.array([0.3, 0.3, 0.32]), grass)
    haze = 1 - np.exp(-dist / 60.0)
    ground = (1 - haze[..., None]) * grass + haze[..., None] * np.array([0.8, 0.84, 0.9])
    rgb = np.where(below[..., None], ground, rgb)
    return np.clip(rgb, 0, 1).astype(np.float32)


def one_type_textures(settings, generator):
    """The cloudscape's textures for ``settings`` (a :class:`pywarp.clouds.cloudscape.CloudscapeSettings`) from
    ``generator`` (a :class:`pywarp.clouds.textures.TextureGenerator`), with the weather map's cloud-type spread set to
    0: the type channel is ``settings.cloud_type`` everywhere, so one genus fills the sky. The base, detail and curl
    textures do not depend on the type (a caching generator returns them from its cache). Returns the
    :class:`pywarp.clouds.cloudscape.RenderTextures` to pass to ``CloudscapeTechnique(settings, textures=...)``."""
    from .clouds import textures as T  # the scene layer (and Warp) only for this helper
    from .clouds.cloudscape import RenderTextures

    s = settings
    tex = generator.textures(
        T.BaseShapeSettings(size=s.base_size, seed=s.seed), T.DetailShapeSettings(size=s.detail_size, seed=s.seed),
        T.CurlNoiseSettings(size=s.curl_size, seed=s.seed),
        T.WeatherMapSettings(size=s.weather_size, seed=s.seed, coverage=s.coverage, precipitation=s.precipitation,
                             cloud_type=s.cloud_type, cloud_type_variation=0.0))
    return RenderTextures.from_textures(tex, s.device)


def run_as_script(main, doc: str, out: str, argv=None) -> list:
    """A tutorial run as a script (``python tutorials/vc/fig_4_09_height_gradients.py [--out DIR] [--quick]``):
    ``main(out_dir, quick)`` with the options, every file written printed on its own line; returns the files.
    ``doc``: the tutorial's docstring (its first line is the description of ``--help``); ``out``: the default folder,
    ``figures/<seed>``."""
    import argparse

    parser = argparse.ArgumentParser(description=doc.splitlines()[0], allow_abbrev=False)
    parser.add_argument("--out", default=out, help=f"output folder (default: {out})")
    parser.add_argument("--quick", action="store_true", help="small sizes, for a fast check")
    args = parser.parse_args(argv)
    written = list(main(args.out, quick=args.quick))
    print(*written, sep="\n")
    return written


#: Pixels two text boxes may share, or a box may stick out of the figure, before it counts: a glyph's box holds the
#: font's full ascent and descent, a pixel or two more than the ink of digits, so touching boxes are not yet clipped
#: or overlapping text.
TEXT_SLACK_PX = 2.0


def _texts(fig, annotations: bool = True):
    """(description, Text, its axes or None) of every drawn, non-empty title, axis label, tick label, text placed in an
    axes (``ax.text``, ``ax.annotate``) and figure text of ``fig`` (the suptitle is a figure text); the ticks are those
    the axis draws (inside its view limits). ``annotations=False``: without the texts placed in an axes (a layout
    does not move them)."""
    out = [(f"figure text {t.get_text()!r}", t, None) for t in fig.texts]
    for i, ax in enumerate(fig.axes):
        if not ax.get_visible():
            continue
        out += [(f"axes {i} title {t.get_text()!r}", t, ax) for t in (ax.title, ax._left_title, ax._right_title)]
        if annotations:  # ax.text / ax.annotate labels
            out += [(f"axes {i} text {t.get_text()!r}", t, ax) for t in ax.texts]
        if not ax.axison:
            continue
        for axis, which in ((ax.xaxis, "x"), (ax.yaxis, "y")):
            if not axis.get_visible():
                continue
            out.append((f"axes {i} {which} label {axis.label.get_text()!r}", axis.label, ax))
            for tick in axis._update_ticks():
                out += [(f"axes {i} {which} tick {lab.get_text()!r}", lab, ax) for lab in (tick.label1, tick.label2)]
    return [(d, t, ax) for d, t, ax in out if t.get_visible() and t.get_text().strip()]


def _overlapping(a, b, e):
    """Pairs (i, j) of boxes a[i], b[j] (x0, y0, x1, y1) that overlap by more than ``e`` both ways."""
    ox = np.minimum(a[:, None, 2], b[None, :, 2]) - np.maximum(a[:, None, 0], b[None, :, 0])
    oy = np.minimum(a[:, None, 3], b[None, :, 3]) - np.maximum(a[:, None, 1], b[None, :, 1])
    return (ox > e) & (oy > e)


def _problems(fig, inside: bool = True, annotations: bool = True) -> list[tuple]:
    """The problems :func:`text_problems` describes, as records: ("out", i, box, fig size), ("text", i, j) or
    ("area", i, k) for text i (of the list returned second) sticking out of the figure, overlapping text j, or
    overlapping the plot area of ``fig.axes[k]``. Returns (records, texts), each text (name, Text, axes, box).
    ``annotations``: whether the texts placed in an axes count (:func:`fit_text`'s layout leaves them out: moving the
    axes does not separate two labels inside one)."""
    from matplotlib.text import Text

    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    texts = []
    for name, t, ax in _texts(fig, annotations):
        b = Text.get_window_extent(t, renderer)  # an annotation's own extent takes in its arrow: the text's only
        if ax is not None and t in ax.texts and t.get_clip_on() and not b.overlaps(ax.bbox):
            continue  # clipped by its axes: not drawn
        if b.width > 0 and b.height > 0:
            texts.append((name, t, ax, (b.x0, b.y0, b.x1, b.y1)))
    found = []
    if not texts:
        return found, texts
    a = np.array([box for *_, box in texts])
    w, h = fig.bbox.width, fig.bbox.height
    e = TEXT_SLACK_PX
    if inside:
        for i, (x0, y0, x1, y1) in enumerate(a):
            if x0 < -e or y0 < -e or x1 > w + e or y1 > h + e:
                found.append(("out", i, (x0, y0, x1, y1), (w, h)))
    for i, j in zip(*np.nonzero(np.triu(_overlapping(a, a, e), 1))):
        found.append(("text", int(i), int(j)))
    axes = [(k, ax) for k, ax in enumerate(fig.axes) if ax.get_visible()]
    if axes:
        areas = np.array([tuple(ax.bbox.extents) for _, ax in axes])
        for i, j in zip(*np.nonzero(_overlapping(a, areas, e))):
            if texts[i][2] is not axes[j][1]:
                found.append(("area", int(i), axes[j][0]))
    return found, texts


def text_problems(fig, inside: bool = True) -> list[str]:
    """What makes the text of ``fig`` hard to read, from the extents the renderer gives: each text box
    (:func:`_texts`) that sticks out of the figure (when ``inside``; off for a figure saved with
    ``bbox_inches="tight"``, whose saved area grows to take it in), each pair of text boxes that overlap, and each text
    box that overlaps the plot area of another axes (a title over the image above it) -- by more than
    :data:`TEXT_SLACK_PX` either way."""
    found, texts = _problems(fig, inside)
    problems = []
    for rec in found:
        n = texts[rec[1]][0]
        if rec[0] == "out":
            (x0, y0, x1, y1), (w, h) = rec[2], rec[3]
            problems.append(f"{n} sticks out of the figure ({x0:.0f}, {y0:.0f}, {x1:.0f}, {y1:.0f} in a "
                            f"{w:.0f} x {h:.0f} figure)")
        elif rec[0] == "text":
            problems.append(f"{n} overlaps {texts[rec[2]][0]}")
        else:
            problems.append(f"{n} overlaps the plot area of axes {rec[2]}")
    # the records come in kind order already: out, text, area -- as the messages always did
    return problems


#: The smallest font size (points) :func:`fit_text` shrinks a title or label to before it wraps it onto more lines:
#: the size of small print in a printed caption, about 10 px a line at the tutorials' 100 dpi (any smaller and the
#: digits of a quick-mode figure blur together).
MIN_FONT_PT = 7.0
#: Pixels :func:`fit_text` keeps between a fitted figure text and the figure's left and right edges.
FIT_MARGIN_PX = 4.0
#: Rounds of :func:`fit_text`'s corrections to a tight layout (each re-measures the text and lays out again); two
#: settle every tutorial figure, the rest are for text a correction pushes into another.
FIT_ROUNDS = 4


def _protect_math(s: str) -> str:
    """Spaces inside ``$...$`` made non-breaking for :mod:`textwrap` (a wrapped line must not split a formula)."""
    parts = s.split("$")
    return "$".join(p.replace(" ", "\x00") if k % 2 else p for k, p in enumerate(parts))


def _protect_terms(s: str) -> str:
    """Also the spaces around a binary operator (``h_A - h_B``, ``pitch = 9.1``) made non-breaking: a line should not
    end on an operator or start with one when it can break elsewhere."""
    import re

    return re.sub(r" ([-+=*/<>]|->) ", "\x00\\1\x00", s)


def _fit_width(t, room: float, renderer, min_fontsize: float) -> bool:
    """Text ``t`` no wider than ``room`` pixels: its font size reduced in half points down to ``min_fontsize``, then,
    if it is still too wide, its words wrapped as one paragraph onto the fewest lines that fit, of even lengths (a
    formula in ``$...$`` kept on one line, and a term ``a - b`` too where the lines can break elsewhere). Returns
    whether it changed."""
    import textwrap

    def width():
        return t.get_window_extent(renderer).width

    if width() <= room:
        return False
    size = t.get_fontsize()
    while width() > room and size - 0.5 >= min_fontsize - 1e-9:
        size -= 0.5
        t.set_fontsize(size)
    if width() > room and size > min_fontsize:
        t.set_fontsize(min_fontsize)
    if width() <= room:
        return True
    # one paragraph: the text's own line breaks were made for a width it does not have
    plain = _protect_math(" ".join(t.get_text().split()))
    for words in (_protect_terms(plain), plain):

        def wrap(n, words=words):
            return textwrap.wrap(words, n, break_long_words=False, break_on_hyphens=False)

        def show(n, wrap=wrap):
            t.set_text("\n".join(wrap(n)).replace("\x00", " "))

        n = len(words)
        while width() > room and n > 8:
            n -= 1
            show(n)
        if width() <= room:
            lines = len(wrap(n))
            while n > 8 and len(wrap(n - 1)) == lines:  # as many lines, of even lengths (no word alone on the last)
                n -= 1
            show(n)
            return True
    return True


def fit_text(fig, *, tight_layout: bool = False, min_fontsize: float = MIN_FONT_PT, **tight_kwargs) -> bool:
    """Makes the text of ``fig`` legible where it is placed, measured by the renderer (as :func:`text_problems`
    measures it); call it where a tutorial would call ``fig.tight_layout()`` (``tight_layout=True``) or, for a figure
    laid out by hand, just before ``savefig``. A figure whose text already fits is left exactly as it was (but for the
    ``tight_layout`` it asked for), so its image does not change.

    * A figure text (the suptitle too) wider than the figure, or an axes title or x label that is wider than its axes
      and sticks out of the figure or overlaps another text, is reduced in size down to ``min_fontsize``
      (:data:`MIN_FONT_PT`) and then wrapped onto more lines (:func:`_fit_width`).
    * A left-aligned text of an axes (``ax.text``: a panel's label) that runs out at the figure's right edge is
      reduced and wrapped likewise, to the room between its start and that edge.
    * ``tight_layout``: lays the figure out with ``fig.tight_layout(**tight_kwargs)``, then corrects what that layout
      does not see (the titles of 3-D axes, an image's aspect, text drawn next to an axes), for up to
      :data:`FIT_ROUNDS` rounds: the area below a figure text that overlaps the axes is lowered, an axes title over
      the plot area of the axes above it gets more space between the rows (``h_pad``), and text that sticks out of
      the figure's bottom or sides gets that much more room at that edge.
    * Otherwise (axes placed by hand in figure fractions): the figure grows at the top by the height a wrapped figure
      text gained, every axes and every other text keeping its place in pixels from the bottom (a title band above
      an image grows; the image is not resampled).

    Returns whether it changed the figure beyond the ``tight_layout`` asked for (a text, a correction, a size)."""
    changed = False
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    w = fig.bbox.width
    found, texts = _problems(fig, annotations=False)
    flagged = {rec[1] for rec in found} | {rec[2] for rec in found if rec[0] == "text"}
    grown = []
    for i, (name, t, ax, (x0, y0, x1, y1)) in enumerate(texts):
        if ax is None:
            room = w - 2 * FIT_MARGIN_PX
        elif i in flagged and (t is ax.title or t is ax._left_title or t is ax._right_title or t is ax.xaxis.label):
            room = ax.bbox.width
        else:
            continue
        if _fit_width(t, room, renderer, min_fontsize):
            changed = True
            if ax is None:
                grown.append((t, y0, y1))
    for ax in fig.axes:  # an axes' own left-aligned text (a panel label) running out at the figure's right edge
        for t in ax.texts:
            b = t.get_window_extent(renderer)
            if t.get_visible() and t.get_ha() == "left" and b.x1 > w + TEXT_SLACK_PX and b.x0 < w:
                changed |= _fit_width(t, w - FIT_MARGIN_PX - b.x0, renderer, min_fontsize)
                if "\n" in t.get_text():  # more lines: they hang down from where its top was, into its axes
                    tr = t.get_transform()
                    x_px = tr.transform(t.get_position())[0]
                    t.set_verticalalignment("top")
                    t.set_position(tuple(tr.inverted().transform((x_px, b.y1))))
    if tight_layout:
        changed |= _tight_with_corrections(fig, tight_kwargs)
    elif grown:
        for t, y0, y1 in grown:
            _grow_top_for(fig, t, y0, y1)
    return changed


def _tight_with_corrections(fig, kwargs) -> bool:
    """``fig.tight_layout(**kwargs)``, then :func:`fit_text`'s corrections, round by round, each from the overlaps
    the renderer measures (pixels; ``tight_layout``'s pads are in units of the default font size). Returns whether
    it corrected the layout."""
    kw = dict(kwargs)
    fig.tight_layout(**kw)
    extra = TEXT_SLACK_PX + 2.0  # beyond the measured overlap: past the check's slack, and a gap one can see
    for k in range(FIT_ROUNDS):
        found, texts = _problems(fig, annotations=False)
        if not found:
            return k > 0
        w, h = fig.bbox.width, fig.bbox.height
        edges = dict(left=0.0, bottom=0.0, right=0.0, top=0.0)
        h_gap = w_gap = 0.0
        for rec in found:
            _, _, ax, (x0, y0, x1, y1) = texts[rec[1]]
            if rec[0] == "out":
                edges["left"] = max(edges["left"], -x0 + extra if x0 < 0 else 0.0)
                edges["bottom"] = max(edges["bottom"], -y0 + extra if y0 < 0 else 0.0)
                edges["right"] = max(edges["right"], x1 - w + extra if x1 > w else 0.0)
                edges["top"] = max(edges["top"], y1 - h + extra if y1 > h else 0.0)
                continue
            if rec[0] == "text":
                other_ax, (u0, v0, u1, v1) = texts[rec[2]][2], texts[rec[2]][3]
            else:
                other_ax, (u0, v0, u1, v1) = fig.axes[rec[2]], tuple(fig.axes[rec[2]].bbox.extents)
            ox, oy = min(x1, u1) - max(x0, u0), min(y1, v1) - max(y0, v0)
            if (ax is None) != (other_ax is None):  # a figure text on the axes' area: shrink that area away from it
                above = (y0 + y1 > v0 + v1) == (ax is None)  # the figure text is above (a suptitle)
                edges["top" if above else "bottom"] = max(edges["top" if above else "bottom"], oy + extra)
            elif oy <= ox:  # one above the other: more space between the rows
                h_gap = max(h_gap, oy + extra)
            else:  # side by side: more space between the columns
                w_gap = max(w_gap, ox + extra)
        x0, y0, x1, y1 = kw.get("rect", (0.0, 0.0, 1.0, 1.0))  # each edge moves everything laid out by as much
        kw["rect"] = (x0 + edges["left"] / w, y0 + edges["bottom"] / h, x1 - edges["right"] / w,
                      y1 - edges["top"] / h)
        pad = kw.get("pad", 1.08)
        if h_gap:
            kw["h_pad"] = kw.get("h_pad", pad) + h_gap / _font_px(fig)
        if w_gap:
            kw["w_pad"] = kw.get("w_pad", pad) + w_gap / _font_px(fig)
        fig.tight_layout(**kw)
    return True


def _font_px(fig) -> float:
    """The size in pixels of the default font, the unit of ``tight_layout``'s pads."""
    import matplotlib as mpl
    from matplotlib.font_manager import FontProperties

    return FontProperties(size=mpl.rcParams["font.size"]).get_size_in_points() * fig.dpi / 72.0


def _grow_top_for(fig, t, y0: float, y1: float) -> None:
    """The figure grown at the top by what figure text ``t`` (before fitting: from ``y0`` to ``y1`` pixels from the
    bottom) gained in height, ``t`` moved so that its bottom stays at ``y0``; the axes and other texts keep their
    pixels from the bottom, but texts above ``t`` move up with the top."""
    renderer = fig.canvas.get_renderer()
    b = t.get_window_extent(renderer)
    w, h = fig.bbox.width, fig.bbox.height
    grow = max(0.0, b.height - (y1 - y0))
    if grow <= 0.5:
        return
    new_h = h + grow
    for ax in fig.axes:
        p = ax.get_position()
        ax.set_position([p.x0, p.y0 * h / new_h, p.width, p.height * h / new_h])
    for other in fig.texts:
        if other.get_transform() != fig.transFigure:
            continue
        x, y = other.get_position()
        y_px = y * h
        if other is t:
            y_px += y0 - b.y0
        elif other.get_window_extent(renderer).y0 >= y1 - TEXT_SLACK_PX:
            y_px += grow
        other.set_position((x, y_px / new_h))
    fig.set_size_inches(w / fig.dpi, new_h / fig.dpi)


@contextmanager
def checking_legibility():
    """Within the block, every ``Figure.savefig`` first records the :func:`text_problems` of the figure it saves:
    yields a list of (file name, problem). Where the tutorials save their figures (they call ``fig.savefig``), so the
    tutorial tests check every figure of every text::

        with checking_legibility() as problems:
            module.main(out_dir, quick=True)
        assert not problems
    """
    from matplotlib.figure import Figure

    found: list[tuple[str, str]] = []
    save = Figure.savefig

    def checked(self, fname, *args, **kwargs):
        inside = kwargs.get("bbox_inches") != "tight"
        found.extend((Path(str(fname)).name, p) for p in text_problems(self, inside=inside))
        return save(self, fname, *args, **kwargs)

    Figure.savefig = checked
    try:
        yield found
    finally:
        Figure.savefig = save
