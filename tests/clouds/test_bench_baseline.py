"""``pywarp bench clouds speed`` and ``--baseline PYTHON``: the same probe measured in another interpreter, the two
sides interleaved, both printed with the ratios.

The mechanism is tested with this interpreter as its own baseline (a wrapper script, since the baseline's environment
is cleaned of this checkout's variables), and with small fake interpreters that speak the probe's protocol: the order
of the measurements, answers lacking keys (an older installation), and every way a baseline can fail. No test
asserts on a time."""
from __future__ import annotations

import importlib
import json
import math
import os
import stat
import sys
from pathlib import Path

import pytest

import pywarp
from pywarp.clouds import bench

cli_main = importlib.import_module("pywarp.cli.main")

SMALL_SCENE = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64, camera_pitch_deg=20.0)
SMALL_SIZES = {"reprojected": (48, 27), "full": (64, 36)}


def _script(path: Path, text: str) -> Path:
    path.write_text(text)
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


@pytest.fixture
def this_python(tmp_path) -> Path:
    """This interpreter and this pywarp as a 'baseline': the baseline's environment loses PYTHONPATH and
    CCLOUDS_LIBRARY (they point at this checkout), so a wrapper puts them back."""
    env = {"PYTHONPATH": str(Path(pywarp.__file__).resolve().parent.parent)}
    if os.environ.get("CCLOUDS_LIBRARY"):
        env["CCLOUDS_LIBRARY"] = os.environ["CCLOUDS_LIBRARY"]
    exports = "".join(f"export {k}='{v}'\n" for k, v in env.items())
    return _script(tmp_path / "python-self", f"#!/bin/sh\n{exports}exec '{sys.executable}' \"$@\"\n")


def _fake(tmp_path: Path, name: str = "fakepy", ready: dict | None = None, die_on: str | None = None,
          garbage: bool = False, start_fails: bool = False) -> tuple[Path, Path]:
    """A fake interpreter answering the probe's protocol (``-c SOURCE CONFIG``), logging every command."""
    log = tmp_path / f"{name}.log"
    ready = {"ready": True, "api": "fake", "version": "0.0.1"} if ready is None else ready
    body = f"""#!{sys.executable}
import json, os, sys
log = open({str(log)!r}, "a")
log.write("pid %d\\n" % os.getpid()); log.flush()
if {start_fails!r}:
    sys.stderr.write("Traceback (most recent call last):\\nModuleNotFoundError: No module named 'pywarp'\\n")
    sys.exit(1)
assert sys.argv[1] == "-c" and "class SpeedProbe" in sys.argv[2]
cfg = json.loads(sys.argv[3])
log.write("config %s\\n" % json.dumps(cfg)); log.flush()
if {garbage!r}:
    print("Warp 1.0 initialized"); sys.stdout.flush()
print({json.dumps(ready)!r}); sys.stdout.flush()
for line in sys.stdin:
    cmd = line.strip()
    log.write("baseline " + cmd + "\\n"); log.flush()
    if cmd == "quit":
        break
    if cmd == {die_on!r}:
        sys.stderr.write("Segmentation fault in the old renderer\\n")
        sys.exit(3)
    print(json.dumps({{"ms": 5.0}})); sys.stdout.flush()
"""
    return _script(tmp_path / name, body), log


@pytest.fixture
def fake_ours(monkeypatch):
    """Our side replaced by a recorder (no rendering): the order of the measurements is what is tested."""
    events = []

    class Probe:
        def __init__(self, cfg):
            self.not_applied = []

        def reprojected(self):
            events.append("ours reprojected")
            return 2.0

        def full(self):
            events.append("ours full")
            return 40.0

        def full_same_size(self):
            events.append("ours full_same_size")
            return 10.0

    ns = {"SpeedProbe": Probe, "describe": lambda probe: {"api": "ours", "settings_not_applied": []}}
    monkeypatch.setattr(bench, "_speed_probe_module", lambda: ns)
    return events


# --- this interpreter as its own baseline --------------------------------------------------------------------------

