"""Lab 8 - image homographies.

Written after Hartley & Zisserman (ch. 4: normalised DLT, RANSAC), Szeliski
(ch. 8-9: feathering, multi-band blending) and the OpenCV / scikit-image
tutorials (feature matching, findHomography, warping).

Conventions: points (x, y), x = column, y = row, origin at the centre of the
top-left pixel, y down. H maps source pixels to output pixels and is defined up
to scale; I normalise to H[2, 2] = 1.
"""

import cv2
import numpy as np
from skimage.transform import ProjectiveTransform, pyramid_reduce, resize, warp


# --------------------------------------------------------------------- ex1
def apply_homography(image, H, dsize=None):
    """Warp ``image`` by ``H`` with scikit-image (bilinear, black outside).

    ``skimage.transform.warp`` wants the output -> input map, which is the
    inverse of the projective transform ``H``.
    """
    image = np.asarray(image)
    if dsize is None:
        dsize = (image.shape[1], image.shape[0])
    out_shape = (int(dsize[1]), int(dsize[0]))
    tform = ProjectiveTransform(matrix=np.asarray(H, dtype=np.float64))
    out = warp(image, tform.inverse, output_shape=out_shape, order=1,
               mode="constant", cval=0.0, preserve_range=True)
    return np.clip(np.round(out), 0, 255).astype(np.uint8)


def transform_points(H, pts):
    """Points mapped by ``H`` with the perspective division (``cv2.perspectiveTransform``)."""
    pts = np.asarray(pts, dtype=np.float64).reshape(-1, 1, 2)
    if len(pts) == 0:
        return np.zeros((0, 2))
    out = cv2.perspectiveTransform(pts, np.asarray(H, dtype=np.float64))
    return out.reshape(-1, 2)


# --------------------------------------------------------------------- ex2
def _normalising_similarity(pts):
    """Hartley's T: centroid to the origin, mean distance sqrt(2)."""
    c = pts.mean(axis=0)
    d = np.sqrt(((pts - c) ** 2).sum(axis=1)).mean()
    s = np.sqrt(2.0) / d if d > 0 else 1.0
    return np.array([[s, 0.0, -s * c[0]],
                     [0.0, s, -s * c[1]],
                     [0.0, 0.0, 1.0]])


def homography_dlt(src, dst):
    """Normalised DLT (Hartley & Zisserman, Algorithm 4.2), solved by SVD.

    Rows as in the lab sheet::

        [-x -y -1  0  0  0  x x'  y x'  x']
        [ 0  0  0 -x -y -1  x y'  y y'  y']
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    T1 = _normalising_similarity(src)
    T2 = _normalising_similarity(dst)
    s = (np.column_stack([src, np.ones(len(src))]) @ T1.T)[:, :2]
    d = (np.column_stack([dst, np.ones(len(dst))]) @ T2.T)[:, :2]

    rows = []
    for (x, y), (xp, yp) in zip(s, d):
        rows.append([-x, -y, -1, 0, 0, 0, x * xp, y * xp, xp])
        rows.append([0, 0, 0, -x, -y, -1, x * yp, y * yp, yp])
    A = np.array(rows)
    _, _, Vt = np.linalg.svd(A)          # full SVD: Vt is 9x9
    Hn = Vt[-1].reshape(3, 3)
    H = np.linalg.inv(T2) @ Hn @ T1
    return H / H[2, 2]


def warp_to_reference(reference, moving, H):
    """``moving`` seen in ``reference``'s frame (its size), black elsewhere."""
    h, w = np.asarray(reference).shape[:2]
    return apply_homography(moving, H, dsize=(w, h))


# --------------------------------------------------------------------- ex3
def _to_grey(img):
    img = np.ascontiguousarray(img)
    return cv2.cvtColor(img, cv2.COLOR_BGR2GRAY) if img.ndim == 3 else img


