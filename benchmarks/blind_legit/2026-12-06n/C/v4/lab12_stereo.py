"""Lab 12 - stereo (Szeliski, "Computer Vision: Algorithms and Applications",
ch. 12, Hartley & Zisserman ch. 12, and the OpenCV stereo tutorials).

- ex1: DLT triangulation, the null vector taken as the eigenvector of A^T A
  with the smallest eigenvalue.
- ex3: cv2.stereoRectify for the rotations and new cameras, then the warp done
  with cv2.remap on sampling maps I build from the inverse homographies.
- ex4: cv2.StereoBM for SSD (the lab sheet's recipe, as in the OpenCV
  tutorial); zero-mean NCC of my own with scipy.ndimage box filters.
- ex5: scanline DP on the sum-of-absolute-differences cost; the minimisation
  over the previous disparity uses the linear-time L1 distance transform
  (Felzenszwalb & Huttenlocher) instead of an (H, D, D) array.
- ex6: Gray codes built by the reflection construction, decoded with a
  cumulative XOR.
"""

import cv2
import numpy as np
from scipy import ndimage


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """DLT triangulation (H&Z 12.2): X = eigenvector of A^T A, smallest eigenvalue."""
    P1 = np.asarray(P1, dtype=np.float64)
    P2 = np.asarray(P2, dtype=np.float64)
    a = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
    b = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
    out = np.empty((len(a), 3))
    for i in range(len(a)):
        A = np.array([a[i, 0] * P1[2] - P1[0],
                      a[i, 1] * P1[2] - P1[1],
                      b[i, 0] * P2[2] - P2[0],
                      b[i, 1] * P2[2] - P2[1]])
        A /= np.linalg.norm(A, axis=1, keepdims=True)     # balance the rows
        _, vecs = np.linalg.eigh(A.T @ A)                 # ascending eigenvalues
        X = vecs[:, 0]
        out[i] = X[:3] / X[3]
    return out[0] if np.ndim(pts1) == 1 else out      # one pair in, one point out


# --------------------------------------------------------------------- ex2
def disparity_from_matches(xl, xr):
    """d = x_l - x_r."""
    xl = np.asarray(xl, dtype=np.float64)
    xr = np.asarray(xr, dtype=np.float64)
    if xl.ndim == 2:
        xl = xl[:, 0]
    if xr.ndim == 2:
        xr = xr[:, 0]
    return xl - xr


def depth_from_disparity(disparity, f, baseline):
    """Z = f b / d, 0 where d is not a positive number."""
    d = np.asarray(disparity, dtype=np.float64)
    good = d > 0                       # False for NaN as well
    safe = np.where(good, d, 1.0)
    return np.where(good, f * baseline / safe, 0.0)


# --------------------------------------------------------------------- ex3
def _warp_with_remap(img, H, size):
    """Warp by H with cv2.remap: every output pixel samples the input at H^-1 p."""
    w, h = size
    Hinv = np.linalg.inv(H)
    u, v = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
    den = Hinv[2, 0] * u + Hinv[2, 1] * v + Hinv[2, 2]
    map_x = (Hinv[0, 0] * u + Hinv[0, 1] * v + Hinv[0, 2]) / den
    map_y = (Hinv[1, 0] * u + Hinv[1, 1] * v + Hinv[1, 2]) / den
    return cv2.remap(img, map_x.astype(np.float32), map_y.astype(np.float32),
                     interpolation=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)


def rectify(img_l, img_r, K1, K2, R, T):
    """cv2.stereoRectify (zero disparity at infinity), maps built by hand, cv2.remap.

    alpha = 0.5 is halfway between alpha = 0 (zoom in until no black border is
    left, which crops away a good part of the scene) and alpha = 1 (keep every
    input pixel, with wide black borders): most of each image stays in view
    and fills most of the frame.
    """
    h, w = img_l.shape[:2]
    K1 = np.asarray(K1, dtype=np.float64)
    K2 = np.asarray(K2, dtype=np.float64)
    R1, R2, Pn1, Pn2, _, _, _ = cv2.stereoRectify(
        K1, None, K2, None, (w, h), np.asarray(R, dtype=np.float64),
        np.asarray(T, dtype=np.float64).reshape(3, 1),
        flags=cv2.CALIB_ZERO_DISPARITY, alpha=0.5)
    H1 = Pn1[:, :3] @ R1 @ np.linalg.inv(K1)
    H2 = Pn2[:, :3] @ R2 @ np.linalg.inv(K2)
    return _warp_with_remap(img_l, H1, (w, h)), _warp_with_remap(img_r, H2, (w, h)), H1, H2


# --------------------------------------------------------------------- ex4 / ext1
def _ssd_own(L, R, D, k):
    """Fallback SSD matcher (block sizes StereoBM does not accept)."""
    h, w = L.shape
    cost = np.full((D + 1, h, w), np.inf)
    for d in range(min(D, w - 1) + 1):
        diff = np.zeros((h, w))
        diff[:, d:] = (L[:, d:] - R[:, :w - d]) ** 2
        cost[d] = ndimage.uniform_filter(diff, k, mode="reflect")
        cost[d][:, :d] = np.inf
    return np.argmin(cost, axis=0).astype(np.float64)