def test_speed_with_this_interpreter_as_its_own_baseline(this_python, capsys):
    res = bench.bench_speed(repeat=2, frames=2, sizes=SMALL_SIZES, scene=SMALL_SCENE, baseline=str(this_python))
    json.dumps(res)  # one JSON object
    assert res["benchmark"] == "speed" and res["schema"] == bench.SPEED_SCHEMA
    assert res["sizes"] == {k: list(v) for k, v in SMALL_SIZES.items()} and res["path_frames"] == 2
    ours, base = res["ours"], res["baseline"]
    for side in (ours, base):
        for k in bench.SPEED_KEYS:
            assert isinstance(side[k], float) and math.isfinite(side[k]) and side[k] > 0.0, (k, side)
        assert set(side["rounds_ms"]) == {"reprojected", "full_same_size", "full"}
        for kind, rounds in side["rounds_ms"].items():
            assert len(rounds) == 2 and side[f"{kind}_ms"] == min(rounds)
        # the ratio of the issue compares frames of one size
        assert side["reprojected_over_full"] == pytest.approx(side["reprojected_ms"] / side["full_same_size_ms"])
        assert side["api"] == "pywarp.clouds.technique" and side["settings_not_applied"] == []
    # the baseline imported the same package, in another process with a cleaned environment
    assert Path(base["pywarp"]).resolve() == Path(ours["pywarp"]).resolve()
    for k in bench.SPEED_KEYS:
        assert res["ours_over_baseline"][k] == pytest.approx(ours[k] / base[k])
    for k in ("reprojected_ms", "full_ms", "full_same_size_ms"):
        assert res["speedup"][k] == pytest.approx(base[k] / ours[k])
    text = bench.report_speed(res)
    assert "ours" in text and "baseline" in text and "48x27 reprojected" in text and "64x36 full frame" in text
    assert "48x27 full frame" in text and "reprojected / full, both 48x27" in text
    assert str(this_python) in text


def test_speed_without_baseline_has_no_ratios():
    res = bench.bench_speed(repeat=1, frames=1, sizes=SMALL_SIZES, scene=SMALL_SCENE)
    assert res["baseline"] is None and res["ours_over_baseline"] is None and res["speedup"] is None
    assert res["ours"]["reprojected_ms"] > 0.0
    assert "n/a" not in bench.report_speed(res).split("targets")[0].replace("reprojected / full", "")


# --- the interleaving and the protocol (fake interpreters) ----------------------------------------------------------

def test_sides_take_turns_a_b_then_b_a(tmp_path, fake_ours, monkeypatch):
    """One measurement at a time, A B in even rounds and B A in odd ones (drifts of the machine cancel)."""
    py, log = _fake(tmp_path)
    events = fake_ours
    measure = bench._BaselineProcess.measure

    def logged(self, kind):
        ms = measure(self, kind)  # returns once the baseline has answered
        events.append(f"baseline {kind}")
        return ms

    monkeypatch.setattr(bench._BaselineProcess, "measure", logged)
    res = bench.bench_speed(repeat=3, frames=4, sizes=SMALL_SIZES, scene={"coverage": 0.5}, baseline=str(py))
    kinds = ("reprojected", "full_same_size", "full")
    ab = [f"{side} {k}" for k in kinds for side in ("ours", "baseline")]
    ba = [f"{side} {k}" for k in kinds for side in ("baseline", "ours")]
    assert events == ab + ba + ab
    lines = log.read_text().splitlines()
    cfg = json.loads(next(line for line in lines if line.startswith("config "))[7:])
    assert cfg == {"scene": {"coverage": 0.5}, "device": "cpu", "workers": None, "frames": 4,
                   "reprojected": [48, 27], "full": [64, 36]}
    assert [line for line in lines if line.startswith("baseline ")][-1] == "baseline quit"
    assert res["baseline"]["reprojected_ms"] == 5.0 and res["ours"]["full_ms"] == 40.0
    assert res["speedup"] == {"reprojected_ms": 2.5, "full_ms": 0.125, "full_same_size_ms": 0.5}
    assert res["ours"]["reprojected_over_full"] == 0.2 and res["baseline"]["reprojected_over_full"] == 1.0


def test_a_baseline_without_the_new_keys_is_tolerated(tmp_path, fake_ours):
    """An older probe answers without the descriptive keys; the numbers and the report still come out."""
    py, _ = _fake(tmp_path, ready={"ready": True})
    res = bench.bench_speed(repeat=1, frames=1, sizes=SMALL_SIZES, baseline=str(py))
    assert res["baseline"]["reprojected_ms"] == 5.0 and res["baseline"].get("version") is None
    assert "baseline" in bench.report_speed(res)


