"""Linear (scene-referred, before the display encoding) image output: OpenEXR and NumPy files, and numbered frames.

``pywarp render --out x.exr`` / ``--out x.npy`` and ``pywarp animate --out frames/frame_%04d.exr`` write the
*display-linear* RGB image of a scene: the float image a technique holds before it clamps to [0, 1] and applies the
sRGB encoding (values above 1 are kept; nothing is tone mapped). The PNG/MP4 outputs are that image clamped and
sRGB-encoded.

The hook (optional, per technique)
----------------------------------
A scene's technique offers linear output by having a method ::

    render_linear(pose=None, progress=None) -> np.ndarray   # float32 (height, width, 3), display-linear RGB

which renders one frame exactly as ``render(pose, progress)`` does (same frame counter, same temporal history: an
animation may mix neither) and returns the float image before its display encoding. A technique without it is
refused by :func:`render_linear` with a ValueError naming the option (``--out: scene 'rain' writes 8-bit images
only, ...; use .png``), before any frame is rendered.

Files
-----
* ``.npy``: float32 (height, width, 3), row 0 at the top, linear RGB (sRGB/Rec. 709 primaries, D65 white);
  ``np.load`` reads it.
* ``.exr``: one part, channels R, G, B, scan lines, ZIP compression, ``half`` (default) or ``float`` pixels
  (:data:`EXR_PRECISIONS`), written with the ``OpenEXR`` package (the Academy Software Foundation's bindings).
  Half floats hold up to 65504 with 11 significant bits: plenty for a display-linear image.
* numbered frames: a path with one printf integer field (``frame_%04d.png``, ``%d``, ``%05d``); ``.png`` frames are
  the encoded frames, ``.exr``/``.npy`` frames the linear ones.

Every file is written atomically through :func:`pywarp.core.output.atomic_path` (a hidden temporary file renamed
into place): a Ctrl-C leaves no partial file; frames already complete stay, the one being written never appears.
NaN or Inf pixels are refused (RuntimeError), as for the PNG writer.
"""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .output import IMAGE_SUFFIXES, atomic_path, check_output_dir, check_output_path, write_png

#: Suffixes of the linear outputs.
LINEAR_SUFFIXES = (".exr", ".npy")
#: Suffixes a numbered frame pattern may end in.
FRAME_SUFFIXES = IMAGE_SUFFIXES + LINEAR_SUFFIXES
#: Pixel types of the EXR writer.
EXR_PRECISIONS = ("half", "float")

_FIELD = re.compile(r"%(0?\d*)d")


def is_linear(path) -> bool:
    """True when ``path`` names a linear output (.exr, .npy)."""
    return Path(str(path)).suffix.lower() in LINEAR_SUFFIXES


def has_linear(technique) -> bool:
    """True when ``technique`` offers the linear-image hook (``render_linear``)."""
    return callable(getattr(technique, "render_linear", None))


def check_linear(technique, scene_name: str, option: str = "--out") -> None:
    """ValueError naming ``option`` when ``technique`` has no linear output (see the module docstring)."""
    if not has_linear(technique):
        raise ValueError(f"{option}: scene {scene_name!r} writes 8-bit images only, not the linear (.exr, .npy) "
                         f"image of a scene such as 'clouds'; use {' or '.join(IMAGE_SUFFIXES)}")


def render_linear(technique, pose=None, progress=None) -> np.ndarray:
    """One display-linear frame, float32 (height, width, 3), through the technique's hook."""
    check_linear(technique, type(technique).__name__)
    img = np.asarray(technique.render_linear(pose, progress=progress), dtype=np.float32)
    if img.ndim != 3 or img.shape[2] != 3:
        raise ValueError(f"render_linear must return (height, width, 3), got {img.shape}")
    return img


def _checked(rgb) -> np.ndarray:
    a = np.asarray(rgb)
    if a.ndim != 3 or a.shape[2] != 3:
        raise ValueError(f"image must have shape (height, width, 3), got {a.shape}")
    a = a.astype(np.float32, copy=False)
    bad = ~np.isfinite(a)
    if bad.any():
        ys, xs = np.nonzero(bad.any(axis=2))
        raise RuntimeError(f"the image holds {len(ys)} non-finite pixels (first at x={xs[0]}, y={ys[0]}); not written")
    return np.ascontiguousarray(a)


