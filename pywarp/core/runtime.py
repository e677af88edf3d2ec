"""Warp runtime for pywarp: initialisation, device choice and the tile-parallel launcher.

Warp's CPU backend runs one ``wp.launch`` on one thread. Launches release the GIL, so an image kernel is split into
row bands that a small persistent thread pool launches concurrently -- one worker per core by default. This is how a
render uses every core of a laptop without a GPU.

Image kernels that go through :class:`TileLauncher` follow one convention: their **first** parameter is
``row0: int``, the first image row of the band, and they are launched with ``dim=(band_rows, width)``, so the pixel
of thread ``(i, j)`` is ``(row0 + i, j)``.
"""
from __future__ import annotations

import os
import threading
import time
from concurrent.futures import ThreadPoolExecutor, as_completed

import warp as wp

_init_lock = threading.Lock()
_initialised = False


def init() -> None:
    """Initialise Warp once: quiet, no backward passes (halves compile time), kernels cached on disk."""
    global _initialised
    with _init_lock:
        if _initialised:
            return
        wp.config.quiet = True
        wp.config.log_level = wp.LOG_WARNING  # no greeting banner on every command
        wp.config.enable_backward = False  # default of every module created after this point
        _init_without_driver_notice()
        _initialised = True


#: The native library prints this on every start on a machine without an NVIDIA driver -- the normal case for this
#: project (CPU rendering), so it is filtered; every other message passes through.
_NO_DRIVER_NOTICE = "Could not find or load the NVIDIA CUDA driver"


def _init_without_driver_notice() -> None:
    """``wp.init()`` with the native library's stderr captured; re-emit everything but the no-driver notice."""
    import sys
    import tempfile

    try:
        fd = sys.stderr.fileno()
    except (AttributeError, OSError, ValueError):  # no real stderr (e.g. captured): nothing to filter
        wp.init()
        return
    sys.stderr.flush()
    saved = os.dup(fd)
    with tempfile.TemporaryFile(mode="w+b") as tmp:
        os.dup2(tmp.fileno(), fd)
        try:
            wp.init()
        finally:
            os.dup2(saved, fd)
            os.close(saved)
            tmp.seek(0)
            text = tmp.read().decode("utf-8", "replace")
    kept = [line for line in text.splitlines(keepends=True) if _NO_DRIVER_NOTICE not in line]
    if kept:
        sys.stderr.write("".join(kept))
        sys.stderr.flush()


#: the device ``resolve_device(None)`` gives (equation evaluators without a device): "cpu". The test suite sets it
#: from the environment variable PYWARP_TEST_DEVICE (tests/conftest.py) to run the C/Warp agreement tests on a GPU.
DEFAULT_DEVICE = "cpu"


def resolve_device(device: str | None = None) -> str:
    """Return a Warp device name; ``None`` means :data:`DEFAULT_DEVICE` (``"cpu"``). Raises ``ValueError`` for an
    unusable device."""
    init()
    if device is None:
        device = DEFAULT_DEVICE
        if device == "cpu":
            return "cpu"
    if not isinstance(device, str):
        raise TypeError(f"device must be a string such as 'cpu' or 'cuda:0', got {type(device).__name__}")
    names = [d.alias for d in wp.get_devices()]
    if device == "cuda" and any(n.startswith("cuda") for n in names):
        return "cuda:0"
    if device not in names:
        raise ValueError(f"device={device!r} is not available here; available: {', '.join(names)}")
    return device


def default_workers() -> int:
    """One worker per core (``os.cpu_count()``), overridable with the environment variable PYWARP_THREADS."""
    env = os.environ.get("PYWARP_THREADS")
    if env:
        n = int(env)
        if n < 1:
            raise ValueError(f"PYWARP_THREADS must be >= 1, got {n}")
        return n
    return max(1, os.cpu_count() or 1)


