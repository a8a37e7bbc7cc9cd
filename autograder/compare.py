"""Geometry-aware comparisons and mistake diagnosis, shared by every lab suite.

Everything here is pure NumPy/OpenCV on values already in the grader's process.
"""

from __future__ import annotations

import functools

import cv2
import numpy as np

# Sub-pixel offsets tried when judging warped images, so that other interpolation
# and pixel-centre conventions (x vs x + 0.5) are not penalised.
HALF_PIXEL_OFFSETS = [(dx, dy) for dx in (-0.5, 0.0, 0.5) for dy in (-0.5, 0.0, 0.5)]


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
    if truth is not None:
        try:
            rivals.append(float(distance(got, truth)))
        except (ValueError, np.linalg.LinAlgError):
            pass
    if any(d <= margin * best for d in rivals):
        return None
    return "; or, the same answer here, ".join(names)


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
