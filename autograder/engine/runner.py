"""Grading a submission: discovery, execution and scoring, kept apart from reporting.

:func:`grade` selects exercises from the registry, loads the submission, starts
one sandboxed worker, runs every check in the grader's process and returns a
:class:`~autograder.engine.results.GradingResult`. It never raises because of the
submission; a failure inside a check is recorded as a grader error for that check.

Student time is budgeted per exercise (``Limits.exercise_budget``, the seconds billed
to its calls), and the whole grading has a wall-clock deadline (``Limits.budget_for`` the
exercises selected -- a lab's share each, at most ``Limits.submission_budget`` -- after it
began, whatever runs meanwhile: calls, restarts, other lanes, the grader's own judging; a
call running then is stopped at it): once either is spent, the checks left
are marked "time budget exhausted" (0 points) without calling anything, and the results
are still complete.

An exercise whose functions are all stubs (bodies that only raise
``NotImplementedError``, see :mod:`autograder.engine.stubs`) costs almost nothing: a check
that can only call one of them gets that function's "not implemented yet" without
running, so no ground truth or pictures are built for it.
"""

from __future__ import annotations

import contextlib
import copy
import logging
import os
import re
import threading
import time
import traceback
from dataclasses import replace
from datetime import datetime, timezone
from concurrent.futures import FIRST_EXCEPTION, ThreadPoolExecutor, wait
from typing import Callable, Sequence

import numpy as np

from .. import __version__
from ..loading.notebooks import point_into_notebook
from ..loading.parsing import PARSE_LOCK
from ..loading.reading import Reading, findings_for, read_file
from ..loading.submission import load_submission
from ..sandbox import cache, confine
from ..sandbox.supervisor import CallOutcome, Limits, Sandbox
from .bounded import Runaway, bounded
from .checks import Fail, StudentFailure, Trial, Verdict
from .claims import measured, rewritten, without_guessed_cause
from .claims import said as said_for_the_code
from .forms import exception_form
from .inputs import Inputs
from .registry import Check, Exercise, discover, hidden_checks_installed, select
from .results import (ADVICE, ERROR, FAILED, NOT_IMPLEMENTED, PARTIAL, PASSED, CheckResult,
                      ExerciseResult, GradingResult)
from .stubs import functions_called, stub_functions
from .version_differences import with_version_note
from .versions import judged_with


PICTURES = ("all", "failed", "none")


def grade(submission_path, selectors=(), *, limits: Limits | None = None,
          include_hidden: bool = True, pictures: str = "all",
          on_check: Callable[[Exercise, CheckResult], None] | None = None,
          forbid: dict[str, list[str]] | None = None, lanes: int = 1,
          sandboxes: Sequence[Sandbox] = (), inputs_secret: str | None = None,
          refuse_weaker: bool = False, rerun: tuple[str, str] | None = None) -> GradingResult:
    """Grade the submission at ``submission_path``.

    Parameters
    ----------
    submission_path : path
        Folder, ``.py``, ``.zip`` or ``.ipynb`` (see :mod:`autograder.loading.submission`).
    selectors : list of str
        ``lab07`` or ``lab07.ex2`` style names; all exercises when empty.
    limits : Limits, optional
        Sandbox limits.
    include_hidden : bool
        Run hidden checks (the instructor's copy and the container do).
    pictures : {"all", "failed", "none"}
        Which checks keep their pictures (encoding them costs time; keep them
        only where someone will look).
    on_check : callable, optional
        Called after every check, e.g. to advance a progress bar (from the lanes'
        threads when there are several).
    forbid : dict, optional
        The instructor's extra rules (course configuration ``forbid``):
        ``{"lab08.homography_ransac": ["cv2.findHomography"]}``.
    lanes : int
        How many labs are graded at once, each lane with a worker of its own.
        Labs are separate modules of the submission, so while one lane waits for the
        student's code another judges: on two cores, two lanes grade a whole
        submission in about two thirds of the time. Each lab is graded whole in one
        lane, its exercises in order; the labs with the most checks are started
        first. A batch grades several submissions at once instead (one lane each).
    sandboxes : sequence of Sandbox, optional
        Sandboxes made without a submission, perhaps already started
        (:meth:`Sandbox.start`, so the workers boot while the caller loads), one per
        lane (lanes without one get their own), with ``limits.shared_by(lanes)``
        (each lane's worker a fixed share of the submission's memory): the submission is
        admitted into each, and all are closed at the end, whatever happens.
    inputs_secret : str, optional
        The course's secret, from which with the submission's content its property
        checks draw their inputs (:class:`~autograder.engine.inputs.Inputs`); None:
        ``$AUTOGRADER_INPUTS_SECRET``, else the content alone.
    refuse_weaker : bool
        Raise :class:`~autograder.sandbox.confine.WeakerConfinement` rather than run student
        code less confined than this machine allows (Gradescope, a batch). Otherwise
        the result says so (``confinement_warning``) and the log warns.

    The result names the confinement level the student code ran at (``confinement``).

    rerun : (str, str), optional
        How the student grades these files again, the text before and after an
        exercise's id (``("python grade.py --submission lab7.py ", "")``): property
        failures say it (:attr:`Inputs.rerun`; default ``python grade.py <id>``).

    Raises
    ------
    SelectionError, SubmissionError
        For a selector that names nothing, or a path that is not a submission.
    WeakerConfinement
        With ``refuse_weaker``, before any student code runs.
    """
    with contextlib.ExitStack() as closing:
        for sandbox in sandboxes:
            closing.enter_context(sandbox)
        return _grade(submission_path, selectors, limits, include_hidden, pictures, on_check, forbid,
                      lanes, list(sandboxes), closing, inputs_secret, refuse_weaker, rerun)


