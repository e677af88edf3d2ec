"""Benchmarks that talk: ``pywarp bench`` prints, on stderr, what a benchmark measures and how long it takes before it
measures, its rows as they finish, and the load average at its start and end with a warning when the machine was
busy; ``bench --help`` lists every benchmark with its duration; ``--json`` keeps one JSON object as the last line of
stdout; the rain table warns when its times fall as the drop count grows."""
from __future__ import annotations

import json
import os

import pytest

from pywarp.cli.main import main
from pywarp.core import scenes, timing

ALL = [(sc.name, name) for sc in scenes.scenes().values() for name in sc.benchmarks]


@pytest.fixture
def fake_drops(monkeypatch):
    """``bench rain drops`` replaced by two rows printed as they finish (the real one measures 24 frames)."""
    import pywarp.rain.bench as bench

    def run(**kw):
        progress = timing.Progress(2, "drop counts")
        progress.step("0 drops: drops 1.00 ms")
        progress.step("10 drops: drops 2.00 ms")
        return {"benchmark": "rain drops", **kw}

    monkeypatch.setattr(bench, "bench_drops", run)
    monkeypatch.setattr(bench, "report_drops", lambda r: f"report of {r['benchmark']}")


def _load(monkeypatch, *values):
    """os.getloadavg answering ``values`` in turn (the start, then the end)."""
    answers = iter(values)
    monkeypatch.setattr(os, "getloadavg", lambda: next(answers))
    monkeypatch.setattr(os, "cpu_count", lambda: 2)


@pytest.mark.parametrize("scene,name", ALL)
def test_every_benchmark_states_its_duration(scene, name):
    expected = scenes.scene(scene).benchmarks[name].expected
    assert any(c.isdigit() for c in expected) and ("s" in expected or "min" in expected), expected


def test_help_lists_every_benchmark_with_its_duration(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["bench", "--help"])
    assert exc.value.code == 0
    out = " ".join(capsys.readouterr().out.split())  # argparse wraps the lines
    assert "benchmarks [time at the defaults on 2 CPU cores]:" in out
    for scene, name in ALL:
        expected = scenes.scene(scene).benchmarks[name].expected
        assert f"{scene} {name} [{expected}]:" in out, (scene, name)


def test_header_rows_and_load_on_stderr_json_last_on_stdout(fake_drops, monkeypatch, capsys):
    _load(monkeypatch, (0.2, 0.3, 0.4), (0.6, 0.5, 0.4))
    assert main(["bench", "rain", "drops", "--width", "32", "--repeat", "1", "--json"]) == 0
    out, err = capsys.readouterr()
    last = json.loads(out.strip().splitlines()[-1])
    assert last["benchmark"] == "rain drops" and last["width"] == 32
    assert last["load"] == {"start": [0.2, 0.3, 0.4], "end": [0.6, 0.5, 0.4], "cores": 2, "busy": False}
    lines = err.splitlines()
    b = scenes.scene("rain").benchmarks["drops"]
    assert lines[0] == f"pywarp bench rain drops: {b.description}"
    assert lines[1].startswith(f"  expected: {b.expected} on 2 CPU cores at its defaults (options: width 32, "
                               "height 360, repeat 1, workers auto, device cpu)")
    assert lines[2] == "  load average at start: 0.20 0.30 0.40 (1, 5, 15 min; 2 cores)"
    assert lines[3].startswith("  drop counts [1/2] 0 drops: drops 1.00 ms (") and "ETA" in lines[3]
    assert lines[4].startswith("  drop counts [2/2] 10 drops: drops 2.00 ms (") and "ETA" not in lines[4]
    assert lines[5] == "load average at end: 0.60 0.50 0.40 (1, 5, 15 min; 2 cores)"
    assert len(lines) == 6 and "warning" not in err  # 0.3 per core at the end: not busy


@pytest.mark.parametrize("start,end,per_core", [((1.6, 1.0, 1.0), (0.4, 0.4, 0.4), "start 0.80, end 0.20"),
                                                ((0.2, 0.2, 0.2), (3.0, 1.0, 1.0), "start 0.10, end 1.50")])
def test_busy_machine_warns_that_numbers_may_be_off(fake_drops, monkeypatch, capsys, start, end, per_core):
    _load(monkeypatch, start, end)
    assert main(["bench", "rain", "drops", "--repeat", "1"]) == 0
    out, err = capsys.readouterr()
    assert out == "report of rain drops\n"  # stdout: the report alone
    assert err.splitlines()[-1] == (f"warning: the machine was busy while this ran (load per core {per_core}; above "
                                    "0.5): the numbers may be off -- compare the ratios within this run, or rerun "
                                    "on an idle machine")


