"""Shared fixtures. The package under test is the installed one (``pip install .``); ``--import-mode=importlib`` keeps
the source folder ``pywarp/`` (which has no compiled library) off ``sys.path``."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]

# `python -m pywarp` in a subprocess must run the installed package, not the source folder it would find first when
# the working directory is the checkout (Python >= 3.11: no current directory on sys.path).
os.environ.setdefault("PYTHONSAFEPATH", "1")



#: The quick subset, ``pytest -m smoke``: one or more fast test files (or tests) of every area -- the C core's names
#: and a C program against the installed library, the registry and its generated contract tests, every kernel topic,
#: the four scenes (C = Warp pixels), the command line, the viewer's controls, the hardening findings, two
#: tutorials, the notebooks and the lint. About a minute on 2 cores with a warm Warp kernel cache (a cold one adds
#: the first compile of each kernel module, 1-2 minutes). ``tests/test_smoke.py`` checks that every area is here.
SMOKE = (
    "tests/c/test_naming.py",
    "tests/c/test_c_core.py::test_installed_library_builds_with_a_plain_compiler_line",
    "tests/cli/test_cli.py",
    "tests/cli/test_cache.py",
    "tests/clouds/test_settings.py",
    "tests/clouds/test_accumulate.py",
    "tests/core/",
    "tests/docs/test_notebooks.py",
    "tests/flight/",
    "tests/hardening/test_fuzz_findings.py",
    "tests/kernels/",
    "tests/rain/",
    "tests/terrain/",
    "tests/tutorials/test_tutorial_helpers.py",
    "tests/tutorials/test_tutorials.py::test_tutorial_runs_in_quick_mode[fig_2_15_height_gradients]",
    "tests/tutorials/test_tutorials.py::test_tutorial_runs_in_quick_mode[fig_7_03_04_shadows]",
    "tests/viewer/test_controls.py",
    "tests/viewer/test_scene_controls.py",
    "tests/test_lint.py",
    "tests/test_smoke.py",
)


def pytest_collection_modifyitems(config, items):
    for item in items:
        if item.nodeid.startswith(SMOKE):
            item.add_marker(pytest.mark.smoke)


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture
def rng():
    """A seeded generator: every randomized test draws the same inputs on every run."""
    return np.random.default_rng(20201)


def pytest_configure(config):
    import pywarp

    if Path(pywarp.__file__).resolve().parent == ROOT / "pywarp" and not os.environ.get("CCLOUDS_LIBRARY"):
        raise pytest.UsageError(
            "pywarp was imported from the source folder, which has no compiled C library: install the package "
            "(pip install '.[test]') and run `pytest` (not `python -m pytest`, which puts the source folder first), or set CCLOUDS_LIBRARY to a built "
            "libcclouds.so to test the source tree")
    # PYWARP_TEST_DEVICE (default cpu): the Warp device of the equation evaluators that name none (the C/Warp
    # agreement tests; tools/gpu_check.sh runs them with cuda:0); refused at once where that device does not exist
    device = os.environ.get("PYWARP_TEST_DEVICE")
    if device and device != "cpu":
        from pywarp.core import runtime

        try:
            runtime.DEFAULT_DEVICE = runtime.resolve_device(device)
        except ValueError as exc:
            raise pytest.UsageError(f"PYWARP_TEST_DEVICE: {exc}") from None
