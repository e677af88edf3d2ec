"""The aircraft of oc §6: attitude from the five height points (oc-6.1.1), the flight model driven by a script of
timed key presses (speed limits, climbing and turning only with speed, attitude change growing with the key time,
determinism, Warp vs C), and the procedural aircraft standing in for the 3DS model (oc-6.1)."""
from __future__ import annotations

import math

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree
from pywarp.flight import model as F


# --- oc-6.1.1 ------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("oc-6.1.1")
def test_attitude_from_known_heights():
    att = pywarp.equation("oc-6.1.1")
    # nose 1 m above the tail over 1 m: 45 deg up; left tip 3 m above the right over 3 m: 45 deg right bank
    pitch, roll = att(101.0, 100.0, 101.5, 98.5, 1.0, 3.0)
    assert float(pitch) == pytest.approx(math.pi / 4, rel=1e-6)
    assert float(roll) == pytest.approx(math.pi / 4, rel=1e-6)
    # independent float64 values of the stated formula on random heights
    rng = np.random.default_rng(1)
    h = rng.uniform(-20, 20, (4, 200)).astype(np.float32)
    L, W = np.float32(7.5), np.float32(12.0)
    pitch, roll = att(h[0], h[1], h[2], h[3], L, W)
    np.testing.assert_allclose(pitch, np.arctan2(h[0].astype(np.float64) - h[1], 7.5), rtol=2e-6, atol=1e-7)
    np.testing.assert_allclose(roll, np.arctan2(h[2].astype(np.float64) - h[3], 12.0), rtol=2e-6, atol=1e-7)
    # level plane at any altitude: no tilt; E does not enter
    p0, r0 = att(500.0, 500.0, 500.0, 500.0, L, W)
    assert float(p0) == 0.0 and float(r0) == 0.0
    assert_twins_agree("oc-6.1.1", h[0], h[1], h[2], h[3], L, W)


@pytest.mark.spec("oc-6.1.1")
def test_attitude_refuses_bad_lengths():
    with pytest.raises(ValueError, match="length"):
        pywarp.equation("oc-6.1.1")(1.0, 0.0, 0.0, 0.0, 0.0, 12.0)
    with pytest.raises(ValueError, match="span"):
        pywarp.equation("oc-6.1.1")(1.0, 0.0, 0.0, 0.0, 7.5, -1.0)


# --- the flight model ----------------------------------------------------------------------------------------------------

@pytest.mark.spec("oc-6.1.1")
def test_speed_limits():
    m = F.FlightModel()
    tr = F.simulate([("w", 0.0, 2.0)], 2.0, dt=0.01)
    assert tr.speed[-1] == pytest.approx(2.0 * m.acceleration, rel=1e-4)
    tr = F.simulate([("w", 0.0, 30.0), ("s", 30.0, 60.0)], 60.0, dt=0.01)
    assert tr.speed.max() == np.float32(m.max_speed)   # never above the maximum
    assert tr.speed[tr.at(29.0)] == np.float32(m.max_speed)
    assert tr.speed[-1] == 0.0 and tr.speed.min() >= 0.0   # never below 0
    # W and S together: no change
    tr = F.simulate([("w", 0.0, 1.0), ("s", 0.0, 1.0)], 1.0, dt=0.01, start=F.FlightState(speed=20.0))
    assert np.all(tr.speed == 20.0)


@pytest.mark.spec("oc-6.1.1")
def test_climbing_and_turning_need_speed():
    # at rest the nose rises but the plane stays put (the text: the plane needs speed to climb)
    tr = F.simulate([("down", 0.0, 1.0)], 3.0, dt=0.01)
    assert tr.pitch[-1] > 0.1
    assert np.all(tr.position == np.float32([0.0, 300.0, 0.0]))
    # with speed it climbs at speed * sin(pitch) and moves forward along -z
    tr = F.simulate([("down", 0.0, 1.0)], 3.0, dt=0.01, start=F.FlightState(speed=30.0))
    assert tr.position[-1, 1] > 300.0 and tr.position[-1, 2] < -80.0
    k = tr.at(2.0)
    climb = (tr.position[k + 1, 1] - tr.position[k, 1]) / 0.01
    assert climb == pytest.approx(30.0 * math.sin(float(tr.pitch[k + 1])), rel=1e-3)
    # a right bank turns right (heading grows, +x) only with speed
    tr = F.simulate([("right", 0.0, 1.0)], 4.0, dt=0.01, start=F.FlightState(speed=40.0))
    assert tr.roll[-1] > 0.0 and tr.heading[-1] > 0.0 and tr.position[-1, 0] > 0.0
    tr = F.simulate([("right", 0.0, 1.0)], 4.0, dt=0.01)
    assert tr.roll[-1] > 0.0 and np.all(tr.heading == 0.0)
    # left lowers the left tip: negative roll, a left turn
    tr = F.simulate([("left", 0.0, 1.0)], 4.0, dt=0.01, start=F.FlightState(speed=40.0))
    assert tr.roll[-1] < 0.0 and tr.heading[-1] < 0.0


