"""Lab 8 - image homographies (reference solution).

A homography H is a 3x3 matrix acting on homogeneous pixel coordinates: the
point (x, y) goes to (u / w, v / w) with (u, v, w) = H (x, y, 1). It is defined
up to scale. Estimating it from point pairs (DLT), making the estimate robust to
wrong matches (RANSAC) and warping images with it is all it takes to stitch a
panorama.
"""

import cv2
import numpy as np


# --------------------------------------------------------------------- ex1
def apply_homography(image, H, dsize=None):
    """Warp ``image`` by H (source to output coordinates), bilinear, black fill.

    ``cv2.warpPerspective`` computes, for every output pixel, the source position
    ``H^-1 (x, y, 1)`` (with the perspective division) and samples it there.
    """
    height, width = image.shape[:2]
    return cv2.warpPerspective(image, np.asarray(H, dtype=np.float64), dsize or (width, height),
                               flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT,
                               borderValue=0)


def transform_points(H, pts):
    """Map (N, 2) points by H: append 1, multiply, divide by the third coordinate."""
    pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
    homogeneous = np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(H, dtype=np.float64).T
    return homogeneous[:, :2] / homogeneous[:, 2:3]


# --------------------------------------------------------------------- ex2
def _normalisation(pts):
    """Hartley's similarity: centroid to the origin, mean distance sqrt(2)."""
    centroid = pts.mean(axis=0)
    mean_distance = np.linalg.norm(pts - centroid, axis=1).mean()
    s = np.sqrt(2.0) / mean_distance if mean_distance > 0 else 1.0
    return np.array([[s, 0.0, -s * centroid[0]],
                     [0.0, s, -s * centroid[1]],
                     [0.0, 0.0, 1.0]])


def _dlt_rows(src, dst):
    """The 2N x 9 matrix A with A h = 0 for h = H.ravel() (two rows per pair)."""
    n = len(src)
    x, y = src[:, 0], src[:, 1]
    u, v = dst[:, 0], dst[:, 1]
    ones, zeros = np.ones(n), np.zeros(n)
    rows_u = np.stack([x, y, ones, zeros, zeros, zeros, -u * x, -u * y, -u], axis=1)
    rows_v = np.stack([zeros, zeros, zeros, x, y, ones, -v * x, -v * y, -v], axis=1)
    A = np.empty((2 * n, 9))
    A[0::2], A[1::2] = rows_u, rows_v
    return A


def homography_dlt(src, dst):
    """Normalised DLT: H with dst ~ H src from N >= 4 pairs, by SVD.

    1. Normalise both point sets (T1 src, T2 dst) so the numbers in the system
       are of order 1 -- with raw pixel coordinates (hundreds), the x*u terms
       (1e5) swamp the constant ones and the solution is biased under noise.
    2. Two rows per pair; h is the right singular vector of the smallest singular
       value (the unit vector minimising |A h|).
    3. Undo the normalisation: H = T2^-1 H~ T1, and scale so H[2, 2] = 1.
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    T1, T2 = _normalisation(src), _normalisation(dst)
    src_n = src @ T1[:2, :2].T + T1[:2, 2]
    dst_n = dst @ T2[:2, :2].T + T2[:2, 2]
    A = _dlt_rows(src_n, dst_n)
    # A reduced SVD is enough for N >= 5 (2N >= 9 rows); with 4 pairs A is 8x9 and
    # only the full SVD has the 9th right singular vector, the null vector.
    _, _, Vt = np.linalg.svd(A, full_matrices=len(A) < 9)
    H = np.linalg.inv(T2) @ Vt[-1].reshape(3, 3) @ T1
    return H / H[2, 2] if abs(H[2, 2]) > 1e-12 else H / np.linalg.norm(H)


def warp_to_reference(reference, moving, H):
    """``moving`` warped into ``reference``'s frame (and size); H maps moving to reference."""
    height, width = reference.shape[:2]
    return apply_homography(moving, H, (width, height))


# --------------------------------------------------------------------- ex3
def _grey(image):
    return image if image.ndim == 2 else cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)


def _detect(image, method="sift"):
    """Keypoint positions (K, 2) and descriptors of an image."""
    if method == "sift":
        detector = cv2.SIFT_create()
    elif method == "orb":
        detector = cv2.ORB_create(nfeatures=1000)
    else:
        raise ValueError(f"unknown method {method!r}; use 'sift' or 'orb'")
    keypoints, descriptors = detector.detectAndCompute(_grey(image), None)
    points = np.array([k.pt for k in keypoints], dtype=np.float64).reshape(-1, 2)
    return points, descriptors


