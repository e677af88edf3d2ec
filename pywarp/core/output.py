"""Writing images and videos safely: validated paths, no NaN image, no partial file.

Every writer renders into a hidden temporary file next to the target (``.<stem>.<random><suffix>.part``) and renames
it into place only when the whole image or video is complete (``os.replace`` is atomic on one file system). On any
exception -- an error, ``KeyboardInterrupt`` (Ctrl-C), or the exception the ``pywarp`` command raises on SIGTERM,
also when Python dropped that exception and only :func:`note_interrupt` kept it -- the temporary file is removed and the MP4 writer's ffmpeg process is killed, so no half-written PNG, GIF or MP4 and
no ``.part`` file is left behind. :func:`remove_temporaries` removes whatever a writer still holds (the command
calls it once more when it is interrupted).

Errors name the target path, and the command-line option that named it when it was checked with
:func:`check_output_path` (``--out: cannot write 'x.png': No space left on device``), never the temporary file.
"""
from __future__ import annotations

import errno
import os
import secrets
import shutil
import subprocess
import tempfile
from contextlib import contextmanager
from fractions import Fraction
from pathlib import Path

import numpy as np

IMAGE_SUFFIXES = (".png",)
VIDEO_SUFFIXES = (".mp4", ".gif")
TEMP_SUFFIX = ".part"

#: Temporary files a writer holds right now (removed by remove_temporaries()).
_LIVE: set[Path] = set()
#: The option that named each path checked by check_output_path (resolved path -> "--out"), for error messages.
_OPTION_OF: dict[str, str] = {}
#: Interrupts a signal handler raised (:func:`note_interrupt`). Python drops an exception raised while it runs a
#: ``__del__`` (a Warp array freed between two frames, say) after printing it, so a handler's exception can be lost;
#: while one is recorded here, no writer publishes a file or takes another frame (:func:`raise_pending`).
_PENDING: list[type] = []


def note_interrupt(exc_type: type) -> None:
    """Record that a signal handler is raising ``exc_type`` (KeyboardInterrupt or a subclass)."""
    _PENDING.append(exc_type)


def raise_pending() -> None:
    """Raise the first recorded interrupt again, if any (its first raise may have been dropped)."""
    if _PENDING:
        raise _PENDING[0]()


def clear_pending() -> None:
    """Forget the recorded interrupts (the command does, once it has handled one or finished)."""
    _PENDING.clear()


def _key(path: Path) -> str:
    return os.path.abspath(os.fspath(path))


def _prefix(path: Path) -> str:
    opt = _OPTION_OF.get(_key(path))
    return f"{opt}: " if opt else ""


def check_output_path(path, suffixes: tuple[str, ...], option: str = "--out") -> Path:
    """Validate an output path before any work is done; raise ValueError naming ``option``.

    Checks the suffix, that the folder exists and is a folder, that the path is not a folder, and that a file can
    really be created in the folder (a probe file is created and removed: this also catches read-only file systems
    and the superuser's permission bypass that ``os.access`` does not see). An existing target must be writable.
    """
    p = Path(path)
    if p.suffix.lower() not in suffixes:
        raise ValueError(f"{option} must end in {' or '.join(suffixes)}, got {str(path)!r}")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.exists():
        raise ValueError(f"{option}: folder {str(parent)!r} does not exist")
    if not parent.is_dir():
        raise ValueError(f"{option}: {str(parent)!r} is not a folder")
    if p.is_dir():
        raise ValueError(f"{option}: {str(path)!r} is a folder")
    if p.exists() and not os.access(p, os.W_OK):
        raise ValueError(f"{option}: {str(path)!r} is not writable")
    reason = _probe(parent)
    if reason:
        raise ValueError(f"{option}: cannot write in folder {str(parent)!r}: {reason}")
    _OPTION_OF[_key(p)] = option
    return p


def check_output_dir(path, option: str = "--out") -> Path:
    """Validate an output folder before any work: an existing folder must be writable; a missing one must be
    creatable (its nearest existing ancestor is a writable folder). Raise ValueError naming ``option``."""
    p = Path(path)
    if p.exists():
        if not p.is_dir():
            raise ValueError(f"{option}: {str(path)!r} is not a folder")
        reason = _probe(p)
        if reason:
            raise ValueError(f"{option}: cannot write in folder {str(path)!r}: {reason}")
        return p
    anc = p.absolute().parent
    while not anc.exists():
        anc = anc.parent
    if not anc.is_dir():
        raise ValueError(f"{option}: cannot create folder {str(path)!r}: {str(anc)!r} is not a folder")
    reason = _probe(anc)
    if reason:
        raise ValueError(f"{option}: cannot create folder {str(path)!r}: {reason}")
    return p


