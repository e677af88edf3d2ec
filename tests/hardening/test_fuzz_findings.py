"""Issue 14 (hardening), the fuzz findings of cclouds/fuzz/README.md: one test per finding, each failing on the code
before its fix. C functions are called through the cffi binding; Python entries through the registry, both
implementations."""
from __future__ import annotations

import math

import numpy as np
import pytest
import warp as wp

import pywarp
from helpers import ulp_distance
from pywarp.core.binding import ffi, lib
from pywarp.core.cbridge import PARTICLES_PARAMS, TERRAIN_PARAMS, VOLUME_PARAMS
from pywarp.core.registry import get, warp_parameters
from pywarp.kernels import camera as CAM
from pywarp.flight import model as F
from pywarp.kernels import noise
from pywarp.kernels import optics as OPT
from pywarp.kernels import particles as PK
from pywarp.kernels import rain as R
from pywarp.kernels import sdf as SDF
from pywarp.kernels import sky as sky_mod
from pywarp.kernels import terrain as K
from pywarp.kernels import volume as V
from pywarp.flight import volumes as VS
from pywarp.kernels.noise import perm_array
from pywarp.rain.settings import RainSettings
from pywarp.terrain.settings import TerrainSettings
from pywarp.terrain.technique import render_pixels_c, render_pixels_warp

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
    assert noise.FBM_MAX_FREQUENCY == lib().CCL_NOISE_FBM_MAX_FREQUENCY == 2 ** 24


# --- findings 5 and 9: volume extents and colours bounded -------------------------------------------------------------

def _volume_grid(extent, density):
    """A ccl_volume_grid over ``density`` (nz, ny, nx) at the origin with ``extent``; returns (grid, keep-alive)."""
    f = ffi()
    d = np.ascontiguousarray(density, np.uint8)
    light = np.ones(d.shape, np.float32)
    skip = np.zeros(d.size, np.uint8)
    g = f.new("ccl_volume_grid *")
    bd, bl, bs = f.from_buffer("unsigned char[]", d), f.from_buffer("float[]", light), f.from_buffer(
        "unsigned char[]", skip)
    g.density, g.light, g.skip = (f.cast(t, b) for t, b in (("const unsigned char *", bd), ("const float *", bl),
                                                            ("const unsigned char *", bs)))
    g.nz, g.ny, g.nx = d.shape
    g.extent.x, g.extent.y, g.extent.z = extent
    return g, (d, light, skip, bd, bl, bs)


def _c_check(p, g, count=1):
    fld = ffi().new("const char **")
    st = lib().ccl_volume_check(p, g, count, fld)
    return st, (ffi().string(fld[0]).decode() if fld[0] != ffi().NULL else None)


@pytest.mark.parametrize("extent", [(9e-41, 1.0, 1.0), (1.0, 1e-7, 1.0), (1.0, 1.0, 2e6), (3e38, 3e38, 3e38)])
def test_volume_check_refuses_extents_outside_the_length_range(extent):
    """Before: any extent > 0 passed; 9e-41 made the voxel scale Inf and ccl_volume_light wrote NaN."""
    p = ffi().new("ccl_volume_params *")
    lib().ccl_volume_params_default(p)
    g, keep = _volume_grid(extent, np.full((2, 2, 4), 200, np.uint8))
    assert _c_check(p, g) == (1, "extent")
    out = np.full(16, -5.0, np.float32)
    assert lib().ccl_volume_light(p, g, ffi().from_buffer("float[]", out), out.size) != 0
    assert np.all(out == -5.0)
    with pytest.raises(ValueError, match=r"^extent must be in \[1e-06, 1e\+06\] m on every axis"):
        VS.PlacedVolume(np.full((2, 2, 4), 200, np.uint8), (0.0, 0.0, 0.0), extent)
    del keep


@pytest.mark.parametrize("extent", [(1e-6, 1e-6, 1e-6), (1e6, 1e6, 1e6), (1e-6, 1e6, 1.0)])
def test_volume_light_in_unit_range_at_the_extent_limits(extent):
    """The limits themselves: light in [0, 1], Warp and C alike (1 um and 1000 km boxes)."""
    vals = VOLUME_PARAMS.defaults()
    dens = np.zeros((3, 4, 5), np.uint8)
    dens[1:, :, 2:] = 255
    v = VS.PlacedVolume(dens, (0.0, 0.0, 0.0), extent)
    vs = VS.VolumeSet([v])
    vs.compute_light(vals)
    c = VS.light_c(vals, v)
    for a in (vs.light[0], c):
        assert np.all((a >= 0.0) & (a <= 1.0)), a
    np.testing.assert_allclose(vs.light[0], c, rtol=2e-6, atol=1e-7)


@pytest.mark.parametrize("field, value", [("sun_colour", (F32_MAX, 1.0, 1.0)), ("ambient_top", (0.5, 2e6, 0.5)),
                                          ("ground_b", (-0.1, 0.3, 0.2)), ("sky_horizon", (0.5, 0.5, 1e30))])
def test_volume_colours_bounded_by_the_check(field, value):
    """Before: any finite colour passed; sun_colour.x = FLT_MAX with the aircraft on gave a NaN pixel (Inf * 0)."""
    vals = VOLUME_PARAMS.defaults()
    vals[field] = value
    g, keep = _volume_grid((10.0, 10.0, 10.0), np.full((2, 2, 2), 100, np.uint8))
    assert _c_check(VOLUME_PARAMS.to_c(vals), g) == (1, field)
    with pytest.raises(ValueError, match=rf"^{field} is out of range \(ccl_volume_check\)"):
        V.checked_params(vals)
    del keep
    vals = VOLUME_PARAMS.defaults()
    vals["sun_glow"] = 2e6
    assert _c_check(VOLUME_PARAMS.to_c(vals), g)[1] == "sun_glow"
    with pytest.raises(ValueError, match=r"^sun_glow is out of range \(ccl_volume_check\)"):
        V.checked_params(vals)


