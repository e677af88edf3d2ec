"""The flight scene's clouds show no box (issue 28): the cloud arrays' falloff envelope (ccl_voxel_envelope) ends every
cloud inside its box, so in rendered frames nothing changes across the outline of a box's projection, while the text's
array without its zero border (oc-5.2.3, the border problem) is cut there. Also the envelope written out, and the
generated ground (ccl_volume_ground) of C and Warp."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pywarp.flight.settings import FlightSettings


def _set_densities(tech, densities):
    from pywarp.flight import volumes as V

    placed = tech.volumes.volumes
    tech.volumes = V.VolumeSet([V.PlacedVolume(d, v.origin, v.extent) for d, v in zip(densities, placed)],
                               device=tech.device)
    tech.volumes.compute_light(tech.settings.c_values())


def _jumps(a, mask):
    """Largest channel difference of ``a`` between 4-neighbours: (pairs across the edge of ``mask``, pairs inside)."""
    across, inside = [], []
    for ax in (0, 1):
        p, q = [slice(None)] * 2, [slice(None)] * 2
        p[ax], q[ax] = slice(0, -1), slice(1, None)
        jump = np.abs(a[tuple(p)] - a[tuple(q)]).max(-1)
        mp, mq = mask[tuple(p)], mask[tuple(q)]
        across.append(jump[mp != mq])
        inside.append(jump[mp & mq])
    return np.concatenate(across), np.concatenate(inside)


@pytest.fixture(scope="module")
def frames():
    """Cockpit frames (no aircraft in front of the boxes) of the default flight at 4 moments: the clouds with the
    scene's envelope, the same boxes without clouds, filled opaque (their projections) and holding the text's array
    without the zero border (cut by the box)."""
    from pywarp.flight.clouds import cloud_volume
    from pywarp.flight.technique import FlightPose, FlightTechnique

    # the plain clamp (no tone curve): the measure compares differences of frames, which a curve would rescale
    s = FlightSettings(width=240, height=135, cloud_count=6, cloud_size=32, tonemap="none", exposure_ev=0.0)
    tech = FlightTechnique(s)
    clouds = [v.density for v in tech.volumes.volumes]
    cut = [cloud_volume(dataclasses.replace(s.cloud_array(k), border="none", envelope=0.0))
           for k in range(len(clouds))]
    out = []
    for t in (0.0, 10.0, 17.0, 24.0):
        pose = FlightPose(t, "cockpit")
        img = {}
        for name, dens in (("clouds", clouds), ("empty", [np.zeros_like(d) for d in clouds]),
                           ("opaque", [np.full_like(d, 255) for d in clouds]), ("cut", cut)):
            _set_densities(tech, dens)
            img[name] = tech.render(pose).astype(np.int32)
        out.append(img)
    return out


@pytest.mark.spec("oc-5.2.3", "oc-5.2.3.2")
def test_no_box_face_shows_in_rendered_frames(frames):
    """What the clouds add to a frame (the frame minus the frame without clouds) is 0 outside the boxes' projections;
    across the outline of a projection it must change no more than between neighbouring pixels inside it -- else a
    box face shows as an edge. The text's array without its zero border fails the same measure (the test can fail)."""
    for img in frames:
        mask = np.abs(img["opaque"] - img["empty"]).max(-1) > 2  # the boxes' projections
        assert 100 < mask.sum() < mask.size
        across, inside = _jumps(img["clouds"] - img["empty"], mask)
        assert inside.max() > 0  # there are clouds in the boxes
        assert np.percentile(across, 99) <= np.percentile(inside, 90)
        assert across.mean() <= inside.mean()
        across_cut, inside_cut = _jumps(img["cut"] - img["empty"], mask)
        assert np.percentile(across_cut, 99) > np.percentile(inside_cut, 90)


@pytest.mark.spec("oc-5.2.1")
def test_the_scene_clouds_are_compact_inside_the_ellipsoid():
    """The scene's cloud arrays keep (almost) all of their cloud inside the ellipsoid inscribed in the box -- a
    rounded outline, not the box's -- fill about a third of the box and form one body; the text's array at the same
    cover and sharpness (envelope 0) fills most of its box and a good part of its corners."""
    from scipy import ndimage

    from pywarp.flight.clouds import cloud_volume

    s = FlightSettings()
    outside = _envelope_q(s.cloud_size, s.cloud_envelope_base) > 1.0
    for k in range(3):
        d = cloud_volume(s.cloud_array(k), impl="c") > 0
        assert d[outside].sum() < 0.08 * d.sum(), k
        assert 0.15 < d.mean() < 0.45, k
        labels, _ = ndimage.label(d)
        sizes = np.bincount(labels.ravel())[1:]
        assert sizes.max() > 0.9 * sizes.sum(), k
        plain = cloud_volume(dataclasses.replace(s.cloud_array(k), envelope=0.0), impl="c") > 0
        assert plain[outside].sum() > 0.2 * plain.sum() and plain.mean() > 0.5, k


