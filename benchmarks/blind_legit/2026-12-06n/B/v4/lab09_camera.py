"""Lab 9 - geometric camera models.

My notes follow Hartley & Zisserman (ch. 6, "Camera models") and Szeliski
(sec. 2.1.4-2.1.6).  Points are projected in homogeneous coordinates and the
depth test uses the H&Z formula  depth(X; P) = sign(det M) * w / (T * ||m3||),
so a point is "in front" of the camera whatever the scale/sign of P is.

Conventions: 3D points (N, 3) or a single (3,) point; 2D points (N, 2) of
(x, y) = (column, row), y down.  Points behind the camera get NaN.
"""

import cv2
import numpy as np


def _as_points(points, dim):
    """Return a float (N, dim) array and whether the input was a single point."""
    pts = np.asarray(points, dtype=np.float64)
    single = pts.ndim == 1
    pts = np.atleast_2d(pts).reshape(-1, dim)
    return pts, single


def _dehomogenise(xh, in_front):
    """(N, 3) homogeneous image points -> (N, 2); NaN where not in front."""
    out = np.full((xh.shape[0], 2), np.nan)
    ok = in_front & (xh[:, 2] != 0)
    out[ok] = xh[ok, :2] / xh[ok, 2:3]
    return out


# --------------------------------------------------------------------- ex1
def pinhole_project(points, f):
    """Pinhole projection x = f X / Z, y = f Y / Z (NaN for Z <= 0)."""
    X, single = _as_points(points, 3)
    # Szeliski eq. (2.56) with a zero principal point: diag(f, f, 1) @ X
    xh = X @ np.diag([float(f), float(f), 1.0]).T
    out = _dehomogenise(xh, X[:, 2] > 0)
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def intrinsic_matrix(f, px, py):
    """K = [[f, 0, px], [0, f, py], [0, 0, 1]]."""
    return np.array([[f, 0.0, px],
                     [0.0, f, py],
                     [0.0, 0.0, 1.0]], dtype=np.float64)


def project_with_intrinsics(K, points):
    """(u, v, w) = K X, then (u / w, v / w); NaN where w <= 0."""
    K = np.asarray(K, dtype=np.float64)
    X, single = _as_points(points, 3)
    xh = X @ K.T
    # K has K[2, 2] > 0 for any real camera, so w has the sign of Z.
    sign = np.sign(K[2, 2]) if K[2, 2] != 0 else 1.0
    out = _dehomogenise(xh, sign * xh[:, 2] > 0)
    return out[0] if single else out


# --------------------------------------------------------------------- ex3
def camera_matrix(K, R, t):
    """P = K [R | t] (3 x 4)."""
    K = np.asarray(K, dtype=np.float64)
    R = np.asarray(R, dtype=np.float64)
    t = np.asarray(t, dtype=np.float64).reshape(3, 1)
    return K @ np.hstack([R, t])


def project(P, points):
    """Project world points with P; NaN for points behind the camera.

    H&Z (6.15): with M = P[:, :3] and (u, v, w) = P X, the depth of X has the
    sign of  sign(det M) * w  (for a finite point with T = 1).  This works for
    any non-zero scale of P, negative ones included.
    """
    P = np.asarray(P, dtype=np.float64)
    X, single = _as_points(points, 3)
    Xh = np.hstack([X, np.ones((X.shape[0], 1))])
    xh = Xh @ P.T
    detM = np.linalg.det(P[:, :3])
    s = np.sign(detM) if detM != 0 else 1.0
    out = _dehomogenise(xh, s * xh[:, 2] > 0)
    return out[0] if single else out


# --------------------------------------------------------------------- ex4
def project_focal_lengths(points, focal_lengths):
    """Stack of pinhole projections, one (N, 2) slice per focal length."""
    X, _ = _as_points(points, 3)
    fs = np.asarray(focal_lengths, dtype=np.float64).ravel()
    result = np.empty((fs.size, X.shape[0], 2))
    for i, f in enumerate(fs):
        result[i] = pinhole_project(X, f)
    return result


