"""The repository students receive: skeletons, ``grade.py``, public checks and fixtures,
the contract (``docs/contract/``, ``docs/api/``) and the student guide (``docs/students/``).

Left out: ``reference_solutions/``, the hidden checks (``autograder/labs/hidden/``),
the mistakes tables (``autograder/labs/mistakes/``), the grader's own tests, and the
scripts that measure the reference solutions.

With a course (``autograder bundle --course``), each of its lab folders ships too, as
``course_labs/<lab key>/`` (which the grader loads unasked), without the parts that
give answers away (``reference/``, ``hidden.py``, ``mistakes.py``); its skeleton goes to
``assignments/`` beside the built-in ones.

:func:`write_wheelhouse` adds ``wheels/``: every package the grader needs, for the
Python and platform that made it, so the bundle installs with no network
(``pip install --no-index --find-links wheels -c constraints.txt -e .``).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from ..engine.labfolders import ANSWERS, BUNDLED, SELECTION, SKELETON
from ..engine.versions import DEFAULT_OPENCV, constraints_file

PROJECT_ROOT = Path(__file__).resolve().parents[2]
STUDENT_README = Path(__file__).resolve().parent / "templates" / "README_student.md"
# The documentation students get: the contract (what each lab asks, the assignment API
# generated from the skeletons and the registry: public checks only) and the student guide.
# Their links stay among these folders (tests/test_bundle.py).
STUDENT_DOCS = ("students", "contract", "api")
COURSE_LABS = BUNDLED.name   # course_labs/, beside the package: the grader loads the labs in it unasked


def _public(path: Path, root: Path) -> bool:
    parts = path.relative_to(root).parts
    if "__pycache__" in parts or path.suffix == ".pyc":
        return False
    if parts[:3] in (("autograder", "labs", "hidden"), ("autograder", "labs", "mistakes")):
        return False
    return not (parts[0] == "fixtures" and path.name.startswith("make_"))


def write_student_bundle(out, root: Path = PROJECT_ROOT, course=None) -> list[Path]:
    """Write the student repository into the folder ``out`` (which must not exist yet), with
    the labs of ``course`` (a :class:`~autograder.instructor.course.CourseConfig`) if given.

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
    if course is not None and course.select:   # (what `python grade.py` grades when nothing is named)
        target = out / COURSE_LABS / SELECTION
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(json.dumps(list(course.select)) + "\n", encoding="utf-8")
        written.append(target.relative_to(out))
    for lab_folder in course_lab_folders(course):
        skeleton = lab_folder.part(SKELETON) / f"{lab_folder.lab.module}.py"
        copy(skeleton, out / "assignments" / skeleton.name)
        for path in shipped_lab_files(lab_folder.folder, leave_out=ANSWERS + (SKELETON,)):
            copy(path, out / COURSE_LABS / lab_folder.lab.key / path.relative_to(lab_folder.folder))
    for folder in STUDENT_DOCS:
        for path in sorted((root / "docs" / folder).glob("*.md")):
            copy(path, out / "docs" / folder / path.name)
    for name in ("grade.py", "pyproject.toml", ".gitignore"):
        if (root / name).exists():
            copy(root / name, out / name)
    # The pins of the course's OpenCV major ("opencv", default 5), as the bundle's constraints.txt.
    pins = constraints_file(course.opencv if course is not None else DEFAULT_OPENCV, root)
    if pins.exists():
        copy(pins, out / "constraints.txt")
    copy(STUDENT_README, out / "README.md")
    return written


def course_lab_folders(course) -> list:
    """The loaded lab folders of ``course`` (none without one), in its order."""
    if course is None or not course.labs:
        return []
    from ..engine.labfolders import use_lab_folders, lab_folder

    return [lab_folder(lab) for lab in use_lab_folders(course.labs)]


