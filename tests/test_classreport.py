"""The class overview: a generated class with planted mistakes shows exactly those counts."""

from __future__ import annotations

import re
import textwrap
from html import unescape

import pytest

from autograder.instructor.classreport.analysis import StudentRecord, first_sentence, mistake_of, summarise
from autograder.instructor.classreport.overview import overview_html, render_overview, safe_href
from autograder.instructor.classreport.pages import records_from_class_results
from autograder.engine.results import (FAILED, NOT_IMPLEMENTED, PASSED, CheckResult, ExerciseResult,
                                GradingResult)

ROTATION_WRONG_WAY = ("the rotation goes the opposite way: with y pointing down, counter-clockwise "
                      "on screen is the lecture's R(-theta)")
TX_TY_SWAPPED = "tx and ty are swapped (x is the column, y the row)"


def passed(name, points=2.0):
    return CheckResult(name, points, points, PASSED)


def failed(name, message, points=2.0, **fields):
    return CheckResult(name, 0.0, points, FAILED, message, **fields)


def lab07(student: int, planted: dict) -> list[ExerciseResult]:
    """lab07.ex1 and ex2 for one student, with the mistakes ``planted`` for them."""
    ex1 = [passed("translation_matrix(100, 50)"), passed("translate(image)", 4.0)]
    if student in planted["swapped"]:
        # Named only in the message (results written before the mistake field existed).
        ex1[0] = failed("translation_matrix(100, 50)", f"translation_matrix(100, 50) is wrong: it looks like {TX_TY_SWAPPED}.")
    if student in planted["timeout"]:
        ex1[1] = failed("translate(image)", "translate() did not finish within 10 s (an infinite loop, or far too slow?)",
                        4.0, failure="timeout")
        ex1.append(failed("translate(grey image)", "translate() timed out 2 times already; not called again",
                          failure="timeout"))
    else:
        ex1.append(passed("translate(grey image)"))
    ex2 = [passed("rotation_matrix(30)"), passed("rotation_matrix property", 3.0), passed("rotate(image)", 3.0)]
    if student in planted["rotation"]:
        # The same mistake seen by two checks counts once for the student.
        ex2[0] = failed("rotation_matrix(30)", f"rotation_matrix(30) is wrong: it looks like {ROTATION_WRONG_WAY}.",
                        mistake=ROTATION_WRONG_WAY)
        ex2[1] = failed("rotation_matrix property", f"rotation_matrix({student}.5, center=(1.0, 2.0)) is wrong: "
                        f"it looks like {ROTATION_WRONG_WAY}.\nSmallest failing input found: ...", 3.0,
                        mistake=ROTATION_WRONG_WAY)
    if student in planted["grey"]:
        ex2[2] = failed("rotate(image)", f"rotate(image) differs from the expected image by {10 + student} grey "
                        "levels on average (see the pictures).", 3.0)
    return [ExerciseResult("lab07.ex1", "Translation", [], ex1), ExerciseResult("lab07.ex2", "Rotation", [], ex2)]


def lab08(student: int, planted: dict) -> list[ExerciseResult]:
    checks = [passed("estimate_homography"), passed("warp")]
    if student in planted["no_lab08"]:
        checks = [failed(c.name, "module lab08_homographies.py not found", failure="missing_module") for c in checks]
    elif student in planted["import"]:
        message = "SyntaxError in lab08_homographies.py, line 3: invalid syntax"
        checks = [failed(c.name, message, failure="import_error") for c in checks]
    elif student in planted["forbidden"]:
        checks[0] = failed("estimate_homography", "estimate_homography() called cv2.findHomography, which this "
                           "exercise asks you to implement yourself", failure="forbidden_call")
    elif student in planted["skeleton08"]:
        checks = [CheckResult(c.name, 0.0, 2.0, NOT_IMPLEMENTED, f"{c.name}() is not implemented yet") for c in checks]
    return [ExerciseResult("lab08.ex1", "Homography", [], checks)]


