"""An OpenCV error the student's function raised, explained from what its code does.

The worker explains an error of a ``cv2`` function from the arguments it was given
(:mod:`autograder.sandbox.beginner`); a method's error -- a matcher's ``knnMatch``, a
detector's ``detectAndCompute`` -- reaches the grader with OpenCV's message alone:
``(-210:Unsupported format or combination of formats) in function 'buildIndex_' > type=0``
names neither the index nor the descriptors. Each rule here ties one such signature to what the
code shows (read with :mod:`ast`, never run): FLANN's KD-tree index (``algorithm=1``) built
where the message measures uint8 descriptors, ``NORM_HAMMING`` where it measures float ones.
A rule names its cause only when the message measures one half and the code writes the other.
"""

from __future__ import annotations

import ast
import re

from .claims import from_code, measured
from .forms import Form
from .hints import _own_nodes, _path
from ..loading.parsing import walk

_BUILD_INDEX = re.compile(r"in function 'buildIndex_'.*?type=(\d+)", re.S)
_HAMMING_FLOATS = re.compile(r"\(type == CV_8U && dtype == CV_32S\) \|\| dtype == CV_32F in function 'batchDistance'")
_ONE_NEIGHBOUR = re.compile(r"K == 1 && update == 0 && mask\.empty\(\) in function 'batchDistance'")
_REMAP_TYPES = re.compile(r"map1\.type\(\) == CV_32FC2.*in function 'remap'", re.S)
_DETECT_DEPTH = re.compile(r"incorrect depth \(!=CV_8U\) in function '(detectAndCompute|detect)'")
_NUM_DISPARITIES = re.compile(r"numDisparities must be positive and divisible by 16")
# FLANN's index algorithms (flann::flann_algorithm_t): the KD-trees take float32 rows, LSH binary (uint8) ones
KDTREE, LSH = (1, 4), 6
FLANN_KDTREE_BINARY = "FLANN's KD-tree index given binary (uint8) descriptors"
FLANN_LSH_FLOAT = "FLANN's LSH index given float descriptors"
FLANN_FLOAT64 = "float64 descriptors given to FLANN"
HAMMING_FLOAT = "Hamming distance on float descriptors"
CROSS_CHECK_KNN = "two nearest neighbours asked of a cross-checking matcher"
REMAP_TYPES = "remap's maps not float32"
DETECT_FLOAT = "a float image given to a feature detector"
DISPARITIES_NOT_16 = "numDisparities not a multiple of 16"
PASSED_AS_GIVEN = "an input passed to OpenCV in the form the caller gave it"
# the worker's sentence on a cv2 function's argument (autograder.sandbox.beginner): its parameter's name
_WORKER_NAMES = re.compile(r"^cv2\.(\w+) (?:needs (?:the points in )?|cannot work on |cannot convert )(\w+)\b")
BINARY_DETECTORS = ("ORB_create", "BRISK_create", "AKAZE_create")
FLOAT_DETECTORS = ("SIFT_create", "xfeatures2d.SURF_create", "KAZE_create")


def opencv_explained(code, fn, line: int, given: dict, message: str, function: str) -> Form | None:
    """The cause of OpenCV's error ``message``, raised on ``line`` of ``fn`` (a function of the
    module called from ``function``), when a rule ties it to the code; None otherwise. An error the
    worker explained already (its sentence leads the message) is left as it was."""
    if not message.startswith(f"{function}() raised"):
        # in the function called only: a helper's parameters may hold a converted copy (another dtype)
        return _argument_as_given(fn, line, given, message) if fn.name == function else None
    functions = code.reachable([function]) or [fn]
    found = _BUILD_INDEX.search(message)
    if found:
        return _flann(functions, int(found.group(1)))
    if _HAMMING_FLOATS.search(message):
        return _hamming(functions)
    if _ONE_NEIGHBOUR.search(message):
        return _cross_checked(functions, fn, line)
    if _REMAP_TYPES.search(message):
        return _remap(fn, line)
    found = _DETECT_DEPTH.search(message)
    if found:
        return _detect_float(fn, line, found.group(1))
    if _NUM_DISPARITIES.search(message):
        return _disparities_unrounded(functions)
    return None


