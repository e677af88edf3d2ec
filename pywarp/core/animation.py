"""Rendering a camera path of a scene into a video or numbered frames (``pywarp animate``).

:func:`open_sink` chooses the writer from the output path: an ``.mp4``/``.gif`` video
(:class:`pywarp.core.output.VideoWriter`) or numbered frames (``frames/frame_%04d.png``, ``.exr`` or ``.npy``;
:class:`pywarp.core.linear.FramePattern`). :func:`frame_times` and :func:`render_frames` are the frame loop: the
scene's technique, the time field advanced per frame, one pose per frame.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from . import linear as L
from .output import VIDEO_SUFFIXES, VideoWriter, check_output_path


class FramesWriter:
    """Numbered frame files (see :class:`pywarp.core.linear.FramePattern`), each written atomically; a context
    manager like :class:`VideoWriter`. On an exception the frame being written never appears (the files of finished
    frames stay)."""

    def __init__(self, pattern: L.FramePattern, precision: str = "half"):
        self.pattern = pattern
        self.precision = precision
        self.count = 0
        self.paths: list[Path] = []

    @property
    def linear(self) -> bool:
        return self.pattern.linear

    def __enter__(self):
        self.pattern.make_folder()
        return self

    def add(self, image, index: int | None = None) -> None:
        i = self.count if index is None else index
        self.paths.append(L.write_image(self.pattern.path(i), image, self.precision))
        self.count += 1

    def __exit__(self, exc_type, exc, tb):
        return False


class _Video:
    """VideoWriter with the sink interface (encoded uint8 frames)."""

    linear = False

    def __init__(self, path: Path, fps: float):
        self.writer = VideoWriter(path, fps=fps)

    @property
    def count(self) -> int:
        return self.writer.count

    def __enter__(self):
        self.writer.__enter__()
        return self

    def add(self, image, index: int | None = None) -> None:
        self.writer.add(image)

    def __exit__(self, exc_type, exc, tb):
        return self.writer.__exit__(exc_type, exc, tb)


def open_sink(out, fps: float, precision: str = "half", option: str = "--out"):
    """The writer for ``out``, validated before any work (ValueError naming ``option``): a video (.mp4, .gif) or
    numbered frames (a path with ``%04d``: .png, .exr, .npy)."""
    if precision not in L.EXR_PRECISIONS:
        raise ValueError(f"--exr-precision must be one of {', '.join(L.EXR_PRECISIONS)}, got {precision!r}")
    if L.is_frame_pattern(out):
        return FramesWriter(L.FramePattern(out, option).check(), precision)
    if Path(str(out)).suffix.lower() in L.FRAME_SUFFIXES:
        raise ValueError(f"{option}: frames need a numbered path such as frames/frame_%04d"
                         f"{Path(str(out)).suffix.lower()}, got {str(out)!r}")
    return _Video(check_output_path(out, VIDEO_SUFFIXES, option), fps)


def frame_times(settings, time_field: str | None, frames: int, fps: float, time_scale: float) -> list[float | None]:
    """The scene time of every frame (None for a static scene): the settings' time plus i / fps * time_scale."""
    if not time_field:
        return [None] * frames
    t0 = getattr(settings, time_field)
    return [t0 + i / fps * time_scale for i in range(frames)]


def render_frames(tech, poses, times, time_field: str | None, linear: bool, start: int = 0):
    """Yield (index, image) for frames ``start, start+1, ...`` of ``poses``/``times`` rendered in order with ``tech``:
    uint8 frames, or display-linear float32 ones when ``linear`` (the technique's ``render_linear`` hook)."""
    for k, pose in enumerate(poses):
        if time_field:
            tech.update(**{time_field: times[k]})
        img = L.render_linear(tech, pose) if linear else tech.render(pose)
        yield start + k, img


def frames_equal(a: np.ndarray, b: np.ndarray) -> bool:
    """Bit-identical frames (same shape, dtype and bytes; NaN patterns included)."""
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()