def test_speed_side_and_report_tolerate_missing_numbers():
    old = bench.speed_side({"reprojected_ms": 84.0})  # e.g. an answer that lacks the full frames
    assert old == {"reprojected_ms": 84.0, "full_ms": None, "full_same_size_ms": None, "reprojected_over_full": None}
    ours = bench.speed_side({"reprojected_ms": 42.0, "full_ms": 1800.0, "full_same_size_ms": 600.0})
    assert ours["reprojected_over_full"] == pytest.approx(42.0 / 600.0)
    cmp = bench.speed_compare(ours, old)
    assert cmp["ours_over_baseline"] == {"reprojected_ms": 0.5, "full_ms": None, "full_same_size_ms": None,
                                         "reprojected_over_full": None}
    assert cmp["speedup"] == {"reprojected_ms": 2.0, "full_ms": None, "full_same_size_ms": None}
    assert bench.speed_compare(ours, None) == {"ours_over_baseline": None, "speedup": None}
    text = bench.report_speed({"ours": ours, "baseline": old, **cmp})  # no sizes, machine, targets: defaults
    assert "640x360 reprojected" in text and "n/a" in text and "2.00x" in text
    assert bench.speed_side({"full_ms": float("nan"), "reprojected_ms": True})["full_ms"] is None


# --- failures -----------------------------------------------------------------------------------------------------

@pytest.fixture
def no_rendering(monkeypatch):
    def refuse():
        raise AssertionError("our side started before the baseline was checked")

    monkeypatch.setattr(bench, "_speed_probe_module", refuse)


def test_a_missing_interpreter_is_refused_naming_the_option(tmp_path, no_rendering):
    with pytest.raises(bench.BaselineError, match=r"--baseline .*'/no/such/python': no such file"):
        bench.bench_speed(baseline="/no/such/python")
    plain = tmp_path / "python"
    plain.write_text("not a program")
    with pytest.raises(ValueError, match="--baseline .*: not executable"):
        bench.bench_speed(baseline=str(plain))


def test_an_interpreter_without_pywarp_fails_at_the_start(tmp_path, no_rendering):
    py, log = _fake(tmp_path, start_fails=True)
    with pytest.raises(bench.BaselineError) as exc:
        bench.bench_speed(baseline=str(py))
    msg = str(exc.value)
    assert msg.startswith(f"--baseline {py} failed at the start (exit status 1): ")
    assert "No module named 'pywarp'" in msg


def test_a_baseline_dying_mid_run_is_reported_and_reaped(tmp_path, fake_ours):
    py, log = _fake(tmp_path, die_on="full")
    with pytest.raises(bench.BaselineError, match=r"failed while measuring full \(exit status 3\): Segmentation"):
        bench.bench_speed(repeat=2, baseline=str(py))
    pid = int(log.read_text().splitlines()[0].split()[1])
    with pytest.raises(ProcessLookupError):  # waited for: no process, no zombie
        os.kill(pid, 0)


def test_a_baseline_answering_something_else_is_refused(tmp_path, fake_ours):
    py, _ = _fake(tmp_path, garbage=True)
    with pytest.raises(bench.BaselineError, match="not the probe's JSON"):
        bench.bench_speed(baseline=str(py))


