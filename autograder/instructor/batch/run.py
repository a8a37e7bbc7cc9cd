"""``autograder batch``: read the class, grade what is new, write every student's page and the CSVs.

Layout of RESULTS::

    gradebook.sqlite          scores and messages (see .gradebook)
    grades.csv                one row per student, one column per exercise
    canvas_import.csv         Canvas gradebook import
    moodle_import.csv         Moodle offline grading worksheet
    roster_unmatched.csv      with --roster: who matched nobody
    index.html                the class overview (see autograder.instructor.classreport)
    similarity.html           with --similarity: the most similar submissions
    <student-id>/feedback.html the student's page (hidden checks as verdicts only)
    <student-id>/results.json the results model as the student may see it, without pictures
    <student-id>/sources/     the files graded (read by ``autograder similarity RESULTS``)

Gradings run in parallel, one sandboxed grading per submission: in a local
process pool (``workers``, forked from a server that imports the grader while
the class is read, the cores shared out among them), or on a Dask cluster
(``dask_scheduler``). The process that grades a submission renders its page; this
one writes it to the student's folder and then commits the grading to the gradebook
in one transaction, so a run killed at any moment resumes where it stopped.
"""

from __future__ import annotations

import json
import os
import shutil
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Callable

from ...engine.registry import discover, select
from ...engine.results import GradingResult, json_text, strip_pictures, write_atomically
from ...reports import html
from ...sandbox import confine
from ...sandbox.supervisor import cores_each
from ...engine.versions import OpenCVMismatch, check_opencv
from ...loading.headings import ExerciseNames
from ..course import CourseConfig, CourseConfigError
from . import changes, exports
from .gradebook import STORAGE_ERRNOS, Gradebook, StorageError, lock_hash, storing, submission_key
from .ingest import Entry, IngestError, read_upload
from .processes import GradingPool, ProcessDeath, batch_process
from .task import grade_files, grading_processes

PICTURES = {"none": "none", "failing": "failed", "all": "all"}
POOL_ATTEMPTS = 3   # a submission whose grading kills the grading process this often is recorded as failed
REGRADE_LEFT = "regrade left"   # the gradebook's record of the submissions a --regrade has still to grade again
# Per submission graded, the pictures and the rubric's figures its page was made with: they change no score, so a
# run asking for others grades nothing again by itself -- and says which pages keep what they were made with.
PRESENTED = "presented"


class Unconfined(IngestError):
    """Grading a class here would let each submission read the others' work."""


def _refuse_unconfined(confinement: confine.Confinement) -> None:
    weaker = confine.shortfall(confinement)  # e.g. AUTOGRADER_CONFINEMENT=namespaces where +user works
    if confinement.level == "process-group" and weaker:   # (forced or asked for: the machine can do better)
        raise Unconfined(f"{weaker}, so each submission could read the other students' work and your files, and "
                         "print them into its feedback: grade the class at the strongest level this machine allows, "
                         "or pass --allow-unconfined to accept that.")
    if confinement.level == "process-group":
        raise Unconfined(
            "this machine cannot confine student code (confinement level 'process-group': no Linux "
            "namespaces), so each submission could read the other students' work and your files, and "
            "print them into its feedback. Grade the class on Linux as root or with unprivileged user "
            "namespaces (see docs/security.md), or pass --allow-unconfined to accept that.")
    if weaker:
        raise Unconfined(f"{weaker}: grade the class at the strongest level this machine allows, "
                         "or pass --allow-unconfined to accept that.")


