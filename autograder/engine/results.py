"""The results model: one JSON-serialisable tree that every report renders.

Keys other tools rely on (see DESIGN.md, "Results and reports")::

    {"total": float, "max_total": float,
     "exercises": [{"id": "lab08.ex2", "score": float, "max_score": float,
                    "checks": [{"name": str, "passed": bool, "score": float,
                                "max_score": float, "message": str,
                                "status": str, "advice": bool}]}]}

A check whose ``status`` is ``"advice"`` (``advice: true``) is a tip worth 0
points: ``message`` says what to change and why; it is never a failure.

What students see of hidden checks before the instructor releases them is made in
one place, :meth:`GradingResult.for_students`: a verdict per check and nothing of
its inputs (``redacted: true``); every report a student reads renders that view.

Timing fields are named ``seconds`` / ``student_seconds`` everywhere (and
``student_wall_seconds``: the wall time during which the student's code ran in
some lane, which is ``student_seconds`` when labs are graded one at a time), so
two gradings of the same submission compare equal once those are dropped.
"""

from __future__ import annotations

import contextlib
import dataclasses
import json
import math
import os
import tempfile
from dataclasses import dataclass, field, fields
from pathlib import Path

from ..loading.text import printable

# Check statuses, in the words reports use. ADVICE is a tip worth 0 points (an
# advice check that had something to say, or the engine's own, e.g. inputs
# modified in place): never a failure, never part of a score.
PASSED, PARTIAL, FAILED, NOT_IMPLEMENTED, ERROR, ADVICE = (
    "passed", "partial", "failed", "not implemented", "grader error", "advice")
TIMING_KEYS = {"seconds", "student_seconds", "student_wall_seconds", "graded_at"}
NOT_STARTED = "not implemented yet"   # an exercise's message when all its functions are the skeleton's stubs


@dataclass
class Artifact:
    """A picture for the feedback page.

    ``kind`` is ``"images"`` (``items``: ``{"label", "mime", "data", "width", "height",
    "encoded_size"}``, base64 PNG or JPEG data made small for a page, see
    :func:`autograder.engine.pictures.picture_item`) or ``"svg"`` (``items``: ``{"label",
    "svg"}`` with inline SVG markup).
    """

    kind: str
    title: str
    items: list[dict] = field(default_factory=list)
    caption: str = ""


@dataclass
class CheckResult:
    name: str
    score: float
    max_score: float
    status: str
    message: str = ""
    hint: str = ""
    hidden: bool = False
    mistake: str = ""   # the named mistake, if the check recognised one
    failure: str = ""   # how the student's code failed, if it did: "timeout", "crashed", ...
    output: str = ""
    traceback: str = ""
    artifacts: list[Artifact] = field(default_factory=list)
    seconds: float = 0.0
    student_seconds: float = 0.0
    redacted: bool = False  # a hidden check as students see it before release: its verdict only
    inputs_digest: str = ""  # what the check gave the student's functions (Trial.given): same files, same digest

    def __post_init__(self):
        # Its texts carry the student's (printed output, exception messages, names from their code): made inert once,
        # here, for every report -- the page, JSON, results.json, the terminal, the gradebook.
        self.message, self.hint, self.output, self.traceback = (
            printable(self.message), printable(self.hint), printable(self.output), printable(self.traceback))

    @property
    def passed(self) -> bool:
        return self.status == PASSED

    @property
    def advice(self) -> bool:
        """A tip (0 points) rather than a verdict."""
        return self.status == ADVICE

    @property
    def lost_points(self) -> bool:
        return self.score < self.max_score

    def to_dict(self) -> dict:
        # What asdict() gives, without its deep copy of every string (a tenth of a second a grading).
        data = {f.name: getattr(self, f.name) for f in fields(self)}
        data["artifacts"] = [{"kind": a.kind, "title": a.title, "items": [dict(item) for item in a.items],
                              "caption": a.caption} for a in self.artifacts]
        data["passed"] = self.passed
        data["advice"] = self.advice
        return data


@dataclass
class ExerciseResult:
    id: str
    title: str
    functions: list[str]
    checks: list[CheckResult] = field(default_factory=list)
    message: str = ""
    rules: list[str] = field(default_factory=list)  # the instructor's extra rules, for the student

    def __post_init__(self):
        self.message = printable(self.message)   # (a module that does not import: its message is the student's)

    @property
    def score(self) -> float:
        return round(sum(c.score for c in self.checks), 6)

    @property
    def max_score(self) -> float:
        return round(sum(c.max_score for c in self.checks), 6)

    @property
    def not_started(self) -> str:
        """One line for an exercise none of whose functions is written yet, or ``""``: its
        stubs only raise NotImplementedError (:data:`NOT_STARTED`), or the module (a
        notebook, say) defines none of them (``"not started: scaling_matrix() and scale()
        are not defined yet"``). Reports say it once instead of a line per check."""
        if self.message == NOT_STARTED:
            return NOT_STARTED
        graded = [c for c in self.checks if c.max_score > 0 and not c.redacted]
        if self.message or not graded or any(c.failure != "missing_function" for c in graded):
            return ""
        names = [f"{f.split('(')[0]}()" for f in self.functions]
        listed = names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"
        return f"not started: {listed} {'is' if len(names) == 1 else 'are'} not defined yet"

    def to_dict(self) -> dict:
        return {"id": self.id, "title": self.title, "functions": self.functions,
                "score": self.score, "max_score": self.max_score, "message": self.message,
                "rules": list(self.rules), "checks": [c.to_dict() for c in self.checks]}


