"""The report page in a real browser: headless Chromium (Debian's chromium) loads the page that
`vgroove report` writes from disk with JavaScript off, through the DevTools protocol over a pipe
(--remote-debugging-pipe: no port, no websocket). It must load with no console message, no error or
warning in the browser's log (a Content-Security-Policy violation, an image that fails), no request
but the file itself and its data: URIs, every image decoded at its stated size, and a screenshot of
the whole page of the expected size that is not blank. A page broken on purpose (an inline script,
a damaged image) must fail those checks. The page is also parsed and its images decoded
(page_check.py). Skipped, with the reason, when chromium is not installed (scripts/install-deps.sh
installs it); VGROOVE_NO_SKIP=1 (CI) makes that a failure."""

import base64
import io
import json
import os
import select
import shutil
import subprocess
import tempfile
import time

import pytest

from conftest import write_json
from page_check import check_page, html_report

CHROMIUM = shutil.which("chromium")
if CHROMIUM is None:
    if os.environ.get("VGROOVE_NO_SKIP") == "1":
        raise RuntimeError("chromium is not installed, and VGROOVE_NO_SKIP=1 forbids skipping the browser test")
    pytest.skip("chromium is not installed (apt-get install chromium; scripts/install-deps.sh installs it)",
                allow_module_level=True)

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-default-apps", "--disable-extensions", "--mute-audio", "--disable-dev-shm-usage",
         "--remote-debugging-pipe"]
WIDTH, HEIGHT = 1280, 900
TIMEOUT = 60.0


class Browser:
    """Chromium driven over --remote-debugging-pipe: commands are written to its fd 3, replies and
    events read from its fd 4, each a JSON message ended by a NUL byte."""

    def __init__(self) -> None:
        self.profile = tempfile.mkdtemp(prefix="vgroove-chromium-")
        to_browser, self._cmd = os.pipe()
        self._events, from_browser = os.pipe()

        def fds():  # in the child: the pipe ends as fds 3 and 4
            a, b = os.dup(to_browser), os.dup(from_browser)
            os.dup2(a, 3)
            os.dup2(b, 4)

        self.proc = subprocess.Popen([CHROMIUM, *FLAGS, f"--user-data-dir={self.profile}", "about:blank"],
                                     preexec_fn=fds, close_fds=False, stdin=subprocess.DEVNULL,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_browser)
        os.close(from_browser)
        self._buf, self._id, self.events = b"", 0, []

    def _read(self, deadline: float) -> dict:
        while b"\0" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self._events], [], [], left)[0]:
                raise TimeoutError("chromium did not answer in time")
            chunk = os.read(self._events, 1 << 20)
            if not chunk:
                raise EOFError(f"chromium closed the pipe (exit {self.proc.poll()})")
            self._buf += chunk
        msg, self._buf = self._buf.split(b"\0", 1)
        return json.loads(msg)

    def call(self, method: str, params: dict = None, session: str = None) -> dict:
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self._cmd, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + TIMEOUT
        while True:
            m = self._read(deadline)
            if m.get("id") == self._id:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error']}")
                return m.get("result", {})
            self.events.append(m)

    def wait_for(self, method: str) -> None:
        deadline = time.monotonic() + TIMEOUT
        while not any(e.get("method") == method for e in self.events):
            self.events.append(self._read(deadline))

    def close(self) -> None:
        try:
            self.call("Browser.close")
        except (OSError, EOFError, TimeoutError, RuntimeError):
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        os.close(self._cmd)
        os.close(self._events)
        shutil.rmtree(self.profile, ignore_errors=True)


