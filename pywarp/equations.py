"""The equation registry: catalogue ID -> title, C symbol, Warp twin, variants, references, tests and figures.

Every computational entry of the catalogues (``spec/*.md``) is registered here by the topic module that implements
it (``pywarp/kernels/<topic>.py``). :func:`equation` turns an entry into a NumPy-in / NumPy-out callable that evaluates
either the Warp twin (default) or the C function, after validating every argument::

    >>> import pywarp
    >>> hg = pywarp.equation("vc-2.13")            # Warp, default device (CPU)
    >>> hg(cos_theta=[1.0, 0.0], g=0.76)
    >>> pywarp.equation("vc-2.13", impl="c")(1.0, 0.76)

Calling convention shared by every entry (so one generic evaluator serves all of them):
  * ``args``: array arguments, broadcast together, passed to the Warp eval kernel as 1-D arrays and to the C function
    as scalars, in this order;
  * ``options``: keyword options (a variant, a metric, a flag) mapped to integers, passed after the arrays;
  * ``outputs``: float32 results; the Warp kernel takes one output array each, the C function returns the single
    output or writes several through trailing out-pointers.
"""
from __future__ import annotations

import inspect
import json
import math
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources
from typing import Any, Callable

import numpy as np

REQUIRED = inspect.Parameter.empty

_DTYPES = {"float32": np.float32, "int32": np.int32, "uint32": np.uint32}


@dataclass(frozen=True)
class Arg:
    """An array argument with its valid domain.

    ``lo``/``hi`` bound the domain (``None`` = unbounded), ``lo_open``/``hi_open`` make a bound exclusive. Float
    arguments must be finite unless ``finite=False``. ``default`` makes the argument optional.
    """

    name: str
    doc: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    dtype: str = "float32"
    default: Any = REQUIRED
    finite: bool = True

    def domain(self) -> str:
        lo = "-inf" if self.lo is None else f"{self.lo:g}"
        hi = "inf" if self.hi is None else f"{self.hi:g}"
        return f"{'(' if self.lo_open or self.lo is None else '['}{lo}, {hi}{')' if self.hi_open or self.hi is None else ']'}"

    def check(self, value, name: str | None = None) -> np.ndarray:
        name = name or self.name
        if isinstance(value, (str, bytes)) or value is None:
            raise TypeError(f"{name} must be a number or an array of numbers, got {value!r}")
        try:
            a = np.asarray(value)
        except Exception as exc:  # ragged lists and the like
            raise ValueError(f"{name} could not be converted to an array: {exc}") from None
        if a.dtype == object or a.dtype.kind not in "biuf":
            raise TypeError(f"{name} must be numeric, got dtype {a.dtype}")
        if self.dtype == "float32":
            if self.finite and not np.all(np.isfinite(a)):
                bad = a[~np.isfinite(a)].flat[0].item()
                raise ValueError(f"{name} must be finite (no NaN or Inf), got {bad}")
        else:
            if a.dtype.kind == "f":
                if not np.all(np.isfinite(a)) or not np.all(a == np.round(a)):
                    raise ValueError(f"{name} must hold integers, got {a.flat[0] if a.size else a}")
        lo_bad = np.zeros(a.shape, bool) if self.lo is None else ((a <= self.lo) if self.lo_open else (a < self.lo))
        hi_bad = np.zeros(a.shape, bool) if self.hi is None else ((a >= self.hi) if self.hi_open else (a > self.hi))
        bad = lo_bad | hi_bad
        if np.any(bad):
            raise ValueError(f"{name} must be in {self.domain()}, got {np.asarray(a)[bad].flat[0].item()!r}")
        return a.astype(_DTYPES[self.dtype], copy=False)


@dataclass(frozen=True)
class Option:
    """A keyword option mapped to an integer for the kernels and C (``choices``: value -> integer)."""

    name: str
    choices: dict
    default: Any
    doc: str = ""

    def check(self, value) -> int:
        if isinstance(value, bool) and all(isinstance(k, bool) for k in self.choices):
            return self.choices[value]
        try:
            if value in self.choices and type(value) is type(next(iter(self.choices))):
                return self.choices[value]
        except TypeError:
            pass
        valid = ", ".join(repr(k) for k in self.choices)
        raise ValueError(f"{self.name} must be one of {valid}, got {value!r}")


VARIANT = Option("variant", {"corrected": 0, "thesis": 1}, "corrected",
                 "'corrected' (default): the formula of the original paper; 'thesis': as printed in the text")


