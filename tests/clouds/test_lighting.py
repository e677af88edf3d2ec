"""The cloudscape's lighting from the sky model: the sun through the atmosphere (Preetham et al. 1999 appendix A.1),
ambient and ground light from the sky model (ccl_cloudscape_light), the lit and shadowed ground, aerial perspective,
multiple-scattering octaves and the dual-lobe phase -- C vs Warp, closed forms, properties of the images -- and the
thesis's constant lighting reproduced bit for bit."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pywarp.clouds.sky import sun_attenuation
from pywarp.kernels import sky as S

# --- the sun through the atmosphere ---------------------------------------------------------------------------------


#: the encoding of the images before the display transform and of the C reference: the plain clamp (pywarp.core.display)
PLAIN = dict(tonemap="none", exposure_ev=0.0)

def _attenuation_f64(theta_s, turbidity, lambda_um):
    """Preetham et al. 1999 appendix A.1 (Rayleigh + Angstrom terms) in float64, written from the paper."""
    m = 1.0 / (np.cos(theta_s) + 0.15 * (93.885 - np.degrees(theta_s)) ** -1.253)
    beta = 0.04608365822050 * turbidity - 0.04586025928522
    return m, np.exp(-0.008735 * lambda_um ** -4.08 * m) * np.exp(-beta * lambda_um ** -1.3 * m)


THETAS = np.float32(np.radians([0.0, 30.0, 55.0, 70.0, 80.0, 86.0, 87.0]))


@pytest.mark.parametrize("impl", ["warp", "c"])
@pytest.mark.parametrize("turbidity", [2.0, 2.5, 6.0, 10.0])
def test_sun_attenuation_closed_form(impl, turbidity):
    m, t = sun_attenuation(THETAS, turbidity, impl=impl)
    th = THETAS.astype(np.float64)
    for c, lam in enumerate(S.SUN_LAMBDA_UM):
        m_ref, t_ref = _attenuation_f64(th, turbidity, lam)
        # exp(-x), x <= 18 here: relative error x * rel_err(x), rel_err(x) <= ~3e-6 (see cclouds/tests/test_lighting.c)
        x = -np.log(t_ref)
        assert np.all(np.abs(t[:, c] - t_ref) <= (2e-5 + 3e-6 * x) * t_ref), (lam, t[:, c], t_ref)
        np.testing.assert_allclose(m, m_ref, rtol=1e-5)


def test_sun_attenuation_known_values():
    """The values quoted in cclouds/sky.h and cloudscape.c (T = 2.5): zenith, the default 35 deg sun, 4 deg."""
    _, t = sun_attenuation(np.float32(np.radians([0.0, 55.0, 86.0])), 2.5)
    np.testing.assert_allclose(t[0], (0.855, 0.778, 0.637), atol=1e-3)
    np.testing.assert_allclose(t[1], (0.762, 0.646, 0.457), atol=1e-3)
    np.testing.assert_allclose(t[2], (0.145, 0.045, 0.0039), atol=1e-3)
    # the default sun_intensity 16 gives the thesis constant's red channel of 12 at the default elevation
    assert abs(16.0 * t[1, 0] - 12.0) < 0.25


def test_sun_reddens_from_zenith_to_horizon():
    th = np.float32(np.linspace(0.0, np.pi / 2, 46))
    th[-1] = S.HALF_PI_F32
    _, t = sun_attenuation(th, 2.5)
    assert np.all(t[:, 0] >= t[:, 1]) and np.all(t[:, 1] >= t[:, 2]) and np.all(t > 0) and np.all(t <= 1)
    assert np.all(np.diff(t, axis=0) < 0)  # every channel dims as the sun sinks
    rb = t[:, 0] / t[:, 2]
    assert np.all(np.diff(rb) > 0)  # and the light reddens
    assert rb[0] < 1.4 and rb[-1] > 1e4


def test_sun_attenuation_c_equals_warp():
    """Bit for bit: the same float32 operations in the same order with the same libm (powf, expf, cosf)."""
    th = np.float32(np.linspace(0.0, S.HALF_PI_F32, 200))
    for T in (2.0, 3.7, 10.0):
        mw, tw = sun_attenuation(th, T)
        mc, tc = sun_attenuation(th, T, impl="c")
        np.testing.assert_array_equal(mw, mc)
        np.testing.assert_array_equal(tw, tc)


@pytest.mark.parametrize("theta_s,turbidity,match", [(-0.1, 2.5, "theta_s"), (1.6, 2.5, "theta_s"),
                                                     (float("nan"), 2.5, "theta_s"), (0.5, 1.9, "turbidity"),
                                                     (0.5, 10.5, "turbidity")])
def test_sun_attenuation_refuses_bad_input(theta_s, turbidity, match):
    with pytest.raises(ValueError, match=match):
        sun_attenuation(theta_s, turbidity)


# --- the cloudscape's lighting: C and Warp twins ----------------------------------------------------------------------

import warp as wp  # noqa: E402

from pywarp.clouds.cloudscape import (  # noqa: E402
    CloudscapeSettings,
    c_sky,
    c_textures,
    render_frame_c,
    render_pixels_c,
    render_pixels_warp,
)
from pywarp.clouds.technique import CloudscapeTechnique  # noqa: E402
from pywarp.core.pose import Pose  # noqa: E402
from pywarp.clouds import settings as CS  # noqa: E402
from pywarp.clouds.settings import CLOUDSCAPE_PARAMS  # noqa: E402
from pywarp.core.binding import ffi, lib  # noqa: E402
from pywarp.kernels import cloudscape as K  # noqa: E402
from pywarp.kernels.camera import pose_camera  # noqa: E402

SMALL = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)
LIGHT = ("sun_colour", "ambient_top", "ambient_bottom", "ambient_ground")
BELOW = Pose(0.0, 0.3, 0.0, 0.0, 12.0, 60.0)
ABOVE = Pose(0.0, 8.0, 0.0, 30.0, -30.0, 60.0)


def small(**kw) -> CloudscapeSettings:
    return CloudscapeSettings(**{"width": 96, "height": 54, **SMALL, **kw})


@pytest.fixture(scope="module")
def tech():
    return CloudscapeTechnique(small())


def _c_lit(settings):
    """ccl_cloudscape_light of the settings' parameters and sky: the C struct."""
    p = CLOUDSCAPE_PARAMS.to_c(settings.c_values())
    lib().ccl_cloudscape_light(p, c_sky(settings), p)
    return p


