"""Timing for every benchmark: best of N with warm-up, in milliseconds, and the machine the numbers come from.

Benchmarks report numbers measured within one run and ratios between them (machines are noisy); no test asserts on
wall time. Comparisons interleave the candidates (:func:`interleaved_ms`) so that all of them see the same machine
state.
"""
from __future__ import annotations

import os
import platform
import time
from typing import Callable


def _check(repeat: int, warmup: int) -> None:
    if isinstance(repeat, bool) or not isinstance(repeat, int) or repeat < 1:
        raise ValueError(f"repeat must be an integer >= 1, got {repeat!r}")
    if isinstance(warmup, bool) or not isinstance(warmup, int) or warmup < 0:
        raise ValueError(f"warmup must be an integer >= 0, got {warmup!r}")


def samples_ms(fn: Callable[[], object], repeat: int = 3, warmup: int = 1) -> list[float]:
    """Wall time of ``repeat`` calls of ``fn()`` in ms, after ``warmup`` untimed calls (compilation, caches)."""
    _check(repeat, warmup)
    for _ in range(warmup):
        fn()
    out = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        out.append(1e3 * (time.perf_counter() - t))
    return out


def best_ms(fn: Callable[[], object], repeat: int = 3, warmup: int = 1) -> float:
    """Best (minimum) wall time of ``repeat`` calls of ``fn()`` in ms, after ``warmup`` untimed calls."""
    return min(samples_ms(fn, repeat, warmup))


def median_ms(fn: Callable[[], object], repeat: int = 3, warmup: int = 1) -> float:
    """Median wall time in ms (for steady-state sequences where each call changes the state, e.g. reprojection)."""
    s = sorted(samples_ms(fn, repeat, warmup))
    n = len(s)
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])


def interleaved_ms(fns: dict[str, Callable[[], object]], repeat: int = 3, warmup: int = 1,
                   keep: dict | None = None) -> dict[str, float]:
    """Best time in ms of each of ``fns``, run in turn ``repeat`` times (after ``warmup`` rounds) so that every
    candidate sees the same machine state. ``keep``: a dict that receives each candidate's last return value."""
    _check(repeat, warmup)
    for _ in range(warmup):
        for fn in fns.values():
            fn()
    best = {name: float("inf") for name in fns}
    for _ in range(repeat):
        for name, fn in fns.items():
            t = time.perf_counter()
            out = fn()
            best[name] = min(best[name], 1e3 * (time.perf_counter() - t))
            if keep is not None:
                keep[name] = out
    return best


def machine() -> dict:
    """Cores, CPU model, Python and Warp versions."""
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        import warp as wp

        warp_version = wp.__version__
    except ImportError:  # pragma: no cover - warp is a dependency
        warp_version = None
    return {"cores": os.cpu_count(), "cpu": model, "python": platform.python_version(), "warp": warp_version}
