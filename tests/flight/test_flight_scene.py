"""The flight scene (oc): settings, the technique (deterministic per seed and thread count, Warp vs the C reference
pixel), the scripted flight through the clouds, and the commands render / animate / bench built from its
registration."""
from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from pywarp.cli.main import main
from pywarp.core import scenes
from pywarp.core.params import specs
from pywarp.flight.settings import FlightSettings

SMALL = dict(width=96, height=54, cloud_count=3, cloud_size=32)


@pytest.fixture(scope="module")
def tech():
    from pywarp.flight.technique import FlightTechnique

    return FlightTechnique(FlightSettings(**SMALL))


def test_settings_validate():
    with pytest.raises(ValueError, match="cloud_size must be a multiple of 8"):
        FlightSettings(cloud_size=36)
    with pytest.raises(ValueError, match="time_s must be in"):
        FlightSettings(time_s=40.0, flight_duration_s=32.0)
    with pytest.raises(ValueError, match="start_speed_mps"):
        FlightSettings(start_speed_mps=70.0, max_speed_mps=60.0)
    with pytest.raises(ValueError, match="cloud_sharpness"):
        FlightSettings(cloud_sharpness=1.0)
    with pytest.raises(ValueError, match="view must be one of"):
        FlightSettings(view="tower")
    for p in specs(FlightSettings):
        assert p.doc and p.reason, p.name


def test_preview_settings():
    s = FlightSettings()
    p = s.preview()
    assert (p.width, p.height) == (320, 180) and p.step_voxels == s.preview_step_voxels == 2.0
    assert replace(p, width=s.width, height=s.height, step_voxels=s.step_voxels) == s
    tiny = FlightSettings(width=20, height=16, preview_scale=0.1).preview()
    assert (tiny.width, tiny.height) == (16, 16)
    with pytest.raises(ValueError, match="preview_scale"):
        FlightSettings(preview_scale=1.5)
    with pytest.raises(ValueError, match="preview_step_voxels"):
        FlightSettings(preview_step_voxels=0.0)


def test_cloud_fields_mirror_the_cloud_array_settings():
    from pywarp.flight.clouds import CloudArraySettings

    theirs = {p.name: p for p in specs(CloudArraySettings)}
    ours = {p.name: p for p in specs(FlightSettings)}
    for mine, their in (("cloud_cover", "cover"), ("cloud_sharpness", "sharpness"),
                        ("cloud_persistence", "persistence"), ("cloud_interpolation", "interpolation"),
                        ("cloud_smoothing", "smoothing"), ("cloud_envelope", "envelope"),
                        ("cloud_envelope_base", "envelope_base")):
        a, b = ours[mine], theirs[their]
        assert (a.lo, a.hi, a.lo_open, a.hi_open) == (b.lo, b.hi, b.lo_open, b.hi_open), mine
        if b.choices:
            assert set(a.choices) <= set(b.choices)
    s = FlightSettings(cloud_cover=140.0, seed=5).cloud_array(2)
    assert s.cover == 140.0 and s.size == 64 and s.envelope == FlightSettings().cloud_envelope > 0


def test_registered_with_paths_and_benchmarks():
    sc = scenes.scene("flight")
    assert sc.default_path == "chase" and set(sc.paths) == {"chase", "cockpit"}
    assert {"frame", "clouds", "all"} <= set(sc.benchmarks)
    poses = sc.path().poses(5, FlightSettings())
    assert [p.time_s for p in poses] == [0.0, 8.0, 16.0, 24.0, 32.0]


def test_flight_goes_through_the_first_cloud_and_around_others(tech):
    tr = tech.trajectory
    boxes = [(np.array(v.origin), np.array(v.origin) + np.array(v.extent)) for v in tech.volumes.volumes]
    inside = np.array([[np.all((p >= lo) & (p <= hi)) for lo, hi in boxes] for p in tr.position])
    assert inside[:, 0].sum() * (tr.time[1] - tr.time[0]) > 2.0  # seconds inside the first cloud
    assert not inside[:, 1:].any() or inside[:, 1:].sum() < inside[:, 0].sum()
    # the script banks both ways and climbs: the attitude comes from the height points
    assert tr.roll.max() > 0.2 and tr.roll.min() < -0.2 and tr.pitch.max() > 0.1
    # every cloud array has its zero border (oc-5.2.3.2): the boxes do not cut the clouds
    for v in tech.volumes.volumes:
        d = v.density
        assert d[0].max() == d[-1].max() == d[:, 0].max() == d[:, :, -1].max() == 0
        assert d.max() > 0


