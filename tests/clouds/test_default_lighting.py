"""The renderer's default lighting is the measured model of issue 32 (``PHYSICAL_MODELS[CONVERGED_MODEL]`` of
pywarp/clouds/bench_reference.py, docs/lighting.rst): the Python defaults, the C defaults
(``ccl_cloudscape_params_default``) and the model's lighting fields agree field by field, so that none can drift from
the others. The thesis's lighting stays the thesis's: ``THESIS_LIGHTING`` (:meth:`c_values`) sets the neutral values,
and no lighting term of the model changes a pixel of lighting='thesis', C or Warp."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pywarp.clouds.bench_reference import CONVERGED_MODEL, MEDIA, PHYSICAL_MODELS
from pywarp.clouds.cloudscape import render_frame_c, render_pixels_c, render_pixels_warp
from pywarp.clouds.settings import CLOUDSCAPE_PARAMS, THESIS_LIGHTING, CloudscapeSettings
from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.core.pose import Pose

SMALL = dict(width=32, height=18, base_size=32, detail_size=16, curl_size=32, weather_size=64)
#: Fields of the model that belong to the comparison's medium, not to the lighting: the reference's air does not
#: scatter, so every model of the physical medium runs without aerial perspective (aerial_km 0); the renderer keeps
#: its haze. (MEDIA's own fields, units and phase, are the medium's too.)
MEDIUM_FIELDS = {"aerial_km", *MEDIA["physical"]}
#: The model's lighting terms switched off (their values before they became the defaults): the thesis's lighting
#: must not see any of them.
OFF = dict(ambient_ground_weight=0.0, mie_delta=0.0, ms_depth=0.0, ms_thin=0.0, ms_view=0.0, ms_view_trans=1.0,
           ambient_aniso=0.0, ms_slab=0.0, ms_slab_mu=1.0, ms_slab_far=0.0)


def _model():
    """The lighting of the converged model: (its settings fields, its ``advanced`` C fields)."""
    model = dict(PHYSICAL_MODELS[CONVERGED_MODEL])
    advanced = model.pop("advanced", {})
    return {k: v for k, v in model.items() if k not in MEDIUM_FIELDS}, advanced


def test_the_model_has_lighting_terms_to_compare():
    fields, advanced = _model()
    # the test below compares something: the model's terms beyond the octaves and its ms_b
    assert {"mie_delta", "ms_depth", "ms_view", "ambient_aniso", "ms_slab", "ambient_ground_weight"} <= set(fields)
    assert "ms_b" in advanced


def test_python_defaults_are_the_converged_model():
    fields, _ = _model()
    s = CloudscapeSettings()
    for name, value in fields.items():
        assert getattr(s, name) == value, (name, getattr(s, name), value)


def test_c_defaults_are_the_converged_model():
    """``ccl_cloudscape_params_default`` holds the model's values (float32), its ``advanced`` fields (ms_a, ms_b)
    included; and the model's settings on top of the defaults change no field of the C parameters."""
    fields, advanced = _model()
    c = CLOUDSCAPE_PARAMS.defaults()
    for name, value in advanced.items():
        assert c[name] == np.float32(value), (name, c[name], value)
    defaults = CloudscapeSettings()
    model = dataclasses.replace(defaults, **fields, advanced=advanced)
    v_default, v_model = defaults.c_values(), model.c_values()
    assert v_default == v_model, {k: (v_default[k], v_model[k]) for k in v_default if v_default[k] != v_model[k]}
    # the Python defaults reach the C struct as the C defaults (Python mirrors C)
    for name in v_default:
        if name in c and name in {**fields, **advanced}:
            assert np.float32(v_default[name]) == np.float32(c[name]), (name, v_default[name], c[name])


def test_thesis_lighting_sets_the_neutral_values_before_advanced():
    """lighting='thesis': c_values sets every field of THESIS_LIGHTING, each of which the defaults turn on (or, the
    lobe, may be turned on), and ``advanced`` may still set one (figure 2.17's silver lobe under the thesis's
    lighting)."""
    defaults = CloudscapeSettings(**SMALL).c_values()
    v = CloudscapeSettings(**SMALL, lighting="thesis").c_values()
    for name, value in THESIS_LIGHTING.items():
        assert v[name] == value, name
        assert name == "silver_weight" or defaults[name] != value, name
    lobe = CloudscapeSettings(**SMALL, lighting="thesis", advanced={"silver_weight": 0.3}).c_values()
    assert lobe["silver_weight"] == 0.3 and lobe["ambient_aniso"] == 0.0


@pytest.mark.parametrize("phase", ["thesis", "mie"])
def test_no_lighting_term_changes_a_thesis_pixel(phase):
    """lighting='thesis' with the defaults and with every term of the model off (and ms_b back at 0.5): the same
    pixels, bit for bit, Warp and C -- under the Mie phase too, where mie_delta would otherwise change the phase."""
    pose = Pose(0.0, 0.3, 0.0, 0.0, 20.0, 60.0)
    on = CloudscapeSettings(**SMALL, lighting="thesis", phase=phase, jitter="none")
    off = dataclasses.replace(on, **OFF, advanced={"ms_b": 0.5})
    t_on = CloudscapeTechnique(on)
    t_off = CloudscapeTechnique(off, textures=t_on.textures)
    img_on = t_on.render(pose, reprojection=False, encode=False)
    assert np.ptp(img_on) > 0.1  # clouds and sky in the frame
    np.testing.assert_array_equal(img_on, t_off.render(pose, reprojection=False, encode=False))
    np.testing.assert_array_equal(render_frame_c(on, t_on.textures, pose), render_frame_c(off, t_on.textures, pose))


def test_the_default_terms_act_with_sky_lighting():
    """The same comparison with sky lighting: the terms change the pixels (the comparison above can fail), C and Warp
    alike."""
    pose = Pose(0.0, 0.3, 0.0, 0.0, 20.0, 60.0)
    on = CloudscapeSettings(**SMALL, phase="mie", jitter="none")
    off = dataclasses.replace(on, **OFF, advanced={"ms_b": 0.5})
    t_on = CloudscapeTechnique(on)
    t_off = CloudscapeTechnique(off, textures=t_on.textures)
    rng = np.random.default_rng(5)
    xs, ys = rng.integers(0, SMALL["width"], 60), rng.integers(0, SMALL["height"], 60)
    assert np.abs(t_on.render(pose, reprojection=False, encode=False)
                  - t_off.render(pose, reprojection=False, encode=False)).max() > 0.01
    c_on = render_pixels_c(on, t_on.textures, xs, ys, pose)
    assert np.abs(c_on - render_pixels_c(off, t_on.textures, xs, ys, pose)).max() > 0.01
    np.testing.assert_allclose(render_pixels_warp(t_on, xs, ys, pose), c_on, rtol=0, atol=1e-5)
