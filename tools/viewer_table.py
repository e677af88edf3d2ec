"""The viewer benchmarks of every scene in one run, as a Markdown table (the README's performance section).

    python tools/viewer_table.py [--seconds 10] [--baseline OTHER/bin/python] [--window] [--json OUT.json]
                                 [--scenes ROW ...] [--previews scaled|temporal ...]

For each row (a scene, and the cloudscape from below, inside and above its layer: :data:`ROWS`) it runs ``pywarp view SCENE --benchmark SECONDS --json --no-window`` (``--window``: also under
``xvfb-run -a`` with the window), this installation with ``--previews scaled`` (the default: the whole picture at a
reduced size, enlarged) and ``--previews temporal`` (the window's size, pywarp.core.temporal; ``--previews`` chooses), and, with
``--baseline``, the same command with another installation's interpreter (e.g. a venv of the commit before; it
takes no ``--previews`` and reports no quality keys). The runs of a scene follow one another, so the machine's load
is alike; each row says the load average at its start. Nothing is asserted: the numbers are printed.
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys

#: the rows: a name, its scene and the scene's options. The cloudscape is measured from below the layer (its default
#: camera, 0.3 km), inside it (2.5 km, the default layer spans 1.5-4 km) and above it (6 km, looking down 25 deg).
ROWS = {
    "clouds": ("clouds", ()),
    "clouds-inside": ("clouds", ("--altitude", "2.5", "--pitch", "0")),
    "clouds-above": ("clouds", ("--altitude", "6", "--pitch", "-25")),
    "terrain": ("terrain", ()),
    "flight": ("flight", ()),
    "rain": ("rain", ()),
}


def run(python: str, scene: str, seconds: float, extra=(), window=False, own_env=False) -> dict:
    """One benchmark; ``own_env``: without PYTHONPATH and CCLOUDS_LIBRARY and with PYTHONSAFEPATH (another
    installation imports its own package and library, not this source tree's or the working folder's)."""
    cmd = [python, "-m", "pywarp", "view", scene, "--benchmark", str(seconds), "--json", *extra]
    env = {k: v for k, v in os.environ.items() if not (own_env and k in ("PYTHONPATH", "CCLOUDS_LIBRARY"))}
    if own_env:
        env["PYTHONSAFEPATH"] = "1"
    if window:
        cmd = ["xvfb-run", "-a", *cmd]
    else:
        cmd.append("--no-window")
    load = os.getloadavg()[0]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=1800, env=env)
    lines = [x for x in p.stdout.splitlines() if x.startswith("{")]
    if p.returncode != 0 or not lines:
        return {"error": (p.stderr.strip().splitlines() or ["no output"])[-1], "load": load}
    r = json.loads(lines[-1])
    r["load"] = load
    return r


def cell(r: dict) -> str:
    if "error" in r:
        return "error: " + r["error"][:40]
    q = "" if r.get("ssim_mean") is None else f", SSIM {r['ssim_mean']:.2f} / p5 {r['ssim_p5']:.2f}"
    sizes = r.get("internal_sizes") or r.get("preview_sizes") or {}
    main = max(sizes, key=sizes.get) if sizes else "?"
    return f"{r['fps']:.1f} fps ({main}{q})"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seconds", type=float, default=10.0)
    ap.add_argument("--baseline", default=None, metavar="PYTHON")
    ap.add_argument("--window", action="store_true", help="also with the window under xvfb-run")
    ap.add_argument("--json", default=None, metavar="OUT")
    ap.add_argument("--scenes", nargs="+", default=list(ROWS), choices=list(ROWS), help="the rows (default: all)")
    ap.add_argument("--previews", nargs="+", default=["scaled", "temporal"], choices=["scaled", "temporal"],
                    help="the preview modes measured (default: both)")
    a = ap.parse_args()
    if a.window and not shutil.which("xvfb-run"):
        ap.error("--window needs xvfb-run")
    rows = []
    for name in a.scenes:
        sc, opts = ROWS[name]
        row = {"scene": name}
        if a.baseline:
            row["baseline"] = run(a.baseline, sc, a.seconds, opts, own_env=True)
        for mode in a.previews:
            row[mode] = run(sys.executable, sc, a.seconds, [*opts, "--previews", mode])
            if a.window:
                row[mode + "_window"] = run(sys.executable, sc, a.seconds, [*opts, "--previews", mode], window=True)
        rows.append(row)
        print(json.dumps(row), file=sys.stderr, flush=True)
    cols = [c for c in ("baseline", "scaled", "scaled_window", "temporal", "temporal_window") if c in rows[0]]
    print("| scene | " + " | ".join(cols) + " | load at start |")
    print("|---|" + "---|" * (len(cols) + 1))
    for row in rows:
        loads = "/".join(f"{row[c]['load']:.1f}" for c in cols)
        print(f"| {row['scene']} | " + " | ".join(cell(row[c]) for c in cols) + f" | {loads} |")
    if a.json:
        with open(a.json, "w", encoding="utf-8") as fh:
            json.dump(rows, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
