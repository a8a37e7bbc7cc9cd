"""Lab 10 - geometric camera models, continued.

Fill in every function that raises ``NotImplementedError``, then check your work
with ``python grade.py lab10`` (or one exercise: ``python grade.py lab10.ex4``).

Conventions used throughout
---------------------------
- 3D points are float arrays ``(N, 3)``; a function documented for ``(N, 3)``
  also accepts a single ``(3,)`` point and then returns a single ``(2,)`` result.
- 2D points are ``(N, 2)`` float arrays of ``(x, y)`` = (column, row), y down.
- Camera frame: the camera looks along ``+Z``; ``X`` right, ``Y`` down.
  ``P = K [R | t]`` maps world points to pixels, ``X_cam = R X + t``.
- Projective matrices (``P``) are defined up to a non-zero scale, sign included.
- Rotations are returned as Rodrigues vectors ``rvec`` (radians), like
  ``cv2.solvePnP`` gives them; ``cv2.Rodrigues`` converts to a 3x3 matrix.
- Lens distortion ``dist`` is OpenCV's ``(k1, k2, p1, p2, k3)``.
"""

import cv2  # noqa: F401  (you will need it)
import numpy as np  # noqa: F401


# --------------------------------------------------------------------- ex1
def perspective_project(points, f):
    """Perspective projection ``x = f X / Z``, ``y = f Y / Z``.

    Used with ``f = 100, 500, 1000`` to see how the focal length scales the image.

    Parameters
    ----------
    points : (N, 3) or (3,) float array
        Camera-frame points.
    f : float

    Returns
    -------
    (N, 2) or (2,) float array
        For points with ``Z <= 0`` (behind the camera: no image) the formula
        gives some value; NaN there is recommended, not required (the grader
        gives a tip, no points either way).
    """
    raise NotImplementedError("ex1: perspective_project")


# --------------------------------------------------------------------- ex2
def weak_perspective_project(points, f, z_avg=None):
    """Weak perspective: every point divided by one common depth.

    ``x = f X / z_avg``, ``y = f Y / z_avg``. A good approximation of
    perspective when the object's depth range is small compared with its
    distance.

    Parameters
    ----------
    points : (N, 3) or (3,) float array
    f : float
    z_avg : float or None
        The common depth; ``None`` means the mean ``Z`` of ``points``.

    Returns
    -------
    (N, 2) or (2,) float array
    """
    raise NotImplementedError("ex2: weak_perspective_project")


# --------------------------------------------------------------------- ex3
def orthographic_project(points):
    """Orthographic projection with the lab sheet's matrix.

    ``[x, y, w]^T = M [X, Y, Z, 1]^T`` with
    ``M = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]]``, then ``(x / w, y / w)``:
    depth is simply dropped.

    Parameters
    ----------
    points : (N, 3) or (3,) float array

    Returns
    -------
    (N, 2) or (2,) float array
    """
    raise NotImplementedError("ex3: orthographic_project")


# --------------------------------------------------------------------- ex4
def camera_matrix_dlt(points3d, points2d):
    """The camera matrix from 3D-2D correspondences by the Direct Linear Transform.

    Each correspondence ``X = (X, Y, Z, 1) <-> (u, v)`` gives two linear
    equations in the 12 entries ``p`` of P (row by row)::

        [X^T, 0^T, -u X^T] p = 0
        [0^T, X^T, -v X^T] p = 0

    Stack them into a ``2N x 12`` matrix ``A`` and take the right singular vector
    of the smallest singular value (the last row of ``Vt`` from
    ``np.linalg.svd(A)``); reshape it to 3 x 4. Implement it yourself
    (``cv2.calibrateCamera`` / ``cv2.solvePnP`` are not allowed here).
    Normalising both point sets first (Hartley) makes it more accurate with noise.

    Parameters
    ----------
    points3d : (N, 3) float array
        World points, N >= 6, not all on one plane.
    points2d : (N, 2) float array
        Their pixel positions.

    Returns
    -------
    P : (3, 4) float array
        Any non-zero scale (sign included).
    """
    raise NotImplementedError("ex4: camera_matrix_dlt")


