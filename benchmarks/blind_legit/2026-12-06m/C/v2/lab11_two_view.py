"""Lab 11 - two-view geometry (vectorised NumPy, Hartley normalisation, OpenCV in ex6).

Conventions
-----------
Points are (N, 2) arrays of (x, y) pixels. F satisfies x2^T F x1 = 0,
E = K2^T F K1. Projective answers are returned at whatever scale falls out.
"""

import cv2
import numpy as np


def _homog(pts):
    """(N, 2) points -> (N, 3) homogeneous points with w = 1."""
    p = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    return np.hstack([p, np.ones((p.shape[0], 1))])


def _skew(v):
    """Stack of cross-product matrices [v]_x for an (N, 3) array -> (N, 3, 3)."""
    z = np.zeros(len(v))
    return np.stack([
        np.stack([z, -v[:, 2], v[:, 1]], axis=-1),
        np.stack([v[:, 2], z, -v[:, 0]], axis=-1),
        np.stack([-v[:, 1], v[:, 0], z], axis=-1),
    ], axis=1)


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear triangulation using the full cross products.

    x x (P X) = [x]_x P X = 0 gives three equations per view (only two are
    independent); I keep all three, so A is 6 x 4 for each point. Each row is
    scaled to unit length so that the two views weigh the same. All the points
    are solved at once with a stacked SVD.
    """
    P1 = np.asarray(P1, dtype=np.float64)
    P2 = np.asarray(P2, dtype=np.float64)
    one_point = np.ndim(pts1) == 1
    x1 = _homog(pts1)
    x2 = _homog(pts2)

    A = np.concatenate([_skew(x1) @ P1, _skew(x2) @ P2], axis=1)   # (N, 6, 4)
    A = A / np.linalg.norm(A, axis=2, keepdims=True)
    _, _, Vt = np.linalg.svd(A)
    Xh = Vt[:, -1, :]                       # (N, 4) null vectors
    X = Xh[:, :3] / Xh[:, 3:4]
    return X[0] if one_point else X


# --------------------------------------------------------------------- ex2
def epipolar_lines(F, pts1):
    """l' = F x for every point, normalised to a^2 + b^2 = 1."""
    L = _homog(pts1) @ np.asarray(F, dtype=np.float64).T     # rows are (F x)^T
    return L / np.hypot(L[:, 0], L[:, 1])[:, None]


def draw_epipolar_lines(image, lines):
    """Draw the lines on a colour copy, clipped to the image with cv2.clipLine.

    A grey input is converted to BGR first so that every line can have its own
    colour.
    """
    if image.ndim == 2:
        canvas = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
    else:
        canvas = image.copy()
    h, w = canvas.shape[:2]
    rng = np.random.default_rng(7)
    big = 4.0 * (w + h)
    for a, b, c in np.asarray(lines, dtype=np.float64).reshape(-1, 3):
        n = np.hypot(a, b)
        if n == 0:
            continue
        # point of the line closest to the image centre, and the line direction
        cx, cy = (w - 1) / 2.0, (h - 1) / 2.0
        dist = (a * cx + b * cy + c) / n
        px, py = cx - dist * a / n, cy - dist * b / n
        dx, dy = -b / n, a / n
        p = (int(round(px - big * dx)), int(round(py - big * dy)))
        q = (int(round(px + big * dx)), int(round(py + big * dy)))
        ok, p, q = cv2.clipLine((0, 0, w, h), p, q)
        if not ok:
            continue
        # a random bright colour: hue random, full saturation and value
        hue = np.uint8(rng.integers(0, 180))
        bgr = cv2.cvtColor(np.array([[[hue, 255, 255]]], np.uint8), cv2.COLOR_HSV2BGR)[0, 0]
        cv2.line(canvas, p, q, tuple(int(v) for v in bgr), 2)
    return canvas


# --------------------------------------------------------------------- ex3
def essential_from_fundamental(F, K1, K2):
    """E = K2^T F K1."""
    return np.linalg.multi_dot([np.asarray(K2, np.float64).T,
                                np.asarray(F, np.float64),
                                np.asarray(K1, np.float64)])


