"""Parameter specs (pywarp.core.params): one validation mechanism with the registry's wording, immutable settings
changed by a validated ``replace``, the specs listed by ``specs``, and command-line options generated from them."""
from __future__ import annotations

import argparse
import dataclasses
from dataclasses import dataclass

import numpy as np
import pytest

from pywarp.core.params import Param, Settings, add_options, from_options, inherit, param, specs


def _even(obj, name, v):
    if v % 2:
        raise ValueError(f"{name} must be even, got {v}")


@dataclass(frozen=True)
class Demo(Settings):
    INVALIDATES = Settings.INVALIDATES + ("sky", "textures")

    count: int = param(8, unit="px", kind="int", lo=1, hi=64, doc="a count", reason="8: small", check=_even)
    size: int = param(16, kind="int", lo=4, hi=512, pow2=True, doc="a size", reason="16: small",
                      invalidates="textures")
    box: int = param(1, kind="int", lo=1, hi=9, odd=True, doc="a box", reason="1: none")
    seed: int = param(0, kind="uint32", lo=0, hi=2 ** 32 - 1, doc="a seed", reason="0: reference")
    offset: int = param(0, kind="int", doc="an unbounded integer", reason="0")
    gain: float = param(2.5, lo=2.0, hi=10.0, doc="a gain", reason="2.5: clear", invalidates="sky")
    g: float = param(0.2, lo=-1.0, hi=1.0, lo_open=True, hi_open=True, doc="asymmetry", reason="0.2")
    angle_deg: float = param(0.0, unit="deg", doc="any angle", reason="0: ahead", cli="--angle")
    mode: str = param("a", choices=("a", "b"), doc="a mode", reason="'a'")
    flag: bool = param(True, doc="a switch", reason="on")
    threads: int | None = param(None, kind="int", lo=1, hi=64, optional=True, default_text="one per core",
                                doc="threads", reason="None: one per core", invalidates="device")
    weights: tuple = param((1.0, 0.5), doc="two weights", reason="halving")
    extra: dict = param({}, doc="anything else", reason="{}: none")


def test_defaults_are_valid_and_specs_list_every_field():
    d = Demo()
    names = [p.name for p in specs(Demo)]
    assert names == [f.name for f in dataclasses.fields(Demo)]
    for p in specs(Demo):
        assert isinstance(p, Param) and p.doc and p.reason and p.invalidates in Demo.INVALIDATES
        assert getattr(d, p.name) == p.default
    assert specs(d) == specs(Demo)


@pytest.mark.parametrize("kw,exc,pattern", [
    (dict(count=0), ValueError, r"^count must be in \[1, 64\], got 0$"),
    (dict(count=3), ValueError, r"^count must be even, got 3$"),
    (dict(count=True), TypeError, r"^count must be an integer, got True$"),
    (dict(count=8.0), TypeError, r"^count must be an integer, got 8\.0$"),
    (dict(count="8"), TypeError, r"^count must be an integer, got '8'$"),
    (dict(size=12), ValueError, r"^size must be a power of two in \[4, 512\], got 12$"),
    (dict(size=1024), ValueError, r"^size must be a power of two in \[4, 512\], got 1024$"),
    (dict(box=2), ValueError, r"^box must be an odd integer in \[1, 9\], got 2$"),
    (dict(seed=-1), ValueError, r"^seed must be in \[0, 4294967295\], got -1$"),
    (dict(seed=2 ** 32), ValueError, r"^seed must be in \[0, 4294967295\], got 4294967296$"),
    (dict(offset=2 ** 31), ValueError, r"^offset must be in \[-2147483648, 2147483647\] \(int32\), got 2147483648$"),
    (dict(gain=11), ValueError, r"^gain must be in \[2, 10\], got 11$"),
    (dict(gain=1.5), ValueError, r"^gain must be in \[2, 10\], got 1\.5$"),
    (dict(gain=float("nan")), ValueError, r"^gain must be finite \(no NaN or Inf\), got nan$"),
    (dict(angle_deg=float("inf")), ValueError, r"^angle_deg must be finite \(no NaN or Inf\), got inf$"),
    (dict(angle_deg=1e39), ValueError, r"^angle_deg must be within the float32 range"),
    (dict(gain=True), TypeError, r"^gain must be a number, got True$"),
    (dict(gain="3"), TypeError, r"^gain must be a number, got '3'$"),
    (dict(g=1.0), ValueError, r"^g must be in \(-1, 1\), got 1\.0$"),
    (dict(mode="c"), ValueError, r"^mode must be one of 'a', 'b', got 'c'$"),
    (dict(flag=1), TypeError, r"^flag must be True or False, got 1$"),
    (dict(threads=0), ValueError, r"^threads must be in \[1, 64\], got 0$"),
    (dict(weights=(1.0,)), ValueError, r"^weights must hold 2 numbers, got 1$"),
    (dict(weights=3.0), TypeError, r"^weights must be a sequence of 2 numbers"),
    (dict(extra=[]), TypeError, r"^extra must be a dict, got \[\]$"),
])
def test_validation_wording_and_types(kw, exc, pattern):
    with pytest.raises(exc, match=pattern):
        Demo(**kw)


