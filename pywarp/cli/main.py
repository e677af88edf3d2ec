"""pywarp: the equations of four texts on procedural atmospheric rendering, their figures, scenes and benchmarks.

    pywarp scenes                                 the scenes: clouds (vc, default), terrain (pt), rain (rr), flight (oc)
    pywarp render [SCENE] [options]               one image of a scene (SCENE --help: its options and defaults)
    pywarp animate [SCENE] [options]              a video along the scene's camera path
    pywarp view [SCENE] [options]                 the scene in an interactive window
    pywarp bench [SCENE] [BENCHMARK] [options]    a benchmark of a scene (bench --help lists them)
    pywarp equations [--seed KEY] [--missing | --figures] [--format table|csv|markdown|json]
                                                  traceability matrix: ID, title, C, Warp, tests, figures
    pywarp figures [--seed KEY] [--quick] [--out DIR] [--only fig-4.9 ...]   regenerate the figures
    pywarp notebooks [--out DIR] [--seed KEY] [--quick]   every figure tutorial as a Jupyter notebook
    pywarp cache info|clear [--json]              the on-disk texture cache: entries, size, cap; remove them

Exit status: 0 success (bare pywarp prints this help and exits 0, like --help); 1 a command failed; 2 a bad argument
or value: one line "pywarp <command>: error: --option ..." on stderr, no traceback (argparse's own errors too); 130
Ctrl-C and 143 SIGTERM: one line "pywarp: interrupted" / "pywarp: terminated", no traceback, and no output file or
hidden temporary file left behind (an animation written as numbered frames keeps the frames it finished). Set
PYWARP_DEBUG=1 for tracebacks (the exit statuses stay the same). Options are never abbreviated; a misspelt one is
named with the closest match.
"""
from __future__ import annotations

import argparse
import os
import re
import signal
import sys
import traceback
from pathlib import Path

from ..core.catalogue import SEEDS as _SEED_TEXTS
from ..core.params import did_you_mean
from ..core.output import clear_pending, note_interrupt, raise_pending
from .cache import add_cache_command
from .equations import add_equations_command
from .notebooks import add_notebooks_command

SEEDS = tuple(_SEED_TEXTS)

#: Exit statuses (see the module docstring).
EXIT_USAGE = 2
EXIT_INTERRUPTED = 130  # 128 + SIGINT
EXIT_TERMINATED = 128 + signal.SIGTERM  # 143


class Terminated(KeyboardInterrupt):
    """Raised in the main thread by the SIGTERM handler of :func:`main`; a KeyboardInterrupt, so everything that
    cleans up after Ctrl-C (the atomic writers, ffmpeg) cleans up after SIGTERM too."""


_ARGPARSE_REWRITES = [  # argparse's wording -> ours: the option first, what is expected, what was given
    (re.compile(r"^argument (?P<opt>[^:]+): invalid int value: (?P<v>.*)$"), "{opt} must be an integer, got {v}"),
    (re.compile(r"^argument (?P<opt>[^:]+): invalid float value: (?P<v>.*)$"), "{opt} must be a number, got {v}"),
    (re.compile(r"^argument (?P<opt>[^:]+): invalid choice: (?P<v>.*?) \(choose from (?P<c>.*)\)$"),
     "{opt} must be one of {c}, got {v}{hint}"),
    (re.compile(r"^argument (?P<opt>[^:]+): expected one argument$"), "{opt} needs a value"),
    (re.compile(r"^argument (?P<opt>[^:]+): expected at least one argument$"), "{opt} needs at least one value"),
    (re.compile(r"^argument (?P<opt>[^:]+): not allowed with argument (?P<o>.*)$"), "{opt} cannot be used with {o}"),
    (re.compile(r"^argument (?P<opt>[^:]+): ignored explicit argument (?P<v>.*)$"), "{opt} takes no value, got {v}"),
    (re.compile(r"^the following arguments are required: (?P<opt>.*)$"), "missing argument: {opt}"),
    (re.compile(r"^unrecognized arguments: (?P<opt>.*)$"), "unknown argument: {opt}"),
    (re.compile(r"^argument (?P<opt>[^:]+): (?P<msg>.*)$"), "{opt}: {msg}"),
]


def _one_line(message: str) -> str:
    return " ".join(str(message).split())


def usage_message(message: str) -> str:
    """argparse's error wording rewritten to name the option first (``--width must be an integer, got 'x'``)."""
    message = _one_line(message)
    for pattern, fmt in _ARGPARSE_REWRITES:
        m = pattern.match(message)
        if m:
            d = m.groupdict()
            if "c" in d:
                choices = [x.strip().strip("'") for x in d["c"].split(",")]
                d["c"] = ", ".join(choices)
                d["hint"] = did_you_mean(d["v"].strip("'"), choices)
            if "msg" in d and d["msg"].startswith(d["opt"].split("/")[0]):
                return d["msg"]  # a type function's own message already names the option
            return fmt.format(**d)
    return message


