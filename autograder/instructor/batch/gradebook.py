"""The class gradebook: SQLite in ``RESULTS/gradebook.sqlite`` (scores and messages, no pictures).

Tables
------
``students``
    The class as last read: derived id, display name, where it came from, LMS
    identities and group members (JSON), submission time, and the key of the
    submission currently graded for the student (or the reason it is unreadable).
    A student missing from a later download keeps their row, ``present`` 0: their
    last grading still counts, and every export shows they were not in the download.
``submissions``
    One row per graded submission, keyed by :func:`submission_key`: the student,
    the content hash of their files, the grader version, the dependency lock's
    hash and the selection graded. ``status`` is ``graded`` or ``failed`` (the grader
    could not finish: a crash of the grading process, never the student's fault
    alone); ``result`` is the results model as JSON without pictures.
``exercises``, ``checks``
    One row per submission and exercise, and per submission, exercise and check.
``gradings``
    One row per grading that completed: resumption is tested by counting them.
``overrides``
    The instructor's adjustments, kept across regrades (see :mod:`.exports`).
``report_files``, ``explanations``
    The student's lab report as last read (see :mod:`.ingest`): its ``.md`` and
    ``.pdf`` files (bytes, bounded), and the explanation of each exercise found in
    them or in the notebooks' tagged cells; ``students.report_problems`` lists what
    could not be read of it (JSON).
``rubric_items``, ``review_marks``, ``review_notes``
    The report's review (``autograder review``): the rubric's items per exercise
    (seeded from the course's ``rubric``, edited centrally: an item's points are
    read from here, so a change reaches every student it is applied to), the items
    applied per student and exercise, and a comment and "reviewed" flag per
    student and exercise; each with who changed it and when.
``comment_bank``
    The reviewers' reusable comments per exercise, by a short key: saved once, inserted
    into a student's comment by key, edited centrally. An insertion copies the text: a
    comment already saved on a student stays as written when the bank's text changes.
``meta``
    ``schema_version`` (a gradebook of an older schema is migrated in place when
    opened for writing) and ``course``, the course configuration of the last batch.

Every grading lands in one transaction (WAL journal, ``synchronous=FULL``), so a
run killed at any moment -- Ctrl-C, ``kill -9``, power loss -- leaves each
submission either fully recorded or not at all, and the next run grades exactly
the ones that are not.

Storage faults -- a full disk, a read-only folder, a damaged gradebook, the
gradebook or its folder deleted while the batch runs (SQLite would go on writing
to the deleted file) -- raise :class:`StorageError`, which names the file and
says what to do; nothing committed is lost.
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import re
import sqlite3
from contextlib import contextmanager, suppress
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path

from ... import __version__
from ...engine.results import strip_pictures
from ...engine.versions import CONSTRAINTS, constraints_file, installed_opencv_major
from ...loading.text import printable

GRADEBOOK = "gradebook.sqlite"
SCHEMA_VERSION = 3   # 2: students.present; 3: reports and their review
LOCK_PACKAGES = ("numpy", "opencv-python-headless", "scikit-image")
REPOSITORY = Path(__file__).resolve().parents[3]

_SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (name TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS students (
    student_id TEXT PRIMARY KEY,
    display_name TEXT NOT NULL,
    source TEXT NOT NULL,
    origin TEXT NOT NULL,
    lms TEXT NOT NULL,                 -- JSON object
    members TEXT NOT NULL,             -- JSON list
    submitted_at TEXT,
    late INTEGER,                      -- NULL: the download does not say
    content_hash TEXT NOT NULL,
    submission_key TEXT,               -- NULL when unreadable
    unreadable TEXT NOT NULL DEFAULT '', -- why the entry could not be read
    present INTEGER NOT NULL DEFAULT 1, -- 0: no longer in SUBMISSIONS (kept with the last grading)
    report_problems TEXT NOT NULL DEFAULT '[]' -- JSON list: what could not be read of the report
);
CREATE TABLE IF NOT EXISTS submissions (
    key TEXT PRIMARY KEY,
    student_id TEXT NOT NULL,
    content_hash TEXT NOT NULL,
    grader_version TEXT NOT NULL,
    lock_hash TEXT NOT NULL,
    selection TEXT NOT NULL,
    status TEXT NOT NULL,              -- graded | failed
    reason TEXT NOT NULL DEFAULT '',
    total REAL, max_total REAL,
    result TEXT,                       -- results model JSON, pictures removed
    seconds REAL,
    graded_at TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS exercises (
    key TEXT NOT NULL, exercise_id TEXT NOT NULL, title TEXT NOT NULL,
    score REAL NOT NULL, max_score REAL NOT NULL, message TEXT NOT NULL,
    PRIMARY KEY (key, exercise_id));
CREATE TABLE IF NOT EXISTS checks (
    key TEXT NOT NULL, exercise_id TEXT NOT NULL, position INTEGER NOT NULL, name TEXT NOT NULL,
    score REAL NOT NULL, max_score REAL NOT NULL, status TEXT NOT NULL,
    message TEXT NOT NULL, hint TEXT NOT NULL, hidden INTEGER NOT NULL,
    PRIMARY KEY (key, exercise_id, position));
CREATE TABLE IF NOT EXISTS gradings (
    key TEXT NOT NULL, student_id TEXT NOT NULL, finished_at TEXT NOT NULL, status TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS overrides (
    position INTEGER PRIMARY KEY, student TEXT NOT NULL, exercise TEXT NOT NULL,
    points REAL, penalty REAL, comment TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS report_files (
    student_id TEXT NOT NULL, path TEXT NOT NULL, data BLOB NOT NULL,
    PRIMARY KEY (student_id, path));
CREATE TABLE IF NOT EXISTS explanations (
    student_id TEXT NOT NULL, exercise TEXT NOT NULL, text TEXT NOT NULL, source TEXT NOT NULL,
    truncated INTEGER NOT NULL, PRIMARY KEY (student_id, exercise));
CREATE TABLE IF NOT EXISTS report_figures (   -- pictures in the report, thumbnailed in a worker
    student_id TEXT NOT NULL, exercise TEXT NOT NULL, number INTEGER NOT NULL, source TEXT NOT NULL,
    width INTEGER NOT NULL, height INTEGER NOT NULL, thumb BLOB NOT NULL,
    PRIMARY KEY (student_id, exercise, number));
CREATE TABLE IF NOT EXISTS rubric_items (
    exercise TEXT NOT NULL, item_id TEXT NOT NULL, position INTEGER NOT NULL,
    text TEXT NOT NULL, points REAL NOT NULL,
    course_text TEXT, course_points REAL,   -- as the course last gave it (NULL: added in the review)
    changed_by TEXT NOT NULL, changed_at TEXT NOT NULL,
    PRIMARY KEY (exercise, item_id));
CREATE TABLE IF NOT EXISTS review_marks (
    student_id TEXT NOT NULL, exercise TEXT NOT NULL, item_id TEXT NOT NULL,
    marked_by TEXT NOT NULL, marked_at TEXT NOT NULL,
    PRIMARY KEY (student_id, exercise, item_id));
CREATE TABLE IF NOT EXISTS comment_bank (
    exercise TEXT NOT NULL, key TEXT NOT NULL, text TEXT NOT NULL,
    changed_by TEXT NOT NULL, changed_at TEXT NOT NULL,
    PRIMARY KEY (exercise, key));
CREATE TABLE IF NOT EXISTS review_notes (
    student_id TEXT NOT NULL, exercise TEXT NOT NULL, comment TEXT NOT NULL DEFAULT '',
    done INTEGER NOT NULL DEFAULT 0, changed_by TEXT NOT NULL, changed_at TEXT NOT NULL,
    PRIMARY KEY (student_id, exercise));
"""

