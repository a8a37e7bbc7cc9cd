"""Lab 12 - stereo.

My own implementations with NumPy (OpenCV only for filtering, warping and lines).
Disparity maps are indexed like the left image; d = x_l - x_r > 0.
"""

import cv2
import numpy as np


# --------------------------------------------------------------------- ex1
def triangulate(P1, P2, pts1, pts2):
    """Linear triangulation: (x p3 - p1) X = 0, (y p3 - p2) X = 0 for both views, SVD."""
    P1 = np.asarray(P1, dtype=float)
    P2 = np.asarray(P2, dtype=float)
    single = np.asarray(pts1).ndim == 1
    p1 = np.asarray(pts1, dtype=float).reshape(-1, 2)
    p2 = np.asarray(pts2, dtype=float).reshape(-1, 2)

    out = np.empty((len(p1), 3))
    for i in range(len(p1)):
        A = np.vstack([
            p1[i, 0] * P1[2] - P1[0],
            p1[i, 1] * P1[2] - P1[1],
            p2[i, 0] * P2[2] - P2[0],
            p2[i, 1] * P2[2] - P2[1],
        ])
        _, _, Vt = np.linalg.svd(A)
        X = Vt[-1]
        out[i] = X[:3] / X[3]
    return out[0] if single else out


# --------------------------------------------------------------------- ex2
def disparity_from_matches(xl, xr):
    """d = x_l - x_r (only the x column is used for (N, 2) points)."""
    xl = np.asarray(xl, dtype=float)
    xr = np.asarray(xr, dtype=float)
    if xl.ndim == 2:
        xl = xl[:, 0]
    if xr.ndim == 2:
        xr = xr[:, 0]
    return xl - xr


def depth_from_disparity(disparity, f, baseline):
    """Z = f b / d where d > 0, and 0 elsewhere (also for NaN disparities)."""
    d = np.asarray(disparity, dtype=float)
    valid = d > 0                       # False for NaN too
    safe = np.where(valid, d, 1.0)      # avoid dividing by zero
    return np.where(valid, f * baseline / safe, 0.0)


