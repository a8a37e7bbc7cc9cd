"""Lab 10 - geometric camera models, continued: the public checks.

Ground truth comes from :mod:`fixtures.lab10`: projections by definition,
camera matrices built from chosen ``K``, ``R``, ``t`` (so DLT and decomposition
are judged against the exact camera), chessboard images rendered from known
poses (with exactly simulated lens distortion), and a rendered sequence with a
known trajectory. Poses are judged by rotation angle and translation error,
accepting the half-turn ambiguity of a symmetric board.
"""

from __future__ import annotations

import ast

import cv2
import numpy as np

from fixtures import lab10 as truth
from fixtures import scene
from fixtures.images import tinted

from ..engine import conventions, inplace
from ..engine import strategies as st
from ..engine.checks import Fail, StudentFailure, Trial, partial, passed
from ..engine.claims import (calls_any, checklist, divides_by, evidenced, from_code, guard, look_at, measured,
                             negates_on_negative_det,
                             passes_argument, reshapes, takes_last_column_of_vt, takes_last_row_of_vt, where_to_look)
from ..engine.compare import (at_precision, blurred_difference, closest, fill_fraction, format_apart, format_arrays_apart,
                       magnitude, projective_distance)
from ..engine.forms import scale_form, shape_form
from ..engine.hints import Hint, Predicate, _path, calls, code_of, expr, functions_read, mentions
from ..engine.judges import (BLACK_FILL_HINT, FILL_TOLERANCE, Probe, call_probe, fingerprint, format_matrix,
                             name_mistake, parameter_ignored,
                             name_correspondences_left_out, repeating_border, where_matrices_differ)
from ..engine.pictures import svg_points
from ..engine.registry import Lab
from ..sandbox.beginner import RGB_FOR_BGR, channels_reversed
from .code_signs import SOLVES_BY_SVD
from .lab09 import (OBJECT_POINTS_ROW_BY_ROW, advise_nan_behind, call_behind, expect_points, judge_in_front, judge_points,
                    judge_single_point, make_points_probe, pinhole_formulas, point_error)
from ..loading.parsing import walk

lab = Lab("lab10", module="lab10_camera2", title="Geometric camera models (continued)")

seeds = st.integers(0, 2**32 - 1)

# Names and sentences that ask for code, held to the student's code (autograder.engine.claims).
guard(truth.RESHAPED_WRONG, asks=reshapes(3, 4),
      instead="the 12 entries of p come out in another order: your code {found}, so look at the order of the "
              "columns of A (P's first row multiplies [X, Y, Z, 1] in the u equations, then the second, then the "
              "third)")
for _taken in (truth.LARGEST_TAKEN, truth.LAST_COLUMN_TAKEN):
    guard(_taken, asks=takes_last_row_of_vt(),
          instead="p comes out as another singular vector than the last row of Vt; your code {found}, so look "
                  "at what is decomposed (A, with a row per equation and a column per entry of P)")
guard(truth.NOT_UNDONE, asks=calls_any("np.linalg.inv", "np.linalg.solve", says="inverts a normalising transform"),
      instead="the normalisation is not undone (the P returned is the camera of the normalised points): your "
              "code {found}; check that the P returned is T2^-1 P_n T3")
LAST_COLUMN = takes_last_column_of_vt()
# the sign fix's own place: P negated (not K, not R) under a test of det(P[:, :3]) < 0
NEGATES_P = negates_on_negative_det(0, says="negates P when det(P[:, :3]) < 0")


def _product_operands(node):
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.MatMult):
        return node.left, node.right
    if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("dot", "matmul") and len(node.args) == 2:
        return node.args[0], node.args[1]
    return None


def _negated_part(node) -> str:
    """"column" for ``X[:, i] *= -1`` (or ``= -X[:, i]``), "row" for ``X[i] *= -1``/``X[i, :]``, else ""."""
    if isinstance(node, ast.AugAssign) and isinstance(node.op, ast.Mult):
        target = node.target
    elif isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.value, ast.UnaryOp):
        target = node.targets[0]
    else:
        return ""
    if not isinstance(target, ast.Subscript):
        return ""
    index = target.slice
    if isinstance(index, ast.Tuple) and index.elts and isinstance(index.elts[0], ast.Slice):
        return "column"
    return "row"


def _flips_both_sides(function) -> bool:
    """K's columns and R's rows flipped by one sign vector: one matrix on the right of one product and the left
    of another (``K @ D``, ``D @ R``), both a column and a row negated (``K[:, i] *= -1``, ``R[i] *= -1``), or a
    sign vector broadcast over rows (``s[:, None] * R``, with ``K * s``)."""
    right = {n.id for node in walk(function) if (pair := _product_operands(node)) and isinstance(pair[1], ast.Name)
             for n in [pair[1]]}
    left = {n.id for node in walk(function) if (pair := _product_operands(node)) and isinstance(pair[0], ast.Name)
            for n in [pair[0]]}
    signs = {t.id for node in walk(function) if isinstance(node, ast.Assign)
             and any(isinstance(n, (ast.Name, ast.Attribute)) and _path(n).rsplit(".", 1)[-1] in ("sign", "diag")
                     for n in walk(node.value)) for t in node.targets if isinstance(t, ast.Name)}
    if right & left & signs:   # one sign matrix on both sides
        return True
    parts = {_negated_part(node) for node in walk(function)}
    if {"column", "row"} <= parts:
        return True
    return (expr("_[:, None] * _") | expr("_[:, np.newaxis] * _") | expr("_ * _[:, None]")).holds([function])


FLIPS_BOTH_SIDES = Predicate("flips K's columns and R's rows with one D", _flips_both_sides)


def _returns_the_fixed(function) -> bool:
    """A ``return`` of (K, R) each a product, or a name the function changes after it is first given a value (the
    sign fix: ``K = K @ D``, ``R[i] *= -1``)."""
    changed: dict[str, int] = {}
    for node in walk(function):
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] \
            if isinstance(node, ast.AugAssign) else []
        for target in targets:
            for name in [target] if isinstance(target, ast.Name) else [target.value] \
                    if isinstance(target, ast.Subscript) else target.elts if isinstance(target, ast.Tuple) else []:
                if isinstance(name, ast.Name):
                    changed[name.id] = changed.get(name.id, 0) + (2 if isinstance(node, ast.AugAssign) else 1)
    for node in walk(function):
        if isinstance(node, ast.Return) and isinstance(node.value, ast.Tuple) and len(node.value.elts) >= 2:
            first_two = node.value.elts[:2]
            if all(_product_operands(e) or isinstance(e, ast.BinOp)
                   or (isinstance(e, ast.Name) and changed.get(e.id, 0) >= 2) for e in first_two):
                return True
    return False


RETURNS_THE_FIXED = Predicate("returns the fixed K and R", _returns_the_fixed)
BLOCK_NOT_NEGATED = "the block decomposed is P[:, :3] as given, not the negated P's, where det(P[:, :3]) < 0"


def _positive_multiple(a, b) -> bool:
    """Whether ``a`` is ``b`` times a positive number (to float64 precision of their size)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = float(np.sum(a * b) / max(np.sum(b * b), 1e-300))
    return scale > 0 and np.abs(a - scale * b).max() <= at_precision(1e-6 * np.abs(a).max(), magnitude(a))


SIGN_FIX = Hint(
    "for this P, det(P[:, :3]) < 0 (P is -1 times a K [R | t]): multiply P by -1 first, then decompose; flipping "
    "signs of K's columns alone would leave det(R) = -1", asks=negates_on_negative_det(),
    instead="for this P, det(P[:, :3]) < 0 (P is -1 times a K [R | t]): your code already {found}; " + checklist(
        "", ("the negated P is the one decomposed and solved for t", NEGATES_P),
        ("flipping K's columns flips the same rows of R", FLIPS_BOTH_SIDES),
        # (the negated P solved for t is the first item: nothing is left to point at)
        none_left=""))
def _orthogonal_first(function) -> bool:
    """``R, K = scipy.linalg.rq(M)`` (or ``Q, K = ...``, cv2.RQDecomp3x3's): an RQ's first factor, the upper
    triangular one, stored under an orthogonal matrix's name."""
    for node in walk(function):
        if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Tuple) and node.targets[0].elts \
                and any(isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] in ("rq", "RQDecomp3x3")
                        for n in walk(node.value)):
            first = node.targets[0].elts[0]
            if isinstance(first, ast.Name) and first.id.lower().startswith(("r", "q", "rot")):
                return True
    return False


# Signs fixed after a decomposition: np.sign, a test of a diagonal entry's sign; read leniently.
SIGNS_READ = (calls("np.sign") | expr("np.diag(_) < 0") | expr("_[_, _] < 0") | expr("np.diag(_) > 0")
              | expr("_[_, _] > 0")).saying("fixes the signs of K's diagonal")


def _rotations_written_out(function) -> bool:
    """A 3x3 rotation written out entry by entry (`np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])`): an
    RQ by Givens rotations, each meant to zero one entry below K's diagonal."""
    for node in walk(function):
        if isinstance(node, ast.Call) and _path(node.func) in ("np.array", "numpy.array") and node.args \
                and isinstance(node.args[0], ast.List) and len(node.args[0].elts) == 3:
            entries = [e for row in node.args[0].elts if isinstance(row, ast.List) for e in row.elts]
            minus = {ast.dump(e.operand) for e in entries if isinstance(e, ast.UnaryOp) and isinstance(e.op, ast.USub)}
            if len(entries) == 9 and any(ast.dump(e) in minus for e in entries):
                return True
    return False


ROTATIONS_WRITTEN_OUT = Predicate("writes the RQ's rotations out (Givens rotations)", _rotations_written_out)
RQ_HINT = Hint(" (use an RQ decomposition of the left 3x3 block)",
               asks=calls_any("scipy.linalg.rq", "cv2.RQDecomp3x3", "cv2.decomposeProjectionMatrix", "np.linalg.qr",
                              says="decomposes P[:, :3]") | ROTATIONS_WRITTEN_OUT,
               instead=" (your code {found}: " + checklist(
                   "", ("the upper-triangular factor becomes K (P[:, :3] = K R)",
                        ~Predicate("takes the orthogonal factor of an RQ as K", _orthogonal_first)),
                   ("the rows and columns are reversed to turn a QR into an RQ",
                    ~calls("np.linalg.qr") | calls_any("np.flipud", "np.fliplr", "np.flip") | expr("_[::-1]")
                    | expr("_[::-1, ::-1]")),
                   # (a rotation written out zeroes its entry only with its sines' signs right: the entries
                   # left below the diagonal, said in the message, point at the rotation meant for them)
                   ("each rotation written out zeroes its entry below the diagonal (the signs of its sines)",
                    ~ROTATIONS_WRITTEN_OUT),
                   none_left=look_at(("the signs fixed after it", SIGNS_READ),
                                     ("K divided by K[2, 2]", divides_by("_[2, 2]", "_[-1, -1]")))) + ")")
NORMALISE_K_HINT = Hint("divide K by K[2, 2] (P is only known up to scale)",
                        asks=divides_by("_[2, 2]", "_[-1, -1]", says="divides by K[2, 2]"),
                        instead="your code {found}, but the K returned is not the divided one (or is changed "
                                "afterwards); P is only known up to scale")
SIGN_TEST_INVERTED = "the sign test on det(P[:, :3]) is the wrong way round (P negated where det > 0)"
SIGN_TEST_MISSED = from_code("the test deciding P's negation does not follow the sign of det(P[:, :3]) (negate P "
                             "exactly where det(P[:, :3]) < 0, the left 3x3 block)")


def another_block_tested(functions) -> str:
    """A test (``if``, ``np.where``, a conditional expression) of ``np.linalg.det`` of a block of a matrix other
    than its left three columns (``P[:, 1:]``, ``P[:, -3:]``), as written; "" where none is."""
    def left_three(index) -> bool:
        if not (isinstance(index, ast.Tuple) and len(index.elts) == 2 and isinstance(index.elts[1], ast.Slice)):
            return True   # (not a column block: another reading's business)
        columns = index.elts[1]
        low = columns.lower.value if isinstance(columns.lower, ast.Constant) else 0 if columns.lower is None else None
        high = columns.upper.value if isinstance(columns.upper, ast.Constant) else \
            -1 if isinstance(columns.upper, ast.UnaryOp) and isinstance(columns.upper.operand, ast.Constant) \
            and columns.upper.operand.value == 1 else None
        return low == 0 and high in (3, -1)
    tests = [n.test for f in functions for n in walk(f) if isinstance(n, (ast.If, ast.IfExp))]
    for test in tests:
        for call in walk(test):
            if isinstance(call, ast.Call) and _path(call.func).endswith("det") and call.args \
                    and isinstance(call.args[0], ast.Subscript) and not left_three(call.args[0].slice):
                return ast.unparse(call)
    # (or a determinant compared with an exact value, `if np.linalg.det(R) == -1:` -- true only where rounding
    # leaves it so -- or the sign of one entry, `if P[2, 2] < 0: P = -P`: an entry's sign is no determinant's)
    for branch in (n for f in functions for n in walk(f) if isinstance(n, ast.If)):
        test = branch.test
        if isinstance(test, ast.Compare) and len(test.ops) == 1 and isinstance(test.ops[0], (ast.Eq, ast.NotEq)) \
                and any(isinstance(side, ast.Call) and _path(side.func).endswith("det")
                        for side in (test.left, test.comparators[0])):
            return ast.unparse(test)
    for branch in (n for f in functions for n in walk(f) if isinstance(n, ast.If)):
        test = branch.test
        negates = any(isinstance(s, ast.Assign) and isinstance(s.value, ast.UnaryOp) and isinstance(s.value.op, ast.USub)
                      or isinstance(s, ast.AugAssign) and isinstance(s.op, ast.Mult)
                      and isinstance(s.value, (ast.UnaryOp, ast.Constant)) for s in branch.body)
        if negates and isinstance(test, ast.Compare) and len(test.ops) == 1 and isinstance(test.left, ast.Subscript) \
                and isinstance(test.left.slice, ast.Tuple) and len(test.left.slice.elts) == 2 \
                and all(isinstance(e, ast.Constant) for e in test.left.slice.elts) \
                and isinstance(test.comparators[0], ast.Constant) and test.comparators[0].value == 0:
            return ast.unparse(test)
    return ""


# (the same answer comes from RQ's signs left unfixed when K's whole diagonal comes out negative and the
# division by K[2, 2] hides it: the test written the wrong way round is read, not inferred)
INVERTED_SIGN_TEST = (expr("np.linalg.det(_) > 0") | expr("np.linalg.det(_) >= 0") | expr("0 < np.linalg.det(_)")
                      | expr("0 <= np.linalg.det(_)")).saying("negates P where det(P[:, :3]) > 0")


def _the_negated_camera(R, t, R_true, t_true) -> bool:
    """Whether (R, t) is the true pose times -1 (the rotation's determinant then -1)."""
    return np.abs(R + R_true).max() <= at_precision(1e-6) and \
        np.abs(t + t_true).max() <= at_precision(1e-6 * magnitude(t_true), magnitude(t_true))


SIGNS_HINT = Hint("multiply the offending columns of K and the same rows of R by -1 (R then comes out with det +1, "
                  "as the block decomposed has det > 0)", asks=(calls("np.sign") | expr("np.diag(np.sign(np.diag(_)))")).saying(
                      "fixes signs with np.sign"),
                  instead="your code {found}: " + checklist(
                      "", ("it flips the same columns of K and rows of R (K D and D R with one D)", FLIPS_BOTH_SIDES),
                      ("the fixed K and R are the ones returned", RETURNS_THE_FIXED),
                      none_left=look_at(("which signs are fixed (those of K's diagonal, to make it positive)",
                                         expr("np.sign(np.diag(_))") | expr("np.diag(_) < 0") | expr("_[_, _] < 0")))))
DIST_TO_PROJECT = passes_argument("cv2.projectPoints", 4, "distCoeffs", says="passes a distortion to cv2.projectPoints")
guard("the corners are projected without dist (pass dist to cv2.projectPoints too)", asks=DIST_TO_PROJECT,
      instead="the corners are projected without dist: your code {found}, but not the dist given (None or zeros?)")
DIST_TO_PNP = (passes_argument("cv2.solvePnP", 3, "distCoeffs") | passes_argument("cv2.solvePnPRansac", 3, "distCoeffs")
               ).saying("passes a distortion to cv2.solvePnP")
DIST_TO_UNDISTORT = (passes_argument("cv2.undistort", 2, "distCoeffs")
                     | passes_argument("cv2.initUndistortRectifyMap", 1, "distCoeffs")).saying(
    "passes a distortion to cv2.undistort")
guard("K is transposed (cv2.undistort wants K as given)",
      asks=~calls_any("cv2.undistort", "cv2.initUndistortRectifyMap"),
      instead="K is transposed (the image is undistorted with K^T)")
FIRST_FRAME = guard(" (use each frame of the loop, not frames[0])", asks=~expr("frames[0]"), instead="")
guard("the object points are built for (rows, cols): np.mgrid[0:rows, 0:cols]", asks=~mentions("np.mgrid"),
      instead="the object points are built for (rows, cols): x runs over the rows")


def projection_probe(t: Trial, function: str, **kwargs):
    """A projection function on its confirmation probe's input (see autograder.engine.judges.Probe):
    points of varied depth away from the axis, an f none of the checks uses, a given z_avg
    apart from every statistic of the depths."""
    X = truth.points_in_front(10_010, n=10, z_range=(3.0, 14.0))
    f = 640.0
    if function == "perspective_project":
        return make_points_probe(t, function, (X, f), {}, truth.pinhole(X, f), perspective_mistakes(f, X),
                                 formulas=pinhole_formulas(X, f))
    if function == "weak_perspective_project":
        z_avg = kwargs.get("z_avg")
        call_kwargs = {} if z_avg is None else {"z_avg": z_avg}
        mistakes = weak_mistakes(X, f, z_avg)
        if z_avg is None:
            del mistakes["the given z_avg is ignored (the mean depth is used instead)"]
        return make_points_probe(t, function, (X, f), call_kwargs, truth.weak_perspective(X, f, z_avg), mistakes)
    return make_points_probe(t, function, (X,), {}, truth.orthographic(X), orthographic_mistakes(X))


