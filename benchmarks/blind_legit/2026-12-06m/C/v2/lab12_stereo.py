"""Lab 12 - stereo (OpenCV where the lab sheet allows it, float32 cost volumes).

Disparity maps are (H, W) float arrays indexed like the left image, with
d = x_l - x_r; invalid pixels are 0.
"""

import cv2
import numpy as np

# ex1: the triangulation written in lab 11 (same folder)
from lab11_two_view import triangulate  # noqa: F401


# --------------------------------------------------------------------- ex2
def disparity_from_matches(xl, xr):
    """d = x_l - x_r; for (N, 2) points only the x coordinates count."""
    def xs(a):
        a = np.asarray(a, dtype=np.float64)
        return a[..., 0] if a.ndim == 2 else a
    return np.subtract(xs(xl), xs(xr))


def depth_from_disparity(disparity, f, baseline):
    """Z = f * baseline / d, 0 where d <= 0 or NaN."""
    d = np.asarray(disparity, dtype=np.float64)
    depth = np.zeros_like(d)
    np.divide(f * baseline, d, out=depth, where=np.nan_to_num(d, nan=0.0) > 0)
    return depth


# --------------------------------------------------------------------- ex3
def rectify(img_l, img_r, K1, K2, R, T):
    """cv2.stereoRectify (zero disparity at infinity) + cv2.warpPerspective.

    I keep OpenCV's default scaling (alpha = -1): alpha = 0 zooms in until no
    black border is left, which can throw away most of a strongly rotated image.
    """
    h, w = img_l.shape[:2]
    K1 = np.asarray(K1, dtype=np.float64)
    K2 = np.asarray(K2, dtype=np.float64)
    R = np.asarray(R, dtype=np.float64)
    T = np.asarray(T, dtype=np.float64).reshape(3, 1)
    R1, R2, P1, P2, _, _, _ = cv2.stereoRectify(
        K1, np.zeros(5), K2, np.zeros(5), (w, h), R, T,
        flags=cv2.CALIB_ZERO_DISPARITY)
    H1 = P1[:, :3] @ R1 @ np.linalg.inv(K1)
    H2 = P2[:, :3] @ R2 @ np.linalg.inv(K2)
    rect_l = cv2.warpPerspective(img_l, H1, (w, h))
    rect_r = cv2.warpPerspective(img_r, H2, (w, h))
    return rect_l, rect_r, H1, H2


# --------------------------------------------------------------------- ex4 / ext1
def _shifted(right, d):
    """Right image moved d columns to the right (column x holds right[:, x - d]);
    the d columns that come in from the left border repeat the first column."""
    if d == 0:
        return right
    return np.hstack([np.repeat(right[:, :1], d, axis=1), right[:, :-d]])


def _ssd_own(left, right, max_disparity, block_size):
    """Own SSD matcher (used when the block is too small for cv2.StereoBM)."""
    L = left.astype(np.float32)
    Rr = right.astype(np.float32)
    vol = np.stack([
        cv2.boxFilter((L - _shifted(Rr, d)) ** 2, -1, (block_size, block_size),
                      normalize=False)
        for d in range(max_disparity + 1)
    ])
    return np.argmin(vol, axis=0).astype(np.float64)


def _ncc(left, right, max_disparity, block_size):
    """Zero-mean NCC with box sums: sum(l r) - n mu_l mu_r over sqrt of the variances."""
    k = (block_size, block_size)
    n = float(block_size * block_size)
    L = left.astype(np.float32)
    Rr = right.astype(np.float32)
    s_l = cv2.boxFilter(L, -1, k, normalize=False)
    ss_l = cv2.boxFilter(L * L, -1, k, normalize=False)
    var_l = ss_l - s_l * s_l / n
    best = np.full(L.shape, -np.inf, dtype=np.float32)
    disp = np.zeros(L.shape, dtype=np.float64)
    for d in range(max_disparity + 1):
        Rs = _shifted(Rr, d)
        s_r = cv2.boxFilter(Rs, -1, k, normalize=False)
        ss_r = cv2.boxFilter(Rs * Rs, -1, k, normalize=False)
        s_lr = cv2.boxFilter(L * Rs, -1, k, normalize=False)
        var_r = ss_r - s_r * s_r / n
        num = s_lr - s_l * s_r / n
        den = np.sqrt(np.clip(var_l, 0, None) * np.clip(var_r, 0, None))
        score = np.where(den > 1e-3, num / np.maximum(den, 1e-3), -np.inf).astype(np.float32)
        better = score > best
        best[better] = score[better]
        disp[better] = d
    return disp