# --------------------------------------------------------------------- ex3
def rectify(img_l, img_r, K1, K2, R, T):
    """Rectification built by hand (the lecture's construction).

    The new common orientation Rn has its x axis along the baseline (from
    camera 1's centre to camera 2's), its y axis perpendicular to x and to the
    mean viewing direction, and z = x cross y. Both new cameras share the
    intrinsics Kn, so a point lands on the same row in both images.
    """
    K1 = np.asarray(K1, dtype=float)
    K2 = np.asarray(K2, dtype=float)
    R = np.asarray(R, dtype=float)
    T = np.asarray(T, dtype=float).reshape(3)
    h, w = img_l.shape[:2]

    # camera 2's centre in camera-1 coordinates
    c2 = -R.T @ T
    r1 = c2 / np.linalg.norm(c2)
    # mean optical axis (camera 2's z axis expressed in camera-1 coordinates is R^T e_z)
    z_mean = np.array([0.0, 0.0, 1.0]) + R.T @ np.array([0.0, 0.0, 1.0])
    r2 = np.cross(z_mean, r1)
    r2 /= np.linalg.norm(r2)
    r3 = np.cross(r1, r2)
    Rn = np.vstack([r1, r2, r3])          # camera-1 coordinates -> rectified ones

    # rotations of the original pixel rays into the rectified frame
    M1 = Rn @ np.linalg.inv(K1)
    M2 = Rn @ R.T @ np.linalg.inv(K2)

    # common intrinsics: mean focal length, principal point chosen so that the
    # two image centres end up (on average) at the centre of the frame
    f = (K1[0, 0] + K1[1, 1] + K2[0, 0] + K2[1, 1]) / 4.0
    centre = np.array([(w - 1) / 2.0, (h - 1) / 2.0, 1.0])
    a = M1 @ centre
    b = M2 @ centre
    mean_xy = f * (a[:2] / a[2] + b[:2] / b[2]) / 2.0
    cx = (w - 1) / 2.0 - mean_xy[0]
    cy = (h - 1) / 2.0 - mean_xy[1]
    Kn = np.array([[f, 0, cx], [0, f, cy], [0, 0, 1.0]])

    H1 = Kn @ M1
    H2 = Kn @ M2
    rect_l = cv2.warpPerspective(img_l, H1, (w, h), flags=cv2.INTER_LINEAR,
                                 borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    rect_r = cv2.warpPerspective(img_r, H2, (w, h), flags=cv2.INTER_LINEAR,
                                 borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return rect_l, rect_r, H1, H2


# --------------------------------------------------------------------- ex4
def _shift_right_image(right, d):
    """Image whose column x holds right[:, x - d] (NaN where x - d < 0)."""
    shifted = np.full(right.shape, np.nan)
    if d == 0:
        shifted[:] = right
    elif d < right.shape[1]:
        shifted[:, d:] = right[:, :-d]
    return shifted


def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
    """Winner-take-all block matching with a cost volume (SSD or NCC)."""
    L = np.asarray(left, dtype=np.float64)
    Rt = np.asarray(right, dtype=np.float64)
    ksize = (block_size, block_size)
    D = int(max_disparity) + 1
    h, w = L.shape

    def box_mean(img):
        return cv2.blur(img, ksize, borderType=cv2.BORDER_REFLECT)

    if cost == "ssd":
        volume = np.full((D, h, w), np.inf)
        for d in range(D):
            Rs = _shift_right_image(Rt, d)
            valid = ~np.isnan(Rs)
            diff2 = np.where(valid, (L - np.nan_to_num(Rs)) ** 2, 0.0)
            ssd = box_mean(diff2)
            volume[d] = np.where(valid, ssd, np.inf)
        disp = np.argmin(volume, axis=0).astype(float)
    elif cost == "ncc":
        mu_l = box_mean(L)
        var_l = box_mean(L * L) - mu_l ** 2
        volume = np.full((D, h, w), -np.inf)
        for d in range(D):
            Rs = _shift_right_image(Rt, d)
            valid = ~np.isnan(Rs)
            Rz = np.nan_to_num(Rs)
            mu_r = box_mean(Rz)
            var_r = box_mean(Rz * Rz) - mu_r ** 2
            cov = box_mean(L * Rz) - mu_l * mu_r
            denom = np.sqrt(np.maximum(var_l, 0) * np.maximum(var_r, 0))
            with np.errstate(invalid="ignore", divide="ignore"):
                ncc = cov / denom
            ncc[~np.isfinite(ncc) | (denom < 1e-6)] = -np.inf
            volume[d] = np.where(valid, ncc, -np.inf)
        disp = np.argmax(volume, axis=0).astype(float)
        # no finite score at all (flat blocks): invalid
        disp[~np.isfinite(volume.max(axis=0))] = 0.0
    else:
        raise ValueError("cost must be 'ssd' or 'ncc'")
    return disp


# --------------------------------------------------------------------- ex5
def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
    """Scanline dynamic programming, all rows at once.

    Data term: mean squared difference over the block (SSD / block area), in
    grey levels squared. Smoothness: smoothness * |d_x - d_(x+1)|.
    """
    if smoothness is None:
        smoothness = 200.0         # my default for a mean-SSD cost (grey levels^2)
    L = np.asarray(left, dtype=np.float64)
    Rt = np.asarray(right, dtype=np.float64)
    h, w = L.shape
    D = int(max_disparity) + 1
    BIG = 1e6                      # cost where x - d leaves the right image

    # data cost C[x, row, d]
    C = np.empty((w, h, D))
    for d in range(D):
        Rs = _shift_right_image(Rt, d)
        valid = ~np.isnan(Rs)
        diff2 = np.where(valid, (L - np.nan_to_num(Rs)) ** 2, 0.0)
        c = cv2.blur(diff2, (block_size, block_size), borderType=cv2.BORDER_REFLECT)
        C[:, :, d] = np.where(valid, c, BIG).T

    dd = np.arange(D)
    jump = smoothness * np.abs(dd[:, None] - dd[None, :])   # jump[d, d']

    # forward pass
    M = C[0].copy()                                # (h, D)
    back = np.zeros((w, h, D), dtype=np.int32)
    for x in range(1, w):
        total = M[:, None, :] + jump[None, :, :]   # (h, d, d')
        best = np.argmin(total, axis=2)
        back[x] = best
        M = C[x] + np.take_along_axis(total, best[:, :, None], axis=2)[:, :, 0]

    # backtracking
    disp = np.zeros((h, w))
    d_cur = np.argmin(M, axis=1)
    rows = np.arange(h)
    for x in range(w - 1, -1, -1):
        disp[:, x] = d_cur
        d_cur = back[x, rows, d_cur]
    return disp


# --------------------------------------------------------------------- ex6
def gray_code_patterns(width, n_bits):
    """Row i = bit i (MSB first) of the Gray code of stripe k = floor(u 2^n / W)."""
    u = np.arange(width, dtype=np.int64)
    k = (u * (2 ** n_bits)) // width
    g = k ^ (k >> 1)
    pats = np.zeros((n_bits, width), dtype=np.uint8)
    for i in range(n_bits):
        bit = (g >> (n_bits - 1 - i)) & 1
        pats[i] = bit * 255
    return pats


def simulate_structured_light(depth, f, baseline, n_bits):
    """Camera images of the projected Gray-code patterns."""
    Z = np.asarray(depth, dtype=float)
    h, w = Z.shape
    pats = gray_code_patterns(w, n_bits)
    u = np.arange(w)[None, :].repeat(h, axis=0)

    lit = Z > 0
    p = np.zeros((h, w), dtype=np.int64)
    p[lit] = np.rint(u[lit] - f * baseline / Z[lit]).astype(np.int64)
    lit &= (p >= 0) & (p < w)

    out = np.zeros((n_bits, h, w), dtype=np.uint8)
    for i in range(n_bits):
        out[i][lit] = pats[i][p[lit]]
    return out


def depth_from_structured_light(images, f, baseline):
    """Decode the Gray code, take the stripe centre and triangulate."""
    imgs = np.asarray(images)
    n_bits, h, w = imgs.shape
    bits = imgs > 127

    # Gray -> binary: b_0 = g_0, b_i = b_(i-1) XOR g_i
    k = np.zeros((h, w), dtype=np.int64)
    b_prev = np.zeros((h, w), dtype=bool)
    for i in range(n_bits):
        b_i = b_prev ^ bits[i]
        k = 2 * k + b_i
        b_prev = b_i

    column = (k + 0.5) * w / 2 ** n_bits - 0.5
    u = np.arange(w)[None, :]
    disparity = u - column
    decodable = bits.any(axis=0)
    ok = decodable & (disparity > 0)
    depth = np.zeros((h, w))
    depth[ok] = f * baseline / disparity[ok]
    return depth
