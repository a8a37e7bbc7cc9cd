"""A NumPy error the student's function raised, explained from the line that raised it.

The worker relays the exception and the student's frames (``Traceback (your code):`` ...);
:mod:`autograder.engine.forms` reads what the message alone tells. Some causes need the
line too: ``np.hstack([R, t])`` fails with "all the input arrays must have same number of
dimensions" for a translation given as a (3,) vector, and which array is ``t``, and that
the caller gave it that shape, only the line and the call's arguments say. The line is read
with :mod:`ast` (never run), and a cause is named only when the array the error points at is
one of the function's own parameters, unchanged before that line, whose given shape shows it.

The same reading explains Python's unpacking errors ("too many values to unpack (expected 2)"
for ``height, width = image.shape`` given a colour image): the count comes from a parameter as
given, from what an OpenCV call returns (:mod:`autograder.engine.outputs`) or from a function of
the module; and OpenCV's errors of methods, from what the code builds
(:mod:`autograder.engine.cv_raised`). A parameter passed on to a helper as it came (or converted
without reshaping) is followed into the helper's frame.
"""

from __future__ import annotations

import ast
import math
import re

import numpy as np

from .claims import from_code, measured
from .forms import Form
from .hints import Code, _own_nodes, _path, none_returned, signature_of_def
from ..loading.parsing import walk

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


def frames_of(traceback_text: str) -> list[tuple[str, int, str, str]]:
    """Every ``(file, line, function, code)`` of a student traceback, outermost first."""
    return [(f, int(n), fn, c.strip()) for f, n, fn, c in _FRAME.findall(traceback_text or "")]


def without_comprehensions(frames: list) -> list:
    """``frames`` with a comprehension's own frames (Python 3.11 runs them apart) folded into the def
    holding it: its innermost line stays, told of that def."""
    frames = list(frames)
    line = frames[-1][1] if frames else 0
    while frames and frames[-1][2] in _COMPREHENSIONS:
        frames.pop()
    if frames and frames[-1][1] != line:
        frames[-1] = (frames[-1][0], line, frames[-1][2], frames[-1][3])
    return frames


def raising_place(code: Code, traceback_text: str, function: str, args, kwargs):
    """``(def, line, given)`` of the innermost frame of ``function``'s traceback: the def that
    raised, its line, and what its parameters were given -- the caller's arguments bound to
    ``function``'s parameters, and through each call of a helper of the module on the way, those of
    its arguments that are the caller's parameters passed on as they came (``_warp(image, M)``).
    None when a frame is not one of the module's functions or ``function`` is not the outermost."""
    frames = without_comprehensions(frames_of(traceback_text))
    line = frames[-1][1] if frames else 0
    if not frames or frames[0][2] != function or any(f[0] != frames[0][0] for f in frames):
        return None
    fn = code.functions.get(function)
    signature = signature_of_def(fn) if fn is not None else None
    if signature is None:
        return None
    try:
        given = dict(signature.bind(*args, **kwargs).arguments)
    except TypeError:
        return None
    for (_, calling, _, _), (_, _, callee, _) in zip(frames, frames[1:]):
        helper = code.functions.get(callee)
        if helper is None:
            return None
        given = _passed_on(fn, calling, helper, given)
        fn = helper
    return fn, line, given


_UNKNOWN = object()
_COMPREHENSIONS = frozenset({"<listcomp>", "<genexpr>", "<setcomp>", "<dictcomp>"})


def _passed_on(caller, line: int, helper, given: dict) -> dict:
    """What ``helper``'s parameters were given by ``caller``'s call of it on ``line``: the caller's
    parameters passed as they came (or converted without reshaping); nothing else is known."""
    calls = [n for n in _own_nodes(caller) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
             and n.func.id == helper.name and n.lineno <= line <= getattr(n, "end_lineno", n.lineno)]
    signature = signature_of_def(helper)
    if len(calls) != 1 or signature is None or any(isinstance(a, ast.Starred) for a in calls[0].args) \
            or any(k.arg is None for k in calls[0].keywords):
        return {}

    def value(node):
        node = _unwrapped(node)
        if isinstance(node, ast.Name) and node.id in given and not _changed(caller, node.id, line):
            return given[node.id]
        return _UNKNOWN

    call = calls[0]
    try:
        bound = signature.bind(*[value(a) for a in call.args], **{k.arg: value(k.value) for k in call.keywords})
    except TypeError:
        return {}
    return {name: v for name, v in bound.arguments.items() if v is not _UNKNOWN}


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
    ``function`` itself or in a function of the module it calls (:func:`raising_place`); None otherwise."""
    place = raising_place(code, traceback_text, function, args, kwargs)
    if place is None:
        return None
    fn, line, given = place
    if _SLICE.search(message):
        return _fraction_sliced(fn, line, given)
    if _TUPLE_INDEX.search(message):
        return _axis_missing(fn, line, given)
    found = _OUT_OF_BOUNDS.search(message)
    if found:
        return _index_beyond(fn, line, given, *map(int, found.groups()))
    if _SINGULAR.search(message):
        return _singular_solved(fn, line)
    if _ZERO_DIVISION.search(message):
        return _zero_divisor(fn, line, given)
    if _NEGATIVE_SHIFT.search(message):
        return _negative_shift(fn, line, given)
    if _RANK.search(message):
        return _sequence_per_axis(fn, line, given)
    if _READ_ONLY.search(message):
        return _read_only_written(fn, line, given)
    if _TOO_MANY.search(message) or _NOT_ENOUGH.search(message):
        return unpacked(code, fn, line, given, message)
    found = _NOT_ITERABLE.search(message)
    if found and _single_unpacked(fn, line, given, found.group(1)) is not None:
        return _single_unpacked(fn, line, given, found.group(1))
    if _INHOMOGENEOUS.search(message):
        return _mixed_items(fn, line)
    found = _CONTAINER_ATTRIBUTE.search(message)
    if found:
        return _item_wrapped(fn, line, *found.groups())
    found = _UNEXPECTED_KEYWORD.search(message)
    if found:
        return _keyword_not_taken(fn, line, *found.groups())
    found = _UNBOUND.search(message)
    if found:
        return _local_read_first(fn, line, found.group(1) or found.group(2))
    found = _REMOVED.search(message)
    if found:
        return _removed_name(fn, line, found.group(1), found.group(2))
    found = _ALIAS_REMOVED.search(message)
    if found:
        return _removed_name(fn, line, found.group(1), found.group(2), release="1.24")
    found = _NO_SUCH_NAME.search(message)
    if found:
        return _no_such_name(fn, line, *found.groups())
    found = _PAD_PAIRS.search(message)
    if found:
        return _pad_pairs(fn, line, *map(int, found.groups()))
    if _FLOAT_SIZE.search(message):
        return _float_size(fn, line)
    if _SCALAR_WRITTEN.search(message):
        return _scalar_written(fn, line)
    if _MATH_DOMAIN.search(message):
        return _math_domain(fn, line, _with_defaults(fn, given) if fn.name == function else given)
    if "NoneType" in message:
        return _none_returned(code, fn, line)
    if "OpenCV(" in message:
        from .cv_raised import opencv_explained

        return opencv_explained(code, fn, line, given, message, function)
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
            for name in (n.id for n in walk(bound) if isinstance(n, ast.Name)) if bound is not None else ():
                value = given.get(name)
                if isinstance(value, (float, np.floating)) and value != int(value) and not _reassigned(fn, name, line):
                    # measured: the line raised on a slice holding this parameter, given a fraction
                    return Form(measured(f"your `{fn.name}` uses `{name}`, given {value!r} here, in a slice "
                                         f"(line {line}), and slice bounds must be whole numbers: a slice moves "
                                         "whole pixels only"), SLICED_MISTAKE)
    return None


_TUPLE_INDEX = re.compile(r"tuple index out of range")
AXIS_MISSING = "an axis read that the array given does not have (a grey image has no channel axis)"


def _axis_missing(fn, line: int, given: dict) -> Form | None:
    """``x.shape[k]`` on the raising line, where ``x`` is a parameter as given with fewer than k + 1
    axes: a grey (H, W) image read as a colour one (``image.shape[2]``), a single point as a stack."""
    for node in _own_nodes(fn):
        if not (isinstance(node, ast.Subscript) and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)
                and isinstance(node.value, ast.Attribute) and node.value.attr == "shape"
                and isinstance(node.slice, ast.Constant) and isinstance(node.slice.value, int)):
            continue
        found = _as_given(fn, line, given, node.value.value)
        shape = _shape_given(found[1]) if found is not None else None
        axis = node.slice.value
        if shape is None or not (axis >= len(shape) or -axis > len(shape)):
            continue
        name, written = found[0], _short(ast.unparse(node), 60)
        # (a grey image: 8 bits, or both sides longer than a point's few coordinates -- (N, 2) points are not)
        grey = len(shape) == 2 and axis in (2, -3) and (getattr(found[1], "dtype", None) == np.uint8 or min(shape) > 4)
        return Form(measured(f"your `{fn.name}` reads `{written}` (line {line}), but `{name}` has shape "
                             f"{tuple(shape)} here: it has no axis {axis}"
                             + (f" -- a grey image (H, W) has no channel axis, and grey images are given here: "
                                f"handle both (`{name}.ndim == 2`)" if grey else "")), AXIS_MISSING)
    return None


def _shape_given(value) -> tuple | None:
    """The shape of an argument as the check gave it; None for a value that has none (a ragged list)."""
    try:
        return tuple(np.shape(value))
    except (ValueError, TypeError):
        return None


_OUT_OF_BOUNDS = re.compile(r"index (-?\d+) is out of bounds for axis (\d+) with size (\d+)")
INDEX_BEYOND = "an index beyond the array given (a column or channel it does not have)"


def _index_beyond(fn, line: int, given: dict, index: int, axis: int, size: int) -> Form | None:
    """``x[:, 2]`` (an index written as a number, at ``axis``) on the raising line, where ``x`` is a
    parameter as given with only ``size`` entries along that axis: points given (N, 2) read as
    homogeneous (N, 3), a grey image's channel read."""
    for node in _own_nodes(fn):
        if not (isinstance(node, ast.Subscript) and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)):
            continue
        parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
        if axis >= len(parts) or not (isinstance(parts[axis], ast.Constant) and parts[axis].value == index) \
                or any(isinstance(part, ast.Constant) and part.value is Ellipsis for part in parts):
            continue
        found = _as_given(fn, line, given, node.value)
        shape = (_shape_given(found[1]) if found is not None else None) or ()
        if len(shape) <= axis or shape[axis] != size:
            continue
        name = found[0]
        return Form(measured(f"your `{fn.name}` reads `{_short(ast.unparse(node), 60)}` (line {line}), but `{name}` has shape "
                             f"{tuple(shape)} here: axis {axis} has {size} entries, so index {index} is beyond it"),
                    INDEX_BEYOND)
    return None