@dataclass
class BatchSummary:
    students: int = 0
    graded: int = 0          # graded in this run
    reused: int = 0          # already in the gradebook
    failed: list[str] = field(default_factory=list)       # "id: reason"
    unreadable: list[str] = field(default_factory=list)   # "origin: reason"
    ignored: list[str] = field(default_factory=list)      # "item: why it is no submission"
    missing: list[str] = field(default_factory=list)      # ids graded before, no longer in SUBMISSIONS (kept)
    unmatched: list[str] = field(default_factory=list)    # roster problems
    files_not_graded: list[str] = field(default_factory=list)  # "id: graded X, not Y, because ..." (a lab handed in twice)
    running: list[str] = field(default_factory=list)      # ids being graded now (local gradings)
    warnings: list[str] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)
    changes: list = field(default_factory=list)           # changes.Change: final grades this run moved
    first_run: bool = False   # no earlier run's final grades to compare with


@batch_process
def run_batch(submissions, out, *, course: CourseConfig | None = None, workers: int | None = None,
              pictures: str = "failing", regrade: bool = False, roster=None, overrides=None,
              dask_scheduler: str | None = None, progress: Callable | None = None,
              allow_unconfined: bool = False) -> BatchSummary:
    """Grade the class at ``submissions`` into the folder ``out``; see the module docstring.

    ``progress(event, entry, summary)`` is called with ``"start"`` (entry None,
    with the number to grade in ``summary.students``) and ``"done"`` per grading.
    Raises :class:`.ingest.IngestError` / :class:`.exports.ExportError` for
    unusable inputs, :class:`~autograder.instructor.course.CourseConfigError` where the
    installed OpenCV is not the course's ``opencv`` major, before anything is graded, and :class:`Unconfined` where this
    machine cannot keep one student's code from reading the others' work (the
    ``process-group`` level) unless ``allow_unconfined`` says that is acceptable.
    A fault of RESULTS -- full, read-only, deleted mid-run, a damaged gradebook --
    stops the batch with :class:`.gradebook.StorageError` (finished gradings kept).
    """
    # Inputs: everything is read, and refused if unusable, before anything is graded.
    course = course or CourseConfig()
    if pictures not in PICTURES:
        raise ValueError(f"pictures must be one of {sorted(PICTURES)}")
    try:   # scores are grades: never with another OpenCV than the course's (versions.check_opencv)
        check_opencv(course.opencv)
    except OpenCVMismatch as exc:
        raise CourseConfigError(str(exc)) from None
    out = Path(out)
    if Path(submissions).is_dir() and Path(submissions).resolve() in out.resolve().parents:
        raise IngestError(f"--out {out} is inside {submissions}: it would be read as a student next time")
    # Probing the confinement starts a process of its own: it runs while the class is read,
    # and so does the process the local gradings will be forked from, importing the grader.
    # Where no namespaced level is even available there is nothing to probe: refused at once.
    probing = dask_scheduler is None and not allow_unconfined
    if probing:
        _refuse_unconfined(confine.strongest_candidate())
        confine.detect_in_background()
    if dask_scheduler is None:
        grading_processes()
    exercises = select(course.select)
    selection = ",".join(e.id for e in exercises)
    modules = sorted({e.lab.module for e in exercises})
    overrides_rows = exports.read_overrides(overrides) if overrides else None
    roster_rows = exports.read_roster(roster) if roster else []
    names = ExerciseNames.of_labs({e.lab.key: e.lab for e in exercises}.values())   # what report headings may name
    upload = read_upload(submissions, modules, [lab.module for lab in discover().values()], _known(out), names,
                         allow_unconfined)   # the reports' PDFs are read in workers as confined as the gradings
    entries = upload.entries
    if probing:
        _refuse_unconfined(confine.detect())

    # Grading: only what the gradebook lacks, each grading committed as it lands.
    lock = f"{lock_hash()}/{_grading_fingerprint(course)}"   # a changed rule regrades everyone
    keys = {e.student_id: submission_key(e.student_id, e.content_hash, selection, lock=lock) for e in entries}
    summary = BatchSummary(students=len(entries), ignored=[f"{item}: {why}" for item, why in upload.ignored],
                           warnings=list(upload.warnings))
    with _only_writer(out), Gradebook(out) as book:
        summary.missing = book.sync_students(entries, keys)
        book.set_meta("course", _course_record(course))   # for `autograder report`
        book.sync_rubric(course.rubric)                   # for `autograder review`
        if overrides_rows is not None:
            book.set_overrides(overrides_rows)   # kept for later runs without --overrides
        if roster:
            book.set_meta("roster", json.dumps({"columns": roster_rows.columns, "rows": list(roster_rows)}))
        readable = [e for e in entries if not e.error]
        summary.unreadable = [f"{e.origin}: {e.error}" for e in entries if e.error]
        # A regrade is kept as the keys still to grade again (REGRADE_LEFT), so one interrupted resumes where it
        # stopped, by the same command or a plain run: what it had regraded is not graded a third time.
        left = set(json.loads(book.get_meta(REGRADE_LEFT) or "[]"))
        if regrade and not left:
            left = {keys[e.student_id] for e in readable}
            book.set_meta(REGRADE_LEFT, json.dumps(sorted(left)))
        elif left:
            count = len(left & set(keys.values()))
            summary.warnings.append(f"an interrupted regrade resumed: {count} submission{'s' if count != 1 else ''} "
                                    f"{'were' if count != 1 else 'was'} left to grade again")
        todo = [e for e in readable if keys[e.student_id] in left or not book.is_graded(keys[e.student_id])]
        summary.reused = len(readable) - len(todo)
        presented, shown = _presented(book), _presentation(pictures, course)
        graded_now = {e.student_id for e in todo}
        kept = sorted(presented[keys[e.student_id]] for e in readable if e.student_id not in graded_now
                      and presented.get(keys[e.student_id], shown) != shown)
        if kept:
            summary.warnings.append(
                f"{len(kept)} submission{'s' if len(kept) != 1 else ''} graded before keep the pages made with "
                f"{kept[0]}{' (or other settings)' if len(set(kept)) > 1 else ''}, not this run's {shown}: "
                "pictures and the rubric's figures change no score, so nothing is graded again for them "
                "-- add --regrade to make those pages anew")

        def finished(entry: Entry, outcome: dict):
            # A fault of RESULTS (full, read-only, deleted) stops the batch with a StorageError;
            # only what is this submission's own (a result that cannot be stored) fails it alone.
            key = keys[entry.student_id]
            if "storage" in outcome:   # this machine's temporary folder is full or read-only
                raise StorageError.from_exception(OSError(outcome["errno"], outcome["storage"]), outcome["path"])
            if "result" in outcome:
                book.check_in_place()   # a deleted RESULTS is not written again piecemeal
                try:
                    _write_student(out, entry, outcome["json"], outcome["page"],   # files first, then the commit
                                   outcome.get("figures"))
                    book.record(key, entry.student_id, entry.content_hash, selection, outcome["result"], lock=lock)
                    presented[key] = shown
                    summary.graded += 1
                except (OSError, ValueError, TypeError, KeyError) as exc:
                    outcome = {"error": f"the results could not be stored: {type(exc).__name__}: {exc}"}
            if "error" in outcome:
                book.record(key, entry.student_id, entry.content_hash, selection, reason=outcome["error"], lock=lock)
                summary.failed.append(f"{entry.student_id}: {outcome['error']}")
            if key in left:
                left.discard(key)
                book.set_meta(REGRADE_LEFT, json.dumps(sorted(left)))
            if progress:
                progress("done", entry, summary)

        if progress:
            progress("start", None, BatchSummary(students=len(todo)))
        arguments = (selection.split(","), course.call_timeout, PICTURES[pictures], course.hidden_points_visible,
                     course.inputs_secret)
        rules = {"forbid": course.forbid, "exercise_budget": course.exercise_budget,
                 "submission_budget": course.submission_budget, "labs": course.labs, "hide": course.hide,
                 "gradings": 1 if dask_scheduler else min(workers or os.cpu_count() or 1, max(len(todo), 1)),
                 "figures": sorted(course.rubric)}   # the review shows them beside the report
        if dask_scheduler:
            from .cluster import grade_on_dask

            grade_on_dask(dask_scheduler, todo, arguments, finished, rules=rules)
        else:
            _grade_locally(todo, arguments, finished, workers or os.cpu_count() or 1, rules,
                           running=lambda ids: setattr(summary, "running", ids))

        if left:   # (every submission graded: a key left belongs to no one handed in now)
            book.set_meta(REGRADE_LEFT, "[]")
        book.set_meta(PRESENTED, json.dumps({key: presented[key] for key in set(keys.values()) if key in presented},
                                            sort_keys=True))
        standing = class_grades(book, course)
        # Every run is an audit: whose final grade moved since the last one, and what moved it.
        before, _ = changes.recorded(book)
        now = changes.standings(standing.grades)
        standing.changes = summary.changes = changes.compare(before, now) if before is not None else []
        summary.first_run = before is None
        changes.record(book, now, standing.changes)
        standing.latest_changes = changes.last_changes(book)
        book.check_in_place()   # not the exports of a gradebook that is gone

    # Exports: every page and file shows the one final grade (course points, overrides, late rule).
    # A full disk or a read-only folder: a StorageError naming the file (the gradings are kept).
    summary.warnings += standing.warnings
    with storing(out):
        summary.files = _write_exports(out, standing)
        summary.files += exports.write_ignored(out, upload.ignored)
    ledger_path = (course.late_days or {}).get("ledger")
    with storing(Path(ledger_path) if ledger_path else out):   # a full disk there: one line, like RESULTS'
        ledger = exports.record_late_days(course, standing.grades)   # the term's other assignments spend after these
    summary.files += [ledger] if ledger else []
    book.check_in_place()   # RESULTS deleted while the exports were written
    summary.files_not_graded = [f"{g.student['student_id']}: {left_aside}" for g in standing.grades
                                if (left_aside := exports.files_not_graded(g.student.get("result")))]
    if standing.roster:
        summary.unmatched = [f"{g.student['student_id'] or g.student['display_name']}: "
                             + ("on the roster, no submission" if g.student["status"] == "no submission"
                                else "not on the roster") for g in standing.grades
                             if g.student["status"] == "no submission" or not g.roster]
    return summary


