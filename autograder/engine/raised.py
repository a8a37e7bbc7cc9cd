"""A NumPy error the student's function raised, explained from the line that raised it.

The worker relays the exception and the student's frames (``Traceback (your code):`` ...);
:mod:`autograder.engine.forms` reads what the message alone tells. Some causes need the
line too: ``np.hstack([R, t])`` fails with "all the input arrays must have same number of
dimensions" for a translation given as a (3,) vector, and which array is ``t``, and that
the caller gave it that shape, only the line and the call's arguments say. The line is read
with :mod:`ast` (never run), and a cause is named only when the array the error points at is
one of the function's own parameters, unchanged before that line, whose given shape shows it.
"""

from __future__ import annotations

import ast
import re

import numpy as np

from .claims import measured
from .forms import Form
from .hints import Code, _own_nodes, signature_of_def

# 'File "lab09_camera.py", line 42, in camera_matrix' and, on the next line, the code
_FRAME = re.compile(r'File "([^"]+)", line (\d+)(?:, in (\S+))?\n(?:    (.*))?')


def innermost_frame(traceback_text: str) -> tuple[str, int, str, str] | None:
    """``(file, line, function, code)`` of the last frame of a student traceback (the worker's
    "Traceback (your code):" text), or None."""
    frames = _FRAME.findall(traceback_text or "")
    if not frames:
        return None
    filename, line, function, code = frames[-1]
    return filename, int(line), function, code.strip()
_NDIM = re.compile(r"the array at index (\d+) has (\d+) dimension\(s\) and the array at index (\d+) has "
                   r"(\d+) dimension\(s\)")
_SIZE = re.compile(r"along dimension (\d+), the array at index (\d+) has size (\d+) and the array at "
                   r"index (\d+) has size (\d+)")
_SLICE = re.compile(r"slice indices must be integers")
SLICED_MISTAKE = "a fractional value used as a slice bound"
JOINS = frozenset({"hstack", "vstack", "concatenate", "column_stack", "row_stack", "stack", "append", "block"})
MISTAKE = "a 1-D vector joined to a 2-D array"


def explained(code: Code, traceback_text: str, message: str, function: str, args, kwargs) -> Form | None:
    """The cause of the exception ``message`` that ``function`` (called with ``args``,
    ``kwargs``) raised, read from its innermost line in ``traceback_text`` when that line is in
    ``function`` itself; None otherwise."""
    frame = innermost_frame(traceback_text)
    fn = code.functions.get(function)
    if frame is None or fn is None or frame[2] != function:
        return None
    line = frame[1]
    signature = signature_of_def(fn)
    try:
        given = signature.bind(*args, **kwargs).arguments if signature else {}
    except TypeError:
        return None
    if _SLICE.search(message):
        return _fraction_sliced(fn, line, given)
    found = _NDIM.search(message) or _SIZE.search(message)
    if found is None:
        return None
    for call in _calls_on_line(fn, line):
        parts = _joined(call)
        if parts is None:
            continue
        return _join_named(fn, call, parts, found, given, line)
    return None


def _fraction_sliced(fn, line: int, given: dict) -> Form | None:
    """A parameter given a fractional number, used in a slice bound on the raising line."""
    for node in _own_nodes(fn):
        if not isinstance(node, ast.Slice) or not node.lineno <= line <= getattr(node, "end_lineno", node.lineno):
            continue
        for bound in (node.lower, node.upper, node.step):
            for name in (n.id for n in ast.walk(bound) if isinstance(n, ast.Name)) if bound is not None else ():
                value = given.get(name)
                if isinstance(value, (float, np.floating)) and value != int(value) and not _reassigned(fn, name, line):
                    # measured: the line raised on a slice holding this parameter, given a fraction
                    return Form(measured(f"your `{fn.name}` uses `{name}`, given {value!r} here, in a slice "
                                         f"(line {line}), and slice bounds must be whole numbers: a slice moves "
                                         "whole pixels only"), SLICED_MISTAKE)
    return None


def _calls_on_line(fn, line: int) -> list[ast.Call]:
    return [node for node in _own_nodes(fn) if isinstance(node, ast.Call)
            and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)
            and _called(node) in JOINS]


def _called(call: ast.Call) -> str:
    target = call.func
    return target.attr if isinstance(target, ast.Attribute) else target.id if isinstance(target, ast.Name) else ""


def _joined(call: ast.Call) -> list[ast.AST] | None:
    """The arrays a join call joins (``np.hstack([a, b])``, ``np.append(a, b, axis=1)``)."""
    if _called(call) == "append":
        return list(call.args[:2]) if len(call.args) >= 2 else None
    if call.args and isinstance(call.args[0], (ast.List, ast.Tuple)):
        return list(call.args[0].elts)
    return None


def _join_named(fn, call, parts, found, given, line) -> Form | None:
    if found.re is _NDIM:
        first, first_ndim, second, second_ndim = (int(g) for g in found.groups())
        pairs = [(first, first_ndim), (second, second_ndim)]
    else:
        return None   # sizes along an axis: which is wrong, the line alone does not say
    flat = [index for index, ndim in pairs if ndim == 1]
    if len(flat) != 1 or flat[0] >= len(parts):
        return None
    part = _unwrapped(parts[flat[0]])
    if not isinstance(part, ast.Name) or part.id not in given or _reassigned(fn, part.id, line):
        return None
    value = given[part.id]
    if not isinstance(value, np.ndarray) or value.ndim != 1:
        return None
    n = value.shape[0]
    joined = ast.unparse(call)
    joined = joined if len(joined) <= 60 else joined[:57] + "..."
    # measured: the line raised with this argument as given, so it was not made a column before
    return Form(measured(f"your `{fn.name}` joins `{part.id}` as it was given, shape ({n},), a 1-D vector, to a 2-D array "
                f"in `{joined}` (line {line}); the API allows a ({n},) vector here: make it a column first "
                f"({part.id}.reshape({n}, 1), or np.column_stack)"), MISTAKE)


# Calls that keep their argument's shape: np.asarray(t, float), t.astype(float), t.copy()
SHAPE_KEEPING = frozenset({"asarray", "array", "asanyarray", "ascontiguousarray", "float64", "float32",
                           "astype", "copy"})


def _unwrapped(node: ast.AST) -> ast.AST:
    """The array ``node`` converts without reshaping (``t`` of ``np.asarray(t, np.float64)``)."""
    while isinstance(node, ast.Call) and _called(node) in SHAPE_KEEPING:
        if isinstance(node.func, ast.Attribute) and _called(node) in ("astype", "copy") \
                and not (isinstance(node.func.value, ast.Name) and node.func.value.id in ("np", "numpy")):
            node = node.func.value
        elif node.args:
            node = node.args[0]
        else:
            break
    return node


def _reassigned(fn, name: str, line: int) -> bool:
    """Whether ``name`` is assigned (or augmented) in ``fn`` before ``line``."""
    for node in _own_nodes(fn):
        targets = node.targets if isinstance(node, ast.Assign) else \
            [node.target] if isinstance(node, (ast.AugAssign, ast.AnnAssign, ast.For)) else []
        for target in targets:
            if any(isinstance(n, ast.Name) and n.id == name for n in ast.walk(target)) and node.lineno < line:
                return True
    return False
