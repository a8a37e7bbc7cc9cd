"""Reading the submitted code, never running it: causes only the source shows.

Some mistakes leave no mark the outputs can name: ``np.linalg.eig`` picks an
eigenvector in an order of its own, an integer array truncates what is written
into it, ``//`` floors coordinates, uint8 images wrap around when subtracted,
OpenCV's masks of 0 and 1 select rows 0 and 1 when used as indices. This module
reads the student's module with Python's :mod:`ast` (the text is parsed, never
executed) and lists, per top-level function, the places that do such things
(:class:`Finding`).

A finding takes no points by itself: the runner uses it only to name the cause of
a failure a check has already measured in a function that holds it, or calls a
helper holding it (:func:`findings_for`), and only when the check named no
confirmed mistake of its own. Findings whose cause shows in the values are used
only when the values show it (:attr:`Finding.needs`: a function given fractional
numbers that returned only whole ones).

Reading is bounded and linear in the source: a module beyond the grader's bounds on
parsing (:data:`MAX_SOURCE_BYTES` characters,
:data:`autograder.loading.parsing.MAX_PARSE_STATEMENTS` statements), or nested too
deeply to parse, or with more than :data:`MAX_NODES` syntax nodes, is not read
(:attr:`Reading.note` says why); nothing in a source can make it raise. Parsing holds
:data:`autograder.loading.parsing.PARSE_LOCK` (``ast`` is not thread-safe).
"""

from __future__ import annotations

import ast
import bisect
import re
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path

from .parsing import MAX_PARSE_CHARS, TooLarge, parse, walk

MAX_SOURCE_BYTES = MAX_PARSE_CHARS   # characters (the file's bytes are checked first, the same number)
MAX_NODES = 400_000

# Parameter names the labs' APIs give uint8 images (see the skeletons' docstrings).
IMAGE_PARAMETERS = frozenset({"image", "img", "img1", "img2", "img_l", "img_r", "left", "right", "moving",
                              "reference", "frame", "distorted"})
# OpenCV calls that return an image of their first argument's dtype.
IMAGE_FUNCTIONS = frozenset({"warpPerspective", "warpAffine", "cvtColor", "resize", "remap", "pyrDown",
                             "pyrUp", "GaussianBlur", "blur", "medianBlur", "copyMakeBorder", "flip",
                             "undistort", "imread"})
# OpenCV calls whose second result (fourth for recoverPose) is a uint8 mask of 0 and 1.
MASK_FUNCTIONS = {"findHomography": 1, "findFundamentalMat": 1, "findEssentialMat": 1, "recoverPose": 3,
                  "estimateAffine2D": 1, "estimateAffinePartial2D": 1}
OPENCV_DISTORTION = ("k1", "k2", "p1", "p2", "k3")
EIGEN_ORDERING = frozenset({"argsort", "argmin", "argmax", "sort", "sorted", "min", "max", "lexsort"})


@dataclass(frozen=True)
class Finding:
    """A place in one function whose code causes a known mistake.

    ``mistake`` names it in a few words (a check's ``mistake`` field); ``sentence``
    says it to the student; ``needs`` is what the measured values must show for the
    finding to be the cause (``""``: a failure is enough; ``"whole numbers"``: the
    function turned fractional inputs into whole-number outputs).
    """

    function: str
    line: int
    mistake: str
    sentence: str
    needs: str = ""
    certain: bool = False   # a slip wherever it is written: said beside a check's own name of the effect too


@dataclass(frozen=True)
class Reading:
    """What reading one module found: each top-level function's findings and the module's
    functions each one calls (its helpers)."""

    findings: dict
    calls: dict
    note: str = ""   # why the module was not read ("" when it was, or could not be parsed)

    def reachable(self, function: str) -> list[str]:
        """``function`` and the module's functions it calls, directly or through others."""
        seen, order, todo = set(), [], [function]
        while todo:
            name = todo.pop()
            if name in seen or name not in self.calls:
                continue
            seen.add(name)
            order.append(name)
            todo.extend(sorted(self.calls[name]))
        return order


NOTHING = Reading({}, {})


def _not_read(why: str) -> Reading:
    return Reading({}, {}, f"the code was not read for causes of mistakes: it holds {why}")


def read_file(path, api=frozenset()) -> Reading:
    """The reading of the module at ``path`` (nothing when it cannot be read); cached per version."""
    try:
        stat = Path(path).stat()
    except (OSError, TypeError, ValueError):
        return NOTHING
    return _read_file(str(path), stat.st_mtime_ns, stat.st_size, frozenset(api))


@lru_cache(maxsize=64)
def _read_file(path: str, mtime_ns: int, size: int, api: frozenset) -> Reading:
    if size > MAX_SOURCE_BYTES * 4:  # at most 4 bytes a character: surely more characters than read
        return _not_read(f"more than {MAX_SOURCE_BYTES:,} characters")
    try:
        text = Path(path).read_bytes().decode("utf-8", errors="replace")
    except OSError:
        return NOTHING
    return read_source(text, api)


def read_source(text: str, api=frozenset()) -> Reading:
    """The findings of every top-level function of the module ``text`` (never raises).

    ``api`` names the lab's functions: only their image parameters are known to hold
    uint8 images (a helper's parameters may hold anything)."""
    try:
        tree = parse(text)   # within the bounds, under the lock
        if sum(1 for _ in walk(tree)) > MAX_NODES:
            return _not_read(f"more than {MAX_NODES:,} syntax nodes")
        functions = {node.name: node for node in tree.body if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))}
        # (the module's own lists: `results = []` at the top level, which a function may grow at every call)
        lists = frozenset(target.id for node in tree.body if isinstance(node, ast.Assign)
                          and (isinstance(node.value, (ast.List, ast.ListComp))
                               or isinstance(node.value, ast.Call) and _call_name(node.value) == "list")
                          for target in node.targets if isinstance(target, ast.Name))
        # (and its arrays: `ORTHOGRAPHIC = np.array(...)` at the top level, which a function may change in place)
        arrays = frozenset(target.id for node in tree.body if isinstance(node, ast.Assign)
                           and isinstance(node.value, ast.Call) and _call_name(node.value) in _MODULE_ARRAYS
                           for target in node.targets if isinstance(target, ast.Name))
        # (and its helpers that filter their first parameter: `_box_mean(cost, k)` is a cv2.blur)
        filtering = frozenset(_FILTERS) | frozenset(name for name, node in functions.items() if _filters_first(node))
        # (and its helpers that give back their first argument's dtype: `_shift_right(image, d)` of a uint8 image)
        keeping = frozenset(name for name, node in functions.items() if _safely_bool(_keeps_first_dtype, node))
        findings, calls = {}, {}
        rows = {name: _read_as_rows(node) for name, node in functions.items()}
        for name, node in functions.items():
            findings[name] = _read_function(node, name in api, lists, keeping) \
                + _safely(_transposed_into_rows, name, node, functions, rows) \
                + _safely(_module_array_changed, name, node, arrays) + _safely(_infinity_filtered, name, node, filtering)
            calls[name] = {called for called in _called_names(node) if called in functions and called != name}
        return Reading(findings, calls)
    except TooLarge as exc:
        return _not_read(str(exc))
    except (SyntaxError, ValueError, RecursionError, MemoryError, TypeError, AttributeError):
        return NOTHING


def findings_for(reading: Reading, functions, values_show_whole_numbers: bool) -> list[Finding]:
    """The findings that may name the cause of a failure in ``functions`` (the student functions
    a check called): theirs first, then their helpers', each kind once; a finding that needs
    whole numbers only when the values showed them."""
    chosen, kinds = [], set()
    for function in sorted(functions):
        for name in reading.reachable(function):
            for finding in reading.findings.get(name, ()):
                if finding.needs == "whole numbers" and not values_show_whole_numbers:
                    continue
                if finding.mistake not in kinds:
                    kinds.add(finding.mistake)
                    chosen.append(finding)
    return chosen


# ------------------------------------------------------------------ one function calling another
def _read_as_rows(function) -> dict[str, str]:
    """The parameters ``function`` reads as one point per row, with the code that shows it: reshaped to
    (-1, k) (`np.asarray(pts1).reshape(-1, 2)`) or sliced by column (`pts1[:, 0]`)."""
    parameters = {a.arg for a in function.args.posonlyargs + function.args.args}
    found = {}
    for node in _nodes(function):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "reshape" \
                and len(node.args) == 2 and isinstance(node.args[0], ast.UnaryOp) \
                and isinstance(node.args[1], ast.Constant) and node.args[1].value in (2, 3):
            named = {n.id for n in walk(node.func.value) if isinstance(n, ast.Name)} & parameters
        elif isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in parameters \
                and isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2 \
                and isinstance(node.slice.elts[0], ast.Slice) and node.slice.elts[0].lower is None \
                and node.slice.elts[0].upper is None and isinstance(node.slice.elts[1], ast.Constant):
            named = {node.value.id}
        else:
            continue
        for parameter in named:
            found.setdefault(parameter, f"`{ast.unparse(node)}` (line {_line(node)})")
    return found


def _transposed_into_rows(name, function, functions, rows) -> list[Finding]:
    """A transposed array (`pts1.T`) given to one of the module's own functions that reads that parameter
    as one point per row: OpenCV's 2 x N convention (cv2.triangulatePoints) kept for a function of the
    (N, 2) kind, whose rows then mix the points' coordinates."""
    for node in _nodes(function):
        if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in functions
                and node.func.id != name):
            continue
        callee = functions[node.func.id]
        parameters = [a.arg for a in callee.args.posonlyargs + callee.args.args]
        for parameter, argument in zip(parameters, node.args):
            if isinstance(argument, ast.Attribute) and argument.attr == "T" and parameter in rows[callee.name]:
                return [Finding(name, _line(node), "points transposed into a function that reads them as rows",
                                f"{name} (line {_line(node)}) calls `{ast.unparse(node)}`: `{callee.name}` reads "
                                f"`{parameter}` as one point per row ({rows[callee.name][parameter]}), so "
                                f"`{ast.unparse(argument)}` (a row per coordinate, as cv2.triangulatePoints takes "
                                "points) has its coordinates mixed into wrong points")]
    return []


# ------------------------------------------------------------------ one function
def _safely(reader, *args) -> list[Finding]:
    """``reader(*args)``, or nothing where it fails on code nobody foresaw: one reader's slip must not cost the
    module every other reader's findings."""
    try:
        return reader(*args)
    except (ValueError, TypeError, AttributeError, IndexError, KeyError, StopIteration):
        return []


def _safely_bool(reader, *args) -> bool:
    """``reader(*args)``, or False where it fails on code nobody foresaw (as :func:`_safely`)."""
    try:
        return bool(reader(*args))
    except (ValueError, TypeError, AttributeError, IndexError, KeyError, StopIteration):
        return False


def _read_function(function: ast.FunctionDef, api: bool = False, lists=frozenset(), keeping=frozenset()) -> list[Finding]:
    name = function.name
    parameters = {a.arg for a in function.args.args + function.args.kwonlyargs + function.args.posonlyargs}
    images = parameters if api else set()
    found: list[Finding] = []
    found += _safely(_eig_unsorted, name, function)
    found += _safely(_integer_arrays, name, function)
    found += _safely(_floor_division, name, function)
    found += _safely(_uint8_arithmetic, name, function, images, keeping)
    found += _safely(_homogeneous_zero, name, function)
    found += _safely(_query_train, name, function)
    found += _safely(_mask_as_index, name, function)
    found += _safely(_distortion_order, name, function, parameters)
    found += _safely(_camera_left_out, name, function)
    found += _safely(_view_overwritten, name, function)
    found += _safely(_seeded_in_a_loop, name, function)
    found += _safely(_data_shuffled_in_a_loop, name, function)
    found += _safely(_mean_after_centring, name, function)
    found += _safely(_w_never_divided, name, function)
    found += _safely(_diagonal_refilled, name, function)
    found += _safely(_constant_out_of_place, name, function)
    found += _safely(_last_turn_used, name, function)
    found += _safely(_third_operand_as_out, name, function)
    found += _safely(_twin_lopsided, name, function)
    found += _safely(_alias_changed, name, function)
    found += _safely(_kept_alias_rewritten, name, function)
    found += _safely(_chained_one_array, name, function)
    found += _safely(_searched_unsorted, name, function)
    found += _safely(_late_bound_lambda, name, function)
    found += _safely(_empty_rows_skipped, name, function)
    found += _safely(_views_merged, name, function)
    found += _safely(_row_norm_of_whole_matrix, name, function)
    found += _safely(_same_array_appended, name, function)
    found += _safely(_one_object_repeated, name, function)
    found += _safely(_comparison_as_a_statement, name, function)
    found += _safely(_running_best_overwritten, name, function)
    found += _safely(_rolled_strip_one_sign, name, function)
    found += _safely(_scaled_in_place_per_turn, name, function)
    found += _safely(_written_into_a_copy, name, function)
    found += _safely(_pose_never_chosen, name, function)
    found += _safely(_distortion_in_pixels, name, function)
    found += _safely(_loop_variable_rebinds, name, function)
    found += _safely(_loop_variable_hides_a_value, name, function)
    found += _safely(_pairs_drawn_apart, name, function)
    found += _safely(_pairs_reordered_apart, name, function)
    found += _safely(_homogeneous_centred, name, function)
    found += _safely(_keypoints_sorted_apart, name, function)
    found += _safely(_mutable_default_written, name, function)
    found += _safely(_conditional_in_a_tuple, name, function)
    found += _safely(_loop_variable_assigned_in_vain, name, function)
    found += _safely(_fisheye_model, name, function)
    found += _safely(_identity_with_a_literal, name, function)
    found += _safely(_rotation_matrix_made_a_vector, name, function)
    found += _safely(_value_of_an_earlier_loop, name, function)
    found += _safely(_running_halves, name, function)
    found += _safely(_norm_of_every_pair_at_once, name, function)
    found += _safely(_whole_norm_divides_vectors, name, function)
    found += _safely(_homogeneous_one_scaled, name, function)
    found += _safely(_determinant_compared_exactly, name, function)
    found += _safely(_flags_joined_with_or, name, function)
    found += _safely(_singular_vectors_unused, name, function)
    found += _safely(_zeros_solved_for, name, function)
    found += _safely(_fundamental_as_essential, name, function)
    found += _safely(_eigenvectors_as_rows, name, function)
    found += _safely(_sign_lost_by_a_root, name, function)
    found += _safely(_dimension_tested_after_reshaping, name, function)
    found += _safely(_outliers_kept, name, function)
    found += _safely(_root_by_a_fraction, name, function)
    found += _safely(_grid_unpacked_as_x_y, name, function)
    found += _safely(_result_rounded, name, function)
    found += _safely(_where_tuple_counted, name, function)
    found += _safely(_null_vector_by_argmin, name, function)
    found += _safely(_rows_repeated, name, function)
    found += _safely(_reciprocal_as_inverse, name, function)
    found += _safely(_comparison_through_bitwise, name, function)
    found += _safely(_iterator_read_twice, name, function)
    found += _safely(_state_kept_between_calls, name, function, lists)
    return found


def _attribute_path(node) -> str:
    """``np.linalg.eig`` for the expression ``np.linalg.eig`` ("" for anything else)."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        parts.append(node.id)
        return ".".join(reversed(parts))
    return ""


def _nodes(function) -> tuple[ast.AST, ...]:
    """Every node of ``function`` in ``ast.walk`` order, walked once and kept on the node: some forty
    findings each look through the whole function, and walking it afresh for each costs more than
    all their tests together."""
    nodes = getattr(function, "_walked", None)
    if nodes is None:
        nodes = tuple(walk(function))
        function._walked = nodes
    return nodes


def _call_name(call: ast.Call) -> str:
    """The last name of what is called: ``eig`` for ``np.linalg.eig(...)``, ``hstack`` ..."""
    func = call.func
    if isinstance(func, ast.Attribute):
        return func.attr
    if isinstance(func, ast.Name):
        return func.id
    return ""


def _called_names(function) -> set[str]:
    """The names ``function`` reads: those it calls, and those it passes or picks to call later
    (``(_ssd_volume if cost == "ssd" else _ncc_volume)(...)``, ``map(_helper, ...)``)."""
    return {node.id for node in _nodes(function) if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)}


def _names_in(node) -> set[str]:
    return {n.id for n in walk(node) if isinstance(n, ast.Name)}


_UNKNOWN = ast.Constant(value=None)   # a value the reading cannot follow (an unpacked call...)


def _assigned_names(function) -> dict[str, list[ast.AST]]:
    """name -> the values assigned to it: ``name = value``, ``a, b = x, y`` pairwise, and an
    unknown value for every other binding (``a, b = f()``, loops, ``with``, augmented)."""
    out: dict[str, list[ast.AST]] = {}

    def bind(target, value):
        if isinstance(target, ast.Name):
            out.setdefault(target.id, []).append(value)
        elif isinstance(target, (ast.Tuple, ast.List)):
            values = value.elts if isinstance(value, (ast.Tuple, ast.List)) and \
                len(value.elts) == len(target.elts) else [_UNKNOWN] * len(target.elts)
            for sub, sub_value in zip(target.elts, values):
                bind(sub, sub_value)
        elif isinstance(target, ast.Starred):
            bind(target.value, _UNKNOWN)

    for node in _nodes(function):
        if isinstance(node, ast.Assign):
            for target in node.targets:
                bind(target, node.value)
        elif isinstance(node, ast.AnnAssign) and node.value is not None:
            bind(node.target, node.value)
        elif isinstance(node, (ast.For, ast.AsyncFor, ast.comprehension)):
            bind(node.target, _UNKNOWN)
        elif isinstance(node, ast.withitem) and node.optional_vars is not None:
            bind(node.optional_vars, _UNKNOWN)
        elif isinstance(node, ast.NamedExpr):
            bind(node.target, node.value)
    return out


def _line(node) -> int:
    return int(getattr(node, "lineno", 0) or 0)


# ------------------------------------------------------------------ np.linalg.eig
def _eig_unsorted(name, function) -> list[Finding]:
    """``eig`` (not ``eigh``) whose eigenvalues are never used to choose a vector."""
    eig_calls = [node for node in _nodes(function) if isinstance(node, ast.Call) and _call_name(node) == "eig"]
    if not eig_calls:
        return []
    ordering = {_call_name(node) for node in _nodes(function) if isinstance(node, ast.Call)}
    if ordering & EIGEN_ORDERING:
        return []   # the eigenvalues may well choose the vector: no finding
    call = eig_calls[0]
    return [Finding(name, _line(call), "np.linalg.eig's eigenvalues are not sorted",
                    f"{name} (line {_line(call)}) calls np.linalg.eig, whose eigenvalues are not sorted: "
                    "its last column is not the eigenvector of the smallest eigenvalue (use "
                    "np.linalg.eigh, which sorts them in ascending order, or take the last row of Vt "
                    "from np.linalg.svd)")]


# ------------------------------------------------------------------ integer arrays
def _is_integer_dtype(node) -> bool:
    if isinstance(node, ast.Name) and node.id == "int":
        return True
    if isinstance(node, ast.Constant) and isinstance(node.value, str):   # not "uint8": images are
        return node.value in ("int", "int16", "int32", "int64", "i4", "i8")
    path = _attribute_path(node)
    return path.split(".")[-1] in {"int_", "intc", "int16", "int32", "int64"} if path else False


def _integer_arrays(name, function) -> list[Finding]:
    """An array made with an integer dtype (or from a literal of whole numbers, ``np.array([[1, 0, 0], ...])``),
    then written into with computed values. Where what is written is fractional by its making (a division, a
    root, a mean: a conditioning matrix's scale), the finding needs no measure: every value written is cut."""
    integer_arrays = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and isinstance(node.value, ast.Call) and (_integer_dtype_given(node.value) or _whole_literal(node.value)):
            integer_arrays[node.targets[0].id] = node
    bindings = None
    for node in _nodes(function):
        if not isinstance(node, ast.Assign):
            continue
        for target in node.targets:
            if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name) \
                    and target.value.id in integer_arrays and _computed(node.value) \
                    and not _integral_by_making(node.value, integer_arrays):
                made = integer_arrays[target.value.id]
                bindings = _bindings(function) if bindings is None else bindings
                fractional = _fractional(node.value, bindings)
                how = "dtype=int" if _integer_dtype_given(made.value) else "from a literal of whole numbers, no dtype"
                return [Finding(name, _line(made), "an integer array: the values written into it are truncated",
                                f"{name} (line {_line(made)}) makes {target.value.id} an integer array "
                                f"({how}) and writes computed values into it (line {_line(node)}): "
                                "their fractions are cut off; make it a float array (dtype=float)",
                                needs="" if fractional else "whole numbers", certain=fractional)]
    return []


_INTEGRAL_OPERATIONS = (ast.Add, ast.Sub, ast.Mult, ast.FloorDiv, ast.Mod)


_INTEGRAL_DEPTH = 8   # operations followed into a value written (a longer chain is read as not whole)


def _integral_by_making(node, integer_arrays: dict, depth: int = _INTEGRAL_DEPTH) -> bool:
    """Whether a value written is whole by its making: read from one of the integer arrays (a backtrack's
    `disp[:, x - 1] = back[x][rows, disp[:, x]]`), or whole-number arithmetic on such values: nothing to cut.
    Each side is read once, :data:`_INTEGRAL_DEPTH` operations deep at most."""
    if isinstance(node, ast.Subscript):
        base = node.value
        while isinstance(base, ast.Subscript):
            base = base.value
        return isinstance(base, ast.Name) and base.id in integer_arrays
    if isinstance(node, ast.Name):
        return node.id in integer_arrays
    if depth <= 0:
        return False
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        return _integral_by_making(node.operand, integer_arrays, depth - 1)
    if isinstance(node, ast.BinOp) and isinstance(node.op, _INTEGRAL_OPERATIONS):
        read = [_integral_by_making(side, integer_arrays, depth - 1) for side in (node.left, node.right)]
        return any(read) and all(whole or _constant_integers(side)
                                 for whole, side in zip(read, (node.left, node.right)))
    return False


def _integer_dtype_given(call: ast.Call) -> bool:
    """``np.zeros(..., dtype=int)`` and its kin."""
    return _call_name(call) in {"zeros", "ones", "empty", "eye", "identity", "full", "zeros_like", "array"} \
        and any(k.arg == "dtype" and _is_integer_dtype(k.value) for k in call.keywords)


def _whole_literal(call: ast.Call) -> bool:
    """``np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1]])``: an array of a literal of whole numbers, its dtype left to NumPy."""
    if _call_name(call) not in ("array", "asarray") or len(call.args) != 1 or call.keywords \
            or not isinstance(call.args[0], (ast.List, ast.Tuple)):
        return False
    leaves = [n for n in walk(call.args[0]) if not isinstance(n, (ast.List, ast.Tuple, ast.Load, ast.UnaryOp, ast.USub))]
    return bool(leaves) and all(isinstance(n, ast.Constant) and type(n.value) is int for n in leaves)


_FRACTIONAL_CALLS = frozenset({"sqrt", "mean", "std", "norm", "cos", "sin", "tan", "arctan2", "average", "median"})


def _fractional(node, bindings, depth: int = 2) -> bool:
    """Whether an expression is fractional by its making: a true division, a root, a mean, a norm, a sine, a float
    constant (or a name whose last binding above is such an expression, followed ``depth`` bindings back)."""
    for sub in walk(node):
        if isinstance(sub, ast.BinOp) and isinstance(sub.op, ast.Div) \
                or isinstance(sub, ast.Call) and _call_name(sub) in _FRACTIONAL_CALLS \
                or isinstance(sub, ast.Constant) and type(sub.value) is float:
            return True
        if isinstance(sub, ast.Name) and depth:
            above = _binding_above(bindings, sub.id, _line(node))
            if above is not None and above[2] is None and above[1] is not _UNKNOWN \
                    and _fractional(above[1], bindings, depth - 1):
                return True
    return False


def _computed(node) -> bool:
    """A variable or arithmetic on variables (or a list of such): what geometry writes into an
    array; not a call (``np.argmin`` gives integers) nor integer constants."""
    if isinstance(node, (ast.List, ast.Tuple)):
        return any(_computed(element) for element in node.elts)
    if isinstance(node, (ast.Name, ast.Attribute, ast.Subscript)):
        return True
    if isinstance(node, (ast.BinOp, ast.UnaryOp)):
        return not _constant_integers(node) and not any(isinstance(sub, ast.Call) for sub in walk(node))
    return False


def _constant_integers(node) -> bool:
    """Whether an expression is made only of integer constants (nothing is truncated then)."""
    for sub in walk(node):
        if isinstance(sub, (ast.Name, ast.Attribute, ast.Call, ast.Subscript)):
            return False
        if isinstance(sub, ast.Constant) and not isinstance(sub.value, (int, bool)):
            return False
    return True


