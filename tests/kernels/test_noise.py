"""Noise (vc §2.3.2, §4.3.1): Perlin noise vc-A1/A2 against an independent transcription of Ken Perlin's
ImprovedNoise.java, Worley noise vc-A3/A4/A5 against a brute-force search over the periodic lattice, fBm vc-2.21/A6,
curl noise and its operators vc-2.22..2.26/A7 (vector results, shape (..., 3) / (..., 2)), Perlin-Worley vc-A8; C vs
Warp agreement and bad input. The fades and remap (vc-2.19, 2.20, 2.27) are tested in test_interp.py, the PCG hash in
test_hash.py."""
from __future__ import annotations

import numpy as np
import pytest

from helpers import assert_twins_agree

import pywarp
from pywarp.core import binding as _cclouds
from pywarp.clouds import noise as host_noise
from pywarp.kernels import noise as knoise

EPS32 = float(np.finfo(np.float32).eps)  # 2^-23

# ---------------------------------------------------------------------------------------------------------------------
# Independent references, written from the published algorithms (not calls to the code under test)
# ---------------------------------------------------------------------------------------------------------------------

# Ken Perlin, ImprovedNoise.java (2002): the permutation[] array of the reference implementation.
PERLIN_P = np.array([
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69, 142, 8, 99, 37, 240,
    21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32, 57, 177, 33, 88,
    237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175, 74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83,
    111, 229, 122, 60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216,
    80, 73, 209, 76, 132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186,
    3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206, 59, 227, 47, 16, 58, 17,
    182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9, 129,
    22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238,
    210, 144, 12, 191, 179, 162, 241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184,
    84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195,
    78, 66, 215, 61, 156, 180], dtype=np.int64)


def java_improved_noise(x, y, z, p=None, period=0, dtype=np.float64):
    """Vectorised transcription of ImprovedNoise.noise(x, y, z). ``p``: the 256-entry permutation (default Perlin's).
    ``period`` > 0 adds the documented tiling: the lattice coordinate is reduced modulo the period before the & 255.
    ``dtype=np.float32`` evaluates every operation in float32, in the order of the Java code, the fade taken as 1 where
    its Horner form rounds above 1 (as ccl_interp_fade_quintic; 22,237 floats in [0.99536, 1), issue 31 finding Q)."""
    p = np.concatenate([PERLIN_P if p is None else np.asarray(p, np.int64)[:256]] * 2)
    f = dtype
    x, y, z = (np.asarray(v, dtype=f) for v in (x, y, z))
    one, six, fifteen, ten = f(1), f(6), f(15), f(10)

    def fade(t):
        return np.minimum(t * t * t * (t * (t * six - fifteen) + ten), one)

    def lerp(t, a, b):
        return a + t * (b - a)

    def grad(hsh, gx, gy, gz):
        h = hsh & 15
        u = np.where(h < 8, gx, gy)
        v = np.where(h < 4, gy, np.where((h == 12) | (h == 14), gx, gz))
        return np.where((h & 1) == 0, u, -u) + np.where((h & 2) == 0, v, -v)

    fx, fy, fz = np.floor(x), np.floor(y), np.floor(z)
    ix, iy, iz = (v.astype(np.int64) for v in (fx, fy, fz))

    def wrap(i):
        return (np.mod(i, period) if period else i) & 255

    X0, Y0, Z0, X1, Y1, Z1 = wrap(ix), wrap(iy), wrap(iz), wrap(ix + 1), wrap(iy + 1), wrap(iz + 1)
    x, y, z = x - fx, y - fy, z - fz
    u, v, w = fade(x), fade(y), fade(z)
    A, A1, B, B1 = p[X0] + Y0, p[X0] + Y1, p[X1] + Y0, p[X1] + Y1
    h000, h010, h100, h110 = p[p[A] + Z0], p[p[A1] + Z0], p[p[B] + Z0], p[p[B1] + Z0]
    h001, h011, h101, h111 = p[p[A] + Z1], p[p[A1] + Z1], p[p[B] + Z1], p[p[B1] + Z1]
    return lerp(w, lerp(v, lerp(u, grad(h000, x, y, z), grad(h100, x - one, y, z)),
                        lerp(u, grad(h010, x, y - one, z), grad(h110, x - one, y - one, z))),
                lerp(v, lerp(u, grad(h001, x, y, z - one), grad(h101, x - one, y, z - one)),
                     lerp(u, grad(h011, x, y - one, z - one), grad(h111, x - one, y - one, z - one))))


def pcg_hash(v):
    """PCG hash (Jarzynski & Olano 2020) on uint32 NumPy arrays (wrapping arithmetic)."""
    with np.errstate(over="ignore"):  # uint32 wrap-around is the point
        s = np.asarray(v, dtype=np.uint32) * np.uint32(747796405) + np.uint32(2891336453)
        word = ((s >> ((s >> np.uint32(28)) + np.uint32(4))) ^ s) * np.uint32(277803737)
        return (word >> np.uint32(22)) ^ word


def fisher_yates(seed):
    """The documented seeded permutation: identity shuffled for i = 255 .. 1 with j = H(H(seed) + i) mod (i + 1)."""
    perm = list(range(256))
    key = int(pcg_hash(np.uint32(seed)))
    for i in range(255, 0, -1):
        j = int(pcg_hash(np.uint32((key + i) % 2 ** 32))) % (i + 1)
        perm[i], perm[j] = perm[j], perm[i]
    return np.array(perm)


def worley_features(cells, seed):
    """Feature offsets (cells, cells, cells, 3) [k, j, i] of the documented hash h0 = H(i + H(j + H(k + H(seed)))),
    h1 = H(h0), h2 = H(h1), offset = (h >> 9) / 2^23."""
    idx = np.arange(cells, dtype=np.uint32)
    hz = pcg_hash(idx + pcg_hash(np.uint32(seed)))
    hy = pcg_hash(idx[None, :] + hz[:, None])
    h0 = pcg_hash(idx[None, None, :] + hy[:, :, None])
    h1 = pcg_hash(h0)
    h2 = pcg_hash(h1)
    return np.stack([(h >> np.uint32(9)).astype(np.float64) / 2.0 ** 23 for h in (h0, h1, h2)], axis=-1)


