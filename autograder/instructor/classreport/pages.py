"""The class pages of a batch's RESULTS folder, from its gradebook (no regrading).

Entry points for ``autograder report RESULTS``, ``autograder similarity`` and
the end of ``autograder batch``:

- :func:`write_overview` writes ``RESULTS/index.html`` from
  ``Gradebook.class_results()`` (see :mod:`autograder.instructor.batch.gradebook`);
- :func:`write_similarity` writes ``RESULTS/similarity.html``.
"""

from __future__ import annotations

from pathlib import Path

from .analysis import StudentRecord
from .overview import render_overview

OVERVIEW = "index.html"
SIMILARITY = "similarity.html"
GRADEBOOK = "gradebook.sqlite"


class NoGradebook(FileNotFoundError):
    """The folder holds no batch gradebook."""


# Every file a batch may write beside the pages, as the overview links them.
REPORTS = (("grades", "grades.csv"), ("changes", "changes.csv"), ("Canvas import", "canvas_import.csv"),
           ("Moodle worksheet", "moodle_import.csv"), ("roster problems", "roster_unmatched.csv"),
           ("not submissions", "ignored.csv"), ("similar submissions", SIMILARITY))


def records_from_class_results(rows: list[dict]) -> list[StudentRecord]:
    """``Gradebook.class_results()`` rows as overview records, without final grades."""
    return [StudentRecord(student_id=row["student_id"], name=row.get("display_name") or "",
                          status=row.get("status", "graded"), reason=row.get("reason") or "",
                          result=row.get("result"), feedback_href=row.get("feedback") or "")
            for row in rows]


def records_from_grades(grades, possible: float) -> list[StudentRecord]:
    """The class's final grades (``batch.run.ClassGrades.grades``) as overview records: named as
    the roster names them, roster students who handed in nothing included."""
    records = []
    for grade in grades:
        row = grade.student
        records.append(StudentRecord(
            student_id=row["student_id"], name=grade.roster.get("name") or row.get("display_name") or "",
            status=row.get("status", "graded"), reason=row.get("reason") or "", result=row.get("result"),
            feedback_href=row.get("feedback") or "", final=grade.total,
            final_max=possible if grade.total is not None else None, rules=rules_applied(grade)))
    return records


def rules_applied(grade) -> list[str]:
    """What the course's rules did to one student's grade (a ``batch.exports.StudentGrade``), in a
    few words: excused, an extension, pooled late days spent, days late (even at 0 points) and
    their penalty."""
    told = ["excused"] if grade.excused else []
    for adjustment in grade.adjustments:
        if adjustment.what == "extension":
            told.append(f"extension {adjustment.change}")
        elif adjustment.what == "late days":
            told.append(f"late days: {adjustment.change}")
    if grade.late_days:
        told.append(f"late {grade.late_days} day{'s' if grade.late_days != 1 else ''}"
                    + (f", -{grade.late_penalty:g}" if grade.late_penalty else ""))
    elif grade.student.get("late") and not told:   # the LMS's flag, no rule counting days (nor an extension)
        told.append("late")
    return told


def write_overview(results_dir, course_title: str | None = None) -> Path:
    """Write ``RESULTS/index.html`` from the gradebook; returns its path.

    ``course_title`` None: the assignment of the batch that wrote the gradebook. Raises
    :class:`NoGradebook`, or :class:`~autograder.instructor.batch.gradebook.StorageError` when the
    gradebook is damaged or the page cannot be written.
    """
    results_dir = Path(results_dir)
    if not (results_dir / GRADEBOOK).is_file():
        raise NoGradebook(f"{results_dir} holds no {GRADEBOOK}: it is the folder a batch writes its results in "
                          f"(autograder batch SUBMISSIONS --out RESULTS), not the students' work -- run the batch, "
                          "then give its RESULTS folder")
    from ..batch.gradebook import Gradebook
    from ..batch.run import class_grades

    with Gradebook(results_dir, readonly=True) as book:
        standing = class_grades(book)
    return write_overview_of(results_dir, standing, course_title)


def write_overview_of(results_dir, standing, course_title: str | None = None) -> Path:
    """Write ``RESULTS/index.html`` for the class's final grades (``batch.run.ClassGrades``),
    linking every report in ``results_dir``."""
    from ..batch.gradebook import storing

    results_dir = Path(results_dir)
    out = results_dir / OVERVIEW
    reports = [(label, name) for label, name in REPORTS if (results_dir / name).is_file()]
    with storing(out):
        render_overview(records_from_grades(standing.grades, standing.possible), out,
                        course_title=standing.course.assignment if course_title is None else course_title,
                        reports=reports, changes=getattr(standing, "changes", ()))
    return out


def write_similarity(submissions, results_dir, threshold: float, course_title: str = "") -> Path:
    """Compare the class's submissions (the SUBMISSIONS folder, or RESULTS where it keeps
    each student's sources) and write ``RESULTS/similarity.html``; returns its path."""
    from .similarity import write_similarity_report

    out = Path(results_dir) / SIMILARITY
    write_similarity_report(submissions, out, threshold=threshold, course_title=course_title)
    return out
