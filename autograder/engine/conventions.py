"""The API's conventions on forms, judged as relations between a student's own answers.

Three conventions of the API hold for every function they apply to, yet no worked example of a
lab shows them, so a submission breaking one could score full marks (issue 35's blind sets: a
grey image warped as BGR, a (1, 3) input squeezed away, a single point counted by its length,
points given as integers answered in integers):

- **channels**: a function that takes images and returns one answers in the input's number of
  channels -- the grey version of its BGR inputs gives the grey form of its BGR answer (the same
  size, uint8, no channel axis), and its other arrays in the same shapes;
- **points one by one**: a function of N points treats each point alone -- the first point given
  as a one-row array, (1, k), is answered as the first row of its answer for all N (N = 1 is a
  number of points like any other: a squeezed (k,) answer is no row);
- **whole numbers as integers**: points and matrices of whole numbers given as integer arrays
  (the sheet's own sample point (1, 1, 2) with f = 1 is one) are answered as the same numbers
  given as floats. The API gives floats, so a function may refuse integers (raise); what it may
  not do is answer them otherwise -- an array made like the input (``np.zeros_like(points)``)
  holds integers, and what is written into it is cut to whole numbers.

All three are relations between two answers of the same student, so they need neither the reference
nor a tolerance for legitimate variants: a recipe the lab sheet allows answers the grey or single
form of an input as it answers the input itself. How right an answer is stays the other checks'
to judge; these take points only for a form, or a point's value, that changes with how the same
input is given. A lab declares them with :func:`keeps_grey`, :func:`point_by_point` and
:func:`whole_numbers` (each adds one check to an exercise) and says why a function is not judged
with :func:`not_judged`; ``tests/test_conventions.py`` holds every lab to saying one or the other
of each function with images or points.
"""

from __future__ import annotations

import ast
from typing import Callable

import cv2
import numpy as np

from .checks import StudentFailure, Trial, passed
from .claims import from_code, measured, where_to_look
from .compare import same_to_precision
from .forms import IMAGE_SIDE
from .hints import code_of
from ..loading.parsing import walk

# per convention ("channels", "rows", "integers"): function -> its lab's key;
# "not judged": (convention, function) -> why
DECLARED: dict[str, dict] = {"channels": {}, "rows": {}, "integers": {}, "not judged": {}}

GREY_NOT_KEPT = "a grey image is not answered in grey"
INTEGERS_CUT = "integer inputs are answered in integers"
SIZE_SLACK = 2     # pixels an image answered in grey may differ in size from the BGR one's
RELATIVE = 1e-7   # the same point's answer among many and alone: the same float operations, up to BLAS order


def keeps_grey(exercise, function: str, inputs: Callable[[], tuple], images=(0,), points: float = 1,
               hidden: bool = False, described: str = "") -> None:
    """Register on ``exercise`` the check that ``function`` answers grey images in grey:
    ``inputs()`` gives its arguments with BGR images at the positions ``images``; ``described``
    names them for the student (``"reference, moving, H"``)."""
    def check(t: Trial):
        return judge_grey(t, function, inputs(), images, described)
    check.__name__ = f"{function}_keeps_grey"
    DECLARED["channels"][function] = exercise.lab.key
    exercise.check(f"{function} answers grey images in grey (the API: an image's channels are kept)",
                   points=points, hidden=hidden)(check)


def point_by_point(exercise, function: str, inputs: Callable[[], tuple], rows=(0,), points: float = 1,
                   hidden: bool = False, described: str = "", one_row: bool = True) -> None:
    """Register on ``exercise`` the checks that ``function`` treats each point alone: ``inputs()``
    gives its arguments with N points at the positions ``rows`` (sliced together), N larger than a
    point's coordinates. Two relations, one check each: the first point as a one-row array (left
    out with ``one_row=False`` where a lab's own checks judge the one-row form against the truth),
    and the first k points where k is a point's number of coordinates -- a (3, 3) array is three
    points, not one point told by its length. (The API's single (3,) point is judged against the
    truth by each lab's own checks.)"""
    def check(t: Trial):
        return judge_rows(t, function, inputs(), rows, described)

    def square(t: Trial):
        return judge_square(t, function, inputs(), rows, described)
    check.__name__, square.__name__ = f"{function}_point_by_point", f"{function}_as_many_as_coordinates"
    DECLARED["rows"][function] = exercise.lab.key
    if one_row:
        exercise.check(f"{function} answers a one-row array as the same point among many", points=points,
                       hidden=hidden)(check)
    exercise.check(f"{function} answers as many points as a point has coordinates as the same points among many",
                   points=points, hidden=hidden)(square)


