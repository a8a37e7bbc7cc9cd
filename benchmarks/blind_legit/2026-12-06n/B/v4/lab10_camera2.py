"""Lab 10 - geometric camera models, continued.

Written after Hartley & Zisserman (ch. 6-7: camera models, DLT, decomposition
of P) and the OpenCV calibration / pose tutorials.

Conventions: 3D points (N, 3) or a single (3,) point; 2D points (N, 2) of
(x, y) = (column, row), y down; X_cam = R X + t; rvec is a Rodrigues vector.
Points behind the camera (Z <= 0) get NaN in the projections.
"""

import cv2
import numpy as np


def _as_points(points, dim):
    pts = np.asarray(points, dtype=np.float64)
    single = pts.ndim == 1
    return np.atleast_2d(pts).reshape(-1, dim), single


# --------------------------------------------------------------------- ex1
def perspective_project(points, f):
    """x = f X / Z, y = f Y / Z; NaN for points with Z <= 0."""
    X, single = _as_points(points, 3)
    out = np.full((X.shape[0], 2), np.nan)
    front = X[:, 2] > 0
    out[front] = f * X[front, :2] / X[front, 2:3]
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def weak_perspective_project(points, f, z_avg=None):
    """x = f X / z_avg, y = f Y / z_avg (z_avg defaults to the mean depth).

    Weak perspective = orthographic projection followed by one isotropic
    scaling f / z_avg (H&Z sec. 6.3.1).
    """
    X, single = _as_points(points, 3)
    if z_avg is None:
        z_avg = X[:, 2].mean()
    scale = float(f) / float(z_avg)
    out = scale * X[:, :2]
    return out[0] if single else out


# --------------------------------------------------------------------- ex3
def orthographic_project(points):
    """[x, y, w] = M [X, Y, Z, 1] with M = [[1,0,0,0],[0,1,0,0],[0,0,0,1]]."""
    X, single = _as_points(points, 3)
    M = np.array([[1.0, 0.0, 0.0, 0.0],
                  [0.0, 1.0, 0.0, 0.0],
                  [0.0, 0.0, 0.0, 1.0]])
    Xh = np.hstack([X, np.ones((X.shape[0], 1))])
    xh = Xh @ M.T
    out = xh[:, :2] / xh[:, 2:3]
    return out[0] if single else out


# --------------------------------------------------------------------- ex4
def _normalising_transform(pts):
    """Similarity T with the centroid at 0 and unit standard deviation per axis."""
    mean = pts.mean(axis=0)
    std = pts.std(axis=0)
    std[std < 1e-12] = 1.0
    d = pts.shape[1]
    T = np.eye(d + 1)
    T[:d, :d] = np.diag(1.0 / std)
    T[:d, d] = -mean / std
    return T


def camera_matrix_dlt(points3d, points2d):
    """Normalised DLT (H&Z algorithm 7.1), solved as an eigenvalue problem.

    The minimiser of ||A p|| with ||p|| = 1 is the eigenvector of A^T A with
    the smallest eigenvalue (the same vector SVD gives as the last row of Vt).
    """
    Xw = np.asarray(points3d, dtype=np.float64).reshape(-1, 3)
    xi = np.asarray(points2d, dtype=np.float64).reshape(-1, 2)
    if Xw.shape[0] < 6 or Xw.shape[0] != xi.shape[0]:
        raise ValueError("need at least 6 matching 3D-2D correspondences")

    U = _normalising_transform(Xw)          # 4 x 4
    T = _normalising_transform(xi)          # 3 x 3
    Xn = np.hstack([Xw, np.ones((len(Xw), 1))]) @ U.T
    xn = np.hstack([xi, np.ones((len(xi), 1))]) @ T.T
    xn = xn[:, :2] / xn[:, 2:3]

    rows = []
    zero = np.zeros(4)
    for Xh, (u, v) in zip(Xn, xn):
        rows.append(np.concatenate([Xh, zero, -u * Xh]))
        rows.append(np.concatenate([zero, Xh, -v * Xh]))
    A = np.array(rows)

    eigvals, eigvecs = np.linalg.eigh(A.T @ A)   # ascending eigenvalues
    Pn = eigvecs[:, 0].reshape(3, 4)

    # undo the normalisation: x = T^-1 Pn U X
    P = np.linalg.inv(T) @ Pn @ U
    return P / np.linalg.norm(P)


# --------------------------------------------------------------------- ex5
def decompose_camera_matrix(P):
    """P ~ K [R | t], by the lab sheet's route: QR of M^-1.

    M^-1 = Q U (Q orthogonal, U upper triangular) gives M = U^-1 Q^T, and
    U^-1 is upper triangular: K = U^-1, R = Q^T.
    """
    P = np.asarray(P, dtype=np.float64).copy()
    if np.linalg.det(P[:, :3]) < 0:       # P is only known up to sign
        P = -P
    M = P[:, :3]

    Q, U = np.linalg.qr(np.linalg.inv(M))
    K = np.linalg.inv(U)
    R = Q.T

    # positive diagonal of K: K R = (K D)(D R) with D = diag(+-1)
    D = np.diag(np.sign(np.diag(K)))
    K = K @ D
    R = D @ R

    t = np.linalg.solve(K, P[:, 3])       # same scale as K before normalising
    K = K / K[2, 2]
    return K, R, t


