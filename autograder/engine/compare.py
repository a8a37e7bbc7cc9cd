"""Geometry-aware comparisons and mistake diagnosis, shared by every lab suite.

Everything here is pure NumPy/OpenCV on values already in the grader's process.
"""

from __future__ import annotations

import functools

import cv2
import numpy as np

from .claims import measured

# Sub-pixel offsets tried when judging warped images, so that other interpolation
# and pixel-centre conventions (x vs x + 0.5) are not penalised.
HALF_PIXEL_OFFSETS = [(dx, dy) for dx in (-0.5, 0.0, 0.5) for dy in (-0.5, 0.0, 0.5)]


# ---------------------------------------------------------------- precision
# Checks judge meaning, not representation. The API pins no float dtype, and float32 is what
# many OpenCV recipes give (cv2.getAffineTransform with float32 points, cv2.findHomography's
# float32 inputs...): float32 is the coarsest legitimate precision, whatever dtype the array
# finally has (float64 arrays may hold float32 work). float16 is not a precision for geometry
# (a 1000 px coordinate is off by up to 0.25 px in it): no tolerance grows for it.
FLOAT32_EPS = float(np.finfo(np.float32).eps)   # 1.19e-7
# float32 work differs from exact arithmetic by its roundings: half an ulp when the result is
# stored, one more for each of a short chain of float32 operations (a 3x3 product, a division,
# a difference of two coordinates). Measured: the reference solutions returning float32 are at
# most 0.3 ulp of the data's magnitude away (tests/test_precision.py grades them); computed
# wholly in float32 from float32 inputs, a few ulps. 16 ulps (1.9e-6 relative) covers that
# and stays far below the nearest named mistake (1e-4 relative and more; the lab tests'
# mistake tables check that every one still loses points).
PRECISION_ULPS = 16


def precision_floor(scale=1.0):
    """The difference float32 work may show in numbers of magnitude ``scale``.

    ``scale`` is the magnitude of the data the result is computed from (for
    ``d = x_l - x_r``, the coordinates, not the disparity): float32 rounds at that scale.
    A number gives a float, an array of scales (one per point) an array.
    """
    floor = PRECISION_ULPS * FLOAT32_EPS * np.abs(np.asarray(scale, dtype=np.float64))
    return float(floor) if floor.ndim == 0 else floor


def at_precision(tolerance, scale=1.0):
    """``tolerance``, raised to :func:`precision_floor` of ``scale`` where it is tighter.

    Every comparison of a returned number with the truth uses this, so no check can ask
    for more digits than float32 holds. Numbers give a float; arrays (per-point
    tolerances or scales) an array.

    >>> at_precision(1e-9, 100.0) == precision_floor(100.0)
    True
    """
    raised = np.maximum(np.asarray(tolerance, dtype=np.float64), precision_floor(scale))
    return float(raised) if raised.ndim == 0 else raised


def magnitude(*values) -> float:
    """The largest finite absolute value in ``values`` (arrays or numbers), at least 1.

    The scale float32 rounds at, for :func:`at_precision`.
    """
    largest = 1.0
    for value in values:
        array = np.asarray(value, dtype=np.float64)
        finite = np.abs(array[np.isfinite(array)])
        if finite.size:
            largest = max(largest, float(finite.max()))
    return largest


def format_apart(value: float, other: float, digits: int = 3, percent: bool = False) -> str:
    """``value`` with the fewest significant digits (``digits`` at least) that never read as ``other``.

    For messages that put a measured figure beside a limit or an expected value: a
    difference that fails a check never prints as the value it was compared with (nor a
    non-zero error as 0). ``percent`` prints a fraction as a percentage.

    >>> format_apart(0.30000001, 0.3)
    '0.30000001'
    >>> format_apart(0.081, 0.0809, digits=2, percent=True)
    '8.1%'
    >>> format_apart(1.0, 0.22, digits=2, percent=True)
    '100%'
    """
    value, other = float(value), float(other)
    factor, suffix = (100.0, "%") if percent else (1.0, "")
    if np.isfinite(value) and 1 <= abs(factor * value) < 1e15:   # every digit before the point: 100%, not 1e+02%
        digits = max(digits, int(np.floor(np.log10(abs(factor * value)))) + 1)
    if np.isfinite(value) and value != other:
        while digits < 17 and f"{factor * value:.{digits}g}" == f"{factor * other:.{digits}g}":
            digits += 1
    return f"{factor * value:.{digits}g}{suffix}"


