"""Escape-time fractals (pt §3.6): Julia iteration (pt-3.1) and the printed examples (pt-u-julia), the quadratic family
with the printed -mu sign as the thesis variant (pt-3.2), Mandelbrot membership (pt-3.3): known members and
non-members, exact escape counts, float64 reference orbits, the mirror of the thesis sign, C vs Warp agreement."""
from __future__ import annotations

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree


def _ref_count(z0, f, escaped, max_iter):
    """Escape count of the float64 orbit a_0 = z0, a_{n+1} = f(a_n), and the smallest margin |test value - R| met."""
    z, margin = complex(z0), np.inf
    for n in range(max_iter):
        done, m = escaped(z)
        margin = min(margin, m)
        if done:
            return n, margin
        z = f(z)
    return max_iter, margin


@pytest.mark.spec("pt-3.2")
def test_quadratic_closed_form_and_printed_sign():
    z, mu = np.array([1.0, 2.0]), np.array([0.5, -1.0])  # z^2 = -3 + 4i
    np.testing.assert_array_equal(pywarp.fractal_quadratic(z, mu), [-2.5, 3.0])
    np.testing.assert_array_equal(pywarp.fractal_quadratic(z, mu, variant="thesis"), [-3.5, 5.0])
    assert_twins_agree("pt-3.2", np.random.default_rng(1).uniform(-2, 2, (50, 2)), [0.3, -0.2], variant="thesis")


@pytest.mark.spec("pt-3.3", "pt-3.2")
def test_mandelbrot_known_members_and_exact_counts():
    members = np.array([[0, 0], [-1, 0], [-2, 0], [0.25, 0], [0, 1], [-0.1, 0.1], [-1.3, 0.0]], np.float32)
    count, smooth = pywarp.fractal_mandelbrot(members, 2000)
    np.testing.assert_array_equal(count, 2000)  # |a_n| <= 2 for every computed n (c = -2: 0, -2, 2, 2, ...)
    np.testing.assert_array_equal(smooth, 2000.0)
    # c = 1: 0, 1, 2, 5 -> a_3 is the first with |a_n| > 2; c = 1 + i: 0, 1 + i, 1 + 3i -> n = 2; c = -2.1: a_1 = -2.1, n = 1
    np.testing.assert_array_equal(pywarp.fractal_mandelbrot([[1, 0], [1, 1], [-2.1, 0], [3, 0]], 100)[0], [3, 2, 1, 1])
    # the printed x^2 - mu gives the mirrored set (mu = -c): antenna towards +2
    assert pywarp.fractal_mandelbrot([2.0, 0.0], 500, variant="thesis")[0] == 500
    assert pywarp.fractal_mandelbrot([2.0, 0.0], 500)[0] < 5
    assert pywarp.fractal_mandelbrot([-1.0, 0.0], 100, variant="thesis")[0] == 3


@pytest.mark.spec("pt-3.3", "pt-3.2")
def test_mandelbrot_thesis_is_the_mirror_of_corrected():
    x, y = np.meshgrid(np.linspace(-2.2, 2.2, 121), np.linspace(-1.3, 1.3, 71))
    mu = np.stack([x, y], -1).astype(np.float32)
    ct, st = pywarp.fractal_mandelbrot(mu, 200, variant="thesis")
    cc, sc = pywarp.fractal_mandelbrot(-mu, 200)
    np.testing.assert_array_equal(ct, cc)  # z^2 - mu == z^2 + (-mu) in IEEE arithmetic
    np.testing.assert_array_equal(st, sc)
    assert_twins_agree("pt-3.3", mu[::3, ::3], 300, variant="thesis")
    assert_twins_agree("pt-3.3", mu[::3, ::3], 300, 64.0)