def _disparities_unrounded(functions) -> Form | None:
    """StereoBM refused its numDisparities (a positive multiple of 16): the value the code gives it, where no
    16 is written in it (`numDisparities=max_disparity`)."""
    for function in functions:
        for node in _own_nodes(function):
            if not (isinstance(node, ast.Call) and _path(node.func).rpartition(".")[2] in ("StereoBM_create",
                                                                                          "StereoSGBM_create")):
                continue
            place = 0 if _path(node.func).endswith("StereoBM_create") else 1
            given = next((k.value for k in node.keywords if k.arg == "numDisparities"),
                         node.args[place] if len(node.args) > place else None)
            if given is None or any(isinstance(n, ast.Constant) and n.value == 16 for n in walk(given)):
                continue
            return Form(from_code(
                f"your code gives {_path(node.func).rpartition('.')[2]} numDisparities={_short(given)} (line "
                f"{node.lineno}), where no 16 is written, and OpenCV takes a positive multiple of 16 only: round it up "
                f"(16 * ceil(max_disparity / 16)) and keep the disparities up to max_disparity"), DISPARITIES_NOT_16)
    return None


def _argument_as_given(fn, line: int, given: dict, message: str) -> Form | None:
    """The worker explained a cv2 function's error from the argument it was given (``cv2.X needs src
    as ...; yours is ...``): when that argument, on the raising line, is one of the function's own
    parameters as the caller gave it (the same object: never reassigned), which input it is."""
    found = _WORKER_NAMES.match(message)
    if not found:
        return None
    function, parameter = found.groups()
    import cv2

    from ..sandbox.beginner import _parameters

    names = _parameters(getattr(getattr(cv2, function, None), "__doc__", "") or "")
    calls = [n for n in _own_nodes(fn) if isinstance(n, ast.Call) and _path(n.func).rpartition(".")[2] == function
             and n.lineno <= line <= n.end_lineno]
    if parameter not in names or len(calls) != 1:
        return None
    index = names.index(parameter)
    call = calls[0]
    argument = call.args[index] if index < len(call.args) and not any(
        isinstance(a, ast.Starred) for a in call.args[:index + 1]) else next(
        (k.value for k in call.keywords if k.arg == parameter), None)
    from .raised import _reassigned

    if not isinstance(argument, ast.Name) or argument.id not in given or _reassigned(fn, argument.id, line):
        return None
    value = given[argument.id]
    form = f"shape {value.shape}, {value.dtype}" if hasattr(value, "shape") and hasattr(value, "dtype") else \
        type(value).__name__
    return Form(measured(
        f"that {parameter} is `{argument.id}` (line {line}) as your `{fn.name}` was given it ({form}): inputs may "
        f"come in that form, so convert `{argument.id}` in your function before it reaches cv2.{function}"),
        PASSED_AS_GIVEN)


def _calls(functions, *names: str):
    """The calls in ``functions`` whose called name ends with one of ``names`` (``cv2.ORB_create``)."""
    for function in functions:
        for node in _own_nodes(function):
            if isinstance(node, ast.Call) and any(_path(node.func).endswith(name) for name in names):
                yield function, node


def _uses(functions, names) -> str:
    """``cv2.ORB_create`` when ``functions`` call one of ``names``, else ``""``."""
    for _, call in _calls(functions, *names):
        return _path(call.func)
    return ""


def _algorithm(function, node, depth: int = 2):
    """The FLANN index algorithm ``node`` (a matcher's index parameters) asks for: a number, or
    the constant's name (``FLANN_INDEX_KDTREE``) read as the algorithm it stands for; None when unknown."""
    if isinstance(node, ast.Dict):
        for key, value in zip(node.keys, node.values):
            if isinstance(key, ast.Constant) and key.value == "algorithm":
                return _algorithm_value(function, value, depth)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "dict":
        for keyword in node.keywords:
            if keyword.arg == "algorithm":
                return _algorithm_value(function, keyword.value, depth)
    if isinstance(node, ast.Name) and depth > 0:
        values = [n.value for n in _own_nodes(function) if isinstance(n, ast.Assign)
                  and any(isinstance(t, ast.Name) and t.id == node.id for t in n.targets)]
        found = {_algorithm(function, value, depth - 1) for value in values}
        return found.pop() if len(found) == 1 else None
    return None


def _algorithm_value(function, node, depth):
    if isinstance(node, ast.Constant) and isinstance(node.value, int) and not isinstance(node.value, bool):
        return node.value
    if isinstance(node, (ast.Name, ast.Attribute)):
        name = _path(node).rpartition(".")[2].upper()
        if "KDTREE" in name:
            return KDTREE[0]
        if "LSH" in name:
            return LSH
        if isinstance(node, ast.Name) and depth > 0:
            values = {n.value.value for n in _own_nodes(function) if isinstance(n, ast.Assign)
                      and isinstance(n.value, ast.Constant) and isinstance(n.value.value, int)
                      and any(isinstance(t, ast.Name) and t.id == node.id for t in n.targets)}
            return values.pop() if len(values) == 1 else None
    return None


