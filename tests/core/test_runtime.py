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


def test_tile_launcher_hands_out_the_longest_bands_first(monkeypatch):
    """From the second launch of a kernel at one image size, the bands are as many as give each about
    MIN_BAND_SECONDS of the work its rows took the last time (at least one per worker, at most bands_per_worker), and
    the longest (the rows where the clouds are) start first, so no worker is left with a long band at the end; the
    same pixels either way."""
    h, w = 48, 32
    a = wp.zeros((h, w), dtype=float, device="cpu")
    b = wp.zeros((h, w), dtype=float, device="cpu")
    started = []
    real = runtime.wp.launch

    def recording(kernel, dim, inputs, outputs, device):
        started.append((inputs[0], dim[0]))  # (row0, rows), in the order the workers take the bands
        return real(kernel, dim=dim, inputs=inputs, outputs=outputs, device=device)

    with runtime.TileLauncher(workers=2, bands_per_worker=4) as tl:
        tl.launch(_bench_image, h, w, [8], [a])
        key = (_bench_image, h, w)
        per_row = tl._row_seconds[key]
        assert len(per_row) == h and all(s >= 0.0 for s in per_row)
        monkeypatch.setattr(runtime.wp, "launch", recording)
        # rows 36..47 took the longest, then rows 0..5; enough work for the 8 bands of 6 rows
        unit = tl.MIN_BAND_SECONDS
        tl._row_seconds[key] = [unit * (0.5 if r < 6 else 3.0 if r >= 36 else 0.1) for r in range(h)]
        tl.launch(_bench_image, h, w, [8], [b])
        assert len(started) == 8
        assert {s[0] for s in started[:2]} == {36, 42}  # the two workers take the two longest bands first
        assert started[2][0] == 0
        np.testing.assert_array_equal(a.numpy(), b.numpy())
        # little work: one band per worker
        started.clear()
        tl._row_seconds[key] = [unit * 0.01] * h
        tl.launch(_bench_image, h, w, [8], [b])
        assert sorted(started) == [(0, 24), (24, 24)]
        # work for 5 bands of 4 ms
        started.clear()
        tl._row_seconds[key] = [unit * 5 / h] * h
        tl.launch(_bench_image, h, w, [8], [b])
        assert len(started) == 5 and sum(r for _, r in started) == h
    np.testing.assert_array_equal(a.numpy(), b.numpy())
