"""Judgements several lab suites share: a returned matrix, a warped image.

Each judge checks the form of the answer (with messages that name expected and
got), compares it with the truth, and when it is wrong compares it with what the
usual mistakes would give, so the feedback can name the mistake.

A mistake is named only when it is confirmed (:func:`name_mistake`): its answer
reproduces the student's on the failing input *and* on a second input chosen to
tell the candidates apart (a :class:`Probe`, whose student answer is asked for
through ``t.call``). Otherwise the message says what is measurably wrong.

The judges' own sentences are held to the code (issue 35; ``tests/test_judges_coverage.py``):
where, and by how much, an answer is wrong, its shape, its channels, an ignored parameter are
measurements of the student's outputs (a fix they name, "keep the input's channels", is about the
array measured: :func:`~autograder.engine.claims.measured`); the two that ask for code are
Hints (:class:`~autograder.engine.hints.Hint`) -- the black fill (code already passing a border mode is
told the fill comes from elsewhere) and "use the PARAMETER argument" (code that reads the
parameter is told its value has no effect, not that it is fixed). A mistake's name ("it looks
like ...") is a lab's, held where the lab registers it.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass, replace
from typing import Any, Callable

import cv2
import numpy as np

from fixtures.images import as_homography, coverage, warp

from ..sandbox.beginner import RGB_FOR_BGR, channels_reversed, integer_entries
from .checks import SIZE_SWAPPED, StudentFailure, Trial, Verdict, fingerprint, partial, passed
from .claims import calls_any, checklist, from_code, measured, seen_in_code, where_to_look
from .forms import (CHANNEL_COPIED, CHANNELS_FIRST, COLOURS_LOST, UNIT_RANGE_CAST, channel_copied, colours_lost, shape_form,
                    unit_range_cast)
from .hints import (Hint, Predicate, _path, calls, code_of, functions_read, mentions, parameter_flows,
                    size_given_as_shape)
from .compare import (SAME_ANSWER, at_precision, blurred_difference, closest, fill_fraction, format_apart,
                      format_arrays_apart, max_abs_error, projective_distance, rows_left_out, rows_left_out_words,
                      warp_error, whole_pixel_shift, DETAIL_KEPT, detail_kept)
from ..loading.parsing import walk

IMAGE_TOLERANCE = 6.0   # mean blurred grey-level error accepted on the covered area


def _border_constant_by_name(function) -> bool:
    """cv2.BORDER_CONSTANT given by name where it is given (`borderMode=cv2.BORDER_CONSTANT`), not in a place
    of its own (a warp's fifth argument is flags)."""
    return all(any(k.arg == "borderMode" and k.value is node for call in walk(function) if isinstance(call, ast.Call)
                   for k in call.keywords)
               for node in walk(function) if isinstance(node, ast.Attribute) and node.attr == "BORDER_CONSTANT"
               and isinstance(node.value, ast.Name) and node.value.id in ("cv2", "cv"))


# (a border mode passed is "already done" only when it is the constant one: BORDER_REPLICATE is not)
BLACK_FILL_HINT = Hint("use borderMode=cv2.BORDER_CONSTANT, borderValue=0 (black fill)",
                       asks=mentions("cv2.BORDER_CONSTANT"),
                       instead="your code already {found}: " + checklist(
                           "", ("cv2.BORDER_CONSTANT is given by name, borderMode=cv2.BORDER_CONSTANT (given in a "
                                "warp's fifth place, it is taken as flags)",
                                Predicate("gives cv2.BORDER_CONSTANT by name", _border_constant_by_name)),
                           none_left="the pixels with no source pixel are filled elsewhere (borderValue, or what is "
                                     "written into the output afterwards)"))
FILL_TOLERANCE = 0.02   # fraction of should-be-black pixels allowed to be non-zero
# border rules that fill the pixels with no source pixel from the image's own edge
REPEATING_BORDERS = ("BORDER_REPLICATE", "BORDER_REFLECT", "BORDER_REFLECT_101", "BORDER_REFLECT101", "BORDER_WRAP",
                     "BORDER_DEFAULT")


def repeating_border(read) -> str | None:
    """The first border rule of :data:`REPEATING_BORDERS` the code ``read`` names (cv2.BORDER_...), or None."""
    return next((name for name in REPEATING_BORDERS if mentions(f"cv2.{name}").found(read)), None)

# what the pixels with no source pixel hold instead of black, by the border rule that gives them
FILLS = {
    cv2.BORDER_WRAP: measured("wrap around from the opposite side (as np.roll and cv2.BORDER_WRAP do)"),
    cv2.BORDER_REPLICATE: measured("repeat the nearest edge pixel (as cv2.BORDER_REPLICATE does)"),
    cv2.BORDER_REFLECT: measured("mirror the image at its edge (as cv2.BORDER_REFLECT does)"),
    cv2.BORDER_REFLECT_101: measured("mirror the image at its edge (as cv2.BORDER_REFLECT_101 does)"),
}
KEPT_INPUT = measured("still hold the input image (the output started as a copy of it?)")
BORDER_NAMES = {cv2.BORDER_WRAP: "BORDER_WRAP", cv2.BORDER_REPLICATE: "BORDER_REPLICATE",
                cv2.BORDER_REFLECT: "BORDER_REFLECT", cv2.BORDER_REFLECT_101: "BORDER_REFLECT_101"}
def _clips_a_coordinate(function) -> bool:
    """A clip (`np.clip`, `np.minimum`, `np.maximum`) whose bounds are not the range of a pixel value (0 to
    255 or 1): `np.clip(xs, 0, w - 1)` clips a coordinate, `np.clip(values, 0, 255)` a value."""
    def value_bound(node) -> bool:
        return isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and node.value in (0, 1, 255)

    for node in walk(function):
        if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in ("clip", "minimum", "maximum") \
                and _path(node.func).split(".", 1)[0] in ("np", "numpy"):
            bounds = node.args[1:] + [k.value for k in node.keywords if k.arg in ("a_min", "a_max", "min", "max")]
            if bounds and not all(value_bound(b) for b in bounds):
                return True
    return False


CLIPS = Predicate("clips coordinates into the image (np.clip)", _clips_a_coordinate)
# np.interp gives a position outside the samples the first or the last sample, unless left= and right= say
INTERP_EXTENDS = Predicate("calls np.interp without left= and right=", lambda function: any(
    isinstance(node, ast.Call) and _path(node.func) in ("np.interp", "numpy.interp")
    and not {"left", "right"} <= {k.arg for k in node.keywords} and len(node.args) < 5 for node in walk(function)))
ROLL_HINT = from_code("np.roll moves the pixels that leave one side back in on the other: set the rows and "
                      "columns it brought round to 0, or warp with cv2.warpAffine (black fill)")


# ---------------------------------------------------------------- naming, confirmed
@dataclass(frozen=True)
class Probe:
    """A second input, independent of the failing one, on which the candidate mistakes
    answer differently: a name stands only if the student's answer there is the named
    mistake's answer too.

    Parameters
    ----------
    key : str
        Names the input within the check: the student is asked once per trial
        (:meth:`autograder.engine.checks.Trial.probe`).
    answer : callable () -> object
        The student's answer on the probe input, through ``t.call`` (a failing call, or
        an answer not of the documented form, confirms nothing).
    candidates : callable () -> dict
        What each candidate mistake answers there, under the same names as on the
        failing input.
    truth : object, optional
        The right answer there. A mistake that answers it rightly (its effect does not
        show on this input) is confirmed by a right answer: the probe then tells it
        from the mistakes that do show.
    distance : callable (answer, candidate) -> float, optional
        Filled in by the judge that uses the probe when None.
    tolerance : float, optional
        How close the student's answer must be to the named mistake's (filled in by
        the judge when None).
    alike : callable (candidate, candidate) -> bool, optional
        Whether two candidates answer alike (default: closer than the match itself).
    """

    key: str
    answer: Callable[[], Any]
    candidates: Callable[[], dict]
    truth: Any = None
    distance: Callable | None = None
    tolerance: float | None = None
    alike: Callable | None = None

    def completed(self, distance, tolerance, alike=None) -> "Probe":
        """This probe, with the judge's distance, tolerance and likeness where it has none."""
        return replace(self, distance=self.distance or distance,
                       tolerance=tolerance if self.tolerance is None else self.tolerance,
                       alike=self.alike or alike)


def confirm(t: Trial, named: str | None, probe: Probe | None, margin: float = 3.0) -> str | None:
    """The part of ``named`` (a mistake, or several that answered the failing input alike,
    joined as :func:`~autograder.engine.compare.closest` joins them) that ``probe`` confirms; None
    when nothing is confirmed, or there is no probe: a name is never a guess.

    A named mistake is confirmed when the student's answer on the probe input is within
    the probe's tolerance of that mistake's answer there, and ``margin`` times closer to
    it than to every other candidate (and the truth) answering differently.
    """
    if not named or probe is None:
        return None
    answer = t.probe(probe.key, probe.answer)
    if answer is None:
        return None
    candidates = dict(probe.candidates())

    def apart(a, b) -> float:
        try:
            with np.errstate(all="ignore"):
                d = float(probe.distance(a, b))
        except (ValueError, TypeError, ArithmeticError, np.linalg.LinAlgError, cv2.error):
            return float("inf")
        return d if d == d else float("inf")

    scored = {name: apart(answer, candidate) for name, candidate in candidates.items()}
    kept = [name for name in named.split(SAME_ANSWER) if scored.get(name, np.inf) <= probe.tolerance]
    if not kept:
        return None
    best = min(scored[name] for name in kept)
    ours = candidates[kept[0]]

    def alike(other) -> bool:
        if probe.alike is not None:
            try:
                return bool(probe.alike(ours, other))
            except (ValueError, TypeError, ArithmeticError, np.linalg.LinAlgError, cv2.error):
                return False
        # Answers closer than a tenth of the tolerance cannot be told apart at this tolerance
        # (a mistake that answers rightly here differs from the truth by rounding only).
        return apart(ours, other) <= max(best, 0.1 * probe.tolerance, 1e-12)

    rivals = [scored[name] for name, candidate in candidates.items() if name not in kept and not alike(candidate)]
    if probe.truth is not None and not alike(probe.truth):
        rivals.append(apart(answer, probe.truth))
    if any(d <= margin * best for d in rivals):
        return None
    return SAME_ANSWER.join(seen_in_code(t, kept))


CORRESPONDENCES_LEFT_OUT = "some correspondences are left out of the system solved"


def name_correspondences_left_out(t: Trial, what: str, errors, unknowns: str, exact: float = 1e-6,
                                  missed: float = 1e-3) -> None:
    """Fail naming the exact correspondences an estimate misses (``errors``: each one's distance in pixels)
    while it satisfies every other one to ``exact``: they are not in its system (measured, whatever the code:
    a loop or a row count over n - 1, the first or last point skipped). ``unknowns``: what the rows left
    leave undetermined ("P's 11 unknowns up to scale"). At most a third of them: more is no estimate."""
    errors = np.asarray(errors, np.float64)
    errors = np.where(np.isfinite(errors), errors, np.inf)
    off = np.flatnonzero(errors > missed)
    if not 0 < len(off) <= len(errors) // 3 or errors[errors <= missed].max(initial=0.0) > exact:
        return
    n = len(errors)
    which = "the last one" if list(off) == [n - 1] else "the first one" if list(off) == [0] else "some"
    t.fail(measured(f"{what}: the answer fits {n - len(off)} of the {n} correspondences exactly and misses "
                    f"{which} (point {', '.join(str(i) for i in off)}, by {errors[off].max():.3g} px): "
                    f"{CORRESPONDENCES_LEFT_OUT} (each correspondence gives two rows: {2 * (n - len(off))} rows for "
                    f"{unknowns} leave it undetermined)."), mistake=CORRESPONDENCES_LEFT_OUT)


def name_mistake(t: Trial, got, candidates: dict, distance, tolerance: float, truth=None,
                 probe: Probe | None = None, margin: float = 3.0) -> str | None:
    """The mistake that explains ``got`` on the failing input (:func:`~autograder.engine.compare.closest`)
    and again on the ``probe``'s input (:func:`confirm`); None otherwise."""
    named = closest(got, candidates, distance, tolerance, truth=truth, margin=margin)
    if named and probe is not None:
        probe = probe.completed(distance, tolerance)
    return confirm(t, named, probe, margin)


def format_matrix(matrix, precision: int = 4) -> str:
    return np.array2string(np.asarray(matrix, float), precision=precision, suppress_small=True)


def digits_apart(value: float, limit: float, digits: int = 3) -> str:
    """``value`` with enough significant digits that it never reads as ``limit``
    (:func:`autograder.engine.compare.format_apart`)."""
    return format_apart(value, limit, digits)


def over_variants(distance, ndim: int):
    """``distance`` between answers of ``ndim`` dimensions, either of which may be a stack of
    textbook variants (one more dimension): the distance of the nearest pair."""
    def nearest(a, b) -> float:
        firsts = list(a) if np.ndim(a) > ndim else [a]
        seconds = list(b) if np.ndim(b) > ndim else [b]
        return min(float(distance(x, y)) for x in firsts for y in seconds)
    return nearest


def call_probe(t: Trial, function: str, args=(), kwargs=None, *, candidates, truth=None,
               shape=None, kind: str | None = "iuf", **fields) -> Probe:
    """A :class:`Probe` whose student answer is ``function(*args, **kwargs)`` (an array of
    ``shape``, when given; any value otherwise). ``candidates`` is a dict or a callable
    giving one; ``fields`` are the other :class:`Probe` fields."""
    kwargs = dict(kwargs or {})

    def answer():
        value = t.call(function, *args, **kwargs)
        if shape is None:
            return value
        return t.expect_array(value, function, shape=shape, kind=kind, finite=True)

    chosen = candidates if callable(candidates) else (lambda: candidates)
    return Probe(f"{function}/{fingerprint(args, kwargs)}", answer, chosen, truth, **fields)


def judge_matrix(t: Trial, what: str, got, expected, mistakes=None, shape=(3, 3),
                 up_to_scale: bool = False, rtol: float = 1e-6, probe: Probe | None = None) -> np.ndarray:
    """Compare a returned matrix with the truth; name the mistake when one fits.

    Parameters
    ----------
    what : str
        The call, as the student reads it: ``"rotation_matrix(30)"``.
    got : object
        What the student returned.
    expected : array
        The true matrix.
    mistakes : dict of str -> array, optional
        What each usual mistake would return.
    up_to_scale : bool
        Compare projective matrices up to scale and sign.
    rtol : float
        Tolerance, relative to the largest entry (or to unit norm, up to scale), raised to
        float32's precision where it is tighter (:func:`autograder.engine.compare.at_precision`).
    probe : Probe, optional
        A second input whose answer confirms a mistake that ``mistakes`` names
        (its truth required; :func:`call_probe` builds one). Without it no mistake is named.
    """
    listed = type(got).__name__ if isinstance(got, (list, tuple)) else ""
    got = t.expect_array(got, what, shape=shape, kind="iuf", finite=True)
    scale = 1.0 if up_to_scale else max(1.0, float(np.abs(expected).max()))
    distance = projective_distance if up_to_scale else max_abs_error
    tolerance = at_precision(rtol * scale, scale)
    if distance(got, expected) <= tolerance and listed:
        # (right numbers in a Python list: the API's matrices are arrays, and a caller's `M.shape`, `M[:2, 2]`
        # or `M @ x` fails on a list)
        t.fail(measured(f"{what} returned a Python {listed} of rows, not a NumPy array: matrices are float arrays "
                        f"(np.array(...)); a caller's `M.shape`, `M[:2, 2]` or `M @ x` fails on a {listed}"),
               mistake="a matrix returned as a Python list")
    if distance(got, expected) <= tolerance:
        if got.dtype.kind in "iu":   # (right here, as whole-number arguments give: any fraction is cut off)
            t.fail(f"{what} returned an integer matrix (dtype {got.dtype}): matrices are float arrays, and "
                   "an integer one cuts off every fraction written into it or computed with it",
                   mistake="an integer matrix: its fractions are cut off")
        return got
    integers = integer_entries(got, expected)
    if integers:
        t.fail(f"{what} is wrong: {integers}", mistake="an integer matrix: its fractions are cut off")
    named = closest(got, mistakes or {}, distance, 1e3 * rtol * scale, truth=expected)
    if named and probe is not None:
        probe_scale = 1.0 if up_to_scale else max(1.0, float(np.abs(np.asarray(probe.truth, float)).max()))
        mistake = confirm(t, named, probe.completed(distance, 1e3 * rtol * probe_scale))
        if mistake:
            t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    shown, wanted = format_arrays_apart(got, expected)
    last = _last_row_only(got, expected, tolerance) if not up_to_scale else ""
    if last:
        t.fail(f"{what} is wrong: {last}.\nIt returned\n{shown}\nexpected\n{wanted}", mistake=LAST_ROW)
    t.fail(f"{what} is wrong {where_matrices_differ(got, expected, up_to_scale)}.\n"
           f"It returned\n{shown}\nexpected\n{wanted}")


LAST_ROW = "the homogeneous matrix's last row is not [0, 0, 1]"


def _last_row_only(got, expected, tolerance: float) -> str:
    """The sentence for a homogeneous 2D transform right in its first two rows and wrong in its last
    (which must be [0, 0, 1]: a point's third coordinate stays 1), else ``""``. Measured."""
    expected = np.asarray(expected, np.float64)
    if expected.shape != (3, 3) or got.shape != (3, 3) or not np.allclose(expected[2], (0, 0, 1)) \
            or max_abs_error(got[:2], expected[:2]) > tolerance or max_abs_error(got[2], expected[2]) <= tolerance:
        return ""
    row = ", ".join(f"{v:g}" for v in np.asarray(got[2], np.float64))
    return measured(f"its first two rows are right and its last row is [{row}], where a 2D transformation's "
                    "homogeneous matrix ends with [0, 0, 1] (so that a point's third coordinate stays 1)")


def where_points_differ(got, expected, tolerance: float, names=("x", "y")) -> str:
    """Which points, and which coordinates of them, are wrong, in words.

    ``got`` and ``expected`` are (N, D) arrays; a coordinate is wrong when it is
    off by more than ``tolerance`` (or not finite). ``names`` name the columns.
    """
    got, expected = np.asarray(got, np.float64), np.asarray(expected, np.float64)
    with np.errstate(invalid="ignore"):
        wrong = ~(np.abs(got - expected) <= tolerance)
    rows = np.flatnonzero(wrong.any(axis=1))
    if rows.size == 0:
        return "nowhere beyond the tolerance"
    columns = [name for name, bad in zip(names, wrong.any(axis=0)) if bad]
    which = "every point" if rows.size == len(got) else \
        f"{rows.size} of {len(got)} points (the first is row {rows[0]})"
    order = _rows_permuted(got, expected, tolerance)
    if order is not None:
        first = int(rows[0])
        return measured(f"for {which}: your rows are the expected ones in another order (your row {first} is the "
                        f"expected row {order[first]}), where row i belongs to input i")
    if len(columns) < len(names):
        return f"for {which}, in {' and '.join(columns)} only"
    return f"for {which}"


def _rows_permuted(got, expected, tolerance: float, largest: int = 400):
    """For each of ``got``'s rows the row of ``expected`` it equals (within ``tolerance``), where the rows are
    those of ``expected`` in another order, each once; None otherwise, or for sets too large to compare pairwise
    (400 rows: a table of 160 000 distances)."""
    if got.shape != expected.shape or got.ndim != 2 or not 2 <= len(got) <= largest \
            or not np.isfinite(got).all() or not np.isfinite(expected).all():
        return None
    apart = np.abs(got[:, None, :] - expected[None, :, :]).max(axis=2)
    order = apart.argmin(axis=1)
    if not (apart[np.arange(len(got)), order] <= float(np.max(tolerance))).all() or len(np.unique(order)) != len(order):
        return None
    return order


_ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth")


def where_matrices_differ(got, expected, up_to_scale: bool = False) -> str:
    """Where the error of ``got`` lies, in words: "in its third row", "in every entry"...

    The entries carrying the error are those at least a tenth of the largest
    entry error (up to scale, both matrices at unit norm and the same sign), or
    of the largest error relative to its row's size (a camera matrix's third row,
    of entries near 1 beside rows of hundreds, wrong by half is wrong too); the
    rows or the columns holding them are named, whichever are fewer.
    """
    got, expected = np.asarray(got, np.float64), np.asarray(expected, np.float64)
    if got.ndim == 1:
        got, expected = got[None, :], expected[None, :]
    if up_to_scale and np.linalg.norm(got) > 0 and np.linalg.norm(expected) > 0:
        got, expected = got / np.linalg.norm(got), expected / np.linalg.norm(expected)
        if np.linalg.norm(got + expected) < np.linalg.norm(got - expected):
            got = -got
    error = np.abs(got - expected)
    sizes = np.abs(expected).max(axis=-1, keepdims=True) if expected.ndim == 2 else np.abs(expected)
    relative = error / np.maximum(sizes, 1e-12 * max(float(np.abs(expected).max()), 1e-300))
    wrong = (error >= 0.1 * error.max()) | ((relative >= 0.1 * relative.max()) & (relative >= 1e-6))
    # (a place is named only where every entry outside it is right, to a thousandth of the largest: a
    # homography's small entries wrong by less than a tenth of its translation's error are wrong still --
    # 06l 08/02 was told "wrong in entries [0, 2], [1, 1], [2, 0]", 06o 08/02 "in its second and third
    # columns", every entry printed apart: then every entry not right is where the error lies)
    right = error <= 1e-3 * max(float(np.abs(expected).max()), 1e-300)
    if not (wrong | right).all():
        wrong = ~right
    if wrong.all() or got.ndim != 2 or max(got.shape) > len(_ORDINALS):
        return "in every entry"
    if wrong.sum() == 1:
        (row, column), = zip(*np.nonzero(wrong))
        return f"in entry [{row}, {column}] only" if got.shape[0] > 1 else f"in entry [{column}] only"
    rows, columns = np.flatnonzero(wrong.any(axis=1)), np.flatnonzero(wrong.any(axis=0))
    # (the rows or the columns holding them, whichever are fewer -- or whichever are not all: a camera matrix
    # wrong in every row but its last column right is wrong "in its first, second and third columns")
    by_rows = len(columns) == got.shape[1] if (len(rows) == got.shape[0]) != (len(columns) == got.shape[1]) \
        else len(rows) <= len(columns)
    kind, where, count = ("row", rows, got.shape[0]) if by_rows else ("column", columns, got.shape[1])
    if len(where) == count:  # spread over every row and every column
        if wrong.sum() > 3:
            return "in every row and every column"
        return "in entries " + ", ".join(f"[{i}, {j}]" for i, j in zip(*np.nonzero(wrong)))
    names = [_ORDINALS[i] for i in where]
    listed = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
    return f"in its {listed} {kind}{'s' if len(names) > 1 else ''}"


def entries_misplaced(got, expected, rtol: float = 1e-6) -> str:
    """Where a matrix holds the expected numbers, each once, but some in other places ("[0, 2] holds the
    value that belongs in [1, 0], ..."): the unknowns of a solved vector put into the matrix in another order
    than the equations use them. "" otherwise (entries that are not all distinct say nothing)."""
    got, expected = np.asarray(got, np.float64), np.asarray(expected, np.float64)
    if got.shape != expected.shape or got.ndim != 2 or not np.isfinite(got).all() or not np.isfinite(expected).all():
        return ""
    flat_got, flat_expected = got.ravel(), expected.ravel()
    scale = max(np.abs(flat_expected).max(), 1e-300)
    close = np.abs(flat_got[:, None] - flat_expected[None, :]) <= rtol * scale
    if not (close.sum(axis=0) == 1).all() or not (close.sum(axis=1) == 1).all():
        return ""   # (not a permutation of distinct values)
    source = close.argmax(axis=1)   # the expected entry each of got's holds
    moved = [(i, int(j)) for i, j in enumerate(source) if i != j]
    if not moved:
        return ""
    columns = got.shape[1]
    return ", ".join(f"[{i // columns}, {i % columns}] holds the value that belongs in [{j // columns}, {j % columns}]"
                     for i, j in moved)


def warp_probe(t: Trial, function: str, source, M, mistakes: dict, args=None, kwargs=None,
               dsize=None) -> Probe:
    """A :class:`Probe` for image warps: the student's ``function(*args, **kwargs)`` (``args``
    by default ``(source,)``: pass the map too when the function takes it) compared with ``source`` warped by each mistake's map
    (``mistakes``: name -> map) and by the true map ``M``, on the output of size ``dsize``
    (the input's by default)."""
    width, height = dsize or (source.shape[1], source.shape[0])
    expected_shape = (height, width) + source.shape[2:]
    args = (source,) if args is None else tuple(args)
    kwargs = dict(kwargs or {})

    def answer():
        got = t.call(function, *args, **kwargs)
        if not (isinstance(got, np.ndarray) and got.shape == expected_shape and got.dtype == np.uint8):
            return None
        return got

    return Probe(f"{function}/{fingerprint(args, kwargs)}", answer, lambda: mistakes, M,
                 distance=lambda got, map_: warp_distance(got, source, map_, dsize),
                 tolerance=IMAGE_TOLERANCE, alike=_same_map)


RESIZED = "the image is resized rather than warped into a frame of the input's size"


def _resized(t: Trial, got, source, M) -> str:
    """For an answer of the wrong size, :data:`RESIZED` when its size is the input's scaled by M's
    scale factors (with the code's cv2.resize call when it has one), else ""."""
    if not isinstance(got, np.ndarray) or got.ndim < 2:
        return ""
    A = np.asarray(M, np.float64)
    h, w = source.shape[:2]
    sx, sy = np.hypot(A[0, 0], A[1, 0]), np.hypot(A[0, 1], A[1, 1])
    if abs(got.shape[0] - h * sy) > 1.5 or abs(got.shape[1] - w * sx) > 1.5 or (abs(sx - 1) < 1e-3 and abs(sy - 1) < 1e-3):
        return ""
    resizes = calls("cv2.resize").found(code_of(t).reachable(functions_read(t)))
    # measured: the size is the input's times M's scales; the call only where the code has it
    return measured(f"{RESIZED} (content that leaves the frame is cut off)") + \
        (from_code("; your code calls cv2.resize") if resizes else "")


def judge_warp(t: Trial, what: str, got, source, M, mistakes=None, dsize=None, show=True,
               probe: Probe | None = None) -> Verdict:
    """Judge an image warped by ``M`` (affine or homography) against the oracle.

    Full credit when the covered area matches (any sensible interpolation or
    pixel-centre convention) and the uncovered area is black; half when only the
    fill is wrong; otherwise the mistake is named when one of ``mistakes``
    (name -> the map that mistake applies) explains the image, and explains the
    student's image on the ``probe``'s input too (:func:`warp_probe` builds one).
    """
    width, height = dsize or (source.shape[1], source.shape[0])
    expected_shape = (height, width) + source.shape[2:]
    expected = warp(source, M, dsize)
    inside, outside = coverage(M, source.shape, dsize)
    if isinstance(got, np.ndarray) and show:
        t.compare_images(what, source, expected, got, valid=inside | outside,  # a map only for the same shape
                         caption="the difference map is grey where the border is not judged"
                         if got.shape == expected_shape else "")
    grey = colours_lost(got, [source]) if isinstance(got, np.ndarray) and got.shape == expected_shape else ""
    if grey and not colours_lost(expected, [source]):
        copied = channel_copied(got, expected, inside)
        if copied:
            t.fail(f"{what}: {copied}.", mistake=CHANNEL_COPIED)
        t.fail(f"{what}: {grey}.", mistake=COLOURS_LOST)
    if isinstance(got, np.ndarray) and got.shape != expected_shape:
        if got.shape[:2] == expected_shape[1::-1] and height != width:   # (a square frame shows no swap)
            read = size_given_as_shape(code_of(t), functions_read(t))
            t.fail(f"{what} returned shape {got.shape}; expected {expected_shape}: "
                   "width and height are swapped (shapes are (rows, columns), dsize is (width, height))"
                   + (f": your code {read}" if read else ""), mistake=SIZE_SWAPPED)
        if got.shape[:2] == expected_shape[:2]:
            form = shape_form(got.shape, expected_shape)   # grey in, grey out, or BGR in, BGR out
            t.fail(f"{what} returned shape {got.shape}; expected {expected_shape}: "
                   + (form.sentence if form else measured("keep the input's channels")),
                   mistake="the channels are not kept")
        resized = "" if dsize else _resized(t, got, source, M)
        if resized:
            t.fail(f"{what} returned shape {got.shape}, the input's size times the transform's scale; expected "
                   f"{expected_shape}: {resized}", mistake=RESIZED)
        form = shape_form(got.shape, expected_shape)
        if form is not None and (got.ndim < len(expected_shape) or form.mistake == CHANNELS_FIRST):
            # (an axis lost, or the channels' axis moved first, not a size: what the form tells, not the size rule)
            t.fail(f"{what} returned shape {got.shape}; expected {expected_shape}: {form.sentence}", mistake=form.mistake)
        size_rule = "" if dsize else ": warps keep the input's size (content that leaves the frame is cut off)"
        t.fail(f"{what} returned shape {got.shape}; expected {expected_shape}{size_rule}")
    got = t.expect_array(got, what, shape=expected_shape, dtype=np.uint8)
    error = warp_error(got, source, M, dsize, good_enough=IMAGE_TOLERANCE / 2, inside=inside)
    if error <= IMAGE_TOLERANCE:
        moved = whole_pixel_shift(got, source, M, dsize, inside)
        if moved is not None:
            dx, dy, within, nearer = moved
            return partial(0.5, measured(
                f"{what}: the image content is right but a whole pixel off: it is the expected image moved by "
                f"{_pixels(dx, 'right', 'left')}{' and ' if dx and dy else ''}{_pixels(dy, 'down', 'up')} "
                f"({nearer:.1f} grey levels from that, {within:.1f} from the expected image at best).") + " "
                + where_to_look(measured(
                    "Where a pixel is (its centre or its corner at (0, 0)) moves an image by half a pixel at most; "
                    "look for a pixel added or lost on the way: a border added and not taken back, a shift split "
                    "into a whole part and a remainder that do not add up, a pixel grid counted from 1.")),
                mistake=WHOLE_PIXEL_OFF)
        detail = detail_kept(got, expected, inside) if _keeps_its_scale(M) else 1.0
        if detail < DETAIL_KEPT:
            return partial(0.5, measured(
                f"{what}: the image content is in place but blurred: it keeps {detail:.0%} of the fine detail the warp "
                f"keeps (any interpolation keeps at least half of it), as when the image is smoothed on the way"),
                mistake=BLURRED)
        nonblack = fill_fraction(got, outside)
        if nonblack > FILL_TOLERANCE:
            held = fill_held(got, source, M, dsize, outside)
            read = code_of(t).reachable(functions_read(t))
            rolls = held == FILLS[cv2.BORDER_WRAP] and calls("np.roll").found(read)
            rule = next((name for border, name in BORDER_NAMES.items() if held == FILLS[border]
                         and mentions(f"cv2.{name}").found(read)), None)
            # (coordinates clipped into the image all find a source pixel, the edge's: a replicated fill
            # with no border rule asking for it comes from there)
            clipped = held == FILLS[cv2.BORDER_REPLICATE] and not rule and CLIPS.found(read)
            extended = held == FILLS[cv2.BORDER_REPLICATE] and not rule and not clipped and INTERP_EXTENDS.found(read)
            if held == KEPT_INPUT and not rule and mentions("cv2.BORDER_TRANSPARENT").found(read):
                rule = "BORDER_TRANSPARENT"   # (it leaves the output's pixels as they were: the input's, here)
            cause = from_code(f" Your code uses cv2.{rule}, which fills them so.") if rule else \
                from_code(f" Your code {clipped}: a coordinate clipped into the image samples the edge pixel, so "
                          "no pixel is left without a source for the fill to make black.") if clipped else \
                from_code(" Your code calls np.interp without left= and right=: a position outside the samples gets "
                          "the first or the last sample, the edge pixel; pass left=0, right=0 for a black fill.") \
                if extended else ""
            return partial(0.5, f"{what}: the image content is right, but {nonblack:.0%} of the "
                                "pixels with no source pixel are not black" + (f": they {held}." if held else ".")
                           + cause,
                           hint=ROLL_HINT if rolls else "" if clipped or extended else BLACK_FILL_HINT.said(t),
                           mistake="the fill is not black")
        return passed(f"mean difference {error:.1f} grey levels on the covered area")
    if channels_reversed(got, expected):
        t.fail(f"{what} is wrong: {RGB_FOR_BGR}.", mistake="the colour channels are reversed (RGB for BGR)")
    cast = unit_range_cast(got, expected)
    if cast and _makes_unit_range(code_of(t)):
        t.fail(f"{what}: {cast}.", mistake=UNIT_RANGE_CAST)
    holes = forward_holes(got, expected, inside)
    if holes:
        t.fail(measured(f"{what}: {holes:.0%} of the pixels inside the warped image are black, scattered among "
                        "right ones (holes), where the image has content: it looks like "
                        f"{FORWARD_MAPPED}. Send each output pixel back through the inverse map and sample the "
                        "source there (cv2.warpAffine and cv2.warpPerspective do)."), mistake=FORWARD_MAPPED)
    explained = []  # the mistakes whose map explains the image (a name only when one does)
    for mistake, wrong_M in (mistakes or {}).items():
        try:
            if _explains(got, source, wrong_M, dsize):
                explained.append((mistake, wrong_M))
        except np.linalg.LinAlgError:
            continue
    if explained and all(_same_map(explained[0][1], wrong_M) for _, wrong_M in explained):
        mistake = confirm(t, SAME_ANSWER.join(name for name, _ in explained), probe)
        if mistake:
            t.fail(f"{what} is wrong: it looks like {mistake}.", mistake=mistake)
    other = _other_map(got, source, M, dsize)
    if other:
        t.fail(f"{what} differs from the expected image by {error:.0f} grey levels on average: " + measured(
               f"an affine map fitted to your image reproduces it: it is the input {other}"))
        # (what the image shows, not a cause: the error model and the repairs still look for the slip that makes it)
    t.fail(f"{what} differs from the expected image by {error:.0f} grey levels on average "
           "(see the pictures).")


def _other_map(got, source, M, dsize) -> str:
    """For an affine ``M``: how the affine map that reproduces ``got`` differs from it (:mod:`.fitted_map`), else ""."""
    from . import fitted_map

    M = np.asarray(M, np.float64)
    if M.shape == (3, 3) and not np.allclose(M[2], (0.0, 0.0, 1.0)):
        return ""
    fitted = fitted_map.fitted_affine(got, source, dsize)
    return "" if fitted is None else fitted_map.told(fitted, M[:2], source)


def _keeps_its_scale(M) -> bool:
    """Whether ``M`` is affine and shrinks the area by less than a quarter (|det| >= 0.75; a shear keeps it): where
    it shrinks, averaging interpolations (cv2.resize's INTER_AREA, legitimate for shrinking) keep less fine detail
    than bilinear (0.38 at a quarter of the size), and the detail kept tells a blur from them no more
    (benchmarks/detail_kept.py)."""
    M = np.asarray(M, np.float64)
    if M.shape == (3, 3) and not np.allclose(M[2], (0.0, 0.0, 1.0)):
        return False
    return abs(float(np.linalg.det(M[:2, :2]))) >= 0.75


WHOLE_PIXEL_OFF = "the image is a whole pixel off"
BLURRED = "the image is blurred (smoothed beyond any interpolation)"


def _pixels(offset: int, positive: str, negative: str) -> str:
    return "" if not offset else f"1 px {positive if offset > 0 else negative}"


FORWARD_MAPPED = ("the image is mapped forward: each source pixel is sent to the output and copied there, "
                  "so the output pixels no source pixel lands on stay black")
HOLES = 0.02         # share of the covered area black where the truth is not (a 1.2x zoom mapped forward: 30%)
HOLES_AROUND = 12.0  # grey levels: the rest is the warp, sampled at the nearest pixel


def forward_holes(got, expected, inside) -> float:
    """The share of the covered area (``inside``, away from its edge) that ``got`` leaves black where the
    truth has content, when those pixels are scattered holes among right ones (most have a non-black
    neighbour, and the non-black pixels are the truth's, nearest-neighbour sampled); 0 otherwise."""
    inner = cv2.erode(np.asarray(inside, np.uint8), np.ones((5, 5), np.uint8)).astype(bool)
    if inner.sum() < 100:
        return 0.0
    level = lambda image: np.asarray(image, np.float32).max(axis=2) if image.ndim == 3 else np.asarray(image, np.float32)  # noqa: E731
    black, content = level(got) == 0, level(expected) > 20
    holes = black & content & inner
    share = float(holes.sum() / max((content & inner).sum(), 1))
    if share < HOLES:
        return 0.0
    # (a black block -- a region cut off, a shifted image -- is no hole: most holes touch a filled pixel)
    neighbours = cv2.blur((~black).astype(np.float32), (3, 3)) * 9
    scattered = float(np.mean(neighbours[holes] >= 3))
    filled = inner & ~black
    apart = np.abs(np.asarray(got, np.float32) - np.asarray(expected, np.float32))
    apart = apart.max(axis=2) if apart.ndim == 3 else apart
    return share if scattered >= 0.8 and filled.any() and float(apart[filled].mean()) <= HOLES_AROUND else 0.0


def fill_held(got, source, M, dsize, outside) -> str:
    """What ``got``'s pixels with no source pixel (``outside``) hold, in words for "they ...": a
    border rule's fill (:data:`FILLS`: wrapped, replicated, mirrored), the input's own pixels, one
    constant grey level; "" when none fits at 90% of them (within 24 grey levels: the fill
    is interpolated at the border too)."""
    outside = np.asarray(outside, dtype=bool)
    if not outside.any():
        return ""
    got = np.asarray(got, dtype=np.float32)
    width, height = dsize or (source.shape[1], source.shape[0])

    def fit(candidate) -> tuple[float, float]:
        """(the share of the pixels within 24 levels, minus their mean distance): the larger, the better."""
        apart = np.abs(got - np.asarray(candidate, dtype=np.float32))
        apart = (apart.max(axis=2) if apart.ndim == 3 else apart)[outside]
        return float(np.mean(apart <= 24)), -float(apart.mean())
    # (the best fit of them all, not the first that fits: an image written into the input's own array keeps
    # the input there, which a smooth photo's replicated edge may resemble at 90% too)
    candidates = [(fit(cv2.warpPerspective(source, as_homography(M), (width, height), borderMode=border)), words)
                  for border, words in FILLS.items()]
    if source.shape[:2] == (height, width):
        candidates.append((fit(source), KEPT_INPUT))
    best, words = max(candidates, key=lambda candidate: candidate[0])
    if best[0] >= 0.9:
        return words
    levels = got[outside]
    if np.ptp(levels) <= 2:
        return f"are all {format_apart(float(levels.mean()), 0.0, 1)} (a constant fill, not 0)"
    return ""


def _explains(got, source, wrong_M, dsize) -> bool:
    """Whether ``got`` is ``source`` warped by ``wrong_M`` (a mistake's map)."""
    return warp_distance(got, source, wrong_M, dsize) <= IMAGE_TOLERANCE


def warp_distance(got, source, M, dsize=None) -> float:
    """How far ``got`` is from ``source`` warped by the map ``M`` (mean blurred grey levels).

    A wrong homography may send most of the image behind the camera (w < 0), where
    :func:`fixtures.images.coverage` sees nothing but OpenCV still samples (it divides
    by w whatever its sign): such a map is judged where its own warp has content
    (infinite when it has almost none).
    """
    error = warp_error(got, source, M, dsize, good_enough=IMAGE_TOLERANCE)
    if np.isfinite(error):
        return error
    expected = warp(source, M, dsize)
    content = expected != 0 if expected.ndim == 2 else np.any(expected != 0, axis=2)
    inner = np.zeros_like(content)  # away from the content's edges (interpolation differs there)
    inner[2:-2, 2:-2] = content[:-4, 2:-2] & content[4:, 2:-2] & content[2:-2, :-4] & content[2:-2, 4:]
    if inner.mean() < 0.05:
        return float("inf")
    return blurred_difference(got, expected, inner)


def _same_map(first, second) -> bool:
    """Whether two pixel maps (affine or homography) are the same map, up to scale."""
    return projective_distance(as_homography(first), as_homography(second)) < 1e-6


def _same_result(first, second) -> bool:
    """Whether two returned values are exactly equal (arrays, or tuples/lists of arrays)."""
    if isinstance(first, (tuple, list)) and isinstance(second, (tuple, list)):
        return len(first) == len(second) and all(_same_result(a, b) for a, b in zip(first, second))
    if not (isinstance(first, np.ndarray) and isinstance(second, np.ndarray)):
        return False
    if first.shape != second.shape or first.dtype.kind not in "biuf" or second.dtype.kind not in "biuf":
        return False
    return bool(np.array_equal(first, second, equal_nan=first.dtype.kind == "f" == second.dtype.kind))


def parameter_ignored(call, parameter: str, values, informative=None) -> bool:
    """Whether ``call(**{parameter: value})`` gives exactly the same, non-constant result for
    both ``values`` (False when a call fails, or when ``informative(result)`` says the
    result could not show the parameter anyway)."""
    try:
        first, second = (call(**{parameter: value}) for value in values)
    except StudentFailure:
        return False
    if informative is not None and not informative(first):
        return False
    return same_informative_result(first, second)


def same_informative_result(first, second) -> bool:
    """``first`` and ``second`` are exactly the same and not constant: a constant output
    ignores every parameter (or comes from a degenerate computation), so it shows no
    parameter's mistake."""
    constant = isinstance(first, np.ndarray) and (
        first.size == 0 or np.ptp(np.nan_to_num(first.astype(float))) == 0)
    return _same_result(first, second) and not constant


def reads(name: str) -> Predicate:
    """The parameter ``name`` read (``ast.Load``) in a function that has it: a parameter used, whatever
    becomes of its value (``k = 5`` before it still reads ``k`` afterwards). A helper's own parameter of
    the same name is another value (`scale` calling `scaling_matrix(1.5, 1.5)`, whose `sy` is its own)."""
    def test(function) -> bool:
        arguments = function.args
        if name not in {a.arg for a in (*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs)}:
            return False
        return any(isinstance(node, ast.Name) and node.id == name and isinstance(node.ctx, ast.Load)
                   for node in walk(function))
    return Predicate(f"reads {name}", test)


def unused_parameter_hint(parameter: str) -> Hint:
    """The hint for ``parameter`` measured as ignored: "use it instead of a fixed value" only to code
    that never reads it; code that reads it is told its value has no effect on the result."""
    return Hint(f"use the {parameter} argument instead of a fixed value", asks=reads(parameter),
                instead=f"your code reads {parameter}, yet the result does not change with it: follow where "
                        "its value goes (is it overwritten before it is used, or used where it has no effect?)")


OVERWRITTEN = from_code("a parameter is overwritten before it is read")


def _ignored(t: Trial, what: str, parameter: str, values, result: str, mistake: str = ""):
    first_value, second_value = values
    same = f"{what}: {parameter}={first_value!r} and {parameter}={second_value!r} give the same {result}"
    code = code_of(t)
    if any(parameter_flows(code, function, parameter) for function in functions_read(t)):
        # The code uses it: on these inputs its value decides nothing because of something upstream (a
        # loop that stops after one sample, a model chosen otherwise). That is no parameter ignored, and
        # saying so points at the right comparison (the blind set 1202i's 08/05): the caller's own
        # diagnoses go on, the error model's repairs among them.
        return
    overwritten = next((found for found in (_overwritten_before_read(code, function, parameter)
                                            for function in functions_read(t)) if found), None)
    if overwritten:
        line, statement = overwritten
        t.fail(f"{same}: {parameter} is ignored. " + from_code(
            f"Your code sets `{statement}` (line {line}) before it reads {parameter}: the value the caller gives "
            "is never used."), mistake=OVERWRITTEN)
    # (read in the functions called, not in their helpers: `scale` passing 1.5 to scaling_matrix(sx, sy)
    # does not read its own sy because the helper reads a parameter of that name)
    hint = unused_parameter_hint(parameter)
    read = hint.asks.found([code.functions[function] for function in functions_read(t) if function in code.functions])
    t.fail(f"{same}: {parameter} is ignored.",
           hint=hint.neutral(read) if read else hint.text,
           mistake=mistake or f"{parameter} is ignored")


def _overwritten_before_read(code, function: str, parameter: str) -> tuple[int, str] | None:
    """(line, statement) of a plain assignment of ``parameter`` in ``function``'s own body, at its top level,
    before any line that reads it (a leftover `levels = 4`); None otherwise."""
    node = code.functions.get(function)
    if node is None or parameter not in {a.arg for a in (*node.args.posonlyargs, *node.args.args, *node.args.kwonlyargs)}:
        return None
    reads = [n.lineno for n in walk(node) if isinstance(n, ast.Name) and n.id == parameter
             and isinstance(n.ctx, ast.Load)]
    for statement in node.body:
        if isinstance(statement, ast.Assign) and any(isinstance(target, ast.Name) and target.id == parameter
                                                     for target in statement.targets) \
                and parameter not in {n.id for n in walk(statement.value) if isinstance(n, ast.Name)}:
            written = " ".join(ast.unparse(statement).split())
            return (statement.lineno, written if len(written) <= 80 else written[:77] + "...") \
                if not reads or min(reads) >= statement.lineno else None
    return None


def judge_parameter_used(t: Trial, what: str, call, parameter: str, values, result: str = "result",
                         informative=None):
    """Fail naming ``parameter`` as ignored when two values of it give exactly the same result.

    The output alone cannot show an ignored parameter, so the student's function
    is called again, ``call(**{parameter: value})`` for each of the two
    ``values``. For checks that already fail: passing work never pays for the
    probe. Returns quietly when the results differ, or when a call fails, or when
    ``informative(result)`` is False (a result that cannot show the parameter).
    """
    if parameter_ignored(call, parameter, values, informative):
        _ignored(t, what, parameter, values, result)


NOT_DETERMINISTIC = "two calls with the same arguments give different answers"


def judge_default_is_the_apis(t: Trial, what: str, call, parameter: str, api_value,
                              result: str = "result") -> Verdict:
    """A check of its own that ``parameter``'s default is the API's ``api_value``: ``call()`` (the
    parameter left out) and ``call(**{parameter: api_value})`` must give the same result (a function
    whose answers vary for one input cannot be judged so: call it where they do not). Named from the
    student's def when it writes another literal (:mod:`autograder.engine.defaults_given`)."""
    left_out, given = call(), call(**{parameter: api_value})
    if _same_result(left_out, given) or not isinstance(left_out, (np.ndarray, tuple, list)):
        return passed(f"{what} with {parameter} left out gives what {parameter}={api_value!r} gives")
    # (the answers vary from call to call: the default is not what makes them differ)
    if not (_same_result(given, call(**{parameter: api_value})) and _same_result(left_out, call())):
        empty = calls_any("np.empty_like", "np.empty").found(code_of(t).reachable(functions_read(t)))
        t.fail(measured(f"{what} with {parameter}={api_value!r}, called twice, gives two different {result}s: the "
                        "answer depends on more than the arguments")
               + (from_code(f"; your code {empty}, whose entries hold whatever was in memory until they are "
                            "written: is every one written before it is read?") if empty else "."),
               mistake=NOT_DETERMINISTIC)
    from . import defaults_given

    said = defaults_given.sentence_for(t, parameter)
    t.fail(f"{what} with {parameter} left out gives another {result} than with {parameter}={api_value!r}, the "
           f"API's default" + (f": {said}." if said else measured(": keep the API's default.")),
           mistake=defaults_given.MISTAKE if said else "")


# Code that makes an image of values in [0, 1]: a division by 255, skimage's float conversions, and its
# transforms, which return floats in [0, 1] unless told preserve_range=True.
_UNIT_RANGE_CALLS = {"img_as_float", "img_as_float32", "img_as_float64", "warp", "rotate", "rescale", "resize",
                     "swirl", "warp_polar", "resize_local_mean", "AffineTransform"}


def _makes_unit_range(code) -> bool:
    """Whether the student's code (any function of it: the image may be made in a helper) makes values in
    [0, 1] that a cast to uint8 would floor to 0: a black or binary image from code that never does has
    another cause (a warp matrix that sends every pixel away). Without their code, True."""
    functions = list(code.functions.values())
    if not functions:
        return True
    for node in (n for fn in functions for n in walk(fn)):
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) and isinstance(node.right, ast.Constant) \
                and node.right.value in (255, 255.0):
            return True
        if isinstance(node, ast.Call) and _path(node.func).rsplit(".", 1)[-1] in _UNIT_RANGE_CALLS \
                and not any(k.arg == "preserve_range" for k in node.keywords):
            return True
    return False


