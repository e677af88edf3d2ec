"""Benchmarks of the clouds scene. Every number is measured in one run and reported as a ratio where it compares two
things, because machines (this one included) are noisy; no test asserts on wall time. Every timing goes through
:mod:`pywarp.core.timing` (best of N after a warm-up, in ms).

    pywarp bench [clouds] tiles|cloudscape|textures|reprojection [--width W --height H --repeat N --workers N
                                                                  --device D --json]
    pywarp bench [clouds] speed [--repeat N --workers N --device D --json] [--baseline PYTHON]
    pywarp bench clouds --baseline PYTHON          (the same: a scene with --baseline runs ``speed``)

``speed`` measures the issue's numbers (640 x 360 reprojected on a steady path, 1280 x 720 full, their ratio); with
``--baseline`` the same probe runs in another interpreter (e.g. a venv with an older commit installed), the two taking
turns measurement by measurement, and both are printed with the ratios (:func:`bench_speed`).

``pywarp.clouds.scene`` registers them with the scene (name -> :class:`pywarp.core.scenes.Benchmark`); the command
line is built from there.
"""
from __future__ import annotations

import math

import numpy as np
import warp as wp

from ..core.baseline import probe_source
from ..core.runtime import TileLauncher, init
from ..core.timing import Progress, best_ms, interleaved_ms, machine, median_ms  # noqa: F401  (machine: re-exported)

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
    # interleaved so that both see the same machine state
    ms = interleaved_ms({"single": lambda: single.launch(_bench_image, height, width, [octaves], [out]),
                         "tiled": lambda: tiled.launch(_bench_image, height, width, [octaves], [out])},
                        repeat, warmup=0)
    tiled.close()
    return {
        "benchmark": "tiles",
        "size": [width, height],
        "device": single.device,
        "workers": tiled.workers,
        "bands": len(tiled.bands(height)),
        "ms_single_launch": round(ms["single"], 2),
        "ms_tile_parallel": round(ms["tiled"], 2),
        "parallel_speedup": round(ms["single"] / ms["tiled"], 3),
        "identical_output": identical,
        "machine": machine(),
    }


def _timed(fn, repeat: int) -> float:
    """Best of ``repeat`` runs of fn() in ms, after one warm-up run."""
    return best_ms(fn, repeat, warmup=1)


def _reprojected_ms(t, n_frames: int = 16) -> float:
    """Median time of steady-state reprojected frames (after one frame without history), slowly moving camera."""
    from ..core.pose import Pose

    p = Pose.from_settings(t.settings)
    step = [0]

    def next_frame():
        step[0] += 1
        k = step[0]
        q = Pose(p.x, p.y, p.z - 0.002 * k, p.yaw_deg + 0.02 * k, p.pitch_deg, p.fov_y_deg)
        t.render(q, reprojection=True)

    t.render(p, reprojection=True)  # the frame without history
    return median_ms(next_frame, n_frames, warmup=0)


class _KernelTimer:
    """A stand-in for a technique's :class:`pywarp.core.runtime.TileLauncher` that adds up the wall time of every
    launch per kernel (launches wait for their kernel): how a frame's time divides between its passes, measured
    without touching the renderer."""

    def __init__(self, launcher):
        self._launcher = launcher
        self.ms: dict[str, float] = {}

    def launch(self, kernel, *args, **kwargs):
        import time

        t = time.perf_counter()
        try:
            return self._launcher.launch(kernel, *args, **kwargs)
        finally:
            name = getattr(kernel, "key", None) or getattr(kernel, "__name__", "kernel")
            self.ms[name] = self.ms.get(name, 0.0) + 1e3 * (time.perf_counter() - t)

    def __getattr__(self, name):
        return getattr(self._launcher, name)


#: The passes of a reprojected frame (fig 4.17 splits its bar into raymarch + reprojection, as the thesis does): the
#: kernels of each, by the start of their names (the reprojection pass has variants: reproject_frame_kernel,
#: reproject_frame_depth_kernel); everything else in the frame (sRGB encoding, copies to the host) is ``other``
REPROJECTION_SPLIT = {"raymarch": ("sky_kernel", "clouds_kernel"), "reprojection": ("reproject_frame",)}


