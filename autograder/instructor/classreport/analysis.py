"""What a class got wrong: statistics over many students' results, as plain data.

The input is one :class:`StudentRecord` per student, each holding the results
model as JSON (``GradingResult.to_dict()``, see :mod:`autograder.engine.results`), or
the reason there is none. :func:`summarise` turns a class into a
:class:`ClassSummary`: score distributions, pass rate per check, the named
mistakes per exercise, and the students whose code hung, crashed, failed to
import or called a forbidden function. Nothing here renders or reads files.

Named mistakes come from a check result's ``mistake`` field (set by the shared
judges when they recognise a mistake). Results written before that field
existed are read too: a message's "it looks like <mistake>." names it, and any
other failure is grouped by its first sentence with the numbers blanked out.
"""

from __future__ import annotations

import re
import statistics
from dataclasses import dataclass, field

from ...engine.results import ERROR, NOT_IMPLEMENTED, PASSED

# How student code failed (the sandbox's outcome kinds) that an instructor wants listed per student.
INCIDENT_KINDS = {
    "timeout": "timeout",
    "crashed": "crash",
    "memory": "out of memory",
    "output_too_large": "too much output",
    "recursion": "infinite recursion",
    "import_error": "import failure",
    "forbidden_call": "forbidden call",
    "grader_error": "grader error",
}
NOT_HANDED_IN = "missing_module"


@dataclass
class StudentRecord:
    """One student of the class, as the gradebook knows them.

    Attributes
    ----------
    student_id : str
        Stable identifier (the batch derives it from the submission entry).
    name : str
        Display name; the id when unknown.
    status : str
        ``"graded"``, or a word for why there is no result (``"unreadable"`` ...).
    reason : str
        Why the submission was not graded (empty when it was).
    result : dict or None
        The results model as JSON (``GradingResult.to_dict()``), pictures optional.
    feedback_href : str
        Link to the student's ``feedback.html``, relative to the class page.
    final, final_max : float or None
        The final grade (course points, late penalty, overrides) where one is known.
    rules : list of str
        What the course's rules for this student did, in a few words ("extension +2 days",
        "excused", "late 1 day, -3"): the list of students shows them beside the grade.
    """

    student_id: str
    name: str = ""
    status: str = "graded"
    reason: str = ""
    result: dict | None = None
    feedback_href: str = ""
    final: float | None = None
    final_max: float | None = None
    rules: list[str] = field(default_factory=list)

    @property
    def label(self) -> str:
        return self.name or self.student_id


@dataclass
class Distribution:
    """Scores of the students who attempted something, out of ``max_score``."""

    max_score: float
    scores: list[float]

    @property
    def mean(self) -> float | None:
        return statistics.fmean(self.scores) if self.scores else None

    @property
    def median(self) -> float | None:
        return statistics.median(self.scores) if self.scores else None

    def histogram(self, bins: int = 10) -> list[int]:
        """Counts in ``bins`` equal bins over [0, max_score] (the top bin holds full marks)."""
        counts = [0] * bins
        for score in self.scores:
            fraction = score / self.max_score if self.max_score else 0.0
            counts[min(max(int(fraction * bins), 0), bins - 1)] += 1
        return counts


@dataclass
class MistakeGroup:
    """Students whose work on one exercise shows the same mistake (each counted once)."""

    exercise_id: str
    label: str
    named: bool                       # recognised by a check, not just a grouped message
    students: list[StudentRecord] = field(default_factory=list)
    checks: set[str] = field(default_factory=set)

    @property
    def count(self) -> int:
        return len(self.students)


@dataclass
class ExerciseSummary:
    id: str
    title: str
    distribution: Distribution
    attempted: int                    # students with at least one implemented check
    mistakes: list[MistakeGroup]      # named ones, most common first
    other_failures: list[MistakeGroup]  # unnamed failures grouped by message

    def percent(self, group: MistakeGroup) -> float:
        return 100.0 * group.count / self.attempted if self.attempted else 0.0


@dataclass
class CheckSummary:
    exercise_id: str
    name: str
    hidden: bool
    attempted: int
    passed: int

    @property
    def pass_rate(self) -> float:
        return self.passed / self.attempted if self.attempted else 0.0


@dataclass
class LabSummary:
    key: str
    submitted: int                    # students who handed in work for the lab
    distribution: Distribution


@dataclass
class Incident:
    """Student code that hung, crashed, did not import or used a forbidden call."""

    student: StudentRecord
    kind: str                         # a key of INCIDENT_KINDS
    message: str
    where: list[str] = field(default_factory=list)   # exercise ids

    @property
    def what(self) -> str:
        return INCIDENT_KINDS.get(self.kind, self.kind)