_SINGULAR = re.compile(r"Singular matrix")
SINGULAR_MISTAKE = "a homogeneous unknown fixed to 1 (a point at infinity has it 0)"


def _singular_solved(fn, line: int) -> Form | None:
    """``np.linalg.solve`` (or ``inv``) raising "Singular matrix" on the raising line; where its answer
    gets a last coordinate of 1 appended (``np.append(np.linalg.solve(A, b), 1.0)``), the cause: a
    homogeneous vector solved with its last unknown fixed to 1, which a point at infinity (0 there)
    cannot have."""
    parents = {id(child): node for node in _own_nodes(fn) for child in ast.iter_child_nodes(node)}
    for node in _own_nodes(fn):
        if not (isinstance(node, ast.Call) and _called(node) in ("solve", "inv") and node.args
                and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)):
            continue
        said = (f"your `{fn.name}` calls `{_short(ast.unparse(node), 60)}` (line {line}), and its matrix "
                f"`{_short(ast.unparse(node.args[0]), 40)}` is singular for this input: the system has no single "
                "solution")
        if not _one_appended(node, parents):
            return Form(measured(said), "a singular system solved")
        # measured: the solve raised here, and the code appends a 1 to what it solves
        return Form(measured(f"{said}. The answer gets a last coordinate of 1 appended: the homogeneous vector "
                             "is solved with its last entry fixed to 1, which a vector whose last entry is 0 (a "
                             "point at infinity) cannot be; the null vector by SVD (the last row of Vt) covers "
                             "every case"), SINGULAR_MISTAKE)
    return None


_CONTAINER_ATTRIBUTE = re.compile(r"'(list|tuple)' object has no attribute '(\w+)'")
ITEM_WRAPPED = "an item read through the list or tuple that holds it"
# OpenCV's matchers that answer each query with a sequence of its k nearest matches
_K_NEAREST = frozenset({"knnMatch", "radiusMatch"})


def _item_wrapped(fn, line: int, kind: str, attribute: str) -> Form | None:
    """``m.<attribute>`` on the raising line, where ``m`` is an item of a sequence whose items are themselves
    lists or tuples: appended wrapped (``good.append([best])``, as OpenCV's drawMatchesKnn takes them), or
    answered so by a matcher (``knnMatch`` gives each query a sequence of its k nearest matches)."""
    read = {node.value.id for node in _own_nodes(fn) if isinstance(node, ast.Attribute) and node.attr == attribute
            and isinstance(node.value, ast.Name) and node.lineno == line}
    tried = set()   # (each sequence looped over is read once, however many loops take it)
    for loop in _own_nodes(fn):
        if not isinstance(loop, (ast.For, ast.comprehension)) or not (loop.lineno if isinstance(loop, ast.For)
                                                                       else loop.target.lineno) <= line:
            continue
        target = loop.target.elts[-1] if isinstance(loop.target, ast.Tuple) and isinstance(loop.iter, ast.Call) \
            and _path(loop.iter.func) == "enumerate" and loop.target.elts else loop.target
        if not (isinstance(target, ast.Name) and target.id in read):
            continue
        looped = loop.iter.args[0] if isinstance(loop.iter, ast.Call) and _path(loop.iter.func) == "enumerate" \
            and loop.iter.args else loop.iter
        if ast.dump(looped) in tried:
            continue
        tried.add(ast.dump(looped))
        said = _wrapped_items(fn, looped, line)
        if said:
            return Form(measured(f"`{target.id}.{attribute}` (line {line}) reads a {kind}: {said}, so "
                                 f"`{target.id}` is that {kind}; read the item inside it (`{target.id}[0].{attribute}`), "
                                 f"or keep the item itself"), ITEM_WRAPPED)
    return None


def _wrapped_items(fn, looped, line: int) -> str:
    """Why the items of ``looped`` are lists or tuples, where the code says so; "" otherwise."""
    calls = [looped] if isinstance(looped, ast.Call) else []
    if isinstance(looped, ast.Name):
        for node in _own_nodes(fn):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "append" \
                    and isinstance(node.func.value, ast.Name) and node.func.value.id == looped.id \
                    and len(node.args) == 1 and isinstance(node.args[0], (ast.List, ast.Tuple)) and node.lineno < line:
                shown = ast.unparse(node)
                return f"each item of `{looped.id}` is appended wrapped in one (`{shown}`, line {node.lineno})"
            if isinstance(node, ast.Assign) and node.lineno < line and isinstance(node.value, ast.Call) \
                    and any(isinstance(t, ast.Name) and t.id == looped.id for t in node.targets):
                calls.append(node.value)
    for call in calls:
        if isinstance(call.func, ast.Attribute) and call.func.attr in _K_NEAREST:
            return (f"`{call.func.attr}` (line {call.lineno}) answers each query with a sequence of its nearest "
                    f"matches, and the loop takes those sequences")
    return ""


_UNEXPECTED_KEYWORD = re.compile(r"(\w+)\(\) got an unexpected keyword argument '(\w+)'")
KEYWORD_NOT_TAKEN = "a keyword argument the function called does not take"


def _keyword_not_taken(fn, line: int, called: str, keyword: str) -> Form | None:
    """``np.diag(v, dtype=float)`` on the raising line: NumPy's function takes no such parameter -- its own
    parameters are told (a dtype is given to the array, before or after)."""
    import inspect

    for node in _own_nodes(fn):
        if isinstance(node, ast.Call) and node.lineno <= line <= getattr(node, "end_lineno", node.lineno) \
                and _path(node.func).rpartition(".")[2] == called and any(k.arg == keyword for k in node.keywords):
            path = _path(node.func)
            head, _, rest = path.partition(".")
            if head not in ("np", "numpy"):
                return None
            try:
                import functools

                target = functools.reduce(getattr, rest.split("."), np)
                parameters = [p for p in inspect.signature(target).parameters if p not in ("args", "kwargs")]
            except (AttributeError, TypeError, ValueError):
                return None
            return Form(measured(f"your `{fn.name}` calls `{path}` with `{keyword}=` (line {line}), a parameter it does "
                                 f"not have (its parameters: {', '.join(parameters)}): " + (
                                     "give the dtype to the array itself, before or after (`np.asarray(..., "
                                     "dtype=...)`, `.astype(...)`)" if keyword == "dtype" else
                                     f"give `{keyword}` another way")), KEYWORD_NOT_TAKEN)
    return None


