"""Reading a class's submissions: one :class:`Entry` per student, whatever the layout.

``SUBMISSIONS`` is a folder or a ``.zip`` (a single top folder inside is looked
through). Four layouts are recognised, in this order:

Gradescope "Export Submissions"
    ``submission_metadata.yml`` beside ``submission_<id>/`` folders. Names,
    student ids (``:sid:``), e-mails and submission times come from the metadata
    (read with ``yaml.safe_load``). A group submission is one entry whose
    ``members`` lists every submitter.
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

Inside an entry only ``.py`` and ``.ipynb`` files count; a ``.zip`` inside is
unpacked where it lies. A single file that is named after no lab module is taken
as the module when the selection grades one lab (``alice.py`` for lab07).
Hidden files and ``__MACOSX`` are ignored; every other top-level item becomes an
entry, and one that cannot be read carries the reason in :attr:`Entry.error`:
nothing is skipped silently.

Student ids are derived from the entry (``smith-john-12345`` from a name and an
LMS id, ``alice`` from a folder) and stay the same between runs.
"""

from __future__ import annotations

import hashlib
import re
import shutil
import tempfile
import unicodedata
import zipfile
from contextlib import contextmanager
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path, PurePosixPath

from ..course import parse_time
from ..submission import MAX_ARCHIVE_BYTES, SubmissionError, read_regular_files, unzip_regular_files

SOURCE_SUFFIXES = (".py", ".ipynb")
MAX_CLASS_ARCHIVE_BYTES = 4 * 2**30   # a whole class's zip, unpacked

CANVAS_NAME = re.compile(r"^(?P<name>.+?)(?P<late>_LATE)?_(?P<user>\d+)_(?P<submission>\d+)_(?P<file>.+)$")
CANVAS_RENAMED = re.compile(r"^(?P<stem>.+)-(?P<n>\d+)(?P<suffix>\.[^.]+)$")
MOODLE_NAME = re.compile(r"^(?P<name>.+)_(?P<participant>\d+)_assignsubmission_(?P<plugin>[a-z]+)_(?P<file>.*)$")
GRADESCOPE_METADATA = "submission_metadata.yml"


class IngestError(ValueError):
    """SUBMISSIONS itself cannot be read (missing, not a folder or zip)."""


@dataclass
class Entry:
    """One student's work, read from a class's submissions.

    Attributes
    ----------
    student_id : str
        Stable derived id (a slug), unique within the class.
    display_name : str
        The name to show (from LMS metadata where there is some).
    source : str
        ``"gradescope"``, ``"canvas"``, ``"moodle"`` or ``"entry"``.
    origin : str
        Where in SUBMISSIONS it came from (for messages).
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

    @property
    def content_hash(self) -> str:
        """SHA-256 over the files' names and bytes (the error instead, when unreadable)."""
        digest = hashlib.sha256()
        if self.error:
            digest.update(b"unreadable\0" + self.error.encode())
        for name in sorted(self.files):
            digest.update(name.encode() + b"\0" + self.files[name] + b"\0")
        return digest.hexdigest()


# ------------------------------------------------------------------ reading a class
def read_class(path, modules: list[str], every_module: list[str] = ()) -> list[Entry]:
    """Every student entry in the class folder or zip at ``path``, sorted by id.

    ``modules`` are the lab modules the selection grades, ``every_module`` those
    of all labs (for the lone-file rule: a file named after another lab's module
    is not renamed).
    """
    with _class_root(Path(path)) as root:
        if (root / GRADESCOPE_METADATA).is_file():
            entries = _gradescope(root)
        elif _looks_like(root, MOODLE_NAME):
            entries = _moodle(root)
        elif _looks_like(root, CANVAS_NAME, files_only=True):
            entries = _canvas(root)
        else:
            entries = _one_per_entry(root)
    for entry in entries:
        if not entry.error:
            _name_lone_file(entry, modules, set(every_module) | set(modules))
    _make_ids_unique(entries)
    return sorted(entries, key=lambda e: e.student_id)


