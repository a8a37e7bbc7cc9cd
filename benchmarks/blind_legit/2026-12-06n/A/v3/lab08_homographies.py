"""Lab 8 - image homographies.

My choices where the lab leaves room:
- ``homography_dlt`` is the lab sheet's DLT solved by SVD, conditioned by
  moving each point set's centroid to the origin and scaling it so that its
  farthest point is at distance 1 (instead of Hartley's mean sqrt(2)); H is
  returned with unit Frobenius norm and whatever sign makes ``H[2, 2] <= 0``
  (any scale and sign is the same homography).
- ``apply_homography`` hands OpenCV the inverse map itself
  (``inv(H)`` together with ``cv2.WARP_INVERSE_MAP``: the same warp).
- ``homography_ransac`` is my own loop: a batch of random 4-point samples,
  adaptive number of iterations, refit on the inliers until the set is stable.
- ``stitch`` blends the overlap by a plain average; ``stitch_many`` uses the
  first (leftmost) image as the reference frame.
- Keypoint coordinates are returned as float32 (as OpenCV stores them).
- Inputs may be lists, read-only or non-contiguous arrays; never modified.
"""

import cv2
import numpy as np


# ----------------------------------------------------------------- helpers
def _img(image):
    return np.ascontiguousarray(np.asarray(image))


def _pts(pts):
    return np.asarray(pts, dtype=np.float64).reshape(-1, 2)


def _grey(image):
    image = _img(image)
    if image.ndim == 3:
        return cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
    return image


def _bgr(image):
    image = _img(image)
    if image.ndim == 2:
        return cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
    return image


