"""The equation registry: an equation is declared once, at its Warp function.

A topic module (``pywarp/kernels/<topic>.py``) writes the ``@wp.func`` twin of a C function and declares it::

    @declare("vc-2.13", c="ccl_phase_hg",
             args=(Arg("cos_theta", "cosine of the scattering angle", lo=-1.0, hi=1.0),
                   Arg("g", "asymmetry parameter", lo=-1.0, hi=1.0, lo_open=True, hi_open=True)),
             outputs=("p",), summary="Henyey-Greenstein phase function [sr^-1].",
             references=("Henyey & Greenstein 1941",))
    @wp.func
    def phase_hg(cos_theta: float, g: float) -> float:
        ...

From that one declaration come: the element-wise evaluation kernel (generated from the function's annotations, in
the topic's Warp module), the NumPy-in / NumPy-out evaluators of the Warp twin and of the C function, the validation
of every argument, the docstring, and the contract tests (``tests/core/test_contracts.py``)::

    >>> import pywarp
    >>> pywarp.equation("vc-2.13")(cos_theta=[1.0, 0.0], g=0.76)     # Warp, CPU
    >>> pywarp.equation("vc-2.13", impl="c")(1.0, 0.76)              # the C function of libcclouds

Calling convention (the same for the Warp function, the generated kernel and the C function):

* ``args``: element-wise arguments, broadcast together. Scalars (``float`` -> float32, ``int`` -> int32,
  ``wp.uint32``) or vectors (``wp.vec2``, ``wp.vec3``: NumPy arrays of shape ``(..., 2)`` / ``(..., 3)``; C takes
  ``ccl_vec2`` / ``ccl_vec3`` by value). The Warp function's parameters are the args, then the options, in the
  declared order.
* ``options``: keyword options (a variant, a metric, a flag) mapped to integers, passed after the args.
* ``outputs``: named results; their types come from the Warp function's return annotation (``-> float``,
  ``-> wp.vec3``, ``-> tuple[float, wp.vec3]``; float32 when there is none). The C function returns the first output
  and writes the others through trailing out-pointers, or writes all of them through out-pointers (its return value
  is then ignored, or checked when it is a ``ccl_status``).
* ``derived``: a Warp parameter computed from an integer argument rather than passed element-wise, e.g. the
  permutation table of a Perlin seed: ``derived={"perm": ("seed", perm_array)}``. The evaluator launches once per
  distinct value of that argument. The C function takes the argument itself.

Entries that are not element-wise (a whole image, a sum over sample arrays, a texture generator) give their own
evaluators, ``make_warp(eq, device)`` and ``make_c(eq)``, and no kernel is generated. Where that evaluator is host code
(a particle system, a texture generator, a volume builder: it lives in a scene package), the declaration names it as
a string ``"module:function"`` (``make_warp="pywarp.rain.particles:simulate_warp"``), imported on first use: a topic
module of ``pywarp/kernels`` never imports upwards.
"""
from __future__ import annotations

import inspect
import linecache
import math
import typing
from dataclasses import dataclass, field, replace
from typing import Any, Callable

import numpy as np

from .catalogue import catalogue, not_computational_reason, sort_key

REQUIRED = inspect.Parameter.empty

_NP = {"float32": np.float32, "int32": np.int32, "uint32": np.uint32}
_INT_RANGE = {"int32": (-(2 ** 31), 2 ** 31 - 1), "uint32": (0, 2 ** 32 - 1)}
_F32_MAX = float(np.finfo(np.float32).max)
_COMPONENTS = "xyzw"

#: Tolerance of ``Arg(unit=True)``: a direction counts as normalised when | |v| - 1 | <= UNIT_TOL. Float32 vectors
#: normalised by the caller are within a few 1e-7 of 1; 1e-3 also accepts directions typed by hand to 4 digits.
UNIT_TOL = 1e-3