@dataclass
class GradingResult:
    submission: str
    submission_hash: str
    grader_version: str
    exercises: list[ExerciseResult] = field(default_factory=list)
    seconds: float = 0.0
    student_seconds: float = 0.0
    hidden_included: bool = True
    notes: list[str] = field(default_factory=list)  # how the submission was read (renames...)
    graded_at: str = ""  # ISO 8601 time of the grading, UTC
    student_wall_seconds: float = 0.0  # wall time during which student code ran (in any lane)
    hidden_points_withheld: bool = False  # a students' view whose scores leave hidden checks out
    confinement: str = ""  # the level student code ran at (autograder.sandbox.confine.LEVELS)
    confinement_warning: str = ""  # why that is weaker than this machine allows ("" when it is not)
    # A lab handed in more than once: per file not graded, {"module", "file", "graded", "why"}
    # (autograder.loading.handed_in.NotGraded.to_dict); ``notes`` says the same in words.
    files_not_graded: list[dict] = field(default_factory=list)
    # The libraries that judged it, {"python", "numpy", "opencv"} -> version (the worker runs
    # the grader's interpreter: autograder.engine.versions.judged_with); {} in results stored
    # before versions were recorded.
    versions: dict[str, str] = field(default_factory=dict)

    @property
    def total(self) -> float:
        return round(sum(e.score for e in self.exercises), 6)

    @property
    def max_total(self) -> float:
        return round(sum(e.max_score for e in self.exercises), 6)

    def to_dict(self) -> dict:
        return {"submission": self.submission, "submission_hash": self.submission_hash,
                "grader_version": self.grader_version, "total": self.total,
                "max_total": self.max_total, "hidden_included": self.hidden_included,
                "seconds": self.seconds, "student_seconds": self.student_seconds,
                "student_wall_seconds": self.student_wall_seconds, "notes": self.notes, "graded_at": self.graded_at,
                "hidden_points_withheld": self.hidden_points_withheld,
                "confinement": self.confinement, "confinement_warning": self.confinement_warning,
                "files_not_graded": [dict(f) for f in self.files_not_graded],
                "versions": dict(self.versions),
                "exercises": [e.to_dict() for e in self.exercises]}

    @classmethod
    def from_dict(cls, data: dict) -> "GradingResult":
        exercises = []
        for e in data["exercises"]:
            checks = []
            for c in e["checks"]:
                c = {k: v for k, v in c.items() if k not in ("passed", "advice")}
                c["artifacts"] = [Artifact(**a) for a in c.get("artifacts", [])]
                checks.append(CheckResult(**c))
            exercises.append(ExerciseResult(e["id"], e["title"], e.get("functions", []),
                                            checks, e.get("message", ""), e.get("rules", [])))
        return cls(data["submission"], data["submission_hash"], data["grader_version"],
                   exercises, data.get("seconds", 0.0), data.get("student_seconds", 0.0),
                   data.get("hidden_included", True), data.get("notes", []), data.get("graded_at", ""),
                   data.get("student_wall_seconds", data.get("student_seconds", 0.0)),
                   data.get("hidden_points_withheld", False), data.get("confinement", ""),
                   data.get("confinement_warning", ""), list(data.get("files_not_graded", [])),
                   dict(data.get("versions") or {}))

    def in_points(self, factors: dict[str, float]) -> "GradingResult":
        """This grading in the course's points: each check's score and maximum times its
        exercise's factor (``CourseConfig.point_factors``; 1 for an exercise not named)."""
        if all(f == 1.0 for f in factors.values()):
            return self
        # Each check's maximum to a ten-thousandth of a point, a lab's rounded together so they add up to its
        # points exactly (largest remainders: 20 points over 65 raw ones are 20, not 19.9992); a full score is its
        # check's maximum, a partial one its share of it.
        scaled = {(e.id, k): c.max_score * factors.get(e.id, 1.0)
                  for e in self.exercises for k, c in enumerate(e.checks) if factors.get(e.id, 1.0) != 1.0}
        maxima: dict = {}
        for lab in dict.fromkeys(key[0].split(".")[0] for key in scaled):
            keys = [key for key in scaled if key[0].split(".")[0] == lab]
            units = {key: math.floor(scaled[key] * 10_000 + 1e-6) for key in keys}
            left = round(sum(scaled[key] for key in keys) * 10_000) - sum(units.values())
            for key in sorted(keys, key=lambda key: units[key] - scaled[key] * 10_000)[:max(0, left)]:
                units[key] += 1
            maxima.update({key: units[key] / 10_000 for key in keys})

        def rescaled(exercise, k, check):
            if (exercise.id, k) not in maxima:
                return check
            most = maxima[(exercise.id, k)]
            share = check.score / check.max_score if check.max_score else 0.0
            return dataclasses.replace(check, max_score=most, score=most if share >= 1 else round(most * share, 4))

        exercises = [ExerciseResult(e.id, e.title, list(e.functions), [rescaled(e, k, c) for k, c in enumerate(e.checks)],
                                    e.message, list(e.rules))
                     for e in self.exercises]
        return dataclasses.replace(self, exercises=exercises)

    def for_students(self, points_visible: bool = False) -> "GradingResult":
        """What a student may see before the instructor releases the hidden checks.

        The one place where hidden checks are kept from students: every report a
        student reads (terminal, feedback page, ``results.json``, Gradescope's text,
        ``check()``) renders this view, never the grading itself. Each hidden check
        becomes ``"hidden check N"`` (its own name may hold its inputs) with a verdict,
        ``"passed"`` or ``"not passed"``, and nothing else: no message, hint, printed
        output, traceback, picture, named mistake or timing of its own.
        Hidden advice (tips) is left out. With ``points_visible`` the hidden checks keep
        their points; otherwise they count for nothing here (``max_score`` 0), so no
        exercise score or total tells what they earned (``hidden_points_withheld``).
        The grading itself is not changed; a view of a view is the same view.
        """
        exercises = []
        for exercise in self.exercises:
            checks, hidden = [], 0
            for check in exercise.checks:
                if not (check.hidden or check.redacted):
                    checks.append(check)
                elif check.max_score > 0 or check.redacted:  # hidden advice: left out
                    hidden += 1
                    checks.append(_redacted(check, hidden, points_visible, exercise.message))
            exercises.append(ExerciseResult(exercise.id, exercise.title, list(exercise.functions), checks,
                                            exercise.message, list(exercise.rules)))
        withheld = self.hidden_points_withheld or (
            not points_visible and any(c.redacted for e in exercises for c in e.checks))
        return GradingResult(self.submission, self.submission_hash, self.grader_version, exercises,
                             self.seconds, self.student_seconds, self.hidden_included, list(self.notes),
                             self.graded_at, self.student_wall_seconds, withheld, self.confinement,
                             self.confinement_warning, [dict(f) for f in self.files_not_graded],
                             dict(self.versions))


