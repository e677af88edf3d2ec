"""Volume rendering of uint8 cloud volumes (the SimVoleon stand-in of oc): the light volume and the pixel, Warp vs the
C reference at sampled pixels; the render is deterministic for every thread count; the survey extras oc-4.2
(metaball kernel) and oc-4.3 (textured ellipsoid)."""
from __future__ import annotations

import math

import numpy as np
import pytest
import warp as wp

import pywarp
from helpers import assert_twins_agree
from pywarp.core.cbridge import VOLUME_PARAMS
from pywarp.core.runtime import TileLauncher
from pywarp.kernels import camera as CAM
from pywarp.flight import model as F
from pywarp.kernels import volume as V
from pywarp.flight import volumes as VS


def ball(n=24, radius=9.0, soft=40.0):
    z, y, x = np.mgrid[0:n, 0:n, 0:n] + 0.5
    r = np.sqrt((x - n / 2) ** 2 + (y - n / 2) ** 2 + (z - n / 2) ** 2)
    return np.clip((radius - r) * soft, 0, 255).astype(np.uint8)


def scene(aircraft=True):
    vals = VOLUME_PARAMS.defaults()
    vs = VS.VolumeSet([VS.PlacedVolume(ball(), (-60.0, 80.0, -300.0), (120.0, 90.0, 120.0)),
                      VS.PlacedVolume(ball(16, 6.0), (40.0, 120.0, -420.0), (160.0, 60.0, 100.0)),
                      VS.PlacedVolume(ball(20, 7.0)[:, :, :], (-200.0, 60.0, -500.0), (90.0, 90.0, 90.0))])
    vs.compute_light(vals)
    if aircraft:
        # banked 20 deg to the right, nose 5 deg up
        f, r, u = F.axes(0.3, 0.09, 0.35)
        vals.update(aircraft=1, aircraft_position=(0.0, 100.0, -60.0), aircraft_forward=f, aircraft_right=r,
                    aircraft_up=u)
    cam = CAM.camera_look_at(np.array([0.0, 104.0, 0.0]), np.array([0.0, 100.0, -100.0]), (0.0, 1.0, 0.0),
                             math.radians(60.0), 16 / 9, 0.1, 1e5)
    return vals, vs, cam


def test_light_volume_warp_vs_c_and_closed_forms():
    vals = VOLUME_PARAMS.defaults()
    vals["sun"] = (0.0, 1.0, 0.0)
    v = VS.PlacedVolume(ball(), (0, 0, 0), (24, 24, 24))
    vs = VS.VolumeSet([v])
    vs.compute_light(vals)
    w = vs.light[0]
    c = VS.light_c(vals, v)
    np.testing.assert_allclose(w, c, rtol=2e-6, atol=1e-7)
    # above the ball the sun is unattenuated; under it darker than on top
    assert np.all(w[:, -1, :] == 1.0)
    assert w[12, 4, 12] < w[12, 18, 12] < 1.0
    # an empty volume lets all light through
    e = VS.VolumeSet([VS.PlacedVolume(np.zeros((8, 8, 8), np.uint8), (0, 0, 0), (1, 1, 1))])
    e.compute_light(vals)
    assert np.all(e.light[0] == 1.0)
    # a uniform slab of density 255 along the sun: exp(-light_tau * k) after k voxels (independent value)
    slab = VS.PlacedVolume(np.full((4, 10, 4), 255, np.uint8), (0, 0, 0), (4, 10, 4))
    s = VS.VolumeSet([slab])
    s.compute_light(vals)
    # voxel y = j sees the samples at j + 1, ..., 9 inside (the one at 10 + 0.5 is outside the box)
    for j in range(10):
        inside = sum(1 for k in range(1, 20) if j + 0.5 + k <= 10.0)
        assert s.light[0][2, j, 2] == pytest.approx(math.exp(-0.25 * inside), rel=1e-5)


