"""Lab 7 - 2D transformations (OpenCV version).

All image warps go through ``cv2.warpAffine`` with bilinear interpolation and a
constant black border, as the lab sheet suggests. The matrices are built as
2x3 affine matrices (OpenCV's format) and returned with the homogeneous row
[0, 0, 1] appended.

Conventions: (x, y) = (column, row), origin at the centre of the top-left
pixel, y pointing down; angles in degrees, positive = counter-clockwise on
screen (like cv2.getRotationMatrix2D).
"""

import cv2
import numpy as np


def _to3x3(A):
    """Append the row [0, 0, 1] to a 2x3 affine matrix."""
    return np.vstack([np.asarray(A, dtype=np.float64), [0.0, 0.0, 1.0]])


def _warp(image, A, dsize=None):
    """cv2.warpAffine with a 2x3 matrix, bilinear, black outside."""
    if dsize is None:
        dsize = (image.shape[1], image.shape[0])
    dsize = (int(dsize[0]), int(dsize[1]))
    return cv2.warpAffine(image, np.asarray(A, dtype=np.float64)[:2], dsize,
                          flags=cv2.INTER_LINEAR,
                          borderMode=cv2.BORDER_CONSTANT, borderValue=0)


# --------------------------------------------------------------------- ex1
def translation_matrix(tx, ty):
    """The 3x3 translation matrix moving every point by ``(tx, ty)``."""
    M = np.eye(3)
    M[:2, 2] = (tx, ty)
    return M


def translate(image, tx=100, ty=50):
    """Shift ``image`` right by ``tx`` and down by ``ty`` pixels, black fill."""
    A = np.float64([[1, 0, tx],
                    [0, 1, ty]])
    return _warp(image, A)


# --------------------------------------------------------------------- ex2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    """The 3x3 matrix rotating by ``angle_deg`` about ``center``.

    Written out in closed form (alpha = cos, beta = sin):

        [ alpha  beta  (1 - alpha) cx - beta cy ]
        [-beta   alpha  beta cx + (1 - alpha) cy ]

    which is T(c) R(-theta) T(-c) multiplied out.
    """
    theta = np.radians(float(angle_deg))
    alpha = np.cos(theta)
    beta = np.sin(theta)
    cx, cy = float(center[0]), float(center[1])
    A = np.array([[alpha, beta, (1.0 - alpha) * cx - beta * cy],
                  [-beta, alpha, beta * cx + (1.0 - alpha) * cy]])
    return _to3x3(A)


def rotate(image, angle_deg=45):
    """Rotate ``image`` by ``angle_deg`` about its centre, keeping its size."""
    h, w = image.shape[:2]
    center = ((w - 1) / 2.0, (h - 1) / 2.0)
    A = cv2.getRotationMatrix2D(center, float(angle_deg), 1.0)
    return _warp(image, A)


# --------------------------------------------------------------------- ex3
def scaling_matrix(sx, sy):
    """The 3x3 matrix scaling x by ``sx`` and y by ``sy`` about the origin."""
    return np.diag([float(sx), float(sy), 1.0])


def scale(image, sx=1.5, sy=1.5):
    """Scale ``image`` about its top-left corner, keeping its size."""
    return _warp(image, scaling_matrix(sx, sy)[:2])


# --------------------------------------------------------------------- ex4
def shear_matrix(s):
    """The 3x3 horizontal shear ``x' = x + s*y, y' = y``."""
    M = np.eye(3)
    M[0, 1] = s
    return M


def shear(image, s=0.5):
    """Shear ``image`` horizontally by ``s`` (rows further down move right)."""
    return _warp(image, shear_matrix(s)[:2])


# --------------------------------------------------------------------- ex5
def affine_from_points(src, dst):
    """The affine map taking three points ``src`` onto three points ``dst``.

    cv2.getAffineTransform wants float32 points; it returns a float64 2x3.
    """
    A = cv2.getAffineTransform(np.float32(src).reshape(3, 2),
                               np.float32(dst).reshape(3, 2))
    return A.astype(np.float64)


def warp_affine(image, A, dsize=None):
    """Warp ``image`` by the 2x3 affine ``A`` (source to output coordinates)."""
    return _warp(image, A, dsize)


# --------------------------------------------------------------------- ex6
def affine_lstsq(src, dst):
    """The least-squares affine map from N >= 3 point pairs.

    The lab sheet's 2N x 6 system with x = [a, b, tx, c, d, ty]; here the
    rows are stacked in two blocks (first the N x'-equations, then the N
    y'-equations) and the system is solved through a QR decomposition
    (A = QR, then R x = Q^T b), which gives the same least-squares solution
    as the normal equations without squaring the condition number.
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    n = len(src)
    X = np.column_stack([src, np.ones(n)])   # N x 3: [x, y, 1]
    zeros = np.zeros((n, 3))
    A = np.block([[X, zeros],
                  [zeros, X]])                # 2N x 6
    b = np.concatenate([dst[:, 0], dst[:, 1]])
    Q, R = np.linalg.qr(A)                    # reduced QR: Q is 2N x 6
    params = np.linalg.solve(R, Q.T @ b)
    return params.reshape(2, 3)
