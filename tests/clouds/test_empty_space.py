"""The empty-space skipping of the cloudscape march (Warp only): the map it reads, the bound of the base shape that
skips base lookups whose coverage test must fail, and frames that are bit for bit those of the march without either;
and the de-tiled weather's short cuts (one map read where the selector is 0 or 1)."""
import numpy as np
import pytest

from pywarp.clouds import cloudscape as C
from pywarp.clouds.settings import CloudscapeSettings
from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.core.pose import Pose
from pywarp.kernels import cloudscape as K
from tests.clouds.test_artefacts import weather_c


def _brute_distance(cov, cap):
    """Chebyshev distance on the torus to the nearest texel with coverage not <= 0, by brute force."""
    n = cov.shape[0]
    occ = np.argwhere(~(cov <= 0.0))
    out = np.zeros(cov.shape, dtype=np.int64)
    for y in range(n):
        for x in range(n):
            dy = np.abs(occ[:, 0] - y)
            dx = np.abs(occ[:, 1] - x)
            dy = np.minimum(dy, n - dy)
            dx = np.minimum(dx, n - dx)
            out[y, x] = min(cap, int(np.min(np.maximum(dx, dy)))) if len(occ) else cap
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_empty_distance_equals_brute_force(seed):
    rng = np.random.default_rng(seed)
    n = 32
    w = np.zeros((n, n, 4), dtype=np.float32)
    # a few occupied blobs near the edges (the torus wraps) and a NaN, which counts as occupied
    for _ in range(4):
        y, x = rng.integers(0, n, 2)
        w[y, x, 0] = rng.uniform(0.01, 1.0)
    w[rng.integers(0, n), rng.integers(0, n), 0] = np.nan
    w[..., 1:] = rng.uniform(0, 1, (n, n, 3))  # other channels do not matter
    got = C.weather_empty_distance(w, cap=9)
    np.testing.assert_array_equal(got, _brute_distance(w[..., 0], 9))


def test_empty_distance_all_empty_is_capped_and_all_occupied_is_zero():
    z = np.zeros((16, 16, 4), dtype=np.float32)
    assert (C.weather_empty_distance(z, cap=5) == 5).all()
    z[..., 0] = 0.5
    assert (C.weather_empty_distance(z, cap=5) == 0).all()


def _pair(**kw):
    s = CloudscapeSettings(width=96, height=54, threads=2, **kw)
    t = CloudscapeTechnique(s)
    pose = Pose.from_settings(s)
    tex = t.textures.warp()
    out = []
    bound = tex.base_bound
    assert 0.5 < bound < 1.0  # the default base texture has a bound that skips lookups
    for skip in (1, 0):
        tex.empty_skip = skip
        t.frame = 0
        out.append((t.render(pose, reprojection=False, encode=False), t.samples_taken()))
    tex.empty_skip = 1
    return out


@pytest.mark.parametrize("kw", [dict(), dict(camera_pitch_deg=-30.0, camera_altitude_km=8.0),
                                dict(weather_detile=False, camera_pitch_deg=60.0),
                                dict(camera_pitch_deg=2.0, coverage=0.3)],
                         ids=["default", "above", "no-detile-up", "horizon"])
def test_skipping_changes_no_pixel(kw):
    (a, sa), (b, sb) = _pair(**kw)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(sa, sb)


def _base_shape_f64(c):
    """vc-2.28's B written out in float64 (independent of the kernels)."""
    c = np.asarray(c, dtype=np.float64)
    lo = 0.625 * c[..., 1] + 0.25 * c[..., 2] + 0.125 * c[..., 3] - 1.0
    return (c[..., 0] - lo) / (1.0 - lo)


def _trilinear_f64(vol, p):
    """Periodic trilinear lookup of vol[z, y, x, 4] at texture coordinates p (n, 3), texel centres at i + 0.5."""
    n = vol.shape[0]
    q = p * n - 0.5
    i0 = np.floor(q)
    t = q - i0
    i0 = i0.astype(np.int64)
    out = 0.0
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                w = ((t[:, 0] if dx else 1 - t[:, 0]) * (t[:, 1] if dy else 1 - t[:, 1])
                     * (t[:, 2] if dz else 1 - t[:, 2]))
                out = out + w[:, None] * vol[(i0[:, 2] + dz) % n, (i0[:, 1] + dy) % n, (i0[:, 0] + dx) % n]
    return out


