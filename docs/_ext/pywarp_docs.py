"""Sphinx extension of the pywarp documentation: the pages generated from the code at the start of every build.

* ``_gallery_src/<seed>/<tutorial>.py``: the sources of the sphinx-gallery gallery, one per tutorial of
  ``tutorials/<seed>/``, made by :func:`stage_gallery`: the tutorial as ``pywarp notebooks`` unrolls it (its
  ``main()`` body cut into cells, a parameter cell), with the Markdown narrative rendered to HTML (sphinx-gallery's
  text blocks are reStructuredText, the tutorials' narrative is Markdown) and ``quick`` set by the build
  (``PYWARP_DOCS_QUICK``, default 1: the small, fast figures; 0: full size); ``PYWARP_DOCS_TUTORIALS`` (a glob
  such as ``vc/extra_*``) stages only some tutorials, for a fast local build;
* ``_generated/equations/<seed>.rst``: every registry entry (``pywarp.core.registry.entries()``) with its IDs,
  arguments (domain, units), options, outputs, references, C symbol, Warp twin, tests and tutorials;
* ``_generated/traceability.rst``: the traceability matrix (the rows of ``pywarp equations``);
* ``_generated/c_api.rst``: every C header of ``cclouds/include/cclouds`` (umbrella order) with each declaration and
  the comment above it;
* ``_generated/scenes/<name>.rst``: one page per registered scene with its settings table from the parameter specs.

Everything is rewritten only when its text changes, so that Sphinx rebuilds only what changed.
"""
from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
GEN = DOCS / "_generated"
STAGE = DOCS / "_gallery_src"
SEED_TITLES = {
    "vc": "vc — volumetric clouds over a Preetham sky",
    "pt": "pt — a ray-marched terrain demo",
    "rr": "rr — realistic rain",
    "oc": "oc — value-noise clouds and a flight simulator",
}


def quick_mode() -> bool:
    """The gallery's tutorials run with ``quick=True`` unless ``PYWARP_DOCS_QUICK=0``."""
    return os.environ.get("PYWARP_DOCS_QUICK", "1").strip().lower() not in ("0", "false", "no", "")


# --- helpers -----------------------------------------------------------------------------------------------------------

def _write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


_RST_SPECIAL = re.compile(r"([\\`*_|<>\[\]])")


def esc(text) -> str:
    """Plain text as one line of reStructuredText (inline markup characters escaped)."""
    s = " ".join(str(text).split())
    s = _RST_SPECIAL.sub(r"\\\1", s)
    if re.match(r"^([-+#]|\.\.|\d+[.)]\s)", s):
        s = "\\" + s
    return s


def title(text: str, char: str = "=") -> str:
    t = esc(text)
    return f"{t}\n{char * max(len(t), 3)}\n"


def lit(text) -> str:
    """Inline literal (code) text."""
    s = " ".join(str(text).split())
    return f"``{s}``" if s and "``" not in s else esc(s)


def list_table(header: list[str], rows: list[list[str]], widths: list[int] | None = None) -> str:
    """A ``list-table`` whose cells are already reStructuredText."""
    out = [".. list-table::", "   :header-rows: 1"]
    if widths:
        out.append("   :widths: " + " ".join(map(str, widths)))
    out.append("")
    for row in [header] + rows:
        out.append("   * - " + (row[0] or "\\-"))
        for cell in row[1:]:
            out.append("     - " + (cell or "\\-"))
    return "\n".join(out) + "\n"


def markdown_html(text: str) -> str:
    from markdown_it import MarkdownIt

    return MarkdownIt("commonmark", {"html": False}).enable("table").render(text)


def raw_html_block(html_text: str) -> str:
    """reStructuredText for raw HTML (as comment lines of a sphinx-gallery text block, without the ``#``)."""
    body = "\n".join("   " + ln if ln.strip() else "" for ln in html_text.strip().splitlines())
    return f".. raw:: html\n\n   <div class=\"tutorial-text\">\n{body}\n   </div>\n"


# --- the gallery -------------------------------------------------------------------------------------------------------

