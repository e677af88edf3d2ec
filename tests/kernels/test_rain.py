"""One raindrop: the Beard-Chuang shape (rr-eq1, rr-tab-2.1) against the catalogue's values and a float64 evaluation
of the table typed here, volume and axis ratio, terminal speeds (rr-tab-2.2) against the 23 rows, refraction masks
(rr-alg-3.1.1) against the analytic sphere and the exact shape's sphere limit, the drop pixel colour (rr-alg-3.1,
rr-alg-3.1.3), the capture parallax (rr-alg-3.2.2) and the light-drop model (rr-A1, rr-A2, rr-A3, rr-CF)."""
from __future__ import annotations

import numpy as np
import pytest

import pywarp
from helpers import assert_twins_agree
from pywarp.kernels import rain
from pywarp.rain import drops

N_W = 1.33
# Table 2.1 of the text (c_n x 1e4), typed here independently of the code
TABLE = {0.5: [-28, -30, -83, -22, -3, 2, 1, 0, 0, 0, 0],
         1.0: [-134, -118, -385, -100, -5, 17, 6, -1, -3, -1, 1],
         3.0: [-843, -472, -2040, -240, 299, 168, -21, -73, -20, 25, 24],
         4.5: [-1328, -403, -2889, -106, 662, 153, -146, -111, 18, 81, 31]}
# the catalogue's check values (mm): r(0), r(pi/2), r(pi)
CHECK = {0.5: (0.491850, 0.502550, 0.496850), 1.0: (0.927700, 1.023600, 0.968300),
         3.0: (2.042100, 3.441900, 2.397300), 4.5: (2.682900, 5.560200, 3.030300)}


def r64(theta, a, coefs=None):
    c = np.asarray(TABLE[a] if coefs is None else coefs, np.float64) * 1e-4
    theta = np.asarray(theta, np.float64)
    return a * (1 + sum(c[n] * np.cos(n * theta) for n in range(11)))


# --- shape -----------------------------------------------------------------------------------------------------------

@pytest.mark.spec("rr-eq1", "rr-tab-2.1")
@pytest.mark.parametrize("a", [0.5, 1.0, 3.0, 4.5])
def test_rain_drop_radius_catalogue_values(a):
    r = pywarp.rain_drop_radius(np.array([0.0, np.pi / 2, np.float32(np.pi)]), a)
    np.testing.assert_allclose(r, CHECK[a], atol=4e-6 * a)
    assert r[0] < r[2]  # the bottom (theta = 0) is flatter
    th = np.linspace(0.0, np.float32(np.pi), 181)
    np.testing.assert_allclose(pywarp.rain_drop_radius(th, a), r64(th.astype(np.float32), a), rtol=2e-6)
    assert_twins_agree("rr-eq1", th, a)
    np.testing.assert_array_equal(pywarp.rain_drop_coefficient(np.arange(11), a),
                                  (np.asarray(TABLE[a], np.float32) * np.float32(1e-4)).astype(np.float32))


@pytest.mark.spec("rr-eq1", "rr-tab-2.1")
def test_rain_drop_radius_interpolation_is_an_explicit_option():
    with pytest.raises(ValueError, match=r"\ba\b.*interp='linear'"):
        pywarp.rain_drop_radius(0.0, 2.0)
    with pytest.raises(ValueError, match=r"\ba\b"):
        pywarp.rain_drop_coefficient(2, 1.5)
    # the linear option reproduces the rows exactly and interpolates each C_n linearly in a between them
    for a in TABLE:
        np.testing.assert_array_equal(pywarp.rain_drop_coefficient(np.arange(11), a, interp="linear"),
                                      pywarp.rain_drop_coefficient(np.arange(11), a))
    c2 = pywarp.rain_drop_coefficient(np.arange(11), 2.0, interp="linear")
    np.testing.assert_allclose(c2, 0.5 * (np.array(TABLE[1.0]) + TABLE[3.0]) * 1e-4, atol=1e-8)
    th = np.linspace(0, 3.14, 50)
    np.testing.assert_allclose(pywarp.rain_drop_radius(th, 2.0, interp="linear"),
                               r64(th, 2.0, 0.5 * (np.array(TABLE[1.0]) + TABLE[3.0])), rtol=2e-6)
    with pytest.raises(ValueError, match=r"\ba\b"):
        pywarp.rain_drop_radius(0.0, 0.4, interp="linear")  # below the table


