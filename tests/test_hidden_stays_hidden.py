"""Hidden checks stay hidden: of a hidden check a student reads its verdict, nothing else.

A property over the registry: every hidden check of every lab is failed by three
submissions of all the labs, each graded once -- the skeletons (not implemented), the
reference solutions with every graded function answering wrongly (the judges' own
messages, naming the hidden inputs, and pictures), and one whose functions raise with
their arguments (tracebacks, counterexamples); both of the latter print their arguments
too. A hidden check's own text (its name, the lines of its message, hint, printed
output and traceback, its named mistake, its pictures' titles and pixels) that no public
check of the same grading shows is looked for in everything a student reads: the
terminal, feedback.html and results.json of ``grade.py``, the page and results.json a
batch writes for the student (and the page it re-renders), Gradescope's results.json,
and ``check()`` as text, as HTML and as its result. None of it may be there, and no score
a student sees may count what a hidden check earned unless the course shows those points.
"""

from __future__ import annotations

import copy
import html as html_text
import json
import re
import textwrap
from pathlib import Path

import pytest

import autograder.engine.runner
from autograder import cli
from autograder.instructor import gradescope
from autograder.student import selfcheck
from autograder.instructor.batch import run as batch_run
from autograder.instructor.batch import task
from autograder.instructor.batch.exports import StudentGrade
from autograder.instructor.course import CourseConfig, CourseConfigError
from autograder.engine.registry import discover
from autograder.reports import html
from autograder.engine.results import GradingResult, strip_pictures
from autograder.engine.runner import grade
from autograder.sandbox.supervisor import Limits
from conftest import REFERENCE, SKELETON

# Appended to a reference module: every graded function prints its arguments, then answers
# wrongly (numbers changed, so every judge fails it with its own message) or raises with them.
WRONG_ANSWERS = '''
import numpy as _agh_np


def _agh_shown_one(value):
    if isinstance(value, _agh_np.ndarray):  # every input its own words: shape, type and sum
        try:
            total = float(_agh_np.nansum(_agh_np.abs(value.astype(complex))))
        except (TypeError, ValueError):
            total = -1.0
        return f"array{value.shape} {value.dtype} sum={total:.9g}"
    if isinstance(value, (list, tuple)):
        inner = ", ".join(_agh_shown_one(v) for v in value[:8])
        return f"[{inner}]" if isinstance(value, list) else f"({inner})"
    return repr(value)[:100].replace("\\n", " ")


def _agh_shown(args, kwargs):
    shown = [_agh_shown_one(a) for a in args] + [f"{k}={_agh_shown_one(v)}" for k, v in kwargs.items()]
    return "(" + ", ".join(shown) + ")"


def _agh_wrong(value):
    if isinstance(value, _agh_np.ndarray):
        if value.dtype.kind in "fc":
            return value * 1.25 + 3.0
        if value.dtype.kind in "iu":
            return (value.astype(_agh_np.int64) // 2 + 7).astype(value.dtype)
        return ~value if value.dtype.kind == "b" else value
    if isinstance(value, (tuple, list)):
        return type(value)(_agh_wrong(v) for v in value)
    return value * 1.25 + 3.0 if isinstance(value, float) else value


def _agh_echo(function, raising):
    def echoed(*args, **kwargs):
        shown = _agh_shown(args, kwargs)
        print("AGH " + function.__name__ + shown)
        if raising:
            raise ValueError("AGH " + shown)
        return _agh_wrong(function(*args, **kwargs))
    return echoed
'''


def _labs():
    return sorted(discover().values(), key=lambda lab: lab.key)


def _hidden_checks() -> list[tuple[str, str]]:
    """(exercise id, check name) of every hidden graded check in the registry."""
    return [(exercise.id, check.name) for lab in _labs() for exercise in lab.exercises.values()
            for check in exercise.checks if check.hidden and not check.advice]


def _echoing_submission(folder: Path, raising: bool) -> Path:
    folder.mkdir(parents=True)
    for lab in _labs():
        functions = dict.fromkeys(f for exercise in lab.exercises.values() for f in exercise.signatures)
        echoes = "\n".join(f"{f} = _agh_echo({f}, {raising})" for f in functions)
        (folder / f"{lab.module}.py").write_text(
            (REFERENCE / f"{lab.module}.py").read_text() + WRONG_ANSWERS + "\n" + echoes + "\n")
    return folder


