"""Lab 12 - stereo.

Fill in every function that raises ``NotImplementedError``, then check your work
with ``python grade.py lab12`` (or one exercise: ``python grade.py lab12.ex4``).

Conventions used throughout
---------------------------
- Images are ``numpy.ndarray`` of dtype ``uint8``, ``(H, W)`` grey (the stereo
  matchers receive grey images).
- Points are ``(x, y)`` with ``x`` the column and ``y`` the row, origin at the
  centre of the top-left pixel, y pointing down.
- A **rectified** pair: the right camera is the left one shifted by the
  baseline ``b`` along its x axis (same ``K``, same orientation). A point at
  depth ``Z`` appears on the **same row** in both images, at ``x_l`` in the
  left image and at ``x_r = x_l - d`` in the right one, with the disparity
  ``d = x_l - x_r = f b / Z > 0`` (objects appear further **left** in the right
  image).
- Disparity maps are ``(H, W)`` float arrays indexed like the **left** image.
  Invalid disparities and depths are ``<= 0`` or NaN.

What you may use
----------------
- ``triangulate``: build and solve the linear system yourself;
  ``cv2.triangulatePoints`` is not allowed. You may copy your lab 11 function
  here, or import it with ``from lab11_two_view import triangulate`` if your
  ``lab11_two_view.py`` sits in the same folder (the grader loads both from your
  submission folder).
- ``rectify``: you may use ``cv2.stereoRectify`` and ``cv2.warpPerspective``
  (or build the rotation yourself, as in the lecture).
- ``block_matching`` with ``cost="ssd"``: the lab sheet's recipe, ``cv2.StereoBM``,
  is allowed (see the function's notes for its fixed-point output and invalid
  band), and so is your own matcher. ``cost="ncc"`` (extension) is your own.
- ``dp_stereo`` is *your own* dynamic programming: ``cv2.StereoBM_create`` /
  ``cv2.StereoSGBM_create`` are not allowed there.
  Filtering helpers (``cv2.blur``, ``cv2.boxFilter``, ``scipy.ndimage``) are fine.
- Loop over disparities (or columns), not over pixels: the grader calls your
  matchers on images of about 185 x 125 pixels and gives each call 30 seconds.
"""