# --------------------------------------------------------------------- ex1
def apply_homography(image, H, dsize=None):
    """Warp ``image`` by ``H`` (source -> output), bilinear, black fill."""
    img = _img(image)
    H = np.asarray(H, dtype=np.float64).reshape(3, 3)
    if dsize is None:
        dsize = (img.shape[1], img.shape[0])
    dsize = (int(dsize[0]), int(dsize[1]))
    Hinv = np.linalg.inv(H)          # output -> source
    out = cv2.warpPerspective(img, Hinv, dsize,
                              flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP,
                              borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return out.reshape((dsize[1], dsize[0]) + img.shape[2:])


def transform_points(H, pts):
    """``(u/w, v/w)`` for ``(u, v, w) = H (x, y, 1)``, for every point."""
    H = np.asarray(H, dtype=np.float64).reshape(3, 3)
    p = _pts(pts)
    u = H[0, 0] * p[:, 0] + H[0, 1] * p[:, 1] + H[0, 2]
    v = H[1, 0] * p[:, 0] + H[1, 1] * p[:, 1] + H[1, 2]
    w = H[2, 0] * p[:, 0] + H[2, 1] * p[:, 1] + H[2, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.column_stack([u / w, v / w])


# --------------------------------------------------------------------- ex2
def _conditioner(p):
    """Similarity moving the centroid to 0 and the farthest point to distance 1."""
    c = p.mean(axis=0)
    r = np.sqrt(((p - c) ** 2).sum(axis=1)).max()
    k = 1.0 / r if r > 0 else 1.0
    return np.array([[k, 0.0, -k * c[0]], [0.0, k, -k * c[1]], [0.0, 0.0, 1.0]])


def homography_dlt(src, dst):
    """DLT: ``dst ~ H src`` from N >= 4 pairs, ``A h = 0`` solved by SVD.

    Raw pixel coordinates make the columns of A differ by ~1e6 and the answer
    sensitive to noise, so both point sets are first conditioned
    (``p_c = C p``), the DLT is solved for ``H_c`` and then
    ``H = inv(C_dst) @ H_c @ C_src``.
    """
    src_raw = _pts(src)
    dst_raw = _pts(dst)
    C_src = _conditioner(src_raw)
    C_dst = _conditioner(dst_raw)
    src = (src_raw - src_raw.mean(axis=0)) * C_src[0, 0]
    dst = (dst_raw - dst_raw.mean(axis=0)) * C_dst[0, 0]
    n = len(src)
    A = np.zeros((2 * n, 9))
    x, y = src[:, 0], src[:, 1]
    xp, yp = dst[:, 0], dst[:, 1]
    A[0::2, 0] = x
    A[0::2, 1] = y
    A[0::2, 2] = 1.0
    A[0::2, 6] = -xp * x
    A[0::2, 7] = -xp * y
    A[0::2, 8] = -xp
    A[1::2, 3] = x
    A[1::2, 4] = y
    A[1::2, 5] = 1.0
    A[1::2, 6] = -yp * x
    A[1::2, 7] = -yp * y
    A[1::2, 8] = -yp
    _, _, Vt = np.linalg.svd(A, full_matrices=True)
    H = np.linalg.inv(C_dst) @ Vt[-1].reshape(3, 3) @ C_src
    H = H / np.linalg.norm(H)
    if H[2, 2] > 0:
        H = -H
    return H


def warp_to_reference(reference, moving, H):
    """``moving`` warped by ``H`` into ``reference``'s frame and size."""
    ref = np.asarray(reference)
    return apply_homography(moving, H, dsize=(ref.shape[1], ref.shape[0]))


# --------------------------------------------------------------------- ex3
def match_features(img1, img2, ratio=0.75, method="sift"):
    """Keypoints matched with Lowe's ratio test; ``(pts1, pts2)`` float32 (M, 2).

    Matches are returned best first (sorted by descriptor distance).
    """
    method = str(method).lower()
    if method == "sift":
        detector, norm = cv2.SIFT_create(), cv2.NORM_L2
    elif method == "orb":
        detector, norm = cv2.ORB_create(nfeatures=1000), cv2.NORM_HAMMING
    else:
        raise ValueError("method must be 'sift' or 'orb'")
    kp1, des1 = detector.detectAndCompute(_grey(img1), None)
    kp2, des2 = detector.detectAndCompute(_grey(img2), None)
    empty = np.zeros((0, 2), dtype=np.float32)
    if des1 is None or des2 is None or len(kp1) == 0 or len(kp2) < 2:
        return empty, empty.copy()
    knn = cv2.BFMatcher(norm).knnMatch(des1, des2, k=2)
    good = [p[0] for p in knn
            if len(p) == 2 and p[0].distance < ratio * p[1].distance]
    good.sort(key=lambda m: m.distance)
    if not good:
        return empty, empty.copy()
    pts1 = np.float32([kp1[m.queryIdx].pt for m in good]).reshape(-1, 2)
    pts2 = np.float32([kp2[m.trainIdx].pt for m in good]).reshape(-1, 2)
    return pts1, pts2


def draw_matches(img1, img2, pts1, pts2):
    """Side-by-side canvas ``(max(H1,H2), W1+W2, 3)`` with one line per match."""
    a, b = _bgr(img1), _bgr(img2)
    h1, w1 = a.shape[:2]
    h2, w2 = b.shape[:2]
    canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
    canvas[:h1, :w1] = a
    canvas[:h2, w1:] = b
    rng = np.random.default_rng(0)           # fixed colours, one per match
    for p, q in zip(_pts(pts1), _pts(pts2)):
        color = tuple(int(c) for c in rng.integers(64, 256, size=3))
        p1 = (int(round(p[0])), int(round(p[1])))
        p2 = (int(round(q[0] + w1)), int(round(q[1])))
        cv2.line(canvas, p1, p2, color, 1, cv2.LINE_AA)
        cv2.circle(canvas, p1, 3, color, 1, cv2.LINE_AA)
        cv2.circle(canvas, p2, 3, color, 1, cv2.LINE_AA)
    return canvas


# --------------------------------------------------------------------- ex4
def _transfer_error(H, src, dst):
    proj = transform_points(H, src)
    err = np.linalg.norm(proj - dst, axis=1)
    return np.where(np.isfinite(err), err, np.inf)


def _degenerate(p):
    """True when three of the four sample points are (nearly) collinear."""
    for i, j, k in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)):
        d1, d2 = p[j] - p[i], p[k] - p[i]
        if abs(d1[0] * d2[1] - d1[1] * d2[0]) < 1e-6:
            return True
    return False


def homography_ransac(src, dst, threshold=3.0, seed=None):
    """RANSAC homography: ``(H, inliers)``, H refitted on its inliers."""
    src = _pts(src)
    dst = _pts(dst)
    n = len(src)
    rng = np.random.default_rng(seed)
    best_mask = np.zeros(n, dtype=bool)
    best_count = 0
    max_iter = 2000
    needed = max_iter
    it = 0
    while it < min(needed, max_iter):
        # draw a batch of samples at once: each row 4 distinct indices
        batch = np.argsort(rng.random((64, n)), axis=1)[:, :4]
        for idx in batch:
            it += 1
            if _degenerate(src[idx]) or _degenerate(dst[idx]):
                continue
            H = homography_dlt(src[idx], dst[idx])
            mask = _transfer_error(H, src, dst) < threshold
            count = int(mask.sum())
            if count > best_count:
                best_count, best_mask = count, mask
                w = count / n
                if w >= 1.0:
                    needed = 0
                else:
                    needed = int(np.ceil(np.log(0.01) / np.log(1.0 - w ** 4 + 1e-300)))
            if it >= min(needed, max_iter):
                break
    if best_count < 4:
        # nothing better found: fit everything
        H = homography_dlt(src, dst)
        return H, _transfer_error(H, src, dst) < threshold
    # refit on the inliers until the inlier set stops changing
    mask = best_mask
    H = homography_dlt(src[mask], dst[mask])
    for _ in range(5):
        new_mask = _transfer_error(H, src, dst) < threshold
        if new_mask.sum() < 4 or np.array_equal(new_mask, mask):
            break
        mask = new_mask
        H = homography_dlt(src[mask], dst[mask])
    mask = _transfer_error(H, src, dst) < threshold
    return H, mask


