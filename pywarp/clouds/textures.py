"""The noise-texture generator of the cloudscape (vc §2.3.3, §4.3.1): settings, generators, cache, weather maps.

Four textures feed the cloud density (spec vc-A9 .. vc-A12):

=================  =====================================  ==============================================================
texture            array (float32, values)                content
=================  =====================================  ==============================================================
base shape         (n, n, n, 4) [z, y, x, c], [0, 1]      R Perlin-Worley (vc-A8), G/B/A inverse-Worley fBm (freq. up)
detail shape       (n, n, n, 3) [z, y, x, c], [0, 1]      R/G/B inverse-Worley fBm of rising frequency
curl noise         (n, n, 2) [y, x, c], signed            2-D curl of Perlin noise (divergence-free), lattice units
weather map        (n, n, 4) [y, x, c], [0, 1]            R coverage, G precipitation, B cloud type, A free (0)
=================  =====================================  ==============================================================

Class design (vc-A32): :class:`TextureGenerator` is the interface (``base_shape``, ``detail_shape``, ``curl_noise``,
``weather_map``); :class:`BasicTextureGenerator` implements it with the Warp kernels (tile-parallel) or the C library,
and a cache; write your own subclass to feed the renderer other textures (:class:`CloudTextures` checks them).
Settings (vc-A13) are frozen dataclasses with parameter specs (:mod:`pywarp.clouds.settings`): every default is
documented with its reason (the thesis gives none); invalid fields raise ``ValueError`` (``TypeError`` for a wrong
type) naming the field.

The readings chosen for what the thesis leaves open are in ``cclouds/texgen.h`` and :mod:`pywarp.kernels.texgen`.

Caching: every generated texture is kept in memory (per settings, implementation and device) and on disk in the user
cache directory -- ``$PYWARP_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/pywarp``, else ``~/.cache/pywarp`` -- under
``textures/``, keyed by a hash of the settings, the implementation, the package version and the texture format
version. Files are written to a temporary file and moved into place with ``os.replace`` (an interrupted run never
leaves a partial entry); each file carries the SHA-256 of its payload, and an entry that fails the check (truncated,
overwritten, wrong shape) is regenerated with a :class:`TextureCacheWarning`.

Size cap: the disk level holds at most ``$PYWARP_CACHE_MAX_SIZE`` (bytes, or with a K/M/G/T suffix: ``500M``, ``4G``;
``0`` keeps nothing on disk; ``unlimited`` no cap), default :data:`DEFAULT_MAX_DISK_BYTES` (2 GiB, reason there).
After each write the least recently used entries go first (a read marks an entry used by touching its modification
time), so entries made stale by a new package version or generator change, never read again, are evicted first.
``pywarp cache info`` shows the folder, the entries and the cap; ``pywarp cache clear`` removes them.

Example::

    from pywarp.clouds.textures import BasicTextureGenerator, BaseShapeSettings
    gen = BasicTextureGenerator()                      # Warp on the CPU, all cores, cached
    base = gen.base_shape(BaseShapeSettings(seed=3))   # (128, 128, 128, 4) float32, read-only
    tex = gen.textures()                               # the four textures, checked (CloudTextures)
"""
from __future__ import annotations

import abc
import hashlib
from functools import lru_cache
import io
import json
import os
import threading
import warnings
from collections import OrderedDict
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import Callable

import numpy as np

from ..kernels.texgen import MAX_SIZE_2D, MIN_SIZE  # cclouds/texgen.h limits
from . import texgen as _texgen  # the whole-texture generation (Warp tile kernels, C)

#: Version of the generated data's definition; bump it whenever a texture's content changes for the same settings.
FORMAT_VERSION = 1
_MAGIC = b"PWTEX01\n"  # 8 bytes, then the 32-byte SHA-256 of the payload, then the payload (.npy)



class TextureCacheWarning(UserWarning):
    """A cache entry was unreadable or corrupt (it is regenerated) or the cache directory is not writable."""


#: Longest curl vector a curl texture may hold (CCL_CLOUDSCAPE_MAX_CURL: ccl_cloudscape_check bounds the detail
#: lookup's displacement with it; generated curl noise stays below 2.5 lattice units).
MAX_CURL = 16.0


