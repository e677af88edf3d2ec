"""Ctrl-C (SIGINT) and SIGTERM during `pywarp animate`: one line on stderr (`pywarp: interrupted`, exit status 130;
`pywarp: terminated`, exit status 143), no traceback, no output file and no hidden temporary file left behind, and
no ffmpeg process left running."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


def _running_children(pid: int) -> list[str]:
    out = subprocess.run(["ps", "-o", "pid=,comm=", "--ppid", str(pid)], capture_output=True, text=True).stdout
    return [line for line in out.splitlines() if line.strip()]


@pytest.mark.parametrize("suffix", [".mp4", ".gif"])
@pytest.mark.parametrize("signum,code,word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")])
def test_animate_interrupted_mid_run_leaves_nothing(tmp_path, suffix, signum, code, word):
    out = tmp_path / f"fly{suffix}"
    # many frames, so that it is still running when the signal comes; it is stopped after a few
    p = subprocess.Popen([sys.executable, "-m", "pywarp", "animate", "--width", "64", "--height", "36", "--frames",
                          "5000", "--out", str(out), "--no-progress"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path)
    try:
        deadline = time.monotonic() + 240
        ffmpeg = []
        while time.monotonic() < deadline and p.poll() is None:  # wait until frames are being written
            parts = [f for f in tmp_path.iterdir() if f.name.endswith(".part")]
            if parts and (suffix == ".gif" or parts[0].stat().st_size > 0):
                break
            time.sleep(0.1)
        assert p.poll() is None, p.communicate()
        time.sleep(0.5)
        if suffix == ".mp4":
            ffmpeg = _running_children(p.pid)
            assert ffmpeg, "the MP4 writer runs ffmpeg"
        assert any(f.name.endswith(".part") for f in tmp_path.iterdir())
        p.send_signal(signum)
        stdout, stderr = p.communicate(timeout=120)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    assert p.returncode == code, stderr
    assert stderr.strip().splitlines() == [f"pywarp: {word}"], stderr
    assert "Traceback" not in stderr
    assert list(tmp_path.iterdir()) == []  # no output file, no hidden .part file
    for line in ffmpeg:  # the encoder was stopped too
        child = int(line.split()[0])
        time.sleep(0.2)
        with pytest.raises(ProcessLookupError):
            os.kill(child, 0)


def test_interrupt_in_process_returns_130_and_removes_temporaries(tmp_path, capsys, monkeypatch):
    """main(argv) (not the program) returns the status instead of ending the process."""
    import importlib

    import numpy as np

    cli_main = importlib.import_module("pywarp.cli.main")
    from pywarp.core.output import VideoWriter

    def run(args):
        with VideoWriter(tmp_path / "v.gif", fps=10) as vw:
            vw.add(np.zeros((8, 8, 3), np.float32))
            raise KeyboardInterrupt

    parser = cli_main.build_parser()
    monkeypatch.setattr(cli_main, "build_parser", lambda: parser)
    parser._commands.choices["figures"].set_defaults(run=run)
    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    assert cli_main.main(["figures"]) == 130
    assert capsys.readouterr().err.strip() == "pywarp: interrupted"
    assert list(tmp_path.iterdir()) == []
    assert (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)) == before  # handlers restored
