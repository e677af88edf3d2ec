"""The disk texture cache's size cap (least recently used entries removed first; $PYWARP_CACHE_MAX_SIZE) and
``pywarp cache info|clear``. Entries are made from small synthetic arrays: no texture is generated."""
from __future__ import annotations

import importlib
import json
import os
import time

import numpy as np
import pytest

from pywarp.clouds import textures as T
from pywarp.clouds.settings import WeatherMapSettings

cli_main = importlib.import_module("pywarp.cli.main")


def _run(*argv):
    try:
        return cli_main.main(list(argv))
    except SystemExit as exc:
        return exc.code


def _put(cache, seed, size=16):
    """One weather-map entry (size x size x 4 float32, ~4 KiB + header for 16) made by a stand-in generator."""
    s = WeatherMapSettings(size=size, seed=seed)
    return cache.get("weather_map", s, "warp", "cpu", lambda: np.full(s.shape, seed / 100.0, np.float32))


def _path(cache, seed, size=16):
    return cache.path("weather_map", cache.key("weather_map", WeatherMapSettings(size=size, seed=seed), "warp", "cpu"))


def _age(cache, seeds, seconds_ago):
    """Last-use times (mtime) of the entries of ``seeds``: one second apart in that order, ``seconds_ago`` back."""
    now = time.time()
    for i, seed in enumerate(seeds):
        os.utime(_path(cache, seed), (now - seconds_ago + i, now - seconds_ago + i))


@pytest.fixture
def cache_env(tmp_path, monkeypatch):
    monkeypatch.setenv("PYWARP_CACHE_DIR", str(tmp_path / "c"))
    monkeypatch.delenv(T.MAX_SIZE_ENV, raising=False)
    monkeypatch.setattr(T, "_default_cache", None)  # a fresh process-wide cache for this test
    return tmp_path / "c" / "textures"


def test_default_cap_and_the_environment_variable(cache_env, monkeypatch):
    assert T.DEFAULT_MAX_DISK_BYTES == 2 * 2 ** 30 and T.max_disk_bytes() == T.DEFAULT_MAX_DISK_BYTES
    for text, value in [("500M", 500 * 2 ** 20), ("4G", 4 * 2 ** 30), ("1.5GiB", int(1.5 * 2 ** 30)),
                        ("123", 123), ("64 KB", 64 * 1024), ("0", 0), ("unlimited", None)]:
        monkeypatch.setenv(T.MAX_SIZE_ENV, text)
        assert T.max_disk_bytes() == value, text
    for bad in ("-1", "5X", "lots", "1e9"):
        monkeypatch.setenv(T.MAX_SIZE_ENV, bad)
        with pytest.raises(ValueError, match=f"^{T.MAX_SIZE_ENV} must be a size"):
            T.max_disk_bytes()
        made = []
        with pytest.raises(ValueError, match=T.MAX_SIZE_ENV):  # before any texture is generated
            T.TextureCache().get("weather_map", WeatherMapSettings(size=16), "warp", "cpu", lambda: made.append(1))
        assert not made
    with pytest.raises(ValueError, match="max_disk_bytes must be >= 0"):
        T.TextureCache(max_disk_bytes=-1)


