"""The path-traced ground truth (pywarp.clouds.reference): the Henyey-Greenstein sampler, the analytic transmittance
and single scattering of a homogeneous slab, convergence as 1/sqrt(N), the local majorant agreeing with the constant
one, determinism (seed, threads), bad input refused before any kernel, and the CLI."""
from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
import warp as wp

from pywarp.clouds.cloudscape import RenderTextures
from pywarp.clouds.reference import (
    ReferenceParams,
    ReferenceRenderer,
    hg_samples_kernel,
    phase_samples_kernel,
)
from pywarp.clouds.settings import CloudscapeSettings
from pywarp.core.pose import Pose
from pywarp.kernels.camera import pose_camera

SMALL = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)


def small(**kw) -> CloudscapeSettings:
    return CloudscapeSettings(**{"width": 24, "height": 16, **SMALL, **kw})


@pytest.fixture(scope="module")
def textures():
    return RenderTextures.generate(small())


# --- sampling ---------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("g", [-0.6, 0.0, 0.2, 0.85])
def test_hg_sampler_moments(g):
    """The sampled cos(theta) has the HG moments: E[cos] = g and E[P2(cos)] = g^2, i.e. E[cos^2] = (1 + 2 g^2) / 3.
    Tolerance: 5 standard errors of the sample mean (n = 2^18; the variance of cos is <= 1)."""
    n = 1 << 18
    out = wp.zeros(n, dtype=float)
    wp.launch(hg_samples_kernel, dim=n, inputs=[g, wp.uint32(11)], outputs=[out])
    c = out.numpy().astype(np.float64)
    assert np.all(np.abs(c) <= 1.0)
    se1 = c.std() / math.sqrt(n)
    se2 = (c * c).std() / math.sqrt(n)
    assert abs(c.mean() - g) < 5 * se1
    assert abs((c * c).mean() - (1.0 + 2.0 * g * g) / 3.0) < 5 * se2


def _mie_fit(mu, d):
    """The approximate Mie phase (vc-x-mie) written out in float64 from the published fit."""
    hg = lambda g: (1 - g * g) / (4 * np.pi * (1 + g * g - 2 * g * mu) ** 1.5)  # noqa: E731
    g_hg = np.exp(-0.0990567 / (d - 1.67154))
    g_d = np.exp(-2.20679 / (d + 3.91029) - 0.428934)
    a = np.exp(3.62489 - 8.29288 / (d + 5.52825))
    w = np.exp(-0.599085 / (d - 0.641583) - 0.665888)
    return (1 - w) * hg(g_hg) + w * hg(g_d) * (1 + a * mu * mu) / (1 + a * (1 + 2 * g_d * g_d) / 3)


@pytest.mark.spec("vc-x-mie")
@pytest.mark.parametrize("d", [5.0, 15.0, 40.0])
def test_mie_sampler_follows_the_phase_function(d):
    """The sampled cos(theta) of phase=mie (the lobe picked with probability w_D, Draine's lobe by rejection) has the
    distribution of the fit: its CDF at 9 cosines against the quadrature of the float64 formula (Gauss-Legendre in
    theta, dense at the forward peak), and its first two moments. Tolerance: 5 binomial / sample standard errors
    (n = 2^18)."""
    n = 1 << 18
    r = ReferenceParams()
    r.phase = 1  # K.PHASE_MIE
    r.droplet_um = d
    r.g = 0.0
    out = wp.zeros(n, dtype=float)
    wp.launch(phase_samples_kernel, dim=n, inputs=[r, wp.uint32(17)], outputs=[out])
    c = out.numpy().astype(np.float64)
    assert np.all(np.abs(c) <= 1.0)
    x, w = np.polynomial.legendre.leggauss(200)
    edges = np.radians([0.0, 0.25, 1.0, 4.0, 15.0, 45.0, 180.0])
    th = np.concatenate([0.5 * (b - a) * x + 0.5 * (a + b) for a, b in zip(edges[:-1], edges[1:])])
    wt = np.concatenate([0.5 * (b - a) * w for a, b in zip(edges[:-1], edges[1:])])
    mass = 2 * np.pi * wt * np.sin(th) * _mie_fit(np.cos(th), d)
    for m, k in ((c, 1), (c * c, 2)):
        expected = float(np.sum(mass * np.cos(th) ** k))
        assert abs(m.mean() - expected) < 5 * m.std() / math.sqrt(n), (k, m.mean(), expected)
    for mu0 in (-0.9, -0.5, 0.0, 0.5, 0.8, 0.95, 0.99, 0.998, 0.9995):
        p = float(np.sum(mass[np.cos(th) <= mu0]))  # P(cos <= mu0)
        assert abs(np.mean(c <= mu0) - p) < 5 * math.sqrt(p * (1 - p) / n) + 1e-4, (mu0, np.mean(c <= mu0), p)


# --- the homogeneous slab: closed forms -------------------------------------------------------------------------------

SLAB = dict(layer_base_km=1.5, layer_top_km=1.6, sigma_per_km=30.0, sun_elevation_deg=90.0, width=8, height=8,
            fov_y_deg=2.0)
