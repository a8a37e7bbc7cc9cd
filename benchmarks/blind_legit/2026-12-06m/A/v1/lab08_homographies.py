"""Lab 8 - image homographies.

My solutions, written from the lecture equations:

- warps are my own backward mapping: every output pixel p' is mapped back with
  H^-1, divided by its third coordinate, and the source image is sampled there
  bilinearly (black outside the image);
- the DLT builds the lab sheet's 2N x 9 matrix and takes the right singular
  vector of the smallest singular value;
- RANSAC is my own loop around the DLT, with an adaptive number of samples;
- the panorama averages the two images where they overlap.

Conventions: points are (x, y) = (column, row), origin at the centre of the
top-left pixel, y pointing down. dsize is (width, height) as in OpenCV.
"""

import cv2
import numpy as np


# ------------------------------------------------------------------ helpers
def _bilinear_sample(image, xs, ys):
    """Bilinear samples of ``image`` at (xs, ys); outside neighbours are black."""
    img = image.astype(np.float64)
    h, w = img.shape[:2]
    if img.ndim == 2:
        img = img[:, :, None]
    x0 = np.floor(xs).astype(np.int64)
    y0 = np.floor(ys).astype(np.int64)
    fx = xs - x0
    fy = ys - y0
    out = np.zeros(xs.shape + (img.shape[2],))
    for dy, dx, wgt in ((0, 0, (1 - fx) * (1 - fy)),
                        (0, 1, fx * (1 - fy)),
                        (1, 0, (1 - fx) * fy),
                        (1, 1, fx * fy)):
        xi = x0 + dx
        yi = y0 + dy
        inside = (xi >= 0) & (xi < w) & (yi >= 0) & (yi < h)
        vals = np.zeros_like(out)
        vals[inside] = img[yi[inside], xi[inside]]
        out += wgt[..., None] * vals
    if image.ndim == 2:
        out = out[..., 0]
    return out


def _warp_float(image, H, out_w, out_h):
    """Backward warp by H (source -> output); float result and coverage mask."""
    Hinv = np.linalg.inv(np.asarray(H, dtype=np.float64))
    ys, xs = np.mgrid[0:out_h, 0:out_w].astype(np.float64)
    pts = np.stack([xs.ravel(), ys.ravel(), np.ones(xs.size)])
    src = Hinv @ pts
    w = src[2]
    # points mapped to infinity (w == 0) or from behind have no source pixel
    ok = np.abs(w) > 1e-12
    w = np.where(ok, w, 1.0)
    sx = np.where(ok, src[0] / w, -1e6).reshape(out_h, out_w)
    sy = np.where(ok, src[1] / w, -1e6).reshape(out_h, out_w)
    sx = np.clip(sx, -1e6, 1e6)
    sy = np.clip(sy, -1e6, 1e6)
    vals = _bilinear_sample(image, sx, sy)
    h, wd = image.shape[:2]
    covered = (sx >= 0) & (sx <= wd - 1) & (sy >= 0) & (sy <= h - 1)
    return vals, covered


def _to_uint8(vals):
    return np.clip(np.rint(vals), 0, 255).astype(np.uint8)


# --------------------------------------------------------------------- ex1
def apply_homography(image, H, dsize=None):
    """Warp ``image`` by the homography ``H`` (source to output coordinates)."""
    if dsize is None:
        dsize = (image.shape[1], image.shape[0])
    vals, _ = _warp_float(image, H, int(dsize[0]), int(dsize[1]))
    return _to_uint8(vals)


def transform_points(H, pts):
    """Map points by ``H``, with the perspective division."""
    H = np.asarray(H, dtype=np.float64)
    pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    homog = np.column_stack([pts, np.ones(len(pts))])   # rows [x, y, 1]
    mapped = homog @ H.T                                  # rows [u, v, w]
    return mapped[:, :2] / mapped[:, 2:3]


# --------------------------------------------------------------------- ex2
def homography_dlt(src, dst):
    """The homography with ``dst ~ H @ src``, by the DLT (solved by SVD).

    Rows of A as on the lab sheet:
        [-x, -y, -1,  0,  0,  0, x x', y x', x']
        [ 0,  0,  0, -x, -y, -1, x y', y y', y']
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    rows = []
    for (x, y), (xp, yp) in zip(src, dst):
        rows.append([-x, -y, -1, 0, 0, 0, x * xp, y * xp, xp])
        rows.append([0, 0, 0, -x, -y, -1, x * yp, y * yp, yp])
    A = np.array(rows, dtype=np.float64)
    # full SVD: with 4 pairs A is 8 x 9 and the null vector is the 9th row
    _, _, Vt = np.linalg.svd(A)
    H = Vt[-1].reshape(3, 3)
    if abs(H[2, 2]) > 1e-12:
        H = H / H[2, 2]
    return H


def warp_to_reference(reference, moving, H):
    """``moving`` warped into ``reference``'s frame (H: moving -> reference)."""
    h, w = reference.shape[:2]
    return apply_homography(moving, H, dsize=(w, h))