@dataclass
class ClassSummary:
    students: list[StudentRecord]
    total: Distribution
    labs: list[LabSummary]
    exercises: list[ExerciseSummary]
    checks: list[CheckSummary]        # hardest first
    incidents: list[Incident]
    not_graded: list[StudentRecord]
    # Students who handed a lab in more than once, with the files not graded (each a
    # NotGraded.to_dict(): module, file, graded, why), in the order of ``students``.
    files_not_graded: list[tuple[StudentRecord, list[dict]]] = field(default_factory=list)

    @property
    def graded(self) -> list[StudentRecord]:
        return [s for s in self.students if s.result is not None]


# ---------------------------------------------------------------- reading one check
_LOOKS_LIKE = re.compile(r"it looks like (.+?)(?: inside your function\b.*)?(?:\.(?:\s|$)|\n|$)", re.S)
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?", re.I)
_INCIDENT_MESSAGES = [   # for results without a ``failure`` field
    ("timeout", re.compile(r"did not finish within|timed out")),
    ("memory", re.compile(r"ran out of memory|(?:used|asked for) more than \d+ MB of memory|"
                          r"was killed by the system while holding")),
    ("crashed", re.compile(r"segmentation fault|ended the worker process|was killed|aborted\b|"
                           r"CPU time limit|was stopped by SIG|closed the grader's pipe|"
                           r"started more than \d+ processes")),
    ("recursion", re.compile(r"recursed too deeply")),
    ("forbidden_call", re.compile(r"which this exercise asks you to implement yourself")),
    (NOT_HANDED_IN, re.compile(r"^module \S+\.py not found")),
    ("import_error", re.compile(r"failed to import|while being imported|^SyntaxError in|^\w*Error in \S+\.py, line")),
]


def failure_kind(check: dict) -> str:
    """How the student's code failed in this check (``""`` if it ran)."""
    if check.get("failure"):
        return check["failure"]
    if check.get("status") == ERROR:
        return "grader_error"
    message = check.get("message") or ""
    for kind, pattern in _INCIDENT_MESSAGES:
        if pattern.search(message):
            return kind
    return ""


def mistake_of(check: dict) -> tuple[str, bool] | None:
    """``(label, named)`` for a check that lost points, ``None`` if there is nothing to group.

    Passed and not-implemented checks, and failures listed as incidents, have no mistake.
    """
    if check.get("status") in (PASSED, NOT_IMPLEMENTED) or check.get("passed"):
        return None
    if check.get("mistake"):
        return _readable(check["mistake"], check.get("message") or ""), True
    if failure_kind(check) in INCIDENT_KINDS or failure_kind(check) == NOT_HANDED_IN:
        return None
    message = (check.get("message") or "").strip()
    if not message:
        return None
    named = _LOOKS_LIKE.search(message)
    if named:
        return named.group(1).strip(), True
    return first_sentence(message), False


# The error model's names and its repairs carry an operator id as their label (``mutant:sign``,
# ``repair:swap_items``): an instructor reads the sentence the student was given instead -- a mutant's is
# written from the reference's code, the same for every student it names -- and, for a repair (the
# student's own code changed, their own lines), the function it mended and the kind of change.
_ERROR_MODEL = "The error model: it looks like "
_ERROR_MODEL_SAID = re.compile(r"(.+?)(?: \([a-z ,+]+\))?\.(?:\s|$)", re.S)
_SENTENCE_CHARS = 600   # of the message read for the sentence (a lazy match over a bounded stretch)
_REPAIRED = re.compile(r"makes `([A-Za-z_][A-Za-z0-9_]*)` give the expected answers")


def _readable(mistake: str, message: str) -> str:
    """A check's ``mistake`` label as an instructor reads it in the class's list of mistakes."""
    kind, _, operator = mistake.partition(":")
    words = operator.replace("_", " ").replace("+", " and ")
    if kind == "mutant":
        start = message.find(_ERROR_MODEL)
        said = _ERROR_MODEL_SAID.match(message, start + len(_ERROR_MODEL), start + len(_ERROR_MODEL) + _SENTENCE_CHARS) \
            if start >= 0 else None
        return said.group(1).strip() if said else f"the error model's {words}"
    if kind == "repair":
        mended = _REPAIRED.search(message)
        return f"one change of {f'`{mended.group(1)}`' if mended else 'the code'} mends it ({words})"
    return mistake


_RAISED_ON = " (raised on "   # the input a relayed exception came from, at the sentence's end (lab07.py, lab08.py)