def format_arrays_apart(got, expected, precision: int = 4) -> tuple[str, str]:
    """Both arrays as text (NumPy's layout), with enough decimals that arrays that differ
    read differently: ``returned [3.5707 9.1915]; expected [3.5707 9.1915]`` cannot happen.

    Arrays of different shapes, or equal ones, are printed at ``precision``.
    """
    got, expected = np.asarray(got, dtype=np.float64), np.asarray(expected, dtype=np.float64)

    def text(array, decimals):
        return np.array2string(array, precision=decimals, suppress_small=True)

    differ = got.shape == expected.shape and not np.array_equal(got, expected, equal_nan=True)
    for decimals in range(precision, 18 if differ else precision + 1):
        shown = text(got, decimals), text(expected, decimals)
        if shown[0] != shown[1]:
            return shown
    if differ:  # every digit NumPy prints agrees: each number's shortest exact form
        return (np.array2string(got, floatmode="unique"), np.array2string(expected, floatmode="unique"))
    return shown


def describe_difference(got, expected, unit: str = "", tolerance: float | None = None) -> str:
    """The largest difference between ``got`` and ``expected`` in words, absolute and relative
    to the largest expected value: ``"up to 4.25e-08 m (6e-08 of the largest value)"``, and
    ``"; at most 1.9e-06 m accepted"`` when ``tolerance`` is given. The figures have the
    digits that tell them from the tolerance; a non-zero difference never reads as 0.
    """
    got, expected = np.asarray(got, dtype=np.float64), np.asarray(expected, dtype=np.float64)
    with np.errstate(invalid="ignore"):
        difference = np.abs(got - expected) if got.shape == expected.shape else np.array([np.inf])
    largest = float(np.nanmax(difference)) if difference.size else 0.0
    if difference.size and np.isnan(difference).any():
        largest = float("nan")
    unit = f" {unit}" if unit else ""
    limit = 0.0 if tolerance is None else tolerance
    text = f"up to {format_apart(largest, limit, 2)}{unit}"
    if np.isfinite(largest) and largest > 0:
        text += f" ({format_apart(largest / magnitude(expected), 0.0, 2)} of the largest value)"
    if tolerance is not None:
        text += f"; at most {format_apart(tolerance, largest, 2)}{unit} accepted"
    return text


def same_to_precision(got, expected, relative: float = 1e-7) -> bool:
    """The same answer up to the precision the student computes in (``relative`` of the answer's largest finite
    entry, at least float32's rounding for float32 answers: a product summed in another order by BLAS), NaN where
    NaN is. Two calls of one function, or one point alone and among many, answer alike by this."""
    got, expected = np.asarray(got), np.asarray(expected)
    eps = max([np.finfo(a.dtype).eps for a in (got, expected) if a.dtype.kind == "f"], default=0.0)
    rtol = max(relative, 16 * float(eps))
    got, expected = got.astype(np.float64), expected.astype(np.float64)
    return got.shape == expected.shape and bool(np.allclose(got, expected, rtol=rtol, atol=rtol * answer_scale(expected),
                                                           equal_nan=True))


def answer_scale(answer) -> float:
    """The scale an answer's precision is measured against: its largest finite entry's size, at least 1."""
    answer = np.asarray(answer, dtype=np.float64)
    finite = np.isfinite(answer)
    return max(1.0, float(np.abs(answer[finite]).max())) if finite.any() else 1.0