@pytest.mark.parametrize("sky", ["preetham", "gradient"])
@pytest.mark.parametrize("elevation", [2.0, 4.0, 35.0, 89.0])
def test_light_c_equals_warp(tech, sky, elevation):
    """The per-frame setup: the same float32 operations in the same order. The sun colour is bit for bit; the sky
    models' twins agree to 2 ulp (their registry bound: a Preetham channel may round differently), the means of 128
    such values in the same order inherit that: rtol 3e-7 (2.5 ulp)."""
    s = small(sky=sky, sun_elevation_deg=elevation, turbidity=3.0)
    t = CloudscapeTechnique(s, textures=tech.textures)
    c = _c_lit(s)
    np.testing.assert_array_equal(np.array(t.params.sun_colour, dtype=np.float32),
                                  np.array(list(c.sun_colour), dtype=np.float32))
    for name in LIGHT[1:]:
        np.testing.assert_allclose(np.array(getattr(t.params, name), dtype=np.float32),
                                   np.array(list(getattr(c, name)), dtype=np.float32), rtol=3e-7, err_msg=name)
    # the sun through the atmosphere of the settings' turbidity
    _, att = sun_attenuation(np.float32(math.radians(90.0 - elevation)), 3.0)
    np.testing.assert_allclose(np.array(t.params.sun_colour), s.sun_intensity * att, rtol=1e-5)
    # ambient: bottom = 0.4 top; the sky is brighter near the horizon than at the zenith, so the cosine-weighted
    # mean (the ground's) lies below the plain mean
    top, bottom, ground = (np.array(getattr(t.params, n)) for n in ("ambient_top", "ambient_bottom", "ambient_ground"))
    np.testing.assert_allclose(bottom, 0.4 * top, rtol=1e-6)
    assert np.all(top > 0) and np.all(ground > 0)


def test_light_thesis_keeps_the_constants(tech):
    s = small(lighting="thesis")
    t = CloudscapeTechnique(s, textures=tech.textures)
    p = ffi().new("ccl_cloudscape_params *")
    lib().ccl_cloudscape_params_default(p)
    for name in ("sun_colour", "ambient_top", "ambient_bottom"):
        np.testing.assert_array_equal(np.array(getattr(t.params, name), dtype=np.float32),
                                      np.array(list(getattr(p, name)), dtype=np.float32))


def test_light_follows_the_sky_on_update(tech):
    t = CloudscapeTechnique(small(sun_elevation_deg=60.0), textures=tech.textures)
    noon = np.array(t.params.sun_colour)
    t.update(sun_elevation_deg=4.0)
    low = np.array(t.params.sun_colour)
    assert np.all(low < noon) and low[0] / low[2] > 10 * noon[0] / noon[2]
    t.update(lighting="thesis")
    np.testing.assert_allclose(np.array(t.params.sun_colour), (12.0, 11.52, 10.56), rtol=1e-6)


@wp.kernel
def _energy_kernel(p: K.CloudscapeParams, d: wp.array(dtype=float), a: wp.array(dtype=float),
                   c: wp.array(dtype=float), out: wp.array(dtype=float)):
    i = wp.tid()
    out[i] = K.cloudscape_energy(p, d[i], a[i], c[i])


@pytest.mark.parametrize("octaves,weight,phase", [(1, 0.0, "thesis"), (3, 0.3, "thesis"), (8, 1.0, "thesis"),
                                                  (1, 0.0, "mie"), (4, 0.3, "mie")])
def test_energy_c_equals_warp(octaves, weight, phase):
    s = small(ms_octaves=octaves, silver_weight=weight, silver_g=0.85, g=0.35, phase=phase, droplet_um=12.0)
    v = s.c_values()
    rng = np.random.default_rng(3)
    d = np.float32(rng.uniform(0, 8, 500))
    a = np.float32(rng.uniform(0, 3, 500))
    c = np.float32(rng.uniform(-1, 1, 500))
    out = wp.zeros(500, dtype=float)
    wp.launch(_energy_kernel, 500, inputs=[CLOUDSCAPE_PARAMS.warp_struct(v), wp.array(d), wp.array(a), wp.array(c)],
              outputs=[out])
    cp = CLOUDSCAPE_PARAMS.to_c(v)
    ce = np.array([lib().ccl_cloudscape_energy(cp, float(x), float(y), float(z)) for x, y, z in zip(d, a, c)],
                  dtype=np.float32)
    np.testing.assert_array_equal(out.numpy(), ce)


