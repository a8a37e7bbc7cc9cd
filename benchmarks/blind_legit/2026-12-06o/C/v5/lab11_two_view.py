"""Lab 11 - two-view geometry.

Short NumPy versions: everything is batched over the points, the 8-point
algorithms use Hartley-normalised coordinates, and the real-world pipeline is
the usual SIFT -> RANSAC F -> recoverPose -> triangulate chain.
"""

import cv2
import numpy as np


def _h(pts):
    """(N, 2) -> (N, 3) homogeneous."""
    pts = np.asarray(pts, float).reshape(-1, 2)
    return np.c_[pts, np.ones(len(pts))]


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
    x1, x2 = np.asarray(pts1, float).reshape(-1, 2), np.asarray(pts2, float).reshape(-1, 2)
    # rows x*p3 - p1, y*p3 - p2 for both views -> (N, 4, 4)
    A = np.concatenate([x1[:, :, None] * P1[2] - P1[:2], x2[:, :, None] * P2[2] - P2[:2]], axis=1)
    X = np.linalg.svd(A)[2][:, -1]
    return X[:, :3] / X[:, 3:]


# --------------------------------------------------------------------- ex2
def epipolar_lines(F, pts1):
    l = _h(pts1) @ np.asarray(F, float).T
    return l / np.hypot(l[:, 0], l[:, 1])[:, None]


def draw_epipolar_lines(image, lines):
    out = image.copy()
    h, w = out.shape[:2]
    palette = [(0, 0, 255), (0, 255, 0), (255, 0, 0), (0, 255, 255), (255, 0, 255), (255, 255, 0)]
    for i, (a, b, c) in enumerate(np.asarray(lines, float).reshape(-1, 3)):
        if a == 0 and b == 0:  # line at infinity: nothing to draw
            continue
        if abs(b) >= abs(a):  # mostly horizontal: cut the left/right borders
            p, q = (0, -c / b), (w - 1, -(c + a * (w - 1)) / b)
        else:                 # steep: cut the top/bottom borders
            p, q = (-c / a, 0), (-(c + b * (h - 1)) / a, h - 1)
        col = 255 if out.ndim == 2 else palette[i % len(palette)]
        cv2.line(out, tuple(int(round(v)) for v in p), tuple(int(round(v)) for v in q), col, 1)
    return out


# --------------------------------------------------------------------- ex3
def essential_from_fundamental(F, K1, K2):
    return np.asarray(K2, float).T @ np.asarray(F, float) @ np.asarray(K1, float)


def essential_8point(pts1, pts2, K1, K2):
    x1 = _h(pts1) @ np.linalg.inv(K1).T
    x2 = _h(pts2) @ np.linalg.inv(K2).T
    A = np.einsum("ni,nj->nij", x2, x1).reshape(-1, 9)
    E = np.linalg.svd(A)[2][-1].reshape(3, 3)
    U, _, Vt = np.linalg.svd(E)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt


# --------------------------------------------------------------------- ex4
def _normaliser(pts):
    c = pts.mean(0)
    s = np.sqrt(2) / np.linalg.norm(pts - c, axis=1).mean()
    return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])


def fundamental_8point(pts1, pts2):
    p1, p2 = np.asarray(pts1, float).reshape(-1, 2), np.asarray(pts2, float).reshape(-1, 2)
    T1, T2 = _normaliser(p1), _normaliser(p2)
    x1, x2 = _h(p1) @ T1.T, _h(p2) @ T2.T
    A = np.einsum("ni,nj->nij", x2, x1).reshape(-1, 9)
    # smallest eigenvector of A^T A == smallest right singular vector of A
    Fn = np.linalg.eigh(A.T @ A)[1][:, 0].reshape(3, 3)
    U, s, Vt = np.linalg.svd(Fn)
    Fn = U @ np.diag([s[0], s[1], 0.0]) @ Vt
    F = T2.T @ Fn @ T1
    return F / np.linalg.norm(F)


# --------------------------------------------------------------------- ex5
def epipoles(F):
    U, _, Vt = np.linalg.svd(np.asarray(F, float))
    return Vt[-1], U[:, -1]


# --------------------------------------------------------------------- ex6
def two_view_reconstruction(img1, img2, K):
    K = np.asarray(K, float)
    sift = cv2.SIFT_create()
    k1, d1 = sift.detectAndCompute(img1, None)
    k2, d2 = sift.detectAndCompute(img2, None)
    good = [m for m, n in (p for p in cv2.BFMatcher().knnMatch(d1, d2, k=2) if len(p) == 2)
            if m.distance < 0.75 * n.distance]
    p1 = np.float64([k1[m.queryIdx].pt for m in good])
    p2 = np.float64([k2[m.trainIdx].pt for m in good])

    F, mask = cv2.findFundamentalMat(p1, p2, cv2.FM_RANSAC, 1.0, 0.999)
    F = F[:3]
    keep = mask.ravel().astype(bool)
    p1, p2 = p1[keep], p2[keep]

    E = K.T @ F @ K
    _, R, t, _ = cv2.recoverPose(E, p1, p2, K)
    P1 = K @ np.eye(3, 4)
    P2 = K @ np.c_[R, t]
    X = cv2.triangulatePoints(P1, P2, p1.T, p2.T)
    X = (X[:3] / X[3]).T
    front = (X[:, 2] > 0) & ((X @ R.T + t.ravel())[:, 2] > 0)
    return F, p1[front], p2[front], X[front]
