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