RHO = 0.5  # tau = 30 * 0.5 * 0.1 = 1.5


def _mean_and_se(r: ReferenceRenderer, img: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mean over the pixels per channel and its standard error from the per-pixel standard errors."""
    se = r.stats["std_error_image"].astype(np.float64)
    n = img.shape[0] * img.shape[1]
    return img.reshape(-1, 3).mean(axis=0), np.sqrt((se.reshape(-1, 3) ** 2).sum(axis=0)) / n


def test_slab_transmittance_of_the_unscattered_sun(textures):
    """A purely absorbing slab (albedo 0) of optical depth tau = sigma rho L = 1.5 between an overhead sun and a
    Lambertian ground of albedo A, seen from below the slab looking down, black sky: the ground's radiance is
    A / pi * E_sun * exp(-tau) exactly (the only light is the sun's, unscattered through the slab; ratio tracking
    with null collisions at rho = 0.5 < the bound 1). The camera looks 1 deg from the nadir, so cos(sun, normal)
    = 1 - O(1e-10). Tolerance: 4 standard errors of the Monte Carlo mean."""
    s = small(**SLAB, camera_altitude_km=0.5, camera_pitch_deg=-89.0)
    a = (0.5, 0.3, 0.8)
    r = ReferenceRenderer(s, textures, spp=128, seed=3, bounces=2, albedo=0.0, density="slab", slab_density=RHO,
                          sky=False, ground_albedo=a, pixel_filter="centre")
    img = r.render(encode=False)
    mean, se = _mean_and_se(r, img)
    e_sun = np.array([r.params.sun_colour[i] for i in range(3)], dtype=np.float64)
    expected = np.array(a) / math.pi * e_sun * math.exp(-30.0 * RHO * 0.1)
    assert np.all(se > 0) and np.all(se < 0.02 * expected)  # the estimate is noisy, and the noise is small
    assert np.all(np.abs(mean - expected) < 4 * se), (mean, expected, se)
    # and not the transmittance of another depth: 10 % off is many standard errors away
    assert np.all(np.abs(mean - expected * math.exp(-0.1 * 1.5)) > 4 * se)


def test_slab_single_scattering_closed_form(textures):
    """Looking up through a scattering slab (albedo 1) at an overhead sun, single scattering only (bounces = 1),
    black sky and ground: L = E p_HG(mu) e^-tau (1 - e^(-tau (1 - mu) / mu)) / (1 - mu) with mu the cosine between
    the view ray and the vertical (the view path t and the sun path L - t mu add up to tau + sigma rho t (1 - mu));
    -> E p(1) tau e^-tau at mu = 1. Evaluated per pixel-centre ray. Tolerance: 4 standard errors."""
    s = small(**SLAB, camera_altitude_km=0.5, camera_pitch_deg=89.0)
    r = ReferenceRenderer(s, textures, spp=128, seed=5, bounces=1, albedo=1.0, density="slab", slab_density=RHO,
                          sky=False, ground_albedo=(0.0, 0.0, 0.0), pixel_filter="centre")
    img = r.render(encode=False)
    mean, se = _mean_and_se(r, img)
    from pywarp import camera_ray

    cam = pose_camera(Pose.from_settings(s), s.width, s.height)
    ys, xs = np.mgrid[0:s.height, 0:s.width]
    d = np.asarray(camera_ray(xs.ravel(), ys.ravel(), s.width, s.height, cam), dtype=np.float64)
    sun = np.asarray(s.sun(), dtype=np.float64)
    mu = d @ sun  # the sun is overhead: the cosine to the vertical is the phase angle's
    g = s.g
    tau = 30.0 * RHO * 0.1
    phase = (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * mu) ** 1.5)
    x = tau * (1 - mu) / mu
    shape = np.where(x > 1e-6, -np.expm1(-x) / np.maximum(1 - mu, 1e-300), tau / mu)
    e_sun = np.array([r.params.sun_colour[i] for i in range(3)], dtype=np.float64)
    expected = e_sun * np.mean(phase * math.exp(-tau) * shape)
    assert np.all(np.abs(mean - expected) < 4 * se), (mean, expected, se)
    assert np.all(se < 0.02 * expected)


@pytest.mark.spec("vc-x-mie")
def test_slab_single_scattering_with_the_mie_phase(textures):
    """test_slab_single_scattering_closed_form with phase=mie: the same closed form with the float64 Mie fit in place
    of HG (the reference's next-event estimation evaluates the medium's phase). Tolerance: 4 standard errors."""
    s = small(**{**SLAB, "fov_y_deg": 40.0}, camera_altitude_km=0.5, camera_pitch_deg=70.0, phase="mie",
              droplet_um=10.0)
    r = ReferenceRenderer(s, textures, spp=256, seed=6, bounces=1, albedo=1.0, density="slab", slab_density=RHO,
                          sky=False, ground_albedo=(0.0, 0.0, 0.0), pixel_filter="centre")
    img = r.render(encode=False)
    mean, se = _mean_and_se(r, img)
    from pywarp import camera_ray

    cam = pose_camera(Pose.from_settings(s), s.width, s.height)
    ys, xs = np.mgrid[0:s.height, 0:s.width]
    d = np.asarray(camera_ray(xs.ravel(), ys.ravel(), s.width, s.height, cam), dtype=np.float64)
    mu = d @ np.asarray(s.sun(), dtype=np.float64)
    tau = 30.0 * RHO * 0.1
    x = tau * (1 - mu) / mu
    shape = np.where(x > 1e-6, -np.expm1(-x) / np.maximum(1 - mu, 1e-300), tau / mu)
    e_sun = np.array([r.params.sun_colour[i] for i in range(3)], dtype=np.float64)
    expected = e_sun * np.mean(_mie_fit(mu, 10.0) * math.exp(-tau) * shape)
    assert np.all(np.abs(mean - expected) < 4 * se), (mean, expected, se)
    assert np.all(se < 0.02 * expected)


def _cut(d, cut_deg):
    """(p_c, f_c) of the truncated Mie phase from the float64 fit: the phase at the cut, and 2 pi int (p - p_c) dmu
    over the cone (Gauss-Legendre in theta, dense at the ~0.4 deg peak)."""
    x, w = np.polynomial.legendre.leggauss(200)
    edges = np.radians([0.0, 0.1, 0.3, 1.0, cut_deg])
    th = np.concatenate([0.5 * (b - a) * x + 0.5 * (a + b) for a, b in zip(edges[:-1], edges[1:])])
    wt = np.concatenate([0.5 * (b - a) * w for a, b in zip(edges[:-1], edges[1:])])
    p_c = float(_mie_fit(math.cos(math.radians(cut_deg)), d))
    return p_c, float(np.sum(2 * np.pi * wt * np.sin(th) * np.maximum(_mie_fit(np.cos(th), d) - p_c, 0.0)))


@pytest.mark.parametrize("d, cut", [(15.0, 3.0), (5.0, 1.0), (40.0, 5.0)])
def test_truncated_peak_cut_and_its_sampler(d, cut):
    """peak_cut: p_c and f_c against the float64 fit's quadrature (rtol 1e-3: p_c is float32); and the sampler of the
    truncated phase min(p, p_c) / (1 - f_c) (rejection from the full phase) follows it: its CDF at 8 cosines against
    the quadrature, 5 binomial standard errors (n = 2^18); nothing inside the cone beyond its flattened share."""
    from pywarp.clouds.reference import peak_cut

    cos_c, p_c, f_c = peak_cut(d, cut)
    ref_pc, ref_fc = _cut(d, cut)
    assert cos_c == pytest.approx(math.cos(math.radians(cut)), abs=1e-7)
    assert p_c == pytest.approx(ref_pc, rel=1e-3) and f_c == pytest.approx(ref_fc, rel=1e-3, abs=1e-4)
    n = 1 << 18
    r = ReferenceParams()
    r.phase = 1  # K.PHASE_MIE
    r.droplet_um = d
    r.peak_cut = 1
    r.cut_value, r.cut_share = p_c, f_c
    out = wp.zeros(n, dtype=float)
    wp.launch(phase_samples_kernel, dim=n, inputs=[r, wp.uint32(19)], outputs=[out])
    c = out.numpy().astype(np.float64)
    x, w = np.polynomial.legendre.leggauss(200)
    edges = np.radians(sorted({0.0, 0.25, 1.0, cut, 4.0, 15.0, 45.0, 180.0}))  # the kink at the cut on an edge
    th = np.concatenate([0.5 * (b - a) * x + 0.5 * (a + b) for a, b in zip(edges[:-1], edges[1:])])
    wt = np.concatenate([0.5 * (b - a) * w for a, b in zip(edges[:-1], edges[1:])])
    # the phase falls monotonically past the cut (no lobe above p_c outside the cone: f_c is all of p - p_c > 0)
    assert np.all(_mie_fit(np.cos(th[th > math.radians(cut)]), d) <= ref_pc)
    mass = 2 * np.pi * wt * np.sin(th) * np.minimum(_mie_fit(np.cos(th), d), ref_pc) / (1.0 - ref_fc)
    assert float(np.sum(mass)) == pytest.approx(1.0, abs=1e-4)  # normalised
    for mu0 in (-0.5, 0.0, 0.5, 0.9, 0.99, 0.998, math.cos(math.radians(cut)), 0.99995):
        q = float(np.sum(mass[np.cos(th) <= mu0]))
        assert abs(np.mean(c <= mu0) - q) < 5 * math.sqrt(q * (1 - q) / n) + 1e-4, (mu0, np.mean(c <= mu0), q)


@pytest.mark.parametrize("pitch, fov", [(70.0, 40.0), (89.0, 3.0)])
def test_truncated_peak_single_scattering_is_tms(textures, pitch, fov):
    """peak='truncated' scatters the camera ray's sun through the full phase over 1 - f_c in the scaled medium (TMS):
    with one scattering (bounces = 1) the image is test_slab_single_scattering_with_the_mie_phase's closed form with
    the optical depth tau (1 - f_c) and the phase p / (1 - f_c) -- p the float64 fit, f_c its quadrature -- for a
    wide view and for one within 3 deg of the sun (inside the cut, where the truncated phase min(p, p_c) would be far
    off). Tolerance: 4 standard errors; and not the exact medium's value (nor, near the sun, the truncated phase's)."""
    d_um = 10.0
    s = small(**{**SLAB, "fov_y_deg": fov}, camera_altitude_km=0.5, camera_pitch_deg=pitch, phase="mie",
              droplet_um=d_um)
    r = ReferenceRenderer(s, textures, spp=256, seed=6, bounces=1, albedo=1.0, density="slab", slab_density=RHO,
                          sky=False, ground_albedo=(0.0, 0.0, 0.0), pixel_filter="centre", peak="truncated")
    mean, se = _mean_and_se(r, r.render(encode=False))
    from pywarp import camera_ray

    cam = pose_camera(Pose.from_settings(s), s.width, s.height)
    ys, xs = np.mgrid[0:s.height, 0:s.width]
    d = np.asarray(camera_ray(xs.ravel(), ys.ravel(), s.width, s.height, cam), dtype=np.float64)
    mu = d @ np.asarray(s.sun(), dtype=np.float64)
    e_sun = np.array([r.params.sun_colour[i] for i in range(3)], dtype=np.float64)
    p_c, f_c = _cut(d_um, 3.0)

    def single(tau, p):
        x = tau * (1 - mu) / mu
        shape = np.where(x > 1e-6, -np.expm1(-x) / np.maximum(1 - mu, 1e-300), tau / mu)
        return e_sun * np.mean(p * math.exp(-tau) * shape)

    tau = 30.0 * RHO * 0.1
    p = _mie_fit(mu, d_um)
    expected = single(tau * (1 - f_c), p / (1 - f_c))
    assert np.all(np.abs(mean - expected) < 4 * se), (mean, expected, se)
    assert np.all(se < 0.02 * expected)
    others = [single(tau, p)] + ([single(tau * (1 - f_c), np.minimum(p, p_c) / (1 - f_c))] if fov < 5 else [])
    for other in others:
        assert np.all(np.abs(mean - other) > 4 * se), (mean, other)


@pytest.mark.parametrize("albedo", [1.0, 0.0])
def test_truncated_peak_passes_its_share_unscattered(textures, albedo):
    """The sun on the ground under a slab, seen from below it (bounces = 1: the ground's next-event estimate only):
    with peak='truncated' the slab's transmittance is exp(-tau (1 - omega f_c)) -- f_c of the float64 quadrature --
    and exp(-tau) when nothing scatters (albedo 0). Tolerance: 4 standard errors; not the exact medium's exp(-tau)
    at albedo 1."""
    s = small(**SLAB, camera_altitude_km=0.5, camera_pitch_deg=-89.0, phase="mie")
    a = (0.5, 0.3, 0.8)
    r = ReferenceRenderer(s, textures, spp=128, seed=3, bounces=1, albedo=albedo, density="slab", slab_density=RHO,
                          sky=False, ground_albedo=a, pixel_filter="centre", peak="truncated")
    mean, se = _mean_and_se(r, r.render(encode=False))
    e_sun = np.array([r.params.sun_colour[i] for i in range(3)], dtype=np.float64)
    tau = 30.0 * RHO * 0.1
    f_c = _cut(s.droplet_um, 3.0)[1]
    expected = np.array(a) / math.pi * e_sun * math.exp(-tau * (1.0 - albedo * f_c))
    assert np.all(np.abs(mean - expected) < 4 * se), (mean, expected, se)
    if albedo > 0:
        assert np.all(np.abs(mean - expected * math.exp(-tau * f_c)) > 4 * se)


def test_forward_peak_option_is_checked(textures):
    with pytest.raises(ValueError, match="peak must be one of 'exact', 'truncated'"):
        ReferenceRenderer(small(phase="mie"), textures, spp=2, peak="none")
    with pytest.raises(ValueError, match="needs the Mie phase"):
        ReferenceRenderer(small(), textures, spp=2, peak="truncated")
    with pytest.raises(ValueError, match=r"peak_cut_deg must be in \[0.5, 5\]"):
        ReferenceRenderer(small(phase="mie"), textures, spp=2, peak="truncated", peak_cut_deg=10.0)


def test_clear_sky_ground_in_physical_units(textures):
    """units=physical, no clouds, the sun overhead, a Lambertian ground seen from 0.5 km looking down: L = A / pi
    (E_sun + E_sky) with E_sun = k 127.5 klx x the transmittance towards the sun (Preetham A.1,
    pywarp.clouds.sky.sun_attenuation) and E_sky = int k C_HDR cos dw, the Preetham sky before its tone map
    (pywarp.sky_preetham_colour, output='hdr', negative channels at 0) integrated by an independent quadrature. One
    bounce. Tolerance: 4 standard errors and the quadrature's 0.3 %."""
    import pywarp
    from pywarp.clouds.sky import sun_attenuation

    s = small(**SLAB, coverage=0.0, camera_altitude_km=0.5, camera_pitch_deg=-89.0, units="physical")
    a = (0.2, 0.5, 0.35)
    r = ReferenceRenderer(s, spp=256, seed=13, bounces=1, ground_albedo=a, pixel_filter="centre")
    img = r.render(encode=False)
    mean, se = _mean_and_se(r, img)
    k = s.sky_exposure
    _, att = sun_attenuation(np.float32(0.0), s.turbidity)
    e_sun = k * 127.5 * att.astype(np.float64)
    th = (np.arange(90) + 0.5) * (math.pi / 2) / 90
    ph = (np.arange(180) + 0.5) * 2 * math.pi / 180
    T, P = np.meshgrid(th, ph, indexing="ij")
    d = np.stack([np.sin(T) * np.sin(P), np.cos(T), -np.sin(T) * np.cos(P)], axis=-1).reshape(-1, 3)
    hdr = np.asarray(pywarp.sky_preetham_colour(d.astype(np.float32), s.turbidity, s.sun_elevation_deg,
                                                s.sun_azimuth_deg, exposure=k, output="hdr"), dtype=np.float64)
    dw = (np.sin(T) * np.cos(T)).reshape(-1, 1) * (math.pi / 2 / 90) * (2 * math.pi / 180)
    e_sky = k * (np.maximum(hdr, 0.0) * dw).sum(axis=0)
    expected = np.array(a) / math.pi * (e_sun + e_sky)
    assert np.all(np.abs(mean - expected) < 4 * se + 0.003 * expected), (mean, expected, se)
    assert np.all(se < 0.01 * expected)


def test_clear_sky_ground_is_lit_by_sun_and_sky_closed_form(textures):
    """No clouds (coverage 0), the gradient sky, the sun overhead, a Lambertian ground seen from 0.5 km looking
    down: L = A / pi (E_sun + E_sky) with the sky's irradiance in closed form, E_sky = int L_sky cos dw over the
    hemisphere = pi H + 2 pi (Z - H) / 3 + 2 pi S / (n + 2) (horizon H, zenith Z, sun glow S max(cos, 0)^n about
    the zenith). One bounce: the ground's sky light comes from the path escaping after it. Tolerance: 4 standard
    errors."""
    from pywarp.kernels.sky import GRADIENT_DEFAULTS as G

    s = small(**{**SLAB, "sigma_per_km": 30.0}, sky="gradient", coverage=0.0, camera_altitude_km=0.5,
              camera_pitch_deg=-89.0)
    a = (0.2, 0.5, 0.35)
    r = ReferenceRenderer(s, spp=256, seed=12, bounces=1, ground_albedo=a, pixel_filter="centre")
    img = r.render(encode=False)
    mean, se = _mean_and_se(r, img)
    e_sun = np.array([r.params.sun_colour[i] for i in range(3)], dtype=np.float64)
    h, z, sun = (np.array(G[k], dtype=np.float64) for k in ("horizon_colour", "zenith_colour", "sun_colour"))
    e_sky = math.pi * h + 2 * math.pi * (z - h) / 3 + 2 * math.pi * sun / (G["sun_exponent"] + 2)
    expected = np.array(a) / math.pi * (e_sun + e_sky)
    assert np.all(np.abs(mean - expected) < 4 * se), (mean, expected, se)
    assert np.all(se < 0.01 * expected)


# --- convergence and determinism --------------------------------------------------------------------------------------

def test_error_falls_as_one_over_sqrt_n(textures):
    """RMS error of 24x16 images of N = 4, 16, 64, 256 paths per pixel (independent seeds) against a 1024-path image
    of another seed: the fitted slope of log RMS over log N is -0.5 +- 0.15. The reference's own variance (its
    per-pixel squared standard errors, an unbiased estimate) is subtracted from each mean squared error, so the
    slope measures the renders' noise alone."""
    s = small()
    ref = ReferenceRenderer(s, textures, spp=1024, seed=1000)
    truth = ref.render(encode=False).astype(np.float64)
    ref_var = float(np.mean(ref.stats["std_error_image"].astype(np.float64) ** 2))
    ns = np.array([4, 16, 64, 256])
    rms = []
    for k, n in enumerate(ns):
        img = ReferenceRenderer(s, textures, spp=int(n), seed=1 + k).render(encode=False)
        mse = float(np.mean((img - truth) ** 2)) - ref_var
        assert mse > 0
        rms.append(math.sqrt(mse))
    slope = np.polyfit(np.log(ns), np.log(rms), 1)[0]
    assert -0.65 <= slope <= -0.35, (slope, rms)
    assert np.std(truth) > 0.05  # the frame has structure (clouds, sky, ground), not a flat colour


def test_local_majorant_gives_the_same_image_in_expectation(textures):
    """The pyramid majorants (local bounds per 0.25 km chunk) and the constant bound sigma * 1 sample the same
    transport: the mean over the frame agrees within 4 standard errors of the difference, per channel."""
    s = small()
    a = ReferenceRenderer(s, textures, spp=64, seed=21)
    ia = a.render(encode=False)
    b = ReferenceRenderer(s, textures, spp=64, seed=22, majorant=False)
    ib = b.render(encode=False)
    ma, sa = _mean_and_se(a, ia)
    mb, sb = _mean_and_se(b, ib)
    assert np.all(np.abs(ma - mb) < 4 * np.sqrt(sa ** 2 + sb ** 2)), (ma, mb, sa, sb)
    # the local bounds held at every density sample (no fallback to the constant bound)
    assert a.stats["majorant"] == "local" and b.stats["majorant"] == "constant"


@pytest.mark.parametrize("scene", ["noon", "low sun", "from above"])
def test_local_majorant_bounds_the_density_of_the_benchmark_scenes(textures, scene):
    """Every density sample of the benchmark's scenes (wind-shifted, de-tiled weather, both thresholds) stays under
    its chunk's bound: the render keeps the local majorant."""
    from dataclasses import replace

    from pywarp.clouds.bench_reference import SCENES

    for extra in ({}, dict(coverage_threshold="coverage", time_s=1800.0)):
        s = replace(small(width=32, height=18), **SCENES[scene], **extra)
        r = ReferenceRenderer(s, textures, spp=2, seed=9)
        r.render(encode=False)
        assert r.stats["majorant"] == "local"


def test_a_broken_bound_falls_back_to_the_constant_majorant(monkeypatch, textures):
    """Bounds made too small (the per-texel base shape lowered by 0.3) are caught by the per-sample check: the
    samples are redone with the constant majorant, with a warning, and the image is the constant majorant's."""
    from pywarp.clouds import reference

    s = small(width=16, height=10)
    expected = ReferenceRenderer(s, textures, spp=4, seed=6, majorant=False).render(encode=False)
    monkeypatch.setattr(reference, "B_MARGIN", -0.3)
    r = ReferenceRenderer(s, textures, spp=4, seed=6)
    fractions = []
    with pytest.warns(RuntimeWarning, match="constant majorant"):
        img = r.render(encode=False, progress=fractions.append)
    assert r.stats["majorant"].startswith("constant (the local bound was exceeded")
    assert np.array_equal(img, expected)
    assert sum(fractions) == pytest.approx(1.0)


def test_same_seed_same_image_on_one_and_two_threads(textures):
    s = small(width=20, height=12)
    one = ReferenceRenderer(s, textures, spp=3, seed=7, threads=1).render(encode=False)
    two = ReferenceRenderer(s, textures, spp=3, seed=7, threads=2).render(encode=False)
    again = ReferenceRenderer(s, textures, spp=3, seed=7, threads=2).render(encode=False)
    other = ReferenceRenderer(s, textures, spp=3, seed=8, threads=2).render(encode=False)
    assert np.array_equal(one, two) and np.array_equal(two, again)
    assert not np.array_equal(two, other)
    assert np.all(np.isfinite(one))


def test_passes_do_not_change_the_image(monkeypatch, textures):
    """The samples are split into launches of PASS_SPP (for the progress bar and Ctrl-C); each sample is added to
    the pixel's float64 sum in sample order, so the split changes no bit."""
    from pywarp.clouds import reference

    s = small(width=12, height=8)
    a = ReferenceRenderer(s, textures, spp=6, seed=2).render(encode=False)
    monkeypatch.setattr(reference, "PASS_SPP", 1)
    b = ReferenceRenderer(s, textures, spp=6, seed=2).render(encode=False)
    assert np.array_equal(a, b)


def test_the_scene_technique_protocol(textures):
    """make_technique gives the reference with settings.reference; update keeps the constructor's arguments and
    follows the settings; resize changes the frame."""
    from pywarp.clouds.scene import make_technique

    t = make_technique(small(width=12, height=8, reference=True, spp=2, reference_seed=3))
    assert isinstance(t, ReferenceRenderer) and t.spp == 2 and t.seed == 3
    a = t.render(encode=False)
    t.update(sun_elevation_deg=60.0)
    b = t.render(encode=False)
    assert t.spp == 2 and a.shape == b.shape == (8, 12, 3) and not np.array_equal(a, b)
    t.resize(10, 6)
    assert t.render().shape == (6, 10, 3)
    r = ReferenceRenderer(small(width=8, height=6), textures, spp=3, bounces=5)
    r.update(spp=9)  # the settings' spp does not override an explicit argument
    assert r.spp == 3 and r.bounces == 5


def test_encoded_image_is_the_real_time_encoding(textures):
    from pywarp.clouds.reference import encode_srgb

    s = small(width=16, height=10)
    r = ReferenceRenderer(s, textures, spp=2, seed=1)
    lin = r.render(encode=False)
    img = ReferenceRenderer(s, textures, spp=2, seed=1).render()
    assert img.dtype == np.uint8 and img.shape == (10, 16, 3)
    assert np.array_equal(img, encode_srgb(lin))
    c = np.clip(lin.astype(np.float64), 0, 1)
    srgb = np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)
    assert np.max(np.abs(img.astype(int) - np.floor(srgb * 255 + 0.5).astype(int))) <= 1