@pytest.mark.spec("rr-eq1")
def test_rain_drop_surface_points_and_normals():
    th, ph = np.meshgrid(np.linspace(0.01, 3.13, 40), np.linspace(0, 2 * np.pi, 24))
    for a in TABLE:
        P, N = drops.drop_surface(th, ph, a)
        np.testing.assert_allclose(np.linalg.norm(P, axis=-1), r64(th, a), rtol=3e-6)
        np.testing.assert_allclose(P[..., 1], -r64(th, a) * np.cos(th), atol=5e-6 * a)  # theta = 0 points down
        np.testing.assert_allclose(np.linalg.norm(N, axis=-1), 1.0, atol=3e-7)
        # the normal is perpendicular to both tangents (float64 finite differences of the independent formula)
        h = 1e-5

        def point(t, p):
            r = r64(t, a)
            return np.stack([r * np.sin(t) * np.cos(p), -r * np.cos(t), r * np.sin(t) * np.sin(p)], -1)
        t_th = (point(th + h, ph) - point(th - h, ph)) / (2 * h)
        t_ph = (point(th, ph + h) - point(th, ph - h)) / (2 * h)
        for t in (t_th, t_ph):
            cos = np.sum(N * t, -1) / np.maximum(np.linalg.norm(t, axis=-1), 1e-12)
            assert np.abs(cos).max() < 2e-5
        assert np.all(np.sum(N * P, -1) > 0)  # outward
        Pc, Nc = drops.drop_surface(th[:3], ph[:3], a, impl="c")
        np.testing.assert_allclose(Pc, P[:3], rtol=0, atol=4e-7 * a)
        np.testing.assert_allclose(Nc, N[:3], atol=4e-7)


@pytest.mark.spec("rr-eq1")
def test_rain_drop_volume_and_axis_ratio_against_float64():
    th = np.linspace(0, np.pi, 200001)
    for a in TABLE:
        r = r64(th, a)
        vol = 2 * np.pi / 3 * np.trapezoid(r ** 3 * np.sin(th), th)
        ratio = (r[0] + r[-1]) / (2 * np.max(r * np.sin(th)))
        assert drops.drop_volume(a) == pytest.approx(vol, rel=2e-6)
        assert drops.drop_volume(a) == pytest.approx(4 / 3 * np.pi * a ** 3, rel=2e-3)  # a: equal-volume radius
        assert drops.drop_axis_ratio(a) == pytest.approx(ratio, rel=3e-6)
        assert drops.drop_volume(a, impl="c") == pytest.approx(drops.drop_volume(a), rel=2e-6)
        assert drops.drop_axis_ratio(a, impl="c") == pytest.approx(drops.drop_axis_ratio(a), rel=1e-6)
        # the extent bounds the drop and is tight to the sampling bound
        ext = drops.drop_extent(a)
        assert r.max() <= ext <= r.max() * 1.0013
        assert drops.drop_extent(a, impl="c") == pytest.approx(ext, rel=1e-6)
    ratios = drops.drop_axis_ratio(np.array([0.5, 1.0, 3.0, 4.5]))
    np.testing.assert_allclose(ratios, [0.9837, 0.9259, 0.6409, 0.5113], atol=1e-4)
    assert np.all(np.diff(ratios) < 0)  # bigger drops are flatter


# --- terminal speed --------------------------------------------------------------------------------------------------

SPEEDS = [(0.1, 0.72), (0.15, 1.17), (0.2, 1.62), (0.25, 2.06), (0.3, 2.47), (0.35, 2.87), (0.4, 3.27), (0.45, 3.67),
          (0.5, 4.0), (0.75, 5.43), (1.0, 6.59), (1.25, 7.46), (1.5, 8.1), (1.75, 8.58), (2.0, 8.91), (2.25, 9.11),
          (2.5, 9.2), (2.75, 9.23), (3.0, 9.23), (3.25, 9.23), (3.5, 9.23), (3.75, 9.23), (4.0, 9.23)]