_INHOMOGENEOUS = re.compile(r"inhomogeneous shape|setting an array element with a sequence")
MIXED_ITEMS = "a list of items of different forms made an array (None, or a number, beside pairs)"


def _item_form(node) -> str | None:
    """What an appended item is, where its code says: "None", "a number" or "a sequence of n"."""
    if isinstance(node, ast.Constant):
        return "None" if node.value is None else "a number" if isinstance(node.value, (int, float)) else None
    if isinstance(node, (ast.Tuple, ast.List)) and not any(isinstance(e, ast.Starred) for e in node.elts):
        return f"a sequence of {len(node.elts)}"
    return None


def _mixed_items(fn, line: int) -> Form | None:
    """``np.array(rows)`` on the raising line, where ``rows`` is a list the function appends items of different
    forms to (``None`` for a point behind the camera, ``(x, y)`` for the others): no array holds both."""
    lists = {node.args[0].id for node in _own_nodes(fn) if isinstance(node, ast.Call)
             and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)
             and isinstance(node.func, ast.Attribute) and node.func.attr in ("array", "asarray", "stack", "vstack")
             and node.args and isinstance(node.args[0], ast.Name)}
    for name in sorted(lists):
        forms = {}
        for node in _own_nodes(fn):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "append" \
                    and isinstance(node.func.value, ast.Name) and node.func.value.id == name and len(node.args) == 1:
                form = _item_form(node.args[0])
                if form is not None:
                    forms.setdefault(form, node.lineno)
        if len(forms) >= 2:
            (first, at), (second, then) = sorted(forms.items(), key=lambda item: item[1])[:2]
            return Form(measured(f"your `{fn.name}` appends {first} to `{name}` (line {at}) and {second} (line {then}): "
                                 f"NumPy cannot make one array of items of different forms; append the same form for "
                                 f"every item (NaN entries, `(np.nan, np.nan)`, where there is no value)"), MIXED_ITEMS)
    return None


_UNBOUND = re.compile(r"cannot access local variable '(\w+)'|local variable '(\w+)' referenced before assignment")
UNBOUND = "a name read before the function assigns it (assigned in the function, it is local everywhere in it)"


def _local_read_first(fn, line: int, name: str) -> Form | None:
    """``name`` read on the raising line before any assignment of it in ``fn`` ran: assigned somewhere in the
    function (under a test, a loop, later), so Python takes it as the function's own name everywhere in it --
    the module's name of that name is not read there."""
    stores = sorted((n for n in _own_nodes(fn) if isinstance(n, ast.Name) and n.id == name
                     and isinstance(n.ctx, ast.Store)), key=lambda n: n.lineno)
    if not stores:
        return None
    first = stores[0]
    guard = next((node for node in _own_nodes(fn) if isinstance(node, (ast.If, ast.For, ast.While, ast.Try))
                  and node.lineno < first.lineno <= getattr(node, "end_lineno", node.lineno)), None)
    under = f", under `{ast.unparse(guard.test) if isinstance(guard, (ast.If, ast.While)) else type(guard).__name__.lower()}`" \
        if guard is not None and not isinstance(guard, ast.Try) else ""
    return Form(measured(f"your `{fn.name}` assigns `{name}` (line {first.lineno}{under}), so Python takes `{name}` "
                         f"as the function's own name everywhere in it -- a module-level `{name}` is not read there -- "
                         f"and on this call no assignment of it had run when line {line} read it: assign it on every "
                         f"path before it is read (or give the module's one another name)"), UNBOUND)


_REMOVED = re.compile(r"`np\.(\w+)` was removed in the NumPy 2\.0 release\.\s*(.+?)\.?(?:\s*$|\.\s)", re.M)
# (NumPy 1.24 removed the aliases of Python's own types: np.int, np.float, np.bool, np.object, np.str)
_ALIAS_REMOVED = re.compile(r"`np\.(\w+)` was a deprecated alias for the builtin `(\w+)`")
# a name NumPy does not have, told by Python alone (removed without a message of NumPy's, or misspelt)
_NO_SUCH_NAME = re.compile(r"module 'numpy((?:\.\w+)*)' has no attribute '(\w+)'")
_REMOVED_SILENTLY = {"product": "np.prod", "cumproduct": "np.cumprod", "msort": "np.sort(a, axis=0)",
                     "asscalar": "a.item()", "alen": "len(a)"}
REMOVED_NAME = "a name NumPy removed"
NO_SUCH_NAME = "a name NumPy does not have"


def _removed_name(fn, line: int, name: str, instead: str, release: str = "2.0") -> Form | None:
    """``np.<name>`` on the raising line, which NumPy ``release`` removed (its message says what replaces it:
    ``Use `np.asarray` with a proper dtype instead``, or the builtin's name)."""
    written = re.fullmatch(r"[Uu]se (`[^`]+`) instead", instead.strip())
    replacement = written.group(1) if written else f"`{instead}`" if re.fullmatch(r"\w+", instead) else ""
    node = _numpy_name_on_line(fn, line, name)
    if node is None:
        return None
    return Form(measured(f"your `{fn.name}` uses `{ast.unparse(node)}` (line {line}), a name NumPy {release} "
                         f"removed (the grading's NumPy is {np.__version__}): "
                         + (f"write {replacement}" if replacement else instead.strip()[:1].lower() + instead.strip()[1:])),
                REMOVED_NAME)


def _numpy_name_on_line(fn, line: int, name: str, module: str = ""):
    """The ``np<module>.<name>`` attribute written on ``line`` of ``fn``, or None."""
    for node in _own_nodes(fn):
        if isinstance(node, ast.Attribute) and node.attr == name \
                and _path(node.value) in (f"np{module}", f"numpy{module}") \
                and node.lineno <= line <= getattr(node, "end_lineno", node.lineno):
            return node
    return None


def _no_such_name(fn, line: int, module: str, name: str) -> Form | None:
    """``np<module>.<name>`` on the raising line, a name the grading's NumPy does not have: one it removed
    without a message of its own (`np.product`), or a misspelling of one it has (`np.linalg.svg`)."""
    node = _numpy_name_on_line(fn, line, name, module)
    if node is None:
        return None
    written = ast.unparse(node)
    if name in _REMOVED_SILENTLY:
        return Form(measured(f"your `{fn.name}` uses `{written}` (line {line}), a name NumPy 2 removed (the "
                             f"grading's NumPy is {np.__version__}): write `{_REMOVED_SILENTLY[name]}`"), REMOVED_NAME)
    import difflib
    import functools

    holder = functools.reduce(getattr, module.strip(".").split("."), np) if module else np
    public = [n for n in dir(holder) if not n.startswith("_")]
    close = difflib.get_close_matches(name, public, n=1, cutoff=0.6)
    if not close:
        return None
    meant = f"{_path(node.value)}.{close[0]}"
    return Form(measured(f"your `{fn.name}` uses `{written}` (line {line}), a name NumPy does not have "
                         f"(the grading's NumPy is {np.__version__}): `{meant}` is the nearest it has"), NO_SUCH_NAME)


_PAD_PAIRS = re.compile(r"remapped shapes \[original->remapped\]: \((\d+),\s*2\)\s+and requested shape \((\d+),\s*2\)")
PAD_PAIRS = "pad widths given for another number of axes than the array has (a colour image's channels)"


def _pad_pairs(fn, line: int, pairs: int, axes: int) -> Form | None:
    """np.pad refusing its pad widths: NumPy's message counts them (``(2,2)``: two (before, after) pairs) and
    the array's axes (``requested shape (3,2)``); the call on the raising line says which."""
    for call in _every_call_on_line(fn, line):
        if _called(call) != "pad" or (len(call.args) < 2 and not call.keywords):
            continue
        widths = call.args[1] if len(call.args) > 1 else next((k.value for k in call.keywords if k.arg == "pad_width"), None)
        if widths is None:
            continue
        colour = " (a colour image: its channel axis needs its `(0, 0)` too)" if axes == 3 and pairs == 2 else ""
        return Form(measured(f"your `{fn.name}` gives `np.pad` the widths `{_short(ast.unparse(widths), 40)}`, "
                             f"{pairs} (before, after) pairs, for an array of {axes} axes{colour} (line {line}): "
                             "np.pad takes one pair per axis"), PAD_PAIRS)
    return None


