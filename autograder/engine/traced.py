"""A failure explained from what the student's own expressions held when it happened.

NumPy's error names shapes ("operands could not be broadcast together with shapes (192,256)
(192,256,3)") and a check measures the shape of a wrong answer ("(6, 6, 20, 2); expected
(6, 20, 2)"); neither says which of the student's expressions made them, and reading the code
cannot know the shape of an array it computes. So the student's functions are run once more on
the failing input, in the companion sandbox (:meth:`~autograder.sandbox.supervisor.Sandbox.companion`),
rewritten so that every expression records what it gave -- an array's shape and dtype, a number,
a short tuple of numbers -- and returns it unchanged (:func:`recording_source`). Only those
descriptions cross back; the values never do.

The recording is then read against the code (:mod:`ast`, never run here), and a cause is said
only as what the recording shows of the student's own expression:

- an exception NumPy or OpenCV raised on a line: the expression of that line whose operands have
  the shapes the error names (``mask * band``: ``mask`` is (192, 256), ``band`` (192, 256, 3)),
  a slice bound that was negative (it counts from the end), an index past its axis, the arrays
  an OpenCV call was given and where each came from when they differ in kind;
- an answer of the wrong shape: following the returned value back through the student's
  assignments to the first expression that made that shape from operands that did not have it
  (``spread[:, None, None] * offsets``: (6, 1, 1, 1) against (6, 20, 2)), with the branch it was
  on.

The sentences are measurements of the student's code on the failing input: they hold whatever
the student meant, and they name the place, never the reference's code.
"""

from __future__ import annotations

import ast
import functools
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..loading.parsing import copy_tree, parse, walk
from .claims import from_code, measured
from .forms import EXCEPTION_FORMS, Form
from .recorder import SMALL_ARRAY as SMALL   # (the recorder's own bound: it is sent with it)

MISTAKE = "an expression of another shape than its use needs"
INDEX = "an index past the end of its axis"
TRUTH = "an array where one truth value is asked"
KINDS = "arrays of different kinds given to one OpenCV call"
RECORDER, RECORDED = "__ag_seen__", "__ag_recorded__"   # (the names recorder.py defines)
ARRAY_ATTRIBUTES = frozenset({"T", "shape", "size", "ndim", "real", "imag"})
TRACE_SECONDS = 3.0
GRADING_SECONDS = 8.0                 # the recordings' own time per grading (not the error model's: they come after it)
SPENT = "traced seconds"
CONFIRMATIONS = 3                     # departures of the student's values confirmed at most, per failed check


# ------------------------------------------------------------------ the rewrite (grader side: text only)
def node_key(node: ast.AST) -> str:
    """Where ``node`` is in the student's file: the key its recording is kept under."""
    return f"{node.lineno}:{node.col_offset}:{node.end_lineno}:{node.end_col_offset}"


class _Recording(ast.NodeTransformer):
    """Wraps each value-giving expression of a def in ``__ag_seen__(key, expression)``."""

    def __init__(self, local_names: frozenset[str]):
        self.local_names = local_names

    def _recorded(self, original: ast.AST, node: ast.AST) -> ast.AST:
        call = ast.Call(ast.Name(RECORDER, ast.Load()), [ast.Constant(node_key(original)), node], [])
        return ast.copy_location(call, original)

    def visit_FunctionDef(self, node):
        # decorators, defaults and annotations run once, when the def runs: left as written
        node.body = [self.visit(statement) for statement in node.body]
        return node

    visit_AsyncFunctionDef = visit_FunctionDef

    def visit_Assign(self, node):
        """``T[2, :2] = v`` records ``T`` as it is after (under the target's place): a matrix filled entry by
        entry has no expression of its own."""
        self.generic_visit(node)
        return [node] + self._containers(node.targets if isinstance(node, ast.Assign) else [node.target])

    visit_AugAssign = visit_Assign

    def _containers(self, targets) -> list:
        after = []
        for target in targets:
            if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Call) \
                    and isinstance(target.value.func, ast.Name) and target.value.func.id == RECORDER:
                base = target.value.args[1]   # (the container's name, recorded before: the same name after)
                if isinstance(base, ast.Name):
                    call = ast.Call(ast.Name(RECORDER, ast.Load()),
                                    [ast.Constant(node_key(target)), ast.Name(base.id, ast.Load())], [])
                    after.append(ast.copy_location(ast.Expr(call), target))
        return after

    def visit_Lambda(self, node):
        node.body = self.visit(node.body)
        return node

    def visit_ClassDef(self, node):
        return node

    def visit_Call(self, node):
        original = node
        node.func = self._callee(node.func)
        node.args = [self.visit(a) for a in node.args]
        node.keywords = [self.visit(k) for k in node.keywords]
        return self._recorded(original, node)

    def _callee(self, func):
        """A called name or method: its receiver is recorded (``band.astype``: ``band``), not itself."""
        if isinstance(func, ast.Attribute):
            func.value = self.visit(func.value)
            return func
        return func if isinstance(func, ast.Name) else self.visit(func)

    def visit_Name(self, node):
        if isinstance(node.ctx, ast.Load) and node.id in self.local_names:
            return self._recorded(node, node)
        return node

    def visit_Attribute(self, node):
        original = node
        self.generic_visit(node)
        if isinstance(node.ctx, ast.Load) and node.attr in ARRAY_ATTRIBUTES:
            return self._recorded(original, node)
        return node

    def _value_node(self, node):
        original = node
        self.generic_visit(node)
        loads = not hasattr(node, "ctx") or isinstance(node.ctx, ast.Load)
        return self._recorded(original, node) if loads else node

    visit_BinOp = visit_UnaryOp = visit_Compare = _value_node

    def visit_Subscript(self, node):
        """A module-level name indexed (`_PALETTE[i]`) is recorded too: its length says what an index past
        its end was past."""
        if isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Name) and node.value.id not in self.local_names:
            original = node
            node.value = self._recorded(node.value, node.value)
            node.slice = self.visit(node.slice)
            return self._recorded(original, node)
        return self._value_node(node)


