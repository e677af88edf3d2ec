"""The display transform (pywarp.core.display): the tone curves' shape, the settings' checks, the 'none' curve giving
the bytes of the plain clamp, and no clipped channel in the scenes' default images and a noon sun over thin cloud."""
from __future__ import annotations

import numpy as np
import pytest

from pywarp.core import display as D


@pytest.mark.parametrize("tonemap", D.TONEMAPS)
@pytest.mark.parametrize("ev", [-2.0, 0.0, 1.5])
def test_curves_map_zero_to_zero_and_are_monotonic(tonemap, ev):
    x = np.concatenate([np.linspace(0.0, 2.0, 4001), np.geomspace(2.0, 1e4, 500)]).astype(np.float32)
    y = D.apply(x, ev, tonemap)
    assert y[0] == 0.0
    assert np.all(np.diff(y) >= 0.0)
    if tonemap != "none":  # strictly increasing below the shoulder: no flat band where detail would vanish
        assert np.all(np.diff(y[:4001]) > 0.0)  # x in [0, 2]
        assert np.all(y <= 1.0)


def test_aces_matches_narkowicz_at_hand_computed_points():
    # x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14): 0.18 -> 0.086724 / 0.324932, 1 -> 2.54 / 3.16
    np.testing.assert_allclose(D.apply(np.float32([0.18, 1.0]), 0.0, "aces"), [0.086724 / 0.324932, 2.54 / 3.16],
                               rtol=1e-6)
    assert D.apply(np.float32([8.0]), 0.0, "aces")[0] == 1.0  # saturates above x = 7.24
    np.testing.assert_allclose(D.apply(np.float32([1.0]), 1.0, "exponential"), [1.0 - np.exp(-2.0)], rtol=1e-6)


def test_negative_values_map_to_black_and_non_finite_stays_non_finite():
    y = D.apply(np.float32([-1.0, np.inf, np.nan]), 0.0, "aces")
    assert y[0] == 0.0 and not np.isfinite(y[1]) and not np.isfinite(y[2])


def test_bad_settings_name_the_field():
    with pytest.raises(ValueError, match="exposure_ev"):
        D.apply(np.zeros(3), 11.0, "aces")
    with pytest.raises(ValueError, match="tonemap"):
        D.apply(np.zeros(3), 0.0, "reinhard")


def test_none_at_zero_ev_is_the_plain_clamp_and_quantisation():
    rng = np.random.default_rng(1)
    x = rng.uniform(-0.5, 1.7, (16, 16, 3)).astype(np.float32)
    assert np.array_equal(D.apply(x, 0.0, "none"), x)
    assert np.array_equal(D.encode_encoded(x, 0.0, "none"), (np.clip(x, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8))


def test_encoded_scenes_round_trip_through_linear_light():
    # a display-encoded value decoded, passed through 'none' at +1 EV and encoded again: sRGB(2 * sRGB^-1(v))
    v = np.float32([[[0.2, 0.5, 0.7]]])
    lin = np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4) * 2.0
    want = np.where(lin <= 0.0031308, 12.92 * lin, 1.055 * np.minimum(lin, 1.0) ** (1 / 2.4) - 0.055)
    got = D.encode_encoded(v, 1.0, "none")
    assert np.max(np.abs(got.astype(int) - (np.clip(want, 0, 1) * 255 + 0.5).astype(int))) <= 1


def test_the_tabulated_curve_of_encoded_scenes_is_the_per_pixel_evaluation_within_one_level():
    x = np.random.default_rng(2).uniform(0.0, 1.0, (64, 64, 3)).astype(np.float32)
    lin = np.where(x <= 0.04045, x / 12.92, ((x.astype(np.float64) + 0.055) / 1.055) ** 2.4)
    y = lin * 2.0 ** -0.3
    y = np.clip(y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14), 0.0, 1.0)
    want = (np.where(y <= 0.0031308, 12.92 * y, 1.055 * y ** (1 / 2.4) - 0.055) * 255.0 + 0.5).astype(int)
    got = D.encode_encoded(x, -0.3, "aces").astype(int)
    assert np.abs(got - want).max() <= 1 and (got != want).mean() < 0.01


# --- the scenes --------------------------------------------------------------------------------------------------

def _clipped(img) -> float:
    return float((np.asarray(img) == 255).any(axis=2).mean())


@pytest.fixture(scope="module")
def small_clouds():
    from pywarp.clouds.settings import CloudscapeSettings

    return CloudscapeSettings(width=160, height=90)


def test_clouds_none_gives_the_bytes_of_the_clamp_encoder(small_clouds):
    from dataclasses import replace

    import warp as wp

    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.kernels import cloudscape as K

    s = replace(small_clouds, tonemap="none", exposure_ev=0.0)
    linear = CloudscapeTechnique(s).render(encode=False)
    tech = CloudscapeTechnique(s)
    got = tech.render()
    # the encoder before the display transform: encode_kernel straight on the frame
    out = wp.zeros(linear.shape, dtype=wp.uint8, device=tech.device)
    bad = wp.zeros(1, dtype=wp.int32, device=tech.device)
    tech.launcher.launch(K.encode_kernel, s.height, s.width, [wp.array(linear, dtype=float, device=tech.device)],
                         [out, bad])
    assert np.array_equal(got, out.numpy())
    assert linear.max() > 1.0 and _clipped(got) > 0.0  # the default view is HDR: the clamp clips it


def test_clouds_default_view_and_noon_sun_over_thin_cloud_do_not_clip(small_clouds):
    from dataclasses import replace

    from pywarp.clouds.technique import CloudscapeTechnique

    noon = replace(small_clouds, sun_elevation_deg=80.0, coverage=0.3, turbidity=8.0, camera_pitch_deg=20.0)
    for s in (small_clouds, noon):
        tech = CloudscapeTechnique(s)
        linear = tech.render(encode=False)
        img = CloudscapeTechnique(s).render()
        assert _clipped(img) == 0.0, (s.sun_elevation_deg, float(linear.max()))
    assert linear.max() > 1.2  # the noon sun is HDR: a plain clamp would clip it


def test_terrain_none_is_todays_encoding_and_the_default_does_not_clip():
    from pywarp.terrain.settings import TerrainSettings
    from pywarp.terrain.technique import TerrainTechnique

    s = TerrainSettings(width=160, height=90, tonemap="none", exposure_ev=0.0)
    tech = TerrainTechnique(s)
    colours = tech.render(encode=False)
    assert np.array_equal(TerrainTechnique(s).render(), (colours * 255.0 + 0.5).astype(np.uint8))
    assert _clipped(TerrainTechnique(s).render()) > 0.0  # the sun's disc, clamped
    assert _clipped(TerrainTechnique(TerrainSettings(width=160, height=90)).render()) == 0.0


def test_display_settings_are_command_line_options():
    from pywarp.clouds.settings import CloudscapeSettings
    from pywarp.core.params import specs
    from pywarp.terrain.settings import TerrainSettings

    for cls in (CloudscapeSettings, TerrainSettings):
        opts = {p.name: p.option for p in specs(cls)}
        assert opts["exposure_ev"] == "--exposure" and opts["tonemap"] == "--tonemap"