@dataclass(frozen=True)
class Arg:
    """An element-wise argument with its valid domain.

    ``lo``/``hi`` bound the domain (``None`` = unbounded; for a vector, every component), ``lo_open``/``hi_open``
    make a bound exclusive. Float arguments must be finite unless ``finite=False``. ``default`` makes the argument
    optional. ``dtype`` and ``length`` (1 for scalars, 2 or 3 for vectors) are taken from the Warp function's
    annotation when the entry is declared; ``nonzero``/``unit`` require a vector of non-zero / unit length.
    """

    name: str
    doc: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    dtype: str | None = None
    default: Any = REQUIRED
    finite: bool = True
    length: int = 1
    nonzero: bool = False
    unit: bool = False
    unit_name: str = ""
    #: range the contract tests draw samples from where the domain is unbounded or wider than meaningful
    #: (default: the domain clipped to [-100, 100])
    sample_range: tuple[float, float] | None = None

    def domain(self) -> str:
        lo = "-inf" if self.lo is None else f"{self.lo:g}"
        hi = "inf" if self.hi is None else f"{self.hi:g}"
        dom = f"{'(' if self.lo_open or self.lo is None else '['}{lo}, {hi}{')' if self.hi_open or self.hi is None else ']'}"
        if self.length > 1:
            dom = f"{self.length}-vector, components in {dom}"
            if self.unit:
                dom += ", unit length"
            elif self.nonzero:
                dom += ", non-zero"
        return dom

    def kind(self) -> str:
        return "float32" if self.dtype is None else self.dtype

    def check(self, value, name: str | None = None) -> np.ndarray:
        """Validate ``value`` against the domain (before any cast) and return it as an array of the kernel dtype."""
        name = name or self.name
        dtype = self.kind()
        if isinstance(value, (str, bytes)) or value is None:
            raise TypeError(f"{name} must be a number or an array of numbers, got {value!r}")
        try:
            a = np.asarray(value)
        except Exception as exc:  # ragged lists and the like
            raise ValueError(f"{name} could not be converted to an array: {exc}") from None
        if a.dtype == object or a.dtype.kind not in "biuf":
            raise TypeError(f"{name} must be numeric, got dtype {a.dtype}")
        if a.dtype.kind == "b":
            raise TypeError(f"{name} must be a number, not a bool")
        if self.length > 1 and (a.ndim == 0 or a.shape[-1] != self.length):
            comps = ", ".join(_COMPONENTS[: self.length])
            raise ValueError(f"{name} must be an array of {self.length}-vectors, shape (..., {self.length}) "
                             f"({comps}), got shape {a.shape}")
        if dtype == "float32":
            if self.finite and not np.all(np.isfinite(a)):
                bad = a[~np.isfinite(a)].flat[0].item()
                raise ValueError(f"{name} must be finite (no NaN or Inf), got {bad}")
            big = np.abs(a.astype(np.float64, copy=False)) > _F32_MAX
            if np.any(big & np.isfinite(a)):
                raise ValueError(f"{name} must be within the float32 range (|x| <= {_F32_MAX:.4g}), "
                                 f"got {a[big].flat[0].item()!r}")
        else:
            if a.dtype.kind == "f":
                if not np.all(np.isfinite(a)) or not np.all(a == np.round(a)):
                    bad = a[~(np.isfinite(a) & (a == np.round(a)))].flat[0].item()
                    raise ValueError(f"{name} must hold integers, got {bad!r}")
            lo_i, hi_i = _INT_RANGE[dtype]
            out = (a < lo_i) | (a > hi_i)
            if np.any(out):
                raise ValueError(f"{name} must be in [{lo_i}, {hi_i}] ({dtype}), got {a[out].flat[0].item()!r}")
        w = a.astype(np.float64) if a.dtype.kind == "f" else a  # compare float16/32 in float64: no cast warnings
        lo_bad = np.zeros(a.shape, bool) if self.lo is None else ((w <= self.lo) if self.lo_open else (w < self.lo))
        hi_bad = np.zeros(a.shape, bool) if self.hi is None else ((w >= self.hi) if self.hi_open else (w > self.hi))
        bad = lo_bad | hi_bad
        if np.any(bad):
            raise ValueError(f"{name} must be in {self.domain()}, got {np.asarray(a)[bad].flat[0].item()!r}")
        if self.length > 1 and (self.nonzero or self.unit):
            norm = np.sqrt(np.sum(np.square(a, dtype=np.float64), axis=-1))
            if self.unit and np.any(np.abs(norm - 1.0) > UNIT_TOL):
                raise ValueError(f"{name} must have unit length (| |v| - 1 | <= {UNIT_TOL:g}), "
                                 f"got |v| = {norm[np.abs(norm - 1.0) > UNIT_TOL].flat[0]:.6g}")
            if self.nonzero and np.any(norm == 0.0):
                raise ValueError(f"{name} must be a non-zero vector, got (0, ..., 0)")
        return a.astype(_NP[dtype], copy=False)


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


