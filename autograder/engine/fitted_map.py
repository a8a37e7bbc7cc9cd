"""What map a wrong warp applied: fitted to the student's image, confirmed by warping with it, told against the map
asked.

A warped image that matches no listed mistake is still, most often, the input warped by *some* affine map -- rotated
about another centre, by another angle, scaled the other way. :func:`fitted_affine` finds that map from features
matched between the input and the student's image (ORB, RANSAC), and keeps it only where warping the input with it
reproduces the student's image (a measurement of their output, not a guess); :func:`told` says how it differs from
the map asked, in the terms of a 2D transformation: a fixed point (the centre a rotation or a scaling turns about),
an angle, scale factors, a shift. Where the fixed point is the input's brightness centroid (what ``cv2.moments``
gives), that is said too: the one other centre a student computes from the image.
"""

from __future__ import annotations

import cv2
import numpy as np

from fixtures.images import warp

from .claims import measured

FEATURES = 800        # ORB features per image
REPRODUCED = 6.0      # grey levels: the fitted map's warp within this of the student's image (blurred, mean)
LINEAR_ALIKE = 0.02   # relative: the linear parts agree within this
CENTROID_NEAR = 3.0   # px: a fixed point this close to the brightness centroid is it


def _grey(image) -> np.ndarray:
    image = np.asarray(image)
    return cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image


def fitted_affine(got, source, dsize=None) -> np.ndarray | None:
    """The 2x3 affine map that warps ``source`` into ``got`` (within :data:`REPRODUCED` grey levels over the
    area it covers), or None when features do not match or no affine map reproduces the image."""
    got, source = np.asarray(got), np.asarray(source)
    if got.dtype != np.uint8 or source.dtype != np.uint8 or min(got.shape[:2]) < 32:
        return None
    orb = cv2.ORB_create(FEATURES)
    k1, d1 = orb.detectAndCompute(_grey(source), None)
    k2, d2 = orb.detectAndCompute(_grey(got), None)
    if d1 is None or d2 is None or len(k1) < 12 or len(k2) < 12:
        return None
    matches = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(d1, d2)
    if len(matches) < 12:
        return None
    src = np.float32([k1[m.queryIdx].pt for m in matches])
    dst = np.float32([k2[m.trainIdx].pt for m in matches])
    A, inliers = cv2.estimateAffine2D(src, dst, method=cv2.RANSAC, ransacReprojThreshold=2.0, maxIters=4000,
                                      confidence=0.999, refineIters=20)
    if A is None or inliers is None or int(inliers.sum()) < 10:
        return None
    apart = _apart(A, got, source)
    if apart is None or apart > REPRODUCED:
        return None
    # (keypoints fix an angle to a few tenths of a degree: 90 taken as radians, 1.57, was fitted as 1.3; the
    # images' own grey levels, aligned from there, fix it to a few hundredths)
    refined = _refined(A, got, source)
    if refined is not None:
        closer = _apart(refined, got, source)
        if closer is not None and closer <= apart:
            return refined
    return A


def _apart(A, got, source) -> float | None:
    """Mean grey levels (of the most different channel, both slightly blurred) between ``got`` and ``source``
    warped by ``A``, over the area the warp covers; None when it covers less than a tenth of the frame."""
    size = (got.shape[1], got.shape[0])
    mine = warp(source, A, size)
    covered = warp(np.full(source.shape[:2], 255, np.uint8), A, size, interpolation=cv2.INTER_NEAREST) > 0
    covered = cv2.erode(covered.astype(np.uint8), np.ones((7, 7), np.uint8)) > 0
    if covered.sum() < 0.1 * covered.size:
        return None
    apart = np.abs(cv2.GaussianBlur(mine.astype(np.float32), (0, 0), 1.0)
                   - cv2.GaussianBlur(got.astype(np.float32), (0, 0), 1.0))
    apart = apart.max(axis=2) if apart.ndim == 3 else apart
    return float(apart[covered].mean())


REFINED_PIXELS = 640 * 480   # sources refined on their grey levels at most this large (the checks' images are smaller)


