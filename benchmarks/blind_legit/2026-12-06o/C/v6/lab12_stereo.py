"""Lab 12 - stereo.

Defensive versions: inputs are converted to fresh arrays of the type each
step needs (so lists, float arrays, non-contiguous views and colour images
are accepted and never modified), sizes are checked, and degenerate cases
(zero/NaN disparities, blocks larger than the image, disparities larger than
the image width, textureless blocks) are handled explicitly.

What is my own here: the linear triangulation, the rectifying rotation (built
as in the lecture rather than with cv2.stereoRectify), the SSD / NCC block
matcher and the dynamic programming.
"""

import cv2
import numpy as np


# ===================================================================== helpers
def _as_grey_float(img, name):
    """uint8 grey or BGR image -> float64 (H, W) grey copy."""
    arr = np.asarray(img)
    if arr.ndim == 3 and arr.shape[2] == 1:
        arr = arr[:, :, 0]
    if arr.ndim == 3 and arr.shape[2] == 3:
        arr = cv2.cvtColor(np.ascontiguousarray(arr, dtype=np.uint8), cv2.COLOR_BGR2GRAY)
    if arr.ndim != 2:
        raise ValueError(f"{name} must be a (H, W) grey or (H, W, 3) BGR image")
    return np.array(arr, dtype=np.float64, copy=True)


def _check_pair(left, right):
    L = _as_grey_float(left, "left")
    R = _as_grey_float(right, "right")
    if L.shape != R.shape:
        raise ValueError("left and right images must have the same size")
    return L, R


def _check_block(block_size):
    b = int(block_size)
    if b < 1 or b % 2 == 0:
        raise ValueError("block_size must be a positive odd integer")
    return b


def _box_mean(a, block):
    """Mean over a block x block window (edges reflected)."""
    return cv2.boxFilter(a, -1, (block, block), normalize=True, borderType=cv2.BORDER_REFLECT_101)


