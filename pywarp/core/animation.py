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
    if Path(str(out)).suffix.lower() not in VIDEO_SUFFIXES:
        raise ValueError(f"{option} must be a video ({' or '.join(VIDEO_SUFFIXES)}) or numbered frames such as "
                         f"frames/frame_%04d.png ({', '.join(L.FRAME_SUFFIXES)}), got {str(out)!r}")
    return _Video(check_output_path(out, VIDEO_SUFFIXES, option), fps)


def frame_times(settings, time_field: str | None, frames: int, fps: float, time_scale: float) -> list[float | None]:
    """The scene time of every frame (None for a static scene): the settings' time plus i / fps * time_scale."""
    if not time_field:
        return [None] * frames
    import dataclasses

    t0 = getattr(settings, time_field)
    times = [t0 + i / fps * time_scale for i in range(frames)]
    try:  # the settings' own spec bounds the time: check the path's end before any frame is rendered
        dataclasses.replace(settings, **{time_field: times[-1]})
    except ValueError as exc:
        raise ValueError(f"--frames/--time-scale: the path ends at {time_field} = {times[-1]:g}, outside the scene's "
                         f"range ({exc})") from None
    return times


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


# --- scale-out on Dask ------------------------------------------------------------------------------------------------
#
# ``pywarp animate ... --scheduler dask[=ADDRESS]`` splits the path into chunks of consecutive frames, renders each
# chunk on a Dask worker (a LocalCluster of worker processes by default, or the existing cluster at ADDRESS, e.g.
# tcp://10.0.0.5:8786) and writes the frames in order as the chunks come back. A frame must not depend on the frames
# before it, so under Dask every frame is a full frame: temporal reprojection (whose history would need a warm-up
# of the whole prefix to be bit-identical) is switched off, and each chunk's technique starts at the chunk's frame
# number (``technique.frame``, which seeds the ray jitter) with the scene time of that frame. The frames are then
# bit-identical to a single-process ``animate`` with ``--no-reprojection``.

SCHEDULERS = ("local", "dask")


def parse_scheduler(text: str | None) -> tuple[str, str | None]:
    """``local`` (one process), ``dask`` (a LocalCluster) or ``dask=ADDRESS`` -> (kind, address)."""
    text = (text or "local").strip()
    kind, _, address = text.partition("=")
    if kind not in SCHEDULERS or (kind == "local" and address):
        raise ValueError(f"--scheduler must be local, dask or dask=ADDRESS (e.g. dask=tcp://host:8786), got {text!r}")
    if kind == "dask" and _ and not address:
        raise ValueError("--scheduler dask=ADDRESS needs an address, e.g. dask=tcp://host:8786")
    return kind, (address or None)


def chunks(frames: int, size: int) -> list[tuple[int, int]]:
    """[start, stop) ranges of ``size`` frames covering ``frames``."""
    return [(s, min(s + size, frames)) for s in range(0, frames, size)]


def render_chunk(scene_name: str, settings, path_name: str | None, frames: int, fps: float, time_scale: float,
                 start: int, stop: int, linear: bool) -> list:
    """Frames [start, stop) of a path, rendered from scratch (what a Dask worker runs): a new technique whose frame
    counter starts at ``start``, the time field advanced as in the single-process loop."""
    from .scenes import scene

    sc = scene(scene_name)
    path = sc.path(path_name)
    poses = path.poses(frames, settings)[start:stop]
    times = frame_times(settings, sc.time_field, frames, fps, time_scale)[start:stop]
    tech = sc.technique(settings)
    if hasattr(tech, "frame"):
        tech.frame = start
    return [img for _, img in render_frames(tech, poses, times, sc.time_field, linear, start)]


def full_frames(settings, explicit: set[str] = frozenset()):
    """The settings for independent frames: reprojection off (ValueError when it was asked for explicitly)."""
    from dataclasses import fields, replace

    if "reprojection" in {f.name for f in fields(settings)} and settings.reprojection:
        if "reprojection" in explicit:
            raise ValueError("--reprojection cannot be used with --scheduler dask: chunks of frames render full frames "
                             "(use --no-reprojection)")
        settings = replace(settings, reprojection=False)
    return settings


def dask_client(address: str | None, workers: int | None = None):
    """(client, cluster): a client of the cluster at ``address``, or of a new LocalCluster of ``workers`` processes
    with one thread each (cluster None for an existing one)."""
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise ValueError("--scheduler dask needs Dask: pip install \"dask[distributed]\" (or the dask extra: "
                         "pip install \"cclouds[dask]\")") from None
    if address:
        return Client(address), None
    import os

    n = workers or max(1, os.cpu_count() or 1)
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
    return Client(cluster), cluster


