"""Lab 7 - 2D transformations.

Careful version. Every transformation is first written as a 3x3 matrix on
homogeneous coordinates (x, y, 1); images are then warped by *inverse mapping*:
for every output pixel we ask where it came from in the source
(``inv(M) @ (x_out, y_out, 1)``) and sample the source there bilinearly with
``cv2.remap``. Output pixels whose source lies outside the image are black (0).

Conventions
-----------
- Images: uint8 (H, W) grey or (H, W, 3) BGR. The result has the same dtype,
  channel count and (unless ``dsize`` is given) size. The input is never
  modified.
- Points: (x, y) with x = column, y = row, origin at the centre of the top-left
  pixel, y pointing down.
- Angles in degrees, positive = counter-clockwise as the image is displayed
  (the convention of ``cv2.getRotationMatrix2D``). Because y points down this
  is the lecture's R(theta) with theta replaced by -theta.
"""

import cv2
import numpy as np


# ----------------------------------------------------------------- helpers
def _as_image(image):
    """Return ``image`` as a C-contiguous ndarray (a copy is made only if needed).

    cv2 functions want contiguous memory; slices such as ``img[:, ::2]`` are not.
    """
    img = np.asarray(image)
    if img.ndim not in (2, 3):
        raise ValueError(f"expected an (H, W) or (H, W, C) image, got shape {img.shape}")
    if img.size == 0:
        raise ValueError("empty image")
    return np.ascontiguousarray(img)


def _as_points(pts, name):
    """(N, 2) float64 copy of a point list; a single (2,) point becomes (1, 2)."""
    p = np.array(pts, dtype=np.float64, copy=True)
    if p.ndim == 1 and p.size == 2:
        p = p.reshape(1, 2)
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"{name} must be an (N, 2) array of (x, y) points, got shape {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError(f"{name} contains NaN or inf")
    return p


def _as_3x3(M):
    """Accept a 2x3 affine or a 3x3 matrix and return the 3x3 float64 version."""
    M = np.array(M, dtype=np.float64, copy=True)
    if M.shape == (2, 3):
        M = np.vstack([M, [0.0, 0.0, 1.0]])
    if M.shape != (3, 3):
        raise ValueError(f"expected a 2x3 or 3x3 matrix, got shape {M.shape}")
    return M


