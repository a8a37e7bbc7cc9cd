"""Lab 9 - geometric camera models.

Fill in every function that raises ``NotImplementedError``, then check your work
with ``python grade.py lab09`` (or one exercise: ``python grade.py lab09.ex2``).

Conventions used throughout
---------------------------
- 3D points are float arrays of shape ``(N, 3)``. Every function documented for
  ``(N, 3)`` points also accepts a single ``(3,)`` point and then returns a
  single ``(2,)`` result (``np.atleast_2d`` on the way in, ``[0]`` on the way out).
- 2D points are ``(N, 2)`` float arrays of ``(x, y)``: ``x`` is the column,
  ``y`` the row; y points down.
- Camera coordinates: the camera looks along ``+Z``, ``X`` points right and
  ``Y`` down in the image. A world point ``X`` has camera coordinates
  ``R @ X + t``.
- **Points behind the camera** (camera-frame ``Z <= 0``, i.e. third homogeneous
  coordinate ``<= 0``) have no image. Recommended: return ``[nan, nan]`` for
  them (without it a point behind the pinhole appears mirrored). The lab sheet
  does not ask for it, so it earns no points: the grader gives it as advice.
  Whatever you return there, return one row per input point.
- Matplotlib is welcome for the visualisations the lab sheet asks for; the
  grader runs it without a window and closes your figures after each call.
- Images are ``uint8`` arrays ``(H, W, 3)`` in BGR order, as ``cv2.imread``
  gives them.
"""

import cv2  # noqa: F401  (you will need it)
import numpy as np  # noqa: F401


# --------------------------------------------------------------------- ex1
def pinhole_project(points, f):
    """Project camera-frame points with a pinhole camera of focal length ``f``.

    Parameters
    ----------
    points : (N, 3) or (3,) float array
        Points ``(X, Y, Z)`` in the camera's frame.
    f : float
        Focal length (in pixels).

    Returns
    -------
    (N, 2) or (2,) float array
        ``x = f X / Z``, ``y = f Y / Z`` (the image origin is on the optical
        axis; no principal point yet). NaN for points with ``Z <= 0`` (recommended).

    Examples
    --------
    >>> pinhole_project(np.array([[1.0, 2.0, 10.0]]), 500)
    array([[ 50., 100.]])
    >>> pinhole_project(np.array([1.0, 2.0, 10.0]), 500)
    array([ 50., 100.])
    """
    raise NotImplementedError("ex1: pinhole_project")


# --------------------------------------------------------------------- ex2
def intrinsic_matrix(f, px, py):
    """The intrinsic matrix with focal length ``f`` and principal point ``(px, py)``.

    Returns
    -------
    K : (3, 3) float array
        ``[[f, 0, px], [0, f, py], [0, 0, 1]]``.
    """
    raise NotImplementedError("ex2: intrinsic_matrix")


def project_with_intrinsics(K, points):
    """Project camera-frame points to pixels with the intrinsic matrix ``K``.

    Parameters
    ----------
    K : (3, 3) float array
        Any intrinsic matrix (``fx`` may differ from ``fy``; ``K[0, 1]`` may be a skew).
    points : (N, 3) or (3,) float array
        Camera-frame points.

    Returns
    -------
    (N, 2) or (2,) float array
        ``(u, v, w) = K @ (X, Y, Z)``, then ``(u / w, v / w)``. NaN where ``w <= 0``
        (recommended).

    Examples
    --------
    >>> K = intrinsic_matrix(500, 320, 240)
    >>> project_with_intrinsics(K, np.array([1.0, 2.0, 10.0]))
    array([370., 340.])
    """
    raise NotImplementedError("ex2: project_with_intrinsics")


# --------------------------------------------------------------------- ex3
def camera_matrix(K, R, t):
    """The 3x4 camera matrix ``P = K [R | t]``.

    Parameters
    ----------
    K : (3, 3) float array
    R : (3, 3) float array
        World-to-camera rotation.
    t : (3,) float array
        Translation: ``X_cam = R @ X_world + t`` (this is *not* the camera
        centre; the centre is ``-R.T @ t``).

    Returns
    -------
    P : (3, 4) float array
    """
    raise NotImplementedError("ex3: camera_matrix")


def project(P, points):
    """Project world points with the camera matrix ``P``.

    Parameters
    ----------
    P : (3, 4) float array
        Any scale of ``K [R | t]`` (``2 * P`` is the same camera).
    points : (N, 3) or (3,) float array
        World points.

    Returns
    -------
    (N, 2) or (2,) float array
        ``(u, v, w) = P @ (X, Y, Z, 1)``, then ``(u / w, v / w)``. NaN
        (recommended) where ``w`` has not the sign of the camera's depth, i.e. for points behind
        the camera: for ``P = s K [R | t]`` with ``s > 0`` that is ``w <= 0``.
        (The checks only use ``s > 0`` for points behind the camera.)
    """
    raise NotImplementedError("ex3: project")