@dataclass(frozen=True)
class Output:
    """A named result: ``dtype`` float32 / int32 / uint32, ``length`` 1 for scalars, 2-4 for vectors."""

    name: str
    dtype: str = "float32"
    length: int = 1


@dataclass
class Equation:
    """One registered entry; it may answer several catalogue IDs (``ids``)."""

    id: str
    name: str
    c_symbol: str | None
    warp: Any  # the @wp.func twin
    kernel: Any = None  # the generated @wp.kernel evaluating ``warp`` element-wise; None for custom evaluators
    args: tuple[Arg, ...] = ()
    options: tuple[Option, ...] = ()
    outputs: tuple[str, ...] = ("value",)
    references: tuple[str, ...] = ()
    summary: str = ""
    check: Callable | None = None  # extra cross-argument validation: check(**arrays_and_options)
    #: ``make_warp(eq, device)`` / ``make_c(eq)``, or a ``"module:function"`` string naming one (see :func:`evaluator`)
    make_warp: Callable | str | None = None
    make_c: Callable | str | None = None
    also: tuple[str, ...] = ()  # further catalogue IDs answered by the same function
    derived: dict = field(default_factory=dict)  # warp parameter -> (argument name, fn(value, device) -> wp.array)
    out_specs: tuple[Output, ...] = ()
    extra: dict = field(default_factory=dict)
    #: C vs Warp agreement bound of the contract tests, in float32 ulp (2 = one differently rounded libm call)
    ulp: int = 2
    #: samples(rng, n) -> {arg name: array of n valid values}, for arguments tied by a cross-argument check; the
    #: contract tests otherwise draw each argument from its own domain
    samples: Callable | None = None
    #: why outputs may be NaN or infinite for accepted inputs ("" = never): a ray that misses gives NaN distances, a
    #: printed erratum overflows. The property tests (tests/hardening) require finite outputs of every other entry.
    nonfinite: str = ""

    @property
    def ids(self) -> tuple[str, ...]:
        return (self.id, *self.also)

    @property
    def elementwise(self) -> bool:
        return self.kernel is not None

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
        found: list[str] = []
        for cid in self.ids:
            found += [t for t in catalogue()["tests"].get(cid, []) if t not in found]
        return found

    @property
    def figures(self) -> list[str]:
        found: list[str] = []
        for cid in self.ids:
            found += [t for t in catalogue()["tutorials"].get(cid, []) if t not in found]
        return found

    @property
    def warp_name(self) -> str:
        """``<topic>.<function>`` of the Warp twin."""
        fn = getattr(self.warp, "func", self.warp)
        return f"{fn.__module__.rsplit('.', 1)[-1]}.{getattr(self.warp, 'key', fn.__name__)}"

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
            shape = np.broadcast_shapes(*(_elem_shape(a, x) for a, x in zip(self.args, arrays))) if arrays else ()
        except ValueError:
            shapes = ", ".join(f"{a.name}{tuple(x.shape)}" for a, x in zip(self.args, arrays))
            raise ValueError(f"{self.name}(): the shapes of the array arguments do not broadcast: {shapes}") from None
        if self.check is not None:
            self.check(**{a.name: x for a, x in zip(self.args, arrays)},
                       **{o.name: bound.arguments[o.name] for o in self.options})
        return shape, arrays, opts

    def docstring(self) -> str:
        ids = ", ".join(self.ids)
        lines = [f"{self.title}  [{ids}]", ""]
        if self.summary:
            lines += [self.summary, ""]
        if self.args or self.options:
            lines.append("Parameters")
        for a in self.args:
            lines.append(f"    {a.name} : array_like ({a.kind()}{', shape (..., %d)' % a.length if a.length > 1 else ''}),"
                         f" domain {a.domain()}" + (f" [{a.unit_name}]" if a.unit_name else "")
                         + ("" if a.default is REQUIRED else f", default {a.default}"))
            if a.doc:
                lines.append(f"        {a.doc}")
        for o in self.options:
            lines.append(f"    {o.name} : one of {', '.join(map(repr, o.choices))}, default {o.default!r}")
            if o.doc:
                lines.append(f"        {o.doc}")
        if self.out_specs:
            outs = ", ".join(f"{o.name} ({o.dtype}{', (..., %d)' % o.length if o.length > 1 else ''})"
                             for o in self.out_specs)
            lines += ["Returns", f"    {outs}, arrays of the broadcast shape"]
        if self.references:
            lines += ["References"] + [f"    {r}" for r in self.references]
        lines.append(f"C: {self.c_symbol}    Warp: pywarp.kernels.{self.warp_name}")
        return "\n".join(lines)


