"""Run the tutorials that reproduce the texts' figures (``pywarp figures``), and say the true status of every figure
and measurement of the catalogue (``pywarp equations --figures``).

A tutorial is a script ``tutorials/<seed>/<name>.py`` with ``main(out_dir, quick=False)`` that writes its figures into
``out_dir`` and returns the list of files written. Its title docstring names the figures it reproduces
(``vc-fig-4.9``), says ``stand-in`` when it stands in for a figure it cannot reproduce (a photograph), and names its
outputs (``figures/vc/fig-4.9.png``). The tutorials ship inside the package (``pywarp/tutorials``); in a source
checkout the top-level ``tutorials/`` folder is used, and the committed outputs are looked for in ``figures/<seed>/``.
"""
from __future__ import annotations

import ast
import importlib.util
import json
import re
from functools import lru_cache
from importlib import resources
from pathlib import Path

from .catalogue import SEEDS

_PKG = Path(__file__).resolve().parents[1]  # the pywarp package folder


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
    return sorted(set(re.findall(rf"\b(?:{'|'.join(SEEDS)})-(?:fig|extra)-[A-Za-z0-9.\-]*[A-Za-z0-9]", doc)))


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


# --- tutorials in parallel on Dask ------------------------------------------------------------------------------------
#
# ``pywarp figures --scheduler dask[=ADDRESS]`` runs each tutorial as one task on a Dask worker (a LocalCluster of
# worker processes by default, see :func:`pywarp.core.animation.dask_client`), exactly as :func:`run` runs it in this
# process: ``main(out_dir, quick)`` writing into ``out_root/<seed>/``. A tutorial depends on nothing but its
# arguments, so the files are the same as those of a serial run. The workers write the files themselves: with an
# existing cluster (ADDRESS) the tutorials and the output folder must be at the same paths on the workers (a shared
# file system).


def run_tutorial(path: str, out_dir: str, quick: bool) -> tuple[list[str], BaseException | None]:
    """Run one tutorial (what a Dask worker runs): (files written, None), or ([], the exception) when it raised --
    the exception itself when it pickles, else a RuntimeError naming its type and message."""
    import pickle

    Path(out_dir).mkdir(parents=True, exist_ok=True)
    try:
        files = load(Path(path)).main(Path(out_dir), quick=quick) or []
    except Exception as exc:  # noqa: BLE001 - handed back to run_on_dask, reported per tutorial
        try:
            pickle.loads(pickle.dumps(exc))
        except Exception:  # noqa: BLE001 - an exception that does not survive the trip back
            exc = RuntimeError(f"{type(exc).__name__}: {exc}")
        return [], exc
    return [str(f) for f in files], None


def run_on_dask(client, paths: list[Path], out_root: Path, quick: bool = False, progress: bool = True,
                failures: list | None = None) -> list[Path]:
    """:func:`run` with every tutorial a task on the Dask cluster of ``client``; the files in the order of
    ``paths`` (as :func:`run` returns them), failures as in :func:`run`."""
    from dask.distributed import as_completed
    from tqdm import tqdm

    futures = [client.submit(run_tutorial, str(p), str(out_root / p.parent.name), bool(quick), pure=False,
                             key=f"pywarp-tutorial-{p.parent.name}-{p.stem}-{id(paths)}") for p in paths]
    results = {}
    try:
        with tqdm(total=len(futures), desc="figures", unit="tutorial", disable=not progress) as bar:
            for fut in as_completed(futures):
                results[fut.key] = fut.result()
                bar.update(1)
    finally:
        client.cancel([f for f in futures if not f.done()])
    written = []
    for p, fut in zip(paths, futures):
        files, exc = results[fut.key]
        if exc is not None:
            if failures is None:
                raise exc
            failures.append((p, exc))
            continue
        written += [Path(f) for f in files]
    return written


# --- status of every figure and measurement -------------------------------------------------------------------------

_FIG_RE = re.compile(r"\b(?:vc|pt|rr|oc)-(?:fig|extra)-[A-Za-z0-9.\-]*[A-Za-z0-9]")
_OUT_RE = re.compile(r"figures/[a-z]+/([\w.\-]+\.png)")

#: The statuses :func:`status` gives: figures (and the tutorials' extra figures), then measurements.
FIGURE_STATUSES = ("reproduced", "stand-in", "not reproduced")
MEASUREMENT_STATUSES = ("measured", "not measured")


def source_root() -> Path | None:
    """The source checkout (``tutorials/`` and the committed ``figures/``) when running from one, else None."""
    root = _PKG.parent
    return root if tutorial_dir() == root / "tutorials" and (root / "figures").is_dir() else None


@lru_cache(maxsize=None)
def _reasons() -> dict:
    text = resources.files("pywarp").joinpath("data/figure_status.json").read_text(encoding="utf-8")
    return {k: v for k, v in json.loads(text).items() if not k.startswith("_")}


