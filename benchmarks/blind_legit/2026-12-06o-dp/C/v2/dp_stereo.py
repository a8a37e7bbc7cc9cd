"""Lab 12, exercise 5: scanline dynamic-programming stereo (v2: SSD data cost)."""

import cv2
import numpy as np

# Data cost: SSD over the block_size x block_size window on images scaled to
# [0, 1] (so 0 .. block_size**2). Default smoothness tuned on skimage's
# stereo_motorcycle and synthetic textured planes (see README).
DEFAULT_SMOOTHNESS = 0.01


def _grey01(img):
    img = np.asarray(img)
    if img.ndim == 3:
        img = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    return img.astype(np.float64) / 255.0


def _cost_volume(left, right, max_disparity, block_size):
    """(H, W, D) SSD over the block; x - d < 0 gets the worst possible SSD."""
    L = _grey01(left)
    R = _grey01(right)
    H, W = L.shape
    D = max_disparity + 1
    worst = float(block_size * block_size)
    cost = np.full((H, W, D), worst)
    for d in range(min(D, W)):
        diff = np.zeros_like(L)
        diff[:, d:] = (L[:, d:] - R[:, :W - d]) ** 2
        ssd = cv2.boxFilter(diff, -1, (block_size, block_size), normalize=False,
                            borderType=cv2.BORDER_REFLECT)
        ssd[:, :d] = worst
        cost[:, :, d] = ssd
    return cost


def _dp(cost, smoothness):
    """Minimise sum C(x, d_x) + smoothness * |d_x - d_(x+1)| on every row at once."""
    H, W, D = cost.shape
    dd = np.arange(D)
    jump = smoothness * np.abs(dd[:, None] - dd[None, :])  # [d, d']
    back = np.empty((H, W, D), dtype=np.int16)
    M = cost[:, 0, :].copy()
    rows = np.arange(H)
    for x in range(1, W):
        tot = M[:, None, :] + jump[None, :, :]  # (H, d, d')
        arg = np.argmin(tot, axis=2)
        back[:, x, :] = arg
        M = cost[:, x, :] + np.take_along_axis(tot, arg[:, :, None], axis=2)[:, :, 0]
    disp = np.empty((H, W), dtype=np.int64)
    disp[:, W - 1] = np.argmin(M, axis=1)
    for x in range(W - 1, 0, -1):
        disp[:, x - 1] = back[rows, x, disp[:, x]]
    return disp


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline stereo by dynamic programming with an SSD block cost.

    C(x, d) = sum over the block_size x block_size window of
    (L(x, y) - R(x - d, y))**2 with both images scaled to [0, 1]
    (range 0 .. block_size**2; x - d < 0 gets the worst cost). On every row
    the DP minimises sum_x C(x, d_x) + smoothness * sum_x |d_x - d_(x+1)|.

    smoothness=None uses DEFAULT_SMOOTHNESS (in SSD units);
    smoothness=0 is winner-take-all. Returns an (H, W) float array in
    0..max_disparity.
    """
    if smoothness is None:
        smoothness = DEFAULT_SMOOTHNESS
    max_disparity = int(max_disparity)
    cost = _cost_volume(left, right, max_disparity, int(block_size))
    if smoothness == 0:
        return np.argmin(cost, axis=2).astype(np.float64)
    return _dp(cost, float(smoothness)).astype(np.float64)