@pytest.mark.spec("pt-3.3")
def test_mandelbrot_counts_match_float64_orbits_and_smooth_count(rng):
    mu = rng.uniform(-2.5, 1.5, (3000, 2)).astype(np.float32)
    count, smooth = pywarp.fractal_mandelbrot(mu, 30, 256.0)
    checked = 0
    for (a, b), n in zip(mu.astype(np.float64), count):
        c = complex(a, b)
        ref, margin = _ref_count(0, lambda z: z * z + c, lambda z: (abs(z) > 256.0, abs(abs(z) - 256.0)), 30)
        if ref < 30 and margin > 1e-2:  # away from the bailout, float32 and float64 orbits escape at the same step
            assert n == ref
            checked += 1
    assert checked > 1000
    esc = count < 30
    frac = smooth[esc] - count[esc]
    assert np.all(frac > -0.05) and np.all(frac <= 1.0)  # about [n, n + 1) for a large bailout


@pytest.mark.spec("pt-3.1")
def test_julia_exact_counts_for_c_zero():
    # f(z) = z^2: the unit disk is the filled Julia set; 1.5 -> 2.25 -> 5.06 -> 25.6 > 16 at n = 3
    z0 = np.array([[0.5, 0.0], [0.0, -0.99], [1.5, 0.0], [0.0, 3.0]], np.float32)
    np.testing.assert_array_equal(pywarp.fractal_julia(z0, [0, 0], 2, 500, 16.0)[0], [500, 500, 3, 2])
    assert pywarp.fractal_julia([1.5, 0.0], [0, 0], 2, 500, 2.0)[0] == 1
    # z^5: 1.1 -> 1.61 -> 10.9 -> 1.5e5 > 16 at n = 3
    assert pywarp.fractal_julia([1.1, 0.0], [0, 0], 5, 500, 16.0)[0] == 3
    # exp map escapes along the real axis: 0 -> 0.35 -> 0.77 -> 1.51 -> 3.86 -> 46.9 -> ~2e20 > 50
    ref, _ = _ref_count(0, lambda z: np.exp(z) - 0.65, lambda z: (z.real > 50.0, abs(z.real - 50.0)), 100)
    assert ref == 6
    assert pywarp.fractal_julia([0.0, 0.0], [-0.65, 0.0], 2, 100, 50.0, map="exp")[0] == ref


@pytest.mark.spec("pt-u-julia", "pt-3.1")
@pytest.mark.parametrize("example", ["x5", "x2", "exp"])
def test_julia_examples_are_the_printed_maps(example, rng):
    z0 = rng.uniform(-1.8, 1.8, (2000, 2)).astype(np.float32)
    count, smooth = pywarp.fractal_julia_example(z0, 40, example=example)
    kind, power, c = {"x5": ("poly", 5, (0.544, 0.0)), "x2": ("poly", 2, (0.285, 0.01)),
                      "exp": ("exp", 2, (-0.65, 0.0))}[example]
    escape = 50.0 if kind == "exp" else 16.0
    gc, gs = pywarp.fractal_julia(z0, c, power, 40, escape, map=kind)
    np.testing.assert_array_equal(count, gc)
    np.testing.assert_array_equal(smooth, gs)
    # independent float64 orbits of the printed maps agree where they stay clear of the escape test
    cc = complex(*c)
    if kind == "exp":
        f, test = (lambda z: np.exp(z) + cc), (lambda z: (z.real > 50.0, abs(z.real - 50.0)))
    else:
        f, test = (lambda z: z ** power + cc), (lambda z: (abs(z) > 16.0, abs(abs(z) - 16.0)))
    checked = 0
    for (a, b), n in zip(z0.astype(np.float64)[:600], count[:600]):
        ref, margin = _ref_count(complex(a, b), f, test, 8)
        if ref < 8 and margin > 1e-2:
            assert n == ref
            checked += 1
    assert checked > 50
    assert (count == 40).any() and (count < 40).any()  # both members and non-members in the viewport
    assert_twins_agree("pt-u-julia", z0[:300], 100, example=example)


@pytest.mark.spec("pt-3.1")
def test_julia_refuses_bad_escape_and_power():
    with pytest.raises(ValueError, match=r"\bescape\b"):
        pywarp.fractal_julia([0, 0], [0, 0], 2, 10, 1.0)
    with pytest.raises(ValueError, match=r"\bpower\b"):
        pywarp.fractal_julia([0, 0], [0, 0], 13, 10)
    with pytest.raises(ValueError, match=r"\bmax_iter\b"):
        pywarp.fractal_mandelbrot([0, 0], 0)
