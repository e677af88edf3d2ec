"""The PCG hash (``cclouds/hash.h``): ccl_hash_pcg / hash_pcg against an independent NumPy transcription of the
published formula (Jarzynski & Olano 2020) and hand-computed values, the Python-integer twin, bijectivity and
mixing; ccl_hash_unit / hash_unit: exact values and range. The hash has no catalogue ID (the texts leave it
unspecified), so these are its C-vs-Warp tests."""
from __future__ import annotations

import numpy as np
import warp as wp

from pywarp.core import binding as _cclouds
from pywarp.kernels import hash as khash


def pcg_hash(v):
    """PCG hash (Jarzynski & Olano 2020) on uint32 NumPy arrays (wrapping arithmetic), from the paper's listing."""
    with np.errstate(over="ignore"):  # uint32 wrap-around is the point
        s = np.asarray(v, dtype=np.uint32) * np.uint32(747796405) + np.uint32(2891336453)
        word = ((s >> ((s >> np.uint32(28)) + np.uint32(4))) ^ s) * np.uint32(277803737)
        return (word >> np.uint32(22)) ^ word


@wp.kernel
def _hash_kernel(v: wp.array(dtype=wp.uint32), h: wp.array(dtype=wp.uint32), u: wp.array(dtype=float)):
    i = wp.tid()
    h[i] = khash.hash_pcg(v[i])
    u[i] = khash.hash_unit(v[i])


def warp_hash(v):
    v = np.ascontiguousarray(v, dtype=np.uint32)
    h = wp.empty(v.size, dtype=wp.uint32, device="cpu")
    u = wp.empty(v.size, dtype=wp.float32, device="cpu")
    wp.launch(_hash_kernel, dim=v.size, inputs=[wp.array(v, dtype=wp.uint32, device="cpu")], outputs=[h, u],
              device="cpu")
    return h.numpy(), u.numpy()


# values computed by hand from the published formula with Python integers mod 2^32
KNOWN = {0: 129708002, 1: 2831084092, 12345: 4099845390, 2 ** 32 - 1: 3861530882}


def test_hash_pcg_known_values_in_c_warp_and_python():
    lib = _cclouds.lib()
    keys = np.array(list(KNOWN), dtype=np.uint32)
    h, _ = warp_hash(keys)
    for k, ref in KNOWN.items():
        assert lib.ccl_hash_pcg(k) == ref
        assert khash.hash_pcg_py(k) == ref
    np.testing.assert_array_equal(h, np.array(list(KNOWN.values()), dtype=np.uint32))


def test_hash_pcg_matches_transcription_in_c_and_warp(rng):
    v = rng.integers(0, 2 ** 32, 4000, dtype=np.uint64).astype(np.uint32)
    ref = pcg_hash(v)
    lib = _cclouds.lib()
    assert all(lib.ccl_hash_pcg(int(a)) == int(b) for a, b in zip(v[:500], ref[:500]))
    assert all(khash.hash_pcg_py(int(a)) == int(b) for a, b in zip(v[:500], ref[:500]))
    np.testing.assert_array_equal(warp_hash(v)[0], ref)


def test_hash_pcg_is_injective_and_mixes():
    v = np.arange(2 ** 16, dtype=np.uint32)
    h = pcg_hash(v)
    assert np.unique(h).size == v.size  # a bijection of uint32: no collisions
    flips = np.unpackbits((h[1:] ^ h[:-1]).view(np.uint8)).reshape(-1, 32).sum(axis=1)
    assert 15.0 < flips.mean() < 17.0  # consecutive inputs flip about half of the 32 bits


def test_hash_unit_exact_values_and_range(rng):
    lib = _cclouds.lib()
    cases = {0: 0.0, 255: 0.0, 256: 2.0 ** -24, 2 ** 31: 0.5, 2 ** 32 - 1: 1.0 - 2.0 ** -24}
    keys = np.array(list(cases), dtype=np.uint32)
    _, u = warp_hash(keys)
    for k, ref in cases.items():
        assert lib.ccl_hash_unit(k) == ref
    np.testing.assert_array_equal(u, np.array(list(cases.values()), dtype=np.float32))
    v = rng.integers(0, 2 ** 32, 3000, dtype=np.uint64).astype(np.uint32)
    _, u = warp_hash(v)
    np.testing.assert_array_equal(u, (v >> 8).astype(np.float64) / 2 ** 24)  # exact in float32
    assert all(lib.ccl_hash_unit(int(a)) == float(b) for a, b in zip(v[:300], u[:300]))
    assert np.all((u >= 0) & (u < 1))
