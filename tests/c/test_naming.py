"""Names of the C API: every public function is ``ccl_<header>_<name>`` after the header that declares it, and the
shared library exports exactly the declared functions (no helper leaks out of a .c file)."""
from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
INCLUDE = ROOT / "cclouds" / "include" / "cclouds"

#: Public functions whose names do not start with their header's name, and why.
ALLOWED = {
    # common.h: library-wide services, not a topic
    "ccl_status_str": "common.h",
    "ccl_version": "common.h",
}
#: common.h's vector maths is named after its type (ccl_vec3_dot), like the type it works on.
ALLOWED_PREFIXES = {"common.h": ("ccl_vec2_", "ccl_vec3_")}

_DECL = re.compile(r"CCL_API\s+[^;{]*?\b(ccl_[A-Za-z0-9_]+)\s*\(", re.S)


def declared() -> dict[str, str]:
    """Public function name -> header file name, from the ``CCL_API`` declarations of every public header."""
    out = {}
    for h in sorted(INCLUDE.glob("*.h")):
        text = re.sub(r"/\*.*?\*/", "", h.read_text(), flags=re.S)
        for m in _DECL.finditer(text):
            out[m.group(1)] = h.name
    return out


def test_declarations_are_found():
    names = declared()
    # the parser above must see the declarations it checks: a few known ones of different shapes
    assert names["ccl_phase_hg"] == "phase.h"
    assert names["ccl_status_str"] == "common.h"
    assert len(names) > 100


def test_every_public_c_function_is_named_after_its_header():
    bad = []
    for name, header in declared().items():
        topic = header[:-2]
        if name.startswith(f"ccl_{topic}_") or ALLOWED.get(name) == header:
            continue
        if name.startswith(ALLOWED_PREFIXES.get(header, ())):
            continue
        bad.append(f"{name} (in {header}: expected ccl_{topic}_...)")
    assert not bad, "public C functions not named ccl_<header>_<name>:\n" + "\n".join(sorted(bad))


def test_allow_list_is_short_and_current():
    names = declared()
    stale = [n for n, h in ALLOWED.items() if names.get(n) != h]
    assert not stale, f"allow-listed names no longer declared where listed: {stale}"
    assert len(ALLOWED) <= 5


@pytest.mark.skipif(shutil.which("nm") is None, reason="nm (binutils) is not installed")
def test_shared_library_exports_only_declared_functions():
    from pywarp.core.binding import _library_path

    lib = _library_path()
    res = subprocess.run(["nm", "-D", "--defined-only", str(lib)], capture_output=True, text=True, check=True)
    exported = {line.split()[-1] for line in res.stdout.splitlines() if " T " in line}
    names = set(declared())
    assert exported, f"nm found no exported functions in {lib}"
    assert exported - names == set(), f"exported but not declared in a public header: {sorted(exported - names)}"
    assert names - exported == set(), f"declared but not exported: {sorted(names - exported)}"
