"""Course labs: labs written like the built-in ones, kept in folders outside the package.

A course names its lab folders in its configuration (``"labs": ["labs/flow"]``,
relative to the configuration file). A folder holds::

    FOLDER/
        suite.py          the public checks: lab = Lab("lab13", module="lab13_flow", ...)
        hidden.py         hidden checks (optional): from .suite import ex1 ... hidden=True
        reference/        the reference solution: reference/lab13_flow.py
        skeleton/         what students fill in: skeleton/lab13_flow.py
        mistakes.py       the mistakes table: MISTAKES (ADVICE, FEWER_MISTAKES optional)
        *.py, data/ ...   helpers and fixtures, imported relatively (from .truth import ...)

Only ``suite.py`` is needed to grade; ``autograder verify`` reads the reference, the
skeleton and the mistakes table, and ``autograder bundle`` the skeleton. The folder is
imported as a package of its own (no ``__init__.py`` needed), so ``suite.py`` reaches
its helpers with relative imports and two courses' helpers never meet. Its checks run
in the grader's process, like the built-in ones; the student's code runs in the sandbox.

:func:`use_lab_folders` makes a list of folders the course's labs (loading each once,
forgetting those of another course); a copy of the grader with a ``course_labs/``
folder beside its package (the student bundle, the Gradescope zip) loads every lab
folder in it from :func:`~autograder.engine.registry.discover`, unasked.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import json
import sys
import traceback
from dataclasses import dataclass
from pathlib import Path

from .registry import REGISTRY, Lab, LabKeyTaken

SUITE, HIDDEN, MISTAKES = "suite.py", "hidden.py", "mistakes.py"
REFERENCE, SKELETON = "reference", "skeleton"
# The parts students never receive: they give answers away (bundle) or are not needed to grade (zip).
ANSWERS = (REFERENCE, HIDDEN, MISTAKES)
# A copy of the grader holding course labs beside its package loads them unasked.
BUNDLED = Path(__file__).resolve().parents[2] / "course_labs"
SELECTION = "selection.json"   # in BUNDLED: what the bundle's course grades by default


class LabFolderError(ValueError):
    """A course lab folder that cannot be used: a missing part, a taken key, a suite that fails."""


@dataclass(frozen=True)
class LabFolder:
    """A loaded course lab: its folder, the package it was imported as, and its lab."""

    folder: Path
    package: str
    lab: Lab

    def part(self, name: str) -> Path:
        """``FOLDER/name``, which must exist (verify's and the bundle's parts)."""
        path = self.folder / name
        if not path.exists():
            raise LabFolderError(f"{self.folder}: {self.lab.key} has no {name}"
                                 f"{'/' + self.lab.module + '.py' if name in (REFERENCE, SKELETON) else ''} "
                                 f"(a lab folder holds {SUITE}, {HIDDEN}, {REFERENCE}/, {SKELETON}/, {MISTAKES})")
        if name in (REFERENCE, SKELETON) and not (path / f"{self.lab.module}.py").is_file():
            raise LabFolderError(f"{path}: no {self.lab.module}.py in it (the module of {self.lab.key})")
        return path


_LOADED: dict[Path, LabFolder] = {}   # resolved folder -> what it registered


def use_lab_folders(folders, *, hidden: bool = True) -> list[Lab]:
    """Make ``folders`` the course's labs, in addition to the built-in ones: each is loaded
    once (``suite.py``, then ``hidden.py`` when present and ``hidden``), and course labs
    loaded before from other folders are forgotten (the bundled ones excepted).

    Raises :class:`LabFolderError` naming the folder, file and line for a folder that is
    missing or has no ``suite.py``, a suite that fails to import, registers no lab or
    several, or a lab key taken by a built-in lab or another folder."""
    from .registry import discover

    discover()   # the built-in labs first: a course lab may not take their keys
    wanted = [Path(folder).resolve() for folder in folders]
    for folder in [f for f in _LOADED if f not in wanted and f.parent != BUNDLED]:
        _forget(folder)
    return [_load(folder, hidden).lab for folder in wanted]


def forget_lab_folders() -> None:
    """Unregister every course lab (the bundled ones too; :func:`discover` loads those again)."""
    for folder in list(_LOADED):
        _forget(folder)


def lab_folder(lab: Lab) -> LabFolder | None:
    """The course folder ``lab`` was loaded from (None for a built-in lab)."""
    return next((loaded for loaded in _LOADED.values() if loaded.lab is lab), None)


def course_lab_folders() -> list[LabFolder]:
    return list(_LOADED.values())


def bundled_selection() -> list[str]:
    """What a student bundle made for a course grades when nothing is named (``course_labs/selection.json``: the
    course's ``select``, its own labs alone for a course of its own labs); ``[]`` (everything) without one."""
    try:
        chosen = json.loads((BUNDLED / SELECTION).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return []
    return [item for item in chosen if isinstance(item, str) and item] if isinstance(chosen, list) else []


def load_bundled() -> None:
    """Load the lab folders of ``course_labs/`` beside the package, if there is one."""
    if BUNDLED.is_dir():
        for folder in sorted(BUNDLED.iterdir()):
            if (folder / SUITE).is_file():
                _load(folder.resolve(), hidden=True)


def _load(folder: Path, hidden: bool) -> LabFolder:
    if folder in _LOADED:
        return _LOADED[folder]
    if not folder.is_dir():
        raise LabFolderError(f"course lab folder {folder} does not exist")
    if not (folder / SUITE).is_file():
        raise LabFolderError(f"{folder} is not a lab folder: it has no {SUITE} (the public checks; "
                             f"`autograder new-lab NAME --into FOLDER` writes one to start from)")
    package = "autograder_course_lab_" + hashlib.sha256(str(folder).encode()).hexdigest()[:12]
    before = set(REGISTRY)
    try:
        _import_package(package, folder)
        _run(package, folder / SUITE)
        added = [REGISTRY[key] for key in REGISTRY if key not in before]
        if len(added) != 1:
            raise LabFolderError(f"{folder / SUITE} registers {len(added)} labs ("
                                 f"{', '.join(lab.key for lab in added) or 'none'}): a lab folder declares "
                                 'exactly one, lab = Lab("lab13", module="lab13_name", title="...")')
        [lab] = added
        lab.folder = folder
        loaded = _LOADED[folder] = LabFolder(folder, package, lab)
        if hidden and (folder / HIDDEN).is_file():
            _run(package, folder / HIDDEN)
    except BaseException:
        for key in set(REGISTRY) - before:
            del REGISTRY[key]
        _LOADED.pop(folder, None)
        _drop_modules(package)
        raise
    return loaded


def _import_package(package: str, folder: Path) -> None:
    spec = importlib.util.spec_from_loader(package, loader=None, is_package=True)
    module = importlib.util.module_from_spec(spec)
    module.__path__ = [str(folder)]
    module.__file__ = str(folder / "__init__.py")
    sys.modules[package] = module


def _run(package: str, path: Path) -> None:
    """Import ``path`` (suite.py or hidden.py) as a module of ``package``; any failure becomes a
    :class:`LabFolderError` naming the file and line where it happened."""
    try:
        importlib.import_module(f"{package}.{path.stem}")
    except LabFolderError:
        raise
    except SyntaxError as exc:
        raise LabFolderError(f"{exc.filename or path}, line {exc.lineno}: SyntaxError: {exc.msg}") from None
    except (Exception, SystemExit) as exc:  # noqa: BLE001 - the author's code: any error, said where (sys.exit too)
        where = _where(exc, path.parent)
        message = str(exc)
        if isinstance(exc, LabKeyTaken):
            key = exc.key
            owner = lab_folder(REGISTRY[key]) if key in REGISTRY else None
            message = (f"the lab key {key} is taken by "
                       + (f"the course lab in {owner.folder}" if owner else "a built-in lab")
                       + ": give this lab another key (lab13, lab14 ...)")
        raise LabFolderError(f"{where}: {type(exc).__name__}: {message}") from None


def _where(exc: BaseException, folder: Path) -> str:
    """``file, line N`` of the innermost frame of ``exc`` inside ``folder`` (else its file)."""
    frames = [frame for frame in traceback.extract_tb(exc.__traceback__)
              if Path(frame.filename).resolve().is_relative_to(folder)]
    if not frames:
        return str(folder / SUITE)
    return f"{frames[-1].filename}, line {frames[-1].lineno}"


def _forget(folder: Path) -> None:
    loaded = _LOADED.pop(folder)
    if REGISTRY.get(loaded.lab.key) is loaded.lab:
        del REGISTRY[loaded.lab.key]
    _drop_modules(loaded.package)


def _drop_modules(package: str) -> None:
    for name in [n for n in sys.modules if n == package or n.startswith(package + ".")]:
        del sys.modules[name]