def _reprojected_path_ms(t, n_frames: int = 16) -> tuple[float, dict]:
    """One pass of the steady reprojected path of :func:`_reprojected_ms` (a frame without history, then
    ``n_frames`` frames of a slowly moving camera): the mean frame time (ms) and its split into
    :data:`REPROJECTION_SPLIT` + ``other`` (mean ms per frame)."""
    import time

    from ..core.pose import Pose

    p = Pose.from_settings(t.settings)
    t.render(p, reprojection=True)  # the frame without history
    timer = _KernelTimer(t.launcher)
    t.launcher = timer
    total = 0.0
    try:
        for k in range(1, n_frames + 1):
            q = Pose(p.x, p.y, p.z - 0.002 * k, p.yaw_deg + 0.02 * k, p.pitch_deg, p.fov_y_deg)
            t0 = time.perf_counter()
            t.render(q, reprojection=True)
            total += 1e3 * (time.perf_counter() - t0)
    finally:
        t.launcher = timer._launcher
    frame = total / n_frames
    split = {g: sum(ms for name, ms in timer.ms.items() if name.startswith(prefixes)) / n_frames
             for g, prefixes in REPROJECTION_SPLIT.items()}
    missing = [g for g, v in split.items() if not v > 0.0]
    if missing:  # a renamed kernel must not turn a pass into 0 ms silently
        raise RuntimeError(f"no kernel of the {', '.join(missing)} pass ran in a reprojected frame (kernels: "
                           f"{', '.join(sorted(timer.ms))}); update REPROJECTION_SPLIT")
    split["other"] = max(frame - sum(split.values()), 0.0)
    return frame, split


#: The steps of the fig 4.17 ladder, each including the previous ones: settings changes of a full frame
LADDER_STEPS = {"unoptimised": dict(adaptive_samples=False, early_exit=False),
                "adaptive_samples": dict(adaptive_samples=True, early_exit=False),
                "early_exit": dict(adaptive_samples=True, early_exit=True)}


def measure_ladder(width: int = 960, height: int = 540, repeat: int = 2, workers: int | None = None,
                   device: str | None = None, detail: dict | None = None, progress: Progress | None = None,
                   **settings):
    """The fig 4.17 ladder on one frame and camera, each step including the previous ones (ms):
    unoptimised, adaptive_samples, early_exit, reprojection. Returns (technique, ladder): each value the best of
    ``repeat`` repetitions after one warm-up frame; the full-frame steps are interleaved (one frame of each step per
    round, so that all see the same machine). ``detail``: a dict that receives every repetition --
    ``samples`` (step -> [ms per round], ``reprojection`` the mean frame of each pass of the steady path) and
    ``reprojection_split`` (raymarch / reprojection / other -> [ms per round], :data:`REPROJECTION_SPLIT`).
    ``progress``: a :class:`Progress` stepped three times (full-frame steps, reprojection, dense clouds)."""
    from ..core.pose import Pose
    from .cloudscape import CloudscapeSettings
    from .technique import CloudscapeTechnique
    from ..core.timing import samples_ms

    if width < 1 or height < 1:
        raise ValueError(f"width and height must be >= 1, got {width}x{height}")
    if repeat < 1:
        raise ValueError(f"repeat must be >= 1, got {repeat}")
    tech = CloudscapeTechnique(CloudscapeSettings(width=width, height=height, device=device or "cpu",
                                                  threads=workers, **settings))
    pose = Pose.from_settings(tech.settings)

    def frame(**changes):
        tech.update(**changes)
        return samples_ms(lambda: tech.render(pose, reprojection=False), 1, warmup=0)[0]

    frame(**LADDER_STEPS["early_exit"])  # warm-up: kernels loaded, buffers touched
    samples = {k: [] for k in LADDER_STEPS}
    for _ in range(repeat):
        for k, changes in LADDER_STEPS.items():
            samples[k].append(frame(**changes))
    ladder = {k: min(v) for k, v in samples.items()}
    if progress is not None:
        progress.step("ladder (fig 4.17): " + ", ".join(f"{k} {v:.0f} ms" for k, v in ladder.items()))
    ladder["reprojection"] = _reprojected_ms(tech)
    if detail is not None:
        split = {g: [] for g in (*REPROJECTION_SPLIT, "other")}
        samples["reprojection"] = []
        for _ in range(repeat):
            ms, parts = _reprojected_path_ms(tech)
            samples["reprojection"].append(ms)
            for g, v in parts.items():
                split[g].append(v)
        detail["samples"] = samples
        detail["reprojection_split"] = split
    if progress is not None:
        progress.step(f"reprojection: {ladder['reprojection']:.1f} ms")
    # vc-M7: early termination saves more with denser clouds (the thesis: up to 85 %); same frame, twice the
    # extinction, measured against its own unoptimised time
    sigma = tech.settings.sigma_per_km
    dense = {"unoptimised": [], "early_exit": []}
    for _ in range(repeat):
        for k in dense:
            dense[k].append(frame(**LADDER_STEPS[k], sigma_per_km=2.0 * sigma))
    tech.update(sigma_per_km=sigma, **LADDER_STEPS["early_exit"])
    ladder["dense_clouds_cut_percent"] = 100.0 * (1.0 - min(dense["early_exit"]) / min(dense["unoptimised"]))
    if progress is not None:
        progress.step(f"dense clouds: early exit cuts {ladder['dense_clouds_cut_percent']:.0f} %")
    if detail is not None:
        detail["dense_samples"] = dense
    return tech, ladder