def _grade(submission_path, selectors, limits, include_hidden, pictures, on_check, forbid,
           lanes, sandboxes, closing, inputs_secret=None, refuse_weaker=False, rerun=None):
    if pictures not in PICTURES:
        raise ValueError(f"pictures must be one of {PICTURES}, got {pictures!r}")
    started = time.perf_counter()
    exercises = select(selectors, include_hidden)
    seconds = (limits or Limits()).budget_for(exercises)  # the deadline scales with what is graded
    deadline = time.monotonic() + seconds
    modules = sorted({ex.lab.module for ex in exercises})
    every_module = {lab.module for lab in discover().values()}  # a lone file is never another lab's
    with load_submission(submission_path, modules, every_module=every_module) as submission:
        result = GradingResult(submission.name, submission.content_hash, __version__,
                               hidden_included=include_hidden and hidden_checks_installed(),
                               notes=_reading_notes(submission),
                               files_not_graded=[f.to_dict() for files in submission.not_graded.values() for f in files],
                               versions=judged_with(),  # the worker runs this interpreter
                               graded_at=datetime.now(timezone.utc).isoformat(timespec="seconds"))
        labs = _labs_heaviest_first(exercises)
        inputs = Inputs.for_submission(submission.content_hash, inputs_secret)
        if rerun is not None:
            inputs = replace(inputs, rerun=tuple(rerun))
        for sandbox in sandboxes:
            sandbox.admit(submission.path)
        # A lab of stubs only costs next to nothing: it needs no lane of its own.
        with_work = [lab for lab in labs if not all(_stubs(exercise, submission) for exercise in lab)]
        lane_limits = (limits or Limits()).shared_by(max(1, lanes))
        if not sandboxes or not sandboxes[0].ready():  # none given, or its level does not work here
            sandboxes[:1] = [closing.enter_context(_first_sandbox(submission.path, lane_limits, sandboxes[:1]))]
        _confinement_of(sandboxes[0], result, refuse_weaker)  # the worker is ready: no student code ran yet
        while len(sandboxes) < min(max(1, lanes), len(with_work)):
            sandboxes.append(closing.enter_context(
                Sandbox(submission.path, lane_limits, confinement=sandboxes[0].confinement)))
            sandboxes[-1].start()  # it boots while the first lane grades
        sandboxes = sandboxes[:max(1, min(lanes, len(labs)))]
        public = _phase(labs, hidden=False)
        hidden = _phase(labs, hidden=True) if include_hidden else []
        # Hidden checks run after every public check, in workers of their own: nothing the
        # student's code keeps (in memory, in its scratch folder) while it serves a hidden
        # check can reach a public check's messages, and the public phase never sees a hidden
        # input. The fresh workers boot while the public checks run.
        # A hidden check that only meets a stub calls nothing (its verdict is known without a
        # call): labs whose hidden checks are all such need no fresh worker, and none gives any
        # hidden input to the student's code, so they are graded in the public phase's workers.
        hidden_calls = [lab for lab in hidden if any(not _only_stub_called(check, _stubs(exercise, submission))
                                                     for exercise, checks in lab for check in checks)]
        fresh = [closing.enter_context(Sandbox(submission.path, lane_limits, confinement=sandboxes[0].confinement))
                 for _ in range(min(len(sandboxes), len(hidden_calls)))]
        for sandbox in fresh:
            sandbox.start()
        _one_naming_time(sandboxes + fresh)
        graded: dict[str, ExerciseResult] = {}
        graded_hidden: dict[str, ExerciseResult] = {}

        stopping = threading.Event()  # set when grading ends early (an interrupt, a grader bug)

        # The public phase may not spend the hidden phase's share of the deadline (its checks'
        # share of all): a slow exercise then cannot starve another exercise's hidden checks.
        public_deadline = deadline - seconds * _hidden_share(public, hidden_calls)

        def lane(sandbox: Sandbox, work: list, into: dict, spent: dict | None = None, until: float = deadline):
            budget = _Budget(sandbox, until, seconds)
            while work and not stopping.is_set():
                try:
                    lab = work.pop(0)  # atomic: each lab goes to one lane
                except IndexError:
                    return
                for exercise, checks in lab:
                    if stopping.is_set():
                        return
                    budget.start_exercise(already_spent=(spent or {}).get(exercise.id, 0.0))
                    rules = _rules_for(exercise, forbid or {})
                    into[exercise.id] = _grade_exercise(
                        sandbox, exercise, checks, pictures, on_check, submission, budget, rules, painter,
                        inputs)

        def run_lanes(lane_sandboxes: list, work: list, into: dict, spent: dict | None = None,
                      until: float = deadline):
            if len(lane_sandboxes) == 1:
                lane(lane_sandboxes[0], work, into, spent, until)
                return
            with ThreadPoolExecutor(len(lane_sandboxes), thread_name_prefix="lane") as pool:
                lanes_running = [pool.submit(lane, sandbox, work, into, spent, until) for sandbox in lane_sandboxes]
                try:   # (the first lane to fail, whichever it is: waiting on them in order would let the
                    # others run their labs out first)
                    done, _ = wait(lanes_running, return_when=FIRST_EXCEPTION)
                    for finished in sorted(lanes_running, key=lambda future: future not in done):
                        finished.result()
                except BaseException:  # Ctrl-C included: the other lanes stop too, at once
                    stopping.set()
                    for sandbox in (*lane_sandboxes, *fresh):
                        sandbox.interrupt()
                    raise

        # Ground truth is kept between gradings only where the worker cannot write it.
        with cache.enabled(sandboxes[0].confinement.hides_files), Painter() as painter:
            run_lanes(sandboxes, public, graded, until=public_deadline)
            if hidden and not fresh:   # no hidden check calls the student's code
                run_lanes(sandboxes, hidden, graded_hidden)
            elif hidden:
                _public_memory_to(fresh, sandboxes)
                for sandbox in sandboxes:  # the public phase's workers are done: free their memory
                    sandbox.close()
                spent = {exercise_id: sum(c.student_seconds for c in done.checks)
                         for exercise_id, done in graded.items()}
                for sandbox in fresh:   # what timed out or blew its memory there is not called again
                    for done in sandboxes:
                        sandbox.remember_strikes(done)
                run_lanes(fresh, hidden, graded_hidden, spent)
                sandboxes = sandboxes + fresh
            painter.finish()
        for exercise_id, hidden_part in graded_hidden.items():
            _merge_hidden(graded[exercise_id], hidden_part, _check_order(exercise_id, exercises))
        result.exercises = [graded[exercise.id] for exercise in exercises]
        for graded_exercise in result.exercises:   # public and hidden checks together
            _defer_to_hand_written(graded_exercise.checks)
            _take_back_refuted(graded_exercise.checks, sandboxes)
        _hints_beside_a_name(list(zip(exercises, result.exercises)))
        result.student_seconds = round(sum(sandbox.student_seconds for sandbox in sandboxes), 6)
        result.student_wall_seconds = round(_covered([span for s in sandboxes for span in s.billed_spans]), 6)
        _point_into_notebooks(result, exercises, submission)
        result.notes += _not_read_notes(exercises, submission)
    result.seconds = round(time.perf_counter() - started, 6)
    return result


def _phase(labs: list[list[Exercise]], hidden: bool) -> list[list[tuple[Exercise, list[Check]]]]:
    """The labs' public (or hidden) checks, lab by lab: ``[[(exercise, checks), ...], ...]``.
    Every exercise has its public part, even without checks (its result must exist); only
    labs with hidden checks have a hidden part."""
    phase = [[(exercise, [c for c in exercise.checks if c.hidden == hidden]) for exercise in lab]
             for lab in labs]
    if hidden:
        phase = [[(exercise, checks) for exercise, checks in lab if checks] for lab in phase]
    return [lab for lab in phase if lab]


def _hidden_share(public: list, hidden: list) -> float:
    """The share of the deadline kept for the hidden checks: theirs of the checks to run, at
    least a quarter (their fresh workers import the student's module again; 0 without hidden checks)."""
    count = lambda phase: sum(len(checks) for lab in phase for _, checks in lab)
    total = count(public) + count(hidden)
    return max(count(hidden) / total, 0.25) if total and count(hidden) else 0.0


def _check_order(exercise_id: str, exercises: list[Exercise]) -> dict[str, int]:
    exercise = next(ex for ex in exercises if ex.id == exercise_id)
    return {check.name: index for index, check in enumerate(exercise.checks)}


def _merge_hidden(public: ExerciseResult, hidden: ExerciseResult, order: dict[str, int]) -> None:
    """Put an exercise's hidden results among its public ones, in the suite's order (the
    engine's own advice last). Everything the hidden phase said is marked hidden: its
    in-place advice included, which students see only with the hidden checks."""
    for check in hidden.checks:
        check.hidden = True
    public.checks = sorted(public.checks + hidden.checks, key=lambda c: order.get(c.name, len(order)))
    graded = [c for c in public.checks if c.max_score > 0]
    if graded and all(c.status == NOT_IMPLEMENTED for c in graded):
        public.message = public.message or hidden.message
    elif public.message == "not implemented yet":
        public.message = ""  # only the public checks were stubs' (an exercise of hidden checks only)


def _first_sandbox(submission_dir, limits, tried=()) -> Sandbox:
    """A sandbox at the strongest confinement level that works here: a worker that gets
    ready at the strongest level shows that it works (what :func:`confine.detect` would
    probe with a process of its own, once per process); else the level the probe finds.
    ``tried``: a sandbox whose worker did not get ready (closed here)."""
    for failed in tried:
        failed.close()
    if not tried:
        sandbox = Sandbox(submission_dir, limits, confinement=confine.strongest_candidate())
        if sandbox.ready():
            return sandbox
        sandbox.close()
    return Sandbox(submission_dir, limits)


def _confinement_of(sandbox: Sandbox, result: GradingResult, refuse_weaker: bool) -> None:
    """Record the level ``sandbox`` confines at; a level weaker than this machine allows is
    refused (``refuse_weaker``) or said loudly: in the result, and in the log."""
    result.confinement = sandbox.confinement.level
    result.confinement_warning = confine.shortfall(sandbox.confinement)
    if result.confinement_warning and refuse_weaker:
        raise confine.WeakerConfinement(result.confinement_warning)
    if result.confinement_warning:
        logging.getLogger("autograder").warning("%s", result.confinement_warning)


def _covered(spans: list[tuple[float, float]]) -> float:
    """The length of the union of the ``(start, end)`` spans."""
    covered, reached = 0.0, float("-inf")
    for start, end in sorted(spans):
        if end > reached:
            covered += end - max(start, reached)
            reached = end
    return covered