# --- bad input --------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs,message", [
    (dict(spp=0), "spp must be in [1, 65536], got 0"),
    (dict(spp=65537), "spp must be in [1, 65536], got 65537"),
    (dict(bounces=0), "bounces must be in [1, 4096], got 0"),
    (dict(bounces=4097), "bounces must be in [1, 4096], got 4097"),
    (dict(seed=-1), "seed must be in [0, 4294967295], got -1"),
    (dict(albedo=1.5), "albedo must be in [0, 1], got 1.5"),
    (dict(phase_g=1.0), "phase_g must be in [-0.999, 0.999], got 1.0"),
    (dict(max_steps=10), "max_steps must be >= "),
    (dict(pixel_filter="gauss"), "pixel_filter must be one of 'box', 'centre', got 'gauss'"),
    (dict(density="fog"), "density must be one of 'cloudscape', 'slab', got 'fog'"),
    (dict(ground_albedo=(0.1, 2.0, 0.1)), "ground_albedo must be in [0, 1], got 2.0"),
])
def test_bad_parameters_are_refused_before_any_kernel(monkeypatch, kwargs, message):
    def no_launch(*a, **k):
        raise AssertionError("a kernel ran before the validation")

    monkeypatch.setattr(wp, "launch", no_launch)
    with pytest.raises(ValueError) as exc:
        ReferenceRenderer(small(), **kwargs)
    assert str(exc.value).startswith(message), str(exc.value)