# --------------------------------------------------------------------- ex4
def project_focal_lengths(points, focal_lengths):
    """The pinhole projection of the same points for several focal lengths.

    Parameters
    ----------
    points : (N, 3) float array
        Camera-frame points.
    focal_lengths : (F,) float array
        E.g. ``[100, 500, 1000]``.

    Returns
    -------
    (F, N, 2) float array
        ``result[i]`` is ``pinhole_project(points, focal_lengths[i])``.
    """
    raise NotImplementedError("ex4: project_focal_lengths")


def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
    """Simulate a pinhole of finite size: where do rays through it land?

    The pinhole is a disc of radius ``aperture`` in the plane ``Z = 0`` (centred
    on the optical axis); the image plane is at distance ``f`` behind it
    (``Z = -f``). For each point ``X`` pick ``n_rays`` points ``A = (ax, ay, 0)``
    uniformly over the disc's *area* (radius ``aperture * sqrt(u)``, angle
    ``2 pi v`` with ``u, v`` uniform in [0, 1)), follow the ray from ``X``
    through ``A`` to the image plane, and report where it lands, turned upright
    like ``pinhole_project`` (the real image is upside down). Working it out:
    ``x = f X / Z - ax (1 + f / Z)`` and ``y = f Y / Z - ay (1 + f / Z)``.

    So with ``aperture = 0`` every ray lands on the ideal projection, the rays
    are centred on it, and they fill a blur disc of radius
    ``aperture * (1 + f / Z)``: bigger for a bigger pinhole and for nearer points.

    Parameters
    ----------
    points : (N, 3) float array
        Camera-frame points (``Z > 0``).
    f : float
    aperture : float
        Radius of the pinhole (same units as ``X``, ``Y``, ``Z``; 0 = ideal).
    n_rays : int
    seed : int or None
        Use ``rng = np.random.default_rng(seed)`` for every random number, so
        the same seed gives the same rays.

    Returns
    -------
    (N, n_rays, 2) float array
        ``result[i, k]`` is where ray ``k`` of point ``i`` lands.
    """
    raise NotImplementedError("ex4: simulate_aperture")


# --------------------------------------------------------------------- ex5
def draw_points(image, pts, radius=3, color=(0, 0, 255)):
    """Draw a filled circle at every point, on a copy of ``image``.

    Parameters
    ----------
    image : (H, W, 3) uint8 array
    pts : (N, 2) float array
        ``(x, y)`` pixel positions; round them to the nearest integer pixel
        (``cv2.circle`` wants integer ``(x, y)`` centres). Points that are NaN
        (e.g. behind the camera) are skipped; points off the image simply do not
        show.
    radius : int
    color : (3,) ints
        BGR colour (the default is red).

    Returns
    -------
    (H, W, 3) uint8 array
        The input is not modified.
    """
    raise NotImplementedError("ex5: draw_points")


def project_onto_image(image, P, points):
    """Project world points with ``P`` and draw them on the image.

    Parameters
    ----------
    image : (H, W, 3) uint8 array
    P : (3, 4) float array
    points : (N, 3) float array

    Returns
    -------
    drawn : (H, W, 3) uint8 array
        ``draw_points(image, pts)`` with the default radius and colour.
    pts : (N, 2) float array
        ``project(P, points)``.
    """
    raise NotImplementedError("ex5: project_onto_image")


# --------------------------------------------------------------------- ext1
def calibrate(images, pattern_size, square_size):
    """Calibrate a camera from chessboard images (Zhang's method, with OpenCV).

    For every image: ``cv2.findChessboardCorners`` (and ``cv2.cornerSubPix`` to
    refine the corners); the matching object points are the inner corners on
    the board plane ``Z = 0``, row by row with ``x`` fastest:
    ``np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size``. Then
    ``cv2.calibrateCamera`` with the image size as ``(width, height)``.

    Parameters
    ----------
    images : list of (H, W) or (H, W, 3) uint8 arrays
        Views of the same chessboard.
    pattern_size : (cols, rows)
        Inner corners per row and per column, as OpenCV takes it.
    square_size : float
        Side of a square, in your unit of length.

    Returns
    -------
    K : (3, 3) float array
    dist : (5,) float array
        ``(k1, k2, p1, p2, k3)``.
    rms : float
        RMS reprojection error in pixels (what ``cv2.calibrateCamera`` returns first).
    """
    raise NotImplementedError("ext1: calibrate")


# --------------------------------------------------------------------- ext2
def distort_points(points, dist):
    """Apply Brown-Conrady lens distortion to normalised image coordinates.

    Normalised coordinates are ``(X / Z, Y / Z)`` (before ``K``). With
    ``dist = (k1, k2, p1, p2, k3)`` (OpenCV's order) and ``r^2 = x^2 + y^2``::

        x' = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)
        y' = y (1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y

    ``cv2.projectPoints`` of ``(x, y, 1)`` with a zero pose and ``K = I`` gives
    the same numbers: either way is accepted (writing the formula is the better exercise).

    Parameters
    ----------
    points : (N, 2) float array
    dist : (5,) float array

    Returns
    -------
    (N, 2) float array
    """
    raise NotImplementedError("ext2: distort_points")
