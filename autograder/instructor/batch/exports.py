"""From the gradebook to grades: course points, overrides, late penalties, the roster, the CSVs.

Files written in RESULTS (every one parses with :mod:`csv`; UTF-8, comma-separated):

``grades.csv``
    ``Student ID,Name,Status,<exercise>...,<exercise> report...,Late penalty,Adjustments,Total``
    -- one row per student (``Status``: graded, unreadable: <reason>, failed: <reason>,
    pending, no submission), exercise columns in course points; when a student handed a
    lab in more than once, a ``Files not graded`` column after ``Status`` says, for each
    such student, which file was graded, which was not and why
    (:class:`autograder.loading.handed_in.NotGraded`); a ``report`` column
    per exercise with a rubric: the points of the rubric items applied in
    ``autograder review`` (empty while nobody reviewed it), counted in the total.
``canvas_import.csv``
    ``Student,ID,SIS User ID,SIS Login ID,Section,<assignment>`` then the
    ``Points Possible`` row: Canvas's gradebook import. The grade column is
    ``"<assignment> (<Canvas id>)"`` when the id is known (course
    ``canvas_assignment_id``, or the roster's column of that name in a Canvas
    export), so Canvas fills the existing assignment.
``moodle_import.csv``
    ``Identifier,Full name,Email address,Grade``: Moodle's offline grading
    worksheet (``Identifier`` is ``Participant <id>``), for a Moodle download,
    a roster with Moodle's ``Identifier`` column, or when the course's
    ``lms_exports`` asks for it (which also turns the Canvas import off unless listed).
``roster_unmatched.csv``
    ``Student ID,Name,Problem``: students with no roster row and roster rows with
    no submission (written when a roster is given). Nobody is dropped: they are
    in the other files too, with the identities known.
``ignored.csv``
    ``Item,Reason``: what the upload held that is no student's submission (a
    stray file, a link, a name no LMS gives), written when there is any.

Every cell a spreadsheet would read as a formula (a leading ``=``, ``+``, ``-``,
``@``, TAB or CR, OWASP's rule) is written with a ``'`` before it
(:func:`spreadsheet_safe`), in every CSV the batch writes; plain numbers
(``-2``, ``+1.5``) are left as they are.

Overrides file (``--overrides``), columns ``student,exercise,points,penalty,comment``:
``student`` is a derived id, an LMS id (sid, e-mail, login, Canvas user id, Moodle
participant) of the student, a group member or the roster row, or a name (the
download's, a member's or the roster's; ``"Kim, Bo"`` and ``"Bo Kim"`` agree); a
row that names several students is refused with their ids;
``exercise`` is an exercise id (``points`` replaces its score, ``penalty``
subtracts), ``late`` (``points`` replaces the late penalty: 0 waives it) or
``total``/empty (``penalty`` subtracts, ``points`` adds a bonus). Exactly one of
points/penalty per row; points are course points.

Roster file (``--roster``): a CSV with any of the columns ``Student ID`` (derived
id), ``Student``/``Name``/``Full name``, ``ID`` (Canvas user id), ``SIS User ID``,
``SIS Login ID``, ``Section``, ``Identifier`` (Moodle ``Participant N``),
``Email``/``Email address`` -- Canvas's own gradebook export works as it is.
A student matches the first row agreeing on the derived id, Canvas id, SIS user
id, e-mail or login, Moodle participant, then the name; a class of one folder per
student matches its folders' names with the logins or SIS user ids.
"""

from __future__ import annotations

import csv
import html
import io
import json
import math
import re
from dataclasses import dataclass, field
from datetime import timedelta
from pathlib import Path

from ...engine.results import NOT_IMPLEMENTED, write_atomically
from ...loading.text import one_line
from ..course import CourseConfig, parse_time

GRADES_HEADER = ["Student ID", "Name", "Status"]
GRADES_TAIL = ["Late penalty", "Adjustments", "Total"]
FILES_NOT_GRADED = "Files not graded"
CANVAS_HEADER = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section"]
MOODLE_HEADER = ["Identifier", "Full name", "Email address", "Grade"]
UNMATCHED_HEADER = ["Student ID", "Name", "Problem"]
OVERRIDES_HEADER = ["student", "exercise", "points", "penalty", "comment"]


class ExportError(ValueError):
    """An overrides or roster file that cannot be used as it is."""


@dataclass(frozen=True)
class Override:
    student: str
    exercise: str
    points: float | None
    penalty: float | None
    comment: str = ""


@dataclass
class Adjustment:
    """One line of the "instructor adjustments" on a student's page."""

    what: str          # exercise id, "late" or "total"
    change: str        # "set to 4", "-2", "+1"
    comment: str


@dataclass
class StudentGrade:
    student: dict                        # a Gradebook.class_results() row (or a roster-only stub)
    exercises: dict[str, float | None]   # course points per exercise (None: not graded)
    late_penalty: float = 0.0
    late_days: int = 0                   # days late by the course's rule and the student's extension
    late_days_used: int = 0              # pooled late days (course late_days) spent on these
    excused: bool = False                # excused by the instructor (course extensions): not counted
    bonus: float = 0.0                   # total-level overrides (bonus minus penalties)
    adjustments: list[Adjustment] = field(default_factory=list)
    roster: dict = field(default_factory=dict)
    reports: dict[str, float | None] = field(default_factory=dict)   # report points per exercise (None: not reviewed)
    reviews: dict[str, "Review"] = field(default_factory=dict)       # the review of each exercise reviewed

    @property
    def graded(self) -> bool:
        return self.student["status"] in ("graded", "unreadable")

    @property
    def earned(self) -> float:
        """The points of the checks and of the reports' reviews, before the late penalty and bonus."""
        return sum(v or 0.0 for v in self.exercises.values()) + sum(v or 0.0 for v in self.reports.values())

    @property
    def total(self) -> float | None:
        if not self.graded or self.excused:
            return None
        return round(max(0.0, self.earned - self.late_penalty + self.bonus), 2)


