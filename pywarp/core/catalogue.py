"""The catalogue: the one list of texts (seeds) and the IDs of their equations, algorithms, tables and figures.

The IDs come from ``spec/<seed>.md`` (regenerated into ``pywarp/data/catalogue.json`` by ``tools/gen_catalogue.py``,
together with the index of the tests and tutorials that cite each ID).
"""
from __future__ import annotations

import json
import re
from functools import lru_cache
from importlib import resources

#: The four texts, in the order the project presents them (key, what it builds).
SEEDS: dict[str, str] = {
    "vc": "volumetric clouds over a Preetham sky (master's thesis, 2020)",
    "pt": "ray-marched procedural terrain demo (2016)",
    "rr": "realistic rain after Rousseau et al. (2009)",
    "oc": "value-noise clouds in OpenGL with a flight simulator (2006)",
}

#: Catalogue kinds that are computational (equations, algorithms, code listings, data tables: implemented in C and
#: Warp and tested); figures and measurements have their own status (reproduced by a tutorial, measured by a bench).
COMPUTATIONAL_KINDS = ("equation", "algorithm", "code", "table")


@lru_cache(maxsize=None)
def catalogue() -> dict:
    """The shipped catalogue data (IDs with titles and kinds, test index, tutorial index)."""
    text = resources.files("pywarp").joinpath("data/catalogue.json").read_text(encoding="utf-8")
    return json.loads(text)


_TOKEN = re.compile(r"(\d+)")


def sort_key(cid: str):
    """Natural order of catalogue IDs: by text (vc, pt, rr, oc), then numbers as numbers (vc-A3 before vc-A28,
    vc-2.9 before vc-2.13)."""
    seed, _, rest = cid.partition("-")
    parts = []
    for tok in re.split(r"[.\-]", rest):
        for piece in _TOKEN.split(tok):
            if piece:
                parts.append((0, int(piece), "") if piece.isdigit() else (1, 0, piece))
        parts.append((-1, 0, ""))  # separator: "2.1" sorts before "2.10" and "2.1a"
    order = list(SEEDS)
    return (order.index(seed) if seed in order else len(order), seed, parts)


@lru_cache(maxsize=None)
def _not_computational() -> dict:
    text = resources.files("pywarp").joinpath("data/not_computational.json").read_text(encoding="utf-8")
    return json.loads(text)


def not_computational_reason(cid: str) -> str | None:
    """Why a catalogued ID has no C/Warp implementation by design (a figure, a class diagram, ...), else None."""
    data = _not_computational()
    if cid in data:
        return data[cid]
    kind = catalogue()["ids"].get(cid, {}).get("kind")
    return data["_kinds"].get(kind)
