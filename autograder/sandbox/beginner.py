"""The beginner's mistakes in one sentence, before any library trace.

The most common ways a first program goes wrong in these labs are not in the
algorithm: an integer matrix handed to ``cv2.warpAffine``, a float image where
OpenCV wants ``uint8``, pixel coordinates that are floats where ``cv2.circle``
wants whole numbers, an image indexed ``[x, y]`` instead of ``[row, column]``,
``cv2.imshow`` where there is no screen. OpenCV answers with a four-line
assertion (``M0.type() == CV_32F || ...``) that names no variable and no fix.

This module turns those into a sentence naming the function, the argument, what
it got and what to do. It is used in two places:

- in the sandboxed worker, which keeps a copy beside ``worker.py`` and imports
  nothing else of the grader: :func:`watch` wraps every function of ``cv2`` so
  that an error raised inside one carries the sentence (:func:`sentence_of`),
  explained from the arguments actually given; the worker puts it before the
  student's exception in the failure message;
- in the grader's checks, where a returned value is judged
  (:func:`integer_entries`, :func:`channels_reversed`).

Everything here is best effort: a sentence is only given when one fits, and
explaining never raises.
"""

from __future__ import annotations

import re

ATTRIBUTE = "_autograder_sentence"   # set on an exception raised inside a watched function
_FLOATS = ("float32", "float64")
_IMAGE_DTYPES = ("uint8", "uint16", "int16", "float32", "float64")


# ------------------------------------------------------------------ in the worker
def watch(library, prefix: str = "cv2") -> None:
    """Wrap every plain function of ``library`` (``cv2.warpAffine``...) so that an error it
    raises carries a sentence explaining it (:data:`ATTRIBUTE`); results, exceptions and
    behaviour are otherwise unchanged. Classes and their methods are left as they are
    (their errors are still explained from the message alone, see :func:`sentence_of`)."""
    builtin = type(len)
    for name, value in list(vars(library).items()):
        if type(value) is builtin and not name.startswith("_"):
            setattr(library, name, _watched(value, f"{prefix}.{name}"))


def _watched(function, qualified: str):
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except Exception as exc:
            try:
                names = _parameters(getattr(function, "__doc__", "") or "")
                arguments = [(names[i] if i < len(names) else f"argument {i + 1}", a) for i, a in enumerate(args)]
                sentence = explain_opencv(qualified, str(exc), arguments + list(kwargs.items()))
                if sentence:
                    setattr(exc, ATTRIBUTE, sentence)
            except Exception:  # noqa: BLE001 - explaining must never change what the student's code sees
                pass
            raise

    call.__name__ = getattr(function, "__name__", qualified)
    call.__qualname__ = call.__name__
    call.__doc__ = getattr(function, "__doc__", None)
    call.__wrapped__ = function
    return call


def _parameters(doc: str) -> list[str]:
    """``["src", "M", "dsize", ...]`` from an OpenCV docstring's first line,
    ``warpAffine(src, M, dsize[, dst[, flags]]) -> dst``."""
    match = re.match(r"\s*\w+\(([^)]*)\)", doc)
    if not match:
        return []
    return [p.strip() for p in match.group(1).replace("[", "").replace("]", "").split(",") if p.strip()]


def sentence_of(exc: BaseException) -> str:
    """The sentence explaining ``exc`` (or the exception it was raised from or during), or ``""``.
    An OpenCV error raised where no watched function was called (a method such as
    ``StereoBM.compute``) is explained from its message alone."""
    seen = 0
    while exc is not None and seen < 8:
        sentence = getattr(exc, ATTRIBUTE, "")
        if isinstance(sentence, str) and sentence:
            return sentence
        if type(exc).__name__ == "error" and type(exc).__module__.startswith("cv2"):
            return explain_opencv("OpenCV", str(exc), [])
        exc = exc.__cause__ or exc.__context__
        seen += 1
    return ""