def measure_sky(tech, repeat: int = 2) -> dict:
    """Fig 4.16: the sky stage alone (ms) for the gradient and Preetham models, over the full frame and with
    reprojection (one pixel per 4 x 4 block), on ``tech``'s frame and camera."""
    from dataclasses import replace

    from ..core.pose import Pose
    from ..kernels.camera import pose_camera
    from .cloudscape import make_sky

    s = tech.settings
    cam = pose_camera(Pose.from_settings(s), s.width, s.height)
    buf = tech._buffers["current"]
    out = {}
    for kind in ("gradient", "preetham"):
        sky = make_sky(replace(s, sky=kind))
        res = {}
        for name, rep in (("full", False), ("reprojection", True)):
            res[name] = _timed(lambda: sky.render(buf, cam, 0, rep, tech.params, tech.launcher), repeat)
        out[kind] = res
    return out


def bench_cloudscape(width: int = 960, height: int = 540, repeat: int = 2, workers: int | None = None,
                     device: str | None = None, small: tuple[int, int] = (160, 90)) -> dict:
    """The vc renderer's numbers, all measured in this run on this machine.

    ladder_ms: the thesis' fig 4.17 ladder on the same frame and camera, each step including the previous ones:
        unoptimised (128 samples always, no early exit), adaptive_samples (64..128 by ray elevation, vc-A18),
        early_exit (vc-A21), reprojection (vc-A26, steady state: one pixel of each 4x4 block raymarched + the
        reprojection pass).
    sky_ms: the sky stage alone over the full frame, gradient and Preetham (fig 4.16).
    parallel_speedup: full frame, tile-parallel over one launch.
    warp_over_c_per_thread: Warp with one launch (one thread) over the C reference ccl_cloudscape_render (one
        thread), the same small frame (``small``), same pixels.
    reprojected_over_full, ms_640x360_reprojected, ms_1280x720_full, machine.
    """
    from ..core.pose import Pose
    from .cloudscape import CloudscapeSettings, render_frame_c
    from .technique import CloudscapeTechnique

    if width < 1 or height < 1:
        raise ValueError(f"width and height must be >= 1, got {width}x{height}")
    if repeat < 1:
        raise ValueError(f"repeat must be >= 1, got {repeat}")
    progress = Progress(9, "cloudscape")
    tech, ladder = measure_ladder(width, height, repeat, workers, device, progress=progress)
    textures = tech.textures
    pose = Pose.from_settings(tech.settings)
    # the proposed cheaper option (not the default): light samples from the base shape only (no detail erosion)
    tech.update(light_detail=False)
    option_light_base_only = _timed(lambda: tech.render(pose, reprojection=False), repeat)
    tech.update(light_detail=True)
    # the renderer's two approximations of the march, each off (what each one saves): every optical depth towards the
    # sun computed (light_interp 0, tests/clouds/test_light_interp.py); the early exit at 1/256 without its fill
    # (tests/clouds/test_early_exit.py)
    options = {"light_base_only": option_light_base_only}
    for name, adv in (("no_light_interp", {"light_interp": 0.0}),
                      ("exit_1_256_no_fill", {"exit_eps": 1.0 / 256.0, "exit_fill": 0})):
        tech.update(advanced=adv)
        options[name] = _timed(lambda: tech.render(pose, reprojection=False), repeat)
    tech.update(advanced={})
    progress.step("options: " + ", ".join(f"{k} {v:.0f} ms" for k, v in options.items()))
    sky = measure_sky(tech, repeat)
    sky_ms = {k: v["full"] for k, v in sky.items()}
    sky_reprojected_ms = {k: v["reprojection"] for k, v in sky.items()}
    progress.step("sky models (fig 4.16): " + ", ".join(f"{k} {v:.1f} ms" for k, v in sky_ms.items()))

    dev = tech.settings.device
    one = CloudscapeTechnique(CloudscapeSettings(width=width, height=height, threads=1, device=dev),
                              textures=textures)
    t_one = _timed(lambda: one.render(pose, reprojection=False), repeat)
    t_all = ladder["early_exit"]
    progress.step(f"one thread: {t_one:.0f} ms")

    sw, sh = small
    warp_over_c = None  # Warp per thread over C per thread: a CPU comparison
    if dev.startswith("cpu"):
        s_small = CloudscapeSettings(width=sw, height=sh, threads=1)
        w_small = CloudscapeTechnique(s_small, textures=textures)
        t_w = _timed(lambda: w_small.render(reprojection=False), repeat)
        t_c = _timed(lambda: render_frame_c(s_small, textures), repeat)
        warp_over_c = round(t_w / t_c, 3)
    progress.step(f"Warp over C per thread, {sw}x{sh}: {warp_over_c if warp_over_c is not None else 'n/a (not cpu)'}")

    t640 = CloudscapeTechnique(CloudscapeSettings(width=640, height=360, threads=workers, device=dev),
                               textures=textures)
    ms_640_reproj = _reprojected_ms(t640)
    progress.step(f"640x360 reprojected: {ms_640_reproj:.1f} ms")
    t1280 = CloudscapeTechnique(CloudscapeSettings(width=1280, height=720, threads=workers, device=dev),
                                textures=textures)
    ms_1280_full = _timed(lambda: t1280.render(reprojection=False), 1)
    progress.step(f"1280x720 full: {ms_1280_full:.0f} ms")

    r = lambda v: round(v, 2)  # noqa: E731
    return {
        "benchmark": "cloudscape",
        "size": [width, height],
        "device": dev,
        "ladder_ms": {k: r(v) for k, v in ladder.items() if k != "dense_clouds_cut_percent"},
        "ladder_cut_percent": {**{k: round(100.0 * (1.0 - v / ladder["unoptimised"]), 1) for k, v in ladder.items()
                                  if k != "dense_clouds_cut_percent"},
                               "early_exit_dense_clouds": round(ladder["dense_clouds_cut_percent"], 1)},
        "thesis_cut_percent": {"adaptive_samples": 20, "early_exit": 70, "early_exit_dense_clouds": 85,
                               "reprojection": 97},
        "sky_ms": {k: r(v) for k, v in sky_ms.items()},
        "sky_reprojected_ms": {k: r(v) for k, v in sky_reprojected_ms.items()},
        "parallel_speedup": round(t_one / t_all, 3),
        "warp_over_c_per_thread": warp_over_c,
        "reprojected_over_full": round(ladder["reprojection"] / ladder["early_exit"], 4),
        "ms_640x360_reprojected": r(ms_640_reproj),
        "fps_640x360_reprojected": round(1e3 / ms_640_reproj, 1),
        "ms_1280x720_full": r(ms_1280_full),
        "options_ms": {k: r(v) for k, v in options.items()},
        "options_speedup": {k: round(ladder["early_exit"] / v, 3) for k, v in options.items()},
        "small_frame": [sw, sh],
        "machine": machine(),
    }


