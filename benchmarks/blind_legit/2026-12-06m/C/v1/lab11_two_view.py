"""Lab 11 - two-view geometry.

My solution, written from the lab sheet's equations with NumPy.

Conventions (as in the assignment):
- 2D points are (N, 2) float arrays of (x, y) pixels, x = column, y = row.
- x2^T F x1 = 0 for every correspondence x1 <-> x2; E = K2^T F K1.
- F, E and epipoles are only defined up to scale (and sign).
"""

import cv2
import numpy as np


def _as_points(pts):
    """(N, 2) float copy of the points (a single (2,) point becomes (1, 2))."""
    return np.atleast_2d(np.asarray(pts, dtype=float)).reshape(-1, 2)


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear triangulation: x1 x (P1 X) = 0 and x2 x (P2 X) = 0, solved by SVD."""
    P1 = np.asarray(P1, dtype=float)
    P2 = np.asarray(P2, dtype=float)
    single = np.asarray(pts1).ndim == 1
    p1 = _as_points(pts1)
    p2 = _as_points(pts2)

    X = np.zeros((len(p1), 3))
    for i in range(len(p1)):
        x1, y1 = p1[i]
        x2, y2 = p2[i]
        # two equations from each cross product
        A = np.array([
            x1 * P1[2] - P1[0],
            y1 * P1[2] - P1[1],
            x2 * P2[2] - P2[0],
            y2 * P2[2] - P2[1],
        ])
        _, _, Vt = np.linalg.svd(A)
        Xh = Vt[-1]            # singular vector of the smallest singular value
        X[i] = Xh[:3] / Xh[3]  # back to Euclidean coordinates
    return X[0] if single else X


# --------------------------------------------------------------------- ex2
def epipolar_lines(F, pts1):
    """Lines l' = F x1 in image 2, scaled so that a^2 + b^2 = 1."""
    F = np.asarray(F, dtype=float)
    p = _as_points(pts1)
    xh = np.column_stack([p, np.ones(len(p))])   # homogeneous points, one per row
    lines = (F @ xh.T).T                          # l' = F x for every x
    norm = np.sqrt(lines[:, 0] ** 2 + lines[:, 1] ** 2)
    return lines / norm[:, None]


# a few bright BGR colours for the lines
_COLOURS = [(0, 0, 255), (0, 255, 0), (255, 0, 0), (0, 255, 255),
            (255, 0, 255), (255, 255, 0), (0, 128, 255), (255, 0, 128)]


def draw_epipolar_lines(image, lines):
    """Draw every line a x + b y + c = 0 from border to border on a copy."""
    out = image.copy()
    h, w = image.shape[:2]
    grey = out.ndim == 2
    for i, (a, b, c) in enumerate(np.asarray(lines, dtype=float).reshape(-1, 3)):
        if a == 0 and b == 0:
            continue                      # not a line
        if abs(b) >= abs(a):
            # mostly horizontal: cut with the left and right borders
            x0, x1 = 0.0, w - 1.0
            y0 = -(a * x0 + c) / b
            y1 = -(a * x1 + c) / b
        else:
            # mostly vertical: cut with the top and bottom borders
            y0, y1 = 0.0, h - 1.0
            x0 = -(b * y0 + c) / a
            x1 = -(b * y1 + c) / a
        # keep the coordinates in a range cv2.line accepts
        pt0 = (int(round(np.clip(x0, -1e6, 1e6))), int(round(np.clip(y0, -1e6, 1e6))))
        pt1 = (int(round(np.clip(x1, -1e6, 1e6))), int(round(np.clip(y1, -1e6, 1e6))))
        colour = 255 if grey else _COLOURS[i % len(_COLOURS)]
        cv2.line(out, pt0, pt1, colour, 1)
    return out


# --------------------------------------------------------------------- ex3
def essential_from_fundamental(F, K1, K2):
    """E = K2^T F K1."""
    return np.asarray(K2, float).T @ np.asarray(F, float) @ np.asarray(K1, float)