def _shift_right(img, d):
    """Image shifted d columns to the right: out[:, x] = img[:, x - d] (0 where x < d)."""
    out = np.zeros_like(img)
    if d < img.shape[1]:
        out[:, d:] = img[:, :img.shape[1] - d]
    return out


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear triangulation, all points at once.

    For each correspondence the 4 x 4 system A X = 0 is formed from
    x cross (P X) = 0 (rows x p3 - p1 and y p3 - p2 of each view) and solved by
    SVD; X is then de-homogenised.
    """
    P1 = np.array(P1, dtype=np.float64).reshape(3, 4)
    P2 = np.array(P2, dtype=np.float64).reshape(3, 4)
    single = np.ndim(pts1) == 1          # one (x, y) pair -> one (3,) point
    p1 = np.array(pts1, dtype=np.float64).reshape(-1, 2)
    p2 = np.array(pts2, dtype=np.float64).reshape(-1, 2)
    if p1.shape != p2.shape:
        raise ValueError("pts1 and pts2 must have the same shape")
    n = p1.shape[0]
    A = np.empty((n, 4, 4))
    A[:, 0] = p1[:, [0]] * P1[2] - P1[0]
    A[:, 1] = p1[:, [1]] * P1[2] - P1[1]
    A[:, 2] = p2[:, [0]] * P2[2] - P2[0]
    A[:, 3] = p2[:, [1]] * P2[2] - P2[1]
    if n == 0:
        return np.zeros((0, 3))
    _, _, Vt = np.linalg.svd(A)
    X = Vt[:, -1, :]
    w = X[:, 3]
    with np.errstate(divide="ignore", invalid="ignore"):
        out = X[:, :3] / w[:, None]
    out[np.abs(w) < 1e-15] = np.nan  # point at infinity
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def disparity_from_matches(xl, xr):
    """d = x_l - x_r; (N, 2) inputs use their x column."""
    xl = np.array(xl, dtype=np.float64)
    xr = np.array(xr, dtype=np.float64)
    if xl.ndim == 2:
        if xl.shape[1] != 2:
            raise ValueError("points must be (N,) x coordinates or (N, 2) points")
        xl = xl[:, 0]
    if xr.ndim == 2:
        if xr.shape[1] != 2:
            raise ValueError("points must be (N,) x coordinates or (N, 2) points")
        xr = xr[:, 0]
    if xl.shape != xr.shape:
        raise ValueError("xl and xr must contain the same number of matches")
    return xl - xr


def depth_from_disparity(disparity, f, baseline):
    """Z = f b / d where d > 0, 0 elsewhere (also for NaN)."""
    d = np.array(disparity, dtype=np.float64)
    depth = np.zeros_like(d)
    valid = np.isfinite(d) & (d > 0)
    depth[valid] = float(f) * float(baseline) / d[valid]
    return depth


# --------------------------------------------------------------------- ex3
def _rectifying_rotation(R, T):
    """Rotation taking camera-1 coordinates to the common rectified frame.

    As in the lecture: the new x axis points along the baseline (from camera 1
    to camera 2), the new y axis is perpendicular to it and to the old optical
    axis, and the new z axis completes the right-handed frame.
    """
    C2 = -R.T @ T               # camera 2's centre in camera-1 coordinates
    r1 = C2 / np.linalg.norm(C2)
    z_old = np.array([0.0, 0.0, 1.0])
    # Average the two optical axes so both cameras turn by a similar amount.
    z_avg = z_old + R.T @ z_old
    r2 = np.cross(z_avg, r1)
    if np.linalg.norm(r2) < 1e-9:   # baseline along the optical axis: no good rectification
        raise ValueError("baseline is parallel to the optical axis")
    r2 /= np.linalg.norm(r2)
    r3 = np.cross(r1, r2)
    return np.vstack([r1, r2, r3])


def rectify(img_l, img_r, K1, K2, R, T):
    """Rectify a calibrated pair; H1, H2 map original pixels to rectified pixels."""
    img_l = np.ascontiguousarray(img_l)
    img_r = np.ascontiguousarray(img_r)
    if img_l.shape != img_r.shape:
        raise ValueError("the two images must have the same shape")
    h, w = img_l.shape[:2]
    K1 = np.array(K1, dtype=np.float64).reshape(3, 3)
    K2 = np.array(K2, dtype=np.float64).reshape(3, 3)
    R = np.array(R, dtype=np.float64).reshape(3, 3)
    T = np.array(T, dtype=np.float64).reshape(3)

    Rrect = _rectifying_rotation(R, T)
    rot1 = Rrect                 # camera-1 ray -> rectified ray
    rot2 = Rrect @ R.T           # camera-2 ray -> rectified ray (same orientation)

    # Common intrinsics: the mean focal lengths, no skew. The principal point is
    # placed so that the two image centres land, on average, in the middle of
    # the output (both cameras share it, so points at infinity have d = 0).
    fx = 0.5 * (K1[0, 0] + K2[0, 0])
    fy = 0.5 * (K1[1, 1] + K2[1, 1])
    centre = np.array([(w - 1) / 2.0, (h - 1) / 2.0, 1.0])
    offsets = []
    for K, rot in ((K1, rot1), (K2, rot2)):
        ray = rot @ np.linalg.solve(K, centre)
        offsets.append([fx * ray[0] / ray[2], fy * ray[1] / ray[2]])
    off = np.mean(offsets, axis=0)
    Knew = np.array([[fx, 0.0, centre[0] - off[0]],
                     [0.0, fy, centre[1] - off[1]],
                     [0.0, 0.0, 1.0]])

    H1 = Knew @ rot1 @ np.linalg.inv(K1)
    H2 = Knew @ rot2 @ np.linalg.inv(K2)
    H1 /= H1[2, 2]
    H2 /= H2[2, 2]
    rect_l = cv2.warpPerspective(img_l, H1, (w, h), flags=cv2.INTER_LINEAR,
                                 borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    rect_r = cv2.warpPerspective(img_r, H2, (w, h), flags=cv2.INTER_LINEAR,
                                 borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return rect_l, rect_r, H1, H2


# --------------------------------------------------------------------- ex4
def _matching_costs(L, R, max_disparity, block, cost):
    """Cost volume (D+1, H, W), lower is better; inf where x - d < 0."""
    h, w = L.shape
    D = max_disparity + 1
    vol = np.full((D, h, w), np.inf)
    if cost == "ncc":
        muL = _box_mean(L, block)
        sdL = np.sqrt(np.maximum(_box_mean(L * L, block) - muL ** 2, 0.0))
    for d in range(D):
        if d >= w:
            break           # no column of the right image is left
        Rs = _shift_right(R, d)
        if cost == "ssd":
            c = _box_mean((L - Rs) ** 2, block)      # mean of squared differences
        else:
            muR = _box_mean(Rs, block)
            sdR = np.sqrt(np.maximum(_box_mean(Rs * Rs, block) - muR ** 2, 0.0))
            cov = _box_mean(L * Rs, block) - muL * muR
            den = sdL * sdR
            # A textureless block has no defined NCC: score it 0 (no evidence).
            ncc = np.where(den > 1e-6, cov / np.maximum(den, 1e-6), 0.0)
            c = -ncc                                  # higher NCC = lower cost
        c[:, :d] = np.inf    # x - d outside the right image
        vol[d] = c
    return vol


def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    """Winner-take-all SSD or NCC block matching (own implementation)."""
    cost = str(cost).lower()
    if cost not in ("ssd", "ncc"):
        raise ValueError("cost must be 'ssd' or 'ncc'")
    max_disparity = int(max_disparity)
    if max_disparity < 0:
        raise ValueError("max_disparity must be >= 0")
    block = _check_block(block_size)
    L, R = _check_pair(left, right)

    vol = _matching_costs(L, R, max_disparity, block, cost)
    disp = np.argmin(vol, axis=0).astype(np.float64)
    # A pixel whose costs are all infinite cannot happen (d = 0 is always
    # available), but a NaN would: mark such pixels invalid.
    bad = ~np.isfinite(np.min(vol, axis=0))
    disp[bad] = 0.0
    return disp


# --------------------------------------------------------------------- ex5
# Data cost: the lab sheet's SSD, as the mean of squared differences over the
# block (grey levels squared, so a correct match costs about 2 * noise^2, i.e.
# 10-50, and a wrong one hundreds to thousands). The smoothness penalty has to
# live on that scale: DEFAULT_SMOOTHNESS is set by trying 10..400 on synthetic
# textured pairs (skimage images, noise 1-4 grey levels, fronto-parallel and
# slanted surfaces). Around 20 was best: much larger values flatten slanted
# surfaces into steps, much smaller ones let noise through in weak texture.
DEFAULT_SMOOTHNESS = 20.0


def _dp_data_cost(L, R, max_disparity, block):
    """(W, H, D) data costs: mean squared difference per block."""
    h, w = L.shape
    D = max_disparity + 1
    big = 1e9       # x - d outside the right image: effectively forbidden
    C = np.full((w, h, D), big)
    for d in range(min(D, w)):
        msd = _box_mean((L - _shift_right(R, d)) ** 2, block)
        C[d:, :, d] = msd[:, d:].T
    return C


def _l1_min_convolution(M, lam):
    """For every d: min over d' of M[:, d'] + lam |d - d'|, and the arg-min d'.

    Two passes over the disparities (the classic distance transform for the L1
    penalty), done for all rows at once.
    """
    h, D = M.shape
    best = M.copy()
    arg = np.tile(np.arange(D), (h, 1))
    for d in range(1, D):              # from the left: d' <= d
        cand = best[:, d - 1] + lam
        better = cand < best[:, d]
        best[better, d] = cand[better]
        arg[better, d] = arg[better, d - 1]
    for d in range(D - 2, -1, -1):     # from the right: d' >= d
        cand = best[:, d + 1] + lam
        better = cand < best[:, d]
        best[better, d] = cand[better]
        arg[better, d] = arg[better, d + 1]
    return best, arg


def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline DP: sum_x C(x, d_x) + smoothness * sum_x |d_x - d_{x+1}|."""
    max_disparity = int(max_disparity)
    if max_disparity < 0:
        raise ValueError("max_disparity must be >= 0")
    block = _check_block(block_size)
    lam = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)
    if lam < 0:
        raise ValueError("smoothness must be >= 0")
    L, R = _check_pair(left, right)
    h, w = L.shape
    D = max_disparity + 1

    C = _dp_data_cost(L, R, max_disparity, block)
    if lam == 0:
        # No smoothness: the DP reduces to winner-take-all on the data cost.
        return np.argmin(C, axis=2).T.astype(np.float64)

    back = np.zeros((w, h, D), dtype=np.int32)
    M = C[0].copy()
    for x in range(1, w):
        best, arg = _l1_min_convolution(M, lam)
        back[x] = arg
        M = C[x] + best
        M -= M.min(axis=1, keepdims=True)   # keep the numbers small

    disp = np.empty((h, w))
    rows = np.arange(h)
    d = np.argmin(M, axis=1)
    for x in range(w - 1, -1, -1):
        disp[:, x] = d
        d = back[x, rows, d]
    return disp


