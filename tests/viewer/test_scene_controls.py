"""The scenes' own viewer controls: rain (rr-tab-A, pywarp.rain.controls) and flight (oc §6.1.2, pywarp.flight.controls).
Every key of each table does what the table says, on the controls and in a headless viewer session; the flight
controls fly the flight model of pywarp.kernels.flight (the same path as ``simulate``), the chase camera renders the
flown aircraft, and the preview frames take the scenes' cheaper settings."""
from __future__ import annotations

import dataclasses
import time

import numpy as np
import pytest

from pywarp.core import scenes as S
from pywarp.viewer import controls as V
from pywarp.rain.settings import CONTROLS, MODES, SHAPES


def press(ctl, settings, keys, dt=0.0):
    keys = frozenset(keys)
    st = ctl.step(settings, V.Input(dt=dt, held=keys, pressed=keys))
    return st, dataclasses.replace(settings, **st.changes) if st.changes else settings


def hold(ctl, settings, keys, dt):
    st = ctl.step(settings, V.Input(dt=dt, held=frozenset(keys)))
    return st, dataclasses.replace(settings, **st.changes) if st.changes else settings


# --- rain: rr-tab-A ----------------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def rain():
    return S.scene("rain")


def rain_settings(rain, **kw):
    values = dict(background="panorama", width=160, height=90, camera_yaw_deg=0.0, camera_pitch_deg=0.0)
    values.update(kw)
    return rain.settings(**values)


def test_rain_has_its_own_controls_with_every_key_of_the_table(rain):
    from pywarp.rain.controls import RainControls

    ctl = V.make_controls(rain, rain_settings(rain))
    assert isinstance(ctl, RainControls)
    shown = " ".join(b.keys for b in ctl.bindings)
    for row in CONTROLS:
        assert row["key"] in shown.split(), row
    assert ctl.benchmark_keys and ctl.benchmark_keys <= {r["key"] for r in CONTROLS}


@pytest.mark.parametrize("row", CONTROLS, ids=[r["key"] for r in CONTROLS])
def test_rain_each_key_of_the_table_does_what_it_says(rain, row):
    key, field, change = row["key"], row["field"], row["change"]
    s = rain_settings(rain, background="clouds", background_options={"camera_altitude_km": 0.05},
                      camera_yaw_deg=90.0, camera_pitch_deg=10.0, drops=3000, size_mm=1.3, shape="1.0",
                      mode="streaks")
    ctl = V.make_controls(rain, s)
    st, s1 = press(ctl, s, {key})
    assert st.moving or key == "P"
    if isinstance(change, float):  # A / D / Y / C / B / N: one step of the table per press
        assert getattr(s1, field) == pytest.approx(getattr(s, field) + change)
    elif change == "x 0.5":
        assert s1.drops == 1500
    elif change == "x 2":
        assert s1.drops == 6000
    elif change == "cycle":
        choices = MODES if field == "mode" else SHAPES
        assert getattr(s1, field) == choices[(choices.index(getattr(s, field)) + 1) % len(choices)]
    elif change == "toggle 0":  # P: the simulation stops (time_s no longer advances), P again: it runs
        _, s2 = hold(ctl, s1, set(), dt=0.5)
        assert ctl.paused and s2.time_s == s1.time_s
        _, s3 = press(ctl, s2, {"P"}, dt=0.5)
        assert not ctl.paused and s3.time_s == pytest.approx(s2.time_s + 0.5 / s.clock_rate)
    else:  # W / S / Q / E move the background scene's camera (yaw 90: forward is +x), one step per press
        from pywarp.rain.controls import move_step

        d = move_step("km")
        o0, o1 = s.background_options, s1.background_options
        expect = {"camera forward": ("camera_x_km", d), "camera backward": ("camera_x_km", -d),
                  "camera up": ("camera_altitude_km", d), "camera down": ("camera_altitude_km", -d)}[change]
        name, delta = expect
        assert o1[name] == pytest.approx(o0.get(name, 0.0) + delta)
        assert o1.get("camera_z_km", 0.0) == pytest.approx(0.0, abs=1e-9)
    changed = {k for k in st.changes if k != "time_s"}
    assert changed == ({field} if field not in (None, "clock_rate") else
                       (set() if key == "P" else {"background_options"})), (key, st.changes)