def _matchers(functions):
    """(line, algorithm) of each cv2.FlannBasedMatcher the code builds with index parameters."""
    for function, call in _calls(functions, "FlannBasedMatcher", "FlannBasedMatcher_create"):
        index = call.args[0] if call.args else next((k.value for k in call.keywords if k.arg == "indexParams"), None)
        if index is not None:
            yield call.lineno, _algorithm(function, index)


def _flann(functions, depth: int) -> Form | None:
    matchers = list(_matchers(functions))
    kd = [line for line, algorithm in matchers if algorithm in KDTREE]
    lsh = [line for line, algorithm in matchers if algorithm == LSH]
    if depth == 0 and kd:   # CV_8U rows: the KD-tree index cannot take them
        binary = _uses(functions, BINARY_DETECTORS)
        whose = f", as {binary}'s are (your code uses it)" if binary else ""
        return Form(from_code(
            f"your code gives cv2.FlannBasedMatcher a KD-tree index (algorithm=1, line {kd[0]}), which works on "
            f"float32 descriptors, and these are uint8 (OpenCV's 'type=0'): binary descriptors{whose}. Match binary "
            "descriptors with FLANN's LSH index, dict(algorithm=6, table_number=6, key_size=12, "
            "multi_probe_level=1), or with cv2.BFMatcher(cv2.NORM_HAMMING)"), FLANN_KDTREE_BINARY)
    if depth == 5 and lsh and not kd:   # CV_32F rows: LSH hashes bits
        floats = _uses(functions, FLOAT_DETECTORS)
        whose = f", as {floats}'s are (your code uses it)" if floats else ""
        return Form(from_code(
            f"your code gives cv2.FlannBasedMatcher an LSH index (algorithm=6, line {lsh[0]}), which hashes binary "
            f"(uint8) descriptors, and these are float32 (OpenCV's 'type=5'){whose}: match float descriptors "
            "with the KD-tree index, dict(algorithm=1, trees=5)"), FLANN_LSH_FLOAT)
    if depth == 6 and kd:
        return Form(measured(
            f"the descriptors given to FLANN's KD-tree index (line {kd[0]}) are float64 (OpenCV's 'type=6'), and it "
            "takes float32: convert them with np.float32(descriptors)"), FLANN_FLOAT64)
    return None


def _hamming(functions) -> Form | None:
    """NORM_HAMMING measures uint8 rows only: the assertion fails for any other type."""
    lines = [call.lineno for _, call in _calls(functions, "BFMatcher", "BFMatcher_create")
             if any(_path(a).endswith(("NORM_HAMMING", "NORM_HAMMING2"))
                    for a in list(call.args) + [k.value for k in call.keywords])]
    if not lines:
        return None
    floats = _uses(functions, FLOAT_DETECTORS)
    whose = f" ({floats}'s are float32; your code uses it)" if floats else ""
    return Form(from_code(
        f"your code gives cv2.BFMatcher cv2.NORM_HAMMING (line {lines[0]}), a distance between binary (uint8) "
        f"descriptors such as ORB's, and these are not uint8{whose}: compare float descriptors with cv2.NORM_L2"),
        HAMMING_FLOAT)


def _cross_checked(functions, fn, line: int) -> Form | None:
    """A BFMatcher built with crossCheck=True asked for k > 1 neighbours (its batchDistance takes K == 1)."""
    lines = [call.lineno for _, call in _calls(functions, "BFMatcher", "BFMatcher_create")
             if any(k.arg == "crossCheck" and isinstance(k.value, ast.Constant) and k.value.value is True
                    for k in call.keywords)
             or len(call.args) >= 2 and isinstance(call.args[1], ast.Constant) and call.args[1].value is True]
    asked = [n for n in _own_nodes(fn) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
             and n.func.attr == "knnMatch" and n.lineno <= line <= n.end_lineno]
    if not lines or len(asked) != 1 or not _neighbours_asked(asked[0]) > 1:
        return None   # k = 1 (or unknown): the assertion's mask or update part failed, not its K
    return Form(from_code(
        f"your code builds cv2.BFMatcher with crossCheck=True (line {lines[0]}), which keeps only mutual best "
        f"matches, one per descriptor, and asks it for more than one neighbour with knnMatch (line {line}): for "
        "the two neighbours of the ratio test, build it with crossCheck=False (the ratio test already drops "
        "ambiguous matches)"), CROSS_CHECK_KNN)


def _neighbours_asked(call: ast.Call) -> int:
    """The ``k`` a ``knnMatch(query, train, k)`` call writes as a number (0 when it is not one)."""
    k = next((kw.value for kw in call.keywords if kw.arg == "k"), call.args[2] if len(call.args) >= 3 else None)
    return k.value if isinstance(k, ast.Constant) and type(k.value) is int else 0