_FLOAT_SIZE = re.compile(r"'(?:numpy\.)?float\w*' object cannot be interpreted as an integer")
FLOAT_SIZE = "a size computed as a float (rounded by NumPy, or divided) given where a whole number belongs"
_FLOATING = frozenset({"floor", "ceil", "round", "rint", "trunc", "fix", "around"})


_WHOLE_MAKING = frozenset({"int", "round", "len", "math.floor", "math.ceil", "math.trunc"})


def _outside_whole(value):
    """The nodes of ``value`` not inside a call that makes a whole number (`int(...)`, Python's `round`, `len`)."""
    stack = [value]
    while stack:
        node = stack.pop()
        yield node
        if not (isinstance(node, ast.Call) and _path(node.func) in _WHOLE_MAKING):
            stack.extend(reversed(list(ast.iter_child_nodes(node))))   # (in the order written)


def _floating(value) -> bool:
    """Whether an expression gives a float however whole its value: np.floor/np.ceil/np.round (float arrays and
    NumPy floats), a true division, float()."""
    for node in _outside_whole(value):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div):
            return True
        if isinstance(node, ast.Call) and (_called(node) in _FLOATING and _path(node.func).startswith(("np.", "numpy."))
                                           or _path(node.func) == "float"):
            return True
    return False


_SIZED = frozenset({"zeros", "ones", "empty", "full"})   # their first argument (or shape=) is a size
_COUNTED = frozenset({"range", "reshape", "resize"})      # every argument a whole number (or a tuple of them)
FOLLOWED = 24   # names followed back from one line at most (each read of a def walks it)


def _size_arguments(call: ast.Call) -> list:
    """The arguments of ``call`` that must be whole numbers: an array's shape, a range's bounds, a reshape's or a
    resize's sizes (other arguments -- a fill value, a scale factor -- may be floats)."""
    called = _called(call)
    if called in _SIZED:
        return call.args[:1] + [k.value for k in call.keywords if k.arg == "shape"]
    if called in _COUNTED:
        return list(call.args) + [k.value for k in call.keywords if k.arg in ("shape", "dsize", "newshape")]
    return []


def _float_size(fn, line: int) -> Form | None:
    """A size given on the raising line (an array's shape, a range's bound, a reshape's sizes) that the function
    bound to a float (`height = bottom - top + 1` with `bottom = np.ceil(...)`): followed back through the names
    it is computed from, at most :data:`FOLLOWED` of them."""
    seen: set = set()

    def made_float(name: str) -> int | None:
        if name in seen or len(seen) >= FOLLOWED:
            return None
        seen.add(name)
        for node in sorted(_assignments(fn, name, line), key=lambda n: -getattr(n, "lineno", 0)):
            value = _bound_value(node, name)
            if value is None:
                continue
            if _floating(value):
                return node.lineno
            names = [inner.id for inner in _outside_whole(value) if isinstance(inner, ast.Name)
                     and isinstance(inner.ctx, ast.Load)]
            return next((found for found in map(made_float, names) if found is not None), None)
        return None

    for call in _every_call_on_line(fn, line):
        for argument in _size_arguments(call):
            for name in (n for n in _outside_whole(argument) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)):
                made = made_float(name.id)
                if made is not None:
                    return Form(measured(
                        f"your `{fn.name}` gives `{_short(ast.unparse(call), 50)}` (line {line}) `{name.id}`, a float: "
                        f"it is computed from a float (line {made}; np.floor, np.ceil and np.round give floats, as a "
                        f"division does), where a whole number belongs: make it one (`int(...)`)"), FLOAT_SIZE)
    return None


def _bound_value(node, name: str):
    """The expression ``node`` (an assignment) binds ``name`` to: the matching item of a tuple unpacked from a
    tuple written out (`w, h = a - b, c - d`), else the whole value."""
    if isinstance(node, ast.Assign):
        for target in node.targets:
            if isinstance(target, ast.Name) and target.id == name:
                return node.value
            if isinstance(target, (ast.Tuple, ast.List)) and isinstance(node.value, (ast.Tuple, ast.List)) \
                    and len(target.elts) == len(node.value.elts):
                for part, value in zip(target.elts, node.value.elts):
                    if isinstance(part, ast.Name) and part.id == name:
                        return value
            if isinstance(target, (ast.Tuple, ast.List)):
                return node.value
    if isinstance(node, (ast.AugAssign, ast.AnnAssign)) and node.value is not None:
        return node.value
    return None


_SCALAR_WRITTEN = re.compile(r"'numpy\.\w+' object does not support item assignment")
SCALAR_WRITTEN = "an entry written into a NumPy scalar (arithmetic on a single value gives a number, not an array)"


def _scalar_written(fn, line: int) -> Form | None:
    """An entry written (`depth[~valid] = 0`) into a name the function computed by arithmetic: given a single value
    (a float, a 0-d array), NumPy's arithmetic gives a scalar, which has no entries to write."""
    for node in _own_nodes(fn):
        if not (isinstance(node, (ast.Assign, ast.AugAssign)) and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)):
            continue
        targets = node.targets if isinstance(node, ast.Assign) else [node.target]
        for target in targets:
            if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name):
                name = target.value.id
                made = [a for a in _assignments(fn, name, line) if isinstance(_bound_value(a, name), (ast.BinOp, ast.UnaryOp))]
                if made:
                    return Form(measured(
                        f"your `{fn.name}` writes into `{name}` (line {line}), which it computes by arithmetic "
                        f"(line {made[-1].lineno}): given a single value (a number, a 0-d array) that arithmetic gives a "
                        f"NumPy scalar, not an array, and a scalar has no entries to write: make it an array first "
                        f"(`np.asarray(..., dtype=float)`) or compute it with `np.where`"), SCALAR_WRITTEN)
    return None


_ZERO_DIVISION = re.compile(r"(?:division|modulo) by zero")
ROUNDED_TO_ZERO = "a floor division that rounds down to 0, used as a divisor"
ZERO_DIVISOR = "a divisor that is 0 for this input"


def _zero_divisor(fn, line: int, given: dict) -> Form | None:
    """A Python division on the raising line whose divisor is worked out as 0 from the numbers the
    parameters were given (and the plain assignments above it); where a floor division made the 0 --
    in the divisor (``u // (width // 2 ** n_bits)`` with width < 2 ** n_bits) or in the assignment of a
    name it reads (``stripe = width // 2 ** n_bits``) -- that is the cause."""
    known, made = _numbers_known(fn, line, given)
    for node in _own_nodes(fn):
        if not (isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Div, ast.FloorDiv, ast.Mod))
                and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)
                and _number(node.right, known) == 0):
            continue
        said = f"your `{fn.name}` divides by `{_short(ast.unparse(node.right), 50)}` (line {line}), which is 0 here"
        places = [(node.right, None)] + [(made[n.id], n.id) for n in walk(node.right)
                                         if isinstance(n, ast.Name) and n.id in made]
        for expression, name in places:
            floored = next((n for n in walk(expression) if isinstance(n, ast.BinOp) and isinstance(n.op, ast.FloorDiv)
                            and _number(n, known) == 0 and _number(n.left, known) not in (0, None)), None)
            if floored is None:
                continue
            # measured: the floor division is worked out from the given numbers, not guessed
            where = f"`{name} = {_short(ast.unparse(expression), 40)}` (line {expression.lineno})" if name else \
                f"`{_short(ast.unparse(floored), 40)}`"
            return Form(measured(f"{said} ({_values(floored, known)}): {where} is a floor division of a smaller number "
                                 "by a larger one, which rounds down to 0 (and elsewhere drops its remainder); "
                                 "multiply first and divide last"), ROUNDED_TO_ZERO)
        return Form(measured(f"{said} ({_values(node.right, known)})"), ZERO_DIVISOR)
    return None