def test_rain_held_keys_repeat_like_a_keyboard_and_values_stay_in_their_domains(rain):
    from pywarp.rain.controls import REPEAT_DELAY_S, REPEAT_HZ

    s = rain_settings(rain)
    ctl = V.make_controls(rain, s)
    _, s1 = press(ctl, s, {"D"}, dt=1 / 60)
    assert s1.camera_yaw_deg == 5.0
    _, s2 = hold(ctl, s1, {"D"}, dt=REPEAT_DELAY_S - 0.01)  # within the delay: no repeat yet
    assert s2.camera_yaw_deg == 5.0
    _, s3 = hold(ctl, s2, {"D"}, dt=0.01 + 3.0 / REPEAT_HZ + 1e-6)  # then REPEAT_HZ steps per second
    assert s3.camera_yaw_deg == pytest.approx(20.0)
    _, s4 = press(ctl, rain_settings(rain, camera_yaw_deg=-178.0), {"A"})  # the heading wraps
    assert s4.camera_yaw_deg == pytest.approx(177.0)
    _, s5 = press(ctl, rain_settings(rain, camera_pitch_deg=87.0), {"Y"})  # the pitch stops at 89
    assert s5.camera_pitch_deg == 89.0
    st, s6 = press(ctl, rain_settings(rain, size_mm=0.6, size_spread_mm=1.0), {"B"})  # 0.6 - 0.5 = 0.1 mm
    assert s6.size_mm == 0.6 and "limit" in st.message
    _, s7 = press(ctl, rain_settings(rain, drops=1), {"G"})
    _, s8 = press(ctl, s7, {"H"})
    assert (s7.drops, s8.drops) == (0, 1)
    st, s9 = press(ctl, s, {"W", "Q"})  # the panorama has no position
    assert "background_options" not in st.changes and "panorama" in st.message


def test_rain_falls_in_the_viewer_and_the_viewers_own_time_is_not_doubled(rain):
    s = rain_settings(rain)
    ctl = V.make_controls(rain, s)
    _, s1 = hold(ctl, s, set(), dt=0.1)
    assert s1.time_s == pytest.approx(0.1 / s.clock_rate)  # one rain second per second
    s2 = dataclasses.replace(s1, time_s=s1.time_s + 2.0)  # the viewer's time plays (F5, the benchmark)
    st, s3 = hold(ctl, s2, set(), dt=0.1)
    assert "time_s" not in st.changes and s3.time_s == s2.time_s


def test_rain_preview_frames_take_a_smaller_capture(rain):
    from pywarp.rain.controls import PREVIEW_CAPTURE

    s = rain_settings(rain)
    assert V.make_controls(rain, s).preview(s) == {"capture_size": PREVIEW_CAPTURE, "background_scale": 4,
                                                   "particles_scale": 2}


def test_rain_background_cached_by_direction_and_reconstructed_while_turning():
    """Rain's background is seen from its own place: time passing renders no background; a turn with
    background_scale 2 reconstructs the view from a quarter of its pixels (pywarp.core.temporal), refined while the
    direction stays; the particle state carries over to another technique (the benchmark's full render)."""
    from pywarp.core.scenes import scene
    from pywarp.rain.technique import SceneBackground

    sc = scene("rain")
    s = sc.settings(width=64, height=36, background="clouds", capture_size=16,
                    background_options={"base_size": 32, "detail_size": 16, "curl_size": 32, "weather_size": 64})
    tech = sc.technique(s)
    calls = []
    bg = tech.background
    assert isinstance(bg, SceneBackground)
    real = bg.render

    def counting(*a, **k):
        calls.append(a[1:3])
        return real(*a, **k)

    bg.render = counting
    full = tech.render()
    assert calls == [(64, 36), (16, 16)]  # the view and the capture
    tech.update(time_s=s.time_s + 0.1)
    tech.render()
    assert len(calls) == 2  # the drops fell, the view did not turn: both cached
    tech.update(background_scale=2, camera_yaw_deg=s.camera_yaw_deg + 2.0)
    tech.render()
    assert calls[2:] == [(16, 16)] and tech._up.count == 1  # the view reconstructed, the capture rendered
    from pywarp.rain.technique import BACKGROUND_REFINE_EVERY

    for _ in range(BACKGROUND_REFINE_EVERY - 1):
        tech.render()
        assert tech._up.count == 1  # the same direction: the drops drawn over the view as it is
    tech.render()
    assert tech._up.count == 2  # then refined by another reconstructed frame
    other = sc.technique(s)
    other.restore(tech.state())
    assert np.array_equal(other.state()["arrays"]["pos"], tech.state()["arrays"]["pos"])
    assert full.shape == (36, 64, 3)


