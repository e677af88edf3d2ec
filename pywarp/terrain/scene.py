"""Registers the ``terrain`` scene (pt): the ray-marched fBm landscape of the procedural-texture demo. Importing this
module imports neither Warp nor the C library: the technique, the camera path, the benchmarks and the controls are
named as "module:function" and imported when first used."""
from __future__ import annotations

from ..core.scenes import Benchmark, CameraPath, Scene, register
from .settings import TerrainSettings


SCENE = register(Scene(
    name="terrain",
    description="ray-marched fBm landscape of the pt demo: dynamic-step march, soft shadows, fog, sky with sun, "
                "2-D clouds, water",
    settings=TerrainSettings,
    technique="pywarp.terrain.technique:TerrainTechnique",
    paths={"walk": CameraPath(
        "walk", "a walk over the landscape standing in for the demo's mouse + W: 3 units per frame along the "
                "heading, swinging +-20 deg, the eye at its start height above the (smoothed) ground or water",
        "pywarp.terrain.technique:walk_path",
        start_fields=("camera_x", "camera_y", "camera_z", "camera_yaw_deg", "camera_pitch_deg"))},
    default_path="walk",
    benchmarks={
        "tables": Benchmark("tables", "everything below in one run: Tabulka 7.1, Tabulka 8.1, bisection, "
                                      "supersampling, viewer preview, stage profile",
                            "pywarp.terrain.bench:bench_tables", "pywarp.terrain.bench:report_tables",
                            {"repeat": 1, "workers": None}, expected="4-5 min"),
        "marching": Benchmark("marching", "Tabulka 7.1: fixed vs dynamic step on the test heightmap at 640x480, "
                                          "1366x768, 1920x1080 (ms, mean steps, ratio beside the text's ~20x)",
                              "pywarp.terrain.bench:bench_marching", "pywarp.terrain.bench:report_marching",
                              {"repeat": 1, "workers": None}, expected="1-1.5 min"),
        "final": Benchmark("final", "Tabulka 8.1: frame time of the final scene at 640x480, 1366x768, 1920x1080",
                           "pywarp.terrain.bench:bench_final", "pywarp.terrain.bench:report_final",
                           {"repeat": 1, "workers": None}, expected="1-1.5 min"),
        "bisect": Benchmark("bisect", "the ch. 9 bisection refinement vs the plain dynamic step: steps, time, image "
                                      "difference",
                            "pywarp.terrain.bench:bench_bisect", "pywarp.terrain.bench:report_bisect",
                            {"width": 640, "height": 360, "repeat": 1, "workers": None}, expected="10-20 s"),
        "supersampling": Benchmark("supersampling", "cost of 1, 4 and 16 rays per pixel (7.1.6)",
                                   "pywarp.terrain.bench:bench_supersampling",
                                   "pywarp.terrain.bench:report_supersampling",
                                   {"width": 320, "height": 180, "repeat": 1, "workers": None}, expected="10-25 s"),
        "preview": Benchmark("preview", "frames per second of the viewer's preview frame (quality='preview') and of "
                                        "its reductions at full size vs the full setting",
                             "pywarp.terrain.bench:bench_preview", "pywarp.terrain.bench:report_preview",
                             {"width": 640, "height": 360, "repeat": 3, "workers": None}, expected="5-15 s"),
        "profile": Benchmark("profile", "time per stage of the final scene (slab, shadows, normals, water, "
                                        "atmosphere switched off one at a time)",
                             "pywarp.terrain.bench:bench_profile", "pywarp.terrain.bench:report_profile",
                             {"width": 640, "height": 360, "repeat": 2, "workers": None}, expected="20-40 s"),
    },
    outputs={"render": "terrain.png", "animate": "walk.mp4"},
    command_defaults={"animate": {"width": 640, "height": 360}},
    time_field="time_s",
    controls="pywarp.terrain.controls:TerrainControls",
))
