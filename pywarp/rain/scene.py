"""Registers the ``rain`` scene (rr): falling rain -- refracting drops or retinal-persistence streaks -- over a
background scene. Importing this module imports neither Warp nor the C library; the technique, the camera path and
the benchmarks load them when used."""
from __future__ import annotations

from ..core.scenes import Benchmark, CameraPath, Scene, register
from .settings import CONTROLS, RainSettings  # noqa: F401  (CONTROLS: rr-tab-A, the controls as data)


def make_technique(settings: RainSettings):
    """The rain technique (init / update / render / resize): background, mask, particle system."""
    from .technique import RainTechnique

    return RainTechnique(settings)


def still(frames: int, settings: RainSettings) -> list:
    from .technique import still_path

    return still_path(frames, settings)


def _lazy(module: str, name: str):
    def call(*args, **kwargs):
        import importlib

        return getattr(importlib.import_module(module, __package__), name)(*args, **kwargs)
    call.__name__ = name
    return call


SCENE = register(Scene(
    name="rain",
    description="realistic rain of the rr text: refracting drops or persistence streaks over a background scene "
                "(clouds, or any registered scene); optional point lights (rr-A1..rr-CF, off by default)",
    settings=RainSettings,
    technique=make_technique,
    paths={"still": CameraPath("still", "the camera of the settings, still; the rain falls (the background is "
                                        "rendered once and cached)", still,
                               start_fields=("camera_yaw_deg", "camera_pitch_deg"))},
    default_path="still",
    benchmarks={
        "drops": Benchmark("drops", "frame time vs drop count (0 .. 50 000) for drops and streaks over a cached "
                                    "background, beside Tables 6.1 / 6.2; mask build times",
                           _lazy(".bench", "bench_drops"), _lazy(".bench", "report_drops"),
                           {"width": 640, "height": 360, "repeat": 3, "workers": None}),
    },
    outputs={"render": "rain.png", "animate": "rain.mp4"},
    command_defaults={"animate": {"width": 640, "height": 360}},
    time_field="time_s",
    controls=_lazy(".controls", "RainControls"),
))
