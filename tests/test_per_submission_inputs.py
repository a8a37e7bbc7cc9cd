"""Property checks draw their inputs per submission (autograder.engine.inputs): the same files meet the
same inputs on every run, other files other inputs, so a table of the answers to one grading's
inputs earns nothing on the next grading of the table itself."""

from __future__ import annotations

import numpy as np
import pytest

from autograder.engine import runner
from autograder.engine.checks import Fail, Trial
from autograder.engine.inputs import SECRET_VARIABLE, Inputs
from autograder.engine.registry import select
from conftest import REFERENCE, mutant

MODULE = "lab07_transformations"
PROPERTY = "translation_matrix for any tx, ty"
EXAMPLE = "translation_matrix(100, 50)"


@pytest.fixture
def recorded(monkeypatch):
    """Every ``translation_matrix`` call a grading makes: ``[(args, kwargs), ...]`` per grading."""
    gradings: list[list] = []

    class Recording(runner.Sandbox):
        def call(self, module, function, args=(), kwargs=None, **options):
            if function == "translation_matrix":
                gradings[-1].append((tuple(args), dict(kwargs or {})))
            return super().call(module, function, args, kwargs, **options)

    real_grade = runner.grade

    def grading(*args, **options):  # every grading, also one started elsewhere (Gradescope's run)
        gradings.append([])
        return real_grade(*args, **options)

    monkeypatch.setattr(runner, "Sandbox", Recording)
    monkeypatch.setattr(runner, "grade", grading)

    def grade(submission, **options):
        result = runner.grade(submission, ["lab07.ex1"], pictures="none", **options)
        return result, gradings[-1]

    grade.gradings = gradings
    return grade


def _check(result, name):
    [exercise] = result.exercises
    return next(c for c in exercise.checks if c.name == name)


def test_the_same_files_draw_the_same_inputs_and_other_files_other_ones(recorded, tmp_path):
    first, drawn = recorded(REFERENCE)
    again, drawn_again = recorded(REFERENCE)           # the second replays the recorded examples
    commented, drawn_commented = recorded(mutant(tmp_path, MODULE, "# a comment changes nothing it computes\n"))
    assert len(drawn) > 20 and drawn_again == drawn
    assert first.submission_hash != commented.submission_hash
    shared = [call for call in drawn_commented if call in drawn]
    # Hypothesis starts every run with the simplest example ((0.0, 0.0)) and the fixed check
    # asks (100, 50); all the rest differs.
    assert len(shared) <= 3 and len(drawn_commented) > 20
    for result in (first, again, commented):
        assert _check(result, PROPERTY).passed


def test_the_course_secret_changes_the_inputs_of_the_same_files(monkeypatch):
    content = "0" * 64
    plain, course, other_course = (Inputs.for_submission(content, ""), Inputs.for_submission(content, "s3cret"),
                                   Inputs.for_submission(content, "another"))
    assert not plain.secret and course.secret
    seeds = {i.seed("lab07.ex1.translation_matrix_property", 0) for i in (plain, course, other_course)}
    assert len(seeds) == 3
    assert course.seed("a", 0) != course.seed("a", 1) != course.seed("b", 0)
    monkeypatch.setenv(SECRET_VARIABLE, "s3cret")
    assert Inputs.for_submission(content) == course       # the variable stands in for the configuration
    assert Inputs.for_submission(content, "") == plain    # an explicit "none" wins over it
    with pytest.raises(TypeError, match="text or bytes"):
        Inputs.for_submission(content, 42)


def _memorising(tmp_path, calls) -> object:
    """The reference with a ``translation_matrix`` that knows only the answers to ``calls``
    (a table built from one grading's inputs, exactly, by the reference) and answers the
    identity otherwise."""
    table = {}
    for args, kwargs in calls:
        tx, ty = args  # the checks of lab07.ex1 call it as translation_matrix(tx, ty)
        answer = np.array([[1.0, 0.0, tx], [0.0, 1.0, ty], [0.0, 0.0, 1.0]])
        table[(float(tx).hex(), float(ty).hex())] = answer.tolist()
    return mutant(tmp_path / "memorising", MODULE, f"""
        _ANSWERS = {table!r}


        def translation_matrix(tx, ty):
            known = _ANSWERS.get((float(tx).hex(), float(ty).hex()))
            return np.array(known if known is not None else np.eye(3))
        """)


def test_a_table_of_one_gradings_answers_loses_the_property_on_its_own_grading(recorded, tmp_path, monkeypatch):
    reference, drawn = recorded(REFERENCE)
    table = _memorising(tmp_path, drawn)
    result, _ = recorded(table)
    property_check = _check(result, PROPERTY)
    assert not property_check.passed and property_check.score == 0
    assert "Smallest failing input found" in property_check.message
    # The fixed example is in the table: a check with one public input is not defended here
    # (the hidden checks are; see the README).
    assert _check(result, EXAMPLE).passed

    # With inputs independent of the content (as before: one seed for every submission),
    # the same table earned the property's points.
    same_for_everyone = Inputs.for_submission(reference.submission_hash)
    monkeypatch.setattr(runner.Inputs, "for_submission", classmethod(lambda cls, *_: same_for_everyone))
    fooled, _ = recorded(table)
    assert _check(fooled, PROPERTY).passed