def worley_bruteforce(x, y, z, cells, seed=0, metric="euclidean"):
    """F1 over ALL cells^3 feature points of the periodic lattice, minimum-image distance per axis (float64), in cell
    units, clamped to 1."""
    feat = worley_features(cells, seed)
    k, j, i = np.meshgrid(np.arange(cells), np.arange(cells), np.arange(cells), indexing="ij")
    fp = np.stack([i + feat[..., 0], j + feat[..., 1], k + feat[..., 2]], axis=-1).reshape(-1, 3)
    q = np.stack([np.mod(np.asarray(c, np.float64), 1.0) * cells for c in (x, y, z)], axis=-1).reshape(-1, 1, 3)
    d = np.abs(q - fp[None])
    d = np.minimum(d, cells - d)  # nearest periodic image along each axis
    dist = d.sum(-1) if metric == "manhattan" else np.sqrt((d * d).sum(-1))
    return np.minimum(dist.min(-1), 1.0).reshape(np.shape(x))


def f32(a):
    """Round to float32 and back (the inputs our float32 functions actually see)."""
    return np.asarray(a, dtype=np.float32).astype(np.float64)


def c_lib():
    return _cclouds.ffi(), _cclouds.lib()


def comps(v):
    """The components of a vector result (..., k) as the leading axis (k, ...)."""
    return np.moveaxis(np.asarray(v), -1, 0)


# Error bound of float32 Perlin noise against the float64 reference (per point, absolute):
#  - fade(t) = t^3 (t (6t - 15) + 10): the roundings of 6t, 6t - 15, t(...), + 10 are at most 2^-22, 2^-21, 2^-21,
#    2^-21 (magnitudes <= 6, 15, 15, 10), scaled by t^3 <= 1, plus the t^3 and final products (<= 10 * 2^-24):
#    |d fade| <= 2.3e-6;
#  - each of the three lerp levels multiplies its weight error by |b - a| <= 4 (corner gradients lie in [-2, 2]):
#    3 * 4 * 2.3e-6 = 2.8e-5;
#  - corner values: x - 1 rounds by <= 2^-25 per coordinate, u + v by <= 2^-23: 1.8e-7; lerp roundings 3 * 2^-23.
PERLIN_ABS_TOL = 3.0e-5
# C vs Warp: the same float32 expression tree, no contraction (gcc -std=c99; Warp's clang CPU backend); observed
# bit-identical. Allowed: 2^-22 absolute (2 ulp at magnitude 1; ulp comparisons are meaningless near the zeros).
C_WARP_ABS = 2.0 ** -22


# Perlin noise vc-A1, vc-A2
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A1")
def test_perm_tables_python_c_and_reference_agree():
    ffi, lib = c_lib()
    assert np.array_equal(knoise.perm_table(0)[:256], PERLIN_P)
    for seed in (0, 1, 2, 12345, 2 ** 31, 2 ** 32 - 1):
        buf = ffi.new("uint8_t[512]")
        assert lib.ccl_noise_perm_table(seed, buf) == lib.CCL_OK
        c_table = np.frombuffer(ffi.buffer(buf), dtype=np.uint8).astype(np.int32)
        py_table = knoise.perm_table(seed)
        assert np.array_equal(c_table, py_table), seed
        assert np.array_equal(np.sort(py_table[:256]), np.arange(256))  # a permutation
        assert np.array_equal(py_table[256:], py_table[:256])
        if seed:
            assert np.array_equal(py_table[:256], fisher_yates(seed))
    assert not np.array_equal(knoise.perm_table(1), knoise.perm_table(2))


@pytest.mark.spec("vc-A1")
def test_perlin3_seed0_is_ken_perlins_reference(rng):
    # Perlin's page: noise(3.14, 42, 7) = 0.13691995878400012; our float32 input 3.14f is 1.0e-7 off 3.14
    assert java_improved_noise(3.14, 42.0, 7.0) == 0.13691995878400012  # the transcription reproduces his value
    assert pywarp.noise_perlin3(3.14, 42, 7) == pytest.approx(0.13691995878400012, abs=1e-6)
    pts = np.concatenate([rng.uniform(-300, 300, (3, 4000)), rng.uniform(0, 4, (3, 4000))], axis=1)
    pts = pts.astype(np.float32)
    ref = java_improved_noise(*f32(pts))
    for impl in ("warp", "c"):
        n = pywarp.equation("vc-A1", impl=impl)(*pts)
        err = np.abs(n - ref)
        assert err.max() <= PERLIN_ABS_TOL, impl  # observed 1.9e-6
    # the same algorithm evaluated in float32 by NumPy, operation by operation: bit-identical
    ref32 = java_improved_noise(*pts, dtype=np.float32)
    np.testing.assert_array_equal(pywarp.noise_perlin3(*pts), ref32)
    assert np.abs(ref).max() > 0.7  # a real range, not a degenerate field


@pytest.mark.spec("vc-A1")
def test_perlin3_zero_at_lattice_points_and_continuous():
    i, j, k = np.meshgrid(np.arange(-4, 5), np.arange(-4, 5), np.arange(-4, 5), indexing="ij")
    for seed, period in ((0, 0), (17, 0), (3, 5)):
        n = pywarp.noise_perlin3(i * 3.0, j, k - 100.0, seed=seed, period=period)
        assert np.all(n == 0.0)
    # continuity and C^1 across a cell face: one-sided differences at x = 5 agree to O(h)
    h = 2.0 ** -12
    y, z = 0.3, 0.7
    left = (pywarp.noise_perlin3(5.0, y, z) - pywarp.noise_perlin3(5.0 - h, y, z)) / h
    right = (pywarp.noise_perlin3(5.0 + h, y, z) - pywarp.noise_perlin3(5.0, y, z)) / h
    assert abs(left - right) < 0.01


