"""A class upload read as one tree: a folder or a zip, read-only, bounded, never following a link.

Everything in a class upload -- folder and file names, archives, LMS metadata -- is
written or influenced by students, so it is read the way the grader reads one
submission (:mod:`autograder.loading.submission`): deny by default. A :class:`UploadTree`
answers three questions about a path (a tuple of names from the upload's top):
what it is (:meth:`~UploadTree.kind`: ``"folder"``, ``"file"``, ``"link"`` or
``"special"``, decided without following anything), what a folder holds, and the
bytes of a file, read only up to a limit. Nothing is ever written to disk: a class
zip is read member by member from the archive, only the members asked for, each
within its declared size and the caller's limit, so a 2.5 GiB picture in the
archive costs nothing, and a member name too long for the file system or a file
and a folder of the same name are just facts about the tree (:meth:`~UploadTree.problem`).

:func:`source_files` collects what can hold code under one path, with the
loader's caps, and unpacks a student's own ``.zip`` in memory the same way; given a
:class:`ReportFiles`, it collects the lab report's files beside them too (``.md``
up to the report's cap, ``.pdf`` as files never parsed here, each bounded and counted; PNG and
JPEG pictures, in memory only, for figure provenance).
"""

from __future__ import annotations

import io
import os
import stat
import zipfile
import zlib
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from ...loading.report import MAX_PROBLEMS, MAX_REPORT_BYTES, is_backup
from ...loading.submission import declared_members
from ...loading.text import shown
from ...sandbox.files import CAPS, SOURCE_SUFFIXES, Caps, Refused, check_name, limit_for, read_regular

FOLDER, FILE, LINK, SPECIAL = "folder", "file", "link", "special"
IGNORED_NAMES = ("__MACOSX", "__pycache__")
NAME_BYTES = 255              # a file or folder name any file system takes (the files are written to disk later)
MAX_CLASS_MEMBERS = 200_000   # members of a class archive (a class of 300 holds a few thousand)
REPORT_FILE_SUFFIXES = (".md", ".pdf")   # a lab report's files (a notebook's cells are read from the code)
# A Markdown report's pictures: kept in memory only, for their thumbnails (made in a sandbox worker) to
# be compared with the code's figures; never stored, never shown. Beyond the caps they are not compared.
PICTURE_SUFFIXES = (".png", ".jpg", ".jpeg")
PICTURE_MAGIC = (b"\x89PNG\r\n\x1a\n", b"\xff\xd8\xff")
MAX_PICTURES = 40                         # pictures kept per student
MAX_PICTURE_BYTES = 8 * 2**20             # one picture
MAX_PICTURES_TOTAL = 64 * 2**20           # their bytes together
MAX_ATTACHMENT_BYTES = 20 * 2**20        # one PDF handed in beside the report
MAX_REPORT_FILES = 20                    # report files kept per student
MAX_REPORT_TOTAL = 40 * 2**20            # their bytes together


class Unreadable(Exception):
    """One item of the upload cannot be read; the message says why, in a sentence."""


@dataclass
class Budget:
    """Bytes the whole class may still hold in memory (every student's sources together)."""

    remaining: int

    def take(self, size: int) -> None:
        if size > self.remaining:
            raise Unreadable("the class holds more sources than the batch keeps in memory "
                             "(grade it in parts)")
        self.remaining -= size


def irregular(mode: int) -> str:
    """Why a file of ``mode`` (``st_mode``, or a zip member's) is not read: what it is."""
    kinds = ((stat.S_ISFIFO, "a named pipe"), (stat.S_ISSOCK, "a socket"), (stat.S_ISCHR, "a character device"),
             (stat.S_ISBLK, "a block device"))
    if stat.S_ISLNK(mode):
        return "it is a symbolic link"
    what = next((name for test, name in kinds if test(mode)), None)
    return f"it is not a regular file ({what})" if what else "it is not a regular file"


