"""``pywarp bench SCENE still [--width W --height H --repeat N --workers N --device D --json] [--baseline PYTHON]``:
the time of one full-quality still, as ``pywarp render SCENE`` makes it, for every registered scene.

A still is what ``pywarp render`` does after the process has started: the scene's settings (its ``render`` command
defaults, the size asked), a new technique, ``render()``. It is timed in-process, warm (after one untimed still: the
kernels loaded, the in-memory caches of the scene's inputs filled), and the best of ``repeat`` is kept. What a new
process adds (Python, Warp and the kernels loaded, the inputs read back from the disk caches, the PNG written) is
measured once per side as the whole ``python -m pywarp render`` command, and reported as ``process_start_ms`` (the
command's time less the best in-process still).

With ``--baseline PYTHON`` (another installation: e.g. a venv of an older commit) the same probe
(:data:`_STILL_PROBE`) runs in that interpreter (:class:`pywarp.core.baseline.BaselineProcess`), the two sides taking
turns still by still (A B, then B A), and the report gives both times, the speed-up (baseline / ours) and how the
images differ: SSIM on luminance (scikit-image) and the mean and 99th percentile of CIEDE2000 (sRGB -> CIELAB), and
the largest channel difference. Nothing is asserted on time.
"""
from __future__ import annotations

import os
import sys

import numpy as np

from .baseline import probe_source

#: Version of the JSON of :func:`bench_still` (keys are only ever added)
STILL_SCHEMA = 1
#: The benchmark's options and their defaults (the issue's still: 640 x 360)
STILL_DEFAULTS = {"width": 640, "height": 360, "repeat": 3, "workers": None, "baseline": None}

#: The measurement, as source: run by ``exec`` here (ours) and by ``PYTHON -c`` in another interpreter (the
#: baseline), where it imports *that* interpreter's pywarp. It uses only what every version with the scene registry
#: has: ``pywarp.core.scenes.scene(name)`` with ``settings``, ``technique``, ``command_defaults``. As a program it
#: answers one JSON line per command (``still``, then ``quit``) on the original stdout; anything else printed (library
#: notices) goes to stderr. Each still's image is saved as ``.npy`` in the folder ``out`` of the configuration.
_STILL_PROBE = probe_source(r"""
import numpy as np
from pywarp.core.scenes import scene as _scene


class StillProbe:
    def __init__(self, cfg):
        self.sc = _scene(cfg["scene"])
        names = {f.name for f in dataclasses.fields(self.sc.settings)}
        wanted = dict(self.sc.command_defaults.get("render", {}), width=cfg["width"], height=cfg["height"],
                      device=cfg["device"], threads=cfg["workers"])
        wanted = {k: v for k, v in wanted.items() if v is not None}
        self.values = {k: v for k, v in wanted.items() if k in names}
        self.not_applied = sorted(k for k in wanted if k not in names)
        self.out, self.tag, self.n = cfg["out"], cfg["tag"], 0
        self.still()  # warm-up: the kernels loaded, the scene's inputs generated or read from the disk caches

    def still(self):
        t0 = time.perf_counter()
        tech = self.sc.technique(self.sc.settings(**self.values))
        t1 = time.perf_counter()
        img = np.asarray(tech.render(), np.uint8)
        t2 = time.perf_counter()
        path = os.path.join(self.out, "%s-%d.npy" % (self.tag, self.n))
        self.n += 1
        np.save(path, img)
        return {"ms": 1e3 * (t2 - t0), "setup_ms": 1e3 * (t1 - t0), "render_ms": 1e3 * (t2 - t1), "image": path}


def describe(probe):
    import pywarp
    return {"pywarp": os.path.dirname(os.path.abspath(pywarp.__file__)),
            "version": getattr(pywarp, "__version__", None), "python": sys.executable,
            "python_version": sys.version.split()[0], "settings": probe.values,
            "settings_not_applied": probe.not_applied}


PROBE_CLASS = StillProbe


def answer(probe, cmd):
    if cmd != "still":
        raise ValueError("unknown command " + repr(cmd))
    return probe.still()
""")


def _probe_module() -> dict:
    """The probe's namespace in this process (the same source the baseline runs)."""
    ns = {"__name__": "pywarp_still_probe"}
    exec(compile(_STILL_PROBE, "<pywarp still probe>", "exec"), ns)  # noqa: S102  (our own constant source)
    return ns