def judge_parameter_changes_result(t: Trial, what: str, call, parameter: str, values,
                                   result: str = "result", mistake: str = "") -> Verdict:
    """A check of its own that ``parameter`` is used: ``call(**{parameter: value})`` for the two
    ``values`` must not give exactly the same result.

    For parameters whose effect the quality checks cannot see (a block size fixed at
    its default still matches well). Unlike :func:`judge_parameter_used`, a failing
    call fails the check (a stub is "not implemented", never "uses its parameter"). ``mistake``: the name
    told for an ignored parameter (default "<parameter> is ignored").
    """
    first, second = (call(**{parameter: value}) for value in values)
    if same_informative_result(first, second):
        _ignored(t, what, parameter, values, result, mistake)
    first_value, second_value = values
    return passed(f"{parameter}={first_value!r} and {parameter}={second_value!r} give different {result}s")


BLANK_CANVAS = "the drawing is made on a new blank image, not on a copy of the input"
# (code that copies the image already: a copy made, and another array drawn on or returned)
BLANK_CANVAS_HINT = Hint("draw on a copy of the input, image.copy()", asks=calls(".copy") | calls("np.copy"),
                         instead="your code copies the image ({found}): is that copy what is drawn on and returned, "
                                 "rather than a new array such as np.zeros_like(image)?")


