"""Lab 10 - geometric camera models, continued.

Choices I made where the lab leaves them open:
- the projections are the lab sheet's formulas as they stand (a point behind
  the camera simply gets the formula's value) and are returned as float32;
- the DLT camera matrix is returned scaled so that its third row's first three
  entries have unit norm, with the sign for which det(P[:, :3]) < 0 (P is only
  defined up to a non-zero scale, sign included);
- the pose uses OpenCV's planar PnP solver (IPPE) refined by Levenberg-Marquardt,
  and I reproject the corners with my own implementation of the camera model;
- undistortion samples with bicubic interpolation from fixed-point maps;
- inputs may be lists, read-only or non-contiguous; they are never modified.
"""

import cv2
import numpy as np


def _points3(points):
    p = np.array(points, dtype=np.float64, copy=True)
    single = p.ndim == 1
    return p.reshape(-1, 3), single


def _out(xy, single):
    xy = np.asarray(xy, dtype=np.float32)
    return xy[0] if single else xy


def _dist5(dist):
    d = np.zeros(5)
    if dist is not None:
        dd = np.asarray(dist, dtype=np.float64).ravel()[:5]
        d[:dd.size] = dd
    return d


# --------------------------------------------------------------------- ex1
def perspective_project(points, f):
    """x = f X / Z, y = f Y / Z, exactly as on the sheet."""
    p, single = _points3(points)
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = float(f) * p[:, :2] / p[:, 2:3]
    return _out(xy, single)


# --------------------------------------------------------------------- ex2
def weak_perspective_project(points, f, z_avg=None):
    """x = f X / z_avg, y = f Y / z_avg; z_avg = mean depth when not given."""
    p, single = _points3(points)
    z = float(np.mean(p[:, 2])) if z_avg is None else float(z_avg)
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = p[:, :2] * (float(f) / z)
    return _out(xy, single)


# --------------------------------------------------------------------- ex3
def orthographic_project(points):
    """The sheet's 3 x 4 orthographic matrix, applied with einsum."""
    p, single = _points3(points)
    M = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=np.float64)
    homog = np.concatenate([p, np.ones((p.shape[0], 1))], axis=1)
    xyw = np.einsum("ij,nj->ni", M, homog)
    return _out(xyw[:, :2] / xyw[:, 2:], single)


# --------------------------------------------------------------------- ex4
def _hartley(pts):
    """Isotropic normalisation: centroid to 0, mean distance sqrt(dim)."""
    dim = pts.shape[1]
    c = pts.mean(axis=0)
    mean_dist = np.mean(np.linalg.norm(pts - c, axis=1))
    s = np.sqrt(dim) / mean_dist if mean_dist > 0 else 1.0
    T = np.eye(dim + 1)
    T[:dim, :dim] *= s
    T[:dim, dim] = -s * c
    return T


def camera_matrix_dlt(points3d, points2d):
    """Normalised DLT, SVD of the 2N x 12 system."""
    X = np.array(points3d, dtype=np.float64).reshape(-1, 3)
    x = np.array(points2d, dtype=np.float64).reshape(-1, 2)
    n = X.shape[0]
    if n < 6 or x.shape[0] != n:
        raise ValueError("camera_matrix_dlt needs N >= 6 matching points")
    U = _hartley(X)
    T = _hartley(x)
    Xh = np.c_[X, np.ones(n)] @ U.T
    xh = np.c_[x, np.ones(n)] @ T.T

    A = np.zeros((2 * n, 12))
    A[0::2, 0:4] = Xh
    A[0::2, 8:12] = -xh[:, 0:1] * Xh
    A[1::2, 4:8] = Xh
    A[1::2, 8:12] = -xh[:, 1:2] * Xh
    _, _, Vt = np.linalg.svd(A)
    P = np.linalg.solve(T, Vt[-1].reshape(3, 4) @ U)

    # choose a representative: ||m3|| = 1, det(M) < 0
    P = P / np.linalg.norm(P[2, :3])
    if np.linalg.det(P[:, :3]) > 0:
        P = -P
    return P


# --------------------------------------------------------------------- ex5
def _rq(M):
    """RQ decomposition M = Rt @ Q (Rt upper triangular) from NumPy's QR."""
    flip = np.eye(3)[::-1]                 # the exchange matrix
    Q0, R0 = np.linalg.qr((flip @ M).T)
    Rt = flip @ R0.T @ flip
    Q = flip @ Q0.T
    return Rt, Q