def _detect_and_match(img1, img2, ratio, method):
    if method == "sift":
        detector = cv2.SIFT_create()
        matcher = cv2.BFMatcher(cv2.NORM_L2)
    elif method == "orb":
        detector = cv2.ORB_create(nfeatures=1000)
        matcher = cv2.BFMatcher(cv2.NORM_HAMMING)
    else:
        raise ValueError(f"unknown method {method!r}")
    kp1, des1 = detector.detectAndCompute(_to_grey(img1), None)
    kp2, des2 = detector.detectAndCompute(_to_grey(img2), None)
    good = []
    if des1 is not None and des2 is not None and len(des2) >= 2:
        for pair in matcher.knnMatch(des1, des2, k=2):
            if len(pair) < 2:
                continue
            m, n = pair
            if m.distance < ratio * n.distance:      # Lowe's ratio test
                good.append(m)
    return kp1, kp2, good


def match_features(img1, img2, ratio=0.75, method="sift"):
    """Ratio-test matches as two ``(M, 2)`` float arrays of (x, y)."""
    kp1, kp2, good = _detect_and_match(img1, img2, ratio, method)
    pts1 = np.array([kp1[m.queryIdx].pt for m in good], dtype=np.float64).reshape(-1, 2)
    pts2 = np.array([kp2[m.trainIdx].pt for m in good], dtype=np.float64).reshape(-1, 2)
    return pts1, pts2


def draw_matches(img1, img2, pts1, pts2):
    """``cv2.drawMatches`` on keypoints made from the matched points."""
    def bgr(img):
        img = np.ascontiguousarray(img)
        return cv2.cvtColor(img, cv2.COLOR_GRAY2BGR) if img.ndim == 2 else img

    a, b = bgr(img1), bgr(img2)
    pts1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
    pts2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
    kp1 = [cv2.KeyPoint(float(x), float(y), 5) for x, y in pts1]
    kp2 = [cv2.KeyPoint(float(x), float(y), 5) for x, y in pts2]
    matches = [cv2.DMatch(i, i, 0.0) for i in range(len(kp1))]
    # drawMatches builds the (max(H1, H2), W1 + W2) canvas itself
    return cv2.drawMatches(a, kp1, b, kp2, matches, None,
                           matchColor=(0, 255, 0), singlePointColor=(0, 0, 255))


# --------------------------------------------------------------------- ex4
def homography_ransac(src, dst, threshold=3.0, seed=None):
    """``cv2.findHomography`` with ``cv2.RANSAC`` (the lab sheet's recipe).

    OpenCV refits H on the inliers itself; ``seed`` is not used (OpenCV has its
    own fixed random generator, so the answer is repeatable anyway).
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 1, 2)
    H, mask = cv2.findHomography(src, dst, cv2.RANSAC, float(threshold))
    if H is None:                      # degenerate input: fall back to plain DLT
        H = homography_dlt(src.reshape(-1, 2), dst.reshape(-1, 2))
        err = np.linalg.norm(transform_points(H, src) - dst.reshape(-1, 2), axis=1)
        return H, err < threshold
    return H, mask.ravel().astype(bool)


# --------------------------------------------------------------------- ex5
def _pairwise_h(img_a, img_b):
    """H mapping ``img_b``'s pixels onto ``img_a``'s (SIFT + RANSAC)."""
    pts_a, pts_b = match_features(img_a, img_b)
    if len(pts_a) < 4:
        raise ValueError("not enough matches between the images")
    H, _ = homography_ransac(pts_b, pts_a, threshold=3.0)
    return H


def _feather_weight(h, w):
    """Weight growing with the distance to the image border (Szeliski 9.3.2)."""
    inner = np.zeros((h + 2, w + 2), np.uint8)
    inner[1:-1, 1:-1] = 255
    dist = cv2.distanceTransform(inner, cv2.DIST_L2, 3)[1:-1, 1:-1]
    return dist.astype(np.float32)


def _feather_panorama(images, homographies):
    """Warp every image onto a common canvas and feather the overlaps."""
    corners = []
    for img, H in zip(images, homographies):
        h, w = img.shape[:2]
        c = np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], np.float64)
        corners.append(transform_points(H, c))
    corners = np.vstack(corners)
    x_min, y_min = np.floor(corners.min(axis=0)).astype(int)
    x_max, y_max = np.ceil(corners.max(axis=0)).astype(int)
    size = (x_max - x_min + 1, y_max - y_min + 1)          # (width, height)
    T = np.array([[1, 0, -x_min], [0, 1, -y_min], [0, 0, 1]], dtype=np.float64)

    acc = np.zeros((size[1], size[0], 3), np.float32)
    wsum = np.zeros((size[1], size[0]), np.float32)
    for img, H in zip(images, homographies):
        img = np.ascontiguousarray(img)
        if img.ndim == 2:
            img = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR)
        M = T @ H
        warped = cv2.warpPerspective(img, M, size, flags=cv2.INTER_LINEAR,
                                     borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        weight = cv2.warpPerspective(_feather_weight(*img.shape[:2]), M, size,
                                     flags=cv2.INTER_LINEAR,
                                     borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        acc += warped.astype(np.float32) * weight[..., None]
        wsum += weight
    pano = np.zeros_like(acc)
    ok = wsum > 1e-6
    pano[ok] = acc[ok] / wsum[ok][:, None]
    return np.clip(np.round(pano), 0, 255).astype(np.uint8)


def stitch(img1, img2):
    """Two-image panorama in ``img1``'s frame, feathered overlap."""
    H21 = _pairwise_h(img1, img2)            # img2 -> img1
    return _feather_panorama([img1, img2], [np.eye(3), H21])


