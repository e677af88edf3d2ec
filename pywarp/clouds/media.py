"""The host side of the sampled-ray media entries (vc-2.8, 2.17, 2.18, 2.34; cclouds/media.h): the evaluators the
registry names for them. A call's sample arrays (shape (..., n), broadcast together) and per-ray arguments (broadcast
to (...)) are checked and flattened to one row per ray; Warp marches one ray per thread (the kernel
``_rows_<name>`` of :mod:`pywarp.kernels.media`), C takes the n samples of one ray by pointer. The equations and
kernels are :mod:`pywarp.kernels.media`.
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.registry import Equation
from ..kernels import media as _media


def _bind_rays(eq: Equation, args, kwargs):
    """Validate a call of a sampled-ray entry: (rays shape, 2-D sample arrays, 1-D per-ray arrays, option ints)."""
    sig = eq.signature()
    try:
        bound = sig.bind(*args, **kwargs)
    except TypeError as exc:
        raise TypeError(f"{eq.name}(): {exc}") from None
    bound.apply_defaults()
    n_samples = eq.extra["n_sample_args"]
    sample_args, ray_args = eq.args[:n_samples], eq.args[n_samples:]
    samples = []
    for a in sample_args:
        x = a.check(bound.arguments[a.name])
        if x.ndim < 1:
            raise ValueError(f"{a.name} must be an array of samples along the ray (last axis), got a scalar")
        samples.append(x)
    try:
        shape = np.broadcast_shapes(*(x.shape for x in samples))
    except ValueError:
        shapes = ", ".join(f"{a.name}{tuple(x.shape)}" for a, x in zip(sample_args, samples))
        raise ValueError(f"{eq.name}(): the shapes of the sample arrays do not broadcast: {shapes}") from None
    rays_shape, n = shape[:-1], shape[-1]
    per_ray = []
    for a in ray_args:
        x = a.check(bound.arguments[a.name])
        try:
            x = np.broadcast_to(x, rays_shape)
        except ValueError:
            raise ValueError(f"{eq.name}(): {a.name} of shape {tuple(x.shape)} does not broadcast to the rays shape "
                             f"{tuple(rays_shape)} (the sample arrays without their last axis)") from None
        per_ray.append(x)
    opts = [o.check(bound.arguments[o.name]) for o in eq.options]
    nrays = int(np.prod(rays_shape, dtype=np.int64))
    samples = [np.ascontiguousarray(np.broadcast_to(x, shape).reshape(nrays, n), dtype=np.float32) for x in samples]
    per_ray = [np.ascontiguousarray(x.reshape(nrays), dtype=np.float32) for x in per_ray]
    if eq.check is not None:
        eq.check(n=n, **{a.name: x for a, x in zip(sample_args, samples)},
                 **{a.name: x for a, x in zip(ray_args, per_ray)})
    return rays_shape, samples, per_ray, opts


def _finish(rays_shape, out):
    out = np.asarray(out, dtype=np.float32).reshape(rays_shape)
    return out[()] if rays_shape == () else out


def rows_warp(eq: Equation, device=None):
    """The Warp evaluator of a sampled-ray entry: one thread marches one ray over its whole sample axis."""
    from ..core.runtime import resolve_device

    dev = resolve_device(device)

    def call(*args, **kwargs):
        rays_shape, samples, per_ray, opts = _bind_rays(eq, args, kwargs)
        nrays = samples[0].shape[0]
        out = np.empty(nrays, dtype=np.float32)
        if nrays:
            ins = [wp.array(x, dtype=float, device=dev) for x in samples]
            ins += [wp.array(x, dtype=float, device=dev) for x in per_ray]
            res = wp.empty(nrays, dtype=float, device=dev)
            wp.launch(getattr(_media, f"_rows_{eq.name}"), dim=nrays, inputs=[*ins, *opts], outputs=[res], device=dev)
            out = res.numpy()
        return _finish(rays_shape, out)

    call.__signature__ = eq.signature()
    return call


def rows_c(eq: Equation):
    """The C evaluator of a sampled-ray entry: the C function takes pointers to the n samples of one ray."""
    from ..core.binding import ffi, lib, status_error

    f, lb = ffi(), lib()
    fn = getattr(lb, eq.c_symbol)

    def call(*args, **kwargs):
        rays_shape, samples, per_ray, opts = _bind_rays(eq, args, kwargs)
        nrays, n = samples[0].shape
        out = np.empty(nrays, dtype=np.float32)
        res = f.new("float *")
        for r in range(nrays):
            ptrs = [f.cast("const float *", f.from_buffer("float[]", x[r])) if n else f.NULL for x in samples]
            status = fn(*ptrs, n, *(float(x[r]) for x in per_ray), *opts, res)
            status_error(status, f"{eq.c_symbol} (ray {r})")
            out[r] = res[0]
        return _finish(rays_shape, out)

    call.__signature__ = eq.signature()
    return call