def decompose_camera_matrix(P):
    """K, R, t with P ~ K [R | t] (K upper triangular, K[2, 2] = 1, det R = 1)."""
    P = np.array(P, dtype=np.float64, copy=True)
    if np.linalg.det(P[:, :3]) < 0:
        P = -P
    K, R = _rq(P[:, :3])
    S = np.diag(np.where(np.diag(K) < 0, -1.0, 1.0))
    K = K @ S
    R = S @ R
    t = np.linalg.solve(K, P[:, 3])
    K = K / K[2, 2]
    K[2, 2] = 1.0
    return K, R, t


def camera_center(P):
    """The right null vector of P (last row of Vt), dehomogenised."""
    _, _, Vt = np.linalg.svd(np.asarray(P, dtype=np.float64))
    C = Vt[-1]
    return C[:3] / C[3]


# --------------------------------------------------------------------- ex6
def _project_with_distortion(obj, rvec, tvec, K, d):
    """My own camera model: rotate, translate, divide, distort, apply K."""
    R, _ = cv2.Rodrigues(np.asarray(rvec, dtype=np.float64).reshape(3, 1))
    cam = obj @ R.T + np.asarray(tvec, dtype=np.float64).ravel()
    x = cam[:, 0] / cam[:, 2]
    y = cam[:, 1] / cam[:, 2]
    k1, k2, p1, p2, k3 = d
    r2 = x * x + y * y
    radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3))
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    pix = np.stack([xd, yd, np.ones_like(xd)], axis=1) @ np.asarray(K, dtype=np.float64).T
    return pix[:, :2] / pix[:, 2:]


def estimate_pose(image, pattern_size, square_size, K, dist=None):
    """Chessboard corners -> planar PnP (IPPE + LM refinement) -> reprojection."""
    failed = (np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2)))
    img = np.ascontiguousarray(image)
    grey = img if img.ndim == 2 else cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    cols, rows = int(pattern_size[0]), int(pattern_size[1])
    ok, corners = cv2.findChessboardCorners(
        grey, (cols, rows),
        flags=cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE)
    if not ok:
        return failed
    corners = cv2.cornerSubPix(
        grey, corners, (5, 5), (-1, -1),
        (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 50, 1e-4))

    grid = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * float(square_size)
    obj = np.c_[grid, np.zeros(len(grid))].astype(np.float64)
    K = np.asarray(K, dtype=np.float64)
    d = _dist5(dist)
    img_pts = corners.reshape(-1, 2).astype(np.float64)
    ok, rvec, tvec = cv2.solvePnP(obj, img_pts, K, d, flags=cv2.SOLVEPNP_IPPE)
    if not ok:
        return failed
    rvec, tvec = cv2.solvePnPRefineLM(obj, img_pts, K, d, rvec, tvec)
    reproj = _project_with_distortion(obj, rvec, tvec, K, d)
    return rvec.ravel().copy(), tvec.ravel().copy(), reproj


# --------------------------------------------------------------------- ext1
def undistort_image(image, K, dist):
    """Undistortion maps from OpenCV (new camera matrix = K), bicubic sampling."""
    img = np.ascontiguousarray(image)
    h, w = img.shape[:2]
    K = np.asarray(K, dtype=np.float64)
    map1, map2 = cv2.initUndistortRectifyMap(K, _dist5(dist), None, K, (w, h),
                                             cv2.CV_16SC2)
    return cv2.remap(img, map1, map2, cv2.INTER_CUBIC,
                     borderMode=cv2.BORDER_CONSTANT, borderValue=0)


# --------------------------------------------------------------------- ext2
def dolly_zoom(points, f0, z0, distances):
    """All distances at once by broadcasting: (F, N, 2) projections."""
    p, _ = _points3(points)
    d = np.asarray(distances, dtype=np.float64).ravel()
    focal = float(f0) * d / float(z0)
    Z = p[None, :, 2] + (d - float(z0))[:, None]          # (F, N)
    with np.errstate(divide="ignore", invalid="ignore"):
        proj = focal[:, None, None] * p[None, :, :2] / Z[:, :, None]
    return focal, proj.astype(np.float32)


# --------------------------------------------------------------------- ext3
def track_pose(frames, pattern_size, square_size, K, dist=None):
    """One [rvec, tvec] row per frame; NaN rows where the board is not found."""
    out = np.full((len(frames), 6), np.nan)
    for i, frame in enumerate(frames):
        rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
        out[i, :3] = rvec
        out[i, 3:] = tvec
    return out
