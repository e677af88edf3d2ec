"""Warp twins of the cclouds C headers: ``pywarp/kernels/<topic>.py`` mirrors ``cclouds/include/cclouds/<topic>.h``.

Each topic module defines ``@wp.func`` functions with the C names minus the ``ccl_`` prefix (usable from your own
kernels), each declared once with its catalogue ID(s) by ``@declare`` (``pywarp.core.registry``), which generates
the element-wise evaluation kernel.
Every topic module is one Warp module, compiled once and cached on disk.
"""
from __future__ import annotations

import importlib

from ..core.cbridge import c_constant
from ..core.runtime import init as _init

_init()

#: ``ccl_variant`` (common.h): the formula of the original source, or as printed in the text
VARIANT_CORRECTED = c_constant("CCL_VARIANT_CORRECTED", 0)
VARIANT_THESIS = c_constant("CCL_VARIANT_THESIS", 1)

#: Topic modules, in the order of the C umbrella header ``cclouds/cclouds.h`` (``common.h`` aside: its types are
#: Warp's own; ``common.py`` holds the helpers of ``src/internal.h``). tests/core/test_binding.py pins the list to
#: the header.
TOPICS = ("camera", "phase", "media", "hash", "interp", "noise", "texgen", "clouds", "raymarch", "colour", "sky",
          "reproj", "cloudscape", "optics", "rain", "draw", "fractal", "sdf", "terrain", "valuenoise", "voxel",
          "particles", "flight", "volume")


def load_all() -> None:
    """Import every topic module (each registers its catalogue entries on import)."""
    for t in TOPICS:
        importlib.import_module(f"{__name__}.{t}")