@pytest.mark.spec("oc-6.1.1")
def test_attitude_change_grows_with_key_time():
    m = F.FlightModel()
    for held in (0.25, 0.5, 1.0):
        tr = F.simulate([("down", 0.0, held)], 2.0, dt=0.01, start=F.FlightState(speed=10.0))
        # the nose point rose point_rate * held, the tail sank as much: pitch = atan2(2 rate held, length)
        assert float(tr.nose_offset[-1]) == pytest.approx(m.point_rate * held, rel=1e-4)
        assert float(tr.pitch[-1]) == pytest.approx(math.atan2(2 * m.point_rate * held, m.length), rel=1e-4)
    # clamped at the attitude limit
    tr = F.simulate([("right", 0.0, 60.0)], 60.0, dt=0.01, start=F.FlightState(speed=10.0))
    assert float(tr.roll.max()) == pytest.approx(m.max_roll, rel=1e-5)
    # level_rate brings a released axis back to level
    tr = F.simulate([("right", 0.0, 1.0)], 5.0, dt=0.01, model=F.FlightModel(level_rate=1.0))
    assert tr.wing_offset[-1] == 0.0


SCRIPT = [("w", 0.0, 4.0), ("down", 1.0, 1.6), ("right", 3.0, 3.8), ("up", 6.0, 6.5), ("left", 8.0, 9.5),
          ("s", 10.0, 11.0), ("right", 12.0, 12.7)]


@pytest.mark.spec("oc-6.1.1")
def test_same_script_same_trajectory_and_c_agrees():
    a = F.simulate(SCRIPT, 15.0)
    b = F.simulate(SCRIPT, 15.0)
    np.testing.assert_array_equal(a.position, b.position)
    np.testing.assert_array_equal(a.heading, b.heading)
    c = F.simulate_c(SCRIPT, 15.0)
    np.testing.assert_array_equal(a.keys, c.keys)
    np.testing.assert_allclose(a.speed, c.speed, rtol=1e-6)
    np.testing.assert_allclose(a.heading, c.heading, rtol=1e-5, atol=1e-6)
    # 900 steps of float32 position updates: libm sin/cos may round differently by an ulp per step
    np.testing.assert_allclose(a.position, c.position, rtol=1e-5, atol=1e-3)


def test_script_validation():
    with pytest.raises(ValueError, match=r"script\[0\]: key"):
        F.simulate([("q", 0.0, 1.0)], 1.0)
    with pytest.raises(ValueError, match=r"script\[1\]: t_off"):
        F.simulate([("w", 0.0, 1.0), ("s", 2.0, 1.0)], 1.0)
    with pytest.raises(ValueError, match=r"script\[0\] must be"):
        F.simulate([("w", 0.0)], 1.0)
    with pytest.raises(ValueError, match="dt"):
        F.simulate([], 1.0, dt=0.0)
    with pytest.raises(ValueError, match="max_roll"):
        F.FlightModel(max_roll=2.0)
    with pytest.raises(ValueError, match="start speed"):
        F.simulate([], 1.0, start=F.FlightState(speed=100.0))


def test_python_defaults_are_the_c_defaults():
    from pywarp.core.binding import ffi, lib

    p = ffi().new("ccl_flight_params *")
    lib().ccl_flight_params_default(p)
    m = F.FlightModel()
    for name in F.FlightModel.__dataclass_fields__:
        assert getattr(p, name) == pytest.approx(getattr(m, name), rel=1e-7), name


# --- oc-6.1: the procedural aircraft -------------------------------------------------------------------------------------

@pytest.mark.spec("oc-6.1")
def test_aircraft_model_parts_and_height_points():
    d, part = pywarp.equation("oc-6.1")(np.float32([[0, 0, 0], [5, -0.25, -0.9], [0, 1.2, 3.35], [0, 0.75, -1.4]]))
    assert np.all(d < 0) and part.tolist() == [0, 1, 2, 3]
    # the height points of oc-6.1.1 lie on the skin: nose A, tail end B, wing tips C, D
    m = F.FlightModel()
    pts = np.float32([[0, 0, -m.length / 2 - 0.05], [-m.span / 2, -0.25, -0.9], [m.span / 2, -0.25, -0.9]])
    d, _ = pywarp.equation("oc-6.1")(pts)
    assert np.all(np.abs(d) < 0.06)
    # far away: a lower bound of the distance, within the bounding radius
    d, _ = pywarp.equation("oc-6.1")(np.float32([0, 100, 0]))
    assert 98.0 < float(d) < 100.0
    rng = np.random.default_rng(3)
    assert_twins_agree("oc-6.1", rng.uniform(-7, 7, (500, 3)).astype(np.float32))


@pytest.mark.spec("oc-6.1")
def test_aircraft_distance_is_safe_for_sphere_tracing():
    # |d(p) - d(q)| <= |p - q| (1-Lipschitz) on random pairs: sphere tracing never steps through the model
    rng = np.random.default_rng(4)
    p = rng.uniform(-7, 7, (2000, 3)).astype(np.float32)
    q = (p + rng.normal(0, 0.3, p.shape)).astype(np.float32)
    dp, _ = pywarp.equation("oc-6.1")(p)
    dq, _ = pywarp.equation("oc-6.1")(q)
    assert np.all(np.abs(dp - dq) <= np.linalg.norm(p - q, axis=1) * (1 + 1e-5) + 1e-5)


def test_host_axes_are_the_c_axes():
    from pywarp.core.binding import ffi, lib

    f_, r_, u_ = (ffi().new("ccl_vec3 *") for _ in range(3))
    for h, p, r in [(0.0, 0.0, 0.0), (0.7, 0.3, 0.4), (-2.0, -0.4, -0.7)]:
        lib().ccl_flight_axes(h, p, r, f_, r_, u_)
        f, rr, u = F.axes(h, p, r)
        for got, want in ((f, f_), (rr, r_), (u, u_)):
            assert got == pytest.approx((want.x, want.y, want.z), abs=2e-7)
        assert np.dot(f, rr) == pytest.approx(0.0, abs=1e-6)
