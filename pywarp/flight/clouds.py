"""The host side of the oc value noise and cloud array (§5.1-5.2, cclouds/valuenoise.h, cclouds/voxel.h): the 2-D octave
procedure of §5.1.1 (:func:`octave_image`), the cloud array's settings (:class:`CloudArraySettings`), the builds that
launch the level and finish kernels level by level (:func:`noise_volume`, :func:`cloud_volume`) or call C, the
per-axis scaling (:func:`scale_volume`), the evaluators the registry names for oc-5.2.1 and oc-5.2.3-scale, and the
generation benchmark (:func:`bench_cloud_array`, ``pywarp bench flight``). The equations and kernels are
:mod:`pywarp.kernels.valuenoise` and :mod:`pywarp.kernels.voxel`.

Public interface (stable; the flight scene renders what it returns)::

    from pywarp.flight.clouds import CloudArraySettings, cloud_volume
    vol = cloud_volume(CloudArraySettings(size=64, seed=3))   # uint8 (64, 64, 64) indexed [z, y, x], 0..255
    vol = cloud_volume(size=64, seed=3, cover=110.0)          # the same with keyword overrides

``cover`` reads inverted in the text ("how big a cloud we want"): a larger cover subtracts more and leaves LESS cloud
-- it is a coverage threshold in 0..255 units.
"""
from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, replace

import numpy as np
import warp as wp

from ..core.params import Settings, param
from ..core.registry import Equation
from ..kernels.valuenoise import INTERPOLATIONS, MAX_COORD, MAX_OCTAVES, SMOOTHINGS, octave_seed
from ..kernels.voxel import (BORDERS, MAX_LEVELS, MAX_SCALE_EDGE, MAX_SIZE, MIN_BASE, VARIANTS, finish_kernel,
                             level_kernel, scale_kernel)


def _check_size(obj, name, v):
    levels = obj.levels
    step = 2 ** (levels - 1)
    if v % step != 0 or v // step < MIN_BASE:
        raise ValueError(f"{name} must be a multiple of 2^(levels - 1) = {step} with {name} / {step} >= {MIN_BASE} "
                         f"(the level-0 array, size/8 for 4 levels), got {v}")


