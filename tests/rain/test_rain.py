"""The rain scene (rr): settings, registration, render/animate over a background, determinism, the Warp frame against
the C reference at sampled pixels, drops that look like drops (inverted scene) and streaks that fall."""
from __future__ import annotations

import dataclasses
import math
from dataclasses import replace

import numpy as np
import pytest

from pywarp.core.pose import Pose
from pywarp.core.scenes import scene, scenes
from pywarp.rain import particles as P
from pywarp.rain.settings import CONTROLS, RainSettings
from pywarp.rain.technique import Panorama, RainTechnique, sphere_mask

SMALL = dict(width=160, height=90, background="panorama", drops=1500, capture_size=128, mask_size=128)


@pytest.mark.spec("rr-alg-4.1", "rr-tab-A")
def test_scene_registered_with_controls_table():
    sc = scene("rain")
    assert sc.settings is RainSettings and "still" in sc.paths and "drops" in sc.benchmarks
    assert [c["key"] for c in CONTROLS] == list("WSADQEYCPFTGHBN")  # Appendix A.1, in order
    fields = {f.name for f in dataclasses.fields(RainSettings)}
    assert all(c["field"] is None or c["field"] in fields for c in CONTROLS)


def test_settings_refuse_bad_values():
    with pytest.raises(ValueError, match="drops"):
        RainSettings(drops=-1)
    with pytest.raises(ValueError, match="persistence_ms"):
        RainSettings(persistence_ms=120.0)
    with pytest.raises(ValueError, match="size_spread_mm"):
        RainSettings(size_mm=4.3, size_spread_mm=1.0)
    with pytest.raises(ValueError, match="background"):
        RainSettings(background="nowhere")
    with pytest.raises(ValueError, match="shape"):
        RainSettings(shape="2.0")


@pytest.mark.spec("rr-alg-3.1.1")
def test_scene_mask_matches_an_independent_sphere():
    from pywarp.rain import drops as R

    m = np.asarray(R.drop_mask(64, 1.0, method="sphere"))
    ref = sphere_mask(64)
    np.testing.assert_array_equal(m[..., 3] > 0, ref[..., 3] > 0)
    ok = (ref[..., 3] > 0) & (ref[..., 2] > 0) & (m[..., 2] > 0)
    np.testing.assert_allclose(m[ok][:, :3], ref[ok][:, :3], atol=2e-5)


@pytest.mark.spec("rr-code-5.2.3", "rr-code-5.2.4", "rr-alg-3.1.2")
@pytest.mark.parametrize("mode", ["drops", "streaks"])
def test_frame_warp_matches_c_at_sampled_pixels_and_is_deterministic(mode):
    s = RainSettings(**SMALL, mode=mode, seed=5, time_s=4.0)
    tech = RainTechnique(s)
    img = tech.render(encode=False)
    again = RainTechnique(s).render(encode=False)
    np.testing.assert_array_equal(img, again)
    ins = tech.frame_inputs()
    assert len(ins["sprites"]) > 100
    bg = ins["background"]
    changed = np.nonzero(np.any(np.abs(img - bg) > 1e-6, axis=2))
    assert len(changed[0]) > 0.02 * s.width * s.height
    rng = np.random.default_rng(0)
    k = rng.choice(len(changed[0]), 150, replace=False)
    ys = np.concatenate([changed[0][k], rng.integers(0, s.height, 50)])
    xs = np.concatenate([changed[1][k], rng.integers(0, s.width, 50)])
    c = P.composite_pixels(**ins, xs=xs, ys=ys, impl="c")
    np.testing.assert_allclose(img[ys, xs], c, atol=1e-6)


