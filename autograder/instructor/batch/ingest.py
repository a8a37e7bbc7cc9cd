"""Reading a class's submissions: one :class:`Entry` per student, whatever the layout.

``SUBMISSIONS`` is a folder or a ``.zip`` (a single top folder inside is looked
through). Four layouts are recognised, in this order:

Gradescope "Export Submissions"
    ``submission_metadata.yml`` beside ``submission_<id>/`` folders. Names,
    student ids (``:sid:``), e-mails and submission times come from the metadata,
    read by a safe YAML loader with bounded size, nesting and aliases; only plain
    text fields are taken. A key names a folder at the export's top, or nothing:
    a key with ``/`` or ``..`` in it is refused. A group submission is one entry
    whose ``members`` lists every submitter.
Canvas "Download Submissions"
    Flat files ``name_userid_submissionid_filename`` (``name_LATE_userid_...`` when
    late). Files are grouped per user id, the prefix is stripped, and Canvas's
    ``-1``/``-2`` renaming of re-uploaded files is undone (``lab07_x-1.py`` is
    ``lab07_x.py``: a Python module name cannot hold a hyphen, so the suffix is
    always Canvas's; the highest number, the latest upload, wins).
Moodle "Download all submissions"
    ``Full Name_participantid_assignsubmission_file_/`` folders (or flat files
    with that prefix when "download in folders" was off); online-text folders
    are ignored beside file folders.
One entry per student
    Anything else: each folder, ``.zip``, ``.py`` or ``.ipynb`` at the top is one
    student, named by it.

**The upload is untrusted input** (students write the names, the archives and part of
the metadata), so every item is read alone and fails alone:

- Ownership follows the LMS's own prefix: Canvas's ``name_userid_`` and Moodle's
  *first* ``_<participant>_assignsubmission_``; a name that holds a second such
  prefix, or files of one LMS id under two names, is ambiguous and refused, never
  filed under another student. Gradescope's own folder names its submission.
- Nothing outside the upload is read: links, devices, pipes and sockets are never
  followed or opened, at any depth, the top level included
  (:mod:`autograder.instructor.batch.tree`); a class zip is read in memory, only the members
  that can hold code, within their declared sizes and the caps.
- Whatever goes wrong in one entry becomes that entry's :attr:`Entry.error`
  ("unreadable" in the gradebook); items that are no student's submission (a
  stray PDF beside the folders, a link, a file not named as the LMS names files)
  are listed in :attr:`ClassUpload.ignored` with the reason, never made students.
- Names are made safe before anything stores them: the display name on one line,
  without control characters, at most 100 characters; the origin (the item's own
  name) with undecodable bytes and control characters escaped. Student ids are
  slugs unique by construction (checked against every id already given, case
  folded), stable between runs; LMS ids shared by two entries are reported.

Inside an entry only ``.py`` and ``.ipynb`` files are graded; a ``.zip`` inside is
unpacked where it lies. The lab report beside them is read the same way, deny by
default (:class:`.tree.ReportFiles`): ``.md`` files up to the report's cap and
``.pdf`` files (kept as files; their text and pictures read only in a sandbox worker,
:mod:`autograder.loading.pdf_report`; bounded), at most 20 per student; what
is refused is a sentence of :attr:`Entry.report`'s problems, never the entry's error.
:attr:`Entry.report` holds the explanations read from them and from the notebooks'
tagged cells (:func:`autograder.loading.report.read_report`). A single file that is named after no lab module is taken
as the module when the selection grades one lab (``alice.py`` for lab07).
"""

from __future__ import annotations

import hashlib
import re
import unicodedata
import zipfile
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path, PurePosixPath

from ...loading.headings import ExerciseNames
from ...loading.pdf_report import ReportReader
from ...sandbox.supervisor import usable_cores
from ...loading.report import Report, read_report
from ...loading.submission import plain_name
from ...loading.text import one_line, shown
from ...sandbox.files import CAPS, SOURCE_SUFFIXES, limit_for
from ..course import parse_time
from .tree import (REPORT_FILE_SUFFIXES, FILE, FOLDER, LINK, Budget, FolderTree, ReportFiles, Unreadable, UploadTree, ZipTree,
                   _zip_sources, is_hidden, source_files)

MAX_CLASS_SOURCE_BYTES = 2 * 2**30   # every student's sources together, held in memory
MAX_TOP_ITEMS = 20_000               # items looked at at the top of an upload
MAX_METADATA_BYTES = 32 * 2**20      # submission_metadata.yml
NAME_LENGTH = 100                    # characters of a display name
PDF_READERS = 4                      # workers reading a class's PDFs side by side, at most (and the cores)

CANVAS_NAME = re.compile(r"^(?P<name>.+?)(?P<late>_LATE)?_(?P<user>\d+)_(?P<submission>\d+)_(?P<file>.+)$")
CANVAS_RENAMED = re.compile(r"^(?P<stem>.+)-(?P<n>\d+)(?P<suffix>\.[^.]+)$")
# The first "_<id>_assignsubmission_<plugin>_" is Moodle's; what follows is the student's file name.
MOODLE_NAME = re.compile(r"^(?P<name>.+?)_(?P<participant>\d+)_assignsubmission_(?P<plugin>[a-z]+)_(?P<file>.*)$",
                         re.DOTALL)
