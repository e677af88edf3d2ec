"""Writing images and videos safely: validated paths, no NaN image, no partial file.

Every writer renders into a temporary file next to the target and renames it into place only when the whole image
or video is complete (``os.replace`` is atomic on one file system), so an error or Ctrl-C never leaves a half-written
PNG, GIF or MP4 behind.
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

IMAGE_SUFFIXES = (".png",)
VIDEO_SUFFIXES = (".mp4", ".gif")


def check_output_path(path, suffixes: tuple[str, ...], option: str = "--out") -> Path:
    """Validate an output path before any work is done; raise ValueError naming ``option``."""
    p = Path(path)
    if p.suffix.lower() not in suffixes:
        raise ValueError(f"{option} must end in {' or '.join(suffixes)}, got {str(path)!r}")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise ValueError(f"{option}: folder {str(parent)!r} does not exist")
    if p.is_dir():
        raise ValueError(f"{option}: {str(path)!r} is a folder")
    if not os.access(parent, os.W_OK) or (p.exists() and not os.access(p, os.W_OK)):
        raise ValueError(f"{option}: {str(path)!r} is not writable")
    return p


def to_uint8(rgb) -> np.ndarray:
    """Display-referred float RGB in [0, 1] (already tone mapped and sRGB encoded) -> uint8.

    Raises RuntimeError when the image holds NaN or Inf: such an image is never written.
    """
    a = np.asarray(rgb, dtype=np.float32)
    if a.ndim != 3 or a.shape[2] not in (3, 4):
        raise ValueError(f"image must have shape (height, width, 3 or 4), got {a.shape}")
    bad = ~np.isfinite(a)
    if bad.any():
        ys, xs = np.nonzero(bad.any(axis=2))
        raise RuntimeError(f"the image holds {len(ys)} non-finite pixels (first at x={xs[0]}, y={ys[0]}); not written")
    return (np.clip(a[..., :3], 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _publish(tmp: Path, path: Path) -> None:
    """Give the finished temporary file the usual permissions (0666 minus the umask; mkstemp makes it 0600) and
    rename it into place atomically."""
    os.chmod(tmp, 0o666 & ~_umask())
    os.replace(tmp, path)


def _temp_next_to(path: Path) -> Path:
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=path.suffix + ".part", dir=path.parent or ".")
    os.close(fd)
    return Path(tmp)


def write_png(path, rgb) -> Path:
    """Write an image atomically (see module docstring). ``rgb`` float in [0, 1] or uint8."""
    from PIL import Image

    path = Path(path)
    img = rgb if (isinstance(rgb, np.ndarray) and rgb.dtype == np.uint8) else to_uint8(rgb)
    tmp = _temp_next_to(path)
    try:
        Image.fromarray(img).save(tmp, format="PNG")
        _publish(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


class VideoWriter:
    """Write frames to an MP4 (H.264 via the ffmpeg binary of imageio-ffmpeg) or a GIF (Pillow), atomically.

    Use as a context manager; the file appears only when the block finishes without an exception.
    """

    def __init__(self, path, fps: float = 24.0):
        self.path = Path(path)
        if self.path.suffix.lower() not in VIDEO_SUFFIXES:
            raise ValueError(f"video path must end in .mp4 or .gif, got {str(path)!r}")
        if not (0 < fps <= 240):
            raise ValueError(f"fps must be in (0, 240], got {fps}")
        self.fps = float(fps)
        self._tmp = None
        self._frames = []
        self._gen = None
        self.count = 0

    def __enter__(self):
        self._tmp = _temp_next_to(self.path)
        return self

    def add(self, rgb) -> None:
        img = rgb if (isinstance(rgb, np.ndarray) and rgb.dtype == np.uint8) else to_uint8(rgb)
        if self.path.suffix.lower() == ".gif":
            self._frames.append(img)
        else:
            if self._gen is None:
                import imageio_ffmpeg

                h, w = img.shape[:2]
                if w % 2 or h % 2:
                    raise ValueError(f"MP4 (H.264, yuv420p) needs an even width and height, got {w}x{h}")
                self._gen = imageio_ffmpeg.write_frames(str(self._tmp), (w, h), fps=self.fps, codec="libx264",
                                                        pix_fmt_out="yuv420p", quality=8, macro_block_size=1,
                                                        output_params=["-f", "mp4"])
                self._gen.send(None)
            self._gen.send(np.ascontiguousarray(img))
        self.count += 1

    def __exit__(self, exc_type, exc, tb):
        try:
            if self._gen is not None:
                self._gen.close()
            if exc_type is None:
                if self.count == 0:
                    raise ValueError("no frames were written")
                if self._frames:
                    from PIL import Image

                    frames = [Image.fromarray(f) for f in self._frames]
                    frames[0].save(self._tmp, format="GIF", save_all=True, append_images=frames[1:],
                                   duration=int(round(1000 / self.fps)), loop=0)
                _publish(Path(self._tmp), self.path)
        finally:
            if self._tmp is not None:
                Path(self._tmp).unlink(missing_ok=True)
        return False
