"""Differential property test of the flight scene's cloud volumes (cclouds/volume.h, pywarp.kernels.volume):
parameter sets and boxes drawn at the edges of their domains and beyond them.

* The parameters' check of the Warp side (:func:`pywarp.kernels.volume.checked_params`: the values written to the C
  struct by :mod:`pywarp.core.cbridge` and checked by ``ccl_volume_check``) and the box check of
  :class:`PlacedVolume` refuse exactly the sets that ``ccl_volume_check`` refuses with a grid (finding 11 was a bound
  both lacked).
* An accepted set gives light volumes in [0, 1] and finite pixels, the Warp kernels and the C reference alike and
  equal within the tolerance of ``tests/hardening/test_fuzz_findings.py`` (relative 1e-5, since colours reach 10^6).

Deterministic (``derandomize=True``, no example database); ``PYWARP_DIFF_EXAMPLES`` sets another number of examples
for a longer search (default 100)."""
from __future__ import annotations

import math
import numpy as np
import pytest
from helpers import differential_settings

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from pywarp.core.binding import ffi, lib  # noqa: E402
from pywarp.core.cbridge import VOLUME_PARAMS  # noqa: E402
from pywarp.kernels import camera as CAM  # noqa: E402
from pywarp.flight import model as F  # noqa: E402
from pywarp.kernels import volume as V  # noqa: E402
from pywarp.flight import volumes as VS  # noqa: E402

SETTINGS = differential_settings(100)
F32_MAX = float(np.finfo(np.float32).max)

#: scalar fields, each at and beyond its edges (the refusals must agree) and at typical values
SCALARS = {
    "sun_glow": [0.0, 0.6, 1e6, 1.1e6, -1.0],
    "sun_glow_power": [1e-6, 64.0, 1e30, 0.0],
    "field_size": [1e-3, 180.0, 1e30, 0.0],
    "fog_distance": [1e-3, 6000.0, 1e30, 0.0],
    "tau_per_voxel": [0.0, 0.35, 1e6, 1.5e6, F32_MAX, -1e-6],
    "light_tau_per_voxel": [0.0, 0.25, 1e6, 1.6e32],
    "step_voxels": [0.05, 1.0, 1e6, 8.4e6, 0.04],
    "light_step_voxels": [0.05, 1.0, 1e6, 8.4e6, 0.0],
    "exit_transmittance": [0.0, 0.01, 0.999, 1.0],
    "max_steps": [1, 512, 100000, 0, 100001],
    "g": [-0.999, 0.0, 0.3, 0.999, 1.0],
}
COLOURS = {
    "sun_colour": [(1.0, 0.96, 0.88), (1e6, 1e6, 1e6), (0.0, 0.0, 0.0), (2e6, 0.0, 0.0)],
    "ambient_top": [(0.42, 0.47, 0.56), (1e6, 0.0, 1e6), (-0.1, 0.0, 0.0)],
    "sky_horizon": [(0.62, 0.72, 0.85), (0.0, 0.0, 1e6)],
}
EXTENTS = [(80.0, 60.0, 80.0), (1e-6, 1e-6, 1e-6), (1e6, 1e6, 1e6), (1e-6, 1e6, 1.0), (1e-7, 1.0, 1.0),
           (1.0, 2e6, 1.0)]


def _grid(v: VS.PlacedVolume, light: np.ndarray):
    f = ffi()
    d = v.density
    skip = np.zeros(d.size, np.uint8)
    bd, bl, bs = f.from_buffer("unsigned char[]", d), f.from_buffer("float[]", light), f.from_buffer(
        "unsigned char[]", skip)
    g = f.new("ccl_volume_grid *")
    g.density, g.light, g.skip = (f.cast(t, b) for t, b in (("const unsigned char *", bd), ("const float *", bl),
                                                            ("const unsigned char *", bs)))
    g.nz, g.ny, g.nx = d.shape
    g.origin.x, g.origin.y, g.origin.z = v.origin
    g.extent.x, g.extent.y, g.extent.z = v.extent
    return g, (light, skip, bd, bl, bs)


