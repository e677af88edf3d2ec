"""Signed distance functions and ray marching (pt §4 - §5): exact distances of sphere, box and torus, the ellipsoid as
a bound, the operators with the printed smooth union = Quilez's smin(k = 1, arguments swapped), both repeat variants,
the scenes' sign and Lipschitz bound, analytic ray-sphere intersection (ray tracing) against sphere tracing."""
from __future__ import annotations

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree


@pytest.mark.spec("pt-code-4.1")
def test_exact_distances_of_sphere_box_torus():
    p = np.array([[3.0, 4.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [2.0, 2.0, 2.0], [0.0, 0.0, 0.0],
                  [0.5, 0.0, 0.0], [0.0, 3.0, 0.0]], np.float32)
    sphere, box, torus, _ = pywarp.sdf_primitives(p, 2.0, [1.0, 1.0, 1.0], [1.5, 0.25], [1.0, 1.0, 1.0])
    np.testing.assert_allclose(sphere, [3.0, 0.0, 2 * np.sqrt(2) - 2, 2 * np.sqrt(3) - 2, -2.0, -1.5, 1.0], rtol=1e-6)
    np.testing.assert_allclose(box, [np.sqrt(13), 1.0, np.sqrt(2), np.sqrt(3), -1.0, -0.5, 2.0], rtol=1e-6)
    # torus R = 1.5, r = 0.25 around y: on the ring -r; at the centre R - r; above the ring height - r
    tp = np.array([[1.5, 0, 0], [0, 0, 0], [0, 0, -1.5], [1.5, 1.0, 0], [3.5, 0, 0], [0, 1, 0]], np.float32)
    torus = pywarp.sdf_primitives(tp, 1.0, [1, 1, 1], [1.5, 0.25], [1, 1, 1])[2]
    np.testing.assert_allclose(torus, [-0.25, 1.25, -0.25, 0.75, 1.75, np.sqrt(1.5 ** 2 + 1) - 0.25], rtol=1e-6)


@pytest.mark.spec("pt-code-4.1")
def test_ellipsoid_is_a_bound_exact_only_for_a_sphere(rng):
    r = np.array([1.0, 0.6, 0.4])
    p = rng.uniform(-2.0, 2.0, (400, 3)).astype(np.float32)
    d = pywarp.sdf_primitives(p, 1.0, [1, 1, 1], [1, 0.25], r)[3].astype(np.float64)
    # true distance by dense sampling of the surface (float64; the sampling error is below 2e-3)
    th, ph = np.meshgrid(np.linspace(0, np.pi, 400), np.linspace(0, 2 * np.pi, 800))
    surf = np.stack([r[0] * np.sin(th) * np.cos(ph), r[1] * np.sin(th) * np.sin(ph), r[2] * np.cos(th)], -1)
    surf = surf.reshape(-1, 3)
    true = np.array([np.sqrt(((surf - q) ** 2).sum(-1)).min() for q in p.astype(np.float64)])
    inside = (p.astype(np.float64) ** 2 / r ** 2).sum(-1) < 1
    assert np.array_equal(d < 0, inside)  # the sign is right
    assert np.all(np.abs(d) <= true + 2e-3)  # a bound: never beyond the true distance
    assert np.max(true - np.abs(d)) > 0.05  # and not exact: the text does not say it is approximate
    # exact for equal semi-axes
    e = pywarp.sdf_primitives(p, 0.7, [1, 1, 1], [1, 0.25], [0.7, 0.7, 0.7])
    np.testing.assert_allclose(e[3], e[0], atol=1e-6)
    assert_twins_agree("pt-code-4.1", p[:100], 0.8, [0.5, 0.7, 0.9], [1.0, 0.3], r)


@pytest.mark.spec("pt-code-4.2")
def test_operators_and_printed_smooth_union_is_quilez_smin_swapped(rng):
    d1 = rng.uniform(-2, 2, 5000).astype(np.float32)
    d2 = rng.uniform(-2, 2, 5000).astype(np.float32)
    u, i, s, su, _ = pywarp.sdf_operators(d1, d2)
    np.testing.assert_array_equal(u, np.minimum(d1, d2))
    np.testing.assert_array_equal(i, np.maximum(d1, d2))
    np.testing.assert_array_equal(s, np.maximum(-d2, d1))

    def smin(a, b, k):  # Quilez, https://iquilezles.org/articles/smin/ (polynomial), float64
        h = np.clip(0.5 + 0.5 * (b - a) / k, 0.0, 1.0)
        return b * (1 - h) + a * h - k * h * (1 - h)

    a64, b64 = d1.astype(np.float64), d2.astype(np.float64)
    np.testing.assert_allclose(su, smin(d2.astype(np.float64), d1.astype(np.float64), 1.0), atol=2e-6)
    for k in (0.1, 0.5, 2.0):
        got = pywarp.sdf_operators(d1, d2, k)[3]
        np.testing.assert_allclose(got, smin(b64, a64, k), atol=4e-6)
        assert np.all(got <= np.minimum(d1, d2) + 1e-6)
        far = np.abs(a64 - b64) >= k
        np.testing.assert_allclose(got[far], np.minimum(d1, d2)[far], atol=1e-6)  # plain min outside the blend
        np.testing.assert_allclose(got[a64 == b64], (a64 - k / 4)[a64 == b64], atol=1e-6)
    assert_twins_agree("pt-code-4.2", d1[:200], d2[:200], 0.3, [0.4, -7.0, 2.5], [1.0, 2.0, 3.0], variant="thesis")


@pytest.mark.spec("pt-code-4.2")
def test_repeat_thesis_places_copies_at_half_cells_corrected_centres_them():
    c = np.array([2.0, 3.0, 4.0])
    k = np.array([[0, 0, 0], [1, -2, 3], [-5, 4, -1]], np.float64)
    rep = lambda p, v: pywarp.sdf_operators(0.0, 0.0, 1.0, p, c, variant=v)[4]  # noqa: E731
    np.testing.assert_allclose(rep((k + 0.5) * c, "thesis"), 0.0, atol=1e-5)  # printed: copies at (k + 1/2) c
    np.testing.assert_allclose(rep(k * c, "corrected"), 0.0, atol=1e-5)       # centred: copies at k c
    np.testing.assert_allclose(np.abs(rep(k * c, "thesis")), np.broadcast_to(0.5 * c, k.shape), atol=1e-5)  # the origin is a cell corner
    p = np.random.default_rng(3).uniform(-20, 20, (2000, 3)).astype(np.float32)
    for v in ("thesis", "corrected"):
        q = rep(p, v)
        assert np.all(q >= -0.5 * c - 1e-5) and np.all(q <= 0.5 * c + 1e-5)
        # periodic: shifting p by one period gives the same point
        np.testing.assert_allclose(rep(p + c.astype(np.float32), v), q, atol=2e-5)


@pytest.mark.spec("pt-alg-4.1")
@pytest.mark.parametrize("scene", ["primitives", "union", "intersection", "subtraction", "repetition", "displacement",
                                   "smooth_union"])
def test_scene_sign_and_distance_bound(scene, rng):
    d = pywarp.sdf_scene
    far = d([40.0, 30.0, -35.0], scene=scene)
    assert far > 0 and far <= np.sqrt(40.0 ** 2 + 30 ** 2 + 35 ** 2)
    inside = {"primitives": [-3.75, 0, 0], "repetition": [0.6, 0, 0.6]}.get(scene, [0.0, 0.0, 0.0])
    if scene == "subtraction":
        assert d([0.0, 0.0, 0.0], scene=scene) > 0  # the sphere is carved out of the box's centre
        assert d([0.69, 0.69, 0.69], scene=scene) < 0  # the corners remain
    else:
        assert d(inside, scene=scene) < 0
    # 1-Lipschitz (a distance bound, safe for sphere tracing): |d(p) - d(q)| <= |p - q|
    p = rng.uniform(-4.5, 4.5, (3000, 3)).astype(np.float32)
    q = (p + rng.normal(0, 0.2, p.shape)).astype(np.float32)
    dp, dq = d(p, scene=scene), d(q, scene=scene)
    assert np.all(np.abs(dp - dq) <= np.linalg.norm(p - q, axis=-1) * (1 + 1e-5) + 1e-5)
    assert_twins_agree("pt-alg-4.1", p[:200], 1 if scene == "displacement" else 0, scene=scene)


@pytest.mark.spec("pt-alg-5.1")
def test_ray_sphere_closed_forms():
    rs = pywarp.sdf_ray_sphere
    assert rs([0, 0, -5], [0, 0, 1], [0, 0, 0], 1.0) == 4.0
    assert rs([0, 0, 0], [0, 0, 1], [0, 0, 0], 1.0) == 1.0  # inside: the exit point
    assert rs([0, 0, 5], [0, 0, 1], [0, 0, 0], 1.0) == -1.0  # behind
    assert rs([0, 2, -5], [0, 0, 1], [0, 0, 0], 1.0) == -1.0  # miss
    # grazing at distance r: t = 5
    assert rs([0, 1, -5], [0, 0, 1], [0, 0, 0], 1.0) == pytest.approx(5.0, abs=1e-6)
    rd = np.array([0.0, 0.6, 0.8])
    assert rs([0, 0, 0], rd, [0, 3, 4], 1.0) == pytest.approx(4.0, rel=1e-6)


@pytest.mark.spec("pt-alg-5.2", "pt-alg-5.1")
def test_sphere_tracing_finds_the_analytic_intersection(rng):
    """Ray marching (5.2) and ray tracing (5.1) agree on the exact sphere of the primitives scene."""
    n = 500
    ro = np.tile(np.array([-3.75, 0.0, -6.0], np.float32), (n, 1))
    target = np.array([-3.75, 0.0, 0.0]) + rng.uniform(-0.4, 0.4, (n, 3)) * [1, 1, 0]
    rd = target - ro
    rd = (rd / np.linalg.norm(rd, axis=-1, keepdims=True)).astype(np.float32)
    t, steps, hit = pywarp.sdf_sphere_trace(ro, rd, 256, 1e-4, 50.0)
    exact = pywarp.sdf_ray_sphere(ro, rd, [-3.75, 0.0, 0.0], 0.8)
    assert np.all(hit == 1) and np.all(exact > 0)
    # the march stops short of the surface by less than precision / cos(angle to the normal) (cos > 0.5 here)
    assert np.all(t <= exact + 1e-5) and np.all(exact - t < 2e-4)
    assert steps.max() < 40
    # a ray that misses runs past max_t; max_steps bounds the loop
    t, steps, hit = pywarp.sdf_sphere_trace([0.0, 5.0, 0.0], [0.0, 1.0, 0.0], 256, 1e-3, 50.0)
    assert hit == 0 and t > 50.0 and steps < 256
    t, steps, hit = pywarp.sdf_sphere_trace(ro[:5], rd[:5], 2, 1e-4, 50.0)
    assert np.all(steps == 2) and np.all(hit == 0)
    assert_twins_agree("pt-alg-5.2", ro[:100], rd[:100], 256, 1e-4, 50.0)


@pytest.mark.spec("pt-alg-5.2")
def test_sphere_tracing_every_scene_hits_from_its_camera():
    ro = np.array([0.0, 2.5, -5.0])
    for scene in ("union", "intersection", "subtraction", "displacement", "smooth_union"):
        # aim at a point inside the object (box minus sphere: a corner, the centre is carved out)
        aim = np.array([0.65, 0.65, -0.65] if scene == "subtraction" else [0.4, 0.3, -0.3])
        assert pywarp.sdf_scene(aim, scene=scene) < 0
        rd = (aim - ro) / np.linalg.norm(aim - ro)
        t, steps, hit = pywarp.sdf_sphere_trace(ro, rd.astype(np.float32), scene=scene)
        assert hit == 1, scene
        p = ro + t * rd
        assert abs(pywarp.sdf_scene(p, scene=scene)) < 2e-3
    with pytest.raises(ValueError, match=r"\bmax_steps\b"):
        pywarp.sdf_sphere_trace([0, 0, -5], [0, 0, 1], 0)
    with pytest.raises(ValueError, match=r"\brd\b"):
        pywarp.sdf_sphere_trace([0, 0, -5], [0, 0, 2])