# --------------------------------------------------------------------- ex3
def _grey(img):
    if img.ndim == 3:
        return cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    return img


def match_features(img1, img2, ratio=0.75, method="sift"):
    """Match keypoints between two images with Lowe's ratio test."""
    if method == "sift":
        detector = cv2.SIFT_create()
        norm = cv2.NORM_L2
    elif method == "orb":
        detector = cv2.ORB_create(nfeatures=1000)
        norm = cv2.NORM_HAMMING
    else:
        raise ValueError("method must be 'sift' or 'orb'")

    kp1, des1 = detector.detectAndCompute(_grey(img1), None)
    kp2, des2 = detector.detectAndCompute(_grey(img2), None)
    pts1, pts2 = [], []
    if des1 is not None and des2 is not None and len(kp1) > 0 and len(kp2) > 1:
        matcher = cv2.BFMatcher(norm)
        for pair in matcher.knnMatch(des1, des2, k=2):
            if len(pair) < 2:
                continue
            best, second = pair
            if best.distance < ratio * second.distance:
                pts1.append(kp1[best.queryIdx].pt)
                pts2.append(kp2[best.trainIdx].pt)
    pts1 = np.array(pts1, dtype=np.float64).reshape(-1, 2)
    pts2 = np.array(pts2, dtype=np.float64).reshape(-1, 2)
    return pts1, pts2


def draw_matches(img1, img2, pts1, pts2):
    """Both images side by side with a line for each match."""
    def to_bgr(img):
        return cv2.cvtColor(img, cv2.COLOR_GRAY2BGR) if img.ndim == 2 else img

    a, b = to_bgr(img1), to_bgr(img2)
    h1, w1 = a.shape[:2]
    h2, w2 = b.shape[:2]
    canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
    canvas[:h1, :w1] = a
    canvas[:h2, w1:w1 + w2] = b

    pts1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
    pts2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
    for (x1, y1), (x2, y2) in zip(pts1, pts2):
        p = (int(round(x1)), int(round(y1)))
        q = (int(round(x2 + w1)), int(round(y2)))
        cv2.line(canvas, p, q, (0, 255, 0), 1, cv2.LINE_AA)
        cv2.circle(canvas, p, 3, (0, 0, 255), 1, cv2.LINE_AA)
        cv2.circle(canvas, q, 3, (0, 0, 255), 1, cv2.LINE_AA)
    return canvas


# --------------------------------------------------------------------- ex4
def _transfer_error(H, src, dst):
    with np.errstate(divide="ignore", invalid="ignore"):
        err = np.linalg.norm(transform_points(H, src) - dst, axis=1)
    return np.where(np.isfinite(err), err, np.inf)


def _collinear(p, tol=1e-6):
    """True if any three of the four sample points are (nearly) collinear."""
    for i in range(4):
        q = np.delete(p, i, axis=0)
        area = abs((q[1, 0] - q[0, 0]) * (q[2, 1] - q[0, 1])
                   - (q[1, 1] - q[0, 1]) * (q[2, 0] - q[0, 0]))
        if area < tol:
            return True
    return False


def homography_ransac(src, dst, threshold=3.0, seed=None):
    """A homography robust to wrong correspondences, by my own RANSAC loop."""
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    n = len(src)
    rng = np.random.default_rng(seed)

    best_inliers = np.zeros(n, dtype=bool)
    best_count = 0
    n_iter = 2000           # upper bound, lowered adaptively below
    it = 0
    while it < n_iter:
        it += 1
        idx = rng.choice(n, 4, replace=False)
        if _collinear(src[idx]) or _collinear(dst[idx]):
            continue
        H = homography_dlt(src[idx], dst[idx])
        inliers = _transfer_error(H, src, dst) < threshold
        count = int(inliers.sum())
        if count > best_count:
            best_count = count
            best_inliers = inliers
            # adaptive number of samples for 99% confidence
            w = count / n
            if w >= 1.0:
                n_iter = it
            else:
                needed = np.log(1 - 0.99) / np.log(1 - w ** 4)
                n_iter = min(n_iter, max(int(np.ceil(needed)), 50))

    if best_count < 4:
        # no usable sample: fall back on all points
        H = homography_dlt(src, dst)
        return H, _transfer_error(H, src, dst) < threshold

    # refit on all inliers, then recompute the inliers (a few rounds)
    inliers = best_inliers
    for _ in range(5):
        H = homography_dlt(src[inliers], dst[inliers])
        new_inliers = _transfer_error(H, src, dst) < threshold
        if new_inliers.sum() < 4 or np.array_equal(new_inliers, inliers):
            break
        inliers = new_inliers
    H = homography_dlt(src[inliers], dst[inliers])
    inliers = _transfer_error(H, src, dst) < threshold
    return H, inliers


