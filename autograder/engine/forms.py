"""Naming a wrong *form* from what was measured: a result's shape, the error NumPy raised.

Many mistakes leave the numbers right and the form wrong -- the 2x3 affine matrix
OpenCV's ``warpAffine`` takes where the 3x3 homogeneous one is asked, points still
homogeneous, OpenCV's ``(N, 1, 2)`` layout -- or stop the function with NumPy's own
error (``operands could not be broadcast together with shapes (15,2) (15,)``, a
matrix product whose inner sizes differ by the homogeneous 1). The shape, or the
shapes in the error, are measured evidence: each name here follows from them alone,
so no probe is needed to confirm it, and a form no rule recognises is left to the
plain description ("returned shape (4, 4); expected (3, 3)").

Each function returns a :class:`Form` (the sentence that explains it, beginning "it
looks like", and the mistake's short name for the class reports) or ``None``.

Held to the code (issue 35; ``tests/test_judges_coverage.py``): a fix a sentence gives
("reshape it to (N, 2)", "keep it a column") is about the array measured -- the one returned,
or the operands in NumPy's error -- so it is true of the student whatever else the code does,
and is marked :func:`~autograder.engine.claims.measured`. Two parts say what the code does and
are :func:`~autograder.engine.claims.guard`-ed: "divide by the last one" (code that already
divides by the last coordinate is told only to keep the first ones) and "the division uses the
wrong coordinate" (code that writes no division is told only the measured scale).
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass

import numpy as np

from ..sandbox import beginner
from .claims import divides_by, guard, guessed, measured
from .hints import Predicate, expr, keyword, mentions
from ..loading.parsing import walk


def _divides_by_last(k: int):
    """A division by the last of ``k + 1`` coordinates, however indexed (``X[:, k]``, ``X[:, -1:]``,
    ``X[..., k, None]``...), written or through a name holding it."""
    ends = (str(k), "-1")
    return divides_by(*(f"_[{form}]" for end in ends for form in (
        f":, {end}", f":, {end}:", f"..., {end}", f"..., {end}:", f":, {end}, None", f":, [{end}]", end,
        f"{end}, :")), f"_[:, {k}:{k + 1}]", "_[:, -1][:, None]", f"_[:, {k}][:, None]",
        says="divides by the last coordinate")


# "divide by the last one and keep the first k", for points of k coordinates (2-D or 3-D)
DEHOMOGENISE = {k: guard(f"divide by the last one and keep the first {k}", _divides_by_last(k),
                         instead=f"your code {{found}}: keep only the first {k} coordinates of what it returns")
                for k in (2, 3)}
# The fixes autograder.sandbox.beginner's sentences give, held to the code here (the grader's side):
# its exceptions' explanations reach the grader as the failure's message, rewritten there.
_ROW_NAME = re.compile(r"^(?:y|yy|row|rows|r|v|i|top|bottom)(?:_?\d*|_\w+)?$", re.I)
_COLUMN_NAME = re.compile(r"^(?:x|xx|col|cols|column|c|u|j|left|right)(?:_?\d*|_\w+)?$", re.I)


def _index_pairs(function):
    """The (first, second) names leading each two-index subscript of ``function`` (``img[y + 1, x]``
    gives ``("y", "x")``, and so does ``img[y][x]``, one index after the other; an index with no name gives ``""``)."""
    def leading(index) -> str:
        return next((n.id for n in walk(index) if isinstance(n, ast.Name)), "")

    for node in walk(function):
        if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2:
            yield tuple(leading(e) for e in node.slice.elts)
        elif isinstance(node, ast.Subscript) and isinstance(node.value, ast.Subscript) \
                and not isinstance(node.slice, (ast.Tuple, ast.Slice)) \
                and not isinstance(node.value.slice, (ast.Tuple, ast.Slice)) \
                and not isinstance(node.value.value, ast.Subscript):
            yield leading(node.value.slice), leading(node.slice)


def _indexes(first: re.Pattern, second: re.Pattern):
    return lambda function: any(first.match(a) and second.match(b) for a, b in _index_pairs(function))


# [y, x] written, and never [x, y]: the IndexError then comes from a range, not the order
INDEXES_Y_X = (Predicate("indexes images as [y, x]", _indexes(_ROW_NAME, _COLUMN_NAME))
               & ~Predicate("indexes [x, y]", _indexes(_COLUMN_NAME, _ROW_NAME))).saying("indexes images as [y, x]")
guard(beginner.INDEX_AS_Y_X, INDEXES_Y_X,
      instead="your code {found}: the index itself goes past that axis (check the range it runs over)")
_FLOAT = ("float", "np.float64", "np.float32", "numpy.float64", "numpy.float32", "float64", "float32")
# One leaf testing each pattern (a chain of ``|`` re-reads its parts at every level of the chain).
_FLOAT_PATTERNS = [expr("_.astype(float)"), expr("_.astype(np.float64)"), expr("_.astype(np.float32)"),
                   expr("np.float64(_)"), expr("np.float32(_)")] + [
    keyword(maker, "dtype", value)   # dtype=float only (dtype=int is how the mistake is written)
    for maker in ("np.array", "np.asarray", "np.zeros", "np.ones", "np.eye", "np.identity", "np.full", "np.empty")
    for value in _FLOAT]
TO_FLOAT = Predicate("builds or converts an array as float",
                     lambda function: any(pattern.test(function) for pattern in _FLOAT_PATTERNS))
guard(beginner.BUILD_AS_FLOAT, TO_FLOAT,
      instead="Your code {found} somewhere, but not this one (follow the array returned back to where it is made).")
guard(beginner.CONVERT_FIRST, TO_FLOAT, instead="your code {found} somewhere, but the array returned is still uint8")
# "convert to RGB only to show a picture": to code that converts to RGB; other code put the channels
# in R, G, B order another way (measured: the image returned is the right one with its channels reversed)
CONVERTS_TO_RGB = (mentions("cv2.COLOR_BGR2RGB") | mentions("cv2.COLOR_RGB2BGR") | expr("_[..., ::-1]")
                   | expr("_[:, :, ::-1]")).saying("converts between BGR and RGB")
guard(beginner.RGB_ONLY_TO_SHOW, ~CONVERTS_TO_RGB,
      instead="your code does not convert to RGB: it puts the channels in R, G, B order another way "
              "(a stack, a channel index, or a flip of every axis: `np.flip(image)` with no axis reverses the "
              "channels too)")
# The cause scale_form names, said only of code that divides somewhere (else the measured scale only).
WRONG_COORDINATE = guard("the division uses the wrong coordinate", ~divides_by("_"),
                         instead="no division is written in your code: the answer is scaled by one over that entry")


@dataclass(frozen=True)
class Form:
    sentence: str    # "it looks like ...; ..." (no final full stop)
    mistake: str     # the short name class reports count


def _size(shape) -> str:
    return "x".join(str(n) for n in shape)


# (inferred from the lengths alone: a change of the code confirmed to mend it says where, and takes its place)
EVERY_PAIR = guessed("a result for every pair of items that go in step")


def shape_form(got: tuple, expected: tuple) -> Form | None:
    """The form a result of shape ``got`` has where ``expected`` is asked (``None`` entries
    of ``expected`` match any length), when a rule recognises it."""
    got, expected = tuple(got), tuple(expected)
    if len(got) == 2 and len(expected) == 2 and None not in expected:
        rows, columns = expected
        if rows != columns and got == (columns, rows):
            # (the lengths alone: an array transposed, or one made with its two sizes in the other order)
            return Form("it looks like its rows and columns are exchanged (transposed, or made with its two sizes "
                        "in the other order)", "the result is transposed")
        if got == (rows - 1, columns) and rows == columns in (3, 4):
            return Form(f"it looks like the {_size(got)} affine form, the matrix without its last row "
                        f"[0 ... 0 1]; a {_size(expected)} homogeneous matrix is asked",
                        f"the {_size(got)} affine form instead of the {_size(expected)} homogeneous matrix")
        if got == (rows + 1, columns) and columns == rows + 1 in (3, 4):
            return Form(f"it looks like the {_size(got)} homogeneous matrix; its top {rows} rows "
                        f"({_size(expected)}) are asked",
                        f"the {_size(got)} homogeneous matrix instead of its {_size(expected)} top rows")
        if got == (rows - 1, columns - 1) and rows == columns in (3, 4):
            return Form(f"it looks like the {_size(got)} linear part alone; a {_size(expected)} homogeneous matrix "
                        f"is asked (that block, a last column for the translation, and a last row [0 ... 0 1])",
                        f"the {_size(got)} linear part instead of the {_size(expected)} homogeneous matrix")
        if got == (rows, columns - 1):
            return Form(f"it looks like the last column is missing ({_size(got)} for {_size(expected)})",
                        "the matrix's last column is missing")
    if len(got) == len(expected) + 1 == 3 and got[1] == 1 and _fits(got[:1] + got[2:], expected):
        return Form(measured(f"it looks like OpenCV's (N, 1, {got[2]}) point layout: reshape it to (N, {got[2]})"),
                    "points left in OpenCV's (N, 1, 2) layout")
    if len(got) == len(expected) == 2 and expected[0] is None and expected[1] in (2, 3) \
            and got[1] == expected[1] + 1:
        return Form(f"it looks like the points are still homogeneous ({got[1]} coordinates): "
                    + DEHOMOGENISE.get(expected[1], measured(f"keep the first {expected[1]}")),
                    "points left in homogeneous coordinates")
    channels = _channels_form(got, expected)
    if channels is not None:
        return channels
    # (two axes at least: a flat 9 where 3 are asked may as well be a 3 x 3 matrix flattened)
    # (n > 2: of two items, 4 = 2 x 2 is also 2 + 2, the items of two inputs stacked)
    if len(got) == len(expected) >= 2 and expected[0] is not None and expected[0] > 2 \
            and got[0] == expected[0] ** 2 and _fits(got[1:], expected[1:]):
        n = expected[0]
        return Form(measured(f"it looks like one result for every pair of items of two length-{n} inputs, {got[0]} = "
                             f"{n} x {n} where {n} are asked: loops nested where the two go in step make them (zip(a, b) "
                             "pairs them item by item)"), EVERY_PAIR)
    if len(got) == len(expected) >= 3 and None not in expected and got != expected \
            and sorted(got) == sorted(expected) and len(set(expected)) == len(expected):
        # (each length once: which axis went where is read from the lengths alone)
        order = tuple(expected.index(n) for n in got)
        moved = [i for i, axis in enumerate(order) if axis != i]
        which = f"axes {moved[0]} and {moved[1]} exchanged" if len(moved) == 2 else f"in the order {order}"
        return Form(measured(f"the same lengths, but the axes are in the wrong order ({which}: stacked along another "
                             f"axis, or transposed?)"), "the axes are in the wrong order")
    if len(expected) == 1 and len(got) == 2 and 1 in got and _fits((max(got),), expected):
        # (no way back is told: the values may be wrong too -- a cv2 call reading a short array as a Scalar)
        return Form(measured(f"it looks like a {'column' if got[1] == 1 else 'row'} of shape {got} where a flat "
                             f"array of {max(got)} values is asked"), "a 2-D column or row where a flat array is asked")
    if len(got) == 1 and len(expected) == 2 and None not in expected and got[0] == expected[0] * expected[1]:
        # (no way back is told: a reshape mends rows written one after the other, and scrambles columns
        # written one after the other -- np.hstack of an x and a y column)
        return Form(measured(f"it looks flattened: {got[0]} values where a {_size(expected)} matrix is asked"),
                    "the matrix is flattened")
    return None


IMAGE_SIDE = 8   # an (H, W) expectation this large on both sides is an image, not a matrix


def _channels_form(got: tuple, expected: tuple) -> Form | None:
    """An image of the asked size with another channel count: grey asked, 3 or 4 channels
    returned (a cv2.cvtColor(..., COLOR_GRAY2BGR) to draw in colour), or BGR asked and grey
    returned. The API's rule: a function that takes an image returns its channel count."""
    if None in expected or len(expected) not in (2, 3) or min(expected[:2]) < IMAGE_SIDE:
        return None
    rule = "a function that takes an image returns the input's channel count"
    if len(expected) == 2 and got == expected + (1,):   # a mask broadcast as mask[..., None], say
        return Form(measured("it looks like the grey image kept a channel axis of length 1, (H, W, 1): a grey "
                             "image is (H, W) (drop the axis: result[..., 0])"), "a grey image with an extra (H, W, 1) axis")
    if len(expected) == 2 and len(got) == 3 and got[:2] == expected and got[2] in (3, 4):
        return Form(f"it looks like the channels are not kept: {got[2]} channels where a grey (H, W) image is "
                    f"asked ({rule}: grey in, grey out)", "the channels are not kept")
    if len(expected) == 2 and got == expected[:1]:   # (H,) for (H, W): `out[..., 0]` of a grey image
        return Form(measured("it looks like one value per row, (H,): a grey (H, W) image indexed on its last axis (`[..., 0]`, "
                             "`[:, :, 0]`, meant for a colour channel) keeps a single column of it"),
                    "a grey image indexed on its last axis (one column kept)")
    if len(expected) == 3 and expected[2] == 3 and got == expected[:2]:
        return Form(f"it looks like the channels are not kept: a grey (H, W) image where a BGR (H, W, 3) one is "
                    f"asked ({rule}: BGR in, BGR out)", "the channels are not kept")
    if len(expected) == 3 and got == expected[2:] + expected[:2]:   # (3, H, W) for (H, W, 3)
        return Form(measured(f"it looks like the channels come first, {got}: the planes stacked along a new first axis, "
                             "where an image's channels are its last axis "
                             "(rows, columns, channels)"), CHANNELS_FIRST)
    return None