_STUDENT_COLUMNS = ("student_id", "display_name", "source", "origin", "lms", "members", "submitted_at",
                    "late", "content_hash", "submission_key", "unreadable", "present", "report_problems")
REVIEW_COMMENT_LENGTH = 10_000   # characters of one review comment
BANK_KEY = re.compile(r"[A-Za-z0-9][A-Za-z0-9_-]{0,29}")   # a reusable comment's key
BANK_MAX_COMMENTS = 100          # reusable comments per exercise

# What a storage fault means for the instructor: errno values and SQLite's result codes.
_FULL_ERRNOS = {errno.ENOSPC, errno.EDQUOT, errno.EFBIG}
_READONLY_ERRNOS = {errno.EROFS, errno.EACCES, errno.EPERM}
STORAGE_ERRNOS = _FULL_ERRNOS | _READONLY_ERRNOS | {errno.EIO}   # the disk's faults, not a file name's
_ADVICE = {
    "full": "Free space and run the same command again: finished gradings are kept.",
    "read-only": "Make it writable (or write the results elsewhere) and run the same command again: "
                 "finished gradings are kept.",
    "busy": "Another program holds it locked: close that program and run the same command again: "
            "finished gradings are kept.",
    "io": "Check the disk and run the same command again: finished gradings are kept.",
    "other": "Fix that and run the same command again: finished gradings are kept.",
}


class StorageError(Exception):
    """RESULTS cannot be read or written as it should be; the message names the file and says what to do.

    ``path`` is the file, ``kind`` one of ``full``, ``read-only``, ``busy``, ``io``,
    ``other`` (the file system refused), ``corrupt`` (the gradebook is not a
    gradebook or is damaged: moved aside by the instructor, never deleted here),
    ``vanished`` (deleted or moved while a batch wrote it) or ``newer`` (written by
    a newer autograder). Gradings already committed are never lost.
    """

    def __init__(self, path, kind: str, message: str):
        super().__init__(message)
        self.path, self.kind = Path(path), kind

    @classmethod
    def from_exception(cls, exc: BaseException, path, action: str = "write") -> "StorageError":
        """The fault ``exc`` (an ``OSError`` or a SQLite error) met reading or writing ``path``."""
        kind, detail = _fault(exc)
        if kind == "corrupt":
            return cls.corrupt(path, detail)
        return cls(path, kind, f"cannot {action} {path}: {detail}. {_ADVICE[kind]}")

    @classmethod
    def corrupt(cls, path, detail: str) -> "StorageError":
        return cls(path, "corrupt",
                   f"{path} is not a gradebook or is damaged ({detail}). Move it aside, e.g. "
                   f"mv {path} {path}.damaged (keep it: it may still be recovered), and run the same "
                   "command again: the class is then graded anew.")

    @classmethod
    def vanished(cls, path) -> "StorageError":
        return cls(path, "vanished",
                   f"{path} was deleted or moved while the batch was writing it, so the batch stopped: "
                   "what it graded since could not be kept. Run the same command again (students the "
                   "gradebook does not hold are graded again).")