def _presentation(pictures: str, course: CourseConfig) -> str:
    """The pictures and figures a grading's page is made with, in words."""
    return f"pictures: {pictures}; figures: {', '.join(sorted(course.rubric)) or 'none'}"


def _presented(book: Gradebook) -> dict[str, str]:
    """:data:`PRESENTED` as the gradebook keeps it (empty where an earlier version kept none)."""
    try:
        kept = json.loads(book.get_meta(PRESENTED) or "{}")
    except ValueError:
        return {}
    return {k: v for k, v in kept.items() if isinstance(k, str) and isinstance(v, str)} if isinstance(kept, dict) else {}


@dataclass
class ClassGrades:
    """The class's final grades, as every page and export shows them (see :func:`class_grades`)."""

    students: list[dict]                   # Gradebook.class_results()
    grades: list                           # exports.StudentGrade, roster-only students last
    exercises: list[tuple[str, float]]     # (exercise id, the checks' own maximum)
    course: CourseConfig
    roster: exports.Roster
    warnings: list[str]
    report_max: dict[str, float] = field(default_factory=dict)   # exercise -> what its report is worth
    changes: list = field(default_factory=list)   # changes.Change: what the last run moved (the overview, CSV)
    latest_changes: list = field(default_factory=list)   # each student's latest change (their page)

    @property
    def possible(self) -> float:
        return exports.max_total(self.exercises, self.course, self.report_max)


