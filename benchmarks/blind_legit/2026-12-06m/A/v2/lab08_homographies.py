"""Lab 8 - image homographies (OpenCV version).

Where the lab sheet names an OpenCV function I use it: cv2.warpPerspective for
the warps, cv2.SIFT_create / cv2.BFMatcher / cv2.drawMatches for the features,
cv2.findHomography with cv2.RANSAC for the robust estimate. The DLT itself is
my own (the sheet asks for it), with Hartley's normalisation of both point
sets, and my homographies are scaled to unit Frobenius norm (any scale is
allowed). The panorama is blended by feathering (distance-transform weights).

Conventions: points are (x, y) = (column, row), origin at the centre of the
top-left pixel, y pointing down. dsize is (width, height) as in OpenCV.
"""

import cv2
import numpy as np


# --------------------------------------------------------------------- ex1
def apply_homography(image, H, dsize=None):
    """Warp ``image`` by the homography ``H`` (source to output coordinates)."""
    if dsize is None:
        dsize = (image.shape[1], image.shape[0])
    return cv2.warpPerspective(image, np.asarray(H, dtype=np.float64),
                               (int(dsize[0]), int(dsize[1])),
                               flags=cv2.INTER_LINEAR,
                               borderMode=cv2.BORDER_CONSTANT, borderValue=0)


def transform_points(H, pts):
    """Map points by ``H``, with the perspective division."""
    pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    if len(pts) == 0:
        return np.zeros((0, 2))
    out = cv2.perspectiveTransform(pts.reshape(-1, 1, 2),
                                   np.asarray(H, dtype=np.float64))
    return out.reshape(-1, 2)


# --------------------------------------------------------------------- ex2
def _normalising_transform(pts):
    """Hartley: centroid to the origin, mean distance sqrt(2)."""
    centroid = pts.mean(axis=0)
    mean_dist = np.mean(np.linalg.norm(pts - centroid, axis=1))
    s = np.sqrt(2) / mean_dist if mean_dist > 0 else 1.0
    return np.array([[s, 0, -s * centroid[0]],
                     [0, s, -s * centroid[1]],
                     [0, 0, 1.0]])


def homography_dlt(src, dst):
    """The homography with ``dst ~ H @ src``, by the normalised DLT (SVD).

    Both point sets are normalised (T_src, T_dst), the 2N x 9 system is built
    in one go with NumPy and solved by SVD, and the result is denormalised:
    H = inv(T_dst) @ H_n @ T_src.
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    T1 = _normalising_transform(src)
    T2 = _normalising_transform(dst)
    s = transform_points(T1, src)
    d = transform_points(T2, dst)

    n = len(s)
    x, y = s[:, 0], s[:, 1]
    u, v = d[:, 0], d[:, 1]
    one, zero = np.ones(n), np.zeros(n)
    A = np.empty((2 * n, 9))
    A[0::2] = np.column_stack([x, y, one, zero, zero, zero, -u * x, -u * y, -u])
    A[1::2] = np.column_stack([zero, zero, zero, x, y, one, -v * x, -v * y, -v])

    _, _, Vt = np.linalg.svd(A, full_matrices=True)
    Hn = Vt[-1].reshape(3, 3)
    H = np.linalg.inv(T2) @ Hn @ T1
    return H / np.linalg.norm(H)


def warp_to_reference(reference, moving, H):
    """``moving`` warped into ``reference``'s frame (H: moving -> reference)."""
    return apply_homography(moving, H, dsize=(reference.shape[1], reference.shape[0]))


# --------------------------------------------------------------------- ex3
def match_features(img1, img2, ratio=0.75, method="sift"):
    """Match keypoints between two images with Lowe's ratio test."""
    g1 = cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY) if img1.ndim == 3 else img1
    g2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY) if img2.ndim == 3 else img2
    if method == "orb":
        detector, norm = cv2.ORB_create(nfeatures=1000), cv2.NORM_HAMMING
    elif method == "sift":
        detector, norm = cv2.SIFT_create(), cv2.NORM_L2
    else:
        raise ValueError(f"unknown method {method!r}")

    kp1, des1 = detector.detectAndCompute(g1, None)
    kp2, des2 = detector.detectAndCompute(g2, None)
    empty = np.zeros((0, 2))
    if des1 is None or des2 is None or len(kp2) < 2:
        return empty, empty.copy()

    knn = cv2.BFMatcher(norm, crossCheck=False).knnMatch(des1, des2, k=2)
    good = [m for m, *rest in (p for p in knn if len(p) == 2)
            if m.distance < ratio * rest[0].distance]
    if not good:
        return empty, empty.copy()
    pts1 = np.float64([kp1[m.queryIdx].pt for m in good])
    pts2 = np.float64([kp2[m.trainIdx].pt for m in good])
    return pts1, pts2


def draw_matches(img1, img2, pts1, pts2):
    """Both images side by side with a line for each match (cv2.drawMatches)."""
    a = cv2.cvtColor(img1, cv2.COLOR_GRAY2BGR) if img1.ndim == 2 else img1
    b = cv2.cvtColor(img2, cv2.COLOR_GRAY2BGR) if img2.ndim == 2 else img2
    pts1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
    pts2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
    kp1 = [cv2.KeyPoint(float(x), float(y), 5) for x, y in pts1]
    kp2 = [cv2.KeyPoint(float(x), float(y), 5) for x, y in pts2]
    matches = [cv2.DMatch(i, i, 0.0) for i in range(len(kp1))]
    h = max(a.shape[0], b.shape[0])
    out = np.zeros((h, a.shape[1] + b.shape[1], 3), dtype=np.uint8)
    out = cv2.drawMatches(a, kp1, b, kp2, matches, out,
                          matchColor=(0, 255, 255), singlePointColor=(0, 0, 255),
                          flags=cv2.DrawMatchesFlags_NOT_DRAW_SINGLE_POINTS)
    return out