def blank_canvas(got, image, away) -> str:
    """What a drawing says of the input where nothing is drawn (``away``: those pixels): when it kept
    none of the input's own there -- one value everywhere, where the input varies -- the sentence naming
    a drawing made on a new blank image (``np.zeros_like(image)``); else ``""``. Measured only."""
    if not isinstance(got, np.ndarray) or got.shape[:2] != image.shape[:2] or not away.any():
        return ""
    mine = got[away].reshape(-1, got.shape[2] if got.ndim == 3 else 1).astype(np.int16)
    theirs = image[away].reshape(-1, image.shape[2] if image.ndim == 3 else 1).astype(np.int16)
    if theirs.shape[1] != mine.shape[1]:
        theirs = np.repeat(theirs.mean(axis=1, keepdims=True), mine.shape[1], axis=1)
    kept = float(np.mean(np.all(np.abs(mine - theirs) <= 25, axis=1)))
    if kept > 0.2 or np.ptp(mine, axis=0).max() > 2 or np.ptp(theirs, axis=0).max() < 50:
        return ""
    value = tuple(int(v) for v in mine[0]) if mine.shape[1] > 1 else int(mine[0, 0])
    return (f"away from what is drawn every pixel is {value}, where the input image has its own "
            f"({kept:.0%} of them kept): it looks like {BLANK_CANVAS}")