# ---------------------------------------------------------------- matrices
def projective_distance(a, b) -> float:
    """Distance between two projective quantities (H, F, E, P), up to scale and sign.

    Both are scaled to unit Frobenius norm; the smaller of ``|a - b|`` and
    ``|a + b|`` is returned (0 = same, about 1.41 = unrelated).

    >>> projective_distance(np.eye(3), -2 * np.eye(3))
    0.0
    """
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    if a.shape != b.shape:
        raise ValueError(f"shapes differ: {a.shape} vs {b.shape}")
    na, nb = np.linalg.norm(a), np.linalg.norm(b)
    if na == 0 or nb == 0 or not (np.isfinite(na) and np.isfinite(nb)):
        return float("inf")
    a, b = a / na, b / nb
    return float(min(np.linalg.norm(a - b), np.linalg.norm(a + b)))


def max_abs_error(got, expected) -> float:
    got = np.asarray(got, dtype=np.float64)
    expected = np.asarray(expected, dtype=np.float64)
    if got.shape != expected.shape:
        return float("inf")
    return float(np.max(np.abs(got - expected))) if got.size else 0.0


SAME_ANSWER = "; or, the same answer here, "   # joins mistakes that answer an input alike


def closest(got, candidates: dict, distance, tolerance: float, truth=None, margin: float = 3.0):
    """The name of the mistake that explains ``got``, when exactly one does; else None.

    ``candidates`` maps a mistake ("tx and ty swapped") to the answer that
    mistake produces on the same input. A mistake is named only when the match
    is unambiguous: its answer is within ``tolerance`` of ``got``, and ``margin``
    times closer than the answer of any other mistake and than ``truth`` (when
    given). Mistakes that give the same answer here cannot be told apart: they
    are named together ("A; or, the same answer here, B").

    Never guessing is the point: a wrong name misleads more than none, and the
    caller then says what is measurably wrong instead.
    """
    scored = []
    for name, answer in candidates.items():
        try:
            d = float(distance(got, answer))
        except (ValueError, np.linalg.LinAlgError):
            continue
        if np.isfinite(d):
            scored.append((d, name, answer))
    if not scored:
        return None
    scored.sort(key=lambda item: item[0])
    best, name, answer = scored[0]
    if not best <= tolerance:
        return None
    names, rivals = [name], []
    for d, other, other_answer in scored[1:]:
        if _same_answer(distance, answer, other_answer, best):
            names.append(other)
        else:
            rivals.append(d)
    for rival in (truth, _nothing_like(answer)):
        if rival is not None:
            try:
                rivals.append(float(distance(got, rival)))
            except (ValueError, TypeError, np.linalg.LinAlgError):
                pass
    if any(d <= margin * best for d in rivals):
        return None
    return SAME_ANSWER.join(names)


def _nothing_like(answer):
    """Zeros of ``answer``'s form, a rival every numeric name must beat: a mistake whose answer is
    nearly zero (x = X / (f Z) with f = 1000) would otherwise be named for any answer of zeros (a focal
    length of 0). None where ``answer`` is not a numeric array or is itself all zeros (that mistake is
    "nothing returned", and is told by its own answer)."""
    if not isinstance(answer, np.ndarray) or answer.dtype.kind not in "iuf" or not answer.size \
            or not np.any(answer):
        return None
    return np.zeros_like(answer)


def _same_answer(distance, first, second, resolution: float) -> bool:
    """Whether two mistakes' answers are indistinguishable at ``resolution``."""
    try:
        return float(distance(first, second)) <= max(resolution, 1e-12)
    except (ValueError, np.linalg.LinAlgError):
        return False


# ---------------------------------------------------------------- images
def blurred_difference(got, expected, valid, sigma: float = 1.0) -> float:
    """Mean absolute difference on ``valid`` after a light blur (max over channels).

    The blur makes the measure tolerant of interpolation choices while keeping it
    sensitive to content being in the wrong place.
    """
    a = cv2.GaussianBlur(np.asarray(expected, np.float32), (0, 0), sigma)
    b = cv2.GaussianBlur(np.asarray(got, np.float32), (0, 0), sigma)
    diff = largest_channel(cv2.absdiff(a, b))
    valid = np.asarray(valid, dtype=bool)
    return float(diff[valid].mean()) if valid.any() else 0.0


WRAP_SHARE = 0.05     # of the region's pixels, at least, changed by the wrap
WRAP_AGREEMENT = 0.8  # of which, at least, as the wrap predicts (within WRAP_TOLERANCE grey levels; seams and edges differ otherwise)
WRAP_TOLERANCE = 12


