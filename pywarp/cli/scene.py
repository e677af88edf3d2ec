"""``pywarp scenes``, ``pywarp render|animate [SCENE]`` and ``pywarp bench [SCENE] [BENCHMARK]``, built from the scene
registry (:mod:`pywarp.core.scenes`) and the settings' parameter specs (:mod:`pywarp.core.params`).

The scene is optional and defaults to ``clouds``, so ``pywarp render``, ``pywarp render --sun-elevation 8 --out
dawn.png``, ``pywarp animate --frames 96 --out x.mp4`` and ``pywarp bench cloudscape --json`` name no scene. Every
settings field with an option is an option of ``render`` and ``animate``; values are parsed and validated by the
specs, and a bad one raises ValueError naming the option (``--turbidity must be in [2, 10], got 11``), which
:func:`pywarp.cli.main.main` prints as one line and exit status 2. ``--out`` is checked before any work.
"""
from __future__ import annotations

import argparse
import dataclasses
import os
import sys
import textwrap
from dataclasses import dataclass

from ..core.params import Settings, add_options, from_options, option_message, param, specs
from ..core.scenes import DEFAULT_SCENE, scene as get_scene, scenes as all_scenes
from ..core.timing import BUSY_LOAD_PER_CORE, busy, load_average, say


# --- the command's own options, declared like settings -----------------------------------------------------------------

@dataclass(frozen=True)
class AnimateOptions(Settings):
    """Options of ``pywarp animate`` besides the scene's settings."""

    frames: int = param(96, unit="frames", kind="int", lo=1, hi=100000, doc="number of frames",
                        reason="96: 4 s at 24 fps, enough to climb through the cloud layer")
    fps: float = param(24.0, unit="1/s", lo=0.01, hi=240.0, doc="frames per second of the video",
                       reason="24: film rate; at least 0.01 (100 s a frame): GIF frame delays end at 655.35 s and "
                              "H.264 encoders refuse time bases far below that")
    time_scale: float = param(20.0, unit="s per s", lo=0.0, hi=1e6,
                              doc="simulated seconds per video second (the wind); 0 freezes the weather",
                              reason="20: at 30 km/h the clouds drift visibly within a few seconds of video")


@dataclass(frozen=True)
class BenchOptions(Settings):
    """Options of ``pywarp bench``; each benchmark takes the ones it lists (its defaults differ)."""

    width: int = param(960, unit="px", kind="int", lo=1, hi=8192, doc="frame width", default_text="per benchmark",
                       reason="the benchmark's own default (listed with it)")
    height: int = param(540, unit="px", kind="int", lo=1, hi=8192, doc="frame height", default_text="per benchmark",
                        reason="the benchmark's own default (listed with it)")
    repeat: int = param(2, kind="int", lo=1, hi=1000, doc="timed repetitions, the best kept (after a warm-up)",
                        default_text="per benchmark",
                        reason="the benchmark's own default (listed with it)")
    workers: int | None = param(None, kind="int", lo=1, hi=4096, optional=True, default_text="one per core",
                                doc="worker threads of the tile launcher", reason="None: one per core")
    spp: int = param(1024, kind="int", lo=1, hi=65536, doc="paths per pixel of the path-traced references",
                     default_text="per benchmark", reason="the benchmark's own default (listed with it)")
    baseline: str | None = param(None, kind="str", optional=True, default_text="none",
                                 doc="another Python interpreter (a venv with another version of this project "
                                     "installed): the benchmark runs there too, interleaved with this one, and "
                                     "both are printed with the ratios",
                                 reason="None: this installation only")


def _check_device(device: str, option: str = "--device") -> str:
    from ..core.runtime import resolve_device

    try:
        return resolve_device(device)
    except (ValueError, TypeError):
        import warp as wp

        names = [d.alias for d in wp.get_devices()]
        raise ValueError(f"{option} must be one of {', '.join(map(repr, names))}, got {device!r}") from None


# --- scene options: the union over the registered scenes ------------------------------------------------------------------

def _dest(option: str) -> str:
    return "opt_" + option.lstrip("-").replace("-", "_")


