"""The converged path-traced references of ``pywarp bench clouds reference`` at 80x45 (tests/data/lighting_reference/):
every scene and view of the benchmark in the physical medium, rendered once with enough paths that the thick cloud's
energy has a standard error of 1-2 % per channel (measured; tests/clouds/test_lighting_converged.py holds it <= 2.5 %).

    python tools/lighting_references.py [--out tests/data/lighting_reference] [--cache DIR] [--views NAME ...]
    python tools/lighting_references.py --peak truncated  # -> tests/data/lighting_reference_truncated

Each view is rendered exactly as :func:`pywarp.clouds.bench_reference.compare` renders a reference (the benchmark's
settings in the 'physical' medium with lighting 'sky', the scene's camera and sun, textures from the settings): two
halves of :data:`SPP` [view] / 2 paths per pixel with seeds 0 and 1, and the view's optical depth (64 ratio-tracking
samples). The file ``<view>.npz`` holds the halves ``a``, ``b`` (linear float32, height x width x 3), ``tau``, their
standard-error images ``se_a``, ``se_b``, ``spp``, ``seed`` (of the first half), ``width``, ``height`` and
``seconds`` (render time, for the record). ``--cache DIR`` also writes each into the benchmark's reference cache
(``compare(..., spp=SPP[view], cache=DIR)`` then reads it instead of rendering).

Why these path counts: the reference's thick-cloud energy has a firefly tail (next-event estimation of the delta
sun through the Mie phase's forward peak): at 512 paths the halves differ by 2-9 % and their CIEDE2000 floor is
1.2-2.8. Measured here (2 threads, shared machine): 35 k paths/s at noon, ~20 k from above, at a low sun and from
view above, so these counts take 6-9 min each; the thick energy's standard error is then 0.2-1.9 % and the halves
differ by 0.1-4.7 % (within 1.8 standard errors). The pixels are not converged: the fireflies still speckle them
(docs/lighting.rst).

``--peak truncated``: the same views with the forward peak truncated (:data:`pywarp.clouds.reference.PEAKS`), 4096
paths each (:data:`SPP_TRUNCATED`; 3-7 min per view here, no firefly tail), into
tests/data/lighting_reference_truncated; the file also records ``peak``. Their pixels converge; they are checked against the exact set in
tests/clouds/test_lighting_converged.py.
"""
from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

WIDTH, HEIGHT = 80, 45
SEED = 0
#: Paths per pixel of each view (both halves together): chosen by the measured paths/s so that each view takes
#: <= ~8 min on two CPU threads; the slow views (low sun, from above, view above: long shadow rays through the
#: layer) get half as many.
SPP = {"noon": 4096, "view below": 4096, "from above": 2048, "low sun": 2048, "view above": 2048}
OUT = Path(__file__).resolve().parents[1] / "tests" / "data" / "lighting_reference"
#: The references with the Mie phase's forward peak truncated (``--peak truncated``): their pixels converge (no
#: firefly tail); 4096 paths each.
SPP_TRUNCATED = 4096
OUT_TRUNCATED = OUT.parent / "lighting_reference_truncated"


def slug(view: str) -> str:
    return view.replace(" ", "-")


def render(view: str, out: Path, cache: str | None = None, peak: str = "exact", spp: int | None = None) -> Path:
    from pywarp.clouds.bench_reference import MEDIA, SCENES, TAU_SAMPLES, VIEWS, _save_reference
    from pywarp.clouds.cloudscape import RenderTextures
    from pywarp.clouds.reference import ReferenceRenderer
    from pywarp.clouds.settings import CloudscapeSettings

    spp = SPP[view] if spp is None else spp
    base = CloudscapeSettings(**{**MEDIA["physical"], "width": WIDTH, "height": HEIGHT, "device": "cpu",
                                 "threads": None})
    textures = RenderTextures.generate(base)
    rs = replace(replace(base, **{**SCENES, **VIEWS}[view]), lighting="sky")
    half = spp // 2
    t0 = time.perf_counter()
    ra = ReferenceRenderer(rs, textures, spp=half, seed=SEED, peak=peak)
    a = ra.render(encode=False)
    rb = ReferenceRenderer(rs, textures, spp=spp - half, seed=SEED + 1, peak=peak)
    b = rb.render(encode=False)
    seconds = time.perf_counter() - t0
    tau = ra.view_optical_depth(samples=TAU_SAMPLES)
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{slug(view)}.npz"
    tmp = path.with_suffix(".tmp.npz")
    np.savez_compressed(tmp, a=a.astype(np.float32), b=b.astype(np.float32), tau=tau.astype(np.float32),
                        se_a=ra.stats["std_error_image"], se_b=rb.stats["std_error_image"], spp=spp, seed=SEED,
                        width=WIDTH, height=HEIGHT, seconds=seconds, peak=peak)
    tmp.replace(path)
    _save_reference(cache, rs, view, spp, SEED, a, b, tau, ra.stats["std_error_image"], rb.stats["std_error_image"],
                    seconds)
    return path


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=None,
                    help=f"folder (default {OUT} for --peak exact, {OUT_TRUNCATED} for truncated)")
    ap.add_argument("--cache", default=None, help="also write into this benchmark reference cache folder (exact)")
    ap.add_argument("--views", nargs="*", default=list(SPP), choices=list(SPP))
    ap.add_argument("--peak", default="exact", choices=("exact", "truncated"),
                    help="the Mie phase's forward peak: exact (unbiased), or truncated (pywarp.clouds.reference.PEAKS)")
    a = ap.parse_args(argv)
    if a.peak == "truncated" and a.cache:
        ap.error("--cache holds the benchmark's (exact) references only")
    out = Path(a.out) if a.out else (OUT if a.peak == "exact" else OUT_TRUNCATED)
    counts = SPP if a.peak == "exact" else {v: SPP_TRUNCATED for v in SPP}
    for view in a.views:
        t0 = time.perf_counter()
        path = render(view, out, a.cache, peak=a.peak, spp=counts[view])
        print(f"{view}: {counts[view]} paths per pixel ({a.peak}), {time.perf_counter() - t0:.0f} s -> {path}",
              file=sys.stderr, flush=True)


if __name__ == "__main__":
    main()