CHANNELS_FIRST = "the channels stacked along the first axis instead of the last"


COLOURS_LOST = "the colours are lost: a grey copy used where the colour image belongs"


CHANNEL_COPIED = "one colour channel copied into all three"
_CHANNEL_NAMES = ("blue", "green", "red")


def channel_copied(got, expected, inside=None) -> str:
    """A sentence when ``got``'s three equal channels are one channel of the ``expected`` colour image (not
    its grey version): that channel made all three; "" otherwise."""
    import cv2

    if not (isinstance(got, np.ndarray) and isinstance(expected, np.ndarray) and got.shape == expected.shape
            and got.ndim == 3 and got.shape[2] == 3):
        return ""
    mask = np.ones(got.shape[:2], bool) if inside is None else np.asarray(inside, bool)
    if not mask.any():
        return ""
    plane = got[..., 0].astype(np.float64)[mask]
    grey = cv2.cvtColor(np.ascontiguousarray(expected), cv2.COLOR_BGR2GRAY).astype(np.float64)[mask]
    apart = [float(np.mean(np.abs(plane - expected[..., c].astype(np.float64)[mask]))) for c in range(3)]
    best = int(np.argmin(apart))
    if apart[best] <= 2.0 and apart[best] < 0.25 * float(np.mean(np.abs(plane - grey))):
        return measured(f"its three channels are all the input's {_CHANNEL_NAMES[best]} channel (channel {best}) "
                        "warped: one channel made all three, where each output channel is warped from its own")
    return ""