def texture_problem(kind: str, arr: np.ndarray) -> str | None:
    """Why ``arr`` is not a valid ``kind`` texture (None when it is): every value finite; base, detail and weather
    values in [0, 1]; curl components within +-MAX_CURL. Checked on every texture generated and every cache entry
    read, so a texture with NaN or out-of-range values is never cached nor rendered."""
    bad = ~np.isfinite(arr)
    if bad.any():
        return f"{int(np.count_nonzero(bad))} non-finite values"
    lo, hi = (-MAX_CURL, MAX_CURL) if kind == "curl_noise" else (0.0, 1.0)
    if arr.size and (arr.min() < lo or arr.max() > hi):
        return f"values in [{arr.min():g}, {arr.max():g}], outside [{lo:g}, {hi:g}]"
    return None


# --- settings (vc-A13): declared once, with their parameter specs, in pywarp.clouds.settings ----------------------

from .settings import (  # noqa: E402  (re-exported: pywarp.clouds.textures.BaseShapeSettings etc.)
    BaseShapeSettings,
    CurlNoiseSettings,
    DetailShapeSettings,
    WeatherMapSettings,
)

SETTINGS = {"base_shape": BaseShapeSettings, "detail_shape": DetailShapeSettings, "curl_noise": CurlNoiseSettings,
            "weather_map": WeatherMapSettings}


def _check_kind(kind) -> type:
    if kind not in SETTINGS:
        raise ValueError(f"kind must be one of {', '.join(map(repr, SETTINGS))}, got {kind!r}")
    return SETTINGS[kind]


def _check_impl(impl) -> str:
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return impl


# --- C structs ------------------------------------------------------------------------------------------------------

def _c_struct(kind: str, values: dict):
    """A cffi ``ccl_<kind>_settings *`` holding ``values`` (see :func:`pywarp.clouds.texgen.settings_struct`)."""
    return _texgen.settings_struct(kind, values)


def texture_settings(kind: str = "base_shape", impl: str = "warp", **fields_):
    """The validated settings dataclass of ``kind`` (vc-A13) with ``fields_`` overriding the defaults.

    ``impl="warp"``: validated in Python (what the Warp generator uses); ``impl="c"``: validated by
    ``ccl_texgen_<kind>_settings_check`` first (the C generator's validation), which names the first invalid field."""
    cls = _check_kind(kind)
    _check_impl(impl)
    if impl == "c":
        from ..core.binding import ffi, lib

        known = {fl.name for fl in fields(cls)}
        unknown = set(fields_) - known
        if unknown:
            raise TypeError(f"{cls.__name__} has no field {sorted(unknown)[0]!r}")
        values = {**asdict(cls()), **fields_}
        st = _c_struct(kind, values)
        out = ffi().new("const char **")
        status = getattr(lib(), f"ccl_texgen_{kind}_settings_check")(st, out)
        if status != 0:
            name = ffi().string(out[0]).decode()
            raise ValueError(f"{name} is invalid (ccl_texgen_{kind}_settings_check), got {values.get(name)!r}")
    return cls(**fields_)


# --- generation -----------------------------------------------------------------------------------------------------

def generate(kind: str, settings=None, impl: str = "warp", device: str | None = None, launcher=None) -> np.ndarray:
    """Generate one texture without caching: a new float32 array of ``settings.shape``.

    ``impl="warp"``: the Warp kernels of :mod:`pywarp.kernels.texgen` launched through ``launcher`` (a
    :class:`pywarp.core.runtime.TileLauncher`; default the process-wide one of ``device``: row bands on every core).
    ``impl="c"``: ``ccl_texgen_<kind>`` of the C library, one thread."""
    cls = _check_kind(kind)
    _check_impl(impl)
    settings = cls() if settings is None else settings
    if not isinstance(settings, cls):
        raise TypeError(f"settings must be a {cls.__name__} for kind {kind!r}, got {type(settings).__name__}")
    return _texgen.generate(kind, settings, impl=impl, device=device, launcher=launcher)


# --- cache ----------------------------------------------------------------------------------------------------------