def wrapped_around(got, expected, valid) -> int:
    """k when ``got`` is ``expected`` computed in uint8 arithmetic that wrapped round: a sum of k uint8
    images (k = 2 to 4) taken modulo 256 before its division by k, so that every pixel whose sum passed
    255 lost 256 / k (a blend ``(a + b) // 2`` of two bright images: 200 and 200 give 72, not 200);
    0 otherwise. Judged where ``valid`` (a boolean mask), on the pixels that differ from ``expected``: at
    least :data:`WRAP_SHARE` of them, and nearly all of those as the wrap predicts."""
    got = np.asarray(got, np.float64)
    expected = np.asarray(expected, np.float64)
    valid = np.asarray(valid, dtype=bool)
    if got.shape != expected.shape or got.shape[:2] != valid.shape or not valid.any():
        return 0
    if got.ndim == 3:
        valid = np.repeat(valid[..., None], got.shape[2], axis=2)
    g, e = got[valid], expected[valid]
    differing = np.abs(g - e) > WRAP_TOLERANCE
    if differing.mean() < WRAP_SHARE:
        return 0
    # (the region may hold pixels no sum made -- where one image alone is seen -- and right there: only
    # the pixels that differ are judged, nearly all of which the wrap must explain)
    for k in (2, 3, 4):
        predicted = e - (256.0 / k) * np.floor(k * e / 256.0 + 1e-9)
        explained = (predicted < e - WRAP_TOLERANCE) & (np.abs(g - predicted) <= WRAP_TOLERANCE)
        if explained[differing].mean() >= WRAP_AGREEMENT:
            return k
    return 0


def wrapped_around_words(k: int) -> str:
    """What :func:`wrapped_around`'s k says, in words (for "the image ...")."""
    return measured(f"is what a sum of {k} uint8 images gives when it wraps round: every pixel whose sum passes 255 "
                    f"starts again at 0 before the division by {k} (it loses {256 // k} grey levels): add in a wider "
                    "type (astype(np.float32) or np.uint16), then convert back")


def largest_channel(image: np.ndarray) -> np.ndarray:
    """(H, W, C) -> (H, W): the largest value over the channels (a 2-D image as it is).

    A channel at a time: NumPy's reduction over a last axis of length 3 is ten times slower.
    """
    if image.ndim != 3:
        return image
    return functools.reduce(np.maximum, (image[..., channel] for channel in range(image.shape[2])))


def warp_error(got, source, M, dsize=None, good_enough: float = 0.0, inside=None) -> float:
    """How far ``got`` is from ``source`` warped by ``M`` (best sub-pixel offset).

    Parameters
    ----------
    got : (H, W[, 3]) array
        The student's image, already checked for shape.
    source : (h, w[, 3]) uint8 array
    M : (2, 3) affine or (3, 3) homography
        The true source-to-output map.
    dsize : (width, height), optional
    good_enough : float
        Stop trying sub-pixel offsets once an error this small is found.
    inside : (H, W) bool array, optional
        The output pixels judged, when the caller has them already
        (``fixtures.images.coverage(M, ...)[0]``).

    Returns
    -------
    float
        Mean blurred grey-level difference over the output pixels that are
        well inside the warped source (about 1-3 for a correct warp, tens for
        a wrong one); infinite when almost nothing of the source is in view.
    """
    from fixtures.images import as_homography, coverage, warp

    H = as_homography(M)
    if inside is None:
        inside, _ = coverage(H, source.shape, dsize)
    if inside.sum() < 0.05 * inside.size:
        return float("inf")  # (a wrong map may send the image almost entirely out of view)
    best = np.inf
    for dx, dy in sorted(HALF_PIXEL_OFFSETS, key=lambda o: abs(o[0]) + abs(o[1])):  # (0, 0) first
        shifted = np.array([[1, 0, dx], [0, 1, dy], [0, 0, 1]]) @ H
        best = min(best, blurred_difference(got, warp(source, shifted, dsize), inside))
        if best <= good_enough:
            break
    return best