@pytest.mark.spec("vc-A1")
def test_perlin3_other_seeds_use_their_table(rng):
    pts = rng.uniform(-40, 40, (3, 3000)).astype(np.float32)
    for seed in (1, 99, 2 ** 32 - 1):
        ref = java_improved_noise(*f32(pts), p=fisher_yates(seed))
        for impl in ("warp", "c"):
            n = pywarp.equation("vc-A1", impl=impl)(*pts, seed=seed)
            assert np.abs(n - ref).max() <= PERLIN_ABS_TOL, (seed, impl)
    a, b = pywarp.noise_perlin3(*pts, seed=1), pywarp.noise_perlin3(*pts, seed=2)
    assert np.corrcoef(a, b)[0, 1] < 0.2  # different seeds, unrelated fields
    # per-element seeds: each element uses its own table
    seeds = np.array([0, 1, 2] * 1000, dtype=np.uint32)
    mixed = pywarp.noise_perlin3(*pts, seed=seeds)
    for s in (0, 1, 2):
        np.testing.assert_array_equal(mixed[seeds == s], pywarp.noise_perlin3(*pts[:, seeds == s], seed=int(s)))
    # determinism
    np.testing.assert_array_equal(pywarp.noise_perlin3(*pts, seed=99), pywarp.noise_perlin3(*pts, seed=99))


@pytest.mark.spec("vc-A2", "vc-A1")
@pytest.mark.parametrize("period", [1, 3, 4, 7, 256, 300])
def test_perlin3_periodic_exactly(rng, period):
    # points on a 1/128 grid: p + period is exact in float32
    pts = (rng.integers(-2000, 2000, (3, 1500)) / 128.0).astype(np.float32)
    base = pywarp.noise_perlin3(*pts, seed=5, period=period)
    for axis in range(3):
        for k in (1, -2):
            shifted = pts.copy()
            shifted[axis] += k * period
            np.testing.assert_array_equal(pywarp.noise_perlin3(*shifted, seed=5, period=period), base)
    tiled = pywarp.equation("vc-A2")
    np.testing.assert_array_equal(tiled(*pts, period, seed=5), base)
    np.testing.assert_array_equal(pywarp.equation("vc-A2", impl="c")(*pts[:, :300], period, seed=5), base[:300])
    # independent reference: the Java code with the lattice reduced modulo the period before hashing
    ref = java_improved_noise(*f32(pts), p=fisher_yates(5), period=period)
    assert np.abs(base - ref).max() <= PERLIN_ABS_TOL
    if period not in (1, 256):  # non-trivial period: the unwrapped noise is not periodic
        assert not np.array_equal(pywarp.noise_perlin3(pts[0] + period, pts[1], pts[2]), pywarp.noise_perlin3(*pts))


@pytest.mark.spec("vc-A1")
def test_perlin2_is_the_z0_slice_and_interpolants(rng):
    x, y = (rng.uniform(-30, 30, (2, 2000))).astype(np.float32)
    for impl in ("warp", "c"):
        np.testing.assert_array_equal(host_noise.perlin2(x, y, seed=4, period=6, impl=impl),
                                      pywarp.noise_perlin3(x, y, 0.0, seed=4, period=6))
    # other interpolants: still 0 at lattice points, continuous, and different from the quintic
    gx, gy = np.meshgrid(np.arange(-3, 4.0), np.arange(-3, 4.0))
    xs = np.linspace(0, 4, 4097)
    for interp in ("cubic", "linear", "cosine"):
        assert np.all(host_noise.perlin2(gx, gy, interp=interp) == 0.0)
        line = host_noise.perlin2(xs, 0.37, interp=interp).astype(np.float64)
        # continuous: steps of 1/1024 change the value by at most a few 1/1024 (|corner gradients| <= 2)
        assert np.abs(np.diff(line)).max() < 8.0 * (xs[1] - xs[0])
        assert np.abs(line - host_noise.perlin2(xs, 0.37)).max() > 1e-3
        # C vs Warp: cosf vs Warp's cos may differ by 1 ulp, scaled by |b - a| <= 4 -> 2^-20
        np.testing.assert_allclose(host_noise.perlin2(x, y, interp=interp, impl="c"),
                                   host_noise.perlin2(x, y, interp=interp), rtol=0, atol=2.0 ** -20)
    # the linear interpolant has a kink at cell borders, the quintic has none
    h = 2.0 ** -10
    kink = {}
    for interp in ("linear", "quintic"):
        f = lambda v: float(host_noise.perlin2(v, 0.37, interp=interp))  # noqa: E731
        kink[interp] = abs((f(2 + h) - f(2.0)) / h - (f(2.0) - f(2 - h)) / h)
    assert kink["linear"] > 0.05 and kink["quintic"] < 0.01


@pytest.mark.spec("vc-A1", "vc-A2")
def test_perlin_c_and_warp_agree(rng):
    pts = rng.uniform(-100, 100, (3, 3000)).astype(np.float32)
    for seed, period in ((0, 0), (7, 0), (7, 9)):
        assert_twins_agree("vc-A1", *pts, seed=seed, period=period, atol=C_WARP_ABS)
    assert_twins_agree("vc-A2", *pts, 9, seed=7, atol=C_WARP_ABS)


# ---------------------------------------------------------------------------------------------------------------------
# Worley noise vc-A3, vc-A4, vc-A5
# ---------------------------------------------------------------------------------------------------------------------

# float32 Worley vs the float64 brute force: q = x * cells rounds by <= cells * 2^-25 (x < 1), d + offset is exact
# (23-bit offsets), (d + o) - t rounds by 2^-24 per axis, the squared sum (<= 3 roundings at magnitude <= 3) and the
# sqrt add ~4 * 2^-24 at distance ~1: allowed 1e-6 + cells * 2^-24 * 2 (L1 adds the three per-axis errors).
def _worley_tol(cells):
    return 1e-6 + 2 * cells * 2.0 ** -24


@pytest.mark.spec("vc-A3", "vc-A5")
@pytest.mark.parametrize("cells, seed", [(1, 0), (2, 3), (3, 0), (5, 77), (8, 2 ** 32 - 1)])
@pytest.mark.parametrize("metric", ["euclidean", "manhattan"])
def test_worley_matches_bruteforce_over_all_feature_points(rng, cells, seed, metric):
    pts = rng.uniform(0, 1, (3, 1500)).astype(np.float32)
    ref = worley_bruteforce(*f32(pts), cells=cells, seed=seed, metric=metric)
    for impl in ("warp", "c"):
        w = pywarp.equation("vc-A3", impl=impl)(*pts, cells, seed=seed, metric=metric)
        assert np.abs(w - ref).max() <= _worley_tol(cells), impl
    assert ref.max() > 0.5 and ref.min() < 0.2  # the points sample the whole range of F1