def _elem_shape(arg: Arg, x: np.ndarray) -> tuple:
    return x.shape[:-1] if arg.length > 1 else x.shape


_REGISTRY: dict[str, Equation] = {}


def register(eq: Equation) -> Equation:
    """Add an entry under each of its IDs (called by :func:`declare`)."""
    for cid in eq.ids:
        if cid in _REGISTRY:
            raise RuntimeError(f"{cid} registered twice ({_REGISTRY[cid].name} and {eq.name})")
    for cid in eq.ids:
        _REGISTRY[cid] = eq
    return eq


# --- annotations -> types ------------------------------------------------------------------------------------------

def _type_of(ann) -> tuple[str, int]:
    """(dtype, length) of a Warp annotation: float/int/uint32 scalars or vec2/vec3/vec4 of float32."""
    import warp as wp

    scalars = {float: "float32", wp.float32: "float32", int: "int32", wp.int32: "int32", wp.uint32: "uint32"}
    if ann in scalars:
        return scalars[ann], 1
    for n, vt in ((2, wp.vec2), (3, wp.vec3), (4, wp.vec4)):
        if ann is vt:
            return "float32", n
    raise TypeError(f"unsupported type {ann!r} for an element-wise argument or result (float, int, wp.uint32, "
                    "wp.vec2, wp.vec3, wp.vec4)")


def _hints(fn) -> dict:
    """The annotations of ``fn`` as objects (modules with ``from __future__ import annotations`` hold strings)."""
    return typing.get_type_hints(fn)


def _return_types(fn, n_out: int) -> list[tuple[str, int]]:
    ann = _hints(fn).get("return")
    if ann is None:
        return [("float32", 1)] * n_out
    if typing.get_origin(ann) is tuple:
        items = list(typing.get_args(ann))
    else:
        items = [ann]
    return [_type_of(t) for t in items]


def warp_parameters(func) -> list[str]:
    """Parameter names of a ``@wp.func``."""
    return list(inspect.signature(func.func).parameters)


_ARRAY_ANN = {("float32", 1): "_Af", ("int32", 1): "_Ai", ("uint32", 1): "_Au", ("float32", 2): "_Av2",
              ("float32", 3): "_Av3", ("float32", 4): "_Av4"}


