"""The ``pywarp`` command.

    pywarp equations [--seed KEY] [--missing]     traceability matrix: ID, title, C, Warp, tests, figures
    pywarp figures [--seed KEY] [--quick] [--out DIR] [--only fig-4.9 ...]
    pywarp bench tiles [--width W] [--height H] [--repeat N] [--workers N] [--device D] [--json]

Bad arguments print one line ``pywarp: error: ...`` naming the option and exit with status 2.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

SEEDS = ("vc", "pt", "rr", "oc")


def _positive_int(name):
    def parse(text):
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be an integer, got {text!r}") from None
        if v < 1:
            raise argparse.ArgumentTypeError(f"{name} must be >= 1, got {v}")
        return v
    return parse


def _short(items, limit=2):
    if not items:
        return "-"
    names = [i.split("::")[-1] if "::" in i else Path(i).name for i in items]
    return ", ".join(names[:limit]) + (f" (+{len(names) - limit})" if len(names) > limit else "")


def cmd_equations(args) -> int:
    from .equations import catalogue, missing, registry

    if args.missing:
        rows = missing(args.seed)
        for cid, e in rows:
            title = e["title"] if len(e["title"]) <= 60 else e["title"][:57] + "..."
            print(f"{cid:<16} {e['kind']:<12} {title:<60} {e['reason'] or 'NOT IMPLEMENTED YET'}")
        todo = sum(1 for _, e in rows if not e["reason"])
        print(f"{len(rows)} catalogued IDs without an implementation" + (f" in {args.seed}" if args.seed else "")
              + f": {len(rows) - todo} not computational (reason given), {todo} not implemented yet")
        return 0
    reg = registry()
    ids = catalogue()["ids"]
    rows = [eq for eq in reg.values() if args.seed is None or eq.id.startswith(args.seed + "-")]
    header = f"{'ID':<10} {'title':<44} {'C':<22} {'Warp':<24} {'tests':<40} figures"
    print(header)
    print("-" * len(header))
    for eq in rows:
        warp_name = f"{eq.warp.func.__module__.rsplit('.', 1)[-1]}.{eq.warp.key}"
        title = eq.title if len(eq.title) <= 44 else eq.title[:41] + "..."
        print(f"{eq.id:<10} {title:<44} {eq.c_symbol or '-':<22} {warp_name:<24} {_short(eq.tests):<40} "
              f"{_short(eq.figures)}")
    total = sum(1 for e in ids.values() if args.seed is None or e["seed"] == args.seed)
    print(f"{len(rows)} implemented of {total} catalogued IDs" + (f" in {args.seed}" if args.seed else "")
          + "; `pywarp equations --missing` lists the rest")
    return 0


def cmd_figures(args) -> int:
    from . import figures

    paths = figures.select(args.seed, args.only)
    if not paths:
        print("no tutorials found", file=sys.stderr)
        return 1
    written = figures.run(paths, Path(args.out), quick=args.quick, progress=not args.no_progress)
    print(f"{len(written)} figure files from {len(paths)} tutorials written under {args.out}")
    return 0


def cmd_bench(args) -> int:
    from . import bench

    bench.main(args.name, as_json=args.json, width=args.width, height=args.height, repeat=args.repeat,
               workers=args.workers, device=args.device)
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="pywarp", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    e = sub.add_parser("equations", help="print the traceability matrix of the catalogued equations")
    e.add_argument("--seed", choices=SEEDS, help="only this text (vc, pt, rr, oc); default: all")
    e.add_argument("--missing", action="store_true", help="list the catalogued IDs not implemented yet")
    e.set_defaults(run=cmd_equations)

    f = sub.add_parser("figures", help="regenerate the figures by running the tutorials")
    f.add_argument("--seed", choices=SEEDS, help="only the tutorials of this text; default: all")
    f.add_argument("--quick", action="store_true", help="small sizes, for a fast check (seconds per tutorial)")
    f.add_argument("--out", default="figures", help="output folder; figures go to OUT/<seed>/ (default: figures)")
    f.add_argument("--only", nargs="+", metavar="FIG", help="only these figures, e.g. fig-4.9 or vc-fig-4.9")
    f.add_argument("--no-progress", action="store_true", help="no progress bar")
    f.set_defaults(run=cmd_figures)

    b = sub.add_parser("bench", help="run a benchmark and print ratios measured in one run")
    b.add_argument("name", choices=("tiles",), help="tiles: tile-parallel launcher vs one launch")
    b.add_argument("--width", type=_positive_int("--width"), default=960, help="frame width in pixels (default 960)")
    b.add_argument("--height", type=_positive_int("--height"), default=540, help="frame height in pixels (default 540)")
    b.add_argument("--repeat", type=_positive_int("--repeat"), default=5, help="timed repetitions, best kept (default 5)")
    b.add_argument("--workers", type=_positive_int("--workers"), default=None,
                   help="worker threads (default: one per core)")
    b.add_argument("--device", default="cpu", help="Warp device: cpu (default) or cuda:N where present")
    b.add_argument("--json", action="store_true", help="print one JSON object as the last line")
    b.set_defaults(run=cmd_bench)
    return p


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except (ValueError, TypeError, OSError) as exc:
        parser.exit(2, f"pywarp: error: {exc}\n")


if __name__ == "__main__":
    sys.exit(main())
