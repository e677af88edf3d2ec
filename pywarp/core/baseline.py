"""Another installation of this project measured beside this one (``pywarp bench ... --baseline PYTHON``): a probe
(Python source) runs in that interpreter, in a clean environment (without the variables that point at this checkout)
and an empty working folder, and answers one JSON line per command on its stdout, so that two installations can take
turns measurement by measurement in one run. Used by ``pywarp bench clouds speed`` and ``pywarp bench SCENE still``.
"""
from __future__ import annotations

#: Variables removed from the baseline's environment: they point at this checkout (its package, its C library), and
#: the other interpreter must import its own installation
BASELINE_ENV_DROP = ("PYTHONPATH", "PYTHONHOME", "PYTHONSTARTUP", "CCLOUDS_LIBRARY", "CCLOUDS_INCLUDE_DIR")


#: The start of every probe's source: the protocol keeps the real stdout; anything else printed (import notices) goes
#: to stderr
PROBE_HEAD = r"""
import dataclasses, json, os, sys, time

if __name__ == "__main__":  # the protocol keeps the real stdout; anything else printed (import notices) goes to stderr
    proto = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)
"""

#: The end of every probe's source: as a program it builds ``PROBE_CLASS(config)``, answers ``describe(probe)`` with
#: ``ready``, then one JSON line per command (``answer(probe, command)``) until ``quit``; an error is answered as
#: ``{"error": ...}`` before the program fails
PROBE_SERVE = r"""
if __name__ == "__main__":
    def send(obj):
        proto.write(json.dumps(obj) + "\n")
        proto.flush()

    try:
        probe = PROBE_CLASS(json.loads(sys.argv[1]))
        send(dict(describe(probe), ready=True))
        for line in sys.stdin:
            cmd = line.strip()
            if cmd == "quit":
                break
            send(answer(probe, cmd))
    except Exception as exc:
        send({"error": type(exc).__name__ + ": " + str(exc)})
        raise
"""


def probe_source(body: str) -> str:
    """A probe's whole source: :data:`PROBE_HEAD`, ``body`` (which defines ``PROBE_CLASS``, ``describe(probe)`` and
    ``answer(probe, command)``, using only what the measured installations have), :data:`PROBE_SERVE`. Self-contained:
    the other interpreter runs it with ``-c`` and needs nothing of this module."""
    return PROBE_HEAD + body + PROBE_SERVE


class BaselineError(ValueError):
    """The ``--baseline`` interpreter is missing, cannot import pywarp, or failed during the measurement."""


def check_baseline(python) -> str:
    """The ``--baseline`` interpreter's full path; :class:`BaselineError` naming ``--baseline`` if it is missing."""
    import os
    import shutil

    if not isinstance(python, (str, os.PathLike)) or not str(python):
        raise BaselineError(f"--baseline must be the path of a Python interpreter, got {python!r}")
    found = shutil.which(str(python))
    if found is None:
        why = "not executable" if os.path.exists(str(python)) else "no such file"
        raise BaselineError(f"--baseline must be a Python interpreter with pywarp installed; {str(python)!r}: {why}")
    return found


class BaselineProcess:
    """The probe in another interpreter, answering one command at a time (so that the two sides never run at once)."""

    def __init__(self, python: str, cfg: dict, probe: str):
        import json
        import os
        import subprocess
        import tempfile

        self.python = python
        env = {k: v for k, v in os.environ.items() if k not in BASELINE_ENV_DROP}
        self._dir = tempfile.TemporaryDirectory(prefix="pywarp-baseline-")  # no source folder on its path
        self._err = tempfile.TemporaryFile()
        self.proc = subprocess.Popen([python, "-c", probe, json.dumps(cfg)], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=self._err, text=True, env=env,
                                     cwd=self._dir.name)
        self.info = self._answer("start")

    def _stderr_tail(self, lines: int = 3) -> str:
        self._err.seek(0)
        text = self._err.read().decode("utf-8", "replace").strip().splitlines()
        return " | ".join(line.strip() for line in text[-lines:]) or "no output"

    def _fail(self, what: str):
        try:
            rc = self.proc.wait(timeout=30)
        except Exception:  # noqa: BLE001  (still running after a broken answer)
            self.proc.kill()
            rc = self.proc.wait()
        tail = self._stderr_tail()
        self.close()
        raise BaselineError(f"--baseline {self.python} failed {what} (exit status {rc}): {tail}")

    def _answer(self, what: str) -> dict:
        import json

        line = self.proc.stdout.readline()
        if not line:
            self._fail(f"at the {what}" if what == "start" else f"while measuring {what}")
        try:
            reply = json.loads(line)
        except ValueError:
            reply = None
        if not isinstance(reply, dict):
            self.proc.kill()
            self._fail(f"at the {what}: it answered {line.strip()[:80]!r}, not the probe's JSON")
        if "error" in reply:
            self._fail(f"at the {what}" if what == "start" else f"while measuring {what}")
        return reply

    def ask(self, kind: str) -> dict:
        """Send one command and return the probe's answer (a dict; a failure raises :class:`BaselineError`)."""
        try:
            self.proc.stdin.write(kind + "\n")
            self.proc.stdin.flush()
        except (BrokenPipeError, OSError):
            self._fail(f"while measuring {kind}")
        return self._answer(kind)

    def measure(self, kind: str) -> float:
        """Send one command whose answer is a time ``ms`` and return it."""
        ms = self.ask(kind).get("ms")
        if not isinstance(ms, (int, float)):
            self._fail(f"while measuring {kind}: no time in its answer")
        return float(ms)

    def close(self) -> None:
        import subprocess

        if self.proc.poll() is None:
            try:
                self.proc.stdin.write("quit\n")
                self.proc.stdin.flush()
                self.proc.wait(timeout=30)
            except (OSError, ValueError, subprocess.TimeoutExpired):
                self.proc.kill()
                self.proc.wait()
        for f in (self.proc.stdin, self.proc.stdout):
            try:
                f.close()
            except (OSError, ValueError):
                pass
        self._err.close()
        self._dir.cleanup()
