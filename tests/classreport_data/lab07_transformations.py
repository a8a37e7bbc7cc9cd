"""Lab 7, written independently of the reference solution (for the similarity tests).

Same answers, a different hand: homogeneous matrices composed from pieces,
the warps through one helper that picks the output size, the least-squares
fit through the normal equations of each output coordinate.
"""

import math

import cv2
import numpy as np


def _homogeneous(linear, offset=(0.0, 0.0)):
    out = np.identity(3)
    out[0:2, 0:2] = linear
    out[0:2, 2] = offset
    return out


def _apply(img, matrix, size=None):
    rows, cols = img.shape[0], img.shape[1]
    if size is None:
        size = (cols, rows)
    affine = np.float64(matrix)[0:2, :]
    return cv2.warpAffine(img, affine, tuple(int(v) for v in size), flags=cv2.INTER_LINEAR,
                          borderMode=cv2.BORDER_CONSTANT, borderValue=0)


def translation_matrix(tx, ty):
    return _homogeneous(np.identity(2), (tx, ty))


def translate(image, tx=100, ty=50):
    return _apply(image, translation_matrix(tx, ty))


def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    # y grows downwards, so a visually counter-clockwise turn uses -angle
    a = math.radians(angle_deg)
    linear = np.array([[math.cos(a), math.sin(a)], [-math.sin(a), math.cos(a)]])
    cx, cy = float(center[0]), float(center[1])
    to_origin = _homogeneous(np.identity(2), (-cx, -cy))
    back = _homogeneous(np.identity(2), (cx, cy))
    return back @ _homogeneous(linear) @ to_origin


def rotate(image, angle_deg=45):
    rows, cols = image.shape[:2]
    return _apply(image, rotation_matrix(angle_deg, center=(0.5 * (cols - 1), 0.5 * (rows - 1))))


def scaling_matrix(sx, sy):
    return _homogeneous([[sx, 0.0], [0.0, sy]])


def scale(image, sx=1.5, sy=1.5):
    return _apply(image, scaling_matrix(sx, sy))


def shear_matrix(s):
    return _homogeneous([[1.0, s], [0.0, 1.0]])


def shear(image, s=0.5):
    return _apply(image, shear_matrix(s))


def affine_from_points(src, dst):
    rows = []
    rhs = []
    for (x, y), (u, v) in zip(np.asarray(src, float), np.asarray(dst, float)):
        rows.append([x, y, 1, 0, 0, 0])
        rows.append([0, 0, 0, x, y, 1])
        rhs += [u, v]
    solution = np.linalg.solve(np.array(rows, float), np.array(rhs, float))
    return solution.reshape(2, 3)


def warp_affine(image, A, dsize=None):
    return _apply(image, np.vstack([np.asarray(A, float), [0.0, 0.0, 1.0]]), dsize)


def affine_lstsq(src, dst):
    pts = np.asarray(src, float)
    design = np.column_stack([pts, np.ones(len(pts))])
    targets = np.asarray(dst, float)
    # the x' and y' rows of A are two independent least-squares problems
    gram = design.T @ design
    first = np.linalg.solve(gram, design.T @ targets[:, 0])
    second = np.linalg.solve(gram, design.T @ targets[:, 1])
    return np.stack([first, second])
