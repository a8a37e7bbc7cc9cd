"""Lab 10 - geometric camera models, continued.

Inputs are converted explicitly (lists, float32, views are all fine) and never
modified. Conventions:

- 3D points ``(N, 3)``; a single ``(3,)`` point gives a single ``(2,)`` result.
- Camera looks along +Z, X right, Y down; ``X_cam = R X + t``; ``P = K [R | t]``.
- P is defined up to a non-zero scale, sign included.
- Rotations are Rodrigues vectors (radians), as ``cv2.solvePnP`` returns them.
- ``dist`` is OpenCV's ``(k1, k2, p1, p2, k3)``; ``None`` means no distortion.
"""

import cv2
import numpy as np


# ------------------------------------------------------------------ helpers
def _as_points(points, dim):
    """float64 (N, dim) copy of ``points`` and whether a single point was given."""
    arr = np.array(points, dtype=np.float64)
    single = arr.ndim == 1
    if single:
        arr = arr.reshape(1, -1)
    if arr.ndim != 2 or arr.shape[1] != dim:
        raise ValueError(f"expected (N, {dim}) or ({dim},) points, got {np.shape(points)}")
    return arr, single


def _finish(result, single):
    return result[0] if single else result


def _as_matrix(M, shape, name):
    arr = np.array(M, dtype=np.float64)
    if arr.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} has non-finite entries")
    return arr


def _dist_vector(dist):
    """OpenCV distortion as a float64 (5,) vector; None -> zeros."""
    d = np.zeros(5)
    if dist is not None:
        coeffs = np.array(dist, dtype=np.float64).reshape(-1)
        if coeffs.size > 5:
            return coeffs.copy()        # OpenCV also takes 8/12/14 coefficients
        d[:coeffs.size] = coeffs
    return d


def _divide_by_depth(xy, z, f):
    """f * xy / z row by row, NaN where z <= 0 (behind the camera)."""
    out = np.full(xy.shape, np.nan)
    front = z > 0
    out[front] = f * xy[front] / z[front, None]
    return out


# --------------------------------------------------------------------- ex1
def perspective_project(points, f):
    """``x = f X / Z``, ``y = f Y / Z``; NaN for points with ``Z <= 0``."""
    pts, single = _as_points(points, 3)
    return _finish(_divide_by_depth(pts[:, :2], pts[:, 2], float(f)), single)


# --------------------------------------------------------------------- ex2
def weak_perspective_project(points, f, z_avg=None):
    """``x = f X / z_avg``, ``y = f Y / z_avg``; ``z_avg`` defaults to the mean Z.

    Every point uses the same depth, so this is a plain scaling by
    ``f / z_avg``. A common depth of exactly 0 has no image: NaN then.
    """
    pts, single = _as_points(points, 3)
    if z_avg is None:
        if pts.shape[0] == 0:
            return _finish(np.zeros((0, 2)), single)
        z_avg = float(np.mean(pts[:, 2]))
    else:
        z_avg = float(z_avg)
    if z_avg == 0.0:
        out = np.full((pts.shape[0], 2), np.nan)
    else:
        out = (float(f) / z_avg) * pts[:, :2]
    return _finish(out, single)


# --------------------------------------------------------------------- ex3
ORTHOGRAPHIC_MATRIX = np.array([[1.0, 0.0, 0.0, 0.0],
                                [0.0, 1.0, 0.0, 0.0],
                                [0.0, 0.0, 0.0, 1.0]])


def orthographic_project(points):
    """The lab sheet's 3x4 orthographic matrix, then division by w (always 1)."""
    pts, single = _as_points(points, 3)
    homog = np.hstack([pts, np.ones((pts.shape[0], 1))])
    xyw = homog @ ORTHOGRAPHIC_MATRIX.T
    out = xyw[:, :2] / xyw[:, 2:3]
    return _finish(out, single)


# --------------------------------------------------------------------- ex4
def _normalising_transform(points):
    """Hartley's similarity: centroid to the origin, RMS distance sqrt(dim).

    Works for 2D (-> 3x3) and 3D (-> 4x4) points.
    """
    dim = points.shape[1]
    centroid = points.mean(axis=0)
    rms = np.sqrt(np.mean(np.sum((points - centroid) ** 2, axis=1)))
    if rms == 0:
        raise ValueError("all points coincide")
    s = np.sqrt(dim) / rms
    T = np.eye(dim + 1)
    T[:dim, :dim] *= s
    T[:dim, dim] = -s * centroid
    return T


def _check_not_planar(X):
    """The DLT for a full P needs 3D points not all on one plane."""
    centred = X - X.mean(axis=0)
    sv = np.linalg.svd(centred, compute_uv=False)
    if sv[-1] <= 1e-9 * sv[0]:
        raise ValueError("the 3D points are (nearly) coplanar: P is not determined")


