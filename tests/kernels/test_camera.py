"""The camera of vc-A25 and pt-code-7.2: look-at and perspective matrices against an independent float64 build and
the C function, primary rays against the pinhole model and against pt-code-7.2's own construction (forward, right,
up), C vs Warp agreement, bad input."""
from __future__ import annotations

import math

import numpy as np
import pytest

import pywarp
from pywarp.kernels import camera as cm

EPS32 = float(np.finfo(np.float32).eps)
IMPLS = ["warp", "c"]


def ordered_ulp(a, b) -> int:
    """Largest ulp distance between two float32 arrays; equal NaN patterns required; +0 and -0 are 0 apart."""
    a = np.asarray(a, dtype=np.float32).ravel()
    b = np.asarray(b, dtype=np.float32).ravel()
    assert np.array_equal(np.isnan(a), np.isnan(b)), "NaN patterns differ"
    m = ~np.isnan(a)

    def key(x):
        i = x.view(np.int32).astype(np.int64)
        return np.where(i < 0, -(i & 0x7FFFFFFF), i)

    return int(np.max(np.abs(key(a[m]) - key(b[m])))) if m.any() else 0


# --- vc-A25 / pt-code-7.2 camera -------------------------------------------------------------------------------------

def basis64(eye, target, up):
    f = np.asarray(target, float) - np.asarray(eye, float)
    f /= np.linalg.norm(f)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    return s, np.cross(s, f), f


@pytest.mark.spec("vc-A25", "pt-code-7.2")
def test_camera_matrices_match_independent_float64_and_c():
    eye, target, up, fov, aspect, zn, zf = (3.0, 0.5, 7.0), (2.0, 0.6, 6.0), (0.0, 1.0, 0.0), 1.1, 1.5, 0.01, 100.0
    cam = cm.camera_look_at(eye, target, up, fov, aspect, zn, zf)
    e = np.array(eye, np.float32).astype(float)
    s, u, f = basis64(e, np.array(target, np.float32), np.array(up))
    view = np.eye(4)
    view[0, :3], view[1, :3], view[2, :3] = s, u, -f
    view[:3, 3] = -view[:3, :3] @ e
    t = math.tan(float(np.float32(fov)) / 2)
    asp, n_, f_ = (float(np.float32(v)) for v in (aspect, zn, zf))
    proj = np.array([[1 / (asp * t), 0, 0, 0], [0, 1 / t, 0, 0],
                     [0, 0, (f_ + n_) / (n_ - f_), 2 * f_ * n_ / (n_ - f_)], [0, 0, -1, 0]])
    rot = view.copy()
    rot[:3, 3] = 0
    refs = {"view": view, "proj": proj, "view_proj": proj @ view, "inv_view_proj": np.linalg.inv(proj @ view),
            "inv_view_proj_rot": np.linalg.inv(proj @ rot)}
    c_cam = cm.c_camera_look_at(eye, target, up, fov, aspect, zn, zf)
    for name, ref in refs.items():
        got = getattr(cam, name).astype(np.float64)
        # both are float64 computations rounded once to float32: half an ulp of each entry (+ tiny absolute slack
        # for entries that are exactly zero in the reference and 1e-17 after np.linalg.inv)
        np.testing.assert_allclose(got, ref, rtol=EPS32, atol=1e-12 * np.abs(ref).max(), err_msg=name)
        # C and Python: the same float64 formulas rounded once; 1 ulp covers a double-rounding tie
        assert ordered_ulp(getattr(c_cam, name), getattr(cam, name)) <= 1, name
    np.testing.assert_array_equal(c_cam.eye, cam.eye)


def pinhole_dirs(eye, target, fov, aspect, x, y, w, h):
    """float64 pinhole model from the float32-rounded camera inputs: d = normalize(ndc_x a t s + ndc_y t u + f)."""
    s, u, f = basis64(np.array(eye, np.float32), np.array(target, np.float32), np.array([0.0, 1.0, 0.0]))
    t = math.tan(float(np.float32(fov)) / 2)
    ndc_x, ndc_y = 2 * (x + 0.5) / w - 1, 1 - 2 * (y + 0.5) / h
    ref = (ndc_x * float(np.float32(aspect)) * t)[:, None] * s + (ndc_y * t)[:, None] * u + f
    return ref / np.linalg.norm(ref, axis=1, keepdims=True)


@pytest.mark.spec("vc-A25", "pt-code-7.2")
@pytest.mark.parametrize("impl", IMPLS)
def test_camera_ray_matches_pinhole_model(impl, rng):
    w, h, fov = 64, 36, 1.2
    x, y = rng.integers(0, w, 500), rng.integers(0, h, 500)
    ray = pywarp.equation("vc-A25", impl=impl)
    # near the origin and 500 km away: the camera-relative inverse keeps the direction exact anywhere
    for eye, target in (((3.0, 0.5, 7.0), (2.0, 0.6, 6.0)), ((503.0, 500.5, 507.0), (502.0, 500.625, 506.0))):
        cam = cm.camera_look_at(eye, target, fov_y=fov, aspect=w / h)
        # float32 matrix entries and four roundings per component: a few eps of the unit vector
        np.testing.assert_allclose(ray(x, y, w, h, cam), pinhole_dirs(eye, target, fov, w / h, x, y, w, h),
                                   atol=8 * EPS32)
    # the centre pixel of an odd-size image looks at the target
    cam = cm.camera_look_at((1, 2, 3), (4, 2.5, -1), fov_y=0.7, aspect=1.0)
    f = np.array([3, 0.5, -4]) / np.linalg.norm([3, 0.5, -4])
    np.testing.assert_allclose(ray(5, 5, 11, 11, cam), f, atol=4 * EPS32)


