"""Lab 9 - geometric camera models.

Choices I made where the lab leaves them open:
- projections follow the lab sheet's formulas literally: a point behind the
  camera gets whatever the formula gives (it appears mirrored), Z = 0 gives
  inf; results are returned as float32 (enough for pixel positions);
- camera matrices are projective, so ``camera_matrix`` returns K [R | t]
  normalised to unit Frobenius norm (and with the overall sign flipped: the
  same camera);
- inputs may be lists, read-only or non-contiguous arrays; they are never
  modified.
"""

import cv2
import numpy as np


def _points3(points):
    p = np.array(points, dtype=np.float64, copy=True)
    single = p.ndim == 1
    return p.reshape(-1, 3), single


def _finish(xy, single):
    xy = np.asarray(xy, dtype=np.float32)
    return xy[0] if single else xy


# --------------------------------------------------------------------- ex1
def pinhole_project(points, f):
    """x = f X / Z, y = f Y / Z (plain formula, no special case for Z <= 0)."""
    p, single = _points3(points)
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = float(f) * p[:, :2] / p[:, 2:3]
    return _finish(xy, single)


# --------------------------------------------------------------------- ex2
def intrinsic_matrix(f, px, py):
    """K = [[f, 0, px], [0, f, py], [0, 0, 1]]."""
    K = np.eye(3)
    K[0, 0] = K[1, 1] = f
    K[0, 2], K[1, 2] = px, py
    return K


def project_with_intrinsics(K, points):
    """u = K X, then divide by the third coordinate."""
    K = np.asarray(K, dtype=np.float64)
    p, single = _points3(points)
    uvw = np.einsum("ij,nj->ni", K, p)
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = uvw[:, :2] / uvw[:, 2:]
    return _finish(xy, single)


# --------------------------------------------------------------------- ex3
def camera_matrix(K, R, t):
    """P ~ K [R | t]; returned with unit Frobenius norm and negative sign."""
    Rt = np.zeros((3, 4))
    Rt[:, :3] = np.asarray(R, dtype=np.float64)
    Rt[:, 3] = np.asarray(t, dtype=np.float64).ravel()
    P = np.asarray(K, dtype=np.float64) @ Rt
    return -P / np.linalg.norm(P)


def project(P, points):
    """x = P [X, 1], then (u / w, v / w).  Any scale of P gives the same answer."""
    P = np.asarray(P, dtype=np.float64)
    p, single = _points3(points)
    uvw = p @ P[:, :3].T + P[:, 3]
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = uvw[:, :2] / uvw[:, 2:]
    return _finish(xy, single)


