"""Registers the ``flight`` scene (oc): value-noise cloud volumes rendered by the SimVoleon stand-in and the aircraft
flown through and around them. Importing this module imports neither Warp nor the C library; the technique, the
camera paths and the benchmarks load them when used."""
from __future__ import annotations

from ..core.scenes import Benchmark, CameraPath, Scene, register
from .settings import FlightSettings


def make_technique(settings: FlightSettings):
    """The flight technique (init / update / render / resize): clouds generated, light volumes, the flight."""
    from .technique import FlightTechnique

    return FlightTechnique(settings)


def chase(frames: int, settings: FlightSettings) -> list:
    from .technique import path_poses

    return path_poses(frames, settings, "chase")


def cockpit(frames: int, settings: FlightSettings) -> list:
    from .technique import path_poses

    return path_poses(frames, settings, "cockpit")


def _lazy(module: str, name: str):
    def call(*args, **kwargs):
        import importlib

        return getattr(importlib.import_module(module, __package__), name)(*args, **kwargs)
    call.__name__ = name
    return call


SCENE = register(Scene(
    name="flight",
    default_benchmark="all",
    description="oc flight simulator: value-noise cloud volumes (SimVoleon stand-in volume renderer) and an aircraft "
                "flown through and around them by a script of key presses",
    settings=FlightSettings,
    technique=make_technique,
    paths={"chase": CameraPath("chase", "the whole scripted flight (pywarp.flight.script.DEFAULT_SCRIPT: a climb into "
                                        "the first cloud, turns around the others) seen by a camera behind and above "
                                        "the aircraft; the frames are spread over --duration seconds",
                               chase, start_fields=("start_altitude_m", "start_speed_mps")),
           "cockpit": CameraPath("cockpit", "the same flight from the pilot's eye (the horizon banks)",
                                 cockpit, start_fields=("start_altitude_m", "start_speed_mps"))},
    default_path="chase",
    benchmarks={
        "frame": Benchmark("frame", "volume-render frame time of the chase view at moments of the flight (Warp, "
                                    "tile-parallel), frames/s; the C reference per pixel on a sample",
                           _lazy(".bench", "bench_frame"), _lazy(".bench", "report_frame"),
                           {"width": 640, "height": 360, "repeat": 3, "workers": None}),
        "clouds": Benchmark("clouds", "cloud-array generation time by size (32^3, 64^3, 128^3) and interpolation "
                                      "(linear, cosine, cubic: the text calls cubic 'unusable in real time')",
                            _lazy(".bench", "bench_clouds"), _lazy(".bench", "report_clouds"),
                            {"repeat": 3, "workers": None}),
        "all": Benchmark("all", "frame and clouds together (one JSON object)",
                         _lazy(".bench", "bench_all"), _lazy(".bench", "report_all"),
                         {"width": 640, "height": 360, "repeat": 3, "workers": None}),
    },
    outputs={"render": "flight.png", "animate": "flight.mp4"},
    command_defaults={"animate": {"width": 640, "height": 360}},
    command_exclude={"animate": ("time_s", "view")},
    time_field=None,
    controls=_lazy(".controls", "FlightControls"),
))
