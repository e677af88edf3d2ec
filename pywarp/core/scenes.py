"""The scene registry: a scene is registered once, and ``pywarp render|animate|bench|view <scene>`` and ``pywarp
scenes`` are built from it (:mod:`pywarp.cli.scene`, :mod:`pywarp.viewer`), the docs too.

A scene is a package with the same five files (``pywarp/terrain/`` is the shortest):

* ``settings.py``: its settings class (a :class:`pywarp.core.params.Settings` dataclass: the command-line options and
  the viewer's panel come from its parameter specs, and each spec says what a change invalidates);
* ``technique.py``: its technique, a :class:`pywarp.core.technique.Technique` (init / update / render / resize) and
  its camera paths; the camera is a :class:`pywarp.core.pose.Pose` read from the settings;
* ``controls.py``: its viewer controls (:mod:`pywarp.viewer.controls`);
* ``bench.py``: its benchmarks;
* ``scene.py``: the registration, which names the others as ``"module:function"`` strings, imported when first used
  (so that importing ``scene.py`` imports neither Warp nor the C library)::

    register(Scene(name="terrain", description="...", settings=TerrainSettings,
                   technique="pywarp.terrain.technique:TerrainTechnique",
                   paths={"walk": CameraPath("walk", "...", "pywarp.terrain.technique:walk_path")},
                   benchmarks={"final": Benchmark("final", "...", "pywarp.terrain.bench:bench_final",
                                                  "pywarp.terrain.bench:report_final")},
                   controls="pywarp.terrain.controls:TerrainControls"))

(a callable works wherever a string does). The technique is an object made by ``technique(settings)`` that is ready
to render (``init`` has run) and has

* ``update(**changes)``: change settings (the specs say what each change invalidates),
* ``render(pose=None, progress=None)``: one frame, uint8 (height, width, 3); ``pose`` from a camera path (None: the
  camera of the settings); ``progress(fraction)`` is called as parts of the frame finish,
* ``resize(width, height)``.

Scene packages register themselves when imported; the registry imports the packages listed in :data:`SCENE_MODULES`
on first use (so that this module imports none of them).

The interactive viewer (``pywarp view <scene>``) opens every registered scene; how keys, the mouse and time move its
camera is the scene's ``controls`` (:mod:`pywarp.viewer.controls`).
"""
from __future__ import annotations

import functools
import importlib
import json
import threading
from dataclasses import dataclass, field
from typing import Any, Callable


def resolve(ref):
    """The object a ``"module:name"`` string names (the module imported now), or ``ref`` itself when it is not a
    string."""
    if not isinstance(ref, str):
        return ref
    module, sep, name = ref.partition(":")
    if not sep or not module or not name:
        raise ValueError(f"a reference must read 'module:name', got {ref!r}")
    return getattr(importlib.import_module(module), name)


@dataclass(frozen=True)
class Lazy:
    """A callable named by a ``"module:function"`` string, imported on its first call (:func:`resolve`)."""

    ref: str

    def __call__(self, *args, **kwargs):
        return resolve(self.ref)(*args, **kwargs)


def lazy(ref):
    """``ref`` as a callable: a :class:`Lazy` for a ``"module:function"`` string, else ``ref`` itself (None too)."""
    return Lazy(ref) if isinstance(ref, str) else ref


def _lazy_fields(obj, *names) -> None:
    for n in names:
        object.__setattr__(obj, n, lazy(getattr(obj, n)))


#: Modules that register a scene when imported, in listing order; the first one's scene is the default.
SCENE_MODULES = ("pywarp.clouds.scene", "pywarp.rain.scene", "pywarp.terrain.scene", "pywarp.flight.scene")
#: The scene of ``pywarp render`` and friends when none is named (the README's commands).
DEFAULT_SCENE = "clouds"


@dataclass(frozen=True)
class CameraPath:
    """A named camera path: ``poses(frames, settings)`` returns one pose per frame (the technique's pose type).
    ``start_fields``: the settings fields that set its start (``animate --help`` says so)."""

    name: str
    description: str
    poses: Callable[[int, Any], list] | str
    start_fields: tuple = ()

    def __post_init__(self):
        _lazy_fields(self, "poses")


