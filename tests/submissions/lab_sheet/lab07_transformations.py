"""Lab 7 written the way the lab sheet says, line by line (a test submission).

OpenCV's own functions wherever the sheet names them (cv2.warpAffine with 2x3
matrices, cv2.getRotationMatrix2D, cv2.getAffineTransform with float32 points),
np.linalg.lstsq for the 2n x 6 system, and Matplotlib to look at the results.
It must score full marks.
"""

import cv2
import matplotlib.pyplot as plt
import numpy as np


def show(title, image):
    """What a student does to look at a result: a Matplotlib window."""
    plt.figure()
    plt.title(title)
    plt.imshow(cv2.cvtColor(image, cv2.COLOR_BGR2RGB) if image.ndim == 3 else image, cmap="gray")
    plt.axis("off")
    plt.show()


def _warp(image, M, dsize=None):
    h, w = image.shape[:2]
    return cv2.warpAffine(image, np.float32(M[:2]), dsize or (w, h))


# Exercise 1
def translation_matrix(tx, ty):
    return np.array([[1, 0, tx], [0, 1, ty], [0, 0, 1]], dtype=np.float64)


def translate(image, tx=100, ty=50):
    result = _warp(image, translation_matrix(tx, ty))
    show("translated", result)
    return result


# Exercise 2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    M = cv2.getRotationMatrix2D((float(center[0]), float(center[1])), angle_deg, 1.0)
    return np.vstack([M, [0, 0, 1]])


def rotate(image, angle_deg=45):
    h, w = image.shape[:2]
    M = cv2.getRotationMatrix2D(((w - 1) / 2, (h - 1) / 2), angle_deg, 1.0)
    rotated = cv2.warpAffine(image, M, (w, h))
    plt.subplot(1, 2, 1)
    plt.imshow(image)
    plt.subplot(1, 2, 2)
    plt.imshow(rotated)
    plt.show()
    return rotated


# Exercise 3
def scaling_matrix(sx, sy):
    return np.array([[sx, 0, 0], [0, sy, 0], [0, 0, 1]], dtype=np.float64)


def scale(image, sx=1.5, sy=1.5):
    return _warp(image, scaling_matrix(sx, sy))


# Exercise 4
def shear_matrix(s):
    return np.array([[1, s, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)


def shear(image, s=0.5):
    return _warp(image, shear_matrix(s))


# Exercise 5: "Use cv2.getAffineTransform with 3 point pairs, then apply with cv2.warpAffine."
def affine_from_points(src, dst):
    return cv2.getAffineTransform(np.float32(src), np.float32(dst))


def warp_affine(image, A, dsize=None):
    h, w = image.shape[:2]
    return cv2.warpAffine(image, np.float32(A), dsize if dsize is not None else (w, h))


# Exercise 6: "Construct Ax = b, where A is 2n x 6 ... solve using np.linalg.lstsq."
def affine_lstsq(src, dst):
    A, b = [], []
    for (x, y), (u, v) in zip(src, dst):
        A.append([x, y, 1, 0, 0, 0])
        A.append([0, 0, 0, x, y, 1])
        b += [u, v]
    params = np.linalg.lstsq(np.array(A, dtype=np.float32), np.array(b, dtype=np.float32), rcond=None)[0]
    return params.reshape(2, 3)