def whole_numbers(exercise, function: str, inputs: Callable[[], tuple], points: float = 1, hidden: bool = False,
                  described: str = "") -> None:
    """Register on ``exercise`` the check that ``function`` answers its inputs' whole numbers given as
    integers as it answers them given as floats: ``inputs()`` gives float arguments, some arrays (or
    numbers) of which hold whole numbers only; those are given again as ``int64`` arrays (Python
    ints)."""
    def check(t: Trial):
        return judge_integers(t, function, inputs(), described)
    check.__name__ = f"{function}_whole_numbers"
    DECLARED["integers"][function] = exercise.lab.key
    exercise.check(f"{function} answers whole numbers given as integers as it answers them as floats",
                   points=points, hidden=hidden)(check)


def column_vector(exercise, function: str, inputs: Callable[[], tuple], position: int, name: str) -> None:
    """Register on ``exercise`` an advice check (no points) that ``function`` answers its 3-vector argument
    ``name`` (at ``position`` of ``inputs()``) given as OpenCV's (3, 1) column as it answers it flat, (3,):
    the skeletons give (3,), OpenCV's calibration and pose functions return (3, 1), and course code hands
    them on. A tip where the column form raises or changes the answer."""
    def check(t: Trial):
        args = inputs()
        flat = t.call(function, *args)   # (the flat form failing is the graded checks' to say)
        column = list(args)
        column[position] = np.asarray(args[position], dtype=np.float64).reshape(-1, 1)
        what = f"{function}(...) with {name} of shape (3, 1)"
        try:
            got = t.call(function, *column)
        except StudentFailure as failure:
            t.advise(measured(f"{what} raised where the same {name} of shape (3,) works ({failure.message.splitlines()[0]}): "
                              f"OpenCV returns {name} as a (3, 1) column; flatten it first (np.ravel({name})) to take both"))
            return
        if not _same_answers(flat, got):
            t.advise(measured(f"{what} answered otherwise than with the same {name} of shape (3,): a (3, 1) column "
                              f"broadcasts against (3,) vectors into a 3x3 matrix; flatten it first (np.ravel({name}))"))
    check.__name__ = f"{function}_{name}_as_a_column"
    exercise.advice(f"{function} takes {name} as a (3, 1) column too, as OpenCV returns it")(check)


def _same_answers(first, second) -> bool:
    """Two answers equal to rounding, however nested (a tuple of images and matrices)."""
    if isinstance(first, (tuple, list)) and isinstance(second, (tuple, list)):
        return len(first) == len(second) and all(_same_answers(a, b) for a, b in zip(first, second))
    a, b = np.asarray(first), np.asarray(second)
    if a.shape != b.shape or a.dtype.kind not in "biuf" or b.dtype.kind not in "biuf":
        return a.shape == b.shape and bool(np.all(a == b))
    scale = max(1.0, float(np.nanmax(np.abs(a))) if a.size and np.isfinite(a).any() else 1.0)
    return bool(np.allclose(a, b, rtol=1e-6, atol=1e-9 * scale, equal_nan=True))


MODEL = "its answer is a model fitted to the points, made in no array of theirs"
DRAWN = "its answer is an image drawn at whole pixels: whole numbers given as integers draw alike"
FITTED = "one model fitted to all the points together"   # an estimator's points are no rows of its answer


def not_judged(convention: str, **why: str) -> None:
    """Say, function by function (``function="why"``), why it has no check of ``convention``
    ("channels", "rows" or "integers"): another check judges it already, its answer is no image of the input's
    channels, the API asks for one kind of image only, one model is fitted to all the points..."""
    for function, reason in why.items():
        DECLARED["not judged"][(convention, function)] = reason


