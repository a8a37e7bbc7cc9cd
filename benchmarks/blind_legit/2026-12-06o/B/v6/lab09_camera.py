"""Lab 9 - geometric camera models.

Every function converts its inputs explicitly (lists, ints, float32, views are
all fine), never writes into them, and follows these conventions:

- 3D points ``(N, 3)``; a single ``(3,)`` point gives a single ``(2,)`` result.
- 2D points ``(N, 2)`` of ``(x, y)`` = (column, row), y down.
- Camera looks along +Z; ``X_cam = R X_world + t``.
- Points behind the camera (depth <= 0) have no image: I return ``[nan, nan]``
  for them, one row per input point all the same.
"""

import cv2
import numpy as np


# ------------------------------------------------------------------ helpers
def _as_points3d(points):
    """Return (float64 (N, 3) copy, was_single_point)."""
    arr = np.array(points, dtype=np.float64)          # np.array copies: input is safe
    single = arr.ndim == 1
    if single:
        arr = arr.reshape(1, -1)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"expected (N, 3) or (3,) points, got shape {np.shape(points)}")
    return arr, single


def _as_matrix(M, shape, name):
    """Return a float64 copy of ``M`` after checking its shape."""
    arr = np.array(M, dtype=np.float64)
    if arr.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {arr.shape}")
    return arr


def _finish(result, single):
    """Undo the (3,) -> (1, 3) promotion on the way out."""
    return result[0] if single else result


def _dehomogenise(uvw, depth_sign=1.0):
    """(N, 3) homogeneous image points -> (N, 2) pixels.

    A point is in front of the camera when ``depth_sign * w > 0``; elsewhere
    the result is NaN (this also avoids dividing by zero).
    """
    out = np.full((uvw.shape[0], 2), np.nan)
    front = depth_sign * uvw[:, 2] > 0
    out[front] = uvw[front, :2] / uvw[front, 2:3]
    return out


# --------------------------------------------------------------------- ex1
def pinhole_project(points, f):
    """Project camera-frame points with a pinhole camera of focal length ``f``.

    ``x = f X / Z``, ``y = f Y / Z``; NaN for points with ``Z <= 0``.
    """
    pts, single = _as_points3d(points)
    f = float(f)
    out = np.full((pts.shape[0], 2), np.nan)
    front = pts[:, 2] > 0
    out[front, 0] = f * pts[front, 0] / pts[front, 2]
    out[front, 1] = f * pts[front, 1] / pts[front, 2]
    return _finish(out, single)


# --------------------------------------------------------------------- ex2
def intrinsic_matrix(f, px, py):
    """``K = [[f, 0, px], [0, f, py], [0, 0, 1]]`` as float64."""
    f, px, py = float(f), float(px), float(py)
    return np.array([[f, 0.0, px],
                     [0.0, f, py],
                     [0.0, 0.0, 1.0]])


def project_with_intrinsics(K, points):
    """``(u, v, w) = K (X, Y, Z)``, then ``(u / w, v / w)``; NaN where ``w <= 0``.

    K may be any intrinsic matrix (fx != fy, skew); K[2] is normally (0, 0, 1)
    so that w = Z.
    """
    K = _as_matrix(K, (3, 3), "K")
    pts, single = _as_points3d(points)
    uvw = pts @ K.T
    return _finish(_dehomogenise(uvw), single)


# --------------------------------------------------------------------- ex3
def camera_matrix(K, R, t):
    """``P = K [R | t]`` (3 x 4)."""
    K = _as_matrix(K, (3, 3), "K")
    R = _as_matrix(R, (3, 3), "R")
    t = np.array(t, dtype=np.float64).reshape(-1)
    if t.shape != (3,):
        raise ValueError(f"t must have 3 entries, got {t.size}")
    Rt = np.hstack([R, t.reshape(3, 1)])
    return K @ Rt


def project(P, points):
    """Project world points with the camera matrix ``P`` (any non-zero scale).

    For ``P = s K [R | t]`` the third coordinate is ``w = s * depth`` (K has a
    positive diagonal, det R = +1), and ``sign(det P[:, :3]) = sign(s)``. So a
    point is in front of the camera when ``w * sign(det M) > 0``; for the usual
    ``s > 0`` that is just ``w > 0``.
    """
    P = _as_matrix(P, (3, 4), "P")
    pts, single = _as_points3d(points)
    homog = np.hstack([pts, np.ones((pts.shape[0], 1))])
    uvw = homog @ P.T
    det_m = np.linalg.det(P[:, :3])
    # A singular M (camera at infinity) has no "behind": fall back to w > 0.
    depth_sign = 1.0 if det_m == 0 else float(np.sign(det_m))
    return _finish(_dehomogenise(uvw, depth_sign), single)


