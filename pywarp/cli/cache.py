"""``pywarp cache info|clear``: the on-disk texture cache (:class:`pywarp.clouds.textures.TextureCache`).

    pywarp cache info [--json]    the folder, its entries by kind, their size and the cap (least recently used first
                                  beyond it; $PYWARP_CACHE_MAX_SIZE changes the cap, $PYWARP_CACHE_DIR the folder)
    pywarp cache clear [--json]   remove every entry (textures are regenerated when next needed)
"""
from __future__ import annotations

import json
import os


def _size(n: int | None) -> str:
    if n is None:
        return "unlimited"
    for unit in ("B", "KiB", "MiB", "GiB"):
        if abs(n) < 1024 or unit == "GiB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1024
    return f"{n:.1f} TiB"  # pragma: no cover


def cache_info(cache=None) -> dict:
    """What ``pywarp cache info`` prints, as a dict (JSON-serialisable)."""
    from ..clouds import textures as T

    cache = cache or T.default_cache()
    cap = cache.max_disk_bytes  # ValueError naming PYWARP_CACHE_MAX_SIZE when it is malformed
    rows = cache.entries()
    by_kind: dict[str, dict] = {}
    for r in rows:
        k = by_kind.setdefault(r["kind"], {"entries": 0, "bytes": 0})
        k["entries"] += 1
        k["bytes"] += r["bytes"]
    env = os.environ.get(T.MAX_SIZE_ENV)
    return {"directory": str(cache.directory), "entries": len(rows), "bytes": sum(r["bytes"] for r in rows),
            "max_bytes": cap, "cap_from": f"${T.MAX_SIZE_ENV}" if env and env.strip() else "default",
            "default_max_bytes": T.DEFAULT_MAX_DISK_BYTES, "by_kind": dict(sorted(by_kind.items())),
            "least_recently_used": rows[0]["used"] if rows else None,
            "most_recently_used": rows[-1]["used"] if rows else None}


def cmd_cache(args) -> int:
    from ..clouds import textures as T

    info = cache_info()
    if args.action == "clear":
        removed, freed = T.default_cache().clear_disk()
        res = {"directory": info["directory"], "removed": removed, "bytes_freed": freed}
        if args.json:
            print(json.dumps(res))
        else:
            print(f"removed {removed} texture cache entries ({_size(freed)}) from {info['directory']}")
        return 0
    if args.json:
        print(json.dumps(info))
        return 0
    import time

    cap = "unlimited" if info["max_bytes"] is None else _size(info["max_bytes"])
    print(f"texture cache {info['directory']}")
    print(f"  {info['entries']} entries, {_size(info['bytes'])} of a cap of {cap} ({info['cap_from']}; set "
          f"${T.MAX_SIZE_ENV}, e.g. 500M, 4G, unlimited, to change it; least recently used entries go first)")
    for kind, k in info["by_kind"].items():
        print(f"  {kind:<13} {k['entries']:5d} entries {_size(k['bytes']):>11}")
    if info["entries"]:
        fmt = lambda t: time.strftime("%Y-%m-%d %H:%M", time.localtime(t))  # noqa: E731
        print(f"  last used between {fmt(info['least_recently_used'])} and {fmt(info['most_recently_used'])}")
    return 0


def add_cache_command(sub) -> None:
    """Add ``cache`` to the ``pywarp`` subparsers ``sub``."""
    c = sub.add_parser("cache", help="show (info) or empty (clear) the on-disk texture cache",
                       description="Show (info) or empty (clear) the on-disk texture cache: $PYWARP_CACHE_DIR, else "
                       "$XDG_CACHE_HOME/pywarp, else ~/.cache/pywarp, under textures/. It holds at most "
                       "$PYWARP_CACHE_MAX_SIZE (default 2 GiB), least recently used entries removed first.")
    c.add_argument("action", choices=("info", "clear"), help="info: folder, entries, size, cap; clear: remove all")
    c.add_argument("--json", action="store_true", help="print one JSON object")
    c.set_defaults(run=cmd_cache)