# ================================================================== ex1 perspective
ex1 = lab.exercise("ex1", "Perspective projection and focal length", functions=[
    "perspective_project(points, f)"])


def perspective_mistakes(f, X):
    Z = X[:, 2]
    common = {"the first point's": Z[0], "the last point's": Z[-1], "the median": np.median(Z),
              "the largest": Z.max(), "the smallest": Z.min()}
    return {
        **truth.lab09.projection_mistakes(f, X),
        "every point is divided by the mean depth: that is weak perspective": truth.weak_perspective(X, f),
        "the division is by the distance |X| from the camera; it is by the depth Z":
            f * X[:, :2] / np.linalg.norm(X, axis=1, keepdims=True),
        **{f"every point is divided by one depth, {name} depth; each point has its own depth Z":
           truth.weak_perspective(X, f, z) for name, z in common.items()},
    }


@ex1.check("perspective_project with f = 100, 500 and 1000", points=3)
def perspective_focal_lengths(t):
    X = truth.scene_points(101, n=10, depth=8.0, relief=4.0)
    plots = {}
    for f in (100.0, 500.0, 1000.0):
        got = t.call("perspective_project", X, f)
        if isinstance(got, np.ndarray) and got.shape == (10, 2):
            plots[f"f = {f:g}"] = got
        judge_points(t, f"perspective_project(points, f={f:g})", got, truth.pinhole(X, f),
                     perspective_mistakes(f, X), formulas=pinhole_formulas(X, f),
                     probe=projection_probe(t, "perspective_project"))
    t.svg("the same points with f = 100, 500, 1000", svg_points(plots))
    return passed("the image scales with f")


@ex1.check("perspective_project for any points and f; a single (3,) point", points=3)
def perspective_property(t):
    def holds(case):
        seed, f = case
        X = truth.points_in_front(seed, n=8)
        judge_points(t, f"perspective_project(points, f={f!r})", t.call("perspective_project", X, f),
                     truth.pinhole(X, f), perspective_mistakes(f, X), formulas=pinhole_formulas(X, f),
                     probe=projection_probe(t, "perspective_project"))

    t.for_all(st.tuples(seeds, st.floats(10.0, 2000.0)), holds, max_examples=12,
              describe=lambda c: f"fixtures.lab09.points_in_front(seed={c[0]}, n=8), f={c[1]!r}")
    X = np.array([0.4, -0.3, 5.0])
    judge_single_point(t, "perspective_project((3,) point, f=500)", t.call("perspective_project", X, 500.0),
                       truth.pinhole(X, 500.0)[0])
    # (the same scene a thousand times smaller, depths of millimetres: f X / Z does not depend on the unit)
    X = truth.points_in_front(5, n=8) / 1000.0
    judge_points(t, "perspective_project(points at millimetre depths, f=500)", t.call("perspective_project", X, 500.0),
                 truth.pinhole(X, 500.0), perspective_mistakes(500.0, X), formulas=pinhole_formulas(X, 500.0),
                 probe=projection_probe(t, "perspective_project"))


def perspective_behind_case():
    X, behind = truth.lab09.with_points_behind(truth.points_in_front(102, n=10), seed=103)
    return "perspective_project(points with some Z <= 0, one at Z = 0, f=500)", X, behind


# The same input convention as lab 9's projections (judge_in_front): a point at Z = 0 or behind the
# camera must not stop the projection of the others.
@ex1.check("perspective_project: with points behind the camera (one at Z = 0), those in front stay right",
           points=1)
def perspective_in_front(t):
    what, X, behind = perspective_behind_case()
    got = call_behind(t, what, "perspective_project", X, 500.0)
    front = ~behind
    if isinstance(got, np.ndarray) and got.shape == (len(X), 2) and got.dtype.kind in "iuf":
        # a wrong projection is named as the other checks name it, on the points in front
        judge_points(t, f"{what}, the points in front", got[front], truth.pinhole(X[front], 500.0),
                     perspective_mistakes(500.0, X[front]), formulas=pinhole_formulas(X[front], 500.0),
                     probe=projection_probe(t, "perspective_project"))
    judge_in_front(t, what, got, truth.pinhole(X, 500.0), behind)


@ex1.advice("NaN for points behind the camera")
def perspective_behind(t):
    # The API leaves points with Z <= 0 to the lab sheet's formula (cv2.projectPoints
    # gives finite pixels too); NaN is only recommended.
    _, X, behind = perspective_behind_case()
    got = t.call("perspective_project", X, 500.0)
    if isinstance(got, np.ndarray) and got.dtype.kind == "f":
        advise_nan_behind(t, "perspective_project(points with some Z <= 0, f=500)", got, behind, truth.pinhole(X, 500.0))


# ================================================================== ex2 weak perspective
ex2 = lab.exercise("ex2", "Weak perspective", functions=["weak_perspective_project(points, f, z_avg=None)"])
# The sheet's exercises 2 and 3 compare each projection with the perspective one of the same points:
# a projection that writes into the caller's points (their Z set to the mean depth) changes the other's.
for _projection in ("perspective_project", "weak_perspective_project", "orthographic_project"):
    inplace.shown_after(lab, _projection, "points", "exercises 2 and 3 compare the weak perspective and the "
                                                     "orthographic projection of the same points with the perspective one")


def weak_mistakes(X, f, z_avg=None):
    X = np.atleast_2d(np.asarray(X, dtype=np.float64))
    return {
        "each point is divided by its own depth: that is full perspective; weak perspective divides "
        "every point by one common depth z_avg": truth.pinhole(X, f),
        "the given z_avg is ignored (the mean depth is used instead)": truth.weak_perspective(X, f),
        "the default depth is the median; it is the mean depth": truth.weak_perspective(X, f, np.median(X[:, 2])),
        "the default depth is the largest depth; it is the mean depth":
            truth.weak_perspective(X, f, X[:, 2].max() if z_avg is None else z_avg),
        "the default depth is the smallest depth; it is the mean depth":
            truth.weak_perspective(X, f, X[:, 2].min() if z_avg is None else z_avg),
        "the default depth is the first point's; it is the mean depth of all points":
            truth.weak_perspective(X, f, X[0, 2] if z_avg is None else z_avg),
        "the default depth is the mean distance |X| from the camera; it is the mean depth Z":
            truth.weak_perspective(X, f, np.linalg.norm(X, axis=1).mean() if z_avg is None else z_avg),
        "x and y are swapped": truth.weak_perspective(X, f, z_avg)[:, ::-1],
        "f is not applied": truth.weak_perspective(X, 1.0, z_avg),
        "f is applied twice (x = f^2 X / z_avg)": f * truth.weak_perspective(X, f, z_avg),
        "the default depth is the mean of every coordinate (X.mean()); it is the mean depth, "
        "X[:, 2].mean()": truth.weak_perspective(X, f, X.mean() if z_avg is None else z_avg),
        "the answer is the orthographic projection (X, Y): the scale f / z_avg does not reach it (not applied, or "
        "cancelled: a factor on the whole projection matrix scales w too, and the division undoes it)": truth.orthographic(X),
        "the scale is inverted: it is f / z_avg, not z_avg / f":
            X[:, :2] * ((X[:, 2].mean() if z_avg is None else z_avg) / f),
    }


@ex2.check("weak_perspective_project with the default z_avg (the mean depth)", points=3)
def weak_default(t):
    X = truth.scene_points(201, n=12, depth=20.0, relief=6.0)
    expected = truth.weak_perspective(X, 500.0)
    mistakes = weak_mistakes(X, 500.0)
    del mistakes["the given z_avg is ignored (the mean depth is used instead)"]
    got = t.call("weak_perspective_project", X, 500.0)
    if isinstance(got, np.ndarray) and got.shape == expected.shape:
        t.svg("weak perspective vs full perspective", svg_points(
            {"weak perspective (truth)": expected, "yours": got, "full perspective": truth.pinhole(X, 500.0)}))
    judge_points(t, "weak_perspective_project(points, f=500)", got, expected, mistakes,
                 probe=projection_probe(t, "weak_perspective_project"))


SINGLE_POINT_DEPTH = "the depth given is not used for a single point"


@ex2.check("weak_perspective_project with a given z_avg (a float, and a whole number); a single (3,) point",
           points=2)
def weak_given(t):
    X = truth.scene_points(202, n=10, depth=15.0, relief=3.0)
    judge_points(t, "weak_perspective_project(points, f=300, z_avg=12.0)",
                 t.call("weak_perspective_project", X, 300.0, z_avg=12.0),
                 truth.weak_perspective(X, 300.0, 12.0), weak_mistakes(X, 300.0, 12.0),
                 probe=projection_probe(t, "weak_perspective_project", z_avg=7.25))
    # (a depth written as a whole number, as a caller writes one: z_avg=10 is a depth like 10.0)
    judge_points(t, "weak_perspective_project(points, f=300, z_avg=10)",
                 t.call("weak_perspective_project", X, 300.0, z_avg=10),
                 truth.weak_perspective(X, 300.0, 10.0), weak_mistakes(X, 300.0, 10.0))
    # the API's convention for (N, 3) functions: a (3,) point gives a (2,) result
    X = np.array([0.4, -0.3, 5.0])
    what = "weak_perspective_project((3,) point, f=300, z_avg=12.0)"
    try:
        judge_single_point(t, what, t.call("weak_perspective_project", X, 300.0, z_avg=12.0),
                           truth.weak_perspective(X, 300.0, 12.0)[0])
    except Fail as failure:
        # (the many points took z_avg -- judged above --: a single point's own path may not)
        if not failure.mistake and parameter_ignored(
                lambda **kw: t.call("weak_perspective_project", X, 300.0, **kw), "z_avg", (12.0, 30.0)):
            t.fail(measured(f"{what}: z_avg=12.0 and z_avg=30.0 give the same point, where the points given as an "
                            "(N, 3) array take it: on a single (3,) point your code does not use z_avg"),
                   mistake=SINGLE_POINT_DEPTH)
        raise
    # (and with z_avg left out: the mean depth of one point is its own)
    judge_single_point(t, "weak_perspective_project((3,) point, f=300) with z_avg left out",
                       t.call("weak_perspective_project", X, 300.0), truth.weak_perspective(X[None], 300.0)[0])


@ex2.check("weak perspective approaches perspective for a shallow, distant object", points=1)
def weak_property(t):
    def holds(seed):
        X = truth.scene_points(seed, n=10, depth=50.0, relief=0.5)
        judge_points(t, "weak_perspective_project(points, f=400)", t.call("weak_perspective_project", X, 400.0),
                     truth.weak_perspective(X, 400.0), weak_mistakes(X, 400.0),
                     probe=projection_probe(t, "weak_perspective_project"))

    t.for_all(seeds, holds, max_examples=6, describe=lambda s: f"fixtures.lab10.scene_points({s}, depth=50)")


# ================================================================== ex3 orthographic
ex3 = lab.exercise("ex3", "Orthographic projection", functions=["orthographic_project(points)"])


def _dehomogenises(function) -> bool:
    """A division of a matrix product by its own last coordinate (`x = (M @ Xh.T).T`, then `x[:, :2] /
    x[:, 2:3]`): the lab sheet's x = P [X, 1] made Euclidean, right for any P (not the points' own Z)."""
    products = {target.id for node in walk(function) if isinstance(node, ast.Assign)
                for target in node.targets if isinstance(target, ast.Name)
                and any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.MatMult)
                        or isinstance(n, ast.Call) and _path(n.func).rsplit(".", 1)[-1] in ("dot", "matmul")
                        for n in walk(node.value))}
    for node in walk(function):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) and isinstance(node.left, ast.Subscript) \
                and isinstance(node.right, ast.Subscript) and isinstance(node.left.value, ast.Name) \
                and isinstance(node.right.value, ast.Name) and node.left.value.id == node.right.value.id \
                and node.left.value.id in products:
            return True
    return False


DIVIDED_BY_Z = guard(
    "the points are divided by Z: that is perspective; orthographic projection ignores depth",
    asks=Predicate("divides x = M [X, 1] by its own third coordinate", _dehomogenises),
    instead="the points come out divided by Z, as in a perspective projection; your code divides M [X, 1] by its "
            "own third coordinate (the recipe), so it is the matrix's third row that reads Z: the lab sheet's "
            "orthographic matrix has the last row [0, 0, 0, 1], so that w = 1")


def orthographic_mistakes(X):
    return {
        DIVIDED_BY_Z: X[:, :2] / X[:, 2:3],
        "it returns (X, Z); the lab sheet's matrix keeps X and Y": X[:, [0, 2]],
        "it returns (Y, Z); the lab sheet's matrix keeps X and Y": X[:, [1, 2]],
        "x and y are swapped": X[:, [1, 0]],
        "the points are scaled by 1 / mean depth (weak perspective with f = 1)": truth.weak_perspective(X, 1.0),
    }


@ex3.check("orthographic_project uses the lab sheet's 3x4 matrix: (X, Y)", points=3)
def orthographic_example(t):
    X = truth.scene_points(301, n=10, depth=10.0, relief=5.0)
    got = t.call("orthographic_project", X)
    if isinstance(got, np.ndarray) and got.shape == (10, 3):
        t.fail("orthographic_project returned shape (10, 3); expected (10, 2): a third coordinate is kept "
               "(Z is kept, or the homogeneous one); only (x, y) is expected", mistake="a third coordinate is kept")
    if isinstance(got, np.ndarray) and got.shape == (2, 3):
        t.fail("orthographic_project returned shape (2, 3); expected (10, 2): points[:2] takes the first two "
               "points (rows); X and Y are the first two columns, points[:, :2].",
               mistake="rows are taken instead of columns")
    judge_points(t, "orthographic_project(points)", got, truth.orthographic(X), orthographic_mistakes(X),
                 probe=projection_probe(t, "orthographic_project"))


@ex3.check("orthographic_project: depth changes nothing; a single (3,) point", points=2)
def orthographic_property(t):
    def holds(seed):
        rng = np.random.default_rng(seed)
        X = rng.uniform(-10, 10, size=(8, 3))
        X[:, 2] = np.abs(X[:, 2]) + 0.5
        judge_points(t, "orthographic_project(points)", t.call("orthographic_project", X), truth.orthographic(X),
                     {DIVIDED_BY_Z: X[:, :2] / X[:, 2:3]},
                     probe=projection_probe(t, "orthographic_project"))

    t.for_all(seeds, holds, max_examples=8, describe=lambda s: f"uniform(-10, 10, (8, 3)) from seed {s}")
    judge_single_point(t, "orthographic_project((3,) point)", t.call("orthographic_project", np.array([1.0, 2.0, 7.0])),
                       np.array([1.0, 2.0]))


# ================================================================== ex4 DLT
ex4 = lab.exercise("ex4", "Camera matrix by the DLT", functions=["camera_matrix_dlt(points3d, points2d)"])
lab.forbid("camera_matrix_dlt", "cv2.calibrateCamera", "cv2.solvePnP", "cv2.solvePnPRansac",
           "cv2.solvePnPGeneric", "cv2.initCameraMatrix2D", "cv2.calibrateCameraExtended")


def _twelve_columns(function) -> bool:
    """12 written where A is built: a constant 12 (``np.zeros((2 * n, 12))``) or a row of 12 entries."""
    return any((isinstance(n, ast.Constant) and n.value == 12) or (isinstance(n, (ast.List, ast.Tuple))
                                                                  and len(n.elts) == 12) for n in walk(function))


TWELVE_COLUMNS = Predicate("builds A with 12 columns", _twelve_columns)
FIXED_P23_HINT = Hint(
    "It looks like P[2, 3] was fixed to 1 (11 unknowns, least squares), which cannot express this "
    "camera: solve A p = 0 for all 12 entries by SVD (the last row of Vt).",
    asks=SOLVES_BY_SVD,
    instead="Your code {found}: " + checklist(
        "", ("A has 12 columns (P[2, 3] is an unknown too)", TWELVE_COLUMNS), ("p is the last row of Vt",
                                                                                takes_last_row_of_vt()),
        # (no reading tells the rows right from wrong: nothing is pointed at rather than rows that may be right)
        none_left="") + ".")


