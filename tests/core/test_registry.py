"""The registry and the shipped catalogue: every registered ID is catalogued and complete (C symbol present in the
library, Warp function, tests), the catalogue data is up to date with spec/ tests/ tutorials/, and the
`pywarp equations` command prints the traceability matrix."""
from __future__ import annotations

import inspect
import subprocess
import sys
from pathlib import Path

import pytest

import pywarp
from pywarp.core import binding as _cclouds
from pywarp.core.registry import catalogue, entries, missing, registry

ROOT = Path(__file__).resolve().parents[2]


def test_catalogue_data_is_up_to_date():
    """pywarp/data/catalogue.json is what tools/gen_catalogue.py makes from spec/, tests/ and tutorials/ now."""
    res = subprocess.run([sys.executable, str(ROOT / "tools" / "gen_catalogue.py"), "--check"],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    shipped = (ROOT / "pywarp" / "data" / "catalogue.json").read_text(encoding="utf-8")
    installed = (Path(pywarp.__file__).parent / "data" / "catalogue.json").read_text(encoding="utf-8")
    assert installed == shipped, "the installed package is older than the source tree: pip install . again"


def test_catalogue_holds_every_id_of_the_four_texts():
    ids = catalogue()["ids"]
    counts = {s: sum(1 for e in ids.values() if e["seed"] == s) for s in ("vc", "pt", "rr", "oc")}
    # vc.md states its contents: 52 equations, 36 algorithm entries, 37 figures, 11 measurement rows
    vc = [e for e in ids.values() if e["seed"] == "vc"]
    assert sum(e["kind"] == "equation" for e in vc) == 52
    assert sum(e["kind"] == "algorithm" for e in vc) == 36
    assert sum(e["kind"] == "figure" for e in vc) == 37
    assert sum(e["kind"] == "measurement" for e in vc) == 11
    assert all(n > 0 for n in counts.values()), counts
    assert ids["vc-2.13"]["title"] == "Henyey–Greenstein (HG) phase function"


def test_every_registered_entry_is_complete():
    ids = catalogue()["ids"]
    lib = _cclouds.lib()
    for cid, eq in registry().items():
        assert cid in ids, f"{cid} is registered but not catalogued"
        assert eq.c_symbol and hasattr(lib, eq.c_symbol), f"{cid}: C symbol {eq.c_symbol} missing from libcclouds"
        assert eq.warp is not None and eq.kernel is not None or eq.make_warp is not None, cid
        assert eq.tests, f"{cid} has no test marked @pytest.mark.spec({cid!r})"
        assert eq.name.isidentifier()


def test_registered_names_are_unique_and_exposed_on_the_package():
    names = [eq.name for eq in entries()]
    assert len(names) == len(set(names))
    for eq in entries():
        fn = getattr(pywarp, eq.name)
        assert fn.equation is eq


def test_phase_contract_keywords():
    """The fixed keyword names of the foundation contract."""
    sig = {n: list(inspect.signature(getattr(pywarp, n)).parameters) for n in
           ("phase_isotropic", "phase_rayleigh", "phase_hg", "phase_schlick", "phase_schlick_k")}
    assert sig == {"phase_isotropic": [], "phase_rayleigh": ["cos_theta"], "phase_hg": ["cos_theta", "g"],
                   "phase_schlick": ["cos_theta", "k", "variant"], "phase_schlick_k": ["g"]}
    assert pywarp.equation("vc-2.15").equation.variants == ("corrected", "thesis")


def test_equation_lookup_errors():
    with pytest.raises(KeyError, match="unknown catalogue ID 'vc-99.1'"):
        pywarp.equation("vc-99.1")
    with pytest.raises(ValueError, match="impl must be 'warp' or 'c'"):
        pywarp.equation("vc-2.13", impl="cuda")
    not_done = missing("vc")
    assert not_done  # the figures and measurements of vc are catalogued but never registered
    cid = not_done[0][0]
    with pytest.raises(NotImplementedError, match=f"{cid} .* not implemented"):
        pywarp.equation(cid)


def test_string_evaluators_resolve_lazily_and_fail_clearly():
    """make_warp/make_c as "module:function" (host evaluators outside pywarp.kernels): imported on first use; a
    malformed string is refused at declaration, a missing module or function names the entry and the reference."""
    from pywarp.core.registry import Equation, declare, evaluator

    eq = Equation("xx-1", "xx", None, None, make_warp="pywarp.core.registry:registry", make_c=len)
    assert evaluator(eq, "warp") is registry and evaluator(eq, "c") is len
    with pytest.raises(ImportError, match=r"xx-1: make_warp 'pywarp\.no_such:f': module 'pywarp\.no_such'"):
        evaluator(Equation("xx-1", "xx", None, None, make_warp="pywarp.no_such:f"), "warp")
    with pytest.raises(AttributeError, match=r"xx-1: make_c 'pywarp\.core\.registry:no_such'.* no function"):
        evaluator(Equation("xx-1", "xx", None, None, make_c="pywarp.core.registry:no_such"), "c")
    for bad in ("pywarp.core.registry.registry", "pywarp.core.registry:", ":registry", "pywarp..core:f"):
        with pytest.raises(ValueError, match="xx-2: make_warp must be a callable or a 'module:function' string"):
            declare("xx-2", c=None, make_warp=bad)
    # the entries that name their host evaluator this way resolve to the scene package's function
    sim = registry()["rr-code-5.2.2"]
    assert isinstance(sim.make_warp, str) and callable(evaluator(sim, "warp")) and callable(evaluator(sim, "c"))


def test_missing_lists_exactly_the_unregistered_ids():
    reg = set(registry())
    ids = catalogue()["ids"]
    assert {cid for cid, _ in missing()} == set(ids) - reg
    assert {cid for cid, _ in missing("pt")} == {c for c, e in ids.items() if e["seed"] == "pt"} - reg


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "pywarp", *args], capture_output=True, text=True, cwd=ROOT / "tests")