@pytest.mark.spec("vc-A3")
def test_worley_feature_points_from_the_documented_hash_are_zeros():
    _, lib = c_lib()
    for cells, seed in ((4, 0), (8, 12), (1, 5)):
        feat = worley_features(cells, seed)
        # cell indices 0 and 1 only: i + offset (23-bit offsets) is exact in float32 for i <= 1
        for (k, j, i) in ((0, 0, 0), (min(1, cells - 1), 0, min(1, cells - 1)), (0, min(1, cells - 1), 0)):
            o = lib.ccl_noise_worley_feature(i, j, k, cells, seed)
            assert (o.x, o.y, o.z) == tuple(feat[k, j, i])
            # wrapped index: same feature point
            o = lib.ccl_noise_worley_feature(i - cells, j + 3 * cells, k, cells, seed)
            assert (o.x, o.y, o.z) == tuple(feat[k, j, i])
            # cells a power of two: (i + offset) / cells is exact, so the distance is exactly 0
            p = [(c + feat[k, j, i][a]) / cells for a, c in enumerate((i, j, k))]
            assert pywarp.noise_worley3(*p, cells, seed=seed) == 0.0
            assert pywarp.noise_worley3(*p, cells, seed=seed, metric="manhattan", inverse=True) == 1.0


@pytest.mark.spec("vc-A3", "vc-A4", "vc-A5")
def test_worley_periodic_range_lipschitz_and_inverse(rng):
    pts = (rng.integers(0, 4096, (3, 3000)) / 4096.0).astype(np.float32)  # exact under + integer
    for cells in (3, 6):
        e = pywarp.noise_worley3(*pts, cells, seed=11)
        m = pywarp.noise_worley3(*pts, cells, seed=11, metric="manhattan")
        assert e.min() >= 0 and e.max() <= 1 and m.min() >= 0 and m.max() <= 1
        assert np.all(m >= e)  # L1 >= L2 point by point, hence for the nearest
        np.testing.assert_array_equal(pywarp.noise_worley3(*pts, cells, seed=11, inverse=True), 1 - e)
        for axis in range(3):
            for k in (1, -3):
                sh = pts.copy()
                sh[axis] += k
                np.testing.assert_array_equal(pywarp.noise_worley3(*sh, cells, seed=11), e)
                np.testing.assert_array_equal(pywarp.noise_worley3(*sh, cells, seed=11, metric="manhattan"), m)
        # F1 is 1-Lipschitz in cell units: |W(p) - W(q)| <= cells |p - q| (L2; L1 for Manhattan) + round-off
        q = (pts + rng.normal(0, 0.01, pts.shape)).astype(np.float32)
        dp = q.astype(np.float64) - pts
        assert np.all(np.abs(pywarp.noise_worley3(*q, cells, seed=11) - e)
                      <= cells * np.sqrt((dp ** 2).sum(0)) + 4e-6)
        assert np.all(np.abs(pywarp.noise_worley3(*q, cells, seed=11, metric="manhattan") - m)
                      <= cells * np.abs(dp).sum(0) + 4e-6)
    # different seeds differ, same seed repeats
    assert not np.array_equal(pywarp.noise_worley3(*pts, 4, seed=1), pywarp.noise_worley3(*pts, 4, seed=2))
    np.testing.assert_array_equal(pywarp.noise_worley3(*pts, 4, seed=1), pywarp.noise_worley3(*pts, 4, seed=1))


@pytest.mark.spec("vc-A4")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_worley_variants_are_the_three_options(rng, impl):
    pts = rng.uniform(0, 1, (3, 800)).astype(np.float32)
    classic, manhattan, inverse = pywarp.equation("vc-A4", impl=impl)(*pts, 5, seed=3)
    w = pywarp.equation("vc-A3", impl=impl)
    np.testing.assert_array_equal(classic, w(*pts, 5, seed=3))
    np.testing.assert_array_equal(manhattan, w(*pts, 5, seed=3, metric="manhattan"))
    np.testing.assert_array_equal(inverse, w(*pts, 5, seed=3, inverse=True))
    np.testing.assert_array_equal(inverse, 1 - classic)


@pytest.mark.spec("vc-A5")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_worley_literal_tiling_construction_equals_27_cell_search(rng, impl):
    pts = rng.uniform(0, 1, (3, 300)).astype(np.float32)
    brute = pywarp.equation("vc-A5", impl=impl)
    for cells, metric in ((2, "euclidean"), (4, "manhattan"), (5, "euclidean")):
        b = brute(*pts, cells, seed=8, metric=metric)
        # both float32, different operation order ((i + c*cells) + o) - q vs (d + o) - t: a few roundings
        np.testing.assert_allclose(b, pywarp.noise_worley3(*pts, cells, seed=8, metric=metric), rtol=0,
                                   atol=_worley_tol(cells))
        np.testing.assert_allclose(b, worley_bruteforce(*f32(pts), cells=cells, seed=8, metric=metric), rtol=0,
                                   atol=_worley_tol(cells))
    # inputs outside [0, 1) are reduced modulo 1 (grid points, so that the shifts are exact)
    g = (rng.integers(0, 1024, (3, 200)) / 1024.0).astype(np.float32)
    np.testing.assert_array_equal(brute(g[0] + 2, g[1] - 1, g[2], 3), brute(*g, 3))


@pytest.mark.spec("vc-A3", "vc-A4", "vc-A5")
def test_worley_c_and_warp_agree(rng):
    """Same float32 operations and the same uint32 hash; sqrt correctly rounded: bit-identical (observed)."""
    pts = rng.uniform(-3, 3, (3, 2000)).astype(np.float32)
    cells = rng.integers(1, 12, 2000).astype(np.int32)
    seeds = rng.integers(0, 2 ** 32, 2000, dtype=np.uint64).astype(np.uint32)
    for metric in ("euclidean", "manhattan"):
        for inverse in (False, True):
            assert_twins_agree("vc-A3", *pts, cells, seed=seeds, metric=metric, inverse=inverse, ulp=0)
    assert_twins_agree("vc-A4", *pts, cells, seed=seeds, ulp=0)