@pytest.fixture(scope="module")
def gradings(tmp_path_factory) -> dict[str, tuple[Path, GradingResult]]:
    """Each submission graded once (every lab, pictures of every check): kind -> (folder, grading).

    A GiB of memory is plenty for every check; the wrong answers' hidden stitch_many (its
    homographies wrong) grows its panorama to 5 GB until its 10 s run out: stopped at the GiB
    instead, a grading of 26 s takes 10 (naming off), and its message is as much its own."""
    root = tmp_path_factory.mktemp("hidden")
    folders = {"skeleton": SKELETON,
               "wrong answers": _echoing_submission(root / "wrong", raising=False),
               "raising": _echoing_submission(root / "raising", raising=True)}
    limits = Limits(memory=1 << 30)
    return {kind: (folder, grade(folder, pictures="all", limits=limits)) for kind, folder in folders.items()}


# ------------------------------------------------------------------ what may not leak
def _squeezed(text: str) -> str:
    """Without whitespace: a line a report wraps or indents is still found."""
    return "".join(text.split())


def _texts(check) -> list[str]:
    texts = [check.name, check.message, check.hint, check.output, check.traceback, check.mistake]
    for artifact in check.artifacts:
        texts += [artifact.title, artifact.caption]
        texts += [str(item.get(key, "")) for item in artifact.items for key in ("label", "data", "svg")]
    return texts


def hidden_text(result: GradingResult) -> dict[tuple[str, str], set[str]]:
    """(exercise id, check name) -> the lines only that hidden check shows (whitespace
    removed, at least 10 characters): its name, message, output, traceback, pictures..."""
    public = _squeezed("\n".join(
        [note for note in result.notes]
        + [text for e in result.exercises for text in [e.id, e.title, e.message, *e.functions, *e.rules]]
        + [text for e in result.exercises for c in e.checks if not c.hidden for text in _texts(c)]))
    found = {}
    for exercise in result.exercises:
        for check in exercise.checks:
            if check.hidden:
                lines = {_squeezed(line) for text in _texts(check) for line in text.splitlines()}
                found[exercise.id, check.name] = {line for line in lines if len(line) >= 10 and line not in public}
    return found


def strings(data) -> list[str]:
    """Every string (keys too) in a JSON document."""
    if isinstance(data, dict):
        return [s for key, value in data.items() for s in [key, *strings(value)]]
    if isinstance(data, list):
        return [s for value in data for s in strings(value)]
    return [data] if isinstance(data, str) else []


def assert_nothing_hidden(result: GradingResult, outputs: dict[str, str]):
    """No line only a hidden check shows appears in any of ``outputs`` (name -> text)."""
    squeezed = {name: _squeezed(html_text.unescape(text)) for name, text in outputs.items()}
    leaks = [f"{exercise_id} {name!r}: {line[:100]!r} in {where}"
             for (exercise_id, name), lines in hidden_text(result).items() for line in lines
             for where, text in squeezed.items() if line in text]
    assert not leaks, f"{len(leaks)} leaks of hidden checks, e.g.\n" + "\n".join(leaks[:20])


def student_scores(result: GradingResult, points_visible: bool) -> dict[str, tuple[float, float]]:
    """Exercise id -> (score, max) a student may see: public checks only, unless points are shown."""
    return {e.id: (round(sum(c.score for c in e.checks if points_visible or not c.hidden), 6),
                   round(sum(c.max_score for c in e.checks if points_visible or not c.hidden), 6))
            for e in result.exercises}


@pytest.fixture
def graded_as(monkeypatch):
    """Make every path that grades return a copy of ``result`` (graded once, above)."""
    def use(result: GradingResult):
        monkeypatch.setattr(autograder.engine.runner, "grade", lambda *args, **kwargs: copy.deepcopy(result))
    return use