def compare_images(new: np.ndarray, old: np.ndarray) -> dict:
    """How ``new`` differs from ``old`` (uint8 RGB of one size): SSIM on luminance (Rec. 709 luma, scikit-image's
    default 7 x 7 window, data range 255), CIEDE2000 mean and 99th percentile (sRGB -> CIELAB), the largest channel
    difference and whether they are identical."""
    from skimage.color import deltaE_ciede2000, rgb2lab
    from skimage.metrics import structural_similarity

    from .display import luminance

    new, old = np.asarray(new, np.uint8), np.asarray(old, np.uint8)
    if new.shape != old.shape:
        raise ValueError(f"the images differ in size: {new.shape} vs {old.shape}")
    de = deltaE_ciede2000(rgb2lab(new[..., :3] / 255.0), rgb2lab(old[..., :3] / 255.0))
    return {"ssim": round(float(structural_similarity(luminance(new), luminance(old), data_range=255.0)), 5),
            "ciede2000_mean": round(float(np.mean(de)), 4), "ciede2000_p99": round(float(np.percentile(de, 99)), 4),
            "max_abs_diff": int(np.max(np.abs(new.astype(np.int16) - old.astype(np.int16)))),
            "identical": bool(np.array_equal(new, old))}


def _process_ms(python: str, scene: str, width: int, height: int, device: str, folder: str, own_env: bool) -> tuple:
    """The whole ``PYTHON -m pywarp render SCENE`` command (process start included), timed once: (ms, image)."""
    import subprocess
    import time

    from .baseline import BASELINE_ENV_DROP

    out = os.path.join(folder, f"process-{'baseline' if own_env else 'ours'}.png")
    cmd = [python, "-m", "pywarp", "render", scene, "--width", str(width), "--height", str(height), "--out", out,
           "--no-progress"] + (["--device", device] if device != "cpu" else [])
    env = {k: v for k, v in os.environ.items() if not (own_env and k in BASELINE_ENV_DROP)}
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=folder, timeout=3600)
    ms = 1e3 * (time.perf_counter() - t0)
    if p.returncode != 0:
        tail = " | ".join(p.stderr.strip().splitlines()[-2:]) or "no output"
        raise RuntimeError(f"{' '.join(cmd[1:5])} failed (exit status {p.returncode}): {tail}")
    from PIL import Image

    return ms, np.asarray(Image.open(out).convert("RGB"))


def check_still(baseline: str | None = None, **_) -> None:
    """The options checked before anything is printed or measured: the ``--baseline`` interpreter."""
    from .baseline import check_baseline

    if baseline is not None:
        check_baseline(baseline)


def bench_still(scene: str, width: int = 640, height: int = 360, repeat: int = 3, workers: int | None = None,
                device: str | None = None, baseline: str | None = None, process: bool = True) -> dict:
    """The best of ``repeat`` warm in-process stills of ``scene`` (and of the ``baseline`` interpreter's
    installation, interleaved), their ratio, the images compared, and (``process``) the whole ``pywarp render``
    command timed once per side (its process start). See the module's docstring."""
    import tempfile

    from .baseline import BaselineProcess, check_baseline
    from .timing import Progress, machine

    if isinstance(repeat, bool) or not isinstance(repeat, int) or repeat < 1:
        raise ValueError(f"repeat must be an integer >= 1, got {repeat!r}")
    for name, v in (("width", width), ("height", height)):
        if isinstance(v, bool) or not isinstance(v, int) or not 1 <= v <= 8192:
            raise ValueError(f"{name} must be an integer in [1, 8192], got {v!r}")
    python = None if baseline is None else check_baseline(baseline)
    device = device or "cpu"
    load_before = list(os.getloadavg()) if hasattr(os, "getloadavg") else None
    with tempfile.TemporaryDirectory(prefix="pywarp-bench-still-") as folder:
        cfg = {"scene": scene, "width": width, "height": height, "device": device, "workers": workers,
               "out": folder}
        ns = _probe_module()
        probe = ns["StillProbe"]({**cfg, "tag": "ours"})  # the scene and its settings checked before the baseline
        other = BaselineProcess(python, {**cfg, "tag": "baseline"}, _STILL_PROBE) if python else None
        try:
            info = {"ours": ns["describe"](probe)}
            if other is not None:
                info["baseline"] = {**{k: v for k, v in other.info.items() if k != "ready"}, "interpreter": python}
            answers: dict = {name: [] for name in info}
            order = list(info)
            progress = Progress(repeat, "stills")
            for r in range(repeat):
                for name in (order if r % 2 == 0 else order[::-1]):
                    answers[name].append(probe.still() if name == "ours" else other.ask("still"))
                progress.step("; ".join(f"{n}: {answers[n][-1]['ms']:.0f} ms" for n in order))
        finally:
            if other is not None:
                other.close()
        sides = {}
        for name, ans in answers.items():
            best = min(ans, key=lambda a: a["ms"])
            sides[name] = {**info[name], "still_ms": round(best["ms"], 2), "setup_ms": round(best["setup_ms"], 2),
                           "render_ms": round(best["render_ms"], 2),
                           "rounds_ms": [round(a["ms"], 2) for a in ans],
                           "image": np.load(best["image"]), "repeat_identical": all(
                               np.array_equal(np.load(a["image"]), np.load(best["image"])) for a in ans)}
        if process:
            for name, side in sides.items():
                ms, img = _process_ms(python if name == "baseline" else sys.executable, scene, width, height,
                                      device, folder, own_env=name == "baseline")
                side.update(process_ms=round(ms, 1), process_start_ms=round(ms - side["still_ms"], 1),
                            process_image_identical=bool(np.array_equal(img, side["image"])))
    ours, base = sides["ours"], sides.get("baseline")
    result = {
        "benchmark": "still", "schema": STILL_SCHEMA, "scene": probe.sc.name, "width": width, "height": height,
        "device": device, "workers": workers, "repeat": repeat,
        "ours": {k: v for k, v in ours.items() if k != "image"},
        "baseline": None if base is None else {k: v for k, v in base.items() if k != "image"},
        "speedup": None if base is None else round(base["still_ms"] / ours["still_ms"], 3),
        "image_change": None if base is None else compare_images(ours["image"], base["image"]),
        "load_average": {"before": load_before, "after": list(os.getloadavg()) if hasattr(os, "getloadavg") else None},
        "machine": machine(),
    }
    result["images"] = {k: v["image"] for k, v in sides.items()}  # for callers in Python; dropped from the JSON
    return result