# ---------------------------------------------------------------------------------------------------------------------
# fBm vc-2.21, vc-A6
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-2.21", "vc-A6")
def test_fbm_perlin_against_reference_octave_sum(rng):
    pts = rng.uniform(-2, 2, (3, 2000)).astype(np.float32)
    for octaves, freq in ((1, 1.0), (3, 2.0), (5, 1.5)):
        ref = sum(0.5 ** i * java_improved_noise(*(f32(pts) * np.float32(freq) * 2 ** i))
                  for i in range(octaves)) / sum(0.5 ** i for i in range(octaves))
        for impl in ("warp", "c"):
            n = pywarp.equation("vc-2.21", impl=impl)(*pts, octaves, freq)
            # each octave within PERLIN_ABS_TOL (x * f is exact for f = 2^i * {1, 2}; for 1.5 the product rounds by
            # 2^-24 |x f| <= 2^-24 * 48, times the noise's Lipschitz constant ~2.5 -> 7e-6); the weighted mean of
            # the octaves keeps the bound
            tol = PERLIN_ABS_TOL + (7e-6 if freq == 1.5 else 0.0)
            assert np.abs(n - ref).max() <= tol, (octaves, freq, impl)
    # one octave = the noise at the base frequency, exactly
    np.testing.assert_array_equal(pywarp.noise_fbm_perlin3(*pts, 1, 2.0), pywarp.noise_perlin3(*(pts * 2)))


@pytest.mark.spec("vc-2.21", "vc-A6")
def test_fbm_perlin_octave_rule_and_tiling(rng):
    pts = (rng.integers(0, 512, (3, 1000)) / 512.0).astype(np.float32)
    # frequency 4, period 4 (octave i: period 4 * 2^i) -> the fBm tiles the unit cube exactly
    f = pywarp.noise_fbm_perlin3(*pts, 4, 4.0, seed=3, period=4)
    for axis in range(3):
        sh = pts.copy()
        sh[axis] += 1
        np.testing.assert_array_equal(pywarp.noise_fbm_perlin3(*sh, 4, 4.0, seed=3, period=4), f)
    # f_i = 2 f_{i-1}, w_i = w_{i-1}/2, normalised by sum w = 1.875
    octs = [pywarp.noise_perlin3(*(pts * 4 * 2 ** i), seed=3, period=4 * 2 ** i).astype(np.float64) for i in range(4)]
    np.testing.assert_allclose(f, (octs[0] + octs[1] / 2 + octs[2] / 4 + octs[3] / 8) / 1.875, rtol=0,
                               atol=4 * EPS32)
    # more octaves add high-frequency detail. With w_i = 2^-i every octave carries the same gradient energy, and
    # the second-difference energy of octave i grows as 4^i: (1 + 4 + 16 + 64) / 1.875^2 = 24 times one octave's
    x = np.linspace(0, 1, 4097, dtype=np.float32)
    rough = [np.mean(np.diff(pywarp.noise_fbm_perlin3(x, 0.3, 0.6, o, 4.0).astype(np.float64), 2) ** 2)
             for o in (1, 4)]
    assert rough[1] > 8 * rough[0]


@pytest.mark.spec("vc-A6", "vc-2.21")
@pytest.mark.parametrize("inverse", [False, True])
def test_fbm_worley_against_bruteforce(rng, inverse):
    pts = rng.uniform(0, 1, (3, 600)).astype(np.float32)
    octaves, cells, seed = 3, 2, 9
    ref = sum(0.5 ** i * worley_bruteforce(*f32(pts), cells=cells * 2 ** i, seed=seed + i) for i in range(octaves))
    ref = ref / 1.75
    if inverse:
        ref = 1 - ref
    for impl in ("warp", "c"):
        n = pywarp.equation("vc-A6", impl=impl)(*pts, octaves, cells, seed=seed, inverse=inverse)
        assert np.abs(n - ref).max() <= _worley_tol(cells * 4) + 4 * EPS32, impl
        assert n.min() >= 0 and n.max() <= 1
    # period 1 exactly
    g = (rng.integers(0, 256, (3, 500)) / 256.0).astype(np.float32)
    v = pywarp.noise_fbm_worley3(*g, 3, 3, seed=1, inverse=inverse)
    np.testing.assert_array_equal(pywarp.noise_fbm_worley3(g[0] - 1, g[1] + 1, g[2] + 2, 3, 3, seed=1,
                                                           inverse=inverse), v)


@pytest.mark.spec("vc-2.21", "vc-A6")
def test_fbm_c_and_warp_agree(rng):
    """Relative 1e-6: the octave sum is the same float32 sequence in both; observed bit-identical."""
    pts = rng.uniform(-1, 1, (3, 1000)).astype(np.float32)
    assert_twins_agree("vc-2.21", *pts, 5, 3.0, seed=4, period=3, atol=C_WARP_ABS)
    assert_twins_agree("vc-A6", *pts, 3, 3, seed=4, metric="manhattan", inverse=True)


# ---------------------------------------------------------------------------------------------------------------------
# Curl noise vc-2.22 .. vc-2.26, vc-A7
# ---------------------------------------------------------------------------------------------------------------------

H = knoise.FD_STEP
O1 = np.array(knoise.CURL_OFFSET_1)[:, None]
O2 = np.array(knoise.CURL_OFFSET_2)[:, None]


def ref_grad(p, h=H):
    """Central differences of the float64 reference noise at float64 points p (3, n)."""
    out = []
    for a in range(3):
        e = np.zeros((3, 1))
        e[a] = h
        out.append((java_improved_noise(*(p + e)) - java_improved_noise(*(p - e))) / (2 * h))
    return np.stack(out)


def ref_curl(p, h=H):
    gx, g1, g2 = ref_grad(p, h), ref_grad(p + O1, h), ref_grad(p + O2, h)
    return np.stack([g2[1] - g1[2], gx[2] - g2[0], g1[0] - gx[1]])


# Our central difference (N(x+h) - N(x-h)) / 2h in float32 vs the same in float64: each noise value is within
# PERLIN_ABS_TOL, so the quotient is within 2 PERLIN_ABS_TOL / 2h; a curl component is a difference of two.
FD_TOL = PERLIN_ABS_TOL / H
# Truncation of the h = 1/256 central difference against the exact derivative (float64 reference, h = 1e-6):
# h^2/6 |N'''| with |N'''| <= ~100 for the quintic-faded lattice -> 3e-4 (observed 2.8e-4).
TRUNC_TOL = 5e-4


