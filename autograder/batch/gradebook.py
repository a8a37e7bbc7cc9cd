"""The class gradebook: SQLite in ``RESULTS/gradebook.sqlite`` (scores and messages, no pictures).

Tables
------
``students``
    The class as last read: derived id, display name, where it came from, LMS
    identities and group members (JSON), submission time, and the key of the
    submission currently graded for the student (or the reason it is unreadable).
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

Every grading lands in one transaction (WAL journal, ``synchronous=FULL``), so a
run killed at any moment -- Ctrl-C, ``kill -9``, power loss -- leaves each
submission either fully recorded or not at all, and the next run grades exactly
the ones that are not.
"""

from __future__ import annotations

import hashlib
import json
import sqlite3
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path

from .. import __version__
from ..results import strip_pictures

GRADEBOOK = "gradebook.sqlite"
SCHEMA_VERSION = 1
LOCK_PACKAGES = ("numpy", "opencv-python-headless", "scikit-image")
REPOSITORY = Path(__file__).resolve().parents[2]

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
    unreadable TEXT NOT NULL DEFAULT '' -- why the entry could not be read
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
"""


def lock_hash() -> str:
    """What the grading depends on besides the grader: ``constraints.txt``, else library versions.

    A change of either (new pins, an upgraded OpenCV) makes every submission due
    for regrading, since scores may move with the libraries.
    """
    constraints = REPOSITORY / "constraints.txt"
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
    """The gradebook in ``folder`` (created on first use).

    Only one process writes (the batch's coordinator); readers -- ``autograder
    report``, the class overview -- may read at any time, best with
    ``Gradebook(folder, readonly=True)`` (which never creates anything).
    """

    def __init__(self, folder, readonly: bool = False):
        self.folder = Path(folder)
        self.path = self.folder / GRADEBOOK
        if readonly:
            if not self.path.is_file():
                raise FileNotFoundError(f"no gradebook in {self.folder}: run autograder batch first")
            self.db = sqlite3.connect(f"{self.path.resolve().as_uri()}?mode=ro", uri=True, timeout=60,
                                      isolation_level=None)
            self.db.row_factory = sqlite3.Row
            return
        self.folder.mkdir(parents=True, exist_ok=True)
        self.db = sqlite3.connect(self.path, timeout=60, isolation_level=None)
        self.db.row_factory = sqlite3.Row
        self.db.execute("PRAGMA journal_mode=WAL")
        self.db.execute("PRAGMA synchronous=FULL")
        with self._transaction():
            for statement in _SCHEMA.split(";"):
                if statement.strip():
                    self.db.execute(statement)
            self.db.execute("INSERT OR IGNORE INTO meta VALUES ('schema_version', ?)", (str(SCHEMA_VERSION),))

    def close(self):
        self.db.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _transaction(self):
        return _Transaction(self.db)

    # ------------------------------------------------------------------ the class
    def sync_students(self, entries, keys: dict[str, str]) -> None:
        """Record the class as read now: ``entries`` (see :mod:`.ingest`), ``keys`` by student id.

        Students no longer in SUBMISSIONS leave ``students``; their gradings stay.
        """
        with self._transaction():
            self.db.execute("DELETE FROM students")
            for e in entries:
                self.db.execute(
                    "INSERT INTO students VALUES (?,?,?,?,?,?,?,?,?,?,?)",
                    (e.student_id, e.display_name, e.source, e.origin, json.dumps(e.lms),
                     json.dumps(e.members), e.submitted_at, None if e.late is None else int(e.late),
                     e.content_hash, None if e.error else keys[e.student_id], e.error))

    def is_graded(self, key: str) -> bool:
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
        rows = self.db.execute("SELECT key, COUNT(*) AS n FROM gradings GROUP BY key")
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
        rows = self.db.execute("SELECT student, exercise, points, penalty, comment FROM overrides ORDER BY position")
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
        """
        rows = self.db.execute(
            "SELECT s.*, g.status AS grading_status, g.reason AS grading_reason, g.result AS result "
            "FROM students s LEFT JOIN submissions g ON g.key = s.submission_key ORDER BY s.student_id")
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
            })
        return out


class _Transaction:
    """``BEGIN IMMEDIATE`` ... ``COMMIT``, or ``ROLLBACK`` on any exception."""

    def __init__(self, db):
        self.db = db

    def __enter__(self):
        self.db.execute("BEGIN IMMEDIATE")

    def __exit__(self, kind, *exc):
        self.db.execute("COMMIT" if kind is None else "ROLLBACK")