def _grey(images):
    """BGR images made grey (a list of them, one by one)."""
    if isinstance(images, (list, tuple)):
        return [_grey(image) for image in images]
    return cv2.cvtColor(images, cv2.COLOR_BGR2GRAY)


def _parts(answer) -> list:
    """The answer's parts: the items of a tuple or list of arrays, else the answer itself."""
    if isinstance(answer, (tuple, list)) and any(isinstance(part, np.ndarray) for part in answer):
        return list(answer)
    return [answer]


def _name(call: str, index: int, count: int, given: str) -> str:
    """How a part of the answer to ``call`` on the ``given`` form of its input is named."""
    return f"{call}{'' if count == 1 else f'[{index}]'} {given}"


def _asked(t: Trial, function: str, args: tuple, said: str):
    """The student's answer on ``args``; an exception is told with the input it was raised on."""
    try:
        return t.call(function, *args)
    except StudentFailure as failure:
        if failure.outcome.kind != "exception":
            raise
        raise failure.said(f"{said}: {failure.message}") from None


def _same_parts(t: Trial, what: str, first, second, mistake: str = "") -> list:
    """``second``'s parts, failing when they are not as many as ``first``'s."""
    ours, theirs = _parts(first), _parts(second)
    if len(ours) != len(theirs):
        t.fail(measured(f"{what} returned {len(theirs)} value(s), where the other form of the input gives "
                        f"{len(ours)}"), mistake=mistake)
    return theirs


STATE_BETWEEN_CALLS = "the answers depend on earlier calls"


def fail_if_answers_drift(t: Trial, function: str, args: tuple, first, call: str) -> None:
    """Before a difference between two forms of an input is blamed on the form: ``function`` called again
    with ``args``, whose answer was ``first``; fail when the same call answers otherwise -- the function
    keeps or changes something between calls (a module-level array changed in place, a list that grows),
    and the second form's answer differed for that, not for its form."""
    try:
        again = t.call(function, *args)
    except StudentFailure:
        return   # (a call raising, or out of time, the second time: the comparison of forms says what it measured)
    for ours, theirs in zip(_parts(first), _parts(again)):
        if isinstance(ours, np.ndarray) and ours.dtype.kind in "biuf" and isinstance(theirs, np.ndarray) \
                and theirs.shape == ours.shape and theirs.dtype.kind in "biuf" and not _close(theirs, ours):
            t.fail(measured(f"{call} called twice with the same arguments returned {_first(ours)}, then "
                            f"{_first(theirs)}: your {function} keeps or changes something between calls, so each "
                            "call answers otherwise; a function's answer may depend on its arguments only.") + " "
                   + where_to_look(measured("Look for an array of the module changed in place, a list that grows, or "
                                            "random numbers drawn without a seed.")), mistake=STATE_BETWEEN_CALLS)


def judge_grey(t: Trial, function: str, args: tuple, images, described: str = ""):
    """Judge ``function`` on the grey versions of its BGR inputs against its own BGR answer."""
    call = f"{function}({described or '...'})"
    what = f"{call} on grey images"
    colour = t.call(function, *args)
    grey_args = tuple(_grey(a) if i in images else a for i, a in enumerate(args))
    grey = _asked(t, function, grey_args, measured(f"{what} (the BGR inputs converted with cv2.cvtColor: "
                                                   "an image may be grey (H, W) as well as BGR)"))
    theirs = _same_parts(t, what, colour, grey, GREY_NOT_KEPT)
    shapes = []
    for index, (ours, given) in enumerate(zip(_parts(colour), theirs)):
        if not isinstance(ours, np.ndarray):
            continue
        name = _name(call, index, len(theirs), "on grey images")
        if ours.ndim == 3 and ours.shape[2] == 3 and min(ours.shape[:2]) >= IMAGE_SIDE:   # an image: its grey form
            # (of about the same size: a canvas fitted to features found anew may move by a pixel)
            # (and of the kind the BGR one has: an image of floats where 8 bits are asked is another
            # check's to judge -- here it would read as channels not kept)
            near = isinstance(given, np.ndarray) and given.ndim in (2, 3) and \
                all(abs(a - b) <= SIZE_SLACK for a, b in zip(given.shape[:2], ours.shape[:2]))
            shape, dtype = (given.shape[:2] if near else ours.shape[:2]), (np.uint8 if ours.dtype == np.uint8 else None)
        else:   # a matrix, points: the same whatever the images' channels
            shape, dtype = ours.shape, None
        got = t.expect_array(given, name, shape=shape, dtype=dtype)
        if dtype is None and got.dtype.kind != ours.dtype.kind:
            t.fail(measured(f"{name} returned dtype {got.dtype}, where on BGR images it returns {ours.dtype}"))
        shapes.append(str(got.shape))
    return passed(f"on grey images: {', '.join(shapes) or 'the same form'}")