@dataclass(frozen=True)
class Benchmark:
    """A benchmark: ``run(**options) -> dict`` (JSON-serialisable) and ``report(result) -> str``. ``defaults``: the
    options it takes besides ``device`` (which every benchmark honours) and their defaults (None: chosen by run).
    ``expected``: how long it runs at its defaults on two CPU cores (e.g. ``"1-2 min"``), printed by ``bench --help``
    and before it starts, so that nobody waits on a silent terminal without knowing for how long. ``check``:
    ``check(**options)`` raises ValueError for options the run would refuse (e.g. a missing ``--baseline``
    interpreter), called before anything is printed, so that a bad option stays a one-line error."""

    name: str
    description: str
    run: Callable[..., dict] | str
    report: Callable[[dict], str] | str
    defaults: dict = field(default_factory=dict)
    expected: str = ""
    check: Callable[..., None] | str | None = None

    def __post_init__(self):
        _lazy_fields(self, "run", "report", "check")

    def print(self, result: dict, as_json: bool = False) -> None:
        """The report, or one JSON object on the last line."""
        print(json.dumps(result) if as_json else self.report(result))


@dataclass(frozen=True)
class Scene:
    """A registered scene (see the module docstring).

    ``outputs``: default output file per command (``{"render": "cloudscape.png", "animate": "flythrough.mp4"}``);
    ``command_defaults``: settings defaults per command (e.g. a smaller frame for ``animate``);
    ``command_exclude``: settings fields that are not options of a command (e.g. reprojection for one image);
    ``time_field``: the settings field that ``animate`` advances (None: a static scene);
    ``controls``: the viewer's controls factory, ``controls(settings) -> Controls`` (None: the free-fly camera;
    :mod:`pywarp.viewer.controls`); ``default_benchmark``: what ``pywarp bench <scene>`` runs without a benchmark name
    (None: the first of ``benchmarks``)."""

    name: str
    description: str
    settings: type
    technique: Callable[[Any], Any] | str
    paths: dict = field(default_factory=dict)
    default_path: str | None = None
    benchmarks: dict = field(default_factory=dict)
    outputs: dict = field(default_factory=dict)
    command_defaults: dict = field(default_factory=dict)
    command_exclude: dict = field(default_factory=dict)
    time_field: str | None = None
    controls: Callable[[Any], Any] | str | None = None
    default_benchmark: str | None = None

    def __post_init__(self):
        _lazy_fields(self, "technique", "controls")

    def path(self, name: str | None = None) -> CameraPath:
        """The camera path ``name`` (default: the scene's default path)."""
        name = name or self.default_path
        if name not in self.paths:
            raise ValueError(f"path must be one of {', '.join(map(repr, self.paths))}, got {name!r}")
        return self.paths[name]

    def benchmark(self, name: str | None = None) -> Benchmark:
        """The benchmark ``name`` (default: ``default_benchmark``, else the first registered)."""
        if name is None:
            name = self.default_benchmark or next(iter(self.benchmarks), None)
        if name not in self.benchmarks:
            raise ValueError(f"benchmark must be one of {', '.join(map(repr, self.benchmarks))}, got {name!r}")
        return self.benchmarks[name]


_scenes: dict[str, Scene] = {}
_lock = threading.RLock()
_loaded = False


def register(scene: Scene) -> Scene:
    """Register ``scene`` (once per name; registering the same name again replaces it, for reloads)."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    if scene.default_path is not None and scene.default_path not in scene.paths:
        raise ValueError(f"default_path must be one of the scene's paths {sorted(scene.paths)}, "
                         f"got {scene.default_path!r}")
    if "still" not in scene.benchmarks:  # every scene's full-quality still, timed as `pywarp render` makes it
        from . import bench_still as B

        scene.benchmarks["still"] = Benchmark(
            "still", B.STILL_DESCRIPTION, functools.partial(Lazy("pywarp.core.bench_still:run_still"), scene.name),
            "pywarp.core.bench_still:report_still", defaults=dict(B.STILL_DEFAULTS), expected=B.STILL_EXPECTED,
            check="pywarp.core.bench_still:check_still")
    with _lock:
        _scenes[scene.name] = scene
    return scene


def _load() -> None:
    global _loaded
    with _lock:
        if _loaded:
            return
        _loaded = True
        for mod in SCENE_MODULES:
            importlib.import_module(mod)


def scenes() -> dict[str, Scene]:
    """Every registered scene, by name (the default first)."""
    _load()
    with _lock:
        order = sorted(_scenes, key=lambda n: (n != DEFAULT_SCENE, n))
        return {n: _scenes[n] for n in order}


def scene(name: str | None = None) -> Scene:
    """The scene ``name`` (default :data:`DEFAULT_SCENE`); ValueError listing the scenes for an unknown name."""
    all_ = scenes()
    name = DEFAULT_SCENE if name is None else name
    if name not in all_:
        from .params import did_you_mean

        raise ValueError(f"scene must be one of {', '.join(map(repr, all_))}, got {name!r}"
                         f"{did_you_mean(name, all_)}")
    return all_[name]
