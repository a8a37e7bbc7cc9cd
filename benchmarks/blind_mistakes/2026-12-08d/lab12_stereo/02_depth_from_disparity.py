"""Lab 12 - stereo (reference solution).

A rectified stereo pair is two pinhole cameras with the same intrinsics and
orientation, the right one shifted by the baseline ``b`` along the x axis. A
scene point at depth ``Z`` is seen on the same row in both images, at columns
``x_l`` and ``x_r = x_l - d`` with the disparity ``d = f b / Z``. Stereo is
therefore (1) getting the pair into that form (rectification), (2) finding,
for every left pixel, the disparity of its match in the right image (block
matching, dynamic programming), and (3) turning disparities into depth.
Structured light replaces the second camera by a projector whose columns
identify themselves through a sequence of Gray-code stripe patterns.

This module is self-contained (it imports nothing from the other labs).
"""

import cv2
import numpy as np


# --------------------------------------------------------------------- helpers
def _grey_float(image):
    """A grey float64 copy of a grey or BGR uint8 image."""
    image = np.asarray(image)
    if image.ndim == 3:
        image = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
    return image.astype(np.float64)


def _box_mean(image, block_size):
    """Mean over the ``block_size x block_size`` window centred on every pixel."""
    return cv2.blur(image, (block_size, block_size), borderType=cv2.BORDER_REFLECT)


