"""The scene skeleton every scene shares: the camera pose (pywarp.core.pose), the technique base driven by the specs'
``invalidates`` (pywarp.core.technique), the "module:function" references of a registration (pywarp.core.scenes) and
the same files in every scene package."""
from __future__ import annotations

import importlib
import math
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from pywarp.core import scenes
from pywarp.core.params import Settings, param
from pywarp.core.pose import Pose, camera_fields

ROOT = Path(__file__).resolve().parents[2]


# --- the pose ----------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("yaw, pitch, expected", [
    (0.0, 0.0, (0.0, 0.0, -1.0)),     # yaw 0 looks along -z
    (90.0, 0.0, (1.0, 0.0, 0.0)),     # a positive yaw turns towards +x
    (180.0, 0.0, (0.0, 0.0, 1.0)),
    (0.0, 90.0, (0.0, 1.0, 0.0)),     # pitch up positive
    (0.0, -30.0, (0.0, -0.5, -math.sqrt(3.0) / 2.0)),
])
def test_forward_follows_the_convention(yaw, pitch, expected):
    np.testing.assert_allclose(Pose(yaw_deg=yaw, pitch_deg=pitch).forward(), expected, atol=1e-15)


def test_basis_is_right_handed_and_orthonormal():
    r, u, f = Pose(yaw_deg=37.0, pitch_deg=-12.0).basis()
    np.testing.assert_allclose(np.stack([r, u, f]) @ np.stack([r, u, f]).T, np.eye(3), atol=1e-15)
    np.testing.assert_allclose(np.cross(r, u), -f, atol=1e-15)  # OpenGL's camera: looking along -z of (r, u, z)
    assert r[1] == 0.0 and u[1] > 0.0  # no roll: right stays level, up points up


def test_every_scene_reads_its_pose_from_its_settings_fields():
    from pywarp.clouds.settings import CloudscapeSettings
    from pywarp.rain.settings import RainSettings
    from pywarp.terrain.settings import TerrainSettings

    c = CloudscapeSettings(camera_x_km=1.5, camera_altitude_km=2.0, camera_z_km=-3.0, camera_yaw_deg=10.0,
                           camera_pitch_deg=-5.0, fov_y_deg=50.0)
    assert Pose.from_settings(c) == Pose(1.5, 2.0, -3.0, 10.0, -5.0, 50.0)
    t = TerrainSettings(camera_x=4.0, camera_y=5.0, camera_z=6.0, camera_yaw_deg=-20.0, camera_pitch_deg=3.0)
    assert Pose.from_settings(t) == Pose(4.0, 5.0, 6.0, -20.0, 3.0, t.fov_y_deg)
    r = RainSettings(camera_yaw_deg=15.0, camera_pitch_deg=4.0, fov_y_deg=70.0)
    assert Pose.from_settings(r) == Pose(0.0, 0.0, 0.0, 15.0, 4.0, 70.0)  # the rain box follows the eye
    assert camera_fields(TerrainSettings) == {"x": "camera_x", "y": "camera_y", "z": "camera_z",
                                              "yaw": "camera_yaw_deg", "pitch": "camera_pitch_deg"}
    camera_fields(TerrainSettings).clear()  # a copy: the cached answer is not changed
    assert "x" in camera_fields(TerrainSettings)


def test_pose_camera_and_its_c_twin_equal_ccl_camera_look_at():
    """pose_camera builds the matrices from the eye and eye + forward; Camera.to_c hands them to C unchanged:
    both equal what ccl_camera_look_at builds from the same eye and target. A jittered pose is the camera moved by
    its sub-pixel offset."""
    from pywarp.kernels.camera import c_camera_look_at, pose_camera

    pose = Pose(0.5, 0.3, -1.0, 25.0, 8.0, 60.0)
    cam = pose_camera(pose, 320, 180)
    ref = c_camera_look_at(pose.eye(), pose.eye() + pose.forward(), (0.0, 1.0, 0.0), math.radians(60.0),
                           320 / 180, 0.01, 1000.0)
    c = cam.to_c()
    assert (c.eye.x, c.eye.y, c.eye.z) == tuple(float(v) for v in ref.eye)
    for name in ("view", "proj", "view_proj", "inv_view_proj", "inv_view_proj_rot"):
        np.testing.assert_array_equal(getattr(cam, name), getattr(ref, name))
        np.testing.assert_array_equal(np.array(list(getattr(c, name)), np.float32), ref.column_major(name))
    moved = pose_camera(Pose(0.5, 0.3, -1.0, 25.0, 8.0, 60.0, jitter_px=(0.25, -0.5)), 320, 180)
    shifted = ref.jittered(0.25, -0.5, 320, 180)
    for name in ("view", "proj", "view_proj", "inv_view_proj", "inv_view_proj_rot"):
        np.testing.assert_array_equal(getattr(moved, name), getattr(shifted, name))
    assert not np.array_equal(moved.proj, cam.proj)