def test_volume_pixels_finite_with_colours_at_the_limit():
    """Every colour and the glow at 10^6, the aircraft in view, a thick cloud: finite pixels, Warp and C alike."""
    vals = VOLUME_PARAMS.defaults()
    for name in ("sun_colour", "ambient_top", "ambient_bottom", "sky_zenith", "sky_horizon", "ground_a", "ground_b"):
        vals[name] = (1e6, 1e6, 1e6)
    vals["sun_glow"] = 1e6
    fw, rt, up = F.axes(0.3, 0.09, 0.35)
    vals.update(aircraft=1, aircraft_position=(0.0, 100.0, -60.0), aircraft_forward=fw, aircraft_right=rt,
                aircraft_up=up, g=0.999)
    vs = VS.VolumeSet([VS.PlacedVolume(np.full((8, 8, 8), 255, np.uint8), (-40.0, 80.0, -300.0), (80.0, 60.0, 80.0))])
    vs.compute_light(vals)
    w, c = _volume_pixels_both(vals, vs)
    assert np.all(np.isfinite(w)) and np.all(np.isfinite(c))
    np.testing.assert_allclose(w, c, rtol=1e-5, atol=1e-6 * 1e6)


def _volume_pixels_both(vals: dict, vs) -> tuple:
    """Pixels of a 64 x 36 view towards the volumes at (-40..40, 80..140, -300..-220), every third pixel: (Warp, C)."""
    cam = CAM.camera_look_at(np.array([0.0, 104.0, 0.0]), np.array([0.0, 100.0, -100.0]), (0.0, 1.0, 0.0),
                             math.radians(60.0), 16 / 9, 0.1, 1e5)
    xs, ys = np.meshgrid(np.arange(0, 64, 3), np.arange(0, 36, 3))
    return (VS.pixels_warp(vals, vs, cam, xs.ravel(), ys.ravel(), 64, 36),
            VS.pixels_c(vals, vs, cam, xs.ravel(), ys.ravel(), 64, 36))


def test_volume_colour_and_length_limits_are_the_c_constants():
    assert V.MAX_COLOUR == lib().CCL_VOLUME_MAX_COLOUR == 1e6
    assert V.LENGTH_RANGE == lib().CCL_VOLUME_LENGTH_RANGE == 1e6
    assert V.MAX_TAU == lib().CCL_VOLUME_MAX_TAU == 1e6
    assert V.MAX_STEP == lib().CCL_VOLUME_MAX_STEP == 1e6


# --- finding 11: volume, the optical depth of a step ------------------------------------------------------------------

@pytest.mark.parametrize("field, value", [("light_tau_per_voxel", 1.6e32), ("light_step_voxels", 8.4e6),
                                          ("tau_per_voxel", 2e6), ("step_voxels", 3e38)])
def test_volume_optical_depths_and_steps_bounded_by_the_check(field, value):
    """Before: any finite optical depth per voxel and step passed; light_tau_per_voxel = 1.6e32 with
    light_step_voxels = 8.4e6 made the step's optical depth Inf, and Inf x a density of 0 wrote NaN light."""
    vals = VOLUME_PARAMS.defaults()
    vals[field] = value
    g, keep = _volume_grid((10.0, 10.0, 10.0), np.full((2, 2, 2), 100, np.uint8))
    assert _c_check(VOLUME_PARAMS.to_c(vals), g) == (1, field)
    out = np.full(8, -5.0, np.float32)
    assert lib().ccl_volume_light(VOLUME_PARAMS.to_c(vals), g, ffi().from_buffer("float[]", out), out.size) != 0
    assert np.all(out == -5.0)
    with pytest.raises(ValueError, match=rf"^{field} is out of range \(ccl_volume_check\)"):
        V.checked_params(vals)
    del keep


def test_volume_light_and_pixels_finite_with_optical_depths_and_steps_at_the_limit():
    """Optical depths per voxel and steps at 10^6 (the step's optical depth 10^12): the light in [0, 1] and the
    pixels finite, Warp and C alike; empty voxels next to dense ones (the density of 0 that met Inf)."""
    vals = VOLUME_PARAMS.defaults()
    vals.update(tau_per_voxel=1e6, light_tau_per_voxel=1e6, step_voxels=1e6, light_step_voxels=1e6)
    dens = np.zeros((4, 4, 4), np.uint8)
    dens[1:3, 1:3, 1:3] = 255
    v = VS.PlacedVolume(dens, (-40.0, 80.0, -300.0), (80.0, 60.0, 80.0))
    vs = VS.VolumeSet([v])
    vs.compute_light(vals)
    c = VS.light_c(vals, v)
    for a in (vs.light[0], c):
        assert np.all((a >= 0.0) & (a <= 1.0)), a
    np.testing.assert_array_equal(vs.light[0], c)
    w, cp = _volume_pixels_both(vals, vs)
    assert np.all(np.isfinite(w)) and np.all(np.isfinite(cp))
    np.testing.assert_allclose(w, cp, rtol=1e-5, atol=1e-6)


def test_volume_sky_glow_clamps_the_cosine_in_c_and_warp():
    """The volume sky's glow has the gradient sky's rounding (finding 4): d . sun of unit vectors rounds above 1 and
    c^power overflowed for powers above ~7e8. Both twins clamp the cosine to [0, 1]."""
    vals = VOLUME_PARAMS.defaults()
    vals["sun"] = (1.0, 0.0, 0.0)
    vals["sun_glow_power"] = 3e38
    d = float(np.float32(1.0 + 2.0 ** -23))  # d . sun = 1 + 2^-23 in float32
    p = VOLUME_PARAMS.to_c(vals)
    dv = ffi().new("ccl_vec3 *")
    dv.x, dv.y, dv.z = d, 0.0, 0.0
    r = lib().ccl_volume_sky(p, dv[0])
    c = np.array([r.x, r.y, r.z], np.float32)
    out = wp.zeros(1, dtype=wp.vec3, device="cpu")
    wp.launch(_volume_sky_kernel, dim=1, inputs=[VOLUME_PARAMS.warp_struct(vals), wp.vec3(d, 0.0, 0.0)], outputs=[out],
              device="cpu")
    w = out.numpy()[0]
    sky = np.array(vals["sky_horizon"], np.float32) + np.array(vals["sun_colour"], np.float32) * np.float32(0.6)
    for a in (c, w):
        assert np.all(np.isfinite(a)), a
        np.testing.assert_allclose(a, sky, rtol=1e-6)