def camera_matrix_dlt(points3d, points2d):
    """P from >= 6 3D-2D correspondences by the (normalised) Direct Linear Transform.

    Both point sets are normalised first (Hartley), the 2N x 12 system of the
    lab sheet is built row pair by row pair, solved by SVD (smallest singular
    vector), and the normalisation undone: ``P = T2^-1 Pn T3``.
    """
    X, _ = _as_points(points3d, 3)
    x, _ = _as_points(points2d, 2)
    n = X.shape[0]
    if x.shape[0] != n:
        raise ValueError("points3d and points2d must have the same length")
    if n < 6:
        raise ValueError("the DLT needs at least 6 correspondences")
    if not (np.all(np.isfinite(X)) and np.all(np.isfinite(x))):
        raise ValueError("points must be finite")
    _check_not_planar(X)

    T3 = _normalising_transform(X)
    T2 = _normalising_transform(x)
    Xn = np.hstack([X, np.ones((n, 1))]) @ T3.T          # (N, 4)
    xn = np.hstack([x, np.ones((n, 1))]) @ T2.T          # (N, 3), last column 1

    A = np.zeros((2 * n, 12))
    zero = np.zeros(4)
    for i in range(n):
        Xi = Xn[i]
        u, v = xn[i, 0] / xn[i, 2], xn[i, 1] / xn[i, 2]
        A[2 * i] = np.concatenate([Xi, zero, -u * Xi])
        A[2 * i + 1] = np.concatenate([zero, Xi, -v * Xi])

    _, _, Vt = np.linalg.svd(A)
    Pn = Vt[-1].reshape(3, 4)
    P = np.linalg.solve(T2, Pn @ T3)                      # T2^-1 Pn T3
    # Fix the free scale to something readable: unit Frobenius norm, and a
    # positive determinant of the left block (points in front have w > 0).
    P /= np.linalg.norm(P)
    if np.linalg.det(P[:, :3]) < 0:
        P = -P
    return P


# --------------------------------------------------------------------- ex5
def _rq(M):
    """RQ decomposition M = R Q (R upper triangular, Q orthogonal) via NumPy's QR.

    With the row-reversal permutation J: QR of (J M)^T = Q' R' gives
    M = (J R'^T J)(J Q'^T).
    """
    J = np.eye(3)[::-1]
    Qp, Rp = np.linalg.qr((J @ M).T)
    upper = J @ Rp.T @ J
    ortho = J @ Qp.T
    return upper, ortho


def decompose_camera_matrix(P):
    """Split ``P ~ K [R | t]``: K upper triangular with positive diagonal and
    ``K[2, 2] = 1``, R a rotation (det +1), ``X_cam = R X + t``."""
    P = _as_matrix(P, (3, 4), "P")
    M = P[:, :3]
    det_m = np.linalg.det(M)
    if abs(det_m) < 1e-12 * max(np.abs(M).max(), 1e-300) ** 3:
        raise ValueError("P[:, :3] is singular: not a finite camera")
    if det_m < 0:                       # P is known only up to sign
        P = -P
        M = P[:, :3]

    K, R = _rq(M)
    # Make K's diagonal positive: K R = (K D)(D R) with D = diag(+-1), D D = I.
    D = np.diag(np.where(np.diag(K) < 0, -1.0, 1.0))
    K = K @ D
    R = D @ R
    # det(M) > 0 and det(K) > 0 now, so det(R) = +1; check it anyway.
    if np.linalg.det(R) < 0:
        raise RuntimeError("decomposition gave a reflection")

    t = np.linalg.solve(K, P[:, 3])     # before rescaling K: P = K [R | t]
    K = K / K[2, 2]
    K[1, 0] = K[2, 0] = K[2, 1] = 0.0   # exact zeros below the diagonal
    return K, R, t


def camera_center(P):
    """The centre C with ``P [C, 1] = 0``.

    For a finite camera ``C = -M^-1 p4``; I take it from the SVD null vector,
    which also works if P is badly scaled, and divide by its last entry.
    """
    P = _as_matrix(P, (3, 4), "P")
    _, _, Vt = np.linalg.svd(P)
    C = Vt[-1]
    if C[3] == 0:
        raise ValueError("camera at infinity: no finite centre")
    return C[:3] / C[3]


# --------------------------------------------------------------------- ex6
def _to_grey(image):
    img = np.asarray(image)
    if img.dtype != np.uint8:
        raise ValueError("image must be uint8")
    if img.ndim == 3 and img.shape[2] == 3:
        return cv2.cvtColor(np.ascontiguousarray(img), cv2.COLOR_BGR2GRAY)
    if img.ndim == 3 and img.shape[2] == 1:
        return np.ascontiguousarray(img[:, :, 0])
    if img.ndim == 2:
        return np.ascontiguousarray(img)
    raise ValueError(f"unsupported image shape {img.shape}")


