"""libFuzzer harnesses of cclouds/fuzz (issue 14, "Keep it fixed" 1): build them with clang under ASan + UBSan,
replay the committed seed corpora, then fuzz each harness for a short, bounded, deterministic run (-seed=1). Any
finding (crash, sanitizer report, broken contract, timeout, memory blow-up) fails the test and leaves the input
under pytest's temporary directory. Skipped when clang with libFuzzer is not available. cclouds/fuzz/README.md says
how to fuzz longer.

Cost: one build of the library (~20-40 s on 2 cores) plus FUZZ_SECONDS per harness (13 harnesses).
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FUZZ = ROOT / "cclouds" / "fuzz"
HARNESSES = sorted(p.stem for p in FUZZ.glob("fuzz_*.c"))
FUZZ_SECONDS = int(os.environ.get("CCLOUDS_FUZZ_SECONDS", "4"))
LIMITS = ["-timeout=2", "-rss_limit_mb=1024", "-seed=1", "-print_final_stats=1"]


def _clang_has_libfuzzer(tmp: Path) -> bool:
    clang = shutil.which("clang")
    if clang is None:
        return False
    src = tmp / "probe.c"
    src.write_text("#include <stdint.h>\n#include <stddef.h>\n"
                   "int LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }\n")
    res = subprocess.run([clang, "-fsanitize=fuzzer,address,undefined", str(src), "-o", str(tmp / "probe")],
                         capture_output=True, text=True)
    return res.returncode == 0


@pytest.fixture(scope="module")
def fuzz_build(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("cclouds-fuzz")
    if shutil.which("cmake") is None:
        pytest.skip("CMake is not installed")
    if not _clang_has_libfuzzer(tmp):
        pytest.skip("clang with libFuzzer (-fsanitize=fuzzer) is not available")
    build = tmp / "build"
    env = dict(os.environ, CC=shutil.which("clang"))
    for cmd in (["cmake", "-S", FUZZ, "-B", build, "-DCMAKE_BUILD_TYPE=RelWithDebInfo"],
                ["cmake", "--build", build, "--parallel", str(max(1, os.cpu_count() or 1))]):
        res = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, env=env)
        assert res.returncode == 0, f"{' '.join(map(str, cmd))} failed:\n{res.stdout[-4000:]}\n{res.stderr[-4000:]}"
    return build


@pytest.fixture(scope="module")
def fuzz_summary(request):
    """Executions and findings per harness, printed as one table at the end of the module (also without -s) and
    recorded as test properties (JUnit XML)."""
    rows: dict[str, tuple[int, int]] = {}
    yield rows
    reporter = request.config.pluginmanager.get_plugin("terminalreporter")
    capture = request.config.pluginmanager.get_plugin("capturemanager")
    if rows and reporter is not None and capture is not None:
        with capture.global_and_fixture_disabled():
            reporter.write_line("")
            reporter.write_line(f"fuzzing: {FUZZ_SECONDS} s per harness after the corpus replay (-seed=1)")
            for name, (runs, found) in sorted(rows.items()):
                reporter.write_line(f"  {name:<18} {runs:>10} executions  {found} findings")
            reporter.write_line(f"  {'total':<18} {sum(r for r, _ in rows.values()):>10} executions  "
                                f"{sum(f for _, f in rows.values())} findings")


def test_every_harness_has_a_seed_corpus():
    assert HARNESSES, "no harness in cclouds/fuzz"
    for name in HARNESSES:
        corpus = FUZZ / "corpus" / name.removeprefix("fuzz_")
        files = [p for p in corpus.glob("*") if p.is_file()] if corpus.is_dir() else []
        assert 1 <= len(files) <= 16, f"{corpus}: {len(files)} seed files"
        assert all(p.stat().st_size <= 4096 for p in files), f"{corpus}: seed files must stay small"


def _run(binary: Path, args: list, cwd: Path, timeout: float):
    res = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=timeout)
    return res, res.stdout + res.stderr


@pytest.mark.parametrize("name", HARNESSES)
def test_fuzz_harness(fuzz_build, fuzz_summary, record_property, tmp_path, name):
    binary = fuzz_build / name
    seeds = FUZZ / "corpus" / name.removeprefix("fuzz_")
    artifacts = f"-artifact_prefix={tmp_path}/"
    # 1. replay the committed corpus (every file once)
    res, log = _run(binary, [*LIMITS, artifacts, "-runs=0", seeds], tmp_path, 120)
    assert res.returncode == 0, f"{name}: replaying {seeds} found a problem:\n{log[-6000:]}"
    # 2. a short deterministic fuzzing run from a copy of the corpus (the fuzzer adds files to its first directory)
    work = tmp_path / "corpus"
    shutil.copytree(seeds, work)
    res, log = _run(binary, [*LIMITS, artifacts, f"-max_total_time={FUZZ_SECONDS}", work], tmp_path,
                    FUZZ_SECONDS + 120)
    found = sorted(p.name for p in tmp_path.glob("*-*") if p.is_file() and p.name.split("-")[0] in
                   ("crash", "leak", "timeout", "oom", "slow-unit"))
    runs = re.search(r"stat::number_of_executed_units:\s*(\d+)", log)
    n_runs = int(runs.group(1)) if runs else 0
    n_found = max(len(found), int(res.returncode != 0))
    fuzz_summary[name] = (n_runs, n_found)
    record_property("executions", n_runs)
    record_property("findings", n_found)
    assert res.returncode == 0 and not found, f"{name}: finding {found}:\n{log[-6000:]}"
    assert n_runs > 0, f"{name}: no executions reported:\n{log[-2000:]}"
    print(f"{name}: {n_runs} executions in {FUZZ_SECONDS} s, 0 findings")
