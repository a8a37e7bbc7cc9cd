"""Every regrade is an audit: whose final grade changed since the last run, and what moved it.

At the end of each run the batch records every student's *standing*: the final grade and
what makes it (each check's points, each exercise's, the late penalty, the instructor's
adjustments, the reviewed reports), with the submission's content and the grader's lock
it was graded under. The next run compares its standings with the recorded ones:

* a student whose final grade moved is listed, ``old -> new``, with the parts that moved it
  ("lab07.ex2: 0 -> 12 (checks' own points: translate moves the image 0 -> 4, ...)", "late penalty
  0 -> 7.3", "override ...", "lab07.ex1 report 0 -> 3") and why it was regraded (a new
  submission, a changed grader or course);
* the list is printed by ``autograder batch``, written as ``changes.csv`` and shown in the
  class overview; each student's page tells its own part ("since your previous grading").

Standings are plain JSON kept in the gradebook's ``meta`` table (``standing`` and
``changes``), so ``autograder report`` shows the same changes as the run that found them.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field

STANDING, CHANGES, LAST_CHANGES = "standing", "changes", "student_changes"
CHANGES_HEADER = ["Student ID", "Name", "Before", "After", "Why regraded", "What moved it"]


@dataclass
class Change:
    """One student's final grade moving between two runs."""

    student_id: str
    name: str
    before: float | None          # None: not graded before (a newcomer, or failed then)
    after: float | None           # None: not graded now
    why: str                      # "new submission", "grader or course changed", "review", ...
    parts: list[str] = field(default_factory=list)   # what moved, most important first

    def sentence(self) -> str:
        """``alice: 0 -> 65.7 (new submission; lab07.ex2: 0 -> 12; late penalty 0 -> 7.3)``."""
        detail = "; ".join([self.why] + self.parts) if self.why else "; ".join(self.parts)
        return f"{self.student_id}: {_points(self.before)} -> {_points(self.after)}" + (f" ({detail})" if detail else "")


def standing_of(grade) -> dict:
    """What one student's final grade is made of (a :class:`.exports.StudentGrade`), as JSON-able data."""
    result = grade.student.get("result") or {}
    checks = {}
    for exercise in result.get("exercises", []):
        hidden = 0
        for check in exercise.get("checks", []):
            hidden += bool(check.get("hidden"))
            if check.get("max_score"):   # a hidden check's name may hold its inputs: numbered, as students see it
                name = f"hidden check {hidden}" if check.get("hidden") else check["name"]
                checks[f"{exercise['id']}: {name}"] = check["score"]
    return {"name": grade.roster.get("name") or grade.student.get("display_name", ""),
            "total": grade.total, "status": grade.student.get("status", ""),
            "content": grade.student.get("content_hash", ""), "lock": grade.student.get("lock", ""),
            "exercises": dict(grade.exercises), "checks": checks,
            "late": grade.late_penalty if grade.graded else None, "bonus": grade.bonus if grade.graded else None,
            "reports": {e: p for e, p in grade.reports.items() if p is not None},
            "adjustments": [f"{a.what} {a.change}" + (f" ({a.comment})" if a.comment else "")
                            for a in grade.adjustments if a.what != "late"]}


def standings(grades) -> dict[str, dict]:
    """Every graded or listed student's standing, by id (roster-only rows left out)."""
    return {g.student["student_id"]: standing_of(g) for g in grades if g.student.get("student_id")}


def compare(before: dict[str, dict], after: dict[str, dict]) -> list[Change]:
    """The students whose final grade differs between two runs' standings, by id."""
    changed = []
    for student_id in sorted(set(before) | set(after)):
        old, new = before.get(student_id), after.get(student_id)
        if new is None:      # gone from the download: kept in the gradebook, not a change of grade
            continue
        if old is not None and _same(old.get("total"), new.get("total")):
            continue
        if old is None and new.get("total") is None:   # (a roster's student with nothing handed in: no grade yet)
            continue
        # (a first grading is told as such: every exercise and check of a newcomer "moved" would bury the real changes)
        changed.append(Change(student_id, new.get("name", ""), (old or {}).get("total"), new.get("total"),
                              _why(old, new), _parts(old, new) if old is not None else []))
    return changed


def _same(a, b) -> bool:
    if a is None or b is None:
        return a is b
    return abs(float(a) - float(b)) < 5e-3


