"""`pywarp figures --scheduler dask`: tutorials run as tasks on the workers of a 2-process LocalCluster write the same
files, pixel for pixel, as a serial run in this process."""
from __future__ import annotations

import importlib

import numpy as np
import pytest

pytest.importorskip("dask.distributed")

cli_main = importlib.import_module("pywarp.cli.main")

TUTORIALS = ["extra_phase_functions", "fig_2_06_interpolation"]  # two quick ones (a few seconds each)


def _run(*argv):
    try:
        return cli_main.main(list(argv))
    except SystemExit as exc:
        return exc.code


def _pngs(folder):
    from PIL import Image

    return {p.relative_to(folder).as_posix(): np.asarray(Image.open(p)) for p in sorted(folder.rglob("*.png"))}


def test_tutorials_on_a_two_worker_local_cluster_equal_a_serial_run(tmp_path, capsys):
    assert _run("figures", "--quick", "--no-progress", "--only", *TUTORIALS, "--out", str(tmp_path / "one")) == 0
    assert _run("figures", "--quick", "--no-progress", "--only", *TUTORIALS, "--scheduler", "dask",
                "--dask-workers", "2", "--out", str(tmp_path / "dask")) == 0
    out = capsys.readouterr().out
    assert "from 2 tutorials written" in out
    one, dask = _pngs(tmp_path / "one"), _pngs(tmp_path / "dask")
    assert len(one) >= 2 and sorted(one) == sorted(dask)
    for name in one:
        assert one[name].shape == dask[name].shape and np.array_equal(one[name], dask[name]), f"{name} differs"


def test_a_failing_tutorial_is_reported_and_the_others_written(tmp_path, monkeypatch, capsys):
    from pywarp.core import figures

    paths = figures.select("vc", ["extra_phase_functions"])
    bad = tmp_path / "tut" / "vc" / "fig_9_99_broken.py"
    bad.parent.mkdir(parents=True)
    bad.write_text('"""Broken on purpose (vc-fig-9.99)."""\n\ndef main(out_dir, quick=False):\n'
                   '    raise ValueError("broken on purpose")\n')
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        failures = []
        written = figures.run_on_dask(client, paths + [bad], tmp_path / "out", quick=True, progress=False,
                                      failures=failures)
    assert [p.name for p, _ in failures] == [bad.name]
    assert isinstance(failures[0][1], ValueError) and "broken on purpose" in str(failures[0][1])
    assert written and all(p.is_file() for p in written)


@pytest.mark.parametrize("argv, message", [(["--scheduler", "spark"], "--scheduler"),
                                           (["--scheduler", "dask", "--dask-workers", "0"], "--dask-workers")])
def test_bad_scheduler_options_name_the_option(tmp_path, capsys, argv, message):
    assert _run("figures", "--quick", "--only", TUTORIALS[0], *argv, "--out", str(tmp_path)) == 2
    assert message in capsys.readouterr().err


def test_dask_benchmark_report_and_device(capsys):
    """`pywarp bench clouds dask`: the table (the real run takes minutes; its numbers are in the issue's note)."""
    from pywarp.core import animation

    res = {"scene": "clouds", "frames": 16, "width": 320, "height": 180, "chunk": 4, "repeat": 1, "cores": 2,
           "rows": [{"workers": 1, "seconds": 30.0, "fps": 16 / 30, "fps_per_worker": 16 / 30, "speedup": 1.0},
                    {"workers": 2, "seconds": 16.0, "fps": 1.0, "fps_per_worker": 0.5, "speedup": 1.875}],
           "load_average_before": [7.5, 7.5, 8.0], "load_average_after": [6.6, 7.2, 7.8]}
    text = animation.report_dask(res)
    assert "16 frames 320x180" in text and "1.88x" in text and "load average before 7.50" in text
    with pytest.raises(ValueError, match="--device must be cpu"):
        animation.run_dask_bench(device="cuda:0")
