"""Hidden checks share nothing with public ones.

A submission may record every call it serves -- in a module global, in files in every
folder it can write -- and repeat the record in what it prints and in the exceptions
it raises. If one worker served public and hidden checks in turn, a later public
check's output would list the hidden checks' inputs on the student's own page and in
Gradescope's visible tests, before the hidden checks are released. The grader runs the
hidden checks after every public check, in fresh workers, so no record made while a
hidden check ran can reach a public check's text, whatever channel carries it.

Each call below is tagged with a fresh random token: a hidden call's token appearing
in any student-visible text is a leak, whatever carried it.
"""

import json
import re

import pytest

from autograder.engine.results import ADVICE
from autograder.engine.runner import grade
from autograder.instructor.course import CourseConfig
from autograder.instructor.gradescope import results_json
from autograder.sandbox.supervisor import Limits
from conftest import mutant

LAB07 = "lab07_transformations"
LIMITS = Limits(call_timeout=5.0, import_timeout=10.0, exercise_budget=30.0, submission_budget=120.0)

# Every channel a submission has for remembering its calls: the module's memory, the
# files it may write (home, temporary folder, working folder), the environment.
SPY = '''
import functools as _functools
import os as _os
import pathlib as _pathlib
import tempfile as _tempfile
import uuid as _uuid

_SEEN = []


def _places():
    folders = {_os.environ.get("HOME") or ".", _tempfile.gettempdir(), "/tmp", _os.getcwd()}
    return [_pathlib.Path(folder) / ".spy-calls" for folder in folders]


def _remember():
    token = "tok" + _uuid.uuid4().hex
    _SEEN.append(token)
    _os.environ["SPY_SEEN"] = _os.environ.get("SPY_SEEN", "") + " " + token
    known = set(_SEEN) | set(_os.environ["SPY_SEEN"].split())
    for place in _places():
        try:
            with open(place, "a") as record:
                record.write(token + "\\n")
            known |= set(place.read_text().split())
        except OSError:
            pass
    return token, sorted(known)


def _spy(function, {mode}):
    @_functools.wraps(function)
    def spied(*args, **kwargs):
        token, known = _remember()
        print("OWN", token, "KNOWN", " ".join(known))
        if raising and len(known) > 1:
            raise ValueError("calls served so far: " + " ".join(known))
        return function(*args, **kwargs)
    return spied


for _name in ("translate", "rotate", "scale", "shear", "affine_from_points", "affine_lstsq"):
    globals()[_name] = _spy(globals()[_name], raising=_name in {raising})
'''


def spied_submission(tmp_path, raising: set[str]):
    source = SPY.replace("{mode}", "raising=False").replace("{raising}", repr(raising))
    return mutant(tmp_path, LAB07, source)


def student_texts(result) -> str:
    """Everything a student may read of a grading before the hidden checks are released:
    their JSON, the Gradescope tests they can see, and the summary at the top."""
    shown = result.for_students(points_visible=True)
    texts = [json.dumps(shown.to_dict())]
    gradescope = results_json(result, CourseConfig())
    texts += [test["output"] + test["name"] for test in gradescope["tests"] if test["visibility"] == "visible"]
    texts.append(gradescope["output"])
    return "\n".join(texts)


@pytest.mark.slow
@pytest.mark.parametrize("raising", [set(), {"scale", "shear"}, {"translate", "rotate", "scale", "shear",
                                                                   "affine_from_points", "affine_lstsq"}],
                         ids=["printing", "some raise", "all raise"])
def test_no_hidden_call_reaches_a_public_check(tmp_path, raising):
    result = grade(spied_submission(tmp_path, raising), ["lab07"], pictures="none", limits=LIMITS)
    checks = [check for exercise in result.exercises for check in exercise.checks]
    own = lambda check: set(re.findall(r"OWN (tok[0-9a-f]+)", check.output))
    hidden_calls = set().union(*(own(check) for check in checks if check.hidden))
    public_calls = set().union(*(own(check) for check in checks if not check.hidden))
    assert hidden_calls and public_calls, "the spy must have served both kinds of check"

    public_text = "\n".join(check.message + check.output + check.hint + check.traceback
                            for check in checks if not check.hidden)
    assert not hidden_calls & set(re.findall(r"tok[0-9a-f]+", public_text))
    leaked = hidden_calls & set(re.findall(r"tok[0-9a-f]+", student_texts(result)))
    assert not leaked, "a hidden check's call reached a student-visible text"
    # Still graded as before: the spy changes no result, it only raises where asked.
    if not raising:
        assert all(check.passed or check.status == ADVICE for check in checks), \
            [(c.name, c.message) for c in checks if not c.passed]


@pytest.mark.slow
def test_hidden_checks_stay_in_the_suites_order_and_keep_their_budget(tmp_path):
    from autograder.engine.registry import select

    result = grade(spied_submission(tmp_path, set()), ["lab07"], pictures="none", limits=LIMITS)
    for exercise, graded in zip(select(["lab07"]), result.exercises):
        assert [c.name for c in graded.checks if c.max_score > 0] == [c.name for c in exercise.checks
                                                                     if not c.advice]
        assert graded.score == graded.max_score


@pytest.mark.slow
def test_hidden_checks_that_meet_only_stubs_need_no_fresh_worker(monkeypatch):
    """A skeleton's hidden checks call nothing (each meets a stub): no worker is booted for them,
    and no hidden input reaches the student's code, which they never call."""
    from autograder.engine import runner
    from conftest import SKELETON

    made = []

    class Recorded(runner.Sandbox):
        def __init__(self, *args, **options):
            made.append(self)
            super().__init__(*args, **options)

    monkeypatch.setattr(runner, "Sandbox", Recorded)
    result = grade(SKELETON, ["lab07"], pictures="none", limits=LIMITS)
    assert any(c.hidden for e in result.exercises for c in e.checks)
    assert len(made) == 1      # the public lane's worker only


def test_what_a_hidden_check_named_never_changes_a_public_checks_words():
    """The error model's name on a public check is taken back only by a public check's own
    hand-written name: a hidden check's name (known only after release) must leave it as it is."""
    from autograder.engine.mutants.naming import APPENDED
    from autograder.engine.results import CheckResult, FAILED
    from autograder.engine.runner import _defer_to_hand_written

    def exercise():
        public = CheckResult("public", 0.0, 2.0, FAILED, f"f(1) is wrong. {APPENDED}in `f`, a sign is flipped.",
                             mistake="mutant:flip_sign")
        hidden = CheckResult("hidden", 0.0, 2.0, FAILED, "f(7) is wrong: it looks like the angle is in radians.",
                             hidden=True, mistake="the angle is used as radians")
        hidden_model = CheckResult("hidden 2", 0.0, 2.0, FAILED, f"f(3) is wrong. {APPENDED}in `f`, a sign is flipped.",
                                   hidden=True, mistake="mutant:flip_sign")
        return [public, hidden, hidden_model]

    checks = exercise()
    _defer_to_hand_written(checks)
    public, _, hidden_model = checks
    assert APPENDED in public.message and public.mistake == "mutant:flip_sign"     # untouched
    assert APPENDED not in hidden_model.message and hidden_model.mistake == ""    # hidden defers to all

    checks = exercise()
    checks[1].hidden = False   # the same hand-written name on a public check takes the public name back
    _defer_to_hand_written(checks)
    assert APPENDED not in checks[0].message