def bench_reprojection(width: int = 640, height: int = 360, frames: int = 48, neighbourhood: int = 1,
                       speed_kmh: float = 300.0, turn_deg_per_s: float = 3.0, fps: float = 24.0,
                       device: str | None = None) -> dict:
    """Error of temporal reprojection (vc-A26) against full renders along a camera path below the layer: the
    camera flies forward at ``speed_kmh`` and turns at ``turn_deg_per_s``, frame by frame at ``fps``; every frame is
    rendered once with reprojection (1/16 of the pixels raymarched) and once in full, at the same pose and frame
    index (same jitter). Reports SSIM and PSNR (scikit-image) of the 8-bit images, skipping the first 16 frames
    (the first reprojection cycle)."""
    from skimage.metrics import peak_signal_noise_ratio, structural_similarity

    from ..core.pose import Pose
    from .cloudscape import CloudscapeSettings
    from .technique import CloudscapeTechnique

    if frames <= 16:
        raise ValueError(f"frames must be > 16 (the first cycle is skipped), got {frames}")
    s = CloudscapeSettings(width=width, height=height, reprojection=True, reprojection_neighbourhood=neighbourhood,
                           device=device or "cpu")
    rep = CloudscapeTechnique(s)
    full = CloudscapeTechnique(s, textures=rep.textures)
    p0 = Pose.from_settings(s)
    ssim, psnr = [], []
    progress = Progress(frames, f"neighbourhood {neighbourhood}: frames", every=8)
    for k in range(frames):
        t = k / fps
        yaw = p0.yaw_deg + turn_deg_per_s * t
        dist = speed_kmh * t / 3600.0
        pose = Pose(p0.x + dist * math.sin(math.radians(yaw)), p0.y,
                    p0.z - dist * math.cos(math.radians(yaw)), yaw, p0.pitch_deg, p0.fov_y_deg)
        a = rep.render(pose, reprojection=True)
        full.frame = rep.frame - 1  # the same frame index: the same ray jitter
        b = full.render(pose, reprojection=False)
        if k >= 16:
            ssim.append(structural_similarity(a, b, channel_axis=2, data_range=255))
            psnr.append(peak_signal_noise_ratio(b, a, data_range=255))
        progress.step(f"frame {k}" + (f": SSIM {ssim[-1]:.4f}, PSNR {psnr[-1]:.1f} dB" if ssim else
                                      " (the first cycle, not compared)"))
    return {
        "benchmark": "reprojection",
        "size": [width, height],
        "frames_compared": len(ssim),
        "neighbourhood": neighbourhood,
        "path": {"speed_kmh": speed_kmh, "turn_deg_per_s": turn_deg_per_s, "fps": fps},
        "ssim_mean": round(float(np.mean(ssim)), 4),
        "ssim_min": round(float(np.min(ssim)), 4),
        "psnr_mean_db": round(float(np.mean(psnr)), 2),
        "psnr_min_db": round(float(np.min(psnr)), 2),
    }