def _envelope_q(n, base):
    """The squared radius of ccl_voxel_envelope written out in float64: [z, y, x]."""
    i = np.arange(n, dtype=np.float64)
    m = n - 1.0
    d = (2.0 * i - m) / m
    c = base / (1.0 + base)
    u = i / m
    dy = np.where(u >= c, (u - c) / (1.0 - c), (c - u) / c)
    return d[:, None, None] ** 2 + dy[None, :, None] ** 2 + d[None, None, :] ** 2


@pytest.mark.spec("oc-5.2.1")
@pytest.mark.parametrize("base", [0.35, 1.0])
def test_envelope_written_out_c_and_warp(base):
    from pywarp.flight.clouds import CloudArraySettings, noise_volume

    s = CloudArraySettings(size=32, seed=3, smoothing="none")
    plain = noise_volume(s).astype(np.float64)
    q = _envelope_q(32, base)
    assert q[16, int(round(31 * base / (1 + base))), 16] < 0.01 and q[0, 0, 0] == pytest.approx(3.0)
    ref = np.clip(plain - 0.2 * q, 0.0, 1.0)
    for impl in ("warp", "c"):
        env = noise_volume(s, impl=impl, envelope=0.2, envelope_base=base)
        np.testing.assert_allclose(env, ref, atol=2e-6)
    # lowered centre: at the same distance from it, the noise falls off faster below than above
    if base < 1.0:
        yc = 31 * base / (1 + base)
        assert q[16, int(yc - 6), 16] > q[16, int(yc + 7), 16]


@pytest.mark.spec("oc-5.2.1")
def test_envelope_settings_are_checked_and_c_defaults_match():
    from pywarp.core.binding import ffi, lib
    from pywarp.flight.clouds import CloudArraySettings, settings_struct

    with pytest.raises(ValueError, match="envelope"):
        CloudArraySettings(envelope=1.5)
    with pytest.raises(ValueError, match="envelope_base"):
        CloudArraySettings(envelope_base=0.0)
    c = lib().ccl_voxel_settings_default()
    s = CloudArraySettings()
    assert c.envelope == np.float32(s.envelope) == 0.0  # the text's array as printed by default
    assert c.envelope_base == np.float32(s.envelope_base)
    st = settings_struct(s)
    st.envelope_base = float("nan")
    field = ffi().new("const char **")
    assert lib().ccl_voxel_settings_check(st, field) != 0
    assert ffi().string(field[0]) == b"envelope_base"


def test_ground_c_and_warp_agree_and_is_not_a_checkerboard():
    """ccl_volume_ground and its Warp twin at scattered points (far ones and the wrap of the period included); the
    albedo varies smoothly within a noise cell (no constant fields with hard edges) and mixes meadow, forest and
    water."""
    import warp as wp

    from pywarp.core.binding import lib
    from pywarp.core.cbridge import VOLUME_PARAMS
    from pywarp.kernels import volume as VK

    values = FlightSettings().c_values()
    p = VK.checked_params(values)
    rng = np.random.default_rng(5)
    pts = np.concatenate([rng.uniform(-4000, 4000, (400, 2)), rng.uniform(-3e5, 3e5, (40, 2)),
                          [[23040.0, -23040.0], [1e30, -1e30]]]).astype(np.float32)
    c = np.array([[v.x, v.y, v.z] for v in (lib().ccl_volume_ground(p, float(x), float(z)) for x, z in pts)])

    @wp.kernel
    def ground_kernel(p: VK.VolumeParams, pts: wp.array(dtype=wp.vec2), out: wp.array(dtype=wp.vec3)):
        i = wp.tid()
        out[i] = VK.volume_ground(p, pts[i][0], pts[i][1])

    out = wp.zeros(len(pts), dtype=wp.vec3, device="cpu")
    wp.launch(ground_kernel, len(pts), [VOLUME_PARAMS.warp_struct(p), wp.array(pts, dtype=wp.vec2, device="cpu")],
              [out], device="cpu")
    np.testing.assert_allclose(out.numpy(), c, rtol=1e-5, atol=1e-6)
    assert np.all(np.isfinite(c)) and c.min() >= 0.0
    # along a line: many distinct values within one 180 m cell, small steps between 5 m neighbours
    line = np.array([[v.x, v.y, v.z] for v in (lib().ccl_volume_ground(p, float(x), 37.0)
                                                 for x in np.arange(0.0, 1800.0, 5.0))])
    assert len(np.unique(line[:36, 1])) > 20
    steps = np.abs(np.diff(line, axis=0)).max(-1)
    assert np.median(steps) < 0.01
    # forest (darker than either field colour) and river water occur over a few km
    grid = np.array([[lib().ccl_volume_ground(p, float(x), float(z)).y for x in np.arange(-4000, 4000, 40.0)]
                     for z in np.arange(-4000, 4000, 40.0)])
    ga = values["ground_a"][1]
    assert np.mean(grid < 0.6 * ga) > 0.05  # forest and water
    assert np.mean(grid > ga) > 0.2  # open fields