def _comment(text: str) -> str:
    return "\n".join(("# " + ln).rstrip() for ln in text.splitlines())


def staged_source(path: Path, quick: bool) -> str:
    """The sphinx-gallery source of one tutorial (see the module docstring)."""
    from pywarp.cli.notebooks import tutorial_notebook

    nb = tutorial_notebook(path, quick=quick)
    first, *cells = nb.cells
    heading, _, intro = first.source.partition("\n")
    doc = title(heading.lstrip("# ").strip()) + "\n"
    if intro.strip():
        doc += raw_html_block(markdown_html(intro)) + "\n"
    doc += (f".. note:: The tutorial ``tutorials/{path.parent.name}/{path.name}``, run with ``quick = {quick}``; "
            f"``pywarp notebooks`` writes it as a notebook.\n")
    parts = ['"""\n' + doc.replace("\\", "\\\\").replace('"""', '\\"\\"\\"') + '"""\n']
    for cell in cells:
        if cell.cell_type == "markdown":
            parts.append("# %%\n" + _comment(raw_html_block(markdown_html(cell.source))) + "\n")
        else:
            parts.append("# %%\n" + cell.source.rstrip() + "\n")
    return "\n".join(parts)


def stage_gallery(quick: bool) -> list[Path]:
    """Write ``_gallery_src/`` (one source per tutorial, a header per text); files of removed tutorials go."""
    from pywarp.core.figures import SEEDS, tutorials

    _write(STAGE / "GALLERY_HEADER.rst",
           "Figure gallery\n==============\n\nEvery tutorial of ``tutorials/``: the figure of a text it reproduces, its "
           "narrative and its code, grouped by text. Each page is the tutorial run at build time"
           + (" in quick mode (small sizes)" if quick else "") + "; ``pywarp figures`` writes the full-size figures "
           "and ``pywarp notebooks`` the tutorials as notebooks.\n")
    wanted = set()
    written = []
    for seed in SEEDS:
        only = os.environ.get("PYWARP_DOCS_TUTORIALS")  # a glob such as "vc/extra_*" for a partial local build
        paths = [p for p in tutorials(seed) if not only or p.relative_to(p.parents[1]).match(only)]
        if not paths:
            continue
        _write(STAGE / seed / "GALLERY_HEADER.rst", title(SEED_TITLES.get(seed, seed), "-") + "\n")
        wanted.add(STAGE / seed / "GALLERY_HEADER.rst")
        for p in paths:
            target = STAGE / seed / p.name
            _write(target, staged_source(p, quick))
            wanted.add(target)
            written.append(target)
    for f in STAGE.glob("*/*"):
        if f.is_file() and f not in wanted:
            f.unlink()
        elif f.is_dir():
            shutil.rmtree(f)  # e.g. figures written by an earlier build
    return written


_SEEN: dict[str, int] = {}


def scrape_files(block, block_vars, gallery_conf):
    """sphinx-gallery image scraper: the PNG files a code block wrote under the example's folder (the tutorials save
    their figures with matplotlib and close them, so the matplotlib scraper would see none)."""
    from sphinx_gallery.scrapers import figure_rst

    folder = Path(block_vars["src_file"]).parent / "figures"
    new = []
    for png in sorted(folder.rglob("*.png")) if folder.is_dir() else []:
        stamp = png.stat().st_mtime_ns
        if _SEEN.get(str(png)) != stamp:
            _SEEN[str(png)] = stamp
            new.append(png)
    images = []
    for png, target in zip(new, block_vars["image_path_iterator"]):
        shutil.copyfile(png, target)
        images.append(target)
    return figure_rst(images, gallery_conf["src_dir"])


def no_argv(gallery_conf, script_vars):
    """sphinx-gallery ``reset_argv``: the staged sources take no command-line arguments."""
    return []


# --- the equations (registry) ------------------------------------------------------------------------------------------

def _topic(eq) -> str:
    return eq.warp_name.split(".", 1)[0]


