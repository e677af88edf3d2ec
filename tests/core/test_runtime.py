"""The Warp runtime: CPU by default, the tile-parallel launcher gives the same image as one launch, bands cover the
frame exactly once, and bad arguments are rejected."""
from __future__ import annotations

import numpy as np
import pytest
import warp as wp

from pywarp.core import runtime
from pywarp.clouds.bench import _bench_image


@wp.kernel
def _write_row_col(row0: int, out: wp.array2d(dtype=wp.int32)):
    i, j = wp.tid()
    y = row0 + i
    wp.atomic_add(out, y, j, y * 1000 + j + 1)


def test_default_device_is_cpu():
    assert runtime.resolve_device() == "cpu"
    with pytest.raises(ValueError, match="device='cuda:7' is not available"):
        runtime.resolve_device("cuda:7")
    with pytest.raises(TypeError, match="device must be a string"):
        runtime.resolve_device(3)


@pytest.mark.parametrize("height,workers", [(1, 2), (7, 2), (540, 2), (31, 3), (64, 1)])
def test_tile_launcher_covers_every_pixel_exactly_once(height, workers):
    width = 13
    out = wp.zeros((height, width), dtype=wp.int32, device="cpu")
    with runtime.TileLauncher(workers=workers) as tl:
        tl.launch(_write_row_col, height, width, [], [out])
        bands = tl.bands(height)
    y, x = np.mgrid[0:height, 0:width]
    np.testing.assert_array_equal(out.numpy(), y * 1000 + x + 1)  # atomic_add: a pixel written twice would differ
    assert sum(r for _, r in bands) == height
    assert [b[0] for b in bands] == sorted(b[0] for b in bands)


def test_tile_parallel_image_equals_single_launch():
    h, w = 45, 64
    a = wp.zeros((h, w), dtype=float, device="cpu")
    b = wp.zeros((h, w), dtype=float, device="cpu")
    runtime.TileLauncher(workers=1).launch(_bench_image, h, w, [8], [a])
    with runtime.TileLauncher(workers=2, bands_per_worker=3) as tl:
        tl.launch(_bench_image, h, w, [8], [b])
    np.testing.assert_array_equal(a.numpy(), b.numpy())
    assert np.all(np.isfinite(a.numpy()))


@pytest.mark.parametrize("height,workers", [(1, 1), (45, 1), (45, 2), (7, 3)])
def test_tile_launcher_progress_per_band_same_pixels(height, workers):
    """progress(rows) is called once per finished band, from the caller's thread, and the rows add up to the image;
    a single worker splits the launch into serial bands so that a progress bar advances. Same pixels as without."""
    import threading

    w = 32
    a = wp.zeros((height, w), dtype=float, device="cpu")
    b = wp.zeros((height, w), dtype=float, device="cpu")
    runtime.TileLauncher(workers=1).launch(_bench_image, height, w, [8], [a])
    calls = []
    with runtime.TileLauncher(workers=workers) as tl:
        tl.launch(_bench_image, height, w, [8], [b], progress=lambda rows: calls.append((rows, threading.get_ident())))
        per_worker = tl.bands_per_worker
    np.testing.assert_array_equal(a.numpy(), b.numpy())
    assert sum(r for r, _ in calls) == height
    assert len(calls) == min(height, runtime.TileLauncher.PROGRESS_BANDS if workers == 1 else workers * per_worker)
    assert {t for _, t in calls} == {threading.get_ident()}