@dataclass(frozen=True)
class CloudArraySettings(Settings):
    """Settings of the cloud array (oc-5.2.1 - 5.2.3-scale); mirrors ``ccl_voxel_settings`` and is checked in the
    order of ``ccl_voxel_settings_check``. The text gives no values: each default says where it comes from."""

    _validation_order = ("levels", "size")
    INVALIDATES = Settings.INVALIDATES + ("textures",)  # the cloud array is regenerated

    size: int = param(64, unit="voxels", kind="int", lo=MIN_BASE, hi=MAX_SIZE, check=_check_size,
                      invalidates="textures", group="cloud array",
                      doc="edge of the cubic cloud array (a multiple of 2^(levels - 1))",
                      reason="64: the array name noise64 of the filter listing (oc-5.2.2) suggests 64^3")
    levels: int = param(4, kind="int", lo=1, hi=MAX_LEVELS, invalidates="textures", group="cloud array",
                        doc="number of arrays from the base to the full size (edge x2 per level)",
                        reason="4: size/8 -> size/4 -> size/2 -> size, the text's size/8 base (§5.2.1)")
    seed: int = param(0, kind="uint32", lo=0, hi=2 ** 32 - 1, invalidates="textures", group="cloud array",
                      doc="seed of the noise (uint32); the same seed gives the same volume",
                      reason="any; 0 is the reproducible default")
    persistence: float = param(0.5, lo=0.0, lo_open=True, hi=1.0, invalidates="textures", group="cloud array",
                               doc="amplitude ratio of successive levels (oc-5.1.2.2)",
                               reason="0.5: Elias's example value; the text says only 0-1 and that lower values "
                                      "look better (fig. 5.5)")
    interpolation: str = param("linear", choices=tuple(INTERPOLATIONS), invalidates="textures", group="cloud array",
                               doc="up-sampling interpolant: linear (trilinear), cosine, or the printed cubic",
                               reason="'linear': the 3-D analogue of the text's bilinear up-sampling, 'mainly used "
                                      "for real time' (§5.1.4.1)")
    smoothing: str = param("elias", choices=tuple(SMOOTHINGS), invalidates="textures", group="cloud array",
                           doc="smoothing of the noise added at each level (oc-5.1.3)",
                           reason="'elias': Elias's weights; with raw per-voxel noise the finest levels make a "
                                  "speckled 'popcorn' cloud, smoothed the clouds are compact")
    variant: str = param("corrected", choices=tuple(VARIANTS), invalidates="textures", group="cloud array",
                         doc="persistence schedule: 'corrected' p^l, 'thesis' the printed squaring p^(2^l)",
                         reason="'corrected': the reading of the cited tutorial (spec erratum 3)")
    border: str = param("zero", choices=tuple(BORDERS), invalidates="textures", group="cloud array",
                        doc="border handling: 'zero' = larger array with zero borders (oc-5.2.3.2), 'sin' = the "
                            "rejected SIN rounding (oc-5.2.3.1), 'none' = the border problem (oc-5.2.3)",
                        reason="'zero': the method the text adopts")
    sin_radius: float = param(0.125, unit="of the edge", lo=0.0, lo_open=True, hi=0.5, invalidates="textures",
                              group="cloud array", doc="radius of the SIN rounding as a fraction of the edge",
                              reason="0.125: one level-0 cell (size/8); the text gives no radius")
    cover: float = param(128.0, unit="0..255", lo=0.0, hi=255.0, invalidates="textures", group="cloud array",
                         doc="cloudCover: noise threshold in 0..255 units; a LARGER cover gives LESS cloud (the "
                             "text's 'how big a cloud we want' reads inverted)",
                         reason="128, the middle of the range: the smoothed noise spreads little around its mean "
                                "(about 0.4 x 255 with the zero border's fall-off), so 128 keeps the brightest 15-30 % "
                                "of the voxels -- one or a few compact clouds inside the box")
    sharpness: float = param(0.96, lo=0.0, hi=1.0, lo_open=True, hi_open=True, invalidates="textures",
                             group="cloud array",
                             doc="cloudSharpness in (0, 1): near 0 hard edges, near 1 soft, faint edges",
                             reason="0.96: half density 17 units above the cover -- soft but visible edges, of the "
                                    "order of Elias's values")
    envelope: float = param(0.0, unit="noise", lo=0.0, hi=1.0, invalidates="textures", group="cloud array",
                            doc="falloff envelope (beyond the text): n - envelope * q, q the squared radius of the "
                                "ellipsoids inscribed in the box (1 on the inscribed one, their centre lowered by "
                                "envelope_base), so the cloud is compact, ends inside its box and shows no face; 0 "
                                "the text's array as printed",
                            reason="0: the text's pipeline; the flight scene and the oc figures ask for 0.5 "
                                   "(FlightSettings.cloud_envelope)")
    envelope_base: float = param(0.35, lo=0.0, lo_open=True, hi=1.0, invalidates="textures", group="cloud array",
                                 doc="lower semi-axis of the envelope's ellipsoids over the upper one (1: centred)",
                                 reason="0.35: the base falls off about three times as fast as the top -- the flat "
                                        "base at the condensation level under the dome of a fair-weather cumulus")

    @property
    def shape(self) -> tuple[int, int, int]:
        return (self.size, self.size, self.size)

    def level_sizes(self) -> list[int]:
        base = self.size >> (self.levels - 1)
        return [base << k for k in range(self.levels)]


def _settings(settings, overrides) -> CloudArraySettings:
    if settings is None:
        settings = CloudArraySettings()
    elif not isinstance(settings, CloudArraySettings):
        raise TypeError(f"settings must be a CloudArraySettings, got {type(settings).__name__}")
    return replace(settings, **overrides) if overrides else settings


def settings_struct(s: CloudArraySettings):
    """A cffi ``ccl_voxel_settings *`` of ``s``."""
    from ..core.binding import ffi

    st = ffi().new("ccl_voxel_settings *")
    st.size, st.levels, st.seed = s.size, s.levels, s.seed
    st.persistence = s.persistence
    st.interpolation = INTERPOLATIONS[s.interpolation]
    st.smoothing = SMOOTHINGS[s.smoothing]
    st.variant = VARIANTS[s.variant]
    st.border = BORDERS[s.border]
    st.sin_radius, st.cover, st.sharpness = s.sin_radius, s.cover, s.sharpness
    st.envelope, st.envelope_base = s.envelope, s.envelope_base
    return st


def voxel_cloud_warp(eq: Equation, device=None):
    """The evaluator of oc-5.2.1 (a whole volume from settings, not element-wise): :func:`cloud_volume` on Warp."""
    def call(settings=None, **overrides):
        return cloud_volume(settings, impl="warp", device=device, **overrides)

    return call


