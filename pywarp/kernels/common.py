"""Small helpers shared by the topic modules -- the Warp twins of the ``static inline`` helpers of
``cclouds/src/internal.h`` (not a topic: no C header, no catalogue entry).

Each is written as its C twin evaluates it (float32, same operations in the same order, comparisons spelled out so
that NaN passes through), so a topic that uses one stays bit-identical to its C source.
"""
from __future__ import annotations

import warp as wp


@wp.func
def clamp01(x: float) -> float:
    """x clamped to [0, 1] (GLSL saturate); NaN passes through (both comparisons are false)."""
    if x < 0.0:
        return 0.0
    if x > 1.0:
        return 1.0
    return x


@wp.func
def bound_cell(x: float, n: int) -> float:
    """A cell coordinate (voxel, texel) bounded to [-1, n] before the floor and the cast: beyond it every read clamps
    to the same edge cell, so the fetch is unchanged, and the cast stays within int for any non-NaN float."""
    r = x
    if x < -1.0:
        r = -1.0
    elif x > float(n):
        r = float(n)
    return r


@wp.func
def mix3(a: wp.vec3, b: wp.vec3, f: float) -> wp.vec3:
    """a + (b - a) f, component-wise (GLSL mix)."""
    return wp.vec3(a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f)