# --------------------------------------------------------------------- ext2
def stitch_many(images):
    """Panorama of a left-to-right list, in the middle image's frame."""
    images = list(images)
    n = len(images)
    ref = n // 2
    # H_pair[i] maps image i+1 onto image i
    H_pair = [_pairwise_h(images[i], images[i + 1]) for i in range(n - 1)]
    Hs = [None] * n
    Hs[ref] = np.eye(3)
    for i in range(ref + 1, n):          # right of the reference: chain forward
        Hs[i] = Hs[i - 1] @ H_pair[i - 1]
    for i in range(ref - 1, -1, -1):     # left of it: inverses
        Hs[i] = Hs[i + 1] @ np.linalg.inv(H_pair[i])
    Hs = [H / H[2, 2] for H in Hs]
    return _feather_panorama(images, Hs)


# --------------------------------------------------------------------- ext3
def _reduce(img):
    """One Gaussian-pyramid step down (blur + halve), scikit-image."""
    return pyramid_reduce(img, downscale=2,
                          channel_axis=-1 if img.ndim == 3 else None,
                          preserve_range=True)


def _expand(img, shape):
    """Back up to ``shape`` by bilinear interpolation."""
    return resize(img, shape, order=1, mode="edge", anti_aliasing=False,
                  preserve_range=True)


def blend_multiband(img1, img2, mask, levels=4):
    """Burt & Adelson multi-band blending (Szeliski 9.3.4) with scikit-image.

    Each image is split into band-pass (Laplacian) levels
    ``L_i = G_i - expand(G_{i+1})`` plus the coarsest Gaussian level; the bands
    are mixed with the mask's Gaussian pyramid (so low frequencies blend over
    a wide region and fine detail over a narrow one) and the result is
    collapsed again with the same ``expand``.
    """
    a = np.asarray(img1).astype(np.float64)
    b = np.asarray(img2).astype(np.float64)
    m = np.asarray(mask, dtype=np.float64)

    ga, gb, gm = [a], [b], [m]
    for _ in range(levels - 1):
        ga.append(_reduce(ga[-1]))
        gb.append(_reduce(gb[-1]))
        gm.append(_reduce(gm[-1]))

    blended = []
    for i in range(levels):
        if i < levels - 1:
            la = ga[i] - _expand(ga[i + 1], ga[i].shape)
            lb = gb[i] - _expand(gb[i + 1], gb[i].shape)
        else:
            la, lb = ga[i], gb[i]
        w = gm[i] if la.ndim == 2 else gm[i][..., None]
        blended.append(w * la + (1.0 - w) * lb)

    out = blended[-1]
    for i in range(levels - 2, -1, -1):
        out = _expand(out, blended[i].shape) + blended[i]
    return np.clip(np.round(out), 0, 255).astype(np.uint8)
