"""Lab 11 - two-view geometry.

Written defensively: every function converts its inputs to fresh float64
arrays (so lists, float32 arrays and non-contiguous views all work and the
caller's arrays are never touched), checks their shapes, and handles the
degenerate cases it can run into (lines at infinity, points at infinity,
too few correspondences).

Conventions: 2D points (N, 2) as (x, y) = (column, row); homogeneous pixels
(x, y, 1); F satisfies x2^T F x1 = 0; E = K2^T F K1.
"""

import colorsys

import cv2
import numpy as np


# ===================================================================== helpers
def _as_points2d(pts, name="points"):
    """Return a float64 (N, 2) copy of ``pts`` (a single (2,) point is allowed)."""
    arr = np.array(pts, dtype=np.float64, copy=True)
    if arr.ndim == 1 and arr.size == 2:
        arr = arr.reshape(1, 2)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (N, 2), got {np.shape(pts)}")
    return arr


def _as_matrix(M, shape, name="matrix"):
    """Return a float64 copy of ``M`` with the expected shape."""
    arr = np.array(M, dtype=np.float64, copy=True)
    if arr.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {arr.shape}")
    return arr


def _homogeneous(pts):
    """(N, 2) -> (N, 3) by appending a column of ones."""
    return np.hstack([pts, np.ones((pts.shape[0], 1))])


def _null_vector(A):
    """Unit vector v minimising |A v| (last right singular vector of A)."""
    _, _, Vt = np.linalg.svd(A)
    return Vt[-1]


def _similarity_normaliser(pts):
    """Hartley's normalisation for (N, 2) points.

    Returns the 3x3 similarity T that moves the centroid to the origin and
    scales the points so their mean distance from it is sqrt(2). If all the
    points coincide (no spread) the scale is left at 1 rather than dividing by
    zero.
    """
    centroid = pts.mean(axis=0)
    mean_dist = np.mean(np.linalg.norm(pts - centroid, axis=1))
    scale = np.sqrt(2.0) / mean_dist if mean_dist > 1e-12 else 1.0
    return np.array([[scale, 0.0, -scale * centroid[0]],
                     [0.0, scale, -scale * centroid[1]],
                     [0.0, 0.0, 1.0]])


def _epipolar_design_matrix(x1h, x2h):
    """Rows ``x2 x1^T`` flattened row by row, so that ``A @ F.ravel() = x2^T F x1``."""
    rows = []
    for a, b in zip(x1h, x2h):
        rows.append(np.outer(b, a).ravel())
    return np.array(rows)


def _check_correspondences(pts1, pts2, minimum):
    p1 = _as_points2d(pts1, "pts1")
    p2 = _as_points2d(pts2, "pts2")
    if p1.shape != p2.shape:
        raise ValueError("pts1 and pts2 must contain the same number of points")
    if p1.shape[0] < minimum:
        raise ValueError(f"at least {minimum} correspondences are needed, got {p1.shape[0]}")
    if not (np.all(np.isfinite(p1)) and np.all(np.isfinite(p2))):
        raise ValueError("points must be finite")
    return p1, p2


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear (DLT) triangulation; returns (N, 3) points ((3,) for a single (2,) pair)."""
    P1 = _as_matrix(P1, (3, 4), "P1")
    P2 = _as_matrix(P2, (3, 4), "P2")
    single = np.ndim(pts1) == 1
    p1, p2 = _check_correspondences(pts1, pts2, 1)

    out = np.empty((p1.shape[0], 3))
    for i, ((x1, y1), (x2, y2)) in enumerate(zip(p1, p2)):
        # Two equations per view from x cross (P X) = 0.
        A = np.array([x1 * P1[2] - P1[0],
                      y1 * P1[2] - P1[1],
                      x2 * P2[2] - P2[0],
                      y2 * P2[2] - P2[1]])
        # Scaling a row does not change the exact solution; giving every row
        # unit length keeps a view with large pixel values from dominating the
        # least-squares fit when the data are noisy.
        norms = np.linalg.norm(A, axis=1, keepdims=True)
        A = A / np.where(norms > 0, norms, 1.0)
        X = _null_vector(A)
        if abs(X[3]) < 1e-12 * np.linalg.norm(X):
            out[i] = np.nan  # point at infinity: no Euclidean position
        else:
            out[i] = X[:3] / X[3]
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def epipolar_lines(F, pts1):
    """Lines l' = F x in image 2, scaled so that a^2 + b^2 = 1."""
    F = _as_matrix(F, (3, 3), "F")
    p1 = _as_points2d(pts1, "pts1")
    lines = _homogeneous(p1) @ F.T
    norm = np.hypot(lines[:, 0], lines[:, 1])
    # A point at the epipole gives F x = 0: there is no line to scale, keep it as is.
    norm = np.where(norm > 0, norm, 1.0)
    return lines / norm[:, None]


