"""The host side of the noise and interp topics (cclouds/noise.h, cclouds/interp.h): NumPy evaluators of the two
helpers without a catalogue ID of their own that the thesis' figures plot -- :func:`perlin2`, 2-D Perlin noise with
a choice of interpolant (vc-fig-2.5), and :func:`interpolants`, the four interpolation curves (vc-fig-2.6) -- by the
Warp kernels or the C functions. The equations and the kernels are :mod:`pywarp.kernels.noise` and
:mod:`pywarp.kernels.interp`.
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.binding import vectorize
from ..core.registry import equation
from ..core.runtime import resolve_device
from ..kernels import interp as IP
from ..kernels import noise as N


def perlin2(x, y, seed: int = 0, period: int = 0, interp: str = "quintic", impl: str = "warp", device=None):
    """2-D Perlin noise (vc-A1) on NumPy arrays: ``noise_perlin3(x, y, 0)`` for ``interp="quintic"``; ``"cubic"``
    (2.19), ``"linear"`` and ``"cosine"`` replace the fade for the interpolation comparison of vc-fig-2.5.
    ``impl="c"`` evaluates ``ccl_noise_perlin2``."""
    if interp not in N.INTERP:
        raise ValueError(f"interp must be one of {', '.join(map(repr, N.INTERP))}, got {interp!r}")
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    seed = N._check_seed(seed)
    xa, ya = N._X.check(x, "x"), N._Y.check(y, "y")
    per = N._PERIOD.check(period, "period")
    if per.ndim:
        raise ValueError(f"period must be a scalar, got shape {per.shape}")
    shape = np.broadcast_shapes(xa.shape, ya.shape)
    xf = np.ascontiguousarray(np.broadcast_to(xa, shape).ravel())
    yf = np.ascontiguousarray(np.broadcast_to(ya, shape).ravel())
    if impl == "c":
        out = vectorize("ccl_noise_perlin2", extra=(seed, int(per), N.INTERP[interp]))(xf, yf)
    else:
        dev = resolve_device(device)
        n = xf.size
        res = wp.empty(n, dtype=wp.float32, device=dev)
        if n:
            wp.launch(N._perlin2_kernel, dim=n,
                      inputs=[wp.array(xf, device=dev), wp.array(yf, device=dev), int(per), N.INTERP[interp],
                              N.perm_array(seed, dev)], outputs=[res], device=dev)
        out = res.numpy()
    out = np.asarray(out, dtype=np.float32).reshape(shape)
    return out[()] if shape == () else out


def interpolants(t, impl: str = "warp"):
    """The four interpolation curves of vc-fig-2.6 on ``t`` in [0, 1]: dict of 'linear' (t, via
    interp_lerp(t, 0, 1)), 'cosine' ((1 - cos pi t)/2, via interp_cosine(t, 0, 1)), 'cubic' (2.19) and
    'quintic' (2.20). ``impl="c"`` evaluates the C functions."""
    ta = IP._T.check(t, "t")
    if impl == "c":
        lin = vectorize("ccl_interp_lerp")(ta, np.float32(0), np.float32(1))
        cos = vectorize("ccl_interp_cosine")(ta, np.float32(0), np.float32(1))
    elif impl == "warp":
        dev = resolve_device(None)
        flat = np.ascontiguousarray(ta.ravel())
        lin_w = wp.empty(flat.size, dtype=wp.float32, device=dev)
        cos_w = wp.empty(flat.size, dtype=wp.float32, device=dev)
        if flat.size:
            wp.launch(IP._lerp_cosine_curves, dim=flat.size, inputs=[wp.array(flat, device=dev)],
                      outputs=[lin_w, cos_w], device=dev)
        lin, cos = lin_w.numpy().reshape(ta.shape), cos_w.numpy().reshape(ta.shape)
    else:
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return {"linear": np.asarray(lin, np.float32), "cosine": np.asarray(cos, np.float32),
            "cubic": np.asarray(equation("vc-2.19", impl=impl)(ta)),
            "quintic": np.asarray(equation("vc-2.20", impl=impl)(ta))}