def report_tiles(res: dict) -> str:
    return "\n".join([
        f"tile-parallel launcher, {res['size'][0]}x{res['size'][1]} frame, {res['device']}, {res['workers']} workers, "
        f"{res['bands']} bands",
        f"  one launch     {res['ms_single_launch']:9.2f} ms",
        f"  tile-parallel  {res['ms_tile_parallel']:9.2f} ms",
        f"  speedup        {res['parallel_speedup']:9.3f} x   (identical output: {res['identical_output']})",
        f"  machine        {res['machine']['cores']} cores, {res['machine']['cpu']}"])


def report_cloudscape(res: dict) -> str:
    lines = [f"cloudscape {res['size'][0]}x{res['size'][1]} on {res['device']}, {res['machine']['cores']} cores "
             f"({res['machine']['cpu']})"]
    for k, v in res["ladder_ms"].items():
        lines.append(f"  ladder {k:<18} {v:10.1f} ms   cut {res['ladder_cut_percent'][k]:5.1f} %"
                     f"   (thesis {res['thesis_cut_percent'].get(k, 0)} %)")
    lines.append(f"  early exit, clouds twice as dense: cut {res['ladder_cut_percent']['early_exit_dense_clouds']} %"
                 f"   (thesis up to 85 %)")
    for k, v in res["sky_ms"].items():
        lines.append(f"  sky {k:<21} {v:10.1f} ms")
    for k in ("parallel_speedup", "warp_over_c_per_thread", "reprojected_over_full", "ms_640x360_reprojected",
              "fps_640x360_reprojected", "ms_1280x720_full"):
        lines.append(f"  {k:<25} {res[k]}")
    for k, v in res.get("options_ms", {}).items():
        lines.append(f"  option {k:<18} {v:10.1f} ms   (default / option: {res['options_speedup'][k]})")
    return "\n".join(lines)


def run_reprojection(width: int = 640, height: int = 360, device: str | None = None) -> dict:
    """:func:`bench_reprojection` with neighbourhoods 1 and 3."""
    res = {str(n): bench_reprojection(width=width, height=height, neighbourhood=n, device=device) for n in (1, 3)}
    return {"benchmark": "reprojection", "size": [width, height], "device": device or "cpu", "neighbourhoods": res}


def report_reprojection(res: dict) -> str:
    return "\n".join(
        f"reprojection {r['size'][0]}x{r['size'][1]}, neighbourhood {n}: SSIM mean {r['ssim_mean']} "
        f"(min {r['ssim_min']}), PSNR mean {r['psnr_mean_db']} dB (min {r['psnr_min_db']} dB) "
        f"over {r['frames_compared']} frames" for n, r in res["neighbourhoods"].items())


# --- speed: the issue's numbers, optionally side by side with another installation ------------------------------------

#: The scene of ``bench_speed``, pinned so that both installations render the same picture whatever their defaults
#: (the defaults of today: the camera 0.3 km up looking 20 deg above the horizon, coverage 0.5, a 35 deg sun). Fields
#: an installation's settings lack are left out there and listed in its ``settings_not_applied``.
SPEED_SCENE = {"coverage": 0.5, "sun_elevation_deg": 35.0, "sun_azimuth_deg": 150.0, "camera_altitude_km": 0.3,
               "camera_x_km": 0.0, "camera_z_km": 0.0, "camera_yaw_deg": 0.0, "camera_pitch_deg": 20.0,
               "fov_y_deg": 60.0}
