"""Lab 7 - 2D transformations.

Compact solutions: every matrix is built with NumPy and every image warp goes
through ``cv2.warpAffine`` (bilinear, black border).

Conventions: images are uint8 (H, W) or (H, W, 3); points are (x, y) with x the
column, y the row, y pointing down; angles in degrees, positive =
counter-clockwise as displayed (like ``cv2.getRotationMatrix2D``, i.e. the
lecture's R(-theta)).
"""

import cv2
import numpy as np


def _warp(image, M, dsize=None):
    """Apply the top 2x3 part of ``M`` to ``image`` (bilinear, black fill)."""
    image = np.asarray(image)
    if dsize is None:
        dsize = (image.shape[1], image.shape[0])
    return cv2.warpAffine(image, np.asarray(M, np.float64)[:2], tuple(int(v) for v in dsize),
                          flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)


# --------------------------------------------------------------------- ex1
def translation_matrix(tx, ty):
    """3x3 translation by (tx, ty)."""
    return np.array([[1.0, 0.0, tx], [0.0, 1.0, ty], [0.0, 0.0, 1.0]])


def translate(image, tx=100, ty=50):
    """Shift right by tx, down by ty; same size, black fill."""
    return _warp(image, translation_matrix(tx, ty))


# --------------------------------------------------------------------- ex2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    """3x3 rotation about ``center``, same top rows as cv2.getRotationMatrix2D(center, angle, 1).

    That is T(c) @ R(-theta) @ T(-c) with the lecture's R (y points down).
    """
    t = np.deg2rad(angle_deg)
    c, s = np.cos(t), np.sin(t)
    cx, cy = map(float, center)
    R = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return translation_matrix(cx, cy) @ R @ translation_matrix(-cx, -cy)


def rotate(image, angle_deg=45):
    """Rotate about the image centre ((W-1)/2, (H-1)/2), same size."""
    h, w = np.shape(image)[:2]
    return _warp(image, rotation_matrix(angle_deg, ((w - 1) / 2.0, (h - 1) / 2.0)))


# --------------------------------------------------------------------- ex3
def scaling_matrix(sx, sy):
    """diag(sx, sy, 1)."""
    return np.diag([float(sx), float(sy), 1.0])


def scale(image, sx=1.5, sy=1.5):
    """Scale about the top-left pixel centre (origin), same size (cropped)."""
    return _warp(image, scaling_matrix(sx, sy))


# --------------------------------------------------------------------- ex4
def shear_matrix(s):
    """x' = x + s*y, y' = y."""
    return np.array([[1.0, s, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def shear(image, s=0.5):
    """Horizontal shear about the origin, same size, black fill."""
    return _warp(image, shear_matrix(s))


# --------------------------------------------------------------------- ex5
def affine_from_points(src, dst):
    """2x3 affine with dst_i = A @ [src_i, 1] (exact for 3 non-collinear pairs)."""
    return cv2.getAffineTransform(np.float32(src)[:3], np.float32(dst)[:3]).astype(np.float64)


def warp_affine(image, A, dsize=None):
    """Warp by the 2x3 affine A (source -> output), dsize=(width, height)."""
    return _warp(image, A, dsize)


# --------------------------------------------------------------------- ex6
def affine_lstsq(src, dst):
    """Least-squares affine from N >= 3 pairs via np.linalg.lstsq.

    The lab sheet's 2N x 6 system is block diagonal: the (a, b, c) rows and the
    (d, e, f) rows share the same design matrix [x y 1], so one lstsq call with
    the two right-hand sides x' and y' solves it exactly.
    """
    src = np.asarray(src, np.float64).reshape(-1, 2)
    dst = np.asarray(dst, np.float64).reshape(-1, 2)
    X = np.c_[src, np.ones(len(src))]
    return np.linalg.lstsq(X, dst, rcond=None)[0].T