@wp.kernel
def _volume_sky_kernel(p: V.VolumeParams, d: wp.vec3, out: wp.array(dtype=wp.vec3)):
    out[0] = V.volume_sky(p, d)


# --- finding 8: terrain noise scales bounded below ----------------------------------------------------------------------

@pytest.mark.parametrize("field", ["horizontal_scale", "cloud_scale", "wave_scale"])
@pytest.mark.parametrize("value", [1.02e-38, 1e-45, 0.0155])
def test_terrain_check_refuses_tiny_noise_scales(field, value):
    """Before: the domains were (0, max]; horizontal_scale 1.02e-38 overflowed x / scale and ccl_terrain_shade
    returned NaN (cloud_scale and wave_scale alike, found by the strict harness)."""
    with pytest.raises(ValueError, match=rf"^{field} is out of range \(ccl_terrain_params_check\)"):
        TERRAIN_PARAMS.checked({field: value})
    with pytest.raises(ValueError, match=field):
        TerrainSettings(**{field: value})


def test_terrain_shade_nan_case_of_the_finding_is_refused_and_the_limit_is_finite():
    """The finding's parameters (march_octaves 1, step_size 3.14, precision 1.001, max_steps 1) with
    horizontal_scale 1.02e-38 are refused; at the limit 1/64 of all three scales ccl_terrain_shade is finite for
    rays in every direction."""
    base = dict(heightmap=1, march_octaves=1, step_size=3.14, precision=1.001, max_steps=1)
    with pytest.raises(ValueError, match=r"^horizontal_scale"):
        TERRAIN_PARAMS.checked(dict(base, horizontal_scale=1.02e-38))
    p = TERRAIN_PARAMS.checked(dict(base, horizontal_scale=K.MIN_SCALE, cloud_scale=K.MIN_SCALE,
    wave_scale=K.MIN_SCALE))
    rng = np.random.default_rng(3)
    steps = ffi().new("int *")
    for _ in range(200):
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        ro, rd = ffi().new("ccl_vec3 *"), ffi().new("ccl_vec3 *")
        ro.x, ro.y, ro.z = rng.uniform(-100, 100), rng.uniform(0, 50), rng.uniform(-100, 100)
        rd.x, rd.y, rd.z = (float(v) for v in d.astype(np.float32))
        c = lib().ccl_terrain_shade(p, ro[0], rd[0], steps)
        assert np.all(np.isfinite([c.x, c.y, c.z])), (ro, d)


def test_terrain_pixels_at_the_scale_limit_finite_and_twins_equal():
    s = TerrainSettings(width=48, height=27, horizontal_scale=K.MIN_SCALE, cloud_scale=K.MIN_SCALE, wave_scale=K.MIN_SCALE,
                        water_level=0.0)
    rng = np.random.default_rng(5)
    xs, ys = rng.integers(0, s.width, 24), rng.integers(0, s.height, 24)
    cw, sw = render_pixels_warp(s, xs, ys)
    cc, sc = render_pixels_c(s, xs, ys)
    assert np.all(np.isfinite(cw))
    np.testing.assert_array_equal(cw, cc)
    np.testing.assert_array_equal(sw, sc)


def test_terrain_min_scale_is_the_c_check_limit():
    """The Python limit is the C one: the C check accepts MIN_SCALE and refuses the float below it."""
    below = float(np.nextafter(np.float32(K.MIN_SCALE), np.float32(0)))
    for field in ("horizontal_scale", "cloud_scale", "wave_scale"):
        TERRAIN_PARAMS.checked({field: K.MIN_SCALE})
        with pytest.raises(ValueError, match=field):
            TERRAIN_PARAMS.checked({field: below})


# --- property-test findings: rr-tab-2.2 slowdown, rr-alg-3.1.3 tan_half_fov / aspect ----------------------------------

@pytest.mark.parametrize("impl", IMPLS)
def test_terminal_speed_refuses_a_tiny_slowdown(impl):
    """Before: slowdown was accepted down to 1e-45 and the speed overflowed to inf."""
    speed = pywarp.equation("rr-tab-2.2", impl=impl)
    for bad in (1e-45, 1e-38, 0.015):
        with pytest.raises(ValueError, match=r"^slowdown must be in \[0\.015625, 1000\]"):
            speed(5.0, bad)
    v = np.asarray(speed(np.linspace(0.0, 10.0, 41), R.MIN_SLOWDOWN))
    assert np.all(np.isfinite(v)) and v.max() == pytest.approx(9.23 * 64, rel=1e-6)


def test_particles_refuse_a_tiny_slowdown_in_c_and_settings():
    p = ffi().new("ccl_particles_params *")
    lib().ccl_particles_params_default(p)
    p.slowdown = 1e-45
    fld = ffi().new("const char **")
    assert lib().ccl_particles_params_check(p, fld) != 0 and ffi().string(fld[0]) == b"slowdown"
    p.slowdown = 0.015625
    assert lib().ccl_particles_params_check(p, fld) == 0
    with pytest.raises(ValueError, match=r"^slowdown is out of range \(ccl_particles_params_check\), got 1e-45$"):
        PARTICLES_PARAMS.checked({"slowdown": 1e-45})
    with pytest.raises(ValueError, match="slowdown"):
        RainSettings(slowdown=1e-45)