@pytest.mark.spec("rr-tab-2.2")
def test_rain_terminal_speed_table_rows_interpolation_plateau():
    r, v = np.array(SPEEDS).T
    assert len(SPEEDS) == 23
    np.testing.assert_allclose(pywarp.rain_terminal_speed(r), v, rtol=1e-6)
    mid = 0.5 * (r[:-1] + r[1:])
    np.testing.assert_allclose(pywarp.rain_terminal_speed(mid), 0.5 * (v[:-1] + v[1:]), rtol=2e-6)
    np.testing.assert_array_equal(pywarp.rain_terminal_speed([4.0, 5.0, 10.0]), np.float32(9.23))  # plateau
    np.testing.assert_allclose(pywarp.rain_terminal_speed([0.0, 0.05]), [0.0, 0.72 / 4], rtol=1e-6)  # Stokes r^2
    x = np.linspace(0, 10, 5001)
    assert np.all(np.diff(pywarp.rain_terminal_speed(x)) >= 0)
    # the application's slow-down by 4 is a parameter
    np.testing.assert_allclose(pywarp.rain_terminal_speed(r, rain.APP_SLOWDOWN), v / 4, rtol=1e-6)
    assert_twins_agree("rr-tab-2.2", x, 4.0)
    with pytest.raises(ValueError, match=r"\bradius_mm\b"):
        pywarp.rain_terminal_speed(-0.1)
    with pytest.raises(ValueError, match=r"\bslowdown\b"):
        pywarp.rain_terminal_speed(1.0, 0.0)


# --- masks -----------------------------------------------------------------------------------------------------------

def sphere_exit64(u, v, n=N_W):
    """Analytic refraction through a sphere: deviation D = 2 (theta_i - theta_t) towards the axis."""
    b = np.clip(np.hypot(u, v), 0.0, 1.0)
    dev = 2 * (np.arcsin(b) - np.arcsin(b / n))
    with np.errstate(invalid="ignore", divide="ignore"):
        ux, uy = np.where(b > 0, u / b, 0.0), np.where(b > 0, v / b, 0.0)
    return np.stack([-np.sin(dev) * ux, -np.sin(dev) * uy, np.cos(dev)], -1)


@pytest.mark.spec("rr-alg-3.1.1")
def test_rain_mask_sphere_against_analytic_refraction():
    size = 128
    m = drops.drop_mask(size)
    assert m.shape == (size, size, 4) and m.dtype == np.float32
    j, i = np.meshgrid(np.arange(size), np.arange(size))
    u, v = 2 * (j + 0.5) / size - 1, 1 - 2 * (i + 0.5) / size
    inside = u ** 2 + v ** 2 <= 1
    np.testing.assert_array_equal(m[..., 3] > 0, inside)
    ref = sphere_exit64(u, v)
    err = np.abs(m[..., :3] - ref)[inside]
    # error of the float32 trace: ~1e-6 in the bulk; the last texels of the rim (b -> 1) amplify the float32
    # rounding of sqrt(1 - b^2) (d dev / d b ~ 1 / sqrt(1 - b^2))
    b = np.hypot(u, v)[inside]
    assert err[b < 0.99].max() < 3e-6
    assert err.max() < 2e-4
    np.testing.assert_array_equal(m[~inside], 0.0)
    assert np.all(m[inside][:, 2] > 0)  # a sphere never reflects totally: every ray goes on into the scene
    # the deviation grows towards the rim, where it reaches the exact drop-FOV half angle 82.49 deg (not the
    # printed 75): dev(b) = 82.49 - O(sqrt(1 - b)), so the outermost texel of a 128 mask is still at 79 deg
    dev = np.degrees(np.arccos(m[inside][:, 2]))
    assert dev.max() == pytest.approx(np.degrees(np.arccos(sphere_exit64(b.max(), 0.0)[2])), abs=0.01)
    rim = pywarp.rain_mask_texel(1.0, 0.0, 1.0, 1.0, N_W)[0]
    assert np.degrees(np.arccos(rim[2])) == pytest.approx(180 - 2 * np.degrees(np.arcsin(1 / N_W)), abs=0.01)


@pytest.mark.spec("rr-alg-3.1.1")
def test_rain_mask_exact_shape_reduces_to_sphere_as_coefficients_vanish(rng):
    u, v = rng.uniform(-1, 1, (2, 400)).astype(np.float32)
    keep = u ** 2 + v ** 2 < 0.98
    u, v = u[keep], v[keep]
    e_s, n_s, in_s = pywarp.rain_mask_texel(u, v, 3.0, 0.0, N_W, method="sphere")
    prev = 0.0
    for deform in (0.0, 1e-3, 1e-2, 1e-1):
        e_x, n_x, in_x = pywarp.rain_mask_texel(u, v, 3.0, deform, N_W, method="exact")
        diff = np.abs(e_x - e_s).max()
        if deform == 0.0:
            np.testing.assert_array_equal(in_x, in_s)
            assert diff < 5e-5  # march + 32 bisections vs the analytic sphere, float32
            np.testing.assert_allclose(n_x, n_s, atol=5e-5)
        else:
            assert diff > prev  # the difference grows with the deformation
        prev = diff
    e_o, _, in_o = pywarp.rain_mask_texel(u, v, 3.0, 0.0, N_W, method="outline")
    np.testing.assert_allclose(e_o, e_s, atol=1e-6)


