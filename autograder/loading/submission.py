"""Finding the lab modules in what a student handed in.

A submission may be a folder (the modules at its top or one level down, as
unzipped archives often are), a single ``.py`` file, a ``.zip`` archive, or
Jupyter notebooks named like the modules (``lab07_transformations.ipynb``, whose
definitions become the module, see :mod:`autograder.loading.notebooks`). The result is a
plain folder of ``.py`` modules that the sandbox copies, plus a content hash
identifying the submission.

Reading is deny-by-default (the grader may run as root): only regular files
from inside the submission are copied, never what a symbolic link points to,
and every cap (:class:`Caps`) is checked before a byte is read or inflated.
A file that breaks a rule is refused with a message naming it
(:attr:`Submission.refused`).

Nothing the student handed in stops the others from being graded: a file
plainly meant as a module (``Lab07_Transformations.py``, ``lab07_transformations (1).py``,
or one inside a ``.zip`` within the folder) is taken, and noted; so is a lone
source file with any name (``lab7.py``) when one module is looked for, unless it
is named after another lab's module (as the batch does). A lab handed in more than
once (a notebook beside the skeleton ``.py``, two notebooks, the module in two
folders, a copy) is graded from the file that implements it, and every other file is
named with the reason (:attr:`Submission.not_graded`, :mod:`autograder.loading.handed_in`);
a module that is
missing, ambiguous or unreadable becomes a *problem* of that module only
(:attr:`Submission.problems`), naming the files found and the rename to make.
An archive handed in as the whole submission that cannot be read (not a zip,
too many members) is every module's problem: the submission is graded 0 with
the reason, as a folder without the modules is.
"""

from __future__ import annotations

import difflib
import hashlib
import os
import re
import shutil
import stat
import struct
import tempfile
import time
import zipfile
import zlib
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Collection

from ..sandbox.files import (CAPS, SKIPPED_FOLDERS, SOURCE_SUFFIXES, Caps, Refused, check_name, copy_regular_files,
                             display_name, limit_for, mib, read_one, read_regular_files, write_file)
from .handed_in import Candidate, NotGraded, Progress, choose, progress
from .notebooks import ConvertedNotebook, NotebookError, convert


class SubmissionError(ValueError):
    """The submission path does not exist or cannot be read as a submission."""


MAX_ARCHIVE_BYTES = CAPS.total_bytes


@dataclass
class Submission:
    """A submission materialised as a folder of modules.

    Attributes
    ----------
    path : Path
        A temporary folder holding the ``<module>.py`` files (converted from
        notebooks where needed); :meth:`cleanup` removes it.
    name : str
        What to call it in reports (the folder or file name).
    content_hash : str
        SHA-256 over the module files' names and bytes.
    refused : dict
        Files that were not read, by path inside the submission, with the reason.
    problems, notebooks, renamed : dict
        Per module: why it cannot be graded (not found, unreadable notebook...),
        the notebook it came from, and the file accepted under another name.
    not_graded : dict
        Per module handed in more than once: the files not graded, each with the file
        graded instead and why (:class:`~autograder.loading.handed_in.NotGraded`).
    """

    path: Path
    name: str
    content_hash: str
    refused: dict[str, str] = field(default_factory=dict)
    problems: dict[str, str] = field(default_factory=dict)
    notebooks: dict[str, tuple[str, ConvertedNotebook]] = field(default_factory=dict)
    renamed: dict[str, str] = field(default_factory=dict)
    not_graded: dict[str, list[NotGraded]] = field(default_factory=dict)

    def cleanup(self):
        shutil.rmtree(self.path, ignore_errors=True)

    def refusal_for(self, module: str) -> str:
        """Why ``module`` (``.py`` or ``.ipynb``) was refused, or ``""``."""
        for name, reason in self.refused.items():
            if PurePosixPath(name).stem == module:
                return f"{name} was not read: {reason}"
        return ""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.cleanup()