def cache_dir() -> Path:
    """The user cache directory of pywarp: $PYWARP_CACHE_DIR, else $XDG_CACHE_HOME/pywarp, else ~/.cache/pywarp."""
    env = os.environ.get("PYWARP_CACHE_DIR")
    if env:
        return Path(env)
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg else Path.home() / ".cache") / "pywarp"


#: Default cap of the disk cache: 2 GiB. Reason: the default texture set takes 33 MiB (the 128^3 base shape 32 MiB),
#: so 2 GiB holds ~60 sets, or 7 with a 256^3 base shape; this project's development cache after every figure and
#: scene had been generated many times over held 679 MiB in 346 entries, so a normal user never sees an eviction,
#: while the cache no longer grows without bound with the entries that version and generator changes leave behind.
DEFAULT_MAX_DISK_BYTES = 2 * 2 ** 30
MAX_SIZE_ENV = "PYWARP_CACHE_MAX_SIZE"
_SIZE_UNITS = {"": 1, "B": 1, "K": 2 ** 10, "M": 2 ** 20, "G": 2 ** 30, "T": 2 ** 40}


def parse_size(text: str, name: str = MAX_SIZE_ENV) -> int | None:
    """``"2G"`` -> 2147483648 (binary units K, M, G, T, optional trailing ``B`` / ``iB``); ``unlimited``/``none`` ->
    None (no cap). ValueError naming ``name`` otherwise."""
    import re

    t = str(text).strip()
    if t.lower() in ("unlimited", "none"):
        return None
    m = re.fullmatch(r"(\d+(?:\.\d+)?)\s*([KMGT]?)(?:I?B)?", t.upper())
    if not m:
        raise ValueError(f"{name} must be a size in bytes (e.g. 2147483648, 500M, 4G) or 'unlimited', got {text!r}")
    return int(float(m[1]) * _SIZE_UNITS[m[2]])


def max_disk_bytes() -> int | None:
    """The disk cap: $PYWARP_CACHE_MAX_SIZE parsed (None: unlimited), else :data:`DEFAULT_MAX_DISK_BYTES`."""
    env = os.environ.get(MAX_SIZE_ENV)
    return DEFAULT_MAX_DISK_BYTES if env is None or not env.strip() else parse_size(env)


def _package_version() -> str:
    from .. import __version__

    return __version__


@lru_cache(maxsize=1)
def _code_hash() -> str:
    """Hash of the generator's sources (Warp modules and C headers), so that a changed generator never reads
    textures cached by an older one even within one package version (a development install)."""
    root = Path(__file__).resolve().parents[1]  # the pywarp package folder
    h = hashlib.sha256()
    for rel in ("kernels/texgen.py", "clouds/texgen.py", "kernels/noise.py", "kernels/interp.py", "kernels/hash.py",
                "include/cclouds/texgen.h", "include/cclouds/noise.h", "include/cclouds/interp.h",
                "include/cclouds/hash.h"):
        f = root / rel
        if f.is_file():
            h.update(f.read_bytes())
    return h.hexdigest()[:16]