@dataclass
class Review:
    """The review of one exercise's report, as the student's page shows it."""

    items: list[tuple[str, float]]   # (text, points) of each rubric item applied
    points: float
    maximum: float                   # the sum of the exercise's positive items
    comment: str


# ------------------------------------------------------------------ reading the instructor's files
def read_overrides(path) -> list[Override]:
    rows = _read_csv(path)
    out = []
    for number, row in enumerate(rows, 2):
        row = {k.strip().lower(): (v or "").strip() for k, v in row.items() if k}
        if not row.get("student"):
            raise ExportError(f"{path}:{number}: no student")
        points, penalty = _number(row.get("points"), path, number), _number(row.get("penalty"), path, number)
        if (points is None) == (penalty is None):
            raise ExportError(f"{path}:{number}: give exactly one of points or penalty")
        out.append(Override(row["student"], row.get("exercise", "").lower() or "total", points, penalty,
                            row.get("comment", "")))
    return out


class Roster(list):
    """The roster's rows (dicts with the keys below), and the CSV's own column names in
    :attr:`columns` (a Canvas export names each assignment ``"Lab 7 (12345)"``)."""

    def __init__(self, rows=(), columns=()):
        super().__init__(rows)
        self.columns = list(columns)


def read_roster(path) -> Roster:
    reader_rows = _read_csv(path)
    rows = Roster(columns=[k.strip() for k in (reader_rows[0].keys() if reader_rows else []) if k])
    for row in reader_rows:
        row = {_roster_key(k): (v or "").strip() for k, v in row.items() if k}
        if "points possible" in row.get("name", "").lower():
            continue  # Canvas's export carries the points possible as a row
        if any(row.values()):
            rows.append(row)
    return rows


_CANVAS_ASSIGNMENT = re.compile(r"^(?P<name>.*\S)\s*\((?P<id>\d+)\)$")


def canvas_assignment_column(course: CourseConfig, roster_columns=()) -> tuple[str, str]:
    """The Canvas import's grade column, and a warning ('' when none).

    Canvas fills an existing assignment only from a column named ``"Lab 7 (12345)"``:
    the id comes from ``canvas_assignment_id``, else from the column of the roster
    (Canvas's own gradebook export) whose name is the assignment's.
    """
    if course.canvas_assignment_id:
        return f"{course.assignment} ({course.canvas_assignment_id})", ""
    assignments = [c for c in roster_columns if _CANVAS_ASSIGNMENT.match(c)]
    same = [c for c in assignments if _CANVAS_ASSIGNMENT.match(c)["name"].casefold() == course.assignment.casefold()]
    if len(same) == 1:
        return same[0], ""
    if assignments:
        return course.assignment, (
            f"the roster (a Canvas export) has {'several columns' if same else 'no column'} for the assignment "
            f"{course.assignment!r} (it has: {', '.join(assignments[:6])}); canvas_import.csv names its column "
            f"{course.assignment!r}, which Canvas would add as a new assignment: set the course's "
            "'assignment' to the Canvas name or give 'canvas_assignment_id'")
    return course.assignment, ""


_ROSTER_KEYS = {"student id": "student_id", "student_id": "student_id", "student": "name", "name": "name",
                "full name": "name", "id": "canvas_user_id", "sis user id": "sid", "sis login id": "login",
                "section": "section", "identifier": "identifier", "email": "email", "email address": "email"}


def _roster_key(key: str) -> str:
    return _ROSTER_KEYS.get(key.strip().lower(), key.strip().lower())


def _read_csv(path) -> list[dict]:
    try:
        text = Path(path).read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise ExportError(f"cannot read {path}: {exc}") from None
    return list(csv.DictReader(io.StringIO(text)))


def _number(text, path, line) -> float | None:
    if not text:
        return None
    try:
        value = float(text)
    except ValueError:
        raise ExportError(f"{path}:{line}: {text!r} is not a number") from None
    if not math.isfinite(value):
        raise ExportError(f"{path}:{line}: {text!r} is not a number")
    return value


# ------------------------------------------------------------------ matching
def _name_key(name: str) -> str:
    """``"Smith, John"``, ``"John Smith"`` and ``"smithjohn"`` all agree."""
    return "".join(sorted(re.sub(r"[^a-z0-9 ]", " ", name.lower()).split()))


def _identities(student: dict) -> set[str]:
    lms = student.get("lms", {})
    ids = {f"student_id:{student['student_id']}"}
    for key, prefix in (("canvas_user_id", "canvas_user_id"), ("sid", "sid"), ("email", "email"),
                        ("moodle_participant_id", "moodle")):
        if lms.get(key):
            ids.add(f"{prefix}:{lms[key].lower()}")
    return ids


def _roster_identities(row: dict) -> set[str]:
    ids = set()
    for key, prefix in (("student_id", "student_id"), ("canvas_user_id", "canvas_user_id"), ("sid", "sid")):
        if row.get(key):
            ids.add(f"{prefix}:{row[key].lower()}")
    for key in ("email", "login"):
        if row.get(key):
            ids.add(f"email:{row[key].lower()}")
    # (a class handed in as a folder per student: its ids are the folders' names, which a roster knows as the login
    # or the SIS user id -- Canvas's gradebook export, as it is)
    from .ingest import slug

    for key in ("login", "sid"):
        if row.get(key):
            ids.add(f"student_id:{slug(row[key])}")
    if row.get("identifier"):
        ids.add("moodle:" + re.sub(r"\D", "", row["identifier"]))
    return ids