def entry_rst(eq) -> str:
    out = [f".. _eq-{eq.id}:", "", title(f"{eq.id}: {eq.name}", "~")]
    if eq.title:
        out += [esc(eq.title), ""]
    if eq.summary and eq.summary != eq.title:
        out += [esc(eq.summary), ""]
    fields = [("IDs", ", ".join(lit(i) for i in eq.ids)),
              ("Python", lit(f"pywarp.{eq.name}") + " / " + lit(f'pywarp.equation("{eq.id}")')),
              ("C", lit(eq.c_symbol) if eq.c_symbol else "none"),
              ("Warp", lit(f"pywarp.kernels.{eq.warp_name}")),
              ("evaluation", "element-wise (generated kernel)" if eq.elementwise else "custom (not element-wise)")]
    if eq.variants:
        fields.append(("variants", ", ".join(lit(v) for v in eq.variants)))
    out += [f":{k}: {v}" for k, v in fields] + [""]
    if eq.args:
        rows = [[lit(a.name), lit(a.kind() + (f"[{a.length}]" if a.length > 1 else "")), esc(a.domain()),
                 esc(a.unit_name), esc(a.doc) + ("" if repr(a.default).startswith("<") else
                                                 f" (default {esc(a.default)})")] for a in eq.args]
        out += ["**Arguments**", "", list_table(["name", "type", "domain", "unit", "meaning"], rows, [14, 10, 22, 8, 46])]
    if eq.options:
        rows = [[lit(o.name), ", ".join(lit(c) for c in o.choices), lit(repr(o.default)), esc(o.doc)]
                for o in eq.options]
        out += ["**Options**", "", list_table(["name", "choices", "default", "meaning"], rows, [14, 30, 12, 44])]
    outs = eq.out_specs or ()
    if outs:
        out += ["**Outputs**: " + ", ".join(lit(o.name) + f" ({esc(o.dtype)}" + (f", length {o.length}"
                                                                               if o.length > 1 else "") + ")"
                                           for o in outs), ""]
    if eq.references:
        out += ["**References**", ""] + [f"* {esc(r)}" for r in eq.references] + [""]
    if eq.tests:
        out += ["**Tests**: " + ", ".join(lit(t.split("::")[-1]) for t in eq.tests[:8])
                + (f" and {len(eq.tests) - 8} more" if len(eq.tests) > 8 else ""), ""]
    if eq.figures:
        out += ["**Tutorials**: " + ", ".join(lit(Path(f).name) for f in eq.figures), ""]
    return "\n".join(out) + "\n"


def equations_pages() -> list[str]:
    from pywarp.core.registry import entries

    by_seed: dict[str, list] = {}
    for eq in entries():
        by_seed.setdefault(eq.id.split("-", 1)[0], []).append(eq)
    names = []
    for seed in [s for s in SEED_TITLES if s in by_seed] + sorted(set(by_seed) - set(SEED_TITLES)):
        eqs = by_seed[seed]
        text = [title(f"Equations of {SEED_TITLES.get(seed, seed)}"),
                f"{len(eqs)} registered entries, grouped by topic module (``pywarp/kernels/<topic>.py``, "
                f"``cclouds/include/cclouds/<topic>.h``). Every entry is evaluated with NumPy arrays by "
                f"``pywarp.<name>(...)`` (Warp) or ``pywarp.equation(ID, impl=\"c\")`` (C).", ""]
        topics: dict[str, list] = {}
        for eq in eqs:
            topics.setdefault(_topic(eq), []).append(eq)
        for topic in sorted(topics):
            text += [title(f"{topic}", "-")]
            text += [entry_rst(eq) for eq in topics[topic]]
        _write(GEN / "equations" / f"{seed}.rst", "\n".join(text))
        names.append(f"equations/{seed}")
    _write(GEN / "equations" / "index.rst",
           title("Equation reference") + "\nEvery catalogued equation or algorithm implemented in C and Warp, from "
           "the declarations of ``pywarp.core.registry`` (``@declare``): catalogue IDs, arguments with their domain "
           "and unit, options (errata variants), outputs, references, the C symbol and the Warp twin.\n\n"
           ".. toctree::\n   :maxdepth: 1\n\n" + "\n".join(f"   {n.split('/')[1]}" for n in names) + "\n")
    return names