def _depths(P, X) -> np.ndarray:
    """Each point's depth in the camera ``P`` (its sign: in front or behind), whatever P's scale and sign."""
    P = np.asarray(P, np.float64)
    return np.column_stack([X, np.ones(len(X))]) @ P[2] * np.sign(np.linalg.det(P[:, :3]))


def _null_vector_w(P1, P2, pts1, pts2, normalised: bool) -> np.ndarray:
    """The fourth entry of each point's null vector as np.linalg.svd gives it, for the textbook system of
    two rows per view (``x p3 - p1``, ``y p3 - p2``), its rows scaled to unit length or not: its sign is
    SVD's choice, not the point's."""
    P1, P2 = np.asarray(P1, np.float64), np.asarray(P2, np.float64)
    x1, x2 = pts1[:, :2] / pts1[:, 2:], pts2[:, :2] / pts2[:, 2:]
    A = np.stack([x1[:, :1] * P1[2] - P1[0], x1[:, 1:] * P1[2] - P1[1],
                  x2[:, :1] * P2[2] - P2[0], x2[:, 1:] * P2[2] - P2[1]], axis=1)
    if normalised:
        A = A / np.linalg.norm(A, axis=2, keepdims=True)
    with np.errstate(all="ignore"):
        return np.linalg.svd(A)[2][:, -1, 3]