def _warp(image, M, dsize=None):
    """Warp ``image`` by the 3x3 (affine) matrix ``M`` mapping source -> output.

    Inverse mapping: output pixel (u, v) samples the source at inv(M) @ (u, v, 1).
    Bilinear interpolation, black outside the source.
    """
    img = _as_image(image)
    M = _as_3x3(M)
    h_in, w_in = img.shape[:2]
    if dsize is None:
        w_out, h_out = w_in, h_in
    else:
        w_out, h_out = (int(round(float(v))) for v in dsize)
        if w_out <= 0 or h_out <= 0:
            raise ValueError(f"dsize must be positive (width, height), got {dsize}")
    try:
        Minv = np.linalg.inv(M)
    except np.linalg.LinAlgError:
        # A singular map squashes the image onto a line: nothing sensible to show.
        return np.zeros((h_out, w_out) + img.shape[2:], dtype=img.dtype)

    # Source coordinates of every output pixel (affine, so no division needed,
    # but divide anyway in case a caller passes a general 3x3).
    u, v = np.meshgrid(np.arange(w_out, dtype=np.float64), np.arange(h_out, dtype=np.float64))
    w = Minv[2, 0] * u + Minv[2, 1] * v + Minv[2, 2]
    map_x = ((Minv[0, 0] * u + Minv[0, 1] * v + Minv[0, 2]) / w).astype(np.float32)
    map_y = ((Minv[1, 0] * u + Minv[1, 1] * v + Minv[1, 2]) / w).astype(np.float32)

    squeeze = img.ndim == 3 and img.shape[2] == 1   # remap drops a single channel axis
    out = cv2.remap(img, map_x, map_y, interpolation=cv2.INTER_LINEAR,
                    borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    if squeeze:
        out = out[..., None]
    return out


# --------------------------------------------------------------------- ex1
def translation_matrix(tx, ty):
    """The 3x3 translation matrix moving every point by ``(tx, ty)``.

    >>> translation_matrix(100, 50) @ [0, 0, 1]
    array([100.,  50.,   1.])
    """
    T = np.eye(3)
    T[0, 2] = float(tx)
    T[1, 2] = float(ty)
    return T


def translate(image, tx=100, ty=50):
    """Shift ``image`` right by ``tx`` and down by ``ty`` pixels (black fill, same size)."""
    return _warp(image, translation_matrix(tx, ty))


# --------------------------------------------------------------------- ex2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    """The 3x3 matrix rotating by ``angle_deg`` (CCW as displayed) about ``center``.

    Built as T(c) @ R @ T(-c). With y pointing down, a counter-clockwise turn
    on screen is the lecture's R(-theta) = [[cos, sin], [-sin, cos]], which
    makes the top two rows equal to ``cv2.getRotationMatrix2D(center, angle_deg, 1)``.
    """
    theta = np.deg2rad(float(angle_deg))
    c, s = np.cos(theta), np.sin(theta)
    cx, cy = (float(v) for v in np.asarray(center, dtype=np.float64).ravel()[:2])
    R = np.array([[c, s, 0.0],
                  [-s, c, 0.0],
                  [0.0, 0.0, 1.0]])
    return translation_matrix(cx, cy) @ R @ translation_matrix(-cx, -cy)


def _image_centre(img):
    """Centre of a W x H image with pixel centres at integer coordinates."""
    h, w = img.shape[:2]
    return ((w - 1) / 2.0, (h - 1) / 2.0)


def rotate(image, angle_deg=45):
    """Rotate ``image`` by ``angle_deg`` about its centre, keeping its size."""
    img = _as_image(image)
    return _warp(img, rotation_matrix(angle_deg, _image_centre(img)))


# --------------------------------------------------------------------- ex3
def scaling_matrix(sx, sy):
    """The 3x3 matrix ``diag(sx, sy, 1)`` (scaling about the origin)."""
    return np.diag([float(sx), float(sy), 1.0])


def scale(image, sx=1.5, sy=1.5):
    """Scale ``image`` about its top-left corner, keeping its size (a warp, not a resize)."""
    if float(sx) == 0.0 or float(sy) == 0.0:
        # Everything collapses onto an axis: only black is left.
        img = _as_image(image)
        return np.zeros_like(img)
    return _warp(image, scaling_matrix(sx, sy))


# --------------------------------------------------------------------- ex4
def shear_matrix(s):
    """The 3x3 horizontal shear ``x' = x + s*y, y' = y``."""
    S = np.eye(3)
    S[0, 1] = float(s)
    return S


def shear(image, s=0.5):
    """Shear horizontally by ``s``: rows further down move further right."""
    return _warp(image, shear_matrix(s))


# --------------------------------------------------------------------- ex5
def affine_from_points(src, dst):
    """The affine map taking three points ``src`` exactly onto ``dst``.

    Two 3x3 systems share the matrix [[x_i, y_i, 1]]: its solution with the
    right-hand side x'_i is the first row (a, b, c) of A, with y'_i the second.
    Solved in float64 with ``np.linalg.solve`` (more precise than the float32
    that ``cv2.getAffineTransform`` needs).
    """
    src = _as_points(src, "src")
    dst = _as_points(dst, "dst")
    if src.shape != (3, 2) or dst.shape != (3, 2):
        raise ValueError("affine_from_points needs exactly three (x, y) pairs")
    X = np.column_stack([src, np.ones(3)])
    # Collinear points give a singular (or nearly singular) system.
    spread = np.abs(src - src.mean(axis=0)).max()
    if abs(np.linalg.det(X)) <= 1e-12 * max(1.0, spread) ** 2:
        raise ValueError("the three source points are collinear: no unique affine map")
    rows = np.linalg.solve(X, dst)          # (3, 2): column j holds row j of A
    return rows.T.copy()


def warp_affine(image, A, dsize=None):
    """Warp ``image`` by the 2x3 affine ``A`` (source -> output), black fill.

    ``dsize`` is (width, height) as in OpenCV; default: the input's size.
    """
    A = np.asarray(A, dtype=np.float64)
    if A.shape != (2, 3):
        raise ValueError(f"A must be 2x3, got shape {A.shape}")
    return _warp(image, A, dsize)


# --------------------------------------------------------------------- ex6
def affine_lstsq(src, dst):
    """Least-squares affine map from N >= 3 pairs (the lab sheet's 2N x 6 system).

    Unknowns (a, b, c, d, e, f) with A = [[a, b, c], [d, e, f]]; each pair adds
        [x  y  1  0  0  0] . p = x'
        [0  0  0  x  y  1] . p = y'
    Solved with ``np.linalg.lstsq`` using every point.
    """
    src = _as_points(src, "src")
    dst = _as_points(dst, "dst")
    if len(src) != len(dst):
        raise ValueError("src and dst must hold the same number of points")
    n = len(src)
    if n < 3:
        raise ValueError("at least three point pairs are needed")

    M = np.zeros((2 * n, 6))
    b = np.zeros(2 * n)
    for i, ((x, y), (xp, yp)) in enumerate(zip(src, dst)):
        M[2 * i] = [x, y, 1.0, 0.0, 0.0, 0.0]
        M[2 * i + 1] = [0.0, 0.0, 0.0, x, y, 1.0]
        b[2 * i] = xp
        b[2 * i + 1] = yp

    p, _, rank, _ = np.linalg.lstsq(M, b, rcond=None)
    if rank < 6:
        # All points on one line: the least-squares problem has many solutions;
        # lstsq returns the minimum-norm one, which still fits as well as any.
        pass
    return p.reshape(2, 3)
