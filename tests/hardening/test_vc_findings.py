"""Issue 14 (hardening), the vc findings: one test per finding, each failing on the code before its fix (or, where
the platform issue fixed it first, pinning the fix). C functions are called through the cffi binding; Python entries
through the registry, both implementations."""
from __future__ import annotations

import math
import os
import subprocess
import sys
import threading
import warnings
from dataclasses import replace

import numpy as np
import pytest

import pywarp
from pywarp.core.binding import ffi, lib

IMPLS = ("warp", "c")


def _f32(x):
    return float(np.float32(x))


# --- validation before the cast (fixed by the platform issue; pinned here) -------------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
def test_float64_beyond_float32_refused_before_the_cast(impl):
    with pytest.raises(ValueError, match=r"^t_a must be within the float32 range"):
        pywarp.equation("vc-2.7", impl=impl)(1e39, 1e39)


@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("cid, args", [("vc-4.1", (2 ** 32 + 3, 0, 0)), ("vc-A18", (0.5, 2 ** 32 + 64, 2 ** 32 + 128)),
                                       ("vc-A23", ([0.0, 0.0, -1.0], 2 ** 32 + 1, 0, 0))])
def test_int64_beyond_int32_refused_not_wrapped(impl, cid, args):
    with pytest.raises(ValueError, match=r"must be in \["):
        pywarp.equation(cid, impl=impl)(*args)


def test_settings_refuse_bool_and_fractional_integers_and_overflow_in_advanced():
    from pywarp.clouds.settings import CloudscapeSettings

    with pytest.raises(TypeError, match=r"^samples_min must be an integer, got True"):
        CloudscapeSettings(samples_min=True)
    with pytest.raises(TypeError, match=r"^samples_min must be an integer, got 3.5"):
        CloudscapeSettings(samples_min=3.5)
    with pytest.raises(ValueError):  # not OverflowError
        CloudscapeSettings(advanced={"samples_min": 2 ** 40})


# --- Henyey-Greenstein total on its open domain -----------------------------------------------------------------------

def _hg64(c, g):
    return (1.0 - g * g) / (4.0 * math.pi * (1.0 + g * g - 2.0 * g * c) ** 1.5)


@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("c, g", [(-1.0, -0.999999), (1.0, 0.999999), (-1.0, _f32(np.nextafter(np.float32(-1), 0))),
                                  (1.0, _f32(np.nextafter(np.float32(1), 0))), (0.3, -0.9999)])
def test_hg_finite_and_accurate_near_the_open_ends(impl, c, g):
    p = float(pywarp.equation("vc-2.13", impl=impl)(c, g))
    g32 = _f32(g)
    assert math.isfinite(p) and p > 0.0
    assert p == pytest.approx(_hg64(c, g32), rel=1e-5)


# --- curl noise: steps below half an ulp of the coordinate ------------------------------------------------------------

@pytest.mark.parametrize("impl", IMPLS)
@pytest.mark.parametrize("cid, args", [("vc-A7", (3.0e6, -2.5e6)), ("vc-2.23", (3.0e6, 1.0, -2.5e6)),
                                       ("vc-2.22", (3.0e6, 1.0, -2.5e6)), ("vc-2.24", (3.0e6, -2.5e6)),
                                       ("vc-2.25", (3.0e6, 1.0, -2.5e6)), ("vc-2.26", (3.0e6, 1.0, -2.5e6))])
def test_curl_finite_for_steps_below_the_coordinates_ulp(impl, cid, args):
    out = pywarp.equation(cid, impl=impl)(*args, h=1e-6)
    out = out if isinstance(out, tuple) else (out,)
    for o in out:
        assert np.all(np.isfinite(o)), (cid, o)


@pytest.mark.parametrize("impl", IMPLS)
def test_curl_texture_with_a_tiny_step_is_finite(impl):
    from pywarp.clouds import textures as T

    s = T.CurlNoiseSettings(size=16, frequency=4096, fd_step=1e-30)
    tex = T.generate("curl_noise", s, impl=impl)
    assert np.all(np.isfinite(tex))


