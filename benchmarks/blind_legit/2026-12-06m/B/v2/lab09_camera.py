"""Lab 9 - geometric camera models (OpenCV flavoured solution).

Wherever the lab sheet names an OpenCV function I use it (cv2.circle,
cv2.projectPoints, cv2.calibrateCamera ...); the projections themselves are
written as homogeneous matrix products.

- 3D points: (N, 3) float arrays, or one (3,) point -> one (2,) result.
- 2D points: (N, 2) arrays of (x, y) = (column, row), y down.
- Points without an image (behind the camera) come back as NaN.
"""

import cv2
import numpy as np


def _prepare(points):
    p = np.asarray(points, dtype=np.float64)
    return np.atleast_2d(p), p.ndim == 1


def _finish(result, single):
    return result[0] if single else result


def _homogeneous_divide(xh, depth_sign=1.0):
    """Divide by the third coordinate; NaN where the point is not in front."""
    w = xh[:, 2:3]
    in_front = (w * depth_sign) > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = xh[:, :2] / w
    return np.where(in_front, xy, np.nan)


# --------------------------------------------------------------------- ex1
def pinhole_project(points, f):
    """x = f X / Z, y = f Y / Z as the matrix diag(f, f, 1) applied to (X, Y, Z)."""
    P, single = _prepare(points)
    F = np.diag([f, f, 1.0])
    return _finish(_homogeneous_divide(P @ F.T), single)


# --------------------------------------------------------------------- ex2
def intrinsic_matrix(f, px, py):
    K = np.eye(3)
    K[0, 0] = K[1, 1] = f
    K[0, 2], K[1, 2] = px, py
    return K


def project_with_intrinsics(K, points):
    P, single = _prepare(points)
    xh = P @ np.asarray(K, dtype=np.float64).T
    return _finish(_homogeneous_divide(xh), single)


# --------------------------------------------------------------------- ex3
def camera_matrix(K, R, t):
    """P = K [R | t]  (K R in the first three columns, K t in the last)."""
    K = np.asarray(K, dtype=np.float64)
    R = np.asarray(R, dtype=np.float64)
    t = np.asarray(t, dtype=np.float64).ravel()
    P = np.empty((3, 4))
    P[:, :3] = K @ R
    P[:, 3] = K @ t
    return P


def project(P, points):
    """Homogeneous projection with P; P may have any non-zero scale.

    For P = s K [R | t] the depth of a point is w / s, and sign(s) is the
    sign of det(P[:, :3]) (det K > 0, det R = 1), so a point is in front of
    the camera when w * sign(det M) > 0.
    """
    P = np.asarray(P, dtype=np.float64)
    X, single = _prepare(points)
    Xh = np.concatenate([X, np.ones((len(X), 1))], axis=1)
    xh = Xh @ P.T
    s = np.sign(np.linalg.det(P[:, :3]))
    if s == 0:
        s = 1.0
    return _finish(_homogeneous_divide(xh, s), single)


# --------------------------------------------------------------------- ex4
def project_focal_lengths(points, focal_lengths):
    """All focal lengths at once by broadcasting: (F, 1, 1) * (1, N, 2)."""
    X, _ = _prepare(points)
    fs = np.asarray(focal_lengths, dtype=np.float64).reshape(-1, 1, 1)
    unit = pinhole_project(X, 1.0)          # normalised coordinates X/Z, Y/Z
    return fs * unit[None, :, :]


def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
    """Image positions of rays through random points of a circular pinhole.

    Ray from X through A = (ax, ay, 0): the image (made upright) is
    f X / Z - ax (1 + f / Z), i.e. the ideal projection shifted by the
    aperture point scaled by (1 + f / Z).
    """
    X, _ = _prepare(points)
    rng = np.random.default_rng(seed)
    n = len(X)
    # one (u, v) pair per ray
    uv = rng.random((n, n_rays, 2))
    radius = aperture * np.sqrt(uv[..., 0])
    angle = 2.0 * np.pi * uv[..., 1]
    A = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)

    ideal = f * X[:, :2] / X[:, 2:3]                # (N, 2)
    scale = (1.0 + f / X[:, 2]).reshape(n, 1, 1)    # (N, 1, 1)
    return ideal[:, None, :] - A * scale


# --------------------------------------------------------------------- ex5
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    """Filled circles with cv2.circle on a copy of the image."""
    canvas = np.ascontiguousarray(image).copy()
    pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    color = tuple(int(c) for c in color)
    ok = np.all(np.isfinite(pts), axis=1)
    centres = np.rint(pts[ok]).astype(np.int64)
    h, w = canvas.shape[:2]
    lim = 4 * max(h, w) + 4 * abs(int(radius)) + 10
    for x, y in centres:
        if abs(x) > lim or abs(y) > lim:
            continue                       # far off the image: nothing to draw
        cv2.circle(canvas, (int(x), int(y)), int(radius), color, thickness=-1)
    return canvas


def project_onto_image(image, P, points):
    pts = np.atleast_2d(project(P, points))
    return draw_points(image, pts), pts


# --------------------------------------------------------------------- ext1
def calibrate(images, pattern_size, square_size):
    """cv2.findChessboardCorners + cv2.cornerSubPix + cv2.calibrateCamera."""
    cols, rows = int(pattern_size[0]), int(pattern_size[1])
    board = np.zeros((rows * cols, 3), np.float32)
    board[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * np.float32(square_size)

    term = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 40, 1e-4)
    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE

    obj_list, img_list, size = [], [], None
    for image in images:
        if image.ndim == 3:
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
        else:
            grey = image
        size = grey.shape[::-1]            # (width, height)
        ok, corners = cv2.findChessboardCorners(grey, (cols, rows), flags=flags)
        if ok:
            corners = cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1), term)
            obj_list.append(board)
            img_list.append(corners.astype(np.float32))

    if not obj_list:
        raise RuntimeError("the chessboard was not found in any image")

    rms, K, dist, _rvecs, _tvecs = cv2.calibrateCamera(
        obj_list, img_list, size, None, None)
    return np.array(K, dtype=np.float64), np.array(dist, np.float64).reshape(-1)[:5], float(rms)


# --------------------------------------------------------------------- ext2
def distort_points(points, dist):
    """Brown-Conrady distortion via cv2.projectPoints of (x, y, 1) with K = I."""
    p, single = _prepare(points)
    if len(p) == 0:
        return np.zeros((0, 2))
    obj = np.concatenate([p, np.ones((len(p), 1))], axis=1).reshape(-1, 1, 3)
    d = np.zeros(5)
    dist = np.asarray(dist, dtype=np.float64).ravel()
    d[:min(5, dist.size)] = dist[:5]
    img, _ = cv2.projectPoints(obj, np.zeros(3), np.zeros(3), np.eye(3), d)
    return _finish(img.reshape(-1, 2), single)