def _constant_integer_nodes(tree) -> set[int]:
    """The ids of the nodes under ``tree`` made only of integer constants (as
    :func:`_constant_integers` judges each), found in one pass from the leaves up: asking
    each ``//`` of a chain ``1 // 1 // ... // 1`` in turn walked it again (quadratic)."""
    order, pending = [], [tree]
    while pending:  # parents before children; reversed, children before parents
        node = pending.pop()
        order.append(node)
        pending.extend(ast.iter_child_nodes(node))
    constant: set[int] = set()
    for node in reversed(order):
        if isinstance(node, (ast.Name, ast.Attribute, ast.Call, ast.Subscript)):
            continue
        if isinstance(node, ast.Constant) and not isinstance(node.value, (int, bool)):
            continue
        if all(id(child) in constant for child in ast.iter_child_nodes(node)):
            constant.add(id(node))
    return constant


# ------------------------------------------------------------------ floor division
def _floor_division(name, function) -> list[Finding]:
    """``//`` between expressions that are not both integer constants (floors fractions)."""
    divisions = [node for node in _nodes(function)
                 if isinstance(node, (ast.BinOp, ast.AugAssign)) and isinstance(node.op, ast.FloorDiv)]
    constant = _constant_integer_nodes(function) if divisions else set()
    for node in divisions:
        left = node.left if isinstance(node, ast.BinOp) else node.target
        if id(left) in constant and id(node.right) in constant:
            continue
        return [Finding(name, _line(node), "// floors the results to whole numbers",
                        f"{name} (line {_line(node)}) uses // (floor division), which rounds its "
                        "result down to a whole number: use / for coordinates, depths and "
                        "focal lengths", needs="whole numbers")]
    return []


# ------------------------------------------------------------------ uint8 arithmetic
_FLOAT_MAKERS = {"float32", "float64", "float_", "double", "single"}


def _to_float(node) -> bool:
    """Whether an expression surely gives a float array (a conversion, a true division...)."""
    if isinstance(node, ast.Call):
        call = _call_name(node)
        if call == "astype" or call in _FLOAT_MAKERS:
            return True
        if call in {"asarray", "array", "asanyarray"} and any(k.arg == "dtype" for k in node.keywords):
            return True
        if call in {"asarray", "array"} and len(node.args) >= 2:
            return True
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div):
        return True
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and any(
            isinstance(side, ast.Constant) and isinstance(side.value, float) for side in (node.left, node.right)):
        return True
    return False


def _uint8_names(function, parameters, keeping=frozenset(), seeds=None) -> set[str]:
    """Names that surely hold uint8 images: image parameters (or ``seeds``) never bound to anything else,
    and what image functions, slices, copies, ``zeros_like`` and the module's helpers ``keeping`` their
    first argument's dtype make of them (a name bound even once to something else -- a conversion, a call
    the reading cannot follow -- is not one)."""
    assigned = _assigned_names(function)
    seeds = {p for p in parameters if p in IMAGE_PARAMETERS} if seeds is None else set(seeds)
    images = set(seeds)
    for _ in range(4):   # a few rounds: names made from names made from images
        changed = False
        for target, values in assigned.items():
            uint8 = bool(values) and all(_is_uint8_expression(value, images | {target}, keeping=keeping) for value in values)
            if target in seeds:
                uint8 = all(_is_uint8_expression(value, images | {target}, keeping=keeping) for value in values)
            if uint8 and target not in images:
                images.add(target)
                changed = True
            elif not uint8 and target in images:
                images.discard(target)
                changed = True
        if not changed:
            break
    return images


def _uint8_lists(function, images, keeping=frozenset()) -> set[str]:
    """Names that surely hold lists of uint8 images (a pyramid: `g = [img]`, then `g.append(cv2.pyrDown(g[i]))`):
    bound only to list displays of uint8 images, and given only uint8 images by `.append`/`.insert`."""
    assigned = _assigned_names(function)
    lists = {name for name, values in assigned.items()
             if values and all(isinstance(v, (ast.List, ast.Tuple)) and v.elts for v in values)}
    for _ in range(4):
        def uint8(node) -> bool:
            return (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in lists) \
                or _is_uint8_expression(node, images, lists, keeping)
        kept = {name for name in lists if all(uint8(e) for v in assigned[name] for e in v.elts)}
        for node in _nodes(function):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in ("append", "insert") \
                    and isinstance(node.func.value, ast.Name) and node.func.value.id in kept \
                    and not (node.args and uint8(node.args[-1])):
                kept.discard(node.func.value.id)
            elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "extend" \
                    and isinstance(node.func.value, ast.Name):
                kept.discard(node.func.value.id)   # (what it is extended by is not followed)
            elif isinstance(node, ast.AugAssign) and isinstance(node.target, ast.Name):
                kept.discard(node.target.id)
        if kept == lists:
            break
        lists = kept
    return lists


def _is_uint8_expression(node, images, lists=frozenset(), keeping=frozenset()) -> bool:
    """Whether ``node`` surely holds a uint8 image: one of ``images``, an item of one of ``lists`` (lists of
    uint8 images), a slice or a copy of one, what an image function or a helper of the module ``keeping`` its
    first argument's dtype makes of one."""
    if isinstance(node, ast.Name):
        return node.id in images
    if isinstance(node, ast.Subscript):
        if isinstance(node.value, ast.Name) and node.value.id in lists:
            return True
        return _is_uint8_expression(node.value, images, lists, keeping)
    if isinstance(node, ast.Call):
        if isinstance(node.func, ast.Name) and node.func.id in keeping and node.args:
            return _is_uint8_expression(node.args[0], images, lists, keeping)
        call = _call_name(node)
        if call in {"copy", "zeros_like", "empty_like", "roll", "ascontiguousarray"} and not any(
                k.arg == "dtype" for k in node.keywords):
            receiver = node.func.value if isinstance(node.func, ast.Attribute) and call == "copy" else \
                (node.args[0] if node.args else None)
            return receiver is not None and _is_uint8_expression(receiver, images, lists, keeping)
        if call in IMAGE_FUNCTIONS and node.args:
            return _is_uint8_expression(node.args[0], images, lists, keeping)
    return False


def _keeps_first_dtype(function) -> bool:
    """Whether every value ``function`` returns is its first parameter's dtype, read as a uint8 image: itself,
    a copy or slice of it, `np.empty_like(image)` filled from it (a helper shifting an image by d columns)."""
    parameters = [a.arg for a in function.args.posonlyargs + function.args.args]
    if not parameters:
        return False
    images = _uint8_names(function, set(parameters), seeds={parameters[0]})
    returned = [n.value for n in _nodes(function) if isinstance(n, ast.Return)]
    return bool(returned) and all(v is not None and _is_uint8_expression(v, images) for v in returned)


def _uint8_arithmetic(name, function, parameters, keeping=frozenset()) -> list[Finding]:
    images = _uint8_names(function, parameters, keeping)
    if not images:
        return []
    lists = _uint8_lists(function, images, keeping)
    for node in _nodes(function):
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult, ast.Pow)):
            sides = (node.left, node.right)
            if isinstance(node.op, ast.Pow):
                wraps = _is_uint8_expression(node.left, images, lists, keeping)
            else:
                wraps = all(_is_uint8_expression(side, images, lists, keeping) for side in sides)
            if wraps:
                return [Finding(name, _line(node), "uint8 arithmetic wraps around",
                                f"{name} (line {_line(node)}) computes {ast.unparse(node)[:60]} on uint8 "
                                "images: uint8 arithmetic wraps around (200 + 100 gives 44, 3 - 5 gives "
                                "254); convert first: image.astype(np.float32)")]
        if isinstance(node, ast.Call) and _call_name(node) in ("subtract", "add") and len(node.args) >= 2 \
                and all(_is_uint8_expression(side, images, lists, keeping) for side in node.args[:2]) \
                and not any(k.arg == "dtype" for k in node.keywords):
            # (OpenCV's saturate at 0 and 255 -- a band-pass level's negative half is lost -- NumPy's wrap round)
            opencv = isinstance(node.func, ast.Attribute) and _dotted_name(node.func.value) == "cv2"
            effect = ("OpenCV's uint8 arithmetic saturates (3 - 5 gives 0, 200 + 100 gives 255): the negative "
                      "values are lost" if opencv else
                      "uint8 arithmetic wraps around (200 + 100 gives 44, 3 - 5 gives 254)")
            return [Finding(name, _line(node), "uint8 arithmetic saturates" if opencv else "uint8 arithmetic wraps around",
                            f"{name} (line {_line(node)}) computes {ast.unparse(node)[:60]} on uint8 images: "
                            f"{effect}; convert first: image.astype(np.float32)")]
    return []


# ------------------------------------------------------------------ homogeneous coordinates
def _zeros_call(node) -> bool:
    """``np.zeros`` of a size that depends on the data (one per point), not a constant shape:
    ``np.zeros((3, 1))`` is the last column of ``[I | 0]``, not a homogeneous coordinate."""
    if not (isinstance(node, ast.Call) and _call_name(node) in {"zeros", "zeros_like"}):
        return False
    return _call_name(node) == "zeros_like" or any(not _constant_integers(arg) for arg in node.args[:1])


def _homogeneous_zero(name, function) -> list[Finding]:
    """Points made homogeneous with 0 (``hstack([pts, zeros])``, ``[X, Y, Z, 0]``) and then
    multiplied by a matrix or used as a row of a linear system."""
    products, pending = set(), [function]
    while pending:  # a product's names are all of its names: those of products inside it are among them
        node = pending.pop()
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.MatMult, ast.Mult)) or \
                isinstance(node, ast.Call) and _call_name(node) in {"dot", "matmul", "outer", "concatenate",
                                                                     "hstack", "kron", "einsum"}:
            products |= _names_in(node)
        else:
            pending.extend(ast.iter_child_nodes(node))
    assigned = _assigned_names(function)
    parameters = {a.arg for a in function.args.args + function.args.kwonlyargs + function.args.posonlyargs}
    data = parameters | {target for target, values in assigned.items()
                         if values and all(_names_in(v) & parameters for v in values)}
    zeros = {target for target, values in assigned.items() if values and all(isinstance(v, ast.Call)
             and _call_name(v) in {"zeros", "zeros_like"} for v in values)}

    def zero_column(node) -> bool:
        return _stacks_zero_column(node, zeros, data)

    for target, values in assigned.items():
        for value in values:
            if (zero_column(value) or _ends_in_zero(value)) and target in products:
                return [_homogeneous_finding(name, value)]
    for node in _nodes(function):   # a stack used at once: (np.hstack([X, zeros]) @ P.T)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult):
            for side in (node.left, node.right):
                if zero_column(side):
                    return [_homogeneous_finding(name, side)]
    return []


def _stacks_zero_column(node, zeros=frozenset(), data=frozenset()) -> bool:
    """``hstack([points, zeros])`` (or ``column_stack``, ``concatenate(axis=1)``): points given a
    last coordinate of 0. A column of constant size counts only after the function's data (a
    parameter, or what is made from one): ``[np.eye(3), np.zeros((3, 1))]`` is ``[I | 0]``."""
    if not (isinstance(node, ast.Call) and node.args and isinstance(node.args[0], (ast.List, ast.Tuple))):
        return False
    call, items = _call_name(node), node.args[0].elts
    if call == "concatenate":
        axis = [ast.unparse(k.value) for k in node.keywords if k.arg == "axis"]
        if axis not in (["1"], ["-1"]):
            return False
    elif call not in {"hstack", "column_stack"}:
        return False
    if len(items) < 2:
        return False
    last, first = items[-1], items[0]
    is_zeros = _zeros_call(last) or (isinstance(last, ast.Name) and last.id in zeros)
    constant_size = isinstance(last, ast.Call) and not _zeros_call(last)
    if isinstance(last, ast.Call) and _call_name(last) in {"zeros", "zeros_like"} and not _zeros_call(last):
        is_zeros, constant_size = True, True
    if not is_zeros:
        return False
    # (a constant column beside a camera's intrinsics or a rotation -- `[K | 0]`, `[R | 0]` -- is a matrix
    # augmented, whatever data K came from)
    while isinstance(first, ast.Call) and _call_name(first) in {"asarray", "array", "float64", "copy"} and first.args:
        first = first.args[0]   # (np.asarray(K, dtype=np.float64): K still)
    if constant_size and isinstance(first, ast.Name) and (first.id in MATRIX_NAMES or first.id.startswith("K")):
        return False
    return not constant_size or bool(_names_in(first) & set(data))


MATRIX_NAMES = frozenset({"R", "R1", "R2", "M", "intrinsics", "camera_matrix", "cam_matrix", "A"})


def _ends_in_zero(node) -> bool:
    """``[x, y, 0]``, ``np.array([X, Y, Z, 0.0])`` or ``np.append(X, 0)``: coordinates, then 0."""
    if isinstance(node, ast.Call) and _call_name(node) in {"array", "asarray"} and node.args:
        node = node.args[0]
    elif isinstance(node, ast.Call) and _call_name(node) == "append" and len(node.args) == 2:
        last = node.args[1]
        return isinstance(last, ast.Constant) and last.value == 0
    if isinstance(node, (ast.List, ast.Tuple)) and 3 <= len(node.elts) <= 4:
        *coordinates, last = node.elts
        return isinstance(last, ast.Constant) and last.value == 0 and not isinstance(last.value, bool) \
            and all(not isinstance(c, ast.Constant) for c in coordinates)
    return False


def _homogeneous_finding(name, node) -> Finding:
    return Finding(name, _line(node), "the homogeneous coordinate is 0 instead of 1",
                   f"{name} (line {_line(node)}) makes the points homogeneous with 0 "
                   f"({ast.unparse(node)[:60]}): the homogeneous coordinate is 1, (x, y, 1) or "
                   "(X, Y, Z, 1); with 0 a matrix's last column (the translation) is lost")


# ------------------------------------------------------------------ DMatch indices
def _query_train(name, function) -> list[Finding]:
    """``kp1[m.trainIdx]`` or ``kp2[m.queryIdx]`` where des1 (of kp1) is the query of the match.

    The points that go with a set of descriptors are found however they were written:
    ``kp, des = detector.detectAndCompute(...)``, siblings of one unpacked tuple
    (``(points1, descriptors1), (points2, descriptors2) = features1, features2``), or names
    ending alike (``kp1``/``des1``, ``pts_l``/``desc_l``); the index may be ``m.trainIdx``
    itself or a name holding only train (or only query) indices (``train = [m.trainIdx for m in good]``)."""
    matched = [node for node in _nodes(function) if isinstance(node, ast.Call)
               and _call_name(node) in {"knnMatch", "match", "radiusMatch"} and len(node.args) >= 2
               and all(isinstance(a, ast.Name) for a in node.args[:2]) and node.args[0].id != node.args[1].id]
    if not matched:
        return []
    role_of_descriptors = {matched[0].args[0].id: "query", matched[0].args[1].id: "train"}
    roles = {}   # points or keypoints name -> "query" / "train"
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple):
            groups = [node.targets[0].elts]
            groups += [e.elts for e in node.targets[0].elts if isinstance(e, ast.Tuple)]
            for group in groups:
                names = [e.id for e in group if isinstance(e, ast.Name)]
                for descriptors in set(names) & set(role_of_descriptors):
                    for other in names:
                        if other != descriptors:
                            roles.setdefault(other, role_of_descriptors[descriptors])
    names = {n.id for n in _nodes(function) if isinstance(n, ast.Name)}
    for descriptors, role in role_of_descriptors.items():
        ending = _index_ending(descriptors)
        for other in names - set(role_of_descriptors):
            if ending and _index_ending(other) == ending and other not in roles:
                roles[other] = role
    if set(roles.values()) != {"query", "train"}:
        return []
    indices = {}   # name -> "queryIdx" / "trainIdx": names holding one kind of index only
    for target, values in _assigned_names(function).items():
        kinds = {n.attr for v in values for n in walk(v)
                 if isinstance(n, ast.Attribute) and n.attr in ("queryIdx", "trainIdx")}
        if len(kinds) == 1:
            indices[target] = kinds.pop()
    for node in _nodes(function):
        if not (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in roles):
            continue
        index = node.slice.attr if isinstance(node.slice, ast.Attribute) and node.slice.attr in ("queryIdx", "trainIdx") \
            else indices.get(node.slice.id) if isinstance(node.slice, ast.Name) else None
        if index is None or (index == "queryIdx") == (roles[node.value.id] == "query"):
            continue
        right = "queryIdx" if roles[node.value.id] == "query" else "trainIdx"
        return [Finding(name, _line(node), "queryIdx and trainIdx are exchanged",
                        f"{name} (line {_line(node)}) indexes {node.value.id} with {index}"
                        f"{'' if index in ast.unparse(node.slice) else f' (in {ast.unparse(node.slice)})'}: "
                        f"its descriptors are the match's {roles[node.value.id]} set, so its index is "
                        f"m.{right} (queryIdx indexes the first set given to the matcher, trainIdx the second)")]
    return []


def _index_ending(name: str) -> str:
    """What tells a pair's names apart at their end: ``1`` of ``kp1``, ``l`` of ``pts_l``, else ""."""
    head = name.rstrip("0123456789")
    if head != name:
        return name[len(head):]
    base, _, last = name.rpartition("_")
    return last if base and len(last) <= 5 else ""


# ------------------------------------------------------------------ OpenCV's default camera
# OpenCV calls that take the camera matrix as an optional argument and otherwise read the points
# as normalised coordinates (focal length 1, principal point (0, 0)): the positional arguments
# before it, and the keywords that give the camera.
CAMERA_DEFAULTED = {"recoverPose": (3, ("cameraMatrix", "focal", "pp")),
                    "findEssentialMat": (2, ("cameraMatrix", "focal", "pp"))}
# What makes pixel points normalised first (then leaving the camera out is right).
NORMALISING = frozenset({"inv", "solve", "undistortPoints", "pinv"})


def _camera_left_out(name, function) -> list[Finding]:
    """``cv2.recoverPose(E, pts1, pts2)`` (or ``cv2.findEssentialMat(pts1, pts2)``) without the
    camera matrix, in a function that never normalises its points with K."""
    if any(_call_name(node) in NORMALISING for node in _nodes(function) if isinstance(node, ast.Call)):
        return []
    for node in _nodes(function):
        if not isinstance(node, ast.Call) or _call_name(node) not in CAMERA_DEFAULTED \
                or _attribute_path(node.func) not in (f"cv2.{_call_name(node)}", _call_name(node)):
            continue
        before, keywords = CAMERA_DEFAULTED[_call_name(node)]
        if len(node.args) <= before and not any(k.arg in keywords or k.arg is None for k in node.keywords):
            called = _call_name(node)
            return [Finding(name, _line(node), f"cv2.{called} without the camera matrix",
                            f"{name} (line {_line(node)}) calls cv2.{called} without the camera matrix: OpenCV "
                            "then takes a focal length of 1 and the principal point (0, 0), reading pixel "
                            "coordinates as normalised ones; pass K to it")]
    return []


# ------------------------------------------------------------------ OpenCV masks
def _mask_as_index(name, function) -> list[Finding]:
    """A mask OpenCV returns (uint8, 0 and 1) used as an index without turning it into booleans."""
    masks = _ransac_masks(function)
    if not masks:
        return []
    converted = set()
    for target, values in _assigned_names(function).items():
        if target in masks and any(_makes_boolean(v) for v in values):
            converted.add(target)
    for node in _nodes(function):
        if isinstance(node, ast.Subscript):
            index = node.slice
            while isinstance(index, ast.Call) and isinstance(index.func, ast.Attribute) \
                    and index.func.attr in ("ravel", "flatten", "squeeze", "reshape"):
                index = index.func.value
            if isinstance(index, ast.Name) and index.id in masks and index.id not in converted:
                return [Finding(name, _line(node), "OpenCV's 0/1 mask is used as indices",
                                f"{name} (line {_line(node)}) indexes with {index.id}, the uint8 mask of "
                                "0 and 1 OpenCV returns: as an index it selects rows 0 and 1 over and "
                                "over, not the inliers; use "
                                f"{index.id}.ravel().astype(bool)")]
    return []


def _ransac_masks(function) -> dict:
    """name -> the assignment binding it to the 0/1 mask an OpenCV estimator returns (:data:`MASK_FUNCTIONS`)."""
    masks = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple) \
                and isinstance(node.value, ast.Call) and _call_name(node.value) in MASK_FUNCTIONS:
            position = MASK_FUNCTIONS[_call_name(node.value)]
            elts = node.targets[0].elts
            if len(elts) > position and isinstance(elts[position], ast.Name):
                masks[elts[position].id] = node
    return masks


def outliers_selected(node, masks) -> bool:
    """Whether ``node`` selects the entries a RANSAC mask marks 0 (its outliers): ``mask == 0``,
    ``mask.ravel() != 1``, ``mask == False``, ``~mask.astype(bool)``, ``np.logical_not(mask)``."""
    def of_a_mask(expression) -> bool:
        return any(isinstance(n, ast.Name) and n.id in masks for n in walk(expression))

    if isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.comparators[0], ast.Constant) \
            and of_a_mask(node.left):
        op, value = node.ops[0], node.comparators[0].value
        return (isinstance(op, ast.Eq) and value in (0, False)) or (isinstance(op, ast.NotEq) and value in (1, True)) \
            or (isinstance(op, ast.Lt) and value == 1)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.Invert, ast.Not)):
        return of_a_mask(node.operand)
    return isinstance(node, ast.Call) and _call_name(node) == "logical_not" and bool(node.args) \
        and of_a_mask(node.args[0])


def _outliers_kept(name, function) -> list[Finding]:
    """The matches a RANSAC mask marks 0 kept: ``inliers = mask.ravel() == 0`` -- its outliers."""
    masks = _ransac_masks(function)
    if not masks:
        return []
    for node in _nodes(function):
        if outliers_selected(node, masks):
            line = _line(node)
            return [Finding(name, line, "the RANSAC mask's outliers kept",
                            f"{name} (line {line}) selects with `{ast.unparse(node)}` the matches the estimator's "
                            "mask marks 0, its outliers; the inliers are those it marks 1 (mask.ravel() == 1, or "
                            "mask.ravel().astype(bool))")]
    return []


def _makes_boolean(node) -> bool:
    if isinstance(node, ast.Compare):
        return True
    if isinstance(node, ast.Call) and _call_name(node) == "astype":
        return bool(node.args) and ast.unparse(node.args[0]) in ("bool", "np.bool_", "np.bool", "'bool'", '"bool"')
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in (
            "ravel", "flatten", "reshape", "squeeze"):
        return _makes_boolean(node.func.value)
    return False


# ------------------------------------------------------------------ coefficient order
def _distortion_order(name, function, parameters) -> list[Finding]:
    """``k1, k2, k3, p1, p2 = dist``: OpenCV's order is (k1, k2, p1, p2, k3)."""
    if "dist" not in parameters:
        return []
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple) \
                and "dist" in _names_in(node.value):
            names = [e.id.lower() if isinstance(e, ast.Name) else "" for e in node.targets[0].elts]
            if len(names) == 5 and sorted(names) == sorted(OPENCV_DISTORTION) and tuple(names) != OPENCV_DISTORTION:
                return [Finding(name, _line(node), "the distortion coefficients are read in the wrong order",
                                f"{name} (line {_line(node)}) unpacks dist as ({', '.join(names)}); "
                                "OpenCV's order is (k1, k2, p1, p2, k3)")]
    return []


# ------------------------------------------------------------------ views overwritten
def _statements_in_order(function) -> list[ast.stmt]:
    """The function's own simple statements, in the order of their lines (loops read top to bottom)."""
    return sorted((node for node in _nodes(function) if isinstance(node, ast.stmt)
                   and not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.For,
                                             ast.While, ast.If, ast.With, ast.Try))), key=_line)


def _basic_view(node) -> bool:
    """``a[:, 0]``, ``a[0]``, ``a[..., 1]``: an index NumPy answers with a view of ``a`` (slices,
    whole numbers, ``...``), not a copy (a list or an array as index copies)."""
    if not (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name)):
        return False
    parts = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
    return all(isinstance(p, ast.Slice) or (isinstance(p, ast.Constant) and (isinstance(p.value, int)
               or p.value is Ellipsis)) or (isinstance(p, ast.UnaryOp) and isinstance(p.operand, ast.Constant))
               for p in parts)


