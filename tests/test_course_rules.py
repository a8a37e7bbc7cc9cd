"""An instructor's extra rules (course configuration ``forbid``): validated, off by
default, enforced in the worker and shown to students in every report."""

import json

import numpy as np
import pytest

from autograder.instructor import gradescope
from autograder.instructor.course import CourseConfig, CourseConfigError
from autograder.engine.registry import REGISTRY, Lab
from autograder.reports import html
from autograder.engine.runner import grade
from conftest import submission_from_source

SOLVER = """
import numpy as np

def solve(A, b):
    return np.linalg.solve(A, b)
"""


@pytest.fixture
def solver_lab():
    lab = Lab("lab96", module="toy_solver", title="Toy")
    ex1 = lab.exercise("ex1", "Solving", functions=["solve(A, b)"])

    @ex1.check("solve a 2x2 system", points=1)
    def solves(t):
        got = t.call("solve", np.eye(2) * 2, np.ones(2))
        if not np.allclose(got, 0.5):
            t.fail(f"solve returned {got}")

    yield lab
    REGISTRY.pop("lab96")


def test_no_rules_by_default(solver_lab, tmp_path):
    assert CourseConfig().forbid == {}
    result = grade(submission_from_source(tmp_path, "toy_solver", SOLVER), ["lab96"])
    assert result.total == 1 and result.exercises[0].rules == []


def test_a_rule_is_enforced_and_shown(solver_lab, tmp_path):
    config = CourseConfig(forbid={"lab96.solve": ["numpy.linalg.solve"]})
    result = grade(submission_from_source(tmp_path, "toy_solver", SOLVER), ["lab96"], forbid=config.forbid)
    [exercise] = result.exercises
    assert exercise.score == 0
    assert "solve() called numpy.linalg.solve" in exercise.checks[0].message
    assert exercise.rules == ["solve() may not call numpy.linalg.solve (your instructor's rule for this course)"]
    assert "Rule: solve() may not call numpy.linalg.solve" in html.render(result)
    assert "Rule for lab96.ex1: solve() may not call numpy.linalg.solve" in \
        gradescope.results_json(result, config)["output"]
    assert json.loads(json.dumps(result.to_dict()))["exercises"][0]["rules"] == exercise.rules


@pytest.mark.parametrize("forbid, fragment", [
    ({"homography_ransac": ["cv2.findHomography"]}, "not a student function"),
    ({"lab08.homography_ransac": "cv2.findHomography"}, "non-empty list"),
    ({"lab08.homography_ransac": ["findHomography"]}, "library functions"),
    (["lab08.homography_ransac"], "must be an object"),
])
def test_rules_are_validated(forbid, fragment):
    with pytest.raises(CourseConfigError, match=fragment):
        CourseConfig(forbid=forbid)


def test_a_rule_for_a_function_no_exercise_grades_fails_the_build(tmp_path):
    with pytest.raises(CourseConfigError, match="lab08.homography_ransack"):
        gradescope.build(tmp_path / "autograder.zip",
                         CourseConfig(forbid={"lab08.homography_ransack": ["cv2.findHomography"]}))


@pytest.mark.parametrize("forbid, said", [
    ({"lab08.homography_ransac2": ["cv2.findHomography"]}, "lab08.homography_ransac2 is not a function any exercise "
                                                           "grades (did you mean lab08.homography_ransac?)"),
    ({"lab08.homography_ransac": ["cv2.findHomographyy"]}, "cv2.findHomographyy is not a function of the cv2 "
                                                           "installed (did you mean cv2.findHomography?)"),
    ({"lab08.homography_ransac": ["np.linalg.svdd"]}, "np.linalg.svdd is not a function of the np installed"),
])
def test_a_forbid_naming_nothing_is_refused_by_every_command(tmp_path, forbid, said):
    """A misspelt student or library function would forbid nothing, silently: the course file is refused where it
    is read, by grade, batch and Gradescope alike (audit of 2026-12-07: only Gradescope's build checked, with a
    traceback)."""
    from autograder.instructor.course import CourseConfig, CourseConfigError

    path = tmp_path / "course.json"
    path.write_text(json.dumps({"forbid": forbid}))
    with pytest.raises(CourseConfigError) as refused:
        CourseConfig.load(path)
    assert said in str(refused.value)
    path.write_text(json.dumps({"forbid": {"lab08.homography_ransac": ["cv2.findHomography", "np.linalg.svd"]}}))
    assert CourseConfig.load(path).forbid


@pytest.mark.parametrize("course, said", [
    ({"select": ["lab77"]}, "select: nothing to grade matches 'lab77'"),
    ({"select": ["lab07", "lab07.ex9"]}, "select: nothing to grade matches 'lab07.ex9'"),
    ({"points": {"lab07": -5}}, "points must be a number, 0 or more: 'lab07' is given -5"),
    ({"points": {"lab07": float("nan")}}, "points must be a number, 0 or more: 'lab07' is given nan"),
    ({"points": {"lab07.ex2": float("inf")}}, "points must be a number, 0 or more: 'lab07.ex2' is given inf"),
    ({"points": {"lab07": True}}, "points must map"),
    ({"call_timeout": 0}, "call_timeout must be a positive number of seconds"),
])
def test_a_course_file_is_refused_with_its_name_and_what_is_wrong(tmp_path, course, said):
    """Audit of 2026-12-07: a misspelt ``select`` went unnoticed by a grading that selects on the command line
    (graded, exit 0), a negative point value was told "must map ... to a number of points", and some keys'
    messages did not name the file. The file is read the same way by every command: each refusal names it."""
    path = tmp_path / "course_lab7.json"
    path.write_text(json.dumps(course))
    with pytest.raises(CourseConfigError) as refused:
        CourseConfig.load(path)
    assert str(refused.value).startswith(f"{path}: ") and said in str(refused.value), str(refused.value)
    assert not str(refused.value).startswith(f"{path}: {path}")


def test_a_bad_selection_in_the_course_stops_a_grading_that_selects_itself(tmp_path, capsys):
    from autograder.cli import main

    path = tmp_path / "course.json"
    path.write_text(json.dumps({"select": ["lab77"]}))
    code = main(["grade", str(tmp_path / "nothing_here"), "lab07.ex1", "--config", str(path)])
    assert code == 2
    assert "nothing to grade matches 'lab77'" in capsys.readouterr().err
