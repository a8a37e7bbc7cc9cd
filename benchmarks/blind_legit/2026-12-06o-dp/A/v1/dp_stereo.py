"""Lab 12, Exercise 5: scanline stereo by dynamic programming (SSD data cost)."""

import cv2
import numpy as np


def _to_grey(img):
    img = np.asarray(img)
    if img.ndim == 3:
        img = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    return img.astype(np.float64)


def _ssd_cost_volume(left, right, max_disparity, block_size):
    """C[d, y, x] = sum over a block_size x block_size window of (L(x) - R(x - d))^2.

    Columns x < d have no partner in the right image: their cost is +inf, so a
    pixel x can never take a disparity d > x.
    """
    H, W = left.shape
    D = max_disparity + 1
    cost = np.full((D, H, W), np.inf)
    for d in range(D):
        if d >= W:
            break
        diff = np.zeros((H, W))
        diff[:, d:] = (left[:, d:] - right[:, :W - d]) ** 2
        # sum (not mean) over the window; border pixels use a reflected window
        ssd = cv2.boxFilter(diff, -1, (block_size, block_size), normalize=False,
                            borderType=cv2.BORDER_REFLECT)
        cost[d, :, d:] = ssd[:, d:]
    return cost


# Default penalty per pixel of disparity change, in SSD units (sum over a 5x5
# window of squared grey-level differences, 0..255).  A mismatch of ~10 grey
# levels per pixel over a 5x5 block costs 25 * 100 = 2500; the default below
# (tuned on Middlebury "motorcycle" and synthetic planes, see README) scales
# with the window area, i.e. it is 40 per window pixel (1000 for 5x5).
_SMOOTHNESS_PER_WINDOW_PIXEL = 40.0


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline stereo by dynamic programming.

    Minimises, independently on every row,
        E = sum_x C(x, d_x) + smoothness * sum_x |d_x - d_(x+1)|
    with C the SSD (sum of squared differences) over a block_size x block_size
    window.  ``smoothness=None`` uses the default (40 * block_size**2, i.e. 1000
    for a 5x5 block); ``smoothness=0`` gives winner-take-all SSD block matching.

    Returns an (H, W) float array of disparities in 0..max_disparity.
    """
    L = _to_grey(left)
    R = _to_grey(right)
    H, W = L.shape
    max_disparity = int(max_disparity)
    D = max_disparity + 1
    if smoothness is None:
        smoothness = _SMOOTHNESS_PER_WINDOW_PIXEL * block_size * block_size
    smoothness = float(smoothness)

    cost = _ssd_cost_volume(L, R, max_disparity, block_size)  # (D, H, W)

    if smoothness == 0:
        return np.argmin(cost, axis=0).astype(np.float64)

    dd = np.arange(D)
    penalty = smoothness * np.abs(dd[:, None] - dd[None, :])  # [d, d']

    # forward pass: M(x, d) = C(x, d) + min_d' [M(x-1, d') + s |d - d'|]
    back = np.zeros((W, H, D), dtype=np.int16)
    M = cost[:, :, 0].T.copy()  # (H, D)
    for x in range(1, W):
        # (H, d, d') array of M(x-1, d') + s |d - d'|
        tot = M[:, None, :] + penalty[None, :, :]
        arg = np.argmin(tot, axis=2)
        best = np.take_along_axis(tot, arg[:, :, None], axis=2)[:, :, 0]
        back[x] = arg
        M = cost[:, :, x].T + best
        M -= M.min(axis=1, keepdims=True)  # keep the numbers small

    # backtrack from the best disparity at the last column
    disp = np.zeros((H, W), dtype=np.int64)
    disp[:, W - 1] = np.argmin(M, axis=1)
    rows = np.arange(H)
    for x in range(W - 1, 0, -1):
        disp[:, x - 1] = back[x, rows, disp[:, x]]
    return disp.astype(np.float64)