def _view_overwritten(name, function) -> list[Finding]:
    """``x = pts[:, 0]`` (a view), then ``pts[:, 0] = ...`` written, then ``x`` read: ``x`` holds the
    new values (the first of Brown's two formulas written back before the second reads x)."""
    statements = _statements_in_order(function)
    views = {}   # name -> (the subscript's text, line bound)
    for statement in statements:
        if isinstance(statement, ast.Assign):
            for target in statement.targets:
                pairs = list(zip(target.elts, statement.value.elts)) if isinstance(target, ast.Tuple) and \
                    isinstance(statement.value, ast.Tuple) and len(target.elts) == len(statement.value.elts) \
                    else [(target, statement.value)]
                for bound, value in pairs:
                    if isinstance(bound, ast.Name):
                        views[bound.id] = (ast.unparse(value), _line(statement)) if _basic_view(value) else None
    written = {}   # the subscript's text -> the line writing into it
    changed = {}   # an array changed whole in place (`src -= p0`) -> the line: every view of it changes too
    for statement in statements:   # (each statement's own names read once: linear in the function)
        read = statement.value if isinstance(statement, (ast.Assign, ast.AugAssign)) else statement
        loaded = {n.id for n in walk(read) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
        for view_name in sorted(loaded & views.keys()):
            if views[view_name] is None:
                continue
            text, bound = views[view_name]
            base = text.split("[", 1)[0]
            line = written.get(text) if text in written else changed.get(base)
            if line is not None and line > bound and _line(statement) > line:
                return [Finding(name, _line(statement), "a view of an array read after the array was written",
                                f"{name} reads `{view_name}` (line {_line(statement)}), a view of `{text}` (line "
                                f"{bound}) that line {line} has written over: it holds the new values, "
                                f"not those it was taken from; take a copy (`{view_name} = {text}.copy()`)")]
        targets = statement.targets if isinstance(statement, ast.Assign) else \
            [statement.target] if isinstance(statement, ast.AugAssign) else []
        for target in targets:
            if isinstance(target, ast.Subscript) and _basic_view(target):
                written.setdefault(ast.unparse(target), _line(statement))
            elif isinstance(statement, ast.AugAssign) and isinstance(target, ast.Name):
                changed.setdefault(target.id, _line(statement))
    return []


# ------------------------------------------------------------------ a generator seeded in a loop
SEEDING = frozenset({"default_rng", "seed", "RandomState", "Generator"})


def _seeded_in_a_loop(name, function) -> list[Finding]:
    """``rng = np.random.default_rng(seed)`` inside a loop, from a value the loop does not change:
    with a seed given, every turn draws the same numbers."""
    for loop in _nodes(function):
        if not isinstance(loop, (ast.For, ast.While)):
            continue
        turned = _names_in(loop.target) if isinstance(loop, ast.For) else set()
        for node in (n for statement in loop.body for n in walk(statement)):
            seeds = isinstance(node, ast.Call) and _call_name(node) in SEEDING and bool(node.args) and (
                _call_name(node) == "default_rng" or "random" in _attribute_path(node.func))   # (not rng.random())
            if seeds and _names_in(node.args[0]) and not _names_in(node.args[0]) & turned:
                return [Finding(name, _line(node), "the random generator is seeded again at every turn of a loop",
                                f"{name} (line {_line(node)}) seeds a new generator from "
                                f"`{ast.unparse(node.args[0])}` at every turn of the loop: with a seed given, "
                                "each turn draws the same numbers; make the generator once, before the loop")]
    return []


# ------------------------------------------------------------------ data shuffled in place in a loop
_INDEX_MAKERS = frozenset({"arange", "range", "permutation", "indices"})


def _data_shuffled_in_a_loop(name, function) -> list[Finding]:
    """``rng.shuffle(pairs)`` (``np.random.shuffle``) inside a loop, on an array of data (not of indices made by
    ``np.arange`` / ``range``) that the function indexes by a name (``pairs[best]``): each turn reorders the
    data itself, so a mask or an index found in one turn's order points at other rows after the next shuffle,
    and what the function answers is in the shuffled order, not its caller's."""
    made_as_indices = {target.id for node in _nodes(function) if isinstance(node, ast.Assign)
                       and isinstance(node.value, ast.Call) and _call_name(node.value) in _INDEX_MAKERS
                       or isinstance(node, ast.Assign) and isinstance(node.value, ast.Call)
                       and _call_name(node.value) == "list" and node.value.args
                       and isinstance(node.value.args[0], ast.Call) and _call_name(node.value.args[0]) == "range"
                       for target in node.targets if isinstance(target, ast.Name)}
    indexed = {node.value.id for node in _nodes(function) if isinstance(node, ast.Subscript)
               and isinstance(node.value, ast.Name) and (isinstance(node.slice, ast.Name) or (   # pairs[best]
                   isinstance(node.slice, ast.Tuple) and node.slice.elts and isinstance(node.slice.elts[0], ast.Name)))}
    for loop in _nodes(function):
        if not isinstance(loop, (ast.For, ast.While)):
            continue
        for node in (n for statement in loop.body for n in walk(statement)):
            if isinstance(node, ast.Call) and _call_name(node) == "shuffle" and len(node.args) == 1 \
                    and isinstance(node.args[0], ast.Name):
                data = node.args[0].id
                if data in indexed and data not in made_as_indices:
                    return [Finding(name, _line(node), "the data are shuffled in place at every turn",
                                    f"{name} (line {_line(node)}) shuffles `{data}` itself at every turn of the loop: "
                                    f"a mask or an index found in one turn's order points at other rows of `{data}` "
                                    "after the next shuffle, and what is answered is in the shuffled order, not in "
                                    "the order the points were given; draw random indices instead "
                                    "(`rng.choice(n, 4, replace=False)`) and leave the data in place", certain=True)]
    return []


# ------------------------------------------------------------------ a mean taken after centring
_MEANS = frozenset({"mean", "average"})


def _mean_call_of(node) -> str:
    """The name whose mean ``node`` is (``x.mean(...)``, ``np.mean(x, ...)``), "" otherwise."""
    if isinstance(node, ast.Call) and _call_name(node) in _MEANS:
        if isinstance(node.func, ast.Attribute) and isinstance(node.func.value, ast.Name) \
                and node.func.value.id not in ("np", "numpy"):
            return node.func.value.id
        if node.args and isinstance(node.args[0], ast.Name):
            return node.args[0].id
    return ""


def _mean_after_centring(name, function) -> list[Finding]:
    """``src = src - src.mean(axis=0)`` (or ``src -= ...``), then ``src.mean(...)`` read again: the
    mean of an array centred is 0, not the centroid it had."""
    centred = {}   # name -> the line centring it
    for statement in _statements_in_order(function):
        target = value = None
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 \
                and isinstance(statement.targets[0], ast.Name):
            target, value = statement.targets[0].id, statement.value
            if target in centred and not (isinstance(value, ast.BinOp) and isinstance(value.op, ast.Sub)):
                centred.pop(target)   # (bound again to something else)
        elif isinstance(statement, ast.AugAssign) and isinstance(statement.target, ast.Name) \
                and isinstance(statement.op, ast.Sub):
            target, value = statement.target.id, ast.BinOp(statement.target, ast.Sub(), statement.value)
        for node in walk(statement):
            mean_of = _mean_call_of(node)
            if mean_of and mean_of in centred and _line(statement) > centred[mean_of]:
                return [Finding(name, _line(node), "a mean taken of an array already centred",
                                f"{name} takes `{ast.unparse(node)}` (line {_line(node)}) after line "
                                f"{centred[mean_of]} centred `{mean_of}`: it is 0 there, not the centroid the "
                                "points had; keep the centroid in a name before centring")]
        if target is not None and isinstance(value, ast.BinOp) and isinstance(value.op, ast.Sub) \
                and isinstance(value.left, ast.Name) and value.left.id == target \
                and _mean_call_of(value.right) == target:
            centred[target] = _line(statement)
    return []


# ------------------------------------------------------------------ triangulatePoints' w
def _w_never_divided(name, function) -> list[Finding]:
    """The 4 x N homogeneous result of ``cv2.triangulatePoints`` whose first three rows are used and
    never divided by the fourth (nor converted with ``cv2.convertPointsFromHomogeneous``)."""
    if any(isinstance(n, ast.Call) and _call_name(n) == "convertPointsFromHomogeneous" for n in _nodes(function)):
        return []
    divisions = [n for n in _nodes(function) if isinstance(n, (ast.BinOp, ast.AugAssign)) and isinstance(n.op, ast.Div)]
    # (what the divisions hold, read once: linear in the function)
    divided_names = set().union(*(_names_in(d) for d in divisions)) if divisions else set()
    divides_a_result = any(isinstance(c, ast.Call) and _call_name(c) == "triangulatePoints"
                           for d in divisions for c in walk(d))

    def finding(line, shown):
        return [Finding(name, line, "the homogeneous result of cv2.triangulatePoints is not divided by w",
                        f"{name} (line {line}) keeps rows of {shown}, the 4 x N homogeneous points "
                        "cv2.triangulatePoints returns, without dividing them by the fourth row (w): each point "
                        "is scaled by its own w, of either sign; divide the first three rows by the fourth")]
    subscripted = {n.value.id for n in _nodes(function) if isinstance(n, ast.Subscript) and isinstance(n.value, ast.Name)}
    for node in _nodes(function):
        # (sliced where it is made: `cv2.triangulatePoints(P1, P2, x1, x2)[:3].T`, nothing divided)
        if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Call) \
                and _call_name(node.value) == "triangulatePoints" and not divides_a_result:
            return finding(_line(node), "the result")
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and isinstance(node.value, ast.Call) and _call_name(node.value) == "triangulatePoints":
            result = node.targets[0].id
            if result in subscripted and result not in divided_names:
                return finding(_line(node), f"`{result}`")
    return []


# ------------------------------------------------------------------ NumPy calls that fill more than meant
def _square_side(node) -> int:
    """The side of a square array a call makes (``np.eye(3)``, ``np.zeros((3, 3))``, ``np.identity(3)``), else 0."""
    if not (isinstance(node, ast.Call) and node.args):
        return 0
    first = node.args[0]
    if _call_name(node) in ("eye", "identity") and isinstance(first, ast.Constant) and isinstance(first.value, int) \
            and (len(node.args) < 2 or ast.unparse(node.args[1]) == ast.unparse(first)):
        return first.value
    if _call_name(node) in ("zeros", "ones", "empty") and isinstance(first, ast.Tuple) and len(first.elts) == 2 \
            and all(isinstance(e, ast.Constant) for e in first.elts) and first.elts[0].value == first.elts[1].value:
        return int(first.elts[0].value)
    return 0


def _diagonal_refilled(name, function) -> list[Finding]:
    """``np.fill_diagonal(M, [sx, sy])`` on a 3x3 ``M``: NumPy writes the values again and again along
    the whole diagonal (M[2, 2] = sx); ``np.eye(3, k=1)`` has ones on its whole superdiagonal, not at
    [0, 1] alone."""
    sides = {target: _square_side(values[-1]) for target, values in _assigned_names(function).items() if values}
    for node in _nodes(function):
        if isinstance(node, ast.Call) and _call_name(node) == "fill_diagonal" and len(node.args) == 2 \
                and isinstance(node.args[0], ast.Name) and isinstance(node.args[1], (ast.List, ast.Tuple)):
            side, given = sides.get(node.args[0].id, 0), len(node.args[1].elts)
            if 0 < given < side:
                return [Finding(name, _line(node), "np.fill_diagonal repeats a list shorter than the diagonal",
                                f"{name} (line {_line(node)}) calls `{ast.unparse(node)}`: np.fill_diagonal writes "
                                f"its {given} values again and again along the whole diagonal ({side} entries), so "
                                f"entry [{given}, {given}] gets {ast.unparse(node.args[1].elts[0])}; give all "
                                f"{side} values", certain=True)]
        if isinstance(node, ast.Call) and _call_name(node) == "eye" and node.args and isinstance(node.args[0], ast.Constant) \
                and isinstance(node.args[0].value, int) and node.args[0].value >= 3 and any(
                    k.arg == "k" and isinstance(k.value, (ast.Constant, ast.UnaryOp)) and ast.unparse(k.value) not in ("0",)
                    for k in node.keywords):
            k = next(ast.unparse(k.value) for k in node.keywords if k.arg == "k")
            return [Finding(name, _line(node), "np.eye(n, k) fills its whole off-diagonal",
                            f"{name} (line {_line(node)}) uses `{ast.unparse(node)}`: it has ones along the whole "
                            f"diagonal k = {k} ({node.args[0].value - abs(int(k)) if k.lstrip('-').isdigit() else 'several'} "
                            "entries), not at one entry; set the entry itself")]
    return []


# ------------------------------------------------------------------ OpenCV constants out of place
# Which parameters each family of OpenCV constants is made for (lower case, as OpenCV's signatures
# name them): a constant of a family given positionally where the signature has another parameter
# fills that one with its number (cv2.LINE_AA = 16 as a circle's thickness, cv2.INTER_NEAREST = 0 as
# resize's dst, cv2.BORDER_DEFAULT = 4 as GaussianBlur's sigmaX).
CONSTANT_FAMILIES = (
    ("LINE_", {"linetype"}), ("FILLED", {"thickness"}), ("INTER_", {"interpolation", "flags"}),
    ("WARP_", {"flags"}), ("BORDER_", {"bordermode", "bordertype"}), ("NORM_", {"normtype", "norm_type"}),
    ("COLOR_", {"code"}), ("ADAPTIVE_THRESH_", {"adaptivemethod"}), ("THRESH_", {"type"}),
    ("RANSAC", {"method"}), ("LMEDS", {"method"}), ("RHO", {"method"}), ("USAC_", {"method"}), ("FM_", {"method"}),
    ("SOLVEPNP_", {"flags"}), ("CALIB_", {"flags"}), ("FONT_", {"fontface"}), ("IMREAD_", {"flags"}),
    ("TM_", {"method"}), ("RETR_", {"mode"}), ("CHAIN_APPROX_", {"method"}), ("ROTATE_", {"rotatecode"}),
    ("CV_", {"ddepth", "dtype", "m1type", "depth", "rtype"}))
OPENCV_MODULES = frozenset({"cv2", "cv"})


def _family(constant: str) -> set[str]:
    return next((places for prefix, places in CONSTANT_FAMILIES if constant.startswith(prefix)), set())


@lru_cache(maxsize=256)
def _opencv_parameters(function: str) -> tuple[tuple[str, ...], ...]:
    """The parameter names of each of OpenCV's signatures of ``cv2.<function>`` (its docstring's
    ``circle(img, center, radius, color[, thickness[, lineType[, shift]]]) -> img`` lines)."""
    try:
        import cv2

        doc = getattr(cv2, function).__doc__ or ""
    except (ImportError, AttributeError):
        return ()
    signatures = []
    for line in doc.splitlines():
        line = line.strip()
        if line.startswith(f"{function}(") and ")" in line:
            inside = line[len(function) + 1:line.index(")")].replace("[", "").replace("]", "")
            signatures.append(tuple(part.strip() for part in inside.split(",") if part.strip()))
    return tuple(signatures)


def _number_of(*constants: str) -> str:
    """The number OpenCV's ``constants`` (dotted, joined by ``|``) stand for."""
    try:
        import cv2

        number = 0
        for constant in constants:
            number |= int(getattr(cv2, constant.rpartition(".")[2]))
        return str(number)
    except (ImportError, AttributeError, TypeError, ValueError):
        return "its number"


def _constant_out_of_place(name, function) -> list[Finding]:
    """An OpenCV constant passed positionally into a parameter of no signature its family is made for:
    ``cv2.circle(out, c, r, color, cv2.LINE_AA)`` draws a ring 16 pixels thick."""
    for node in _nodes(function):
        if not isinstance(node, ast.Call) or not isinstance(node.func, ast.Attribute) \
                or _attribute_path(node.func.value) not in OPENCV_MODULES:
            continue
        signatures = _opencv_parameters(node.func.attr)
        for position, argument in enumerate(node.args):
            if isinstance(argument, ast.Starred):   # (the places after it are not known)
                break
            flags = _joined_constants(argument)
            path = ast.unparse(argument) if flags else ""
            module, _, constant = (flags[0] if flags else "").rpartition(".")
            places = _family(constant) if module in OPENCV_MODULES else set()
            fitting = [names for names in signatures if len(names) > position]
            if not places or not fitting or any(names[position].lower() in places for names in fitting):
                continue
            meant = next((p for names in signatures for p in names if p.lower() in places), "")
            if not meant:
                continue
            given = fitting[0][position]
            called = f"{module}.{node.func.attr}"
            return [Finding(name, _line(node), f"{path} is passed as {called}'s {given}",
                            f"{name} (line {_line(node)}) passes {path} as argument {position + 1} of {called}, "
                            f"which is `{given}` there, so {given} gets {_number_of(*flags)}; {path} belongs to "
                            f"`{meant}`: pass it by name ({meant}={path})", certain=True)]
    return []


def _joined_constants(node) -> list[str]:
    """The dotted constants of an OpenCV flag, alone or joined by ``|`` or ``+``
    (``cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP``); [] for any other expression."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.BitOr, ast.Add)):
        left, right = _joined_constants(node.left), _joined_constants(node.right)
        return left + right if left and right else []
    path = _attribute_path(node)
    return [path] if path.rpartition(".")[0] in OPENCV_MODULES else []


# ------------------------------------------------------------------ the last turn's value after a loop
def _kept_copies(loop) -> dict[str, str]:
    """In ``loop``'s body, the names an ``if <comparison>:`` copies into another (``best_inliers =
    inliers``, ``best_H, best_mask = H, mask``): {name: the copy's name}."""
    kept = {}
    for node in walk(loop):
        if not (isinstance(node, ast.If) and isinstance(node.test, ast.Compare)):
            continue
        for statement in node.body:
            if not isinstance(statement, ast.Assign) or len(statement.targets) != 1:
                continue
            target, value = statement.targets[0], statement.value
            pairs = zip(target.elts, value.elts) if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) \
                and len(target.elts) == len(value.elts) else [(target, value)]
            for copy, original in pairs:
                if isinstance(original, ast.Call) and isinstance(original.func, ast.Attribute) \
                        and original.func.attr == "copy":
                    original = original.func.value
                if isinstance(copy, ast.Name) and isinstance(original, ast.Name) and copy.id != original.id:
                    kept[original.id] = copy.id
    return kept


def _plain_copies(statement) -> list:
    """[(target, the name it copies)] of an assignment `a = b` or `a = b.copy()` (one target, names only)."""
    if not isinstance(statement, ast.Assign) or len(statement.targets) != 1 or not isinstance(statement.targets[0], ast.Name):
        return []
    value = statement.value
    if isinstance(value, ast.Call) and isinstance(value.func, ast.Attribute) and value.func.attr == "copy" and not value.args:
        value = value.func.value
    return [(statement.targets[0], value.id)] if isinstance(value, ast.Name) else []


def _assigns(statement, name: str) -> bool:
    return any(isinstance(n, ast.Name) and n.id == name and isinstance(n.ctx, ast.Store)
               for n in walk(statement))


def _last_turn_used(name, function) -> list[Finding]:
    """A name a loop copies into a best-so-far name under a comparison, read after the loop before it is
    assigned again: the last turn's value where the best one was kept (``best_inliers = inliers`` in the
    loop, ``src[inliers]`` after it)."""
    # Each block read once from its end: `following` holds, per name, its first read after the statement at
    # hand (None where it is assigned first) -- no walk of the rest of the block per loop.
    for block in (getattr(node, field) for node in _nodes(function) for field in ("body", "orelse", "finalbody")
                  if isinstance(getattr(node, field, None), list)):
        following: dict = {}
        for statement in reversed(block):
            if isinstance(statement, (ast.For, ast.While)):
                stored = {n.id for part in statement.body for n in walk(part)
                          if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}   # (one value every turn)
                for original, copy in _kept_copies(statement).items():
                    read = following.get(original)
                    if original in stored and read is not None:
                        # (the best copy taken on after the loop under another name -- `mask = best_inliers`, refined
                        # by a refit -- is what the read belongs to: that name is told, not the copy)
                        after = block[block.index(statement) + 1:]
                        renamed = [target.id for later in after if _line(later) < _line(read)
                                   for target, value in _plain_copies(later) if value == copy]
                        use = f"`{renamed[-1]}`, which your code makes from it after the loop," if renamed \
                            else f"`{copy}`"
                        return [Finding(name, _line(read), "the last turn's value is used after the loop, not the "
                                        "best one kept",
                                        f"{name} (line {_line(read)}) reads `{original}` after the loop: that is the "
                                        f"value of the loop's last turn, while the best one was kept in `{copy}` "
                                        f"(line {_line(statement)} on); use {use} there", certain=True)]
            following.update(_first_uses(statement))
    return []


_COMPOUND = (ast.For, ast.AsyncFor, ast.While, ast.If, ast.With, ast.AsyncWith, ast.Try) + \
    ((ast.TryStar,) if hasattr(ast, "TryStar") else ())


def _first_uses(statement) -> dict:
    """name -> its first read in ``statement`` as it runs (the node), or None where it is assigned before any
    read of it. A simple statement's reads come first (`x = x + 1` reads the value before it); a compound
    statement's header comes first, then its blocks in order (`for ...: norm = ...; if norm > best:` assigns
    `norm` before reading it -- the value from before the loop is not read there)."""
    if not isinstance(statement, _COMPOUND):
        reads, stores = {}, set()
        for n in walk(statement):
            if isinstance(n, ast.Name):
                if isinstance(n.ctx, ast.Load):
                    reads.setdefault(n.id, n)
                else:
                    stores.add(n.id)
        return {**dict.fromkeys(stores - reads.keys()), **reads}
    first: dict = {}
    head = [statement.iter] if isinstance(statement, (ast.For, ast.AsyncFor)) else \
        [statement.test] if isinstance(statement, (ast.While, ast.If)) else \
        [item.context_expr for item in getattr(statement, "items", ())]
    bound = [statement.target] if isinstance(statement, (ast.For, ast.AsyncFor)) else \
        [item.optional_vars for item in getattr(statement, "items", ()) if item.optional_vars is not None]
    for part in head + bound:
        for n in walk(part):
            if isinstance(n, ast.Name):
                first.setdefault(n.id, n if isinstance(n.ctx, ast.Load) else None)
    blocks = [getattr(statement, field, []) for field in ("body", "orelse")] + \
        [handler.body for handler in getattr(statement, "handlers", ())] + [getattr(statement, "finalbody", [])]
    for block in blocks:
        for inner in block:
            for name, node in _first_uses(inner).items():
                first.setdefault(name, node)
    return first


# ------------------------------------------------------------------ a ufunc's third argument
# NumPy's binary functions take (a, b, out): a third array given positionally is written into, not
# multiplied (``np.matmul(K2.T, F, K1)`` is K2^T F, stored into K1).
BINARY_UFUNCS = frozenset({"matmul", "dot", "multiply", "add", "subtract", "divide", "true_divide"})


def _third_operand_as_out(name, function) -> list[Finding]:
    for node in _nodes(function):
        if isinstance(node, ast.Call) and len(node.args) == 3 and _call_name(node) in BINARY_UFUNCS \
                and _attribute_path(node.func) in (f"np.{_call_name(node)}", f"numpy.{_call_name(node)}") \
                and not any(isinstance(a, ast.Starred) for a in node.args) \
                and not (isinstance(node.args[2], ast.Constant) and node.args[2].value is None):
            called, third = _attribute_path(node.func), ast.unparse(node.args[2])
            return [Finding(name, _line(node), f"{called}'s third argument is its output, not an operand",
                            f"{name} (line {_line(node)}) calls `{ast.unparse(node)}`: the third argument of "
                            f"{called} is `out`, the array the result is written into, so {called} computes "
                            f"{ast.unparse(node.args[0])} with {ast.unparse(node.args[1])} alone and overwrites "
                            f"`{third}`; for a product of three, write a @ b @ c", certain=True)]
        # (the method's own: `a.dot(b, c)` -- ndarray.dot(b, out) -- the second argument is `out`)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "dot" \
                and len(node.args) == 2 and not any(isinstance(a, ast.Starred) for a in node.args) \
                and _attribute_path(node.func) not in ("np.dot", "numpy.dot", "np.ndarray.dot", "numpy.ndarray.dot",
                                                       "ndarray.dot") \
                and not (isinstance(node.args[1], ast.Constant) and node.args[1].value is None):
            first, second = ast.unparse(node.func.value), ast.unparse(node.args[0])
            third = ast.unparse(node.args[1])
            return [Finding(name, _line(node), "ndarray.dot's second argument is its output, not an operand",
                            f"{name} (line {_line(node)}) calls `{ast.unparse(node)}`: the second argument of the "
                            f"method .dot is `out`, the array the result is written into, so it computes {first} "
                            f"with {second} alone and overwrites `{third}`; for a product of three, write "
                            f"{first} @ {second} @ {third}", certain=True)]
    return []