@pytest.mark.parametrize("impl", IMPLS)
def test_refracted_uv_refuses_tiny_projections_and_is_finite_at_the_limit(impl):
    """Before: tan_half_fov and aspect were accepted down to 1e-45 and P_o, P_c overflowed to +-inf (NaN)."""
    uv = pywarp.equation("rr-alg-3.1.3", impl=impl)
    view, exit_ = (0.6, 0.0, -0.8), (0.5, 0.5, 0.5)
    with pytest.raises(ValueError, match=r"^tan_half_fov must be in \[0\.015625, 100\]"):
        uv(view, exit_, 1e-45, 1.0)
    with pytest.raises(ValueError, match=r"^aspect must be in \[0\.015625, 100\]"):
        uv(view, exit_, 3.7, 1e-45)
    rng = np.random.default_rng(11)
    v = rng.normal(size=(200, 3))
    v[:, 2] = -np.abs(v[:, 2]) - 0.05
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    e = rng.uniform(-1.0, 1.0, (200, 3))
    e[:, 2] = np.abs(e[:, 2]) + 1e-3
    for mapping in ("offset", "project"):
        pc, po, valid = uv(v.astype(np.float32), e.astype(np.float32), R.MIN_PROJECTION, R.MIN_PROJECTION,
                           mapping=mapping)
        assert np.all(np.isfinite(pc)) and np.all(np.isfinite(po)), mapping


# --- finding 10: cloudscape, the far light sample's weight --------------------------------------------------------------

def test_cloudscape_far_light_factor_bounded_and_finite_at_the_limit():
    """Before: light_far_factor = 3e38 with light_step_km = 1e-39 passed ccl_cloudscape_check (the far sample's
    distance, their product x 5, is 1.5 km), but its weight (light_far_factor - 1) x 5 x light_step_km overflowed to
    Inf in the first product, and Inf x a density of 0 made the pixel NaN."""
    from pywarp.clouds.cloudscape import render_pixels_c, render_pixels_warp
    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.clouds.settings import CloudscapeSettings

    finding = {"light_far_factor": 3.0e38, "light_step_km": 1.0e-39}
    with pytest.raises(ValueError, match=r"^light_far_factor is out of range: it must be in \[1, 10\^6\] "):
        CloudscapeSettings(advanced=finding)
    with pytest.raises(ValueError, match=r"^light_far_factor is out of range"):  # the C check itself
        CloudscapeSettings().c_params({**CloudscapeSettings().c_values(), **finding})
    # at the limit, a far sample 5 km away with a weight of 5 km: finite pixels, the twins equal
    s = CloudscapeSettings(width=16, height=9, base_size=16, detail_size=32, curl_size=16, weather_size=512,
                           samples_min=8, samples_max=16,
                           advanced={"light_far_factor": 1.0e6, "light_step_km": 1.0e-6})
    t = CloudscapeTechnique(s)
    ys, xs = np.mgrid[0:9, 0:16]
    w = render_pixels_warp(t, xs.ravel(), ys.ravel())
    assert np.all(np.isfinite(w))
    np.testing.assert_array_equal(w, render_pixels_c(s, t.textures, xs.ravel(), ys.ravel()))


# --- issue 31, N4: the volume samplers bound the voxel coordinate before the cast to int ----------------------------

