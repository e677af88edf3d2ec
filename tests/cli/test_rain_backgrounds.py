"""``pywarp render rain --background SCENE --background-set KEY=VALUE``: every registered scene renders as the rain's
background with its own default options (and the rain scene's own for it), options reach the background scene, and an
unknown key is an error naming it and the background, with the closest field."""
from __future__ import annotations

import numpy as np
import pytest

from pywarp.cli.main import main
from pywarp.core.scenes import scenes

SMALL = ["--width", "48", "--height", "32", "--drops", "200", "--capture-size", "32", "--mask-size", "32",
         "--no-progress"]


def _render(tmp_path, *args) -> np.ndarray:
    from PIL import Image

    out = tmp_path / "rain.png"
    assert main(["render", "rain", *args, *SMALL, "--out", str(out)]) == 0
    return np.asarray(Image.open(out).convert("RGB"), dtype=np.float64)


@pytest.mark.parametrize("background", ["panorama"] + sorted(set(scenes()) - {"rain"}))
def test_every_background_renders(tmp_path, background):
    img = _render(tmp_path, "--background", background)
    assert img.shape == (32, 48, 3) and img.std() > 5.0  # a picture, not a flat colour


def test_the_default_background_is_the_overcast_terrain(tmp_path):
    default = _render(tmp_path)
    assert np.array_equal(default, _render(tmp_path, "--background", "terrain"))
    # the rain scene's sky for it is grey: the top rows (sky) have about equal channels, unlike the terrain's blue
    sky = default[:4].reshape(-1, 3).mean(axis=0)
    assert sky.max() - sky.min() < 25


def test_background_set_passes_options_to_the_background(tmp_path):
    base = _render(tmp_path, "--background", "terrain")
    fog = _render(tmp_path, "--background", "terrain", "--background-set", "fog_density=0.05",
                  "--background-set", "sky_colour=0.9,0.3,0.2")
    assert np.abs(fog - base).mean() > 10.0
    sky = fog[:4].reshape(-1, 3).mean(axis=0)
    assert sky[0] > sky[2] + 40  # the red sky it was given


@pytest.mark.parametrize("background, item, message", [
    ("terrain", "fog_densty=0.1", r"--background-set has no field\(s\) \['fog_densty'\] in scene 'terrain' "
                                  r"\(did you mean fog_density\?\)"),
    ("clouds", "coverage=lots", r"--background-set coverage must be a number, got 'lots'"),
    ("flight", "nonsense", r"--background-set must be KEY=VALUE, got 'nonsense'"),
    ("panorama", "seed=1", r"--background-set has no field\(s\) \['seed'\] in the built-in panorama"),
])
def test_background_set_refuses_what_the_background_has_not(tmp_path, capsys, background, item, message):
    with pytest.raises(SystemExit) as exc:
        main(["render", "rain", "--background", background, "--background-set", item, *SMALL,
              "--out", str(tmp_path / "x.png")])
    assert exc.value.code == 2
    import re

    assert re.search(message, capsys.readouterr().err)