def _wait(session, full=None, version=None, timeout=300.0):
    t0 = time.time()
    while time.time() - t0 < timeout:
        session.tick(V.Input(dt=0.0))
        session.poll()
        f = session.frame
        assert not session.worker.error, session.worker.error
        if f is not None and (full is None or f.full == full) and (version is None or f.version == version):
            return f
        time.sleep(0.01)
    raise AssertionError("no frame")


def _settle(session):
    session.tick(V.Input(dt=0.0))  # the controls' pose of this state (a first pose counts as a change)
    session.clock += 1.0  # then still for a while: refined
    session.tick(V.Input(dt=0.0))
    return _wait(session, full=True, version=session.version)


def test_rain_keys_in_a_headless_session_change_the_image(rain):
    from pywarp.viewer.session import Session

    s = rain_settings(rain, drops=2000, mode="streaks")
    session = Session(rain, s, temporal=True)  # rain's temporal previews: the window's size, the drops whole
    try:
        session.tick(V.Input(dt=0.0, pressed=frozenset({"P"}), held=frozenset({"P"})))  # paused: the rain stands
        first = _settle(session)
        assert session.settings.time_s == 0.0
        offline = rain.technique(session.settings).render()
        assert np.array_equal(first.image, offline)  # the refined frame is pywarp render's
        images = {"start": first.image}
        for key, check in (("F", lambda st: st.mode == "drops"), ("H", lambda st: st.drops == 4000),
                           ("D", lambda st: st.camera_yaw_deg == 5.0), ("T", lambda st: st.shape == "3.0"),
                           ("N", lambda st: st.size_mm == pytest.approx(1.4))):
            session.tick(V.Input(dt=1 / 30, pressed=frozenset({key}), held=frozenset({key})))
            assert check(session.settings), (key, session.settings)
            f = _wait(session, version=session.version)
            assert not f.full or f.version == session.version
            if key in "FHD":  # the image changes (T / N change single drops, checked on the settings)
                img = _settle(session).image
                assert np.mean(np.abs(img.astype(float) - images["start"].astype(float))) > 0.2, key
                images["start"] = img
        session.tick(V.Input(dt=1 / 30, held=frozenset({"D"}), pressed=frozenset({"D"})))
        f = _wait(session, version=session.version)
        from pywarp.rain.controls import PREVIEW_CAPTURE

        # the preview: the window's size (the drops drawn whole), a smaller capture
        assert not f.full and f.settings.capture_size == PREVIEW_CAPTURE and f.image.shape == first.image.shape
    finally:
        session.close()


# --- flight: oc §6.1.2 -------------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def flight():
    return S.scene("flight")


def flight_settings(flight, **kw):
    values = dict(width=96, height=64, cloud_count=2, cloud_size=32, time_s=0.0)
    values.update(kw)
    return flight.settings(**values)


def fly(ctl, s, keys, seconds, fps=30):
    st = None
    for _ in range(int(round(seconds * fps))):
        st = ctl.step(s, V.Input(dt=1.0 / fps, held=frozenset(keys)))
    return st