PLANTED = {"rotation": {0, 3, 5, 8, 11, 14, 19}, "swapped": {1, 3, 4, 9}, "grey": {2, 6, 7},
           "timeout": {5, 12, 13}, "no_lab08": {16, 17, 18}, "import": {10, 15}, "forbidden": {7},
           "skeleton08": {19}}
CLASS_SIZE = 20


def student_name(i: int) -> str:
    return f"Student {i:02d}"


@pytest.fixture(scope="module")
def planted_class() -> list[StudentRecord]:
    students = []
    for i in range(CLASS_SIZE):
        result = GradingResult(f"s{i:02d}", "hash", "test", lab07(i, PLANTED) + lab08(i, PLANTED))
        students.append(StudentRecord(f"s{i:02d}", student_name(i), result=result.to_dict(),
                                      feedback_href=f"s{i:02d}/feedback.html"))
    students.append(StudentRecord("broken-zip", status="unreadable", reason="broken.zip is not a valid zip archive"))
    return students


def group(summary, exercise_id, label):
    [exercise] = [e for e in summary.exercises if e.id == exercise_id]
    matches = [g for g in exercise.mistakes + exercise.other_failures if g.label == label]
    assert matches, f"{exercise_id}: no group {label!r}; groups: {[g.label for g in exercise.mistakes]}"
    return exercise, matches[0]


def test_planted_named_mistakes_are_counted_exactly(planted_class):
    summary = summarise(planted_class)
    exercise, rotation = group(summary, "lab07.ex2", ROTATION_WRONG_WAY)
    assert rotation.named
    assert sorted(s.student_id for s in rotation.students) == [f"s{i:02d}" for i in sorted(PLANTED["rotation"])]
    assert exercise.attempted == CLASS_SIZE
    assert exercise.percent(rotation) == pytest.approx(35.0)
    assert rotation.checks == {"rotation_matrix(30)", "rotation_matrix property"}
    # Named by the message alone ("it looks like ..."), without the mistake field.
    _, swapped = group(summary, "lab07.ex1", TX_TY_SWAPPED)
    assert swapped.named and swapped.count == len(PLANTED["swapped"])


def test_unnamed_failures_group_by_their_first_sentence_without_numbers(planted_class):
    summary = summarise(planted_class)
    _, grey = group(summary, "lab07.ex2", "rotate(image) differs from the expected image by # grey levels on average (see the pictures)")
    assert not grey.named and grey.count == len(PLANTED["grey"])
    [ex2] = [e for e in summary.exercises if e.id == "lab07.ex2"]
    assert ex2.mistakes == [g for g in ex2.mistakes if g.named] and len(ex2.mistakes) == 1


def test_incidents_per_student_and_who_submitted(planted_class):
    summary = summarise(planted_class)
    incidents = {(i.student.student_id, i.kind): i for i in summary.incidents}
    expected = ({(f"s{i:02d}", "timeout") for i in PLANTED["timeout"]}
                | {(f"s{i:02d}", "import_error") for i in PLANTED["import"]}
                | {(f"s{i:02d}", "forbidden_call") for i in PLANTED["forbidden"]})
    assert set(incidents) == expected   # a lab not handed in is no incident
    assert incidents[("s10", "import_error")].where == ["lab08.ex1"]   # both checks, one incident
    assert "did not finish" in incidents[("s05", "timeout")].message   # two timeouts, one line, the first message
    timeouts_are_not_mistakes = [g for e in summary.exercises for g in e.mistakes + e.other_failures
                                 if "did not finish" in g.label]
    assert not timeouts_are_not_mistakes
    labs = {lab.key: lab for lab in summary.labs}
    assert labs["lab07"].submitted == CLASS_SIZE
    assert labs["lab08"].submitted == CLASS_SIZE - len(PLANTED["no_lab08"]) - len(PLANTED["skeleton08"])
    assert [s.student_id for s in summary.not_graded] == ["broken-zip"]