@pytest.mark.spec("vc-2.22")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_gradient_matches_reference_derivative(rng, impl):
    p = rng.uniform(-20, 20, (3, 1500)).astype(np.float32)
    g = comps(pywarp.equation("vc-2.22", impl=impl)(*p))
    assert np.abs(g - ref_grad(f32(p))).max() <= FD_TOL
    assert np.abs(g - ref_grad(f32(p), 1e-6)).max() <= FD_TOL + TRUNC_TOL
    # closed form: at a lattice point fade' = 0 removes every corner but its own, so nabla N is that corner's gradient
    # vector, one of Perlin's 12 edge directions (two components +-1, one 0)
    i = np.arange(-5, 6, dtype=np.float32)
    gl = comps(pywarp.noise_gradient3(i, 2 * i, -i, h=2.0 ** -12))
    assert np.allclose(np.sort(np.abs(gl), axis=0), np.array([[0.0], [1.0], [1.0]]), atol=1e-3)


@pytest.mark.spec("vc-2.23", "vc-A7")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_curl3_matches_reference_and_is_divergence_free(rng, impl):
    p = rng.uniform(-20, 20, (3, 800)).astype(np.float32)
    v = comps(pywarp.equation("vc-2.23", impl=impl)(*p))
    assert np.abs(v - ref_curl(f32(p))).max() <= 2 * FD_TOL
    # divergence of the sampled field on a grid (spacing 1/32, outer central differences in float64 by NumPy):
    # compare with the size of the individual derivative terms
    if impl == "warp":
        s = np.arange(-8, 9) / 32.0
        X, Y, Z = np.meshgrid(s + 3.3, s - 1.7, s + 0.4, indexing="ij")
        vx, vy, vz = comps(pywarp.noise_curl3(X, Y, Z)).astype(np.float64)
        d = 1 / 32.0
        terms = [np.gradient(vx, d, axis=0), np.gradient(vy, d, axis=1), np.gradient(vz, d, axis=2)]
        div = sum(terms)[1:-1, 1:-1, 1:-1]
        scale = sum(np.abs(t) for t in terms)[1:-1, 1:-1, 1:-1]
        # O(d^2) truncation of the outer differences and O(h^2) of the inner ones do not cancel exactly: bounded by
        # (d^2/6) |v'''| relative to |v'| ~ 10: observed 1.5 %, allowed 5 %; a field with a wrong sign is O(100 %)
        assert np.sqrt(np.mean(div ** 2)) <= 0.05 * np.sqrt(np.mean(scale ** 2))
        # the unprotected potential itself is far from divergence-free (vc-2.25)
        psi = [java_improved_noise(X, Y, Z), java_improved_noise(X + O1[0, 0], Y + O1[1, 0], Z + O1[2, 0]),
               java_improved_noise(X + O2[0, 0], Y + O2[1, 0], Z + O2[2, 0])]
        dpsi = sum(np.gradient(c, d, axis=a) for a, c in enumerate(psi))[1:-1, 1:-1, 1:-1]
        assert np.sqrt(np.mean(dpsi ** 2)) > 0.2


@pytest.mark.spec("vc-2.24", "vc-2.23")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_rot2_is_scalar_z_component_of_curl3(rng, impl):
    x, y = rng.uniform(-20, 20, (2, 800)).astype(np.float32)
    r = pywarp.equation("vc-2.24", impl=impl)(x, y)
    vz = pywarp.equation("vc-2.23", impl=impl)(x, y, 0.0)[..., 2]
    np.testing.assert_array_equal(r, vz)
    p = np.stack([f32(x), f32(y), np.zeros_like(f32(x))])
    g, g1 = ref_grad(p), ref_grad(p + O1)
    assert np.abs(r - (g1[0] - g[1])).max() <= 2 * FD_TOL
    assert np.abs(r).max() > 1.0  # a real rotation field, not a degenerate one


@pytest.mark.spec("vc-2.25")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_divergence_of_potential_matches_reference(rng, impl):
    p = rng.uniform(-20, 20, (3, 800)).astype(np.float32)
    d = pywarp.equation("vc-2.25", impl=impl)(*p)
    pd = f32(p)
    ref = ref_grad(pd)[0] + ref_grad(pd + O1)[1] + ref_grad(pd + O2)[2]  # sum over i = 1..3
    assert np.abs(d - ref).max() <= 3 * FD_TOL
    assert np.median(np.abs(d)) > 0.3  # not divergence-free: contrast with vc-2.26


@pytest.mark.spec("vc-2.26", "vc-2.23", "vc-2.25")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_curl_property_corrected_vs_printed(rng, impl):
    p = rng.uniform(-20, 20, (3, 300)).astype(np.float32)
    prop = pywarp.equation("vc-2.26", impl=impl)
    div = prop(*p)  # corrected: div(curl psi)
    curlcurl = prop(*p, variant="thesis")  # as printed: curl(curl psi) = 0?
    # The nested central differences commute in exact arithmetic, so div(curl psi) is pure float32 round-off:
    # noise errors ~1e-7 divided by (2h)^2 = 6e-5 give ~1e-3 at worst; observed < 4e-5. The derivatives of v are
    # O(10) (see the thesis variant), so 1e-3 is 1e-4 of the scale.
    assert np.abs(div).max() <= 1e-3
    # the printed reading is false: |curl curl psi| = |grad div psi - laplacian psi| is O(10)
    assert np.median(curlcurl) > 3.0 and np.all(curlcurl >= 0)
    # pin both variants with an independent value at one point (float64 nested central differences)
    q = np.array([[1.25], [-0.5], [2.75]])
    jac = np.zeros((3, 3))
    for a in range(3):
        e = np.zeros((3, 1))
        e[a] = H
        jac[:, a] = ((ref_curl(q + e) - ref_curl(q - e)) / (2 * H))[:, 0]
    ref_cc = np.linalg.norm([jac[2, 1] - jac[1, 2], jac[0, 2] - jac[2, 0], jac[1, 0] - jac[0, 1]])
    ref_div = np.trace(jac)
    assert abs(ref_div) < 1e-8  # the reference confirms the identity
    # the nested differences amplify the float32 noise error (~1e-7 per value, see above) by 1/(2h)^2 per term:
    # ~1e-2 absolute on |curl curl psi| = 15, i.e. 1e-3 relative (observed 1.4e-4)
    assert float(prop(*q[:, 0], variant="thesis")) == pytest.approx(ref_cc, rel=1e-3)
    assert abs(float(prop(*q[:, 0]))) <= 1e-3