# --------------------------------------------------------------------- ex5
def _corners(image):
    h, w = image.shape[:2]
    return np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], dtype=np.float64)


def _homography_between(img_from, img_to):
    """H mapping ``img_from``'s pixels onto ``img_to``'s."""
    p_to, p_from = match_features(img_to, img_from)
    if len(p_to) < 4:
        raise ValueError("not enough matches to stitch these images")
    H, _ = homography_ransac(p_from, p_to, threshold=3.0, seed=0)
    return H


def _compose(images, Hs):
    """Warp every image by its H onto one canvas; average where they overlap."""
    corners = np.vstack([transform_points(H, _corners(im)) for im, H in zip(images, Hs)])
    x_min, y_min = np.floor(corners.min(axis=0))
    x_max, y_max = np.ceil(corners.max(axis=0))
    width = int(x_max - x_min) + 1
    height = int(y_max - y_min) + 1
    T = np.array([[1.0, 0.0, -x_min], [0.0, 1.0, -y_min], [0.0, 0.0, 1.0]])
    acc = np.zeros((height, width, 3), dtype=np.float64)
    cnt = np.zeros((height, width), dtype=np.float64)
    for im, H in zip(images, Hs):
        im = _bgr(im)
        M = T @ H
        warped = apply_homography(im, M, (width, height))
        # coverage with nearest neighbour so borders are not half-weighted
        cover = cv2.warpPerspective(np.full(im.shape[:2], 255, np.uint8), M,
                                    (width, height), flags=cv2.INTER_NEAREST,
                                    borderMode=cv2.BORDER_CONSTANT, borderValue=0) > 0
        acc[cover] += warped[cover]
        cnt[cover] += 1.0
    out = np.zeros_like(acc)
    seen = cnt > 0
    out[seen] = acc[seen] / cnt[seen][:, None]
    return np.clip(np.rint(out), 0, 255).astype(np.uint8)


def stitch(img1, img2):
    """Panorama of two images in ``img1``'s frame (img1 only shifted)."""
    H21 = _homography_between(img2, img1)
    return _compose([img1, img2], [np.eye(3), H21])


# --------------------------------------------------------------------- ext2
def stitch_many(images):
    """Panorama of a left-to-right list of images, in the first image's frame."""
    images = list(images)
    Hs = [np.eye(3)]
    for i in range(1, len(images)):
        H = _homography_between(images[i], images[i - 1])   # i -> i-1
        Hs.append(Hs[-1] @ H)                                # i -> 0
        Hs[-1] = Hs[-1] / Hs[-1][2, 2]
    return _compose(images, Hs)


# --------------------------------------------------------------------- ext3
def blend_multiband(img1, img2, mask, levels=4):
    """Laplacian-pyramid blend; ``mask`` is img1's weight in [0, 1]."""
    a = np.asarray(img1)
    b = np.asarray(img2)
    m = np.asarray(mask, dtype=np.float64)
    if m.ndim == 3:
        m = m[..., 0]
    levels = max(int(levels), 1)
    ga = [a.astype(np.float64)]
    gb = [b.astype(np.float64)]
    gm = [m]
    for _ in range(levels - 1):
        if min(ga[-1].shape[:2]) < 2:
            break
        ga.append(cv2.pyrDown(ga[-1]))
        gb.append(cv2.pyrDown(gb[-1]))
        gm.append(cv2.pyrDown(gm[-1]))

    def up(x, like):
        return cv2.pyrUp(x, dstsize=(like.shape[1], like.shape[0])).reshape(like.shape)

    top = len(ga) - 1
    out = None
    for i in range(top, -1, -1):
        if i == top:
            la, lb = ga[i], gb[i]
        else:
            la = ga[i] - up(ga[i + 1], ga[i])
            lb = gb[i] - up(gb[i + 1], gb[i])
        w = gm[i] if la.ndim == 2 else gm[i][..., None]
        band = w * la + (1.0 - w) * lb
        out = band if out is None else up(out, band) + band
    out = np.floor(out + 0.5)                      # round half up
    return np.clip(out, 0, 255).astype(np.uint8).reshape(a.shape)