# ------------------------------------------------------------------ a conditional taken into a tuple
def _conditional_in_a_tuple(name, function) -> list[Finding]:
    """``size = dsize if dsize is not None else width, height``: the comma binds looser than ``if ... else``,
    so the value is the pair (the conditional, ``height``), not the conditional between ``dsize`` and the pair.
    A conditional in brackets (``(a if c else b), d``: the tuple starts before it), or a tuple returned or unpacked
    (a pair meant), is not read as one."""
    for node in _nodes(function):
        # (one name given the tuple: `return H if ok else None, mask` and `H, mask = ...` mean the pair)
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and isinstance(node.value, ast.Tuple) and node.value.elts \
                and isinstance(node.value.elts[0], ast.IfExp) and len(node.value.elts) >= 2 \
                and (node.value.lineno, node.value.col_offset) == (node.value.elts[0].lineno,
                                                                    node.value.elts[0].col_offset):
            line, choice = _line(node), node.value.elts[0]
            rest = ", ".join(ast.unparse(e) for e in node.value.elts[1:])
            meant = f"{ast.unparse(choice.body)} if {ast.unparse(choice.test)} else ({ast.unparse(choice.orelse)}, {rest})"
            return [Finding(name, line, "a conditional expression taken into a tuple (the comma binds looser)",
                            f"{name} (line {line}) writes `{_shortened(node.value, 80)}`: a comma binds looser than "
                            f"`if ... else`, so this is a pair whose first item is the whole conditional and whose "
                            f"second is `{rest}`; for the pair as the other choice, bracket it: `{meant}`")]
    return []


# ------------------------------------------------------------------ a sample's pairs drawn apart
_DRAWS = frozenset({"choice", "permutation", "sample", "integers", "randint"})
_PAIRED_WORDS = ({"src", "dst"}, {"left", "right"}, {"source", "destination"})


def _a_draw(node) -> bool:
    """A random draw of indices: `rng.choice(n, 4)`, `np.random.permutation(n)[:4]`, `random.sample(...)`."""
    if isinstance(node, ast.Subscript):
        node = node.value
    return isinstance(node, ast.Call) and _call_name(node) in _DRAWS


def _paired(a: str, b: str) -> bool:
    """Two arrays of one set of pairs: one digit apart (`pts1`/`pts2`, `x1`/`x2`) or a pair's words
    (`src`/`dst`, `left_pts`/`right_pts`)."""
    if len(a) == len(b):
        apart = [(x, y) for x, y in zip(a, b) if x != y]
        if len(apart) == 1 and all(c.isdigit() for c in apart[0]):
            return True
    parts_a, parts_b = a.split("_"), b.split("_")
    return len(parts_a) == len(parts_b) and sum(x != y for x, y in zip(parts_a, parts_b)) == 1 and any(
        {x, y} in _PAIRED_WORDS for x, y in zip(parts_a, parts_b) if x != y)


def _pairs_drawn_apart(name, function) -> list[Finding]:
    """``src[rng.choice(n, 4)]`` beside ``dst[rng.choice(n, 4)]`` (a RANSAC sample): the two arrays of one set
    of pairs, each indexed only by a random draw of its own -- the points drawn from one are not the partners of
    those drawn from the other. (One pass over the def's nodes.)"""
    drawn = {statement.targets[0].id for statement in _nodes(function) if isinstance(statement, ast.Assign)
             and len(statement.targets) == 1 and isinstance(statement.targets[0], ast.Name) and _a_draw(statement.value)}
    indexed: dict[str, dict] = {}   # array -> {its index's text: the subscript}
    for node in _nodes(function):
        if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Name):
            key = node.slice.id if isinstance(node.slice, ast.Name) and node.slice.id in drawn else \
                f"draw@{id(node.slice)}" if _a_draw(node.slice) else None
            if key is not None:
                indexed.setdefault(node.value.id, {})[key] = node
    arrays = sorted(indexed)
    for i, a in enumerate(arrays):
        for b in arrays[i + 1:]:
            if _paired(a, b) and not set(indexed[a]) & set(indexed[b]):
                first, second = sorted((next(iter(indexed[a].values())), next(iter(indexed[b].values()))),
                                       key=lambda node: (node.lineno, node.col_offset))
                a, b = first.value.id, second.value.id   # (told in the order they are written)
                return [Finding(name, _line(second), "one sample's pairs drawn apart, by two random draws",
                                f"{name} (lines {_line(first)} and {_line(second)}) indexes `{a}` with "
                                f"`{ast.unparse(first.slice)}` and `{b}` with `{ast.unparse(second.slice)}`, two "
                                f"separate random draws: the rows taken from `{a}` are not the partners of those "
                                f"taken from `{b}` (row k of one pairs with row k of the other); draw the indices "
                                f"once and take both with them", certain=True)]
    return []


def _reordering(value, array: str) -> str:
    """How ``value`` reorders the rows of ``array`` on their own: ``np.unique(array, axis=0)`` (sorted,
    repeats dropped), ``np.sort(array, axis=0)``, ``array[np.argsort(array[:, 0])]``; "" otherwise."""
    mentions = lambda node: any(isinstance(n, ast.Name) and n.id == array for n in walk(node))  # noqa: E731
    if isinstance(value, ast.Call) and _call_name(value) in ("unique", "sort") and value.args and mentions(value.args[0]):
        axis = [k.value for k in value.keywords if k.arg == "axis"]
        if axis and isinstance(axis[0], ast.Constant) and axis[0].value == 0:
            return "np.unique sorts the rows and drops repeats" if _call_name(value) == "unique" else \
                "np.sort along axis 0 sorts each column on its own"
    if isinstance(value, ast.Subscript) and isinstance(value.value, ast.Name) and value.value.id == array \
            and isinstance(value.slice, ast.Call) and _call_name(value.slice) in ("argsort", "lexsort") \
            and mentions(value.slice):
        return f"`{_call_name(value.slice)}` of its own values orders its rows"
    return ""


def _first_name(node) -> str:
    """The array a reordering call or index is given: ``pts1`` of ``np.unique(pts1, axis=0)``."""
    inner = node.args[0] if isinstance(node, ast.Call) and node.args else \
        node.value if isinstance(node, ast.Subscript) else None
    return inner.id if isinstance(inner, ast.Name) else ""


def _pairs_reordered_apart(name, function) -> list[Finding]:
    """``pts1 = np.unique(pts1, axis=0)`` beside ``pts2 = np.unique(pts2, axis=0)``: the two arrays of one set
    of pairs, each reordered (or thinned) by its own values -- row k of one is no longer the partner of row k
    of the other. (One pass over the def's assignments.)"""
    reordered = {}   # array -> (the expression reordering it, how)
    for statement in _nodes(function):
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 \
                and isinstance(statement.targets[0], ast.Name):
            made = [(statement.targets[0].id, statement.value)]
        elif isinstance(statement, ast.Return) and isinstance(statement.value, ast.Tuple):   # (returned as made)
            made = [(_first_name(item), item) for item in statement.value.elts]
        else:
            continue
        for array, value in made:
            how = _reordering(value, array) if array else ""
            if how:
                reordered.setdefault(array, (value, how))
    arrays = sorted(reordered)
    for i, a in enumerate(arrays):
        for b in arrays[i + 1:]:
            if _paired(a, b):
                (first, how), (second, _) = sorted((reordered[a], reordered[b]),
                                                   key=lambda x: (x[0].lineno, x[0].col_offset))
                a, b = (a, b) if reordered[a][0] is first else (b, a)
                where = f"line {_line(first)}" if _line(first) == _line(second) else \
                    f"lines {_line(first)} and {_line(second)}"
                return [Finding(name, _line(second), "the two arrays of one set of pairs reordered apart",
                                f"{name} ({where}) reorders `{a}` and `{b}` each by "
                                f"its own values ({how}): row k of `{a}` is no longer the partner of row k of "
                                f"`{b}`; keep or reorder the pairs together, with one index for both", certain=True)]
    return []


def _made_homogeneous(value) -> bool:
    """``_homogeneous(pts)``, ``np.hstack([pts, np.ones((n, 1))])``, ``np.column_stack([x, y, np.ones(n)])``:
    rows ending in a homogeneous 1."""
    if not isinstance(value, ast.Call):
        return False
    called = _call_name(value)
    if "homogen" in called.lower() and "convertPoints" not in called:
        return True
    return called in ("hstack", "column_stack", "concatenate") and value.args \
        and isinstance(value.args[0], (ast.List, ast.Tuple)) and value.args[0].elts \
        and isinstance(value.args[0].elts[-1], ast.Call) and _call_name(value.args[0].elts[-1]) in ("ones", "ones_like")


def _column_means(value, array: str) -> bool:
    """``array.mean(axis=0)`` or ``np.mean(array, axis=0)``: the mean of every column."""
    if not (isinstance(value, ast.Call) and _call_name(value) == "mean" and isinstance(value.func, ast.Attribute)):
        return False
    if isinstance(value.func.value, ast.Name) and value.func.value.id in ("np", "numpy"):   # np.mean(array, axis=0)
        of, positional = (value.args[0] if value.args else None), value.args[1:2]
    else:                                                                                # array.mean(axis=0)
        of, positional = value.func.value, value.args[:1]
    axis = [k.value for k in value.keywords if k.arg == "axis"] or positional
    return isinstance(of, ast.Name) and of.id == array and bool(axis) and isinstance(axis[0], ast.Constant) \
        and axis[0].value == 0


def _homogeneous_centred(name, function) -> list[Finding]:
    """``p = _homogeneous(pts)`` then ``p - p.mean(axis=0)``: the centroid of rows (x, y, 1) is (cx, cy, 1), so
    the subtraction makes every homogeneous 1 a 0 -- the points sent to infinity -- where only x and y are
    to be centred. (One pass over the def's nodes.)"""
    homogeneous, means = set(), {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            target = node.targets[0].id
            if _made_homogeneous(node.value):
                homogeneous.add(target)
            for array in homogeneous:
                if _column_means(node.value, array):
                    means[target] = array
    for node in _nodes(function):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Sub) and isinstance(node.left, ast.Name) \
                and node.left.id in homogeneous and (_column_means(node.right, node.left.id) or (
                    isinstance(node.right, ast.Name) and means.get(node.right.id) == node.left.id)):
            array = node.left.id
            return [Finding(name, _line(node), "the homogeneous 1s centred with the points",
                            f"{name} (line {_line(node)}) subtracts from `{array}`, whose rows end in a homogeneous 1, "
                            f"the mean of every column: that 1 becomes 0 in every row (the points are sent to "
                            f"infinity); centre x and y only (`{array}[:, :2]` and its mean)", certain=True)]
    return []


def _keypoints_sorted_apart(name, function) -> list[Finding]:
    """``kp, des = sift.detectAndCompute(...)`` then ``kp = sorted(kp, key=...)`` with ``des`` left in its order:
    descriptor i no longer belongs to keypoint i, so every match's indices point at other keypoints. (One
    pass over the def's assignments.)"""
    made, later = {}, []   # keypoints -> (descriptors, line); assignments after
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1:
            target = node.targets[0]
            if isinstance(target, ast.Tuple) and len(target.elts) == 2 and all(isinstance(e, ast.Name) for e in target.elts) \
                    and isinstance(node.value, ast.Call) and _call_name(node.value) in ("detectAndCompute", "compute"):
                made[target.elts[0].id] = (target.elts[1].id, _line(node))
            later.append(node)
    for node in sorted(later, key=_line):
        target = node.targets[0]
        if isinstance(target, ast.Name) and target.id in made and isinstance(node.value, ast.Call) \
                and _call_name(node.value) in ("sorted", "reversed") and node.value.args \
                and isinstance(node.value.args[0], ast.Name) and node.value.args[0].id == target.id:
            descriptors, line = made[target.id]
            if any(_line(other) > line and any(isinstance(t, ast.Name) and t.id == descriptors
                                               for t in walk(other.targets[0])) for other in later):
                continue   # (the descriptors are given an order too: whether it is the same, the checks say)
            return [Finding(name, _line(node), "keypoints reordered apart from their descriptors",
                            f"{name} (line {_line(node)}) reorders `{target.id}` with `{_call_name(node.value)}` but "
                            f"not `{descriptors}`, made with it on line {line}: descriptor i no longer belongs to "
                            f"keypoint i, so each match's indices point at other keypoints; keep them in the order "
                            f"they were made, or put both in one order", certain=True)]
    return []


# ------------------------------------------------------------------ twins written unlike each other
_TWIN_TOKEN = re.compile(r"^([a-z]?)([xy])([a-z0-9]?)$")


def _twin_name(identifier: str) -> str:
    """``identifier`` with x and y exchanged where they stand as a coordinate (``map_x`` -> ``map_y``,
    ``cx`` -> ``cy``, ``xs`` -> ``ys``, ``x0`` -> ``y0``; ``max`` stays)."""
    parts = identifier.split("_")
    for i, part in enumerate(parts):
        match = _TWIN_TOKEN.match(part)
        if match:
            parts[i] = match.group(1) + {"x": "y", "y": "x"}[match.group(2)] + match.group(3)
    return "_".join(parts)


def _twin_lopsided(name, function) -> list[Finding]:
    """Two assignments of twin names (``map_x = cx + c * dx - s * dy``, ``map_y = s * dx + c * dy``)
    whose right sides read the same names, x and y exchanged, but for one the other lacks, which the
    function has (``cy``): a step applied to one coordinate only."""
    known = set(_assigned_names(function)) | {a.arg for a in function.args.args + function.args.kwonlyargs}
    assigned = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            assigned.setdefault(node.targets[0].id, node)
    for first, statement in assigned.items():
        second = _twin_name(first)
        if second == first or second not in assigned or first > second:
            continue
        mine = {_twin_name(n) for n in _names_in(statement.value)}
        theirs = _names_in(assigned[second].value)
        for lacking, kept, missing in ((second, first, mine - theirs), (first, second, theirs - mine)):
            lone = assigned[lacking]
            term = _twin_name(next(iter(missing))) if lacking == first and missing else next(iter(missing), "")
            # (one name apart; the name missing is a coordinate's, is the function's, is neither twin itself, and
            # its own twin is not there either -- x's skew term K[0, 1] * yd beside yd has no twin in y's)
            if len(mine ^ theirs) == 1 and len(missing) == 1 and term in known and term != _twin_name(term) \
                    and term not in (first, second) and _twin_name(term) not in _names_in(lone.value):
                return [Finding(name, _line(lone), f"`{lacking}` lacks the `{term}` its twin `{kept}` has",
                                f"{name} (line {_line(lone)}) computes `{lacking} = {ast.unparse(lone.value)}`, "
                                f"without the `{term}` its twin `{kept}` has (`{_twin_name(term)}` there): a step "
                                f"applied to one coordinate only")]
    return []


# ------------------------------------------------------------------ one array appended at every turn
_MADE_ARRAYS = frozenset({"empty", "zeros", "ones", "full", "empty_like", "zeros_like", "ones_like", "full_like",
                          "array", "copy", "eye", "identity"})


_OPERATOR_TEXT = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.MatMult: "@"}


def _makes_a_container(node) -> bool:
    """Whether ``node`` makes a list or a dict (`[]`, `[None] * n`, `list(...)`, `{}`, `dict()`): a container
    whose items are the objects put in it."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult):
        return _makes_a_container(node.left) or _makes_a_container(node.right)
    return isinstance(node, (ast.List, ast.ListComp, ast.Dict, ast.DictComp)) \
        or (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("list", "dict"))


def _comparison_as_a_statement(name, function) -> list[Finding]:
    """``M[0, 1] == s`` written as a statement of its own: a comparison of an entry whose result nothing keeps,
    where an assignment (``=``) was meant -- the entry keeps its value."""
    for node in _nodes(function):
        # (an entry's: `result.shape == (3,)` or `x == 5`, a check left from debugging, writes nothing anyway)
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Compare) and len(node.value.ops) == 1 \
                and isinstance(node.value.ops[0], ast.Eq) and isinstance(node.value.left, ast.Subscript):
            target = ast.unparse(node.value.left)
            return [Finding(name, _line(node), "a comparison written where an assignment belongs", certain=True,
                            sentence=f"{name} (line {_line(node)}) writes `{ast.unparse(node.value)[:60]}` as a "
                                     f"statement: == compares and nothing keeps the answer, so `{target}` keeps its "
                                     f"value; = assigns (`{target} = {ast.unparse(node.value.comparators[0])[:40]}`)")]
    return []


def _one_object_repeated(name, function) -> list[Finding]:
    """``Hs = [np.eye(3)] * n`` (or ``grid = [[0] * w] * h``) and an item changed in place (``Hs[k] @= step``,
    ``grid[i][j] = v``): a list repeated by ``*`` holds the one object n times, so the change is every item's.
    (One pass over the def's nodes: linear in its size.)"""
    repeated: dict[str, ast.Assign] = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and isinstance(node.value, ast.BinOp) and isinstance(node.value.op, ast.Mult):
            listed = next((side for side in (node.value.left, node.value.right)
                           if isinstance(side, ast.List) and len(side.elts) == 1), None)
            item = listed.elts[0] if listed is not None else None
            if (isinstance(item, ast.Call) and _call_name(item) in _MADE_ARRAYS) or isinstance(item, ast.List) or (
                    isinstance(item, ast.BinOp) and isinstance(item.op, ast.Mult)
                    and any(isinstance(side, ast.List) for side in (item.left, item.right))):
                repeated.setdefault(node.targets[0].id, node)
    if not repeated:
        return []
    for node in sorted(_nodes(function), key=_line):
        # (an item changed where it is: `Hs[k] @= ...` on an array, `grid[i][j] = ...` on an inner list)
        target = node.target if isinstance(node, ast.AugAssign) else \
            node.targets[0] if isinstance(node, ast.Assign) and len(node.targets) == 1 else None
        item = target.value if isinstance(node, ast.Assign) and isinstance(target, ast.Subscript) else target
        if not (isinstance(item, ast.Subscript) and isinstance(item.value, ast.Name) and item.value.id in repeated):
            continue
        if isinstance(node, ast.AugAssign) and isinstance(repeated[item.value.id].value, ast.BinOp) \
                and not _repeats_an_array(repeated[item.value.id].value):
            continue   # (`counts[k] += 1` on a list of numbers rebinds the item: no object is changed)
        made = repeated[item.value.id]
        return [Finding(name, _line(node), "one object repeated by * and changed in place", certain=True, sentence=
                        f"{name} (line {_line(made)}) makes `{item.value.id}` with `{ast.unparse(made.value)[:60]}`: "
                        f"a list repeated by * holds the one object that many times, not copies, so "
                        f"`{ast.unparse(node)[:60]}` (line {_line(node)}), which changes an item in place, changes "
                        f"every item; make each its own (`[... for _ in range(n)]`)")]
    return []


def _repeats_an_array(value: ast.BinOp) -> bool:
    """Whether ``[x] * n`` repeats an array made by a call (not a number or a list, which ``+=`` rebinds)."""
    return any(isinstance(side, ast.List) and isinstance(side.elts[0], ast.Call) for side in (value.left, value.right)
               if isinstance(side, ast.List) and side.elts)


def _same_array_appended(name, function) -> list[Finding]:
    """``buf = np.empty(...)`` before a loop, ``buf[:] = ...`` (or ``buf *= ...``) in it, and ``out.append(buf)``:
    each item of the list is that one array, which ends with the last turn's values."""
    made_before: dict = {}
    made = _assigned_names(function)
    containers = {target for target, values in made.items() if values and all(_makes_a_container(v) for v in values)}
    found: list[Finding] = []
    within: set = set()   # (the nodes of a loop already read: only outermost loops are, each node once)
    for statement in sorted((node for node in _nodes(function) if isinstance(node, (ast.Assign, ast.For, ast.While))),
                            key=_line):
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 and isinstance(statement.targets[0], ast.Name):
            value = statement.value
            if isinstance(value, ast.Call) and _call_name(value) in _MADE_ARRAYS:
                made_before[statement.targets[0].id] = _line(statement)
            else:
                made_before.pop(statement.targets[0].id, None)
        if not isinstance(statement, (ast.For, ast.While)) or id(statement) in within:
            continue
        inside = [n for part in statement.body for n in walk(part)]
        within.update(id(n) for n in inside)
        rebound = {t.id for n in inside if isinstance(n, (ast.Assign, ast.AugAssign, ast.For))
                   for target in (n.targets if isinstance(n, ast.Assign) else [n.target])
                   for t in ([target] if isinstance(target, ast.Name) else
                             [e for e in getattr(target, "elts", []) if isinstance(e, ast.Name)])
                   if not isinstance(n, ast.AugAssign)}
        changed = {n.targets[0].value.id: _line(n) for n in inside
                   if isinstance(n, ast.Assign) and len(n.targets) == 1 and isinstance(n.targets[0], ast.Subscript)
                   and isinstance(n.targets[0].value, ast.Name)}
        changed.update({n.target.id: _line(n) for n in inside if isinstance(n, ast.AugAssign)
                        and isinstance(n.target, ast.Name)})
        for call in inside:
            # (kept by `out.append(buf)`, or by `out[k] = buf` -- a running product `chain @= step` kept per image)
            if isinstance(call, ast.Call) and isinstance(call.func, ast.Attribute) and call.func.attr == "append" \
                    and len(call.args) == 1 and isinstance(call.args[0], ast.Name):
                array, listed, verb = call.args[0].id, ast.unparse(call.func.value), "appends"
            elif isinstance(call, ast.Assign) and len(call.targets) == 1 and isinstance(call.targets[0], ast.Subscript) \
                    and isinstance(call.value, ast.Name) and isinstance(call.targets[0].value, ast.Name) \
                    and call.targets[0].value.id in containers:
                # (a list's or a dict's item holds the object; an array's item is written with its values, a copy)
                array, listed, verb = call.value.id, call.targets[0].value.id, "stores"
            else:
                continue
            if array in made_before and array in changed and array not in rebound:
                copied = "append a copy" if verb == "appends" else "store a copy"
                update = next((n for n in inside if isinstance(n, ast.AugAssign) and isinstance(n.target, ast.Name)
                               and n.target.id == array), None)
                fresh = f" (`{array} = {array} {_OPERATOR_TEXT.get(type(update.op), '?')} " \
                        f"{ast.unparse(update.value)}`)" if update is not None and type(update.op) in _OPERATOR_TEXT else ""
                found.append(Finding(name, _line(call), "one array is appended at every turn",
                                     f"{name} (line {_line(call)}) {verb} `{array}` in `{listed}` at every turn of the "
                                     f"loop, and line {changed[array]} changes `{array}` in place: every item it put in "
                                     f"`{listed}` is that one array (made on line {made_before[array]}), holding the "
                                     f"last turn's values; {copied} (`{array}.copy()`) or make a new array at each "
                                     f"turn{fresh}", certain=True))
                break   # (one per loop)
    if len(found) > 1:   # (the same in several loops -- a walk to each side of a reference image: one finding)
        others = " and ".join(str(f.line) for f in found[1:])
        found[0] = replace(found[0], sentence=f"{found[0].sentence}; " + (f"lines {others} do the same" if len(found) > 2
                                                                           else f"line {others} does the same"))
    return found[:1]


# ------------------------------------------------------------------ a running best overwritten
def _loop_body_nodes(loop):
    """The nodes of ``loop``'s body outside the loops nested in it (each node is read with its nearest loop)."""
    pending = list(loop.body)
    while pending:
        node = pending.pop()
        yield node
        if not isinstance(node, (ast.For, ast.While)):
            pending.extend(ast.iter_child_nodes(node))


def overwritten_running_bests(function) -> list[tuple[ast.Compare, ast.Assign, str, str, bool]]:
    """In a loop, a value compared with a best so far (``better = ssd < best_cost``, ``if score > best:``) and
    that best then set to the value whole at every turn (``best_cost = ssd`` outside the ``if`` of the
    comparison): the best holds the last turn's value, not the lowest (highest). Each as (the comparison,
    the assignment, the value's name, the best's name, whether the lowest is kept)."""
    found = []
    for loop in (node for node in _nodes(function) if isinstance(node, (ast.For, ast.While))):
        nodes = list(_loop_body_nodes(loop))
        # (an assignment under an `if` of the loop -- `if c < best: best = c` -- keeps the best; each node read once)
        guarded = {id(statement) for node in nodes if isinstance(node, ast.If) for statement in node.body + node.orelse}
        compares = {}
        for node in nodes:
            if isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], (ast.Lt, ast.Gt, ast.LtE, ast.GtE)) \
                    and isinstance(node.left, ast.Name) and isinstance(node.comparators[0], ast.Name):
                lower = isinstance(node.ops[0], (ast.Lt, ast.LtE))
                value, best = node.left.id, node.comparators[0].id
                compares.setdefault((value, best), (node, lower))
                compares.setdefault((best, value), (node, not lower))   # (best > c: c is lower)
        for node in nodes:
            if isinstance(node, ast.Assign) and id(node) not in guarded and len(node.targets) == 1 \
                    and isinstance(node.targets[0], ast.Name) and isinstance(node.value, ast.Name):
                best, value = node.targets[0].id, node.value.id
                if (value, best) in compares and best != value:
                    compare, lower = compares[(value, best)]
                    found.append((compare, node, value, best, lower))
    return found


