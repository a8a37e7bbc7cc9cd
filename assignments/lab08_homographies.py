"""Lab 8 - image homographies.

Fill in every function that raises ``NotImplementedError``, then check your work
with ``python grade.py lab08`` (or one exercise: ``python grade.py lab08.ex2``).

Conventions used throughout
---------------------------
- Images are ``numpy.ndarray`` of dtype ``uint8``, shape ``(H, W)`` (grey) or
  ``(H, W, 3)`` (BGR, as ``cv2.imread`` gives). A function that takes an image
  returns the same dtype and channel count unless its docstring says otherwise.
- Points are float arrays of shape ``(N, 2)`` holding ``(x, y)``: ``x`` is the
  column, ``y`` the row, the origin is the centre of the top-left pixel and
  **y points down**. (``cv2.KeyPoint.pt`` uses the same convention.)
- A homography ``H`` is a 3x3 float array acting on homogeneous coordinates:
  ``(x, y)`` goes to ``(u / w, v / w)`` with ``(u, v, w) = H @ (x, y, 1)``.
  It is defined up to a non-zero scale (sign included): the grader accepts any
  scale, but normalising to ``H[2, 2] == 1`` is customary.
- Image warps are bilinear with black fill (pixels with no source pixel are 0);
  ``cv2.warpPerspective`` with ``borderMode=cv2.BORDER_CONSTANT, borderValue=0``
  does this. ``dsize`` is ``(width, height)``, as in OpenCV.
- Functions that use randomness take ``seed``; use
  ``rng = np.random.default_rng(seed)`` so that a given seed always gives the
  same answer.

What you may use
----------------
- ex2: build and solve the DLT system yourself; ``cv2.findHomography`` and
  ``cv2.getPerspectiveTransform`` are not allowed inside ``homography_dlt``.
- ex4: the lab sheet's recipe, ``cv2.findHomography(src, dst, cv2.RANSAC,
  threshold)``, is allowed (``seed`` then goes unused), and so is your own
  RANSAC loop calling your ``homography_dlt``. (If your instructor asks for
  your own loop, the grader's feedback says that ``cv2.findHomography`` is not
  allowed there.)
- Matplotlib is welcome for looking at your results; the grader runs it
  without a window and closes your figures after each call.
- Everything else may use OpenCV freely (``cv2.warpPerspective``,
  ``cv2.SIFT_create``, ``cv2.BFMatcher``, ``cv2.pyrDown`` ...), and ``stitch``
  may use any of your functions.
"""

import cv2  # noqa: F401  (you will need it)
import numpy as np  # noqa: F401


# --------------------------------------------------------------------- ex1
def apply_homography(image, H, dsize=None):
    """Warp ``image`` by the homography ``H`` (source to output coordinates).

    Parameters
    ----------
    image : (H, W) or (H, W, 3) uint8 array
    H : (3, 3) float array
        Maps a source pixel ``(x, y)`` to the output pixel ``H (x, y, 1)``
        (after the perspective division).
    dsize : (width, height), optional
        Output size; defaults to the input's size.

    Returns
    -------
    uint8 array of shape (height, width[, 3])
        Bilinear interpolation, black fill. Note that ``cv2.warpPerspective``
        takes the source-to-output H and inverts it itself: do not pass
        ``np.linalg.inv(H)`` or ``cv2.WARP_INVERSE_MAP``.
    """
    raise NotImplementedError("ex1: apply_homography")


def transform_points(H, pts):
    """Map points by ``H``, with the perspective division.

    Parameters
    ----------
    H : (3, 3) float array
    pts : (N, 2) float array
        Points ``(x, y)``.

    Returns
    -------
    (N, 2) float array
        ``(u / w, v / w)`` for ``(u, v, w) = H @ (x, y, 1)`` for every point.
        Forgetting to divide by ``w`` is right only for affine H (last row
        ``[0, 0, 1]``); a real homography has ``w != 1``. Vectorise: stack the
        points as rows ``[x, y, 1]`` and multiply by ``H.T``.

    Examples
    --------
    >>> transform_points(np.diag([2.0, 2.0, 1.0]), [[1.0, 3.0]])
    array([[2., 6.]])
    """
    raise NotImplementedError("ex1: transform_points")


