"""Checks that can only call a stub are scored without running: same verdicts, no setup."""

import textwrap

import pytest
from conftest import REFERENCE, SKELETON, lab_exercises

from autograder.engine import runner
from autograder.engine.registry import discover
from autograder.engine.results import NOT_IMPLEMENTED
from autograder.engine.runner import grade
from autograder.engine.stubs import functions_called, stub_functions


def _verdicts(result):
    """Everything a student or a gradebook sees of each check, timings and pictures aside."""
    return [(e.id, e.message, e.score, c.name, c.score, c.max_score, c.status, c.message, c.hint,
             c.mistake, c.failure, c.output, c.traceback)
            for e in result.exercises for c in e.checks]


@pytest.mark.slow
def test_skeleton_verdicts_are_those_of_running_every_check(skeleton_result, monkeypatch):
    monkeypatch.setattr(runner, "stub_functions", lambda path: frozenset())
    assert _verdicts(skeleton_result) == _verdicts(grade(SKELETON))


def test_skeleton_checks_are_mostly_not_run(skeleton_result):
    # graded checks: an advice check always runs (a failure may turn into a tip)
    checks = [c for e in skeleton_result.exercises for c in e.checks if c.max_score > 0]
    skipped = [c for c in checks if c.seconds == 0 and c.status == NOT_IMPLEMENTED]
    assert len(skipped) >= 0.9 * len(checks)
    assert all(not c.artifacts for c in skipped)  # no pictures of ground truth for a stub


def _stubs(tmp_path, source):
    path = tmp_path / "module.py"
    path.write_text(textwrap.dedent(source))
    return stub_functions(path)


def test_stub_is_docstring_and_raise_only(tmp_path):
    assert _stubs(tmp_path, '''
        import numpy as np

        def bare():
            raise NotImplementedError

        def documented(x):
            """Docs."""
            raise NotImplementedError("ex1: documented")

        def started(x):
            y = x + 1
            raise NotImplementedError

        def conditional(x):
            if x:
                raise NotImplementedError
            return x

        def computed_message(x):
            raise NotImplementedError(f"{x}")

        @staticmethod
        def decorated():
            raise NotImplementedError

        def redefined():
            raise NotImplementedError

        redefined = lambda: 1
        ''') == {"bare", "documented"}


@pytest.mark.parametrize("rebinding", [
    "NotImplementedError = ValueError",
    "from builtins import NotImplementedError",
    "globals()['f'] = print",
    "def g():\n    global f\n    f = print",
])
def test_no_stubs_where_names_can_be_rebound(tmp_path, rebinding):
    assert _stubs(tmp_path, "def f():\n    raise NotImplementedError\n" + rebinding + "\n") == set()


def test_unreadable_modules_have_no_stubs(tmp_path):
    assert _stubs(tmp_path, "def f(:\n") == set()
    assert stub_functions(tmp_path / "missing.py") == set()


def test_functions_called_follows_helpers():
    lab07 = discover()["lab07"]
    by_name = {c.func.__name__: c for c in lab07.exercises["ex1"].checks}
    # The name reaches t.call through judge_matrix_call, a helper of the suite.
    assert functions_called(by_name["translation_matrix_example"]) == {"translation_matrix"}
    assert functions_called(by_name["translate_defaults"]) == {"translate"}


def test_a_stub_beside_a_real_function_is_still_run(tmp_path, monkeypatch):
    """Only an exercise made entirely of stubs is skipped: here translate() is real,
    so every check runs and the implemented function still earns its points."""
    source = (REFERENCE / "lab07_transformations.py").read_text()
    start = source.index("def translation_matrix(")
    end = source.index("\ndef ", start + 1)
    source = (source[:start] + "def translation_matrix(tx, ty):\n    raise NotImplementedError\n"
              + source[end:] + textwrap.dedent("""

        def translate(image, tx=100, ty=50):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, np.float64([[1, 0, tx], [0, 1, ty]]), (w, h))
        """))
    folder = tmp_path / "submission"
    folder.mkdir()
    (folder / "lab07_transformations.py").write_text(source)
    assert stub_functions(folder / "lab07_transformations.py") == {"translation_matrix"}
    result = grade(folder, ["lab07.ex1"])
    (exercise,) = lab_exercises(result, "lab07")
    assert exercise.checks[0].status == NOT_IMPLEMENTED
    assert all(c.seconds > 0 for c in exercise.checks)  # all run
    assert exercise.score > 0
    monkeypatch.setattr(runner, "stub_functions", lambda path: frozenset())
    assert _verdicts(result) == _verdicts(grade(folder, ["lab07.ex1"]))