def _local_names(fn: ast.AST) -> frozenset[str]:
    """The names a def binds itself (its parameters, what it assigns): the ones worth recording."""
    names = {a.arg for a in walk(fn) if isinstance(a, ast.arg)}   # (a nested def's too)
    names |= {n.id for n in walk(fn) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
    return frozenset(names)


_RECORDER = Path(__file__).with_name("recorder.py")   # the recorder's code, sent as text (see there)


def recording_source(code, function: str) -> str | None:
    """The student's ``function`` and the module's functions it calls, rewritten to record their
    expressions, with ``__ag_recorded__(*args, **kwargs)`` calling ``function`` and answering
    ``{"record": {key: description}, "returned": description}`` (``"raised"``: the exception's type)
    -- plain data; None when the code is not read."""
    reached = code.reachable([function])
    if not reached or reached[0].name != function:
        return None
    defs = []
    for fn in reached:
        rewritten = _Recording(_local_names(fn)).visit(copy_tree(fn))
        defs.append(ast.unparse(ast.fix_missing_locations(rewritten)))
    recorder = _RECORDER.read_text(encoding="utf-8")
    return recorder + "\n\n" + "\n\n".join(defs) + f"\n\n__ag_target__ = {function!r}\n"


# ------------------------------------------------------------------ the recording
@dataclass(frozen=True)
class Recording:
    """What each expression of the student's functions gave on one call (its last evaluation)."""

    values: dict
    returned: tuple | None = None
    raised: str = ""

    def shape(self, node) -> tuple | None:
        found = self.values.get(node_key(node))
        return found[1] if found and found[0] == "array" else None

    def dtype(self, node) -> str:
        found = self.values.get(node_key(node))
        return found[2] if found and found[0] == "array" else ""

    def value(self, node) -> np.ndarray | None:
        """The values of a small array (:data:`SMALL`) or of a number the node gave, as floats."""
        found = self.values.get(node_key(node))
        if found and found[0] == "array" and len(found) >= 4 and found[3] is not None:
            return found[3]
        return np.array(found[1]) if found and found[0] == "number" else None

    def range(self, node) -> tuple | None:
        """``(smallest, largest)`` of an integer array the node gave (an index array)."""
        found = self.values.get(node_key(node))
        if found and found[0] == "array" and len(found) == 6:
            return found[4], found[5]
        values = self.value(node)
        return (float(values.min()), float(values.max())) if values is not None and values.size else None

    def number(self, node) -> float | None:
        found = self.values.get(node_key(node))
        return found[1] if found and found[0] == "number" else None

    def length(self, node) -> int | None:
        """How many items a list, tuple or array the node gave holds (an array: along its first axis)."""
        found = self.values.get(node_key(node))
        if not found:
            return None
        if found[0] == "sequence":
            return found[1]
        if found[0] == "tuple":
            return len(found[1])
        return found[1][0] if found[0] == "array" and found[1] else None


def _description(value):
    """A recorded description checked for form (what came back is the student's process's)."""
    if not isinstance(value, (list, tuple)) or not value or not isinstance(value[0], str):
        return None
    kind = value[0]
    if kind == "array" and len(value) == 6 and isinstance(value[1], (list, tuple)) and len(value[1]) <= 32 \
            and all(isinstance(n, int) and 0 <= n < 2**62 for n in value[1]) and isinstance(value[2], str) \
            and all(isinstance(v, int) for v in value[4:]):
        return ("array", tuple(value[1]), value[2][:20], None, value[4], value[5])   # (an index array's range)
    if kind == "array" and len(value) in (3, 4) and isinstance(value[1], (list, tuple)) and len(value[1]) <= 32 \
            and all(isinstance(n, int) and 0 <= n < 2**62 for n in value[1]) and isinstance(value[2], str):
        numbers = value[3] if len(value) == 4 else None
        if isinstance(numbers, (list, tuple)) and len(numbers) == int(np.prod(value[1])) <= SMALL \
                and all(isinstance(v, (int, float)) for v in numbers):
            return ("array", tuple(value[1]), value[2][:20], np.array(numbers, float).reshape(value[1]))
        return ("array", tuple(value[1]), value[2][:20])
    if kind == "number" and len(value) == 2 and isinstance(value[1], (int, float)):
        return ("number", float(value[1]))
    if kind == "tuple" and len(value) == 2 and isinstance(value[1], (list, tuple)) and len(value[1]) <= 8 \
            and all(isinstance(v, (int, float)) for v in value[1]):
        return ("tuple", tuple(float(v) for v in value[1]))
    if kind == "sequence" and len(value) == 4 and isinstance(value[2], int) and 0 <= value[2] < 2**62:
        return ("sequence", value[2])   # (a list or tuple: its length)
    return ("other",)


_KEY = re.compile(r"\d+:\d+:\d+:\d+\Z")


def recording_of(value) -> Recording | None:
    """The :class:`Recording` in a variant's answer, or None when it is not one."""
    if not isinstance(value, dict) or not isinstance(value.get("record"), dict):
        return None
    values = {}
    for key, described in list(value["record"].items())[:100_000]:
        if isinstance(key, str) and _KEY.match(key):
            found = _description(described)
            if found is not None:
                values[key] = found
    raised = value.get("raised")
    return Recording(values, _description(value.get("returned")), raised[:60] if isinstance(raised, str) else "")


def record(trial, function: str, args, kwargs) -> Recording | None:
    """The recording of the student's ``function`` called with ``args``/``kwargs``, run in the
    trial's companion sandbox within the recordings' time (:data:`GRADING_SECONDS`); None when it cannot
    be had (kept per sandbox: a hidden check's recording is never a public one's)."""
    from .hints import code_of

    sandbox = getattr(trial, "sandbox", None)
    if sandbox is None or not hasattr(sandbox, "companion"):
        return None
    from .checks import fingerprint

    cache = sandbox.shared.setdefault("traced recordings", {})
    key = fingerprint(function, tuple(args), dict(kwargs))
    if key in cache:
        return cache[key]
    source = recording_source(code_of(trial), function)
    spent = sandbox.shared.setdefault(SPENT, [0.0])
    seconds = min(TRACE_SECONDS, GRADING_SECONDS - spent[0])
    if source is None or seconds <= 0.2:
        return None
    import time

    started = time.monotonic()
    forbid = () if getattr(trial, "forbidden_allowed", False) else tuple(trial.forbidden(function))
    try:
        outcome = sandbox.companion().call_variant(trial.lab.module, source, RECORDED, [(tuple(args), dict(kwargs))],
                                                   timeout=seconds, forbid=forbid)
    finally:
        spent[0] += time.monotonic() - started
    values = outcome.value if outcome.ok else None
    found = recording_of(values[0]) if isinstance(values, list) and len(values) == 1 else None
    cache[key] = found
    return found


# ------------------------------------------------------------------ reading it
def _shape_text(shape) -> str:
    return "(" + ", ".join(str(n) for n in shape) + ("," if len(shape) == 1 else "") + ")"


def _quote(node, limit: int = 60) -> str:
    text = ast.unparse(node)
    return f"`{text}`" if len(text) <= limit else f"`{text[:limit - 3]}...`"


def _statement_at(fn, line: int):
    """The innermost statement of ``fn`` running ``line``: its own expressions, not its body's."""
    found = None
    for node in walk(fn):
        if isinstance(node, ast.stmt) and node is not fn and node.lineno <= line <= (node.end_lineno or node.lineno):
            if found is None or node.lineno >= found.lineno and (node.end_lineno or 0) <= (found.end_lineno or 0):
                found = node
    return found


def _own_expressions(statement) -> list[ast.AST]:
    """The expressions of ``statement`` itself (a loop's header, not its body), innermost first."""
    bodies = {id(s) for field in ("body", "orelse", "finalbody", "handlers")
              for s in getattr(statement, field, []) or []}
    out = []

    def walk(node):
        for child in ast.iter_child_nodes(node):
            if id(child) in bodies or isinstance(child, (ast.FunctionDef, ast.Lambda, ast.ClassDef)):
                continue
            walk(child)
            if isinstance(child, ast.expr):
                out.append(child)
    walk(statement)
    return out


def _conditions(fn, statement) -> list[ast.AST]:
    """The ``if`` tests whose body holds ``statement`` (outermost first)."""
    found = []

    def walk(node, tests):
        for field in ("body", "orelse"):
            for child in getattr(node, field, []) or []:
                here = tests + ([node.test] if isinstance(node, ast.If) and field == "body" else [])
                if child is statement:
                    found.extend(here)
                    return True
                if walk(child, here):
                    return True
        return False
    walk(fn, [])
    return found


def _operands(node) -> list[ast.AST]:
    if isinstance(node, ast.BinOp):
        return [node.left, node.right]
    if isinstance(node, ast.Call):
        return list(node.args) + [k.value for k in node.keywords]
    if isinstance(node, ast.Compare):
        return [node.left, *node.comparators]
    return []


_SHAPES = re.compile(r"\(([\d,\s]*)\)")
_BROADCAST = re.compile(r"operands could not be broadcast together with (?:remapped )?shapes")
_INTO = re.compile(r"could not broadcast input array from shape \(([\d,\s]*)\) into shape \(([\d,\s]*)\)")
_MATMUL = re.compile(r"matmul: Input operand \d has a mismatch|shapes \([\d,\s]*\) and \([\d,\s]*\) not aligned")
_TOO_MANY_INDICES = re.compile(r"too many indices for array: array is (\d+)-dimensional")
_AMBIGUOUS = re.compile(r"truth value of an array with more than one element is ambiguous")
_RESHAPE = re.compile(r"cannot reshape array of size (\d+) into shape")
# (two of the call's arrays compared with each other: `_queryDescriptors.type() == trainDescType`; not one
# compared with a type OpenCV takes, `M0.type() == CV_32F`, where the arrays' kinds differ by design)
_OPENCV_KINDS = re.compile(r"(?:type|depth)\(\) *== *(?!CV_)[A-Za-z_]|types? do(?: not|n't) match|same type")
_OPENCV_SIZES = re.compile(r"size\(\) *== *(?!Size\b)[A-Za-z_]|[Ss]izes? of input arguments do not match|same size")
_OUT_OF_BOUNDS = re.compile(r"index (-?\d+) is out of bounds for axis (\d+) with size (\d+)")
_SEQUENCE_INDEX = re.compile(r"\b(?:list|tuple) index out of range")
_ZERO_DIVISION = re.compile(r"ZeroDivisionError|division by zero|divide by zero")
ZERO_DIVISOR = "a division by a value that is 0 on this input"
_NOT_SQUARE = re.compile(r"Last 2 dimensions of the array must be square")
_MASK_ASSIGNMENT = re.compile(r"boolean array indexing assignment (?:requires a 0 or 1-dimensional input|cannot assign)")
_MASK_INDEX = re.compile(r"boolean index did not match indexed array along (?:axis|dimension) (\d+); "
                         r"(?:size of axis|dimension) is (\d+) but (?:size of )?corresponding boolean "
                         r"(?:axis|dimension) is (\d+)")
_CAST = re.compile(r"Cannot cast ufunc '(\w+)' output from dtype\('(\w+)'\) to dtype\('(\w+)'\)")
CAST = "an in-place operation on an integer array given a float result"
WINDOW_CUT = "a window sliced past the image's edge (a negative start, or an end past it) is cut short"
ASSERTION = "the code's own assert fails on this input"
_UNPACK = re.compile(r"(?:not enough|too many) values to unpack \(expected (\d+)")
_SQUARE_ONLY = frozenset({"solve", "inv", "det", "eig", "eigvals", "cholesky", "matrix_power", "slogdet"})


def _parsed(text: str) -> tuple:
    return tuple(int(n) for n in text.replace(" ", "").split(",") if n)


def explain_raised(code, recording: Recording, fn, line: int, message: str, frames=()) -> Form | None:
    """The cause of the error ``message`` raised on ``line`` of ``fn``, from the recording (``frames``:
    the traceback's ``(file, line, function, code)``, outermost first, the innermost ``fn``'s)."""
    frames = list(frames) or [("", line, fn.name, "")]
    statement = _statement_at(fn, line)
    if statement is None:
        return None
    where = f"(line {line})"
    expressions = _own_expressions(statement)
    if _BROADCAST.search(message):
        shapes = [_parsed(s) for s in _SHAPES.findall(message.split("shapes", 1)[1])]
        return _broadcast_named(recording, expressions, shapes, where, fn, line)
    found = _INTO.search(message)
    if found:
        return _assigned_named(recording, statement, _parsed(found.group(1)), _parsed(found.group(2)), where, fn)
    if _MATMUL.search(message):
        return _product_named(recording, expressions, where)
    found = _OUT_OF_BOUNDS.search(message)
    if found:
        return _index_named(recording, expressions, *(int(g) for g in found.groups()), where)
    if _SEQUENCE_INDEX.search(message):
        return _item_named(recording, expressions, where)
    if _ZERO_DIVISION.search(message):
        return _divisor_named(recording, expressions, where)
    if _NOT_SQUARE.search(message):
        return _square_named(recording, expressions, where)
    if _MASK_ASSIGNMENT.search(message):
        return _masked_assignment_named(recording, statement, where)
    found = _MASK_INDEX.search(message)
    if found:
        return _mask_index_named(recording, expressions, fn, line, where)
    found = _CAST.search(message)
    if found:
        return _cast_named(fn, statement, found.group(2), found.group(3), where)
    found = _TOO_MANY_INDICES.search(message)
    if found:
        return _indexed_named(recording, expressions, int(found.group(1)), where, fn, statement)
    if _AMBIGUOUS.search(message):
        return _truth_named(recording, statement, expressions, where)
    found = _RESHAPE.search(message)
    if found:
        return _reshape_named(recording, expressions, int(found.group(1)), where)
    found = _UNPACK.search(message)
    if found:
        return _unpack_named(recording, statement, int(found.group(1)), where)
    if isinstance(statement, ast.Assert) and not message.strip().startswith(("ValueError", "TypeError")):
        return _assertion_named(recording, statement, where)
    if "OpenCV(" in message and _OPENCV_KINDS.search(message):
        return _opencv_named(code, recording, fn, statement, expressions, where, frames, by_type=True)
    if "OpenCV(" in message and _OPENCV_SIZES.search(message):
        return _opencv_named(code, recording, fn, statement, expressions, where, frames, by_type=False)
    return None


def _broadcast_named(recording, expressions, shapes, where, fn=None, line: int = 0) -> Form | None:
    for node in expressions:
        operands = [(o, recording.shape(o)) for o in _operands(node)]
        arrays = [(o, s) for o, s in operands if s is not None]
        if len(arrays) < 2 or sorted(s for _, s in arrays[:len(shapes)]) != sorted(shapes[:len(arrays)]):
            continue
        (a, sa), (b, sb) = arrays[:2]
        said = f"in {_quote(node)} {where}, {_quote(a)} has shape {_shape_text(sa)} and {_quote(b)} {_shape_text(sb)}"
        why = (_channels_stacked(fn, line, a, sa, b, sb) or _axis_lost_in_opencv(fn, line, a, sa, b, sb)) \
            if fn is not None else ""
        return Form(said + (why or _why_not_broadcast(a, sa, b, sb)) + _pyramid_sizes(a, sa, b, sb), MISTAKE)
    return None


# calls that make an array's last axis out of copies of one array (`np.dstack([w, w, w])`): channels
_STACKS = frozenset({"dstack", "stack", "repeat", "tile", "merge", "concatenate"})


def _channels_stacked(fn, line: int, a, sa, b, sb) -> str:
    """Where one operand is a name the function gave its last axis by stacking copies of one array
    (`w = np.dstack([w, w, w])`, `np.repeat(m[..., None], 3, axis=2)`, `cv2.merge([m] * 3)`) and the
    other has no such axis (a grey image's band): that line is told, not an axis for the other operand
    -- the copies suit colour images only, and an axis given to the grey operand would make its result
    3-channel."""
    for long_, sl, short, ss in ((a, sa, b, sb), (b, sb, a, sa)):
        if not (isinstance(long_, ast.Name) and len(sl) == len(ss) + 1 and tuple(sl[:-1]) == tuple(ss)
                and sl[-1] > 1):
            continue
        given = _last_given(fn, long_.id, line)
        if given is None or not isinstance(given[0], ast.Call) or _called_name(given[0]) not in _STACKS:
            continue
        copies = [n for n in walk(given[0]) if isinstance(n, ast.Name)
                  and n.id not in {"np", "numpy", "cv2"}]
        if len({n.id for n in copies}) != 1:
            continue   # (made of several arrays: channels of their own, not copies of one)
        return from_code(f": NumPy lines shapes up from their last axes, and {_quote(long_)} has its last axis of "
                         f"{sl[-1]} from line {given[1]} ({_quote(given[0])}): copies of one array, where "
                         f"{_quote(short)} has no such axis; make them only where {_quote(short)} has channels "
                         "(a colour image)")
    return ""


def _axis_lost_in_opencv(fn, line: int, a, sa, b, sb) -> str:
    """Where the operand short of the other's last axis was made, through the function's assignments
    (and the lists it appends to), from an array given an axis of size 1 (`m[..., None]`) and later
    passed through an OpenCV call: OpenCV returns a one-channel image as (rows, cols), so the axis
    given before the call is gone after it -- the advice to add it at the use would then break the
    levels that kept it."""
    for short, ss, long_, sl in ((a, sa, b, sb), (b, sb, a, sa)):
        if not (isinstance(short, ast.Name) and len(sl) == len(ss) + 1 and tuple(sl[:-1]) == tuple(ss)):
            continue
        made = _made_of(fn, short.id, line)
        added = [(n.lineno, n) for n in made if _axis_added(n)]
        calls = [(n.lineno, n) for n in made if isinstance(n, ast.Call) and ast.unparse(n.func).startswith("cv2.")]
        later = [(at, call) for at, call in calls if added and at > min(at_ for at_, _ in added)]
        if not later:
            continue
        (at_axis, axis), (at_call, call) = min(added, key=lambda x: x[0]), min(later, key=lambda x: x[0])
        return from_code(f": NumPy lines shapes up from their last axes, so {_quote(short)} has no axis for the "
                         f"last axis of {_quote(long_)}. Line {at_axis} gives an array an axis of size 1 "
                         f"({_quote(axis)}), but `{ast.unparse(call.func)}` (line {at_call}) returns a one-channel "
                         "image as (rows, cols), without that axis (OpenCV drops it): give the axis after the "
                         "OpenCV calls, where the arrays are combined")
    return ""


def _axis_added(node) -> bool:
    """`x[..., None]`, `x[:, :, np.newaxis]`, `np.expand_dims(x, ...)`: an axis of size 1 given to an array."""
    if isinstance(node, ast.Subscript):
        parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
        return any(isinstance(p, ast.Constant) and p.value is None or ast.unparse(p) in ("np.newaxis", "numpy.newaxis")
                   for p in parts)
    return isinstance(node, ast.Call) and ast.unparse(node.func) in ("np.expand_dims", "numpy.expand_dims")


def _made_of(fn, name: str, line: int, depth: int = 5) -> list[ast.AST]:
    """The expressions ``name`` was made from before ``line``: the values assigned to it, appended or
    added to it, and, in turn, to the names those values read (``depth`` steps back, in ``fn``)."""
    statements = [n for n in _own_nodes(fn) if getattr(n, "lineno", line) < line]
    found, names, frontier = [], {name}, [name]
    for _ in range(depth):
        values = []
        for statement in statements:
            if isinstance(statement, ast.Assign):
                values += [v for t in statement.targets for n in frontier
                           for v in [_element_for(t, statement.value, n)] if v is not None]
            elif isinstance(statement, ast.AugAssign) and isinstance(statement.target, ast.Name) \
                    and statement.target.id in frontier:
                values.append(statement.value)
            elif isinstance(statement, ast.Call) and isinstance(statement.func, ast.Attribute) \
                    and statement.func.attr in ("append", "extend", "insert") \
                    and isinstance(statement.func.value, ast.Name) and statement.func.value.id in frontier:
                values += statement.args
        nodes = [n for v in values for n in walk(v)]
        found += nodes
        frontier = sorted({n.id for n in nodes if isinstance(n, ast.Name)} - names - {"np", "numpy", "cv2"})
        names.update(frontier)
        if not frontier or len(found) > 2000:
            break
    return found


def _pyramid_sizes(a, sa, b, sb) -> str:
    """A pyramid level brought back up by cv2.pyrUp without ``dstsize`` beside the level it is added to:
    pyrUp doubles each side, one too many for an odd side."""
    for up, su, other, so in ((a, sa, b, sb), (b, sb, a, sa)):
        if isinstance(up, ast.Call) and ast.unparse(up.func).endswith("pyrUp") \
                and not any(k.arg == "dstsize" for k in up.keywords) and len(up.args) < 3 \
                and len(su) == len(so) >= 2 and all(0 <= m - n <= 1 for m, n in zip(su[:2], so[:2])):
            finer = ast.unparse(other)   # (written as the student wrote it, when short and one term)
            size = f"`dstsize=({finer}.shape[1], {finer}.shape[0])`" \
                if isinstance(other, (ast.Name, ast.Subscript, ast.Attribute)) and len(finer) <= 30 else \
                "`dstsize` = (its width, its height)"
            # measured: the two shapes at the raising line, one side one pixel longer after pyrUp
            return measured(f"; cv2.pyrUp doubles each side of the coarser level, one pixel too many where the "
                            f"finer level's side is odd: give it the finer level's size, {size}")
    return ""


def _why_not_broadcast(a, sa, b, sb) -> str:
    short, long_, ss, sl = (a, b, sa, sb) if len(sa) < len(sb) else (b, a, sb, sa)
    if len(ss) < len(sl) and tuple(sl[:len(ss)]) == tuple(ss):
        extra = len(sl) - len(ss)
        axes = 'axis' if extra == 1 else f'{extra} axes'
        if all(n == 1 for n in sl[len(ss):]):   # (an axis of 1 added to the longer one: which one is right?)
            return (f": NumPy lines shapes up from their last axes, and {_quote(long_)} has an {axes} of size 1 "
                    f"at the end that {_quote(short)} has not (was it added to the one that does not need it?)")
        return (f": NumPy lines shapes up from their last axes, so {_quote(short)} has no axis for the last "
                f"{axes} of {_quote(long_)} ({_quote(short)[:-1]}[..., None]` gives it one)")
    if len(ss) < len(sl) and all(m == n or 1 in (m, n) for m, n in zip(tuple(ss) + (1,) * (len(sl) - len(ss)), sl)):
        # (its axes meant as the longer one's first ones: `fs[:, None] * xy[None]`, (3, 1) and (1, 9, 2))
        extra = len(sl) - len(ss)
        return (f": NumPy lines shapes up from their last axes; with {'an axis' if extra == 1 else f'{extra} axes'} "
                f"of size 1 added at its end, shape {_shape_text(tuple(ss) + (1,) * extra)}, {_quote(short)} would "
                f"line up with {_quote(long_)} axis by axis ({_quote(short)[:-1]}{'[..., None]' * extra}`)")
    if len(sa) == len(sb):
        differ = [i for i, (m, n) in enumerate(zip(sa, sb)) if m != n and 1 not in (m, n)]
        if differ:
            i = differ[0]
            return f": they differ on axis {i} ({sa[i]} and {sb[i]}), where neither is 1"
    return ": NumPy lines shapes up from their last axes"


def _assigned_named(recording, statement, given, into, where, fn=None) -> Form | None:
    if not isinstance(statement, (ast.Assign, ast.AugAssign)):
        return None
    targets = statement.targets if isinstance(statement, ast.Assign) else [statement.target]
    for target in targets:
        if not isinstance(target, ast.Subscript):
            continue
        for bound in _slice_bounds(target.slice):
            value = recording.number(bound)
            if value is not None and value < 0 and not _written_negative(bound):
                return Form(f"{_quote(bound)} is {value:g} here {where}, and a negative slice bound "
                                     f"counts from the end of the axis: {_quote(target)} is then "
                                     f"{_shape_text(into)}, for a value of shape {_shape_text(given)}", MISTAKE)
        said = f"{_quote(target)} {where} has shape {_shape_text(into)} and is given a value of shape {_shape_text(given)}"
        bounds = [(b, recording.number(b)) for b in _slice_bounds(target.slice)]
        known = [f"{_quote(b)} = {v:g}" for b, v in bounds if v is not None and not isinstance(b, ast.Constant)]
        said += f" ({', '.join(known[:4])})" if known else ""
        for sliced in (n for n in walk(statement.value) if isinstance(n, ast.Subscript)):
            # (the value's own slice given a negative bound: `right[:, :width - d]` with d past the width keeps
            # all but the last columns, where none were meant)
            for bound in _slice_bounds(sliced.slice):
                value = recording.number(bound)
                if value is not None and value < 0 and not _written_negative(bound):
                    return Form(f"{said}: {_quote(bound)} is {value:g} here, and a negative slice bound counts from "
                                f"the end of the axis, so {_quote(sliced)} keeps entries where none were meant", MISTAKE)
        # (an array made without the value's last axis -- a grey canvas for a colour image: where it was made)
        made = _last_given(fn, target.value.id, statement.lineno) \
            if fn is not None and isinstance(target.value, ast.Name) and len(given) > len(into) else None
        base = recording.shape(target.value)
        last_item = isinstance(target.slice, ast.Tuple) and len(target.slice.elts) == 2 \
            and isinstance(target.slice.elts[0], ast.Constant) and target.slice.elts[0].value is Ellipsis
        if last_item and base is not None and len(base) == 2:
            # (a loop over the channels, `for c in range(image.shape[-1])`, given a grey (H, W) image: the last
            # axis is the width, and `out[..., c]` a column)
            # (measured: the recording's shape of the array written into, and the item index after `...`)
            return Form(said + measured(f"; {_quote(target.value)} has shape {_shape_text(base)}, a grey image's "
                                        f"(H, W): its last axis is the width, so {_quote(target)} is a column, not a "
                                        "channel (a loop over `range(image.shape[-1])` runs over the columns "
                                        "there); treat a grey image apart"), MISTAKE)
        if made is not None:
            axes = len(base) if base is not None else len(into)
            said += f"; {_quote(target.value)} comes from {_quote(made[0])} (line {made[1]}), of {axes} axes " \
                    f"where the value has {len(given) + axes - len(into)}"
        return Form(said, MISTAKE)
    return None


def _slice_bounds(index) -> list[ast.AST]:
    parts = index.elts if isinstance(index, ast.Tuple) else [index]
    return [b for p in parts if isinstance(p, ast.Slice) for b in (p.lower, p.upper) if b is not None]


def _written_negative(node) -> bool:
    return isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) or \
        isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and node.value < 0


