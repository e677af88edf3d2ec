"""Render one small image per registered scene for the README and the docs: ``docs/images/<scene>.png``.

    python tools/readme_images.py                 # every registered scene, 480 x 270
    python tools/readme_images.py --scenes clouds --width 480 --height 270

Each image is ``pywarp render <scene>`` at the given size with the scene's default settings (its ``render``
command defaults included), written atomically; the script prints what it wrote and how long each took. Rerun it
when a scene's look changes, and commit the images (a few tens of kB each).
"""
from __future__ import annotations

import argparse
import time
from dataclasses import fields
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def render_scene(name: str, width: int, height: int):
    from pywarp.core.scenes import scene

    sc = scene(name)
    names = {f.name for f in fields(sc.settings)}
    values = dict(sc.command_defaults.get("render", {}))
    if {"width", "height"} <= names:
        values.update(width=width, height=height)
    tech = sc.technique(sc.settings(**values))
    return tech.render()


def main(argv=None) -> list[Path]:
    from pywarp.core.output import write_png
    from pywarp.core.scenes import scenes

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenes", nargs="+", default=None, help="scene names (default: every registered scene)")
    p.add_argument("--width", type=int, default=480)
    p.add_argument("--height", type=int, default=270)
    p.add_argument("--out", default=str(ROOT / "docs" / "images"), help="folder (default: docs/images)")
    args = p.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name in args.scenes or list(scenes()):
        t0 = time.perf_counter()
        img = render_scene(name, args.width, args.height)
        path = write_png(out / f"{name}.png", img)
        written.append(path)
        print(f"{path} ({img.shape[1]}x{img.shape[0]}, {path.stat().st_size // 1024} kB, "
              f"{time.perf_counter() - t0:.1f} s)", flush=True)
    return written


if __name__ == "__main__":
    main()