def class_grades(book: Gradebook, course: CourseConfig | None = None) -> ClassGrades:
    """Every student's final grade, computed in this one place for the batch's exports, the
    students' pages, ``autograder report``, ``autograder review`` and the class overview: the
    checks' scores in the course's points, the reports' reviews (the rubric items applied, at
    the points the gradebook's rubric gives them now), the late rule, the instructor's overrides
    (kept in the gradebook) and the roster (the last one given, kept there too). ``course``:
    the batch's own unless given."""
    course = course or batch_course(book)
    students = book.class_results()
    overrides = [exports.Override(**o) for o in book.overrides()]
    roster = stored_roster(book)
    exercises = [(e.id, e.max_score()) for e in select(course.select)]
    rubric = book.rubric()
    grades, warnings = exports.compute_grades(students, exercises, course, overrides, roster,
                                              rubric=rubric, reviews=book.reviews(), ledger=exports.read_ledger(course))
    warnings += exports.lms_warnings(grades, course, roster.columns)
    return ClassGrades(students, grades, exercises, course, roster, warnings,
                       exports.report_maxima(rubric, exercises), changes.recorded(book)[1],
                       changes.last_changes(book))


def _write_exports(out: Path, standing: ClassGrades, course_title: str | None = None,
                   unreadable: list[str] | None = None) -> list[Path]:
    """The CSVs, every graded student's page brought up to date (adjustments, review, final
    grade) and the class overview; returns the files written (the pages left out). With
    ``unreadable``, a page whose stored grading cannot be rendered is named there
    (``"id: why"``) instead of stopping the rest."""
    files = exports.write_csvs(out, standing.grades, standing.exercises, standing.course,
                               roster_given=bool(standing.roster), roster_columns=standing.roster.columns,
                               report_max=standing.report_max)
    files.append(exports.write_csv(out / "changes.csv", changes.rows(standing.changes)))
    for grade in standing.grades:
        if grade.student.get("feedback"):
            try:
                _refresh_page(out, grade, standing.possible, standing.course,
                              changes.for_student(standing.latest_changes, grade.student["student_id"]))
            except ValueError as exc:
                if unreadable is None:
                    raise
                unreadable.append(f"{grade.student['student_id']}: {exc}")
    files.append(_write_overview(out, standing, course_title))
    return files