def _close(got, expected) -> bool:
    """The same answer up to the precision the student computes in (:func:`..compare.same_to_precision`)."""
    return same_to_precision(got, expected, RELATIVE)


def judge_rows(t: Trial, function: str, args: tuple, rows, described: str = ""):
    """Judge ``function`` on its first point alone, as a one-row array, against its answer for all
    the points."""
    n = len(args[rows[0]])
    many = t.call(function, *args)
    call = f"{function}({described or '...'})"
    given = f"with a one-row array of shape {np.shape(np.asarray(args[rows[0]])[:1])}"
    alone = _asked(t, function, tuple(np.asarray(a)[:1] if i in rows else a for i, a in enumerate(args)),
                   f"{call} {given}")
    # (measured, not named: a slip in one point's form, or a formula reading every point -- a mean
    # depth where each point's own belongs -- both show so)
    theirs = _same_parts(t, f"{call} {given}", many, alone)
    for index, (ours, answer) in enumerate(zip(_parts(many), theirs)):
        if not (isinstance(ours, np.ndarray) and ours.ndim >= 1 and len(ours) == n and ours.dtype.kind in "biuf"):
            continue   # not one row per point (a wrong answer for all N is the other checks' to judge)
        name = _name(call, index, len(theirs), given)
        if isinstance(answer, np.ndarray) and answer.ndim == ours.ndim and len(answer) == 1 \
                and answer.shape[1:] != ours.shape[1:]:
            # (one row of another width: which form is right is the other checks' to say, not this one's)
            t.fail(measured(f"{name} returned shape {answer.shape}, but among {n} points each point's row has shape "
                            f"{ours.shape[1:]}: the form of a point's answer must not depend on how many points "
                            "are given"))
        got = t.expect_array(answer, name, shape=ours[:1].shape, kind="biuf")
        if not _close(got, ours[:1]):
            fail_if_answers_drift(t, function, args, many, call)
            t.fail(measured(f"{name} returned {np.array2string(got, precision=6)}, but the same point among {n} "
                            f"gives {np.array2string(ours[:1], precision=6)}: a point's answer must not depend "
                            "on how many points are given"))
    return passed(f"the first point, as a one-row array, answered as the same point among {n}")


SQUARE_TAKEN = "as many points as coordinates are taken for one point"