def test_same_seed_same_image_any_thread_count(tech):
    from pywarp.flight.technique import FlightPose, FlightTechnique

    pose = FlightPose(4.0)
    a = tech.render(pose)
    b = FlightTechnique(FlightSettings(**SMALL, threads=1)).render(pose)
    assert np.array_equal(a, b)
    c = FlightTechnique(FlightSettings(**SMALL, seed=9)).render(pose)
    assert not np.array_equal(a, c)
    assert a.shape == (54, 96, 3) and a.dtype == np.uint8


def test_warp_matches_the_c_reference_pixel(tech):
    from pywarp.flight.technique import FlightPose

    rng = np.random.default_rng(2)
    xs, ys = rng.integers(0, 96, 80), rng.integers(0, 54, 80)
    for pose in (FlightPose(4.0), FlightPose(12.0, "cockpit")):
        w = tech.render_pixels_warp(xs, ys, pose)
        c = tech.render_pixels_c(xs, ys, pose)
        np.testing.assert_allclose(w, c, rtol=1e-5, atol=1e-6)


def test_update_rebuilds_only_what_changed(tech):
    from pywarp.flight.technique import FlightTechnique

    t = FlightTechnique(FlightSettings(**SMALL))
    vols = t.volumes
    t.update(fov_y_deg=50.0)
    assert t.volumes is vols
    light = [l.copy() for l in t.volumes.light]
    t.update(sun_elevation_deg=60.0)
    assert t.volumes is vols and not all(np.array_equal(a, b) for a, b in zip(light, t.volumes.light))
    t.update(seed=3)
    assert t.volumes is not vols
    t.update(width=48, height=30)
    assert t.render().shape == (30, 48, 3)


def test_cli_render_animate_bench(tmp_path, capsys):
    small = ["--width", "64", "--height", "36", "--cloud-count", "2", "--cloud-size", "32", "--no-progress"]
    out = tmp_path / "f.png"
    assert main(["render", "flight", *small, "--out", str(out)]) == 0
    assert out.exists()
    gif = tmp_path / "f.gif"
    assert main(["animate", "flight", *small, "--frames", "3", "--out", str(gif)]) == 0
    assert gif.exists()
    capsys.readouterr()
    assert main(["bench", "flight", "frame", "--width", "32", "--height", "18", "--repeat", "1", "--json"]) == 0
    r = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert r["fps"] > 0 and set(r["frame_ms"]) == {"3", "6", "10", "18", "26"}
    # the one-brick-per-jump path gives the same pixels; the preview is measured in the same run
    assert r["previous_same_pixels"] is True and set(r["previous_frame_ms"]) == set(r["frame_ms"])
    assert r["preview"]["fps"] > 0 and r["preview"]["step_voxels"] == 2.0


def test_invalidation_names_are_the_flight_scenes():
    """The flight's own names: a new speed simulates the flight again (not a "texture" change), a cloud setting
    rebuilds the clouds, the sun the light volumes."""
    base = FlightSettings()
    assert FlightSettings.INVALIDATES == ("nothing", "size", "device", "clouds", "flight", "light")
    cases = {"max_speed_mps": (50.0, {"flight"}), "flight_duration_s": (20.0, {"flight"}), "seed": (3, {"clouds"}),
             "cloud_cover": (100.0, {"clouds"}), "sun_elevation_deg": (20.0, {"light"}), "g": (0.5, set()),
             "width": (320, {"size"})}
    for name, (value, stale) in cases.items():
        assert replace(base, **{name: value}).invalidated(base) == stale, name


def test_flight_frames_go_through_the_shared_display_transform():
    """tonemap none at 0 EV is the kernel's plain clamp and sRGB encoding; the default (ACES at -0.5 EV) is
    pywarp.core.display of the same display-linear pixels (the C reference's ccl_volume_pixel at sampled pixels)."""
    import dataclasses

    from pywarp.core import display
    from pywarp.flight.technique import FlightTechnique

    s = FlightSettings(width=64, height=36, cloud_count=2, cloud_size=32)
    assert (s.tonemap, s.exposure_ev) == ("aces", -0.5)
    tech = FlightTechnique(s)
    img = tech.render()
    xs, ys = np.array([3, 20, 40, 60]), np.array([2, 18, 30, 35])
    lin = tech.render_pixels_c(xs, ys)
    np.testing.assert_array_equal(img[ys, xs], display.quantise(display.apply(lin, -0.5, "aces"), srgb=True))
    plain = FlightTechnique(dataclasses.replace(s, tonemap="none", exposure_ev=0.0)).render()
    np.testing.assert_allclose(plain[ys, xs], display.quantise(lin, srgb=True), atol=1)
    assert not np.array_equal(img, plain)