def write_exports(out, course: CourseConfig | None = None,
                  course_title: str | None = None) -> tuple[list[Path], list[str]]:
    """``autograder report``: every export written again from the gradebook (the CSVs, each
    student's page with the current adjustments, review and final grade, the overview), as
    the batch writes them at its end. Returns the files written and warnings (a page that
    cannot be written again is one; :func:`restore_student_files` names it too).

    While a batch writes RESULTS nothing is written here (:class:`.ingest.IngestError`): the
    batch writes every export itself when it finishes, reviews included.
    Raises :class:`StorageError` if RESULTS cannot be read or written.
    """
    out = Path(out)
    with _only_writer(out), Gradebook(out, readonly=True) as book:
        standing = class_grades(book, course)
        unreadable: list[str] = []
        with storing(out):
            files = _write_exports(out, standing, course_title, unreadable)
    return files, standing.warnings + unreadable


def stored_roster(book: Gradebook) -> exports.Roster:
    """The roster the batch was last given (an empty one when it never was)."""
    try:
        data = json.loads(book.get_meta("roster") or "{}")
        return exports.Roster((row for row in data.get("rows", []) if isinstance(row, dict)),
                              [str(c) for c in data.get("columns", [])])
    except (TypeError, ValueError, AttributeError):   # written by another version: no roster
        return exports.Roster()


def _grading_fingerprint(course: CourseConfig) -> str:
    """What of the course changes a grading (its time limits, forbidden calls, the inputs'
    secret, what the student's page shows), hashed: never the secret itself."""
    import hashlib

    rules = {name: getattr(course, name) for name in ("call_timeout", "exercise_budget", "submission_budget",
                                                       "forbid", "inputs_secret", "hidden_points_visible")}
    return hashlib.sha256(json.dumps(rules, sort_keys=True).encode()).hexdigest()[:16]