def test_base_bound_bounds_every_sample_of_the_chain(small_textures):
    """B at random points of every mip level and of blends of two levels (the samples the march takes) never
    exceeds the bound; the bound is not loose by more than the spread of the channels allows (within 0.1 of the
    largest B of a texel for the default textures)."""
    chain = small_textures.mips("base")
    bound = C.base_shape_bound(chain)
    n = small_textures.base.shape[0]
    rng = np.random.default_rng(5)
    p = rng.uniform(-3.0, 3.0, (4000, 3))
    levels, off, size = [], 0, n
    while size >= 1:
        levels.append(chain[off:off + size ** 3].reshape(size, size, size, 4).astype(np.float64))
        off += size ** 3
        size //= 2
    best = 0.0
    for k, vol in enumerate(levels):
        a = _trilinear_f64(vol, p)
        b = _trilinear_f64(levels[min(k + 1, len(levels) - 1)], p)
        for f in (0.0, 0.3, 1.0):
            bs = _base_shape_f64(a + (b - a) * f)
            assert bs.max() <= bound
            best = max(best, bs.max())
    texel_max = _base_shape_f64(chain).max()
    assert texel_max <= bound < texel_max + 0.1
    assert best > 0.5


def test_base_bound_is_off_outside_its_proof():
    """A channel R > 1 (B would rise with L), an L >= 2 or a NaN: no bound (0), so nothing is skipped."""
    ok = np.full((9, 4), 0.5, dtype=np.float32)
    assert C.base_shape_bound(ok) == pytest.approx(1.0 / 1.5, rel=1e-4)  # R = 0.5, L = 0.5: B = 1 / 1.5
    for bad in ((0, 1.5), (1, 2.5), (2, np.nan)):
        a = ok.copy()
        a[3, bad[0]] = bad[1]
        if bad[0] == 1:
            a[3, 1:] = bad[1]
        assert C.base_shape_bound(a) == 0.0


def test_skipping_has_work_to_skip():
    # the map of the default textures has wide empty regions: without them the skipping would test nothing
    s = CloudscapeSettings(width=8, height=8)
    w = C.RenderTextures.generate(s).weather
    d = C.weather_empty_distance(w)
    assert (d >= K.EMPTY_MARGIN + 4).mean() > 0.2


def _bilinear_np(tex, u, v):
    """Periodic bilinear lookup, texel centres at (i + 0.5) / n, in float64 (independent of the samplers)."""
    n = tex.shape[0]
    x, y = u * n - 0.5, v * n - 0.5
    x0, y0 = np.floor(x), np.floor(y)
    tx, ty = (x - x0)[:, None], (y - y0)[:, None]
    x0, y0 = x0.astype(np.int64) % n, y0.astype(np.int64) % n
    x1, y1 = (x0 + 1) % n, (y0 + 1) % n
    t = tex.astype(np.float64)
    c0 = t[y0, x0] + (t[y0, x1] - t[y0, x0]) * tx
    c1 = t[y1, x0] + (t[y1, x1] - t[y1, x0]) * tx
    return c0 + (c1 - c0) * ty


