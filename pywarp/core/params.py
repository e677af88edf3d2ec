"""Parameter specs: every settings field is declared once, with its unit, default, domain, doc, the reason for the
default and what a change invalidates.

A settings class is a frozen dataclass deriving from :class:`Settings` whose fields are made by :func:`param`::

    @dataclass(frozen=True)
    class SkySettings(Settings):
        turbidity: float = param(2.5, unit="", lo=2.0, hi=10.0, doc="Preetham turbidity",
                                 reason="a clear day", invalidates="sky")

From the spec come:

* validation -- one mechanism, run by ``__post_init__`` on construction and on ``dataclasses.replace`` (settings are
  immutable). The wording is the equation registry's: ``turbidity must be in [2, 10], got 11.0``,
  ``sky must be one of 'preetham', 'gradient', got 'hosek'``, ``coverage must be finite (no NaN or Inf), got nan``.
  A wrong type raises ``TypeError`` (a bool or a float for an integer field, a string for a number), a value outside
  the domain ``ValueError``; integers must fit their C type (int32 or uint32), floats the float32 range;
* the command-line options and their ``--help`` (:func:`add_options`, :func:`from_options`): unit, default, range
  or choices are shown, never a bare ``STR``;
* :func:`specs` lists them (the viewer's panels and the docs' settings tables are built from it);
* the C parameter a field reaches (``c="fog_density"``; choices by ``c_enum``, {choice: C enum name}):
  :mod:`pywarp.core.cbridge` builds the C struct, its check and the Warp struct from these.

What a change of a field makes stale (``invalidates``) is one of the names its class declares in ``INVALIDATES``
(each scene's technique acts on its own names).
"""
from __future__ import annotations

import argparse
import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

#: Kinds of values: ``int`` (int32), ``uint32``, ``float`` (float32), ``bool``, ``str``, ``floats`` (a fixed-length
#: tuple of float32), ``mapping`` (a dict; a command-line option only where ``cli`` names one: ``--opt KEY=VALUE``,
#: repeatable, the values kept as strings for the settings' own check to parse).
KINDS = ("int", "uint32", "float", "bool", "str", "floats", "mapping")

_INT_RANGE = {"int": (-(2 ** 31), 2 ** 31 - 1), "uint32": (0, 2 ** 32 - 1)}
_C_INT = {"int": "int32", "uint32": "uint32"}
_F32_MAX = float(np.finfo(np.float32).max)


def did_you_mean(word: str, candidates) -> str:
    """`` (did you mean --width?)`` for the closest of ``candidates`` to a misspelt ``word``; empty if none is close
    (the command line's options and choices, the settings' choices, the scene names)."""
    import difflib

    close = difflib.get_close_matches(str(word), [str(c) for c in candidates], n=1, cutoff=0.75)
    return f" (did you mean {close[0]}?)" if close else ""


def _fmt(v) -> str:
    return str(int(v)) if isinstance(v, (int, np.integer)) else f"{v:g}"


