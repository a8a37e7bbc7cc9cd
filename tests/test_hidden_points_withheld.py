"""Nothing derived from hidden points reaches a student before release.

While the course withholds hidden checks' points (``hidden_points_visible`` false), a
student's page shows each hidden check's verdict only. Everything else on it must then
be computed on what the student may see, or withheld: a late penalty of "10% of the
points earned" printed as "-7.1" beside 60/60 tells that 11 hidden points were earned.

The property: two gradings that differ only in what the hidden checks are worth and
earned (the same verdicts) give the student the same page and the same results.json,
whatever the late rule, the days late and the instructor's overrides.
"""

from __future__ import annotations

import json

from hypothesis import given, strategies as st

from autograder.engine.results import FAILED, PASSED, CheckResult, ExerciseResult, GradingResult
from autograder.instructor.batch.exports import Override, compute_grades, max_total, student_page
from autograder.instructor.course import CourseConfig
from autograder.reports import html

EXERCISE = "lab07.ex1"


def grading(public: list[tuple[float, float]], hidden: list[tuple[bool, float, float]]) -> GradingResult:
    """A grading of one exercise: public checks (score, max) and hidden ones (passed, max, partial share)."""
    checks = [CheckResult(f"public {i}", score, maximum, PASSED if score == maximum else FAILED,
                          "" if score == maximum else "wrong")
              for i, (score, maximum) in enumerate(public)]
    checks += [CheckResult(f"hidden {i}", maximum if passed else round(share * maximum, 4), maximum,
                           PASSED if passed else FAILED, "hidden message", hidden=True)
               for i, (passed, maximum, share) in enumerate(hidden)]
    return GradingResult("s1", "hash", "0", [ExerciseResult(EXERCISE, "Translation", ["translate"], checks)],
                         graded_at="2026-11-28T00:00:00+00:00")


def student_outputs(result: GradingResult, course: CourseConfig, late: bool, overrides) -> tuple[str, str]:
    """The student's page and results.json, as the batch writes them."""
    student = {"student_id": "s1", "display_name": "Student One", "lms": {}, "members": [],
               "status": "graded", "reason": "", "result": result.to_dict(), "feedback": None, "late": late}
    exercises = [(EXERCISE, result.max_total)]
    [grade], _ = compute_grades([student], exercises, course, overrides)
    view = result.for_students(course.hidden_points_visible)
    page = student_page(html.render(view), grade, max_total(exercises, course), course)
    return page, json.dumps(view.to_dict(), sort_keys=True)


points = st.sampled_from([1.0, 2.0, 3.0, 5.0, 11.0])
public_checks = st.lists(st.tuples(st.sampled_from([0.0, 0.5, 1.0]), points).map(
    lambda c: (round(c[0] * c[1], 4), c[1])), min_size=1, max_size=3)
verdicts = st.lists(st.booleans(), min_size=1, max_size=3)
hidden_worth = st.lists(st.tuples(points, st.sampled_from([0.0, 0.25, 0.5, 0.9])), min_size=3, max_size=3)
overrides = st.lists(st.sampled_from([
    Override("s1", "late", None, 1.0, "one more day"),
    Override("s1", "late", 0.0, None, "waived"),
    Override("s1", "total", 2.0, None, "bonus"),
    Override("s1", EXERCISE, None, 1.0, "copied a line"),
]), max_size=2)


@given(public=public_checks, passed=verdicts, worth_a=hidden_worth, worth_b=hidden_worth,
       per_day=st.sampled_from([5, 10, 25]), late=st.booleans(), overrides=overrides)
def test_the_student_sees_nothing_computed_from_withheld_hidden_points(public, passed, worth_a, worth_b,
                                                                       per_day, late, overrides):
    course = CourseConfig(points={"lab07": 40}, late_penalty={"per_day": per_day}, hidden_points_visible=False)
    first = grading(public, [(p, m, s) for p, (m, s) in zip(passed, worth_a)])
    second = grading(public, [(p, m, s) for p, (m, s) in zip(passed, worth_b)])
    assert student_outputs(first, course, late, overrides) == student_outputs(second, course, late, overrides)


def test_a_late_penalty_is_told_once_the_hidden_points_are_shown():
    """The counterpart: where hidden points are visible, the late penalty's points are shown
    (so the property above is not met by showing nothing)."""
    result = grading([(6.0, 6.0)], [(True, 4.0, 0.0)])
    withheld, _ = student_outputs(result, CourseConfig(late_penalty={"per_day": 10}), True, [])
    shown, _ = student_outputs(result, CourseConfig(late_penalty={"per_day": 10}, hidden_points_visible=True),
                               True, [])
    assert "-1" in shown and "10% of the points earned" in shown
    assert "shown when the hidden checks are released" in withheld and "<td>-1</td>" not in withheld


def test_the_checks_passed_count_leaves_the_hidden_checks_apart_where_the_score_does():
    """The student's table: a score without the hidden points beside "checks passed" counting the hidden checks
    (`4 / 11 | 1 / 6` for 5 public checks and 1 hidden: first-time user's audit of 2026-12-07)."""
    from rich.console import Console

    from autograder.reports.terminal import render

    result = grading([(0.0, 2.0), (1.0, 1.0)], [(True, 3.0, 0.0)])
    view = result.for_students(False)
    console = Console(width=200, record=True)
    render(view, console, details=False)
    assert "1 / 2 (hidden: 1 / 1)" in console.export_text()
    console = Console(width=200, record=True)
    render(result, console, details=False)   # (the instructor's view: the hidden points are in the score)
    assert "2 / 3" in console.export_text()


def test_a_late_students_page_with_no_public_point_tells_nothing_of_the_hidden_ones():
    """The property's corner: no public point earned, the hidden checks failed with partial credit or without. A
    late row (and the headline's note beside it) shown only where the penalty, a share of all points earned, is not
    0 told that some hidden point was earned. The late rule is told wherever days are late, whatever its points."""
    course = CourseConfig(late_penalty={"per_day": 10}, hidden_points_visible=False)
    nothing = grading([(0.0, 2.0)], [(False, 4.0, 0.0)])
    partial = grading([(0.0, 2.0)], [(False, 4.0, 0.5)])
    assert student_outputs(nothing, course, True, []) == student_outputs(partial, course, True, [])