class TextureCache:
    """In-memory (LRU, bounded in bytes) and on-disk cache of generated textures.

    Parameters
    ----------
    directory : path, optional
        Root of the disk cache (entries go to ``<directory>/textures``); default :func:`cache_dir` at each use, so
        the environment variables are honoured when they change.
    memory, disk : bool
        Enable the two levels.
    max_memory_bytes : int
        Memory budget of the in-memory level (least recently used entries are dropped first). Default 512 MiB:
        the default base texture is 32 MiB.
    max_disk_bytes : int, optional
        Cap of the disk level (least recently used entries are removed after each write); default
        :func:`max_disk_bytes` at each use ($PYWARP_CACHE_MAX_SIZE, else :data:`DEFAULT_MAX_DISK_BYTES`).
    """

    def __init__(self, directory: str | os.PathLike | None = None, memory: bool = True, disk: bool = True,
                 max_memory_bytes: int = 512 * 2 ** 20, max_disk_bytes: int | None = None):
        self._directory = None if directory is None else Path(directory)
        self.memory = bool(memory)
        self.disk = bool(disk)
        self.max_memory_bytes = int(max_memory_bytes)
        if max_disk_bytes is not None and int(max_disk_bytes) < 0:
            raise ValueError(f"max_disk_bytes must be >= 0, got {max_disk_bytes}")
        self._max_disk_bytes = None if max_disk_bytes is None else int(max_disk_bytes)
        self._mem: OrderedDict[str, np.ndarray] = OrderedDict()
        self._lock = threading.RLock()
        self.stats = {"memory_hits": 0, "disk_hits": 0, "misses": 0, "corrupt": 0}
        self.evicted = 0  # disk entries this cache removed to stay under the cap

    @property
    def directory(self) -> Path:
        return (self._directory if self._directory is not None else cache_dir()) / "textures"

    @staticmethod
    def key(kind: str, settings, impl: str, device: str) -> str:
        """Hash of everything that determines the data: kind, settings, implementation, device type, package
        version, format version."""
        desc = {"kind": kind, "settings": asdict(settings), "impl": impl, "device": device.split(":")[0],
                "version": _package_version(), "format": FORMAT_VERSION, "code": _code_hash()}
        return hashlib.sha256(json.dumps(desc, sort_keys=True).encode()).hexdigest()[:40]

    def path(self, kind: str, key: str) -> Path:
        return self.directory / f"{kind}-{key}.pwtex"

    def get(self, kind: str, settings, impl: str, device: str, make: Callable[[], np.ndarray]) -> np.ndarray:
        """The cached texture, or ``make()`` stored in both levels. Returned arrays are read-only."""
        key = self.key(kind, settings, impl, device)
        if self.disk:
            self.max_disk_bytes  # noqa: B018 - a malformed $PYWARP_CACHE_MAX_SIZE raises before any work
        with self._lock:
            if self.memory and key in self._mem:
                self._mem.move_to_end(key)
                self.stats["memory_hits"] += 1
                return self._mem[key]
            arr = self._read(kind, key, settings.shape) if self.disk else None
            if arr is not None:
                self.stats["disk_hits"] += 1
            else:
                self.stats["misses"] += 1
                arr = np.ascontiguousarray(make(), dtype=np.float32)
                if arr.shape != tuple(settings.shape):
                    raise RuntimeError(f"generated {kind} has shape {arr.shape}, expected {settings.shape}")
                problem = texture_problem(kind, arr)
                if problem:  # never cached, never rendered
                    raise RuntimeError(f"the generated {kind} texture is invalid ({problem}) for {settings!r}")
                if self.disk:
                    self._write(kind, key, arr)
            arr.setflags(write=False)
            if self.memory:
                self._remember(key, arr)
            return arr

    def _remember(self, key: str, arr: np.ndarray) -> None:
        self._mem[key] = arr
        total = sum(a.nbytes for a in self._mem.values())
        while total > self.max_memory_bytes and len(self._mem) > 1:
            _, old = self._mem.popitem(last=False)
            total -= old.nbytes

    def clear_memory(self) -> None:
        with self._lock:
            self._mem.clear()

    @staticmethod
    def _read_regular(path: Path, limit: int) -> bytes:
        """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes. Opened non-blocking, so that a
        FIFO (or a link to one) does not hang the reader, and checked with fstat before reading, so that a device
        (/dev/zero, a terminal) is never read; both raise OSError."""
        import stat

        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
        try:
            st = os.fstat(fd)
            if not stat.S_ISREG(st.st_mode):
                raise OSError(f"not a regular file (mode {stat.filemode(st.st_mode)})")
            if st.st_size > limit:
                raise OSError(f"{st.st_size} bytes, more than the {limit} an entry of this shape takes")
            chunks, left = [], limit + 1
            while left > 0:
                chunk = os.read(fd, min(left, 1 << 24))
                if not chunk:
                    break
                chunks.append(chunk)
                left -= len(chunk)
            return b"".join(chunks)
        finally:
            os.close(fd)

    def _read(self, kind: str, key: str, shape: tuple) -> np.ndarray | None:
        path = self.path(kind, key)
        # header + digest + .npy header (< 4 KiB) + the float32 data
        limit = len(_MAGIC) + 32 + 4096 + 4 * int(np.prod(shape))
        try:
            data = self._read_regular(path, limit)
        except FileNotFoundError:
            return None
        except OSError as exc:
            self.stats["corrupt"] += 1
            warnings.warn(f"texture cache entry {path} is unreadable ({exc.strerror or exc}); regenerating",
                          TextureCacheWarning, stacklevel=4)
            return None
        reason = None
        if len(data) < len(_MAGIC) + 32 or data[:len(_MAGIC)] != _MAGIC:
            reason = "bad header"
        else:
            digest, payload = data[len(_MAGIC):len(_MAGIC) + 32], data[len(_MAGIC) + 32:]
            if hashlib.sha256(payload).digest() != digest:
                reason = "checksum mismatch"
            else:
                try:
                    arr = np.load(io.BytesIO(payload), allow_pickle=False)
                except Exception as exc:  # a malformed .npy payload with a matching hash: treat as corrupt
                    reason = f"unreadable payload: {exc}"
                else:
                    if arr.dtype != np.float32 or arr.shape != tuple(shape):
                        reason = f"shape {arr.shape} / dtype {arr.dtype}, expected {tuple(shape)} float32"
                    else:
                        # a valid hash says only that the file is what was written: check the values too
                        reason = texture_problem(kind, arr)
                        if reason is None:
                            self._touch(path)
                            return np.ascontiguousarray(arr)
        self.stats["corrupt"] += 1
        warnings.warn(f"corrupt texture cache entry {path} ({reason}); regenerating", TextureCacheWarning,
                      stacklevel=4)
        return None

    def _write(self, kind: str, key: str, arr: np.ndarray) -> None:
        from ..core.output import atomic_path

        if self.max_disk_bytes == 0:  # $PYWARP_CACHE_MAX_SIZE=0: nothing kept on disk
            return
        path = self.path(kind, key)
        buf = io.BytesIO()
        np.save(buf, arr, allow_pickle=False)
        payload = buf.getvalue()
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            # a registered temporary of pywarp.core.output: removed on any exception, Ctrl-C and SIGTERM included
            # (and by remove_temporaries()), renamed into place atomically only when complete
            with atomic_path(path) as tmp:
                with open(tmp, "wb") as fh:
                    fh.write(_MAGIC)
                    fh.write(hashlib.sha256(payload).digest())
                    fh.write(payload)
                    fh.flush()
                    os.fsync(fh.fileno())
        except OSError as exc:
            warnings.warn(f"could not write the texture cache entry {path} ({exc}); continuing without it",
                          TextureCacheWarning, stacklevel=4)
            return
        self.evict()

    # --- size cap (least recently used first) -------------------------------------------------------------------

    @property
    def max_disk_bytes(self) -> int | None:
        """The disk cap in bytes (None: unlimited): the constructor's, else :func:`max_disk_bytes` now."""
        return self._max_disk_bytes if self._max_disk_bytes is not None else max_disk_bytes()

    @staticmethod
    def _touch(path: Path) -> None:
        try:  # the modification time is the "last used" mark of the LRU eviction (access times are often off)
            os.utime(path)
        except OSError:
            pass

    def entries(self) -> list[dict]:
        """The disk entries, least recently used first: ``path``, ``kind``, ``bytes``, ``used`` (mtime, s)."""
        rows = []
        try:
            it = list(os.scandir(self.directory))
        except (FileNotFoundError, NotADirectoryError):
            return rows
        for e in it:
            if e.name.startswith(".") or not e.name.endswith(".pwtex"):
                continue
            try:
                st = e.stat(follow_symlinks=False)
            except FileNotFoundError:  # removed meanwhile by another process
                continue
            rows.append({"path": Path(e.path), "kind": e.name.rsplit("-", 1)[0], "bytes": st.st_size,
                         "used": st.st_mtime})
        rows.sort(key=lambda r: (r["used"], r["path"].name))
        return rows

    def evict(self, limit: int | None = -1) -> tuple[int, int]:
        """Remove the least recently used disk entries until they take at most ``limit`` bytes (default: the cap;
        None: nothing removed). Returns (entries removed, bytes freed)."""
        limit = self.max_disk_bytes if limit == -1 else limit
        if limit is None:
            return 0, 0
        rows = self.entries()
        total = sum(r["bytes"] for r in rows)
        removed = freed = 0
        for r in rows:
            if total <= limit:
                break
            try:
                r["path"].unlink()
            except FileNotFoundError:
                pass
            except OSError:
                continue
            total -= r["bytes"]
            removed += 1
            freed += r["bytes"]
        self.evicted += removed
        return removed, freed

    def clear_disk(self) -> tuple[int, int]:
        """Remove every disk entry, and temporaries an interrupted writer left more than an hour ago. Returns
        (entries removed, bytes freed)."""
        import time

        removed, freed = self.evict(0)
        try:
            stale = [e for e in os.scandir(self.directory) if e.name.startswith(".") and ".pwtex" in e.name]
        except (FileNotFoundError, NotADirectoryError):
            stale = []
        for e in stale:
            try:
                st = e.stat(follow_symlinks=False)
                if time.time() - st.st_mtime > 3600:
                    os.unlink(e.path)
                    freed += st.st_size
            except OSError:
                pass
        return removed, freed