# ------------------------------------------------------------------ OpenCV's errors
def explain_opencv(function: str, message: str, arguments: list[tuple[str, object]]) -> str:
    """One sentence for an OpenCV error, or ``""``.

    Parameters
    ----------
    function : str
        ``"cv2.warpAffine"`` (the function called), or ``"OpenCV"`` when unknown.
    message : str
        The error's text.
    arguments : list of (name, value)
        What the function was given, by parameter name (``[("src", image), ("M", M)]``).
    """
    function = _called(function, message)
    values = dict(arguments)
    for rule in (_bad_argument, _no_screen, _wrong_matrix, _wrong_points, _wrong_image, _empty, _odd_kernel,
                 _pyramid_size, _sizes_differ, _point_arrays, _borders, _from_message_alone):
        sentence = rule(function, message, arguments, values)
        if sentence:
            return sentence
    return ""


def _called(function: str, message: str) -> str:
    if function != "OpenCV":
        return function
    found = re.search(r"in function '(?:cv::)?(\w+)'", message)
    return f"OpenCV's {found.group(1)}" if found else "OpenCV"


def _bad_argument(function, message, arguments, values) -> str:
    """Arguments OpenCV could not even read: floats for pixels, a list for an image..."""
    found = re.search(r"Argument '(\w+)' is required to be an integer", message)
    if found:
        name = found.group(1)
        return (f"{function} needs a whole number for {name}; yours is {_shown(values.get(name, '?'))}: "
                f"use int(round({name}))")
    found = re.search(r"Argument '(\w+)' can not be treated as a double", message)
    if found:
        # (cv2.addWeighted's alpha given a mask: one number weighs the whole image alike)
        name = found.group(1)
        value = values.get(name, "?")
        per_pixel = _is_array(value) and value.size > 1
        return (f"{function} needs one number for {name}; yours is {_shown(value)}"
                + (f": {function} applies {name} to every pixel alike, so a weight that changes from pixel to "
                   "pixel is applied with NumPy (multiply the arrays by it)" if per_pixel else ""))
    found = re.search(r"Can't parse '(\w+)'\. (.*)", message)
    if found:
        name, why = found.group(1), found.group(2)
        value = _shown(values[name]) if name in values else "not that"
        if "wrong type" in why and _beyond_c_int(values.get(name)):
            # whole numbers already, too large for OpenCV's int: rounding is not the fix
            return (f"{function} needs {name} as whole numbers within OpenCV's int range (below 2^31 in size); "
                    f"yours is {value}: a point that far away cannot be drawn, clip the end points to the "
                    "image first (cv2.clipLine)")
        given = values.get(name)
        if "wrong type" in why and isinstance(given, (tuple, list)) and any(
                isinstance(item, (tuple, list)) or _is_array(item) for item in given):
            # (an item that is itself a pair -- `dsize if dsize else w, h` makes ((w, h), h) -- is no number
            # to round)
            return (f"{function} needs {name} as {len(given)} numbers; yours is {value}, whose items are not all "
                    f"numbers (a sequence inside the sequence)")
        if "wrong type" in why:
            what = "(width, height)" if name in ("dsize", "size", "ksize") else "pixel coordinates"
            return (f"{function} needs {name} as whole numbers, {what}; yours is {value}: round them, "
                    f"e.g. (int(round(x)), int(round(y)))")
        length = re.search(r"Expected sequence length (\d+), got (\d+)", why)
        if length:
            return f"{function} needs {name} as {length.group(1)} numbers; yours has {length.group(2)} ({value})"
        return f"{function} needs {name} as a tuple of numbers; yours is {value}"
    found = re.search(r"Expected Ptr<cv::UMat> for argument '(\w+)'|(\w+) is not a numpy array", message)
    if found:
        name = found.group(1) or found.group(2)
        value = values.get(name, "?")
        why = (" (did cv2.imread find the file, or a function of yours return nothing?)"
               if value is None else ": np.asarray(...) makes one")
        shown = "None" if value is None else f"a {type(value).__name__}, {_shown(value)}"
        return f"{function} needs a numpy array for {name}; yours is {shown}{why}"
    return ""


