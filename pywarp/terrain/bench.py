"""Benchmarks of the terrain scene: Tabulka 7.1 (fixed vs dynamic step), Tabulka 8.1 (the final scene), the bisection
refinement of ch. 9, supersampling (7.1.6) and the viewer's preview setting. Each prints the text's numbers beside
ours; the ratios are what compares across machines (the text: a GTX 860M laptop GPU; here: whatever device runs)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..core.timing import Progress, best_ms, machine
from .settings import PREVIEW, TEST_HEIGHTMAP, TerrainSettings

SIZES = ((640, 480), (1366, 768), (1920, 1080))
#: Tabulka 7.1 (ms; rig not named, presumably rig 1: GTX 860M)
TEXT_7_1 = {"fixed": (8.4, 29.0, 57.7), "dynamic": (0.6, 1.4, 2.3)}
#: Tabulka 8.1 (ms): rig 1 GTX 860M, rig 2 GTX 960M
TEXT_8_1 = {"rig1": (6.6, 20.2, 40.2), "rig2": (5.1, 17.5, 35.4)}


def _tech(settings: TerrainSettings):
    from .technique import TerrainTechnique

    return TerrainTechnique(settings)


def _time_frame(settings: TerrainSettings, repeat: int) -> tuple[float, float, np.ndarray]:
    """(best ms, mean view-march steps per pixel, the float image) of one frame of ``settings``."""
    tech = _tech(settings)
    img = tech.render(encode=False)  # warm-up: compile and load the module
    ms = best_ms(lambda: tech.render(encode=False), repeat=repeat, warmup=0)
    return ms, float(tech.steps_taken().mean()) / settings.rays_per_pixel, img


def _base(device, workers, **changes) -> TerrainSettings:
    return TerrainSettings(device=device or "cpu", threads=workers, **changes)


def bench_marching(repeat: int = 1, workers: int | None = None, device: str | None = None) -> dict:
    """Tabulka 7.1: the test heightmap (Kod 7.4 / 7.5 map, lit as in 7.2, no shadows) with the fixed step (STEP_SIZE
    0.1, MAX_T 200) and the dynamic step (PRECISION 0.01, MAX_STEPS 1000) at the text's three sizes."""
    rows = []
    progress = Progress(len(SIZES), "Tabulka 7.1")
    for (w, h), fixed_text, dyn_text in zip(SIZES, TEXT_7_1["fixed"], TEXT_7_1["dynamic"]):
        s = _base(device, workers, width=w, height=h, **TEST_HEIGHTMAP)
        ms_f, steps_f, img_f = _time_frame(replace(s, march="fixed"), repeat)
        ms_d, steps_d, img_d = _time_frame(replace(s, march="dynamic"), repeat)
        rows.append({"size": [w, h], "ms_fixed": round(ms_f, 2), "ms_dynamic": round(ms_d, 2),
                     "ratio": round(ms_f / ms_d, 2), "steps_fixed": round(steps_f, 1),
                     "steps_dynamic": round(steps_d, 1), "step_ratio": round(steps_f / steps_d, 2),
                     "max_abs_image_difference": round(float(np.abs(img_f - img_d).max()), 4),
                     "text_ms_fixed": fixed_text, "text_ms_dynamic": dyn_text,
                     "text_ratio": round(fixed_text / dyn_text, 1)})
        progress.step(f"{w}x{h}: fixed {ms_f:.1f} ms, dynamic {ms_d:.1f} ms")
    mean = float(np.mean([r["ratio"] for r in rows]))
    return {"benchmark": "marching", "table": "pt-tab-7.1", "rows": rows, "mean_ratio": round(mean, 2),
            "text_mean_ratio": 19.9, "settings": {k: v for k, v in TEST_HEIGHTMAP.items()},
            "device": device or "cpu", "machine": machine()}


