"""Depth-aware temporal reprojection (not in the thesis; cclouds/reproj.h has the method and its choices): the surface
depth a marched pixel keeps, the fixed-point iteration on the previous frame's depth against closed forms (a plane of
known depth and a sideways step of a whole number of pixels; a sphere of known radius around the previous eye and any
step), the clamped Catmull-Rom history filter, the depths carried with the frame, C vs Warp, the tile-parallel launch,
bad input."""
from __future__ import annotations

import math

import numpy as np
import pytest
import warp as wp

import pywarp
from helpers import look_at64, max_ulp_diff

from pywarp.core.runtime import TileLauncher
from pywarp.kernels import camera as cm
from pywarp.kernels import raymarch as rm
from pywarp.kernels import reproj as rp
from pywarp.clouds import reproj as crp

IMPLS = ["warp", "c"]
R_E = 6371.0


# --- float64 camera math written here ---------------------------------------------------------------------------------


def rays64(view, fov, w, h, x, y):
    """Unit rays (..., 3) through pixel centres (x, y) of the camera (eye, target)."""
    e, s, u, f = look_at64(*view)
    t = math.tan(float(np.float32(fov)) / 2)
    a = float(np.float32(w / h))
    nx, ny = 2 * (np.asarray(x) + 0.5) / w - 1, 1 - 2 * (np.asarray(y) + 0.5) / h
    d = (nx * a * t)[..., None] * s + (ny * t)[..., None] * u + f
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def project64(view, fov, w, h, p):
    """Pixel coordinates (pixel (i, j) centred at (i, j)) of world points p (..., 3) in the camera (eye, target)."""
    e, s, u, f = look_at64(*view)
    t = math.tan(float(np.float32(fov)) / 2)
    a = float(np.float32(w / h))
    q = p - e
    z = q @ f
    return ((q @ s) / (z * a * t) * 0.5 + 0.5) * w - 0.5, (0.5 - (q @ u) / (z * t) * 0.5) * h - 0.5


def cams(cur, prev, fov, w, h):
    return (cm.camera_look_at(*cur, fov_y=fov, aspect=w / h), cm.camera_look_at(*prev, fov_y=fov, aspect=w / h))


def grid(w, h):
    return np.meshgrid(np.arange(w), np.arange(h))