def test_curl_default_step_unchanged_on_the_texture_range():
    # the step floor |x| 2^-22 stays below the default 2^-8 up to |x| = 2^14: every texel of a 4096-cell texture
    # keeps its value (C vs float64 central difference of the same noise, at the largest coordinates)
    v = pywarp.equation("vc-A7", impl="c")(4095.75, 4095.25, h=1.0 / 256)
    w = pywarp.equation("vc-A7")(4095.75, 4095.25, h=1.0 / 256)
    assert np.array_equal(v, w)


# --- samplers: NaN and huge coordinates never reach an int conversion -------------------------------------------------

@pytest.mark.parametrize("coord", [float("nan"), 1e30, -1e30, 8388608.0])
def test_samplers_return_nan_outside_their_domain(coord):
    F, L = ffi(), lib()
    tex = np.arange(4 * 4 * 4 * 4, dtype=np.float32) / 256
    out = F.new("float[4]")
    L.ccl_texgen_sample_trilinear_wrap(F.cast("const float *", F.from_buffer("float[]", tex)), 3, 0.1, coord,
                                       0.2, out + 0, out + 1, out + 2, out + 3)
    assert all(math.isnan(out[i]) for i in range(4))
    tex2 = tex[: 4 * 4 * 4].copy()
    out2 = F.new("float[4]")
    L.ccl_cloudscape_sample_bilinear_wrap(F.cast("const float *", F.from_buffer("float[]", tex2)), 3,
                                          coord / 4 if math.isfinite(coord) else coord, 0.3, out2)
    assert all(math.isnan(out2[i]) for i in range(4))


# --- ccl_cloudscape_check: texture coordinates below 2^23, sun tolerance ----------------------------------------------

SIZES = {"base": 128, "detail": 32, "curl": 128, "weather": 512}


@pytest.mark.parametrize("field, value", [("base_scale_km", 1e-3), ("curl_scale_km", 1e-3),
                                          ("weather_offset", (1e30, 0.0)), ("curl_strength_km", 1e30),
                                          ("detail_offset", (0.0, -1e9, 0.0)), ("weather_scale_km", 1e-4)])
def test_cloudscape_check_bounds_texture_coordinates(field, value):
    from pywarp.clouds.settings import CloudscapeSettings

    s = CloudscapeSettings(**{f"{k}_size": v for k, v in SIZES.items()})
    values = s.c_values()
    s.c_params(values)  # the defaults pass
    values[field] = value
    with pytest.raises(ValueError, match=r"out of range \(ccl_cloudscape_check"):
        s.c_params(values)


def test_cloudscape_check_passes_at_the_largest_sizes_time_and_wind():
    from pywarp.clouds.settings import MAX_SIZE_2D, MAX_SIZE_3D, MAX_TIME_S, CloudscapeSettings

    for t in (MAX_TIME_S, -MAX_TIME_S):
        CloudscapeSettings(base_size=MAX_SIZE_3D, detail_size=MAX_SIZE_3D, curl_size=MAX_SIZE_2D,
                           weather_size=MAX_SIZE_2D, time_s=t, wind_speed_kmh=1000.0,
                           wind_direction_deg=45.0).c_params()


def test_settings_with_coordinates_beyond_the_bound_refused_before_rendering():
    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.clouds.settings import CloudscapeSettings

    with pytest.raises(ValueError, match=r"^detail_scale_km is out of range"):
        CloudscapeSettings(width=8, height=8, base_size=16, detail_size=8, curl_size=16, weather_size=16,
                           advanced={"detail_scale_km": 1e-4})
    # in range at the settings' defaults, beyond at the largest detail texture: checked at the real sizes
    s = CloudscapeSettings(width=8, height=8, base_size=16, detail_size=8, curl_size=16, weather_size=16,
                           advanced={"detail_scale_km": 0.2})
    with pytest.raises(ValueError, match=r"^detail_scale_km is out of range"):
        CloudscapeSettings(**{**{f: getattr(s, f) for f in ("width", "height", "base_size", "curl_size",
                                                             "weather_size")},
                              "detail_size": 512, "advanced": {"detail_scale_km": 0.2}})
    CloudscapeTechnique(replace(s, advanced={}))