def colours_lost(got, images) -> str:
    """A sentence when ``got`` is a BGR image whose three channels are equal while one of the colour
    ``images`` it was made from has channels that differ: a grey copy (made for a comparison or a
    feature matching) carried into the result; "" otherwise."""
    def equal_channels(image) -> bool:
        return bool(np.all(image[..., 0] == image[..., 1]) and np.all(image[..., 1] == image[..., 2]))

    if not (isinstance(got, np.ndarray) and got.ndim == 3 and got.shape[2] == 3 and got.size):
        return ""
    colour = [image for image in images if isinstance(image, np.ndarray) and image.ndim == 3 and image.shape[2] == 3
              and not equal_channels(image)]
    if not colour or not equal_channels(got):
        return ""
    # (a black or nearly uniform result has equal channels too -- a float in [0, 1] cast to uint8 -- and is no
    # grey copy of a photo, which spans many grey levels)
    if int(np.ptp(got[..., 0])) < 16:
        return ""
    return measured("it looks like the colours are lost: its three channels are equal (a grey image in BGR form) "
                    "where the input's differ: a grey copy of the input (cv2.COLOR_BGR2GRAY, made for a comparison "
                    "or the feature matching?) went into the result in place of the colour image")


UNIT_RANGE_CAST = "an image of values in [0, 1] is cast to uint8 (everything but 1.0 becomes 0)"