def _no_screen(function, message, arguments, values) -> str:
    if "Rebuild the library with" in message or "highgui" in message.lower() and "not implemented" in message:
        return (f"{function} opens a window, and grading runs without a screen: show pictures in your "
                "notebook's demo cells (plt.imshow), not inside a graded function")
    return ""


def _wrong_matrix(function, message, arguments, values) -> str:
    """A transformation matrix of the wrong dtype or shape (``cv2.warpAffine``'s ``M``)."""
    matrices = [(n, v) for n, v in arguments if _is_matrix(v)]
    if not matrices:
        return ""
    typed = re.search(r"M0?\.type\(\) == CV_32F|floating-point|32f or 64f|ktype == CV_32F", message)
    shape = re.search(r"rows == (\d) && M0?\.cols == (\d)", message)
    wanted = tuple(int(n) for n in shape.groups()) if shape else None
    for name, matrix in matrices:
        if typed and str(matrix.dtype) not in _FLOATS:
            return (f"{function} needs {name} as a float32 or float64 matrix; yours is {matrix.dtype}: "
                    f"build it with dtype=float (np.array([[1, 0, tx], ...], dtype=float)) "
                    f"or convert it with {name}.astype(np.float64)")
        if wanted and matrix.shape != wanted:
            fixes = {((2, 3), (3, 3)): f": pass its first two rows, {name}[:2]",
                     ((3, 3), (2, 3)): ": add the row [0, 0, 1], or warp with cv2.warpAffine"}
            return (f"{function} needs {name} of shape {wanted}; yours is {matrix.shape}"
                    + fixes.get((wanted, matrix.shape), ""))
    if "3x3" in message:
        for name, matrix in matrices:
            if matrix.shape != (3, 3) or str(matrix.dtype) not in _FLOATS:
                return f"{function} needs {name} as a 3x3 float matrix; yours is {_shown(matrix)}"
    return ""


def _wrong_points(function, message, arguments, values) -> str:
    """Point arrays: their dtype, their shape, their number."""
    points = [(n, v) for n, v in arguments if _is_points(v)]
    found = re.search(r"checkVector\((\d), CV_32F\) == (\d+)", message)
    if found and points:
        size, count = found.groups()
        for name, value in points:
            if str(value.dtype) != "float32" or len(value.reshape(-1, int(size))) != int(count):
                return (f"{function} needs {name} as exactly {count} points of {size} float32 coordinates, "
                        f"shape ({count}, {size}); yours is {_shown(value)}: np.float32({name})")
    if "scn + 1 == m.cols" in message:
        described = ", ".join(f"{n} {_shown(v)}" for n, v in arguments if _is_array(v))
        return (f"{function} needs points of shape (N, 1, 2) and a 3x3 matrix; yours are {described}: "
                "pass points.reshape(-1, 1, 2)")
    found = re.search(r"'npoints' is (\d+)", message)
    if found and "npoints >= 4" in message:
        return f"{function} needs at least 4 point pairs; yours has {found.group(1)}"
    if "checkVector(2) == dst.checkVector(2)" in message and len(points) >= 2:
        (a, first), (b, second) = points[:2]
        return (f"{function} needs as many points in {b} as in {a}; yours have "
                f"{len(second.reshape(-1, 2)) if second.size % 2 == 0 else '?'} and "
                f"{len(first.reshape(-1, 2)) if first.size % 2 == 0 else '?'}")
    typed = re.search(r"depth\d? == CV_32F|CV_32F \|\| depth", message)
    if typed:
        for name, value in points:
            if str(value.dtype) not in _FLOATS:
                return (f"{function} needs the points in {name} as float32 or float64; yours are {value.dtype}: "
                        f"convert them with {name}.astype(np.float64)")
    return ""