def match_roster(students: list[dict], roster: list[dict]) -> tuple[dict[str, dict], list[dict], list[dict]]:
    """(roster row by student id, students with no row, rows with no student)."""
    matched, used = {}, set()
    for student in students:
        ids = _identities(student)
        candidates = [i for i, row in enumerate(roster) if i not in used and ids & _roster_identities(row)]
        if not candidates:
            name = _name_key(student["display_name"])
            candidates = [i for i, row in enumerate(roster)
                          if i not in used and name and _name_key(row.get("name", "")) == name]
        if candidates:
            used.add(candidates[0])
            matched[student["student_id"]] = roster[candidates[0]]
    unmatched = [s for s in students if s["student_id"] not in matched]
    absent = [row for i, row in enumerate(roster) if i not in used]
    return matched, unmatched, absent


# ------------------------------------------------------------------ grades
def exercise_factors(exercises, course: CourseConfig) -> dict[str, float]:
    """Course points per raw point, by exercise id (``exercises``: (id, raw max) pairs)."""
    return course.point_factors(exercises)


def late_days(student: dict, rule: dict, extension: dict | None = None) -> int:
    """Days late (started days count whole) by the course's rule and the student's extension
    (``{"days": n}`` moves the due date, ``{"due": time}`` replaces it); 0 when on time or
    unknown. A late flag without times (Canvas's ``_LATE_``) is one day, unless the extension
    gives days."""
    extension = extension or {}
    if not rule:
        return 0
    due = extension.get("due") or rule.get("due")
    if due and student.get("submitted_at"):
        try:
            submitted = parse_time(student["submitted_at"])
        except ValueError:
            submitted = None
        if submitted is not None:
            over = (submitted - parse_time(str(due)) - timedelta(minutes=rule.get("grace_minutes", 0))
                    - timedelta(days=extension.get("days", 0)))
            return max(0, math.ceil(over / timedelta(days=1)))
    return 1 if student.get("late") and not extension.get("days") and not extension.get("due") else 0


# ------------------------------------------------------------------ extensions and late days
def _extensions(course: CourseConfig, grades: list[StudentGrade], index) -> tuple[dict[int, dict], list[str]]:
    """Each student's extension (by ``id()`` of their grade), matched by any identity the
    download or roster knows, as overrides are; warnings for one naming nobody or several."""
    found, warnings = {}, []
    for who, extension in course.extensions.items():
        named = _named_by(who, grades, index, absent_too=True)
        if len(named) == 1:
            found[id(named[0])] = extension
        elif not named:
            warnings.append(f"extension for {who!r} names no student; ignored")
        else:
            warnings.append(f"extension for {who!r} is ambiguous: it names "
                            f"{', '.join(g.student['student_id'] for g in named)}; ignored (name the student by id)")
    return found, warnings


def ledger_key(student: dict) -> str:
    """Who a student is in the term's late-day ledger: the LMS's user id, else where they were
    in the download (the same folder name in every assignment)."""
    from .ingest import identity_keys

    return identity_keys(student.get("origin", student.get("student_id", "")), student.get("lms") or {})[0]


def read_ledger(course: CourseConfig) -> dict:
    """The term's late-day ledger (``{"assignments": {name: {"due": time or None, "late": {key: days}}}}``),
    empty when the course keeps none or it is not written yet."""
    path = (course.late_days or {}).get("ledger")
    if not path:
        return {"assignments": {}}
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except FileNotFoundError:
        return {"assignments": {}}
    except (OSError, ValueError) as exc:
        raise ExportError(f"the late-day ledger {path} cannot be read ({exc}); fix or remove it") from None
    assignments = data.get("assignments") if isinstance(data, dict) else None
    if not isinstance(assignments, dict) or not all(
            isinstance(a, dict) and isinstance(a.get("late", {}), dict)
            and all(isinstance(days, int) and not isinstance(days, bool) and days >= 0 for days in a.get("late", {}).values())
            for a in assignments.values()):
        raise ExportError(f"the late-day ledger {path} is not a ledger (assignments, each with its late days "
                          "per student); fix or remove it")
    return data


def record_late_days(course: CourseConfig, grades: list[StudentGrade]) -> Path | None:
    """Write this assignment's late days (before any token is spent) into the term's ledger, so
    every assignment spends the tokens in the order of the due dates, whichever runs first."""
    path = (course.late_days or {}).get("ledger")
    if not path:
        return None
    ledger = read_ledger(course)
    ledger["assignments"][course.assignment] = {
        "due": course.late_penalty.get("due"),
        "late": {ledger_key(g.student): g.late_days for g in grades if g.graded and g.late_days}}
    write_atomically(Path(path), json.dumps(ledger, indent=1, sort_keys=True))
    return Path(path)


def _tokens_left(student: dict, course: CourseConfig, ledger: dict) -> int:
    """The pooled late days a student has left for this assignment: the course's tokens less
    those the assignments due before it spent (each spends what it needs while some are left)."""
    due = str(course.late_penalty.get("due") or "")
    key, left = ledger_key(student), course.late_days["tokens"]
    earlier = sorted((str(a.get("due") or ""), name) for name, a in ledger.get("assignments", {}).items()
                     if name != course.assignment and (str(a.get("due") or ""), name) < (due, course.assignment))
    for _, name in earlier:
        left -= min(left, int(ledger["assignments"][name].get("late", {}).get(key, 0)))
    return left


def _late_rules(grade: StudentGrade, extension: dict, course: CourseConfig, ledger: dict) -> int:
    """Apply the student's extension and pooled late days; the days left to penalise."""
    if extension.get("excused"):
        grade.excused = True
        grade.adjustments.append(Adjustment("excused", "not counted", "excused by your instructor"))
        return 0
    if extension:
        change = f"+{extension['days']:g} days" if "days" in extension else f"due {extension['due']}"
        grade.adjustments.append(Adjustment("extension", change, "your instructor's extension"))
    days = grade.late_days = late_days(grade.student, course.late_penalty, extension)
    if days and course.late_days and grade.graded:
        left = _tokens_left(grade.student, course, ledger)
        grade.late_days_used = min(days, left)
        if grade.late_days_used:
            grade.adjustments.append(Adjustment(
                "late days", f"{grade.late_days_used} used",
                f"{left - grade.late_days_used} of {course.late_days['tokens']} left for the term"))
        days -= grade.late_days_used
    return days