def _add_scene_options(parser: argparse.ArgumentParser, command: str, only: str | None = None) -> None:
    """One option per settings field of every scene (shared option strings added once), or of the scene ``only``
    (the help of ``pywarp <command> <scene> --help``: that scene's options with that scene's defaults). Defaults are
    not stored in the namespace: each scene's own defaults apply (shown in the help)."""
    added, groups = set(), {}
    chosen = [get_scene(only)] if only is not None else list(all_scenes().values())
    for sc in chosen:
        exclude = sc.command_exclude.get(command, ())
        defaults = {**(view_defaults(sc) if command == "view" else {}), **sc.command_defaults.get(command, {})}
        starts = set(sc.path().start_fields) if (command == "animate" and sc.paths) else set()
        for p in specs(sc.settings):
            opt = p.option
            if opt is None or p.name in exclude or opt in added:
                continue
            added.add(opt)
            title = p.group or "settings"
            if only is None and len(all_scenes()) > 1 and sc.name != DEFAULT_SCENE:
                title = f"{sc.name}: {title}"
            if title not in groups:
                groups[title] = parser.add_argument_group(title)
            text = p.help(defaults.get(p.name, dataclasses.MISSING))
            if p.name in starts:
                text += "; the start of the camera path"
            if p.kind == "bool":
                groups[title].add_argument(opt, dest=_dest(opt), action=argparse.BooleanOptionalAction,
                                           default=argparse.SUPPRESS, help=text)
            elif p.kind == "mapping":  # repeatable KEY=VALUE
                groups[title].add_argument(opt, dest=_dest(opt), action="append", default=argparse.SUPPRESS,
                                           metavar=p.metavar(), help=text + " (repeatable)")
            else:
                groups[title].add_argument(opt, dest=_dest(opt), default=argparse.SUPPRESS, metavar=p.metavar(),
                                           help=text)


def help_scene(argv: list[str]) -> str | None:
    """The scene whose options ``argv`` asks to see: ``pywarp render|animate|view [SCENE] ... --help`` (the scene
    named right after the command, else the default scene); None when ``argv`` asks for no such help."""
    if len(argv) < 2 or argv[0] not in ("render", "animate", "view") or not {"-h", "--help"} & set(argv):
        return None
    return argv[1] if argv[1] in all_scenes() else DEFAULT_SCENE


def settings_from_args(sc, args: argparse.Namespace, command: str, defaults: dict | None = None):
    """The scene's settings from the parsed options: every given option parsed and validated (errors name it), the
    command's defaults (``defaults`` under them), then the settings' own checks (errors reworded to name the
    option)."""
    options = {p.name: p.option for p in specs(sc.settings) if p.option is not None}
    allowed = {o for n, o in options.items() if n not in sc.command_exclude.get(command, ())}
    given = {k[4:] for k in vars(args) if k.startswith("opt_")}
    for dest in sorted(given):
        if not any(_dest(o)[4:] == dest for o in allowed):
            raise ValueError(f"--{dest.replace('_', '-')} is not an option of scene {sc.name!r}")
    values = {**(defaults or {}), **sc.command_defaults.get(command, {})}
    for p in specs(sc.settings):
        opt = options.get(p.name)
        if opt is None or opt not in allowed or not hasattr(args, _dest(opt)):
            continue
        raw = getattr(args, _dest(opt))
        values[p.name] = raw if p.kind == "bool" else p.parse(raw, opt)
    try:
        settings = sc.settings(**values)
    except (ValueError, TypeError) as exc:
        raise type(exc)(option_message(str(exc), options)) from None
    if hasattr(settings, "device"):
        _check_device(settings.device, options.get("device", "--device"))
    return settings


def _scene_arg(parser: argparse.ArgumentParser) -> None:
    names = ", ".join(all_scenes())
    parser.add_argument("scene", nargs="?", default=None, metavar="SCENE",
                        help=f"the scene: {names} (default: {DEFAULT_SCENE}); `pywarp scenes` lists them")


def _progress_bar(total, desc: str, unit: str, disable: bool):
    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit=unit, disable=disable, dynamic_ncols=True,
                bar_format="{l_bar}{bar}| {n:.0f}/{total:.0f} {unit} [{elapsed}<{remaining}{postfix}]")