MOODLE_PREFIX = re.compile(r"_\d+_assignsubmission_[a-z]+_")
GRADESCOPE_METADATA = "submission_metadata.yml"
GRADESCOPE_KEY = re.compile(r"^[A-Za-z0-9_-]{1,100}$")


class IngestError(ValueError):
    """SUBMISSIONS itself cannot be read (missing, not a folder or zip)."""


@dataclass
class Entry:
    """One student's work, read from a class's submissions.

    Attributes
    ----------
    student_id : str
        Stable derived id (a slug of ``[a-z0-9-]``, at most 80 characters), unique
        within the class whatever the case.
    display_name : str
        The name to show (from LMS metadata where there is some): one line, no
        control characters, at most 100 characters.
    source : str
        ``"gradescope"``, ``"canvas"``, ``"moodle"`` or ``"entry"``.
    origin : str
        Where in SUBMISSIONS it came from (for messages), escaped as :func:`autograder.loading.text.shown` does.
    files : dict of str to bytes
        Relative POSIX path to content, ``.py``/``.ipynb`` only.
    lms : dict of str to str
        LMS identities: ``canvas_user_id``, ``canvas_submission_id``,
        ``gradescope_submission_id``, ``sid``, ``email``, ``moodle_participant_id``.
    members : list of dict
        Every submitter of a group submission (``name``, ``sid``, ``email``).
    submitted_at : str or None
        ISO 8601 submission time where the download carries it.
    late : bool or None
        Whether the LMS marked it late (Canvas ``_LATE_``); None when unknown.
    error : str
        Why it cannot be graded; empty when it can.
    report_files : dict of str to bytes
        The lab report's ``.md`` and ``.pdf`` files, relative POSIX path to content
        (never graded, never part of :attr:`content_hash`: a report handed in later
        regrades nothing).
    report : Report or None
        The explanations read from the report files and the notebooks, the PDFs, and
        the problems (files refused included); None until the upload is read.
    """

    student_id: str
    display_name: str
    source: str
    origin: str
    files: dict[str, bytes] = field(default_factory=dict)
    lms: dict[str, str] = field(default_factory=dict)
    members: list[dict] = field(default_factory=list)
    submitted_at: str | None = None
    late: bool | None = None
    error: str = ""
    report_files: dict[str, bytes] = field(default_factory=dict)
    report: Report | None = None
    reports_found: ReportFiles = field(default_factory=ReportFiles, repr=False)

    @property
    def content_hash(self) -> str:
        """SHA-256 over the files' names and bytes (the error instead, when unreadable)."""
        digest = hashlib.sha256()
        if self.error:
            digest.update(b"unreadable\0" + self.error.encode())
        for name in sorted(self.files):
            digest.update(name.encode() + b"\0" + self.files[name] + b"\0")
        return digest.hexdigest()


@dataclass
class ClassUpload:
    """What :func:`read_upload` found: the students, what is no one's submission, and warnings."""

    entries: list[Entry] = field(default_factory=list)
    ignored: list[tuple[str, str]] = field(default_factory=list)   # (item, why it is not a submission)
    warnings: list[str] = field(default_factory=list)

    def ignore(self, item: str, reason: str) -> None:
        self.ignored.append((shown(item), reason))


# ------------------------------------------------------------------ reading a class
def read_class(path, modules: list[str], every_module: list[str] = ()) -> list[Entry]:
    """Every student entry in the class folder or zip at ``path``, sorted by id (see :func:`read_upload`)."""
    return read_upload(path, modules, every_module).entries