def _probe(folder: Path) -> str | None:
    """None when a file can be created in ``folder``, else the reason (e.g. 'Permission denied')."""
    try:
        tmp = _new_temp(folder / "probe.tmp")
    except OSError as exc:
        return exc.strerror or str(exc)
    _discard(tmp)
    return None


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


def _new_temp(path: Path) -> Path:
    """Create an empty hidden temporary file next to ``path`` (mode 0600) and register it in _LIVE *before* it
    exists, so that an interrupt at any point leaves nothing that remove_temporaries() does not know about."""
    folder = path.parent if str(path.parent) else Path(".")
    for _ in range(100):
        tmp = folder / f".{path.stem}.{secrets.token_hex(4)}{path.suffix}{TEMP_SUFFIX}"
        _LIVE.add(tmp)
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        except FileExistsError:
            _LIVE.discard(tmp)
            continue
        except BaseException:
            _LIVE.discard(tmp)
            raise
        os.close(fd)
        return tmp
    raise FileExistsError(errno.EEXIST, "no free temporary file name", str(folder))


def _discard(tmp: Path) -> None:
    try:
        tmp.unlink(missing_ok=True)
    except OSError:
        pass
    _LIVE.discard(tmp)


def remove_temporaries() -> list[Path]:
    """Remove every temporary file a writer still holds (after an interrupt); return the paths removed."""
    removed = []
    for tmp in list(_LIVE):
        if tmp.exists():
            removed.append(tmp)
        _discard(tmp)
    return removed


def _publish(tmp: Path, path: Path) -> None:
    """Give the finished temporary file the usual permissions (0666 minus the umask; the temporary file is 0600) and
    rename it into place atomically -- not while an interrupt is pending (:func:`raise_pending`)."""
    raise_pending()
    os.chmod(tmp, 0o666 & ~_umask())
    os.replace(tmp, path)
    _LIVE.discard(tmp)


def _disk_full(path: Path) -> bool:
    """Whether the file system of ``path`` has (almost) no space left: a short write reported without an errno
    (NumPy's "N requested and M written", ffmpeg's own messages) is then a full disk."""
    try:
        return shutil.disk_usage(path.parent if str(path.parent) else ".").free < 64 * 1024
    except OSError:
        return False


def _write_error(path: Path, exc: OSError) -> OSError:
    """An OSError about ``path`` (and its option), never about the temporary file."""
    reason = exc.strerror or str(exc).replace(TEMP_SUFFIX, "")
    if exc.errno == errno.ENOSPC or "No space left on device" in reason or _disk_full(path):
        return _oserror(errno.ENOSPC, f"{_prefix(path)}cannot write {str(path)!r}: disk full ({reason})")
    return _oserror(exc.errno, f"{_prefix(path)}cannot write {str(path)!r}: {reason}")


@contextmanager
def atomic_path(path):
    """``with atomic_path("x.npy") as tmp: write to tmp`` -- ``path`` appears only when the block succeeds; on any
    exception (Ctrl-C included) the temporary file is removed. OSErrors name ``path``, not the temporary file."""
    path = Path(path)
    try:
        tmp = _new_temp(path)
    except OSError as exc:
        raise _write_error(path, exc) from None
    try:
        try:
            yield tmp
            _publish(tmp, path)
        except OSError as exc:
            raise _write_error(path, exc) from None
    finally:
        _discard(tmp)


def write_png(path, rgb) -> Path:
    """Write an image atomically (see module docstring). ``rgb`` float in [0, 1] or uint8."""
    from PIL import Image

    path = Path(path)
    img = rgb if (isinstance(rgb, np.ndarray) and rgb.dtype == np.uint8) else to_uint8(rgb)
    with atomic_path(path) as tmp:
        Image.fromarray(img).save(tmp, format="PNG")
    return path


def _oserror(code: int | None, message: str) -> OSError:
    """An OSError whose str() is ``message`` alone (no "[Errno N]"), with errno ``code``."""
    exc = OSError(message)
    exc.errno = code  # (setting strerror too would make str() "[Errno N] message")
    return exc