def voxel_cloud_c(eq: Equation):
    """The C evaluator of oc-5.2.1: :func:`cloud_volume` with ``ccl_voxel_cloud``."""
    def call(settings=None, **overrides):
        return cloud_volume(settings, impl="c", **overrides)

    return call


def voxel_scale_warp(eq: Equation, device=None):
    """The evaluator of oc-5.2.3-scale (a resampled volume, not element-wise): :func:`scale_volume` on Warp."""
    def call(volume, scale):
        return scale_volume(volume, scale, impl="warp", device=device)

    return call


def voxel_scale_c(eq: Equation):
    """The C evaluator of oc-5.2.3-scale: :func:`scale_volume` with ``ccl_voxel_scale``."""
    def call(volume, scale):
        return scale_volume(volume, scale, impl="c")

    return call


def _build_warp(s: CloudArraySettings, filtered: bool, device, launcher):
    from ..core.runtime import launcher as shared_launcher

    lau = launcher if launcher is not None else shared_launcher(device)
    dev = lau.device
    sizes = s.level_sizes()
    prev, nc, norm = wp.zeros(1, dtype=float, device=dev), 1, np.float32(0.0)
    amp = np.float32(1.0) if s.variant == "corrected" else np.float32(s.persistence)
    for lvl, nl in enumerate(sizes):
        cur = wp.empty(nl ** 3, dtype=float, device=dev)
        lau.launch(level_kernel, nl * nl, nl,
                   [nl, nc, int(lvl == 0), float(amp), wp.uint32(octave_seed(s.seed, lvl)), SMOOTHINGS[s.smoothing],
                    INTERPOLATIONS[s.interpolation], BORDERS[s.border], prev], [cur])
        norm = np.float32(norm + amp)
        amp = np.float32(amp * amp) if s.variant == "thesis" else np.float32(amp * np.float32(s.persistence))
        prev, nc = cur, nl
    n = s.size
    noise = wp.empty(n ** 3, dtype=float, device=dev)
    cloud = wp.empty(n ** 3 if filtered else 1, dtype=wp.uint8, device=dev)
    lau.launch(finish_kernel, n * n, n,
               [n, float(norm), BORDERS[s.border], float(np.float32(s.sin_radius) * np.float32(n)),
                s.envelope, s.envelope_base, s.cover, s.sharpness, int(filtered), prev], [noise, cloud])
    if filtered:
        return np.array(cloud.numpy(), copy=True).reshape(s.shape)
    return np.array(noise.numpy(), dtype=np.float32, copy=True).reshape(s.shape)


def _build_c(s: CloudArraySettings, filtered: bool):
    from ..core.binding import ffi, lib, status_error

    st = settings_struct(s)
    if filtered:
        out = np.empty(s.shape, dtype=np.uint8)
        status_error(lib().ccl_voxel_cloud(st, ffi().from_buffer("uint8_t[]", out), out.size), "ccl_voxel_cloud")
    else:
        out = np.empty(s.shape, dtype=np.float32)
        status_error(lib().ccl_voxel_noise(st, ffi().from_buffer("float[]", out), out.size), "ccl_voxel_noise")
    return out


def noise_volume(settings: CloudArraySettings | None = None, impl: str = "warp", device: str | None = None,
                 launcher=None, **overrides) -> np.ndarray:
    """The noise array before filtering (fig. 5.11's "nebula"): float32 (size, size, size) in [0, 1] indexed
    [z, y, x]. ``settings`` (default :class:`CloudArraySettings`) with keyword ``overrides`` of its fields;
    ``impl="warp"``: row bands through ``launcher`` (default the process-wide TileLauncher of ``device``);
    ``impl="c"``: ``ccl_voxel_noise``, one thread. Ref: oc-5.2.1, oc-5.2.3, oc-5.2.3.1, oc-5.2.3.2."""
    s = _settings(settings, overrides)
    if impl == "c":
        return _build_c(s, False)
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return _build_warp(s, False, device, launcher)


def cloud_volume(settings: CloudArraySettings | None = None, impl: str = "warp", device: str | None = None,
                 launcher=None, **overrides) -> np.ndarray:
    """The cloud array: :func:`noise_volume` cut out by :func:`pywarp.kernels.voxel.voxel_filter` (cover,
    sharpness), uint8 (size, size, size) indexed [z, y, x], 0 = invisible .. 255 = fully opaque. With
    ``border="zero"`` (default) every voxel of the six outer faces is 0. Same arguments as :func:`noise_volume`; the
    same settings give the same volume (any thread count). Ref: oc-5.2.1, oc-5.2.2, oc-5.2.3.2."""
    s = _settings(settings, overrides)
    if impl == "c":
        return _build_c(s, True)
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    return _build_warp(s, True, device, launcher)


