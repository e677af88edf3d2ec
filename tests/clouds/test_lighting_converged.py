"""The real-time lighting against the converged path-traced references (tests/data/lighting_reference and
tests/data/lighting_reference_truncated, made by tools/lighting_references.py; docs/lighting.rst): issue 32's targets
without any rescaling, absolute CIEDE2000 <= 3 and the thick cloud's energy (tau >= 3; from above the sunlit tops)
within +-10 % per channel, in every scene and view of ``pywarp bench clouds reference`` at 80x45 -- the tuning views
and the two held out alike.

The references are the judge, and the reason to believe them is independent of this project's code: the path tracer
agrees with Mitsuba 3 within its noise (tests/clouds/test_crosscheck_mitsuba.py). Two sets: the exact Mie phase
(unbiased; its thick-cloud energy converged -- standard error <= 2.5 % per channel, halves of independent seeds
agreeing -- but its pixels speckled by a firefly tail), and the forward peak truncated (peak='truncated',
pywarp.clouds.reference.PEAKS: converged pixels), checked here against the exact set: every pixel class's energy
within the two sets' standard errors, and 4x3-pixel blocks within the exact set's own noise. The truncated set is the
judge (bench_reference.PEAK); the thick cloud's energy is held to the targets against the exact set too."""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from pywarp.clouds.bench_reference import (ACCUMULATE, CLASS_EDGES, CONVERGED, CONVERGED_MODEL, CONVERGED_TRUNCATED,
                                           MEDIA, PEAK, SCENES, TUNING_SCENES, VIEWS, absolute_errors, class_mask,
                                           exposure, load_converged, model_settings)

ROOT = Path(__file__).resolve().parents[2]
FOLDER = ROOT / CONVERGED
FOLDER_TRUNCATED = ROOT / CONVERGED_TRUNCATED
VIEW_NAMES = [*SCENES, *VIEWS]
#: issue 32's targets
DE_MAX = 3.0
ENERGY = (0.90, 1.10)


@pytest.fixture(scope="module")
def base_and_textures():
    from pywarp.clouds.cloudscape import RenderTextures
    from pywarp.clouds.settings import CloudscapeSettings

    base = CloudscapeSettings(**{**MEDIA["physical"], "width": 80, "height": 45, "device": "cpu", "threads": None})
    return base, RenderTextures.generate(base)


def _class_energy(z, cls="thick"):
    """(sum over the class's pixels (default thick) of the full reference per channel, its standard error, the
    halves' difference in standard errors of the difference) from the per-pixel standard-error images (pixels
    independent)."""
    m = class_mask(z["tau"], cls)
    n, h = z["spp"], z["spp"] // 2
    sa, sb = z["a"][m].sum(axis=0), z["b"][m].sum(axis=0)
    ea, eb = np.sqrt((z["se_a"][m] ** 2).sum(axis=0)), np.sqrt((z["se_b"][m] ** 2).sum(axis=0))
    full = (h * sa + (n - h) * sb) / n
    se = np.sqrt((h * ea) ** 2 + ((n - h) * eb) ** 2) / n
    return full, se, (sa - sb) / np.sqrt(ea ** 2 + eb ** 2)


@pytest.mark.parametrize("view", VIEW_NAMES)
def test_the_references_are_converged(view):
    """Each file is 80x45, finite and non-negative, with thick cloud to judge; the thick cloud's energy of the full
    reference has a standard error <= 2.5 % per channel (so the target of +-10 % is >= 4 standard errors away), and
    its two halves (independent seeds) agree within 4 standard errors of their difference."""
    z = load_converged(FOLDER, view, 80, 45)
    assert z["spp"] >= 2048
    for k in ("a", "b"):
        assert np.all(np.isfinite(z[k])) and z[k].min() >= 0.0
    assert np.mean(z["tau"] >= 3.0) > 0.05
    full, se, z_halves = _class_energy(z)
    assert np.all(se / full <= 0.025), se / full
    assert np.all(np.abs(z_halves) <= 4.0), z_halves


def test_the_physical_medium_is_judged_with_the_truncated_peak():
    assert PEAK == {"display": "exact", "physical": "truncated"}


@pytest.mark.parametrize("view", VIEW_NAMES)
def test_the_truncated_references_are_converged_pixel_by_pixel(view):
    """The truncated set: 4096 paths per pixel, thick energy with a standard error <= 1 % and halves within 4
    standard errors, and converged pixels -- the halves' mean absolute CIEDE2000 under the reference's exposure <=
    PIXEL_FLOOR (the exact set's is 0.95-2.68: its fireflies)."""
    z = load_converged(FOLDER_TRUNCATED, view, 80, 45)
    assert z["peak"] == "truncated" and z["spp"] >= 4096
    for k in ("a", "b"):
        assert np.all(np.isfinite(z[k])) and z[k].min() >= 0.0
    full, se, z_halves = _class_energy(z)
    assert np.all(se / full <= 0.01), se / full
    assert np.all(np.abs(z_halves) <= 4.0), z_halves
    floor = absolute_errors(z["a"], z["b"], exposure(z["ref"]), z["tau"])["delta_e"]
    assert floor <= PIXEL_FLOOR, floor


#: The largest half-to-half CIEDE2000 of the truncated set (measured 0.29-0.80; the exact set 0.95-2.68).
PIXEL_FLOOR = 1.0


def _blocks(x):
    """Means over 4x3-pixel blocks (80x45 -> 20x15)."""
    return x.reshape(15, 3, 20, 4, *x.shape[2:]).mean(axis=(1, 3))


