"""tools/gpu_check.sh where no CUDA device exists: it says so and exits 2 before any work (it is run by hand where a
GPU is at hand; its numbers go in the docs). PYWARP_TEST_DEVICE sets the device of the evaluators that name none."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_gpu_check_refuses_a_missing_device(tmp_path):
    import warp as wp

    wp.init()
    if any(d.alias.startswith("cuda") for d in wp.get_devices()):
        pytest.skip("a CUDA device is present: the check would run")
    out = tmp_path / "gpu.json"
    r = subprocess.run(["bash", str(ROOT / "tools" / "gpu_check.sh"), str(out)], capture_output=True, text=True,
                       env={**os.environ, "PYTHON": sys.executable}, timeout=300)
    assert r.returncode == 2 and "no CUDA device cuda:0 here" in r.stderr and not out.exists()


def test_default_device_is_what_resolve_device_gives(monkeypatch):
    from pywarp.core import runtime

    assert runtime.resolve_device(None) == runtime.DEFAULT_DEVICE == os.environ.get("PYWARP_TEST_DEVICE", "cpu")
    monkeypatch.setattr(runtime, "DEFAULT_DEVICE", "cuda:7")
    with pytest.raises(ValueError, match="cuda:7"):
        runtime.resolve_device(None)