def _product_named(recording, expressions, where) -> Form | None:
    for node in expressions:
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult) or \
                isinstance(node, ast.Call) and _called_name(node) in ("dot", "matmul"):
            arrays = [(o, recording.shape(o)) for o in _operands(node)]
            if len(arrays) == 2 and all(s for _, s in arrays):
                (a, sa), (b, sb) = arrays
                inner = sb[-2] if len(sb) >= 2 else sb[0]
                return Form(f"in {_quote(node)} {where}, {_quote(a)} has shape {_shape_text(sa)} and "
                                     f"{_quote(b)} {_shape_text(sb)}: a product needs the last size of the first "
                                     f"({sa[-1]}) to equal the {'first' if len(sb) < 2 else 'next-to-last'} of the "
                                     f"second ({inner})", MISTAKE)
    return None


def _called_name(call) -> str:
    func = call.func
    return func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""


def _index_named(recording, expressions, index, axis, size, where) -> Form | None:
    for node in expressions:
        if not isinstance(node, ast.Subscript):
            continue
        parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
        for part in parts:
            shape = recording.shape(node.value)
            if isinstance(part, ast.Constant) and part.value == index and shape and axis < len(shape) \
                    and shape[axis] == size:
                # (a fixed index past an axis the input made short -- empty: a null space of no vectors)
                entries = "no entries at all" if size == 0 else f"only {size} entries, numbered 0 to {size - 1}"
                said = f"{_quote(node.value)} has shape {_shape_text(shape)} in {_quote(node)} {where}: its axis " \
                       f"{axis} has {entries} on this input"
                if size == 0 and isinstance(node.value, ast.Call) and _called_name(node.value) == "null_space":
                    # (SciPy's null_space keeps the singular vectors of singular values below a tolerance: a
                    # least-squares system of noisy data has none)
                    said += from_code(" -- scipy.linalg.null_space keeps only exact null vectors, and a system "
                                      "of noisy equations has full rank: the least-squares solution is the last "
                                      "row of Vt from np.linalg.svd")
                return Form(said, INDEX)
            if isinstance(part, (ast.Slice, ast.Constant)):
                continue
            span = recording.range(part) if recording.shape(part) else None
            values = recording.value(part)
            holds = span is not None and (values is None or bool(np.any(values == index))) \
                and (span[0] <= index <= span[1])
            if recording.number(part) == index or holds:
                shape = recording.shape(node.value)
                of = f" of {_quote(node.value)} (shape {_shape_text(shape)})" if shape else ""
                said = f"holds {index} (its values go from {span[0]:g} to {span[1]:g})" if holds else f"is {index}"
                return Form(f"{_quote(part)} {said} in {_quote(node)} {where}: axis {axis}{of} "
                            f"has {size} entries, numbered 0 to {size - 1}", INDEX)
    return None


