"""``autograder review`` in a real browser (headless Chromium, the project's DevTools harness).

1. A class of 30 reviewed by keyboard only (a digit applies an item, ``s`` saves, ``j``
   moves on), two tabs on one gradebook seeing each other's changes on reload, the
   server killed (SIGKILL) and restarted with nothing lost.
2. The whole path: students hand in code and a report; a batch grades them and makes
   their figures; the review (by keyboard, while a second batch grades the class again)
   applies rubric items; ``autograder report`` puts the points in grades.csv and the
   final grade in the Canvas import.
"""

from __future__ import annotations

import csv
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import pytest

from browser import _DevTools, find_chromium

pytest.importorskip("flask")
pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(find_chromium() is None,
                                 reason="Chromium is not installed (apt-get install chromium, or set CHROMIUM)")]

ROOT = Path(__file__).resolve().parents[1]


class Server:
    """``autograder review RESULTS`` in a process of its own, its address read from what it prints."""

    def __init__(self, results, *options):
        self.process = subprocess.Popen([sys.executable, "-m", "autograder", "review", str(results), "--reviewer",
                                         "ta", *options], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                        cwd=ROOT)
        for line in self.process.stdout:
            if line.strip().startswith("http://127.0.0.1:"):
                self.url = line.strip()
                break
        else:
            raise AssertionError(f"the server printed no address: {self.process.stderr.read()}")

    def kill(self):
        self.process.send_signal(signal.SIGKILL)
        self.process.wait(10)
        self.process.stdout.close()
        self.process.stderr.close()


