"""Lab 8 - image homographies.

Careful version: inputs are converted and checked, the DLT is Hartley-normalised,
RANSAC is my own loop (seeded with ``np.random.default_rng(seed)``) around my
``homography_dlt``, and the panorama is blended with my multi-band blender.

Conventions
-----------
- Images: uint8 (H, W) grey or (H, W, 3) BGR; inputs are never modified.
- Points: (N, 2) float arrays of (x, y), x = column, y = row, origin at the
  centre of the top-left pixel, y pointing down (like ``cv2.KeyPoint.pt``).
- H acts on (x, y, 1): (u, v, w) = H @ (x, y, 1) -> (u / w, v / w). Any non-zero
  scale is the same homography; I return H with H[2, 2] == 1 when possible.
- Warps: bilinear, black fill, ``dsize = (width, height)``.
"""

import math

import cv2
import numpy as np


# ----------------------------------------------------------------- helpers
def _as_image(image, name="image"):
    """C-contiguous ndarray view/copy of an (H, W) or (H, W, C) image."""
    img = np.asarray(image)
    if img.ndim not in (2, 3) or img.size == 0:
        raise ValueError(f"{name} must be a non-empty (H, W) or (H, W, C) image, got {img.shape}")
    return np.ascontiguousarray(img)


def _to_grey(img):
    """uint8 grey version of a grey or BGR(A) image, for the feature detectors."""
    img = _as_image(img)
    if img.ndim == 3:
        if img.shape[2] == 1:
            img = img[..., 0]
        elif img.shape[2] == 4:
            img = cv2.cvtColor(img, cv2.COLOR_BGRA2GRAY)
        else:
            img = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    if img.dtype != np.uint8:
        img = np.clip(img, 0, 255).astype(np.uint8)
    return np.ascontiguousarray(img)


def _to_bgr(img):
    """3-channel uint8 version of a grey or BGR image (a copy)."""
    img = _as_image(img)
    if img.ndim == 2:
        return cv2.cvtColor(img, cv2.COLOR_GRAY2BGR)
    if img.shape[2] == 1:
        return cv2.cvtColor(img[..., 0], cv2.COLOR_GRAY2BGR)
    return img[..., :3].copy()


def _as_points(pts, name="pts"):
    """(N, 2) float64 copy; a single (2,) point becomes (1, 2); (N, 1, 2) is flattened."""
    p = np.array(pts, dtype=np.float64, copy=True)
    if p.size == 0:
        return np.zeros((0, 2))
    if p.ndim == 1 and p.size == 2:
        p = p.reshape(1, 2)
    if p.ndim == 3 and p.shape[1:] == (1, 2):
        p = p.reshape(-1, 2)
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"{name} must be an (N, 2) array of (x, y), got shape {p.shape}")
    return p


def _as_h(H):
    """3x3 float64 copy of a homography."""
    H = np.array(H, dtype=np.float64, copy=True)
    if H.shape != (3, 3):
        raise ValueError(f"H must be 3x3, got shape {H.shape}")
    if not np.all(np.isfinite(H)):
        raise ValueError("H contains NaN or inf")
    return H


def _normalise_scale(H):
    """Scale H so H[2, 2] == 1 if that entry is usable, else to unit norm."""
    if abs(H[2, 2]) > 1e-12 * np.abs(H).max():
        return H / H[2, 2]
    return H / np.linalg.norm(H)


