# A block matcher as course code written for OpenCV 3/4 (2018) has it: the costs of every
# disparity at a pixel in one 1-D vector, the best found with cv2.minMaxLoc. OpenCV 4 reads a
# 1-D array as a column, so the index is the location's y (min_loc[1]); OpenCV 5 reads it as a
# row, the index is x and min_loc[1] is always 0. Appended to the reference module (its
# other exercises): tests/test_opencv_versions.py grades it under the installed OpenCV.
import cv2
import numpy as np


def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    if left.ndim == 3:
        left = cv2.cvtColor(left, cv2.COLOR_BGR2GRAY)
        right = cv2.cvtColor(right, cv2.COLOR_BGR2GRAY)
    if cost not in ("ssd", "ncc"):
        raise ValueError("cost must be 'ssd' or 'ncc'")
    L = left.astype(np.float64)
    R = right.astype(np.float64)
    h, w = L.shape
    k = (block_size, block_size)

    def mean(a):
        return cv2.blur(a, k, borderType=cv2.BORDER_REFLECT)

    mean_l = mean(L)
    std_l = np.sqrt(np.maximum(mean(L * L) - mean_l ** 2, 0))
    volume = np.full((h, w, max_disparity + 1), np.inf)
    for d in range(min(max_disparity, w - 1) + 1):
        shifted = np.empty_like(R)
        shifted[:, d:] = R[:, :w - d]
        shifted[:, :d] = R[:, :1]
        if cost == "ssd":
            c = mean((L - shifted) ** 2)
        else:
            mean_r = mean(shifted)
            std_r = np.sqrt(np.maximum(mean(shifted * shifted) - mean_r ** 2, 0))
            cov = mean(L * shifted) - mean_l * mean_r
            den = std_l * std_r
            c = -np.divide(cov, den, out=np.zeros_like(cov), where=den > 1e-6)
        c[:, :d] = np.inf
        volume[:, :, d] = c
    disparity = np.zeros((h, w))
    for y in range(h):
        for x in range(w):
            min_val, max_val, min_loc, max_loc = cv2.minMaxLoc(volume[y, x])
            disparity[y, x] = min_loc[1]
    return disparity
