"""A full disk while writing: one line saying "disk full" that names the file, exit status 1, nothing left behind.
Needs a small tmpfs (mounting one needs root); skipped where the machine does not allow it."""
from __future__ import annotations

import subprocess
import sys

import pytest


@pytest.fixture
def tiny_disk(tmp_path):
    mnt = tmp_path / "tiny"
    mnt.mkdir()
    res = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=128k", "tmpfs", str(mnt)], capture_output=True)
    if res.returncode != 0:
        pytest.skip("cannot mount a small tmpfs here (needs root): " + res.stderr.decode(errors="replace").strip())
    try:
        yield mnt
    finally:
        subprocess.run(["umount", str(mnt)], capture_output=True)


def test_render_to_a_full_disk_says_disk_full_and_leaves_nothing(tiny_disk, tmp_path):
    out = tiny_disk / "x.npy"  # 256 x 256 x 3 float32 = 768 KiB > 128 KiB
    res = subprocess.run([sys.executable, "-m", "pywarp", "render", "--width", "256", "--height", "256",
                          "--out", str(out), "--no-progress"], capture_output=True, text=True, cwd=tmp_path,
                         timeout=600)
    assert res.returncode == 1, res.stderr
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in res.stderr
    assert lines[0].startswith(f"pywarp render: error: --out: cannot write '{out}': disk full")
    assert list(tiny_disk.iterdir()) == []  # no partial file, no temporary file
