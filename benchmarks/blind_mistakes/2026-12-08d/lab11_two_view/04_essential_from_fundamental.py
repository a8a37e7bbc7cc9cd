"""Lab 11 - two-view geometry (reference solution).

Notation: ``x1 <-> x2`` are corresponding pixels in image 1 and image 2, in
homogeneous coordinates ``(x, y, 1)``. The fundamental matrix F satisfies the
epipolar constraint ``x2^T F x1 = 0``; the essential matrix E satisfies the same
constraint on normalised coordinates ``K^-1 x``; ``E = K2^T F K1``.
"""

import cv2
import numpy as np


def _homogeneous(pts):
    """(N, 2) pixels -> (N, 3) homogeneous points ``(x, y, 1)``."""
    pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    return np.hstack([pts, np.ones((len(pts), 1))])


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear triangulation: for each pair, solve ``x x (P X) = 0`` in both views by SVD.

    The cross product ``x x (P X) = 0`` gives two independent equations per view,
    ``x p3^T X - p1^T X = 0`` and ``y p3^T X - p2^T X = 0`` (``pi^T`` the rows of P),
    so four equations ``A X = 0`` for the four homogeneous unknowns. The solution
    is the right singular vector of A with the smallest singular value, divided
    by its last entry w.
    """
    P1, P2 = np.asarray(P1, np.float64), np.asarray(P2, np.float64)
    pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
    pts2 = np.asarray(pts2, np.float64).reshape(-1, 2)
    A = np.stack([pts1[:, 0:1] * P1[2] - P1[0],
                  pts1[:, 1:2] * P1[2] - P1[1],
                  pts2[:, 0:1] * P2[2] - P2[0],
                  pts2[:, 1:2] * P2[2] - P2[1]], axis=1)          # (N, 4, 4), one system per point
    X = np.linalg.svd(A)[2][:, -1, :]                            # (N, 4) null vectors
    return X[:, :3] / X[:, 3:4]


# --------------------------------------------------------------------- ex2
def epipolar_lines(F, pts1):
    """The epipolar lines ``l' = F x1`` in image 2, scaled so that ``a^2 + b^2 = 1``.

    With that scale, ``|a x + b y + c|`` is the distance in pixels from ``(x, y)``
    to the line.
    """
    lines = _homogeneous(pts1) @ np.asarray(F, np.float64).T
    return lines / np.linalg.norm(lines[:, :2], axis=1, keepdims=True)


_PALETTE = [(0, 0, 255), (0, 255, 0), (255, 0, 0), (0, 255, 255), (255, 0, 255), (255, 255, 0),
            (0, 128, 255), (255, 0, 128), (128, 255, 0)]


def draw_epipolar_lines(image, lines):
    """Draw each line ``a x + b y + c = 0`` across the whole image (1 px).

    A copy with the input's channels (the API's rule): on a BGR image a colour
    per line, on a grey one white lines.
    """
    canvas = np.array(image, dtype=np.uint8, copy=True)
    height, width = canvas.shape[:2]
    for i, (a, b, c) in enumerate(np.asarray(lines, np.float64).reshape(-1, 3)):
        if abs(b) >= abs(a):   # mostly horizontal: intersect with the left and right borders
            p, q = (0.0, -c / b), (width - 1.0, -(c + a * (width - 1)) / b)
        else:                  # mostly vertical: intersect with the top and bottom borders
            p, q = (-c / a, 0.0), (-(c + b * (height - 1)) / a, height - 1.0)
        # Far-away end points can overflow cv2.line's integer coordinates: clip first.
        inside, p, q = cv2.clipLine((0, 0, width, height), _to_int(p, width, height), _to_int(q, width, height))
        if inside:
            colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255
            cv2.line(canvas, p, q, colour, 1, cv2.LINE_8)
    return canvas


def _to_int(point, width, height):
    limit = 4.0 * (width + height)
    return tuple(int(round(np.clip(v, -limit, limit))) for v in point)


# --------------------------------------------------------------------- ex3
def essential_from_fundamental(F, K1, K2):
    """``E = K2^T F K1``: F acts on pixels, E on normalised coordinates ``K^-1 x``."""
    return np.asarray(K1, np.float64).T @ np.asarray(F, np.float64) @ np.asarray(K2, np.float64)


def essential_8point(pts1, pts2, K1, K2):
    """The 8-point algorithm on normalised coordinates, then singular values forced to (1, 1, 0)."""
    x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
    x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
    E = _eight_point_core(x1, x2)
    U, _, Vt = np.linalg.svd(E)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt


def _eight_point_core(x1, x2):
    """Least-squares solution of ``x2^T M x1 = 0``: each row of A is ``kron(x2, x1)``."""
    A = (x2[:, :, None] * x1[:, None, :]).reshape(len(x1), 9)
    return np.linalg.svd(A)[2][-1].reshape(3, 3)


# --------------------------------------------------------------------- ex4
def _hartley_normalisation(pts):
    """Similarity moving the centroid to the origin with mean distance sqrt(2)."""
    centre = pts.mean(axis=0)
    scale = np.sqrt(2.0) / np.mean(np.linalg.norm(pts - centre, axis=1))
    return np.array([[scale, 0.0, -scale * centre[0]],
                     [0.0, scale, -scale * centre[1]],
                     [0.0, 0.0, 1.0]])


def fundamental_8point(pts1, pts2):
    """Hartley's normalised 8-point algorithm with rank-2 enforcement.

    1. Normalise each image's points (centroid at 0, mean distance sqrt(2)) with T1, T2.
    2. Solve ``x2n^T Fn x1n = 0`` by SVD.
    3. Enforce rank 2: zero the smallest singular value of Fn.
    4. Undo the normalisation: ``F = T2^T Fn T1``.
    """
    pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
    pts2 = np.asarray(pts2, np.float64).reshape(-1, 2)
    T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
    Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T)
    U, s, Vt = np.linalg.svd(Fn)
    Fn = U @ np.diag([s[0], s[1], 0.0]) @ Vt
    F = T2.T @ Fn @ T1
    return F / np.linalg.norm(F)


# --------------------------------------------------------------------- ex5
def epipoles(F):
    """Right and left null vectors of F: ``F e1 = 0``, ``F^T e2 = 0``.

    Returned as homogeneous unit vectors (not divided by w, which is 0 for an
    epipole at infinity).
    """
    U, _, Vt = np.linalg.svd(np.asarray(F, np.float64))
    return Vt[-1], U[:, -1]


# --------------------------------------------------------------------- ex6
def two_view_reconstruction(img1, img2, K):
    """SIFT matches -> F by RANSAC -> E -> relative pose -> triangulated inliers.

    Returns F, the inlier correspondences and their 3-D points in camera 1's
    frame, up to the global scale that two views cannot recover.
    """
    grey1 = cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY) if img1.ndim == 3 else img1
    grey2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY) if img2.ndim == 3 else img2
    sift = cv2.SIFT_create()
    kp1, des1 = sift.detectAndCompute(grey1, None)
    kp2, des2 = sift.detectAndCompute(grey2, None)
    pairs = cv2.BFMatcher(cv2.NORM_L2).knnMatch(des1, des2, k=2)
    good = [m for m, n in (p for p in pairs if len(p) == 2) if m.distance < 0.75 * n.distance]
    pts1 = np.float64([kp1[m.queryIdx].pt for m in good])
    pts2 = np.float64([kp2[m.trainIdx].pt for m in good])

    F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
    inliers = mask.ravel().astype(bool)
    pts1, pts2 = pts1[inliers], pts2[inliers]

    K = np.asarray(K, np.float64)
    E = essential_from_fundamental(F, K, K)
    _, R, t, pose_mask = cv2.recoverPose(E, pts1, pts2, K)
    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K @ np.hstack([R, t.reshape(3, 1)])
    points3d = triangulate(P1, P2, pts1, pts2)
    in_front = (points3d[:, 2] > 0) & ((points3d @ R.T + t.reshape(3))[:, 2] > 0)
    return F, pts1[in_front], pts2[in_front], points3d[in_front]