@pytest.mark.parametrize("view", VIEW_NAMES)
def test_the_truncated_references_agree_with_the_exact_ones(view):
    """The truncated forward peak changes nothing the exact references can resolve: per pixel class (clear, thin,
    thick) and channel the energies differ by <= 4 standard errors of their difference, and on 4x3-pixel blocks the
    two sets are closer (mean absolute CIEDE2000) than the exact set's two halves are to each other."""
    d = load_converged(FOLDER_TRUNCATED, view, 80, 45)
    e = load_converged(FOLDER, view, 80, 45)
    np.testing.assert_array_equal(d["tau"] >= 3.0, e["tau"] >= 3.0)  # the same view, the same cloud
    for cls in CLASS_EDGES:
        if not class_mask(e["tau"], cls).any():
            continue
        fd, sd, _ = _class_energy(d, cls)
        fe, se, _ = _class_energy(e, cls)
        z_diff = (fd - fe) / np.sqrt(sd ** 2 + se ** 2)
        assert np.all(np.abs(z_diff) <= 4.0), (cls, fd / fe, z_diff)
    ex = exposure(e["ref"])
    tau = _blocks(e["tau"].astype(np.float64))
    between = absolute_errors(_blocks(d["ref"]), _blocks(e["ref"]), ex, tau)["delta_e"]
    halves = absolute_errors(_blocks(e["a"]), _blocks(e["b"]), ex, tau)["delta_e"]
    assert between <= halves, (between, halves)


def test_the_tuning_views_leave_two_held_out():
    assert set(TUNING_SCENES) < set(VIEW_NAMES)
    assert {"low sun", "view above"}.isdisjoint(TUNING_SCENES)


def test_a_reference_of_another_size_is_refused():
    with pytest.raises(ValueError, match="80x45"):
        load_converged(FOLDER, "noon", 160, 90)
    with pytest.raises(FileNotFoundError, match="lighting_references"):
        load_converged(FOLDER, "no such view")


#: The targets CONVERGED_MODEL misses today: none (the three misses of ``physical slab`` against the exact
#: references -- the CIEDE2000 of both views from above and the view above's thick green -- are met by
#: ``physical slab 2`` against the truncated-peak ones). Strict expected failures would go here.
MISSES: set = set()
_ERRORS = {}


def _model_errors(view, base_and_textures):
    """The model's absolute errors against the judge (the truncated set) and against the exact set (each under its own
    exposure)."""
    if view not in _ERRORS:
        from pywarp.clouds.technique import CloudscapeTechnique

        base, textures = base_and_textures
        ms, why = model_settings(replace(base, **{**SCENES, **VIEWS}[view]), CONVERGED_MODEL)
        assert ms is not None, why
        lin = CloudscapeTechnique(ms, textures=textures).render_accumulated(None, ACCUMULATE, encode=False)
        _ERRORS[view] = {}
        for name, folder in (("judge", FOLDER_TRUNCATED), ("exact", FOLDER)):
            z = load_converged(folder, view, 80, 45)
            _ERRORS[view][name] = absolute_errors(lin, z["ref"], exposure(z["ref"]), z["tau"])
    return _ERRORS[view]


def _cases():
    for view in VIEW_NAMES:
        for target in ("delta_e", "energy"):
            marks = [pytest.mark.xfail(strict=True, reason="issue 32: not met by the model yet")] \
                if (view, target) in MISSES else []
            yield pytest.param(view, target, marks=marks, id=f"{view}-{target}")


@pytest.mark.parametrize("view, target", list(_cases()))
def test_the_model_meets_the_targets_without_rescaling(view, target, base_and_textures):
    """CONVERGED_MODEL (bench_reference) against the converged references, under the reference's exposure alone: the
    mean CIEDE2000 against the judge <= 3, the thick cloud's energy within 0.90-1.10 of the reference's per channel
    against the judge and the exact set."""
    e = _model_errors(view, base_and_textures)
    if target == "delta_e":
        assert e["judge"]["delta_e"] <= DE_MAX, e["judge"]["delta_e"]
    else:
        for name in ("judge", "exact"):
            thick = e[name]["ratio"]["thick"]
            assert all(ENERGY[0] <= v <= ENERGY[1] for v in thick), (name, thick)


def test_compare_reads_the_converged_references():
    """compare(converged=DIR) takes each scene's reference from the folder with its own path count (the row's
    ``spp``) and reports the halves' thick-energy difference in the noise floor; only in the physical medium."""
    from pywarp.clouds.bench_reference import compare, report

    small = dict(base_size=32, detail_size=16, curl_size=32, weather_size=64)
    res, images = compare(80, 45, scenes=["low sun"], settings=small, medium="physical", converged=str(FOLDER),
                          progress=lambda m: None)
    assert res["spp"] is None and res["converged"] == str(FOLDER)
    assert "converged references" in report(res) and "2048 paths" in report(res)
    row = res["scenes"][0]
    z = load_converged(FOLDER, "low sun", 80, 45)
    assert row["spp"] == z["spp"]
    np.testing.assert_allclose(row["exposure"], exposure(z["ref"]))
    te = row["noise_floor"]["thick_energy"]
    np.testing.assert_allclose(te, z["a"][class_mask(z["tau"], "thick")].sum(axis=0)
                               / z["b"][class_mask(z["tau"], "thick")].sum(axis=0) - 1.0, rtol=1e-9)
    assert images["low sun"]["reference"].shape == (45, 80, 3)
    with pytest.raises(ValueError, match="physical"):
        compare(80, 45, scenes=["low sun"], settings=small, medium="display", converged=str(FOLDER))