def report_marching(r: dict) -> str:
    lines = [f"Tabulka 7.1 -- fixed vs dynamic step, test heightmap ({r['device']}; the text: GTX 860M)",
             f"{'size':>10} {'fixed ms':>10} {'dyn ms':>8} {'ratio':>6} {'steps f/d':>12}   text: fixed, dyn, ratio"]
    for row in r["rows"]:
        w, h = row["size"]
        lines.append(f"{w:>5}x{h:<4} {row['ms_fixed']:>10.1f} {row['ms_dynamic']:>8.1f} {row['ratio']:>6.1f} "
                     f"{row['steps_fixed']:>6.0f}/{row['steps_dynamic']:<5.0f}   {row['text_ms_fixed']}, "
                     f"{row['text_ms_dynamic']}, {row['text_ratio']}x")
    lines.append(f"mean ratio {r['mean_ratio']}x (the text: ~20x, 19.9x from its ms)")
    return "\n".join(lines)


def bench_final(repeat: int = 1, workers: int | None = None, device: str | None = None) -> dict:
    """Tabulka 8.1: the final scene (default settings) at the text's three sizes."""
    rows = []
    progress = Progress(len(SIZES), "Tabulka 8.1")
    for (w, h), r1, r2 in zip(SIZES, TEXT_8_1["rig1"], TEXT_8_1["rig2"]):
        ms, steps, _ = _time_frame(_base(device, workers, width=w, height=h), repeat)
        rows.append({"size": [w, h], "ms": round(ms, 1), "fps": round(1000.0 / ms, 2), "steps": round(steps, 1),
                     "text_ms_rig1": r1, "text_ms_rig2": r2})
        progress.step(f"{w}x{h}: {ms:.1f} ms")
    base = rows[0]["ms"]
    for row in rows:
        row["ratio_to_640x480"] = round(row["ms"] / base, 2)
    return {"benchmark": "final", "table": "pt-tab-8.1", "rows": rows,
            "text_ratio_to_640x480_rig1": [round(v / TEXT_8_1["rig1"][0], 2) for v in TEXT_8_1["rig1"]],
            "device": device or "cpu", "machine": machine()}


def report_final(r: dict) -> str:
    lines = [f"Tabulka 8.1 -- final scene ({r['device']}; the text: GTX 860M / GTX 960M)",
             f"{'size':>10} {'ms':>9} {'fps':>7} {'x640':>6}   text rig 1, rig 2 (ms)"]
    for row in r["rows"]:
        w, h = row["size"]
        lines.append(f"{w:>5}x{h:<4} {row['ms']:>9.1f} {row['fps']:>7.2f} {row['ratio_to_640x480']:>6.2f}   "
                     f"{row['text_ms_rig1']}, {row['text_ms_rig2']}")
    lines.append(f"the text's growth with size (rig 1): {r['text_ratio_to_640x480_rig1']}")
    return "\n".join(lines)


def bench_bisect(width: int = 640, height: int = 360, repeat: int = 1, workers: int | None = None,
                 device: str | None = None) -> dict:
    """The ch. 9 refinement against the plain dynamic step on the final scene: time, steps, image difference."""
    s = _base(device, workers, width=width, height=height)
    progress = Progress(2, "bisection")
    ms_d, steps_d, img_d = _time_frame(replace(s, march="dynamic"), repeat)
    progress.step(f"dynamic step: {ms_d:.1f} ms")
    ms_b, steps_b, img_b = _time_frame(replace(s, march="bisect"), repeat)
    progress.step(f"bisection: {ms_b:.1f} ms")
    diff = np.abs(img_b - img_d)
    mse = float(np.mean((img_b - img_d) ** 2))
    return {"benchmark": "bisect", "size": [width, height], "ms_dynamic": round(ms_d, 1), "ms_bisect": round(ms_b, 1),
            "speedup": round(ms_d / ms_b, 3), "steps_dynamic": round(steps_d, 2), "steps_bisect": round(steps_b, 2),
            "mean_abs_difference": round(float(diff.mean()), 5), "max_abs_difference": round(float(diff.max()), 4),
            "pixels_differing_over_1_255": round(float(np.mean(diff.max(axis=-1) > 1.0 / 255.0)), 4),
            "psnr_db": round(10.0 * np.log10(1.0 / mse), 2) if mse > 0 else None,
            "threshold": s.bisect_threshold, "bisect_steps": s.bisect_steps, "device": device or "cpu",
            "machine": machine()}


