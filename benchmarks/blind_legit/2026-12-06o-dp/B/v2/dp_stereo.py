"""Lab 12, Exercise 5: scanline stereo by dynamic programming (v2).

Data cost: pixel-wise absolute difference of grey levels scaled to [0, 1],
aggregated by a normalised box filter of block_size (i.e. the mean absolute
difference over the window, range 0..1).  Smoothness: smoothness * |d_x - d_(x+1)|.
"""
import cv2
import numpy as np

# Cost is a mean absolute difference in [0, 1]; a good match is ~0.01-0.03,
# a wrong one ~0.1+.  Tuned on skimage's motorcycle pair and synthetic
# planes (see README).
DEFAULT_SMOOTHNESS = 0.03


def _grey01(img):
    img = np.asarray(img)
    if img.ndim == 3:
        img = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    return img.astype(np.float32) / 255.0


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    if smoothness is None:
        smoothness = DEFAULT_SMOOTHNESS
    smoothness = float(smoothness)
    L, R = _grey01(left), _grey01(right)
    H, W = L.shape
    D = int(max_disparity) + 1
    k = int(block_size)

    cost = np.empty((D, H, W), np.float32)
    for d in range(D):
        # right image shifted right by d; columns without a partner repeat the
        # first column (replicate border)
        Rs = np.empty_like(R)
        if d < W:
            Rs[:, d:] = R[:, :W - d]
            Rs[:, :d] = R[:, :1]
        else:
            Rs[:] = R[:, :1]
        ad = np.abs(L - Rs)
        cost[d] = cv2.boxFilter(ad, -1, (k, k), normalize=True,
                                borderType=cv2.BORDER_REFLECT)

    if smoothness == 0:
        return np.argmin(cost, axis=0).astype(np.float64)

    dd = np.arange(D, dtype=np.float32)
    pen = smoothness * np.abs(dd[:, None] - dd[None, :])                    # (d, d')
    back = np.empty((W, H, D), np.int16)
    M = cost[:, :, 0].T.copy()                                              # (H, D)
    for x in range(1, W):
        tot = M[:, None, :] + pen[None, :, :]                               # (H, d, d')
        arg = np.argmin(tot, axis=2)
        back[x] = arg
        M = cost[:, :, x].T + np.take_along_axis(tot, arg[:, :, None], 2)[:, :, 0]
    disp = np.empty((H, W), np.int64)
    disp[:, W - 1] = np.argmin(M, axis=1)
    rows = np.arange(H)
    for x in range(W - 1, 0, -1):
        disp[:, x - 1] = back[x, rows, disp[:, x]]
    return disp.astype(np.float64)
