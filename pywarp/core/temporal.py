"""Temporal reconstruction: a full-resolution picture while moving, from a fraction of its pixels per frame.

Every scene's viewer uses it (:class:`pywarp.viewer.session.RenderWorker`): while the view moves, a frame renders
1/f^2 of the window's pixels -- the scene at (width/f) x (height/f) with a sub-pixel camera offset, so that its pixel
(i, j) is exactly the window's pixel (f j + ox, f i + oy) -- and the phase (ox, oy) steps through the f x f pixels
of each block (Guerrilla's Nubis: 1/16 of the pixels per frame, Schneider 2015; checkerboard and TAA upsampling:
Karis 2014, Yang et al. 2020). :meth:`TemporalUpsampler.resolve` writes the window's picture:

* a pixel rendered this frame is that pixel of the full render (the same ray);
* any other pixel is the previous picture reprojected with the camera's motion (each window pixel's ray through the
  previous camera, as a point at infinity: exact for turning and for the distant cloudscape; where the camera
  translates near a surface the clamp below bounds the error), sampled bilinearly and clamped into the colour box of
  this frame's nearest fresh pixel and its four neighbours (Karis 2014's neighbourhood clamping on the fresh grid; the
  cross costs less than a 3 x 3 box and measured as good): history that disagrees with what the neighbourhood shows
  now -- a disocclusion, a moving object, changed lighting -- is pulled to it, so it cannot ghost -- and mixed with
  the interpolated fresh pixels (:data:`HISTORY_BLEND`);
* where the history falls outside the previous picture, or there is none, the fresh pixels interpolated bilinearly.

With the camera and the scene still, the clamp is off (the history is then exact) and after f^2 frames every pixel
has been rendered once: the picture is the full render. What a scene feeds the pass: its uint8 frame at the reduced
size rendered with the phase's ``jitter_px`` (:meth:`pywarp.core.technique.Technique.jitter`) and its camera
(:func:`pywarp.viewer.session.technique_camera`: the same matrices at any size of the same aspect). A scene may also feed
per-pixel depth (the distance along each fresh pixel's ray; the terrain's march does): each window pixel then takes
the depth of its nearest fresh pixel and its history from where that point was in the previous picture -- exact under
translation too (walking towards a hill), not only under turning.
"""
from __future__ import annotations

import numpy as np
import warp as wp

#: the share of the fresh pixels' bilinear interpolation mixed into the clamped history while anything changes:
#: 0.35 measured against 0 on the viewer's motion at 1/16 of the pixels (SSIM against the full render, clouds 0.868 ->
#: 0.889, flight 0.933 -> 0.955): the sparse cross lets the history flicker, the interpolation steadies it
HISTORY_BLEND = wp.constant(0.35)
#: with depth: the four fresh pixels around a window pixel whose depths are within this ratio of each other lie on
#: one smooth surface, and the pixel's depth is their bilinear interpolation (else the nearest one's: an edge).
#: 1.25: the ground seen at a grazing angle changes its depth by ~10-20 % per fresh pixel at 1/16 of the pixels;
#: a silhouette over a farther slope changes it by more
DEPTH_SMOOTH = wp.constant(1.25)
#: the reduction factors a reconstruction may use: 1/f^2 of the pixels are rendered per frame (f must divide both
#: sides); the viewer's own previews pick from the first three (:data:`VIEWER_FACTORS`), rain's background renders a
#: new direction at 8
FACTORS = (1, 2, 4, 8)
VIEWER_FACTORS = (1, 2, 4)


