"""Lab 8 - image homographies.

Short route: NumPy for the algebra, OpenCV for warps, features, RANSAC
(``cv2.findHomography`` as on the lab sheet) and pyramids.

Conventions: images uint8 grey or BGR; points (N, 2) as (x, y), x = column,
y = row, y down; H maps (x, y, 1) to (u, v, w) -> (u/w, v/w), any scale.
"""

import cv2
import numpy as np


def _size(img):
    return (img.shape[1], img.shape[0])


# --------------------------------------------------------------------- ex1
def apply_homography(image, H, dsize=None):
    """Warp by H (source -> output), bilinear, black fill."""
    image = np.asarray(image)
    return cv2.warpPerspective(image, np.asarray(H, np.float64),
                               _size(image) if dsize is None else tuple(int(v) for v in dsize),
                               flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)


def transform_points(H, pts):
    """(u/w, v/w) for (u, v, w) = H @ (x, y, 1), vectorised."""
    p = np.c_[np.asarray(pts, np.float64).reshape(-1, 2), np.ones(np.size(pts) // 2)] @ np.asarray(H, np.float64).T
    return p[:, :2] / p[:, 2:]


# --------------------------------------------------------------------- ex2
def _normaliser(p):
    """Hartley similarity: centroid to origin, mean distance sqrt(2)."""
    c = p.mean(0)
    d = np.linalg.norm(p - c, axis=1).mean()
    s = np.sqrt(2) / d if d > 0 else 1.0
    return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])


def homography_dlt(src, dst):
    """Normalised DLT: 2N x 9 system A h = 0, h = last right singular vector."""
    src = np.asarray(src, np.float64).reshape(-1, 2)
    dst = np.asarray(dst, np.float64).reshape(-1, 2)
    Ts, Td = _normaliser(src), _normaliser(dst)
    s, d = transform_points(Ts, src), transform_points(Td, dst)
    n = len(s)
    x, y, u, v = s[:, 0], s[:, 1], d[:, 0], d[:, 1]
    o, z = np.ones(n), np.zeros(n)
    A = np.empty((2 * n, 9))
    A[0::2] = np.c_[x, y, o, z, z, z, -u * x, -u * y, -u]
    A[1::2] = np.c_[z, z, z, x, y, o, -v * x, -v * y, -v]
    Hn = np.linalg.svd(A)[2][-1].reshape(3, 3)
    H = np.linalg.inv(Td) @ Hn @ Ts
    return H / H[2, 2] if abs(H[2, 2]) > 1e-12 else H / np.linalg.norm(H)


def warp_to_reference(reference, moving, H):
    """``moving`` warped by H into ``reference``'s size."""
    return apply_homography(moving, H, _size(np.asarray(reference)))


# --------------------------------------------------------------------- ex3
def _grey(img):
    img = np.asarray(img)
    return cv2.cvtColor(img, cv2.COLOR_BGR2GRAY) if img.ndim == 3 else img


def match_features(img1, img2, ratio=0.75, method="sift"):
    """SIFT (L2) or ORB (Hamming) + BFMatcher knnMatch(k=2) + Lowe's ratio test."""
    if method == "orb":
        det, norm = cv2.ORB_create(nfeatures=1000), cv2.NORM_HAMMING
    elif method == "sift":
        det, norm = cv2.SIFT_create(), cv2.NORM_L2
    else:
        raise ValueError(f"unknown method {method!r}")
    k1, d1 = det.detectAndCompute(_grey(img1), None)
    k2, d2 = det.detectAndCompute(_grey(img2), None)
    empty = np.zeros((0, 2))
    if d1 is None or d2 is None or len(k1) == 0 or len(k2) < 2:
        return empty, empty.copy()
    good = [m[0] for m in cv2.BFMatcher(norm).knnMatch(d1, d2, k=2)
            if len(m) == 2 and m[0].distance < ratio * m[1].distance]
    if not good:
        return empty, empty.copy()
    return (np.array([k1[m.queryIdx].pt for m in good], np.float64),
            np.array([k2[m.trainIdx].pt for m in good], np.float64))


def draw_matches(img1, img2, pts1, pts2):
    """cv2.drawMatches on keypoints built from the point lists."""
    bgr = lambda im: cv2.cvtColor(im, cv2.COLOR_GRAY2BGR) if im.ndim == 2 else im
    img1, img2 = bgr(np.ascontiguousarray(img1)), bgr(np.ascontiguousarray(img2))
    kp = lambda P: [cv2.KeyPoint(float(x), float(y), 5) for x, y in np.asarray(P, float).reshape(-1, 2)]
    k1, k2 = kp(pts1), kp(pts2)
    matches = [cv2.DMatch(i, i, 0.0) for i in range(len(k1))]
    return cv2.drawMatches(img1, k1, img2, k2, matches, None, matchColor=(0, 255, 0),
                           singlePointColor=(0, 255, 0),
                           flags=cv2.DrawMatchesFlags_NOT_DRAW_SINGLE_POINTS)


