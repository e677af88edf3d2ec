"""The viewer's controls interface (pywarp.viewer.controls): the free-fly default on the settings' camera fields (keys
move the camera as the bindings say, values stay in their specs' domains), scenes without camera fields, a scene's
own controls, and backward compatibility of Scene."""
from __future__ import annotations

import math
from dataclasses import dataclass

import pytest

from pywarp.core import scenes as S
from pywarp.core.pose import camera_fields
from pywarp.viewer import controls as V
from pywarp.core.params import Settings, param


def clouds():
    return S.scene("clouds")


def flat(**kw):
    """Clouds settings with a level camera at the origin looking along -z."""
    values = dict(camera_x_km=0.0, camera_z_km=0.0, camera_altitude_km=0.3, camera_yaw_deg=0.0,
                  camera_pitch_deg=0.0)
    values.update(kw)
    return clouds().settings(**values)


def step(ctl, settings, dt=1.0, held=(), pressed=(), mouse=(0.0, 0.0), wheel=0.0):
    st = ctl.step(settings, V.Input(dt=dt, held=frozenset(held), pressed=frozenset(pressed), mouse=mouse,
                                    wheel=wheel))
    return st, (settings if not st.changes else __import__("dataclasses").replace(settings, **st.changes))


def test_clouds_camera_fields_are_found_by_name():
    assert camera_fields(clouds().settings) == {
        "x": "camera_x_km", "y": "camera_altitude_km", "z": "camera_z_km", "yaw": "camera_yaw_deg",
        "pitch": "camera_pitch_deg"}


def test_clouds_fly_freely_as_the_bindings_say():
    s = flat()
    ctl = V.make_controls(clouds(), s)
    assert isinstance(ctl, V.FreeFlyControls) and ctl.unit == "km" and ctl.speed == V.FREE_FLY_SPEED["km"]
    v = ctl.speed
    st, s1 = step(ctl, s, held={"W"})  # yaw 0, pitch 0: forward is -z
    assert st.moving and s1.camera_z_km == pytest.approx(-v) and s1.camera_x_km == pytest.approx(0.0)
    assert s1.camera_altitude_km == pytest.approx(0.3)
    _, s2 = step(ctl, s, held={"S"})
    assert s2.camera_z_km == pytest.approx(v)
    _, s3 = step(ctl, s, held={"D"})  # strafe right: +x
    assert s3.camera_x_km == pytest.approx(v) and s3.camera_z_km == pytest.approx(0.0)
    _, s4 = step(ctl, s, held={"E"}, dt=0.5)
    assert s4.camera_altitude_km == pytest.approx(0.3 + 0.5 * v)
    _, s5 = step(ctl, flat(camera_yaw_deg=90.0), held={"W"})  # yaw 90: forward is +x
    assert s5.camera_x_km == pytest.approx(v) and s5.camera_z_km == pytest.approx(0.0, abs=1e-12)
    _, s6 = step(ctl, flat(camera_pitch_deg=30.0), held={"W"})  # flies along the view: climbs with the pitch
    assert s6.camera_altitude_km == pytest.approx(0.3 + v * math.sin(math.radians(30.0)))
    _, s7 = step(ctl, s, held={"W", "Shift"})
    assert s7.camera_z_km == pytest.approx(-10 * v)


def test_free_fly_looks_with_arrows_and_mouse_drag():
    s = flat()
    ctl = V.make_controls(clouds(), s)
    _, s1 = step(ctl, s, held={"Right"}, dt=0.5)
    assert s1.camera_yaw_deg == pytest.approx(0.5 * V.FREE_FLY_TURN_DEG_S)
    _, s2 = step(ctl, s, held={"Up"}, dt=0.25)
    assert s2.camera_pitch_deg == pytest.approx(0.25 * V.FREE_FLY_TURN_DEG_S)
    _, s3 = step(ctl, s, mouse=(10.0, -5.0), dt=0.0)  # drag right and up: look right and up
    assert s3.camera_yaw_deg == pytest.approx(10 * V.FREE_FLY_MOUSE_DEG)
    assert s3.camera_pitch_deg == pytest.approx(5 * V.FREE_FLY_MOUSE_DEG)


def test_free_fly_stays_in_the_domains_of_the_specs():
    ctl = V.make_controls(clouds(), flat())
    _, s1 = step(ctl, flat(camera_pitch_deg=80.0), held={"Up"}, dt=10.0)
    assert s1.camera_pitch_deg == 89.0  # the spec's hi
    _, s2 = step(ctl, flat(camera_altitude_km=0.1), held={"Q"}, dt=10.0)
    assert s2.camera_altitude_km == 0.0  # the spec's lo: not below the ground