def is_hidden(name: str) -> bool:
    """Dot files, macOS's ``__MACOSX`` and Python's caches are no one's work."""
    return name.startswith(".") or name in IGNORED_NAMES


@dataclass
class ReportFiles:
    """One student's report files as they are found (relative path -> bytes), and those refused
    (shown path -> why): deny by default, as the sources are read, with the report's own caps."""

    files: dict[str, bytes] = field(default_factory=dict)
    refused: dict[str, str] = field(default_factory=dict)
    total: int = 0
    pictures: dict[str, bytes] = field(default_factory=dict)   # PNG/JPEG files, for figure provenance
    pictures_total: int = 0

    @staticmethod
    def wanted(name: str) -> bool:
        return name.lower().endswith(REPORT_FILE_SUFFIXES + PICTURE_SUFFIXES) and not is_backup(name)

    def _picture(self, tree: "UploadTree", path: tuple, text: str, budget: Budget, caps: Caps) -> None:
        """Keep a picture within its caps, quietly: one not kept is only not compared."""
        if tree.kind(path) != FILE or len(self.pictures) >= MAX_PICTURES or text in self.pictures:
            return
        limit = min(MAX_PICTURE_BYTES, MAX_PICTURES_TOTAL - self.pictures_total)
        try:
            check_name(text, caps)
            data = tree.read(path, limit)
            if not data.startswith(PICTURE_MAGIC):
                return
            budget.take(len(data))
        except (Refused, Unreadable):
            return
        self.pictures[text] = data
        self.pictures_total += len(data)

    def refuse(self, text: str, why: str) -> None:
        """Note the report file ``text`` as not read, because ``why`` (named on the review screen)."""
        self.refused[shown(text)] = why

    def read(self, tree: "UploadTree", path: tuple, text: str, budget: Budget, caps: Caps = CAPS) -> None:
        """Keep the report file ``text`` (at ``path`` in ``tree``), or the reason it is refused."""
        if text.lower().endswith(PICTURE_SUFFIXES):
            self._picture(tree, path, text, budget, caps)
            return
        pdf = text.lower().endswith(".pdf")
        if tree.kind(path) in (LINK, SPECIAL):
            self.refuse(text, tree.not_regular(path))
            return
        try:
            check_name(text, caps)
            if any(len(part.encode()) > NAME_BYTES for part in PurePosixPath(text).parts):
                raise Unreadable(f"a name in its path is longer than {NAME_BYTES} bytes; shorten it")
            if len(self.files) >= MAX_REPORT_FILES:
                raise Unreadable(f"more than {MAX_REPORT_FILES} report files; the rest was not read")
            limit = MAX_ATTACHMENT_BYTES if pdf else MAX_REPORT_BYTES
            if self.total + limit > MAX_REPORT_TOTAL:
                limit = MAX_REPORT_TOTAL - self.total
            data = tree.read(path, limit)
            if pdf and not data.startswith(b"%PDF-"):
                raise Unreadable("it is not a PDF (it does not begin with %PDF-)")
            budget.take(len(data))
        except (Refused, Unreadable) as exc:
            self.refuse(text, str(exc))
            return
        if text in self.files:
            self.refuse(text, "the upload holds it twice")
            return
        self.files[text] = data
        self.total += len(data)

    def merge(self, other: "ReportFiles", folder: str = "") -> None:
        """``other``'s files and refusals, under ``folder`` (a zip's, unpacked where it lies)."""
        prefix = f"{folder}/" if folder else ""
        for name, data in other.files.items():
            key = prefix + name
            if key in self.files or len(self.files) >= MAX_REPORT_FILES or self.total + len(data) > MAX_REPORT_TOTAL:
                self.refused[shown(key)] = ("the upload holds it twice" if key in self.files
                                            else "more report files than are kept; not read")
                continue
            self.files[key] = data
            self.total += len(data)
        self.refused.update({prefix + name: why for name, why in other.refused.items()})
        for name, data in other.pictures.items():
            if prefix + name not in self.pictures and len(self.pictures) < MAX_PICTURES \
                    and self.pictures_total + len(data) <= MAX_PICTURES_TOTAL:
                self.pictures[prefix + name] = data
                self.pictures_total += len(data)

    def problems(self) -> list[str]:
        """Why each refused file was, at most :data:`MAX_PROBLEMS` sentences (thousands of files
        sent would be as many lines on the review screen and in the gradebook)."""
        sentences = [f"{name} was not read: {why}" for name, why in list(self.refused.items())[:MAX_PROBLEMS]]
        more = len(self.refused) - len(sentences)
        return sentences + ([f"and {more} more files were not read"] if more else [])