def _shift_right(image, d):
    """``out[:, x] = image[:, x - d]`` (columns ``x < d`` repeat column 0)."""
    if d == 0:
        return image
    out = np.empty_like(image)
    out[:, d:] = image[:, :-d]
    out[:, :d] = image[:, :1]
    return out


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear (DLT) triangulation of matched points.

    For a view with camera matrix ``P`` (rows ``p1, p2, p3``) and image point
    ``(x, y)``, the constraint ``x × (P X) = 0`` gives two independent linear
    equations in the homogeneous point ``X``::

        (x p3 - p1) X = 0
        (y p3 - p2) X = 0

    Two views give a 4x4 system ``A X = 0``; its least-squares solution with
    ``|X| = 1`` is the right singular vector of the smallest singular value.
    Each row is scaled to unit length first, which does not change the exact
    solution but balances the equations when there is noise.

    Parameters
    ----------
    P1, P2 : (3, 4) float arrays
    pts1, pts2 : (N, 2) float arrays (or single (2,) points)

    Returns
    -------
    (N, 3) float array (or (3,) for single points)
    """
    P1 = np.asarray(P1, dtype=np.float64)
    P2 = np.asarray(P2, dtype=np.float64)
    pts1 = np.asarray(pts1, dtype=np.float64)
    single = pts1.ndim == 1
    pts1 = pts1.reshape(-1, 2)
    pts2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
    A = np.stack([
        pts1[:, :1] * P1[2] - P1[0],
        pts1[:, 1:] * P1[2] - P1[1],
        pts2[:, :1] * P2[2] - P2[0],
        pts2[:, 1:] * P2[2] - P2[1],
    ], axis=1)                                            # (N, 4, 4)
    A /= np.linalg.norm(A, axis=2, keepdims=True)
    _, _, Vt = np.linalg.svd(A)
    X = Vt[:, -1]                                         # (N, 4) homogeneous
    X = X[:, :3] / X[:, 3:]
    return X[0] if single else X


# --------------------------------------------------------------------- ex2
def disparity_from_matches(xl, xr):
    """Disparities ``d = x_l - x_r`` of matches in a rectified pair.

    Parameters
    ----------
    xl, xr : (N,) float arrays of x coordinates, or (N, 2) arrays of (x, y) points

    Returns
    -------
    (N,) float array
    """
    xl = np.asarray(xl, dtype=np.float64)
    xr = np.asarray(xr, dtype=np.float64)
    if xl.ndim == 2:
        xl = xl[:, 0]
    if xr.ndim == 2:
        xr = xr[:, 0]
    return xl - xr


def depth_from_disparity(disparity, f, baseline):
    """Z = f * b / d where d > 0, 0 elsewhere (NaN compares False, so it gets 0 too)."""
    d = np.asarray(disparity, dtype=float)
    depth = np.zeros(d.shape)
    good = d >= 0
    depth[good] = f * baseline / d[good]
    return depth


# --------------------------------------------------------------------- ex3
def rectify(img_l, img_r, K1, K2, R, T):
    """Rectify a calibrated pair (Fusiello's construction).

    Both cameras are rotated, about their own centres, to a common orientation
    whose x axis points along the baseline (from camera 1 to camera 2), and given
    the same new intrinsics. A rotation about the centre is the homography
    ``K_new R_rect K^-1`` in the image, so no 3D information is needed.

    In camera-1 coordinates camera 2's centre is ``C2 = -R^T T``. The new axes
    are ``e1 = C2 / |C2|``, ``e2`` perpendicular to ``e1`` and to the mean
    optical axis, ``e3 = e1 × e2``; ``R_rect`` has them as rows. Camera 2's
    rays ``r2`` are ``R^T r2`` in camera-1 coordinates, hence
    ``H2 = K_new R_rect R^T K2^-1``. The new principal point centres the two
    rectified images in their frames (same for both, so ``d = x_l - x_r = f b / Z``).

    Parameters
    ----------
    img_l, img_r : (H, W) or (H, W, 3) uint8 arrays
    K1, K2 : (3, 3) float arrays
    R, T : (3, 3) and (3,) float arrays with ``X2 = R X1 + T``

    Returns
    -------
    rect_l, rect_r : uint8 arrays, the input size
    H1, H2 : (3, 3) float arrays mapping original to rectified pixels
    """
    K1 = np.asarray(K1, dtype=np.float64)
    K2 = np.asarray(K2, dtype=np.float64)
    R = np.asarray(R, dtype=np.float64)
    T = np.asarray(T, dtype=np.float64).reshape(3)
    height, width = np.asarray(img_l).shape[:2]

    C2 = -R.T @ T
    e1 = C2 / np.linalg.norm(C2)
    mean_axis = np.array([0.0, 0.0, 1.0]) + R.T @ np.array([0.0, 0.0, 1.0])
    e2 = np.cross(mean_axis, e1)
    e2 /= np.linalg.norm(e2)
    e3 = np.cross(e1, e2)
    R_rect = np.vstack([e1, e2, e3])

    f = (K1[0, 0] + K1[1, 1] + K2[0, 0] + K2[1, 1]) / 4.0
    rot1 = R_rect @ np.linalg.inv(K1)
    rot2 = R_rect @ R.T @ np.linalg.inv(K2)
    # Principal point: put the mean of the two rectified image centres at the centre.
    centre = np.array([(width - 1) / 2.0, (height - 1) / 2.0, 1.0])
    mapped = []
    for rot in (rot1, rot2):
        ray = rot @ centre
        mapped.append(f * ray[:2] / ray[2])
    cx, cy = centre[:2] - np.mean(mapped, axis=0)
    K_new = np.array([[f, 0.0, cx], [0.0, f, cy], [0.0, 0.0, 1.0]])
    H1 = K_new @ rot1
    H2 = K_new @ rot2
    rect_l = cv2.warpPerspective(np.asarray(img_l), H1, (width, height), flags=cv2.INTER_LINEAR)
    rect_r = cv2.warpPerspective(np.asarray(img_r), H2, (width, height), flags=cv2.INTER_LINEAR)
    return rect_l, rect_r, H1, H2


# --------------------------------------------------------------------- ex4 / ext1
def _ssd_volume(left, right, max_disparity, block_size):
    """(D, H, W) mean squared difference over the block for d = 0..max_disparity."""
    height, width = left.shape
    costs = np.full((max_disparity + 1, height, width), np.inf)
    for d in range(min(max_disparity, width - 1) + 1):
        squared = (left - _shift_right(right, d)) ** 2
        costs[d] = _box_mean(squared, block_size)
        costs[d, :, :d] = np.inf                 # x - d falls outside the right image
    return costs


def _ncc_volume(left, right, max_disparity, block_size):
    """(D, H, W) negative normalised cross-correlation (lower = better match).

    NCC = (mean(L R) - mean(L) mean(R)) / (std(L) std(R)) over the block; it
    ignores a gain and offset between the views. Flat blocks (std ~ 0) get 0.
    """
    height, width = left.shape
    mean_l = _box_mean(left, block_size)
    std_l = np.sqrt(np.maximum(_box_mean(left * left, block_size) - mean_l ** 2, 0.0))
    costs = np.full((max_disparity + 1, height, width), np.inf)
    for d in range(min(max_disparity, width - 1) + 1):
        shifted = _shift_right(right, d)
        mean_r = _box_mean(shifted, block_size)
        std_r = np.sqrt(np.maximum(_box_mean(shifted * shifted, block_size) - mean_r ** 2, 0.0))
        covariance = _box_mean(left * shifted, block_size) - mean_l * mean_r
        denominator = std_l * std_r
        ncc = np.divide(covariance, denominator, out=np.zeros_like(covariance),
                        where=denominator > 1e-6)
        costs[d] = -ncc
        costs[d, :, :d] = np.inf
    return costs


def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    """Winner-take-all block matching on a rectified pair.

    For every left pixel ``(x, y)`` and every candidate ``d`` in
    ``0..max_disparity`` the block around ``(x, y)`` in the left image is
    compared with the block around ``(x - d, y)`` in the right image; the
    disparity is the ``d`` with the lowest cost. The whole cost volume is built
    one disparity at a time with box filters (no loop over pixels).

    Parameters
    ----------
    left, right : (H, W) uint8 arrays (BGR is converted to grey)
    max_disparity : int
    block_size : int, odd
    cost : {"ssd", "ncc"}

    Returns
    -------
    (H, W) float array of disparities in ``0..max_disparity``
    """
    if cost not in ("ssd", "ncc"):
        raise ValueError(f"unknown cost {cost!r}: use 'ssd' or 'ncc'")
    left, right = _grey_float(left), _grey_float(right)
    volume = (_ssd_volume if cost == "ssd" else _ncc_volume)(
        left, right, int(max_disparity), int(block_size))
    return np.argmin(volume, axis=0).astype(np.float64)


# --------------------------------------------------------------------- ex5
DEFAULT_SMOOTHNESS = 6.0   # grey levels (mean absolute difference) per disparity step


def _sad_volume(left, right, max_disparity, block_size):
    """(W, H, D) mean absolute difference over the block, column-major for the DP.

    Built one disparity at a time as (D, H, W) maps, then transposed once so
    that each column ``x`` is a contiguous (H, D) slab. Where ``x - d < 0`` no
    match exists: the cost is 255, worse than any real one.
    """
    height, width = left.shape
    costs = np.full((max_disparity + 1, height, width), 255.0, dtype=np.float32)
    for d in range(min(max_disparity, width - 1) + 1):
        costs[d, :, d:] = _box_mean(np.abs(left - _shift_right(right, d)), block_size)[:, d:]
    return np.ascontiguousarray(costs.transpose(2, 1, 0))


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline stereo by dynamic programming.

    Along each row the disparities ``d_x`` minimise

        E = sum_x C(x, d_x) + smoothness * sum_x |d_x - d_{x+1}|

    with ``C`` the mean absolute grey-level difference over the block. The
    forward pass computes the best energy ``M(x, d)`` of the row up to ``x``
    ending in ``d``::

        M(x, d) = C(x, d) + min_d' [M(x-1, d') + smoothness |d - d'|]

    The inner minimum (a distance transform under the L1 penalty) splits into
    ``d' <= d`` and ``d' >= d``, which are running minima of ``M - s d'`` and
    ``M + s d'`` along the disparity axis: ``np.minimum.accumulate`` does each
    in one call. Every row is processed at once, so the only Python loop runs
    over the columns. Backtracking then picks, from the right end, the ``d'``
    that achieved each minimum.

    Parameters
    ----------
    left, right : (H, W) uint8 arrays (BGR is converted to grey)
    max_disparity : int
    block_size : int, odd
    smoothness : float, optional
        Penalty per unit of disparity change, in grey levels; ``None`` means
        :data:`DEFAULT_SMOOTHNESS`. 0 gives winner-take-all.

    Returns
    -------
    (H, W) float array of disparities in ``0..max_disparity``
    """
    s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)
    left, right = _grey_float(left), _grey_float(right)
    D = int(max_disparity) + 1
    costs = _sad_volume(left, right, D - 1, int(block_size))      # (W, H, D)
    if s == 0:
        return np.argmin(costs, axis=2).T.astype(np.float64)

    width = costs.shape[0]
    ramp = (s * np.arange(D)).astype(np.float32)
    energy = np.empty_like(costs)                 # M(x, d) for every row at once
    energy[0] = costs[0]
    for x in range(1, width):
        previous = energy[x - 1]
        from_below = np.minimum.accumulate(previous - ramp, axis=1) + ramp
        from_above = np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1)[:, ::-1] - ramp
        best = np.minimum(from_below, from_above)
        energy[x] = costs[x] + best - best.min(axis=1, keepdims=True)   # keep the numbers small

    disparity = np.empty((width, costs.shape[1]), dtype=np.int64)
    disparity[-1] = np.argmin(energy[-1], axis=1)
    candidates = np.arange(D)
    for x in range(width - 1, 0, -1):
        jump = ramp[np.abs(candidates[None, :] - disparity[x][:, None])]
        disparity[x - 1] = np.argmin(energy[x - 1] + jump, axis=1)
    return disparity.T.astype(np.float64)