@pytest.mark.spec("rr-alg-3.1.1")
def test_rain_mask_outline_and_exact_share_the_silhouette_and_differ_inside():
    size = 96
    for a in (1.0, 3.0, 4.5):
        ex = drops.drop_mask(size, a, method="exact")
        ol = drops.drop_mask(size, a, method="outline")
        np.testing.assert_array_equal(ex[..., 3], ol[..., 3])
        # the silhouette is the meridian profile r(theta) (a body of revolution seen from the side)
        j, i = np.meshgrid(np.arange(size), np.arange(size))
        L = drops.drop_extent(a)
        x, y = (2 * (j + 0.5) / size - 1) * L, (1 - 2 * (i + 0.5) / size) * L
        rho, theta = np.hypot(x, y), np.arctan2(np.abs(x), -y)
        sure = np.abs(rho - r64(theta, a)) > 1e-3 * a
        np.testing.assert_array_equal((ex[..., 3] > 0)[sure], (rho <= r64(theta, a))[sure])
        inside = ex[..., 3] > 0
        diff = np.degrees(np.arccos(np.clip(np.sum(ex[..., :3] * ol[..., :3], -1), -1, 1)))[inside]
        if a == 1.0:
            assert np.median(diff) < 3.0
        else:
            assert np.median(diff) > 3.0  # flattened drops refract visibly differently from the text's sphere
    # the two implementations compute the same mask
    for method in ("sphere", "outline", "exact"):
        w = drops.drop_mask(48, 3.0, method=method)
        c = drops.drop_mask(48, 3.0, method=method, impl="c")
        np.testing.assert_allclose(w, c, atol=2e-5)
    assert_twins_agree("rr-alg-3.1.1", np.linspace(-0.9, 0.9, 19)[:, None], np.linspace(-0.9, 0.9, 19), 4.5,
                       method="exact")


@pytest.mark.spec("rr-alg-3.1.1")
def test_rain_drop_mask_is_cached_read_only_and_validated():
    a = drops.drop_mask(32, 1.0, method="outline")
    assert drops.drop_mask(32, 1.0, method="outline") is a
    assert not a.flags.writeable
    m, n = drops.drop_mask(32, 1.0, method="outline", normals=True)
    assert m is a and n.shape == (32, 32, 3)
    with pytest.raises(ValueError, match=r"\bmethod\b"):
        drops.drop_mask(32, method="cone")
    with pytest.raises(ValueError, match=r"\ba\b"):
        drops.drop_mask(32, 2.0, method="exact")
    with pytest.raises(ValueError, match=r"\bsize\b"):
        drops.drop_mask(0)


# --- drop pixel colour -------------------------------------------------------------------------------------------------

@pytest.mark.spec("rr-alg-3.1.3")
def test_rain_refracted_uv_offset_and_projection():
    tan_h = np.tan(np.radians(rain.CAPTURE_FOV_DEG / 2))
    e = np.array([[0.1, -0.2, 0.9746794], [0.0, 0.0, 1.0]])
    pc, po, valid = pywarp.rain_refracted_uv([0.0, 0.0, -1.0], e, tan_h, 1.0)
    np.testing.assert_array_equal(valid, 1)
    np.testing.assert_allclose(po, 0.5)
    np.testing.assert_allclose(pc[0], [0.5 + 0.5 / tan_h * 0.1 / 0.9746794, 0.5 + 0.5 / tan_h * 0.2 / 0.9746794],
                               rtol=1e-6)
    pc2, _, _ = pywarp.rain_refracted_uv([0.0, 0.0, -1.0], e, tan_h, 1.0, mapping="project")
    np.testing.assert_allclose(pc2, pc, atol=1e-7)  # the two mappings agree at the centre of the view
    # off-centre: the projection is exact; P_o is the perspective projection of the view direction
    c = np.array([0.3, 0.2, -1.0]) / np.linalg.norm([0.3, 0.2, -1.0])
    pc3, po3, _ = pywarp.rain_refracted_uv(c, [0.0, 0.0, 1.0], tan_h, 16 / 9, mapping="project")
    np.testing.assert_allclose(po3, [0.5 + 0.5 * 0.3 / (tan_h * 16 / 9), 0.5 - 0.5 * 0.2 / tan_h], rtol=1e-6)
    np.testing.assert_allclose(pc3, po3, atol=1e-7)  # an undeviated ray lands on P_o
    # rays that do not go on into the scene (the shader's refract.z > 0 test) are invalid
    assert pywarp.rain_refracted_uv([0.0, 0.0, -1.0], [0.0, 0.0, 0.0], tan_h, 1.0)[2] == 0
    assert_twins_agree("rr-alg-3.1.3", c, e, tan_h, 1.5, mapping="project")


