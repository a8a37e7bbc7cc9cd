"""What the student's code shows of a mistake, read with :mod:`ast` (labs 11 and 12; issue 35).

A check that has measured a failure names its likely cause only where the code shows it: these
predicates (:class:`~autograder.engine.hints.Predicate`, evaluated on the functions a check judges
and their helpers, never executed) are the code's half of such a name; the measurement is the
check's. A predicate that holds is a *sign*, not a proof: every name built on one is said only
with the measurement that makes it likely (a map 16 times the truth, the lines missed being those
leaving through the top or bottom), so code doing the right thing in a way not read (a division
by 16 held in a module-level name) gives no such measurement and no name.

- :data:`STEREO_MATCHER` -- OpenCV's block matchers (``cv2.StereoBM_create``, ``cv2.StereoSGBM.create``);
- :data:`DIVIDES_BY_16` -- a division by 16 of anything but the search range (``d / 16``,
  ``d * (1 / 16)``, ``d >> 4``; not ``-(-(max_disparity + 1) // 16)``);
- :func:`zero_taken_for_missing` -- a numeric parameter tested for truth (``smoothness or DEFAULT``,
  ``if not smoothness:``), which takes 0 for "not given";
- :data:`LINES_FROM_SIDES_ONLY` -- lines ``a x + b y + c = 0`` drawn by dividing by ``b`` only (the
  left and right borders, ``x = 0`` and ``x = w - 1``): a steep line leaves through the top and bottom;
- :data:`SKIPS_VERTICAL` -- a line with ``b = 0`` skipped (``continue``) before dividing by ``b``;
- :data:`CAMERA_WITHOUT_K` -- a camera matrix ``[R | t]`` stacked and never multiplied by K, in code
  that never normalises its points (``K^-1 x``, ``cv2.undistortPoints``);
- :func:`name_batched_vt_row` -- ``Vt[-1]`` of an SVD of a stack of systems, told from an answer with
  the system's size as its first dimension;
- :func:`constant_factor`, :func:`factor_words` -- an answer that is the expected times one constant
  (measured, no code read), and that constant in words.
"""

from __future__ import annotations

import ast

import numpy as np

from ..engine.claims import calls_any, divides_by, from_code, takes_last_row_of_vt
from ..engine.hints import Predicate, _path, calls, code_of, expr, mentions
from ..loading.parsing import walk

STEREO_MATCHER = (mentions("cv2.StereoBM") | mentions("cv2.StereoSGBM") | calls("cv2.StereoBM_create")
                  | calls("cv2.StereoSGBM_create")).saying("uses OpenCV's block matcher (cv2.StereoBM or StereoSGBM)")


def _sixteen(node) -> bool:
    return isinstance(node, ast.Constant) and not isinstance(node.value, bool) and node.value == 16


def _of_the_range(node) -> bool:
    """Whether ``node`` involves the search range (``max_disparity``, ``numDisparities``, ``num_disp``):
    ``-(-(max_disparity + 1) // 16)`` rounds the range up to a multiple of 16, it divides no disparity."""
    return any(isinstance(n, ast.Name) and ("max" in n.id.lower() or "num" in n.id.lower() or "range" in n.id.lower())
               for n in walk(node))


def _divides_disparities_by_16(function) -> bool:
    """A division by 16 (``/``, ``//``, ``/=``, ``np.divide``, ``np.true_divide``, ``np.floor_divide``) of
    something other than the search range."""
    for node in walk(function):
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Div, ast.FloorDiv)) and _sixteen(node.right):
            if not _of_the_range(node.left):
                return True
        elif isinstance(node, ast.AugAssign) and isinstance(node.op, (ast.Div, ast.FloorDiv)) and _sixteen(node.value):
            if not _of_the_range(node.target):
                return True
        elif isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in (
                "divide", "true_divide", "floor_divide") and len(node.args) >= 2 and _sixteen(node.args[1]):
            if not _of_the_range(node.args[0]):
                return True
    return False


DIVIDES_BY_16 = (Predicate("divides by 16", _divides_disparities_by_16) | expr("_ * 0.0625") | expr("_ * (1 / 16)")
                 | expr("(1 / 16) * _") | expr("0.0625 * _") | expr("_ >> 4")).saying("divides by 16")


def _parameters(function) -> set[str]:
    arguments = function.args
    return {a.arg for a in arguments.posonlyargs + arguments.args + arguments.kwonlyargs}


def zero_taken_for_missing(parameter: str) -> Predicate:
    """The parameter ``parameter`` tested for truth where a default replaces it: ``parameter or X``,
    ``X if parameter else Y``, ``if not parameter:`` / ``if parameter:`` (0 is false, as ``None`` is)."""
    def named(node) -> bool:
        return isinstance(node, ast.Name) and node.id == parameter

    def truth_test(node) -> bool:
        return named(node) or isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not) and named(node.operand)

    def test(function) -> bool:
        if parameter not in _parameters(function):
            return False
        for node in walk(function):
            if isinstance(node, ast.BoolOp) and isinstance(node.op, ast.Or) and named(node.values[0]):
                return True
            if isinstance(node, (ast.If, ast.IfExp)) and truth_test(node.test):
                return True
        return False
    return Predicate(f"tests {parameter} for truth ({parameter} or ..., if not {parameter})", test)


