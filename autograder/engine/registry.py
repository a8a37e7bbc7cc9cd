"""Labs, exercises and checks, and how lab suites register themselves.

The engine knows no lab. A lab suite (``autograder/labs/lab07.py``) declares::

    lab = Lab("lab07", module="lab07_transformations", title="2D transformations")
    ex1 = lab.exercise("ex1", "Translation",
                       functions=["translation_matrix(tx, ty)",
                                  "translate(image, tx=100, ty=50)"])

    @ex1.check("the lab sheet's matrix", points=2)
    def sheet_matrix(t):
        ...

Hidden checks live in ``autograder/labs/hidden/`` and add themselves to the same
exercises with ``hidden=True``; the student bundle ships without that folder.

Advice: a convention worth following that neither the lab sheet nor the API
asks for (NaN for points behind the camera, ...) is never worth points. A suite
registers it as an advice check, worth 0 points, whose body calls ``t.advise``
when the student's code does something worth a tip and returns normally
otherwise::

    @ex1.advice("NaN for points behind the camera")
    def nan_behind_camera(t):
        uv = t.call("project_points", P, X_behind)
        if np.all(np.isfinite(uv)):
            t.advise("project_points() returned finite pixels for points behind "
                     "the camera; NaN tells the caller they are not visible")

Reports show each tip with its reason; it never fails and never lowers a score.
If the student's function raises or is missing, an advice check says nothing
(the graded checks report that). The engine adds advice of its own, e.g. when a
student function modifies its input arrays in place.
Third-party suites can register through the ``autograder.labs`` entry-point group, and a
course's own labs from folders outside the package (:mod:`.labfolders`).
"""

from __future__ import annotations

import importlib
import importlib.util
import logging
import pkgutil
import re
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Callable

REGISTRY: dict[str, "Lab"] = {}


class SelectionError(ValueError):
    """A selector like ``lab07.ex9`` names nothing that exists."""


class LabKeyTaken(ValueError):
    """A lab declared with the key of a lab already registered (``key``)."""

    def __init__(self, key: str):
        super().__init__(f"lab {key} is registered twice")
        self.key = key


@dataclass
class Check:
    """One graded check: ``func(t)`` inspects the student's functions through ``t``."""

    name: str
    points: float
    func: Callable
    exercise: "Exercise"
    hidden: bool = False
    timeout: float | None = None
    advice: bool = False  # an advice check: 0 points, a tip when it has something to say

    @property
    def id(self) -> str:
        return f"{self.exercise.id}::{self.func.__name__}"


@dataclass
class Exercise:
    lab: "Lab"
    key: str
    title: str
    signatures: dict[str, str]
    checks: list[Check] = field(default_factory=list)

    @property
    def id(self) -> str:
        return f"{self.lab.key}.{self.key}"

    def check(self, name: str, points: float, *, hidden: bool = False, timeout: float | None = None):
        """Decorator registering a check worth ``points`` on this exercise."""
        if points <= 0:
            raise ValueError(f"{self.id}: check {name!r} needs positive points")
        return self._register(name, float(points), hidden, timeout, advice=False)

    def advice(self, name: str, *, hidden: bool = False, timeout: float | None = None):
        """Decorator registering an advice check (0 points) on this exercise.

        Its body calls ``t.advise(message)`` when there is a tip to give, and
        returns normally otherwise (see the module docstring).
        """
        return self._register(name, 0.0, hidden, timeout, advice=True)

    def _register(self, name, points, hidden, timeout, advice):
        def register(func):
            if any(c.name == name for c in self.checks):
                raise ValueError(f"{self.id}: duplicate check name {name!r}")
            self.checks.append(Check(name, points, func, self, hidden, timeout, advice))
            return func

        return register

    def max_score(self, include_hidden: bool = True) -> float:
        return sum(c.points for c in self.checks if include_hidden or not c.hidden)


