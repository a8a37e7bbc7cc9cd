"""Lab 10 - geometric camera models, continued.

Projections, DLT and decomposition written from the lecture equations with
NumPy; the chessboard pose uses OpenCV as the lab sheet says.

- 3D points (N, 3) (or one (3,) point -> one (2,) result), 2D points (N, 2) of
  (x, y) = (column, row), y down; camera looks along +Z; X_cam = R X + t.
- P is defined up to a non-zero scale.
- Rotations are Rodrigues vectors (radians).
"""

import cv2
import numpy as np


def _as_points(points):
    pts = np.asarray(points, dtype=float)
    single = pts.ndim == 1
    return np.atleast_2d(pts).reshape(-1, 3), single


# --------------------------------------------------------------------- ex1
def perspective_project(points, f):
    """x = f X / Z, y = f Y / Z; NaN for points with Z <= 0 (no image)."""
    pts, single = _as_points(points)
    out = np.full((len(pts), 2), np.nan)
    Z = pts[:, 2]
    ok = Z > 0
    out[ok, 0] = f * pts[ok, 0] / Z[ok]
    out[ok, 1] = f * pts[ok, 1] / Z[ok]
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def weak_perspective_project(points, f, z_avg=None):
    """x = f X / z_avg, y = f Y / z_avg, z_avg the mean depth by default."""
    pts, single = _as_points(points)
    if z_avg is None:
        z_avg = np.mean(pts[:, 2])
    out = np.zeros((len(pts), 2))
    out[:, 0] = f * pts[:, 0] / z_avg
    out[:, 1] = f * pts[:, 1] / z_avg
    return out[0] if single else out


# --------------------------------------------------------------------- ex3
def orthographic_project(points):
    """[x, y, w] = M [X, Y, Z, 1] with M = [[1,0,0,0],[0,1,0,0],[0,0,0,1]]."""
    pts, single = _as_points(points)
    M = np.array([[1.0, 0.0, 0.0, 0.0],
                  [0.0, 1.0, 0.0, 0.0],
                  [0.0, 0.0, 0.0, 1.0]])
    X_h = np.hstack([pts, np.ones((len(pts), 1))])
    x_h = (M @ X_h.T).T
    out = x_h[:, :2] / x_h[:, 2:3]        # w is always 1 here
    return out[0] if single else out


# --------------------------------------------------------------------- ex4
def camera_matrix_dlt(points3d, points2d):
    """Camera matrix by the plain DLT: two rows per correspondence, SVD of A."""
    X = np.asarray(points3d, dtype=float).reshape(-1, 3)
    x = np.asarray(points2d, dtype=float).reshape(-1, 2)
    n = len(X)
    if n < 6:
        raise ValueError("need at least 6 correspondences")

    A = np.zeros((2 * n, 12))
    for i in range(n):
        Xi = np.array([X[i, 0], X[i, 1], X[i, 2], 1.0])
        u, v = x[i]
        A[2 * i, 0:4] = Xi
        A[2 * i, 8:12] = -u * Xi
        A[2 * i + 1, 4:8] = Xi
        A[2 * i + 1, 8:12] = -v * Xi

    _, _, Vt = np.linalg.svd(A)
    p = Vt[-1]                            # singular vector of the smallest singular value
    P = p.reshape(3, 4)
    return P


# --------------------------------------------------------------------- ex5
def decompose_camera_matrix(P):
    """P ~ K [R | t] via the lab sheet's recipe: QR decomposition of M^-1.

    M = K R  =>  M^-1 = R^T K^-1 = Q U  with Q orthogonal and U upper
    triangular, so R = Q^T and K = U^-1.
    """
    P = np.asarray(P, dtype=float).copy()
    M = P[:, :3]
    if np.linalg.det(M) < 0:              # fix the sign so that det(R) = +1
        P = -P
        M = P[:, :3]

    Q, U = np.linalg.qr(np.linalg.inv(M))
    R = Q.T
    K = np.linalg.inv(U)

    # make the diagonal of K positive: K R = (K D)(D R) with D = diag(+-1)
    signs = np.sign(np.diag(K))
    signs[signs == 0] = 1.0
    D = np.diag(signs)
    K = K @ D
    R = D @ R

    t = np.linalg.solve(K, P[:, 3])       # t = K^-1 p4
    K = K / K[2, 2]
    return K, R, t