def report_still(res: dict) -> str:
    """The table of :func:`bench_still`."""
    ours, base = res["ours"], res.get("baseline")
    m = res.get("machine", {})
    lines = [f"{res['scene']}: full-quality still {res['width']}x{res['height']} on {res['device']}, "
             f"{m.get('cores', '?')} cores, best of {res['repeat']} warm in-process stills"
             + (" (interleaved with the baseline)" if base else "")]
    cols = [("ours", ours)] + ([("baseline", base)] if base else [])
    lines.append(f"  {'':<34}" + "".join(f"{n:>12}" for n, _ in cols))
    rows = [("still (settings + technique + render)", "still_ms"), ("  of which the technique's set-up", "setup_ms"),
            ("whole `pywarp render` command", "process_ms"), ("  process start (command - still)", "process_start_ms")]
    for label, key in rows:
        if all(s.get(key) is None for _, s in cols):
            continue
        lines.append(f"  {label:<34}" + "".join(f"{'n/a' if s.get(key) is None else f'{s[key]:.0f} ms':>12}"
                                                for _, s in cols))
    if base:
        c = res["image_change"]
        lines.append(f"  speed-up (baseline / ours): {res['speedup']:.2f}x")
        lines.append(f"  image vs the baseline's: SSIM {c['ssim']:.4f}, CIEDE2000 mean {c['ciede2000_mean']:.3f} / "
                     f"p99 {c['ciede2000_p99']:.3f}, largest channel difference {c['max_abs_diff']}"
                     + (" (identical)" if c["identical"] else ""))
        lines.append(f"  baseline: {base.get('interpreter')} (pywarp at {base.get('pywarp')})")
        if base.get("settings_not_applied"):
            lines.append(f"  the baseline's settings lack {', '.join(base['settings_not_applied'])} (its defaults)")
    la = res.get("load_average") or {}
    if la.get("before"):
        lines.append(f"  load average before {la['before'][0]:.2f}, after {la['after'][0]:.2f}")
    return "\n".join(lines)


#: What ``pywarp bench SCENE still`` says it measures and how long it takes (:func:`pywarp.core.scenes.register` adds
#: the benchmark to every scene)
STILL_DESCRIPTION = ("a full-quality still as `pywarp render` makes it (warm, in-process; the command's process start "
                     "measured once), with --baseline beside another installation's: times, ratio, image SSIM / "
                     "CIEDE2000")
STILL_EXPECTED = "10 s - 2 min (x2 with --baseline)"


def run_still(scene: str, **kw) -> dict:
    """:func:`bench_still` as the benchmark runs it (the images left out of the result: it is printed as JSON)."""
    res = bench_still(scene, **kw)
    res.pop("images", None)
    return res