def _match(features1, features2, ratio, method="sift"):
    """Lowe's ratio test on two (points, descriptors) sets -> (pts1, pts2)."""
    (points1, descriptors1), (points2, descriptors2) = features1, features2
    empty = np.zeros((0, 2))
    if descriptors1 is None or descriptors2 is None or len(points2) < 2:
        return empty, empty.copy()
    norm = cv2.NORM_HAMMING if method == "orb" else cv2.NORM_L2
    pairs = cv2.BFMatcher(norm).knnMatch(descriptors1, descriptors2, k=2)
    good = [best for best, second in (p for p in pairs if len(p) == 2)
            if best.distance < ratio * second.distance]
    query = np.array([m.queryIdx for m in good], dtype=int)
    train = np.array([m.trainIdx for m in good], dtype=int)
    return points1[query].reshape(-1, 2), points2[train].reshape(-1, 2)


def match_features(img1, img2, ratio=0.75, method="sift"):
    """Keypoints matched between two images, filtered by Lowe's ratio test.

    For every descriptor of ``img1`` find its two nearest neighbours in ``img2``;
    keep the match only when the best is clearly better than the second best
    (``best < ratio * second``). SIFT descriptors are compared with the L2 norm,
    ORB's binary descriptors with the Hamming distance.
    """
    return _match(_detect(img1, method), _detect(img2, method), ratio, method)


def _bgr(image):
    return cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image


def draw_matches(img1, img2, pts1, pts2):
    """Both images side by side (img2 shifted right by img1's width), a line per match."""
    h1, w1 = img1.shape[:2]
    h2, w2 = img2.shape[:2]
    canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
    canvas[:h1, :w1] = _bgr(img1)
    canvas[:h2, w1:] = _bgr(img2)
    rng = np.random.default_rng(0)
    for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
        colour = tuple(int(c) for c in rng.integers(64, 256, size=3))
        a = (int(round(x1)), int(round(y1)))
        b = (int(round(x2 + w1)), int(round(y2)))
        cv2.line(canvas, a, b, colour, 1, cv2.LINE_AA)
        cv2.circle(canvas, a, 3, colour, 1, cv2.LINE_AA)
        cv2.circle(canvas, b, 3, colour, 1, cv2.LINE_AA)
    return canvas


# --------------------------------------------------------------------- ex4
def _transfer_errors(Hs, src, dst):
    """|H src - dst| for a stack of homographies: (K, 3, 3) -> (K, N)."""
    homogeneous = np.hstack([src, np.ones((len(src), 1))])
    mapped = np.einsum("kij,nj->kni", Hs, homogeneous)
    with np.errstate(divide="ignore", invalid="ignore"):
        xy = mapped[..., :2] / mapped[..., 2:3]
    errors = np.linalg.norm(xy - dst, axis=2)
    return np.where(np.isfinite(errors), errors, np.inf)


def _minimal_solutions(src_n, dst_n, samples):
    """One DLT per 4-point sample, all at once: (K, 4) indices -> (K, 3, 3)."""
    K = len(samples)
    A = _dlt_rows(src_n[samples].reshape(-1, 2), dst_n[samples].reshape(-1, 2))
    A = A.reshape(K, 4, 2, 9).reshape(K, 8, 9)
    _, _, Vt = np.linalg.svd(A)
    return Vt[:, -1].reshape(K, 3, 3)


def homography_ransac(src, dst, threshold=3.0, seed=None, confidence=0.999, max_iterations=5000):
    """Robust homography: RANSAC over 4-point samples, then a DLT refit on the inliers."""
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    n = len(src)
    if n < 4:
        raise ValueError("need at least 4 correspondences")
    rng = np.random.default_rng(seed)
    best_inliers = np.zeros(n, dtype=bool)
    needed = max_iterations
    it = 0
    while it < min(needed, max_iterations):
        it += 1
        idx = rng.choice(n, 4, replace=False)
        H = homography_dlt(src[idx], dst[idx])
        if not np.all(np.isfinite(H)):
            continue
        proj = transform_points(H, src)
        err = np.sum((proj - dst) ** 2, axis=1)
        inliers = err < threshold
        if inliers.sum() > best_inliers.sum():
            best_inliers = inliers
            w = inliers.sum() / n
            needed = int(np.ceil(np.log(1 - confidence) / np.log(max(1 - w ** 4, 1e-12))))
    if best_inliers.sum() < 4:
        return homography_dlt(src, dst), np.ones(n, dtype=bool)
    H = homography_dlt(src[best_inliers], dst[best_inliers])
    err = np.sum((transform_points(H, src) - dst) ** 2, axis=1)
    inliers = err < threshold
    if inliers.sum() >= 4:
        H = homography_dlt(src[inliers], dst[inliers])
    else:
        inliers = best_inliers
    return H, inliers


# --------------------------------------------------------------------- ex5
def _translation(tx, ty):
    return np.array([[1.0, 0.0, tx], [0.0, 1.0, ty], [0.0, 0.0, 1.0]])


def _corners(image):
    h, w = image.shape[:2]
    return np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], dtype=np.float64)