_default_cache: TextureCache | None = None
_default_lock = threading.Lock()


def default_cache() -> TextureCache:
    """The process-wide cache used by :class:`BasicTextureGenerator` unless told otherwise."""
    global _default_cache
    with _default_lock:
        if _default_cache is None:
            _default_cache = TextureCache()
        return _default_cache


# --- weather maps ---------------------------------------------------------------------------------------------------

def _is_pow2(n: int) -> bool:
    return n > 0 and n & (n - 1) == 0


@dataclass(frozen=True, eq=False)
class WeatherMap:
    """A weather map (vc-A12): float32 (height, width, 4) in [0, 1], row = y, column = x;
    R coverage, G precipitation, B cloud type (0 stratus, 0.5 stratocumulus, 1 cumulus), A free.
    Width and height are powers of two in [4, 8192] (the renderer wraps with a bit mask)."""

    data: np.ndarray

    def __post_init__(self):
        a = np.asarray(self.data)
        if a.ndim != 3 or a.shape[2] != 4:
            raise ValueError(f"data must have shape (height, width, 4), got {a.shape}")
        h, w = a.shape[:2]
        if not (_is_pow2(h) and _is_pow2(w) and MIN_SIZE <= min(h, w) and max(h, w) <= MAX_SIZE_2D):
            raise ValueError(f"size must be powers of two in [{MIN_SIZE}, {MAX_SIZE_2D}], got {w}x{h}")
        a = np.ascontiguousarray(a, dtype=np.float32)
        if not np.all(np.isfinite(a)) or a.min() < 0.0 or a.max() > 1.0:
            raise ValueError("data must hold finite values in [0, 1]")
        a.setflags(write=False)
        object.__setattr__(self, "data", a)

    @property
    def coverage(self) -> np.ndarray:
        return self.data[..., 0]

    @property
    def precipitation(self) -> np.ndarray:
        return self.data[..., 1]

    @property
    def cloud_type(self) -> np.ndarray:
        return self.data[..., 2]

    @classmethod
    def generate(cls, settings: WeatherMapSettings | None = None,
                 generator: TextureGenerator | None = None) -> WeatherMap:
        """A procedural weather map from ``generator`` (default a :class:`BasicTextureGenerator`)."""
        gen = generator if generator is not None else BasicTextureGenerator()
        return cls(gen.weather_map(settings))

    @classmethod
    def from_image(cls, path: str | os.PathLike) -> WeatherMap:
        """Load an 8-bit RGB or RGBA image (PNG, ...) with Pillow: R coverage, G precipitation, B cloud type
        (A, when present, is kept; RGB images get A = 0), scaled by 1/255. Row 0 of the image is y = 0.

        Raises FileNotFoundError for a missing file, ValueError for a file Pillow cannot read, an image mode other
        than 'RGB'/'RGBA' or a size that is not a power of two in [4, 8192] on both axes."""
        from PIL import Image, UnidentifiedImageError

        p = Path(path)
        if not p.is_file():
            raise FileNotFoundError(f"weather map image not found: {p}")
        try:
            with Image.open(p) as img:
                img.load()
                mode, (w, h) = img.mode, img.size
                if mode not in ("RGB", "RGBA"):
                    raise ValueError(f"mode of the weather map image must be 'RGB' or 'RGBA' (8 bits per channel: "
                                     f"R coverage, G precipitation, B cloud type), got {mode!r}; convert it first, "
                                     f"e.g. Image.open(path).convert('RGB')")
                if not (_is_pow2(w) and _is_pow2(h) and MIN_SIZE <= min(w, h) and max(w, h) <= MAX_SIZE_2D):
                    raise ValueError(f"size of the weather map image must be powers of two in [{MIN_SIZE}, "
                                     f"{MAX_SIZE_2D}] (the renderer wraps with a bit mask), got {w}x{h}")
                px = np.asarray(img, dtype=np.uint8)
        except (UnidentifiedImageError, OSError, SyntaxError) as exc:
            if isinstance(exc, FileNotFoundError):
                raise
            raise ValueError(f"path {str(p)!r} is not an image Pillow can read: {exc}") from None
        data = px.astype(np.float32) / np.float32(255.0)
        if mode == "RGB":
            data = np.concatenate([data, np.zeros(data.shape[:2] + (1,), np.float32)], axis=2)
        return cls(data)

    def to_image(self, path: str | os.PathLike) -> None:
        """Save as an 8-bit RGBA PNG (values rounded to multiples of 1/255); written atomically."""
        from PIL import Image

        from ..core.output import atomic_path

        p = Path(path)
        px = np.clip(np.rint(self.data * 255.0), 0, 255).astype(np.uint8)
        with atomic_path(p) as tmp:  # a registered temporary: removed on any exception, SIGTERM included
            Image.fromarray(px, mode="RGBA").save(tmp, format="PNG")