def test_free_fly_yaw_wraps_around():
    ctl = V.make_controls(clouds(), flat())
    _, s1 = step(ctl, flat(camera_yaw_deg=170.0), held={"Right"}, dt=0.5)  # +30 deg
    assert s1.camera_yaw_deg == pytest.approx(-160.0)
    _, s2 = step(ctl, flat(camera_yaw_deg=-175.0), mouse=(-50.0, 0.0), dt=0.0)  # -10 deg
    assert s2.camera_yaw_deg == pytest.approx(175.0)


def test_free_fly_speed_keys_and_nothing_held_is_still():
    s = flat()
    ctl = V.make_controls(clouds(), s)
    v = ctl.speed
    st, _ = step(ctl, s)
    assert not st.moving and st.changes == {} and "km/s" in st.message
    step(ctl, s, pressed={"+"})
    assert ctl.speed == 2 * v
    step(ctl, s, pressed={"-"}, wheel=-1.0)
    assert ctl.speed == v / 2


def test_clouds_preview_turns_reprojection_on_with_a_cheaper_march():
    from pywarp.clouds.controls import PREVIEW_MARCH, PREVIEW_SAMPLES

    changes = V.make_controls(clouds(), flat()).preview(flat())
    assert changes == {"reprojection": True, "samples_min": PREVIEW_SAMPLES[0], "samples_max": PREVIEW_SAMPLES[1],
                       "advanced": PREVIEW_MARCH}
    # the preview settings are valid settings, and a user's own values win where they are already cheaper or set
    own = flat(samples_min=16, samples_max=24, advanced={"exit_eps": 0.1})
    mine = V.make_controls(clouds(), own).preview(own)
    assert (mine["samples_min"], mine["samples_max"]) == (16, 24)
    assert mine["advanced"]["exit_eps"] == 0.1 and mine["advanced"]["light_interp"] == PREVIEW_MARCH["light_interp"]
    __import__("dataclasses").replace(own, **mine)
    assert V.FreeFlyControls.bindings and V.FreeFlyControls.benchmark_keys


@dataclass(frozen=True)
class _Plain(Settings):
    gain: float = param(1.0, lo=0.0, hi=2.0, doc="a gain", reason="1: the identity")


def _technique(settings):
    raise AssertionError("not rendered here")


def test_a_scene_without_camera_fields_opens_with_the_default_and_moves_nothing():
    sc = S.Scene("plain", "a scene without a camera", _Plain, _technique)
    assert sc.controls is None  # the new field is optional: older registrations are unchanged
    ctl = V.make_controls(sc, _Plain())
    assert isinstance(ctl, V.FreeFlyControls) and ctl.fields == {}
    st, _ = step(ctl, _Plain(), held={"W", "Right", "E"})
    assert st.changes == {} and not st.moving and ctl.preview(_Plain()) == {}


class _Toggle(V.Controls):
    bindings = (V.Binding("G / H", "lower / raise the gain"),)

    def step(self, settings, inp):
        changes = {}
        if "H" in inp.pressed:
            changes["gain"] = min(settings.gain + 0.5, 2.0)
        if "G" in inp.pressed:
            changes["gain"] = max(settings.gain - 0.5, 0.0)
        return V.Step(changes=changes, moving=bool(changes), message=f"gain {settings.gain:g}")


def test_a_scene_supplies_its_own_controls():
    sc = S.Scene("plain", "own controls", _Plain, _technique, controls=_Toggle)
    ctl = V.make_controls(sc, _Plain())
    assert isinstance(ctl, _Toggle) and ctl.bindings[0].keys == "G / H"
    st, s1 = step(ctl, _Plain(), pressed={"H"})
    assert s1.gain == 1.5 and st.moving
    bad = S.Scene("plain", "bad controls", _Plain, _technique, controls=lambda s: object())
    with pytest.raises(TypeError, match="must be a Controls"):
        V.make_controls(bad, _Plain())


def test_every_registered_scene_makes_its_controls():
    for sc in S.scenes().values():
        ctl = V.make_controls(sc, sc.settings())
        assert isinstance(ctl, V.Controls) and isinstance(ctl.bindings, tuple)
        for b in ctl.bindings:
            assert isinstance(b, V.Binding) and b.keys and b.help
