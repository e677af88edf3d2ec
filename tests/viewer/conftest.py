"""Fixtures of the viewer tests: a display server (our own Xvfb, else the DISPLAY given; the window tests skip with
the reason where there is neither), small settings per scene, and running ``pywarp view`` as a program."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

#: small settings options per scene (fast renders); every scene with a width and height gets 160 x 90
SMALL = {"clouds": ["--base-size", "32", "--detail-size", "16", "--curl-size", "32", "--weather-size", "64"]}


def _small_options(sc) -> list[str]:
    from pywarp.core.params import specs

    names = {p.name for p in specs(sc.settings)}
    opts = ["--width", "160", "--height", "90"] if {"width", "height"} <= names else []
    return opts + SMALL.get(sc.name, [])


def _small_settings(sc, **changes):
    """The scene's settings at the size of :func:`small_options`."""
    from pywarp.core.params import specs

    names = {p.name for p in specs(sc.settings)}
    values = {"width": 160, "height": 90} if {"width", "height"} <= names else {}
    if sc.name == "clouds":
        values.update(base_size=32, detail_size=16, curl_size=32, weather_size=64)
    values.update(changes)
    return sc.settings(**values)


@pytest.fixture(scope="session")
def display():
    """A display for real windows: our own Xvfb (``-displayfd``), else $DISPLAY; skip where there is neither or
    where imgui-bundle is missing."""
    try:
        import imgui_bundle  # noqa: F401
    except ImportError:
        pytest.skip("imgui-bundle is not installed: no window can be opened")
    xvfb = shutil.which("Xvfb")
    if xvfb is None:
        if os.environ.get("DISPLAY"):
            yield os.environ["DISPLAY"]
            return
        pytest.skip("no display server: DISPLAY is unset and Xvfb is not installed (apt-get install xvfb)")
    r, w = os.pipe()
    proc = subprocess.Popen([xvfb, "-displayfd", str(w), "-screen", "0", "1280x800x24", "-nolisten", "tcp"],
                            pass_fds=(w,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(w)
    number = b""
    with os.fdopen(r, "rb") as fh:
        while not number.endswith(b"\n"):
            c = fh.read(1)
            if not c:
                break
            number += c
    if not number.strip():
        proc.kill()
        proc.wait()
        pytest.skip("Xvfb could not be started")
    try:
        yield f":{number.decode().strip()}"
    finally:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def _run_view(args, cwd: Path, display: str | None, timeout: float = 600.0) -> subprocess.CompletedProcess:
    """``pywarp view ARGS`` as a program (window on ``display``, or --no-window where it is None)."""
    env = dict(os.environ)
    env.pop("WAYLAND_DISPLAY", None)
    if display is None:
        env.pop("DISPLAY", None)
    else:
        env["DISPLAY"] = display
    return subprocess.run([sys.executable, "-m", "pywarp", "view", *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=timeout)


@pytest.fixture(scope="session")
def small_options():
    """``small_options(scene) -> [options]``: command-line options for small, fast renders."""
    return _small_options


@pytest.fixture(scope="session")
def small_settings():
    """``small_settings(scene, **changes)``: the scene's settings for small, fast renders."""
    return _small_settings


@pytest.fixture(scope="session")
def run_view():
    """``run_view(args, cwd, display)``: ``pywarp view ARGS`` as a program."""
    return _run_view
