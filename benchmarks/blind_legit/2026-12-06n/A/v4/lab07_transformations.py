"""Lab 7 - 2D transformations.

Written following Szeliski (ch. 2.1 / 3.6) and the scikit-image and OpenCV
tutorials: every transform is a 3x3 matrix in homogeneous coordinates, images
are warped by *inverse* mapping (for each output pixel, look up where it comes
from) so that no holes appear.

Conventions: points are (x, y), x = column, y = row, origin at the centre of
the top-left pixel, y down. Angles in degrees, positive = counter-clockwise on
screen, i.e. the lecture's R(theta) with theta -> -theta.
"""

import cv2
import numpy as np
from scipy.linalg import solve_triangular
from skimage.transform import AffineTransform, warp


def _warp_skimage(image, M, output_shape=None):
    """Warp with skimage: ``M`` (3x3) maps source pixels to output pixels.

    skimage's ``warp`` wants the inverse map (output -> source); bilinear
    (order=1), black outside, values kept in 0..255.
    """
    image = np.asarray(image)
    if output_shape is None:
        output_shape = image.shape[:2]
    tform = AffineTransform(matrix=np.asarray(M, dtype=np.float64))
    out = warp(image, tform.inverse, output_shape=output_shape, order=1,
               mode="constant", cval=0.0, preserve_range=True)
    return np.clip(np.round(out), 0, 255).astype(np.uint8)


# --------------------------------------------------------------------- ex1
def translation_matrix(tx, ty):
    """``[[1, 0, tx], [0, 1, ty], [0, 0, 1]]``."""
    return np.array([[1.0, 0.0, tx],
                     [0.0, 1.0, ty],
                     [0.0, 0.0, 1.0]], dtype=np.float64)


def translate(image, tx=100, ty=50):
    """Shift right by ``tx`` and down by ``ty``, black fill.

    Built by hand as a ``cv2.remap``: output pixel (x, y) reads the input at
    (x - tx, y - ty).
    """
    image = np.ascontiguousarray(image)
    h, w = image.shape[:2]
    map_x, map_y = np.meshgrid(np.arange(w, dtype=np.float32) - np.float32(tx),
                               np.arange(h, dtype=np.float32) - np.float32(ty))
    return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR,
                     borderMode=cv2.BORDER_CONSTANT, borderValue=0)


# --------------------------------------------------------------------- ex2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    """Rotation about ``center``: ``T(c) @ R @ T(-c)``.

    The lecture's R(theta) with theta = -angle (y points down), so
    ``R = [[cos a, sin a], [-sin a, cos a]]``.
    """
    a = np.radians(angle_deg)
    R = np.array([[np.cos(a), np.sin(a), 0.0],
                  [-np.sin(a), np.cos(a), 0.0],
                  [0.0, 0.0, 1.0]])
    cx, cy = center
    return translation_matrix(cx, cy) @ R @ translation_matrix(-cx, -cy)


def rotate(image, angle_deg=45):
    """Rotate about the centre ``((W-1)/2, (H-1)/2)``, same size (skimage warp)."""
    h, w = np.asarray(image).shape[:2]
    M = rotation_matrix(angle_deg, ((w - 1) / 2.0, (h - 1) / 2.0))
    return _warp_skimage(image, M)


# --------------------------------------------------------------------- ex3
def scaling_matrix(sx, sy):
    """``diag(sx, sy, 1)``."""
    return np.diag([float(sx), float(sy), 1.0])


def scale(image, sx=1.5, sy=1.5):
    """Scale about the top-left corner, keeping the size (skimage warp)."""
    return _warp_skimage(image, scaling_matrix(sx, sy))


# --------------------------------------------------------------------- ex4
def shear_matrix(s):
    """``x' = x + s*y, y' = y``."""
    return np.array([[1.0, s, 0.0],
                     [0.0, 1.0, 0.0],
                     [0.0, 0.0, 1.0]])


def shear(image, s=0.5):
    """Horizontal shear with ``cv2.warpAffine`` (the lab sheet's recipe)."""
    image = np.ascontiguousarray(image)
    h, w = image.shape[:2]
    return cv2.warpAffine(image, shear_matrix(s)[:2], (w, h),
                          flags=cv2.INTER_LINEAR,
                          borderMode=cv2.BORDER_CONSTANT, borderValue=0)


# --------------------------------------------------------------------- ex5
def affine_from_points(src, dst):
    """``cv2.getAffineTransform`` on three point pairs (float32 points)."""
    src = np.float32(src).reshape(3, 2)
    dst = np.float32(dst).reshape(3, 2)
    return cv2.getAffineTransform(src, dst).astype(np.float64)


def warp_affine(image, A, dsize=None):
    """Warp by the 2x3 affine ``A`` (source -> output) with a hand-built remap.

    ``cv2.invertAffineTransform`` gives the output -> source map; every output
    pixel is then looked up bilinearly in the input (black outside).
    """
    image = np.ascontiguousarray(image)
    if dsize is None:
        dsize = (image.shape[1], image.shape[0])
    w, h = int(dsize[0]), int(dsize[1])
    Ainv = cv2.invertAffineTransform(np.asarray(A, dtype=np.float64).reshape(2, 3))
    xs, ys = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
    map_x = (Ainv[0, 0] * xs + Ainv[0, 1] * ys + Ainv[0, 2]).astype(np.float32)
    map_y = (Ainv[1, 0] * xs + Ainv[1, 1] * ys + Ainv[1, 2]).astype(np.float32)
    return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR,
                     borderMode=cv2.BORDER_CONSTANT, borderValue=0)


# --------------------------------------------------------------------- ex6
def affine_lstsq(src, dst):
    """Least-squares affine map from N >= 3 pairs, solved by QR.

    The 2N x 6 system ``M p = b`` of the lab sheet (two rows per pair) is
    solved through ``M = Q R``: ``R p = Q^T b`` by back substitution
    (numerically better than the normal equations ``M^T M p = M^T b``).
    """
    src = np.asarray(src, dtype=np.float64)
    dst = np.asarray(dst, dtype=np.float64)
    n = src.shape[0]
    M = np.zeros((2 * n, 6))
    b = np.zeros(2 * n)
    M[0::2, 0:2] = src
    M[0::2, 2] = 1.0
    M[1::2, 3:5] = src
    M[1::2, 5] = 1.0
    b[0::2] = dst[:, 0]
    b[1::2] = dst[:, 1]
    Q, R = np.linalg.qr(M)                 # reduced QR: Q (2N, 6), R (6, 6)
    p = solve_triangular(R, Q.T @ b)
    return p.reshape(2, 3)
