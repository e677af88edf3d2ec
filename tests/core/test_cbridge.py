"""The settings -> C -> Warp bridge (pywarp.core.cbridge): the Warp constants and the choices' enum tables pinned to
the C values, every spec's C field present in its struct, the C check's errors in Python names, and the Warp struct
holding the C struct's float32 values."""
from __future__ import annotations

import importlib

import numpy as np
import pytest

import pywarp.kernels as kernels
from pywarp.clouds.settings import CLOUDSCAPE_PARAMS, CloudscapeSettings
from pywarp.core import cbridge
from pywarp.core.binding import ffi, lib
from pywarp.core.params import specs
from pywarp.flight.settings import FlightSettings
from pywarp.rain.settings import RainSettings
from pywarp.terrain.settings import TerrainSettings

#: each settings class and the struct its c= fields name
SCENES = [(CloudscapeSettings, CLOUDSCAPE_PARAMS), (TerrainSettings, cbridge.TERRAIN_PARAMS),
          (FlightSettings, cbridge.VOLUME_PARAMS), (RainSettings, cbridge.PARTICLES_PARAMS)]


def test_every_warp_constant_is_its_c_value():
    kernels.load_all()
    assert len(cbridge.C_CONSTANTS) >= 50
    for name, value in cbridge.C_CONSTANTS.items():
        assert int(getattr(lib(), name)) == value, name


def test_a_constant_declared_twice_with_two_values_is_refused():
    with pytest.raises(ValueError, match="CCL_VARIANT_THESIS declared as 1 and 0"):
        cbridge.c_constant("CCL_VARIANT_THESIS", 0)


@pytest.mark.parametrize("cls, struct", SCENES, ids=lambda x: getattr(x, "__name__", getattr(x, "name", "")))
def test_spec_fields_and_enum_tables_match_the_c_struct(cls, struct):
    fields = set(struct.defaults())
    named = [p for p in specs(cls) if p.c]
    assert named, cls
    for p in named:
        assert p.c in fields, (cls.__name__, p.name, p.c)
        if p.choices is not None:
            assert p.c_enum is not None and set(p.c_enum) == set(p.choices), p.name
            values = [int(getattr(lib(), n)) for n in p.c_enum.values()]
            assert len(set(values)) == len(values), p.name  # distinct C values: no two choices alike
    assert len({p.c for p in named}) == len(named)  # no C field written by two settings


@pytest.mark.parametrize("cls, struct", SCENES, ids=lambda x: getattr(x, "__name__", getattr(x, "name", "")))
def test_settings_values_reach_the_c_struct_and_the_warp_struct_alike(cls, struct):
    s = cls()
    values = s.c_values()
    c = struct.to_c(values)
    back = cbridge.read(c)
    for name, v in cbridge.settings_values(s).items():  # the settings' values, float32-rounded by the C struct
        np.testing.assert_array_equal(np.float32(back[name]), np.float32(v), err_msg=name)
    w = struct.warp_struct(c)
    module, warp_cls = struct.warp.split(":")
    for name in getattr(importlib.import_module(module), warp_cls).vars:
        got = getattr(w, name)
        got = tuple(got) if hasattr(got, "__len__") else got
        np.testing.assert_array_equal(np.float32(got), np.float32(back[name]), err_msg=name)


def test_choices_map_to_their_enum_constants():
    v = cbridge.settings_values(TerrainSettings(march="bisect", shadows="hard", fog="corrected", stage="materials"))
    L = lib()
    assert (v["march_method"], v["shadows"], v["fog_variant"], v["stage"]) == (
        L.CCL_TERRAIN_MARCH_BISECT, L.CCL_TERRAIN_SHADOWS_HARD, L.CCL_VARIANT_CORRECTED, L.CCL_TERRAIN_STAGE_MATERIALS)
    v = cbridge.settings_values(CloudscapeSettings(jitter="none", lighting="thesis", beer=False))
    assert (v["jitter_mode"], v["lighting"], v["beer"]) == (L.CCL_JITTER_NONE, L.CCL_LIGHTING_THESIS, 0)


def test_the_c_check_names_the_setting_or_the_c_field():
    s = TerrainSettings()
    object.__setattr__(s, "fog_density", -1.0)  # as if the settings' domain had let it through
    with pytest.raises(ValueError, match=r"^fog_density is out of range: it must be in \(0, 100\] "
                                         r"\(ccl_terrain_params_check\), got -1\.0$"):
        cbridge.TERRAIN_PARAMS.checked(s.c_values(), settings=s)
    with pytest.raises(ValueError, match=r"^fog_density is out of range \(ccl_terrain_params_check\), got -1\.0$"):
        cbridge.TERRAIN_PARAMS.checked(s.c_values())  # without the settings: the C name
    s = TerrainSettings()
    with pytest.raises(ValueError, match=r"^samples_per_axis is out of range \(ccl_terrain_params_check\), got 0$"):
        cbridge.TERRAIN_PARAMS.checked({**s.c_values(), "samples_per_axis": 0}, settings=s)
    with pytest.raises(ValueError, match=r"^unknown ccl_terrain_params field 'fog'$"):
        cbridge.TERRAIN_PARAMS.to_c({"fog": 1})
    with pytest.raises(ValueError, match=r"^sun must hold 3 numbers, got \(1\.0, 0\.0\)$"):
        cbridge.TERRAIN_PARAMS.to_c({"sun": (1.0, 0.0)})
    with pytest.raises(TypeError, match=r"^max_steps does not fit the C field"):
        cbridge.TERRAIN_PARAMS.to_c({"max_steps": 2.5})


def test_the_check_fills_what_it_fills_and_the_defaults_are_the_c_defaults():
    p = ffi().new("ccl_terrain_params *")
    lib().ccl_terrain_params_default(p)
    d = cbridge.TERRAIN_PARAMS.defaults()
    assert d["max_steps"] == p.max_steps and d["sun"] == (p.sun.x, p.sun.y, p.sun.z)
    c = cbridge.TERRAIN_PARAMS.checked({"seed": 7})  # ccl_terrain_params_check fills the Perlin table of the seed
    assert sorted(cbridge.read(c)["perm"][:256]) == list(range(256))