import cv2  # noqa: F401  (you will need it)
import numpy as np  # noqa: F401


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear triangulation of matched points (as in lab 11).

    For a view with camera matrix ``P`` (rows ``p1, p2, p3``) and its image point
    ``(x, y)``, ``x × (P X) = 0`` gives two equations in the homogeneous point
    ``X``: ``(x p3 - p1) X = 0`` and ``(y p3 - p2) X = 0``. Stack the four rows of
    the two views into ``A`` (4 x 4); ``X`` is the right singular vector of the
    smallest singular value of ``A`` (``np.linalg.svd``), divided by its fourth
    coordinate.

    Parameters
    ----------
    P1, P2 : (3, 4) float arrays
        Camera matrices of the two views.
    pts1, pts2 : (N, 2) float arrays
        Matching pixel coordinates in view 1 and view 2.

    Returns
    -------
    (N, 3) float array
        The 3D points, one per row (not homogeneous).

    Notes
    -----
    On a rectified rig (``P1 = K [I | 0]``, ``P2 = K [I | (-b, 0, 0)]``) the
    triangulated depth equals ``f b / d``: a good way to test ex2 against ex1.
    """
    raise NotImplementedError("ex1: triangulate")


# --------------------------------------------------------------------- ex2
def disparity_from_matches(xl, xr):
    """Disparities ``d = x_l - x_r`` of matches in a rectified pair.

    Parameters
    ----------
    xl, xr : (N,) float arrays of x coordinates, or (N, 2) arrays of (x, y) points
        Matching positions in the left and right image. For ``(N, 2)`` points,
        only the x coordinates (column 0) are used: in a rectified pair the rows
        agree.

    Returns
    -------
    (N,) float array
        Positive for points in front of the rig.
    """
    raise NotImplementedError("ex2: disparity_from_matches")


def depth_from_disparity(disparity, f, baseline):
    """Depth from disparity by similar triangles: ``Z = f * baseline / d``.

    Parameters
    ----------
    disparity : float array of any shape
        E.g. ``(N,)`` disparities of matches or an ``(H, W)`` disparity map.
    f : float
        Focal length in pixels.
    baseline : float
        Distance between the two camera centres; the depth comes out in the
        same unit (metres in, metres out).

    Returns
    -------
    float array of the same shape as ``disparity``
        ``f * baseline / d`` where ``d > 0``; **0** where ``d <= 0`` or NaN (no
        valid disparity - never inf, NaN or a negative depth).

    Examples
    --------
    >>> depth_from_disparity(np.array([10.0, 0.0]), f=500.0, baseline=0.1)
    array([5., 0.])
    """
    raise NotImplementedError("ex2: depth_from_disparity")


# --------------------------------------------------------------------- ex3
def rectify(img_l, img_r, K1, K2, R, T):
    """Rectify a calibrated stereo pair (no lens distortion).

    Warp both images so that corresponding points end up on the same row and
    the disparities ``x_l - x_r`` are positive.

    Parameters
    ----------
    img_l, img_r : (H, W) or (H, W, 3) uint8 arrays
        Left (camera 1) and right (camera 2) images, the same size.
    K1, K2 : (3, 3) float arrays
        Intrinsic matrices of the two cameras.
    R : (3, 3) float array
    T : (3,) float array
        The pose of camera 2 relative to camera 1: ``X2 = R @ X1 + T`` takes
        camera-1 coordinates to camera-2 coordinates (camera 2's centre is at
        ``-R.T @ T`` in camera-1 coordinates, to the right of camera 1).

    Returns
    -------
    rect_l, rect_r : uint8 arrays, the same shape as the inputs
        The rectified images (black where no input pixel lands).
    H1, H2 : (3, 3) float arrays
        Homographies from **original** pixel coordinates to **rectified** ones:
        ``rect_l`` is ``img_l`` warped by ``H1`` (``cv2.warpPerspective(img_l, H1,
        (W, H))``), and likewise for the right image.

    Notes
    -----
    - With ``cv2.stereoRectify(K1, None, K2, None, (W, H), R, T, ...)`` you get
      ``R1, R2, P1, P2``; the homographies are ``H1 = P1[:, :3] @ R1 @ inv(K1)``
      and ``H2 = P2[:, :3] @ R2 @ inv(K2)``. Both rectified cameras must share
      the same ``K`` (``flags=cv2.CALIB_ZERO_DISPARITY`` gives them the same
      principal point).
    - Most of each image must stay in view, and fill most of its frame.
    """
    raise NotImplementedError("ex3: rectify")


# --------------------------------------------------------------------- ex4 / ext1
def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    """Winner-take-all block matching on a rectified grey pair.

    For every left pixel ``(x, y)`` and every candidate ``d = 0..max_disparity``,
    compare the ``block_size x block_size`` block around ``(x, y)`` in the left
    image with the block around ``(x - d, y)`` in the right image, and keep the
    ``d`` with the best score.

    Parameters
    ----------
    left, right : (H, W) uint8 arrays
        A rectified pair.
    max_disparity : int
        Largest disparity searched (inclusive).
    block_size : int, odd
        Side of the square block.
    cost : {"ssd", "ncc"}
        ``"ssd"``: sum (or mean) of squared differences, lower is better.
        ``"ncc"`` (extension 1): normalised cross-correlation, **higher** is
        better; subtract each block's mean and divide by the product of the
        blocks' standard deviations, so that a change of brightness and contrast
        between the views does not matter.

    Returns
    -------
    (H, W) float array
        Disparities in ``0..max_disparity``, the left image's size; ``d = 0``
        (a point at infinity) is a disparity like any other. Pixels you cannot
        match may be marked invalid (0 or NaN). The grader judges the fraction of
        pixels off by more than 1 pixel (invalid ones count as wrong) where the
        truth is known, ignoring the outer 4 pixels of the image (a block does
        not fit there) and the band on the left where ``x - d`` leaves the right
        image for some ``d`` (``16 * ceil((max_disparity + 1) / 16) + block_size // 2``
        columns, where ``cv2.StereoBM`` gives no answer).

    Notes
    -----
    Your own matcher: vectorise over pixels. For each ``d``, shift the right
    image by ``d`` columns, compute the per-pixel squared difference, and sum it
    over blocks with a box filter (``cv2.boxFilter`` or ``cv2.blur``). That gives
    a cost volume ``(max_disparity + 1, H, W)``; ``np.argmin`` over its first
    axis is the disparity map. The ``d`` columns a shift brings in on the left
    have no partner in the right image: an infinite cost there keeps a pixel
    ``x`` from matching ``d > x`` (recommended, with a tip; the band is not judged).

    The lab sheet's ``cv2.StereoBM`` (``cost="ssd"`` only) needs three careful
    steps: ``numDisparities`` must be a multiple of 16, so round
    ``max_disparity + 1`` up and set what it finds above ``max_disparity`` to 0;
    its output is fixed point (int16, 16 x the disparity), so divide by 16.0;
    pixels it cannot match (the left band, low texture) come out negative: set
    them to 0 (invalid)::

        n = 16 * -(-(max_disparity + 1) // 16)
        d = cv2.StereoBM_create(numDisparities=n, blockSize=block_size).compute(left, right) / 16.0
        d[(d <= 0) | (d > max_disparity)] = 0
    """
    raise NotImplementedError("ex4: block_matching")


# --------------------------------------------------------------------- ex5
def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline stereo by dynamic programming (write it yourself).

    On every row, choose the disparities ``d_x`` minimising

        E = sum_x C(x, d_x) + smoothness * sum_x |d_x - d_(x+1)|

    where ``C(x, d)`` is a block-matching cost (e.g. the mean absolute or
    squared difference over a ``block_size`` block). Forward pass:
    ``M(x, d) = C(x, d) + min_d' [M(x-1, d') + smoothness |d - d'|]``; then
    backtrack from the best ``d`` at the last column.

    Parameters
    ----------
    left, right : (H, W) uint8 arrays
        A rectified pair.
    max_disparity : int
        Largest disparity searched (inclusive).
    block_size : int, odd
    smoothness : float, optional
        Penalty per pixel of disparity change, in the units of your cost.
        ``None`` means your own default, chosen to suit your cost's scale (the
        grader uses the default and judges the result). ``0`` switches the
        smoothness term off: every pixel then takes its best data cost
        (winner-take-all).

    Returns
    -------
    (H, W) float array of disparities in ``0..max_disparity``.

    Notes
    -----
    Process all rows at once: loop over the columns ``x`` and do the
    minimisation for every row and disparity with NumPy (an ``(H, D, D)`` array
    of ``M(x-1, d') + smoothness |d - d'|`` is small). A Python loop over every
    pixel will be too slow. ``cv2.StereoSGBM`` is not allowed here.
    """
    raise NotImplementedError("ex5: dp_stereo")


# --------------------------------------------------------------------- ex6
def gray_code_patterns(width, n_bits):
    """Gray-code stripe patterns for a projector ``width`` pixels wide.

    Column ``u`` belongs to stripe ``k = floor(u * 2**n_bits / width)`` (use
    integer arithmetic: ``(u * 2**n_bits) // width``). Its binary-reflected Gray
    code is ``g = k ^ (k >> 1)``; row ``i`` of the result holds bit ``i`` of ``g``
    counted from the **most significant** (row 0 = the coarsest pattern).

    Returns
    -------
    (n_bits, width) uint8 array
        0 for a 0 bit, 255 for a 1 bit.

    Examples
    --------
    >>> gray_code_patterns(8, 2)
    array([[  0,   0,   0,   0, 255, 255, 255, 255],
           [  0,   0, 255, 255, 255, 255,   0,   0]], dtype=uint8)
    """
    raise NotImplementedError("ex6: gray_code_patterns")


def simulate_structured_light(depth, f, baseline, n_bits):
    """The images a camera takes while the projector shows each Gray-code pattern.

    The projector is as wide as the image, rectified with the camera and
    ``baseline`` to its right (+x), with the same ``f`` and principal point.
    Camera pixel ``(u, v)`` (column, row) at depth ``Z = depth[v, u] > 0`` is lit
    by projector column ``p = round(u - f * baseline / Z)``, so in image ``i`` it
    has the value of pattern ``i`` at column ``p``.

    Parameters
    ----------
    depth : (H, W) float array
        Depth of every camera pixel; ``<= 0`` means nothing is there.
    f : float
        Focal length in pixels.
    baseline : float
    n_bits : int

    Returns
    -------
    (n_bits, H, W) uint8 array
        0 in every image where ``Z <= 0`` or ``p`` is not a projector column
        (``p < 0`` or ``p >= W``).
    """
    raise NotImplementedError("ex6: simulate_structured_light")


def depth_from_structured_light(images, f, baseline):
    """Depth from the images of :func:`simulate_structured_light`.

    Threshold each image at mid-grey (above 127 = bit 1), read the Gray code
    with image 0 as the most significant bit, convert it to the stripe index
    ``k`` (``b_0 = g_0``, ``b_i = b_(i-1) XOR g_i``), take the stripe centre
    ``(k + 0.5) * W / 2**n_bits - 0.5`` as the projector column, and
    triangulate: the disparity is ``u - column`` and ``Z = f * baseline / disparity``.

    Parameters
    ----------
    images : (n_bits, H, W) uint8 array
    f : float
    baseline : float

    Returns
    -------
    (H, W) float array
        0 where the pixel is undecodable (black in every image) or the
        disparity is not positive.
    """
    raise NotImplementedError("ex6: depth_from_structured_light")