# --------------------------------------------------------------------- ex2
def homography_dlt(src, dst):
    """The homography with ``dst ~ H @ src``, by the DLT (solved by SVD).

    Parameters
    ----------
    src, dst : (N, 2) float arrays, N >= 4
        Corresponding points; no three of the first four collinear.

    Returns
    -------
    H : (3, 3) float array
        Any scale is accepted (``H / H[2, 2]`` is customary).

    Notes
    -----
    Each pair ``(x, y) -> (x', y')`` gives two rows of a 2N x 9 system
    ``A h = 0`` with ``h = H.ravel()`` (row-major: h11, h12, h13, h21, ...)::

        [x  y  1  0  0  0  -x'x  -x'y  -x']
        [0  0  0  x  y  1  -y'x  -y'y  -y']

    ``h`` is the right singular vector of ``A`` for the smallest singular value
    (the last row of ``Vt`` from ``np.linalg.svd(A)``), reshaped to 3x3. Keep the
    full SVD: with 4 pairs A is 8x9, and ``full_matrices=False`` would drop the
    9th right singular vector, the one you need.

    Recommended (advice, no points: the lab sheet does not ask for it):
    normalise first (Hartley): for each point set, a similarity ``T`` moving the
    centroid to the origin and scaling so the mean distance to it is sqrt(2).
    Solve for ``H_n`` with the normalised points, then return
    ``inv(T_dst) @ H_n @ T_src``. With raw pixel coordinates the entries of A
    range from 1 to about 1e6 and, under noise, the estimate is visibly worse;
    the grader's advice shows this on a small patch far from the image origin.
    """
    raise NotImplementedError("ex2: homography_dlt")


def warp_to_reference(reference, moving, H):
    """``moving`` warped into ``reference``'s frame.

    Parameters
    ----------
    reference : (Hr, Wr[, 3]) uint8 array
        Only its size is used.
    moving : (Hm, Wm[, 3]) uint8 array
    H : (3, 3) float array
        Maps ``moving``'s pixel coordinates to ``reference``'s.

    Returns
    -------
    uint8 array of shape (Hr, Wr[, 3]) (the moving image's channels)
        Pixels that ``moving`` does not cover are black.
    """
    raise NotImplementedError("ex2: warp_to_reference")


# --------------------------------------------------------------------- ex3
def match_features(img1, img2, ratio=0.75, method="sift"):
    """Match keypoints between two images with Lowe's ratio test.

    Parameters
    ----------
    img1, img2 : uint8 images, grey or BGR
        Convert to grey for the detector.
    ratio : float
        Keep a match only when ``best.distance < ratio * second_best.distance``
        (``cv2.BFMatcher(...).knnMatch(des1, des2, k=2)``). Smaller is stricter:
        fewer, more reliable matches.
    method : {"sift", "orb"}
        ``"sift"``: ``cv2.SIFT_create()``, descriptors compared with ``cv2.NORM_L2``.
        ``"orb"`` (extension 1): ``cv2.ORB_create(nfeatures=1000)``, binary
        descriptors compared with ``cv2.NORM_HAMMING``.

    Returns
    -------
    pts1, pts2 : (M, 2) float arrays
        Row i holds the two ends of match i: ``pts1[i]`` in ``img1``
        (``keypoints1[m.queryIdx].pt``) and ``pts2[i]`` in ``img2``
        (``keypoints2[m.trainIdx].pt``), as ``(x, y)``. ``M`` may be 0.
    """
    raise NotImplementedError("ex3: match_features")


def draw_matches(img1, img2, pts1, pts2):
    """Both images side by side with a line for each match.

    Parameters
    ----------
    img1 : (H1, W1[, 3]) uint8 array
    img2 : (H2, W2[, 3]) uint8 array
    pts1, pts2 : (M, 2) float arrays
        Matches as returned by ``match_features``.

    Returns
    -------
    (max(H1, H2), W1 + W2, 3) uint8 array
        ``img1`` at the left, ``img2`` right after it (starting at column
        ``W1``), both in colour (grey images converted with
        ``cv2.COLOR_GRAY2BGR``), black below the shorter one. For each match a
        line from ``pts1[i]`` to ``pts2[i] + (W1, 0)`` in a clearly visible
        colour (small circles at the ends are welcome). You may build it with
        numpy and ``cv2.line``, or with ``cv2.drawMatches``.
    """
    raise NotImplementedError("ex3: draw_matches")


