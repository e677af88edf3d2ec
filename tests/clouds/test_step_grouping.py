"""The grouping of short view steps (CCL_CLOUDSCAPE_GROUP_SPAN in cclouds/cloudscape.h): with the refinement on,
steep rays whose view steps are already no longer than refine_step_km take one coarse test (base shape, no detail)
per group of steps spanning at most 2 x refine_step_km, and skip a group where the tests at both of its ends find no
cloud.

The reference is the march without it (refine_step_km = 0, the thesis's march): on rays whose steps are short it is
the same march sample for sample, except for the skipped groups. A group is skipped wrongly only where a cloud lies
wholly between two coarse tests, so the frames must agree except in a few pixels, while many of the view samples
are no longer taken -- also for the thinnest clouds (stratus), whose density is positive only in small pockets at
their edges: with groups of up to 0.8 km those pockets were missed by some pixels and not by their neighbours (0.8 %
of a stratus frame off by more than 8 levels of 8 bits). C and Warp agree on a grouped view in
tests/clouds/test_cloudscape.py (test_warp_pixels_match_c_reference)."""
import numpy as np
import pytest
from helpers import LIGHTING_TERMS_OFF

from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.clouds.settings import CloudscapeSettings
from pywarp.core.pose import Pose

#: a view from below the layer pitched up so far that every ray's view steps are short (elevation >= 15 deg: the
#: 2.5 km layer takes <= 9.7 km of ray in >= 100 steps, < 0.1 km each): every ray is grouped
#: (under the lighting without the terms of issue 32, helpers.LIGHTING_TERMS_OFF)
STEEP = dict(camera_pitch_deg=45.0, fov_y_deg=60.0, jitter="offset", **LIGHTING_TERMS_OFF)
#: the default clouds (mostly cumulus) and the thinnest ones, stratus, at full texture size
GENERA = {"default": {}, "stratus": dict(cloud_type=0.0, coverage=0.9)}


@pytest.fixture(scope="module", params=sorted(GENERA))
def pair(request):
    out = {}
    tex = None
    for name, kw in {"grouped": {}, "ungrouped": dict(refine_step_km=0.0)}.items():
        s = CloudscapeSettings(width=240, height=135, **STEEP, **GENERA[request.param], **kw)
        t = CloudscapeTechnique(s, textures=tex)
        tex = t.textures
        pose = Pose.from_settings(s)
        out[name] = t.render(pose, reprojection=False, encode=False)
        out[name + "_samples"] = t.samples_taken().astype(np.int64)
        # the next frame: the same march at another jitter offset, the variation every frame already has
        out[name + "_next"] = t.render(pose, reprojection=False, encode=False)
    s = CloudscapeSettings(width=240, height=135, **STEEP, **{**GENERA[request.param], "coverage": 0.0})
    out["clear"] = CloudscapeTechnique(s).render(Pose.from_settings(s), reprojection=False, encode=False)
    return out


@pytest.mark.spec("vc-A17", "vc-A18", "vc-A21")
def test_grouping_skips_view_samples(pair):
    grouped, ungrouped = pair["grouped_samples"], pair["ungrouped_samples"]
    # the steep rays take 64..115 view samples each without grouping (fewer where a dense cloud ends the march);
    # with it, empty air costs one test per group of up to 8 steps (0.2 km): measured 0.45 of the samples
    assert np.median(ungrouped) >= 64
    assert grouped.sum() < 0.6 * ungrouped.sum()


@pytest.mark.spec("vc-A17", "vc-A18", "vc-A21")
def test_grouping_changes_the_frame_far_less_than_the_jitter_does(pair):
    """The yardstick is the march's own sampling: the ungrouped march's next frame (another jitter offset) differs
    from this one in 6 % (default) / 30 % (stratus) of the pixels by more than a level of 8 bits. Grouping changes
    0.09 % / 0.27 % (the pockets of cloud shorter than a group that both of its ends miss), by at most 3.6 / 15
    levels against the jitter's 7.5 / 32. Groups of up to 0.8 km fail: 5.9 % of the stratus frame, and up to 43
    levels in the default one."""
    a, b, jittered = pair["grouped"], pair["ungrouped"], pair["ungrouped_next"]
    assert np.all(np.isfinite(a))
    # the frame has clouds in it (else agreement would prove nothing): many pixels differ from the clear sky
    assert np.mean(np.abs(b - pair["clear"]).max(axis=2) > 0.02) > 0.2
    group = np.abs(a - b).max(axis=2)
    jitter = np.abs(jittered - b).max(axis=2)
    level = 1.0 / 255.0
    assert np.mean(group > level) < 0.05 * np.mean(jitter > level)
    assert group.mean() < 0.05 * jitter.mean()
    assert group.max() <= jitter.max()