# --------------------------------------------------------------------- ex1
def apply_homography(image, H, dsize=None):
    """Warp ``image`` by ``H`` (source -> output), bilinear, black fill.

    ``cv2.warpPerspective`` receives the forward H and inverts it itself.
    """
    img = _as_image(image)
    H = _as_h(H)
    if dsize is None:
        dsize = (img.shape[1], img.shape[0])
    w, h = (int(round(float(v))) for v in dsize)
    if w <= 0 or h <= 0:
        raise ValueError(f"dsize must be a positive (width, height), got {dsize}")
    out = cv2.warpPerspective(img, H, (w, h), flags=cv2.INTER_LINEAR,
                              borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    if img.ndim == 3 and out.ndim == 2:       # OpenCV drops a single channel axis
        out = out[..., None]
    return out


def transform_points(H, pts):
    """Map (N, 2) points by ``H`` with the perspective division.

    A point mapped to infinity (w == 0) comes back as inf/NaN rather than
    raising: that is the honest answer.
    """
    H = _as_h(H)
    p = _as_points(pts)
    if len(p) == 0:
        return np.zeros((0, 2))
    hom = np.column_stack([p, np.ones(len(p))]) @ H.T      # rows (u, v, w)
    with np.errstate(divide="ignore", invalid="ignore"):
        return hom[:, :2] / hom[:, 2:3]


# --------------------------------------------------------------------- ex2
def _hartley(p):
    """Similarity T: centroid -> origin, mean distance to it -> sqrt(2)."""
    centroid = p.mean(axis=0)
    mean_dist = np.sqrt(((p - centroid) ** 2).sum(axis=1)).mean()
    s = math.sqrt(2.0) / mean_dist if mean_dist > 1e-12 else 1.0
    return np.array([[s, 0.0, -s * centroid[0]],
                     [0.0, s, -s * centroid[1]],
                     [0.0, 0.0, 1.0]])


def homography_dlt(src, dst):
    """DLT homography with ``dst ~ H @ src`` from N >= 4 pairs, solved by SVD.

    Points are Hartley-normalised first (raw pixel coordinates make the 2N x 9
    matrix badly conditioned); the result is denormalised as inv(T_dst) H_n T_src.
    """
    src = _as_points(src, "src")
    dst = _as_points(dst, "dst")
    if len(src) != len(dst):
        raise ValueError("src and dst must hold the same number of points")
    if len(src) < 4:
        raise ValueError("the DLT needs at least 4 point pairs")

    T_src, T_dst = _hartley(src), _hartley(dst)
    s = transform_points(T_src, src)
    d = transform_points(T_dst, dst)

    rows = []
    for (x, y), (xp, yp) in zip(s, d):
        rows.append([x, y, 1.0, 0.0, 0.0, 0.0, -xp * x, -xp * y, -xp])
        rows.append([0.0, 0.0, 0.0, x, y, 1.0, -yp * x, -yp * y, -yp])
    A = np.asarray(rows)

    # Full SVD: with 4 pairs A is 8 x 9 and we need the 9th right singular vector.
    _, _, Vt = np.linalg.svd(A, full_matrices=True)
    H_n = Vt[-1].reshape(3, 3)
    H = np.linalg.inv(T_dst) @ H_n @ T_src
    return _normalise_scale(H)


def warp_to_reference(reference, moving, H):
    """``moving`` warped by ``H`` (moving -> reference) into ``reference``'s frame."""
    ref = np.asarray(reference)
    return apply_homography(moving, H, (ref.shape[1], ref.shape[0]))


# --------------------------------------------------------------------- ex3
def _detector(method):
    method = str(method).lower()
    if method == "sift":
        return cv2.SIFT_create(), cv2.NORM_L2
    if method == "orb":
        return cv2.ORB_create(nfeatures=1000), cv2.NORM_HAMMING
    raise ValueError(f"method must be 'sift' or 'orb', got {method!r}")


def match_features(img1, img2, ratio=0.75, method="sift"):
    """Keypoint matches between ``img1`` and ``img2`` after Lowe's ratio test.

    Returns pts1, pts2 as (M, 2) float64 arrays (M may be 0).
    """
    detector, norm = _detector(method)
    k1, d1 = detector.detectAndCompute(_to_grey(img1), None)
    k2, d2 = detector.detectAndCompute(_to_grey(img2), None)
    none = (np.zeros((0, 2)), np.zeros((0, 2)))
    # The ratio test needs two candidates in img2 for every descriptor.
    if d1 is None or d2 is None or len(d1) == 0 or len(d2) < 2:
        return none

    matcher = cv2.BFMatcher(norm, crossCheck=False)
    pts1, pts2 = [], []
    for cand in matcher.knnMatch(d1, d2, k=2):
        if len(cand) < 2:
            continue
        best, second = cand
        if best.distance < float(ratio) * second.distance:
            pts1.append(k1[best.queryIdx].pt)
            pts2.append(k2[best.trainIdx].pt)
    if not pts1:
        return none
    return np.asarray(pts1, dtype=np.float64), np.asarray(pts2, dtype=np.float64)


def draw_matches(img1, img2, pts1, pts2):
    """Both images side by side (img2 starting at column W1), one line per match."""
    a, b = _to_bgr(img1), _to_bgr(img2)
    p1, p2 = _as_points(pts1, "pts1"), _as_points(pts2, "pts2")
    if len(p1) != len(p2):
        raise ValueError("pts1 and pts2 must have the same length")
    h1, w1 = a.shape[:2]
    h2, w2 = b.shape[:2]
    canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
    canvas[:h1, :w1] = a
    canvas[:h2, w1:] = b

    rng = np.random.default_rng(0)   # fixed colours: the same figure every run
    for (x1, y1), (x2, y2) in zip(p1, p2):
        if not np.all(np.isfinite([x1, y1, x2, y2])):
            continue
        colour = tuple(int(c) for c in rng.integers(64, 256, size=3))
        q1 = (int(round(x1)), int(round(y1)))
        q2 = (int(round(x2)) + w1, int(round(y2)))
        cv2.line(canvas, q1, q2, colour, 1, cv2.LINE_AA)
        cv2.circle(canvas, q1, 3, colour, 1, cv2.LINE_AA)
        cv2.circle(canvas, q2, 3, colour, 1, cv2.LINE_AA)
    return canvas


# --------------------------------------------------------------------- ex4
def _transfer_error(H, src, dst):
    """|H src - dst| in pixels for every pair (inf where H sends a point to infinity)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        err = np.linalg.norm(transform_points(H, src) - dst, axis=1)
    return np.where(np.isfinite(err), err, np.inf)


def _sample_is_degenerate(p):
    """True when three of the four sample points are (nearly) collinear."""
    for i in range(4):
        q = np.delete(p, i, axis=0)
        area2 = abs((q[1, 0] - q[0, 0]) * (q[2, 1] - q[0, 1]) - (q[1, 1] - q[0, 1]) * (q[2, 0] - q[0, 0]))
        if area2 < 1e-6:
            return True
    return False


def homography_ransac(src, dst, threshold=3.0, seed=None):
    """RANSAC homography: my own loop around ``homography_dlt``.

    Adaptive number of samples: after each improvement, the samples needed for
    99% confidence are log(1 - 0.99) / log(1 - w**4), w = current inlier ratio
    (capped at 5000, at least 50). The best consensus set is refitted with the
    DLT, and the inliers are recomputed from that final H, twice, so the mask
    and H agree.
    """
    src = _as_points(src, "src")
    dst = _as_points(dst, "dst")
    n = len(src)
    if n != len(dst):
        raise ValueError("src and dst must hold the same number of points")
    if n < 4:
        raise ValueError("RANSAC for a homography needs at least 4 pairs")
    threshold = float(threshold)
    rng = np.random.default_rng(seed)

    confidence, max_iter, min_iter = 0.99, 5000, 50
    best_mask, best_count, best_err = None, -1, np.inf
    needed, it = max_iter, 0
    while it < min(needed, max_iter) or it < min_iter:
        it += 1
        idx = rng.choice(n, size=4, replace=False)
        if _sample_is_degenerate(src[idx]) or _sample_is_degenerate(dst[idx]):
            continue
        try:
            H = homography_dlt(src[idx], dst[idx])
        except np.linalg.LinAlgError:
            continue
        err = _transfer_error(H, src, dst)
        mask = err < threshold
        count = int(mask.sum())
        # Ties broken by the smaller total inlier error.
        total = float(err[mask].sum()) if count else np.inf
        if count > best_count or (count == best_count and total < best_err):
            best_mask, best_count, best_err = mask, count, total
            w = count / n
            if w >= 1.0:
                needed = 0
            elif w > 0:
                needed = int(math.ceil(math.log(1 - confidence) / math.log(1 - w ** 4)))
        if it >= max_iter:
            break

    if best_mask is None or best_count < 4:
        # No usable sample at all: the plain DLT on everything is all we can do.
        H = homography_dlt(src, dst)
        return H, _transfer_error(H, src, dst) < threshold

    mask = best_mask
    H = homography_dlt(src[mask], dst[mask])
    for _ in range(2):   # refit until the consensus set is stable
        new_mask = _transfer_error(H, src, dst) < threshold
        if new_mask.sum() < 4 or np.array_equal(new_mask, mask):
            break
        mask = new_mask
        H = homography_dlt(src[mask], dst[mask])
    mask = _transfer_error(H, src, dst) < threshold
    return H, mask


# --------------------------------------------------------------------- ex5
def _corners(shape):
    """The four pixel-centre corners (x, y) of an image of this shape."""
    h, w = shape[:2]
    return np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], dtype=np.float64)


def _border_distance(shape):
    """Distance of every pixel to the outside of the image (1 on the edge pixels)."""
    h, w = shape[:2]
    pad = np.zeros((h + 2, w + 2), np.uint8)
    pad[1:-1, 1:-1] = 1
    return cv2.distanceTransform(pad, cv2.DIST_L2, 5)[1:-1, 1:-1].astype(np.float32)


def _estimate_h(img_moving, img_fixed):
    """H mapping ``img_moving``'s pixels onto ``img_fixed``'s (SIFT + my RANSAC)."""
    p_fixed, p_moving = match_features(img_fixed, img_moving)
    if len(p_fixed) < 4:
        raise RuntimeError(f"only {len(p_fixed)} matches: the images do not seem to overlap")
    H, inliers = homography_ransac(p_moving, p_fixed, threshold=3.0, seed=0)
    if inliers.sum() < 8:
        raise RuntimeError("too few RANSAC inliers for a reliable homography")
    return H


def _composite(images, Hs, reference):
    """Warp every image into one canvas and blend.

    Blending: every canvas pixel goes to the image whose border is farthest
    (the distance-transform seam); across that seam the images are mixed by
    my multi-band blender, two images at a time. Outside the overlap every
    pixel is copied from the only image covering it, so the reference image
    is reproduced exactly there (only shifted).
    """
    corners = np.vstack([transform_points(H, _corners(im.shape)) for im, H in zip(images, Hs)])
    if not np.all(np.isfinite(corners)):
        raise RuntimeError("a homography sends an image corner to infinity")
    x_min, y_min = np.floor(corners.min(axis=0)).astype(int)
    x_max, y_max = np.ceil(corners.max(axis=0)).astype(int)
    width, height = int(x_max - x_min + 1), int(y_max - y_min + 1)
    if width * height > 50_000_000:
        raise RuntimeError("panorama would be enormous: the homography looks wrong")
    T = np.array([[1.0, 0.0, -x_min], [0.0, 1.0, -y_min], [0.0, 0.0, 1.0]])

    warped, weights = [], []
    for im, H in zip(images, Hs):
        M = T @ H
        # Image warped with its border replicated (its validity is in the weight),
        # weight = distance to its own border, 0 outside it.
        warped.append(cv2.warpPerspective(im, M, (width, height), flags=cv2.INTER_LINEAR,
                                          borderMode=cv2.BORDER_REPLICATE))
        weights.append(cv2.warpPerspective(_border_distance(im.shape), M, (width, height),
                                           flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT,
                                           borderValue=0))
    # The reference is placed by an integer shift: paste it exactly.
    ref_h, ref_w = images[reference].shape[:2]
    ox, oy = -x_min, -y_min

    pano = np.zeros((height, width, 3), np.float32)
    covered = np.zeros((height, width), bool)
    best_w = np.zeros((height, width), np.float32)
    for img, wt in zip(warped, weights):
        valid = wt > 0
        img = img.astype(np.float32)
        fresh = valid & ~covered
        pano[fresh] = img[fresh]
        overlap = valid & covered
        if overlap.any():
            # mask = weight of what is already there against the new image,
            # smoothed so the seam is soft; then blend frequencies separately
            mask = best_w / np.maximum(best_w + wt, 1e-6)
            mask = np.where(covered & ~valid, 1.0, np.where(fresh, 0.0, mask)).astype(np.float32)
            # fill each side's holes with the other so pyramids do not see black
            a = np.where(covered[..., None], pano, img)
            b = np.where((valid | ~covered)[..., None], img, pano)
            mixed = blend_multiband(np.clip(np.rint(a), 0, 255).astype(np.uint8),
                                    np.clip(np.rint(b), 0, 255).astype(np.uint8), mask, levels=4)
            pano[overlap] = mixed[overlap]
        covered |= valid
        best_w = np.maximum(best_w, wt)

    out = np.clip(np.rint(pano), 0, 255).astype(np.uint8)
    # Reference pixels outside any overlap stay exactly as they were.
    ref_region = out[oy:oy + ref_h, ox:ox + ref_w]
    only_ref = np.ones((ref_h, ref_w), bool)
    for k, wt in enumerate(weights):
        if k != reference:
            only_ref &= ~(wt[oy:oy + ref_h, ox:ox + ref_w] > 0)
    ref_region[only_ref] = images[reference][only_ref]
    return out


def stitch(img1, img2):
    """Panorama of two overlapping BGR images in ``img1``'s frame."""
    a, b = _to_bgr(img1), _to_bgr(img2)
    H21 = _estimate_h(b, a)            # img2 -> img1
    return _composite([a, b], [np.eye(3), H21], reference=0)


# --------------------------------------------------------------------- ext2
def stitch_many(images):
    """Panorama of 3+ overlapping images (left to right), in the middle image's frame.

    The middle image distorts least. H[i] maps image i onto the reference: for
    images to its right H[i] = H[i-1] @ H_(i -> i-1); to its left
    H[i] = H[i+1] @ inv(H_(i+1 -> i)) = H[i+1] @ H_(i -> i+1).
    """
    imgs = [_to_bgr(im) for im in images]
    if len(imgs) == 0:
        raise ValueError("no images")
    if len(imgs) == 1:
        return imgs[0].copy()
    r = (len(imgs) - 1) // 2
    Hs = [None] * len(imgs)
    Hs[r] = np.eye(3)
    for i in range(r + 1, len(imgs)):
        Hs[i] = _normalise_scale(Hs[i - 1] @ _estimate_h(imgs[i], imgs[i - 1]))
    for i in range(r - 1, -1, -1):
        # estimate image i -> image i+1 directly rather than inverting
        Hs[i] = _normalise_scale(Hs[i + 1] @ _estimate_h(imgs[i], imgs[i + 1]))
    return _composite(imgs, Hs, reference=r)


# --------------------------------------------------------------------- ext3
def _pyr_up(img, like):
    """pyrUp to exactly ``like``'s size (keeps a trailing channel axis)."""
    up = cv2.pyrUp(img, dstsize=(like.shape[1], like.shape[0]))
    return up.reshape(like.shape)


def blend_multiband(img1, img2, mask, levels=4):
    """Laplacian-pyramid blend of two aligned images; ``mask`` is img1's weight."""
    a = np.asarray(img1)
    b = np.asarray(img2)
    if a.shape != b.shape:
        raise ValueError(f"images differ in shape: {a.shape} vs {b.shape}")
    m = np.clip(np.asarray(mask, dtype=np.float32), 0.0, 1.0)
    if m.shape != a.shape[:2]:
        raise ValueError(f"mask must be {a.shape[:2]}, got {m.shape}")
    levels = int(levels)
    if levels < 1:
        raise ValueError("levels must be >= 1")
    # never ask for more levels than the image can be halved
    max_levels = 1 + int(math.floor(math.log2(max(1, min(a.shape[:2])))))
    levels = min(levels, max_levels)

    fa, fb = a.astype(np.float32), b.astype(np.float32)
    fm = m[..., None] if a.ndim == 3 else m
    fm = np.repeat(fm, a.shape[2], axis=2) if a.ndim == 3 else fm

    def gaussian(x):
        pyr = [np.ascontiguousarray(x)]
        for _ in range(levels - 1):
            pyr.append(cv2.pyrDown(pyr[-1]).reshape(
                ((pyr[-1].shape[0] + 1) // 2, (pyr[-1].shape[1] + 1) // 2) + pyr[-1].shape[2:]))
        return pyr

    def laplacian(g):
        return [g[i] - _pyr_up(g[i + 1], g[i]) for i in range(len(g) - 1)] + [g[-1]]

    La, Lb, Gm = laplacian(gaussian(fa)), laplacian(gaussian(fb)), gaussian(fm)
    blended = [gm * la + (1.0 - gm) * lb for la, lb, gm in zip(La, Lb, Gm)]
    out = blended[-1]
    for lvl in range(levels - 2, -1, -1):
        out = _pyr_up(out, blended[lvl]) + blended[lvl]
    return np.clip(np.rint(out), 0, 255).astype(a.dtype if a.dtype == np.uint8 else np.uint8)