def test_values_are_normalised_and_edges_accepted():
    d = Demo(count=np.int64(64), size=4, box=9, seed=np.uint32(2 ** 32 - 1), gain=np.float32(10), g=-0.999,
             threads=64, weights=[2, 1], flag=np.bool_(False), offset=-(2 ** 31))
    assert type(d.count) is int and type(d.seed) is int and type(d.gain) is float and d.weights == (2.0, 1.0)
    assert d.flag is False and Demo(threads=None).threads is None


def test_settings_are_immutable_and_replace_validates():
    d = Demo()
    with pytest.raises(dataclasses.FrozenInstanceError):
        d.gain = 3.0
    e = dataclasses.replace(d, gain=3.0)
    assert e.gain == 3.0 and d.gain == 2.5
    with pytest.raises(ValueError, match=r"^gain must be in \[2, 10\], got 12\.0$"):
        dataclasses.replace(d, gain=12.0)
    assert e.changed(d) == {"gain"} and e.invalidated(d) == {"sky"}
    assert dataclasses.replace(d, angle_deg=5.0).invalidated(d) == set()
    assert dataclasses.replace(d, size=32, threads=2).invalidated(d) == {"textures", "device"}


def test_param_refuses_a_spec_without_doc_reason_or_known_invalidation():
    with pytest.raises(ValueError, match="doc and the reason"):
        param(1.0, doc="x", reason="")
    @dataclass(frozen=True)
    class Bad(Settings):
        x: float = param(1.0, doc="x", reason="y", invalidates="textures")  # not one of Settings.INVALIDATES

    with pytest.raises(ValueError, match=r"^Bad\.x: invalidates must be one of 'nothing', 'size', 'device', "
                                         r"got 'textures'$"):
        Bad()
    with pytest.raises(ValueError, match="^c_enum must map every choice"):
        param("a", choices=("a", "b"), doc="x", reason="y", c="mode", c_enum={"a": "CCL_A"})


def test_inherit_takes_the_spec_declared_once():
    @dataclass(frozen=True)
    class Other(Settings):
        INVALIDATES = Demo.INVALIDATES

        gain: float = inherit(Demo, "gain")
        size: int = inherit(Demo, "size", cli="--texture-size")

    (g, s) = specs(Other)
    assert dataclasses.replace(g, name="") == dataclasses.replace(specs(Demo)[5], name="")
    assert s.option == "--texture-size" and Other().size == 16
    with pytest.raises(ValueError, match=r"^gain must be in \[2, 10\]"):
        Other(gain=1.0)


def _parser():
    p = argparse.ArgumentParser(prog="demo")
    add_options(p, Demo, defaults={"count": 16})
    return p


def test_cli_options_and_help_come_from_the_specs():
    p = _parser()
    text = p.format_help()
    assert "STR" not in text and "--extra" not in text and "--weights" not in text  # no option for dict/tuple
    assert "--angle" in text and "--angle-deg" not in text
    flat = " ".join(text.split())
    assert "a count [px]; [1, 64]; default: 16" in flat  # the command's default, unit and range
    assert "{a,b}" in flat and "choices: a, b; default: a" in flat
    assert "a power of two in [4, 512]; default: 16" in flat
    assert "threads; [1, 64]; default: one per core" in flat
    assert "any angle [deg]; any finite value; default: 0" in flat
    assert "--flag, --no-flag" in flat


def test_cli_values_are_parsed_and_errors_name_the_option():
    p = _parser()
    d = from_options(Demo, p.parse_args(["--gain", "3", "--no-flag", "--mode", "b", "--threads", "auto"]),
                     defaults={"count": 16})
    assert (d.gain, d.flag, d.mode, d.threads, d.count) == (3.0, False, "b", None, 16)
    cases = [(["--gain", "11"], r"^--gain must be in \[2, 10\], got 11$"),
             (["--gain", "abc"], r"^--gain must be a number, got 'abc'$"),
             (["--gain", "nan"], r"^--gain must be finite \(no NaN or Inf\), got nan$"),
             (["--count", "2.5"], r"^--count must be an integer, got '2\.5'$"),
             (["--count", "7"], r"^--count must be even, got 7$"),
             (["--seed", "-1"], r"^--seed must be in \[0, 4294967295\], got -1$"),
             (["--mode", "z"], r"^--mode must be one of 'a', 'b', got 'z'$"),
             (["--angle", "1e40"], r"^--angle must be within the float32 range")]
    for argv, pattern in cases:
        with pytest.raises(ValueError, match=pattern):
            from_options(Demo, p.parse_args(argv))
