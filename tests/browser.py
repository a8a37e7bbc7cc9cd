"""Render a page in headless Chromium and report what a reader would stumble on.

Drives Chromium through the DevTools protocol over ``--remote-debugging-pipe``
(file descriptors 3 and 4, NUL-terminated JSON), with the standard library
only. :func:`inspect_page` loads a local HTML file at a given viewport width
and returns console errors, broken images, horizontal overflow and a
screenshot. Tests skip with a reason where Chromium is not installed.
"""

from __future__ import annotations

import base64
import fcntl
import json
import os
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")


def find_chromium() -> str | None:
    explicit = os.environ.get("CHROMIUM")
    if explicit:
        return explicit if Path(explicit).exists() else None
    for name in CANDIDATES:
        found = shutil.which(name)
        if found:
            return found
    return None


@dataclass
class PageReport:
    width: int
    errors: list[str] = field(default_factory=list)          # console errors, exceptions, failed loads
    broken_images: list[str] = field(default_factory=list)
    scroll_width: int = 0                                      # document width; > width means sideways scrolling
    overflowing: list[str] = field(default_factory=list)      # elements sticking out on the right
    has_viewport_meta: bool = False
    empty_svgs: int = 0
    screenshot: bytes = b""

    def problems(self) -> list[str]:
        found = [f"console: {e}" for e in self.errors]
        found += [f"broken image: {src}" for src in self.broken_images]
        if self.scroll_width > self.width:
            found.append(f"page is {self.scroll_width} px wide at a {self.width} px viewport "
                         f"(sideways scrolling); sticking out: {self.overflowing[:5]}")
        if not self.has_viewport_meta:
            found.append("no <meta name=viewport>: phones would show a shrunken desktop page")
        if self.empty_svgs:
            found.append(f"{self.empty_svgs} inline SVG pictures render with no size")
        return found


_PROBE = r"""
(() => {
  const width = document.documentElement.clientWidth;
  const images = [...document.images].filter(i => !i.complete || i.naturalWidth === 0)
                                     .map(i => (i.currentSrc || i.src).slice(0, 80));
  const sticking = [];
  for (const el of document.body.querySelectorAll('*')) {
    const r = el.getBoundingClientRect();
    if (r.width > 0 && r.right > width + 1) {
      sticking.push(el.tagName.toLowerCase() + (el.className && typeof el.className === 'string' ? '.' + el.className : '')
                    + ' right=' + Math.round(r.right));
      if (sticking.length > 20) break;
    }
  }
  const svgs = [...document.querySelectorAll('svg')].filter(s => {
    const r = s.getBoundingClientRect(); return !(r.width > 0 && r.height > 0) && s.closest('details:not([open])') === null;
  }).length;
  return JSON.stringify({scrollWidth: document.documentElement.scrollWidth, images, sticking, svgs,
                         viewportMeta: !!document.querySelector('meta[name=viewport]')});
})()
"""


class _DevTools:
    """A minimal DevTools-protocol client over Chromium's debugging pipe."""

    def __init__(self, chromium: str, profile: str):
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()

        def wire_fds():  # the browser reads commands on fd 3 and writes replies on fd 4
            high = [fcntl.fcntl(fd, fcntl.F_DUPFD, 10) for fd in (to_browser_r, from_browser_w)]
            for target, fd in zip((3, 4), high):
                os.dup2(fd, target)
                os.set_inheritable(target, True)

        self.proc = subprocess.Popen(
            [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
             "--disable-component-update", "--disable-sync", "--no-first-run", "--no-default-browser-check",
             "--disable-extensions", "--mute-audio", f"--user-data-dir={profile}",
             "--remote-debugging-pipe", "about:blank"],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            preexec_fn=wire_fds, close_fds=False)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._buffer = b""
        self._next_id = 0
        self.events: list[dict] = []

    def send(self, method: str, params: dict | None = None, session: str | None = None,
             timeout: float = 30.0) -> dict:
        self._next_id += 1
        message = {"id": self._next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self._to_browser, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            reply = self._receive(deadline)
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self.events.append(reply)

    def wait_for(self, method: str, timeout: float = 30.0) -> dict:
        deadline = time.monotonic() + timeout
        for event in self.events:
            if event.get("method") == method:
                return event
        while True:
            event = self._receive(deadline)
            self.events.append(event)
            if event.get("method") == method:
                return event

    def _receive(self, deadline: float) -> dict:
        import select

        while b"\0" not in self._buffer:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError("Chromium did not answer in time")
            ready, _, _ = select.select([self._from_browser], [], [], remaining)
            if ready:
                chunk = os.read(self._from_browser, 1 << 20)
                if not chunk:
                    raise EOFError("Chromium closed the debugging pipe")
                self._buffer += chunk
        message, _, self._buffer = self._buffer.partition(b"\0")
        return json.loads(message)

    def close(self):
        try:
            self.send("Browser.close", timeout=5)
        except (OSError, RuntimeError, TimeoutError, EOFError):
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        os.close(self._to_browser)
        os.close(self._from_browser)


def inspect_page(path, widths=(390, 1280), height: int = 900, chromium: str | None = None) -> list[PageReport]:
    """Load the HTML file at ``path`` at each viewport width; one :class:`PageReport` per width."""
    chromium = chromium or find_chromium()
    if chromium is None:
        raise FileNotFoundError("Chromium is not installed")
    url = Path(path).resolve().as_uri()
    reports = []
    with tempfile.TemporaryDirectory(prefix="chromium-profile-") as profile:
        browser = _DevTools(chromium, profile)
        try:
            for width in widths:
                target = browser.send("Target.createTarget", {"url": "about:blank"})["targetId"]
                session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
                for domain in ("Page", "Runtime", "Log"):
                    browser.send(f"{domain}.enable", session=session)
                browser.send("Emulation.setDeviceMetricsOverride", {
                    "width": width, "height": height, "deviceScaleFactor": 1, "mobile": width < 600},
                    session=session)
                browser.events.clear()
                browser.send("Page.navigate", {"url": url}, session=session)
                browser.wait_for("Page.loadEventFired")
                probe = json.loads(browser.send("Runtime.evaluate", {
                    "expression": _PROBE, "returnByValue": True}, session=session)["result"]["value"])
                metrics = browser.send("Page.getLayoutMetrics", session=session)["cssContentSize"]
                shot = browser.send("Page.captureScreenshot", {   # the whole page, for a person to look at
                    "format": "png", "captureBeyondViewport": True,
                    "clip": {"x": 0, "y": 0, "width": width, "height": min(metrics["height"], 6000), "scale": 1}},
                    session=session)
                report = PageReport(width, scroll_width=probe["scrollWidth"], broken_images=probe["images"],
                                    overflowing=probe["sticking"], has_viewport_meta=probe["viewportMeta"],
                                    empty_svgs=probe["svgs"], screenshot=base64.b64decode(shot["data"]))
                report.errors = _errors(browser.events, session)
                reports.append(report)
                browser.send("Target.closeTarget", {"targetId": target})
        finally:
            browser.close()
    return reports


def _errors(events: list[dict], session: str) -> list[str]:
    errors = []
    for event in events:
        if event.get("sessionId") != session:
            continue
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.exceptionThrown":
            details = params.get("exceptionDetails", {})
            errors.append(details.get("exception", {}).get("description") or details.get("text", "exception"))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            errors.append(" ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", [])))
        elif method == "Log.entryAdded" and params.get("entry", {}).get("level") == "error":
            entry = params["entry"]
            errors.append(f"{entry.get('text', '')} {entry.get('url', '')}".strip())
    return errors