def write_npy(path, rgb) -> Path:
    """Write float32 (height, width, 3) linear RGB as a .npy file, atomically."""
    path = Path(path)
    a = _checked(rgb)
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as f:
            np.save(f, a, allow_pickle=False)
    return path


def write_exr(path, rgb, precision: str = "half") -> Path:
    """Write linear RGB as an OpenEXR file (channels R, G, B; ZIP; ``half`` or ``float`` pixels), atomically."""
    if precision not in EXR_PRECISIONS:
        raise ValueError(f"precision must be one of {', '.join(EXR_PRECISIONS)}, got {precision!r}")
    import OpenEXR

    path = Path(path)
    a = _checked(rgb)
    if precision == "half":
        big = np.abs(a) > np.finfo(np.float16).max
        if big.any():
            raise RuntimeError(f"{int(big.any(axis=2).sum())} pixels exceed the half-float range (65504); "
                               f"write float EXR instead")
        a = a.astype(np.float16)
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    with atomic_path(path) as tmp:
        with OpenEXR.File(header, {"RGB": a}) as f:
            f.write(str(tmp))
    return path


def read_exr(path) -> np.ndarray:
    """Read an RGB OpenEXR file as (height, width, 3) in its stored pixel type (float16 or float32)."""
    import OpenEXR

    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        if "RGB" in ch:
            return np.array(ch["RGB"].pixels)
        return np.stack([np.array(ch[c].pixels) for c in "RGB"], axis=-1)


def write_image(path, image, precision: str = "half") -> Path:
    """Write one image by suffix: .png (uint8, or float in [0, 1] display-encoded), .exr, .npy (linear float)."""
    suffix = Path(path).suffix.lower()
    if suffix == ".npy":
        return write_npy(path, image)
    if suffix == ".exr":
        return write_exr(path, image, precision)
    return write_png(path, image)


# --- numbered frames --------------------------------------------------------------------------------------------------

def is_frame_pattern(path) -> bool:
    """True when ``path`` holds a printf integer field (``frame_%04d.png``)."""
    return "%" in str(path)


class FramePattern:
    """A numbered-frame path such as ``frames/frame_%04d.exr``: exactly one ``%d`` / ``%0Nd`` field, a suffix of
    :data:`FRAME_SUFFIXES`; ``%%`` is a literal percent sign. :meth:`path` gives frame ``i``'s file."""

    def __init__(self, pattern, option: str = "--out"):
        self.text = str(pattern)
        self.option = option
        name = Path(self.text).name
        if "%" in str(Path(self.text).parent):
            raise ValueError(f"{option}: the frame number field must be in the file name, got {self.text!r}")
        fields = _FIELD.findall(name.replace("%%", ""))
        stray = _FIELD.sub("", name.replace("%%", ""))
        if len(fields) != 1 or "%" in stray:
            raise ValueError(f"{option} must hold one frame number field such as %04d (e.g. frames/frame_%04d.png), "
                             f"got {self.text!r}")
        self.suffix = Path(self.text).suffix.lower()
        if self.suffix not in FRAME_SUFFIXES:
            raise ValueError(f"{option}: numbered frames must end in {' or '.join(FRAME_SUFFIXES)}, "
                             f"got {self.text!r}")
        self.folder = Path(self.text).parent if str(Path(self.text).parent) else Path(".")

    @property
    def linear(self) -> bool:
        return self.suffix in LINEAR_SUFFIXES

    def path(self, i: int) -> Path:
        return self.folder / (Path(self.text).name % i)

    def check(self) -> "FramePattern":
        """Validate before any work: the folder writable, or creatable when missing (:meth:`make_folder` creates
        it). Returns self."""
        check_output_dir(self.folder, self.option)
        if self.folder.is_dir():
            check_output_path(self.path(0), FRAME_SUFFIXES, self.option)
        return self

    def make_folder(self) -> None:
        self.folder.mkdir(parents=True, exist_ok=True)

    def __str__(self) -> str:
        return self.text
