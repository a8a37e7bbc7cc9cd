"""OpenCV's multiple outputs, in the order OpenCV returns them, and code that unpacks them.

``rms, dist, K, rvecs, tvecs = cv2.calibrateCamera(...)`` runs, and ``K`` then holds the
distortion coefficients: the check sees a (1, 5) "K" and can only say its shape is wrong
(issue 35). What the student meant is in the names they chose: a name that reads as one of the
call's outputs, placed at another output's position, is said to be out of order -- a fact of
the code, read with :mod:`ast` (never run). A name that reads as none of them (``a``, ``out``)
or as two of them says nothing, and nothing is said of it.

The same table tells how many values a call returns, for "too many values to unpack" on a line
unpacking it (:mod:`autograder.engine.raised`).
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass

from .hints import _own_nodes, _path
from ..loading.parsing import walk

# What a name reads as: a quantity, and for a stereo pair's outputs a side (1 or 2).
_KINDS = {
    "rms": r"ret|retval|rval|rms|rmse|err|error|reproj\w*|rep_?err\w*|mean_?error|re|reprojection_?error|calib_?error",
    "ok": r"ret|retval|rval|ok|success|found|flag|is_?found|pattern_?found",
    "count": r"ret|retval|rval|n|count|inliers|num_?inliers|n_?inliers|inlier_?count|good|n_?good|points_?in_?front",
    "K": r"k|mtx|camera_?matrix|cam_?matrix|cam_?mtx|cameramatrix|intrinsics?|matrix|k_?mat|kmatrix|k_?matrix|"
         r"intrinsic_?matrix|new_?k|new_?camera_?matrix",
    "dist": r"dist|dists|distortion|dist_?coeffs?|distcoeffs?|dist_?coefs?|coeffs|distortion_?coeffs?|d|dc|kc",
    "rvecs": r"rvecs|r_?vecs|rotations|rot_?vecs|rotation_?vectors|rvec_?list",
    "tvecs": r"tvecs|t_?vecs|translations|trans_?vecs|translation_?vectors|tvec_?list",
    "rvec": r"rvec|r_?vec|rotation_?vector|rot_?vec|rodrigues",
    "tvec": r"tvec|t_?vec|translation_?vector|trans_?vec",
    "R": r"r|rot|rotation|r_?mat|rmat|rotation_?matrix|rot_?mat|rect|r_?rect|rectify",
    "t": r"t|trans|translation|c|centre|center|camera_?centre|camera_?center",
    "P": r"p|proj|projection|p_?mat|proj_?mat|projection_?matrix|p_?new|new_?p",
    "Q": r"q|disparity_?to_?depth|reproject_?matrix",
    "roi": r"roi|valid_?roi|validpixroi|valid_?pix_?roi",
    "H": r"h|homography|hom|h_?mat",
    "F": r"f|fundamental|f_?mat",
    "E": r"e|essential|e_?mat",
    "mask": r"mask|inlier_?mask|inliers_?mask|status|inliers|is_?inlier|ransac_?mask|mask_?inliers",
    "jacobian": r"j|jac|jacobian|jacob",
    "corners": r"corners|pts|points|image_?points|img_?points|corner_?points",
    "contours": r"contours|cnts|contour_?list",
    "hierarchy": r"hierarchy|hier",
    "keypoints": r"kp|kps|keypoints|key_?points|kpts",
    "descriptors": r"des|desc|descs|descriptors|descriptor|features",
    "singular": r"w|s|sigma|sv|singular(?:_?values)?|d",
    "U": r"u|u_?mat|left",
    "Vt": r"vt|v_?t|vh|v",
}
_PATTERNS = {kind: re.compile(f"^(?:{pattern})$") for kind, pattern in _KINDS.items()}
_SIDE = re.compile(r"^(.+?)_?(1|2|left|right)$")
_SIDES = {"1": 1, "left": 1, "2": 2, "right": 2}
_UPPER = frozenset("rpqhfek")   # single letters that name a matrix only written upper case


@dataclass(frozen=True)
class Output:
    kind: str        # what a name reads as (see _KINDS)
    words: str       # what it is, in a sentence
    short: str       # how it is written in the order ("K")
    side: int = 0    # camera/image 1 or 2 of a stereo pair, 0 for none


def _o(kind, words, short=None, side=0):
    return Output(kind, words, short or kind, side)


# The documented order of each OpenCV function's outputs (the Python bindings' tuple).
ORDER = {
    "calibrateCamera": (_o("rms", "the RMS reprojection error"), _o("K", "the camera matrix"),
                        _o("dist", "the distortion coefficients"), _o("rvecs", "the views' rotation vectors"),
                        _o("tvecs", "the views' translation vectors")),
    "stereoCalibrate": (_o("rms", "the RMS reprojection error"), _o("K", "camera 1's matrix", "K1", 1),
                        _o("dist", "camera 1's distortion coefficients", "dist1", 1),
                        _o("K", "camera 2's matrix", "K2", 2),
                        _o("dist", "camera 2's distortion coefficients", "dist2", 2),
                        _o("R", "the rotation between the cameras"), _o("t", "the translation between them", "T"),
                        _o("E", "the essential matrix"), _o("F", "the fundamental matrix")),
    "stereoRectify": (_o("R", "image 1's rectifying rotation", "R1", 1),
                      _o("R", "image 2's rectifying rotation", "R2", 2),
                      _o("P", "image 1's new projection matrix", "P1", 1),
                      _o("P", "image 2's new projection matrix", "P2", 2),
                      _o("Q", "the disparity-to-depth matrix"), _o("roi", "image 1's valid region", "roi1", 1),
                      _o("roi", "image 2's valid region", "roi2", 2)),
    "findHomography": (_o("H", "the homography"), _o("mask", "the inlier mask")),
    "findFundamentalMat": (_o("F", "the fundamental matrix"), _o("mask", "the inlier mask")),
    "findEssentialMat": (_o("E", "the essential matrix"), _o("mask", "the inlier mask")),
    "recoverPose": (_o("count", "the number of inliers in front of both cameras", "retval"),
                    _o("R", "the rotation"), _o("t", "the translation"), _o("mask", "the inlier mask")),
    "decomposeEssentialMat": (_o("R", "the first possible rotation", "R1", 1),
                              _o("R", "the second possible rotation", "R2", 2), _o("t", "the translation")),
    "decomposeProjectionMatrix": (_o("K", "the camera matrix"), _o("R", "the rotation"),
                                  _o("t", "the camera centre (homogeneous, 4 values)", "C"),
                                  _o("Rx", "the rotation about x", "Rx"), _o("Ry", "the rotation about y", "Ry"),
                                  _o("Rz", "the rotation about z", "Rz"), _o("euler", "the Euler angles", "euler")),
    "solvePnP": (_o("ok", "whether it succeeded", "retval"), _o("rvec", "the rotation vector"),
                 _o("tvec", "the translation vector")),
    "solvePnPRansac": (_o("ok", "whether it succeeded", "retval"), _o("rvec", "the rotation vector"),
                       _o("tvec", "the translation vector"), _o("mask", "the inliers' indices", "inliers")),
    "Rodrigues": (_o("R", "the converted rotation (a matrix for a vector, a vector for a matrix)", "dst"),
                  _o("jacobian", "the Jacobian")),
    "findChessboardCorners": (_o("ok", "whether the pattern was found", "retval"), _o("corners", "the corners")),
    "findContours": (_o("contours", "the contours"), _o("hierarchy", "their hierarchy")),
    "projectPoints": (_o("corners", "the projected points", "imagePoints"), _o("jacobian", "the Jacobian")),
    "detectAndCompute": (_o("keypoints", "the keypoints"), _o("descriptors", "the descriptors")),
    # (OpenCV's SVD answers the singular values first, where np.linalg.svd answers U first)
    "SVDecomp": (_o("singular", "the singular values", "w"), _o("U", "the left singular vectors", "u"),
                 _o("Vt", "the right singular vectors, transposed", "vt")),
}
# Calls whose count of outputs is the same in every OpenCV version the labs meet and every overload
# (recoverPose has a 5-output overload; findContours returned 3 before OpenCV 4).
COUNTS = {name: len(order) for name, order in ORDER.items() if name not in ("recoverPose",)}
COUNTS.update({"findContours": 2, "threshold": 2, "getOptimalNewCameraMatrix": 2, "estimateAffine2D": 2,
               "estimateAffinePartial2D": 2, "calcOpticalFlowPyrLK": 3, "initUndistortRectifyMap": 2,
               "RQDecomp3x3": 6, "decomposeHomographyMat": 4, "connectedComponentsWithStats": 4,
               "minMaxLoc": 4, "cartToPolar": 2, "polarToCart": 2})
NAMES = {"findContours": "contours, hierarchy", "threshold": "retval, dst",
         "getOptimalNewCameraMatrix": "newK, roi", "estimateAffine2D": "A, inliers",
         "estimateAffinePartial2D": "A, inliers", "calcOpticalFlowPyrLK": "next_points, status, err",
         "initUndistortRectifyMap": "map1, map2", "RQDecomp3x3": "angles, R, Q, Qx, Qy, Qz",
         "decomposeHomographyMat": "retval, rotations, translations, normals",
         "connectedComponentsWithStats": "retval, labels, stats, centroids",
         "minMaxLoc": "min_value, max_value, min_location, max_location", "cartToPolar": "magnitude, angle",
         "polarToCart": "x, y"}
# methods (detector.detectAndCompute) are read by their name alone; the rest must be cv2's
_METHODS = frozenset({"detectAndCompute"})
MISTAKE = "OpenCV's outputs unpacked out of order"
_ORDINALS = ("1st", "2nd", "3rd", "4th", "5th", "6th", "7th", "8th", "9th")


def shown(function: str) -> str:
    """How a call is written: ``cv2.calibrateCamera``, a method as ``.detectAndCompute``."""
    return f".{function}" if function in _METHODS else f"cv2.{function}"


def order_text(function: str) -> str:
    """``rms, K, dist, rvecs, tvecs`` for cv2.calibrateCamera."""
    order = ORDER.get(function)
    return ", ".join(o.short for o in order) if order else NAMES.get(function, "")


def opencv_called(node, function=None) -> str:
    """``calibrateCamera`` for a call of ``cv2.calibrateCamera`` (under any alias, or imported from
    cv2, as ``function``'s module reads), or of a method named in :data:`_METHODS`; ``""`` otherwise."""
    if not isinstance(node, ast.Call):
        return ""
    from .hints import _resolved, _scope

    head, _, last = _path(node.func).rpartition(".")
    if last in _METHODS and isinstance(node.func, ast.Attribute):
        return last
    if function is None:
        return last if head in ("cv2", "cv") else ""
    kind, resolved = _resolved(node.func, _scope(function))
    return resolved.rpartition(".")[2] if kind == "module" and resolved.split(".")[0] == "cv2" else ""


def reads_as(name: str, order: tuple) -> list[int]:
    """The positions in ``order`` whose output the variable ``name`` reads as (``K`` -> the camera
    matrix's; ``R1`` -> image 1's rotation's; ``R`` -> both rotations' of a stereo pair)."""
    lowered = name.lower().strip("_")
    if not lowered:
        return []
    side, base = 0, lowered
    found = _SIDE.match(lowered)
    if found and found.group(1):
        side, base = _SIDES[found.group(2)], found.group(1)
    if base in _UPPER and (name.strip("_")[:1]).islower():
        return []   # a lone r, p, k...: not the matrices' R, P, K (an ROI's r1, a point's p)
    positions = []
    for position, output in enumerate(order):
        pattern = _PATTERNS.get(output.kind)
        plain = pattern is not None and pattern.match(lowered)
        sided = pattern is not None and side and pattern.match(base) and output.side in (0, side)
        if plain and not (side and output.side and output.side != side) or sided:
            positions.append(position)
    return positions


@dataclass(frozen=True)
class Misread:
    """One variable of an unpack holding another output than its name says."""
    function: str       # cv2's function ("calibrateCamera")
    line: int
    targets: str        # "rms, dist, K, rvecs, tvecs" as written
    name: str           # the variable ("K")
    position: int       # where it sits (its output's index)
    meant: int          # where the output its name reads as sits
    owner: str          # the student's function that unpacks

    def sentence(self, others: list["Misread"] = ()) -> str:
        order = ORDER[self.function]
        held = order[self.position]
        text = (f"{shown(self.function)} returns ({order_text(self.function)}) in that order, and your `{self.owner}` "
                f"unpacks it as `{self.targets}` (line {self.line}): your `{self.name}` takes its "
                f"{_ORDINALS[self.position]} output, {held.words}"
                f"{'' if held.short in held.words else f' ({held.short})'}, not {order[self.meant].words}")
        more = [o for o in others if o.name != self.name and o.line == self.line][:1]
        for other in more:
            text += (f", and your `{other.name}` its {_ORDINALS[other.position]}, "
                     f"{order[other.position].words}")
        return text


def misread(function) -> list[Misread]:
    """The variables of ``function``'s unpacks of OpenCV calls that hold another output than their
    names read as: each name reading as one output only, of another position, while another name of
    the unpack reads as the output it holds, or the output it reads as is thrown away (``_``)."""
    found = []
    for node in _own_nodes(function):
        if not isinstance(node, ast.Assign) or len(node.targets) != 1 \
                or not isinstance(node.targets[0], (ast.Tuple, ast.List)):
            continue
        value, first, last = _sliced(node.value)
        called = opencv_called(value, function)
        order = ORDER.get(called)
        elements = node.targets[0].elts
        if not order:
            continue
        last = len(order) if last is None else min(last, len(order))
        positions = _positions(elements, last - first)
        if positions is None:
            continue
        positions = [p + first if p >= 0 else p for p in positions]
        targets = ", ".join(ast.unparse(e) for e in elements)
        # each target's position and the one output its name reads as (None: none, or several)
        read = [(position, element.id, _one(reads_as(element.id, order)))
                for position, element in zip(positions, elements) if position >= 0 and isinstance(element, ast.Name)]
        claimed = {meant for _, _, meant in read if meant is not None}
        discarded = {position for position, name, _ in read if not name.strip("_")}
        for position, name, meant in read:
            # out of order: its name reads as another output, and another name reads as the one it holds,
            # or the place of the one it reads as is thrown away (``_, R = cv2.Rodrigues(rvec)``); ``a, b,
            # c, d, e``'s d reads as the distortion, but nothing there says c is not it
            if meant is not None and meant != position and (position in claimed or meant in discarded):
                found.append(Misread(called, node.lineno, targets, name, position, meant, function.name))
    return found


def _one(positions: list[int]) -> int | None:
    return positions[0] if len(positions) == 1 else None


def _sliced(value) -> tuple[ast.AST, int, int | None]:
    """``(call, first, end)`` for ``call(...)[first:end]`` (``cv2.stereoRectify(...)[:4]``: 0, 4), and
    ``(value, 0, None)`` for anything else."""
    if isinstance(value, ast.Subscript) and isinstance(value.slice, ast.Slice) and value.slice.step is None:
        bounds = [value.slice.lower, value.slice.upper]
        if all(b is None or isinstance(b, ast.Constant) and type(b.value) is int and b.value >= 0 for b in bounds):
            lower, upper = (b.value if b is not None else None for b in bounds)
            return value.value, lower or 0, upper
    return value, 0, None


def _positions(elements, count: int) -> list[int] | None:
    """The output each target of an unpack of ``count`` outputs takes (``R1, R2, *_``: 0, 1, and the
    starred rest after them); None when they cannot all be given one."""
    starred = [i for i, e in enumerate(elements) if isinstance(e, ast.Starred)]
    if not starred:
        return list(range(count)) if len(elements) == count else None
    if len(starred) > 1 or len(elements) - 1 > count:
        return None
    split = starred[0]
    after = len(elements) - split - 1
    return list(range(split)) + [-1] + list(range(count - after, count))


def _names_read(node) -> set[str]:
    return {n.id for n in walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}


def feeding(function, expression, steps: int = 4) -> set[str]:
    """The names ``expression`` reads in ``function``, and those their assignments read, ``steps`` deep."""
    assigned = {}
    for node in _own_nodes(function):
        if isinstance(node, ast.Assign):
            for target in node.targets:
                for name in (n.id for n in walk(target) if isinstance(n, ast.Name)):
                    assigned.setdefault(name, []).append(node.value)
        elif isinstance(node, (ast.AugAssign, ast.AnnAssign)) and isinstance(node.target, ast.Name) and node.value:
            assigned.setdefault(node.target.id, []).append(node.value)
    names, frontier = set(), _names_read(expression)
    for _ in range(steps):
        new = frontier - names
        if not new:
            break
        names |= new
        frontier = set().union(*(_names_read(v) for name in new for v in assigned.get(name, ())))
    return names


def _returned(function, index: int | None, count: int | None):
    """The expressions ``function`` returns (the ``index``-th of a tuple of ``count`` when given)."""
    for node in _own_nodes(function):
        if not isinstance(node, ast.Return) or node.value is None:
            continue
        if index is None:
            yield node.value
        elif isinstance(node.value, (ast.Tuple, ast.List)) and len(node.value.elts) == count:
            yield node.value.elts[index]
        elif count is None and index == 0:
            yield node.value


def returned_misread(code, function: str, index: int | None = None, count: int | None = None) -> list[Misread]:
    """The misread variables (:func:`misread`) that what ``function`` returns -- its ``index``-th
    result of ``count`` when given -- is made from: in ``function`` itself, or in a function of the
    module it calls whose own return they reach."""
    fn = code.functions.get(function)
    if fn is None:
        return []
    found = []
    for expression in _returned(fn, index, count):
        fed = feeding(fn, expression)
        found += [m for m in misread(fn) if m.name in fed]
        for helper in code.reachable([function]):
            if helper is fn or helper.name not in fed:
                continue
            helper_fed = set().union(*(feeding(helper, e) for e in _returned(helper, None, None)))
            found += [m for m in misread(helper) if m.name in helper_fed]
    unique = []
    for m in found:
        if m not in unique:
            unique.append(m)
    return unique


def out_of_order(function, called: str | None = None) -> bool:
    """Whether ``function`` unpacks an OpenCV call's outputs out of order (``called``'s only, when given)."""
    return any(called is None or m.function == called for m in misread(function))


def told(code, function: str, index: int | None = None, count: int | None = None) -> tuple[str, str] | None:
    """(sentence, mistake) for a failure of ``function``'s result (its ``index``-th of ``count``),
    when that result is made from a misread output; None otherwise."""
    found = returned_misread(code, function, index, count)
    if not found:
        return None
    return found[0].sentence(found), MISTAKE
