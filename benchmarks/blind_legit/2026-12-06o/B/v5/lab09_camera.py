"""Lab 9 - geometric camera models.

Short vectorised NumPy versions; OpenCV where the sheet/skeleton names a call.
Points behind the camera come back as NaN.
"""

import cv2
import numpy as np


def _dehom(xyw):
    """(N, 3) homogeneous -> (N, 2); NaN where the third coordinate is <= 0."""
    w = xyw[:, 2:3]
    with np.errstate(divide="ignore", invalid="ignore"):
        out = xyw[:, :2] / w
    out[w[:, 0] <= 0] = np.nan
    return out


def _pts3(points):
    p = np.asarray(points, dtype=float)
    return np.atleast_2d(p), p.ndim == 1


# --------------------------------------------------------------------- ex1
def pinhole_project(points, f):
    """x = f X / Z, y = f Y / Z (NaN for Z <= 0)."""
    p, single = _pts3(points)
    out = _dehom(p * [f, f, 1.0])
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def intrinsic_matrix(f, px, py):
    """K = [[f, 0, px], [0, f, py], [0, 0, 1]]."""
    return np.array([[f, 0, px], [0, f, py], [0, 0, 1]], dtype=float)


def project_with_intrinsics(K, points):
    """(u, v, w) = K X, then (u/w, v/w); NaN where w <= 0."""
    p, single = _pts3(points)
    out = _dehom(p @ np.asarray(K, float).T)
    return out[0] if single else out


# --------------------------------------------------------------------- ex3
def camera_matrix(K, R, t):
    """P = K [R | t]."""
    return np.asarray(K, float) @ np.column_stack([np.asarray(R, float), np.ravel(t).astype(float)])


def project(P, points):
    """(u, v, w) = P (X, 1), then (u/w, v/w).

    P is only known up to scale, so "in front of the camera" means w has the
    sign of det(P[:, :3]) (the depth of P = s K[R|t] is sign(det M) * w).
    """
    P = np.asarray(P, float)
    p, single = _pts3(points)
    xyw = np.c_[p, np.ones(len(p))] @ P.T
    s = np.sign(np.linalg.det(P[:, :3])) or 1.0
    out = _dehom(xyw * s)  # scaling by s changes nothing but the sign test
    return out[0] if single else out


# --------------------------------------------------------------------- ex4
def project_focal_lengths(points, focal_lengths):
    """(F, N, 2): the unit-focal projection scaled by each f."""
    p, _ = _pts3(points)
    return np.asarray(focal_lengths, float).reshape(-1, 1, 1) * pinhole_project(p, 1.0)[None]


def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
    """Rays from each point through random points of a disc of radius ``aperture``.

    x = f X/Z - ax (1 + f/Z), y = f Y/Z - ay (1 + f/Z).
    """
    p, _ = _pts3(points)
    rng = np.random.default_rng(seed)
    u, v = rng.random((2, len(p), n_rays))
    r, th = aperture * np.sqrt(u), 2 * np.pi * v
    a = np.stack([r * np.cos(th), r * np.sin(th)], axis=-1)          # (N, n, 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        blur = (1 + f / p[:, 2])[:, None, None]
    return pinhole_project(p, f)[:, None, :] - a * blur


# --------------------------------------------------------------------- ex5
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    """Filled circles at the rounded points, on a copy; NaN / far-off points skipped."""
    out = np.ascontiguousarray(image).copy()
    h, w = out.shape[:2]
    pts = np.asarray(pts, float).reshape(-1, 2)
    ok = np.isfinite(pts).all(1) & (np.abs(pts) < 4 * max(h, w) + radius + 1).all(1)
    color = tuple(int(c) for c in color)
    for x, y in np.rint(pts[ok]).astype(int):
        cv2.circle(out, (int(x), int(y)), int(radius), color, -1)
    return out


def project_onto_image(image, P, points):
    pts = project(P, points)
    return draw_points(image, pts), pts


# --------------------------------------------------------------------- ext1
def calibrate(images, pattern_size, square_size):
    """Zhang calibration with cv2.findChessboardCorners / cornerSubPix / calibrateCamera."""
    cols, rows = pattern_size
    objp = np.zeros((cols * rows, 3), np.float32)
    objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
    crit = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)
    obj, img, size = [], [], None
    for im in images:
        g = cv2.cvtColor(im, cv2.COLOR_BGR2GRAY) if im.ndim == 3 else np.ascontiguousarray(im)
        size = g.shape[::-1]
        ok, c = cv2.findChessboardCorners(g, (cols, rows))
        if ok:
            obj.append(objp)
            img.append(cv2.cornerSubPix(g, c, (5, 5), (-1, -1), crit))
    if not obj:
        raise ValueError("no chessboard found in any image")
    rms, K, dist, _, _ = cv2.calibrateCamera(obj, img, size, None, None)
    return K, dist.ravel()[:5].astype(float), float(rms)


# --------------------------------------------------------------------- ext2
def distort_points(points, dist):
    """Brown-Conrady distortion of normalised points, via cv2.projectPoints (K = I, zero pose)."""
    p = np.asarray(points, float)
    single = p.ndim == 1
    p = p.reshape(-1, 2)
    obj = np.c_[p, np.ones(len(p))]
    out, _ = cv2.projectPoints(obj, np.zeros(3), np.zeros(3), np.eye(3),
                               np.asarray(dist, float).ravel())
    out = out.reshape(-1, 2)
    return out[0] if single else out