def _generate_kernel(func, eq: Equation):
    """Build ``_eval_<name>``: one thread per element, args as arrays indexed by the thread, options and derived
    tables passed whole, one output array per result. Defined in the Warp module of ``func``."""
    import warp as wp

    fn = func.func
    params = warp_parameters(func)
    arg_by_name = {a.name: a for a in eq.args}
    opt_names = {o.name for o in eq.options}
    src_params, call = [], []
    ns: dict[str, Any] = {"wp": wp, "_f": func, "__name__": fn.__module__,
                          "_Af": wp.array(dtype=wp.float32), "_Ai": wp.array(dtype=wp.int32),
                          "_Au": wp.array(dtype=wp.uint32), "_Av2": wp.array(dtype=wp.vec2),
                          "_Av3": wp.array(dtype=wp.vec3), "_Av4": wp.array(dtype=wp.vec4)}
    for p in params:
        if p in eq.derived:
            ns[f"_T_{p}"] = _hints(fn)[p]
            src_params.append(f"{p}: _T_{p}")
            call.append(p)
        elif p in opt_names:
            src_params.append(f"{p}: int")
            call.append(p)
        else:
            a = arg_by_name[p]
            src_params.append(f"{p}: {_ARRAY_ANN[(a.kind(), a.length)]}")
            call.append(f"{p}[_tid]")
    outs = [f"out_{o.name}" for o in eq.out_specs]
    src_params += [f"out_{o.name}: {_ARRAY_ANN[(o.dtype, o.length)]}" for o in eq.out_specs]
    kname = f"_eval_{func.key}"
    body = [f"def {kname}({', '.join(src_params)}):", "    _tid = wp.tid()"]
    results = [f"r{k}" for k in range(len(outs))]
    body.append(f"    {', '.join(results)} = _f({', '.join(call)})")
    body += [f"    {o}[_tid] = {r}" for o, r in zip(outs, results)]
    src = "\n".join(body) + "\n"
    filename = f"<pywarp generated {fn.__module__}.{kname}>"
    linecache.cache[filename] = (len(src), None, src.splitlines(True), filename)
    exec(compile(src, filename, "exec"), ns)
    return wp.kernel(ns[kname], module=fn.__module__)


