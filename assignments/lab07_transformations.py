"""Lab 7 - 2D transformations.

Fill in every function that raises ``NotImplementedError``, then check your work
with ``python grade.py lab07`` (or one exercise: ``python grade.py lab07.ex2``).

Conventions used throughout
---------------------------
- Images are ``numpy.ndarray`` of dtype ``uint8``, shape ``(H, W)`` (grey) or
  ``(H, W, 3)`` (BGR, as ``cv2.imread`` gives). Every function that takes an
  image returns an image of the same dtype, channel count and size (unless a
  ``dsize`` says otherwise).
- Points are ``(x, y)`` with ``x`` the column and ``y`` the row; the origin is
  the centre of the top-left pixel and **y points down**.
- Matrices act on homogeneous coordinates ``(x, y, 1)`` and are float arrays.
- Angles are in **degrees**. A positive angle rotates **counter-clockwise as the
  image is displayed**, like ``cv2.getRotationMatrix2D``. Because y points down,
  that is the lecture's R(theta) with theta replaced by -theta.
- "Black fill": output pixels that no source pixel lands on are 0.
- Warps use bilinear interpolation (``cv2.INTER_LINEAR``). You may use
  ``cv2.warpAffine`` to apply a matrix to an image, with
  ``borderMode=cv2.BORDER_CONSTANT, borderValue=0``.
- Matplotlib is welcome for looking at your results (``import
  matplotlib.pyplot as plt``, ``plt.imshow``, ``plt.show()``): the grader runs
  it without a window and closes your figures after each call.
"""

import cv2  # noqa: F401  (you will need it)
import numpy as np  # noqa: F401


# --------------------------------------------------------------------- ex1
def translation_matrix(tx, ty):
    """The 3x3 translation matrix moving every point by ``(tx, ty)``.

    Parameters
    ----------
    tx, ty : float
        Shift to the right (x) and down (y), in pixels.

    Returns
    -------
    (3, 3) float array
        ``[[1, 0, tx], [0, 1, ty], [0, 0, 1]]``.

    Examples
    --------
    >>> translation_matrix(100, 50) @ [0, 0, 1]
    array([100.,  50.,   1.])
    """
    raise NotImplementedError("ex1: translation_matrix")


def translate(image, tx=100, ty=50):
    """Shift ``image`` right by ``tx`` and down by ``ty`` pixels, black fill.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) uint8 array
    tx, ty : float
        May be negative (left / up) or fractional.

    Returns
    -------
    (H, W) or (H, W, 3) uint8 array
        Same size as ``image``: content shifted out of the frame is lost, and
        the uncovered strip on the left/top is black (0).
    """
    raise NotImplementedError("ex1: translate")


# --------------------------------------------------------------------- ex2
def rotation_matrix(angle_deg, center=(0.0, 0.0)):
    """The 3x3 matrix rotating by ``angle_deg`` about ``center``.

    The top two rows must equal ``cv2.getRotationMatrix2D(center, angle_deg, 1)``
    (you may check against it, but build the matrix yourself from cos and sin).

    Parameters
    ----------
    angle_deg : float
        Degrees, counter-clockwise as displayed (y points down, so this is the
        lecture's R(-theta)).
    center : (x, y)
        The fixed point of the rotation. Rotating about ``c`` is
        ``T(c) @ R @ T(-c)``: move ``c`` to the origin, rotate, move back.

    Returns
    -------
    (3, 3) float array with last row ``[0, 0, 1]``.
    """
    raise NotImplementedError("ex2: rotation_matrix")


def rotate(image, angle_deg=45):
    """Rotate ``image`` by ``angle_deg`` about its centre, keeping its size.

    The centre of a W x H image is ``((W - 1) / 2, (H - 1) / 2)`` with pixel
    centres at integer coordinates. Corners rotated out of the frame are cut off;
    uncovered pixels are black.

    Returns
    -------
    uint8 array, same shape as ``image``.
    """
    raise NotImplementedError("ex2: rotate")


# --------------------------------------------------------------------- ex3
def scaling_matrix(sx, sy):
    """The 3x3 matrix scaling x by ``sx`` and y by ``sy`` about the origin.

    Returns
    -------
    (3, 3) float array ``diag(sx, sy, 1)``.
    """
    raise NotImplementedError("ex3: scaling_matrix")


def scale(image, sx=1.5, sy=1.5):
    """Scale ``image`` about its top-left corner, keeping its size.

    With ``sx, sy > 1`` the result is an enlarged, cropped view of the top-left
    part; with values below 1 the image shrinks towards the top-left corner and
    the rest is black. (This is a warp with ``scaling_matrix``, not ``cv2.resize``.)

    Returns
    -------
    uint8 array, same shape as ``image``.
    """
    raise NotImplementedError("ex3: scale")


# --------------------------------------------------------------------- ex4
def shear_matrix(s):
    """The 3x3 horizontal shear ``x' = x + s*y, y' = y``.

    Returns
    -------
    (3, 3) float array.
    """
    raise NotImplementedError("ex4: shear_matrix")


def shear(image, s=0.5):
    """Shear ``image`` horizontally by ``s`` (rows further down move further right).

    Returns
    -------
    uint8 array, same shape as ``image``; uncovered pixels black.
    """
    raise NotImplementedError("ex4: shear")


# --------------------------------------------------------------------- ex5
def affine_from_points(src, dst):
    """The affine map taking three points ``src`` onto three points ``dst``.

    Parameters
    ----------
    src, dst : (3, 2) float arrays
        Corresponding points, not collinear.

    Returns
    -------
    A : (2, 3) float array
        ``dst[i] = A @ [src[i, 0], src[i, 1], 1]`` for i = 0, 1, 2.
        The lab sheet's recipe is ``cv2.getAffineTransform`` (it wants float32
        points: ``np.float32(src)``); solving the 6x6 (or two 3x3) linear
        systems yourself (``np.linalg.solve``) is just as good.
    """
    raise NotImplementedError("ex5: affine_from_points")


def warp_affine(image, A, dsize=None):
    """Warp ``image`` by the 2x3 affine ``A`` (source to output coordinates).

    Parameters
    ----------
    image : uint8 array
    A : (2, 3) float array
    dsize : (width, height), optional
        Output size - note the order: width first, as in OpenCV. Defaults to
        the input's size.

    Returns
    -------
    uint8 array of shape (height, width[, 3]), black fill.
    """
    raise NotImplementedError("ex5: warp_affine")


# --------------------------------------------------------------------- ex6
def affine_lstsq(src, dst):
    """The least-squares affine map from N >= 3 point pairs.

    Build the 2N x 6 system of the lab sheet, two rows per pair, with the
    unknowns ordered ``(a, b, c, d, e, f)`` so that ``A = [[a, b, c], [d, e, f]]``::

        [x_i  y_i  1   0    0    0] . (a, b, c, d, e, f) = x'_i
        [0    0    0   x_i  y_i  1] . (a, b, c, d, e, f) = y'_i

    and solve it in the least-squares sense (``np.linalg.lstsq``). Use every
    point, not just three. ``cv2.estimateAffine2D`` and
    ``cv2.estimateAffinePartial2D`` are not allowed here.

    Parameters
    ----------
    src, dst : (N, 2) float arrays, N >= 3

    Returns
    -------
    A : (2, 3) float array minimising ``sum_i |A [src_i, 1] - dst_i|^2``.
    """
    raise NotImplementedError("ex6: affine_lstsq")
