"""``pywarp equations``: the traceability matrix of the catalogue.

    pywarp equations                 every implemented catalogue ID: title, C function, Warp function, tests, tutorials
    pywarp equations --missing       the computational IDs (equations, algorithms, code listings, tables) not implemented
    pywarp equations --figures       every figure and measurement with its true status: reproduced (by which tutorial,
                                     committed output), stand-in, or not reproduced (why); measured or not
    --seed vc|pt|rr|oc               one text only
    --format table|csv|markdown|json table (default) fits the terminal; the others give every cell in full

One row per catalogue ID, in natural order (vc-A3 before vc-A28); an entry that answers several IDs (the camera of
vc-A25 and pt-code-7.2) has a row for each. The table is as wide as ``--width``, else ``$COLUMNS``, else the terminal;
when the output is not a terminal (a pipe, a file) and neither is set, cells are not truncated. Cells too long for
their column end in an ellipsis; use ``--format csv``/``json`` for scripts.
"""
from __future__ import annotations

import argparse
import csv
import json
import os
import shutil
import sys
import textwrap
from pathlib import Path

FORMATS = ("table", "csv", "markdown", "json")
MIN_FLEX = 8  # a truncated column keeps at least this many characters


# --- data ------------------------------------------------------------------------------------------------------------

def _names(items: list[str]) -> list[str]:
    return [i.split("::")[-1] if "::" in i else Path(i).name for i in items]


def _short(items: list[str], limit: int = 2) -> str:
    if not items:
        return "-"
    names = _names(items)
    return ", ".join(names[:limit]) + (f" (+{len(names) - limit})" if len(names) > limit else "")


def implemented_rows(seed: str | None = None) -> list[dict]:
    """One row per implemented catalogue ID (natural order)."""
    from ..core.catalogue import catalogue
    from ..core.registry import registry

    ids = catalogue()["ids"]
    rows = []
    for cid, eq in registry().items():  # natural order; an entry appears under each of its IDs
        e = ids.get(cid, {})
        s = e.get("seed", cid.split("-", 1)[0])
        if seed is not None and s != seed:
            continue
        rows.append({"id": cid, "entry": eq.id, "seed": s, "kind": e.get("kind", ""),
                     "title": e.get("title", eq.summary), "c": eq.c_symbol or "", "warp": eq.warp_name,
                     "tests": list(eq.tests), "figures": list(eq.figures)})
    return rows


def missing_rows(seed: str | None = None) -> list[dict]:
    """The computational catalogue IDs (COMPUTATIONAL_KINDS) without an implementation."""
    from ..core.registry import missing

    return [{"id": cid, "seed": e["seed"], "kind": e["kind"], "title": e["title"],
             "note": f"not computational: {e['reason']}" if e["reason"] else ""}
            for cid, e in missing(seed, computational=True)]


def figure_rows(seed: str | None = None) -> list[dict]:
    from ..core import figures

    return figures.status(seed)


# --- output ----------------------------------------------------------------------------------------------------------

def table_width(requested: int | None = None, stream=None) -> int | None:
    """The width to fit: ``requested`` (0 = no limit), else ``$COLUMNS``, else the terminal's width when ``stream``
    is a terminal, else None (no limit)."""
    if requested is not None:
        return requested or None
    env = os.environ.get("COLUMNS", "").strip()
    if env.isdigit() and int(env) > 0:
        return int(env)
    stream = stream or sys.stdout
    try:
        if stream.isatty():
            return shutil.get_terminal_size().columns
    except (AttributeError, ValueError, OSError):
        pass
    return None


def _ellipsis(stream) -> str:
    try:
        "\u2026".encode(getattr(stream, "encoding", None) or "ascii")
        return "\u2026"
    except (UnicodeEncodeError, LookupError):
        return "..."


def _cut(text: str, width: int, ell: str) -> str:
    if len(text) <= width:
        return text
    if width <= len(ell):
        return text[:width]
    return text[: width - len(ell)] + ell