def _square_named(recording, expressions, where) -> Form | None:
    """A matrix that is not square given to a solve or an inverse (NumPy's error names no operand)."""
    for node in expressions:
        if not (isinstance(node, ast.Call) and node.args and _called_name(node) in _SQUARE_ONLY):
            continue
        matrix = node.args[0]
        shape = recording.shape(matrix)
        if shape is None or len(shape) < 2 or shape[-1] == shape[-2]:
            continue
        said = (f"in {_quote(node)} {where}, {_quote(matrix)} has shape {_shape_text(shape)}: "
                f"`{_called_name(node)}` needs a square matrix")
        if _called_name(node) in ("solve", "inv") and shape[-2] > shape[-1]:
            said += measured(f" -- {shape[-2]} equations in {shape[-1]} unknowns are solved in the least-squares "
                             "sense, by np.linalg.lstsq")   # (measured: the recording's rows and columns)
        return Form(said, MISTAKE)
    return None


def _masked_assignment_named(recording, statement, where) -> Form | None:
    """`out[mask] = expr` where ``expr`` is as large as the whole array, not one value per selected entry:
    the right side's array of the mask's shape, which the mask is to select too."""
    if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1
            and isinstance(statement.targets[0], ast.Subscript) and isinstance(statement.targets[0].slice, ast.Name)):
        return None
    mask = statement.targets[0].slice
    shape, value = recording.shape(mask), recording.shape(statement.value)
    if shape is None or value is None or tuple(value) != tuple(shape):
        return None
    whole = [node for node in walk(statement.value)
             if isinstance(node, ast.Name) and recording.shape(node) is not None and tuple(recording.shape(node)) == tuple(shape)]
    # (measured: the recording's shapes of the mask, the right side and the array named in it)
    select = measured(f": select the same entries on the right too, `{whole[0].id}[{mask.id}]`") if whole else \
        measured(f": select the same entries on the right too, with `[{mask.id}]`")
    return Form(f"in {_quote(statement)} {where}, the right side has shape {_shape_text(value)}, a value for every entry "
                f"of the array, where `{_quote(statement.targets[0])[1:-1]}` takes one value per entry {_quote(mask)} "
                f"selects{select}", MISTAKE)


def _mask_index_named(recording, expressions, fn, line: int, where) -> Form | None:
    """`window[mask]` with the mask's shape not the array's: the shapes, and where the array is a slice of
    another made before (`window = out[cy - r:cy + r + 1, cx - r:cx + r + 1]`), the bound that cut it -- a
    start below 0 counts from the axis' end, an end past the axis stops at it."""
    for node in expressions:
        if not isinstance(node, ast.Subscript):
            continue
        shape, mask = recording.shape(node.value), recording.shape(node.slice)
        if shape is None or mask is None or recording.dtype(node.slice) != "bool" or tuple(shape[:len(mask)]) == tuple(mask):
            continue
        said = (f"in {_quote(node)} {where}, {_quote(node.value)} has shape {_shape_text(shape)} and the mask "
                f"{_quote(node.slice)} {_shape_text(mask)}")
        given = _last_given(fn, node.value.id, line) if isinstance(node.value, ast.Name) else None
        sliced = given[0] if given is not None and isinstance(given[0], ast.Subscript) else None
        whole = recording.shape(sliced.value) if sliced is not None else None
        parts = (sliced.slice.elts if isinstance(sliced.slice, ast.Tuple) else [sliced.slice]) if sliced is not None else []
        for axis, part in enumerate(parts):
            if not isinstance(part, ast.Slice) or whole is None or axis >= len(whole):
                continue
            start = recording.number(part.lower) if part.lower is not None else None
            stop = recording.number(part.upper) if part.upper is not None else None
            if start is not None and start < 0:
                return Form(said + f": {_quote(node.value)} is {_quote(sliced)} (line {given[1]}), where "
                            f"{_quote(part.lower)} is {int(start)}" + measured(
                                ": a slice's start below 0 counts from the axis' end, so the window is cut (here "
                                "to nothing); clip the window to the image, and the mask with it"), WINDOW_CUT)
            if stop is not None and stop > whole[axis]:
                return Form(said + f": {_quote(node.value)} is {_quote(sliced)} (line {given[1]}), where "
                            f"{_quote(part.upper)} is {int(stop)} on an axis of {whole[axis]}" + measured(
                                ": a slice stops at the axis' end, so the window is cut short; clip the window to "
                                "the image, and the mask with it"), WINDOW_CUT)
        # (the arrays of the function as long as the mask is, which it was likely made for: `in1[front]` where
        # `matched1[front]` indexes the matches from before RANSAC kept its inliers)
        fitting = list(dict.fromkeys(
            n.id for n in sorted((n for n in walk(fn) if isinstance(n, ast.Name)), key=lambda n: (n.lineno, n.col_offset))
            if n.id not in (getattr(node.value, "id", None), getattr(node.slice, "id", None))
            and (recording.shape(n) or (None,))[0] == mask[0] and tuple(recording.shape(n)[1:]) == tuple(shape[1:])))[:3]
        if fitting:
            names = ", ".join(f"`{name}`" for name in fitting[:-1]) + (" and " if len(fitting) > 1 else "") + f"`{fitting[-1]}`"
            said += measured(f"; {names} {'is' if len(fitting) == 1 else 'are'} of shape "
                             f"{_shape_text((mask[0],) + tuple(shape[1:]))}, as long as the mask")
        return Form(said, MISTAKE)
    return None


def _item_named(recording, expressions, where) -> Form | None:
    """A list or tuple indexed past its end (Python's error says neither the index nor the length)."""
    for node in expressions:
        if not isinstance(node, ast.Subscript) or isinstance(node.slice, (ast.Slice, ast.Tuple)):
            continue
        size, index = recording.length(node.value), recording.number(node.slice)
        if size is None and isinstance(node.value, (ast.List, ast.Tuple)) \
                and not any(isinstance(item, ast.Starred) for item in node.value.elts):
            size = len(node.value.elts)   # (a literal table: its length is written out)
        if size is None or index is None or index != int(index) or -size <= index < size:
            continue
        numbered = f"numbered 0 to {size - 1}" if size else "none at all"
        # (an index counted in steps -- `angle // 90` -- and never wrapped: the table is meant to be gone round)
        counted = any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.FloorDiv) for n in walk(node.slice)) \
            and not any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.Mod) for n in walk(node.slice))
        wraps = f"; a count of steps goes round a table of {size} taken `% {size}`" if counted and size else ""
        return Form(f"{_quote(node.slice)} is {int(index)} in {_quote(node)} {where}: {_quote(node.value)} holds "
                    f"{size} item{'s' if size != 1 else ''}, {numbered}{wraps}", INDEX)
    return None


def _cast_named(fn, statement, result: str, kept: str, where) -> Form | None:
    """An in-place operation (`offset -= R @ centre`) on an array whose dtype cannot hold its result: NumPy keeps
    the array's dtype in place and refuses to cast the float result into integers. Said from the error's own
    dtypes, with where the array was made (the student's last assignment to it)."""
    if not isinstance(statement, ast.AugAssign) or not isinstance(statement.target, ast.Name):
        return None
    name = statement.target.id
    said = (f"{_quote(statement)} {where} writes a {result} result into `{name}`, an array of {kept}: an in-place "
            f"operation keeps the array's dtype, and NumPy will not cast {result} values into it")
    made = _last_given(fn, name, statement.lineno)
    if made is not None:
        said += f"; `{name}` comes from {_quote(made[0])} (line {made[1]})"
        origin, steps = made[0], 0
        while steps < 3 and isinstance(origin, ast.Call) and isinstance(origin.func, ast.Attribute) and origin.func.attr == "copy" \
                and isinstance(origin.func.value, ast.Name):
            # (a copy of another local: where that one was made, the dtype's source)
            earlier = _last_given(fn, origin.func.value.id, made[1])
            if earlier is None:
                break
            said += f", a copy of {_quote(earlier[0])} (line {earlier[1]})"
            made, origin, steps = earlier, earlier[0], steps + 1   # (a few copies back: each step reads the def)
    return Form(said + from_code(": make it a float array where it is made (`dtype=float`)"), CAST)


def _divisor_named(recording, expressions, where) -> Form | None:
    """A Python number divided by 0 (ZeroDivisionError: its message names no value): which divisor is 0; an entry
    on a diagonal (`A[k][k]`, `A[k, k]`) is the pivot of an elimination written without exchanging rows."""
    for node in expressions:
        if not (isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Div, ast.FloorDiv, ast.Mod))) \
                or recording.number(node.right) != 0:
            continue
        said = f"{_quote(node.right)} is 0 in {_quote(node)} {where}"
        if _on_a_diagonal(node.right):
            said += measured(": a pivot of your elimination is 0 -- bring up the row with the largest entry of the "
                             "column first (partial pivoting), or solve with np.linalg.solve")
        return Form(said, ZERO_DIVISOR)
    return None


def _on_a_diagonal(node) -> bool:
    """`A[k][k]` or `A[k, k]`: the same index on both axes."""
    if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2:
        first, second = node.slice.elts
        return ast.dump(first) == ast.dump(second)
    return isinstance(node, ast.Subscript) and isinstance(node.value, ast.Subscript) \
        and not isinstance(node.slice, (ast.Slice, ast.Tuple)) and ast.dump(node.slice) == ast.dump(node.value.slice)