def test_bad_types_are_refused():
    with pytest.raises(TypeError, match="spp must be an integer"):
        ReferenceRenderer(small(), spp=2.5)
    with pytest.raises(TypeError, match="bounces must be an integer"):
        ReferenceRenderer(small(), bounces=True)


def test_settings_fields_are_validated():
    with pytest.raises(ValueError, match="spp"):
        small(spp=0)
    with pytest.raises(ValueError, match="reference_bounces"):
        small(reference_bounces=5000)


# --- the command line -------------------------------------------------------------------------------------------------

def _cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "pywarp", *args], capture_output=True, text=True, cwd=cwd)


_CLI_SMALL = ["--base-size", "32", "--detail-size", "16", "--curl-size", "32", "--weather-size", "64"]


def test_cli_reference_writes_the_path_traced_image(tmp_path, textures):
    out = tmp_path / "ref.png"
    res = _cli("render", "clouds", "--reference", "--spp", "2", "--reference-seed", "4", "--width", "24",
               "--height", "16", *_CLI_SMALL, "--out", str(out), "--no-progress", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    from PIL import Image

    img = np.asarray(Image.open(out))
    expected = ReferenceRenderer(small(), textures, spp=2, seed=4).render()
    assert np.array_equal(img, expected)


@pytest.mark.parametrize("args,message", [
    (["--spp", "0"], "pywarp render: error: --spp must be in [1, 65536], got 0"),
    (["--bounces", "4097"], "pywarp render: error: --bounces must be in [1, 4096], got 4097"),
    (["--reference-seed", "-2"], "pywarp render: error: --reference-seed must be in [0, 4294967295], got -2"),
])
def test_cli_reference_bad_values_one_line_no_file(tmp_path, args, message):
    res = _cli("render", "clouds", "--reference", "--width", "16", "--height", "9", *args, cwd=tmp_path)
    assert res.returncode == 2
    assert res.stderr.strip().splitlines()[-1].startswith(message), res.stderr
    assert list(tmp_path.iterdir()) == []


# --- the benchmark's metrics ----------------------------------------------------------------------------------------

def test_absolute_errors_keep_the_exposure_and_split_by_class(rng):
    """No rescaling: a model twice as bright as the reference has energy ratio 2 in every class and a positive dE;
    the reference itself has ratio 1 and dE 0; the classes follow the optical depth."""
    from pywarp.clouds.bench_reference import absolute_errors, exposure

    ref = rng.uniform(0.05, 1.0, (10, 12, 3))
    tau = np.zeros((10, 12))
    tau[:3] = 5.0
    tau[3:6] = 1.0
    same = absolute_errors(ref, ref, exposure(ref), tau)
    assert same["delta_e"] == pytest.approx(0.0, abs=1e-9)
    assert same["pixels"] == {"clear": 48, "thin": 36, "thick": 36}
    double = ref.copy()
    double[:3] *= 2.0  # only the thick pixels
    e = absolute_errors(double, ref, exposure(ref), tau)
    np.testing.assert_allclose(e["ratio"]["thick"], 2.0)
    np.testing.assert_allclose(e["ratio"]["thin"], 1.0)
    assert e["delta_e_class"]["thick"] > 1.0 and e["delta_e_class"]["clear"] == pytest.approx(0.0, abs=1e-9)


def test_view_optical_depth_of_the_slab(textures):
    """The slab of optical depth 1.5 seen through from below at the vertical: tau = 1.5 / cos(angle to the vertical)
    per pixel, within 5 standard errors of the 256 ratio-tracking estimates (T's relative error, bounded by
    sqrt((1 - T) / (T n)) for estimates in [0, 1])."""
    s = small(**SLAB, camera_altitude_km=0.5, camera_pitch_deg=89.0)
    r = ReferenceRenderer(s, textures, density="slab", slab_density=RHO)
    tau = r.view_optical_depth(samples=256).astype(np.float64)
    from pywarp import camera_ray

    cam = pose_camera(Pose.from_settings(s), s.width, s.height)
    ys, xs = np.mgrid[0:s.height, 0:s.width]
    d = np.asarray(camera_ray(xs.ravel(), ys.ravel(), s.width, s.height, cam), dtype=np.float64)
    expected = 1.5 / d[:, 1]
    t = np.exp(-expected)
    rel = np.sqrt((1 - t) / (t * 256))
    assert np.all(np.abs(np.exp(-tau.ravel()) / t - 1.0) < 5 * rel + 1e-6)


def test_error_metrics_after_the_best_exposure_scale(rng):
    from pywarp.clouds.bench_reference import best_scale, errors, exposure

    ref = rng.uniform(0.0, 2.0, (20, 30, 3))
    k = best_scale(ref / 3.0, ref)
    assert k == pytest.approx(3.0, rel=1e-12)
    same = errors(ref / 3.0, ref * exposure(ref))  # a model that differs only by its exposure: no error
    assert same["ssim"] == pytest.approx(1.0, abs=1e-9) and same["delta_e"] == pytest.approx(0.0, abs=1e-6)
    assert np.percentile(np.max(ref * exposure(ref), axis=2), 99.5) == pytest.approx(1.0)
    noisy = errors(ref + rng.normal(0.0, 0.5, ref.shape), ref * exposure(ref))
    assert noisy["ssim"] < 0.9 and noisy["delta_e"] > 1.0
    # a colour cast the exposure cannot remove
    tinted = errors(ref * np.array([1.0, 0.8, 0.6]), ref * exposure(ref))
    assert tinted["delta_e"] > 3.0


@pytest.mark.parametrize("medium", ["display", "physical"])
def test_compare_gives_a_row_per_scene_and_model(medium):
    from pywarp.clouds.bench_reference import CLASS_EDGES, MODELS, PHYSICAL_MODELS, compare, report

    res, images = compare(16, 9, spp=4, scenes=["noon"], progress=lambda m: None, settings=SMALL, medium=medium)
    (sc,) = res["scenes"]
    assert res["medium"] == medium
    # the physical medium's references treat the Mie phase's forward peak as unscattered light (converged pixels)
    assert res["peak"] is None and sc["peak"] == ("truncated" if medium == "physical" else "exact")
    extra = list(PHYSICAL_MODELS) if medium == "physical" else []
    assert sc["scene"] == "noon" and [m["model"] for m in sc["models"]] == [*MODELS, *extra, "default"]
    assert sum(sc["pixels"].values()) == 16 * 9
    for m in sc["models"]:
        assert -1.0 <= m["ssim"] <= 1.0 and m["delta_e"] >= 0.0 and m["scale"] > 0.0
        assert images["noon"][m["model"]].shape == (9, 16, 3)
        a = m["absolute"]
        assert a["delta_e"] >= 0.0 and set(a["ratio"]) == set(CLASS_EDGES) == set(a["pixels"])
        for k, r in a["ratio"].items():
            assert (r is None) == (a["pixels"][k] == 0) and (r is None or len(r) == 3)
    assert sc["std_error"] > 0 and 0 < sc["noise_floor"]["ssim"] <= 1 and sc["noise_floor"]["abs_delta_e"] > 0
    assert "noise floor" in report(res)
    import json

    json.dumps(res)  # the --json output
    with pytest.raises(ValueError, match=r"spp must be in \[4, 65536\]"):
        compare(16, 9, spp=3)
    with pytest.raises(ValueError, match="peak must be None, 'exact' or"):
        compare(16, 9, spp=4, medium="display", peak="truncated")


def test_compare_reads_the_references_it_cached(tmp_path):
    """compare(cache=DIR) writes each scene's reference (both halves, the view's optical depth) and reads it back on
    the next run: the same numbers; another path count or scene setting is another file."""
    from pywarp.clouds.bench_reference import compare

    kw = dict(scenes=["noon"], progress=lambda m: None, settings=SMALL, medium="physical", cache=str(tmp_path))
    first, _ = compare(16, 9, spp=4, **kw)
    files = sorted(tmp_path.glob("*.npz"))
    assert len(files) == 1 and files[0].name.startswith("reference-noon-truncated-16x9-4-")
    said = []
    again, _ = compare(16, 9, spp=4, **{**kw, "progress": said.append})
    assert any("from " + str(tmp_path) in m for m in said)
    for a, b in zip(first["scenes"][0]["models"], again["scenes"][0]["models"]):
        assert a["absolute"] == b["absolute"] and a["delta_e"] == b["delta_e"]
    assert first["scenes"][0]["noise_floor"] == again["scenes"][0]["noise_floor"]
    compare(16, 9, spp=6, **kw)
    compare(16, 9, spp=4, **{**kw, "settings": {**SMALL, "droplet_um": 20.0}})
    assert len(list(tmp_path.glob("*.npz"))) == 3
    exact, _ = compare(16, 9, spp=4, **kw, peak="exact")  # the exact forward peak: another reference
    assert len(list(tmp_path.glob("*.npz"))) == 4 and exact["scenes"][0]["peak"] == "exact"
    assert exact["scenes"][0]["noise_floor"] != first["scenes"][0]["noise_floor"]