def _wrong_image(function, message, arguments, values) -> str:
    """An image of a dtype or a channel count OpenCV does not take here."""
    images = [(n, v) for n, v in arguments if _is_image(v)]
    if not images:
        return ""
    channels = re.search(r"Bad number of channels|Invalid number of channels|'scn' is (\d)", message)
    if channels:
        name, image = images[0]
        count = 1 if image.ndim == 2 else image.shape[2]
        return (f"{function} cannot convert {name} with {count} channel{'s' * (count != 1)} with this code: "
                "a grey image (H, W) has 1 channel, a BGR image (H, W, 3) has 3 (is it already grey? "
                "is the COLOR_ code the right way round?)")
    if re.search(r"CV_8UC1|8UC1", message):
        for name, image in images:
            if str(image.dtype) != "uint8" or image.ndim != 2:
                # (each conversion only where it is needed: an (H, W) array is grey already -- a mask made
                # float by np.zeros needs only its dtype)
                colour = image.ndim == 3 and image.shape[2] in (3, 4)   # ((H, W, 1): its one channel, x[..., 0])
                steps = (["cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)"] if colour else ["x[..., 0]"] if image.ndim == 3
                         else []) + (
                    ["np.clip(x, 0, 255).astype(np.uint8)" if str(image.dtype) != "bool" else "x.astype(np.uint8)"]
                    if str(image.dtype) != "uint8" else [])
                return (f"{function} needs {name} as a grey uint8 image (H, W); yours is {_shown(image)}: "
                        f"convert it with {' and '.join(steps)}")
    allowed = re.search(r"VDepth = [^;\]]*Set<([\d, ]+)>", message)
    given = re.search(r"'depth' is (\d+)", message)
    if allowed and given:
        # (the depths the call takes, OpenCV's own list -- cv2.cvtColor: 8U, 16U, 32F -- and the one it was given)
        names = {0: "uint8", 1: "int8", 2: "uint16", 3: "int16", 4: "int32", 5: "float32", 6: "float64"}
        takes = [names[int(d)] for d in allowed.group(1).split(",") if int(d) in names]
        # (the array's own dtype: OpenCV reports an int64 array as the 32-bit depth it converted it to)
        odd = [(n, image) for n, image in images if str(image.dtype) not in takes]
        name, wrong = (odd[0][0], str(odd[0][1].dtype)) if odd else (images[0][0], names.get(int(given.group(1)), ""))
        # (a dtype no OpenCV image has -- int64 -- is told by the general sentence below, with its uint8 fix)
        if takes and wrong and wrong in _IMAGE_DTYPES:
            fix = "x.astype(np.float32)" if "float32" in takes else f"x.astype(np.{takes[0]})"
            return (f"{function} takes {name} as {', '.join(takes[:-1]) + ' or ' + takes[-1] if len(takes) > 1 else takes[0]}"
                    f"; yours is {wrong}: convert it with {fix}")
    if re.search(r"type\(\)|depth|CV_\d+[UFS]|format|ifunc|Unsupported|data type", message):
        for name, image in images:
            if str(image.dtype) not in _IMAGE_DTYPES:
                return (f"{function} cannot work on {name}, a {image.dtype} image: OpenCV images are uint8 "
                        "(or float32); convert it with np.clip(x, 0, 255).astype(np.uint8) "
                        "or x.astype(np.float32)")
    return ""


def _empty(function, message, arguments, values) -> str:
    if not re.search(r"empty\(\)|cols > 0|rows > 0|area\(\) > 0|inv_scale_x > 0|width ?> ?0", message):
        return ""
    for name, value in arguments:
        if value is None and name in ("src", "img", "image", "src1", "src2", "left", "right"):
            return (f"{function} got None for {name}: no image (did cv2.imread find the file, "
                    "or a function of yours return nothing?)")
        if _is_array(value) and value.size == 0:
            return f"{function} got an empty {name} (shape {value.shape})"
    if "dsize" in values:
        return (f"{function} needs dsize as (width, height), both above 0; yours is {_shown(values['dsize'])}"
                + (" (for a scale, pass dsize=None with fx= and fy=)" if "resize" in function else ""))
    return ""


def _odd_kernel(function, message, arguments, values) -> str:
    if re.search(r"ksize\.width % 2 == 1|ksize % 2 == 1", message):
        return f"{function} needs an odd, positive kernel size; yours is {_shown(values.get('ksize', '?'))}"
    return ""