def _indexed_named(recording, expressions, ndim: int, where, fn=None, statement=None) -> Form | None:
    for node in expressions:
        if isinstance(node, ast.Subscript):
            shape = recording.shape(node.value)
            parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
            indexed = sum(1 for p in parts if not (isinstance(p, ast.Constant) and p.value in (None, Ellipsis)))
            if shape is not None and len(shape) == ndim and indexed > ndim:
                return Form(f"in {_quote(node)} {where}, {_quote(node.value)} has shape {_shape_text(shape)}: "
                            f"{ndim} ax{'is' if ndim == 1 else 'es'}, indexed with {indexed}"
                            + _let_in_by(fn, statement, node.value, shape), MISTAKE)
    return None


def _let_in_by(fn, statement, array, shape) -> str:
    """The test of the ``if`` that sent this array to a line indexing more axes than it has, when the test
    reads one of the array's sizes (`x.shape[-1] == 2`) and the branch does not set it before that line: an
    array of one axis and that many values passes it too (told with the number of axes to test instead);
    "" otherwise."""
    if fn is None or statement is None or not isinstance(array, ast.Name):
        return ""
    parents = {id(child): parent for parent in walk(fn) for child in ast.iter_child_nodes(parent)}
    branches, node = [], statement   # (the ifs whose body holds the statement, innermost first)
    while id(node) in parents:
        parent = parents[id(node)]
        if isinstance(parent, ast.If) and any(node is s for s in parent.body):
            branches.append(parent)
        node = parent
    for branch in branches:
        # (the array tested is the one indexed only where the branch sets it nowhere before that line)
        before = [s for s in branch.body if s.lineno < statement.lineno]
        if any(isinstance(n, ast.Name) and n.id == array.id and isinstance(n.ctx, ast.Store)
               for s in before for n in walk(s)):
            continue
        for size in walk(branch.test):
            if isinstance(size, ast.Subscript) and isinstance(size.value, ast.Attribute) and size.value.attr == "shape" \
                    and isinstance(size.value.value, ast.Name) and size.value.value.id == array.id \
                    and isinstance(size.slice, (ast.Constant, ast.UnaryOp)):
                return (f"; it got there because {_quote(branch.test)} (line {branch.lineno}) holds for it: an array of "
                        f"shape {_shape_text(shape)} passes that test too -- test its number of axes, `{array.id}.ndim`")
    return ""


def _truth_named(recording, statement, expressions, where) -> Form | None:
    """An array where one truth value is asked: an ``if``/``while`` test, ``and``/``or``/``not``."""
    asked = [statement.test] if isinstance(statement, (ast.If, ast.While, ast.Assert)) else []
    asked += [v for node in expressions if isinstance(node, ast.BoolOp) for v in node.values]
    asked += [node.operand for node in expressions if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not)]
    asked += [node.test for node in expressions if isinstance(node, ast.IfExp)]
    for node in asked:
        shape = recording.shape(node)
        if shape is not None and int(np.prod(shape)) > 1:
            return Form(f"{_quote(node)} {where} is an array of shape {_shape_text(shape)} where one truth value is "
                        + measured("asked (`if`, `and`, `or`, `not` take one: an element-wise test needs `&`, `|`, `~`, "
                                   "`np.where` or a mask; a question about all of them, `.all()` or `.any()`)"), TRUTH)
    return None


def _unpack_named(recording, statement, expected: int, where) -> Form | None:
    """`h, w = image.shape[:-1]` given another number of values than names: how many the value holds here,
    and where it is a slice of a shape, the array's own shape (a grey image's (H, W) has no channel axis)."""
    targets = statement.targets if isinstance(statement, ast.Assign) else \
        [statement.target] if isinstance(statement, ast.For) else []
    value = statement.value if isinstance(statement, ast.Assign) else getattr(statement, "iter", None)
    if not targets or not isinstance(targets[0], (ast.Tuple, ast.List)) or value is None:
        return None
    count = recording.length(value)
    if count is None or count == expected:
        return None
    found = recording.values.get(node_key(value))
    shown = f": {_quote(value)} is ({', '.join(f'{v:g}' for v in found[1])}{',' if len(found[1]) == 1 else ''})" \
        if found and found[0] == "tuple" else f" ({_quote(value)})"
    said = (f"{_quote(statement if isinstance(statement, ast.Assign) else targets[0])} {where} unpacks into "
            f"{expected} names a value of {count} item{'s' if count != 1 else ''} here{shown}")
    sliced = value.value if isinstance(value, ast.Subscript) else value
    if isinstance(sliced, ast.Attribute) and sliced.attr == "shape":
        shape = recording.shape(sliced.value)
        if shape is not None:
            said += (f"; {_quote(sliced.value)} has shape {_shape_text(shape)}"
                     + (", a grey image's (H, W), with no channel axis" if len(shape) == 2 else ""))
    return Form(said, MISTAKE)


def _assertion_named(recording, statement, where) -> Form | None:
    """The student's own `assert` that failed on this input, with the values its test compared."""
    test = statement.test
    parts = [test.left, *test.comparators] if isinstance(test, ast.Compare) else [test]
    known = [f"{_quote(part)} is {recording.number(part):g}" for part in parts
             if not isinstance(part, ast.Constant) and recording.number(part) is not None]
    return Form(f"your own `assert {' '.join(ast.unparse(test).split())}` {where} fails"
                + (f" ({', '.join(known[:3])})" if known else ""), ASSERTION)


def _reshape_named(recording, expressions, size: int, where) -> Form | None:
    for node in expressions:
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "reshape":
            numpy_function = isinstance(node.func.value, ast.Name) and node.func.value.id in ("np", "numpy")
            source = (node.args[0] if node.args else None) if numpy_function else node.func.value
            shape = recording.shape(source) if source is not None else None
            if shape is not None and int(np.prod(shape)) == size:
                return Form(f"in {_quote(node)} {where}, {_quote(source)} has shape {_shape_text(shape)} "
                            f"({size} values)", MISTAKE)
    return None


def _opencv_named(code, recording, fn, statement, expressions, where, frames, by_type: bool) -> Form | None:
    """OpenCV asserted that two arrays agree in type (or in size): the arrays the call on the line was
    given, when they do not, and where each came from."""
    for node in expressions:
        if not isinstance(node, ast.Call):
            continue
        arrays = [(o, recording.shape(o), recording.dtype(o)) for o in node.args]
        arrays = [a for a in arrays if a[1] is not None]
        kinds = {dtype if by_type else shape for _, shape, dtype in arrays}
        if len(arrays) < 2 or len(kinds) < 2:
            continue
        given = ", ".join(f"{_quote(o)} {dtype} of shape {_shape_text(s)}" for o, s, dtype in arrays[:3])
        said = f"{_quote(node)} {where} was given {given}: arrays of different {'types' if by_type else 'sizes'}"
        origins = [_origin(code, fn, o, statement, frames) for o, _, _ in arrays[:3]]
        origins = [o for o in origins if o]
        if len(origins) >= 2:
            said += " (" + "; ".join(origins) + ")"
        return Form(said, KINDS)
    return None


def _origin(code, fn, node, before, frames) -> str:
    """``"`des2` comes from `_detect(img2)` (line 40)"``: the value a name was last given before a
    statement, followed through tuple unpacking and, for a parameter, to the call in the frame that
    called ``fn`` (``frames``: the traceback's, outermost first)."""
    if not isinstance(node, ast.Name):
        return ""
    expression, line, depth = node, before.lineno, len(frames) - 1
    for _ in range(6):
        if not isinstance(expression, ast.Name):
            break
        given = _last_given(fn, expression.id, line)
        if given is not None:
            expression, line = given
            continue
        caller = _caller_argument(code, fn, expression.id, frames, depth)
        if caller is None:
            break
        fn, expression, line, depth = caller
    if expression is node:
        return ""
    return f"{_quote(node)} comes from {_quote(expression)} (line {line})"


def _last_given(fn, name: str, line: int):
    """``(expression, line)`` of the last assignment to ``name`` in ``fn`` before ``line`` (the element
    of a tuple assigned to it when the value is written as one), or None."""
    found = None
    for statement in _own_nodes(fn):
        if isinstance(statement, ast.Assign) and statement.lineno < line:
            for target in statement.targets:
                value = _element_for(target, statement.value, name)
                if value is not None and (found is None or statement.lineno > found[1]):
                    found = (value, statement.lineno)
    return found


def _element_for(target, value, name):
    if isinstance(target, ast.Name):
        return value if target.id == name else None
    if isinstance(target, (ast.Tuple, ast.List)):
        for i, part in enumerate(target.elts):
            if isinstance(value, (ast.Tuple, ast.List)) and len(value.elts) == len(target.elts):
                found = _element_for(part, value.elts[i], name)
            else:
                found = value if name in {n.id for n in walk(part) if isinstance(n, ast.Name)} else None
            if found is not None:
                return found
    return None


def _caller_argument(code, fn, name: str, frames, depth: int):
    """``(caller def, argument expression, line, depth)`` for the parameter ``name`` of ``fn``, from the
    call in the traceback frame that called it; None when that frame or call is not there."""
    parameters = [a.arg for a in fn.args.posonlyargs + fn.args.args]
    if depth < 1 or frames[depth][2] != fn.name or name not in parameters + [a.arg for a in fn.args.kwonlyargs]:
        return None
    _, line, caller_name, _ = frames[depth - 1]
    caller = code.functions.get(caller_name)
    if caller is None:
        return None
    for call in _own_nodes(caller):
        if isinstance(call, ast.Call) and isinstance(call.func, ast.Name) and call.func.id == fn.name \
                and call.lineno <= line <= (call.end_lineno or call.lineno):
            keyword = [k.value for k in call.keywords if k.arg == name]
            index = parameters.index(name) if name in parameters else len(call.args)
            argument = keyword[0] if keyword else call.args[index] if index < len(call.args) \
                and not any(isinstance(a, ast.Starred) for a in call.args[:index + 1]) else None
            return (caller, argument, call.lineno, depth - 1) if argument is not None else None
    return None


# ------------------------------------------------------------------ a wrong shape
def explain_shape(code, recording: Recording, function: str, got: tuple, expected: tuple,
                  item: str = "") -> Form | None:
    """Where the answer of shape ``got`` (``expected`` asked) was given that shape: the first expression on
    the returned value's way that makes ``got`` from operands that do not have it."""
    fn = code.functions.get(function)
    if fn is None or recording.returned is None:
        return None
    if recording.returned[:2] == ("array", tuple(got)):
        statement = _returning(fn, recording, got)
        node = statement.value if statement is not None else None
    elif recording.returned[0] == "sequence":   # an item of a tuple returned (`return e1, e2`)
        statement, node = _returning_item(fn, recording, got, item)
    else:
        return None
    if node is None:
        return None
    seen = 0
    while seen < 16:
        seen += 1
        helper = _helper(code, fn, node)
        inner = _returning(helper, recording, got) if helper is not None and helper is not fn else None
        if inner is not None:   # a helper of the module made it: on into the helper
            fn, statement, node = helper, inner, inner.value
            continue
        if isinstance(node, ast.Name):
            assigned = _assignment_giving(fn, node, recording, got, statement)
            if assigned is None:
                return None
            statement, node = assigned, assigned.value
            continue
        same = [o for o in _children(node) if recording.shape(o) == tuple(got)]
        if same:
            node = same[0]
            continue
        # (a row taken from an operand whose two axes are exchanged: `result[0]` of a (2, 1) `result`, where its
        # (1, 2) would give the (2,) asked -- the layout came with the operand, followed there)
        source = recording.shape(node.value) if isinstance(node, ast.Subscript) and _integer(node.slice) else None
        if source is not None and len(source) == 2 and source[0] != source[1] \
                and (source[1],) == tuple(got) and (source[0],) == tuple(expected):
            node, got, expected = node.value, source, source[::-1]
            continue
        # (an operand that already has the wrong sizes on every axis that is wrong, the others changed here:
        # `X[:, :3]` of an (4, 4) X, where (N, 3) is asked -- the wrong axis came with X, followed there)
        wrong = [i for i, (g, e) in enumerate(zip(got, expected)) if g != e] if len(got) == len(expected) else []
        carried = [o for o in _children(node) for shape in [recording.shape(o)]
                   if wrong and shape is not None and len(shape) == len(got) and all(shape[i] == got[i] for i in wrong)]
        if carried and not (isinstance(node, ast.Subscript)   # (a crop of that axis made it: told here)
                            and _bounded_where_short(node.slice, recording.shape(carried[0]), expected)):
            node = carried[0]
            carried_shape = recording.shape(node)
            expected = tuple(expected[i] if i in wrong else carried_shape[i] for i in range(len(got)))
            got = carried_shape
            continue
        return _made_here(fn, recording, node, statement, got, expected)
    return None