def _capture(h=96, w=96):
    img = np.zeros((h, w, 3), np.float32)
    img[: h // 2] = (1.0, 0.2, 0.1)  # top half red
    img[h // 2:] = (0.1, 0.2, 1.0)  # bottom half blue
    return img


@pytest.mark.spec("rr-alg-3.1", "rr-alg-3.1.3")
def test_rain_shade_drop_uniform_background_and_inverted_image():
    mask = drops.drop_mask(64)
    uni = np.full((32, 48, 3), 0.25, np.float32)
    out = pywarp.rain_shade_drop(uni, mask, [0.0, 0.0, -1.0], out_size=32)
    inside = out[..., 3] > 0
    np.testing.assert_array_equal(out[inside][:, :3], 0.25)  # a drop over a uniform scene shows that colour
    np.testing.assert_array_equal(out[~inside], 0.0)
    # a drop is a lens: its top shows the lower part of the scene (the image is inverted, Obrazek 2.4)
    for flt in ("nearest", "linear"):
        out = pywarp.rain_shade_drop(_capture(), mask, [0.0, 0.0, -1.0], out_size=32, filter=flt)
        top, bottom = out[4, 16], out[27, 16]
        assert top[3] == 1 and bottom[3] == 1
        assert top[2] > top[0] and bottom[0] > bottom[2]
        c = pywarp.equation("rr-alg-3.1", impl="c")(_capture(), mask, [0.0, 0.0, -1.0], out_size=32, filter=flt)
        np.testing.assert_allclose(c, out, atol=1e-6)
    with pytest.raises(ValueError, match=r"\bcentre_dir\b"):
        pywarp.rain_shade_drop(uni, mask, [0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match=r"\bmask\b"):
        pywarp.rain_shade_drop(uni, mask[..., :3], [0.0, 0.0, -1.0])


# --- accepted approximations ------------------------------------------------------------------------------------------

@pytest.mark.spec("rr-alg-3.2.2")
def test_rain_capture_parallax_small_for_far_backgrounds():
    e = np.array([0.0, 0.0, -1.0])
    assert pywarp.rain_capture_parallax([0.0, 0.0, 0.0], e, 100.0) == 0.0  # a drop at the eye sees the capture
    assert pywarp.rain_capture_parallax([0.0, 0.0, -3.0], e, 100.0) == pytest.approx(0.0, abs=1e-7)
    p = np.array([1.0, 0.0, -2.0])
    for R in (50.0, 500.0, 5000.0):
        got = pywarp.rain_capture_parallax(p, e, R)
        s = -p @ e + np.sqrt((p @ e) ** 2 - p @ p + R * R)
        q = p + s * e
        assert got == pytest.approx(np.arccos(q @ e / R), rel=1e-3)
        assert got == pytest.approx(1.0 / R, rel=0.05)  # |p| sin(p, e) / R
    assert np.isnan(pywarp.rain_capture_parallax([0.0, 0.0, 20.0], e, 10.0))


# --- light-drop model ------------------------------------------------------------------------------------------------

@pytest.mark.spec("rr-A1", "rr-A2", "rr-A3")
def test_rain_light_terms_closed_forms_and_guards():
    n = np.array([0.0, 0.0, 1.0])
    # A2: cosine of the angle to the light, clamped
    ang = np.radians([0, 30, 60, 90, 120])
    vpl = np.stack([np.sin(ang), np.zeros(5), np.cos(ang)], -1)
    np.testing.assert_allclose(pywarp.rain_light_a2(vpl, n), np.maximum(np.cos(ang), 0), atol=1e-7)
    # A1: C_L / (1 + (d / r_half)^2) cos; corrected clamps, the thesis variant (as printed) does not
    a1 = pywarp.rain_light_a1([1.0, 0.5, 0.25], 2.0, [0.0, 0.0, 1.0], n, 2.0)
    np.testing.assert_allclose(a1, [0.5, 0.25, 0.125], rtol=1e-6)
    back = [0.0, 0.0, -1.0]
    np.testing.assert_array_equal(pywarp.rain_light_a1([1.0, 1.0, 1.0], 0.0, back, n, 1.0), 0.0)
    np.testing.assert_allclose(pywarp.rain_light_a1([1.0, 1.0, 1.0], 0.0, back, n, 1.0, variant="thesis"), -1.0)
    # A3: (-V_PL2D . V_N2D)(1 + V_PL . V_N), clamped; vertical vectors (no horizontal plane) give 0
    l, m = np.array([-0.5, np.sqrt(3) / 2, 0.0]), np.array([np.sqrt(3) / 2, 0.5, 0.0])
    assert pywarp.rain_light_a3(l, m) == pytest.approx(1.0, abs=1e-6)
    assert pywarp.rain_light_a3([0.0, 1.0, 0.0], m) == 0.0
    assert pywarp.rain_light_a3(l, [0.0, -1.0, 0.0]) == 0.0
    assert pywarp.rain_light_a3([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]) == 0.0  # straight through: no up/down exit
    assert pywarp.rain_light_a3([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]) == 0.0  # light in front: sideways, suppressed
    t = np.linspace(0, np.pi, 50)
    rnd = np.stack([np.cos(t), np.sin(3 * t), np.sin(t)], -1)
    rnd /= np.linalg.norm(rnd, axis=1, keepdims=True)
    vals = pywarp.rain_light_a3(rnd, rnd[::-1])
    assert vals.min() >= 0 and vals.max() < 2
    assert_twins_agree("rr-A3", rnd, rnd[::-1])
    assert_twins_agree("rr-A1", [1.0, 0.5, 0.2], np.linspace(0, 5, 50), rnd, rnd[::-1], 1.5, variant="thesis")


@pytest.mark.spec("rr-CF", "rr-A1", "rr-A2", "rr-A3")
def test_rain_light_colour_composes_the_terms():
    c_o, amb = np.array([0.4, 0.5, 0.6]), np.array([0.8, 0.7, 0.5])
    p, n, eye = np.zeros(3), np.array([0.0, 0.0, 1.0]), np.array([0.0, 0.0, 5.0])
    off = np.zeros(3)
    np.testing.assert_allclose(pywarp.rain_light_colour(c_o, amb, p, n, eye, [1, 1, 1], off, [2, 2, 2], off, 1.0),
                               c_o * amb, rtol=1e-7)
    # one light: C_O C_amb + A1 (A2 + A3), composed here in float64 from the formulas
    l1, cl = np.array([1.0, 2.0, 2.0]), np.array([1.0, 0.9, 0.8])
    d = l1 - p
    dist = np.linalg.norm(d)
    vpl, vpe = d / dist, (eye - p) / np.linalg.norm(eye - p)
    a1 = cl / (1 + (dist / 1.5) ** 2) * max(vpe @ n, 0)
    a2 = max(vpl @ n, 0)
    h = -(vpl[[0, 2]] / np.linalg.norm(vpl[[0, 2]])) @ (n[[0, 2]] / max(np.linalg.norm(n[[0, 2]]), 1))
    a3 = 0.0  # n is horizontal-less in x/z? n = +z has a horizontal part: recompute below
    nh = n[[0, 2]] / np.linalg.norm(n[[0, 2]])
    h = -(vpl[[0, 2]] / np.linalg.norm(vpl[[0, 2]])) @ nh
    a3 = max(0.0, h * (1 + vpl @ n))
    want = c_o * amb + a1 * (a2 + a3)
    got = pywarp.rain_light_colour(c_o, amb, p, n, eye, l1, cl, [0, 0, 0], off, 1.5)
    np.testing.assert_allclose(got, want, rtol=2e-6)
    # the two lights add
    both = pywarp.rain_light_colour(c_o, amb, p, n, eye, l1, cl, l1, cl, 1.5)
    np.testing.assert_allclose(both, c_o * amb + 2 * a1 * (a2 + a3), rtol=2e-6)
    assert_twins_agree("rr-CF", c_o, amb, p, n, eye, l1, cl, [-1.0, 3.0, 1.0], [0.2, 0.3, 1.0], 1.5)