def report_maxima(rubric: dict[str, list[dict]], exercises) -> dict[str, float]:
    """What each graded exercise's report is worth: the sum of its rubric's positive items
    (``rubric`` as :meth:`.gradebook.Gradebook.rubric` gives it; exercises without one left out)."""
    ids = [e for e, _ in exercises]
    return {e: round(sum(max(0.0, item["points"]) for item in rubric[e]), 4) for e in ids if rubric.get(e)}


def compute_grades(students: list[dict], exercises, course: CourseConfig,
                   overrides: list[Override] = (), roster: list[dict] = (), rubric: dict | None = None,
                   reviews: dict | None = None, ledger: dict | None = None) -> tuple[list[StudentGrade], list[str]]:
    """Every student's grade, plus warnings (overrides naming nobody).

    ``students`` are :meth:`Gradebook.class_results` rows; ``exercises`` the
    selection's ``(id, raw max)`` pairs in order. Roster rows with no submission
    are added with status ``no submission``. ``rubric`` and ``reviews`` (as
    :meth:`.gradebook.Gradebook.rubric` and :meth:`~.gradebook.Gradebook.reviews` give
    them) add each reviewed exercise's report points (course points, as the rubric gives them).
    The course's ``extensions`` move a student's due date (or excuse them), and its pooled
    ``late_days`` are spent before any penalty, as the term's ``ledger`` (:func:`read_ledger`) leaves them.
    """
    rubric, reviews = rubric or {}, reviews or {}
    maxima = report_maxima(rubric, exercises)
    factors = exercise_factors(exercises, course)
    matched, _, absent = match_roster(students, list(roster))
    grades, warnings = [], []
    if not course.lms_exports or "canvas" in course.lms_exports:
        _, warning = canvas_assignment_column(course, getattr(roster, "columns", ()))
        warnings += [warning] if warning else []
    for student in students:
        scores: dict[str, float | None] = {e: None for e, _ in exercises}
        if student["status"] == "graded":
            for e in student["result"]["exercises"]:
                if e["id"] in scores:
                    scores[e["id"]] = round(e["score"] * factors[e["id"]], 4)
        elif student["status"] == "unreadable":
            scores = {e: 0.0 for e in scores}
        grade = StudentGrade(student, scores, roster=matched.get(student["student_id"], {}))
        _add_reviews(grade, rubric, maxima, reviews)
        grades.append(grade)
    index = _identity_index(grades)
    # (a roster's student with nothing handed in may be excused too: Canvas's EX, not an empty cell)
    missing = [StudentGrade({"student_id": row.get("student_id", ""), "display_name": row.get("name", ""), "lms": {},
                             "members": [], "status": "no submission", "reason": "", "result": None, "feedback": None},
                            {e: None for e, _ in exercises}, roster=row) for row in absent]
    extensions, extension_warnings = _extensions(course, grades + missing, _identity_index(grades + missing))
    warnings += extension_warnings
    for grade in missing:
        if extensions.get(id(grade), {}).get("excused"):
            _late_rules(grade, {"excused": True}, course, ledger or {})
    for grade in grades:
        days = _late_rules(grade, extensions.get(id(grade), {}), course, ledger or {})
        if days and grade.graded:
            percent = min(course.late_penalty.get("max", 100), course.late_penalty.get("per_day", 0) * days)
            earned = grade.earned
            grade.late_penalty = round(earned * percent / 100, 2)
            if percent:   # (told wherever days are late: shown only where it is not 0, it would tell points earned)
                grade.adjustments.append(Adjustment("late", f"-{grade.late_penalty:g}" if grade.late_penalty else "0",
                                                    f"{days} day(s) late: {percent:g}% of the points earned"))
    if course.late_penalty and any(g.graded for g in grades) \
            and not any(g.student.get("submitted_at") or g.student.get("late") for g in grades):
        # (a plain folder or zip says nothing of when work was handed in: no day can be late)
        warnings.append("late_penalty: this upload carries no submission times (a folder or zip of the students' "
                        "work has none; an LMS download has them), so no late penalty was applied")
    for o in overrides:
        candidates = _named_by(o.student, grades, index)
        if not candidates:
            warnings.append(f"override for {o.student!r} names no student; ignored")
        elif len(candidates) > 1:
            warnings.append(f"override for {o.student!r} is ambiguous: it names "
                            f"{', '.join(g.student['student_id'] for g in candidates)}; ignored "
                            "(name the student by id)")
        else:
            _apply(candidates[0], o, warnings)
    warnings += _unreviewed(grades, maxima, reviews)
    return grades + missing, warnings


def _unreviewed(grades: list[StudentGrade], maxima: dict[str, float], reviews: dict) -> list[str]:
    """A warning per exercise whose reports are not all reviewed yet: their points count 0 in
    every export until they are (a perfect submission shows less than full marks)."""
    graded = [g for g in grades if g.graded]
    warnings = []
    for exercise, maximum in sorted(maxima.items()):
        waiting = sum((g.student["student_id"], exercise) not in reviews for g in graded)
        if waiting:
            warnings.append(f"{exercise}: {waiting} of {len(graded)} reports not reviewed yet; until they are, "
                            f"their {maximum:g} report points count 0 in grades.csv and the LMS imports "
                            "(autograder review)")
    return warnings