@dataclass(frozen=True)
class Param:
    """The spec of one settings field (see the module docstring). ``name`` is filled in by :func:`specs`."""

    default: Any
    unit: str = ""
    doc: str = ""
    reason: str = ""
    invalidates: str = "nothing"
    kind: str = "float"
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    choices: tuple | None = None
    optional: bool = False
    pow2: bool = False
    odd: bool = False
    length: int | None = None
    #: extra check run right after the domain check, in validation order: ``check(obj, name, value)`` raises
    #: ValueError naming the field (cross-field constraints such as ``layer_top_km > layer_base_km``)
    check: Callable | None = None
    #: replaces the generic conversion for a field with its own rules (must raise TypeError/ValueError naming it)
    convert: Callable | None = None
    #: command-line option (default ``--`` + the name with dashes); ``None``: not an option
    cli: str | None = ""
    #: what ``--help`` shows as the default where the value itself says little (e.g. None -> "one per core")
    default_text: str = ""
    #: group of related fields (the help's sections, the viewer's panels)
    group: str = ""
    #: the C struct field this value is written to (:mod:`pywarp.core.cbridge`); "" if none
    c: str = ""
    #: choices -> C enum constant names (a field with choices and ``c``)
    c_enum: dict | None = None
    name: str = ""

    # --- the domain ----------------------------------------------------------------------------------------------
    def domain(self) -> str:
        """The valid values in words: ``[2, 10]``, ``(0, inf)``, ``one of 'a', 'b'``, ``a power of two in [4, 512]``."""
        if self.choices is not None:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        if self.kind == "bool":
            return "True or False"
        if self.kind == "str":
            return "a string"
        if self.kind == "mapping":
            return "a dict"
        if self.kind in _INT_RANGE:
            lo = _INT_RANGE[self.kind][0] if self.lo is None else self.lo
            hi = _INT_RANGE[self.kind][1] if self.hi is None else self.hi
            rng = f"[{_fmt(lo)}, {_fmt(hi)}]"
            if self.pow2:
                return f"a power of two in {rng}"
            if self.odd:
                return f"an odd integer in {rng}"
            return rng
        lo = "-inf" if self.lo is None else _fmt(self.lo)
        hi = "inf" if self.hi is None else _fmt(self.hi)
        return (f"{'(' if self.lo_open or self.lo is None else '['}{lo}, "
                f"{hi}{')' if self.hi_open or self.hi is None else ']'}")

    def _range_error(self, name: str, value, shown) -> ValueError:
        if self.kind in _INT_RANGE and self.lo is None and self.hi is None:
            return ValueError(f"{name} must be in {self.domain()} ({_C_INT[self.kind]}), got {shown}")
        return ValueError(f"{name} must be {'' if self.pow2 or self.odd else 'in '}{self.domain()}, got {shown}")

    def validate(self, value, name: str | None = None, shown: str | None = None):
        """``value`` checked against the spec and normalised (Python int/float/bool/str, tuple for ``floats``).
        ``shown``: how the value is quoted in the error (default its repr), e.g. the text typed on the command line."""
        name = name or self.name
        if value is None and self.optional:
            return None
        if self.convert is not None:
            return self.convert(value, name)
        shown = repr(value) if shown is None else shown
        k = self.kind
        if k == "bool":
            if not isinstance(value, (bool, np.bool_)):
                raise TypeError(f"{name} must be True or False, got {shown}")
            return bool(value)
        if k == "str":
            if not isinstance(value, str):
                raise (ValueError if self.choices else TypeError)(
                    f"{name} must be {self.domain() if self.choices else 'a string'}, got {shown}")
            if self.choices is not None and value not in self.choices:
                raise ValueError(f"{name} must be {self.domain()}, got {shown}{did_you_mean(value, self.choices)}")
            return value
        if k == "mapping":
            if not isinstance(value, dict):
                raise TypeError(f"{name} must be a dict, got {shown}")
            return value
        if k == "floats":
            try:
                items = tuple(value)
            except TypeError:
                raise TypeError(f"{name} must be a sequence of {self.length} numbers, got {shown}") from None
            if self.length is not None and len(items) != self.length:
                raise ValueError(f"{name} must hold {self.length} numbers, got {len(items)}")
            return tuple(self._float(v, name, repr(v)) for v in items)
        if k in _INT_RANGE:
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
                raise TypeError(f"{name} must be an integer, got {shown}")
            v = int(value)
            c_lo, c_hi = _INT_RANGE[k]
            lo = c_lo if self.lo is None else max(self.lo, c_lo)
            hi = c_hi if self.hi is None else min(self.hi, c_hi)
            if not lo <= v <= hi or (self.pow2 and v & (v - 1)) or (self.odd and v % 2 == 0):
                raise self._range_error(name, v, shown)
            return v
        v = self._float(value, name, shown)
        lo_bad = self.lo is not None and (v <= self.lo if self.lo_open else v < self.lo)
        hi_bad = self.hi is not None and (v >= self.hi if self.hi_open else v > self.hi)
        if lo_bad or hi_bad:
            raise self._range_error(name, v, shown)
        return v

    @staticmethod
    def _float(value, name: str, shown: str) -> float:
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
            raise TypeError(f"{name} must be a number, got {shown}")
        v = float(value)
        if not math.isfinite(v):
            raise ValueError(f"{name} must be finite (no NaN or Inf), got {shown}")
        if abs(v) > _F32_MAX:
            raise ValueError(f"{name} must be within the float32 range (|x| <= {_F32_MAX:.4g}), got {shown}")
        return v

    # --- the command line ----------------------------------------------------------------------------------------
    @property
    def option(self) -> str | None:
        if self.cli is None or self.kind == "floats" or (self.kind == "mapping" and not self.cli):
            return None
        return self.cli or "--" + self.name.replace("_", "-")

    def parse(self, text: str, option: str | None = None):
        """The value of a command-line string, validated; errors name ``option``."""
        option = option or self.option or self.name
        if self.kind == "mapping":  # the KEY=VALUE items of a repeated option
            items = [text] if isinstance(text, str) else list(text)
            out = {}
            for item in items:
                key, eq, value = item.partition("=")
                if not eq or not key.strip():
                    raise ValueError(f"{option} must be KEY=VALUE, got {item!r}")
                out[key.strip()] = value.strip()
            return self.validate(out, option)
        if self.optional and text.strip().lower() in ("none", "auto"):
            return None
        if self.kind in _INT_RANGE:
            try:
                v = int(text.strip(), 10)
            except ValueError:
                raise ValueError(f"{option} must be an integer, got {text!r}") from None
        elif self.kind == "float":
            try:
                v = float(text)
            except ValueError:
                raise ValueError(f"{option} must be a number, got {text!r}") from None
        else:
            v = text
        return self.validate(v, option, shown=text if self.kind in ("int", "uint32", "float") else repr(text))

    def metavar(self) -> str:
        if self.choices is not None:
            return "{" + ",".join(self.choices) + "}"
        return {"int": "INT", "uint32": "INT", "float": "FLOAT", "str": "NAME", "mapping": "KEY=VALUE"}.get(
            self.kind, "VALUE")

    def help(self, default: Any = dataclasses.MISSING) -> str:
        """``--help`` text: doc [unit]; range or choices; default."""
        d = self.default if default is dataclasses.MISSING else default
        parts = [self.doc.rstrip(".")]
        if self.unit:
            parts[0] += f" [{self.unit}]"
        if self.choices is not None:
            parts.append("choices: " + ", ".join(self.choices))
        elif self.kind == "float" and self.lo is None and self.hi is None:
            parts.append("any finite value")
        elif self.kind not in ("bool", "str"):
            parts.append(self.domain())
        shown = self.default_text if (self.default_text and d == self.default) else (
            "on" if d is True else "off" if d is False else _fmt(d) if isinstance(d, (int, float)) else d)
        parts.append(f"default: {shown}")
        return "; ".join(parts).replace("%", "%%")