def _labs_heaviest_first(exercises: list[Exercise]) -> list[list[Exercise]]:
    """The exercises grouped by lab (in their order), the labs with the most checks first:
    the order in which lanes take them (the longest first, so that lanes end together)."""
    labs: dict[str, list[Exercise]] = {}
    for exercise in exercises:
        labs.setdefault(exercise.lab.key, []).append(exercise)
    return sorted(labs.values(), key=lambda lab: -sum(len(exercise.checks) for exercise in lab))


class _Budget:
    """A lane's time: each exercise's budget of billed student seconds, and the submission's
    wall-clock deadline (``time.monotonic()``), the same for every lane."""

    def __init__(self, sandbox: Sandbox, deadline: float, seconds: float):
        self.sandbox, self.deadline, self.seconds = sandbox, deadline, seconds
        self.limits = sandbox.limits
        sandbox.set_deadline(deadline)  # within a check too: a call running then is stopped at it

    def start_exercise(self, already_spent: float = 0.0):
        """A new exercise (or its hidden checks, which get what its public checks left)."""
        self.sandbox.start_exercise(self.sandbox.student_seconds + self.limits.exercise_budget - already_spent)

    def exhausted(self) -> str:
        """Which budget is spent ("" while there is time left)."""
        if time.monotonic() >= self.deadline:
            return f"time budget exhausted (the submission's {self.seconds:g} s)"
        if self.sandbox.remaining() <= 0:
            return f"time budget exhausted (this exercise's {self.limits.exercise_budget:g} s)"
        return ""


def _rules_for(exercise: Exercise, forbid: dict) -> dict[str, tuple[str, ...]]:
    """The instructor's forbids that concern this exercise's functions."""
    return {function: tuple(forbid[f"{exercise.lab.key}.{function}"]) for function in exercise.signatures
            if f"{exercise.lab.key}.{function}" in forbid}


def _grade_exercise(sandbox, exercise, checks, pictures, on_check, submission=None,
                    budget=None, rules=None, painter=None, inputs=None) -> ExerciseResult:
    functions = list(exercise.signatures.values())
    rules = rules or {}
    out = ExerciseResult(exercise.id, exercise.title, functions, rules=[
        f"{function}() may not call {', '.join(names)} (your instructor's rule for this course)"
        for function, names in rules.items()])
    imported = _import(sandbox, exercise.lab.module, submission)
    refusal = submission.refusal_for(exercise.lab.module) if submission is not None else ""
    if not imported.ok:
        # A missing or broken module: every check scores 0 with the same message.
        message = imported.message
        if imported.kind == "missing_module" and refusal:
            message = refusal
        elif imported.kind == "budget" and budget is not None:
            message = budget.exhausted() or message
        out.message = message
        for check in checks:
            status = ERROR if imported.kind == "grader_error" else FAILED
            out.checks.append(CheckResult(check.name, 0.0, check.points, status,
                                          message, hidden=check.hidden, failure=imported.kind,
                                          traceback=imported.traceback, output=imported.output))
            if on_check:
                on_check(exercise, out.checks[-1])
        return out
    modified: list[tuple[str, str]] = []  # (function, argument) changed in place
    stubs = _stubs(exercise, submission)
    reading = _reading(exercise, submission)
    for check in checks:
        spent = budget.exhausted() if budget is not None else ""
        stub = _only_stub_called(check, stubs)
        if spent:
            out.checks.append(CheckResult(check.name, 0.0, check.points, FAILED, spent,
                                          hidden=check.hidden, failure="budget"))
        elif stub:
            out.checks.append(_not_implemented(check, stub))
        else:
            out.checks.append(run_check(sandbox, check, pictures, modified, rules, painter, inputs, reading))
        if on_check:
            on_check(exercise, out.checks[-1])
    _zero_constant(sandbox, exercise, out.checks)
    graded = [c for c in out.checks if c.max_score > 0]
    if graded and all(c.status == NOT_IMPLEMENTED for c in graded):
        out.message = "not implemented yet"
    if modified:
        out.checks.append(_in_place_advice(modified))
    unused = _unused_value_advice(sandbox, exercise, out.checks) if any(not c.hidden for c in checks) else None
    if unused is not None:   # (told once, in the public phase, from the public checks alone: what the hidden checks
        #                          found must not show in it before they are released)
        out.checks.append(unused)
    return out


UNUSED_VALUE_ADVICE = "every value computed is used"


def _unused_value_advice(sandbox, exercise: Exercise, results) -> CheckResult | None:
    """The engine's own advice where every public graded check of the exercise passed: a value one of its functions
    computes and never reads (sub-pixel corners refined, then the raw ones calibrated). The failing checks
    say it themselves (:func:`_named_by_unused_parameter`); here it costs nothing, and says what the checks
    could not tell (a step the sheet does not ask for, begun and not finished)."""
    from . import ignored
    from .hints import module_code

    graded = [r for r in results if r.max_score > 0 and not r.hidden]
    if not graded or any(r.score < r.max_score for r in graded):
        return None
    found = ignored.computed_unused(module_code(sandbox.submission_dir, exercise.lab.module), list(exercise.signatures))
    if found is None:
        return None
    return CheckResult(UNUSED_VALUE_ADVICE, 0.0, 0.0, ADVICE, ignored.unused_value_sentence(*found))


def _not_read_notes(exercises, submission) -> list[str]:
    """Why a module's code was not read (too large to parse in the grader's process): no
    failure is then explained from the code, and the student should know why."""
    notes, seen = [], set()
    for exercise in exercises:
        if exercise.lab.module in seen:
            continue
        seen.add(exercise.lab.module)
        reading = _reading(exercise, submission)
        if reading is not None and reading.note:
            notes.append(f"{exercise.lab.module}.py: {reading.note}")
    return notes


def _reading(exercise: Exercise, submission) -> Reading | None:
    """The reading of the submission's module (see :mod:`autograder.loading.reading`), if there is one."""
    if submission is None:
        return None
    api = frozenset(name for ex in exercise.lab.exercises.values() for name in ex.signatures)
    try:
        with bounded(own_work_bound()):
            return read_file(submission.path / f"{exercise.lab.module}.py", api)
    except Runaway as runaway:   # (the checks are judged without it: nothing is read in their code)
        _log_runaway(f"{exercise.lab.module}.py", "reading it", runaway)
        return None


def _named_by_exception(verdict: Verdict, trial: Trial, traceback_text: str) -> Verdict:
    """A failure whose exception NumPy raised for a wrong form (a per-row value kept flat, points
    not made homogeneous: :func:`autograder.engine.forms.exception_form`; a 1-D vector given by the
    caller joined to a 2-D array in the raising line: :func:`autograder.engine.raised.explained`),
    naming that form; the shapes in the error, and the line with the arguments given, are the evidence."""
    return _told_exception(verdict, exception_form(str(verdict.message)) or _explained_from_the_line(trial, traceback_text))


def _told_exception(verdict: Verdict, form) -> Verdict:
    """``verdict`` of an exception with the cause ``form`` told after its first line (None: as it was)."""
    if form is None:
        return verdict
    first, newline, rest = str(verdict.message).partition("\n")
    if " raised " in first:
        said = f"{first.rstrip().rstrip('.')}: {form.sentence}."   # (an error's own full stop before the colon dropped)
    else:   # the worker's sentence on the OpenCV call leads: this one follows it
        said = f"{first.rstrip().rstrip('.')}. {form.sentence[:1].upper()}{form.sentence[1:]}."
    return replace(verdict, message=f"{said}{newline}{rest}", mistake=form.mistake)


def _explained_from_the_line(trial: Trial, traceback_text: str):
    from . import raised
    from .hints import code_of

    if not getattr(trial, "raised", None):
        return None
    function, args, kwargs, message = trial.raised
    try:   # (reading is a bonus: code too deep to read, or read wrongly, says nothing)
        return raised.explained(code_of(trial), traceback_text, message, function, args, kwargs)
    except Exception as exc:  # noqa: BLE001 - the verdict stands without it
        _log_grader_error(trial.check, exc)
        return None


