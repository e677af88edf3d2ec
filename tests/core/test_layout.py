"""The package layout of ARCHITECTURE.md: no two modules import each other (also not inside functions), and the
layers only look down: core <- kernels <- viewer <- scenes <- cli (the viewer reaches the scenes through the registry
of pywarp.core.scenes; a scene package's controls subclass the viewer's)."""
from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PKG = ROOT / "pywarp"


def module_name(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def imports(path: Path) -> set[str]:
    """Every pywarp module ``path`` imports, at any depth of its code (relative imports resolved)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.startswith("pywarp")}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            if not mod.startswith("pywarp"):
                continue
            found.add(mod)
            for a in node.names:  # `from . import textures` imports a module
                if (PKG.parent / (mod.replace(".", "/") + f"/{a.name}.py")).is_file():
                    found.add(f"{mod}.{a.name}")
    found.discard(name)
    return found


MODULES = {module_name(p): p for p in PKG.rglob("*.py")}
GRAPH = {m: {i for i in imports(p) if i in MODULES} for m, p in MODULES.items()}


def test_the_import_scanner_sees_imports():
    assert "pywarp.core.registry" in GRAPH["pywarp.kernels.phase"]
    assert "pywarp.core.runtime" in GRAPH["pywarp.kernels"]


def test_no_two_modules_import_each_other():
    pairs = sorted({tuple(sorted((a, b))) for a, deps in GRAPH.items() for b in deps
                    if a in GRAPH.get(b, ()) and not (a == "pywarp" or b == "pywarp")})
    assert not pairs, "modules that import each other: " + ", ".join(f"{a} <-> {b}" for a, b in pairs)


LAYER = {"core": 0, "kernels": 1, "viewer": 2, "clouds": 3, "terrain": 3, "rain": 3, "flight": 3, "cli": 4}


def test_layers_only_import_downwards():
    bad = []
    for m, deps in GRAPH.items():
        parts = m.split(".")
        if len(parts) < 2 or parts[1] not in LAYER:
            continue
        for d in deps:
            dp = d.split(".")
            if len(dp) >= 2 and dp[1] in LAYER and LAYER[dp[1]] > LAYER[parts[1]]:
                bad.append(f"{m} -> {d}")
    assert not bad, "imports from a higher layer: " + ", ".join(sorted(bad))


def test_the_kernels_load_no_scene_package():
    """Importing every topic module of pywarp/kernels (and registering its entries) in a fresh interpreter loads no
    scene package, viewer or CLI: the host evaluators some entries name ("module:function") are imported only when
    such an entry is evaluated."""
    import subprocess
    import sys

    code = ("import sys, pywarp.kernels as k; k.load_all(); "
            "print(' '.join(m for m in sys.modules if m.startswith('pywarp.')))")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert res.returncode == 0, res.stderr
    loaded = res.stdout.split()
    assert any(m.startswith("pywarp.kernels.") for m in loaded), loaded  # the probe saw the topic modules
    above = [m for m in loaded if m.split(".")[1] in LAYER and LAYER[m.split(".")[1]] > LAYER["kernels"]]
    assert not above, "pywarp.kernels loads " + ", ".join(above)