# --------------------------------------------------------------------- ex6
def gray_code_patterns(width, n_bits):
    """Gray-code stripe patterns, one row per bit, most significant first.

    Column ``u`` belongs to stripe ``k = floor(u 2^n / width)``; its Gray code
    ``g = k XOR (k >> 1)`` changes by a single bit between neighbouring stripes,
    so a decoding error at a stripe edge is off by one stripe at most.

    Returns
    -------
    (n_bits, width) uint8 array of 0 and 255
    """
    u = np.arange(int(width))
    k = (u * (1 << int(n_bits))) // int(width)
    gray = k ^ (k >> 1)
    shifts = np.arange(int(n_bits) - 1, -1, -1)[:, None]
    return (((gray[None, :] >> shifts) & 1) * 255).astype(np.uint8)


def simulate_structured_light(depth, f, baseline, n_bits):
    """What the camera sees while the projector shows each Gray-code pattern.

    The projector is rectified with the camera, ``baseline`` to its right, so
    camera pixel ``(u, v)`` at depth ``Z`` is lit by projector column
    ``round(u - f b / Z)`` (the disparity is ``f b / Z``).

    Returns
    -------
    (n_bits, H, W) uint8 array; 0 where ``Z <= 0`` or the column is off the projector
    """
    depth = np.asarray(depth, dtype=np.float64)
    height, width = depth.shape
    patterns = gray_code_patterns(width, n_bits)
    valid = np.isfinite(depth) & (depth > 0)
    u = np.broadcast_to(np.arange(width, dtype=np.float64), depth.shape)
    disparity = np.divide(float(f) * float(baseline), depth, out=np.zeros_like(depth), where=valid)
    column = np.floor(u - disparity + 0.5).astype(np.int64)
    lit = valid & (column >= 0) & (column < width)
    images = np.zeros((int(n_bits), height, width), dtype=np.uint8)
    images[:, lit] = patterns[:, column[lit]]
    return images


def depth_from_structured_light(images, f, baseline):
    """Decode the Gray code at every pixel and triangulate with the projector.

    Each image is thresholded at mid-grey; the bits (most significant first)
    form the Gray code ``g``, converted to the stripe index ``k`` by
    ``b_0 = g_0, b_i = b_{i-1} XOR g_i``. The stripe's centre column
    ``(k + 0.5) W / 2^n - 0.5`` is the projector column, so the disparity is
    ``u - column`` and ``Z = f b / disparity``.

    Returns
    -------
    (H, W) float array; 0 where the pixel is black in every image or the
    disparity is not positive
    """
    images = np.asarray(images)
    n_bits, height, width = images.shape
    bits = images > 127
    binary = np.zeros((height, width), dtype=np.int64)
    bit = np.zeros((height, width), dtype=bool)
    for i in range(n_bits):
        bit = bit ^ bits[i]
        binary = (binary << 1) | bit
    column = (binary + 0.5) * width / (1 << n_bits) - 0.5
    disparity = np.arange(width)[None, :] - column
    decodable = bits.any(axis=0)
    return np.where(decodable, depth_from_disparity(disparity, f, baseline), 0.0)