# A warp's pixel convention (the centre of a pixel or its corner at (0, 0)) moves the image by at most
# half a pixel, which warp_error forgives; a whole pixel more is a slip (a border added and not taken
# back, a shift split into int() and a remainder). Measured (benchmarks/whole_pixel_shift.py, the lab 7
# and 8 checks' images and maps): legitimate warps -- bilinear, nearest, cubic, Lanczos, a float32 map,
# either half-pixel convention -- fit the expected image moved by a whole pixel at best 1.56 times
# worse than within half a pixel; warps off by a whole pixel fit it at least 1.45 times better (0.68).
WHOLE_PIXEL_OFFSETS = [(dx, dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1) if dx or dy]
WHOLE_PIXEL_RATIO = 0.75   # the moved fit at most this share of the best fit within half a pixel
WHOLE_PIXEL_FLOOR = 0.3    # grey levels: a fit within half a pixel nearer than this is exact


DETAIL_KEPT = 0.4   # of the warp's fine detail any interpolation keeps (benchmarks/detail_kept.py)


def detail_kept(got, expected, inside) -> float:
    """The fine detail of ``got`` as a share of ``expected``'s (bilinear): the mean squared Laplacian of the grey
    image over ``inside`` eroded by 2 px (the border, where the warp meets the fill, left out). Measured on four
    photographs and four affine maps: nearest, cubic and Lanczos keep 1.1 to 4.1 times bilinear's, cv2.resize with
    INTER_AREA shrinking by half 0.49 to 0.70 (by a quarter down to 0.38: the judges measure no map that shrinks the
    area by a quarter or more);
    a 3x3 Gaussian blur after the warp 0.09 to 0.32. 1.0 where there is too little to measure."""
    def energy(image):
        grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
        return cv2.Laplacian(grey.astype(np.float32), cv2.CV_32F) ** 2
    kept = cv2.erode(np.asarray(inside, np.uint8), np.ones((5, 5), np.uint8)) > 0
    if kept.sum() < 400:
        return 1.0
    wanted = float(energy(np.asarray(expected))[kept].mean())
    return float(energy(np.asarray(got))[kept].mean()) / wanted if wanted > 1.0 else 1.0


def whole_pixel_shift(got, source, M, dsize=None, inside=None) -> tuple[int, int, float, float] | None:
    """``(dx, dy, within, moved)`` when ``got`` is ``source`` warped by ``M`` and then moved by a whole
    pixel (dx, dy in -1, 0, 1), as measured by the mean blurred difference: ``moved`` from the warp so
    moved, ``within`` from the nearest warp within half a pixel (:func:`warp_error`); None when no
    whole-pixel move fits clearly better (:data:`WHOLE_PIXEL_RATIO`)."""
    from fixtures.images import as_homography, coverage, warp

    H = as_homography(M)
    if inside is None:
        inside, _ = coverage(H, source.shape, dsize)
    within = warp_error(got, source, M, dsize, inside=inside)
    # (and a centre taken half a pixel off in both images -- `(w / 2, h / 2)` for a rotation's centre, as
    # OpenCV's tutorial has it -- which moves the output by (I - A) c: a whole pixel for a quarter turn)
    for cx, cy in HALF_PIXEL_OFFSETS:
        if within < WHOLE_PIXEL_FLOOR:
            break
        conjugated = np.array([[1, 0, cx], [0, 1, cy], [0, 0, 1]]) @ H @ np.array([[1, 0, -cx], [0, 1, -cy], [0, 0, 1]])
        within = min(within, blurred_difference(got, warp(source, conjugated, dsize), inside))
    if not np.isfinite(within) or within < WHOLE_PIXEL_FLOOR:
        return None
    moved, dx, dy = min((blurred_difference(got, warp(source, np.array([[1, 0, dx], [0, 1, dy], [0, 0, 1]]) @ H, dsize),
                                            inside), dx, dy) for dx, dy in WHOLE_PIXEL_OFFSETS)
    return (dx, dy, within, moved) if moved < WHOLE_PIXEL_RATIO * within else None