@pytest.mark.spec("vc-x-mie")
def test_energy_with_the_mie_phase_closed_form():
    """phase=mie: octave i weighs c^i of the Mie phase and 1 - c^i isotropic, so without Beer and powder the energy is
    sum_i b^i (c^i p_Mie + (1 - c^i) / (4 pi)) -- p_Mie written out in float64 from the published fit; the HG g and
    the silver lobe are not read."""
    d_um = 20.0
    cos_t = np.linspace(-1.0, 1.0, 21)
    g_hg = math.exp(-0.0990567 / (d_um - 1.67154))
    g_d = math.exp(-2.20679 / (d_um + 3.91029) - 0.428934)
    al = math.exp(3.62489 - 8.29288 / (d_um + 5.52825))
    w_d = math.exp(-0.599085 / (d_um - 0.641583) - 0.665888)
    hg = lambda g: (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * cos_t) ** 1.5)  # noqa: E731
    mie = (1 - w_d) * hg(g_hg) + w_d * hg(g_d) * (1 + al * cos_t ** 2) / (1 + al * (1 + 2 * g_d ** 2) / 3)
    for octaves in (1, 3):
        # the full Mie phase (no delta scaling) and the octaves' sum alone (no gain by the depth), b = 0.5
        cp = CLOUDSCAPE_PARAMS.to_c(small(phase="mie", droplet_um=d_um, ms_octaves=octaves, beer=False, powder=False,
                                          silver_weight=0.7, g=-0.5, mie_delta=0.0, ms_depth=0.0,
                                          advanced={"ms_b": 0.5}).c_values())
        e = np.array([lib().ccl_cloudscape_energy(cp, 1.0, 1.0, float(c)) for c in cos_t])
        expected = sum(0.5 ** i * (0.5 ** i * mie + (1 - 0.5 ** i) / (4 * math.pi)) for i in range(octaves))
        np.testing.assert_allclose(e, expected, rtol=3e-4)


def test_physical_units_light_closed_form(tech):
    """units=physical: the sun is k x 127.5 klx x the atmosphere's transmittance (k = sky_exposure), and the ambient
    is the mean of the sky k C_HDR -- the Preetham sky before the tone map (pywarp.sky_preetham_colour,
    output='hdr'), averaged here by an independent quadrature (64 x 128 cells); C and Warp agree."""
    s = small(units="physical", sun_elevation_deg=35.0, sky_exposure=0.05, ambient_ground_weight=0.0)  # the sky alone
    t = CloudscapeTechnique(s, textures=tech.textures)
    c = _c_lit(s)
    np.testing.assert_array_equal(np.array(t.params.sun_colour, dtype=np.float32),
                                  np.array(list(c.sun_colour), dtype=np.float32))
    _, att = sun_attenuation(np.float32(math.radians(55.0)), s.turbidity)
    np.testing.assert_allclose(np.array(t.params.sun_colour), 0.05 * 127.5 * att, rtol=1e-5)
    import pywarp

    th = (np.arange(64) + 0.5) * (math.pi / 2) / 64
    ph = (np.arange(128) + 0.5) * 2 * math.pi / 128
    T, P = np.meshgrid(th, ph, indexing="ij")
    d = np.stack([np.sin(T) * np.sin(P), np.cos(T), -np.sin(T) * np.cos(P)], axis=-1).reshape(-1, 3)
    hdr = np.asarray(pywarp.sky_preetham_colour(d.astype(np.float32), s.turbidity, s.sun_elevation_deg,
                                                s.sun_azimuth_deg, exposure=s.sky_exposure, output="hdr"),
                     dtype=np.float64)
    w = np.sin(T).reshape(-1, 1)
    mean = 0.05 * (np.maximum(hdr, 0.0) * w).sum(axis=0) / w.sum()
    np.testing.assert_allclose(np.array(t.params.ambient_top), mean, rtol=0.01)
    # a physical sky is not tone mapped: its zenith is k C_HDR, beyond 1 - exp(-k C_HDR)
    assert np.all(mean > 1 - np.exp(-mean))


