"""The camera pose every scene shares: a position, a yaw and a pitch (the vc demo's free-look camera, the pt demo's
cameraPosition / cameraTarget) and the vertical field of view.

    from pywarp.core.pose import Pose
    pose = Pose(x=0.0, y=0.3, z=0.0, yaw_deg=0.0, pitch_deg=8.0)   # the position in the scene's unit (km, units)
    pose.forward()                      # (sin yaw cos pitch, sin pitch, -cos yaw cos pitch)
    cam = pose_camera(pose, 640, 360)   # pywarp.kernels.camera: the matrices; cam.to_c() is the ccl_camera

Yaw 0 looks along -z, a positive yaw turns towards +x; the pitch is up positive; y is up. A scene's settings hold the
pose in fields found by name (:func:`camera_fields`), so ``Pose.from_settings`` and the viewer's free-fly camera
(:class:`pywarp.viewer.controls.FreeFlyControls`) read every scene's camera the same way. The pose is plain numbers
(this module imports neither Warp nor the C library); the camera matrices of a pose are
:func:`pywarp.kernels.camera.pose_camera`'s.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from .params import specs

#: field-name prefixes of the camera's roles in a settings class (``camera_x_km`` and ``camera_x`` are both ``x``)
CAMERA_PREFIXES = {"x": ("camera_x",), "y": ("camera_y", "camera_altitude"), "z": ("camera_z",),
                   "yaw": ("camera_yaw",), "pitch": ("camera_pitch",)}


def camera_fields(settings_class) -> dict[str, str]:
    """The camera's float fields of a settings class by role (``x``, ``y``, ``z``, ``yaw``, ``pitch``): a field named
    after a prefix of :data:`CAMERA_PREFIXES` (exactly, or followed by ``_`` and its unit); roles without a field are
    absent."""
    return dict(_camera_fields(settings_class))


@functools.lru_cache(maxsize=None)
def _camera_fields(settings_class) -> tuple:
    names = [p.name for p in specs(settings_class) if p.kind == "float"]
    found = []
    for role, prefixes in CAMERA_PREFIXES.items():
        n = next((n for n in names if any(n == p or n.startswith(p + "_") for p in prefixes)), None)
        if n is not None:
            found.append((role, n))
    return tuple(found)


def forward(yaw_deg: float, pitch_deg: float) -> tuple[float, float, float]:
    """The unit view direction of a yaw and a pitch (deg; see the module docstring), float64."""
    y, p = math.radians(yaw_deg), math.radians(pitch_deg)
    return math.sin(y) * math.cos(p), math.sin(p), -math.cos(y) * math.cos(p)


@dataclass(frozen=True)
class Pose:
    """Camera position (the scene's unit; y up), yaw / pitch (deg), vertical field of view (deg) and a sub-pixel
    offset of the image (``jitter_px``: (dx, dy) pixels, TAA-style; the frames of an accumulated still)."""

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    yaw_deg: float = 0.0
    pitch_deg: float = 0.0
    fov_y_deg: float = 60.0
    jitter_px: tuple = (0.0, 0.0)

    @classmethod
    def from_settings(cls, s) -> "Pose":
        """The pose of a scene's settings: its camera fields (:func:`camera_fields`; a role without a field is 0)
        and ``fov_y_deg``."""
        f = dict(_camera_fields(type(s)))
        x, y, z, yaw, pitch = (getattr(s, f[r]) if r in f else 0.0 for r in ("x", "y", "z", "yaw", "pitch"))
        return cls(x, y, z, yaw, pitch, s.fov_y_deg)

    def eye(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z])

    def forward(self) -> np.ndarray:
        """The unit view direction (float64)."""
        return np.array(forward(self.yaw_deg, self.pitch_deg))

    def basis(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(right, up, forward) unit vectors (float64; world up (0, 1, 0))."""
        f = self.forward()
        r = np.cross(f, [0.0, 1.0, 0.0])
        r /= np.linalg.norm(r)
        return r, np.cross(r, f), f
