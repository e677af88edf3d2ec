"""`pywarp equations`: one row per catalogue ID in natural order, a table that fits the terminal, csv / markdown /
json, `--missing` for the computational IDs only, `--figures` with the true status of every figure and measurement."""
from __future__ import annotations

import csv
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from pywarp.core import figures
from pywarp.core.catalogue import COMPUTATIONAL_KINDS, catalogue, sort_key
from pywarp.core.registry import missing, registry

ROOT = Path(__file__).resolve().parents[2]


def _cli(*args, columns=None, tmp_path):
    env = dict(os.environ)
    env.pop("COLUMNS", None)
    if columns is not None:
        env["COLUMNS"] = str(columns)
    res = subprocess.run([sys.executable, "-m", "pywarp", "equations", *args], capture_output=True, text=True,
                         cwd=tmp_path, env=env, timeout=300)
    assert res.returncode == 0, res.stderr
    return res.stdout


def test_sort_key_is_natural():
    ids = ["vc-A28", "vc-A3", "vc-2.13", "vc-2.9", "vc-2.1", "pt-3.1", "vc-fig-4.17", "vc-fig-4.9", "oc-1.1",
           "rr-2.1", "vc-2.10"]
    assert sorted(ids, key=sort_key) == ["vc-2.1", "vc-2.9", "vc-2.10", "vc-2.13", "vc-A3", "vc-A28", "vc-fig-4.9",
                                         "vc-fig-4.17", "pt-3.1", "rr-2.1", "oc-1.1"]


def test_one_row_per_implemented_id_in_natural_order(tmp_path):
    rows = json.loads(_cli("--format", "json", tmp_path=tmp_path))
    ids = [r["id"] for r in rows]
    assert ids == list(registry())  # every ID an entry answers, the entry's aliases included
    assert ids == sorted(ids, key=sort_key) and len(set(ids)) == len(ids)
    vc = [i for i in ids if i.startswith("vc-A")]
    assert vc.index("vc-A3") < vc.index("vc-A28")
    by_id = {r["id"]: r for r in rows}
    hg = by_id["vc-2.13"]
    assert hg["c"] == "ccl_phase_hg" and hg["warp"] == "phase.phase_hg" and hg["entry"] == "vc-2.13"
    assert any("test_phase" in t for t in hg["tests"])
    for r in rows:  # an alias row names the entry that answers it
        assert registry()[r["id"]].id == r["entry"]


def test_table_fits_columns_and_keeps_every_id(tmp_path):
    for width in (60, 100, 160):
        out = _cli("--seed", "vc", columns=width, tmp_path=tmp_path)
        lines = out.splitlines()
        assert all(len(line) <= width for line in lines), max(lines, key=len)
        listed = [line.split()[0] for line in lines if line.startswith("vc-")]
        assert listed == [c for c in registry() if c.startswith("vc-")]
    assert "implemented of" in out


def test_width_option_and_no_truncation_when_piped(tmp_path):
    narrow = _cli("--seed", "vc", "--width", "70", tmp_path=tmp_path)
    assert max(len(line) for line in narrow.splitlines()) <= 70
    full = _cli("--seed", "vc", tmp_path=tmp_path)  # not a terminal, no $COLUMNS: full cells
    assert "\u2026" not in full and max(len(line) for line in full.splitlines()) > 70


def test_csv_and_markdown_have_every_row(tmp_path):
    reg = [c for c in registry() if c.startswith("vc-")]
    rows = list(csv.DictReader(io.StringIO(_cli("--seed", "vc", "--format", "csv", tmp_path=tmp_path))))
    assert [r["id"] for r in rows] == reg
    assert {r["id"]: r["c"] for r in rows}["vc-2.13"] == "ccl_phase_hg"
    md = _cli("--seed", "vc", "--format", "markdown", tmp_path=tmp_path).splitlines()
    assert md[0].startswith("| id |") and md[1].startswith("|---|")
    assert [line.split("|")[1].strip() for line in md[2:]] == reg