# All a student reads of a hidden check before release, besides its points where shown.
HIDDEN_PASSED, HIDDEN_NOT_PASSED = "passed", "not passed"
HIDDEN_NOT_GRADED = "not graded: an error in the grader, not in your code"


def _redacted(check: CheckResult, number: int, points_visible: bool, module_message: str) -> CheckResult:
    """Hidden check ``number`` of its exercise as a student sees it (see :meth:`GradingResult.for_students`).
    ``module_message`` is the exercise's own (the module was not found, did not import...):
    the reason of every check, hidden or not, it says nothing of any."""
    if check.status == ERROR:
        status, message = ERROR, HIDDEN_NOT_GRADED
    elif check.passed:
        status, message = PASSED, HIDDEN_PASSED
    else:  # a partial score is told by the points, where they are shown
        status = PARTIAL if points_visible and check.score > 0 else FAILED
        message = HIDDEN_NOT_PASSED
    if module_message and check.message == module_message:
        message = module_message
    score, max_score = (check.score, check.max_score) if points_visible else (0.0, 0.0)
    return CheckResult(f"hidden check {number}", score, max_score, status, message, hidden=True, redacted=True)


def without_timings(data):
    """A copy of a results dict with every timing field removed (for comparisons)."""
    if isinstance(data, dict):
        return {k: without_timings(v) for k, v in data.items() if k not in TIMING_KEYS}
    if isinstance(data, list):
        return [without_timings(v) for v in data]
    return data


def write_atomically(path, text: str) -> None:
    """Write ``text`` to ``path`` via a temporary file beside it, flushed to the disk, and a
    rename: never half a file, nor an empty one after a power cut. On failure the temporary
    file is removed and the ``OSError`` names ``path`` (not the temporary file)."""
    path = Path(path)
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; a report is an ordinary file
        os.replace(tmp, path)
    except BaseException as exc:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        if isinstance(exc, OSError) and exc.filename != str(path):
            raise OSError(exc.errno, exc.strerror or str(exc), str(path)) from exc
        raise


def strip_pictures(data: dict) -> dict:
    """A results-model dict without pictures (``artifacts`` emptied), for storage and results.json."""
    data = dict(data)
    data["exercises"] = [
        {**e, "checks": [{**c, "artifacts": []} for c in e["checks"]]} for e in data.get("exercises", [])]
    return data


def write_json(result: GradingResult, path, pictures: bool = False) -> None:
    """The results model as JSON; pictures (base64, megabytes) only when asked for."""
    data = result.to_dict()
    write_atomically(path, json_text(data if pictures else strip_pictures(data)))


def json_text(data: dict) -> str:
    """A results-model dict as the text of a ``results.json`` file (indented: people read it)."""
    return json.dumps(data, indent=1, allow_nan=False) + "\n"