class Settings:
    """Base of the settings dataclasses: validates every :func:`param` field on construction (and so on
    ``dataclasses.replace``), in declaration order or ``_validation_order``, and normalises the values."""

    #: field names in the order they are checked (default: declaration order); lets a class report the same first
    #: invalid field as the C check it mirrors
    _validation_order: tuple = ()

    #: What a change of a field can make stale (its spec's ``invalidates``): ``nothing`` (the next frame simply uses
    #: the new value), ``size`` (the frame buffers are reallocated), ``device`` (everything is rebuilt on the new
    #: device); a class adds its own (e.g. ``textures``, ``sky``), which its technique acts on.
    INVALIDATES: tuple = ("nothing", "size", "device")

    def __post_init__(self):
        by_name = {p.name: p for p in specs(type(self))}
        order = list(self._validation_order) + [n for n in by_name if n not in self._validation_order]
        for n in order:
            p = by_name[n]
            v = p.validate(getattr(self, n), n)
            object.__setattr__(self, n, v)
            if p.check is not None:
                p.check(self, n, v)
        self._check()

    def _check(self) -> None:
        """Cross-field constraints of the class beyond the per-field hooks (override; raise ValueError)."""

    def changed(self, other) -> set[str]:
        """Names of the fields whose values differ from ``other`` (same class)."""
        return {f.name for f in dataclasses.fields(self) if getattr(self, f.name) != getattr(other, f.name)}

    def invalidated(self, other) -> set[str]:
        """What a change from ``other`` to ``self`` invalidates (names of the class's ``INVALIDATES`` except
        'nothing')."""
        by_name = {p.name: p for p in specs(type(self))}
        return {by_name[n].invalidates for n in self.changed(other) if n in by_name} - {"nothing"}


def param(default, *, unit: str = "", doc: str, reason: str, invalidates: str = "nothing", kind: str | None = None,
          lo=None, hi=None, lo_open: bool = False, hi_open: bool = False, choices=None, optional: bool = False,
          pow2: bool = False, odd: bool = False, length: int | None = None, check: Callable | None = None,
          convert: Callable | None = None, cli: str | None = "", default_text: str = "", group: str = "",
          c: str = "", c_enum: dict | None = None):
    """A dataclass field carrying a :class:`Param` (see the module docstring). ``kind`` is taken from the default
    (``bool``, ``int``, ``float``, ``str``, ``tuple`` -> ``floats``, ``dict`` -> ``mapping``) unless given.
    ``invalidates`` is checked against the class's ``INVALIDATES`` by :func:`specs`."""
    if kind is None:
        kind = ("bool" if isinstance(default, bool) else "int" if isinstance(default, int)
                else "float" if isinstance(default, float) else "str" if isinstance(default, str)
                else "floats" if isinstance(default, tuple) else "mapping" if isinstance(default, dict) else None)
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(map(repr, KINDS))}, got {kind!r}")
    if not doc or not reason:
        raise ValueError("every parameter needs a doc and the reason for its default")
    if kind == "floats" and length is None:
        length = len(default)
    if c_enum is not None and (not c or choices is None or set(c_enum) != set(choices)):
        raise ValueError(f"c_enum must map every choice {tuple(choices or ())} of a field with c=, got {c_enum!r}")
    p = Param(default=default, unit=unit, doc=doc, reason=reason, invalidates=invalidates, kind=kind, lo=lo, hi=hi,
              lo_open=lo_open, hi_open=hi_open, choices=None if choices is None else tuple(choices),
              optional=optional, pow2=pow2, odd=odd, length=length, check=check, convert=convert, cli=cli,
              default_text=default_text, group=group, c=c, c_enum=None if c_enum is None else dict(c_enum))
    if kind == "mapping":
        return dataclasses.field(default_factory=lambda: dict(default), metadata={"param": p})
    return dataclasses.field(default=default, metadata={"param": p})