@contextmanager
def _class_root(path: Path):
    if not path.exists():
        raise IngestError(f"submissions not found: {path}")
    if path.is_dir():
        yield _unwrap(path)
        return
    if not zipfile.is_zipfile(path):
        raise IngestError(f"{path.name}: expected a folder or a .zip holding the class's submissions")
    tmp = Path(tempfile.mkdtemp(prefix="class-"))
    try:
        _extract(path, tmp, MAX_CLASS_ARCHIVE_BYTES)
        yield _unwrap(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _unwrap(root: Path) -> Path:
    """A folder holding just one folder (``export/``) is looked through."""
    children = _visible(root)
    if len(children) == 1 and children[0].is_dir() and not _is_student_folder(children[0]):
        return _unwrap(children[0])
    return root


def _is_student_folder(folder: Path) -> bool:
    return any(p.suffix in SOURCE_SUFFIXES for p in folder.iterdir() if p.is_file())


def _visible(folder: Path) -> list[Path]:
    return sorted(p for p in folder.iterdir() if not p.name.startswith(".") and p.name != "__MACOSX")


def _looks_like(root: Path, pattern: re.Pattern, files_only: bool = False) -> bool:
    children = [p for p in _visible(root) if p.is_file() or not files_only]
    return bool(children) and sum(bool(pattern.match(p.name)) for p in children) >= max(1, len(children) // 2)


# ------------------------------------------------------------------ layouts
def _one_per_entry(root: Path) -> list[Entry]:
    entries = []
    for item in _visible(root):
        name = item.stem if item.is_file() else item.name
        entry = Entry(slug(name), name, "entry", item.name)
        _read_into(entry, item)
        entries.append(entry)
    return entries


def _gradescope(root: Path) -> list[Entry]:
    import yaml

    try:
        metadata = yaml.safe_load((root / GRADESCOPE_METADATA).read_text(encoding="utf-8")) or {}
        if not isinstance(metadata, dict):
            raise ValueError("expected a mapping of submission_<id> to its metadata")
    except (OSError, ValueError, yaml.YAMLError) as exc:
        raise IngestError(f"{GRADESCOPE_METADATA} is not readable: {exc}") from None
    entries, seen = [], set()
    for key, meta in sorted(metadata.items(), key=lambda kv: str(kv[0])):
        key = str(key)
        meta = meta if isinstance(meta, dict) else {}
        members = [{"name": str(s.get(":name", "")), "sid": str(s.get(":sid") or ""),
                    "email": str(s.get(":email") or "")}
                   for s in meta.get(":submitters") or [] if isinstance(s, dict)]
        first = members[0] if members else {"name": key, "sid": "", "email": ""}
        submission_id = key.removeprefix("submission_")
        name = " & ".join(m["name"] for m in members) or key
        # The sid (else the e-mail's user) keeps the id stable across resubmissions and exports.
        stable = first["sid"] or first["email"].split("@")[0] or submission_id
        entry = Entry(slug(first["name"] or key, stable), name, "gradescope", key,
                      lms={"gradescope_submission_id": submission_id, "sid": first["sid"], "email": first["email"]},
                      members=members, submitted_at=_iso(meta.get(":created_at")))
        folder = root / key
        if folder.is_dir():
            _read_into(entry, folder)
        else:
            entry.error = f"{key} is listed in {GRADESCOPE_METADATA} but has no folder in the export"
        seen.add(key)
        entries.append(entry)
    for item in _visible(root):
        if item.name not in seen and item.name != GRADESCOPE_METADATA:
            entry = Entry(slug(item.name), item.name, "gradescope", item.name,
                          error=f"{item.name} is not listed in {GRADESCOPE_METADATA}")
            entries.append(entry)
    return entries


def _canvas(root: Path) -> list[Entry]:
    by_user: dict[str, Entry] = {}
    uploads: dict[str, dict[str, tuple[int, bytes]]] = {}
    entries = []
    for item in _visible(root):
        match = CANVAS_NAME.match(item.name) if item.is_file() else None
        if not match:
            entries.append(Entry(slug(item.stem), item.name, "canvas", item.name,
                                 error="not named like a Canvas download (name_userid_submissionid_file)"))
            continue
        user = match["user"]
        entry = by_user.get(user)
        if entry is None:
            entry = by_user[user] = Entry(slug(match["name"], user), match["name"], "canvas", item.name,
                                          lms={"canvas_user_id": user, "canvas_submission_id": match["submission"]},
                                          late=False)
            uploads[user] = {}
        entry.late = entry.late or bool(match["late"])
        original, number = _undo_canvas_renaming(match["file"])
        if original not in uploads[user] or number > uploads[user][original][0]:
            try:
                uploads[user][original] = (number, _upload_bytes(item))
            except (OSError, ValueError) as exc:
                entry.error = str(exc)
    for user, entry in by_user.items():
        files = {name: data for name, (_, data) in uploads[user].items()}
        if not entry.error:
            _read_files_into(entry, files)
        entries.append(entry)
    return entries


def _undo_canvas_renaming(filename: str) -> tuple[str, int]:
    """``lab07-2.py`` -> (``lab07.py``, 2); a name without the suffix -> (name, 0)."""
    match = CANVAS_RENAMED.match(filename)
    if match and match["suffix"] in SOURCE_SUFFIXES + (".zip",):
        return match["stem"] + match["suffix"], int(match["n"])
    return filename, 0


def _moodle(root: Path) -> list[Entry]:
    by_participant: dict[str, Entry] = {}
    files: dict[str, dict[str, bytes]] = {}
    entries = []
    for item in _visible(root):
        match = MOODLE_NAME.match(item.name)
        if not match:
            entries.append(Entry(slug(item.stem), item.name, "moodle", item.name,
                                 error="not named like a Moodle download (Full Name_id_assignsubmission_file_)"))
            continue
        participant = match["participant"]
        entry = by_participant.get(participant)
        if entry is None:
            entry = by_participant[participant] = Entry(
                slug(match["name"], participant), match["name"], "moodle", item.name,
                lms={"moodle_participant_id": participant})
            files[participant] = {}
        if match["plugin"] != "file":
            continue  # online text, comments: nothing to grade
        if item.is_dir():
            part = Entry("", "", "", item.name)
            _read_into(part, item)
            if part.error and not part.files:
                entry.error = part.error
            files[participant].update(part.files)
        else:
            try:
                files[participant][match["file"]] = _upload_bytes(item)
            except (OSError, ValueError) as exc:
                entry.error = str(exc)
    for participant, entry in by_participant.items():
        if not entry.error:
            _read_files_into(entry, files[participant])
        entries.append(entry)
    return entries


# ------------------------------------------------------------------ one entry's files
def _read_into(entry: Entry, item: Path) -> None:
    """Collect ``item``'s source files (a folder, zip, .py or .ipynb) into ``entry``."""
    try:
        if item.is_dir():
            files = _folder_sources(item)
        elif item.suffix in SOURCE_SUFFIXES + (".zip",):
            files = {item.name: _upload_bytes(item)}
        else:
            raise ValueError(f"not a submission: expected a folder, .zip, .py or .ipynb, got {item.name}")
    except (OSError, ValueError) as exc:
        entry.error = str(exc)
        return
    _read_files_into(entry, files)


def _folder_sources(folder: Path) -> dict[str, bytes]:
    """The source files and zips of a student's folder, read as loading reads a submission:
    regular files only (a link is never followed), within the caps; reports, images and
    the like are never read."""
    refused: dict[str, str] = {}
    files = dict(sorted(read_regular_files(folder, refused, suffixes=SOURCE_SUFFIXES + (".zip",)).items()))
    if not files and refused:
        name, reason = next(iter(refused.items()))
        raise ValueError(f"{name} was not read: {reason}")
    return files


def _upload_bytes(item: Path) -> bytes:
    """A flat upload's bytes when it can hold code (.py, .ipynb, .zip); other uploads
    (a report PDF, pictures) are kept by name only, never read."""
    if PurePosixPath(item.name).suffix not in SOURCE_SUFFIXES + (".zip",):
        return b""
    if item.is_symlink() or not item.is_file():
        raise ValueError(f"{item.name} is not a regular file")
    if item.stat().st_size > MAX_ARCHIVE_BYTES:
        raise ValueError(f"{item.name} is larger than {MAX_ARCHIVE_BYTES // 2**20} MB")
    return item.read_bytes()


def _read_files_into(entry: Entry, files: dict[str, bytes]) -> None:
    """Keep the source files; unpack zips where they lie; record why when nothing is left."""
    try:
        kept: dict[str, bytes] = {}
        for name, data in sorted(files.items()):
            path = PurePosixPath(name)
            if path.suffix == ".zip":
                folder = path.parent / path.stem
                for inner, inner_data in _zip_sources(data, name).items():
                    kept[(folder / inner).as_posix()] = inner_data
            elif path.suffix in SOURCE_SUFFIXES:
                kept[name] = data
        if not kept:
            raise ValueError("no .py or .ipynb file in it" + (f" (found: {', '.join(sorted(files))[:200]})"
                                                              if files else " (it is empty)"))
    except ValueError as exc:
        entry.error = str(exc)
        return
    entry.files = kept


def _zip_sources(data: bytes, name: str) -> dict[str, bytes]:
    """The source files of a student's zip, unpacked by the loader's own deny-by-default
    reader (regular members only, caps, inflation checked as it streams)."""
    with tempfile.TemporaryDirectory(prefix="ingest-zip-") as scratch:
        archive, target = Path(scratch) / "upload.zip", Path(scratch) / "files"
        archive.write_bytes(data)
        target.mkdir()
        try:
            unzip_regular_files(archive, target)
        except SubmissionError as exc:
            raise ValueError(str(exc).replace("upload.zip", name)) from None
        return {p.relative_to(target).as_posix(): p.read_bytes()
                for p in sorted(target.rglob("*")) if p.is_file()}


def _extract(archive: Path, target: Path, limit: int) -> None:
    """Unpack the class's archive (every member: nested zips and metadata too), safely."""
    try:
        with zipfile.ZipFile(archive) as zf:
            if sum(info.file_size for info in zf.infolist()) > limit:
                raise IngestError(f"{archive.name} unpacks to more than {limit // 2**20} MB")
            for info in zf.infolist():
                if info.is_dir() or not _safe_member(info.filename):
                    continue
                dest = target / info.filename
                dest.parent.mkdir(parents=True, exist_ok=True)
                with zf.open(info) as source, open(dest, "wb") as sink:
                    shutil.copyfileobj(source, sink)
    except (zipfile.BadZipFile, zipfile.LargeZipFile, EOFError, NotImplementedError) as exc:
        raise IngestError(f"{archive.name} is not a readable zip archive: {exc}") from None


def _safe_member(name: str) -> bool:
    path = PurePosixPath(name.replace("\\", "/"))
    return not path.is_absolute() and ".." not in path.parts and not _ignored(path.parts)


def _ignored(parts) -> bool:
    return any(part.startswith(".") or part == "__MACOSX" or part == "__pycache__" for part in parts)


def _name_lone_file(entry: Entry, modules: list[str], every_module: set[str]) -> None:
    """A single source file named after no module is the module, when one lab is graded."""
    names = {PurePosixPath(n).stem for n in entry.files}
    if len(entry.files) != 1 or names & every_module or len(modules) != 1:
        if not names & every_module and len(entry.files) == 1 and len(modules) > 1:
            entry.error = (f"one file, {next(iter(entry.files))}, named after no lab module: "
                           f"name it like {modules[0]}.py")
        return
    [(name, data)] = entry.files.items()
    entry.files = {modules[0] + PurePosixPath(name).suffix: data}


# ------------------------------------------------------------------ ids
def slug(*parts: str) -> str:
    """A stable, readable id: ``slug("Élodie Durand", "123")`` is ``elodie-durand-123``."""
    text = " ".join(p for p in parts if p)
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode()
    text = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")
    return text[:80] or "student"


def _make_ids_unique(entries: list[Entry]) -> None:
    seen: dict[str, int] = {}
    for entry in sorted(entries, key=lambda e: (e.student_id, e.origin)):
        count = seen.get(entry.student_id, 0)
        seen[entry.student_id] = count + 1
        if count:
            entry.student_id = f"{entry.student_id}-{count + 1}"


def _iso(value) -> str | None:
    if value is None or value == "":
        return None
    if isinstance(value, datetime):
        return value.isoformat()
    try:
        return parse_time(str(value)).isoformat()
    except ValueError:
        return str(value)


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
    if (root / GRADESCOPE_METADATA).is_file():
        return f"{path} is a Gradescope export; {hint}"
    for pattern, lms in ((MOODLE_NAME, "Moodle"), (CANVAS_NAME, "Canvas")):
        if _looks_like(root, pattern, files_only=lms == "Canvas") and len(_visible(root)) > 1:
            return f"{path} looks like a {lms} download of several students' work; {hint}"
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
