"""Lab 7 - 2D transformations.

My solutions follow the lecture equations directly: every transformation is
written down as a 3x3 matrix in homogeneous coordinates, and images are warped
with my own backward-mapping warp (``_warp``) in NumPy:

    for every output pixel p' the source position is p = M^-1 p',
    and the source image is sampled there with bilinear interpolation.

Backward mapping avoids holes in the output; pixels whose source position falls
outside the image get black (0), exactly like cv2.warpAffine with
BORDER_CONSTANT.

Conventions: (x, y) = (column, row), origin at the centre of the top-left
pixel, y pointing down. Angles in degrees, positive = counter-clockwise as the
image is displayed (the lecture's R(theta) with theta replaced by -theta).
"""

import cv2  # noqa: F401  (only used to check my results by hand)
import numpy as np


# ------------------------------------------------------------------ helpers
def _bilinear_sample(image, xs, ys):
    """Sample ``image`` at the float positions (xs, ys) bilinearly.

    Neighbours that lie outside the image count as black, so the border of
    the warped image fades to black like OpenCV's BORDER_CONSTANT.
    Returns float64 values of shape xs.shape (+ channels).
    """
    img = image.astype(np.float64)
    h, w = img.shape[:2]
    if img.ndim == 2:
        img = img[:, :, None]

    x0 = np.floor(xs).astype(np.int64)
    y0 = np.floor(ys).astype(np.int64)
    fx = xs - x0
    fy = ys - y0

    out = np.zeros(xs.shape + (img.shape[2],), dtype=np.float64)
    # the four neighbours and their bilinear weights
    for dy, dx, wgt in ((0, 0, (1 - fx) * (1 - fy)),
                        (0, 1, fx * (1 - fy)),
                        (1, 0, (1 - fx) * fy),
                        (1, 1, fx * fy)):
        xi = x0 + dx
        yi = y0 + dy
        inside = (xi >= 0) & (xi < w) & (yi >= 0) & (yi < h)
        vals = np.zeros(xs.shape + (img.shape[2],), dtype=np.float64)
        vals[inside] = img[yi[inside], xi[inside]]
        out += wgt[..., None] * vals
    if image.ndim == 2:
        out = out[..., 0]
    return out


def _warp(image, M, dsize=None):
    """Warp ``image`` by the 3x3 matrix ``M`` (source -> output coordinates).

    ``dsize`` is (width, height) of the output; default: the input's size.
    """
    h, w = image.shape[:2]
    if dsize is None:
        out_w, out_h = w, h
    else:
        out_w, out_h = int(dsize[0]), int(dsize[1])

    M = np.asarray(M, dtype=np.float64)
    Minv = np.linalg.inv(M)

    # homogeneous coordinates of every output pixel
    ys, xs = np.mgrid[0:out_h, 0:out_w].astype(np.float64)
    ones = np.ones_like(xs)
    pts = np.stack([xs.ravel(), ys.ravel(), ones.ravel()])  # 3 x (out_h*out_w)
    src = Minv @ pts
    sx = (src[0] / src[2]).reshape(out_h, out_w)
    sy = (src[1] / src[2]).reshape(out_h, out_w)

    # source positions more than one pixel outside the image see only black
    # neighbours; _bilinear_sample takes care of that by itself
    vals = _bilinear_sample(image, sx, sy)
    return np.clip(np.rint(vals), 0, 255).astype(np.uint8)


# --------------------------------------------------------------------- ex1
def translation_matrix(tx, ty):
    """The 3x3 translation matrix moving every point by ``(tx, ty)``."""
    T = np.array([[1.0, 0.0, float(tx)],
                  [0.0, 1.0, float(ty)],
                  [0.0, 0.0, 1.0]])
    return T


def translate(image, tx=100, ty=50):
    """Shift ``image`` right by ``tx`` and down by ``ty`` pixels, black fill."""
    return _warp(image, translation_matrix(tx, ty))


