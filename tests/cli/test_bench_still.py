"""``pywarp bench SCENE still [--baseline PYTHON]``: every scene has it; it renders the still ``pywarp render`` makes
(the same pixels), times it in-process and the whole command once, and with a baseline interpreter runs the same
probe there, interleaved, and compares the two images. The baseline is this interpreter itself (a wrapper putting
back the variables the baseline's environment loses), so the two images must be equal and the ratio defined. No test
asserts on a time."""
from __future__ import annotations

import json
import os
import stat
import sys
from pathlib import Path

import numpy as np
import pytest

import pywarp
from pywarp.cli.main import main
from pywarp.core import scenes
from pywarp.core.baseline import BaselineError
from pywarp.core.bench_still import bench_still, compare_images

QUICK = dict(width=32, height=18, repeat=2)


@pytest.fixture
def this_python(tmp_path) -> Path:
    """This interpreter and this pywarp as a 'baseline' (its environment loses PYTHONPATH and CCLOUDS_LIBRARY)."""
    env = {"PYTHONPATH": str(Path(pywarp.__file__).resolve().parent.parent)}
    if os.environ.get("CCLOUDS_LIBRARY"):
        env["CCLOUDS_LIBRARY"] = os.environ["CCLOUDS_LIBRARY"]
    exports = "".join(f"export {k}='{v}'\n" for k, v in env.items())
    path = tmp_path / "python-self"
    path.write_text(f"#!/bin/sh\n{exports}exec '{sys.executable}' \"$@\"\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


def test_every_scene_has_the_still_benchmark():
    for sc in scenes.scenes().values():
        b = sc.benchmarks["still"]
        assert b.defaults == {"width": 640, "height": 360, "repeat": 3, "workers": None, "baseline": None}


def test_quick_still_without_baseline_is_pywarp_renders_image(tmp_path):
    res = bench_still("flight", **QUICK)
    ours = res["ours"]
    assert res["baseline"] is None and res["speedup"] is None and res["image_change"] is None
    assert len(ours["rounds_ms"]) == 2 and ours["still_ms"] == min(ours["rounds_ms"])
    assert ours["repeat_identical"] and ours["process_image_identical"]  # the command wrote the same pixels
    assert ours["process_ms"] > 0 and "process_start_ms" in ours
    img = res["images"]["ours"]
    assert img.shape == (18, 32, 3) and img.dtype == np.uint8
    sc = scenes.scene("flight")
    offline = np.asarray(sc.technique(sc.settings(width=32, height=18)).render(), np.uint8)
    assert np.array_equal(img, offline)


def test_baseline_of_itself_gives_the_same_image_and_a_ratio(this_python, capsys):
    assert main(["bench", "rain", "still", "--width", "32", "--height", "18", "--repeat", "2",
                 "--baseline", str(this_python), "--json"]) == 0
    res = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert res["benchmark"] == "still" and res["scene"] == "rain" and "images" not in res
    assert res["baseline"]["pywarp"] == res["ours"]["pywarp"]  # the same installation on both sides
    assert res["baseline"]["settings"] == res["ours"]["settings"] and res["baseline"]["settings_not_applied"] == []
    assert len(res["ours"]["rounds_ms"]) == len(res["baseline"]["rounds_ms"]) == 2
    assert res["speedup"] == pytest.approx(res["baseline"]["still_ms"] / res["ours"]["still_ms"], rel=1e-2)
    change = res["image_change"]
    assert change["identical"] and change["ssim"] == 1.0 and change["ciede2000_mean"] == 0.0
    assert change["max_abs_diff"] == 0
    assert res["baseline"]["process_image_identical"] and res["ours"]["process_image_identical"]


def test_report_names_both_sides_and_the_image_change(this_python):
    from pywarp.core.bench_still import report_still

    res = bench_still("flight", width=32, height=18, repeat=1, baseline=str(this_python), process=False)
    text = report_still(res)
    assert "ours" in text and "baseline" in text and "speed-up (baseline / ours)" in text
    assert "SSIM 1.0000" in text and "(identical)" in text
    assert "process start" not in text  # not measured


def test_compare_images_sees_a_change():
    a = np.full((20, 30, 3), 100, np.uint8)
    b = a.copy()
    b[5:15, 10:20] = 180
    c = compare_images(b, a)
    assert not c["identical"] and c["max_abs_diff"] == 80 and c["ssim"] < 0.9 and c["ciede2000_mean"] > 1.0
    with pytest.raises(ValueError, match="differ in size"):
        compare_images(a, a[:10])


def test_bad_options_are_refused_before_anything_runs(tmp_path):
    with pytest.raises(BaselineError, match=r"--baseline .*no such file"):
        bench_still("flight", baseline=str(tmp_path / "nope"))
    with pytest.raises(ValueError, match="repeat must be an integer >= 1"):
        bench_still("flight", repeat=0)
    with pytest.raises(ValueError, match="width must be an integer"):
        bench_still("flight", width=0)
    with pytest.raises(ValueError, match="no-such-scene"):
        bench_still("no-such-scene")
