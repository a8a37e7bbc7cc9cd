"""Lab 9 - geometric camera models.

My solutions, written straight from the lecture equations with NumPy.
OpenCV is only used where the lab sheet asks for it (drawing is done by hand,
chessboard detection and calibration use OpenCV).

Conventions
-----------
- 3D points are (N, 3) float arrays; a single (3,) point gives a single (2,) result.
- 2D points are (N, 2) arrays of (x, y) = (column, row), y pointing down.
- A world point X has camera coordinates R @ X + t; the camera looks along +Z.
- Points behind the camera (Z <= 0) have no image: I return NaN for them.
"""

import cv2
import numpy as np


def _as_points(points, dim=3):
    """Return the points as a float (N, dim) array and whether one point was given."""
    pts = np.asarray(points, dtype=float)
    single = pts.ndim == 1
    pts = np.atleast_2d(pts).reshape(-1, dim)
    return pts, single


# --------------------------------------------------------------------- ex1
def pinhole_project(points, f):
    """Pinhole projection x = f X / Z, y = f Y / Z (NaN for Z <= 0).

    >>> pinhole_project(np.array([[1.0, 2.0, 10.0]]), 500)
    array([[ 50., 100.]])
    """
    pts, single = _as_points(points)
    X, Y, Z = pts[:, 0], pts[:, 1], pts[:, 2]
    out = np.full((pts.shape[0], 2), np.nan)
    front = Z > 0
    out[front, 0] = f * X[front] / Z[front]
    out[front, 1] = f * Y[front] / Z[front]
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def intrinsic_matrix(f, px, py):
    """K = [[f, 0, px], [0, f, py], [0, 0, 1]]."""
    K = np.array([[f, 0.0, px],
                  [0.0, f, py],
                  [0.0, 0.0, 1.0]], dtype=float)
    return K


def _dehomogenise(x_h):
    """(N, 3) homogeneous image points -> (N, 2), NaN where w <= 0."""
    out = np.full((x_h.shape[0], 2), np.nan)
    w = x_h[:, 2]
    front = w > 0
    out[front] = x_h[front, :2] / w[front, None]
    return out


def project_with_intrinsics(K, points):
    """(u, v, w) = K (X, Y, Z), then (u / w, v / w); NaN where w <= 0."""
    K = np.asarray(K, dtype=float)
    pts, single = _as_points(points)
    x_h = (K @ pts.T).T          # one homogeneous image point per row
    out = _dehomogenise(x_h)
    return out[0] if single else out


# --------------------------------------------------------------------- ex3
def camera_matrix(K, R, t):
    """P = K [R | t]."""
    K = np.asarray(K, dtype=float)
    R = np.asarray(R, dtype=float)
    t = np.asarray(t, dtype=float).reshape(3, 1)
    Rt = np.hstack([R, t])       # the 3x4 extrinsic matrix [R | t]
    return K @ Rt


def project(P, points):
    """(u, v, w) = P (X, Y, Z, 1), then (u / w, v / w); NaN where w <= 0."""
    P = np.asarray(P, dtype=float)
    pts, single = _as_points(points)
    X_h = np.hstack([pts, np.ones((pts.shape[0], 1))])
    x_h = (P @ X_h.T).T
    out = _dehomogenise(x_h)
    return out[0] if single else out


# --------------------------------------------------------------------- ex4
def project_focal_lengths(points, focal_lengths):
    """result[i] = pinhole_project(points, focal_lengths[i]), shape (F, N, 2)."""
    pts, _ = _as_points(points)
    fs = np.atleast_1d(np.asarray(focal_lengths, dtype=float))
    result = np.zeros((len(fs), pts.shape[0], 2))
    for i, f in enumerate(fs):
        result[i] = pinhole_project(pts, f)
    return result


