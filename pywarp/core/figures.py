"""Run the tutorials that reproduce the texts' figures (``pywarp figures``).

A tutorial is a script ``tutorials/<seed>/<name>.py`` with ``main(out_dir, quick=False)`` that writes its figures into
``out_dir`` and returns the list of files written. The tutorials ship inside the package (``pywarp/tutorials``); in a
source checkout the top-level ``tutorials/`` folder is used.
"""
from __future__ import annotations

import ast
import importlib.util
import re
from pathlib import Path

_PKG = Path(__file__).resolve().parents[1]  # the pywarp package folder
SEEDS = ("vc", "pt", "rr", "oc")


def tutorial_dir() -> Path:
    packaged = _PKG / "tutorials"
    return packaged if packaged.is_dir() else _PKG.parent / "tutorials"


def tutorials(seed: str | None = None) -> list[Path]:
    root = tutorial_dir()
    seeds = [seed] if seed else list(SEEDS)
    out = []
    for s in seeds:
        out += sorted(p for p in (root / s).glob("*.py") if not p.name.startswith("_"))
    return out


def figure_ids(path: Path) -> list[str]:
    """The figure IDs (``vc-fig-4.9``) a tutorial's title docstring names, plus extras (``vc-extra-…``)."""
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
    return sorted(set(re.findall(r"\b(?:vc|pt|rr|oc)-(?:fig|extra)-[A-Za-z0-9.\-]*[A-Za-z0-9]", doc)))


def load(path: Path):
    spec = importlib.util.spec_from_file_location(f"pywarp_tutorial_{path.parent.name}_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def select(seed: str | None = None, only: list[str] | None = None) -> list[Path]:
    """Tutorials of ``seed`` whose figure IDs or file stems match one of ``only`` (``fig-4.9`` or ``vc-fig-4.9``)."""
    if seed is not None and seed not in SEEDS:
        raise ValueError(f"seed must be one of {', '.join(SEEDS)}, got {seed!r}")
    paths = tutorials(seed)
    if not only:
        return paths
    chosen = []
    for p in paths:
        ids = figure_ids(p)
        for want in only:
            if want == p.stem or any(i == want or i.endswith("-" + want) for i in ids):
                chosen.append(p)
                break
    unmatched = [w for w in only if not any(w == p.stem or any(i == w or i.endswith("-" + w) for i in figure_ids(p))
                                            for p in paths)]
    if unmatched:
        raise ValueError(f"--only: no tutorial reproduces {', '.join(unmatched)}")
    return chosen


def run(paths: list[Path], out_root: Path, quick: bool = False, progress: bool = True,
        failures: list | None = None) -> list[Path]:
    """Run ``main(out_dir, quick)`` of each tutorial; figures go to ``out_root/<seed>/``.

    A tutorial that raises does not stop the others: ``(path, exception)`` is appended to ``failures`` when a list
    is given, else the exception propagates."""
    from tqdm import tqdm

    written = []
    bar = tqdm(paths, desc="figures", unit="tutorial", disable=not progress)
    for p in bar:
        bar.set_postfix_str(p.stem)
        out_dir = out_root / p.parent.name
        out_dir.mkdir(parents=True, exist_ok=True)
        try:
            files = load(p).main(out_dir, quick=quick) or []
        except Exception as exc:  # noqa: BLE001 - reported per tutorial below
            if failures is None:
                raise
            failures.append((p, exc))
            continue
        written += [Path(f) for f in files]
    return written