def _returning(fn, recording, got):
    """``fn``'s one ``return`` (not a nested def's) whose value the recording shows with shape ``got``."""
    returns = [r for r in _own_nodes(fn) if isinstance(r, ast.Return) and r.value is not None
               and recording.shape(r.value) == tuple(got)]
    return returns[0] if len(returns) == 1 else None


def _returning_item(fn, recording, got, name: str = ""):
    """``(statement, item)``: ``fn``'s one ``return`` of a tuple whose item ``name`` (the API's: written so, or
    the n-th for a name ending in n, ``e2``) the recording shows with shape ``got``, or its one item of that
    shape ((None, None) otherwise)."""
    returns = [r for r in _own_nodes(fn) if isinstance(r, ast.Return) and isinstance(r.value, ast.Tuple)]
    found = [(r, item) for r in returns for item in r.value.elts if recording.shape(item) == tuple(got)]
    if len(returns) != 1 or not found:
        return None, None
    items = returns[0].value.elts
    named = [pair for pair in found if ast.unparse(pair[1]) == name]
    if not named and name[-1:].isdigit() and 0 < int(name[-1]) <= len(items):
        named = [pair for pair in found if pair[1] is items[int(name[-1]) - 1]]
    chosen = named or found
    return chosen[0] if len(chosen) == 1 else (None, None)


def _own_nodes(fn):
    """The nodes of ``fn``'s body, not those of the defs nested in it."""
    todo = list(ast.iter_child_nodes(fn))
    while todo:
        node = todo.pop()
        yield node
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            todo.extend(ast.iter_child_nodes(node))


def _helper(code, fn, node):
    """The def a call ``helper(...)`` runs: one nested in ``fn``, or a function of the module."""
    if not isinstance(node, ast.Call) or not isinstance(node.func, ast.Name):
        return None
    return _nested_defs(fn).get(node.func.id) or code.functions.get(node.func.id)


@functools.lru_cache(maxsize=64)
def _nested_defs(fn) -> dict:
    """The defs nested in ``fn`` by name (the last of a name wins), read once per def: asked for every
    call the reading meets, a walk each time would make it quadratic in the function's size."""
    return {d.name: d for d in sorted((d for d in _own_nodes(fn) if isinstance(d, ast.FunctionDef)),
                                      key=lambda d: d.lineno)}


def _children(node) -> list[ast.AST]:
    if isinstance(node, ast.Subscript):
        return [node.value]
    if isinstance(node, ast.Attribute):
        return [node.value]
    if isinstance(node, ast.Call):
        receiver = [node.func.value] if isinstance(node.func, ast.Attribute) else []
        return receiver + list(node.args) + [k.value for k in node.keywords]
    if isinstance(node, ast.UnaryOp):
        return [node.operand]
    return _operands(node)


def _assignment_giving(fn, name, recording, got, before):
    """The latest assignment of ``name`` before ``before`` whose value the recording shows with shape ``got``."""
    found = None
    for statement in walk(fn):
        if isinstance(statement, (ast.Assign, ast.AnnAssign)) and statement.value is not None \
                and statement.lineno < before.lineno \
                and any(isinstance(t, ast.Name) and t.id == name.id
                        for t in (statement.targets if isinstance(statement, ast.Assign) else [statement.target])) \
                and recording.shape(statement.value) == tuple(got):
            if found is None or statement.lineno > found.lineno:
                found = statement
    return found


def _stack_transposed(fn, arrays, line: int) -> str:
    """Where an operand of three or more axes is a name last given as ``x.T``: on a stack of matrices
    ``.T`` reverses every axis, the stack's own axis moved last, not each matrix transposed."""
    for operand, shape in arrays:
        if not (isinstance(operand, ast.Name) and len(shape) >= 3):
            continue
        given = _last_given(fn, operand.id, line)
        if given is not None and isinstance(given[0], ast.Attribute) and given[0].attr == "T":
            # measured: the recorded shape (3+ axes); read: the assignment's `.T`
            return measured(f": {_quote(operand)} comes from {_quote(given[0])} (line {given[1]}), and on a stack of "
                            f"matrices .T reverses every axis (here to {_shape_text(shape)}): the stack's axis goes "
                            "last; np.swapaxes(x, -1, -2) transposes each matrix")
    return ""


def _integer(index) -> bool:
    """Whether an index is one whole number written out (`x[0]`, `x[-1]`)."""
    if isinstance(index, ast.UnaryOp) and isinstance(index.op, ast.USub):
        index = index.operand
    return isinstance(index, ast.Constant) and type(index.value) is int


def _bounded_where_short(index, source, expected) -> bool:
    """Whether the index gives each axis the source is short on a slice with an end (`[:h, :w]`), as a crop
    written for a larger array does; a whole axis (`:`) kept as it came crops nothing there."""
    parts = index.elts if isinstance(index, ast.Tuple) else [index]
    if any(isinstance(p, ast.Constant) and p.value is Ellipsis for p in parts):
        return False
    short = [i for i, (s, e) in enumerate(zip(source, expected)) if s < e]
    return bool(short) and all(i < len(parts) and isinstance(parts[i], ast.Slice) and parts[i].upper is not None
                               for i in short)


def _made_here(fn, recording, node, statement, got, expected) -> Form | None:
    # (a list's items are the operands of a call given it: `np.hstack([x, y])`)
    operands = [(o, recording.shape(o)) for o in _inputs(node)]
    arrays = [(o, s) for o, s in operands if s is not None]
    if not arrays:
        return None
    line = getattr(node, "lineno", statement.lineno)
    parts = []
    for operand, shape in arrays[:3]:
        inner = [(o, s) for o, s in ((o, recording.shape(o)) for o in _children(operand)) if s is not None and s != shape]
        deeper = f" ({_quote(inner[0][0])} is {_shape_text(inner[0][1])})" if inner and not isinstance(operand, ast.Name) else ""
        parts.append(f"{_quote(operand)} of shape {_shape_text(shape)}{deeper}")
    said = f"{_quote(node)} (line {line}) makes the shape {_shape_text(got)} from {' and '.join(parts)}"
    if isinstance(node, ast.BinOp) and len(arrays) == 2 and np.prod(got) > max(np.prod(s) for _, s in arrays):
        said += ": NumPy broadcasts them against each other, every entry of one with every entry of the other"
    if any(s == tuple(expected) for _, s in arrays):
        said += f" ({' and '.join(_quote(o) for o, s in arrays if s == tuple(expected))} has the shape asked, {_shape_text(expected)})"
    if isinstance(node, ast.Call) and _called_name(node) in ("hstack", "concatenate") and len(arrays) >= 2 \
            and all(len(s) == 1 for _, s in arrays) and len(expected) == 2 and expected[1] == len(arrays) \
            and all(s[0] == expected[0] for _, s in arrays):
        # (measured: the recording's shapes, each (N,), and the (N, k) asked)
        said += measured(": NumPy joins (N,) arrays end to end; as the columns of an (N, k) array they go side by "
                         "side (np.column_stack)")
    if len(got) == 2 and got[0] != got[1] and tuple(got) == tuple(expected)[::-1]:
        said += measured(f": its two axes are exchanged (the transpose of the {_shape_text(expected)} asked)")
    said += _stack_transposed(fn, arrays, line)
    source = arrays[0][1]
    if isinstance(node, ast.Subscript) and len(arrays) == 1 and len(got) == len(expected) == len(source) \
            and any(s < e for s, e in zip(source, expected)) \
            and tuple(got) == tuple(min(s, e) for s, e in zip(source, expected)) \
            and _bounded_where_short(node.slice, source, expected):
        # (a crop written for a larger array: a slice never pads; measured: the slice's shapes here)
        said += measured(f": a slice crops but never pads -- where {_quote(arrays[0][0])} is smaller than "
                         f"{_shape_text(expected)}, copy it into an array of that size (zeros elsewhere: black for an image)")
    tests = [t for t in _conditions(fn, statement) if getattr(t, "lineno", 0)]
    if tests:
        test = tests[-1]
        said += f", on the branch `if {ast.unparse(test)}:` (line {test.lineno})"
        given = _last_given(fn, test.id, test.lineno) if isinstance(test, ast.Name) else None
        if given is not None:   # (a flag: what set it)
            said += f", where {_quote(test)} is {_quote(given[0])} (line {given[1]})"
    return Form(said, MISTAKE)


# ------------------------------------------------------------------ a failed check's verdict
_WRONG_SHAPE = re.compile(r"(\w+)\(.*?\)(?: with [\w=.,\- ]*?)? returned (?:an array of |homogeneous points of )?shape "
                          r"\(([\d, ]*)\)"
                          r"(?:, i\.e\. \([^)]*\))?; expected \(([\d, ]*)\)")
# one item of a tuple answer: "epipoles(F): e1 has shape (3, 1); expected (3,)"
_WRONG_ITEM_SHAPE = re.compile(r"(\w+)\([^:]*?\)[^:]*: (\w+) has shape \(([\d, ]*)\); expected \(([\d, ]*)\)")
_WRONG_SCALAR = re.compile(r"(\w+)\(.*?\)(?: with [\w=.,\- ]*?)? returned an? (?:float|int|integer|number)\b[^;]*; "
                           r"expected a numpy array of shape")
LEAD = "On this input,"