def _line_endpoints(a, b, c, width, height):
    """End points of a x + b y + c = 0 on the image border, or None."""
    if not np.all(np.isfinite([a, b, c])) or (a == 0 and b == 0):
        return None
    if abs(b) >= abs(a):
        # Mostly horizontal: evaluate y at the left and right borders.
        x0, x1 = 0.0, width - 1.0
        y0, y1 = -(a * x0 + c) / b, -(a * x1 + c) / b
    else:
        # Mostly vertical: evaluate x at the top and bottom borders.
        y0, y1 = 0.0, height - 1.0
        x0, x1 = -(b * y0 + c) / a, -(b * y1 + c) / a
    # cv2.line wants int coordinates that fit into 32 bits; far-away end points
    # are clamped (the line is clipped to the image by OpenCV anyway, and the
    # clamp keeps the direction almost exactly for any line crossing the image).
    lim = 1e6
    pts = np.clip(np.array([x0, y0, x1, y1]), -lim, lim)
    pts = np.rint(pts).astype(int)
    return (int(pts[0]), int(pts[1])), (int(pts[2]), int(pts[3]))


def _bright_colour(i, n):
    """A fully saturated colour (BGR) taken around the hue circle."""
    r, g, b = colorsys.hsv_to_rgb((i / max(n, 1)) % 1.0, 1.0, 1.0)
    return (int(255 * b), int(255 * g), int(255 * r))


def draw_epipolar_lines(image, lines):
    """Draw each line from border to border on a copy of ``image``."""
    img = np.asarray(image)
    if img.dtype != np.uint8:
        raise ValueError("image must be uint8")
    if not (img.ndim == 2 or (img.ndim == 3 and img.shape[2] in (1, 3))):
        raise ValueError("image must be (H, W) or (H, W, 3)")
    out = np.ascontiguousarray(img).copy()  # never draw on the caller's array
    height, width = out.shape[:2]
    lines = np.array(lines, dtype=np.float64).reshape(-1, 3)
    grey = out.ndim == 2 or out.shape[2] == 1
    for i, (a, b, c) in enumerate(lines):
        ends = _line_endpoints(a, b, c, width, height)
        if ends is None:
            continue
        colour = 255 if grey else _bright_colour(i, len(lines))
        cv2.line(out, ends[0], ends[1], colour, 1, cv2.LINE_8)
    return out


# --------------------------------------------------------------------- ex3
def essential_from_fundamental(F, K1, K2):
    F = _as_matrix(F, (3, 3), "F")
    K1 = _as_matrix(K1, (3, 3), "K1")
    K2 = _as_matrix(K2, (3, 3), "K2")
    return K2.T @ F @ K1


def _enforce_essential(E):
    """Closest matrix with singular values (1, 1, 0)."""
    U, _, Vt = np.linalg.svd(E)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt


def essential_8point(pts1, pts2, K1, K2):
    """8-point algorithm on K^-1-normalised points, then singular values (s, s, 0)."""
    p1, p2 = _check_correspondences(pts1, pts2, 8)
    K1 = _as_matrix(K1, (3, 3), "K1")
    K2 = _as_matrix(K2, (3, 3), "K2")
    n1 = _homogeneous(p1) @ np.linalg.inv(K1).T
    n2 = _homogeneous(p2) @ np.linalg.inv(K2).T
    # Calibrated coordinates are already of order 1, but they need not be
    # centred; a further (exact, undone afterwards) Hartley normalisation
    # makes the linear system a little better conditioned.
    n1 = n1[:, :2] / n1[:, 2:]
    n2 = n2[:, :2] / n2[:, 2:]
    T1, T2 = _similarity_normaliser(n1), _similarity_normaliser(n2)
    A = _epipolar_design_matrix(_homogeneous(n1) @ T1.T, _homogeneous(n2) @ T2.T)
    En = _null_vector(A).reshape(3, 3)
    E = T2.T @ En @ T1
    E = _enforce_essential(E)
    return E


