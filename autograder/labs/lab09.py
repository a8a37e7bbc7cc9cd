"""Lab 9 - geometric camera models: the public checks.

Ground truth comes from :mod:`fixtures.lab09` (projections by definition,
chessboard views rendered by :mod:`fixtures.scene` from a known camera), and
OpenCV's ``cv2.projectPoints`` for the distortion model. Wrong answers are
compared with what the usual mistakes would give, so the feedback can name them.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from typing import Callable

import numpy as np

from fixtures import lab09 as truth
from fixtures.lab09 import photo

from ..engine import conventions
from ..engine import strategies as st
from ..engine import judges
from ..engine import defaults_given
from ..engine.checks import Fail, StudentFailure, Trial, partial, passed
from ..engine.claims import (THIRD_COORDINATE, checklist, divides_by, evidenced, from_code, guard, guessed, look_at,
                             measured, where_to_look)
from ..engine.compare import at_precision, closest, format_apart, format_arrays_apart, magnitude, precision_floor
from ..engine.hints import (Hint, Predicate, _resolved, _scope, call_in_a_loop, calls, code_of, expr, functions_read, keyword,
                            matmul_of, mentions,
                            nan_behind)
from ..engine.hints import _path as _hints_path
from ..engine.judges import (BLANK_CANVAS, BLANK_CANVAS_HINT, Probe, blank_canvas, call_probe, confirm, fingerprint,
                              format_matrix)
from ..engine.pictures import svg_points
from ..engine.registry import Lab
from ..sandbox.beginner import RGB_ONLY_TO_SHOW, channels_reversed, integer_entries
from ..loading.parsing import walk

def _tangential_coefficient_swapped(function) -> bool:
    """Whether x's line gives p1 the term p2 belongs to (`x_t = ... p1 * (r2 + 2 * x ** 2)`), or y's line
    p2 p1's: the coefficients written in each other's place, where x and y swapped in the formulas put
    y's square in x's line instead."""
    wanted = {"x": [expr("p1 * (_ + _ * x ** 2)"), expr("p1 * (_ + _ * x * x)")],
              "y": [expr("p2 * (_ + _ * y ** 2)"), expr("p2 * (_ + _ * y * y)")]}
    for node in walk(function):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            axis = node.targets[0].id[:1]
            if axis in wanted and any(pattern.test(node.value) for pattern in wanted[axis]):
                return True
    return False


# p1 and p2 swapped gives the answer x and y swapped in the formulas gives (the model is symmetric): the
# code tells them apart
evidenced(truth.P1_P2_SWAPPED, Predicate("writes p1 where p2 belongs", _tangential_coefficient_swapped))

lab = Lab("lab09", module="lab09_camera", title="Geometric camera models")

# Names that ask for code, held to the student's code (autograder.engine.claims).
DIVIDES = (THIRD_COORDINATE | divides_by("Z", "z", "Z[:, None]", "z[:, None]", "Z[..., None]",
                                           says="divides by Z")).saying(
    "divides by a third coordinate")
# (named only where the answers are exactly the clamped ones, on the failing points and on the probe's)
measured(truth.DEPTH_CLAMPED)
for _missing in (truth.DIVISION_MISSING, truth.DIVISION_MISSING_KX):
    guard(_missing, asks=DIVIDES, instead="the perspective division is missing: your code {found}, but the "
          "points returned are not the divided ones")
guard(truth.K_TRANSPOSED, asks=(expr("_ @ K.T") | expr("np.dot(_, K.T)") | matmul_of("K", None)).saying(
          "multiplies by K"),
      instead="K is transposed (the points are multiplied by K^T where K X is due): your code {found}, so "
              "look at the points' layout: points @ K.T for (N, 3) rows, K @ X for (3, N) columns")
APPENDS_ONE = (mentions("np.ones") | mentions("np.ones_like") | expr("np.append(_, 1)") | expr("np.append(_, 1.0)")
               | expr("np.r_[_, 1]") | expr("np.c_[_, 1]")).saying("appends a 1 to the points")
TRANSLATION_DROPPED = guard(
    "the translation is dropped: append 1 to each point before applying P (P @ [X, Y, Z, 1])", asks=APPENDS_ONE,
    instead="the translation is dropped (P's last column has no effect): your code {found}, but the last "
            "column of P never multiplies it (P[:, :3] used?)")
PROJECTION_DIVISION_MISSING = guard(
    "the perspective division is missing (divide by the third coordinate)", asks=DIVIDES,
    instead="the perspective division is missing: your code {found}, but the points returned are not the "
            "divided ones")


def _focal_in_third_row(function) -> bool:
    """A matrix written as a literal of three rows (3x3 or 3x4) whose third row holds ``f``: the focal
    length multiplies the third coordinate too, and the division by it takes f out again."""
    for node in walk(function):
        if isinstance(node, (ast.List, ast.Tuple)) and len(node.elts) == 3 and all(
                isinstance(row, (ast.List, ast.Tuple)) and len(row.elts) in (3, 4) for row in node.elts):
            if any(isinstance(n, ast.Name) and n.id == "f" for n in walk(node.elts[2])):
                return True
    return False


guard(truth.FOCAL_NOT_APPLIED, asks=Predicate("puts f in its matrix's third row too", _focal_in_third_row),
      instead="the focal length cancels (x = X / Z; it should be f X / Z): your code {found} -- f multiplies the "
              "third coordinate as well, and the division by it takes f out again; the third row is [0, 0, 1, 0]")
ROUNDED = measured("the pixels are rounded to integers; return the exact (float) projection")
TRUNCATED = measured("the pixels are truncated to integers; return the exact (float) projection")
WRONG_DIVISOR = measured("the division is by the world point's Z; divide P [X, 1] by its own third coordinate")

seeds = st.integers(0, 2**32 - 1)


# ================================================================== confirmation probes
@dataclass(frozen=True)
class PointsProbe:
    """:func:`judge_points`' confirmation probe (see :class:`autograder.engine.judges.Probe`): the
    student's points on another input, and there the truth, what each mistake gives and the
    formulas a coordinate may have been computed with."""

    key: str
    answer: Callable
    expected: np.ndarray
    mistakes: dict
    formulas: dict

    def candidates_probe(self, tolerance: float) -> Probe:
        return Probe(self.key, self.answer, lambda: self.mistakes, self.expected, distance=point_error,
                     tolerance=tolerance * magnitude(self.expected))


def _probe_camera():
    K = np.array([[430.0, 1.5, 170.0], [0.0, 390.0, 115.0], [0.0, 0.0, 1.0]])
    R, tvec = truth.random_pose(909)
    return K, R, tvec


def points_probe(t: Trial, function: str) -> PointsProbe:
    """``function`` on its probe input: points of other depths, f far from the checks' values, a
    camera with fx != fy and a principal point apart from the origin, distortion coefficients of
    other signs: inputs on which the usual mistakes answer differently."""
    X = truth.points_in_front(9090, n=10)
    if function == "pinhole_project":
        f = 730.0
        args, expected = (X, f), truth.pinhole(X, f)
        mistakes, formulas = truth.projection_mistakes(f, X), pinhole_formulas(X, f)
    elif function == "project_with_intrinsics":
        K = _probe_camera()[0]
        args, expected = (K, X), truth.homogeneous_project(K, X)
        mistakes, formulas = truth.intrinsics_projection_mistakes(K, X), intrinsics_formulas(K, X)
    elif function in ("project", "project_onto_image"):
        K, R, tvec = _probe_camera()
        P = truth.camera(K, R, tvec)
        Xw = truth.world_points_for(K, R, tvec, seed=9091, n=10)
        args = (P, Xw) if function == "project" else (photo("coffee", (320, 240)), P, Xw)
        expected, mistakes, formulas = truth.homogeneous_project(P, Xw), project_mistakes(P, Xw), project_formulas(P, Xw)
    elif function == "project_focal_lengths":
        f = 260.0
        args, expected = (X, np.array([f, 900.0])), truth.pinhole(X, f)
        mistakes, formulas = truth.projection_mistakes(f, X), pinhole_formulas(X, f)
    elif function == "simulate_aperture":
        f = 340.0
        args, expected = (X, f, 0.0), truth.pinhole(X, f)
        mistakes, formulas = truth.projection_mistakes(f, X), pinhole_formulas(X, f)
    elif function == "distort_points":
        rng = np.random.default_rng(9092)
        pts = rng.uniform(-0.65, 0.65, size=(14, 2))
        dist = np.array([0.21, -0.13, -0.004, 0.007, 0.05])
        args, expected = (pts, dist), truth.distort_truth(pts, dist)
        mistakes, formulas = truth.distortion_mistakes(pts, dist), {}
    else:
        raise ValueError(f"no probe for {function}")

    def pick(got):
        if function == "project_onto_image":
            return got[1] if isinstance(got, (tuple, list)) and len(got) == 2 else None
        if function == "project_focal_lengths":
            return got[0] if isinstance(got, np.ndarray) and got.ndim == 3 else None
        if function == "simulate_aperture":
            return got.mean(axis=1) if isinstance(got, np.ndarray) and got.ndim == 3 else None
        return got

    return make_points_probe(t, function, args, {}, expected, mistakes, formulas, pick)


def make_points_probe(t: Trial, function: str, args, kwargs, expected, mistakes, formulas=None,
                      pick=None) -> PointsProbe:
    """A :class:`PointsProbe` calling ``function(*args, **kwargs)``; ``pick`` takes the points
    out of what it returns (by default the value itself)."""
    expected = np.asarray(expected, dtype=np.float64)

    def answer():
        got = t.call(function, *args, **kwargs)
        got = pick(got) if pick is not None else got
        if not (isinstance(got, np.ndarray) and got.shape == expected.shape and got.dtype.kind in "iuf"):
            return None
        return got

    return PointsProbe(f"{function}/{fingerprint(args, kwargs)}", answer, expected, dict(mistakes),
                       dict(formulas or {}))


def matrix_probe(t: Trial, function: str) -> Probe:
    """intrinsic_matrix or camera_matrix on a probe input (f, px, py all apart; a general camera)."""
    if function == "intrinsic_matrix":
        f, px, py = 733.0, 291.5, 187.25
        return call_probe(t, function, (f, px, py), candidates=lambda: truth.intrinsic_mistakes(f, px, py),
                          truth=truth.intrinsic(f, px, py), shape=(3, 3))
    K, R, tvec = _probe_camera()
    return call_probe(t, function, (K, R, tvec), candidates=lambda: truth.camera_mistakes(K, R, tvec),
                      truth=truth.camera(K, R, tvec), shape=(3, 4))


# ================================================================== shared judges
def point_error(got, expected) -> float:
    """Largest distance between corresponding points; NaN must meet NaN."""
    got = np.asarray(got, dtype=np.float64)
    expected = np.asarray(expected, dtype=np.float64)
    if got.shape != expected.shape:
        return float("inf")
    nan_expected = np.isnan(expected).any(axis=-1)
    nan_got = ~np.isfinite(got).all(axis=-1)
    if np.any(nan_expected != nan_got):
        return float("inf")
    keep = ~nan_expected
    if not keep.any():
        return 0.0
    return float(np.max(np.linalg.norm(got[keep] - expected[keep], axis=-1)))


def expect_points(t: Trial, what: str, got, shape) -> np.ndarray:
    """Shape-check a returned point array, naming a transposed result."""
    if isinstance(got, np.ndarray) and got.ndim == 2 and len(shape) == 2 and got.shape == shape[::-1] \
            and shape[0] != shape[1]:
        t.fail(f"{what} returned shape {got.shape}; expected {shape}: one row (x, y) per point "
               "(the result is transposed)", mistake="the result is transposed")
    expect_shape(t, what, got, shape)
    return t.expect_array(got, what, shape=shape, kind="iuf")


def expect_shape(t: Trial, what: str, got, shape, axes=None):
    """Name the usual shape slips of an array result: axes in another order, a third
    (homogeneous or Z) coordinate kept. ``axes`` names the expected axes ("F", "N", "2")."""
    if not isinstance(got, np.ndarray) or got.shape == tuple(shape):
        return
    shape = tuple(shape)
    if got.ndim == len(shape) and sorted(got.shape) == sorted(shape) and len(set(shape)) == len(shape):
        if axes:
            order = ", ".join(axes[shape.index(n)] for n in got.shape)
            t.fail(f"{what} returned shape {got.shape}, i.e. ({order}); expected {shape} = ({', '.join(axes)}): "
                   "the axes are in the wrong order.", mistake="the axes are in the wrong order")
        t.fail(f"{what} returned shape {got.shape}; expected {shape}: the axes are in the wrong order.",
               mistake="the axes are in the wrong order")
    if got.shape == shape[:-1] + (3,) and shape[-1] == 2:
        t.fail(f"{what} returned shape {got.shape}; expected {shape}: a third coordinate is kept (Z is kept, "
               "or the homogeneous one); only (x, y) is expected.", mistake="a third coordinate is kept")


def judge_points(t: Trial, what: str, got, expected, mistakes=None, tolerance=1e-6, show=None,
                 mistake_tolerance=1e-4, formulas=None, probe: PointsProbe | None = None):
    """Compare returned 2D points with the truth; name the mistake when one fits.

    ``show`` (a title) attaches a plot of the true and the returned points.
    ``tolerance`` is relative to the largest coordinate, raised to float32's precision.
    A mistake is named when its answer is within ``mistake_tolerance`` (relative
    to the largest coordinate) and clearly closer than any other and than the truth,
    here and on the ``probe``'s input (:func:`points_probe`; without one nothing is named).
    Otherwise ``formulas`` (see :func:`fixtures.lab09.coordinate_formulas`) may say
    which formula each coordinate was computed with, when they say it on the probe too.
    """
    expected = np.asarray(expected, dtype=np.float64)
    got = expect_points(t, what, got, expected.shape)
    scale = magnitude(expected)
    tolerance = at_precision(tolerance * scale, scale) / scale
    error = point_error(got, expected)
    if show and got.ndim == 2:
        truth_pts = expected.reshape(-1, 2)
        got_pts = np.asarray(got, float).reshape(-1, 2)
        t.svg(show, svg_points({"true projection": truth_pts, "yours": got_pts},
                               lines=list(zip(truth_pts, got_pts))))
    if error <= tolerance * scale:
        return got
    rounded = {ROUNDED: np.round(expected), TRUNCATED: np.trunc(expected)}
    if np.isfinite(expected).all():
        slip = closest(got, rounded, point_error, 1e-9, truth=expected, margin=1.0)
        if slip:
            t.fail(f"{what} is wrong: {slip}.", mistake="the pixels are rounded to integers")
    mistake = closest(got, mistakes or {}, point_error, mistake_tolerance * scale, truth=expected)
    if mistake and probe is not None:
        mistake = confirm(t, mistake, probe.candidates_probe(mistake_tolerance))
        if mistake:
            t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    explained = explain_coordinates(got, expected, formulas or {})
    if explained and probe is not None:
        again = t.probe(probe.key, probe.answer)
        if again is not None and explain_coordinates(again, probe.expected, probe.formulas) == explained:
            t.fail(f"{what} is wrong: {explained}.{_skew_not_taken(t, explained)}", mistake=explained)
    if not np.isnan(expected).any() and np.isnan(got).any():
        t.fail(f"{what} returned NaN for points in front of the camera (Z > 0).")
    worst = _worst_point(got, expected)
    wanted, shown = format_arrays_apart(expected.reshape(-1, 2)[worst], np.asarray(got, float).reshape(-1, 2)[worst])
    t.fail(f"{what} is off {where_points_wrong(got, expected, tolerance * scale)}, by up to "
           f"{format_apart(error, tolerance * scale, 4)}; for example point {worst} should be {wanted}, "
           f"yours is {shown}.")


SKEW_TERM = " + s Y / Z"


def _skew_not_taken(t: Trial, explained: str) -> str:
    """Where x lacks only the skew term and the code projects with cv2.projectPoints: that call takes no
    skew (its camera matrix is read for fx, fy, cx and cy; K[0, 1] never), so the term is lost there."""
    computed, _, wanted = explained.partition("; it should be ")
    if not (computed.startswith("x is computed as ") and wanted == computed[len("x is computed as "):] + SKEW_TERM):
        return ""
    if not calls("cv2.projectPoints").found(code_of(t).reachable(functions_read(t))):
        return ""
    return from_code(" Your code projects with cv2.projectPoints, which takes no skew: it reads fx, fy, cx and cy "
                     "of the camera matrix, never K[0, 1]; add s Y / Z yourself, or project with K @ X.")


def _worst_point(got, expected) -> int:
    """The index of the point farthest from the truth (a non-finite one first)."""
    got = np.asarray(got, np.float64).reshape(-1, 2)
    expected = np.asarray(expected, np.float64).reshape(-1, 2)
    with np.errstate(invalid="ignore"):
        distance = np.linalg.norm(got - expected, axis=1)
    distance = np.where(np.isfinite(expected).all(axis=1), np.nan_to_num(distance, nan=np.inf), -1.0)
    return int(np.argmax(distance))


def explain_coordinates(got, expected, formulas: dict) -> str:
    """"y = fx Y / Z + py; it should be fy Y / Z + py": the one formula each wrong coordinate
    equals, when every wrong coordinate equals exactly one (else "")."""
    got = np.asarray(got, np.float64).reshape(-1, 2)
    expected = np.asarray(expected, np.float64).reshape(-1, 2)
    keep = np.isfinite(expected).all(axis=1)
    if not formulas or not keep.any() or not np.isfinite(got[keep]).all():
        return ""

    def matching(column):
        scale = max(1.0, float(np.abs(column).max()))
        return [words for words, value in formulas.items()
                if np.all(np.abs(np.broadcast_to(value, got.shape[:1])[keep] - column)
                          <= at_precision(1e-7 * scale, scale))]

    parts, computed, wanted = [], [], []
    for j, name in enumerate("xy"):
        right = matching(expected[keep, j])
        column_scale = max(1.0, np.abs(expected[keep, j]).max())
        if np.allclose(got[keep, j], expected[keep, j], rtol=0, atol=at_precision(1e-7 * column_scale, column_scale)):
            continue
        found = matching(got[keep, j])
        if not found or not right or any(not np.allclose(np.broadcast_to(formulas[w], got.shape[:1])[keep],
                                                           np.broadcast_to(formulas[found[0]], got.shape[:1])[keep])
                                         for w in found[1:]):
            return ""           # unexplained, or explained by formulas that differ elsewhere: no guess
        parts.append(f"{name} is computed as {found[0]}; it should be {right[0]}")
        computed.append(found[0])
        wanted.append(right[0])
    if len(parts) == 2 and computed == wanted[::-1]:
        return f"x and y are swapped (x should be {wanted[0]}, y {wanted[1]})"
    return "; ".join(parts)


def where_points_wrong(got, expected, tolerance) -> str:
    """Which points and coordinates are off, and whether by a common shift or a common factor."""
    got = np.asarray(got, np.float64).reshape(-1, 2)
    expected = np.asarray(expected, np.float64).reshape(-1, 2)
    where = judges.where_points_differ(got, expected, tolerance)
    keep = np.isfinite(got).all(axis=1) & np.isfinite(expected).all(axis=1)
    if keep.sum() >= 2:
        shift = got[keep] - expected[keep]
        if np.ptp(shift, axis=0).max() <= tolerance:
            return f"{where} by the same shift {format_matrix(shift[0])} (an offset is added or missing)"
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = got[keep] / expected[keep]
        ratio = ratio[np.abs(expected[keep]) > tolerance]
        if ratio.size and not np.any(got[keep]):
            return f"{where} (every coordinate returned is 0)"
        if ratio.size and np.ptp(ratio) <= 1e-6 * max(1.0, np.abs(ratio).max()):
            return f"{where} by the same factor {ratio[0]:.4g} (a scale is applied wrongly)"
    return where


SINGLE_POINT_HINT = Hint(
    " (np.atleast_2d in, [0] out)", asks=calls("np.atleast_2d"),
    instead=" (your code calls np.atleast_2d: a (3,) point's result is row [0] of what it "
            "computes)")


def judge_single_point(t: Trial, what: str, got, expected):
    """A single (3,) point must give a single (2,) result."""
    if isinstance(got, np.ndarray) and got.shape == (1, 2):
        t.fail(f"{what} returned shape (1, 2) for a single (3,) point; expected (2,): "
               "a (3,) point gives a (2,) result" + SINGLE_POINT_HINT.said(t))
    got = t.expect_array(got, what, shape=(2,), kind="iuf")
    scale = magnitude(expected)
    if point_error(got[None], np.asarray(expected)[None]) > at_precision(1e-6 * scale, scale):
        integers = integer_entries(got, expected)
        if integers:   # (where the code makes an array like its integer input and writes into it: that line)
            why = conventions.why_integers(t, t.calls[-1][0]) if t.calls else ""   # (the function just called)
            said = f"it holds integers ({got.dtype}), where the answer has fractions.{why}" if why else integers
            t.fail(f"{what} is wrong: {said}", mistake="integer arithmetic: the fractions are cut off")
        shown, wanted = format_arrays_apart(got, expected)
        t.fail(f"{what} returned {shown}; expected {wanted}")


def call_behind(t: Trial, what: str, function: str, *args):
    """``t.call(function, *args)`` on points some of which are at Z = 0 or behind the camera: an
    exception the student's code raises says which input it met (one convention for every lab
    sharing a projection's form: such points must not stop the others' projection)."""
    try:
        return t.call(function, *args)
    except StudentFailure as failure:
        if failure.outcome.kind != "exception":
            raise
        if _raises_in_front_too(t, function, args):   # (the points behind are not what it stumbles on: 06k 10/01)
            raise StudentFailure(failure.outcome, f"{what}: {failure.message}") from None
        raise StudentFailure(failure.outcome, f"{what}: {failure.message}\nThese points include one at Z = 0 "
                             "(on the camera's principal plane) and some behind the camera (Z < 0): the "
                             "projection must not raise for them (NaN is the usual value there).") from None


def _raises_in_front_too(t: Trial, function: str, args) -> bool:
    """Whether ``function`` raises on the same call with only the points in front of the camera (the (N, 3)
    argument's rows with Z > 0, three at least): then its exception is not the points behind's."""
    at = next((k for k, a in enumerate(args) if isinstance(a, np.ndarray) and a.ndim == 2 and a.shape[1] == 3
               and np.any(a[:, 2] <= 0)), None)
    if at is None:
        return False
    front = args[at][args[at][:, 2] > 0]
    if len(front) < 3:
        return False
    try:
        t.call(function, *args[:at], front, *args[at + 1:])
    except StudentFailure as failure:
        return failure.outcome.kind == "exception"
    return False


def judge_in_front(t: Trial, what: str, got, expected, behind):
    """With some points behind the camera (Z <= 0), one row per point and those in front right.

    The lab sheet's formulas give *some* value behind the camera; what it is
    earns no points either way (NaN is advice: :func:`advise_nan_behind`).
    """
    if isinstance(got, np.ndarray) and got.ndim == 2 and got.shape[1:] == (2,) \
            and len(got) == int((~behind).sum()) != len(behind):
        t.fail(f"{what} returned {len(got)} rows for {len(behind)} points: "
               + measured("it drops the points behind the camera; return one row per input point (NaN is the "
                          "usual value for a point with no image)"))
    got = np.asarray(expect_points(t, what, got, expected.shape), dtype=np.float64)
    front = ~behind
    error = point_error(got[front], expected[front])
    scale = magnitude(expected[front])
    tolerance = at_precision(1e-6 * scale, scale)
    if error > tolerance:
        t.fail(f"{what}: with some points behind the camera, the points in front are off by "
               f"up to {format_apart(error, tolerance, 4)} px (at most {tolerance:.2g} px accepted).")


NAN_BEHIND_HINT = nan_behind("e.g. np.where(Z[:, None] > 0, projected, np.nan)")


def advise_nan_behind(t: Trial, what: str, got, behind, in_front=None):
    """Advice: a point behind the camera (Z <= 0) has no image; NaN says so. ``in_front``: the right pixels of
    the other points, where known -- where those are wrong, the points the answer projects are not the ones
    meant (a dolly's depths moved otherwise), and the graded checks say so: no tip about the others."""
    got = np.asarray(got, dtype=np.float64) if isinstance(got, np.ndarray) else None
    if got is None or got.shape != (len(behind), 2):
        return  # the graded check says what is wrong with the shape
    if in_front is not None and not np.allclose(got[~behind], np.asarray(in_front, float)[~behind], rtol=1e-6, atol=1e-6):
        return
    finite = behind & np.isfinite(got).all(axis=1)
    infinite = behind & ~np.isnan(got).any(axis=1) & ~finite   # (Z = 0 divided by: inf)
    if finite.any():
        t.advise(f"{what} gave finite pixels for the points with Z <= 0 (rows "
                 f"{np.nonzero(finite)[0].tolist()}): they are behind the camera and have no "
                 "image (the formula mirrors them through the pinhole); NaN tells the caller so. "
                 "No points depend on it.",
                 hint=NAN_BEHIND_HINT.said(t))
    if infinite.any():   # (the hint once, beside the finite rows' tip when there is one)
        t.advise(f"{what} gave infinite values for the points on the camera plane (rows "
                 f"{np.nonzero(infinite)[0].tolist()}: Z = 0, the division by Z): they have no image; NaN tells the "
                 "caller so. No points depend on it.", hint="" if finite.any() else NAN_BEHIND_HINT.said(t))


def judge_matrix(t: Trial, what: str, got, expected, mistakes=None, shape=(3, 3), up_to_scale=False):
    """The shared matrix judge, with this lab's tighter tolerance; where the matrix is defined exactly
    (K, whose K[2, 2] is 1), one right only up to a factor is named as such. P is the API's projective
    quantity: its checks pass ``up_to_scale`` (any non-zero scale, sign included)."""
    scale = magnitude(expected)
    if not up_to_scale and isinstance(got, np.ndarray) and got.shape == tuple(shape) and got.dtype.kind in "iuf" \
            and np.isfinite(got).all() and np.abs(got - expected).max() > at_precision(1e-7 * scale, scale):
        from ..engine.compare import projective_distance
        if projective_distance(got, expected) <= precision_floor():
            i = np.unravel_index(np.argmax(np.abs(expected)), expected.shape)
            factor = got[i] / expected[i]
            t.fail(f"{what} is wrong: it is {factor:.4g} times the right matrix: it is right only up to "
                   "scale" + measured("; return the matrix itself, not a rescaled one."),
                   mistake="the matrix is rescaled")
    function = what.split("(")[0]
    return judges.judge_matrix(t, what, got, expected, mistakes, shape, up_to_scale, rtol=1e-7,
                               probe=matrix_probe(t, function))


# ================================================================== ex1 pinhole
ex1 = lab.exercise("ex1", "The pinhole camera", functions=["pinhole_project(points, f)"])

SHEET_POINTS = np.array([[1.0, 2.0, 10.0], [-3.0, 1.5, 5.0], [0.5, -0.5, 2.0], [4.0, 3.0, 20.0]])


def pinhole_formulas(X, f):
    """The formulas one coordinate of a pinhole projection may have been computed with."""
    return truth.coordinate_formulas(X, {"f": f, "": 1.0, "f^2": f * f, "-f": -f, "1 / f": 1.0 / f}, {"": 0.0})


def intrinsics_formulas(K, X):
    """The formulas one coordinate of ``K X`` (divided) may have been computed with."""
    K = np.asarray(K, float)
    gains = {"fx": K[0, 0], "fy": K[1, 1], "": 1.0}
    offsets = {"": 0.0, "+ px": K[0, 2], "+ py": K[1, 2], "- px": -K[0, 2], "- py": -K[1, 2]}
    return truth.coordinate_formulas(X, gains, offsets, skew=K[0, 1])


@ex1.check("pinhole_project on the lab sheet's points, f = 500", points=3)
def pinhole_example(t):
    judge_points(t, "pinhole_project(points, f=500)", t.call("pinhole_project", SHEET_POINTS, 500.0),
                 truth.pinhole(SHEET_POINTS, 500.0), truth.projection_mistakes(500.0, SHEET_POINTS),
                 formulas=pinhole_formulas(SHEET_POINTS, 500.0),
                 show="pinhole projection, f = 500", probe=points_probe(t, "pinhole_project"))


@ex1.check("pinhole_project for any points in front and any f", points=3)
def pinhole_property(t):
    def holds(case):
        seed, f = case
        # (any depth in front: near the camera, Z < 1, as well as far -- a depth clamped at 1 shows only there)
        X = truth.points_in_front(seed, n=10, z_range=ANY_DEPTH)
        judge_points(t, f"pinhole_project(points, f={f!r})", t.call("pinhole_project", X, f),
                     truth.pinhole(X, f), truth.projection_mistakes(f, X), formulas=pinhole_formulas(X, f),
                     probe=points_probe(t, "pinhole_project"))

    t.for_all(st.tuples(seeds, st.floats(10.0, 2000.0)), holds, max_examples=15,
              describe=lambda c: f"fixtures.lab09.points_in_front(seed={c[0]}, n=10, z_range={ANY_DEPTH}), "
                                 f"f={c[1]!r}")


ANY_DEPTH = (0.1, 10.0)


READS_NDIM = expr("_.ndim") | calls("np.ndim")


@ex1.check("a single (3,) point gives a single (2,) result, the lab sheet's (1, 1, 2) with f = 1 too; "
           "one row (1, 3) gives (1, 2)", points=1)
def pinhole_single(t):
    X = np.array([0.3, -0.2, 4.0])
    judge_single_point(t, "pinhole_project((3,) point, f=100)", t.call("pinhole_project", X, 100.0),
                       truth.pinhole(X, 100.0)[0])
    # An (N, 3) array with N = 1 is an array of points like any other: one row back, not a single point.
    row = t.call("pinhole_project", X[None], 100.0)
    if isinstance(row, np.ndarray) and row.shape == (2,):
        by_ndim = READS_NDIM.found(code_of(t).reachable(["pinhole_project"]))
        t.fail("pinhole_project((1, 3) array, f=100) returned shape (2,); expected (1, 2): only a (3,) point "
               "gives a (2,) result, an (N, 3) array gives (N, 2) for N = 1 too"
               + (" (your code reads the input's number of dimensions: follow where the (2,) is made)" if by_ndim
                  else " (tell them apart by the input's number of dimensions, not by its length)"))
    row, expected = t.expect_array(row, "pinhole_project((1, 3) array, f=100)", shape=(1, 2), kind="iuf"), \
        truth.pinhole(X[None], 100.0)
    if point_error(row, expected) > at_precision(1e-6 * magnitude(expected), magnitude(expected)):
        shown, wanted = format_arrays_apart(row, expected)
        t.fail(f"pinhole_project((1, 3) array, f=100) returned {shown}; expected {wanted}")
    # The sheet's own sample, as a student types it: whole numbers, so an integer array.
    sample = np.array([1, 1, 2])
    judge_single_point(t, "pinhole_project(np.array([1, 1, 2]), f=1)", t.call("pinhole_project", sample, 1),
                       truth.pinhole(sample.astype(float), 1.0)[0])


def pinhole_behind_case():
    X, behind = truth.with_points_behind(truth.points_in_front(5, n=10), seed=6)
    return "pinhole_project(points with some Z <= 0, f=300)", X, behind


@ex1.check("with points behind the camera (Z <= 0), those in front stay right", points=1)
def pinhole_behind(t):
    what, X, behind = pinhole_behind_case()
    judge_in_front(t, what, call_behind(t, what, "pinhole_project", X, 300.0), truth.pinhole(X, 300.0), behind)


@ex1.advice("NaN for points behind the camera")
def pinhole_behind_nan(t):
    what, X, behind = pinhole_behind_case()
    advise_nan_behind(t, what, t.call("pinhole_project", X, 300.0), behind, truth.pinhole(X, 300.0))


# ================================================================== ex2 intrinsics
ex2 = lab.exercise("ex2", "The intrinsic matrix", functions=[
    "intrinsic_matrix(f, px, py)", "project_with_intrinsics(K, points)"])


@ex2.check("intrinsic_matrix(500, 320, 240)", points=2)
def intrinsic_example(t):
    # (the numbers as written, whole: a K of integers cuts off every fraction computed with it)
    judge_matrix(t, "intrinsic_matrix(500, 320, 240)", t.call("intrinsic_matrix", 500, 320, 240),
                 truth.intrinsic(500, 320, 240), truth.intrinsic_mistakes(500, 320, 240))
    # (a whole focal length given as an int, the principal point at a pixel's edge: 640 x 480's centre)
    judge_matrix(t, "intrinsic_matrix(500, 319.5, 239.5)", t.call("intrinsic_matrix", 500, 319.5, 239.5),
                 truth.intrinsic(500, 319.5, 239.5), truth.intrinsic_mistakes(500, 319.5, 239.5))


@ex2.check("intrinsic_matrix for any f, px, py", points=1)
def intrinsic_property(t):
    def holds(case):
        f, px, py = case
        judge_matrix(t, f"intrinsic_matrix({f!r}, {px!r}, {py!r})", t.call("intrinsic_matrix", f, px, py),
                     truth.intrinsic(f, px, py), truth.intrinsic_mistakes(f, px, py))

    t.for_all(st.tuples(st.floats(1.0, 3000.0), st.floats(0.0, 2000.0), st.floats(0.0, 2000.0))
              .filter(lambda c: abs(c[1] - c[2]) > 1e-3), holds, max_examples=10)


@ex2.check("project_with_intrinsics(K, points)", points=3)
def project_intrinsics_example(t):
    K = truth.intrinsic(500.0, 320.0, 240.0)
    X = truth.points_in_front(21, n=12)
    judge_points(t, "project_with_intrinsics(K, points)", t.call("project_with_intrinsics", K, X),
                 truth.homogeneous_project(K, X), truth.intrinsics_projection_mistakes(K, X),
                 show="projection with K", formulas=intrinsics_formulas(K, X),
                 probe=points_probe(t, "project_with_intrinsics"))


@ex2.check("project_with_intrinsics with non-square pixels, skew, and a single point", points=1)
def project_intrinsics_general(t):
    K = np.array([[420.0, 2.0, 150.0], [0.0, 380.0, 110.0], [0.0, 0.0, 1.0]])
    X = truth.points_in_front(22, n=8)
    judge_points(t, "project_with_intrinsics(K with fx != fy and skew, points)",
                 t.call("project_with_intrinsics", K, X), truth.homogeneous_project(K, X),
                 truth.intrinsics_projection_mistakes(K, X), formulas=intrinsics_formulas(K, X),
                 probe=points_probe(t, "project_with_intrinsics"))
    judge_single_point(t, "project_with_intrinsics(K, (3,) point)",
                       t.call("project_with_intrinsics", K, X[0]), truth.homogeneous_project(K, X[0])[0])


def intrinsics_behind_case():
    K = truth.intrinsic(400.0, 160.0, 120.0)
    X, behind = truth.with_points_behind(truth.points_in_front(23, n=10), seed=24)
    return "project_with_intrinsics(K, points with some Z <= 0)", K, X, behind


@ex2.check("project_with_intrinsics: with points behind the camera, those in front stay right", points=1)
def project_intrinsics_behind(t):
    what, K, X, behind = intrinsics_behind_case()
    judge_in_front(t, what, call_behind(t, what, "project_with_intrinsics", K, X), truth.homogeneous_project(K, X),
                   behind)


@ex2.advice("NaN for points behind the camera")
def project_intrinsics_behind_nan(t):
    what, K, X, behind = intrinsics_behind_case()
    advise_nan_behind(t, what, t.call("project_with_intrinsics", K, X), behind, truth.homogeneous_project(K, X))


# ================================================================== ex3 full camera
ex3 = lab.exercise("ex3", "The full camera matrix", functions=[
    "camera_matrix(K, R, t)", "project(P, points)"])


def _example_camera(seed=31):
    K = np.array([[400.0, 0.0, 160.0], [0.0, 410.0, 120.0], [0.0, 0.0, 1.0]])
    R, tvec = truth.random_pose(seed)
    return K, R, tvec


# P is a projective quantity: the API's conventions accept any non-zero scale of it, sign included (the blind
# legitimate set 1206n's K [R | t] scaled to unit norm and negated lost 3 points), here as wherever P is judged.
@ex3.check("camera_matrix(K, R, t) = K [R | t], for a camera at the world origin too (t = 0)", points=2)
def camera_matrix_example(t):
    K, R, tvec = _example_camera()
    judge_matrix(t, "camera_matrix(K, R, t)", t.call("camera_matrix", K, R, tvec),
                 truth.camera(K, R, tvec), truth.camera_mistakes(K, R, tvec), shape=(3, 4), up_to_scale=True)
    # (t = 0: the camera at the world origin, P = K [R | 0] -- still 3 x 4, its last column 0)
    zero = np.zeros(3)
    judge_matrix(t, "camera_matrix(K, R, t=np.zeros(3))", t.call("camera_matrix", K, R, zero),
                 truth.camera(K, R, zero), truth.camera_mistakes(K, R, zero), shape=(3, 4), up_to_scale=True)


@ex3.check("camera_matrix for random cameras", points=1)
def camera_matrix_property(t):
    def holds(seed):
        K, R, tvec = _example_camera(seed)
        judge_matrix(t, "camera_matrix(K, R, t)", t.call("camera_matrix", K, R, tvec),
                     truth.camera(K, R, tvec), truth.camera_mistakes(K, R, tvec), shape=(3, 4), up_to_scale=True)

    t.for_all(seeds, holds, max_examples=8, describe=lambda s: f"fixtures.lab09.random_pose({s})")


# (the skeleton gives t as (3,); cv2.solvePnP and cv2.calibrateCamera give a pose's t as a (3, 1) column --
# the blind set 1205f's 09/02 inserted it as three columns)
conventions.column_vector(ex3, "camera_matrix", _example_camera, 2, "t")


def project_formulas(P, X):
    """The formulas one coordinate of ``project`` may have been computed with, in terms of
    the entries of ``P [X, 1]``: ``(P X)[0] / (P X)[2]``, ``(P X)[2]``..."""
    h = np.column_stack([X, np.ones(len(X))]) @ np.asarray(P, float).T
    parts = {f"(P X)[{i}]": h[:, i] for i in range(3)}
    out = {f"{a} / {b}": parts[a] / parts[b] for a in parts for b in parts if a != b}
    out.update(parts)
    out["1 (a coordinate divided by itself)"] = np.ones(len(X))
    return out


def project_mistakes(P, X):
    Xh = np.column_stack([X, np.ones(len(X))])
    x = Xh @ P.T
    right = truth.homogeneous_project(P, X)
    return {
        PROJECTION_DIVISION_MISSING: x[:, :2],
        "x and y are swapped": right[:, ::-1],
        TRANSLATION_DROPPED: truth.homogeneous_project(P[:, :3], X),
        WRONG_DIVISOR: x[:, :2] / X[:, 2:3],
    }


@ex3.check("project(P, points) for world points in view", points=3)
def project_example(t):
    K, R, tvec = _example_camera()
    P = truth.camera(K, R, tvec)
    X = truth.world_points_for(K, R, tvec, seed=32)
    judge_points(t, "project(P, points)", t.call("project", P, X), truth.homogeneous_project(P, X),
                 project_mistakes(P, X), show="projection with P = K [R | t]", formulas=project_formulas(P, X),
                 probe=points_probe(t, "project"))


def other_cameras():
    """``(what, P, X)``: cameras the usual set-up (world origin some metres ahead) leaves out, with
    world points in their view: P at another scale, a camera at the world origin (t = 0, so
    P[2, 3] = 0: the world origin on the camera's principal plane) and one the world origin is
    behind (t_z < 0, P[2, 3] < 0). P is only defined up to a positive factor; its last column is
    any camera's too."""
    K, R, tvec = _example_camera(33)
    P = truth.camera(K, R, tvec)
    cameras = [("2.5 * P", 2.5 * P, truth.world_points_for(K, R, tvec, seed=34, n=6))]
    # (and a small one, as a DLT returns it: P / |P|, its w about 1e-3 -- an epsilon added to w is not small beside
    # it, where a guard against w near 0 of up to 1e-4 still lets every point through)
    cameras.append(("P / |P| (a unit-norm P, as a DLT returns it)", P / np.linalg.norm(P),
                    truth.world_points_for(K, R, tvec, seed=41, n=6)))
    R, _ = truth.random_pose(37)
    cameras.append(("P of a camera at the world origin (t = 0, P[2, 3] = 0)", truth.camera(K, R, np.zeros(3)),
                    truth.world_points_for(K, R, np.zeros(3), seed=38, n=6)))
    R, tvec = truth.random_pose(39)
    tvec = tvec - (0.0, 0.0, 9.0)
    cameras.append((f"P of a camera the world origin is behind (t_z = {tvec[2]:.2f}, P[2, 3] < 0)",
                    truth.camera(K, R, tvec), truth.world_points_for(K, R, tvec, seed=40, n=6)))
    return cameras


@ex3.check("project for any camera: P at any scale, the world origin on or behind the camera's plane "
           "(P[2, 3] = 0 or < 0), and a single (3,) point", points=1)
def project_scale(t):
    for name, P, X in other_cameras():
        judge_points(t, f"project({name}, points)", t.call("project", P, X), truth.homogeneous_project(P, X),
                     project_mistakes(P, X), probe=points_probe(t, "project"))
    _, P, X = other_cameras()[0]
    judge_single_point(t, "project(2.5 * P, (3,) point)", t.call("project", P, X[0]),
                       truth.homogeneous_project(P, X[0])[0])


def project_behind_case():
    K, R, tvec = _example_camera(35)
    P = truth.camera(K, R, tvec)
    Xc, behind = truth.with_points_behind(truth.points_in_front(36, n=10), seed=37)
    X = (Xc - tvec) @ R                       # camera-frame points to world points
    return "project(P, points with some behind the camera)", P, X, behind


@ex3.check("project: with points behind the camera, those in front stay right", points=1)
def project_behind(t):
    what, P, X, behind = project_behind_case()
    judge_in_front(t, what, call_behind(t, what, "project", P, X), truth.homogeneous_project(P, X), behind)


@ex3.advice("NaN for points behind the camera")
def project_behind_nan(t):
    what, P, X, behind = project_behind_case()
    advise_nan_behind(t, what, t.call("project", P, X), behind, truth.homogeneous_project(P, X))


# ================================================================== ex4 focal length, aperture
ex4 = lab.exercise("ex4", "Focal length and pinhole size", functions=[
    "project_focal_lengths(points, focal_lengths)",
    "simulate_aperture(points, f, aperture, n_rays=100, seed=None)"])


@ex4.check("project_focal_lengths: one pinhole projection per focal length, (F, N, 2)", points=3)
def focal_lengths(t):
    X = truth.points_in_front(41, n=9)
    fs = np.array([100.0, 500.0, 1000.0])
    expected = np.stack([truth.pinhole(X, f) for f in fs])
    got = t.call("project_focal_lengths", X, fs)
    if isinstance(got, np.ndarray) and got.shape == (9, 3, 2):
        t.fail("project_focal_lengths returned shape (N, F, 2) = (9, 3, 2); expected (F, N, 2) = (3, 9, 2): "
               "one (N, 2) projection per focal length, stacked along the first axis")
    expect_shape(t, "project_focal_lengths(points, [100, 500, 1000])", got, (3, 9, 2), axes=("F", "N", "2"))
    got = t.expect_array(got, "project_focal_lengths(points, [100, 500, 1000])", shape=(3, 9, 2), kind="iuf")
    t.svg("projections for f = 100, 500, 1000", svg_points(
        {f"f = {f:g}": got[i] for i, f in enumerate(fs)}))
    scale = magnitude(expected)
    order = [next((j for j in range(len(fs)) if point_error(got[i], expected[j]) <= at_precision(1e-6 * scale, scale)),
                  None) for i in range(len(fs))]
    if None not in order and order != list(range(len(fs))):
        t.fail(*focal_order_named(fs[order], fs))
    for i, f in enumerate(fs):
        judge_points(t, f"project_focal_lengths(...)[{i}] (f = {f:g})", got[i], expected[i],
                     truth.projection_mistakes(f, X), probe=points_probe(t, "project_focal_lengths"))
    return passed("the image grows in proportion to f")


def judge_single_point_rays(t: Trial, what: str, got, expected):
    """simulate_aperture given a single (3,) point, where the API documents (N, 3) points and promises a single
    point a single result (``expected``: that point's (1, n_rays, 2) answer): (n_rays, 2) or (1, n_rays, 2) are
    both fair readings of it; raising is not."""
    if isinstance(got, np.ndarray) and got.shape == expected.shape[1:]:
        got = got[None]
    got = t.expect_array(got, what, shape=expected.shape, kind="iuf", finite=True)
    scale = magnitude(expected)
    if np.abs(got - expected).max() > at_precision(1e-6 * scale, scale):
        shown, wanted = format_arrays_apart(got[0, :3], expected[0, :3])
        t.fail(f"{what} is wrong for a single point (first rays {shown}; expected {wanted}), where the same point "
               "among others is right.")


def focal_order_named(used, fs) -> tuple[str, str, str]:
    """(message, hint, mistake) for projections that each match some focal length's, but not in the
    order given: ``used[i]`` is the focal length projection i was made with (values: ``fs`` may
    repeat one). Only what the order shows is named: one focal length for all, the order reversed,
    sorted or another, or some focal lengths used for several projections and others for none."""
    used, fs = [float(f) for f in used], [float(f) for f in fs]
    found = f"project_focal_lengths: projection i is the one for f = {format_matrix(np.array(used))}"
    hint = "projection i belongs to focal_lengths[i]"
    if len(set(used)) == 1:
        # (a value given twice is named by its last place where that is the list's end: the last one given)
        at = len(fs) - 1 if fs[-1] == used[0] else fs.index(used[0])
        which = {0: "the first", len(fs) - 1: "the last"}.get(at, f"focal_lengths[{at}]")
        return (f"{found}: every projection is made with {which} focal length (f = {used[0]:g}).", hint,
                f"every projection uses {which} focal length")
    if sorted(used) == sorted(fs):
        order = "in reverse order" if used == fs[::-1] else "sorted" if used == sorted(fs) else "in another order"
        return f"{found}: the focal lengths are used {order}.", hint, f"the focal lengths are used {order}"
    return (f"{found}: some focal lengths are used for several projections and others for none.", hint,
            "a focal length is used for several projections")


SORTED_UNIQUE = measured("the focal lengths are sorted and their repeats dropped")
# Focal lengths as a caller gives them: not sorted, one of them twice; then a single one.
CALLER_FOCAL_LENGTHS = ((1000.0, 100.0, 500.0, 100.0), (250.0,))


@ex4.check("project_focal_lengths keeps the caller's focal lengths: in any order, with a repeat, or just one",
           points=1)
def focal_lengths_as_given(t):
    X = truth.points_in_front(46, n=7)
    for fs in CALLER_FOCAL_LENGTHS:
        what = f"project_focal_lengths(points, np.array({list(fs)}))"
        expected = np.stack([truth.pinhole(X, f) for f in fs])
        got = t.call("project_focal_lengths", X, np.array(fs))
        if isinstance(got, np.ndarray) and got.ndim == 3 and got.shape[1:] == expected.shape[1:] \
                and got.shape[0] != len(fs):
            used = focal_lengths_used(got, X, fs)
            kept = f": its projections are those of f = {format_matrix(np.array(used))}" if used else ""
            deduplicated = SORTED_UNIQUE if used == sorted(set(fs)) else ""
            t.fail(f"{what} returned {got.shape[0]} projections for {len(fs)} focal lengths{kept}"
                   + (f": {deduplicated}" if deduplicated else "")
                   + "; expected one per focal length given, in the order given (repeats included).",
                   mistake=deduplicated)
        expect_shape(t, what, got, expected.shape, axes=("F", "N", "2"))
        got = t.expect_array(got, what, shape=expected.shape, kind="iuf")
        used = focal_lengths_used(got, X, fs)
        if used is not None and used != list(fs):
            message, hint, mistake = focal_order_named(used, fs)
            t.fail(f"{what}: " + message.split(": ", 1)[1], hint=hint, mistake=mistake)
        for i, f in enumerate(fs):
            judge_points(t, f"{what}[{i}] (f = {f:g})", got[i], expected[i], truth.projection_mistakes(f, X),
                         probe=points_probe(t, "project_focal_lengths"))


def focal_lengths_used(got, X, fs) -> list | None:
    """The focal length (of ``fs``) each projection of ``got`` (F', N, 2) is made with, or None
    when one is made with none of them."""
    used = []
    for projection in np.asarray(got, np.float64):
        match = [f for f in dict.fromkeys(fs) if point_error(projection, truth.pinhole(X, f))
                 <= at_precision(1e-6 * magnitude(truth.pinhole(X, f)), magnitude(truth.pinhole(X, f)))]
        if not match:
            return None
        used.append(match[0])
    return used


APERTURE_F = 200.0


def _aperture_call(t: Trial, X, aperture, n_rays, seed, f=APERTURE_F):
    what = f"simulate_aperture(points, f={f:g}, aperture={aperture:g}, n_rays={n_rays}, seed={seed})"
    got = t.call("simulate_aperture", X, f, aperture, n_rays=n_rays, seed=seed)
    if isinstance(got, np.ndarray) and got.shape == (n_rays, len(X), 2) and n_rays != len(X):
        t.fail(f"{what} returned shape {got.shape}; expected (N, n_rays, 2) = ({len(X)}, {n_rays}, 2): "
               + measured("the axes are exchanged, (n_rays, N, 2): the rays are stacked along the first axis, where "
                          "row i must hold point i's rays."), mistake="the axes are in the wrong order")
    return t.expect_array(got, what, shape=(len(X), n_rays, 2), kind="f", finite=True), what


@ex4.check("simulate_aperture with aperture 0 is the ideal pinhole projection", points=2)
def aperture_zero(t):
    X = truth.points_in_front(42, n=6)
    got, what = _aperture_call(t, X, 0.0, 20, 0)
    ideal = truth.pinhole(X, APERTURE_F)
    error = np.abs(got - ideal[:, None, :]).max()
    tolerance = at_precision(1e-6, magnitude(ideal))
    if error > tolerance:
        mistake = judges.name_mistake(t, got.mean(axis=1), truth.projection_mistakes(APERTURE_F, X), point_error,
                                      1e-3, truth=ideal, probe=points_probe(t, "simulate_aperture").candidates_probe(1e-5))
        if mistake:
            t.fail(f"{what} is not the ideal projection: it looks like {mistake}.", mistake=mistake)
        t.fail(f"{what}: with a point-sized pinhole every ray should land on the ideal projection "
               f"f X / Z; yours are up to {format_apart(error, tolerance)} px away (at most "
               f"{tolerance:.2g} px accepted).")
    judge_single_point_rays(t, f"simulate_aperture((3,) point, f={APERTURE_F:g}, aperture=0, n_rays=20, seed=0)",
                            t.call("simulate_aperture", X[0], APERTURE_F, 0.0, n_rays=20, seed=0),
                            np.repeat(ideal[:1, None, :], 20, axis=1))
    # (every other check gives n_rays: its default is judged here)
    return judges.judge_default_is_the_apis(
        t, f"simulate_aperture(points, f={APERTURE_F:g}, aperture=0, seed=0)",
        lambda **kw: t.call("simulate_aperture", X, APERTURE_F, 0.0, seed=0, **kw), "n_rays", 100, "array of rays")


def _spread(got, ideal):
    d = np.linalg.norm(got - ideal[:, None, :], axis=-1)     # (N, n_rays)
    return d, np.sqrt((d ** 2).mean(axis=1))                 # distances, RMS per point


SPREAD_FOCAL = "the blur disc's scale (1 + f / Z) is made with another focal length than f"


@ex4.check("simulate_aperture: rays spread over the blur disc around the ideal projection", points=3)
def aperture_statistics(t):
    X = truth.points_in_front(43, n=6, z_range=(1.0, 8.0))
    aperture, n = 0.5, 4000
    got, what = _aperture_call(t, X, aperture, n, 7)
    ideal = truth.pinhole(X, APERTURE_F)
    radius = truth.blur_radius(X, APERTURE_F, aperture)           # a (1 + f / Z)
    t.svg("rays of point 0 (first 300) around its ideal projection", svg_points(
        {"ideal projection": ideal[:1], "rays": got[0, :300]}))
    d, rms = _spread(got, ideal)
    mean_error = np.linalg.norm(got.mean(axis=1) - ideal, axis=1) / radius
    if np.all(rms < at_precision(1e-9, magnitude(ideal))):
        t.fail(f"{what}: every ray lands on the ideal projection; the aperture is ignored.")
    sampled = aperture_sampling((got - ideal[:, None, :]) / radius[:, None, None])
    if sampled:
        t.fail(f"{what}: {sampled}.", mistake=sampled.split(":")[0].split(" (")[0])
    if np.any(mean_error > 0.1):
        t.fail(f"{what}: the rays of a point are not centred on its ideal projection f X / Z "
               f"(their mean is off by up to {mean_error.max():.2f} blur radii).")
    # A round pinhole spreads a point's rays alike in x and in y (half a blur radius RMS each; 0.41 where
    # the radius is drawn uniformly): rays along a line or a thin ellipse stay inside the disc with a
    # plausible overall RMS, and fill none of it.
    along = np.sqrt(np.mean((got - ideal[:, None, :]) ** 2, axis=1)) / radius[:, None]   # (N, 2): x, y
    lopsided = along.min(axis=1) / np.maximum(along.max(axis=1), 1e-300)
    if np.all(np.isfinite(along)) and np.any(lopsided < 0.6):
        point = int(np.argmin(lopsided))
        axis = int(np.argmin(along[point]))
        t.fail(f"{what}: the rays spread in one direction only: {along[point, axis]:.2f} blur radii RMS in "
               f"{'xy'[axis]} against {along[point, 1 - axis]:.2f} in {'yx'[axis]} (point {point}); a round "
               "pinhole spreads them alike in x and in y (0.5 radii RMS each, uniform over the disc).")
    ratio = d.max(axis=1) / radius
    per_point = rms / radius
    if np.all(np.abs(ratio - 2.0) < 0.1):
        # Twice the disc: the radius used is 2 * aperture (a diameter where the radius belongs),
        # when a larger aperture spreads twice its disc too.
        doubled = "the aperture is doubled (2 * aperture, a diameter, is used as the radius)"
        named = f": it looks like {doubled}; aperture is the pinhole's radius" \
            if _disc_ratio_on_probe(t, 0.8) is not None and abs(_disc_ratio_on_probe(t, 0.8) - 2.0) < 0.1 else ""
        t.fail(f"{what}: the rays spread over twice the expected disc (up to {ratio.max():.2f} radii from "
               f"the ideal projection){named}.", mistake=doubled if named else "")
    if np.ptp(rms / aperture) < 0.05 * np.mean(rms / aperture) and np.ptp(radius) > 0.2 * radius.mean():
        unscaled = _spread_independent_of_depth_on_probe(t)
        t.fail(f"{what}: the spread is the same for every point, but it should depend on depth: "
               + ("the offsets through the aperture are not scaled by (1 + f / Z): " if unscaled else "")
               + "the blur disc has radius aperture * (1 + f / Z) (near points blur more).",
               mistake="the aperture offsets are not scaled by (1 + f / Z)" if unscaled else "")
    if np.any(ratio > 1.02):
        t.fail(f"{what}: some rays land outside the blur disc of radius aperture * (1 + f / Z) "
               f"(up to {ratio.max():.2f} radii from the ideal projection).")
    if np.all(np.abs(ratio - 0.5) < 0.05):
        # At aperture 0.5, halving it and squaring it give the same disc: at aperture 0.8 they
        # do not (0.4 and 0.64, ratios 0.5 and 0.8), and the probe tells which it is.
        ratio_08 = _disc_ratio_on_probe(t, 0.8)
        cause = ("the aperture is halved (taken as a diameter)" if ratio_08 is not None and abs(ratio_08 - 0.5) < 0.05
                 else "the aperture is squared" if ratio_08 is not None and abs(ratio_08 - 0.8) < 0.05 else "")
        t.fail(f"{what}: the rays fill only the inner half of the blur disc (at most {ratio.max():.2f} "
               "radii from the ideal projection)" + (f": it looks like {cause}; it is the pinhole's radius"
                                                       if cause else "") + ".", mistake=cause)
    own = rms / np.maximum(d.max(axis=1), 1e-300)   # the spread against the disc the rays do fill
    if np.all((own > 0.6) & (own < 0.8)) and (np.all(ratio < 0.9) or np.all(ratio > 1.1)):
        # (a uniform disc of another size: its radius, measured per point, says which focal length made it)
        made_with = (d.max(axis=1) / aperture - 1.0) * X[:, 2]   # c of a radius aperture * (1 + c / Z)
        c = float(np.median(made_with))
        same = np.all(np.abs(made_with - c) <= 0.05 * max(abs(c), 1.0))
        c = round(c) if abs(c - round(c)) <= 0.02 * max(abs(c), 1.0) else float(f"{c:.3g}")   # (the farthest of
        # 4000 rays lands a thousandth short of the disc's edge)
        t.fail(f"{what}: the rays fill a disc {'smaller' if ratio.max() < 1 else 'larger'} than the blur disc, "
               f"evenly: their farthest lands {ratio.min():.2f}..{ratio.max():.2f} radii from the ideal projection"
               + (measured(f"; each disc's radius is aperture * (1 + c / Z) with c = {c:g} for every point, where "
                           f"c is the focal length f = {APERTURE_F:g}") if same else "") + ".",
               mistake=SPREAD_FOCAL if same else "")
    if np.any(per_point < 0.5) or np.any(per_point > 0.8):
        t.fail(f"{what}: the rays fill the blur disc unevenly (RMS distance {per_point.min():.2f}.."
               f"{per_point.max():.2f} radii; uniform over the disc gives 0.71).",
               hint=UNIFORM_DISC_HINT.said(t))
    return passed(f"mean on the ideal projection, RMS spread {per_point.mean():.2f} blur radii")


# Where f is large against Z (the check above: f = 200, Z of 1 to 8) the disc's radius a (1 + f / Z) is
# nearly a f / Z: an offset scaled by f / Z alone (the 1 dropped) spreads 96-99.5% as far and passes there.
# With f = 1 and Z of 1 to 8 it spreads 50-11% as far; the reference's largest ray lands 0.999-1.0 radii
# out on 4000 rays a point.
SMALL_F = 1.0
DROPPED_ONE = "the aperture offsets are scaled by f / Z, without the 1 of (1 + f / Z)"


@ex4.check("simulate_aperture with a short focal length: the blur disc's radius is aperture * (1 + f / Z), "
           "never less than the aperture", points=1)
def aperture_short_focal(t):
    X = truth.points_in_front(44, n=6, z_range=(1.0, 8.0))
    aperture, n = 0.3, 4000
    got, what = _aperture_call(t, X, aperture, n, 3, f=SMALL_F)
    ideal = truth.pinhole(X, SMALL_F)
    radius = truth.blur_radius(X, SMALL_F, aperture)
    d, _ = _spread(got, ideal)
    reach = d.max(axis=1) / radius
    if np.all((reach > 0.97) & (reach < 1.02)):
        return passed(f"the farthest rays land {reach.min():.3f}-{reach.max():.3f} radii from the ideal projection")
    fraction = (SMALL_F / X[:, 2]) / (1.0 + SMALL_F / X[:, 2])
    if np.all(np.abs(reach - fraction) < 0.03):
        t.fail(measured(f"{what}: the farthest rays of each point land {format_matrix(reach, 2)} radii out, which is "
                        f"(f / Z) / (1 + f / Z) for each point's Z: it looks like {DROPPED_ONE}; a ray through the "
                        "aperture point A lands A (1 + f / Z) from the ideal projection, at least A away."),
               mistake=DROPPED_ONE)
    t.fail(f"{what}: the farthest rays of each point land {format_matrix(reach, 2)} radii from the ideal projection; "
           "with the blur disc's radius aperture * (1 + f / Z) they reach 1.")


TWO_PI = (expr("2 * np.pi") | expr("np.pi * 2") | expr("_ * 2 * np.pi") | expr("2.0 * np.pi") | expr("2 * math.pi")
          | expr("2 * pi") | mentions("np.tau") | mentions("math.tau")).saying("computes 2 pi")
ANGLE_DRAWN = (calls("np.cos") & calls("np.sin")).saying("computes a cosine and a sine")
UNIFORM_DISC_HINT = Hint(
    "draw the aperture point uniformly over the disc: radius = aperture * sqrt(u)",
    asks=calls("np.sqrt") | expr("_ ** 0.5"),
    instead="your code already {found}: " + checklist(
        "", ("u is uniform in [0, 1)", calls(".random") | calls(".uniform") | calls(".rand")),
        # (code drawing no angle -- a normal vector made unit length, another recipe of a random direction -- is
        # asked of its directions, not of an angle it does not have)
        ("the angle is uniform in [0, 2 pi)", TWO_PI | ~ANGLE_DRAWN),
        ("each direction is of unit length (a vector divided by its own norm, axis=-1, keepdims=True)",
         ANGLE_DRAWN | keyword("np.linalg.norm", "axis")),
        ("the radius is aperture * sqrt(u)", expr("_ * np.sqrt(_)") | expr("np.sqrt(_) * _") | expr("_ * _ ** 0.5")
         | expr("_ ** 0.5 * _") | expr("_ * np.sqrt(_)[:, None]")),
        none_left=look_at(("how the angle and the radius become the two coordinates (r cos t, r sin t)",
                           (calls("np.cos") & calls("np.sin")).saying("computes a cosine and a sine")))))


def _ks_distance(samples, cdf) -> float:
    """Kolmogorov-Smirnov distance between ``samples``' empirical distribution and ``cdf``."""
    x = np.sort(np.ravel(samples))
    model = cdf(x)
    n = len(x)
    return float(max(np.max(np.arange(1, n + 1) / n - model), np.max(model - np.arange(n) / n)))


def aperture_sampling(offsets) -> str:
    """How the aperture points were drawn, when not uniformly over the disc, from the rays'
    offsets from the ideal projection in blur radii (``(N, n_rays, 2)``; a right answer fills
    the unit disc uniformly: P(r < s) = s^2); "" when no known shape fits. Thresholds leave
    thousands of rays far from every right answer (a KS distance of 0.02 at 4000 rays a point).
    A radius drawn uniformly (aperture * u, crowding the centre) is random points of the disc too,
    which the API asks for: the RMS judgement below accepts it, so it is not named a mistake here."""
    u = np.asarray(offsets, dtype=np.float64).reshape(-1, 2)
    r = np.hypot(u[:, 0], u[:, 1])
    if len(r) < 1000 or not np.isfinite(r).all() or r.max() == 0 or np.any(u.std(axis=0) == 0):
        return ""   # a coordinate that never moves has no distribution to tell (the other checks say so)
    if np.mean(np.abs(r - 1) < 0.02) > 0.99:
        return measured("every ray lands on the rim of the blur disc: the aperture point's radius is always the "
                        "aperture's, never drawn (uniform over the disc: radius aperture * sqrt(u))")
    if abs(np.corrcoef(u[:, 0], u[:, 1])[0, 1]) > 0.99:
        # (x = y, or x = -y: one number for both coordinates -- cos used twice, one draw for x and y; a line at
        # another angle: one direction for every ray -- an angle drawn once, not one per ray: audit of 2026-12-06)
        diagonal = np.median(np.abs(np.abs(u[:, 0]) - np.abs(u[:, 1])) / np.maximum(r, 1e-300)) < 1e-6
        return measured("the rays lie on one line through the ideal projection: " + (
            "both coordinates of the aperture point are made from the same random numbers (x = +-y)" if diagonal else
            "every ray's aperture point lies in the same direction, one angle for all the rays (an angle drawn once, "
            "not one per ray)"))
    for axis, name in ((0, "x"), (1, "y")):   # a half disc's mean is 4 / (3 pi) radii off its centre
        side = np.mean(u[:, axis] > 0)
        if (side < 0.005 or side > 0.995) and r.max() <= 1.02 and abs(abs(u[:, axis].mean()) - 4 / (3 * np.pi)) < 0.03:
            return f"the rays fill only half of the blur disc (one side in {name}): the angle covers half a turn"
    angles = np.arctan2(u[:, 1], u[:, 0])[r > 1e-9]
    directions = np.unique(np.round(np.mod(angles, 2 * np.pi), 6))
    if len(angles) >= 1000 and len(directions) <= 72:
        # (uniform angles give every ray its own direction: a few dozen at most is a drawing of a few values)
        whole = np.all(np.abs(directions - np.round(directions)) < 1e-6)
        return (f"the rays leave the ideal projection along a few directions only ({len(directions)}): the aperture "
                "point's angle takes a few values" + (" (whole numbers of radians: rng.integers draws integers)" if whole else "")
                + ", where it is uniform over a whole turn (rng.uniform(0, 2 pi))")
    uniform_square = _ks_distance(u, lambda x: np.clip((x + 1) / 2, 0, 1))
    if uniform_square < 0.02 and 0.15 < np.mean(r > 1.02) < 0.28:
        return (f"the aperture points fill the square [-aperture, aperture]^2, not the disc of radius aperture: "
                f"rays reach its corners, up to {r.max():.2f} blur radii away")
    spread = u.std()
    kurtosis = np.mean((u - u.mean(axis=0)) ** 4, axis=0) / np.var(u, axis=0) ** 2
    if r.max() > 1.3 and np.all(np.abs(kurtosis - 3) < 0.3):
        return (f"the aperture points follow a normal distribution (standard deviation {spread:.2f} blur radii, "
                f"no edge: rays up to {r.max():.1f} radii away), not a uniform disc of radius aperture")
    return ""


def _aperture_probe(t: Trial, f: float, aperture: float):
    """The student's rays on the aperture probe's points (depths 1 to 8), with the ideal projection."""
    X = truth.points_in_front(9093, n=6, z_range=(1.0, 8.0))

    def answer():
        got = t.call("simulate_aperture", X, f, aperture, n_rays=2000, seed=5)
        ok = isinstance(got, np.ndarray) and got.shape == (len(X), 2000, 2) and got.dtype.kind == "f"
        return got if ok and np.isfinite(got).all() else None

    return t.probe(f"simulate_aperture/probe/{f}/{aperture}", answer), X


def _disc_ratio_on_probe(t: Trial, aperture: float):
    """How far the rays reach on the probe, in blur radii (f = 200): None if it cannot be said."""
    got, X = _aperture_probe(t, APERTURE_F, aperture)
    if got is None:
        return None
    d, _ = _spread(got, truth.pinhole(X, APERTURE_F))
    ratio = d.max(axis=1) / truth.blur_radius(X, APERTURE_F, aperture)
    return float(np.median(ratio))


def _spread_independent_of_depth_on_probe(t: Trial) -> bool:
    """Whether with f = 2 (where 1 + f / Z and 1 + Z / f both vary a lot over depths 1 to 8) the
    spread is the same for every point again: the offsets are scaled by no depth at all."""
    got, X = _aperture_probe(t, 2.0, 0.5)
    if got is None:
        return False
    _, rms = _spread(got, truth.pinhole(X, 2.0))
    return bool(np.ptp(rms) < 0.05 * np.mean(rms))


@ex4.check("simulate_aperture: the spread grows with the aperture", points=2)
def aperture_growth(t):
    X = truth.points_in_front(44, n=5)
    ideal = truth.pinhole(X, APERTURE_F)
    spreads = []
    for aperture in (0.05, 0.2, 0.8):
        got, what = _aperture_call(t, X, aperture, 1000, 3)
        spreads.append(_spread(got, ideal)[1].mean())
    spreads = np.array(spreads)
    if not np.all(np.diff(spreads) > 0):
        t.fail(f"the spread of the rays for apertures 0.05, 0.2, 0.8 is {format_matrix(spreads)} px: "
               "it should grow with the aperture.")
    ratios = spreads[1:] / spreads[:-1]
    if np.any(np.abs(ratios / 4.0 - 1) > 0.15):
        t.fail(f"the spread for apertures 0.05, 0.2, 0.8 is {format_matrix(spreads)} px: each aperture is 4x "
               "the previous, so the spread should be about 4x too (it is proportional to the aperture).")
    return passed(f"spread {format_matrix(spreads)} px for apertures 0.05, 0.2, 0.8")


GENERATORS = ("default_rng", "Generator", "SeedSequence", "PCG64", "RandomState")


def _seeds_the_generator(function) -> bool:
    """A ``np.random.default_rng`` given a value that is no constant (the seed passed in, not 0)."""
    return any(isinstance(node, ast.Call) and _resolved(node.func, _scope(function))[1] == "numpy.random.default_rng"
               and any(not isinstance(value, ast.Constant) for value in [*node.args, *(k.value for k in node.keywords)])
               for node in walk(function))


def _draws_from_np_random(function) -> bool:
    """A call of one of ``np.random``'s own functions (``np.random.normal``), not a generator's method."""
    for node in walk(function):
        if isinstance(node, ast.Call):
            kind, path = _resolved(node.func, _scope(function))
            if kind == "module" and path.startswith("numpy.random.") and path.rsplit(".", 1)[-1] not in GENERATORS:
                return True
    return False


SEED_HINT = Hint(
    "use rng = np.random.default_rng(seed) and draw every random number from rng.",
    asks=calls("np.random.default_rng"),
    instead="your code calls np.random.default_rng: " + checklist(
        "", ("it is given seed", Predicate("gives the generator the seed", _seeds_the_generator)),
        ("every random number is drawn from that generator (none from np.random's own functions)",
         ~Predicate("calls np.random's own functions", _draws_from_np_random)),
        # (what it is given is the first item; a generator made in the function read is made once per call)
        none_left="") + ".")


@ex4.check("simulate_aperture is reproducible with a seed, and draws without one", points=1)
def aperture_seed(t):
    X = truth.points_in_front(45, n=4)
    a, what = _aperture_call(t, X, 0.3, 50, 123)
    b, _ = _aperture_call(t, X, 0.3, 50, 123)
    c, _ = _aperture_call(t, X, 0.3, 50, 124)
    if not np.array_equal(a, b):
        t.fail(f"{what} gave different rays for the same seed: the seed is ignored; " + SEED_HINT.said(t),
               mistake="the seed is ignored")
    if np.array_equal(a, c):
        t.fail("simulate_aperture gave the same rays for seeds 123 and 124: the seed is ignored.",
               mistake="the seed is ignored")
    # (0 is a seed like any other: a test of the seed's truth, `if seed:`, takes it for no seed)
    zero, what = _aperture_call(t, X, 0.3, 50, 0)
    again, _ = _aperture_call(t, X, 0.3, 50, 0)
    if not np.array_equal(zero, again):
        t.fail(f"{what} gave different rays on a second call with the same seed 0: " + measured(
               "seed=0 is taken for no seed (0 is a seed like any other; `if seed is None` tells no seed apart, "
               "`if seed` does not)"), mistake="seed=0 taken for no seed")
    # (and with no seed, the API's default: fresh rays, in the same blur discs -- a generator made only where a
    # seed is given leaves the default with none; the blind set 1205g's 09/03)
    what = "simulate_aperture(points, f=200, aperture=0.3, n_rays=50) with the default seed=None"
    unseeded = t.expect_array(t.call("simulate_aperture", X, APERTURE_F, 0.3, n_rays=50), what,
                              shape=(len(X), 50, 2), kind="f", finite=True)
    apart = np.hypot(*np.moveaxis(unseeded - truth.pinhole(X, APERTURE_F)[:, None, :], -1, 0))
    radius = truth.blur_radius(X, APERTURE_F, 0.3)[:, None]
    if (apart > 1.02 * radius + 1e-9).any():
        # (said of the seeded rays only where they were measured to stay in: rays outside with any seed are the
        # blur-disc checks' to judge, and no difference of the default's)
        seeded = np.hypot(*np.moveaxis(a - truth.pinhole(X, APERTURE_F)[:, None, :], -1, 0)) \
            if isinstance(a, np.ndarray) and a.shape == unseeded.shape else None
        kept = seeded is not None and not (seeded > 1.02 * radius + 1e-9).any()
        t.fail(f"{what}: some rays fall outside their point's blur disc"
               + (", where the same call with a seed keeps them in" if kept else ""))


# The API asks for "random points of a circular pinhole", not points uniform over its area: a
# radius drawn uniformly (aperture * u) is accepted by the graded checks (its RMS spread, 0.58
# radii, is within their 0.5..0.8), and told here. Measured on the rays: their distances from the
# ideal projection, in blur radii, are uniform on [0, 1] (P(r < s) = s) where a disc filled
# uniformly gives P(r < s) = s^2 (KS distance 0.25 from uniform; 0.02 leaves thousands of rays' margin).
CROWDED_CENTRE = measured("the rays crowd the centre of the blur disc: the radius is drawn uniformly "
                          "(aperture * u); points uniform over the disc's area take radius aperture * sqrt(u)")
SQRT_RADIUS_HINT = Hint("radius = aperture * np.sqrt(rng.random(n_rays)), angle = 2 pi * rng.random(n_rays)",
                        asks=calls("np.sqrt") | expr("_ ** 0.5"),
                        instead="your code already {found}: check that the square root is of the uniform "
                                "number u, before it is multiplied by the aperture")


@ex4.advice("simulate_aperture fills the pinhole uniformly over its area")
def aperture_uniform_area(t):
    X = truth.points_in_front(43, n=6, z_range=(1.0, 8.0))
    aperture, n = 0.5, 4000
    got = t.call("simulate_aperture", X, APERTURE_F, aperture, n_rays=n, seed=7)
    if not (isinstance(got, np.ndarray) and got.shape == (len(X), n, 2) and got.dtype.kind == "f"
            and np.isfinite(got).all()):
        return   # the graded checks say what is wrong with the form
    offsets = (got - truth.pinhole(X, APERTURE_F)[:, None, :]) / truth.blur_radius(X, APERTURE_F, aperture)[:, None, None]
    r = np.hypot(offsets[..., 0], offsets[..., 1]).ravel()
    if aperture_sampling(offsets) or not 0.95 < r.max() <= 1.02:
        return   # another shape, judged (and named) by the graded checks
    what = f"simulate_aperture(points, f={APERTURE_F:g}, aperture={aperture:g}, n_rays={n}, seed=7)"
    if _ks_distance(r, lambda s: np.clip(s, 0.0, 1.0)) < 0.02:
        t.advise(f"{what}: {CROWDED_CENTRE} (half the rays lie within {np.median(r):.2f} blur radii of the ideal "
                 "projection; uniform over the area puts half within 0.71). No points depend on it.",
                 hint=SQRT_RADIUS_HINT.said(t))
    elif abs(np.mean(r < 0.5) - 0.25) > 0.03:
        # (another shape inside the disc -- a radius drawn apart for x and for y --: the share within half the
        # radius is a quarter for points uniform over the area, within 0.003 on these 24000 rays)
        # (the recipe is told only to code that takes no square root: code that does may draw its radius right
        # and scale it by a blur radius of another size -- the distance |X| where the depth Z belongs)
        rooted = SQRT_RADIUS_HINT.asks.found(code_of(t).reachable(["simulate_aperture"]))
        farthest = np.max(np.hypot(offsets[..., 0], offsets[..., 1]), axis=1)   # per point, in blur radii
        if not rooted:
            after = measured(": one radius and one angle per ray, radius aperture * sqrt(u), fill it evenly.")
        elif np.abs(farthest - 1).max() > 0.01:
            after = measured(", and the farthest of each point's rays do not all reach its blur radius "
                             "aperture * (1 + f / Z).")
        else:
            after = "."
        t.advise(f"{what}: " + measured(
            f"{np.mean(r < 0.5):.1%} of the rays land within half the blur radius of the ideal projection, where "
            "points uniform over the pinhole's area put a quarter there (the inner disc's share of the area)")
            + after + " No points depend on it.")


# ================================================================== ex5 points on a real image
ex5 = lab.exercise("ex5", "Points on a real image", functions=[
    "draw_points(image, pts, radius=3, color=(0, 0, 255))", "project_onto_image(image, P, points)"])


DISCS_SMALLER = "the circles are drawn smaller than the radius asked"
DISC_AREA_SHARE = 0.7   # of the pixels cv2.circle changes: own discs (x^2 + y^2 <= r^2) and LINE_AA change as many
#                         or more; a radius one smaller, 3 -> 2, changes 45% as many


def _discs_smaller(got, image, expected, far, radius) -> str:
    """A measured sentence where the discs drawn change far fewer pixels than cv2.circle's of ``radius`` (within
    ``radius + 2`` of the points), else ""."""
    def changed(drawing):
        return (np.any(drawing != image, axis=-1) if drawing.ndim == 3 else drawing != image)[~far].sum()
    theirs, wanted = int(changed(got)), int(changed(expected))
    if wanted == 0 or theirs >= DISC_AREA_SHARE * wanted:
        return ""
    return measured(f"the circles cover {theirs} pixels in all, where filled circles of radius {radius} cover "
                    f"{wanted}: they are drawn smaller than the radius asked (cv2.circle's radius is the disc's own, "
                    "in pixels)")


DRAWN_AT_YX = measured("the circles are drawn at (y, x): cv2.circle takes the centre as (x, y) = (column, row).")
XY_SWAPPED = "x and y (column and row) are swapped"


def judge_drawing(t: Trial, what: str, got, image, pts, radius=3, color=(0, 0, 255), show=True, redraw=None):
    """Judge ``got``, ``image`` with filled circles of ``radius`` and ``color`` drawn at ``pts``;
    ``redraw(r)``, the same drawing asked with radius r, tells how a wrong radius comes about."""
    expected = truth.expected_drawing(image, pts, radius, color)
    if isinstance(got, np.ndarray) and show:
        t.compare_images(what, image, expected, got)
    got = t.expect_array(got, what, shape=image.shape, dtype=np.uint8)
    core, far = truth.circle_regions(image.shape, pts, radius)
    painted = np.all(got == np.asarray(color, np.uint8), axis=-1) if got.ndim == 3 else got == color[0]
    changed = np.any(got != image, axis=-1) if got.ndim == 3 else got != image
    untouched = 1.0 - changed[far].mean()
    coverage = painted[core].mean() if core.any() else 1.0
    if coverage >= 0.97 and untouched >= 0.999:
        smaller = _discs_smaller(got, image, expected, far, radius)
        if smaller:
            t.fail(f"{what}: {smaller}", mistake=DISCS_SMALLER)
        return passed(f"every circle drawn, {coverage:.0%} of the disc pixels in the colour {tuple(color)}")
    blank = blank_canvas(got, image, far)
    if blank:
        t.fail(f"{what}: {blank}.", hint=BLANK_CANVAS_HINT.said(t, ["draw_points"]), mistake=BLANK_CANVAS)
    if got.ndim == 3 and channels_reversed(got, image):
        # (the picture drawn on a copy converted for display: every pixel away from the circles reversed)
        t.fail(f"{what}: away from the circles, the image is the input with its colour channels reversed (RGB for BGR): "
               f"OpenCV images are BGR; {RGB_ONLY_TO_SHOW}.",
               mistake="the colour channels are reversed (RGB for BGR)")
    pts = np.asarray(pts, float).reshape(-1, 2)
    height, width = image.shape[:2]
    for moved, said, mistake in (
            (pts[:, ::-1], DRAWN_AT_YX, XY_SWAPPED),
            (np.column_stack([pts[:, 0], height - 1 - pts[:, 1]]),
             measured("the circles are drawn upside down, at (x, h - 1 - y): y counted up from the bottom row as in a "
                      "plot; in an image y is the row, counted down from the top."),
             "the points are drawn upside down (y from the bottom)"),
            (np.column_stack([width - 1 - pts[:, 0], pts[:, 1]]),
             measured("the circles are drawn mirrored, at (w - 1 - x, y): x is the column, counted from the left "
                      "border."), "the points are drawn mirrored left to right")):
        moved_core, _ = truth.circle_regions(image.shape, moved, radius)
        if moved_core.any() and painted[moved_core].mean() > 0.9 and not (painted[core].mean() > 0.9):
            t.fail(f"{what}: {said}", mistake=mistake)
    if got.ndim == 3 and core.any():
        # (a colour the call left to a default of their own is that default, neither reversed nor ignored:
        # the default is named after the check, from their def)
        own_default = defaults_given.left_to_its_own(t, "color")
        reversed_colour = np.all(got == np.asarray(color[::-1], np.uint8), axis=-1)
        if tuple(color[::-1]) != tuple(color) and reversed_colour[core].mean() > 0.9 and not own_default:
            t.fail(f"{what}: the circles have colour {tuple(color[::-1])}, not {tuple(color)}: the colour is "
                   "reversed (RGB for BGR); OpenCV images are BGR, so pass the colour as given.",
                   mistake="the colour is reversed (RGB vs BGR)")
        default_colour = np.all(got == np.array([0, 0, 255], np.uint8), axis=-1)
        if tuple(color) != (0, 0, 255) and default_colour[core].mean() > 0.9 and not own_default:
            t.fail(f"{what}: the circles are red (0, 0, 255), not {tuple(color)}: the color argument is "
                   "ignored.", mistake="color is ignored")
        drawn = got[core].reshape(-1, got.shape[-1])
        colours, counts = np.unique(drawn, axis=0, return_counts=True)
        if counts.max() > 0.9 * len(drawn) and not np.all(painted[core]):
            other = tuple(int(v) for v in colours[counts.argmax()])
            t.fail(measured(f"{what}: the circles are drawn, in the colour {other}, not {tuple(color)}."))
    # outlines: the centres empty, and what is painted near the points lies on rings around the
    # whole-pixel centres cv2.circle draws at (a ring through sub-pixel centres is half painted)
    d = truth.distance_map(image.shape, np.round(pts))
    # (and an unpainted centre keeps the image's pixel: another drawing over the circles -- a polyline through
    # their centres -- is not an outline)
    inner, near = d <= radius - 1.5, painted & (d <= radius + 1)
    if inner.any() and painted[inner].mean() < 0.5 and near.any() and (d[near] >= radius - 1).mean() > 0.9 \
            and not changed[inner & ~painted].mean() > 0.5:
        # (thickness=-1 is cv2.circle's: code drawing otherwise -- cv2.drawMarker, which refuses it -- is
        # told what to draw, not that argument)
        circles = calls("cv2.circle").holds(code_of(t).reachable(["draw_points"])) or not code_of(t).functions
        t.fail(f"{what}: the circles are outlines; they should be filled (thickness=-1)." if circles else
               f"{what}: " + from_code("the points are drawn as outlines, not filled discs: your code does not call "
                                       "cv2.circle, which draws a filled disc with thickness=-1."),
               mistake="the circles are outlines, not filled")
    # thick rings: the centres empty, a band around them painted past the radius (a thickness given the radius)
    centres, band = d <= 0.5, (d >= radius - 1) & (d <= radius)
    if radius >= 2 and centres.any() and painted[centres].mean() < 0.2 and band.any() and painted[band].mean() > 0.8 \
            and not changed[centres & ~painted].mean() > 0.5:
        beyond = (d > radius + 0.5) & (d <= radius + 2)
        outside = f", and {painted[beyond].mean():.0%} of those up to 2 px beyond it" if beyond.any() else ""
        t.fail(f"{what}: " + measured(f"the circles are rings: no centre pixel is painted, {painted[band].mean():.0%} "
                                      f"of the pixels at the radius are{outside}; "
                                      "a filled disc is drawn with thickness=-1 (cv2.FILLED), a positive thickness "
                                      "draws a ring that wide around the circle."),
               mistake="the circles are outlines, not filled")
    wrapped = _wrapped_at_256(got, image, pts, radius, color)
    if wrapped:
        t.fail(f"{what}: {wrapped}.", mistake=wrapped.split(":")[0])
    missing = _points_not_drawn(painted, image.shape, pts, radius)
    if missing and not _points_not_drawn(changed, image.shape, pts, radius):
        # (every point has its disc drawn, some in other colours than asked: a colour of the student's own choosing)
        t.fail(measured(f"{what}: the circles at point(s) {missing} (of {len(pts)}) are drawn, but not in the "
                        f"colour {tuple(int(v) for v in color)}: every circle takes the colour given (draw_points' "
                        "default, red (0, 0, 255))."), mistake="circles drawn in other colours than the one given")
    if missing:
        only = sorted(set(range(len(pts))) - set(missing) - set(_off_image(image.shape, pts)))
        # (why, only where the code shows it: a return in the loop's body ends it after the first point)
        returned = _return_in_a_loop(code_of(t).reachable([what.split("(", 1)[0]])) if only == [0] else None
        first = "" if only != [0] else " (only the first point is drawn" + (
            from_code(f": your code returns inside the loop (line {returned}), which ends it after one point)")
            if returned else ")")
        h, w = image.shape[:2]
        border = "" if first or not all(x in (0, w - 1) or y in (0, h - 1) for x, y in np.round(pts[missing])) \
            else (f" (on the image's border: x = 0 and {w - 1}, y = 0 and {h - 1} are pixels of the image, "
                  f"0 <= x < {w}" + measured(": check the bounds)"))
        t.fail(f"{what}: no circle at point(s) {missing} (of {len(pts)}){first}{border}.",
               mistake="only the first point is drawn" if first else "some points are not drawn")
    drawn_radius = _drawn_radius(got, image, pts, color)
    if drawn_radius is not None and drawn_radius != radius:
        misused = _radius_misused(drawn_radius, radius, redraw)
        t.fail(f"{what}: the circles have radius {drawn_radius}, not {radius}: {misused}.", mistake=misused)
    # (something else drawn, far from the points and over the circles: the drawing the code adds is the cause)
    read = code_of(t).reachable([what.split("(", 1)[0]])
    others = _other_drawings(read) if untouched < 0.999 else ""
    if others:
        t.fail(f"{what}: {1 - untouched:.1%} of the pixels far from every point were changed: "
               + from_code(f"your code also draws with {others}; only the filled circles should be drawn."),
               mistake=from_code("more drawn than the circles"))
    if coverage < 0.97:
        t.fail(f"{what}: only {coverage:.0%} of the pixels that should be covered by the circles "
               f"(radius {radius}, colour {tuple(color)}) are.")
    larger = painted & far
    if larger.any() and larger.sum() >= 0.9 * changed[far].sum() and d[larger].max() <= radius + 30:
        t.fail(f"{what}: " + measured(f"the circles are larger than radius {radius}: the colour {tuple(color)} "
                                      f"reaches {int(np.ceil(d[larger].max()))} px from the centres (a positive "
                                      "thickness widens a circle by half of it on each side; filled is "
                                      "thickness=-1)."))
    if clipped_into_view(image.shape, pts, changed & far, radius):
        t.fail(f"{what}: {1 - untouched:.1%} of the pixels far from every point were changed: " + measured(
            "they are circles at the image's border where points off the image are moved to the nearest border "
            "pixel (clipped into it). A point off the image draws only the part of its circle inside the image "
            "(cv2.circle clips it), nothing when it is farther than the radius: draw it where it is."),
            mistake=CLIPPED_INTO_VIEW)
    copied = COPIES.found(read)   # (the copy is not asked of code that copies)
    t.fail(f"{what}: {1 - untouched:.1%} of the pixels far from every point were changed; "
           + ("only the circles should be drawn." if copied else
              "only the circles should be drawn (on a copy of the image)."))


_DRAWINGS = ("line", "polylines", "rectangle", "putText", "drawMarker", "arrowedLine", "ellipse", "fillPoly",
             "fillConvexPoly", "drawContours")


def _other_drawings(functions) -> str:
    """The OpenCV drawing calls other than cv2.circle in the functions read, as `cv2.polylines` (line 12);
    "" when there are none."""
    found = {}
    for function in functions:
        for node in walk(function):
            if isinstance(node, ast.Call) and _hints_path(node.func).startswith(("cv2.", "cv.")) \
                    and _hints_path(node.func).rsplit(".", 1)[-1] in _DRAWINGS:
                found.setdefault(_hints_path(node.func), node.lineno)
    return " and ".join(f"`{name}` (line {line})" for name, line in found.items())


def _return_in_a_loop(functions) -> int | None:
    """The line of a ``return`` in the body of a ``for`` or ``while`` loop (not in a function nested there)."""
    for function in functions:
        for loop in walk(function):
            if isinstance(loop, (ast.For, ast.While)):
                for node in (n for statement in loop.body for n in walk(statement)):
                    if isinstance(node, ast.Return):
                        return node.lineno
    return None


def _wrapped_at_256(got, image, pts, radius, color) -> str:
    """A sentence when the drawing is the right one for the centres taken modulo 256 (and not for
    the centres themselves): the circles of points with x or y of 256 or more (or below 0) are
    drawn where that coordinate, wrapped around at 256, puts them; "" otherwise."""
    centres = np.round(np.asarray(pts, np.float64).reshape(-1, 2))
    finite = np.isfinite(centres).all(axis=1)
    beyond = finite & ((centres >= 256) | (centres < 0)).any(axis=1)
    if not beyond.any() or got.shape != image.shape:
        return ""
    wrapped = centres.copy()
    wrapped[finite] = np.mod(centres[finite], 256)

    def apart(expected):
        return float(np.mean(np.any(got != expected, axis=-1) if got.ndim == 3 else got != expected))

    if apart(truth.expected_drawing(image, wrapped, radius, color)) > 2e-4:
        return ""
    shown = ", ".join(f"({x:g}, {y:g}) at ({u:g}, {v:g})" for (x, y), (u, v) in zip(centres[beyond][:3], wrapped[beyond][:3]))
    return measured(f"the circles are wrong for coordinates of 256 and more (or below 0): they are drawn with "
                    f"the coordinate taken modulo 256 ({shown}: all an 8-bit integer keeps of it); pass cv2.circle "
                    "the centre as Python integers (int(round(x)), int(round(y)))")


CLIPPED_INTO_VIEW = "points off the image drawn at its border (clipped into it)"


def clipped_into_view(shape, pts, stray, radius) -> bool:
    """Whether the ``stray`` pixels (changed where no circle belongs) are nearly all within the radius of
    where the finite points off the image land when clipped to its border."""
    h, w = shape[:2]
    pts = np.asarray(pts, np.float64).reshape(-1, 2)
    off = [i for i in _off_image(shape, pts) if np.isfinite(pts[i]).all()]
    if not off or stray.sum() < 5:
        return False
    clipped = np.clip(pts[off], 0, [w - 1, h - 1])
    ys, xs = np.nonzero(stray)
    near = np.hypot(xs[:, None] - clipped[:, 0], ys[:, None] - clipped[:, 1]).min(axis=1) <= radius + 1.5
    return bool(near.mean() >= 0.9)


def _off_image(shape, pts):
    h, w = shape[:2]
    return [i for i, (x, y) in enumerate(pts) if not (0 <= x < w and 0 <= y < h)]


def _points_not_drawn(painted, shape, pts, radius):
    """Indices of the points on the image with no painted pixel within their disc."""
    off = set(_off_image(shape, pts))
    missing = []
    for i, (x, y) in enumerate(pts):
        if i in off or not (np.isfinite(x) and np.isfinite(y)):
            continue
        disc = truth.distance_map(shape, np.array([[x, y]])) <= radius + 1.0     # anything drawn there
        if disc.any() and not painted[disc].any():
            missing.append(i)
    return missing


RADIUS_IGNORED = "the radius argument is ignored"
RADIUS_HALVED = "the radius is halved (it is the radius, not the diameter)"
RADIUS_DOUBLED = "the radius is doubled (it is the radius, not the diameter)"
RADIUS_MISUSED = "the radius is used wrongly"


def _radius_misused(drawn: int, radius: int, redraw=None) -> str:
    """How a circle of radius ``drawn`` comes from the ``radius`` asked: doubled, halved, ignored (the
    default, 3). Where two fit (3 for 6 is halved and the default), the drawing asked with another
    radius (``redraw``: the radius drawn for a radius asked, None when it tells nothing) decides."""
    fits = [mistake for mistake, holds in (
        (RADIUS_DOUBLED, drawn == 2 * radius), (RADIUS_HALVED, 2 * drawn in (radius - 1, radius, radius + 1)),
        (RADIUS_IGNORED, drawn == 3)) if holds]
    if len(fits) > 1 and redraw is not None:
        other = 2 * radius + 4
        again = redraw(other)
        fits = [] if again is None else [mistake for mistake in fits if _radius_misused(again, other) == mistake]
    return fits[0] if len(fits) == 1 else RADIUS_MISUSED


def _drawn_radius(got, image, pts, color):
    """The radius r in 1..12 whose filled circles (in ``color``) give exactly ``got``, if one does."""
    differences = []
    for r in range(1, 13):
        expected = truth.expected_drawing(image, pts, r, color)
        if got.shape != expected.shape:
            return None
        differences.append(np.mean(np.any(got != expected, axis=-1) if got.ndim == 3 else got != expected))
    best = int(np.argmin(differences))
    others = [d for i, d in enumerate(differences) if i != best]
    # near-exact (rounding of the centre), and clearly better than every other radius
    return best + 1 if differences[best] < 2e-4 and differences[best] * 3 < min(others) else None


@ex5.check("draw_points draws filled circles at the points, anywhere on a 400x300 image, grey or colour",
           points=2)
def draw_example(t):
    image = photo("astronaut", (400, 300))
    # x and y past 255 too: pixel coordinates of an ordinary photo do not fit in 8 bits
    pts = np.array([[20.3, 30.7], [300.0, 75.0], [380.6, 20.2], [50.5, 280.4], [270.2, 260.9], [150.2, 130.9]])
    verdict = judge_drawing(t, "draw_points(400x300 image, pts)", t.call("draw_points", image, pts), image, pts)
    grey = photo("astronaut", (400, 300), grey=True)
    drawn = t.call("draw_points", grey, pts)
    if isinstance(drawn, np.ndarray) and drawn.shape != grey.shape:
        t.fail(f"draw_points(grey 400x300 image, pts) returned shape {drawn.shape}; expected {grey.shape}: a grey "
               "image comes back grey (a function returns the channel count it is given; cv2.circle draws on a "
               "grey image with the colour's first value)")
    t.expect_array(drawn, "draw_points(grey 400x300 image, pts)", shape=grey.shape, dtype=np.uint8)
    return verdict


DRAWING = ("circle", "line", "rectangle", "drawMarker", "putText", "ellipse", "polylines", "fillPoly")
COPIES = (expr("_.copy()") | expr("np.copy(_)") | expr("np.array(_)")).saying("copies the image")


def _first_parameter(function) -> str:
    arguments = function.args.posonlyargs + function.args.args
    return arguments[0].arg if arguments else ""


def _draws_on_the_callers_image(function) -> bool:
    """A drawing call (``cv2.circle(image, ...)``) or an assignment into the function's first parameter, never
    rebound to a copy (``image = image.copy()`` draws on the copy after)."""
    image = _first_parameter(function)
    if not image or any(isinstance(n, ast.Assign) and any(isinstance(t, ast.Name) and t.id == image for t in n.targets)
                        for n in walk(function)):
        return False
    for node in walk(function):
        if isinstance(node, ast.Call) and _hints_path(node.func).rsplit(".", 1)[-1] in DRAWING and node.args \
                and isinstance(node.args[0], ast.Name) and node.args[0].id == image:
            return True
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Subscript) and isinstance(t.value, ast.Name)
                                                and t.value.id == image for t in node.targets):
            return True
    return False


