"""Grading a submission: discovery, execution and scoring, kept apart from reporting.

:func:`grade` selects exercises from the registry, loads the submission, starts
one sandboxed worker, runs every check in the grader's process and returns a
:class:`~autograder.results.GradingResult`. It never raises because of the
submission; a failure inside a check is recorded as a grader error for that check.

Student time is budgeted per exercise and per submission (``Limits.exercise_budget``,
``Limits.submission_budget``): once a budget is spent, the checks left are marked
"time budget exhausted" (0 points) without calling anything, and the results are
still complete.
"""

from __future__ import annotations

import logging
import time
import traceback
from typing import Callable

from . import __version__
from .checks import Fail, StudentFailure, Trial, Verdict
from .registry import Check, Exercise, hidden_checks_installed, select
from .results import (ERROR, FAILED, NOT_IMPLEMENTED, PARTIAL, PASSED, CheckResult,
                      ExerciseResult, GradingResult)
from .sandbox import Limits, Sandbox
from .submission import load_submission


PICTURES = ("all", "failed", "none")


def grade(submission_path, selectors=(), *, limits: Limits | None = None,
          include_hidden: bool = True, pictures: str = "all",
          on_check: Callable[[Exercise, CheckResult], None] | None = None) -> GradingResult:
    """Grade the submission at ``submission_path``.

    Parameters
    ----------
    submission_path : path
        Folder, ``.py``, ``.zip`` or ``.ipynb`` (see :mod:`autograder.submission`).
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
        Called after every check, e.g. to advance a progress bar.

    Raises
    ------
    SelectionError, SubmissionError
        For a selector that names nothing, or a path that is not a submission.
    """
    if pictures not in PICTURES:
        raise ValueError(f"pictures must be one of {PICTURES}, got {pictures!r}")
    started = time.perf_counter()
    exercises = select(selectors, include_hidden)
    modules = sorted({ex.lab.module for ex in exercises})
    with load_submission(submission_path, modules) as submission:
        result = GradingResult(submission.name, submission.content_hash, __version__,
                               hidden_included=include_hidden and hidden_checks_installed())
        with Sandbox(submission.path, limits) as sandbox:
            budget = _Budget(sandbox)
            for exercise in exercises:
                checks = [c for c in exercise.checks if include_hidden or not c.hidden]
                budget.start_exercise()
                result.exercises.append(_grade_exercise(
                    sandbox, exercise, checks, pictures, on_check, budget,
                    submission.refusal_for(exercise.lab.module)))
            result.student_seconds = round(sandbox.student_seconds, 6)
    result.seconds = round(time.perf_counter() - started, 6)
    return result


class _Budget:
    """The per-exercise and per-submission time budgets, as limits on the sandbox's billed time."""

    def __init__(self, sandbox: Sandbox):
        self.sandbox = sandbox
        self.limits = sandbox.limits

    def start_exercise(self):
        spent = self.sandbox.student_seconds
        self.sandbox.start_exercise(min(spent + self.limits.exercise_budget, self.limits.submission_budget))

    def exhausted(self) -> str:
        """Which budget is spent ("" while there is time left)."""
        if self.sandbox.student_seconds >= self.limits.submission_budget:
            return f"time budget exhausted (the submission's {self.limits.submission_budget:g} s)"
        if self.sandbox.remaining() <= 0:
            return f"time budget exhausted (this exercise's {self.limits.exercise_budget:g} s)"
        return ""


def _grade_exercise(sandbox, exercise, checks, pictures, on_check, budget=None,
                    refusal: str = "") -> ExerciseResult:
    functions = list(exercise.signatures.values())
    out = ExerciseResult(exercise.id, exercise.title, functions)
    imported = sandbox.import_module(exercise.lab.module)
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
                                          message, hidden=check.hidden,
                                          traceback=imported.traceback, output=imported.output))
            if on_check:
                on_check(exercise, out.checks[-1])
        return out
    for check in checks:
        spent = budget.exhausted() if budget is not None else ""
        if spent:
            out.checks.append(CheckResult(check.name, 0.0, check.points, FAILED, spent,
                                          hidden=check.hidden))
        else:
            out.checks.append(run_check(sandbox, check, pictures))
        if on_check:
            on_check(exercise, out.checks[-1])
    if out.checks and all(c.status == NOT_IMPLEMENTED for c in out.checks):
        out.message = "not implemented yet"
    return out


def run_check(sandbox: Sandbox, check: Check, pictures: str = "all") -> CheckResult:
    """Run one check and turn however it ends into a scored :class:`CheckResult`."""
    trial = Trial(sandbox, check)
    started = time.perf_counter()
    tb = ""
    try:
        verdict = check.func(trial)
        if verdict is None:
            verdict = Verdict(1.0)
        elif not isinstance(verdict, Verdict):
            raise TypeError(f"check returned {type(verdict).__name__}, not a Verdict")
        status = PASSED if verdict.fraction >= 1.0 else (PARTIAL if verdict.fraction > 0 else FAILED)
    except Fail as failure:
        verdict, status = Verdict(0.0, failure.message, failure.hint), FAILED
    except StudentFailure as failure:
        verdict = Verdict(0.0, failure.message)
        status = {"not_implemented": NOT_IMPLEMENTED, "grader_error": ERROR}.get(failure.outcome.kind, FAILED)
        tb = failure.outcome.traceback
    except Exception as exc:  # noqa: BLE001 - a bug in the grader must not stop grading
        verdict, status = Verdict(0.0, f"grader error in this check ({type(exc).__name__}: {exc}); "
                                       "the rest was graded - please tell your instructor"), ERROR
        tb = ""
        _log_grader_error(check, exc)
    artifacts = []
    if pictures == "all" or (pictures == "failed" and status != PASSED):
        try:
            artifacts = trial.artifacts()
        except Exception as exc:  # noqa: BLE001 - a picture never costs the check its verdict
            _log_grader_error(check, exc)
    fraction = verdict.fraction if isinstance(verdict.fraction, (int, float)) else 0.0
    fraction = min(max(float(fraction), 0.0), 1.0) if fraction == fraction else 0.0
    return CheckResult(
        name=check.name, score=round(fraction * check.points, 6), max_score=check.points,
        status=status, message=str(verdict.message), hint=str(verdict.hint), hidden=check.hidden,
        output="\n".join(trial.outputs)[:6000], traceback=tb,
        artifacts=artifacts,
        seconds=round(time.perf_counter() - started, 6),
        student_seconds=round(trial.student_seconds, 6))


def _log_grader_error(check: Check, exc: Exception):
    logging.getLogger("autograder").error(
        "grader error in %s:\n%s", check.id, "".join(traceback.format_exception(exc)))
