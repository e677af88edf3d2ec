"""Differential property test of the cloudscape pixel: parameter sets drawn at the edges of what the settings and
``ccl_cloudscape_check`` accept (the fuzz harness ``fuzz_cloudscape`` covers the C side alone; the Warp renderer has
paths of its own -- the empty-space skip, the base-shape bound, the half-float base texture), each rendered at a few
pixels by the Warp kernel and by the C reference: both finite, and equal within the tolerance of
``tests/clouds/test_cloudscape.py::test_warp_pixels_match_c_reference`` (relative to the values' size, since the sun
intensity scales them). A set the settings refuse is skipped: the refusal itself is tested in test_settings.py and
test_vc_findings.py. Deterministic (``derandomize=True``, no example database); ``PYWARP_DIFF_EXAMPLES`` sets another
number of examples for a longer search (default 150)."""
from __future__ import annotations

import numpy as np
import pytest
from helpers import differential_settings

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import assume, given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from pywarp.clouds.cloudscape import RenderTextures, render_pixels_c, render_pixels_warp  # noqa: E402
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.clouds.settings import CloudscapeSettings  # noqa: E402

SETTINGS = differential_settings(150)
#: small textures (generated once) and a small frame
TEXTURE_SIZES = dict(base_size=16, detail_size=16, curl_size=16, weather_size=64)
SIZE = dict(width=48, height=27)

#: public settings, each at its edges and a typical value
PUBLIC = {
    "camera_altitude_km": [0.0, 0.3, 2.5, 4.0, 8.0, 1000.0],
    "camera_pitch_deg": [-89.0, -25.0, 0.0, 12.0, 89.0],
    "camera_yaw_deg": [0.0, 137.0, -360.0],
    "fov_y_deg": [1.0, 60.0, 170.0],
    "sun_elevation_deg": [0.0, 2.0, 35.0, 90.0],
    "sky": ["preetham", "gradient"],
    "lighting": ["sky", "thesis"],
    "jitter": ["tilt", "offset", "none"],
    "coverage_threshold": ["one_minus_coverage", "coverage"],
    "sigma_per_km": [1e-3, 30.0, 1000.0],
    "g": [-0.999, 0.0, 0.2, 0.999],
    "samples_min": [1, 8],
    "samples_max": [8, 64],
    "refine_step_km": [0.0, 0.01, 0.1, 10.0],
    "refine_max": [1, 8, 64],
    "lod": [True, False],
    "lod_bias": [-4.0, 0.0, 4.0],
    "light_detail": [True, False],
    "powder": [True, False],
    "beer": [True, False],
    "base_precision": ["half", "single"],
    "weather_detile": [True, False],
    "march": ["fast", "textbook"],
    "ms_octaves": [1, 4, 8],
    "silver_weight": [0.0, 0.5, 1.0],
    "sun_intensity": [0.0, 16.0, 1000.0],
    "aerial_km": [0.0, 30.0, 1e6],
    "aerial_height_km": [0.0, 2.0, 1e6],
    "time_s": [0.0, 10800.0],
}
#: fields of ccl_cloudscape_params reached through ``advanced`` only
ADVANCED = {
    "exit_eps": [1e-6, 1.0 / 64.0, 0.999],
    "exit_fill": [0, 1],
    "light_interp": [0.0, 1.0 / 256.0, 1e3],
    "light_step_km": [1e-6, 0.1, 10.0],
    "light_far_factor": [1.0, 3.0, 1e4],
    "light_cone_angle": [0.0, 0.26, 1.5],
    "jitter_amount": [0.0, 1.0, 100.0],
    "ms_a": [0.0, 1.0],
    "ms_b": [0.0, 1.0],
    "ms_c": [0.0, 1.0],
}


def _subset(table: dict, most: int):
    keys = sorted(table)
    return st.lists(st.sampled_from(keys), max_size=most, unique=True).flatmap(
        lambda ks: st.fixed_dictionaries({k: st.sampled_from(table[k]) for k in ks}))


@pytest.fixture(scope="module")
def textures():
    return RenderTextures.generate(CloudscapeSettings(**TEXTURE_SIZES))


@SETTINGS
@given(public=_subset(PUBLIC, 8), advanced=_subset(ADVANCED, 4), seed=st.integers(0, 2 ** 16))
def test_warp_pixels_finite_and_equal_to_c_at_the_edges(textures, public, advanced, seed):
    try:
        s = CloudscapeSettings(**SIZE, **TEXTURE_SIZES, **public, advanced=advanced)
    except ValueError:
        assume(False)  # refused before any kernel runs: not this test's subject
    t = CloudscapeTechnique(s, textures=textures)
    rng = np.random.default_rng(seed)
    xs, ys = rng.integers(0, s.width, 24), rng.integers(0, s.height, 24)
    w = render_pixels_warp(t, xs, ys)
    c = render_pixels_c(s, textures, xs, ys)
    assert np.all(np.isfinite(w)), (public, advanced, w)
    assert np.all(np.isfinite(c)), (public, advanced, c)
    np.testing.assert_allclose(w, c, rtol=1e-5, atol=1e-5, err_msg=f"{public} {advanced}")