def _returns_a_copy(function) -> bool:
    """A ``return`` of a name assigned a copy (``out = image.copy()``), or of the copy itself."""
    copies = {t.id for n in walk(function) if isinstance(n, ast.Assign) and COPIES.holds([n.value])
              for t in n.targets if isinstance(t, ast.Name)}
    return any(isinstance(n, ast.Return) and n.value is not None
               and ((isinstance(n.value, ast.Name) and n.value.id in copies) or COPIES.holds([n.value]))
               for n in walk(function))


COPY_HINT = Hint(
    "out = image.copy(), then draw on out", asks=calls(".copy") | calls("np.copy"),
    instead="your code copies the image ({found}): " + checklist(
        "", ("each point is drawn on the copy, not on `image`",
             ~Predicate("draws on the caller's image", _draws_on_the_callers_image)),
        ("the copy is returned", Predicate("returns the copy", _returns_a_copy)),
        # (the arrays drawn on are the first item's reading, helpers included: nothing is left to point at)
        none_left=""))


@ex5.check("draw_points twice on the same image: each drawing shows its own points only", points=1)
def draw_twice(t):
    image = photo("astronaut", (200, 150))
    first_pts = np.array([[30.0, 40.0], [160.0, 110.0]])
    second_pts = np.array([[100.0, 30.0], [60.0, 120.0]])
    what = "draw_points(image, pts) called a second time on the same image"
    t.call("draw_points", image, first_pts)
    (held, _), _ = t.held(image, first_pts)
    got = t.call("draw_points", held, second_pts)
    both = truth.expected_drawing(truth.expected_drawing(image, first_pts), second_pts)
    if not np.array_equal(held, image) and isinstance(got, np.ndarray) and got.shape == image.shape \
            and np.mean(np.any(got != both, axis=-1)) < 0.002:
        t.images(what, first_points_then_second=got)
        t.fail(f"{what}: the second drawing shows the first one's points too: draw_points draws on the caller's "
               "`image` (the array given) instead of on a copy, so whoever calls it twice, or uses the image "
               "afterwards, finds points drawn on it.", hint=COPY_HINT.said(t),
               mistake="draw_points draws on the caller's image")
    return judge_drawing(t, what, got, image, second_pts)