# --- commands --------------------------------------------------------------------------------------------------------------

def cmd_scenes(args) -> int:
    rows = []
    for sc in all_scenes().values():
        rows.append({"name": sc.name, "default": sc.name == DEFAULT_SCENE, "description": sc.description,
                     "settings": sc.settings.__name__, "paths": list(sc.paths), "default_path": sc.default_path,
                     "benchmarks": list(sc.benchmarks), "options": sum(p.option is not None
                                                                       for p in specs(sc.settings))})
    if args.json:
        import json

        print(json.dumps(rows))
        return 0
    for r in rows:
        print(f"{r['name']}{' (default)' if r['default'] else ''}: {r['description']}")
        print(f"    settings   {r['settings']} ({r['options']} options: pywarp render {r['name']} --help)")
        print(f"    paths      {', '.join(r['paths']) or '-'} (animate uses {r['default_path']})")
        print(f"    benchmarks {', '.join(r['benchmarks']) or '-'} (pywarp bench {r['name']} NAME)")
    return 0


def cmd_render(args) -> int:
    from ..core import linear
    from ..core.output import IMAGE_SUFFIXES, check_output_path

    sc = get_scene(args.scene)
    out = check_output_path(args.out or sc.outputs.get("render", f"{sc.name}.png"),
                            IMAGE_SUFFIXES + linear.LINEAR_SUFFIXES)
    settings = settings_from_args(sc, args, "render")
    height = getattr(settings, "height", 1)
    with _progress_bar(height, "render", "rows", args.no_progress) as bar:
        # what a first run spends its time on before the first row: the scene's inputs (noise textures, cloud
        # arrays: generated once, then cached) and Warp's kernels (compiled once, then loaded from its cache)
        bar.set_postfix_str("preparing the scene (the first run generates its textures)")
        tech = sc.technique(settings)
        if linear.is_linear(out):
            linear.check_linear(tech, sc.name)
        size = f"{settings.width}x{settings.height}"
        if getattr(settings, "accumulate", 1) > 1:
            size += f", {settings.accumulate} frames"
        bar.set_postfix_str(f"{size}, loading the kernels (the first run compiles them)")
        started = []

        def progress(fraction):
            if not started:  # the first band is done: the kernels are loaded
                started.append(True)
                bar.set_postfix_str(size)
            bar.update(fraction * height)

        if getattr(settings, "accumulate", 1) > 1:  # a still averaged over jittered frames (clouds: --accumulate)
            img = tech.render_accumulated(None, settings.accumulate, progress=progress,
                                          encode=not linear.is_linear(out))
        elif linear.is_linear(out):
            img = linear.render_linear(tech, progress=progress)
        else:
            img = tech.render(progress=progress)
        bar.n = height
        bar.refresh()
    linear.write_image(out, img, args.exr_precision)
    print(f"wrote {out} ({img.shape[1]}x{img.shape[0]}, scene {sc.name}"
          + (f", {settings.accumulate} frames accumulated" if getattr(settings, "accumulate", 1) > 1 else "")
          + (", display-linear" if linear.is_linear(out) else "") + ")")
    return 0


