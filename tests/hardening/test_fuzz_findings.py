"""Issue 14 (hardening), the fuzz findings of cclouds/fuzz/README.md: one test per finding, each failing on the code
before its fix. C functions are called through the cffi binding; Python entries through the registry, both
implementations."""
from __future__ import annotations

import numpy as np
import pytest

import pywarp
from pywarp.core.binding import ffi, lib
from pywarp.kernels import sky as sky_mod

IMPLS = ("warp", "c")


# --- finding 4: gradient sky, d . s rounding above 1 ------------------------------------------------------------------

# Sun directions whose float32 dot product with themselves (after the entry's normalisation) rounds to 1 + 2^-23:
# before the clamp, c^n overflowed to Inf for n = 1e9 (found by a scan over elevation/azimuth).
SKY_ABOVE_ONE = ((0.0, 14.6), (0.0, 65.7), (0.37, 102.2), (0.37, 262.8))


@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("elevation, azimuth", SKY_ABOVE_ONE)
def test_sky_gradient_finite_for_huge_exponent_at_the_sun(impl, elevation, azimuth):
    sky = pywarp.equation("vc-A28", impl=impl)
    s = sky_mod.sun_direction(elevation, azimuth)
    sun_colour = (1.0, 0.9, 0.6)
    for n in (1e9, 3.0e38):
        rgb = np.asarray(sky(s, elevation, azimuth, sun_colour=sun_colour, sun_exponent=n), np.float64)
        assert np.all(np.isfinite(rgb)), (n, rgb)
        # at most one sun colour above the lerp (c clamped to 1); the lerp itself is within [0, 1] here
        assert np.all(rgb <= np.array(sun_colour) + 1.0)
    # a zero sun colour gives the lerp, not NaN (0 * Inf before the clamp)
    rgb = np.asarray(sky(s, elevation, azimuth, sun_colour=(0.0, 0.0, 0.0), sun_exponent=1e9))
    assert np.all(np.isfinite(rgb))


def test_sky_gradient_rgb_clamps_the_cosine_in_c():
    g = ffi().new("ccl_sky_gradient *")
    lib().ccl_sky_gradient_defaults(g)
    g.sun_exponent = 1e9
    d = ffi().new("ccl_vec3 *")
    # a direction of length 1 + 2^-23 stands for the rounding: d . d = 1 + 2^-22 in float32
    d.x, d.y, d.z = float(np.float32(1.0 + 2.0 ** -23)), 0.0, 0.0
    r = lib().ccl_sky_gradient_rgb(d[0], d[0], g)
    assert np.all(np.isfinite([r.x, r.y, r.z]))
    assert r.x == pytest.approx(g.horizon[0] + g.sun[0], rel=1e-6)


# --- finding 2: single texels periodic for any lattice frequency and any int32 coordinate -------------------------------

TEXEL_INSIDE = ([114, 4194301, -4194303, 1001, 3000000], [-3963638, 7, 3000001, -4000001, 5],
                [-1, -4194303, 4000000, 3999999, -3999999])  # |i| < 2^22: accepted before, values differed
TEXEL_INT32 = ([2 ** 31 - 1, -2 ** 31, 2 ** 30 + 1], [-2 ** 31 + 5, 2 ** 31 - 2, -2 ** 30 - 1],
               [2 ** 30 + 3, -4194305, 2 ** 31 - 1])  # any int32 (refused beyond 2^22 before)


@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("coords", [TEXEL_INSIDE, TEXEL_INT32], ids=["inside-2^22", "int32"])
def test_texel_entries_periodic_for_non_power_of_two_frequencies(impl, coords):
    """Texel i + k size equals texel i bit for bit also when u * frequency rounds (frequency 3, cells 3, 5): the
    coordinate is reduced modulo size before the conversion to float. Before, base texel (114, -3963638, -1) of size 4,
    frequency 3, cells 3 differed from texel (2, 2, 3) (R 0.542 vs 0.678)."""
    size = 4
    ix, iy, iz = (np.array(c, np.int64) for c in coords)
    red = [a & (size - 1) for a in (ix, iy, iz)]
    bt = pywarp.equation("vc-A9", impl=impl)
    for freq, cells in ((3, 3), (5, 3), (7, 5)):
        b = dict(size=size, seed=0, perlin_octaves=3, perlin_frequency=freq, worley_cells=cells, worley_w0=0.625,
                 worley_w1=0.25, worley_w2=0.125, gamma=1.0)
        np.testing.assert_array_equal(np.stack(bt(ix, iy, iz, **b), -1), np.stack(bt(*red, **b), -1))
    dt = pywarp.equation("vc-A10", impl=impl)
    for cells in (3, 5, 7):
        d = dict(size=size, seed=4, worley_cells=cells, worley_w0=0.625, worley_w1=0.25, worley_w2=0.125, gamma=1.0)
        np.testing.assert_array_equal(np.stack(dt(ix, iy, iz, **d), -1), np.stack(dt(*red, **d), -1))
