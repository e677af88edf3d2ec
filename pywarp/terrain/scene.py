"""Registers the ``terrain`` scene (pt): the ray-marched fBm landscape of the procedural-texture demo. Importing this
module imports neither Warp nor the C library; the technique, the camera path and the benchmarks load them when used."""
from __future__ import annotations

from ..core.scenes import Benchmark, CameraPath, Scene, register
from .settings import TerrainSettings


def make_technique(settings: TerrainSettings):
    """The terrain technique (init / update / render / resize)."""
    from .technique import TerrainTechnique

    return TerrainTechnique(settings)


def walk(frames: int, settings: TerrainSettings) -> list:
    from .technique import walk_path

    return walk_path(frames, settings)


def controls(settings: TerrainSettings):
    """The viewer's controls: the demo's mouse look + W (pywarp.terrain.controls)."""
    from .controls import TerrainControls

    return TerrainControls(settings)


def _lazy(module: str, name: str):
    def call(*args, **kwargs):
        import importlib

        return getattr(importlib.import_module(module, __package__), name)(*args, **kwargs)
    call.__name__ = name
    return call


SCENE = register(Scene(
    name="terrain",
    description="ray-marched fBm landscape of the pt demo: dynamic-step march, soft shadows, fog, sky with sun, "
                "2-D clouds, water",
    settings=TerrainSettings,
    technique=make_technique,
    paths={"walk": CameraPath(
        "walk", "a walk over the landscape standing in for the demo's mouse + W: 3 units per frame along the "
                "heading, swinging +-20 deg, the eye at its start height above the (smoothed) ground or water",
        walk, start_fields=("camera_x", "camera_y", "camera_z", "camera_yaw_deg", "camera_pitch_deg"))},
    default_path="walk",
    benchmarks={
        "tables": Benchmark("tables", "everything below in one run: Tabulka 7.1, Tabulka 8.1, bisection, "
                                      "supersampling, viewer preview, stage profile",
                            _lazy(".bench", "bench_tables"), _lazy(".bench", "report_tables"),
                            {"repeat": 1, "workers": None}),
        "marching": Benchmark("marching", "Tabulka 7.1: fixed vs dynamic step on the test heightmap at 640x480, "
                                          "1366x768, 1920x1080 (ms, mean steps, ratio beside the text's ~20x)",
                              _lazy(".bench", "bench_marching"), _lazy(".bench", "report_marching"),
                              {"repeat": 1, "workers": None}),
        "final": Benchmark("final", "Tabulka 8.1: frame time of the final scene at 640x480, 1366x768, 1920x1080",
                           _lazy(".bench", "bench_final"), _lazy(".bench", "report_final"),
                           {"repeat": 1, "workers": None}),
        "bisect": Benchmark("bisect", "the ch. 9 bisection refinement vs the plain dynamic step: steps, time, image "
                                      "difference", _lazy(".bench", "bench_bisect"), _lazy(".bench", "report_bisect"),
                            {"width": 640, "height": 360, "repeat": 1, "workers": None}),
        "supersampling": Benchmark("supersampling", "cost of 1, 4 and 16 rays per pixel (7.1.6)",
                                   _lazy(".bench", "bench_supersampling"), _lazy(".bench", "report_supersampling"),
                                   {"width": 320, "height": 180, "repeat": 1, "workers": None}),
        "preview": Benchmark("preview", "frames per second of the viewer's preview frame (quality='preview') and of "
                                        "its reductions at full size vs the full setting",
                             _lazy(".bench", "bench_preview"), _lazy(".bench", "report_preview"),
                             {"width": 640, "height": 360, "repeat": 3, "workers": None}),
        "profile": Benchmark("profile", "time per stage of the final scene (slab, shadows, normals, water, "
                                        "atmosphere switched off one at a time)",
                             _lazy(".bench", "bench_profile"), _lazy(".bench", "report_profile"),
                             {"width": 640, "height": 360, "repeat": 2, "workers": None}),
    },
    outputs={"render": "terrain.png", "animate": "walk.mp4"},
    command_defaults={"animate": {"width": 640, "height": 360}},
    time_field="time_s",
    controls=controls,
))
