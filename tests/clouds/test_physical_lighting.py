"""The terms of the physical real-time lighting model (docs/lighting.rst). The weight of the multiple-scattering
octaves by the optical depth towards the sun (vc-x-ms-gain): closed form, limits, C and Warp, the energy.
Delta scaling of the approximate Mie phase (vc-x-mie-delta, vc-x-mie-delta-scale; cclouds/cloudscape.h "Delta
scaling"): the closed form written out again in float64 from the published fit, the
identity sigma' p' = sigma p - sigma f (1 - w_D) HG(g_HG), the normalisation, C and Warp agreeing (the functions,
the energy and the per-frame light set-up), bad values refused, and the path-traced reference's medium untouched.
The octaves' weights by the depth along the view (vc-x-ms-view) and by the sun's elevation and the sample's place
between the sun and the viewer (vc-x-ms-slab), the ambient's anisotropy (vc-x-ambient-aniso): closed forms, limits,
C and Warp (functions and pixels), their effect on the image, bad values refused, the reference ignoring them."""
from __future__ import annotations

import math

import numpy as np
import pytest
import warp as wp

from helpers import assert_twins_agree

from pywarp.clouds.cloudscape import c_sky
from pywarp.clouds.settings import CLOUDSCAPE_PARAMS, CloudscapeSettings
from pywarp.clouds.technique import CloudscapeTechnique
from pywarp.core.binding import lib
from pywarp.kernels import cloudscape as K

SMALL = dict(width=24, height=16, base_size=32, detail_size=16, curl_size=32, weather_size=64)


def small(**kw) -> CloudscapeSettings:
    return CloudscapeSettings(**{**SMALL, **kw})


def _fit(d: float):
    """Jendersie & d'Eon 2023's parameters (g_HG, g_D, alpha, w_D), float64."""
    return (math.exp(-0.0990567 / (d - 1.67154)), math.exp(-2.20679 / (d + 3.91029) - 0.428934),
            math.exp(3.62489 - 8.29288 / (d + 5.52825)), math.exp(-0.599085 / (d - 0.641583) - 0.665888))


def _hg(mu, g):
    return (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * mu) ** 1.5)


def _expected(mu, d, f):
    """((1 - f)(1 - w_D) HG(g_HG) + w_D Draine) / (1 - f (1 - w_D)) in float64 (cloudscape.h)."""
    g_hg, g_d, al, w_d = _fit(d)
    draine = _hg(mu, g_d) * (1 + al * mu ** 2) / (1 + al * (1 + 2 * g_d ** 2) / 3)
    return ((1 - f) * (1 - w_d) * _hg(mu, g_hg) + w_d * draine) / (1 - f * (1 - w_d))


@pytest.mark.spec("vc-x-mie-delta", "vc-x-mie-delta-scale")
@pytest.mark.parametrize("d", [5.0, 15.0, 50.0])
@pytest.mark.parametrize("f", [0.0, 0.4, 1.0])
def test_closed_form_and_identity(d, f):
    mu = np.linspace(-1.0, 1.0, 201)
    p = np.array([lib().ccl_cloudscape_mie_delta_phase(float(m), d, f) for m in mu])
    s = lib().ccl_cloudscape_mie_delta_scale(d, f)
    g_hg, g_d, al, w_d = _fit(d)
    np.testing.assert_allclose(s, 1 - f * (1 - w_d), rtol=1e-6)
    np.testing.assert_allclose(p, _expected(mu, d, f), rtol=2e-4)
    # sigma' p' = sigma p - sigma f (1 - w_D) HG(g_HG): the scattered light outside the peak is kept (p the Mie fit
    # in float64: the difference cancels in the peak)
    mie64 = (1 - w_d) * _hg(mu, g_hg) + w_d * _hg(mu, g_d) * (1 + al * mu ** 2) / (1 + al * (1 + 2 * g_d ** 2) / 3)
    np.testing.assert_allclose(s * p, mie64 - f * (1 - w_d) * _hg(mu, g_hg), rtol=2e-4, atol=1e-6)
    if f == 0.0:  # off: the Mie phase itself, bit for bit
        mie = np.array([lib().ccl_phase_mie(float(m), d) for m in mu], dtype=np.float64)
        np.testing.assert_array_equal(np.float32(p), np.float32(mie))


