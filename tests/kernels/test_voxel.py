"""The 3-D cloud array of the oc text (§5.2): the exponential filter (oc-5.2.2: range, monotonicity in cover and
sharpness, sharpness outside (0, 1) refused), the SIN window (oc-5.2.3.1), the level build written out in float64
(oc-5.2.1), the border problem reproduced and removed by the zero-border larger array (oc-5.2.3, oc-5.2.3.2), the
persistence schedules in the volume, determinism (same seed -> same volume, any thread count), per-axis scaling
(oc-5.2.3-scale), C vs Warp, and the benchmark function."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree
from pywarp.core.runtime import TileLauncher
from pywarp.flight.clouds import (CloudArraySettings, bench_cloud_array, cloud_volume, noise_volume, scale_volume,
                                  scaled_shape)

filt = pywarp.equation("oc-5.2.2")
sin_window = pywarp.equation("oc-5.2.3.1")
smooth = pywarp.equation("oc-5.1.3")
amplitude = pywarp.equation("oc-5.1.2.2")


def _faces(v):
    return np.concatenate([v[0].ravel(), v[-1].ravel(), v[:, 0].ravel(), v[:, -1].ravel(), v[:, :, 0].ravel(),
                           v[:, :, -1].ravel()])


@pytest.mark.spec("oc-5.2.2")
def test_filter_closed_form_and_range():
    n = np.linspace(0, 1, 101).astype(np.float32).astype(np.float64)
    for cover in (0.0, 64.0, 128.0, 200.0):
        for s in (0.5, 0.9, 0.99):
            c = np.maximum(n * 255 - cover, 0.0)
            ref = 255 * (1 - s ** c)
            # float32: c = n*255 - cover carries up to 2 roundings of values < 256 (2^-16 each), which move
            # 255 s^c by 255 |ln s| s^c dc; then the powf and the subtraction (a few ulp of 255)
            tol = 255 * abs(np.log(s)) * s ** c * 2 * 2.0 ** -16 + 1e-4
            assert np.all(np.abs(filt(n, cover, s) - ref) <= tol)
            d = filt(n, cover, s)
            assert d.min() >= 0.0 and d.max() <= 255.0
            assert np.all(d[n * 255 <= cover] == 0.0)  # at or below the threshold: invisible


@pytest.mark.spec("oc-5.2.2")
def test_filter_monotonic_in_cover_and_sharpness():
    n = np.linspace(0, 1, 41)[:, None]
    covers = np.linspace(0, 255, 35)[None, :]
    d = filt(n, covers, 0.95)
    assert np.all(np.diff(d, axis=1) <= 0)  # a LARGER cover gives LESS cloud (the text's label reads inverted)
    assert np.all(np.diff(d, axis=0) >= 0)  # denser noise, denser cloud
    sharp = np.linspace(0.01, 0.99, 50)[None, :]
    d = filt(n, 50.0, sharp)
    assert np.all(np.diff(d, axis=1) <= 0)  # sharpness near 0: hard edges (jumps to ~255), near 1: soft


@pytest.mark.spec("oc-5.2.2")
@pytest.mark.parametrize("bad", [0.0, 1.0, 1.5, -0.2, np.nan])
def test_sharpness_outside_0_1_refused(bad):
    with pytest.raises(ValueError, match="sharpness"):
        filt(0.5, 100.0, bad)
    with pytest.raises(ValueError, match="sharpness"):
        CloudArraySettings(sharpness=bad)


@pytest.mark.spec("oc-5.2.3.1")
def test_sin_window():
    assert sin_window(0, 8.0) == 0.0
    assert sin_window(8, 8.0) == 1.0 and sin_window(200, 8.0) == 1.0
    d = np.arange(8)
    np.testing.assert_allclose(sin_window(d, 8.0), np.sin(np.pi / 2 * d / 8), atol=1e-7)
    assert_twins_agree("oc-5.2.3.1", np.arange(40), np.float32(13.5))


def _upsample_linear(a, nf):
    """Corner-aligned trilinear up-sampling in float64 (independent of voxel.c/voxel.py)."""
    nc = a.shape[0]
    pos = np.arange(nf) * (nc - 1) / (nf - 1)
    i0 = np.minimum(np.floor(pos).astype(int), nc - 2)
    t = pos - i0
    for axis in range(3):
        lo = np.take(a, i0, axis=axis)
        hi = np.take(a, i0 + 1, axis=axis)
        shape = [1, 1, 1]
        shape[axis] = nf
        a = lo * (1 - t.reshape(shape)) + hi * t.reshape(shape)
    return a


def _level_noise(n, seed_l, smoothing):
    z, y, x = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
    return np.asarray(smooth(x, y, z, seed_l, 3, smoothing=smoothing), np.float64)


@pytest.mark.spec("oc-5.2.1", "oc-5.1.2.2")
@pytest.mark.parametrize("variant", ["corrected", "thesis"])
def test_level_build_written_out(variant):
    """size/2 -> size with added noise, border none: n = (U(a0 N0) + a1 N1) / (a0 + a1), trilinear U."""
    from pywarp.kernels.valuenoise import octave_seed

    s = CloudArraySettings(size=16, levels=2, seed=4, border="none", persistence=0.6, variant=variant)
    a0, a1 = (np.float64(amplitude(i, 0.6, variant=variant)) for i in range(2))
    n0 = _level_noise(8, octave_seed(4, 0), "elias")
    n1 = _level_noise(16, octave_seed(4, 1), "elias")
    ref = np.clip((_upsample_linear(a0 * n0, 16) + a1 * n1) / (a0 + a1), 0, 1)
    np.testing.assert_allclose(noise_volume(s), ref, atol=1e-6)
    # one level: the smoothed lattice itself (the base array of random noise)
    one = noise_volume(dataclasses.replace(s, levels=1, size=8))
    np.testing.assert_allclose(one, n0, atol=1e-7)


@pytest.mark.spec("oc-5.2.1", "oc-5.1.2.2")
def test_volume_persistence_schedules_differ():
    a = noise_volume(size=32, variant="corrected")
    b = noise_volume(size=32, variant="thesis")
    assert not np.array_equal(a, b)
    # the thesis schedule (p, p^2, p^4, p^8) weights the fine levels less: a smoother volume
    assert np.abs(np.diff(b, axis=2)).mean() < np.abs(np.diff(a, axis=2)).mean()


@pytest.mark.spec("oc-5.2.3", "oc-5.2.3.1", "oc-5.2.3.2", "oc-5.2.1")
@pytest.mark.parametrize("interpolation", ["linear", "cosine", "cubic"])
def test_larger_array_zeroes_the_faces_and_the_border_problem_is_reproduced(interpolation):
    s = CloudArraySettings(size=32, seed=7, cover=100.0, interpolation=interpolation)
    zero = cloud_volume(s)
    assert zero.dtype == np.uint8 and zero.shape == (32, 32, 32)
    assert np.all(_faces(zero) == 0)  # after the larger-array build and filtering, every outer-face voxel is 0
    assert np.count_nonzero(zero) > 0.05 * zero.size  # ... and there is a cloud inside
    cut = cloud_volume(dataclasses.replace(s, border="none"))
    assert np.count_nonzero(_faces(cut)) > 0  # without it, the cloud is cut by the box (fig. 5.12)
    rounded = cloud_volume(dataclasses.replace(s, border="sin"))
    assert np.all(_faces(rounded) == 0)
    # the zero border of every level: the noise falls off toward the faces, the cloud is compact
    noise = noise_volume(s)
    assert np.all(_faces(noise) == 0.0)
    assert noise[1:-1, 1:-1, 1].mean() < 0.5 * noise[12:20, 12:20, 12:20].mean()


@pytest.mark.spec("oc-5.2.1", "oc-5.2.2")
def test_same_seed_same_volume_any_thread_count():
    s = CloudArraySettings(size=32, seed=11)
    a = cloud_volume(s)
    assert np.array_equal(a, cloud_volume(s))
    assert np.array_equal(a, cloud_volume(s, launcher=TileLauncher(workers=1)))
    assert np.array_equal(a, cloud_volume(s, launcher=TileLauncher(workers=3, bands_per_worker=7)))
    assert not np.array_equal(a, cloud_volume(s, seed=12))
    assert np.array_equal(cloud_volume(s, impl="c"), cloud_volume(s, impl="c"))


@pytest.mark.spec("oc-5.2.1", "oc-5.2.2", "oc-5.2.3.1")
@pytest.mark.parametrize("interpolation", ["linear", "cosine", "cubic"])
@pytest.mark.parametrize("border", ["zero", "sin", "none"])
def test_c_and_warp_build_the_same_volume(interpolation, border):
    s = CloudArraySettings(size=32, seed=5, interpolation=interpolation, border=border, smoothing="8-neighbour")
    np.testing.assert_allclose(noise_volume(s), noise_volume(s, impl="c"), rtol=0, atol=4e-7)
    w, c = cloud_volume(s), cloud_volume(s, impl="c")
    assert np.abs(w.astype(int) - c).max() <= 1  # powf of two libms; rounding to uint8 may differ by one
    assert np.mean(w != c) < 1e-3


@pytest.mark.spec("oc-5.2.2")
def test_cover_and_sharpness_in_the_volume():
    base = CloudArraySettings(size=32, seed=2)
    amounts = [np.count_nonzero(cloud_volume(base, cover=c)) for c in (90.0, 110.0, 130.0)]
    assert amounts[0] > amounts[1] > amounts[2]  # more cover, less cloud
    soft = cloud_volume(base, sharpness=0.99).astype(float).sum()
    hard = cloud_volume(base, sharpness=0.5).astype(float).sum()
    assert hard > soft


@pytest.mark.spec("oc-5.2.3-scale")
def test_per_axis_scaling():
    vol = cloud_volume(size=32, seed=3)
    assert np.array_equal(scale_volume(vol, (1, 1, 1)), vol)  # identity
    flat = scale_volume(vol, (1.5, 1.25, 0.5))
    assert flat.shape == scaled_shape(vol.shape, (1.5, 1.25, 0.5)) == (16, 40, 48)
    assert np.all(_faces(flat) == 0)  # faces map onto faces: the zero border stays zero
    assert np.count_nonzero(flat) > 0
    assert np.array_equal(flat, scale_volume(vol, (1.5, 1.25, 0.5), impl="c"))
    assert np.array_equal(pywarp.equation("oc-5.2.3-scale")(vol, (1.5, 1.25, 0.5)), flat)
    # a corner-aligned factor-2 up-scaling keeps every original voxel at even indices
    up = scale_volume(vol[:9, :9, :9], (17 / 9, 17 / 9, 17 / 9))
    assert up.shape == (17, 17, 17) and np.array_equal(up[::2, ::2, ::2], vol[:9, :9, :9])
    with pytest.raises(ValueError, match="scale"):
        scale_volume(vol, (1, 0, 1))
    with pytest.raises(ValueError, match="volume"):
        scale_volume(vol.astype(np.float32), (1, 1, 1))


@pytest.mark.spec("oc-5.2.1")
def test_settings_are_validated_naming_the_field():
    with pytest.raises(ValueError, match="size"):
        CloudArraySettings(size=60)  # not a multiple of 2^(levels - 1) = 8
    with pytest.raises(ValueError, match="size"):
        CloudArraySettings(size=24)  # base 3 < 4
    with pytest.raises(ValueError, match="cover"):
        CloudArraySettings(cover=300.0)
    with pytest.raises(ValueError, match="border"):
        CloudArraySettings(border="wrap")
    with pytest.raises(ValueError, match="persistence"):
        cloud_volume(persistence=0.0)
    with pytest.raises(TypeError, match="settings"):
        cloud_volume({"size": 32})
    assert CloudArraySettings(size=64).level_sizes() == [8, 16, 32, 64]  # size/8 -> size


def test_settings_defaults_match_c():
    from pywarp.core.binding import ffi, lib
    from pywarp.kernels.valuenoise import INTERPOLATIONS, SMOOTHINGS
    from pywarp.kernels.voxel import BORDERS, VARIANTS

    c = lib().ccl_voxel_settings_default()
    s = CloudArraySettings()
    assert (c.size, c.levels, c.seed) == (s.size, s.levels, s.seed)
    assert (c.interpolation, c.smoothing, c.variant, c.border) == (
        INTERPOLATIONS[s.interpolation], SMOOTHINGS[s.smoothing], VARIANTS[s.variant], BORDERS[s.border])
    for f in ("persistence", "sin_radius", "cover", "sharpness"):
        assert getattr(c, f) == np.float32(getattr(s, f)), f
    assert ffi() is not None


def test_bench_cloud_array_reports_every_case():
    res = bench_cloud_array(sizes=(32,), interpolations=("linear", "cubic"), repeats=1, c_reference=True)
    assert set(res["cloud_array_ms"]) == {"linear", "cubic"}
    assert res["cloud_array_ms"]["cubic"]["32"] > 0 and res["c_ms"]["linear"]["32"] > 0
    assert res["cubic_over_linear"]["32"] > 0
    with pytest.raises(ValueError, match="interpolations"):
        bench_cloud_array(interpolations=("bicubic",))
