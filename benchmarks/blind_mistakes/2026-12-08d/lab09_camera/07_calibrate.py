"""Lab 9 - geometric camera models (reference solution).

A pinhole camera maps a 3D point to the image by a perspective division:
``x = f X / Z``. Writing the same thing with homogeneous coordinates gives the
intrinsic matrix ``K`` (focal length and principal point) and the camera matrix
``P = K [R | t]``, which first moves world points into the camera's frame
(``X_cam = R X + t``) and then projects them.

Points with ``Z <= 0`` (behind the camera, or in the plane of the pinhole)
have no image: every projection here returns NaN for them.
"""

import cv2
import numpy as np


def _points(points):
    """``(N, 3)`` float array, and whether a single ``(3,)`` point was given."""
    points = np.asarray(points, dtype=np.float64)
    return np.atleast_2d(points), points.ndim == 1


def _divide(homogeneous, single):
    """Perspective division of ``(N, 3)`` homogeneous image points; NaN where w <= 0."""
    w = homogeneous[:, 2:3]
    with np.errstate(divide="ignore", invalid="ignore"):
        pts = homogeneous[:, :2] / w
    pts[w[:, 0] <= 0] = np.nan
    return pts[0] if single else pts


# --------------------------------------------------------------------- ex1
def pinhole_project(points, f):
    """``x = f X / Z``, ``y = f Y / Z`` (image origin on the optical axis)."""
    X, single = _points(points)
    return _divide(np.column_stack([f * X[:, 0], f * X[:, 1], X[:, 2]]), single)


# --------------------------------------------------------------------- ex2
def intrinsic_matrix(f, px, py):
    """K = [[f, 0, px], [0, f, py], [0, 0, 1]]."""
    return np.array([[f, 0.0, px],
                     [0.0, f, py],
                     [0.0, 0.0, 1.0]], dtype=np.float64)


def project_with_intrinsics(K, points):
    """Camera-frame points to pixels: ``x ~ K X``, then divide by the third coordinate."""
    X, single = _points(points)
    return _divide(X @ np.asarray(K, dtype=np.float64).T, single)


# --------------------------------------------------------------------- ex3
def camera_matrix(K, R, t):
    """P = K [R | t] (3 x 4)."""
    Rt = np.column_stack([np.asarray(R, dtype=np.float64), np.asarray(t, dtype=np.float64).reshape(3)])
    return np.asarray(K, dtype=np.float64) @ Rt


def project(P, points):
    """World points to pixels: ``x ~ P [X, 1]``, then the perspective division."""
    X, single = _points(points)
    homogeneous = np.column_stack([X, np.ones(len(X))])
    return _divide(homogeneous @ np.asarray(P, dtype=np.float64).T, single)


# --------------------------------------------------------------------- ex4
def project_focal_lengths(points, focal_lengths):
    """The pinhole projection for every focal length: (F, N, 2)."""
    X, _ = _points(points)
    return np.stack([pinhole_project(X, f) for f in np.asarray(focal_lengths, dtype=np.float64).ravel()])


def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
    """Where rays through random points of a round pinhole of radius ``aperture`` land.

    The pinhole is the disc of radius ``aperture`` in the plane ``Z = 0``; the
    image plane is ``Z = -f`` behind it. The ray from ``X`` through the aperture
    point ``A = (ax, ay, 0)`` meets the image plane at ``-f X / Z + A (1 + f / Z)``
    (per coordinate); like ``pinhole_project`` we report the upright (virtual)
    image, so the sign flips: ``f X / Z - A (1 + f / Z)``. Each point spreads
    into a disc of radius ``aperture * (1 + f / Z)`` centred on its ideal
    projection.
    """
    X, _ = _points(points)
    rng = np.random.default_rng(seed)
    # uniform over the disc's area: radius ~ sqrt(uniform)
    radius = aperture * np.sqrt(rng.uniform(0.0, 1.0, size=(len(X), n_rays)))
    angle = rng.uniform(0.0, 2 * np.pi, size=(len(X), n_rays))
    A = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)     # (N, n_rays, 2)
    ideal = pinhole_project(X, f)                                                # (N, 2)
    spread = 1.0 + f / X[:, 2]                                                   # (N,)
    return ideal[:, None, :] - A * spread[:, None, None]


# --------------------------------------------------------------------- ex5
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    """A copy of ``image`` with a filled circle at every finite point."""
    out = image.copy()
    color = tuple(int(c) for c in color)
    for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
        if np.isfinite(x) and np.isfinite(y):
            cv2.circle(out, (int(round(x)), int(round(y))), int(radius), color, thickness=-1)
    return out


def project_onto_image(image, P, points):
    """Project world points with ``P`` and draw them on (a copy of) ``image``."""
    pts = project(P, points)
    pts = pts.reshape(-1, 2)
    return draw_points(image, pts), pts


# --------------------------------------------------------------------- ext1
def calibrate(images, pattern_size, square_size):
    """Zhang's calibration from chessboard views with OpenCV.

    The object points are the inner corners on the board plane Z = 0, row by
    row: ``(i * square_size, j * square_size, 0)`` for ``j`` in rows, ``i`` in
    columns -- the order ``cv2.findChessboardCorners`` returns them in.
    """
    cols, rows = pattern_size
    objp = np.zeros((cols * rows, 3), np.float32)
    objp[:, :2] = np.mgrid[0:rows, 0:cols].T.reshape(-1, 2) * square_size
    object_points, image_points = [], []
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)
    for image in images:
        grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
        found, corners = cv2.findChessboardCorners(grey, (cols, rows))
        if not found:
            continue
        corners = cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1), criteria)
        object_points.append(objp)
        image_points.append(corners)
    if not image_points:
        raise ValueError("no chessboard found in any image")
    height, width = images[0].shape[:2]
    rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, (width, height), None, None)
    return K, dist.ravel()[:5], float(rms)


# --------------------------------------------------------------------- ext2
def distort_points(points, dist):
    """Brown-Conrady distortion of normalised image coordinates (OpenCV's model).

    ``r^2 = x^2 + y^2``;
    ``x' = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)``;
    ``y' = y (1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y``.
    """
    pts = np.asarray(points, dtype=np.float64)
    single = pts.ndim == 1
    pts = np.atleast_2d(pts)
    k1, k2, p1, p2, k3 = (list(np.asarray(dist, dtype=np.float64).ravel()) + [0.0] * 5)[:5]
    x, y = pts[:, 0], pts[:, 1]
    r2 = x * x + y * y
    radial = 1.0 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    out = np.column_stack([xd, yd])
    return out[0] if single else out
