"""The sky/ground edge is anti-aliased: with the sky lighting the background of a pixel the horizon crosses is the
haze and the lit ground mixed by the pixel's coverage by the Earth (analytic, a box filter) -- where before every
pixel was either ground or sky, a staircase along the (curved) horizon. Clouds are switched off (coverage 0) and so
is the haze (aerial_km 0), so that the edge is the full contrast of ground against sky, and both sides are flat
colours: the ground's (a flat albedo lit by one sun) and the sky's towards the horizon (the haze colour of every ray
below the horizontal). The covered fraction of each pixel is computed independently from the camera geometry in
float64."""
from __future__ import annotations

import math

import numpy as np
import pytest

from pywarp.clouds.cloudscape import CloudscapeSettings
from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.core.pose import Pose
from pywarp.kernels.camera import pose_camera

def horizon_rows(s: CloudscapeSettings, pose: Pose) -> np.ndarray:
    """Per column, the (fractional) image row where the horizon crosses, from the camera geometry in float64:
    the elevation of the horizon is -acos(R / (R + altitude)); the pixel rays of a pinhole camera pitched up."""
    cam = pose_camera(pose, s.width, s.height)
    inv = np.asarray(cam.inv_view_proj_rot, dtype=np.float64).reshape(4, 4)
    dip = math.acos(s.earth_radius_km / (s.earth_radius_km + pose.y))
    ys = np.linspace(0.0, s.height, 8 * s.height + 1)
    out = []
    for x in range(s.width):
        ndc_x = 2.0 * (x + 0.5) / s.width - 1.0
        ndc_y = 1.0 - 2.0 * ys / s.height
        pts = np.stack([np.full_like(ys, ndc_x), ndc_y, np.ones_like(ys), np.ones_like(ys)], axis=1) @ inv.T
        d = pts[:, :3] / pts[:, 3:4]
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        elev = np.arcsin(d[:, 1]) + dip
        out.append(np.interp(0.0, -elev, ys))  # elev decreases with the row
    return np.asarray(out)


def _linear(img):
    c = np.asarray(img, dtype=np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


@pytest.fixture(scope="module")
def frame():
    s = CloudscapeSettings(width=192, height=108, coverage=0.0, aerial_km=0.0, camera_pitch_deg=20.0,
                           camera_altitude_km=0.3, threads=2)
    t = CloudscapeTechnique(s)
    pose = Pose.from_settings(s)
    return s, pose, _linear(t.render(pose, reprojection=False))


def test_pixels_on_the_horizon_show_their_covered_fraction(frame):
    """Per column, the pixel the horizon crosses is sky + (ground - sky) x the fraction of the pixel below the
    horizon (sky and ground read 2 rows above / below), to within 8-bit rounding; an aliased edge gives 0 or 1 there,
    off by up to 0.5."""
    s, pose, lin = frame
    rows = horizon_rows(s, pose)
    err = []
    fractions = []
    for x in range(s.width):
        r = rows[x]
        y = int(math.floor(r))
        if r - y < 0.05 or r - y > 0.95:
            continue  # the horizon on a pixel boundary: no pixel to test in this column
        sky, ground, pix = lin[y - 2, x], lin[y + 2, x], lin[y, x]
        ch = int(np.argmax(np.abs(ground - sky)))
        assert abs(ground[ch] - sky[ch]) > 0.1  # a strong edge
        want = (y + 1) - r  # the part of row y below the horizon
        got = (pix[ch] - sky[ch]) / (ground[ch] - sky[ch])
        err.append(abs(got - want))
        fractions.append(want)
    assert len(err) > s.width // 2
    assert max(fractions) - min(fractions) > 0.2  # the horizon crosses the rows at different heights
    assert max(err) <= 0.03, (max(err), float(np.mean(err)))


def test_rows_next_to_the_horizon_are_plain_ground_and_sky(frame):
    """One row and more away from the horizon's pixel, every pixel of a column is the flat sky or ground colour (the
    filter reaches no further than the pixel the horizon crosses)."""
    s, pose, lin = frame
    rows = horizon_rows(s, pose)
    for x in range(0, s.width, 7):
        y = int(math.floor(rows[x]))
        assert np.abs(lin[y - 1, x] - lin[y - 3, x]).max() < 0.01
        assert np.abs(lin[y + 1, x] - lin[y + 3, x]).max() < 0.01