@ex5.check("project_onto_image twice on the same image: each drawing shows its own points only", points=1)
def project_onto_twice(t):
    """The caller's image as the first call left it, drawn on again, against the student's own drawing of the
    same points on a fresh copy: no truth, no drawing convention enters."""
    image, P, X = _photo_scene()
    what = "project_onto_image(image, P, points) called a second time on the same image, with other points"
    t.call("project_onto_image", image, P, X[:5])
    (held, _, _), _ = t.held(image, P, X[:5])
    if np.array_equal(held, image):
        return passed("the caller's image is left as it was")
    again = t.call("project_onto_image", held, P, X[5:])
    fresh = t.call("project_onto_image", image.copy(), P, X[5:])
    drawn, own = (answer[0] if isinstance(answer, (tuple, list)) and answer else answer for answer in (again, fresh))
    if isinstance(drawn, np.ndarray) and isinstance(own, np.ndarray) and drawn.shape == own.shape \
            and np.mean(np.any(drawn != own, axis=tuple(range(2, drawn.ndim)))) > 0.0005:
        t.images(what, first_points_then_second=drawn, second_points_alone=own)
        t.fail(f"{what}: the second drawing shows the first one's points too: project_onto_image draws on the "
               "caller's `image` (the array given) instead of on a copy, so whoever calls it twice, or uses the "
               "image afterwards, finds points drawn on it.", hint=COPY_HINT.said(t),
               mistake="project_onto_image draws on the caller's image")
    return passed("the second drawing shows its own points only")