def _running_best_overwritten(name, function) -> list[Finding]:
    for compare, assign, value, best, lower in overwritten_running_bests(function):
        keep = "np.minimum" if lower else "np.maximum"
        return [Finding(name, _line(assign), "the best so far is overwritten at every turn",
                        f"{name} compares `{value}` with the best so far `{best}` (line {_line(compare)}), then sets "
                        f"`{best} = {value}` at every turn of the loop (line {_line(assign)}): `{best}` holds the last "
                        f"turn's values, not the {'lowest' if lower else 'highest'} found; keep it where it is beaten "
                        f"(`{best} = {keep}({best}, {value})`, or `{best}[better] = {value}[better]`)", certain=True)]
    return []


# ------------------------------------------------------------------ an alias changed in place
def _made_as_arrays(made: dict) -> set[str]:
    """Of :func:`_assigned_names`' names, those every assignment makes an array or list (a call, a subscript, a
    list): an int's `j += 1` binds anew, it changes nothing shared."""
    return {target for target, values in made.items() if values and all(_array_or_list(v) for v in values)}


def _a_list(value) -> bool:
    """A list written out, made by a comprehension, or lists joined by +."""
    if isinstance(value, ast.BinOp) and isinstance(value.op, ast.Add):
        return _a_list(value.left) and _a_list(value.right)
    return isinstance(value, (ast.List, ast.ListComp))


def _array_or_list(value) -> bool:
    """A call, a subscript, a list, or lists joined (`["0" + c for c in codes] + [...]`)."""
    if isinstance(value, ast.BinOp) and isinstance(value.op, ast.Add):
        return _array_or_list(value.left) and _array_or_list(value.right) \
            and not isinstance(value.left, ast.Call) and not isinstance(value.right, ast.Call)
    return isinstance(value, (ast.Call, ast.Subscript, ast.List, ast.ListComp))


# methods that reorder or overwrite their list or array in place (and return None); growing a list through another
# name for it (`rows = out; rows.append(x)`) is as often meant as not, and is not read
_IN_PLACE_METHODS = frozenset({"reverse", "sort", "fill"})


def _alias_changed(name, function) -> list[Finding]:
    """``b = a`` (another name for the same array, no copy), then ``b *= f`` or ``b[...] = v`` in place, in a
    loop or with ``a`` read afterwards: ``a`` changes with it."""
    loops = [node for node in _nodes(function) if isinstance(node, (ast.For, ast.While))]
    in_loop: set = set()
    for loop in loops:   # (breadth first: an outer loop marks the loops inside it, which are then skipped)
        if id(loop) not in in_loop:
            in_loop.update(id(n) for statement in loop.body for n in walk(statement))
    last_read: dict = {}   # name -> the last line reading it
    for n in _nodes(function):
        if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load):
            last_read[n.id] = max(last_read.get(n.id, 0), _line(n))
    # (arrays: names made by a call or a subscript -- an int's `j += 1` binds anew, it changes nothing shared)
    counters = {n.id for loop in loops if isinstance(loop, ast.For) for n in walk(loop.target)
                if isinstance(n, ast.Name)}
    made = _assigned_names(function)
    # (and lists: `row_x = [x, y, 1, 0, 0, 0]` is as shared by `row_y = row_x`)
    arrays = _made_as_arrays(made) - counters
    lists = {target for target in arrays if all(_a_list(v) for v in made[target])}
    statements = _statements_in_order(function)
    aliases = {}   # alias -> (original, line bound, bound in a loop)
    for statement in statements:
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 and isinstance(statement.targets[0], ast.Name):
            target, value = statement.targets[0].id, statement.value
            aliases.pop(target, None)
            if isinstance(value, ast.Name) and value.id != target and value.id in arrays:
                aliases[target] = (value.id, _line(statement), id(statement) in in_loop)
            continue
        # (`n -= 1` counts: a number binds anew)
        changed = statement.target if isinstance(statement, ast.AugAssign) \
            and not isinstance(statement.value, ast.Constant) else None
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 and isinstance(statement.targets[0],
                                                                                          ast.Subscript):
            changed = statement.targets[0].value
        if isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Call) \
                and isinstance(statement.value.func, ast.Attribute) and statement.value.func.attr in _IN_PLACE_METHODS:
            changed = statement.value.func.value   # (`mirrored.reverse()`, `b.sort()`, `b.fill(0)`)
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 \
                and isinstance(statement.targets[0], (ast.Tuple, ast.List)):
            # (`row_y[:3], row_y[3:] = zeros, xy1`: parts written together)
            changed = next((part.value for part in statement.targets[0].elts if isinstance(part, ast.Subscript)
                            and isinstance(part.value, ast.Name) and part.value.id in aliases), changed)
        if isinstance(changed, ast.Name) and changed.id in aliases:
            original, bound, looping = aliases[changed.id]
            later = last_read.get(original, 0) > _line(statement)
            if looping or later:
                return [Finding(name, _line(statement), "an alias of an array is changed in place",
                                f"{name} (line {_line(statement)}) changes `{changed.id}` in place, but "
                                f"`{changed.id} = {original}` (line {bound}) made it another name for the same "
                                f"{'list' if original in lists else 'array'}, "
                                f"so `{original}` changes with it" + (" at every turn of the loop" if looping else "")
                                + f"; take a copy (`{changed.id} = {original}.copy()`)", certain=True)]
    return []


# ------------------------------------------------------------------ a kept value that is the array the loop rewrites
def _written_in_place(node) -> str | None:
    """The name ``node`` writes into in place, if it does: ``a[...] = v``, ``a += v`` of an array, a call's
    ``out=a``, ``np.copyto(a, v)``, ``a.fill(v)``."""
    if isinstance(node, ast.Assign):
        for target in node.targets:
            if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name):
                return target.value.id
    if isinstance(node, ast.AugAssign) and isinstance(node.target, ast.Subscript) \
            and isinstance(node.target.value, ast.Name):
        return node.target.value.id
    if isinstance(node, ast.Call):
        out = next((k.value for k in node.keywords if k.arg == "out"), None)
        if isinstance(out, ast.Tuple) and out.elts:
            out = out.elts[0]
        if isinstance(out, ast.Name):
            return out.id
        if _call_name(node) == "copyto" and node.args and isinstance(node.args[0], ast.Name):
            return node.args[0].id
        if isinstance(node.func, ast.Attribute) and node.func.attr == "fill" and isinstance(node.func.value, ast.Name):
            return node.func.value.id
    return None


def _first_writes(nodes) -> dict:
    """name -> the first of ``nodes`` that writes into it in place (:func:`_written_in_place`)."""
    written: dict = {}
    for n in nodes:
        target = _written_in_place(n)
        if target is not None:
            written.setdefault(target, n)
    return written


def _kept_alias_rewritten(name, function) -> list[Finding]:
    """In a loop, ``best = mask`` (another name for the array, no copy) where the loop writes ``mask`` in place
    at every turn (``np.less(err, t, out=mask)``, ``mask[:] = ...``) and ``mask`` is made once, outside it: the
    value kept is that same array, so after the loop it holds the last turn's values, not those kept."""
    arrays = _made_as_arrays(_assigned_names(function))
    read_at: dict = {}
    for n in _nodes(function):
        if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load):
            read_at.setdefault(n.id, []).append(_line(n))
    for loop in (node for node in _nodes(function) if isinstance(node, (ast.For, ast.While))):
        nodes = [n for statement in loop.body for n in walk(statement)]
        rebound = {n.id for n in nodes if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
        written = _first_writes(nodes)
        end = max((_line(n) for n in nodes), default=_line(loop))
        for n in nodes:
            if not (isinstance(n, ast.Assign) and len(n.targets) == 1):
                continue
            pairs = zip(n.targets[0].elts, n.value.elts) if isinstance(n.targets[0], ast.Tuple) \
                and isinstance(n.value, ast.Tuple) and len(n.targets[0].elts) == len(n.value.elts) \
                else [(n.targets[0], n.value)]
            for kept, original in pairs:
                if not (isinstance(kept, ast.Name) and isinstance(original, ast.Name)) or kept.id == original.id \
                        or original.id not in arrays or original.id in rebound or original.id not in written:
                    continue
                if not any(line > end for line in read_at.get(kept.id, ())):
                    continue
                write = written[original.id]
                return [Finding(name, _line(n), "a value kept in a loop is the array the loop rewrites",
                                f"{name} keeps `{kept.id} = {original.id}` (line {_line(n)}), another name for the same "
                                f"array, not a copy, and the loop writes `{original.id}` in place at every turn "
                                f"(line {_line(write)}): after the loop `{kept.id}` holds the last turn's values, not "
                                f"those kept; keep a copy (`{kept.id} = {original.id}.copy()`)", certain=True)]
    return []


# ------------------------------------------------------------------ one array under two names from the start
def _chained_one_array(name, function) -> list[Finding]:
    """``xs = ys = np.full(n, np.nan)``: a chained assignment gives one array two names, and each is then
    written into as if it were its own (``xs[i] = ...``, ``ys[i] = ...``): every write lands in both."""
    made = _assigned_names(function)
    written = _first_writes(_nodes(function))
    for n in _nodes(function):
        if not (isinstance(n, ast.Assign) and len(n.targets) >= 2
                and all(isinstance(t, ast.Name) for t in n.targets)
                and isinstance(n.value, (ast.Call, ast.List, ast.ListComp, ast.Dict))):
            continue
        names = list(dict.fromkeys(t.id for t in n.targets))
        # (each of them written into, and none given an array of its own elsewhere)
        if len(names) >= 2 and all(x in written and len(made.get(x, ())) == 1 for x in names[:2]):
            first, second = names[:2]
            return [Finding(name, _line(n), "one array given two names by a chained assignment",
                            f"{name} makes `{first}` and `{second}` with `{ast.unparse(n)[:80]}` (line {_line(n)}): a "
                            f"chained assignment gives one array two names, so what is written into `{second}` "
                            f"(line {_line(written[second])}) is written into `{first}` too; make each its own "
                            f"(`{first} = ...` and `{second} = ...` on lines of their own)", certain=True)]
    return []


# ------------------------------------------------------------------ a binary search of a table not sorted
def _gray_encoded(value) -> bool:
    """``k ^ (k >> 1)`` somewhere in ``value``: Gray codes, a table of stripes' codes in stripe order."""
    for n in walk(value):
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.BitXor):
            for one, other in ((n.left, n.right), (n.right, n.left)):
                if isinstance(other, ast.BinOp) and isinstance(other.op, ast.RShift) \
                        and ast.dump(other.left) == ast.dump(one):
                    return True
    return False


def _searched_unsorted(name, function) -> list[Finding]:
    """``np.searchsorted(codes, g)`` with ``codes = k ^ (k >> 1)``: a binary search finds a value's place only in
    a sorted array, and the Gray codes in stripe order are not sorted (0, 1, 3, 2, 6, ...), so most values are
    answered with another index than theirs."""
    made = _assigned_names(function)
    for n in _nodes(function):
        if not (isinstance(n, ast.Call) and _dotted_name(n.func) in ("np.searchsorted", "numpy.searchsorted")
                and n.args and isinstance(n.args[0], ast.Name) and not any(k.arg == "sorter" for k in n.keywords)):
            continue
        table = n.args[0].id
        values = made.get(table, ())
        value = values[0] if len(values) == 1 else _UNKNOWN
        # (the table as the XOR made it, or a list of it -- not sorted after: np.sort(...), codes.sort())
        made_as_is = isinstance(value, ast.BinOp) or (isinstance(value, (ast.ListComp, ast.Call)) and not (
            isinstance(value, ast.Call) and _dotted_name(value.func).rsplit(".", 1)[-1] in ("sort", "sorted", "unique")))
        sorted_later = any(isinstance(m, ast.Call) and isinstance(m.func, ast.Attribute) and m.func.attr == "sort"
                           and isinstance(m.func.value, ast.Name) and m.func.value.id == table for m in _nodes(function))
        if value is not _UNKNOWN and made_as_is and not sorted_later and _gray_encoded(value):
            return [Finding(name, _line(n), "a binary search (np.searchsorted) of a table that is not sorted",
                            f"{name} looks values up with `{ast.unparse(n)[:70]}` (line {_line(n)}), a binary search, "
                            f"in `{table}`, the Gray codes in stripe order ({ast.unparse(values[0])[:40]}), which are "
                            "not sorted (0, 1, 3, 2, 6, 7, 5, 4, ...): it answers most codes with another stripe's "
                            f"index; invert the table instead (`index[{table}] = np.arange(len({table}))`, then "
                            "`index[g]`) or decode the bits by XOR", certain=True)]
    return []


# ------------------------------------------------------------------ a lambda reading a loop's variable late
def _late_bound_lambda(name, function) -> list[Finding]:
    """``[lambda p: project(p, f) for f in fs]`` (or ``fns.append(lambda ...)`` in a ``for f`` loop): the lambda
    reads ``f`` when it is called, after the loop has ended, so every one of them uses f's last value."""
    def free_reads(lam: ast.Lambda) -> set:
        own = {a.arg for a in lam.args.args + lam.args.kwonlyargs + lam.args.posonlyargs}
        return {n.id for n in walk(lam.body) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)} - own

    def targets(node) -> set:
        return {n.id for n in walk(node) if isinstance(n, ast.Name)}

    for n in _nodes(function):
        places = []
        if isinstance(n, (ast.ListComp, ast.GeneratorExp, ast.SetComp)) and isinstance(n.elt, ast.Lambda):
            places = [(n.elt, set().union(*(targets(g.target) for g in n.generators)))]
        elif isinstance(n, ast.DictComp) and isinstance(n.value, ast.Lambda):
            places = [(n.value, set().union(*(targets(g.target) for g in n.generators)))]
        elif isinstance(n, ast.For):
            loop_names = targets(n.target)
            places = [(arg, loop_names) for statement in n.body for call in walk(statement)
                      if isinstance(call, ast.Call) and isinstance(call.func, ast.Attribute)
                      and call.func.attr in ("append", "extend", "insert")
                      for arg in call.args if isinstance(arg, ast.Lambda)]
        for lam, loop_names in places:
            late = sorted(free_reads(lam) & loop_names)
            if late:
                var = late[0]
                return [Finding(name, _line(lam), "a lambda made in a loop reads the loop's variable when called",
                                f"{name} makes `{ast.unparse(lam)[:70]}` in a loop over `{var}` (line {_line(lam)}): a "
                                f"lambda reads `{var}` when it is called, after the loop has ended, so every one of "
                                f"them uses `{var}`'s last value; bind it as it is made (`lambda ..., {var}={var}: "
                                f"...`) or compute each result in the loop", certain=True)]
    return []


# ------------------------------------------------------------------ np.empty rows a loop skips
def _empty_rows_skipped(name, function) -> list[Finding]:
    """``out = np.empty((n, 6))`` filled row by row in a loop that ``continue``s past some turns before writing
    their row: those rows hold whatever the memory held (not NaN, not 0)."""
    empties = {}
    for n in _nodes(function):
        if isinstance(n, ast.Assign) and len(n.targets) == 1 and isinstance(n.targets[0], ast.Name) \
                and isinstance(n.value, ast.Call) and _call_name(n.value) in ("empty", "empty_like"):
            empties[n.targets[0].id] = n
    if not empties:
        return []
    for loop in (node for node in _nodes(function) if isinstance(node, (ast.For, ast.While))):
        body = list(_loop_body_nodes(loop))
        inside = {id(n) for statement in loop.body for n in walk(statement)}
        # (an array also written outside the loop -- filled with NaN before it, its skipped rows set after it --
        # is no garbage)
        outside = {_written_in_place(n) for n in _nodes(function) if id(n) not in inside}
        writes = [n for n in body if _written_in_place(n) in empties.keys() - outside and isinstance(n, ast.Assign)]
        blocks = {id(statement): block for n in body if isinstance(n, (ast.If, ast.Try, ast.With))
                  for block in (getattr(n, "body", []), getattr(n, "orelse", [])) for statement in block}
        for skip in (n for n in body if isinstance(n, ast.Continue)):
            # (the block that continues writes nothing of the array before it: `out[i] = np.nan; continue` is fine)
            block = blocks.get(id(skip))
            if block is None or any(_written_in_place(s) in empties for s in block):
                continue
            later = [w for w in writes if _line(w) > _line(skip)]
            if later:
                array = _written_in_place(later[0])
                return [Finding(name, _line(skip), "rows of np.empty left unwritten where a loop continues",
                                f"{name} makes `{array}` with np.empty (line {_line(empties[array])}), which holds "
                                f"whatever the memory held, and the turns that `continue` (line {_line(skip)}) never "
                                f"write their row (line {_line(later[0])}): those rows are garbage, not the value the "
                                f"API asks; make it with np.full(..., np.nan) (or write the row before continuing)",
                                certain=True)]
    return []


# ------------------------------------------------------------------ a whole row's norm where its block's belongs
def _column_block(node) -> str | None:
    """``P[:, :3]``, ``P[:3, :3]`` or ``P[:, :-1]``: the name of the matrix whose left block is taken."""
    if not (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and isinstance(node.slice, ast.Tuple)
            and len(node.slice.elts) == 2 and isinstance(node.slice.elts[1], ast.Slice)):
        return None
    columns = node.slice.elts[1]
    return node.value.id if columns.lower is None and columns.upper is not None and columns.step is None else None


def _row_norm_of_whole_matrix(name, function) -> list[Finding]:
    """``P / np.linalg.norm(P[2])`` where the code takes P's left block ``P[:, :3]`` as the matrix it decomposes:
    the whole row's length counts its last column too (P[2, 3], t_z's share), where the block's row's belongs."""
    blocks = {found for n in _nodes(function) if (found := _column_block(n)) is not None}
    # (code that divides by a matrix's last diagonal entry -- K / K[2, 2] -- fixes the scale afterwards, and with t
    # solved from the K before it, the whole row's norm does no harm)
    if any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.Div) and isinstance(n.right, ast.Subscript)
           and ast.unparse(n.right.slice).strip("()") in ("2, 2", "-1, -1") for n in _nodes(function)) \
            or any(isinstance(n, ast.AugAssign) and isinstance(n.op, ast.Div) and isinstance(n.value, ast.Subscript)
                   and ast.unparse(n.value.slice).strip("()") in ("2, 2", "-1, -1") for n in _nodes(function)):
        return []
    for n in _nodes(function):
        if isinstance(n, ast.Call) and _call_name(n) == "norm" and len(n.args) == 1 and not n.keywords \
                and isinstance(n.args[0], ast.Subscript) and isinstance(n.args[0].value, ast.Name) \
                and n.args[0].value.id in blocks and isinstance(n.args[0].slice, ast.Constant) \
                and isinstance(n.args[0].slice.value, int):
            matrix, row = n.args[0].value.id, n.args[0].slice.value
            block = next(ast.unparse(b) for b in _nodes(function) if _column_block(b) == matrix)
            columns = block.split(",", 1)[1].strip(" ]")
            return [Finding(name, _line(n), "a whole row's norm where the block's row's belongs",
                            f"{name} scales by `{ast.unparse(n)}` (line {_line(n)}), the length of {matrix}'s whole row "
                            f"{row}, its last column included, while the matrix it works on is the block `{block}`: that "
                            f"row's length in the block is `np.linalg.norm({matrix}[{row}, {columns}])`", certain=True)]
    return []


# ------------------------------------------------------------------ every view given as one
_CALIBRATIONS = {"calibrateCamera", "calibrateCameraExtended", "calibrateCameraRO", "stereoCalibrate"}
_JOINS = {"concatenate", "vstack", "hstack", "row_stack", "stack"}


def _views_merged(name, function) -> list[Finding]:
    """``cv2.calibrateCamera([np.concatenate(object_points)], [np.concatenate(image_points)], ...)``: a list of one
    view made of every view's points; OpenCV fits one pose per view, and no pose puts the board's points, the same
    for every view, on corners seen from different places."""
    def merged(node):
        return isinstance(node, ast.List) and len(node.elts) == 1 and isinstance(node.elts[0], ast.Call) \
            and _call_name(node.elts[0]) in _JOINS

    made = _assigned_names(function)
    for n in _nodes(function):
        if not (isinstance(n, ast.Call) and _call_name(n) in _CALIBRATIONS):
            continue
        for argument in n.args[:2]:
            value = argument if merged(argument) else None
            if value is None and isinstance(argument, ast.Name):
                value = next((v for v in made.get(argument.id, ()) if merged(v)), None)
            if value is not None:
                return [Finding(name, _line(value), "every view given to the calibration as one view",
                                f"{name} gives cv2.{_call_name(n)} `{ast.unparse(value)[:60]}` (line {_line(value)}): "
                                f"one view made of every view's points. OpenCV fits one pose per view, and no single "
                                f"pose puts the board's points, the same in every view, on corners seen from "
                                f"different places; give it the lists of per-view arrays as they are", certain=True)]
    return []


# ------------------------------------------------------------------ infinity through a box filter
_FILTERS = {"blur", "boxFilter", "filter2D", "GaussianBlur", "sepFilter2D", "uniform_filter", "convolve",
            "correlate", "convolve2d", "fftconvolve", "gaussian_filter"}


def _filters_first(function) -> bool:
    """Whether ``function`` passes its first parameter to a filter (:data:`_FILTERS`) as the image filtered."""
    parameters = function.args.posonlyargs + function.args.args
    return bool(parameters) and any(
        isinstance(n, ast.Call) and _call_name(n) in _FILTERS and n.args and isinstance(n.args[0], ast.Name)
        and n.args[0].id == parameters[0].arg for n in walk(function))


def _infinity_filtered(name, function, filters=frozenset(_FILTERS)) -> list[Finding]:
    """``cost[:, :d] = np.inf`` and then ``cv2.blur(cost, ...)`` (or a helper of the module that filters its
    first parameter, ``filters``): a filter's sums meet inf - inf (NaN) and spread inf or NaN over every window
    holding one; comparisons with NaN then choose nothing (argmin takes the first)."""
    def infinite(node) -> bool:
        return (isinstance(node, ast.Attribute) and node.attr == "inf") or (
            isinstance(node, ast.Call) and _call_name(node) == "float" and node.args
            and isinstance(node.args[0], ast.Constant) and str(node.args[0].value).lower() in ("inf", "+inf"))

    set_inf = {}
    for n in _nodes(function):
        if isinstance(n, ast.Assign) and infinite(n.value):
            for target in n.targets:
                if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name):
                    set_inf.setdefault(target.value.id, n)
    for n in _nodes(function):
        if isinstance(n, ast.Call) and _call_name(n) in filters and n.args and isinstance(n.args[0], ast.Name) \
                and n.args[0].id in set_inf and _line(n) > _line(set_inf[n.args[0].id]):
            array = n.args[0].id
            return [Finding(name, _line(set_inf[array]), "infinity written into an array before it is filtered",
                            f"{name} writes inf into `{array}` (line {_line(set_inf[array])}) and then filters it "
                            f"with `{_call_name(n)}` (line {_line(n)}): a filter's sums meet inf - inf, which is NaN, "
                            f"and carry inf or NaN into every window that holds one (a comparison with NaN chooses "
                            f"nothing); filter first, then set the entries to inf", certain=True)]
    return []


# ------------------------------------------------------------------ one array scaled in place at every turn
def _scaled_in_place_per_turn(name, function) -> list[Finding]:
    """``xy = project(X, 1.0)`` before ``for f in fs: xy *= f; out[i] = xy``: the array made once is scaled
    in place at every turn by that turn's value, and each turn's answer kept, so turn i holds it times every
    value so far (f_0 f_1 ... f_i), not times f_i. (A running product or sum kept on purpose starts at a
    constant -- 1, 0, np.eye(3) -- and is read after the loop: not this.)"""
    assignments: dict = {}   # name -> [(line, value)], in line order
    for statement in _statements_in_order(function):
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 and isinstance(statement.targets[0], ast.Name):
            assignments.setdefault(statement.targets[0].id, []).append((_line(statement), statement.value))

    def made_by_call(name: str, before: int) -> bool:
        earlier = [value for line, value in assignments.get(name, ()) if line < before]
        return bool(earlier) and isinstance(earlier[-1], ast.Call) and _call_name(earlier[-1]) not in (
            "eye", "ones", "zeros", "identity", "ones_like", "zeros_like", "array", "asarray", "float", "int")

    for statement in _nodes(function):
        if not isinstance(statement, ast.For):
            continue
        turn = {n.id for n in walk(statement.target) if isinstance(n, ast.Name)}
        assigned_inside = {t.id for s in walk(statement) if isinstance(s, ast.Assign)
                           for target in s.targets for t in walk(target) if isinstance(t, ast.Name)}
        for inner in statement.body:
            if not (isinstance(inner, ast.AugAssign) and isinstance(inner.op, (ast.Mult, ast.Div))
                    and isinstance(inner.target, ast.Name)):
                continue
            scaled = inner.target.id
            if not made_by_call(scaled, _line(statement)) or scaled in assigned_inside or not (_names_in(inner.value) & turn):
                continue
            kept = any(isinstance(s, (ast.Assign, ast.Expr)) and scaled in _names_in(s.value if isinstance(s, ast.Assign)
                                                                                       else s)
                       and s is not inner for s in statement.body)
            if kept:
                op = "*=" if isinstance(inner.op, ast.Mult) else "/="
                return [Finding(name, _line(inner), "an array scaled in place at every turn of a loop",
                                f"{name} (line {_line(inner)}) scales `{scaled}` in place (`{scaled} {op} "
                                f"{ast.unparse(inner.value)}`) at every turn of the loop, and `{scaled}` was made once "
                                "before it: each turn scales what the turns before left, so turn i holds it scaled by "
                                "every value so far, not by its own alone; scale a new array each turn "
                                f"(`{scaled} * {ast.unparse(inner.value)}`)", certain=True)]
    return []


