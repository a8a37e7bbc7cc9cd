"""A course's grading configuration (``--config COURSE``), a small JSON file.

Example ``course.json``::

    {"select": ["lab07", "lab08"], "public_visibility": "visible",
     "hidden_visibility": "after_published", "call_timeout": 10,
     "exercise_budget": 60, "submission_budget": 240,
     "forbid": {"lab08.homography_ransac": ["cv2.findHomography"]}}

``call_timeout`` bounds one call into the student's code, ``exercise_budget`` the
student time of one exercise (calls, timeouts and worker restarts), and
``submission_budget`` the wall-clock time of the whole grading of a submission
(whatever runs: calls, restarts, the grader's judging); checks left when a budget
is spent score 0 as "time budget exhausted". Keep ``submission_budget`` well below
the Gradescope assignment's own timeout, so results are always written.

Every key is optional; unknown keys and bad values are refused with a message.

Hidden checks stay hidden from students until the instructor releases them: in
every report a student reads (terminal, feedback page, ``results.json``, check(),
Gradescope's text) a hidden check is "hidden check N" with "passed" or "not
passed", never its inputs, messages, output or pictures. ``hidden_points_visible``
(default false) also shows its points; while false, the scores students see leave
the hidden checks out. On Gradescope the hidden tests carry their points anyway
(the grade needs them) and Gradescope keeps them, and the total, from students
until the tests' ``hidden_visibility`` allows (``after_published``: until the
grades are published; ``after_due_date``: until the due date). With ``visible``
students see them at once, and with ``hidden`` Gradescope shows the total with
their points in it: either needs ``hidden_points_visible: true``.

``forbid`` (off by default) adds the instructor's own rules to the lab sheet's:
inside the student function ``labNN.function``, calling any of the listed
library functions (``module.name``) fails the check with "... which this
exercise asks you to implement yourself". The feedback lists the rule under
the exercise, so students see it before they lose a point.

Keys read by ``autograder batch`` (instructor grading):

``select``
    The labs/exercises making up the assignment. Default: the course's own ``labs`` when it
    has some (list built-in ones too to grade them as well:
    ``"select": ["lab07", "lab13"]``), else every built-in lab; every exercise of each.
``assignment``
    The assignment's name: the grade column of the Canvas and Moodle CSVs.
``points``
    Rescaled points, by lab or exercise: ``{"lab07": 20, "lab08.ex2": 5}``. A lab's
    entry scales all its exercises alike; an exercise's entry wins over its lab's.
    Default: the checks' own points.
``canvas_assignment_id``
    The assignment's number in Canvas (``.../assignments/12345``). Canvas fills an
    existing assignment from an import only when its column is named
    ``"<assignment> (<id>)"``; without this key the id is taken from the roster
    when the roster is Canvas's own gradebook export holding a column for the
    assignment.
``lms_exports``
    Which LMS imports to write: ``["canvas", "moodle"]``. Default: the Canvas
    import always, Moodle's worksheet only for a Moodle download or a roster with
    Moodle's ``Identifier`` column.
``late_penalty``
    ``{"due": "2026-03-01T23:59:00+01:00", "grace_minutes": 15, "per_day": 10,
    "max": 50}``. A submission ``d`` started days late (after the grace period)
    loses ``min(max, per_day * d)`` percent of the points it earned. The time comes
    from the download (Gradescope's ``:created_at:``); where only a late flag is
    known (Canvas's ``_LATE_``) it counts as one day late. No ``late_penalty``, no
    penalty. An override row with exercise ``late`` replaces the penalty.

``rubric``
    The lab report's rubric, per exercise: a list of items, each with an ``id``
    (letters, digits, ``-``, ``_``; unique within the exercise), a ``text`` and
    ``points`` (positive: earned when applied; negative: a deduction)::

        "rubric": {"lab08.ex3": [
            {"id": "corners", "text": "explains the black corners of the warp", "points": 2},
            {"id": "no-figure", "text": "discusses no figure", "points": -1}]}

    ``autograder batch`` stores it in the gradebook, where ``autograder review``
    applies and edits the items; the points of the items applied to a student's
    exercise are added to their final grade (see ``autograder review``), and the
    exercise's report is worth the sum of its positive items.

Read by ``autograder similarity`` (and ``autograder batch --similarity``):

``similarity_threshold``
    Default 0.5. Pairs of submissions whose score -- the mean share of each
    file's own code (skeleton excluded) found in the other -- is at least this
    are shown side by side. Disguised copies score about 0.9, independent work
    about 0.1.

Read by every grading (``autograder batch``, Gradescope, ``grade --config``):

``inputs_secret``
    Default none. The course's secret from which, with each submission's content,
    the property checks draw their inputs (see :mod:`autograder.engine.inputs`): the same
    files always meet the same inputs, and nobody without the secret knows which.
    Keep it out of the student bundle (it never ships there) and out of anything
    students see; ``$AUTOGRADER_INPUTS_SECRET`` works too. ``gradescope build``
    makes one when the configuration has none.

``allow_weaker_confinement``
    Default false: Gradescope does not run a submission where student code would
    be less confined than the machine allows (a namespaced level that is there but
    fails, a level forced weaker); the student is told to ask the instructor and the
    log says why. True accepts grading at the weaker level.

``error_model``
    Default true: the Gradescope zip holds the reference solutions (the built-in labs' and
    the course labs' ``reference/``) so that the error model names mistakes nobody listed
    there too; student code never sees them (the worker's file system holds neither them nor
    the hidden checks). False leaves them out: the container then names only what the
    checks name by hand.

``labs``
    Default none. The course's own labs, beside the built-in ones: folders written like
    them (``suite.py``, ``hidden.py``, ``reference/``, ``skeleton/``, ``mistakes.py``; see
    :mod:`autograder.engine.labfolders`), relative to this file:
    ``"labs": ["labs/flow"]``. Their lab keys must be new (``lab13``); they are graded,
    listed (``autograder list --course``), bundled and shipped like the built-in labs.

``opencv``
    Default ``"5"``. The OpenCV major the course grades with, ``"4"`` or ``"5"``: the student
    bundle and Gradescope's ``setup.sh`` install its pins (``constraints.txt``, or
    ``constraints-opencv4.txt`` shipped as ``constraints.txt``), and ``autograder batch``
    stops, saying what to install, in an environment with the other major. A few OpenCV
    calls behave differently between the two (``cv2.minMaxLoc`` on a one-row array); every
    result says which NumPy and OpenCV judged it.

``hide``
    Default none. Checks of any lab graded as hidden checks for this course (students
    see their verdict only): ``"hide": ["lab07.ex1::translate_grey", "lab08.ext1"]``, a
    check's id (``autograder list --ids``), an exercise or a lab. The check's code
    still ships in the student bundle when it is a public one.

Read by ``autograder verify`` (lab authors):

``min_mistakes``
    Default 5. The fewest cases of its mistakes table each exercise of a lab must have
    (its ``ADVICE`` cases not counted), for every lab verified with this course, built-in
    or the course's own; an exercise below it is a problem unless the table's
    ``FEWER_MISTAKES`` gives the reason. 0: no minimum.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import asdict, dataclass, field, fields, replace
from datetime import datetime
from pathlib import Path

from ..engine.versions import OPENCV_MAJORS

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")
_EXERCISE = re.compile(r"lab\d\d\.[A-Za-z0-9_-]+")                 # lab07.ex1
_RUBRIC_ITEM_ID = re.compile(r"[A-Za-z0-9_-]{1,40}")
RUBRIC_TEXT_LENGTH = 500           # characters of one item's text
RUBRIC_MAX_POINTS = 1000           # |points| of one item
RUBRIC_MAX_ITEMS = 50              # items of one exercise
_STUDENT_FUNCTION = re.compile(r"lab\d\d\.[A-Za-z_]\w*")          # lab08.homography_ransac
_LIBRARY_FUNCTION = re.compile(r"[A-Za-z_]\w*(\.[A-Za-z_]\w*)+")   # cv2.findHomography


class CourseConfigError(ValueError):
    """The course configuration file is malformed."""


LMS_EXPORTS = ("canvas", "moodle")
_GRADING = {"select", "call_timeout", "exercise_budget", "submission_budget", "forbid", "inputs_secret",
            "hidden_points_visible", "labs", "hide"}
# What each mode applies; the rest of a course is refused or warned about there (CourseConfig.ignored_by).
_AUTHORING = {"min_mistakes"}   # read by autograder verify: no grading applies it, and none needs to say so
_APPLIED_BY = {
    "grade": _GRADING,
    "gradescope": _GRADING | {"points", "public_visibility", "hidden_visibility", "stdout_visibility",
                              "allow_weaker_confinement", "opencv", "error_model"},
    "batch": _GRADING | {"assignment", "points", "late_penalty", "extensions", "late_days",
                         "similarity_threshold", "canvas_assignment_id",
                         "lms_exports", "rubric", "opencv"},
}


@dataclass(frozen=True)
class CourseConfig:
    select: list[str] = field(default_factory=list)     # labs/exercises graded; empty = all
    public_visibility: str = "visible"                  # Gradescope visibility of public checks
    hidden_visibility: str = "after_published"          # ... and of hidden checks
    stdout_visibility: str = "hidden"                   # the grader's own log
    call_timeout: float = 10.0                          # seconds per call into student code
    assignment: str = "Computer vision labs"            # grade column name in LMS exports
    points: dict[str, float] = field(default_factory=dict)   # "lab07" / "lab07.ex2" -> points
    late_penalty: dict = field(default_factory=dict)    # due, grace_minutes, per_day, max (percent)
    # Per student (any identity the roster or download knows: id, e-mail, name...): {"days": 3},
    # {"due": "2026-03-08T23:59:00+01:00"} or {"excused": true}.
    extensions: dict = field(default_factory=dict)
    # Pooled late days: {"tokens": 5, "ledger": "late_days.json"} (the ledger, shared by the term's
    # assignments, spends the tokens in the order of their due dates).
    late_days: dict = field(default_factory=dict)
    similarity_threshold: float = 0.5                   # similarity report: pairs shown side by side
    inputs_secret: str = ""                             # property inputs: HMAC(secret, content); see inputs.py
    allow_weaker_confinement: bool = False              # Gradescope grades below the machine's strongest level
    error_model: bool = True                            # the Gradescope zip holds the reference solutions
    exercise_budget: float = 60.0                       # student seconds per exercise
    submission_budget: float = 240.0                    # wall seconds for grading a submission
    forbid: dict = field(default_factory=dict)          # "lab08.homography_ransac": ["cv2.findHomography"]
    hidden_points_visible: bool = False                 # students see hidden checks' points before release
    canvas_assignment_id: str = ""                      # Canvas's id of the assignment: "Lab 7 (12345)"
    lms_exports: list[str] = field(default_factory=list)  # "canvas", "moodle"; empty: as the upload says
    labs: list[str] = field(default_factory=list)       # course lab folders (absolute once loaded)
    hide: list[str] = field(default_factory=list)       # checks graded as hidden: "lab07.ex1::name", "lab07.ex1"
    rubric: dict = field(default_factory=dict)          # "lab07.ex1": [{"id", "text", "points"}, ...]
    opencv: str = "5"                                   # the OpenCV major graded with: "4" or "5" (versions.py)
    min_mistakes: int = 5                               # verify: mistakes-table cases per exercise, at least

    def __post_init__(self):
        for name in ("public_visibility", "hidden_visibility", "stdout_visibility"):
            if getattr(self, name) not in VISIBILITIES:
                raise CourseConfigError(f"{name} must be one of {VISIBILITIES}, got {getattr(self, name)!r}")
        if not (isinstance(self.select, list) and all(isinstance(s, str) for s in self.select)):
            raise CourseConfigError("select must be a list of names like 'lab07' or 'lab07.ex2'")
        for name in ("call_timeout", "exercise_budget", "submission_budget"):
            value = getattr(self, name)
            if isinstance(value, bool) or not (isinstance(value, (int, float)) and value > 0):
                raise CourseConfigError(f"{name} must be a positive number of seconds")
        if not (isinstance(self.assignment, str) and self.assignment.strip()):
            raise CourseConfigError("assignment must be a non-empty name")
        if not (isinstance(self.points, dict) and all(
                isinstance(k, str) and isinstance(v, (int, float)) and not isinstance(v, bool)
                for k, v in self.points.items())):
            raise CourseConfigError("points must map 'lab07' or 'lab07.ex2' to a number of points")
        wrong = [k for k, v in self.points.items() if not (math.isfinite(v) and v >= 0)]   # (JSON reads NaN too)
        if wrong:
            raise CourseConfigError(f"points must be a number, 0 or more: {wrong[0]!r} is given "
                                    f"{self.points[wrong[0]]!r}")
        self._check_late_penalty()
        self._check_extensions()
        if not isinstance(self.inputs_secret, str):
            raise CourseConfigError("inputs_secret must be a string (the course's secret, e.g. 32 random hex digits)")
        if not isinstance(self.allow_weaker_confinement, bool):
            raise CourseConfigError("allow_weaker_confinement must be true or false")
        if not isinstance(self.error_model, bool):
            raise CourseConfigError("error_model must be true or false")
        if not (isinstance(self.similarity_threshold, (int, float)) and 0 < self.similarity_threshold <= 1):
            raise CourseConfigError("similarity_threshold must be a number in (0, 1]")
        self._check_forbid()
        if not (isinstance(self.canvas_assignment_id, str) and re.fullmatch(r"\d*", self.canvas_assignment_id)):
            raise CourseConfigError("canvas_assignment_id must be the assignment's number in Canvas, "
                                    'as text: "12345" (from the assignment\'s address, .../assignments/12345)')
        if not (isinstance(self.lms_exports, list) and set(self.lms_exports) <= set(LMS_EXPORTS)):
            raise CourseConfigError(f"lms_exports must be a list of {list(LMS_EXPORTS)}")
        if not isinstance(self.hidden_points_visible, bool):
            raise CourseConfigError("hidden_points_visible must be true or false")
        for name in ("labs", "hide"):
            if not (isinstance(getattr(self, name), list) and all(isinstance(s, str) and s
                                                                   for s in getattr(self, name))):
                raise CourseConfigError(f'{name} must be a list of names, like "labs": ["labs/flow"] '
                                        'or "hide": ["lab07.ex1::translate_grey"]')
        check_rubric(self.rubric)
        if isinstance(self.min_mistakes, bool) or not isinstance(self.min_mistakes, int) or self.min_mistakes < 0:
            raise CourseConfigError("min_mistakes must be a whole number, 0 or more: the fewest cases of its "
                                    "mistakes table autograder verify asks of each exercise (default 5)")
        if isinstance(self.opencv, int) and not isinstance(self.opencv, bool):   # "opencv": 4 means "4"
            object.__setattr__(self, "opencv", str(self.opencv))
        if self.opencv not in OPENCV_MAJORS:
            raise CourseConfigError(f'opencv must be "4" or "5" (the OpenCV major the course grades with), '
                                    f"got {self.opencv!r}")
        outside = [e for e in self.rubric if self.select and not {e, e.split(".")[0]} & set(self.select)]
        if outside:
            raise CourseConfigError(f"rubric: {', '.join(outside)} not in select ({', '.join(self.select)}): "
                                    "a rubric is for an exercise the assignment grades")
        if self.hidden_visibility in ("visible", "hidden") and not self.hidden_points_visible:
            # Gradescope hides a student's total only while some test is after_due_date/after_published.
            raise CourseConfigError(
                f'hidden_visibility "{self.hidden_visibility}" lets students see what the hidden checks '
                'scored on Gradescope at once (their tests, or the total): set "hidden_points_visible": '
                'true too, or keep hidden_visibility "after_published"')

    def point_factors(self, exercises) -> dict[str, float]:
        """Course points per raw point, by exercise id (``exercises``: (id, raw max) pairs):
        ``points`` rescales a lab's exercises alike, or one exercise; 1 elsewhere."""
        lab_max: dict[str, float] = {}
        for exercise_id, maximum in exercises:
            lab = exercise_id.split(".")[0]
            lab_max[lab] = lab_max.get(lab, 0.0) + maximum
        factors = {}
        for exercise_id, maximum in exercises:
            lab = exercise_id.split(".")[0]
            if exercise_id in self.points:
                factors[exercise_id] = self.points[exercise_id] / maximum if maximum else 0.0
            elif lab in self.points:
                factors[exercise_id] = self.points[lab] / lab_max[lab] if lab_max[lab] else 0.0
            else:
                factors[exercise_id] = 1.0
        return factors

    def ignored_by(self, mode: str) -> list[str]:
        """The keys set in this course (not left at their defaults) that ``mode`` -- ``"grade"``
        (a student's or an instructor's single grading), ``"gradescope"`` or ``"batch"`` --
        does not apply, so the command can say so instead of ignoring them silently."""
        default = CourseConfig()
        return [f.name for f in fields(self) if f.name not in _APPLIED_BY[mode] | _AUTHORING
                and getattr(self, f.name) != getattr(default, f.name)]

    def limits(self):
        """The sandbox limits this course asks for."""
        from ..sandbox.supervisor import Limits

        return Limits(call_timeout=self.call_timeout, exercise_budget=self.exercise_budget,
                      submission_budget=self.submission_budget)

    def _check_forbid(self):
        example = '{"lab08.homography_ransac": ["cv2.findHomography"]}'
        if not isinstance(self.forbid, dict):
            raise CourseConfigError(f"forbid must be an object like {example}")
        for function, libraries in self.forbid.items():
            if not (isinstance(function, str) and _STUDENT_FUNCTION.fullmatch(function)):
                raise CourseConfigError(f"forbid: {function!r} is not a student function like "
                                        f"'lab08.homography_ransac' (example: {example})")
            if not (isinstance(libraries, list) and libraries
                    and all(isinstance(n, str) and _LIBRARY_FUNCTION.fullmatch(n) for n in libraries)):
                raise CourseConfigError(f"forbid[{function!r}] must be a non-empty list of library "
                                        f"functions like 'cv2.findHomography' (example: {example})")

    def forbidden(self, lab: str) -> dict[str, tuple[str, ...]]:
        """The instructor's extra forbids for one lab: student function -> library functions."""
        return {key.split(".", 1)[1]: tuple(names) for key, names in self.forbid.items()
                if key.split(".", 1)[0] == lab}

    def _check_late_penalty(self):
        rule = self.late_penalty
        if not isinstance(rule, dict):
            raise CourseConfigError("late_penalty must be an object (due, grace_minutes, per_day, max)")
        unknown = sorted(set(rule) - {"due", "grace_minutes", "per_day", "max"})
        if unknown:
            raise CourseConfigError(f"late_penalty: unknown keys {unknown}")
        for key in ("grace_minutes", "per_day", "max"):
            if key in rule and not (isinstance(rule[key], (int, float)) and rule[key] >= 0):
                raise CourseConfigError(f"late_penalty.{key} must be a non-negative number")
        if "due" in rule:
            try:
                due = parse_time(str(rule["due"]))
            except ValueError:
                raise CourseConfigError("late_penalty.due must be an ISO 8601 time, "
                                        "e.g. 2026-03-01T23:59:00+01:00") from None
            if due.tzinfo is None:
                raise CourseConfigError("late_penalty.due needs a time zone, e.g. +01:00 or Z")

    def _check_extensions(self):
        example = '{"alice@uni.edu": {"days": 3}, "s2231234": {"due": "2026-03-08T23:59:00+01:00"}, "Bo Chen": {"excused": true}}'
        if not isinstance(self.extensions, dict):
            raise CourseConfigError(f"extensions must be an object of students to their extension, like {example}")
        for who, extension in self.extensions.items():
            if not (isinstance(who, str) and who.strip() and isinstance(extension, dict) and len(extension) == 1
                    and set(extension) <= {"days", "due", "excused"}):
                raise CourseConfigError(f"extensions[{who!r}] must be one of {{\"days\": N}}, {{\"due\": time}} "
                                        f"or {{\"excused\": true}} (example: {example})")
            [(kind, value)] = extension.items()
            if kind == "days" and (isinstance(value, bool) or not isinstance(value, (int, float)) or value < 0):
                raise CourseConfigError(f"extensions[{who!r}].days must be a non-negative number of days")
            if kind == "excused" and value is not True:
                raise CourseConfigError(f"extensions[{who!r}].excused must be true")
            if kind == "due":
                try:
                    due = parse_time(str(value))
                except ValueError:
                    due = None
                if due is None or due.tzinfo is None:
                    raise CourseConfigError(f"extensions[{who!r}].due must be an ISO 8601 time with a time zone")
        rule = self.late_days
        if not isinstance(rule, dict) or set(rule) - {"tokens", "ledger"} or (rule and "tokens" not in rule):
            raise CourseConfigError('late_days must be like {"tokens": 5, "ledger": "late_days.json"} '
                                    "(the ledger is optional: without it, the tokens are this assignment's only)")
        if rule and (isinstance(rule["tokens"], bool) or not isinstance(rule["tokens"], int) or rule["tokens"] < 0):
            raise CourseConfigError("late_days.tokens must be a whole number of days, 0 or more")
        if rule.get("ledger") is not None and not (isinstance(rule["ledger"], str) and rule["ledger"].strip()):
            raise CourseConfigError("late_days.ledger must be a file name")

    @classmethod
    def load(cls, path) -> "CourseConfig":
        try:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise CourseConfigError(f"cannot read course configuration {path}: {exc}") from None
        if not isinstance(data, dict):
            raise CourseConfigError(f"{path}: expected a JSON object")
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(data) - known)
        if unknown:
            raise CourseConfigError(f"{path}: unknown keys {unknown}; known keys are {sorted(known)}")
        if isinstance(data.get("labs"), list):   # relative to this file, wherever the command runs
            folders = [str((Path(path).parent / Path(folder).expanduser()).resolve())
                       if isinstance(folder, str) and folder else folder for folder in data["labs"]]
            # A folder named twice (labs/flow, ./labs/flow) is one.
            data["labs"] = [folder for i, folder in enumerate(folders) if folder not in folders[:i]]
        late = data.get("late_days")
        if isinstance(late, dict) and isinstance(late.get("ledger"), str) and late["ledger"].strip():
            data["late_days"] = {**late, "ledger": str((Path(path).parent / Path(late["ledger"]).expanduser()).resolve())}
        try:   # (every message names the file: an instructor may keep one per assignment)
            course = cls(**data)
            own = course.use_labs(path)
            course.check_selection()
            if own and not course.select:   # a course of its own labs grades those, not every built-in lab too
                course = replace(course, select=own)
            course.check_forbidden_names()
        except CourseConfigError as exc:
            raise CourseConfigError(str(exc) if str(exc).startswith(f"{path}:") else f"{path}: {exc}") from None
        return course

    def check_selection(self) -> None:
        """Every name in ``select`` grades something (its labs registered): a misspelt one would
        otherwise be noticed only by a grading that reads it -- never by one that selects on the
        command line. Raises :class:`CourseConfigError` naming the first that does not."""
        from ..engine.registry import SelectionError, select

        for selector in self.select:
            try:
                select([selector])
            except SelectionError as exc:
                raise CourseConfigError(f"select: {exc}") from None

    def check_forbidden_names(self) -> None:
        """Every ``forbid`` key names a student function some exercise grades (its lab registered), and every
        library function it lists exists in the library installed: a misspelt name would forbid nothing, silently.
        Raises :class:`CourseConfigError` naming the first that does not."""
        import difflib
        import importlib

        from ..engine.registry import discover

        labs = discover()
        for key, libraries in self.forbid.items():
            lab, function = key.split(".", 1)
            graded = sorted({name for e in labs[lab].exercises.values() for name in e.signatures}) if lab in labs else []
            if function not in graded:
                close = difflib.get_close_matches(function, graded, n=1)
                raise CourseConfigError(f"forbid: {key} is not a function any exercise grades"
                                        + (f" (did you mean {lab}.{close[0]}?)" if close else ""))
            for name in libraries:
                top, *path = name.split(".")
                try:
                    found = importlib.import_module({"np": "numpy"}.get(top, top))
                except ImportError:
                    continue   # (a library this machine lacks: the students' may have it)
                for part in path:
                    owner, found = found, getattr(found, part, None)
                    if found is None:
                        known = [n for n in dir(owner) if not n.startswith("_")]
                        close = difflib.get_close_matches(part, known, n=1)
                        raise CourseConfigError(f"forbid[{key!r}]: {name} is not a function of the {top} installed"
                                                + (f" (did you mean {name.rsplit('.', 1)[0]}.{close[0]}?)" if close
                                                   else ""))

    def use_labs(self, where="the course configuration") -> list[str]:
        """Register this course's lab folders (``labs``, forgetting another course's) and
        hide its ``hide`` checks, so every later selection sees them; returns the keys of
        its labs (``lab13``), in its order. Raises :class:`CourseConfigError` saying what is
        wrong with a folder."""
        from ..engine.labfolders import LabFolderError, use_lab_folders
        from ..engine.registry import SelectionError, hide_checks

        try:
            labs = use_lab_folders(self.labs)
            hide_checks(self.hide)
        except (LabFolderError, SelectionError) as exc:
            raise CourseConfigError(f"{where}: {exc}") from None
        return [lab.key for lab in labs]

    def to_json(self) -> str:
        return json.dumps(asdict(self), indent=2) + "\n"