OPTION_COLOUR = (40, 200, 90)


@ex5.check("draw_points with radius, colour, and points off the image and on its border", points=2)
def draw_options(t):
    # (a colour with a channel between 0 and 255: one scaled to [0, 1] and back, or saturated, shows)
    image = photo("coffee", (160, 120))
    # off the image, then on its first and last columns and rows (the ends of 0..W-1, 0..H-1)
    pts = np.array([[40.0, 40.0], [120.4, 80.6], [-30.0, 50.0], [500.0, 60.0], [0.0, 119.0], [159.0, 0.0]])
    def redraw(radius: int) -> int | None:   # the radius drawn when another is asked
        try:
            got = t.call("draw_points", image, pts, radius=radius, color=OPTION_COLOUR)
        except StudentFailure:
            return None
        return _drawn_radius(got, image, pts, OPTION_COLOUR) if isinstance(got, np.ndarray) else None

    return judge_drawing(t, f"draw_points(image, pts, radius=6, color={OPTION_COLOUR})",
                         t.call("draw_points", image, pts, radius=6, color=OPTION_COLOUR),
                         image, pts, radius=6, color=OPTION_COLOUR, redraw=redraw)


LEFT_OUT_OFF_THE_IMAGE = from_code("circles centred just off the image are left out by a test of the image's bounds")