def _told_after_the_first_line(verdict: Verdict, said: str, mistake: str) -> Verdict:
    """``verdict`` with the sentence ``said`` after its message's first line (ended by a full stop where it
    has no end of its own), naming ``mistake``."""
    first, newline, rest = str(verdict.message).partition("\n")
    lead = first.rstrip()
    lead += "" if not lead or lead[-1] in ".:;!?" else "."
    return replace(verdict, message=f"{lead} {said[:1].upper()}{said[1:]}.{newline}{rest}", mistake=mistake)


def _calls_made(trial: Trial) -> list:
    """The check's calls of the student's functions, the one that raised last."""
    return list(trial.calls) + ([trial.raised] if getattr(trial, "raised", None) else [])


def _named_by_misread_output(verdict: Verdict, trial: Trial) -> Verdict:
    """A failing verdict that names no mistake, naming an OpenCV output the student's code unpacks
    under another output's name (``rms, dist, K, ... = cv2.calibrateCamera(...)``) when what a
    function the check called returns is made from it (:mod:`autograder.engine.outputs`)."""
    from . import outputs
    from .hints import code_of

    code = code_of(trial)
    for function in dict.fromkeys(call[0] for call in reversed(list(trial.calls) + list(getattr(trial, "served", ())))):
        found = outputs.told(code, function)
        if found is not None:
            sentence, mistake = found
            return _told_after_the_first_line(verdict, f"Reading your code: {sentence}", mistake)
    return verdict


def _named_against_the_reference(verdict: Verdict, trial: Trial, read, module) -> Verdict:
    """``verdict`` with what ``read(code, reference source)`` finds in the student's code told after its
    first line (``module``'s ``sentence`` and ``MISTAKE``); unchanged when nothing is found, without a
    reference, or when the reading fails (reading is a bonus: the verdict stands without it)."""
    from .hints import code_of
    from .mutants import naming

    model = naming.model_for(trial.lab)
    if model is None:
        return verdict
    try:
        found = read(code_of(trial), model.source)
    except Exception as exc:  # noqa: BLE001
        _log_grader_error(trial.check, exc)
        return verdict
    if found is None:
        return verdict
    return _told_after_the_first_line(verdict, module.sentence(*found), module.MISTAKE)


def _named_by_defaults(verdict: Verdict, trial: Trial) -> Verdict:
    """A failing verdict that names no mistake, naming a default the student's def gives a parameter
    other than the API's, where a call of the check left it out (:mod:`autograder.engine.defaults_given`)."""
    from . import defaults_given

    calls = _calls_made(trial)
    if not calls:
        return verdict
    return _named_against_the_reference(
        verdict, trial, lambda code, source: defaults_given.left_out(code, source, calls), defaults_given)


def _named_by_strings(verdict: Verdict, check: Check, trial: Trial) -> Verdict:
    """A failing verdict that names no mistake, naming a comparison of a parameter with a string the API
    spells otherwise (`method == "ORB"`) in the functions the check called and their helpers
    (:mod:`autograder.engine.strings_compared`)."""
    from . import strings_compared

    return _named_against_the_reference(
        verdict, trial, lambda code, source: strings_compared.misspelt(code.reachable(functions_called(check)), source),
        strings_compared)


def _named_by_unused_parameter(verdict: Verdict, trial: Trial) -> Verdict:
    """A failing verdict that names no mistake, naming a parameter the check's calls gave a value and
    the student's function never reads (:mod:`autograder.engine.ignored`)."""
    from . import ignored
    from .hints import code_of

    calls = _calls_made(trial)
    code = code_of(trial)
    found = ignored.unused_given(code, calls) if calls else None
    if found is not None:
        said, mistake = ignored.sentence(*found), ignored.MISTAKE
    else:   # (or a value it computes and never reads: the functions it judged, served ones too)
        judged = list(dict.fromkeys([call[0] for call in calls + list(getattr(trial, "served", ()))]
                                    + sorted(functions_called(trial.check))))
        unused = ignored.computed_unused(code, judged) if code.functions else None
        if unused is None:
            return verdict
        said, mistake = ignored.unused_value_sentence(*unused), ignored.UNUSED_VALUE
    return _told_after_the_first_line(verdict, said, mistake)


def _named_by_reading(verdict: Verdict, reading: Reading, check: Check, trial: Trial) -> Verdict:
    """A failing verdict naming the cause the submission's code shows in the functions the check called
    (a finding of :mod:`autograder.loading.reading`), when there is one: the check measured the failure,
    the reading says where it comes from. It takes no points. Where the check named the mistake itself
    (an effect: "the last row is not [0, 0, 1]"), only a finding that is a slip wherever it is written
    (:attr:`Finding.certain`) is said, after that name, which stays."""
    called = functions_called(check)
    findings = findings_for(reading, called, bool(trial.whole_numbers & called))
    if verdict.mistake:
        findings = [f for f in findings if f.certain and f.sentence.split(" (line", 1)[-1] not in str(verdict.message)]
    if not findings:
        return verdict
    first, newline, rest = str(verdict.message).partition("\n")
    finding = findings[0]
    if finding.certain:   # (the usual places a check advises looking at give way to the place read)
        from .claims import without_where_to_look

        first = without_where_to_look(first)
    # "module.py, line N": a notebook's cell and line replace it (_point_into_notebooks)
    where = finding.sentence.replace(f"(line {finding.line})",
                                     f"({check.exercise.lab.module}.py, line {finding.line})", 1)
    sentence = f"Reading your code: {where}."
    lead = first.rstrip() + ("" if not first.strip() or first.rstrip().endswith((".", ":", "!", "?")) else ".")
    if verdict.mistake:
        # (a cause the check guessed from its measures gives way to a slip read in the code: "the default
        # smoothness is far too large" where one array appended at every turn makes every row the last; and so
        # does any cause it inferred from what the answers look like, "it looks like x is computed from Y", where
        # the code computes x from X into an array that is also y's: the reading is certain, the look is not)
        # (only a slip read in a function the check called itself: one in a helper it reaches may be another
        # mistake than the one the answers show)
        guessed = without_guessed_cause(lead, verdict.mistake, inferred=finding.function in called)
        if guessed != lead:
            return replace(verdict, message=f"{guessed} {sentence}{newline}{rest}", mistake=finding.mistake, hint="")
        return replace(verdict, message=f"{lead} {sentence}{newline}{rest}")
    # (a fixed hint beside the cause read in their code would only guess at another one)
    return replace(verdict, message=f"{lead} {sentence}{newline}{rest}", mistake=finding.mistake, hint="")


def _state_read(reading: Reading | None, check: Check, trial: Trial) -> bool:
    """Whether the reading of the code finds state kept between calls in the functions the check called."""
    from ..loading.reading import STATE_KEPT

    if reading is None:
        return False
    called = functions_called(check)
    return any(f.mistake in STATE_KEPT for f in findings_for(reading, called, bool(trial.whole_numbers & called)))


def _named_by_fresh_start(verdict: Verdict, check: Check, trial: Trial) -> Verdict:
    """A failed verdict named as state kept between calls when the failing call, made first in the
    student's module imported anew, answers right (:mod:`autograder.engine.fresh_start`). Never costs
    the verdict (logged)."""
    from . import fresh_start

    try:
        return fresh_start.named(verdict, trial)
    except Exception as exc:  # noqa: BLE001 - naming is a bonus: the verdict stands without it
        _log_grader_error(check, exc)
        return verdict


def _named_by_error_model(verdict: Verdict, check: Check, trial: Trial, raised: bool = False) -> Verdict:
    """A failed verdict named by the error model (:mod:`autograder.engine.mutants`): a mutant of the
    reference confirmed on the student's inputs (``raised``: one raising the student's exception).
    A failure of the error model itself never costs the verdict (logged)."""
    from .mutants.naming import named_by_error_model

    try:
        return named_by_error_model(verdict, trial, raised=raised)
    except Exception as exc:  # noqa: BLE001 - naming is a bonus: the verdict stands without it
        _log_grader_error(check, exc)
        return verdict


def _unused_mistakes() -> tuple[str, str]:
    from . import ignored

    return ignored.MISTAKE, ignored.UNUSED_VALUE