def cmd_animate(args) -> int:
    from ..core import animation, linear

    sc = get_scene(args.scene)
    anim = from_options(AnimateOptions, args, dest_prefix="anim_")
    sink = animation.open_sink(args.out or sc.outputs.get("animate", f"{sc.name}.mp4"), anim.fps, args.exr_precision)
    out = getattr(sink, "pattern", None) or sink.writer.path
    settings = settings_from_args(sc, args, "animate")
    if str(out).lower().endswith(".mp4") and (settings.width % 2 or settings.height % 2):
        raise ValueError(f"--width and --height must be even for MP4, got {settings.width}x{settings.height}")
    try:
        path = sc.path(args.path)
    except ValueError as exc:
        raise ValueError(f"--{exc}") from None
    kind, address = animation.parse_scheduler(args.scheduler)
    if not 1 <= args.chunk <= 100000:
        raise ValueError(f"--chunk must be in [1, 100000], got {args.chunk}")
    if args.dask_workers is not None and not 1 <= args.dask_workers <= 4096:
        raise ValueError(f"--dask-workers must be in [1, 4096], got {args.dask_workers}")
    if kind == "dask":  # independent chunks of full frames (see pywarp.core.animation)
        settings = animation.full_frames(settings, {k[4:] for k in vars(args) if k.startswith("opt_")})
        if sink.linear:
            linear.check_linear(sc.technique(settings), sc.name)
        client, cluster = animation.dask_client(address, args.dask_workers)
        try:
            with sink, _progress_bar(anim.frames, "animate", "frames", args.no_progress) as bar:
                animation.render_on_dask(client, sc.name, settings, path.name, anim.frames, anim.fps,
                                         anim.time_scale, args.chunk, sink.linear, sink, progress=bar.update)
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    else:
        poses = path.poses(anim.frames, settings)
        tech = sc.technique(settings)
        if sink.linear:
            linear.check_linear(tech, sc.name)
        times = animation.frame_times(settings, sc.time_field, anim.frames, anim.fps, anim.time_scale)
        with sink, _progress_bar(anim.frames, "animate", "frames", args.no_progress) as bar:
            for i, img in animation.render_frames(tech, poses, times, sc.time_field, sink.linear):
                sink.add(img, i)
                bar.update(1)
    print(f"wrote {out} ({anim.frames} frames, {settings.width}x{settings.height}, scene {sc.name}, path {path.name}"
          + (f", reprojection {'on' if settings.reprojection else 'off'}" if hasattr(settings, "reprojection")
             else "") + ")")
    return 0


def cmd_bench(args) -> int:
    names = [args.first] + ([args.second] if args.second is not None else [])
    if len(names) == 2:
        sc = get_scene(names[0])
        name = names[1]
    elif names[0] in all_scenes() and names[0] not in get_scene().benchmarks:
        sc = get_scene(names[0])  # `pywarp bench <scene>`: the scene's default benchmark
        name = sc.default_benchmark or next(iter(sc.benchmarks), None)
        if hasattr(args, "bench_baseline"):  # `pywarp bench <scene> --baseline PYTHON`: the benchmark that takes it
            name = next((n for n, bm in sc.benchmarks.items() if "baseline" in bm.defaults), name)
        if name is None:
            raise ValueError(f"scene {sc.name!r} has no benchmarks")
    else:
        sc, name = get_scene(), names[0]
    if name not in sc.benchmarks:
        raise ValueError(f"benchmark must be one of {', '.join(map(repr, sc.benchmarks))} (scene {sc.name}), "
                         f"got {name!r}")
    b = sc.benchmarks[name]
    opts = {p.name: p.option for p in specs(BenchOptions)}
    for field_, opt in opts.items():
        if hasattr(args, "bench_" + field_) and field_ not in b.defaults:
            takes = ", ".join([opts[k] for k in b.defaults if k in opts] + ["--device", "--json"])
            raise ValueError(f"{opt} is not an option of benchmark {name!r} (it takes {takes})")
    values = from_options(BenchOptions, args, dest_prefix="bench_",
                          defaults={k: v for k, v in b.defaults.items() if v is not None})
    kwargs = {k: getattr(values, k) for k in b.defaults}
    kwargs["device"] = _check_device(args.device)
    if b.check is not None:
        b.check(**kwargs)
    load = {"start": _bench_header(sc.name, b, kwargs)}
    result = b.run(**kwargs)
    load["end"] = load_average()
    was_busy = busy(load["start"]) or busy(load["end"])
    if isinstance(result, dict):
        result.setdefault("load", {**load, "cores": os.cpu_count(), "busy": was_busy})
    sys.stdout.flush()
    b.print(result, args.json)
    sys.stdout.flush()
    if args.json and isinstance(result, dict):  # the report prints a benchmark's own warnings; JSON only holds them
        for warning in result.get("warnings", ()):
            say(f"warning: {warning}")
    say(f"load average at end: {_load_text(load['end'])}")
    if was_busy:
        per_core = ", ".join(f"{at} {v[0] / (os.cpu_count() or 1):.2f}" for at, v in load.items() if v)
        say(f"warning: the machine was busy while this ran (load per core {per_core}; above {BUSY_LOAD_PER_CORE}): "
            f"the numbers may be off -- compare the ratios within this run, or rerun on an idle machine")
    return 0