def _fault(exc: BaseException) -> tuple[str, str]:
    """(kind, what the system said) for a storage fault."""
    if isinstance(exc, OSError):
        detail = exc.strerror or str(exc)
        if exc.errno in _FULL_ERRNOS:
            return "full", detail
        if exc.errno in _READONLY_ERRNOS:
            return "read-only", detail
        return ("io" if exc.errno == errno.EIO else "other"), detail
    name, text = getattr(exc, "sqlite_errorname", "") or "", str(exc)
    if name in ("SQLITE_NOTADB", "SQLITE_CORRUPT") or "not a database" in text or "malformed" in text:
        return "corrupt", text
    if name == "SQLITE_FULL" or "is full" in text:
        return "full", text
    if name.startswith(("SQLITE_READONLY", "SQLITE_CANTOPEN", "SQLITE_PERM")) or "readonly" in text \
            or "unable to open" in text:
        return "read-only", text
    if name.startswith(("SQLITE_BUSY", "SQLITE_LOCKED")) or "locked" in text:
        return "busy", text
    return ("io" if name.startswith("SQLITE_IOERR") or "I/O" in text else "other"), text


def _storage_fault(exc: BaseException) -> bool:
    """An error of the disk or the file, not of the program (a constraint, a bad statement)."""
    return isinstance(exc, (OSError, sqlite3.OperationalError)) or type(exc) is sqlite3.DatabaseError


@contextmanager
def storing(path, action: str = "write"):
    """Storage faults inside become :class:`StorageError` naming the file (the ``OSError``'s
    own file name where it has one, else ``path``)."""
    try:
        yield
    except (OSError, sqlite3.Error) as exc:
        if not _storage_fault(exc):
            raise
        named = getattr(exc, "filename", None) or path
        raise StorageError.from_exception(exc, named, action) from exc


def lock_hash() -> str:
    """What the grading depends on besides the grader: the pins of the installed OpenCV major
    (``constraints.txt``, or ``constraints-opencv4.txt`` under OpenCV 4), else library versions.

    A change of either (new pins, an upgraded OpenCV, a course moved to the other
    OpenCV major) makes every submission due for regrading, since scores may move
    with the libraries.
    """
    constraints = constraints_file(installed_opencv_major(), REPOSITORY) \
        if installed_opencv_major() in CONSTRAINTS else REPOSITORY / "constraints.txt"
    if constraints.is_file():
        text = constraints.read_text(encoding="utf-8")
    else:
        versions = []
        for package in LOCK_PACKAGES:
            try:
                versions.append(f"{package}=={metadata.version(package)}")
            except metadata.PackageNotFoundError:
                versions.append(f"{package} missing")
        text = "\n".join(versions)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def submission_key(student_id: str, content_hash: str, selection: str, grader_version: str = __version__,
                   lock: str | None = None) -> str:
    """The gradebook key of one student's submission graded one way.

    Two students handing in the same files are two submissions: each is graded
    (and timed, and shown) as their own.
    """
    lock = lock if lock is not None else lock_hash()
    parts = (student_id, content_hash, grader_version, lock, selection)
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()


