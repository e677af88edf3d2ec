"""Load the cclouds C library with cffi (ABI mode).

The declarations are read from the public C headers installed next to the library (``pywarp/include/cclouds``) --
never retyped here. The headers keep to a plain C subset (see ``cclouds/common.h``); this module strips the
preprocessor lines and the ``extern "C"`` guards and hands the rest to ``cffi.FFI.cdef``.

Environment variables (for working on the C core without reinstalling):
    CCLOUDS_LIBRARY       path of a libcclouds shared library to load instead of the packaged one
    CCLOUDS_INCLUDE_DIR   directory holding ``cclouds/*.h`` to read instead of the packaged headers
"""
from __future__ import annotations

import glob
import os
import re
import sys
from functools import lru_cache
from pathlib import Path

import numpy as np

_PKG = Path(__file__).resolve().parents[1]  # the pywarp package folder

_DEFINE_INT = re.compile(r"^\s*#\s*define\s+(CCL_[A-Z0-9_]+)\s+(-?\d+)\s*$")


def _include_dir() -> Path:
    env = os.environ.get("CCLOUDS_INCLUDE_DIR")
    if env:
        return Path(env)
    packaged = _PKG / "include"
    if (packaged / "cclouds" / "cclouds.h").is_file():
        return packaged
    source = _PKG.parent / "cclouds" / "include"  # running from a source checkout with CCLOUDS_LIBRARY set
    return source


def _library_path() -> Path:
    env = os.environ.get("CCLOUDS_LIBRARY")
    if env:
        return Path(env)
    patterns = {"win32": "cclouds.dll", "darwin": "libcclouds*.dylib"}.get(sys.platform, "libcclouds.so*")
    found = sorted(glob.glob(str(_PKG / patterns)), key=len)
    if not found:
        raise ImportError(
            f"the cclouds shared library was not found in {_PKG}; install the package with `pip install .` "
            "(it builds the C core with CMake) or set CCLOUDS_LIBRARY to a built libcclouds")
    return Path(found[0])


def header_order(include_dir: Path) -> list[Path]:
    """Public headers in the order the umbrella header ``cclouds/cclouds.h`` includes them."""
    umbrella = (include_dir / "cclouds" / "cclouds.h").read_text()
    names = re.findall(r'#\s*include\s+"cclouds/([a-z0-9_]+\.h)"', umbrella)
    return [include_dir / "cclouds" / n for n in names]


def cdef_source(include_dir: Path | None = None) -> str:
    """The declarations of every public header, cleaned for ``cffi.FFI.cdef``."""
    include_dir = include_dir or _include_dir()
    parts = []
    for path in header_order(include_dir):
        text = path.read_text()
        text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)  # comments (cffi would accept them; keep the cdef lean)
        text = re.sub(r"//[^\n]*", "", text)
        text = re.sub(r"#ifdef __cplusplus.*?#endif", "", text, flags=re.S)
        lines = []
        depth = 0  # skip the bodies of #if blocks other than the include guard (e.g. the CCL_API definition)
        for line in text.splitlines():
            stripped = line.strip()
            if stripped.startswith("#"):
                m = _DEFINE_INT.match(line)
                if re.match(r"#\s*if(?!ndef CCLOUDS_)", stripped):
                    depth += 1
                elif re.match(r"#\s*endif", stripped) and depth:
                    depth -= 1
                elif m and not depth:
                    lines.append(f"#define {m.group(1)} {m.group(2)}")
                continue
            if depth:
                continue
            lines.append(line.replace("CCL_API ", ""))
        parts.append(f"/* {path.name} */\n" + "\n".join(lines))
    return "\n".join(parts)


@lru_cache(maxsize=None)
def _load():
    import cffi

    ffi = cffi.FFI()
    ffi.cdef(cdef_source())
    lib = ffi.dlopen(str(_library_path()))
    return ffi, lib


def ffi():
    """The cffi ``FFI`` object holding every declaration of the public headers."""
    return _load()[0]


def lib():
    """The loaded cclouds library; attributes are the C functions (``lib.ccl_phase_hg``)."""
    return _load()[1]


def status_error(status: int, what: str) -> None:
    """Raise ``ValueError``/``MemoryError``/``OSError`` for a non-OK ``ccl_status``."""
    if status == 0:
        return
    f, lb = _load()
    msg = f"{what}: {f.string(lb.ccl_status_str(status)).decode()}"
    if status == lb.CCL_ENOMEM:
        raise MemoryError(msg)
    if status == lb.CCL_EIO:
        raise OSError(msg)
    raise ValueError(msg)


def vectorize(symbol: str, n_out: int = 1, out_pointers: bool | None = None, extra: tuple = ()):
    """Evaluate the scalar C function ``symbol`` over NumPy arrays with broadcasting.

    Positional array arguments are broadcast together; ``extra`` holds trailing scalar arguments passed unchanged to
    every call (a variant, a seed). A function with ``n_out > 1`` writes its results through trailing out-pointers;
    the call returns a tuple of float32 arrays of the broadcast shape (a single array when ``n_out == 1``).
    """
    f, lb = _load()
    fn = getattr(lb, symbol)
    if out_pointers is None:
        out_pointers = n_out > 1

    def call(*arrays):
        arrays = [np.asarray(a) for a in arrays]
        shape = np.broadcast_shapes(*(a.shape for a in arrays)) if arrays else ()
        flat = [np.broadcast_to(a, shape).ravel() for a in arrays]
        outs = [np.empty(int(np.prod(shape)), dtype=np.float32) for _ in range(n_out)]
        if out_pointers:
            ptrs = [f.new("float *") for _ in range(n_out)]
            for i in range(outs[0].size):
                fn(*(v[i].item() for v in flat), *extra, *ptrs)
                for o, p in zip(outs, ptrs):
                    o[i] = p[0]
        else:
            o = outs[0]
            for i in range(o.size):
                o[i] = fn(*(v[i].item() for v in flat), *extra)
        res = tuple(o.reshape(shape) for o in outs)
        return res[0] if n_out == 1 else res

    call.__name__ = symbol
    return call