def _bench_header(scene: str, b, kwargs: dict) -> list | None:
    """What the benchmark measures, how long it takes and the load average at its start, on stderr before it
    measures (stdout keeps the report, or one JSON object as its last line). Returns the load average."""
    opts = ", ".join(f"{k} {v if v is not None else 'none' if k == 'baseline' else 'auto'}"
                     for k, v in kwargs.items())
    say(f"pywarp bench {scene} {b.name}: {b.description}")
    say(f"  expected: {b.expected or 'not stated'} on 2 CPU cores at its defaults (options: {opts})")
    load = load_average()
    say(f"  load average at start: {_load_text(load)}")
    return load


def _load_text(load: list | None) -> str:
    if not load:
        return "not available on this system"
    return " ".join(f"{v:.2f}" for v in load) + f" (1, 5, 15 min; {os.cpu_count()} cores)"


def view_defaults(sc) -> dict:
    """Settings defaults of ``pywarp view``: ``command_defaults["view"]``, else 640 x 360 where the settings have a
    width and a height (the issue's interactive size)."""
    names = {p.name for p in specs(sc.settings)}
    return {"width": 640, "height": 360} if {"width", "height"} <= names else {}


def cmd_view(args) -> int:
    from ..viewer import Script, check_window, view

    sc = get_scene(args.scene)
    if args.benchmark is not None and not args.benchmark > 0:
        raise ValueError(f"--benchmark must be > 0 seconds, got {args.benchmark:g}")
    window = not args.no_window
    if window:
        check_window()
    settings = settings_from_args(sc, args, "view", view_defaults(sc))
    script = Script.load(args.script) if args.script else None
    if args.screenshot_at:
        from pathlib import Path

        events = [] if script is None else list(script.events)
        for t in args.screenshot_at:
            if not t >= 0:
                raise ValueError(f"--screenshot-at must be >= 0 seconds, got {t:g}")
            events.append({"t": t, "screenshot": str(Path(args.screenshot_dir) / f"{sc.name}-{t:g}s.png")})
        script = Script.parse(events)
    if args.dump is not None and args.benchmark is None:
        raise ValueError("--dump needs --benchmark (it writes the benchmark's sampled frames)")
    return view(sc, settings, window=window, script=script, benchmark=args.benchmark, as_json=args.json,
                screenshot_dir=args.screenshot_dir, window_screenshot=args.window_screenshot,
                state_out=args.state_out, seconds=args.seconds, dump=args.dump,
                temporal=None if args.previews is None else args.previews == "temporal")


# --- the parsers ---------------------------------------------------------------------------------------------------------