class _InProcess:
    """Stands in for the sandbox: the reference's functions called here, wrong from the n-th call."""

    def __init__(self, wrong_from):
        import importlib.util

        spec = importlib.util.spec_from_file_location(MODULE, REFERENCE / f"{MODULE}.py")
        self.module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(self.module)
        self.calls, self.wrong_from, self.shared = 0, wrong_from, {}

    def call(self, module, function, args=(), kwargs=None, **_):
        from autograder.sandbox.supervisor import CallOutcome

        self.calls += 1
        value = getattr(self.module, function)(*args, **(kwargs or {}))
        return CallOutcome(ok=True, value=value.T if self.calls >= self.wrong_from else value)


@pytest.mark.parametrize("secret", ["", "s3cret"])
def test_a_failure_names_its_input_and_says_whether_a_rerun_draws_it_again(secret):
    [exercise] = select(["lab07.ex1"])
    check = next(c for c in exercise.checks if c.name == PROPERTY)
    messages = []
    for _ in range(2):
        with pytest.raises(Fail) as failed:
            check.func(Trial(_InProcess(wrong_from=3), check, inputs=Inputs.for_submission("ab" * 32, secret)))
        messages.append(failed.value.message)
    assert messages[0] == messages[1] and "Smallest failing input found: (" in messages[0]
    rerun = "re-run with python grade.py lab07.ex1" in messages[0]
    assert rerun == (not secret)
    assert ("your own runs draw others" in messages[0]) == bool(secret)


def test_a_check_run_outside_a_grading_draws_the_inputs_of_no_submission():
    [exercise] = select(["lab07.ex1"])
    check = next(c for c in exercise.checks if c.name == PROPERTY)
    outside, sandbox = Trial(_InProcess(wrong_from=10**9), check), _InProcess(wrong_from=10**9)
    assert outside.inputs == Inputs.for_submission("", "")
    check.func(outside)
    check.func(Trial(sandbox, check, inputs=Inputs.for_submission("", "")))
    assert sandbox.calls == outside.sandbox.calls > 20


def test_the_official_grading_draws_with_the_courses_secret(recorded, tmp_path, monkeypatch):
    import json
    import zipfile

    from autograder.instructor import gradescope
    from autograder.instructor.course import CourseConfig, CourseConfigError

    with pytest.raises(CourseConfigError, match="inputs_secret"):
        CourseConfig(inputs_secret=1234)
    monkeypatch.delenv(SECRET_VARIABLE, raising=False)
    for secret in ("one course", "another course"):
        results = tmp_path / f"{secret}.json"
        gradescope.run(REFERENCE, results, CourseConfig(select=["lab07.ex1"], inputs_secret=secret))
        assert json.loads(results.read_text())["score"] == 12
    recorded(REFERENCE)  # a student's own run: no secret
    assert len(recorded.gradings) == 3 and all(len(calls) > 20 for calls in recorded.gradings)
    assert len({repr(calls) for calls in recorded.gradings}) == 3  # each secret, and none, its own inputs

    # A zip built without a secret carries a new one; a configured one is kept.
    secrets_shipped = []
    for config in (CourseConfig(select=["lab07"]), CourseConfig(select=["lab07"]),
                   CourseConfig(select=["lab07"], inputs_secret="kept")):
        built = gradescope.build(tmp_path / "autograder.zip", config)
        with zipfile.ZipFile(built) as archive:
            secrets_shipped.append(json.loads(archive.read("course.json"))["inputs_secret"])
    new, other, kept = secrets_shipped
    assert len(new) == 32 and new != other and kept == "kept"


def test_a_batch_grades_with_the_courses_secret(tmp_path):
    import json

    from autograder.instructor.batch import task

    # A submission that prints what it is asked: its output tells the inputs it met.
    source = (mutant(tmp_path, MODULE, """
        _reference_translation = translation_matrix


        def translation_matrix(tx, ty):
            print(repr((tx, ty)))
            return _reference_translation(tx, ty)
        """) / f"{MODULE}.py").read_bytes()

    def printed(secret):
        outcome = task.grade_files({f"{MODULE}.py": source}, ["lab07.ex1"], 10.0, "none", True, secret, "student")
        [exercise] = json.loads(outcome["json"])["exercises"]
        return next(c for c in exercise["checks"] if c["name"] == PROPERTY)["output"]

    course, again, other = printed("course"), printed("course"), printed("another course")
    assert course.count("\n") > 20 and course == again != other