def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
    """Trace rays from every point through random points of a round pinhole.

    The pinhole is the disc of radius ``aperture`` in Z = 0, the image plane is
    Z = -f.  A ray from X through A = (ax, ay, 0) is X + s (A - X); it meets
    Z = -f for s = (Z + f) / Z.  The (inverted) image is flipped upright.
    """
    X, _ = _as_points(points, 3)
    n = X.shape[0]
    rng = np.random.default_rng(seed)
    # uniform over the disc's area: r = a sqrt(u), phi = 2 pi v
    u = rng.random((n, n_rays))
    v = rng.random((n, n_rays))
    r = float(aperture) * np.sqrt(u)
    phi = 2.0 * np.pi * v
    ax = r * np.cos(phi)
    ay = r * np.sin(phi)

    Xw = X[:, 0:1]
    Yw = X[:, 1:2]
    Zw = X[:, 2:3]
    s = (Zw + f) / Zw                     # ray parameter at the image plane
    hit_x = Xw + s * (ax - Xw)            # landing point on Z = -f (upside down)
    hit_y = Yw + s * (ay - Yw)
    # turn the real (inverted) image upright, as pinhole_project does
    return np.stack([-hit_x, -hit_y], axis=-1)


# --------------------------------------------------------------------- ex5
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    """Filled circles (cv2.circle) at the rounded positions, on a copy."""
    out = np.array(image, copy=True, order="C")
    pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    col = tuple(int(c) for c in np.atleast_1d(color))
    h, w = out.shape[:2]
    for x, y in pts:
        if not (np.isfinite(x) and np.isfinite(y)):
            continue                      # behind the camera: nothing to draw
        # far away points cannot touch the image (and would overflow int32)
        if x < -radius - 1 or y < -radius - 1 or x > w + radius or y > h + radius:
            continue
        cv2.circle(out, (int(np.round(x)), int(np.round(y))), int(radius), col,
                   thickness=-1)
    return out


def project_onto_image(image, P, points):
    """Project with P and mark the points on the image."""
    pts = project(P, points)
    pts = np.atleast_2d(pts)
    return draw_points(image, pts), pts


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


# --------------------------------------------------------------------- ext1
def calibrate(images, pattern_size, square_size):
    """Zhang calibration, following the OpenCV calibration tutorial."""
    cols, rows = int(pattern_size[0]), int(pattern_size[1])
    objp = np.zeros((cols * rows, 3), np.float32)
    objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size

    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 0.001)
    obj_points, img_points = [], []
    size = None
    for img in images:
        img = np.asarray(img)
        grey = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY) if img.ndim == 3 else img
        grey = np.ascontiguousarray(grey, dtype=np.uint8)
        size = (grey.shape[1], grey.shape[0])
        found, corners = cv2.findChessboardCorners(grey, (cols, rows), None)
        if not found:
            continue
        win = _subpix_window(corners, (cols, rows))
        corners = cv2.cornerSubPix(grey, corners, win, (-1, -1), criteria)
        obj_points.append(objp)
        img_points.append(corners)
    if not obj_points:
        raise ValueError("no chessboard found in any image")

    rms, K, dist, _, _ = cv2.calibrateCamera(obj_points, img_points, size,
                                             None, None)
    return (np.asarray(K, dtype=np.float64),
            np.asarray(dist, dtype=np.float64).ravel()[:5],
            float(rms))


# --------------------------------------------------------------------- ext2
def distort_points(points, dist):
    """Brown-Conrady distortion of normalised coordinates (Szeliski eq. 2.78)."""
    pts, single = _as_points(points, 2)
    d = np.zeros(5)
    dd = np.asarray(dist, dtype=np.float64).ravel()[:5]
    d[:dd.size] = dd
    k1, k2, p1, p2, k3 = d
    x, y = pts[:, 0], pts[:, 1]
    r2 = x * x + y * y
    radial = 1.0 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    xd = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x)
    yd = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y
    out = np.column_stack([xd, yd])
    return out[0] if single else out