def _bounds_test(functions) -> str:
    """A comparison of a point's coordinate with 0 (`x >= 0`, `0 <= x < w`, `pts[:, 0] >= 0`), as written: a
    name the def loops over, or its points parameter, compared with 0; "" when none is made (`radius > 0` is no
    test of a point)."""
    for function in functions:
        params = [a.arg for a in function.args.args]
        coordinates = set(params[1:2]) | {n.id for loop in walk(function) if isinstance(loop, ast.For)
                                          for n in walk(loop.target) if isinstance(n, ast.Name)}
        for node in walk(function):
            sides = [node.left, *node.comparators] if isinstance(node, ast.Compare) else []
            if any(isinstance(op, (ast.Lt, ast.LtE, ast.Gt, ast.GtE)) for op in getattr(node, "ops", ())) \
                    and any(isinstance(side, ast.Constant) and side.value == 0 and not isinstance(side.value, bool)
                            for side in sides) \
                    and any(isinstance(n, ast.Name) and n.id in coordinates for side in sides for n in walk(side)):
                return " ".join(ast.unparse(node).split())
    return ""


@ex5.check("draw_points draws the part in view of a circle centred just off the image", points=1)
def draw_partly_in_view(t):
    """A point a few pixels left of or above the image (a projection just off the frame) has a filled circle
    that reaches into the image: that part is drawn, as cv2.circle draws it (a test that keeps only the
    points inside the frame loses it)."""
    image = photo("coffee", (160, 120))
    pts = np.array([[40.0, 40.0], [-3.0, 70.0], [90.0, -2.0]])
    radius = 8
    what = f"draw_points(image, pts, radius={radius}) with points at (-3, 70) and (90, -2), just off the image"
    got = t.call("draw_points", image, pts, radius=radius)
    got = t.expect_array(got, what, shape=image.shape, dtype=np.uint8)
    painted = np.all(got == np.array([0, 0, 255], np.uint8), axis=-1) if got.ndim == 3 else got == 255
    shares = [painted[core].mean() if core.any() else 1.0
              for core in (truth.circle_regions(image.shape, pts[i:i + 1], radius)[0] for i in range(len(pts)))]
    if shares[0] >= 0.97 and min(shares[1:]) < 0.97:   # (the point in view drawn: this check's question only)
        missing = [f"({x:g}, {y:g})" for (x, y), share in zip(pts[1:], shares[1:]) if share < 0.97]
        t.images(what, "the circles of points just off the image reach into it", input=image, yours=got)
        # (the point in view sits on the diagonal: circles drawn at (y, x) miss only the others -- 06l 09/04 was
        # told their parts in view are not drawn, as if left out)
        at_yx = [truth.circle_regions(image.shape, pts[i:i + 1, ::-1], radius)[0] for i in (1, 2)]
        if all(core.any() and painted[core].mean() > 0.9 for core in at_yx):
            t.fail(f"{what}: {DRAWN_AT_YX}", mistake=XY_SWAPPED)
        bound = _bounds_test(code_of(t).reachable(["draw_points"]))
        t.fail(measured(f"{what}: the part of the circle{'s' if len(missing) > 1 else ''} at {', '.join(missing)} "
                        "inside the image is not drawn: a circle centred just off the image reaches into it, and "
                        "cv2.circle draws that part")
               + (from_code(f"; your code tests the points against the image's bounds (`{bound}`): a point off the "
                            "image or on the image's border may be left out only where its whole circle misses "
                            "the image.") if bound else "."),
               mistake=LEFT_OUT_OFF_THE_IMAGE if bound else "")
    return passed(measured("the circles' parts in view are drawn"))