def _named_by_trace(verdict: Verdict, check: Check, trial: Trial, traceback_text: str = "") -> Verdict:
    """A failed verdict that names nothing, named by what the student's own expressions held on the
    failing call (:mod:`autograder.engine.traced`). Never costs the verdict (logged)."""
    from . import traced

    try:
        verdict = traced.named(verdict, trial, traceback_text)
        return verdict if traceback_text else traced.named_by_values(verdict, trial)
    except Exception as exc:  # noqa: BLE001 - naming is a bonus: the verdict stands without it
        _log_grader_error(check, exc)
        return verdict


def _named_by_repair(verdict: Verdict, check: Check, trial: Trial, traceback_text: str = "") -> Verdict:
    """A failed verdict that names nothing, named by a change of the student's own code that makes
    their answers right (:mod:`autograder.engine.mutants.repair`; ``traceback_text``: their code
    raised). Never costs the verdict (logged)."""
    from . import traced
    from .mutants.repair import named_by_repair

    try:   # (a change after the first of the student's values to go wrong undoes it there: that value is told)
        return traced.departure_before_repair(named_by_repair(verdict, trial, traceback_text), trial)
    except Exception as exc:  # noqa: BLE001 - naming is a bonus: the verdict stands without it
        _log_grader_error(check, exc)
        return verdict


def _one_naming_time(sandboxes: list) -> None:
    """One time per grading for naming failures (the error model's and repairs',
    ``naming.GRADING_SECONDS``; the inherited failures' own), whatever its lanes and phases: every
    worker's shared values hold the same counters -- seconds only, nothing of a hidden check's; and the
    recordings' own, :data:`autograder.engine.traced.GRADING_SECONDS`)."""
    from .inherited import SHARED_SECONDS
    from .mutants.naming import SPENT
    from .traced import SPENT as TRACED

    for key in (SPENT, SHARED_SECONDS, TRACED):
        counter = [0.0]
        for sandbox in sandboxes:
            sandbox.shared[key] = counter


def _public_memory_to(fresh: list, public: list) -> None:
    """Give the hidden phase's workers what the public checks left for confirming repairs: the checks
    that called each function (their inputs are public), the functions failing their own checks, the
    calls seen and the changes told. Copies, one way: what a hidden check adds never reaches a public worker's, and
    the public phase has ended."""
    from .inherited import SHARED_FAILING, SHARED_RIGHT_ITSELF
    from .mutants.repair import CHECK_FRACTIONS, TOLD_BESIDE

    for sandbox in fresh:
        for done in public:
            for key, value in getattr(done, "shared", {}).items():
                if isinstance(key, tuple) and key[0] == "checks calling":
                    kept = sandbox.shared.setdefault(key, [])
                    kept += [entry for entry in value if all(entry[0] is not mine[0] for mine in kept)]
                elif isinstance(key, tuple) and key[0] in (SHARED_FAILING, SHARED_RIGHT_ITSELF):
                    sandbox.shared.setdefault(key, set()).update(value)
                elif key == "repair seen":
                    for function, calls in value.items():
                        sandbox.shared.setdefault(key, {}).setdefault(function, []).extend(calls)
                elif key == CHECK_FRACTIONS:   # (the public checks' scores: what a change in a shared helper may not lower)
                    sandbox.shared.setdefault(key, {}).update(value)
                elif key in ("repair found", "repair complete", TOLD_BESIDE):   # (the changes told, and whether every
                    for function, told in value.items():   # other was tried: one mistake, one repair, hidden checks too)
                        sandbox.shared.setdefault(key, {}).setdefault(function, list(told) if key == "repair found" else told)


def _remember_check(check: Check, trial: Trial, verdict: Verdict) -> None:
    """Keep the check under the functions it called, and the share of its points the student's code earned,
    for repairs judged by checks run again (:func:`autograder.engine.mutants.repair.remember_check`). Never
    costs the verdict (logged)."""
    from .mutants.repair import remember_check

    try:
        fraction = verdict.fraction if isinstance(verdict.fraction, (int, float)) else None
        remember_check(trial, fraction)
    except Exception as exc:  # noqa: BLE001 - the verdict stands without it
        _log_grader_error(check, exc)


def _remember_answers(check: Check, trial: Trial) -> None:
    """Keep what the check's calls answered, to tell a function whose answer does not depend on its input
    (:mod:`autograder.engine.constant`). Never costs the verdict (logged)."""
    from .constant import remember

    try:
        remember(trial)
    except Exception as exc:  # noqa: BLE001 - the verdict stands without it
        _log_grader_error(check, exc)


def _zero_constant(sandbox, exercise: Exercise, results: list) -> None:
    """The exercise's checks that called a function answering one same answer whatever it is given score 0
    (:mod:`autograder.engine.constant`); a failure of that reading costs nothing (logged)."""
    from .constant import zero_constant

    try:
        with bounded(own_work_bound()):
            zero_constant(sandbox, exercise, results)
    except Runaway as runaway:
        _log_runaway(exercise.id, "telling constant answers", runaway)
    except Exception as exc:  # noqa: BLE001 - the verdicts stand without it
        logging.getLogger("autograder").exception("telling constant answers in %s: %s", exercise.id, exc)


def _told_if_inherited(verdict: Verdict, check: Check, trial: Trial) -> tuple[Verdict, bool]:
    """A failed verdict told as inherited from another of the student's functions when it is
    (:mod:`autograder.engine.inherited`), and whether it is. Never costs the verdict (logged)."""
    from .inherited import told

    try:
        return told(verdict, trial)
    except Exception as exc:  # noqa: BLE001 - the verdict stands without it
        _log_grader_error(check, exc)
        return verdict, False


def _defer_to_hand_written(results) -> None:
    """The error model's names on an exercise's checks are taken back when one of them names the
    mistake by hand (:func:`autograder.engine.mutants.naming.defer_to_hand_written`). A public
    check answers to public checks only: what a hidden check named must not change a word students
    read before the release."""
    from .mutants.naming import defer_to_hand_written

    public = [result for result in results if not result.hidden]
    defer_to_hand_written(public)
    defer_to_hand_written([result for result in results if result.hidden], evidence=results)


def _take_back_refuted(results, sandboxes) -> None:
    """The error model's names and the repairs a later check of the function refuted, in any worker of
    the grading, are taken back (:func:`autograder.engine.mutants.naming.take_back_refuted`,
    :func:`autograder.engine.mutants.repair.take_back_refuted`)."""
    from .mutants import naming, repair

    for module in (naming, repair):
        module.take_back_refuted(results, [taken for sandbox in sandboxes
                                           for taken in getattr(sandbox, "shared", {}).get(module.REFUTED, [])])


def _hints_beside_a_name(graded: list) -> None:
    """One mistake, one account (issue 35: no hint contradicts the code), over ``graded``'s
    (exercise, its result) pairs. A check the error model names keeps its name without the check's
    recipe hint (the name is the cause; the recipe describes code that is mostly right). Where a
    failed check of a student function names a mistake, the recipe hints of the other failed,
    unnamed checks of that function -- in any exercise: lab 12's NCC checks call the matcher
    whose search another exercise names -- are replaced by a pointer to it. A check's function is
    the one of its own exercise it calls; a public check never points at a hidden one. In place."""
    def function(exercise, result) -> str:
        check = next((c for c in exercise.checks if c.name == result.name), None)
        own = functions_called(check) & set(exercise.signatures) if check is not None else set()
        return next(iter(own)) if len(own) == 1 else ""
    failed = [(function(exercise, r), r) for exercise, done in graded for r in done.checks
              if r.max_score > 0 and r.score < r.max_score]
    for _, result in failed:
        if result.mistake.startswith("mutant:"):
            result.hint = ""
    named: dict[str, object] = {}
    for called, result in failed:
        if called and result.mistake:
            named.setdefault(called, result)
            if not result.hidden:   # a public name is the one to point at
                named[called] = named[called] if not named[called].hidden else result
    for called, result in failed:
        first = named.get(called)
        if first is None or result.mistake or not result.hint or (first.hidden and not result.hidden):
            continue
        result.hint = (f"the check \u201c{first.name}\u201d names the mistake found in your `{called}`; this one "
                       "may fail for the same reason")


def _stubs(exercise: Exercise, submission) -> frozenset[str]:
    """The submission's stubs (functions that only raise NotImplementedError), when
    every function of ``exercise`` is one; else none: a check might call a real one."""
    if submission is None:
        return frozenset()
    stubs = stub_functions(submission.path / f"{exercise.lab.module}.py")
    return stubs if set(exercise.signatures) <= stubs else frozenset()


