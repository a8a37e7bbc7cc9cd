"""Shared helpers for the grader's own tests.

The pattern every lab follows (see ``test_lab07.py``):

- the reference solutions score full marks, the skeletons score 0 with
  "not implemented yet" messages;
- for each exercise, a realistic wrong implementation -- the reference module
  with one function redefined (:func:`mutant`) -- loses points with the right
  diagnosis.

What "sound" means is ``autograder verify``'s (:mod:`autograder.instructor.verify`): the
helpers below assert its judgements, and :class:`SharedGradings` lets verify reuse the
gradings these tests make (tests/test_verify.py).
"""

from __future__ import annotations

import atexit
import fcntl
import hashlib
import json
import os
import re
import shutil
import tempfile
import textwrap
import uuid
from pathlib import Path

import pytest
from hypothesis import settings

from autograder.engine.properties import GRADING
from autograder.engine.results import GradingResult, write_atomically
from autograder.engine.runner import grade
from autograder.instructor import verify
from naming_switch import turn_naming_off

settings.load_profile(GRADING)

# Every temporary folder of this test run -- the tests' own, and those of the graders, batches and
# sandboxes they start, which inherit TMPDIR -- lies in one folder removed at the end: a process the
# tests kill on purpose (SIGKILL leaves no clean-up) leaks nothing into the system's /tmp. Mode 711:
# the sandbox's unprivileged worker must pass through it to reach its own folder.
if "AUTOGRADER_TEST_TMPDIR" not in os.environ:
    os.environ["AUTOGRADER_TEST_TMPDIR"] = tempfile.mkdtemp(prefix="autograder-tests-")
    os.chmod(os.environ["AUTOGRADER_TEST_TMPDIR"], 0o711)
    atexit.register(shutil.rmtree, os.environ["AUTOGRADER_TEST_TMPDIR"], ignore_errors=True)
os.environ["TMPDIR"] = tempfile.tempdir = os.environ["AUTOGRADER_TEST_TMPDIR"]

# The grader's store of ground truth and recorded examples (autograder/sandbox/cache.py) is a
# folder of this test run, shared by its workers and removed at the end: the suite
# writes nothing outside temporary folders.
if "AUTOGRADER_CACHE_DIR" not in os.environ:
    os.environ["AUTOGRADER_CACHE_DIR"] = tempfile.mkdtemp(prefix="autograder-test-store-")
    atexit.register(shutil.rmtree, os.environ["AUTOGRADER_CACHE_DIR"], ignore_errors=True)

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / "reference_solutions"
SKELETON = ROOT / "assignments"


def mutant(tmp_path: Path, module: str, source: str, base: Path = REFERENCE) -> Path:
    """A submission: ``base``'s module with ``source`` appended (its ``def``s win).

    Functions of the module that call a redefined function use the new one,
    just as they would in a student's file.
    """
    folder = tmp_path / "submission"
    folder.mkdir(parents=True, exist_ok=True)
    original = (base / f"{module}.py").read_text()
    (folder / f"{module}.py").write_text(verify.with_mutation(original, source))
    return folder


def edited_reference(tmp_path: Path, module: str, *edits: tuple[str, str]) -> Path:
    """A submission: the reference ``module`` with each ``(old, new)`` text edit made (``old``
    found exactly once), as a student changes a line of a working solution."""
    source = (REFERENCE / f"{module}.py").read_text()
    for old, new in edits:
        assert source.count(old) == 1, old
        source = source.replace(old, new)
    folder = tmp_path / "submission"
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{module}.py").write_text(source)
    return folder


def submission_from_source(tmp_path: Path, module: str, source: str) -> Path:
    """A submission whose module is exactly ``source``."""
    folder = tmp_path / "submission"
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{module}.py").write_text(textwrap.dedent(source))
    return folder


def check_results(result, exercise_id: str):
    [exercise] = [e for e in result.exercises if e.id == exercise_id]
    return exercise.checks


def failing_messages(folder, exercise_id: str, public_only: bool = True, startswith: str = "") -> list[str]:
    """The messages of ``exercise_id``'s checks that lost points when ``folder`` is graded on that
    exercise (its public checks only, unless asked; those whose name starts with ``startswith``)."""
    from autograder.engine.runner import grade

    result = grade(str(folder), [exercise_id], include_hidden=not public_only)
    return [c.message for c in check_results(result, exercise_id)
            if c.score < c.max_score and c.name.startswith(startswith)]