def declare(cid: str, *also: str, c: str | None, args: tuple[Arg, ...] = (), options: tuple[Option, ...] = (),
            outputs: tuple[str, ...] = ("value",), summary: str = "", references: tuple[str, ...] = (),
            check: Callable | None = None, derived: dict | None = None, name: str | None = None,
            make_warp: Callable | str | None = None, make_c: Callable | str | None = None, extra: dict | None = None,
            ulp: int = 2, samples: Callable | None = None, nonfinite: str = ""):
    """Decorator of a ``@wp.func``: register it as the twin of C function ``c`` for catalogue ID(s) ``cid, *also``.

    For an element-wise entry (no ``make_warp``), the Warp parameters must be ``args`` then ``options`` in order
    (with each ``derived`` parameter standing in the place of its argument), and the evaluation kernel is generated
    from the annotations. ``ulp`` bounds the C vs Warp difference in the contract tests (state the reason where it
    is above 2); ``samples(rng, n)`` draws valid inputs where arguments are tied by ``check``; ``nonfinite`` says why
    outputs may be NaN or infinite for accepted inputs (a ray miss; empty: never). ``make_warp``/``make_c`` may be
    ``"module:function"`` strings, resolved on first use (:func:`evaluator`). Returns the Warp function unchanged.
    """

    for label, ev in (("make_warp", make_warp), ("make_c", make_c)):
        if isinstance(ev, str):
            _split_ref(ev, f"{cid}: {label}")

    def wrap(func):
        fn = getattr(func, "func", None)
        if fn is None:
            raise TypeError(f"@declare({cid!r}) must decorate a @wp.func (put it above @wp.func)")
        eq = Equation(cid, name or func.key, c, func, None, args=tuple(args), options=tuple(options),
                      outputs=tuple(outputs), references=tuple(references), summary=summary, check=check,
                      make_warp=make_warp, make_c=make_c, also=tuple(also), derived=dict(derived or {}),
                      extra=dict(extra or {}), ulp=ulp, samples=samples, nonfinite=nonfinite)
        if make_warp is None:
            params = warp_parameters(func)
            expected = [a.name for a in args] + [o.name for o in options]
            seen = [eq.derived[p][0] if p in eq.derived else p for p in params]
            if seen != expected:
                raise TypeError(f"{cid}: the parameters of {func.key} {params} do not match the declared arguments "
                                f"and options {expected} (derived: {eq.derived})")
            typed = []
            for a in args:
                if a.name in eq.derived.values() or any(a.name == src for src, _ in eq.derived.values()):
                    typed.append(a if a.dtype else replace(a, dtype="int32"))
                    continue
                dtype, length = _type_of(_hints(fn)[a.name])
                if a.dtype is not None and a.dtype != dtype:
                    raise TypeError(f"{cid}: argument {a.name} is declared {a.dtype} but annotated {dtype}")
                typed.append(replace(a, dtype=dtype, length=length))
            eq.args = tuple(typed)
            types = _return_types(fn, len(outputs))
            if len(types) != len(outputs):
                raise TypeError(f"{cid}: {func.key} returns {len(types)} values, declared outputs {outputs}")
            eq.out_specs = tuple(Output(n, d, k) for n, (d, k) in zip(outputs, types))
            eq.kernel = _generate_kernel(func, eq)
        register(eq)
        func.equation = eq
        return func

    return wrap


def _split_ref(ref: str, what: str) -> tuple[str, str]:
    """(module, function) of a ``"module:function"`` reference; ValueError naming ``what`` when malformed."""
    module, sep, name = ref.partition(":")
    if not sep or not all(p.isidentifier() for p in module.split(".")) or not name.isidentifier():
        raise ValueError(f"{what} must be a callable or a 'module:function' string (e.g. "
                         f"'pywarp.rain.particles:simulate_warp'), got {ref!r}")
    return module, name


def evaluator(eq: Equation, impl: str) -> Callable | None:
    """``eq.make_warp`` (``impl="warp"``) or ``eq.make_c`` (``"c"``) as a callable: a ``"module:function"`` string is
    imported here, on first use, so that the topic module declaring it needs no import of the (scene-level) module
    that holds it. ImportError/AttributeError name the entry and the reference."""
    import importlib

    label = "make_warp" if impl == "warp" else "make_c"
    ev = getattr(eq, label)
    if not isinstance(ev, str):
        return ev
    module, name = _split_ref(ev, f"{eq.id}: {label}")
    try:
        mod = importlib.import_module(module)
    except ImportError as exc:
        raise ImportError(f"{eq.id}: {label} {ev!r}: module {module!r} cannot be imported ({exc})") from exc
    fn = getattr(mod, name, None)
    if not callable(fn):
        raise AttributeError(f"{eq.id}: {label} {ev!r}: {module} has no function {name!r}")
    return fn


# --- lookup ----------------------------------------------------------------------------------------------------------

def registry() -> dict[str, Equation]:
    """All registered entries, by ID in natural order (imports every topic module on first use)."""
    import importlib

    importlib.import_module("pywarp.kernels").load_all()  # topic modules register on import
    return dict(sorted(_REGISTRY.items(), key=lambda kv: sort_key(kv[0])))


def entries() -> list[Equation]:
    """Every registered function once (an entry answering several IDs appears once)."""
    seen, out = set(), []
    for eq in registry().values():
        if id(eq) not in seen:
            seen.add(id(eq))
            out.append(eq)
    return out