def test_tile_launcher_hands_out_the_longest_bands_first():
    """From the second launch of a kernel at one image size, the bands are as many as give each about
    MIN_BAND_SECONDS of the work its rows took the last time (at least one per worker, at most bands_per_worker), and
    the longest (the rows where the clouds are) are handed to the workers first, so no worker is left with a long band
    at the end; the same pixels either way."""
    h, w = 48, 32
    a = wp.zeros((h, w), dtype=float, device="cpu")
    b = wp.zeros((h, w), dtype=float, device="cpu")
    with runtime.TileLauncher(workers=2, bands_per_worker=4) as tl:
        tl.launch(_bench_image, h, w, [8], [a])
        key = (_bench_image, h, w)
        per_row = tl._row_seconds[key]
        assert len(per_row) == h and all(s >= 0.0 for s in per_row)
        handed = []  # the bands (row0, rows) in the order they are queued for the workers (first in, first out)
        submit = tl._pool.submit
        tl._pool.submit = lambda fn, band, *rest: (handed.append(band), submit(fn, band, *rest))[1]
        # rows 36..47 took the longest, then rows 0..5; enough work for the 8 bands of 6 rows
        unit = tl.MIN_BAND_SECONDS
        tl._row_seconds[key] = [unit * (0.5 if r < 6 else 3.0 if r >= 36 else 0.1) for r in range(h)]
        tl.launch(_bench_image, h, w, [8], [b])
        assert handed == [(36, 6), (42, 6), (0, 6), (6, 6), (12, 6), (18, 6), (24, 6), (30, 6)]
        np.testing.assert_array_equal(a.numpy(), b.numpy())
        # little work: one band per worker
        handed.clear()
        tl._row_seconds[key] = [unit * 0.01] * h
        tl.launch(_bench_image, h, w, [8], [b])
        assert handed == [(0, 24), (24, 24)]
        # work for 5 bands of 4 ms
        handed.clear()
        tl._row_seconds[key] = [unit * 5 / h] * h
        tl.launch(_bench_image, h, w, [8], [b])
        assert len(handed) == 5 and sum(r for _, r in handed) == h
    np.testing.assert_array_equal(a.numpy(), b.numpy())


def test_tile_launcher_rejects_bad_arguments():
    with pytest.raises(ValueError, match="workers must be >= 1"):
        runtime.TileLauncher(workers=0)
    with pytest.raises(ValueError, match="bands_per_worker must be >= 1"):
        runtime.TileLauncher(bands_per_worker=0)
    out = wp.zeros((1, 1), dtype=float, device="cpu")
    with pytest.raises(ValueError, match="image size must be at least 1x1, got 0x5"):
        runtime.TileLauncher(workers=1).launch(_bench_image, 5, 0, [1], [out])


def test_default_workers_env(monkeypatch):
    monkeypatch.setenv("PYWARP_THREADS", "3")
    assert runtime.default_workers() == 3
    monkeypatch.setenv("PYWARP_THREADS", "0")
    with pytest.raises(ValueError, match="PYWARP_THREADS must be >= 1"):
        runtime.default_workers()


def test_backward_passes_are_off():
    import pywarp.kernels.phase  # noqa: F401

    assert wp.config.enable_backward is False
    assert wp.get_module("pywarp.kernels.phase").options["enable_backward"] is False


def test_cli_bench_tiles_json_small(tmp_path):
    import json
    import subprocess
    import sys

    res = subprocess.run([sys.executable, "-m", "pywarp", "bench", "tiles", "--width", "64", "--height", "32",
                          "--repeat", "1", "--json"], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    out = json.loads(res.stdout.strip().splitlines()[-1])
    assert out["identical_output"] is True and out["parallel_speedup"] > 0 and out["device"] == "cpu"
    res = subprocess.run([sys.executable, "-m", "pywarp", "bench", "tiles", "--width", "-5"],
                         capture_output=True, text=True)
    assert res.returncode == 2 and "--width must be in [1, 8192], got -5" in res.stderr
    res = subprocess.run([sys.executable, "-m", "pywarp", "bench", "tiles", "--device", "cuda:3"],
                         capture_output=True, text=True)
    assert res.returncode == 2 and "--device must be one of 'cpu'" in res.stderr and "got 'cuda:3'" in res.stderr


def test_init_filters_only_the_no_driver_notice(tmp_path):
    """On a machine without an NVIDIA driver (the normal case here) Warp's native library prints a notice on every
    start; pywarp filters that line only."""
    import subprocess
    import sys

    code = ("import sys, pywarp.core.runtime as r; r.init(); "
            "print('other message', file=sys.stderr)")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert "NVIDIA CUDA driver" not in res.stderr
    assert "other message" in res.stderr