@pytest.mark.parametrize("units", ["display", "physical"])
def test_ambient_ground_weight_blends_in_the_lit_ground(tech, units):
    """ambient_ground_weight w: ambient_top = (1 - w) x the sky's mean + w x the unshadowed ground's radiance
    albedo (E_sun cos theta_s / pi + ambient_ground), from the lights of w = 0; bottom keeps its ratio; C and Warp
    agree."""
    s0 = small(units=units, sun_elevation_deg=50.0, ground_albedo=(0.2, 0.3, 0.1), ambient_ground_weight=0.0)
    t0 = CloudscapeTechnique(s0, textures=tech.textures)
    s = dataclasses.replace(s0, ambient_ground_weight=0.5)
    t = CloudscapeTechnique(s, textures=tech.textures)
    sun, top0, amb_g = (np.array(getattr(t0.params, n), dtype=np.float64)
                        for n in ("sun_colour", "ambient_top", "ambient_ground"))
    ground = np.array([0.2, 0.3, 0.1]) * (sun * math.sin(math.radians(50.0)) / math.pi + amb_g)
    np.testing.assert_allclose(np.array(t.params.ambient_top), 0.5 * top0 + 0.5 * ground, rtol=1e-5)
    np.testing.assert_allclose(np.array(t.params.ambient_bottom), 0.4 * np.array(t.params.ambient_top), rtol=1e-6)
    c = _c_lit(s)
    for name in LIGHT:
        np.testing.assert_allclose(np.array(getattr(t.params, name), dtype=np.float32),
                                   np.array(list(getattr(c, name)), dtype=np.float32), rtol=3e-7, err_msg=name)


@wp.kernel
def _ground_kernel(p: K.CloudscapeParams, tex: K.CloudTextures, pts: wp.array(dtype=wp.vec3), sun: wp.vec3,
                   out: wp.array(dtype=wp.vec3), shadow: wp.array(dtype=float)):
    i = wp.tid()
    g, sh = K.cloudscape_ground(p, tex, pts[i], sun)
    out[i] = g
    shadow[i] = sh


def _ground_points(n: int = 24, half_km: float = 12.0) -> np.ndarray:
    """A grid of points on the Earth sphere (centre (0, -6371, 0)) around the origin."""
    xs = np.linspace(-half_km, half_km, n)
    x, z = np.meshgrid(xs, xs)
    r = CS.EARTH_RADIUS_KM
    y = np.sqrt(r * r - x * x - z * z) - r
    return np.float32(np.stack([x, y, z], axis=-1).reshape(-1, 3))


def _fine_shadow(values, tex_c, point, sun, n: int = 400) -> float:
    """exp(-sigma_light x optical depth) towards the sun from n base-shape samples at full resolution -- the same
    density field, marched independently of ccl_cloudscape_ground (30 times finer)."""
    p = CLOUDSCAPE_PARAMS.to_c({**values, "lod": 0})
    c = np.array([0.0, -CS.EARTH_RADIUS_KM, 0.0])

    def far_root(r):
        f = point - c
        b = f @ sun
        return -b + math.sqrt(b * b - (f @ f - r * r))

    t0, t1 = far_root(CS.EARTH_RADIUS_KM + 1.5), far_root(CS.EARTH_RADIUS_KM + 4.0)
    dt = (t1 - t0) / n
    pr = ffi().new("float *")
    od = 0.0
    for k in range(n):
        q = point + sun * (t0 + (k + 0.5) * dt)
        od += lib().ccl_cloudscape_density(p, tex_c, tuple(float(x) for x in q), 0, pr)
    return math.exp(-values["sigma_light"] * od * dt)


def test_ground_c_equals_warp_and_clouds_shadow_the_ground(tech):
    """The lit ground at a grid of points: C vs Warp, and the shadows are the clouds' (the sun's ray through the same
    density field, checked against an independent march 30x finer): ground under a cloud is darker than beside it."""
    s = small(sun_elevation_deg=50.0, sun_azimuth_deg=30.0)
    t = CloudscapeTechnique(s, textures=tech.textures)
    pts = _ground_points()
    sun = np.float32(s.sun())
    out = wp.zeros(len(pts), dtype=wp.vec3)
    sh = wp.zeros(len(pts), dtype=float)
    wp.launch(_ground_kernel, len(pts), inputs=[t.params, t.textures.warp(), wp.array(pts, dtype=wp.vec3),
                                                wp.vec3(*sun.tolist())], outputs=[out, sh])
    g_w, sh_w = out.numpy(), sh.numpy()
    p = _c_lit(s)
    tex_c = c_textures(t.textures)
    rgb, shp = ffi().new("float[3]"), ffi().new("float *")
    g_c, sh_c = np.empty_like(g_w), np.empty_like(sh_w)
    for k, q in enumerate(pts):
        lib().ccl_cloudscape_ground(p, tex_c, tuple(float(x) for x in q), tuple(float(x) for x in sun), rgb, shp)
        g_c[k] = rgb[0], rgb[1], rgb[2]
        sh_c[k] = shp[0]
    # the shadow bit for bit; the radiance to the ulp or two of ambient_ground (see test_light_c_equals_warp)
    np.testing.assert_array_equal(sh_w, sh_c)
    np.testing.assert_allclose(g_w, g_c, rtol=5e-7)
    # both kinds of ground in the sample: in a shadow and in the sun
    shadowed, lit = sh_w < 0.1, sh_w > 0.9
    assert shadowed.sum() >= 20 and lit.sum() >= 20
    lum = g_w @ np.array([0.2126, 0.7152, 0.0722])
    assert lum[shadowed].max() < lum[lit].min()
    # the shadows are the clouds': an independent fine march agrees on which points lie in shadow
    v = s.c_values()
    fine = np.array([_fine_shadow(v, tex_c, q.astype(np.float64), sun.astype(np.float64)) for q in pts[::3]])
    agree = (sh_w[::3] < 0.5) == (fine < 0.5)
    assert agree.mean() >= 0.9, agree.mean()


