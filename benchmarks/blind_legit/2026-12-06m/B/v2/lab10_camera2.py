"""Lab 10 - geometric camera models, continued (second solution).

Here I use the OpenCV calls the lab sheet names (solvePnP, projectPoints,
undistort), a Hartley-normalised DLT and scipy's RQ decomposition.

- 3D points (N, 3) or one (3,) point (then one (2,) result); 2D points (N, 2)
  of (x, y) = (column, row), y down; X_cam = R X + t; camera looks along +Z.
- P is returned up to scale; rotations as Rodrigues vectors.
"""

import cv2
import numpy as np
import scipy.linalg


def _pts3(points):
    p = np.asarray(points, dtype=np.float64)
    return np.atleast_2d(p), p.ndim == 1


def _ret(out, single):
    return out[0] if single else out


# --------------------------------------------------------------------- ex1
def perspective_project(points, f):
    """Homogeneous form: (f X, f Y, Z), divided by Z; NaN where Z <= 0."""
    X, single = _pts3(points)
    Kf = np.diag([float(f), float(f), 1.0])
    xh = X @ Kf.T
    z = xh[:, 2:3]
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(z > 0, xh[:, :2] / z, np.nan)
    return _ret(out, single)


# --------------------------------------------------------------------- ex2
def weak_perspective_project(points, f, z_avg=None):
    """Weak perspective = scaled orthographic projection with scale f / z_avg."""
    X, single = _pts3(points)
    depth = X[:, 2].mean() if z_avg is None else float(z_avg)
    m = f / depth                          # one magnification for the whole object
    return _ret(m * X[:, :2], single)


# --------------------------------------------------------------------- ex3
def orthographic_project(points):
    """The lab sheet's 3x4 matrix; w = 1, so (x, y) = (X, Y)."""
    X, single = _pts3(points)
    M = np.zeros((3, 4))
    M[0, 0] = M[1, 1] = M[2, 3] = 1.0
    xh = np.hstack([X, np.ones((len(X), 1))]) @ M.T
    return _ret(xh[:, :2] / xh[:, 2:], single)


# --------------------------------------------------------------------- ex4
def _normalise_2d(x):
    """Similarity T: centroid to the origin, mean distance sqrt(2)."""
    c = x.mean(axis=0)
    s = np.sqrt(2) / np.mean(np.linalg.norm(x - c, axis=1))
    return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])


def _normalise_3d(X):
    """Similarity U: centroid to the origin, mean distance sqrt(3)."""
    c = X.mean(axis=0)
    s = np.sqrt(3) / np.mean(np.linalg.norm(X - c, axis=1))
    U = np.diag([s, s, s, 1.0])
    U[:3, 3] = -s * c
    return U


def camera_matrix_dlt(points3d, points2d):
    """Normalised DLT (Hartley & Zisserman, alg. 7.1).

    Normalise both point sets, build the 2N x 12 system of the lab sheet
    (vectorised), take the null vector as the eigenvector of A^T A with the
    smallest eigenvalue, and undo the normalisation: P = T^-1 P_n U.
    """
    X = np.asarray(points3d, dtype=np.float64).reshape(-1, 3)
    x = np.asarray(points2d, dtype=np.float64).reshape(-1, 2)
    if len(X) < 6:
        raise ValueError("at least 6 correspondences are needed")

    T = _normalise_2d(x)
    U = _normalise_3d(X)
    Xn = np.hstack([X, np.ones((len(X), 1))]) @ U.T          # (N, 4)
    xn = np.hstack([x, np.ones((len(x), 1))]) @ T.T          # (N, 3)
    xn = xn[:, :2] / xn[:, 2:]

    n = len(X)
    zeros = np.zeros((n, 4))
    rows_u = np.hstack([Xn, zeros, -xn[:, :1] * Xn])
    rows_v = np.hstack([zeros, Xn, -xn[:, 1:2] * Xn])
    A = np.empty((2 * n, 12))
    A[0::2] = rows_u
    A[1::2] = rows_v

    evals, evecs = np.linalg.eigh(A.T @ A)                  # ascending eigenvalues
    Pn = evecs[:, 0].reshape(3, 4)
    P = np.linalg.inv(T) @ Pn @ U
    return P / np.linalg.norm(P)