class _FFmpeg:
    """An H.264 MP4 encoder: the ffmpeg binary of imageio-ffmpeg fed raw RGB frames on stdin.

    Run in its own session, so a Ctrl-C at the terminal reaches only Python (no ffmpeg message); ``kill()`` stops it
    at once (used on any exception), ``finish()`` waits for it to write the file."""

    def __init__(self, out: Path, width: int, height: int, fps: float):
        import imageio_ffmpeg

        fps_arg = str(Fraction(fps).limit_denominator())
        # the encoding imageio_ffmpeg.write_frames(codec="libx264", quality=8, pix_fmt_out="yuv420p") chooses
        cmd = [imageio_ffmpeg.get_ffmpeg_exe(), "-y", "-f", "rawvideo", "-vcodec", "rawvideo", "-s", f"{width}x{height}",
               "-pix_fmt", "rgb24", "-r", fps_arg, "-i", "-", "-an", "-vcodec", "libx264", "-pix_fmt", "yuv420p",
               "-crf", "10", "-v", "error", "-f", "mp4", str(out)]
        self._err = tempfile.TemporaryFile()  # anonymous: nothing to clean up
        self.proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=self._err,
                                     start_new_session=True)

    def _message(self) -> str:
        self._err.seek(0)
        lines = [ln.strip() for ln in self._err.read().decode(errors="replace").splitlines() if ln.strip()]
        return lines[-1].replace(TEMP_SUFFIX, "") if lines else f"ffmpeg exited with status {self.proc.returncode}"

    def send(self, frame: np.ndarray) -> None:
        try:
            self.proc.stdin.write(np.ascontiguousarray(frame).tobytes())
        except (BrokenPipeError, ValueError):
            self.proc.wait()
            raise _oserror(errno.EPIPE, f"ffmpeg stopped: {self._message()}") from None

    def finish(self) -> None:
        try:
            self.proc.stdin.close()
        except BrokenPipeError:
            pass
        if self.proc.wait() != 0:
            raise _oserror(errno.EIO, f"ffmpeg failed: {self._message()}")
        self._err.close()

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        try:
            self.proc.stdin.close()
        except OSError:
            pass
        self.proc.wait()
        self._err.close()


class VideoWriter:
    """Write frames to an MP4 (H.264 via the ffmpeg binary of imageio-ffmpeg) or a GIF (Pillow), atomically.

    Use as a context manager; the file appears only when the block finishes without an exception. On an exception
    (Ctrl-C included) the ffmpeg process is killed and the temporary file removed.
    """

    def __init__(self, path, fps: float = 24.0):
        self.path = Path(path)
        if self.path.suffix.lower() not in VIDEO_SUFFIXES:
            raise ValueError(f"video path must end in .mp4 or .gif, got {str(path)!r}")
        if not (0.01 <= fps <= 240):  # GIF frame delays end at 655.35 s; see the --fps spec of pywarp animate
            raise ValueError(f"fps must be in [0.01, 240], got {fps}")
        self.fps = float(fps)
        self._tmp: Path | None = None
        self._frames: list[np.ndarray] = []
        self._enc: _FFmpeg | None = None
        self.count = 0

    def __enter__(self):
        try:
            self._tmp = _new_temp(self.path)
        except OSError as exc:
            raise _write_error(self.path, exc) from None
        return self

    def add(self, rgb) -> None:
        if self._tmp is None:
            raise RuntimeError("VideoWriter.add() outside its with block")
        raise_pending()  # an interrupt whose first raise was dropped: no further frame
        img = rgb if (isinstance(rgb, np.ndarray) and rgb.dtype == np.uint8) else to_uint8(rgb)
        if self.path.suffix.lower() == ".gif":
            self._frames.append(img)
        else:
            h, w = img.shape[:2]
            if self._enc is None:
                if w % 2 or h % 2:
                    raise ValueError(f"MP4 (H.264, yuv420p) needs an even width and height, got {w}x{h}")
                try:
                    self._enc = _FFmpeg(self._tmp, w, h, self.fps)
                except OSError as exc:
                    raise _write_error(self.path, exc) from None
                self._size = (w, h)
            elif (w, h) != self._size:
                raise ValueError(f"every frame must be {self._size[0]}x{self._size[1]}, got {w}x{h}")
            try:
                self._enc.send(img)
            except OSError as exc:
                raise _write_error(self.path, exc) from None
        self.count += 1

    def __exit__(self, exc_type, exc, tb):
        tmp, enc = self._tmp, self._enc
        self._tmp, self._enc = None, None
        try:
            if exc_type is not None:
                if enc is not None:
                    enc.kill()
                return False
            if self.count == 0:
                if enc is not None:
                    enc.kill()
                raise ValueError("no frames were written")
            try:
                if enc is not None:
                    enc.finish()
                if self._frames:
                    from PIL import Image

                    frames = [Image.fromarray(f) for f in self._frames]
                    frames[0].save(tmp, format="GIF", save_all=True, append_images=frames[1:],
                                   duration=int(round(1000 / self.fps)), loop=0)
                _publish(tmp, self.path)
            except OSError as exc:
                raise _write_error(self.path, exc) from None
        except BaseException:
            if enc is not None and enc.proc.poll() is None:
                enc.kill()
            raise
        finally:
            if tmp is not None:
                _discard(tmp)
        return False
