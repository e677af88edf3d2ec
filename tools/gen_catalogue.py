#!/usr/bin/env python3
"""Regenerate ``pywarp/data/catalogue.json`` -- the catalogued IDs and the test/figure index shipped in the package.

Sources, all in this repository:
  spec/{vc,pt,rr,oc}.md   every ID of the four texts: a heading ``### <ID> — <title>`` or a table row ``| <ID> | …``
  tests/**/test_*.py      tests carry ``@pytest.mark.spec("vc-2.13", ...)``: the IDs they check
  tutorials/*/*.py        a tutorial's title docstring names the figure it reproduces and the equations it uses

Run it after adding a test or a tutorial:  python tools/gen_catalogue.py
``tests/core/test_registry.py`` fails when the committed file is out of date.
"""
from __future__ import annotations

import ast
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from pywarp.core.catalogue import SEEDS  # noqa: E402  (the four texts: one list, in the package)

OUT = ROOT / "pywarp" / "data" / "catalogue.json"
ID_RE = rf"(?:{'|'.join(SEEDS)})-[A-Za-z0-9][A-Za-z0-9.\-]*[A-Za-z0-9]"
HEADING = re.compile(rf"^###\s+({ID_RE})\s+—\s+(.*?)\s*$")
ROW = re.compile(rf"^\|\s*({ID_RE})\s*\|\s*([^|]*?)\s*\|")
ID_ANYWHERE = re.compile(rf"\b({ID_RE})\b")


def kind_of(cid: str) -> str:
    rest = cid.split("-", 1)[1]
    if rest.startswith("x-"):  # beyond the text (vc-x-mie): catalogued with its source, not counted as the text's
        return "extra"
    if rest.startswith("fig-"):
        return "figure"
    if rest.startswith("tab-"):
        return "table"
    if rest.startswith("code-"):
        return "code"
    if re.fullmatch(r"M\d+", rest):
        return "measurement"
    if re.fullmatch(r"\d+\.\d+", rest) or rest.startswith("eq"):
        return "equation"
    return "algorithm"


def parse_spec(path: Path) -> dict:
    entries = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        m = HEADING.match(line) or ROW.match(line)
        if m and m.group(1) not in entries:
            title = re.sub(r"\s+", " ", m.group(2)).strip()
            entries[m.group(1)] = {"title": title, "kind": kind_of(m.group(1))}
    return entries


def _spec_ids_of_decorators(decorators) -> list[str]:
    ids = []
    for d in decorators:
        if isinstance(d, ast.Call) and isinstance(d.func, ast.Attribute) and d.func.attr == "spec":
            ids += [a.value for a in d.args if isinstance(a, ast.Constant) and isinstance(a.value, str)]
    return ids


def index_tests(test_dir: Path) -> dict:
    index: dict[str, list[str]] = {}
    for path in sorted(test_dir.rglob("test_*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        module_ids = []
        for node in tree.body:
            if isinstance(node, ast.Assign) and any(getattr(t, "id", "") == "pytestmark" for t in node.targets):
                vals = node.value.elts if isinstance(node.value, (ast.List, ast.Tuple)) else [node.value]
                module_ids += _spec_ids_of_decorators(vals)
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef) and node.name.startswith("test_"):
                for cid in module_ids + _spec_ids_of_decorators(node.decorator_list):
                    index.setdefault(cid, []).append(f"{path.relative_to(test_dir.parent).as_posix()}::{node.name}")
    return {k: sorted(set(v)) for k, v in sorted(index.items())}


def index_tutorials(tut_dir: Path) -> dict:
    index: dict[str, list[str]] = {}
    for path in sorted(tut_dir.glob("*/*.py")):
        doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
        rel = path.relative_to(ROOT).as_posix()
        for cid in sorted(set(ID_ANYWHERE.findall(doc))):
            index.setdefault(cid, []).append(rel)
    return {k: sorted(v) for k, v in sorted(index.items())}


def build() -> dict:
    ids = {}
    for seed in SEEDS:
        for cid, entry in parse_spec(ROOT / "spec" / f"{seed}.md").items():
            ids[cid] = {"seed": seed, **entry}
    return {
        "generated_by": "tools/gen_catalogue.py",
        "ids": ids,
        "tests": index_tests(ROOT / "tests"),
        "tutorials": index_tutorials(ROOT / "tutorials"),
    }


def render(data: dict) -> str:
    return json.dumps(data, indent=1, ensure_ascii=False, sort_keys=False) + "\n"


def main(argv: list[str]) -> int:
    text = render(build())
    if "--check" in argv:
        current = OUT.read_text(encoding="utf-8") if OUT.exists() else ""
        if current != text:
            print(f"{OUT.relative_to(ROOT)} is out of date: run python tools/gen_catalogue.py", file=sys.stderr)
            return 1
        return 0
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(text, encoding="utf-8")
    d = json.loads(text)
    print(f"wrote {OUT.relative_to(ROOT)}: {len(d['ids'])} IDs, {len(d['tests'])} tested, "
          f"{len(d['tutorials'])} used by tutorials")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