def test_flight_keys_fly_the_aircraft_as_the_table_says(flight):
    from pywarp.flight.controls import FlightControls
    from pywarp.flight.technique import AircraftState, FlightPose

    s = flight_settings(flight)
    ctl = V.make_controls(flight, s)
    assert isinstance(ctl, FlightControls)
    assert {"Up", "Down", "Left", "Right", "W", "S"} <= set(" ".join(b.keys for b in ctl.bindings).split())
    st = ctl.step(s, V.Input(dt=0.0))
    a0 = ctl.aircraft()
    assert st.pose is None and a0.position == (0.0, s.start_altitude_m, 0.0) and a0.speed == 40.0  # not flown yet
    flown = ctl.step(s, V.Input(dt=0.1)).pose
    assert isinstance(flown, FlightPose) and isinstance(flown.aircraft, AircraftState)  # flying: the flown aircraft

    def after(keys, seconds=1.0):
        c = V.make_controls(flight, s)
        return fly(c, s, keys, seconds).pose.aircraft

    still = after(set())  # no key: straight on at the start speed (heading 0: along -z)
    assert still.position[2] == pytest.approx(-40.0, rel=1e-3) and still.position[0] == pytest.approx(0.0, abs=1e-4)
    assert still.speed == 40.0 and still.pitch == 0.0 and still.roll == 0.0
    assert after({"W"}).speed == pytest.approx(48.0, rel=1e-4)  # W: faster (acceleration 8 m/s^2)
    assert after({"S"}).speed == pytest.approx(32.0, rel=1e-4)  # S: slower
    down, up = after({"Down"}), after({"Up"})
    assert down.pitch > 0.05 and down.position[1] > s.start_altitude_m  # Down arrow: nose up, climb
    assert up.pitch < -0.05 and up.position[1] < s.start_altitude_m  # Up arrow: nose down, descend
    left, right = after({"Left"}, 2.0), after({"Right"}, 2.0)
    assert left.roll < -0.05 and left.heading < 0.0 and left.position[0] < -0.01  # bank and turn left (-x)
    assert right.roll > 0.05 and right.heading > 0.0 and right.position[0] > 0.01


def test_flight_controls_fly_the_path_of_the_flight_model(flight):
    from pywarp.flight.script import DT
    from pywarp.flight.model import simulate

    s = flight_settings(flight)
    ctl = V.make_controls(flight, s)
    for _ in range(30):
        ctl.step(s, V.Input(dt=1 / 30, held=frozenset({"Down", "Right"})))
    for _ in range(15):
        ctl.step(s, V.Input(dt=1 / 30, held=frozenset({"W"})))
    tr = simulate([("down", 0.0, 1.0), ("right", 0.0, 1.0), ("w", 1.0, 1.5)], 1.5, dt=DT, start=s.start_state(),
                  model=s.flight_model())
    a = ctl.aircraft()
    assert np.allclose(a.position, tr.position[-1], rtol=1e-5, atol=1e-3)
    assert a.heading == pytest.approx(float(tr.heading[-1]), abs=1e-5) and a.speed == pytest.approx(
        float(tr.speed[-1]))


def test_flight_starts_from_the_scripted_moment_and_restarts_on_a_panel_change(flight):
    from pywarp.flight.technique import FlightPose

    s = flight_settings(flight, time_s=4.0)
    tech = flight.technique(s)
    ctl = V.make_controls(flight, s)
    st = ctl.step(s, V.Input(dt=0.0))
    assert st.pose is None and ctl.aircraft() == tech.aircraft(4.0) and not st.moving  # the settings' camera
    pose = FlightPose(4.0, "chase", ctl.aircraft())
    assert np.array_equal(tech.render(pose), tech.render())  # the same aircraft as pywarp render's
    st = fly(ctl, s, {"Left"}, 0.5)
    assert st.moving and st.pose.aircraft != tech.aircraft(4.0)
    s2 = dataclasses.replace(s, time_s=8.0)
    assert ctl.step(s2, V.Input(dt=0.0)).pose.aircraft == tech.aircraft(8.0)
    assert V.make_controls(flight, s).preview(s) == {"step_voxels": s.preview_step_voxels}


def test_flight_chase_camera_follows_the_flown_aircraft_in_a_headless_session(flight):
    from pywarp.viewer.session import Session

    s = flight_settings(flight, time_s=4.0)
    session = Session(flight, s)
    try:
        _settle(session)
        v0 = session.version
        for _ in range(10):
            session.tick(V.Input(dt=1 / 30, held=frozenset(session.controls.benchmark_keys)))
        assert session.version > v0  # the benchmark keys move the aircraft: the pose changes
        f = _wait(session, version=session.version)
        assert not f.full and f.settings.step_voxels == s.preview_step_voxels
        pose = session.pose
        assert pose.aircraft.roll < 0.0  # Left: banking left
        f = _settle(session)  # the keys released and the flight held still (no frame time): refined
        assert np.array_equal(f.image, flight.technique(session.settings).render(pose))
    finally:
        session.close()