@pytest.mark.spec("vc-A25", "pt-code-7.2")
def test_camera_rejects_bad_input():
    with pytest.raises(ValueError, match=r"^target must differ from eye"):
        cm.camera_look_at((0, 0, 0), (0, 0, 0))
    with pytest.raises(ValueError, match=r"^up must not be parallel"):
        cm.camera_look_at((0, 0, 0), (0, 2, 0))
    with pytest.raises(ValueError, match=r"^up must be a non-zero vector"):
        cm.camera_look_at((0, 0, 0), (0, 0, -1), up=(0, 0, 0))
    with pytest.raises(ValueError, match=r"^fov_y must be in \(0, pi\)"):
        cm.camera_look_at((0, 0, 0), (0, 0, -1), fov_y=3.2)
    with pytest.raises(ValueError, match=r"^aspect must be > 0"):
        cm.camera_look_at((0, 0, 0), (0, 0, -1), aspect=0)
    with pytest.raises(ValueError, match=r"^z_far must be > z_near"):
        cm.camera_look_at((0, 0, 0), (0, 0, -1), z_near=1.0, z_far=1.0)
    with pytest.raises(ValueError, match=r"^eye must be finite"):
        cm.camera_look_at((0, np.nan, 0), (0, 0, -1))
    with pytest.raises(ValueError, match=r"^eye must be a 3-vector"):
        cm.camera_look_at((0, 0), (0, 0, -1))
    with pytest.raises(ValueError, match=r"ccl_camera_look_at: invalid argument"):
        cm.c_camera_look_at((0, 0, 0), (0, 0, 0))
    cam = cm.camera_look_at((0, 0, 0), (0, 0, -1))
    for impl in IMPLS:
        ray = pywarp.equation("vc-A25", impl=impl)
        with pytest.raises(ValueError, match=r"^x must be in \[0, width - 1\]"):
            ray(10, 0, 10, 5, cam)
        with pytest.raises(ValueError, match=r"^width must be >= 1"):
            ray(0, 0, 0, 5, cam)
        with pytest.raises(ValueError, match=r"^y must be in \[0, inf\)"):
            ray(0, -1, 10, 5, cam)
        with pytest.raises(TypeError, match=r"^camera must be a pywarp.kernels.camera.Camera"):
            ray(0, 0, 10, 5, "camera")


def pt_code_7_2(position, target, x, y, w, h):
    """pt-code-7.2 verbatim in float64: forward = normalize(target - position), right = normalize(cross(forward,
    (0, 1, 0))), up = normalize(cross(right, forward)), rd = normalize(p.x right + p.y up + forward), with
    pt-code-7.1's p = (gl_FragCoord.xy / iResolution.xy) * 2 - 1, p.x *= aspect; gl_FragCoord = pixel centre with
    the origin at the bottom-left, so our row y (from the top) is row h - 1 - y."""
    position = np.asarray(position, np.float32).astype(float)
    forward = np.asarray(target, np.float32).astype(float) - position
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    up /= np.linalg.norm(up)
    px = ((x + 0.5) / w * 2.0 - 1.0) * (w / h)
    py = ((h - 1 - y) + 0.5) / h * 2.0 - 1.0
    rd = px[:, None] * right + py[:, None] * up + forward
    return rd / np.linalg.norm(rd, axis=1, keepdims=True)


@pytest.mark.spec("pt-code-7.2", "vc-A25")
@pytest.mark.parametrize("impl", IMPLS)
def test_camera_ray_is_the_pt_demo_camera(impl, rng):
    """pt-code-7.2's camera is camera_look_at with up = (0, 1, 0) and fov_y = pi/2 (image plane at distance 1,
    half-height 1): the same directions to float32 accuracy, at 4:3 and 16:9."""
    ray = pywarp.equation("pt-code-7.2", impl=impl)
    assert ray.equation is pywarp.equation("vc-A25").equation
    for (w, h), (pos, target) in (((64, 48), ((1.0, 2.0, 3.0), (4.0, 2.5, -1.0))),
                                  ((96, 54), ((0.0, 0.3, 0.0), (0.2, 0.1, -1.0)))):
        cam = cm.camera_look_at(pos, target, (0.0, 1.0, 0.0), fov_y=math.pi / 2, aspect=w / h)
        x, y = rng.integers(0, w, 400), rng.integers(0, h, 400)
        # float32 matrix entries and four roundings per component: a few eps of the unit vector
        np.testing.assert_allclose(ray(x, y, w, h, cam), pt_code_7_2(pos, target, x, y, w, h), atol=8 * EPS32)


@pytest.mark.spec("vc-A25")
def test_camera_ray_c_and_warp_agree(rng):
    """The same float32 operations in the same order (no contraction, correctly rounded sqrt): within 2 ulp (the
    camera is a struct argument, so the entry has its own evaluators and the comparison is written here)."""
    cam = cm.camera_look_at((3, 0.5, 7), (2, 0.6, 6), aspect=1.5)
    x, y = rng.integers(0, 300, 1500), rng.integers(0, 200, 1500)
    assert ordered_ulp(pywarp.camera_ray(x, y, 300, 200, cam),
                       pywarp.equation("vc-A25", impl="c")(x, y, 300, 200, cam)) <= 2