# --------------------------------------------------------------------- ex5
def _corners(img):
    h, w = img.shape[:2]
    return np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]],
                     dtype=np.float64)


def _to_colour(img):
    return cv2.cvtColor(img, cv2.COLOR_GRAY2BGR) if img.ndim == 2 else img


def _composite(images, homographies):
    """Warp every image with its H into a common canvas and average overlaps."""
    all_corners = np.vstack([transform_points(H, _corners(img))
                             for img, H in zip(images, homographies)])
    x_min = int(np.floor(all_corners[:, 0].min()))
    y_min = int(np.floor(all_corners[:, 1].min()))
    x_max = int(np.ceil(all_corners[:, 0].max()))
    y_max = int(np.ceil(all_corners[:, 1].max()))
    out_w = x_max - x_min + 1
    out_h = y_max - y_min + 1
    # shift everything so the bounding box starts at (0, 0)
    T = np.array([[1.0, 0.0, -x_min],
                  [0.0, 1.0, -y_min],
                  [0.0, 0.0, 1.0]])

    acc = np.zeros((out_h, out_w, 3))
    count = np.zeros((out_h, out_w))
    for img, H in zip(images, homographies):
        vals, covered = _warp_float(_to_colour(img), T @ H, out_w, out_h)
        acc[covered] += vals[covered]
        count[covered] += 1
    pano = np.zeros_like(acc)
    has = count > 0
    pano[has] = acc[has] / count[has][:, None]
    return _to_uint8(pano)


def stitch(img1, img2):
    """A panorama of two overlapping images, in ``img1``'s frame."""
    pts1, pts2 = match_features(img1, img2)
    H21, _ = homography_ransac(pts2, pts1, threshold=3.0, seed=0)
    return _composite([img1, img2], [np.eye(3), H21])


# --------------------------------------------------------------------- ext2
def stitch_many(images):
    """A panorama of three or more overlapping images (middle one as reference)."""
    images = list(images)
    n = len(images)
    ref = n // 2
    # H_pair[i] maps image i+1 onto image i
    H_pair = []
    for i in range(n - 1):
        p_i, p_next = match_features(images[i], images[i + 1])
        H, _ = homography_ransac(p_next, p_i, threshold=3.0, seed=0)
        H_pair.append(H)

    # chain every image to the reference
    Hs = [None] * n
    Hs[ref] = np.eye(3)
    for i in range(ref + 1, n):        # right of the reference: i -> i-1 -> ... -> ref
        Hs[i] = Hs[i - 1] @ H_pair[i - 1]
    for i in range(ref - 1, -1, -1):   # left of it: i -> i+1 uses the inverse
        Hs[i] = Hs[i + 1] @ np.linalg.inv(H_pair[i])
    Hs = [H / H[2, 2] for H in Hs]
    return _composite(images, Hs)


# --------------------------------------------------------------------- ext3
def blend_multiband(img1, img2, mask, levels=4):
    """Laplacian-pyramid (multi-band) blending of two aligned images."""
    a = img1.astype(np.float32)
    b = img2.astype(np.float32)
    m = np.asarray(mask, dtype=np.float32)
    if a.ndim == 3:
        m = np.repeat(m[:, :, None], a.shape[2], axis=2)

    def gaussian(img):
        pyr = [img]
        for _ in range(levels - 1):
            pyr.append(cv2.pyrDown(pyr[-1]))
        return pyr

    def laplacian(img):
        g = gaussian(img)
        lap = []
        for i in range(levels - 1):
            h, w = g[i].shape[:2]
            lap.append(g[i] - cv2.pyrUp(g[i + 1], dstsize=(w, h)))
        lap.append(g[-1])
        return lap

    la, lb, gm = laplacian(a), laplacian(b), gaussian(m)
    blended = [gm[i] * la[i] + (1 - gm[i]) * lb[i] for i in range(levels)]

    out = blended[-1]
    for i in range(levels - 2, -1, -1):
        h, w = blended[i].shape[:2]
        out = cv2.pyrUp(out, dstsize=(w, h)) + blended[i]
    return np.clip(np.rint(out), 0, 255).astype(np.uint8)