def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    """Block matching: StereoBM for SSD, own zero-mean NCC for "ncc"."""
    D = int(max_disparity)
    k = int(block_size)
    if cost == "ssd":
        n = 16 * -(-(D + 1) // 16)
        if k % 2 == 1 and 5 <= k <= 255 and min(left.shape) > k:
            bm = cv2.StereoBM_create(numDisparities=n, blockSize=k)
            d = bm.compute(np.ascontiguousarray(left), np.ascontiguousarray(right)) / 16.0
            d[(d <= 0) | (d > D)] = 0
            return d
        return _ssd_own(left.astype(np.float64), right.astype(np.float64), D, k)
    if cost != "ncc":
        raise ValueError("cost must be 'ssd' or 'ncc'")

    # Zero-mean NCC (Szeliski eq. 12.x):
    # ncc = (mean(L R) - mean(L) mean(R)) / (std(L) std(R))
    L = left.astype(np.float64)
    R = right.astype(np.float64)
    h, w = L.shape
    box = lambda im: ndimage.uniform_filter(im, k, mode="reflect")
    mu_l = box(L)
    sd_l = np.sqrt(np.maximum(box(L * L) - mu_l ** 2, 0))
    score = np.full((D + 1, h, w), -np.inf)
    for d in range(min(D, w - 1) + 1):
        Rs = np.zeros_like(R)
        Rs[:, d:] = R[:, :w - d]
        mu_r = box(Rs)
        sd_r = np.sqrt(np.maximum(box(Rs * Rs) - mu_r ** 2, 0))
        ncc = (box(L * Rs) - mu_l * mu_r) / np.maximum(sd_l * sd_r, 1e-9)
        ncc[:, :d] = -np.inf           # no partner in the right image
        score[d] = ncc
    return np.argmax(score, axis=0).astype(np.float64)


# --------------------------------------------------------------------- ex5
def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline DP, cost = mean absolute difference over the block.

    Recurrence: M(x, d) = C(x, d) + min_d' [M(x-1, d') + lam |d - d'|].
    The inner minimum is an L1 distance transform of M(x-1, .), computed in two
    sweeps over d (up, then down), for all rows at once. Default lam = 8 grey
    levels per pixel of disparity change (a suitable scale for a mean absolute
    difference on 8-bit images).
    """
    lam = 8.0 if smoothness is None else float(smoothness)
    D = int(max_disparity)
    L = left.astype(np.float64)
    R = right.astype(np.float64)
    h, w = L.shape
    big = 1e9                          # "impossible" cost where x - d < 0

    C = np.full((w, h, D + 1), big)
    for d in range(min(D, w - 1) + 1):
        ad = np.zeros((h, w))
        ad[:, d:] = np.abs(L[:, d:] - R[:, :w - d])
        c = ndimage.uniform_filter(ad, block_size, mode="nearest")
        c[:, :d] = big
        C[:, :, d] = c.T

    M = C[0].copy()                    # (h, D+1)
    back = np.empty((w, h, D + 1), dtype=np.int32)
    rows = np.arange(h)
    for x in range(1, w):
        m = M.copy()
        arg = np.tile(np.arange(D + 1, dtype=np.int32), (h, 1))
        for d in range(1, D + 1):      # sweep up: coming from smaller d'
            cand = m[:, d - 1] + lam
            better = cand < m[:, d]
            m[better, d] = cand[better]
            arg[better, d] = arg[better, d - 1]
        for d in range(D - 1, -1, -1): # sweep down: coming from larger d'
            cand = m[:, d + 1] + lam
            better = cand < m[:, d]
            m[better, d] = cand[better]
            arg[better, d] = arg[better, d + 1]
        back[x] = arg
        M = C[x] + m

    disp = np.empty((h, w))
    d = np.argmin(M, axis=1)
    for x in range(w - 1, -1, -1):
        disp[:, x] = d
        d = back[x, rows, d]
    return disp


# --------------------------------------------------------------------- ex6
def _reflected_gray(n_bits):
    """Table of the n-bit binary-reflected Gray code, built by reflection:
    G(n) = [0 G(n-1), 1 reverse(G(n-1))]."""
    codes = [0]
    for bit in range(n_bits):
        codes = codes + [c | (1 << bit) for c in reversed(codes)]
    return np.array(codes, dtype=np.int64)


def gray_code_patterns(width, n_bits):
    """Row i: bit i (most significant first) of the Gray code of stripe k."""
    k = (np.arange(width) * 2 ** n_bits) // width
    g = _reflected_gray(n_bits)[k]
    shifts = np.arange(n_bits - 1, -1, -1)[:, None]
    return (((g[None, :] >> shifts) & 1) * 255).astype(np.uint8)


def simulate_structured_light(depth, f, baseline, n_bits):
    """Camera pixel (u, v) at depth Z sees projector column round(u - f b / Z),
    rounded the school way (halves up: floor(x + 0.5))."""
    depth = np.asarray(depth, dtype=np.float64)
    h, w = depth.shape
    patterns = gray_code_patterns(w, n_bits)
    u = np.arange(w)[None, :].repeat(h, axis=0)
    valid = depth > 0
    disparity = np.where(valid, f * baseline / np.where(valid, depth, 1.0), 0.0)
    col = np.floor(u - disparity + 0.5).astype(np.int64)
    valid &= (col >= 0) & (col < w)
    images = np.zeros((n_bits, h, w), dtype=np.uint8)
    for i in range(n_bits):
        images[i][valid] = patterns[i][col[valid]]
    return images


def depth_from_structured_light(images, f, baseline):
    """Threshold, Gray -> binary with a cumulative XOR, stripe centre, Z = f b / d."""
    images = np.asarray(images)
    n_bits, h, w = images.shape
    g = (images > 127).astype(np.int64)
    b = np.bitwise_xor.accumulate(g, axis=0)              # b_i = b_(i-1) xor g_i
    weights = (2 ** np.arange(n_bits - 1, -1, -1))[:, None, None]
    k = np.sum(b * weights, axis=0)
    column = (k + 0.5) * w / 2 ** n_bits - 0.5
    disparity = np.arange(w)[None, :] - column
    ok = g.any(axis=0) & (disparity > 0)
    return np.where(ok, f * baseline / np.where(ok, disparity, 1.0), 0.0)
