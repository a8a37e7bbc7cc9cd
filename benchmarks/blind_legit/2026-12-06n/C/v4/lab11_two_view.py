"""Lab 11 - two-view geometry (following Hartley & Zisserman, "Multiple View
Geometry", 2nd ed., and the OpenCV epipolar-geometry tutorial).

- ex1: the homogeneous DLT triangulation of H&Z section 12.2, with each point
  pair pre-conditioned (H&Z 4.4) before the SVD.
- ex3/ex4: the normalised 8-point algorithm (H&Z algorithm 11.1) with the
  RMS-distance sqrt(2) normalisation; the null vector is found from a QR
  decomposition of A followed by an SVD of the small triangular factor.
- ex5: epipoles as eigenvectors of F^T F and F F^T (smallest eigenvalue).
- ex6: SIFT + ratio test, F by RANSAC, E = K^T F K, the four (R, t) candidates
  of H&Z result 9.19 and the cheirality test, triangulation with
  cv2.triangulatePoints (allowed in ex6).
"""

import cv2
import numpy as np


def _to_h(pts):
    p = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    return np.column_stack([p, np.ones(len(p))])


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear (DLT) triangulation, H&Z section 12.2.

    For each correspondence the 4 x 4 matrix
        A = [x p3^T - p1^T ; y p3^T - p2^T ; x' p3'^T - p1'^T ; y' p3'^T - p2'^T]
    is built; X is its right null vector. Before the SVD I normalise the
    columns of A (a diagonal change of variables X = D Y), which keeps the
    system well conditioned when world coordinates are large.
    """
    P1 = np.asarray(P1, dtype=np.float64)
    P2 = np.asarray(P2, dtype=np.float64)
    a = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
    b = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)

    A = np.empty((len(a), 4, 4))
    A[:, 0] = a[:, [0]] * P1[2] - P1[0]
    A[:, 1] = a[:, [1]] * P1[2] - P1[1]
    A[:, 2] = b[:, [0]] * P2[2] - P2[0]
    A[:, 3] = b[:, [1]] * P2[2] - P2[1]

    # column scaling D (per point): A X = 0  <=>  (A D) Y = 0 with X = D Y
    d = np.linalg.norm(A, axis=1)                       # (N, 4)
    d = np.where(d > 0, 1.0 / d, 1.0)
    _, _, Vt = np.linalg.svd(A * d[:, None, :])
    X = Vt[:, -1, :] * d
    X = X[:, :3] / X[:, 3:4]
    return X[0] if np.ndim(pts1) == 1 else X          # one pair in, one point out


# --------------------------------------------------------------------- ex2
def epipolar_lines(F, pts1):
    """l' = F x for each x, normalised so a^2 + b^2 = 1."""
    F = np.asarray(F, dtype=np.float64)
    lines = (F @ _to_h(pts1).T).T
    return lines / np.sqrt(lines[:, 0] ** 2 + lines[:, 1] ** 2)[:, None]


def draw_epipolar_lines(image, lines):
    """Draw the lines across the image as in the OpenCV epipolar tutorial.

    Mostly horizontal lines (|b| >= |a|) are cut at x = 0 and x = W - 1, the
    others at y = 0 and y = H - 1. Colours come from a seeded generator, lifted
    so that no channel combination is dark; grey images get white lines.
    """
    out = image.copy()
    h, w = out.shape[:2]
    rng = np.random.default_rng(0)
    for a, b, c in np.asarray(lines, dtype=np.float64).reshape(-1, 3):
        if abs(b) >= abs(a):
            if b == 0:
                continue
            p = (0, -c / b)
            q = (w - 1, -(c + a * (w - 1)) / b)
        else:
            p = (-c / a, 0)
            q = (-(c + b * (h - 1)) / a, h - 1)
        if not np.all(np.isfinite(p + q)) or max(map(abs, p + q)) > 1e8:
            continue
        p = tuple(int(round(v)) for v in p)
        q = tuple(int(round(v)) for v in q)
        if out.ndim == 2:
            colour = 255
        else:
            colour = rng.integers(0, 256, 3)
            k = rng.integers(0, 3)
            colour[k] = 255                           # one full channel ...
            colour[(k + 1) % 3] = rng.integers(0, 100)  # ... and one low: a real colour
            colour = tuple(int(v) for v in colour)
        cv2.line(out, p, q, colour, 1)
    return out


# --------------------------------------------------------------------- ex3
def essential_from_fundamental(F, K1, K2):
    """E = K'^T F K (H&Z eq. 9.12)."""
    return np.asarray(K2, float).T @ np.asarray(F, float) @ np.asarray(K1, float)


