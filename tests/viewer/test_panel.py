"""The viewer's panel is generated from the parameter specs: every setting of every registered scene has a row with
its unit, range and help (doc, default, reason, what a change invalidates), and the widget fits its kind."""
from __future__ import annotations

import pytest

from pywarp.core import scenes as S
from pywarp.core.params import specs
from pywarp.viewer import panel as P


@pytest.mark.parametrize("name", list(S.scenes()))
def test_every_setting_has_a_row_with_unit_range_and_help(name):
    sc = S.scene(name)
    rows = P.rows(sc.settings)
    assert [r.name for r in rows] == [p.name for p in specs(sc.settings)]
    for r in rows:
        p = r.spec
        assert r.widget in P.WIDGETS
        assert r.label.startswith(p.name) and (f"[{p.unit}]" in r.label if p.unit else "[" not in r.label)
        assert p.doc.rstrip(".") in r.help and p.domain() in r.help and p.reason in r.help
        assert f"a change invalidates: {p.invalidates}" in r.help
        assert r.live == (p.invalidates not in P.APPLY_ON_RELEASE)
        if r.widget in ("slider_float", "slider_int"):
            assert (r.lo, r.hi) == (float(p.lo), float(p.hi))
        if p.kind == "float":
            narrow = p.lo is not None and p.hi is not None and p.hi - p.lo <= P.SLIDER_FLOAT_SPAN
            assert r.widget == ("slider_float" if narrow else "drag_float")
        if p.choices:
            assert r.widget == "combo" and r.choices == tuple(p.choices)
        kind_widgets = {"bool": {"checkbox"}, "str": {"combo", "text"}, "mapping": {"readonly"},
                        "floats": {"floats"}, "float": {"slider_float", "drag_float"},
                        "int": {"slider_int", "input_int", "pow2_combo"},
                        "uint32": {"slider_int", "input_int", "pow2_combo"}}
        assert r.widget in kind_widgets[p.kind]
    groups = P.groups(sc.settings)
    assert sum(len(v) for v in groups.values()) == len(rows)


def test_clouds_rows():
    rows = {r.name: r for r in P.rows(S.scene("clouds").settings)}
    cov = rows["coverage"]
    assert cov.widget == "slider_float" and (cov.lo, cov.hi) == (0.0, 1.0) and cov.group == "weather"
    assert not cov.live  # regenerates the weather map: applied when the slider is released
    sun = rows["sun_elevation_deg"]
    assert sun.widget == "slider_float" and sun.live and sun.label == "sun_elevation_deg [deg]"
    assert rows["earth_radius_km"].widget == "drag_float"  # unbounded above
    alt = rows["camera_altitude_km"]
    assert alt.widget == "slider_float" and alt.log  # 0.3 km in [0, 1000]: logarithmic
    assert not sun.log
    assert rows["base_size"].widget == "pow2_combo" and rows["base_size"].choices == (4, 8, 16, 32, 64, 128, 256,
                                                                                      512)
    assert rows["sky"].widget == "combo" and rows["sky"].choices == ("preetham", "gradient")
    assert rows["beer"].widget == "checkbox"
    assert rows["samples_min"].widget == "slider_int" and rows["seed"].widget == "input_int"
    assert rows["threads"].spec.optional and "or auto" in rows["threads"].help
    assert rows["advanced"].widget == "readonly"
    assert rows["width"].live is False  # size: reallocated on release
