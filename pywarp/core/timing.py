"""Timing for every benchmark: best of N with warm-up, in milliseconds, and the machine the numbers come from.

Benchmarks report numbers measured within one run and ratios between them (machines are noisy); no test asserts on
wall time. Comparisons interleave the candidates (:func:`interleaved_ms`) so that all of them see the same machine
state. Benchmarks talk while they measure (:func:`say`, :class:`Progress`): a benchmark that runs for minutes prints
its rows as they finish, on stderr, so that ``--json`` keeps one JSON object as the last line of stdout; the load
average (:func:`load_average`, :func:`busy`) says whether the machine was shared while it ran.
"""
from __future__ import annotations

import os
import platform
import sys
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


#: load per core above which a benchmark warns that its numbers may be off (a shared machine slows every number)
BUSY_LOAD_PER_CORE = 0.5


def say(text: str) -> None:
    """One line of a benchmark's progress, on stderr and at once (stdout carries the report or the JSON)."""
    print(text, file=sys.stderr, flush=True)


class Progress:
    """Rows of a benchmark as they finish: ``step(text)`` prints ``[k/total] text (elapsed, ETA)`` on stderr, every
    ``every``-th step and the last (long loops of frames). The ETA assumes the remaining steps cost what the finished
    ones did on average: rough where steps differ (short where they grow, e.g. a ladder of sizes; long after a costly
    first step)."""

    def __init__(self, total: int, label: str = "", every: int = 1):
        self.total, self.label, self.every, self.done, self.t0 = total, label, every, 0, time.perf_counter()

    def step(self, text: str) -> None:
        self.done += 1
        if self.done % self.every and self.done != self.total:
            return
        elapsed = time.perf_counter() - self.t0
        left = self.total - self.done
        eta = f", ETA {_duration(elapsed / self.done * left)}" if left > 0 else ""
        head = f"{self.label} " if self.label else ""
        say(f"  {head}[{self.done}/{self.total}] {text} ({_duration(elapsed)}{eta})")


def _duration(seconds: float) -> str:
    return f"{seconds:.1f} s" if seconds < 60 else f"{int(seconds // 60)} min {int(seconds % 60):02d} s"


def load_average() -> list[float] | None:
    """The 1, 5 and 15 minute load averages (None where the system has none)."""
    try:
        return [round(x, 2) for x in os.getloadavg()]
    except (AttributeError, OSError):
        return None


def busy(load: list[float] | None, cores: int | None = None) -> bool:
    """Whether a machine with this 1-minute load was busy: more than :data:`BUSY_LOAD_PER_CORE` per core."""
    return bool(load) and load[0] / max(cores or os.cpu_count() or 1, 1) > BUSY_LOAD_PER_CORE


def non_monotonic(xs, ys, rel: float = 0.1) -> list[tuple]:
    """Where ``ys`` (times along growing ``xs``, e.g. frame time vs drop count) falls from one row to the next by more
    than ``rel`` of the row before: ``(x_before, y_before, x, y)`` per fall. Such a table should grow; a fall means
    that the machine's load changed while it was measured (or that too few repeats caught a slow outlier)."""
    return [(x0, y0, x, y) for (x0, y0), (x, y) in zip(zip(xs, ys), zip(xs[1:], ys[1:])) if y < y0 * (1.0 - rel)]