@pytest.mark.spec("rr-alg-3.1", "rr-code-5.2.3")
def test_drops_show_the_scene_upside_down():
    # one big drop in the middle of the view: its upper half sees the ground (darker, greener), its lower half the
    # sky -- the inversion of a refracting sphere (fig 2.4)
    w, h = 200, 120
    pose = Pose(yaw_deg=0.0, pitch_deg=0.0, fov_y_deg=60.0)
    pano = Panorama()
    view = pano.render(pose, w, h, 60.0)
    cap = pano.render(Pose(yaw_deg=0.0, pitch_deg=0.0, fov_y_deg=150.0), 256, 256, 150.0)
    sp = np.array([[100.0, 60.0, 30.0, 30.0, 0.0, 1.0]], np.float32)
    out = P.composite(view, cap, sphere_mask(128), sp, math.radians(60))
    top = out[38:52, 92:108].mean(axis=(0, 1))
    bottom = out[68:82, 92:108].mean(axis=(0, 1))
    assert top[1] > top[2] and bottom[2] > bottom[1]  # green ground on top, blue-grey sky below


@pytest.mark.spec("rr-code-5.2.2", "rr-alg-3.2.3")
def test_animation_makes_the_rain_fall():
    # the text's streaks (half opaque): the frame changes by > 20 grey levels where they move; the physical ones are
    # a few % opaque (tests/rain/test_streak_quality.py)
    tech = RainTechnique(RainSettings(**SMALL, mode="streaks", streaks="thesis"))
    y0 = tech.system.state()["pos"][:, 1].copy()
    a = tech.render()
    tech.update(time_s=1.0)  # 0.05 s of rain at the default clock rate
    b = tech.render()
    y1 = tech.system.state()["pos"][:, 1]
    fell = y0 - y1
    speeds = tech.system.state()["speed"]
    moved = fell > 0  # not respawned
    np.testing.assert_allclose(fell[moved], speeds[moved] * 0.05, rtol=1e-4, atol=1e-6)
    assert np.abs(a.astype(int) - b.astype(int)).max() > 20
    tech.update(drops=100)
    tech.render()
    assert tech.system.count == 100  # the G key takes effect at once


@pytest.mark.spec("rr-code-5.2.2", "rr-tab-A")
@pytest.mark.parametrize("warm, counts", [(True, (3000, 500, 3000, 12000, 1500, 0, 12000)),
                                          (False, (30, 100, 10, 100, 40))])
def test_drop_count_follows_drops_up_and_down(warm, counts):
    """update(drops=N) (the G / H keys, fig 6.12) shows the particles of a fresh technique with N drops, whatever
    the counts before; with warm_start off the count grows one per 1/30 s step, 60 steps here."""
    base = dict(SMALL, mode="streaks", seed=4, time_s=2.0 / 0.05, warm_start=warm)
    tech = RainTechnique(RainSettings(**dict(base, drops=counts[0])))
    seen = {}
    for n in counts:
        tech.update(drops=n)
        got = tech.frame_inputs()["sprites"]
        fresh = RainTechnique(RainSettings(**dict(base, drops=n))).frame_inputs()["sprites"]
        assert len(got) == len(fresh), n
        np.testing.assert_array_equal(got, fresh)
        seen[n] = len(got)
    if warm:  # more drops, more streaks in view (about 1/5 of the spawn box is in this view)
        assert 0 == seen[0] < seen[500] < seen[1500] < seen[3000] < seen[12000]
        assert 3 < seen[3000] / seen[500] < 9 and 3 < seen[12000] / seen[3000] < 5
    else:
        assert tech.system.count == 40


def test_cli_render_rain(tmp_path):
    from pywarp.cli.main import main

    out = tmp_path / "rain.png"
    assert main(["render", "rain", "--background", "panorama", "--width", "96", "--height", "64", "--drops", "300",
                 "--capture-size", "64", "--mask-size", "64", "--out", str(out), "--no-progress"]) == 0
    assert out.stat().st_size > 1000