def essential_8point(pts1, pts2, K1, K2):
    """8-point algorithm on normalised coordinates K^-1 x, then singular values (1, 1, 0)."""
    p1 = _as_points(pts1)
    p2 = _as_points(pts2)
    n = len(p1)
    x1 = (np.linalg.inv(K1) @ np.column_stack([p1, np.ones(n)]).T).T
    x2 = (np.linalg.inv(K2) @ np.column_stack([p2, np.ones(n)]).T).T

    # one row per correspondence: x2n x1n^T flattened row by row
    A = np.zeros((n, 9))
    for i in range(n):
        A[i] = np.outer(x2[i], x1[i]).ravel()
    _, _, Vt = np.linalg.svd(A)
    E = Vt[-1].reshape(3, 3)

    # project onto the essential matrices: singular values (1, 1, 0)
    U, _, Vt = np.linalg.svd(E)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt


# --------------------------------------------------------------------- ex4
def fundamental_8point(pts1, pts2):
    """The lab sheet's 8-point algorithm on the pixels, then rank 2 by SVD.

    Each row of A is [x x', x y', x, y x', y y', y, x', y', 1] with (x, y) in
    image 1 and (x', y') in image 2, exactly as on the lab sheet. This row is
    the outer product x1 x2'^T flattened, so the solution reshaped row by row is
    F^T (x1^T F^T x2 = x2^T F x1): I transpose it at the end.
    """
    p1 = _as_points(pts1)
    p2 = _as_points(pts2)
    A = []
    for (x, y), (xp, yp) in zip(p1, p2):
        A.append([x * xp, x * yp, x, y * xp, y * yp, y, xp, yp, 1.0])
    A = np.array(A)
    _, _, Vt = np.linalg.svd(A)
    G = Vt[-1].reshape(3, 3)          # G = F^T
    F = G.T

    # enforce rank 2: zero the smallest singular value
    U, S, Vt = np.linalg.svd(F)
    S[2] = 0.0
    return U @ np.diag(S) @ Vt


# --------------------------------------------------------------------- ex5
def epipoles(F):
    """Right and left null vectors of F by SVD: F e1 = 0, F^T e2 = 0."""
    U, _, Vt = np.linalg.svd(np.asarray(F, dtype=float))
    e1 = Vt[-1]        # right null space
    e2 = U[:, -1]      # left null space
    return e1.copy(), e2.copy()


# --------------------------------------------------------------------- ex6
def two_view_reconstruction(img1, img2, K):
    """SIFT + ratio test, F by RANSAC, pose from E, my own triangulation."""
    K = np.asarray(K, dtype=float)
    g1 = cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY) if img1.ndim == 3 else img1
    g2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY) if img2.ndim == 3 else img2

    # 1. features and Lowe's ratio test
    sift = cv2.SIFT_create()
    kp1, des1 = sift.detectAndCompute(g1, None)
    kp2, des2 = sift.detectAndCompute(g2, None)
    matcher = cv2.BFMatcher(cv2.NORM_L2)
    good = []
    for pair in matcher.knnMatch(des1, des2, k=2):
        if len(pair) == 2 and pair[0].distance < 0.75 * pair[1].distance:
            good.append(pair[0])
    pts1 = np.array([kp1[m.queryIdx].pt for m in good], dtype=float)
    pts2 = np.array([kp2[m.trainIdx].pt for m in good], dtype=float)

    # 2. F with RANSAC, keep its inliers
    F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
    F = F[:3]
    inl = mask.ravel().astype(bool)
    pts1, pts2 = pts1[inl], pts2[inl]

    # 3. relative pose from E = K^T F K
    E = K.T @ F @ K
    _, R, t, _ = cv2.recoverPose(E, pts1, pts2, K)

    # 4. triangulate with P1 = K[I|0], P2 = K[R|t]
    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K @ np.hstack([R, t.reshape(3, 1)])
    X = triangulate(P1, P2, pts1, pts2)

    # keep the points in front of both cameras
    z2 = (X @ R.T + t.reshape(1, 3))[:, 2]
    front = (X[:, 2] > 0) & (z2 > 0)
    return F, pts1[front], pts2[front], X[front]