def traceability_page() -> None:
    from pywarp.cli.equations import implemented_rows

    rows = implemented_rows()
    body = [[lit(r["id"]), esc(r["title"]), lit(r["c"]) if r["c"] else "", lit(r["warp"]),
             esc(f"{len(r['tests'])} tests" if r["tests"] else "no test"),
             ", ".join(lit(Path(f).name) for f in r["figures"][:3])] for r in rows]
    _write(GEN / "traceability.rst",
           title("Traceability matrix") + "\nOne row per implemented catalogue ID (the table of "
           "``pywarp equations``; ``pywarp equations --format markdown`` prints it with every cell in full): the "
           "catalogue title, the C function, the Warp twin, its tests and the tutorials that use it. "
           "``pywarp equations --missing`` lists what is not implemented, ``pywarp equations --figures`` the status of "
           f"every figure.\n\n{len(rows)} IDs.\n\n"
           + list_table(["ID", "title", "C", "Warp", "tests", "tutorials"], body, [10, 34, 18, 18, 8, 12]))


# --- the C API ---------------------------------------------------------------------------------------------------------

_DECL_START = re.compile(r"^(CCL_API\b|typedef\b|#define\s+CCL_|enum\b|struct\b)")


def header_order() -> list[Path]:
    inc = ROOT / "cclouds" / "include" / "cclouds"
    umbrella = inc / "cclouds.h"
    order = [inc / m for m in re.findall(r'#include\s+"cclouds/([^"]+)"', umbrella.read_text())] if umbrella.exists() \
        else []
    order = [p for p in order if p.exists()]
    return order + sorted(p for p in inc.glob("*.h") if p not in order)


def header_items(text: str) -> tuple[str, list[tuple[str, str, str]]]:
    """(the header's leading comment, [(name, comment, declaration)]) of a header in the cffi-parsable subset."""
    lines = text.splitlines()
    lead = []
    i = 0
    while i < len(lines) and not lines[i].lstrip().startswith("/*") and not lines[i].startswith("#"):
        i += 1
    if i < len(lines) and lines[i].lstrip().startswith("/*"):
        while i < len(lines):
            lead.append(lines[i])
            if "*/" in lines[i]:
                break
            i += 1
    items, comment = [], []
    j = 0
    while j < len(lines):
        ln = lines[j]
        s = ln.strip()
        if s.startswith("/*") and j > len(lead) - 1:
            comment = [ln]
            while "*/" not in lines[j] and j + 1 < len(lines):
                j += 1
                comment.append(lines[j])
            j += 1
            continue
        if s.startswith("//"):
            comment = comment + [ln]
            j += 1
            continue
        if _DECL_START.match(s) and not s.startswith("#define CCL_API"):
            decl = [ln]
            if s.startswith("#define"):
                pass
            else:
                depth = ln.count("{") - ln.count("}")
                while (depth > 0 or not decl[-1].rstrip().endswith(";")) and j + 1 < len(lines):
                    j += 1
                    decl.append(lines[j])
                    depth += lines[j].count("{") - lines[j].count("}")
            text_decl = "\n".join(decl)
            m = (re.search(r"(ccl_\w+)\s*\(", text_decl) or re.search(r"}\s*(ccl_\w+)\s*;", text_decl)
                 or re.search(r"#define\s+(CCL_\w+)", text_decl) or re.search(r"(ccl_\w+)\s*;", text_decl))
            items.append((m.group(1) if m else s.split()[0], "\n".join(comment), text_decl))
            comment = []
        elif s:
            if not s.startswith("*"):
                comment = []
        j += 1
    return "\n".join(lead), items