# --------------------------------------------------------------------- ex4
def fundamental_8point(pts1, pts2):
    """Normalised 8-point algorithm with the rank-2 constraint."""
    p1, p2 = _check_correspondences(pts1, pts2, 8)
    T1, T2 = _similarity_normaliser(p1), _similarity_normaliser(p2)
    A = _epipolar_design_matrix(_homogeneous(p1) @ T1.T, _homogeneous(p2) @ T2.T)
    Fn = _null_vector(A).reshape(3, 3)

    # Rank 2: zero the smallest singular value.
    U, s, Vt = np.linalg.svd(Fn)
    Fn = U @ np.diag([s[0], s[1], 0.0]) @ Vt

    F = T2.T @ Fn @ T1
    norm = np.linalg.norm(F)
    if not np.isfinite(norm) or norm == 0:
        raise ValueError("degenerate configuration: F could not be estimated")
    return F / norm


# --------------------------------------------------------------------- ex5
def epipoles(F):
    """Right and left null vectors of F, as unit homogeneous 3-vectors."""
    F = _as_matrix(F, (3, 3), "F")
    U, _, Vt = np.linalg.svd(F)
    e1 = Vt[-1].copy()     # F e1 = 0
    e2 = U[:, -1].copy()   # F^T e2 = 0
    return e1, e2


# --------------------------------------------------------------------- ex6
def _to_grey(img):
    img = np.ascontiguousarray(np.asarray(img))
    if img.ndim == 3 and img.shape[2] == 3:
        return cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    if img.ndim == 3 and img.shape[2] == 1:
        return img[:, :, 0].copy()
    return img


def _sift_matches(img1, img2, ratio=0.75):
    """SIFT key points matched with a brute-force L2 matcher and Lowe's ratio test."""
    sift = cv2.SIFT_create()
    kp1, des1 = sift.detectAndCompute(_to_grey(img1), None)
    kp2, des2 = sift.detectAndCompute(_to_grey(img2), None)
    if des1 is None or des2 is None or len(kp1) < 2 or len(kp2) < 2:
        return np.zeros((0, 2)), np.zeros((0, 2))
    matcher = cv2.BFMatcher(cv2.NORM_L2)
    pts1, pts2 = [], []
    for pair in matcher.knnMatch(des1, des2, k=2):
        if len(pair) < 2:
            continue
        best, second = pair
        if best.distance < ratio * second.distance:
            pts1.append(kp1[best.queryIdx].pt)
            pts2.append(kp2[best.trainIdx].pt)
    return np.array(pts1, dtype=np.float64).reshape(-1, 2), np.array(pts2, dtype=np.float64).reshape(-1, 2)


def two_view_reconstruction(img1, img2, K):
    """SIFT matches -> robust essential matrix -> pose -> triangulated points.

    Because K is known, the relative pose is estimated with the calibrated
    five-point RANSAC (``cv2.findEssentialMat``) rather than via F; F is then
    ``K^-T E K^-1``, which has rank 2 by construction.
    """
    K = _as_matrix(K, (3, 3), "K")
    empty = (np.full((3, 3), np.nan), np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 3)))
    pts1, pts2 = _sift_matches(img1, img2)
    if len(pts1) < 8:
        return empty

    # 1 pixel threshold and 0.999 confidence, as for the fundamental matrix.
    E, mask = cv2.findEssentialMat(pts1, pts2, K, method=cv2.RANSAC, prob=0.999, threshold=1.0)
    if E is None or mask is None:
        return empty
    E = E[:3]  # several solutions may be stacked; keep the first
    inl = mask.ravel() > 0
    pts1, pts2 = pts1[inl], pts2[inl]
    if len(pts1) < 5:
        return empty

    _, R, t, pose_mask = cv2.recoverPose(E, pts1, pts2, K)
    t = t.ravel()

    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K @ np.hstack([R, t[:, None]])
    X = triangulate(P1, P2, pts1, pts2).reshape(-1, 3)

    # Keep points in front of both cameras (and finite).
    z1 = X[:, 2]
    z2 = (X @ R.T + t)[:, 2]
    keep = np.isfinite(X).all(axis=1) & (z1 > 0) & (z2 > 0)

    Kinv = np.linalg.inv(K)
    F = Kinv.T @ E @ Kinv
    F = F / np.linalg.norm(F)
    return F, pts1[keep], pts2[keep], X[keep]