def judge_dlt(t: Trial, seed: int, n: int, noise: float, show=False, origin_on_principal_plane=False):
    P, X, x, X_test, x_test = truth.dlt_problem(seed, n=n, noise=noise,
                                                origin_on_principal_plane=origin_on_principal_plane)
    what = f"camera_matrix_dlt(points3d, points2d) with N={n}" + (f", noise {noise:g} px" if noise else "") \
        + (", world origin on the camera's principal plane (t_z = 0)" if origin_on_principal_plane else "")
    got = t.expect_array(t.call("camera_matrix_dlt", X, x), what, shape=(3, 4), kind="iuf", finite=True)
    if np.linalg.norm(got) == 0:
        t.fail(f"{what} returned the zero matrix (the trivial solution of A p = 0)")
    fresh = np.linalg.norm(truth.project_any_sign(got, X_test) - x_test, axis=1)
    fresh = np.where(np.isfinite(fresh), fresh, np.inf)
    if show:
        t.svg("new points: true projection vs projected with your P", svg_points(
            {"true": x_test[:40], "with your P": truth.project_any_sign(got, X_test[:40])},
            lines=list(zip(x_test[:40], truth.project_any_sign(got, X_test[:40])))))
    if noise == 0:
        if projective_distance(got, P) < at_precision(1e-6) and fresh.max() < 1e-3:
            return passed(f"P recovered up to scale (new points reprojected within {fresh.max():.1e} px)")
    else:
        residual = np.sqrt(np.mean(np.sum((truth.project_any_sign(got, X) - x) ** 2, axis=1)))
        true_residual = np.sqrt(np.mean(np.sum((truth.project_any_sign(P, X) - x) ** 2, axis=1)))
        if np.isfinite(residual) and residual <= 1.2 * true_residual and fresh.mean() <= 1.0:
            return passed(f"RMS residual {residual:.2f} px (the true P: {true_residual:.2f} px); "
                          f"new points within {fresh.mean():.2f} px on average")
    mistake = name_mistake(t, got, truth.dlt_mistakes(P, X, x), projective_distance, 0.05 if noise else 1e-4,
                           probe=dlt_probe(t))
    if mistake:
        t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    # (Vt's last column mixes entries of every singular vector, each of a sign LAPACK chooses: no number to
    # compare with holds on every machine, the code shows it)
    column = LAST_COLUMN.found(code_of(t).reachable(["camera_matrix_dlt"]))
    if column:
        t.fail(f"{what} is wrong: your code {column}: " + from_code(truth.LAST_COLUMN_TAKEN) + ".",
               mistake=truth.LAST_COLUMN_TAKEN)
    if origin_on_principal_plane and abs(got[2, 3]) > 1e-3 * np.linalg.norm(got) and dlt_right_on_probe(t):
        t.fail(f"{what}: here the true P[2, 3] is 0 (P[2, 3] = t_z, the depth of the world origin), "
               f"yours is {got[2, 3] / np.linalg.norm(got):.3g} of |P|. " + FIXED_P23_HINT.said(t),
               mistake="P[2, 3] is fixed to 1")
    if noise == 0:
        name_correspondences_left_out(t, what, np.linalg.norm(truth.project_any_sign(got, X) - x, axis=1),
                                      "P's 11 unknowns up to scale")
    t.fail(f"{what}: P is wrong {where_matrices_differ(got, P, up_to_scale=True)} (compared with the "
           f"true camera up to scale): projecting new points with it misses their true projections by "
           f"{np.mean(fresh):.3g} px on average.")


def dlt_probe(t: Trial) -> Probe:
    """camera_matrix_dlt on 10 exact correspondences of another camera (its t_z far from 0)."""
    P, X, x, _, _ = truth.dlt_problem(10_020, n=10, noise=0.0)
    return call_probe(t, "camera_matrix_dlt", (X, x), candidates=lambda: truth.dlt_mistakes(P, X, x), truth=P,
                      shape=(3, 4), distance=projective_distance, tolerance=1e-4)


def dlt_right_on_probe(t: Trial) -> bool:
    """Whether the DLT is right on the probe's camera (t_z far from 0): fixing P[2, 3] = 1 is
    wrong only where t_z = 0, a DLT wrong for another reason is wrong there too."""
    probe = dlt_probe(t)
    answer = t.probe(probe.key, probe.answer)
    return answer is not None and projective_distance(answer, probe.truth) < 1e-6


@ex4.check("camera_matrix_dlt from exact correspondences (N = 6, N = 20, and t_z = 0)", points=4)
def dlt_exact(t):
    judge_dlt(t, 401, 6, 0.0)
    judge_dlt(t, 404, 12, 0.0, origin_on_principal_plane=True)
    return judge_dlt(t, 402, 20, 0.0, show=True)


@ex4.check("camera_matrix_dlt from noisy correspondences (0.5 px, N = 40)", points=3)
def dlt_noisy(t):
    return judge_dlt(t, 403, 40, 0.5, show=True)


@ex4.check("camera_matrix_dlt for random cameras", points=2)
def dlt_property(t):
    t.for_all(seeds, lambda seed: judge_dlt(t, seed, 12, 0.0), max_examples=8,
              describe=lambda s: f"fixtures.lab10.dlt_problem(seed={s}, n=12)")


# ================================================================== ex5 decomposition
ex5 = lab.exercise("ex5", "Decomposing the camera matrix", functions=[
    "decompose_camera_matrix(P)", "camera_center(P)"])


def judge_decomposition(t: Trial, P, K_true, R_true, t_true, what="decompose_camera_matrix(P)"):
    got = t.call("decompose_camera_matrix", P)
    if not (isinstance(got, (tuple, list)) and len(got) == 3):
        t.fail(f"{what} should return a triple (K, R, t)")
    K = t.expect_array(got[0], f"{what}[0] (K)", shape=(3, 3), kind="iuf", finite=True)
    R = t.expect_array(got[1], f"{what}[1] (R)", shape=(3, 3), kind="iuf", finite=True)
    tv = got[2]
    if isinstance(tv, np.ndarray) and tv.shape in ((4,), (4, 1)):
        t.fail(f"{what}[2] (t) has shape {tv.shape}: " + measured(
            "that looks like the homogeneous camera centre (what cv2.decomposeProjectionMatrix returns as its "
            "'translation'); t is the (3,) vector in P = K [R | t], t = -R C."),
            mistake="the homogeneous camera centre returned as t")
    tv = t.expect_array(tv, f"{what}[2] (t)", kind="iuf", finite=True)
    if tv.shape == (3, 1):
        tv = tv.ravel()
    tv = t.expect_array(tv, f"{what}[2] (t)", shape=(3,))
    problems, labels = [], []
    negative = np.linalg.det(np.asarray(P, float)[:, :3]) < 0
    # a P the code negates (det < 0) leaves RQ's own sign ambiguity as the cause, as for det > 0
    other_block = another_block_tested(code_of(t).reachable(["decompose_camera_matrix"]))
    # (code that negates P under a test of something else -- another block, one entry's sign -- does negate it)
    unnegated = negative and not NEGATES_P.found(code_of(t).reachable(["decompose_camera_matrix"])) and not other_block
    sign_fix = SIGN_FIX.said(t)
    K_scale = magnitude(K)
    triangular = np.abs(np.tril(K, -1)).max() <= at_precision(1e-6 * np.abs(K).max(), K_scale)
    if not triangular:
        below = [f"K[{i}, {j}] = {K[i, j]:.3g}" for i, j in zip(*np.tril_indices(3, -1))
                 if abs(K[i, j]) > at_precision(1e-6 * np.abs(K).max(), K_scale)]
        problems.append("K is not upper triangular" + measured(f" ({', '.join(below)})") + RQ_HINT.said(t))
    if abs(K[2, 2] - 1) > at_precision(1e-6):
        # (the recipe's step is where to look where nothing better is known: a slip read in the code -- P scaled
        # by its whole row's norm -- says where)
        problems.append(f"K[2, 2] is {K[2, 2]:.4g}, not 1: K is not normalised"
                        + where_to_look("; " + NORMALISE_K_HINT.said(t)))
        labels.append("K is not normalised (K[2, 2] != 1)")
    rotation = np.abs(R @ R.T - np.eye(3)).max() <= at_precision(1e-6)
    unsigned = np.any(np.diag(K) <= 0)
    if unsigned:
        labels.append("P is not negated when det(P[:, :3]) < 0" if unnegated else "the signs of K's diagonal are not fixed")
        problems.append(f"K has a negative diagonal entry ({format_matrix(np.diag(K))}): "
                        + (sign_fix if unnegated else "RQ is unique only up to signs; " + SIGNS_HINT.said(t)))
    if not rotation:
        problems.append("R is not a rotation (R R^T != I)" + _triangular_factor(R))
        if _triangular_factor(R):
            labels.append(TRIANGULAR_R)
    elif np.linalg.det(R) < 0 and not unsigned and not unnegated and _the_negated_camera(R, tv, R_true, t_true) \
            and INVERTED_SIGN_TEST.found(code_of(t).reachable(["decompose_camera_matrix"])):
        # (K right, R and t the true ones negated: K [R | t] = -P -- the sign test on det(P[:, :3]) went the
        # wrong way: a P of det > 0 negated, or one of det < 0 left by code that negates P under a test)
        labels.append(SIGN_TEST_INVERTED)
        problems.append(measured("det(R) = -1, with K right and R and t the true ones times -1 (K [R | t] = -P, "
                                 f"det(P[:, :3]) {'< 0' if negative else '> 0'} here)")
                        + from_code(f": {SIGN_TEST_INVERTED}; negate P only where det(P[:, :3]) < 0"))
    elif np.linalg.det(R) < 0 and not unsigned and not unnegated and other_block:
        # (the code negates P under a test of another block's determinant, read: its sign is not det(P[:, :3])'s)
        labels.append(SIGN_TEST_MISSED)
        problems.append(f"det(R) = -1 (det(P[:, :3]) {'<' if negative else '>'} 0 here): "
                        + from_code(f"your code tests `{other_block}`: {SIGN_TEST_MISSED}"))
    elif np.linalg.det(R) < 0 and not unsigned and not unnegated and negative \
            and _positive_multiple(K @ R, np.asarray(P, float)[:, :3]) \
            and SIGNS_HINT.contradicts(code_of(t), ["decompose_camera_matrix"]):
        # (K R is the given block itself, det < 0, from code that negates P and fixes RQ's signs: the block
        # decomposed was never negated -- `M = P[:, :3]` above `P = -P`. Without a sign fix, K divided by a
        # negative K[2, 2] gives the same product: RQ's signs are the cause there.)
        labels.append(BLOCK_NOT_NEGATED)
        problems.append("det(R) = -1: " + measured("K R is P[:, :3] itself times a positive number, and det(P[:, :3]) "
                                                   "< 0 here: the block decomposed was not negated")
                        + "; " + sign_fix)
    elif np.linalg.det(R) < 0 and not unsigned and not triangular and not unnegated:
        # (K R is no RQ of the block: the signs fixed after it follow from its diagonal, whatever they are)
        problems.append("det(R) = -1 as well")
    elif np.linalg.det(R) < 0 and not unsigned and not unnegated and not any(
            _positive_multiple(K @ R, sign * np.asarray(P, float)[:, :3]) for sign in (1.0, -1.0)):
        # (K R is not the block, nor the block negated, at any scale: what was factored is not the block -- signs
        # fixed after the factoring are not the cause, whatever they are: an entrywise M ** -1 for M^-1, say)
        problems.append("det(R) = -1, and " + measured("K R is not P[:, :3] (nor -P[:, :3]) at any scale: K and R "
                                                       "do not factor the block given")
                        + where_to_look(measured("; look at what the factoring step is given")))
    elif np.linalg.det(R) < 0 and not unsigned:   # with K's signs unfixed, det(R) = -1 follows from them
        flips = SIGNS_HINT.contradicts(code_of(t), ["decompose_camera_matrix"]) \
            and not FLIPS_BOTH_SIDES.found(code_of(t).reachable(["decompose_camera_matrix"]))
        labels.append("P is not negated when det(P[:, :3]) < 0" if unnegated else
                      "K's columns are flipped without R's rows" if flips else "the signs of K's diagonal are not fixed")
        problems.append("det(R) = -1: " + (
            sign_fix if unnegated else
            "with a block of det > 0 decomposed, that comes from a sign flip of K's columns without the same rows "
            "of R" if flips else
            "with a block of det > 0 decomposed, K had an odd number of negative diagonal entries before it was "
            "normalised; RQ is unique only up to signs: " + SIGNS_HINT.said(t)))
    if problems:
        # a named mistake only when the problems point to one cause
        t.fail(f"{what}: " + "; ".join(problems) + ".", mistake=labels[0] if len(set(labels)) == 1 else "")
    Kn = K_true / K_true[2, 2]
    tolerances = {"K": at_precision(1e-6 * np.abs(Kn).max(), magnitude(Kn)), "R": at_precision(1e-6),
                  "t": at_precision(1e-6 * magnitude(t_true), magnitude(t_true))}
    ok = (np.abs(K - Kn).max() <= tolerances["K"] and np.abs(R - R_true).max() <= tolerances["R"]
          and np.abs(tv - t_true).max() <= tolerances["t"])
    if ok:
        return
    for mistake in decomposition_explained((K, R, tv), Kn, R_true, t_true):
        if mistake in decomposition_on_probe(t):
            t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    disagreeing = t_against_p(P, K, R, tv)
    if disagreeing:
        t.fail(f"{what}: K, R and t do not come from the same P: {disagreeing[0]}.", mistake=disagreeing[1])
    recomposed = K @ np.column_stack([R, tv])
    if projective_distance(R @ K, np.asarray(P, float)[:, :3]) <= at_precision(1e-6) < projective_distance(recomposed, P):
        t.fail(f"{what} is wrong: R K gives back P[:, :3], not K R: it looks like a QR decomposition "
               "(M = Q U) was used where P = K [R | t] needs an RQ decomposition (M = K R).",
               mistake="QR was used instead of RQ")
    if projective_distance(recomposed, P) > at_precision(1e-6):
        t.fail(f"{what}: K [R | t] does not give back P (distance {projective_distance(recomposed, P):.2g} "
               "after normalising scale).")
    wrong = [name for name, part, right in (("K", K, Kn), ("R", R, R_true), ("t", tv, t_true))
             if np.abs(part - right).max() > tolerances[name]]
    first = f"{what}: {' and '.join(wrong)} differ{'s' if len(wrong) == 1 else ''} from the camera's"
    if "K" in wrong:
        first += f" (K is wrong {where_matrices_differ(K, Kn)})"
    shown, wanted = format_arrays_apart(K, Kn)
    t.fail(f"{first}.\nK\n{shown}\nexpected\n{wanted}")


def t_against_p(P, K, R, tv) -> tuple[str, str] | None:
    """(sentence, mistake) when the returned K and R give back P's left block, P[:, :3] = s K R for a
    scale s, but t is not the t of the same P, K^-1 P[:, 3] / s: the results of one decomposition
    disagree. Told apart by the measured factor c with t = c K^-1 P[:, 3] / s: c = s (t solved
    from P before its scale is divided out), c = -1 (t from P while K and R come from -P), any
    other factor or none. None when K R is not P's left block (the other judgements say so) or
    t agrees."""
    P, K, R, tv = (np.asarray(a, np.float64) for a in (P, K, R, tv))
    KR, M = K @ R, P[:, :3]
    s = float(np.sum(KR * M) / np.sum(KR * KR)) if np.any(KR) else 0.0
    if s == 0 or np.abs(s * KR - M).max() > at_precision(1e-6 * np.abs(M).max(), magnitude(M)):
        return None
    try:
        own = np.linalg.solve(K, P[:, 3]) / s
    except np.linalg.LinAlgError:
        return None
    size = max(magnitude(own), 1e-12)
    if np.abs(tv - own).max() <= at_precision(1e-6 * size, size):
        return None
    told = f"with your K and R, P[:, :3] = s K R (s = {s:.4g}) and its t is K^-1 P[:, 3] / s = {format_matrix(own)}, " \
           f"yours is {format_matrix(tv)}"
    c = float(tv @ own / (own @ own)) if np.any(own) else 0.0
    if np.abs(tv - c * own).max() <= at_precision(1e-6 * size * max(1.0, abs(c)), size):
        if abs(s) != 1 and abs(c - s) <= 1e-6 * abs(s):
            return (f"{told}: t is K^-1 P[:, 3] without dividing by P's scale s",
                    "t is solved from P without dividing by its scale")
        if abs(c + 1) <= 1e-6:
            return (f"{told}: " + measured("t has the opposite sign (K and R come from -P, t from P: negate P before "
                                           "solving for t too)"), "t is solved from P while K and R come from -P")
        if c > 0 and abs(np.linalg.norm(tv) - 1.0) <= 1e-6:
            # (the right direction, made of length 1: as an essential matrix's t is, known only up to scale)
            return (f"{told}: " + measured(f"t points the right way but has length 1, where P's is {np.linalg.norm(own):.4g}: "
                                           "t is normalised to unit length; P fixes its scale (K[2, 2] = 1), keep it"),
                    "t is normalised to unit length")
        if c > 0:
            return (f"{told}: " + measured(f"t points the right way, {c:.4g} times as long"), "t is rescaled")
    return f"{told}: t must be solved from the same P as K and R, t = K^-1 P[:, 3] / s", \
        "t does not come from the same P as K and R"


def decomposition_explained(got, Kn, R_true, t_true) -> list[str]:
    """The usual decomposition mistakes whose (K, R, t) is ``got``."""
    K, R, tv = got
    return [mistake for mistake, (Km, Rm, tm) in truth.decomposition_mistakes(Kn, R_true, t_true).items()
            if np.abs(K - Km).max() <= 1e-4 * np.abs(Km).max() and np.abs(R - Rm).max() <= 1e-4
            and np.abs(tv - tm).max() <= 1e-4 * max(1.0, np.abs(tm).max())]


def decomposition_on_probe(t: Trial) -> list[str]:
    """The mistakes that explain the decomposition of another camera (the confirmation probe)."""
    P, K, R, tv, _ = truth.random_camera_matrix(10_030)

    def answer():
        got = t.call("decompose_camera_matrix", P)
        if not (isinstance(got, (tuple, list)) and len(got) == 3):
            return None
        parts = [np.asarray(part, dtype=np.float64) for part in got]
        if [part.size for part in parts] != [9, 9, 3] or not all(np.isfinite(part).all() for part in parts):
            return None
        return parts[0].reshape(3, 3), parts[1].reshape(3, 3), parts[2].reshape(3)

    got = t.probe(f"decompose_camera_matrix/{fingerprint(P)}", answer)
    return [] if got is None else decomposition_explained(got, K / K[2, 2], R, tv)


SLICED_COLUMN = expr("_[:, 3:]").saying("slices the last column as P[:, 3:]")


@ex5.check("decompose_camera_matrix of P = K [R | t], for a camera at the world origin too (t = 0)", points=3)
def decompose_example(t):
    _, K, R, tv, _ = truth.random_camera_matrix(501)
    judge_decomposition(t, truth.camera(K, R, tv), K, R, tv)
    # (the world's origin on the camera's principal plane -- a camera at the origin -- makes P[2, 3] = 0: the
    # API's P = K [R | t] for any t, and the first camera of every two-view setup, K [I | 0])
    origin = np.zeros(3)
    judge_decomposition(t, truth.camera(K, R, origin), K, R, origin, what="decompose_camera_matrix(K [R | 0])")