def test_least_recently_used_entries_are_evicted_beyond_the_cap(tmp_path):
    probe = T.TextureCache(tmp_path / "probe", memory=False)
    _put(probe, 0)
    one = probe.entries()[0]["bytes"]
    cache = T.TextureCache(tmp_path, memory=False, max_disk_bytes=3 * one)
    for seed in (1, 2, 3):
        _put(cache, seed)
    _age(cache, (1, 2, 3), 100)
    assert [r["path"] for r in cache.entries()] == [_path(cache, s) for s in (1, 2, 3)]
    assert sum(r["bytes"] for r in cache.entries()) == 3 * one
    oldest = _path(cache, 1).name
    # reading seed 1 (the oldest) marks it used: seed 2 is now the least recently used and goes on the next write
    cache_reader = T.TextureCache(tmp_path, memory=False, max_disk_bytes=3 * one)
    assert float(_put(cache_reader, 1)[0, 0, 0]) == pytest.approx(0.01) and cache_reader.stats["disk_hits"] == 1
    assert cache.entries()[-1]["path"].name == oldest
    lru = _path(cache, 2).name
    assert cache.entries()[0]["path"].name == lru
    _put(cache, 4)
    names = [r["path"].name for r in cache.entries()]
    assert len(names) == 3 and lru not in names and oldest in names and cache.evicted == 1
    assert sum(r["bytes"] for r in cache.entries()) <= 3 * one
    # a smaller cap applies at the next write: down to one entry, the newest
    small = T.TextureCache(tmp_path, memory=False, max_disk_bytes=one)
    _put(small, 5)
    assert len(small.entries()) == 1 and small.stats["misses"] == 1
    assert float(_put(T.TextureCache(tmp_path, memory=False), 5)[0, 0, 0]) == pytest.approx(0.05)


def test_cap_zero_keeps_nothing_on_disk_and_unlimited_keeps_everything(tmp_path, monkeypatch):
    monkeypatch.setenv(T.MAX_SIZE_ENV, "0")
    cache = T.TextureCache(tmp_path, memory=False)
    _put(cache, 1)
    assert cache.entries() == [] and not list(cache.directory.glob("*.pwtex*"))
    monkeypatch.setenv(T.MAX_SIZE_ENV, "unlimited")
    for seed in range(4):
        _put(cache, seed)
    assert len(cache.entries()) == 4 and cache.evict() == (0, 0)


def test_cli_cache_info_and_clear(cache_env, capsys):
    cache = T.default_cache()
    for seed in (1, 2):
        _put(cache, seed)
    stale = cache_env / ".weather_map-x.1234abcd.pwtex.part"  # what a killed writer leaves
    stale.write_bytes(b"x" * 10)
    os.utime(stale, (time.time() - 7200, time.time() - 7200))
    fresh = cache_env / ".weather_map-y.5678abcd.pwtex.part"  # a writer at work now: left alone
    fresh.write_bytes(b"y")
    (cache_env / "notes.txt").write_text("not an entry")

    assert _run("cache", "info") == 0
    out = capsys.readouterr().out
    assert str(cache_env) in out and "2 entries" in out and "cap of 2.0 GiB (default" in out
    assert "weather_map" in out and T.MAX_SIZE_ENV in out
    assert _run("cache", "info", "--json") == 0
    info = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    total = sum(r["bytes"] for r in cache.entries())
    assert info["entries"] == 2 and info["bytes"] == total and info["max_bytes"] == T.DEFAULT_MAX_DISK_BYTES
    assert info["by_kind"] == {"weather_map": {"entries": 2, "bytes": total}} and info["cap_from"] == "default"

    assert _run("cache", "clear", "--json") == 0
    res = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert res == {"directory": str(cache_env), "removed": 2, "bytes_freed": total + 10}
    assert cache.entries() == [] and not stale.exists() and fresh.exists() and (cache_env / "notes.txt").exists()
    assert _run("cache", "clear") == 0
    assert "removed 0 texture cache entries" in capsys.readouterr().out


def test_cli_cache_bad_arguments(cache_env, capsys, monkeypatch):
    assert _run("cache", "purge") == 2
    assert "action must be one of info, clear, got 'purge'" in capsys.readouterr().err
    monkeypatch.setenv(T.MAX_SIZE_ENV, "big")
    assert _run("cache", "info") == 2
    assert f"pywarp cache: error: {T.MAX_SIZE_ENV} must be a size" in capsys.readouterr().err


def test_cli_cache_info_on_a_missing_folder(cache_env, capsys):
    assert _run("cache", "info", "--json") == 0
    info = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert info["entries"] == 0 and info["least_recently_used"] is None
