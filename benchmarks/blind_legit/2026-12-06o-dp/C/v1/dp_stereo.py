"""Lab 12, exercise 5: scanline dynamic-programming stereo (v1: ZNCC data cost)."""

import cv2
import numpy as np

# Data cost: 1 - ZNCC over the block, in [0, 2] (0 = perfect match, 1 = uncorrelated).
# Default smoothness tuned on skimage's stereo_motorcycle and synthetic textured
# planes (see README): 0.3 cost units per pixel of disparity change.
DEFAULT_SMOOTHNESS = 0.3


def _grey(img):
    img = np.asarray(img)
    if img.ndim == 3:
        img = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    return img.astype(np.float64)


def _cost_volume(left, right, max_disparity, block_size):
    """(H, W, D) cost 1 - ZNCC over a block_size x block_size window."""
    L = _grey(left)
    R = _grey(right)
    H, W = L.shape
    D = max_disparity + 1
    k = (block_size, block_size)
    box = lambda a: cv2.blur(a, k, borderType=cv2.BORDER_REFLECT)
    mu_l = box(L)
    var_l = np.maximum(box(L * L) - mu_l ** 2, 0.0)
    mu_r = box(R)
    var_r = np.maximum(box(R * R) - mu_r ** 2, 0.0)
    eps = 1e-2  # grey levels^2: keeps flat blocks from dividing by zero
    cost = np.full((H, W, D), 2.0)  # columns x - d < 0 have no partner: worst cost
    for d in range(D):
        if d >= W:
            break
        Rs = np.empty_like(R)
        Rs[:, d:] = R[:, :W - d]
        Rs[:, :d] = R[:, :1]  # filler, overwritten by the invalid cost below
        mu_rs = np.empty_like(mu_r)
        mu_rs[:, d:] = mu_r[:, :W - d]
        mu_rs[:, :d] = mu_r[:, :1]
        var_rs = np.empty_like(var_r)
        var_rs[:, d:] = var_r[:, :W - d]
        var_rs[:, :d] = var_r[:, :1]
        cov = box(L * Rs) - mu_l * mu_rs
        ncc = cov / np.sqrt((var_l + eps) * (var_rs + eps))
        c = 1.0 - np.clip(ncc, -1.0, 1.0)
        c[:, :d] = 2.0
        cost[:, :, d] = c
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
    """Scanline stereo by dynamic programming with a 1 - ZNCC block cost.

    C(x, d) = 1 - ZNCC between the block_size x block_size block around (x, y)
    in the left image and the block around (x - d, y) in the right image
    (range [0, 2]; x - d < 0 gets the worst cost, 2). On every row the DP
    minimises sum_x C(x, d_x) + smoothness * sum_x |d_x - d_(x+1)|.

    smoothness=None uses DEFAULT_SMOOTHNESS (0.3, in 1 - NCC units);
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
