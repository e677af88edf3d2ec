"""Warp twins of the cclouds C headers: ``pywarp/kernels/<topic>.py`` mirrors ``cclouds/include/cclouds/<topic>.h``.

Each topic module defines ``@wp.func`` functions with the C names minus the ``ccl_`` prefix (usable from your own
kernels), one element-wise ``@wp.kernel`` per function for NumPy evaluation, and registers its catalogue entries.
Every topic module is one Warp module, compiled once and cached on disk.
"""
from __future__ import annotations

import importlib

from ..core.runtime import init as _init

_init()

#: Topic modules, in the order of the C umbrella header.
TOPICS = ("camera", "phase", "media", "hash", "interp", "noise", "texgen", "clouds",
          "raymarch", "colour", "sky", "reproj", "cloudscape")


def load_all() -> None:
    """Import every topic module (each registers its catalogue entries on import)."""
    for t in TOPICS:
        importlib.import_module(f"{__name__}.{t}")
