"""A parameter the check gave a value, and the student's function never reads.

``warp_affine(image, A, dsize=(220, 100))`` answering at the input's size, ``rotate(image, 30,
center=(10, 20))`` turning about the middle: the outputs show a difference, the code shows why --
the body never reads ``dsize`` or ``center``. The function is read with :mod:`ast` (never run): a
parameter counts as read wherever its name is loaded, in nested functions and lambdas too, and a
function that reads ``locals()``/``vars()`` or forwards ``*args``/``**kwargs`` is not judged. A cause
is named only for a parameter the failing check's own calls gave a value (not None, not the
function's default), so that the value the check chose is the one the function dropped.
"""

from __future__ import annotations

import ast

import numpy as np

from .claims import from_code
from .hints import Code, _own_nodes, signature_of_def
from ..loading.parsing import walk

MISTAKE = "a parameter given is never used"
_INTROSPECTION = frozenset({"locals", "vars", "globals", "eval", "exec"})
# Randomness is often left to a library (cv2.findHomography draws its own samples): a seed unused is
# no cause of another failure, and the checks of the seed itself say when it matters.
_RANDOMNESS = ("seed", "rng", "random")


def never_read(fn: ast.FunctionDef) -> set[str]:
    """The parameters of ``fn`` its body never reads, or reads only to convert them into themselves
    (`dsize = tuple(dsize)` and no other read: :func:`read_beyond_itself`); empty when it reads ``locals()``
    and the like."""
    arguments = fn.args
    parameters = {a.arg for a in arguments.posonlyargs + arguments.args + arguments.kwonlyargs}
    loaded = read_beyond_itself(fn)
    return set() if loaded is None else parameters - loaded


def unused_given(code: Code, calls) -> tuple[str, str, object] | None:
    """``(function, parameter, value)``: in the trial's ``calls`` [(function, args, kwargs, ...)],
    a call that gave ``parameter`` a value its function never reads; None if there is none."""
    for function, args, kwargs, *_ in reversed(list(calls)):
        fn = code.functions.get(function)
        if fn is None:
            continue
        unread = never_read(fn)
        signature = signature_of_def(fn) if unread else None
        if signature is None:
            continue
        try:
            bound = signature.bind(*args, **kwargs).arguments
        except TypeError:
            continue
        for name in sorted(unread & set(bound)):
            value = bound[name]
            if any(word in name.lower() for word in _RANDOMNESS):
                continue
            if value is not None and not _is_default(fn, name, value):
                return function, name, value
    return None


def _is_default(fn: ast.FunctionDef, name: str, value) -> bool:
    """Whether ``value`` equals the literal default ``fn`` declares for ``name``."""
    arguments = fn.args
    positional = arguments.posonlyargs + arguments.args
    defaults = dict(zip([a.arg for a in positional[len(positional) - len(arguments.defaults):]], arguments.defaults))
    defaults.update({a.arg: d for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults) if d is not None})
    if name not in defaults:
        return False
    try:
        default = ast.literal_eval(defaults[name])
    except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
        return False
    try:
        return bool(np.array_equal(np.asarray(default, dtype=object), np.asarray(value, dtype=object)))
    except (ValueError, TypeError):
        return False


def sentence(function: str, parameter: str, value) -> str:
    """What is said: the function, the parameter and the value the check gave it."""
    shown = repr(value) if not isinstance(value, np.ndarray) else f"an array of shape {value.shape}"
    shown = shown if len(shown) <= 40 else shown[:37] + "..."
    # from the code: its body never loads the name (never_read)
    return from_code(f"your `{function}` never uses its parameter `{parameter}` (given {shown} here)")


UNUSED_VALUE = "a value computed is never used"


def read_beyond_itself(fn: ast.FunctionDef) -> set[str] | None:
    """The names ``fn`` reads other than to make themselves anew (`P1 = np.asarray(P1, float)` reads P1 only to
    bind P1 again: a conversion whose result is never read leaves P1 unused); None where it reads ``locals()``
    and the like."""
    converting = set()
    for statement in walk(fn):
        if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1):
            continue
        target, value = statement.targets[0], statement.value
        pairs = [(target, value)] if isinstance(target, ast.Name) else \
            list(zip(target.elts, value.elts)) if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) \
            and len(target.elts) == len(value.elts) else []   # (`P1, P2 = np.asarray(P1), np.asarray(P2)`)
        converting |= {id(node) for name, made in pairs if isinstance(name, ast.Name)
                       for node in walk(made) if isinstance(node, ast.Name) and node.id == name.id}
    loaded = set()
    for node in walk(fn):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
            if node.id in _INTROSPECTION:
                return None
            if id(node) not in converting:
                loaded.add(node.id)
    return loaded


def computed_unused(code: Code, functions) -> tuple[str, str, int] | None:
    """``(function, name, line)``: a value one of ``functions`` computes into a local name and never
    reads (`corners1 = ...` beside a canvas built from `corners2` alone: the step that needs it is
    missing); None if there is none. Only a plain `name = <an expression that computes>` counts (not a
    constant, not one name of a tuple unpacked: `h, w = shape` leaving `w` is no step left out)."""
    for function in functions:
        fn = code.functions.get(function)
        if fn is None:
            continue
        loaded = read_beyond_itself(fn)
        if loaded is None:
            continue
        stored = []
        for node in _own_nodes(fn):   # (not those of the functions defined in it)
            if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                    and not isinstance(node.value, ast.Constant) and not node.targets[0].id.startswith("_"):
                stored.append((node.lineno, node.targets[0].id))
        for line, name in sorted(stored):
            if name not in loaded:
                return function, name, line
    return None


def unused_value_sentence(function: str, name: str, line: int) -> str:
    # from the code: the name is stored once and never loaded in the function
    return from_code(f"your `{function}` computes `{name}` (line {line}) and never uses it: a step that "
                     f"needs it may be missing")
