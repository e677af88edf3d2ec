"""pywarp -- the equations of procedural atmospheric rendering as NVIDIA Warp kernels, with a C99 twin (cclouds).

Every catalogued equation is reachable by its ID, ``pywarp.equation("vc-2.13")``, or by its name,
``pywarp.phase_hg(cos_theta, g)``; both evaluate the Warp twin on NumPy arrays (CPU by default).
``pywarp.equation("vc-2.13", impl="c")`` evaluates the C function of the cclouds library instead.
"""
from __future__ import annotations

import pkgutil
from importlib.metadata import PackageNotFoundError, version as _version

from .core.registry import equation, missing, registry

try:
    __version__ = _version("cclouds")
except PackageNotFoundError:  # running from a source tree
    __version__ = "0.0.0+source"

#: The package's modules and subpackages (``core``, ``kernels``, the scene packages, ...): never catalogue names, so
#: ``pywarp.<submodule>`` before its import fails at once instead of importing every topic module to look it up.
_SUBMODULES = frozenset(m.name for m in pkgutil.iter_modules(__path__))

__all__ = ["equation", "registry", "missing", "__version__"]


#: Public helpers that are not catalogue entries: name -> (module, attribute).
_HELPERS = {
    "camera_look_at": ("pywarp.kernels.camera", "camera_look_at"),  # vc-A25 / pt-code-7.2 camera matrices
    "sun_direction": ("pywarp.kernels.sky", "sun_direction"),  # unit sun vector from elevation/azimuth
    "perlin2": ("pywarp.clouds.noise", "perlin2"),  # 2-D Perlin noise with a choice of interpolant (fig 2.5)
    "interpolants": ("pywarp.clouds.noise", "interpolants"),  # linear/cosine/cubic/quintic curves (fig 2.6)
}


def __getattr__(name: str):
    """``pywarp.<name>`` for every registered function, evaluated with Warp (lazily: imports the kernels)."""
    if name.startswith("_") or name in _SUBMODULES:
        raise AttributeError(f"module 'pywarp' has no attribute {name!r}")
    if name in _HELPERS:
        import importlib

        mod, attr = _HELPERS[name]
        value = getattr(importlib.import_module(mod), attr)
        globals()[name] = value
        return value
    for eq in registry().values():
        if eq.name == name:
            fn = equation(eq.id)
            globals()[name] = fn
            return fn
    raise AttributeError(f"module 'pywarp' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_HELPERS) | {eq.name for eq in registry().values()})
