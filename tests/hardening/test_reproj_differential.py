"""Differential property test of the depth-aware reprojection pass (``ccl_reproj_frame_depth`` and its Warp twin
:func:`pywarp.clouds.reproj.reproj_frame_depth`): tiny frames (1..9 px a side, 1, 3 or 4 channels), colours from
-1e30 to 1e30, depths that are unknown (0, negative, NaN), near, far, the sky's and infinite, cameras that move a
little or far, turn or look away, every filter, iteration count, neighbourhood and history. ``fuzz_reproj`` covers
the C side alone; here the two must agree within 2 ulp (as ``tests/kernels/test_reproj_depth.py`` expects on
ordinary frames, measured 0), NaN in the same places, and the colours stay finite and within the inputs' range.
Deterministic (``derandomize=True``, no example database); ``PYWARP_DIFF_EXAMPLES`` sets another number of examples
for a longer search (default 100)."""
from __future__ import annotations

import math
import numpy as np
import pytest
from helpers import differential_settings, max_ulp_diff

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from pywarp.kernels import camera as cm  # noqa: E402
from pywarp.kernels import reproj as rp  # noqa: E402
from pywarp.clouds import reproj as crp  # noqa: E402

SETTINGS = differential_settings(100)

COLOURS = np.array([0.0, 1e-30, 0.25, 1.0, 1e30, -1e30], np.float32)
DEPTHS = np.array([0.0, -1.0, np.nan, 1e-30, 0.9, 2.6, 40.0, rp.SKY_DEPTH_KM, np.inf], np.float32)
#: (eye, target) of the current camera; the previous one is this moved by a step and turned
EYES = [(0.0, 0.3, 0.0), (0.2, 1.7, 0.1), (0.0, 9.0, 0.0), (1e4, 0.5, -1e4)]
STEPS = [(0.0, 0.0, 0.0), (0.002, 0.0, -0.002), (0.2, 0.05, 0.1), (30.0, 0.0, 0.0)]
LOOKS = [(0.5, 0.7, -0.9), (0.0, -1.0, -0.2), (0.0, 0.0, 1.0), (1.0, 0.001, 0.0)]


@SETTINGS
@given(w=st.integers(1, 9), h=st.integers(1, 9), channels=st.sampled_from([1, 3, 4]),
       frame=st.sampled_from([0, 5, 9, 15, 16, 2 ** 31 - 1, -(2 ** 31)]), eye=st.sampled_from(EYES),
       look=st.sampled_from(LOOKS), step=st.sampled_from(STEPS), turn=st.sampled_from([0.0, 0.01, 0.5, math.pi]),
       fov=st.sampled_from([0.02, 1.0, 2.9]), flt=st.sampled_from(sorted(rp.FILTERS)),
       iterations=st.sampled_from([0, 1, 2, rp.MAX_DEPTH_ITERATIONS]), neighbourhood=st.sampled_from([1, 3, 9]),
       history=st.booleans(), seed=st.integers(0, 2 ** 16))
def test_c_and_warp_agree_at_the_edges(w, h, channels, frame, eye, look, step, turn, fov, flt, iterations,
                                       neighbourhood, history, seed):
    rng = np.random.default_rng(seed)
    cur = rng.choice(COLOURS, (h, w, channels))
    prev = rng.choice(COLOURS, (h, w, channels))
    red = rng.choice(COLOURS, ((h - 1) // 4 + 1, (w - 1) // 4 + 1, channels))
    dep, pdep = rng.choice(DEPTHS, (h, w)), rng.choice(DEPTHS, (h, w))
    target = tuple(e + d for e, d in zip(eye, look))
    cam = cm.camera_look_at(eye, target, fov_y=fov, aspect=w / h)
    c, s = math.cos(turn), math.sin(turn)
    prev_look = (look[0] * c + look[2] * s, look[1], -look[0] * s + look[2] * c)
    prev_eye = tuple(e - d for e, d in zip(eye, step))
    pcam = cm.camera_look_at(prev_eye, tuple(e + d for e, d in zip(prev_eye, prev_look)), fov_y=fov, aspect=w / h)
    kw = dict(filter=flt, iterations=iterations, neighbourhood=neighbourhood, history=history)
    a_img, a_dep = crp.reproj_frame_depth(cur, dep, prev, pdep, red, frame, cam, pcam, **kw)
    b_img, b_dep = crp.reproj_frame_depth(cur, dep, prev, pdep, red, frame, cam, pcam, impl="c", **kw)
    # colours: finite, within the inputs' range (the filters are clamped) to a relative 1e-5 as fuzz_reproj checks
    # it: the n x n mean is a float32 sum of up to 81 samples times 1 / n^2, which rounds beyond the range by a few
    # ulp (81 samples of 1e-30 average to 1.0000011e-30); the twins equal to 2 ulp
    lo = float(min(cur.min(), prev.min(), red.min()))
    hi = float(max(cur.max(), prev.max(), red.max()))
    for img in (a_img, b_img):
        assert np.all(np.isfinite(img))
        assert img.min() >= lo - 1e-5 * abs(lo) and img.max() <= hi + 1e-5 * abs(hi)
    assert max_ulp_diff(a_img, b_img) <= 2
    # depths: NaN in the same places (an unknown depth carried), the rest to 2 ulp
    assert np.array_equal(np.isnan(a_dep), np.isnan(b_dep))
    ok = ~np.isnan(a_dep)
    assert max_ulp_diff(a_dep[ok], b_dep[ok]) <= 2