@dataclass
class Equation:
    """One registered catalogue entry."""

    id: str
    name: str
    c_symbol: str | None
    warp: Any  # the @wp.func twin
    kernel: Any  # the @wp.kernel evaluating ``warp`` element-wise (calling convention above)
    args: tuple[Arg, ...] = ()
    options: tuple[Option, ...] = ()
    outputs: tuple[str, ...] = ("value",)
    references: tuple[str, ...] = ()
    summary: str = ""
    c_out_pointers: bool | None = None  # default: True when there are several outputs
    check: Callable | None = None  # extra cross-argument validation: check(**arrays_and_options)
    # Entries that are not element-wise (a sum over sample arrays, a texture generator, a whole pixel pipeline) give
    # their own NumPy-level evaluators instead of the generic ones: make_warp(eq, device) / make_c(eq) -> callable.
    # The callable must validate its input like Equation.bind does (ValueError naming the parameter).
    make_warp: Callable | None = None
    make_c: Callable | None = None
    extra: dict = field(default_factory=dict)

    @property
    def title(self) -> str:
        return catalogue()["ids"].get(self.id, {}).get("title", self.summary)

    @property
    def variants(self) -> tuple[str, ...]:
        for o in self.options:
            if o.name == "variant":
                return tuple(o.choices)
        return ()

    @property
    def tests(self) -> list[str]:
        return catalogue()["tests"].get(self.id, [])

    @property
    def figures(self) -> list[str]:
        return catalogue()["tutorials"].get(self.id, [])

    def signature(self) -> inspect.Signature:
        params = [inspect.Parameter(a.name, inspect.Parameter.POSITIONAL_OR_KEYWORD, default=a.default)
                  for a in self.args]
        params += [inspect.Parameter(o.name, inspect.Parameter.KEYWORD_ONLY, default=o.default) for o in self.options]
        return inspect.Signature(params)

    def bind(self, *args, **kwargs):
        """Validate a call; return (broadcast shape, list of arrays, list of option integers)."""
        try:
            bound = self.signature().bind(*args, **kwargs)
        except TypeError as exc:
            raise TypeError(f"{self.name}(): {exc}") from None
        bound.apply_defaults()
        arrays = [a.check(bound.arguments[a.name]) for a in self.args]
        opts = [o.check(bound.arguments[o.name]) for o in self.options]
        try:
            shape = np.broadcast_shapes(*(a.shape for a in arrays)) if arrays else ()
        except ValueError:
            shapes = ", ".join(f"{a.name}{tuple(x.shape)}" for a, x in zip(self.args, arrays))
            raise ValueError(f"{self.name}(): the shapes of the array arguments do not broadcast: {shapes}") from None
        if self.check is not None:
            self.check(**{a.name: x for a, x in zip(self.args, arrays)},
                       **{o.name: bound.arguments[o.name] for o in self.options})
        return shape, arrays, opts

    def docstring(self) -> str:
        lines = [f"{self.title}  [{self.id}]", ""]
        if self.summary:
            lines += [self.summary, ""]
        lines.append("Parameters")
        for a in self.args:
            lines.append(f"    {a.name} : array_like ({a.dtype}), domain {a.domain()}"
                         + ("" if a.default is REQUIRED else f", default {a.default}"))
            if a.doc:
                lines.append(f"        {a.doc}")
        for o in self.options:
            lines.append(f"    {o.name} : one of {', '.join(map(repr, o.choices))}, default {o.default!r}")
            if o.doc:
                lines.append(f"        {o.doc}")
        lines += ["Returns", "    " + ", ".join(self.outputs) + " (float32 arrays of the broadcast shape)"]
        if self.references:
            lines += ["References"] + [f"    {r}" for r in self.references]
        lines.append(f"C: {self.c_symbol}    Warp: pywarp.kernels.{self.warp.func.__module__.rsplit('.', 1)[-1]}."
                     f"{self.warp.key if hasattr(self.warp, 'key') else self.name}")
        return "\n".join(lines)


_REGISTRY: dict[str, Equation] = {}


def register(eq: Equation) -> Equation:
    if eq.id in _REGISTRY:
        raise RuntimeError(f"{eq.id} registered twice")
    _REGISTRY[eq.id] = eq
    return eq


@lru_cache(maxsize=None)
def catalogue() -> dict:
    """The shipped catalogue data (IDs with titles and kinds, test index, tutorial index)."""
    text = resources.files("pywarp").joinpath("data/catalogue.json").read_text(encoding="utf-8")
    return json.loads(text)


def registry() -> dict[str, Equation]:
    """All registered entries, by ID (imports every topic module on first use)."""
    import importlib

    importlib.import_module("pywarp.kernels").load_all()  # topic modules register on import
    return dict(sorted(_REGISTRY.items(), key=lambda kv: _sort_key(kv[0])))