def scaled_shape(shape, scale) -> tuple[int, int, int]:
    """Edges of a volume of ``shape`` (z, y, x) scaled by ``scale`` = (sx, sy, sz) per axis: round(n * s) >= 2."""
    sx, sy, sz = scale
    nz, ny, nx = shape
    return (max(2, int(round(nz * sz))), max(2, int(round(ny * sy))), max(2, int(round(nx * sx))))


def scale_volume(volume, scale, impl: str = "warp", device: str | None = None, launcher=None) -> np.ndarray:
    """Per-axis scaling of a uint8 cloud array (oc-5.2.3-scale): ``volume`` (nz, ny, nx) indexed [z, y, x],
    ``scale`` = (sx, sy, sz) factors > 0 (e.g. (1.5, 1.5, 0.6) for a wide, flat cloud). Trilinear resampling with
    corners aligned (a face maps onto a face, so a zero border stays zero), rounded to uint8. Returns uint8 of
    :func:`scaled_shape`. ``impl="c"``: ``ccl_voxel_scale``."""
    vol = np.asarray(volume)
    if vol.dtype != np.uint8 or vol.ndim != 3:
        raise ValueError(f"volume must be a 3-D uint8 array, got {vol.dtype} of shape {vol.shape}")
    if any(n < 2 or n > MAX_SCALE_EDGE for n in vol.shape):
        raise ValueError(f"volume edges must be in [2, {MAX_SCALE_EDGE}], got {vol.shape}")
    try:
        sc = tuple(float(v) for v in scale)
    except TypeError:
        raise TypeError(f"scale must be a sequence of 3 numbers, got {scale!r}") from None
    if len(sc) != 3 or not all(math.isfinite(v) and v > 0.0 for v in sc):
        raise ValueError(f"scale must hold 3 finite factors > 0 (x, y, z), got {scale!r}")
    mz, my, mx = scaled_shape(vol.shape, sc)
    if max(mz, my, mx) > MAX_SCALE_EDGE:
        raise ValueError(f"scale gives edges {(mz, my, mx)}, above {MAX_SCALE_EDGE}")
    nz, ny, nx = vol.shape
    src = np.ascontiguousarray(vol)
    if impl == "c":
        from ..core.binding import ffi, lib, status_error

        out = np.empty((mz, my, mx), dtype=np.uint8)
        status_error(lib().ccl_voxel_scale(ffi().from_buffer("uint8_t[]", src), nx, ny, nz,
                                           ffi().from_buffer("uint8_t[]", out), mx, my, mz), "ccl_voxel_scale")
        return out
    if impl != "warp":
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    from ..core.runtime import launcher as shared_launcher

    lau = launcher if launcher is not None else shared_launcher(device)
    dst = wp.empty(mz * my * mx, dtype=wp.uint8, device=lau.device)
    lau.launch(scale_kernel, mz * my, mx,
               [nx, ny, nz, mx, my, mz, wp.array(src.ravel(), dtype=wp.uint8, device=lau.device)], [dst])
    return np.array(dst.numpy(), copy=True).reshape(mz, my, mx)