@ex5.check("decompose_camera_matrix for P at any scale and sign", points=3)
def decompose_property(t):
    def holds(seed):
        P, K, R, tv, _ = truth.random_camera_matrix(seed)
        judge_decomposition(t, P, K, R, tv, what="decompose_camera_matrix(s * K [R | t])")

    t.for_all(seeds, holds, max_examples=15,
              describe=lambda s: f"fixtures.lab10.random_camera_matrix({s}) (negative scale included)")


@ex5.check("decompose_camera_matrix returns t as a (3,) vector, the API's shape", points=1)
def decompose_t_shape(t):
    """The values are the other checks' (which read a (3, 1) column's numbers too); this one asks the shape
    the API gives t, so that `R @ X + t` and `np.hstack([R, t[:, None]])` work as written."""
    _, K, R, tv, _ = truth.random_camera_matrix(501)
    got = t.call("decompose_camera_matrix", truth.camera(K, R, tv))
    shape = getattr(got[2], "shape", None) if isinstance(got, (tuple, list)) and len(got) == 3 else None
    if shape in ((3, 1), (1, 3)):
        column = SLICED_COLUMN.found(code_of(t).reachable(["decompose_camera_matrix"]))
        t.fail(measured(f"decompose_camera_matrix(P)[2] (t) has shape {shape}; the API's t is a (3,) vector "
                        "(its numbers are judged by the other checks)")
               + (from_code(f": your code {column}, a (3, 1) column; P[:, 3] is the (3,) vector.") if column
                  else measured(": give it as a (3,) vector (t.ravel()).")),
               mistake="t is returned as a column, not a (3,) vector")
    return passed(measured("t has the API's shape" if shape == (3,) else "t's form is the other checks' to judge"))


SIGN_OF_THE_CENTRE = "it returned R^T t; the centre is C = -R^T t (the sign is wrong)"


def center_mistakes(R, tv) -> dict:
    return {
        "it returned t; the centre is C = -R^T t (the point with P [C, 1] = 0)": tv,
        "it returned -t; the centre is C = -R^T t (the rotation matters)": -tv,
        "it returned -R t; the centre is C = -R^T t (R transposed)": -R @ tv,
        SIGN_OF_THE_CENTRE: R.T @ tv,
    }


def minor_sign_mistakes(R, tv) -> dict:
    """The centre from P's 3x3 minors, C = (det[p2 p3 p4], -det[p1 p3 p4], det[p1 p2 p4], -det[p1 p2 p3]),
    with the alternating signs left out: all four taken +, Y's and W's signs are both lost, so X and Z come
    out negated; only Y's sign left out, Y comes out negated; only W's, the whole centre (-C, which is R^T t:
    said so of code made of minors, in the place of :data:`SIGN_OF_THE_CENTRE`)."""
    C = -R.T @ tv
    return {
        "the 3x3 minors of P enter C with alternating signs (+, -, +, -): with all four taken +, X and Z come "
        "out with the wrong sign": C * [-1.0, 1.0, -1.0],
        "the minor for Y, det[p1 p3 p4], enters C with a minus sign (the signs alternate +, -, +, -): Y comes out "
        "with the wrong sign": C * [1.0, -1.0, 1.0],
        "the 3x3 minors enter the homogeneous centre with alternating signs (+, -, +, -: W = -det[p1 p2 p3]), "
        "and W's sign is flipped against X's, Y's and Z's (W taken +, or X, Y, Z all negated): every coordinate "
        "comes out with the wrong sign (-C)": -C,
    }


def centre_mistakes_for(R, tv, minors: bool) -> dict:
    """The centre's named mistakes; for code made of P's minors, its sign told as the minors' (read)."""
    if not minors:
        return center_mistakes(R, tv)
    named = {name: value for name, value in center_mistakes(R, tv).items() if name != SIGN_OF_THE_CENTRE}
    return {**named, **minor_sign_mistakes(R, tv)}


PRINCIPAL_AXIS = "the principal axis (m3, det(M) m3) returned for the camera centre"


def along(vector, direction) -> bool:
    """Whether ``vector`` (not 0) lies along ``direction``, either way (to within float32 rounding: an
    answer computed in single precision is judged as one in double)."""
    vector, direction = np.asarray(vector, float), np.asarray(direction, float)
    norms = np.linalg.norm(vector) * np.linalg.norm(direction)
    return bool(norms > 0 and abs(abs(float(vector @ direction)) / norms - 1.0) <= 1e-6)


def judge_center(t: Trial, P, R, tv):
    what = "camera_center(P)"
    got = t.call("camera_center", P)
    if isinstance(got, np.ndarray) and got.shape == (4,):
        t.fail(f"{what} returned a (4,) homogeneous vector; expected the (3,) centre: (X, Y, Z) / W of the "
               "homogeneous (X, Y, Z, W)", mistake="the homogeneous centre returned (4 entries)")
    got = t.expect_array(got, what, shape=(3,), kind="iuf", finite=True)
    C = -R.T @ tv
    scale = magnitude(C)
    if np.abs(got - C).max() <= at_precision(1e-6 * scale, scale):
        return
    # (read from the code: the centre made of P's 3x3 minors, Hartley & Zisserman's formula)
    minors = bool(calls("np.linalg.det").found(code_of(t).reachable(["camera_center"])))
    mistakes = centre_mistakes_for(R, tv, minors)
    null = np.append(C, 1.0) / np.linalg.norm(np.append(C, 1.0))      # the SVD's null vector, up to sign
    if min(np.abs(got - null[:3]).max(), np.abs(got + null[:3]).max()) <= at_precision(1e-6):
        t.fail(f"{what} is wrong: it returned the first three entries of the null vector of P without "
               "dividing by the fourth (C = v[:3] / v[3]).", mistake="the null vector is not de-homogenised")
    P2, _, R2, tv2, _ = truth.random_camera_matrix(10_031)
    probe = call_probe(t, "camera_center", (P2,), candidates=lambda: centre_mistakes_for(R2, tv2, minors),
                       truth=-R2.T @ tv2,
                       shape=(3,), tolerance=1e-6 * magnitude(-R2.T @ tv2))
    mistake = name_mistake(t, got, mistakes, lambda a, b: float(np.abs(a - b).max()), 1e-6 * scale, truth=C,
                           probe=probe)
    if mistake:
        t.fail(f"{what} is wrong: {mistake}.", mistake=mistake)
    form = scale_form(got, C)
    if form is not None:
        t.fail(f"{what} is wrong: {form.sentence}.", mistake=form.mistake)
    if along(got, np.asarray(P, float)[2, :3]) and not along(C, np.asarray(P, float)[2, :3]):
        # (the viewing direction: the third row m3 of M = P[:, :3], det(M) m3 pointing the way the camera looks)
        t.fail(f"{what} is wrong: it returned a vector along the principal axis (the third row m3 of M = P[:, :3], "
               "the direction the camera looks in, as det(M) m3 is), not the camera centre: the point C with "
               "P [C, 1] = 0, C = -M^-1 p4.", mistake=PRINCIPAL_AXIS)
    residual = np.linalg.norm(P @ np.append(got, 1.0)) / np.linalg.norm(P)
    shown, wanted = format_arrays_apart(got, C)
    t.fail(f"{what} returned {shown}; expected {wanted} (|P [C, 1]| / |P| = {residual:.2g}, should be 0)")


# P is defined up to scale, and its last entry P[2, 3] = t_z is 0 for a camera whose principal plane holds
# the world origin: P / P[2, 3] (a homography's habit) has no centre there.
DIVIDES_BY_P34 = divides_by("P[2, 3]", "P[-1, -1]", "P[2, -1]", "P[-1, 3]", "P[2][3]", "P[-1][-1]",
                            says="divides P by P[2, 3]")   # (the API's name of the camera: P's own entry only)
P34_IS_ZERO = "P divided by P[2, 3], which is 0"


@ex5.check("camera_center(P) satisfies P [C, 1] = 0", points=2)
def center_check(t):
    for seed in (511, 512, 513):
        P, K, R, tv, _ = truth.random_camera_matrix(seed)
        judge_center(t, P, R, tv)
    # a camera far from the world origin (3 m away in millimetres): the SVD's unit null vector has a last
    # entry of about 1 / |C|, 3e-4, which is no camera at infinity
    _, K, R, _, s = truth.random_camera_matrix(515)
    tv = -R @ np.array([1500.0, -800.0, 3000.0])
    judge_center(t, s * K @ np.column_stack([R, tv]), R, tv)
    # the world origin on the camera's principal plane: t_z = 0, so P[2, 3] = 0
    _, K, R, tv, s = truth.random_camera_matrix(514)
    tv = np.array([tv[0], tv[1], 0.0])
    P = s * K @ np.column_stack([R, tv])
    try:
        judge_center(t, P, R, tv)
    except Fail as failure:
        if DIVIDES_BY_P34.found(code_of(t).reachable(["camera_center"])):
            said = failure.message.removeprefix("camera_center(P) ").rstrip(".")
            t.fail(f"camera_center(P) for a camera with P[2, 3] = 0 (the world origin lies on its principal plane, "
                   f"t_z = 0) {said}. "
                   + from_code("Your code divides P by P[2, 3], which is 0 here: P is defined up to scale, and its "
                               "centre needs no normalisation (C = -M^-1 p4, or P's null vector de-homogenised)."),
                   mistake=P34_IS_ZERO)
        raise


# ================================================================== ex6 pose from a chessboard
ex6 = lab.exercise("ex6", "Pose from a chessboard", functions=[
    "estimate_pose(image, pattern_size, square_size, K, dist=None)"])

ANGLE_TOLERANCE = 1.0        # degrees
TRANSLATION_TOLERANCE = 0.01  # fraction of the distance
REPROJECTION_TOLERANCE = 0.75  # pixels, max over the corners


def draw_corners(image, true_corners, got_corners):
    """The image with the true corners (green) and the student's reprojection (red)."""
    canvas = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image.copy()
    for x, y in np.asarray(true_corners, float).reshape(-1, 2):
        cv2.circle(canvas, (int(round(x)), int(round(y))), 4, (0, 200, 0), 1)
    for x, y in np.asarray(got_corners, float).reshape(-1, 2):
        if np.isfinite(x) and np.isfinite(y) and abs(x) < 1e5 and abs(y) < 1e5:
            cv2.circle(canvas, (int(round(x)), int(round(y))), 2, (0, 0, 255), -1)
    return canvas


def _unpack_pose(t: Trial, what, got, n_corners):
    if not (isinstance(got, (tuple, list)) and len(got) == 3):
        t.fail(f"{what} should return a triple (rvec, tvec, reprojected)")
    rvec, tvec, reprojected = got
    if isinstance(rvec, np.ndarray) and rvec.shape == (3, 3):
        t.fail(f"{what} returned a 3x3 rotation matrix as rvec; " + measured(
            "return the (3,) Rodrigues vector (what cv2.solvePnP gives; cv2.Rodrigues converts)"))
    rvec = t.expect_array(np.asarray(rvec).reshape(-1) if isinstance(rvec, np.ndarray) and rvec.size == 3 else rvec,
                          f"{what}[0] (rvec)", shape=(3,), kind="f")
    tvec = t.expect_array(np.asarray(tvec).reshape(-1) if isinstance(tvec, np.ndarray) and tvec.size == 3 else tvec,
                          f"{what}[1] (tvec)", shape=(3,), kind="f")
    if isinstance(reprojected, np.ndarray) and reprojected.shape == (n_corners, 1, 2):
        reprojected = reprojected.reshape(-1, 2)
    reprojected = expect_points(t, f"{what}[2] (reprojected)", reprojected, (n_corners, 2)) \
        if n_corners else t.expect_array(reprojected, f"{what}[2] (reprojected)", shape=(0, 2))
    return rvec, tvec, reprojected


AXES_EXCHANGED = "the board's x and y axes are exchanged (turned by 90 degrees in its plane)"
OBJECT_XY_EXCHANGED = "the object points' x and y are exchanged (the board turned over about its diagonal)"
OBJECT_XY_HINT = Hint(
    "that is the pose of object points whose x and y are exchanged; x runs along a row of corners, fastest: "
    "np.mgrid[0:cols, 0:rows].T.reshape(-1, 2).", asks=OBJECT_POINTS_ROW_BY_ROW,
    instead="that is the pose of object points whose x and y are exchanged, though your code {found}: check "
            "the corners' order and what reaches cv2.solvePnP.")
PATTERN_AXES_HINT = Hint(
    "passed to cv2.findChessboardCorners as given, and the object points run row by row with x "
    "fastest: np.mgrid[0:cols, 0:rows].T.reshape(-1, 2).", asks=OBJECT_POINTS_ROW_BY_ROW,
    instead="and your code {found}: check that pattern_size reaches cv2.findChessboardCorners "
            "as given.")
def _projections(function) -> list[ast.Call]:
    return [n for n in walk(function) if isinstance(n, ast.Call)
            and _path(n.func).rsplit(".", 1)[-1] == "projectPoints"]


def _projects_in_order(function) -> bool:
    """A cv2.projectPoints call given five arguments not visibly out of order (no ``tvec`` where rvec goes, no
    ``dist`` where K goes, and the reverse)."""
    def named(node, *words) -> bool:
        return any(isinstance(n, ast.Name) and any(w in n.id.lower() for w in words) for n in walk(node))
    for call in _projections(function):
        given = list(call.args) + [k.value for k in call.keywords]
        if len(given) < 5:
            continue
        if len(call.args) >= 5 and (named(call.args[1], "tvec", "trans") or named(call.args[2], "rvec", "rot")
                                    or named(call.args[3], "dist") or named(call.args[4], "mtx", "camera")
                                    or (isinstance(call.args[4], ast.Name) and call.args[4].id == "K")):
            continue
        return True
    return False


def _returns_the_projection(function) -> bool:
    """A ``return`` holding cv2.projectPoints' result: the call itself, or a name it (or a value made from it)
    is stored in."""
    held = set()
    for _ in range(3):   # a few steps: projected, _ = cv2.projectPoints(...); out = projected.reshape(-1, 2)
        for node in walk(function):
            if isinstance(node, ast.Assign) and (_projections(node.value) or any(
                    isinstance(n, ast.Name) and n.id in held for n in walk(node.value))):
                held |= {n.id for target in node.targets for n in walk(target) if isinstance(n, ast.Name)}
    return any(isinstance(node, ast.Return) and node.value is not None
               and (_projections(node.value) or any(isinstance(n, ast.Name) and n.id in held
                                                    for n in walk(node.value)))
               for node in walk(function))


PROJECT_POINTS_HINT = Hint(
    "project the object points with rvec, tvec, K and dist (cv2.projectPoints), in the same order.",
    asks=calls("cv2.projectPoints"),
    instead="your code calls cv2.projectPoints: " + checklist(
        "", ("it is given the object points, rvec, tvec, K and dist of this pose, in that order",
             Predicate("gives cv2.projectPoints its arguments in order", _projects_in_order)),
        ("its output is what is returned", Predicate("returns cv2.projectPoints' output", _returns_the_projection)),
        # (the pose and points given, in order, are the first item: nothing is left to point at)
        none_left="") + ".")
CORNER_ORDER_HINT = Hint(
    ": np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size.", asks=OBJECT_POINTS_ROW_BY_ROW,
    instead=" (your code {found}: check how pattern_size is read, as (cols, rows)).")
DIST_TO_PNP_HINT = Hint(
    "pass it to cv2.solvePnP (and to cv2.projectPoints).", asks=DIST_TO_PNP,
    instead="your code {found}, but not the dist given (None or zeros?).")
# (said to code that already gives cv2.projectPoints the distortion: the call it misses alone)
DIST_TO_PNP_ONLY_HINT = Hint(
    "pass it to cv2.solvePnP too.", asks=DIST_TO_PNP,
    instead="your code {found}, but not the dist given (None or zeros?).")


def dist_to_pnp_said(t: Trial) -> str:
    """What the pose's ignored distortion asks of ``t``'s code: a call the code already gives dist is not named."""
    projects = DIST_TO_PROJECT.found(code_of(t).reachable(functions_read(t)))
    return (DIST_TO_PNP_ONLY_HINT if projects else DIST_TO_PNP_HINT).said(t)


LAYOUT_SHARE = 0.75   # of a pose check's points, for a right pose and right corners in cv2.projectPoints's (M, 1, 2)