# --------------------------------------------------------------------- ex4
def project_focal_lengths(points, focal_lengths):
    """``result[i] = pinhole_project(points, focal_lengths[i])``, shape (F, N, 2)."""
    pts, _ = _as_points3d(points)             # keep the N axis even for one point
    fls = np.array(focal_lengths, dtype=np.float64).reshape(-1)
    result = np.empty((fls.size, pts.shape[0], 2))
    # A short loop over the (few) focal lengths reads like the lab sheet.
    for i, f in enumerate(fls):
        result[i] = pinhole_project(pts, f)
    return result


def _sample_disc(rng, radius, shape):
    """Points uniform over the area of a disc: r = R sqrt(u), angle = 2 pi v."""
    u = rng.random(shape)
    v = rng.random(shape)
    r = radius * np.sqrt(u)
    angle = 2.0 * np.pi * v
    return r * np.cos(angle), r * np.sin(angle)


def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
    """Where the rays from each point through a finite pinhole land.

    Pinhole: disc of radius ``aperture`` in the plane Z = 0; image plane at
    Z = -f. The ray from X = (X, Y, Z) through A = (ax, ay, 0) meets Z = -f at
    ``A + (A - X) f / Z``; turned upright (negated) that is
    ``x = f X / Z - ax (1 + f / Z)`` (same for y). So the rays scatter around
    the ideal projection in a blur disc of radius ``aperture (1 + f / Z)``.
    """
    pts, _ = _as_points3d(points)
    f = float(f)
    aperture = float(aperture)
    n_rays = int(n_rays)
    if aperture < 0:
        raise ValueError("aperture is a radius and must be >= 0")
    if n_rays < 0:
        raise ValueError("n_rays must be >= 0")
    rng = np.random.default_rng(seed)
    n = pts.shape[0]
    ax, ay = _sample_disc(rng, aperture, (n, n_rays))

    ideal = pinhole_project(pts, f)                    # (N, 2), NaN for Z <= 0
    with np.errstate(divide="ignore", invalid="ignore"):
        spread = np.where(pts[:, 2] > 0, 1.0 + f / pts[:, 2], np.nan)   # (N,)
    result = np.empty((n, n_rays, 2))
    result[:, :, 0] = ideal[:, 0:1] - ax * spread[:, None]
    result[:, :, 1] = ideal[:, 1:2] - ay * spread[:, None]
    return result


# --------------------------------------------------------------------- ex5
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    """Filled circles at the (rounded) points, drawn on a copy of ``image``.

    NaN / infinite points are skipped. Points far outside the image are skipped
    too (they could not show, and cv2 only takes int32 centres).
    """
    img = np.asarray(image)
    if img.dtype != np.uint8:
        raise ValueError("image must be uint8")
    out = np.ascontiguousarray(img).copy()             # never draw on the input
    h, w = out.shape[:2]
    radius = int(round(float(radius)))
    color_vals = [int(c) for c in np.ravel(color)]
    if out.ndim == 2:
        # A grey image has one channel: use the colour's brightness.
        b, g, r = (color_vals + [0, 0, 0])[:3]
        colour = int(round(0.114 * b + 0.587 * g + 0.299 * r))
    else:
        colour = tuple(color_vals)

    p = np.array(pts, dtype=np.float64).reshape(-1, 2)
    for x, y in p:
        if not (np.isfinite(x) and np.isfinite(y)):
            continue
        cx, cy = int(np.rint(x)), int(np.rint(y))
        if cx < -radius or cy < -radius or cx > w + radius or cy > h + radius:
            continue                                    # cannot touch the image
        cv2.circle(out, (cx, cy), radius, colour, thickness=-1)
    return out


def project_onto_image(image, P, points):
    """Project ``points`` with ``P`` and draw them (default radius / colour)."""
    pts = project(P, points)
    pts2 = np.atleast_2d(pts)
    return draw_points(image, pts2), pts