def _c_refuses(values: dict, v: VS.PlacedVolume) -> str | None:
    g, keep = _grid(v, np.ones(v.density.shape, np.float32))
    out = ffi().new("const char **")
    st_ = lib().ccl_volume_check(VOLUME_PARAMS.to_c(values), g, 1, out)
    del keep
    return ffi().string(out[0]).decode() if st_ != 0 else None


def _python_refuses(values: dict, extent) -> tuple[bool, bool]:
    """(the parameters refused, the extent refused) by the Python validation."""
    try:
        V.checked_params(values)
        params = False
    except ValueError:
        params = True
    try:
        VS.PlacedVolume(DENSITY, (-40.0, 80.0, -300.0), extent)
        box = False
    except ValueError:
        box = True
    return params, box


#: a small cloud with empty voxels beside dense ones (the density of 0 that met Inf in finding 11)
DENSITY = np.zeros((4, 5, 6), np.uint8)
DENSITY[1:3, 1:4, 2:5] = 255
DENSITY[2, 2, 1] = 90


@SETTINGS
@given(scalars=st.lists(st.sampled_from(sorted(SCALARS)), max_size=4, unique=True).flatmap(
           lambda ks: st.fixed_dictionaries({k: st.sampled_from(SCALARS[k]) for k in ks})),
       colours=st.lists(st.sampled_from(sorted(COLOURS)), max_size=2, unique=True).flatmap(
           lambda ks: st.fixed_dictionaries({k: st.sampled_from(COLOURS[k]) for k in ks})),
       extent=st.sampled_from(EXTENTS), aircraft=st.booleans(), seed=st.integers(0, 2 ** 16))
def test_python_and_c_refuse_alike_and_accepted_sets_render_finite_and_equal(scalars, colours, extent, aircraft,
                                                                             seed):
    values = {**VOLUME_PARAMS.defaults(), **scalars, **colours}
    if aircraft:
        fw, rt, up = F.axes(0.3, 0.09, 0.35)
        values.update(aircraft=1, aircraft_position=(0.0, 100.0, -60.0), aircraft_forward=fw, aircraft_right=rt,
                      aircraft_up=up)
    # the parameters with a box both accept, and the box with the default parameters: each refused alike (which
    # field a check names first when several are bad depends on its order, which the two need not share)
    py_params, py_box = _python_refuses(values, extent)
    ok_box = VS.PlacedVolume(DENSITY, (-40.0, 80.0, -300.0), (80.0, 60.0, 80.0))
    box = VS.PlacedVolume(DENSITY, (-40.0, 80.0, -300.0), (80.0, 60.0, 80.0))
    box.extent = tuple(float(e) for e in extent)  # (the C check must see the extent itself)
    c_params, c_box = _c_refuses(values, ok_box), _c_refuses(VOLUME_PARAMS.defaults(), box)
    assert py_params == (c_params is not None), (scalars, colours, aircraft, c_params)
    assert py_box == (c_box is not None), (extent, c_box)
    if c_box is not None:
        assert c_box == "extent"
    if py_params or py_box:
        return
    v = VS.PlacedVolume(DENSITY, (-40.0, 80.0, -300.0), extent)
    vs = VS.VolumeSet([v])
    vs.compute_light(values)
    light_c = VS.light_c(values, v)
    for a in (vs.light[0], light_c):
        assert np.all((a >= 0.0) & (a <= 1.0)), (scalars, extent)
    np.testing.assert_allclose(vs.light[0], light_c, rtol=2e-6, atol=1e-7)
    cam = CAM.camera_look_at(np.array([0.0, 104.0, 0.0]), np.array([0.0, 100.0, -100.0]), (0.0, 1.0, 0.0),
                             math.radians(60.0), 16 / 9, 0.1, 1e5)
    rng = np.random.default_rng(seed)
    xs, ys = rng.integers(0, 64, 16), rng.integers(0, 36, 16)
    w = VS.pixels_warp(values, vs, cam, xs, ys, 64, 36)
    cp = VS.pixels_c(values, vs, cam, xs, ys, 64, 36)
    assert np.all(np.isfinite(w)) and np.all(np.isfinite(cp)), (scalars, colours, extent)
    np.testing.assert_allclose(w, cp, rtol=1e-5, atol=1e-6, err_msg=f"{scalars} {colours} {extent}")
