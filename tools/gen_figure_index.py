#!/usr/bin/env python3
"""Regenerate ``figures/README.md``: every figure ID of the catalogues -> the tutorial that reproduces it, its
output file and the equations it uses, or why it is not reproduced (``pywarp/data/figure_status.json``).

Run after adding a tutorial:  python tools/gen_figure_index.py   (tests/test_tutorials.py fails when it is stale)
"""
from __future__ import annotations

import ast
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT))
from gen_catalogue import ID_ANYWHERE, parse_spec  # noqa: E402

from pywarp.core.figures import tutorial_info as _doc_info  # noqa: E402  (stand-in or reproduced: one rule)

OUT = ROOT / "figures" / "README.md"
STATUS = ROOT / "pywarp" / "data" / "figure_status.json"  # {"vc-fig-2.2": "photograph; stand-in: ...", ...}
FIG_RE = re.compile(r"\b((?:vc|pt|rr|oc)-(?:fig|extra)-[A-Za-z0-9.\-]*[A-Za-z0-9])\b")


def tutorial_info():
    info = {}
    for path in sorted((ROOT / "tutorials").glob("*/*.py")):
        if path.name.startswith("_"):
            continue
        doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
        figs = sorted(set(FIG_RE.findall(doc)))
        eqs = sorted(i for i in set(ID_ANYWHERE.findall(doc)) if i not in figs and "-fig-" not in i)
        outputs = sorted(set(re.findall(r"figures/[a-z]+/([\w.\-]+\.png)", doc)))
        stand_in = bool(_doc_info(path)["stand_in"])
        for f in figs:
            info[f] = {"script": path.relative_to(ROOT).as_posix(), "equations": eqs, "outputs": outputs,
                       "stand_in": stand_in}
    return info


def build() -> str:
    status = json.loads(STATUS.read_text(encoding="utf-8")) if STATUS.exists() else {}
    tuts = tutorial_info()
    lines = ["# Figures", "",
             "Every figure of the four catalogues (`spec/*.md`): the tutorial that reproduces it, or why it is not",
             "reproduced and what stands in for it. Regenerate the images with `pywarp figures` and this index with",
             "`python tools/gen_figure_index.py`.", ""]
    for seed in ("vc", "pt", "rr", "oc"):
        entries = {k: v for k, v in parse_spec(ROOT / "spec" / f"{seed}.md").items() if v["kind"] == "figure"}
        extras = sorted(k for k in tuts if k.startswith(f"{seed}-extra-"))
        done = sum(1 for k in entries if k in tuts and not tuts[k]["stand_in"])
        stood = sum(1 for k in entries if k in tuts and tuts[k]["stand_in"])
        lines += [f"## {seed} ({done} of {len(entries)} reproduced, {stood} stood in for)", "",
                  "| figure | title | status | script | equations |", "|---|---|---|---|---|"]
        for fid, e in list(entries.items()) + [(k, {"title": "(extra, not a figure of the text)"}) for k in extras]:
            title = e["title"].replace("|", "\\|")
            if fid in tuts:
                t = tuts[fid]
                # a tutorial of several figures: each figure links its own image where one has its name
                stem = fid.split("-", 1)[1]  # fig-4.6: fig-4.6.png, fig-4.6-errata.png (not fig-4.60.png)
                own = [o for o in t["outputs"] if o.startswith(stem) and o[len(stem):len(stem) + 1] in (".", "-")]
                imgs = " ".join(f"[{o}]({seed}/{o})" for o in (own or t["outputs"])) or "(no output named)"
                if t["stand_in"]:
                    imgs = "stand-in: " + imgs
                lines.append(f"| {fid} | {title} | {imgs} | [{Path(t['script']).name}](../{t['script']}) | "
                             f"{', '.join(t['equations']) or '-'} |")
            else:
                lines.append(f"| {fid} | {title} | {status.get(fid, 'not reproduced yet')} | - | - |")
        lines.append("")
    return "\n".join(lines)


def main(argv) -> int:
    text = build()
    if "--check" in argv:
        if not OUT.exists() or OUT.read_text(encoding="utf-8") != text:
            print("figures/README.md is out of date: run python tools/gen_figure_index.py", file=sys.stderr)
            return 1
        return 0
    OUT.write_text(text, encoding="utf-8")
    print(f"wrote {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
