"""Registers the ``clouds`` scene (vc): the volumetric cloudscape. Importing this module imports neither Warp nor the C
library: the camera path, the benchmarks and the controls are named as "module:function" and imported when first used,
and the technique factory (the real-time technique, or the path-traced reference) imports its choice when called."""
from __future__ import annotations

from ..core.scenes import Benchmark, CameraPath, Scene, register
from .settings import CloudscapeSettings


def make_technique(settings: CloudscapeSettings):
    """The cloudscape technique (vc-A33: init / update / render / resize), textures generated (cached); with
    ``settings.reference`` the path-traced ground truth (:class:`pywarp.clouds.reference.ReferenceRenderer`)."""
    if settings.reference:
        from .reference import ReferenceRenderer

        return ReferenceRenderer(settings)
    from .technique import CloudscapeTechnique

    return CloudscapeTechnique(settings)


#: the path tracer's settings: options of ``pywarp render`` only
_REFERENCE_FIELDS = ("reference", "spp", "reference_seed", "reference_bounces")

SCENE = register(Scene(
    name="clouds",
    default_benchmark="cloudscape",
    description="volumetric cloudscape of the vc thesis: Preetham or gradient sky, cloud-layer raymarch, reprojection",
    settings=CloudscapeSettings,
    technique=make_technique,
    paths={"flythrough": CameraPath(
        "flythrough", "climb from the start altitude below the cloud layer, through it, to 1.5 km above its top, "
                      "flying 12 km forward along the heading; the pitch eases down to -12 deg",
        "pywarp.clouds.technique:flythrough_path",
        start_fields=("camera_altitude_km", "camera_pitch_deg", "camera_yaw_deg", "camera_x_km", "camera_z_km"))},
    default_path="flythrough",
    benchmarks={
        "tiles": Benchmark("tiles", "tile-parallel launcher vs one launch, on a frame-sized kernel",
                           "pywarp.clouds.bench:bench_tiles", "pywarp.clouds.bench:report_tiles",
                           {"width": 960, "height": 540, "repeat": 5, "workers": None}, expected="5-20 s"),
        "cloudscape": Benchmark("cloudscape", "the renderer's optimisation ladder (fig 4.17), sky models (fig 4.16), "
                                              "Warp vs C, reprojection; keys in the README",
                                "pywarp.clouds.bench:bench_cloudscape", "pywarp.clouds.bench:report_cloudscape",
                                {"width": 960, "height": 540, "repeat": 2, "workers": None}, expected="4-6 min"),
        "textures": Benchmark("textures", "noise-texture generation: C one thread vs Warp tile-parallel vs one "
                                          "launch", "pywarp.clouds.bench_textures:bench_textures",
                              "pywarp.clouds.bench_textures:report",
                              {"repeat": 3, "workers": None}, expected="30 s-1 min"),
        "reprojection": Benchmark("reprojection", "SSIM/PSNR of reprojected frames against full renders along a "
                                                  "camera path (needs scikit-image, a test extra)",
                                  "pywarp.clouds.bench:run_reprojection", "pywarp.clouds.bench:report_reprojection",
                                  {"width": 640, "height": 360}, expected="2.5-5 min"),
        "dask": Benchmark("dask", "the fly-through's frames on a Dask LocalCluster of 1 and 2 worker processes: "
                                  "speed-up of 2 over 1 and frames/s per worker, to size a cluster (needs dask)",
                          "pywarp.core.animation:run_dask_bench", "pywarp.core.animation:report_dask",
                          {"width": 320, "height": 180, "repeat": 1}, expected="30 s-1 min"),
        "speed": Benchmark("speed", "640x360 reprojected (mean over a steady path) and 1280x720 full frame, and their "
                                    "ratio; --baseline PYTHON measures another installation's the same way, "
                                    "interleaved in one run, and prints both and the speed-ups",
                           "pywarp.clouds.bench:bench_speed", "pywarp.clouds.bench:report_speed",
                           {"repeat": 3, "workers": None, "baseline": None}, expected="1-2 min",
                           check="pywarp.clouds.bench:check_speed"),
        "reference": Benchmark("reference", "the real-time lighting models (thesis, +sky light, +multiple "
                                            "scattering, default) against the path-traced ground truth of three "
                                            "scenes and two views, in physical units with the Mie phase (its "
                                            "forward peak truncated in the reference): SSIM and "
                                            "mean CIEDE2000 after the best exposure scale, and without rescaling "
                                            "CIEDE2000 and energy ratios in thick / thin / clear pixels (needs "
                                            "scikit-image and colour-science)",
                               "pywarp.clouds.bench_reference:bench_reference", "pywarp.clouds.bench_reference:report",
                               {"width": 160, "height": 90, "spp": 1024, "workers": None},
                               expected="15-30 min (about 1 s per --spp: the truncated forward peak)"),
    },
    outputs={"render": "cloudscape.png", "animate": "flythrough.mp4"},
    command_defaults={"animate": {"width": 640, "height": 360, "reprojection": True}},
    # --accumulate averages the frames of one still (render only)
    command_exclude={"render": ("reprojection", "reprojection_neighbourhood", "reprojection_depth",
                                "reprojection_filter"),
                     "animate": ("accumulate",) + _REFERENCE_FIELDS, "view": ("accumulate",) + _REFERENCE_FIELDS},
    time_field="time_s",
    controls="pywarp.clouds.controls:CloudscapeControls",
))