@pytest.mark.spec("vc-A7")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_curl2_stream_function_tangent_and_divergence_free(rng, impl):
    x, y = rng.uniform(-20, 20, (2, 1500)).astype(np.float32)
    vx, vy = comps(pywarp.equation("vc-A7", impl=impl)(x, y))
    p = np.stack([f32(x), f32(y), np.zeros(x.size)])
    g = ref_grad(p, 1e-6)  # exact gradient of psi = N(x, y, 0) (float64)
    # v = (dpsi/dy, -dpsi/dx)
    assert np.abs(vx - g[1]).max() <= FD_TOL + TRUNC_TOL
    assert np.abs(vy + g[0]).max() <= FD_TOL + TRUNC_TOL
    # tangent to the level sets of psi: v . grad psi = 0 relative to |v| |grad psi|
    norm = np.hypot(vx, vy) * np.hypot(g[0], g[1])
    ok = norm > 1e-2
    assert np.all(np.abs(vx * g[0] + vy * g[1])[ok] <= 2 * (FD_TOL + TRUNC_TOL) * np.hypot(g[0], g[1])[ok])
    # moving along v keeps psi constant to second order: |dpsi| << |v| * step
    step = 1e-3
    moved = java_improved_noise(f32(x) + step * vx, f32(y) + step * vy, 0.0) - java_improved_noise(f32(x), f32(y), 0.0)
    across = (java_improved_noise(f32(x) + step * g[0], f32(y) + step * g[1], 0.0)
              - java_improved_noise(f32(x), f32(y), 0.0))
    assert np.median(np.abs(moved)) < 0.01 * np.median(np.abs(across))
    if impl == "warp":  # divergence of the sampled 2-D field on a grid (float64 outer differences)
        s = np.arange(-8, 9) / 32.0
        X, Y = np.meshgrid(s + 2.1, s - 0.6, indexing="ij")
        ux, uy = comps(pywarp.noise_curl2(X, Y)).astype(np.float64)
        tx, ty = np.gradient(ux, 1 / 32.0, axis=0), np.gradient(uy, 1 / 32.0, axis=1)
        div = (tx + ty)[1:-1, 1:-1]
        assert np.sqrt(np.mean(div ** 2)) <= 0.05 * np.sqrt(np.mean((np.abs(tx) + np.abs(ty))[1:-1, 1:-1] ** 2))


@pytest.mark.spec("vc-2.22", "vc-2.23", "vc-2.24", "vc-2.25", "vc-2.26", "vc-A7")
def test_curl_family_c_and_warp_agree(rng):
    """Differences of bit-identical noise values (see test_perlin_c_and_warp_agree) divided by the same float
    spacing: identical up to the same 2-ulp-of-noise allowance, amplified by 1/(2h) per difference level."""
    p = rng.uniform(-20, 20, (3, 300)).astype(np.float32)
    tol1 = C_WARP_ABS / H  # one difference level
    cases = [("vc-2.22", tuple(p), {}, tol1), ("vc-2.23", tuple(p), {"seed": 3, "period": 7}, 2 * tol1),
             ("vc-2.24", tuple(p[:2]), {}, 2 * tol1), ("vc-2.25", tuple(p), {}, 3 * tol1),
             ("vc-2.26", tuple(p[:, :60]), {"variant": "thesis"}, 6 * tol1 / H),
             ("vc-2.26", tuple(p[:, :60]), {}, 6 * tol1 / H), ("vc-A7", tuple(p[:2]), {"h": 0.01}, C_WARP_ABS / 0.01)]
    for cid, args, kw, tol in cases:
        assert_twins_agree(cid, *args, **kw, atol=tol)


@pytest.mark.spec("vc-2.23", "vc-A7")
def test_curl_noise_periodic_with_period(rng):
    pts = (rng.integers(-1000, 1000, (3, 300)) / 64.0).astype(np.float32)
    v = pywarp.noise_curl3(*pts, period=8)
    sh = pts.copy()
    sh[0] += 8
    # the offsets (dyadic) and the step 1/256 keep every sample point exact under the shift
    np.testing.assert_array_equal(pywarp.noise_curl3(*sh, period=8), v)
    np.testing.assert_array_equal(pywarp.noise_curl2(pts[0], pts[1] - 8, period=8),
                                  pywarp.noise_curl2(pts[0], pts[1], period=8))


# ---------------------------------------------------------------------------------------------------------------------
# Perlin-Worley vc-A8
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A8", "vc-2.27")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_perlin_worley_combinations_closed_forms(impl):
    pw = pywarp.equation("vc-A8", impl=impl)
    P, W = np.meshgrid(np.linspace(0, 1, 41), np.linspace(0, 1, 41))
    Pd, Wd = f32(P), f32(W)
    expected = {
        "thesis": (Wd + Pd * (1 - Wd)) ** 2,  # remap(P, 0, 1, W, 1)^2 (the cataloguer's expansion)
        "hillaire": Wd + Pd * (1 - Wd),
        "gpu_pro_7": np.where(Wd < 1, np.clip((Pd - Wd) / np.where(Wd < 1, 1 - Wd, 1), 0, 1), 0.0),
        "product": Pd * Wd,
        "average": (Pd + Wd) / 2,
    }
    for name, ref in expected.items():
        got = pw(P, W, combination=name)
        assert got.min() >= 0 and got.max() <= 1, name
        # a remap (subtraction, division, product, sum) and a square: <= 8 roundings at magnitude <= 1; the
        # gpu_pro_7 division by 1 - W (>= 1/40 here) amplifies the 2-ulp error of P - W by up to 40
        tol = 8 * EPS32 * (40 if name == "gpu_pro_7" else 1)
        np.testing.assert_allclose(got, ref, rtol=0, atol=tol, err_msg=name)
    assert pw(0.5, 0.2) == pytest.approx(0.36, abs=1e-7)  # default = thesis
    assert pw(0.3, 1.0, combination="gpu_pro_7") == 0.0  # W = 1: the limit of the clamped form
    # the thesis' default lies in [W^2, 1]; gpu_pro_7 is 0 wherever P <= W
    t = pw(P, W)
    assert np.all(t >= (Wd ** 2) * (1 - 1e-6)) and np.all(t <= 1)
    assert np.all(pw(P, W, combination="gpu_pro_7")[Pd <= Wd] == 0)