def render_table(columns: list[tuple[str, str, float]], rows: list[dict], width: int | None,
                 ell: str = "\u2026") -> list[str]:
    """Lines of a plain-text table. ``columns``: (header, key, weight); weight 0 = never truncated. The others
    shrink, the one with the largest width/weight first, down to MIN_FLEX, until the table fits ``width``
    (a weight-2 column keeps about twice the room of a weight-1 one); lines still too wide are cut at ``width``."""
    cells = [[_cell(r[k]) for _, k, _ in columns] for r in rows]
    widths = [max([len(h)] + [len(c[i]) for c in cells]) for i, (h, _, _) in enumerate(columns)]
    sep = "  "
    if width is not None:
        excess = sum(widths) + len(sep) * (len(columns) - 1) - width
        flex = [i for i, (_, _, wt) in enumerate(columns) if wt]
        while excess > 0:
            shrinkable = [i for i in flex if widths[i] > MIN_FLEX]
            if not shrinkable:
                break
            i = max(shrinkable, key=lambda j: widths[j] / columns[j][2])
            widths[i] -= 1
            excess -= 1

    def line(values):
        parts = [_cut(v, w, ell).ljust(w) for v, w in zip(values, widths)]
        text = sep.join(parts).rstrip()
        return _cut(text, width, ell) if width is not None else text

    header = line([h for h, _, _ in columns])
    out = [header, "-" * len(header)]
    out += [line(c) for c in cells]
    return out


def _cell(v) -> str:
    if v is None:
        return "-"
    if isinstance(v, (list, tuple)):
        return _short(list(v)) if v else "-"
    return " ".join(str(v).split()) or "-"


def _flat(v) -> str:
    if v is None:
        return ""
    if isinstance(v, (list, tuple)):
        return "; ".join(str(x) for x in v)
    return str(v)


def emit(rows: list[dict], columns: list[tuple[str, str, float]], fmt: str, width: int | None, out=None) -> None:
    """Print ``rows`` as ``fmt``: a table of ``columns``; csv / markdown / json with every field in full."""
    out = out or sys.stdout
    keys = list(rows[0]) if rows else [k for _, k, _ in columns]
    if fmt == "json":
        out.write(json.dumps(rows, indent=1, ensure_ascii=False) + "\n")
    elif fmt == "csv":
        w = csv.writer(out, lineterminator="\n")
        w.writerow(keys)
        for r in rows:
            w.writerow([_flat(r[k]) for k in keys])
    elif fmt == "markdown":
        out.write("| " + " | ".join(keys) + " |\n")
        out.write("|" + "---|" * len(keys) + "\n")
        for r in rows:
            out.write("| " + " | ".join(_flat(r[k]).replace("|", "\\|").replace("\n", " ") for k in keys) + " |\n")
    else:
        for ln in render_table(columns, rows, width, _ellipsis(out)):
            out.write(ln + "\n")


# --- command ---------------------------------------------------------------------------------------------------------

def _committed(row: dict) -> str:
    if not row["outputs"]:
        return "-"
    if row["committed"] is None:
        return ", ".join(row["outputs"])
    return ", ".join(o if ok else f"{o} (not committed)" for o, ok in zip(row["outputs"], row["committed"]))


def _summary(text: str, width: int | None) -> None:
    print("\n".join(textwrap.wrap(text, width)) if width else text)