def check_rubric(rubric) -> None:
    """Raise :class:`CourseConfigError`, saying which item and why, unless ``rubric`` maps
    exercise ids of the labs to lists of items ``{"id", "text", "points"}`` (see the module
    docstring)."""
    example = ('{"lab08.ex3": [{"id": "corners", "text": "explains the black corners of the warp", '
               '"points": 2}]}')
    if not isinstance(rubric, dict):
        raise CourseConfigError(f"rubric must be an object of exercises to their items, like {example}")
    known = None
    for exercise, items in rubric.items():
        if not (isinstance(exercise, str) and _EXERCISE.fullmatch(exercise)):
            raise CourseConfigError(f"rubric: {exercise!r} is not an exercise id like 'lab07.ex1' (example: {example})")
        if known is None:
            from ..engine.registry import discover

            known = {e.id for lab in discover().values() for e in lab.exercises.values()}
        if exercise not in known:
            same_lab = sorted(e for e in known if e.split(".")[0] == exercise.split(".")[0])
            raise CourseConfigError(f"rubric: {exercise} is no exercise of the labs"
                                    + (f" ({exercise.split('.')[0]} has {', '.join(same_lab)})" if same_lab else ""))
        if not (isinstance(items, list) and items):
            raise CourseConfigError(f"rubric[{exercise!r}] must be a non-empty list of items (example: {example})")
        if len(items) > RUBRIC_MAX_ITEMS:
            raise CourseConfigError(f"rubric[{exercise!r}] has {len(items)} items; at most {RUBRIC_MAX_ITEMS}")
        seen = set()
        for number, item in enumerate(items, 1):
            where = f"rubric[{exercise!r}] item {number}"
            if not isinstance(item, dict):
                raise CourseConfigError(f"{where} must be an object with id, text and points (example: {example})")
            unknown = sorted(set(item) - {"id", "text", "points"})
            missing = [key for key in ("id", "text", "points") if key not in item]
            if unknown or missing:
                raise CourseConfigError(f"{where}: " + "; ".join(
                    ([f"unknown keys {unknown}"] if unknown else []) + ([f"missing {missing}"] if missing else []))
                    + " (an item has id, text and points)")
            check_rubric_item(item["id"], item["text"], item["points"], where)
            if item["id"] in seen:
                raise CourseConfigError(f"{where}: the id {item['id']!r} is used twice in {exercise}")
            seen.add(item["id"])


