#!/usr/bin/env python3
"""Write the images and the table of docs/lighting.rst: ``pywarp bench clouds reference`` in the physical medium
(:func:`pywarp.clouds.bench_reference.compare`), every scene and view, at a size and path count that a 2-core
machine finishes in about half an hour.

    python tools/lighting_docs.py [--width 96 --height 54 --spp 128] [--json OUT.json]

Writes docs/images/lighting/<scene>-<row>.png (the reference exposed for display and the rows ``default``,
``physical``, ``physical energy`` and ``physical slab`` under the reference's exposure alone -- no rescaling) and
docs/lighting_table.inc (included by the page). The images stay linear up to the renderer's display step (clamp, sRGB); a shared display transform would
replace :func:`pywarp.clouds.bench_reference._srgb` here and in the benchmark.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

#: The rows shown as images (the reference besides): the renderer's defaults and the physical models.
IMAGE_ROWS = ("default", "physical", "physical energy", "physical slab")


def _slug(name: str) -> str:
    return name.replace(" ", "-").replace("+", "")


def _role(scene: str) -> str:
    """' (tuning)' or ' (held out)': whether the physical model's parameters were chosen on this scene."""
    from pywarp.clouds.bench_reference import TUNING_SCENES

    return " (tuning)" if scene in TUNING_SCENES else " (held out)"


def table(res: dict) -> str:
    """The rst list-table of the result: per scene and row, best-scale SSIM / dE, then without rescaling dE and the
    energy ratios R/G/B in thick and thin pixels."""
    def ratio(r):
        return "--" if r is None else " / ".join("--" if v is None else f"{v:.2f}" for v in r)

    rows = [".. list-table::", "   :header-rows: 1", "",
            "   * - scene", "     - model", "     - SSIM (best scale)", "     - ΔE00 (best scale)",
            "     - ΔE00 (absolute)", "     - energy thick R/G/B", "     - energy thin R/G/B"]
    for sc in res["scenes"]:
        for m in sc["models"]:
            if "skipped" in m:
                continue
            a = m["absolute"]
            rows += [f"   * - {sc['scene']}{_role(sc['scene'])}", f"     - {m['model']}", f"     - {m['ssim']:.3f}",
                     f"     - {m['delta_e']:.2f}", f"     - {a['delta_e']:.2f}", f"     - {ratio(a['ratio']['thick'])}",
                     f"     - {ratio(a['ratio']['thin'])}"]
        nf = sc["noise_floor"]
        absf = nf.get("abs_delta_e")
        te = nf.get("thick_energy")
        halves = "" if te is None else "halves " + " / ".join("--" if v is None else f"{100 * v:+.1f} %" for v in te)
        rows += [f"   * - {sc['scene']}", f"     - (noise floor: one half of the {sc.get('spp', res['spp'])} paths "
                 "against the other)",
                 f"     - {nf['ssim']:.3f}", f"     - {nf['delta_e']:.2f}",
                 "     - " + ("" if absf is None else f"{absf:.2f}"), f"     - {halves}", "     - "]
    return "\n".join(rows) + "\n"


def block_errors(folder: str, model: str, block=(4, 3)) -> dict:
    """Diagnostic of docs/lighting.rst: the absolute CIEDE2000 of ``model`` against each converged reference and of
    the reference's halves against each other (the floor), both averaged over blocks of ``block`` = (columns, rows)
    pixels first (model and reference alike, linear RGB, the reference's exposure) -- how much of the per-pixel
    error is the reference's pixel noise. {view: (model dE, floor dE)}."""
    from dataclasses import replace

    from pywarp.clouds.bench_reference import (ACCUMULATE, MEDIA, SCENES, VIEWS, absolute_errors, exposure,
                                               load_converged, model_settings)
    from pywarp.clouds.cloudscape import RenderTextures
    from pywarp.clouds.settings import CloudscapeSettings
    from pywarp.clouds.technique import CloudscapeTechnique

    bw, bh = block

    def blocks(x):
        h, w = x.shape[0] // bh * bh, x.shape[1] // bw * bw
        return x[:h, :w].reshape(h // bh, bh, w // bw, bw, *x.shape[2:]).mean(axis=(1, 3))

    base = CloudscapeSettings(**{**MEDIA["physical"], "width": 80, "height": 45, "device": "cpu", "threads": None})
    textures = RenderTextures.generate(base)
    out = {}
    for view, changes in {**SCENES, **VIEWS}.items():
        z = load_converged(folder, view, base.width, base.height)
        ex = exposure(z["ref"])
        ms, why = model_settings(replace(base, **changes), model)
        if ms is None:
            raise ValueError(why)
        lin = CloudscapeTechnique(ms, textures=textures).render_accumulated(None, ACCUMULATE, encode=False)
        tau = blocks(z["tau"].astype("float64"))
        out[view] = (absolute_errors(blocks(lin), blocks(z["ref"]), ex, tau)["delta_e"],
                     absolute_errors(blocks(z["a"]), blocks(z["b"]), ex, tau)["delta_e"])
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--width", type=int, default=96)
    ap.add_argument("--height", type=int, default=54)
    ap.add_argument("--spp", type=int, default=128)
    ap.add_argument("--json", default=None)
    ap.add_argument("--cache", default=None,
                    help="folder of cached references (written when missing; pywarp.clouds.bench_reference.compare)")
    ap.add_argument("--converged", default=None,
                    help="folder of converged references (tools/lighting_references.py), read instead of rendering "
                         "(--spp is then unused)")
    ap.add_argument("--blocks", action="store_true",
                    help="with --converged: print the diagnostic block_errors of CONVERGED_MODEL (4x3 pixels) only")
    args = ap.parse_args(argv)
    if args.blocks:
        from pywarp.clouds.bench_reference import CONVERGED_MODEL

        if not args.converged:
            ap.error("--blocks needs --converged")
        for view, (m, f) in block_errors(args.converged, CONVERGED_MODEL).items():
            print(f"{view}: {CONVERGED_MODEL} dE00 {m:.2f} on 4x3-pixel blocks, floor {f:.2f}")
        return 0
    import imageio.v3 as iio

    from pywarp.clouds.bench_reference import SCENES, VIEWS, compare

    res, images = compare(args.width, args.height, args.spp, scenes=[*SCENES, *VIEWS], medium="physical",
                          cache=args.cache, converged=args.converged)
    out = ROOT / "docs" / "images" / "lighting"
    out.mkdir(parents=True, exist_ok=True)
    for scene, imgs in images.items():
        iio.imwrite(out / f"{_slug(scene)}-reference.png", imgs["reference"])
        for row in IMAGE_ROWS:
            if "abs " + row in imgs:
                iio.imwrite(out / f"{_slug(scene)}-{_slug(row)}.png", imgs["abs " + row])
    (ROOT / "docs" / "lighting_table.inc").write_text(table(res), encoding="utf-8")
    if args.json:
        Path(args.json).write_text(json.dumps(res), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