# (Python 3.11-3.13 say "math domain error"; 3.14 names the domain)
_MATH_DOMAIN = re.compile(r"math domain error|expected a (?:positive|nonnegative) input|expected a number in range")
OUTSIDE_DOMAIN = "a math function given a number outside the numbers it takes"
# math's functions by what they take, and what to do where a value can reach the edge
_DOMAINS = {
    **dict.fromkeys(("log", "log2", "log10"), ("a positive number", "0 or negative",
                                               from_code("where it can reach 0 (a ratio of 1, say), keep it above 0 "
                                                         "or treat that case apart"))),
    "log1p": ("a number above -1", "-1 or below", from_code("keep it above -1")),
    "sqrt": ("a number >= 0", "negative", from_code("a rounding error can take a value that is 0 just below it: "
                                                           "clip it at 0")),
    **dict.fromkeys(("acos", "asin"), ("a number from -1 to 1", "outside it",
                                       from_code("a rounding error can take a cosine just past 1: clip it to [-1, 1]"))),
    "acosh": ("a number >= 1", "below 1", from_code("clip it at 1")),
    "atanh": ("a number strictly between -1 and 1", "outside it", from_code("keep it inside")),
}


# math's other functions that raise the same error for some arguments (not told: their domains take two numbers)
_OTHER_DOMAINS = frozenset({"pow", "fmod", "remainder", "gamma", "lgamma", "ldexp", "dist", "hypot"})


def _math_domain(fn, line: int, given: dict) -> Form | None:
    """The one call of :mod:`math` on the raising line whose argument can leave what it takes
    (``math.log(1 - w ** 4)`` with w = 1; ``math.log(1 - confidence)`` beside it is worked out from the
    numbers given, and takes them): Python's math functions raise there, where NumPy's give nan."""
    known, _ = _numbers_known(fn, line, given)
    calls = []
    for call in _every_call_on_line(fn, line):
        name = _path(call.func).rsplit(".", 1)[-1]
        if _path(call.func).startswith("math.") and name in _OTHER_DOMAINS:
            return None   # (math.pow(-1, 0.5) raises the same error: which call did is not known)
        if not (_path(call.func).startswith("math.") and name in _DOMAINS and call.args):
            continue
        value = _number(call.args[0], known)
        if value is None or not _takes(name, value):
            calls.append((call, name))
    if len(calls) != 1:
        return None   # (which of several raised is not known)
    call, name = calls[0]
    takes, was, advice = _DOMAINS[name]
    return Form(from_code(f"your `{fn.name}` calls `{_short(ast.unparse(call), 60)}` (line {line}): math.{name} takes "
                          f"{takes} only, and `{_short(ast.unparse(call.args[0]), 40)}` was {was} here; {advice}"),
                OUTSIDE_DOMAIN)


def _with_defaults(fn, given: dict) -> dict:
    """``given`` with the number defaults of ``fn``'s parameters it lacks (for the def called itself: a
    parameter it lacks was not passed; a helper's may have been passed a value not known)."""
    positional = [*fn.args.posonlyargs, *fn.args.args]
    pairs = list(zip(positional[len(positional) - len(fn.args.defaults):], fn.args.defaults)) + [
        (a, d) for a, d in zip(fn.args.kwonlyargs, fn.args.kw_defaults) if d is not None]
    defaults = {a.arg: d.value for a, d in pairs if isinstance(d, ast.Constant)
                and isinstance(d.value, (int, float)) and not isinstance(d.value, bool)}
    return {**defaults, **given}


def _takes(name: str, value) -> bool:
    """Whether math's ``name`` takes the number ``value``."""
    try:
        getattr(math, name)(float(value))
        return True
    except (ValueError, TypeError, OverflowError):
        return False


_NEGATIVE_SHIFT = re.compile(r"negative shift count")
NEGATIVE_SHIFT = "a bit shift by a count that is negative for this input"


def _negative_shift(fn, line: int, given: dict) -> Form | None:
    """The shift (``a >> n``, ``a << n``) on the raising line whose count is worked out as negative
    from the numbers the parameters were given (``u >> (int(np.log2(width)) - n_bits)`` with
    ``n_bits > log2(width)``), or the only shift there by a count that is not a constant."""
    known, _ = _numbers_known(fn, line, given)
    shifts = [node for node in _own_nodes(fn) if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.RShift, ast.LShift))
              and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)
              and not (isinstance(node.right, ast.Constant) and isinstance(node.right.value, int) and node.right.value >= 0)]
    for node in shifts:
        count = _number(node.right, known)
        if (count is not None and count < 0) or (count is None and len(shifts) == 1):
            worked = f"{count!r} here ({_values(node.right, known)})" if count is not None else "negative here"
            # measured: the shift raised on this line, and its count is worked out (or the only candidate)
            return Form(measured(f"your `{fn.name}` shifts by `{_short(ast.unparse(node.right), 50)}` (line {line}), "
                                 f"which is {worked}, and a shift count must be 0 or more"), NEGATIVE_SHIFT)
    return None


_RANK = re.compile(r"sequence argument must have length equal to input rank")
SEQUENCE_PER_AXIS = "values given per axis for another number of axes than the array has (a colour image's channels)"


def _sequence_per_axis(fn, line: int, given: dict) -> Form | None:
    """scipy.ndimage's "one value per axis" refused on the raising line: a call there gives an array the
    parameter holds as it came (its shape known) and a tuple or list of fewer (or more) values than its axes
    (`ndimage.shift(image, (ty, tx))` for a colour image)."""
    for call in (n for n in _own_nodes(fn) if isinstance(n, ast.Call) and n.lineno <= line <= getattr(n, "end_lineno", n.lineno)):
        arrays = [found for found in (_as_given(fn, line, given, a) for a in call.args[:1]) if found is not None]
        shape = _shape_given(arrays[0][1]) if arrays else None
        if not shape:
            continue
        for sequence in (a for a in list(call.args[1:]) + [k.value for k in call.keywords] if isinstance(a, (ast.Tuple, ast.List))):
            count = len(sequence.elts)
            if count != len(shape):
                colour = " (a colour image: the channel axis needs its 0 too)" if len(shape) == 3 and shape[2] in (3, 4) \
                    and count == 2 else ""
                # measured: the shape is the argument's as given; the values are counted in the code
                return Form(measured(f"your `{fn.name}` gives `{_short(ast.unparse(call.func), 30)}` "
                                     f"`{_short(ast.unparse(sequence), 30)}`, {count} values, for `{arrays[0][0]}` of "
                                     f"shape {shape}, which has {len(shape)} axes{colour} (line {line}): scipy.ndimage "
                                     "takes one value per axis"), SEQUENCE_PER_AXIS)
    return None


_READ_ONLY = re.compile(r"(?:assignment destination|output array) is read-only")
READ_ONLY_VIEW = from_code("a write into a read-only view (np.diagonal, np.broadcast_to give one)")
INPUT_WRITTEN = from_code("a write into an array the caller gave (read-only here)")
_VIEWS = ("diagonal", "broadcast_to", "broadcast_arrays")


def _read_only_written(fn, line: int, given: dict) -> Form | None:
    """The array written into on the raising line: a read-only view NumPy made (``S.diagonal()[:2] = ...``,
    or a name assigned one above) or a parameter as the caller gave it (the grader's inputs are read-only,
    so a function never changes its caller's arrays)."""
    views = {}   # name -> the call that made it a view
    for node in _own_nodes(fn):
        if isinstance(node, ast.Assign) and node.lineno < line and len(node.targets) == 1 \
                and isinstance(node.targets[0], ast.Name) and isinstance(node.value, ast.Call) \
                and _path(node.value.func).rsplit(".", 1)[-1] in _VIEWS:
            views[node.targets[0].id] = node.value
    for node in _own_nodes(fn):
        if not (isinstance(node, (ast.Assign, ast.AugAssign)) and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)):
            continue
        for target in (node.targets if isinstance(node, ast.Assign) else [node.target]):
            base = target
            while isinstance(base, ast.Subscript):
                base = base.value
            if isinstance(base, ast.Call) and _path(base.func).rsplit(".", 1)[-1] in _VIEWS:
                made = base
            elif isinstance(base, ast.Name) and base.id in views:
                made = views[base.id]
            else:
                made = None
            if made is not None:
                call = _short(ast.unparse(made), 40)
                return Form(measured(f"your `{fn.name}` writes into `{call}` (line {line}), a read-only view NumPy "
                                     f"returns: write into the array itself (`np.fill_diagonal`, an index such as "
                                     f"`S[i, i] = ...`) or build it whole (`np.diag([...])`)"), READ_ONLY_VIEW)
            # (an entry or slice written, `x[0] = ...`, or the whole array updated, `x /= s`)
            written = target is not base or isinstance(node, ast.AugAssign)
            if written and isinstance(base, ast.Name) and isinstance(given.get(base.id), np.ndarray):
                return Form(measured(f"your `{fn.name}` writes into `{base.id}` (line {line}), the array the caller "
                                     "gave, which is read-only here: a function must not change its caller's arrays; "
                                     f"work on a copy (`{base.id} = {base.id}.copy()`, or `x = x / s` rather than "
                                     "`x /= s`)"), INPUT_WRITTEN)
    return None


