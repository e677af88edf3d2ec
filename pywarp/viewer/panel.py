"""The viewer's side panel, generated from a settings class's parameter specs (:mod:`pywarp.core.params`).

:func:`rows` turns every spec into a :class:`Row` -- the widget, its label (name and unit), its range and its help
text (doc, unit, domain, default, the reason for the default, what a change invalidates) -- without touching Dear
ImGui, so that the panel can be tested without a window. :func:`draw` draws the rows with ImGui and returns the
changes the user made.

Which widget: a bounded float is a slider (logarithmic from 0 to far beyond its default; a drag field where the range
is unbounded or very wide), a bounded int a slider (a
power-of-two field a combo of the powers of two; an odd one steps by 2), a bool a checkbox, a choice a combo, a free
string a text field (applied on Enter), a fixed-length tuple of floats one field per item; an optional value has an
"auto" checkbox. A ``mapping`` field (e.g. clouds' ``advanced``) is shown read-only. When a change applies:
``nothing`` and ``sky`` fields apply while the slider moves (live); ``textures``, ``size`` and ``device`` fields
apply when the widget is released (regenerating textures at every slider step would stall the view).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.params import Param, specs

#: fields whose change is costly (by their settings class's invalidation names) apply when the widget is released, the
#: others while it moves
APPLY_ON_RELEASE = ("textures", "clouds", "flight", "mask", "size", "device")
#: integer ranges up to this span get a slider; wider ones an input field
SLIDER_INT_SPAN = 4096
#: float ranges up to this span get a slider; wider ones (e.g. a camera position in +-1000 km) a drag field
SLIDER_FLOAT_SPAN = 1000.0
#: a slider from lo >= 0 to at least this many times its default is logarithmic (e.g. an altitude of 0.3 in [0, 1000])
LOG_RATIO = 100.0
#: widget kinds (Row.widget)
WIDGETS = ("slider_float", "drag_float", "slider_int", "input_int", "pow2_combo", "checkbox", "combo", "text",
           "floats", "readonly")


@dataclass(frozen=True)
class Row:
    """One panel row: ``spec`` (the field's Param), ``widget`` (one of :data:`WIDGETS`), ``label`` (name [unit]),
    ``lo``/``hi`` (slider range, None if unbounded), ``choices`` (for combos), ``help`` (the tooltip), ``live``
    (applied while dragging, else on release)."""

    spec: Param
    widget: str
    label: str
    lo: float | None
    hi: float | None
    choices: tuple
    help: str
    live: bool
    log: bool = False

    @property
    def name(self) -> str:
        return self.spec.name

    @property
    def group(self) -> str:
        return self.spec.group or "settings"


def _help(p: Param) -> str:
    lines = [p.doc.rstrip(".") + (f" [{p.unit}]" if p.unit else "")]
    lines.append(f"range: {p.domain()}" + (" or auto" if p.optional else ""))
    d = p.default_text or (p.default if not isinstance(p.default, float) else f"{p.default:g}")
    lines.append(f"default: {d} -- {p.reason}")
    lines.append(f"a change invalidates: {p.invalidates}")
    if p.option:
        lines.append(f"option: {p.option}")
    return "\n".join(lines)


def row(p: Param) -> Row:
    """The panel row of one spec."""
    label = p.name + (f" [{p.unit}]" if p.unit else "")
    lo = None if p.lo is None else float(p.lo)
    hi = None if p.hi is None else float(p.hi)
    choices: tuple = ()
    k = p.kind
    if k == "bool":
        widget = "checkbox"
    elif k == "str":
        widget, choices = ("combo", tuple(p.choices)) if p.choices else ("text", ())
    elif k in ("int", "uint32"):
        if p.pow2 and lo is not None and hi is not None:
            widget = "pow2_combo"
            lo_e = max(0, math.ceil(math.log2(max(lo, 1))))
            choices = tuple(2 ** e for e in range(lo_e, int(math.log2(hi)) + 1))
        elif lo is not None and hi is not None and hi - lo <= SLIDER_INT_SPAN:
            widget = "slider_int"
        else:
            widget = "input_int"
    elif k == "float":
        bounded = lo is not None and hi is not None and hi - lo <= SLIDER_FLOAT_SPAN
        widget = "slider_float" if bounded else "drag_float"
        d = p.default if isinstance(p.default, (int, float)) else 0.0
        log = bounded and lo >= 0.0 and d > 0.0 and hi >= LOG_RATIO * d
    elif k == "floats":
        widget = "floats"
    else:
        widget = "readonly"
    return Row(spec=p, widget=widget, label=label, lo=lo, hi=hi, choices=choices, help=_help(p),
               live=p.invalidates not in APPLY_ON_RELEASE, log=k == "float" and log)


def rows(settings_class, exclude=()) -> list[Row]:
    """One row per settings field (``exclude``: names left out), in declaration order."""
    return [row(p) for p in specs(settings_class) if p.name not in exclude]


def groups(settings_class, exclude=()) -> dict[str, list[Row]]:
    """The rows by group (the panel's collapsing headers), groups in order of first appearance."""
    out: dict[str, list[Row]] = {}
    for r in rows(settings_class, exclude):
        out.setdefault(r.group, []).append(r)
    return out


# --- drawing (needs Dear ImGui) ---------------------------------------------------------------------------------------

def _drag_speed(r: Row, v: float) -> float:
    return max(abs(v) * 0.01, 0.01)


def draw_row(imgui, r: Row, value, state: dict):
    """Draw one row; returns (changed, new value, apply now). ``state`` keeps per-row editing state (pending values
    of on-release rows, text buffers)."""
    p = r.spec
    key = f"##{p.name}"
    changed, new = False, value
    if p.optional:
        auto = value is None
        c, auto_new = imgui.checkbox(f"auto##auto_{p.name}", auto)
        if imgui.is_item_hovered():
            imgui.set_tooltip(r.help)
        imgui.same_line()
        if c:
            return True, (None if auto_new else (p.default if p.default is not None else int(p.lo or 1))), True
        if auto:
            imgui.text_disabled(r.label)
            return False, value, False
    pending = state.get(p.name, value) if not r.live else value
    if r.widget == "checkbox":
        changed, new = imgui.checkbox(r.label + key, bool(value))
    elif r.widget == "combo":
        idx = r.choices.index(value) if value in r.choices else 0
        changed, idx = imgui.combo(r.label + key, idx, list(r.choices))
        new = r.choices[idx]
    elif r.widget == "pow2_combo":
        idx = r.choices.index(value) if value in r.choices else 0
        changed, idx = imgui.combo(r.label + key, idx, [str(c) for c in r.choices])
        new = r.choices[idx]
    elif r.widget == "slider_int":
        changed, new = imgui.slider_int(r.label + key, int(pending), int(r.lo), int(r.hi))
        if p.odd and new % 2 == 0:
            new = new + 1 if new + 1 <= r.hi else new - 1
    elif r.widget == "input_int":
        changed, new = imgui.input_int(r.label + key, int(pending))
    elif r.widget == "slider_float":
        flags = imgui.SliderFlags_.logarithmic.value if r.log else 0
        changed, new = imgui.slider_float(r.label + key, float(pending), float(r.lo), float(r.hi), "%.4g", flags)
    elif r.widget == "drag_float":
        lo = -math.inf if r.lo is None else r.lo
        hi = math.inf if r.hi is None else r.hi
        changed, new = imgui.drag_float(r.label + key, float(pending), _drag_speed(r, float(pending)), 0.0, 0.0,
                                        "%.4g")
        new = min(max(new, lo), hi)
    elif r.widget == "text":
        buf = state.get("text_" + p.name, str(value))
        changed_t, buf = imgui.input_text(r.label + key, buf, imgui.InputTextFlags_.enter_returns_true.value)
        state["text_" + p.name] = buf
        if changed_t:
            return True, buf, True
        changed = False
    elif r.widget == "floats":
        vals = list(value)
        for i, v in enumerate(vals):
            c, vals[i] = imgui.drag_float(f"{r.label}[{i}]##{p.name}_{i}", float(v), _drag_speed(r, float(v)))
            changed = changed or c
        new = tuple(vals)
    else:
        imgui.text(f"{r.label}: {value!r} (set on the command line)")
    if imgui.is_item_hovered():
        imgui.set_tooltip(r.help)
    if r.live or r.widget in ("checkbox", "combo", "pow2_combo", "floats"):
        return changed, new, changed
    # on-release rows: keep the value while the widget is active, apply when it is released
    if changed:
        state[p.name] = new
    if imgui.is_item_deactivated_after_edit() and p.name in state:
        return True, state.pop(p.name), True
    if not imgui.is_item_active() and p.name in state and not changed:
        state.pop(p.name, None)
    return False, value, False


def draw(imgui, settings, state: dict, exclude=(), open_groups=("camera", "sky", "weather", "clouds")) -> dict:
    """Draw the panel for ``settings``; returns {field: new value} of the changes to apply now."""
    changes = {}
    for group, rs in groups(type(settings), exclude).items():
        flags = imgui.TreeNodeFlags_.default_open.value if group in open_groups else 0
        if not imgui.collapsing_header(group, flags):
            continue
        for r in rs:
            value = getattr(settings, r.name)
            try:
                changed, new, apply = draw_row(imgui, r, value, state)
            except (TypeError, ValueError):  # a value a widget cannot show (e.g. out of its int range)
                imgui.text(f"{r.label}: {value!r}")
                continue
            if apply and changed and new != value:
                changes[r.name] = new
    return changes