def unit_range_cast(got, expected) -> str:
    """A sentence when ``got`` (uint8) holds only 0 and 1 where ``expected`` spans many grey levels: a float
    image in [0, 1] cast to uint8 without scaling it back (measured); "" otherwise."""
    if not (isinstance(got, np.ndarray) and got.dtype == np.uint8 and got.size and isinstance(expected, np.ndarray)):
        return ""
    if int(got.max()) > 1 or int(np.ptp(expected)) < 32:
        return ""
    return measured(f"its pixels are all 0 or 1, where the expected image spans {int(expected.min())} to "
                    f"{int(expected.max())}: it looks like {UNIT_RANGE_CAST}. Scale a float image in [0, 1] (what "
                    "skimage's transforms return unless preserve_range=True, or an image divided by 255) back to "
                    "0-255 before the cast")


def _fits(shape: tuple, expected: tuple) -> bool:
    return len(shape) == len(expected) and all(e is None or e == s for s, e in zip(shape, expected))


_ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth")


def scale_form(got, expected, rtol: float = 1e-6) -> Form | None:
    """The form of a vector that is the right one times a single factor ``k`` (measured: the
    residual of the best factor is within ``rtol`` of the truth's size), when ``k`` tells how:
    -1 (the sign), or one over one of the truth's own entries (divided by the wrong coordinate).
    Any other factor is left to the description."""
    import numpy as np

    got = np.asarray(got, dtype=np.float64).ravel()
    expected = np.asarray(expected, dtype=np.float64).ravel()
    size = float(np.abs(expected).max()) if expected.size else 0.0
    if got.shape != expected.shape or size == 0 or not np.all(np.isfinite(got)):
        return None
    k = float(got @ expected / (expected @ expected))
    if np.abs(got - k * expected).max() > rtol * size or abs(k - 1) <= rtol:
        return None
    if abs(k + 1) <= 1e-6:
        return Form("it looks like the right answer with its sign flipped", "the sign is flipped")
    for index, entry in enumerate(expected):
        if abs(entry) > 1e-9 * size and abs(k * entry - 1) <= 1e-6:
            nth = _ORDINALS[index] if index < len(_ORDINALS) else f"number {index + 1}"
            return Form(f"it looks like the right answer divided by its own {nth} entry (which becomes 1): "
                        + WRONG_COORDINATE,
                        f"divided by the wrong coordinate (its {nth} entry)")
    return None