def unknown_arguments_message(parser: argparse.ArgumentParser, extra: list[str]) -> str:
    """The error for arguments a command does not know, with the closest option of that command for a misspelt one
    (``--widht`` -> ``--width``)."""
    options = [o for action in parser._actions for o in action.option_strings]
    hints = "".join(did_you_mean(a.split("=", 1)[0], options) for a in extra if a.startswith("--"))
    return f"unrecognized arguments: {' '.join(extra)}{hints}"


class Parser(argparse.ArgumentParser):
    """ArgumentParser whose every error is one line ``<prog>: error: <message>`` on stderr, exit status 2 -- no usage
    block. Sub-command parsers are of this class too (add_subparsers uses the parent's class). Options are never
    abbreviated (``--wid 64`` is an error, not ``--width 64``): an abbreviation that works today would break as soon
    as a scene adds an option with the same prefix."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message):  # noqa: D401 - argparse API
        self.exit(EXIT_USAGE, f"{self.prog}: error: {usage_message(message)}\n")


def cmd_figures(args) -> int:
    from ..core import figures
    from ..core import animation
    from ..core.output import check_output_dir

    kind, address = animation.parse_scheduler(args.scheduler)
    if args.dask_workers is not None and not 1 <= args.dask_workers <= 4096:
        raise ValueError(f"--dask-workers must be in [1, 4096], got {args.dask_workers}")
    check_output_dir(args.out, "--out")
    paths = figures.select(args.seed, args.only)
    if not paths:
        print("no tutorials found", file=sys.stderr)
        return 1
    failures = []
    if kind == "dask":  # one task per tutorial on the workers (see pywarp.core.figures.run_on_dask)
        client, cluster = animation.dask_client(address, args.dask_workers or min(len(paths), os.cpu_count() or 1))
        try:
            written = figures.run_on_dask(client, paths, Path(args.out), quick=args.quick,
                                          progress=not args.no_progress, failures=failures)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    else:
        written = figures.run(paths, Path(args.out), quick=args.quick, progress=not args.no_progress,
                              failures=failures)
    print(f"{len(written)} figure files from {len(paths) - len(failures)} tutorials written under {args.out}")
    for path, exc in failures:
        print(f"pywarp figures: error: {path.name}: {type(exc).__name__}: {_one_line(exc)}", file=sys.stderr)
    return 1 if failures else 0


def build_parser(help_for: str | None = None) -> argparse.ArgumentParser:
    """The ``pywarp`` parser; ``help_for`` a scene name: built to print that scene's ``--help`` (see
    :func:`pywarp.cli.scene.add_scene_commands`)."""
    from .. import __version__

    p = Parser(prog="pywarp", description=__doc__.split("\n\n")[0], epilog="\n\n".join(__doc__.split("\n\n")[1:3]),
               formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action="version", version=f"pywarp {__version__}",
                   help="print the package version and exit")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND", parser_class=Parser)
    p._commands = sub  # main() routes errors to the command's own parser

    add_equations_command(sub)

    f = sub.add_parser("figures", help="regenerate the figures by running the tutorials")
    f.add_argument("--seed", choices=SEEDS, help="only the tutorials of this text: " + ", ".join(SEEDS)
                   + " (default: all)")
    f.add_argument("--quick", action="store_true", help="small sizes, for a fast check (seconds per tutorial)")
    f.add_argument("--out", default="figures", metavar="DIR",
                   help="output folder, checked writable first; figures go to DIR/<seed>/ (default: figures)")
    f.add_argument("--only", nargs="+", metavar="FIG", help="only these figures, e.g. fig-4.9 or vc-fig-4.9")
    f.add_argument("--no-progress", action="store_true", help="no progress bar")
    f.add_argument("--scheduler", default="local", metavar="local|dask[=ADDRESS]",
                   help="local: one tutorial after the other in this process (default); dask: each tutorial a task "
                        "on the workers of a Dask LocalCluster (--dask-workers processes), or of the cluster at "
                        "ADDRESS (dask=tcp://host:8786; the tutorials and --out at the same paths on the workers). "
                        "Same files as a local run")
    f.add_argument("--dask-workers", type=int, default=None, metavar="N",
                   help="worker processes of the LocalCluster (default: one per core, at most one per tutorial)")
    f.set_defaults(run=cmd_figures)
    add_notebooks_command(sub)
    add_cache_command(sub)

    from .scene import add_scene_commands  # scenes, render, animate, bench: built from the scene registry

    add_scene_commands(sub, help_for)
    return p


def _raise_terminated(signum, frame):
    # further SIGINT/SIGTERM while the writers clean up are ignored; main() restores the defaults afterwards. The
    # interrupt is also recorded: raised inside a __del__, Python drops it, and the writers and main() raise it again
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    note_interrupt(Terminated)
    raise Terminated()


def _raise_interrupted(signum, frame):
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    note_interrupt(KeyboardInterrupt)
    raise KeyboardInterrupt()


def _quiet_dropped_interrupts(hook):
    """A ``sys.unraisablehook`` that passes everything to ``hook`` except an interrupt the signal handlers raised
    while Python ran a ``__del__`` (e.g. a Warp array's): Python cannot raise it there and would print it with a
    traceback; the handler recorded it (note_interrupt) and main() raises it again, so the command still ends with
    its one line."""
    def unraisable(u):
        if u.exc_type is not None and issubclass(u.exc_type, KeyboardInterrupt):
            return
        hook(u)
    return unraisable


def _error_text(exc: BaseException) -> str:
    if isinstance(exc, OSError) and exc.strerror and exc.filename is not None:
        return f"{exc.strerror}: {exc.filename}"
    if isinstance(exc, OSError) and exc.strerror:
        return exc.strerror
    return str(exc) or type(exc).__name__


def main(argv: list[str] | None = None) -> int:
    """Run the command; return its exit status (see the module docstring).

    Called as the program (``argv`` None, the console script and ``python -m pywarp``), an interrupt ends the process
    with ``os._exit`` once the output files are cleaned up, so that render threads still busy with a tile do not
    delay it; called with ``argv`` (tests, scripts) it returns 130 / 143 instead."""
    as_program = argv is None
    argv = sys.argv[1:] if argv is None else list(argv)
    clear_pending()
    handlers = {}
    if sys.platform != "win32":
        for signum, handler in ((signal.SIGTERM, _raise_terminated), (signal.SIGINT, _raise_interrupted)):
            try:  # only the main thread may install handlers; a signal ignored by the parent (nohup) stays ignored
                if signal.getsignal(signum) is not signal.SIG_IGN:
                    handlers[signum] = signal.signal(signum, handler)
            except ValueError:
                break
    old_unraisable = sys.unraisablehook
    if handlers:
        sys.unraisablehook = _quiet_dropped_interrupts(old_unraisable)
    command = None
    try:
        try:
            from .scene import help_scene

            scene_help = help_scene(argv)  # `pywarp render terrain --help`: terrain's options and defaults
            parser = build_parser(scene_help) if scene_help else build_parser()
            if not argv:
                parser.print_help()
                return 0
            args, extra = parser.parse_known_args(argv)
            command = args.command
            sub = parser._commands.choices[command]
            if extra:
                sub.error(unknown_arguments_message(sub, extra))
            try:
                status = args.run(args)
                raise_pending()  # an interrupt whose first raise was dropped ends the command as interrupted
                return status
            except (ValueError, TypeError, OSError) as exc:
                if isinstance(exc, BrokenPipeError):
                    raise
                if os.environ.get("PYWARP_DEBUG"):  # the traceback, then the same line and exit status as without
                    traceback.print_exc()
                sub.exit(EXIT_USAGE if not isinstance(exc, OSError) or exc.errno is None else 1,
                         f"{sub.prog}: error: {_one_line(_error_text(exc))}\n")
        except BrokenPipeError:  # `pywarp equations | head`: the reader left; not an error of ours
            try:
                sys.stdout = open(os.devnull, "w")
            except OSError:
                pass
            return 0
    except KeyboardInterrupt as exc:
        from ..core.output import remove_temporaries

        remove_temporaries()
        code, word = ((EXIT_TERMINATED, "terminated") if isinstance(exc, Terminated)
                      else (EXIT_INTERRUPTED, "interrupted"))
        _finish_interrupt(code, word, as_program)
        return code
    finally:
        clear_pending()
        sys.unraisablehook = old_unraisable
        for signum, old in handlers.items():
            try:
                signal.signal(signum, old)
            except (ValueError, TypeError):
                pass


def _finish_interrupt(code: int, word: str, as_program: bool) -> None:
    try:
        sys.stdout.flush()
    except (OSError, ValueError):
        pass
    try:
        sys.stderr.write(f"\npywarp: {word}\n" if _on_partial_line() else f"pywarp: {word}\n")
        sys.stderr.flush()
    except (OSError, ValueError):
        pass
    if as_program:
        os._exit(code)


def _on_partial_line() -> bool:
    """Whether stderr is a terminal (a progress bar may be mid-line there)."""
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


if __name__ == "__main__":
    sys.exit(main())