# --------------------------------------------------------------------- ex4
def homography_ransac(src, dst, threshold=3.0, seed=None):
    """A homography robust to wrong correspondences, by RANSAC.

    Parameters
    ----------
    src, dst : (N, 2) float arrays, N >= 4
        Putative correspondences, some of them wrong (outliers).
    threshold : float
        A pair is an inlier when its transfer error ``|H src - dst|`` (pixels,
        the distance itself, not its square) is below ``threshold``.
    seed : int, optional
        Seed of your random generator (``np.random.default_rng(seed)``).

    Returns
    -------
    H : (3, 3) float array
        Re-estimated on all its inliers (``homography_dlt`` on them; a
        4-point sample's H is noisy). ``cv2.findHomography`` with
        ``cv2.RANSAC`` does this refit itself.
    inliers : (N,) bool array
        True for the inliers: the pairs within ``threshold`` of the final H
        (or of the best sample's H, as ``cv2.findHomography`` reports them).

    Notes
    -----
    Repeat: draw 4 distinct pairs, fit H to them, count the pairs within the
    threshold; keep the H with the most inliers. Draw enough samples: with an
    inlier ratio w, a sample is all inliers with probability w**4, so
    ``log(1 - 0.99) / log(1 - w**4)`` samples find one with 99% confidence
    (72 for w = 0.5; the grader uses up to 50% outliers). Finally refit H on
    every inlier and recompute the mask. The grader runs several seeds.
    """
    raise NotImplementedError("ex4: homography_ransac")


# --------------------------------------------------------------------- ex5
def stitch(img1, img2):
    """A panorama of two overlapping images, in ``img1``'s frame.

    Parameters
    ----------
    img1, img2 : uint8 BGR images that overlap (img2 may lie on any side)

    Returns
    -------
    panorama : (Hp, Wp, 3) uint8 array
        ``img1`` appears unwarped (only shifted); ``img2`` is warped onto it.

    Notes
    -----
    1. Match features and estimate H mapping img2's pixels onto img1's with
       your ``homography_ransac`` (from ``pts2`` to ``pts1``).
    2. Map img2's four corners with H; with img1's corners they give the
       bounding box ``x_min, y_min, x_max, y_max`` (it may start at negative
       coordinates).
    3. ``T = [[1, 0, -x_min], [0, 1, -y_min], [0, 0, 1]]`` (round ``x_min``,
       ``y_min`` down to integers so img1 is copied exactly); warp img1 with
       ``T`` and img2 with ``T @ H`` onto a canvas of the bounding box's size.
    4. Blend the overlap: an average, or better feathering (weights growing
       with the distance to each image's border, ``cv2.distanceTransform``).
    """
    raise NotImplementedError("ex5: stitch")


# --------------------------------------------------------------------- ext2
def stitch_many(images):
    """A panorama of three or more overlapping images.

    Parameters
    ----------
    images : list of uint8 BGR images
        In left-to-right order; each overlaps its neighbours.

    Returns
    -------
    panorama : (Hp, Wp, 3) uint8 array
        In the frame of one of the images (any one; the middle one distorts
        least), which appears unwarped, only shifted.

    Notes
    -----
    Estimate the homographies between neighbours, then chain them to the
    reference r: e.g. with ``H_21`` mapping image 2 onto image 1 and ``H_32``
    mapping image 3 onto image 2, image 3 goes to image 1 with
    ``H_31 = H_21 @ H_32`` (first 3 -> 2, then 2 -> 1). Images on the other side
    of the reference use inverses. Then proceed as in ``stitch``: bounding box
    of all warped corners, one translation, warp, blend.
    """
    raise NotImplementedError("ext2: stitch_many")


# --------------------------------------------------------------------- ext3
def blend_multiband(img1, img2, mask, levels=4):
    """Laplacian-pyramid (multi-band) blending of two aligned images.

    Parameters
    ----------
    img1, img2 : uint8 arrays of the same shape, grey or BGR
    mask : (H, W) float array in [0, 1]
        The weight of ``img1`` (``1 - mask`` is the weight of ``img2``).
    levels : int
        Number of pyramid levels, the full-resolution one included (so the
        images are downsampled ``levels - 1`` times).

    Returns
    -------
    uint8 array, same shape as ``img1``

    Notes
    -----
    Work in float (``np.float32``): Laplacian levels are negative in places.
    Gaussian pyramid: ``G[0] = image``, ``G[i + 1] = cv2.pyrDown(G[i])``.
    Laplacian pyramid: ``L[i] = G[i] - cv2.pyrUp(G[i + 1], dstsize=(w_i, h_i))``
    for the finer levels and ``L[top] = G[top]`` (pass ``dstsize`` so sizes that
    are not multiples of 2**levels work). Blend each level with the mask's
    Gaussian pyramid at that level: ``Gm[i] * L1[i] + (1 - Gm[i]) * L2[i]``, then
    collapse from the top: ``out = pyrUp(out, dstsize) + blended[i]``.
    Blending an image with itself must give the image back; far from the seam
    the result equals the image the mask selects; across the seam coarse
    differences (exposure) fade over a wide band while detail stays sharp.
    """
    raise NotImplementedError("ext3: blend_multiband")