def inherit(cls, name: str, **changes):
    """A field with the spec of ``cls.<name>`` (declared once, there), with ``changes`` (e.g. ``cli``, ``group``,
    ``default`` with its ``reason``)."""
    p = {q.name: q for q in specs(cls)}[name]
    p = dataclasses.replace(p, name="", **changes)
    return dataclasses.field(default=p.default, metadata={"param": p})


def specs(cls) -> tuple[Param, ...]:
    """The :class:`Param` of every field of a settings class (or instance), in declaration order, named."""
    if not isinstance(cls, type):
        cls = type(cls)
    cached = cls.__dict__.get("_specs_cache")
    if cached is not None:
        return cached
    out = tuple(dataclasses.replace(f.metadata["param"], name=f.name) for f in dataclasses.fields(cls)
                if "param" in f.metadata)
    names = getattr(cls, "INVALIDATES", Settings.INVALIDATES)
    for p in out:
        if p.invalidates not in names:
            raise ValueError(f"{cls.__name__}.{p.name}: invalidates must be one of {', '.join(map(repr, names))}, "
                             f"got {p.invalidates!r}")
    setattr(cls, "_specs_cache", out)
    return out


# --- the command line ------------------------------------------------------------------------------------------------

def add_options(parser: argparse.ArgumentParser, cls, *, defaults: dict | None = None, exclude=(), notes=None,
                dest_prefix: str = "") -> dict[str, str]:
    """Add one option per field of ``cls`` that has one (grouped by ``Param.group``). Values are parsed and
    validated by :func:`from_options` (so that the errors name the option, in the registry's wording); options not
    given are absent from the namespace. ``defaults`` overrides the defaults shown (and used) per field; ``notes``
    appends text to a field's help. Returns {field name: option string}."""
    defaults = defaults or {}
    notes = notes or {}
    groups: dict[str, argparse._ArgumentGroup] = {}
    options = {}
    for p in specs(cls):
        opt = p.option
        if opt is None or p.name in exclude:
            continue
        target = parser
        if p.group:
            if p.group not in groups:
                groups[p.group] = parser.add_argument_group(p.group)
            target = groups[p.group]
        text = p.help(defaults.get(p.name, dataclasses.MISSING))
        if p.name in notes:
            text += "; " + notes[p.name].replace("%", "%%")
        dest = dest_prefix + p.name
        if p.kind == "bool":
            target.add_argument(opt, dest=dest, action=argparse.BooleanOptionalAction, default=argparse.SUPPRESS,
                                help=text)
        else:
            target.add_argument(opt, dest=dest, default=argparse.SUPPRESS, metavar=p.metavar(), help=text)
        options[p.name] = opt
    return options


def from_options(cls, args: argparse.Namespace, *, defaults: dict | None = None, extra: dict | None = None,
                 dest_prefix: str = ""):
    """Settings of ``cls`` from the options :func:`add_options` added: every given option parsed and validated
    (ValueError naming the option), ``defaults`` for the others, then the class's own checks (an error naming a
    field is reworded to name its option)."""
    values = dict(defaults or {})
    options = {}
    for p in specs(cls):
        opt = p.option
        if opt is None:
            continue
        options[p.name] = opt
        if hasattr(args, dest_prefix + p.name):
            raw = getattr(args, dest_prefix + p.name)
            values[p.name] = raw if p.kind == "bool" else p.parse(raw, opt)
    values.update(extra or {})
    try:
        return cls(**values)
    except (ValueError, TypeError) as exc:
        raise type(exc)(option_message(str(exc), options)) from None


def option_message(message: str, options: dict[str, str]) -> str:
    """``message`` with a leading field name replaced by its command-line option."""
    for name in sorted(options, key=len, reverse=True):
        if message.startswith(name + " ") or message.startswith(name + ":"):
            return options[name] + message[len(name):]
    return message