# --- the technique base ------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class _Toy(Settings):
    INVALIDATES = Settings.INVALIDATES + ("sky", "textures")

    width: int = param(8, kind="int", lo=1, hi=64, invalidates="size", doc="width", reason="small")
    height: int = param(4, kind="int", lo=1, hi=64, invalidates="size", doc="height", reason="small")
    sun: float = param(1.0, lo=0.0, hi=2.0, invalidates="sky", doc="a sky setting", reason="1")
    seed: int = param(0, kind="int", lo=0, hi=9, invalidates="textures", doc="a texture setting", reason="0")
    gain: float = param(1.0, lo=0.0, hi=2.0, doc="a setting that invalidates nothing", reason="1")
    device: str = param("cpu", invalidates="device", doc="device", reason="cpu")
    threads: int | None = param(None, kind="int", lo=1, hi=64, optional=True, invalidates="device", doc="threads",
                                reason="all cores")


def _toy_technique():
    from pywarp.core.technique import Technique, invalidations

    class Toy(Technique):
        settings_class = _Toy

        def __init__(self, settings=None):
            self.log = []
            super().__init__(settings)

        def rebuild(self, stale, changed):
            self.log.append(("rebuild", frozenset(stale), frozenset(changed)))

        def allocate(self, width, height):
            self.log.append(("allocate", width, height))

    return Toy, invalidations(_Toy)


def test_technique_init_rebuilds_everything_then_allocates():
    Toy, everything = _toy_technique()
    t = Toy()
    assert t.settings == _Toy() and t.frame == 0 and t.device == "cpu"
    assert t.log == [("rebuild", everything, frozenset({"width", "height", "sun", "seed", "gain", "device",
                                                        "threads"})), ("allocate", 8, 4)]
    assert everything == {"sky", "textures", "size", "device"}


@pytest.mark.parametrize("changes, stale, allocates", [
    ({"gain": 0.5}, set(), False),
    ({"sun": 0.5}, {"sky"}, False),
    ({"seed": 3, "gain": 2.0}, {"textures"}, False),
    ({"width": 16}, {"size"}, True),
    ({"threads": 1}, {"device"}, True),
])
def test_technique_update_rebuilds_what_the_specs_invalidate(changes, stale, allocates):
    Toy, _ = _toy_technique()
    t = Toy()
    t.log.clear()
    t.update(**changes)
    assert t.log[0] == ("rebuild", frozenset(stale), frozenset(changes))
    assert t.log[1:] == ([("allocate", t.settings.width, t.settings.height)] if allocates else [])
    assert all(getattr(t.settings, k) == v for k, v in changes.items())


def test_technique_resize_changes_the_settings_size():
    Toy, _ = _toy_technique()
    t = Toy()
    t.resize(20, 10)
    assert (t.settings.width, t.settings.height) == (20, 10) and t.log[-1] == ("allocate", 20, 10)


# --- "module:function" references -------------------------------------------------------------------------------------

def test_a_registration_names_its_parts_lazily():
    def still(frames, settings):
        return [None] * frames

    sc = scenes.Scene("toy", "a toy", _Toy, "tests.core.test_scenes_skeleton:_toy_factory",
                      paths={"still": scenes.CameraPath("still", "no motion", "tests.core.test_scenes_skeleton:_still"),
                             "own": scenes.CameraPath("own", "a callable", still)},
                      benchmarks={"b": scenes.Benchmark("b", "a benchmark", "tests.core.test_scenes_skeleton:_run",
                                                        "tests.core.test_scenes_skeleton:_report")})
    assert sc.technique(_Toy()) == ("made", _Toy())
    assert sc.path("still").poses(2, _Toy()) == ["pose", "pose"] and sc.path("own").poses(1, _Toy()) == [None]
    assert sc.benchmark().report(sc.benchmark().run(n=3)) == "ran 3"
    assert sc.controls is None
    bad = scenes.Scene("toy", "a toy", _Toy, "tests.core.test_scenes_skeleton._toy_factory")
    with pytest.raises(ValueError, match="a reference must read 'module:name'"):
        bad.technique(_Toy())
    with pytest.raises(AttributeError, match="nope"):
        scenes.resolve("tests.core.test_scenes_skeleton:nope")


def _toy_factory(settings):
    return ("made", settings)


def _still(frames, settings):
    return ["pose"] * frames


def _run(n):
    return {"n": n}


def _report(result):
    return f"ran {result['n']}"


def test_every_registered_reference_resolves():
    for sc in scenes.scenes().values():
        refs = [sc.technique] + [p.poses for p in sc.paths.values()]
        refs += [f for b in sc.benchmarks.values() for f in (b.run, b.report)]
        refs += [sc.controls] if sc.controls is not None else []
        for ref in refs:
            if isinstance(ref, scenes.Lazy):
                assert callable(scenes.resolve(ref.ref)), (sc.name, ref.ref)


def test_registering_the_scenes_imports_neither_warp_nor_the_viewer_window():
    code = ("import sys; from pywarp.core import scenes; scenes.scenes(); import pywarp.viewer.controls; "
            "print(sorted(m for m in ('warp', 'imgui_bundle', 'pywarp.core.binding') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    assert out.stdout.strip() == "[]"


@pytest.mark.parametrize("package", ["clouds", "terrain", "rain", "flight"])
def test_every_scene_package_has_the_same_files(package):
    for name in ("settings", "technique", "controls", "bench", "scene"):
        assert (ROOT / "pywarp" / package / f"{name}.py").is_file(), (package, name)
    from pywarp.core.technique import Technique

    tech = importlib.import_module(f"pywarp.{package}.technique")
    assert any(isinstance(v, type) and issubclass(v, Technique) and v is not Technique for v in vars(tech).values())