def render_on_dask(client, scene_name: str, settings, path_name: str | None, frames: int, fps: float,
                   time_scale: float, chunk: int, linear: bool, sink, progress=None) -> int:
    """Render every chunk on the cluster of ``client`` and add the frames to ``sink`` in order; the frame count."""
    futures = [client.submit(render_chunk, scene_name, settings, path_name, frames, fps, time_scale, s, e, linear,
                             pure=False, key=f"pywarp-frames-{s}-{e}-{id(sink)}")
               for s, e in chunks(frames, chunk)]
    try:
        i = 0
        for fut in futures:
            imgs = fut.result()
            for img in imgs:
                sink.add(img, i)
                i += 1
            if progress is not None:
                progress(len(imgs))
        return i
    finally:
        client.cancel([f for f in futures if not f.done()])


def bench_dask(scene_name: str = "clouds", frames: int = 16, width: int = 320, height: int = 180, chunk: int = 4,
               workers: tuple = (1, 2), repeat: int = 1) -> dict:
    """Frames/s of a path rendered on LocalClusters of ``workers`` processes (one thread each; cluster start-up not
    timed, one warm-up chunk per worker first; the best of ``repeat`` timed runs), the speed-up over the first, and
    frames/s per worker: what a user needs to size a cluster. ``pywarp bench clouds dask [--json]`` runs it; the
    result carries the load average before and after, since a shared machine's other work shows in the speed-up."""
    import os
    import time

    from .scenes import scene

    sc = scene(scene_name)
    names = {p.name for p in __import__("dataclasses").fields(sc.settings)}
    values = {**sc.command_defaults.get("animate", {}), "width": width, "height": height}
    values = {k: v for k, v in values.items() if k in names}
    if "threads" in names:
        values["threads"] = 1  # one core per worker process
    settings = full_frames(sc.settings(**values))

    class _Count:
        linear = False

        def add(self, img, index=None):
            pass

    if repeat < 1:
        raise ValueError(f"--repeat must be >= 1, got {repeat}")
    load_before = list(os.getloadavg()) if hasattr(os, "getloadavg") else None
    rows = []
    for n in workers:
        client, cluster = dask_client(None, n)
        try:
            # warm-up (textures, compile): one single-frame task pinned to each worker
            client.gather([client.submit(render_chunk, scene_name, settings, sc.default_path, frames, 24.0, 20.0,
                                         0, 1, False, pure=False, workers=[w], allow_other_workers=False)
                           for w in client.scheduler_info()["workers"]])
            dt = float("inf")
            for _ in range(repeat):
                t0 = time.perf_counter()
                render_on_dask(client, scene_name, settings, sc.default_path, frames, 24.0, 20.0, chunk, False,
                               _Count())
                dt = min(dt, time.perf_counter() - t0)
        finally:
            client.close()
            cluster.close()
        rows.append({"workers": n, "seconds": dt, "fps": frames / dt, "fps_per_worker": frames / dt / n})
    base = rows[0]["fps"]
    for r in rows:
        r["speedup"] = r["fps"] / base
    return {"scene": scene_name, "frames": frames, "width": width, "height": height, "chunk": chunk,
            "repeat": repeat, "rows": rows, "cores": os.cpu_count(), "load_average_before": load_before,
            "load_average_after": list(os.getloadavg()) if hasattr(os, "getloadavg") else None}


def run_dask_bench(width: int = 320, height: int = 180, repeat: int = 1, device: str = "cpu") -> dict:
    """``pywarp bench clouds dask``: :func:`bench_dask` of the clouds fly-through, 16 frames in chunks of 4, on 1 and
    2 worker processes. The workers render on their CPUs (``--device`` must be cpu)."""
    if str(device).split(":")[0] != "cpu":
        raise ValueError(f"--device must be cpu for the dask benchmark (its workers render on their CPUs), "
                         f"got {device!r}")
    return bench_dask("clouds", frames=16, width=width, height=height, chunk=4, workers=(1, 2), repeat=repeat)


def report_dask(res: dict) -> str:
    """The table of :func:`bench_dask`."""
    lines = [f"{res['scene']} path on a Dask LocalCluster: {res['frames']} frames {res['width']}x{res['height']}, "
             f"chunks of {res['chunk']}, one thread per worker, best of {res['repeat']}, {res['cores']} cores"]
    lines.append(f"  {'workers':>7} {'seconds':>9} {'frames/s':>9} {'per worker':>10} {'speed-up':>9}")
    for r in res["rows"]:
        lines.append(f"  {r['workers']:>7} {r['seconds']:9.2f} {r['fps']:9.2f} {r['fps_per_worker']:10.2f} "
                     f"{r['speedup']:8.2f}x")
    if res.get("load_average_before") is not None:
        fmt = lambda la: " ".join(f"{x:.2f}" for x in la)  # noqa: E731
        lines.append(f"  load average before {fmt(res['load_average_before'])}, after "
                     f"{fmt(res['load_average_after'])} (a shared machine's other work lowers the speed-up)")
    return "\n".join(lines)