# --- pixels: C vs Warp ------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("sky,pose,extra", [
    ("preetham", BELOW, {}),
    ("gradient", BELOW, dict(sun_elevation_deg=4.0, ms_octaves=5, silver_weight=0.6)),
    ("preetham", ABOVE, dict(ms_octaves=2, silver_weight=0.0, aerial_height_km=0.0)),
    ("gradient", ABOVE, dict(ms_octaves=1, silver_weight=0.5, beer=False)),
    ("preetham", Pose(0.0, 2.5, 0.0, 60.0, 3.0, 60.0), dict(powder=False, aerial_km=8.0)),
    ("preetham", BELOW, dict(units="physical", phase="mie")),
    ("preetham", ABOVE, dict(units="physical", phase="mie", ms_octaves=3, droplet_um=30.0)),
])
def test_sky_lighting_pixels_match_c_reference(tech, sky, pose, extra):
    """Sky lighting, multiple-scattering octaves, the dual lobe, the lit ground and aerial perspective: Warp vs the C
    reference at 300 pixels (ground and sky, below, inside and above the layer). The same float32 operations in the
    same order: bit-identical here; the tolerance of test_cloudscape's comparison, 1e-5 absolute, allows a few ulp
    per operation on another platform."""
    s = small(sky=sky, **extra)
    t = CloudscapeTechnique(s, textures=tech.textures)
    rng = np.random.default_rng(11)
    xs, ys = rng.integers(0, s.width, 300), rng.integers(0, s.height, 300)
    w = render_pixels_warp(t, xs, ys, pose)
    c = render_pixels_c(s, t.textures, xs, ys, pose)
    assert np.all(np.isfinite(w)) and np.all(w >= 0)
    np.testing.assert_allclose(w, c, rtol=0, atol=1e-5)
    # the sample holds cloudy pixels (else the comparison would prove little)
    clear = render_pixels_warp(CloudscapeTechnique(small(sky=sky, coverage=0.0, **extra)), xs, ys, pose)
    assert np.mean(np.any(np.abs(w - clear) > 1e-3, axis=1)) > 0.1


def test_sky_lighting_whole_frame_warp_equals_c_render(tech):
    """ccl_cloudscape_render calls ccl_cloudscape_light itself; the technique's frame (sky pass + cloud pass, the
    ground and haze in the cloud pass) equals it."""
    s = small(width=48, height=27, **PLAIN)  # the C reference encodes by the plain clamp (no display transform)
    t = CloudscapeTechnique(s, textures=tech.textures)
    for pose in (BELOW, ABOVE):
        img = t.render(pose, reprojection=False)
        c_img = render_frame_c(s, t.textures, pose, frame=t.frame - 1)
        # 1 level of 8 bits: see test_cloudscape.test_whole_frame_warp_equals_c_render
        np.testing.assert_allclose(np.round(c_img * 255.0).astype(int), img.astype(int), atol=1)


# --- what the images show -----------------------------------------------------------------------------------------------

@wp.kernel
def _march_kernel(p: K.CloudscapeParams, tex: K.CloudTextures, sun: wp.vec3, inv_view_proj_rot: wp.mat44,
                  eye: wp.vec3, width: int, height: int,
                  # outputs
                  colour: wp.array2d(dtype=wp.vec3), opacity: wp.array2d(dtype=float)):
    y, x = wp.tid()
    d, offset = K.pixel_ray(p, inv_view_proj_rot, x, y, width, height, 0)
    cl, trans, taken, depth = K.cloudscape_march(p, tex, eye, d, sun, offset,
                                                 K.pixel_angle(inv_view_proj_rot, x, y, width, height))
    colour[y, x] = cl
    opacity[y, x] = 1.0 - trans


def _cloud_light(t: CloudscapeTechnique, pose: Pose):
    """(the clouds' own colour C / O_D, opacity O_D) per pixel: the light the clouds send, before compositing and
    aerial perspective."""
    s = t.settings
    cam = pose_camera(pose, s.width, s.height)
    col = wp.zeros((s.height, s.width), dtype=wp.vec3)
    op = wp.zeros((s.height, s.width), dtype=float)
    wp.launch(_march_kernel, (s.height, s.width),
              inputs=[t.params, t.textures.warp(), wp.vec3(*t.sky.sun.tolist()), cam.mat44("inv_view_proj_rot"),
                      cam.eye_vec3(), s.width, s.height], outputs=[col, op])
    o = op.numpy()
    return col.numpy() / np.maximum(o, 1e-6)[..., None], o


def test_sunset_clouds_are_warmer_than_noon(tech):
    """Preetham sky, sun 4 deg up against 60 deg: the light of the opaque clouds is redder (R/B up by more than 1.5x)
    -- the sun's path through 12 air masses and the sky's own colour; with the thesis's constants nothing changes but
    the phase angle."""
    ratios = {}
    for lighting in ("sky", "thesis"):
        for elevation in (60.0, 4.0):
            t = CloudscapeTechnique(small(lighting=lighting, sun_elevation_deg=elevation), textures=tech.textures)
            c, o = _cloud_light(t, BELOW)
            thick = o > 0.9
            assert thick.sum() > 100
            ratios[lighting, elevation] = c[thick, 0].mean() / c[thick, 2].mean()
    assert ratios["sky", 4.0] > 1.5 * ratios["sky", 60.0]
    assert ratios["sky", 4.0] > 1.0  # warm: more red than blue
    assert abs(ratios["thesis", 4.0] / ratios["thesis", 60.0] - 1.0) < 0.15