def tutorial_info(path: Path) -> dict:
    """What a tutorial's docstring says: ``figures`` (IDs), ``stand_in`` (its title says it stands in for them),
    ``outputs`` (file names under figures/<seed>/) and ``title`` (its first paragraph, one line). ``stand_in`` is
    the sentence that says what stands in (from "stand-in"), or False."""
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
    paragraphs = [p.strip() for p in doc.split("\n\n") if p.strip()]
    title = " ".join(paragraphs[0].split()) if paragraphs else ""
    stand_in: str | bool = False  # the sentence that says what stands in
    if "stand-in" in title.lower():
        stand_in = title[title.lower().index("stand-in"):]
    else:
        for par in paragraphs:
            if par.lower().startswith("stand-in:"):
                text = " ".join(par.split())
                stand_in = text.split(". ")[0].rstrip(".") + "."
                break
    return {"figures": sorted(set(_FIG_RE.findall(doc))), "stand_in": stand_in, "title": title,
            "outputs": sorted(set(_OUT_RE.findall(doc)))}


def _outputs_of(fid: str, outputs: list[str]) -> list[str]:
    """The outputs of a tutorial that belong to figure ``fid`` (vc-fig-4.9 -> fig-4.9.png, fig-4.9-errata.png);
    all of them when none is named after it."""
    stem = fid.split("-", 1)[1]  # fig-4.9, extra-curl-texture
    mine = [o for o in outputs if o[:-4] == stem or o.startswith(stem + "-")]
    return mine or list(outputs)


def _range_ids(cid: str) -> list[str]:
    """``vc-M4..M9`` (a tutorial index key) -> vc-M4, ..., vc-M9; other IDs unchanged."""
    m = re.fullmatch(r"((?:vc|pt|rr|oc)-)([A-Za-z]*)(\d+)\.\.([A-Za-z]*)(\d+)", cid)
    if not m:
        return [cid]
    return [f"{m[1]}{m[2]}{i}" for i in range(int(m[3]), int(m[5]) + 1)]


def status(seed: str | None = None) -> list[dict]:
    """The true status of every catalogued figure and measurement (of ``seed``, or all), and of the tutorials'
    extra figures: by text, figures then extras then measurements, each in natural ID order. Each row: ``id``, ``seed``, ``kind`` (figure, extra, measurement),
    ``title``, ``status`` (one of FIGURE_STATUSES or MEASUREMENT_STATUSES), ``tutorial`` (repository-relative
    path or None), ``outputs`` (file names), ``committed`` (per output: True/False in a source checkout, None when
    it cannot be checked), ``note`` (why not reproduced, what stands in, how it is measured)."""
    from .catalogue import catalogue, sort_key

    if seed is not None and seed not in SEEDS:
        raise ValueError(f"--seed must be one of {', '.join(SEEDS)}, got {seed!r}")
    cat = catalogue()
    reasons = _reasons()
    root = source_root()
    by_fig: dict[str, tuple[Path, dict]] = {}
    for p in tutorials(seed):
        info = tutorial_info(p)
        for fid in info["figures"]:
            by_fig.setdefault(fid, (p, info))
    used_by: dict[str, list[str]] = {}
    for key, paths in cat.get("tutorials", {}).items():
        for cid in _range_ids(key):
            used_by.setdefault(cid, [])
            used_by[cid] += [t for t in paths if t not in used_by[cid]]
    ids = {cid: e for cid, e in cat["ids"].items()
           if e["kind"] in ("figure", "measurement") and (seed is None or e["seed"] == seed)}
    for fid in by_fig:
        if "-extra-" in fid and fid not in ids:
            ids[fid] = {"seed": fid.split("-", 1)[0], "title": "(extra, not a figure of the text)", "kind": "extra"}
    rows = []
    rank = {"figure": 0, "extra": 1, "measurement": 2}
    for cid, e in sorted(ids.items(), key=lambda kv: (sort_key(kv[0])[:2], rank[kv[1]["kind"]], sort_key(kv[0]))):
        row = {"id": cid, "seed": e["seed"], "kind": e["kind"], "title": e["title"], "status": "",
               "tutorial": None, "outputs": [], "committed": None, "note": ""}
        if e["kind"] == "measurement":
            note = reasons.get(cid, "")
            row["status"] = "measured" if note.startswith("measured") else "not measured"
            row["note"] = note.split(":", 1)[1].strip() if ":" in note else (note or "no benchmark measures it yet")
            row["tutorial"] = (used_by.get(cid) or [None])[0]
        elif cid in by_fig:
            path, info = by_fig[cid]
            row["tutorial"] = f"tutorials/{path.parent.name}/{path.name}"
            row["outputs"] = _outputs_of(cid, info["outputs"])
            if root is not None:
                row["committed"] = [(root / "figures" / e["seed"] / o).is_file() for o in row["outputs"]]
            if info["stand_in"]:
                row["status"] = "stand-in"
                row["note"] = info["stand_in"] if isinstance(info["stand_in"], str) else reasons.get(cid, "")
            else:
                row["status"] = "reproduced"
                row["note"] = "in kind" if "in kind" in info["title"] else ""
            if row["committed"] is not None and not all(row["committed"]):
                missing_out = [o for o, ok in zip(row["outputs"], row["committed"]) if not ok]
                row["note"] = "; ".join(x for x in (row["note"], "not committed: " + ", ".join(missing_out)) if x)
        else:
            row["status"] = "not reproduced"
            row["note"] = reasons.get(cid, "no tutorial yet")
        rows.append(row)
    return rows
