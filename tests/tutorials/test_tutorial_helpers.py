"""pywarp.tutorial: the camera rays and the stand-in scene the tutorials share, checked against closed forms."""
from __future__ import annotations

import numpy as np
import pytest

from pywarp.tutorial import billboard_frame, environment, fisheye_directions, pinhole_directions, row_of_elevation


def test_pinhole_directions_centre_edges_and_turns():
    # 90 deg FOVy, 3 x 3: the pixel centres sit at u, v in {-2/3, 0, 2/3} (tan 45 deg = 1)
    d = pinhole_directions(3, 3, 90.0)
    assert d.shape == (3, 3, 3)
    np.testing.assert_allclose(np.linalg.norm(d, axis=-1), 1.0, rtol=1e-15)
    np.testing.assert_allclose(d[1, 1], [0.0, 0.0, -1.0], atol=1e-15)  # looks down -Z
    np.testing.assert_allclose(d[0, 1], np.array([0.0, 2 / 3, -1.0]) / np.sqrt(1 + 4 / 9), atol=1e-15)  # row 0: up
    np.testing.assert_allclose(d[1, 2], np.array([2 / 3, 0.0, -1.0]) / np.sqrt(1 + 4 / 9), atol=1e-15)  # right: +X
    # the aspect widens u only: 5 x 3 reaches u = 4/5 * 5/3 = 4/3 at the last column
    np.testing.assert_allclose(pinhole_directions(5, 3, 90.0)[1, 4], np.array([4 / 3, 0.0, -1.0]) / (5 / 3),
                               atol=1e-15)
    # azimuth 90 deg looks along +X, pitch 30 deg lifts the centre ray to elevation 30 deg; no roll: the centre row
    # of a level camera stays on the horizon
    np.testing.assert_allclose(pinhole_directions(3, 3, 60.0, azimuth_deg=90.0)[1, 1], [1.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(pinhole_directions(3, 3, 60.0, 0.0, 30.0)[1, 1], [0.0, 0.5, -np.sqrt(3) / 2],
                               atol=1e-15)
    np.testing.assert_allclose(pinhole_directions(7, 3, 60.0, azimuth_deg=40.0)[1, :, 1], 0.0, atol=1e-15)


def test_fisheye_directions_zenith_rim_and_mirrored_azimuth():
    d, inside = fisheye_directions(5)
    assert d.shape == (5, 5, 3) and inside.shape == (5, 5)
    np.testing.assert_allclose(np.linalg.norm(d, axis=-1), 1.0, rtol=1e-15)
    np.testing.assert_allclose(d[2, 2], [0.0, 1.0, 0.0], atol=1e-15)  # centre = zenith
    # the centre of the top-middle pixel is at r = 0.8: zenith angle 72 deg, azimuth 0 (-Z)
    np.testing.assert_allclose(d[0, 2], [0.0, np.cos(np.radians(72)), -np.sin(np.radians(72))], atol=1e-15)
    # left-middle: azimuth 90 deg (+X), seen from below
    np.testing.assert_allclose(d[2, 0], [np.sin(np.radians(72)), np.cos(np.radians(72)), 0.0], atol=1e-15)
    assert inside[2, 2] and inside[0, 2] and not inside[0, 0]  # corner: r = 0.8 sqrt 2 > 1
    np.testing.assert_allclose(d[0, 0, 1], 0.0, atol=1e-15)  # outside: the rim's direction (on the horizon)


def test_row_of_elevation_closed_form():
    # level camera, 90 deg FOVy, 100 rows: the horizon at the middle (row 49.5), 45 deg at the top edge (row -0.5)
    np.testing.assert_allclose(row_of_elevation(0.0, 100, 90.0, 0.0), 49.5, atol=1e-12)
    np.testing.assert_allclose(row_of_elevation([45.0, -45.0], 100, 90.0, 0.0), [-0.5, 99.5], atol=1e-12)
    # pitched up by 25 deg: the elevation the camera looks at is the middle row
    np.testing.assert_allclose(row_of_elevation(25.0, 64, 60.0, 25.0), 31.5, atol=1e-12)


def test_billboard_frame_faces_the_viewer():
    rt, up = billboard_frame(np.array([0.0, 0.0, -1.0]))
    np.testing.assert_allclose(rt, [1.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(up, [0.0, 1.0, 0.0], atol=1e-15)
    f = np.array([0.3, 0.2, -1.0])
    f = f / np.linalg.norm(f)
    rt, up = billboard_frame(f)
    np.testing.assert_allclose([rt @ rt, up @ up, rt @ up, rt @ f, up @ f, rt[1]], [1, 1, 0, 0, 0, 0], atol=1e-15)
    assert up[1] > 0  # upright


def test_environment_sky_sun_ridge_and_ground():
    d = np.array([[0.0, 1.0, 0.0],                          # zenith: the sky's top colour
                  [-0.45, 0.45, -1.0],                      # the sun: the sky plus the sun's colour, clipped
                  [0.0, 0.01, -1.0],                        # just above the horizon, ahead: the ridge
                  [0.0, -1.0, 0.0],                         # straight down: the road, 1.6 m away
                  [0.0, -1e-3, -1.0]])                      # far ahead on the ground: all haze
    rgb = environment(d * 3.0)  # any length
    assert rgb.dtype == np.float32 and rgb.shape == (5, 3)
    np.testing.assert_allclose(rgb[0], [0.22, 0.42, 0.85], rtol=1e-6)
    assert np.all(rgb[1] >= rgb[0]) and rgb[1][0] == 1.0
    np.testing.assert_allclose(rgb[2], [0.42, 0.45, 0.58], rtol=1e-6)
    haze = 1 - np.exp(-1.6 / 60.0)
    np.testing.assert_allclose(rgb[3], (1 - haze) * np.array([0.3, 0.3, 0.32]) + haze * np.array([0.8, 0.84, 0.9]),
                               rtol=1e-6)
    np.testing.assert_allclose(rgb[4], [0.8, 0.84, 0.9], rtol=1e-5)
    img = environment(pinhole_directions(32, 16, 120.0))
    assert img.shape == (16, 32, 3) and img.min() >= 0.0 and img.max() <= 1.0


def test_one_type_textures_fill_the_weather_map_with_one_type(tmp_path):
    from pywarp.clouds import textures as T
    from pywarp.clouds.cloudscape import CloudscapeSettings
    from pywarp.tutorial import one_type_textures

    gen = T.BasicTextureGenerator(cache=T.TextureCache(tmp_path))
    s = CloudscapeSettings(width=16, height=9, base_size=32, detail_size=16, curl_size=32, weather_size=64,
                           coverage=0.6, precipitation=0.3, cloud_type=0.7, seed=4)
    tex = one_type_textures(s, gen)
    assert np.all(tex.weather[..., 2] == np.float32(0.7))  # the type channel: one value
    # coverage and precipitation are those of the same weather map with its default type spread
    spread = gen.weather_map(T.WeatherMapSettings(size=64, seed=4, coverage=0.6, precipitation=0.3, cloud_type=0.7))
    assert np.ptp(spread[..., 2]) > 0.1
    np.testing.assert_array_equal(tex.weather[..., :2], spread[..., :2])
    np.testing.assert_array_equal(tex.base, gen.base_shape(T.BaseShapeSettings(size=32, seed=4)))
    assert tex.base.shape == (32, 32, 32, 4) and tex.detail.shape == (16, 16, 16, 4) and tex.curl.shape == (32, 32, 4)


def test_run_as_script_passes_the_options_and_prints_every_file(tmp_path, capsys):
    from pywarp.tutorial import run_as_script

    calls = []

    def main(out_dir, quick=False):
        calls.append((out_dir, quick))
        return [f"{out_dir}/a.png", f"{out_dir}/b.png"]

    assert run_as_script(main, "Title line.\n\nMore.", "figures/vc", argv=[]) == ["figures/vc/a.png",
                                                                               "figures/vc/b.png"]
    assert run_as_script(main, "Title line.", "figures/vc", argv=["--out", str(tmp_path), "--quick"])
    assert calls == [("figures/vc", False), (str(tmp_path), True)]
    assert capsys.readouterr().out.splitlines() == ["figures/vc/a.png", "figures/vc/b.png", f"{tmp_path}/a.png",
                                                    f"{tmp_path}/b.png"]
    with pytest.raises(SystemExit):  # no abbreviations
        run_as_script(main, "Title line.", "figures/vc", argv=["--qu"])