def fill_fraction(got, outside) -> float:
    """Fraction of the pixels that should be black fill (``outside``) that are not 0."""
    outside = np.asarray(outside, dtype=bool)
    if not outside.any():
        return 0.0
    pixels = np.asarray(got)
    nonzero = pixels != 0 if pixels.ndim == 2 else np.any(pixels != 0, axis=2)
    return float(nonzero[outside].mean())


# ---------------------------------------------------------------- disparity maps
def bad_pixel_rate(got, truth, threshold: float = 1.0, valid=None) -> float:
    """Fraction of pixels with a valid true disparity where ``got`` is off by more than ``threshold``.

    Parameters
    ----------
    got, truth : (H, W) float arrays
        Disparity maps. ``truth`` is valid where finite and > 0 (and ``valid``, if given).
        A pixel where ``got`` is invalid (NaN, infinite or <= 0) counts as bad.
    threshold : float
        Largest accepted absolute error in pixels.

    Returns
    -------
    float in [0, 1] (1.0 when the shapes differ; 0.0 when no pixel is judged)
    """
    got = np.asarray(got, dtype=np.float64)
    truth = np.asarray(truth, dtype=np.float64)
    if got.shape != truth.shape:
        return 1.0
    judged = np.isfinite(truth) & (truth > 0)
    if valid is not None:
        judged &= np.asarray(valid, dtype=bool)
    if not judged.any():
        return 0.0
    with np.errstate(invalid="ignore"):
        good = np.isfinite(got) & (got > 0) & (np.abs(got - truth) <= threshold)
    return float(1.0 - good[judged].mean())


def nearest_variants(got, candidates: dict, distance) -> dict:
    """Each candidate's answer nearest to ``got``, for candidates given as several answers.

    A mistake's answer may depend on a legitimate textbook choice (rows scaled or not,
    Hartley's normalisation or not): such a candidate is a sequence of answers, and the one
    the student's choice gives is the one nearest to ``got``. Reducing every candidate
    first keeps :func:`closest`'s "same answer" test to the answers actually compared.
    """
    reduced = {}
    for name, answers in candidates.items():
        scored = []
        for answer in answers:
            try:
                scored.append((float(distance(got, answer)), answer))
            except (ValueError, np.linalg.LinAlgError):
                continue
        scored = [(d, answer) for d, answer in scored if np.isfinite(d)]
        if scored:
            reduced[name] = min(scored, key=lambda item: item[0])[1]
    return reduced


def rows_left_out(got, expected, tolerance) -> list[int] | None:
    """The rows of ``expected`` that ``got`` leaves out, when ``got`` is ``expected`` with some of its rows
    removed and the rest in order (each within ``tolerance``: a number, or one per row of ``expected``);
    None otherwise. A function returning fewer rows than it was given points drops some of them: which
    ones tells why (those behind the camera, those not found)."""
    got, expected = np.asarray(got, dtype=np.float64), np.asarray(expected, dtype=np.float64)
    if got.ndim != 2 or expected.ndim != 2 or got.shape[1] != expected.shape[1] or not 0 < len(got) < len(expected):
        return None
    tolerance = np.broadcast_to(np.asarray(tolerance, dtype=np.float64), (len(expected),))
    left, j = [], 0
    for i, row in enumerate(expected):
        if j < len(got) and np.all(np.isfinite(got[j])) and np.linalg.norm(got[j] - row) <= tolerance[i]:
            j += 1
        else:
            left.append(i)
    return left if j == len(got) else None


def rows_left_out_words(left: list[int], expected, kept_where: dict) -> str:
    """What the rows ``left`` out of ``expected`` have in common, of ``kept_where`` (words -> a boolean per
    row: "whose Z is <= 0": the rows it holds for), or which they are."""
    left_set = set(left)
    for words, holds in kept_where.items():
        holds = np.asarray(holds, dtype=bool)
        if all(holds[i] == (i in left_set) for i in range(len(expected))):
            return f"the {len(left)} left out are exactly the ones {words}"
    shown = ", ".join(str(i) for i in left[:8]) + (", ..." if len(left) > 8 else "")
    return f"rows {shown} are left out"