def judge_pose(t: Trial, what, got, image, R, tv, corners, pattern, square, K, dist=None, show=True):
    """Judge (rvec, tvec, reprojected) against the true pose, up to the board's symmetry."""
    # (the corners as cv2.projectPoints returns them, (M, 1, 2), are judged as points; what the API asks, (M, 2), is
    # told where everything else is right)
    layout = isinstance(got, (tuple, list)) and len(got) == 3 and isinstance(got[2], np.ndarray) \
        and got[2].shape == (len(corners), 1, 2) and len(corners) > 0
    rvec, tvec, reprojected = _unpack_pose(t, what, got, len(corners))
    if show:
        t.images(f"{what}: true corners (green rings) and your reprojection (red dots)",
                 image=draw_corners(image, corners, reprojected))
    if not (np.all(np.isfinite(rvec)) and np.all(np.isfinite(tvec))):
        t.fail(f"{what}: no pose (NaN) although the whole board is visible: is pattern_size passed "
               "as (cols, rows) of inner corners, exactly as given?")
    angle, shift, alternative = truth.pose_error(rvec, tvec, R, tv, pattern, square)
    distance = float(np.linalg.norm(tv))
    rel = shift / distance
    perm = truth.board_symmetries(pattern, square)[alternative][2]
    reproj_error = np.linalg.norm(reprojected - corners[perm], axis=1).max()
    if angle <= ANGLE_TOLERANCE and rel <= TRANSLATION_TOLERANCE:
        if reproj_error > REPROJECTION_TOLERANCE:
            slip = _reprojection_slip(reprojected, rvec, tvec, pattern, square, K, dist)
            if slip and _slip_on_probe(t, dist is not None) != slip:
                slip = None
            if slip:
                return partial(0.5, f"{what}: the pose is right, but the reprojected corners are wrong: "
                                    f"it looks like {slip}.", mistake=slip)
            off = f"rotation off by {angle:.2f} deg, translation by {rel:.2%}"
            missed = f"{format_apart(reproj_error, REPROJECTION_TOLERANCE, 2)} px"
            if _apart_from_own_projection(reprojected, rvec, tvec, pattern, square, K, dist) <= CONSISTENCY_TOLERANCE:
                # (measured: the corners returned are the returned pose's own projection -- the projection step
                # is right; the pose is off by just enough to move them)
                # (read: where the code calls cv2.solvePnP, its inputs are the place; else the pose's own computation)
                solves = calls("cv2.solvePnP").found(code_of(t).reachable(functions_read(t)))
                look = from_code("look at what cv2.solvePnP is given (the corners as found, the object points, K "
                                 "and dist as they are)") if solves else \
                    measured("look at how the pose is computed from the corners")
                return partial(0.5, measured(
                    f"{what}: the corners returned are your pose's own projection, but they miss the corners by up "
                    f"to {missed}: the pose is near ({off}) but not as exact as cv2.solvePnP gives from the "
                    "detected corners (refined), so ") + look + ".")
            return partial(0.5, f"{what}: the pose is right ({off}), but the reprojected corners miss the corners by "
                                f"up to {missed}: " + PROJECT_POINTS_HINT.said(t))
        apart = _apart_from_own_projection(reprojected, rvec, tvec, pattern, square, K, dist)
        if apart > CONSISTENCY_TOLERANCE:
            return partial(0.5, measured(f"{what}: the pose is right, but the corners returned are not the board "
                                         f"projected with it: they are up to {apart:.3g} px from where "
                                         f"cv2.projectPoints(object points, rvec, tvec, K, dist) puts the corners with "
                                         f"your own rvec and tvec (at most {CONSISTENCY_TOLERANCE} px expected)")
                           + _detected_returned(image, pattern, reprojected),
                           mistake=DETECTED_RETURNED if _detected_returned(image, pattern, reprojected) else "")
        if layout:
            form = shape_form((len(corners), 1, 2), (len(corners), 2))
            return partial(LAYOUT_SHARE, measured(
                f"{what}: the pose and the reprojected corners are right, but the corners are returned as an array of "
                f"shape {(len(corners), 1, 2)} where ({len(corners)}, 2) is asked: {form.sentence} (cv2.projectPoints "
                "gives that layout)"), mistake=form.mistake)
        return passed(f"rotation within {angle:.2f} deg, translation within {rel:.2%}, "
                      f"reprojection within {reproj_error:.2f} px")
    # diagnosis
    R_got = scene.rotation_from_rvec(rvec)
    if angle <= ANGLE_TOLERANCE:
        M, c, _ = truth.board_symmetries(pattern, square)[alternative]
        t_alt = R @ c + tv
        factor = float(tvec @ t_alt / (t_alt @ t_alt))
        # a scale slip changes tvec by a clear factor (1 / square_size, 1 / square_size^2...),
        # not by the few percent other slips (such as an ignored dist) give
        if factor > 0 and abs(np.log(factor)) > np.log(1.5) and \
                np.linalg.norm(tvec - factor * t_alt) <= TRANSLATION_TOLERANCE * factor * distance:
            ignored = "square_size is ignored" if abs(factor * square - 1) < 0.02 else \
                "the object points are not in the units of square_size"
            t.fail(f"{what}: the rotation is right but tvec is {factor:.3g} times the true one: {ignored}: "
                   "the object points must be in real units, i.e. the grid multiplied by square_size.",
                   mistake=ignored)
    fail_if_axes_exchanged(t, what, R_got, R)
    if truth.rotation_angle_deg(R_got, R.T) <= 2 * ANGLE_TOLERANCE and rel <= TRANSLATION_TOLERANCE:
        t.fail(f"{what}: the translation is right but the rotation is transposed (rvec has the wrong "
               "sign): " + measured("return rvec as cv2.solvePnP gives it, the board's rotation into the camera "
                                    "frame."),
               mistake="the rotation is transposed")
    C = -R.T @ tv
    if truth.rotation_angle_deg(R_got, R.T) <= 2 * ANGLE_TOLERANCE and np.linalg.norm(tvec - C) < 0.05 * distance:
        t.fail(f"{what}: that is the camera's pose in the board's frame (R^T, -R^T t): the pose is inverted; "
               + measured("the task wants the board's pose in the camera frame, as cv2.solvePnP returns it."),
               mistake="the pose is inverted (the camera's pose in the board's frame)")
    if dist is not None:
        objp = scene.chessboard_object_points(pattern, square)
        found, detected = cv2.findChessboardCorners(image, tuple(pattern))
        if found:
            _, r0, t0 = cv2.solvePnP(objp, detected, K, None)
            a0, s0, _ = truth.pose_error(r0.ravel(), t0.ravel(), R, tv, pattern, square)
            if truth.rotation_angle_deg(R_got, scene.rotation_from_rvec(r0.ravel())) < 0.3 and \
                    np.linalg.norm(tvec - t0.ravel()) < 0.003 * distance and _dist_ignored_on_probe(t):
                t.fail(f"{what}: the lens distortion dist is ignored: " + dist_to_pnp_said(t),
                       mistake="dist is ignored")
    for (slip, label) in _wrong_grids_explaining(rvec, tvec, pattern, square, corners, K, dist):
        if (slip, label) in _wrong_grids_on_probe(t):
            t.fail(f"{what}: {slip}; OpenCV gives the corners row by row, x fastest" + CORNER_ORDER_HINT.said(t),
                   mistake=label)
    t.fail(f"{what}: the pose is off by {format_apart(angle, ANGLE_TOLERANCE, 2)} degrees and "
           f"{format_apart(rel, TRANSLATION_TOLERANCE, 2, percent=True)} of the distance (at most "
           f"{ANGLE_TOLERANCE:g} degrees and {TRANSLATION_TOLERANCE:.0%} accepted; reprojection off by up to "
           f"{reproj_error:.1f} px).")


def fail_if_axes_exchanged(t: Trial, what: str, R_got, R) -> None:
    """Fail naming the board's x and y axes exchanged: the plane right, the pose turned by 90 degrees in it
    (pattern_size read as (rows, cols): the corners found in another order), or turned over about its diagonal,
    its normal reversed (the object points' x and y exchanged: a reflection, which a rotation makes proper by
    turning z round)."""
    facing = float(R_got[:, 2] @ R[:, 2])
    normal_angle = np.degrees(np.arccos(np.clip(abs(facing), -1.0, 1.0)))
    in_plane = np.degrees(np.arccos(np.clip(abs(R_got[:, 0] @ R[:, 0]), -1.0, 1.0)))
    if normal_angle >= 2.0 or abs(in_plane - 90.0) >= 2.0:
        return
    if facing > 0:
        t.fail(f"{what}: the board plane is right but its x and y axes are exchanged (the pose is turned "
               "by 90 degrees in the board plane): pattern_size is (cols, rows) = (inner corners per row, "
               "per column), " + PATTERN_AXES_HINT.said(t),
               mistake=AXES_EXCHANGED)
    t.fail(f"{what}: the board plane is right but the board is turned over about its diagonal (its x and y axes "
           "exchanged, its z axis reversed): " + OBJECT_XY_HINT.said(t), mistake=OBJECT_XY_EXCHANGED)


def _wrong_grids_explaining(rvec, tvec, pattern, square, corners, K, dist) -> list:
    """The (slip, label) of each wrongly built grid whose cv2.solvePnP pose is (rvec, tvec)."""
    R_got = scene.rotation_from_rvec(rvec)
    distance = float(np.linalg.norm(tvec)) or 1.0
    return [key for key, (r_slip, t_slip) in _poses_from_wrong_grids(pattern, square, corners, K, dist).items()
            if truth.rotation_angle_deg(R_got, scene.rotation_from_rvec(r_slip)) < 2 * ANGLE_TOLERANCE
            and np.linalg.norm(tvec - t_slip) < 2 * TRANSLATION_TOLERANCE * distance]


# The pose checks' confirmation probe: another view of the board, or the same board through
# another lens when dist matters (see autograder.engine.judges.Probe).
POSE_PROBE_VIEW = ((-0.2, -0.35, 0.05), 12.0, 3.9, (0.15, -0.05))


def _pose_on_probe(t: Trial, with_dist: bool):
    """(rvec, tvec, reprojected, corners, dist) of the student's pose on the probe view, or None."""
    K, pattern, square = truth.POSE_K, truth.POSE_PATTERN, truth.POSE_SQUARE
    if with_dist:
        dist = np.array(UNDISTORT_PROBE_DIST)
        image, _, R, tv, _ = truth.distorted_view(UNDISTORT_PROBE_DIST)
        objp = scene.chessboard_object_points(pattern, square)
        seen, _ = cv2.projectPoints(objp, scene.rvec_from_rotation(R), tv, K, dist)
        corners = seen.reshape(-1, 2)
    else:
        dist = None
        image, R, tv, corners = truth.render_pose_view(*POSE_PROBE_VIEW)

    def answer():
        _, got = _call_pose(t, image, pattern, square, K, dist)
        if not (isinstance(got, (tuple, list)) and len(got) == 3):
            return None
        rvec, tvec, reprojected = (np.asarray(part, dtype=np.float64) for part in got)
        if rvec.size != 3 or tvec.size != 3 or reprojected.size != corners.size:
            return None
        return rvec.reshape(3), tvec.reshape(3), reprojected.reshape(-1, 2), corners, dist

    return t.probe(f"estimate_pose/probe/{with_dist}", answer)


def _slip_on_probe(t: Trial, with_dist: bool):
    got = _pose_on_probe(t, with_dist)
    if got is None:
        return None
    rvec, tvec, reprojected, _, dist = got
    return _reprojection_slip(reprojected, rvec, tvec, truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_K, dist)


def _dist_ignored_on_probe(t: Trial) -> bool:
    """Whether through the probe's lens too the pose is cv2.solvePnP's without dist."""
    got = _pose_on_probe(t, with_dist=True)
    if got is None:
        return False
    rvec, tvec, _, corners, _ = got
    objp = scene.chessboard_object_points(truth.POSE_PATTERN, truth.POSE_SQUARE)
    _, r0, t0 = cv2.solvePnP(objp, corners.reshape(-1, 1, 2), truth.POSE_K, None)
    return truth.rotation_angle_deg(scene.rotation_from_rvec(rvec), scene.rotation_from_rvec(r0.ravel())) < 0.3 \
        and np.linalg.norm(tvec - t0.ravel()) < 0.003 * np.linalg.norm(t0)


def _wrong_grids_on_probe(t: Trial) -> list:
    got = _pose_on_probe(t, with_dist=False)
    if got is None:
        return []
    rvec, tvec, _, corners, _ = got
    return _wrong_grids_explaining(rvec, tvec, truth.POSE_PATTERN, truth.POSE_SQUARE, corners, truth.POSE_K, None)


def _poses_from_wrong_grids(pattern, square, corners, K, dist) -> dict:
    """{(slip, label): (rvec, tvec)}: what cv2.solvePnP gives for the true corners with the
    object points built in the usual wrong ways."""
    cols, rows = pattern
    grids = {
        ("the object points are in column order (y fastest)", "the object points are in the wrong (column) order"):
            np.mgrid[0:cols, 0:rows].reshape(2, -1).T,
        ("the object points are built for (rows, cols): np.mgrid[0:rows, 0:cols]",
         "the object points are built for (rows, cols)"): np.mgrid[0:rows, 0:cols].T.reshape(-1, 2),
        ("the object points are built for (rows, cols) and in column order",
         "the object points are built for (rows, cols)"): np.mgrid[0:rows, 0:cols].reshape(2, -1).T,
        ("the object points have x and y exchanged (each is (row, column))",
         "the object points have x and y exchanged"): np.mgrid[0:cols, 0:rows].T.reshape(-1, 2)[:, ::-1],
        ("the object points (or the corners) are in reverse order",
         "the corners are in reverse order"): np.mgrid[0:cols, 0:rows].T.reshape(-1, 2)[::-1],
    }
    out = {}
    for key, grid in grids.items():
        objp = np.column_stack([grid * square, np.zeros(len(grid))]).astype(np.float64)
        ok, r, tv = cv2.solvePnP(objp, np.asarray(corners, np.float64).reshape(-1, 1, 2), np.asarray(K, float),
                                 None if dist is None else np.asarray(dist, float))
        if ok:
            out[key] = (r.ravel(), tv.ravel())
    return out


def _board_projected(rvec, tvec, pattern, square, K, dist) -> np.ndarray:
    """(M, 2): the board's corners, in OpenCV's order, projected with the pose ``rvec``, ``tvec``."""
    objp = scene.chessboard_object_points(pattern, square)
    out, _ = cv2.projectPoints(objp, np.asarray(rvec, float), np.asarray(tvec, float), np.asarray(K, float),
                               None if dist is None else np.asarray(dist, float))
    return out.reshape(-1, 2)


# The corners returned and the pose returned must agree: ``reprojected`` is the board projected with the
# student's own rvec and tvec. Measured on every view of the checks: the reference's, and its pose rounded
# to float32 and projected again, agree with it within 1e-5 px; the corners
# detected in those views (cv2.findChessboardCorners, cornerSubPix) lie 0.06 to 0.08 px (max) from them.
CONSISTENCY_TOLERANCE = 0.02   # px, max over the corners
DETECTED_RETURNED = "the detected corners are returned, not the board projected with the pose"


def _apart_from_own_projection(reprojected, rvec, tvec, pattern, square, K, dist) -> float:
    own = _board_projected(rvec, tvec, pattern, square, K, dist)
    reprojected = np.asarray(reprojected, float).reshape(-1, 2)
    if reprojected.shape != own.shape:
        return float("inf")
    # (the board's other corner order, where it is symmetric, is the same projection read backwards)
    return float(min(np.linalg.norm(reprojected - own, axis=1).max(),
                     np.linalg.norm(reprojected[::-1] - own, axis=1).max()))


def _detected_returned(image, pattern, reprojected) -> str:
    """Said where ``reprojected`` is the image's corners as OpenCV detects them (refined or not)."""
    grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
    found, corners = cv2.findChessboardCorners(grey, tuple(pattern))
    if not found:
        return ""
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)
    seen = [corners.reshape(-1, 2)] + [cv2.cornerSubPix(grey, corners.copy(), (w, w), (-1, -1), criteria).reshape(-1, 2)
                                       for w in (3, 5, 11)]
    got = np.asarray(reprojected, float).reshape(-1, 2)
    if any(got.shape == c.shape and np.linalg.norm(got - c, axis=1).max() <= CONSISTENCY_TOLERANCE / 2 for c in seen):
        return measured(": they are the corners detected in the image (cv2.findChessboardCorners, refined or not); "
                        "reprojected must be the object points projected back with the pose found "
                        "(cv2.projectPoints)")
    return ""


def _reprojection_slip(reprojected, rvec, tvec, pattern, square, K, dist):
    """The name of the slip that gives ``reprojected`` from a right pose, if one does."""
    def projected(dist_used):
        return _board_projected(rvec, tvec, pattern, square, K, dist_used)

    candidates = {"the corners are projected without dist (pass dist to cv2.projectPoints too)": projected(None)} \
        if dist is not None else {}
    right = projected(dist)
    candidates["the reprojected corners have x and y swapped"] = right[:, ::-1]
    return closest(reprojected, candidates, point_error, 0.05, truth=right)


def _call_pose(t: Trial, image, pattern, square, K, dist=None):
    what = f"estimate_pose(image, pattern_size={pattern}, square_size={square}, K" + \
           (", dist)" if dist is not None else ")")
    kwargs = {} if dist is None else {"dist": dist}
    return what, t.call("estimate_pose", image, pattern, square, K, **kwargs)


def colour_photo(grey) -> np.ndarray:
    """(H, W) uint8 -> a BGR photo of the same scene, as cv2.imread reads one (slightly warm)."""
    grey = np.asarray(grey, np.uint8)
    return np.dstack([np.round(grey * 0.92).astype(np.uint8), grey, grey])


# Code that converts already is pointed at where a colour view still reaches a call wanting one channel.
COLOUR_POSE_HINT = Hint("estimate_pose takes either: convert a colour image to grey where OpenCV wants one channel "
                        "(cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)).", asks=calls("cv2.cvtColor"),
                        instead="estimate_pose takes either; your code {found}: look at which view each OpenCV call "
                                "is given (one that wants one channel still gets the colour one).")


@ex6.check("estimate_pose on three rendered views with known pose (one a colour photo, BGR)", points=5)
def pose_views(t):
    messages = []
    for i, (image, R, tv, corners) in enumerate(truth.pose_views()):
        # the second view as cv2.imread reads a photo: BGR (OpenCV's corner refinement wants grey)
        given = colour_photo(image) if i == 1 else image
        try:
            what, got = _call_pose(t, given, truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_K)
        except StudentFailure as failure:
            if i != 1 or failure.outcome.kind != "exception":
                raise
            raise StudentFailure(failure.outcome, measured(
                f"estimate_pose(colour image, ...): {failure.message}\nThis view is a colour photo (BGR, as "
                "cv2.imread reads one); the grey view before it passed. ") + COLOUR_POSE_HINT.said(t)) from None
        what = what.replace("(image,", "(colour image,") if i == 1 else what
        verdict = judge_pose(t, what, got, image, R, tv, corners, truth.POSE_PATTERN, truth.POSE_SQUARE,
                             truth.POSE_K, show=(i == 0))
        if verdict.fraction < 1:
            return verdict
        messages.append(verdict.message)
    return passed(messages[-1])


@ex6.check("estimate_pose on a symmetric board seen upside down (either corner order is accepted)", points=1)
def pose_symmetric(t):
    image, R, tv, corners = truth.symmetric_view()
    what, got = _call_pose(t, image, truth.SYMMETRIC_PATTERN, truth.POSE_SQUARE, truth.POSE_K)
    return judge_pose(t, what, got, image, R, tv, corners, truth.SYMMETRIC_PATTERN, truth.POSE_SQUARE,
                      truth.POSE_K, show=False)


