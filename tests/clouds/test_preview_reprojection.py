"""The viewer's preview frames of the cloudscape above the layer (CloudscapeTechnique.preview / reprojects): a preview
above the layer top reprojects with the depth-aware reprojection; stills, the inner-sphere reprojection and cameras
inside the layer keep the thesis's full march (vc-A24)."""
from __future__ import annotations

import numpy as np
import pytest

from pywarp.clouds.settings import CloudscapeSettings
from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.core.pose import Pose

SMALL = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)
#: 6 km up (the default layer spans 1.5-4 km) looking 60 deg down: with the 60 deg field of view every ray hits the
#: inner sphere, so the reprojection of a still camera is exact
ABOVE = Pose(0.0, 6.0, 0.0, 20.0, -60.0, 60.0)


def small(**kw) -> CloudscapeSettings:
    return CloudscapeSettings(**{"width": 64, "height": 36, "jitter": "none", "reprojection": True, **SMALL, **kw})


@pytest.fixture(scope="module")
def textures():
    return CloudscapeTechnique(small()).textures


def test_who_reprojects(textures):
    t = CloudscapeTechnique(small(), textures=textures)
    below, inside, top = Pose(0, 0.3, 0, 0, 20, 60), Pose(0, 2.5, 0, 0, 0, 60), Pose(0, 4.0, 0, 0, -20, 60)
    assert not t.preview  # the default: the thesis's rule
    assert [t.reprojects(p, True) for p in (below, inside, top, ABOVE)] == [True, False, False, False]
    t.preview = True
    assert [t.reprojects(p, True) for p in (below, inside, top, ABOVE)] == [True, False, False, True]
    assert not any(t.reprojects(p, False) for p in (below, inside, top, ABOVE))
    t.update(reprojection_depth="inner_sphere")  # the thesis's reprojection through the inner sphere: never above
    assert not t.reprojects(ABOVE, True) and t.reprojects(below, True)


def test_a_still_above_the_layer_is_the_full_march(textures):
    full = CloudscapeTechnique(small(reprojection=False), textures=textures).render(ABOVE, encode=False)
    t = CloudscapeTechnique(small(), textures=textures)
    np.testing.assert_array_equal(t.render(ABOVE, encode=False), full)  # reprojection on, not a preview


def test_a_preview_above_the_layer_reprojects_and_a_still_camera_converges_to_the_full_render(textures):
    """The first preview frame marches 1/16 of the pixels (the rest from the reduced buffer: not the full render);
    with the camera still, after 16 frames every pixel was marched once and carried over exactly."""
    full = CloudscapeTechnique(small(reprojection=False), textures=textures).render(ABOVE, encode=False)
    t = CloudscapeTechnique(small(), textures=textures)
    t.preview = True
    first = t.render(ABOVE, encode=False)
    assert np.mean(np.abs(first - full)) > 1e-3
    for _ in range(15):
        img = t.render(ABOVE, encode=False)
    np.testing.assert_array_equal(img, full)


def test_the_viewer_renders_previews_as_previews_and_refined_frames_as_stills():
    """RenderWorker marks each frame: a preview above the layer reprojects (not the full render), the refined frame
    of the same state is the full march (pywarp render's image)."""
    from pywarp.core import scenes as S
    from pywarp.viewer.session import RenderWorker

    scene = S.scene("clouds")
    st = small(reprojection=False, camera_altitude_km=6.0, camera_pitch_deg=-60.0)
    w = RenderWorker(scene, preview=lambda s: {"reprojection": True}, fixed_scale=True, scale_index=0)
    try:
        w.submit(1, st, None, full=False)
        assert w.wait_frame(0, 300.0) and w.error == ""
        assert w.tech.preview is True
        preview = w.latest().image
        w.submit(1, st, None, full=True)
        assert w.wait_frame(1, 300.0) and w.error == ""
        assert w.tech.preview is False
        refined = w.latest().image
    finally:
        w.close()
    still = CloudscapeTechnique(st).render()
    np.testing.assert_array_equal(refined, still)
    assert np.mean(np.abs(preview.astype(int) - still.astype(int))) > 0.5