def test_missing_lists_only_computational_ids(tmp_path):
    rows = json.loads(_cli("--missing", "--format", "json", tmp_path=tmp_path))
    assert [r["id"] for r in rows] == [cid for cid, _ in missing(computational=True)]
    assert {r["kind"] for r in rows} <= set(COMPUTATIONAL_KINDS)
    ids = {r["id"] for r in rows}
    assert "vc-2.13" not in ids and not any("-fig-" in i or "-M" in i for i in ids)
    table = _cli("--missing", columns=100, tmp_path=tmp_path)
    assert "not implemented" in table and "--figures" in table
    assert {line.split()[0] for line in table.splitlines() if line[:3] in ("vc-", "pt-", "rr-", "oc-")} == ids


def test_figures_true_status(tmp_path):
    rows = json.loads(_cli("--figures", "--format", "json", tmp_path=tmp_path))
    cat = catalogue()["ids"]
    assert {r["id"] for r in rows if r["kind"] != "extra"} == {c for c, e in cat.items()
                                                               if e["kind"] in ("figure", "measurement")}
    by_id = {r["id"]: r for r in rows}
    # reproduced: by its tutorial, with the committed output
    r = by_id["vc-fig-4.9"]
    assert r["status"] == "reproduced" and r["tutorial"] == "tutorials/vc/fig_2_15_height_gradients.py"
    # "committed" is known when pywarp runs from the checkout, None when installed (CI): check the file here
    assert r["outputs"] == ["fig-4.9.png"] and r["committed"] in ([True], None)
    assert (ROOT / "figures" / "vc" / "fig-4.9.png").is_file()
    # a photograph stood in for by renders is not "reproduced"
    assert by_id["vc-fig-2.2"]["status"] == "stand-in" and by_id["vc-fig-2.2"]["note"]
    # not reproduced, with the reason
    assert by_id["vc-fig-2.3"]["status"] == "not reproduced" and "photograph" in by_id["vc-fig-2.3"]["note"]
    # measurements
    assert by_id["vc-M4"]["status"] == "measured" and "pywarp bench" in by_id["vc-M4"]["note"]
    assert by_id["vc-M1"]["status"] == "not measured"
    for r in rows:
        assert r["status"] in figures.FIGURE_STATUSES + figures.MEASUREMENT_STATUSES
        if r["status"] in ("reproduced", "stand-in"):
            assert r["tutorial"] and (ROOT / r["tutorial"]).is_file() and r["outputs"]
            seed = r["id"].split("-")[0]
            assert all((ROOT / "figures" / seed / o).is_file() for o in r["outputs"]), r  # outputs are committed
        if r["status"] == "not reproduced":
            assert r["tutorial"] is None and r["note"]
    table = _cli("--figures", "--seed", "vc", columns=120, tmp_path=tmp_path)
    assert all(len(line) <= 120 for line in table.splitlines())
    assert "stood in for" in table and "not reproduced" in table


def test_figure_status_agrees_with_the_tutorials():
    """Every tutorial's figures are reproduced or stood in for; nothing else is."""
    named = {fid for p in figures.tutorials() for fid in figures.figure_ids(p)}
    done = {r["id"] for r in figures.status() if r["status"] in ("reproduced", "stand-in")}
    assert done == named


@pytest.mark.parametrize("width,expect", [(None, None), (0, None), (50, 50)])
def test_table_width_rules(monkeypatch, width, expect):
    from pywarp.cli.equations import table_width

    monkeypatch.delenv("COLUMNS", raising=False)
    assert table_width(width, io.StringIO()) == expect
    monkeypatch.setenv("COLUMNS", "77")
    assert table_width(None, io.StringIO()) == 77


def test_render_table_truncates_flexible_columns_only():
    from pywarp.cli.equations import render_table

    rows = [{"id": "vc-A28", "title": "x" * 50, "c": "ccl_sky_gradient_rgb"}]
    lines = render_table([("ID", "id", 0), ("title", "title", 2), ("C", "c", 1)], rows, 40, "~")
    assert all(len(line) <= 40 for line in lines)
    assert lines[2].startswith("vc-A28  ") and "~" in lines[2]
