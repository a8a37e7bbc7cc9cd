"""Rough edges a new student meets (issue 27, polish): a pipe closed early, a tip about a
function not written yet, a page header for a submission given as "."."""

from __future__ import annotations

import re
import subprocess
import sys

from autograder.reports import html
from autograder.results import ADVICE, NOT_IMPLEMENTED, GradingResult
from autograder.runner import grade
from conftest import ROOT, mutant


def test_a_reader_that_stops_early_is_no_error():
    listing = subprocess.Popen([sys.executable, "-m", "autograder", "list"], cwd=ROOT, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, bufsize=0)
    assert listing.stdout.readline().startswith(b"lab07")
    listing.stdout.close()  # as `| head -1` does
    _, errors = listing.communicate(timeout=120)
    assert listing.returncode == 0 and b"Traceback" not in errors and b"BrokenPipe" not in errors


def test_advice_about_a_function_not_written_yet_is_no_tip(tmp_path):
    stub = "def draw_points(image, pts, radius=3, color=(0, 0, 255)):\n    raise NotImplementedError\n"
    result = grade(mutant(tmp_path, "lab09_camera", stub), ["lab09.ex5"], pictures="none")
    [advice] = [c for e in result.exercises for c in e.checks if c.name == "draw_points skips NaN points"]
    assert advice.status == NOT_IMPLEMENTED and advice.status != ADVICE
    assert advice.message == "draw_points() is not implemented yet" and advice.hint == ""


def test_the_page_header_has_no_stray_separator_and_names_a_dot_by_its_folder(tmp_path):
    for name, shown in (("", "grader 9.9"), ("<b>x</b> & y", "&lt;b&gt;x&lt;/b&gt; &amp; y · grader 9.9")):
        html.write(GradingResult(name, "hash", "9.9"), tmp_path / "page.html")
        [header] = re.findall(r'<div class="muted">(.*?)</div>', (tmp_path / "page.html").read_text())[:1]
        assert header == shown
    folder = mutant(tmp_path / "dot", "lab07_transformations", "")  # .../dot/submission
    completed = subprocess.run([sys.executable, "-m", "autograder", "grade", ".", "lab07.ex1", "--no-html",
                                "--quiet"], cwd=folder, capture_output=True, text=True, timeout=300)
    assert "Grading submission" in completed.stdout, completed.stdout + completed.stderr