def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
    """Where rays through a circular pinhole of radius ``aperture`` land.

    A ray from X through the aperture point A = (ax, ay, 0) hits the image
    plane Z = -f at  X_img = -f X / Z + ax (1 + f / Z); turned upright that is
    x = f X / Z - ax (1 + f / Z)  (same for y).
    """
    pts, _ = _as_points(points)
    rng = np.random.default_rng(seed)
    n = pts.shape[0]

    # uniform samples over the disc's area
    u = rng.random((n, n_rays))
    v = rng.random((n, n_rays))
    r = aperture * np.sqrt(u)
    phi = 2.0 * np.pi * v
    ax = r * np.cos(phi)
    ay = r * np.sin(phi)

    X = pts[:, 0:1]
    Y = pts[:, 1:2]
    Z = pts[:, 2:3]
    blur = 1.0 + f / Z                      # (N, 1), grows for near points
    result = np.zeros((n, n_rays, 2))
    result[:, :, 0] = f * X / Z - ax * blur
    result[:, :, 1] = f * Y / Z - ay * blur
    return result


# --------------------------------------------------------------------- ex5
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    """Filled discs of ``radius`` around each (rounded) point, on a copy."""
    out = image.copy()
    h, w = out.shape[:2]
    pts = np.asarray(pts, dtype=float).reshape(-1, 2)
    rows, cols = np.mgrid[0:h, 0:w]
    col = np.array(color, dtype=out.dtype)
    if out.ndim == 2:
        col = col[0]
    for x, y in pts:
        if not (np.isfinite(x) and np.isfinite(y)):
            continue                        # no image (behind the camera)
        cx = int(np.floor(x + 0.5))
        cy = int(np.floor(y + 0.5))
        # only look at the bounding box of the disc
        x0, x1 = max(cx - radius, 0), min(cx + radius + 1, w)
        y0, y1 = max(cy - radius, 0), min(cy + radius + 1, h)
        if x0 >= x1 or y0 >= y1:
            continue                        # off the image
        rr = rows[y0:y1, x0:x1]
        cc = cols[y0:y1, x0:x1]
        disc = (cc - cx) ** 2 + (rr - cy) ** 2 <= radius ** 2
        out[y0:y1, x0:x1][disc] = col
    return out


def project_onto_image(image, P, points):
    """Project world points with P and mark them on a copy of the image."""
    pts = project(P, points)
    pts = np.atleast_2d(pts)
    drawn = draw_points(image, pts)
    return drawn, pts


# --------------------------------------------------------------------- ext1
def _board_points(pattern_size, square_size):
    cols, rows = pattern_size
    obj = np.zeros((cols * rows, 3), np.float32)
    obj[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
    return obj


def calibrate(images, pattern_size, square_size):
    """Zhang calibration with OpenCV from several chessboard views."""
    pattern_size = (int(pattern_size[0]), int(pattern_size[1]))
    obj = _board_points(pattern_size, square_size)
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)

    object_points, image_points = [], []
    image_size = None
    for img in images:
        gray = img if img.ndim == 2 else cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
        image_size = (gray.shape[1], gray.shape[0])       # (width, height)
        found, corners = cv2.findChessboardCorners(gray, pattern_size, None)
        if not found:
            continue
        corners = cv2.cornerSubPix(gray, corners, (11, 11), (-1, -1), criteria)
        object_points.append(obj)
        image_points.append(corners)

    if len(object_points) == 0:
        raise ValueError("no chessboard found in any image")

    rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points,
                                             image_size, None, None)
    return K.astype(float), np.asarray(dist, dtype=float).ravel()[:5], float(rms)


# --------------------------------------------------------------------- ext2
def distort_points(points, dist):
    """Brown-Conrady distortion of normalised coordinates (OpenCV's order)."""
    pts = np.asarray(points, dtype=float)
    single = pts.ndim == 1
    pts = np.atleast_2d(pts)
    d = np.zeros(5)
    dd = np.asarray(dist, dtype=float).ravel()
    d[:min(5, dd.size)] = dd[:5]
    k1, k2, p1, p2, k3 = d

    x = pts[:, 0]
    y = pts[:, 1]
    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    out = np.column_stack([xd, yd])
    return out[0] if single else out