def _divides_by_name_or_entry(names: tuple[str, ...], index: int) -> Predicate:
    """A division by one of ``names`` or by the entry ``index`` of anything (``line[1]``, ``l[:, 1]``)."""
    patterns = [*names, f"_[{index}]", f"_[:, {index}]", f"_[..., {index}]", f"_[i, {index}]"]
    return divides_by(*patterns)


# Lines a x + b y + c = 0 drawn as y = -(a x + c) / b only: a division by b, none by a.
LINES_FROM_SIDES_ONLY = (_divides_by_name_or_entry(("b",), 1) & ~_divides_by_name_or_entry(("a",), 0)).saying(
    "computes each line's y from x, y = -(a x + c) / b (it divides by b, never by a)")


def _skips_zero_b(function) -> bool:
    """An ``if`` testing a line's ``b`` against zero (``b == 0``, ``abs(b) < 1e-12``, ``np.isclose(b, 0)``)
    whose body skips the line (``continue``): vertical lines are never drawn."""
    for node in walk(function):
        if not isinstance(node, ast.If) or not any(isinstance(n, ast.Continue) for n in node.body):
            continue
        names = {n.id for n in walk(node.test) if isinstance(n, ast.Name)}
        numbers = [n.value for n in walk(node.test) if isinstance(n, ast.Constant)
                   and isinstance(n.value, (int, float)) and not isinstance(n.value, bool)]
        if "b" in names and numbers and all(abs(v) < 1e-3 for v in numbers):
            return True
    return False


# Lines with b = 0 (vertical) skipped before y = -(a x + c) / b is computed.
SKIPS_VERTICAL = Predicate("skips every line with b = 0 (`if ...: continue`)", _skips_zero_b)


_STACKS = ("hstack", "column_stack", "concatenate", "c_")


def _stacked(node) -> bool:
    """``np.hstack([R, t])``, ``np.column_stack((R, t))``, ``np.concatenate([R, t], axis=1)``, ``np.c_[R, t]``,
    ``np.eye(3, 4)`` (a camera's ``[I | 0]``)."""
    if isinstance(node, ast.Call):
        last = _path(node.func).rsplit(".", 1)[-1]
        if last == "eye" and len(node.args) == 2:
            return True
        if last in _STACKS and node.args and isinstance(node.args[0], (ast.List, ast.Tuple)) \
                and len(node.args[0].elts) == 2:
            return True
    return isinstance(node, ast.Subscript) and _path(node.value).rsplit(".", 1)[-1] == "c_"


def _products(function) -> list[ast.AST]:
    """The operands of every matrix product in ``function`` (``a @ b``, ``np.dot(a, b)``, ``a.dot(b)``)."""
    operands = []
    for node in walk(function):
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.MatMult, ast.Mult)):
            operands += [node.left, node.right]
        elif isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("dot", "matmul"):
            operands += list(node.args) + ([node.func.value] if isinstance(node.func, ast.Attribute) else [])
    return operands


def _camera_without_k(function) -> bool:
    """A stacked ``[R | t]`` (or ``[I | 0]``) assigned to a name or passed on, that no product takes (and whose
    rotation part is no product: ``np.hstack([K @ R, t])`` has K in it, on R's columns only; ``[R, -R @ C]``
    computes its translation, without K)."""
    multiplied = _products(function)
    multiplied_names = {n.id for operand in multiplied for n in walk(operand) if isinstance(n, ast.Name)}
    multiplied_nodes = {id(n) for operand in multiplied for n in walk(operand)}

    def bare(stack) -> bool:
        parts = stack.args[0].elts if isinstance(stack, ast.Call) and stack.args \
            and isinstance(stack.args[0], (ast.List, ast.Tuple)) else []
        return _stacked(stack) and id(stack) not in multiplied_nodes and not (parts and _products(parts[0]))
    for node in walk(function):
        if isinstance(node, ast.Assign) and bare(node.value):
            names = {t.id for t in node.targets if isinstance(t, ast.Name)}
            if names and not names & multiplied_names:
                return True
        if isinstance(node, ast.Call) and any(bare(a) for a in node.args) \
                and _path(node.func).rsplit(".", 1)[-1] not in _STACKS:
            return True
    return False


NORMALISES_POINTS = (calls_any("np.linalg.inv", "np.linalg.solve", "np.linalg.pinv", "cv2.undistortPoints",
                               "cv2.undistortImagePoints")).saying("normalises its points with K^-1")
CAMERA_WITHOUT_K = (Predicate("builds a camera [R | t] without K", _camera_without_k) & ~NORMALISES_POINTS).saying(
    "builds a camera matrix [R | t] (or [I | 0]) without K and triangulates pixels with it")