def _values(node, known: dict) -> str:
    """``width=5, n_bits=3``: the known numbers of the names ``node`` reads, in their order."""
    names = dict.fromkeys(n.id for n in walk(node) if isinstance(n, ast.Name) and n.id in known)
    return ", ".join(f"{name}={known[name]!r}" for name in names)


def _numbers_known(fn, line: int, given: dict) -> tuple[dict, dict]:
    """``(known, made)``: the names whose number is known at ``line`` -- the parameters given plain
    numbers, and the names the statements above it bind to numbers worked out from them (``width =
    int(width)``) -- and, of the latter, the expression each was bound to. A name bound in the
    statement holding ``line`` (a loop's body) is not known there."""
    known = {name: value.item() if isinstance(value, np.generic) else value for name, value in given.items()
             if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))}
    made = {}
    for statement in fn.body:
        holds = statement.lineno <= line <= getattr(statement, "end_lineno", statement.lineno)
        pairs = []
        if not holds and isinstance(statement, ast.Assign) and len(statement.targets) == 1:
            target, value = statement.targets[0], statement.value
            if isinstance(target, ast.Name):
                pairs = [(target, value)]
            elif isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) and len(target.elts) == len(value.elts):
                pairs = list(zip(target.elts, value.elts))
        worked = [(t.id, v, _number(v, known)) for t, v in pairs if isinstance(t, ast.Name)]
        for node in walk(statement):   # every name the statement binds is unknown, then set again
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
                known.pop(node.id, None)
                made.pop(node.id, None)
        for name, expression, value in worked:
            if value is not None:
                known[name] = value
                made[name] = expression
        if holds:
            break
    return known, made


_ARITHMETIC = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b,
               ast.Div: lambda a, b: a / b, ast.FloorDiv: lambda a, b: a // b, ast.Mod: lambda a, b: a % b,
               ast.Pow: lambda a, b: a ** b, ast.LShift: lambda a, b: a << b, ast.RShift: lambda a, b: a >> b}


_LOGS = {"log2": math.log2, "log10": math.log10, "log": math.log}


def _number(node, known: dict):
    """The number ``node`` works out to from ``known`` (constants, names, arithmetic, ``int()``,
    ``float()``, ``round()``, ``abs()``, ``np.log2()`` and its kin), or None. Never runs the student's code: small numbers only."""
    if isinstance(node, ast.Constant) and type(node.value) in (int, float):
        return node.value
    if isinstance(node, ast.Name):
        return known.get(node.id)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        value = _number(node.operand, known)
        return None if value is None else (-value if isinstance(node.op, ast.USub) else value)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in _LOGS \
            and isinstance(node.func.value, ast.Name) and node.func.value.id in ("np", "numpy", "math") \
            and len(node.args) == 1 and not node.keywords:
        value = _number(node.args[0], known)
        return None if value is None or value <= 0 else _LOGS[node.func.attr](value)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("int", "float", "round", "abs") \
            and len(node.args) == 1 and not node.keywords:
        value = _number(node.args[0], known)
        return None if value is None else {"int": int, "float": float, "round": round, "abs": abs}[node.func.id](value)
    if isinstance(node, ast.BinOp) and type(node.op) in _ARITHMETIC:
        left, right = _number(node.left, known), _number(node.right, known)
        if left is None or right is None or abs(left) > 2 ** 40 or abs(right) > 2 ** 40 \
                or (isinstance(node.op, (ast.Pow, ast.LShift)) and not 0 <= right <= 64):
            return None
        try:
            value = _ARITHMETIC[type(node.op)](left, right)
        except (ArithmeticError, TypeError, ValueError):
            return None
        return value if abs(value) <= 2 ** 64 else None   # (small numbers only: `2 ** 40 ** 64` is no divisor)
    return None


# methods that work in place and return None (`pts = pts.append(p)`, `order = order.sort()`)
_IN_PLACE_METHODS = frozenset({"sort", "append", "extend", "insert", "reverse", "shuffle", "fill", "resize",
                               "update", "remove", "clear", "setflags", "put"})
NONE_RETURNED = "the result of a call that returns None (a function without a return, a method that works in place)"


def _none_returned(code: Code, fn, line: int) -> Form | None:
    """A NoneType error on the raising line, where the one value there that comes from a call (on the
    line, or assigned from one above it) comes from a function of the module that returns None
    somewhere (:func:`~autograder.engine.hints.none_returned`: no ``return`` of a value, a bare one, an
    end reached without one), or from a method that works in place (``.sort()``, ``.append()``)."""
    on_line = [n for n in _own_nodes(fn) if getattr(n, "lineno", 0) <= line <= getattr(n, "end_lineno", 0)]
    calls = [n for n in on_line if isinstance(n, ast.Call)]
    for name in dict.fromkeys(n.id for n in on_line if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)):
        bound = _assignments(fn, name, line)
        if len(bound) == 1 and isinstance(bound[0], ast.Assign) and len(bound[0].targets) == 1 \
                and isinstance(bound[0].targets[0], ast.Name) and isinstance(bound[0].value, ast.Call):
            calls.append(bound[0].value)
    told = [said for said in (_gives_none(code, call) for call in calls) if said]
    if len(set(told)) != 1:
        return None   # (none, or several: which one was None the message does not say)
    return Form(from_code(f"{told[0]} (read in line {line})"), NONE_RETURNED)


def _gives_none(code: Code, call: ast.Call) -> str | None:
    """What makes ``call`` give None, read from the code, or None when nothing does."""
    written = f"`{_short(ast.unparse(call), 50)}` (line {call.lineno})"
    if isinstance(call.func, ast.Name) and call.func.id in code.functions:
        where = none_returned(code, call.func.id)   # (how the helper ends, as for a graded function)
        return f"{written} gives None: your `{call.func.id}` {where}" if where else None
    if isinstance(call.func, ast.Attribute) and call.func.attr in _IN_PLACE_METHODS:
        return f"{written} gives None: `.{call.func.attr}()` changes its object in place and returns None"
    return None


def _one_appended(solved, parents) -> bool:
    """Whether a 1 follows ``solved`` among the items it is joined with: ``np.append(solve(A, b), 1.0)``,
    ``np.hstack([solve(A, b), [1]])`` (a 1 inside the solve's own arguments, or before it, is not)."""
    holder, item = parents.get(id(solved)), solved
    if isinstance(holder, (ast.List, ast.Tuple)):
        holder, item = parents.get(id(holder)), holder
        items = item.elts
        after = items[items.index(solved) + 1:]
    else:
        after = None
    if not (isinstance(holder, ast.Call) and _called(holder) in ("append", "hstack", "concatenate")):
        return False
    if after is None:
        if item not in holder.args:
            return False
        after = holder.args[holder.args.index(item) + 1:]
    elif not (holder.args and holder.args[0] is item):
        return False

    def one(node) -> bool:
        values = node.elts if isinstance(node, (ast.List, ast.Tuple)) else [node]
        return len(values) == 1 and isinstance(values[0], ast.Constant) and type(values[0].value) in (int, float) \
            and values[0].value == 1
    return len(after) == 1 and one(after[0])


def _every_call_on_line(fn, line: int) -> list[ast.Call]:
    return [node for node in _own_nodes(fn) if isinstance(node, ast.Call)
            and node.lineno <= line <= getattr(node, "end_lineno", node.lineno)]


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


IMAGES_JOINED = "two images joined as they came (of different heights or channel counts)"