def _sort_key(cid: str):
    seed, rest = cid.split("-", 1)
    parts = []
    for tok in rest.replace("-", ".").split("."):
        parts.append((0, int(tok), "") if tok.isdigit() else (1, 0, tok))
    return ("vc pt rr oc".split().index(seed) if seed in ("vc", "pt", "rr", "oc") else 9, parts)


def get(cid: str) -> Equation:
    reg = registry()
    if cid not in reg:
        known = catalogue()["ids"]
        if cid in known:
            raise NotImplementedError(f"{cid} ({known[cid]['title']}) is catalogued but not implemented yet")
        raise KeyError(f"unknown catalogue ID {cid!r}; see `pywarp equations`")
    return reg[cid]


def _warp_eval(eq: Equation, device: str | None):
    import warp as wp

    from .runtime import resolve_device

    dev = resolve_device(device)

    def call(*args, **kwargs):
        shape, arrays, opts = eq.bind(*args, **kwargs)
        n = int(math.prod(shape))
        outs_np = [np.empty(n, dtype=np.float32) for _ in eq.outputs]
        if n:
            ins = [wp.array(np.ascontiguousarray(np.broadcast_to(a, shape).ravel()), device=dev) for a in arrays]
            outs = [wp.empty(n, dtype=wp.float32, device=dev) for _ in eq.outputs]
            wp.launch(eq.kernel, dim=n, inputs=[*ins, *opts], outputs=outs, device=dev)
            outs_np = [o.numpy() for o in outs]
        res = tuple(o.reshape(shape)[()] if shape == () else o.reshape(shape) for o in outs_np)
        return res[0] if len(res) == 1 else res

    return call


def _c_eval(eq: Equation):
    from ._cclouds import vectorize

    if eq.c_symbol is None:
        raise NotImplementedError(f"{eq.id} has no C implementation")

    def call(*args, **kwargs):
        shape, arrays, opts = eq.bind(*args, **kwargs)
        fn = vectorize(eq.c_symbol, n_out=len(eq.outputs), out_pointers=eq.c_out_pointers, extra=tuple(opts))
        res = fn(*arrays) if arrays else fn()
        if len(eq.outputs) == 1:
            res = (res,)
        res = tuple(np.asarray(r, dtype=np.float32).reshape(shape) for r in res)
        res = tuple(r[()] if shape == () else r for r in res)
        return res[0] if len(res) == 1 else res

    return call


def equation(cid: str, impl: str = "warp", device: str | None = None) -> Callable:
    """A NumPy-in / NumPy-out callable for catalogue entry ``cid``.

    ``impl="warp"`` (default) evaluates the Warp twin on ``device`` (default CPU); ``impl="c"`` the C function.
    Keyword names are the fixed contract of each entry; see ``help()`` of the returned callable.
    """
    if impl not in ("warp", "c"):
        raise ValueError(f"impl must be 'warp' or 'c', got {impl!r}")
    eq = get(cid)
    if impl == "warp":
        fn = eq.make_warp(eq, device) if eq.make_warp else _warp_eval(eq, device)
    else:
        fn = eq.make_c(eq) if eq.make_c else _c_eval(eq)
    fn.__name__ = eq.name
    fn.__qualname__ = eq.name
    fn.__doc__ = eq.docstring()
    if not (eq.make_warp or eq.make_c):
        fn.__signature__ = eq.signature()
    fn.equation = eq
    return fn


@lru_cache(maxsize=None)
def _not_computational() -> dict:
    text = resources.files("pywarp").joinpath("data/not_computational.json").read_text(encoding="utf-8")
    return json.loads(text)


def not_computational_reason(cid: str) -> str | None:
    """Why a catalogued ID has no C/Warp implementation by design (a figure, a class diagram, ...), else None."""
    data = _not_computational()
    if cid in data:
        return data[cid]
    kind = catalogue()["ids"].get(cid, {}).get("kind")
    return data["_kinds"].get(kind)


def missing(seed: str | None = None) -> list[tuple[str, dict]]:
    """Catalogued IDs (of ``seed``, or all) that have no registered implementation, with their catalogue entry and
    ``reason``: why it is not computational, or None when it is simply not implemented yet."""
    reg = registry()
    return [(cid, {**e, "reason": not_computational_reason(cid)})
            for cid, e in sorted(catalogue()["ids"].items(), key=lambda kv: _sort_key(kv[0]))
            if cid not in reg and (seed is None or e["seed"] == seed)]
