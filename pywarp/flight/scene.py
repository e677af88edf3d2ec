"""Registers the ``flight`` scene (oc): value-noise cloud volumes rendered by the SimVoleon stand-in and the aircraft
flown through and around them. Importing this module imports neither Warp nor the C library: the technique, the
camera paths, the benchmarks and the controls are named as "module:function" and imported when first used."""
from __future__ import annotations

from ..core.scenes import Benchmark, CameraPath, Scene, register
from .settings import FlightSettings


SCENE = register(Scene(
    name="flight",
    default_benchmark="all",
    description="oc flight simulator: value-noise cloud volumes (SimVoleon stand-in volume renderer) and an aircraft "
                "flown through and around them by a script of key presses",
    settings=FlightSettings,
    technique="pywarp.flight.technique:FlightTechnique",
    paths={"chase": CameraPath("chase", "the whole scripted flight (pywarp.flight.script.DEFAULT_SCRIPT: a climb into "
                                        "the first cloud, turns around the others) seen by a camera behind, beside "
                                        "and above the aircraft (three-quarter view); the frames are spread over --duration seconds",
                               "pywarp.flight.technique:chase_path",
                               start_fields=("start_altitude_m", "start_speed_mps")),
           "cockpit": CameraPath("cockpit", "the same flight from the pilot's eye (the horizon banks)",
                                 "pywarp.flight.technique:cockpit_path",
                                 start_fields=("start_altitude_m", "start_speed_mps"))},
    default_path="chase",
    benchmarks={
        "frame": Benchmark("frame", "volume-render frame time of the chase view at moments of the flight (Warp, "
                                    "tile-parallel), frames/s; the C reference per pixel on a sample",
                           "pywarp.flight.bench:bench_frame", "pywarp.flight.bench:report_frame",
                           {"width": 640, "height": 360, "repeat": 3, "workers": None}, expected="30 s-1 min"),
        "clouds": Benchmark("clouds", "cloud-array generation time by size (32^3, 64^3, 128^3) and interpolation "
                                      "(linear, cosine, cubic: the text calls cubic 'unusable in real time')",
                            "pywarp.flight.bench:bench_clouds", "pywarp.flight.bench:report_clouds",
                            {"repeat": 3, "workers": None}, expected="5-15 s"),
        "all": Benchmark("all", "frame and clouds together (one JSON object)",
                         "pywarp.flight.bench:bench_all", "pywarp.flight.bench:report_all",
                         {"width": 640, "height": 360, "repeat": 3, "workers": None}, expected="40 s-1.5 min"),
    },
    outputs={"render": "flight.png", "animate": "flight.mp4"},
    command_defaults={"animate": {"width": 640, "height": 360}},
    command_exclude={"animate": ("time_s", "view")},
    time_field=None,
    controls="pywarp.flight.controls:FlightControls",
))