class Gradebook:
    """The gradebook in ``folder`` (created on first use; an older schema is migrated).

    Only one process writes (the batch's coordinator); readers -- ``autograder
    report``, the class overview -- may read at any time, best with
    ``Gradebook(folder, readonly=True)`` (which never creates or changes anything).
    A damaged gradebook is refused when opened (:class:`StorageError`), before
    anything is graded; every storage fault afterwards raises it too.
    """

    def __init__(self, folder, readonly: bool = False, threads: bool = False):
        self.folder = Path(folder)
        self.path = self.folder / GRADEBOOK
        if readonly and not self.path.is_file():
            raise FileNotFoundError(f"no gradebook in {self.folder}: run autograder batch first")
        with storing(self.path, "read" if readonly else "write"):
            if readonly:
                self.db = sqlite3.connect(f"{self.path.resolve().as_uri()}?mode=ro", uri=True, timeout=60,
                                          isolation_level=None, check_same_thread=not threads)
            else:
                self.folder.mkdir(parents=True, exist_ok=True)
                # threads: the caller serialises its threads' use (the review application's lock)
                self.db = sqlite3.connect(self.path, timeout=60, isolation_level=None,
                                          check_same_thread=not threads)
            try:
                self.db.row_factory = sqlite3.Row
                self._open(readonly)
            except BaseException:
                self.db.close()
                raise

    def _open(self, readonly: bool) -> None:
        if not readonly:
            self.db.execute("PRAGMA journal_mode=WAL")   # the first read of the file: not a database?
            self.db.execute("PRAGMA synchronous=FULL")
        problems = [row[0] for row in self.db.execute("PRAGMA quick_check(3)")]
        if problems != ["ok"]:
            raise StorageError.corrupt(self.path, "; ".join(problems).replace("\n", " "))
        # SQLite writes whole pages: a part of one is a file cut short, which reads as zeros.
        page_size, size = self.db.execute("PRAGMA page_size").fetchone()[0], os.path.getsize(self.path)
        if size % page_size:
            raise StorageError.corrupt(self.path, f"cut short: {size} bytes is not a whole number of "
                                                  f"{page_size}-byte pages")
        # Refused before anything is created in it: a newer schema may have other tables.
        has_meta = self.db.execute("SELECT 1 FROM sqlite_master WHERE type='table' AND name='meta'").fetchone()
        version = self.get_meta("schema_version") if has_meta else None
        if version is not None and int(version) > SCHEMA_VERSION:
            raise StorageError(self.path, "newer",
                               f"{self.path} was written by a newer autograder (gradebook schema {version}; "
                               f"this one, {__version__}, knows up to {SCHEMA_VERSION}). Use that version, "
                               "or write the results elsewhere.")
        if not readonly:
            self.db.execute("BEGIN IMMEDIATE")
            try:
                for statement in _SCHEMA.split(";"):
                    if statement.strip():
                        self.db.execute(statement)
                self.db.execute("INSERT OR IGNORE INTO meta VALUES ('schema_version', ?)", (str(SCHEMA_VERSION),))
                self._migrate()
                self.db.execute("COMMIT")
            except BaseException:
                self._rollback()
                raise
        columns = {row["name"] for row in self.db.execute("PRAGMA table_info(students)")}
        self._present = "s.present" if "present" in columns else "1"   # a schema-1 gradebook read as it is
        self._tables = {row[0] for row in self.db.execute("SELECT name FROM sqlite_master WHERE type='table'")}
        stat = os.stat(self.path)
        self._identity = (stat.st_dev, stat.st_ino)

    def _migrate(self) -> None:
        """An older schema brought up to this one, in the open transaction."""
        version = int(self.db.execute("SELECT value FROM meta WHERE name='schema_version'").fetchone()[0])
        if version >= SCHEMA_VERSION:
            return
        columns = {row["name"] for row in self.db.execute("PRAGMA table_info(students)")}
        if "present" not in columns:   # schema 1: students missing from a download were deleted
            self.db.execute("ALTER TABLE students ADD COLUMN present INTEGER NOT NULL DEFAULT 1")
        if "report_problems" not in columns:   # schema 2: no reports (their tables are made above)
            self.db.execute("ALTER TABLE students ADD COLUMN report_problems TEXT NOT NULL DEFAULT '[]'")
        self.db.execute("UPDATE meta SET value=? WHERE name='schema_version'", (str(SCHEMA_VERSION),))

    def close(self):
        self.db.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def check_in_place(self) -> None:
        """Raise :class:`StorageError` unless the file this book opened is still at its path.

        A gradebook deleted (or its folder) while open is written on, unlinked, by
        SQLite without complaint: every grading since would be lost with it.
        """
        with storing(self.path, "read"):
            try:
                stat = os.stat(self.path)
            except FileNotFoundError:
                stat = None
        if stat is None or (stat.st_dev, stat.st_ino) != self._identity:
            raise StorageError.vanished(self.path)

    @contextmanager
    def _transaction(self):
        """``BEGIN IMMEDIATE`` ... ``COMMIT``, or ``ROLLBACK`` on any exception; storage faults
        as :class:`StorageError`, and none committed to a gradebook no longer in place."""
        with storing(self.path):
            self.check_in_place()
            self.db.execute("BEGIN IMMEDIATE")
            try:
                yield
                self.db.execute("COMMIT")
            except BaseException:
                self._rollback()
                raise

    def _rollback(self) -> None:
        # SQLite may have rolled back itself (a full disk): a second ROLLBACK must not hide the cause.
        if self.db.in_transaction:
            with suppress(sqlite3.Error):
                self.db.execute("ROLLBACK")

    def _reading(self):
        return storing(self.path, "read")

    # ------------------------------------------------------------------ meta
    def get_meta(self, name: str) -> str | None:
        with self._reading():
            row = self.db.execute("SELECT value FROM meta WHERE name=?", (name,)).fetchone()
        return None if row is None else row[0]

    def set_meta(self, name: str, value: str) -> None:
        with self._transaction():
            self.db.execute("INSERT OR REPLACE INTO meta VALUES (?, ?)", (name, value))

    # ------------------------------------------------------------------ the class
    def sync_students(self, entries, keys: dict[str, str]) -> list[str]:
        """Record the class as read now: ``entries`` (see :mod:`.ingest`), ``keys`` by student id,
        each with its report (files, explanations, problems) as read now.

        Students no longer in SUBMISSIONS keep their row (and so their last grading, their
        report and its review), marked ``present = 0``; returns their ids, sorted.
        """
        columns = ", ".join(_STUDENT_COLUMNS)
        with self._transaction():
            self.db.execute("UPDATE students SET present=0")
            for e in entries:
                report = getattr(e, "report", None)
                self.db.execute(
                    f"INSERT OR REPLACE INTO students ({columns}) VALUES ({', '.join('?' * len(_STUDENT_COLUMNS))})",
                    (e.student_id, e.display_name, e.source, e.origin, json.dumps(e.lms),
                     json.dumps(e.members), e.submitted_at, None if e.late is None else int(e.late),
                     e.content_hash, None if e.error else keys[e.student_id], e.error, 1,
                     json.dumps(list(report.problems) if report else [])))
                self.db.execute("DELETE FROM report_files WHERE student_id=?", (e.student_id,))
                self.db.execute("DELETE FROM explanations WHERE student_id=?", (e.student_id,))
                self.db.execute("DELETE FROM report_figures WHERE student_id=?", (e.student_id,))
                for f in getattr(report, "figures", ()):
                    self.db.execute("INSERT OR IGNORE INTO report_figures VALUES (?,?,?,?,?,?,?)",
                                    (e.student_id, f.exercise, f.number, f.source, f.width, f.height, f.thumb.tobytes()))
                for path, data in sorted(getattr(e, "report_files", {}).items()):
                    self.db.execute("INSERT INTO report_files VALUES (?,?,?)", (e.student_id, path, data))
                for exercise, x in sorted((report.explanations if report else {}).items()):
                    self.db.execute("INSERT INTO explanations VALUES (?,?,?,?,?)",
                                    (e.student_id, exercise, x.text, x.source, int(x.truncated)))
            rows = self.db.execute("SELECT student_id FROM students WHERE present=0 ORDER BY student_id")
            return [row[0] for row in rows]

    def identities(self) -> "Identities":
        """The ids given so far, by what tells each student apart (see :class:`.ingest.Identities`),
        students gone since included: the next download gives them to nobody else."""
        from .ingest import Identities

        with self._reading():
            rows = self.db.execute("SELECT student_id, origin, lms FROM students").fetchall()
        return Identities.of([{"student_id": row["student_id"], "origin": row["origin"],
                               "lms": _json_object(row["lms"])} for row in rows])

    def is_graded(self, key: str) -> bool:
        with self._reading():
            row = self.db.execute("SELECT status FROM submissions WHERE key=?", (key,)).fetchone()
        return row is not None and row["status"] == "graded"

    # ------------------------------------------------------------------ gradings
    def record(self, key: str, student_id: str, content_hash: str, selection: str,
               result: dict | None = None, reason: str = "", lock: str | None = None) -> None:
        """Store one grading (``result``, a results-model dict) or why it failed (``reason``)."""
        now = datetime.now(timezone.utc).isoformat(timespec="seconds")
        lock = lock if lock is not None else lock_hash()
        status = "graded" if result is not None else "failed"
        stored = json.dumps(strip_pictures(result), allow_nan=False) if result is not None else None
        with self._transaction():
            for table in ("submissions", "exercises", "checks"):
                self.db.execute(f"DELETE FROM {table} WHERE key=?", (key,))
            self.db.execute(
                "INSERT INTO submissions VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?)",
                (key, student_id, content_hash, __version__, lock, selection, status, reason,
                 result["total"] if result else None, result["max_total"] if result else None,
                 stored, result.get("seconds") if result else None, now))
            for exercise in (result or {}).get("exercises", []):
                self.db.execute("INSERT INTO exercises VALUES (?,?,?,?,?,?)",
                                (key, exercise["id"], exercise["title"], exercise["score"],
                                 exercise["max_score"], exercise.get("message", "")))
                for position, check in enumerate(exercise["checks"]):
                    self.db.execute("INSERT INTO checks VALUES (?,?,?,?,?,?,?,?,?,?)",
                                    (key, exercise["id"], position, check["name"], check["score"],
                                     check["max_score"], check["status"], check.get("message", ""),
                                     check.get("hint", ""), int(check.get("hidden", False))))
            self.db.execute("INSERT INTO gradings VALUES (?,?,?,?)", (key, student_id, now, status))

    def grading_counts(self) -> dict[str, int]:
        """How many times each submission key was graded (to completion)."""
        with self._reading():
            rows = self.db.execute("SELECT key, COUNT(*) AS n FROM gradings GROUP BY key").fetchall()
        return {row["key"]: row["n"] for row in rows}

    # ------------------------------------------------------------------ overrides
    def set_overrides(self, overrides) -> None:
        """Replace the stored overrides (rows of :class:`.exports.Override`)."""
        with self._transaction():
            self.db.execute("DELETE FROM overrides")
            for position, o in enumerate(overrides):
                self.db.execute("INSERT INTO overrides VALUES (?,?,?,?,?,?)",
                                (position, o.student, o.exercise, o.points, o.penalty, o.comment))

    def overrides(self) -> list[dict]:
        with self._reading():
            rows = self.db.execute(
                "SELECT student, exercise, points, penalty, comment FROM overrides ORDER BY position").fetchall()
        return [dict(row) for row in rows]

    # ------------------------------------------------------------------ reading
    def class_results(self) -> list[dict]:
        """The class as graded, one dict per student, sorted by student id.

        This is the interface the class overview (``index.html``) and every export
        read; it needs no grading and no pictures. Each dict holds:

        ``student_id`` : str
            The derived id; also the student's folder in RESULTS.
        ``display_name`` : str
            Name from the LMS metadata, else the entry's name.
        ``source``, ``origin`` : str
            Layout (``gradescope``/``canvas``/``moodle``/``entry``) and the item in SUBMISSIONS.
        ``lms`` : dict
            LMS identities (``canvas_user_id``, ``sid``, ``email``, ``moodle_participant_id`` ...).
        ``members`` : list of dict
            Group submitters (Gradescope), else empty.
        ``submitted_at`` : str or None; ``late`` : bool or None
            Submission time (ISO 8601) and the LMS's own late flag where known.
        ``status`` : str
            ``"graded"``, ``"unreadable"`` (the entry could not be read),
            ``"failed"`` (the grader could not finish) or ``"pending"`` (not graded yet).
        ``reason`` : str
            Why, for ``unreadable`` and ``failed``; empty otherwise.
        ``result`` : dict or None
            The results model exactly as :meth:`GradingResult.to_dict` makes it
            (``total``, ``max_total``, ``exercises[].checks[]`` with ``name``,
            ``status``, ``passed``, ``score``, ``max_score``, ``message``, ``hint``,
            ``output``, ``traceback`` ...) with every ``artifacts`` list empty;
            None unless graded.
        ``feedback`` : str or None
            Path of the student's ``feedback.html`` relative to RESULTS
            (``"alice/feedback.html"``), None unless graded.
        ``missing_from_download`` : bool
            True for a student the last batch did not find in SUBMISSIONS: kept, with
            the status, reason and result of their last grading.
        ``graded_at`` : str or None
            When the submission shown was graded (ISO 8601, UTC); None if never.
        ``content_hash``, ``lock`` : str
            The files' hash as read last, and the grader and course the shown grading was made
            under (empty if none): what tells a new submission from a changed grader
            (:mod:`.changes`).
        """
        with self._reading():
            rows = self.db.execute(
                "SELECT s.student_id, s.display_name, s.source, s.origin, s.lms, s.members, s.submitted_at, "
                f"s.late, s.unreadable, {self._present} AS present, g.status AS grading_status, "
                "g.reason AS grading_reason, g.result AS result, g.graded_at AS graded_at, "
                "s.content_hash AS content_hash, g.lock_hash AS lock "
                "FROM students s LEFT JOIN submissions g ON g.key = s.submission_key "
                "ORDER BY s.student_id").fetchall()
        out = []
        for row in rows:
            if row["unreadable"]:
                status, reason = "unreadable", row["unreadable"]
            elif row["grading_status"] is None:
                status, reason = "pending", ""
            else:
                status, reason = row["grading_status"], row["grading_reason"]
            graded = status == "graded"
            out.append({
                "student_id": row["student_id"], "display_name": row["display_name"],
                "source": row["source"], "origin": row["origin"],
                "lms": json.loads(row["lms"]), "members": json.loads(row["members"]),
                "submitted_at": row["submitted_at"],
                "late": None if row["late"] is None else bool(row["late"]),
                "status": status, "reason": reason,
                "result": json.loads(row["result"]) if graded else None,
                "feedback": f"{row['student_id']}/feedback.html" if graded else None,
                "missing_from_download": not row["present"],
                "graded_at": row["graded_at"],
                "content_hash": row["content_hash"], "lock": row["lock"] or "",
            })
        return out

    # ------------------------------------------------------------------ the report and its review
    def _has(self, table: str) -> bool:
        """Whether this gradebook has ``table`` (a read-only gradebook of an older schema may not)."""
        return table in self._tables

    def report(self, student_id: str) -> dict:
        """The student's report as last read: ``explanations`` (exercise -> dict with ``text``,
        ``source``, ``truncated``), ``files`` (path -> size in bytes: the ``.md`` and ``.pdf``
        handed in) and ``problems`` (sentences)."""
        out = {"explanations": {}, "files": {}, "problems": []}
        if not self._has("explanations"):
            return out
        with self._reading():
            for row in self.db.execute("SELECT exercise, text, source, truncated FROM explanations "
                                       "WHERE student_id=? ORDER BY exercise", (student_id,)):
                out["explanations"][row["exercise"]] = {"text": row["text"], "source": row["source"],
                                                        "truncated": bool(row["truncated"])}
            for row in self.db.execute("SELECT path, length(data) AS size FROM report_files WHERE student_id=? "
                                       "ORDER BY path", (student_id,)):
                out["files"][row["path"]] = row["size"]
            row = self.db.execute("SELECT report_problems FROM students WHERE student_id=?", (student_id,)).fetchone()
        if row is not None:
            out["problems"] = json.loads(row[0] or "[]")
        return out

    def report_figures(self, student_id: str) -> list[dict]:
        """The pictures in the student's report as last read (see
        :class:`autograder.loading.report.ReportFigure`): dicts with ``exercise`` ("" when
        under no exercise's heading), ``number``, ``source``, ``width``, ``height`` and
        ``thumb`` (its bytes: ``THUMB x THUMB`` grey ``uint8``), by number."""
        if not self._has("report_figures"):
            return []
        with self._reading():
            rows = self.db.execute("SELECT exercise, number, source, width, height, thumb FROM report_figures "
                                   "WHERE student_id=? ORDER BY number, exercise", (student_id,)).fetchall()
        return [{**dict(row), "thumb": bytes(row["thumb"])} for row in rows]

    def reports_handed_in(self) -> dict[str, dict]:
        """Per student with a report: ``explained`` (the exercises it explains, a set) and
        ``files`` (how many ``.md``/``.pdf`` files were handed in). Students without are absent."""
        out: dict[str, dict] = {}
        if not self._has("explanations"):
            return out

        def of(student_id):
            return out.setdefault(student_id, {"explained": set(), "files": 0})

        with self._reading():
            for row in self.db.execute("SELECT student_id, exercise FROM explanations"):
                of(row["student_id"])["explained"].add(row["exercise"])
            for row in self.db.execute("SELECT student_id, COUNT(*) AS n FROM report_files GROUP BY student_id"):
                of(row["student_id"])["files"] = row["n"]
        return out

    def report_file(self, student_id: str, path: str) -> bytes | None:
        """The bytes of one file of the student's report, None when there is no such file."""
        if not self._has("report_files"):
            return None
        with self._reading():
            row = self.db.execute("SELECT data FROM report_files WHERE student_id=? AND path=?",
                                  (student_id, path)).fetchone()
        return None if row is None else bytes(row[0])

    def sync_rubric(self, rubric: dict, who: str = "course") -> None:
        """Bring the stored rubric up to the course's ``rubric`` (see :class:`..course.CourseConfig`).

        A new item is added. An item the course now gives otherwise than it last did
        is changed as the course says (the course file was edited); an item the course
        gives as before keeps what the review made of it (its text and points edited
        centrally). Items the course no longer lists are kept, with their marks.
        """
        now = _now()
        with self._transaction():
            for exercise, items in rubric.items():
                for item in items:
                    row = self.db.execute("SELECT course_text, course_points FROM rubric_items "
                                          "WHERE exercise=? AND item_id=?", (exercise, item["id"])).fetchone()
                    given = (item["text"], float(item["points"]))
                    if row is None:   # last in its exercise, in the course's order
                        position = self.db.execute("SELECT COALESCE(MAX(position) + 1, 0) FROM rubric_items "
                                                   "WHERE exercise=?", (exercise,)).fetchone()[0]
                        self.db.execute("INSERT INTO rubric_items VALUES (?,?,?,?,?,?,?,?,?)",
                                        (exercise, item["id"], position, *given, *given, who, now))
                    elif (row["course_text"], row["course_points"]) != given:
                        self.db.execute("UPDATE rubric_items SET text=?, points=?, course_text=?, course_points=?, "
                                        "changed_by=?, changed_at=? WHERE exercise=? AND item_id=?",
                                        (*given, *given, who, now, exercise, item["id"]))

    def rubric(self) -> dict[str, list[dict]]:
        """The stored rubric: exercise -> its items in order, each a dict with ``id``, ``text``,
        ``points``, ``changed_by``, ``changed_at``."""
        if not self._has("rubric_items"):
            return {}
        with self._reading():
            rows = self.db.execute("SELECT exercise, item_id, text, points, changed_by, changed_at FROM rubric_items "
                                   "ORDER BY exercise, position, item_id").fetchall()
        out: dict[str, list[dict]] = {}
        for row in rows:
            out.setdefault(row["exercise"], []).append({
                "id": row["item_id"], "text": row["text"], "points": row["points"],
                "changed_by": row["changed_by"], "changed_at": row["changed_at"]})
        return out

    def set_rubric_item(self, exercise: str, item_id: str, text: str, points: float, who: str) -> None:
        """Change an item's text and points for every student it is applied to, or add the item
        (last in its exercise). Raises :class:`..course.CourseConfigError` for a malformed item."""
        from ..course import RUBRIC_MAX_ITEMS, CourseConfigError, check_rubric_item

        check_rubric_item(item_id, text, points, f"rubric item {item_id!r} of {exercise}")
        with self._transaction():
            updated = self.db.execute("UPDATE rubric_items SET text=?, points=?, changed_by=?, changed_at=? "
                                      "WHERE exercise=? AND item_id=?",
                                      (text, float(points), who, _now(), exercise, item_id)).rowcount
            if not updated:
                count, position = self.db.execute("SELECT COUNT(*), COALESCE(MAX(position) + 1, 0) FROM rubric_items "
                                                  "WHERE exercise=?", (exercise,)).fetchone()
                if count >= RUBRIC_MAX_ITEMS:   # as the course file may have, no more
                    raise CourseConfigError(f"rubric item {item_id!r} of {exercise}: {exercise} has "
                                            f"{count} items already; at most {RUBRIC_MAX_ITEMS}")
                self.db.execute("INSERT INTO rubric_items VALUES (?,?,?,?,?,NULL,NULL,?,?)",
                                (exercise, item_id, position, text, float(points), who, _now()))

    def set_mark(self, student_id: str, exercise: str, item_id: str, applied: bool, who: str) -> None:
        """Apply (or take back) a rubric item to one student's exercise; ``KeyError`` for an item
        the exercise's rubric does not have."""
        with self._transaction():
            if not self.db.execute("SELECT 1 FROM rubric_items WHERE exercise=? AND item_id=?",
                                   (exercise, item_id)).fetchone():
                raise KeyError(f"{exercise} has no rubric item {item_id!r}")
            if applied:
                self.db.execute("INSERT OR IGNORE INTO review_marks VALUES (?,?,?,?,?)",
                                (student_id, exercise, item_id, who, _now()))
            else:
                self.db.execute("DELETE FROM review_marks WHERE student_id=? AND exercise=? AND item_id=?",
                                (student_id, exercise, item_id))

    def set_review_note(self, student_id: str, exercise: str, who: str, comment: str | None = None,
                        done: bool | None = None) -> None:
        """Set the comment on a student's exercise and/or whether its review is done (None: unchanged).
        The comment is kept as written, control characters but newlines and tabs removed, bounded."""
        with self._transaction():
            row = self.db.execute("SELECT comment, done FROM review_notes WHERE student_id=? AND exercise=?",
                                  (student_id, exercise)).fetchone()
            old_comment, old_done = (row["comment"], bool(row["done"])) if row else ("", False)
            if comment is not None:
                comment = printable(comment)[:REVIEW_COMMENT_LENGTH]
            self.db.execute("INSERT OR REPLACE INTO review_notes VALUES (?,?,?,?,?,?)",
                            (student_id, exercise, old_comment if comment is None else comment,
                             int(old_done if done is None else done), who, _now()))

    def comment_bank(self) -> dict[str, list[dict]]:
        """The reusable comments: exercise -> dicts with ``key``, ``text``, ``changed_by``,
        ``changed_at``, by key."""
        if not self._has("comment_bank"):
            return {}
        with self._reading():
            rows = self.db.execute("SELECT * FROM comment_bank ORDER BY exercise, key").fetchall()
        out: dict[str, list[dict]] = {}
        for row in rows:
            out.setdefault(row["exercise"], []).append({name: row[name] for name in
                                                        ("key", "text", "changed_by", "changed_at")})
        return out

    def set_bank_comment(self, exercise: str, key: str, text: str, who: str) -> None:
        """Save (or change, for every later insertion) the reusable comment ``key`` of ``exercise``;
        an empty ``text`` deletes it. Raises ``ValueError`` for a malformed key or too many comments."""
        if not BANK_KEY.fullmatch(key):
            raise ValueError(f"a comment's key is 1 to 30 letters, digits, '-' or '_', starting with a letter "
                             f"or digit; not {key[:40]!r}")
        text = printable(text).strip()[:REVIEW_COMMENT_LENGTH]
        with self._transaction():
            if not text:
                self.db.execute("DELETE FROM comment_bank WHERE exercise=? AND key=?", (exercise, key))
                return
            count = self.db.execute("SELECT COUNT(*) FROM comment_bank WHERE exercise=? AND key<>?",
                                    (exercise, key)).fetchone()[0]
            if count >= BANK_MAX_COMMENTS:
                raise ValueError(f"{exercise} has {count} saved comments already; at most {BANK_MAX_COMMENTS}")
            self.db.execute("INSERT OR REPLACE INTO comment_bank VALUES (?,?,?,?,?)", (exercise, key, text, who, _now()))

    def reviews(self) -> dict[tuple[str, str], dict]:
        """Every review: (student id, exercise) -> dict with ``items`` (ids applied, in the rubric's
        order), ``points`` (their points now), ``comment``, ``done``, ``changed_by``, ``changed_at``
        (the last change of a mark or note). Pairs nobody reviewed are absent."""
        if not self._has("review_marks"):
            return {}
        with self._reading():
            marks = self.db.execute(
                "SELECT m.student_id, m.exercise, m.item_id, m.marked_by, m.marked_at, r.points "
                "FROM review_marks m JOIN rubric_items r ON r.exercise = m.exercise AND r.item_id = m.item_id "
                "ORDER BY m.student_id, m.exercise, r.position").fetchall()
            notes = self.db.execute("SELECT * FROM review_notes").fetchall()
        out: dict[tuple[str, str], dict] = {}

        def review(student_id, exercise):
            return out.setdefault((student_id, exercise), {"items": [], "points": 0.0, "comment": "", "done": False,
                                                           "changed_by": "", "changed_at": ""})

        for row in marks:
            r = review(row["student_id"], row["exercise"])
            r["items"].append(row["item_id"])
            r["points"] = round(r["points"] + row["points"], 4)
            if row["marked_at"] >= r["changed_at"]:
                r["changed_by"], r["changed_at"] = row["marked_by"], row["marked_at"]
        for row in notes:
            r = review(row["student_id"], row["exercise"])
            r["comment"], r["done"] = row["comment"], bool(row["done"])
            if row["changed_at"] >= r["changed_at"]:
                r["changed_by"], r["changed_at"] = row["changed_by"], row["changed_at"]
        return out


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="seconds")


def _json_object(text) -> dict:
    """A stored JSON object (``{}`` for anything else: an identity is then told by its origin)."""
    try:
        value = json.loads(text or "{}")
    except (TypeError, ValueError):
        return {}
    return value if isinstance(value, dict) else {}
