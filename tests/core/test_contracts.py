"""Contract tests generated from the registry: every declared entry, the same checks.

For each element-wise entry (its evaluation kernel generated from the Warp function):
  * the Warp parameters are the declared arguments then options (a derived parameter stands for its argument);
  * the C function takes the arguments, the options and the outputs (the first output may be the return value);
  * the Python name is the C name without ``ccl_``;
  * every closed finite domain edge is accepted and evaluates, the first value beyond it (or an open edge) is refused
    with a ValueError naming the argument; NaN and infinities are refused for finite arguments;
  * scalars give scalars (or one vector), arguments broadcast like NumPy;
  * C and Warp agree on seeded samples of every argument's domain, for every value of every option, within the
    entry's declared ulp bound.
Topic tests (tests/kernels/) add the properties, closed forms, independent values and errata.
"""
from __future__ import annotations

import numpy as np
import pytest
from helpers import assert_twins_agree

import pywarp
from pywarp.core.registry import c_layout, entries, warp_parameters

ALL = entries()
ELEMENTWISE = [eq for eq in ALL if eq.elementwise]
N_SAMPLES = 64
#: arguments a derived table is computed from (a Perlin seed -> its permutation table): a few distinct values, since
#: the evaluator launches once per value
DERIVED_VALUES = 3


def _ids(eqs):
    return [eq.id for eq in eqs]


def _derived_sources(eq) -> set[str]:
    return {src for src, _ in eq.derived.values()}


def _draw(arg, rng, n, derived=False):
    """n values from the argument's domain (its sample_range where given, else the domain clipped to [-100, 100]);
    open bounds are kept out of reach."""
    lo, hi = arg.sample_range if arg.sample_range else (arg.lo, arg.hi)
    lo = -100.0 if lo is None else max(float(lo), -100.0) if arg.sample_range is None else float(lo)
    hi = 100.0 if hi is None else min(float(hi), 100.0) if arg.sample_range is None else float(hi)
    if arg.kind() in ("int32", "uint32"):
        lo_i = int(np.ceil(lo)) + (1 if arg.lo_open and arg.lo is not None and np.ceil(lo) == arg.lo else 0)
        hi_i = int(np.floor(hi)) - (1 if arg.hi_open and arg.hi is not None and np.floor(hi) == arg.hi else 0)
        if derived:
            return rng.choice(np.arange(lo_i, min(hi_i, lo_i + DERIVED_VALUES - 1) + 1), size=n)
        return rng.integers(lo_i, hi_i + 1, size=n)
    shape = (n, arg.length) if arg.length > 1 else (n,)
    span = hi - lo
    x = lo + span * (0.001 + 0.998 * rng.random(shape))  # strictly inside: open bounds are never hit
    if arg.length > 1 and (arg.unit or arg.nonzero):
        norm = np.linalg.norm(x, axis=-1, keepdims=True)
        x = np.where(norm == 0.0, 1.0, x)
        if arg.unit:
            x = x / np.linalg.norm(x, axis=-1, keepdims=True)
    return x.astype(np.float32)


def samples(eq, rng, n=N_SAMPLES) -> dict:
    """Valid inputs for every argument of ``eq``: the entry's own ``samples`` where it declares one (arguments
    tied by a cross-argument check), the argument's domain otherwise."""
    own = eq.samples(rng, n) if eq.samples else {}
    src = _derived_sources(eq)
    return {a.name: np.asarray(own[a.name]) if a.name in own else _draw(a, rng, n, derived=a.name in src)
            for a in eq.args}


def _one(eq, vals, k=0):
    """The k-th sample of every argument (a scalar, or one vector)."""
    return {name: v[k] for name, v in vals.items()}


def _edges(arg):
    """(accepted, refused) edge values of one argument."""
    acc, ref = [], []
    is_int = arg.kind() in ("int32", "uint32")
    for bound, is_open, down in ((arg.lo, arg.lo_open, True), (arg.hi, arg.hi_open, False)):
        if bound is None or not np.isfinite(bound):
            continue
        if is_int:
            b = int(bound)
            acc_v, ref_v = (b, b - 1) if down else (b, b + 1)
            if is_open:
                acc_v, ref_v = (b + 1, b) if down else (b - 1, b)
            limits = {"int32": (-(2 ** 31), 2 ** 31 - 1), "uint32": (0, 2 ** 32 - 1)}[arg.kind()]
            acc.append(acc_v)
            if limits[0] <= ref_v <= limits[1]:
                ref.append(ref_v)
            continue
        b = np.float32(bound)
        outward = np.nextafter(b, np.float32(-np.inf if down else np.inf))
        inward = np.nextafter(b, np.float32(np.inf if down else -np.inf))
        if is_open:
            acc.append(float(inward))
            ref.append(float(b))
        else:
            acc.append(float(b))
            ref.append(float(outward))
    return acc, ref


def _with(eq, base, name, value):
    arg = next(a for a in eq.args if a.name == name)
    if arg.length > 1:
        value = np.full(arg.length, value, dtype=np.float64)
    return {**base, name: value}


@pytest.mark.parametrize("eq", ELEMENTWISE, ids=_ids(ELEMENTWISE))
def test_warp_parameters_match_the_declaration(eq):
    params = [eq.derived[p][0] if p in eq.derived else p for p in warp_parameters(eq.warp)]
    assert params == [a.name for a in eq.args] + [o.name for o in eq.options]


