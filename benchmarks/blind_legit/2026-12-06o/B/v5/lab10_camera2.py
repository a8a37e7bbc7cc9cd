"""Lab 10 - geometric camera models, continued.

Compact NumPy / SciPy / OpenCV versions.
"""

import cv2
import numpy as np
from scipy.linalg import rq


def _pts3(points):
    p = np.asarray(points, dtype=float)
    return np.atleast_2d(p), p.ndim == 1


# --------------------------------------------------------------------- ex1
def perspective_project(points, f):
    """x = f X / Z, y = f Y / Z; NaN for Z <= 0."""
    p, single = _pts3(points)
    z = p[:, 2:3]
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(z > 0, f * p[:, :2] / z, np.nan)
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def weak_perspective_project(points, f, z_avg=None):
    """x = f X / z_avg, y = f Y / z_avg (z_avg = mean Z by default)."""
    p, single = _pts3(points)
    z = p[:, 2].mean() if z_avg is None else float(z_avg)
    out = f * p[:, :2] / z
    return out[0] if single else out


# --------------------------------------------------------------------- ex3
ORTHO = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)


def orthographic_project(points):
    """[x, y, w] = M [X, Y, Z, 1], then (x/w, y/w) - w is always 1."""
    p, single = _pts3(points)
    xyw = np.c_[p, np.ones(len(p))] @ ORTHO.T
    out = xyw[:, :2] / xyw[:, 2:]
    return out[0] if single else out


# --------------------------------------------------------------------- ex4
def _similarity(x):
    """Hartley normalisation: centroid to 0, mean distance sqrt(dim)."""
    c = x.mean(0)
    s = np.sqrt(x.shape[1]) / np.linalg.norm(x - c, axis=1).mean()
    T = np.eye(x.shape[1] + 1)
    T[:-1, :-1] *= s
    T[:-1, -1] = -s * c
    return T


def camera_matrix_dlt(points3d, points2d):
    """Normalised DLT: stack [X^T 0 -uX^T; 0 X^T -vX^T], smallest right singular vector."""
    X = np.asarray(points3d, float).reshape(-1, 3)
    x = np.asarray(points2d, float).reshape(-1, 2)
    T3, T2 = _similarity(X), _similarity(x)
    Xh = np.c_[X, np.ones(len(X))] @ T3.T
    xh = np.c_[x, np.ones(len(x))] @ T2.T
    xh = xh[:, :2] / xh[:, 2:]
    Z = np.zeros_like(Xh)
    A = np.vstack([np.hstack([Xh, Z, -xh[:, :1] * Xh]),
                   np.hstack([Z, Xh, -xh[:, 1:] * Xh])])
    Pn = np.linalg.svd(A)[2][-1].reshape(3, 4)
    P = np.linalg.inv(T2) @ Pn @ T3
    return P / np.linalg.norm(P)


# --------------------------------------------------------------------- ex5
def decompose_camera_matrix(P):
    """RQ of M = P[:, :3] -> K R, signs fixed so diag(K) > 0 and det(R) = +1."""
    P = np.asarray(P, float)
    if np.linalg.det(P[:, :3]) < 0:
        P = -P
    K, R = rq(P[:, :3])
    D = np.diag(np.sign(np.diag(K)))
    K, R = K @ D, D @ R                 # D = D^-1
    t = np.linalg.solve(K, P[:, 3])
    return K / K[2, 2], R, t


def camera_center(P):
    """Null vector of P (SVD), dehomogenised."""
    C = np.linalg.svd(np.asarray(P, float))[2][-1]
    return C[:3] / C[3]


# --------------------------------------------------------------------- ex6
def _board(pattern_size, square_size):
    cols, rows = pattern_size
    obj = np.zeros((cols * rows, 3), np.float64)
    obj[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
    return obj


def estimate_pose(image, pattern_size, square_size, K, dist=None):
    """findChessboardCorners + cornerSubPix + solvePnP + projectPoints."""
    g = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else np.ascontiguousarray(image)
    ok, corners = cv2.findChessboardCorners(g, tuple(int(v) for v in pattern_size))
    if not ok:
        return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))
    corners = cv2.cornerSubPix(g, corners, (5, 5), (-1, -1),
                               (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3))
    K = np.asarray(K, float)
    dist = np.zeros(5) if dist is None else np.asarray(dist, float).ravel()
    obj = _board(pattern_size, square_size)
    _, rvec, tvec = cv2.solvePnP(obj, corners.astype(np.float64), K, dist)
    rep, _ = cv2.projectPoints(obj, rvec, tvec, K, dist)
    return rvec.ravel(), tvec.ravel(), rep.reshape(-1, 2)


# --------------------------------------------------------------------- ext1
def undistort_image(image, K, dist):
    """cv2.undistort with the same K as the new camera matrix."""
    return cv2.undistort(np.ascontiguousarray(image), np.asarray(K, float),
                         np.asarray(dist, float).ravel())


# --------------------------------------------------------------------- ext2
def dolly_zoom(points, f0, z0, distances):
    """Move the camera so the subject plane is at d, zoom to f0 d / z0."""
    p, _ = _pts3(points)
    d = np.asarray(distances, float).ravel()
    fs = f0 * d / z0
    z = p[None, :, 2:] + (d - z0)[:, None, None]                    # (F, N, 1) new depths
    with np.errstate(divide="ignore", invalid="ignore"):
        proj = np.where(z > 0, fs[:, None, None] * p[None, :, :2] / z, np.nan)
    return fs, proj


# --------------------------------------------------------------------- ext3
def track_pose(frames, pattern_size, square_size, K, dist=None):
    """[rvec, tvec] per frame, NaN rows where the board is missing."""
    return np.array([np.r_[estimate_pose(f, pattern_size, square_size, K, dist)[:2]]
                     for f in frames], dtype=float).reshape(-1, 6)
