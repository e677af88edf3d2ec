"""The viewer's session without a window (pywarp.viewer.session): every registered scene opens and renders with its
controls; the render thread gives previews (a fraction of the pixels rendered, the window's size reconstructed) while
the camera moves and a refined frame equal to the offline render when it stops; panel changes recompute only what they invalidate; scripts are deterministic; the
benchmark mode counts frames."""
from __future__ import annotations

import time

import numpy as np
import pytest

from pywarp.core import scenes as S
from pywarp.viewer import controls as V
from pywarp.viewer.session import Script, Session, run_benchmark_headless, run_headless


def wait_frame(session, full=None, timeout=300.0, version=None):
    """The newest frame (possibly already shown) once it is ``full`` (None: either) and of ``version`` (None: any)."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        session.tick(V.Input(dt=0.0))
        session.poll()
        f = session.frame
        assert not session.worker.error, session.worker.error
        if f is not None and (full is None or f.full == full) and (version is None or f.version == version):
            return f
        time.sleep(0.01)
    raise AssertionError("no frame")


def ssim(a, b) -> float:
    from skimage.metrics import structural_similarity

    return structural_similarity(a, b, channel_axis=2, data_range=255)


@pytest.mark.parametrize("name", list(S.scenes()))
def test_every_registered_scene_opens_and_renders_with_its_controls(name, small_settings):
    sc = S.scene(name)
    session = Session(sc, small_settings(sc))
    try:
        f = wait_frame(session, full=True)
        assert f.image.dtype == np.uint8 and f.image.ndim == 3 and f.image.shape[2] == 3
        keys = set(session.controls.benchmark_keys) | {"W"}
        for _ in range(3):  # the controls drive the scene; frames keep coming
            session.tick(V.Input(dt=0.1, held=frozenset(keys), pressed=frozenset(keys)))
        wait_frame(session, version=session.version)
        assert not session.worker.error and not session.error
    finally:
        session.close()


@pytest.fixture(scope="module")
def clouds():
    return S.scene("clouds")


def test_previews_while_moving_then_the_refined_frame_equals_the_offline_render(clouds, small_settings):
    s0 = small_settings(clouds)
    session = Session(clouds, s0)
    try:
        wait_frame(session, full=True)
        for _ in range(4):
            session.tick(V.Input(dt=0.05, held=frozenset({"W"})))
            f = wait_frame(session, version=session.version)
        assert not f.full and f.image.shape[1] < s0.width  # reduced resolution while moving
        assert f.settings.reprojection  # clouds: temporal reprojection on for the previews
        assert session.settings.camera_z_km < 0.0  # W flew forward (yaw 0: along -z)
        session.clock += 1.0  # still for a while: refined
        session.tick(V.Input(dt=0.0))
        f = wait_frame(session, full=True, version=session.version)
        assert f.image.shape[:2] == (s0.height, s0.width) and not f.settings.reprojection
        offline = clouds.technique(session.settings).render()
        assert np.array_equal(f.image, offline)
    finally:
        session.close()


def test_temporal_previews_have_the_window_size_and_a_fraction_rendered(clouds, small_settings):
    """--previews temporal: while moving, frames of the window's size of which a quarter of the pixels was rendered
    (the reduction held at its start), reconstructed by pywarp.core.temporal; refined when still."""
    s0 = small_settings(clouds)
    session = Session(clouds, s0, fixed_scale=True, temporal=True)
    try:
        wait_frame(session, full=True)
        for _ in range(4):
            session.tick(V.Input(dt=0.05, held=frozenset({"W"})))
            f = wait_frame(session, version=session.version)
        assert not f.full and f.image.shape[:2] == (s0.height, s0.width)
        assert f.fresh == (s0.width // 2, s0.height // 2) and f.settings.width == f.fresh[0]
        assert f.settings.reprojection
        session.clock += 1.0
        session.tick(V.Input(dt=0.0))
        f = wait_frame(session, full=True, version=session.version)
        assert np.array_equal(f.image, clouds.technique(session.settings).render())
    finally:
        session.close()


def test_panel_changes_recompute_only_what_they_invalidate(clouds, small_settings):
    session = Session(clouds, small_settings(clouds))
    try:
        first = wait_frame(session, full=True)
        tech = session.worker.tech
        textures = tech.textures
        assert session.apply({"sun_elevation_deg": 60.0})  # sky only
        session.clock += 1.0
        session.tick(V.Input())
        sun = wait_frame(session, full=True, version=session.version)
        assert session.worker.tech is tech and tech.textures is textures
        assert not np.array_equal(sun.image, first.image)
        assert session.apply({"coverage": 0.9})  # the weather map: textures regenerated
        session.clock += 1.0
        session.tick(V.Input())
        cov = wait_frame(session, full=True, version=session.version)
        assert session.worker.tech is tech and tech.textures is not textures
        assert np.mean(np.abs(cov.image.astype(float) - sun.image.astype(float))) > 1.0
        assert not session.apply({"coverage": 2.0}) and "coverage must be in [0, 1]" in session.error
        assert session.settings.coverage == 0.9
    finally:
        session.close()


def test_a_script_plays_keys_changes_and_screenshots_deterministically(clouds, tmp_path, small_settings):
    from PIL import Image

    shots = []
    for run in range(2):
        events = [{"t": 0.0, "key": "W", "hold": 0.5}, {"t": 0.2, "key": "Right", "hold": 0.3},
                  {"t": 0.6, "screenshot": str(tmp_path / f"a{run}.png")}, {"t": 0.7, "set": {"coverage": 0.8}},
                  {"t": 0.8, "screenshot": str(tmp_path / f"b{run}.png")}]
        session = Session(clouds, small_settings(clouds), script=Script.parse(events))
        try:
            run_headless(session, timeout=600)
        finally:
            session.close()
        assert [p.name for p in session.shots_written] == [f"a{run}.png", f"b{run}.png"]
        shots.append([np.asarray(Image.open(tmp_path / f"{k}{run}.png")) for k in "ab"])
        st = session.settings
        assert st.camera_yaw_deg == pytest.approx(0.3 * V.FREE_FLY_TURN_DEG_S, abs=1e-6)
        assert st.coverage == 0.8
    assert np.array_equal(shots[0][0], shots[1][0]) and np.array_equal(shots[0][1], shots[1][1])
    assert not np.array_equal(shots[0][0], shots[0][1])
    import json

    state = json.loads((tmp_path / "a0.json").read_text())
    offline = clouds.technique(clouds.settings(**{k: (tuple(v) if isinstance(v, list) else v)
                                                  for k, v in state["settings"].items()})).render()
    assert ssim(shots[0][0], offline) >= 0.9


def test_script_errors_name_the_event():
    with pytest.raises(ValueError, match="event 0 needs a time"):
        Script.parse([{"key": "W"}])
    with pytest.raises(ValueError, match="exactly one of"):
        Script.parse([{"t": 0, "key": "W", "set": {}}])
    with pytest.raises(ValueError, match="hold must be >= 0"):
        Script.parse([{"t": 0, "key": "W", "hold": -1}])
    with pytest.raises(ValueError, match="JSON list"):
        Script.parse({"t": 0})
    s = Script.parse([{"t": 1.0, "key": "W", "hold": 0.5}, {"t": 0.0, "quit": True}])
    assert s.end == 1.5 and s.events[0]["t"] == 0.0
    pressed, held, *_ = s.at(1.0, 1.1)
    assert pressed == {"W"} and held == {"W"}
    pressed, held, *_ = s.at(1.2, 1.3)
    assert pressed == set() and held == {"W"}
    assert s.at(1.5, 1.6)[1] == set()


def test_benchmark_mode_counts_the_frames_shown(clouds, small_settings):
    session = Session(clouds, small_settings(clouds), temporal=True)
    try:
        r = run_benchmark_headless(session, seconds=1.0, warmup_s=0.5)
    finally:
        session.close()
    assert r["scene"] == "clouds" and r["frames"] > 0 and r["fps"] > 0 and r["target_fps"] == 30.0  # no window
    assert r["keys"] == sorted(V.FreeFlyControls.benchmark_keys) and r["window"] is False
    assert r["moved"] and r["time_playing"]  # clouds: the camera circles and the wind blows
    assert set(r["preview_sizes"]) and all("x" in k for k in r["preview_sizes"])
    # previews at the window's size through the temporal reconstruction, their quality against the full render
    # (1/f^2 of them rendered: f = 1 or 2 at 160 x 90, whose sides 4 does not divide; f follows the frame time)
    assert r["temporal"] and set(r["preview_sizes"]) <= {"160x90"} and 0.25 <= r["fresh_fraction"] <= 1.0
    assert set(r["internal_sizes"]) <= {"160x90", "80x45"}
    assert r["quality_samples"] >= 1 and 0 < r["ssim_p5"] <= r["ssim_mean"] <= 1 and r["ciede2000_mean"] >= 0
    assert r["target_ssim"] == [0.90, 0.80]
    assert r["meets_quality"] == (r["ssim_mean"] >= 0.90 and r["ssim_p5"] >= 0.80)


def test_benchmark_dump_holds_what_pywarp_render_reproduces(tmp_path, small_settings):
    """--dump: each sampled frame as shown, its full render and a JSON whose `render` command gives that full
    render again (run here through the CLI)."""
    import json

    from pywarp.cli.main import main

    sc = S.scene("terrain")
    session = Session(sc, small_settings(sc))
    try:
        r = run_benchmark_headless(session, seconds=1.0, warmup_s=0.5, dump=tmp_path)
    finally:
        session.close()
    infos = sorted(tmp_path.glob("terrain-*.json"))
    assert len(infos) == r["quality_samples"] >= 1
    info = json.loads(infos[-1].read_text())
    assert info["render"][:3] == ["pywarp", "render", "terrain"] and 0 < info["ssim"] <= 1
    out = tmp_path / "again.png"
    assert main(info["render"][1:] + ["--out", str(out), "--no-progress"]) == 0
    from PIL import Image

    full = np.asarray(Image.open(str(infos[-1]).replace(".json", "-full.png")))
    again = np.asarray(Image.open(out))
    assert np.array_equal(full, again)
    shown = np.asarray(Image.open(str(infos[-1]).replace(".json", "-shown.png")))
    assert shown.shape == full.shape


def test_the_viewer_shows_the_display_transform_of_the_panel(clouds, small_settings):
    """The viewer's frames are the technique's 8-bit frames: a change of exposure or tone curve in the panel shows the
    same display transform as the offline render, and rebuilds nothing (no new textures)."""
    session = Session(clouds, small_settings(clouds))
    try:
        first = wait_frame(session, full=True)
        textures = session.worker.tech.textures
        assert session.apply({"exposure_ev": 1.0, "tonemap": "exponential"})
        session.clock += 1.0
        session.tick(V.Input())
        f = wait_frame(session, full=True, version=session.version)
        assert session.worker.tech.textures is textures
        assert f.image.mean() > first.image.mean()  # 1.5 EV more than the default -0.5: brighter
        assert np.array_equal(f.image, clouds.technique(session.settings).render())
    finally:
        session.close()


def test_the_temporal_factor_doubles_at_once_for_a_preview_far_over_its_budget():
    """A temporal preview over FACTOR_JUMP budgets doubles the factor with that frame; one over 1.25 budgets only
    after three frames; one under halves it again (after three) only where four times its cost fits."""
    from pywarp.core import scenes as S
    from pywarp.core.temporal import VIEWER_FACTORS
    from pywarp.viewer.session import FACTOR_JUMP, RenderWorker

    worker = RenderWorker(S.scene("terrain"), budget_s=0.03, factor=2)
    try:
        worker._adapt_factor(0.03 * (FACTOR_JUMP + 0.5))  # the first preview: 3 budgets
        assert worker.factor == 4
        worker._adapt_factor(0.03 * 1.5)  # over 1.25 budgets but below the jump: waits for the average
        worker._adapt_factor(0.03 * 1.5)
        assert worker.factor == 4
        worker._adapt_factor(0.03 * 1.5)
        assert worker.factor == min(8, VIEWER_FACTORS[-1])
        worker.factor = 4
        worker._since_scale, worker._ema = 0, None
        for _ in range(3):
            worker._adapt_factor(0.03 * 0.1)  # 4 x 0.1 budget fits in 0.8: back to 1/4 of the pixels
        assert worker.factor == 2
        fixed = RenderWorker(S.scene("terrain"), budget_s=0.03, factor=2, fixed_scale=True)
        try:
            fixed._adapt_factor(0.03 * 10)
            assert fixed.factor == 2  # a fixed scale never adapts
        finally:
            fixed.close()
    finally:
        worker.close()
