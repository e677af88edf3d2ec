"""The documentation site (docs/, Sphinx + sphinx-gallery): every tutorial runs in the gallery and gets a page with
its figure, the generated pages exist, and the index and a gallery page render in headless Chromium with no console
error and every image loaded.

The site is built by `.ci/run` (`sphinx-build -W`, quick mode) into docs/_build/html, or wherever PYWARP_DOCS_HTML
points. Without a built site or without Chromium these tests skip, unless PYWARP_DOCS_REQUIRED=1 (set by `.ci/run`),
where they fail instead.

The browser check speaks the Chrome DevTools protocol over `--remote-debugging-pipe` (file descriptors 3 and 4,
NUL-separated JSON messages): no WebSocket client and no browser download are needed, only Debian's `chromium`. It
records console errors (`Runtime.consoleAPICalled` of type error, `Runtime.exceptionThrown`, `Log.entryAdded` of
level error -- a missing image or script is logged there -- and `Network.loadingFailed`), then asks the page for
every `<img>`: complete with a natural width > 0.
"""
from __future__ import annotations

import ast
import json
import os
import re
import shutil
import subprocess
import time
from pathlib import Path

import pytest

from pywarp.core.figures import tutorials

ROOT = Path(__file__).resolve().parents[2]
REQUIRED = os.environ.get("PYWARP_DOCS_REQUIRED", "") not in ("", "0")


def _skip(reason: str):
    if REQUIRED:
        pytest.fail(f"{reason} (PYWARP_DOCS_REQUIRED is set)")
    pytest.skip(reason)