@contextmanager
def _only_writer(out: Path):
    """One batch at a time writes RESULTS (the lock goes with the process, however it ends).
    A folder that cannot be written is refused here, before anything is graded."""
    import fcntl

    with storing(out / ".batch.lock"):
        out.mkdir(parents=True, exist_ok=True)
        handle = open(out / ".batch.lock", "w")
    with handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            raise IngestError(f"another autograder batch is writing {out}; wait for it to finish") from None
        yield


def overdue_after(rules: dict | None) -> float:
    """Seconds after which a grading process still on one submission is stopped: twice the course's
    submission budget and two minutes (the grading stops its own work at that budget; what follows it --
    the page, its pictures -- is bounded too)."""
    budget = (rules or {}).get("submission_budget") or CourseConfig().submission_budget
    return 2 * float(budget) + 120.0


def _grade_locally(todo: list[Entry], arguments, finished, workers: int, rules: dict | None = None,
                   running: Callable[[list[str]], None] | None = None) -> None:
    """A pool of grading processes, the cores shared out among them. A process that dies is
    charged to the submission it was grading alone (the others go on; it is replaced), and
    a submission whose grading kills its process ``POOL_ATTEMPTS`` times is failed."""
    if not todo:
        return
    workers = min(workers, len(todo))
    threads = cores_each(workers)
    entries = {e.student_id: e for e in todo}
    deaths: dict[str, list[str]] = {}
    # Every grading has landed (or the batch stops): the processes end while the exports
    # are written; on Ctrl-C or SIGTERM they stop their gradings before this returns.
    with GradingPool(workers, grade_files, task_seconds=overdue_after(rules)) as pool:
        for entry in todo:
            pool.submit(entry.student_id, (entry.files, *arguments, entry.student_id, threads, rules))
        for student_id, outcome in pool.outcomes():
            entry = entries[student_id]
            if running:
                running(pool.running)
            if isinstance(outcome, ProcessDeath) and outcome.overdue:   # (run again, it would hang again)
                outcome = {"error": f"the grading process was {outcome.how}"}
            elif isinstance(outcome, ProcessDeath):
                deaths.setdefault(student_id, []).append(outcome.how)
                if len(deaths[student_id]) < POOL_ATTEMPTS:
                    pool.submit(student_id, (entry.files, *arguments, student_id, threads, rules))
                    continue
                how = ", ".join(dict.fromkeys(deaths[student_id]))   # each way it died, once
                outcome = {"error": f"the grading process died while grading this submission, "
                                    f"{POOL_ATTEMPTS} times: {how}"}
            finished(entry, outcome)


def _write_student(out: Path, entry: Entry, results_json: str, page: str, figures: dict | None = None) -> None:
    """The student's page, results, the sources graded (``sources/``, for the similarity report)
    and the figures made from their code for the review (``figures/<figure id>.png``).

    Raises :class:`StorageError` when RESULTS cannot be written (full, read-only...);
    an ``OSError`` only for what is the submission's own (a file name this file
    system refuses)."""
    folder = out / entry.student_id
    with storing(folder):
        write_atomically(folder / "feedback.html", page)
        write_atomically(folder / "results.json", results_json)
        sources = folder / "sources"
        shutil.rmtree(sources, ignore_errors=True)
        shutil.rmtree(folder / "figures", ignore_errors=True)
        for figure_id, png in (figures or {}).items():   # ids of the grader's own producers
            (folder / "figures").mkdir(exist_ok=True)
            (folder / "figures" / f"{figure_id}.png").write_bytes(png)
    for relative, data in entry.files.items():
        parts = PurePosixPath(relative).parts
        if parts and not any(part in ("", ".", "..") for part in parts) and not relative.startswith("/"):
            target = sources.joinpath(*parts)
            try:
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_bytes(data)
            except OSError as exc:
                if exc.errno in STORAGE_ERRNOS:
                    raise StorageError.from_exception(exc, exc.filename or target) from exc
                raise