def judge_square(t: Trial, function: str, args: tuple, rows, described: str = ""):
    """Judge ``function`` on its first k points, k the number of coordinates of a point (three 3D
    points, a (3, 3) array; two 2D points, (2, 2)), against its answer for all the points: code that
    tells a single point by its length (``len(points) == 3``) or a transposed input by its first
    axis (``if pts.shape[0] == 2: pts = pts.T``) answers those otherwise."""
    given_all = np.asarray(args[rows[0]])
    n, k = len(given_all), given_all.shape[-1] if given_all.ndim == 2 else 0
    if not 1 < k < n:
        raise ValueError(f"{function}: the check needs N > k points of k >= 2 coordinates, not {given_all.shape}")
    many = t.call(function, *args)
    call = f"{function}({described or '...'})"
    given = f"with {k} points, an array of shape {(k, k)}"
    few = _asked(t, function, tuple(np.asarray(a)[:k] if i in rows else a for i, a in enumerate(args)),
                 f"{call} {given}")
    theirs = _same_parts(t, f"{call} {given}", many, few, SQUARE_TAKEN)
    for index, (ours, answer) in enumerate(zip(_parts(many), theirs)):
        if not (isinstance(ours, np.ndarray) and ours.ndim >= 1 and len(ours) == n and ours.dtype.kind in "biuf"):
            continue   # not one row per point (a wrong answer for all N is the other checks' to judge)
        name = _name(call, index, len(theirs), given)
        expected = ours[:k]
        shaped = isinstance(answer, np.ndarray) and answer.shape == expected.shape
        if shaped and _close(answer, expected):
            continue
        shown = f"shape {answer.shape}" if isinstance(answer, np.ndarray) and not shaped else \
            _first(np.asarray(answer)) if shaped else type(answer).__name__
        why = why_square(t, function, k)
        if not why and shaped:
            fail_if_answers_drift(t, function, args, many, call)
        # (named only where the form changed or the code tests the length: other values alone may come
        # from a formula reading every point -- a mean depth where each point's own belongs)
        # (the rule said is the one the answer breaks: rows for points where its form changed or the code
        # tests the length; else, answers of the right form, a point's own answer, whatever is given beside it)
        # (k rows of another width are k points' answers: their form depends on how many are given, not on the
        # points taken for one -- an (N, 1) column broadcast against N values gives (N, 2N) for any N)
        rows_kept = isinstance(answer, np.ndarray) and answer.ndim >= 1 and len(answer) == k
        taken = why or not (shaped or rows_kept)
        rule = f"{k} points are {k} rows of the answer, whatever a point's number of coordinates" if taken \
            else "a point's answer must not depend on the other points given with it"
        t.fail(measured(f"{name} returned {shown}, but the same {k} points among {n} give {_first(expected)}: "
                        f"{rule}.") + why, mistake=SQUARE_TAKEN if taken else "")
    return passed(f"the first {k} points, as many as a point has coordinates, answered as the same points among {n}")


def _counts_rows(node) -> str:
    """The name whose number of rows ``node`` reads (``len(pts)``, ``pts.shape[0]``, ``np.shape(pts)[0]``,
    ``pts.size``); "" for anything else."""
    if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "len" and len(node.args) == 1:
        return _root(node.args[0], any_dtype=True)
    if isinstance(node, ast.Attribute) and node.attr == "size":
        return _root(node.value, any_dtype=True)
    if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Constant) and node.slice.value == 0:
        shape = node.value
        if isinstance(shape, ast.Attribute) and shape.attr == "shape":
            return _root(shape.value, any_dtype=True)
        if isinstance(shape, ast.Call) and getattr(shape.func, "attr", "") == "shape" and shape.args:
            return _root(shape.args[0], any_dtype=True)
    return ""


def _length_tests(functions, parameters: set, k: int) -> list:
    """The tests in ``functions`` (read, never run) of an input's number of rows against ``k``
    (``len(points) == 3``, ``pts.shape[0] != 2``, ``X.size == 3``, ``len(p) in (2, 3)``); as (line, text)."""
    found = []
    for function in functions:
        inputs, _ = _read_from_inputs(function, parameters, any_dtype=True)
        for node in walk(function):
            if not isinstance(node, ast.Compare) or len(node.ops) != 1 or _counts_rows(node.left) not in inputs:
                continue
            right = node.comparators[0]
            values = [right.value] if isinstance(right, ast.Constant) else \
                [e.value for e in right.elts if isinstance(e, ast.Constant)] if isinstance(right, (ast.Tuple, ast.List, ast.Set)) else []
            if k in values and isinstance(node.ops[0], (ast.Eq, ast.NotEq, ast.In, ast.NotIn)):
                found.append((node.lineno, ast.unparse(node)))
    return sorted(set(found))[:2]


