"""The C core on its own, as a C user gets it: CMake configure/build with warnings as errors, ctest, the same under
AddressSanitizer + UndefinedBehaviorSanitizer, install, and a C program built against the installed package config.

These tests need CMake and a C compiler (the README's prerequisites); they build into pytest's temporary directory.
"""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "cclouds"

pytestmark = pytest.mark.skipif(shutil.which("cmake") is None, reason="CMake is not installed")


def run(cmd, **kw):
    res = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    assert res.returncode == 0, f"{' '.join(map(str, cmd))} failed:\n{res.stdout[-4000:]}\n{res.stderr[-4000:]}"
    return res


def jobs():
    return str(max(1, os.cpu_count() or 1))


@pytest.fixture(scope="module")
def release_build(tmp_path_factory):
    build = tmp_path_factory.mktemp("cclouds-build")
    run(["cmake", "-S", SRC, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DCCLOUDS_WERROR=ON"])
    run(["cmake", "--build", build, "--parallel", jobs()])
    return build


def test_c_library_builds_warning_free_and_ctest_passes(release_build):
    res = run(["ctest", "--test-dir", release_build, "--output-on-failure"])
    assert "100% tests passed" in res.stdout
    # one ctest test per cclouds/tests/test_*.c: nothing silently left out
    n_sources = len(list((SRC / "tests").glob("test_*.c")))
    assert f"out of {n_sources}" in res.stdout


def test_c_tests_pass_under_address_and_undefined_sanitizers(tmp_path):
    build = tmp_path / "asan"
    run(["cmake", "-S", SRC, "-B", build, "-DCMAKE_BUILD_TYPE=Debug", "-DCCLOUDS_SANITIZE=ON", "-DCCLOUDS_WERROR=ON",
         "-DCCLOUDS_BUILD_STATIC=OFF"])
    run(["cmake", "--build", build, "--parallel", jobs()])
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=1:abort_on_error=1", UBSAN_OPTIONS="halt_on_error=1")
    res = run(["ctest", "--test-dir", build, "--output-on-failure"], env=env)
    assert "100% tests passed" in res.stdout


def _version() -> str:
    import tomllib

    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]


@pytest.fixture(scope="module")
def installed(release_build, tmp_path_factory):
    """``cmake --install`` of the release build into a fresh prefix, as the README's C route does."""
    prefix = tmp_path_factory.mktemp("prefix")
    run(["cmake", "--install", release_build, "--prefix", prefix])
    libdir = next(p for p in (prefix / "lib", prefix / "lib64") if p.is_dir())
    return prefix, libdir


def test_installed_package_config_builds_a_c_program(installed, tmp_path):
    prefix, libdir = installed
    headers = sorted(p.name for p in (prefix / "include" / "cclouds").glob("*.h"))
    assert headers == sorted(p.name for p in (SRC / "include" / "cclouds").glob("*.h"))
    assert (libdir / "cmake" / "cclouds" / "ccloudsConfig.cmake").is_file()
    example = tmp_path / "example"
    # the README's command: the prefix given as CMAKE_PREFIX_PATH; the executables find the shared library through
    # the RPATH CMake sets in the build tree (no LD_LIBRARY_PATH)
    run(["cmake", "-S", SRC / "examples", "-B", example, f"-DCMAKE_PREFIX_PATH={prefix}"])
    run(["cmake", "--build", example])
    env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
    res = run([example / "hello_cclouds"], env=env)
    assert res.stdout.startswith(f"cclouds {_version()}: HG(cos=1, g=0.8) = 3.58")
    # the cloudscape with the C library alone: a small PPM with sky and clouds
    ppm = tmp_path / "c.ppm"
    run([example / "cloudscape_ppm", "48", "27", ppm], env=env)
    data = ppm.read_bytes()
    header = b"P6\n48 27\n255\n"
    assert data.startswith(header) and len(data) == len(header) + 48 * 27 * 3
    pixels = data[len(header):]
    assert len(set(pixels)) > 20  # not a flat image


def _cc() -> str:
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if cc is None:
        pytest.skip("no C compiler")
    return cc


def test_installed_library_builds_with_a_plain_compiler_line(installed, tmp_path):
    """The README's one-line build: include and library folders, the run-time path (-Wl,-rpath), -lcclouds -lm."""
    prefix, libdir = installed
    exe = tmp_path / "hello"
    run([_cc(), SRC / "examples" / "hello_cclouds.c", f"-I{prefix / 'include'}", f"-L{libdir}",
         f"-Wl,-rpath,{libdir}", "-lcclouds", "-lm", "-o", exe])
    env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
    assert run([exe], env=env).stdout.startswith(f"cclouds {_version()}: ")


@pytest.mark.skipif(shutil.which("pkg-config") is None, reason="pkg-config is not installed")
def test_installed_pkg_config_file_builds_a_c_program(installed, tmp_path):
    """cclouds.pc: relocatable (its prefix follows the folder it lies in), with the package's version."""
    prefix, libdir = installed
    env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
    env["PKG_CONFIG_PATH"] = str(libdir / "pkgconfig")
    assert run(["pkg-config", "--modversion", "cclouds"], env=env).stdout.strip() == _version()
    flags = run(["pkg-config", "--cflags", "--libs", "cclouds"], env=env).stdout.split()
    found = Path(run(["pkg-config", "--variable=libdir", "cclouds"], env=env).stdout.strip())
    assert found.resolve() == libdir.resolve()
    exe = tmp_path / "hello"
    run([_cc(), SRC / "examples" / "hello_cclouds.c", *flags, f"-Wl,-rpath,{found}", "-o", exe], env=env)
    assert run([exe], env=env).stdout.startswith(f"cclouds {_version()}: ")


@pytest.mark.skipif(shutil.which("c++") is None and shutil.which("g++") is None, reason="no C++ compiler")
def test_public_headers_compile_as_cpp(tmp_path):
    """The headers carry extern "C" guards: a C++ translation unit can include the umbrella header."""
    cxx = shutil.which("c++") or shutil.which("g++")
    src = tmp_path / "use.cpp"
    src.write_text('#include <cclouds/cclouds.h>\nint main() { return ccl_version() > 0 ? 0 : 1; }\n')
    run([cxx, "-std=c++11", "-Wall", "-Wextra", "-Werror", "-I", SRC / "include", "-c", src, "-o", tmp_path / "use.o"])
