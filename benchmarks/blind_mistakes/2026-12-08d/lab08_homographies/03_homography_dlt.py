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
    """Normalised DLT: H with dst ~ H src from N >= 4 pairs, by SVD."""
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    T_src = _normalisation(src)
    T_dst = _normalisation(dst)
    p = np.hstack([src, np.ones((len(src), 1))]) @ T_src.T
    q = np.hstack([dst, np.ones((len(dst), 1))]) @ T_dst.T
    A = np.zeros((2 * len(src), 9))
    for i in range(len(src)):
        x, y = p[i, 0], p[i, 1]
        u, v = q[i, 0], q[i, 1]
        A[2 * i] = [x, y, 1, 0, 0, 0, -u * x, -u * y, -u]
        A[2 * i + 1] = [0, 0, 0, x, y, 1, -v * x, -v * y, -v]
    U, S, Vt = np.linalg.svd(A, full_matrices=False)
    Hn = Vt[-1].reshape(3, 3)
    H = np.linalg.inv(T_dst) @ Hn @ T_src
    return H / H[2, 2]


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
    """Robust homography: RANSAC over 4-point samples, then a DLT refit on the inliers.

    Hypotheses are drawn in batches (vectorised); the number of samples adapts to
    the best inlier ratio w seen so far: log(1 - confidence) / log(1 - w^4).
    A pair is an inlier when its transfer error |H src - dst| is below
    ``threshold`` pixels.
    """
    src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
    dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
    n = len(src)
    if n < 4:
        raise ValueError("need at least 4 correspondences")
    rng = np.random.default_rng(seed)
    # Minimal solutions are computed in normalised coordinates (well conditioned)
    # and mapped back to pixels to count inliers.
    T1, T2 = _normalisation(src), _normalisation(dst)
    src_n = src @ T1[:2, :2].T + T1[:2, 2]
    dst_n = dst @ T2[:2, :2].T + T2[:2, 2]
    back = np.linalg.inv(T2)

    best_count, best_inliers, best_error = -1, None, np.inf
    needed, drawn, batch = max_iterations, 0, 256
    while drawn < min(needed, max_iterations):
        samples = np.argsort(rng.random((batch, n)), axis=1)[:, :4]
        Hs = back @ _minimal_solutions(src_n, dst_n, samples) @ T1
        errors = _transfer_errors(Hs, src, dst)
        inliers = errors < threshold
        counts = inliers.sum(axis=1)
        spread = np.where(inliers, errors, 0).sum(axis=1)
        k = int(np.lexsort((spread, -counts))[0])  # most inliers, then smallest error
        if counts[k] > best_count or (counts[k] == best_count and spread[k] < best_error):
            best_count, best_inliers, best_error = int(counts[k]), inliers[k], spread[k]
            w = best_count / n
            needed = int(np.ceil(np.log(1 - confidence) / np.log(max(1 - w ** 4, 1e-12))))
        drawn += batch

    if best_count < 4:
        return homography_dlt(src, dst), np.ones(n, dtype=bool)
    # Refit on every inlier, re-select inliers with the better H, refit once more.
    inliers = best_inliers
    for _ in range(2):
        H = homography_dlt(src[inliers], dst[inliers])
        refined = _transfer_errors(H[None], src, dst)[0] < threshold
        if refined.sum() < 4:
            break
        inliers = refined
    H = homography_dlt(src[inliers], dst[inliers])
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