@ex6.check("estimate_pose through a distorting lens (dist given)", points=2)
def pose_distorted(t):
    distorted, _, R, tv, corners = truth.distorted_view()
    # the true corners as the distorting lens shows them
    objp = scene.chessboard_object_points(truth.POSE_PATTERN, truth.POSE_SQUARE)
    seen, _ = cv2.projectPoints(objp, scene.rvec_from_rotation(R), tv, truth.POSE_K, truth.DIST)
    what, got = _call_pose(t, distorted, truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_K, truth.DIST)
    return judge_pose(t, what, got, distorted, R, tv, seen.reshape(-1, 2), truth.POSE_PATTERN,
                      truth.POSE_SQUARE, truth.POSE_K, dist=truth.DIST)


@ex6.check("estimate_pose without a board: NaN rvec and tvec, empty (0, 2) corners", points=1)
def pose_no_board(t):
    what, got = _call_pose(t, truth.empty_view(), truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_K)
    if got is None:
        t.fail(f"{what} returned None when no board is visible; expected (NaN (3,), NaN (3,), (0, 2) array)")
    rvec, tvec, reprojected = _unpack_pose(t, what, got, 0)
    if np.isfinite(rvec).any() or np.isfinite(tvec).any():
        t.fail(f"{what}: no board is visible, so rvec and tvec should be NaN; yours are finite.")


# ================================================================== ext1 undistortion
ext1 = lab.exercise("ext1", "Extension: undistortion", functions=["undistort_image(image, K, dist)"])
UNDISTORT_TOLERANCE = 6.0


# (an image returned unchanged by code that passes dist to cv2.undistort: its answer dropped, a copy made before the
# call returned, an early return -- not "dist is not used": audit of 2026-12-06)
DIST_TO_UNDISTORT_HINT = Hint(
    ": dist is not used (cv2.undistort(image, K, dist)).", asks=DIST_TO_UNDISTORT,
    instead=": your code {found}, yet it returns the input as it was: check that the image returned is "
            "cv2.undistort's answer, given the dist passed in (not None or zeros).")


def undistorted(t: Trial, what: str, image, expected, seen: str, dist=None):
    """``undistort_image(image, K, dist)`` through the checks' lens (``dist``, by default
    truth.DIST), shown beside ``expected`` (the view without distortion``seen``): the answer of the
    input's shape and uint8, its mean blurred difference from ``expected`` and the pixels judged."""
    K, dist = truth.POSE_K, truth.DIST if dist is None else np.asarray(dist, float)
    got = t.call("undistort_image", image, K, dist)
    valid = truth.undistortion_valid(K, dist, truth.POSE_SIZE)
    if isinstance(got, np.ndarray):
        t.compare_images(what, image, expected, got, valid=valid,
                         caption=f"expected: the same view rendered without distortion{seen}")
    got = undistorted_answer(t, what, got, image.shape)
    return got, blurred_difference(got, expected, valid), valid


def undistorted_answer(t: Trial, what: str, got, shape) -> np.ndarray:
    """``got`` checked for the input's shape and uint8; an answer of another size from code calling
    cv2.getOptimalNewCameraMatrix is told both steps of OpenCV's calibration tutorial it took: another
    camera matrix, and its region of interest cut out (removing the cut alone leaves the view in the
    other camera: 26 grey levels from K's on a blind set's lens)."""
    if isinstance(got, np.ndarray) and got.shape[:2] != tuple(shape[:2]) \
            and NEW_CAMERA_MATRIX.found(code_of(t).reachable(["undistort_image"])):
        t.fail(f"{what} returned an array of shape {got.shape}; expected {tuple(shape)}: "
               + from_code("your code calls cv2.getOptimalNewCameraMatrix, as OpenCV's calibration tutorial "
                           "does: its matrix makes the result the view of another camera, and the image is cut "
                           "to another size. ")
               + measured("Keep K and the whole image, as the skeleton asks: cv2.undistort(image, K, dist), "
                          "without a newCameraMatrix and without a crop."),
               mistake=NEW_CAMERA_MATRIX_MISTAKE)
    return t.expect_array(got, what, shape=shape, dtype=np.uint8)


@ext1.check("undistort_image straightens views through two distorting lenses (the second with large "
            "tangential terms p1, p2)", points=4)
def undistort_check(t):
    distorted, clean, _, _, _ = truth.distorted_view()
    K, dist = truth.POSE_K, truth.DIST
    what = "undistort_image(image, K, dist)"
    got, error, valid = undistorted(t, what, distorted, clean, "")
    if error <= UNDISTORT_TOLERANCE:
        return levels_kept(t, distorted, clean, valid) or undistort_full_lens(t, error)
    renamed = new_camera_matrix_verdict(t, what, got, clean, K, dist)
    if renamed:
        return renamed
    if blurred_difference(got, distorted, valid) <= 1.0:
        t.fail(f"{what} returned the image unchanged" + DIST_TO_UNDISTORT_HINT.said(t),
               mistake="the image is returned unchanged")
    mistake = name_mistake(t, got, undistortion_mistakes(distorted, K, dist),
                           lambda a, b: blurred_difference(a, b, valid), UNDISTORT_TOLERANCE, truth=clean,
                           probe=undistort_probe(t))
    if mistake:
        t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    t.fail(f"{what} differs from the distortion-free view by {error:.0f} grey levels on average.")


# An undistortion moves pixels and keeps their levels. A chessboard view spans black to white, so a result
# stretched to the full range (cv2.normalize with NORM_MINMAX, an equalisation) is the view itself there:
# the same view dimmed to levels DIM_LEVELS shows it (blind set 1204c's 10/06). Legitimate undistortions
# (bilinear, its black border) keep the dimmed levels: linear interpolation commutes with them.
DIM_LEVELS = (40, 167)


def levels_kept(t: Trial, distorted, clean, valid):
    """None when ``undistort_image`` keeps a dimmed view's grey levels; else the verdict (half the points:
    the geometry was right on the full-range view)."""
    low, high = DIM_LEVELS
    dim = lambda image: (low + image.astype(np.float64) * (high - low) / 255.0).round().astype(np.uint8)  # noqa: E731
    what = f"undistort_image(image, K, dist) on the same view dimmed to grey levels {low}-{high}"
    got = undistorted_answer(t, what, t.call("undistort_image", dim(distorted), truth.POSE_K, truth.DIST),
                             distorted.shape)
    error = blurred_difference(got, dim(clean), valid)
    if error <= UNDISTORT_TOLERANCE:
        return None
    seen = got[valid]
    return partial(0.5, measured(
        f"{what} differs from that view undistorted by {error:.0f} grey levels on average: its levels span "
        f"{int(seen.min())}-{int(seen.max())} where the input's span {low}-{high} (on the full-range view the "
        "result is right). Undistortion moves pixels; it does not change their grey levels."),
        mistake="the grey levels are changed")


# The API's distortion is OpenCV's whole model (k1, k2, p1, p2, k3). The first lens's tangential
# terms (1e-3) move its image by a fraction of a pixel, so an undistortion without them passes
# there; truth.FULL_DIST's (1e-2) move it by several pixels. Measured (blurred_difference, grey
# levels, through FULL_DIST and the probe's FULL_PROBE_DIST): cv2.undistort, float32 K and dist,
# initUndistortRectifyMap + remap (CV_32FC1 or CV_16SC2 maps, linear or cubic) and an own map of
# the full model 0.7-1.3 from the clean view; without p1, p2 11.9-12.7; p1, p2 swapped 22-24;
# without k3 1.3-1.5 (k3's r^6 is too small at this field of view to judge).
FULL_PROBE_DIST = (-0.22, 0.05, -0.014, 0.012, 0.02)


def undistort_full_lens(t: Trial, first: float):
    """undistort_image through truth.FULL_DIST, after the first lens passed with ``first`` levels."""
    K, dist = truth.POSE_K, truth.FULL_DIST
    distorted, clean, _, _, _ = truth.distorted_view(tuple(dist))
    what = f"undistort_image(image, K, dist={format_matrix(dist)})"
    got, error, valid = undistorted(t, what, distorted, clean, " (a lens with tangential terms)", dist=dist)
    if error <= UNDISTORT_TOLERANCE:
        return tangential_only(t) or passed(
            f"mean difference {first:.1f} and {error:.1f} grey levels from the distortion-free views (the second "
            "lens's tangential terms included)")
    mistake = name_mistake(t, got, undistortion_mistakes(distorted, K, dist),
                           lambda a, b: blurred_difference(a, b, valid), UNDISTORT_TOLERANCE, truth=clean,
                           probe=undistort_probe(t, FULL_PROBE_DIST))
    # right through the first lens: half the points
    if mistake:
        return partial(0.5, f"{what} is wrong through this lens (through the first one, whose tangential terms are "
                            f"1e-3, it is right): it looks like {mistake}.", mistake=mistake)
    return partial(0.5, f"{what}: through this lens, with tangential terms p1 = {dist[2]:g}, p2 = {dist[3]:g} and "
                        f"k3 = {dist[4]:g}, the result differs from the distortion-free view by {error:.0f} grey "
                        f"levels on average; through the first lens (tangential terms of 1e-3, k3 = 0) by {first:.1f}.")


def tangential_only(t: Trial):
    """None when undistort_image straightens a lens with tangential terms alone (k1 = k2 = k3 = 0: a distortion
    like any other); else half the points, the image returned unchanged told so."""
    dist = np.array([0.0, 0.0, *truth.FULL_DIST[2:4], 0.0])
    distorted, clean, _, _, _ = truth.distorted_view(tuple(dist))
    what = f"undistort_image(image, K, dist={format_matrix(dist)})"
    got, error, valid = undistorted(t, what, distorted, clean, " (tangential terms only)", dist=dist)
    if error <= UNDISTORT_TOLERANCE:
        return None
    unchanged = blurred_difference(got, distorted, valid) <= 1.0
    return partial(0.5, f"{what}: through a lens whose radial terms are 0 and whose tangential terms are not, the result "
                        f"differs from the distortion-free view by {error:.0f} grey levels on average" + (measured(
                            ": it is the input unchanged, as if the lens had no distortion (p1 and p2 distort "
                            "too)") if unchanged else "."),
                   mistake="a lens with tangential terms only is left undistorted" if unchanged else "")


# k3 (r^6) moves only the image's outer ring: over the whole image an undistortion without it is
# 1.3-1.5 grey levels from the clean view (see above), within any fair tolerance. Judged on the ring
# (normalised radius > 0.5, 18% of the pixels) through a lens whose k3 is as large as calibrations
# of wide lenses give. Measured there (blurred_difference, two lenses of k3 = +-0.3):
# cv2.undistort, float32 K and dist, initUndistortRectifyMap + remap (CV_32FC1 or CV_16SC2, linear,
# cubic or nearest) 0.4-1.5; k3 left out (dist[:4]) 7.8-9.8; k3 halved 4.0-5.2.
K3_DIST = np.array([-0.3, 0.1, 0.001, -0.0015, 0.3])
K3_PROBE_DIST = (-0.2, 0.0, 0.001, -0.001, -0.3)
RING_RADIUS = 0.5
RING_TOLERANCE = 3.5
K3_LEFT_OUT = "k3 is left out (the image is undistorted with dist[:4], as with k3 = 0)"


def outer_ring(K, dist) -> np.ndarray:
    """(H, W) bool: the judged pixels (truth.undistortion_valid) beyond RING_RADIUS of the principal point."""
    w, h = truth.POSE_SIZE
    ys, xs = np.mgrid[0:h, 0:w]
    radius = np.hypot((xs - K[0, 2]) / K[0, 0], (ys - K[1, 2]) / K[1, 1])
    return truth.undistortion_valid(K, dist, truth.POSE_SIZE) & (radius > RING_RADIUS)


def k3_mistakes(distorted, K, dist) -> dict:
    return {**undistortion_mistakes(distorted, K, dist), K3_LEFT_OUT: cv2.undistort(distorted, K, dist[:4])}


@ext1.check("undistort_image uses k3 too (a lens whose r^6 term bends the image's outer ring)", points=1)
def undistort_k3(t):
    K, dist = truth.POSE_K, K3_DIST
    distorted, clean, _, _, _ = truth.distorted_view(tuple(dist))
    what = f"undistort_image(image, K, dist={format_matrix(dist)})"
    got, whole, valid = undistorted(t, what, distorted, clean, " (k3 = 0.3)", dist=dist)
    if whole > UNDISTORT_TOLERANCE:
        return passed(measured(f"the image is {whole:.0f} grey levels from the distortion-free view as a whole: "
                               "the first check judges it"))
    ring = outer_ring(K, dist)
    error = blurred_difference(got, clean, ring)
    if error <= RING_TOLERANCE:
        return passed(f"{error:.1f} grey levels from the distortion-free view on the outer ring, where k3 acts")
    probe_distorted, probe_clean, _, _, _ = truth.distorted_view(K3_PROBE_DIST)
    probe_ring = outer_ring(K, np.array(K3_PROBE_DIST))
    probe = Probe(undistort_probe_key(K3_PROBE_DIST), lambda: _undistort_answer(t, probe_distorted, K3_PROBE_DIST),
                  lambda: k3_mistakes(probe_distorted, K, np.array(K3_PROBE_DIST)), probe_clean,
                  distance=lambda a, b: blurred_difference(a, b, probe_ring), tolerance=RING_TOLERANCE)
    mistake = name_mistake(t, got, k3_mistakes(distorted, K, dist), lambda a, b: blurred_difference(a, b, ring),
                           RING_TOLERANCE, truth=clean, probe=probe)
    t.fail(f"{what}: the image's outer ring (beyond {RING_RADIUS:g} focal lengths of the principal point, where "
           f"k3 r^6 acts) differs from the distortion-free view by {format_apart(error, RING_TOLERANCE)} grey levels "
           f"on average (at most {RING_TOLERANCE:g}); the whole image by {whole:.1f}"
           + (f": it looks like {mistake}." if mistake else
              ". OpenCV's model has five coefficients (k1, k2, p1, p2, k3): all of them undistort."),
           mistake=mistake or "")


# The output keeps K: the skeleton pins it ("Remove lens distortion from an image, keeping the
# camera matrix K": the image an ideal pinhole camera with the same K would record; the API leaves
# what its table does not pin to the skeleton's docstring) and the lab sheet's recipe,
# cv2.undistort(image, K, dist), keeps K. OpenCV's calibration tutorial undistorts into
# cv2.getOptimalNewCameraMatrix's matrix instead: the lens is undone rightly, the output camera is
# another (focal lengths 0.86-0.97 of K's here), so half the points. Measured (blurred_difference,
# grey levels, this check's lens and the probe's; OpenCV 4.14 and 5.0 give the same images and
# matrices to the bit): the legitimate variants (cv2.undistort, initUndistortRectifyMap + remap
# with CV_32FC1 or CV_16SC2 maps, float32 K and dist, cubic or nearest remap) 0.7-2.4 from the
# clean view; the tutorial's four matrices (alpha 0 or 1, principal point kept or centred)
# 19.8-89 from it, each 0.6-0.8 from its own view and >= 7.8 from the other three.
def new_camera_matrix_verdict(t: Trial, what: str, got, clean, K, dist):
    """Half the points, named, when ``got`` (wrong against ``clean``) is the distortion-free view in
    one of the tutorial's new camera matrices; the name is confirmed by the probe's lens (the same
    matrix's view there) or by the code calling cv2.getOptimalNewCameraMatrix. None otherwise."""
    name = _new_camera_matrix_view(got, clean, K, dist)
    if name is None:
        return None
    distorted, probe_clean, _, _, _ = truth.distorted_view(UNDISTORT_PROBE_DIST)
    again = t.probe(undistort_probe_key(), lambda: _undistort_answer(t, distorted))
    confirmed = again is not None and \
        _new_camera_matrix_view(again, probe_clean, K, np.array(UNDISTORT_PROBE_DIST)) == name
    read = NEW_CAMERA_MATRIX.found(code_of(t).reachable(["undistort_image"]))
    return partial(0.5, f"{what} removes the distortion, but into another camera matrix: the result is the "
                        f"distortion-free view with the camera matrix of {name}"
                        f"{' (on a second lens too)' if confirmed else ''}"
                        f"{', which your code calls' if read else ''}, not K. "
                        + measured("Keep K, as the skeleton asks (the image a pinhole camera with the same K would "
                                   "record): cv2.undistort(image, K, dist), without a newCameraMatrix."),
                   mistake=NEW_CAMERA_MATRIX_MISTAKE if confirmed or read else "")


NEW_CAMERA_MATRIX = calls("cv2.getOptimalNewCameraMatrix")
NEW_CAMERA_MATRIX_MISTAKE = measured("undistorted into a new camera matrix (cv2.getOptimalNewCameraMatrix), not K")


def _new_camera_matrix_view(got, clean, K, dist) -> str | None:
    """The tutorial's camera matrix whose distortion-free view ``got`` is, or None."""
    for name, (expected, judged) in truth.undistorted_views_with_new_camera_matrix(clean, K, dist).items():
        if judged.mean() > 0.3 and blurred_difference(got, expected, judged) <= UNDISTORT_TOLERANCE:
            return name
    return None


def undistortion_mistakes(distorted, K, dist) -> dict:
    twice = truth.distort_image(np.pad(distorted, truth.MARGIN), K, dist, truth.POSE_SIZE)
    dist = np.asarray(dist, float)
    return {
        "the distortion is applied instead of removed (the lines bend even more)": twice,
        "the sign of the coefficients is flipped (undistorting with -dist)": cv2.undistort(distorted, K, -dist),
        "K is transposed (cv2.undistort wants K as given)": cv2.undistort(distorted, K.T, dist),
        TANGENTIAL_LEFT_OUT: cv2.undistort(distorted, K, dist * [1.0, 1.0, 0.0, 0.0, 1.0]),
        "p1 and p2 are swapped (the image is undistorted with (k1, k2, p2, p1, k3))":
            cv2.undistort(distorted, K, dist[[0, 1, 3, 2, 4]]),
    }