# ------------------------------------------------------------------ the strip np.roll brought round, for one sign
def _rolled_strip_one_sign(name, function) -> list[Finding]:
    """``np.roll(image, (dy, dx), ...)`` then ``shifted[:dy] = 0`` (the strip rolled round for dy >= 0) with
    nothing in the function comparing dy with 0: for dy < 0 the strip is ``shifted[dy:]``, and ``[:dy]``
    blanks every row but the last |dy|."""
    shifts = {n.id for node in _nodes(function) if isinstance(node, ast.Call) and _call_name(node) == "roll"
              for argument in node.args[1:2] + [k.value for k in node.keywords if k.arg == "shift"]
              for n in walk(argument) if isinstance(n, ast.Name)}
    signed = {n.id for node in _nodes(function)
              if isinstance(node, ast.Compare) or (isinstance(node, ast.Call) and _call_name(node) in
                                                   ("max", "min", "abs", "maximum", "minimum", "clip", "sign"))
              for n in walk(node) if isinstance(n, ast.Name)}
    # (a loop's `for d in range(...)` never goes below 0)
    signed |= {node.target.id for node in _nodes(function) if isinstance(node, ast.For)
               and isinstance(node.target, ast.Name) and isinstance(node.iter, ast.Call) and _call_name(node.iter) == "range"}
    blanked = []   # (line, the subscript blanked, the shift's name)
    for node in _nodes(function):
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Subscript)):
            continue
        index = node.targets[0].slice
        for part in index.elts if isinstance(index, ast.Tuple) else [index]:
            if isinstance(part, ast.Slice) and part.step is None and (part.lower is None) != (part.upper is None):
                bound = part.upper if part.lower is None else part.lower
                if isinstance(bound, ast.Name) and bound.id in shifts and bound.id not in signed:
                    blanked.append((_line(node), ast.unparse(node.targets[0]), bound.id))
    if not blanked:
        return []
    blanked.sort()
    places = " and ".join(f"`{text}` (line {line})" for line, text, _ in blanked)
    names = ", ".join(dict.fromkeys(shift for _, _, shift in blanked))
    return [Finding(name, blanked[0][0], "the strip np.roll brings round is blanked for one sign only",
                    f"{name} blanks {places}: the strip np.roll brings round when {names} >= 0; for a negative "
                    "shift that strip is at the other end of the axis, and the line blanks the image itself instead")]


# ------------------------------------------------------------------ a write through an index that copies
_INDEX_ARRAYS = frozenset({"array", "asarray", "arange", "where", "nonzero", "flatnonzero", "argsort", "ix_"})


def _copying_index(node, made) -> bool:
    """Whether indexing with ``node`` makes NumPy copy: a list, an array of positions or a mask
    (written there, or a name only ever bound to one), never a whole number or a slice."""
    if isinstance(node, (ast.List, ast.ListComp, ast.Compare)) or (
            isinstance(node, ast.BinOp) and isinstance(node.op, (ast.BitAnd, ast.BitOr))):
        return True
    if isinstance(node, ast.Call):
        return _call_name(node).rsplit(".", 1)[-1] in _INDEX_ARRAYS
    if isinstance(node, ast.Name):
        values = made.get(node.id, [])
        return bool(values) and all(v is not _UNKNOWN and _copying_index(v, {}) for v in values)
    return False


def _written_into_a_copy(name, function) -> list[Finding]:
    """``M[d][:, d] = v`` (or ``+=``) with ``d`` a list, an array of positions or a mask: ``M[d]`` is a
    new array (NumPy copies for such an index), the write goes into it and is lost; ``M`` is unchanged."""
    made = _assigned_names(function)
    for node in _nodes(function):
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AugAssign) \
            else []
        for target in targets:
            if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Subscript) \
                    and isinstance(target.value.value, ast.Name) and _copying_index(target.value.slice, made):
                inner = ast.unparse(target.value)
                return [Finding(name, _line(node), "a write into a copy made by an index",
                                f"{name} (line {_line(node)}) writes into `{ast.unparse(target)}`, but `{inner}` "
                                f"indexes `{target.value.value.id}` with a list, an array of positions or a mask, which "
                                f"makes a new array: the values go into that copy and `{target.value.value.id}` "
                                f"is left unchanged; index once (`{target.value.value.id}[np.ix_(rows, columns)] = "
                                f"...`, or a slice) so the write lands in the array itself", certain=True)]
    return []


# ------------------------------------------------------------------ a decomposition's candidates never chosen
def _pose_never_chosen(name, function) -> list[Finding]:
    """``R, _, t = cv2.decomposeEssentialMat(E)`` (or ``[0]`` of it) in a function without
    ``cv2.recoverPose``: one of the two rotations never read, so the four candidate poses (either
    rotation, t or -t) are never tested for the one with the points in front of both cameras."""
    calls = [node for node in _nodes(function) if isinstance(node, ast.Call)]
    if any(_call_name(node) == "recoverPose" for node in calls):
        return []
    read = {node.id for node in _nodes(function) if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)}
    for node in _nodes(function):
        value = node.value if isinstance(node, (ast.Assign, ast.Subscript)) else None
        if not (isinstance(value, ast.Call) and _call_name(value) == "decomposeEssentialMat"):
            continue
        if isinstance(node, ast.Subscript):
            one_rotation = True
        else:
            target = node.targets[0] if len(node.targets) == 1 else None
            rotations = target.elts[:2] if isinstance(target, (ast.Tuple, ast.List)) and len(target.elts) == 3 else []
            one_rotation = any(isinstance(r, ast.Name) and (r.id == "_" or r.id not in read) for r in rotations)
        if one_rotation:
            line = _line(node)
            return [Finding(name, line, "a pose taken from cv2.decomposeEssentialMat without the test of its candidates",
                            f"{name} (line {line}) keeps one rotation of cv2.decomposeEssentialMat and never reads the "
                            "other, but E gives four poses (either rotation, with t or -t) and only one puts the "
                            "points in front of both cameras; test the four by triangulating (cv2.recoverPose does it)")]
    return []


# ------------------------------------------------------------------ a lens model evaluated in pixels
def _squared_names(node) -> tuple | None:
    """(a, b) of `a * a + b * b` or `a ** 2 + b ** 2` (names only); None otherwise."""
    if not (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add)):
        return None
    names = []
    for side in (node.left, node.right):
        if isinstance(side, ast.BinOp) and isinstance(side.op, ast.Mult) and isinstance(side.left, ast.Name) \
                and isinstance(side.right, ast.Name) and side.left.id == side.right.id:
            names.append(side.left.id)
        elif isinstance(side, ast.BinOp) and isinstance(side.op, ast.Pow) and isinstance(side.left, ast.Name) \
                and isinstance(side.right, ast.Constant) and side.right.value == 2:
            names.append(side.left.id)
        else:
            return None
    return tuple(names)


_MIDDLES = {"mean", "median", "average", "nanmean"}   # a value of the data's own middle


def _is_a_mean(node) -> bool:
    """`pts.mean(axis=0)`, `np.mean(x)`, `np.median(...)`: a value of the data's own middle."""
    return isinstance(node, ast.Call) and _attribute_path(node.func).rsplit(".", 1)[-1] in _MIDDLES or (
        isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in _MIDDLES)


def _centroid_names(function) -> set[str]:
    """The names bound to a mean, whole or unpacked (`cx, cy = pts.mean(axis=0)`), or to an item of one."""
    names = set()
    for node in _nodes(function):
        if isinstance(node, ast.Assign):
            value = node.value.value if isinstance(node.value, ast.Subscript) else node.value
            if _is_a_mean(value):
                for target in node.targets:
                    names |= {n.id for n in walk(target) if isinstance(n, ast.Name)}
    return names


def _distortion_in_pixels(name, function) -> list[Finding]:
    """A lens model (a `k1` read) whose radius is taken of pixel offsets: `r2 = x * x + y * y` with
    `x = u - cx` and nothing divided by a focal length -- the coefficients are of normalised coordinates."""
    read = {n.id for n in _nodes(function) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    if "k1" not in read:
        return []
    made = _assigned_names(function)
    offsets: dict = {}   # name -> whether it is only ever a difference with no division in it (read once)

    def pixel_offset(part: str) -> bool:
        if part not in offsets:
            values = made.get(part, [])
            offsets[part] = bool(values) and all(
                isinstance(v, ast.BinOp) and isinstance(v.op, ast.Sub)
                and not any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.Div) for n in walk(v)) for v in values)
        return offsets[part]
    centroids = _centroid_names(function)

    def about_a_centroid(part: str) -> bool:
        """A difference from the points' own mean (`x = pts[:, 0] - cx`, `cx, cy = pts.mean(axis=0)`)."""
        return any(isinstance(v, ast.BinOp) and isinstance(v.op, ast.Sub) and (
            (isinstance(v.right, ast.Name) and v.right.id in centroids) or _is_a_mean(v.right))
            for v in made.get(part, []))
    for node in _nodes(function):
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)):
            continue
        pair = _squared_names(node.value)
        if pair is None:
            continue
        line = _line(node)
        shown = ", ".join(f"`{part} = {ast.unparse(made[part][0])}`" for part in pair if made.get(part))
        if all(about_a_centroid(part) for part in pair):
            return [Finding(name, line, "the lens model centred on the points' centroid",
                            f"{name} (line {line}) takes the radius of {shown}, offsets from the points' own mean: "
                            "the lens model's centre is fixed (the principal point, (0, 0) in normalised coordinates), "
                            "not the centroid of the points given, which moves with them")]
        if all(pixel_offset(part) for part in pair):
            return [Finding(name, line, "the lens model evaluated on pixel offsets, not normalised coordinates",
                            f"{name} (line {line}) takes the radius of {shown}, offsets in pixels, but the "
                            "distortion coefficients are of normalised coordinates ((u - cx) / fx, (v - cy) / fy): "
                            "divide by the focal lengths before the polynomial and multiply back after")]
    return []


# ------------------------------------------------------------------ a loop variable named as a value read after it
def _value_of_an_earlier_loop(name, function) -> list[Finding]:
    """Two loops of one block, the first computing a value per turn from its own variable and keeping each
    (``f = f0 * d / z0; focal_lengths.append(f)``), the second reading that value without computing it
    (``perspective_project(moved, f)`` in ``for d in distances:``): every turn of the second reads the first
    loop's last value. (Each block is read once, its loops' bodies walked once each.)"""
    for block in (getattr(node, field) for node in _nodes(function) for field in ("body", "orelse")
                  if isinstance(getattr(node, field, None), list)):
        kept: dict[str, ast.For] = {}   # name -> the earlier loop whose per-turn value it holds after it
        for statement in block:
            if not isinstance(statement, ast.For):
                for bound in (n.id for n in walk(statement) if isinstance(n, ast.Name)
                              and isinstance(n.ctx, ast.Store)):
                    kept.pop(bound, None)
                continue
            stored = {n.id for part in statement.body for n in walk(part)
                      if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)} \
                | {n.id for n in walk(statement.target) if isinstance(n, ast.Name)}
            for value, earlier in kept.items():
                if value in stored:
                    continue
                read = next((n for part in statement.body for n in walk(part)
                             if isinstance(n, ast.Name) and n.id == value and isinstance(n.ctx, ast.Load)), None)
                if read is not None:
                    return [Finding(name, _line(read), "a loop reads the value an earlier loop left",
                                    f"{name} (line {_line(read)}) reads `{value}` in the loop of line "
                                    f"{_line(statement)}, which never computes it: every turn there gets the value "
                                    f"the loop of line {_line(earlier)} left, its last turn's (that loop kept each "
                                    f"turn's `{value}`)", certain=True)]
            for bound in stored:
                kept.pop(bound, None)
            for value in _kept_per_turn(statement):
                kept[value] = statement
    return []


def _running_halves(name, function) -> list[Finding]:
    """``z = (z + depth) / 2`` at every turn of a loop over the values (straight in its body, not under a
    test: a bisection halves its bracket under one): a running average of pairs, where the last value
    weighs 1/2 and the first 1/2^(n-1) -- not the mean."""
    for loop in (n for n in _nodes(function) if isinstance(n, ast.For)):
        variables = {n.id for n in walk(loop.target) if isinstance(n, ast.Name)}
        for statement in loop.body:
            if not (isinstance(statement, ast.Assign) and len(statement.targets) == 1
                    and isinstance(statement.targets[0], ast.Name)):
                continue
            total, target = _halved_sum(statement.value), statement.targets[0].id
            if total is None:
                continue
            operands = [ast.unparse(side) for side in (total.left, total.right)]
            other = total.right if operands[0] == target else total.left if operands[1] == target else None
            if other is not None and variables & {n.id for n in walk(other) if isinstance(n, ast.Name)}:
                return [Finding(name, _line(statement), "a running average of pairs where the mean belongs",
                                f"{name} (line {_line(statement)}) sets `{ast.unparse(statement)}` at every turn of "
                                f"the loop of line {_line(loop)}: each turn halves the weight of every earlier value "
                                "(the last weighs 1/2, the first 1/2^(n-1)), which is not their mean (the sum "
                                "divided by the count, np.mean)", certain=True)]
    return []


def _norm_of_every_pair_at_once(name, function) -> list[Finding]:
    """``errors = np.linalg.norm(H_src - dst)`` (no axis) then ``errors < threshold``: the norm of the whole
    difference is one number, so the comparison is one True or False, where one per pair was meant."""
    norms = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and isinstance(node.value, ast.Call) and _call_name(node.value) == "norm" \
                and _attribute_path(node.value.func).startswith(("np.linalg", "numpy.linalg")) \
                and len(node.value.args) == 1 and not node.value.keywords \
                and isinstance(node.value.args[0], ast.BinOp) and isinstance(node.value.args[0].op, ast.Sub):
            norms[node.targets[0].id] = node
    if not norms:
        return []
    # (a comparison used as a mask of the pairs: returned, or kept and then counted or used as an index --
    # `np.linalg.norm(c1 - c2) < tol` of two single points tests one thing rightly)
    masks = {t.id: n.value for n in _nodes(function) if isinstance(n, ast.Assign) and isinstance(n.value, ast.Compare)
             for t in n.targets if isinstance(t, ast.Name)}
    used = {n.slice.id for n in _nodes(function) if isinstance(n, ast.Subscript) and isinstance(n.slice, ast.Name)} \
        | {a.id for n in _nodes(function) if isinstance(n, ast.Call)
           and _call_name(n) in ("sum", "count_nonzero", "flatnonzero", "where", "nonzero", "mean")
           for a in [*n.args, *([n.func.value] if isinstance(n.func, ast.Attribute) else [])] if isinstance(a, ast.Name)}
    returned = {id(n.value) for n in _nodes(function) if isinstance(n, ast.Return) and n.value is not None}
    as_masks = {id(value) for name_, value in masks.items() if name_ in used} | returned
    for node in _nodes(function):
        if isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], (ast.Lt, ast.LtE)) \
                and isinstance(node.left, ast.Name) and node.left.id in norms and id(node) in as_masks:
            made = norms[node.left.id]
            return [Finding(name, _line(made), "a norm of every pair at once, where one per pair belongs",
                            f"{name} (line {_line(made)}) computes `{ast.unparse(made)}` without an axis: the norm "
                            f"of the whole difference, one number, so `{ast.unparse(node)}` (line {_line(node)}) is "
                            "one True or False for all the pairs; axis=1 gives each row's distance",
                            certain=True)]
    return []


_STACKS = frozenset({"hstack", "column_stack", "concatenate", "c_"})


def _ones_piece(node, ones: set) -> bool:
    """Whether ``node`` is a column of ones (`np.ones((n, 1))`, `np.ones(n)`, `np.ones_like(...)`, a name of one)."""
    if isinstance(node, ast.Name):
        return node.id in ones
    return isinstance(node, ast.Call) and _call_name(node) in ("ones", "ones_like")


def _in_matrices(function) -> set[str]:
    """The names written into a matrix (a list literal of rows, `np.diag(...)`): the transform that undoes a
    normalisation -- only a factor found there makes a 1 scaled with the coordinates disagree with it."""
    names: set[str] = set()
    for node in _nodes(function):
        if isinstance(node, (ast.List, ast.Tuple)) and any(isinstance(e, (ast.List, ast.Tuple)) for e in node.elts) \
                or isinstance(node, ast.Call) and _call_name(node) == "diag":
            names |= _names_in(node)
    return names


def _homogeneous_one_scaled(name, function) -> list[Finding]:
    """``np.hstack([pts - c, ones]) * s``: points made homogeneous, then the whole row scaled -- the appended 1
    becomes s, so the normalised point is (s (x - c), s (y - c), s), the merely centred point up to scale; the
    scale belongs to the coordinates before the 1 is appended."""
    ones = {n.targets[0].id for n in _nodes(function) if isinstance(n, ast.Assign) and len(n.targets) == 1
            and isinstance(n.targets[0], ast.Name) and _ones_piece(n.value, set())}
    in_matrices = _in_matrices(function)
    for node in _nodes(function):
        if not (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult)):
            continue
        for stacked, factor in ((node.left, node.right), (node.right, node.left)):
            if isinstance(stacked, ast.Call) and _call_name(stacked) in _STACKS and stacked.args \
                    and isinstance(stacked.args[0], (ast.List, ast.Tuple)) and len(stacked.args[0].elts) >= 2 \
                    and _ones_piece(stacked.args[0].elts[-1], ones) and isinstance(factor, ast.Name) \
                    and factor.id in in_matrices:
                first = ast.unparse(stacked.args[0].elts[0])
                return [Finding(name, _line(node), "the homogeneous 1 is scaled with the coordinates",
                                f"{name} (line {_line(node)}) computes `{ast.unparse(node)}`: the column of ones is "
                                f"multiplied by `{ast.unparse(factor)}` too, so each point's last coordinate is "
                                f"`{ast.unparse(factor)}`, not 1 -- up to scale that is the point before the scaling; "
                                f"scale the coordinates before appending the 1 (`({first}) * {ast.unparse(factor)}`)")]
    return []


def _flags_joined_with_or(name, function) -> list[Finding]:
    """``flags=cv2.INTER_LINEAR or cv2.WARP_INVERSE_MAP``: Python's ``or`` gives its first true operand (or the
    last), not both flags -- OpenCV's flags are bits, joined with ``|``."""
    for node in _nodes(function):
        if isinstance(node, ast.BoolOp) and isinstance(node.op, (ast.Or, ast.And)) \
                and sum(_attribute_path(v).startswith(("cv2.", "cv.")) for v in node.values) >= 2:
            joined = " | ".join(ast.unparse(v) for v in node.values)
            word = "or" if isinstance(node.op, ast.Or) else "and"
            return [Finding(name, _line(node), "OpenCV flags joined with `or` or `and`",
                            f"{name} (line {_line(node)}) computes `{ast.unparse(node)}`: Python's `{word}` gives one "
                            f"of its operands, not the flags together, so all but one are lost; OpenCV's flags are "
                            f"bits, combined with `|` (`{joined}`)", certain=True)]
    return []


def _determinant_compared_exactly(name, function) -> list[Finding]:
    """``if np.linalg.det(R) == -1:`` (or ``!= 1``): a determinant computed in floating point is -1 only to
    rounding (-0.9999999999999998), so the test is almost never true; its sign is what tells a reflection."""
    for node in _nodes(function):
        if isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], (ast.Eq, ast.NotEq)):
            sides = [node.left, node.comparators[0]]
            det = next((side for side in sides if isinstance(side, ast.Call) and _call_name(side) == "det"), None)
            value = next((side for side in sides if side is not det), None)
            number = value.value if isinstance(value, ast.Constant) else \
                -value.operand.value if isinstance(value, ast.UnaryOp) and isinstance(value.op, ast.USub) \
                and isinstance(value.operand, ast.Constant) else None
            if det is not None and isinstance(number, (int, float)) and number in (1, -1):
                sign = "< 0" if (number == -1) == isinstance(node.ops[0], ast.Eq) else "> 0"
                return [Finding(name, _line(node), "a determinant compared with an exact value",
                                f"{name} (line {_line(node)}) tests `{ast.unparse(node)}`: a determinant computed in "
                                f"floating point is {number} only to rounding ({number * 0.9999999999999998!r}, say), so "
                                f"the test is almost never what it means; test its sign (`{ast.unparse(det)} {sign}`)",
                                certain=True)]
    return []


_DRAWN_WITH_A_SHAPE = frozenset({"standard_normal", "normal", "randn", "rand", "random", "uniform", "empty", "zeros",
                                 "ones", "full"})


def _shape_of_two_or_more(call: ast.Call) -> bool:
    """Whether a NumPy maker or random draw is given a shape of two axes or more (`rng.standard_normal((n, k, 2))`,
    `np.random.randn(n, 2)`, `rng.uniform(-1, 1, size=(n, 2))`)."""
    shapes = [k.value for k in call.keywords if k.arg in ("size", "shape")]
    if _call_name(call) in ("standard_normal", "random", "empty", "zeros", "ones", "full", "rand") and call.args:
        shapes.append(call.args[0])
    if _call_name(call) in ("randn", "rand") and len(call.args) >= 2:
        return True
    return any(isinstance(shape, (ast.Tuple, ast.List)) and len(shape.elts) >= 2 for shape in shapes)


def _whole_norm_divides_vectors(name, function) -> list[Finding]:
    """``d = rng.standard_normal((n, k, 2))`` then ``d / np.linalg.norm(d)`` (or ``d /= ...``), no axis: the
    norm of the whole array, one number, where each vector's own belongs -- no vector comes out of unit length."""
    made = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and isinstance(node.value, ast.Call) and _call_name(node.value) in _DRAWN_WITH_A_SHAPE \
                and _shape_of_two_or_more(node.value):
            made[node.targets[0].id] = node
    for node in _nodes(function):
        divided, norm = None, None
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div):
            divided, norm = node.left, node.right
        elif isinstance(node, ast.AugAssign) and isinstance(node.op, ast.Div):
            divided, norm = node.target, node.value
        if isinstance(divided, ast.Name) and divided.id in made and isinstance(norm, ast.Call) \
                and _call_name(norm) == "norm" and _attribute_path(norm.func).startswith(("np.linalg", "numpy.linalg")) \
                and len(norm.args) == 1 and not norm.keywords and isinstance(norm.args[0], ast.Name) \
                and norm.args[0].id == divided.id:
            return [Finding(name, _line(node), "every vector divided by the norm of the whole array",
                            f"{name} (line {_line(node)}) divides `{divided.id}` (made with a shape of several axes on "
                            f"line {_line(made[divided.id])}) by `{ast.unparse(norm)}`: without an axis that is the "
                            "norm of the whole array, one number, so no vector comes out of unit length; give each "
                            f"its own, `np.linalg.norm({divided.id}, axis=-1, keepdims=True)`", certain=True)]
    return []


def _singular_vectors_unused(name, function) -> list[Finding]:
    """``U, S, Vt = np.linalg.svd(M)`` where ``U`` (or ``Vt``) is never read while the other is: a matrix
    rebuilt from its SVD without one of its factors (``np.diag([1, 1, 0]) @ Vt``)."""
    reads = {n.id for n in _nodes(function) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
    # (the names a product with a diagonal rebuilds a matrix from -- `np.diag([1, 1, 0]) @ Vt` -- gathered once,
    # from the outermost such products: a null vector read from Vt alone, `Vt[-1]`, needs no U)
    rebuilt, inside = set(), set()
    for n in _nodes(function):
        if id(n) in inside or not (isinstance(n, ast.BinOp) and isinstance(n.op, ast.MatMult)):
            continue
        below = list(walk(n))
        inside.update(id(m) for m in below)
        if any(isinstance(m, ast.Call) and _call_name(m) == "diag" for m in below):
            rebuilt.update(m.id for m in below if isinstance(m, ast.Name))
    for node in _nodes(function):
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple)
                and len(node.targets[0].elts) == 3 and isinstance(node.value, ast.Call)
                and _call_name(node.value) == "svd"):
            continue
        left, _, right = (e.id if isinstance(e, ast.Name) else "_" for e in node.targets[0].elts)
        for unused, used in ((left, right), (right, left)):
            if used in rebuilt and unused != "_" and not unused.startswith("_") and unused not in reads \
                    and used in reads:
                return [Finding(name, _line(node), "a factor of an SVD left out of the rebuild",
                                f"{name} (line {_line(node)}) unpacks `{unused}` from `{ast.unparse(node.value)}` and "
                                f"never uses it: a matrix rebuilt from its SVD needs both factors, "
                                f"`{left} @ np.diag(...) @ {right}`")]
    return []