def _add_reviews(grade: StudentGrade, rubric: dict, maxima: dict[str, float], reviews: dict) -> None:
    """The report points and reviews of ``grade``'s student, for the exercises with a rubric."""
    texts = {(e, item["id"]): (item["text"], item["points"]) for e, items in rubric.items() for item in items}
    for exercise, maximum in maxima.items():
        review = reviews.get((grade.student["student_id"], exercise))
        grade.reports[exercise] = None if review is None or not grade.graded else review["points"]
        if review is not None and grade.graded:
            grade.reviews[exercise] = Review([texts[(exercise, i)] for i in review["items"] if (exercise, i) in texts],
                                             review["points"], maximum, review["comment"])


def _identity_index(grades: list[StudentGrade]) -> dict[str, list[StudentGrade]]:
    """Every identity an override may use -> the grades it names: the derived id, LMS ids
    and e-mails (the student's, each group member's, the roster's), and the names (the
    download's, each member's, the roster's) as written and in any order of their words."""
    index: dict[str, list[StudentGrade]] = {}
    for grade in grades:
        student, roster = grade.student, grade.roster
        members = student.get("members", [])
        ids = [student["student_id"], *student.get("lms", {}).values(),
               *(v for m in members for k, v in m.items() if k != "name"),
               *(v for k, v in roster.items() if k in ("student_id", "sid", "email", "login", "canvas_user_id"))]
        names = [student["display_name"], roster.get("name", ""), *(m.get("name", "") for m in members)]
        keys = {f"id:{v.strip().lower()}" for v in ids if v and v.strip()}
        keys |= {f"name:{_name_key(n)}" for n in names if _name_key(n)}
        for key in keys:
            index.setdefault(key, []).append(grade)
    return index


def _named_by(who: str, grades: list[StudentGrade], index, absent_too: bool = False) -> list[StudentGrade]:
    """The graded students an override's ``student`` names (a derived id is never ambiguous); ``absent_too``: and
    the roster's students with nothing handed in (whom an extension may excuse)."""
    exact = [g for g in grades if g.student["student_id"] == who.strip()]
    if exact:
        return exact
    found = index.get(f"id:{who.strip().lower()}", []) + index.get(f"name:{_name_key(who)}", [])
    unique = list({id(g): g for g in found if absent_too or g.student["status"] != "no submission"}.values())
    return unique


def _apply(grade: StudentGrade, o: Override, warnings: list[str]) -> None:
    if o.exercise == "late":
        change = o.points if o.points is not None else grade.late_penalty + o.penalty
        grade.late_penalty = change
        grade.adjustments = [a for a in grade.adjustments if a.what != "late"]
        grade.adjustments.append(Adjustment("late", f"penalty set to {change:g}", o.comment))
    elif o.exercise == "total":
        delta = o.points if o.points is not None else -o.penalty
        grade.bonus += delta
        grade.adjustments.append(Adjustment("total", f"{delta:+g}", o.comment))
    elif o.exercise in grade.exercises:
        current = grade.exercises[o.exercise] or 0.0
        if o.points is not None:
            grade.exercises[o.exercise] = o.points
            grade.adjustments.append(Adjustment(o.exercise, f"set to {o.points:g}", o.comment))
        else:
            grade.exercises[o.exercise] = current - o.penalty
            grade.adjustments.append(Adjustment(o.exercise, f"-{o.penalty:g}", o.comment))
    else:
        warnings.append(f"override for {o.student!r} names exercise {o.exercise!r}, "
                        "which the assignment does not grade; ignored")


def max_total(exercises, course: CourseConfig, report_max: dict[str, float] | None = None) -> float:
    """The points possible: the checks' in course points, and the reports' (:func:`report_maxima`)."""
    factors = exercise_factors(exercises, course)
    return round(sum(maximum * factors[e] for e, maximum in exercises) + sum((report_max or {}).values()), 2)


# ------------------------------------------------------------------ CSV files
def _status(grade: StudentGrade) -> str:
    """What happened to the student's work, in words: graded, nothing implemented, does not
    import (why), could not be read (why), failed, missing; and late, even at 0 points."""
    status, reason = grade.student["status"], grade.student.get("reason", "")
    if grade.student.get("missing_from_download"):   # kept from an earlier download (see Gradebook)
        graded_at = grade.student.get("graded_at")
        return f"not in this download; last graded {graded_at[:10]}" if status == "graded" and graded_at \
            else f"{status} (not in this download)"
    if grade.excused:
        return "excused"
    if status == "graded":
        status = _what_was_graded(grade.student.get("result") or {})
    elif status == "unreadable":
        status = "could not be read"
    told = f"{status}: {reason}" if reason else status
    if grade.late_days:
        told += f"; late ({grade.late_days} day{'s' if grade.late_days != 1 else ''})"
    elif grade.student.get("late"):
        told += "; late"
    return told


# How a check fails when its lab's module could not be used at all.
_UNUSABLE = ("import_error", "missing_module")


def _what_was_graded(result: dict) -> str:
    """``graded``, or what the grading found instead of work to judge: every graded check met a
    stub ("nothing implemented"), or no module could be imported ("does not import: why")."""
    checks = [c for e in result.get("exercises", []) for c in e.get("checks", []) if c.get("max_score")]
    if checks and all(c.get("status") == NOT_IMPLEMENTED for c in checks):
        return "nothing implemented"
    if checks and all(c.get("failure") in _UNUSABLE for c in checks):
        messages = [e.get("message", "") for e in result.get("exercises", []) if e.get("message")]
        first = messages[0].splitlines()[0] if messages else ""
        return f"does not import ({one_line(first, 160)})" if first else "does not import"
    return "graded"


def files_not_graded(result: dict | None) -> str:
    """The files a result's submission held that were not graded (a lab handed in twice),
    one sentence each (``"graded lab07_transformations.ipynb, not lab07_transformations.py, because ..."``),
    or ``""``."""
    return " | ".join(f"graded {f.get('graded', '')}, not {f.get('file', '')}, because {f.get('why', '')}"
                      for f in (result or {}).get("files_not_graded") or [])