def read_upload(path, modules: list[str], every_module: list[str] = (),
                known: "Identities | None" = None, names: ExerciseNames | None = None,
                allow_unconfined: bool = False) -> ClassUpload:
    """Read the class folder or zip at ``path``: entries sorted by id, ignored items, warnings.

    ``modules`` are the lab modules the selection grades, ``every_module`` those
    of all labs (for the lone-file rule: a file named after another lab's module
    is not renamed). ``known``: the ids earlier downloads gave (the gradebook's,
    :meth:`.gradebook.Gradebook.identities`): a student seen before keeps their id, and
    no id ever given goes to anybody else. Raises :class:`IngestError` only when
    ``path`` itself cannot be read; anything wrong inside it is one entry's error or
    one ignored item. ``names``: the graded labs' exercises, which the headings of a report
    in the student's own structure may name (:mod:`autograder.loading.headings`); with them,
    PDFs and the report's pictures are read in sandbox workers, at the ``process-group``
    level only when ``allow_unconfined`` (as the batch grades).
    """
    upload = ClassUpload()
    unsafe: dict[int, str] = {}   # each entry's name as the download wrote it (see _names_told_apart)
    every = set(every_module) | set(modules)
    with _open_tree(Path(path)) as tree:
        for name in getattr(tree, "outside", []):
            upload.ignore(name, "its name points outside the archive; not read")
        _Reader(tree, _unwrap(tree, (), every), upload).read()
    # PDFs and report pictures: parsed in sandbox workers only (confined, unless allow_unconfined)
    with ReportReader(allow_unconfined=allow_unconfined) as reader:
        if names is not None:   # a class's PDFs read side by side first (read_report then finds them read)
            reader.prefetch([data for entry in upload.entries for path, data in entry.reports_found.files.items()
                             if path.lower().endswith(".pdf")], min(usable_cores(), PDF_READERS))
        for entry in upload.entries:
            if not entry.error:
                _name_lone_file(entry, modules, every)
            _read_report(entry, names, reader)
            written = entry.display_name
            _make_safe(entry)
            unsafe[id(entry)] = written
    _assign_ids(upload.entries, known or Identities())
    _names_told_apart(upload.entries, unsafe)
    upload.warnings += _shared_identities(upload.entries)
    upload.entries.sort(key=lambda e: e.student_id)
    return upload


def _read_report(entry: Entry, names: ExerciseNames | None = None, reader: ReportReader | None = None) -> None:
    """The entry's explanations, from its report files and notebooks (never raising); with
    ``names`` and ``reader``, the text of its PDFs and the report's figures too (read in workers)."""
    entry.report_files = dict(entry.reports_found.files)
    refused = entry.reports_found.problems()
    try:
        report = read_report({**entry.files, **entry.report_files}, names, reader, entry.reports_found.pictures)
    except Exception as exc:  # noqa: BLE001 - the contract says it never raises; a student's report never stops the class
        report = Report(problems=(f"the report could not be read ({type(exc).__name__})",))
    entry.report = Report(report.explanations, report.attachments, tuple(refused) + tuple(report.problems),
                          report.figures)


def _open_tree(path: Path) -> UploadTree:
    if path.is_symlink():
        raise IngestError(f"{shown(path)} is a symbolic link; give the class folder or zip itself")
    if not path.exists():
        raise IngestError(f"submissions not found: {shown(path)}")
    if path.is_dir():
        return FolderTree(path)
    try:
        return ZipTree.open(path, shown(path.name))
    except Unreadable as exc:
        raise IngestError(f"{exc}: expected a folder or a .zip holding the class's submissions") from None


def _unwrap(tree: UploadTree, root: tuple, modules: set[str]) -> tuple:
    """A folder holding just one folder (``export/``) is looked through, unless that folder
    is one student's work (it holds a lab module)."""
    names = _visible(tree, root)
    if len(names) == 1 and tree.kind(root + (names[0],)) == FOLDER \
            and not _holds_a_module(tree, root + (names[0],), modules):
        return _unwrap(tree, root + (names[0],), modules)
    return root


def _holds_a_module(tree: UploadTree, folder: tuple, modules: set[str]) -> bool:
    return any(PurePosixPath(n).stem in modules and n.endswith(SOURCE_SUFFIXES) and tree.kind(folder + (n,)) == FILE
               for n in _visible(tree, folder))


def _visible(tree: UploadTree, folder: tuple) -> list[str]:
    try:
        return [n for n in tree.children(folder) if not is_hidden(n)]
    except Unreadable:
        return []


def _layout(tree: UploadTree, root: tuple, names: list[str]) -> str:
    if GRADESCOPE_METADATA in names and tree.kind(root + (GRADESCOPE_METADATA,)) == FILE:
        return "gradescope"
    kinds = {n: tree.kind(root + (n,)) for n in names}
    if _mostly(kinds, MOODLE_NAME, (FILE, FOLDER)):
        return "moodle"
    if _mostly(kinds, CANVAS_NAME, (FILE,)):
        return "canvas"
    return "entry"


