"""Benchmarks of the clouds scene. Every number is measured in one run and reported as a ratio where it compares two
things, because machines (this one included) are noisy; no test asserts on wall time. Every timing goes through
:mod:`pywarp.core.timing` (best of N after a warm-up, in ms).

    pywarp bench [clouds] tiles|cloudscape|textures|reprojection [--width W --height H --repeat N --workers N
                                                                  --device D --json]

``pywarp.clouds.scene`` registers them with the scene (name -> :class:`pywarp.core.scenes.Benchmark`); the command
line is built from there.
"""
from __future__ import annotations

import math

import numpy as np
import warp as wp

from ..core.runtime import TileLauncher, init
from ..core.timing import best_ms, interleaved_ms, machine, median_ms  # noqa: F401  (machine: re-exported)

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
    from .cloudscape import CameraPose

    p = CameraPose.from_settings(t.settings)
    step = [0]

    def next_frame():
        step[0] += 1
        k = step[0]
        q = CameraPose(p.x_km, p.altitude_km, p.z_km - 0.002 * k, p.yaw_deg + 0.02 * k, p.pitch_deg, p.fov_y_deg)
        t.render(q, reprojection=True)

    t.render(p, reprojection=True)  # the frame without history
    return median_ms(next_frame, n_frames, warmup=0)


def measure_ladder(width: int = 960, height: int = 540, repeat: int = 2, workers: int | None = None,
                   device: str | None = None, **settings):
    """The fig 4.17 ladder on one frame and camera, each step including the previous ones (ms):
    unoptimised, adaptive_samples, early_exit, reprojection. Returns (technique, ladder)."""
    from .cloudscape import CameraPose, CloudscapeSettings, CloudscapeTechnique

    if width < 1 or height < 1:
        raise ValueError(f"width and height must be >= 1, got {width}x{height}")
    if repeat < 1:
        raise ValueError(f"repeat must be >= 1, got {repeat}")
    tech = CloudscapeTechnique(CloudscapeSettings(width=width, height=height, device=device or "cpu",
                                                  threads=workers, **settings))
    pose = CameraPose.from_settings(tech.settings)

    def full(**changes):
        tech.update(**changes)
        return _timed(lambda: tech.render(pose, reprojection=False), repeat)

    ladder = {
        "unoptimised": full(adaptive_samples=False, early_exit=False),
        "adaptive_samples": full(adaptive_samples=True, early_exit=False),
        "early_exit": full(adaptive_samples=True, early_exit=True),
    }
    ladder["reprojection"] = _reprojected_ms(tech)
    # vc-M7: early termination saves more with denser clouds (the thesis: up to 85 %); same frame, twice the
    # extinction, measured against its own unoptimised time
    sigma = tech.settings.sigma_per_km
    dense_unopt = full(adaptive_samples=False, early_exit=False, sigma_per_km=2.0 * sigma)
    dense_exit = full(adaptive_samples=True, early_exit=True)
    tech.update(sigma_per_km=sigma)
    ladder["dense_clouds_cut_percent"] = 100.0 * (1.0 - dense_exit / dense_unopt)
    return tech, ladder


def measure_sky(tech, repeat: int = 2) -> dict:
    """Fig 4.16: the sky stage alone (ms) for the gradient and Preetham models, over the full frame and with
    reprojection (one pixel per 4 x 4 block), on ``tech``'s frame and camera."""
    from .cloudscape import CameraPose, make_sky, replace

    s = tech.settings
    cam = CameraPose.from_settings(s).camera(s.width, s.height)
    buf = tech._buffers["current"]
    out = {}
    for kind in ("gradient", "preetham"):
        sky = make_sky(replace(s, sky=kind).validate())
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
    from .cloudscape import CameraPose, CloudscapeSettings, CloudscapeTechnique, render_frame_c

    if width < 1 or height < 1:
        raise ValueError(f"width and height must be >= 1, got {width}x{height}")
    if repeat < 1:
        raise ValueError(f"repeat must be >= 1, got {repeat}")
    tech, ladder = measure_ladder(width, height, repeat, workers, device)
    textures = tech.textures
    pose = CameraPose.from_settings(tech.settings)
    # the proposed cheaper option (not the default): light samples from the base shape only (no detail erosion)
    tech.update(light_detail=False)
    option_light_base_only = _timed(lambda: tech.render(pose, reprojection=False), repeat)
    tech.update(light_detail=True)
    sky = measure_sky(tech, repeat)
    sky_ms = {k: v["full"] for k, v in sky.items()}
    sky_reprojected_ms = {k: v["reprojection"] for k, v in sky.items()}

    dev = tech.settings.device
    one = CloudscapeTechnique(CloudscapeSettings(width=width, height=height, threads=1, device=dev),
                              textures=textures)
    t_one = _timed(lambda: one.render(pose, reprojection=False), repeat)
    t_all = ladder["early_exit"]

    sw, sh = small
    warp_over_c = None  # Warp per thread over C per thread: a CPU comparison
    if dev.startswith("cpu"):
        s_small = CloudscapeSettings(width=sw, height=sh, threads=1)
        w_small = CloudscapeTechnique(s_small, textures=textures)
        t_w = _timed(lambda: w_small.render(reprojection=False), repeat)
        t_c = _timed(lambda: render_frame_c(s_small, textures), repeat)
        warp_over_c = round(t_w / t_c, 3)

    t640 = CloudscapeTechnique(CloudscapeSettings(width=640, height=360, threads=workers, device=dev),
                               textures=textures)
    ms_640_reproj = _reprojected_ms(t640)
    t1280 = CloudscapeTechnique(CloudscapeSettings(width=1280, height=720, threads=workers, device=dev),
                                textures=textures)
    ms_1280_full = _timed(lambda: t1280.render(reprojection=False), 1)

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
        "options_ms": {"light_base_only": r(option_light_base_only)},
        "options_speedup": {"light_base_only": round(ladder["early_exit"] / option_light_base_only, 3)},
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

    from .cloudscape import CameraPose, CloudscapeSettings, CloudscapeTechnique

    if frames <= 16:
        raise ValueError(f"frames must be > 16 (the first cycle is skipped), got {frames}")
    s = CloudscapeSettings(width=width, height=height, reprojection=True, reprojection_neighbourhood=neighbourhood,
                           device=device or "cpu")
    rep = CloudscapeTechnique(s)
    full = CloudscapeTechnique(s, textures=rep.textures)
    p0 = CameraPose.from_settings(s)
    ssim, psnr = [], []
    for k in range(frames):
        t = k / fps
        yaw = p0.yaw_deg + turn_deg_per_s * t
        dist = speed_kmh * t / 3600.0
        pose = CameraPose(p0.x_km + dist * math.sin(math.radians(yaw)), p0.altitude_km,
                          p0.z_km - dist * math.cos(math.radians(yaw)), yaw, p0.pitch_deg, p0.fov_y_deg)
        a = rep.render(pose, reprojection=True)
        full.frame = rep.frame - 1  # the same frame index: the same ray jitter
        b = full.render(pose, reprojection=False)
        if k >= 16:
            ssim.append(structural_similarity(a, b, channel_axis=2, data_range=255))
            psnr.append(peak_signal_noise_ratio(b, a, data_range=255))
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


def main(name: str, as_json: bool = False, **kw) -> dict:
    """Run benchmark ``name`` with the options it takes (others are ignored); print the report, or one JSON object
    (``as_json``)."""
    from .scene import SCENE

    b = SCENE.benchmark(name)
    res = b.run(**{k: v for k, v in kw.items() if k in b.defaults or k == "device"})
    b.print(res, as_json)
    return res