TANGENTIAL_LEFT_OUT = "the tangential terms are left out (the image is undistorted as with p1 = p2 = 0)"


UNDISTORT_PROBE_DIST = (-0.18, 0.03, -0.002, 0.0025, 0.01)


def undistort_probe_key(dist=UNDISTORT_PROBE_DIST) -> str:
    return f"undistort_image/{tuple(dist)}"


def _undistort_answer(t: Trial, distorted, dist=UNDISTORT_PROBE_DIST):
    """undistort_image on a probe's lens (K, dist); None unless of the input's form."""
    got = t.call("undistort_image", distorted, truth.POSE_K, np.array(dist))
    ok = isinstance(got, np.ndarray) and got.shape == distorted.shape and got.dtype == np.uint8
    return got if ok else None


def undistort_probe(t: Trial, lens=UNDISTORT_PROBE_DIST) -> Probe:
    """undistort_image of the same board through another lens (its tangential terms of other signs)."""
    K, dist = truth.POSE_K, np.array(lens)
    distorted, clean, _, _, _ = truth.distorted_view(tuple(lens))
    valid = truth.undistortion_valid(K, dist, truth.POSE_SIZE)
    return Probe(undistort_probe_key(lens), lambda: _undistort_answer(t, distorted, lens),
                 lambda: undistortion_mistakes(distorted, K, dist), clean,
                 distance=lambda a, b: blurred_difference(a, b, valid), tolerance=UNDISTORT_TOLERANCE)


# The API's K is any camera matrix; the first check's POSE_K has its principal point at the image
# centre ((w - 1) / 2, (h - 1) / 2), where cv2.initUndistortRectifyMap given no new camera matrix
# puts it too (OpenCV's getDefaultNewCameraMatrix(K, size, True)), so that mistake passed there.
# Here K's is off the centre, and fx != fy. Measured (benchmarks/spread_undistort_off_centre.py,
# this camera and the probe's, both lenses): cv2.undistort, float32 K and dist,
# initUndistortRectifyMap with K as the new matrix (CV_32FC1 or CV_16SC2 maps, linear, cubic or
# nearest remap) and an own map of OpenCV's model 0.7-2.4 grey levels from the distortion-free view;
# the principal point recentred 91.6-95.6: UNDISTORT_TOLERANCE (6) holds.
RECENTRED = "the principal point is moved to the image centre ((w - 1) / 2, (h - 1) / 2) instead of kept at K's"
KEEPS_NEW_MATRIX = passes_argument("cv2.initUndistortRectifyMap", 3, "newCameraMatrix",
                                   says="passes a new camera matrix to cv2.initUndistortRectifyMap")
RECENTRED_HINT = Hint(
    "cv2.initUndistortRectifyMap given no newCameraMatrix (None) builds one with the principal point at "
    "the image centre: pass K as newCameraMatrix to keep K",
    asks=KEEPS_NEW_MATRIX | ~calls("cv2.initUndistortRectifyMap"),
    instead="look at where your code puts the principal point of the output: at K's (cx, cy)")


def off_centre_mistakes(distorted, K, dist) -> dict:
    """The usual undistortion mistakes on the camera ``K``, and the principal point recentred."""
    w, h = truth.POSE_SIZE
    centred = K.copy()
    centred[:2, 2] = (w - 1) / 2, (h - 1) / 2
    return {RECENTRED: cv2.undistort(distorted, K, dist, None, centred), **undistortion_mistakes(distorted, K, dist)}


def off_centre_probe(t: Trial) -> Probe:
    """undistort_image of the board through a camera whose principal point is off on the other side."""
    K, dist = truth.OFF_CENTRE_PROBE_K, truth.DIST
    distorted, clean, _, _, _ = truth.distorted_view(tuple(dist), tuple(K.ravel()))
    valid = truth.undistortion_valid(K, dist, truth.POSE_SIZE)

    def answer():
        got = t.call("undistort_image", distorted, K, dist)
        ok = isinstance(got, np.ndarray) and got.shape == distorted.shape and got.dtype == np.uint8
        return got if ok else None

    return Probe("undistort_image/off-centre probe", answer, lambda: off_centre_mistakes(distorted, K, dist), clean,
                 distance=lambda a, b: blurred_difference(a, b, valid), tolerance=UNDISTORT_TOLERANCE)


@ext1.check("undistort_image keeps K's principal point off the image centre (and fx != fy)", points=2)
def undistort_off_centre(t):
    K, dist = truth.OFF_CENTRE_K, truth.DIST
    (w, h), (cx, cy) = truth.POSE_SIZE, K[:2, 2]
    distorted, clean, _, _, _ = truth.distorted_view(tuple(dist), tuple(K.ravel()))
    what = (f"undistort_image(image, K, dist) with fx = {K[0, 0]:g}, fy = {K[1, 1]:g} and the principal point "
            f"({cx:g}, {cy:g})")
    got = t.call("undistort_image", distorted, K, dist)
    valid = truth.undistortion_valid(K, dist, truth.POSE_SIZE)
    if isinstance(got, np.ndarray):
        t.compare_images(what, distorted, clean, got, valid=valid,
                         caption="expected: the same view rendered without distortion, with the same K")
    got = undistorted_answer(t, what, got, distorted.shape)
    error = blurred_difference(got, clean, valid)
    if error <= UNDISTORT_TOLERANCE:
        return passed(f"mean difference {error:.1f} grey levels from the distortion-free view")
    if _new_camera_matrix_view(got, clean, K, dist):   # a new camera matrix loses its points once, in the first check
        return passed(measured("the distortion-free view in cv2.getOptimalNewCameraMatrix's camera matrix, as in the "
                               "first check, which judges that choice"))
    mistake = name_mistake(t, got, off_centre_mistakes(distorted, K, dist),
                           lambda a, b: blurred_difference(a, b, valid), UNDISTORT_TOLERANCE, truth=clean,
                           probe=off_centre_probe(t))
    if mistake == RECENTRED:
        t.fail(f"{what} is wrong: the result is the distortion-free view with the principal point at the image "
               f"centre ({(w - 1) / 2:g}, {(h - 1) / 2:g}) instead of K's ({cx:g}, {cy:g}), so it is shifted by "
               f"({(w - 1) / 2 - cx:+g}, {(h - 1) / 2 - cy:+g}) px (on a second camera too). The first check's K "
               "has its principal point at the centre, which hides this. " + RECENTRED_HINT.said(t),
               mistake=RECENTRED)
    if mistake:
        t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    t.fail(f"{what} differs from the distortion-free view by {format_apart(error, UNDISTORT_TOLERANCE, 2)} grey "
           f"levels on average (at most {UNDISTORT_TOLERANCE:g} accepted). Here K's principal point is off the "
           f"image centre ({(w - 1) / 2:g}, {(h - 1) / 2:g}) and fx != fy.")


# "Black fill" (the API): undistorting a pincushion lens (k1 > 0) samples the corners beyond the distorted
# image, so they are 0 -- as cv2.undistort and cv2.remap's default constant border leave them. The other
# checks' barrel lenses sample inside the image everywhere, where no fill shows.
PINCUSHION = np.array([0.35, 0.1, 0.0, 0.0, 0.0])


@ext1.check("undistort_image leaves black the pixels whose source lies outside the image (a pincushion lens)",
            points=1)
def undistort_black_fill(t):
    from fixtures.images import photo

    K, image = truth.POSE_K, photo("astronaut", truth.POSE_SIZE)
    outside = ~truth.undistortion_valid(K, PINCUSHION, truth.POSE_SIZE, margin=-1.5)   # 1.5 px beyond the image
    what = f"undistort_image(image, K, dist={format_matrix(PINCUSHION)}) (a pincushion lens)"
    got = t.call("undistort_image", image, K, PINCUSHION)
    if isinstance(got, np.ndarray):
        t.images(what, "the corners sample beyond the distorted image: black fill", input=image, yours=got)
    got = undistorted_answer(t, what, got, image.shape)
    valid = truth.undistortion_valid(K, PINCUSHION, truth.POSE_SIZE)
    if blurred_difference(got, cv2.undistort(image, K, PINCUSHION), valid) > UNDISTORT_TOLERANCE:
        return passed(measured("the image itself is not the undistorted one here: the other checks judge it"))
    nonblack = fill_fraction(got, outside)
    if nonblack <= FILL_TOLERANCE:
        return passed(f"{nonblack:.0%} of the {int(outside.sum())} pixels with no source pixel are not black")
    read = code_of(t).reachable(["undistort_image"])
    if calls("cv2.getOptimalNewCameraMatrix").found(read):   # another camera matrix: the first check's to judge
        return passed(measured("the view in cv2.getOptimalNewCameraMatrix's camera matrix, which the first check "
                               "judges"))
    rule = repeating_border(read)
    t.fail(measured(f"{what}: {nonblack:.0%} of the pixels whose source lies outside the distorted image are not "
                    "black (the API's black fill: a pixel with no source pixel is 0)")
           + (from_code(f"; your code uses cv2.{rule}, which fills them from the image's edge.") if rule else "."),
           hint=BLACK_FILL_HINT.said(t), mistake="the fill is not black")


@ext1.check("undistort_image keeps a colour image in colour (BGR in, BGR out)", points=1)
def undistort_colour(t):
    """The skeleton: (H, W) or (H, W, 3) in, the same shape out. One question, the colour: what
    the undistortion itself is worth is the grey check's, so an answer equal to the student's own
    grey undistortion of each channel passes (a new camera matrix loses its points once)."""
    distorted, clean, _, _, _ = truth.distorted_view()
    K, dist = truth.POSE_K, truth.DIST
    colour, expected = tinted(distorted), tinted(clean)
    what = "undistort_image(colour image, K, dist)"
    # rounding 0.6 x grey before or after the remap: under one level apart
    got, error, valid = undistorted(t, what, colour, expected, ", in colour")
    if error <= UNDISTORT_TOLERANCE:
        return passed(f"mean difference {error:.1f} levels from the distortion-free view, in every channel")
    if channels_reversed(got, expected):
        t.fail(f"{what} is wrong: {RGB_FOR_BGR}.", mistake="the colour channels are reversed (RGB for BGR)")
    per_channel = [t.expect_array(t.call("undistort_image", np.ascontiguousarray(colour[..., c]), K, dist),
                                  f"undistort_image(channel {c} of the colour image, K, dist)",
                                  shape=distorted.shape, dtype=np.uint8) for c in range(3)]
    if blurred_difference(got, np.dstack(per_channel), valid) <= UNDISTORT_TOLERANCE:
        return passed("each channel is undistorted as your code undistorts a grey image "
                      "(the undistortion itself is the other check's)")
    told = UNDISTORT_CHANNELS_HINT.said(t)
    t.fail(f"{what} differs by {error:.0f} levels on average from the distortion-free view, and is not your "
           "own undistortion of each channel either" + (f": {told}" if told else "."))


# Told only to code that converts or splits the colour image (code undistorting it as it comes does what it says).
UNDISTORT_CHANNELS_HINT = Hint(
    "undistort the three channels alike (cv2.undistort takes a BGR image as it is).",
    asks=~(calls("cv2.cvtColor") | calls("cv2.split") | expr("_[..., 0]") | expr("_[:, :, 0]")).saying(
        "converts or splits the image"), instead="")


# ================================================================== ext2 dolly zoom
ext2 = lab.exercise("ext2", "Extension: dolly zoom", functions=["dolly_zoom(points, f0, z0, distances)"])


def _scales_points_by_a_ratio_to_z0(function) -> bool:
    """A product of the points (anything but a focal length) with a ratio to z0: `X * [1, 1, d / z0]`."""
    def reads(node, name):
        return any(isinstance(n, ast.Name) and n.id == name for n in walk(node))

    def over_z0(node):
        return any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.Div) and reads(n.right, "z0") for n in walk(node))
    for node in walk(function):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult):
            for side, other in ((node.left, node.right), (node.right, node.left)):
                if over_z0(side) and not reads(other, "f0") and not reads(other, "f") and not over_z0(other):
                    return True
    return False


# Of the dolly's mistakes that give the same answers -- every depth scaled by d / z0, and a camera that does
# not move projected with f0 -- the one the code shows is said alone (a product of the points with d / z0).
evidenced("every depth is scaled by d / z0; the camera moves, so each depth changes by d - z0",
          Predicate("scales the points by a ratio to z0", _scales_points_by_a_ratio_to_z0))


def dolly_scene():
    rng = np.random.default_rng(601)
    subject = np.column_stack([rng.uniform(-1, 1, 8), rng.uniform(-1.5, 1.5, 8), np.full(8, 5.0)])
    background = np.column_stack([rng.uniform(-6, 6, 12), rng.uniform(-4, 4, 12), rng.uniform(12, 25, 12)])
    return np.vstack([subject, background]), 8


def dolly_distance(a, b):
    """Relative error of the focal lengths and of the projections, the larger."""
    (fa, pa), (fb, pb) = a, b
    return max(float(np.abs(fa - fb).max() / np.abs(fb).max()),
               point_error(pa.reshape(-1, 2), pb.reshape(-1, 2)) / float(np.nanmax(np.abs(pb))))


def dolly_probe(t: Trial) -> Probe:
    """dolly_zoom of other points (depths spread around z0) with an f0, z0 and distances no check uses."""
    rng = np.random.default_rng(10_040)
    X = np.column_stack([rng.uniform(-3, 3, 9), rng.uniform(-2, 2, 9), 3.5 + rng.uniform(-1.5, 9, 9)])
    f0, z0, distances = 275.0, 3.5, np.array([2.25, 4.75, 8.5])

    def answer():
        got = t.call("dolly_zoom", X, f0, z0, distances)
        if not (isinstance(got, (tuple, list)) and len(got) == 2):
            return None
        fs, proj = (np.asarray(g, dtype=np.float64) if isinstance(g, np.ndarray) else None for g in got)
        ok = fs is not None and proj is not None and fs.shape == (3,) and proj.shape == (3, len(X), 2)
        return (fs, proj) if ok else None

    return Probe(f"dolly_zoom/{fingerprint(X)}", answer, lambda: truth.dolly_mistakes(X, f0, z0, distances),
                 truth.dolly_zoom(X, f0, z0, distances), distance=dolly_distance, tolerance=1e-6,
                 alike=lambda a, b: dolly_distance(a, b) <= 1e-9)


def judge_dolly(t: Trial, X, f0, z0, distances, n_subject=None, show=False):
    what = f"dolly_zoom(points, f0={f0:g}, z0={z0:g}, distances={format_matrix(distances)})"
    got = t.call("dolly_zoom", X, f0, z0, distances)
    if not (isinstance(got, (tuple, list)) and len(got) == 2):
        t.fail(f"{what} should return a pair (focal_lengths, projections)")
    fs_true, proj_true = truth.dolly_zoom(X, f0, z0, distances)
    if all(isinstance(g, np.ndarray) for g in got) and got[0].shape == proj_true.shape \
            and got[1].shape == fs_true.shape:
        t.fail(f"{what} returned (projections, focal_lengths); the API's order is (focal_lengths, projections).",
               mistake="the pair is returned in the wrong order")
    fs = t.expect_array(got[0], f"{what}[0] (focal lengths)", shape=fs_true.shape, kind="iuf", finite=True)
    proj = got[1]
    if isinstance(proj, np.ndarray) and proj.shape == (len(X), len(fs_true), 2) and len(X) != len(fs_true):
        t.fail(f"{what}[1] has shape (N, F, 2); expected (F, N, 2): one (N, 2) projection per distance")
    proj = t.expect_array(proj, f"{what}[1] (projections)", shape=proj_true.shape, kind="iuf")
    if show and n_subject:
        t.svg("frames of the dolly zoom: the subject (first 8 points) keeps its size", svg_points(
            {f"d = {d:g}": proj[i] for i, d in enumerate(list(distances)[:4])}))
    f_scale, p_scale = magnitude(fs_true), magnitude(proj_true)
    ok_f = np.abs(fs - fs_true).max() <= at_precision(1e-6 * np.abs(fs_true).max(), f_scale)
    ok_p = point_error(proj.reshape(-1, 2), proj_true.reshape(-1, 2)) <= \
        at_precision(1e-6 * np.nanmax(np.abs(proj_true)), p_scale)
    if ok_f and ok_p:
        return
    mistake = name_mistake(t, (fs, proj), truth.dolly_mistakes(X, f0, z0, distances), dolly_distance, 1e-6,
                           truth=(fs_true, proj_true), probe=dolly_probe(t))
    if mistake:
        t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    if not ok_f:
        shown, wanted = format_arrays_apart(fs, fs_true)
        # (a focal length that keeps one point's own size -- f0 (Z_k + d - z0) / Z_k --, where the subject plane's,
        # at depth z0, belongs: measured against every point's)
        kept = [k for k, Z in enumerate(np.asarray(X, float)[:, 2]) if Z > 0 and not np.isclose(Z, z0)
                and np.allclose(fs, f0 * (Z + np.asarray(distances, float) - z0) / Z, rtol=1e-6)]
        t.fail(f"{what}: the focal lengths are {shown}; expected f0 * d / z0 = {wanted}" + (measured(
            f": they are f0 (Z + d - z0) / Z for point {kept[0]} (Z = {X[kept[0]][2]:g}), the focal lengths that keep "
            f"that point's size; the subject is the plane at depth z0 = {z0:g}, whose size f0 d / z0 keeps")
            if kept else ""), mistake="the focal length keeps one point's size, not the subject plane's" if kept else "")
    if n_subject:
        drift = np.abs(proj[:, :n_subject] - proj[:1, :n_subject]).max()
        if drift > at_precision(1e-6, p_scale):
            t.fail(f"{what}: the subject (the points at depth z0) should keep its image across frames; "
                   f"yours moves by up to {drift:.3g} px.")
    t.fail(f"{what}: the focal lengths are right, but the projections are off by up to "
           f"{point_error(proj.reshape(-1, 2), proj_true.reshape(-1, 2)):.3g} px.")