def cmd_equations(args) -> int:
    from ..core.catalogue import COMPUTATIONAL_KINDS, catalogue

    width = table_width(args.width)
    fmt = args.format
    where = f" in {args.seed}" if args.seed else ""
    if args.figures:
        rows = figure_rows(args.seed)
        if fmt == "table":
            view = [{**r, "tutorial": Path(r["tutorial"]).name if r["tutorial"] else "-", "output": _committed(r)}
                    for r in rows]
            emit(view, [("ID", "id", 0), ("kind", "kind", 0), ("status", "status", 0), ("title", "title", 2),
                        ("tutorial", "tutorial", 1), ("output", "output", 1), ("note", "note", 2)], fmt, width)
            figs = [r for r in rows if r["kind"] == "figure"]
            meas = [r for r in rows if r["kind"] == "measurement"]
            count = {s: sum(1 for r in figs if r["status"] == s) for s in ("reproduced", "stand-in", "not reproduced")}
            extras = sum(1 for r in rows if r["kind"] == "extra")
            _summary(f"{len(figs)} figures{where}: {count['reproduced']} reproduced, {count['stand-in']} stood in "
                     f"for, {count['not reproduced']} not reproduced" + (f" (+{extras} extra figures)" if extras else "")
                     + f"; {len(meas)} measurements: {sum(1 for r in meas if r['status'] == 'measured')} measured",
                     width)
        else:
            emit(rows, [], fmt, width)
        return 0
    if args.missing:
        rows = missing_rows(args.seed)
        emit(rows, [("ID", "id", 0), ("kind", "kind", 0), ("title", "title", 2), ("note", "note", 1)], fmt, width)
        if fmt == "table":
            todo = sum(1 for r in rows if not r["note"])
            _summary(f"{len(rows)} computational IDs ({', '.join(COMPUTATIONAL_KINDS)}) not implemented{where}: "
                     f"{todo} to do, {len(rows) - todo} not computational by design (note given); figures and "
                     "measurements: `pywarp equations --figures`", width)
        return 0
    rows = implemented_rows(args.seed)
    emit(rows, [("ID", "id", 0), ("title", "title", 2), ("C", "c", 1), ("Warp", "warp", 1), ("tests", "tests", 1),
                ("figures", "figures", 1)], fmt, width)
    if fmt == "table":
        total = sum(1 for e in catalogue()["ids"].values()
                    if e["kind"] in COMPUTATIONAL_KINDS and (args.seed is None or e["seed"] == args.seed))
        _summary(f"{len(rows)} implemented of {total} computational catalogued IDs{where}; "
                 "`pywarp equations --missing` lists the rest, `--figures` the figures and measurements", width)
    return 0


def _width_arg(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--width must be an integer >= 0, got {text!r}") from None
    if v < 0:
        raise argparse.ArgumentTypeError(f"--width must be an integer >= 0, got {v}")
    return v


def add_equations_command(sub) -> None:
    """Add ``equations`` to the ``pywarp`` sub-command parsers."""
    from ..core.catalogue import SEEDS

    e = sub.add_parser("equations", help="the traceability matrix: every catalogue ID with its C and Warp functions, "
                                         "tests and tutorials; --missing, --figures",
                       description=__doc__.split("\n\n")[0] + "\n\n" + __doc__.split("\n\n", 1)[1].split("\n\n")[0],
                       epilog=__doc__.split("\n\n")[2].strip(),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    e.add_argument("--seed", choices=tuple(SEEDS), help="only this text: " + ", ".join(SEEDS) + " (default: all)")
    which = e.add_mutually_exclusive_group()
    which.add_argument("--missing", action="store_true",
                       help="list the computational IDs (equations, algorithms, code listings, tables) not "
                            "implemented yet")
    which.add_argument("--figures", action="store_true",
                       help="list the figures and measurements with their status: reproduced (tutorial, committed "
                            "output), stand-in or not reproduced (why); measured or not")
    e.add_argument("--format", choices=FORMATS, default="table",
                   help="output format: table (fits the terminal), csv, markdown or json (default: table)")
    e.add_argument("--width", type=_width_arg, default=None, metavar="N",
                   help="table width in characters, 0 = no limit (default: $COLUMNS, else the terminal's width; no "
                        "limit when the output is not a terminal)")
    e.set_defaults(run=cmd_equations)
