"""The clouds scene's settings (pywarp.clouds.settings): every Python default that mirrors a C ``*_default()`` is pinned
to the C value, the constants mirror the C headers, every field has a full spec, the weather map is declared once,
and a change invalidates what its spec says."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pywarp.clouds import settings as S
from pywarp.core.binding import ffi, lib
from pywarp.core.params import specs

SMALL = dict(width=32, height=18, base_size=16, detail_size=8, curl_size=16, weather_size=32)


def _c_default(kind: str):
    """The C defaults of ``ccl_<kind>_settings`` (the function's name with or without the header prefix)."""
    for name in (f"ccl_texgen_{kind}_settings_default", f"ccl_{kind}_settings_default"):
        if hasattr(lib(), name):
            return getattr(lib(), name)()
    raise AssertionError(f"no C default function for {kind}")


def _f32(x) -> float:
    return float(np.float32(x))


@pytest.mark.spec("vc-A13")
@pytest.mark.parametrize("kind", list(S.TEXTURE_SETTINGS))
def test_texture_settings_defaults_equal_the_c_defaults(kind):
    c = _c_default(kind)
    py = S.TEXTURE_SETTINGS[kind]()
    names = list(S.COMBINATION_NAMES)
    for p in specs(py):
        v, cv = getattr(py, p.name), getattr(c, p.name)
        if p.name == "combination":
            assert names.index(v) == cv
        elif p.kind == "floats":
            assert tuple(_f32(x) for x in v) == tuple(cv)
        elif p.kind == "float":
            assert _f32(v) == cv, p.name
        else:
            assert v == cv, p.name
    # and every C field has its Python twin
    assert {f[0] for f in ffi().typeof(c).fields} == {p.name for p in specs(py)}


@pytest.mark.spec("vc-A14", "vc-A36")
def test_cloudscape_defaults_equal_ccl_cloudscape_params_default():
    p = ffi().new("ccl_cloudscape_params *")
    lib().ccl_cloudscape_params_default(p)
    s = S.CloudscapeSettings()
    jitter = {name: getattr(lib(), f"CCL_JITTER_{name.upper()}") for name in S.JITTER_NAMES}
    assert (_f32(s.g), _f32(s.sigma_per_km)) == (p.g, p.sigma)
    assert _f32(s.sigma_per_km) == p.sigma_light
    assert (s.samples_min, s.samples_max) == (p.samples_min, p.samples_max)
    assert (s.adaptive_samples, s.early_exit, s.light_detail, s.beer, s.powder) == tuple(
        bool(x) for x in (p.adaptive_samples, p.early_exit, p.light_detail, p.beer, p.powder))
    assert jitter[s.jitter] == p.jitter_mode
    assert S.COVERAGE_THRESHOLD_NAMES.index(s.coverage_threshold) == p.coverage_threshold
    assert p.coverage_threshold == lib().CCL_COVERAGE_ONE_MINUS
    # the cloud layer: ccl_..._cloud_layer_default
    layer_default = next(getattr(lib(), n) for n in ("ccl_raymarch_cloud_layer_default", "ccl_cloud_layer_default")
                         if hasattr(lib(), n))
    layer = ffi().new("ccl_cloud_layer *")
    layer_default(layer)
    assert _f32(s.earth_radius_km) == layer.r_earth
    assert _f32(s.earth_radius_km + s.layer_base_km) == layer.r_inner
    assert _f32(s.earth_radius_km + s.layer_top_km) == layer.r_outer


def test_constants_mirror_the_c_headers_and_the_kernels():
    from pywarp.kernels import noise, raymarch, texgen

    for name in ("MIN_SIZE", "MAX_SIZE_3D", "MAX_SIZE_2D", "MAX_OCTAVES", "MAX_LATTICE"):
        assert getattr(S, name) == getattr(lib(), f"CCL_TEXGEN_{name}") == getattr(texgen, name)
    assert [noise.COMBINATIONS[n] for n in S.COMBINATION_NAMES] == list(range(len(S.COMBINATION_NAMES)))
    assert [getattr(lib(), f"CCL_PW_{n.upper()}") for n in S.COMBINATION_NAMES] == list(range(5))
    assert [raymarch.JITTER_MODES[n] for n in S.JITTER_NAMES] == [0, 1, 2]
    assert (S.EARTH_RADIUS_KM, S.LAYER_BASE_KM, S.LAYER_TOP_KM) == (
        raymarch.EARTH_RADIUS_KM, raymarch.LAYER_BASE_KM, raymarch.LAYER_TOP_KM)
    assert S.CurlNoiseSettings().fd_step == 1.0 / lib().CCL_NOISE_FD_STEP_INV


@pytest.mark.parametrize("cls", [S.CloudscapeSettings, *S.TEXTURE_SETTINGS.values()])
def test_every_field_has_a_full_spec(cls):
    fields = [f.name for f in dataclasses.fields(cls)]
    ps = specs(cls)
    assert [p.name for p in ps] == fields
    for p in ps:
        assert p.doc and p.reason and p.invalidates in cls.INVALIDATES, p.name
        assert getattr(cls(), p.name) == p.default
    for p in ps:  # the unit is in the name where the field has one (deg, km, ...)
        for suffix, unit in (("_deg", "deg"), ("_km", "km"), ("_kmh", "km/h"), ("_s", "s"), ("_per_km", "1/km")):
            if p.name.endswith(suffix) and not p.name.endswith("_per_km" if suffix == "_km" else "\0"):
                assert p.unit == unit, p.name


def test_the_weather_map_is_declared_once():
    """CloudscapeSettings has no weather-map parameter of its own: its fields carry WeatherMapSettings' specs (same
    domain, doc, reason and default), and the textures of a render are built from them."""
    weather = {p.name: p for p in specs(S.WeatherMapSettings)}
    scene = {p.name: p for p in specs(S.CloudscapeSettings)}
    for name in ("coverage", "precipitation", "cloud_type", "cloud_type_variation"):
        assert dataclasses.replace(scene[name], name="") == dataclasses.replace(weather[name], name="")
    assert scene["weather_size"].default == weather["size"].default
    s = S.CloudscapeSettings(coverage=0.3, cloud_type=0.6, seed=5, weather_size=64)
    assert s.textures()["weather_map"] == S.WeatherMapSettings(size=64, seed=5, coverage=0.3, cloud_type=0.6)
    assert S.CloudscapeSettings().textures()["weather_map"] == S.WeatherMapSettings()


@pytest.mark.spec("vc-A14")
def test_cloudscape_validation_names_the_field():
    cases = [
        (dict(width=0), r"^width must be in \[1, 8192\], got 0$"),
        (dict(turbidity=11.0), r"^turbidity must be in \[2, 10\], got 11\.0$"),
        (dict(sky="hosek"), r"^sky must be one of 'preetham', 'gradient', got 'hosek'$"),
        (dict(sun_elevation_deg=-5.0), r"^sun_elevation_deg must be in \[0, 90\], got -5\.0$"),
        (dict(sky="gradient", sun_elevation_deg=-5.0), r"^sun_elevation_deg must be in \[0, 90\], got -5\.0$"),
        (dict(coverage=float("nan")), r"^coverage must be finite \(no NaN or Inf\), got nan$"),
        (dict(coverage=1.5), r"^coverage must be in \[0, 1\], got 1\.5$"),
        (dict(layer_top_km=1.0), r"^layer_top_km must be > layer_base_km \(1\.5 km\), got 1\.0$"),
        (dict(base_size=100), r"^base_size must be a power of two in \[4, 512\], got 100$"),
        (dict(samples_min=100, samples_max=90), r"^samples_max must be in \[samples_min \(100\), 4096\], got 90$"),
        (dict(reprojection_neighbourhood=2), r"^reprojection_neighbourhood must be an odd integer in \[1, 9\]"),
        (dict(seed=-1), r"^seed must be in \[0, 4294967295\], got -1$"),
        (dict(threads=0), r"^threads must be in \[1, 4096\], got 0$"),
        (dict(advanced={"sigma": -1.0}), r"^sigma is out of range"),
        (dict(advanced={"bogus": 1.0}), r"^advanced: unknown parameter 'bogus'"),
        (dict(advanced={"light_far_factor": 3.0e6}), r"^light_far_factor is out of range: it must be in \[1, 10\^6\] "
         r"\(CCL_CLOUDSCAPE_MAX_LIGHT_FAR_FACTOR\), with light_far_factor x 5 x light_step_km <= 10\^6 km "
         r".*got 3000000\.0$"),
        (dict(advanced={"light_far_factor": 3.0e38, "light_step_km": 1.0e-39}),
         r"^light_far_factor is out of range: it must be in \[1, 10\^6\] .*got 3e\+38$"),
        (dict(advanced={"light_interp": -0.5}),
         r"^light_interp is out of range: it must be >= 0 and finite .*got -0\.5$"),
        (dict(advanced={"exit_fill": 2}), r"^exit_fill is out of range: it must be 0 or 1 .*got 2$"),
        (dict(advanced={"exit_eps": 0.0}), r"^exit_eps is out of range: it must be in \(0, 1\) .*got 0\.0$"),
    ]
    for kw, pattern in cases:
        with pytest.raises(ValueError, match=pattern):
            S.CloudscapeSettings(**kw)
    with pytest.raises(TypeError, match=r"^width must be an integer, got 64\.0$"):
        S.CloudscapeSettings(width=64.0)
    with pytest.raises(TypeError, match=r"^beer must be True or False, got 1$"):
        S.CloudscapeSettings(beer=1)
    s = S.CloudscapeSettings(sky="gradient", sun_elevation_deg=0.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.width = 10


def test_invalidation_follows_the_specs():
    base = S.CloudscapeSettings()
    cases = {"time_s": (5.0, set()), "camera_pitch_deg": (10.0, set()), "coverage": (0.4, {"textures"}),
             "seed": (3, {"textures"}), "weather_size": (256, {"textures"}), "sun_elevation_deg": (10.0, {"sky"}),
             "turbidity": (3.0, {"sky"}), "width": (100, {"size"}), "threads": (1, {"device"})}
    for name, (value, stale) in cases.items():
        assert dataclasses.replace(base, **{name: value}).invalidated(base) == stale, name


def test_technique_update_regenerates_only_what_the_change_invalidates():
    from pywarp.clouds.technique import CloudscapeTechnique

    t = CloudscapeTechnique(S.CloudscapeSettings(**SMALL))
    textures, sky, buffers = t.textures, t.sky, t._buffers
    t.update(time_s=12.0, camera_pitch_deg=5.0)
    assert t.textures is textures and t.sky is sky and t._buffers is buffers
    t.update(sun_elevation_deg=12.0)
    assert t.textures is textures and t.sky is not sky and t._buffers is buffers
    t.update(coverage=0.25)
    assert t.textures is not textures
    t.update(width=24, height=12)
    assert t._buffers is not buffers and t.render(reprojection=False).shape == (12, 24, 3)
    t.resize(20, 10)
    assert (t.settings.width, t.settings.height) == (20, 10) and t.render().shape == (10, 20, 3)
    with pytest.raises(ValueError, match=r"^width must be in \[1, 8192\], got 0$"):
        t.update(width=0)
    assert t.settings.width == 20  # a refused change leaves the settings as they were


@pytest.mark.parametrize("threads", [1, 2])
def test_render_progress_adds_up_to_one_frame_and_changes_no_pixel(threads):
    """A progress callback splits the cloud pass into bands (also with one worker, serially); the pixels are those
    of the render without it."""
    from pywarp.clouds.technique import CloudscapeTechnique

    s = S.CloudscapeSettings(**SMALL, threads=threads)
    ref = CloudscapeTechnique(s).render(reprojection=False)
    t = CloudscapeTechnique(s)
    parts = []
    img = t.render(reprojection=False, progress=parts.append)
    assert len(parts) > 1 and math.isclose(sum(parts), 1.0)
    np.testing.assert_array_equal(img, ref)