def test_pixels_warp_vs_c():
    vals, vs, cam = scene()
    rng = np.random.default_rng(7)
    w_, h_ = 320, 180
    xs = np.concatenate([rng.integers(0, w_, 300), np.arange(150, 170)])
    ys = np.concatenate([rng.integers(0, h_, 300), np.full(20, 95)])
    w = VS.pixels_warp(vals, vs, cam, xs, ys, w_, h_)
    c = VS.pixels_c(vals, vs, cam, xs, ys, w_, h_)
    np.testing.assert_allclose(w, c, rtol=1e-5, atol=1e-6)
    # the samples cover the three kinds of background and the clouds
    assert np.isfinite(w).all()


def test_render_is_deterministic_for_any_thread_count():
    vals, vs, cam = scene()
    g, n, d, l, o = vs.warp()
    args = [VOLUME_PARAMS.warp_struct(vals), g, n, d, l, o, cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), 160, 90]
    imgs = []
    for workers in (1, 2, 3):
        out = wp.zeros((90, 160, 3), dtype=wp.uint8)
        with TileLauncher(workers=workers) as lau:
            lau.launch(V.render_kernel, 90, 160, args, [out])
        imgs.append(out.numpy())
    assert np.array_equal(imgs[0], imgs[1]) and np.array_equal(imgs[0], imgs[2])
    img = imgs[0]
    # sky above (blue > red), ground below (green > blue), clouds bright near the centre
    assert img[2, :, 2].mean() > img[2, :, 0].mean()
    assert img[-2, :, 1].mean() > img[-2, :, 2].mean()


def test_skipping_changes_no_pixel():
    """The skip distances (jumps over cubes of empty bricks), one brick per jump, and no skipping at all (a skip map
    of zeros) give the same image."""
    vals, vs, cam = scene()
    assert VS.skip_distance(vs.volumes[0].density).max() > 1
    imgs = []
    for cap in (255, 1, 0):
        vs.set_skip_cap(max(cap, 1))
        g, n, d, l, o = vs.warp()
        if cap == 0:
            o = wp.zeros_like(o)
        out = wp.zeros((90, 160, 3), dtype=wp.uint8)
        wp.launch(V.render_kernel, dim=(90, 160), inputs=[0, VOLUME_PARAMS.warp_struct(vals), g, n, d, l, o,
                                                         cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), 160, 90],
                  outputs=[out])
        imgs.append(out.numpy())
    vs.set_skip_cap(255)
    assert np.array_equal(imgs[0], imgs[1]) and np.array_equal(imgs[0], imgs[2])
    with pytest.raises(ValueError, match="skip_cap"):
        vs.set_skip_cap(0)