def _only_stub_called(check: Check, stubs: frozenset[str]) -> str:
    """The stub ``check`` calls, when it names exactly one student function and that
    one is a stub (its verdict is then known without running it); else ``""``.
    Advice checks always run: they may turn a failure into a tip."""
    if not stubs or check.advice:
        return ""
    called = functions_called(check)
    return next(iter(called)) if len(called) == 1 and called <= stubs else ""


def _not_implemented(check: Check, function: str) -> CheckResult:
    """The verdict ``check`` would reach by calling the stub ``function``, without
    building its ground truth, scenes or pictures."""
    message = f"{function}() is not implemented yet"  # the worker's words for NotImplementedError
    return CheckResult(check.name, 0.0, check.points, NOT_IMPLEMENTED, message,
                       hidden=check.hidden, failure="not_implemented")


def _import(sandbox: Sandbox, module: str, submission) -> CallOutcome:
    """Import the module in the worker, unless loading already found why it cannot be
    (not found, unreadable notebook); an import error names the file and line."""
    problem = submission.problems.get(module) if submission is not None else None
    if problem:
        return CallOutcome(ok=False, kind="missing_module", message=problem)
    outcome = sandbox.import_module(module)
    if not outcome.ok and outcome.kind == "import_error" and ", line " not in outcome.message:
        where = _innermost_frame(outcome.traceback)
        if where:
            outcome = replace(outcome, message=f"{outcome.message}\n  at {where}")
    if not outcome.ok and outcome.kind == "import_error":
        outcome = replace(outcome, message=outcome.message + (_another_labs_module(outcome.message, module)
                                                              or _library_not_offered(outcome.message, sandbox)))
    return outcome


def _library_not_offered(message: str, sandbox: Sandbox) -> str:
    """Where graded code imports a library the sandbox does not offer (a progress bar's ``tqdm``, ``pandas``): what it
    does offer, and that the library being installed where the grader runs changes nothing; else ""."""
    import importlib.util
    import sys

    from ..sandbox.confine import OFFERED

    missing = re.search(r"No module named '([A-Za-z_][A-Za-z0-9_]*)", message)
    if missing is None or not sandbox.confinement.hides_files or missing.group(1) in sys.stdlib_module_names:
        return ""
    name = missing.group(1)
    try:
        installed = importlib.util.find_spec(name) is not None   # (a top-level name: found, never imported)
    except (ImportError, ValueError):
        installed = False
    if installed:
        return "\n  " + measured(f"graded code may import {OFFERED} only ({name} is installed where the grader runs, "
                                 f"but graded code does not see it): take the import of {name} out, or write what it "
                                 "did with those")
    # (nowhere here: a library, or a file of the student's own not handed in beside the module)
    return "\n  " + measured(f"graded code may import {OFFERED}, and the .py files handed in beside it: if {name}.py is "
                             f"a file of yours, add it to what you hand in; else take the import of {name} out")


def _another_labs_module(message: str, module: str) -> str:
    """Why an import of another lab's module failed, when it did (a lab 12 file reusing lab 11's
    functions, graded without lab 11's file beside it): the module it needs and what to do; else ""."""
    missing = re.search(r"No module named '([A-Za-z_][A-Za-z0-9_]*)'", message)
    if missing is None or missing.group(1) == module:
        return ""
    lab = next((lab for lab in discover().values() if lab.module == missing.group(1)), None)
    if lab is None:
        return ""
    # (measured: the import raised for that module, whatever the code that asked for it)
    return "\n  " + measured(f"{lab.module}.py is the file of {lab.key}, which {module}.py imports: hand it in beside "
                             f"{module}.py (the grader imports it from the same folder), or copy what {module}.py "
                             "uses from it")


def _innermost_frame(traceback_text: str) -> str:
    """``lab07_transformations.py, line 12: x = undefined_name`` from a student traceback."""
    from .raised import innermost_frame

    frame = innermost_frame(traceback_text)
    if frame is None:
        return ""
    filename, line, _, code = frame
    return f"{filename}, line {line}" + (f": {code}" if code else "")


def _reading_notes(submission) -> list[str]:
    """What the student should know about how their files were read: first each file
    handed in but not graded (a lab handed in twice), then renames and notebooks."""
    notes = [f.sentence() for files in submission.not_graded.values() for f in files]
    notes += [f"graded {found} as {module}.py (the name the grader looks for); rename it to be sure"
              for module, found in submission.renamed.items()]
    for module, (name, converted) in submission.notebooks.items():
        note = converted.left_out_note(name)  # one line: the statements left out, and why
        if note:
            notes.append(note)
    return notes


def _point_into_notebooks(result: GradingResult, exercises, submission) -> None:
    """Messages and tracebacks about a module converted from a notebook name the
    notebook's cell and line instead of the converted module's line."""
    modules = {ex.id: ex.lab.module for ex in exercises}
    for exercise in result.exercises:
        module = modules.get(exercise.id)
        if module not in submission.notebooks:
            continue
        name, converted = submission.notebooks[module]
        exercise.message = point_into_notebook(exercise.message, module, name, converted)
        for check in exercise.checks:
            check.message = point_into_notebook(check.message, module, name, converted)
            check.traceback = point_into_notebook(check.traceback, module, name, converted)


def _in_place_advice(modified) -> CheckResult:
    """The engine's own advice: a function that writes into its caller's arrays."""
    lines = [f"{function}() modified its input array `{argument}` in place; callers do not expect that"
             for function, argument in modified]
    return CheckResult("inputs left unchanged", 0.0, 0.0, ADVICE, "\n".join(lines),
                       # measured: the caller's array did change, so it was not copied before the write
                       hint=measured("work on a copy (e.g. image = image.copy()) or write into a new array"))


def besides_forbidden(verdict: Verdict, sandbox: Sandbox, check: Check, rules: dict | None,
                      inputs: Inputs | None) -> Verdict:
    """A check lost for a forbidden library call, with what the answer that call gave is worth: whether
    writing the step themselves is all that is left (told after the rule), or the answer is wrong besides
    (a result of the library's left as columns: the rule alone would hide it), told first -- the rule,
    after it, loses the points either way. The check is run once more with the calls allowed, in the first public check of its exercise
    that lost points so, and in the next ones while the answer passed there (at most
    :data:`FORBIDDEN_LOOKS` checks: the runs' time comes out of the exercise's budget, which the
    exercise's other functions need); anything but a verdict tells nothing."""
    # (the exercise -> what the look found, in the check it was made in: the exercise's other checks
    # lost so point to it -- "called X" alone would hide that the answer was wrong besides)
    looked = sandbox.shared.setdefault("forbidden call looked at", {})
    found = looked.get(check.exercise.id, 0)
    if found == FORBIDDEN_LOOKS:
        return verdict
    if not isinstance(found, int):
        name, what, mistake = found
        # (the mistake in words where it has them -- "the two images' points are swapped" -- not a
        # machine label such as "repair:swap_items")
        said = f" ({mistake})" if mistake and ":" not in mistake and len(mistake) <= 200 else ""
        return replace(verdict, message=f"With the forbidden call allowed, the answer in the check '{name}' was {what}{said}: "
                                        f"see there. {_rule_besides(verdict.message)}",
                       mistake=verdict.mistake or mistake)
    # (looked at again in the next check while the answer passed: RANSAC in place of the 8-point
    # algorithm gives the exact correspondences' F, and another F on noisy ones)
    looked[check.exercise.id] = found + 1
    verdict, what = _looked_besides_forbidden(verdict, sandbox, check, rules, inputs)
    if what is not None:
        looked[check.exercise.id] = (check.name, what, verdict.mistake)
    return verdict


FORBIDDEN_LOOKS = 3   # the checks of an exercise run again with a forbidden call allowed, at most


