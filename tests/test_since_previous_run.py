"""``python grade.py`` tells what changed since the student's previous run, read from the
page (or ``--json`` file) that run left, before this one overwrites it."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from autograder.engine.results import CheckResult, ExerciseResult, GradingResult, PASSED, FAILED
from autograder.reports import html
from autograder.student.progress import previous_scores, since
from conftest import ROOT, mutant

MODULE = "lab07_transformations"
WRONG = '''
def translation_matrix(tx, ty):
    return np.array([[1.0, 0.0, -tx], [0.0, 1.0, -ty], [0.0, 0.0, 1.0]])
'''


def result_with(scores: dict[str, float]) -> GradingResult:
    return GradingResult("s", "h", "0", [ExerciseResult(e, e, [], [CheckResult("c", s, 10.0, PASSED if s == 10 else FAILED)])
                                         for e, s in scores.items()])


def test_the_page_keeps_its_scores_for_the_next_run(tmp_path):
    page = tmp_path / "feedback.html"
    html.write(result_with({"lab07.ex1": 4.0, "lab07.ex2": 10.0}), page)
    previous = previous_scores(page)
    assert since(previous, result_with({"lab07.ex1": 10.0, "lab07.ex2": 10.0})) == ["lab07.ex1: 4 -> 10"]
    assert since(previous, result_with({"lab07.ex3": 0.0})) == []            # not graded both times
    assert since(None, result_with({"lab07.ex1": 1.0})) == []                 # a first run


def test_another_submissions_page_in_the_folder_is_not_a_previous_run(tmp_path):
    """An instructor grading student after student in one folder: carla's page is no previous run of alice's
    (audit of 2026-12-07: "since your previous run: lab07.ex1: 0 -> 10")."""
    page = tmp_path / "feedback.html"
    html.write(result_with({"lab07.ex1": 0.0}), page)
    alice = result_with({"lab07.ex1": 10.0})
    assert since(previous_scores(page), alice) == ["lab07.ex1: 0 -> 10"]
    alice.submission = "alice"
    assert since(previous_scores(page), alice) == []


@pytest.mark.parametrize("content", ["", "<html>not ours</html>", '<script type="application/json" '
                                     'id="autograder-scores">{"exercises": "x"}</script>'])
def test_a_page_without_scores_is_a_first_run(tmp_path, content):
    page = tmp_path / "feedback.html"
    page.write_bytes(content.encode("utf-8", errors="surrogateescape") if content else b"\xff" * 10)
    assert previous_scores(page) is None


def test_a_score_cannot_end_the_data_block(tmp_path):
    hostile = GradingResult("s", "h", "0", [ExerciseResult("lab07.ex1</script><b>x<!--", "t", [], [])])
    page = tmp_path / "feedback.html"
    html.write(hostile, page)
    assert "</script><b>x" not in page.read_text() and "x<!--" not in page.read_text().split("autograder-scores")[1]
    assert previous_scores(page) == {"exercises": {"lab07.ex1</script><b>x<!--": [0.0, 0.0]},   # read back whole
                                     "submission": "s"}


@pytest.mark.slow
def test_consecutive_runs_of_grade_py_say_what_moved(tmp_path):
    wrong = mutant(tmp_path / "first", MODULE, WRONG)
    command = [sys.executable, str(ROOT / "grade.py"), "--submission", str(wrong), "lab07.ex1",
               "--html", str(tmp_path / "feedback.html")]
    first = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert "since your previous run" not in first.stdout
    (wrong / f"{MODULE}.py").write_text((ROOT / "reference_solutions" / f"{MODULE}.py").read_text())
    second = subprocess.run(command, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert "since your previous run: lab07.ex1: " in second.stdout, second.stdout
    line = next(l for l in second.stdout.splitlines() if "since your previous run" in l)
    before, after = line.split("lab07.ex1: ")[1].split(" -> ")
    assert float(before) < float(after.split()[0])
    assert 'id="since"' in (tmp_path / "feedback.html").read_text()