#: The sizes of the issue: a 640 x 360 reprojected frame (the interactive view) and a 1280 x 720 full frame (a still)
SPEED_SIZES = {"reprojected": (640, 360), "full": (1280, 720)}
#: Version of the JSON of ``bench_speed`` (keys are only ever added; a reader tolerates missing ones)
SPEED_SCHEMA = 1
#: The numbers of one side, in the JSON and the report; any of them may be missing (None) in a side's answer.
#: reprojected_over_full compares frames of one size (the reprojected frame's), as the ladder of fig 4.17 does
SPEED_KEYS = ("reprojected_ms", "full_ms", "full_same_size_ms", "reprojected_over_full")
#: The measurements of a round, in order (probe commands)
SPEED_MEASUREMENTS = ("reprojected", "full_same_size", "full")

#: The measurement, as source: run by ``exec`` in this process (ours) and by ``PYTHON -c`` in another interpreter
#: (the baseline), where it imports *that* interpreter's pywarp. It uses only what every version of the package has
#: had (CloudscapeSettings, CloudscapeTechnique(settings, textures=), render(pose, reprojection=), a pose class built
#: from_settings or from its first six fields in order: pywarp.clouds.technique with pywarp.core.pose.Pose, before
#: that pywarp.clouds.cloudscape with CameraPose, before that pywarp.cloudscape). As a program it answers one JSON line
#: per command (:data:`SPEED_MEASUREMENTS`, then ``quit``) on the original stdout; everything else that writes to
#: stdout (library notices) is sent to stderr.
_SPEED_PROBE = probe_source(r"""
try:
    from pywarp.clouds.settings import CloudscapeSettings
    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.core.pose import Pose
    API = "pywarp.clouds.technique"
except ImportError:
    try:
        from pywarp.clouds.cloudscape import CameraPose as Pose, CloudscapeSettings, CloudscapeTechnique
        API = "pywarp.clouds.cloudscape"
    except ImportError:
        from pywarp.cloudscape import CameraPose as Pose, CloudscapeSettings, CloudscapeTechnique
        API = "pywarp.cloudscape"


class SpeedProbe:
    def __init__(self, cfg):
        names = {f.name for f in dataclasses.fields(CloudscapeSettings)}
        wanted = dict(cfg["scene"], device=cfg["device"], threads=cfg["workers"])
        common = {k: v for k, v in wanted.items() if k in names}
        self.not_applied = sorted(k for k in wanted if k not in names)
        (rw, rh), (fw, fh) = cfg["reprojected"], cfg["full"]
        self.rep = CloudscapeTechnique(CloudscapeSettings(width=rw, height=rh, **common))
        self.fullt = CloudscapeTechnique(CloudscapeSettings(width=fw, height=fh, **common), textures=self.rep.textures)
        self.pose = Pose.from_settings(self.rep.settings)
        self.frames = int(cfg["frames"])
        self.reprojected()  # warm-up: every kernel of both paths loaded, the buffers touched

    def reprojected(self):
        # the steady path: one frame without history, then the mean over frames of a slowly moving camera
        p, t = self.pose, self.rep
        t.render(p, reprojection=True)
        total = 0.0
        for k in range(1, self.frames + 1):
            x, y, z, yaw, pitch, fov = dataclasses.astuple(p)[:6]
            q = Pose(x, y, z - 0.002 * k, yaw + 0.02 * k, pitch, fov)
            t0 = time.perf_counter()
            t.render(q, reprojection=True)
            total += time.perf_counter() - t0
        return 1e3 * total / self.frames

    def full(self):
        t0 = time.perf_counter()
        self.fullt.render(self.pose, reprojection=False)
        return 1e3 * (time.perf_counter() - t0)

    def full_same_size(self):
        # a full frame at the size of the reprojected one: the reference of the ratio reprojected / full
        t0 = time.perf_counter()
        self.rep.render(self.pose, reprojection=False)
        return 1e3 * (time.perf_counter() - t0)


def describe(probe):
    import pywarp
    return {"api": API, "pywarp": os.path.dirname(os.path.abspath(pywarp.__file__)),
            "version": getattr(pywarp, "__version__", None), "python": sys.executable,
            "python_version": sys.version.split()[0], "settings_not_applied": probe.not_applied}


PROBE_CLASS = SpeedProbe


def answer(probe, cmd):
    if cmd not in ("reprojected", "full", "full_same_size"):
        raise ValueError("unknown command " + repr(cmd))
    return {"ms": getattr(probe, cmd)()}
""")

from ..core.baseline import BaselineError, BaselineProcess  # noqa: E402,F401  (BaselineError: re-exported)
from ..core.baseline import check_baseline as _check_baseline  # noqa: E402


