"""One submission's grading as a task: plain data in, plain data out.

The same function runs in a local process pool and on a Dask worker. It writes
the files it is given into a fresh temporary folder, grades them with
:func:`autograder.engine.runner.grade` (one sandboxed worker, as a single
``autograder grade`` does), and returns the results model as a dict -- never an
object of the student's making, and never raising. Locally, the processes that run
it are forked from a server that has imported the grader (:mod:`.processes`).
"""

from __future__ import annotations

import tempfile
import time
import traceback
import warnings
from pathlib import Path

from .gradebook import STORAGE_ERRNOS
from .processes import grading_processes  # noqa: F401 - where the command line starts it


def grade_files(files: dict[str, bytes], selectors: list[str], call_timeout: float,
                pictures: str, hidden_points_visible: bool, inputs_secret: str, name: str,
                threads: int | None = None, rules: dict | None = None) -> dict:
    """``{"result": <results-model dict, without pictures>, "json": <the student's results.json
    text>, "page": <the student's feedback page>}``, ``{"error": <reason>}``, or
    ``{"storage": <reason>, "path": <file>, "errno": <n>}`` when this machine's temporary
    folder is full or read-only (no fault of the submission: the batch stops).

    The page is rendered here, where the pictures are, and the JSON written out here too:
    the process that collects the class (one for any number of workers) just stores them.
    ``result`` is the whole grading (for the gradebook: the instructor's); the page and the
    JSON are what the student may see of it (:meth:`GradingResult.for_students`).

    Parameters
    ----------
    files : dict of str to bytes
        Relative POSIX paths (``.py``/``.ipynb``) to their contents.
    selectors : list of str
        What to grade (``lab07``, ``lab07.ex1``); all when empty.
    call_timeout : float
        Seconds per call into student code.
    pictures : {"all", "failed", "none"}
        Which checks keep their pictures.
    hidden_points_visible : bool
        Whether the student's page and JSON show what the hidden checks scored.
    inputs_secret : str
        The course's secret for the property checks' inputs ("": ``$AUTOGRADER_INPUTS_SECRET``).
    name : str
        The submission's name in the results (the student id).
    threads : int, optional
        OpenCV's threads in this process and in the submission's worker, where
        several gradings share the machine's cores (None: OpenCV's default).
    rules : dict, optional
        The course's other grading rules, as a single grading applies them:
        ``forbid`` (library functions a student function may not call),
        ``exercise_budget`` and ``submission_budget`` (seconds); ``labs`` and ``hide``, the
        course's own lab folders (absolute paths, on this machine) and hidden checks; and ``gradings``,
        how many gradings share this machine at once (their memory: :func:`_sharing_the_machine`);
        ``figures``, the exercises whose lab-sheet figures are made too (returned as
        ``"figures"``: figure id -> PNG bytes; see :func:`_figures`).
    """
    from ...reports import html
    from ...engine.results import json_text, strip_pictures
    from ...engine.runner import grade
    from ...figures import grading_budget
    from ...sandbox.supervisor import Limits

    try:
        with tempfile.TemporaryDirectory(prefix="batch-") as tmp, warnings.catch_warnings():
            # On a Dask worker other threads use the global `random` while a property
            # check draws its (derandomised) examples; Hypothesis takes that for the
            # strategy's doing and warns. The examples do not depend on it.
            warnings.filterwarnings("ignore", message="Do not use the `random` module inside strategies")
            folder = Path(tmp) / name
            try:
                for relative, data in files.items():
                    target = folder / relative
                    target.parent.mkdir(parents=True, exist_ok=True)
                    target.write_bytes(data)
                folder.mkdir(exist_ok=True)
            except OSError as exc:
                if exc.errno in STORAGE_ERRNOS:   # the machine's fault, not the submission's
                    return {"storage": exc.strerror or str(exc), "path": str(exc.filename or tmp),
                            "errno": exc.errno}
                raise
            if threads:
                import cv2

                cv2.setNumThreads(threads)
            rules = rules or {}
            if rules.get("labs") or rules.get("hide"):   # this process registers the course's labs too
                from ..course import CourseConfig

                CourseConfig(labs=list(rules.get("labs") or []), hide=list(rules.get("hide") or [])).use_labs()
            budgets = {k: rules[k] for k in ("exercise_budget", "submission_budget") if rules.get(k)}
            limits = _sharing_the_machine(Limits(call_timeout=call_timeout, threads=threads, **budgets),
                                          rules.get("gradings", 1))
            begun = time.monotonic()  # the submission's deadline counts from here: its figures share it
            result = grade(folder, selectors, limits=limits,
                           pictures=pictures, inputs_secret=inputs_secret or None, forbid=rules.get("forbid"))
            student = result.for_students(hidden_points_visible)
            figures = _figures(folder, rules.get("figures") or [], limits, Path(tmp) / "figures",
                               begun + grading_budget(limits, selectors))
            return {"result": strip_pictures(result.to_dict()),
                    "json": json_text(strip_pictures(student.to_dict())), "page": html.render(student),
                    "figures": figures}
    except Exception as exc:  # noqa: BLE001 - one submission never stops the batch
        return {"error": f"the grader could not finish: {type(exc).__name__}: {exc}",
                "traceback": traceback.format_exc()[-4000:]}


def _figures(folder: Path, exercises: list[str], limits, out: Path, deadline: float) -> dict[str, bytes]:
    """The lab sheet's figures of ``exercises`` (those the course reviews with a rubric) made by
    the submission's functions in the sandbox, with its graded calls' ``limits``, by the
    submission's ``deadline`` (``time.monotonic()``: grading and figures share its budget):
    figure id -> PNG bytes. A figure that cannot be made is left out (the review says so);
    making them never fails the grading."""
    if not exercises:
        return {}
    from ...figures import make_figures

    try:
        outcomes = make_figures(folder, exercises, out, limits, deadline)
        return {o.figure_id: o.path.read_bytes() for o in outcomes if o.path is not None}
    except Exception:  # noqa: BLE001 - the grading stands without its figures
        return {}


def _sharing_the_machine(limits, gradings: int):
    """``limits`` for one of ``gradings`` submissions graded side by side on this machine: each
    keeps its own memory limit, but never more than its share of what the machine can give
    the workers together, so one submission's memory bomb never takes another's memory."""
    from dataclasses import replace

    from ...sandbox.supervisor import memory_for_workers

    machine = memory_for_workers()
    if gradings <= 1 or not machine:
        return limits
    return replace(limits, memory=min(limits.memory, machine // gradings))