def load_submission(path, modules: list[str], caps: Caps = CAPS,
                    every_module: Collection[str] = ()) -> Submission:
    """Materialise the submission at ``path`` as a folder holding ``modules``.

    Parameters
    ----------
    path : str or Path
        Folder, ``.py`` file, ``.zip`` archive or ``.ipynb`` notebook.
    modules : list of str
        Module names the grader looks for (``lab07_transformations`` ...).
    caps : Caps
        Limits on what is read.
    every_module : collection of str
        Every lab's module name: a lone file named after one of them is that module,
        never taken for another (see :func:`_lone_file`).

    Raises
    ------
    SubmissionError
        For a path that does not exist or is no folder, ``.py``, ``.zip`` or
        ``.ipynb``. What is handed in but cannot be read, a broken archive included,
        is a module's problem instead (a grade of 0 with the reason).
    """
    source = Path(path)
    if not source.exists():
        raise SubmissionError(f"submission not found: {source}")
    out = Path(tempfile.mkdtemp(prefix="submission-"))
    refused: dict[str, str] = {}
    unreadable = ""  # why the archive that is the whole submission cannot be read
    try:
        root = out / "_read"
        root.mkdir()
        if source.is_dir():
            copy_regular_files(source, root, refused, caps, SOURCE_SUFFIXES + (".zip",))
            _keep_times(source, root)  # "the newer file" is the student's, not the copy's
        elif source.suffix == ".zip":
            try:
                unzip_regular_files(source, root, refused, caps)
            except SubmissionError as exc:
                unreadable = str(exc)
        elif source.suffix in SOURCE_SUFFIXES:
            data = read_one(source, source.name, refused, caps, [0])
            if data is not None:
                write_file(root / display_name(source.name), data)
        else:
            raise SubmissionError(f"cannot grade {display_name(source.name)}: "
                                  "expected a folder, .py, .zip or .ipynb")
        named = source.name if source.name not in ("", ".", "..") else source.resolve().name  # "." is its folder
        submission = Submission(out, display_name(named), "", refused)
        lone = _lone_file(root, set(modules) | set(every_module))
        for module in modules:
            if unreadable:
                submission.problems[module] = (f"{unreadable}, so {module}.py could not be read from it: "
                                               f"zip your files again, or hand in {module}.py itself")
                continue
            found, converted = _chosen(root, module, out, submission)
            if found is None and lone is not None and len(modules) == 1:
                found = lone
                submission.renamed[module] = _shown(lone, root, out)
            found = found or _find_misnamed(root, module, out, submission, caps)
            if found is None:
                if lone is not None:
                    submission.problems[module] += ("; a single file is graded as a lab's module "
                                                    "when only that lab is selected")
                continue
            _materialise_module(found, module, out, submission, converted)
            # Helper modules the student keeps beside the lab module come along.
            for helper in found.parent.glob("*.py"):
                if helper.stem.isidentifier() and helper.stem not in modules \
                        and helper != found and not (out / helper.name).exists():
                    shutil.copyfile(helper, out / helper.name)
        for folder in (root, out / "_zips"):
            shutil.rmtree(folder, ignore_errors=True)
    except BaseException:
        shutil.rmtree(out, ignore_errors=True)
        raise
    submission.content_hash = _hash_folder(out)
    return submission


def unzip_regular_files(archive: Path, target: Path, refused: dict | None = None,
                        caps: Caps = CAPS, suffixes=SOURCE_SUFFIXES) -> dict[str, str]:
    """Extract the regular ``suffixes`` members of a zip archive into ``target``, streaming.

    The member count is read from the archive's end record before the directory
    is parsed; encrypted members, links, names outside the archive and members
    that inflate beyond what they declare or beyond the caps are refused.
    """
    refused = {} if refused is None else refused
    name = display_name(Path(archive).name)
    count = _zip_member_count(archive)
    if count is None or count > caps.entries:
        raise SubmissionError(f"{name} holds more than {caps.entries} files" if count
                              else f"{name} is not a valid zip archive")
    try:
        with zipfile.ZipFile(archive) as zf:
            members = zf.infolist()
            if len(members) > caps.entries:
                raise SubmissionError(f"{name} holds more than {caps.entries} files")
            total = 0
            for info in members:
                relative = info.filename.replace("\\", "/")
                parts = PurePosixPath(relative).parts
                if info.is_dir() or not relative.endswith(suffixes) or any(
                        (p.startswith(".") and p != "..") or p in SKIPPED_FOLDERS for p in parts):
                    continue
                try:
                    check_name(relative, caps)
                    total += _extract_member(zf, info, target / relative, caps, total)
                except Refused as exc:
                    refused[display_name(relative)] = str(exc)
    except (zipfile.BadZipFile, OSError, UnicodeDecodeError, ValueError, EOFError) as exc:
        if isinstance(exc, SubmissionError):
            raise
        raise SubmissionError(f"{name} is not a valid zip archive ({type(exc).__name__})") from None
    return refused