def test_pass_rates_hardest_first(planted_class):
    checks = summarise(planted_class).checks
    rates = [c.pass_rate for c in checks]
    assert rates == sorted(rates)
    [rotation] = [c for c in checks if c.name == "rotation_matrix(30)"]
    assert (rotation.passed, rotation.attempted) == (CLASS_SIZE - 7, CLASS_SIZE)


def test_distribution_mean_median_histogram(planted_class):
    summary = summarise(planted_class)
    [ex2] = [e for e in summary.exercises if e.id == "lab07.ex2"]
    scores = sorted(ex2.distribution.scores)
    assert len(scores) == CLASS_SIZE and ex2.distribution.max_score == 8.0
    assert ex2.distribution.median == pytest.approx((scores[9] + scores[10]) / 2)
    assert sum(ex2.distribution.histogram(10)) == CLASS_SIZE
    assert ex2.distribution.histogram(10)[-1] == scores.count(8.0)   # full marks in the top bin
    assert len(summary.total.scores) == CLASS_SIZE


def _text(html: str) -> str:
    return unescape(re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", html)))


def test_page_shows_the_counts_and_links_to_each_students_feedback(planted_class, tmp_path):
    out = tmp_path / "index.html"
    render_overview(planted_class, out, course_title="Computer vision")
    html = out.read_text()
    text = _text(html)
    assert f"35% 7 of 20: {ROTATION_WRONG_WAY}" in text
    assert f"20% 4 of 20: {TX_TY_SWAPPED}" in text
    item = html[html.index("7 of 20"):]
    item = item[:item.index("</li>")]
    assert sorted(re.findall(r'href="(s\d\d)/feedback.html"', item)) == [f"s{i:02d}" for i in sorted(PLANTED["rotation"])]
    for i in range(CLASS_SIZE):
        assert f'href="s{i:02d}/feedback.html"' in html
    assert "broken.zip is not a valid zip archive" in text
    assert "<script" not in html and "<img" not in html   # pictures are inline SVG, no scripts
    assert html.count("<svg") == 1 + 3   # the total and each exercise


def test_student_text_is_escaped():
    result = GradingResult("x", "h", "v", [ExerciseResult("lab07.ex1", "T", [], [
        failed("c", "<img src=x onerror=alert(1)> is wrong: it looks like <script>alert(2)</script>.")])]).to_dict()
    students = [StudentRecord("evil", "<script>alert(3)</script>", result=result, feedback_href="javascript:alert(4)"),
                StudentRecord("odd name", "Zoë O'Brien", result=result, feedback_href="odd name/feedback.html")]
    html = overview_html(students)
    assert "<script>" not in html and "<img src=x" not in html and "javascript:" not in html
    assert 'href="odd%20name/feedback.html"' in html
    assert safe_href("https://lms.example/x") == "https://lms.example/x" and safe_href("data:text/html,x") == ""


def test_mistake_labels():
    assert mistake_of({"status": PASSED, "message": "it looks like x."}) is None
    assert mistake_of({"status": NOT_IMPLEMENTED, "message": "f() is not implemented yet"}) is None
    assert mistake_of({"status": FAILED, "message": "m", "mistake": "K transposed"}) == ("K transposed", True)
    assert mistake_of({"status": FAILED, "message": "F(x) is wrong: it looks like F transposed.\nmore"}) == (
        "F transposed", True)
    assert mistake_of({"status": FAILED, "message": "f() did not finish within 10 s"}) is None
    # (the error model's names and its repairs: the sentence the student read, or the function mended and how)
    named = ("camera_matrix_dlt(P) is wrong. The error model: it looks like in `camera_matrix_dlt`, a minus sign is "
             "missing in the third item of the first argument of the second `np.hstack` (sign). It returned ...")
    assert mistake_of({"status": FAILED, "message": named, "mistake": "mutant:sign"}) == (
        "in `camera_matrix_dlt`, a minus sign is missing in the third item of the first argument of the second "
        "`np.hstack`", True)
    repaired = ("rotate(image) is wrong. Trying small changes to your code: changing `np.radians(a)` to `a` (line 55) "
                "makes `rotate` give the expected answers on all 15 inputs tried")
    assert mistake_of({"status": FAILED, "message": repaired, "mistake": "repair:swap_items"}) == (
        "one change of `rotate` mends it (swap items)", True)
    assert mistake_of({"status": FAILED, "message": "m", "mistake": "mutant:add_sub+other_name"}) == (
        "the error model's add sub and other name", True)
    assert first_sentence("error 3.5 px where the best has 0.25 px. Look again") == "error # px where the best has # px"


def test_one_exception_relayed_by_several_checks_is_one_kind_of_failure():
    """Audit of 2026-12-07: one student's NameError, told by one check as it was and by another with the input it
    raised on, was listed as two kinds of failure of one student."""
    exercise = {"id": "lab07.ex1", "title": "t", "score": 0.0, "max_score": 2.0, "checks": [
        {"name": "a", "status": FAILED, "score": 0, "max_score": 1,
         "message": "scale() raised NameError: name 'np' is not defined"},
        {"name": "b", "status": FAILED, "score": 0, "max_score": 1,
         "message": "scale() raised NameError: name 'np' is not defined (raised on scale(grey image, sx=2.0, sy=0.8))"},
    ]}
    student = StudentRecord("ann", "Ann", result={"total": 0.0, "max_total": 2.0, "exercises": [exercise]})
    [summary] = summarise([student]).exercises
    assert [(g.label, g.count) for g in summary.other_failures] == [("scale() raised NameError: name 'np' is not defined", 1)]


def test_records_from_the_gradebooks_class_results():
    rows = [{"student_id": "alice", "display_name": "Alice A", "status": "graded", "reason": "",
             "result": {"total": 1.0, "max_total": 2.0, "exercises": []}, "feedback": "alice/feedback.html",
             "source": "entry", "origin": "alice", "lms": {}, "members": [], "submitted_at": None, "late": None},
            {"student_id": "bob", "display_name": "bob", "status": "unreadable", "reason": "empty zip",
             "result": None, "feedback": None}]
    alice, bob = records_from_class_results(rows)
    assert (alice.label, alice.feedback_href, alice.result["total"]) == ("Alice A", "alice/feedback.html", 1.0)
    assert (bob.status, bob.reason, bob.result, bob.feedback_href) == ("unreadable", "empty zip", None, "")


@pytest.mark.slow
def test_real_gradings_carry_named_mistakes_and_failures(tmp_path):
    """End to end: the judges name the mistake, the runner records how student code failed."""
    from autograder.engine.runner import grade
    from autograder.sandbox.supervisor import Limits
    from conftest import mutant

    wrong = mutant(tmp_path, "lab07_transformations", textwrap.dedent("""
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
            c = np.asarray(center, float)
            M = np.eye(3); M[:2, :2] = R; M[:2, 2] = c - R @ c
            return M

        def translate(image, tx=100, ty=50):
            while True:
                pass
        """))
    result = grade(wrong, ["lab07.ex1", "lab07.ex2"], limits=Limits(call_timeout=1.0), pictures="none")
    summary = summarise([StudentRecord("w", result=result.to_dict(), feedback_href="w/feedback.html")])
    [ex2] = [e for e in summary.exercises if e.id == "lab07.ex2"]
    assert [g.label for g in ex2.mistakes][:1] == [ROTATION_WRONG_WAY]
    assert {c["mistake"] for e in result.to_dict()["exercises"] for c in e["checks"]} >= {ROTATION_WRONG_WAY}
    assert {(i.kind, tuple(i.where)) for i in summary.incidents} == {("timeout", ("lab07.ex1",))}