def _null_vector_qr(A):
    """Right null vector of a tall matrix: A = Q R, then the SVD of the 9x9 R."""
    R = np.linalg.qr(A, mode="r")
    if R.shape[0] < A.shape[1]:   # fewer rows than unknowns: pad with zeros
        R = np.vstack([R, np.zeros((A.shape[1] - R.shape[0], A.shape[1]))])
    return np.linalg.svd(R)[2][-1]


def _hartley_T(p):
    """Similarity taking the points to centroid 0, RMS distance sqrt(2)."""
    c = p.mean(axis=0)
    rms = np.sqrt(np.mean(np.sum((p - c) ** 2, axis=1)))
    s = np.sqrt(2.0) / rms if rms > 0 else 1.0
    return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1.0]])


def _eight_point(x1, x2):
    """Rows of A: kron(x2, x1) so that A vec(F) = 0 with F flattened row by row."""
    A = np.einsum("ni,nj->nij", x2, x1).reshape(len(x1), 9)
    return _null_vector_qr(A).reshape(3, 3)


def essential_8point(pts1, pts2, K1, K2):
    """E from normalised coordinates, then the projection onto the essential
    manifold: singular values (1, 1, 0) (H&Z 11.7.3)."""
    x1 = np.linalg.solve(np.asarray(K1, float), _to_h(pts1).T).T
    x2 = np.linalg.solve(np.asarray(K2, float), _to_h(pts2).T).T
    E = _eight_point(x1, x2)
    U, _, Vt = np.linalg.svd(E)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt


# --------------------------------------------------------------------- ex4
def fundamental_8point(pts1, pts2):
    """The normalised 8-point algorithm, H&Z algorithm 11.1."""
    p1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
    p2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
    T1, T2 = _hartley_T(p1), _hartley_T(p2)
    Fn = _eight_point(_to_h(p1) @ T1.T, _to_h(p2) @ T2.T)
    U, s, Vt = np.linalg.svd(Fn)
    Fn = U @ np.diag([s[0], s[1], 0.0]) @ Vt        # closest rank-2 matrix
    F = T2.T @ Fn @ T1
    return F / np.linalg.norm(F)


# --------------------------------------------------------------------- ex5
def epipoles(F):
    """e1: eigenvector of F^T F, e2: eigenvector of F F^T, smallest eigenvalue.

    F e1 = 0 means e1 minimises |F e|^2 = e^T F^T F e over unit vectors, i.e.
    the eigenvector of the symmetric matrix F^T F with the smallest eigenvalue
    (np.linalg.eigh sorts them in ascending order).
    """
    F = np.asarray(F, dtype=np.float64)
    e1 = np.linalg.eigh(F.T @ F)[1][:, 0]
    e2 = np.linalg.eigh(F @ F.T)[1][:, 0]
    return e1, e2


# --------------------------------------------------------------------- ex6
def _pose_candidates(E):
    """The four (R, t) of H&Z result 9.19."""
    U, _, Vt = np.linalg.svd(E)
    if np.linalg.det(U) < 0:
        U = -U
    if np.linalg.det(Vt) < 0:
        Vt = -Vt
    W = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1.0]])
    t = U[:, 2]
    return [(U @ W @ Vt, t), (U @ W @ Vt, -t), (U @ W.T @ Vt, t), (U @ W.T @ Vt, -t)]


def two_view_reconstruction(img1, img2, K):
    """SIFT matches -> RANSAC F -> E -> the pose that puts most points in front."""
    K = np.asarray(K, dtype=np.float64)
    sift = cv2.SIFT_create()
    g1 = cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY) if img1.ndim == 3 else img1
    g2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY) if img2.ndim == 3 else img2
    kp1, des1 = sift.detectAndCompute(g1, None)
    kp2, des2 = sift.detectAndCompute(g2, None)

    matches = cv2.BFMatcher(cv2.NORM_L2).knnMatch(des1, des2, k=2)
    good = [m for m, n in (p for p in matches if len(p) == 2) if m.distance < 0.75 * n.distance]
    pts1 = np.array([kp1[m.queryIdx].pt for m in good], dtype=np.float64)
    pts2 = np.array([kp2[m.trainIdx].pt for m in good], dtype=np.float64)

    F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
    F = F[:3]
    inl = mask.ravel() == 1
    pts1, pts2 = pts1[inl], pts2[inl]

    E = K.T @ F @ K
    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    best = None
    for R, t in _pose_candidates(E):
        P2 = K @ np.hstack([R, t[:, None]])
        Xh = cv2.triangulatePoints(P1, P2, pts1.T, pts2.T)
        X = (Xh[:3] / Xh[3]).T
        z1 = X[:, 2]
        z2 = (X @ R.T + t)[:, 2]
        n_front = np.count_nonzero((z1 > 0) & (z2 > 0))
        if best is None or n_front > best[0]:
            best = (n_front, X, (z1 > 0) & (z2 > 0))
    _, X, front = best
    return F, pts1[front], pts2[front], X[front]