def test_cli_equations_prints_traceability_matrix():
    res = _cli("equations", "--seed", "vc")
    assert res.returncode == 0, res.stderr
    lines = {line.split()[0]: line for line in res.stdout.splitlines() if line.startswith("vc-")}
    for cid in ("vc-2.11", "vc-2.12", "vc-2.13", "vc-2.15", "vc-2.16"):
        assert cid in lines
        assert "ccl_" in lines[cid] and "phase." in lines[cid] and "test_" in lines[cid]
    assert "implemented of" in res.stdout


def test_cli_equations_missing_lists_other_texts():
    res = _cli("equations", "--missing")  # the computational IDs only; figures: `pywarp equations --figures`
    assert res.returncode == 0, res.stderr
    listed = {line.split()[0] for line in res.stdout.splitlines() if line[:3] in ("vc-", "pt-", "rr-", "oc-")}
    assert listed == {cid for cid, _ in missing(computational=True)}
    assert "vc-2.13" not in listed and not any("-fig-" in cid for cid in listed)


def test_cli_bad_option_is_one_line_error():
    res = _cli("equations", "--seed", "xx")
    assert res.returncode == 2
    assert res.stderr == "pywarp equations: error: --seed must be one of vc, pt, rr, oc, got 'xx'\n"


def test_not_computational_reasons_only_for_catalogued_unregistered_ids():
    import json

    data = json.loads((ROOT / "pywarp" / "data" / "not_computational.json").read_text(encoding="utf-8"))
    ids, reg = catalogue()["ids"], registry()
    for cid in data:
        if cid.startswith("_"):
            continue
        assert cid in ids and cid not in reg, cid
    rows = dict(missing("vc"))
    assert "figure" in rows["vc-fig-2.2"]["reason"]
    assert rows["vc-A34"]["reason"].startswith("technologies")


def test_public_helpers_are_reachable_from_the_package():
    from pywarp.clouds import noise
    from pywarp.kernels import camera, sky

    assert pywarp.camera_look_at is camera.camera_look_at
    assert pywarp.sun_direction is sky.sun_direction
    assert pywarp.perlin2 is noise.perlin2 and pywarp.interpolants is noise.interpolants
    with pytest.raises(AttributeError):
        pywarp.no_such_name