# --- textures for the renderer ----------------------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class CloudTextures:
    """The four input textures of the cloudscape, checked: shapes as in the module docstring, power-of-two edges,
    float32, finite; base/detail/weather values in [0, 1]."""

    base_shape: np.ndarray
    detail_shape: np.ndarray
    curl_noise: np.ndarray
    weather_map: np.ndarray

    def __post_init__(self):
        checks = {"base_shape": (4, 4), "detail_shape": (4, 3), "curl_noise": (3, 2), "weather_map": (3, 4)}
        for name, (ndim, ch) in checks.items():
            a = np.asarray(getattr(self, name), dtype=np.float32)
            edges = a.shape[:-1]
            ok = a.ndim == ndim and a.shape[-1] == ch and all(_is_pow2(e) and e >= MIN_SIZE for e in edges)
            if ndim == 4:
                ok = ok and len(set(edges)) == 1
            if not ok:
                raise ValueError(f"{name} must have shape {('(n, n, n, ' if ndim == 4 else '(h, w, ')}{ch}) with "
                                 f"power-of-two edges >= {MIN_SIZE}, got {a.shape}")
            if not np.all(np.isfinite(a)):
                raise ValueError(f"{name} must be finite")
            if name != "curl_noise" and (a.min() < 0.0 or a.max() > 1.0):
                raise ValueError(f"{name} values must be in [0, 1], got [{a.min()}, {a.max()}]")
            object.__setattr__(self, name, a)