def _cli_rain_background(tmp_path, background: str) -> np.ndarray:
    """The rain scene's image without drops over ``background`` at 48 x 32 (the command's defaults otherwise)."""
    from PIL import Image

    from pywarp.cli.main import main

    out = tmp_path / f"rain_{background}.png"
    assert main(["render", "rain", "--background", background, "--width", "48", "--height", "32", "--drops", "0",
                 "--capture-size", "32", "--mask-size", "32", "--out", str(out), "--no-progress"]) == 0
    return np.asarray(Image.open(out).convert("RGB"), dtype=np.float64)


@pytest.fixture(scope="module")
def clouds_background(tmp_path_factory):
    return _cli_rain_background(tmp_path_factory.mktemp("clouds"), "clouds")


@pytest.mark.parametrize("background", sorted(set(scenes()) - {"rain", "clouds"}))
def test_cli_render_rain_over_every_registered_background(tmp_path, clouds_background, background):
    """Every registered scene is a background with the default options (the rain scene's own for the clouds apply
    to the clouds only)."""
    img = _cli_rain_background(tmp_path, background)
    assert img.shape == clouds_background.shape and img.std() > 5.0  # a picture, not a flat colour
    assert np.abs(img - clouds_background).mean() > 20.0  # that scene, not the clouds


def test_background_options_name_the_keys_the_background_has_not():
    plain = {"tonemap": "none", "exposure_ev": 0.0}  # a background's 8-bit image: the plain clamp
    assert RainSettings().background == "terrain"  # the default: ground under an overcast sky
    assert RainSettings().background_values()["sun_colour"] == (0.0, 0.0, 0.0)
    assert RainSettings().background_values()["tonemap"] == "none"
    assert RainSettings(background="flight").background_values() == {}  # a scene not named: its own defaults
    clouds = RainSettings(background="clouds", background_options={"coverage": 0.3})
    assert clouds.background_values() == {"coverage": 0.3, "precipitation": 0.7, "camera_altitude_km": 0.05,
                                          "ground_albedo": (0.12, 0.14, 0.08), "ground_variation": 0.8, **plain}
    with pytest.raises(ValueError, match=r"background_options has no field\(s\) \['coverage'\] in scene 'terrain'"):
        RainSettings(background="terrain", background_options={"coverage": 0.3})
    with pytest.raises(ValueError, match=r"\['coverage'\] in scene 'terrain'"):  # given for the clouds: not dropped
        dataclasses.replace(clouds, background="terrain")
    with pytest.raises(ValueError, match=r"\['bogus'\] in scene 'flight'"):
        RainSettings(background="flight", background_options={"bogus": 1})
    with pytest.raises(ValueError, match=r"\['seed'\] in the built-in panorama"):
        RainSettings(background="panorama", background_options={"seed": 1})
    with pytest.raises(ValueError, match=r"\['fog_densty'\] in scene 'terrain' \(did you mean fog_density\?\)"):
        RainSettings(background_options={"fog_densty": 0.01})


def test_background_options_given_as_text_are_parsed_by_the_background_field():
    s = RainSettings(background_options={"fog_density": "0.01", "sky_colour": "0.4, 0.4,0.5", "seed": "3"})
    v = s.background_values()
    assert v["fog_density"] == 0.01 and v["sky_colour"] == (0.4, 0.4, 0.5) and v["seed"] == 3
    for bad, msg in (({"fog_density": "thick"}, "--background-set fog_density must be a number"),
                     ({"sky_colour": "0.4,0.4"}, "--background-set sky_colour must hold 3 numbers"),
                     ({"fog_density": "-1"}, "--background-set fog_density must be in")):
        with pytest.raises(ValueError, match=msg):
            RainSettings(background_options=bad)


@pytest.mark.parametrize("less, more", [("G", "H"), ("-", "+")])
def test_viewer_keys_halve_and_double_the_drops(less, more):
    from pywarp.rain.controls import RainControls
    from pywarp.viewer.controls import Input

    s = RainSettings(**SMALL)  # 1500 drops
    ctl = RainControls(s)
    assert ctl.step(s, Input(pressed=frozenset({more}), held=frozenset({more}))).changes["drops"] == 3000
    ctl.step(s, Input())  # released
    assert ctl.step(s, Input(pressed=frozenset({less}), held=frozenset({less}))).changes["drops"] == 750


