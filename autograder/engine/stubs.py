"""Knowing, without running anything, that a check can only say "not implemented yet".

A skeleton function whose body is nothing but ``raise NotImplementedError(...)``
(after its docstring) answers every call the same way. A check whose only
student call is such a function therefore scores 0 with "``name()`` is not
implemented yet", whatever ground truth, scene or pictures it would build first.
The runner records that verdict without running the check when every function
of the exercise is such a stub and the check names exactly one student function
(see :func:`autograder.engine.runner._grade_exercise`); advice checks, and everything
else, run as usual. It uses two facts:

- :func:`stub_functions` reads the student's module source (``ast`` only, never
  executed) for such stubs;
- :func:`functions_called` reads a check's code (and its helpers' in the same
  package) for the student functions it names (``t.call("translate", ...)``,
  ``judge_matrix_call(t, "translation_matrix", ...)``). A helper whose name holds
  ``probe`` is not read: a confirmation probe runs only after the check's own call
  has given an answer to confirm (a stub's call fails first), so name every probe
  helper so, or a skeleton's checks run instead of being recorded.
"""

from __future__ import annotations

import inspect
import types
from functools import lru_cache
from pathlib import Path

from ..loading.handed_in import stub_names
from ..loading.parsing import parse
from .registry import Check

_MAX_SOURCE_BYTES = 2_000_000  # a larger module is simply graded the normal way


def stub_functions(module_file: Path) -> frozenset[str]:
    """Top-level functions of ``module_file`` that can only raise ``NotImplementedError``
    (read once per version of the file)."""
    try:
        stat = Path(module_file).stat()
    except OSError:
        return frozenset()
    return _stub_functions(str(module_file), stat.st_mtime_ns, stat.st_size)


@lru_cache(maxsize=64)
def _stub_functions(module_file: str, mtime_ns: int, size: int) -> frozenset[str]:
    """A function counts when it is undecorated, its body is an optional docstring
    followed by ``raise NotImplementedError`` (with constant arguments, if any),
    and nothing else in the module binds its name or ``NotImplementedError``
    (:func:`autograder.loading.handed_in.stub_names`, which also picks the file graded
    when a lab is handed in twice).
    """
    try:
        source = Path(module_file).read_bytes()
        if len(source) > _MAX_SOURCE_BYTES:
            return frozenset()
        text = source.decode("utf-8")
        if "NotImplementedError" not in text:  # no stub can be there: no need to parse
            return frozenset()
        tree = parse(text)   # under the parse lock, within its bounds (TooLarge is a ValueError)
    except (OSError, UnicodeDecodeError, SyntaxError, ValueError, RecursionError):
        return frozenset()
    return stub_names(tree, text)


def functions_called(check: Check) -> frozenset[str]:
    """The lab's student functions named (as string constants) in ``check``'s code
    or in the code of the module-level helpers it uses."""
    names = frozenset(name for exercise in check.exercise.lab.exercises.values()
                      for name in exercise.signatures)
    return _named_in(check.func, names)


def _named_in(func, names: frozenset[str]) -> frozenset[str]:
    found, seen, todo = set(), set(), [func]
    while todo:
        function = todo.pop()
        if function in seen or (function is not func and "probe" in function.__name__):
            # A probe confirms a mistake the check has already measured on the student's
            # answer, so it runs only after the check's own call of a function it names
            # (a stub's call fails first): its names add nothing to what the check needs.
            continue
        seen.add(function)
        strings, helpers = _mentions(function)
        found |= strings & names
        todo += helpers
    return frozenset(found)


@lru_cache(maxsize=None)
def _mentions(function):
    """The string constants in ``function``'s code (its lambdas and inner functions
    included) and closure, and the module-level functions of the same package it refers to
    (helpers that may call students too)."""
    strings, names, codes = set(), set(), [function.__code__]
    while codes:
        code = codes.pop()
        names.update(code.co_names)
        constants = list(code.co_consts)
        while constants:
            constant = constants.pop()
            if isinstance(constant, str):
                strings.add(constant)
            elif isinstance(constant, (tuple, frozenset)):
                constants += constant
            elif isinstance(constant, types.CodeType):
                codes.append(constant)
    # (a check made by a factory holds the function's name in its closure: conventions.keeps_grey)
    for cell in function.__closure__ or ():
        try:
            if isinstance(cell.cell_contents, str):
                strings.add(cell.cell_contents)
        except ValueError:   # an empty cell
            continue
    namespace = function.__globals__
    helpers = [namespace[name] for name in names if inspect.isfunction(namespace.get(name))
               and _package(namespace[name]) == _package(function)]
    return strings, helpers


def _package(function) -> str:
    return (function.__module__ or "").split(".")[0]