def report_bisect(r: dict) -> str:
    return (f"bisection refinement (ch. 9) vs dynamic step, {r['size'][0]}x{r['size'][1]} ({r['device']}):\n"
            f"  dynamic {r['ms_dynamic']} ms, {r['steps_dynamic']} steps/pixel; bisect {r['ms_bisect']} ms, "
            f"{r['steps_bisect']} steps/pixel (threshold {r['threshold']}, {r['bisect_steps']} halvings); speedup "
            f"{r['speedup']}x\n  image difference: mean {r['mean_abs_difference']}, max {r['max_abs_difference']}, "
            f"{100 * r['pixels_differing_over_1_255']:.2f} % of pixels > 1/255, PSNR {r['psnr_db']} dB")


def bench_supersampling(width: int = 320, height: int = 180, repeat: int = 1, workers: int | None = None,
                        device: str | None = None) -> dict:
    """7.1.6: cost of 1, 4 and 16 rays per pixel (the text: an 'unacceptable' drop, no numbers)."""
    rows = []
    progress = Progress(3, "supersampling")
    for rays in (1, 4, 16):
        ms, steps, _ = _time_frame(_base(device, workers, width=width, height=height, rays_per_pixel=rays), repeat)
        rows.append({"rays_per_pixel": rays, "ms": round(ms, 1)})
        progress.step(f"{rays} rays per pixel: {ms:.1f} ms")
    for row in rows:
        row["cost_ratio"] = round(row["ms"] / rows[0]["ms"], 2)
    return {"benchmark": "supersampling", "size": [width, height], "rows": rows, "device": device or "cpu",
            "machine": machine()}


def report_supersampling(r: dict) -> str:
    return (f"supersampling cost, {r['size'][0]}x{r['size'][1]} ({r['device']}): "
            + ", ".join(f"{row['rays_per_pixel']} rays {row['ms']} ms ({row['cost_ratio']}x)" for row in r["rows"]))


def bench_preview(width: int = 640, height: int = 360, repeat: int = 3, workers: int | None = None,
                  device: str | None = None) -> dict:
    """Frames per second of the full setting, of the :data:`PREVIEW` reductions at full resolution and of the
    viewer's preview frame (quality='preview': the reductions at 1/preview_scale resolution, enlarged)."""
    s = _base(device, workers, width=width, height=height)
    progress = Progress(3, "preview")
    ms_full, _, img_full = _time_frame(s, repeat)
    progress.step(f"full setting: {ms_full:.1f} ms")
    ms_red, _, img_red = _time_frame(replace(s, **PREVIEW), repeat)
    progress.step(f"reductions at full size: {ms_red:.1f} ms")
    ms_prev, _, img_prev = _time_frame(replace(s, quality="preview"), repeat)
    progress.step(f"preview frame: {ms_prev:.1f} ms")
    return {"benchmark": "preview", "size": [width, height], "ms_full": round(ms_full, 1),
            "fps_full": round(1000.0 / ms_full, 2), "ms_reduced": round(ms_red, 1),
            "fps_reduced": round(1000.0 / ms_red, 2), "ms_preview": round(ms_prev, 1),
            "fps_preview": round(1000.0 / ms_prev, 2), "preview_scale": s.preview_scale, "preview_reduces": PREVIEW,
            "mean_abs_difference_reduced": round(float(np.abs(img_full - img_red).mean()), 4),
            "mean_abs_difference_preview": round(float(np.abs(img_full - img_prev).mean()), 4),
            "device": device or "cpu", "machine": machine()}