class UploadTree:
    """What every view of an upload answers (see the module docstring)."""

    label = "the upload"

    def kind(self, path: tuple[str, ...]) -> str | None:
        raise NotImplementedError

    def children(self, path: tuple[str, ...]) -> list[str]:
        """The names in the folder at ``path``, sorted."""
        raise NotImplementedError

    def read(self, path: tuple[str, ...], limit: int) -> bytes:
        """The bytes of the regular file at ``path``; :class:`Unreadable` beyond ``limit``."""
        raise NotImplementedError

    def problem(self, path: tuple[str, ...]) -> str:
        """Why ``path`` cannot be taken as it is (empty when it can)."""
        return ""

    def not_regular(self, path: tuple[str, ...]) -> str:
        """Why the link or special file at ``path`` is not read, naming what it is."""
        return "it is a symbolic link" if self.kind(path) == LINK else "it is not a regular file"

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class FolderTree(UploadTree):
    """A folder on disk, every item classified by ``lstat``: a link is a link, never its target."""

    def __init__(self, root: Path):
        self.root = Path(root)
        self.label = shown(self.root.name)

    def _path(self, path) -> Path:
        return self.root.joinpath(*path)

    def kind(self, path):
        try:
            mode = os.lstat(self._path(path)).st_mode
        except (OSError, ValueError):
            return None
        if stat.S_ISLNK(mode):
            return LINK
        if stat.S_ISDIR(mode):
            return FOLDER
        return FILE if stat.S_ISREG(mode) else SPECIAL

    def not_regular(self, path):
        try:
            return irregular(os.lstat(self._path(path)).st_mode)
        except (OSError, ValueError):
            return super().not_regular(path)

    def children(self, path):
        try:
            return sorted(os.listdir(self._path(path)))
        except OSError as exc:
            raise Unreadable(f"it cannot be listed ({exc.strerror})") from None

    def read(self, path, limit):
        try:
            return read_regular(self._path(path), limit)
        except Refused as exc:
            raise Unreadable(str(exc)) from None
        except ValueError:   # a NUL in a name
            raise Unreadable("its name cannot be opened") from None


@dataclass
class _Node:
    kind: str
    info: zipfile.ZipInfo | None = None
    children: set = field(default_factory=set)
    problem: str = ""