def essential_8point(pts1, pts2, K1, K2):
    """The lab sheet's route: F by the (normalised) 8-point algorithm, E = K2^T F K1,
    then the closest matrix with singular values (s, s, 0)."""
    F = fundamental_8point(pts1, pts2)
    E = essential_from_fundamental(F, K1, K2)
    U, S, Vt = np.linalg.svd(E)
    s = (S[0] + S[1]) / 2.0
    return U @ np.diag([s, s, 0.0]) @ Vt


# --------------------------------------------------------------------- ex4
def _hartley(p):
    """Similarity T moving the centroid to 0 and the RMS distance to sqrt(2)."""
    c = p.mean(axis=0)
    rms = np.sqrt(np.mean(np.sum((p - c) ** 2, axis=1)))
    s = np.sqrt(2.0) / rms if rms > 0 else 1.0
    return np.array([[s, 0, -s * c[0]],
                     [0, s, -s * c[1]],
                     [0, 0, 1.0]])


def fundamental_8point(pts1, pts2):
    """Normalised 8-point algorithm (Hartley) with the rank-2 constraint."""
    p1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
    p2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
    T1, T2 = _hartley(p1), _hartley(p2)
    x1 = _homog(p1) @ T1.T
    x2 = _homog(p2) @ T2.T

    # rows x2n x1n^T flattened: x2n^T Fn x1n = 0
    A = (x2[:, :, None] * x1[:, None, :]).reshape(-1, 9)
    # null vector = eigenvector of A^T A with the smallest eigenvalue
    w, V = np.linalg.eigh(A.T @ A)
    Fn = V[:, 0].reshape(3, 3)

    U, S, Vt = np.linalg.svd(Fn)
    Fn = U @ np.diag([S[0], S[1], 0.0]) @ Vt
    F = T2.T @ Fn @ T1
    return F / np.linalg.norm(F)


# --------------------------------------------------------------------- ex5
def epipoles(F):
    """Null vectors from the symmetric eigenproblems F^T F and F F^T.

    F e1 = 0  <=>  e1 is the eigenvector of F^T F with eigenvalue 0 (the smallest);
    F^T e2 = 0 <=> e2 is the eigenvector of F F^T with eigenvalue 0.
    """
    F = np.asarray(F, dtype=np.float64)
    _, V1 = np.linalg.eigh(F.T @ F)
    _, V2 = np.linalg.eigh(F @ F.T)
    return V1[:, 0].copy(), V2[:, 0].copy()


# --------------------------------------------------------------------- ex6
def two_view_reconstruction(img1, img2, K):
    """SIFT + FLANN ratio test, E by RANSAC (cv2.findEssentialMat), F = K^-T E K^-1,
    pose by cv2.recoverPose, points by cv2.triangulatePoints."""
    K = np.asarray(K, dtype=np.float64)
    sift = cv2.SIFT_create(nfeatures=4000)
    kp1, d1 = sift.detectAndCompute(img1, None)
    kp2, d2 = sift.detectAndCompute(img2, None)

    flann = cv2.FlannBasedMatcher(dict(algorithm=1, trees=5), dict(checks=64))
    knn = flann.knnMatch(d1.astype(np.float32), d2.astype(np.float32), k=2)
    good = [m for m, *rest in knn if rest and m.distance < 0.8 * rest[0].distance]
    pts1 = np.float32([kp1[m.queryIdx].pt for m in good])
    pts2 = np.float32([kp2[m.trainIdx].pt for m in good])

    E, mask = cv2.findEssentialMat(pts1, pts2, K, method=cv2.RANSAC,
                                   prob=0.999, threshold=1.0)
    E = E[:3]
    _, R, t, pose_mask = cv2.recoverPose(E, pts1, pts2, K, mask=mask.copy())
    keep = pose_mask.ravel() > 0
    pts1, pts2 = pts1[keep], pts2[keep]

    Kinv = np.linalg.inv(K)
    F = Kinv.T @ E @ Kinv

    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K @ np.hstack([R, t.reshape(3, 1)])
    Xh = cv2.triangulatePoints(P1, P2, pts1.T.astype(np.float64), pts2.T.astype(np.float64))
    X = (Xh[:3] / Xh[3]).T

    in_front = (X[:, 2] > 0) & ((X @ R.T + t.reshape(1, 3))[:, 2] > 0)
    return (F, pts1[in_front].astype(np.float64), pts2[in_front].astype(np.float64),
            X[in_front])
