"""OpenCV calls whose behaviour differs between majors 4 and 5, read in the student's code.

Course code written for OpenCV 4 may rely on what OpenCV 4 does, and be right there: a
1-D NumPy array is a column (N x 1) to OpenCV 4, a row (1 x N, or 1-D) to OpenCV 5, so
``cv2.minMaxLoc(costs)[2][1]`` is the index of the smallest cost under 4 and always 0 under
5. Such code then fails checks whose diagnosis ("the cost argument is ignored") would be a
false statement about the student's code. :data:`KNOWN` lists the differences measured (each
with a demonstration, ``tests/test_opencv_versions.py`` runs it under the installed OpenCV
and compares with what each major gives); :func:`version_note` names those the checked
functions' code reaches (read with :mod:`ast`, never run), in a sentence that is true
whatever the arrays are: "if that array is one-dimensional, ...".
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .hints import Predicate, code_of
from ..loading.parsing import walk

LOCATION_INDICES = (2, 3)   # minMaxLoc returns (minVal, maxVal, minLoc, maxLoc)


def _name(func) -> str:
    return func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""


def _is_minmaxloc(node) -> bool:
    """A call of ``minMaxLoc``, unless on what is surely 2-D (``cv2.matchTemplate``'s result)."""
    if not (isinstance(node, ast.Call) and _name(node.func) == "minMaxLoc"):
        return False
    first = node.args[0] if node.args else None
    return not (isinstance(first, ast.Call) and _name(first.func) == "matchTemplate")


def _index(node) -> int | None:
    return node.value if isinstance(node, ast.Constant) and isinstance(node.value, int) else None


def _reads_minmaxloc_location(function) -> bool:
    """``cv2.minMaxLoc(x)[2]``, ``_, _, loc, _ = cv2.minMaxLoc(x)`` (a location bound to a
    name other than ``_``), or ``r = cv2.minMaxLoc(x)`` and then ``r[3]``."""
    bound = set()
    for node in walk(function):
        if isinstance(node, ast.Subscript) and _is_minmaxloc(node.value) \
                and _index(node.slice) in LOCATION_INDICES:
            return True
        if isinstance(node, ast.Assign) and _is_minmaxloc(node.value):
            for target in node.targets:
                if isinstance(target, (ast.Tuple, ast.List)) and len(target.elts) == 4 and any(
                        not (isinstance(t, ast.Name) and t.id.startswith("_")) for t in target.elts[2:]):
                    return True
                if isinstance(target, ast.Name):
                    bound.add(target.id)
    return any(isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in bound
               and _index(node.slice) in LOCATION_INDICES for node in walk(function))


@dataclass(frozen=True)
class VersionDifference:
    """One measured difference: the code that depends on it (``reads``), what to tell the
    student (``says``, completed with the OpenCV that graded), and a demonstration whose
    value under each major is ``under`` (``{"4": ..., "5": ...}``)."""

    name: str
    reads: Predicate
    says: str
    demonstrate: Callable[[], object]
    under: dict


def _opencv_call(name: str, passing: str | None = None) -> Predicate:
    """A call of OpenCV's ``name`` itself (``cv2.solve``, or ``cv.solve`` after ``import cv2 as
    cv``), passing the keyword ``passing`` when given: never another library's function of the
    same name (``np.linalg.solve``), about which a note on OpenCV's versions would be false."""
    def test(function) -> bool:
        return any(isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == name
                   and isinstance(node.func.value, ast.Name) and node.func.value.id in ("cv2", "cv")
                   and (passing is None or any(k.arg == passing for k in node.keywords))
                   for node in walk(function))
    return Predicate(f"calls cv2.{name}" + (f" with {passing}=" if passing else ""), test)


_ROW = np.array([3.0, 1.0, 2.0, 5.0])   # a 1-D array: a column to OpenCV 4, a row to OpenCV 5

# Left out, measured too: cv2.flip, filters (blur, Sobel, filter2D), normalize, threshold and
# inRange on a 1-D array also read it as a column under 4 and a row under 5, but students call
# them on images, where a note would only be noise.
KNOWN = (
    VersionDifference(
        "minMaxLoc's location on a 1-D array",
        Predicate("reads the location cv2.minMaxLoc returns", _reads_minmaxloc_location),
        "your code reads cv2.minMaxLoc's location; on a one-dimensional array it is (0, i) under "
        "OpenCV 4 (a column) and (i, 0) under OpenCV 5 (a row)",
        lambda: __import__("cv2").minMaxLoc(_ROW)[2], {"4": (0, 1), "5": (1, 0)}),
    VersionDifference(
        "cv2.sortIdx on a 1-D array",
        _opencv_call("sortIdx"),
        "your code calls cv2.sortIdx; a one-dimensional array is a column to OpenCV 4 and a row to "
        "OpenCV 5, where SORT_EVERY_COLUMN sorts nothing",
        lambda: __import__("cv2").sortIdx(_ROW, __import__("cv2").SORT_EVERY_COLUMN).ravel().tolist(),
        {"4": [1, 2, 0, 3], "5": [0, 0, 0, 0]}),
    VersionDifference(
        "cv2.undistortPoints' termination criteria",
        _opencv_call("undistortPointsIter") | _opencv_call("undistortPoints", passing="criteria"),
        "your code gives cv2.undistortPoints termination criteria: OpenCV 4 takes them in "
        "cv2.undistortPointsIter only, OpenCV 5 as undistortPoints(..., criteria=...) and has no "
        "undistortPointsIter",
        lambda: hasattr(__import__("cv2"), "undistortPointsIter"), {"4": True, "5": False}),
    VersionDifference(
        "cv2.solve / cv2.gemm with a 1-D vector",
        _opencv_call("solve") | _opencv_call("gemm"),
        "your code calls cv2.solve or cv2.gemm; if one of the arrays it gives them is one-dimensional, "
        "OpenCV 4 reads it as a column and OpenCV 5 as a row, which it refuses (an (N, 1) column is read "
        "alike by both)",
        lambda: _outcome(lambda: __import__("cv2").solve(np.eye(2), np.array([1.0, 2.0]))[1].ravel().tolist()),
        {"4": [1.0, 2.0], "5": "error"}),
)


def _outcome(call):
    """``call()``'s value, or ``"error"`` where OpenCV refuses it."""
    import cv2

    try:
        return call()
    except cv2.error:
        return "error"


def differences_in(functions) -> list[VersionDifference]:
    """The known differences the code of ``functions`` (``ast`` function nodes) depends on. Each
    difference's reading holds of the functions together when it holds of one of them (a call
    made, a value read), so what each function depends on is read once and kept on its node
    (a read tree is never changed; every failed check of a grading asks again)."""
    found = set()
    for function in functions:
        depends = getattr(function, "_version_differences", None)
        if depends is None:
            depends = function._version_differences = frozenset(
                number for number, difference in enumerate(KNOWN) if difference.reads.holds([function]))
        found |= depends
    return [difference for number, difference in enumerate(KNOWN) if number in found]


def version_note(t) -> str:
    """A sentence naming each version difference the code of the functions the check ``t``
    calls (and their helpers in the module) depends on, ending with the OpenCV this course
    grades with; ``""`` when none (or no code to read)."""
    import cv2

    from .stubs import functions_called

    found = differences_in(code_of(t).reachable(functions_called(t.check)))
    if not found:
        return ""
    return "; ".join(d.says for d in found) + f"; this course grades with OpenCV {cv2.__version__}."


def with_version_note(verdict, t):
    """``verdict`` (a failed one) with :func:`version_note` after its message. A named cause
    (``mistake``) stays: checks name one only when it is shown by the outputs themselves
    (lab12's "cost argument is ignored" needs two informative maps, not two maps of zeros)."""
    from dataclasses import replace

    try:
        note = version_note(t)
    except Exception:   # noqa: BLE001 - a note is a bonus: the verdict stands without it
        return verdict
    if not note:
        return verdict
    message = str(verdict.message).rstrip()
    return replace(verdict, message=f"{message} Note: {note}" if message else f"Note: {note}")