def _looked_besides_forbidden(verdict: Verdict, sandbox: Sandbox, check: Check, rules: dict | None,
                              inputs: Inputs | None) -> tuple[Verdict, str | None]:
    """:func:`besides_forbidden`'s look: the check run again with the calls allowed. The verdict with
    what the look found told, and what the answer was besides the rule ("wrong", "an exception"; None
    when nothing is wrong besides it, or nothing could be told)."""
    trial = Trial(_SharedApart(sandbox), check, rules, inputs)
    trial.forbidden_allowed = True
    try:
        with np.errstate(all="ignore"):
            again = check.func(trial)
    except Fail as failure:
        # (and where in their code, as for any failed check: the library's result reshaped where it is
        # transposed is a mistake of its own, which writing the step themselves would not mend)
        named = _named_by_repair(Verdict(0.0, failure.message, failure.hint, failure.mistake), check, trial)
        first = str(named.message).split("\n", 1)[0].rstrip()
        return replace(verdict, message=f"With the forbidden call allowed, the answer is wrong: {_sentence(first)}\n"
                                        f"{_rule_besides(verdict.message)}",
                       mistake=named.mistake or verdict.mistake), "wrong"
    except StudentFailure as failure:
        if failure.outcome.kind != "exception":   # (a timeout, a crash: nothing more to tell)
            return verdict, None
        # (the code around the call raising: `cv2.convertPointsFromHomogeneous(Xh)` of a 4 x N result)
        named = _named_by_repair(Verdict(0.0, failure.message), check, trial)
        first = str(named.message).split("\n", 1)[0].rstrip()
        return replace(verdict, message=f"With the forbidden call allowed, your code fails: {_sentence(first)}\n"
                                        f"{_rule_besides(verdict.message)}",
                       mistake=named.mistake or verdict.mistake), "an exception"
    except Exception:  # noqa: BLE001 - anything else: nothing more to tell
        return verdict, None
    if again is None or (isinstance(again, Verdict) and again.fraction >= 1.0):
        return replace(verdict, message=f"{_sentence(verdict.message)} The answer it gave passes this check "
                                        "otherwise: here, writing that step yourself is all that is left to do."), None
    if isinstance(again, Verdict) and again.message:   # (part of the check lost besides the rule)
        named = _named_by_repair(again, check, trial)
        first = str(named.message).split("\n", 1)[0].rstrip()
        return replace(verdict, message=f"With the forbidden call allowed, the answer is partly wrong: {_sentence(first)}\n"
                                        f"{_rule_besides(verdict.message)}",
                       mistake=named.mistake or verdict.mistake), "partly wrong"
    return verdict, None


def _rule_besides(rule) -> str:
    """The forbidden call's rule told after the mistake the answer has besides it: the mistake leads (it
    is what the student's code gets wrong however the step is written); the rule alone loses the points."""
    rule = str(rule).rstrip().rstrip(".")
    return f"Besides that mistake, {rule}: that alone loses this check."


class _SharedApart:
    """The sandbox, with a copy of what the grading's checks share (``shared``): a value computed with
    the forbidden calls allowed (a panorama another check would be served) must never reach a check
    that judges the student's code under the rules. Everything else is the sandbox's own."""

    def __init__(self, sandbox: Sandbox):
        # (the repairs' notes too -- changes ruled out, found -- are of the call allowed; the naming
        # time, a list, stays the grading's one)
        self._sandbox = sandbox
        self.shared = {key: copy.deepcopy(value) if isinstance(value, (dict, set)) else value
                       for key, value in sandbox.shared.items()}

    def __getattr__(self, name):
        return getattr(self._sandbox, name)


def _sentence(message) -> str:
    message = str(message).rstrip()
    return message if not message or message[-1] in ".:;!?" else message + "."


def run_check(sandbox: Sandbox, check: Check, pictures: str = "all",
              modified: list | None = None, rules: dict | None = None,
              painter: "Painter | None" = None, inputs: Inputs | None = None,
              reading: Reading | None = None) -> CheckResult:
    """Run one check and turn however it ends into a scored :class:`CheckResult`.

    ``modified`` collects the (function, argument) pairs the student's calls
    changed in place; ``rules`` are the instructor's extra forbids; ``inputs``
    where its properties draw their inputs (the submission's). With a
    ``painter`` the check's pictures are drawn on its threads (the result's
    ``artifacts`` are filled in by :meth:`Painter.finish`), else at once.
    ``reading``, the submission's code read (:mod:`autograder.loading.reading`), names
    the cause of a failure the check measured but did not name.
    """
    if check.advice:
        return _run_advice(sandbox, check, modified, rules, inputs)
    trial = Trial(sandbox, check, rules, inputs)
    started = time.perf_counter()
    tb, student_failure = "", ""
    try:
        # (the check's arithmetic on a student's NaN or inf: judged, not warned of)
        with np.errstate(all="ignore"), bounded(own_work_bound()):
            verdict = check.func(trial)
        if verdict is None:
            verdict = Verdict(1.0)
        elif not isinstance(verdict, Verdict):
            raise TypeError(f"check returned {type(verdict).__name__}, not a Verdict")
        status = PASSED if verdict.fraction >= 1.0 else (PARTIAL if verdict.fraction > 0 else FAILED)
    except Fail as failure:
        verdict, status = Verdict(0.0, failure.message, failure.hint, failure.mistake), FAILED
    except StudentFailure as failure:
        verdict = Verdict(0.0, failure.message)
        status = {"not_implemented": NOT_IMPLEMENTED, "grader_error": ERROR}.get(failure.outcome.kind, FAILED)
        tb, student_failure = failure.outcome.traceback, failure.outcome.kind
        if student_failure == "forbidden_call" and not check.hidden:
            try:
                with bounded(own_work_bound()):
                    verdict = besides_forbidden(verdict, sandbox, check, rules, inputs)
            except Runaway as runaway:   # (the forbidden call is told as it was)
                _log_runaway(check, "looking besides its forbidden call", runaway)
    except Runaway as runaway:
        verdict, status = Verdict(0.0, "grader error in this check (judging it ran far past its time or memory); "
                                       "the rest was graded - please tell your instructor"), ERROR
        _log_runaway(check, "judging it", runaway)
    except Exception as exc:  # noqa: BLE001 - a bug in the grader must not stop grading
        verdict, status = Verdict(0.0, f"grader error in this check ({type(exc).__name__}: {exc}); "
                                       "the rest was graded - please tell your instructor"), ERROR
        tb = ""
        _log_grader_error(check, exc)
    try:
        with bounded(own_work_bound()):
            verdict = _explained(verdict, status, check, trial, reading, tb, student_failure)
    except Runaway as runaway:   # the verdict stands as judged; a hint no reading has held against the code is not said
        _log_runaway(check, "naming its failure", runaway)
        verdict = replace(verdict, hint="")
    artifacts = []
    if pictures == "all" or (pictures == "failed" and status != PASSED):
        artifacts = painter.draw(check, trial.artifacts) if painter else drawn(check, trial.artifacts)
    fraction = verdict.fraction if isinstance(verdict.fraction, (int, float)) else 0.0
    fraction = min(max(float(fraction), 0.0), 1.0) if fraction == fraction else 0.0
    _collect(modified, trial)
    return CheckResult(
        name=check.name, score=round(fraction * check.points, 6), max_score=check.points,
        status=status, message=str(verdict.message), hint=str(verdict.hint), hidden=check.hidden,
        mistake=verdict.mistake, failure=student_failure, output="\n".join(trial.outputs)[:6000],
        traceback=tb, artifacts=artifacts,
        seconds=round(time.perf_counter() - started, 6),
        student_seconds=round(trial.student_seconds, 6), inputs_digest=trial.given)