def phases(f: int) -> list[tuple[int, int]]:
    """The order in which the f x f pixels of a block are rendered: the ordered-dither (Bayer) order, so that any
    f^2/4 consecutive frames cover the block evenly (f = 2: (0,0), (1,1), (1,0), (0,1))."""
    if f == 1:
        return [(0, 0)]
    bayer = np.array([[0]])
    while bayer.shape[0] < f:
        n = bayer.shape[0]
        bayer = np.block([[4 * bayer, 4 * bayer + 2], [4 * bayer + 3, 4 * bayer + 1]])
        assert bayer.shape[0] == 2 * n
    order = sorted(((int(bayer[y, x]), x, y) for y in range(f) for x in range(f)))
    return [(x, y) for _, x, y in order]


def reprojection(camera, previous, width: int, height: int) -> np.ndarray:
    """The 3 x 3 homography (float64) that takes a window pixel (x, y, 1) of ``camera`` to the previous picture's
    pixel coordinates (homogeneous, the last component > 0 in front of the previous camera) of the same direction:
    the far-field reprojection. Pixel -> NDC (x + 0.5, y + 0.5 at the centre) -> direction through the camera's
    ``inv_view_proj_rot`` (vc-A25's ray, unnormalised) -> the previous ``view_proj`` (w = 0: a point at infinity)
    -> the previous pixel."""
    w, h = float(width), float(height)
    to_ndc = np.array([[2.0 / w, 0.0, 1.0 / w - 1.0], [0.0, -2.0 / h, 1.0 - 1.0 / h], [0.0, 0.0, 1.0]])
    m = np.asarray(camera.inv_view_proj_rot, np.float64)
    to_dir = np.column_stack([m[:3, 0], m[:3, 1], m[:3, 2] + m[:3, 3]])
    to_clip = np.asarray(previous.view_proj, np.float64)[[0, 1, 3]][:, :3]
    to_px = np.array([[w / 2.0, 0.0, w / 2.0 - 0.5], [0.0, -h / 2.0, h / 2.0 - 0.5], [0.0, 0.0, 1.0]])
    return to_px @ to_clip @ to_dir @ to_ndc


def _mat44(m) -> wp.mat44:
    return wp.mat44(*np.asarray(m, np.float32).ravel().tolist())


def factor_for(width: int, height: int, wanted: int) -> int:
    """The largest factor of :data:`FACTORS` up to ``wanted`` that divides both sides (1 always does)."""
    return max(f for f in FACTORS if f <= wanted and width % f == 0 and height % f == 0)


@wp.func
def depth_reprojection(x: int, y: int, t: float, width: int, height: int, inv_view_proj_rot: wp.mat44,
                       eye: wp.vec3, prev_view_proj: wp.mat44) -> wp.vec3:
    """The previous picture's pixel (homogeneous: (x w, y w, w), w > 0 in front of the previous camera) of the point
    at distance ``t`` along window pixel (x, y)'s unit ray (vc-A25's ray through ``inv_view_proj_rot`` from ``eye``):
    the reprojection with depth, exact under translation too."""
    nx = 2.0 * (float(x) + 0.5) / float(width) - 1.0
    ny = 1.0 - 2.0 * (float(y) + 0.5) / float(height)
    m = inv_view_proj_rot
    d = wp.normalize(wp.vec3(m[0][0] * nx + m[0][1] * ny + m[0][2] + m[0][3],
                             m[1][0] * nx + m[1][1] * ny + m[1][2] + m[1][3],
                             m[2][0] * nx + m[2][1] * ny + m[2][2] + m[2][3]))
    c = prev_view_proj * wp.vec4(eye[0] + d[0] * t, eye[1] + d[1] * t, eye[2] + d[2] * t, 1.0)
    w = float(width)
    h = float(height)
    return wp.vec3(c[0] * w * 0.5 + c[3] * (w * 0.5 - 0.5), -c[1] * h * 0.5 + c[3] * (h * 0.5 - 0.5), c[3])


