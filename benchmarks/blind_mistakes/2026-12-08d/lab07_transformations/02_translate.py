"""Lab 7 - 2D transformations (reference solution).

Every transformation is a 3x3 matrix acting on homogeneous pixel coordinates
``(x, y, 1)``; warping an image applies the matrix with ``cv2.warpAffine``,
which samples the source at the inverse-mapped position of every output pixel.
"""

import cv2
import numpy as np


def _warp(image, M, dsize=None):
    """Warp ``image`` by the affine part of ``M``, bilinear, black fill."""
    height, width = image.shape[:2]
    return cv2.warpAffine(image, np.asarray(M, dtype=np.float64)[:2], dsize or (width, height),
                          flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)


# --------------------------------------------------------------------- ex1
def translation_matrix(tx, ty):
    """[[1, 0, tx], [0, 1, ty], [0, 0, 1]]: moves every point by (tx, ty)."""
    return np.array([[1.0, 0.0, tx],
                     [0.0, 1.0, ty],
                     [0.0, 0.0, 1.0]])


def translate(image, tx=100, ty=50):
    """Shift the image right by ``tx`` and down by ``ty`` pixels."""
    rows, cols = image.shape[:2]
    M = np.float32([[1, 0, tx],
                    [0, 1, ty]])
    shifted = cv2.warpAffine(image, M, (cols, rows),
                             borderMode=cv2.BORDER_REPLICATE)
    return shifted


# --------------------------------------------------------------------- ex2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    """Rotation by ``angle_deg`` (counter-clockwise on screen) about ``center``.

    With y pointing down, a counter-clockwise rotation on screen is the
    lecture's R(-theta). Rotating about c is T(c) R T(-c), whose translation
    column works out to (I - R) c.
    """
    theta = np.deg2rad(angle_deg)
    cos, sin = np.cos(theta), np.sin(theta)
    R = np.array([[cos, sin],
                  [-sin, cos]])
    c = np.asarray(center, dtype=np.float64)
    M = np.eye(3)
    M[:2, :2] = R
    M[:2, 2] = c - R @ c
    return M


def rotate(image, angle_deg=45):
    """Rotate the image about its centre; corners that leave the frame are cut off."""
    height, width = image.shape[:2]
    centre = ((width - 1) / 2.0, (height - 1) / 2.0)
    return _warp(image, rotation_matrix(angle_deg, centre))


# --------------------------------------------------------------------- ex3
def scaling_matrix(sx, sy):
    """diag(sx, sy, 1): scales about the origin (the top-left pixel)."""
    return np.diag([float(sx), float(sy), 1.0])


def scale(image, sx=1.5, sy=1.5):
    """Scale about the top-left corner, keeping the image size (the result is cropped)."""
    return _warp(image, scaling_matrix(sx, sy))


# --------------------------------------------------------------------- ex4
def shear_matrix(s):
    """Horizontal shear: x' = x + s*y, y' = y."""
    return np.array([[1.0, s, 0.0],
                     [0.0, 1.0, 0.0],
                     [0.0, 0.0, 1.0]])


def shear(image, s=0.5):
    """Shear the image horizontally, keeping its size."""
    return _warp(image, shear_matrix(s))


# --------------------------------------------------------------------- ex5
def affine_from_points(src, dst):
    """The affine map A (2x3) with dst_i = A [src_i, 1] for three point pairs.

    Each pair gives two equations in the six unknowns (a, b, c, d, e, f):
    ``x' = a x + b y + c`` and ``y' = d x + e y + f``. With the points as rows of
    ``S = [src | 1]`` (3x3), this is ``S @ A.T = dst``.
    """
    src = np.asarray(src, dtype=np.float64)
    dst = np.asarray(dst, dtype=np.float64)
    S = np.hstack([src, np.ones((3, 1))])
    return np.linalg.solve(S, dst).T


def warp_affine(image, A, dsize=None):
    """Warp the image by the 2x3 affine ``A``; ``dsize = (width, height)`` or the input size."""
    return _warp(image, A, dsize)


# --------------------------------------------------------------------- ex6
def affine_lstsq(src, dst):
    """Least-squares affine map from N >= 3 point pairs.

    Stack two rows per pair into the 2N x 6 system of the lab sheet,

        [x_i  y_i  1   0    0    0] [a b c d e f]^T = x'_i
        [0    0    0   x_i  y_i  1]                 = y'_i

    and solve it in the least-squares sense.
    """
    src = np.asarray(src, dtype=np.float64)
    dst = np.asarray(dst, dtype=np.float64)
    n = len(src)
    M = np.zeros((2 * n, 6))
    M[0::2, 0:2] = src
    M[0::2, 2] = 1.0
    M[1::2, 3:5] = src
    M[1::2, 5] = 1.0
    b = dst.reshape(-1)  # x'_0, y'_0, x'_1, y'_1, ...
    params, *_ = np.linalg.lstsq(M, b, rcond=None)
    return params.reshape(2, 3)
