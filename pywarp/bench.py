"""Benchmarks of pywarp. Every number is measured in one run and reported as a ratio where it compares two things,
because machines (this one included) are noisy; no test asserts on wall time.

    pywarp bench tiles [--width 960 --height 540 --repeat 5 --json]
"""
from __future__ import annotations

import json
import os
import platform
import time

import numpy as np
import warp as wp

from .runtime import TileLauncher, init

init()


@wp.kernel
def _bench_image(row0: int, octaves: int, out: wp.array2d(dtype=float)):
    """A frame-sized kernel with per-pixel work comparable to a sky + short raymarch: a loop of transcendental math."""
    i, j = wp.tid()
    y = row0 + i
    x = float(j) * 0.01
    z = float(y) * 0.01
    acc = float(0.0)
    for k in range(octaves):
        f = float(1 << (k % 8))
        acc += wp.sin(x * f + float(k)) * wp.cos(z * f - float(k)) / f + wp.exp(-0.001 * float(k) * x)
    out[y, j] = acc


def machine() -> dict:
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return {"cores": os.cpu_count(), "cpu": model, "python": platform.python_version(), "warp": wp.__version__}


def _best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def bench_tiles(width: int = 960, height: int = 540, repeat: int = 5, octaves: int = 48,
                workers: int | None = None, device: str | None = None) -> dict:
    """Speedup of the tile-parallel launcher over one launch, for a frame-sized kernel (same kernel, same pixels)."""
    if width < 1 or height < 1:
        raise ValueError(f"width and height must be >= 1, got {width}x{height}")
    if repeat < 1:
        raise ValueError(f"repeat must be >= 1, got {repeat}")
    single = TileLauncher(workers=1, device=device)
    tiled = TileLauncher(workers=workers, device=device)
    out = wp.zeros((height, width), dtype=float, device=single.device)
    single.launch(_bench_image, height, width, [octaves], [out])  # compile/load, warm up
    ref = out.numpy().copy()
    tiled.launch(_bench_image, height, width, [octaves], [out])
    identical = bool(np.array_equal(ref, out.numpy()))
    # interleave the two so that both see the same machine state
    t1, tn = [], []
    for _ in range(repeat):
        t1.append(_best(lambda: single.launch(_bench_image, height, width, [octaves], [out]), 1))
        tn.append(_best(lambda: tiled.launch(_bench_image, height, width, [octaves], [out]), 1))
    tiled.close()
    return {
        "benchmark": "tiles",
        "size": [width, height],
        "device": single.device,
        "workers": tiled.workers,
        "bands": len(tiled.bands(height)),
        "ms_single_launch": round(1e3 * min(t1), 2),
        "ms_tile_parallel": round(1e3 * min(tn), 2),
        "parallel_speedup": round(min(t1) / min(tn), 3),
        "identical_output": identical,
        "machine": machine(),
    }


def main(name: str, as_json: bool = False, **kw) -> dict:
    if name != "tiles":
        raise ValueError(f"unknown benchmark {name!r}; available: tiles")
    res = bench_tiles(**kw)
    if as_json:
        print(json.dumps(res))
    else:
        print(f"tile-parallel launcher, {res['size'][0]}x{res['size'][1]} frame, {res['workers']} workers, "
              f"{res['bands']} bands")
        print(f"  one launch     {res['ms_single_launch']:9.2f} ms")
        print(f"  tile-parallel  {res['ms_tile_parallel']:9.2f} ms")
        print(f"  speedup        {res['parallel_speedup']:9.3f} x   (identical output: {res['identical_output']})")
        print(f"  machine        {res['machine']['cores']} cores, {res['machine']['cpu']}")
    return res
