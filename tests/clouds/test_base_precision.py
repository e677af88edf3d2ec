"""The base-shape texture in half floats (CloudscapeSettings.base_precision, default 'half'): the texels are rounded
to float16 values once, Warp stores them as half floats (half the memory) and the C renderer is given the same
rounded values, so the twins still agree bit for bit; 'single' keeps the generated float32 texels (the thesis's
renderer, whose golden images tests/clouds/test_lighting.py checks). The rounding changes a frame far less than
the jitter changes it from one frame to the next."""
from __future__ import annotations

import numpy as np
import pytest

from helpers import march_frames, pixel_change
from pywarp.clouds.cloudscape import (HALF_MAX, RenderTextures, base_shape_bound, half_values, mip_chain,
                                      render_pixels_c, render_pixels_warp)
from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.clouds.settings import CloudscapeSettings
from pywarp.core.pose import Pose

SMALL = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)


def test_half_values_are_the_nearest_float16_values():
    a = np.array([0.0, 1.0, 0.1, 1.0 / 3.0, 0.99951171875, 1e-8, -2.5, np.nan, np.inf, HALF_MAX], np.float32)
    h = half_values(a, "base texture")
    assert h.dtype == np.float32
    expected = a.astype(np.float16).astype(np.float32)  # numpy's float16 conversion: round to nearest even
    np.testing.assert_array_equal(h, expected)
    # independent of numpy's float16: within half an ulp of 11 significant bits, and representable in 11 bits
    finite = np.isfinite(a) & (np.abs(a) >= 2.0 ** -14)
    assert np.all(np.abs(h[finite] - a[finite]) <= np.abs(a[finite]) * 2.0 ** -11)
    m, _ = np.frexp(h[finite].astype(np.float64))
    assert np.all(m * 2.0 ** 11 == np.round(m * 2.0 ** 11))
    with pytest.raises(ValueError, match=r"base texture: a texel of 70000.0 is beyond the float16 range"):
        half_values(np.array([0.5, 70000.0], np.float32), "base texture")


def test_half_base_holds_the_rounded_chain_in_half_the_memory():
    tex = RenderTextures.generate(CloudscapeSettings(**SMALL))
    half, single = tex.warp(True), tex.warp(False)
    assert (half.half_base, single.half_base) == (1, 0)
    chain = tex.mips("base", True)
    # every level rounded, level 0 the rounded texels
    np.testing.assert_array_equal(chain, half_values(chain, "base texture"))
    np.testing.assert_array_equal(chain[:32 ** 3].reshape(tex.base.shape), half_values(tex.base, "base texture"))
    np.testing.assert_array_equal(half.base_half.numpy().astype(np.float32).reshape(-1, 4), chain)
    np.testing.assert_array_equal(single.base.numpy().reshape(-1, 4), mip_chain(tex.base))
    assert half.base_half.capacity * 2 == single.base.capacity
    # the other textures are the same in both
    np.testing.assert_array_equal(half.detail.numpy(), single.detail.numpy())
    assert half.base_bound == base_shape_bound(chain)


@pytest.mark.parametrize("precision", ["half", "single"])
def test_c_and_warp_read_the_same_base_texels(precision):
    s = CloudscapeSettings(width=64, height=36, base_precision=precision, **SMALL)
    t = CloudscapeTechnique(s)
    xs = [3, 17, 31, 40, 52, 60, 8, 25]
    ys = [30, 24, 20, 18, 22, 33, 12, 16]
    pose = Pose.from_settings(s)
    np.testing.assert_array_equal(render_pixels_warp(t, xs, ys, pose), render_pixels_c(s, t.textures, xs, ys, pose))


def test_half_base_changes_the_frame_far_less_than_the_jitter():
    """The same frame with the base texels rounded to float16 and as generated, against the jitter's change of the
    frame from one frame to the next (levels of 8 bits): the rounding moves a noise value by at most 2^-11 of itself,
    and the frame by a small fraction of what every frame already varies."""
    f = march_frames({}, {"single": dict(base_precision="single"), "half": dict(base_precision="half")},
                     reference="single", width=160, height=90)
    change = pixel_change(f["half"], f["single"])
    jitter = pixel_change(f["single_next"], f["single"])
    assert jitter.mean() > 0.05  # the yardstick is not empty
    assert change.max() > 0.0  # the setting reaches the renderer
    assert change.mean() < 0.1 * jitter.mean(), (change.mean(), jitter.mean())
    assert np.quantile(change, 0.999) < 0.5 * np.quantile(jitter, 0.999), (np.quantile(change, 0.999),
                                                                          np.quantile(jitter, 0.999))
    assert change.max() < jitter.max()


def test_a_base_texture_beyond_the_float16_range_is_refused_before_any_kernel():
    tex = RenderTextures.generate(CloudscapeSettings(**SMALL))
    big = RenderTextures(tex.base * 1e5, tex.detail, tex.curl, tex.weather)
    with pytest.raises(ValueError, match="beyond the float16 range"):
        big.warp(True)
    big.warp(False)  # single precision takes it
