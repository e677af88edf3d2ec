"""The quick subset (``pytest -m smoke``, tests/conftest.py SMOKE) covers every area of the tests and names only
tests that exist."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from conftest import SMOKE

ROOT = Path(__file__).resolve().parents[1]


def test_every_area_has_smoke_tests():
    areas = {p.name for p in (ROOT / "tests").iterdir() if p.is_dir() and any(p.glob("test_*.py"))}
    covered = {entry.split("/")[1] for entry in SMOKE if entry.count("/") >= 2}
    assert areas <= covered, sorted(areas - covered)


def test_every_smoke_entry_names_a_test():
    """Each entry's file exists, and a test named in an entry is collected (a renamed test would drop silently)."""
    for entry in SMOKE:
        path = entry.split("::")[0]
        assert (ROOT / path).exists(), entry
    named = [e for e in SMOKE if "::" in e]
    res = subprocess.run([sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider", *named],
                         cwd=ROOT, capture_output=True, text=True, timeout=300)
    collected = res.stdout.splitlines()
    for e in named:
        assert any(line.startswith(e) for line in collected), (e, res.stdout[-2000:], res.stderr[-2000:])