def _fmt(value) -> str:
    return "" if value is None else f"{round(value, 4):g}"


def write_csvs(out, grades: list[StudentGrade], exercises, course: CourseConfig, roster_given: bool,
               roster_columns=(), report_max: dict[str, float] | None = None) -> list[Path]:
    """Write grades.csv, the LMS imports that apply (see ``lms_exports`` in the course) and,
    with a roster, roster_unmatched.csv; returns the files written. ``report_max``: what
    each exercise's report is worth (:func:`report_maxima`), one column each."""
    out = Path(out)
    ids = [e for e, _ in exercises]
    reported = list(report_max or {})
    files = []

    not_graded = [files_not_graded(g.student.get("result")) for g in grades]
    extra = [FILES_NOT_GRADED] if any(not_graded) else []   # only when some lab was handed in twice
    rows = [GRADES_HEADER + extra + ids + [f"{e} report" for e in reported] + GRADES_TAIL]
    for g, left_aside in zip(grades, not_graded):
        rows.append([g.student["student_id"], g.roster.get("name") or g.student["display_name"], _status(g)]
                    + ([left_aside] if extra else []) + [_fmt(g.exercises[e]) for e in ids]
                    + [_fmt(g.reports.get(e)) for e in reported]
                    + [_fmt(g.late_penalty if g.graded else None), _fmt(g.bonus if g.graded else None),
                       _fmt(g.total)])
    files.append(write_csv(out / "grades.csv", rows))

    canvas = out / "canvas_import.csv"
    column, _ = canvas_assignment_column(course, roster_columns)
    possible = max_total(exercises, course, report_max)
    rows = [CANVAS_HEADER + [column], ["Points Possible", "", "", "", "", _fmt(possible)]]
    rows += [_canvas_row(g, member) for g, member in _members(grades)]
    if _canvas_wanted(course):
        files.append(write_csv(canvas, rows))
    else:
        canvas.unlink(missing_ok=True)

    moodle = out / "moodle_import.csv"
    if not _moodle_wanted(grades, course, roster_columns):
        moodle.unlink(missing_ok=True)   # a worksheet from an earlier run would be taken for this one's
    rows = [MOODLE_HEADER] + [_moodle_row(g, member) for g, member in _members(grades)]
    if _moodle_wanted(grades, course, roster_columns):
        files.append(write_csv(moodle, rows))

    if roster_given:
        rows = [UNMATCHED_HEADER]
        for g in grades:
            if g.student["status"] == "no submission":
                rows.append([g.student["student_id"], g.student["display_name"], "on the roster, no submission"])
            elif not g.roster:
                rows.append([g.student["student_id"], g.student["display_name"], "submitted, not on the roster"])
        files.append(write_csv(out / "roster_unmatched.csv", rows))
    return files


def _canvas_row(g: StudentGrade, member: dict) -> list[str]:
    """One student's row of Canvas's import: name, Canvas user id, SIS user id, SIS login, section, grade."""
    lms, r = g.student.get("lms", {}), g.roster
    return [r.get("name") or member.get("name") or g.student["display_name"],
            r.get("canvas_user_id") or lms.get("canvas_user_id", ""),
            r.get("sid") or member.get("sid", ""), r.get("login") or member.get("email", ""),
            r.get("section", ""), "EX" if g.excused else _fmt(g.total)]   # Canvas's "excused"


def _moodle_row(g: StudentGrade, member: dict) -> list[str]:
    """One student's row of Moodle's grading worksheet: identifier, name, e-mail, grade."""
    lms, r = g.student.get("lms", {}), g.roster
    participant = lms.get("moodle_participant_id")
    return [r.get("identifier") or (f"Participant {participant}" if participant else ""),
            r.get("name") or member.get("name") or g.student["display_name"],
            r.get("email") or member.get("email", ""), _fmt(g.total)]


def lms_warnings(grades: list[StudentGrade], course: CourseConfig, roster_columns=()) -> list[str]:
    """What the LMS imports written cannot do: rows with a grade and nothing the LMS matches a row by (Canvas: its
    user id, SIS user id or login; Moodle: the worksheet's identifier) -- a class handed as plain folders names no
    LMS user, and Moodle's identifiers come only from a Moodle download or roster."""
    said = []
    graded = [(g, member) for g, member in _members(grades) if g.total is not None or g.excused]
    if _canvas_wanted(course):
        blind = [g for g, member in graded if not any(_canvas_row(g, member)[1:4])]
        if blind:
            said.append(f"canvas_import.csv: {len(blind)} of {len(graded)} graded rows have no Canvas ID, SIS User "
                        "ID or SIS Login ID, which Canvas matches students by (a folder of submissions names no "
                        "Canvas user): give --roster with the class's Canvas roster or gradebook export")
    if _moodle_wanted(grades, course, roster_columns):
        blind = [g for g, member in graded if not _moodle_row(g, member)[0]]
        if blind:
            said.append(f"moodle_import.csv: {len(blind)} of {len(graded)} graded rows have no Identifier "
                        "(\"Participant N\"), which Moodle's worksheet import matches students by: grade Moodle's "
                        "download, or give --roster with Moodle's grading worksheet")
    return said


def _canvas_wanted(course: CourseConfig) -> bool:
    return not course.lms_exports or "canvas" in course.lms_exports


def _moodle_wanted(grades, course: CourseConfig, roster_columns) -> bool:
    """Moodle's worksheet when asked for, for a Moodle download, or with a Moodle roster."""
    if course.lms_exports:
        return "moodle" in course.lms_exports
    return (any(g.student.get("source") == "moodle" for g in grades)
            or any(c.strip().lower() == "identifier" for c in roster_columns))