def test_cloudscape_check_sun_tolerance_and_march_clamps_the_phase_argument():
    from pywarp.clouds.cloudscape import CLOUDSCAPE_PARAMS, RenderTextures
    from pywarp.clouds.settings import CloudscapeSettings

    F, L = ffi(), lib()
    s = CloudscapeSettings(base_size=16, detail_size=8, curl_size=16, weather_size=16)
    p = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    tex = RenderTextures.generate(s)
    from pywarp.clouds.cloudscape import c_textures

    t = c_textures(tex)
    sky = F.new("ccl_cloudscape_sky *")
    sky.kind = L.CCL_SKY_GRADIENT
    L.ccl_sky_gradient_defaults(F.addressof(sky.gradient))
    out = F.new("const char **")
    for n, ok in ((1.0009, True), (0.9991, True), (1.0011, False), (0.9989, False)):
        sky.sun[0], sky.sun[1], sky.sun[2] = 0.0, n, 0.0
        assert (L.ccl_cloudscape_check(p, t, sky, out) == 0) == ok, n
    # a sun 0.09 % too long, looking straight at it: dot(d, sun) > 1 reaches the phase function clamped to 1
    rgb, tr, ns = F.new("float[3]"), F.new("float *"), F.new("int *")
    L.ccl_cloudscape_march(p, t, (0.0, 2.0, 0.0), (0.0, 1.0, 0.0), (0.0, 1.0009, 0.0), 0.5, 0.0, rgb, tr, ns, F.NULL)
    assert all(math.isfinite(rgb[i]) for i in range(3)) and math.isfinite(tr[0])


# --- reprojection: bounded neighbourhood, no int overflow -------------------------------------------------------------

@pytest.mark.parametrize("n", [33, 46341, 10 ** 7])
def test_reproject_frame_neighbourhood_bounded_in_c_and_python(n):
    from pywarp.kernels.camera import camera_look_at

    F, L = ffi(), lib()
    img = np.zeros((4, 4, 1), np.float32)
    red = np.zeros((1, 1, 1), np.float32)
    m = F.new("float[16]", [1.0 if i % 5 == 0 else 0.0 for i in range(16)])
    buf = lambda a: F.from_buffer("float[]", a)  # noqa: E731
    st = L.ccl_reproj_frame(buf(img), buf(img.copy()), buf(red), 4, 4, 1, 0, m, (0.0, 0.0, 0.0), m,
                            (0.0, -6371.0, 0.0), 6372.5, n, 1, buf(img.copy()))
    assert st == L.CCL_EINVAL
    cam = camera_look_at((0.0, 0.002, 0.0), (0.0, 0.4, -1.0), aspect=1.0)
    for impl in IMPLS:
        with pytest.raises(ValueError, match=r"^neighbourhood must be an odd integer in \[1, 31\]"):
            pywarp.equation("vc-A27", impl=impl)(img, img, red, 0, cam, cam, neighbourhood=n)


def test_reproj_pixel_domain_and_sample_count_clamps():
    F, L = ffi(), lib()
    x, y = F.new("int *"), F.new("int *")
    L.ccl_reproj_pixel(L.CCL_REPROJ_MAX_ID, L.CCL_REPROJ_MAX_ID, 15, x, y)
    assert (x[0], y[0]) == (2 ** 31 - 1, 2 ** 31 - 1)
    for impl in IMPLS:
        with pytest.raises(ValueError, match=r"^id_x must be in \[0, "):
            pywarp.equation("vc-4.1", impl=impl)(L.CCL_REPROJ_MAX_ID + 1, 0, 0)
        with pytest.raises(ValueError, match=r"^n_max must be in \(-inf, 65536\]"):
            pywarp.equation("vc-A18", impl=impl)(0.5, 64, 2 ** 31 - 1)
    assert L.CCL_RAYMARCH_MAX_VIEW_SAMPLES == 65536
    # outside the documented domain the release build still returns a count in [n_min, n_max], never UB
    if os.environ.get("CCLOUDS_ASSERTS") != "1":
        assert L.ccl_raymarch_view_sample_count(0.0, 1, 2 ** 31 - 1) == 2 ** 31 - 1
        assert L.ccl_raymarch_view_sample_count(0.5, 2 ** 31 - 2, 2 ** 31 - 1) in (2 ** 31 - 2, 2 ** 31 - 1)