def _extract_member(zf: zipfile.ZipFile, info: zipfile.ZipInfo, dest: Path, caps: Caps,
                    total: int) -> int:
    mode = info.external_attr >> 16
    if stat.S_ISLNK(mode):
        raise Refused("it is a symbolic link")
    if mode and stat.S_IFMT(mode) and not stat.S_ISREG(mode):
        raise Refused("it is not a regular file")
    if info.flag_bits & 0x1:
        raise Refused("it is encrypted; zip it without a password")
    limit = min(limit_for(info.filename, caps), caps.total_bytes - total)
    if info.file_size > limit:
        raise Refused(f"it unpacks to more than {mib(limit)}")
    dest.parent.mkdir(parents=True, exist_ok=True)
    written = 0
    try:
        with zf.open(info) as member, open(dest, "wb") as out:
            while True:
                chunk = member.read(1 << 16)  # bounded memory, whatever the compression ratio
                if not chunk:
                    break
                written += len(chunk)
                if written > info.file_size or written > limit:
                    raise Refused("it unpacks to more than it declares")
                out.write(chunk)
        try:  # the member's own date: "the newer file" when a lab is handed in twice
            stamp = time.mktime(info.date_time + (0, 0, -1))
            os.utime(dest, (stamp, stamp))
        except (OverflowError, ValueError, OSError):
            pass
    except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError, RuntimeError, OSError) as exc:
        dest.unlink(missing_ok=True)
        raise Refused(f"it cannot be unpacked ({type(exc).__name__})") from None
    except Refused:
        dest.unlink(missing_ok=True)
        raise
    return written


_END_RECORD = struct.Struct("<4s4H2LH")


def _zip_member_count(archive: Path) -> int | None:
    """How many members the archive's end record declares (None if it has none)."""
    try:
        with open(archive, "rb") as f:
            return declared_members(f)
    except OSError:
        return None


def declared_members(handle) -> int | None:
    """How many members a zip's end record declares, read from the open file ``handle``
    (rewound after), before anything parses the archive's directory; None without one."""
    try:
        handle.seek(0, os.SEEK_END)
        size = handle.tell()
        handle.seek(max(0, size - (_END_RECORD.size + 65535)))
        tail = handle.read()
        handle.seek(0)
    except OSError:
        return None
    at = tail.rfind(b"PK\x05\x06")
    if at < 0 or len(tail) - at < _END_RECORD.size:
        return None
    total = _END_RECORD.unpack_from(tail, at)[4]
    return 2**31 if total == 0xFFFF else total  # ZIP64: more than we would ever read


# ------------------------------------------------------------------ finding modules
def _find_module(root: Path, module: str) -> Path | None:
    """``module.py`` (or ``.ipynb``) at the top of ``root``, else the shallowest one below."""
    for suffix in SOURCE_SUFFIXES:
        candidates = [p for p in root.rglob(module + suffix)
                      if "__MACOSX" not in p.parts and not any(part.startswith(".") for part in p.relative_to(root).parts)
                      and len(p.relative_to(root).parts) <= 3]
        if candidates:
            return min(candidates, key=lambda p: (len(p.parts), str(p)))
    return None