def _mostly(kinds: dict[str, str | None], pattern: re.Pattern, named: tuple) -> bool:
    """Whether at least half the items that could be someone's work are named by the LMS's
    pattern. Strays (a PDF, a link) are left out of the count, so thousands of them never
    turn an LMS download into a folder of entries; folders and code files that the pattern
    does not name count against it, so one student's oddly named file never turns a folder
    of entries into an LMS download."""
    matches = [n for n, kind in kinds.items() if kind in named and pattern.match(n)]
    work = [n for n, kind in kinds.items()
            if kind == FOLDER or (kind == FILE and n.endswith(SOURCE_SUFFIXES + (".zip",)))]
    return bool(matches) and len(matches) >= max(1, len(set(work) | set(matches)) // 2)


# ------------------------------------------------------------------ layouts
class _Reader:
    """Reads one upload's entries into ``upload``; each item alone, whatever happens to it."""

    def __init__(self, tree: UploadTree, root: tuple, upload: ClassUpload):
        self.tree, self.root, self.upload = tree, root, upload
        self.budget = Budget(MAX_CLASS_SOURCE_BYTES)

    def read(self) -> None:
        names = _visible(self.tree, self.root)
        if len(names) > MAX_TOP_ITEMS:
            self.upload.ignore(f"{len(names) - MAX_TOP_ITEMS} items after {shown(names[MAX_TOP_ITEMS - 1])}",
                               f"the upload holds more than {MAX_TOP_ITEMS} items; these were not looked at")
            names = names[:MAX_TOP_ITEMS]
        layouts = {"gradescope": self.gradescope, "canvas": self.canvas, "moodle": self.moodle,
                   "entry": self.one_per_entry}
        layouts[_layout(self.tree, self.root, names)](names)

    def kind(self, name: str) -> str | None:
        return self.tree.kind(self.root + (name,))

    def _not_followed(self, name: str) -> bool:
        """Links and special files at the top are listed and never looked into."""
        kind = self.kind(name)
        if kind in (FILE, FOLDER):
            return False
        self.upload.ignore(name, "a symbolic link; links are never followed" if kind == LINK
                           else "not a regular file or folder; not read")
        return True

    def add(self, entry: Entry, read) -> Entry:
        """Run ``read()`` to fill ``entry``; whatever it raises becomes the entry's error."""
        try:
            read()
        except Unreadable as exc:
            entry.error = str(exc)
        except Exception as exc:  # noqa: BLE001 - one student's upload never stops the class
            entry.error = f"it could not be read ({type(exc).__name__}: {exc})"
        self.upload.entries.append(entry)
        return entry

    # -------------------------------------------------------------- one entry per student
    def one_per_entry(self, names: list[str]) -> None:
        for name in names:
            if self._not_followed(name):
                continue
            if self.kind(name) == FILE and not name.endswith(SOURCE_SUFFIXES + (".zip",)):
                self.upload.ignore(name, "not a submission: expected a folder, .zip, .py or .ipynb")
                continue
            stem = PurePosixPath(name).stem if self.kind(name) == FILE else name
            entry = Entry(slug(stem), stem, "entry", name)
            self.add(entry, lambda: self.read_item(entry, name))

    def read_item(self, entry: Entry, name: str) -> None:
        """A folder's sources, or one top-level file (a zip unpacked in memory)."""
        path = self.root + (name,)
        if self.tree.problem(path):
            raise Unreadable(self.tree.problem(path))
        if self.kind(name) == FOLDER:
            entry.files = self.folder_sources(path, entry)
        else:
            entry.files = self.file_sources(path, name, entry=entry)

    def folder_sources(self, path: tuple, entry: Entry | None = None) -> dict[str, bytes]:
        """The sources under ``path`` (and the report's files, into ``entry``'s)."""
        refused: dict[str, str] = {}
        files = source_files(self.tree, path, refused, self.budget,
                             reports=entry.reports_found if entry is not None else None)
        if files:
            return files
        if refused:
            item, reason = next(iter(refused.items()))
            raise Unreadable(f"{item} was not read: {reason}")
        found = _visible(self.tree, path)
        raise Unreadable("no .py or .ipynb file in it" + (f" (found: {shown(', '.join(found[:10]), 200)})"
                                                          if found else " (it is empty)"))

    def file_sources(self, path: tuple, name: str, as_name: str | None = None,
                     entry: Entry | None = None) -> dict[str, bytes]:
        """One uploaded file: a source file as it is, a zip's sources in a folder named after it
        (and its report files, into ``entry``'s)."""
        as_name = as_name or name
        if name.endswith(".zip"):
            data = self.tree.read(path, CAPS.total_bytes)
            folder = PurePosixPath(as_name).with_suffix("")
            reports = ReportFiles() if entry is not None else None
            sources = _zip_sources(data, name, CAPS, self.budget, reports)
            if entry is not None:
                entry.reports_found.merge(reports, folder.as_posix())
            return {(folder / inner).as_posix(): d for inner, d in sources.items()}
        data = self.tree.read(path, limit_for(name, CAPS))
        self.budget.take(len(data))
        return {as_name: data}

    # -------------------------------------------------------------- Gradescope
    def gradescope(self, names: list[str]) -> None:
        metadata = self.gradescope_metadata()
        listed = set()
        for key, meta in sorted(metadata.items(), key=lambda kv: _text(kv[0])):
            key = _text(key)
            if not GRADESCOPE_KEY.match(key) or key in listed:
                self.upload.ignore(key or "(an empty key)", f"a key of {GRADESCOPE_METADATA} that names no "
                                   "submission folder of the export (folder names only); not read")
                continue
            listed.add(key)
            if not isinstance(meta, dict):
                self.upload.ignore(key, f"its entry in {GRADESCOPE_METADATA} is no submission's metadata; "
                                   "not read")
                continue
            submitters = meta.get(":submitters")
            members = [{"name": one_line(_text(s.get(":name")), NAME_LENGTH), "sid": _text(s.get(":sid"))[:100],
                        "email": _text(s.get(":email"))[:200]}
                       for s in (submitters if isinstance(submitters, list) else [])[:50] if isinstance(s, dict)]
            first = members[0] if members else {"name": key, "sid": "", "email": ""}
            submission_id = key.removeprefix("submission_")
            name = " & ".join(m["name"] for m in members if m["name"]) or key
            # The sid (else the e-mail's user) keeps the id stable across resubmissions and exports.
            stable = first["sid"] or first["email"].split("@")[0] or submission_id
            entry = Entry(slug(first["name"] or key, stable), name, "gradescope", key,
                          lms={"gradescope_submission_id": submission_id, "sid": first["sid"],
                               "email": first["email"]},
                          members=members, submitted_at=_iso(meta.get(":created_at")))

            def read(entry=entry, key=key):
                if key not in names or self.kind(key) != FOLDER or self.tree.problem(self.root + (key,)):
                    kind = self.kind(key) if key in names else None
                    raise Unreadable(f"{key} is listed in {GRADESCOPE_METADATA} but "
                                     + ("is a symbolic link, not followed" if kind == LINK else
                                        "is not a folder of the export" if kind else "has no folder in the export"))
                entry.files = self.folder_sources(self.root + (key,), entry)

            self.add(entry, read)
        for name in names:
            if name not in listed and name != GRADESCOPE_METADATA and not self._not_followed(name):
                self.upload.ignore(name, f"not listed in {GRADESCOPE_METADATA}; not graded")

    def gradescope_metadata(self) -> dict:
        try:
            text = self.tree.read(self.root + (GRADESCOPE_METADATA,), MAX_METADATA_BYTES).decode("utf-8")
            metadata = safe_yaml(text)
        except (Unreadable, UnicodeDecodeError, ValueError) as exc:
            raise IngestError(f"{GRADESCOPE_METADATA} is not readable: {one_line(exc, 300)}") from None
        if not isinstance(metadata, dict):
            raise IngestError(f"{GRADESCOPE_METADATA} is not readable: expected a mapping of "
                              "submission_<id> to its metadata")
        return metadata

    # -------------------------------------------------------------- Canvas
    def _unread_report(self, name: str, pattern: re.Pattern, owner: str, unread: dict) -> None:
        """A link or special file at the top named like a student's report file (listed as ignored
        already): kept in ``unread`` by its owner's LMS id, to be named on their review screen too."""
        match = pattern.match(name)
        if match and ReportFiles.wanted(match["file"]):
            why = self.tree.not_regular(self.root + (name,))
            file = _undo_canvas_renaming(match["file"])[0] if pattern is CANVAS_NAME else match["file"]
            unread.setdefault(match[owner], []).append((file, why))

    def canvas(self, names: list[str]) -> None:
        by_user: dict[str, list[tuple[str, re.Match]]] = {}
        unread: dict[str, list[tuple[str, str]]] = {}
        for name in names:
            if self._not_followed(name):
                self._unread_report(name, CANVAS_NAME, "user", unread)
                continue
            match = CANVAS_NAME.match(name) if self.kind(name) == FILE else None
            if not match:
                self.upload.ignore(name, "not named like a Canvas download (name_userid_submissionid_file); "
                                   "not graded")
                continue
            by_user.setdefault(match["user"], []).append((name, match))
        for user, uploads in sorted(by_user.items()):
            first = uploads[0][1]
            entry = Entry(slug(first["name"], user), first["name"], "canvas", uploads[0][0],
                          lms={"canvas_user_id": user, "canvas_submission_id": first["submission"]},
                          late=any(m["late"] for _, m in uploads))
            for file, why in unread.get(user, ()):
                entry.reports_found.refuse(file, why)
            self.add(entry, lambda entry=entry, uploads=uploads: self.canvas_files(entry, uploads))

    def canvas_files(self, entry: Entry, uploads) -> None:
        named = sorted({m["name"] for _, m in uploads})
        if len(named) > 1:
            raise Unreadable(f"files of Canvas user {entry.lms['canvas_user_id']} carry different names "
                             f"({shown(', '.join(named), 200)}): check the download")
        latest: dict[str, tuple[int, str]] = {}
        for name, match in uploads:
            original, number = _undo_canvas_renaming(match["file"])
            if original not in latest or number > latest[original][0]:
                latest[original] = (number, name)
        self.flat_files(entry, {original: name for original, (_, name) in latest.items()})

    def flat_files(self, entry: Entry, uploads: dict[str, str]) -> None:
        """An entry from flat uploads (file name in the entry -> item at the top)."""
        files: dict[str, bytes] = {}
        refused: dict[str, str] = {}
        for as_name, name in sorted(uploads.items()):
            if ReportFiles.wanted(as_name):
                entry.reports_found.read(self.tree, self.root + (name,), as_name, self.budget)
                continue
            if not as_name.endswith(SOURCE_SUFFIXES + (".zip",)):
                continue   # a picture, anything else: kept by name only, never read
            try:
                for key, data in self.file_sources(self.root + (name,), name, as_name, entry).items():
                    if key in files:
                        refused[shown(key)] = "two uploads give a file of that name"
                    else:
                        files[key] = data
            except Unreadable as exc:
                refused[shown(name)] = str(exc)
        if not files:
            if refused:
                item, reason = next(iter(refused.items()))
                raise Unreadable(f"{item} was not read: {reason}")
            raise Unreadable("no .py or .ipynb file in it (found: "
                             f"{shown(', '.join(sorted(uploads)[:10]), 200)})")
        entry.files = files

    # -------------------------------------------------------------- Moodle
    def moodle(self, names: list[str]) -> None:
        by_participant: dict[str, list[tuple[str, re.Match]]] = {}
        unread: dict[str, list[tuple[str, str]]] = {}
        for name in names:
            if self._not_followed(name):
                self._unread_report(name, MOODLE_NAME, "participant", unread)
                continue
            match = MOODLE_NAME.match(name)
            if not match:
                self.upload.ignore(name, "not named like a Moodle download (Full Name_id_assignsubmission_file_); "
                                   "not graded")
                continue
            if MOODLE_PREFIX.search(match["file"]) or (self.kind(name) == FOLDER and match["file"]):
                self.upload.ignore(name, "ambiguous: the name holds a second Moodle prefix "
                                   "(_<id>_assignsubmission_); filed under nobody, not graded")
                continue
            by_participant.setdefault(match["participant"], []).append((name, match))
        for participant, items in sorted(by_participant.items()):
            first = items[0][1]
            entry = Entry(slug(first["name"], participant), first["name"], "moodle", items[0][0],
                          lms={"moodle_participant_id": participant})
            for file, why in unread.get(participant, ()):
                entry.reports_found.refuse(file, why)
            self.add(entry, lambda entry=entry, items=items: self.moodle_files(entry, items))

    def moodle_files(self, entry: Entry, items) -> None:
        named = sorted({m["name"] for _, m in items})
        if len(named) > 1:
            raise Unreadable(f"items of Moodle participant {entry.lms['moodle_participant_id']} carry different "
                             f"names ({shown(', '.join(named), 200)}): check the download")
        flat: dict[str, str] = {}
        folders = []
        for name, match in items:
            if match["plugin"] != "file":
                continue   # online text, comments: nothing to grade
            if self.kind(name) == FOLDER:
                folders.append(name)
            elif match["file"] in flat:
                raise Unreadable(f"two uploads are named {shown(match['file'])}")
            else:
                flat[match["file"]] = name
        files: dict[str, bytes] = {}
        for folder in folders:
            files.update(self.folder_sources(self.root + (folder,), entry))
        if flat:
            part = Entry("", "", "", "")
            try:
                self.flat_files(part, flat)
            except Unreadable:
                if not files:
                    raise
            finally:
                entry.reports_found.merge(part.reports_found)
            clashes = sorted(set(files) & set(part.files))
            if clashes:
                raise Unreadable(f"two uploads are named {shown(clashes[0])}")
            files.update(part.files)
        if not files:
            raise Unreadable("no file submission in it (online text only)" if not folders
                             else "no .py or .ipynb file in it")
        entry.files = files


def _undo_canvas_renaming(filename: str) -> tuple[str, int]:
    """``lab07-2.py`` -> (``lab07.py``, 2); a name without the suffix -> (name, 0)."""
    match = CANVAS_RENAMED.match(filename)
    if match and match["suffix"].lower() in SOURCE_SUFFIXES + (".zip",) + REPORT_FILE_SUFFIXES:
        return match["stem"] + match["suffix"], int(match["n"])
    return filename, 0


# ------------------------------------------------------------------ metadata
def safe_yaml(text: str, max_expanded: int = 100_000, max_depth: int = 20):
    """``yaml.safe_load`` with bounded nesting and aliases: :class:`ValueError` when the
    aliases would expand to more than ``max_expanded`` values (a "billion laughs")
    or the nesting goes deeper than ``max_depth``.

    Only plain values are ever taken from the result (:func:`_text`) besides.
    """
    import yaml

    class Loader(yaml.SafeLoader):
        expanded = depth = 0

        def compose_node(self, parent, index):
            alias = self.check_event(yaml.AliasEvent)
            self.depth += 1
            try:
                if self.depth > max_depth:
                    raise ValueError(f"nested more than {max_depth} levels deep")
                node = super().compose_node(parent, index)
            finally:
                self.depth -= 1
            if alias:
                self.expanded += _node_count(node, self.sizes)
                if self.expanded > max_expanded:
                    raise ValueError(f"its aliases expand to more than {max_expanded} values")
            return node

    loader = Loader(text)
    loader.sizes = {}
    try:
        return loader.get_single_data()
    except yaml.YAMLError as exc:
        raise ValueError(str(exc)) from None
    except RecursionError:
        raise ValueError("nested too deep") from None
    finally:
        loader.dispose()


def _node_count(node, sizes: dict) -> int:
    """How many values a YAML node stands for once its aliases are expanded (memoised by node)."""
    import yaml

    key = id(node)
    if key not in sizes:
        sizes[key] = 1   # a node that holds itself counts once
        if isinstance(node, yaml.SequenceNode):
            sizes[key] = 1 + sum(_node_count(child, sizes) for child in node.value)
        elif isinstance(node, yaml.MappingNode):
            sizes[key] = 1 + sum(_node_count(k, sizes) + _node_count(v, sizes) for k, v in node.value)
    return sizes[key]


def _text(value) -> str:
    """A plain text or number from metadata as text; anything else (lists, maps, huge numbers) is ''."""
    if isinstance(value, str):
        return value[:1000]
    if isinstance(value, (int, float)) and not isinstance(value, bool) and abs(value) < 1e30:
        return str(value)
    return ""


def _iso(value) -> str | None:
    if value is None or value == "":
        return None
    if isinstance(value, datetime):
        return value.isoformat()
    text = _text(value)
    try:
        return parse_time(text).isoformat()
    except (ValueError, OverflowError):
        return shown(text, 40) or None


# ------------------------------------------------------------------ names and ids
def _name_lone_file(entry: Entry, modules: list[str], every_module: set[str]) -> None:
    """A single source file named after no module is the module, when one lab is graded. One whose name was
    plainly meant as a module (``Lab07_Transformations.py``, ``lab07_transformations (1).py``) is left as it is: the
    grading finds it under that name, with a note, as ``autograder grade`` does."""
    names = {plain_name(PurePosixPath(n).stem) for n in entry.files}
    if len(entry.files) != 1 or names & every_module or len(modules) != 1:
        if not names & every_module and len(entry.files) == 1 and len(modules) > 1:
            entry.error = (f"one file, {next(iter(entry.files))}, named after no lab module: "
                           f"name it like {modules[0]}.py")
        return
    [(name, data)] = entry.files.items()
    entry.files = {modules[0] + PurePosixPath(name).suffix: data}


def _make_safe(entry: Entry) -> None:
    """Every text of the entry fit to store (valid UTF-8) and to show (one line, bounded)."""
    entry.display_name = one_line(entry.display_name, NAME_LENGTH) or shown(entry.origin, NAME_LENGTH)
    entry.origin = shown(entry.origin)
    entry.error = one_line(entry.error, 500)
    entry.lms = {key: one_line(value, 200) for key, value in entry.lms.items()}
    entry.members = [{key: one_line(value, NAME_LENGTH if key == "name" else 200) for key, value in m.items()}
                     for m in entry.members]


def slug(*parts: str) -> str:
    """A stable, readable id: ``slug("Élodie Durand", "123")`` is ``elodie-durand-123``."""
    text = " ".join(p for p in parts if p)
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode()
    text = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")
    return text[:80].strip("-") or "student"


# The LMS's own identities of a person, surest first (see identity_keys).
_LMS_IDENTITIES = (("canvas", "canvas_user_id"), ("moodle", "moodle_participant_id"), ("sid", "sid"),
                   ("email", "email"))


def identity_keys(origin: str, lms: dict) -> list[str]:
    """What tells this student from every other across downloads, surest first: the LMS's
    user ids where the download carries them (a Canvas file name changes with each
    resubmission, its user id does not), else the place in the download (a folder's name,
    case and all: ``alice/`` and ``Alice/`` are two students)."""
    keys = [f"{kind}:{str(lms.get(field, '')).strip().lower()}" for kind, field in _LMS_IDENTITIES
            if str(lms.get(field, "")).strip()]
    return keys or [f"origin:{origin}"]


@dataclass
class Identities:
    """The ids earlier downloads gave: ``ids`` by identity key (:func:`identity_keys`; a key
    two students shared is left out: it tells neither), and every id ever given, of
    students still here or gone (``given``): none of them is ever given to anybody else."""

    ids: dict[str, str] = field(default_factory=dict)
    given: set[str] = field(default_factory=set)

    @classmethod
    def of(cls, students) -> "Identities":
        """From rows with ``student_id``, ``origin`` and ``lms`` (a dict)."""
        holders: dict[str, set[str]] = {}
        for row in students:
            for key in identity_keys(row["origin"], row["lms"]):
                holders.setdefault(key, set()).add(row["student_id"])
        return cls({key: next(iter(ids)) for key, ids in holders.items() if len(ids) == 1},
                   {row["student_id"] for row in students})


def _assign_ids(entries: list[Entry], known: Identities) -> None:
    """Unique ids by construction, and stable across downloads. A student seen before
    (:class:`Identities`) keeps their id. The others: an entry whose slug is its alone and
    was never given keeps it; the rest, in the order of their origins, take ``slug-2``,
    ``slug-3``, ... skipping every id already given, now or before (so ``alice``, ``Alice``
    and a folder ``alice-2`` never collide, and a newcomer ``Alice`` never takes the id
    ``alice`` of a student graded before, nor that of one gone since)."""
    kept: dict[str, Entry] = {}
    for entry in sorted(entries, key=lambda e: (e.origin, e.source)):
        earlier = next((known.ids[key] for key in identity_keys(entry.origin, entry.lms) if key in known.ids), None)
        if earlier is not None and earlier not in kept:
            kept[earlier] = entry
            entry.student_id = earlier
    returning = {id(entry) for entry in kept.values()}
    wanted: dict[str, list[Entry]] = {}
    for entry in entries:
        if id(entry) not in returning:
            wanted.setdefault(entry.student_id, []).append(entry)
    taken = set(known.given) | set(kept)
    alone = {base for base, group in wanted.items() if len(group) == 1 and base not in taken}
    taken |= alone
    for base, group in sorted(wanted.items()):
        if base in alone:
            continue
        number = 1
        for entry in sorted(group, key=lambda e: (e.origin, e.source)):
            candidate = base
            while candidate in taken:
                number += 1
                candidate = f"{base[:72]}-{number}"
            taken.add(candidate)
            entry.student_id = candidate


def _names_told_apart(entries: list[Entry], written: dict[int, str]) -> None:
    """Names made alike by making them safe (``bob`` and ``bob`` with an invisible character, ``written`` as the
    download wrote them, by ``id()`` of the entry) followed by each one's id, so that no two rows of a page or an
    export read as one student. Names that were alike as written (two students called Wei Zhang) stay as they are:
    the roster and the overrides find students by name too."""
    shown_by: dict[str, list[Entry]] = {}
    for entry in entries:
        shown_by.setdefault(entry.display_name, []).append(entry)
    for group in shown_by.values():
        if len({written.get(id(entry), entry.display_name) for entry in group}) > 1:
            for entry in group:   # (within the names' bound: the id is what tells them apart)
                told = f" ({entry.student_id[:NAME_LENGTH // 2]})"
                entry.display_name = one_line(entry.display_name, max(1, NAME_LENGTH - len(told))) + told


def _shared_identities(entries: list[Entry]) -> list[str]:
    """One warning per LMS identity (sid, e-mail, Canvas or Moodle id) found in several entries."""
    holders: dict[tuple[str, str], list[str]] = {}
    for entry in entries:
        identities = {("Canvas user id", entry.lms.get("canvas_user_id", "")),
                      ("Moodle participant", entry.lms.get("moodle_participant_id", ""))}
        for person in entry.members or [entry.lms]:
            identities |= {("SIS id", person.get("sid", "")), ("e-mail", person.get("email", "").lower())}
        for kind, value in identities:
            if value:
                holders.setdefault((kind, value), []).append(entry.student_id)
    return [f"{kind} {value} appears in {len(ids)} submissions ({', '.join(sorted(ids)[:5])}): "
            "each is graded on its own; check the download"
            for (kind, value), ids in sorted(holders.items()) if len(ids) > 1]


# ------------------------------------------------------------------ grade's guard
def several_students(path, modules: list[str]) -> str | None:
    """Why the folder at ``path`` looks like a class rather than one submission, or None.

    A folder is a class when some module has more than one candidate file in it,
    when it holds archives beside other students' folders, or when it is an LMS
    bulk download. One student's per-lab subfolders (``lab07/``, ``lab08/``) are fine.
    """
    root = Path(path)
    if not root.is_dir():
        return None
    hint = f"to grade a class, run: autograder batch {path} --out RESULTS"
    tree = FolderTree(root)
    names = _visible(tree, ())
    layout = _layout(tree, (), names)
    if layout == "gradescope":
        return f"{path} is a Gradescope export; {hint}"
    if layout in ("moodle", "canvas") and len(names) > 1:
        return f"{path} looks like a {layout.capitalize()} download of several students' work; {hint}"
    wanted = {m + s for m in modules for s in SOURCE_SUFFIXES}
    found: dict[str, list[Path]] = {}
    for file in root.rglob("*"):
        relative = file.relative_to(root)
        if file.name in wanted and not _ignored(relative.parts) and len(relative.parts) <= 4:
            found.setdefault(file.name, []).append(relative)
    for name, paths in sorted(found.items()):
        if len(paths) > 1:
            shown = ", ".join(str(p) for p in sorted(paths)[:4])
            return f"{path} holds {len(paths)} files named {name} ({shown}, ...); {hint}"
    # Per-lab subfolders (lab07/, lab08/) are one student's; archives beside them are not.
    archives = {p.relative_to(root).parts[0] for p in root.rglob("*.zip")
                if not _ignored(p.relative_to(root).parts) and len(p.relative_to(root).parts) <= 2}
    holders = archives | {p.parts[0] for paths in found.values() for p in paths if len(p.parts) > 1}
    if archives and len(holders) > 1:
        return (f"{path} holds submissions in {len(holders)} places ({', '.join(sorted(holders)[:4])}, ...); "
                f"{hint}")
    return None


def _ignored(parts) -> bool:
    return any(is_hidden(part) for part in parts)
