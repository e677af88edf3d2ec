"""The look-at + perspective camera and primary rays -- Warp twins of ``cclouds/camera.h``.

One camera for every scene: the cloudscape's (vc-A25) and the ray-marched terrain demo's (pt-code-7.2), which is the
same camera. The pt text builds ``forward = normalize(target - position)``, ``right = normalize(cross(forward,
(0, 1, 0)))``, ``up = normalize(cross(right, forward))`` and ``rd = normalize(p.x right + p.y up + forward)`` with
``p = (NDC x * aspect, NDC y)`` from ``gl_FragCoord`` (the pixel centre, origin at the bottom-left): that is
:func:`camera_look_at` with ``up = (0, 1, 0)`` and ``fov_y = pi/2`` (image plane at distance 1, half-height 1) and
:func:`camera_ray` with its rows counted from the top. Its one degenerate case (looking straight up or down, where
the cross product vanishes and GLSL gives NaN) is refused here with a ValueError.

Conventions (shared with the C header):
  * World frame y up; any length unit (the cloudscape uses km).
  * Matrices: ``wp.mat44`` / NumPy in mathematical (row, column) indexing; the C code stores the same matrices
    column-major. Right-handed look-at view (the camera looks down -z), OpenGL perspective (NDC z in [-1, 1]).
  * Pixel ``(x, y)``, ``y = 0`` the top row; uv = ((x + 0.5)/W, (y + 0.5)/H); NDC = (2u - 1, 1 - 2v).
  * :func:`camera_look_at` computes in float64 from the float32-rounded inputs and rounds once, as
    ``ccl_camera_look_at``; :func:`camera_ray` performs the float32 operations of ``ccl_camera_ray`` in order.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import warp as wp

from ..core.registry import Arg, declare

# --- validation helpers (also used by the other topic modules) --------------------------------------------------------


def _finite_float(value, name: str) -> float:
    if isinstance(value, (bool, str, bytes)) or value is None:
        raise TypeError(f"{name} must be a number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {v}")
    return v


def _vec3_value(value, name: str) -> np.ndarray:
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a 3-vector of numbers, got {value!r}") from None
    if a.shape != (3,):
        raise ValueError(f"{name} must be a 3-vector, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite, got {a.tolist()}")
    return a


def _check_size(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    if value < 1:
        raise ValueError(f"{name} must be >= 1, got {value}")
    return int(value)


# --- the camera (twin of ccl_camera / ccl_camera_look_at) -------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class Camera:
    """Camera matrices (float32, mathematical row/column layout, ``m[row, col]``), the twin of ``ccl_camera``; see
    :func:`camera_look_at`.

    ``mat44(name)`` gives a ``wp.mat44`` for kernels, ``column_major(name)`` the float[16] layout of the C code.
    """

    eye: np.ndarray
    view: np.ndarray
    proj: np.ndarray
    view_proj: np.ndarray
    inv_view_proj: np.ndarray
    inv_view_proj_rot: np.ndarray  # inverse of proj @ (view without translation): clip -> direction from the eye

    def mat44(self, name: str = "inv_view_proj") -> wp.mat44:
        return wp.mat44(*getattr(self, name).ravel().tolist())

    def column_major(self, name: str = "inv_view_proj") -> np.ndarray:
        return np.ascontiguousarray(getattr(self, name).T.ravel(), dtype=np.float32)

    def eye_vec3(self) -> wp.vec3:
        return wp.vec3(*self.eye.tolist())

    def to_c(self):
        """The same camera as a ``ccl_camera`` (cffi; the matrices column-major, as the C code reads them)."""
        from ..core.binding import ffi

        c = ffi().new("ccl_camera *")
        c.eye.x, c.eye.y, c.eye.z = (float(v) for v in self.eye)
        for name in ("view", "proj", "view_proj", "inv_view_proj", "inv_view_proj_rot"):
            arr = getattr(c, name)
            for i, v in enumerate(self.column_major(name)):
                arr[i] = float(v)
        return c

    def jittered(self, dx_px: float, dy_px: float, width: int, height: int) -> "Camera":
        """The same camera moved by a fraction of a pixel (TAA-style sub-pixel jitter): pixel (x, y) of a width x
        height image then looks through the point (x + 0.5 + dx_px, y + 0.5 + dy_px) of this camera's image plane
        (y down). The projection is translated in clip space by (tx, ty) = (-2 dx_px / width, +2 dy_px / height)
        (x_clip += tx w_clip: proj' = J proj, J = I + tx e_x e_w^T + ty e_y e_w^T), the inverses by J^-1; float64,
        rounded once. dx = dy = 0 returns the matrices unchanged, bit for bit."""
        width = _check_size(width, "width")
        height = _check_size(height, "height")
        tx = -2.0 * _finite_float(dx_px, "dx_px") / width
        ty = 2.0 * _finite_float(dy_px, "dy_px") / height
        j = np.eye(4)
        j[0, 3], j[1, 3] = tx, ty
        j_inv = np.eye(4)
        j_inv[0, 3], j_inv[1, 3] = -tx, -ty
        f32 = lambda m: np.ascontiguousarray(m, dtype=np.float32)  # noqa: E731
        d = lambda name: getattr(self, name).astype(np.float64)  # noqa: E731
        return Camera(eye=self.eye, view=self.view, proj=f32(j @ d("proj")), view_proj=f32(j @ d("view_proj")),
                      inv_view_proj=f32(d("inv_view_proj") @ j_inv),
                      inv_view_proj_rot=f32(d("inv_view_proj_rot") @ j_inv))


def pose_camera(pose, width: int, height: int, z_near: float = 0.01, z_far: float = 1000.0) -> Camera:
    """The camera of a :class:`pywarp.core.pose.Pose` for a width x height image (pt-code-7.2: cameraPosition and
    cameraTarget = position + forward, world up (0, 1, 0); the pose's vertical field of view), moved by its
    sub-pixel ``jitter_px`` (:meth:`Camera.jittered`) where that is not (0, 0)."""
    eye = pose.eye()
    cam = camera_look_at(eye, eye + pose.forward(), (0.0, 1.0, 0.0), math.radians(pose.fov_y_deg), width / height,
                         z_near, z_far)
    if pose.jitter_px != (0.0, 0.0):
        cam = cam.jittered(pose.jitter_px[0], pose.jitter_px[1], width, height)
    return cam


def _check_camera(camera, name: str = "camera") -> Camera:
    if not isinstance(camera, Camera):
        raise TypeError(f"{name} must be a pywarp.kernels.camera.Camera (see camera_look_at), got "
                        f"{type(camera).__name__}")
    return camera


def camera_look_at(eye, target, up=(0.0, 1.0, 0.0), fov_y: float = math.radians(60.0), aspect: float = 16.0 / 9.0,
                   z_near: float = 0.01, z_far: float = 1000.0) -> Camera:
    """vc-A25 / pt-code-7.2 camera: right-handed look-at view (GLM ``lookAt``) and OpenGL perspective (GLM
    ``perspective``). The pt demo's camera is ``up=(0, 1, 0)``, ``fov_y=pi/2``.

    ``fov_y`` vertical field of view in radians (0, pi); ``aspect`` = width / height; ``0 < z_near < z_far``.
    The inputs are rounded to float32 first (as the C function receives them), the matrices, their product and the
    closed-form inverses ``inv(view) inv(proj)`` (and the same with the eye moved to the origin, ``inv_view_proj_rot``,
    the matrix ray generation uses) are computed in float64 and rounded once: the twin of ``ccl_camera_look_at``.
    Raises ValueError naming the parameter.
    """
    e = _vec3_value(eye, "eye").astype(np.float32).astype(np.float64)
    tg = _vec3_value(target, "target").astype(np.float32).astype(np.float64)
    u_in = _vec3_value(up, "up").astype(np.float32).astype(np.float64)
    fov = float(np.float32(_finite_float(fov_y, "fov_y")))
    asp = float(np.float32(_finite_float(aspect, "aspect")))
    zn = float(np.float32(_finite_float(z_near, "z_near")))
    zf = float(np.float32(_finite_float(z_far, "z_far")))
    if not 0.0 < fov < float(np.float32(math.pi)):
        raise ValueError(f"fov_y must be in (0, pi) radians, got {fov_y}")
    if not asp > 0.0:
        raise ValueError(f"aspect must be > 0, got {aspect}")
    if not zn > 0.0:
        raise ValueError(f"z_near must be > 0, got {z_near}")
    if not zf > zn:
        raise ValueError(f"z_far must be > z_near ({z_near}), got {z_far}")
    f = tg - e
    n = math.sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2])
    if not n > 0.0:
        raise ValueError("target must differ from eye")
    f = f / n
    nu = math.sqrt(u_in[0] * u_in[0] + u_in[1] * u_in[1] + u_in[2] * u_in[2])
    if not nu > 0.0:
        raise ValueError("up must be a non-zero vector")
    s = np.array([f[1] * u_in[2] - f[2] * u_in[1], f[2] * u_in[0] - f[0] * u_in[2], f[0] * u_in[1] - f[1] * u_in[0]])
    t = math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2])
    if not t > 1e-6 * nu:
        raise ValueError("up must not be parallel to the view direction (target - eye)")
    s = s / t
    u = np.array([s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]])
    view = np.zeros((4, 4))
    inv_view = np.zeros((4, 4))
    view[0, :3], view[1, :3], view[2, :3] = s, u, -f
    inv_view[:3, 0], inv_view[:3, 1], inv_view[:3, 2] = s, u, -f
    view[0, 3] = -(s[0] * e[0] + s[1] * e[1] + s[2] * e[2])
    view[1, 3] = -(u[0] * e[0] + u[1] * e[1] + u[2] * e[2])
    view[2, 3] = f[0] * e[0] + f[1] * e[1] + f[2] * e[2]
    view[3, 3] = 1.0
    inv_view[:3, 3] = e
    inv_view[3, 3] = 1.0
    th = math.tan(0.5 * fov)
    proj = np.zeros((4, 4))
    inv_proj = np.zeros((4, 4))
    proj[0, 0] = 1.0 / (asp * th)
    proj[1, 1] = 1.0 / th
    proj[2, 2] = -(zf + zn) / (zf - zn)
    proj[2, 3] = -(2.0 * zf * zn) / (zf - zn)
    proj[3, 2] = -1.0
    inv_proj[0, 0] = asp * th
    inv_proj[1, 1] = th
    inv_proj[2, 3] = -1.0
    inv_proj[3, 2] = (zn - zf) / (2.0 * zf * zn)
    inv_proj[3, 3] = (zf + zn) / (2.0 * zf * zn)
    inv_view_rot = inv_view.copy()
    inv_view_rot[:3, 3] = 0.0
    mats = dict(view=view, proj=proj, view_proj=proj @ view, inv_view_proj=inv_view @ inv_proj,
                inv_view_proj_rot=inv_view_rot @ inv_proj)
    for name, m in mats.items():  # as ccl_camera_look_at: every entry within the float32 range (C9)
        if not np.all(np.abs(m) <= float(np.finfo(np.float32).max)):
            raise ValueError(f"eye, aspect, z_near and z_far must keep every camera matrix entry within the float32 "
                             f"range, got a {name} entry beyond it (|eye| {float(np.max(np.abs(e))):g}, aspect {asp:g}, "
                             f"z_near {zn:g}, z_far {zf:g})")
    f32 = lambda m: np.ascontiguousarray(m, dtype=np.float32)  # noqa: E731
    return Camera(eye=f32(e), **{name: f32(m) for name, m in mats.items()})


def c_camera_look_at(eye, target, up=(0.0, 1.0, 0.0), fov_y: float = math.radians(60.0), aspect: float = 16.0 / 9.0,
                     z_near: float = 0.01, z_far: float = 1000.0) -> Camera:
    """The same camera built by the C function ``ccl_camera_look_at`` (for checking the two against each other)."""
    from ..core.binding import ffi, lib, status_error

    cam = ffi().new("ccl_camera *")
    st = lib().ccl_camera_look_at(tuple(map(float, eye)), tuple(map(float, target)), tuple(map(float, up)),
                                  float(fov_y), float(aspect), float(z_near), float(z_far), cam)
    status_error(st, "ccl_camera_look_at")

    def m(name):
        return np.frombuffer(ffi().buffer(getattr(cam, name)), dtype=np.float32).reshape(4, 4).T.copy()

    return Camera(eye=np.array([cam.eye.x, cam.eye.y, cam.eye.z], np.float32), view=m("view"), proj=m("proj"),
                  view_proj=m("view_proj"), inv_view_proj=m("inv_view_proj"),
                  inv_view_proj_rot=m("inv_view_proj_rot"))


#: R2 sequence (Roberts 2018): the Kronecker lattice of the plastic number phi_2 (x^3 = x + 1), alpha = (1/phi_2,
#: 1/phi_2^2); the 2-D low-discrepancy sequence with the best-known packing for every prefix length
R2_PLASTIC = 1.32471795724474602596
R2_ALPHA = (1.0 / R2_PLASTIC, 1.0 / R2_PLASTIC ** 2)


def subpixel_jitter(n: int) -> np.ndarray:
    """The first ``n`` sub-pixel offsets (dx, dy) in [-0.5, 0.5)^2 (float64, (n, 2)) of the R2 low-discrepancy
    sequence with seed 0.5: (frac(0.5 + k alpha_1), frac(0.5 + k alpha_2)) - 0.5, k = 0 .. n-1. Offset 0 is the
    pixel centre (0, 0), so one sample is the unjittered image; every prefix covers the pixel evenly (a box filter
    over the pixel when averaged). For :meth:`Camera.jittered`."""
    n = _check_size(n, "n")
    k = np.arange(n, dtype=np.float64)[:, None]
    return np.mod(0.5 + k * np.array(R2_ALPHA), 1.0) - 0.5


# --- vc-A25 / pt-code-7.2: primary rays -------------------------------------------------------------------------------

def _camera_ray_args(x, y, width, height, camera):
    width = _check_size(width, "width")
    height = _check_size(height, "height")
    camera = _check_camera(camera)
    xa = Arg("x", lo=0, dtype="int32").check(x)
    ya = Arg("y", lo=0, dtype="int32").check(y)
    if np.any(xa >= width):
        raise ValueError(f"x must be in [0, width - 1] = [0, {width - 1}], got {xa[xa >= width].flat[0]}")
    if np.any(ya >= height):
        raise ValueError(f"y must be in [0, height - 1] = [0, {height - 1}], got {ya[ya >= height].flat[0]}")
    try:
        shape = np.broadcast_shapes(xa.shape, ya.shape)
    except ValueError:
        raise ValueError(f"camera_ray(): the shapes of x{xa.shape} and y{ya.shape} do not broadcast") from None
    return (np.ascontiguousarray(np.broadcast_to(xa, shape).ravel()),
            np.ascontiguousarray(np.broadcast_to(ya, shape).ravel()), shape, width, height, camera)


def _warp_camera_ray(eq, device):
    from ..core.runtime import resolve_device

    dev = resolve_device(device)

    def camera_ray(x, y, width, height, camera):
        """Unit view directions (..., 3) through pixel centres (x, y) of a width x height image (vc-A25)."""
        xs, ys, shape, width, height, camera = _camera_ray_args(x, y, width, height, camera)
        out = wp.empty(xs.size, dtype=wp.vec3, device=dev)
        if xs.size:
            wp.launch(_camera_ray_kernel, dim=xs.size, inputs=[wp.array(xs, dtype=wp.int32, device=dev),
                                                              wp.array(ys, dtype=wp.int32, device=dev), width, height,
                                                              camera.mat44("inv_view_proj_rot")],
                      outputs=[out], device=dev)
        return out.numpy().reshape(*shape, 3)

    return camera_ray


def _c_camera_ray(eq):
    from ..core.binding import ffi, lib

    def camera_ray(x, y, width, height, camera):
        """Unit view directions (..., 3) through pixel centres (x, y) of a width x height image (vc-A25), C."""
        xs, ys, shape, width, height, camera = _camera_ray_args(x, y, width, height, camera)
        m = ffi().new("float[16]", camera.column_major("inv_view_proj_rot").tolist())
        out = np.empty((xs.size, 3), np.float32)
        fn = lib().ccl_camera_ray
        for k in range(xs.size):
            d = fn(m, int(xs[k]), int(ys[k]), width, height)
            out[k] = (d.x, d.y, d.z)
        return out.reshape(*shape, 3)

    return camera_ray


# Not element-wise: the camera (four matrices of ccl_camera) is a struct argument, shared by every pixel.
@declare("vc-A25", "pt-code-7.2", c="ccl_camera_ray", make_warp=_warp_camera_ray, make_c=_c_camera_ray,
         summary="camera_ray(x, y, width, height, camera) -> unit directions (..., 3) through pixel centres: "
                 "uv = ((x+0.5)/W, (y+0.5)/H), NDC = (2u-1, 1-2v, 1), h = inverse view-projection of the camera "
                 "moved to the origin times (NDC, 1), d = normalize(h.xyz). camera from camera_look_at (GLM lookAt + "
                 "perspective, float32 matrices). pt-code-7.2 (the terrain demo's camera: forward = normalize(target "
                 "- position), right = normalize(forward x (0,1,0)), up = right x forward, rd = normalize(p.x right "
                 "+ p.y up + forward) with p = (NDC x * aspect, NDC y)) is this camera with up = (0, 1, 0) and "
                 "fov_y = pi/2; its gl_FragCoord rows count from the bottom, ours from the top.",
         references=("GLM lookAt / perspective (OpenGL conventions)",
                     "Procedural-texture demo (2016), Kod 7.1-7.2 (spec/pt.md pt-code-7.2)"))
@wp.func
def camera_ray(inv_view_proj_rot: wp.mat44, x: int, y: int, width: int, height: int) -> wp.vec3:
    """vc-A25: unit direction through the centre of pixel (x, y): uv -> NDC (z = 1) -> h = M (ndc, 1) with M the
    camera-relative inverse view-projection (``Camera.inv_view_proj_rot``) -> normalize(h.xyz)."""
    m = inv_view_proj_rot
    u = (float(x) + 0.5) / float(width)
    v = (float(y) + 0.5) / float(height)
    nx = 2.0 * u - 1.0
    ny = 1.0 - 2.0 * v
    hx = m[0][0] * nx + m[0][1] * ny + m[0][2] + m[0][3]
    hy = m[1][0] * nx + m[1][1] * ny + m[1][2] + m[1][3]
    hz = m[2][0] * nx + m[2][1] * ny + m[2][2] + m[2][3]
    return wp.normalize(wp.vec3(hx, hy, hz))


@wp.kernel
def _camera_ray_kernel(xs: wp.array(dtype=wp.int32), ys: wp.array(dtype=wp.int32), width: int, height: int,
                       inv_view_proj_rot: wp.mat44, out: wp.array(dtype=wp.vec3)):
    i = wp.tid()
    out[i] = camera_ray(inv_view_proj_rot, xs[i], ys[i], width, height)


__all__ = ["Camera", "camera_look_at", "c_camera_look_at", "camera_ray", "pose_camera", "subpixel_jitter"]