@pytest.mark.spec("vc-x-mie-delta")
@pytest.mark.parametrize("f", [0.3, 1.0])
def test_phase_integrates_to_one(f):
    """2 pi int p'(mu) dmu = 1, by the trapezoid rule in x = log(1 - mu) near the forward peak (width ~ 1 - g_HG)
    and in mu elsewhere."""
    d = 15.0
    x = np.linspace(math.log(1e-9), math.log(0.5), 4001)
    mu_peak = 1.0 - np.exp(x)
    vals = np.array([lib().ccl_cloudscape_mie_delta_phase(float(m), d, f) for m in mu_peak], dtype=np.float64)
    peak = np.trapezoid(vals * np.exp(x), x)  # dmu = -(1 - mu) dx
    mu = np.linspace(-1.0, 0.5, 4001)
    rest = np.trapezoid(np.array([lib().ccl_cloudscape_mie_delta_phase(float(m), d, f) for m in mu]), mu)
    assert abs(2 * math.pi * (peak + rest) - 1.0) < 2e-3


@pytest.mark.spec("vc-x-mie-delta", "vc-x-mie-delta-scale")
def test_c_and_warp_agree():
    rng = np.random.default_rng(5)
    mu = np.float32(rng.uniform(-1, 1, 300))
    d = np.float32(rng.uniform(5, 50, 300))
    f = np.float32(rng.uniform(0, 1, 300))
    assert_twins_agree("vc-x-mie-delta", mu, d, f, ulp=8)
    assert_twins_agree("vc-x-mie-delta-scale", d, f, ulp=4)


