"""Lab 12, Exercise 5: scanline stereo by dynamic programming (v1).

Data cost: mean of squared differences (MSD) of grey levels (0..255 scale)
over a block_size x block_size window. Smoothness: smoothness * |d_x - d_(x+1)|.
"""
import cv2
import numpy as np

# MSD is in grey-level^2 units (0..65025); a typical textured match costs
# tens to a few hundred, a wrong one hundreds to thousands.  Tuned on
# skimage's motorcycle pair and synthetic planes (see README).
DEFAULT_SMOOTHNESS = 50.0


def _grey(img):
    img = np.asarray(img)
    if img.ndim == 3:
        img = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    return img.astype(np.float32)


def _cost_volume(L, R, max_disparity, block_size):
    H, W = L.shape
    D = max_disparity + 1
    cost = np.empty((D, H, W), np.float32)
    for d in range(D):
        sq = np.zeros((H, W), np.float32)
        if d < W:
            sq[:, d:] = (L[:, d:] - R[:, :W - d]) ** 2
        sq = cv2.blur(sq, (block_size, block_size), borderType=cv2.BORDER_REFLECT)
        cost[d] = sq
    # x - d outside the right image: no partner, forbid (large finite cost)
    big = np.float32(1e6)
    for d in range(1, D):
        cost[d, :, :min(d, W)] = big
    return cost


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    if smoothness is None:
        smoothness = DEFAULT_SMOOTHNESS
    smoothness = float(smoothness)
    L, R = _grey(left), _grey(right)
    H, W = L.shape
    D = int(max_disparity) + 1
    cost = _cost_volume(L, R, int(max_disparity), int(block_size))   # (D, H, W)

    if smoothness == 0:
        return np.argmin(cost, axis=0).astype(np.float64)

    dd = np.arange(D)
    pen = smoothness * np.abs(dd[:, None] - dd[None, :]).astype(np.float32)  # (d, d')
    back = np.empty((W, H, D), np.int16)
    M = cost[:, :, 0].T.copy()                                              # (H, D)
    for x in range(1, W):
        tot = M[:, None, :] + pen[None, :, :]                               # (H, d, d')
        arg = np.argmin(tot, axis=2)                                        # (H, d)
        back[x] = arg
        M = cost[:, :, x].T + np.take_along_axis(tot, arg[:, :, None], 2)[:, :, 0]
    disp = np.empty((H, W), np.int64)
    disp[:, W - 1] = np.argmin(M, axis=1)
    rows = np.arange(H)
    for x in range(W - 1, 0, -1):
        disp[:, x - 1] = back[x, rows, disp[:, x]]
    return disp.astype(np.float64)