class Load:
    """What the browser did with one page: its messages, requests, images and screenshot."""

    def __init__(self, browser: Browser, path: str, scripts: bool = True) -> None:
        b = browser
        target = b.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        s = b.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            b.call(f"{domain}.enable", session=s)
        b.call("Emulation.setScriptExecutionDisabled", {"value": not scripts}, session=s)
        b.call("Emulation.setDeviceMetricsOverride",
               {"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1, "mobile": False}, session=s)
        b.events.clear()
        self.url = "file://" + os.path.abspath(path)
        b.call("Page.navigate", {"url": self.url}, session=s)
        b.wait_for("Page.loadEventFired")

        def evaluate(expr: str):
            return b.call("Runtime.evaluate", {"expression": expr, "returnByValue": True}, session=s)["result"]["value"]

        # DevTools evaluates even with the page's scripts off (they stay off for the page itself).
        self.images = evaluate("Array.from(document.images).map(i => [i.complete, i.naturalWidth, i.naturalHeight, "
                               "i.width, Number(i.getAttribute('width')), Number(i.getAttribute('height'))])")
        self.scripts = evaluate("document.getElementsByTagName('script').length")
        self.text = evaluate("document.body.innerText")
        self.size = evaluate("[document.documentElement.scrollWidth, document.documentElement.scrollHeight]")
        height = min(self.size[1], 16000)
        shot = b.call("Page.captureScreenshot",
                      {"format": "png", "captureBeyondViewport": True,
                       "clip": {"x": 0, "y": 0, "width": WIDTH, "height": height, "scale": 1}}, session=s)
        self.screenshot = base64.b64decode(shot["data"])
        self.expected_shot = (WIDTH, height)
        self.events = [e for e in b.events if e.get("sessionId") == s]
        b.call("Target.closeTarget", {"targetId": target})

    def console(self):
        """Console calls, exceptions and the browser log's errors and warnings."""
        out = []
        for e in self.events:
            m, p = e.get("method"), e.get("params", {})
            if m == "Runtime.consoleAPICalled":
                out.append(f"console.{p.get('type')}: {[a.get('value') for a in p.get('args', [])]}")
            elif m == "Runtime.exceptionThrown":
                out.append(f"exception: {p.get('exceptionDetails', {}).get('text')}")
            elif m == "Log.entryAdded" and p.get("entry", {}).get("level") in ("error", "warning"):
                out.append(f"log {p['entry']['level']}: {p['entry'].get('text')}")
        return out

    def requests(self):
        return [e["params"]["request"]["url"] for e in self.events if e.get("method") == "Network.requestWillBeSent"]

    def bad_images(self):
        return [i for i in self.images if not (i[0] and i[1] == i[4] and i[2] == i[5] and i[1] > 0)]


def blank_share(png: bytes):
    """The screenshot's size, the share of its pixels that are not the page's white, and its
    number of distinct colours (4097: more than 4096)."""
    import numpy as np
    from PIL import Image
    with Image.open(io.BytesIO(png)) as im:
        rgb = im.convert("RGB")
        ink = float((np.asarray(rgb) != 255).any(axis=2).mean())
        colours = rgb.getcolors(4096)  # None: more than 4096
        return rgb.size, ink, 4097 if colours is None else len(colours)


@pytest.fixture(scope="module")
def browser():
    b = Browser()
    yield b
    b.close()


HOSTILE = "<script>alert('x')</script>\u202e\x1b"


@pytest.fixture(scope="module")
def page(reports, tmp_path_factory):
    """A page of two reports, their plots drawn for the page, hostile names in one."""
    d = tmp_path_factory.mktemp("run")
    shutil.copy(reports["table2"], d / "table2.json")
    with open(reports["table1_set"]) as f:
        r = json.load(f)
    r["suite"], r["git"], r["suites"][1]["suite"] = HOSTILE, HOSTILE, HOSTILE
    write_json(d / "table1_set.json", r)
    out = d / "index.html"
    t0 = time.monotonic()
    info = html_report.write(str(d), str(out))
    print(f"page written in {time.monotonic() - t0:.2f} s ({info['plots']} plots drawn)")
    assert info["plots"] == 2 and info["skipped"] == []
    return out


@pytest.mark.parametrize("scripts", [True, False], ids=["javascript-on", "javascript-off"])
def test_the_page_in_chromium(browser, page, scripts):
    t0 = time.monotonic()
    load = Load(browser, str(page), scripts)
    print(f"loaded and captured in {time.monotonic() - t0:.2f} s")
    assert load.console() == []
    assert load.url in load.requests()
    assert [u for u in load.requests() if u != load.url and not u.startswith("data:image/png;base64,")] == []
    assert load.scripts == 0
    assert len(load.images) == 2 and load.bad_images() == []
    assert "tiny_table2" in load.text and "<script>alert('x')</script>\\u202e\\u001b" in load.text
    assert "The paper's figures beside ours" in load.text
    size, ink, colours = blank_share(load.screenshot)
    assert size == load.expected_shot and load.size[0] <= WIDTH and load.size[1] > 2 * HEIGHT  # no sideways scroll
    assert ink > 0.05 and colours > 200, (ink, colours)
    # The same page parsed: the elements the generator writes, every image decoded.
    assert len(check_page(str(page)).images) == 2


def test_a_broken_page_fails_the_checks(browser, page, tmp_path):
    # The checks above have teeth: an inline script (refused by the page's Content-Security-Policy,
    # and logged), an image whose header is damaged (the browser cannot decode it) and one cut short
    # (the browser draws what it has; PIL refuses it) are all seen.
    html = page.read_text()
    head = 'src="data:image/png;base64,'
    first = html.index(head) + len(head)
    second = html.index(head, first) + len(head)
    end = html.index('"', second)
    broken = (html[:first] + "AAAA" + html[first + 4:second] + html[second:second + 4000] + html[end:]).replace(
        "<body>", "<body><script>document.title = 'ran'</script>", 1)
    bad = tmp_path / "broken.html"
    bad.write_text(broken)
    load = Load(browser, str(bad))
    assert any("Content Security Policy" in c for c in load.console()), load.console()
    assert len(load.bad_images()) == 1
    with pytest.raises(Exception):
        check_page(str(bad))