def camera_center(P):
    """Camera centre from the determinants of P's columns (H&Z eq. 6.13).

    C = (det[p2,p3,p4], -det[p1,p3,p4], det[p1,p2,p4], -det[p1,p2,p3]).
    """
    P = np.asarray(P, dtype=np.float64)
    cols = [P[:, i] for i in range(4)]

    def det3(a, b, c):
        return np.linalg.det(np.column_stack([a, b, c]))

    X = det3(cols[1], cols[2], cols[3])
    Y = -det3(cols[0], cols[2], cols[3])
    Z = det3(cols[0], cols[1], cols[3])
    T = -det3(cols[0], cols[1], cols[2])
    return np.array([X, Y, Z]) / T


def _subpix_window(corners, pattern):
    """Half-size of the cornerSubPix window.

    The OpenCV tutorial uses (11, 11), i.e. a 23 x 23 search window; on a small
    or oblique board that is wider than a square and the refinement can jump
    to a neighbouring corner.  I keep the window below a third of the smallest
    distance between neighbouring corners (at most the tutorial's 11).
    """
    cols, rows = pattern
    grid = corners.reshape(rows, cols, 2)
    gaps = []
    if cols > 1:
        gaps.append(np.linalg.norm(np.diff(grid, axis=1), axis=2).min())
    if rows > 1:
        gaps.append(np.linalg.norm(np.diff(grid, axis=0), axis=2).min())
    spacing = min(gaps) if gaps else 33.0
    half = int(np.clip(spacing / 3.0, 2, 11))
    return (half, half)


# --------------------------------------------------------------------- ex6
def _board_points(pattern_size, square_size):
    cols, rows = int(pattern_size[0]), int(pattern_size[1])
    objp = np.zeros((cols * rows, 3), np.float32)
    objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
    return objp


def estimate_pose(image, pattern_size, square_size, K, dist=None):
    """Chessboard pose, as in the OpenCV "Pose Estimation" tutorial."""
    nan3 = np.full(3, np.nan)
    img = np.asarray(image)
    grey = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY) if img.ndim == 3 else img
    grey = np.ascontiguousarray(grey, dtype=np.uint8)
    pattern = (int(pattern_size[0]), int(pattern_size[1]))

    found, corners = cv2.findChessboardCorners(grey, pattern, None)
    if not found:
        return nan3, nan3.copy(), np.zeros((0, 2))
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 0.001)
    win = _subpix_window(corners, pattern)
    corners = cv2.cornerSubPix(grey, corners, win, (-1, -1), criteria)

    objp = _board_points(pattern, square_size)
    K = np.asarray(K, dtype=np.float64)
    d = np.zeros(5) if dist is None else np.asarray(dist, dtype=np.float64).ravel()
    ok, rvec, tvec = cv2.solvePnP(objp, corners, K, d)
    if not ok:
        return nan3, nan3.copy(), np.zeros((0, 2))
    reproj, _ = cv2.projectPoints(objp, rvec, tvec, K, d)
    return rvec.ravel().astype(np.float64), tvec.ravel().astype(np.float64), \
        reproj.reshape(-1, 2).astype(np.float64)


# --------------------------------------------------------------------- ext1
def undistort_image(image, K, dist):
    """Undistort with cv2.remap and maps I build myself.

    For every pixel (u, v) of the ideal image: back to normalised coordinates
    with K^-1, apply the distortion model, back to pixels with K; that is where
    the distorted image must be sampled (bilinear, black outside).
    """
    img = np.ascontiguousarray(image)
    K = np.asarray(K, dtype=np.float64)
    d = np.zeros(5)
    dd = np.asarray(dist, dtype=np.float64).ravel()[:5]
    d[:dd.size] = dd
    k1, k2, p1, p2, k3 = d

    h, w = img.shape[:2]
    u, v = np.meshgrid(np.arange(w, dtype=np.float64),
                       np.arange(h, dtype=np.float64))
    pix = np.stack([u.ravel(), v.ravel(), np.ones(u.size)])
    x, y, _ = np.linalg.inv(K) @ pix

    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y

    src = K @ np.stack([xd, yd, np.ones_like(xd)])
    map_x = src[0].reshape(h, w).astype(np.float32)
    map_y = src[1].reshape(h, w).astype(np.float32)
    return cv2.remap(img, map_x, map_y, interpolation=cv2.INTER_LINEAR,
                     borderMode=cv2.BORDER_CONSTANT, borderValue=0)


# --------------------------------------------------------------------- ext2
def dolly_zoom(points, f0, z0, distances):
    """Vertigo effect: move to distance d and zoom to f0 d / z0."""
    X, _ = _as_points(points, 3)
    ds = np.asarray(distances, dtype=np.float64).ravel()
    focal_lengths = f0 * ds / z0
    projections = np.empty((ds.size, X.shape[0], 2))
    for i, (d, f) in enumerate(zip(ds, focal_lengths)):
        moved = X.copy()
        moved[:, 2] += d - z0             # the camera slides along its axis
        projections[i] = perspective_project(moved, f)
    return focal_lengths, projections


# --------------------------------------------------------------------- ext3
def track_pose(frames, pattern_size, square_size, K, dist=None):
    """[rvec, tvec] per frame (NaN where the board is lost)."""
    rows = []
    for frame in frames:
        rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
        rows.append(np.concatenate([rvec, tvec]))
    return np.array(rows, dtype=np.float64).reshape(-1, 6)