@pytest.mark.parametrize("sky", ["preetham", "gradient"])
def test_sunset_sunlight_on_the_clouds_is_warmer_than_noon(tech, sky):
    """The sun's part of the clouds' light (the render minus the same render with sun_intensity 0) reddens at sunset
    under either sky. (The gradient sky of vc-A28 does not change with the sun: its ambient stays blue, so there the
    clouds as a whole turn bluer at sunset as the sun dims -- a property of that sky model.)"""
    ratios = {}
    for elevation in (60.0, 4.0):
        lit, o = _cloud_light(CloudscapeTechnique(small(sky=sky, sun_elevation_deg=elevation),
                                                  textures=tech.textures), BELOW)
        amb, _ = _cloud_light(CloudscapeTechnique(small(sky=sky, sun_elevation_deg=elevation, sun_intensity=0.0),
                                                  textures=tech.textures), BELOW)
        sun = (lit - amb)[o > 0.9]
        ratios[elevation] = sun[:, 0].mean() / sun[:, 2].mean()
    assert ratios[4.0] > 10.0 * ratios[60.0]


def test_aerial_perspective_fades_distant_clouds_into_the_horizon_sky(tech):
    """With aerial perspective a cloud's colour moves towards the haze colour H (here the clear sky of the same
    pixel), the more the farther it is: |on - H| / |off - H| <= 1, and smaller for the clouds near the horizon
    (tens of km away) than for those high in the view (a few km)."""
    pose = Pose(0.0, 0.3, 0.0, 0.0, 10.0, 60.0)
    base = dict(sun_elevation_deg=35.0, aerial_height_km=0.0)
    on = render_pixels_grid(CloudscapeTechnique(small(aerial_km=30.0, **base), textures=tech.textures), pose)
    off = render_pixels_grid(CloudscapeTechnique(small(aerial_km=0.0, **base), textures=tech.textures), pose)
    haze = render_pixels_grid(CloudscapeTechnique(small(coverage=0.0, **base)), pose)
    sky_rows = np.arange(on.shape[0]) < on.shape[0] * 0.6  # above the horizon (pitch 10, fov 60: horizon at 0.67)
    d_off = np.linalg.norm(off - haze, axis=-1)
    d_on = np.linalg.norm(on - haze, axis=-1)
    cloudy = (d_off > 0.05) & sky_rows[:, None]
    r = d_on[cloudy] / d_off[cloudy]
    assert np.all(r <= 1.0 + 1e-5)
    rows = np.nonzero(cloudy)[0]
    near = r[rows < np.percentile(rows, 30)]  # high in the view: the nearest clouds
    far = r[rows > np.percentile(rows, 70)]   # towards the horizon
    assert len(near) > 20 and len(far) > 20
    assert np.median(far) < np.median(near) - 0.1


def render_pixels_grid(t: CloudscapeTechnique, pose: Pose) -> np.ndarray:
    """Display-linear frame (height, width, 3) of the technique at ``pose``."""
    return t.render(pose, reprojection=False, encode=False)


def test_multiple_scattering_brightens_thick_clouds_most(tech):
    """More octaves never darken a cloud, and they lift the dark (thick, self-shadowed) parts by a larger factor than
    the bright (thin, sunlit) ones: the octaves' halved extinction reaches deep inside."""
    light = {}
    for n in (1, 3):
        t = CloudscapeTechnique(small(ms_octaves=n, silver_weight=0.0), textures=tech.textures)
        c, o = _cloud_light(t, ABOVE)
        light[n] = c @ np.array([0.2126, 0.7152, 0.0722])
    thick = o > 0.9
    l1, l3 = light[1][thick], light[3][thick]
    assert np.all(l3 >= l1 - 1e-6)
    dark = l1 < np.percentile(l1, 20)
    bright = l1 > np.percentile(l1, 80)
    assert np.median(l3[dark] / l1[dark]) > np.median(l3[bright] / l1[bright])


def test_silver_lobe_brightens_clouds_towards_the_sun(tech):
    """The second, narrow forward lobe lights the clouds seen towards the sun and dims those seen away from it (the
    phase function's weight moves forward)."""
    s = dict(sun_elevation_deg=10.0, sun_azimuth_deg=0.0, ms_octaves=1)
    pose = Pose(0.0, 0.3, 0.0, 0.0, 12.0, 60.0)
    away = Pose(0.0, 0.3, 0.0, 180.0, 12.0, 60.0)
    lum = {}
    for w in (0.0, 0.5):
        t = CloudscapeTechnique(small(silver_weight=w, **s), textures=tech.textures)
        for name, p in (("towards", pose), ("away", away)):
            c, o = _cloud_light(t, p)
            lum[w, name] = (c[o > 0.5] @ np.array([0.2126, 0.7152, 0.0722])).mean()
    assert lum[0.5, "towards"] > 1.2 * lum[0.0, "towards"]
    assert lum[0.5, "away"] < lum[0.0, "away"]


