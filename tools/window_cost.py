"""The viewer window's own CPU cost per UI frame: what drawing the window takes from the renderer.

    xvfb-run -a python tools/window_cost.py [--scene clouds] [--width 640] [--height 360] [--frames 200] [--upload]

Opens the viewer's window (:class:`pywarp.viewer.window.Window`) on a session whose refined frame is done, so the
render thread is idle, draws ``--frames`` UI frames (after 30 of warm-up) as fast as the UI's frame cap allows, and
prints one JSON line: the process CPU time per UI frame (every thread: Python, ImGui, the OpenGL driver's -- under
Xvfb Mesa's llvmpipe rasterises on threads of its own) and the wall time per frame. ``--upload``: the shown image is
uploaded to its texture again every UI frame (what a frame that brings a new image costs more). Timing is noisy on a
shared machine: compare two versions by running them one after the other, more than once. Nothing is asserted.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time

#: UI frames drawn before the measurement starts (fonts, shaders and the texture made)
WARMUP_FRAMES = 30
#: the cloudscape's texture sizes here: they do not change the window's cost, and small ones start fast
SMALL_CLOUDS = {"base_size": 32, "detail_size": 16, "curl_size": 32, "weather_size": 64}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="clouds")
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=360)
    ap.add_argument("--frames", type=int, default=200)
    ap.add_argument("--upload", action="store_true", help="upload the shown image again every UI frame")
    a = ap.parse_args()
    if a.frames < 1:
        ap.error(f"--frames must be at least 1 (got {a.frames})")
    from pywarp.core import scenes as S
    from pywarp.viewer import check_window
    from pywarp.viewer import window as W
    from pywarp.viewer.session import Session

    check_window()
    sc = S.scene(a.scene)
    st = sc.settings(width=a.width, height=a.height, **(SMALL_CLOUDS if a.scene == "clouds" else {}))
    session = Session(sc, st, exclude=sc.command_exclude.get("view", ()))
    t0 = time.perf_counter()
    while session.worker.latest() is None or session.worker.busy():  # the refined frame: the renderer idle
        if session.worker.error:
            raise SystemExit(session.worker.error)
        if time.perf_counter() - t0 > 600:
            raise SystemExit("no refined frame within 600 s")
        time.sleep(0.05)
    m: dict = {}

    class Measured(W.Window):
        n = 0

        def gui(self) -> None:
            from imgui_bundle import hello_imgui

            super().gui()
            if a.upload and self.session.frame is not None:
                self._upload(self.session.frame)
            self.n += 1
            if self.n == WARMUP_FRAMES:
                m["cpu0"], m["t0"] = time.process_time(), time.perf_counter()
            if self.n == WARMUP_FRAMES + a.frames:
                m["cpu1"], m["t1"] = time.process_time(), time.perf_counter()
                hello_imgui.get_runner_params().app_shall_exit = True
            hello_imgui.request_refresh()  # no idling: every UI frame drawn

    try:
        Measured(session).run()
    finally:
        session.close()
    print(json.dumps({"scene": a.scene, "view": f"{a.width}x{a.height}", "upload": a.upload, "frames": a.frames,
                      "cpu_ms_per_ui_frame": round((m["cpu1"] - m["cpu0"]) / a.frames * 1e3, 2),
                      "wall_ms_per_ui_frame": round((m["t1"] - m["t0"]) / a.frames * 1e3, 2),
                      "LP_NUM_THREADS": os.environ.get("LP_NUM_THREADS"), "load": round(os.getloadavg()[0], 2)}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