def _handed_in(root: Path, module: str) -> list[Path]:
    """Every file of ``root`` handed in as ``module``: named exactly (``.py`` or ``.ipynb``,
    at most three levels down, as :func:`_find_module` searches) or under a name plainly
    meant (``Lab07_Transformations (1).ipynb``, :func:`plain_name`)."""
    exact = [p for suffix in SOURCE_SUFFIXES for p in root.rglob(module + suffix)
             if "__MACOSX" not in p.parts and not any(part.startswith(".") for part in p.relative_to(root).parts)
             and len(p.relative_to(root).parts) <= 3]
    meant = [p for p in _source_files(root) if plain_name(p.stem) == module and p not in exact]
    return exact + meant


def _chosen(root: Path, module: str, out: Path, submission: Submission
            ) -> tuple[Path | None, ConvertedNotebook | None]:
    """The file to grade as ``module`` (its notebook converted, when it is one): the one
    found by name when it is alone, else the one that implements the lab
    (:func:`autograder.loading.handed_in.choose`), the others recorded in
    :attr:`Submission.not_graded`. ``(None, None)`` when no file is named as ``module``."""
    files = _handed_in(root, module)
    if len(files) < 2:
        return _find_module(root, module), None
    candidates, converted = [], {}
    for path in files:
        read = _progress(path)
        if isinstance(read, tuple):
            read, converted[path] = read
        candidates.append(Candidate(path, _shown(path, root, out), read, path.stat().st_mtime))
    best, others = choose(module, candidates)
    submission.not_graded[module] = others
    if best.path.stem != module:
        submission.renamed[module] = best.shown
    return best.path, converted.get(best.path)


def _progress(path: Path) -> Progress | tuple[Progress, ConvertedNotebook]:
    """How much of its lab ``path`` implements (a notebook: with its conversion, to reuse)."""
    try:
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError:
        return Progress(0, 0, "is not UTF-8 text")
    except OSError as exc:
        return Progress(0, 0, f"cannot be read ({exc.strerror})")
    if path.suffix.lower() != ".ipynb":
        return progress(text)
    try:
        converted = convert(text, path.name)
    except NotebookError as exc:
        return Progress(0, 0, f"cannot be read as a notebook ({exc})")
    return progress(converted.source), converted


def _keep_times(source: Path, copy: Path) -> None:
    """Give the files copied from ``source`` into ``copy`` their modification times."""
    for file in copy.rglob("*"):
        try:
            original = os.lstat(source / file.relative_to(copy))
            os.utime(file, ns=(original.st_atime_ns, original.st_mtime_ns))
        except (OSError, ValueError):
            continue


def _lone_file(root: Path, modules: set[str]) -> Path | None:
    """The submission's one source file, when it holds exactly one (no archive beside it)
    and its name is not meant as any of ``modules`` (``lab7.py``, ``my_work.ipynb``)."""
    files = _source_files(root, suffixes=(".py", ".ipynb", ".zip"))
    if len(files) != 1 or files[0].suffix.lower() == ".zip" or plain_name(files[0].stem) in modules:
        return None
    return files[0]


def _materialise_module(found: Path, module: str, out: Path, submission: Submission,
                        converted: ConvertedNotebook | None = None):
    """``out/<module>.py`` from the file found (``converted``: the notebook already read);
    a notebook that cannot be read becomes a problem of that module only, so the other
    modules are still graded."""
    target = out / f"{module}.py"
    if found.suffix.lower() == ".py":
        shutil.copyfile(found, target)
        return
    try:
        converted = converted or convert(found.read_bytes().decode("utf-8"), found.name)
    except (NotebookError, UnicodeDecodeError) as exc:
        submission.problems[module] = (str(exc) if isinstance(exc, NotebookError)
                                       else f"{found.name} is not a readable notebook (not UTF-8 text)")
        return
    target.write_text(converted.guarded_source, encoding="utf-8")  # a failing value is skipped, as in Jupyter
    submission.notebooks[module] = (found.name, converted)


def notebook_to_source(text: str) -> str:
    """The graded part of a notebook as one module (see :mod:`autograder.loading.notebooks`)."""
    try:
        return convert(text).source
    except NotebookError as exc:
        raise SubmissionError(str(exc)) from None


