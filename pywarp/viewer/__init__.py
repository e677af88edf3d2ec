"""``pywarp view <scene>``: the interactive viewer of every registered scene.

A real window (Dear ImGui through ``imgui-bundle``, :mod:`pywarp.viewer.window`) shows the scene's image as a texture
beside a panel generated from the scene's parameter specs (:mod:`pywarp.viewer.panel`); keys, the mouse and time
drive the camera and the settings through the scene's controls (:mod:`pywarp.viewer.controls`: ``Scene.controls``,
the free-fly default). Rendering runs off the UI thread on the tile-parallel launcher, at reduced resolution while the
view moves and refined to full quality when it stops (:mod:`pywarp.viewer.session`).

    pywarp view clouds                         # fly: W/S/A/D, E/Q, arrows or left-drag; F1 help, F12 screenshot
    pywarp view clouds --benchmark 10 --json   # frames/s measured by the viewer's own frame counter
    pywarp view clouds --script s.json         # timed key presses, panel changes and screenshots (deterministic)
    xvfb-run -a pywarp view clouds ...         # without a display

:func:`view` is what the command calls.
"""
from __future__ import annotations

import json
import os
import sys

from .session import Benchmark, Script, Session, report, run_benchmark_headless, run_headless

__all__ = ["view", "display_available", "Session", "Script"]


def display_available() -> bool:
    """Whether a window can be opened here (an X11 or Wayland display is named in the environment)."""
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def check_window() -> None:
    """ValueError naming what is missing before any work: the display or the imgui-bundle package."""
    if not display_available():
        raise ValueError("no display (DISPLAY and WAYLAND_DISPLAY are unset): run it under `xvfb-run -a`, or use "
                         "--no-window")
    try:
        import imgui_bundle  # noqa: F401
    except ImportError:
        raise ValueError("the viewer needs the imgui-bundle package: pip install imgui-bundle") from None


def view(scene, settings, *, window: bool = True, script: Script | None = None, benchmark: float | None = None,
         as_json: bool = False, screenshot_dir=".", window_screenshot=None, state_out=None,
         warmup_s: float = 3.0, seconds: float | None = None, dump=None, temporal: bool | None = None) -> int:
    """Run the viewer; returns the exit status (0). ``benchmark``: seconds of the benchmark mode (prints its report,
    or JSON as the last line with ``as_json``); ``state_out``: write the session's final state (settings, frame
    counts, screenshots) as JSON; ``seconds``: quit after this long (wall time); ``dump``: a folder for the
    benchmark's sampled frames (:func:`pywarp.viewer.session.compare_samples`); ``temporal``: previews through the
    temporal reconstruction (True) or enlarged reduced frames (False); None: the technique's ``preview_mode``."""
    if window:
        check_window()
    # the panel shows the settings `pywarp view` takes (e.g. not the clouds' accumulate, which only render uses)
    session = Session(scene, settings, script=script, screenshot_dir=screenshot_dir,
                      exclude=scene.command_exclude.get("view", ()), temporal=temporal)
    result = None
    try:
        if window:
            from .window import Window

            b = Benchmark(session, benchmark, warmup_s, dump=dump) if benchmark is not None else None
            w = Window(session, benchmark=b, window_screenshot=window_screenshot, seconds=seconds)
            w.run()
            result = w.result
        elif benchmark is not None:
            result = run_benchmark_headless(session, benchmark, warmup_s, dump=dump)
        else:
            run_headless(session, seconds=seconds)
    finally:
        session.close()
    if state_out is not None:
        with open(state_out, "w", encoding="utf-8") as fh:
            json.dump(session.state(), fh, indent=1)
            fh.write("\n")
    if benchmark is not None:
        if result is None:
            raise RuntimeError("the benchmark did not finish (the window was closed)")
        sys.stdout.flush()
        print(json.dumps(result) if as_json else report(result))
    if session.worker.error and (script is not None or benchmark is not None):
        raise RuntimeError(session.worker.error)
    return 0