_BROADCAST = re.compile(r"operands could not be broadcast together with shapes ((?:\([\d,]*\)\s*)+)")
_SHAPE = re.compile(r"\(([\d,]*)\)")
_MATMUL = re.compile(r"mismatch in its core dimension \d.*?\(size (\d+) is different from (\d+)\)", re.S)
_DOT = re.compile(r"shapes \(([\d, ]+)\) and \(([\d, ]+)\) not aligned")
_INTO = re.compile(r"could not broadcast input array from shape \((\d+),\s*(\d+)(?:,\s*(\d+))?\) into shape "
                   r"\((\d+),\s*(\d+)(?:,\s*(\d+))?\)")
GREY_INTO_COLOUR = "a grey image written into a colour (3-channel) array"
COLOUR_INTO_GREY = "a colour image written into a grey (2-D) array"
FLAT_PER_ROW = "a per-row value kept flat (N,) against an (N, k) array"
HOMOGENEOUS_MIXED = "homogeneous and plain coordinates mixed in a matrix product"
ROWS_AS_COLUMNS = "points multiplied as columns while stored as rows"
# what exception_form names from NumPy's message alone: which expression of the student's it was is still open
EXCEPTION_FORMS = frozenset({GREY_INTO_COLOUR, COLOUR_INTO_GREY, FLAT_PER_ROW, HOMOGENEOUS_MIXED, ROWS_AS_COLUMNS})