def _halved_sum(node):
    """The sum ``a + b`` of ``(a + b) / 2``, ``0.5 * (a + b)`` or ``(a + b) * 0.5``; None otherwise."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) and isinstance(node.right, ast.Constant) \
            and node.right.value == 2:
        inner = node.left
    elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult):
        half = [side for side in (node.left, node.right) if isinstance(side, ast.Constant) and side.value == 0.5]
        inner = (node.right if half[0] is node.left else node.left) if half else None
    else:
        inner = None
    return inner if isinstance(inner, ast.BinOp) and isinstance(inner.op, ast.Add) else None


def _kept_per_turn(loop: ast.For) -> set:
    """The names ``loop``'s body computes from its own variable and appends to a list (``f = f0 * d / z0`` then
    ``focal_lengths.append(f)``)."""
    variables = {n.id for n in walk(loop.target) if isinstance(n, ast.Name)}
    computed = {target.id for statement in loop.body if isinstance(statement, ast.Assign)
                for target in statement.targets if isinstance(target, ast.Name)
                and variables & {n.id for n in walk(statement.value) if isinstance(n, ast.Name)}}
    appended = {a.id for n in walk(loop) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
                and n.func.attr == "append" for a in n.args if isinstance(a, ast.Name)}
    return computed & appended


def _fisheye_model(name, function) -> list[Finding]:
    """A call of ``cv2.fisheye.*``: OpenCV's fisheye model bends rays by their angle (theta_d = theta (1 + k1 theta^2
    + ...), four coefficients), another lens than the one a calibration's (k1, k2, p1, p2, k3) describe --
    the model of the course's cv2.calibrateCamera, cv2.undistort and cv2.projectPoints."""
    for node in _nodes(function):
        if isinstance(node, ast.Call) and _attribute_path(node.func).startswith(("cv2.fisheye.", "cv.fisheye.")):
            line = _line(node)
            return [Finding(name, line, "the fisheye lens model used for the calibration's distortion",
                            f"{name} (line {line}) calls `{_attribute_path(node.func)}`: the fisheye model bends each ray "
                            "by its angle from the axis, with four coefficients of its own, where the distortion "
                            "(k1, k2, p1, p2, k3) is that of cv2.calibrateCamera's lens model; use the functions of "
                            "that model (cv2.undistort, cv2.projectPoints, cv2.undistortPoints)")]
    return []


_ROTATION_MATRICES = {"R", "R1", "R2", "rotation", "R_rect"}   # the API's 3x3 rotation matrices, by name


def _rotation_matrix_made_a_vector(name, function) -> list[Finding]:
    """`R, _ = cv2.Rodrigues(R)` on a parameter the API gives as a 3x3 rotation matrix, with no test of its
    shape before: cv2.Rodrigues converts both ways, so a 3x3 matrix comes back as its (3, 1) rotation
    vector (a "rotation vector accepted too" that turns every matrix given into a vector)."""
    parameters = {a.arg for a in function.args.args + function.args.posonlyargs + function.args.kwonlyargs}
    rotations = parameters & _ROTATION_MATRICES
    if not rotations:
        return []
    guarded = any(isinstance(node, (ast.If, ast.IfExp)) and any(
        isinstance(n, ast.Name) and n.id in rotations for n in walk(node.test)) for node in _nodes(function))
    if guarded:
        return []
    for assign in _nodes(function):
        # (assigned back to the same name -- `R, _ = cv2.Rodrigues(R)`, `R = cv2.Rodrigues(R)[0]`: the matrix replaced;
        # a rotation vector made from R under another name, for cv2.projectPoints, is right)
        if not (isinstance(assign, ast.Assign) and len(assign.targets) == 1):
            continue
        target = assign.targets[0]
        first = target.elts[0] if isinstance(target, (ast.Tuple, ast.List)) and target.elts else target
        node = assign.value.value if isinstance(assign.value, ast.Subscript) else assign.value
        if isinstance(first, ast.Name) and isinstance(node, ast.Call) \
                and _attribute_path(node.func) in ("cv2.Rodrigues", "cv.Rodrigues") \
                and node.args and first.id in rotations \
                and first.id in {n.id for n in walk(node.args[0]) if isinstance(n, ast.Name)}:
            line = _line(node)
            return [Finding(name, line, "a rotation matrix turned into a rotation vector by cv2.Rodrigues",
                            f"{name} (line {line}) calls `{ast.unparse(node)}` on every {first.id}: cv2.Rodrigues "
                            f"converts both ways, so the 3x3 rotation matrix {first.id} comes back as its (3, 1) "
                            "rotation vector; convert only what is a vector (size 3), or not at all where the matrix "
                            "is given")]
    return []


def _identity_with_a_literal(name, function) -> list[Finding]:
    """`method is "orb"` (or `is not`, a number or a string on either side): `is` asks whether two names hold one
    object, not equal values. A literal and an equal value made at run time -- the caller's argument, a string
    joined or read from a file -- are two objects, so the test fails where `==` holds (Python warns: "is" with
    a literal). None, True, False and the Ellipsis are single objects: `is` is right for them."""
    for node in _nodes(function):
        if not isinstance(node, ast.Compare) or not any(isinstance(op, (ast.Is, ast.IsNot)) for op in node.ops):
            continue
        sides = [node.left, *node.comparators]
        literal = next((side for side in sides if isinstance(side, ast.Constant)
                        and isinstance(side.value, (str, bytes, int, float, complex))
                        and not isinstance(side.value, bool)), None)
        if literal is None:
            continue
        line = _line(node)
        text = ast.unparse(node)
        equal = text.replace(" is not ", " != ").replace(" is ", " == ")
        return [Finding(name, line, "a value compared with a literal by identity (is)",
                        f"{name} (line {line}) tests `{text}`: `is` asks whether both are one object, not whether "
                        f"they are equal, and {ast.unparse(literal)} made at run time (the caller's argument) is another "
                        f"object of the same value, so the test fails; compare values: `{equal}`")]
    return []


def _loop_variable_assigned_in_vain(name, function) -> list[Finding]:
    """``for x, K in ((x1, K1), (x2, K2)): x = x @ inv(K).T`` and nothing reads ``x`` after it, in the turn or after
    the loop: the value assigned to the loop variable is dropped when the next turn binds it again, so the items
    looped over (x1, x2) are not changed (a list, or names assigned one by one, keep them). (Each name's last
    reading is found once: linear in the function's size.)"""
    last_read: dict[str, tuple] = {}
    for node in _nodes(function):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
            last_read[node.id] = max(last_read.get(node.id, (0, 0)), (node.lineno, node.col_offset))
    for loop in _nodes(function):
        if not isinstance(loop, ast.For) or loop.orelse:
            continue
        elements = loop.target.elts if isinstance(loop.target, ast.Tuple) else [loop.target]
        targets = [t.id if isinstance(t, ast.Name) else None for t in elements]
        for assign in (node for statement in loop.body for node in walk(statement)):
            if isinstance(assign, (ast.Yield, ast.YieldFrom, ast.Return, ast.Nonlocal, ast.Global)):
                break   # (a value handed out or kept beyond the turn)
            if not (isinstance(assign, ast.Assign) and len(assign.targets) == 1
                    and isinstance(assign.targets[0], ast.Name) and assign.targets[0].id in targets):
                continue
            variable = assign.targets[0].id
            if last_read.get(variable, (0, 0)) > (assign.end_lineno, assign.end_col_offset):
                continue   # (read after it: later in the turn, or after the loop)
            # (what the loop went over, where it is a literal: the items that stay unchanged)
            position = targets.index(variable)
            items = loop.iter.elts if isinstance(loop.iter, (ast.Tuple, ast.List)) else []
            names = [ast.unparse(item.elts[position] if isinstance(item, ast.Tuple) and position < len(item.elts)
                                 else item) for item in items if isinstance(item, ast.Tuple) or len(targets) == 1]
            unchanged = f"{', '.join(f'`{n}`' for n in names)} stay as they were" if names else \
                "the items looped over stay as they were"
            line = _line(assign)
            sources = _looped_sources(loop.iter, position, len(targets))
            if sources and all(last_read.get(source, (0, 0)) <= (loop.end_lineno, loop.end_col_offset)
                               for source in sources):
                # (what was looped over is not read after the loop: no change of it was awaited -- the value
                # itself, made each turn, is what nothing uses)
                return [Finding(name, line, "a value made in a loop and never used",
                                f"{name} (line {line}) gives `{variable}` a new value (`{ast.unparse(assign)[:80]}`), "
                                f"and nothing reads `{variable}` after it, in the loop of line {_line(loop)} or "
                                f"below: what the loop gives `{variable}` each turn is never used")]
            return [Finding(name, line, "a value assigned to the loop variable and dropped",
                            f"{name} (line {line}) assigns `{ast.unparse(assign)[:80]}` to `{variable}`, the variable of "
                            f"the loop at line {_line(loop)}, and nothing reads it after: the next turn binds "
                            f"`{variable}` again, so the value is dropped and {unchanged}. Keep the results (append them "
                            "to a list, or assign each name on its own line)")]
    return []


def _looped_sources(iterated, position: int, count: int) -> list[str]:
    """The names whose items a loop variable (the ``position``-th of ``count``) takes: `xs` of `for x in xs`, the
    `position`-th argument of `zip(...)`, the items of `enumerate(xs)`; [] where they are not names."""
    if isinstance(iterated, ast.Name) and count == 1:
        return [iterated.id]
    if isinstance(iterated, ast.Call) and isinstance(iterated.func, ast.Name) and not iterated.keywords:
        if iterated.func.id == "zip" and len(iterated.args) == count and isinstance(iterated.args[position], ast.Name):
            return [iterated.args[position].id]
        if iterated.func.id == "enumerate" and count == 2 and position == 1 and iterated.args \
                and isinstance(iterated.args[0], ast.Name):
            return [iterated.args[0].id]
    return []


def _name_places(function) -> dict[str, list]:
    """Each name of the def -> its places, sorted: ``[(line, column, read)]`` (gathered once, searched by bisection)."""
    places: dict[str, list] = {}
    for node in _nodes(function):
        if isinstance(node, ast.Name):
            places.setdefault(node.id, []).append((node.lineno, node.col_offset, isinstance(node.ctx, ast.Load)))
    for found in places.values():
        found.sort()
    return places


def _loop_variable_rebinds(name, function) -> list[Finding]:
    """``for world in np.atleast_2d(world):`` then ``world.ndim`` after the loop: the loop rebinds a
    name already bound (a parameter, or assigned above the loop), and a line after the loop reads it
    before binding it again -- it reads the loop's last item, not what the name held before. (Each
    name's places are gathered once and searched by bisection: linear in the function's size.)"""
    places = _name_places(function)
    parameters = {a.arg for a in function.args.args + function.args.kwonlyargs}
    for loop in _nodes(function):
        if not isinstance(loop, ast.For):
            continue
        for target in (t for t in walk(loop.target) if isinstance(t, ast.Name)):
            found = places[target.id]
            first = found[0]
            if target.id not in parameters and not (first[0] < loop.lineno and not first[2]):
                continue   # (bound before the loop: a parameter, or written on an earlier line first)
            after = bisect.bisect_left(found, (loop.end_lineno + 1, -1, False))
            if after < len(found) and found[after][2]:
                line, read = _line(loop), found[after][0]
                return [Finding(name, line, "a loop variable named as a value read after the loop",
                                f"{name} (line {line}) loops with `for {ast.unparse(loop.target)} in ...`, which rebinds "
                                f"`{target.id}`, bound before the loop; line {read} reads `{target.id}` after the "
                                f"loop, where it holds the loop's last item, not what it held before: give the loop "
                                f"variable a name of its own")]
    return []


def _loop_variable_hides_a_value(name, function) -> list[Finding]:
    """``r, c = out.shape[:2]`` then ``for a, b, c in lines:`` reading ``c`` in the loop as the width: the loop
    takes as its variable a name assigned above it whose value nothing read yet, so every read of it in the
    loop gets the loop's items and the value assigned is never read (one name for two values). A constant
    assigned first (``i = 0``) is an initialisation, not a value meant. (Each name's places are gathered once and
    searched by bisection: linear in the function's size.)"""
    places = _name_places(function)
    assigned = {(target.id, statement.lineno): statement for statement in _nodes(function)
                if isinstance(statement, ast.Assign)
                for target in walk(ast.Tuple(elts=statement.targets)) if isinstance(target, ast.Name)}
    for loop in _nodes(function):
        if not isinstance(loop, ast.For):
            continue
        iterated = {n.id for n in walk(loop.iter) if isinstance(n, ast.Name)}
        for target in (t for t in walk(loop.target) if isinstance(t, ast.Name) and t.id not in iterated):
            found = places[target.id]
            at = bisect.bisect_left(found, (loop.lineno, -1, False))
            if at == 0 or found[at - 1][2]:
                continue   # (not assigned above the loop, or read since)
            statement = assigned.get((target.id, found[at - 1][0]))
            if statement is None or isinstance(statement.value, ast.Constant):
                continue
            end = bisect.bisect_left(found, (loop.end_lineno + 1, -1, False))
            inside = [place for place in found[at:end] if place[2] and place[0] > loop.target.end_lineno]
            if not inside or (end < len(found) and found[end][2]):
                continue   # (not read in the loop; or read after it: _loop_variable_rebinds tells that)
            line, read = _line(statement), inside[0][0]
            return [Finding(name, line, "a value assigned above a loop whose variable takes its name",
                            f"{name} (line {line}) assigns `{target.id}` (`{_shortened(statement)}`) and, before "
                            f"anything reads it, the loop of line {_line(loop)} (`for {_target_text(loop.target)} in "
                            f"...`) takes `{target.id}` as its own variable: the reads of `{target.id}` in the loop "
                            f"(line {read}) get the loop's items, and line {line}'s value is never read -- one name "
                            f"for two values: give one of them another name", certain=True)]
    return []


def _target_text(target) -> str:
    """A loop's target as written (`i, (a, b, c)`, without the brackets ast.unparse puts around a tuple)."""
    return ", ".join(ast.unparse(e) for e in target.elts) if isinstance(target, ast.Tuple) else ast.unparse(target)


def _shortened(node, limit: int = 60) -> str:
    text = " ".join(ast.unparse(node).split())
    return text if len(text) <= limit else text[:limit - 3] + "..."


# ------------------------------------------------------------------ a homogeneous system solved by least squares
_ZEROS = frozenset({"zeros", "zeros_like"})


def _zeros_solved_for(name, function) -> list[Finding]:
    """``np.linalg.lstsq(A, np.zeros(n))`` (or ``solve``): the least-squares answer of ``A x = 0`` is
    ``x = 0``, never the non-zero solution a homogeneous system is solved for."""
    for node in _nodes(function):
        if isinstance(node, ast.Call) and _call_name(node) in ("lstsq", "solve") and len(node.args) >= 2 \
                and isinstance(node.args[1], ast.Call) and _call_name(node.args[1]) in _ZEROS:
            line = _line(node)
            return [Finding(name, line, "a homogeneous system solved by least squares",
                            f"{name} (line {line}) solves `{ast.unparse(node.args[0])} x = 0` with "
                            f"np.linalg.{_call_name(node)}, whose answer with a zero right-hand side is x = 0; the "
                            "non-zero solution of a homogeneous system is the right singular vector of the smallest "
                            "singular value (the last row of Vt from np.linalg.svd)", certain=True)]
    return []


# ------------------------------------------------------------------ a fundamental matrix where an essential one belongs
_FUNDAMENTAL_MAKERS = frozenset({"fundamental_8point", "findFundamentalMat"})
_ESSENTIAL_TAKERS = frozenset({"recoverPose", "decomposeEssentialMat"})


def _bindings(function) -> dict[str, list]:
    """name -> its bindings in line order, each ``(line, value, position)``: the value assigned and which of
    its results the name gets -- ``position`` is the name's place in a tuple target (``F, mask = f(x)``) or
    the constant index taken at once (``v = f(x)[1]``), None for the value itself. Any other subscript, an
    augmented or an annotated assignment binds an unknown value."""
    bindings: dict[str, list] = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign):
            targets, value = node.targets, node.value
        elif isinstance(node, (ast.AugAssign, ast.AnnAssign)):
            targets, value = [node.target], _UNKNOWN
        else:
            continue
        taken = None
        if isinstance(value, ast.Subscript):
            index = value.slice
            taken = index.value if isinstance(index, ast.Constant) and type(index.value) is int else None
            value = value.value if taken is not None else _UNKNOWN
        for target in targets:
            places = list(enumerate(target.elts)) if isinstance(target, (ast.Tuple, ast.List)) else [(taken, target)]
            for position, place in places:
                for bound in walk(place):
                    if isinstance(bound, ast.Name):
                        bindings.setdefault(bound.id, []).append(
                            (_line(node), value if bound is place and (taken is None or place is target) else _UNKNOWN,
                             position))
    for found in bindings.values():
        found.sort(key=lambda binding: binding[0])
    return bindings


def _binding_above(bindings: dict, name: str, line: int):
    """The last binding of ``name`` on a line above ``line`` (None when there is none); by bisection."""
    found = bindings.get(name, [])
    last = bisect.bisect_left(found, line, key=lambda binding: binding[0]) - 1
    return found[last] if last >= 0 else None


def _fundamental_as_essential(name, function) -> list[Finding]:
    """``F = fundamental_8point(pts1, pts2)`` (or ``cv2.findFundamentalMat``'s first result) given to
    ``cv2.recoverPose(F, ...)`` or ``cv2.decomposeEssentialMat(F)``, which take the essential matrix:
    F acts on pixels, E on coordinates normalised by K (E = K2^T F K1). The name's last binding above the
    call decides (`F = K.T @ F @ K` in between makes it E)."""
    bindings = _bindings(function)
    for node in _nodes(function):
        if not (isinstance(node, ast.Call) and _call_name(node) in _ESSENTIAL_TAKERS and node.args
                and isinstance(node.args[0], ast.Name)):
            continue
        given, line = node.args[0].id, _line(node)
        last = _binding_above(bindings, given, line)
        if last is not None and isinstance(last[1], ast.Call) and _call_name(last[1]) in _FUNDAMENTAL_MAKERS \
                and last[2] in (None, 0):
            made = _essential_made_from(bindings, given, last[0], line)
            fix = (f"your code makes the essential matrix `{made[0]}` at line {made[1]}: give cv2.{_call_name(node)} "
                   f"`{made[0]}` instead of `{given}`" if made else
                   "make E = K2^T F K1 first (essential_from_fundamental)")
            return [Finding(name, line, "a fundamental matrix given where the essential matrix belongs",
                            f"{name} (line {line}) gives cv2.{_call_name(node)} `{given}`, the fundamental matrix "
                            f"made at line {last[0]}, where it takes the essential matrix: F acts on pixels, "
                            f"E on coordinates normalised by K; {fix}", certain=True)]
    return []


def _essential_made_from(bindings: dict, fundamental: str, since: int, line: int) -> tuple[str, int] | None:
    """(name, line) of an essential matrix the code makes from ``fundamental`` between lines ``since`` and ``line``:
    `E = essential_from_fundamental(F, K, K)`, or a matrix product reading F (`E = K.T @ F @ K`)."""
    for other, found in bindings.items():
        if other == fundamental:
            continue
        for at, value, _ in found:
            if not since < at < line:
                continue
            reads = {n.id for n in walk(value) if isinstance(n, ast.Name)} if value is not _UNKNOWN else set()
            if fundamental in reads and ((isinstance(value, ast.Call) and "essential" in _call_name(value).lower())
                                         or (isinstance(value, ast.BinOp) and isinstance(value.op, ast.MatMult))):
                return other, at
    return None


# ------------------------------------------------------------------ an eigenvector taken as a row
_EIGEN_SOLVERS = frozenset({"eig", "eigh"})


def _picks_a_row(index) -> bool:
    """``v[i]``, ``v[-1]``, ``v[np.argmin(w)]`` or ``v[i, :]``: one row of a matrix (not a slice of rows)."""
    if isinstance(index, ast.Tuple):
        return len(index.elts) == 2 and _picks_a_row(index.elts[0]) and isinstance(index.elts[1], ast.Slice) \
            and index.elts[1].lower is None and index.elts[1].upper is None and index.elts[1].step is None
    return not isinstance(index, (ast.Slice, ast.Starred, ast.List)) \
        and not (isinstance(index, ast.Constant) and not isinstance(index.value, int))


def _eigenvectors_as_rows(name, function) -> list[Finding]:
    """``w, v = np.linalg.eig(M)`` (or ``eigh``, or ``eig(M)[1]``) then ``v[i]``: NumPy returns the
    eigenvectors as the columns of ``v``; a row of it is no eigenvector. Only a name bound once, to the
    vectors, is followed (``v = v.T`` makes the rows right)."""
    bindings = _bindings(function)
    for node in _nodes(function):
        if not (isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) and isinstance(node.value, ast.Name)
                and _picks_a_row(node.slice)):
            continue
        found = bindings.get(node.value.id, [])
        if len(found) != 1:
            continue
        line, value, position = found[0]
        made_by = _call_name(value) if isinstance(value, ast.Call) else ""
        if made_by in _EIGEN_SOLVERS and position == 1 and _line(node) >= line:   # (the vectors: result 1)
            vectors, taken = node.value.id, ast.unparse(node)
            return [Finding(name, _line(node), "a row of the eigenvector matrix taken as an eigenvector",
                            f"{name} (line {_line(node)}) takes `{taken}`, a row of `{vectors}`, the eigenvectors "
                            f"np.linalg.{made_by} returned at line {line}; they are its columns: "
                            f"`{vectors}[:, i]` is the eigenvector of the i-th eigenvalue", certain=True)]
    return []


