"""Labs graded side by side in lanes, a worker each (runner.grade(lanes=...)): the same results as
one lane, in the same order, and the submission's time budget counted over every lane."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from autograder.cli import lanes_for
from autograder.engine.registry import select
from autograder.engine.results import without_timings
from autograder.engine.runner import grade
from autograder.sandbox.supervisor import Limits

ROOT = Path(__file__).resolve().parents[1]
SELECT = ["lab07", "lab09.ex1", "lab10.ex1"]


# What names a failed check's mistake runs under a time budget (the error model, the repairs, the
# recordings): on a loaded machine another lane may end it elsewhere. Everything before it is the verdict.
NAMING_LEADS = ("Trying small changes", "On this input,", "it looks like")


def _graded(submission, lanes, **options):
    result = grade(submission, SELECT, pictures="none", lanes=lanes, **options)
    data = without_timings(result.to_dict())
    for exercise in data["exercises"]:
        for check in exercise["checks"]:
            for lead in NAMING_LEADS:
                check["message"] = check["message"].split(lead, 1)[0]
            check.pop("mistake", None)
            check.pop("hint", None)
    return result, data


def test_lanes_give_the_results_of_one_lane_in_the_same_order(tmp_path):
    submission = tmp_path / "submission"
    shutil.copytree(ROOT / "reference_solutions", submission)
    with open(submission / "lab09_camera.py", "a") as module:  # one exercise wrong, with a message
        module.write("\ndef pinhole_project(points, f):\n    return points[:, :2] * f\n")
    one, one_data = _graded(submission, lanes=1)
    three, three_data = _graded(submission, lanes=3)
    assert three_data == one_data
    assert [e.id for e in three.exercises] == [e.id for e in one.exercises] == \
        [e.id for e in select(SELECT)]
    [wrong] = [e for e in three.exercises if e.id == "lab09.ex1"]
    assert wrong.score < wrong.max_score
    assert three.student_seconds > 0


def test_the_submission_budget_counts_every_lane(tmp_path):
    submission = tmp_path / "slow"
    shutil.copytree(ROOT / "reference_solutions", submission)
    for module in ("lab07_transformations.py", "lab09_camera.py", "lab10_camera2.py"):
        with open(submission / module, "a") as source:
            source.write("\nimport time as _time\nimport functools as _functools\n"
                         "for _name, _f in list(globals().items()):\n"
                         "    if callable(_f) and not _name.startswith('_') and getattr(_f, '__module__', '') "
                         "== __name__:\n"
                         "        globals()[_name] = (lambda f: _functools.wraps(f)(lambda *a, **k: "
                         "(_time.sleep(0.4), f(*a, **k))[1]))(_f)\n")
    limits = Limits(call_timeout=2.0, exercise_budget=30.0, submission_budget=3.0)
    result, _ = _graded(submission, lanes=3, limits=limits)
    messages = [c.message for e in result.exercises for c in e.checks]
    assert sum("time budget exhausted" in m for m in messages) > 10
    assert result.student_seconds < limits.submission_budget + 3 * limits.call_timeout


def test_grade_py_grades_with_a_lane_per_core_and_selected_lab(monkeypatch):
    monkeypatch.setattr("autograder.cli.usable_cores", lambda: 2)
    assert (lanes_for([]), lanes_for(["lab07"]), lanes_for(["lab07.ex1", "lab07.ex2"]),
            lanes_for(["lab07", "lab08.ex1", "lab11"])) == (2, 1, 1, 2)
    monkeypatch.setattr("autograder.cli.usable_cores", lambda: 16)
    assert (lanes_for([]), lanes_for(["lab07", "lab08.ex1", "lab11"])) == (4, 3)
    monkeypatch.setattr("autograder.cli.usable_cores", lambda: 1)
    assert lanes_for([]) == 1


def test_a_lane_that_fails_stops_the_others_at_once(tmp_path, monkeypatch):
    import time

    from autograder.engine import runner

    submission = tmp_path / "slow"
    shutil.copytree(ROOT / "reference_solutions", submission)
    with open(submission / "lab09_camera.py", "a") as source:  # every call of lab 9 takes a second
        source.write("\nimport time as _time\n_project = pinhole_project\n"
                     "def pinhole_project(points, f):\n    _time.sleep(1.0)\n    return _project(points, f)\n")
    grade_exercise = runner._grade_exercise

    def broken_for_lab07(sandbox, exercise, *args, **kwargs):
        if exercise.lab.key == "lab07":
            time.sleep(0.5)  # lab 9's lane is well into its slow calls by now
            raise RuntimeError("a bug in the grader")
        return grade_exercise(sandbox, exercise, *args, **kwargs)

    monkeypatch.setattr(runner, "_grade_exercise", broken_for_lab07)
    started = time.perf_counter()
    with pytest.raises(RuntimeError, match="a bug in the grader"):
        grade(submission, ["lab07.ex1", "lab09.ex1"], pictures="none", lanes=2)
    assert time.perf_counter() - started < 6  # lab 9's checks alone would take well over 10 s


def test_the_lanes_workers_share_the_submissions_memory_and_the_cores(tmp_path, monkeypatch):
    from autograder.engine import runner

    made = []

    class Recorded(runner.Sandbox):
        def __init__(self, submission_dir, limits=None, **options):
            made.append(limits)
            super().__init__(submission_dir, limits, **options)

    monkeypatch.setattr(runner, "Sandbox", Recorded)
    grade(ROOT / "reference_solutions", SELECT, pictures="none", lanes=3)
    # three lanes for the public checks, and a fresh worker per lab of hidden checks (run apart)
    hidden_labs = {exercise.lab.key for exercise in select(SELECT) if any(c.hidden for c in exercise.checks)}
    assert hidden_labs and len(made) == 3 + min(3, len(hidden_labs))
    assert {limits.memory for limits in made} == {Limits().memory // 3}
    # what the grader holds of the lanes' replies at once is what it would hold of one
    assert {limits.max_result_bytes for limits in made} == {Limits().max_result_bytes // 3}
    assert Limits().shared_by(1) == Limits()
    monkeypatch.setattr("autograder.sandbox.supervisor.usable_cores", lambda: 4)
    assert (Limits().shared_by(2).threads, Limits().shared_by(3).threads, Limits().shared_by(8).threads) == (2, 1, 1)