@wp.kernel
def _energy_kernel(p: K.CloudscapeParams, d: wp.array(dtype=float), a: wp.array(dtype=float),
                   c: wp.array(dtype=float), out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = K.cloudscape_energy(p, d[i], a[i], c[i])


def test_energy_c_equals_warp_and_uses_the_delta_phase():
    # the octaves' sum alone (b = 0.5, no gain by the depth towards the sun)
    s = small(phase="mie", droplet_um=12.0, ms_octaves=3, mie_delta=0.7, beer=False, powder=False, ms_depth=0.0,
              advanced={"ms_b": 0.5})
    v = s.c_values()
    rng = np.random.default_rng(3)
    d = np.float32(rng.uniform(0, 8, 300))
    a = np.float32(rng.uniform(0, 3, 300))
    c = np.float32(rng.uniform(-1, 1, 300))
    out = wp.zeros(300, dtype=float)
    wp.launch(_energy_kernel, 300, inputs=[CLOUDSCAPE_PARAMS.warp_struct(v), wp.array(d), wp.array(a), wp.array(c)],
              outputs=[out])
    cp = CLOUDSCAPE_PARAMS.to_c(v)
    ce = np.array([lib().ccl_cloudscape_energy(cp, float(x), float(y), float(z)) for x, y, z in zip(d, a, c)],
                  dtype=np.float32)
    np.testing.assert_array_equal(out.numpy(), ce)
    # without Beer and powder: sum_i b^i (c^i p' + (1 - c^i) / 4 pi), p' the delta-scaled phase (float64 above)
    expected = sum(0.5 ** i * (0.5 ** i * _expected(c.astype(np.float64), 12.0, 0.7) + (1 - 0.5 ** i) / (4 * math.pi))
                   for i in range(3))
    np.testing.assert_allclose(ce, expected, rtol=3e-4)


@pytest.mark.parametrize("phase,lighting,scaled", [("mie", "sky", True), ("thesis", "sky", False),
                                                   ("mie", "thesis", False)])
def test_light_setup_scales_the_extinction(phase, lighting, scaled):
    """ccl_cloudscape_light (and its Warp twin, the technique's parameters) multiply sigma and sigma_light by
    1 - f (1 - w_D) with sky lighting and the Mie phase only."""
    s = small(phase=phase, lighting=lighting, units="physical" if lighting == "sky" else "display", mie_delta=0.6,
              sigma_per_km=30.0)
    p = CLOUDSCAPE_PARAMS.to_c(s.c_values())
    lib().ccl_cloudscape_light(p, c_sky(s), p)
    w = CloudscapeTechnique(s).params
    k = 1 - 0.6 * (1 - _fit(15.0)[3]) if scaled else 1.0
    for name in ("sigma", "sigma_light"):
        assert np.float32(getattr(w, name)) == np.float32(getattr(p, name))
        assert getattr(p, name) == pytest.approx(30.0 * k, rel=1e-6)


def test_bad_values_are_refused():
    with pytest.raises(ValueError, match="mie_delta"):
        small(mie_delta=1.5)
    with pytest.raises(ValueError, match="mie_delta"):
        small(advanced={"mie_delta": -0.1}).c_params()


def test_the_reference_medium_is_not_delta_scaled():
    """The path tracer's medium is sigma and the full Mie phase whatever the lighting model's mie_delta."""
    from pywarp.clouds.reference import ReferenceRenderer

    s = small(phase="mie", units="physical", mie_delta=1.0, sigma_per_km=30.0, lighting="sky")
    r = ReferenceRenderer(s, spp=1)
    assert r.params.sigma == pytest.approx(30.0) and r.params.sigma_light == pytest.approx(30.0)
    assert r.params.mie_delta == 0.0


# --- the octaves' weight (vc-x-ms-gain) --------------------------------------------------------------------------------

@pytest.mark.spec("vc-x-ms-gain")
def test_ms_gain_closed_form_and_limits():
    d = np.linspace(0.0, 20.0, 81)
    for depth, thin in ((0.5, 0.0), (2.0, 0.3), (7.0, 1.0)):
        g = np.array([lib().ccl_cloudscape_ms_gain(float(x), depth, thin) for x in d])
        np.testing.assert_allclose(g, thin + (1 - thin) * (1 - np.exp(-d / depth)), rtol=1e-6, atol=1e-7)
        assert g[0] == pytest.approx(thin) and np.all(np.diff(g) >= 0) and np.all(g <= 1.0)
    # off: exactly 1 whatever d and thin
    assert all(lib().ccl_cloudscape_ms_gain(float(x), 0.0, 0.4) == 1.0 for x in d)


@pytest.mark.spec("vc-x-ms-gain")
def test_ms_gain_c_and_warp_agree():
    rng = np.random.default_rng(9)
    d = np.float32(rng.uniform(0, 30, 300))
    depth = np.float32(np.where(rng.uniform(size=300) < 0.2, 0.0, rng.uniform(0.1, 10, 300)))
    thin = np.float32(rng.uniform(0, 1, 300))
    assert_twins_agree("vc-x-ms-gain", d, depth, thin, ulp=4)


def test_energy_weighs_the_octaves_by_the_gain():
    """Without Beer and powder: E = p_0 + gain sum_{i >= 1} b^i p_i, gain from the closed form; C equals Warp."""
    s = small(phase="mie", droplet_um=15.0, ms_octaves=4, ms_depth=2.0, ms_thin=0.2, beer=False, powder=False)
    off = small(phase="mie", droplet_um=15.0, ms_octaves=4, beer=False, powder=False, ms_depth=0.0)
    one = small(phase="mie", droplet_um=15.0, ms_octaves=1, beer=False, powder=False)
    cp, cp_off, cp_one = (CLOUDSCAPE_PARAMS.to_c(x.c_values()) for x in (s, off, one))
    for d in (0.0, 0.7, 5.0):
        for c in (-0.5, 0.3, 0.95):
            e0 = lib().ccl_cloudscape_energy(cp_one, d, 0.0, c)
            ms = lib().ccl_cloudscape_energy(cp_off, d, 0.0, c) - e0
            gain = 0.2 + 0.8 * (1 - math.exp(-d / 2.0))
            assert lib().ccl_cloudscape_energy(cp, d, 0.0, c) == pytest.approx(e0 + gain * ms, rel=2e-6)
    v = s.c_values()
    rng = np.random.default_rng(4)
    d = np.float32(rng.uniform(0, 8, 200))
    a = np.float32(rng.uniform(0, 3, 200))
    c = np.float32(rng.uniform(-1, 1, 200))
    out = wp.zeros(200, dtype=float)
    wp.launch(_energy_kernel, 200, inputs=[CLOUDSCAPE_PARAMS.warp_struct(v), wp.array(d), wp.array(a), wp.array(c)],
              outputs=[out])
    ce = np.array([lib().ccl_cloudscape_energy(cp, float(x), float(y), float(z)) for x, y, z in zip(d, a, c)],
                  dtype=np.float32)
    np.testing.assert_array_equal(out.numpy(), ce)


def test_ms_gain_bad_values_are_refused():
    with pytest.raises(ValueError, match="ms_thin"):
        small(ms_thin=1.5)
    with pytest.raises(ValueError, match="ms_depth"):
        small(ms_depth=-1.0)


# --- the octaves' weight by the depth along the view (vc-x-ms-view), the ambient's anisotropy (vc-x-ambient-aniso) -----

@pytest.mark.spec("vc-x-ms-view")
def test_ms_view_closed_form_and_limits():
    trans = np.linspace(0.0, 1.0, 101)
    for k, t0 in ((1.0, 1.0), (3.0, 0.3), (0.5, 0.05)):
        w = np.array([lib().ccl_cloudscape_ms_view(float(x), k, t0) for x in trans])
        np.testing.assert_allclose(w, 1 + k * np.maximum(1 - trans / t0, 0), rtol=1e-6)
        # 1 + k where the view is opaque, 1 from T0 on (thin cloud untouched), never growing with T
        assert w[0] == pytest.approx(1 + k) and np.all(w[trans >= t0] == 1.0) and np.all(np.diff(w) <= 0)
    assert all(lib().ccl_cloudscape_ms_view(float(x), 0.0, 0.3) == 1.0 for x in trans)  # off


@pytest.mark.spec("vc-x-ambient-aniso")
def test_ambient_aniso_closed_form_and_limits():
    mu = np.linspace(-1.0, 1.0, 41)
    for alpha, trans in ((0.5, 1.0), (0.8, 0.4), (1.0, 0.0)):
        w = np.array([lib().ccl_cloudscape_ambient_aniso(float(m), trans, alpha) for m in mu])
        np.testing.assert_allclose(w, 1 + alpha * mu * trans, rtol=1e-6, atol=1e-7)
        # from above (mu < 0) less ambient, from below more, a horizontal view and an opaque view in front: 1
        assert np.all(w[mu < 0] <= 1.0) and np.all(w[mu > 0] >= 1.0) and np.all(w >= 1 - alpha - 1e-7)
    assert lib().ccl_cloudscape_ambient_aniso(0.0, 1.0, 1.0) == 1.0
    assert all(lib().ccl_cloudscape_ambient_aniso(float(m), 0.7, 0.0) == 1.0 for m in mu)  # off


@pytest.mark.spec("vc-x-ms-view", "vc-x-ambient-aniso")
def test_ms_view_and_ambient_aniso_c_and_warp_agree():
    rng = np.random.default_rng(11)
    trans = np.float32(rng.uniform(0, 1, 300))
    k = np.float32(np.where(rng.uniform(size=300) < 0.2, 0.0, rng.uniform(0, 8, 300)))
    t0 = np.float32(rng.uniform(0.01, 1, 300))
    assert_twins_agree("vc-x-ms-view", trans, k, t0, ulp=4)
    mu = np.float32(rng.uniform(-1, 1, 300))
    alpha = np.float32(rng.uniform(0, 1, 300))
    assert_twins_agree("vc-x-ambient-aniso", mu, trans, alpha, ulp=4)


#: the views of the image tests of the terms: from 0.3 km looking up 25 deg, from 6 km looking down 35 deg
_BELOW = dict(camera_altitude_km=0.3, camera_pitch_deg=25.0)
_ABOVE = dict(camera_altitude_km=6.0, camera_pitch_deg=-35.0)


#: The terms of the image tests, off in their base model (each test turns its own on; the defaults turn them on)
VIEW_TERMS_OFF = dict(ms_view=0.0, ms_view_trans=1.0, ambient_aniso=0.0, ms_slab=0.0, ms_slab_mu=1.0, ms_slab_far=0.0)


def _pixel_renderer():
    """(px, xs, ys): 200 sampled pixels of the small scene, and ``px(**settings)`` -> (their Warp colours, the
    technique) in the physical medium with the octaves' gain on (b = 0.5, the sky's ambient alone), the terms of
    VIEW_TERMS_OFF off, no haze, no powder, no jitter."""
    from pywarp.clouds.cloudscape import render_pixels_warp

    phys = dict(units="physical", phase="mie", lighting="sky", mie_delta=1.0, ms_depth=1.5, ms_thin=0.3,
                aerial_km=0.0, powder=False, jitter="none", ambient_ground_weight=0.0, advanced={"ms_b": 0.5},
                **VIEW_TERMS_OFF)
    rng = np.random.default_rng(2)
    xs, ys = rng.integers(0, SMALL["width"], 200), rng.integers(0, SMALL["height"], 200)

    def px(**kw):
        t = CloudscapeTechnique(small(**{**phys, **kw}))
        return render_pixels_warp(t, xs, ys), t

    return px, xs, ys


def _agrees_with_c(w, t, xs, ys):
    """Warp's colours ``w`` of the sampled pixels are finite and C's of the same technique's settings agree."""
    from pywarp.clouds.cloudscape import render_pixels_c

    c = render_pixels_c(t.settings, t.textures, xs, ys)
    assert np.all(np.isfinite(w))
    np.testing.assert_allclose(w, c, rtol=0, atol=1e-5)


def test_ms_view_and_ambient_aniso_change_the_image_as_stated():
    """Whole pixels, C and Warp: the view weight brightens the clouds and never darkens a pixel (weight >= 1 on the
    octaves only); with the ambient's anisotropy a view from above is darker than without, one from below brighter;
    C and Warp agree on sampled pixels with both terms on."""
    px, xs, ys = _pixel_renderer()
    below, above = _BELOW, _ABOVE
    base_b, _ = px(**below)
    view_b, _ = px(ms_view=3.0, ms_view_trans=0.3, **below)
    assert np.all(view_b >= base_b - 1e-6) and np.mean(view_b.sum(1) > base_b.sum(1) + 1e-4) > 0.1
    aniso_b, _ = px(ambient_aniso=0.6, **below)
    base_a, _ = px(**above)
    aniso_a, _ = px(ambient_aniso=0.6, **above)
    cloudy_b = np.any(np.abs(aniso_b - base_b) > 1e-5, axis=1)
    cloudy_a = np.any(np.abs(aniso_a - base_a) > 1e-5, axis=1)
    assert cloudy_a.mean() > 0.1 and cloudy_b.mean() > 0.1
    assert aniso_a[cloudy_a].sum() < base_a[cloudy_a].sum() and aniso_b[cloudy_b].sum() > base_b[cloudy_b].sum()
    for view in (below, above):
        w, t = px(ms_view=3.0, ms_view_trans=0.3, ambient_aniso=0.6, **view)
        _agrees_with_c(w, t, xs, ys)


# --- the octaves' weight by the sun's elevation and the sample's place between the sun and the viewer (vc-x-ms-slab) ---

def _slab(mu0, d, trans, k, p, s_):
    """vc-x-ms-slab in float64, written from its specification (spec/vc.md)."""
    tau_v = -np.log(np.maximum(trans, 1e-30))
    r = np.where(d + tau_v > 0, d / np.where(d + tau_v > 0, d + tau_v, 1.0), 0.0)
    return k * np.maximum(mu0, 0.0) ** p * (1.0 - s_ * r)


@pytest.mark.spec("vc-x-ms-slab")
def test_ms_slab_closed_form_and_limits():
    f = lib().ccl_cloudscape_ms_slab
    mu0 = np.linspace(-0.2, 1.0, 25)
    for d, trans in ((0.0, 1.0), (0.0, 0.2), (4.0, 1.0), (4.0, 0.05), (30.0, 0.9), (1.0, 0.0)):
        for k, p, s_ in ((1.8, 0.5, 0.67), (1.0, 1.0, 0.0), (3.0, 2.0, 1.0)):
            w = np.array([f(float(m), d, trans, k, p, s_) for m in mu0])
            np.testing.assert_allclose(w, _slab(mu0, d, trans, k, p, s_), rtol=2e-6, atol=1e-7)
            # no sun flux at or below the horizon; growing with the sun's elevation
            assert np.all(w[mu0 <= 0] == 0.0) and np.all(np.diff(w) >= 0)
    # the lit side (nothing towards the sun): k mu0^p; the far side (nothing back to the eye): k mu0^p (1 - s)
    assert f(0.25, 0.0, 0.3, 1.0, 0.5, 0.6) == pytest.approx(0.5, rel=1e-6)
    assert f(0.25, 5.0, 1.0, 1.0, 0.5, 0.6) == pytest.approx(0.2, rel=1e-6)
    # deeper towards the sun (d up) at the same view depth: the weight falls
    ws = [f(0.6, d, 0.3, 1.8, 0.5, 0.67) for d in (0.0, 1.0, 5.0, 50.0)]
    assert all(a > b for a, b in zip(ws, ws[1:]))
    assert all(f(float(m), 3.0, 0.5, 0.0, 0.5, 0.67) == 1.0 for m in mu0)  # off


@pytest.mark.spec("vc-x-ms-slab")
def test_ms_slab_c_and_warp_agree():
    rng = np.random.default_rng(13)
    n = 300
    mu0 = np.float32(rng.uniform(-1, 1, n))
    d = np.float32(np.where(rng.uniform(size=n) < 0.1, 0.0, rng.exponential(5.0, n)))
    trans = np.float32(np.where(rng.uniform(size=n) < 0.1, rng.choice([0.0, 1.0], n), rng.uniform(0, 1, n)))
    k = np.float32(np.where(rng.uniform(size=n) < 0.2, 0.0, rng.uniform(0, 5, n)))
    p = np.float32(rng.uniform(0, 4, n))
    s_ = np.float32(rng.uniform(0, 1, n))
    assert_twins_agree("vc-x-ms-slab", mu0, d, trans, k, p, s_, ulp=8)


def test_ms_slab_changes_the_image_as_stated():
    """Whole pixels, C and Warp: with the sun's flux alone (p = 1, s = 0) the octaves fall with the sun's elevation,
    so a low sun darkens the clouds more than a high one against the model without the term; the share lost on the
    far side (s > 0) darkens a view from below (the bases, on the side away from the sun) by more than a view from
    above (the sunlit tops); C and Warp agree on sampled pixels with the term on."""
    px, xs, ys = _pixel_renderer()
    below, above = _BELOW, _ABOVE
    ratio = {}
    for elev in (75.0, 10.0):
        base, _ = px(sun_elevation_deg=elev, **below)
        flux, _ = px(sun_elevation_deg=elev, ms_slab=1.0, **below)
        cloudy = np.any(np.abs(flux - base) > 1e-5, axis=1)
        assert cloudy.mean() > 0.1 and np.all(flux <= base + 1e-6)  # weight mu0 <= 1 on the octaves only
        ratio[elev] = flux[cloudy].sum() / base[cloudy].sum()
    assert ratio[10.0] < ratio[75.0] < 1.0
    far = {}
    for name, view in (("below", below), ("above", above)):
        flux, _ = px(ms_slab=1.0, ms_slab_mu=0.5, **view)
        lost, _ = px(ms_slab=1.0, ms_slab_mu=0.5, ms_slab_far=0.67, **view)
        cloudy = np.any(np.abs(lost - flux) > 1e-5, axis=1)
        assert cloudy.mean() > 0.1 and np.all(lost <= flux + 1e-6)
        far[name] = lost[cloudy].sum() / flux[cloudy].sum()
    assert far["below"] < far["above"]
    for view in (below, above):
        w, t = px(ms_slab=1.8, ms_slab_mu=0.5, ms_slab_far=0.67, ms_view=3.0, ms_view_trans=0.3, **view)
        _agrees_with_c(w, t, xs, ys)


def test_ms_slab_bad_values_are_refused():
    with pytest.raises(ValueError, match="ms_slab"):
        small(ms_slab=-1.0)
    with pytest.raises(ValueError, match="ms_slab_mu"):
        small(ms_slab_mu=4.5)
    with pytest.raises(ValueError, match="ms_slab_far"):
        small(ms_slab_far=1.5)


def test_ms_view_and_ambient_aniso_bad_values_are_refused():
    with pytest.raises(ValueError, match="ms_view"):
        small(ms_view=-1.0)
    with pytest.raises(ValueError, match="ms_view_trans"):
        small(ms_view_trans=0.0)
    with pytest.raises(ValueError, match="ambient_aniso"):
        small(ambient_aniso=1.5)


def test_the_reference_ignores_the_view_terms_and_its_cache_key_too():
    """The path tracer does not read ms_view, ms_view_trans, ambient_aniso, ms_slab* (real-time only): the same image with and
    without them, so they do not key its cache (bench_reference.NOT_IN_REFERENCE_KEY) and the references cached
    before them stay valid; a setting it reads (the sun) changes the key."""
    from dataclasses import replace

    from pywarp.clouds.bench_reference import _reference_key
    from pywarp.clouds.reference import ReferenceRenderer

    s = small(phase="mie", units="physical", lighting="sky", width=12, height=8)
    t = replace(s, ms_view=3.0, ms_view_trans=0.3, ambient_aniso=0.6, ms_slab=1.8, ms_slab_mu=0.5, ms_slab_far=0.67)
    a = ReferenceRenderer(s, spp=2, seed=3).render(encode=False)
    b = ReferenceRenderer(t, spp=2, seed=3).render(encode=False)
    np.testing.assert_array_equal(a, b)
    assert _reference_key(s, "v", 2, 0) == _reference_key(t, "v", 2, 0)
    assert _reference_key(s, "v", 2, 0) != _reference_key(replace(s, sun_elevation_deg=10.0), "v", 2, 0)
