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


# --- finding 3: finite differences near FLT_MAX -----------------------------------------------------------------------

F32_MAX = float(np.finfo(np.float32).max)
# within |c| 2^-22 of FLT_MAX, where c + max(h, |c| 2^-22) overflowed
NEAR_MAX = (F32_MAX, -F32_MAX, float(np.nextafter(np.float32(F32_MAX), np.float32(0))),
            float(np.float32(F32_MAX) * np.float32(1 - 2 ** -23)), -float(np.float32(F32_MAX) * np.float32(1 - 2 ** -23)),
            float(np.float32(F32_MAX) * np.float32(1 - 3 * 2 ** -24)))


def _fd_c(x, y, z, h):
    """Every finite-difference entry of noise.h at one point (seed 7, period 0), as a flat list of floats."""
    L = lib()
    perm = ffi().new("uint8_t[]", 512)
    assert L.ccl_noise_perm_table(7, perm) == 0
    out = []
    for v in (L.ccl_noise_curl3(x, y, z, 7, 0, h), L.ccl_noise_curl3_perm(x, y, z, perm, 0, h),
              L.ccl_noise_gradient3(x, y, z, 7, 0, h)):
        out += [v.x, v.y, v.z]
    for v in (L.ccl_noise_curl2(x, y, 7, 0, h), L.ccl_noise_curl2_perm(x, y, perm, 0, h)):
        out += [v.x, v.y]
    out += [L.ccl_noise_rot2(x, y, 7, 0, h), L.ccl_noise_divergence3(x, y, z, 7, 0, h)]
    out += [L.ccl_noise_curl_property(x, y, z, 7, 0, h, variant) for variant in (0, 1)]
    return out


@pytest.mark.parametrize("c", NEAR_MAX)
def test_c_finite_differences_finite_near_float_max(c):
    """Before: the step max(h, |c| 2^-22) made c + step overflow to Inf and every result NaN."""
    for h in (1.0 / 256, 0.25, 1e-30):
        for x, y, z in ((c, 0.5, -2.25), (0.5, c, 1.0), (-3.0, 7.5, c), (c, c, c)):
            vals = _fd_c(x, y, z, h)
            assert np.all(np.isfinite(vals)), (x, y, z, h, vals)


def _warp_raw(cid, **arrays):
    """The Warp twin of ``cid`` on float32/int32 arrays without the registry's validation (for points outside the
    Python domain, which the C twin documents): one launch of the generated evaluation kernel."""
    import warp as wp

    from pywarp.core.registry import get, warp_parameters
    from pywarp.kernels.noise import perm_array

    eq = get(cid)
    n = len(next(iter(arrays.values())))
    inputs = []
    for p in warp_parameters(eq.warp):
        if p == "perm":
            inputs.append(perm_array(7, "cpu"))
        elif p == "variant":
            inputs.append(arrays[p])
        else:
            inputs.append(wp.array(np.asarray(arrays[p]), device="cpu"))
    outs = [wp.empty(n, dtype=wp.vec3 if o.length == 3 else (wp.vec2 if o.length == 2 else wp.float32),
                     device="cpu") for o in eq.out_specs]
    wp.launch(eq.kernel, dim=n, inputs=inputs, outputs=outs, device="cpu")
    return outs[0].numpy()


def test_warp_finite_differences_finite_near_float_max_and_equal_c():
    """The Warp twin steps the same way (one-sided at the overflowing end): finite, and equal to C in the same
    ulp bound as on the domain (the twins share the float32 expression tree)."""
    from helpers import ulp_distance
    from pywarp.core.registry import get

    pts = [(x, y, z) for c in NEAR_MAX for x, y, z in ((c, 0.5, -2.25), (0.5, c, 1.0), (-3.0, 7.5, c))]
    x, y, z = (np.array(v, np.float32) for v in zip(*pts))
    h = np.full(len(pts), 1.0 / 256, np.float32)
    per = np.zeros(len(pts), np.int32)
    L = lib()
    cases = {"vc-2.22": ("gradient3", 3), "vc-2.23": ("curl3", 3), "vc-2.25": ("divergence3", 1),
             "vc-2.24": ("rot2", 1), "vc-A7": ("curl2", 2)}
    for cid, (cname, k) in cases.items():
        args = dict(x=x, y=y, z=z, period=per, h=h) if cname not in ("rot2", "curl2") else \
            dict(x=x, y=y, period=per, h=h)
        w = np.asarray(_warp_raw(cid, **args), np.float32).reshape(len(pts), k)
        fn = getattr(L, f"ccl_noise_{cname}")
        c = []
        for i in range(len(pts)):
            r = fn(*([x[i], y[i]] + ([] if cname in ("rot2", "curl2") else [z[i]])), 7, 0, h[i])
            c.append([getattr(r, a) for a in "xyz"[:k]] if k > 1 else [r])
        c = np.array(c, np.float32)
        assert np.all(np.isfinite(w)), (cid, w)
        np.testing.assert_array_equal(np.isfinite(c), True)
        assert np.all(ulp_distance(w, c) <= get(cid).ulp), (cid, w, c)
    for variant in (0, 1):
        w = _warp_raw("vc-2.26", x=x, y=y, z=z, period=per, h=h, variant=variant)
        c = np.array([L.ccl_noise_curl_property(x[i], y[i], z[i], 7, 0, h[i], variant) for i in range(len(pts))],
                     np.float32)
        assert np.all(np.isfinite(w)) and np.all(np.isfinite(c)), (variant, w, c)
        assert np.all(ulp_distance(w, c) <= get("vc-2.26").ulp), (variant, w, c)


# --- finding 6: fBm frequency * 2^(octaves - 1) bounded -----------------------------------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
def test_fbm_perlin3_refuses_a_top_frequency_beyond_2_24(impl):
    """Before: frequency 3e38 with two octaves at p = 0 passed the check and gave NaN (0 * Inf)."""
    fbm = pywarp.equation("vc-2.21", impl=impl)
    with pytest.raises(ValueError, match=r"^frequency .*must be"):
        fbm(0.0, 0.0, 0.0, 2, 3.0e38)
    with pytest.raises(ValueError, match=r"^frequency \* 2\^\(octaves - 1\) must be <= 2\^24"):
        fbm(0.0, 0.0, 0.0, 24, 4.0)
    # the edge itself is accepted and finite: 2^24 in the finest octave
    v = np.asarray(fbm([0.0, 1e-8, -3e-8], 0.0, 0.0, 24, 2.0))
    assert np.all(np.isfinite(v))
    np.testing.assert_array_equal(np.asarray(fbm(0.0, 0.0, 0.0, 1, 2.0 ** 24)), 0.0)


def test_fbm_max_frequency_is_the_c_constant():
    from pywarp.kernels import noise

    assert noise.FBM_MAX_FREQUENCY == lib().CCL_NOISE_FBM_MAX_FREQUENCY == 2 ** 24