@wp.func
def resolve_pixel(fresh: wp.array(dtype=wp.vec3, ndim=2), hist: wp.array(dtype=wp.vec3, ndim=2), f: int, ox: int,
                  oy: int, has_hist: int, clamp: int, g: wp.mat33, width: int, height: int, x: int,
                  y: int) -> wp.vec3:
    """One pixel of the window's picture (see the module docstring), the far-field reprojection."""
    return resolve_pixel_depth(fresh, hist, f, ox, oy, has_hist, clamp, g, width, height, x, y, fresh, 0,
                               wp.identity(n=4, dtype=float), wp.vec3(0.0, 0.0, 0.0), wp.identity(n=4, dtype=float))


@wp.func
def resolve_pixel_depth(fresh: wp.array(dtype=wp.vec3, ndim=2), hist: wp.array(dtype=wp.vec3, ndim=2), f: int,
                        ox: int, oy: int, has_hist: int, clamp: int, g: wp.mat33, width: int, height: int, x: int,
                        y: int, depth: wp.array(dtype=wp.vec3, ndim=2), has_depth: int, inv_view_proj_rot: wp.mat44,
                        eye: wp.vec3, prev_view_proj: wp.mat44) -> wp.vec3:
    """One pixel of the window's picture (see the module docstring); with ``has_depth`` the history is found
    through the depth of the nearest fresh pixel (``depth[j, i][0]``, distance along the ray; < 0: far field)."""
    lh = fresh.shape[0]
    lw = fresh.shape[1]
    dx = x - ox
    dy = y - oy
    if dx >= 0 and dy >= 0 and dx % f == 0 and dy % f == 0:
        return fresh[dy // f, dx // f]
    # this pixel in the fresh grid: bilinear weights, and the nearest fresh pixel (the centre of the clamp's cross)
    u = wp.clamp(float(dx) / float(f), 0.0, float(lw - 1))
    v = wp.clamp(float(dy) / float(f), 0.0, float(lh - 1))
    i0 = wp.min(int(u), lw - 1)
    j0 = wp.min(int(v), lh - 1)
    i1 = wp.min(i0 + 1, lw - 1)
    j1 = wp.min(j0 + 1, lh - 1)
    a = u - float(i0)
    b = v - float(j0)
    spatial = (fresh[j0, i0] * (1.0 - a) + fresh[j0, i1] * a) * (1.0 - b) + (fresh[j1, i0] * (1.0 - a)
                                                                               + fresh[j1, i1] * a) * b
    if has_hist == 0:
        return spatial
    q = g * wp.vec3(float(x), float(y), 1.0)
    if has_depth != 0:
        # the depth of the nearest fresh pixel; on a smooth surface (the four around within DEPTH_SMOOTH of each
        # other) their bilinear interpolation, which follows a plane's depth between the fresh pixels
        t = depth[wp.min(int(v + 0.5), lh - 1), wp.min(int(u + 0.5), lw - 1)][0]
        t00 = depth[j0, i0][0]
        t10 = depth[j0, i1][0]
        t01 = depth[j1, i0][0]
        t11 = depth[j1, i1][0]
        tlo = wp.min(wp.min(t00, t10), wp.min(t01, t11))
        thi = wp.max(wp.max(t00, t10), wp.max(t01, t11))
        if tlo > 0.0 and thi <= tlo * DEPTH_SMOOTH:
            t = (t00 * (1.0 - a) + t10 * a) * (1.0 - b) + (t01 * (1.0 - a) + t11 * a) * b
        if t > 0.0:
            q = depth_reprojection(x, y, t, width, height, inv_view_proj_rot, eye, prev_view_proj)
    if q[2] <= 0.0:  # the point was behind the previous camera
        return spatial
    px = q[0] / q[2]
    py = q[1] / q[2]
    if px < -0.5 or py < -0.5 or px > float(width) - 0.5 or py > float(height) - 0.5:  # off the previous picture
        return spatial
    px = wp.clamp(px, 0.0, float(width - 1))
    py = wp.clamp(py, 0.0, float(height - 1))
    x0 = wp.min(int(px), width - 2)
    y0 = wp.min(int(py), height - 2)
    x0 = wp.max(x0, 0)
    y0 = wp.max(y0, 0)
    ta = wp.clamp(px - float(x0), 0.0, 1.0)
    tb = wp.clamp(py - float(y0), 0.0, 1.0)
    h = (hist[y0, x0] * (1.0 - ta) + hist[y0, x0 + 1] * ta) * (1.0 - tb) + (hist[y0 + 1, x0] * (1.0 - ta)
                                                                          + hist[y0 + 1, x0 + 1] * ta) * tb
    if clamp != 0:
        ci = wp.min(int(u + 0.5), lw - 1)
        cj = wp.min(int(v + 0.5), lh - 1)
        xa = wp.max(ci - 1, 0)
        xb = wp.min(ci + 1, lw - 1)
        ya = wp.max(cj - 1, 0)
        yb = wp.min(cj + 1, lh - 1)
        s1 = fresh[ya, ci]
        s3 = fresh[cj, xa]
        s4 = fresh[cj, ci]
        s5 = fresh[cj, xb]
        s7 = fresh[yb, ci]
        lo = wp.min(wp.min(wp.min(s1, s3), wp.min(s4, s5)), s7)
        hi = wp.max(wp.max(wp.max(s1, s3), wp.max(s4, s5)), s7)
        h = wp.min(wp.max(h, lo), hi)
        h = h + (spatial - h) * HISTORY_BLEND
    return h


@wp.kernel
def resolve_kernel(row0: int, fresh: wp.array(dtype=wp.vec3, ndim=2), hist: wp.array(dtype=wp.vec3, ndim=2),
                   f: int, ox: int, oy: int, has_hist: int, clamp: int, g: wp.mat33, width: int, height: int,
                   depth: wp.array(dtype=wp.vec3, ndim=2), has_depth: int, inv_view_proj_rot: wp.mat44,
                   eye: wp.vec3, prev_view_proj: wp.mat44,
                   out: wp.array(dtype=wp.vec3, ndim=2),
                   shown: wp.array(dtype=wp.uint8, ndim=3)):
    i, x = wp.tid()
    y = row0 + i
    c = resolve_pixel_depth(fresh, hist, f, ox, oy, has_hist, clamp, g, width, height, x, y, depth, has_depth,
                            inv_view_proj_rot, eye, prev_view_proj)
    out[y, x] = c
    for k in range(3):
        shown[y, x, k] = wp.uint8(int(wp.clamp(c[k], 0.0, 255.0) + 0.5))


class TemporalUpsampler:
    """The reconstruction of one viewer (see the module docstring): ``plan`` says what the next frame renders,
    ``resolve`` turns that render into the window's picture and keeps it as the next frame's history.

    ``width`` x ``height`` the window's picture; ``factor`` the wanted reduction (:func:`factor_for` picks the
    largest that divides both sides)."""

    def __init__(self, launcher, width: int, height: int, factor: int = 2):
        self.launcher = launcher
        self.device = launcher.device
        self.width, self.height = int(width), int(height)
        self.set_factor(factor)
        self.count = 0
        self._hist = wp.zeros((self.height, self.width), dtype=wp.vec3, device=self.device)
        self._out = wp.zeros((self.height, self.width), dtype=wp.vec3, device=self.device)
        self._shown = wp.zeros((self.height, self.width, 3), dtype=wp.uint8, device=self.device)
        self._prev_cam = None
        self._prev_key = None

    def set_factor(self, factor: int) -> None:
        self.factor = factor_for(self.width, self.height, int(factor))
        self._phases = phases(self.factor)

    def reset(self) -> None:
        """Forget the history (the next frame is interpolated from its own pixels)."""
        self._prev_cam = None
        self._prev_key = None

    def remember(self, image: np.ndarray, camera, key=None) -> None:
        """Take a full-resolution picture (uint8, e.g. the viewer's refined frame) as the history."""
        if image.shape[:2] != (self.height, self.width):
            raise ValueError(f"image must be {self.width}x{self.height}, got {image.shape[1]}x{image.shape[0]}")
        self._hist = wp.array(np.ascontiguousarray(image[..., :3], dtype=np.float32), dtype=wp.vec3,
                              device=self.device)
        self._prev_cam = camera
        self._prev_key = key

    def plan(self) -> tuple[int, int, tuple[float, float]]:
        """(width, height, jitter_px) of the next frame's render: the reduced size and the sub-pixel offset (in the
        reduced image's pixels) that puts its pixel (i, j) on the window's pixel (f i + ox, f j + oy)."""
        f = self.factor
        ox, oy = self._phases[self.count % len(self._phases)]
        return self.width // f, self.height // f, ((ox + 0.5) / f - 0.5, (oy + 0.5) / f - 0.5)

    def resolve(self, fresh: np.ndarray, camera, key=None, depth: np.ndarray | None = None,
                clamp: bool | None = None) -> np.ndarray:
        """The window's picture (uint8, height x width x 3) from ``fresh`` (the planned render, uint8) and the
        frame's ``camera`` (:class:`pywarp.kernels.camera.Camera` without the jitter, any size of this aspect).
        ``key``: what the picture depends on besides the camera (the scene's settings other than its size); the
        clamp is off while the key and the camera stay the same. ``depth``: optional, ``fresh``'s size, each pixel's
        distance along its (jittered) unit ray from the camera's eye to the surface it shows (< 0 or not finite:
        far, e.g. the sky); with it the history is reprojected through the nearest fresh pixel's depth, exact under
        translation as well as turning (without it: the far-field homography). ``clamp=False``: off whatever moves --
        for a picture that is a function of the view direction only (a background seen from its own place, as
        rain's), where the far-field reprojection is exact and the clamp would only blur the history."""
        f = self.factor
        ox, oy = self._phases[self.count % len(self._phases)]
        lw, lh = self.width // f, self.height // f
        if fresh.shape[:2] != (lh, lw):
            raise ValueError(f"fresh must be {lw}x{lh} (the planned size), got {fresh.shape[1]}x{fresh.shape[0]}")
        src = wp.array(np.ascontiguousarray(fresh[..., :3], dtype=np.float32), dtype=wp.vec3, device=self.device)
        has_hist = self._prev_cam is not None
        still = has_hist and key == self._prev_key and all(
            np.array_equal(getattr(camera, n), getattr(self._prev_cam, n)) for n in ("view_proj", "inv_view_proj"))
        prev = self._prev_cam if has_hist else camera
        g = reprojection(camera, prev, self.width, self.height)
        if depth is not None:
            depth = np.asarray(depth, np.float32)
            if depth.shape != (lh, lw):
                raise ValueError(f"depth must be {lw}x{lh} (the planned size), got "
                                 f"{'x'.join(str(n) for n in depth.shape[::-1])}")
            d = np.where(np.isfinite(depth), depth, -1.0).astype(np.float32)
            dep = wp.array(np.repeat(d[..., None], 3, axis=2), dtype=wp.vec3, device=self.device)
        else:
            dep = src
        self.launcher.launch(resolve_kernel, self.height, self.width,
                             [src, self._hist, f, ox, oy, int(has_hist),
                              int(not still if clamp is None else clamp),
                              wp.mat33(*g.astype(np.float32).ravel().tolist()), self.width, self.height,
                              dep, int(depth is not None), _mat44(camera.inv_view_proj_rot),
                              wp.vec3(*np.asarray(camera.eye, np.float32).tolist()), _mat44(prev.view_proj)],
                             [self._out, self._shown])
        self._hist, self._out = self._out, self._hist
        self._prev_cam, self._prev_key = camera, key
        self.count += 1
        return self._shown.numpy().copy()
