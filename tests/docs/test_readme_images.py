"""The README opens with one rendered image per registered scene (docs/images/<scene>.png, made by
tools/readme_images.py), committed small."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_the_readme_opens_with_an_image_of_every_scene():
    from PIL import Image

    from pywarp.core.scenes import scenes

    readme = ROOT / "README.md"
    if not readme.exists():
        pytest.skip("no README in this tree")
    head = readme.read_text(encoding="utf-8").split("\n## ", 1)[0]  # before the first section
    shown = re.findall(r'<img src="docs/images/([\w-]+)\.png"', head)
    assert sorted(shown) == sorted(scenes()), "one image per registered scene (python tools/readme_images.py)"
    for name in shown:
        path = ROOT / "docs" / "images" / f"{name}.png"
        assert path.is_file(), path
        with Image.open(path) as img:
            assert img.size == (480, 270), (name, img.size)
        assert path.stat().st_size < 400_000, (name, path.stat().st_size)
    assert "docs/" in head  # the docs are linked from the top
