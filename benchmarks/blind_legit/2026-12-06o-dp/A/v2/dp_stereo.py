"""Lab 12, Exercise 5: scanline stereo by dynamic programming (SAD data cost)."""

import numpy as np
from scipy.ndimage import uniform_filter


def _to_grey(img):
    img = np.asarray(img, dtype=np.float64)
    if img.ndim == 3:
        # BGR -> grey with the usual luma weights
        img = 0.114 * img[..., 0] + 0.587 * img[..., 1] + 0.299 * img[..., 2]
    return img


def _sad_cost_volume(left, right, max_disparity, block_size):
    """C[x, y, d] = sum over a block_size x block_size window of |L(x) - R(x - d)|.

    Where x - d falls off the right image the right image's first column is
    repeated (edge padding), so every (x, d) has a finite cost.
    """
    H, W = left.shape
    D = max_disparity + 1
    area = block_size * block_size
    padded = np.pad(right, ((0, 0), (D, 0)), mode="edge")
    cost = np.empty((W, H, D))
    for d in range(D):
        shifted = padded[:, D - d:D - d + W]  # R(x - d)
        ad = np.abs(left - shifted)
        cost[:, :, d] = (uniform_filter(ad, size=block_size, mode="nearest") * area).T
    return cost


# Default penalty per pixel of disparity change, in SAD units (sum over the
# window of absolute grey-level differences).  Tuned on Middlebury
# "motorcycle" and synthetic planes (see README): 6 grey levels per window
# pixel, i.e. 150 for the default 5x5 block.
_SMOOTHNESS_PER_WINDOW_PIXEL = 6.0


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline stereo by dynamic programming.

    Minimises, independently on every row,
        E = sum_x C(x, d_x) + smoothness * sum_x |d_x - d_(x+1)|
    with C the SAD (sum of absolute differences) over a block_size x block_size
    window.  ``smoothness=None`` uses the default (6 * block_size**2, i.e. 150 for
    a 5x5 block); ``smoothness=0`` gives winner-take-all SAD block matching.

    Returns an (H, W) float array of disparities in 0..max_disparity.
    """
    L = _to_grey(left)
    R = _to_grey(right)
    H, W = L.shape
    max_disparity = int(max_disparity)
    D = max_disparity + 1
    if smoothness is None:
        smoothness = _SMOOTHNESS_PER_WINDOW_PIXEL * block_size * block_size
    s = float(smoothness)

    cost = _sad_cost_volume(L, R, max_disparity, block_size)  # (W, H, D)

    if s == 0:
        return np.argmin(cost, axis=2).T.astype(np.float64)

    # forward pass; min_d' [M(x-1, d') + s |d - d'|] is an L1 distance
    # transform, computed with one forward and one backward sweep over d.
    M = np.empty_like(cost)
    M[0] = cost[0]
    for x in range(1, W):
        m = M[x - 1].copy()
        for d in range(1, D):
            np.minimum(m[:, d], m[:, d - 1] + s, out=m[:, d])
        for d in range(D - 2, -1, -1):
            np.minimum(m[:, d], m[:, d + 1] + s, out=m[:, d])
        M[x] = cost[x] + m
        M[x] -= M[x].min(axis=1, keepdims=True)

    # backtrack: d_x = argmin_d' M(x, d') + s |d_(x+1) - d'|
    dd = np.arange(D)
    disp = np.zeros((H, W), dtype=np.int64)
    disp[:, W - 1] = np.argmin(M[W - 1], axis=1)
    for x in range(W - 2, -1, -1):
        nxt = disp[:, x + 1]
        disp[:, x] = np.argmin(M[x] + s * np.abs(dd[None, :] - nxt[:, None]), axis=1)
    return disp.astype(np.float64)