# ------------------------------------------------------------------ the submissions really fail them
def test_every_hidden_check_is_failed_and_its_text_is_findable(gradings):
    """The property is not vacuous: each grading holds every hidden check of the registry;
    the raising submission fails each one with text of its own, which a page rendered from
    the whole grading (what students were shown before) does contain."""
    registry = _hidden_checks()
    assert len(registry) >= 30
    for kind, (_, result) in gradings.items():
        graded = {(e.id, c.name): c for e in result.exercises for c in e.checks if c.hidden}
        assert set(registry) <= set(graded), kind
        if kind != "wrong answers":  # a wrong number may still pass a loose check
            assert not any(graded[key].passed for key in registry), kind
    _, raising = gradings["raising"]
    own = hidden_text(raising)
    page = _squeezed(html_text.unescape(html.render(raising)))
    for key in registry:
        beyond_name = own[key] - {_squeezed(key[1])}
        assert beyond_name, f"{key}: no text of its own to look for"
        assert any(line in page for line in beyond_name), key
    _, wrong = gradings["wrong answers"]
    failed = [(e.id, c.name) for e in wrong.exercises for c in e.checks if c.hidden and not c.passed]
    assert len(failed) >= len(registry) - 2  # the judges' own messages, for nearly all
    shown = _squeezed(html_text.unescape(html.render(wrong)))
    # The hidden rotation's angle is drawn for the submission (one beyond 180 degrees, one negative).
    printed = _squeezed("".join(c.output for e in wrong.exercises for c in e.checks if c.hidden))
    angle = re.search(r"rotation_matrix\((-?\d+\.\d+),\(89\.5,59\.5\)\)", printed)
    assert angle and f"angle_deg={angle.group(1)}" in shown


# ------------------------------------------------------------------ every student-facing output
KINDS = ["skeleton", "wrong answers", "raising"]


@pytest.mark.parametrize("points_visible", [False, True], ids=["points withheld", "points shown"])
@pytest.mark.parametrize("kind", KINDS)
def test_grade_py_terminal_page_and_json(gradings, graded_as, kind, points_visible, tmp_path, capsys,
                                         monkeypatch):
    folder, result = gradings[kind]
    graded_as(result)
    monkeypatch.setattr(cli, "_early_sandbox", lambda limits: None)
    monkeypatch.setenv("COLUMNS", "400")
    course = tmp_path / "course.json"
    course.write_text(json.dumps({"hidden_points_visible": points_visible}))
    page, results = tmp_path / "feedback.html", tmp_path / "results.json"
    status = cli.grade_py_main(["--submission", str(folder), "--html", str(page), "--json", str(results),
                                "--json-pictures", "--config", str(course)])
    terminal = capsys.readouterr().out
    assert status == 0 and "hidden check 1" in page.read_text()
    data = json.loads(results.read_text())
    assert_nothing_hidden(result, {"terminal": terminal, "feedback.html": page.read_text(),
                                   "results.json": "\n".join(strings(data))})
    seen = {e["id"]: (e["score"], e["max_score"]) for e in data["exercises"]}
    assert seen == student_scores(result, points_visible)
    assert data["hidden_points_withheld"] is not points_visible


def test_autograder_grade_shows_hidden_checks_in_full_when_asked(gradings, graded_as, tmp_path, monkeypatch):
    folder, result = gradings["raising"]
    graded_as(result)
    monkeypatch.setattr(cli, "_early_sandbox", lambda limits: None)
    results = tmp_path / "results.json"
    assert cli.main(["grade", str(folder), "--no-html", "--quiet", "--json", str(results), "--show-hidden"]) == 0
    assert json.loads(results.read_text()) == json.loads(json.dumps(strip_pictures(result.to_dict())))


@pytest.mark.parametrize("points_visible", [False, True], ids=["points withheld", "points shown"])
@pytest.mark.parametrize("kind", KINDS)
def test_batch_student_files(gradings, graded_as, kind, points_visible, tmp_path):
    folder, result = gradings[kind]
    graded_as(result)
    files = {path.name: path.read_bytes() for path in folder.glob("*.py")}
    outcome = task.grade_files(files, [], 10.0, "all", points_visible, "", "student1")
    assert "error" not in outcome, outcome
    data = json.loads(outcome["json"])
    # The batch re-renders a lost page from the gradebook, which keeps the whole grading.
    student = StudentGrade(student={"student_id": "student1", "status": "graded", "result": outcome["result"]},
                           exercises={})
    course = CourseConfig(hidden_points_visible=points_visible)
    batch_run._refresh_page(tmp_path, student, result.max_total, course)
    assert_nothing_hidden(result, {"feedback.html": outcome["page"], "results.json": "\n".join(strings(data)),
                                   "page re-rendered": (tmp_path / "student1" / "feedback.html").read_text()})
    assert {e["id"]: (e["score"], e["max_score"]) for e in data["exercises"]} == student_scores(result,
                                                                                                points_visible)
    assert outcome["result"] == GradingResult.to_dict(
        GradingResult.from_dict(outcome["result"]))  # the gradebook's copy is the whole grading
    kept = "\n".join(strings(outcome["result"]))
    assert all(name in kept for _, name in _hidden_checks())