class ZipTree(UploadTree):
    """The members of a zip archive as a tree, read from the archive itself, never unpacked to disk.

    Member names are taken apart on ``/`` and ``\\``; an absolute name or one with a
    ``..`` part lies outside the archive (:attr:`outside`, listed by the caller); a
    name that is both a file and a folder, or that appears twice, is a
    :meth:`problem` of that path.
    """

    def __init__(self, archive: zipfile.ZipFile, label: str):
        self.archive, self.label = archive, label
        self.nodes: dict[tuple, _Node] = {(): _Node(FOLDER)}
        self.outside: list[str] = []
        for info in archive.infolist():
            self._add(info)

    @classmethod
    def open(cls, source, label: str, max_members: int = MAX_CLASS_MEMBERS) -> "ZipTree":
        """A tree over the archive at ``source`` (a path, or the bytes of a nested zip).

        The member count is read from the archive's end record before its directory
        is parsed; :class:`Unreadable` when it is not a zip or holds too many members.
        """
        handle = io.BytesIO(source) if isinstance(source, bytes) else open(source, "rb")
        try:
            count = declared_members(handle)
            if count is None:
                raise Unreadable(f"{label} is not a valid zip archive")
            if count > max_members:
                raise Unreadable(f"{label} holds more than {max_members} files")
            return cls(zipfile.ZipFile(handle), label)
        except Unreadable:
            handle.close()
            raise
        except (zipfile.BadZipFile, zipfile.LargeZipFile, OSError, EOFError, ValueError,
                NotImplementedError, UnicodeDecodeError) as exc:
            handle.close()
            raise Unreadable(f"{label} is not a valid zip archive ({type(exc).__name__})") from None

    def _add(self, info: zipfile.ZipInfo) -> None:
        name = info.filename.replace("\\", "/")
        parts = tuple(p for p in name.split("/") if p not in ("", "."))
        if not parts:
            return
        if name.startswith("/") or ".." in parts or ":" in parts[0]:
            self.outside.append(shown(info.filename))
            return
        mode = info.external_attr >> 16
        if info.is_dir():
            kind = FOLDER
        elif stat.S_ISLNK(mode):
            kind = LINK
        elif mode and stat.S_IFMT(mode) and not stat.S_ISREG(mode):
            kind = SPECIAL
        else:
            kind = FILE
        for depth in range(1, len(parts)):
            self._place(parts[:depth], FOLDER, None)
        self._place(parts, kind, None if kind == FOLDER else info)

    def _place(self, parts: tuple, kind: str, info) -> None:
        node = self.nodes.get(parts)
        if node is None:
            self.nodes[parts] = _Node(kind, info)
            self.nodes[parts[:-1]].children.add(parts[-1])
        elif kind == FOLDER and node.kind == FOLDER:
            return
        elif FOLDER in (kind, node.kind):
            node.problem = f"the archive holds a file and a folder both named {shown(parts[-1])}"
        else:
            node.problem = f"the archive holds {shown(parts[-1])} twice"

    def kind(self, path):
        node = self.nodes.get(tuple(path))
        return node.kind if node else None

    def children(self, path):
        return sorted(self.nodes[tuple(path)].children)

    def problem(self, path):
        node = self.nodes.get(tuple(path))
        return node.problem if node else ""

    def not_regular(self, path):
        node = self.nodes.get(tuple(path))
        if node is None or node.info is None:
            return super().not_regular(path)
        return irregular(node.info.external_attr >> 16)

    def read(self, path, limit):
        node = self.nodes.get(tuple(path))
        if node is None or node.kind != FILE or node.info is None:
            raise Unreadable("it is not a regular file")
        if node.problem:
            raise Unreadable(node.problem)
        return read_member(self.archive, node.info, limit)

    def close(self):
        handle = self.archive.fp
        self.archive.close()
        if handle is not None:
            handle.close()


def read_member(archive: zipfile.ZipFile, info: zipfile.ZipInfo, limit: int) -> bytes:
    """A member's bytes, inflated in 64 KiB steps and stopped at ``limit`` or at what it declares."""
    if info.flag_bits & 0x1:
        raise Unreadable("it is encrypted; zip it without a password")
    if info.file_size > limit:
        raise Unreadable(f"it unpacks to more than {limit / 2**20:g} MiB")
    chunks, size = [], 0
    try:
        with archive.open(info) as member:
            while chunk := member.read(1 << 16):
                size += len(chunk)
                if size > info.file_size or size > limit:
                    raise Unreadable("it unpacks to more than it declares")
                chunks.append(chunk)
    except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError, RuntimeError, OSError,
            ValueError) as exc:
        raise Unreadable(f"it cannot be unpacked ({type(exc).__name__})") from None
    return b"".join(chunks)