# ------------------------------------------------------------------ misnamed files
_COPY_SUFFIX = re.compile(r"(\s*\(\d+\)|[\s_-]*copy(\s*\d+)?|[\s_-]+\d+)$", re.IGNORECASE)


def plain_name(stem: str) -> str:
    """``Lab07_Transformations (1)`` -> ``lab07_transformations``: how a name was meant."""
    return re.sub(r"[\s-]+", "_", _COPY_SUFFIX.sub("", stem.strip())).lower()


def _source_files(root: Path, depth: int = 3, suffixes=(".py", ".ipynb")) -> list[Path]:
    """The .py and .ipynb files of a submission, as _find_module would search them (at most
    ``depth`` levels down, hidden folders and __MACOSX left out, never a whole tree)."""
    found = []
    for folder, subfolders, files in os.walk(root):
        level = len(Path(folder).relative_to(root).parts)
        subfolders[:] = [] if level + 1 >= depth else sorted(
            d for d in subfolders if not d.startswith(".") and d != "__MACOSX")
        found += [Path(folder) / f for f in files
                  if Path(f).suffix.lower() in suffixes and not f.startswith(".")]
    return sorted(found)


def _find_misnamed(root: Path, module: str, out: Path, submission: Submission,
                   caps: Caps = CAPS) -> Path | None:
    """The module under a name that was plainly meant (another case, `` (1)``, ``-copy``),
    also inside a .zip handed in within the folder; else None, with the problem recorded:
    what was found, and the rename to make when one name is close."""
    files = _source_files(root)
    archives = _source_files(root, suffixes=(".zip",))
    broken = []
    for index, archive in enumerate(archives):
        unpacked, why_not = out / "_zips" / str(index), out / "_zips" / f"{index}.broken"
        if not unpacked.exists():  # else unpacked (or found broken) for an earlier module
            unpacked.mkdir(parents=True)
            try:
                unzip_regular_files(archive, unpacked, submission.refused, caps)
            except SubmissionError as exc:
                why_not.write_text(str(exc), encoding="utf-8")
        if why_not.exists():
            broken.append(why_not.read_text(encoding="utf-8"))
            continue
        files += [p for p in _source_files(out / "_zips" / str(index)) if p not in files]
    meant = [p for p in files if plain_name(p.stem) == module]
    for suffix in (".py", ".ipynb"):
        matches = [p for p in meant if p.suffix.lower() == suffix]
        if len(matches) == 1:
            submission.renamed[module] = _shown(matches[0], root, out)
            return matches[0]
        if len(matches) > 1:
            names = ", ".join(_shown(p, root, out) for p in matches)
            submission.problems[module] = (f"module {module}.py not found, but several files look "
                                           f"meant to be it: {names}; keep one and name it {module}{suffix}")
            return None
    problem = f"module {module}.py not found"
    if broken:
        problem += "; " + "; ".join(broken)
    python_files = [p for p in files if p.suffix.lower() in (".py", ".ipynb")]
    if python_files:
        shown = [_shown(p, root, out) for p in python_files]
        problem += f" (found: {', '.join(shown[:12])}{', ...' if len(shown) > 12 else ''})"
        close = difflib.get_close_matches(module, [plain_name(p.stem) for p in python_files], n=1, cutoff=0.75)
        if close:
            [near] = [p for p in python_files if plain_name(p.stem) == close[0]][:1]
            problem += f"; if {near.name} is this lab, rename it {module}{near.suffix.lower()}"
    submission.problems[module] = problem
    return None


def _shown(path: Path, root: Path, out: Path) -> str:
    for base in (root, out / "_zips"):
        try:
            relative = path.relative_to(base)
            return relative.as_posix() if base == root else "/".join(relative.parts[1:])
        except ValueError:
            continue
    return path.name


def _hash_folder(folder: Path) -> str:
    digest = hashlib.sha256()
    for file in sorted(folder.glob("*.py")):
        digest.update(file.name.encode() + b"\0" + file.read_bytes() + b"\0")
    return digest.hexdigest()
