"""Lab 11 - two-view geometry.

Fill in every function that raises ``NotImplementedError``, then check your work
with ``python grade.py lab11`` (or one exercise: ``python grade.py lab11.ex4``).

Conventions used throughout
---------------------------
- 2D points are float arrays ``(N, 2)`` of ``(x, y)`` pixel coordinates, ``x`` the
  column and ``y`` the row, y pointing down. In equations a pixel is the
  homogeneous vector ``x = (x, y, 1)``.
- ``pts1[i]`` (in image 1) and ``pts2[i]`` (in image 2) are the same scene point:
  a *correspondence* ``x1 <-> x2``.
- 3D points are float arrays ``(N, 3)``.
- A camera matrix ``P = K [R | t]`` (3 x 4) maps a world point ``X`` (homogeneous,
  ``(X, Y, Z, 1)``) to the pixel ``x ~ P X``.
- The fundamental matrix F (3 x 3, rank 2) satisfies the epipolar constraint
  ``x2^T F x1 = 0`` for every correspondence. The essential matrix E satisfies
  the same constraint on *normalised* coordinates ``K^-1 x``, so
  ``E = K2^T F K1``, and its singular values are ``(s, s, 0)``.
- F, E and epipoles are projective: any non-zero multiple (sign included) is
  the same answer. The grader compares them up to scale and sign.
- In ex1-ex5 implement the linear algebra yourself with NumPy
  (``np.linalg.svd``); OpenCV's ``cv2.triangulatePoints`` and
  ``cv2.findFundamentalMat`` are not allowed there. In ex6 anything in OpenCV
  goes.
"""