def bench_cloud_array(sizes=(32, 64, 128), interpolations=("linear", "cosine", "cubic"), repeats: int = 3,
                      impl: str = "warp", device: str | None = None, settings: CloudArraySettings | None = None,
                      c_reference: bool = False) -> dict:
    """Cloud-array generation time (:func:`cloud_volume`, noise + filter) by size and by interpolation, the best of
    ``repeats`` runs after one warm-up (Warp compiles on first use). Returns a JSON-ready dict::

        {"unit": "ms", "impl": ..., "device": ..., "workers": ..., "repeats": ...,
         "cloud_array_ms": {"linear": {"32": ms, "64": ms, "128": ms}, "cosine": {...}, "cubic": {...}},
         "cubic_over_linear": {"32": ratio, ...},
         "c_ms": {...}  # only with c_reference=True: the single-threaded C reference, same layout
        }

    The text claims cubic interpolation is "unusable in real time" (§5.1.4.3) without measuring it; this measures
    it. ``settings``: the other parameters (default :class:`CloudArraySettings`)."""
    from ..core.runtime import launcher as shared_launcher

    if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
        raise ValueError(f"repeats must be an integer >= 1, got {repeats!r}")
    for it in interpolations:
        if it not in INTERPOLATIONS:
            raise ValueError(f"interpolations must be among {', '.join(map(repr, INTERPOLATIONS))}, got {it!r}")
    base = settings if settings is not None else CloudArraySettings()
    cases = [(it, int(n), replace(base, size=int(n), interpolation=it)) for it in interpolations for n in sizes]

    def timed(fn):
        fn()  # warm-up (compilation, allocation)
        best = math.inf
        for _ in range(repeats):
            t0 = time.perf_counter()
            fn()
            best = min(best, time.perf_counter() - t0)
        return best * 1e3

    lau = shared_launcher(device) if impl == "warp" else None
    res: dict = {"unit": "ms", "impl": impl, "repeats": repeats, "settings": asdict(base),
                 "cloud_array_ms": {it: {} for it in interpolations}}
    if lau is not None:
        res["device"], res["workers"] = lau.device, lau.workers
    for it, n, s in cases:
        res["cloud_array_ms"][it][str(n)] = timed(lambda s=s: cloud_volume(s, impl=impl, launcher=lau))
    if "linear" in interpolations and "cubic" in interpolations:
        res["cubic_over_linear"] = {k: res["cloud_array_ms"]["cubic"][k] / res["cloud_array_ms"]["linear"][k]
                                    for k in res["cloud_array_ms"]["linear"]}
    if c_reference:
        res["c_ms"] = {it: {} for it in interpolations}
        for it, n, s in cases:
            res["c_ms"][it][str(n)] = timed(lambda s=s: cloud_volume(s, impl="c"))
    return res


def octave_image(size: int = 256, base: int = 16, octaves: int = 5, persistence: float = 0.5, seed: int = 0,
                 smoothing: str = "elias", interpolation: str = "linear", variant: str = "corrected",
                 value_range: str = "unit", impl: str = "warp"):
    """The 2-D procedure of §5.1.1 on a ``size`` x ``size`` image: layer i is the smoothed lattice of
    ``base * 2^i`` cells per image edge up-sampled to the final resolution (``interpolation="linear"``: bilinear, as
    the text), pixel (px, py) at lattice coordinate (px, py) * base * 2^i / size; the layers are weighted by
    valuenoise_amplitude and summed, divided by the amplitude sum. Defaults: 16 x 16 -> 256 x 256 = 5 layers
    (16, 32, 64, 128, 256), persistence 0.5. Returns ``(layers, amplitudes, total)``: the unweighted layers (list of
    float32 (size, size) arrays indexed [py, px]), the amplitudes, and the sum -- equal to valuenoise_fbm (dims 2)
    at (px, py) * base / size."""
    from ..core.registry import equation

    for name, v, lo in (("size", size, 2), ("base", base, 1), ("octaves", octaves, 1)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
            raise ValueError(f"{name} must be an integer >= {lo}, got {v!r}")
    if octaves > MAX_OCTAVES:
        raise ValueError(f"octaves must be <= {MAX_OCTAVES}, got {octaves}")
    if size > 4096:
        raise ValueError(f"size must be <= 4096, got {size}")
    if base * (size - 1) / size * 2 ** (octaves - 1) > MAX_COORD:
        raise ValueError(f"base * 2^(octaves - 1) must be <= {MAX_COORD}, got {base * 2 ** (octaves - 1)}")
    amp_fn = equation("oc-5.1.2.2", impl=impl)
    noise_fn = equation("oc-5.1.4", impl=impl)
    amps = [np.float32(amp_fn(i, persistence, variant=variant)) for i in range(octaves)]
    px = np.arange(size, dtype=np.float32) * np.float32(base) / np.float32(size)
    xx, yy = np.meshgrid(px, px)
    layers, total, norm = [], np.zeros((size, size), np.float32), np.float32(0.0)
    freq = np.float32(1.0)
    for i in range(octaves):
        layer = np.asarray(noise_fn(xx * freq, yy * freq, 0.0, octave_seed(seed, i), 2, smoothing=smoothing,
                                    interpolation=interpolation, value_range=value_range), np.float32)
        layers.append(layer)
        total = (total + amps[i] * layer).astype(np.float32)
        norm = np.float32(norm + amps[i])
        freq = np.float32(freq * 2)
    return layers, amps, (total / norm).astype(np.float32)