def named(verdict, trial, traceback_text: str = ""):
    """A failed verdict that names nothing, with what the recording of the failing call shows
    (:func:`explain_raised` for the exception the trial's last call raised, :func:`explain_shape`
    for an answer of the wrong shape), or unchanged."""
    from dataclasses import replace

    from .hints import code_of
    from .raised import frames_of, without_comprehensions

    first, newline, rest = str(verdict.message).partition("\n")
    code = code_of(trial)
    form = None
    if traceback_text and getattr(trial, "raised", None):
        if (verdict.mistake and verdict.mistake not in EXCEPTION_FORMS and not _a_case_removed(verdict)) \
                or (_named_by_a_change(verdict) and not _a_case_removed(verdict)):
            return verdict   # (a form read from NumPy's message alone is told where it happened too)
        function, args, kwargs, message = trial.raised
        frames = without_comprehensions(frames_of(traceback_text))
        frame = frames[-1] if frames else None
        fn = code.functions.get(frame[2]) if frame and frame[0] == f"{trial.lab.module}.py" else None
        if fn is not None:
            recording = record(trial, function, args, kwargs)
            if recording is not None and recording.raised:
                form = explain_raised(code, recording, fn, frame[1], message, frames)
    elif not _named_by_a_change(verdict):
        found = _WRONG_SHAPE.search(first)
        item = _WRONG_ITEM_SHAPE.search(first) if found is None else None
        function, item_name, got, expected = (found.group(1), "", found.group(2), found.group(3)) if found else \
            item.groups() if item else (None, "", "", "")
        call = _call_answering(trial, function, _parsed(got)) if function else None
        if call is not None:
            function, args, kwargs = call
            recording = record(trial, function, args, kwargs)
            if recording is not None:
                form = explain_shape(code, recording, function, _parsed(got), _parsed(expected), item_name)
        scalar = _WRONG_SCALAR.search(first) if function is None else None
        call = _call_answering(trial, scalar.group(1), None) if scalar else None
        if call is not None:
            function, args, kwargs = call
            recording = record(trial, function, args, kwargs)
            if recording is not None:
                form = explain_scalar(code, recording, function)
    if form is None:
        return verdict
    lead = first.rstrip()
    lead += "" if not lead or lead[-1] in ".:;!?" else "."
    # (a shape the check named by its form -- "it looks flattened" -- keeps that name: this says where)
    return replace(verdict, message=f"{lead} {LEAD} {form.sentence}.{newline}{rest}",
                   mistake=verdict.mistake or form.mistake)


def _named_by_a_change(verdict) -> bool:
    """Whether a change confirmed on the student's answers already names the failure (a repair of their
    code, a mutant of the reference): where it comes from is then said."""
    from .mutants import naming, repair

    message = str(verdict.message)
    return str(verdict.mistake).startswith("mutant:") or naming.APPENDED in message or repair.HEAD in message


def _a_case_removed(verdict) -> bool:
    """Whether the change that names the failure takes out a case of the student's own whole (`removing
    `if ...: ...``): it says where, not why -- what the raising line held is told beside it."""
    from .mutants import repair

    return repair.HEAD in str(verdict.message) and "removing `if " in str(verdict.message)


def _call_answering(trial, function: str, shape: tuple | None):
    """``(function, args, kwargs)`` of the trial's last call of ``function`` answering an array of ``shape``
    (None: a single number)."""
    for name, args, kwargs, answer in reversed(list(getattr(trial, "calls", ()))):
        items = answer if isinstance(answer, (tuple, list)) else (answer,)
        if name == function and any(isinstance(a, np.ndarray) and a.shape == tuple(shape) if shape is not None
                                    else isinstance(a, (int, float, np.number)) and not isinstance(a, bool)
                                    for a in items):
            return name, args, kwargs
    return None


def explain_scalar(code, recording: Recording, function: str) -> Form | None:
    """Where an answer that should be an array came out a single number: an index after `...` (`xl[..., 0]`)
    on an array with no other axis, which takes one of its values where a column of (N, 2) points was meant."""
    fn = code.functions.get(function)
    if fn is None or recording.returned is None or not (recording.returned[0] == "number"
                                                         or tuple(recording.returned[:2]) == ("array", ())):
        return None
    for node in sorted((n for n in _own_nodes(fn) if isinstance(n, ast.Subscript)),
                       key=lambda n: (n.lineno, n.col_offset)):
        if isinstance(node.slice, ast.Tuple) and node.slice.elts \
                and isinstance(node.slice.elts[0], ast.Constant) and node.slice.elts[0].value is Ellipsis:
            base = recording.shape(node.value)
            single = recording.number(node) is not None or recording.shape(node) == ()
            if base is not None and len(base) == len(node.slice.elts) - 1 and single:
                return Form(f"{_quote(node)} (line {node.lineno}) is a single number: {_quote(node.value)} has "
                            f"shape {_shape_text(base)}, and `...` then stands for no axis, so the index after it "
                            "takes one value of its only axis (on (N, 2) points it is the x column)", MISTAKE)
    return None


# ------------------------------------------------------------------ a value that departs from the reference's
def reference_recording(trial, function: str, args, kwargs) -> Recording | None:
    """The recording of the reference's ``function`` on the same input, run in the error model's helper
    process (trusted code, bounded in time); None without a reference or in time."""
    from .hints import read_code
    from .mutants.helper import HelperFailed
    from .mutants.naming import helper, model_for, release_helper

    from .checks import fingerprint

    cache = trial.sandbox.shared.setdefault("traced reference recordings", {})
    key = fingerprint(function, tuple(args), dict(kwargs))
    if key in cache:   # (a departure confirmed, then the repairs' pruning: one recording of the call)
        return cache[key]
    model = model_for(trial.lab)
    spent = trial.sandbox.shared.setdefault(SPENT, [0.0])
    seconds = min(TRACE_SECONDS, GRADING_SECONDS - spent[0])
    if model is None or seconds <= 0.2:
        return None
    source = recording_source(read_code(model.source), function)
    if source is None:
        return None
    import time

    started = time.monotonic()
    try:
        runner = helper()
        runner.prepare(model.source + "\n" + source, model.module, [(RECORDED, tuple(args), dict(kwargs))], seconds)
        [value] = runner.run((), [0], seconds)
    except HelperFailed:
        return None
    finally:
        spent[0] += time.monotonic() - started
        release_helper()
    cache[key] = recording_of(value)
    return cache[key]


def explain_values(code, mine: Recording, reference: Recording, function: str):
    """The student's values (small arrays) that depart from every value the reference's computation has
    on the same input while what they are computed from agrees, and are one of those values transposed,
    inverted, negated, reversed or scaled: ``(form, def, node, relation)`` for each, in the order the code
    is written (:func:`undone` confirms one). A departure not confirmed is taken as the student's own
    legitimate step: what is computed from it agrees too (``R.T`` kept for ``-R.T @ t``)."""
    theirs = [found[3] for found in reference.values.values() if found[0] == "array" and len(found) == 4
              and found[3].size >= 2 and np.isfinite(found[3]).all()]
    fn = code.functions.get(function)
    if not theirs or fn is None:
        return
    for fn, node, relation in _departures(code, fn, mine, theirs, depth=0):
        made_from = ", ".join(_quote(c) for c in _inputs(node) if mine.value(c) is not None)
        gives = "gives, in reverse order, a value" if relation == "in reverse order" else f"gives {relation} a value"
        yield (Form(f"{_quote(node)} (line {node.lineno}) {gives} the reference's computation has at that point, "
                    f"where what it is computed from ({made_from[:160]}) agrees with the reference's", MISTAKE_OF_VALUE),
               fn, node, relation)
        theirs.append(mine.value(node))   # (not confirmed, if asked for the next one: the student's own step)


def _agrees(value, theirs) -> bool:
    """Whether ``value`` is one of the reference's values, or one item of one (``A[i]`` of an ``(N, 4, 4)``
    stack: a loop over the points where the reference computes them all at once)."""
    # (an item of 4 numbers at least -- a row of a system, a matrix --: a point equal to a row of an input,
    # `pts[0]`, says nothing of the step)
    return any((value.shape == other.shape and _close(value, other))
               or (value.size >= 4 and other.ndim == value.ndim + 1 and other.shape[1:] == value.shape
                   and _an_item(value, other))
               or _made_homogeneous(value, other)
               for other in theirs)


def _rank_two(value) -> bool:
    """A 3 x 3 matrix of rank 2 (an F or an E): its smallest singular value a millionth of its largest."""
    if value.shape != (3, 3) or not np.isfinite(value).all():
        return False
    s = np.linalg.svd(value, compute_uv=False)
    return bool(s[0] > 0 and s[2] <= 1e-6 * s[0] < s[1])


def _made_homogeneous(value, other) -> bool:
    """Whether ``value`` is ``other`` with one more row or column, first or last, that is constant (a
    column of ones: points made homogeneous) or a unit vector (a matrix's [0, 0, 1] row): the student's
    own homogeneous form of the reference's value, where it keeps the reference's numbers."""
    if value.ndim != other.ndim or value.ndim == 0 or other.size < 2:
        return False
    grown = [axis for axis in range(value.ndim) if value.shape[axis] != other.shape[axis]]
    if len(grown) != 1 or value.shape[grown[0]] != other.shape[grown[0]] + 1:
        return False
    axis = grown[0]
    for kept, extra in ((slice(None, -1), -1), (slice(1, None), 0)):
        if not _close(np.take(value, np.arange(value.shape[axis])[kept], axis=axis), other):
            continue
        added = np.take(value, extra, axis=axis).ravel()
        if np.allclose(added, added[0]) or (np.count_nonzero(added) == 1 and np.isclose(np.abs(added).max(), 1.0)):
            return True
    return False


def _an_item(value, stack) -> bool:
    scale = max(1.0, float(np.abs(stack).max(initial=0.0)))
    return bool(np.isclose(stack, value, rtol=1e-5, atol=1e-8 * scale).reshape(len(stack), -1).all(axis=1).any())


def _close(value, other) -> bool:
    if value.shape != other.shape:
        return False
    scale = max(1.0, float(np.abs(other).max(initial=0.0)))
    return bool(np.allclose(value, other, rtol=1e-5, atol=1e-8 * scale))


def _inputs(node) -> list:
    """What an expression is computed from: its operands, a call's arguments (a list's items too)."""
    found = []
    for child in _children(node):
        found += list(child.elts) if isinstance(child, (ast.List, ast.Tuple)) else [child]
    return found


def _departures(code, fn, mine, theirs, depth: int, related: bool = True):
    """``(def, node, relation)`` of each of the student's values departing from the reference's (only
    those with a relation to one of the reference's values, unless not ``related``: relation None)."""
    kinds = (ast.BinOp, ast.Call, ast.Subscript, ast.UnaryOp, ast.Attribute)
    filled = {id(t): s.value for s in _own_nodes(fn) if isinstance(s, (ast.Assign, ast.AugAssign))
              for t in (s.targets if isinstance(s, ast.Assign) else [s.target]) if isinstance(t, ast.Subscript)}
    nodes = sorted((n for n in _own_nodes(fn) if isinstance(n, kinds) and mine.value(n) is not None),
                   key=lambda n: (n.lineno, n.col_offset))
    for node in nodes:
        value = mine.value(node)
        if value.size < 2 or not np.isfinite(value).all() or _agrees(value, theirs):
            continue
        # (a container filled in place -- `T[2, :2] = v` -- is made from itself before and the value put in)
        made_from = [node.value, filled[id(node)]] if id(node) in filled else _inputs(node)
        inputs = [mine.value(c) for c in made_from]
        inputs = [v for v in inputs if v is not None and v.size >= 2]
        if not inputs or not all(_agrees(v, theirs) for v in inputs):
            continue   # (made from a value that departed before, or from nothing to compare)
        helper = _helper(code, fn, node)
        if helper is not None and helper is not fn and depth < 3:
            yield from _departures(code, helper, mine, theirs, depth + 1, related)
        if not related:
            yield fn, node, None
            continue
        relation = _relation(value, theirs)
        if relation is not None and id(node) not in filled:   # (a target cannot be turned back in place)
            yield fn, node, relation


MISTAKE_OF_VALUE = "a value transposed, inverted, negated, reversed or scaled"