# The API does not say what draw_points does with a NaN point (a projection
# behind the camera, if the student follows the NaN advice): advice.
@ex5.advice("draw_points skips NaN points")
def draw_nan(t):
    image = photo("coffee", (160, 120))
    # (and an infinite one: the sheet's formula f X / Z gives inf for a point at Z = 0)
    pts = np.array([[40.0, 40.0], [np.nan, np.nan], [120.4, 80.6], [np.inf, 60.0]])
    what = "draw_points(image, pts with a NaN row and an infinite one)"
    try:
        got = t.call("draw_points", image, pts)
        judge_drawing(t, what, got, image, pts, radius=3, color=(0, 0, 255))
    except (StudentFailure, Fail) as failure:
        finite = pts[np.isfinite(pts).all(axis=1)]
        try:
            judge_drawing(t, what, t.call("draw_points", image, finite), image, finite, radius=3, color=(0, 0, 255))
        except (StudentFailure, Fail):
            # (the same points without the NaN and infinite rows fail too: the drawing's own mistake, which
            # the graded checks tell; skipping non-finite rows is no advice for it)
            t.advise(f"{what} failed: {failure.message.splitlines()[0]} -- it fails without the NaN "
                     "and infinite rows too, so the failure is not about them. No points depend on it.")
            return
        t.advise(f"{what} failed: {failure.message.splitlines()[0]} -- projections of points "
                 "behind the camera are NaN if you follow that advice, and f X / Z is infinite at Z = 0, "
                 "so skip the rows that are not finite (NaN or infinite). No points depend on it.",
                 hint=Hint("if np.isfinite(x) and np.isfinite(y): cv2.circle(...)",
                           asks=calls("np.isfinite") | calls("math.isfinite") | calls("np.isnan") | calls("math.isnan"),
                           instead="your code already {found}: check that the rows it skips are those not "
                                   "finite, before any int() conversion").said(t))


def _truncates_coordinates(function) -> bool:
    """An ``int(...)`` call on something other than a constant, the radius or the colour (a
    coordinate), in a function that rounds nothing (round, np.round, np.rint, np.around, np.floor)."""
    rounding = {"round", "np.round", "np.rint", "np.around", "np.floor", "numpy.round", "numpy.rint"}
    if any(isinstance(node, ast.Call) and _hints_path(node.func) in rounding for node in walk(function)):
        return False
    def names(node) -> set[str]:
        return {n.id.lower() for n in walk(node) if isinstance(n, ast.Name)}

    def other(name: str) -> bool:
        return any(word in name for word in ("radius", "color", "colour", "thick"))

    # names iterating over the colour or the radius (``tuple(int(c) for c in color)``) are not coordinates
    others = set().union(*(names(node.target) for node in walk(function)
                           if isinstance(node, (ast.comprehension, ast.For)) and any(map(other, names(node.iter)))))
    for node in walk(function):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "int" \
                and len(node.args) == 1 and not isinstance(node.args[0], ast.Constant):
            read = names(node.args[0])
            if read and not any(other(name) or name in others for name in read):
                return True
    return False


TRUNCATES = Predicate("calls int() on the coordinates, rounding none", _truncates_coordinates)
# The API asks for "filled circles" at the points, not at their nearest pixels: a centre one pixel
# off is accepted by the graded coverage, and told here, measured on the drawing (every fractional
# part >= 0.5, away from ties, so truncating and rounding give different pixels everywhere).
TRUNCATED_CENTRES = measured("the circles are centred at (floor(x), floor(y)), one pixel short of the nearest "
                             "pixel (round(x), round(y)) where the fractional part is 0.5 or more")
TRUNCATED_CAUSE = from_code("the centres are truncated (int()); round them (int(round(x)))")


@ex5.advice("draw_points centres the circles on the nearest pixels")
def draw_rounded(t):
    image = photo("coffee", (160, 120))
    pts = np.array([[40.7, 30.6], [100.8, 75.9], [60.6, 100.7], [130.9, 20.8]])
    got = t.call("draw_points", image, pts)
    if not (isinstance(got, np.ndarray) and got.shape == image.shape and got.dtype == np.uint8):
        return   # the graded checks say what is wrong with the form

    def apart(expected):
        return float(np.mean(np.any(got != expected, axis=-1)))

    rounded, floored = apart(truth.expected_drawing(image, pts)), apart(truth.expected_drawing(image, np.floor(pts)))
    if floored < 2e-4 and rounded > 10 * max(floored, 1e-5):
        truncates = TRUNCATES.found(code_of(t).reachable(["draw_points"]))
        t.advise(f"draw_points(image, pts at x.6 .. x.9): {TRUNCATED_CENTRES}"
                 + (f": {TRUNCATED_CAUSE}" if truncates else "") + ". No points depend on it.")


def _photo_scene(seed=51):
    """(image, P, world points): a 320x240 photo, points in view, two of them at x >= 256."""
    image = photo("chelsea", (320, 240))
    K = np.array([[350.0, 0.0, 159.5], [0.0, 350.0, 119.5], [0.0, 0.0, 1.0]])
    R, tvec = truth.random_pose(seed)
    X = truth.world_points_for(K, R, tvec, seed=seed + 1, n=10, width=320, height=240)
    return image, truth.camera(K, R, tvec), X


@ex5.check("project_onto_image returns the projected points and the image with them drawn", points=4)
def project_onto_image_check(t):
    image, P, X = _photo_scene()
    got = t.call("project_onto_image", image, P, X)
    if not (isinstance(got, (tuple, list)) and len(got) == 2):
        t.fail("project_onto_image should return a pair (image, pts)")
    drawn, pts = got
    expected = truth.homogeneous_project(P, X)
    if isinstance(drawn, np.ndarray) and drawn.shape == expected.shape and isinstance(pts, np.ndarray) \
            and pts.shape == image.shape:
        t.fail("project_onto_image returned (pts, image); the API wants the pair the other way round: "
               "(image, pts).", mistake="the pair is returned in the wrong order")
    judge_points(t, "project_onto_image(...)[1] (the points)", pts, expected, project_mistakes(P, X),
                 tolerance=1e-6, show="projected points", probe=points_probe(t, "project_onto_image"))
    if isinstance(drawn, np.ndarray) and drawn.shape == image.shape and np.array_equal(drawn, image):
        t.fail("project_onto_image(...)[0] is the image unchanged: the projected points are not drawn on it "
               "(draw_points(image, pts)).", mistake="the points are not drawn on the image")
    return judge_drawing(t, "project_onto_image(...)[0] (the image)", drawn, image, expected)


def _scene_off_the_frame(seed=51):
    """(image, P, world points): three of the photo scene's points in view and, between them, three whose
    images fall off the 320x240 frame (left of it, right of it, below it)."""
    image = photo("chelsea", (320, 240))
    K = np.array([[350.0, 0.0, 159.5], [0.0, 350.0, 119.5], [0.0, 0.0, 1.0]])
    R, tvec = truth.random_pose(seed)
    inside = truth.world_points_for(K, R, tvec, seed=seed + 1, n=3, width=320, height=240)
    seen = np.array([[-3.0, 0.2, 5.0], [2.8, -0.1, 4.0], [0.3, 2.5, 6.0]])   # in the camera: x -50.5, x 404.5, y 265.3
    outside = (seen - tvec) @ R   # (world = R^T (camera - t), row by row)
    return image, truth.camera(K, R, tvec), np.vstack([inside[:2], outside[:2], inside[2:], outside[2:]])


@ex5.check("project_onto_image with points off the image: a row per point", points=1)
def project_onto_image_off_the_frame(t):
    """Every point keeps its row, so that row i is point i's: off the frame it is where the camera sends
    it (nothing is drawn there). (No point behind the camera: NaN, the skeleton's advice, would reach
    the student's own drawing, which the API does not ask to take NaN.)"""
    image, P, X = _scene_off_the_frame()
    got = t.call("project_onto_image", image, P, X)
    if not (isinstance(got, (tuple, list)) and len(got) == 2):
        t.fail("project_onto_image should return a pair (image, pts)")
    pts, expected = got[1], truth.homogeneous_project(P, X)
    what = f"project_onto_image(image, P, points)[1], {len(X)} points of which 3 fall off the 320x240 image"
    rows = getattr(pts, "shape", (None,))[0] if getattr(pts, "ndim", 0) == 2 else None
    if rows is not None and rows < len(X):
        t.fail(f"{what}, has {rows} rows: every point keeps its row (row i is point i's, its image off the frame "
               "too), so that a caller can match the points to what it gave. "
               + measured(f"{len(X) - rows} fewer rows than points: are the points off the image left out?"),
               mistake="points off the image are left out")
    judge_points(t, what, pts, expected, project_mistakes(P, X), tolerance=1e-6,
                 probe=points_probe(t, "project_onto_image"))


@ex5.check("project_onto_image for any camera: the world origin on or behind the camera's plane", points=1)
def project_onto_image_any_camera(t):
    """The cameras ``project`` is checked with beyond the usual set-up (P at another scale, P[2, 3] = 0
    and < 0), through project_onto_image: the same camera gives the same points in both functions."""
    # (on a photo the size of a camera's frame: the image drawn on is the one given, at its own size)
    image = photo("chelsea", (960, 720))
    for name, P, X in other_cameras():
        got = t.call("project_onto_image", image, P, X)
        if not (isinstance(got, (tuple, list)) and len(got) == 2):
            t.fail("project_onto_image should return a pair (image, pts)")
        t.expect_array(got[0], f"project_onto_image(960x720 image, {name}, points)[0] (the image)",
                       shape=image.shape, dtype=image.dtype)
        judge_points(t, f"project_onto_image(image, {name}, points)[1] (the points)", got[1],
                     truth.homogeneous_project(P, X), project_mistakes(P, X), tolerance=1e-6,
                     probe=points_probe(t, "project_onto_image"))
    return passed("the same points as project gives, for every camera")


def _scene_with_a_point_behind():
    """The off-the-frame scene with a point 3 units behind the camera as point 3."""
    image, P, X = _scene_off_the_frame()
    R, tvec = truth.random_pose(51)
    behind = (np.array([[0.5, -0.4, -3.0]]) - tvec) @ R   # 3 units behind the camera, in world coordinates
    return image, P, np.vstack([X[:3], behind, X[3:]])


@ex5.check("project_onto_image with a point behind the camera: still a row per point", points=1)
def project_onto_image_behind(t):
    """A point behind the camera keeps its row too (its value is open: NaN, the skeleton's advice, or what
    the formulas give), so that row i stays point i's. A call that raises is not judged here: NaN given
    to the student's own drawing may raise there, which the API does not ask it to take."""
    image, P, X = _scene_with_a_point_behind()
    what = f"project_onto_image(image, P, points)[1], {len(X)} points of which point 3 is behind the camera"
    try:
        got = t.call("project_onto_image", image, P, X)
    except StudentFailure:
        # (raising with the points in front too is a failure of its own: told as it is)
        t.call("project_onto_image", image, P, np.delete(X, 3, axis=0))
        return passed(measured("the call raised with a point behind the camera only: not judged here (NaN may "
                               "reach the drawing, which the API does not ask to take it)"))
    if not (isinstance(got, (tuple, list)) and len(got) == 2):
        t.fail("project_onto_image should return a pair (image, pts)")
    pts = got[1]
    rows = getattr(pts, "shape", (None,))[0] if getattr(pts, "ndim", 0) == 2 else None
    if rows is not None and rows < len(X):
        finite = int(np.isfinite(truth.homogeneous_project(P, X)).all(axis=1).sum())
        t.fail(f"{what}, has {rows} rows: every point keeps its row (row i is point i's; behind the camera its "
               "value is yours to choose, NaN is the skeleton's advice), so that a caller can match the points to "
               "what it gave. " + measured(f"{len(X) - rows} fewer rows than points"
                                           + (": the point behind the camera is left out (are the rows that are "
                                              "not finite dropped?)" if rows == finite else "")),
               mistake="a point behind the camera is left out" if rows == finite else "")
    expected = truth.homogeneous_project(P, X)
    keep = np.arange(len(X)) != 3
    judge_points(t, what + " (the points in front)", np.asarray(pts, np.float64)[keep] if rows == len(X) else pts,
                 expected[keep], project_mistakes(P, X[keep]), tolerance=1e-6)