def _shapes(text: str) -> list[tuple[int, ...]]:
    return [tuple(int(n) for n in group.split(",") if n.strip()) for group in _SHAPE.findall(text)]


def exception_form(message: str) -> Form | None:
    """The form behind NumPy's error in ``message`` (the student's exception line), when a rule
    recognises it: a per-row value kept flat against an ``(N, k)`` array, or a matrix product
    whose inner sizes differ by the homogeneous coordinate."""
    found = _INTO.search(message)
    if found:
        h, w, c, H, W, C = found.groups()
        if (h, w) == (H, W) and c is None and C == "3":
            return Form(measured(f"a grey image, shape ({h}, {w}), is written into a colour array of shape "
                                 f"({H}, {W}, 3): convert it to BGR first (cv2.cvtColor(img, cv2.COLOR_GRAY2BGR))"),
                        GREY_INTO_COLOUR)
        if (h, w) == (H, W) and c == "3" and C is None:
            return Form(measured(f"a colour image, shape ({h}, {w}, 3), is written into a grey array of shape "
                                 f"({H}, {W}): keep the input's channels (np.zeros_like(image), or "
                                 "image.shape for the new array)"), COLOUR_INTO_GREY)
        return None
    found = _BROADCAST.search(message)
    if found:
        shapes = _shapes(found.group(1))
        for flat in shapes:
            for table in shapes:
                if len(flat) == 1 and len(table) == 2 and table[0] == flat[0] != table[1]:
                    n, k = table
                    return Form(measured(f"it looks like a value per row, shape ({n},), meets an ({n}, {k}) "
                                         f"array: NumPy lines up the last axes, so either the values belong in a "
                                         f"column, shape ({n}, 1) (for example x[:, 2:3] or w[:, None]), or the "
                                         f"({n}, {k}) array should be one value per row too (a column of it "
                                         "taken, x[:, 0])"),
                                FLAT_PER_ROW)
        return None
    found = _MATMUL.search(message)
    if found:
        sizes = sorted(int(n) for n in found.groups())
        if sizes[1] - sizes[0] == 1 and sizes[1] in (3, 4):
            return _homogeneous_product(sizes)
        return None
    found = _DOT.search(message)
    if found:
        first, second = (tuple(int(n) for n in g.split(",") if n.strip()) for g in found.groups())
        if len(first) == 2 and len(second) == 2:
            sizes = sorted((first[1], second[0]))
            if sizes[1] - sizes[0] == 1 and sizes[1] in (3, 4):
                return _homogeneous_product(sizes)
            if first[1] == second[1] and first[1] != second[0]:
                return Form(measured(f"it looks like the points are rows ({_size(second)}) multiplied as "
                                     "columns: use pts @ M.T (or M @ pts.T)"), ROWS_AS_COLUMNS)
    return None


def _homogeneous_product(sizes: list[int]) -> Form:
    # NumPy's error gives both inner sizes, not which operand holds the points: the name says
    # what is measured (one side has the homogeneous coordinate, the other not), both fixes.
    short, full = sizes
    return Form(measured(f"it looks like homogeneous and plain coordinates meet in a matrix product (inner "
                         f"sizes {short} and {full}): append a coordinate of ones to points of {short}, or use "
                         "the matrix that fits them"), HOMOGENEOUS_MIXED)
