"""``pywarp notebooks --out DIR``: every figure tutorial as a Jupyter notebook (``DIR/<seed>/<name>.ipynb``).

A tutorial is a ``# %%`` script (jupytext's percent format) whose narrative and code cells mostly live *inside*
``main(out_dir, quick=False)``, indented. jupytext alone would cut the function into cells that cannot run, so the
notebook is built as follows (:func:`tutorial_notebook`):

1. a Markdown cell from the title docstring (its first line as the heading);
2. the module's top-level cells (imports, constants, helper functions) as jupytext reads them, without ``main`` and
   without the ``if __name__ == "__main__":`` block;
3. a parameter cell ``out_dir = Path("figures") / "<seed>"``, ``quick = False`` (``--quick``: True);
4. ``main``'s body, dedented, cut at its own ``# %%`` / ``# %% [markdown]`` markers (so its narrative becomes
   Markdown cells), its final ``return [...]`` turned into ``outputs = [...]``;
5. a cell that shows the PNG files written.

When ``main``'s body cannot be unrolled like that (a ``return`` before its end, a ``yield``, ``global`` /
``nonlocal``, or a cell that does not compile on its own), ``main`` stays one code cell and step 4 becomes
``outputs = main(out_dir, quick=quick)``. Either way the notebook runs top to bottom and writes the same files as
``pywarp figures``.
"""
from __future__ import annotations

import ast
import sys
import textwrap
from pathlib import Path

PARAM_CELL = 'out_dir = Path("figures") / "{seed}"  # where the figures are written\nquick = {quick}  # True: small sizes'
SHOW_CELL = ("from IPython.display import Image, display\n\n"
             "for path in outputs:\n"
             "    if str(path).endswith(\".png\"):\n"
             "        display(Image(filename=str(path)))")


def _main_node(tree: ast.Module) -> ast.FunctionDef | None:
    return next((n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "main"), None)


def _is_main_guard(node) -> bool:
    return (isinstance(node, ast.If) and isinstance(node.test, ast.Compare)
            and isinstance(node.test.left, ast.Name) and node.test.left.id == "__name__")


def _signature_end(lines: list[str], node: ast.FunctionDef) -> int:
    """Index of the line after ``def main(...):`` (which may span lines)."""
    start = (node.decorator_list[0].lineno if node.decorator_list else node.lineno) - 1
    for i in range(node.lineno - 1, node.body[0].lineno):
        try:
            ast.parse("".join(lines[start:i + 1]) + "    pass\n")
            return i + 1
        except SyntaxError:
            continue
    return node.body[0].lineno - 1


def _unrollable(node: ast.FunctionDef) -> bool:
    last = node.body[-1]
    if not isinstance(last, ast.Return) or last.value is None:
        return False
    stack = list(node.body[:-1])
    while stack:
        n = stack.pop()
        if isinstance(n, (ast.Return, ast.Yield, ast.YieldFrom, ast.Global, ast.Nonlocal)):
            return False
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            continue  # a return inside a nested function is its own
        stack.extend(ast.iter_child_nodes(n))
    return True


def _cells_compile(nb) -> bool:
    for cell in nb.cells:
        if cell.cell_type == "code":
            try:
                compile(cell.source, "<cell>", "exec")
            except SyntaxError:
                return False
    return True


