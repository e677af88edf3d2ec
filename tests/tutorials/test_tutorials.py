"""Tutorials: each runs headless in quick mode and writes the figures its docstring promises; at full size the
deterministic ones reproduce the committed PNGs (SSIM >= 0.99, slow); `pywarp figures` selects and runs them."""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pywarp.core import figures

ROOT = Path(__file__).resolve().parents[2]
TUTORIALS = sorted(p for p in (ROOT / "tutorials").glob("*/*.py") if not p.name.startswith("_"))


def _read_png(path):
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0


def test_installed_tutorials_match_the_source_tree():
    installed = sorted(p.relative_to(figures.tutorial_dir()).as_posix() for p in figures.tutorials())
    assert installed == sorted(p.relative_to(ROOT / "tutorials").as_posix() for p in TUTORIALS)


@pytest.mark.parametrize("path", TUTORIALS, ids=lambda p: p.stem)
def test_tutorial_runs_in_quick_mode(path, tmp_path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    doc = ast.get_docstring(tree)
    assert doc and figures.figure_ids(path), f"{path.name}: the title docstring must name the figure it reproduces"
    assert "plt.show" not in path.read_text(encoding="utf-8")
    written = figures.load(path).main(tmp_path, quick=True)
    assert written, f"{path.name} wrote nothing"
    for f in written:
        f = Path(f)
        assert f.is_file() and f.parent == tmp_path and f.suffix == ".png"
        img = _read_png(f)
        assert img.ndim == 3 and img.shape[0] > 50 and img.shape[1] > 50
        assert np.all(np.isfinite(img)) and img.std() > 0.01  # not blank


@pytest.mark.slow
@pytest.mark.parametrize("path", TUTORIALS, ids=lambda p: p.stem)
def test_tutorial_full_size_matches_committed_figure(path, tmp_path):
    from skimage.metrics import structural_similarity

    module = figures.load(path)
    if not getattr(module, "DETERMINISTIC", True):
        pytest.skip(f"{path.name} draws measurements (timings): not comparable run to run")
    written = module.main(tmp_path, quick=False)
    assert written, f"{path.name} wrote nothing"
    for f in written:
        committed = ROOT / "figures" / path.parent.name / Path(f).name
        assert committed.is_file(), f"{committed} is not committed"
        a, b = _read_png(f), _read_png(committed)
        assert a.shape == b.shape
        assert structural_similarity(a, b, channel_axis=2, data_range=1.0) >= 0.99


def test_cli_figures_only_and_bad_selection(tmp_path):
    res = subprocess.run([sys.executable, "-m", "pywarp", "figures", "--seed", "vc", "--quick", "--out",
                          str(tmp_path), "--only", "extra-phase-functions", "--no-progress"],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    assert (tmp_path / "vc" / "extra-phase-functions.png").is_file()
    res = subprocess.run([sys.executable, "-m", "pywarp", "figures", "--only", "fig-9.99", "--out", str(tmp_path)],
                         capture_output=True, text=True)
    assert res.returncode == 2
    assert res.stderr.strip().splitlines()[-1] == "pywarp figures: error: --only: no tutorial reproduces fig-9.99"


def test_figure_index_is_up_to_date():
    res = subprocess.run([sys.executable, str(ROOT / "tools" / "gen_figure_index.py"), "--check"],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr


def test_figure_index_links_each_figure_to_its_own_image():
    """A tutorial of several figures (oc figs 2.6-2.9, pt 4.1/4.2, ...): each row of figures/README.md links the
    image of its own figure, and every image it links exists."""
    import re

    index = (ROOT / "figures" / "README.md").read_text(encoding="utf-8")
    rows = [r for r in index.splitlines() if r.startswith("| ") and "-fig-" in r.split("|")[1]]
    checked = 0
    for row in rows:
        fid = row.split("|")[1].strip()
        seed, stem = fid.split("-", 1)
        links = re.findall(r"\]\(([a-z]+/[\w.\-]+\.png)\)", row.split("|")[3])
        for link in links:
            assert (ROOT / "figures" / link).is_file(), (fid, link)
        if (ROOT / "figures" / seed / f"{stem}.png").is_file() and links:
            assert f"{seed}/{stem}.png" in links, (fid, links)
            assert all(Path(k).name.startswith(stem) for k in links), (fid, links)
            checked += 1
    assert checked > 100, checked


def test_a_failing_tutorial_is_reported_and_the_others_run(tmp_path):
    seed = tmp_path / "vc"
    seed.mkdir()
    (seed / "broken.py").write_text("def main(out_dir, quick=False):\n    raise RuntimeError('boom')\n")
    (seed / "fine.py").write_text("from pathlib import Path\n\ndef main(out_dir, quick=False):\n"
                                  "    p = Path(out_dir) / 'ok.txt'\n    p.write_text('x')\n    return [p]\n")
    failures = []
    written = figures.run([seed / "broken.py", seed / "fine.py"], tmp_path / "out", progress=False,
                          failures=failures)
    assert [p.name for p in written] == ["ok.txt"]
    assert [(p.name, str(e)) for p, e in failures] == [("broken.py", "boom")]
    with pytest.raises(RuntimeError, match="^boom$"):
        figures.run([seed / "broken.py"], tmp_path / "out", progress=False)
