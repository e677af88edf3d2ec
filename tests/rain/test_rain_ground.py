"""The cloudscape's ground in patches (ground_variation; the rain scene's clouds background, seen from 50 m): C and
Warp agree, 0 is the uniform ground bit for bit, the patches span the albedo range they are given and are the size
CCL_CLOUDSCAPE_GROUND_PATCH_KM says."""
from __future__ import annotations

import numpy as np
import pytest
import warp as wp

from pywarp.clouds import settings as CS
from pywarp.clouds.cloudscape import c_sky, c_textures
from pywarp.clouds.settings import CLOUDSCAPE_PARAMS, CloudscapeSettings
from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.core.binding import ffi, lib
from pywarp.kernels import cloudscape as K

SMALL = dict(width=32, height=18, base_size=32, detail_size=16, curl_size=32, weather_size=64)


@wp.kernel
def _ground_kernel(p: K.CloudscapeParams, tex: K.CloudTextures, pts: wp.array(dtype=wp.vec3), sun: wp.vec3,
                   out: wp.array(dtype=wp.vec3)):
    i = wp.tid()
    g, sh = K.cloudscape_ground(p, tex, pts[i], sun)
    out[i] = g


def _points(n: int, half_km: float) -> np.ndarray:
    """An n x n grid of points on the Earth sphere around the origin."""
    xs = np.linspace(-half_km, half_km, n)
    x, z = np.meshgrid(xs, xs)
    r = CS.EARTH_RADIUS_KM
    return np.float32(np.stack([x, np.sqrt(r * r - x * x - z * z) - r, z], axis=-1).reshape(-1, 3))


_TEXTURES: list = []


def _technique(s: CloudscapeSettings) -> CloudscapeTechnique:
    """A technique of ``s`` with the textures made once for the module."""
    if not _TEXTURES:
        _TEXTURES.append(CloudscapeTechnique(s).textures)
    return CloudscapeTechnique(s, textures=_TEXTURES[0])


def _ground(variation: float, pts: np.ndarray):
    """(Warp, C) radiance of the lit ground at pts, the sun below the horizon (only the sky's light: no shadows)."""
    s = CloudscapeSettings(**SMALL, ground_variation=variation, sun_elevation_deg=0.0)
    t = _technique(s)
    sun = np.float32([0.0, -1.0, 0.0])
    out = wp.zeros(len(pts), dtype=wp.vec3)
    wp.launch(_ground_kernel, len(pts), inputs=[t.params, t.textures.warp(), wp.array(pts, dtype=wp.vec3),
                                                wp.vec3(*sun.tolist())], outputs=[out])
    p = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    lib().ccl_cloudscape_light(p, c_sky(s), p)
    tex = c_textures(t.textures)
    rgb = ffi().new("float[3]")
    c = np.empty((len(pts), 3), np.float32)
    for k, q in enumerate(pts):
        lib().ccl_cloudscape_ground(p, tex, tuple(float(x) for x in q), tuple(float(x) for x in sun), rgb, ffi().NULL)
        c[k] = rgb[0], rgb[1], rgb[2]
    return out.numpy(), c, np.array([p.ambient_ground[i] * p.ground_albedo[i] for i in range(3)], np.float32)


@pytest.mark.parametrize("variation", [0.0, 0.6, 1.0])
def test_ground_patches_c_equals_warp_and_span_the_variation(variation):
    pts = _points(40, 8 * K.GROUND_PATCH_KM)  # 16 patches across
    w, c, uniform = _ground(variation, pts)
    np.testing.assert_allclose(w, c, rtol=5e-7)  # the ulp or two of ambient_ground (tests/clouds/test_lighting.py)
    rel = w / uniform
    if variation == 0.0:
        np.testing.assert_array_equal(w, np.broadcast_to(uniform, w.shape))  # the uniform ground, bit for bit
        return
    assert np.all(rel >= 1.0 - variation - 1e-5) and np.all(rel <= 1.0 + variation + 1e-5)
    assert rel.max() - rel.min() > 0.8 * variation  # the patches use most of the range
    np.testing.assert_allclose(rel[:, 0], rel[:, 1], rtol=1e-5)  # the albedo's colour kept: brightness only


def test_ground_patches_have_the_patch_size():
    """Neighbours 1/10 of the fine octave's cell apart (P / 40) are alike; points 10 patches apart are not."""
    patch = K.GROUND_PATCH_KM
    pts = _points(120, 119 * patch / 2)  # one patch apart
    w, _, uniform = _ground(0.6, pts)
    rel = (w / uniform)[:, 1].reshape(120, 120)
    far = np.corrcoef(rel[:, :-10].ravel(), rel[:, 10:].ravel())[0, 1]
    wf, _, _ = _ground(0.6, _points(120, 119 * patch / 80))  # P / 40 apart
    relf = (wf / uniform)[:, 1].reshape(120, 120)
    near = np.corrcoef(relf[:, :-1].ravel(), relf[:, 1:].ravel())[0, 1]
    assert near > 0.9 and abs(far) < 0.2


def test_ground_variation_out_of_range_is_refused():
    with pytest.raises(ValueError, match="ground_variation"):
        CloudscapeSettings(ground_variation=1.5)
    s = CloudscapeSettings(**SMALL)
    p = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    tex = c_textures(_technique(s).textures)
    fld = ffi().new("const char **")
    assert lib().ccl_cloudscape_check(p, tex, c_sky(s), fld) == lib().CCL_OK
    for bad in (-0.1, 1.01, float("nan")):
        p.ground_variation = bad
        assert lib().ccl_cloudscape_check(p, tex, c_sky(s), fld) == lib().CCL_EINVAL
        assert ffi().string(fld[0]) == b"ground_variation"