# --- generators (vc-A32) ----------------------------------------------------------------------------------------------

class TextureGenerator(abc.ABC):
    """Interface of a noise-texture generator (vc-A32; the thesis names the methods baseShape, detailShape,
    curlNoise, weatherMap). Implement the four methods to feed the renderer your own textures; each returns a
    float32 NumPy array with the shape and value range of the table in the module docstring, and ``None`` settings
    mean the defaults."""

    @abc.abstractmethod
    def base_shape(self, settings: BaseShapeSettings | None = None) -> np.ndarray:
        """The base-shape texture, (n, n, n, 4) in [0, 1] (vc-A9)."""

    @abc.abstractmethod
    def detail_shape(self, settings: DetailShapeSettings | None = None) -> np.ndarray:
        """The detail texture, (n, n, n, 3) in [0, 1] (vc-A10)."""

    @abc.abstractmethod
    def curl_noise(self, settings: CurlNoiseSettings | None = None) -> np.ndarray:
        """The 2-D curl-noise texture, (n, n, 2) (vc-A11)."""

    @abc.abstractmethod
    def weather_map(self, settings: WeatherMapSettings | None = None) -> np.ndarray:
        """The weather map, (h, w, 4) in [0, 1] (vc-A12)."""

    def textures(self, base_shape: BaseShapeSettings | None = None, detail_shape: DetailShapeSettings | None = None,
                 curl_noise: CurlNoiseSettings | None = None,
                 weather_map: WeatherMapSettings | None = None) -> CloudTextures:
        """All four textures, checked."""
        return CloudTextures(self.base_shape(base_shape), self.detail_shape(detail_shape),
                             self.curl_noise(curl_noise), self.weather_map(weather_map))