def test_occupancy_numpy_vs_c_and_conservative():
    from pywarp.core.binding import ffi, lib

    rng = np.random.default_rng(11)
    for shape in [(8, 8, 8), (9, 13, 6), (24, 24, 24)]:
        d = np.where(rng.random(shape) < 0.02, 200, 0).astype(np.uint8)
        occ = VS.occupancy(d)
        vs = VS.VolumeSet([VS.PlacedVolume(d, (0, 0, 0), (1, 1, 1))], [np.zeros(shape, np.float32)])
        arr, keep = VS.c_grids(vs)
        out = np.zeros(occ.shape, np.uint8)
        assert lib().ccl_volume_occupancy(arr, ffi().from_buffer("unsigned char[]", out), out.size) == 0
        np.testing.assert_array_equal(occ, out)
        # conservative: a voxel > 0 marks its own brick and the bricks whose trilinear reach includes it
        B = V.BRICK
        for z, y, x in zip(*np.nonzero(d)):
            assert occ[z // B, y // B, x // B] == 1
            if x % B == B - 1 and x // B + 1 < occ.shape[2]:
                assert occ[z // B, y // B, x // B + 1] == 1
            if x % B == 0 and x >= B:
                assert occ[z // B, y // B, x // B - 1] == 1
        # skip distances: NumPy = C, and each one the Chebyshev distance to the nearest occupied brick (brute force)
        sk = VS.skip_distance(d)
        out = np.zeros(occ.shape, np.uint8)
        assert lib().ccl_volume_skip(arr, ffi().from_buffer("unsigned char[]", out), out.size) == 0
        np.testing.assert_array_equal(sk, out)
        occupied = np.argwhere(occ > 0)
        for b in np.ndindex(occ.shape):
            want = 0 if occ[b] else (255 if len(occupied) == 0 else
                                     min(255, int(np.abs(occupied - np.array(b)).max(axis=1).min())))
            assert sk[b] == want, b
    # one voxel in a 24^3 volume: the distance grows by one per brick away from it (Chebyshev)
    d = np.zeros((24, 24, 24), np.uint8)
    d[3, 3, 3] = 90
    sk = VS.skip_distance(d)
    b = np.argwhere(VS.occupancy(d) > 0)
    idx = np.stack(np.meshgrid(*[np.arange(n) for n in sk.shape], indexing="ij"), -1)
    want = np.abs(idx[..., None, :] - b).max(-1).min(-1)
    np.testing.assert_array_equal(sk, want)
    assert sk.max() > 5
    # no brick occupied: 255 everywhere
    assert np.all(VS.skip_distance(np.zeros((6, 6, 6), np.uint8)) == 255)


def test_empty_scene_and_opaque_cloud():
    vals, vs, cam = scene(aircraft=False)
    xs, ys = np.array([160]), np.array([90])
    empty = VS.VolumeSet([])
    bg = VS.pixels_warp(vals, empty, cam, xs, ys, 320, 180)
    bg_c = VS.pixels_c(vals, empty, cam, xs, ys, 320, 180)
    np.testing.assert_array_equal(bg, bg_c)
    # a dense cube filling the view hides the background entirely: the pixel no longer depends on it
    cube = VS.VolumeSet([VS.PlacedVolume(np.full((8, 8, 8), 255, np.uint8), (-500, -400, -900), (1000, 1000, 500))])
    cube.compute_light(vals)
    a = VS.pixels_warp(vals, cube, cam, xs, ys, 320, 180)
    vals2 = dict(vals, sky_zenith=(1.0, 0.0, 0.0), sky_horizon=vals["sky_horizon"])
    b = VS.pixels_warp(vals2, cube, cam, xs, ys, 320, 180)
    np.testing.assert_allclose(a, b, atol=1e-6)


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="density"):
        VS.PlacedVolume(np.zeros((4, 4, 4), np.float32), (0, 0, 0), (1, 1, 1))
    with pytest.raises(ValueError, match="extent"):
        VS.PlacedVolume(np.zeros((4, 4, 4), np.uint8), (0, 0, 0), (1, 0, 1))
    with pytest.raises(ValueError, match="at most"):
        VS.VolumeSet([VS.PlacedVolume(np.zeros((2, 2, 2), np.uint8), (0, 0, 0), (1, 1, 1))] * 17)
    vals = VOLUME_PARAMS.defaults()
    with pytest.raises(ValueError, match=r"^g is out of range \(ccl_volume_check\), got 1\.0$"):
        V.checked_params(dict(vals, g=1.0))
    with pytest.raises(ValueError, match=r"^sun is out of range \(ccl_volume_check\)"):
        V.checked_params(dict(vals, sun=(0.0, 2.0, 0.0)))
    V.checked_params(vals)


def test_the_default_sun_is_sun_direction_of_its_angles():
    assert V.sun_direction(35.0, 150.0) == pytest.approx(VOLUME_PARAMS.defaults()["sun"], abs=1e-6)


# --- survey extras ---------------------------------------------------------------------------------------------------

@pytest.mark.spec("oc-4.2")
def test_metaball_kernel():
    r = np.linspace(0, 3, 301, dtype=np.float32)
    f = pywarp.equation("oc-4.2")(r, 2.0, 1.5)
    ref = np.where(r < 2.0, 1.5 * (1 - (r.astype(np.float64) / 2.0) ** 2) ** 3, 0.0)
    np.testing.assert_allclose(f, ref, rtol=1e-5, atol=1e-7)
    assert float(f[0]) == 1.5 and np.all(np.diff(f) <= 0)
    # smooth at R: value and slope vanish
    assert float(pywarp.equation("oc-4.2")(1.999, 2.0, 1.0)) < 1e-8
    assert_twins_agree("oc-4.2", r, 2.0, np.float32([[0.5], [-1.0], [3.0]]))
    with pytest.raises(ValueError, match="radius"):
        pywarp.equation("oc-4.2")(1.0, 0.0, 1.0)


@pytest.mark.spec("oc-4.3")
def test_textured_ellipsoid_opacity():
    E = pywarp.equation("oc-4.3")
    radii = np.float32([4.0, 2.0, 3.0])
    # centre: (texture - T1) / D; on the surface the texture must exceed T1 + D
    assert float(E(np.float32([0, 0, 0]), radii, 0.6, 0.2, 0.8)) == pytest.approx(0.5, rel=1e-6)
    assert float(E(np.float32([4, 0, 0]), radii, 0.9, 0.2, 0.8)) == 0.0
    assert float(E(np.float32([0, 0, 9]), radii, 1.0, 0.0, 0.5)) == 0.0
    # independent float64 formula on random points
    rng = np.random.default_rng(5)
    p = rng.uniform(-5, 5, (400, 3)).astype(np.float32)
    tex = rng.uniform(0, 1, 400).astype(np.float32)
    q = np.sum((p.astype(np.float64) / radii) ** 2, axis=1)
    ref = np.clip((tex - 0.1 - 0.5 * q) / 0.5, 0, 1)
    np.testing.assert_allclose(E(p, radii, tex, 0.1, 0.5), ref, atol=2e-6)
    assert_twins_agree("oc-4.3", p, radii, tex, 0.1, 0.5)
    with pytest.raises(ValueError, match="texture"):
        E(np.float32([0, 0, 0]), radii, 1.5, 0.1, 0.5)


@wp.kernel
def _sample_u8(values: wp.array(dtype=wp.uint8), offset: int, nx: int, ny: int, nz: int, v: wp.array(dtype=wp.vec3),
               out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = V.volume_sample(values, offset, nx, ny, nz, v[i], V._INV_255)


@wp.kernel
def _sample_f32(values: wp.array(dtype=float), offset: int, nx: int, ny: int, nz: int, v: wp.array(dtype=wp.vec3),
                out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = V.volume_sample(values, offset, nx, ny, nz, v[i], 1.0)


def test_volume_sample_is_the_twin_of_both_c_samplers():
    """The one generic sampler gives, bit for bit, ccl_volume_sample on uint8 densities (scale 1/255) and
    ccl_volume_sample_float on float32 values (scale 1), inside the grid, on its faces and clamped outside it, with the
    grid at an offset of the flat array."""
    from pywarp.core.binding import ffi, lib

    rng = np.random.default_rng(5)
    nx, ny, nz, offset = 5, 4, 3, 7
    dens = rng.integers(0, 256, (nz, ny, nx), dtype=np.uint8)
    vals = rng.normal(0.0, 3.0, (nz, ny, nx)).astype(np.float32)
    pts = np.concatenate([rng.uniform(-2.0, 8.0, (200, 3)), [[0.5, 0.5, 0.5], [5.0, 4.0, 3.0], [2.5, 1.0, 0.0]]])
    pts = pts.astype(np.float32)
    v = wp.array(pts, dtype=wp.vec3, device="cpu")
    for grid, kernel, c_fn, ctype in [(dens, _sample_u8, lib().ccl_volume_sample, "unsigned char[]"),
                                      (vals, _sample_f32, lib().ccl_volume_sample_float, "float[]")]:
        flat = np.concatenate([np.zeros(offset, grid.dtype), grid.ravel()])
        out = wp.zeros(len(pts), dtype=float, device="cpu")
        wp.launch(kernel, dim=len(pts), inputs=[wp.array(flat, device="cpu"), offset, nx, ny, nz, v, out],
                  device="cpu")
        buf = ffi().from_buffer(ctype, np.ascontiguousarray(grid.ravel()))
        want = np.array([c_fn(buf, nx, ny, nz, {"x": p[0], "y": p[1], "z": p[2]}) for p in pts], np.float32)
        np.testing.assert_array_equal(out.numpy().view(np.uint32), want.view(np.uint32))
