"""Issue 14, build hygiene: the library and its C unit tests build warning-free with -Werror, -Wconversion and
-Wdouble-promotion under GCC and clang (the flags are in CCLOUDS_LIB_WARNINGS of cclouds/CMakeLists.txt), the tests
share one set of vector helpers (cclouds/tests/ccl_test.h), and the example programs build with the same flags and
free what they allocate on their error paths."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _compiler(name):
    path = shutil.which(name)
    if path is None:
        pytest.skip(f"{name} is not installed (.ci/run installs clang from Debian's packages)")
    return path


def test_library_flags_include_conversion_warnings():
    text = (ROOT / "cclouds" / "CMakeLists.txt").read_text()
    assert "-Wconversion -Wdouble-promotion" in text


@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_library_builds_clean_with_werror(tmp_path, cc):
    path = _compiler(cc)
    if shutil.which("cmake") is None:
        pytest.skip("cmake is not installed")
    env = dict(os.environ, CC=path)
    cfg = subprocess.run(["cmake", "-S", str(ROOT / "cclouds"), "-B", str(tmp_path), "-DCMAKE_BUILD_TYPE=Release",
                          "-DCCLOUDS_WERROR=ON", "-DCCLOUDS_BUILD_TESTS=OFF", "-DCCLOUDS_BUILD_STATIC=OFF",
                          "-DCCLOUDS_INSTALL=OFF"], env=env, capture_output=True, text=True)
    assert cfg.returncode == 0, cfg.stdout + cfg.stderr
    build = subprocess.run(["cmake", "--build", str(tmp_path), "-j2"], env=env, capture_output=True, text=True)
    assert build.returncode == 0, build.stdout[-4000:] + build.stderr[-4000:]
    assert "warning:" not in build.stdout + build.stderr


def test_c_unit_tests_use_the_library_warnings():
    text = (ROOT / "cclouds" / "CMakeLists.txt").read_text()
    loop = text[text.index("foreach(test_src ${CCLOUDS_TEST_SOURCES})"):text.index("endforeach()")]
    assert "${CCLOUDS_LIB_WARNINGS}" in loop


def test_c_unit_tests_define_no_vector_helpers_of_their_own():
    """V(), V2() and len3() live in ccl_test.h; a test file defining its own vector constructor or length copies
    them."""
    own = re.compile(r"^static (?:inline )?(?:ccl_vec[234] \w+\(float \w+(?:, float \w+)*\)"
                     r"|(?:double|float) \w+\(ccl_vec[234] \w+\))", re.M)
    offenders = {p.name: own.findall(p.read_text()) for p in (ROOT / "cclouds" / "tests").glob("test_*.c")}
    assert not {k: v for k, v in offenders.items() if v}


@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_c_unit_tests_build_clean_with_werror_and_pass(tmp_path, cc):
    path = _compiler(cc)
    if shutil.which("cmake") is None:
        pytest.skip("cmake is not installed")
    env = dict(os.environ, CC=path)
    cfg = subprocess.run(["cmake", "-S", str(ROOT / "cclouds"), "-B", str(tmp_path), "-DCMAKE_BUILD_TYPE=Release",
                          "-DCCLOUDS_WERROR=ON", "-DCCLOUDS_BUILD_TESTS=ON", "-DCCLOUDS_BUILD_STATIC=OFF",
                          "-DCCLOUDS_INSTALL=OFF"], env=env, capture_output=True, text=True)
    assert cfg.returncode == 0, cfg.stdout + cfg.stderr
    build = subprocess.run(["cmake", "--build", str(tmp_path), "-j2"], env=env, capture_output=True, text=True)
    assert build.returncode == 0, build.stdout[-4000:] + build.stderr[-4000:]
    assert "warning:" not in build.stdout + build.stderr
    res = subprocess.run(["ctest", "--test-dir", str(tmp_path), "--output-on-failure"], capture_output=True, text=True)
    assert res.returncode == 0 and "100% tests passed" in res.stdout, res.stdout[-4000:]


@pytest.mark.parametrize("cc", ["gcc", "clang"])
@pytest.mark.parametrize("example", ["hello_cclouds.c", "cloudscape_ppm.c"])
def test_examples_build_clean(tmp_path, cc, example):
    path = _compiler(cc)
    res = subprocess.run([path, "-std=c99", "-Wall", "-Wextra", "-pedantic", "-Wconversion", "-Wdouble-promotion",
                          "-Werror", f"-I{ROOT / 'cclouds' / 'include'}", "-c",
                          str(ROOT / "cclouds" / "examples" / example), "-o", str(tmp_path / "x.o")],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr


def test_cloudscape_ppm_error_paths_free_everything(tmp_path):
    """The example under ASan's leak checker: a bad size and an unwritable output both end with nothing leaked."""
    cc = _compiler("gcc")
    lib = os.environ.get("CCLOUDS_LIBRARY")
    if not lib:
        from pywarp.core.binding import _library_path

        lib = str(_library_path())
    exe = tmp_path / "ppm"
    res = subprocess.run([cc, "-std=c99", "-O1", "-g", "-fsanitize=address", f"-I{ROOT / 'cclouds' / 'include'}",
                          str(ROOT / "cclouds" / "examples" / "cloudscape_ppm.c"), lib, "-lm",
                          f"-Wl,-rpath,{Path(lib).parent}", "-o", str(exe)], capture_output=True, text=True)
    if res.returncode != 0:
        pytest.skip(f"cannot build the example with ASan: {res.stderr[-500:]}")
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=1")
    bad = subprocess.run([str(exe), "0", "8"], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert bad.returncode == 2 and "usage" in bad.stderr
    unwritable = subprocess.run([str(exe), "8", "8", str(tmp_path / "no" / "x.ppm")], capture_output=True, text=True,
                                env=env, cwd=tmp_path, timeout=300)
    assert unwritable.returncode == 1, unwritable.stderr
    assert "LeakSanitizer" not in unwritable.stderr, unwritable.stderr