# --------------------------------------------------------------------- ex6
def gray_code_patterns(width, n_bits):
    """(n_bits, width) uint8 stripes, row 0 = most significant Gray-code bit."""
    width, n_bits = int(width), int(n_bits)
    if width <= 0 or n_bits <= 0:
        raise ValueError("width and n_bits must be positive")
    u = np.arange(width, dtype=np.int64)
    k = (u * (1 << n_bits)) // width
    gray = k ^ (k >> 1)
    patterns = np.zeros((n_bits, width), dtype=np.uint8)
    for i in range(n_bits):
        bit = (gray >> (n_bits - 1 - i)) & 1
        patterns[i] = np.where(bit == 1, 255, 0)
    return patterns


def simulate_structured_light(depth, f, baseline, n_bits):
    """Camera images of the Gray-code patterns projected onto a scene of known depth."""
    Z = np.array(depth, dtype=np.float64)
    if Z.ndim != 2:
        raise ValueError("depth must be (H, W)")
    h, w = Z.shape
    n_bits = int(n_bits)
    patterns = gray_code_patterns(w, n_bits)

    lit = np.isfinite(Z) & (Z > 0)
    col = np.full((h, w), -1, dtype=np.int64)
    u = np.broadcast_to(np.arange(w, dtype=np.float64), (h, w))
    # round half up (floor(x + 0.5)) for the projector column
    col[lit] = np.floor(u[lit] - float(f) * float(baseline) / Z[lit] + 0.5).astype(np.int64)
    lit &= (col >= 0) & (col < w)

    images = np.zeros((n_bits, h, w), dtype=np.uint8)
    for i in range(n_bits):
        images[i][lit] = patterns[i][col[lit]]
    return images


def depth_from_structured_light(images, f, baseline):
    """Decode the Gray code per pixel and triangulate with the projector."""
    imgs = np.array(images)
    if imgs.ndim != 3:
        raise ValueError("images must be (n_bits, H, W)")
    n_bits, h, w = imgs.shape
    bits = imgs > 127

    # Gray -> binary: b_0 = g_0, b_i = b_(i-1) xor g_i
    k = np.zeros((h, w), dtype=np.int64)
    b = np.zeros((h, w), dtype=bool)
    for i in range(n_bits):
        b = b ^ bits[i]
        k = (k << 1) | b.astype(np.int64)

    column = (k + 0.5) * w / float(1 << n_bits) - 0.5
    disparity = np.arange(w, dtype=np.float64)[None, :] - column
    depth = depth_from_disparity(disparity, f, baseline)
    depth[~bits.any(axis=0)] = 0.0      # never lit: undecodable
    return depth