import cv2  # noqa: F401  (you will need it)
import numpy as np  # noqa: F401


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear triangulation of corresponding points seen by two cameras.

    For one correspondence ``x1 <-> x2`` the unknown point X (homogeneous, 4
    entries) satisfies ``x1 x (P1 X) = 0`` and ``x2 x (P2 X) = 0``. Each cross
    product gives two independent equations; with ``p1^T, p2^T, p3^T`` the rows
    of P and ``(x, y)`` the pixel::

        x * p3^T X - p1^T X = 0
        y * p3^T X - p2^T X = 0

    Stack the two rows of each view into a 4 x 4 matrix A and solve ``A X = 0``
    by SVD: X is the right singular vector with the smallest singular value (the
    last row of ``Vt``). Finally divide X by its last entry ``w`` and keep the
    first three.

    Parameters
    ----------
    P1, P2 : (3, 4) float arrays
        The two camera matrices.
    pts1, pts2 : (N, 2) float arrays
        Corresponding pixels in image 1 and image 2.

    Returns
    -------
    (N, 3) float array
        The 3D points (Euclidean, in the cameras' world frame), one row per
        correspondence. Work on all N points at once if you can (``np.linalg.svd``
        accepts a stack of matrices of shape (N, 4, 4)).

    Notes
    -----
    ``cv2.triangulatePoints`` is not allowed here.
    """
    raise NotImplementedError("ex1: triangulate")


# --------------------------------------------------------------------- ex2
def epipolar_lines(F, pts1):
    """The epipolar lines in image 2 of points of image 1: ``l' = F x1``.

    Parameters
    ----------
    F : (3, 3) float array
        Fundamental matrix with ``x2^T F x1 = 0`` (any scale).
    pts1 : (N, 2) float array
        Points in image 1.

    Returns
    -------
    (N, 3) float array
        One line ``(a, b, c)`` per point, meaning ``a x + b y + c = 0`` in image 2,
        each scaled so that ``a^2 + b^2 = 1`` (either sign). With that scale
        ``|a x + b y + c|`` is the distance in pixels of ``(x, y)`` from the line,
        and the point ``pts2[i]`` matching ``pts1[i]`` lies on line i.
    """
    raise NotImplementedError("ex2: epipolar_lines")


def draw_epipolar_lines(image, lines):
    """Draw lines ``a x + b y + c = 0`` across the whole image.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) uint8 array
        Grey or BGR. It is not modified: draw on a copy.
    lines : (N, 3) float array
        Lines ``(a, b, c)`` in this image's pixel coordinates (any scale), e.g.
        from :func:`epipolar_lines`.

    Returns
    -------
    uint8 array with the input's channels
        The API's rule for functions that take an image: grey in, grey out
        (lines in white, 255); BGR in, BGR out (lines in bright colours, for
        instance a different colour per line; not black, not grey). A BGR copy
        of a grey input (``cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)``, as
        OpenCV's epipolar tutorial makes to draw in colour) breaks that rule:
        the lines are judged either way, the shape costs half of one check. Each
        line is drawn from border to border of the image, 1 or 2 pixels thick
        (``cv2.line``). Nothing else is changed.

    Notes
    -----
    A line may be steep or even vertical (``b = 0``): intersect it with the left
    and right borders (``x = 0`` and ``x = W - 1``) when it is mostly horizontal
    (``|b| >= |a|``), with the top and bottom borders otherwise.
    ``cv2.line`` needs integer end points.
    """
    raise NotImplementedError("ex2: draw_epipolar_lines")


# --------------------------------------------------------------------- ex3
def essential_from_fundamental(F, K1, K2):
    """The essential matrix ``E = K2^T F K1``.

    Parameters
    ----------
    F : (3, 3) float array
        Fundamental matrix (``x2^T F x1 = 0``).
    K1, K2 : (3, 3) float arrays
        Intrinsics of camera 1 and camera 2 (they may differ).

    Returns
    -------
    (3, 3) float array
        E (any scale).
    """
    raise NotImplementedError("ex3: essential_from_fundamental")


def essential_8point(pts1, pts2, K1, K2):
    """Estimate E from N >= 8 correspondences with the 8-point algorithm.

    1. Normalise the pixels: ``x1n = K1^-1 (x, y, 1)``, ``x2n = K2^-1 (x, y, 1)``.
    2. Each correspondence gives one linear equation ``x2n^T E x1n = 0`` in the
       nine entries of E (row i of the N x 9 matrix A is the outer product
       ``x2n x1n^T``, flattened row by row). Solve ``A e = 0`` by SVD.
    3. An essential matrix has singular values ``(s, s, 0)``: with
       ``E = U diag(s1, s2, s3) V^T``, return ``U diag(1, 1, 0) V^T``.

    Parameters
    ----------
    pts1, pts2 : (N, 2) float arrays
        Corresponding pixels, N >= 8.
    K1, K2 : (3, 3) float arrays

    Returns
    -------
    (3, 3) float array
        E with singular values (s, s, 0) (any scale and sign).
    """
    raise NotImplementedError("ex3: essential_8point")


# --------------------------------------------------------------------- ex4
def fundamental_8point(pts1, pts2):
    """Estimate F from N >= 8 correspondences: the 8-point algorithm with rank 2.

    The lab sheet's recipe is steps 2 and 3 on the pixels themselves; step 1
    (Hartley's normalisation) is recommended, not required: the grader accepts
    the accuracy of either on noisy data.

    1. (Recommended) Normalise each image's points with a similarity T (T1 for
       image 1, T2 for image 2): move the centroid to the origin and scale so
       that the mean distance from it is sqrt(2). Without this step the linear
       system mixes entries of order 1e5 (x * x') with 1 and the result suffers
       more from noise.
    2. Solve ``x2n^T Fn x1n = 0`` by SVD (rows ``x2n x1n^T`` flattened, as in
       :func:`essential_8point`).
    3. Enforce rank 2: ``Fn = U diag(s1, s2, 0) V^T``.
    4. Undo the normalisation: ``F = T2^T Fn T1``.

    Parameters
    ----------
    pts1, pts2 : (N, 2) float arrays
        Corresponding pixels, N >= 8.

    Returns
    -------
    (3, 3) float array
        F with ``x2^T F x1 = 0`` and rank 2 (any scale and sign).

    Notes
    -----
    ``cv2.findFundamentalMat`` is not allowed here.
    """
    raise NotImplementedError("ex4: fundamental_8point")


# --------------------------------------------------------------------- ex5
def epipoles(F):
    """The two epipoles of F.

    ``e1`` (in image 1, the image of camera 2's centre) satisfies ``F e1 = 0``;
    ``e2`` (in image 2) satisfies ``F^T e2 = 0``. Both are null vectors: with
    ``F = U S V^T``, e1 is the last row of ``V^T`` and e2 the last column of U.

    Parameters
    ----------
    F : (3, 3) float array
        Rank-2 fundamental matrix.

    Returns
    -------
    e1, e2 : (3,) float arrays
        Homogeneous vectors (any scale). Do not divide by the last entry: when
        the cameras move parallel to the image plane the epipoles are at
        infinity and that entry is 0.
    """
    raise NotImplementedError("ex5: epipoles")


# --------------------------------------------------------------------- ex6
def two_view_reconstruction(img1, img2, K):
    """The real-world pipeline: from two photos to 3D points.

    Any OpenCV function is allowed here. A typical pipeline:

    1. Detect and match features (``cv2.SIFT_create``, a ``cv2.BFMatcher``
       with Lowe's ratio test, as in lab 8).
    2. Estimate F robustly: ``cv2.findFundamentalMat(pts1, pts2,
       cv2.FM_RANSAC, 1.0, 0.999)``; keep only its inliers.
    3. ``E = K^T F K`` (both photos come from the same camera), then the
       relative pose: ``cv2.recoverPose(E, pts1, pts2, K)`` gives R, t with
       ``X2 = R X1 + t``.
    4. Triangulate with ``P1 = K [I | 0]`` and ``P2 = K [R | t]`` (your
       :func:`triangulate`) and keep the points in front of both cameras.

    Parameters
    ----------
    img1, img2 : (H, W, 3) uint8 arrays
        Two BGR photos of the same static scene from different positions.
    K : (3, 3) float array
        The camera's intrinsics (the same for both photos).

    Returns
    -------
    F : (3, 3) float array
        With ``x2^T F x1 = 0``.
    pts1, pts2 : (M, 2) float arrays
        The matches you keep (inliers), M >= 20: most of them must be correct.
    points3d : (M, 3) float array
        The 3D point of each match in camera 1's frame (camera 1 at the origin,
        looking along +Z, so visible points have Z > 0). Two views fix the scene
        only up to one global scale (``|t| = 1`` from ``recoverPose`` is fine):
        the grader accepts any positive overall scale.
    """
    raise NotImplementedError("ex6: two_view_reconstruction")
