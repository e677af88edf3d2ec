"""The cffi binding: declarations come from the public headers (never retyped), the library loads, and the scalar
evaluator broadcasts over NumPy arrays."""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from pywarp.core import binding as _cclouds

ROOT = Path(__file__).resolve().parents[2]


def test_every_public_c_function_is_declared_from_the_headers():
    """Each `CCL_API` declaration of every header reaches cffi, and the library exports it."""
    headers = sorted((ROOT / "cclouds" / "include" / "cclouds").glob("*.h"))
    declared = set()
    for h in headers:
        declared |= set(re.findall(r"^CCL_API\s+[^;(]*?\b(ccl_\w+)\s*\(", h.read_text(), flags=re.M))
    assert "ccl_phase_hg" in declared and "ccl_status_str" in declared
    lib = _cclouds.lib()
    for name in declared:
        assert hasattr(lib, name), name


def test_umbrella_header_includes_every_header():
    inc = ROOT / "cclouds" / "include"
    order = [p.name for p in _cclouds.header_order(inc)]
    assert sorted(order) == sorted(p.name for p in (inc / "cclouds").glob("*.h") if p.name != "cclouds.h")
    assert order[0] == "common.h"


def test_cdef_has_no_preprocessor_lines_but_keeps_integer_constants():
    src = _cclouds.cdef_source(ROOT / "cclouds" / "include")
    assert "#include" not in src and "#ifndef" not in src and "extern \"C\"" not in src
    assert "CCL_API" not in src
    assert "#define CCL_VERSION_MAJOR 0" in src
    assert _cclouds.lib().CCL_VERSION_MAJOR * 10000 + _cclouds.lib().CCL_VERSION_MINOR * 100 \
        + _cclouds.lib().CCL_VERSION_PATCH == _cclouds.lib().ccl_version()


def test_status_strings_and_errors():
    ffi, lib = _cclouds.ffi(), _cclouds.lib()
    assert ffi.string(lib.ccl_status_str(lib.CCL_OK)) == b"ok"
    assert ffi.string(lib.ccl_status_str(lib.CCL_EINVAL)) == b"invalid argument"
    assert ffi.string(lib.ccl_status_str(99)) == b"unknown status"
    _cclouds.status_error(lib.CCL_OK, "x")
    with pytest.raises(ValueError, match="^render: invalid argument$"):
        _cclouds.status_error(lib.CCL_EINVAL, "render")
    with pytest.raises(MemoryError, match="^alloc: out of memory$"):
        _cclouds.status_error(lib.CCL_ENOMEM, "alloc")
    with pytest.raises(OSError, match="^write: input/output error$"):
        _cclouds.status_error(lib.CCL_EIO, "write")


def test_vectorize_broadcasts_like_numpy():
    hg = _cclouds.vectorize("ccl_phase_hg")
    mu = np.linspace(-1, 1, 5).reshape(5, 1)
    g = np.array([0.0, 0.5, -0.5])
    out = hg(mu, g)
    assert out.shape == (5, 3) and out.dtype == np.float32
    ref = (1 - g ** 2) / (4 * np.pi * (1 + g ** 2 - 2 * g * mu) ** 1.5)
    np.testing.assert_allclose(out, ref, rtol=1e-6)
    schlick = _cclouds.vectorize("ccl_phase_schlick", extra=(1,))  # variant as a trailing scalar
    assert schlick(1.0, 0.5) == pytest.approx((1 - 0.25) / (4 * np.pi * 1.5 ** 2), rel=1e-6)