def camera_center(P):
    """The null vector of P (last right singular vector), dehomogenised."""
    P = np.asarray(P, dtype=float)
    _, _, Vt = np.linalg.svd(P)
    C = Vt[-1]
    return C[:3] / C[3]


# --------------------------------------------------------------------- ex6
def _board_points(pattern_size, square_size):
    cols, rows = pattern_size
    obj = np.zeros((cols * rows, 3), np.float32)
    obj[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
    return obj


def _distort(xn, dist):
    """Brown-Conrady distortion of normalised points (N, 2)."""
    k1, k2, p1, p2, k3 = dist
    x, y = xn[:, 0], xn[:, 1]
    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    return np.column_stack([xd, yd])


def _dist5(dist):
    d = np.zeros(5)
    if dist is not None:
        dd = np.asarray(dist, dtype=float).ravel()
        d[:min(5, dd.size)] = dd[:5]
    return d


def estimate_pose(image, pattern_size, square_size, K, dist=None):
    """Chessboard pose with cv2.findChessboardCorners / cornerSubPix / solvePnP.

    The corners are projected back by hand: X_cam = R X + t, normalise,
    distort, apply K.
    """
    pattern_size = (int(pattern_size[0]), int(pattern_size[1]))
    K = np.asarray(K, dtype=float)
    d = _dist5(dist)
    gray = image if image.ndim == 2 else cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)

    found, corners = cv2.findChessboardCorners(gray, pattern_size, None)
    if not found:
        return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))

    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)
    corners = cv2.cornerSubPix(gray, corners, (11, 11), (-1, -1), criteria)

    obj = _board_points(pattern_size, square_size)
    ok, rvec, tvec = cv2.solvePnP(obj, corners, K, d)
    rvec = rvec.ravel().astype(float)
    tvec = tvec.ravel().astype(float)

    # reproject by hand
    R, _ = cv2.Rodrigues(rvec)
    Xc = obj.astype(float) @ R.T + tvec
    xn = Xc[:, :2] / Xc[:, 2:3]
    xd = _distort(xn, d)
    u = K[0, 0] * xd[:, 0] + K[0, 1] * xd[:, 1] + K[0, 2]
    v = K[1, 1] * xd[:, 1] + K[1, 2]
    reprojected = np.column_stack([u, v])
    return rvec, tvec, reprojected


# --------------------------------------------------------------------- ext1
def undistort_image(image, K, dist):
    """Inverse mapping: for every pixel of the ideal image find where the
    distorted camera saw it, then sample there (bilinear, black outside)."""
    K = np.asarray(K, dtype=float)
    d = _dist5(dist)
    h, w = image.shape[:2]
    u, v = np.meshgrid(np.arange(w, dtype=float), np.arange(h, dtype=float))

    # pixel -> normalised coordinates with K^-1
    pix = np.stack([u.ravel(), v.ravel(), np.ones(u.size)])
    norm = np.linalg.inv(K) @ pix
    xn = (norm[:2] / norm[2]).T

    # distort, back to pixels
    xd = _distort(xn, d)
    src = K @ np.vstack([xd.T, np.ones(len(xd))])
    map_x = (src[0] / src[2]).reshape(h, w).astype(np.float32)
    map_y = (src[1] / src[2]).reshape(h, w).astype(np.float32)

    out = cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR,
                    borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return out


# --------------------------------------------------------------------- ext2
def dolly_zoom(points, f0, z0, distances):
    """Move the camera so the subject is at distance d and zoom to f0 d / z0."""
    pts, _ = _as_points(points)
    distances = np.atleast_1d(np.asarray(distances, dtype=float))
    focal_lengths = np.zeros(len(distances))
    projections = np.zeros((len(distances), len(pts), 2))
    for i, d in enumerate(distances):
        moved = pts.copy()
        moved[:, 2] = pts[:, 2] + (d - z0)
        focal_lengths[i] = f0 * d / z0
        projections[i] = perspective_project(moved, focal_lengths[i])
    return focal_lengths, projections


# --------------------------------------------------------------------- ext3
def track_pose(frames, pattern_size, square_size, K, dist=None):
    """[rvec, tvec] for every frame (NaN where the board is not found)."""
    poses = np.full((len(frames), 6), np.nan)
    for i, frame in enumerate(frames):
        rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
        poses[i, :3] = rvec
        poses[i, 3:] = tvec
    return poses
