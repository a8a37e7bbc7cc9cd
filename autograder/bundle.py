"""The repository students receive: skeletons, ``grade.py``, public checks and fixtures,
the contract (``docs/contract/``, ``docs/api/``) and the student guide (``docs/students/``).

Left out: ``reference_solutions/``, the hidden checks (``autograder/labs/hidden/``),
the grader's own tests, and the scripts that measure the reference solutions.
"""

from __future__ import annotations

import shutil
from pathlib import Path

PROJECT_ROOT = Path(__file__).resolve().parents[1]
STUDENT_README = Path(__file__).resolve().parent / "templates" / "README_student.md"
# The documentation students get: the contract (what each lab asks, the assignment API
# generated from the skeletons and the registry: public checks only) and the student guide.
# Their links stay among these folders (tests/test_bundle.py).
STUDENT_DOCS = ("students", "contract", "api")


def _public(path: Path, root: Path) -> bool:
    parts = path.relative_to(root).parts
    if "__pycache__" in parts or path.suffix == ".pyc":
        return False
    if parts[:3] == ("autograder", "labs", "hidden"):
        return False
    return not (parts[0] == "fixtures" and path.name.startswith("make_"))


def write_student_bundle(out, root: Path = PROJECT_ROOT) -> list[Path]:
    """Write the student repository into the folder ``out`` (which must not exist yet).

    Returns the files written, relative to ``out``.
    """
    out = Path(out)
    if out.exists() and any(out.iterdir()):
        raise FileExistsError(f"{out} exists and is not empty")
    written = []

    def copy(source: Path, target: Path):
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(source, target)
        written.append(target.relative_to(out))

    for top in ("autograder", "fixtures"):
        for path in sorted((root / top).rglob("*")):
            if path.is_file() and _public(path, root):
                copy(path, out / path.relative_to(root))
    for path in sorted((root / "assignments").glob("*.py")):
        copy(path, out / "assignments" / path.name)
    for folder in STUDENT_DOCS:
        for path in sorted((root / "docs" / folder).glob("*.md")):
            copy(path, out / "docs" / folder / path.name)
    for name in ("grade.py", "pyproject.toml", "constraints.txt", ".gitignore"):
        if (root / name).exists():
            copy(root / name, out / name)
    copy(STUDENT_README, out / "README.md")
    return written
