"""Rough edges a new student meets (issue 27, polish): a pipe closed early, a tip about a
function not written yet, a page header for a submission given as ".", and the command a
failing property names to meet its input again."""

from __future__ import annotations

import json
import re
import subprocess
import sys

from autograder.student import selfcheck
from autograder.reports import html
from autograder.engine.results import ADVICE, NOT_IMPLEMENTED, GradingResult
from autograder.engine.runner import grade
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


WRONG_FOR_LARGE_SHIFTS = '''
def translation_matrix(tx, ty):
    return np.array([[1.0, 0.0, tx], [0.0, 1.0, ty if abs(ty) < 500 else 0.0], [0.0, 0.0, 1.0]])
'''


def _rerun_hint(messages) -> str:
    [hint] = {m.rsplit("re-run with ", 1)[1] for m in messages if "re-run with " in m}
    return hint


def test_a_failing_property_says_how_to_grade_the_same_files_again(tmp_path):
    folder = mutant(tmp_path, "lab07_transformations", WRONG_FOR_LARGE_SHIFTS)
    lone = folder / "lab07_transformations.py"
    run = subprocess.run([sys.executable, str(ROOT / "grade.py"), "--submission", str(lone), "lab07.ex1",
                          "--no-html", "--json", str(tmp_path / "r.json")], capture_output=True, text=True,
                         timeout=300, cwd=tmp_path)
    data = json.loads((tmp_path / "r.json").read_text())
    messages = [c["message"] for e in data["exercises"] for c in e["checks"]]
    assert _rerun_hint(messages) == f"python grade.py --submission {lone} lab07.ex1)", run.stderr
    report = selfcheck.check("lab07.ex1", submission=folder)
    messages = [c.message for e in report.result.exercises for c in e.checks]
    assert _rerun_hint(messages) == f"check(\"lab07.ex1\", submission='{folder}'))"
    result = grade(folder, ["lab07.ex1"], pictures="none")  # called as a library: grade.py's words
    assert _rerun_hint([c.message for e in result.exercises for c in e.checks]) == "python grade.py lab07.ex1)"
