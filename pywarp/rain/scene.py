"""Registers the ``rain`` scene (rr): falling rain -- refracting drops or retinal-persistence streaks -- over a
background scene. Importing this module imports neither Warp nor the C library: the technique, the camera paths,
the benchmarks and the controls are named as "module:function" and imported when first used."""
from __future__ import annotations

from ..core.scenes import Benchmark, CameraPath, Scene, register
from .settings import CONTROLS, RainSettings  # noqa: F401  (CONTROLS: rr-tab-A, the controls as data)


SCENE = register(Scene(
    name="rain",
    description="realistic rain of the rr text: refracting drops or persistence streaks over a background scene "
                "(clouds, or any registered scene); optional point lights (rr-A1..rr-CF, off by default)",
    settings=RainSettings,
    technique="pywarp.rain.technique:RainTechnique",
    paths={"still": CameraPath("still", "the camera of the settings, still; the rain falls (the background is "
                                        "rendered once and cached)",
                               "pywarp.rain.technique:still_path",
                               start_fields=("camera_yaw_deg", "camera_pitch_deg"))},
    default_path="still",
    benchmarks={
        "drops": Benchmark("drops", "frame time vs drop count (0 .. 50 000) for drops and streaks over a cached "
                                    "background, beside Tables 6.1 / 6.2; mask build times",
                           "pywarp.rain.bench:bench_drops", "pywarp.rain.bench:report_drops",
                           {"width": 640, "height": 360, "repeat": 3, "workers": None}, expected="10-20 s"),
    },
    outputs={"render": "rain.png", "animate": "rain.mp4"},
    command_defaults={"animate": {"width": 640, "height": 360}},
    time_field="time_s",
    controls="pywarp.rain.controls:RainControls",
))