def test_detiled_weather_equals_the_blend_everywhere(small_textures):
    """The de-tiled weather (C, which reads one map where the selector is 0 or 1) against the full blend
    a + (b - a) smoothstep(k) written out in float64, at points with selectors 0, 1 and between."""
    from dataclasses import replace

    wd = K.WEATHER_DETILE
    s = replace(CloudscapeSettings(base_size=32, detail_size=16, curl_size=32, weather_size=128), wind_speed_kmh=0.0)
    rng = np.random.default_rng(11)
    x, z = rng.uniform(-200.0, 200.0, 2000).astype(np.float32), rng.uniform(-200.0, 200.0, 2000).astype(np.float32)
    got = weather_c(s, small_textures, x, z)
    # texture coordinates in float32 as the sampler gets them (the lookups and the blend in float64)
    f = np.float32
    u, v = x / f(32.0), z / f(32.0)  # the default weather_scale_km, no wind
    c, sn = f(wd["cos"]), f(wd["sin"])
    w = small_textures.weather
    a = _bilinear_np(w, u, v)
    b = _bilinear_np(w, (c * u - sn * v) / f(wd["scale_b"]) + f(wd["shift_u"]),
                     (sn * u + c * v) / f(wd["scale_b"]) + f(wd["shift_v"]))
    m = _bilinear_np(w, (c * u + sn * v) / f(wd["scale_m"]) + f(wd["shift_v"]),
                     (c * v - sn * u) / f(wd["scale_m"]) + f(wd["shift_u"]))
    k = np.clip((m[:, 0] - wd["edge0"]) / (wd["edge1"] - wd["edge0"]), 0.0, 1.0)
    k = (k * k * (3.0 - 2.0 * k))[:, None]
    want = a + (b - a) * k
    assert (k == 0).mean() > 0.1 and (k == 1).mean() > 0.02 and ((k > 0) & (k < 1)).mean() > 0.1
    np.testing.assert_allclose(got, want, rtol=0, atol=2e-6)


def test_selector_class_against_brute_force():
    """Each cell's class from its four texels written out one by one (float64), with values on both sides of the
    margins and a NaN (class 2)."""
    rng = np.random.default_rng(4)
    n = 16
    w = rng.uniform(0.0, 1.0, (n, n, 4)).astype(np.float32)
    w[rng.uniform(size=(n, n)) < 0.4, 0] = 0.1
    w[rng.uniform(size=(n, n)) < 0.2, 0] = 0.9
    w[2, 3, 0] = np.float32(K.WEATHER_DETILE["edge0"])  # on the edge: not certain
    w[5, 5, 0] = np.nan
    got = C.selector_class(w)
    lo = K.WEATHER_DETILE["edge0"] - C.SELECTOR_MARGIN
    hi = K.WEATHER_DETILE["edge1"] + C.SELECTOR_MARGIN
    for i in range(n):
        for j in range(n):
            four = [float(w[i, j, 0]), float(w[i, (j + 1) % n, 0]), float(w[(i + 1) % n, j, 0]),
                    float(w[(i + 1) % n, (j + 1) % n, 0])]
            want = 0 if all(c <= lo for c in four) else 1 if all(c >= hi for c in four) else 2
            assert got[i, j] == want, (i, j, four)
    assert {0, 1, 2} <= set(np.unique(got).tolist())


def test_weather_with_the_selector_classes_is_bit_for_bit_the_lookup(small_textures):
    """The de-tiled weather (Warp) where the class map short-cuts the selector equals the full lookup everywhere,
    at random points and on a fine line across cell edges; the map short-cuts most points of the default map."""
    import warp as wp

    from pywarp.clouds.settings import CLOUDSCAPE_PARAMS

    s = CloudscapeSettings(base_size=32, detail_size=16, curl_size=32, weather_size=128)
    rng = np.random.default_rng(9)
    x = np.concatenate([rng.uniform(-400.0, 400.0, 20000), np.linspace(-3.0, 3.0, 20000)]).astype(np.float32)
    z = np.concatenate([rng.uniform(-400.0, 400.0, 20000), np.linspace(1.0, 1.7, 20000)]).astype(np.float32)
    tex = small_textures.warp()
    pts = wp.array(np.stack([x, np.zeros_like(x), z], axis=1), dtype=wp.vec3)
    out = []
    for skip in (1, 0):
        tex.empty_skip = skip
        o = wp.zeros(len(x), dtype=wp.vec4)
        wp.launch(K.weather_points_kernel, dim=len(x), inputs=[CLOUDSCAPE_PARAMS.warp_struct(s.c_values()), tex, pts],
                  outputs=[o])
        out.append(o.numpy())
    tex.empty_skip = 1
    np.testing.assert_array_equal(out[0], out[1])
    assert (C.selector_class(small_textures.weather) < 2).mean() > 0.5