@pytest.mark.spec("rr-CF", "rr-A1", "rr-A2", "rr-A3")
@pytest.mark.parametrize("mode, streaks, brighter", [("drops", "physical", 0.1), ("streaks", "thesis", 0.1),
                                                     ("streaks", "physical", 0.03)])
def test_lights_in_the_scene_match_c_at_sampled_pixels(mode, streaks, brighter):
    """``brighter``: the least the lights change the frame somewhere -- opaque drops and half-opaque thesis streaks
    by 0.1, physical streaks (at most ~15 % opaque in this small frame) by 0.03."""
    base = RainSettings(**SMALL, mode=mode, streaks=streaks, seed=2, time_s=2.0, camera_yaw_deg=20.0,
                        camera_pitch_deg=-5.0)
    assert base.light1_colour == (0.0, 0.0, 0.0) and base.light2_colour == (0.0, 0.0, 0.0)  # off: the text has none
    assert "lights" not in RainTechnique(base).frame_inputs()
    s = dataclasses.replace(base, light1_colour=(1.0, 0.8, 0.5), light2_colour=(0.3, 0.5, 1.0))
    tech = RainTechnique(s)
    img = tech.render(encode=False)
    ins = tech.frame_inputs()
    assert ins["lights"]["c_l1"] == (1.0, 0.8, 0.5) and ins["positions"].shape == (len(ins["sprites"]), 3)
    unlit = RainTechnique(base).render(encode=False)
    assert np.abs(img - unlit).max() > brighter  # the lights brighten the drops
    changed = np.nonzero(np.any(np.abs(img - ins["background"]) > 1e-6, axis=2))
    rng = np.random.default_rng(1)
    k = rng.choice(len(changed[0]), 150, replace=False)
    ys, xs = changed[0][k], changed[1][k]
    c = P.composite_pixels(**ins, xs=xs, ys=ys, impl="c")
    np.testing.assert_allclose(img[ys, xs], c, rtol=1e-6, atol=1e-6)
    with pytest.raises(ValueError, match="light1_colour"):
        RainSettings(light1_colour=(-0.1, 0.0, 0.0))


def test_particle_settings_invalidate_the_particles():
    base = RainSettings()
    for name, value in {"size_mm": 1.0, "slowdown": 2.0, "wind_x": 1.0, "seed": 5, "variant": "thesis",
                        "warm_start": False}.items():
        assert dataclasses.replace(base, **{name: value}).invalidated(base) == {"particles"}, name
    assert dataclasses.replace(base, drops=10).invalidated(base) == set()  # the technique follows the count itself
    assert dataclasses.replace(base, mask_size=256).invalidated(base) == {"mask"}


def test_rain_frames_go_through_the_shared_display_transform():
    """The default (tonemap none at 0 EV) is the plain clamp of the float frame; another curve or exposure is the
    shared display transform of that frame (pywarp.core.display.encode_encoded), not a clamp."""
    from pywarp.core import display
    from pywarp.rain.technique import RainTechnique

    s = RainSettings(width=48, height=27, background="panorama", drops=300)
    tech = RainTechnique(s)
    linear = tech.render(encode=False)
    assert np.array_equal(RainTechnique(s).render(), (np.clip(linear, 0, 1) * 255 + 0.5).astype(np.uint8))
    aces = RainTechnique(replace(s, tonemap="aces", exposure_ev=0.5)).render()
    assert np.array_equal(aces, display.encode_encoded(linear, 0.5, "aces"))
    assert not np.array_equal(aces, RainTechnique(s).render())
    with pytest.raises(ValueError, match="tonemap"):
        RainSettings(tonemap="filmic")