def check_speed(baseline: str | None = None, **_) -> None:
    """``pywarp bench clouds speed``'s options checked before it prints or measures anything: the ``--baseline``
    interpreter (:func:`bench_speed` checks it again when called directly)."""
    if baseline is not None:
        _check_baseline(baseline)


class _BaselineProcess(BaselineProcess):
    """The speed probe (:data:`_SPEED_PROBE`) in another interpreter."""

    def __init__(self, python: str, cfg: dict):
        super().__init__(python, cfg, _SPEED_PROBE)


def _speed_probe_module() -> dict:
    """The probe's namespace in this process (the same source the baseline runs)."""
    ns = {"__name__": "pywarp_speed_probe"}
    exec(compile(_SPEED_PROBE, "<pywarp speed probe>", "exec"), ns)  # noqa: S102  (our own constant source)
    return ns


def speed_side(answer: dict | None) -> dict | None:
    """One side's numbers from a probe's answers, every key of :data:`SPEED_KEYS` present (None where the side did not
    give it: a baseline of an older layout); the ratio is computed when both times are there."""
    if answer is None:
        return None
    out = dict(answer)
    for k in SPEED_KEYS:
        v = out.get(k)
        out[k] = float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) else None
    if out["reprojected_over_full"] is None and out["reprojected_ms"] and out["full_same_size_ms"]:
        out["reprojected_over_full"] = out["reprojected_ms"] / out["full_same_size_ms"]
    return out


def speed_compare(ours: dict, baseline: dict | None) -> dict:
    """Ratios of two sides (:func:`speed_side`): ``ours_over_baseline`` (time ours / time baseline; for the ratio
    reprojected/full, ours / baseline too) and ``speedup`` (baseline / ours, for the two times). None where either
    side lacks the number."""
    ours, baseline = speed_side(ours), speed_side(baseline)
    if baseline is None:
        return {"ours_over_baseline": None, "speedup": None}
    q = {k: (ours[k] / baseline[k] if ours.get(k) and baseline.get(k) else None) for k in SPEED_KEYS}
    return {"ours_over_baseline": q,
            "speedup": {k: (1.0 / q[k] if q[k] else None) for k in ("reprojected_ms", "full_ms", "full_same_size_ms")}}


def bench_speed(repeat: int = 3, workers: int | None = None, device: str | None = None, baseline: str | None = None,
                frames: int = 16, sizes: dict | None = None, scene: dict | None = None) -> dict:
    """The speed numbers of the issue: the mean time of a reprojected frame on a steady path (``frames`` frames of a
    slowly moving camera after one without history) at 640 x 360, the time of a full frame at 1280 x 720, and the
    ratio of the reprojected frame to a full frame of its own size (640 x 360, also measured: the ratio of the
    ladder, fig 4.17); each the best of ``repeat`` rounds.

    ``baseline``: another Python interpreter (e.g. a venv with an older commit of this project installed). The same
    probe (:data:`_SPEED_PROBE`) then runs there too, in a subprocess that imports that interpreter's pywarp, with
    the same scene (:data:`SPEED_SCENE`), sizes, device and workers; the two sides take turns, one measurement at a
    time (A B, then B A in the next round: interleaved, so both see the same machine), and the result holds both
    sides and the ratios (ours / baseline, and the speed-up baseline / ours). The interpreter is checked and started
    (importing its pywarp) before this side renders anything; a missing or failing one raises
    :class:`BaselineError` (a ValueError) naming ``--baseline``. ``sizes``/``scene`` override the issue's (tests).
    """
    import os

    if isinstance(repeat, bool) or not isinstance(repeat, int) or repeat < 1:
        raise ValueError(f"repeat must be an integer >= 1, got {repeat!r}")
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise ValueError(f"frames must be an integer >= 1, got {frames!r}")
    sizes = {**SPEED_SIZES, **(sizes or {})}
    scene = dict(SPEED_SCENE if scene is None else scene)
    python = None if baseline is None else _check_baseline(baseline)
    cfg = {"scene": scene, "device": device or "cpu", "workers": workers, "frames": frames,
           "reprojected": list(sizes["reprojected"]), "full": list(sizes["full"])}
    load_before = list(os.getloadavg()) if hasattr(os, "getloadavg") else None
    other = _BaselineProcess(python, cfg) if python else None
    try:
        ns = _speed_probe_module()
        probe = ns["SpeedProbe"](cfg)
        sides = {"ours": probe}
        info = {"ours": ns["describe"](probe)}
        if other is not None:
            sides["baseline"] = other
            info["baseline"] = {**other.info, "interpreter": python}  # as given (python: what it runs)
        rounds = {name: {kind: [] for kind in SPEED_MEASUREMENTS} for name in sides}
        order = list(sides)
        progress = Progress(repeat, "rounds")
        for r in range(repeat):
            for kind in SPEED_MEASUREMENTS:
                for name in (order if r % 2 == 0 else order[::-1]):
                    side = sides[name]
                    ms = getattr(side, kind)() if name == "ours" else side.measure(kind)
                    rounds[name][kind].append(round(float(ms), 3))
            progress.step("; ".join(f"{name}: " + ", ".join(f"{kind} {rounds[name][kind][-1]:.1f} ms"
                                                            for kind in SPEED_MEASUREMENTS) for name in sides))
    finally:
        if other is not None:
            other.close()
    load_after = list(os.getloadavg()) if hasattr(os, "getloadavg") else None

    def side(name):
        if name not in rounds:
            return None
        d = {k: v for k, v in info[name].items() if k != "ready"}
        for kind in SPEED_MEASUREMENTS:
            d[f"{kind}_ms"] = min(rounds[name][kind])
        d["rounds_ms"] = rounds[name]
        return speed_side(d)

    ours, base = side("ours"), side("baseline")
    return {
        "benchmark": "speed",
        "schema": SPEED_SCHEMA,
        "device": cfg["device"],
        "workers": workers,
        "repeat": repeat,
        "path_frames": frames,
        "sizes": {k: list(v) for k, v in sizes.items()},
        "scene": scene,
        "ours": ours,
        "baseline": base,
        **speed_compare(ours, base),
        "targets": {"speedup": 1.8, "reprojected_over_full": round(1.0 / 14.0, 4)},
        "load_average": {"before": load_before, "after": load_after},
        "machine": machine(),
    }