# ------------------------------------------------------------------ a sign lost by a square root
def _square_of(node):
    """``c`` for ``c ** 2`` or ``c * c`` (None for anything else)."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and isinstance(node.right, ast.Constant) \
            and node.right.value == 2:
        return node.left
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and ast.dump(node.left) == ast.dump(node.right):
        return node.left
    return None


def _sign_lost_by_a_root(name, function) -> list[Finding]:
    """``np.sqrt(1 - c ** 2)`` (or ``(1 - c * c) ** 0.5``): the sine from the cosine (or the reverse) by
    the identity sin^2 + cos^2 = 1 is never negative -- |sin| -- so its sign is lost wherever it is
    negative (an angle past 180 degrees, a negative one)."""
    for node in _nodes(function):
        if isinstance(node, ast.Call) and _call_name(node) == "sqrt" and len(node.args) == 1:
            root = node.args[0]
        elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and isinstance(node.right, ast.Constant) \
                and node.right.value == 0.5:
            root = node.left
        else:
            continue
        if isinstance(root, ast.BinOp) and isinstance(root.op, ast.Sub) and isinstance(root.left, ast.Constant) \
                and root.left.value == 1 and _square_of(root.right) is not None:
            squared = ast.unparse(_square_of(root.right))
            return [Finding(name, _line(node), "a sine or cosine from the other by a square root: its sign is lost",
                            f"{name} (line {_line(node)}) computes `{ast.unparse(node)}`, which is never negative: "
                            f"it is the size of the sine (or cosine) whose partner is `{squared}`, not its value, "
                            "so where that value is negative (a negative angle, one past 180 degrees) its sign is "
                            "lost; take np.sin / np.cos of the angle itself")]
    return []


# ------------------------------------------------------------------ a dimension tested after reshaping
_MAKE_2D = frozenset({"atleast_2d"})


def _makes_two_dimensional(value) -> bool:
    """``np.atleast_2d(x)``, ``x.reshape(-1, 3)`` / ``reshape((-1, 3))``, ``np.array(x, ndmin=2)``,
    also at the end of a chain (``np.asarray(x, float).reshape(-1, 3)``)."""
    if not isinstance(value, ast.Call):
        return False
    called = _call_name(value)
    if called in _MAKE_2D:
        return True
    if called == "reshape":
        shape = value.args[0] if len(value.args) == 1 else ast.Tuple(elts=list(value.args))
        return isinstance(shape, (ast.Tuple, ast.List)) and len(shape.elts) == 2
    return called in ("array", "asarray") and any(k.arg == "ndmin" and isinstance(k.value, ast.Constant)
                                                  and k.value.value == 2 for k in value.keywords)


def _one_dimensional_test(node):
    """The name tested by ``x.ndim == 1``, ``x.ndim < 2``, ``len(x.shape) == 1`` (None otherwise)."""
    if not (isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.comparators[0], ast.Constant)):
        return None
    left, op, bound = node.left, node.ops[0], node.comparators[0].value
    if not ((isinstance(op, ast.Eq) and bound == 1) or (isinstance(op, ast.Lt) and bound == 2)):
        return None
    if isinstance(left, ast.Attribute) and left.attr == "ndim" and isinstance(left.value, ast.Name):
        return left.value.id
    if isinstance(left, ast.Call) and _call_name(left) == "len" and len(left.args) == 1 \
            and isinstance(left.args[0], ast.Attribute) and left.args[0].attr == "shape" \
            and isinstance(left.args[0].value, ast.Name):
        return left.args[0].value.id
    return None


def _dimension_tested_after_reshaping(name, function) -> list[Finding]:
    """``x = np.atleast_2d(x)`` then ``single = x.ndim == 1``: the test reads the reshaped array, whose
    dimension is 2 whatever was given, so it is never true and a single point is never told apart."""
    bindings = _bindings(function)
    for node in _nodes(function):
        tested = _one_dimensional_test(node)
        last = _binding_above(bindings, tested, _line(node)) if tested else None
        if last is not None and last[2] is None and _makes_two_dimensional(last[1]):
            return [Finding(name, _line(node), "a dimension tested after the array was made two-dimensional",
                            f"{name} (line {_line(node)}) tests `{ast.unparse(node)}` after line {last[0]} made "
                            f"`{tested}` two-dimensional (`{ast.unparse(last[1])}`): the test is never true, so a "
                            "single point is never told apart; test the input as it was given, before reshaping it",
                            certain=True)]
    return []


# ------------------------------------------------------------------ a root written x ** 1/2
def _root_by_a_fraction(name, function) -> list[Finding]:
    """``s ** 1/2`` (or ``** 1/3``): ``**`` binds tighter than ``/``, so it is ``(s ** 1) / 2``, half of ``s``,
    not its square root."""
    for node in _nodes(function):
        power = _rightmost_factor(node.left) if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) \
            and isinstance(node.right, ast.Constant) and node.right.value in (2, 3) else None
        if isinstance(power, ast.BinOp) and isinstance(power.op, ast.Pow) and isinstance(power.right, ast.Constant) \
                and power.right.value == 1:
            line, written = _line(node), ast.unparse(node)
            base, n = ast.unparse(power.left), node.right.value
            return [Finding(name, line, "a root written as a power of 1/n (** binds tighter than /)",
                            f"{name} (line {line}) writes `{written}`: ** binds tighter than /, so it is "
                            f"({base}) ** 1 / {n}, the value divided by {n}, not its root; write "
                            f"({base}) ** (1 / {n})" + (" or np.sqrt(...)" if n == 2 else ""), certain=True)]
    return []


def _rightmost_factor(node):
    """The last factor of a product or quotient chain (``a / b ** 1`` -> ``b ** 1``): what a ``/`` after it
    divides first."""
    while isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Mult, ast.Div)):
        node = node.right
    return node


# ------------------------------------------------------------------ np.mgrid unpacked as (x, y)
_GRIDS = frozenset({"mgrid", "ogrid", "indices"})
_X_NAME = re.compile(r"^(x|xs|xx|x_?grid|gx|cols?|u|us|map_?x|x_?coords?)$", re.I)
_HEIGHT = re.compile(r"(^|[^a-z0-9])(h|height|rows?|n_?rows|hh)($|[^a-z0-9])|shape\[0\]", re.I)


def _grid_unpacked_as_x_y(name, function) -> list[Finding]:
    """``xs, ys = np.mgrid[0:h, 0:w]`` (or ``np.indices((h, w))``): NumPy's grids give the row index (y)
    first, so the name meant for x holds the rows. Only where the first axis runs over the height."""
    for node in _nodes(function):
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple)
                and len(node.targets[0].elts) == 2 and all(isinstance(e, ast.Name) for e in node.targets[0].elts)):
            continue
        value = node.value
        while isinstance(value, ast.Call) and isinstance(value.func, ast.Attribute) \
                and value.func.attr in ("astype", "copy"):
            value = value.func.value   # (np.mgrid[...].astype(float): the grid itself)
        grid = value.value if isinstance(value, ast.Subscript) else value.func if isinstance(value, ast.Call) else None
        called = grid.attr if isinstance(grid, ast.Attribute) else grid.id if isinstance(grid, ast.Name) else ""
        if called not in _GRIDS:
            continue
        first_axis = value.slice.elts[0] if isinstance(value, ast.Subscript) and isinstance(value.slice, ast.Tuple) \
            and value.slice.elts else value.args[0].elts[0] if isinstance(value, ast.Call) and value.args \
            and isinstance(value.args[0], (ast.Tuple, ast.List)) and value.args[0].elts else None
        first, second = (e.id for e in node.targets[0].elts)
        if first_axis is not None and _X_NAME.match(first) and _HEIGHT.search(ast.unparse(first_axis)):
            line = _line(node)
            return [Finding(name, line, "a grid's rows taken for its x",
                            f"{name} (line {line}) unpacks `{first}, {second} = {ast.unparse(value)}`: NumPy's "
                            f"{called} gives the row index (y) first, over the height, then the column index (x), "
                            f"so `{first}` holds rows and `{second}` columns; unpack it as `{second}, {first}`")]
    return []


# ------------------------------------------------------------------ a result rounded to a few decimals
def _result_rounded(name, function) -> list[Finding]:
    """``return np.round(E, 4)`` (or a name so made and returned): a habit of printing a matrix in a report,
    which cuts the result's digits -- to nothing for a matrix given at a small scale."""
    rounded: dict[str, ast.AST] = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and _rounds_to_decimals(node.value):
            rounded[node.targets[0].id] = node.value
    for node in _nodes(function):
        if isinstance(node, ast.Return) and node.value is not None:
            made = node.value if _rounds_to_decimals(node.value) else rounded.get(getattr(node.value, "id", None))
            if made is not None:
                line = _line(node)
                return [Finding(name, line, "the result rounded to a few decimals",
                                f"{name} (line {line}) returns `{ast.unparse(made)}`, its result rounded to a few "
                                "decimals: every digit past them is lost (all of them for a small value); round "
                                "only where a number is printed")]
    return []


# ------------------------------------------------------------------ np.where's tuple counted as indices
_INDEX_TUPLES = frozenset({"where", "nonzero"})   # (one argument: a tuple of index arrays, one per axis)


def _index_tuple(node) -> bool:
    """``np.where(cond)`` or ``np.nonzero(x)`` (``x.nonzero()``) as written, not indexed: a tuple of arrays."""
    if not (isinstance(node, ast.Call) and _call_name(node) in _INDEX_TUPLES and not node.keywords):
        return False
    of_numpy = _attribute_path(node.func).split(".")[0] in ("np", "numpy")
    return len(node.args) == (1 if of_numpy else 0 if _call_name(node) == "nonzero" else -1)


def _where_tuple_counted(name, function) -> list[Finding]:
    """``len(np.where(errors < t))`` (or of a name only ever bound so): the tuple np.where returns has one array per
    axis, so its length is the number of axes (1 for a row of errors), not how many entries pass -- a RANSAC's
    every hypothesis then has one inlier."""
    tuples = {target for target, values in _assigned_names(function).items()
              if values and all(_index_tuple(value) for value in values)}
    for node in _nodes(function):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "len" \
                and len(node.args) == 1 and (_index_tuple(node.args[0]) or getattr(node.args[0], "id", None) in tuples):
            line, counted = _line(node), ast.unparse(node.args[0])
            made = "" if _index_tuple(node.args[0]) else \
                f" (`{counted}` is bound to `{ast.unparse(_assigned_names(function)[counted][0])}`)"
            return [Finding(name, line, "np.where's tuple counted as the entries found",
                            f"{name} (line {line}) counts with `len({counted})`{made}: np.where (np.nonzero) "
                            "returns a tuple of index arrays, one per axis, so its length is the number of axes "
                            "(1 for a 1-D condition), not how many entries pass; take the indices with "
                            "`np.where(...)[0]` or count with `np.count_nonzero(...)`", certain=True)]
    return []


def _null_vector_by_argmin(name, function) -> list[Finding]:
    """``U, S, Vt = np.linalg.svd(A)`` then ``Vt[np.argmin(S)]``: S has min(rows, columns) values, so for fewer equations
    than unknowns (8 point pairs, 9 unknowns) the null vector -- Vt's last row -- has no singular value, and the
    argmin picks the row of the smallest one there is."""
    made = {}
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Tuple) \
                and len(node.targets[0].elts) == 3 and isinstance(node.value, ast.Call) \
                and _attribute_path(node.value.func).endswith("svd") \
                and all(isinstance(e, ast.Name) for e in node.targets[0].elts[1:]):
            made.setdefault(node.targets[0].elts[2].id, set()).add(node.targets[0].elts[1].id)
    if not made:
        return []
    for node in _nodes(function):
        if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in made:
            values = made[node.value.id]
            if any(isinstance(n, ast.Call) and ((_attribute_path(n.func).endswith("argmin") and n.args
                                                 and isinstance(n.args[0], ast.Name) and n.args[0].id in values)
                                                or (isinstance(n.func, ast.Attribute) and n.func.attr == "argmin"
                                                    and isinstance(n.func.value, ast.Name) and n.func.value.id in values))
                   for n in walk(node.slice)):
                line = _line(node)
                return [Finding(name, line, "the null vector picked by the argmin of the singular values",
                                f"{name} (line {line}) takes `{ast.unparse(node)}`: np.linalg.svd gives as many singular "
                                "values as the smaller side of the matrix, so with fewer equations than unknowns (8 "
                                "point pairs for 9 unknowns) the null vector, Vt's last row, has none, and the argmin "
                                "picks the row of the smallest one there is; take `Vt[-1]`")]
    return []


# ------------------------------------------------------------------ Python's own pitfalls
_ITERATORS = frozenset({"zip", "map", "filter", "enumerate", "reversed", "iter"})   # (read once, then empty)


def _rows_repeated(name, function) -> list[Finding]:
    """``M = [[0.0] * 3] * 3`` then ``M[0][0] = sx``: the outer ``*`` repeats one row object, so writing into one
    row writes into all (every row ends the same)."""
    written: dict = {}   # name -> the first statement writing into one of its rows (`M[0][0] = ...`), read once
    for w in _nodes(function):
        if isinstance(w, (ast.Assign, ast.AugAssign)):
            for target in (w.targets if isinstance(w, ast.Assign) else [w.target]):
                for t in walk(target):
                    if isinstance(t, ast.Subscript) and isinstance(t.value, ast.Subscript) \
                            and isinstance(t.value.value, ast.Name):
                        written.setdefault(t.value.value.id, w)
    for node in _nodes(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and node.targets[0].id in written \
                and isinstance(node.value, ast.BinOp) and isinstance(node.value.op, ast.Mult) \
                and any(isinstance(side, ast.List) and len(side.elts) == 1 and isinstance(side.elts[0], (ast.List, ast.BinOp))
                        and (isinstance(side.elts[0], ast.List) or isinstance(side.elts[0].op, ast.Mult)
                             and isinstance(side.elts[0].left, ast.List))
                        for side in (node.value.left, node.value.right)):
            made = node.targets[0].id
            line = _line(node)
            # (the advice in the student's own terms: their row, their count of rows -- `n`, not a 3 of ours)
            row, count = (node.value.left, node.value.right) if isinstance(node.value.left, ast.List) \
                else (node.value.right, node.value.left)
            inner = ast.unparse(row.elts[0])
            width = ast.unparse(row.elts[0].right) if isinstance(row.elts[0], ast.BinOp) else str(len(row.elts[0].elts))
            rows = ast.unparse(count)
            return [Finding(name, line, "one row repeated: the list's rows are the same list",
                            f"{name} (line {line}) makes {made} as `{ast.unparse(node.value)}`: the outer `*` repeats "
                            f"one row object, so writing into one row (line {_line(written[made])}) writes into every row; "
                            f"make each row anew (`[{inner} for _ in range({rows})]`, or np.zeros(({rows}, {width})))",
                            certain=True)]
    return []


def _reciprocal_as_inverse(name, function) -> list[Finding]:
    """``T2 ** -1`` where a matrix's inverse belongs (MATLAB's ``T2^-1``): NumPy's ``**`` works entry by entry, so it
    gives each entry's reciprocal (inf for its zeros), not the inverse matrix."""
    in_products = {id(side) for p in _nodes(function) if isinstance(p, ast.BinOp) and isinstance(p.op, ast.MatMult)
                   for side in (p.left, p.right)}   # (read once: a def's every power asks)
    # (and transposed there: `x @ (K ** -1).T`)
    in_products |= {id(n.value) for n in _nodes(function) if isinstance(n, ast.Attribute) and n.attr == "T"
                    and id(n) in in_products}
    for node in _nodes(function):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and isinstance(node.right, ast.UnaryOp) \
                and isinstance(node.right.op, ast.USub) and isinstance(node.right.operand, ast.Constant) \
                and node.right.operand.value == 1 and isinstance(node.left, ast.Name) and id(node) in in_products:
            line = _line(node)
            return [Finding(name, line, "** -1 taken for a matrix's inverse",
                            f"{name} (line {line}) writes `{ast.unparse(node)}` in a matrix product: NumPy's ** works "
                            "entry by entry, so it is each entry's reciprocal (inf where an entry is 0), not the inverse "
                            f"matrix; use np.linalg.inv({node.left.id})", certain=True)]
    return []


_BITWISE = {ast.BitAnd: "&", ast.BitOr: "|"}


def _comparison_through_bitwise(name, function) -> list[Finding]:
    """``a > 0 & b > 0``: ``&`` (and ``|``) bind before the comparisons, so Python reads ``a > (0 & b) > 0``, a
    chained comparison of ``0 & b`` -- a TypeError for float arrays, an ambiguous truth value or a wrong mask
    for others. Two comparisons joined by ``&`` need their own parentheses."""
    for node in _nodes(function):
        if not isinstance(node, ast.Compare) or len(node.ops) != 2:
            continue
        middle = node.comparators[0]
        if isinstance(middle, ast.BinOp) and type(middle.op) in _BITWISE:
            joined = _BITWISE[type(middle.op)]
            first = ast.unparse(ast.Compare(node.left, node.ops[:1], [middle.left]))
            second = ast.unparse(ast.Compare(middle.right, node.ops[1:], node.comparators[1:]))
            line = _line(node)
            return [Finding(name, line, f"two comparisons joined by {joined} without parentheses",
                            f"{name} (line {line}) writes `{ast.unparse(node)}`: `{joined}` binds before the "
                            f"comparisons, so Python reads `{ast.unparse(node.left)} {_OPS.get(type(node.ops[0]), '?')} "
                            f"({ast.unparse(middle)}) {_OPS.get(type(node.ops[1]), '?')} "
                            f"{ast.unparse(node.comparators[1])}`, a chained comparison; write `({first}) {joined} "
                            f"({second})`", certain=True)]
    return []


_OPS = {ast.Gt: ">", ast.GtE: ">=", ast.Lt: "<", ast.LtE: "<=", ast.Eq: "==", ast.NotEq: "!="}


def _as_list(value) -> str:
    """The list an iterator's maker would make: `[f(d) for d in ds]` for a generator, `list(zip(a, b))` else."""
    if isinstance(value, ast.GeneratorExp):
        return ast.unparse(ast.ListComp(value.elt, value.generators))
    return f"list({ast.unparse(value)})"


_CONSUMERS = {"list", "tuple", "set", "sorted", "sum", "min", "max", "any", "all", "fromiter", "dict",
              "stack", "vstack", "hstack", "column_stack"}   # calls that read an iterator to its end


def _dotted_name(node) -> str:
    return f"{_dotted_name(node.value)}.{node.attr}" if isinstance(node, ast.Attribute) else \
        node.id if isinstance(node, ast.Name) else ""


def _iterator_read_twice(name, function) -> list[Finding]:
    """``pairs = zip(a, b)`` read by one loop (or comprehension) and then by another: an iterator is used up by the
    first, and the second sees nothing (no line drawn)."""
    made = {node.targets[0].id: node for node in _nodes(function)
            if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)
            and (isinstance(node.value, ast.GeneratorExp)   # (a generator: `(f0 * d / z0 for d in distances)`)
                 or (isinstance(node.value, ast.Call) and isinstance(node.value.func, ast.Name)
                     and node.value.func.id in _ITERATORS))}
    if not made:
        return []
    readers: dict = {}
    in_loops = {id(n) for node in _nodes(function) if isinstance(node, (ast.For, ast.comprehension))
                for n in walk(node.iter)}
    for node in _nodes(function):
        if isinstance(node, (ast.For, ast.comprehension)):
            for read in walk(node.iter):
                if isinstance(read, ast.Name) and read.id in made:
                    readers.setdefault(read.id, []).append(node)
        elif isinstance(node, ast.Call) and id(node) not in in_loops \
                and _dotted_name(node.func).rsplit(".", 1)[-1] in _CONSUMERS:
            # (or a call that reads it whole: `np.fromiter(focal_lengths, ...)`, `list(pairs)`)
            for read in node.args[:1]:
                if isinstance(read, ast.Name) and read.id in made:
                    readers.setdefault(read.id, []).append(node)
    for iterator, loops in readers.items():
        # (a first loop that may stop early -- `break` -- leaves the rest to the next one on purpose)
        first = min(loops, key=lambda loop: _line(loop.iter if isinstance(loop, (ast.For, ast.comprehension)) else loop))
        if len(loops) >= 2 and not (isinstance(first, ast.For) and any(isinstance(n, ast.Break) for n in walk(first))):
            line = _line(made[iterator])
            return [Finding(name, line, "an iterator read twice: the second reading finds it empty",
                            f"{name} (line {line}) makes {iterator} with `{ast.unparse(made[iterator].value)}`, an "
                            "iterator, and reads it twice: the first reading uses it up and the second finds nothing; "
                            f"make it a list (`{_as_list(made[iterator].value)}`)", certain=True)]
    return []


# The findings of state a function keeps between calls, read in its code: a failure they cause is told by them
# (not by making the call again in a fresh module, autograder.engine.fresh_start, which only measures it).
STATE_KEPT = frozenset({"a container outside the function keeps what earlier calls put in",
                        "an array of the module changed in place"})
GROWS = frozenset({"append", "extend", "insert", "appendleft"})   # (a list grown: a cache's dict is no mistake)


def _state_kept_between_calls(name, function, lists=frozenset()) -> list[Finding]:
    """``results.append(x)`` (``extend``, ``insert``) on ``results``, one of the module's ``lists`` (made at its
    top level) that the function neither makes anew (a `global` list reset inside it is) nor is given: made once,
    it keeps what every earlier call put in (``np.append(f, 1.0)`` grows no list of the module's)."""
    own = {a.arg for a in walk(function.args) if isinstance(a, ast.arg)} | set(_assigned_names(function))
    own |= {n.id for n in _nodes(function) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
    for node in _nodes(function):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in GROWS \
                and isinstance(node.func.value, ast.Name):
            held = node.func.value.id
            if held in lists and held not in own:
                line = _line(node)
                return [Finding(name, line, "a container outside the function keeps what earlier calls put in",
                                f"{name} (line {line}) calls `{held}.{node.func.attr}(...)` on `{held}`, a list made "
                                "once, at the top of the module, outside the function: it keeps what every earlier "
                                "call put in it; make it inside the function, anew at each call")]
    return []


_MODULE_ARRAYS = frozenset({"array", "asarray", "eye", "identity", "zeros", "ones", "full", "diag"})
_GROWN_OR_FILLED = GROWS | {"update", "fill", "sort", "reverse", "resize", "clear"}


def _mutable_default_written(name, function) -> list[Finding]:
    """``def _condition(pts, T=np.eye(3)):`` writing into ``T`` (``T[:2, 2] = ...``, ``T *= s``, ``rows.append``):
    a default is made once, when the def runs, so every call that leaves the parameter out writes into that one
    object and gets it back -- two calls' results are the same array. A parameter rebound before it is written
    (``T = T.copy()``) is not read as one. (One pass over the def's statements in order.)"""
    arguments = function.args
    positional = arguments.posonlyargs + arguments.args
    defaults = dict(zip((a.arg for a in positional[len(positional) - len(arguments.defaults):]), arguments.defaults))
    defaults |= {a.arg: d for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults) if d is not None}
    mutable = {parameter: default for parameter, default in defaults.items()
               if isinstance(default, (ast.List, ast.Dict, ast.Set)) or (isinstance(default, ast.Call) and (
                   _call_name(default) in _MODULE_ARRAYS | {"list", "dict", "set"}))}
    if not mutable:
        return []
    for statement in _statements_in_order(function):
        targets = statement.targets if isinstance(statement, ast.Assign) else \
            [statement.target] if isinstance(statement, ast.AugAssign) else []
        written = None
        for target in targets:
            if isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name) and target.value.id in mutable:
                written = target.value.id
            elif isinstance(statement, ast.AugAssign) and isinstance(target, ast.Name) and target.id in mutable:
                written = target.id
        call = statement.value if isinstance(statement, ast.Expr) else None
        if isinstance(call, ast.Call) and isinstance(call.func, ast.Attribute) and call.func.attr in _GROWN_OR_FILLED \
                and isinstance(call.func.value, ast.Name) and call.func.value.id in mutable:
            written = call.func.value.id
        if written is not None:
            line = _line(statement)
            default = ast.unparse(mutable[written])
            return [Finding(name, line, "a default made once and written into by every call",
                            f"{name} (line {line}) writes into `{written}`, whose default `{default}` is made once, "
                            f"when the def runs: every call that leaves `{written}` out writes into that one object "
                            f"and gets it back, so two calls share it; give it the default None and make a new one "
                            f"in the function", certain=True)]
        if isinstance(statement, ast.Assign):   # (rebound first: a copy of its own from here on)
            for target in statement.targets:
                for bound in (n.id for n in walk(target) if isinstance(n, ast.Name)):
                    mutable.pop(bound, None)
            if not mutable:
                return []
    return []


def _module_array_changed(name, function, arrays) -> list[Finding]:
    """An array made at the top of the module changed in place by the function, directly (``ORTHO[:2] *= s``)
    or through a name given it without a copy (``M = ORTHO``, then ``M[:2] *= s``): the module's array itself
    changes, so every later call (and every other function reading it) sees it changed."""
    if not arrays:
        return []
    # (a name the function assigns anywhere is its own, unless declared global: Python's rule)
    declared = {name for node in _nodes(function) if isinstance(node, ast.Global) for name in node.names}
    own = {a.arg for a in walk(function.args) if isinstance(a, ast.arg)} | (
        {n.id for n in _nodes(function) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)} - declared)
    aliases: dict = {}   # a name of the function -> the module's array it was given (no copy)
    for statement in _statements_in_order(function):
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1 and isinstance(statement.targets[0], ast.Name):
            target, value = statement.targets[0].id, statement.value
            if isinstance(value, ast.Name) and (value.id in arrays or value.id in aliases) and value.id not in own:
                aliases[target] = aliases.get(value.id, value.id)
            else:
                aliases.pop(target, None)
            continue
        targets = statement.targets if isinstance(statement, ast.Assign) else \
            [statement.target] if isinstance(statement, ast.AugAssign) else []
        for target in targets:
            held = target.value if isinstance(target, ast.Subscript) else target if isinstance(statement, ast.AugAssign) else None
            if not isinstance(held, ast.Name):
                continue
            array = aliases.get(held.id) or (held.id if held.id in arrays and held.id not in own else None)
            if array is None:
                continue
            line = _line(statement)
            through = f"`{held.id}`, which is `{array}` itself (`{held.id} = {array}` makes no copy)" \
                if held.id != array else f"`{array}`"
            return [Finding(name, line, "an array of the module changed in place",
                            f"{name} (line {line}) changes {through} in place: `{array}` is made once, at the top of "
                            f"the module, so every later call (and every function reading `{array}`) gets it changed; "
                            f"work on a copy (`{held.id} = {array}.copy()`)", certain=True)]
    return []


def _rounds_to_decimals(node) -> bool:
    """``np.round(x, 4)``, ``np.around(x, decimals=3)``, ``round(x, 2)``, ``x.round(4)``: decimals >= 1 given."""
    if not isinstance(node, ast.Call):
        return False
    called = _call_name(node)
    method = isinstance(node.func, ast.Attribute) and called == "round" and not _attribute_path(node.func) \
        in ("np.round", "numpy.round")
    if called not in ("round", "around", "round_"):
        return False
    given = node.args[0] if method and node.args else node.args[1] if len(node.args) > 1 else next(
        (k.value for k in node.keywords if k.arg in ("decimals", "ndigits")), None)
    return isinstance(given, ast.Constant) and isinstance(given.value, int) and given.value >= 1
