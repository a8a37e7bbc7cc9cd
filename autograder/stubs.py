"""Knowing, without running anything, that a check can only say "not implemented yet".

A skeleton function whose body is nothing but ``raise NotImplementedError(...)``
(after its docstring) answers every call the same way. A check whose only
student call is such a function therefore scores 0 with "``name()`` is not
implemented yet", whatever ground truth, scene or pictures it would build first.
The runner uses the two facts below to record that verdict without running the
check (see :func:`autograder.runner.run_check`); everything else runs as usual.

- :func:`stub_functions` reads the student's module source (``ast`` only, never
  executed) for such stubs;
- :func:`functions_called` reads a check's source (and its helpers' in the same
  suite) for the student functions it names (``t.call("translate", ...)``,
  ``judge_matrix_call(t, "translation_matrix", ...)``).
"""

from __future__ import annotations

import ast
import inspect
from functools import lru_cache
from pathlib import Path

from .registry import Check

_MAX_SOURCE_BYTES = 2_000_000  # a larger module is simply graded the normal way
# Code that can rebind a module's names at run time: a function "stub" might not stay one.
_DYNAMIC = ("globals(", "setattr(", "__dict__", "sys.modules", "exec(", "eval(", "importlib")


def stub_functions(module_file: Path) -> frozenset[str]:
    """Top-level functions of ``module_file`` that can only raise ``NotImplementedError``.

    A function counts when it is undecorated, its body is an optional docstring
    followed by ``raise NotImplementedError`` (with constant arguments, if any),
    and nothing else in the module binds its name or ``NotImplementedError``.
    """
    try:
        source = Path(module_file).read_bytes()
        if len(source) > _MAX_SOURCE_BYTES:
            return frozenset()
        text = source.decode("utf-8")
        tree = ast.parse(text)
    except (OSError, UnicodeDecodeError, SyntaxError, ValueError, RecursionError):
        return frozenset()
    if any(token in text for token in _DYNAMIC):
        return frozenset()
    bindings: dict[str, int] = {}
    for node in ast.walk(tree):
        for name in _bound_names(node):
            bindings[name] = bindings.get(name, 0) + 1
    if bindings.get("NotImplementedError"):
        return frozenset()
    return frozenset(node.name for node in tree.body
                     if isinstance(node, ast.FunctionDef) and _is_stub(node)
                     and bindings.get(node.name) == 1)


def _bound_names(node: ast.AST):
    """Names a node binds (defs, assignments, imports, ``global``, deletions...)."""
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        yield node.name
    elif isinstance(node, ast.Name) and not isinstance(node.ctx, ast.Load):
        yield node.id
    elif isinstance(node, (ast.Import, ast.ImportFrom)):
        for alias in node.names:
            yield alias.asname or alias.name.split(".")[0]
    elif isinstance(node, (ast.Global, ast.Nonlocal)):
        yield from node.names
    elif isinstance(node, ast.arg):
        yield node.arg


def _is_stub(function: ast.FunctionDef) -> bool:
    if function.decorator_list:
        return False
    body = function.body
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
            and isinstance(body[0].value.value, str):
        body = body[1:]
    if len(body) != 1 or not isinstance(body[0], ast.Raise) or body[0].cause is not None:
        return False
    raised = body[0].exc
    if isinstance(raised, ast.Name):
        return raised.id == "NotImplementedError"
    return (isinstance(raised, ast.Call) and isinstance(raised.func, ast.Name)
            and raised.func.id == "NotImplementedError" and not raised.keywords
            and all(isinstance(arg, ast.Constant) for arg in raised.args))


def functions_called(check: Check) -> frozenset[str]:
    """The lab's student functions named in ``check``'s source or in the source of
    the module-level helpers it uses (empty when a source cannot be read)."""
    names = frozenset(name for exercise in check.exercise.lab.exercises.values()
                      for name in exercise.signatures)
    return _named_in(check.func, names)


def _named_in(func, names: frozenset[str]) -> frozenset[str]:
    found, seen, todo = set(), set(), [func]
    while todo:
        function = todo.pop()
        if function in seen:
            continue
        seen.add(function)
        strings, helpers = _mentions(function)
        if strings is None:
            return frozenset()  # source unknown: claim nothing
        found |= strings & names
        todo += helpers
    return frozenset(found)


@lru_cache(maxsize=None)
def _mentions(function):
    """The string constants in ``function``'s source, and the module-level functions
    of the same package it refers to (helpers that may call students too)."""
    node = _definitions(function.__code__.co_filename).get(function.__code__.co_firstlineno)
    if node is None:
        return None, []
    strings, helpers = set(), []
    namespace = function.__globals__
    for inner in ast.walk(node):
        if isinstance(inner, ast.Constant) and isinstance(inner.value, str):
            strings.add(inner.value)
        elif isinstance(inner, ast.Name):
            helper = namespace.get(inner.id)
            if inspect.isfunction(helper) and _package(helper) == _package(function):
                helpers.append(helper)
    return strings, helpers


@lru_cache(maxsize=None)
def _definitions(filename: str) -> dict[int, ast.AST]:
    """Every function (and lambda) of a source file, by the first line of its code
    object (its first decorator's line when decorated)."""
    try:
        tree = ast.parse(Path(filename).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, SyntaxError, ValueError):
        return {}
    definitions = {}
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            first = min([node.lineno] + [d.lineno for d in node.decorator_list])
            definitions[first] = node
        elif isinstance(node, ast.Lambda):
            definitions.setdefault(node.lineno, node)
    return definitions


def _package(function) -> str:
    return (function.__module__ or "").split(".")[0]
