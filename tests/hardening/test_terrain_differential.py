"""Differential property test of the terrain pixel (pt-alg-7.1.6): settings drawn at the edges of what
:class:`pywarp.terrain.settings.TerrainSettings` and ``ccl_terrain_params_check`` accept, rendered at a few pixels by
the Warp kernel and by the C reference (``fuzz_terrain`` covers the C side alone): both finite, colours and step
counts bit for bit equal, as ``tests/terrain`` expects at the defaults. A set the settings refuse is skipped (the
refusals are tested in tests/terrain and test_fuzz_findings.py). Deterministic (``derandomize=True``, no example
database); ``PYWARP_DIFF_EXAMPLES`` sets another number of examples for a longer search (default 60)."""
from __future__ import annotations

import numpy as np
import pytest
from helpers import differential_settings

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import assume, given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from pywarp.terrain.settings import TerrainSettings  # noqa: E402
from pywarp.terrain.technique import render_pixels_c, render_pixels_warp  # noqa: E402

SETTINGS = differential_settings(60)
SIZE = dict(width=48, height=27)

#: settings, each at its edges and a typical value (the march's lengths kept small enough for a quick test)
FIELDS = {
    "camera_y": [-1e4, 0.0, 9.0, 1e4],
    "camera_pitch_deg": [-89.0, -8.0, 0.0, 89.0],
    "camera_yaw_deg": [0.0, 271.0],
    "fov_y_deg": [1.0, 90.0, 170.0],
    "sun_elevation_deg": [0.5, 20.0, 90.0],
    "heightmap": ["fbm", "test"],
    "seed": [0, 5, 2 ** 32 - 1],
    "march_octaves": [1, 4, 16],
    "height_scale": [0.0, 12.0, 1000.0],
    "horizontal_scale": [0.015625, 24.0, 1e4],
    "march": ["dynamic", "fixed", "bisect"],
    "max_t": [1e-3, 400.0, 1e4],
    "step_size": [0.015625, 0.1, 100.0],
    "precision": [1e-6, 0.01, 10.0],
    "max_steps": [1, 300, 3000],
    "step_scale": [1e-3, 0.5, 1.0],
    "bisect_steps": [0, 6, 64],
    "slab": [True, False],
    "precision_per_unit": [0.0, 1.0],
    "normal_h": [1e-6, 0.002, 1.0],
    "normal_octaves_max": [1, 9, 16],
    "lod_distance": [1e-3, 15.0, 1e4],
    "shadows": ["soft", "hard", "none"],
    "shadow_k": [1e-3, 4.0, 1000.0],
    "shadow_max_t": [1e-3, 80.0, 1e4],
    "fog_density": [1e-6, 0.0018, 100.0],
    "sun_power": [1e-3, 80.0, 1e4],
    "clouds": ["corrected", "thesis"],
    "cloud_scale": [0.015625, 150.0, 1e6],
    "time_s": [0.0, 1e6],
    "water_level": [-1e4, -5.0, 1e4],
    "wave_scale": [0.015625, 2.0, 1e4],
    "wave_strength": [0.0, 0.08, 10.0],
    "stage": ["final", "atmosphere", "materials", "heightmap"],
}


@SETTINGS
@given(changes=st.lists(st.sampled_from(sorted(FIELDS)), max_size=6, unique=True).flatmap(
           lambda ks: st.fixed_dictionaries({k: st.sampled_from(FIELDS[k]) for k in ks})),
       seed=st.integers(0, 2 ** 16))
def test_warp_pixels_finite_and_bit_equal_to_c_at_the_edges(changes, seed):
    try:
        s = TerrainSettings(**SIZE, **changes)
    except ValueError:
        assume(False)  # refused before any kernel runs: not this test's subject
    rng = np.random.default_rng(seed)
    xs, ys = rng.integers(0, s.width, 12), rng.integers(0, s.height, 12)
    cw, sw = render_pixels_warp(s, xs, ys)
    cc, sc = render_pixels_c(s, xs, ys)
    assert np.all(np.isfinite(cw)) and np.all(np.isfinite(cc)), changes
    np.testing.assert_array_equal(cw, cc, err_msg=str(changes))
    np.testing.assert_array_equal(sw, sc, err_msg=str(changes))