def _gallery_conf() -> dict:
    """sphinx_gallery_conf of docs/conf.py, its literal values only (conf.py itself is not run: it stages files)."""
    tree = ast.parse((ROOT / "docs" / "conf.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "sphinx_gallery_conf":
            out = {}
            for k, v in zip(node.value.keys, node.value.values):
                try:
                    out[ast.literal_eval(k)] = ast.literal_eval(v)
                except ValueError:
                    pass
            return out
    raise AssertionError("docs/conf.py defines no sphinx_gallery_conf")


def test_the_gallery_pattern_executes_every_tutorial():
    """sphinx-gallery executes only the files whose path matches filename_pattern (re.search on the full path; the
    default runs only plot_*): every tutorial's staged source must match it and not ignore_pattern."""
    if not (ROOT / "docs" / "conf.py").exists():
        pytest.skip("no docs/ in this tree")
    conf = _gallery_conf()
    pattern, ignore = conf["filename_pattern"], conf.get("ignore_pattern", r"__init__\.py")
    src = ROOT / "docs" / conf["examples_dirs"]
    paths = tutorials()
    assert paths
    for p in paths:
        staged = str(src / p.parent.name / p.name)
        assert re.search(pattern, staged), staged
        assert not re.search(ignore, os.path.normpath(staged)), staged


@pytest.fixture(scope="module")
def html() -> Path:
    d = Path(os.environ.get("PYWARP_DOCS_HTML", ROOT / "docs" / "_build" / "html"))
    if not (d / "index.html").exists():
        _skip(f"no built documentation in {d} (sphinx-build -W -b html docs docs/_build/html)")
    return d


def test_every_tutorial_has_an_executed_gallery_page_with_its_figure(html):
    missing, no_figure = [], []
    for p in tutorials():
        page = html / "gallery" / p.parent.name / f"{p.stem}.html"
        if not page.exists():
            missing.append(str(page.relative_to(html)))
            continue
        text = page.read_text(encoding="utf-8")
        imgs = re.findall(r'<img[^>]+src="([^"]*sphx_glr_[^"]+\.png)"', text)
        if not imgs or not all((page.parent / src).resolve().is_file() for src in imgs):
            no_figure.append(p.name)
    assert not missing, f"tutorials without a gallery page: {missing}"
    assert not no_figure, f"gallery pages without their figure: {no_figure}"


def test_generated_pages_exist(html):
    from pywarp.core.scenes import scenes

    for page in ["usage.html", "gallery/index.html", "_generated/traceability.html", "_generated/c_api.html",
                 "_generated/equations/index.html", "_generated/equations/vc.html", "_generated/scenes/index.html"]:
        assert (html / page).is_file(), page
    for name in scenes():
        text = (html / "_generated" / "scenes" / f"{name}.html").read_text(encoding="utf-8")
        assert "Settings" in text and "<table" in text, name
    api = (html / "_generated" / "equations" / "vc.html").read_text(encoding="utf-8")
    assert "ccl_phase_hg" in api and "vc-2.13" in api
    c_api = (html / "_generated" / "c_api.html").read_text(encoding="utf-8")
    assert "phase.h" in c_api and "ccl_phase_hg" in c_api


# --- headless Chromium over the DevTools protocol ---------------------------------------------------------------------

def _chromium() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome", "chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


class _Browser:
    """Headless Chromium driven through --remote-debugging-pipe (CDP messages on fds 3/4, NUL-terminated)."""

    def __init__(self, exe: str, profile: Path):
        import fcntl

        def high(fd):  # above 9, so that moving the pipe ends to 3 and 4 cannot clobber one of them
            moved = fcntl.fcntl(fd, fcntl.F_DUPFD, 10)
            os.close(fd)
            return moved

        to_r, self._to_w = os.pipe()  # our writes -> the browser's fd 3
        self._from_r, from_w = os.pipe()  # the browser's fd 4 -> our reads
        to_r, from_w = high(to_r), high(from_w)
        args = [exe, "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-first-run",
                "--no-default-browser-check", "--disable-extensions", "--disable-background-networking",
                f"--user-data-dir={profile}", "--remote-debugging-pipe", "about:blank"]
        # bash (dash takes one-digit fds only) moves the pipe ends to fds 3 and 4 of the browser
        script = f'exec "$@" 3<&{to_r} 4>&{from_w} {to_r}<&- {from_w}>&-'
        self.proc = subprocess.Popen(["bash", "-c", script, "bash", *args], pass_fds=(to_r, from_w),
                                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_r)
        os.close(from_w)
        self._buf = b""
        self._id = 0
        self.events: list[dict] = []

    def close(self):
        try:
            self.send("Browser.close", timeout=10)
        except Exception:  # noqa: BLE001 - it may be gone already
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for fd in (self._to_w, self._from_r):
            try:
                os.close(fd)
            except OSError:
                pass

    def _read_message(self, deadline: float) -> dict:
        import select

        while b"\0" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("no answer from chromium")
            ready, _, _ = select.select([self._from_r], [], [], left)
            if ready:
                chunk = os.read(self._from_r, 1 << 16)
                if not chunk:
                    raise RuntimeError("chromium closed the DevTools pipe")
                self._buf += chunk
        msg, self._buf = self._buf.split(b"\0", 1)
        return json.loads(msg)

    def send(self, method: str, params: dict | None = None, session: str | None = None, timeout: float = 60):
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self._to_w, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            m = self._read_message(deadline)
            if m.get("id") == self._id:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error']}")
                return m.get("result", {})
            self.events.append(m)

    def wait_event(self, method: str, session: str, timeout: float = 60) -> dict:
        deadline = time.monotonic() + timeout
        for i, m in enumerate(self.events):
            if m.get("method") == method and m.get("sessionId") == session:
                return self.events.pop(i)
        while True:
            m = self._read_message(deadline)
            if m.get("method") == method and m.get("sessionId") == session:
                return m
            self.events.append(m)

    def open(self, url: str) -> dict:
        """Load ``url`` in a new tab; return its console errors and images."""
        target = self.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.send(f"{domain}.enable", session=session)
        self.events.clear()
        self.send("Page.navigate", {"url": url}, session=session)
        self.wait_event("Page.loadEventFired", session)
        time.sleep(0.5)  # late console messages
        state = self.send("Runtime.evaluate", {"returnByValue": True, "expression": (
            "JSON.stringify({title: document.title, images: Array.from(document.images).map(i => "
            "({src: i.currentSrc || i.src, complete: i.complete, width: i.naturalWidth}))})")},
            session=session)["result"]["value"]
        errors = []
        for m in self.events:
            if m.get("sessionId") != session:
                continue
            p = m.get("params", {})
            if m["method"] == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
                errors.append("console: " + " ".join(str(a.get("value", a.get("description", ""))) for a in p["args"]))
            elif m["method"] == "Runtime.exceptionThrown":
                errors.append("exception: " + p["exceptionDetails"].get("text", "")
                              + str(p["exceptionDetails"].get("exception", {}).get("description", "")))
            elif m["method"] == "Log.entryAdded" and p["entry"]["level"] == "error":
                errors.append(f"log: {p['entry']['text']} {p['entry'].get('url', '')}")
            elif m["method"] == "Network.loadingFailed" and not p.get("canceled"):
                errors.append(f"network: {p.get('errorText')} {p.get('type')}")
        self.send("Target.closeTarget", {"targetId": target})
        return {"errors": errors, **json.loads(state)}


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    exe = _chromium()
    if exe is None:
        _skip("chromium is not installed (Debian: apt-get install chromium)")
    b = _Browser(exe, tmp_path_factory.mktemp("chromium-profile"))
    try:
        b.send("Browser.getVersion", timeout=60)
        yield b
    finally:
        b.close()


def _gallery_page(html: Path) -> Path:
    return html / "gallery" / "vc" / "extra_phase_functions.html"


@pytest.mark.parametrize("page", ["index.html", "gallery"])
def test_pages_render_in_headless_chromium_without_errors_and_with_images(html, browser, page):
    path = _gallery_page(html) if page == "gallery" else html / page
    if not path.exists():  # the gallery page of a partial local build
        path = next(iter(sorted((html / "gallery").glob("*/*.html"))), path)
    result = browser.open(path.resolve().as_uri())
    assert result["errors"] == [], result["errors"]
    assert result["title"], "the page has a title"
    assert result["images"], "the page shows images"
    bad = [i for i in result["images"] if not (i["complete"] and i["width"] > 0)]
    assert bad == [], f"images that did not load: {bad}"


def test_the_browser_check_sees_a_broken_image(browser, tmp_path):
    """The check itself: a page with a missing image and a console error is caught."""
    page = tmp_path / "broken.html"
    page.write_text('<!doctype html><title>x</title><img src="missing.png"><script>console.error("boom")</script>')
    result = browser.open(page.as_uri())
    assert any("boom" in e for e in result["errors"])
    assert result["images"] and result["images"][0]["width"] == 0