class BasicTextureGenerator(TextureGenerator):
    """The library's generator (vc-A32 ``BasicSkyTextureGenerator``): all four textures generated from settings --
    including the curl noise and the weather map the thesis loads from shipped files -- or the weather map loaded
    from an image (``weather_image``), like the thesis.

    Parameters
    ----------
    impl : 'warp' (default) or 'c'
        Warp kernels launched tile-parallel (one worker per core) or the single-threaded C library.
    device : str, optional
        Warp device (default CPU).
    workers : int, optional
        Tile-launcher workers (default one per core).
    cache : TextureCache, None or False
        None (default): the process-wide :func:`default_cache`; False: no caching.
    weather_image : path, optional
        An RGB/RGBA image used as the weather map (:meth:`WeatherMap.from_image`) instead of generating one.
    """

    def __init__(self, impl: str = "warp", device: str | None = None, workers: int | None = None,
                 cache: TextureCache | None | bool = None, weather_image: str | os.PathLike | None = None):
        self.impl = _check_impl(impl)
        from ..core.runtime import resolve_device

        self.device = resolve_device(device) if impl == "warp" else "cpu"
        self.workers = workers
        if cache is None or cache is True:
            cache = default_cache()
        elif cache is not False and not isinstance(cache, TextureCache):
            raise TypeError(f"cache must be a TextureCache, None or False, got {type(cache).__name__}")
        self.cache = cache or None
        self.weather_image = None if weather_image is None else Path(weather_image)
        self._weather_loaded: WeatherMap | None = None
        if self.weather_image is not None and not self.weather_image.is_file():
            raise FileNotFoundError(f"weather_image not found: {self.weather_image}")

    def _get(self, kind: str, settings) -> np.ndarray:
        cls = SETTINGS[kind]
        settings = cls() if settings is None else settings
        if not isinstance(settings, cls):
            raise TypeError(f"settings must be a {cls.__name__}, got {type(settings).__name__}")

        def make():
            lau = None
            if self.impl == "warp":
                from ..core.runtime import launcher

                lau = launcher(self.device, self.workers)
            return generate(kind, settings, impl=self.impl, device=self.device, launcher=lau)

        if self.cache is None:
            arr = make()
            arr.setflags(write=False)
            return arr
        return self.cache.get(kind, settings, self.impl, self.device, make)

    def base_shape(self, settings: BaseShapeSettings | None = None) -> np.ndarray:
        return self._get("base_shape", settings)

    def detail_shape(self, settings: DetailShapeSettings | None = None) -> np.ndarray:
        return self._get("detail_shape", settings)

    def curl_noise(self, settings: CurlNoiseSettings | None = None) -> np.ndarray:
        return self._get("curl_noise", settings)

    def weather_map(self, settings: WeatherMapSettings | None = None) -> np.ndarray:
        if self.weather_image is not None:
            if settings is not None:
                raise ValueError("settings cannot be combined with weather_image: the weather map is the image")
            if self._weather_loaded is None:
                self._weather_loaded = WeatherMap.from_image(self.weather_image)
            return self._weather_loaded.data
        return self._get("weather_map", settings)