@pytest.mark.parametrize("points_visible", [False, True], ids=["points withheld", "points shown"])
@pytest.mark.parametrize("kind", KINDS)
def test_gradescope_results(gradings, graded_as, kind, points_visible, tmp_path):
    folder, result = gradings[kind]
    graded_as(result)
    data = gradescope.run(folder, tmp_path / "results.json",
                          CourseConfig(hidden_points_visible=points_visible))
    assert data == json.loads((tmp_path / "results.json").read_text())
    assert len(data["tests"]) == sum(len(e.checks) for e in result.for_students().exercises)
    assert_nothing_hidden(result, {"results.json": "\n".join(strings(data))})
    # The grade counts every check (Gradescope keeps hidden tests and the total from students
    # until they are published); the text at the top only what students may see.
    assert data["score"] == result.total
    hidden = [t for t in data["tests"] if t["visibility"] == "after_published"]
    assert sum(t["max_score"] for t in hidden) == sum(c.max_score for e in result.exercises
                                                     for c in e.checks if c.hidden)
    scores = student_scores(result, points_visible)
    total = sum(score for score, _ in scores.values()), sum(maximum for _, maximum in scores.values())
    withheld = "" if points_visible else " (public checks only; the grade counts the hidden checks too)"
    assert f"Total: {total[0]:g} / {total[1]:g}{withheld}\n" in data["output"]
    for e in result.exercises:
        assert f"{e.id} {e.title}: {scores[e.id][0]:g} / {scores[e.id][1]:g}" in data["output"]


@pytest.mark.parametrize("stdout_visibility", ["hidden", "visible"])
def test_gradescope_log_tells_instructors_only(gradings, graded_as, stdout_visibility, tmp_path, capsys):
    """Gradescope shows the autograder's output to instructors only while stdout_visibility is
    hidden: then it holds the hidden checks in full, else nothing of them."""
    folder, result = gradings["raising"]
    graded_as(result)
    gradescope.run(folder, tmp_path / "results.json", CourseConfig(stdout_visibility=stdout_visibility))
    log = _squeezed(capsys.readouterr().out)
    for (exercise_id, name), lines in hidden_text(result).items():
        assert any(line in log for line in lines) is (stdout_visibility == "hidden"), (exercise_id, name)


@pytest.mark.parametrize("kind", KINDS)
def test_check_in_a_notebook(gradings, graded_as, kind):
    folder, result = gradings[kind]
    graded_as(result)
    report = selfcheck.check(submission=folder)
    assert_nothing_hidden(result, {"check() text": str(report), "check() HTML": report._repr_html_(),
                                   "check().result": "\n".join(strings(report.result.to_dict()))})
    assert (report.score, report.max_score) == (sum(s for s, _ in student_scores(result, False).values()),
                                                sum(m for _, m in student_scores(result, False).values()))


# ------------------------------------------------------------------ the view itself
def test_a_hidden_check_shows_its_verdict_and_nothing_else(gradings):
    _, result = gradings["raising"]
    view = result.for_students()
    for exercise, shown in zip(result.exercises, view.exercises):
        hidden = [c for c in exercise.checks if c.hidden and c.max_score > 0]
        redacted = [c for c in shown.checks if c.redacted]
        assert [c.name for c in redacted] == [f"hidden check {n}" for n in range(1, len(hidden) + 1)]
        for original, c in zip(hidden, redacted):
            assert c.hidden and (c.passed, c.message) == (original.passed, "passed" if original.passed
                                                         else "not passed")
            assert (c.hint, c.output, c.traceback, c.mistake, c.failure, c.artifacts) == ("", "", "", "", "", [])
            assert (c.score, c.max_score, c.seconds) == (0, 0, 0)
        assert [c for c in shown.checks if not c.hidden] == [c for c in exercise.checks if not c.hidden]
    assert view.for_students().to_dict() == view.to_dict()  # a view of a view is the same view
    assert GradingResult.from_dict(view.to_dict()).to_dict() == view.to_dict()
    assert result.for_students(points_visible=True).total == result.total


def test_course_says_whether_hidden_points_show():
    assert CourseConfig().hidden_points_visible is False
    with pytest.raises(CourseConfigError, match="hidden_points_visible"):
        CourseConfig(hidden_points_visible="yes")
    for visibility in ("visible", "hidden"):  # Gradescope would show what hidden checks scored
        with pytest.raises(CourseConfigError, match="hidden_points_visible"):
            CourseConfig(hidden_visibility=visibility)
        assert CourseConfig(hidden_visibility=visibility, hidden_points_visible=True)
    assert CourseConfig(hidden_visibility="after_due_date")
