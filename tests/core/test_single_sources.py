"""Lists that name what the source tree holds are derived from it or pinned to it here: the kernel topics (the C
umbrella header), the scene modules (the scene packages), the four texts (one list, ``pywarp.core.catalogue.SEEDS``)
and the package's submodules."""
from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pywarp

ROOT = Path(__file__).resolve().parents[2]
PKG = Path(pywarp.__file__).resolve().parent


def test_topics_are_the_umbrella_header_in_order():
    from pywarp.core.binding import header_order
    from pywarp.kernels import TOPICS

    headers = [p.stem for p in header_order(ROOT / "cclouds" / "include")]
    assert headers[0] == "common"  # types only: Warp has its own
    assert list(TOPICS) == headers[1:]
    # every other module of pywarp/kernels is a topic; common.py holds the helpers of cclouds/src/internal.h
    assert {p.stem for p in (PKG / "kernels").glob("*.py")} - {"__init__", "common"} == set(TOPICS)


def test_scene_modules_are_the_scene_packages():
    """Every subpackage above the layers of ARCHITECTURE.md (core, kernels, viewer, cli) is a scene package; its
    ``scene`` module is listed once and registers one scene."""
    from pywarp.core.scenes import SCENE_MODULES, scenes

    packages = {p.name for p in PKG.iterdir() if (p / "__init__.py").is_file()} - {"core", "kernels", "viewer", "cli"}
    assert len(SCENE_MODULES) == len(set(SCENE_MODULES))
    assert set(SCENE_MODULES) == {f"pywarp.{name}.scene" for name in packages}
    assert len(scenes()) == len(SCENE_MODULES) and {"clouds", "rain", "terrain", "flight"} <= set(scenes())


def test_the_four_texts_are_one_list():
    from pywarp.core import figures
    from pywarp.core.catalogue import SEEDS

    assert figures.SEEDS is SEEDS
    spec = importlib.util.spec_from_file_location("gen_catalogue", ROOT / "tools" / "gen_catalogue.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    assert gen.SEEDS is SEEDS
    # the folders and catalogues of the tree are those of the list
    assert sorted(p.stem for p in (ROOT / "spec").glob("*.md")) == sorted(SEEDS)
    assert sorted(p.name for p in (ROOT / "tutorials").iterdir()
                  if p.is_dir() and not p.name.startswith(("_", "."))) == sorted(SEEDS)


def test_submodules_are_never_looked_up_as_entries():
    packages = {p.name for p in PKG.iterdir() if (p / "__init__.py").is_file()}
    assert {"core", "kernels", "cli", "clouds", "terrain", "rain", "flight", "viewer"} <= packages
    assert packages <= pywarp._SUBMODULES
    # an attribute named like a submodule not yet imported fails at once, without importing the topic modules
    code = ("import sys, pywarp\n"
            "for name in sorted(pywarp._SUBMODULES):\n"
            "    if f'pywarp.{name}' not in sys.modules:\n"
            "        try:\n"
            "            getattr(pywarp, name)\n"
            "        except AttributeError:\n"
            "            pass\n"
            "        else:\n"
            "            raise SystemExit(name + ' resolved')\n"
            "print('pywarp.kernels.phase' in sys.modules)\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "False"
