"""The host side of the sky topic (cclouds/sky.h) and of the colour topic's display step: the per-frame structs of
the two sky models -- validated, then computed by the same float32 Warp code as the kernels (:func:`preetham_params`
for vc-A29, :func:`gradient_params` for vc-A28) --, the sun's air mass and transmittance on NumPy arrays
(:func:`sun_attenuation`, Preetham et al. 1999 appendix A.1) and the sRGB encoding of the frame buffer on NumPy arrays
(:func:`srgb_encode_array`). The equations and the kernels are :mod:`pywarp.kernels.sky` and
:mod:`pywarp.kernels.colour`; the unit sun vector of the scenes' settings stays with the equations
(:func:`pywarp.kernels.sky.sun_direction`).
"""
from __future__ import annotations

import numpy as np
import warp as wp

from ..core.binding import lib
from ..core.registry import VARIANT, Arg
from ..core.runtime import resolve_device
from ..kernels import sky as S
from ..kernels import colour as C
from ..kernels.colour import TONEMAP_EXPOSURE


def _colour(name: str, value) -> tuple[float, float, float]:
    a = np.asarray(value, dtype=np.float64) if not isinstance(value, (str, bytes)) else None
    if a is None or a.shape != (3,):
        raise ValueError(f"{name} must be an RGB triple, got {value!r}")
    if not np.all((a >= 0) & (a <= S.GRADIENT_MAX_COLOUR)):
        raise ValueError(f"{name} must hold values in [0, 1e6] (linear RGB, CCL_SKY_GRADIENT_MAX_COLOUR), "
                         f"got {tuple(a.tolist())}")
    return tuple(float(np.float32(v)) for v in a)


def _struct_from_numpy(cls, rec):
    s = cls()
    for name, (dtype, _) in rec.dtype.fields.items():
        v = rec[name]
        cur = getattr(s, name)
        setattr(s, name, type(cur)(*v.tolist()) if hasattr(cur, "__len__") else type(cur)(v.item()))
    return s


def preetham_params(turbidity, theta_s, exposure=TONEMAP_EXPOSURE, variant="corrected",
                    device: str | None = None) -> S.Preetham:
    """Validated per-frame constants of the Preetham sky (vc-A29) as a Warp struct for
    :func:`pywarp.kernels.sky.sky_preetham_rgb`.

    ``turbidity`` in [2, 10]; ``theta_s`` (sun zenith angle, rad) in [0, pi/2] -- a sun below the horizon is invalid
    for the Preetham model; ``exposure`` > 0; ``variant`` 'corrected' or 'thesis' (applies to vc-2.39, 4.4 and 4.5).
    The fields are computed by the Warp twin ``sky_preetham_init`` (float32, the same operations as
    ``ccl_sky_preetham_init``).
    """
    T = S._scalar(S._TURBIDITY, turbidity)
    ts = S._scalar(S._THETA_S, theta_s)
    k = S._scalar(S._EXPOSURE, exposure)
    v = VARIANT.check(variant)
    dev = resolve_device(device)
    out = wp.empty(1, dtype=S.Preetham, device=dev)
    wp.launch(S._k_preetham_init, dim=1, inputs=[T, ts, k, v], outputs=[out], device=dev)
    return _struct_from_numpy(S.Preetham, out.numpy()[0])


def gradient_params(horizon_colour=S.GRADIENT_DEFAULTS["horizon_colour"],
                    zenith_colour=S.GRADIENT_DEFAULTS["zenith_colour"], sun_colour=S.GRADIENT_DEFAULTS["sun_colour"],
                    sun_exponent=S.GRADIENT_DEFAULTS["sun_exponent"]) -> S.SkyGradient:
    """Validated per-frame constants of the gradient sky (vc-A28) as a Warp struct for
    :func:`pywarp.kernels.sky.sky_gradient_rgb`."""
    g = S.SkyGradient()
    g.horizon = wp.vec3(*_colour("horizon_colour", horizon_colour))
    g.zenith = wp.vec3(*_colour("zenith_colour", zenith_colour))
    g.sun = wp.vec3(*_colour("sun_colour", sun_colour))
    g.sun_exponent = S._scalar(Arg("sun_exponent", lo=0.0, lo_open=True), sun_exponent)
    return g


def sun_attenuation(theta_s, turbidity, impl: str = "warp", device: str | None = None):
    """(relative air mass m, transmittance RGB) towards a sun at zenith angle ``theta_s`` [rad, 0 .. pi/2] through an
    atmosphere of ``turbidity`` [2, 10]: NumPy arrays of the broadcast shape, float32, and shape + (3,) for the
    transmittance. ``impl``: 'warp' (:func:`pywarp.kernels.sky.sky_sun_attenuation`) or 'c'
    (``ccl_sky_sun_attenuation``)."""
    ts = S._THETA_S.check(theta_s)
    T = S._TURBIDITY.check(turbidity)
    ts, T = np.broadcast_arrays(np.asarray(ts, dtype=np.float32), np.asarray(T, dtype=np.float32))
    shape = ts.shape
    ts, T = ts.ravel(), T.ravel()
    if impl == "c":
        L = lib()
        m = np.array([L.ccl_sky_relative_air_mass(float(a)) for a in ts], dtype=np.float32)
        t = np.array([[v.x, v.y, v.z] for v in (L.ccl_sky_sun_attenuation(float(a), float(b)) for a, b in zip(ts, T))],
                     dtype=np.float32).reshape(-1, 3)
        return m.reshape(shape), t.reshape(shape + (3,))
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    dev = resolve_device(device)
    n = max(ts.size, 1)
    om = wp.empty(n, dtype=float, device=dev)
    ot = wp.empty(n, dtype=wp.vec3, device=dev)
    if ts.size:
        wp.launch(S._k_sun_attenuation, dim=ts.size, inputs=[wp.array(ts, dtype=float, device=dev),
                                                             wp.array(T, dtype=float, device=dev)],
                  outputs=[om, ot], device=dev)
    return om.numpy()[:ts.size].reshape(shape), ot.numpy()[:ts.size].reshape(shape + (3,))


_SRGB_ARG = Arg("c", "linear channel value")


def srgb_encode_array(c, impl: str = "warp", device: str | None = None) -> np.ndarray:
    """Element-wise sRGB encoding (IEC 61966-2-1) of a NumPy array -- the display step of the vc-A29 chain, which has
    no catalogue ID of its own. ``impl="c"`` evaluates ``ccl_colour_srgb_encode``. ``c`` must be finite."""
    a = _SRGB_ARG.check(c)
    flat = np.ascontiguousarray(a.reshape(-1))
    if impl == "c":
        enc = lib().ccl_colour_srgb_encode
        out = np.array([enc(v) for v in flat.tolist()], dtype=np.float32)
    elif impl == "warp":
        dev = resolve_device(device)
        out = np.empty(flat.shape, np.float32)
        if flat.size:
            res = wp.empty(flat.size, dtype=float, device=dev)
            wp.launch(C._srgb_encode_kernel, dim=flat.size, inputs=[wp.array(flat, dtype=float, device=dev)],
                      outputs=[res], device=dev)
            out = res.numpy()
    else:
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    out = out.reshape(a.shape)
    return out[()] if a.shape == () else out