def report_preview(r: dict) -> str:
    return (f"viewer preview {r['size'][0]}x{r['size'][1]} ({r['device']}): full {r['ms_full']} ms "
            f"({r['fps_full']} fps); reductions at full size {r['ms_reduced']} ms ({r['fps_reduced']} fps); preview "
            f"frame (1/{r['preview_scale']} size) {r['ms_preview']} ms ({r['fps_preview']} fps); the preview sets "
            + ", ".join(f"{k}={v}" for k, v in r["preview_reduces"].items()))


#: the stage profile: each row switches one part off (or to the march's octaves); its cost is the difference
PROFILE = (("full", {}), ("slab off (the printed loops)", {"slab": False}), ("no shadows", {"shadows": "none"}),
           ("normals at the march's octaves", {"normal_octaves_max": 4, "normal_octaves_min": 4}),
           ("no water (stage atmosphere)", {"stage": "atmosphere"}),
           ("no clouds, fog, grass, water (stage materials)", {"stage": "materials"}),
           ("march + 4-octave normal only", {"stage": "materials", "shadows": "none", "normal_octaves_max": 4,
                                             "normal_octaves_min": 4}))


def bench_profile(width: int = 640, height: int = 360, repeat: int = 2, workers: int | None = None,
                  device: str | None = None) -> dict:
    """Time per stage of the final scene: frames with one stage switched off, CPU time of the process (steadier
    than the wall clock on a shared machine) and wall time."""
    import time

    rows = []
    progress = Progress(len(PROFILE), "profile")
    for name, changes in PROFILE:
        tech = _tech(_base(device, workers, width=width, height=height, **changes))
        tech.render(encode=False)
        best = (float("inf"), float("inf"))
        for _ in range(repeat):
            w0, c0 = time.perf_counter(), time.process_time()
            tech.render(encode=False)
            best = min(best, (time.perf_counter() - w0, time.process_time() - c0))
        rows.append({"case": name, "changes": changes, "wall_ms": round(best[0] * 1e3, 1),
                     "cpu_ms": round(best[1] * 1e3, 1), "steps": round(float(tech.steps_taken().mean()), 2)})
        progress.step(f"{name}: {rows[-1]['cpu_ms']:.0f} ms CPU")
    full = rows[0]["cpu_ms"]
    for row in rows:
        row["cpu_share_of_full"] = round(row["cpu_ms"] / full, 3)
    return {"benchmark": "profile", "size": [width, height], "rows": rows, "device": device or "cpu",
            "machine": machine()}


def report_profile(r: dict) -> str:
    lines = [f"stage profile {r['size'][0]}x{r['size'][1]} ({r['device']}): CPU ms / wall ms / view steps per pixel"]
    for row in r["rows"]:
        lines.append(f"  {row['case']:<48} {row['cpu_ms']:>8.0f} {row['wall_ms']:>8.0f} {row['steps']:>7.2f}  "
                     f"({row['cpu_share_of_full']:.2f} of full)")
    return "\n".join(lines)


def bench_tables(repeat: int = 1, workers: int | None = None, device: str | None = None) -> dict:
    """Every terrain benchmark in one run (one JSON object)."""
    return {"benchmark": "tables",
            "marching": bench_marching(repeat, workers, device),
            "final": bench_final(repeat, workers, device),
            "bisect": bench_bisect(repeat=repeat, workers=workers, device=device),
            "supersampling": bench_supersampling(repeat=repeat, workers=workers, device=device),
            "preview": bench_preview(repeat=max(repeat, 2), workers=workers, device=device),
            "profile": bench_profile(repeat=max(repeat, 2), workers=workers, device=device)}


def report_tables(r: dict) -> str:
    return "\n\n".join([report_marching(r["marching"]), report_final(r["final"]), report_bisect(r["bisect"]),
                        report_supersampling(r["supersampling"]), report_preview(r["preview"]),
                        report_profile(r["profile"])])