def _pyramid_size(function, message, arguments, values) -> str:
    """cv2.pyrUp doubles its image, cv2.pyrDown halves it: a ``dstsize`` (width, height) not within a pixel
    of that size (the other level's shape, or a shape's (rows, columns) order)."""
    up = "pyrUp" in function or "'pyrUp_'" in message
    if not (up or "pyrDown" in function or "'pyrDown_'" in message) or not re.search(r"dsize\.width", message):
        return ""
    source, size = values.get("src"), values.get("dstsize")
    if not (_is_image(source) and isinstance(size, (tuple, list)) and len(size) == 2):
        return ""
    height, width = source.shape[:2]
    made = (2 * width, 2 * height) if up else ((width + 1) // 2, (height + 1) // 2)
    fits = (lambda w, h: abs(w - made[0]) <= 1 and abs(h - made[1]) <= 1)
    said = (f"{function} {'doubles' if up else 'halves'} its image: src of shape {tuple(source.shape[:2])} gives a "
            f"dstsize (width, height) within a pixel of {made}; yours is {_shown(tuple(size))}")
    if fits(size[1], size[0]):
        return said + ", width and height in the other order (dstsize is (width, height), a shape (rows, columns))"
    if tuple(size) == (width, height):
        # (the src given is as large as the level it is to make: the size asked is right where the src is a level
        # never halved -- a Gaussian level kept as it was --, or the size is that of src's own level)
        return said + (", the size of src itself: either src is a level too large (a pyramid level that was never "
                       "halved by cv2.pyrDown) or the dstsize is src's own level's")
    return said


def _sizes_differ(function, message, arguments, values) -> str:
    """Two arrays an operation combines element by element, of different shapes (or channel counts)."""
    if "Sizes of input arguments do not match" not in message:
        return ""
    arrays = [(n, v) for n, v in arguments if _is_array(v) and v.ndim >= 2]
    if len(arrays) >= 2 and len({v.shape for _, v in arrays}) > 1:
        given = "; ".join(f"{n} {_shown(v)}" for n, v in arrays)
        return f"{function} needs its arrays of the same shape (size and channels); yours are {given}"
    if "All the images must have the same size" in message:
        return f"{function} needs the left and right images of the same size"
    return ""


# a function's point array and the coordinates each point has, where OpenCV reads "npoints" from it
_POINTS_READ = {"projectPoints": ("objectPoints", 3), "undistortPoints": ("src", 2), "solvePnP": ("imagePoints", 2),
                "calibrateCamera": ("objectPoints", 3)}


def _point_arrays(function, message, arguments, values) -> str:
    """Point arrays OpenCV could not read as points: a wrong number of coordinates, too few points, a
    single view where a list of views belongs (cv2.calibrateCamera)."""
    name = function.rpartition(".")[2]
    if name == "calibrateCamera" and re.search(r"number of points in the view #\d+ is < 4", message):
        given = values.get("objectPoints")
        if _is_array(given):
            return (f"{function} takes a list of views, one array of points for each, and reads a view of fewer "
                    f"than 4 points; yours is one array, objectPoints {_shown(given)}: a single view is the list "
                    "[objectPoints] (and [imagePoints])")
        return f"{function} needs at least 4 points in every view"
    if name == "solvePnP" and "npoints >= 4" in message:
        world, image = values.get("objectPoints"), values.get("imagePoints")
        if _is_array(world) and _is_array(image):
            return (f"{function} needs at least 4 object points and as many image points of 2 coordinates; yours "
                    f"are objectPoints {_shown(world)} and imagePoints {_shown(image)}")
    if name in _POINTS_READ and re.search(r"npoints >= 0", message):
        parameter, size = _POINTS_READ[name]
        given = values.get(parameter)
        if _is_array(given) and given.shape[-1] != size:
            return (f"{function} needs {parameter} as N points of {size} coordinates, shape (N, {size}) or "
                    f"(N, 1, {size}); yours is {_shown(given)}")
    found = re.search(r"'requested_size' is \[(\d+) x (\d+)\].*'sz' is \[(\d+) x (\d+)\]", message, re.S)
    if found:   # an output sized from one input: OpenCV gives [columns x rows]
        given = (int(found.group(2)), int(found.group(1)))
        wanted = (int(found.group(4)), int(found.group(3)))
        named = [n for n, v in arguments if _is_matrix(v) and v.shape == given]
        if named:
            return f"{function} needs {named[0]} of shape {wanted}; yours is {given}"
    return ""


def _borders(function, message, arguments, values) -> str:
    if "top >= 0 && bottom >= 0" not in message:
        return ""
    given = ", ".join(f"{n}={_scalar(values[n])}" for n in ("top", "bottom", "left", "right") if n in values)
    return f"{function} needs borders of 0 pixels or more" + (f"; yours are {given}" if given else "")


def _from_message_alone(function, message, arguments, values) -> str:
    """What the message says when the arguments are unknown (an OpenCV method's error)."""
    if "SADWindowSize must be odd" in message:
        return (f"{function} needs StereoBM's blockSize odd, within 5..255 and no larger than the images "
                "(StereoBM_create(numDisparities, blockSize))")
    found = re.search(r"(\w+)\.(rows|cols) == (\d) && \1\.(rows|cols) == (\d)", message)
    if found:
        rows = found.group(3) if found.group(2) == "rows" else found.group(5)
        cols = found.group(5) if found.group(2) == "rows" else found.group(3)
        given = values.get(found.group(1))
        return (f"{function} needs {found.group(1)} of shape ({rows}, {cols})"
                + (f"; yours is {_shown(given)}" if _is_array(given) else ""))
    if re.search(r"type == src2\.type\(\) && src1\.cols == src2\.cols", message):
        return (f"{function} compares descriptors of one type and length: the two sets differ in their dtype or "
                "their number of columns (made by two different detectors, or converted one only?)")
    if re.search(r"ksize\.width > 0 && ksize\.height > 0", message):
        return f"{function} needs a kernel size of at least 1 in both directions" + (
            f"; yours is {_shown(values['ksize'])}" if "ksize" in values else "")
    if re.search(r"CV_8UC1|8UC1", message):
        return (f"{function} needs grey uint8 images, shape (H, W): convert with "
                "cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) and np.clip(x, 0, 255).astype(np.uint8)")
    if re.search(r"type\(\) == CV_32F \|\| \w+\.type\(\) == CV_64F", message):
        return f"{function} needs a float32 or float64 matrix: build it with dtype=float"
    return ""


# ------------------------------------------------------------------ (x, y) vs (row, column)
# The parts of these sentences that say what to write are held to the student's code in the grader
# (autograder.engine.forms guards them: code that already indexes [y, x], or converts to float, is
# told something else); the rest describes the value measured.
INDEX_AS_Y_X = "index it as image[y, x]"
BUILD_AS_FLOAT = "Build it with dtype=float."
CONVERT_FIRST = "convert first, x.astype(np.float64)"


def explain_index_error(message: str, arguments: list) -> str:
    """``image[x, y]`` for ``image[y, x]``: an IndexError whose index fits the other axis of
    an image the function was given. ``arguments``: the call's values."""
    found = re.search(r"index (-?\d+) is out of bounds for axis ([01]) with size (\d+)", message)
    if not found:
        return ""
    index, axis, size = (int(g) for g in found.groups())
    for image in arguments:
        if _is_image(image) and image.shape[axis] == size and abs(index) < image.shape[1 - axis]:
            return (f"an image is indexed [row, column], that is [y, x]: index {index} fits its "
                    f"{'width' if axis == 0 else 'height'} ({image.shape[1 - axis]}) but not its "
                    f"{'height' if axis == 0 else 'width'} ({size}); " + INDEX_AS_Y_X)
    return ""


# ------------------------------------------------------------------ returned values (in the grader)
def integer_entries(got, expected) -> str:
    """A sentence when an integer array stands where the answer has fractions (the fractions were
    cut off: ``M = np.eye(3, dtype=int)`` then ``M[:2, :2] = R``), else ``""``."""
    import numpy as np

    if not isinstance(got, np.ndarray) or got.dtype.kind not in "iub":
        return ""
    expected = np.asarray(expected, dtype=np.float64)
    if got.shape != expected.shape or np.allclose(expected, np.round(expected)):
        return ""
    return (f"it holds integers ({got.dtype}), where the answer has fractions: an array made of whole "
            "numbers (np.array([[1, 0, 0], ...]), np.eye(3, dtype=int)) is an integer array, and the "
            "fractions written into it are cut off. " + BUILD_AS_FLOAT)


def uint8_wraps(got) -> str:
    """A hint for a uint8 array where floats are expected (its arithmetic wraps around)."""
    return ("uint8 arithmetic wraps around at 256 and cuts off fractions: " + CONVERT_FIRST) if getattr(getattr(got, "dtype", None), "name", "") == "uint8" else ""


def channels_reversed(got, expected) -> bool:
    """Whether a colour image ``got`` is ``expected`` with its channels reversed (RGB for BGR)."""
    import numpy as np

    if not (isinstance(got, np.ndarray) and isinstance(expected, np.ndarray)) or got.shape != expected.shape:
        return False
    if got.ndim != 3 or got.shape[2] != 3:
        return False
    if np.array_equal(expected[..., 0], expected[..., 2]):
        return False  # a grey picture: reversing changes nothing
    close = lambda a, b: float(np.mean(np.abs(a.astype(np.float64) - b.astype(np.float64))))  # noqa: E731
    return close(got[..., ::-1], expected) < min(3.0, 0.25 * close(got, expected))


RGB_ONLY_TO_SHOW = "convert to RGB only to show a picture with Matplotlib, never in what a function returns"
RGB_FOR_BGR = "the colour channels are reversed (RGB for BGR): OpenCV images are BGR; " + RGB_ONLY_TO_SHOW


# ------------------------------------------------------------------ describing values
def _is_array(value) -> bool:
    return type(value).__name__ == "ndarray" and hasattr(value, "dtype")


def _is_matrix(value) -> bool:
    return _is_array(value) and value.ndim == 2 and max(value.shape) <= 4 and min(value.shape) >= 2


def _is_points(value) -> bool:
    """(N, 2), (N, 3), (N, 1, 2), or (2, N), (3, N): a (4, 2) array may be points or a matrix."""
    return _is_array(value) and (
        (value.ndim == 2 and (value.shape[1] in (2, 3) or value.shape[0] in (2, 3)))
        or (value.ndim == 3 and value.shape[1:] == (1, 2)))


def _is_image(value) -> bool:
    return _is_array(value) and value.ndim in (2, 3) and min(value.shape[:2]) > 4 \
        and (value.ndim == 2 or value.shape[2] <= 4)


def _beyond_c_int(value) -> bool:
    """Whether ``value`` is a sequence of integers, one of them outside C's 32-bit int."""
    if not isinstance(value, (list, tuple)) or not value:
        return False
    whole = all(isinstance(v, int) and not isinstance(v, bool) or type(v).__name__.startswith(("int", "uint"))
                for v in value)
    return whole and any(abs(int(v)) >= 2 ** 31 for v in value)


def _shown(value) -> str:
    """What a value is, in a few words: ``an int64 array of shape (3, 3)``, ``(1.5, 2.0)``, ``None``."""
    if _is_array(value):
        return f"a {value.dtype} array of shape {tuple(value.shape)}"
    if value is None:
        return "None"
    if isinstance(value, (list, tuple)):
        inner = ", ".join(_scalar(v) for v in value[:6]) + (", ..." if len(value) > 6 else "")
        return f"[{inner}]" if isinstance(value, list) else f"({inner}{',' * (len(value) == 1)})"
    if isinstance(value, (int, float, bool, str)) or type(value).__module__ == "numpy":
        return f"{_scalar(value)} ({type(value).__name__})"
    return f"a {type(value).__name__}"


def _scalar(value) -> str:
    if isinstance(value, float) or type(value).__name__.startswith("float"):
        number = float(value)
        return f"{number:.1f}" if number.is_integer() and abs(number) < 1e15 else f"{number:g}"
    text = str(value) if type(value).__module__ == "numpy" else repr(value)
    return text if len(text) <= 40 else text[:39] + "…"