@pytest.mark.parametrize("eq", [e for e in ALL if e.c_symbol], ids=_ids([e for e in ALL if e.c_symbol]))
def test_c_symbol_exists_and_is_named_after_the_python_name(eq):
    from pywarp.core.binding import lib

    assert hasattr(lib(), eq.c_symbol), f"{eq.c_symbol} is not exported by libcclouds"
    assert eq.c_symbol == "ccl_" + eq.name, f"{eq.id}: Python name {eq.name!r} vs C symbol {eq.c_symbol!r}"


@pytest.mark.parametrize("eq", [e for e in ELEMENTWISE if e.c_symbol], ids=_ids([e for e in ELEMENTWISE if e.c_symbol]))
def test_c_arity_is_arguments_options_outputs(eq):
    n_ptr, ret_first, _ = c_layout(eq)  # raises TypeError naming the mismatch
    assert n_ptr + ret_first == len(eq.outputs)


@pytest.mark.parametrize("eq", ELEMENTWISE, ids=_ids(ELEMENTWISE))
def test_domain_edges_accepted_and_just_outside_refused(eq):
    rng = np.random.default_rng(8)
    base = _one(eq, samples(eq, rng))
    fn = pywarp.equation(eq.id)
    checked = 0
    for arg in eq.args:
        acc, ref = _edges(arg)
        for v in acc:
            fn(**_with(eq, base, arg.name, v))  # must not raise
            checked += 1
        for v in ref:
            with pytest.raises(ValueError, match=rf"\b{arg.name}\b"):
                fn(**_with(eq, base, arg.name, v))
            checked += 1
    if not any(_edges(a) != ([], []) for a in eq.args):
        assert checked == 0  # an entry without bounded arguments has no edge to check; the others are covered


@pytest.mark.parametrize("eq", ELEMENTWISE, ids=_ids(ELEMENTWISE))
def test_nan_and_infinity_refused(eq):
    rng = np.random.default_rng(9)
    base = _one(eq, samples(eq, rng))
    fn = pywarp.equation(eq.id)
    for arg in eq.args:
        if arg.kind() != "float32" or not arg.finite:
            continue
        for bad in (np.nan, np.inf, -np.inf):
            with pytest.raises(ValueError, match=rf"\b{arg.name}\b"):
                fn(**_with(eq, base, arg.name, bad))
    for arg in eq.args:
        if arg.kind() in ("int32", "uint32"):
            with pytest.raises(ValueError, match=rf"\b{arg.name}\b"):
                fn(**{**base, arg.name: 2 ** 40})
            with pytest.raises((ValueError, TypeError), match=rf"\b{arg.name}\b"):
                fn(**{**base, arg.name: 0.5})


@pytest.mark.parametrize("eq", ELEMENTWISE, ids=_ids(ELEMENTWISE))
def test_scalars_give_scalars_and_arguments_broadcast(eq):
    rng = np.random.default_rng(10)
    vals = samples(eq, rng, n=12)
    fn = pywarp.equation(eq.id)
    out = fn(**_one(eq, vals))
    outs = out if isinstance(out, tuple) else (out,)
    for spec, o in zip(eq.out_specs, outs):
        assert np.shape(o) == ((spec.length,) if spec.length > 1 else ()), spec.name
    if not eq.args:
        return
    # the first argument along a column, the others along a row: the result has the outer shape
    first = eq.args[0]
    kw = {}
    for k, a in enumerate(eq.args):
        v = vals[a.name]
        if k == 0:
            v = v[:3].reshape((3, 1) + v.shape[1:])
        else:
            v = v[:4].reshape((1, 4) + v.shape[1:]) if a.name not in _derived_sources(eq) else v[:1].reshape(
                (1, 1) + v.shape[1:])
        kw[a.name] = v
    shape = (3, 4) if len(eq.args) > 1 and any(a.name not in _derived_sources(eq) for a in eq.args[1:]) else (3, 1)
    if eq.check is not None and eq.samples is not None:
        # arguments tied by a check are drawn together: broadcast one consistent sample against itself instead
        kw = {a.name: vals[a.name][:3].reshape((3,) + vals[a.name].shape[1:]) for a in eq.args}
        shape = (3,)
    out = fn(**kw)
    outs = out if isinstance(out, tuple) else (out,)
    for spec, o in zip(eq.out_specs, outs):
        assert o.shape == shape + ((spec.length,) if spec.length > 1 else ()), (spec.name, o.shape, first.name)
        assert o.dtype == {"float32": np.float32, "int32": np.int32, "uint32": np.uint32}[spec.dtype]


@pytest.mark.parametrize("eq", [e for e in ELEMENTWISE if e.c_symbol], ids=_ids([e for e in ELEMENTWISE if e.c_symbol]))
def test_c_and_warp_agree_on_samples_of_the_domain(eq):
    rng = np.random.default_rng(11)
    vals = samples(eq, rng)
    assert_twins_agree(eq.id, **vals)
    for opt in eq.options:
        for choice in opt.choices:
            if choice != opt.default:
                assert_twins_agree(eq.id, **vals, **{opt.name: choice})


@pytest.mark.parametrize("eq", [e for e in ALL if not e.elementwise], ids=_ids([e for e in ALL if not e.elementwise]))
def test_entries_that_are_not_elementwise_have_both_evaluators(eq):
    """The generated checks above run for every element-wise entry; the others bring a Warp evaluator and, where
    the C function exists, a C evaluator (their topic tests compare the two)."""
    assert eq.make_warp is not None, f"{eq.id} has neither a generated kernel nor its own evaluator"
    if eq.c_symbol:
        assert eq.make_c is not None, f"{eq.id}: C function {eq.c_symbol} but no C evaluator"