def _members(grades):
    """(grade, member) pairs: every submitter of a group gets the group's grade."""
    for g in grades:
        members = g.student.get("members") or [{"name": "", "sid": g.student.get("lms", {}).get("sid", ""),
                                                "email": g.student.get("lms", {}).get("email", "")}]
        for member in members:
            yield g, member


IGNORED_HEADER = ["Item", "Reason"]
_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
_PLAIN_NUMBER = re.compile(r"[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?")


def spreadsheet_safe(cell) -> str:
    """``cell`` as text a spreadsheet shows and never evaluates: a leading ``=``, ``+``,
    ``-``, ``@``, TAB or CR gets a ``'`` before it, unless the cell is a plain number.

    >>> spreadsheet_safe("=1+1"), spreadsheet_safe("@SUM(A1)"), spreadsheet_safe("-2.5")
    ("'=1+1", "'@SUM(A1)", '-2.5')
    """
    text = "" if cell is None else str(cell)
    if text.startswith(_FORMULA_START) and not _PLAIN_NUMBER.fullmatch(text):
        return "'" + text
    return text


def write_csv(path: Path, rows) -> Path:
    """Write ``rows`` to the CSV file at ``path`` (atomically), every cell made :func:`spreadsheet_safe`."""
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerows([spreadsheet_safe(cell) for cell in row] for row in rows)
    write_atomically(path, buffer.getvalue())
    return path



def write_ignored(out, ignored: list[tuple[str, str]]) -> list[Path]:
    """``ignored.csv`` listing what the upload held that is no submission (removed when nothing is)."""
    path = Path(out) / "ignored.csv"
    if not ignored:
        path.unlink(missing_ok=True)
        return []
    return [write_csv(path, [IGNORED_HEADER] + [list(item) for item in ignored])]


# ------------------------------------------------------------------ the student's page
BEGIN, END = "<!-- instructor-adjustments -->", "<!-- /instructor-adjustments -->"


def shows_final(grade: StudentGrade, course: CourseConfig) -> bool:
    """Whether the student's page may show the final grade: not while it holds points of
    hidden checks the course keeps from students (their page shows a verdict only)."""
    result = grade.student.get("result") or {}
    hidden = any(c.get("hidden") for e in result.get("exercises", []) for c in e.get("checks", []))
    return course.hidden_points_visible or not hidden


def adjustments_html(grade: StudentGrade, possible: float, show_final: bool = True) -> str:
    """The block shown on a student's page: every adjustment and the final grade (or, while
    hidden checks' points are withheld, when it will be shown), or nothing."""
    if not grade.adjustments and not grade.reviews:   # (a late penalty is an adjustment)
        return f"{BEGIN}{END}"
    # The reports' points are in the final grade, not in the checks' total the headline shows
    # while hidden points are withheld: listed here, each beside the others that make the grade.
    reviewed = [(f"{exercise} report, reviewed", f"{review.points:+g}", "")
                for exercise, review in sorted(grade.reviews.items())]
    adjustments = [(a.what, a.change, a.comment) if show_final or not _derived_from_points(a)
                   else (a.what, "shown when the hidden checks are released", a.comment)
                   for a in grade.adjustments]
    rows = "".join(f"<tr><td>{html.escape(what)}</td><td>{html.escape(change)}</td>"
                   f"<td>{html.escape(comment)}</td></tr>"
                   for what, change, comment in reviewed + adjustments)
    final = ("excused: not counted" if grade.excused
             else f"final grade {_fmt(grade.total)} / {possible:g}" if show_final
             else "final grade: shown when the hidden checks are released")
    return (f'{BEGIN}<section class="exercise" id="adjustments"><header><h2>Instructor adjustments</h2>'
            f'<span class="score">{final}</span></header>'
            f'<table class="overview"><tr><th>what</th><th>change</th><th>comment</th></tr>{rows}</table>'
            f"</section>{END}")


def _derived_from_points(adjustment: Adjustment) -> bool:
    """Whether the adjustment's change is computed from the points earned (a late penalty is a
    share of them): while hidden points are withheld, its number would tell theirs."""
    return adjustment.what == "late"


def student_page(page: str, grade: StudentGrade, possible: float, course: CourseConfig, change=None) -> str:
    """The student's feedback ``page`` (rendered from :meth:`GradingResult.for_students`) with
    what the class's grading adds: adjustments, reviews, what changed since the previous
    grading (``change``, a :class:`.changes.Change`) and, where it may be shown
    (:func:`shows_final`), the final grade. While hidden points are withheld nothing here is
    computed from them (a late penalty's points included)."""
    show_final = shows_final(grade, course)
    page = with_adjustments(page, adjustments_html(grade, possible, show_final))
    page = _with_block(page, CHANGED, CHANGED_END, changed_html(change, show_final) if change else "")
    page = with_reviews(page, grade)
    if show_final:   # the headline is the final grade (never while it holds withheld hidden points)
        page = with_final_grade(page, grade, possible)
    else:
        # (the public checks' points, as the page tells them, beside adjustments that change the grade: said what
        # the headline counts -- its numbers left as they are, any other could hold hidden points; a page is
        # brought up to date run after run: the note is made anew each time)
        start, stop = page.find(HEADLINE), page.find(HEADLINE_END)
        if 0 <= start < stop:
            told = page[start + len(HEADLINE):stop].split(f" {WITHHELD_NOTE}")[0]
            adjusted = grade.adjustments or grade.reviews   # (never the penalty's points: they count hidden ones)
            page = _between(page, HEADLINE, HEADLINE_END, f"{told} {WITHHELD_NOTE}" if adjusted else told)
    return page


WITHHELD_NOTE = ('<span class="muted withheld" style="font-size: 1rem; font-weight: normal">(the public checks; your '
                 "final grade, with the adjustments below, is shown when the hidden checks are released)</span>")


