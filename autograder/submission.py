"""Finding the lab modules in what a student handed in.

A submission may be a folder (the modules at its top or one level down, as
unzipped archives often are), a single ``.py`` file, a ``.zip`` archive, or
Jupyter notebooks named like the modules (``lab07_transformations.ipynb``, whose
definitions become the module, see :mod:`autograder.notebooks`). The result is a
plain folder of ``.py`` modules that the sandbox copies, plus a content hash
identifying the submission.

Nothing the student handed in stops the others from being graded: a file
plainly meant as a module (``Lab07_Transformations.py``, ``lab07_transformations (1).py``,
or one inside a ``.zip`` within the folder) is taken, and noted; a module that is
missing, ambiguous or unreadable becomes a *problem* of that module only
(:attr:`Submission.problems`), naming the files found and the rename to make.
"""

from __future__ import annotations

import difflib
import hashlib
import os
import re
import shutil
import tempfile
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

from .notebooks import ConvertedNotebook, NotebookError, convert

MAX_ARCHIVE_BYTES = 50 * 2**20


class SubmissionError(ValueError):
    """The submission path does not exist or cannot be read as a submission."""


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
    """

    path: Path
    name: str
    content_hash: str
    # Per module: why it cannot be graded (not found, unreadable notebook...), the
    # notebooks it came from, and the files accepted under another name.
    problems: dict[str, str] = field(default_factory=dict)
    notebooks: dict[str, tuple[str, ConvertedNotebook]] = field(default_factory=dict)
    renamed: dict[str, str] = field(default_factory=dict)

    def cleanup(self):
        shutil.rmtree(self.path, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.cleanup()


def load_submission(path, modules: list[str]) -> Submission:
    """Materialise the submission at ``path`` as a folder holding ``modules``.

    Parameters
    ----------
    path : str or Path
        Folder, ``.py`` file, ``.zip`` archive or ``.ipynb`` notebook.
    modules : list of str
        Module names the grader looks for (``lab07_transformations`` ...).
    """
    source = Path(path)
    if not source.exists():
        raise SubmissionError(f"submission not found: {source}")
    out = Path(tempfile.mkdtemp(prefix="submission-"))
    try:
        if source.is_dir():
            root = source
        elif source.suffix == ".zip":
            root = out / "_unzipped"
            _safe_unzip(source, root)
        elif source.suffix in (".py", ".ipynb"):
            root = out / "_single"
            root.mkdir()
            shutil.copy(source, root / source.name)
        else:
            raise SubmissionError(f"cannot grade {source.name}: expected a folder, .py, .zip or .ipynb")
        submission = Submission(out, source.name, "")
        for module in modules:
            found = _find_module(root, module) or _find_misnamed(root, module, out, submission)
            if found is not None:
                _materialise_module(found, module, out, submission)
                # Helper modules the student keeps beside the lab module come along.
                for helper in found.parent.glob("*.py"):
                    if not (out / helper.name).exists() and helper.stem not in modules \
                            and helper != found:
                        shutil.copy(helper, out / helper.name)
        for folder in (root, out / "_zips"):
            if folder.parent == out:
                shutil.rmtree(folder, ignore_errors=True)
    except BaseException:
        shutil.rmtree(out, ignore_errors=True)
        raise
    submission.content_hash = _hash_folder(out)
    return submission


def _find_module(root: Path, module: str) -> Path | None:
    """``module.py`` (or ``.ipynb``) at the top of ``root``, else the shallowest one below."""
    for suffix in (".py", ".ipynb"):
        candidates = [p for p in root.rglob(module + suffix)
                      if "__MACOSX" not in p.parts and not any(part.startswith(".") for part in p.relative_to(root).parts)
                      and len(p.relative_to(root).parts) <= 3]
        if candidates:
            return min(candidates, key=lambda p: (len(p.parts), str(p)))
    return None


def _materialise_module(found: Path, module: str, out: Path, submission: Submission):
    """``out/<module>.py`` from the file found; a notebook that cannot be read becomes a
    problem of that module only, so the other modules are still graded."""
    target = out / f"{module}.py"
    if found.suffix == ".py":
        shutil.copy(found, target)
        return
    try:
        converted = convert(found.read_bytes().decode("utf-8"), found.name)
    except (NotebookError, UnicodeDecodeError) as exc:
        submission.problems[module] = (str(exc) if isinstance(exc, NotebookError)
                                       else f"{found.name} is not a readable notebook (not UTF-8 text)")
        return
    target.write_text(converted.source, encoding="utf-8")
    submission.notebooks[module] = (found.name, converted)


def notebook_to_source(text: str) -> str:
    """The graded part of a notebook as one module (see :mod:`autograder.notebooks`)."""
    try:
        return convert(text).source
    except NotebookError as exc:
        raise SubmissionError(str(exc)) from None


# ------------------------------------------------------------------ misnamed files
_COPY_SUFFIX = re.compile(r"(\s*\(\d+\)|[\s_-]*copy(\s*\d+)?|[\s_-]+\d+)$", re.IGNORECASE)


def _plain_name(stem: str) -> str:
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


def _find_misnamed(root: Path, module: str, out: Path, submission: Submission) -> Path | None:
    """The module under a name that was plainly meant (another case, `` (1)``, ``-copy``),
    also inside a .zip handed in within the folder; else None, with the problem recorded:
    what was found, and the rename to make when one name is close."""
    files = _source_files(root)
    archives = _source_files(root, suffixes=(".zip",))
    broken = []
    for index, archive in enumerate(archives):
        try:
            _safe_unzip(archive, out / "_zips" / str(index))
        except FileExistsError:
            pass  # unpacked for an earlier module
        except SubmissionError as exc:
            broken.append(str(exc))
            continue
        files += [p for p in _source_files(out / "_zips" / str(index)) if p not in files]
    meant = [p for p in files if _plain_name(p.stem) == module]
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
        close = difflib.get_close_matches(module, [_plain_name(p.stem) for p in python_files], n=1, cutoff=0.75)
        if close:
            [near] = [p for p in python_files if _plain_name(p.stem) == close[0]][:1]
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


def _safe_unzip(archive: Path, target: Path):
    try:
        with zipfile.ZipFile(archive) as zf:
            total = sum(info.file_size for info in zf.infolist())
            if total > MAX_ARCHIVE_BYTES:
                raise SubmissionError(f"{archive.name} unpacks to more than {MAX_ARCHIVE_BYTES // 2**20} MB")
            target.mkdir(parents=True)
            for info in zf.infolist():
                name = Path(info.filename)
                if name.is_absolute() or ".." in name.parts:
                    continue  # no path traversal out of the target
                if info.is_dir() or name.suffix not in (".py", ".ipynb"):
                    continue
                dest = target / name
                dest.parent.mkdir(parents=True, exist_ok=True)
                dest.write_bytes(zf.read(info))
    except zipfile.BadZipFile:
        raise SubmissionError(f"{archive.name} is not a valid zip archive") from None


def _hash_folder(folder: Path) -> str:
    digest = hashlib.sha256()
    for file in sorted(folder.glob("*.py")):
        digest.update(file.name.encode() + b"\0" + file.read_bytes() + b"\0")
    return digest.hexdigest()