def _pairwise_homography(moving, reference):
    """H mapping ``moving``'s pixels onto ``reference``'s (features + RANSAC).

    ``moving`` and ``reference`` are images, or their precomputed ``_detect`` features.
    """
    features = [_detect(i) if isinstance(i, np.ndarray) else i for i in (reference, moving)]
    pts_ref, pts_mov = _match(features[0], features[1], ratio=0.75)
    if len(pts_ref) < 4:
        raise ValueError("not enough matches to relate the images")
    H, _ = homography_ransac(pts_mov, pts_ref, threshold=3.0, seed=0)
    return H


def _compose(images, homographies):
    """Warp every image by its H (into a common frame), on the smallest canvas, feathered.

    The canvas is the bounding box of all warped corners; a translation moves
    its top-left corner to (0, 0). Where images overlap, each pixel is a
    weighted mean, the weight growing with the distance to the image's border,
    so seams fade out.
    """
    corners = np.vstack([transform_points(H, _corners(im)) for im, H in zip(images, homographies)])
    x_min, y_min = np.floor(corners.min(axis=0))
    x_max, y_max = np.ceil(corners.max(axis=0))
    shift = _translation(-x_min, -y_min)  # integer shift: the reference is copied exactly
    size = (int(x_max - x_min) + 1, int(y_max - y_min) + 1)
    total = np.zeros((size[1], size[0], 3), np.float64)
    weights = np.zeros((size[1], size[0]), np.float64)
    for image, H in zip(images, homographies):
        h, w = image.shape[:2]
        ones = np.zeros((h + 2, w + 2), np.uint8)
        ones[1:-1, 1:-1] = 1
        border_distance = cv2.distanceTransform(ones, cv2.DIST_L2, 3)[1:-1, 1:-1]
        warped = apply_homography(_bgr(image), shift @ H, size).astype(np.float64)
        weight = apply_homography(border_distance.astype(np.float32), shift @ H, size)
        total += warped * weight[..., None]
        weights += weight
    panorama = total / np.maximum(weights, 1e-9)[..., None]
    return np.clip(np.round(panorama), 0, 255).astype(np.uint8)


def stitch(img1, img2):
    """Panorama of two overlapping images in ``img1``'s frame (img1 only shifted)."""
    H21 = _pairwise_homography(img2, img1)
    return _compose([img1, img2], [np.eye(3), H21])


def stitch_many(images):
    """Panorama of 3+ images in left-to-right order, in the middle image's frame.

    Neighbours are registered pairwise (H_k maps image k+1 onto image k); the
    homography of image k into the reference r is the product of the chain
    between them, e.g. H_{3->1} = H_{2->1} @ H_{3->2}.
    """
    images = list(images)
    if len(images) < 2:
        raise ValueError("need at least two images")
    features = [_detect(image) for image in images]   # once per image
    step = [_pairwise_homography(features[k + 1], features[k]) for k in range(len(images) - 1)]
    r = len(images) // 2
    homographies = []
    for k in range(len(images)):
        H = np.eye(3)
        if k > r:      # k -> k-1 -> ... -> r
            for j in range(k - 1, r - 1, -1):
                H = step[j] @ H
        elif k < r:    # k -> k+1 -> ... -> r, with inverses
            for j in range(k, r):
                H = np.linalg.inv(step[j]) @ H
        homographies.append(H / H[2, 2])
    return _compose(images, homographies)


# --------------------------------------------------------------------- ext3
def _gaussian_pyramid(image, levels):
    pyramid = [image]
    for _ in range(levels - 1):
        pyramid.append(cv2.pyrDown(pyramid[-1]))
    return pyramid


def _laplacian_pyramid(image, levels):
    """Band-pass levels G_i - up(G_{i+1}), and the low-pass residual on top."""
    gaussian = _gaussian_pyramid(image, levels)
    bands = []
    for fine, coarse in zip(gaussian[:-1], gaussian[1:]):
        size = (fine.shape[1], fine.shape[0])
        bands.append(fine - cv2.pyrUp(coarse, dstsize=size))
    return bands + [gaussian[-1]]


def blend_multiband(img1, img2, mask, levels=4):
    """Laplacian-pyramid blending (Burt and Adelson).

    Each band of the two images is blended with the mask smoothed to the same
    scale (its Gaussian pyramid): fine detail switches sharply at the seam,
    coarse brightness changes fade over a wide region. Everything is computed in
    float (band-pass levels are negative in places). ``levels`` counts the
    pyramid levels including the full-resolution one, so the image is
    downsampled ``levels - 1`` times.
    """
    a = np.asarray(img1, dtype=np.float32)
    b = np.asarray(img2, dtype=np.float32)
    weights = _gaussian_pyramid(np.clip(np.asarray(mask, dtype=np.float32), 0, 1), levels)
    bands = []
    for band_a, band_b, w in zip(_laplacian_pyramid(a, levels), _laplacian_pyramid(b, levels), weights):
        if band_a.ndim == 3:
            w = w[..., None]
        bands.append(w * band_a + (1 - w) * band_b)
    result = bands[-1]
    for band in reversed(bands[:-1]):
        result = cv2.pyrUp(result, dstsize=(band.shape[1], band.shape[0])) + band
    return np.clip(np.round(result), 0, 255).astype(np.uint8)
