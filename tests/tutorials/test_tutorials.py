"""Tutorials: each runs headless in quick mode and writes the figures its docstring promises, with legible text (no
title, label or tick label outside the figure or over another text or another plot); at full size the deterministic
ones reproduce the committed PNGs (SSIM >= 0.99, slow); `pywarp figures` selects and runs them."""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pywarp.core import figures
from pywarp.tutorial import checking_legibility, fit_text, text_problems

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
    with checking_legibility() as problems:
        written = figures.load(path).main(tmp_path, quick=True)
    assert written, f"{path.name} wrote nothing"
    assert not problems, problems
    for f in written:
        f = Path(f)
        assert f.is_file() and f.parent == tmp_path and f.suffix == ".png"
        img = _read_png(f)
        assert img.ndim == 3 and img.shape[0] > 50 and img.shape[1] > 50
        assert np.all(np.isfinite(img)) and img.std() > 0.01  # not blank


def test_legibility_check_finds_clipped_and_overlapping_text():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 1, figsize=(4, 3), dpi=100)
    for ax in axes:
        ax.imshow(np.zeros((4, 4)))
        ax.set_axis_off()
    axes[0].set_title("fits")
    assert text_problems(fig) == []
    axes[1].set_title("a title\nof three\nlines")  # climbs over the image above it
    fig.suptitle("a suptitle far wider than a figure four inches wide can hold")
    found = text_problems(fig)
    assert any("sticks out of the figure" in p and "suptitle" in p for p in found), found
    assert any("axes 1 title" in p and "plot area of axes 0" in p for p in found), found
    plt.close(fig)


def test_text_problems_checks_the_labels_placed_in_an_axes():
    """Labels placed with ax.text / ax.annotate count: two that overlap are reported; an annotation's arrow over
    another label is not (the text's own box counts), nor is a clipped text outside its axes (it is not drawn)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(3, 2), dpi=100)
    ax.plot([0, 1], [0, 1])
    ax.set_axis_off()  # no tick labels: only the placed labels are in question
    ax.annotate("label one", (0.2, 0.2), xytext=(0.1, 0.8), arrowprops=dict(arrowstyle="->"))
    ax.text(0.6, 0.5, "label two")  # the arrow of "label one" passes nowhere near; apart from it
    ax.text(5.0, 5.0, "clipped away", clip_on=True)  # outside the view limits: not drawn
    assert text_problems(fig) == []
    ax.text(0.62, 0.52, "label three")  # on top of "label two"
    found = text_problems(fig)
    assert any("axes 0 text 'label two'" in p and "'label three'" in p for p in found), found
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(3, 2), dpi=100)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_axis_off()
    ax.text(0.45, 0.5, "a label")
    # the arrow of this annotation crosses "a label"; its text stands clear of it
    ax.annotate("far", (0.5, 0.52), xytext=(0.1, 0.15), arrowprops=dict(arrowstyle="-"))
    assert text_problems(fig) == []
    plt.close(fig)


def test_fit_text_makes_a_crowded_figure_legible_and_leaves_a_legible_one_as_it_was(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def figure(suptitle):
        # seven square images in a 2 x 4 grid: tight_layout puts the second row's titles on the first row's images
        fig, axes = plt.subplots(2, 4, figsize=(13, 7), dpi=50)
        for ax in axes.ravel()[:7]:
            ax.imshow(np.arange(16.0).reshape(4, 4))
            ax.set_title("a title", fontsize=8)
        for ax in axes.ravel():
            ax.set_axis_off()
        fig.suptitle(suptitle, fontsize=11)
        return fig

    crowded = "a suptitle " + "far wider than the figure, " * 12 + "even at seven points"
    fig = figure(crowded)
    fig.tight_layout()
    found = text_problems(fig)
    assert any("figure text" in p and "sticks out of the figure" in p for p in found), found
    assert any("axes 4 title" in p and "plot area of axes 0" in p for p in found), found
    plt.close(fig)
    fig = figure(crowded)
    assert fit_text(fig, tight_layout=True) is True
    assert text_problems(fig) == []
    sup = fig.texts[0]
    assert sup.get_fontsize() >= 7.0 and "\n" in sup.get_text()  # shrunk to the floor, then wrapped
    assert " ".join(sup.get_text().split()) == crowded  # every word kept
    plt.close(fig)

    # legible as laid out: fit_text is the tight_layout asked for, the same pixels
    for name in ("plain", "fitted"):
        fig, axes = plt.subplots(1, 2, figsize=(4, 2), dpi=50)
        for ax in axes:
            ax.plot([0, 1], [1, 0])
            ax.set_title("fits", fontsize=8)
        fig.suptitle("fits")
        if name == "plain":
            fig.tight_layout()
        else:
            assert fit_text(fig, tight_layout=True) is False
        assert text_problems(fig) == []
        fig.savefig(tmp_path / f"{name}.png")
        plt.close(fig)
    assert (tmp_path / "plain.png").read_bytes() == (tmp_path / "fitted.png").read_bytes()

    # a title band above an image laid out by hand: the band grows, the image keeps its pixels
    fig = plt.figure(figsize=(1.0, 0.9), dpi=100)
    ax = fig.add_axes([0, 0, 1, 0.6])
    ax.imshow(np.zeros((6, 10)))
    ax.set_axis_off()
    fig.text(0.5, 0.8, "a title much wider than this small figure", ha="center", va="center", fontsize=9)
    label = ax.text(0.5, 1.0, "a panel label running out of the figure", color="white", fontsize=8)
    bottom, height = ax.get_position().y0 * 90, ax.get_position().height * 90
    assert text_problems(fig)
    assert fit_text(fig) is True
    assert text_problems(fig) == []
    h = fig.bbox.height
    assert h > 90 and abs(ax.get_position().y0 * h - bottom) < 1e-6 and abs(ax.get_position().height * h - height) < 1e-6
    box = label.get_window_extent(fig.canvas.get_renderer())
    assert box.x1 <= fig.bbox.width and "\n" in label.get_text()  # wrapped to fit, hanging down into its axes
    assert box.y1 <= ax.bbox.y1 + 1
    plt.close(fig)


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