def check_rubric_item(item_id, text, points, where: str = "rubric item") -> None:
    """One rubric item's fields, as the course file and the review application take them."""
    if not (isinstance(item_id, str) and _RUBRIC_ITEM_ID.fullmatch(item_id)):
        raise CourseConfigError(f"{where}: id must be 1 to 40 letters, digits, '-' or '_', got {item_id!r}")
    if not (isinstance(text, str) and text.strip() and len(text) <= RUBRIC_TEXT_LENGTH
            and not any(ord(c) < 32 for c in text)):
        raise CourseConfigError(f"{where}: text must be one line of 1 to {RUBRIC_TEXT_LENGTH} characters")
    if isinstance(points, bool) or not isinstance(points, (int, float)) or not math.isfinite(points) \
            or abs(points) > RUBRIC_MAX_POINTS:
        raise CourseConfigError(f"{where}: points must be a number from -{RUBRIC_MAX_POINTS} to "
                                f"{RUBRIC_MAX_POINTS} (negative: a deduction), got {points!r}")


def parse_time(text: str) -> datetime:
    """An ISO 8601 time; ``Z`` and Gradescope's ``2026-03-01 23:59:00.1 -08:00`` too (Python 3.10)."""
    text = text.strip().replace(" -", "-").replace(" +", "+")
    if text.endswith(("Z", "z")):
        text = text[:-1] + "+00:00"
    date, _, rest = text.partition("T") if "T" in text else text.partition(" ")
    if "." in rest:  # Python 3.10 accepts 3 or 6 fraction digits only
        clock, _, fraction = rest.partition(".")
        digits = len(fraction) - len(fraction.lstrip("0123456789"))
        rest = f"{clock}.{fraction[:digits][:6].ljust(6, '0')}{fraction[digits:]}"
    return datetime.fromisoformat(f"{date}T{rest}" if rest else date)