def _images_joined(fn, call, parts, found, given, line) -> Form | None:
    """Two images the function was given (unchanged before ``line``) joined as they came, where the API
    allows them unlike: a grey and a colour one (their dimensions), or side by side of different heights
    (their sizes along axis 0)."""
    names = [_unwrapped(part) for part in parts]
    if len(names) != 2 or not all(isinstance(n, ast.Name) and n.id in given and not _changed(fn, n.id, line)
                                  for n in names):
        return None
    images = [given[n.id] for n in names]
    if not all(isinstance(v, np.ndarray) and v.ndim in (2, 3) and min(v.shape[:2]) >= 8 for v in images):
        return None
    a, b = (n.id for n in names)
    joined = ast.unparse(call)
    joined = joined if len(joined) <= 60 else joined[:57] + "..."
    if found.re is _NDIM and {v.ndim for v in images} == {2, 3}:
        grey = a if images[0].ndim == 2 else b
        return Form(measured(f"your `{fn.name}` joins `{a}` {images[0].shape} and `{b}` {images[1].shape} as they came in "
                             f"`{joined}` (line {line}): a grey image and a colour one have different numbers of "
                             f"dimensions; convert `{grey}` to BGR first (cv2.cvtColor({grey}, cv2.COLOR_GRAY2BGR))"),
                    IMAGES_JOINED)
    if found.re is _SIZE and int(found.group(1)) == 0 and _called(call) in ("hstack", "concatenate"):
        return Form(measured(f"your `{fn.name}` puts `{a}` ({images[0].shape[0]} rows) and `{b}` ({images[1].shape[0]} "
                             f"rows) side by side as they came in `{joined}` (line {line}): images of different "
                             "heights are joined only on a canvas as high as the taller one (np.zeros of max(H1, H2) "
                             "rows and W1 + W2 columns, each image copied into its part)"), IMAGES_JOINED)
    return None


def _join_named(fn, call, parts, found, given, line) -> Form | None:
    images = _images_joined(fn, call, parts, found, given, line)
    if images is not None:
        return images
    if found.re is _NDIM:
        first, first_ndim, second, second_ndim = (int(g) for g in found.groups())
        pairs = [(first, first_ndim), (second, second_ndim)]
    else:
        return None   # sizes along an axis: which is wrong, the line alone does not say
    flat = [index for index, ndim in pairs if ndim == 1]
    if len(flat) != 1 or flat[0] >= len(parts):
        return None
    # (a parameter as given, or a name bound once to it converted without reshaping, `X = np.asarray(points)`)
    found = _as_given(fn, line, given, parts[flat[0]])
    if found is None:
        return None
    name, value = found
    if not isinstance(value, (np.ndarray, list, tuple)) or np.ndim(value) != 1:
        return None
    n = np.shape(value)[0]
    joined = ast.unparse(call)
    joined = joined if len(joined) <= 60 else joined[:57] + "..."
    # measured: the line raised with this argument as given, so it was not made a row or a column before
    if n in (2, 3) and _one_point(fn, name, given):
        return Form(measured(f"your `{fn.name}` joins `{name}` as it was given, shape ({n},), a single point, to a 2-D "
                             f"array in `{joined}` (line {line}); the API allows a single ({n},) point: make it a row "
                             f"of one point first (np.atleast_2d({name}), or {name}.reshape(-1, {n})), and give one "
                             f"point back"), MISTAKE)
    return Form(measured(f"your `{fn.name}` joins `{name}` as it was given, shape ({n},), a 1-D vector, to a 2-D array "
                f"in `{joined}` (line {line}); the API allows a ({n},) vector here: make it a column first "
                f"({name}.reshape({n}, 1), or np.column_stack)"), MISTAKE)


def _one_point(fn, name: str, given: dict) -> bool:
    """Whether ``name`` holds the points parameter (`points`, `pts`, `X`...) of ``fn``: a (2,) or (3,) value
    there is one point, a row, where another parameter's (3,) vector (`t`) is a column."""
    parameters = [a.arg for a in fn.args.args]
    source = name if name in given else next(
        (n.id for node in walk(fn) if isinstance(node, ast.Assign) and any(
            isinstance(t, ast.Name) and t.id == name for t in node.targets)
         for n in [_unwrapped(node.value)] if isinstance(n, ast.Name)), name)
    return source in parameters and ("point" in source.lower() or source.lower() in ("pts", "x", "xw", "world"))


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
            if any(isinstance(n, ast.Name) and n.id == name for n in walk(target)) and node.lineno < line:
                return True
    return False


def _assignments(fn, name: str, line: int) -> list[ast.AST]:
    """The statements of ``fn`` that bind ``name`` and may run before ``line``: those above it, and
    any in a loop holding ``line``."""
    loops = [n for n in _own_nodes(fn) if isinstance(n, (ast.For, ast.While))
             and n.lineno <= line <= getattr(n, "end_lineno", n.lineno)]
    inside = {id(n) for loop in loops for n in walk(loop)}
    found = []
    for node in _own_nodes(fn):
        if isinstance(node, ast.Assign):
            targets = node.targets
        elif isinstance(node, (ast.AugAssign, ast.AnnAssign, ast.For)):
            targets = [node.target]
        elif isinstance(node, ast.NamedExpr):
            targets = [node.target]
        elif isinstance(node, (ast.With, ast.AsyncWith)):
            targets = [item.optional_vars for item in node.items if item.optional_vars is not None]
        else:
            continue
        if any(isinstance(n, ast.Name) and n.id == name for t in targets for n in walk(t)) \
                and (node.lineno < line or id(node) in inside):
            found.append(node)
    return found


def _changed(fn, name: str, line: int) -> bool:
    """Whether ``name``'s shape may differ at ``line`` from what it was given: it is bound there by
    anything but a conversion of itself that keeps shapes (``image = np.asarray(image, float)``)."""
    for node in _assignments(fn, name, line):
        value = getattr(node, "value", None)
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)
                and value is not None and value is not _unwrapped(value)
                and isinstance(_unwrapped(value), ast.Name) and _unwrapped(value).id == name):
            return True
    return False


# "too many values to unpack (expected 2)" (Python 3.11; 3.13 adds ", got 3"), "not enough ... got 2)"
_TOO_MANY = re.compile(r"too many values to unpack \(expected (\d+)(?:, got (\d+))?\)")
_NOT_ENOUGH = re.compile(r"not enough values to unpack \(expected (\d+), got (\d+)\)")
UNPACK_MISTAKE = "a value unpacked into the wrong number of names"
COLOUR_SHAPE = "a colour image's shape unpacked into two values"
GREY_SHAPE = "a grey image's shape unpacked into three values"
ROWS_UNPACKED = "an array's rows unpacked as its columns"
OUTPUTS_COUNTED = "an OpenCV call's outputs unpacked into the wrong number of names"


_NOT_ITERABLE = re.compile(r"cannot unpack non-iterable (\w+) object")
NOT_ITERABLE = "a single value (or None) unpacked into several names"


def _defaults(fn) -> dict:
    """The parameters of ``fn`` whose default is written as a constant (``center=None``), and it."""
    arguments = fn.args
    positional = arguments.posonlyargs + arguments.args
    pairs = list(zip(positional[len(positional) - len(arguments.defaults):], arguments.defaults)) + \
        [(a, d) for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults) if d is not None]
    return {a.arg: d.value for a, d in pairs if isinstance(d, ast.Constant)}


def _single_unpacked(fn, line: int, given: dict, kind: str) -> Form | None:
    """``cx, cy = center`` raising "cannot unpack non-iterable NoneType object": a parameter given a
    single value, or not given and holding its written default, of the type the message names."""
    for names, source, loop in _unpack_sites(fn, line):
        if loop or not isinstance(source, ast.Name) or _changed(fn, source.id, line):
            continue
        name, written = source.id, ", ".join(ast.unparse(n) for n in names)
        if name in given and type(given[name]).__name__ == kind:
            return Form(measured(f"`{name}` is given a single value here ({given[name]!r}), and your code unpacks it "
                                 f"into `{written}` (line {line})"), NOT_ITERABLE)
        defaults = _defaults(fn)
        if name not in given and name in defaults and type(defaults[name]).__name__ == kind:
            return Form(measured(f"this call does not give `{name}`, so it holds its default, {defaults[name]!r}, and "
                                 f"your code unpacks it into `{written}` (line {line}): give it a value when it is "
                                 f"{defaults[name]!r} before unpacking it"), NOT_ITERABLE)
    return None


def _counts(message: str) -> tuple[int, int | None, bool] | None:
    """(names expected, values there if told, too many) from Python's unpacking error."""
    found = _TOO_MANY.search(message)
    if found:
        return int(found.group(1)), int(found.group(2)) if found.group(2) else None, True
    found = _NOT_ENOUGH.search(message)
    return (int(found.group(1)), int(found.group(2)), False) if found else None


def _fits_count(count: int, expected: int, got: int | None, too_many: bool) -> bool:
    """Whether ``count`` values unpacked into ``expected`` names raise the error measured."""
    return count == got if got is not None else (count > expected if too_many else False)


