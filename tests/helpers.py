"""Helpers shared by the tests (importable because pyproject sets pytest's pythonpath to tests/)."""
from __future__ import annotations

import numpy as np


def max_ulp_diff(a, b) -> int:
    """Largest distance in units in the last place between two float32 arrays (same-sign finite values)."""
    a = np.asarray(a, dtype=np.float32).ravel().view(np.int32).astype(np.int64)
    b = np.asarray(b, dtype=np.float32).ravel().view(np.int32).astype(np.int64)
    return int(np.max(np.abs(a - b))) if a.size else 0


def ulp_distance(a, b) -> np.ndarray:
    """Element-wise distance in float32 ulp, valid across zero (the ordered-integer mapping of IEEE floats)."""
    def ordered(x):
        i = np.asarray(x, dtype=np.float32).view(np.int32).astype(np.int64)
        return np.where(i < 0, -(i & 0x7FFFFFFF), i)
    return np.abs(ordered(a) - ordered(b))


def assert_twins_agree(cid: str, *args, ulp: int | None = None, atol: float = 0.0, **kwargs):
    """Evaluate catalogue entry ``cid`` with its Warp twin and its C function on the same inputs and assert that
    they agree: the same shapes and dtypes, NaN in the same places, integers equal, floats within ``ulp`` float32
    ulp (default: the entry's declared bound) or ``atol`` absolute (for values that cancel to near zero, where a
    relative bound says nothing). Returns the (warp, c) results as tuples of arrays."""
    import pywarp
    from pywarp.core.registry import get

    eq = get(cid)
    bound = eq.ulp if ulp is None else ulp
    w = pywarp.equation(cid)(*args, **kwargs)
    c = pywarp.equation(cid, impl="c")(*args, **kwargs)
    w = w if isinstance(w, tuple) else (w,)
    c = c if isinstance(c, tuple) else (c,)
    assert len(w) == len(c), f"{cid}: Warp gives {len(w)} outputs, C gives {len(c)}"
    for name, x, y in zip(eq.outputs, w, c):
        x, y = np.asarray(x), np.asarray(y)
        assert x.shape == y.shape, f"{cid} {name}: shapes differ, Warp {x.shape} vs C {y.shape}"
        assert x.dtype == y.dtype, f"{cid} {name}: dtypes differ, Warp {x.dtype} vs C {y.dtype}"
        if x.dtype.kind in "iu":
            assert np.array_equal(x, y), f"{cid} {name}: integers differ at {np.argwhere(x != y)[:5].tolist()}"
            continue
        nan_w, nan_c = np.isnan(x), np.isnan(y)
        assert np.array_equal(nan_w, nan_c), f"{cid} {name}: NaN in different places"
        ok = ~nan_w
        d = ulp_distance(x[ok], y[ok])
        with np.errstate(invalid="ignore"):  # inf - inf where both overflow alike (equal: d == 0)
            close = (d <= bound) | (np.abs(x[ok].astype(np.float64) - y[ok]) <= atol)
        if not np.all(close):
            k = int(np.argmax(~close))
            raise AssertionError(f"{cid} {name}: Warp and C differ by {int(d[k])} ulp > {bound} "
                                 f"(Warp {x[ok][k]!r}, C {y[ok][k]!r}); max {int(d.max())} ulp")
    return w, c


def look_at64(eye, target):
    """Right-handed look-at basis (e, s, u, f) with up = +y, from float32-rounded inputs, in float64: camera maths
    written independently of the kernels, for the reprojection tests."""
    e = np.asarray(eye, np.float32).astype(float)
    f = np.asarray(target, np.float32).astype(float) - e
    f /= np.linalg.norm(f)
    s = np.cross(f, [0.0, 1.0, 0.0])
    s /= np.linalg.norm(s)
    return e, s, np.cross(s, f), f


#: The lighting terms of issue 32's measured model (on by default) switched off and the octaves' contribution ms_b
#: back at 0.5: the lighting under which the march's approximations -- the early exit and its fill, step grouping, light
#: interpolation, the textbook march's long steps -- were measured, whose numbers their tests hold. The terms that read
#: the view's transmittance T in front of each sample (vc-x-ms-view, vc-x-ambient-aniso, vc-x-ms-slab) take it once
#: per sample, so any coarser march (a longer step, a group, the fill of the rest of the ray) also changes their
#: weights. Under the defaults (240 x 135) the approximations change the frame by more than the jitter in places:
#: the exit's 99.9th percentile 8.1 levels against the jitter's 6.9 (dense view); light interpolation at a low sun at
#: most 7.1 levels against 2.6 (mean 0.037 against 0.064); step grouping at most 0.12 against 0.042 (linear); the
#: textbook march's long steps 26.5 levels on average against its noise of 7.2 (below, sun 35 deg).
LIGHTING_TERMS_OFF = dict(ms_view=0.0, ambient_aniso=0.0, ms_slab=0.0, ms_depth=0.0, ambient_ground_weight=0.0,
                          advanced={"ms_b": 0.5})


def merged(*parts: dict) -> dict:
    """Settings changes one after the other, their ``advanced`` dicts merged (not replaced)."""
    out, advanced = {}, {}
    for part in parts:
        out.update(part)
        advanced.update(part.get("advanced", {}))
    if advanced:
        out["advanced"] = advanced
    return out


def march_frames(view: dict, marches: dict, reference: str, width: int = 240, height: int = 135) -> dict:
    """The cloudscape seen from ``view`` (settings) under each settings change of ``marches`` (one texture set):
    display-linear frames in levels of 8 bits by name, the view samples each took as ``name + "_samples"``, and the
    frame after ``reference``'s (the same march at the next jitter offset: the variation every frame already has) as
    ``reference + "_next"``."""
    from pywarp.core.pose import Pose
    from pywarp.clouds.technique import CloudscapeTechnique
    from pywarp.clouds.settings import CloudscapeSettings

    out = {}
    tex = None
    for name, kw in marches.items():
        s = CloudscapeSettings(width=width, height=height, **merged(view, kw))
        t = CloudscapeTechnique(s, textures=tex)
        tex = t.textures
        pose = Pose.from_settings(s)
        out[name] = t.render(pose, reprojection=False, encode=False) * 255.0
        out[name + "_samples"] = int(t.samples_taken().astype(np.int64).sum())
        if name == reference:
            out[name + "_next"] = t.render(pose, reprojection=False, encode=False) * 255.0
    return out


def pixel_change(a, b) -> np.ndarray:
    """Per pixel the largest channel difference of two (height, width, channels) frames."""
    return np.abs(np.asarray(a) - np.asarray(b)).max(axis=2)


def differential_settings(default_examples: int):
    """The hypothesis settings of the differential tests in tests/hardening (Warp against C at the edges of the
    domains): deterministic (``derandomize=True``, no example database, no deadline), ``default_examples`` examples
    or the number in the environment variable ``PYWARP_DIFF_EXAMPLES`` (a longer search)."""
    import os

    from hypothesis import HealthCheck, settings

    n = int(os.environ.get("PYWARP_DIFF_EXAMPLES", str(default_examples)))
    return settings(max_examples=n, derandomize=True, database=None, deadline=None,
                    suppress_health_check=list(HealthCheck), print_blob=True)