def updated_mask(w, h, frame):
    f = frame % 16
    x, y = grid(w, h)
    return (x % 4 == f // 4) & (y % 4 == f % 4)


def coordinate_frame(w, h):
    """A previous frame holding its own pixel coordinates: a filter that reproduces linear functions returns the
    sample position exactly."""
    x, y = np.meshgrid(np.arange(w, dtype=np.float32), np.arange(h, dtype=np.float32))
    return np.stack([x, y], -1)


# --- the surface depth ------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
def test_surface_depth_is_cloud_else_ground_else_sky(impl):
    eye = np.array([0.0, 0.3, 0.0])
    down = np.array([0.0, -math.sin(0.2), -math.cos(0.2)])  # 11.5 deg below the horizontal: meets the ground
    up = np.array([0.0, math.sin(0.3), -math.cos(0.3)])
    d = np.stack([up, down, up, down, up])
    md = np.array([2.5, 1.75, 0.0, 0.0, np.nan], np.float32)
    out = crp.surface_depth(md, eye, d, impl=impl)
    # the ground: |eye + t d - c| = R_E in float64 (the near root)
    oc = eye - np.array([0.0, -R_E, 0.0])
    b = down @ oc
    t_ground = -b - math.sqrt(b * b - (oc @ oc - R_E * R_E))
    assert out[0] == np.float32(2.5) and out[1] == np.float32(1.75)  # a cloud: the march's mean distance
    assert out[2] == np.float32(rp.SKY_DEPTH_KM)  # the sky: far away (pins CCL_REPROJ_SKY_DEPTH_KM in C)
    # the ground ahead (1.5 km), to the float32 resolution of the Earth-centred radii (ulp(6371 km) = 0.5 m, a few)
    assert out[3] == pytest.approx(t_ground, abs=2e-3)
    assert np.isnan(out[4])
    assert np.isnan(crp.surface_depth(0.0, (0.0, np.nan, 0.0), up, impl=impl))


def test_surface_depth_c_and_warp_agree(rng):
    d = rng.normal(size=(2000, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    md = rng.choice(np.array([0.0, -1.0, 0.25, 3.0, 40.0, np.nan], np.float32), 2000)
    for eye in ((0.0, 0.3, 0.0), (5.0, 0.0, -3.0), (0.0, 2.5, 0.0), (0.0, 7.0, 1.0)):
        a = crp.surface_depth(md, eye, d)
        b = crp.surface_depth(md, eye, d, impl="c")
        assert np.array_equal(np.isnan(a), np.isnan(b))
        assert max_ulp_diff(a[~np.isnan(a)], b[~np.isnan(b)]) == 0


# --- the fixed-point iteration: closed forms --------------------------------------------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("k", [1, 3])
def test_uv_depth_plane_sideways_step_is_exact(impl, k):
    """A plane facing the camera at z = -2 km (the previous frame's depth buffer holds the exact distance along each
    pixel's ray) and a sideways step of exactly k pixels at that distance: every point the current frame sees was
    at (x + k, y) in the previous one, exactly, while the thesis's inner-sphere point is off by nearly k pixels."""
    w, h, fov = 96, 54, 1.0
    z_plane = 2.0
    eye = np.array([0.0, 0.3, 0.0])
    view = lambda e: (e, e + np.array([0.0, 0.0, -1.0]))  # noqa: E731
    # the width of a pixel at distance z_plane (float32-rounded camera constants, as the camera uses)
    px_km = 2 * z_plane * math.tan(float(np.float32(fov)) / 2) * float(np.float32(w / h)) / w
    prev_eye = eye.copy()
    cur_eye = eye + np.array([k * px_km, 0.0, 0.0])
    cam, pcam = cams(view(cur_eye), view(prev_eye), fov, w, h)
    x, y = grid(w, h)
    d_prev = rays64(view(prev_eye), fov, w, h, x, y)
    prev_depth = ((np.float32(prev_eye[2]) - (-z_plane)) / -d_prev[..., 2]).astype(np.float32)
    inside = x + k <= w - 1  # seen by the previous frame
    ok, u, v, t = crp.reproj_uv_depth_at(x, y, cam, pcam, prev_depth, impl=impl)
    assert np.all(ok[inside] == 1)
    # tolerance: float32 round-off of the camera matrices and of the projection (~1e-4 px at this size)
    np.testing.assert_allclose((u * w - 0.5)[inside], (x + k)[inside], atol=1e-3)
    np.testing.assert_allclose((v * h - 0.5)[inside], y[inside], atol=1e-3)
    # the depth carried: the distance from the current eye to the plane along the current ray (converged: the default
    # 2 refinements leave 6e-5 of it here, where the first lookup lands k pixels off; the position is then already
    # exact to 2e-4 px)
    d_cur = rays64(view(cur_eye), fov, w, h, x, y)
    t = crp.reproj_uv_depth_at(x, y, cam, pcam, prev_depth, iterations=4, impl=impl)[3]
    np.testing.assert_allclose(t[inside], ((cur_eye[2] + z_plane) / -d_cur[..., 2])[inside], rtol=2e-5)
    # the thesis's point (the layer base, 100+ km away along these rays) has almost no parallax: off by ~k pixels
    ok0, u0, v0, t0 = crp.reproj_uv_depth_at(x, y, cam, pcam, prev_depth, iterations=0, impl=impl)
    err0 = np.abs((u0 * w - 0.5) - (x + k))[inside & (ok0 == 1)]
    assert np.median(err0) > 0.9 * k


def sphere_case(step, radius, w=640, h=360, fov=1.0):
    """The previous frame saw a sphere of the given radius (km) around its eye (every depth = radius); the camera has
    moved by ``step`` (km, 3-vector) since. Returns the cameras, the previous depth buffer and, in float64, the exact
    previous pixel coordinates and distance of what each current pixel sees (the far hit: the eye is inside)."""
    prev_eye = np.array([0.0, 0.3, 0.0])
    target = np.array([0.3, 0.7, -1.0])
    cur = (prev_eye + step, prev_eye + step + target)
    prev = (prev_eye, prev_eye + target)
    cam, pcam = cams(cur, prev, fov, w, h)
    x, y = grid(w, h)
    d = rays64(cur, fov, w, h, x, y)
    e = np.asarray(cur[0], np.float32).astype(float)
    pe = np.asarray(prev_eye, np.float32).astype(float)
    b = d @ (e - pe)
    t = -b + np.sqrt(b * b - ((e - pe) @ (e - pe) - radius * radius))
    xp, yp = project64(prev, fov, w, h, e + t[..., None] * d)
    return cam, pcam, np.full((h, w), radius, np.float32), x, y, xp, yp, t


@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("step", [(0.0, 0.0, -0.02), (0.15, 0.05, 0.1)])
def test_uv_depth_sphere_of_known_radius_is_exact(impl, step):
    """A previous depth of 2 km everywhere (a sphere around the previous eye) and any camera step: the iteration
    converges onto the ray-sphere hit, and the reprojected position is its projection into the previous camera."""
    cam, pcam, depth, x, y, xp, yp, t_hit = sphere_case(np.array(step), 2.0, 160, 90)
    ok, u, v, t = crp.reproj_uv_depth_at(x, y, cam, pcam, depth, impl=impl)
    vis = (xp > 0) & (xp < 159) & (yp > 0) & (yp < 89)
    assert vis.mean() > 0.7 and np.all(ok[vis] == 1)
    np.testing.assert_allclose((u * 160 - 0.5)[vis], xp[vis], atol=2e-3)  # float32 round-off, < 1e-3 px measured
    np.testing.assert_allclose((v * 90 - 0.5)[vis], yp[vis], atol=2e-3)
    # the distance, converged (the default 2 refinements leave up to 6e-5 of it for the larger step)
    t = crp.reproj_uv_depth_at(x, y, cam, pcam, depth, iterations=4, impl=impl)[3]
    np.testing.assert_allclose(t[vis], t_hit[vis], rtol=1e-5)


def test_uv_depth_converges_in_the_default_iterations():
    """The error falls geometrically with the iterations; a forward step of 20 m with clouds 2 km away is within a
    thousandth of a pixel at 640 x 360 after one, a step of 200 m within 0.01 px after the default 2."""
    cam, pcam, depth, x, y, xp, yp, _ = sphere_case(np.array([0.0, 0.0, -0.02]), 2.0)
    sel = (slice(20, 340, 7), slice(20, 620, 7))
    errs = []
    for n in range(4):
        ok, u, v, t = crp.reproj_uv_depth_at(x[sel], y[sel], cam, pcam, depth, iterations=n)
        assert np.all(ok == 1)
        errs.append(float(np.max(np.hypot(u * 640 - 0.5 - xp[sel], v * 360 - 0.5 - yp[sel]))))
    assert errs[0] > 1.0  # the inner sphere (1.2 km above the camera) is the wrong depth: parallax error > 1 px
    assert errs[1] < 1e-3 and errs[2] < 1e-3 and errs[3] < 1e-3, errs
    assert rp.DEPTH_ITERATIONS == 2
    # and a step ten times larger (200 m) still converges by the default count
    cam, pcam, depth, x, y, xp, yp, _ = sphere_case(np.array([0.0, 0.0, -0.2]), 2.0)
    ok, u, v, t = crp.reproj_uv_depth_at(x[sel], y[sel], cam, pcam, depth)
    assert np.max(np.hypot(u * 640 - 0.5 - xp[sel], v * 360 - 0.5 - yp[sel])) < 0.01


@pytest.mark.parametrize("impl", IMPLS)
def test_uv_depth_without_iterations_or_depth_is_the_inner_sphere_point(impl, rng):
    """iterations = 0, or a previous depth that is unknown (not > 0) everywhere: the thesis's inner-sphere point,
    bit for bit (its distance is the inner-sphere hit)."""
    w, h = 64, 36
    cam, pcam = cams(((0.0, 0.3, 0.0), (0.2, 0.6, -1.0)), ((0.03, 0.3, 0.05), (0.23, 0.6, -0.95)), 1.1, w, h)
    x, y = grid(w, h)
    ref = crp.reproj_uv_depth_at(x, y, cam, pcam, np.full((h, w), 0.0, np.float32), iterations=0, impl=impl)
    for depth, n in ((rng.uniform(0.5, 9.0, (h, w)), 0), (np.zeros((h, w)), 3), (np.full((h, w), -1.0), 3),
                     (np.full((h, w), np.nan), 3)):
        out = crp.reproj_uv_depth_at(x, y, cam, pcam, depth.astype(np.float32), iterations=n, impl=impl)
        for a, b in zip(out, ref):
            np.testing.assert_array_equal(a, b)
    # the distance: the inner sphere's far root (the camera is inside it) along the pixel's ray, the same float32
    # operations as vc-A25 then vc-A14
    layer = rm.CloudLayer()
    d = pywarp.camera_ray(x, y, w, h, cam)
    t0, t1 = pywarp.equation("vc-A14")(np.asarray(cam.eye, np.float32), d, layer.centre, layer.r_inner)
    np.testing.assert_array_equal(ref[3], t1)
    assert np.all(t0 < 0)


# --- the frame pass ---------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
def test_frame_depth_thesis_settings_equal_reproj_frame(impl, rng):
    """iterations = 0 with the bilinear filter: the colours of vc-A26 / vc-A27 (ccl_reproj_frame) bit for bit."""
    w, h = 50, 31
    cam, pcam = cams(((0.2, 0.3, 0.1), (0.5, 0.7, -0.9)), ((0.25, 0.31, 0.05), (0.52, 0.7, -0.9)), 1.2, w, h)
    cur, prev = rng.random((h, w, 3), np.float32), rng.random((h, w, 3), np.float32)
    red = rng.random((8, 13, 3), np.float32)
    dep, pdep = rng.uniform(0.5, 9.0, (h, w)), rng.uniform(0.5, 9.0, (h, w))
    for kw in ({}, {"neighbourhood": 3}, {"history": False}):
        for frame in (0, 6, 13):
            ref = pywarp.equation("vc-A26", impl=impl)(cur, prev, red, frame, cam, pcam, **kw)
            out, _ = crp.reproj_frame_depth(cur, dep, prev, pdep, red, frame, cam, pcam, iterations=0,
                                           filter="bilinear", impl=impl, **kw)
            np.testing.assert_array_equal(out, ref)


@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("flt", ["catmull_rom", "bilinear"])
def test_frame_depth_static_camera_returns_previous_frame_exactly(impl, flt, rng):
    w, h = 48, 30
    cam = cm.camera_look_at((0.3, 0.3, -0.4), (0.8, 0.8, -1.2), fov_y=1.1, aspect=w / h)
    cur, prev = rng.random((h, w, 3), np.float32), rng.random((h, w, 3), np.float32)
    red = rng.random((8, 12, 3), np.float32)
    dep = rng.uniform(0.5, 9.0, (h, w)).astype(np.float32)
    pdep = rng.choice(np.array([0.7, 2.0, 3.5, rp.SKY_DEPTH_KM], np.float32), (h, w))
    for frame in (0, 7, 100):
        out, od = crp.reproj_frame_depth(cur, dep, prev, pdep, red, frame, cam, cam, filter=flt, impl=impl)
        upd = updated_mask(w, h, frame)
        np.testing.assert_array_equal(out[upd], cur[upd])
        np.testing.assert_array_equal(out[~upd], prev[~upd])
        np.testing.assert_array_equal(od[upd], dep[upd])
        np.testing.assert_allclose(od[~upd], pdep[~upd], rtol=1e-6)  # |Y - eye| with Y = eye + D dir: rounding


@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("flt", ["catmull_rom", "bilinear"])
def test_frame_depth_moving_camera_fetches_the_closed_form_position(impl, flt):
    """A previous frame holding its own pixel coordinates, its depth a 2 km sphere around its eye, and a camera step:
    the reprojected pixels hold the exact previous position of what they see (both filters reproduce linear
    functions) and carry its exact distance."""
    w, h = 96, 54
    cam, pcam, depth, x, y, xp, yp, t_hit = sphere_case(np.array([0.15, 0.0, 0.0]), 2.0, w, h)
    prev = coordinate_frame(w, h)
    cur = np.full((h, w, 2), -7.0, np.float32)
    red = np.full((14, 24, 2), -9.0, np.float32)
    out, od = crp.reproj_frame_depth(cur, np.full((h, w), 5.0), prev, depth, red, 3, cam, pcam, filter=flt,
                                    iterations=4, impl=impl)  # converged depths (the default 2: positions alike)
    upd = updated_mask(w, h, 3)
    # away from the borders (the filters clamp to the edge; Catmull-Rom reads one pixel further)
    inner = ~upd & (xp > 2) & (xp < w - 3) & (yp > 2) & (yp < h - 3)
    assert inner.sum() > 0.5 * w * h
    np.testing.assert_allclose(out[inner, 0], xp[inner], atol=1 / 256 + 2e-3)
    np.testing.assert_allclose(out[inner, 1], yp[inner], atol=1 / 256 + 2e-3)
    np.testing.assert_allclose(od[inner], t_hit[inner], rtol=1e-5)
    # what the previous frame did not see comes from the reduced buffer
    hidden = ~upd & ((xp < -0.5) | (xp > w - 0.5) | (yp < -0.5) | (yp > h - 0.5))
    assert hidden.sum() > 0 and np.all(out[hidden] == -9.0)


def resample_twice(flt, img):
    """Reproject img by half a pixel sideways and back (a plane 2 km away; depths exact): the detail left."""
    w, h = img.shape[1], img.shape[0]
    fov = 1.0
    px_km = 2 * 2.0 * math.tan(float(np.float32(fov)) / 2) * float(np.float32(w / h)) / w
    a = np.array([0.0, 0.3, 0.0])
    b = a + np.array([0.5 * px_km, 0.0, 0.0])
    view = lambda e: (e, e + np.array([0.0, 0.0, -1.0]))  # noqa: E731
    x, y = grid(w, h)
    out = img
    for src, dst in ((a, b), (b, a)):
        cam, pcam = cams(view(dst), view(src), fov, w, h)
        d = rays64(view(src), fov, w, h, x, y)
        depth = ((np.float32(src[2]) + 2.0) / -d[..., 2]).astype(np.float32)
        # frame 0 renders (0, 0) of every block: keep the test on the reprojected pixels only
        out, _ = crp.reproj_frame_depth(out, depth, out, depth, np.zeros((h // 4, w // 4, img.shape[2])), 0, cam,
                                       pcam, filter=flt, history=True)
    return out


def test_catmull_rom_keeps_detail_that_bilinear_blurs(rng):
    """The reason for the filter: a pixel is resampled at every frame it is carried; at half-pixel offsets the
    bilinear filter halves the variance of white noise each time (weights 1/2, 1/2; the marched pixel of each block
    is kept, so 0.38 of it is left after two), the clamped Catmull-Rom (weights -1/16, 9/16, 9/16, -1/16, clamped)
    keeps a third more (measured 0.50)."""
    img = rng.random((48, 96, 1), np.float32)
    upd = updated_mask(96, 48, 0)
    inner = ~upd
    inner[:, :3] = inner[:, -3:] = False
    ref = img[inner, 0].var()
    bil = resample_twice("bilinear", img)[inner, 0].var()
    cr = resample_twice("catmull_rom", img)[inner, 0].var()
    assert bil < 0.42 * ref
    assert cr > 0.47 * ref and cr > 1.25 * bil


@pytest.mark.parametrize("impl", IMPLS)
def test_catmull_rom_never_overshoots_the_bilinear_footprint(impl, rng):
    """On a step edge and on white noise, every reprojected value lies within the range of the 2 x 2 pixels the
    bilinear lookup reads, so no ringing builds up over the frames a pixel is carried."""
    w, h = 64, 40
    cam, pcam = cams(((0.0, 0.3, 0.0), (0.2, 0.6, -1.0)), ((0.031, 0.3, 0.017), (0.231, 0.6, -0.983)), 1.0, w, h)
    depth = rng.uniform(0.8, 3.0, (h, w)).astype(np.float32)
    x, y = grid(w, h)
    for prev in ((x > 30).astype(np.float32)[..., None], rng.random((h, w, 1), np.float32)):
        out, _ = crp.reproj_frame_depth(np.zeros_like(prev), depth, prev, depth, np.full((10, 16, 1), -5.0), 2, cam,
                                       pcam, impl=impl)
        ok, u, v, _ = crp.reproj_uv_depth_at(x, y, cam, pcam, depth, impl=impl)
        sel = (ok == 1) & ~updated_mask(w, h, 2)
        # the position the pass samples: snapped to a pixel centre within SNAP_PX
        xs, ys = u[sel] * w - 0.5, v[sel] * h - 0.5
        xs = np.where(np.abs(xs - np.round(xs)) <= rp.SNAP_PX, np.round(xs), xs)
        ys = np.where(np.abs(ys - np.round(ys)) <= rp.SNAP_PX, np.round(ys), ys)
        x0 = np.clip(np.floor(xs).astype(int), 0, w - 1)
        y0 = np.clip(np.floor(ys).astype(int), 0, h - 1)
        x1, y1 = np.clip(x0 + 1, 0, w - 1), np.clip(y0 + 1, 0, h - 1)
        quad = np.stack([prev[y0, x0, 0], prev[y0, x1, 0], prev[y1, x0, 0], prev[y1, x1, 0]])
        got = out[sel, 0]
        assert np.all(got >= quad.min(axis=0)) and np.all(got <= quad.max(axis=0))
        assert sel.sum() > 0.5 * w * h


@pytest.mark.parametrize("impl", IMPLS)
def test_frame_depth_fallback_depth_interpolates_the_marched_depths(impl):
    """Without history (first frame, camera cut), a pixel's depth is the bilinear interpolation of this frame's
    marched depths at its reduced-buffer position, like its colour: a depth linear in the texel coordinates of the
    marched pixels is reproduced exactly."""
    w, h, frame = 26, 15, 6  # (a, b) = (1, 2); not divisible by 4
    a, b = 1, 2
    x, y = grid(w, h)
    ex = np.clip((x - a) / 4, 0, (w - 1 - a) // 4)
    ey = np.clip((y - b) / 4, 0, (h - 1 - b) // 4)
    upd = updated_mask(w, h, frame)
    depth = np.where(upd, 1.0 + 0.5 * ((x - a) / 4) + 0.25 * ((y - b) / 4), -3.0).astype(np.float32)
    cam = cm.camera_look_at((0, 0.3, 0), (0, 0.7, -1), aspect=w / h)
    cur = np.zeros((h, w, 1), np.float32)
    red = np.zeros((4, 7, 1), np.float32)
    _, od = crp.reproj_frame_depth(cur, depth, cur, np.full((h, w), 9.0), red, frame, cam, cam, history=False,
                                  impl=impl)
    np.testing.assert_allclose(od, 1.0 + 0.5 * ex + 0.25 * ey, atol=1e-6)
    # a 2-pixel-wide frame in a cycle frame that renders no column: previous (history) or current depth as is
    tiny = np.zeros((8, 2, 1), np.float32)
    tcam = cm.camera_look_at((0, 0.3, 0), (0, 0.7, -1), aspect=0.25)
    away = cm.camera_look_at((0, 0.3, 0), (0, 0.7, 1), aspect=0.25)
    _, od = crp.reproj_frame_depth(tiny, np.full((8, 2), 1.0), tiny, np.full((8, 2), 2.0), np.zeros((2, 1, 1)), 9,
                                  tcam, away, impl=impl)
    assert np.all(od == 2.0)
    _, od = crp.reproj_frame_depth(tiny, np.full((8, 2), 1.0), tiny, np.full((8, 2), 2.0), np.zeros((2, 1, 1)), 9,
                                  tcam, tcam, history=False, impl=impl)
    assert np.all(od == 1.0)


def test_frame_depth_c_and_warp_agree(rng):
    """The pass in C and Warp on random images and depths (clouds, sky, unknown) and moving cameras, for every filter,
    iteration count, neighbourhood and history: at most 2 ulp apart (the same float32 operations in the same order;
    measured 0)."""
    w, h = 70, 45
    cam, pcam = cams(((0.2, 0.3, 0.1), (0.5, 0.7, -0.9)), ((0.23, 0.3, 0.13), (0.53, 0.71, -0.87)), 1.2, w, h)
    cur, prev = rng.random((h, w, 4), np.float32), rng.random((h, w, 4), np.float32)
    red = rng.random((12, 18, 4), np.float32)
    dep = rng.uniform(0.5, 9.0, (h, w)).astype(np.float32)
    pdep = rng.choice(np.array([0.0, 0.9, 1.7, 2.6, 4.0, rp.SKY_DEPTH_KM], np.float32), (h, w))
    for kw in ({}, {"filter": "bilinear"}, {"iterations": 1}, {"iterations": rp.MAX_DEPTH_ITERATIONS},
               {"neighbourhood": 3}, {"history": False}):
        for frame in (0, 9):
            a = crp.reproj_frame_depth(cur, dep, prev, pdep, red, frame, cam, pcam, **kw)
            b = crp.reproj_frame_depth(cur, dep, prev, pdep, red, frame, cam, pcam, impl="c", **kw)
            assert max_ulp_diff(a[0], b[0]) <= 2 and max_ulp_diff(a[1], b[1]) <= 2, kw
    x, y = grid(w, h)
    a = crp.reproj_uv_depth_at(x, y, cam, pcam, pdep)
    b = crp.reproj_uv_depth_at(x, y, cam, pcam, pdep, impl="c")
    np.testing.assert_array_equal(a[0], b[0])
    for p, q in zip(a[1:], b[1:]):
        assert np.array_equal(np.isnan(p), np.isnan(q)) and max_ulp_diff(p[~np.isnan(p)], q[~np.isnan(q)]) <= 2


def test_frame_depth_kernel_tile_parallel_equals_single_band(rng):
    w, h = 37, 29
    cam, pcam = cams(((0, 0.3, 0), (0.2, 0.8, -1)), ((0.03, 0.3, 0.02), (0.23, 0.8, -0.98)), 1.0, w, h)
    cur, prev = rng.random((h, w, 3), np.float32), rng.random((h, w, 3), np.float32)
    red = rng.random((8, 10, 3), np.float32)
    dep, pdep = (rng.uniform(0.5, 5.0, (h, w)).astype(np.float32) for _ in range(2))
    ref, ref_d = crp.reproj_frame_depth(cur, dep, prev, pdep, red, 11, cam, pcam)
    layer = rm.CloudLayer()
    for workers in (1, 3):
        with TileLauncher(workers=workers, bands_per_worker=3) as tl:
            out = wp.empty((h, w, 3), dtype=float, device=tl.device)
            out_d = wp.empty((h, w), dtype=float, device=tl.device)
            tl.launch(rp.reproject_frame_depth_kernel, h, w,
                      inputs=[wp.array(cur, dtype=float), wp.array(dep, dtype=float), wp.array(prev, dtype=float),
                              wp.array(pdep, dtype=float), wp.array(red, dtype=float), 11,
                              cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), pcam.mat44("view_proj"),
                              pcam.eye_vec3(), layer.centre_vec3(), layer.r_inner, 1,
                              rp.FILTERS["catmull_rom"], rp.DEPTH_ITERATIONS, 1], outputs=[out, out_d])
            np.testing.assert_array_equal(out.numpy(), ref)
            np.testing.assert_array_equal(out_d.numpy(), ref_d)


# --- bad input --------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
def test_frame_depth_bad_input_raises_naming_parameter(impl):
    cam = cm.camera_look_at((0, 0.3, 0), (0, 0.7, -1), aspect=2.0)
    cur = np.zeros((8, 16, 3), np.float32)
    red = np.zeros((2, 4, 3), np.float32)
    dep = np.ones((8, 16), np.float32)

    def call(**kw):
        args = dict(current=cur, depth=dep, previous=cur, previous_depth=dep, reduced=red, frame=0, camera=cam,
                    prev_camera=cam, impl=impl)
        args.update(kw)
        return crp.reproj_frame_depth(**args)

    with pytest.raises(ValueError, match=r"^depth must have shape \(height, width\) = \(8, 16\), got \(8, 15\)"):
        call(depth=dep[:, :15])
    with pytest.raises(ValueError, match=r"^previous_depth must have shape \(height, width\) = \(8, 16\)"):
        call(previous_depth=dep[:, :, None])
    with pytest.raises(TypeError, match=r"^previous_depth must be a float array"):
        call(previous_depth=None)
    with pytest.raises(ValueError, match=r"^iterations must be in \[0, 16\], got 17"):
        call(iterations=17)
    with pytest.raises(ValueError, match=r"^iterations must be in \[0, 16\], got -1"):
        call(iterations=-1)
    with pytest.raises(TypeError, match=r"^iterations must be an integer"):
        call(iterations=2.0)
    with pytest.raises(ValueError, match=r"^filter must be one of 'bilinear', 'catmull_rom', got 'cubic'"):
        call(filter="cubic")
    with pytest.raises(ValueError, match=r"^neighbourhood must be an odd integer in \[1, 31\], got 4"):
        call(neighbourhood=4)
    with pytest.raises(TypeError, match=r"^prev_camera must be a pywarp.kernels.camera.Camera"):
        call(prev_camera=None)
    with pytest.raises(ValueError, match=r"^impl must be 'warp' or 'c'"):
        call(impl="cuda")
    with pytest.raises(ValueError, match=r"^x, y must be pixels of the 16x8 frame"):
        crp.reproj_uv_depth_at(16, 0, cam, cam, dep, impl=impl)
    with pytest.raises(ValueError, match=r"^iterations must be in \[0, 16\], got 99"):
        crp.reproj_uv_depth_at(0, 0, cam, cam, dep, iterations=99, impl=impl)


def test_c_frame_depth_rejects_invalid_arguments_and_allows_in_place_outputs(rng):
    """ccl_reproj_frame_depth: CCL_EINVAL with the outputs untouched for NULL buffers, bad sizes, an unknown filter,
    iterations out of range, a written buffer that is also read; out == current and out_depth == current_depth give
    the result of separate buffers."""
    from pywarp.core.binding import ffi, lib

    F, L = ffi(), lib()
    w, h, c = 9, 7, 2
    cam, pcam = cams(((0, 0.3, 0), (0.1, 0.7, -1)), ((0.02, 0.3, 0.01), (0.12, 0.7, -0.99)), 1.0, w, h)
    ivp = F.new("float[16]", cam.column_major("inv_view_proj_rot").tolist())
    pvp = F.new("float[16]", pcam.column_major("view_proj").tolist())
    eye, peye = tuple(cam.eye.tolist()), tuple(pcam.eye.tolist())
    layer = rm.CloudLayer()
    bufs = {n: rng.random(s, np.float32) for n, s in (("cur", (h, w, c)), ("dep", (h, w)), ("prev", (h, w, c)),
                                                      ("pdep", (h, w)), ("red", (2, 3, c)), ("out", (h, w, c)),
                                                      ("od", (h, w)))}

    def run(b, filt=1, its=3, size=(w, h, c), **ptr):
        p = {n: F.from_buffer("float[]", a) for n, a in b.items()}
        p.update(ptr)
        return L.ccl_reproj_frame_depth(p["cur"], p["dep"], p["prev"], p["pdep"], p["red"], *size, 5, ivp, eye, pvp,
                                        peye, layer.centre, layer.r_inner, 1, filt, its, 1, p["out"], p["od"])

    assert L.CCL_REPROJ_MAX_DEPTH_ITERATIONS == rp.MAX_DEPTH_ITERATIONS
    assert L.CCL_REPROJ_DEPTH_ITERATIONS == rp.DEPTH_ITERATIONS
    assert L.CCL_REPROJ_FILTER_BILINEAR == rp.FILTERS["bilinear"]
    assert L.CCL_REPROJ_FILTER_CATMULL_ROM == rp.FILTERS["catmull_rom"]
    before = {n: a.copy() for n, a in bufs.items()}
    for kw in ({"filt": 2}, {"filt": -1}, {"its": -1}, {"its": rp.MAX_DEPTH_ITERATIONS + 1}, {"size": (0, h, c)},
               {"pdep": F.NULL}, {"dep": F.NULL}):
        ptr = {k: v for k, v in kw.items() if k in ("pdep", "dep")}
        args = {k: v for k, v in kw.items() if k not in ptr}
        assert run(bufs, **args, **ptr) == L.CCL_EINVAL, kw
    for alias in (("out", "prev"), ("out", "pdep"), ("od", "pdep"), ("od", "prev"), ("od", "cur"), ("out", "dep"),
                  ("out", "od")):
        assert run(bufs, **{alias[0]: F.from_buffer("float[]", bufs[alias[1]])}) == L.CCL_EINVAL, alias
    for n, a in bufs.items():
        np.testing.assert_array_equal(a, before[n])
    assert run(bufs) == 0
    ref_out, ref_od = bufs["out"].copy(), bufs["od"].copy()
    b = {n: a.copy() for n, a in bufs.items()}
    b["out"], b["od"] = b["cur"], b["dep"]
    assert run(b) == 0
    np.testing.assert_array_equal(b["cur"], ref_out)
    np.testing.assert_array_equal(b["dep"], ref_od)


def test_settings_name_the_depth_modes_and_filters_of_the_kernels():
    """The settings module imports neither Warp nor the C library: its choices and its doc's iteration count are
    pinned to the kernels here."""
    from pywarp.clouds.settings import REPROJECTION_DEPTHS, REPROJECTION_FILTERS, CloudscapeSettings
    from pywarp.core.params import specs

    assert set(REPROJECTION_FILTERS) == set(rp.FILTERS)
    assert REPROJECTION_DEPTHS == ("clouds", "inner_sphere")
    doc = {p.name: p for p in specs(CloudscapeSettings)}["reprojection_depth"].doc
    assert f"{rp.DEPTH_ITERATIONS} fixed-point steps" in doc
    s = CloudscapeSettings()
    assert (s.reprojection_depth, s.reprojection_filter) == ("clouds", "catmull_rom")