# --------------------------------------------------------------------- ex4
def homography_ransac(src, dst, threshold=3.0, seed=None):
    """cv2.findHomography with cv2.RANSAC (deterministic, so ``seed`` is unused)."""
    src = np.asarray(src, np.float64).reshape(-1, 2)
    dst = np.asarray(dst, np.float64).reshape(-1, 2)
    H, mask = cv2.findHomography(src, dst, cv2.RANSAC, float(threshold))
    if H is None:  # degenerate input: fall back to plain DLT on everything
        return homography_dlt(src, dst), np.ones(len(src), bool)
    return H, mask.ravel().astype(bool)


# --------------------------------------------------------------------- ex5
def _corners(img):
    h, w = img.shape[:2]
    return np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], np.float64)


def _composite(images, Hs):
    """Warp every image with its H into one canvas, feathered by distance to border."""
    pts = np.vstack([transform_points(H, _corners(im)) for im, H in zip(images, Hs)])
    x0, y0 = np.floor(pts.min(0)).astype(int)
    x1, y1 = np.ceil(pts.max(0)).astype(int)
    size = (x1 - x0 + 1, y1 - y0 + 1)
    T = np.array([[1.0, 0, -x0], [0, 1, -y0], [0, 0, 1]])
    acc = np.zeros((size[1], size[0], 3))
    wsum = np.zeros((size[1], size[0]))
    for im, H in zip(images, Hs):
        im = cv2.cvtColor(im, cv2.COLOR_GRAY2BGR) if im.ndim == 2 else im
        # weight = distance to the image's own border (+1 so edge pixels count)
        m = np.pad(np.ones(im.shape[:2], np.uint8), 1)
        w = cv2.distanceTransform(m, cv2.DIST_L2, 5)[1:-1, 1:-1]
        w = cv2.warpPerspective(w, T @ H, size, flags=cv2.INTER_LINEAR)
        # replicate the border so edge pixels are not darkened; w is 0 outside anyway
        acc += cv2.warpPerspective(im, T @ H, size, flags=cv2.INTER_LINEAR,
                                   borderMode=cv2.BORDER_REPLICATE).astype(np.float64) * w[..., None]
        wsum += w
    out = acc / np.maximum(wsum, 1e-9)[..., None]
    return np.clip(np.rint(out), 0, 255).astype(np.uint8)


def stitch(img1, img2):
    """Panorama in img1's frame: SIFT matches, RANSAC H (img2 -> img1), feathered."""
    p1, p2 = match_features(img1, img2)
    H, _ = homography_ransac(p2, p1)
    return _composite([img1, img2], [np.eye(3), H])


# --------------------------------------------------------------------- ext2
def stitch_many(images):
    """Chain neighbour homographies to the middle image and composite."""
    images = list(images)
    r = len(images) // 2
    pair = []  # pair[i] maps image i+1 onto image i
    for a, b in zip(images, images[1:]):
        pa, pb = match_features(a, b)
        pair.append(homography_ransac(pb, pa)[0])
    Hs = [np.eye(3)] * len(images)
    for i in range(r + 1, len(images)):   # right of the reference
        Hs[i] = Hs[i - 1] @ pair[i - 1]
    for i in range(r - 1, -1, -1):        # left of the reference
        Hs[i] = Hs[i + 1] @ np.linalg.inv(pair[i])
    Hs = [H / H[2, 2] for H in Hs]
    return _composite(images, Hs)


# --------------------------------------------------------------------- ext3
def blend_multiband(img1, img2, mask, levels=4):
    """Laplacian-pyramid blend; ``mask`` weights img1."""
    a, b = np.float32(img1), np.float32(img2)
    m = np.float32(mask)
    if a.ndim == 3:
        m = np.repeat(m[..., None], a.shape[2], 2)
    G = [(a, b, m)]
    for _ in range(levels - 1):
        G.append(tuple(cv2.pyrDown(x) for x in G[-1]))
    up = lambda x, ref: cv2.pyrUp(x, dstsize=(ref.shape[1], ref.shape[0])).reshape(ref.shape)
    out = G[-1][2] * G[-1][0] + (1 - G[-1][2]) * G[-1][1]
    for i in range(levels - 2, -1, -1):
        ga, gb, gm = G[i]
        la, lb = ga - up(G[i + 1][0], ga), gb - up(G[i + 1][1], gb)
        out = up(out, ga) + gm * la + (1 - gm) * lb
    return np.clip(np.rint(out), 0, 255).astype(np.uint8)