class Tab:
    """One browser tab driven through the DevTools protocol."""

    def __init__(self, browser: _DevTools):
        self.browser = browser
        self.target = browser.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = browser.send("Target.attachToTarget", {"targetId": self.target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime"):
            browser.send(f"{domain}.enable", session=self.session)

    def eval(self, expression: str):
        reply = self.browser.send("Runtime.evaluate", {"expression": expression, "returnByValue": True},
                                  session=self.session)
        return reply.get("result", {}).get("value")

    def wait(self, expression: str, timeout: float = 20.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                value = self.eval(expression)
            except RuntimeError:   # the page is being replaced
                value = None
            if value:
                return value
            time.sleep(0.02)
        raise AssertionError(f"never true: {expression}; page: {self.eval('document.body && document.body.innerText')!r:.500}")

    def open(self, url: str):
        self.browser.send("Page.navigate", {"url": url}, session=self.session)
        self.wait(f"location.href === {json.dumps(url)} && document.readyState === 'complete'")

    def key(self, key: str):
        for kind in ("keyDown", "keyUp"):
            event = {"type": kind, "key": key}
            if kind == "keyDown" and len(key) == 1:
                event["text"] = key
            self.browser.send("Input.dispatchKeyEvent", event, session=self.session)

    def text(self, selector: str) -> str:
        return self.eval(f"document.querySelector({json.dumps(selector)}).textContent")


@pytest.fixture(scope="module")
def browser():
    with tempfile.TemporaryDirectory(prefix="chromium-profile-") as profile:
        devtools = _DevTools(find_chromium(), profile)
        try:
            yield devtools
        finally:
            devtools.close()


def review_by_keyboard(tab: Tab, url: str, position: int, keys: str):
    """On the review screen at ``position``: press ``keys`` (digits), ``s``, wait until saved."""
    tab.wait(f"location.pathname.endsWith('/review/{position}') && document.readyState === 'complete' "
             "&& !!document.getElementById('status')")
    for key in keys:
        tab.key(key)
    tab.key("s")
    tab.wait("document.getElementById('status').textContent === 'saved' "
             "&& document.getElementById('done').textContent === 'reviewed'")


# ------------------------------------------------------------------ 1. a class of 30
def test_a_class_of_30_by_keyboard_two_tabs_and_a_killed_server(browser, tmp_path):
    from autograder.instructor.batch.gradebook import Gradebook
    from test_review_storage import graded_book

    students = tuple(f"s{i:02d}" for i in range(30))
    graded_book(tmp_path, students, tuple(float(i % 13) for i in range(30))).close()
    server = Server(tmp_path)
    tab = Tab(browser)
    try:
        tab.open(server.url)
        assert "0 of 30 reviewed" in tab.text("h1")
        tab.key("u")   # the first not reviewed
        expected = {}
        for position in range(30):
            keys = "1" if position % 3 == 0 else ("12" if position % 3 == 1 else "3")
            review_by_keyboard(tab, server.url, position, keys)
            expected[students[position]] = {"1": 2.0, "12": 3.0, "3": -1.0}[keys]
            tab.key("j")
        tab.wait(f"location.href === {json.dumps(server.url)}")   # after the last: the queue
        assert "30 of 30 reviewed" in tab.text("h1")

        # Two tabs: a change in one is seen by the other on reload.
        other = Tab(browser)
        other.open(server.url + "review/4")
        tab.open(server.url + "review/4")
        tab.key("2")   # s04 had "12": item 2 taken back
        tab.wait("document.getElementById('status').textContent === 'saved'")
        assert other.text("#points") == "3"
        other.open(server.url + "review/4")
        assert other.text("#points") == "2" and other.eval(
            "[...document.querySelectorAll('#rubric input')].map(b => b.checked).join()") == "true,false,false"
        expected["s04"] = 2.0
        # A comment typed in one tab, saved as it is typed, then the server killed at once.
        other.key("c")
        for letter in "Good":
            other.key(letter)
        other.wait("document.getElementById('status').textContent === 'saved'")
    finally:
        server.kill()

    with Gradebook(tmp_path, readonly=True) as book:
        reviews = book.reviews()
    assert {s: reviews[(s, "lab07.ex1")]["points"] for s in students} == expected
    assert all(reviews[(s, "lab07.ex1")]["done"] and reviews[(s, "lab07.ex1")]["changed_by"] == "ta" for s in students)
    assert reviews[("s04", "lab07.ex1")]["comment"] == "Good"

    server = Server(tmp_path)   # restarted: a new token, the same reviews
    try:
        tab.open(server.url)
        assert "30 of 30 reviewed" in tab.text("h1")
        tab.open(server.url + "review/4")
        assert tab.text("#points") == "2" and tab.eval("document.getElementById('comment').value") == "Good"
    finally:
        server.kill()


# ------------------------------------------------------------------ 2. from the report to Canvas
def test_from_the_report_to_the_final_grade_in_the_canvas_import_while_a_batch_runs(browser, tmp_path):
    from autograder.instructor.batch.run import run_batch
    from autograder.instructor.course import CourseConfig
    from test_batch import MODULE, WRONG_WAY, reference, write

    download = tmp_path / "download"
    report = ("## lab07.ex1: Translation\n\n![lab07.ex1](figures/lab07.ex1.png)\n\n"
              "<!-- explanation lab07.ex1 -->\nThe image moves right by **tx**; the corners it leaves are black:\n\n"
              "![the corners](figures/lab07.ex1.png)\n\n![tracker](https://example.org/t.png)"
              "\n<!-- end explanation -->\n")
    write(download / f"smithjohn_1234_5678_{MODULE}.py", reference())
    write(download / "smithjohn_1234_5678_lab07_report.md", report)
    write(download / f"leeann_3456_7890_{MODULE}.py", reference() + WRONG_WAY)
    course = CourseConfig(select=["lab07.ex1"], assignment="Lab 7", canvas_assignment_id="4242",
                          rubric={"lab07.ex1": [{"id": "corners", "text": "explains the black corners", "points": 3},
                                                {"id": "none", "text": "no explanation", "points": -1}]})
    out = tmp_path / "out"
    run_batch(download, out, course=course, workers=2)
    assert (out / "smithjohn-1234" / "figures" / "lab07.ex1.png").read_bytes().startswith(b"\x89PNG")

    server = Server(out)
    tab = Tab(browser)
    summaries = []
    regrading = threading.Thread(target=lambda: summaries.append(
        run_batch(download, out, course=course, workers=1, regrade=True)))
    try:
        tab.open(server.url + "review/0")
        assert tab.text("#student").strip() == "leeann"
        assert "No explanation written" in tab.text("#explanation")
        regrading.start()   # a batch grades the class again meanwhile
        review_by_keyboard(tab, server.url, 0, "2")
        tab.key("j")
        review_by_keyboard(tab, server.url, 1, "1")
        assert "black" in tab.text("#explanation") and tab.eval(
            "document.querySelector('#explanation strong').textContent") == "tx"
        tab.wait("[...document.images].filter(i => i.complete && i.naturalWidth > 0).length === 2")   # in the
        # explanation (its ![...](figures/lab07.ex1.png)) and beside it: the figure the batch made
        regrading.join(120)
        assert not regrading.is_alive() and summaries and summaries[0].graded == 2, "the batch finished its work"
    finally:
        server.kill()

    from autograder.cli import main

    assert main(["report", str(out)]) == 0
    grades = {r["Student ID"]: r for r in csv.DictReader((out / "grades.csv").open())}
    assert grades["smithjohn-1234"]["lab07.ex1 report"] == "3" and grades["leeann-3456"]["lab07.ex1 report"] == "-1"
    checks = {s: float(grades[s]["lab07.ex1"]) for s in grades}
    canvas = {row["ID"]: row for row in csv.DictReader((out / "canvas_import.csv").open())}
    assert float(canvas["1234"]["Lab 7 (4242)"]) == checks["smithjohn-1234"] + 3
    assert float(canvas["3456"]["Lab 7 (4242)"]) == max(0.0, checks["leeann-3456"] - 1)
    page = (out / "smithjohn-1234" / "feedback.html").read_text()
    assert "explains the black corners <b>+3</b>" in page


# ------------------------------------------------------------------ 3. the screen at 1280x900
def test_the_review_screen_at_1280x900_keeps_the_review_in_view(browser, tmp_path):
    """A long explanation and a 1500-pixel-wide figure: the rubric, the comment box, the saved
    comments and the save button stay above the fold, the figure keeps its own width (scrolled
    inside its pane), and a saved comment is inserted by keyboard (v, 1) and saved."""
    import numpy as np
    import cv2
    from autograder.instructor.batch.gradebook import Gradebook
    from test_review_storage import graded_book

    with graded_book(tmp_path, ("ada", "bo"), (3.0, 6.0)) as book:
        book.db.execute("INSERT INTO explanations VALUES ('ada', 'lab07.ex1', ?, 'lab07_report.md', 0)",
                        ("The corners are black. " * 300,))
        book.set_bank_comment("lab07.ex1", "corners", "Why are the corners black?", "ta")
    (tmp_path / "ada" / "figures").mkdir(parents=True)
    cv2.imwrite(str(tmp_path / "ada" / "figures" / "lab07.ex1.png"), np.full((400, 1500, 3), 200, np.uint8))
    server = Server(tmp_path)
    tab = Tab(browser)
    try:
        browser.send("Emulation.setDeviceMetricsOverride", {"width": 1280, "height": 900, "deviceScaleFactor": 1,
                                                            "mobile": False}, session=tab.session)
        tab.open(server.url + "review/0")
        tab.wait("[...document.images].every(i => i.complete && i.naturalWidth > 0)")
        bottoms = tab.eval("Object.fromEntries(['rubric', 'comment', 'bank', 'save', 'head'].map("
                           "id => [id, document.getElementById(id).getBoundingClientRect().bottom]))")
        assert all(0 < bottom <= 900 for bottom in bottoms.values()), bottoms
        assert tab.eval("document.documentElement.scrollHeight") <= 900, "the page itself does not scroll"
        assert tab.eval("document.getElementById('work').scrollHeight > document.getElementById('work').clientHeight")
        assert tab.eval("document.querySelector('#figures img').width") == 1500, "the figure at its own width"
        tab.key("z")
        assert tab.eval("document.querySelector('#figures img').width") < 900, "z fits it to the pane"
        tab.key("v")
        tab.key("1")
        tab.wait("document.getElementById('status').textContent === 'saved'")
    finally:
        server.kill()
    with Gradebook(tmp_path, readonly=True) as book:
        assert book.reviews()[("ada", "lab07.ex1")]["comment"] == "Why are the corners black?"