# --- bounded angles and times; no NaN image ---------------------------------------------------------------------------

@pytest.mark.parametrize("field, value", [("sun_azimuth_deg", 361.0), ("sun_azimuth_deg", 1e30), ("time_s", 10801.0),
                                          ("time_s", -1e6), ("camera_yaw_deg", 1e20), ("wind_direction_deg", -1e20),
                                          ("camera_x_km", 1e30), ("camera_z_km", -2000.0)])
def test_angles_times_positions_bounded(field, value):
    from pywarp.clouds.settings import CloudscapeSettings

    with pytest.raises(ValueError, match=rf"^{field} must be in \["):
        CloudscapeSettings(**{field: value})
    with pytest.raises(ValueError, match=rf"^{field} must be "):  # beyond float32: refused before any cast
        CloudscapeSettings(**{field: 1e300})


def test_largest_time_and_wind_still_render_finite_pixels():
    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.clouds.settings import MAX_TIME_S, CloudscapeSettings

    s = CloudscapeSettings(width=8, height=8, base_size=16, detail_size=32, curl_size=16, weather_size=512,
                           time_s=MAX_TIME_S, wind_speed_kmh=1000.0, sun_azimuth_deg=-360.0, samples_min=8,
                           samples_max=16)
    img = CloudscapeTechnique(s).render(reprojection=False)
    assert img.shape == (8, 8, 3)


def test_nan_pixels_raise_before_encoding_not_black():
    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.clouds.settings import CloudscapeSettings

    tech = CloudscapeTechnique(CloudscapeSettings(width=8, height=8, base_size=16, detail_size=8, curl_size=16,
                                                  weather_size=16, samples_min=8, samples_max=16, sky="gradient"))
    tech.sky.sun = np.array([np.nan, 1.0, 0.0], np.float32)  # a NaN that the sRGB encoding would clamp to 0
    with pytest.raises(RuntimeError, match=r"non-finite pixels .*nothing is written"):
        tech.render(reprojection=False)
    with pytest.raises(RuntimeError, match=r"non-finite pixels"):
        tech.render(reprojection=False, encode=False)


