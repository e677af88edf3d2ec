"""Differential property test of the flight scene's frame pixel (the cloud volumes, the aircraft, the sky and the
ground through ``ccl_volume_pixel`` and its Warp twin): the lighting, camera and quality settings of
:class:`pywarp.flight.settings.FlightSettings` at the edges of what they accept, both views, moments along the whole
flight; one small cloud field (generated once; its settings are the volume test's and the voxel harness's subject).
The Warp and C pixels are finite and equal within the tolerance of
``tests/flight/test_flight_scene.py::test_warp_matches_the_c_reference_pixel``. A set the settings refuse is skipped.
Deterministic (``derandomize=True``, no example database); ``PYWARP_DIFF_EXAMPLES`` sets another number of examples
for a longer search (default 40)."""
from __future__ import annotations

import numpy as np
import pytest
from helpers import differential_settings

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import assume, given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from pywarp.flight.settings import FlightSettings  # noqa: E402
from pywarp.flight.technique import FlightPose, FlightTechnique  # noqa: E402

SETTINGS = differential_settings(40)
SMALL = dict(width=64, height=36, cloud_count=3, cloud_size=32)

#: settings that need no new cloud field, each at its edges and a typical value
FIELDS = {
    "sun_elevation_deg": [1.0, 35.0, 90.0],
    "sun_azimuth_deg": [0.0, 150.0, -720.0],
    "tau_per_voxel": [0.0, 0.35, 50.0],
    "light_tau_per_voxel": [0.0, 0.25, 50.0],
    "g": [-0.999, 0.0, 0.3, 0.999],
    "fog_distance_m": [1.0, 6000.0, 1e7],
    "step_voxels": [0.05, 1.0, 16.0],
    "light_step_voxels": [0.05, 1.0, 16.0],
    "chase_distance_m": [1.0, 22.0, 10000.0],
    "chase_height_m": [-1000.0, 7.0, 1000.0],
    "fov_y_deg": [1.0, 60.0, 170.0],
}


@pytest.fixture(scope="module")
def tech():
    return FlightTechnique(FlightSettings(**SMALL))


@SETTINGS
@given(changes=st.lists(st.sampled_from(sorted(FIELDS)), max_size=5, unique=True).flatmap(
           lambda ks: st.fixed_dictionaries({k: st.sampled_from(FIELDS[k]) for k in ks})),
       view=st.sampled_from(["chase", "cockpit"]), moment=st.sampled_from([0.0, 0.25, 0.5, 1.0]),
       seed=st.integers(0, 2 ** 16))
def test_warp_pixels_finite_and_equal_to_c_at_the_edges(tech, changes, view, moment, seed):
    try:
        FlightSettings(**SMALL, **changes)
    except ValueError:
        assume(False)  # refused before any kernel runs: not this test's subject
    defaults = {k: getattr(FlightSettings(**SMALL), k) for k in FIELDS}
    tech.update(**{**defaults, **changes})  # (the fixture's technique: every field of FIELDS set each time)
    pose = FlightPose(moment * tech.settings.flight_duration_s, view)
    rng = np.random.default_rng(seed)
    xs, ys = rng.integers(0, 64, 24), rng.integers(0, 36, 24)
    w = tech.render_pixels_warp(xs, ys, pose)
    c = tech.render_pixels_c(xs, ys, pose)
    assert np.all(np.isfinite(w)) and np.all(np.isfinite(c)), (changes, view, moment)
    np.testing.assert_allclose(w, c, rtol=1e-5, atol=1e-6, err_msg=f"{changes} {view} {moment}")