def why_square(t: Trial, function: str, k: int) -> str:
    """Where the student's code tells a point's form by its number of rows (read, never run), in
    words; "" when the reading sees no such test."""
    tests = _length_tests(*_reached(t, function), k)
    if not tests:
        return ""
    where = " and ".join(f"`{text}` (line {line})" for line, text in tests)
    return from_code(f" Reading your code: {where} {'tests' if len(tests) == 1 else 'test'} the input's number of "
                     f"rows against {k}, and {k} points have {k} rows: tell a single point by its number of "
                     "dimensions (`np.ndim(points) == 1`).")


def _as_integers(value):
    """``value`` given as integers when it is a float array (or a float) of whole numbers only, else
    itself."""
    if isinstance(value, np.ndarray) and value.dtype.kind == "f" and value.size \
            and np.isfinite(value).all() and (value == np.round(value)).all():
        return value.astype(np.int64)
    if isinstance(value, float) and value.is_integer():
        return int(value)
    return value


LIKE_INPUT = ("zeros_like", "empty_like", "ones_like", "full_like", "copy", "array", "asarray", "asanyarray")
PASSES_ON = LIKE_INPUT + ("reshape", "atleast_2d", "squeeze", "ravel", "flatten", "transpose")


def _root(node, any_dtype: bool = False) -> str:
    """The name an expression is read from through indexing, attributes and the calls that pass an
    array on in its dtype (``np.asarray(pts1).reshape(-1, 2)`` -> ``pts1``; with ``any_dtype``, also
    those given another dtype: its rows are the same); "" for anything else."""
    while True:
        if isinstance(node, (ast.Subscript, ast.Attribute)):
            node = node.value
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in PASSES_ON \
                and (any_dtype or not any(k.arg == "dtype" for k in node.keywords)):
            module = isinstance(node.func.value, ast.Name) and node.func.value.id in ("np", "numpy")
            if module and not node.args:
                return ""
            node = node.args[0] if module else node.func.value
        else:
            return node.id if isinstance(node, ast.Name) else ""


def _reached(t: Trial, function: str) -> tuple[list, set]:
    """The student's ``function`` and the module functions it runs (read, never run), and all their
    parameters: the inputs a reading follows."""
    functions = code_of(t).reachable([function])
    return functions, {a.arg for f in functions for a in (*f.args.posonlyargs, *f.args.args, *f.args.kwonlyargs)}


def _read_from_inputs(function, parameters: set, any_dtype: bool = False) -> tuple[set, list]:
    """The names ``function`` reads from its inputs (the ``parameters``, and names assigned from them:
    ``pts = np.asarray(pts1).reshape(-1, 2)``, followed three assignments deep), and its assignments
    to a single name."""
    inputs = set(parameters)
    assigned = [node for node in walk(function) if isinstance(node, ast.Assign) and len(node.targets) == 1
                and isinstance(node.targets[0], ast.Name)]
    for _ in range(3):
        inputs |= {node.targets[0].id for node in assigned if _root(node.value, any_dtype) in inputs}
    return inputs, assigned


def _copied(call: ast.Call):
    """The array ``call`` makes a new one like, its dtype kept (``np.zeros_like(x)``, ``np.array(x)``,
    ``x.copy()``, ``np.copy(x)``: ``x``); None for another call, or one given a dtype (by keyword or in
    its place: ``np.array(x, float)``)."""
    name = call.func.attr if isinstance(call.func, ast.Attribute) else getattr(call.func, "id", "")
    if name not in LIKE_INPUT or any(k.arg == "dtype" for k in call.keywords):
        return None
    if name == "copy":   # x.copy() or np.copy(x)
        return call.args[0] if call.args else call.func.value if isinstance(call.func, ast.Attribute) else None
    dtype_at = 2 if name == "full_like" else 1
    return call.args[0] if call.args and len(call.args) <= dtype_at else None