def _remap(fn, line: int) -> Form | None:
    """cv2.remap's type assertion: the maps are not float32 (a CV_32FC2 map alone, or two CV_32FC1)."""
    calls = [n for n in _own_nodes(fn) if isinstance(n, ast.Call) and _path(n.func).endswith("remap")
             and n.lineno <= line <= n.end_lineno and len(n.args) >= 3]
    if len(calls) != 1:
        return None
    map_x, map_y = calls[0].args[1:3]
    if isinstance(map_y, ast.Constant) and map_y.value is None:
        return None   # one map given: its layout, not only its type, is in question
    shown = f"`{_short(map_x)}` and `{_short(map_y)}`"
    return Form(measured(
        f"cv2.remap takes its two maps, {shown} (line {line}), as float32 arrays, and OpenCV's check of their "
        "types failed: convert both with .astype(np.float32) (NumPy's arithmetic makes float64, and np.indices "
        "or np.arange of whole numbers int64)"), REMAP_TYPES)


_FLOAT_REDUCTIONS = ("mean", "average", "std", "var")   # (of uint8 pixels: float64)


def _float_made(node) -> ast.expr | None:
    """The part of ``node`` that makes an array float, or None: ``x.astype(np.float32)``,
    ``np.float64(x)``, ``np.asarray(x, dtype=float)``, ``x / 255`` (a true division is float whatever it
    divides), a mean of pixels (``img.mean(axis=2)``), arithmetic with a float number or weights
    (``img @ [0.114, 0.587, 0.299]``), arithmetic on one of them (the whole arithmetic is told), or either
    branch of a conditional."""
    # (walked with a stack, not by recursion: a chain `a + b + ...` nests as deep as it is long)
    stack = [(node, None)]   # (a part, the outermost arithmetic it is in)
    while stack:
        part, arithmetic = stack.pop()
        if isinstance(part, ast.IfExp):
            stack += [(part.orelse, arithmetic), (part.body, arithmetic)]
        elif isinstance(part, ast.BinOp):
            if isinstance(part.op, ast.Div) or _float_numbers(part.left) or _float_numbers(part.right):
                return arithmetic or part
            stack += [(part.right, arithmetic or part), (part.left, arithmetic or part)]
        elif isinstance(part, ast.Call) and _float_call(part):
            return arithmetic or part
    return None


def _float_call(node: ast.Call) -> bool:
    last = _path(node.func).rpartition(".")[2]
    words = [ast.unparse(a) for a in node.args[1:] if last in ("asarray", "array")] + \
        [ast.unparse(k.value) for k in node.keywords if k.arg == "dtype"] + \
        [ast.unparse(a) for a in node.args if last == "astype"]
    if last == "astype" or any(k.arg == "dtype" for k in node.keywords):
        # (the type written decides: `.astype(np.uint8)` after a mean makes it uint8 again)
        return any(w.endswith(("float", "float32", "float64")) for w in words)
    return last in ("float32", "float64") or any(w.endswith(("float", "float32", "float64")) for w in words) \
        or last in _FLOAT_REDUCTIONS or (last in ("dot", "matmul", "tensordot") and any(_float_numbers(a) for a in node.args))


def _float_numbers(node) -> bool:
    """A float number, or a list or tuple of numbers with a float among them (weights)."""
    if isinstance(node, ast.Constant):
        return isinstance(node.value, float)
    if isinstance(node, (ast.List, ast.Tuple)):
        return any(_float_numbers(e) for e in node.elts) \
            and all(isinstance(e, ast.Constant) or _float_numbers(e) for e in node.elts)
    return False


def _detect_float(fn, line: int, method: str) -> Form | None:
    """A detector given an image the code itself makes float (``grey.astype(np.float32)``,
    ``img.mean(axis=2)``)."""
    calls = [n for n in _own_nodes(fn) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
             and n.func.attr == method and n.lineno <= line <= n.end_lineno and n.args]
    if len(calls) != 1:
        return None
    image = calls[0].args[0]
    made = image
    if isinstance(image, ast.Name):
        values = [n.value for n in _own_nodes(fn) if isinstance(n, ast.Assign) and n.lineno < line
                  and any(isinstance(t, ast.Name) and t.id == image.id for t in n.targets)]
        made = values[-1] if len(values) == 1 else None
    made = None if made is None else _float_made(made)
    if made is None:
        return None
    return Form(from_code(
        f"your code makes the image it gives {method} a float array (`{_short(made)}`, line {made.lineno}), and "
        "OpenCV's detectors take uint8 images: give it the uint8 image (grey, np.uint8)"), DETECT_FLOAT)


def _short(node, limit: int = 40) -> str:
    text = ast.unparse(node)
    return text if len(text) <= limit else text[:limit - 3] + "..."
