"""The scene registry: a scene is registered once, and ``pywarp render|animate|bench <scene>`` and ``pywarp scenes`` are
built from it (:mod:`pywarp.cli.scene`), the viewer and the docs later.

A scene declares its name, a one-line description, its settings class (a :class:`pywarp.core.params.Settings`
dataclass: the command-line options come from its parameter specs), a technique factory, named camera paths and
benchmarks::

    register(Scene(name="clouds", description="...", settings=CloudscapeSettings, technique=make_technique,
                   paths={"flythrough": CameraPath(...)}, benchmarks={"tiles": Benchmark(...)}))

The technique (vc-A33's design, shared by every scene) is an object made by ``technique(settings)`` that is ready to
render (``init`` has run) and has

* ``update(**changes)``: change settings (the specs say what each change invalidates),
* ``render(pose=None, progress=None)``: one frame, uint8 (height, width, 3); ``pose`` from a camera path (None: the
  camera of the settings); ``progress(fraction)`` is called as parts of the frame finish,
* ``resize(width, height)``.

Scene packages register themselves when imported; the registry imports the packages listed in :data:`SCENE_MODULES`
on first use (so that this module imports none of them).
"""
from __future__ import annotations

import importlib
import json
import threading
from dataclasses import dataclass, field
from typing import Any, Callable

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
    poses: Callable[[int, Any], list]
    start_fields: tuple = ()


@dataclass(frozen=True)
class Benchmark:
    """A benchmark: ``run(**options) -> dict`` (JSON-serialisable) and ``report(result) -> str``. ``defaults``: the
    options it takes besides ``device`` (which every benchmark honours) and their defaults (None: chosen by run)."""

    name: str
    description: str
    run: Callable[..., dict]
    report: Callable[[dict], str]
    defaults: dict = field(default_factory=dict)

    def print(self, result: dict, as_json: bool = False) -> None:
        """The report, or one JSON object on the last line."""
        print(json.dumps(result) if as_json else self.report(result))


@dataclass(frozen=True)
class Scene:
    """A registered scene (see the module docstring).

    ``outputs``: default output file per command (``{"render": "cloudscape.png", "animate": "flythrough.mp4"}``);
    ``command_defaults``: settings defaults per command (e.g. a smaller frame for ``animate``);
    ``command_exclude``: settings fields that are not options of a command (e.g. reprojection for one image);
    ``time_field``: the settings field that ``animate`` advances (None: a static scene)."""

    name: str
    description: str
    settings: type
    technique: Callable[[Any], Any]
    paths: dict = field(default_factory=dict)
    default_path: str | None = None
    benchmarks: dict = field(default_factory=dict)
    outputs: dict = field(default_factory=dict)
    command_defaults: dict = field(default_factory=dict)
    command_exclude: dict = field(default_factory=dict)
    time_field: str | None = None

    def path(self, name: str | None = None) -> CameraPath:
        """The camera path ``name`` (default: the scene's default path)."""
        name = name or self.default_path
        if name not in self.paths:
            raise ValueError(f"path must be one of {', '.join(map(repr, self.paths))}, got {name!r}")
        return self.paths[name]

    def benchmark(self, name: str) -> Benchmark:
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
        raise ValueError(f"scene must be one of {', '.join(map(repr, all_))}, got {name!r}")
    return all_[name]