# --------------------------------------------------------------------- ex2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    """The 3x3 matrix rotating by ``angle_deg`` about ``center``.

    Since y points down, a counter-clockwise rotation on screen is the
    lecture's R(-theta) = [[cos, sin], [-sin, cos]].  About a centre c:
    T(c) @ R @ T(-c).
    """
    theta = np.deg2rad(angle_deg)
    c, s = np.cos(theta), np.sin(theta)
    R = np.array([[c, s, 0.0],
                  [-s, c, 0.0],
                  [0.0, 0.0, 1.0]])
    cx, cy = float(center[0]), float(center[1])
    return translation_matrix(cx, cy) @ R @ translation_matrix(-cx, -cy)


def rotate(image, angle_deg=45):
    """Rotate ``image`` by ``angle_deg`` about its centre, keeping its size."""
    h, w = image.shape[:2]
    center = ((w - 1) / 2.0, (h - 1) / 2.0)
    return _warp(image, rotation_matrix(angle_deg, center))


# --------------------------------------------------------------------- ex3
def scaling_matrix(sx, sy):
    """The 3x3 matrix scaling x by ``sx`` and y by ``sy`` about the origin."""
    return np.array([[float(sx), 0.0, 0.0],
                     [0.0, float(sy), 0.0],
                     [0.0, 0.0, 1.0]])


def scale(image, sx=1.5, sy=1.5):
    """Scale ``image`` about its top-left corner, keeping its size."""
    return _warp(image, scaling_matrix(sx, sy))


# --------------------------------------------------------------------- ex4
def shear_matrix(s):
    """The 3x3 horizontal shear ``x' = x + s*y, y' = y``."""
    return np.array([[1.0, float(s), 0.0],
                     [0.0, 1.0, 0.0],
                     [0.0, 0.0, 1.0]])


def shear(image, s=0.5):
    """Shear ``image`` horizontally by ``s`` (rows further down move right)."""
    return _warp(image, shear_matrix(s))


# --------------------------------------------------------------------- ex5
def affine_from_points(src, dst):
    """The affine map taking three points ``src`` onto three points ``dst``.

    Each pair gives two equations; with the unknowns (a, b, tx, c, d, ty) the
    three pairs give a 6x6 linear system that I solve exactly.
    """
    src = np.asarray(src, dtype=np.float64)
    dst = np.asarray(dst, dtype=np.float64)
    M = np.zeros((6, 6))
    rhs = np.zeros(6)
    for i in range(3):
        x, y = src[i]
        M[2 * i] = [x, y, 1, 0, 0, 0]
        M[2 * i + 1] = [0, 0, 0, x, y, 1]
        rhs[2 * i] = dst[i, 0]
        rhs[2 * i + 1] = dst[i, 1]
    params = np.linalg.solve(M, rhs)
    return params.reshape(2, 3)


def warp_affine(image, A, dsize=None):
    """Warp ``image`` by the 2x3 affine ``A`` (source to output coordinates)."""
    A = np.asarray(A, dtype=np.float64)
    M = np.vstack([A, [0.0, 0.0, 1.0]])
    return _warp(image, M, dsize)


# --------------------------------------------------------------------- ex6
def affine_lstsq(src, dst):
    """The least-squares affine map from N >= 3 point pairs.

    The 2N x 6 system of the lab sheet, two rows per pair, solved with
    np.linalg.lstsq.
    """
    src = np.asarray(src, dtype=np.float64)
    dst = np.asarray(dst, dtype=np.float64)
    n = src.shape[0]
    A = np.zeros((2 * n, 6))
    b = np.zeros(2 * n)
    for i in range(n):
        x, y = src[i]
        A[2 * i] = [x, y, 1, 0, 0, 0]
        A[2 * i + 1] = [0, 0, 0, x, y, 1]
        b[2 * i] = dst[i, 0]
        b[2 * i + 1] = dst[i, 1]
    params, *_ = np.linalg.lstsq(A, b, rcond=None)
    return params.reshape(2, 3)