# --------------------------------------------------------------------- ex4
def homography_ransac(src, dst, threshold=3.0, seed=None):
    """A robust homography: cv2.findHomography with cv2.RANSAC.

    OpenCV draws its own samples (``seed`` is not used), refits H on the
    inliers and returns the inlier mask.
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    H, mask = cv2.findHomography(src, dst, cv2.RANSAC, float(threshold))
    if H is None:
        # OpenCV found no model; fall back on the DLT over every pair
        H = homography_dlt(src, dst)
        err = np.linalg.norm(transform_points(H, src) - dst, axis=1)
        return H, err < threshold
    return H, mask.ravel().astype(bool)


# --------------------------------------------------------------------- ex5
def _corners(img):
    h, w = img.shape[:2]
    return np.float64([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]])


def _feather_composite(images, homographies):
    """Warp all images into one canvas; blend with distance-transform weights."""
    pts = np.vstack([transform_points(H, _corners(im))
                     for im, H in zip(images, homographies)])
    x_min, y_min = np.floor(pts.min(axis=0)).astype(int)
    x_max, y_max = np.ceil(pts.max(axis=0)).astype(int)
    size = (int(x_max - x_min + 1), int(y_max - y_min + 1))
    T = np.float64([[1, 0, -x_min], [0, 1, -y_min], [0, 0, 1]])

    acc = np.zeros((size[1], size[0], 3), np.float32)
    wsum = np.zeros((size[1], size[0]), np.float32)
    for im, H in zip(images, homographies):
        if im.ndim == 2:
            im = cv2.cvtColor(im, cv2.COLOR_GRAY2BGR)
        M = T @ H
        warped = cv2.warpPerspective(im, M, size, flags=cv2.INTER_LINEAR,
                                     borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        ones = np.full(im.shape[:2], 255, np.uint8)
        cover = cv2.warpPerspective(ones, M, size, flags=cv2.INTER_LINEAR,
                                    borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        cover = (cover == 255).astype(np.uint8)
        # weight grows with the distance to the image's border
        weight = cv2.distanceTransform(cover, cv2.DIST_L2, 3)
        acc += weight[:, :, None] * warped.astype(np.float32)
        wsum += weight
    pano = np.zeros_like(acc)
    ok = wsum > 0
    pano[ok] = acc[ok] / wsum[ok][:, None]
    return np.clip(np.rint(pano), 0, 255).astype(np.uint8)


def stitch(img1, img2):
    """A panorama of two overlapping images, in ``img1``'s frame."""
    pts1, pts2 = match_features(img1, img2)
    H21, _ = homography_ransac(pts2, pts1, threshold=3.0)
    H21 = H21 / H21[2, 2]
    return _feather_composite([img1, img2], [np.eye(3), H21])


# --------------------------------------------------------------------- ext2
def stitch_many(images):
    """A panorama of three or more overlapping images, in the first one's frame.

    H_{i+1 -> i} from matches between neighbours, chained:
    H_{k -> 0} = H_{1 -> 0} @ H_{2 -> 1} @ ... @ H_{k -> k-1}.
    """
    images = list(images)
    Hs = [np.eye(3)]
    for i in range(1, len(images)):
        p_prev, p_cur = match_features(images[i - 1], images[i])
        H, _ = homography_ransac(p_cur, p_prev, threshold=3.0)
        H_total = Hs[-1] @ H
        Hs.append(H_total / H_total[2, 2])
    return _feather_composite(images, Hs)


# --------------------------------------------------------------------- ext3
def blend_multiband(img1, img2, mask, levels=4):
    """Laplacian-pyramid (multi-band) blending of two aligned images.

    My pyramid: blur with a 5x5 Gaussian and keep every second row and column
    to go down; bilinear resize to go back up. Each Laplacian level is the
    difference between a level and its upsampled coarser level, so collapsing
    the pyramid gives the image back exactly.
    """
    def down(img):
        return cv2.GaussianBlur(img, (5, 5), 1.0)[::2, ::2].copy()

    def up(img, shape):
        return cv2.resize(img, (shape[1], shape[0]), interpolation=cv2.INTER_LINEAR)

    a = img1.astype(np.float32)
    b = img2.astype(np.float32)
    m = np.clip(np.asarray(mask, np.float32), 0, 1)

    ga, gb, gm = [a], [b], [m]
    for _ in range(levels - 1):
        ga.append(down(ga[-1]))
        gb.append(down(gb[-1]))
        gm.append(down(gm[-1]))

    out = None
    for i in range(levels - 1, -1, -1):
        if i == levels - 1:
            la, lb = ga[i], gb[i]
        else:
            la = ga[i] - up(ga[i + 1], ga[i].shape)
            lb = gb[i] - up(gb[i + 1], gb[i].shape)
        w = gm[i][:, :, None] if a.ndim == 3 else gm[i]
        level = w * la + (1 - w) * lb
        out = level if out is None else up(out, level.shape) + level
    return np.clip(np.rint(out), 0, 255).astype(np.uint8)