def _unpack_sites(fn, line: int):
    """``(names, source, loop)`` for each unpacking on ``line``: an assignment's target tuple and its
    value, or a loop's (or comprehension's) target tuple and what it iterates (``loop`` True); a loop
    over ``enumerate(x)`` or ``zip(x, y)`` gives the tuple unpacking each of x's, y's items."""
    for node in _own_nodes(fn):
        if isinstance(node, ast.Assign) and node.lineno <= line <= node.end_lineno and len(node.targets) == 1:
            target = node.targets[0]
            if isinstance(target, (ast.Tuple, ast.List)):
                yield target.elts, node.value, False
        elif isinstance(node, ast.For) and node.lineno == line or isinstance(node, ast.comprehension) and \
                node.target.lineno <= line <= node.iter.end_lineno:
            yield from _loop_sites(node.target, node.iter)


def _loop_sites(target, iterated):
    if not isinstance(target, (ast.Tuple, ast.List)):
        return
    yield target.elts, iterated, True
    called = iterated.func.id if isinstance(iterated, ast.Call) and isinstance(iterated.func, ast.Name) else ""
    if called == "enumerate" and len(target.elts) == 2 and iterated.args:
        yield from _loop_sites(target.elts[1], iterated.args[0])
    elif called == "zip" and len(target.elts) == len(iterated.args):
        for part, source in zip(target.elts, iterated.args):
            yield from _loop_sites(part, source)


def unpacked(code: Code, fn, line: int, given: dict, message: str) -> Form | None:
    """What is unpacked on ``line`` into the wrong number of names, when the value given, or what the
    code unpacks (an OpenCV call, a function of the module), shows how many values it holds."""
    counts = _counts(message)
    if counts is None:
        return None
    expected, got, too_many = counts
    sites = [(names, source, loop) for names, source, loop in _unpack_sites(fn, line)
             if len(names) == expected and not any(isinstance(n, ast.Starred) for n in names)]
    forms = [form for names, source, loop in sites
             for form in [_unpacked_from(code, fn, line, given, names, source, loop, counts)] if form is not None]
    return forms[0] if len(forms) == 1 else None


def _as_given(fn, line: int, given: dict, node) -> tuple[str, object] | None:
    """(name, value) when ``node`` is a parameter of ``fn`` holding, at ``line``, the shape it was given,
    or a name bound once, before, to such a parameter converted without reshaping."""
    node = _unwrapped(node)
    if isinstance(node, ast.Name) and node.id in given and not _changed(fn, node.id, line):
        return node.id, given[node.id]
    if isinstance(node, ast.Name) and node.id not in given:   # img = np.float32(image): one conversion
        bound = _assignments(fn, node.id, line)
        if len(bound) == 1 and isinstance(bound[0], ast.Assign) and len(bound[0].targets) == 1 \
                and isinstance(bound[0].targets[0], ast.Name) and bound[0].value is not _unwrapped(bound[0].value):
            source = _unwrapped(bound[0].value)
            if isinstance(source, ast.Name) and source.id in given and not _changed(fn, source.id, bound[0].lineno):
                return node.id, given[source.id]
    return None


def _unpacked_from(code, fn, line, given, names, source, loop, counts) -> Form | None:
    expected, got, too_many = counts
    written = ", ".join(ast.unparse(n) for n in names)
    where = f"line {line}"
    if not loop and isinstance(source, ast.Attribute) and source.attr == "shape":
        found = _as_given(fn, line, given, source.value)
        shape = getattr(found[1], "shape", None) if found else None
        if shape is None or not _fits_count(len(shape), expected, got, too_many):
            return None
        return _shape_unpacked(found[0], tuple(shape), expected, written, where)
    if loop:
        found = _as_given(fn, line, given, source)
        value = found[1] if found else None
        if isinstance(value, np.ndarray) and value.ndim == 2 and _fits_count(value.shape[1], expected, got, too_many):
            n, k = value.shape
            return Form(measured(f"each row of `{found[0]}`, given with shape ({n}, {k}) here, holds {k} values, and "
                                 f"your loop unpacks each into {expected} (`for {written} in "
                                 f"{_short(ast.unparse(source))}`, {where})"),
                        UNPACK_MISTAKE)
        return None
    found = _as_given(fn, line, given, source)
    if found is not None:
        return _value_unpacked(found[0], found[1], written, where, counts)
    from .outputs import COUNTS, NAMES, opencv_called, order_text, shown

    called = opencv_called(source, fn)
    if called in COUNTS and _fits_count(COUNTS[called], expected, got, too_many):
        outputs = order_text(called) or NAMES.get(called, "")
        old = (" (OpenCV 3 returned 3: image, contours, hierarchy)" if called == "findContours" and expected == 3
               else "")
        return Form(measured(f"{shown(called)} returns {COUNTS[called]} values ({outputs}){old}, and your code unpacks "
                             f"{expected} (`{written}`, {where})"), OUTPUTS_COUNTED)
    if isinstance(source, ast.Call) and isinstance(source.func, ast.Name) and source.func.id in code.functions:
        return _own_returns(code.functions[source.func.id], expected, got, too_many, written, where)
    return None


def _shape_unpacked(name: str, shape: tuple, expected: int, written: str, where: str) -> Form:
    n = len(shape)
    if len(shape) == 3 and shape[2] in (3, 4) and expected == 2:
        return Form(measured(f"`{name}.shape` is {shape} for the colour image given here: {n} values, and your code "
                             f"unpacks 2 (`{written} = {name}.shape`, {where}); take `{name}.shape[:2]` (height and "
                             "width), which a grey image has too"), COLOUR_SHAPE)
    if len(shape) == 2 and expected == 3:
        return Form(measured(f"`{name}.shape` is {shape} for the grey image given here: 2 values, no channel axis, and "
                             f"your code unpacks 3 (`{written} = {name}.shape`, {where}); take `{name}.shape[:2]`, "
                             f"and `{name}.ndim` tells a grey image (2) from a colour one (3)"), GREY_SHAPE)
    return Form(measured(f"`{name}.shape` is {shape} here ({n} values), and your code unpacks it into "
                         f"{expected} (`{written}`, {where})"), UNPACK_MISTAKE)


def _value_unpacked(name: str, value, written: str, where: str, counts) -> Form | None:
    expected, got, too_many = counts
    if isinstance(value, np.ndarray) and value.ndim >= 1:
        if not _fits_count(value.shape[0], expected, got, too_many):
            return None
        if value.ndim == 2 and value.shape[1] == expected:
            n, k = value.shape
            return Form(measured(f"`{name}` is given with shape ({n}, {k}) here, and unpacking it (`{written} = "
                                 f"{name}`, {where}) takes its {n} rows, not its {k} columns: write "
                                 f"`{written} = {name}.T` (or index the columns, {name}[:, 0])"), ROWS_UNPACKED)
        return Form(measured(f"`{name}` is given with shape {value.shape} here: unpacking it takes its "
                             f"{value.shape[0]} entries along the first axis, and your code unpacks {expected} "
                             f"(`{written}`, {where})"), UNPACK_MISTAKE)
    if isinstance(value, (tuple, list)) and _fits_count(len(value), expected, got, too_many):
        shown = repr(value)
        shown = shown if len(shown) <= 40 else shown[:37] + "..."
        return Form(measured(f"`{name}` is given {len(value)} values here ({shown}), and your code unpacks "
                             f"{expected} (`{written}`, {where})"), UNPACK_MISTAKE)
    return None


def _own_returns(helper, expected, got, too_many, written, where) -> Form | None:
    """Every ``return`` of ``helper`` a tuple of one length that raises the error measured."""
    returns = [n for n in _own_nodes(helper) if isinstance(n, ast.Return)]
    lengths = {len(n.value.elts) if isinstance(n.value, (ast.Tuple, ast.List)) else None for n in returns}
    if len(lengths) != 1 or None in lengths:
        return None
    count = lengths.pop()
    if not _fits_count(count, expected, got, too_many):
        return None
    first = min(returns, key=lambda n: n.lineno)
    # from the code: every return of the helper is a tuple of that many values
    return Form(from_code(f"your `{helper.name}` returns {count} values (`{_short(ast.unparse(first.value))}`, line "
                          f"{first.lineno}), and your code unpacks {expected} (`{written}`, {where})"), UNPACK_MISTAKE)


def _short(text: str, limit: int = 50) -> str:
    return text if len(text) <= limit else text[:limit - 3] + "..."