def c_api_page() -> None:
    out = [title("C API"), "The public C interface of ``cclouds``, read from the headers of "
           "``cclouds/include/cclouds`` (in the order of the umbrella header ``cclouds.h``): every declaration with "
           "the comment above it (summary, ``Ref:`` catalogue ID, symbols, units, domain, output range). Link with "
           "``-lcclouds`` (CMake: ``find_package(cclouds)``, target ``cclouds::cclouds``).", ""]
    for h in header_order():
        lead, items = header_items(h.read_text(encoding="utf-8"))
        out += [f".. _c-{h.stem}:", "", title(f"{h.name}", "-")]
        if lead.strip():
            out += [".. code-block:: c", ""] + ["   " + ln for ln in lead.splitlines()] + [""]
        funcs = [n for n, _, d in items if d.lstrip().startswith("CCL_API")]
        out += [f"{len(funcs)} functions" + (": " + ", ".join(lit(n) for n in funcs) if funcs else "") + ".", ""]
        for name, comment, decl in items:
            out += [f"**{esc(name)}**", "", ".. code-block:: c", ""]
            out += ["   " + ln if ln.strip() else "" for ln in (comment + "\n" + decl).strip("\n").splitlines()]
            out += [""]
    _write(GEN / "c_api.rst", "\n".join(out) + "\n")


# --- the scenes --------------------------------------------------------------------------------------------------------

def _spec_default(p) -> str:
    if p.default_text:
        return esc(p.default_text)
    return lit(repr(p.default) if isinstance(p.default, str) else p.default)


def scene_pages() -> list[str]:
    from pywarp.core.params import specs
    from pywarp.core.scenes import scenes

    names = []
    for name, sc in scenes().items():
        out = [f".. _scene-{name}:", "", title(f"Scene {name}"), esc(sc.description), "",
               f"``pywarp render {name}``, ``pywarp animate {name}``, ``pywarp bench {name} NAME`` and "
               f"``pywarp view {name}``; settings class ``{sc.settings.__module__}.{sc.settings.__name__}``.", ""]
        if sc.paths:
            out += ["**Camera paths** (``animate --path``)", ""]
            out += [f"* ``{p.name}``{' (default)' if p.name == sc.default_path else ''}: {esc(p.description)}"
                    for p in sc.paths.values()] + [""]
        if sc.benchmarks:
            out += ["**Benchmarks** (``pywarp bench``)", ""]
            out += [f"* ``{b.name}``: {esc(b.description)}" for b in sc.benchmarks.values()] + [""]
        if sc.command_defaults:
            out += ["**Command defaults**: " + "; ".join(
                f"``{cmd}``: " + ", ".join(f"{esc(k)} = {lit(v)}" for k, v in d.items())
                for cmd, d in sc.command_defaults.items()), ""]
        out += [title("Settings", "-"), "Every field of the settings, from its parameter spec "
                "(``pywarp.core.params.specs``): the command-line option, unit, default, domain, meaning, the reason "
                "for the default and what a change invalidates.", ""]
        rows = []
        groups: dict[str, list] = {}
        for p in specs(sc.settings):
            groups.setdefault(p.group or "settings", []).append(p)
        for group, ps in groups.items():
            for p in ps:
                rows.append([lit(p.option) if p.option else lit(p.name) + " (no option)", esc(group),
                             esc(p.unit), _spec_default(p), esc(p.domain()),
                             esc(p.doc), esc(p.reason), esc(p.invalidates)])
        out.append(list_table(["option", "group", "unit", "default", "domain", "meaning", "reason for the default",
                               "invalidates"], rows, [14, 8, 6, 8, 12, 24, 20, 8]))
        _write(GEN / "scenes" / f"{name}.rst", "\n".join(out))
        names.append(name)
    _write(GEN / "scenes" / "index.rst", title("Scenes") + "\nThe registered scenes (``pywarp scenes``); each "
           "page's settings table is generated from the parameter specs.\n\n.. toctree::\n   :maxdepth: 1\n\n"
           + "\n".join(f"   {n}" for n in names) + "\n")
    return names


def generate(app=None) -> None:
    equations_pages()
    traceability_page()
    c_api_page()
    scene_pages()


def setup(app):
    app.connect("builder-inited", generate)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