class TileLauncher:
    """Launch an image kernel as row bands from a persistent thread pool.

    Parameters
    ----------
    workers : int, optional
        Number of worker threads (default: one per core, see :func:`default_workers`).
    bands_per_worker : int
        Bands per worker and frame (default 16): rows of a cloudscape differ in cost by 10x or more (clear sky,
        ground, cloud bases), so several bands per worker, handed out as workers become free, even out the load.
        That is the most: from the second launch of a kernel at an image size on, its bands are as many as give each
        about MIN_BAND_SECONDS of work by what its rows took the last time (at least one per worker), handed out
        longest first -- a frame of an animation costs nearly what the previous one did, so no worker is left with a
        long band at the end, and a cheap pass is not cut into bands whose launches cost more than they share out.
        Neither the bands nor their order change a pixel: each pixel is one thread's.
    device : str, optional
        Warp device. On CUDA a single launch already uses the whole GPU, so bands are launched from the caller.
    """

    def __init__(self, workers: int | None = None, bands_per_worker: int = 16, device: str | None = None):
        self.device = resolve_device(device)
        self.workers = default_workers() if workers is None else int(workers)
        if self.workers < 1:
            raise ValueError(f"workers must be >= 1, got {workers}")
        if bands_per_worker < 1:
            raise ValueError(f"bands_per_worker must be >= 1, got {bands_per_worker}")
        self.bands_per_worker = bands_per_worker
        self._pool = None
        self._loaded = set()
        #: (kernel, height, width) -> CPU seconds per row at its last launch (each band's time spread over its rows)
        self._row_seconds: dict[tuple, list[float]] = {}

    def _ensure_loaded(self, kernel) -> None:
        # Modules must be compiled/loaded before worker threads launch them concurrently.
        if kernel.module not in self._loaded:
            wp.load_module(kernel.module, device=self.device)
            self._loaded.add(kernel.module)

    #: CPU seconds of work a band is given where the last launch says how much there is: a launch costs ~30 us of
    #: Python (its arguments are packed under the GIL), under 1 % of a band of 4 ms
    MIN_BAND_SECONDS = 0.004

    def bands(self, height: int, n: int | None = None) -> list[tuple[int, int]]:
        """Row ranges ``(row0, rows)`` covering ``height`` rows: ``n`` bands (default: the most, bands_per_worker
        per worker; one on a single worker or a GPU)."""
        if self.workers == 1 or not self.device.startswith("cpu"):
            n = 1
        elif n is None:
            n = self.workers * self.bands_per_worker
        n = max(1, min(n, height))
        edges = [round(k * height / n) for k in range(n + 1)]
        return [(edges[k], edges[k + 1] - edges[k]) for k in range(n) if edges[k + 1] > edges[k]]

    #: bands a single-worker CPU launch is split into when progress is reported (launched one after the other from
    #: the caller, so that a progress bar advances; the pixels are the same as one launch's)
    PROGRESS_BANDS = 16

    def launch(self, kernel, height: int, width: int, inputs: list, outputs: list | None = None,
               progress=None) -> None:
        """Run ``kernel(row0, *inputs, *outputs)`` over a ``height`` x ``width`` image and wait for it.

        ``progress``: optional callable, called from the caller's thread with the number of rows of each band as
        the band finishes (the rows add up to ``height``) -- a progress bar advances per band."""
        if height < 1 or width < 1:
            raise ValueError(f"image size must be at least 1x1, got {width}x{height}")
        self._ensure_loaded(kernel)
        outputs = outputs or []
        key = (kernel, height, width)
        per_row = self._row_seconds.get(key)
        n = None
        if per_row is not None:
            n = max(self.workers, min(self.workers * self.bands_per_worker,
                                      round(sum(per_row) / self.MIN_BAND_SECONDS)))
        bands = self.bands(height, n)
        order = list(range(len(bands)))
        if per_row is not None:  # longest first (stable: ties top to bottom)
            cost = [sum(per_row[r0:r0 + rows]) for r0, rows in bands]
            order.sort(key=lambda k: -cost[k])
        seconds = [0.0] * len(bands)
        if progress is not None and len(bands) == 1 and self.device.startswith("cpu"):
            n = max(1, min(self.PROGRESS_BANDS, height))
            edges = [round(k * height / n) for k in range(n + 1)]
            bands = [(edges[k], edges[k + 1] - edges[k]) for k in range(n) if edges[k + 1] > edges[k]]
            serial = True
        else:
            serial = len(bands) == 1

        def run(band, seconds=None, k=0):
            row0, rows = band
            t0 = time.thread_time()
            wp.launch(kernel, dim=(rows, width), inputs=[row0, *inputs], outputs=outputs, device=self.device)
            if seconds is not None:
                seconds[k] = time.thread_time() - t0
            return rows

        if serial:
            for band in bands:
                rows = run(band)
                if progress is not None:
                    if not self.device.startswith("cpu"):
                        wp.synchronize_device(self.device)
                    progress(rows)
        else:
            if self._pool is None:
                self._pool = ThreadPoolExecutor(max_workers=self.workers, thread_name_prefix="pywarp-tile")
            futures = [self._pool.submit(run, bands[k], seconds, k) for k in order]
            try:
                for f in as_completed(futures):
                    rows = f.result()
                    if progress is not None:
                        progress(rows)
            except BaseException:
                for f in futures:
                    f.cancel()
                raise
            if len(self._row_seconds) > 256:  # many image sizes (a resized viewer): forget the old ones
                self._row_seconds.clear()
            self._row_seconds[key] = [seconds[k] / rows for k, (_, rows) in enumerate(bands) for _ in range(rows)]
        if not self.device.startswith("cpu"):
            wp.synchronize_device(self.device)

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=True)
            self._pool = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


_shared: dict[tuple, TileLauncher] = {}


def launcher(device: str | None = None, workers: int | None = None) -> TileLauncher:
    """A process-wide :class:`TileLauncher` per (device, workers), so pools are created once."""
    key = (resolve_device(device), workers)
    if key not in _shared:
        _shared[key] = TileLauncher(workers=workers, device=key[0])
    return _shared[key]