def test_the_probe_keeps_other_output_off_the_protocol(this_python):
    """The real probe in a child: what its libraries print while importing (Warp's banner, an old package's notices)
    goes to stderr, and stdout carries only the answers."""
    import subprocess

    cfg = {"scene": SMALL_SCENE, "device": "cpu", "workers": 1, "frames": 1, "reprojected": [16, 9], "full": [16, 9]}
    source = bench._SPEED_PROBE.replace("\ntry:\n", "\nprint('noise on stdout')\ntry:\n", 1)
    assert source != bench._SPEED_PROBE
    proc = subprocess.run([str(this_python), "-c", source, json.dumps(cfg)], input="full\nreprojected\nquit\n",
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    answers = [json.loads(line) for line in proc.stdout.splitlines()]
    assert len(answers) == 3 and answers[0]["ready"] is True
    assert answers[1]["ms"] > 0.0 and answers[2]["ms"] > 0.0
    assert "noise on stdout" in proc.stderr


# --- the fig 4.17 ladder ----------------------------------------------------------------------------------------------

def test_measure_ladder_keeps_every_repetition_and_splits_the_reprojected_frame():
    detail = {}
    sizes = {k: v for k, v in SMALL_SCENE.items() if k.endswith("_size")}
    _, ladder = bench.measure_ladder(48, 27, 2, detail=detail, **sizes)
    assert set(detail["samples"]) == {"unoptimised", "adaptive_samples", "early_exit", "reprojection"}
    for k, v in detail["samples"].items():
        assert len(v) == 2 and all(x > 0.0 for x in v)
        if k != "reprojection":
            assert ladder[k] == min(v)  # the ladder (bench cloudscape) keeps the best repetition
    split = detail["reprojection_split"]
    assert set(split) == {"raymarch", "reprojection", "other"}
    for r in range(2):
        # every pass found by its kernels' names; the parts never exceed the frame
        assert split["raymarch"][r] > 0.0 and split["reprojection"][r] > 0.0 and split["other"][r] >= 0.0
        parts = split["raymarch"][r] + split["reprojection"][r] + split["other"][r]
        assert parts >= detail["samples"]["reprojection"][r] * (1.0 - 1e-9)
    # the cut is the best early-exit frame against the best unoptimised one, from the repetitions it reports (its
    # sign is a timing: a loaded machine may make either faster, so it is not asserted)
    dense = detail["dense_samples"]
    assert len(dense["unoptimised"]) == 2 and len(dense["early_exit"]) == 2
    assert ladder["dense_clouds_cut_percent"] == pytest.approx(
        100.0 * (1.0 - min(dense["early_exit"]) / min(dense["unoptimised"])))


def test_a_renamed_reprojection_kernel_is_an_error_not_zero(monkeypatch):
    monkeypatch.setattr(bench, "REPROJECTION_SPLIT", {"raymarch": ("sky_kernel", "clouds_kernel"),
                                                      "reprojection": ("no_such_kernel",)})
    with pytest.raises(RuntimeError, match="no kernel of the reprojection pass"):
        bench.measure_ladder(32, 18, 1, detail={}, **{k: v for k, v in SMALL_SCENE.items() if k.endswith("_size")})


# --- the command line -----------------------------------------------------------------------------------------------

@pytest.fixture
def fake_speed(monkeypatch):
    calls = []

    def run(**kw):
        calls.append(kw)
        return {"benchmark": "speed", "device": kw["device"], "ours": {"reprojected_ms": 1.0, "full_ms": 20.0},
                "baseline": None, "ours_over_baseline": None, "speedup": None}

    monkeypatch.setattr(bench, "bench_speed", run)
    monkeypatch.setattr(bench, "check_speed", lambda **kw: None)  # the interpreters named here need not exist
    return calls


@pytest.mark.parametrize("argv,kwargs", [
    (["bench", "clouds", "--baseline", "/opt/old/bin/python"], {"baseline": "/opt/old/bin/python"}),
    (["bench", "clouds", "speed", "--repeat", "2"], {"repeat": 2, "baseline": None}),
    (["bench", "speed", "--baseline", "python3", "--workers", "2"], {"baseline": "python3", "workers": 2}),
])
def test_cli_bench_speed_and_baseline(fake_speed, capsys, argv, kwargs):
    assert cli_main.main([*argv, "--json"]) == 0
    assert fake_speed == [{"repeat": 3, "workers": None, "baseline": None, "device": "cpu", **kwargs}]
    assert json.loads(capsys.readouterr().out.strip().splitlines()[-1])["benchmark"] == "speed"


def test_cli_bench_scene_alone_still_runs_its_default_benchmark(monkeypatch, fake_speed, capsys):
    called = []
    monkeypatch.setattr(bench, "bench_cloudscape", lambda **kw: called.append(kw) or {"benchmark": "cloudscape"})
    monkeypatch.setattr(bench, "report_cloudscape", lambda res: "cloudscape")
    assert cli_main.main(["bench", "clouds", "--repeat", "1"]) == 0
    assert called and not fake_speed


def test_cli_bench_baseline_errors_are_one_line(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        cli_main.main(["bench", "clouds", "--baseline", str(tmp_path / "nope")])
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"pywarp bench: error: --baseline must be a Python interpreter with pywarp installed; "
                   f"'{tmp_path / 'nope'}': no such file")
    with pytest.raises(SystemExit) as exc:
        cli_main.main(["bench", "tiles", "--baseline", sys.executable])
    assert exc.value.code == 2
    assert "--baseline is not an option of benchmark 'tiles'" in capsys.readouterr().err
