"""Finding the lab modules in what a student handed in.

A submission may be a folder (the modules at its top or one level down, as
unzipped archives often are), a single ``.py`` file, a ``.zip`` archive, or
Jupyter notebooks named like the modules (``lab07_transformations.ipynb``, whose
code cells become the module). The result is a plain folder of ``.py`` modules
that the sandbox copies, plus a content hash identifying the submission.
"""

from __future__ import annotations

import hashlib
import json
import shutil
import tempfile
import zipfile
from dataclasses import dataclass
from pathlib import Path

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
        for module in modules:
            found = _find_module(root, module)
            if found is not None:
                _materialise(found, out / f"{module}.py")
                # Helper modules the student keeps beside the lab module come along.
                for helper in found.parent.glob("*.py"):
                    if not (out / helper.name).exists() and helper.stem not in modules:
                        shutil.copy(helper, out / helper.name)
        if root.parent == out:
            shutil.rmtree(root, ignore_errors=True)
    except BaseException:
        shutil.rmtree(out, ignore_errors=True)
        raise
    return Submission(out, source.name, _hash_folder(out))


def _find_module(root: Path, module: str) -> Path | None:
    """``module.py`` (or ``.ipynb``) at the top of ``root``, else the shallowest one below."""
    for suffix in (".py", ".ipynb"):
        candidates = [p for p in root.rglob(module + suffix)
                      if "__MACOSX" not in p.parts and not any(part.startswith(".") for part in p.relative_to(root).parts)
                      and len(p.relative_to(root).parts) <= 3]
        if candidates:
            return min(candidates, key=lambda p: (len(p.parts), str(p)))
    return None


def _materialise(found: Path, target: Path):
    if found.suffix == ".py":
        shutil.copy(found, target)
    else:
        target.write_text(notebook_to_source(found.read_text(encoding="utf-8")), encoding="utf-8")


def notebook_to_source(text: str) -> str:
    """The code cells of a notebook as one module; IPython magics are commented out."""
    try:
        notebook = json.loads(text)
        cells = notebook["cells"]
    except (ValueError, KeyError, TypeError) as exc:
        raise SubmissionError(f"not a readable notebook: {exc}") from None
    chunks = []
    for number, cell in enumerate(cells, 1):
        if cell.get("cell_type") != "code":
            continue
        source = cell.get("source", "")
        source = "".join(source) if isinstance(source, list) else str(source)
        lines = [("# " + line) if line.lstrip().startswith(("%", "!")) else line
                 for line in source.splitlines()]
        chunks.append(f"# --- notebook cell {number}\n" + "\n".join(lines))
    return "\n\n".join(chunks) + "\n"


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