# --- the thesis's lighting, bit for bit ---------------------------------------------------------------------------------

#: The thesis's renderer: its lighting, and every later change that alters pixels switched off (the level of detail,
#: the step refinement, the ray jitter's default, the de-tiled weather map, the half-float base texture, the
#: depth-aware reprojection and its history filter -- these two alter reprojected frames only; a future change of
#: that kind must add its switch here).
THESIS_RENDERER = {k: v for k, v in dict(lighting="thesis", powder=True, lod=False, refine_step_km=0.0, jitter="tilt",
                                         weather_detile=False, base_precision="single",
                                         reprojection_depth="inner_sphere",
                                         reprojection_filter="bilinear",
                                         advanced={"exit_eps": 1.0 / 256.0, "exit_fill": 0, "light_interp": 0.0},
                                         **PLAIN).items()
                   if k in {f.name for f in dataclasses.fields(CloudscapeSettings)}}
GOLDEN_XS = [8, 8, 51, 31, 37, 38, 45, 1, 31, 9, 25, 59, 35, 4, 34, 8]
GOLDEN_YS = [27, 34, 35, 22, 31, 13, 5, 18, 15, 23, 35, 9, 30, 4, 12, 28]
#: float32 bit patterns of the display-linear pixels (GOLDEN_XS[k], GOLDEN_YS[k]) of a 64x36 frame, and the SHA-256
#: of the whole frame (the Warp renderer's uint8 image; the C reference's float32 sRGB frame), computed by the code
#: of commit ec4f252 -- before the sky lighting existed -- in a scratch worktree of that commit with its own C library.
GOLDEN = {
    "below": (dict(sun_elevation_deg=35.0), Pose(0.0, 0.3, 0.0, 0.0, 20.0, 60.0), [
        1042075884, 1043547249, 1046495443, 1035489772, 1036831949, 1034147594, 1035489772, 1036831949, 1034147594,
        1048541920, 1051439918, 1055482694, 1035489772, 1036831949, 1034147594, 1041434224, 1048502004, 1054026392,
        1044516412, 1048944113, 1053082191, 1047556000, 1051186998, 1055534190, 1042190408, 1048968346, 1054357650,
        1049987135, 1050645633, 1051961733, 1035489772, 1036831949, 1034147594, 1043060000, 1049258576, 1054856570,
        1035489772, 1036831949, 1034147594, 1040249924, 1047225764, 1053397256, 1047436904, 1050135664, 1053601790,
        1042250468, 1043813780, 1046941486],
        "307ccb9258deddda14473438fe1ec4499132dceb52011936c17790af86613cec",
        "9ba6be6be9a62ea9ef591a0425df2ff74a97ad6fe7c2564e734df22efa5a8253"),
    "sunset": (dict(sun_elevation_deg=4.0, sun_azimuth_deg=10.0, sky="gradient"),
               Pose(0.0, 0.3, 0.0, 0.0, 12.0, 60.0), [
        1035489772, 1036831949, 1034147594, 1035489772, 1036831949, 1034147594, 1035489772, 1036831949, 1034147594,
        1046242012, 1047466104, 1049243191, 1035489772, 1036831949, 1034147594, 1058200939, 1060415644, 1064069246,
        1053658127, 1057845162, 1062438278, 1056918670, 1057917328, 1059450266, 1058399206, 1060585285, 1064093654,
        1048717106, 1049484451, 1051014197, 1035489772, 1036831949, 1034147594, 1056501242, 1059096115, 1063063530,
        1035489772, 1036831949, 1034147594, 1054793780, 1058344832, 1062687885, 1057068260, 1059402200, 1063353946,
        1035489772, 1036831949, 1034147594],
        "510c368682cfbb5c0674c068e4a5f723c0b6fcd0accd75570bc19b14c69181ec",
        "2f966b473407f3e5fc3a8ce15c3ecca7778c5cfd40e8e8932e949742ba0eee6b"),
    "above": (dict(sun_elevation_deg=35.0, g=0.4), Pose(0.0, 8.0, 0.0, 30.0, -30.0, 60.0), [
        1050236406, 1051241825, 1053248348, 1048196120, 1049238192, 1050939326, 1035489772, 1036831949, 1034147594,
        1035489772, 1036831949, 1034147594, 1035489772, 1036831949, 1034147594, 1049107509, 1049965101, 1051676691,
        1036065207, 1037509993, 1035262889, 1051446325, 1052526199, 1054682307, 1050709143, 1051617197, 1053428934,
        1051010644, 1052083492, 1054225547, 1035489772, 1036831949, 1034147594, 1047178646, 1048695707, 1050330648,
        1035489772, 1036831949, 1034147594, 1050806714, 1051673043, 1053405439, 1049142421, 1050003071, 1051720839,
        1049794588, 1050779611, 1052744809],
        "6a44cb3bb6de4a8100e341c8758807bda563d5b87a21b5eeda654c368eee3483",
        "cf1ea888678ddc83fff5c9639918c5966697fe0afbbcb9b30d92be4d3eee670f"),
}