@dataclass
class Lab:
    key: str
    module: str
    title: str
    exercises: dict[str, Exercise] = field(default_factory=dict)
    forbidden: dict[str, tuple[str, ...]] = field(default_factory=dict)
    folder: Path | None = None   # a course lab's folder (see .labfolders); None: built in

    def __post_init__(self):
        if not re.fullmatch(r"lab\d\d", self.key):
            raise ValueError(f"lab key must look like 'lab07', got {self.key!r}")
        if self.key in REGISTRY:
            raise LabKeyTaken(self.key)
        REGISTRY[self.key] = self

    def exercise(self, key: str, title: str, functions: list[str]) -> Exercise:
        """Declare an exercise and the student functions it grades, as signatures."""
        if key in self.exercises:
            return self.exercises[key]
        signatures = {sig.split("(", 1)[0].strip(): sig for sig in functions}
        self.exercises[key] = Exercise(self, key, title, signatures)
        return self.exercises[key]

    def forbid(self, function: str, *library_functions: str):
        """Inside ``function``, calling any of ``library_functions`` fails the check."""
        self.forbidden[function] = self.forbidden.get(function, ()) + library_functions

    def signature(self, function: str) -> str:
        for exercise in self.exercises.values():
            if function in exercise.signatures:
                return exercise.signatures[function]
        return f"{function}(...)"


def discover() -> dict[str, Lab]:
    """Import every lab suite: ``autograder.labs.*``, then hidden checks, then plug-ins."""
    for package_name in ("autograder.labs", "autograder.labs.hidden"):
        try:
            package = importlib.import_module(package_name)
        except ModuleNotFoundError:
            continue  # the student bundle has no hidden checks
        for info in pkgutil.iter_modules(package.__path__):
            if not info.ispkg and not info.name.startswith("_"):
                name = f"{package_name}.{info.name}"
                _load_suite(name, lambda: importlib.import_module(name))
    for entry in _plugins():
        _load_suite(entry.name, entry.load)
    from .labfolders import load_bundled

    _load_suite("course_labs/", load_bundled)
    return REGISTRY


@lru_cache(maxsize=1)
def _plugins() -> tuple:
    """Lab suites installed as plug-ins (entry points ``autograder.labs``), looked up once:
    the lookup reads every installed distribution's metadata."""
    return tuple(metadata.entry_points(group="autograder.labs"))


def hidden_checks_installed() -> bool:
    """Whether this copy has the hidden checks (the student bundle does not)."""
    return importlib.util.find_spec("autograder.labs.hidden") is not None


def _load_suite(name: str, load) -> None:
    """Load one lab suite; a broken suite is logged and skipped, never fatal to grading."""
    try:
        load()
    except Exception:  # noqa: BLE001
        logging.getLogger("autograder").exception("lab suite %s failed to load; skipped", name)


_HIDDEN_BY_COURSE: set[str] = set()   # ids of checks a course configuration hides


def hide_checks(selectors) -> None:
    """Make the checks named by ``selectors`` hidden checks, and only those (the course
    configuration's ``hide``): a check id (``lab07.ex1::translate_grey``), an exercise
    (``lab07.ex1``) or a lab (``lab07``). A hidden check is graded as before; students see
    its verdict only. Raises :class:`SelectionError` for a selector that names nothing."""
    checks = {c.id: c for lab in discover().values() for e in lab.exercises.values() for c in e.checks}
    chosen = set()
    for selector in selectors:
        matches = {i for i, c in checks.items()
                   if selector in (i, c.exercise.id, c.exercise.lab.key)}
        if not matches:
            raise SelectionError(f"hide: {selector!r} names no check (checks look like "
                                 "lab07.ex1::translate_grey; `autograder list --ids` lists them)")
        chosen |= {i for i in matches if not checks[i].hidden or i in _HIDDEN_BY_COURSE}
    for check_id in _HIDDEN_BY_COURSE - chosen:
        if check_id in checks:
            checks[check_id].hidden = False
    for check_id in chosen:
        checks[check_id].hidden = True
    _HIDDEN_BY_COURSE.clear()
    _HIDDEN_BY_COURSE.update(chosen)


def select(selectors=(), include_hidden: bool = True) -> list[Exercise]:
    """Exercises named by selectors like ``lab07`` or ``lab07.ex2`` (all when empty)."""
    labs = sorted(discover().values(), key=lambda lab: lab.key)
    every = [ex for lab in labs for ex in lab.exercises.values()
             if ex.max_score(include_hidden) > 0]
    if not selectors:
        return every
    chosen = []
    for selector in selectors:
        selector = selector.strip().lower()
        matches = [ex for ex in every if ex.id == selector or ex.lab.key == selector
                   or ex.lab.module == selector]
        if not matches:
            available = ", ".join(lab.key for lab in labs) or "none"
            raise SelectionError(f"nothing to grade matches {selector!r} "
                                 f"(labs: {available}; exercises look like lab07.ex2)")
        chosen += [ex for ex in matches if ex not in chosen]
    return chosen