# --------------------------------------------------------------------- ex4
def project_focal_lengths(points, focal_lengths):
    """(F, N, 2): the pinhole image for every focal length, by broadcasting."""
    p, _ = _points3(points)
    fs = np.asarray(focal_lengths, dtype=np.float64).reshape(-1, 1, 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        base = p[:, :2] / p[:, 2:3]          # f = 1 image, (N, 2)
    return (fs * base[None]).astype(np.float32)


def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
    """Landing points of rays through a round pinhole of radius ``aperture``.

    x = f X / Z - ax (1 + f / Z), y = f Y / Z - ay (1 + f / Z).
    The random numbers are drawn ray-major: one (n_rays, N, 2) block, angle
    first then radius.
    """
    p, _ = _points3(points)
    n = p.shape[0]
    rng = np.random.default_rng(seed)
    draws = rng.random((n_rays, n, 2))
    phi = 2.0 * np.pi * draws[..., 0]               # v -> angle
    r = float(aperture) * np.sqrt(draws[..., 1])    # u -> radius (uniform area)
    a = np.stack([r * np.cos(phi), r * np.sin(phi)], axis=-1)   # (n_rays, N, 2)
    a = np.transpose(a, (1, 0, 2))                  # (N, n_rays, 2)

    Z = p[:, 2:3]
    ideal = float(f) * p[:, :2] / Z                 # (N, 2)
    blur = 1.0 + float(f) / Z                       # (N, 1)
    rays = ideal[:, None, :] - a * blur[:, :, None]
    return rays.astype(np.float32)


# --------------------------------------------------------------------- ex5
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    """Filled discs, drawn with a NumPy mask (all pixels within ``radius``).

    Centres are rounded half-up (floor(x + 0.5)).  A grey image stays grey
    (it gets the first colour component).
    """
    out = np.array(image, copy=True)
    pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    h, w = out.shape[:2]
    r = int(radius)
    col = np.asarray(color, dtype=np.float64).ravel()
    value = col[0] if out.ndim == 2 else col[:out.shape[2]]
    value = np.clip(np.round(value), 0, 255).astype(out.dtype)
    dy, dx = np.mgrid[-r:r + 1, -r:r + 1]
    disc = dx * dx + dy * dy <= r * r
    for x, y in pts:
        if not (np.isfinite(x) and np.isfinite(y)):
            continue
        cx = int(np.floor(x + 0.5)) if abs(x) < 1e9 else -10 ** 9
        cy = int(np.floor(y + 0.5)) if abs(y) < 1e9 else -10 ** 9
        ys = dy[disc] + cy
        xs = dx[disc] + cx
        keep = (xs >= 0) & (xs < w) & (ys >= 0) & (ys < h)
        out[ys[keep], xs[keep]] = value
    return out


def project_onto_image(image, P, points):
    """Project the points with P and draw them (red, radius 3)."""
    pts = np.asarray(project(P, points)).reshape(-1, 2)
    return draw_points(image, pts), pts


# --------------------------------------------------------------------- ext1
def calibrate(images, pattern_size, square_size):
    """Zhang calibration with OpenCV (smaller sub-pixel window, tighter stop)."""
    cols, rows = int(pattern_size[0]), int(pattern_size[1])
    grid = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * float(square_size)
    board = np.hstack([grid, np.zeros((grid.shape[0], 1))]).astype(np.float32)

    stop = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 50, 1e-4)
    flags = cv2.CALIB_CB_ADAPTIVE_THRESH | cv2.CALIB_CB_NORMALIZE_IMAGE
    objs, imgs, size = [], [], None
    for image in list(images):
        image = np.ascontiguousarray(image)
        grey = image if image.ndim == 2 else cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
        size = (grey.shape[1], grey.shape[0])
        ok, corners = cv2.findChessboardCorners(grey, (cols, rows), flags=flags)
        if not ok:
            continue
        corners = cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1), stop)
        objs.append(board)
        imgs.append(corners.reshape(-1, 1, 2))
    if not objs:
        raise RuntimeError("calibrate: the chessboard was not found in any image")
    rms, K, dist, _rvecs, _tvecs = cv2.calibrateCamera(
        objs, imgs, size, np.eye(3), np.zeros(5))
    d = np.zeros(5)
    dd = np.asarray(dist, dtype=np.float64).ravel()[:5]
    d[:dd.size] = dd
    return np.asarray(K, dtype=np.float64), d, float(rms)


# --------------------------------------------------------------------- ext2
def distort_points(points, dist):
    """Brown-Conrady distortion via cv2.projectPoints of (x, y, 1), zero pose, K = I.

    Accepts 4, 5 (or more) OpenCV coefficients.
    """
    p = np.array(points, dtype=np.float64, copy=True)
    single = p.ndim == 1
    p = p.reshape(-1, 2)
    d = np.asarray(dist, dtype=np.float64).ravel()
    if d.size < 4:
        d = np.concatenate([d, np.zeros(4 - d.size)])
    obj = np.hstack([p, np.ones((p.shape[0], 1))]).reshape(-1, 1, 3)
    if p.shape[0] == 0:
        out = np.zeros((0, 2))
    else:
        img, _ = cv2.projectPoints(obj, np.zeros(3), np.zeros(3), np.eye(3), d)
        out = img.reshape(-1, 2).astype(np.float64)
    return out[0] if single else out