def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    """SSD: the lab sheet's cv2.StereoBM; NCC (extension): my own matcher."""
    max_disparity = int(max_disparity)
    if cost == "ncc":
        return _ncc(left, right, max_disparity, block_size)
    if cost != "ssd":
        raise ValueError("cost must be 'ssd' or 'ncc'")
    if block_size < 5:
        # StereoBM only accepts odd blocks from 5 up
        return _ssd_own(left, right, max_disparity, block_size)
    n = 16 * -(-(max_disparity + 1) // 16)       # multiple of 16
    bm = cv2.StereoBM_create(numDisparities=n, blockSize=block_size)
    d = bm.compute(left, right).astype(np.float64) / 16.0
    d[(d <= 0) | (d > max_disparity)] = 0.0
    return d


# --------------------------------------------------------------------- ex5
def _min_plus_l1(M, lam):
    """out[d] = min_d' M[d'] + lam |d - d'| for every row of M (..., D).

    The lower envelope of cones of slope lam, by one forward and one backward
    sweep over d (the 1-D distance transform), instead of the D x D minimum.
    """
    out = M.copy()
    D = M.shape[-1]
    for d in range(1, D):
        np.minimum(out[..., d], out[..., d - 1] + lam, out=out[..., d])
    for d in range(D - 2, -1, -1):
        np.minimum(out[..., d], out[..., d + 1] + lam, out=out[..., d])
    return out


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline DP with a sum-of-absolute-differences data term (float32).

    Cost C(x, d) = mean |L - R| over the block (grey levels). Smoothness
    penalty smoothness * |d_x - d_(x+1)|; my default is 10 grey levels per
    pixel of disparity change.
    """
    lam = 10.0 if smoothness is None else float(smoothness)
    max_disparity = int(max_disparity)
    D = max_disparity + 1
    L = left.astype(np.float32)
    Rr = right.astype(np.float32)
    h, w = L.shape

    # cost volume (H, W, D)
    C = np.empty((h, w, D), dtype=np.float32)
    for d in range(D):
        C[:, :, d] = cv2.blur(np.abs(L - _shifted(Rr, d)), (block_size, block_size))

    # forward pass: M(x, d) = C(x, d) + min_d' [M(x-1, d') + lam |d - d'|]
    M = C[:, 0, :].copy()
    Ms = np.empty((w, h, D), dtype=np.float32)
    Ms[0] = M
    for x in range(1, w):
        M = C[:, x, :] + _min_plus_l1(M, lam)
        Ms[x] = M

    # backtrack: at column x choose the d' minimising M(x, d') + lam |d' - d_(x+1)|
    disp = np.zeros((h, w), dtype=np.float64)
    rows = np.arange(h)
    d_next = np.argmin(Ms[w - 1], axis=1)
    disp[:, w - 1] = d_next
    dd = np.arange(D)[None, :]
    for x in range(w - 2, -1, -1):
        cand = Ms[x] + lam * np.abs(dd - d_next[:, None])
        d_next = np.argmin(cand, axis=1)
        disp[rows, x] = d_next
    return disp


# --------------------------------------------------------------------- ex6
def gray_code_patterns(width, n_bits):
    """Gray-code stripes, row 0 the most significant bit, 0 / 255."""
    k = (np.arange(width, dtype=np.int64) << n_bits) // width
    g = k ^ (k >> 1)
    shifts = np.arange(n_bits - 1, -1, -1, dtype=np.int64)
    return (((g[None, :] >> shifts[:, None]) & 1) * 255).astype(np.uint8)


def simulate_structured_light(depth, f, baseline, n_bits):
    """What the camera sees for each pattern (projector baseline to the right)."""
    Z = np.asarray(depth, dtype=np.float64)
    h, w = Z.shape
    pats = gray_code_patterns(w, n_bits)
    u = np.broadcast_to(np.arange(w, dtype=np.float64), (h, w))
    with np.errstate(divide="ignore", invalid="ignore"):
        col = np.floor(u - f * baseline / Z + 0.5)
    ok = (Z > 0) & np.isfinite(col) & (col >= 0) & (col <= w - 1)
    p = np.where(ok, col, 0).astype(np.int64)
    imgs = pats[:, p]                    # (n_bits, H, W)
    imgs[:, ~ok] = 0
    return imgs


def depth_from_structured_light(images, f, baseline):
    """Decode (cumulative XOR turns Gray into binary), stripe centre, Z = f b / d."""
    images = np.asarray(images)
    n_bits, h, w = images.shape
    g = (images > 127).astype(np.int64)
    b = np.bitwise_xor.accumulate(g, axis=0)          # b_i = b_(i-1) xor g_i
    weights = 2 ** np.arange(n_bits - 1, -1, -1, dtype=np.int64)
    k = np.tensordot(weights, b, axes=1)              # (H, W) stripe index
    proj_col = (k + 0.5) * w / float(2 ** n_bits) - 0.5
    disp = np.arange(w)[None, :] - proj_col
    good = (g.sum(axis=0) > 0) & (disp > 0)
    depth = np.zeros((h, w), dtype=np.float64)
    depth[good] = f * baseline / disp[good]
    return depth
