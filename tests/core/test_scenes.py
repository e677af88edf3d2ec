"""The scene registry (pywarp.core.scenes) and the commands built from it: `pywarp scenes`, `pywarp render|animate
[SCENE]`, `pywarp bench [SCENE] BENCHMARK` -- clouds is the default, every benchmark has --json and honours --device,
and the timing helper (pywarp.core.timing)."""
from __future__ import annotations

import json

import pytest

from pywarp.cli.main import main
from pywarp.core import scenes, timing
from pywarp.core.params import Settings, specs


def test_clouds_is_registered_and_the_default():
    from pywarp.clouds.settings import CloudscapeSettings

    all_ = scenes.scenes()
    assert list(all_)[0] == scenes.DEFAULT_SCENE == "clouds"
    sc = scenes.scene()
    assert sc is all_["clouds"] is scenes.scene("clouds")
    assert sc.settings is CloudscapeSettings and issubclass(sc.settings, Settings)
    assert sc.description and sc.default_path == "flythrough" and sc.path().name == "flythrough"
    assert set(sc.benchmarks) == {"tiles", "cloudscape", "textures", "reprojection", "dask", "speed",
                                  "reference", "still"}
    assert {"camera_altitude_km", "camera_pitch_deg", "camera_yaw_deg"} <= set(sc.path().start_fields)
    assert sc.outputs["render"] == "cloudscape.png"
    with pytest.raises(ValueError, match=r"^scene must be one of 'clouds'(, '[a-z]+')*, got 'nope'$"):
        scenes.scene("nope")
    with pytest.raises(ValueError, match=r"^path must be one of 'flythrough', got 'orbit'$"):
        sc.path("orbit")
    with pytest.raises(ValueError, match=r"^benchmark must be one of 'tiles', "):
        sc.benchmark("nope")


def test_register_checks_the_scene():
    with pytest.raises(TypeError, match="scene must be a Scene"):
        scenes.register("clouds")
    sc = scenes.scene()
    with pytest.raises(ValueError, match="default_path must be one of the scene's paths"):
        scenes.register(scenes.Scene("x", "y", sc.settings, sc.technique, paths={}, default_path="flythrough"))


def test_the_technique_factory_gives_init_update_render_resize():
    sc = scenes.scene()
    t = sc.technique(sc.settings(width=24, height=14, base_size=16, detail_size=8, curl_size=16, weather_size=32))
    for name in ("init", "update", "render", "resize"):
        assert callable(getattr(t, name))
    poses = sc.path().poses(3, t.settings)
    assert len(poses) == 3 and t.render(poses[0]).shape == (14, 24, 3)


def test_cli_scenes_lists_them(capsys):
    assert main(["scenes"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("clouds (default): ") and "tiles, cloudscape, textures, reprojection" in out
    assert main(["scenes", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert rows[0]["name"] == "clouds" and rows[0]["default"] is True
    assert rows[0]["options"] == sum(p.option is not None for p in specs(scenes.scene().settings))


@pytest.fixture
def fake_benchmarks(monkeypatch):
    """Every benchmark's run replaced by a recorder (the real ones take seconds to minutes)."""
    import pywarp.clouds.bench as bench
    import pywarp.clouds.bench_reference as bench_reference
    import pywarp.clouds.bench_textures as bench_textures
    import pywarp.core.animation as animation

    calls = []

    def fake(name):
        def run(**kw):
            calls.append((name, kw))
            return {"benchmark": name, **kw}
        return run

    for mod, name in ((bench, "bench_tiles"), (bench, "bench_cloudscape"), (bench, "run_reprojection"),
                      (bench_textures, "bench_textures"), (animation, "run_dask_bench"),
                      (bench_reference, "bench_reference")):
        monkeypatch.setattr(mod, name, fake(name))
    return calls


@pytest.mark.parametrize("argv,called,kwargs", [
    (["bench", "tiles"], "bench_tiles", {"width": 960, "height": 540, "repeat": 5, "workers": None}),
    (["bench", "clouds", "tiles", "--width", "64", "--workers", "2"], "bench_tiles",
     {"width": 64, "height": 540, "repeat": 5, "workers": 2}),
    (["bench", "cloudscape", "--repeat", "1"], "bench_cloudscape",
     {"width": 960, "height": 540, "repeat": 1, "workers": None}),
    (["bench", "textures", "--repeat", "1"], "bench_textures", {"repeat": 1, "workers": None}),
    (["bench", "clouds", "reprojection", "--height", "90"], "run_reprojection", {"width": 640, "height": 90}),
    (["bench", "clouds", "dask", "--width", "64"], "run_dask_bench", {"width": 64, "height": 180, "repeat": 1}),
    (["bench", "clouds", "reference", "--width", "32", "--spp", "8"], "bench_reference",
     {"width": 32, "height": 90, "spp": 8, "workers": None}),
    (["bench", "clouds", "--repeat", "1"], "bench_cloudscape",  # a scene alone: its default benchmark
     {"width": 960, "height": 540, "repeat": 1, "workers": None}),
])
def test_cli_bench_every_benchmark_has_json_and_honours_device(fake_benchmarks, capsys, argv, called, kwargs):
    assert main([*argv, "--json", "--device", "cpu"]) == 0
    name, kw = fake_benchmarks[-1]
    assert name == called and kw == {**kwargs, "device": "cpu"}
    last = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert last["benchmark"] == called and last["device"] == "cpu"


@pytest.mark.parametrize("argv,message", [
    (["bench", "textures", "--width", "64"], "--width is not an option of benchmark 'textures' (it takes --repeat, "
                                             "--workers, --device, --json)"),
    (["bench", "tiles", "--width", "-5"], "--width must be in [1, 8192], got -5"),
    (["bench", "tiles", "--repeat", "x"], "--repeat must be an integer, got 'x'"),
    (["bench", "tiles", "--device", "cuda:3"], "--device must be one of 'cpu'"),
    (["bench", "nope"], "benchmark must be one of 'tiles', 'cloudscape', 'textures', 'reprojection', 'dask', "
                        "'speed', 'reference', 'still' (scene clouds), got 'nope'"),
    (["bench", "clouds", "drops"], "benchmark must be one of 'tiles', 'cloudscape', 'textures', 'reprojection', "
                                   "'dask', 'speed', 'reference', 'still' (scene clouds), got 'drops'"),
])
def test_cli_bench_bad_arguments(fake_benchmarks, capsys, argv, message):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("pywarp bench: error: " + message), err
    assert not fake_benchmarks


def test_timing_helper_best_of_n_after_warm_up():
    calls = []
    ms = timing.best_ms(lambda: calls.append(1), repeat=3, warmup=2)
    assert len(calls) == 5 and ms >= 0.0
    assert len(timing.samples_ms(lambda: None, repeat=4, warmup=0)) == 4
    keep = {}
    best = timing.interleaved_ms({"a": lambda: "A", "b": lambda: "B"}, repeat=2, warmup=1, keep=keep)
    assert set(best) == {"a", "b"} and keep == {"a": "A", "b": "B"}
    with pytest.raises(ValueError, match="repeat must be an integer >= 1"):
        timing.best_ms(lambda: None, repeat=0)
    m = timing.machine()
    assert m["cores"] >= 1 and m["python"]