def _made_like(functions, parameters: set) -> list:
    """The lines of ``functions`` (the student's, read never run) that make an array in an input's
    dtype and then write into it: ``out = np.zeros_like(points[:, :2])``, ``out = pts.copy()``,
    ``np.zeros((n, 3), dtype=pts.dtype)`` (``pts`` read from a parameter), ... followed by
    ``out[i] = ...`` or ``out /= w``; as (line, text)."""
    found = []
    for function in functions:
        inputs, assigned = _read_from_inputs(function, parameters)
        written = {node.target.id for node in walk(function)
                   if isinstance(node, ast.AugAssign) and isinstance(node.target, ast.Name)}
        written |= {_root(target) for node in walk(function) if isinstance(node, (ast.Assign, ast.AugAssign))
                    for target in (node.targets if isinstance(node, ast.Assign) else [node.target])
                    if isinstance(target, ast.Subscript)}
        for node in assigned:
            call = node.value
            while isinstance(call, ast.Subscript):   # ``np.array(points)[..., :2]``: a view of the array made
                call = call.value
            if not isinstance(call, ast.Call) or node.targets[0].id not in written:
                continue
            dtype = next((k.value for k in call.keywords if k.arg == "dtype"), None)
            typed = isinstance(dtype, ast.Attribute) and dtype.attr == "dtype" and _root(dtype.value) in inputs
            source = _copied(call)
            if typed or (source is not None and _root(source) in inputs):
                found.append((node.lineno, ast.unparse(node)))
    return sorted(set(found))[:2]


def why_integers(t: Trial, function: str) -> str:
    """Where the student's code makes an array of its input's dtype (read, never run), in words; ""
    when it makes none that the reading sees."""
    made = _made_like(*_reached(t, function))
    if not made:
        return ""
    where = " and ".join(f"`{text}` (line {line})" for line, text in made)
    return from_code(f" {where} {'makes an array' if len(made) == 1 else 'make arrays'} of the input's dtype, "
                     f"then {'writes into it' if len(made) == 1 else 'write into them'}: given integers, what is "
                     "written is cut to whole numbers; give it dtype=float.")


def _first(array: np.ndarray) -> str:
    """An answer shown on one line: its first row when it has several ("[...] in its first row")."""
    shown = array[0] if array.ndim >= 2 and len(array) > 1 else array
    text = np.array2string(shown, precision=4, separator=", ", threshold=12, max_line_width=10**6)
    return " ".join(text.split()) + (" in its first row" if shown is not array else "")


def judge_integers(t: Trial, function: str, args: tuple, described: str = ""):
    """Judge ``function`` on the whole numbers of ``args`` given as integers against its own answer on
    them as floats."""
    call = f"{function}({described or '...'})"
    integers = tuple(_as_integers(a) for a in args)
    if all(a is b for a, b in zip(integers, args)):
        raise ValueError(f"{call}: the check's inputs hold no whole-number float array")
    floats = t.call(function, *args)
    given = "with its whole-number inputs given as integer arrays"
    try:
        answer = t.call(function, *integers)
    except StudentFailure as failure:
        if failure.outcome.kind != "exception":
            raise
        return passed(f"raises on integer arrays ({failure.message.splitlines()[0][:120]}): the API gives floats, "
                      "so refusing integers is allowed")
    theirs = _same_parts(t, f"{call} {given}", floats, answer, INTEGERS_CUT)
    for index, (ours, got) in enumerate(zip(_parts(floats), theirs)):
        if not (isinstance(ours, np.ndarray) and ours.dtype.kind in "biuf"):
            continue
        name = _name(call, index, len(theirs), given)
        got = t.expect_array(got, name, shape=ours.shape, kind="biuf")
        if _close(got, ours):
            continue
        cut = got.dtype.kind in "iu" and ours.dtype.kind == "f"
        if not cut:
            fail_if_answers_drift(t, function, args, floats, call)
        said = (f"{name} returned {_first(got)} (dtype {got.dtype}), but the same numbers given as floats give "
                f"{_first(ours)}: whole numbers given as integers (the sheet's own sample point (1, 1, 2)) must give "
                "the same answer")
        if cut:
            said += "; your answer is an integer array, its values cut to whole numbers."
            t.fail(measured(said) + why_integers(t, function), mistake=INTEGERS_CUT)
        t.fail(measured(said + "."), mistake=INTEGERS_CUT)
    return passed("whole numbers given as integers are answered as the same numbers given as floats")
