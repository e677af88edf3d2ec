"""Ctrl-C (SIGINT) and SIGTERM during `pywarp animate`: one line on stderr (`pywarp: interrupted`, exit status 130;
`pywarp: terminated`, exit status 143), no traceback, no output file and no hidden temporary file left behind, and
no ffmpeg process left running."""
from __future__ import annotations

import importlib
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


def _writer_temporaries(folder, out) -> list:
    """The video writer's hidden file for ``out`` (``.<stem>.<random><suffix>.part``), not the one the output check
    creates and removes at once to see that the folder is writable (``.probe.<random>.tmp.part``): a GIF writer's
    file stays empty until the end, so a wait for any ``.part`` could catch that probe and find nothing 0.5 s later."""
    return [f for f in folder.iterdir() if f.name.startswith(f".{out.stem}.") and f.name.endswith(f"{out.suffix}.part")]


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
            parts = _writer_temporaries(tmp_path, out)
            if parts and (suffix == ".gif" or parts[0].stat().st_size > 0):
                break
            time.sleep(0.1)
        assert p.poll() is None, p.communicate()
        time.sleep(0.5)
        if suffix == ".mp4":
            ffmpeg = _running_children(p.pid)
            assert ffmpeg, "the MP4 writer runs ffmpeg"
        # (if not: what the folder holds, and how the command ended if it did)
        assert _writer_temporaries(tmp_path, out), (
            sorted(f.name for f in tmp_path.iterdir()), p.poll(), p.communicate() if p.poll() is not None else "")
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


@pytest.mark.parametrize("signum,code,word", [(signal.SIGINT, 130, "interrupted"), (signal.SIGTERM, 143, "terminated")])
def test_an_interrupt_raised_in_a_destructor_prints_only_its_line(tmp_path, capsys, monkeypatch, signum, code, word):
    """A signal that lands while Python runs a ``__del__`` (as CI saw in a Warp array's, during `pywarp animate`):
    the handler's exception cannot be raised there and Python would print it with a traceback ("Exception ignored
    in ..."); the command still ends as interrupted, with its one line on stderr and nothing else."""
    cli_main = importlib.import_module("pywarp.cli.main")

    class Drop:
        def __del__(self):
            os.kill(os.getpid(), signum)
            for _ in range(100000):  # the Python-level handler runs at one of these bytecode boundaries
                pass

    def run(args):
        d = Drop()
        del d
        return 0

    parser = cli_main.build_parser()
    monkeypatch.setattr(cli_main, "build_parser", lambda: parser)
    parser._commands.choices["figures"].set_defaults(run=run)
    # Python's own hook (pytest replaces it with one that turns what it gets into warnings): it prints to stderr
    monkeypatch.setattr(sys, "unraisablehook", sys.__unraisablehook__)
    hook = sys.unraisablehook
    assert cli_main.main(["figures"]) == code
    err = capsys.readouterr().err
    assert err.strip().splitlines() == [f"pywarp: {word}"], err
    assert sys.unraisablehook is hook  # restored


def _drop_a_signal_in_a_destructor(signum) -> list:
    """Deliver ``signum`` while Python runs a ``__del__``, where the handler's exception is printed and dropped (as CI
    once saw a SIGTERM land in a Warp array's ``__del__``: `pywarp animate` went on and exited 0 with its file
    written). Returns what reached sys.unraisablehook."""
    dropped = []
    old_hook = sys.unraisablehook
    sys.unraisablehook = lambda u: dropped.append(u.exc_type)

    class Drop:
        def __del__(self):
            os.kill(os.getpid(), signum)
            for _ in range(100000):  # the Python-level handler runs at one of these bytecode boundaries
                pass

    try:
        d = Drop()
        del d
    finally:
        sys.unraisablehook = old_hook
    return dropped


@pytest.mark.parametrize("signum,exc_name", [(signal.SIGTERM, "Terminated"), (signal.SIGINT, "KeyboardInterrupt")])
def test_an_interrupt_dropped_in_a_destructor_still_stops_every_writer(tmp_path, signum, exc_name):
    import numpy as np

    from pywarp.core import output

    M = importlib.import_module("pywarp.cli.main")  # (pywarp.cli's `main` is the function)

    exc_type = M.Terminated if exc_name == "Terminated" else KeyboardInterrupt
    handler = M._raise_terminated if signum == signal.SIGTERM else M._raise_interrupted
    saved = {s: signal.getsignal(s) for s in (signal.SIGTERM, signal.SIGINT)}
    try:
        signal.signal(signum, handler)
        assert _drop_a_signal_in_a_destructor(signum) == [exc_type]  # the first raise was lost
        with pytest.raises(exc_type):
            output.write_png(tmp_path / "x.png", np.zeros((2, 2, 3)))
        with pytest.raises(exc_type):
            with output.VideoWriter(tmp_path / "y.gif") as w:
                w.add(np.zeros((2, 2, 3), np.uint8))
        with pytest.raises(exc_type):
            with output.atomic_path(tmp_path / "z.npy") as tmp, open(tmp, "wb") as fh:
                np.save(fh, np.zeros(3))
        assert list(tmp_path.iterdir()) == []  # no file, no .part file
    finally:
        output.clear_pending()
        for s, h in saved.items():
            signal.signal(s, h)


def test_the_command_ends_as_terminated_when_the_interrupt_was_dropped(monkeypatch, capsys):
    """A command that finishes after its SIGTERM was dropped (nothing raised it again) still ends as terminated."""
    import argparse

    M = importlib.import_module("pywarp.cli.main")

    def build_parser():
        p = argparse.ArgumentParser(prog="pywarp")
        sub = p.add_subparsers(dest="command")
        c = sub.add_parser("job")
        c.set_defaults(run=lambda args: (M.note_interrupt(M.Terminated), 0)[1])  # the handler's record, raise lost
        p._commands = sub
        return p

    monkeypatch.setattr(M, "build_parser", build_parser)
    assert M.main(["job"]) == 143
    assert capsys.readouterr().err.strip().splitlines() == ["pywarp: terminated"]
    assert M.main(["job"]) == 143  # (the record is per run: cleared at the start and the end of main)
