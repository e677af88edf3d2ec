"""The one bridge from settings to the C core and the Warp twin: ``ccl_*_params_default`` -> the settings' values (and
the values the scene computes) -> the C check -> the Warp struct.

A settings field that reaches the pixel names its C field in its spec (``param(..., c="fog_density")``); a field with
choices maps them to C enum constants by ``c_enum`` ({choice: "CCL_..."}: names, looked up in the library, so the
table is pinned to the C values by the binding itself). Each parameter struct is a :class:`CStruct` (below; the
cloudscape's, with the domains of its error messages, in :mod:`pywarp.clouds.settings`); a settings class's
``c_values()`` is the C defaults, :func:`settings_values` and the values the scene computes. The C check is the one
check of the values: its error names the field by its Python name and domain where a setting carries it, by its C
name (and ``CStruct.domains``) otherwise. The Warp struct is read back from the checked C struct, so both twins see
the same float32 values.

Kernels name C enum values with :func:`c_constant` (a Warp constant recorded in :data:`C_CONSTANTS`, which
``tests/core/test_cbridge.py`` pins to the library)."""
from __future__ import annotations

import importlib
from dataclasses import dataclass, field

#: Warp constants standing for C enum / #define values, by C name (see :func:`c_constant`).
C_CONSTANTS: dict[str, int] = {}


def c_constant(c_name: str, value: int):
    """A Warp constant for the C constant ``c_name`` (its value written here, so that kernels import without the C
    library; ``tests/core/test_cbridge.py`` checks it against the library)."""
    import warp as wp

    if C_CONSTANTS.setdefault(c_name, value) != value:
        raise ValueError(f"{c_name} declared as {C_CONSTANTS[c_name]} and {value}")
    return wp.constant(value)


@dataclass(frozen=True)
class CStruct:
    """A C parameter struct with its default, its check and its Warp twin."""

    name: str  #: the C type, e.g. ``ccl_terrain_params``; its defaults come from ``<name>_default``
    check: str  #: the C check, called ``check(p, *check_args, &field)``
    warp: str  #: the Warp struct, ``"module:Class"``
    #: domain in words of C fields that no setting carries (for the error; as the C check states it)
    domains: dict = field(default_factory=dict)
    #: what the check also bounds, appended to an error naming a field absent from ``domains``
    note: str = ""

    def defaults(self) -> dict:
        """The values of ``<name>_default`` (nested structs flattened, vectors and arrays as tuples)."""
        from .binding import ffi, lib

        c = ffi().new(self.name + " *")
        getattr(lib(), self.name + "_default")(c)
        return read(c)

    def to_c(self, values: dict):
        """A cffi ``<name> *`` of the defaults with ``values`` written over them (not checked)."""
        from .binding import ffi, lib

        c = ffi().new(self.name + " *")
        getattr(lib(), self.name + "_default")(c)
        places = _places(c[0])
        for name, v in values.items():
            if name not in places:
                raise ValueError(f"unknown {self.name} field {name!r}")
            owner, attr = places[name]
            cur = getattr(owner, attr)
            vec = hasattr(cur, "x")
            if vec or _is_array(cur):  # a ccl_vec2/3 or an array: a sequence of its length
                items = list(v)
                if len(items) != (len(_vec(cur)) if vec else len(cur)):
                    raise ValueError(f"{name} must hold {len(_vec(cur)) if vec else len(cur)} numbers, got {v!r}")
                for i, a in enumerate(items):
                    if vec:
                        setattr(cur, "xyz"[i], float(a))
                    else:
                        cur[i] = a
            else:
                try:
                    setattr(owner, attr, v)
                except (TypeError, OverflowError) as exc:  # a float for an int field, a seed beyond uint32, ...
                    raise (TypeError if isinstance(exc, TypeError) else ValueError)(
                        f"{name} does not fit the C field ({exc}), got {v!r}") from None
        return c

    def checked(self, values: dict, *check_args, settings=None, overrides=()):
        """:meth:`to_c` of ``values``, checked by the C check; ValueError naming the first bad field: the setting
        that carries it (its name and domain) where ``settings`` are given and the field is not one of
        ``overrides`` (values set beside the settings), else the C name."""
        from .binding import ffi, lib

        c = self.to_c(values)
        out = ffi().new("const char **")
        if getattr(lib(), self.check)(c, *check_args, out) != 0:
            raise self._error(ffi().string(out[0]).decode(), values, c, settings, overrides)
        return c

    def _error(self, c_name: str, values: dict, c, settings, overrides) -> ValueError:
        from .params import specs

        by_c = {p.c: p for p in specs(settings) if p.c not in overrides} if settings is not None else {}
        if c_name in by_c:
            p = by_c[c_name]
            dom = p.domain()
            dom = dom if dom.startswith(("one of", "a ", "an ", "True")) else "in " + dom
            return ValueError(f"{p.name} is out of range: it must be {dom} ({self.check}), "
                              f"got {getattr(settings, p.name)!r}")
        shown = values.get(c_name, read(c).get(c_name))
        if c_name in self.domains:
            return ValueError(f"{c_name} is out of range: it must be {self.domains[c_name]} ({self.check}), "
                              f"got {shown!r}")
        return ValueError(f"{c_name} is out of range ({self.check}{self.note}), got {shown!r}")

    def warp_struct(self, c):
        """The Warp struct of the (checked) C struct ``c`` (or of :meth:`to_c` of a dict of values): every Warp field
        read from the C field of its name, so that both twins see the same float32 values."""
        import warp as wp

        module, cls_name = self.warp.split(":")
        cls = getattr(importlib.import_module(module), cls_name)
        values = read(self.to_c(c) if isinstance(c, dict) else c)
        s = cls()
        for name, var in cls.vars.items():
            v, t = values[name], var.type
            if t in (int, wp.int32):
                setattr(s, name, int(v))
            elif t is wp.uint32:
                setattr(s, name, wp.uint32(int(v)))
            elif t in (float, wp.float32):
                setattr(s, name, float(v))
            else:
                setattr(s, name, t(*v))
        return s