def _why(old: dict | None, new: dict) -> str:
    if old is None:
        return "first grading"
    if old.get("content") != new.get("content"):
        return "new submission"
    if old.get("lock") != new.get("lock"):
        return "grader or course changed"
    if old.get("status") != new.get("status"):
        return f"{old.get('status') or 'not graded'} -> {new.get('status')}"
    if old.get("reports", {}) != new.get("reports", {}):
        return "report reviewed"
    if old.get("adjustments", []) != new.get("adjustments", []):
        return "override changed"
    if not _same(old.get("late") or 0.0, new.get("late") or 0.0):
        return "late rules changed (extension, late days, penalty)"
    return ""


def _parts(old: dict, new: dict) -> list[str]:
    """What moved between two standings: exercises (with the checks that moved them), the late
    penalty, the adjustments, the reviewed reports."""
    parts = []
    old_checks, new_checks = old.get("checks", {}), new.get("checks", {})
    for exercise in sorted(set(old.get("exercises", {})) | set(new.get("exercises", {}))):
        a, b = old.get("exercises", {}).get(exercise), new.get("exercises", {}).get(exercise)
        if _same(a, b):
            continue
        moved = [f"{name.split(': ', 1)[1]} {_points(old_checks.get(name))} -> {_points(new_checks.get(name))}"
                 for name in sorted(set(old_checks) | set(new_checks))
                 if name.startswith(f"{exercise}: ") and not _same(old_checks.get(name), new_checks.get(name))]
        # (an exercise in the course's points, its checks in their own: the course may rescale them)
        parts.append(f"{exercise}: {_points(a)} -> {_points(b)}" + (f" (checks' own points: {', '.join(moved[:4])}"
                                                                     + (", ..." if len(moved) > 4 else "") + ")"
                                                                     if moved else ""))
    if not _same(old.get("late") or 0.0, new.get("late") or 0.0):
        parts.append(f"late penalty {_points(old.get('late') or 0)} -> {_points(new.get('late') or 0)}")
    added = [a for a in new.get("adjustments", []) if a not in old.get("adjustments", [])]
    removed = [a for a in old.get("adjustments", []) if a not in new.get("adjustments", [])]
    parts += [f"override {a}" for a in added] + [f"override removed: {a}" for a in removed]
    for exercise in sorted(set(old.get("reports", {})) | set(new.get("reports", {}))):
        a, b = old.get("reports", {}).get(exercise), new.get("reports", {}).get(exercise)
        if not _same(a, b):
            parts.append(f"{exercise} report {_points(a, 'not reviewed')} -> {_points(b, 'not reviewed')}")
    return parts


def _points(value, missing: str = "-") -> str:
    if value is None:
        return missing
    return f"{round(float(value), 2):g}"


# ------------------------------------------------------------------ kept in the gradebook
def recorded(book) -> tuple[dict[str, dict] | None, list[Change]]:
    """The last run's standings (None before the first run that kept them) and the changes it found."""
    standing, changes = book.get_meta(STANDING), book.get_meta(CHANGES)
    try:
        before = json.loads(standing) if standing else None
        found = [Change(**c) for c in json.loads(changes)] if changes else []
    except (TypeError, ValueError):   # kept by another version: start the audit afresh
        return None, []
    return (before if isinstance(before, dict) else None), found


def record(book, now: dict[str, dict], changes: list[Change]) -> None:
    """Keep this run's standings and the changes it found (for the next run, and for ``autograder report``),
    and each student's latest change (their page tells it until their grade moves again)."""
    latest = {c.student_id: c for c in last_changes(book)}
    latest.update({c.student_id: c for c in changes})
    book.set_meta(STANDING, json.dumps(now, sort_keys=True))
    book.set_meta(CHANGES, json.dumps([asdict(c) for c in changes]))
    book.set_meta(LAST_CHANGES, json.dumps([asdict(c) for _, c in sorted(latest.items())]))


def last_changes(book) -> list[Change]:
    """Each student's latest change of grade, whichever run found it."""
    try:
        return [Change(**c) for c in json.loads(book.get_meta(LAST_CHANGES) or "[]")]
    except (TypeError, ValueError):
        return []


def rows(changes: list[Change]) -> list[list]:
    """``changes.csv``'s rows, header first."""
    return [CHANGES_HEADER] + [[c.student_id, c.name, _points(c.before), _points(c.after), c.why, "; ".join(c.parts)]
                               for c in changes]


def for_student(changes: list[Change], student_id: str) -> Change | None:
    return next((c for c in changes if c.student_id == student_id), None)