def _cli(*args, cwd):
    # the pywarp the tests import (installed, or PYTHONPATH's; conftest sets PYTHONSAFEPATH)
    return subprocess.run([sys.executable, "-m", "pywarp", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=300)


SMALL = ("--width", "8", "--height", "8", "--base-size", "16", "--detail-size", "8", "--curl-size", "16",
         "--weather-size", "16")


@pytest.mark.parametrize("option, value", [("--sun-azimuth", "1e30"), ("--time", "1e30"), ("--yaw", "1e30"),
                                           ("--wind-direction", "7200"), ("--camera-x", "1e30")])
def test_cli_render_extreme_angles_and_times_exit_2_one_line_no_file(tmp_path, option, value):
    res = _cli("render", "clouds", *SMALL, option, value, "--out", "x.png", cwd=tmp_path)
    assert res.returncode == 2, res.stderr
    last = res.stderr.strip().splitlines()
    assert len(last) == 1 and last[0].startswith(f"pywarp render: error: {option} must be in ["), res.stderr
    assert list(tmp_path.iterdir()) == []


def test_cli_animate_failed_encode_is_not_success(tmp_path):
    res = _cli("animate", "clouds", *SMALL, "--frames", "2", "--fps", "1e-6", "--out", "a.mp4", cwd=tmp_path)
    assert res.returncode != 0, res.stderr
    assert "wrote" not in res.stdout
    assert [p.name for p in tmp_path.iterdir()] == []


# --- texture cache ----------------------------------------------------------------------------------------------------

def _cache(tmp_path):
    from pywarp.clouds.textures import TextureCache

    return TextureCache(directory=tmp_path, memory=False)


def _entry(cache, settings):
    key = cache.key("curl_noise", settings, "c", "cpu")
    return cache.path("curl_noise", key)


def _get(cache, settings):
    from pywarp.clouds import textures as T

    return cache.get("curl_noise", settings, "c", "cpu", lambda: T.generate("curl_noise", settings, impl="c"))


def test_cache_fifo_entry_does_not_hang(tmp_path):
    from pywarp.clouds import textures as T

    s = T.CurlNoiseSettings(size=16)
    cache = _cache(tmp_path)
    path = _entry(cache, s)
    path.parent.mkdir(parents=True)
    os.mkfifo(path)
    result = {}
    th = threading.Thread(target=lambda: result.setdefault("a", _get(cache, s)), daemon=True)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        th.start()
        th.join(60)
    if th.is_alive():  # unblock the reader so that the test process can end
        fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
        os.close(fd)
        pytest.fail("reading a FIFO cache entry hangs")
    assert np.all(np.isfinite(result["a"]))
    assert any("not a regular file" in str(w.message) for w in rec)


def test_cache_symlink_to_a_device_is_refused(tmp_path):
    from pywarp.clouds import textures as T

    s = T.CurlNoiseSettings(size=16)
    cache = _cache(tmp_path)
    path = _entry(cache, s)
    path.parent.mkdir(parents=True)
    path.symlink_to("/dev/zero")
    with pytest.warns(T.TextureCacheWarning, match="not a regular file"):
        a = _get(cache, s)
    assert a.shape == (16, 16, 2)


@pytest.mark.parametrize("poison", [np.nan, 1e6])
def test_cache_entry_with_valid_hash_but_bad_values_is_regenerated_with_a_warning(tmp_path, poison):
    from pywarp.clouds import textures as T

    s = T.CurlNoiseSettings(size=16)
    cache = _cache(tmp_path)
    good = _get(cache, s).copy()
    bad = good.copy()
    bad[3, 4, 1] = poison
    cache._write("curl_noise", cache.key("curl_noise", s, "c", "cpu"), bad)  # a well-formed entry, valid hash
    with pytest.warns(T.TextureCacheWarning, match="corrupt texture cache entry"):
        again = _get(cache, s)
    assert np.array_equal(again, good)
    assert np.array_equal(_get(cache, s), good)  # the regenerated entry replaced the bad one


def test_generated_texture_with_nan_is_never_cached(tmp_path):
    from pywarp.clouds import textures as T

    s = T.CurlNoiseSettings(size=16)
    cache = _cache(tmp_path)
    with pytest.raises(RuntimeError, match="invalid"):
        cache.get("curl_noise", s, "c", "cpu", lambda: np.full(s.shape, np.nan, np.float32))
    assert not _entry(cache, s).exists()


def test_cache_write_interrupted_leaves_no_temporary(tmp_path, monkeypatch):
    from pywarp.clouds import textures as T
    from pywarp.core import output

    s = T.CurlNoiseSettings(size=16)
    cache = _cache(tmp_path)

    def interrupted(fd):
        assert output._LIVE, "the temporary is registered with pywarp.core.output"
        raise KeyboardInterrupt  # what the pywarp command raises on SIGTERM

    monkeypatch.setattr(T.os, "fsync", interrupted)
    with pytest.raises(KeyboardInterrupt):
        _get(cache, s)
    assert [p for p in tmp_path.rglob("*") if p.is_file()] == []


def test_sigterm_during_a_cache_write_leaves_no_temporary(tmp_path):
    # the pywarp command's SIGTERM handler raises in the main thread; the cache writer's temporary goes with it
    script = f"""
import os, signal, sys
from pywarp.clouds import textures as T
real = T.os.fsync
def slow(fd):
    os.kill(os.getpid(), signal.SIGTERM)
    real(fd)
T.os.fsync = slow
import pywarp.cli.main as M
s = T.CurlNoiseSettings(size=16)
cache = T.TextureCache(directory={str(tmp_path)!r}, memory=False)
signal.signal(signal.SIGTERM, M._raise_terminated)
try:
    cache.get("curl_noise", s, "c", "cpu", lambda: T.generate("curl_noise", s, impl="c"))
except BaseException as exc:
    print(type(exc).__name__)
"""
    res = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert "Terminated" in res.stdout or "KeyboardInterrupt" in res.stdout or res.returncode != 0, res
    assert [p for p in tmp_path.rglob("*") if p.is_file()] == [], res