def source_files(tree: UploadTree, path: tuple[str, ...], refused: dict[str, str], budget: Budget,
                 caps: Caps = CAPS, nested: bool = False, reports: ReportFiles | None = None) -> dict[str, bytes]:
    """The files under ``path`` that can hold code: relative POSIX path -> bytes.

    The loader's rules: hidden items skipped; links, devices and pipes refused,
    never followed; at most ``caps.entries`` items looked at, ``caps.depth`` folders
    deep, ``caps.total_bytes`` in all, each file within its own cap; a name that is
    not valid UTF-8 or holds control characters is refused. A ``.zip`` among them
    is unpacked in memory into a folder named after it (unless ``nested``: a zip's
    own zips are not). What is refused goes into ``refused``: shown name -> reason.
    With ``reports``, the lab report's files are kept there (:class:`ReportFiles`).
    """
    suffixes = SOURCE_SUFFIXES if nested else SOURCE_SUFFIXES + (".zip",)
    files: dict[str, bytes] = {}
    seen, total = 0, 0
    pending = [((), 0)]
    while pending:
        relative, depth = pending.pop()
        try:
            names = tree.children(path + relative)
        except Unreadable as exc:
            refused[shown("/".join(relative) or tree.label)] = str(exc)
            continue
        for name in names:
            seen += 1
            item = relative + (name,)
            text = "/".join(item)
            if seen > caps.entries:
                refused[shown(text)] = f"more than {caps.entries} files; the rest was not read"
                return files
            if is_hidden(name):
                continue
            kind = tree.kind(path + item)
            problem = tree.problem(path + item)
            report = reports is not None and kind != FOLDER and ReportFiles.wanted(name)
            if problem and report:
                reports.refuse(text, problem)   # named on the review screen, not the entry's error
            elif problem:
                refused[shown(text)] = problem
            elif kind == FOLDER:
                if depth < caps.depth:
                    pending.append((item, depth + 1))
            elif report:   # a link or a special file too: refused there, with what it is
                reports.read(tree, path + item, text, budget, caps)
            elif kind in (LINK, SPECIAL):
                if name.endswith(suffixes) or kind == LINK:
                    refused[shown(text)] = tree.not_regular(path + item)
            elif kind == FILE and name.endswith(suffixes):
                try:
                    check_name(text, caps)
                    if any(len(part.encode()) > NAME_BYTES for part in item):
                        raise Unreadable(f"a name in its path is longer than {NAME_BYTES} bytes; shorten it")
                    limit = min(limit_for(name, caps), caps.total_bytes - total)
                    data = tree.read(path + item, limit)
                except (Refused, Unreadable) as exc:
                    refused[shown(text)] = str(exc)
                    continue
                if name.endswith(".zip"):
                    inner_reports = ReportFiles() if reports is not None else None
                    try:
                        inner = _zip_sources(data, name, caps, budget, inner_reports)
                    except Unreadable as exc:
                        refused[shown(text)] = str(exc)
                        continue
                    folder = PurePosixPath(text).with_suffix("")
                    if reports is not None:
                        reports.merge(inner_reports, folder.as_posix())
                    for inner_name, inner_data in inner.items():
                        key = (folder / inner_name).as_posix()
                        if key in files:
                            refused[shown(key)] = f"{shown(text)} holds a file of the same name"
                        else:
                            files[key] = inner_data
                    total += sum(map(len, inner.values()))
                    continue
                budget.take(len(data))
                total += len(data)
                if text in files:
                    refused[shown(text)] = "the upload holds it twice"
                else:
                    files[text] = data
    return files


def _zip_sources(data: bytes, name: str, caps: Caps, budget: Budget,
                 reports: ReportFiles | None = None) -> dict[str, bytes]:
    """The source files of a student's own zip, read in memory with the loader's caps (and its
    report files into ``reports``, when given)."""
    refused: dict[str, str] = {}
    with ZipTree.open(data, shown(name), max_members=caps.entries) as tree:
        files = source_files(tree, (), refused, budget, caps, nested=True, reports=reports)
    if not files and refused:
        inner, reason = next(iter(refused.items()))
        raise Unreadable(f"{inner} in {shown(name)} was not read: {reason}")
    return files