def test_no_load_average_on_the_system(fake_drops, monkeypatch, capsys):
    def none():
        raise OSError("no load average")

    monkeypatch.setattr(os, "getloadavg", none)
    assert main(["bench", "rain", "drops", "--json"]) == 0
    out, err = capsys.readouterr()
    assert json.loads(out.strip().splitlines()[-1])["load"]["busy"] is False
    assert "load average at start: not available on this system" in err and "warning" not in err


def test_bad_arguments_print_no_header(fake_drops, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["bench", "rain", "drops", "--width", "0"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("pywarp bench: error: --width") and "expected" not in err


def test_a_bad_baseline_is_refused_before_the_header(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["bench", "clouds", "speed", "--baseline", str(tmp_path / "nope")])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("pywarp bench: error: --baseline must be") and len(err.splitlines()) == 1


def test_busy_is_load_per_core_over_a_half():
    assert not timing.busy([1.0, 9.0, 9.0], cores=2)  # the 1-minute load counts
    assert timing.busy([1.01, 0.0, 0.0], cores=2)
    assert not timing.busy(None, cores=2)


def test_non_monotonic_finds_falls_beyond_the_tolerance():
    assert timing.non_monotonic([0, 1, 10, 100], [1.0, 1.05, 2.0, 3.0]) == []
    assert timing.non_monotonic([0, 1, 10], [1.0, 0.95, 2.0]) == []  # a 5 % fall is noise
    assert timing.non_monotonic([0, 10, 50, 100], [1.0, 3.9, 2.7, 4.0]) == [(10, 3.9, 50, 2.7)]
    assert timing.non_monotonic([0, 10, 50, 100, 500], [1.0, 6.1, 1.6, 2.5, 1.7]) == [(10, 6.1, 50, 1.6),
                                                                                     (100, 2.5, 500, 1.7)]


def test_rain_table_warns_when_not_monotonic():
    from pywarp.rain.bench import monotonic_warnings, report_drops

    rows = [{"drops": 0, "drops_ms": 1.0, "streaks_ms": 1.0, "drops_fps": 1000.0, "streaks_fps": 1000.0},
            {"drops": 10, "drops_ms": 3.87, "streaks_ms": 2.0, "drops_fps": 258.4, "streaks_fps": 500.0},
            {"drops": 50, "drops_ms": 2.69, "streaks_ms": 3.0, "drops_fps": 371.7, "streaks_fps": 333.3}]
    warnings = monotonic_warnings(rows)
    assert len(warnings) == 1 and warnings[0].startswith("drops: the time falls as the drop count grows (3.87 ms at "
                                                         "10 drops -> 2.69 ms at 50)")
    text = report_drops({"width": 32, "height": 18, "device": "cpu", "workers": 2, "background": "panorama",
                         "rows": rows, "mask_build_ms": {}, "warnings": warnings})
    assert text.splitlines()[-1] == "warning: " + warnings[0]
    rows[2]["drops_ms"] = 4.0
    assert monotonic_warnings(rows) == []


def test_progress_every_nth_step_and_the_last(capsys):
    progress = timing.Progress(5, "frames", every=2)
    for k in range(5):
        progress.step(f"frame {k}")
    err = capsys.readouterr().err.splitlines()
    assert [line.split(" (")[0] for line in err] == ["  frames [2/5] frame 1", "  frames [4/5] frame 3",
                                                     "  frames [5/5] frame 4"]


def test_json_warnings_of_a_benchmark_go_to_stderr(monkeypatch, capsys):
    import pywarp.rain.bench as bench

    monkeypatch.setattr(bench, "bench_drops", lambda **kw: {"benchmark": "rain drops", "warnings": ["drops: falls"]})
    assert main(["bench", "rain", "drops", "--json"]) == 0
    out, err = capsys.readouterr()
    assert json.loads(out.strip().splitlines()[-1])["warnings"] == ["drops: falls"]
    assert "warning: drops: falls\n" in err


def test_rain_bench_prints_each_row_as_it_finishes(capsys):
    from pywarp.rain.bench import bench_drops

    r = bench_drops(width=32, height=18, repeat=1, counts=(0, 10, 100), masks=False)
    err = capsys.readouterr().err.splitlines()
    assert [line.split(" drops:")[0] for line in err] == [f"  drop counts [{k}/3] {n}" for k, n in
                                                          ((1, 0), (2, 10), (3, 100))]
    assert [row["drops"] for row in r["rows"]] == [0, 10, 100] and isinstance(r["warnings"], list)