def _board_points(pattern_size, square_size):
    """Object points on Z = 0 in OpenCV's corner order (row by row, x fastest)."""
    cols, rows = int(pattern_size[0]), int(pattern_size[1])
    obj = np.zeros((cols * rows, 3), np.float64)
    obj[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * float(square_size)
    return obj


def _refine_window(corners, cols):
    """cornerSubPix half-window of about a third of the corner spacing (2..11 px).

    A fixed large window reaches into neighbouring corners when the board is
    small in the image; this keeps it inside one square.
    """
    c = corners.reshape(-1, 2)
    rows = c.shape[0] // cols
    grid = c.reshape(rows, cols, 2)
    steps = []
    if cols > 1:
        steps.append(np.linalg.norm(np.diff(grid, axis=1), axis=2).ravel())
    if rows > 1:
        steps.append(np.linalg.norm(np.diff(grid, axis=0), axis=2).ravel())
    spacing = float(np.min(np.concatenate(steps))) if steps else 15.0
    half = int(np.clip(spacing / 3.0, 2, 11))
    return (half, half)


def _detect_corners(image, pattern_size):
    """Refined corners (M, 2) float64, or None if the board is not found."""
    grey = _to_grey(image)
    size = (int(pattern_size[0]), int(pattern_size[1]))
    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE
    found, corners = cv2.findChessboardCorners(grey, size, flags=flags)
    if not found or corners is None or len(corners) != size[0] * size[1]:
        return None
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 50, 1e-4)
    corners = cv2.cornerSubPix(grey, corners.astype(np.float32),
                               _refine_window(corners, size[0]), (-1, -1), criteria)
    return corners.reshape(-1, 2).astype(np.float64)


def _no_pose():
    return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))


def estimate_pose(image, pattern_size, square_size, K, dist=None):
    """Pose of a chessboard: findChessboardCorners + cornerSubPix + solvePnP.

    The board is planar, so I start from OpenCV's planar solver (IPPE) and
    polish with the iterative Levenberg-Marquardt refinement; the default
    iterative solver is the fallback if IPPE fails.
    """
    K = _as_matrix(K, (3, 3), "K")
    d = _dist_vector(dist)
    corners = _detect_corners(image, pattern_size)
    if corners is None:
        return _no_pose()
    obj = _board_points(pattern_size, square_size)

    ok, rvec, tvec = False, None, None
    if obj.shape[0] >= 4:
        try:
            ok, rvec, tvec = cv2.solvePnP(obj, corners, K, d, flags=cv2.SOLVEPNP_IPPE)
            if ok:
                rvec, tvec = cv2.solvePnPRefineLM(obj, corners, K, d, rvec, tvec)
        except cv2.error:
            ok = False
    if not ok:
        ok, rvec, tvec = cv2.solvePnP(obj, corners, K, d, flags=cv2.SOLVEPNP_ITERATIVE)
    if not ok:
        return _no_pose()

    reproj, _ = cv2.projectPoints(obj, rvec, tvec, K, d)
    rvec = np.asarray(rvec, dtype=np.float64).reshape(3)
    tvec = np.asarray(tvec, dtype=np.float64).reshape(3)
    return rvec, tvec, reproj.reshape(-1, 2).astype(np.float64)


# --------------------------------------------------------------------- ext1
def undistort_image(image, K, dist):
    """The image an ideal pinhole camera with the same K would record.

    For every output pixel, ``cv2.initUndistortRectifyMap`` gives where the
    distorted camera saw it; ``cv2.remap`` samples there (bilinear, black
    outside). Grey and colour images alike.
    """
    img = np.asarray(image)
    if img.ndim not in (2, 3):
        raise ValueError(f"unsupported image shape {img.shape}")
    K = _as_matrix(K, (3, 3), "K")
    d = _dist_vector(dist)
    h, w = img.shape[:2]
    map_x, map_y = cv2.initUndistortRectifyMap(K, d, None, K, (w, h), cv2.CV_32FC1)
    out = cv2.remap(np.ascontiguousarray(img), map_x, map_y, cv2.INTER_LINEAR,
                    borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return out.reshape(img.shape).astype(img.dtype, copy=False)


# --------------------------------------------------------------------- ext2
def dolly_zoom(points, f0, z0, distances):
    """Dolly zoom: move so the subject plane is at ``d``, zoom to ``f0 d / z0``.

    Returns ``(focal_lengths (F,), projections (F, N, 2))``; points that end up
    behind the moved camera are NaN.
    """
    pts, _ = _as_points(points, 3)
    f0, z0 = float(f0), float(z0)
    if z0 == 0:
        raise ValueError("z0 must be non-zero (it is the subject's depth)")
    d = np.array(distances, dtype=np.float64).reshape(-1)
    focal_lengths = f0 * d / z0
    projections = np.empty((d.size, pts.shape[0], 2))
    for i, (di, fi) in enumerate(zip(d, focal_lengths)):
        moved = pts.copy()
        moved[:, 2] += di - z0            # every depth changes by d - z0
        projections[i] = perspective_project(moved, fi)
    return focal_lengths, projections


# --------------------------------------------------------------------- ext3
def track_pose(frames, pattern_size, square_size, K, dist=None):
    """``(F, 6)`` rows ``[rvec, tvec]`` per frame; NaN where the board is not found."""
    frames = list(frames)
    out = np.full((len(frames), 6), np.nan)
    for i, frame in enumerate(frames):
        rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
        out[i, :3] = rvec
        out[i, 3:] = tvec
    return out