# --------------------------------------------------------------------- ex5
def decompose_camera_matrix(P):
    """RQ decomposition of M = P[:, :3] with scipy.linalg.rq."""
    P = np.asarray(P, dtype=np.float64)
    if np.linalg.det(P[:, :3]) < 0:
        P = -P                               # P is only known up to sign
    K, R = scipy.linalg.rq(P[:, :3])

    # positive diagonal: flip columns of K and rows of R together
    signs = np.where(np.diag(K) < 0, -1.0, 1.0)
    K = K * signs[None, :]
    R = R * signs[:, None]

    t = scipy.linalg.solve_triangular(K, P[:, 3], lower=False)
    K = K / K[2, 2]
    return K, R, t


def camera_center(P):
    """The sheet's formula: C = -M^-1 p4 (M the left 3x3 block of P)."""
    P = np.asarray(P, dtype=np.float64)
    return -np.linalg.solve(P[:, :3], P[:, 3])


# --------------------------------------------------------------------- ex6
def _dist_or_zero(dist):
    d = np.zeros(5)
    if dist is not None:
        dist = np.asarray(dist, dtype=np.float64).ravel()
        d[:min(5, dist.size)] = dist[:5]
    return d


def estimate_pose(image, pattern_size, square_size, K, dist=None):
    """Board pose: corners, planar PnP (IPPE), reprojection with projectPoints."""
    cols, rows = int(pattern_size[0]), int(pattern_size[1])
    grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
    K = np.asarray(K, dtype=np.float64)
    d = _dist_or_zero(dist)

    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE
    found, corners = cv2.findChessboardCorners(grey, (cols, rows), flags=flags)
    if not found:
        nan3 = np.full(3, np.nan)
        return nan3, nan3.copy(), np.zeros((0, 2))
    term = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 40, 1e-4)
    corners = cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1), term)

    obj = np.zeros((rows * cols, 3), np.float64)
    obj[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * float(square_size)

    # the board is planar, so IPPE is the natural PnP solver
    ok, rvec, tvec = cv2.solvePnP(obj, corners.astype(np.float64), K, d,
                                  flags=cv2.SOLVEPNP_IPPE)
    if not ok:
        nan3 = np.full(3, np.nan)
        return nan3, nan3.copy(), np.zeros((0, 2))
    reproj, _ = cv2.projectPoints(obj, rvec, tvec, K, d)
    return rvec.reshape(3).astype(np.float64), tvec.reshape(3).astype(np.float64), \
        reproj.reshape(-1, 2).astype(np.float64)


# --------------------------------------------------------------------- ext1
def undistort_image(image, K, dist):
    """cv2.undistort with the same camera matrix for the output."""
    K = np.asarray(K, dtype=np.float64)
    return cv2.undistort(image, K, _dist_or_zero(dist), None, K)


# --------------------------------------------------------------------- ext2
def dolly_zoom(points, f0, z0, distances):
    """All camera positions at once with broadcasting."""
    X, _ = _pts3(points)
    d = np.asarray(distances, dtype=np.float64).reshape(-1)
    focal = f0 * d / z0                                   # (F,)
    Z = X[None, :, 2] + (d - z0)[:, None]                 # (F, N) new depths
    with np.errstate(divide="ignore", invalid="ignore"):
        proj = focal[:, None, None] * X[None, :, :2] / Z[:, :, None]
    proj = np.where((Z > 0)[:, :, None], proj, np.nan)
    return focal, proj


# --------------------------------------------------------------------- ext3
def track_pose(frames, pattern_size, square_size, K, dist=None):
    rows = []
    for frame in frames:
        rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
        rows.append(np.concatenate([rvec, tvec]))
    return np.array(rows, dtype=np.float64).reshape(-1, 6)