# --------------------------------------------------------------------- ext1
def _to_grey(image):
    img = np.asarray(image)
    if img.dtype != np.uint8:
        raise ValueError("images must be uint8")
    if img.ndim == 3 and img.shape[2] == 3:
        return cv2.cvtColor(np.ascontiguousarray(img), cv2.COLOR_BGR2GRAY)
    if img.ndim == 3 and img.shape[2] == 1:
        return np.ascontiguousarray(img[:, :, 0])
    if img.ndim == 2:
        return np.ascontiguousarray(img)
    raise ValueError(f"unsupported image shape {img.shape}")


def _board_points(pattern_size, square_size):
    """Inner corners on Z = 0, row by row with x fastest (OpenCV's order)."""
    cols, rows = int(pattern_size[0]), int(pattern_size[1])
    obj = np.zeros((cols * rows, 3), np.float32)
    obj[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * float(square_size)
    return obj


def _refine_window(corners, pattern_size):
    """cornerSubPix half-window: about a third of the corner spacing in pixels.

    A fixed (11, 11) window covers neighbouring corners on a small board and
    pulls the estimate away; scaling with the spacing (between 2 and 11)
    keeps the window inside one square.
    """
    cols = int(pattern_size[0])
    c = corners.reshape(-1, 2)
    rows = c.shape[0] // cols
    grid = c.reshape(rows, cols, 2)
    steps = [np.linalg.norm(np.diff(grid, axis=1), axis=2).ravel()]
    if rows > 1:
        steps.append(np.linalg.norm(np.diff(grid, axis=0), axis=2).ravel())
    spacing = float(np.min(np.concatenate(steps))) if cols > 1 or rows > 1 else 15.0
    half = int(np.clip(spacing / 3.0, 2, 11))
    return (half, half)


def _find_corners(grey, pattern_size):
    """Detected and sub-pixel refined corners (M, 1, 2) float32, or None."""
    size = (int(pattern_size[0]), int(pattern_size[1]))
    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE
    found, corners = cv2.findChessboardCorners(grey, size, flags=flags)
    if not found or corners is None or len(corners) != size[0] * size[1]:
        return None
    criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 50, 1e-4)
    win = _refine_window(corners, size)
    corners = cv2.cornerSubPix(grey, corners.astype(np.float32), win, (-1, -1), criteria)
    return corners


def calibrate(images, pattern_size, square_size):
    """Zhang's calibration from chessboard views with OpenCV.

    Returns ``(K (3, 3), dist (5,) = (k1, k2, p1, p2, k3), rms)``. Views where
    the board is not found are left out; at least one view must have it.
    """
    images = list(images)
    if not images:
        raise ValueError("no images given")
    objp = _board_points(pattern_size, square_size)
    object_points, image_points = [], []
    image_size = None
    for img in images:
        grey = _to_grey(img)
        size = (grey.shape[1], grey.shape[0])              # (width, height)
        if image_size is None:
            image_size = size
        elif size != image_size:
            raise ValueError("all calibration images must have the same size")
        corners = _find_corners(grey, pattern_size)
        if corners is not None:
            object_points.append(objp.copy())
            image_points.append(corners)
    if not object_points:
        raise ValueError("the chessboard was not found in any image")

    rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points,
                                             image_size, None, None)
    dist = np.asarray(dist, dtype=np.float64).reshape(-1)
    dist5 = np.zeros(5)
    dist5[:min(5, dist.size)] = dist[:5]
    return np.asarray(K, dtype=np.float64), dist5, float(rms)


# --------------------------------------------------------------------- ext2
def distort_points(points, dist):
    """Brown-Conrady distortion of normalised coordinates, written out.

    ``dist = (k1, k2, p1, p2, k3)``; a shorter vector is padded with zeros
    (four coefficients means k3 = 0).
    """
    p = np.array(points, dtype=np.float64)
    single = p.ndim == 1
    p = p.reshape(-1, 2)
    d = np.zeros(5)
    coeffs = np.array(dist, dtype=np.float64).reshape(-1)[:5]
    d[:coeffs.size] = coeffs
    k1, k2, p1, p2, k3 = d

    x, y = p[:, 0], p[:, 1]
    r2 = x * x + y * y
    radial = 1.0 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
    xd = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x)
    yd = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y
    out = np.column_stack([xd, yd])
    return _finish(out, single)