@wp.kernel
def _sample_u8(values: wp.array(dtype=wp.uint8), nx: int, ny: int, nz: int, v: wp.array(dtype=wp.vec3),
               out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = V.volume_sample(values, 0, nx, ny, nz, v[i], V._INV_255)


@wp.kernel
def _sample_f32(values: wp.array(dtype=float), nx: int, ny: int, nz: int, v: wp.array(dtype=wp.vec3),
                out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = V.volume_sample(values, 0, nx, ny, nz, v[i], 1.0)


def test_volume_samplers_give_the_edge_voxel_for_huge_and_infinite_coordinates():
    """Before: floor(v - 0.5) was converted to int before the clamp, undefined for |v| >= 2^31 or +-Inf; in practice
    v = 1e10 read voxel 0 (INT_MIN clamped) instead of the far edge, and +-Inf gave NaN (Inf - Inf weights). Now any
    non-NaN v beyond the grid reads its edge voxel (the clamp's meaning), and a NaN component gives NaN; C and Warp
    alike, bit for bit."""
    nx, ny, nz = 5, 4, 3
    dens = np.arange(nx * ny * nz, dtype=np.uint8).reshape(nz, ny, nx) * np.uint8(4) + np.uint8(3)
    vals = dens.astype(np.float32) * np.float32(-1.5)
    inf = float("inf")
    far = (1e10, 2.0 ** 31, 3e38, inf)
    pts = [(x, 0.5, 0.5) for x in far] + [(-x, 0.5, 0.5) for x in far] + \
        [(0.5, x, 0.5) for x in far] + [(0.5, 0.5, -x) for x in far]
    edge = [(0, 0, nx - 1)] * 4 + [(0, 0, 0)] * 4 + [(0, ny - 1, 0)] * 4 + [(0, 0, 0)] * 4  # (z, y, x) voxel read
    pts_nan = [(float("nan"), 0.5, 0.5), (0.5, 0.5, float("nan"))]
    v = wp.array(np.float32(pts + pts_nan), dtype=wp.vec3, device="cpu")
    for grid, kernel, c_fn, ctype, scale in [
            (dens, _sample_u8, lib().ccl_volume_sample, "unsigned char[]", np.float32(1.0 / 255.0)),
            (vals, _sample_f32, lib().ccl_volume_sample_float, "float[]", np.float32(1.0))]:
        want = np.array([np.float32(grid[e]) * scale for e in edge] + [np.nan, np.nan], np.float32)
        buf = ffi().from_buffer(ctype, np.ascontiguousarray(grid.ravel()))
        c = np.array([c_fn(buf, nx, ny, nz, {"x": p[0], "y": p[1], "z": p[2]}) for p in pts + pts_nan], np.float32)
        out = wp.zeros(len(c), dtype=float, device="cpu")
        wp.launch(kernel, dim=len(c), inputs=[wp.array(grid.ravel(), device="cpu"), nx, ny, nz, v, out],
                  device="cpu")
        for got in (c, out.numpy()):
            np.testing.assert_array_equal(got, want)


# --- issue 31, N3: the capture fetch bounds the texel coordinate before the cast to int -----------------------------

@wp.kernel
def _particles_tap_kernel(mask: wp.array(dtype=float), capture: wp.array(dtype=float), capture_size: int,
                          filt: int, out: wp.array(dtype=wp.vec3), hits: wp.array(dtype=int)):
    hit, rgb = PK.particles_tap(mask, 1, capture, capture_size, 0.5, 0.5, wp.vec2(0.5, 0.5), 1.0, filt)
    out[0] = rgb
    hits[0] = hit


# (mask texel x, y, z, a) -> the capture texel (row, column) read: P_c = (0.5, 0.5) + (x, -y) / z
TAP_FAR = [((0.5, 0.5, 2e-33, 0.5), (0, -1)),         # the finding's texel: P_c = (2.5e32, -2.5e32), top right
           ((-3e38, -3e38, 1e-3, 1.0), (-1, 0)),      # P_c = (-Inf, +Inf): bottom left
           ((3e38, 3e38, 1e-3, 1.0), (0, -1))]        # P_c = (+Inf, -Inf): top right


@pytest.mark.parametrize("filt", [PK.NEAREST, PK.LINEAR], ids=["nearest", "linear"])
def test_particles_tap_reads_the_edge_texel_for_huge_and_infinite_capture_coordinates(filt):
    """Before: the capture coordinate times the size was converted to int before the clamp, undefined for |u size|
    >= 2^31 or +-Inf; in practice the far right edge read column 0 (INT_MIN clamped) and an infinite coordinate gave
    NaN (Inf - Inf weight). Now any non-NaN P_c beyond the capture reads its edge texel; C and Warp alike (a NaN
    exit direction has no ray: the next test)."""
    size = 4
    cap = (np.arange(size * size * 3, dtype=np.float32).reshape(size, size, 3) + 1.0) / 64.0
    for texel, rc in TAP_FAR:
        mask = np.float32(texel)
        want = cap[rc]
        rgb = ffi().new("ccl_vec3 *")
        p_o = ffi().new("ccl_vec2 *")
        p_o.x, p_o.y = 0.5, 0.5
        hit = lib().ccl_particles_tap(ffi().from_buffer("float[]", mask), 1,
                                      ffi().from_buffer("float[]", np.ascontiguousarray(cap.ravel())), size,
                                      0.5, 0.5, p_o[0], 1.0, filt, rgb)
        out = wp.zeros(1, dtype=wp.vec3, device="cpu")
        hits = wp.zeros(1, dtype=int, device="cpu")
        wp.launch(_particles_tap_kernel, dim=1, inputs=[wp.array(mask, device="cpu"),
                                                         wp.array(cap.ravel(), device="cpu"), size, filt],
                  outputs=[out, hits], device="cpu")
        assert hit == 1 and hits.numpy()[0] == 1
        for got in (np.float32([rgb.x, rgb.y, rgb.z]), out.numpy()[0]):
            np.testing.assert_array_equal(got, want, err_msg=str(texel))


@pytest.mark.parametrize("filt", [PK.NEAREST, PK.LINEAR], ids=["nearest", "linear"])
def test_particles_tap_a_nan_exit_direction_has_no_ray(filt):
    """Fuzz finding (fuzz_optics, composite: pixel NaN): a mask texel inside the drop (a > 0, z > 0) with x or y
    NaN, or x / z = Inf / Inf, made the tap fetch the capture at a NaN point. Now such a texel has no ray -- the tap
    misses, as outside the drop -- in C and Warp, and the packed mask marks it (NaN). Before, the tap hit with NaN
    rgb (this test fails on that library)."""
    from pywarp.rain.particles import pack_mask

    size = 4
    cap = (np.arange(size * size * 3, dtype=np.float32).reshape(size, size, 3) + 1.0) / 64.0
    for texel in [(np.nan, 0.5, 0.5, 1.0), (0.5, np.nan, 0.5, 1.0), (float("inf"), 0.0, float("inf"), 1.0),
                  (np.nan, np.nan, 1.0, 1.0)]:
        mask = np.float32(texel)
        rgb = ffi().new("ccl_vec3 *")
        p_o = ffi().new("ccl_vec2 *")
        p_o.x, p_o.y = 0.5, 0.5
        hit = lib().ccl_particles_tap(ffi().from_buffer("float[]", mask), 1,
                                      ffi().from_buffer("float[]", np.ascontiguousarray(cap.ravel())), size,
                                      0.5, 0.5, p_o[0], 1.0, filt, rgb)
        hits = wp.zeros(1, dtype=int, device="cpu")
        wp.launch(_particles_tap_kernel, dim=1, inputs=[wp.array(mask, device="cpu"),
                                                         wp.array(cap.ravel(), device="cpu"), size, filt],
                  outputs=[wp.zeros(1, dtype=wp.vec3, device="cpu"), hits], device="cpu")
        assert hit == 0 and hits.numpy()[0] == 0, str(texel)
        assert np.isnan(pack_mask(mask.reshape(1, 1, 4))).all(), str(texel)


def test_particles_composite_of_the_finding_is_in_the_unit_range():
    """The fuzz finding's composite, replayed: two sprites over a 6 x 5 background, a 4 x 4 mask with NaN exit
    directions inside the drop, a 4 x 4 capture; every pixel in [0, 1]."""
    w, h = 6, 5
    rng = np.random.default_rng(7)
    bg = rng.uniform(0, 1, (h, w, 3)).astype(np.float32)
    cap = rng.uniform(0, 1, (4, 4, 3)).astype(np.float32)
    mask = np.tile(np.float32([0.396, 0.396, 0.698, 1.0]), (4, 4, 1))
    mask[1, 1] = (-0.99994, np.nan, np.nan, 1.0)
    mask[2, 0] = (0.992, np.nan, 2.35e-38, 1.0)
    mask[1, 2] = (np.nan, np.nan, np.nan, 1.0)
    sp = ffi().new("ccl_particles_sprite[2]")
    for j, (cx, cy, r, hh, tap, depth) in enumerate([(4.98, 4.28, 2.82, 8.73, 0.112, 7.0),
                                                      (4.98, 4.28, 0.1, 0.1, 0.0, 0.1)]):
        sp[j].cx, sp[j].cy, sp[j].radius, sp[j].half_height, sp[j].tap_offset, sp[j].depth = cx, cy, r, hh, tap, depth
    out = np.zeros((h, w, 3), np.float32)
    buf = lambda a: ffi().from_buffer("float[]", np.ascontiguousarray(a.ravel()))  # noqa: E731
    for streaks in (PK.DROPS, PK.STREAKS_THESIS, PK.STREAKS_PHYSICAL):
        for filt in (PK.NEAREST, PK.LINEAR):
            st = lib().ccl_particles_composite(buf(bg), w, h, sp, 2, buf(mask), 4, buf(cap), 4, 0.1, 0.015625, filt,
                                               streaks, 0.996, ffi().from_buffer("float[]", out))
            assert st == 0
            assert np.all(np.isfinite(out)) and out.min() >= 0.0 and out.max() <= 1.0


# --- issue 31, N6: the metaball field for radii whose square leaves the floats --------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
def test_metaball_finite_for_tiny_and_huge_radii(impl):
    """Before: r^2 / R^2 with R = 1e-30 was 0/0 and with r = R = 1e20 Inf/Inf, both NaN. Now r >= R gives 0 before
    any square, and radii beyond 2^+-60 use (r/R)^2: exact values at powers of two (r/R = 1/2: (3/4)^3)."""
    m = pywarp.equation("oc-4.2", impl=impl)
    cases = [((0.0, 1e-30, 1.0), 1.0), ((1e20, 1e20, 1.0), 0.0), ((3e38, 1e20, -2.0), 0.0),
             ((2.0 ** -101, 2.0 ** -100, 2.0), 2.0 * 27 / 64), ((2.0 ** 65, 2.0 ** 66, 1.0), 27 / 64),
             ((0.0, 1e-45, 1.0), 1.0), ((1e-45, 3e38, 1.0), 1.0), ((0.5, 1.0, 1.0), 27 / 64)]
    for (r, radius, strength), want in cases:
        got = float(m(r, radius, strength))
        assert got == want, (r, radius, strength, got)


# --- issue 31, N7: the capture parallax for radii whose square leaves the floats ------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
def test_capture_parallax_finite_for_tiny_and_huge_background_radii(impl):
    """Before: |p|^2 < R^2 and the root used R^2, which overflowed for R = 1e20 (NaN through Inf - Inf) and
    underflowed for R = 1e-45 (NaN although |p| = 0 < R). The angle is scale-free: p = (R/2, 0, 0) seen along y gives
    asin(1/2) = pi/6 for every R, p = 0 gives 0, and |p| = R stays NaN."""
    f = pywarp.equation("rr-alg-3.2.2", impl=impl)
    e = (0.0, 1.0, 0.0)
    for radius in (1e20, 2.0 ** 70, 3e38, 2.0 ** -140, 1e-30, 1.0):
        got = float(f((radius / 2, 0.0, 0.0), e, radius))
        assert got == pytest.approx(math.pi / 6, rel=1e-6), radius
    for radius in (1e-45, 1e20, 3e38):
        assert float(f((0.0, 0.0, 0.0), e, radius)) == 0.0, radius
        assert math.isnan(float(f((radius, 0.0, 0.0), e, radius))), radius


# --- issue 31, N8 (and N3's tiny capture FOVs): the capture FOV bounded below ---------------------------------------

def _c_composite_status(fov_capture):
    bg = np.zeros((2, 2, 3), np.float32)
    mask = np.zeros((1, 1, 4), np.float32)
    cap = np.zeros((1, 1, 3), np.float32)
    out = np.zeros((2, 2, 3), np.float32)
    def buf(a):
        return ffi().from_buffer("float[]", a)

    return lib().ccl_particles_composite(buf(bg), 2, 2, ffi().NULL, 0, buf(mask), 1, buf(cap), 1, 1.0, fov_capture,
                                         PK.NEAREST, 0, 1.0, buf(out))


@pytest.mark.parametrize("impl", IMPLS)
def test_capture_uv_refuses_a_capture_fov_below_the_minimum_and_is_finite_at_it(impl):
    """Before: fov_capture = 1e-45 was accepted and tan(fov_capture/2) = 0 made (u, v) = (NaN, NaN) at the view's
    centre (0 x Inf); the composite accepted 1e-9. The capture FOV is now >= 1/64 rad (CCL_PARTICLES_MIN_FOV_CAPTURE)
    in C (the composite's check), the registry and the composite's validation; at the limit the lookup is finite."""
    uv = pywarp.equation("rr-alg-3.1.2", impl=impl)
    for fov in (1e-45, 1e-9, 0.0155):
        with pytest.raises(ValueError, match="fov_capture"):
            uv((0.0, 0.0), 1.0, 1.0, fov)
    ndc = np.float32([[0.0, 0.0], [1.0, -1.0], [-1.0, 1.0]])
    got = np.asarray(uv(ndc, 100.0, float(np.float32(math.pi) - np.float32(2e-7)), PK.MIN_FOV_CAPTURE))
    assert np.all(np.isfinite(got)) and np.all(got[0] == 0.5)
    rng = np.random.default_rng(3)
    bg = rng.uniform(0, 1, (4, 4, 3)).astype(np.float32)
    cap = rng.uniform(0, 1, (8, 8, 3)).astype(np.float32)
    mask = np.zeros((4, 4, 4), np.float32)
    sp = np.float32([[2.0, 2.0, 1.5, 1.5, 0.0, 1.0]])
    f = pywarp.equation("rr-code-5.2.3", impl=impl)
    with pytest.raises(ValueError, match="fov_capture"):
        f(bg, cap, mask, sp, 1.0, 1e-9)
    assert np.all(np.isfinite(f(bg, cap, mask, sp, 1.0, PK.MIN_FOV_CAPTURE)))


def test_composite_min_capture_fov_is_the_c_check_limit():
    limit = np.float32(PK.MIN_FOV_CAPTURE)
    assert _c_composite_status(float(limit)) == 0
    assert _c_composite_status(float(np.nextafter(limit, np.float32(0)))) != 0


# --- issue 31, N12: the terrain clouds for rays grazing the horizon -------------------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("variant", ["corrected", "thesis"])
def test_terrain_clouds_finite_for_rays_grazing_the_horizon(impl, variant):
    """Before: for |rd.y| ~1e-36 and below, t = (cloud_height - ro.y) / rd.y or the fBm coordinate q.xz / cloud_scale
    overflowed, fbm(Inf) was NaN and the colour NaN (rd.x = 0: 0 x Inf already in q). Now such a plane point gives the
    colour unchanged, the weight's limit as for rd.y = 0; where the coordinate is finite the weight f rd.y is tiny."""
    clouds = pywarp.equation("pt-code-7.11", impl=impl)
    colour = np.float32([0.2, 0.4, 0.6])
    cases = [((1.0, y, 0.0), s) for y in (1e-36, 1e-38, 1e-45) for s in (1.0 / 64, 1.0)] + \
        [((0.0, 1e-45, 1.0), 1.0)] + ([((0.6, -1e-45, 0.8), 1.0 / 64)] if variant == "thesis" else [])
    for rd, scale in cases:
        got = np.asarray(clouds(colour, (0.0, 0.0, 0.0), rd, 100.0, (0.0, 0.0), 0.0, scale, (1.0, 1.0, 1.0), 7,
                                variant=variant))
        assert np.all(np.isfinite(got)), (rd, scale, got)
        assert np.max(np.abs(got - colour)) <= 1e-6, (rd, scale, got)


# --- issue 31, N13: the particle box and scene unit bounded -----------------------------------------------------------

def _c_particles_check(**fields):
    p = ffi().new("ccl_particles_params *")
    lib().ccl_particles_params_default(p)
    for name, value in fields.items():
        setattr(p, name, value)
    fld = ffi().new("const char **")
    status = lib().ccl_particles_params_check(p, fld)
    return status, (ffi().string(fld[0]).decode() if status else None)


@pytest.mark.parametrize("impl", IMPLS)
def test_particles_refuse_a_huge_box_and_a_tiny_scene_unit_and_are_finite_at_the_limits(impl):
    """Before: a box of +-3e38 passed the check and max - min = Inf made the positions NaN; metres_per_unit = 1e-45
    made the fall speed Inf and y NaN. The box and the respawn level are now within +-2^20 units
    (CCL_PARTICLES_MAX_EXTENT) and the scene unit >= 1/1024 m (CCL_PARTICLES_MIN_METRES_PER_UNIT); at these limits,
    with the fastest drops (slowdown 1/64), every particle is finite."""
    sim = pywarp.equation("rr-code-5.2.2", impl=impl)
    for fields, name in (({"box_min": (-3e38, -3e38, -3e38), "box_max": (3e38, 3e38, 3e38), "respawn_y": -3.1e38},
                          "box_min"),
                         ({"box_max": (1.0, 3e38, 1.5)}, "box_max"),
                         ({"respawn_y": -3e38}, "respawn_y"),
                         ({"metres_per_unit": 1e-45}, "metres_per_unit")):
        with pytest.raises(ValueError, match=name):
            sim(10, 10, **fields)
    e = PK.MAX_EXTENT
    got = sim(30, 64, dt=1.0, warm=True, box_min=(-e, -e + 1.0, -e), box_max=(e, e, e), respawn_y=-e,
              slowdown=0.015625, metres_per_unit=PK.MIN_METRES_PER_UNIT, wind=(1e5, 0.0, -1e5))
    for key in ("pos", "speed"):
        assert np.all(np.isfinite(np.asarray(got[key]))), key


def test_particles_box_and_scene_unit_limits_are_the_c_check_and_settings_limits():
    e = np.float32(PK.MAX_EXTENT)
    beyond = float(np.nextafter(e, np.float32(np.inf)))
    assert _c_particles_check(box_min=(-float(e), -1.0, -1.5), respawn_y=-float(e)) == (0, None)
    assert _c_particles_check(box_min=(-beyond, -1.0, -1.5))[1] == "box_min"
    assert _c_particles_check(box_max=(beyond, 1.25, 1.5))[1] == "box_max"
    assert _c_particles_check(respawn_y=-beyond)[1] == "respawn_y"
    m = np.float32(PK.MIN_METRES_PER_UNIT)
    assert _c_particles_check(metres_per_unit=float(m)) == (0, None)
    assert _c_particles_check(metres_per_unit=float(np.nextafter(m, np.float32(0))))[1] == "metres_per_unit"
    with pytest.raises(ValueError, match="metres_per_unit"):
        RainSettings(metres_per_unit=1e-45)
    assert RainSettings(metres_per_unit=0.001).metres_per_unit >= PK.MIN_METRES_PER_UNIT


# --- issue 31, N10: the ray-sphere intersection for radii whose square overflows ------------------------------------

@wp.kernel
def _ray_sphere(ro: wp.array(dtype=wp.vec3), rd: wp.array(dtype=wp.vec3), radius: wp.array(dtype=float),
                out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = SDF.sdf_ray_sphere(ro[i], rd[i], wp.vec3(0.0, 0.0, 0.0), radius[i])


def test_ray_sphere_finite_for_radii_whose_square_overflows():
    """Before: radius >= ~1.85e19 made radius^2 Inf and t = -b + sqrt(Inf) Inf (the Python registry refuses radii
    above 1e4; the C function documents any radius > 0). t scales with the sphere: from the centre, or from 1e4 units
    off it, the exit is at t = radius (to float precision); C and Warp alike, bit for bit, unchanged up to 2^60."""
    radii = [1.85e19, 1e20, 2.0 ** 100, 3e38, float(np.finfo(np.float32).max)]
    ro = [(0.0, 0.0, 0.0), (0.0, 0.0, -1e4), (1e4, -1e4, 1e4)]
    rd = [(0.0, 0.0, 1.0), (0.0, 0.0, 1.0), (0.0, 1.0, 0.0)]
    cases = [(o, d, r) for r in radii for o, d in zip(ro, rd)]
    o, d, r = (np.float32([c[k] for c in cases]) for k in range(3))
    out = wp.empty(len(cases), dtype=float, device="cpu")
    wp.launch(_ray_sphere, dim=len(cases), inputs=[wp.array(o, dtype=wp.vec3, device="cpu"),
                                                   wp.array(d, dtype=wp.vec3, device="cpu"),
                                                   wp.array(r, device="cpu")], outputs=[out], device="cpu")
    w = out.numpy()
    zero = ffi().new("ccl_vec3 *")[0]
    c = np.float32([lib().ccl_sdf_ray_sphere(tuple(o[i]), tuple(d[i]), zero, float(r[i])) for i in range(len(cases))])
    assert np.all(np.isfinite(c)), c
    np.testing.assert_allclose(c, r, rtol=1e-6)
    np.testing.assert_array_equal(w, c)
    at = np.float32(2.0 ** 60)
    for radius in (at, np.nextafter(at, np.float32(np.inf))):
        assert lib().ccl_sdf_ray_sphere((0.0, 0.0, -1e4), (0.0, 0.0, 1.0), zero, float(radius)) == \
            pytest.approx(float(radius), rel=1e-6)


# --- issue 31, N9: Snell's law for index ratios whose square overflows ------------------------------------------------

@wp.kernel
def _snell(d: wp.array(dtype=wp.vec3), n: wp.array(dtype=wp.vec3), n2: wp.array(dtype=float),
           t: wp.array(dtype=wp.vec3), tir: wp.array(dtype=int)):
    i = wp.tid()
    ti, ri, fi = OPT.optics_snell(d[i], n[i], 1.0, n2[i])
    t[i] = ti
    tir[i] = fi


def test_snell_finite_where_the_index_ratio_squared_overflows():
    """Before: with n2 below ~5e-20 (n1 = 1; the registry refuses n2 < 1e-3, the C header allowed any index > 0)
    eta^2 = Inf and at normal incidence k = 1 - Inf x 0 was NaN, the refracted ray NaN. Now a ray along the normal
    goes on unchanged (t = d) and an oblique one is totally reflected (eta^2 sin^2 > 1); C and Warp alike."""
    s = math.sqrt(0.5)
    cases = [((0.0, 0.0, -1.0), (0.0, 0.0, 1.0), False), ((0.0, -1.0, 0.0), (0.0, -1.0, 0.0), False),
             ((0.0, -s, -s), (0.0, 0.0, 1.0), True), ((0.6, -0.8, 0.0), (0.0, 1.0, 0.0), True)]
    n2s = (5e-20, 1e-30, 1e-45)
    rows = [(d, n, n2, tir) for d, n, tir in cases for n2 in n2s]
    d, n, n2 = (np.float32([r[k] for r in rows]) for k in range(3))
    t_w = wp.empty(len(rows), dtype=wp.vec3, device="cpu")
    tir_w = wp.empty(len(rows), dtype=int, device="cpu")
    wp.launch(_snell, dim=len(rows), inputs=[wp.array(d, dtype=wp.vec3, device="cpu"),
                                             wp.array(n, dtype=wp.vec3, device="cpu"), wp.array(n2, device="cpu")],
              outputs=[t_w, tir_w], device="cpu")
    r_c = ffi().new("ccl_vec3 *")
    tir_c = ffi().new("int *")
    for i, (di, ni, n2i, tir) in enumerate(rows):
        got = lib().ccl_optics_snell(tuple(d[i]), tuple(n[i]), 1.0, float(n2[i]), r_c, tir_c)
        got = np.float32([got.x, got.y, got.z])
        want = np.zeros(3, np.float32) if tir else d[i]
        assert tir_c[0] == int(tir) and np.array_equal(got, want), (di, ni, n2i, got)
        assert tir_w.numpy()[i] == int(tir) and np.array_equal(t_w.numpy()[i], want), (di, ni, n2i, t_w.numpy()[i])


# --- issue 31, N11: the terrain sky for a ray on the sun --------------------------------------------------------------

@wp.kernel
def _terrain_sky(v: wp.vec3, power: wp.array(dtype=float), out: wp.array(dtype=wp.vec3)):
    i = wp.tid()
    out[i] = K.terrain_sky(v, v, wp.vec3(0.2, 0.4, 0.6), wp.vec3(1.0, 0.0, 0.5), power[i])


@pytest.mark.parametrize("impl", IMPLS)
def test_terrain_sky_glow_at_most_the_sun_colour_for_a_ray_on_the_sun(impl):
    """Before: rd.sun of two unit vectors rounded to 1 + 2^-22 for rd = sun = 0.577350318 (1, 1, 1), and its power was
    not clamped: 1.0024 times the sun colour at power 1e4 (the registry's limit), Inf above ~7e8 (NaN with a zero
    sun colour component). The cosine is now taken in [0, 1], as in the gradient and volume skies."""
    v = (0.577350318,) * 3
    sky = pywarp.equation("pt-code-7.10", impl=impl)
    got = np.asarray(sky(v, v, (0.2, 0.4, 0.6), (1.0, 0.0, 0.5), 1.0e4), np.float32)
    np.testing.assert_array_equal(got, np.float32([0.2, 0.4, 0.6]) + np.float32([1.0, 0.0, 0.5]))


def test_terrain_sky_finite_for_huge_powers_on_the_sun():
    v = np.float32([0.577350318] * 3)
    powers = np.float32([1e9, 1e20, np.finfo(np.float32).max])
    out = wp.empty(len(powers), dtype=wp.vec3, device="cpu")
    wp.launch(_terrain_sky, dim=len(powers), inputs=[wp.vec3(*v), wp.array(powers, device="cpu")], outputs=[out],
              device="cpu")
    want = np.float32([1.2, 0.4, 1.1])
    for i, power in enumerate(powers):
        c = lib().ccl_terrain_sky(tuple(v), tuple(v), (0.2, 0.4, 0.6), (1.0, 0.0, 0.5), float(power))
        np.testing.assert_array_equal(np.float32([c.x, c.y, c.z]), want)
        np.testing.assert_array_equal(out.numpy()[i], want)
