"""Lab 12 - stereo.

Compact versions: triangulation reused from lab 11, OpenCV for rectification
and for SSD block matching (cv2.StereoBM, the lab sheet's recipe), a box-filter
cost volume for NCC, and a vectorised scanline DP.
"""

import cv2
import numpy as np

from lab11_two_view import triangulate  # noqa: F401  (ex1: same function as lab 11)


# --------------------------------------------------------------------- ex2
def disparity_from_matches(xl, xr):
    xl, xr = np.asarray(xl, float), np.asarray(xr, float)
    if xl.ndim == 2:
        xl, xr = xl[:, 0], xr[:, 0]
    return xl - xr


def depth_from_disparity(disparity, f, baseline):
    d = np.asarray(disparity, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(d > 0, f * baseline / d, 0.0)


# --------------------------------------------------------------------- ex3
def rectify(img_l, img_r, K1, K2, R, T):
    h, w = img_l.shape[:2]
    K1, K2 = np.asarray(K1, float), np.asarray(K2, float)
    R1, R2, P1, P2, *_ = cv2.stereoRectify(K1, None, K2, None, (w, h), np.asarray(R, float),
                                           np.asarray(T, float).reshape(3, 1),
                                           flags=cv2.CALIB_ZERO_DISPARITY)
    H1 = P1[:, :3] @ R1 @ np.linalg.inv(K1)
    H2 = P2[:, :3] @ R2 @ np.linalg.inv(K2)
    return (cv2.warpPerspective(img_l, H1, (w, h)), cv2.warpPerspective(img_r, H2, (w, h)), H1, H2)


# --------------------------------------------------------------------- ex4
def _cost_volume(left, right, D, block, cost):
    """(D+1, H, W) costs, lower is better; inf where x - d leaves the right image."""
    L, Rt = left.astype(np.float32), right.astype(np.float32)
    k = (block, block)
    box = lambda a: cv2.blur(a, k, borderType=cv2.BORDER_REFLECT)  # noqa: E731
    h, w = L.shape
    vol = np.full((D + 1, h, w), np.inf, np.float32)
    if cost == "ncc":
        mL = box(L)
        sL = np.sqrt(np.maximum(box(L * L) - mL ** 2, 0))
    for d in range(min(D, w - 1) + 1):
        Rs = np.zeros_like(Rt)
        Rs[:, d:] = Rt[:, :w - d]
        if cost == "ssd":
            c = box((L - Rs) ** 2)
        else:
            mR = box(Rs)
            sR = np.sqrt(np.maximum(box(Rs * Rs) - mR ** 2, 0))
            c = -(box(L * Rs) - mL * mR) / (sL * sR + 1e-6)
        c[:, :d] = np.inf
        vol[d] = c
    return vol


def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    n = 16 * -(-(max_disparity + 1) // 16)
    if cost == "ssd" and 5 <= block_size <= min(left.shape) and n < left.shape[1]:
        bm = cv2.StereoBM_create(numDisparities=n, blockSize=block_size)
        bm.setUniquenessRatio(0)  # tried 0..15 on textured pairs: rejecting ambiguous pixels only adds holes
        bm.setPreFilterCap(63)
        d = bm.compute(np.ascontiguousarray(left), np.ascontiguousarray(right)) / 16.0
        d[(d <= 0) | (d > max_disparity)] = 0
        return d
    if cost not in ("ssd", "ncc"):
        raise ValueError(cost)
    # own matcher (NCC, or sizes StereoBM cannot handle)
    return np.argmin(_cost_volume(left, right, max_disparity, block_size, cost), 0).astype(float)


# --------------------------------------------------------------------- ex5
DEFAULT_SMOOTHNESS = 4.0  # in grey levels: the cost is the mean absolute difference per block


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    lam = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)
    L, Rt = left.astype(np.float32), right.astype(np.float32)
    h, w = L.shape
    D = max_disparity + 1
    C = np.full((w, h, D), 1e9, np.float32)  # column-major so C[x] is (H, D)
    for d in range(min(D, w)):
        sad = cv2.blur(np.abs(L[:, d:] - Rt[:, :w - d]), (block_size, block_size),
                       borderType=cv2.BORDER_REFLECT)
        C[d:, :, d] = sad.T
    pen = lam * np.abs(np.arange(D)[:, None] - np.arange(D)[None, :])  # (d, d')
    M = C[0].copy()
    back = np.zeros((w, h, D), np.int32)
    for x in range(1, w):
        tot = M[:, None, :] + pen  # (H, d, d')
        back[x] = tot.argmin(2)
        M = C[x] + np.take_along_axis(tot, back[x][:, :, None], 2)[:, :, 0]
        M -= M.min(1, keepdims=True)  # keep float32 precision along the row
    disp = np.empty((h, w))
    d = M.argmin(1)
    for x in range(w - 1, -1, -1):
        disp[:, x] = d
        d = back[x, np.arange(h), d]
    return disp


# --------------------------------------------------------------------- ex6
def gray_code_patterns(width, n_bits):
    k = (np.arange(width) * 2 ** n_bits) // width
    g = k ^ (k >> 1)
    return (((g[None] >> np.arange(n_bits - 1, -1, -1)[:, None]) & 1) * 255).astype(np.uint8)


def simulate_structured_light(depth, f, baseline, n_bits):
    Z = np.asarray(depth, float)
    h, w = Z.shape
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.rint(np.arange(w)[None] - f * baseline / Z)
    ok = (Z > 0) & (p >= 0) & (p < w)
    pats = gray_code_patterns(w, n_bits)
    return np.where(ok, pats[:, np.where(ok, p, 0).astype(int)], 0).astype(np.uint8)


def depth_from_structured_light(images, f, baseline):
    bits = np.asarray(images) > 127
    n, h, w = bits.shape
    k = np.cumsum(bits, 0) % 2  # b_i = g_0 xor ... xor g_i
    k = (k * (1 << np.arange(n - 1, -1, -1))[:, None, None]).sum(0)
    disp = np.arange(w)[None] - ((k + 0.5) * w / 2 ** n - 0.5)
    Z = depth_from_disparity(disp, f, baseline)
    return np.where(bits.any(0), Z, 0.0)
