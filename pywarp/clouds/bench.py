"""Benchmarks of pywarp. Every number is measured in one run and reported as a ratio where it compares two things,
because machines (this one included) are noisy; no test asserts on wall time.

    pywarp bench tiles [--width 960 --height 540 --repeat 5 --json]
"""
from __future__ import annotations

import json
import math
import os
import platform
import time

import numpy as np
import warp as wp

from ..core.runtime import TileLauncher, init

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


def _timed(fn, repeat: int) -> float:
    """Best of ``repeat`` runs of fn(), in ms."""
    return 1e3 * _best(fn, repeat)


def _reprojected_ms(t, n_frames: int = 16) -> float:
    """Median time of steady-state reprojected frames (after one frame without history), slowly moving camera."""
    from .cloudscape import CameraPose

    p = CameraPose.from_settings(t.settings)
    t.render(p, reprojection=True)
    times = []
    for k in range(n_frames):
        q = CameraPose(p.x_km, p.altitude_km, p.z_km - 0.002 * (k + 1), p.yaw_deg + 0.02 * (k + 1), p.pitch_deg,
                       p.fov_y_deg)
        t0 = time.perf_counter()
        t.render(q, reprojection=True)
        times.append(time.perf_counter() - t0)
    return 1e3 * float(np.median(times))


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
    tech.render(pose, reprojection=False)  # compile / warm up

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
            sky.render(buf, cam, 0, rep, tech.params, tech.launcher)
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
    tech.render(pose, reprojection=False)
    option_light_base_only = _timed(lambda: tech.render(pose, reprojection=False), repeat)
    tech.update(light_detail=True)
    sky = measure_sky(tech, repeat)
    sky_ms = {k: v["full"] for k, v in sky.items()}
    sky_reprojected_ms = {k: v["reprojection"] for k, v in sky.items()}

    one = CloudscapeTechnique(CloudscapeSettings(width=width, height=height, threads=1), textures=textures)
    one.render(pose, reprojection=False)
    t_one = _timed(lambda: one.render(pose, reprojection=False), repeat)
    t_all = ladder["early_exit"]

    sw, sh = small
    s_small = CloudscapeSettings(width=sw, height=sh, threads=1)
    w_small = CloudscapeTechnique(s_small, textures=textures)
    w_small.render(reprojection=False)
    t_w = _timed(lambda: w_small.render(reprojection=False), repeat)
    t_c = _timed(lambda: render_frame_c(s_small, textures), repeat)

    t640 = CloudscapeTechnique(CloudscapeSettings(width=640, height=360, threads=workers), textures=textures)
    ms_640_reproj = _reprojected_ms(t640)
    t1280 = CloudscapeTechnique(CloudscapeSettings(width=1280, height=720, threads=workers), textures=textures)
    t1280.render(reprojection=False)
    ms_1280_full = _timed(lambda: t1280.render(reprojection=False), 1)

    r = lambda v: round(v, 2)  # noqa: E731
    return {
        "benchmark": "cloudscape",
        "size": [width, height],
        "ladder_ms": {k: r(v) for k, v in ladder.items() if k != "dense_clouds_cut_percent"},
        "ladder_cut_percent": {**{k: round(100.0 * (1.0 - v / ladder["unoptimised"]), 1) for k, v in ladder.items()
                                  if k != "dense_clouds_cut_percent"},
                               "early_exit_dense_clouds": round(ladder["dense_clouds_cut_percent"], 1)},
        "thesis_cut_percent": {"adaptive_samples": 20, "early_exit": 70, "early_exit_dense_clouds": 85,
                               "reprojection": 97},
        "sky_ms": {k: r(v) for k, v in sky_ms.items()},
        "sky_reprojected_ms": {k: r(v) for k, v in sky_reprojected_ms.items()},
        "parallel_speedup": round(t_one / t_all, 3),
        "warp_over_c_per_thread": round(t_w / t_c, 3),
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


def main(name: str, as_json: bool = False, **kw) -> dict:
    if name == "reprojection":
        res = {n: bench_reprojection(width=kw.get("width") or 640, height=kw.get("height") or 360,
                                     neighbourhood=n, device=kw.get("device"))
               for n in (1, 3)}
        if as_json:
            print(json.dumps(res))
        else:
            for n, r in res.items():
                print(f"reprojection {r['size'][0]}x{r['size'][1]}, neighbourhood {n}: SSIM mean {r['ssim_mean']} "
                      f"(min {r['ssim_min']}), PSNR mean {r['psnr_mean_db']} dB (min {r['psnr_min_db']} dB) "
                      f"over {r['frames_compared']} frames")
        return res
    if name == "cloudscape":
        res = bench_cloudscape(**{k: v for k, v in kw.items() if k in ("width", "height", "repeat", "workers",
                                                                          "device")})
        if as_json:
            print(json.dumps(res))
        else:
            print(f"cloudscape {res['size'][0]}x{res['size'][1]} on {res['machine']['cores']} cores "
                  f"({res['machine']['cpu']})")
            for k, v in res["ladder_ms"].items():
                print(f"  ladder {k:<18} {v:10.1f} ms   cut {res['ladder_cut_percent'][k]:5.1f} %"
                      f"   (thesis {res['thesis_cut_percent'].get(k, 0)} %)")
            print(f"  early exit, clouds twice as dense: cut {res['ladder_cut_percent']['early_exit_dense_clouds']} %"
                  f"   (thesis up to 85 %)")
            for k, v in res["sky_ms"].items():
                print(f"  sky {k:<21} {v:10.1f} ms")
            for k in ("parallel_speedup", "warp_over_c_per_thread", "reprojected_over_full",
                      "ms_640x360_reprojected", "fps_640x360_reprojected", "ms_1280x720_full"):
                print(f"  {k:<25} {res[k]}")
        return res
    if name == "textures":
        from .bench_textures import bench_textures, report

        res = bench_textures(repeat=kw.get("repeat", 3), workers=kw.get("workers"))
        print(json.dumps(res) if as_json else report(res))
        return res
    if name != "tiles":
        raise ValueError(f"unknown benchmark {name!r}; available: tiles, cloudscape, textures")
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