@pytest.mark.parametrize("scene", list(GOLDEN))
def test_thesis_lighting_reproduces_the_images_before_sky_lighting(scene):
    """lighting='thesis' (one octave, one HG lobe, the constants, the flat ground, no haze) gives today's renderer
    exactly the images of the code before the sky lighting, Warp and C: pixel bits and whole-frame hashes."""
    import hashlib

    kw, pose, bits, sha_warp, sha_c = GOLDEN[scene]
    s = CloudscapeSettings(width=64, height=36, **SMALL, **kw, **THESIS_RENDERER)
    t = CloudscapeTechnique(s)
    expected = np.array(bits, dtype=np.uint32).view(np.float32).reshape(-1, 3)
    np.testing.assert_array_equal(render_pixels_warp(t, GOLDEN_XS, GOLDEN_YS, pose), expected)
    np.testing.assert_array_equal(render_pixels_c(s, t.textures, GOLDEN_XS, GOLDEN_YS, pose), expected)
    img = t.render(pose, reprojection=False)
    assert hashlib.sha256(img.tobytes()).hexdigest() == sha_warp
    c_img = render_frame_c(s, t.textures, pose, frame=0)
    assert hashlib.sha256(c_img.tobytes()).hexdigest() == sha_c


# --- settings -------------------------------------------------------------------------------------------------------------

def test_lighting_defaults_equal_ccl_cloudscape_params_default():
    p = ffi().new("ccl_cloudscape_params *")
    lib().ccl_cloudscape_params_default(p)
    s = CloudscapeSettings()
    f32 = lambda x: float(np.float32(x))  # noqa: E731
    assert CS.LIGHTING_NAMES.index(s.lighting) == p.lighting == lib().CCL_LIGHTING_SKY
    assert CS.LIGHTING_NAMES.index("thesis") == lib().CCL_LIGHTING_THESIS
    assert (f32(s.sun_intensity), f32(s.aerial_km), f32(s.aerial_height_km)) == (
        p.sun_intensity, p.aerial_km, p.aerial_height_km)
    assert tuple(f32(x) for x in s.ground_albedo) == tuple(p.ground_albedo)
    assert (s.ms_octaves, f32(s.silver_g), f32(s.silver_weight)) == (p.ms_octaves, p.silver_g, p.silver_weight)
    assert f32(s.turbidity) == p.turbidity
    assert CS.MAX_MS_OCTAVES == K.MAX_MS_OCTAVES == lib().CCL_CLOUDSCAPE_MAX_MS_OCTAVES
    assert (int(K.GROUND_SHADOW_SAMPLES), int(K.SKY_THETA_CELLS), int(K.SKY_PHI_CELLS)) == (
        lib().CCL_CLOUDSCAPE_GROUND_SHADOW_SAMPLES, lib().CCL_CLOUDSCAPE_SKY_THETA_CELLS,
        lib().CCL_CLOUDSCAPE_SKY_PHI_CELLS)
    assert tuple(S.SUN_LAMBDA_UM) == (0.680, 0.550, 0.440)
    # lighting='thesis' maps to the thesis's single octave and lobe
    v = CloudscapeSettings(lighting="thesis").c_values()
    assert (v["lighting"], v["ms_octaves"], v["silver_weight"]) == (0, 1, 0.0)


@pytest.mark.parametrize("field,value,err,match", [
    ("lighting", "physical", ValueError, "lighting must be one of"),
    ("sun_intensity", -1.0, ValueError, "sun_intensity"),
    ("ground_albedo", (0.1, 1.2, 0.1), ValueError, "ground_albedo must hold 3 numbers in"),
    ("ground_albedo", (0.1, 0.1), ValueError, "ground_albedo must hold 3"),
    ("aerial_km", float("nan"), ValueError, "aerial_km"),
    ("aerial_height_km", -2.0, ValueError, "aerial_height_km"),
    ("ms_octaves", 0, ValueError, "ms_octaves"),
    ("ms_octaves", 9, ValueError, "ms_octaves"),
    ("ms_octaves", 2.5, TypeError, "ms_octaves"),
    ("silver_g", 1.0, ValueError, "silver_g"),
    ("silver_weight", 1.5, ValueError, "silver_weight"),
    ("phase", "hg", ValueError, "phase must be one of"),
    ("droplet_um", 4.0, ValueError, "droplet_um"),
    ("droplet_um", 60.0, ValueError, "droplet_um"),
    ("units", "si", ValueError, "units must be one of"),
    ("ambient_ground_weight", 1.5, ValueError, "ambient_ground_weight"),
])
def test_lighting_settings_refuse_bad_values(field, value, err, match):
    with pytest.raises(err, match=match):
        CloudscapeSettings(**{field: value})


@pytest.mark.parametrize("changes", [dict(sky="gradient"), dict(lighting="thesis")])
def test_physical_units_need_the_preetham_sky_and_sky_lighting(changes):
    with pytest.raises(ValueError, match="units='physical' needs sky='preetham' and lighting='sky'"):
        CloudscapeSettings(units="physical", **changes)


@pytest.mark.parametrize("name,value", [("ms_a", 1.5), ("ms_b", -0.1), ("ms_c", 2.0), ("ambient_bottom_ratio", 3.0),
                                        ("ambient_ground", (0.1, -0.2, 0.1))])
def test_advanced_lighting_parameters_checked_by_c(name, value):
    with pytest.raises(ValueError, match=name):
        CloudscapeSettings(advanced={name: value})
