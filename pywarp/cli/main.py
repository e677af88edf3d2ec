"""The ``pywarp`` command.

    pywarp render [options] [--out cloudscape.png]   one image of the volumetric cloudscape (vc)
    pywarp animate [options] [--out flythrough.mp4]  a camera path from below the cloud layer, into it and above it
    pywarp equations [--seed KEY] [--missing]     traceability matrix: ID, title, C, Warp, tests, figures
    pywarp figures [--seed KEY] [--quick] [--out DIR] [--only fig-4.9 ...]
    pywarp bench tiles|cloudscape|textures [--width W] [--height H] [--repeat N] [--workers N] [--device D] [--json]

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
    from ..core.registry import catalogue, missing, registry

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
    from ..core import figures

    paths = figures.select(args.seed, args.only)
    if not paths:
        print("no tutorials found", file=sys.stderr)
        return 1
    failures = []
    written = figures.run(paths, Path(args.out), quick=args.quick, progress=not args.no_progress, failures=failures)
    print(f"{len(written)} figure files from {len(paths) - len(failures)} tutorials written under {args.out}")
    for path, exc in failures:
        print(f"pywarp: error: {path.name}: {type(exc).__name__}: {exc}", file=sys.stderr)
    return 1 if failures else 0


def cmd_bench(args) -> int:
    from ..clouds import bench

    repeat = args.repeat or (5 if args.name == "tiles" else 2)
    size = {} if args.name == "reprojection" else {"width": args.width or 960, "height": args.height or 540}
    if args.name == "reprojection":
        size = {"width": args.width or 640, "height": args.height or 360}
    bench.main(args.name, as_json=args.json, repeat=repeat, workers=args.workers, device=args.device, **size)
    return 0


# --- render / animate --------------------------------------------------------------------------------------------------

# option -> (settings field, type, help with unit and default filled in from CloudscapeSettings)
_SCENE_OPTIONS = [
    ("--width", "width", int, "image width in pixels"),
    ("--height", "height", int, "image height in pixels"),
    ("--sky", "sky", str, "sky model: preetham (vc-A29) or gradient (vc-A28)"),
    ("--sun-elevation", "sun_elevation_deg", float, "sun elevation above the horizon in degrees (>= 0 for preetham)"),
    ("--sun-azimuth", "sun_azimuth_deg", float, "sun azimuth in degrees, 0 = straight ahead of the default camera"),
    ("--turbidity", "turbidity", float, "Preetham turbidity, in [2, 10]"),
    ("--sky-variant", "sky_variant", str, "errata of the sky chain (vc-2.39, 4.4, 4.5): corrected or thesis"),
    ("--sky-exposure", "sky_exposure", float, "exposure k of the Preetham tone map 1 - exp(-k C) (vc-4.5), > 0"),
    ("--coverage", "coverage", float, "cloud coverage of the weather map, in [0, 1]"),
    ("--precipitation", "precipitation", float, "precipitation of the weather map, in [0, 1] (darker clouds)"),
    ("--cloud-type", "cloud_type", float, "mean cloud type, 0 stratus, 0.5 stratocumulus, 1 cumulus"),
    ("--coverage-threshold", "coverage_threshold", str,
     "reading of C in vc-2.29: one_minus_coverage (C = 1 - coverage) or coverage (C = coverage, literal)"),
    ("--seed", "seed", int, "seed of every texture; the same seed gives the same image"),
    ("--altitude", "camera_altitude_km", float, "camera altitude above the ground in km (layer: 1.5-4 km)"),
    ("--yaw", "camera_yaw_deg", float, "camera heading in degrees, 0 = -z"),
    ("--pitch", "camera_pitch_deg", float, "camera pitch above the horizon in degrees"),
    ("--fov", "fov_y_deg", float, "vertical field of view in degrees"),
    ("--time", "time_s", float, "time in seconds: the wind moves the clouds"),
    ("--wind-speed", "wind_speed_kmh", float, "wind speed in km/h"),
    ("--jitter", "jitter", str, "ray jitter against banding (vc-A23): tilt, offset or none"),
    ("--device", "device", str, "Warp device: cpu or cuda:N where present"),
    ("--threads", "threads", int, "worker threads"),
]


def _add_scene_options(p: argparse.ArgumentParser, overrides: dict | None = None) -> None:
    from ..clouds.cloudscape import CloudscapeSettings

    defaults = {**{f: getattr(CloudscapeSettings, f) for _, f, _, _ in _SCENE_OPTIONS
                   if hasattr(CloudscapeSettings, f)}, **(overrides or {})}
    for opt, fld, typ, text in _SCENE_OPTIONS:
        d = defaults.get(fld)
        p.add_argument(opt, dest=fld, type=typ, default=d, metavar=typ.__name__.upper(),
                       help=f"{text} (default: {'one per core' if d is None and fld == 'threads' else d})")


def _settings_from_args(args, **extra):
    from ..clouds.cloudscape import CloudscapeSettings

    kw = {f: getattr(args, f) for _, f, _, _ in _SCENE_OPTIONS}
    kw.update(extra)
    try:
        return CloudscapeSettings(**kw).validate()
    except ValueError as exc:
        msg = str(exc)
        for opt, fld, _, _ in _SCENE_OPTIONS:  # name the command-line option, not the Python field
            if msg.startswith(fld + " "):
                msg = opt + msg[len(fld):]
                break
        raise ValueError(msg) from None


def cmd_render(args) -> int:
    from tqdm import tqdm

    from ..clouds.cloudscape import CloudscapeTechnique
    from ..core.output import IMAGE_SUFFIXES, check_output_path, write_png

    out = check_output_path(args.out, IMAGE_SUFFIXES)
    settings = _settings_from_args(args)
    with tqdm(total=2, desc="render", unit="stage", disable=args.no_progress) as bar:
        bar.set_postfix_str("textures")
        tech = CloudscapeTechnique(settings)
        bar.update(1)
        bar.set_postfix_str(f"{settings.width}x{settings.height}")
        img = tech.render(reprojection=False)
        bar.update(1)
    write_png(out, img)
    print(f"wrote {out} ({settings.width}x{settings.height}, {settings.sky} sky, seed {settings.seed})")
    return 0


def cmd_animate(args) -> int:
    from tqdm import tqdm

    from ..clouds.cloudscape import CloudscapeTechnique, flythrough_path
    from ..core.output import VIDEO_SUFFIXES, VideoWriter, check_output_path

    out = check_output_path(args.out, VIDEO_SUFFIXES)
    if args.frames < 1:
        raise ValueError(f"--frames must be >= 1, got {args.frames}")
    if not 0 < args.fps <= 240:
        raise ValueError(f"--fps must be in (0, 240], got {args.fps}")
    settings = _settings_from_args(args, reprojection=args.reprojection)
    if out.suffix.lower() == ".mp4" and (settings.width % 2 or settings.height % 2):
        raise ValueError(f"--width and --height must be even for MP4, got {settings.width}x{settings.height}")
    poses = flythrough_path(args.frames, settings)
    tech = CloudscapeTechnique(settings)
    with VideoWriter(out, fps=args.fps) as video:
        for i, pose in enumerate(tqdm(poses, desc="animate", unit="frame", disable=args.no_progress)):
            tech.update(time_s=settings.time_s + i / args.fps * args.time_scale)
            video.add(tech.render(pose))
    print(f"wrote {out} ({args.frames} frames, {settings.width}x{settings.height}, "
          f"reprojection {'on' if settings.reprojection else 'off'})")
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

    r = sub.add_parser("render", help="render one image of the volumetric cloudscape (vc)",
                       description="Render one image of the volumetric cloudscape: Preetham or gradient sky, cloud "
                                   "layer raymarch (vc chapter 4). Every option has a unit and a default.")
    _add_scene_options(r)
    r.add_argument("--out", default="cloudscape.png", metavar="PATH", help="output PNG (default: cloudscape.png)")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    r.set_defaults(run=cmd_render)

    a = sub.add_parser("animate", help="render a fly-through video: below the cloud layer, into it and above it",
                       description="Render a camera path that climbs from below the cloud layer through it to above "
                                   "it while the wind moves the clouds; MP4 (H.264) or GIF.")
    _add_scene_options(a, {"width": 640, "height": 360})
    a.add_argument("--frames", type=int, default=96, help="number of frames (default: 96)")
    a.add_argument("--fps", type=float, default=24.0, help="frames per second of the video (default: 24)")
    a.add_argument("--time-scale", type=float, default=20.0,
                   help="simulated seconds per video second, for the wind (default: 20)")
    a.add_argument("--reprojection", action=argparse.BooleanOptionalAction, default=True,
                   help="temporal reprojection (vc-A26) below the layer; full frames inside and above it "
                        "(default: on)")
    a.add_argument("--out", default="flythrough.mp4", metavar="PATH",
                   help="output .mp4 or .gif (default: flythrough.mp4)")
    a.add_argument("--no-progress", action="store_true", help="no progress bar")
    a.set_defaults(run=cmd_animate)

    b = sub.add_parser("bench", help="run a benchmark and print ratios measured in one run")
    b.add_argument("name", choices=("tiles", "cloudscape", "textures", "reprojection"),
                   help="tiles: tile-parallel launcher vs one launch; cloudscape: the vc renderer's optimisation "
                        "ladder, sky models, Warp vs C, reprojection (keys documented in the README); textures: "
                        "noise-texture generation, C one thread vs Warp tile-parallel; reprojection: SSIM/PSNR of reprojected frames "
                        "against full renders along a camera path (needs scikit-image, a test extra)")
    b.add_argument("--width", type=_positive_int("--width"), default=None,
                   help="frame width in pixels (default 960; 640 for reprojection)")
    b.add_argument("--height", type=_positive_int("--height"), default=None,
                   help="frame height in pixels (default 540; 360 for reprojection)")
    b.add_argument("--repeat", type=_positive_int("--repeat"), default=None,
                   help="timed repetitions, best kept (default 5 for tiles, 2 for cloudscape)")
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