def fail_if_front_points_not_given(t: Trial, what: str, got, expected, P1, P2, pts1=None, pts2=None):
    """A triangulation (labs 11 and 12) of the right shape giving NaN or infinite rows: which, and where
    every one of them is in front of both cameras, that they are (no point there is left without an
    answer: a test of "behind the camera" that marks them is the slip, not the points)."""
    if not (isinstance(got, np.ndarray) and got.dtype.kind == "f" and got.shape == np.shape(expected)):
        return
    lost = ~np.all(np.isfinite(got), axis=1)
    expected = np.asarray(expected, dtype=np.float64)
    if not lost.any():
        return
    front = (_depths(P1, expected) > 0) & (_depths(P2, expected) > 0)
    if front[lost].all():
        # (what the points given NaN share, of the tests a student writes for "behind": P's third row alone,
        # whose sign is the depth's only for P at a positive scale; the disparity's sign; Z in camera 1)
        homogeneous = np.column_stack([expected, np.ones(len(expected))])
        third = [homogeneous @ np.asarray(P, np.float64)[2] for P in (P1, P2)]
        projected1 = (homogeneous @ np.asarray(P1, np.float64).T)
        projected2 = (homogeneous @ np.asarray(P2, np.float64).T)
        # (the points as given: the sign of a null vector SVD picks turns with the smallest rounding difference)
        given1 = projected1 if pts1 is None else np.column_stack([np.reshape(pts1, (-1, 2)), np.ones(len(expected))])
        given2 = projected2 if pts2 is None else np.column_stack([np.reshape(pts2, (-1, 2)), np.ones(len(expected))])
        with np.errstate(divide="ignore", invalid="ignore"):
            disparity = projected1[:, 0] / projected1[:, 2] - projected2[:, 0] / projected2[:, 2]
        rules = {"the third coordinate of P X is <= 0 in one of the cameras (P's third row alone gives the depth "
                 "only for a P of positive scale: the depth is that coordinate times the sign of det(P[:, :3]), "
                 "and P is defined up to a scale, sign included)": (third[0] <= 0) | (third[1] <= 0),
                 "the disparity x1 - x2 is <= 0 (its sign says which side camera 2 is on, not whether a point "
                 "is in front: the depth in each camera does)": ~(disparity > 0),
                 "Z <= 0 in the world frame (camera 1's frame only when camera 1 is [I | 0])": expected[:, 2] <= 0}
        # (the sign of the null vector's w, of the textbook system with its rows scaled or not: SVD's own choice)
        null_w = "the fourth entry w of the SVD's null vector is negative (SVD gives v and -v alike: its sign " \
                 "says nothing of the depth, which is w's sign times the sign of the third coordinate of P X)"
        rules[null_w] = _null_vector_w(P1, P2, given1, given2, False) < 0
        fitting = [words for words, rule in rules.items() if np.array_equal(rule, lost)]
        if not fitting and np.array_equal(_null_vector_w(P1, P2, given1, given2, True) < 0, lost):
            fitting = [null_w]
        # (two tests that mark the same points on this input: neither is told -- another input tells them apart)
        shared = fitting[0] if len(fitting) == 1 else ""
        t.fail(measured(f"{what} returned NaN or infinite values for {lost.sum()} of the {len(got)} points, and "
                        f"each of those {lost.sum()} is in front of both cameras (a positive depth in each): NaN "
                        "is for a point behind a camera; " + (f"they are exactly the points where {shared}" if shared
                                                              else "look at the test that decides which points are "
                                                                   "behind")),
               mistake="points in front of both cameras given NaN")


def fail_if_points_left_out(t: Trial, what: str, got, expected, P1):
    """A triangulation (labs 11 and 12) returning fewer rows than correspondences, each the answer
    (``expected``, its rows) of one of them in order: which are left out, and what they share."""
    if not isinstance(got, np.ndarray):
        return
    expected = np.asarray(expected, dtype=np.float64)
    depth = np.linalg.norm(expected, axis=1)
    left = rows_left_out(got, expected, 1e-3 * np.maximum(depth, 1e-9))
    if left:
        w = np.column_stack([expected, np.ones(len(expected))]) @ np.asarray(P1, np.float64)[2] \
            * np.sign(np.linalg.det(np.asarray(P1, np.float64)[:, :3]))
        t.fail(f"{what} returned {len(got)} rows for {len(expected)} correspondences: " + measured(
            "each row is the answer of one correspondence, in order, and " + rows_left_out_words(
                left, expected, {"whose Z is <= 0": expected[:, 2] <= 0, "behind camera 1 (negative depth)": w <= 0})
            + ": return one row per correspondence, whatever its depth (a wrong match too: its point is its answer)"),
            mistake="some correspondences' points are left out")