CHANGED, CHANGED_END = "<!-- changed -->", "<!-- /changed -->"
REGRADED = ("new submission", "grader or course changed")   # the reasons of a change that graded the code again


def changed_html(change, show_final: bool) -> str:
    """What moved the student's grade since their previous grading. While hidden points are
    withheld, only that it was regraded and why (every number could hold hidden points)."""
    if change.before is None:
        return ""
    if not show_final:   # (an override, a reviewed report or an extension moves a grade without grading anew)
        said = "Graded again" if change.why in REGRADED else "Your grade changed"
        return (f'<div class="rule changed"><strong>{said} since your previous grading</strong>'
                f"{f' ({html.escape(change.why)})' if change.why else ''}.</div>")
    items = "".join(f"<li>{html.escape(part)}</li>" for part in change.parts)
    return (f'<div class="rule changed"><strong>Since your previous grading: {_fmt(change.before)} → '
            f"{_fmt(change.after)}</strong>{f' ({html.escape(change.why)})' if change.why else ''}"
            f"{f'<ul>{items}</ul>' if items else ''}</div>")


HEADLINE, HEADLINE_END = "<!-- headline -->", "<!-- /headline -->"


def headline(grade: StudentGrade, possible: float) -> str:
    """The page's headline (HTML): the final grade, with the checks' own points beside it,
    labelled, where the two differ (course points, late penalty, overrides). Only for a page
    that may show the final grade (:func:`shows_final`)."""
    result = grade.student.get("result") or {}
    raw, raw_max = result.get("total"), result.get("max_total")
    checks = (f'<span class="muted" style="font-size: 1rem; font-weight: normal">'
              f"(checks: {_fmt(raw)} / {_fmt(raw_max)} points)</span>")
    if grade.excused:   # no final grade: the work is not counted
        return f"excused, not counted {checks}"
    final = f"{_fmt(grade.total)} / {possible:g}"
    if raw == grade.total and raw_max == possible:
        return f"{final} points"
    return f"final grade {final} {checks}"


def with_final_grade(page: str, grade: StudentGrade, possible: float) -> str:
    """``page`` telling ``grade``'s final grade wherever it tells a total: the headline (between
    the template's markers), the bar under it and the window's title. Only for a page that may
    show the final grade (:func:`shows_final`)."""
    page = _between(page, HEADLINE, HEADLINE_END, headline(grade, possible))
    percent = round(100 * grade.total / possible) if possible and grade.total is not None else 0
    page = _between(page, BAR, BAR_END, f'<div class="bar" role="img" aria-label="{percent} percent">'
                                        f'<span style="width: {percent}%"></span></div>')
    told = "excused" if grade.excused else f"final grade {_fmt(grade.total)} / {possible:g}"
    return re.sub(r"<title>Feedback: [^<]*? — ", lambda _: f"<title>Feedback: {told} — ", page, count=1)


BAR, BAR_END = "<!-- bar -->", "<!-- /bar -->"


def _between(page: str, begin: str, end: str, text: str) -> str:
    """``page`` with what stands between the markers ``begin`` and ``end`` replaced; unchanged without them."""
    start, stop = page.find(begin), page.find(end)
    if start < 0 or stop < start:
        return page
    return page[:start + len(begin)] + text + page[stop:]


def with_adjustments(page: str, block: str) -> str:
    """``page`` with its adjustments block replaced (inserted after the summary the first time)."""
    start, stop = page.find(BEGIN), page.find(END)
    if start >= 0 and stop > start:
        return page[:start] + block + page[stop + len(END):]
    return _after_summary(page, block)


def _with_block(page: str, begin: str, end: str, text: str) -> str:
    """``page`` with ``text`` between the markers ``begin`` and ``end`` (placed after the summary,
    before any block placed so before, the first time)."""
    if page.find(begin) >= 0 and page.find(end) > page.find(begin):
        return _between(page, begin, end, text)
    return _after_summary(page, f"{begin}{text}{end}")


def _after_summary(page: str, block: str) -> str:
    anchor = page.find("</header>")
    at = anchor + len("</header>") if anchor >= 0 else page.find("<main>") + len("<main>")
    return page[:at] + "\n" + block + page[at:]


def review_html(exercise: str, review: Review) -> str:
    """The review of one exercise's report on the student's page: the rubric items applied with
    their points, the report's points and the reviewer's comment (all escaped)."""
    items = "".join(f"<li>{html.escape(text)} <b>{points:+g}</b></li>" for text, points in review.items)
    comment = (f'<p class="review-comment">{html.escape(review.comment).replace(chr(10), "<br>")}</p>'
               if review.comment.strip() else "")
    return (f'<div class="rule review" id="review-{html.escape(exercise)}"><strong>Report, reviewed by your '
            f"instructor: {_fmt(review.points)} / {review.maximum:g} points</strong>"
            f"{f'<ul>{items}</ul>' if items else ''}{comment}</div>")


def with_reviews(page: str, grade: StudentGrade) -> str:
    """``page`` showing the review of each exercise's report in that exercise's section, under its
    automatic score (between markers, so a later review replaces it; an exercise no longer
    reviewed loses it)."""
    for exercise in grade.reports:
        begin, end = f"<!-- review {exercise} -->", f"<!-- /review {exercise} -->"
        review = grade.reviews.get(exercise)
        block = begin + (review_html(exercise, review) if review else "") + end
        start, stop = page.find(begin), page.find(end)
        if start >= 0 and stop > start:
            page = page[:start] + block + page[stop + len(end):]
            continue
        section = page.find(f'<section class="exercise" id="{html.escape(exercise)}">')
        anchor = page.find("</header>", section) if section >= 0 else -1
        if anchor >= 0:
            at = anchor + len("</header>")
            page = page[:at] + "\n" + block + page[at:]
    return page
