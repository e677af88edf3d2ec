"""`pywarp notebooks --out DIR`: every tutorial as a valid .ipynb whose code cells compile, narrative as Markdown cells;
one notebook executed top to bottom with nbclient (it writes its figure and shows it)."""
from __future__ import annotations

import importlib
import json

import pytest

from pywarp.core.figures import tutorials

cli_main = importlib.import_module("pywarp.cli.main")

pytest.importorskip("jupytext")
nbformat = pytest.importorskip("nbformat")

#: a quick tutorial whose main() body is unrolled into cells (narrative cells inside main)
EXECUTED = "vc/extra_phase_functions.py"


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("nb")
    assert cli_main.main(["notebooks", "--out", str(out), "--quick"]) == 0
    return out


def test_every_tutorial_becomes_a_valid_notebook(written):
    want = sorted(f"{p.parent.name}/{p.stem}.ipynb" for p in tutorials())
    got = sorted(str(p.relative_to(written)) for p in written.rglob("*.ipynb"))
    assert got == want
    for path in written.rglob("*.ipynb"):
        nb = nbformat.read(path, as_version=4)
        nbformat.validate(nb)
        assert nb.cells[0].cell_type == "markdown" and nb.cells[0].source.startswith("# ")
        assert any(c.cell_type == "code" and "quick = True" in c.source for c in nb.cells), path
        for cell in nb.cells:
            if cell.cell_type == "code":
                compile(cell.source, str(path), "exec")  # every cell compiles on its own
        assert not any(c.cell_type == "code" and "__main__" in c.source for c in nb.cells), path
        assert not list(written.rglob("*.part"))


def test_narrative_inside_main_becomes_markdown_cells(written):
    nb = nbformat.read(written / EXECUTED.replace(".py", ".ipynb"), as_version=4)
    kinds = [c.cell_type for c in nb.cells]
    assert kinds.count("markdown") >= 3
    assert not any(c.source.startswith("def main") for c in nb.cells)


def test_one_notebook_executes_with_nbclient(written, tmp_path):
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    nb = nbformat.read(written / EXECUTED.replace(".py", ".ipynb"), as_version=4)
    client = nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    pngs = sorted((tmp_path / "figures" / "vc").glob("*.png"))
    assert pngs, "the notebook writes its figure"
    shown = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs if "image/png" in o.get("data", {})]
    assert len(shown) == len(pngs)
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs if o.output_type == "error"]
    assert errors == [], json.dumps(errors)[:2000]


def test_open_hint_names_what_is_installed(monkeypatch):
    """The hint after ``pywarp notebooks`` names ``jupyter lab`` only where it exists; else how to install it."""
    import shutil

    from pywarp.cli import notebooks

    monkeypatch.setattr(shutil, "which", lambda *a, **k: None)
    hint = notebooks.open_hint("nb")
    assert 'pip install "cclouds[notebooks]"' in hint and hint.endswith("jupyter lab nb")
    monkeypatch.setattr(shutil, "which", lambda *a, **k: "/usr/bin/jupyter-lab")
    assert notebooks.open_hint("nb") == "open with: jupyter lab nb"
