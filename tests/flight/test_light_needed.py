"""The flight still's light volumes as the technique computes them: shared out among the launcher's workers and
marched only where a ray reads them (``VolumeSet.compute_light(..., launcher=, needed_only=True)``). The voxels a
ray reads (:func:`pywarp.flight.volumes.grown`) keep the values of the one-thread-per-voxel twin of
``ccl_volume_light`` exactly, the others are 1, and the rendered pixels are the same bit for bit. Also the brick
occupancy against a direct loop over its definition."""
from __future__ import annotations

import numpy as np
import pytest

from pywarp.flight import volumes as V
from pywarp.flight.settings import FlightSettings
from pywarp.flight.technique import FlightTechnique


@pytest.fixture(scope="module")
def tech():
    return FlightTechnique(FlightSettings(width=96, height=54, time_s=6.0))


def test_needed_light_equals_the_full_light_where_read_and_the_pixels_are_the_same(tech):
    vs = tech.volumes
    values = tech.settings.c_values()
    needed = [l.copy() for l in vs.light]  # the technique's: launcher + needed_only
    vs.compute_light(values)  # the one-thread-per-voxel twin of ccl_volume_light, every voxel
    full = [l.copy() for l in vs.light]
    img_full = tech.render()
    for v, a, b in zip(vs.volumes, needed, full):
        g = V.grown(v.density)
        assert 0.05 < g.mean() < 0.95  # some voxels skipped, some marched: the test can fail both ways
        assert np.array_equal(a[g], b[g])
        assert np.all(a[~g] == 1.0)
        assert not np.array_equal(a, b)  # the skipped voxels' light was not 1 in the full volume
    vs.compute_light(values, launcher=tech.launcher)  # shared out, every voxel: the twin's values
    assert all(np.array_equal(a, b) for a, b in zip(vs.light, full))
    vs.compute_light(values, launcher=tech.launcher, needed_only=True)
    assert np.array_equal(tech.render(), img_full)


def _occupancy_loop(density):
    d = np.asarray(density) > 0
    b = V.BRICK
    shape = tuple(-(-n // b) for n in d.shape)
    out = np.zeros(shape, np.uint8)
    for bz in range(shape[0]):
        for by in range(shape[1]):
            for bx in range(shape[2]):
                sl = tuple(slice(max(k * b - 1, 0), min(k * b + b, n - 1) + 1) for k, n in zip((bz, by, bx), d.shape))
                out[bz, by, bx] = d[sl].any()
    return out


@pytest.mark.parametrize("shape", [(5, 7, 9), (8, 8, 8), (1, 3, 2), (17, 4, 33)])
@pytest.mark.parametrize("p", [0.0, 0.02, 0.3])
def test_occupancy_matches_its_definition(shape, p):
    d = (np.random.default_rng(7).random(shape) < p).astype(np.uint8) * 9
    assert np.array_equal(V.occupancy(d), _occupancy_loop(d))


def test_grown_is_the_26_neighbourhood():
    d = np.zeros((5, 6, 7), np.uint8)
    d[2, 3, 4] = 1
    g = V.grown(d)
    assert g.sum() == 27 and g[1:4, 2:5, 3:6].all()
    d[0, 0, 0] = 1
    assert V.grown(d)[:2, :2, :2].all() and V.grown(d).sum() == 27 + 8