def shipped_lab_files(folder: Path, leave_out) -> list[Path]:
    """The files of a course lab folder except the parts ``leave_out`` names (top-level
    files or folders) and their copies an editor leaves (``hidden.py~``, ``mistakes.py.bak``,
    ``.hidden.py.swp``: any dot-file or dot-folder, any name ending in ``~``), and Python's caches."""
    def left_out(path: Path) -> bool:
        parts = path.relative_to(folder).parts
        return (any(parts[0] == part or parts[0].startswith(part + ".") for part in leave_out)
                or any(p.startswith(".") or p.endswith("~") or p == "__pycache__" for p in parts)
                or path.suffix == ".pyc")

    return [path for path in sorted(folder.rglob("*")) if path.is_file() and not left_out(path)]


# ------------------------------------------------------------------ the wheelhouse
WHEELS = "wheels"
OFFLINE_README = """
## Set up without a network

`wheels/` holds every package the grader needs, built for {python} on {platform}
(the machine that made this folder). On such a machine, this installs with no
network at all:

```bash
{venv} -m venv .venv && . .venv/bin/activate && python -m pip install --no-index --find-links wheels -c constraints.txt -e . && python grade.py
```

On another Python version or system, use the command above, which needs a network.

"""


class WheelhouseError(RuntimeError):
    """The wheels could not be downloaded (no network, a package without a wheel here)."""


def bundle_requirements(out: Path) -> list[str]:
    """What an install of the bundle in ``out`` fetches: its build backend (pyproject's
    ``build-system.requires``) and its dependencies (``project.dependencies``; extras not)."""
    try:
        import tomllib
    except ImportError:  # Python 3.10: tomli comes with pytest
        import tomli as tomllib

    project = tomllib.loads((Path(out) / "pyproject.toml").read_text(encoding="utf-8"))
    return list(project["build-system"]["requires"]) + list(project["project"].get("dependencies", []))


def write_wheelhouse(out, python: str = sys.executable, timeout: float = 1800) -> list[Path]:
    """Download into ``out/wheels`` the wheels of :func:`bundle_requirements` and of all they
    need, at ``out/constraints.txt``'s versions, for ``python``'s version and platform
    (``pip download --only-binary :all:``, with pip's own configuration: indexes, proxies);
    then say in ``out/README.md`` how to install from them offline.

    Returns the wheels, relative to ``out``. Raises WheelhouseError, leaving no
    ``wheels/`` and the README as it was, when pip cannot get them all.
    """
    out = Path(out)
    partial, target = out / f".{WHEELS}.partial", out / WHEELS
    if target.exists():
        raise WheelhouseError(f"{target} exists already")
    shutil.rmtree(partial, ignore_errors=True)
    command = [python, "-m", "pip", "download", "--disable-pip-version-check", "--only-binary", ":all:",
               "--dest", str(partial), "-c", str(out / "constraints.txt"), *bundle_requirements(out)]
    try:
        run = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        shutil.rmtree(partial, ignore_errors=True)
        raise WheelhouseError(f"pip download did not finish within {timeout:g} s") from None
    if run.returncode != 0:
        shutil.rmtree(partial, ignore_errors=True)
        said = [line.strip() for line in run.stderr.splitlines() if line.strip()]
        errors = [line for line in said if line.startswith("ERROR")] or said[-2:]
        raise WheelhouseError("pip download failed: " + " ".join(errors[-2:])[:600])
    partial.rename(target)
    readme = out / "README.md"
    readme.write_text(_with_offline_section(readme.read_text(encoding="utf-8"), python), encoding="utf-8")
    return sorted(path.relative_to(out) for path in target.glob("*.whl"))


def _with_offline_section(readme: str, python: str) -> str:
    """The student README with :data:`OFFLINE_README` (naming ``python``'s version and
    platform) before its "## Grading", or at its end when it has none."""
    implementation, number, platform = subprocess.run(
        [python, "-c", "import sys, sysconfig; print(sys.implementation.name, '%d.%d' % sys.version_info[:2], "
                       "sysconfig.get_platform())"], capture_output=True, text=True, check=True).stdout.split()
    name = "CPython" if implementation == "cpython" else implementation
    section = OFFLINE_README.format(python=f"{name} {number}", platform=platform, venv=f"python{number}")
    at = readme.find("\n## Grading")
    if at < 0:
        return readme.rstrip("\n") + "\n" + section
    return readme[:at + 1] + section.lstrip("\n") + readme[at + 1:]