def add_scene_commands(sub, help_for: str | None = None) -> None:
    """Add ``scenes``, ``render``, ``animate``, ``view`` and ``bench`` to the ``pywarp`` subparsers ``sub``.

    ``help_for``: a scene name when the parser is built to print ``pywarp render|animate|view <scene> --help``: the
    commands then have that scene's options only, with its defaults (size, ``--out``, camera path). Otherwise they
    accept the options of every scene (each checked against the chosen scene when the command runs)."""
    default = get_scene(help_for)
    fmt = argparse.RawDescriptionHelpFormatter
    others = ", ".join(n for n in all_scenes() if n != default.name)
    depends = textwrap.fill(
        f"Options depend on the scene; these are {default.name}'s"
               f"{' (the default scene)' if default.name == DEFAULT_SCENE else ''}. Other scenes: {others} "
        f"(`pywarp {{command}} SCENE --help` lists a scene's options; `pywarp scenes` describes them).", 100)

    s = sub.add_parser("scenes", help="list the scenes (render, animate, bench take one; default clouds)",
                       description="List the registered scenes with their camera paths and benchmarks.")
    s.add_argument("--json", action="store_true", help="one JSON array instead of the listing")
    s.set_defaults(run=cmd_scenes)

    r = sub.add_parser("render", help=f"render one image of a scene (default {default.name}: {default.description})",
                       formatter_class=fmt,
                       description=depends.format(command="render") + "\n\nRender one image of a scene. Every "
                                   "option has a unit, a range and a default.\n\n"
                                   f"{default.name}: {default.description}")
    _scene_arg(r)
    _add_scene_options(r, "render", help_for)
    r.add_argument("--out", default=None, metavar="PATH",
                   help=f"output .png (sRGB, 8 bit), or .exr / .npy (display-linear float RGB before the sRGB "
                        f"encoding; scenes with a linear image), checked writable before any work (default: "
                        f"{default.outputs.get('render', 'SCENE.png')})")
    r.add_argument("--exr-precision", choices=("half", "float"), default="half",
                   help="pixel type of an .exr output (default: half)")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    r.set_defaults(run=cmd_render)

    path = default.path() if default.paths else None
    a = sub.add_parser("animate", help="render a video along a scene's camera path "
                                       f"({default.name}: {path.description if path else '-'})",
                       formatter_class=fmt,
                       description=depends.format(command="animate") + "\n\n"
                                   "Render a video along a camera path of a scene: MP4 (H.264) or GIF. The camera "
                                   "options (" + ", ".join(
                                       o for o in (next((p.option for p in specs(default.settings) if p.name == f),
                                                        None) for f in (path.start_fields if path else ()))
                                       if o) + ") set the start of the path; the path then moves the camera."
                                   + (f"\n\n{default.name}, path {path.name}: {path.description}" if path else ""))
    _scene_arg(a)
    add_options(a, AnimateOptions, dest_prefix="anim_")
    a.add_argument("--path", default=None, metavar="NAME",
                   help="camera path: " + "; ".join(f"{sc.name}: {', '.join(sc.paths)}"
                                                    for sc in all_scenes().values() if sc.paths)
                        + " (default: the scene's default path"
                        + (f", {path.name} for {default.name})" if path else ")"))
    _add_scene_options(a, "animate", help_for)
    a.add_argument("--out", default=None, metavar="PATH",
                   help=f"output .mp4 or .gif, or numbered frames with a %%04d field: frames/frame_%%04d.png "
                        f"(sRGB), .exr or .npy (display-linear float); checked writable before any work (default: "
                        f"{default.outputs.get('animate', 'SCENE.mp4')})")
    a.add_argument("--exr-precision", choices=("half", "float"), default="half",
                   help="pixel type of .exr frames (default: half)")
    a.add_argument("--scheduler", default="local", metavar="local|dask[=ADDRESS]",
                   help="local: this process (default); dask: chunks of --chunk frames rendered by the workers of a "
                        "Dask LocalCluster (--dask-workers processes), or of the cluster at ADDRESS "
                        "(dask=tcp://host:8786), assembled in order. Under dask every frame is a full frame "
                        "(reprojection off), identical to a local run with --no-reprojection")
    a.add_argument("--chunk", type=int, default=8, metavar="FRAMES",
                   help="frames per Dask task (default: 8)")
    a.add_argument("--dask-workers", type=int, default=None, metavar="N",
                   help="worker processes of the LocalCluster (default: one per core)")
    a.add_argument("--no-progress", action="store_true", help="no progress bar")
    a.set_defaults(run=cmd_animate)

    v = sub.add_parser("view", help="open a scene in an interactive window (fly, panel of every setting)",
                       formatter_class=fmt,
                       description=depends.format(command="view") + "\n\n"
                                   "Open a scene in a window: its image beside a panel of every setting (unit, range "
                                   "and help on hover; changes apply live), frame time and frames/s. Keys: the "
                                   "scene's (F1 shows them), F12 screenshot, Esc quit. Renders at reduced resolution "
                                   "while the view moves and refines when it stops. Default size 640 x 360. Needs a "
                                   "display (run under `xvfb-run -a` without one) unless --no-window.\n\n"
                                   "scenes: " + ", ".join(all_scenes()))
    _scene_arg(v)
    _add_scene_options(v, "view", help_for)
    v.add_argument("--benchmark", type=float, default=None, metavar="SECONDS",
                   help="benchmark mode: hold the scene's benchmark keys (the free-fly default: D + Left, circling "
                        "at constant altitude) and count the frames shown for SECONDS after a warm-up; prints "
                        "frames/s against the target")
    v.add_argument("--json", action="store_true", help="with --benchmark: print one JSON object as the last line")
    v.add_argument("--dump", default=None, metavar="DIR",
                   help="with --benchmark: write each sampled frame as shown (SCENE-NN-shown.png), its full render "
                        "(-full.png) and its settings, pose and `pywarp render` command (.json) to DIR")
    v.add_argument("--previews", choices=("scaled", "temporal"), default=None,
                   help="what moving shows: 'scaled' the whole picture at a reduced size, enlarged; 'temporal' the "
                        "window's resolution, 1/4 or 1/16 of its pixels rendered per frame and the rest reprojected "
                        "from the previous frames (pywarp.core.temporal); default: the scene's own choice "
                        "(terrain: temporal, the others: scaled)")
    v.add_argument("--script", default=None, metavar="FILE",
                   help="play a JSON list of timed events: {\"t\": 0, \"key\": \"W\", \"hold\": 1.5}, "
                        "{\"t\": 2, \"set\": {\"coverage\": 0.7}}, {\"t\": 3, \"screenshot\": \"a.png\"}, "
                        "{\"t\": 4, \"quit\": true}; the clock steps 1/30 s per frame, so the same script gives "
                        "the same screenshots; the viewer quits when it ends")
    v.add_argument("--screenshot-at", type=float, action="append", default=[], metavar="SECONDS",
                   help="save the refined frame at this script time (repeatable) as SCENE-<t>s.png in "
                        "--screenshot-dir")
    v.add_argument("--screenshot-dir", default=".", metavar="DIR",
                   help="folder of F12 and --screenshot-at screenshots (default: the current folder)")
    v.add_argument("--window-screenshot", default=None, metavar="PATH",
                   help="save the whole window (panel and image) as PNG when the viewer exits")
    v.add_argument("--state-out", default=None, metavar="PATH",
                   help="write the final state (settings, frames shown, screenshots) as JSON on exit")
    v.add_argument("--no-window", action="store_true",
                   help="run the session without a window (benchmarks and scripts on machines without a display)")
    v.add_argument("--seconds", type=float, default=None, metavar="SECONDS",
                   help="quit after this long (wall time)")
    v.set_defaults(run=cmd_view)

    lines = []
    for sc in all_scenes().values():
        for bname, bm in sc.benchmarks.items():
            opts = ", ".join(f"{k} {v if v is not None else 'none' if k == 'baseline' else 'auto'}"
                             for k, v in bm.defaults.items())
            lines.append(f"  {sc.name} {bname} [{bm.expected or 'duration not stated'}]: {bm.description} "
                         f"(defaults: {opts or '-'})")
    b = sub.add_parser("bench", help="run a benchmark and print ratios measured in one run",
                       formatter_class=fmt,
                       description="Run a benchmark of a scene: pywarp bench [SCENE] [BENCHMARK] (a scene alone runs its default "
                                   "benchmark). Numbers are measured "
                                   "in one run (best of --repeat after a warm-up); ratios compare them. Each "
                                   "prints, on stderr, what it measures, how long it takes, its rows as they "
                                   "finish and the load average at its start and end, with a warning when the "
                                   "machine was busy (a shared machine slows every number).\n\n"
                                   "benchmarks [time at the defaults on 2 CPU cores]:\n" + "\n".join(lines))
    b.add_argument("first", metavar="[SCENE]",
                   help=f"the scene (default {DEFAULT_SCENE}; may be left out) -- or the benchmark when it is")
    b.add_argument("second", nargs="?", default=None, metavar="BENCHMARK",
                   help="the benchmark: " + "; ".join(f"{sc.name}: {', '.join(sc.benchmarks)}"
                                                      for sc in all_scenes().values()))
    add_options(b, BenchOptions, dest_prefix="bench_")
    b.add_argument("--device", default="cpu", metavar="NAME",
                   help="Warp device: cpu, or cuda:N where present; honoured by every benchmark (default: cpu)")
    b.add_argument("--json", action="store_true", help="print one JSON object as the last line")
    b.set_defaults(run=cmd_bench)