def _relation(value, theirs) -> str | None:
    found = []
    for other in theirs:
        if _close(value, other):
            return None
        if value.ndim == 2 and value.shape == other.T.shape and not _close(other, other.T) and _close(value, other.T):
            found.append("the transpose of")
        elif value.ndim == 2 and value.shape == other.shape and value.shape[0] == value.shape[1]:
            inverse = _inverse(other)
            if inverse is not None and not _close(inverse, other) and _close(value, inverse):
                found.append("the inverse of")
        if value.shape == other.shape and np.abs(other).max() > 0 and _close(value, -other) and not _rank_two(value):
            # (a fundamental or essential matrix, of rank 2, is defined up to scale and sign: its negative is
            # the same matrix, no departure)
            found.append("the negative of")
        if value.shape == other.shape and np.all(other != 0) and not _close(np.abs(other), np.ones_like(other)) \
                and _close(value, 1.0 / other):
            found.append("the reciprocal of")
        if value.shape == other.shape and value.shape[0] > 1 and not _close(other, other[::-1]) \
                and _close(value, other[::-1]):
            found.append("in reverse order")
        if value.shape == other.shape and np.count_nonzero(other) >= 2:
            ratio = _constant_ratio(value, other)
            if ratio is not None:
                found.append(f"{ratio:.6g} times")
    kinds = {kind.split()[0] if kind[0].isdigit() else kind for kind in found}
    if len(kinds) != 1:
        return None
    relation = found[0]
    return "in reverse order" if relation == "in reverse order" else relation


def _inverse(matrix):
    try:
        if abs(np.linalg.det(matrix)) < 1e-12 * max(1.0, float(np.abs(matrix).max())) ** matrix.shape[0]:
            return None
        return np.linalg.inv(matrix)
    except np.linalg.LinAlgError:
        return None


def _constant_ratio(value, other) -> float | None:
    """k when ``value`` is k times ``other`` (k not 1 nor -1), else None."""
    nonzero = other != 0
    if np.any(value[~nonzero] != 0):
        return None
    ratios = value[nonzero] / other[nonzero]
    k = float(np.median(ratios))
    if not np.isfinite(k) or not np.allclose(ratios, k, rtol=1e-6):
        return None
    # (the slips' factors only: a value of a homogeneous quantity is right at any scale)
    return k if any(abs(k - f) <= 1e-6 * abs(f) for f in FACTORS) else None


FACTORS = (2.0, 0.5, np.pi / 180, 180 / np.pi, 255.0, 1 / 255, np.sqrt(2), 1 / np.sqrt(2), 0.25, 4.0)


_UNDO = {"the transpose of": "({}).T", "the inverse of": "np.linalg.inv({})", "the negative of": "-({})",
         "the reciprocal of": "1.0 / ({})", "in reverse order": "({})[::-1]"}


def undo_text(node, relation: str) -> str:
    """``node``'s code with its value turned back by ``relation``: ``R`` for ``R.T`` transposed back,
    ``(expr).T`` otherwise."""
    if relation == "the transpose of" and isinstance(node, ast.Attribute) and node.attr == "T":
        return ast.unparse(node.value)
    if relation == "the negative of" and isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        return ast.unparse(node.operand)
    if relation == "the inverse of" and isinstance(node, ast.Call) and _called_name(node) == "inv" and len(node.args) == 1:
        return ast.unparse(node.args[0])
    text = ast.unparse(node)
    if relation in _UNDO:
        return ast.unparse(parse(_UNDO[relation].format(text), mode="eval"))
    k = float(relation.split()[0])
    if abs(1 / k - round(1 / k)) < 1e-9:   # (half of it: twice that)
        return f"{round(1 / k)} * ({text})"
    return f"({text}) / {k!r}"


def undone(fn, node, relation: str) -> str | None:
    """The source of ``fn`` with ``node``'s value turned back by ``relation`` (``(expr).T`` for a
    transpose, ``(expr) / 2.0`` for twice), or None."""
    wrapped = undo_text(node, relation)
    key = node_key(node)

    class Swap(ast.NodeTransformer):
        def generic_visit(self, child):
            if isinstance(child, ast.expr) and hasattr(child, "lineno") and node_key(child) == key:
                return parse(wrapped, mode="eval").body
            return super().generic_visit(child)

    changed = Swap().visit(copy_tree(fn))
    return ast.unparse(ast.fix_missing_locations(changed))


def confirmed_departure(trial):
    """``(form, node, relation, function)``: the first of the student's values to depart from the
    reference's on the trial's last call (:func:`explain_values`), confirmed by turning it back in their
    code -- the function then gives the reference's answers on every call of it the trial made (at most
    :data:`CONFIRMATIONS` departures tried); None otherwise."""
    import time

    from .hints import code_of
    from .mutants.naming import model_for

    if not getattr(trial, "calls", None):
        return None
    function, args, kwargs, _ = trial.calls[-1]
    calls = [call for call in trial.calls if call[0] == function][-4:]
    code = code_of(trial)
    mine = record(trial, function, args, kwargs)
    theirs = reference_recording(trial, function, args, kwargs) if mine is not None and not mine.raised else None
    model = model_for(trial.lab)
    if theirs is None or model is None:
        return None
    expected = [None]   # (the reference's answers, asked once)
    spent = trial.sandbox.shared.setdefault(SPENT, [0.0])
    for tried, (form, fn, node, relation) in enumerate(explain_values(code, mine, theirs, function)):
        if tried >= CONFIRMATIONS or GRADING_SECONDS - spent[0] <= 0.2 or expected[0] is False:
            return None
        started = time.monotonic()
        try:
            if _confirmed(trial, code, model, node, relation, function, calls, expected):
                return form, node, relation, function
        finally:
            spent[0] += time.monotonic() - started
    return None


def _confirmed(trial, code, model, node, relation, function, calls, expected_of) -> bool:
    """Whether turning ``node``'s value back by ``relation`` in the student's code gives the reference's
    answers on ``calls`` (``expected_of[0]``: those answers, asked of the reference once and kept there;
    False when this call's answer is right, so that nothing is to be confirmed)."""
    from .mutants import repair
    from .mutants.helper import HelperFailed
    from .mutants.naming import helper, release_helper

    seconds = min(TRACE_SECONDS, GRADING_SECONDS - trial.sandbox.shared.setdefault(SPENT, [0.0])[0])
    top = next((f for f in code.functions.values() if f.lineno <= node.lineno <= (f.end_lineno or f.lineno)), None)
    source = undone(top, node, relation) if top is not None else None   # (a nested def: the def holding it)
    if source is None or seconds <= 0.2:
        return False
    expected = expected_of[0]
    if expected is None:
        try:
            runner = helper()
            runner.prepare(model.source, model.module, [(f, tuple(a), dict(k)) for f, a, k, _ in calls], seconds)
            expected = runner.run((), range(len(calls)), seconds)
        except HelperFailed:
            expected_of[0] = False
            return False
        finally:
            release_helper()
        if repair.right(calls[-1][3], expected[-1]):
            expected_of[0] = False   # (this call's answer is right: another call failed the check)
            return False
        expected_of[0] = expected
    forbid = () if getattr(trial, "forbidden_allowed", False) else tuple(trial.forbidden(function))
    outcome = trial.sandbox.companion().call_variant(trial.lab.module, source, function,
                                                     [(tuple(a), dict(k)) for _, a, k, _ in calls],
                                                     timeout=seconds, forbid=forbid)
    answers = outcome.value if outcome.ok and isinstance(outcome.value, list) and len(outcome.value) == len(calls) \
        else None
    # (right as a repair is: exactly, or near where the student's own answer is far off)
    return answers is not None and all(repair.right(a, e, student=call[3]) for a, e, call in zip(answers, expected, calls))


def departure_sentence(found) -> str:
    form, node, relation, function = found
    return f"{LEAD} {form.sentence}; with `{undo_text(node, relation)}` there, `{function}` gives the expected answers"


def named_by_values(verdict, trial):
    """A failed verdict that names nothing, named by a :func:`confirmed_departure` of the student's values."""
    from dataclasses import replace

    if verdict.mistake or _named_by_a_change(verdict):
        return verdict
    found = confirmed_departure(trial)
    if found is None:
        return verdict
    first, newline, rest = str(verdict.message).partition("\n")
    lead = first.rstrip()
    lead += "" if not lead or lead[-1] in ".:;!?" else "."
    return replace(verdict, message=f"{lead} {departure_sentence(found)}.{newline}{rest}", mistake=found[0].mistake)


_PLACES = re.compile(r"\(line (\d+)(?:, in `(\w+)`)?")   # a repair's places: its line, and the helper it is in
GUESS = ": it looks like "


def departure_before_repair(verdict, trial):
    """A verdict named by a repair of the student's code (:mod:`autograder.engine.mutants.repair`) -- alone,
    or beside a check's guess from the answer ("it looks like pts1 and pts2 are swapped") -- whose changes
    are all at lines after a :func:`confirmed_departure` of their values: the departure is where the values
    first go wrong, and a change after it undoes it (`H_norm.T` after a reshape in column order); the
    departure is told in the repair's place (and the guess's). Otherwise unchanged."""
    from dataclasses import replace

    from .mutants import repair

    message = str(verdict.message)
    first, newline, rest = message.partition("\n")
    guessed = GUESS in first and not str(verdict.mistake).startswith(repair.MISTAKE)
    if not (str(verdict.mistake).startswith(repair.MISTAKE) or guessed) or repair.HEAD not in first:
        return verdict
    lead, _, told = first.partition(repair.HEAD)
    places = [(int(line), helper) for line, helper in _PLACES.findall(told)]
    found = confirmed_departure(trial) if places else None
    if found is None:
        return verdict
    # (lines are ordered within one def only: a change in a helper -- "(line 175, in `_core`)" -- is
    # after the departure only where the departure is in that helper too)
    from .hints import code_of

    holder = next((name for name, fn in code_of(trial).functions.items()
                   if fn.lineno <= found[1].lineno <= (fn.end_lineno or fn.lineno)), None)
    graded = found[3]
    if not all((helper or graded) == holder and line > found[1].lineno for line, helper in places):
        return verdict
    if guessed:   # (a check's guess from the answer alone -- "it looks like pts1 and pts2 are swapped" -- whose
        lead = lead.split(GUESS, 1)[0]   # repair undoes the departure later: the departure is the cause shown)
    lead = lead.rstrip()
    lead += "" if not lead or lead[-1] in ".:;!?" else "."
    return replace(verdict, message=f"{lead} {departure_sentence(found)}.{newline}{rest}", mistake=found[0].mistake,
                   hint="")


def first_departure(trial, function: str, args, kwargs):
    """``(def name, line)`` of the first of the student's values (small arrays) on this call that departs
    from every value of the reference's computation while what it is computed from agrees, related to
    them or not: where the values first go wrong, or the student's own step; None when none is seen."""
    from .hints import code_of

    mine = record(trial, function, args, kwargs)
    theirs = reference_recording(trial, function, args, kwargs) if mine is not None and not mine.raised else None
    if theirs is None:
        return None
    values = [found[3] for found in theirs.values.values() if found[0] == "array" and len(found) == 4
              and found[3].size >= 2 and np.isfinite(found[3]).all()]
    code = code_of(trial)
    fn = code.functions.get(function)
    if fn is None or not values:
        return None
    for where, node, _ in _departures(code, fn, mine, values, depth=0, related=False):
        return where.name, node.lineno
    return None