def tutorial_notebook(path, quick: bool = False):
    """The notebook (an ``nbformat`` node) of the tutorial at ``path`` (see the module docstring)."""
    import jupytext
    import nbformat.v4 as v4

    path = Path(path)
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines(keepends=True)
    tree = ast.parse(text)
    doc = ast.get_docstring(tree) or path.stem
    main = _main_node(tree)
    if main is None:
        raise ValueError(f"{path.name}: a tutorial defines main(out_dir, quick=False)")

    drop = set()  # line indices of the docstring, main and the __main__ guard
    first = tree.body[0]
    if isinstance(first, ast.Expr) and isinstance(getattr(first, "value", None), ast.Constant):
        drop.update(range(first.lineno - 1, first.end_lineno))
    for node in tree.body:
        if node is main or _is_main_guard(node):
            start = (node.decorator_list[0].lineno if getattr(node, "decorator_list", None) else node.lineno) - 1
            drop.update(range(start, node.end_lineno))
    for node in tree.body:  # cell markers inside other top-level functions/classes stay comments of their cell
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node is not main:
            drop.update(i for i in range(node.lineno, node.end_lineno) if lines[i].lstrip().startswith("# %%"))
    top = "".join(ln for i, ln in enumerate(lines) if i not in drop)

    title, _, rest = doc.strip().partition("\n\n")  # the first paragraph is the title
    cells = [v4.new_markdown_cell(f"# {' '.join(title.split())}\n\n{rest.strip()}".strip())]
    cells += [c for c in jupytext.reads(top, fmt="py:percent").cells if c.source.strip()]
    cells.append(v4.new_code_cell("from pathlib import Path\n\n" + PARAM_CELL.format(seed=path.parent.name,
                                                                                      quick=bool(quick))))
    body_cells = None
    if _unrollable(main):
        body_start = _signature_end(lines, main)
        ret = main.body[-1]
        body = lines[body_start:ret.lineno - 1]
        ret_text = "".join(lines[ret.lineno - 1:ret.end_lineno])
        body.append(ret_text.replace("return ", "outputs = ", 1))
        unrolled = jupytext.reads(textwrap.dedent("".join(body)), fmt="py:percent")
        if _cells_compile(unrolled):
            body_cells = [c for c in unrolled.cells if c.source.strip()]
    if body_cells is None:
        start = (main.decorator_list[0].lineno if main.decorator_list else main.lineno) - 1
        body_cells = [v4.new_code_cell("".join(lines[start:main.end_lineno]).rstrip()),
                      v4.new_code_cell("outputs = main(out_dir, quick=quick)")]
    cells += body_cells
    cells.append(v4.new_code_cell(SHOW_CELL))
    nb = v4.new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nb.metadata["language_info"] = {"name": "python"}
    nb.metadata["pywarp"] = {"tutorial": f"{path.parent.name}/{path.name}"}
    for c in nb.cells:  # plain nbformat cells (jupytext adds its own metadata)
        c.metadata = {}
        if c.cell_type == "code":
            c.outputs, c.execution_count = [], None
    return nb


def write_notebooks(out_dir, seed: str | None = None, quick: bool = False) -> list[Path]:
    """Write every tutorial (of ``seed``) as ``out_dir/<seed>/<name>.ipynb``, each atomically; the paths written."""
    import nbformat

    from ..core.figures import tutorials
    from ..core.output import atomic_path

    written = []
    for path in tutorials(seed):
        nb = tutorial_notebook(path, quick=quick)
        nbformat.validate(nb)
        target = Path(out_dir) / path.parent.name / (path.stem + ".ipynb")
        target.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(target) as tmp:
            tmp.write_text(nbformat.writes(nb), encoding="utf-8")
        written.append(target)
    return written


def cmd_notebooks(args) -> int:
    from ..core.output import check_output_dir

    check_output_dir(args.out, "--out")
    paths = write_notebooks(args.out, args.seed, quick=args.quick)
    print(f"wrote {len(paths)} notebooks under {args.out} ({open_hint(args.out)})")
    return 0


def open_hint(out) -> str:
    """How to open the notebooks: ``jupyter lab`` where it is installed, else how to install it (the ``notebooks``
    extra) -- nothing else of the package installs Jupyter."""
    import shutil

    if shutil.which("jupyter-lab") or shutil.which("jupyter-lab", path=str(Path(sys.executable).parent)):
        return f"open with: jupyter lab {out}"
    return f'open with JupyterLab, not installed here: pip install "cclouds[notebooks]", then jupyter lab {out}'



def add_notebooks_command(sub) -> None:
    """Add ``notebooks`` to the ``pywarp`` subparsers ``sub``."""
    from ..core.figures import SEEDS

    n = sub.add_parser("notebooks", help="write every figure tutorial as a Jupyter notebook (.ipynb)",
                       description="Write every figure tutorial as a Jupyter notebook DIR/<seed>/<name>.ipynb: the "
                                   "narrative as Markdown cells, main()'s body unrolled into cells, a parameter cell "
                                   "(out_dir, quick) and a cell showing the figures. Needs jupytext.")
    n.add_argument("--out", default="notebooks", metavar="DIR",
                   help="output folder, checked writable first (default: notebooks)")
    n.add_argument("--seed", choices=SEEDS, help="only the tutorials of this text (default: all)")
    n.add_argument("--quick", action="store_true", help="set quick = True in every notebook (small, fast figures)")
    n.set_defaults(run=cmd_notebooks)