def get(cid: str) -> Equation:
    reg = registry()
    if cid not in reg:
        known = catalogue()["ids"]
        if cid in known:
            raise NotImplementedError(f"{cid} ({known[cid]['title']}) is catalogued but not implemented yet")
        raise KeyError(f"unknown catalogue ID {cid!r}; see `pywarp equations`")
    return reg[cid]


# --- evaluators ------------------------------------------------------------------------------------------------------

def _finish(eq: Equation, shape: tuple, outs: list[np.ndarray]):
    res = []
    for spec, o in zip(eq.out_specs, outs):
        full = shape + ((spec.length,) if spec.length > 1 else ())
        o = o.reshape(full)
        res.append(o[()] if full == () else o)
    return res[0] if len(res) == 1 else tuple(res)


def _flat(arg: Arg, x: np.ndarray, shape: tuple) -> np.ndarray:
    full = shape + ((arg.length,) if arg.length > 1 else ())
    return np.ascontiguousarray(np.broadcast_to(x, full).reshape((-1,) + full[len(shape):]))


def _warp_eval(eq: Equation, device: str | None):
    import warp as wp


    from .runtime import resolve_device

    dev = resolve_device(device)
    wp_types = {("float32", 1): wp.float32, ("int32", 1): wp.int32, ("uint32", 1): wp.uint32,
                ("float32", 2): wp.vec2, ("float32", 3): wp.vec3, ("float32", 4): wp.vec4}
    params = warp_parameters(eq.warp)
    arg_index = {a.name: k for k, a in enumerate(eq.args)}
    opt_index = {o.name: k for k, o in enumerate(eq.options)}

    def call(*args, **kwargs):
        shape, arrays, opts = eq.bind(*args, **kwargs)
        n = int(math.prod(shape))
        flat = [_flat(a, x, shape) for a, x in zip(eq.args, arrays)]
        outs = [np.empty((n,) + ((o.length,) if o.length > 1 else ()), dtype=_NP[o.dtype]) for o in eq.out_specs]
        if n:
            # launch once per distinct value of each argument a derived table is computed from
            sources = sorted({src for src, _ in eq.derived.values()}, key=lambda s: arg_index[s])
            if sources:
                keys = np.stack([flat[arg_index[s]].astype(np.int64) for s in sources], axis=1)
                groups = np.unique(keys, axis=0)
            else:
                groups = [()]
            for g in groups:
                if sources:
                    sel = np.all(keys == g, axis=1)
                    value_of = {s: int(v) for s, v in zip(sources, g)}
                else:
                    sel = slice(None)
                    value_of = {}
                m = n if not sources else int(np.count_nonzero(sel))
                inputs = []
                for p in params:
                    if p in eq.derived:
                        src, make = eq.derived[p]
                        inputs.append(make(value_of[src], dev))
                    elif p in opt_index:
                        inputs.append(opts[opt_index[p]])
                    else:
                        a = eq.args[arg_index[p]]
                        inputs.append(wp.array(flat[arg_index[p]][sel], dtype=wp_types[(a.kind(), a.length)],
                                               device=dev))
                res = [wp.empty(m, dtype=wp_types[(o.dtype, o.length)], device=dev) for o in eq.out_specs]
                wp.launch(eq.kernel, dim=m, inputs=inputs, outputs=res, device=dev)
                for o, r in zip(outs, res):
                    o[sel] = r.numpy()
        return _finish(eq, shape, outs)

    return call