# --------------------------------------------------------------------- ex5
def decompose_camera_matrix(P):
    """Split ``P ~ K [R | t]`` into intrinsics and pose.

    Use an RQ decomposition of the left 3x3 block ``M = K R`` (e.g.
    ``scipy.linalg.rq``, or ``np.linalg.qr`` of a flipped matrix), then:

    - make K's diagonal positive (flip the signs of the matching columns of K
      and rows of R),
    - P is known only up to sign: if ``det(M) < 0`` negate P first, so that
      ``det(R) = +1``,
    - ``t = K^-1 p4`` (``p4`` the last column of P), and divide K by ``K[2, 2]``.

    Note: ``t`` is the translation in ``X_cam = R X + t``, *not* the camera
    centre (that is ``camera_center(P) = -R^T t``).

    Parameters
    ----------
    P : (3, 4) float array

    Returns
    -------
    K : (3, 3) float array
        Upper triangular, positive diagonal, ``K[2, 2] == 1``.
    R : (3, 3) float array
        Rotation, ``det(R) == +1``.
    t : (3,) float array
    """
    raise NotImplementedError("ex5: decompose_camera_matrix")


def camera_center(P):
    """The camera centre: the point ``C`` with ``P @ [C, 1] = 0``.

    Parameters
    ----------
    P : (3, 4) float array

    Returns
    -------
    C : (3,) float array
        In world coordinates (the null vector of P, divided by its last entry).
    """
    raise NotImplementedError("ex5: camera_center")


# --------------------------------------------------------------------- ex6
def estimate_pose(image, pattern_size, square_size, K, dist=None):
    """The pose of a chessboard seen in ``image``.

    Find the inner corners (``cv2.findChessboardCorners``, refine with
    ``cv2.cornerSubPix``); their object points lie on the board plane ``Z = 0``
    in OpenCV's corner order, row by row with ``x`` fastest:
    ``np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size``. Then
    ``cv2.solvePnP`` gives the pose, and ``cv2.projectPoints`` the corners
    projected back with it.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) uint8 array
    pattern_size : (cols, rows)
        Inner corners per row and per column.
    square_size : float
        Side of a square (the unit of ``tvec``).
    K : (3, 3) float array
    dist : (5,) float array or None
        Lens distortion of the camera (None: no distortion).

    Returns
    -------
    rvec : (3,) float array
        Rodrigues vector of the board-to-camera rotation.
    tvec : (3,) float array
        Board origin (corner 0) in camera coordinates: ``X_cam = R X_board + tvec``.
    reprojected : (M, 2) float array
        The object points projected with the pose (same order as the corners;
        ``cv2.projectPoints`` gives them as (M, 1, 2): reshape to (M, 2)).

    If no board is found: ``rvec`` and ``tvec`` full of NaN and
    ``reprojected = np.zeros((0, 2))``.
    """
    raise NotImplementedError("ex6: estimate_pose")


# --------------------------------------------------------------------- ext1
def undistort_image(image, K, dist):
    """Remove lens distortion from an image, keeping the camera matrix ``K``.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) uint8 array
    K : (3, 3) float array
    dist : (5,) float array

    Returns
    -------
    uint8 array, same shape as ``image``
        The image an ideal pinhole camera with the same ``K`` would record.
    """
    raise NotImplementedError("ext1: undistort_image")


# --------------------------------------------------------------------- ext2
def dolly_zoom(points, f0, z0, distances):
    """Simulate a dolly zoom ("Vertigo effect").

    The points are given in the original camera's frame; the subject is the
    plane at depth ``z0``. For each ``d`` in ``distances`` the camera moves
    along its optical axis so that the subject plane is at distance ``d``:
    every depth changes by ``d - z0`` (``Z -> Z + d - z0``, X and Y unchanged).
    At the same time it zooms to ``f = f0 * d / z0`` so the subject keeps its
    size, while the background (points at other depths) changes.

    Parameters
    ----------
    points : (N, 3) float array
    f0 : float
        Focal length when the subject is at ``z0``.
    z0 : float
    distances : (F,) float array

    Returns
    -------
    focal_lengths : (F,) float array
    projections : (F, N, 2) float array
        ``perspective_project`` of the moved points with each focal length.
    """
    raise NotImplementedError("ext2: dolly_zoom")


# --------------------------------------------------------------------- ext3
def track_pose(frames, pattern_size, square_size, K, dist=None):
    """The chessboard's pose in every frame of a sequence.

    Parameters
    ----------
    frames : list of (H, W) or (H, W, 3) uint8 arrays
    pattern_size, square_size, K, dist
        As for ``estimate_pose``.

    Returns
    -------
    (F, 6) float array
        Row ``i`` is ``[rvec, tvec]`` of frame ``i``; NaN where the board is not found.
    """
    raise NotImplementedError("ext3: track_pose")
