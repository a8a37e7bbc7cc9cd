"""Lab 11 - two-view geometry.

My choices where the lab leaves things open
-------------------------------------------
- Inputs may be lists, read-only or non-contiguous arrays: everything is copied
  to float64 with ``np.asarray(..., dtype=np.float64)`` before any arithmetic,
  and nothing is written into the caller's arrays.
- Results are returned as float32 (the geometry is computed in float64 and only
  the final answer is stored in single precision).
- Projective answers (F, E, epipoles) are returned with my own scale and sign:
  F and E with unit Frobenius norm and a negative largest entry, epipoles as
  unit vectors. Any non-zero multiple is the same answer.
- Triangulation uses all three rows of each cross product ``[x]_x P X = 0``
  (a 6 x 4 system per point), rows scaled to unit length; a point whose
  homogeneous coordinate w is 0 (at infinity) comes out as NaN.
- The fundamental matrix follows the lab sheet literally: the 8-point system
  on the raw pixels (no Hartley normalisation), rank 2 enforced by SVD.
"""

import cv2
import numpy as np


def _points2d(pts):
    """(N, 2) float64 copy of a point array or list (a single (2,) point too)."""
    p = np.array(pts, dtype=np.float64, copy=True)
    return p.reshape(-1, 2)


def _homog(pts):
    p = _points2d(pts)
    return np.hstack([p, np.ones((p.shape[0], 1))])


def _skew(v):
    """Stack of 3x3 cross-product matrices [v]_x for v of shape (N, 3)."""
    n = v.shape[0]
    S = np.zeros((n, 3, 3))
    S[:, 0, 1], S[:, 0, 2] = -v[:, 2], v[:, 1]
    S[:, 1, 0], S[:, 1, 2] = v[:, 2], -v[:, 0]
    S[:, 2, 0], S[:, 2, 1] = -v[:, 1], v[:, 0]
    return S