def assert_diagnosed(result, exercise_id: str, *fragments: str):
    """The exercise lost points, one failure message contains every fragment, and no check
    names another mistake (:func:`autograder.instructor.verify.case_problems`)."""
    check_results(result, exercise_id)
    problems = verify.case_problems(result, verify.Case("", exercise_id, "", fragments))
    assert not problems, f"{exercise_id}: " + "\n".join(problems)


named_mistakes = verify.named_mistakes   # (label, message) of each failing check naming a mistake


def lab_exercises(result, lab: str):
    """The graded exercises of ``lab`` (``"lab08"``); there must be some."""
    exercises = [e for e in result.exercises if e.id.startswith(lab + ".")]
    assert exercises, f"no exercise of {lab} was graded"
    return exercises


def assert_full_marks(result, lab: str):
    """Every check of every exercise of ``lab`` passed (:func:`verify.reference_problems`)."""
    lab_exercises(result, lab)
    problems = verify.reference_problems(result, lab)
    assert not problems, "\n".join(problems)


def advice_given(result, exercise_id: str) -> list[str]:
    """The tips (0-point advice) an exercise's report gives, lower-cased."""
    return [c.message.lower() for c in check_results(result, exercise_id) if c.advice]


def assert_advised(result, exercise_id: str, *fragments: str):
    """One tip of the exercise contains every fragment."""
    tips = advice_given(result, exercise_id)
    assert any(all(f.lower() in tip for f in fragments) for tip in tips), \
        f"{exercise_id}: no tip mentions {fragments}; tips were:\n" + "\n".join(tips)


def assert_advice_case(module: str, exercise: str, source: str, fragments):
    """A convention (a lab's ``ADVICE`` case): its tip given, no point lost (verify's judgement)."""
    result = graded_case(module, exercise, source)
    problems = verify.case_problems(result, verify.Case("", exercise, source, tuple(fragments), advice=True))
    assert not problems, f"{exercise}: " + "\n".join(problems)


def assert_all_not_implemented(result, lab: str):
    """Every exercise of ``lab`` scores 0 with "not implemented yet" and no traceback noise
    (:func:`verify.skeleton_problems`)."""
    lab_exercises(result, lab)
    problems = verify.skeleton_problems(result, lab)
    assert not problems, "\n".join(problems)


_GRADED_CASES: dict = {}


def graded_case(module: str, exercise: str, source: str, base: Path = REFERENCE):
    """``base``'s module with ``source`` appended, graded on ``exercise`` (no pictures), once per
    test process: a lab's mistake table is graded case by case by its own tests and, whole,
    by ``autograder verify`` in tests/test_verify.py; both carry the lab's ``xdist_group``, so
    each case is graded once per run."""
    key = (module, exercise, source, base)
    if key not in _GRADED_CASES:
        from autograder.engine.mutants import naming, repair

        folder = Path(tempfile.mkdtemp(prefix="mistake-case-"))
        # The tables test the checks' own names of their mistakes; a repair told beside such a name
        # (repair.BESIDE_NAMES) only adds to it, and has tests of its own (tests/test_repair.py):
        # searched here too, it would add seconds to each of hundreds of cases.
        beside, repair.BESIDE_NAMES = repair.BESIDE_NAMES, False
        # Naming's budget is CPU seconds, bounded in wall-clock time at WALL_SLACK times it for a busy machine:
        # two test processes on two cores beside their sandboxes and helpers pass that bound, and a table's
        # name then depended on the machine's load (CI's DP ramp case). The tables test what the budget of CPU
        # time names: the wall-clock bound is widened here, the budget is as graded.
        slack, naming.WALL_SLACK = naming.WALL_SLACK, 4 * naming.WALL_SLACK
        try:
            _GRADED_CASES[key] = grade(mutant(folder, module, source, base), [exercise], pictures="none")
        finally:
            repair.BESIDE_NAMES, naming.WALL_SLACK = beside, slack
            shutil.rmtree(folder, ignore_errors=True)
    return _GRADED_CASES[key]


_WHOLE_GRADINGS: dict = {}