def first_sentence(message: str) -> str:
    """The message's first sentence with every number blanked and the input it names left out: failures that
    differ only in numbers, or one exception relayed by several checks, each on its own input, group together."""
    line = message.strip().splitlines()[0]
    sentence = re.split(r"(?<=[.!?])\s", line, maxsplit=1)[0].rstrip(".:; ")
    if sentence.endswith(")") and _RAISED_ON in sentence:   # (string search: a student's text read once)
        sentence = sentence[:sentence.rfind(_RAISED_ON)]
    return _NUMBER.sub("#", sentence)


def _attempted(exercise: dict) -> bool:
    """The student handed in code for this exercise and implemented some of it."""
    return any(c.get("status") != NOT_IMPLEMENTED and failure_kind(c) != NOT_HANDED_IN
               for c in exercise.get("checks", []))


# ---------------------------------------------------------------- the class
def summarise(students: list[StudentRecord]) -> ClassSummary:
    """Statistics of a class; students without a result are listed in ``not_graded``."""
    graded = [s for s in students if s.result is not None]
    exercise_order: dict[str, dict] = {}           # first seen id -> {"title", "max_score"}
    scores: dict[str, list[float]] = {}
    attempted: dict[str, int] = {}
    groups: dict[tuple[str, str, bool], MistakeGroup] = {}
    check_stats: dict[tuple[str, str], CheckSummary] = {}
    lab_scores: dict[str, dict[str, float]] = {}    # lab -> student id -> score
    lab_max: dict[str, float] = {}
    incidents: dict[tuple[str, str], Incident] = {}
    totals, max_total = [], 0.0

    for student in graded:
        result = student.result
        max_total = max(max_total, float(result.get("max_total") or 0.0))
        attempted_any = False
        for exercise in result.get("exercises", []):
            eid = exercise["id"]
            lab = eid.split(".")[0]
            info = exercise_order.setdefault(eid, {"title": exercise.get("title", ""), "max_score": 0.0})
            info["max_score"] = max(info["max_score"], float(exercise.get("max_score") or 0.0))
            lab_max.setdefault(lab, 0.0)   # labs in the order first seen
            if not _attempted(exercise):
                continue
            attempted_any = True
            attempted[eid] = attempted.get(eid, 0) + 1
            scores.setdefault(eid, []).append(float(exercise.get("score") or 0.0))
            lab_scores.setdefault(lab, {})
            lab_scores[lab][student.student_id] = lab_scores[lab].get(student.student_id, 0.0) + float(
                exercise.get("score") or 0.0)
            seen_here: set[tuple[str, bool]] = set()
            for check in exercise.get("checks", []):
                stats = check_stats.setdefault((eid, check["name"]), CheckSummary(
                    eid, check["name"], bool(check.get("hidden")), 0, 0))
                stats.attempted += 1
                stats.passed += check.get("status") == PASSED
                kind = failure_kind(check)
                if kind in INCIDENT_KINDS:
                    # One line per student and kind, with the first message ("timed out 2 times
                    # already" after a timeout says nothing new).
                    incident = incidents.setdefault((student.student_id, kind), Incident(
                        student, kind, check.get("message", "")))
                    if eid not in incident.where:
                        incident.where.append(eid)
                mistake = mistake_of(check)
                if mistake is None:
                    continue
                group = groups.setdefault((eid,) + mistake, MistakeGroup(eid, *mistake))
                group.checks.add(check["name"])
                if mistake not in seen_here:
                    seen_here.add(mistake)
                    group.students.append(student)
        if attempted_any:
            totals.append(float(result.get("total") or 0.0))
    for eid, info in exercise_order.items():
        lab_max[eid.split(".")[0]] += info["max_score"]

    exercises = []
    for eid, info in exercise_order.items():
        mine = sorted((g for g in groups.values() if g.exercise_id == eid),
                      key=lambda g: (-g.count, g.label))
        exercises.append(ExerciseSummary(
            eid, info["title"], Distribution(info["max_score"], scores.get(eid, [])),
            attempted.get(eid, 0), [g for g in mine if g.named], [g for g in mine if not g.named]))
    labs = [LabSummary(lab, len(lab_scores.get(lab, {})),
                       Distribution(lab_max[lab], list(lab_scores.get(lab, {}).values())))
            for lab in lab_max]
    checks = sorted(check_stats.values(), key=lambda c: (c.pass_rate, c.exercise_id, c.name))
    ordered_incidents = sorted(incidents.values(), key=lambda i: (i.student.label.lower(), i.kind))
    return ClassSummary(students, Distribution(max_total, totals), labs, exercises, checks,
                        ordered_incidents, [s for s in students if s.result is None],
                        [(s, s.result["files_not_graded"]) for s in graded if s.result.get("files_not_graded")])