def _fix_scale(M):
    """Unit Frobenius norm, sign chosen so that the largest |entry| is negative."""
    M = M / np.linalg.norm(M)
    k = np.argmax(np.abs(M))
    if M.flat[k] > 0:
        M = -M
    return M


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear triangulation with the full cross products.

    ``x x (P X) = [x]_x P X = 0`` gives three equations per view (only two are
    independent). I keep all three, normalise every row to unit length so the
    two views weigh the same, and take the right singular vector of the
    smallest singular value of the 6 x 4 matrix. Returns (N, 3) float32; a
    single (2,) point pair gives a (3,) result.
    """
    P1 = np.asarray(P1, dtype=np.float64).reshape(3, 4)
    P2 = np.asarray(P2, dtype=np.float64).reshape(3, 4)
    single = np.ndim(pts1) == 1
    x1, x2 = _homog(pts1), _homog(pts2)
    n = x1.shape[0]
    if n == 0:
        return np.zeros((0, 3), dtype=np.float32)

    A = np.concatenate([_skew(x1) @ P1, _skew(x2) @ P2], axis=1)   # (N, 6, 4)
    norms = np.linalg.norm(A, axis=2, keepdims=True)
    A = A / np.where(norms > 0, norms, 1.0)
    _, _, Vt = np.linalg.svd(A)
    X = Vt[:, -1, :]                                  # (N, 4) homogeneous

    w = X[:, 3:4]
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(np.abs(w) > 1e-300, X[:, :3] / w, np.nan)
    out = out.astype(np.float32)
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def epipolar_lines(F, pts1):
    """``l' = F x1`` for every point, scaled to ``a^2 + b^2 = 1``.

    Sign convention of my own: c >= 0 (the normal points away from the origin
    side); float32 output.
    """
    F = np.asarray(F, dtype=np.float64).reshape(3, 3)
    x1 = _homog(pts1)
    L = x1 @ F.T                                      # row i = (F x1_i)^T
    ab = np.hypot(L[:, 0], L[:, 1])
    ab = np.where(ab > 0, ab, 1.0)
    L = L / ab[:, None]
    L = L * np.where(L[:, 2] < 0, -1.0, 1.0)[:, None]
    return L.astype(np.float32)


def _line_colour(i):
    """A bright, saturated BGR colour per line index (walk around the hue circle)."""
    hue = int((i * 47) % 180)
    hsv = np.uint8([[[hue, 255, 255]]])
    b, g, r = cv2.cvtColor(hsv, cv2.COLOR_HSV2BGR)[0, 0]
    return int(b), int(g), int(r)


def _clip_to_box(x0, y0, dx, dy, w, h):
    """Liang-Barsky: the part of the infinite line (x0, y0) + s (dx, dy) inside
    [0, w-1] x [0, h-1], as two float end points, or None if it misses."""
    s_lo, s_hi = -np.inf, np.inf
    for p0, dp, hi in ((x0, dx, w - 1.0), (y0, dy, h - 1.0)):
        if abs(dp) < 1e-12:
            if p0 < 0 or p0 > hi:
                return None
            continue
        s1, s2 = (0.0 - p0) / dp, (hi - p0) / dp
        s_lo, s_hi = max(s_lo, min(s1, s2)), min(s_hi, max(s1, s2))
    if s_lo > s_hi:
        return None
    return (x0 + s_lo * dx, y0 + s_lo * dy), (x0 + s_hi * dx, y0 + s_hi * dy)


def draw_epipolar_lines(image, lines):
    """Draw each line from border to border, 2 pixels thick.

    The end points are where the line meets the image rectangle, found by
    clipping the infinite line against all four borders at once (Liang-Barsky),
    so steep, vertical and horizontal lines need no special case. Grey stays
    grey (white lines), BGR stays BGR (a different saturated colour per line).
    """
    img = np.array(image, dtype=np.uint8, copy=True, order="C")
    h, w = img.shape[:2]
    L = np.asarray(lines, dtype=np.float64).reshape(-1, 3)
    for i, (a, b, c) in enumerate(L):
        if not np.all(np.isfinite((a, b, c))) or (a == 0 and b == 0):
            continue
        n = np.hypot(a, b)
        a, b, c = a / n, b / n, c / n
        # foot of the perpendicular from the origin, and the line's direction
        seg = _clip_to_box(-a * c, -b * c, -b, a, w, h)
        if seg is None:
            continue
        p = (int(round(seg[0][0])), int(round(seg[0][1])))
        q = (int(round(seg[1][0])), int(round(seg[1][1])))
        colour = 255 if img.ndim == 2 else _line_colour(i)
        cv2.line(img, p, q, colour, 2)
    return img


# --------------------------------------------------------------------- ex3
def essential_from_fundamental(F, K1, K2):
    """``E = K2^T F K1`` (returned with unit norm, my sign convention)."""
    F = np.asarray(F, dtype=np.float64).reshape(3, 3)
    K1 = np.asarray(K1, dtype=np.float64).reshape(3, 3)
    K2 = np.asarray(K2, dtype=np.float64).reshape(3, 3)
    return _fix_scale(K2.T @ F @ K1).astype(np.float32)


def _solve_8point(x1, x2):
    """Null vector of the stacked rows ``x2 x1^T`` (flattened row by row)."""
    A = (x2[:, :, None] * x1[:, None, :]).reshape(-1, 9)
    _, _, Vt = np.linalg.svd(A)
    return Vt[-1].reshape(3, 3)


def essential_8point(pts1, pts2, K1, K2):
    """E from N >= 8 correspondences on normalised coordinates.

    The two equal singular values are set to their mean (the closest essential
    matrix in the Frobenius norm) rather than to 1.
    """
    K1 = np.asarray(K1, dtype=np.float64).reshape(3, 3)
    K2 = np.asarray(K2, dtype=np.float64).reshape(3, 3)
    x1 = np.linalg.solve(K1, _homog(pts1).T).T
    x2 = np.linalg.solve(K2, _homog(pts2).T).T
    E = _solve_8point(x1, x2)
    U, s, Vt = np.linalg.svd(E)
    m = 0.5 * (s[0] + s[1])
    E = U @ np.diag([m, m, 0.0]) @ Vt
    return _fix_scale(E).astype(np.float32)


# --------------------------------------------------------------------- ex4
def fundamental_8point(pts1, pts2):
    """F from N >= 8 correspondences: the lab sheet's 8-point algorithm.

    Rows ``x2 x1^T`` on the raw pixel coordinates, SVD, then the smallest
    singular value of F set to 0 (rank 2).
    """
    F = _solve_8point(_homog(pts1), _homog(pts2))
    U, s, Vt = np.linalg.svd(F)
    F = U @ np.diag([s[0], s[1], 0.0]) @ Vt
    return _fix_scale(F).astype(np.float32)


# --------------------------------------------------------------------- ex5
def epipoles(F):
    """``F e1 = 0`` and ``F^T e2 = 0`` from the SVD of F, as unit vectors.

    Sign: the entry of largest magnitude is made positive.
    """
    F = np.asarray(F, dtype=np.float64).reshape(3, 3)
    U, _, Vt = np.linalg.svd(F)
    e1, e2 = Vt[-1].copy(), U[:, -1].copy()
    for e in (e1, e2):
        e /= np.linalg.norm(e)
        if e[np.argmax(np.abs(e))] < 0:
            e *= -1.0
    return e1.astype(np.float32), e2.astype(np.float32)


# --------------------------------------------------------------------- ex6
def two_view_reconstruction(img1, img2, K):
    """Photos -> matches -> E (with K) -> pose -> 3D points in camera 1's frame.

    Route: SIFT on the grey images, FLANN kd-tree matching with Lowe's ratio
    0.7, the essential matrix straight from the calibrated points
    (``cv2.findEssentialMat`` with RANSAC), its inliers, ``cv2.recoverPose``,
    my own triangulation, points kept in front of both cameras. F follows
    from E: ``F = K^-T E K^-1``.
    """
    K = np.asarray(K, dtype=np.float64).reshape(3, 3)
    g1 = img1 if np.ndim(img1) == 2 else cv2.cvtColor(np.ascontiguousarray(img1), cv2.COLOR_BGR2GRAY)
    g2 = img2 if np.ndim(img2) == 2 else cv2.cvtColor(np.ascontiguousarray(img2), cv2.COLOR_BGR2GRAY)
    g1 = np.ascontiguousarray(g1, dtype=np.uint8)
    g2 = np.ascontiguousarray(g2, dtype=np.uint8)

    sift = cv2.SIFT_create()
    k1, d1 = sift.detectAndCompute(g1, None)
    k2, d2 = sift.detectAndCompute(g2, None)
    flann = cv2.FlannBasedMatcher(dict(algorithm=1, trees=5), dict(checks=64))
    pairs = flann.knnMatch(d1, d2, k=2)
    good = [p[0] for p in pairs if len(p) == 2 and p[0].distance < 0.7 * p[1].distance]
    p1 = np.float64([k1[m.queryIdx].pt for m in good])
    p2 = np.float64([k2[m.trainIdx].pt for m in good])

    E, mask = cv2.findEssentialMat(p1, p2, K, method=cv2.RANSAC, prob=0.999, threshold=1.0)
    if E is not None and E.shape[0] > 3:      # several solutions stacked: keep the first
        E = E[:3]
    keep = mask.ravel().astype(bool)
    p1, p2 = p1[keep], p2[keep]
    _, R, t, _ = cv2.recoverPose(E, p1, p2, K)

    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K @ np.hstack([R, t.reshape(3, 1)])
    X = np.asarray(triangulate(P1, P2, p1, p2), dtype=np.float64)
    Z2 = (X @ R.T + t.reshape(1, 3))[:, 2]
    front = np.isfinite(X).all(axis=1) & (X[:, 2] > 0) & (Z2 > 0)

    Kinv = np.linalg.inv(K)
    F = _fix_scale(Kinv.T @ E @ Kinv)
    return F, p1[front], p2[front], X[front]
