"""Lab 10 - geometric camera models, continued (reference solution).

Three projection models (perspective, weak perspective, orthographic); the
camera matrix from 3D-2D correspondences by the Direct Linear Transform and its
decomposition into ``K``, ``R``, ``t``; the pose of a chessboard with OpenCV;
undistortion, the dolly zoom and pose tracking.
"""

import cv2
import numpy as np


def _points(points):
    points = np.asarray(points, dtype=np.float64)
    return np.atleast_2d(points), points.ndim == 1


# --------------------------------------------------------------------- ex1
def perspective_project(points, f):
    """``x = f X / Z``, ``y = f Y / Z``; NaN for points with ``Z <= 0``."""
    X, single = _points(points)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = f * X[:, :2] / X[:, 2:3]
    x[X[:, 2] <= 0] = np.nan
    return x[0] if single else x


# --------------------------------------------------------------------- ex2
def weak_perspective_project(points, f, z_avg=None):
    """Every point divided by the same depth ``z_avg`` (default: the mean depth).

    A good approximation when the object's depth range is small compared with
    its distance: the projection is then a scaled orthographic one, with scale
    ``f / z_avg``.
    """
    X, single = _points(points)
    z = X[:, 2].mean() if z_avg is None else float(z_avg)
    x = (f / z) * X[:, :2]
    return x[0] if single else x


# --------------------------------------------------------------------- ex3
ORTHOGRAPHIC = np.array([[1.0, 0.0, 0.0, 0.0],
                         [0.0, 1.0, 0.0, 0.0],
                         [0.0, 0.0, 0.0, 1.0]])


def orthographic_project(points):
    """``[x, y, w] = M [X, Y, Z, 1]`` with the lab sheet's M: simply ``(X, Y)``."""
    X, single = _points(points)
    homogeneous = np.column_stack([X, np.ones(len(X))]) @ ORTHOGRAPHIC.T
    x = homogeneous[:, :2] / homogeneous[:, 2:3]
    return x[0] if single else x


# --------------------------------------------------------------------- ex4
def _normalising_transform(points):
    """Similarity moving ``points`` to their centroid, mean distance sqrt(dim)."""
    centroid = points.mean(axis=0)
    mean_distance = np.linalg.norm(points - centroid, axis=1).mean()
    s = np.sqrt(points.shape[1]) / mean_distance
    T = np.eye(points.shape[1] + 1)
    T[:-1, :-1] *= s
    T[:-1, -1] = -s * centroid
    return T


def camera_matrix_dlt(points3d, points2d):
    """P from N >= 6 correspondences ``x ~ P X`` by the (normalised) DLT.

    Each correspondence gives two rows of ``A p = 0`` (p = P row by row):
    ``[X^T, 0, -u X^T]`` and ``[0, X^T, -v X^T]`` with ``X = (X, Y, Z, 1)``.
    The solution is the right singular vector of the smallest singular value.
    Hartley's normalisation (both point sets centred and scaled) keeps the
    system well conditioned; it is undone at the end.
    """
    X = np.asarray(points3d, dtype=np.float64)
    x = np.asarray(points2d, dtype=np.float64)
    T = _normalising_transform(x)
    U = _normalising_transform(X)
    xn = (np.column_stack([x, np.ones(len(x))]) @ T.T)[:, :2]
    Xn = np.column_stack([X, np.ones(len(X))]) @ U.T
    zeros = np.zeros_like(Xn)
    rows_u = np.hstack([Xn, zeros, -xn[:, :1] * Xn])
    rows_v = np.hstack([zeros, Xn, -xn[:, 1:] * Xn])
    A = np.vstack([rows_u, rows_v])
    p = np.linalg.svd(A)[2][-1]
    P = np.linalg.inv(T) @ p.reshape(3, 4) @ U
    return P / np.linalg.norm(P)


# --------------------------------------------------------------------- ex5
def decompose_camera_matrix(P):
    """``P ~ K [R | t]`` by an RQ decomposition of the left 3x3 block.

    RQ is unique only up to the signs of K's columns / R's rows: they are fixed
    so that K has a positive diagonal. P itself is known only up to scale and
    sign: if the resulting R has det -1, P is negated first.
    """
    P = np.asarray(P, dtype=np.float64)
    if np.linalg.det(P[:, :3]) < 0:
        P = -P
    # RQ via QR of the row-reversed transpose
    flip = np.eye(3)[::-1]
    Q, U = np.linalg.qr((flip @ P[:, :3]).T)
    K = flip @ U.T @ flip
    R = flip @ Q.T
    signs = np.diag(np.sign(np.diag(K)))
    K, R = K @ signs, signs @ R
    t = np.linalg.solve(K, P[:, 3])
    scale = K[2, 2]
    return K / scale, R, t


def camera_center(P):
    """The null vector of P, dehomogenised: ``P @ [C, 1] = 0``."""
    C = np.linalg.svd(np.asarray(P, dtype=np.float64))[2][-1]
    return C[:3] / C[3]


# --------------------------------------------------------------------- ex6
def _object_points(pattern_size, square_size):
    cols, rows = pattern_size
    objp = np.zeros((cols * rows, 3), np.float64)
    objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
    return objp


def estimate_pose(image, pattern_size, square_size, K, dist=None):
    """Board pose from one image: corners, then ``cv2.solvePnP``."""
    grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
    found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size))
    if not found:
        return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)
    corners = cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1), criteria)
    objp = _object_points(pattern_size, square_size)
    K = np.asarray(K, dtype=np.float64)
    dist = None if dist is None else np.asarray(dist, dtype=np.float64)
    _, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
    reprojected, _ = cv2.projectPoints(objp, rvec, tvec, K, dist)
    return rvec.ravel(), tvec.ravel(), reprojected.reshape(-1, 2)


# --------------------------------------------------------------------- ext1
def undistort_image(image, K, dist):
    """Undistort with a remap table, keeping the same camera matrix."""
    K = np.asarray(K, dtype=np.float64)
    dist = np.asarray(dist, dtype=np.float64)
    h, w = image.shape[:2]
    map_x, map_y = cv2.initUndistortRectifyMap(K, dist, None, K, (h, w), cv2.CV_32FC1)
    return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR)


# --------------------------------------------------------------------- ext2
def dolly_zoom(points, f0, z0, distances):
    """Move the camera so the subject plane is at distance d, and zoom to f0 d / z0."""
    X, _ = _points(points)
    distances = np.asarray(distances, dtype=np.float64).ravel()
    focal_lengths = f0 * distances / z0
    projections = np.stack([perspective_project(X + [0.0, 0.0, d - z0], f)
                            for f, d in zip(focal_lengths, distances)])
    return focal_lengths, projections


# --------------------------------------------------------------------- ext3
def track_pose(frames, pattern_size, square_size, K, dist=None):
    """``estimate_pose`` on every frame: rows ``[rvec, tvec]``, NaN where no board."""
    rows = []
    for frame in frames:
        rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
        rows.append(np.concatenate([rvec, tvec]))
    return np.array(rows, dtype=np.float64).reshape(-1, 6)