NAN_TO_ZERO = calls("np.nan_to_num")


@ex5.check("project_onto_image draws nothing where none of its points is (a point behind the camera)", points=1)
def project_onto_image_draws_its_points(t):
    """One call's two results agree: the image shows a circle at each finite returned point and nothing
    elsewhere. A point behind the camera is the question: whatever value its row holds (NaN, the skeleton's
    advice, or the formulas'), nothing may be drawn where no returned point is. A call that raises is not
    judged here (see the rows check)."""
    image, P, X = _scene_with_a_point_behind()
    try:
        got = t.call("project_onto_image", image, P, X)
    except StudentFailure:
        # (raising with the points in front too is a failure of its own: told as it is)
        t.call("project_onto_image", image, P, np.delete(X, 3, axis=0))
        return passed(measured("the call raised with a point behind the camera only: not judged here"))
    drawn, pts = got if isinstance(got, (tuple, list)) and len(got) == 2 else (None, None)
    pts = np.asarray(pts, dtype=np.float64) if isinstance(pts, np.ndarray) and pts.dtype.kind in "iuf" else None
    if not (isinstance(drawn, np.ndarray) and drawn.shape == image.shape and pts is not None
            and pts.shape == (len(X), 2)):
        return passed(measured("the form of the answer is the other checks' to judge"))
    shown = pts[np.isfinite(pts).all(axis=1)]
    _, far = truth.circle_regions(image.shape, shown, 3) if len(shown) else (None, np.ones(image.shape[:2], bool))
    stray = np.any(drawn != image, axis=-1) & far
    if stray.sum() <= 3:
        return passed(measured("every drawn pixel is near a returned point"))
    if stray.sum() > 0.01 * far.sum():   # (the whole image changed -- its colours, a blank canvas: the other checks')
        return passed(measured("the image itself is changed away from the points: the other checks judge it"))
    ys, xs = np.nonzero(stray)
    at = (int(round(xs.mean())), int(round(ys.mean())))
    corner = max(at) <= 6 and not np.isfinite(pts[3]).all()
    via_draw_points = bool(calls("draw_points").found(code_of(t).reachable(["project_onto_image"])))
    t.images("project_onto_image(image, P, points)[0]", "point 3 is behind the camera", input=image, yours=drawn)
    t.fail(measured(f"project_onto_image(image, P, points), point 3 behind the camera: {int(stray.sum())} pixels "
                    f"are drawn around (x, y) = {at}, where none of the returned points is (row 3 is "
                    f"{format_matrix(pts[3])})")
           + (measured(": the point whose projection is NaN is drawn at the corner (0, 0)")
              + (from_code(", where np.nan_to_num puts it (NaN becomes 0): draw only the finite points.")
                 if NAN_TO_ZERO.found(code_of(t).reachable(["project_onto_image"])) else ".") if corner else
              (measured(". The image and the points returned should agree: draw the points you return.")
               if not via_draw_points else
               from_code(". Your project_onto_image draws with your draw_points: what draw_points draws for these "
                         "points (off the image, or not finite) is the place to look."))),
           mistake="a point behind the camera is drawn" if corner else
           "" if via_draw_points else "the drawing is not of the returned points")


# ================================================================== ext1 calibration
# Object points built row by row, x fastest, from pattern_size = (cols, rows) (labs 9 and 10).
OBJECT_POINTS_ROW_BY_ROW = (expr("np.mgrid[0:_[0], 0:_[1]].T.reshape(-1, 2)")
                            | expr("np.mgrid[0:cols, 0:rows].T.reshape(-1, 2)")
                            | expr("np.mgrid[0:nx, 0:ny].T.reshape(-1, 2)")
                            | expr("np.mgrid[0:w, 0:h].T.reshape(-1, 2)")).saying(
    "builds the object points with np.mgrid[0:cols, 0:rows].T.reshape(-1, 2)")
ROWS_FIRST = ("r", "h", "ny", "n_rows", "nrows", "height")
OBJECT_POINTS_ORDER = guessed("the object points are in the wrong order")


def _pattern_read_rows_first(function) -> bool:
    """``rows, cols = pattern_size`` (or ``h, w``, ``ny, nx``) read from a name holding "pattern", or
    ``np.mgrid[0:p[1], 0:p[0]]``: pattern_size read as (rows, cols)."""
    for node in walk(function):
        if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Tuple) \
                and any("pattern" in n.id for n in walk(node.value) if isinstance(n, ast.Name)):
            first = node.targets[0].elts[0]
            if isinstance(first, ast.Name) and (first.id.lower() in ROWS_FIRST or first.id.lower().startswith("row")):
                return True
    return expr("np.mgrid[0:_[1], 0:_[0]]").holds([function])


def _corners_asked_cols_first(function) -> bool:
    """Whether every cv2.findChessboardCorners call is given the pattern as pattern_size comes, (cols,
    rows): a name holding "pattern", or a pair whose first item is not a count of rows (``(rows, cols)``,
    ``(h, w)``, ``(p[1], p[0])`` are); read leniently (anything else counts as given rightly)."""
    for node in walk(function):
        if not (isinstance(node, ast.Call) and _hints_path(node.func).endswith(("findChessboardCorners",
                                                                                  "findChessboardCornersSB"))):
            continue
        given = node.args[1] if len(node.args) > 1 else next(
            (k.value for k in node.keywords if k.arg == "patternSize"), None)
        if isinstance(given, (ast.Tuple, ast.List)) and len(given.elts) == 2:
            first = given.elts[0]
            if isinstance(first, ast.Name) and (first.id.lower() in ROWS_FIRST or first.id.lower().startswith("row")):
                return False
            if isinstance(first, ast.Subscript) and isinstance(first.slice, ast.Constant) and first.slice.value == 1:
                return False
    return True


def _views_appended_apart(function) -> bool:
    """Object points and corners appended in different blocks (one under ``if found:``, the other not):
    a view's object points may then go with another view's corners, or with none."""
    blocks = {"obj": set(), "corner": set()}
    for parent in walk(function):
        for field in ("body", "orelse"):
            for statement in getattr(parent, field, []) if isinstance(getattr(parent, field, None), list) else []:
                for node in walk(statement) if isinstance(statement, ast.Expr) else []:
                    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                            and node.func.attr == "append" and node.args:
                        held = " ".join(n.id.lower() for n in walk(node.args[0]) if isinstance(n, ast.Name))
                        for kind, words in (("obj", ("obj",)), ("corner", ("corner", "img_p", "imgp", "pts"))):
                            if any(word in held for word in words):
                                blocks[kind].add((id(parent), field))
    return bool(blocks["obj"] and blocks["corner"] and not blocks["obj"] & blocks["corner"])


def _scales_by_square_size(function) -> bool:
    """A product with a name holding "square" (the parameter square_size, a copy of it); read leniently."""
    return any(isinstance(n, (ast.BinOp, ast.AugAssign)) and isinstance(n.op, ast.Mult)
               and any(isinstance(m, ast.Name) and "square" in m.id.lower() for m in walk(n))
               for n in walk(function))


def _tests_a_found_flag(function) -> bool:
    """A test of a name (``if found:``, ``if not ret: continue``, ``[... if ok]``): the views whose corners were
    found kept; read leniently."""
    def flag(test) -> bool:
        test = test.operand if isinstance(test, ast.UnaryOp) and isinstance(test.op, ast.Not) else test
        return isinstance(test, ast.Name) or isinstance(test, ast.Compare) and isinstance(test.left, ast.Name)
    return any(isinstance(n, (ast.If, ast.IfExp)) and flag(n.test) for n in walk(function)) or any(
        isinstance(n, ast.comprehension) and any(flag(test) for test in n.ifs) for n in walk(function))


OBJECT_POINTS_HINT = Hint(
    "build them row by row, x fastest: np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size.",
    asks=OBJECT_POINTS_ROW_BY_ROW,
    instead="your code {found}: " + checklist(
        "", ("pattern_size is read as (cols, rows)", ~Predicate("reads pattern_size as (rows, cols)",
                                                                _pattern_read_rows_first)),
        ("each view's object points go with that view's corners",
         ~Predicate("appends object points and corners apart", _views_appended_apart)),
        ("cv2.findChessboardCorners is given the pattern as (cols, rows), as pattern_size comes",
         Predicate("gives cv2.findChessboardCorners the pattern as (cols, rows)", _corners_asked_cols_first)),
        none_left=look_at(("the square size", Predicate("scales by the square size", _scales_by_square_size)),
                          ("the views kept (those whose corners were found)",
                           Predicate("keeps the views whose corners were found", _tests_a_found_flag)))) + ".")
ext1 = lab.exercise("ext1", "Extension: camera calibration", functions=[
    "calibrate(images, pattern_size, square_size)"])


_POINT_COUNTS = re.compile(r"'numberOfObjectPoints' is (\d+)\s*>?\s*must be equal to\s*>?\s*'numberOfImagePoints' is (\d+)")
GRID_MISCOUNTED = "the board's grid has another number of points than the corners found"


def _float_step_grid(t: Trial) -> str:
    """The sentence naming an np.arange with a float step (the square's size) in calibrate's code, or ''."""
    for function in code_of(t).reachable(["calibrate"]):
        for node in walk(function):
            if isinstance(node, ast.Call) and _hints_path(node.func).rsplit(".", 1)[-1] == "arange" \
                    and len(node.args) == 3 and not isinstance(node.args[2], ast.Constant):
                return from_code(f" Your code makes the grid with `{ast.unparse(node)[:60]}` (line {node.lineno}): with a "
                                 "float step, where the end falls is left to rounding, and np.arange can give one "
                                 "entry more (np.arange(0, 7 * 0.3, 0.3) has 8); count the squares instead "
                                 "(np.arange(n) * square_size).")
    return ""


def calibration_result(t: Trial, images, pattern, square=truth.CALIBRATION_SQUARE) -> tuple[str, np.ndarray, np.ndarray, float]:
    """``calibrate(images, pattern, square)`` called once per grading (the checks of one set of
    views share it), checked for its form: (what, K, dist, rms). K, dist and rms do not depend on the
    square's size (it scales the boards' positions only)."""
    what = f"calibrate({len(images)} views, pattern_size={pattern}, square_size={square})"
    try:
        got = t.shared(("calibrate", pattern, square, fingerprint(*images)),
                       lambda: t.call("calibrate", list(images), pattern, square))
    except StudentFailure as failure:
        counts = _POINT_COUNTS.search(failure.message) if failure.outcome.kind == "exception" else None
        if counts is None:
            raise
        objects, corners = int(counts.group(1)), int(counts.group(2))
        t.fail(f"{what} raised OpenCV's error: the object points of a view are {objects} where its corners are "
               f"{corners}. " + measured(f"The board's grid has one point per inner corner ({pattern[0]} x "
                                         f"{pattern[1]} = {pattern[0] * pattern[1]}), whatever the square's size ("
                                         f"{square} here).") + _float_step_grid(t),
               mistake=GRID_MISCOUNTED)
    if not (isinstance(got, (tuple, list)) and len(got) == 3):
        t.fail(f"{what} should return a triple (K, dist, rms)")
    K, dist, rms = got
    K = t.expect_array(K, f"{what}[0] (K)", shape=(3, 3), kind="iuf", finite=True)
    dist = t.expect_array(dist, f"{what}[1] (dist)", kind="iuf", finite=True)
    if dist.size < 4:
        t.fail(f"{what}[1] (dist) has {dist.size} values; expected OpenCV's (k1, k2, p1, p2, k3)")
    if not isinstance(rms, (int, float)) and not (isinstance(rms, np.ndarray) and rms.size == 1):
        t.fail(f"{what}[2] (rms) should be a number (the RMS reprojection error in pixels)")
    return what, K, dist, float(np.asarray(rms).ravel()[0])


# (where the code builds the object points row by row, the cause is not read from the error: the usual places)
NOT_FITTING = where_to_look(
    " Look at how each view's corners are found and refined (on that view's own image?) and paired with the "
    "board's points (the same view, the same order?).")


# The object points laid out in another order than the corners cv2.findChessboardCorners gives (row by row,
# x fastest): column by column, or for the pattern read as (rows, cols). Their calibration on the views' own
# corners gives an rms of several pixels; a student's rms within ORDER_RMS_SHARE of one of those is told
# that order -- others far off (a coordinate left unscaled: 2.6 px where the orders give 9 and more) are not.
_OTHER_ORDERS = {
    "column by column": lambda cols, rows: np.mgrid[0:cols, 0:rows].reshape(2, -1).T,
    "for the pattern read as (rows, cols)": lambda cols, rows: np.mgrid[0:rows, 0:cols].T.reshape(-1, 2),
}
ORDER_RMS_SHARE = 0.25


def _order_with_rms(images, pattern, square, rms: float) -> str:
    """The other orders of the object points (keys of :data:`_OTHER_ORDERS`, joined by ", or ") whose calibration
    on the views' own corners (found as the sheet's recipe finds them) gives about ``rms``; "" when none does,
    or the corners are not found."""
    orders = _orders_rms(images, pattern, square)
    return ", or ".join(order for order, theirs in orders.items()
                        if abs(theirs - rms) <= ORDER_RMS_SHARE * theirs)   # (both alike: y fastest either way)


_ORDERS_RMS: dict = {}   # the views' fingerprint -> {order: rms}: a grading's failing checks share the views


def _orders_rms(images, pattern, square) -> dict:
    """{order: the rms of cv2.calibrateCamera with the object points in that order} on ``images``' corners."""
    import cv2

    key = fingerprint(list(images), tuple(pattern), float(square))
    if key in _ORDERS_RMS:
        return _ORDERS_RMS[key]
    cols, rows = pattern
    corners = []
    for image in images:
        grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
        # (a view without the whole board is given up at once: hidden views include one)
        found, found_corners = cv2.findChessboardCorners(grey, (cols, rows), flags=cv2.CALIB_CB_ADAPTIVE_THRESH
                                                         | cv2.CALIB_CB_NORMALIZE_IMAGE | cv2.CALIB_CB_FAST_CHECK)
        if found:
            corners.append(cv2.cornerSubPix(grey, found_corners, (5, 5), (-1, -1),
                                            (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)))
    orders = {}
    if len(corners) >= 3:
        size = (images[0].shape[1], images[0].shape[0])   # (width, height)
        for order, grid in _OTHER_ORDERS.items():
            board = np.zeros((cols * rows, 3), np.float32)
            board[:, :2] = grid(cols, rows) * square
            orders[order] = float(cv2.calibrateCamera([board] * len(corners), corners, size, None, None)[0])
    if len(_ORDERS_RMS) >= 16:
        _ORDERS_RMS.clear()
    _ORDERS_RMS[key] = orders
    return orders


def judge_calibration(t: Trial, images, K_true, pattern, square=truth.CALIBRATION_SQUARE):
    """Calibrate on rendered views of a board with ``pattern`` inner corners, rendered with ``K_true``."""
    what, K, dist, rms = calibration_result(t, images, pattern, square)
    if abs(K[2, 2]) > 1e-12:
        K = K / K[2, 2]
    if abs(K[2, 0]) > 1.0 and abs(K[0, 2]) < 1.0:
        t.fail(f"{what}: K is transposed: the principal point belongs in the last column.",
               mistake="K is transposed")
    f_error = np.abs(np.array([K[0, 0], K[1, 1]]) / np.array([K_true[0, 0], K_true[1, 1]]) - 1.0)
    c_error = np.abs(K[:2, 2] - K_true[:2, 2])
    if not np.isfinite(rms) or rms < 0:
        t.fail(f"{what}: rms = {rms} is not a reprojection error")
    if rms > 1.0:
        # (the order is guessed only where the code does not build them row by row: corners refined on
        # another view's image match no object points either -- the blind set 1204c's 09/08)
        # (and the order is a guess: a change of the code confirmed to mend it -- a coordinate left unscaled
        # in a loop building them row by row -- takes its place, and the recipe's hint with it)
        ordered = OBJECT_POINTS_ROW_BY_ROW.found(code_of(t).reachable(["calibrate"]))
        # (where the points are built row by row no cause is told: a slip read in the code -- every view merged
        # into one -- or a change confirmed takes their place; elsewhere an order is told only where the points
        # laid out in it give the student's rms on these views: a coordinate left unscaled is no order)
        order = "" if ordered else _order_with_rms(images, pattern, square, rms)
        t.fail(f"{what}: the reprojection error is {rms:.2f} px (a good calibration on these clean "
               "views has < 0.1 px)"
               + (": the object points do not correspond to the detected corners: it looks like "
                  f"{OBJECT_POINTS_ORDER} ({order}: object points laid out that way give about this reprojection error "
                  "on these views)."
                  if order else ": no camera puts the object points on the corners as they are paired." + NOT_FITTING),
               hint=OBJECT_POINTS_HINT.said(t) if order else "", mistake=OBJECT_POINTS_ORDER if order else "")
    if np.abs(K[:2, 2] - K_true[1::-1, 2]).max() < 3.0 and c_error.max() > 3.0:
        # (the image size given rows first does not do it -- cv2.calibrateCamera only starts from it -- the corners'
        # x and y exchanged, or the view transposed, do: audit of 2026-12-06)
        t.fail(measured(f"{what}: the principal point is swapped: ({K[0, 2]:.1f}, {K[1, 2]:.1f}) where "
                        f"({K_true[0, 2]:.1f}, {K_true[1, 2]:.1f}) is asked, x and y exchanged between the image points "
                        "and the image: the corners cv2.findChessboardCorners gives are (x, y) = (column, row), of "
                        "the view as it is"), mistake="the principal point is swapped")
    if f_error.max() > 0.015 or c_error.max() > 3.0:
        fail_if_calibrated_at_another_scale(t, what, K, K_true)
        looped = (call_in_a_loop(code_of(t).reachable(["calibrate"]), ("calibrateCamera",)) or ("", 0))[1]
        cause = from_code(f" Your code calls cv2.calibrateCamera inside a loop (line {looped}), a calibration of each "
                          "view alone (one view cannot fix the focal lengths and the principal point): calibrate "
                          "once, with the object points and corners of every view together.") if looped else ""
        t.fail(f"{what}: K is off: its focal lengths by {f_error.max():.1%}, its principal point by "
               f"{c_error.max():.1f} px.{cause}\nIt is\n{format_matrix(K)}\nbut the views were rendered with\n"
               f"{format_matrix(K_true)}", mistake=from_code("cv2.calibrateCamera called on each view alone") if looped else "")
    if rms > 0.5:
        return partial(0.5, f"{what}: K is right, but the reported reprojection error is {rms:.2f} px; "
                            "these clean views allow < 0.2 px.",
                       hint=Hint("refine corners with cv2.cornerSubPix", asks=calls("cv2.cornerSubPix"),
                                 instead="your code already {found}: the error is elsewhere (the RMS returned "
                                         "is cv2.calibrateCamera's, for the K and distortion returned)").said(t))
    return passed(f"focal lengths within {f_error.max():.2%}, principal point within {c_error.max():.2f} px, "
                  f"rms {rms:.3f} px")


RESCALED = "the corners are in the pixels of the views resized"


