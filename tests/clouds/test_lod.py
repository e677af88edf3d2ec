"""The cloudscape's level of detail: mip chains (ccl_cloudscape_mip3 / mip_chain), the mip level of a footprint
(ccl_cloudscape_lod / cloudscape_lod) and the density at a level (ccl_cloudscape_density_lod /
cloudscape_density_lod), against closed forms and against each other."""
from __future__ import annotations

import numpy as np
import pytest
import warp as wp

from pywarp.core.binding import ffi, lib
from pywarp.clouds import cloudscape as C
from pywarp.kernels import cloudscape as K


def _volume(n: int, seed: int = 1) -> np.ndarray:
    return np.random.default_rng(seed).random((n, n, n, 4), dtype=np.float32)


def _c_mips(tex: np.ndarray) -> np.ndarray:
    f, lb = ffi(), lib()
    n = tex.shape[0]
    length = lb.ccl_cloudscape_mip3_len(n)
    out = np.empty(length, dtype=np.float32)
    status = lb.ccl_cloudscape_mip3(f.from_buffer("float[]", np.ascontiguousarray(tex)), n,
                                    f.from_buffer("float[]", out), length)
    assert status == 0
    return out.reshape(-1, 4)


@pytest.mark.parametrize("n", [1, 2, 8, 32])
def test_mip_chain_levels_are_box_means_in_c_and_numpy_alike(n):
    tex = _volume(n)
    chain = C.mip_chain(tex)
    assert chain.shape == (sum((n >> k) ** 3 for k in range(C.mip_levels(n))), 4)
    # C and NumPy: the same sums in the same order, bit for bit
    if n > 1:
        np.testing.assert_array_equal(_c_mips(tex), chain[n ** 3:])
    # independent: every level is the float64 box mean of level 0 over 2^k-wide blocks; the last level is the mean
    off = 0
    for k in range(C.mip_levels(n)):
        m = n >> k
        level = chain[off:off + m ** 3].reshape(m, m, m, 4)
        ref = tex.astype(np.float64).reshape(m, n // m, m, n // m, m, n // m, 4).mean(axis=(1, 3, 5))
        np.testing.assert_allclose(level, ref, rtol=0, atol=1e-6)
        off += m ** 3
    np.testing.assert_allclose(chain[-1], tex.astype(np.float64).mean(axis=(0, 1, 2)), atol=1e-6)


def test_mip3_refuses_bad_sizes_and_lengths():
    f, lb = ffi(), lib()
    tex = np.zeros(27 * 4, dtype=np.float32)
    out = np.zeros(64, dtype=np.float32)
    assert lb.ccl_cloudscape_mip3_len(3) == 0 and lb.ccl_cloudscape_mip3_len(8192) == 0
    assert lb.ccl_cloudscape_mip3(f.from_buffer("float[]", tex), 3, f.from_buffer("float[]", out), 4) != 0
    assert lb.ccl_cloudscape_mip3_len(4) == 4 * (8 + 1)
    assert lb.ccl_cloudscape_mip3(f.from_buffer("float[]", tex), 4, f.from_buffer("float[]", out), 35) != 0


@wp.kernel
def _lod_kernel(fp: wp.array(dtype=float), texel: wp.array(dtype=float), bias: float, out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = K.cloudscape_lod(fp[i], texel[i], bias)


def test_lod_is_log2_of_footprint_over_texel_plus_bias_in_c_and_warp():
    fp = np.array([0.047, 0.094, 0.4, 3.0, 0.0, -1.0, np.nan], dtype=np.float32)
    texel = np.full(len(fp), 0.047, dtype=np.float32)
    out = wp.zeros(len(fp), dtype=float)
    wp.launch(_lod_kernel, dim=len(fp), inputs=[wp.array(fp), wp.array(texel), 0.5], outputs=[out])
    warp = out.numpy()
    c = np.array([lib().ccl_cloudscape_lod(float(a), float(b), 0.5) for a, b in zip(fp, texel)], dtype=np.float32)
    expect = np.where(fp > 0, np.log2(np.where(fp > 0, fp, 1) / texel.astype(np.float64)) + 0.5, 0.0)
    np.testing.assert_allclose(c, expect, atol=1e-5)
    np.testing.assert_allclose(warp, expect, atol=1e-5)
    assert c[0] == pytest.approx(0.5, abs=1e-6) and c[1] == pytest.approx(1.5, abs=1e-6)  # one texel, two texels


@wp.kernel
def _mip_kernel(tex: wp.array(dtype=wp.vec4), size: int, levels: int, lod: float, pts: wp.array(dtype=wp.vec3),
                out: wp.array(dtype=wp.vec4)):
    i = wp.tid()
    out[i] = K.sample_mip(tex, size, levels, lod, pts[i])


def test_sampling_at_a_level_blends_the_two_nearest_levels():
    n = 16
    tex = _volume(n, 5)
    chain = wp.array(C.mip_chain(tex), dtype=wp.vec4)
    pts_np = np.random.default_rng(2).uniform(-3, 3, (64, 3)).astype(np.float32)
    pts = wp.array(pts_np, dtype=wp.vec3)

    def at(lod):
        out = wp.zeros(len(pts_np), dtype=wp.vec4)
        wp.launch(_mip_kernel, dim=len(pts_np), inputs=[chain, n, C.mip_levels(n), lod, pts], outputs=[out])
        return out.numpy()

    # level 0 (and any lod <= 0) is the plain trilinear sample of the texture: the C sampler's values
    f, lb = ffi(), lib()
    buf = f.from_buffer("float[]", np.ascontiguousarray(tex))
    r, g, b, a = (f.new("float *") for _ in range(4))
    ref = []
    for x, y, z in pts_np:
        lb.ccl_texgen_sample_trilinear_wrap(buf, n - 1, float(x), float(y), float(z), r, g, b, a)
        ref.append((r[0], g[0], b[0], a[0]))
    np.testing.assert_allclose(at(0.0), np.array(ref), rtol=0, atol=1e-6)
    np.testing.assert_array_equal(at(0.0), at(-2.0))
    # the last level is the texture's mean everywhere, and beyond it nothing changes
    np.testing.assert_allclose(at(4.0), np.broadcast_to(tex.astype(np.float64).mean(axis=(0, 1, 2)), (64, 4)),
                               atol=1e-6)
    np.testing.assert_array_equal(at(9.0), at(4.0))
    # a fractional level is the linear blend of its two neighbours
    np.testing.assert_allclose(at(1.25), 0.75 * at(1.0) + 0.25 * at(2.0), atol=1e-6)