def _known(out: Path):
    """The ids earlier runs gave (none before the first): a student keeps theirs in every download."""
    try:
        with Gradebook(out, readonly=True) as book:
            return book.identities()
    except FileNotFoundError:
        return None


def _write_overview(out: Path, standing: ClassGrades, course_title: str | None = None) -> Path:
    """``index.html``: the class's final grades, what it got wrong, and every report written."""
    from ..classreport.pages import write_overview_of

    return write_overview_of(out, standing, course_title)


def _refresh_page(out: Path, grade, possible: float, course: CourseConfig, change=None) -> list[Path]:
    """Show the current adjustments on the student's page, and write again what was lost of the
    student's folder, from the gradebook's whole grading as the student may see it: the page
    (without its pictures) and ``results.json``. Returns the files written again.

    Raises :class:`StorageError` if RESULTS cannot be written, ``ValueError`` if the stored
    grading cannot be rendered."""
    folder = out / grade.student["student_id"]
    page_path, results_path = folder / "feedback.html", folder / "results.json"
    restored, view = [], None
    with storing(page_path, "read"):
        try:
            page = page_path.read_text(encoding="utf-8")
        except (FileNotFoundError, UnicodeDecodeError):   # lost, or damaged beyond reading
            page = None
    results_lost = not results_path.is_file()
    if page is None or results_lost:
        try:
            view = GradingResult.from_dict(grade.student["result"]).for_students(course.hidden_points_visible)
        except (KeyError, TypeError, ValueError) as exc:
            raise ValueError(f"its stored grading cannot be read ({type(exc).__name__}: {exc})") from None
    if page is None:
        page = html.render(view)
        restored.append(page_path)
    updated = exports.student_page(page, grade, possible, course, change)
    with storing(folder):
        if updated != page or restored:
            write_atomically(page_path, updated)
        if results_lost:
            write_atomically(results_path, json_text(strip_pictures(view.to_dict())))
            restored.append(results_path)
    return restored


# What `autograder report` needs of the batch's course to write a student's files as the batch
# did (never the inputs secret, nor the grading limits).
_REPORTED_COURSE = ("select", "assignment", "points", "late_penalty", "extensions", "late_days",
                    "hidden_points_visible", "canvas_assignment_id", "lms_exports", "rubric", "labs", "hide")


def _course_record(course: CourseConfig) -> str:
    return json.dumps({name: getattr(course, name) for name in _REPORTED_COURSE if hasattr(course, name)})


def batch_course(book: Gradebook) -> CourseConfig:
    """The course of the batch that last wrote ``book`` (the defaults for a gradebook without one)."""
    try:
        course = CourseConfig(**json.loads(book.get_meta("course") or "{}"))
    except (TypeError, ValueError):   # written by another version; CourseConfigError is a ValueError
        return CourseConfig()
    course.use_labs("the batch's course")   # its own labs, for the selection (a folder gone: an error)
    return course


def restore_student_files(out, course: CourseConfig | None = None) -> tuple[list[Path], list[str]]:
    """Write again each graded student's ``feedback.html`` and ``results.json`` lost from RESULTS,
    from the gradebook, as the batch writes them (the page without its pictures, with the
    instructor's adjustments); ``course`` is the batch's own (kept in the gradebook) unless given.

    Returns the files written and, for each student whose files could not be, ``"id: why"``.
    Raises :class:`StorageError` if RESULTS cannot be read or written.
    """
    out = Path(out)
    with Gradebook(out, readonly=True) as book:
        standing = class_grades(book, course)
    lost = {s["student_id"] for s in standing.students if s.get("feedback") and not all(
        (out / s["student_id"] / name).is_file() for name in ("feedback.html", "results.json"))}
    restored, problems = [], []
    for grade in standing.grades:
        if grade.student["student_id"] in lost:
            try:
                restored += _refresh_page(out, grade, standing.possible, standing.course)
            except ValueError as exc:
                problems.append(f"{grade.student['student_id']}: {exc}")
    return restored, problems