def fail_if_calibrated_at_another_scale(t: Trial, what: str, K: np.ndarray, K_true: np.ndarray) -> None:
    """Fail naming a K that is the true one at another scale as a whole -- both focal lengths and the principal
    point by one factor s (a pixel centre x of a view resized by s is at s (x + 0.5) - 0.5) --: the corners were
    found on resized views and never scaled back to the pixels of the views given."""
    s = K[0, 0] / K_true[0, 0]
    if not 0.05 < s < 20 or abs(s - 1.0) < 0.05:
        return
    scaled = K_true[:2, 2] * s + (s - 1.0) / 2
    if abs(K[1, 1] / (s * K_true[1, 1]) - 1.0) > 0.015 or np.abs(K[:2, 2] - scaled).max() > 3.0 * max(s, 1.0):
        return
    resized = (calls("cv2.resize") | calls("cv2.pyrDown")).found(code_of(t).reachable(["calibrate"]))
    t.fail(measured(f"{what}: your K is the true K scaled by {s:.3g} as a whole (focal lengths and principal point "
                    f"alike): it looks like {RESCALED} by {s:.3g} and not scaled back to the pixels of the views "
                    f"given ({1 / s:.3g} times the corners found there), so K describes the resized camera.")
           + (from_code(f" Your code {resized} in calibrate.") if resized else "")
           + f"\nIt is\n{format_matrix(K)}\nbut the views were rendered with\n{format_matrix(K_true)}",
           mistake=f"{RESCALED} and not scaled back")


@ext1.check("calibrate on views of 1280 x 960 pixels (a webcam's frames)", points=1)
def calibrate_large(t):
    images, K, _ = truth.large_calibration_views()
    return judge_calibration(t, images, K, truth.CALIBRATION_PATTERN)


@ext1.check("calibrate on six rendered chessboard views recovers K", points=4)
def calibrate_rendered(t):
    images, K, _ = truth.calibration_views()
    t.images("two of the calibration views", view_1=images[0], view_2=images[3])
    return judge_calibration(t, images, K, truth.CALIBRATION_PATTERN)


# The K, dist and rms of one calibration must agree: the board's corners reprojected with the
# returned K and dist (each view's best pose, on the exact corners) are as far from them as the rms
# says, or closer (the student's rms also holds their corner detection's noise). Measured on the
# public views: the reference 0.005 px recomputed for rms 0.037; without cornerSubPix 0.006 / 0.041;
# float32, CALIB_FIX_K3, CALIB_ZERO_TANGENT_DIST 0.004-0.005 / 0.037 (recomputed - rms <= -0.03). K
# from cv2.getOptimalNewCameraMatrix (alpha 1, its focal lengths 1.5% off: within recovers-K's
# tolerance) 0.159 / 0.037; alpha 0.5 0.098; without cornerSubPix 0.217 / 0.041 (>= +0.06).
CONSISTENCY_SLACK = 0.05   # px the recomputed error may exceed the returned rms
# And no detection finds the rendered corners exactly: cv2.calibrateCamera's rms on these views is
# 0.037 px (findChessboardCorners + cornerSubPix 5x5, any calibration flags), 0.041 without
# cornerSubPix, 0.044 / 0.095 with 3x3 / 11x11 windows, 0.094 with findChessboardCornersSB. The
# OpenCV tutorial's "mean error" (each view's error norm divided by its corner count, averaged) is
# about rms / sqrt(corners): 0.006-0.014 px for the same detections. Below this, the number returned
# is not an RMS of detected corners.
RMS_FLOOR = 0.02   # px
# cv2.calibrateCamera's RMS on these views, measured: 0.037-0.096 px with corners refined by cv2.cornerSubPix in
# windows of 3x3 to 11x11 or not refined at all, with flags 0, CALIB_RATIONAL_MODEL or CALIB_FIX_K3
RMS_CEILING = 0.15   # px


def _divides_a_norm(function) -> bool:
    """A division whose numerator takes a norm (``cv2.norm(a, b, cv2.NORM_L2) / len(p)``,
    ``np.linalg.norm(e) / n``): the error vector's length divided by its count, not its RMS."""
    return any(isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div)
               and any(isinstance(n, ast.Call) and _hints_path(n.func).rsplit(".", 1)[-1] == "norm"
                       for n in walk(node.left))
               for node in walk(function))


NORM_OVER_COUNT = Predicate("divides an error norm by a count", _divides_a_norm)


@ext1.check("calibrate: the K, dist and rms it returns agree with each other", points=1)
def calibration_consistent(t):
    images, _, corners = truth.calibration_views()
    what, K, dist, rms = calibration_result(t, images, truth.CALIBRATION_PATTERN)
    if dist.size == 4:   # (the K may still be right: only this check, of the three, asks for all five)
        t.fail(f"{what}[1] (dist) has 4 values; expected OpenCV's five (k1, k2, p1, p2, k3): without k3 the "
               "lens the calibration estimated is not the one returned")
    recomputed = truth.reprojection_rms(K, dist, corners)
    if np.isnan(recomputed):
        t.fail(f"{what}[1] (dist) has {dist.size} values, a length OpenCV's distortion model does not have "
               "(4, 5, 8, 12 or 14)")
    if 0 <= rms < RMS_FLOOR:
        _fail_rms_below_detection(t, what, rms, corners)
    if rms > RMS_CEILING and recomputed <= RMS_CEILING:
        _fail_rms_above_detection(t, what, rms, recomputed)
    if recomputed <= rms + CONSISTENCY_SLACK:
        return passed(f"the board's corners reprojected with your K and dist (best pose per view) are "
                      f"{recomputed:.3f} px RMS from the true corners; your rms says {rms:.3f} px")
    shown = "far off" if recomputed > 1e3 else f"{recomputed:.3f} px"
    read = code_of(t).reachable(["calibrate"])
    reading = calls("cv2.getOptimalNewCameraMatrix").found(read)
    calibrations = sum(1 for function in read for node in walk(function) if isinstance(node, ast.Call)
                       and _hints_path(node.func).rsplit(".", 1)[-1] == "calibrateCamera")
    # Named only with the cause the code shows: the disagreement alone has several (a K returned
    # transposed, another call's K or dist, a calibration of some of the views only, whose rms is
    # theirs), which the message leaves to the student (the blind set 1203a's 09/08: "not the pair
    # the rms was computed for" told to code whose one call used only the last view).
    looped = (call_in_a_loop(read, ("calibrateCamera",)) or ("", 0))[1]
    cause = from_code(": your code calls cv2.getOptimalNewCameraMatrix, and K is measured not to be the calibrated "
                      "camera's: that matrix is for undistorted images (cv2.undistort's newCameraMatrix), not the "
                      "calibrated camera's K") if reading else \
        from_code(f": your code calls cv2.calibrateCamera {calibrations} times; return K, dist and rms of the same "
                  "call") if calibrations > 1 else \
        from_code(f": your code calls cv2.calibrateCamera inside a loop (line {looped}), one calibration per view; "
                  "calibrate once, with every view's points, and return that call's K, dist and rms") if looped else ""
    t.fail(measured(f"{what}: the K, dist and rms returned do not agree: with your K and dist, the best pose of each "
                    f"view reprojects the board's corners {shown} RMS from the true corners, while the rms returned "
                    f"says {rms:.3f} px") + (cause or "."),
           mistake=from_code("K from cv2.getOptimalNewCameraMatrix instead of the calibrated K") if reading else "")


def _fail_rms_above_detection(t: Trial, what: str, rms: float, recomputed: float) -> None:
    """The rms returned is above what any detection gives on these views while K and dist reproject the corners
    well: not cv2.calibrateCamera's RMS. Said with the square root the code takes of it, where it takes one."""
    roots = [node for function in code_of(t).reachable(["calibrate"]) for node in walk(function)
             if isinstance(node, ast.Call) and _hints_path(node.func).rsplit(".", 1)[-1] == "sqrt"
             or isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) and isinstance(node.right, ast.Constant)
             and node.right.value == 0.5]
    cause = from_code(f" Your code takes a square root (`{ast.unparse(roots[0])}`, line {roots[0].lineno}): the first "
                      "result of cv2.calibrateCamera is already the root mean square reprojection error, in pixels; "
                      "return it as it is.") if roots else ""
    t.fail(measured(f"{what}: the rms returned is {rms:.3f} px, above what cv2.calibrateCamera's RMS reprojection "
                    f"error is on these rendered views (0.04-0.1 px, whatever the corner refinement and flags), while "
                    f"your K and dist reproject the board's corners {recomputed:.3f} px RMS from the true ones: the rms "
                    "is not the calibration's own.") + cause,
           mistake=from_code("the square root of the RMS returned as the rms") if roots else "")


def _fail_rms_below_detection(t: Trial, what: str, rms: float, corners) -> None:
    """The rms returned is below what any corner detection reaches on these views: it is not
    cv2.calibrateCamera's RMS. Named as the tutorial's mean error where the code computes one."""
    per_view = int(np.asarray(corners[0]).reshape(-1, 2).shape[0])
    cause = ""
    if NORM_OVER_COUNT.found(code_of(t).reachable(["calibrate"])):
        cause = from_code(
            f" Your code divides a norm of the reprojection errors by their count (the OpenCV tutorial's mean "
            f"error): ||e|| / N is the RMS divided by sqrt(N) (N = {per_view} corners per view here), not the "
            "RMS. Return the rms cv2.calibrateCamera returns (its first result).")
    t.fail(measured(f"{what}: the rms returned is {rms:.4f} px, below what any corner detection reaches on these "
                    f"rendered views (cv2.calibrateCamera's RMS reprojection error is 0.04-0.1 px here, whatever the "
                    f"detector and flags): it is not the RMS reprojection error of the calibration.") + cause,
           mistake=from_code("a mean error norm per corner (the tutorial's error) returned as the rms") if cause else "")


def _converted_names(function) -> set[str]:
    """Names ``function`` assigns a cv2.cvtColor result (``grey = cv2.cvtColor(view, ...)``)."""
    return {t.id for n in walk(function) if isinstance(n, ast.Assign)
            and any(isinstance(c, ast.Call) and _hints_path(c.func).rsplit(".", 1)[-1] == "cvtColor"
                    for c in walk(n.value)) for t in n.targets if isinstance(t, ast.Name)}


def _unconverted_to_one_channel(functions) -> bool:
    """A cv2.cornerSubPix given a name no cv2.cvtColor result was stored in (the view as it came)."""
    for function in functions:
        converted = _converted_names(function)
        for n in walk(function):
            if isinstance(n, ast.Call) and _hints_path(n.func).rsplit(".", 1)[-1] == "cornerSubPix" and n.args \
                    and isinstance(n.args[0], ast.Name) and n.args[0].id not in converted:
                return True
    return False


def _size_of_three_channels(functions) -> bool:
    """cv2.calibrateCamera given ``view.shape[::-1]`` of a view not converted (3 entries for a colour view)."""
    for function in functions:
        converted = _converted_names(function)
        for n in walk(function):
            if isinstance(n, ast.Call) and _hints_path(n.func).rsplit(".", 1)[-1] == "calibrateCamera" \
                    and len(n.args) > 2:
                size = n.args[2]
                if isinstance(size, ast.Subscript) and isinstance(size.value, ast.Attribute) \
                        and size.value.attr == "shape" and isinstance(size.slice, ast.Slice) \
                        and size.slice.lower is None and size.slice.upper is None \
                        and not (isinstance(size.value.value, ast.Name) and size.value.value.id in converted):
                    return True
    return False


GREY_FOR_OPENCV = Hint(
    "Convert each view to grey where an OpenCV call needs one channel (cv2.cornerSubPix does), when it has 3: "
    "cv2.cvtColor(image, cv2.COLOR_BGR2GRAY), and pass the image size as (width, height)",
    asks=calls("cv2.cvtColor"),
    instead="Your code {found}: " + checklist(
        "", ("every call that needs one channel gets the converted view",
             ~Predicate("gives cv2.cornerSubPix a view not converted", _unconverted_to_one_channel, kind="all")),
        ("the image size passed is (width, height), not the shape of a 3-channel array",
         ~Predicate("gives cv2.calibrateCamera a colour view's shape", _size_of_three_channels, kind="all")),
        # (the views each call is given are the items' readings: nothing is left to point at)
        none_left=""))


SKIMAGE_SQUARE = 0.3
# (an error a colour view can cause: a depth or channel count refused, a conversion asked of a colour image)
_CHANNEL_TROUBLE = re.compile(r"depth|channel|scn|CV_8U|cvtColor|type|dimension", re.IGNORECASE)


@ext1.check("calibrate on views of scikit-image's chessboard picture (7 x 7 inner corners, squares of 0.3), with 3 "
            "channels as cv2.imread reads a photo", points=1)
def calibrate_skimage(t):
    grey, K = truth.skimage_chessboard_views()
    images = [np.repeat(view[..., None], 3, axis=2) for view in grey]   # BGR, as cv2.imread reads a photo of a board
    t.images("scikit-image's chessboard, in two of the poses", view_1=images[1], view_2=images[4])
    try:
        # (squares of 0.3, whose multiples a float step counts unevenly: np.arange(0, 7 * 0.3, 0.3) has 8 entries)
        return judge_calibration(t, images, K, truth.SKIMAGE_PATTERN, square=SKIMAGE_SQUARE)
    except StudentFailure as failure:
        if failure.outcome.kind != "exception":
            raise
        if not _CHANNEL_TROUBLE.search(failure.message):
            raise   # (an error of another kind: the channels are no part of it)
        raise StudentFailure(failure.outcome, f"{failure.message}\n" + measured(
            "These views have 3 channels (BGR), as cv2.imread reads a photo of a board, where the other calibration "
            "check's views are grey: calibrate takes both. ") + GREY_FOR_OPENCV.said(t)) from None


# ================================================================== ext2 lens distortion
ext2 = lab.exercise("ext2", "Extension: lens distortion", functions=["distort_points(points, dist)"])
# No forbid: the sheet asks to simulate lens distortion, not to write the model by hand, so
# cv2.projectPoints of (x, y, 1) with a zero pose and K = I is a right answer (docs/authors/fairness.md).

DIST_EXAMPLE = np.array([-0.28, 0.09, 0.0015, -0.002, -0.015])


def judge_distortion(t: Trial, pts, dist, show=False):
    what = f"distort_points(points, dist={format_matrix(dist)})"
    expected = truth.distort_truth(pts, dist)
    got = t.call("distort_points", pts, dist)
    if show and isinstance(got, np.ndarray) and got.shape == expected.shape:
        t.svg("normalised points: ideal, OpenCV's distortion, yours", svg_points(
            {"undistorted": pts, "OpenCV (truth)": expected, "yours": got}, lines=list(zip(expected, got))))
    judge_points(t, what, got, expected, truth.distortion_mistakes(pts, dist), tolerance=1e-7,
                 mistake_tolerance=1e-6, probe=points_probe(t, "distort_points"))


@ext2.check("distort_points matches OpenCV's model (cv2.projectPoints) on a grid", points=4)
def distortion_grid(t):
    xs, ys = np.meshgrid(np.linspace(-0.6, 0.6, 7), np.linspace(-0.45, 0.45, 5))
    pts = np.column_stack([xs.ravel(), ys.ravel()])
    judge_distortion(t, pts, DIST_EXAMPLE, show=True)


@ext2.check("distort_points for any coefficients", points=3)
def distortion_property(t):
    def holds(seed):
        rng = np.random.default_rng(seed)
        # (as far out as a wide-angle lens sees, x = X / Z up to 1.1: the model holds past the unit circle too)
        pts = rng.uniform(-1.1, 1.1, size=(12, 2))
        dist = rng.uniform([-0.4, -0.2, -0.01, -0.01, -0.1], [0.4, 0.2, 0.01, 0.01, 0.1])
        # (any coefficients: a lens may have some of them 0 -- one tangential term without the other)
        dist[rng.random(5) < 0.3] = 0.0
        judge_distortion(t, pts, dist)

    t.for_all(seeds, holds, max_examples=12,
              describe=lambda s: f"points = uniform(-1.1, 1.1, (12, 2)), dist random (some of its coefficients 0), "
                                 f"from seed {s}")


# ================================================================== the API's conventions
# Each point alone, as among many (one row (1, 3) gives one row (1, 2); a (3,) point is judged by
# the checks above), and a grey image answered in grey.
conventions.point_by_point(ex2, "project_with_intrinsics", lambda: (_example_camera()[0], truth.points_in_front(41, n=6)),
                           rows=(1,), described="K, points")
conventions.point_by_point(ex3, "project", lambda: _photo_scene()[1:], rows=(1,), described="P, points")
conventions.point_by_point(ext2, "distort_points", lambda: (truth.points_in_front(42, n=6)[:, :2] / 10.0, DIST_EXAMPLE),
                           described="points, dist")
conventions.point_by_point(ex1, "pinhole_project", lambda: (truth.points_in_front(40, n=6), 500.0),
                           described="points, f=500", one_row=False)   # its (1, 3) row is judged against the truth
conventions.keeps_grey(ex5, "project_onto_image", _photo_scene, described="image, P, points")
conventions.not_judged(
    "rows", project_focal_lengths="its answer is (F, N, 2): the points are its second axis",
    simulate_aperture="its rays are random: the same point among many draws other rays",
    project_onto_image="its image shows every point drawn; its points are judged with project's",
    draw_points="its answer is an image")
WHOLE_K = np.array([[400.0, 0.0, 160.0], [0.0, 410.0, 120.0], [0.0, 0.0, 1.0]])
WHOLE_P = WHOLE_K @ np.array([[0.0, -1.0, 0.0, 1.0], [1.0, 0.0, 0.0, -2.0], [0.0, 0.0, 1.0, 30.0]])   # R: 90 degrees


def _whole_points(seed: int, n: int = 6) -> np.ndarray:
    """``n`` points in front of the camera, of whole coordinates (depths 20 to 100)."""
    return np.round(truth.points_in_front(seed, n=n) * 10.0)


# Whole numbers given as integers (the sheet's own sample point is (1, 1, 2)) answered as the same
# numbers given as floats: an array made like an integer input holds integers only.
SHEET_SAMPLES = np.array([[1.0, 1.0, 2.0], [3.0, -2.0, 5.0], [0.0, 4.0, 7.0]])   # the sheet's (1, 1, 2) first
conventions.whole_numbers(ex1, "pinhole_project", lambda: (SHEET_SAMPLES, 1.0), described="points, f=1")
conventions.whole_numbers(ex2, "project_with_intrinsics", lambda: (WHOLE_K, _whole_points(43)), described="K, points")
conventions.whole_numbers(ex3, "project", lambda: (WHOLE_P, _whole_points(44)), described="P, points")
conventions.whole_numbers(ex4, "project_focal_lengths", lambda: (_whole_points(45), np.array([0.5, 1.0, 2.0])),
                          described="points, focal_lengths=[0.5, 1, 2]")
conventions.whole_numbers(ex5, "project_onto_image", lambda: (photo("chelsea", (320, 240)), WHOLE_P, _whole_points(47)),
                          described="image, P, points")
conventions.not_judged("integers", draw_points=conventions.DRAWN,
                       simulate_aperture="its rays are random: each call draws other rays",
                       distort_points="its points are normalised coordinates (about -1 to 1): whole numbers are "
                       "no sensible input")
conventions.not_judged(
    "channels", draw_points="judged on grey and colour images against the truth",
    calibrate="its answer is no image; views with 3 channels are judged against the truth")