def settings_values(settings) -> dict:
    """The C values of the fields of ``settings`` that name one (``c=``): choices by their ``c_enum`` constant,
    booleans as 0/1."""
    from .binding import lib
    from .params import specs

    out = {}
    for p in specs(settings):
        if not p.c:
            continue
        v = getattr(settings, p.name)
        if p.c_enum is not None:
            v = int(getattr(lib(), p.c_enum[v]))
        elif isinstance(v, bool):
            v = int(v)
        out[p.c] = v
    return out


def read(c) -> dict:
    """The fields of a cffi struct as Python values: nested structs other than vectors flattened into their fields,
    ``ccl_vec2``/``ccl_vec3`` and arrays as tuples."""
    return {name: _value(getattr(owner, attr)) for name, (owner, attr) in _places(c[0] if _is_ptr(c) else c).items()}


def _places(s) -> dict:
    from .binding import ffi

    out = {}
    for name, f in ffi().typeof(s).fields:
        if f.type.kind == "struct" and not f.type.cname.startswith("ccl_vec"):
            out.update(_places(getattr(s, name)))
        else:
            out[name] = (s, name)
    return out


def _is_ptr(c) -> bool:
    from .binding import ffi

    return ffi().typeof(c).kind == "pointer"


def _is_array(v) -> bool:
    from .binding import ffi

    return isinstance(v, ffi().CData) and ffi().typeof(v).kind == "array"


def _vec(v) -> tuple:
    return (v.x, v.y, v.z) if hasattr(v, "z") else (v.x, v.y)


def _value(v):
    if hasattr(v, "x"):
        return tuple(float(a) for a in _vec(v))
    if _is_array(v):
        return tuple(v)
    return v


# --- the parameter structs of the scenes (the cloudscape's, with its error domains: pywarp.clouds.settings) ----------

TERRAIN_PARAMS = CStruct("ccl_terrain_params", "ccl_terrain_params_check", "pywarp.kernels.terrain:TerrainParams")
VOLUME_PARAMS = CStruct("ccl_volume_params", "ccl_volume_check", "pywarp.kernels.volume:VolumeParams")
PARTICLES_PARAMS = CStruct("ccl_particles_params", "ccl_particles_params_check",
                           "pywarp.kernels.particles:ParticlesParams")