def _explained(verdict: Verdict, status: str, check: Check, trial: Trial, reading: Reading | None, tb: str,
               student_failure: str) -> Verdict:
    """``verdict`` with its failure named where something names it (the inherited failures', a fresh start's,
    the readings', the error model's, the repairs', the recordings'), and no hint that the student's code
    contradicts. Each naming is a bonus: a failure of one is logged and the verdict stands without it."""
    _remember_check(check, trial, verdict)
    _remember_answers(check, trial)
    # a failure another of the student's functions causes is not this one's mistake, nor one an earlier
    # call's leftovers decided
    inherited = False
    if status in (FAILED, PARTIAL) and student_failure in ("", "exception"):
        verdict, inherited = _told_if_inherited(verdict, check, trial)
    if status in (FAILED, PARTIAL) and student_failure in ("", "exception") and not inherited \
            and not _state_read(reading, check, trial):
        # (an answer an earlier call's leftovers decided: what the check measured describes the stale
        # answer, a change of the code would only work around it -- nothing else names it; where the
        # reading of the code finds the state itself, it tells it)
        stale = _named_by_fresh_start(verdict, check, trial)
        inherited, verdict = stale is not verdict, stale
    if student_failure == "exception" and not verdict.mistake and not inherited:
        # The cause read in the raising line itself (what it was given, what it computes) is certain and
        # comes first; then a change of their code confirmed to mend the exception (a change that mends the
        # inputs tried may still be no fix: `log(1 - w)` made `log(1 + w)`), and only then the NumPy forms'
        # reading of its message, which guesses which operand is wrong ("keep it a column").
        # (an OpenCV error's reading says what the call was given, which the slip upstream -- a test of the other
        # image -- may explain better: a change confirmed comes first there, as for the NumPy forms)
        if "OpenCV(" not in str(verdict.message):
            verdict = _told_exception(verdict, _explained_from_the_line(trial, tb))
        if not verdict.mistake:
            verdict = _named_by_repair(verdict, check, trial, tb)
    if student_failure == "exception" and not verdict.mistake:
        verdict = _named_by_exception(verdict, trial, tb)
    if status in (FAILED, PARTIAL) and not verdict.mistake and student_failure == "" and not inherited:
        verdict = _named_by_misread_output(verdict, trial)
    if reading is not None and status in (FAILED, PARTIAL) and student_failure in ("", "exception") \
            and not inherited:
        verdict = _named_by_reading(verdict, reading, check, trial)
    if status in (FAILED, PARTIAL) and not verdict.mistake and student_failure in ("", "exception") and not inherited:
        verdict = _named_by_defaults(verdict, trial)
    if status in (FAILED, PARTIAL) and not verdict.mistake and student_failure in ("", "exception") and not inherited:
        verdict = _named_by_strings(verdict, check, trial)
    if status in (FAILED, PARTIAL) and student_failure in ("", "exception") and not inherited:
        verdict = _named_by_error_model(verdict, check, trial, raised=student_failure == "exception")
    if status in (FAILED, PARTIAL) and student_failure == "" and not inherited:   # (an exception's: above)
        verdict = _named_by_repair(verdict, check, trial)
    if status in (FAILED, PARTIAL) and not verdict.mistake and student_failure in ("", "exception") \
            and not inherited and "looks like" not in str(verdict.message).lower():
        verdict = _named_by_unused_parameter(verdict, trial)   # true, but not confirmed
    if status in (FAILED, PARTIAL) and student_failure in ("", "exception") and not inherited \
            and verdict.mistake not in _unused_mistakes():
        # what the student's expressions held: the operands an exception refused, where an answer of the
        # wrong shape was made (after the error model: a place is no cause, and a name set here would
        # keep the model from the function's later checks; after a parameter never read, the cause)
        verdict = _named_by_trace(verdict, check, trial, tb if student_failure == "exception" else "")
    if status in (FAILED, PARTIAL):   # a diagnosis asking for code the student wrote is not said
        verdict = rewritten(verdict, trial)
    if status in (FAILED, PARTIAL):   # code relying on what only one OpenCV major does is told so
        verdict = with_version_note(verdict, trial)
    return verdict


class Painter:
    """Draws and encodes the checks' pictures on other threads while grading goes on:
    the grader mostly waits for the worker meanwhile, and OpenCV's drawing and
    encoding release the GIL. A picture never costs a check its verdict: one that
    cannot be drawn is left out (and logged)."""

    def __init__(self, threads: int | None = None):
        threads = threads or max(1, min(2, os.cpu_count() or 1))
        self._pool = ThreadPoolExecutor(threads, thread_name_prefix="pictures")
        self._pending: list = []

    def draw(self, check: Check, make: Callable[[], list]) -> list:
        """A list that :meth:`finish` fills with ``make()``'s artifacts."""
        artifacts: list = []
        self._pending.append((check, artifacts, self._pool.submit(make)))
        return artifacts

    def finish(self) -> None:
        """Wait for every picture asked for so far."""
        pending, self._pending = self._pending, []
        for check, artifacts, future in pending:
            artifacts.extend(drawn(check, future.result))

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self._pool.shutdown(cancel_futures=True)


def drawn(check: Check, make: Callable[[], list]) -> list:
    """``make()``'s artifacts, or none if they cannot be drawn (logged): a picture never
    costs a check its verdict."""
    try:
        return list(make())
    except Exception as exc:  # noqa: BLE001
        _log_grader_error(check, exc)
        return []


def _run_advice(sandbox: Sandbox, check: Check, modified, rules=None, inputs=None) -> CheckResult:
    """An advice check: a tip if it gave one, else silence; never a failure, never points."""
    trial = Trial(sandbox, check, rules, inputs)
    started = time.perf_counter()
    status, message, hint = PASSED, "", ""
    try:
        with np.errstate(all="ignore"), bounded(own_work_bound()):
            check.func(trial)
    except StudentFailure as failure:  # the graded checks report the student's failure
        if failure.outcome.kind == "not_implemented":
            status, message = NOT_IMPLEMENTED, failure.message
    except Fail:
        pass  # a tip is given with t.advise, not by failing
    except Runaway as runaway:
        status, message = ERROR, "grader error in this advice (it ran far past its time or memory); no points depend on it"
        _log_runaway(check, "giving its advice", runaway)
        trial.tips.clear()
    except Exception as exc:  # noqa: BLE001
        status, message = ERROR, f"grader error in this advice ({type(exc).__name__}: {exc}); no points depend on it"
        _log_grader_error(check, exc)
    unimplemented = trial.not_implemented()
    if unimplemented and status == PASSED:  # the advice caught it: a tip about a stub is no tip
        status, message = NOT_IMPLEMENTED, unimplemented
        trial.tips.clear()
    if trial.tips and status == PASSED:
        status = ADVICE
        # (said for the student's code as a failed check's words are: a checklist in a tip lists only what the code
        # does not do already -- "your code already normalises ...; the error is elsewhere", not "check that each set
        # has its own transform" to code whose sets have theirs)
        tips = [(said_for_the_code(trial, tip), said_for_the_code(trial, h) if h else h) for tip, h in trial.tips]
        message = "\n".join(tip for tip, _ in tips)
        hint = " ".join(h for _, h in tips if h)
    _collect(modified, trial)
    return CheckResult(name=check.name, score=0.0, max_score=0.0, status=status, message=message,
                       hint=hint, hidden=check.hidden, output="\n".join(trial.outputs)[:6000],
                       seconds=round(time.perf_counter() - started, 6),
                       student_seconds=round(trial.student_seconds, 6), inputs_digest=trial.given)


def _collect(modified, trial: Trial) -> None:
    if modified is not None:
        modified += [pair for pair in trial.modified_inputs if pair not in modified]


def own_work_bound() -> float:
    """The CPU seconds the grader's own work about one check (judging it, naming its failure) may take before it
    is stopped as a runaway (:mod:`autograder.engine.bounded`): twice every naming time of a whole grading
    together, at the machine's pace last measured, and a minute more -- no check's work legitimately takes the
    grading's."""
    from . import inherited, traced
    from .mutants import naming

    every = 2 * naming.GRADING_SECONDS + traced.GRADING_SECONDS + inherited.GRADING_SECONDS
    return 2 * every * naming.last_pace() + 60


def _log_runaway(where: Check | str, doing: str, runaway: Runaway) -> None:
    """The instructor's log: the grader's own work on ``where`` (a check, or what else it was reading) was
    stopped by its backstop (:mod:`autograder.engine.bounded`)."""
    logging.getLogger("autograder").error(
        "grader error in %s: %s was stopped (%s); a fault of the grader's, not of the submission's code",
        getattr(where, "id", where), doing, runaway)


def _log_grader_error(check: Check, exc: Exception):
    logging.getLogger("autograder").error(
        "grader error in %s:\n%s", check.id, _formatted(exc))


def _formatted(exc: BaseException) -> str:
    """The traceback of ``exc`` as text. Python 3.11 parses source lines to point at the failing
    expression: under the parse lock, as every parse in the grader's process is."""
    with PARSE_LOCK:
        return "".join(traceback.format_exception(exc))