def c_layout(eq: Equation):
    """How the C function takes ``eq``'s outputs: (number of out-pointers, whether the return value is the first
    output, whether the return value is a ``ccl_status`` to check). Raises ``TypeError`` if the arity is wrong."""
    from .binding import ffi, lib

    ct = ffi().typeof(getattr(lib(), eq.c_symbol))
    n_in = len(eq.args) + len(eq.options)
    n_ptr = len(ct.args) - n_in
    n_out = len(eq.out_specs)
    returns = ct.result.cname != "void"
    status = ct.result.cname == "ccl_status" or ct.result.cname == "enum ccl_status"
    if n_ptr == n_out:
        return n_ptr, False, status
    if n_ptr == n_out - 1 and returns and not status:
        return n_ptr, True, False
    raise TypeError(f"{eq.id}: {eq.c_symbol} takes {len(ct.args)} parameters and returns {ct.result.cname}; "
                    f"expected {n_in} arguments and options, then the {n_out} outputs {eq.outputs} "
                    "(the first may be the return value)")


def _c_eval(eq: Equation):
    from .binding import ffi as _ffi, lib as _lib, status_error

    if eq.c_symbol is None:
        raise NotImplementedError(f"{eq.id} has no C implementation")
    f, lb = _ffi(), _lib()
    fn = getattr(lb, eq.c_symbol)
    n_ptr, ret_first, status = c_layout(eq)
    ptr_specs = eq.out_specs[1:] if ret_first else eq.out_specs
    ctype = {1: None, 2: "ccl_vec2", 3: "ccl_vec3", 4: "ccl_vec4"}
    c_scalar = {"float32": "float", "int32": "int", "uint32": "uint32_t"}

    def ptr_type(o: Output) -> str:
        return (ctype[o.length] if o.length > 1 else c_scalar[o.dtype]) + " *"

    def to_c(a: Arg, v):
        if a.length > 1:
            return f.new(ctype[a.length] + " *", [float(c) for c in v])[0]
        return v.item()

    def from_c(o: Output, v):
        if o.length > 1:
            return [getattr(v, c) for c in _COMPONENTS[: o.length]]
        return v

    def call(*args, **kwargs):
        shape, arrays, opts = eq.bind(*args, **kwargs)
        n = int(math.prod(shape))
        flat = [_flat(a, x, shape) for a, x in zip(eq.args, arrays)]
        outs = [np.empty((n,) + ((o.length,) if o.length > 1 else ()), dtype=_NP[o.dtype]) for o in eq.out_specs]
        ptrs = [f.new(ptr_type(o)) for o in ptr_specs]
        for i in range(n):
            r = fn(*(to_c(a, x[i]) for a, x in zip(eq.args, flat)), *opts, *ptrs)
            if status:
                status_error(r, f"{eq.c_symbol}")
            k = 0
            if ret_first:
                outs[0][i] = from_c(eq.out_specs[0], r)
                k = 1
            for o, p in zip(eq.out_specs[k:], ptrs):
                outs[k][i] = from_c(o, p[0])
                k += 1
        return _finish(eq, shape, outs)

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
        fn = evaluator(eq, "warp")(eq, device) if eq.make_warp else _warp_eval(eq, device)
    else:
        fn = evaluator(eq, "c")(eq) if eq.make_c else _c_eval(eq)
    fn.__name__ = eq.name
    fn.__qualname__ = eq.name
    fn.__doc__ = eq.docstring()
    if not (eq.make_warp or eq.make_c):
        fn.__signature__ = eq.signature()
    fn.equation = eq
    return fn


def missing(seed: str | None = None, computational: bool | None = None) -> list[tuple[str, dict]]:
    """Catalogued IDs (of ``seed``, or all) that have no registered implementation, with their catalogue entry and
    ``reason``: why it is not computational, or None when it is simply not implemented yet. ``computational=True``
    keeps only equations, algorithms, code listings and tables; ``False`` only the others."""
    from .catalogue import COMPUTATIONAL_KINDS

    reg = registry()
    rows = []
    for cid, e in sorted(catalogue()["ids"].items(), key=lambda kv: sort_key(kv[0])):
        if cid in reg or (seed is not None and e["seed"] != seed):
            continue
        if computational is not None and (e["kind"] in COMPUTATIONAL_KINDS) != computational:
            continue
        rows.append((cid, {**e, "reason": not_computational_reason(cid)}))
    return rows

