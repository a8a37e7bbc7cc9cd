"""Issue 37, a PDF report in a real browser (headless Chromium): a student hands in code and a
PDF report with their own headings and two pictures; ``autograder batch`` grades them, makes
the figures from their code and reads the PDF in a sandbox worker; the review screen of each
exercise shows that exercise's text from the PDF, and which report figure the code does not
make, in view at 1280x900 beside the figures from the code.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from browser import find_chromium
from test_review_browser import ROOT, Server, Tab, browser  # noqa: F401  (the fixture)

pytest.importorskip("flask")
pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(find_chromium() is None,
                                 reason="Chromium is not installed (apt-get install chromium, or set CHROMIUM)")]


def test_a_pdf_reports_text_and_figure_provenance_on_the_review_screen(browser, tmp_path):  # noqa: F811
    import cv2
    import numpy as np

    from pdf_making import pdf

    student = tmp_path / "class" / "ada"
    student.mkdir(parents=True)
    (student / "lab07_transformations.py").write_bytes((ROOT / "reference_solutions" / "lab07_transformations.py")
                                                       .read_bytes())
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"select": ["lab07.ex1", "lab07.ex2"], "rubric": {
        "lab07.ex1": [{"id": "shift", "text": "explains the shift", "points": 2}],
        "lab07.ex2": [{"id": "centre", "text": "explains the centre", "points": 2}]}}))
    # First the figures the code makes (the batch draws them), then the PDF that embeds one of them.
    results = tmp_path / "results"
    batch = [sys.executable, "-m", "autograder", "batch", str(tmp_path / "class"), "--out", str(results),
             "--course", str(course), "--workers", "1"]
    subprocess.run(batch, cwd=ROOT, check=True, capture_output=True, timeout=600)
    made = cv2.imread(str(results / "ada" / "figures" / "lab07.ex1.png"), cv2.IMREAD_GRAYSCALE)
    half = cv2.resize(made, None, fx=0.5, fy=0.5, interpolation=cv2.INTER_AREA)
    noise = cv2.GaussianBlur(np.random.default_rng(3).random(half.shape).astype(np.float32), (0, 0), 4)
    other = cv2.normalize(noise, None, 0, 255, cv2.NORM_MINMAX).astype(np.uint8)
    (student / "lab07_report.pdf").write_bytes(pdf(
        [["Lab 7 report", "Exercise 1: Translation", "Every pixel moves by (tx, ty)."],
         ["Lab 7 report", "2. Rotation", "It turns about the centre of the image."]], {0: [half], 1: [other]}))
    subprocess.run(batch, cwd=ROOT, check=True, capture_output=True, timeout=600)   # the report is read again

    server = Server(results)
    tab = Tab(browser)
    try:
        browser.send("Emulation.setDeviceMetricsOverride", {"width": 1280, "height": 900, "deviceScaleFactor": 1,
                                                            "mobile": False}, session=tab.session)
        for position, words, finding in (
                (0, "Every pixel moves by (tx, ty).",
                 "report figure 1 (lab07_report.pdf, page 1) matches the figure lab07.ex1 the code makes"),
                (1, "It turns about the centre of the image.",
                 "report figure 2 (lab07_report.pdf, page 2) matches none of the figures your code makes")):
            tab.open(server.url + f"review/{position}")
            tab.wait("[...document.images].every(i => i.complete && i.naturalWidth > 0)")
            explanation = tab.text("#explanation")
            assert words in explanation and f"lab07_report.pdf, page {position + 1}" in explanation
            listed = tab.eval("[...document.querySelectorAll('#figures li')].map(li => [li.className, li.textContent])")
            assert listed == [["bad" if "none" in finding else "muted", finding]]
            # the finding is on the screen once the left pane is scrolled to it, the review still in view
            tab.eval("document.getElementById('provenance').scrollIntoView()")
            top = tab.eval("document.getElementById('provenance').getBoundingClientRect().top")
            assert 0 <= top < 900 and tab.eval("document.getElementById('save').getBoundingClientRect().bottom") <= 900
    finally:
        server.kill()
