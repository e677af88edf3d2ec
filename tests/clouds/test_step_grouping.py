"""The grouping of short view steps (cclouds/cloudscape.h, CCL_CLOUDSCAPE_COARSE_MAX_FACTOR's neighbour): with the
refinement on, steep rays whose view steps are already no longer than refine_step_km take one coarse test (base
shape, no detail) per refine_max steps and skip a group where the tests at both of its ends find no cloud.

The reference is the march without it (refine_step_km = 0, the thesis's march): on rays whose steps are short it is
the same march sample for sample, except for the skipped groups. A group is skipped wrongly only where a cloud lies
wholly between two coarse tests at most refine_step_km x refine_max apart, so the frames must agree except in a few
pixels, while most of the view samples are no longer taken. C and Warp agree on a grouped view in
tests/clouds/test_cloudscape.py (test_warp_pixels_match_c_reference)."""
import numpy as np
import pytest

from pywarp.clouds.cloudscape import CameraPose, CloudscapeTechnique
from tests.clouds.test_cloudscape import small

#: a view from below the layer pitched up so far that every ray's view steps are short (elevation >= 15 deg: the
#: 2.5 km layer takes <= 9.7 km of ray in >= 100 steps, < 0.1 km each): every ray is grouped
STEEP = dict(camera_pitch_deg=45.0, fov_y_deg=60.0)


@pytest.fixture(scope="module")
def steep_pair():
    out = {}
    tex = None
    for name, kw in {"grouped": {}, "ungrouped": dict(refine_step_km=0.0)}.items():
        t = CloudscapeTechnique(small(width=160, height=90, jitter="offset", **STEEP, **kw), textures=tex)
        tex = t.textures
        img = t.render(CameraPose.from_settings(t.settings), reprojection=False, encode=False)
        out[name] = (img, t.samples_taken().astype(np.int64))
    return out


@pytest.mark.spec("vc-A17", "vc-A18", "vc-A21")
def test_grouping_skips_most_view_samples(steep_pair):
    (_, grouped), (_, ungrouped) = steep_pair["grouped"], steep_pair["ungrouped"]
    # the steep rays take 64..115 view samples each without grouping (fewer where a dense cloud ends the march);
    # with it, empty air costs one test per 8 steps
    assert np.median(ungrouped) >= 64
    assert grouped.sum() < 0.5 * ungrouped.sum()


@pytest.mark.spec("vc-A17", "vc-A18", "vc-A21")
def test_grouping_changes_only_a_few_pixels(steep_pair):
    (a, _), (b, _) = steep_pair["grouped"], steep_pair["ungrouped"]
    assert np.all(np.isfinite(a))
    diff = np.abs(a - b).max(axis=2)
    # the frame has clouds in it (else agreement would prove nothing): many pixels differ from the clear sky
    clear = CloudscapeTechnique(small(width=160, height=90, jitter="offset", coverage=0.0, **STEEP)).render(
        reprojection=False, encode=False)
    assert np.mean(np.abs(b - clear).max(axis=2) > 0.02) > 0.2
    # the same march where a group is not skipped wrongly: most pixels bit for bit, and no more than 0.2 % of them
    # off by more than one level of 8 bits (a cloud wholly between two coarse tests, < 0.8 km of ray)
    assert np.mean(diff == 0.0) > 0.95
    assert np.mean(diff > 1.0 / 255.0) < 0.002