@pytest.mark.spec("vc-A8")
def test_perlin_worley_c_and_warp_agree(rng):
    """Identical float32 expressions without contraction: within the entry's 2 ulp (observed 0)."""
    t = rng.uniform(0, 1, 2000).astype(np.float32)
    w = rng.uniform(0, 1, 2000).astype(np.float32)
    for k in knoise.COMBINATIONS:
        assert_twins_agree("vc-A8", t, w, combination=k)


# ---------------------------------------------------------------------------------------------------------------------
# Bad input
# ---------------------------------------------------------------------------------------------------------------------

@pytest.mark.spec("vc-A1", "vc-A2", "vc-A3", "vc-A5", "vc-2.21", "vc-A6", "vc-2.23", "vc-2.26", "vc-A8")
@pytest.mark.parametrize("impl", ["warp", "c"])
def test_noise_bad_input_raises_value_error_naming_parameter(impl):
    def eq(cid):
        return pywarp.equation(cid, impl=impl)

    with pytest.raises(ValueError, match=r"^x must be finite"):
        eq("vc-A1")(np.nan, 0.0, 0.0)
    with pytest.raises(ValueError, match=r"^seed must be in \[0, 4294967295\] \(uint32\), got -1"):
        eq("vc-A1")(0.5, 0.5, 0.5, seed=-1)
    with pytest.raises(ValueError, match=r"^seed must be in"):
        eq("vc-A1")(0.5, 0.5, 0.5, seed=2 ** 32)
    with pytest.raises(ValueError, match=r"^seed must hold integers"):
        eq("vc-A1")(0.5, 0.5, 0.5, seed=1.5)
    with pytest.raises(ValueError, match=r"^period must be in \[0, "):
        eq("vc-A1")(0.5, 0.5, 0.5, period=-1)
    with pytest.raises(ValueError, match=r"^period must be in \[1, "):
        eq("vc-A2")(0.5, 0.5, 0.5, 0)
    with pytest.raises(ValueError, match=r"^z must be in"):
        eq("vc-A1")(0.5, 0.5, 3e7)
    with pytest.raises(ValueError, match=r"^cells must be in \[1, "):
        eq("vc-A3")(0.5, 0.5, 0.5, 0)
    with pytest.raises(ValueError, match=r"^metric must be one of 'euclidean', 'manhattan', got 'chebyshev'"):
        eq("vc-A3")(0.5, 0.5, 0.5, 4, metric="chebyshev")
    with pytest.raises(ValueError, match=r"^inverse must be one of"):
        eq("vc-A3")(0.5, 0.5, 0.5, 4, inverse="yes")
    with pytest.raises(ValueError, match=r"^cells \* \|x\|, \|y\|, \|z\| must be < 2\^24"):
        eq("vc-A3")(2e6, 0.5, 0.5, 64)
    with pytest.raises(ValueError, match=r"^cells must be in \[1, 64\]"):
        eq("vc-A5")(0.5, 0.5, 0.5, 65)
    with pytest.raises(ValueError, match=r"^octaves must be in \[1, 24\]"):
        eq("vc-2.21")(0.5, 0.5, 0.5, 0, 1.0)
    with pytest.raises(ValueError, match=r"^frequency must be in \(0, 1\.67772e\+07\]"):
        eq("vc-2.21")(0.5, 0.5, 0.5, 3, 0.0)
    with pytest.raises(ValueError, match=r"^period must satisfy"):
        eq("vc-2.21")(0.5, 0.5, 0.5, 20, 1.0, period=2 ** 20)
    with pytest.raises(ValueError, match=r"^cells must satisfy"):
        eq("vc-A6")(0.5, 0.5, 0.5, 16, 4)
    with pytest.raises(ValueError, match=r"^h must be in \(0, 0\.25\]"):
        eq("vc-2.23")(0.5, 0.5, 0.5, h=0.0)
    with pytest.raises(ValueError, match=r"^variant must be one of 'corrected', 'thesis'"):
        eq("vc-2.26")(0.5, 0.5, 0.5, variant="printed")
    with pytest.raises(ValueError, match=r"^combination must be one of 'thesis', 'gpu_pro_7'"):
        eq("vc-A8")(0.5, 0.5, combination="screen")
    with pytest.raises(ValueError, match=r"^p must be in \[0, 1\]"):
        eq("vc-A8")(1.5, 0.5)
    with pytest.raises(ValueError, match=r"do not broadcast: x\(2,\), y\(3,\)"):
        eq("vc-A1")([0.1, 0.2], [0.1, 0.2, 0.3], 0.0)
    with pytest.raises(TypeError, match=r"noise_perlin3\(\): missing a required argument: 'z'"):
        eq("vc-A1")(0.1, 0.2)


@pytest.mark.spec("vc-A1")
def test_noise_helpers_bad_input():
    with pytest.raises(ValueError, match=r"^interp must be one of"):
        host_noise.perlin2(0.5, 0.5, interp="smooth")
    with pytest.raises(ValueError, match=r"^seed must be in"):
        knoise.perm_table(-3)
    with pytest.raises(TypeError, match=r"^seed must be an integer"):
        knoise.perm_array(1.5)
    with pytest.raises(ValueError, match=r"^period must be a scalar"):
        host_noise.perlin2(0.5, 0.5, period=[1, 2])


@pytest.mark.spec("vc-A1", "vc-A3")
def test_noise_shapes_broadcast_and_scalars():
    out = pywarp.noise_perlin3(np.zeros((3, 1)) + 0.5, np.array([0.1, 0.2]), 0.3)
    assert out.shape == (3, 2) and out.dtype == np.float32
    assert np.ndim(pywarp.noise_perlin3(0.1, 0.2, 0.3)) == 0
    assert pywarp.noise_perlin3(np.zeros((0,)), 0.5, 0.5).shape == (0,)
    v = pywarp.noise_curl3(np.zeros((2, 2)), 0.5, 0.5)
    assert v.shape == (2, 2, 3) and v.dtype == np.float32
    assert pywarp.noise_curl2(0.3, 0.5).shape == (2,) and pywarp.noise_gradient3(0.1, 0.2, 0.3).shape == (3,)
    assert pywarp.noise_worley3(np.zeros((4, 1)), np.zeros(3), 0.5, 4).shape == (4, 3)
