"""``pywarp bench rain drops``: frame time vs drop count for drops and streaks over a cached background (the
measurements of rr-tab-6.1 / rr-tab-6.2, beside the text's fps), and the mask build times."""
from __future__ import annotations

import json
import time

from ..core.timing import Progress, non_monotonic

#: rr-tab-6.1 (notebook: GeForce Go 7400, 1.733 GHz dual core) and rr-tab-6.2 (PC: Radeon 3850, Core2Duo 2.667 GHz):
#: drops -> (drop fps, streak fps), as printed.
TABLE_6_1 = {0: (14.3, 14.3), 10: (13.9, 13.7), 50: (13.7, 13.5), 100: (13.5, 13.3), 500: (12.9, 12.4),
             1000: (12.3, 12.1)}
TABLE_6_2 = {0: (588, 588), 1: (585, 585), 10: (580, 581), 100: (550, 558), 1000: (308, 384), 2000: (205, 283),
             5000: (106, 160), 10000: (58, 95), 20000: (32, 55), 50000: (17, 22)}
COUNTS = (0, 1, 10, 50, 100, 500, 1000, 2000, 5000, 10000, 20000, 50000)


def bench_drops(width: int = 640, height: int = 360, repeat: int = 3, workers=None, device: str = "cpu",
                counts=COUNTS, background: str = "panorama", masks: bool = True) -> dict:
    """Best-of-``repeat`` frame time (ms) per drop count and mode; the particles advance one 1/30 s step per frame,
    the background is cached (the text's measurements include its scene; ours is rendered once). The drop size is the
    text's measurement default, 0.5 mm (§6.1). ``masks``: also time the 512^2 mask builds (sphere, outline, exact)."""
    from . import particles as P
    from .settings import RainSettings
    from .technique import RainTechnique, _build_mask

    s = RainSettings(width=width, height=height, background=background, drops=max(counts), size_mm=0.5,
                     size_spread_mm=0.6, device=device, threads=workers)
    tech = RainTechnique(s)
    rows = []
    progress = Progress(len(counts), "drop counts")
    for n in counts:
        row = {"drops": n}
        for mode in ("drops", "streaks"):
            tech.update(drops=n, mode=mode)
            tech._reset_particles()  # the requested count at once (warm), not one per frame
            tech.render()  # warm-up (compiles, fills the cache)
            best = float("inf")
            sprites = 0
            for k in range(repeat):
                tech.update(time_s=tech.settings.time_s + s.frame_dt / s.clock_rate)
                t0 = time.perf_counter()
                ins = tech.frame_inputs()
                P.composite(**ins, launcher=tech.launcher, cache=tech._device_cache)
                best = min(best, time.perf_counter() - t0)
                sprites = len(ins["sprites"])
            row[f"{mode}_ms"] = round(best * 1e3, 3)
            row[f"{mode}_fps"] = round(1.0 / best, 1)
            row[f"{mode}_visible"] = sprites
        if n in TABLE_6_1:
            row["table_6_1_fps"] = TABLE_6_1[n]
        if n in TABLE_6_2:
            row["table_6_2_fps"] = TABLE_6_2[n]
        rows.append(row)
        progress.step(f"{n} drops: drops {row['drops_ms']:.2f} ms, streaks {row['streaks_ms']:.2f} ms")
    from . import drops as R

    mask_ms = {}
    for method in ("sphere", "outline", "exact") if masks else ():
        with R._MASK_LOCK:  # time a build, not a hit of drop_mask's in-memory cache
            R._MASK_CACHE.clear()
        t0 = time.perf_counter()
        _build_mask(1.0, method, 512)
        mask_ms[method] = round((time.perf_counter() - t0) * 1e3, 1)
    return {"benchmark": "rain drops", "width": width, "height": height, "device": tech.device,
            "workers": tech.launcher.workers, "background": background, "size_mm": 0.5, "rows": rows,
            "mask_build_ms": mask_ms, "warnings": monotonic_warnings(rows),
            "aim": "10 000 streaks at 640x360 in <= 50 ms on two cores (issue 11)"}


def monotonic_warnings(rows: list[dict]) -> list[str]:
    """A warning per mode whose frame time falls as the drop count grows by more than 10 % (more drops cost more:
    a fall is the machine's load changing during the run, or too few repeats for the smallest times)."""
    out = []
    for mode in ("drops", "streaks"):
        falls = non_monotonic([row["drops"] for row in rows], [row[f"{mode}_ms"] for row in rows])
        if falls:
            where = ", ".join(f"{y0:.2f} ms at {x0} drops -> {y:.2f} ms at {x}" for x0, y0, x, y in falls)
            out.append(f"{mode}: the time falls as the drop count grows ({where}): the machine's load changed while "
                       f"it was measured, or the times are too small for --repeat; rerun with a higher --repeat on "
                       f"an idle machine")
    return out


def report_drops(r: dict) -> str:
    lines = [f"rain: frame time vs drop count, {r['width']}x{r['height']}, {r['device']}, {r['workers']} workers, "
             f"cached {r['background']} background, drops of 0.5 mm",
             f"{'drops':>7} {'drops ms':>9} {'fps':>7} {'streaks ms':>11} {'fps':>7}   text: tab 6.1 (drops/streaks)"
             f"  tab 6.2 (drops/streaks)"]
    for row in r["rows"]:
        t1 = "/".join(map(str, row.get("table_6_1_fps", ()))) or "-"
        t2 = "/".join(map(str, row.get("table_6_2_fps", ()))) or "-"
        lines.append(f"{row['drops']:>7} {row['drops_ms']:>9.2f} {row['drops_fps']:>7.1f} {row['streaks_ms']:>11.2f} "
                     f"{row['streaks_fps']:>7.1f}   {t1:>22}  {t2:>22}")
    lines.append("mask build (512^2, a = 1 mm): " + ", ".join(f"{k} {v} ms" for k, v in r["mask_build_ms"].items()))
    lines += [f"warning: {w}" for w in r.get("warnings", ())]
    return "\n".join(lines)


if __name__ == "__main__":
    print(json.dumps(bench_drops(counts=(0, 1000), repeat=1)))