@ext2.check("dolly_zoom keeps the subject's size while the background changes", points=4)
def dolly_example(t):
    X, n_subject = dolly_scene()
    judge_dolly(t, X, 400.0, 5.0, np.array([5.0, 7.5, 10.0, 15.0]), n_subject, show=True)
    return passed("subject fixed, background moving")


@ext2.advice("NaN for points the dolly moves behind the camera")
def dolly_behind(t):
    # A dolly towards the subject moves the nearer points to Z <= 0 (one exactly onto the camera plane):
    # they have no image, as perspective_project's points behind the camera (NaN recommended, 0 points).
    X = np.array([[0.5, -0.3, 5.0], [1.0, 0.8, 2.0], [-1.2, 0.4, 9.0], [0.3, 0.2, 3.0]])
    z0, distances = 5.0, np.array([5.0, 2.0])   # at d = 2 every depth drops by 3: -1 and 0 for rows 1, 3
    got = t.call("dolly_zoom", X, 400.0, z0, distances)
    if isinstance(got, (tuple, list)) and len(got) == 2 and isinstance(got[1], np.ndarray) \
            and got[1].shape == (2, len(X), 2) and got[1].dtype.kind == "f":
        moved = X + [0.0, 0.0, distances[1] - z0]
        with np.errstate(divide="ignore", invalid="ignore"):
            in_front = 400.0 * distances[1] / z0 * moved[:, :2] / moved[:, 2:]
        advise_nan_behind(t, "dolly_zoom(points, f0=400, z0=5, distances=[5, 2]), in its frame at d = 2,",
                          got[1][1], moved[:, 2] <= 0, in_front)


@ext2.check("dolly_zoom for other focal lengths and distances (in any order, repeated, a single one)", points=2)
def dolly_property(t):
    def points(rng, z0):
        return np.column_stack([rng.uniform(-2, 2, 10), rng.uniform(-2, 2, 10), z0 + rng.uniform(0, 10, 10)])

    def holds(case):
        seed, f0, z0 = case
        rng = np.random.default_rng(seed)
        X = points(rng, z0)
        # a dolly may move in and out: the distances in any order, one of them twice
        distances = rng.uniform(0.5 * z0, 3 * z0, 5)
        distances[3] = distances[1]
        judge_dolly(t, X, f0, z0, distances)

    t.for_all(st.tuples(seeds, st.floats(50, 2000), st.floats(1, 20)), holds, max_examples=10)
    # one distance: one frame, projections of shape (1, N, 2)
    judge_dolly(t, points(np.random.default_rng(602), 4.0), 350.0, 4.0, np.array([6.5]))


# ================================================================== ext3 tracking
ext3 = lab.exercise("ext3", "Extension: tracking the pose over a sequence", functions=[
    "track_pose(frames, pattern_size, square_size, K, dist=None)"])


def _track_rows_match(rows, candidate, poses, pattern, square) -> bool:
    """Whether ``rows`` are ``candidate``'s poses (NaN for None) wherever the true ``poses`` differ from it."""
    differs = False
    for row, pose, true_pose in zip(rows, candidate, poses):
        if pose is None:
            if np.isfinite(row).any() and true_pose is None:
                return False
            continue
        if not np.isfinite(row).all():
            return False
        R, tv = pose
        angle, shift, _ = truth.pose_error(row[:3], row[3:], R, tv, pattern, square)
        # (a candidate's translation may be 0 -- a motion since the first frame --: the board's own distance
        # is the scale then)
        distance = max(np.linalg.norm(tv), 0.0 if true_pose is None else np.linalg.norm(true_pose[1]))
        if angle > ANGLE_TOLERANCE or shift > TRANSLATION_TOLERANCE * distance:
            return False
        differs = differs or true_pose is None or truth.rotation_angle_deg(R, true_pose[0]) > ANGLE_TOLERANCE
    return differs


def _poses_without_dist(frames, K) -> list:
    """Per frame, the (R, t) cv2.solvePnP gives for its detected corners without a distortion
    (None where no board is found)."""
    objp = scene.chessboard_object_points(truth.POSE_PATTERN, truth.POSE_SQUARE)
    out = []
    for frame in frames:
        found, corners = cv2.findChessboardCorners(frame, tuple(truth.POSE_PATTERN))
        if not found:
            out.append(None)
            continue
        corners = cv2.cornerSubPix(frame, corners, (5, 5), (-1, -1),
                                   (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3))
        _, r, tv = cv2.solvePnP(objp, corners, K, None)
        out.append((scene.rotation_from_rvec(r.ravel()), tv.ravel()))
    return out


def _without_dist(rows, frames, poses, K) -> float | None:
    """The largest translation error (fraction of the distance) of the true poses when every
    row is the pose solved without dist (within a tenth of the tolerances), else None."""
    worst = 0.0
    for row, pose, true_pose in zip(rows, _poses_without_dist(frames, K), poses):
        if true_pose is None or pose is None:
            continue
        if not np.isfinite(row).all():
            return None
        angle, shift, _ = truth.pose_error(row[:3], row[3:], *pose, truth.POSE_PATTERN, truth.POSE_SQUARE)
        if angle > 0.1 * ANGLE_TOLERANCE or shift > 0.1 * TRANSLATION_TOLERANCE * np.linalg.norm(pose[1]):
            return None
        worst = max(worst, np.linalg.norm(pose[1] - true_pose[1]) / np.linalg.norm(true_pose[1]))
    return worst if worst > TRANSLATION_TOLERANCE else None


@ext3.check("track_pose follows a board along a known trajectory (NaN where it leaves the view; a single frame "
            "too; a board rocking through face-on), also through a distorting lens (dist given)", points=4)
def track_check(t):
    frames, poses = truth.track_sequence()
    first = judge_track(t, frames, poses)
    judge_track(t, frames[:1], poses[:1], what="track_pose([one frame], pattern_size, square_size, K)")
    judge_track(t, *truth.rocking_sequence(), what="track_pose(frames of a board rocking through face-on, "
                                                    "pattern_size, square_size, K)")
    frames, poses = truth.distorted_track_sequence()
    try:
        return judge_track(t, frames, poses, dist=truth.DIST)
    except Fail as failure:   # the tracking itself is right (the first sequence): half the points
        return partial(0.5, f"{failure.message} (Without a lens distortion: {first.message}.)", failure.hint,
                       failure.mistake)


TRIANGULAR_R = "R is the triangular factor of the decomposition, not its rotation"


def _triangular_factor(R) -> str:
    """The sentence saying ``R`` is triangular (upper or lower) where a rotation belongs -- a QR or RQ
    decomposition's triangular factor kept in its rotation's place --, or ''. A rotation is triangular only where
    it is diagonal (signs), which is a rotation."""
    scale = np.abs(R).max()
    if scale == 0 or not np.isfinite(R).all():
        return ""
    if np.abs(R - np.diag(np.diag(R))).max() <= 1e-9 * scale:
        return ""   # (diagonal: a triangular factor has entries above its diagonal -- `S * R`, element-wise, keeps none)
    for side, zeros in (("upper", np.tril(R, -1)), ("lower", np.triu(R, 1))):
        if np.abs(zeros).max() <= 1e-9 * scale:
            return measured(f": it is {side} triangular, as a QR or RQ decomposition's triangular factor is; the "
                            "rotation is the decomposition's orthogonal factor (Q, or Q^T)")
    return ""


def _warm_started(function) -> bool:
    """cv2.solvePnP given a starting pose: ``useExtrinsicGuess=True`` (a keyword or the 7th argument)."""
    for node in walk(function):
        if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] == "solvePnP":
            given = [k.value for k in node.keywords if k.arg == "useExtrinsicGuess"] + node.args[6:7]
            if any(not (isinstance(v, ast.Constant) and not v.value) for v in given):
                return True
    return False


WARM_START = Predicate("starts cv2.solvePnP from a given pose (useExtrinsicGuess)", _warm_started)
WARM_START_FROM_NAN = from_code("the solve after a frame without a board starts from that frame's NaN row")
RELATIVE_TO_FIRST = measured("each row is the pose relative to the first frame with a board (its row is the identity, "
                     "R = I and t = 0): every row must be the board's own pose in that frame's camera, as "
                     "estimate_pose (cv2.solvePnP) gives it, not the motion since the first frame")


def judge_track(t: Trial, frames, poses, dist=None, what=None):
    """track_pose on ``frames`` (with ``dist`` when given) against the true ``poses``."""
    pattern, square, K = truth.POSE_PATTERN, truth.POSE_SQUARE, truth.POSE_K
    what = what or "track_pose(frames, pattern_size, square_size, K" + (
        ", dist) through a distorting lens" if dist is not None else ")")
    got = t.call("track_pose", list(frames), pattern, square, K, **({} if dist is None else {"dist": dist}))
    if isinstance(got, np.ndarray) and got.ndim > 2 and got.shape[0] == len(frames) and got.size == 6 * len(frames):
        t.fail(f"{what} returned shape {got.shape}; expected ({len(frames)}, 6): the rows are not flattened "
               "(each row is the 6 numbers of rvec, then tvec).", mistake="the rows are not flattened to [rvec, tvec]")
    if isinstance(got, np.ndarray) and got.ndim == 2 and got.shape[1] == 6 and got.shape[0] < len(frames):
        # (rows up to the first frame without a board, and none after: the loop stopped there)
        lost = next((k for k, pose in enumerate(poses) if pose is None), None)
        stopped = lost is not None and got.shape[0] == lost
        t.fail(f"{what} returned {got.shape[0]} rows for {len(frames)} frames: " + measured(
            (f"the rows stop at frame {lost}, the first where the board is not found, and no row follows for the later frames "
             "(is the loop left there, with break or return?); " if stopped else "")
            + "keep one row per frame, NaN where the board is not found."),
            mistake="the frames after the first without a board are left out" if stopped else "")
    got = t.expect_array(got, what, shape=(len(frames), 6), kind="f")
    shifted = {
        "the rows are off by one frame (one frame late): row i must be the pose in frame i (frames[i])": (None,) + poses[:-1],
        "the rows are off by one frame (one frame early): row i must be the pose in frame i (frames[i])": poses[1:] + (None,),
        measured("the rows are in reverse frame order (the last frame's pose first): row i must be the pose in frame "
                 "i (frames[i])"): tuple(reversed(poses)),
        measured("each row is the camera's pose in the board's frame (R^T, -R^T t): the pose is inverted; "
                 "the rows are the board's pose in the camera frame, as cv2.solvePnP gives it"):
            tuple(None if p is None else (p[0].T, -p[0].T @ p[1]) for p in poses),
    }
    found = [p for p in poses if p is not None]
    if len(found) > 1:   # (a camera's motion since the first frame, in either frame: not the board's pose)
        R0, t0 = found[0]
        shifted[measured(RELATIVE_TO_FIRST)] = tuple(None if p is None else (p[0] @ R0.T, p[1] - p[0] @ R0.T @ t0)
                                                     for p in poses)
        shifted[measured(RELATIVE_TO_FIRST + " (composed the other way, R0^T R)")] = tuple(
            None if p is None else (R0.T @ p[0], R0.T @ (p[1] - t0)) for p in poses)
    if tuple(found) + (None,) * (len(poses) - len(found)) != tuple(poses):
        # (the rows kept in a list of the found poses, the frames without a board appended after the loop)
        shifted[measured("the rows of the frames with a board come first, in their order, and the NaN rows of "
                         "the frames without one last: row i must be frame i's pose (NaN in its own place)")] = \
            tuple(found) + (None,) * (len(poses) - len(found))
    for k, pose in enumerate(poses):
        if pose is not None:
            shifted[f"every row is the pose in frame {k}: the same frame is used for every row"
                    + (FIRST_FRAME if k == 0 else "")] = \
                (pose,) * len(poses)
    for mistake, candidate in shifted.items():
        if _track_rows_match(got, candidate, poses, pattern, square):
            t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake.split(":")[0])
    errors = []
    for i, pose in enumerate(poses):
        row = got[i]
        if pose is None:
            if i > 0 and np.isfinite(row).all() and np.allclose(row, got[i - 1]):
                t.fail(f"{what}: frame {i} shows no board, but its row repeats the pose of frame {i - 1}: the "
                       "last pose is carried over; a frame without a board gets a NaN row.",
                       mistake="the last pose is carried over to frames without a board")
            if np.isfinite(row).any():
                zeros = " Zeros are a pose (the board at the camera centre), not 'not found'." \
                    if np.all(row == 0) else ""
                t.fail(f"{what}: frame {i} shows no board, so its row should be NaN (the API's marker for "
                       f"'not found'); yours is {format_matrix(row)}.{zeros}",
                       mistake="a frame without a board does not get a NaN row")
            continue
        R, tv = pose
        if not np.isfinite(row).all():
            lost = [k for k, p in enumerate(poses) if p is not None and not np.isfinite(got[k]).all()]
            if i > 0 and all(k > 0 and poses[k - 1] is None for k in lost) \
                    and WARM_START.found(code_of(t).reachable(["track_pose"])):
                # (every such frame follows one without a board, and each solve starts from the previous row)
                t.fail(f"{what}: frame {i} shows the whole board, but its row is NaN: "
                       + measured(f"frame {i - 1} shows none, and every frame with a board whose row is NaN follows "
                                  "a frame without one")
                       + "; " + from_code("your code gives cv2.solvePnP a starting pose (useExtrinsicGuess=True): "
                                          "a start taken from the row of a frame without a board is NaN, and so is "
                                          "the pose solved from it; start from the last pose found (or solve without "
                                          "a guess)"),
                       mistake=WARM_START_FROM_NAN)
            t.fail(f"{what}: frame {i} shows the whole board, but its row is NaN.")
        angle, shift, _ = truth.pose_error(row[:3], row[3:], R, tv, pattern, square)
        if angle > ANGLE_TOLERANCE or shift > TRANSLATION_TOLERANCE * np.linalg.norm(tv):
            swapped = truth.pose_error(row[3:], row[:3], R, tv, pattern, square)
            if swapped[0] <= ANGLE_TOLERANCE and swapped[1] <= TRANSLATION_TOLERANCE * np.linalg.norm(tv):
                t.fail(f"{what}: the rows are [tvec, rvec]; the API wants [rvec, tvec].")
            off = None if dist is None else _without_dist(got, frames, poses, K)
            fail_if_axes_exchanged(t, f"{what}: frame {i}", scene.rotation_from_rvec(row[:3]), R)
            if off is not None:
                t.fail(measured(f"{what}: every row is the pose cv2.solvePnP finds for the frame's corners without "
                                f"dist, as if the lens had no distortion (up to {off:.1%} of the distance off the true "
                                f"pose; at most {TRANSLATION_TOLERANCE:.0%} accepted): the dist given is not used."),
                       mistake="track_pose does not use dist")
            t.fail(f"{what}: frame {i}: the pose is off by {format_apart(angle, ANGLE_TOLERANCE, 2)} degrees "
                   f"and {format_apart(shift / np.linalg.norm(tv), TRANSLATION_TOLERANCE, 2, percent=True)} of "
                   f"the distance (at most {ANGLE_TOLERANCE:g} degrees and {TRANSLATION_TOLERANCE:.0%} accepted).")
        errors.append(angle)
    trajectory = np.array([pose[1] if pose else [np.nan] * 3 for pose in poses])
    t.svg("board position (x, z) along the sequence: truth vs yours"
          + (" (through the distorting lens)" if dist is not None else ""), svg_points(
        {"true": trajectory[:, [0, 2]], "yours": got[:, [3, 5]]}, flip_y=False))
    return passed(f"every frame within {max(errors):.2f} degrees")


# ================================================================== the API's conventions
# Each point alone, as among many: one row (1, 3) gives one row (1, 2) (a (3,) point is judged by the
# checks above).
conventions.point_by_point(ex1, "perspective_project", lambda: (truth.points_in_front(141, n=6), 500.0),
                           described="points, f=500")
conventions.point_by_point(ex2, "weak_perspective_project",
                           lambda: (truth.scene_points(142, n=6, depth=15.0, relief=3.0), 300.0, 12.0),
                           described="points, f=300, z_avg=12.0")
conventions.point_by_point(ex3, "orthographic_project", lambda: (truth.points_in_front(143, n=6),),
                           described="points")
# Whole numbers given as integers (the sheet's own sample point is (1, 1, 2)) answered as the same
# numbers given as floats: an array made like an integer input holds integers only.
conventions.whole_numbers(ex1, "perspective_project", lambda: (np.round(truth.points_in_front(151, n=6) * 10.0), 500.0),
                          described="points, f=500")
conventions.whole_numbers(ex2, "weak_perspective_project",
                          lambda: (np.round(truth.scene_points(152, n=6, depth=15.0, relief=3.0) * 10.0), 300.0),
                          described="points, f=300")
# (distances whose focal lengths f0 d / z0 are not whole numbers: 583.3 and 708.3 show an integer array cutting them)
conventions.whole_numbers(ext2, "dolly_zoom", lambda: (np.round(truth.points_in_front(154, n=6) * 10.0), 500.0, 60.0,
                                                       np.array([60.0, 70.0, 85.0])),
                          described="points, f0=500, z0=60, distances=[60, 70, 85]")
conventions.not_judged("integers", camera_matrix_dlt=conventions.MODEL,
                       orthographic_project="its answer is the points' own x and y: whole numbers in are whole "
                       "numbers out")
conventions.not_judged("rows", dolly_zoom="its projections are (F, N, 2): the points are their second axis",
                       camera_matrix_dlt=conventions.FITTED)
conventions.not_judged(
    "channels", undistort_image="judged on a grey image against the truth, and on a colour one",
    estimate_pose="its answer is no image; a colour photo and grey renders are judged against the truth",
    track_pose="its answer is no image; its frames are judged against the true trajectory")
