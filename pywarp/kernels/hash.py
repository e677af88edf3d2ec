"""The integer hash of the project -- Warp twins of ``cclouds/hash.h``.

:func:`hash_pcg` is the PCG hash of Jarzynski & Olano (2020) in ``wp.uint32`` arithmetic (wrapping like C's
``uint32_t``), so C and Warp build identical noise lattices and jitter sequences; :func:`hash_unit` maps a hash to a
uniform float in [0, 1) from its top 24 bits. Neither has a catalogue ID of its own (the texts leave the hash
unspecified, vc-A1), so they are not registry entries: :func:`hash_pcg_py` is the same hash in Python integers, for
building tables on the NumPy side.
"""
from __future__ import annotations

import warp as wp

# PCG hash constants (Jarzynski & Olano 2020); > 2^31 values must be uint32 constants, not bare literals
_PCG_MUL = wp.constant(wp.uint32(747796405))
_PCG_INC = wp.constant(wp.uint32(2891336453))
_PCG_MUL2 = wp.constant(wp.uint32(277803737))
_U4 = wp.constant(wp.uint32(4))
_U8 = wp.constant(wp.uint32(8))
_U22 = wp.constant(wp.uint32(22))
_U28 = wp.constant(wp.uint32(28))
_INV_2_24 = wp.constant(1.0 / 16777216.0)  # 2^-24

#: The constants of the hash, for the documentation and the NumPy twin.
PCG_MULTIPLIER = 747796405
PCG_INCREMENT = 2891336453
PCG_OUTPUT_MULTIPLIER = 277803737


@wp.func
def hash_pcg(v: wp.uint32) -> wp.uint32:
    """PCG hash (Jarzynski & Olano 2020), as ``ccl_hash_pcg``: s = v * 747796405 + 2891336453,
    w = ((s >> ((s >> 28) + 4)) ^ s) * 277803737, return (w >> 22) ^ w (all mod 2^32)."""
    state = v * _PCG_MUL + _PCG_INC
    word = ((state >> ((state >> _U28) + _U4)) ^ state) * _PCG_MUL2
    return (word >> _U22) ^ word


@wp.func
def hash_unit(h: wp.uint32) -> float:
    """Uniform float in [0, 1) from the top 24 bits of a hash, (h >> 8) * 2^-24 (exact), as ``ccl_hash_unit``."""
    return float(h >> _U8) * _INV_2_24


def hash_pcg_py(v: int) -> int:
    """``ccl_hash_pcg`` in Python integers (mod 2^32), for tables built on the NumPy side."""
    state = (v * PCG_MULTIPLIER + PCG_INCREMENT) & 0xFFFFFFFF
    word = (((state >> ((state >> 28) + 4)) ^ state) * PCG_OUTPUT_MULTIPLIER) & 0xFFFFFFFF
    return ((word >> 22) ^ word) & 0xFFFFFFFF