# ------------------------------------------------------------------ shapes that say where the index went
def _inverts_a_gram_matrix(function) -> bool:
    """The normal equations solved by an inverse: ``np.linalg.inv(A.T @ A)`` (a product with a transpose
    inside the inverse), where inverting a normalising transform (``np.linalg.inv(T)``) has none."""
    for node in walk(function):
        if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == "inv" and node.args:
            inside = list(walk(node.args[0]))
            product = any((isinstance(n, ast.BinOp) and isinstance(n.op, ast.MatMult))
                          or (isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] in ("dot", "matmul"))
                          for n in inside)
            transposed = any((isinstance(n, ast.Attribute) and n.attr == "T")
                             or (isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] == "transpose")
                             for n in inside)
            if product and transposed:
                return True
    return False


# Least squares over fewer unknowns (an entry fixed to 1), where an SVD may still be called for another step (F's
# rank 2): a solver's call, or the normal equations inverted.
SOLVES_LEAST_SQUARES = calls_any("np.linalg.lstsq", "np.linalg.solve", "np.linalg.pinv", "scipy.linalg.lstsq") \
    | Predicate("inverts A^T A (the normal equations)", _inverts_a_gram_matrix)
SOLVES_BY_SVD = (calls("np.linalg.svd") & ~SOLVES_LEAST_SQUARES).saying("solves by np.linalg.svd")


LAST_VT_OF_A_STACK = "the last row of a batched SVD's Vt is taken (Vt[-1]) instead of each system's (Vt[:, -1])"
TAKES_LAST_ROW_OF_VT = takes_last_row_of_vt()


def _svd_in_a_loop(functions) -> bool:
    """Whether the functions read take an SVD inside a loop (or a comprehension): one system at a time."""
    for function in functions:
        for loop in walk(function):
            inside = loop.body if isinstance(loop, (ast.For, ast.While)) else \
                [loop.elt] if isinstance(loop, (ast.ListComp, ast.GeneratorExp)) else []
            if any(isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] in ("svd", "SVDecomp")
                   for part in inside for n in walk(part)):
                return True
    return False


def name_batched_vt_row(t, what: str, got, n: int, size: int = 4, function: str = "triangulate"):
    """Fail naming ``Vt[-1]`` of an SVD of a stack of ``size x size`` systems when the answer has
    ``size`` rows for ``n`` points (its first dimension is the system's size, not N: measured) and the
    code takes the last row of an SVD's Vt (read). ``Vt`` of an ``(N, 4, 4)`` stack is ``(N, 4, 4)``:
    ``Vt[-1]`` is the last point's whole ``Vt``, each point's solution is ``Vt[:, -1]``."""
    if not (isinstance(got, np.ndarray) and got.ndim == 2 and got.shape[0] == size != n):
        return
    read = code_of(t).reachable([function])
    found = TAKES_LAST_ROW_OF_VT.found(read)
    if not found or _svd_in_a_loop(read):
        return   # (an SVD per system, in a loop: its Vt[-1] is that system's solution, and the rows went elsewhere)
    t.fail(f"{what} returned shape {got.shape} for {n} points: {size} rows is the size of each point's "
           f"{size} x {size} system, not the number of points. It looks like {LAST_VT_OF_A_STACK}: your code "
           + from_code(f"takes Vt[-1]; for A of shape (N, {size}, {size}) np.linalg.svd gives Vt of shape "
                       f"(N, {size}, {size}), so Vt[-1] is the last point's whole Vt and each point's solution "
                       "is Vt[:, -1] (shape (N, 4)), or solve the points one at a time."),
           mistake=LAST_VT_OF_A_STACK)


# ------------------------------------------------------------------ an answer off by a constant factor
ROUND_FACTORS = {16.0: "16 times", 1 / 16: "1/16 of", 2.0: "twice", 0.5: "half", -1.0: "the negative of",
                 255.0: "255 times", 1 / 255: "1/255 of", 1000.0: "1000 times", 1e-3: "1/1000 of",
                 100.0: "100 times", 1e-2: "1/100 of", 10.0: "10 times", 0.1: "1/10 of", 4.0: "4 times",
                 0.25: "a quarter of"}


def constant_factor(got, expected, relative: float = 1e-6) -> float | None:
    """The factor ``c`` with ``got == c * expected`` entry by entry (within ``relative`` of the largest
    ``|c * expected|``, on the entries finite in both), when it is not 1; None otherwise."""
    got, expected = np.asarray(got, np.float64), np.asarray(expected, np.float64)
    if got.shape != expected.shape:
        return None
    both = np.isfinite(got) & np.isfinite(expected)
    if both.sum() < 2 or not np.any(expected[both]):
        return None
    g, e = got[both], expected[both]
    c = float(np.dot(g, e) / np.dot(e, e))
    scale = abs(c) * float(np.max(np.abs(e)))
    if c == 0 or abs(c - 1) <= 1e-3 or np.max(np.abs(g - c * e)) > relative * scale + 1e-300:
        return None
    return c


def factor_words(c: float) -> str:
    """``c`` in words: "16 times", "half", "the negative of" (a round factor within 1%), else "2.37 times"."""
    for value, words in ROUND_FACTORS.items():
        if abs(c / value - 1) <= 0.01:
            return words
    return f"{c:.3g} times"