def _refined(A, got, source) -> np.ndarray | None:
    """``A`` refined on the images' grey levels (cv2.findTransformECC from ``A``, over the source's pixels
    ``A`` puts inside ``got``'s frame, a few pixels in from its edges: the frame's fill is no content), or None
    when it does not converge."""
    if source.shape[0] * source.shape[1] > REFINED_PIXELS:   # (the time of an explanation stays bounded)
        return None
    template, moved = _grey(source).astype(np.float32), _grey(got).astype(np.float32)
    h, w = template.shape
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)
    x, y = A[0, 0] * xs + A[0, 1] * ys + A[0, 2], A[1, 0] * xs + A[1, 1] * ys + A[1, 2]
    margin = 4
    inside = ((x >= margin) & (x <= moved.shape[1] - 1 - margin)
              & (y >= margin) & (y <= moved.shape[0] - 1 - margin)).astype(np.uint8)
    if inside.sum() < 0.1 * inside.size:
        return None
    criteria = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 60, 1e-6)
    try:
        _, W = cv2.findTransformECC(template, moved, A.astype(np.float32), cv2.MOTION_AFFINE, criteria, inside, 5)
    except cv2.error:   # (no convergence, or an image without texture)
        return None
    return W.astype(np.float64) if np.isfinite(W).all() else None


def _fixed_point(A) -> np.ndarray | None:
    """The point a map leaves in place, x = L x + t (None when L - I is singular: a pure shift)."""
    L, t = A[:, :2], A[:, 2]
    try:
        if abs(np.linalg.det(np.eye(2) - L)) < 1e-6:
            return None
        return np.linalg.solve(np.eye(2) - L, t)
    except np.linalg.LinAlgError:
        return None


def _similarity(L) -> tuple[float, float] | None:
    """(angle in degrees counter-clockwise as the image shows it, i.e. turning x towards -y; scale) of a rotation
    and uniform scaling, None for another linear map."""
    a, b, c, d = L[0, 0], L[0, 1], L[1, 0], L[1, 1]
    if abs(a - d) > 1e-2 * max(1.0, abs(a)) or abs(b + c) > 1e-2 * max(1.0, abs(b)):
        return None
    return float(np.degrees(np.arctan2(-c, a))), float(np.hypot(a, c))


def _pair(v, digits: int = 0) -> str:
    return f"({v[0]:.{digits}f}, {v[1]:.{digits}f})"   # (a fixed point to the pixel: a small error of the map moves it far)


def centroid_of(source) -> np.ndarray | None:
    moments = cv2.moments(_grey(source).astype(np.float32))
    if moments["m00"] <= 0:
        return None
    return np.array([moments["m10"] / moments["m00"], moments["m01"] / moments["m00"]])


def told(fitted, asked, source) -> str:
    """How the fitted map differs from the map asked (both 2x3), in words after "it is the input ..."; "" when they
    agree (the image's error lies elsewhere) or no difference can be put in a 2D transformation's terms."""
    fitted, asked = np.asarray(fitted, np.float64), np.asarray(asked, np.float64)[:2]
    L, La = fitted[:, :2], asked[:, :2]
    scale = max(1.0, float(np.abs(La).max()))
    if np.abs(L - La).max() <= LINEAR_ALIKE * scale:
        shift = fitted[:, 2] - asked[:, 2]
        if np.abs(shift).max() < 1.5:
            return ""
        mine, theirs = _fixed_point(fitted), _fixed_point(asked)
        if mine is None or theirs is None:
            # (a shift refined on the grey levels, to a tenth of a pixel: (16.5, -18.5) was told (17, -17))
            return f"shifted by about {_pair(fitted[:, 2], 1)} px where ({asked[0, 2]:g}, {asked[1, 2]:g}) is asked"
        said = f"warped about the point {_pair(mine)} (the point it keeps in place), where the map asked keeps {_pair(theirs)}"
        centroid = centroid_of(source)
        if centroid is not None and np.linalg.norm(centroid - mine) <= CENTROID_NEAR:
            said += measured("; that point is the image's brightness centroid (what cv2.moments gives), where the centre "
                             "asked is a point of the frame")
        return said
    mine, theirs = _similarity(L), _similarity(La)
    if mine is not None and theirs is not None:
        parts = []
        if abs(mine[0] - theirs[0]) > 0.5:
            parts.append(f"rotated by about {_degrees(mine[0])} degrees where {_degrees(theirs[0])} is asked")
        if abs(mine[1] - theirs[1]) > 0.01 * theirs[1]:
            parts.append(f"scaled by {mine[1]:.2f} where {theirs[1]:.2f} is asked")
        if parts:
            return " and ".join(parts)
    rows = "; ".join("[" + ", ".join(f"{v:.3g}" for v in row) + "]" for row in fitted)
    asked_rows = "; ".join("[" + ", ".join(f"{v:.3g}" for v in row) + "]" for row in asked)
    return f"warped by the affine map [{rows}], where [{asked_rows}] is asked"


def _degrees(angle: float) -> str:
    """An angle fitted to a picture (refined on its grey levels: a few hundredths of a degree off), to the degree --
    and to a tenth below 10 degrees: 90 taken as radians is 1.6, not 2."""
    return f"{angle:.0f}" if abs(angle) >= 10 else f"{angle:.1f}"
