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
  suptitle, figure texts) inside the figure and not overlapping, checked where the tutorials save their figures.

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
           "one_type_textures", "run_as_script", "text_problems", "checking_legibility"]


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


def _texts(fig):
    """(description, Text, its axes or None) of every drawn, non-empty title, axis label, tick label and figure text
    of ``fig`` (the suptitle is a figure text); the ticks are those the axis draws (inside its view limits)."""
    out = [(f"figure text {t.get_text()!r}", t, None) for t in fig.texts]
    for i, ax in enumerate(fig.axes):
        if not ax.get_visible():
            continue
        out += [(f"axes {i} title {t.get_text()!r}", t, ax) for t in (ax.title, ax._left_title, ax._right_title)]
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


def text_problems(fig, inside: bool = True) -> list[str]:
    """What makes the text of ``fig`` hard to read, from the extents the renderer gives: each text box
    (:func:`_texts`) that sticks out of the figure (when ``inside``; off for a figure saved with
    ``bbox_inches="tight"``, whose saved area grows to take it in), each pair of text boxes that overlap, and each text
    box that overlaps the plot area of another axes (a title over the image above it) -- by more than
    :data:`TEXT_SLACK_PX` either way."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes, names, owners = [], [], []
    for name, t, ax in _texts(fig):
        b = t.get_window_extent(renderer)
        if b.width > 0 and b.height > 0:
            boxes.append((b.x0, b.y0, b.x1, b.y1))
            names.append(name)
            owners.append(ax)
    problems = []
    if not boxes:
        return problems
    a = np.array(boxes)
    w, h = fig.bbox.width, fig.bbox.height
    e = TEXT_SLACK_PX
    if inside:
        for (x0, y0, x1, y1), n in zip(a, names):
            if x0 < -e or y0 < -e or x1 > w + e or y1 > h + e:
                problems.append(f"{n} sticks out of the figure ({x0:.0f}, {y0:.0f}, {x1:.0f}, {y1:.0f} in a "
                                f"{w:.0f} x {h:.0f} figure)")
    for i, j in zip(*np.nonzero(np.triu(_overlapping(a, a, e), 1))):
        problems.append(f"{names[i]} overlaps {names[j]}")
    axes = [(k, ax) for k, ax in enumerate(fig.axes) if ax.get_visible()]
    if axes:
        areas = np.array([tuple(ax.bbox.extents) for _, ax in axes])
        for i, j in zip(*np.nonzero(_overlapping(a, areas, e))):
            if owners[i] is not axes[j][1]:
                problems.append(f"{names[i]} overlaps the plot area of axes {axes[j][0]}")
    return problems


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