# The whole gradings every test process needs (the reference's takes ~40 s) are made once per
# run: the first process to ask grades under a file lock and leaves the result as JSON in a
# folder the run's processes share (made here by the first process, inherited by xdist's
# workers through the environment, removed at the end); the others read it.
if "AUTOGRADER_TEST_GRADINGS_DIR" not in os.environ:
    os.environ["AUTOGRADER_TEST_GRADINGS_DIR"] = tempfile.mkdtemp(prefix="autograder-test-gradings-")
    atexit.register(shutil.rmtree, os.environ["AUTOGRADER_TEST_GRADINGS_DIR"], ignore_errors=True)


def _code_digest(folder: Path) -> str:
    """What a grading of ``folder`` depends on: the grader's code and ``folder``'s files (the
    tree may change during a run; a changed one is graded again, not read)."""
    digest = hashlib.sha256(str(folder).encode())
    for root in (ROOT / "autograder", folder):
        for path in sorted(root.rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts:
                digest.update(str(path.relative_to(root)).encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:32]


def whole_grading(folder: Path):
    """Every lab of ``folder`` (the reference solutions, the skeletons) graded once per run,
    shared by its processes (a ``GradingResult`` through ``to_dict``/``from_dict``, which keep
    every field)."""
    if folder not in _WHOLE_GRADINGS:
        shared = Path(os.environ["AUTOGRADER_TEST_GRADINGS_DIR"]) / f"{_code_digest(folder)}.json"
        with open(shared.with_suffix(".lock"), "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)   # the other processes wait for the one grading
            if shared.exists():
                result = GradingResult.from_dict(json.loads(shared.read_text()))
            else:
                result = grade(folder)
                write_atomically(shared, json.dumps(result.to_dict()))
        _WHOLE_GRADINGS[folder] = result
    return _WHOLE_GRADINGS[folder]


class SharedGradings(verify.Gradings):
    """verify's gradings, shared with the other tests of this process: the reference and the
    skeletons graded whole once (the session fixtures' gradings), each case once
    (:func:`graded_case`); the reference's second grading, which verify compares with the
    first, is its own."""

    def reference(self, parts, run=0):
        return whole_grading(parts.reference) if run == 0 else super().reference(parts, run)

    def skeleton(self, parts):
        return whole_grading(parts.skeleton)

    def case(self, parts, case):
        return graded_case(parts.lab.module, case.exercise, case.source, parts.reference)


def assert_mistake_named(module: str, exercise: str, source: str, fragments):
    """The reference with ``source`` appended loses points on ``exercise``, named by ``fragments``."""
    result = graded_case(module, exercise, source)
    assert_diagnosed(result, exercise, *fragments)
    return result


def told_or_pointed(check, checks, change: str) -> bool:
    """Whether ``check``'s message tells ``change``, or points to the check among ``checks`` that told it beside
    the same mistake (a later check of a function whose change was told: not searched again)."""
    if change in check.message:
        return True
    pointed = re.search(r'The same mistake is named at the check "(.+?)", with the change', check.message)
    return pointed is not None and any(c.name == pointed.group(1) and change in c.message and c.mistake == check.mistake
                                       for c in checks)


def assert_only_exercise_lost(result, lost: str, *fragments: str):
    """Exercise ``lost`` scores 0 with every fragment in its messages; all others full marks."""
    for exercise in result.exercises:
        if exercise.id == lost:
            assert exercise.score == 0, exercise.id
            messages = " ".join([exercise.message] + [c.message for c in exercise.checks])
            for fragment in fragments:
                assert fragment in messages, messages
        else:
            assert exercise.score == exercise.max_score, (exercise.id, exercise.checks)


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config, items):
    """Tests that share work run in one process (``--dist loadgroup``, README's command):

    - the tests of a module that use one of its module-scoped fixtures (a class batch-graded
      once, a whole submission graded with pictures) share an ``xdist_group`` named after the
      module, so the fixture is made once, not once in each process (loadgroup spreads
      ungrouped tests one by one); a test already in a group (a lab's) keeps its own;
    - in an xdist worker, each grouped test's id ends in ``@group``, which is how xdist's
      scheduler finds the groups. xdist 3.8 writes that suffix into ``item._nodeid``, which
      pytest 9 no longer reads (``Item.nodeid`` is ``str(item._id)``): without this, no group
      held (a lab's mistake cases were graded again by tests/test_verify.py in the other
      process, each module fixture made twice).
    """
    for item in items:
        module = getattr(item, "module", None)
        info = getattr(item, "_fixtureinfo", None)
        if module is None or info is None or item.get_closest_marker("xdist_group"):
            continue
        if any(definitions[-1].scope in ("module", "class") for definitions in info.name2fixturedefs.values()):
            item.add_marker(pytest.mark.xdist_group(module.__name__))
    if getattr(config, "workerinput", None) is None or not config.getvalue("loadgroup"):
        return
    try:
        from _pytest.nodeid import NodeId
    except ImportError:   # pytest 8 and before read item._nodeid, where xdist writes the suffix
        return
    for item in items:
        names = sorted({str(mark.args[0] if mark.args else mark.kwargs.get("name", "default"))
                        for mark in item.iter_markers("xdist_group")})
        suffix = "@" + "_".join(names)
        if names and hasattr(item, "_id") and not item.nodeid.endswith(suffix):
            item._id = NodeId.parse(item.nodeid + suffix)


@pytest.fixture(scope="session")
def reference_result():
    """The reference solutions graded once for the whole test session (all labs)."""
    return whole_grading(REFERENCE)


@pytest.fixture(scope="session")
def skeleton_result():
    return whole_grading(SKELETON)


@pytest.fixture
def no_naming(monkeypatch):
    """Gradings in this process (not in a ``grade.py`` subprocess) name no mistake by the error
    model or by repairs and decide no failure inherited: each spends up to seconds per failed
    check and per worker (``naming.GRADING_SECONDS``, ``inherited.GRADING_SECONDS``), which a test
    of what failing costs elsewhere -- pictures, statuses, scores -- does not need. Only for tests
    that assert nothing those diagnoses write (tests/test_error_model.py and the labs' mistake
    tables test them). A ``grade.py`` subprocess: ``naming_switch.pythonpath_without_naming``."""
    turn_naming_off(monkeypatch.setattr)


# ------------------------------------------------------------------ hostile submissions
def marker() -> str:
    """A process name (15 chars max) that survivors of an attack would carry."""
    return "agh" + uuid.uuid4().hex[:12]


def processes_named(name: str, settle: float = 2.0) -> list[int]:
    """Live processes on this machine whose name is ``name`` (survivors of an attack).

    A killed process is a zombie until someone reaps it, and hundreds take a moment to be
    killed: zombies hold nothing (where the machine's init does not reap orphans they stay),
    so they are no survivors; the others get ``settle`` seconds to finish dying. Survivors
    of the attacks here live for seconds, so they are still found."""
    import time

    deadline = time.monotonic() + settle
    while True:
        found = []
        for entry in os.listdir("/proc"):
            if entry.isdigit():
                try:
                    with open(f"/proc/{entry}/comm") as f:
                        if f.read().strip() != name:
                            continue
                    with open(f"/proc/{entry}/stat") as f:
                        state = f.read().rsplit(")", 1)[1].split()[0]
                except (OSError, IndexError):
                    continue
                if state not in ("Z", "X"):
                    found.append(int(entry))
        if not found or time.monotonic() > deadline:
            return found
        time.sleep(0.1)


# Source a hostile submission starts with, to give its processes a findable name.
NAME_PROCESS = """
        import ctypes
        def _name_this_process(name):
            ctypes.CDLL(None).prctl(15, name.encode(), 0, 0, 0)   # PR_SET_NAME
        """


# Linear triangulation with all three rows of x × (P X) = 0 per view (the lab
# sheet's words), rows not scaled: a textbook variant labs 11 and 12 must accept.
THREE_ROW_TRIANGULATION = """
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.atleast_2d(np.asarray(pts1, float)); pts2 = np.atleast_2d(np.asarray(pts2, float))
            X = []
            for (x1, y1), (x2, y2) in zip(pts1, pts2):
                A = np.array([x1 * P1[2] - P1[0], y1 * P1[2] - P1[1], y1 * P1[0] - x1 * P1[1],
                              x2 * P2[2] - P2[0], y2 * P2[2] - P2[1], y2 * P2[0] - x2 * P2[1]])
                h = np.linalg.svd(A)[2][-1]
                X.append(h[:3] / h[3])
            return np.array(X)
        """
