"""`pywarp animate --scheduler dask`: a path split into chunks of frames rendered by the workers of a 2-process
LocalCluster gives frames identical to a single-process render of the same path (full frames: reprojection off)."""
from __future__ import annotations

import importlib

import numpy as np
import pytest

pytest.importorskip("dask.distributed")

cli_main = importlib.import_module("pywarp.cli.main")

ARGS = ["--frames", "5", "--width", "32", "--height", "18", "--no-progress"]


def _run(*argv):
    try:
        return cli_main.main(list(argv))
    except SystemExit as exc:
        return exc.code


def _frames(folder):
    from PIL import Image

    return [np.asarray(Image.open(p)) for p in sorted(folder.glob("f_*.png"))]


def test_frames_on_a_two_worker_local_cluster_equal_a_single_process_render(tmp_path):
    assert _run("animate", *ARGS, "--no-reprojection", "--out", str(tmp_path / "one" / "f_%03d.png")) == 0
    # chunks of 2 frames: the second and third chunks start mid-path (frame counter, wind time, pose)
    assert _run("animate", *ARGS, "--scheduler", "dask", "--dask-workers", "2", "--chunk", "2",
                "--out", str(tmp_path / "dask" / "f_%03d.png")) == 0
    one, dask = _frames(tmp_path / "one"), _frames(tmp_path / "dask")
    assert len(one) == len(dask) == 5
    for i, (a, b) in enumerate(zip(one, dask)):
        assert np.array_equal(a, b), f"frame {i} differs"
    assert not np.array_equal(one[0], one[4])  # the path moves


def test_reprojection_is_refused_under_dask(tmp_path, capsys):
    assert _run("animate", *ARGS, "--reprojection", "--scheduler", "dask", "--out", str(tmp_path / "f_%03d.png")) == 2
    assert "--reprojection cannot be used with --scheduler dask" in capsys.readouterr().err


@pytest.mark.parametrize("value", ["spark", "local=x", "dask="])
def test_bad_scheduler_names_the_option(tmp_path, capsys, value):
    assert _run("animate", *ARGS, "--scheduler", value, "--out", str(tmp_path / "f_%03d.png")) == 2
    assert "--scheduler" in capsys.readouterr().err
