"""Temporal reprojection vc-4.1, vc-A22, vc-A26, vc-A27: the 16-frame coverage contract, the reduced-buffer mapping,
the reprojection pass against float64 camera math written here, C vs Warp, the tile-parallel launch, bad input."""
from __future__ import annotations

import math

import numpy as np
import pytest
import warp as wp

import pywarp
from helpers import assert_twins_agree, look_at64

from pywarp.kernels import camera as cm
from pywarp.kernels import raymarch as rm
from pywarp.kernels import reproj as rp
from pywarp.core.runtime import TileLauncher

IMPLS = ["warp", "c"]
R_E, R_I = 6371.0, 6372.5


# --- vc-4.1 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-4.1")
@pytest.mark.parametrize("impl", IMPLS)
def test_reprojection_pixel_contract(impl):
    px = pywarp.equation("vc-4.1", impl=impl)
    f = np.arange(16)
    x, y = px(0, 0, f)
    assert x.dtype == np.int32 and y.dtype == np.int32
    # a = floor(f / 4) (x offset), b = f mod 4 (y offset): column by column (0,0), (0,1), (0,2), (0,3), (1,0), ...
    np.testing.assert_array_equal(x, f // 4)
    np.testing.assert_array_equal(y, f % 4)
    assert px(2, 3, 6) == (9, 14)
    # f wraps mod 16, negative frames too
    np.testing.assert_array_equal(px(5, 7, f + 16 * 11)[0], px(5, 7, f)[0])
    np.testing.assert_array_equal(px(5, 7, f - 32)[1], px(5, 7, f)[1])
    assert px(0, 0, -1) == (3, 3)


def coverage(width, height, first_frame, impl):
    gw, gh = rp.reproj_grid(width, height)
    ii, jj = np.meshgrid(np.arange(gw), np.arange(gh))
    count = np.zeros((height, width), int)
    px = pywarp.equation("vc-4.1", impl=impl)
    for f in range(first_frame, first_frame + 16):
        x, y = px(ii.ravel(), jj.ravel(), f)
        inside = (x < width) & (y < height)  # the bounds rule: threads outside the image are skipped
        np.add.at(count, (y[inside], x[inside]), 1)
    return count


@pytest.mark.spec("vc-4.1")
@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("size", [(16, 12), (10, 7), (1, 1), (5, 3), (33, 2)])
def test_reprojection_every_pixel_exactly_once_in_16_frames(impl, size):
    for first in (0, 37):
        assert np.all(coverage(*size, first, impl) == 1), (size, first)


@pytest.mark.spec("vc-4.1", "vc-A22")
def test_reproj_grid_is_ceil_quarter_and_rejects_bad_sizes():
    assert rp.reproj_grid(10, 7) == (3, 2)
    assert rp.reproj_grid(1920, 1080) == (480, 270)
    assert rp.reproj_grid(1, 1) == (1, 1)
    with pytest.raises(ValueError, match=r"^width must be >= 1, got 0"):
        rp.reproj_grid(0, 7)
    with pytest.raises(ValueError, match=r"^height must be >= 1, got -3"):
        rp.reproj_grid(10, -3)
    with pytest.raises(TypeError, match=r"^width must be an integer"):
        rp.reproj_grid(10.5, 7)


@pytest.mark.spec("vc-4.1")
@pytest.mark.parametrize("impl", IMPLS)
def test_reprojection_pixel_bad_input(impl):
    px = pywarp.equation("vc-4.1", impl=impl)
    with pytest.raises(ValueError, match=r"^id_x must be in \[0, 5.36871e\+08\], got -1"):
        px(-1, 0, 0)
    with pytest.raises(ValueError, match=r"^frame must hold integers"):
        px(0, 0, 1.5)
    # the pixel index 4 id + 3 must fit in int32
    assert px(0, (2**31 - 4) // 4, 15) == (3, 2**31 - 1)
    with pytest.raises(ValueError, match=r"^id_y must be in \[0, 5.36871e\+08\], got 536870912"):
        px(0, 2**29, 0)
    with pytest.raises(ValueError, match=r"^reproj_pixel\(\): the shapes of the array arguments do not broadcast"):
        px([0, 1], [0, 1, 2], 0)


# --- vc-A22 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A22", "vc-4.1")
@pytest.mark.parametrize("impl", IMPLS)
def test_reduced_coord_maps_rendered_pixels_to_their_texel(impl):
    rc = pywarp.equation("vc-A22", impl=impl)
    w, h = 10, 7
    gw, gh = rp.reproj_grid(w, h)
    ii, jj = (a.ravel() for a in np.meshgrid(np.arange(gw), np.arange(gh)))
    for f in range(16):
        x, y = pywarp.reproj_pixel(ii, jj, f)
        inside = (x < w) & (y < h)
        rx, ry = rc(x[inside], y[inside], f, w, h)
        np.testing.assert_array_equal(rx, ii[inside])  # the texel (x div 4, y div 4) the pixel writes
        np.testing.assert_array_equal(ry, jj[inside])
    # every pixel: ((x - a)/4, (y - b)/4) clamped to [0, floor((W - 1 - a)/4)] x [0, floor((H - 1 - b)/4)]
    xs, ys = (a.ravel() for a in np.meshgrid(np.arange(w), np.arange(h)))
    for f in range(16):
        a, b = f // 4, f % 4
        rx, ry = rc(xs, ys, f, w, h)
        np.testing.assert_array_equal(rx, np.clip((xs - a) / 4, 0, (w - 1 - a) // 4))
        np.testing.assert_array_equal(ry, np.clip((ys - b) / 4, 0, (h - 1 - b) // 4))
    # a frame 2 pixels wide renders no column when a >= 2: NaN
    rx, ry = rc(1, 0, 9, 2, 8)
    assert np.isnan(rx) and ry == 0.0
    with pytest.raises(ValueError, match=r"^x must be < width"):
        rc(10, 0, 0, 10, 7)
    with pytest.raises(ValueError, match=r"^x must be < width"):
        rc(0, 0, 0, 0, 7)
    with pytest.raises(ValueError, match=r"^y must be in \[0, inf\)"):
        rc(0, -1, 0, 4, 7)


# --- vc-A26 / vc-A27 helpers: float64 camera math written independently -----------------------------------------------


def expected_previous_pixel(cur, prev, fov, w, h):
    """float64: pixel centre ray of the current camera -> inner-sphere hit -> previous camera -> pixel coordinates
    (x_prev, y_prev) with pixel (i, j) centred at (i, j); NaN where not visible."""
    e, s, u, f = look_at64(*cur)
    ep, sp, up, fp = look_at64(*prev)
    t = math.tan(float(np.float32(fov)) / 2)
    a = float(np.float32(w / h))
    x, y = np.meshgrid(np.arange(w), np.arange(h))
    nx, ny = 2 * (x + 0.5) / w - 1, 1 - 2 * (y + 0.5) / h
    d = (nx * a * t)[..., None] * s + (ny * t)[..., None] * u + f
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    oc = e - np.array([0.0, -R_E, 0.0])
    b = d @ oc
    tt = -b + np.sqrt(b * b - (oc @ oc - R_I * R_I))  # camera inside the inner sphere: the far root
    p = e + tt[..., None] * d - ep
    zc = p @ fp  # depth along the previous view direction
    px = (p @ sp) / (zc * a * t)
    py = (p @ up) / (zc * t)
    up_, vp_ = px * 0.5 + 0.5, 0.5 - py * 0.5
    vis = (zc > 0) & (up_ >= 0) & (up_ <= 1) & (vp_ >= 0) & (vp_ <= 1)
    return np.where(vis, up_ * w - 0.5, np.nan), np.where(vis, vp_ * h - 0.5, np.nan)


def coordinate_frame(w, h):
    """A previous frame holding its own pixel coordinates: bilinear lookup returns the sample position exactly."""
    x, y = np.meshgrid(np.arange(w, dtype=np.float32), np.arange(h, dtype=np.float32))
    return np.stack([x, y], -1)


def updated_mask(w, h, frame):
    f = frame % 16
    x, y = np.meshgrid(np.arange(w), np.arange(h))
    return (x % 4 == f // 4) & (y % 4 == f % 4)


# --- vc-A26 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A26")
@pytest.mark.parametrize("impl", IMPLS)
def test_reproject_static_camera_returns_previous_frame_exactly(impl, rng):
    w, h = 48, 30
    cam = cm.camera_look_at((0.3, 0.002, -0.4), (0.8, 0.5, -1.2), fov_y=1.1, aspect=w / h)
    cur, prev = rng.random((h, w, 3), np.float32), rng.random((h, w, 3), np.float32)
    red = rng.random((8, 12, 3), np.float32)
    rep = pywarp.equation("vc-A26", impl=impl)
    for frame in (0, 7, 15, 100):
        out = rep(cur, prev, red, frame, cam, cam)
        upd = updated_mask(w, h, frame)
        np.testing.assert_array_equal(out[upd], cur[upd])
        np.testing.assert_array_equal(out[~upd], prev[~upd])


@pytest.mark.spec("vc-A26")
@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("motion", ["yaw", "pitch", "translate"])
def test_reproject_moving_camera_matches_float64_projection(impl, motion):
    """Content moves as the float64 projection written above predicts: a pure yaw by 1.5 deg shifts the centre by
    ~1.5 deg / (pixel angle); a translation shows the parallax of the inner-sphere points."""
    w, h, fov = 96, 54, 1.0
    eye = np.array([0.0, 0.002, 0.0])
    target = eye + np.array([0.0, 0.35, -1.0])
    cur = (eye, target)
    if motion == "yaw":
        c, s = math.cos(math.radians(1.5)), math.sin(math.radians(1.5))
        d = target - eye
        prev = (eye, eye + np.array([c * d[0] + s * d[2], d[1], -s * d[0] + c * d[2]]))
    elif motion == "pitch":
        prev = (eye, eye + np.array([0.0, 0.33, -1.0]))
    else:
        prev = (eye + np.array([0.8, 0.0, 0.5]), target + np.array([0.8, 0.0, 0.5]))
    cam = cm.camera_look_at(*cur, fov_y=fov, aspect=w / h)
    pcam = cm.camera_look_at(*prev, fov_y=fov, aspect=w / h)
    prev_img = coordinate_frame(w, h)
    cur_img = np.full((h, w, 2), -7.0, np.float32)
    red = np.full((14, 24, 2), -9.0, np.float32)
    out = pywarp.equation("vc-A26", impl=impl)(cur_img, prev_img, red, 3, cam, pcam)
    ex, ey = expected_previous_pixel(cur, prev, fov, w, h)
    upd = updated_mask(w, h, 3)
    vis = ~np.isnan(ex) & ~upd
    # away from the borders (within a pixel the lookup clamps, and visibility may flip by round-off)
    inner = vis & (ex > 1) & (ex < w - 2) & (ey > 1) & (ey < h - 2)
    assert inner.sum() > 0.5 * w * h
    # tolerance: the 1/256 px snap + float32 round-off of the reprojected position (< 1e-3 px at this size) + the
    # bilinear sum of coordinates up to 96 in float32 (~1e-5 px)
    np.testing.assert_allclose(out[inner, 0], ex[inner], atol=1 / 256 + 2e-3)
    np.testing.assert_allclose(out[inner, 1], ey[inner], atol=1 / 256 + 2e-3)
    # points not visible in the previous frame come from the reduced buffer
    hidden = np.isnan(ex) & ~upd
    if motion != "pitch":
        assert hidden.sum() > 0
    assert np.all(out[hidden] == -9.0)
    if motion == "yaw":
        # closed form near the image centre: the previous camera was turned left by 1.5 deg about the world y axis;
        # for a camera pitched up by phi that is a turn of 1.5 cos(phi) deg about its own up axis (plus a roll, which
        # does not move the centre), so the content sits fx tan(1.5 deg cos phi) pixels right of where it is now
        fx = (w / 2) / (math.tan(float(np.float32(fov)) / 2) * float(np.float32(w / h)))
        phi = math.atan2(0.35, 1.0)
        cy, cx = h // 2, w // 2 + 1  # pixel (49, 27): not rendered in frame 3, 1.5 px right of the centre
        shift = fx * math.tan(math.radians(1.5) * math.cos(phi))
        assert out[cy, cx, 0] - cx == pytest.approx(shift, rel=0.02)


@pytest.mark.spec("vc-A26", "vc-A22")
@pytest.mark.parametrize("impl", IMPLS)
def test_reproject_fallback_interpolates_reduced_buffer(impl):
    """history=False (first frame / camera cut) or nothing visible: bilinear lookup in the reduced buffer at the
    true positions of this frame's rendered pixels; a reduced buffer linear in its texel coordinates is reproduced
    exactly."""
    w, h, frame = 26, 15, 6  # (a, b) = (1, 2); 26 x 15 not divisible by 4
    gw, gh = rp.reproj_grid(w, h)
    ti, tj = np.meshgrid(np.arange(gw, dtype=np.float32), np.arange(gh, dtype=np.float32))
    red = np.stack([ti, tj], -1)
    cam = cm.camera_look_at((0, 0.002, 0), (0, 0.4, -1), aspect=w / h)
    away = cm.camera_look_at((0, 0.002, 0), (0, 0.4, 1), aspect=w / h)
    rng = np.random.default_rng(3)
    cur, prev = rng.random((h, w, 2), np.float32), rng.random((h, w, 2), np.float32)
    x, y = np.meshgrid(np.arange(w), np.arange(h))
    a, b = 1, 2
    ex = np.clip((x - a) / 4, 0, (w - 1 - a) // 4)
    ey = np.clip((y - b) / 4, 0, (h - 1 - b) // 4)
    upd = updated_mask(w, h, frame)
    rep = pywarp.equation("vc-A26", impl=impl)
    for kwargs, pcam in (({"history": False}, cam), ({}, away)):
        out = rep(cur, prev, red, frame, cam, pcam, **kwargs)
        np.testing.assert_allclose(out[~upd, 0], ex[~upd], atol=1e-6)
        np.testing.assert_allclose(out[~upd, 1], ey[~upd], atol=1e-6)
        np.testing.assert_array_equal(out[upd], cur[upd])
    # a 2-pixel-wide frame in a cycle frame that renders no column: keep previous (history) or current (no history)
    tiny_cur, tiny_prev = np.full((8, 2, 1), 1.0, np.float32), np.full((8, 2, 1), 2.0, np.float32)
    tiny_red = np.zeros((2, 1, 1), np.float32)
    tcam = cm.camera_look_at((0, 0.002, 0), (0, 0.4, -1), aspect=0.25)
    assert np.all(rep(tiny_cur, tiny_prev, tiny_red, 9, tcam, away) == 2.0)
    assert np.all(rep(tiny_cur, tiny_prev, tiny_red, 9, tcam, tcam, history=False) == 1.0)


# --- vc-A27 -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A27", "vc-A26")
@pytest.mark.parametrize("impl", IMPLS)
def test_reproject_neighbourhood_average_is_box_filter(impl, rng):
    w, h = 40, 24
    cam = cm.camera_look_at((0.1, 0.002, 0.2), (0.3, 0.5, -0.8), fov_y=0.9, aspect=w / h)
    cur = rng.random((h, w), np.float32)
    prev = rng.random((h, w), np.float32)
    red = rng.random((6, 10), np.float32)
    avg = pywarp.equation("vc-A27", impl=impl)
    assert avg.equation is pywarp.equation("vc-A26").equation  # one entry: vc-A27 is neighbourhood > 1
    out3 = avg(cur, prev, red, 5, cam, cam, neighbourhood=rp.AVERAGE_NEIGHBOURHOOD)  # the thesis's 3 x 3 (fig 4.14b)
    # static camera: the 3 x 3 box mean of previous with clamp-to-edge, computed with NumPy
    pad = np.pad(prev.astype(np.float64), 1, mode="edge")
    box = sum(pad[1 + j:1 + j + h, 1 + i:1 + i + w] for j in (-1, 0, 1) for i in (-1, 0, 1)) / 9
    upd = updated_mask(w, h, 5)
    np.testing.assert_allclose(out3[~upd], box[~upd], rtol=0, atol=1e-6)  # 9 float32 adds of values <= 1
    np.testing.assert_array_equal(out3[upd], cur[upd])
    # neighbourhood=1 is exact sampling (vc-A26), 5 a wider box
    np.testing.assert_array_equal(avg(cur, prev, red, 5, cam, cam, neighbourhood=1)[~upd], prev[~upd])
    pad2 = np.pad(prev.astype(np.float64), 2, mode="edge")
    box5 = sum(pad2[2 + j:2 + j + h, 2 + i:2 + i + w] for j in range(-2, 3) for i in range(-2, 3)) / 25
    np.testing.assert_allclose(avg(cur, prev, red, 5, cam, cam, neighbourhood=5)[~upd], box5[~upd], atol=2e-6)
    # averaging smooths: lower variance than exact sampling on white noise
    assert out3[~upd].var() < 0.3 * prev[~upd].var()


# --- C vs Warp, tiles -------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A26", "vc-A27", "vc-4.1", "vc-A22")
def test_reproject_c_and_warp_agree(rng):
    """The frame pass in C and Warp on random images and a moving camera: at most 2 ulp apart. Both evaluate the same
    float32 operations in the same order (no contraction, correctly rounded sqrt, the same floor/clamp decisions),
    so they agree exactly in practice (measured 0 ulp); reduced_coord and the pixel index must be equal."""
    w, h = 70, 45
    cam = cm.camera_look_at((0.2, 0.003, 0.1), (0.5, 0.4, -0.9), fov_y=1.2, aspect=w / h)
    pcam = cm.camera_look_at((0.25, 0.003, 0.05), (0.52, 0.41, -0.9), fov_y=1.2, aspect=w / h)
    cur, prev = rng.random((h, w, 4), np.float32), rng.random((h, w, 4), np.float32)
    red = rng.random((12, 18, 4), np.float32)
    for cid, kw in (("vc-A26", {}), ("vc-A27", {"neighbourhood": 3}), ("vc-A26", {"history": False}),
                    ("vc-A27", {"neighbourhood": 5})):
        for frame in (0, 9):
            a = pywarp.equation(cid)(cur, prev, red, frame, cam, pcam, **kw)
            b = pywarp.equation(cid, impl="c")(cur, prev, red, frame, cam, pcam, **kw)
            assert np.max(np.abs(a.view(np.int32).astype(np.int64) - b.view(np.int32).astype(np.int64))) <= 2
    x, y = rng.integers(0, w, 500), rng.integers(0, h, 500)
    f = rng.integers(-40, 40, 500)
    assert_twins_agree("vc-A22", x, y, f, w, h, ulp=0)  # exact: a clamp of (p - off) / 4
    assert_twins_agree("vc-4.1", x, y, f)


@pytest.mark.spec("vc-A26")
def test_reproject_kernel_tile_parallel_equals_single_band(rng):
    """The image kernel follows TileLauncher's row-band convention: any banding gives the same frame."""
    w, h = 37, 29
    cam = cm.camera_look_at((0, 0.002, 0), (0.2, 0.5, -1), aspect=w / h)
    pcam = cm.camera_look_at((0.3, 0.002, 0), (0.5, 0.5, -1), aspect=w / h)
    cur, prev = rng.random((h, w, 3), np.float32), rng.random((h, w, 3), np.float32)
    red = rng.random((8, 10, 3), np.float32)
    ref = pywarp.reproj_frame(cur, prev, red, 11, cam, pcam)
    layer = rm.CloudLayer()
    for workers in (1, 3):
        with TileLauncher(workers=workers, bands_per_worker=3) as tl:
            out = wp.empty((h, w, 3), dtype=float, device=tl.device)
            tl.launch(rp.reproject_frame_kernel, h, w,
                      inputs=[wp.array(cur, dtype=float), wp.array(prev, dtype=float), wp.array(red, dtype=float), 11,
                              cam.mat44("inv_view_proj_rot"), cam.eye_vec3(), pcam.mat44("view_proj"),
                              layer.centre_vec3(), layer.r_inner, 1, 1], outputs=[out])
            np.testing.assert_array_equal(out.numpy(), ref)


# --- bad input --------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A26", "vc-A27")
@pytest.mark.parametrize("impl", IMPLS)
def test_reproject_bad_input_raises_naming_parameter(impl):
    rep = pywarp.equation("vc-A26", impl=impl)
    cam = cm.camera_look_at((0, 0.002, 0), (0, 0.4, -1), aspect=2.0)
    cur = np.zeros((8, 16, 3), np.float32)
    red = np.zeros((2, 4, 3), np.float32)
    with pytest.raises(ValueError, match=r"^previous must have the shape of current"):
        rep(cur, cur[:, :8], red, 0, cam, cam)
    with pytest.raises(ValueError, match=r"^reduced must have shape \(ceil\(H/4\), ceil\(W/4\), channels\) = "
                                         r"\(2, 4, 3\)"):
        rep(cur, cur, red[:1], 0, cam, cam)
    with pytest.raises(ValueError, match=r"^current: frame size must be at least 1x1"):
        rep(np.zeros((0, 16, 3)), cur, red, 0, cam, cam)
    with pytest.raises(ValueError, match=r"^neighbourhood must be an odd integer in \[1, 31\], got 2"):
        rep(cur, cur, red, 0, cam, cam, neighbourhood=2)
    with pytest.raises(ValueError, match=r"^neighbourhood must be an odd integer in \[1, 31\], got 0"):
        pywarp.equation("vc-A27", impl=impl)(cur, cur, red, 0, cam, cam, neighbourhood=0)
    with pytest.raises(TypeError, match=r"^frame must be an integer"):
        rep(cur, cur, red, 1.5, cam, cam)
    with pytest.raises(TypeError, match=r"^prev_camera must be a pywarp.kernels.camera.Camera"):
        rep(cur, cur, red, 0, cam, None)
    with pytest.raises(TypeError, match=r"^layer must be a CloudLayer"):
        rep(cur, cur, red, 0, cam, cam, layer=6372.5)
    with pytest.raises(TypeError, match=r"^history must be True or False"):
        rep(cur, cur, red, 0, cam, cam, history=1)
    with pytest.raises(ValueError, match=r"^current must have shape"):
        rep(np.zeros(5), cur, red, 0, cam, cam)