def report_speed(res: dict) -> str:
    """The table of :func:`bench_speed`; tolerates a result whose sides lack keys (an older baseline)."""
    sizes = res.get("sizes", {k: list(v) for k, v in SPEED_SIZES.items()})
    rw, rh = sizes["reprojected"]
    fw, fh = sizes["full"]
    fmt = lambda v, spec: "n/a" if v is None else format(v, spec)  # noqa: E731
    ours = speed_side(res.get("ours")) or {}
    base = speed_side(res.get("baseline"))
    rows = ((f"{rw}x{rh} reprojected (mean of {res.get('path_frames', '?')} frames)", "reprojected_ms", "10.1f",
             " ms"),
            (f"{fw}x{fh} full frame", "full_ms", "10.1f", " ms"),
            (f"{rw}x{rh} full frame", "full_same_size_ms", "10.1f", " ms"),
            (f"reprojected / full, both {rw}x{rh}", "reprojected_over_full", "10.4f", ""))
    m = res.get("machine", {})
    head = (f"speed on {res.get('device', '?')}, {m.get('cores', '?')} cores ({m.get('cpu', '?')}), best of "
            f"{res.get('repeat', '?')} interleaved rounds")
    lines = [head]
    if base is None:
        for label, key, spec, unit in rows:
            lines.append(f"  {label:<40} {fmt(ours.get(key), spec)}{unit}")
    else:
        q = res.get("ours_over_baseline") or {}
        sp = res.get("speedup") or {}
        lines.append(f"  {'':<40} {'ours':>10}   {'baseline':>10}   {'ours/base':>9}   {'speed-up':>8}")
        for label, key, spec, unit in rows:
            lines.append(f"  {label:<40} {fmt(ours.get(key), spec):>10}   {fmt(base.get(key), spec):>10}   "
                         f"{fmt(q.get(key), '9.3f'):>9}   {fmt(sp.get(key), '7.2f') + ('x' if sp.get(key) else ''):>8}")
        lines.append(f"  baseline: {base.get('interpreter') or base.get('python')} (pywarp {base.get('version')} at "
                     f"{base.get('pywarp')})")
        if base.get("settings_not_applied"):
            lines.append(f"  the baseline's settings lack {', '.join(base['settings_not_applied'])} (its defaults)")
    t = res.get("targets", {})
    if t:
        lines.append(f"  targets: speed-up >= {t.get('speedup')}x, reprojected / full <= {t.get('reprojected_over_full')}"
                     " (1/14)")
    la = res.get("load_average") or {}
    if la.get("before"):
        lines.append(f"  load average before {la['before'][0]:.2f}, after {la['after'][0]:.2f}")
    return "\n".join(lines)


def main(name: str, as_json: bool = False, **kw) -> dict:
    """Run benchmark ``name`` with the options it takes (others are ignored); print the report, or one JSON object
    (``as_json``)."""
    from .scene import SCENE

    b = SCENE.benchmark(name)
    res = b.run(**{k: v for k, v in kw.items() if k in b.defaults or k == "device"})
    b.print(res, as_json)
    return res
