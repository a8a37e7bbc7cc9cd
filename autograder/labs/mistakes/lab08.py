"""Lab 8's mistakes table (image homographies): realistic wrong implementations, each the
reference solution with one function redefined, the exercise it must lose points in, and
the words its diagnosis must contain (read by ``autograder verify``; see
:mod:`autograder.labs.mistakes`)."""

from . import columns_by_first_axis, reference_def_with

# draw_matches' start as the sheet has it: both images side by side on a black canvas (each case draws its lines)
_SIDE_BY_SIDE = """
        def draw_matches(img1, img2, pts1, pts2):
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
            canvas[:h1, :w1] = _bgr(img1)
            canvas[:h2, w1:] = _bgr(img2)
"""

# A stitch's first lines as the reference's _compose writes them (img2's H, the canvas of both images' corners),
# before each case's own way of putting the two warps on it.
_STITCH_CANVAS = """
        def stitch(img1, img2):
            H21 = _pairwise_homography(img2, img1)
            corners = np.vstack([_corners(img1), transform_points(H21, _corners(img2))])
            x_min, y_min = np.floor(corners.min(axis=0))
            x_max, y_max = np.ceil(corners.max(axis=0))
            shift = _translation(-x_min, -y_min)
            size = (int(x_max - x_min) + 1, int(y_max - y_min) + 1)"""

# The reference's _compose, a feathered sum over the canvas of both images' corners, up to the panorama made of it.
_COMPOSE_FEATHERED = """
        def _compose(images, homographies):
            corners = np.vstack([transform_points(H, _corners(im)) for im, H in zip(images, homographies)])
            x_min, y_min = np.floor(corners.min(axis=0))
            x_max, y_max = np.ceil(corners.max(axis=0))
            shift = _translation(-x_min, -y_min)
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
            panorama = {panorama}
            return np.clip(np.round(panorama), 0, 255).astype(np.uint8)
        """

MISTAKES = {
    # the blind set 1206a's 08/02: the adaptive count with math.log and no guard: every pair an inlier (w = 1) raises
    # (four exact pairs are no refusal of the minimal set: twelve exact pairs raise too)
    "homography_ransac taking math.log of 1 - w^4 unguarded": ("lab08.ex4", reference_def_with(
        "lab08_homographies", "homography_ransac",
        "needed = int(np.ceil(np.log(1 - confidence) / np.log(max(1 - w ** 4, 1e-12))))",
        "import math\nneeded = int(np.ceil(math.log(1 - confidence) / math.log(1 - w ** 4)))"),
        ["math.log takes a positive number only"]),
    # the blind set 1206a's 08/03: a list repeated by * holds one array, which @= changes for every image
    "stitch_many keeping one matrix n times ([np.eye(3)] * n) and updating it in place": ("lab08.ext2", """
        def stitch_many(images):
            images = list(images)
            if len(images) < 2:
                raise ValueError("need at least two images")
            features = [_detect(image) for image in images]   # once per image
            step = [_pairwise_homography(features[k + 1], features[k]) for k in range(len(images) - 1)]
            r = len(images) // 2
            # homographies[k] takes image k into the reference image r; start from I
            homographies = [np.eye(3)] * len(images)
            for k in range(r + 1, len(images)):
                # right of r: H_{k->r} = step[r] @ step[r+1] @ ... @ step[k-1]
                for j in range(r, k):
                    homographies[k] @= step[j]
            for k in range(r):
                # left of r: H_{k->r} = inv(step[r-1]) @ ... @ inv(step[k])
                for j in range(r - 1, k - 1, -1):
                    homographies[k] @= np.linalg.inv(step[j])
            homographies = [H / H[2, 2] for H in homographies]
            return _compose(images, homographies)
        """, ['holds the one object']),
    # the blind set 1206a's 08/06: the apple/orange tutorial's halves, the mask's level computed and never read
    "blend_multiband joining left and right halves of each band, the mask level unused": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            a = np.asarray(img1, dtype=np.float32)
            b = np.asarray(img2, dtype=np.float32)
            m = np.clip(np.asarray(mask, dtype=np.float32), 0, 1)

            # Gaussian pyramids (level 0 = full size)
            gauss_a, gauss_b, gauss_m = [a], [b], [m]
            for _ in range(levels - 1):
                gauss_a.append(cv2.pyrDown(gauss_a[-1]))
                gauss_b.append(cv2.pyrDown(gauss_b[-1]))
                gauss_m.append(cv2.pyrDown(gauss_m[-1]))

            # Laplacian pyramids: band i = G_i - up(G_{i+1}); the top keeps the low-pass G
            lap_a, lap_b = [], []
            for i in range(levels - 1):
                size = (gauss_a[i].shape[1], gauss_a[i].shape[0])
                lap_a.append(gauss_a[i] - cv2.pyrUp(gauss_a[i + 1], dstsize=size))
                lap_b.append(gauss_b[i] - cv2.pyrUp(gauss_b[i + 1], dstsize=size))
            lap_a.append(gauss_a[-1])
            lap_b.append(gauss_b[-1])

            # blend every level with the mask at that scale
            blended = []
            for la, lb, w in zip(lap_a, lap_b, gauss_m):
                if la.ndim == 3:
                    w = w[..., None]
                half = la.shape[1] // 2
                blended.append(np.hstack([la[:, :half], lb[:, half:]]))

            # collapse: upsample and add the next finer band
            result = blended[-1]
            for band in reversed(blended[:-1]):
                result = cv2.pyrUp(result, dstsize=(band.shape[1], band.shape[0])) + band
            return np.clip(np.round(result), 0, 255).astype(np.uint8)
        """, ['is never used']),
    # the blind set 1205h's 08/03: the collapsed pyramid min-max stretched to 0..255 where it belongs clipped
    "blend_multiband stretching the blend to 0..255 instead of clipping it": ("lab08.ext3", reference_def_with(
        "lab08_homographies", "blend_multiband", "return np.clip(np.round(result), 0, 255).astype(np.uint8)",
        "result = cv2.normalize(result, None, 0, 255, cv2.NORM_MINMAX)\nreturn np.round(result).astype(np.uint8)"),
        ["to `np.clip(result, 0, 255)`"]),
    # the blind set 1205h's 08/01: Lowe's test as a ratio divides by a second distance of 0 (a patch repeated exactly)
    "match_features writing Lowe's test as a ratio of the distances": ("lab08.ex3", reference_def_with(
        "lab08_homographies", "_match", "if best.distance < ratio * second.distance]",
        "if best.distance / second.distance < ratio]"),
        ["changing `best.distance / second.distance < ratio` to `best.distance < ratio * second.distance`"]),
    # the blind set 1204c's 08/05: the lines drawn on the canvas, the circles on its copy, and the copy returned
    "draw_matches drawing the lines on the canvas it does not return": ("lab08.ex3", """
        def draw_matches(img1, img2, pts1, pts2):
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
            canvas[:h1, :w1] = img1 if img1.ndim == 3 else cv2.cvtColor(img1, cv2.COLOR_GRAY2BGR)
            canvas[:h2, w1:] = img2 if img2.ndim == 3 else cv2.cvtColor(img2, cv2.COLOR_GRAY2BGR)
            out = canvas.copy()
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                a, b = (int(round(x1)), int(round(y1))), (int(round(x2 + w1)), int(round(y2)))
                cv2.line(canvas, a, b, (0, 255, 0), 1, cv2.LINE_AA)
                cv2.circle(out, a, 3, (0, 0, 255), 1, cv2.LINE_AA)
                cv2.circle(out, b, 3, (0, 0, 255), 1, cv2.LINE_AA)
            return out
        """, ["none of the"]),
    # the blind set 1204c's 08/04: the method told by identity, `is "orb"`, false for the caller's equal string
    "match_features choosing ORB by identity": ("lab08.ext1", """
        def match_features(img1, img2, ratio=0.75, method="sift"):
            if method is "orb":
                detector, norm = cv2.ORB_create(nfeatures=2000), cv2.NORM_HAMMING
            elif method == "sift":
                detector, norm = cv2.SIFT_create(), cv2.NORM_L2
            else:
                raise ValueError(f"unknown method {method!r}")
            g1 = img1 if img1.ndim == 2 else cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY)
            g2 = img2 if img2.ndim == 2 else cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY)
            k1, d1 = detector.detectAndCompute(g1, None)
            k2, d2 = detector.detectAndCompute(g2, None)
            if d1 is None or d2 is None or len(k1) < 2 or len(k2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            pairs = cv2.BFMatcher(norm).knnMatch(d1, d2, k=2)
            good = [p[0] for p in pairs if len(p) == 2 and p[0].distance < ratio * p[1].distance]
            pts1 = np.float64([k1[m.queryIdx].pt for m in good]).reshape(-1, 2)
            pts2 = np.float64([k2[m.trainIdx].pt for m in good]).reshape(-1, 2)
            return pts1, pts2
        """, ["`is` asks whether both are one object"]),
    # the blind set 1204c's 08/03: the identity H taken as "nothing to do", the moving image returned as it is
    "warp_to_reference returning the moving image for the identity": ("lab08.ex2", """
        def warp_to_reference(reference, moving, H):
            height, width = reference.shape[:2]
            H = np.asarray(H, dtype=np.float64)
            if np.allclose(H, H[2, 2] * np.eye(3)):
                return moving.copy()
            return apply_homography(moving, H, (width, height))
        """, ["the identity too"]),
    # the blind set 1204b's 08/03: the denormalising similarity inverted by hand, its translation not scaled
    "homography_dlt inverting T_dst by hand without scaling its translation": ("lab08.ex2", """
        def homography_dlt(src, dst):
            src, dst = np.asarray(src, np.float64), np.asarray(dst, np.float64)
            def similarity(p):
                c = p.mean(axis=0)
                s = np.sqrt(2) / np.linalg.norm(p - c, axis=1).mean()
                return np.array([[s, 0.0, -s * c[0]], [0.0, s, -s * c[1]], [0.0, 0.0, 1.0]])
            T1, T2 = similarity(src), similarity(dst)
            a = (np.column_stack([src, np.ones(len(src))]) @ T1.T)[:, :2]
            b = (np.column_stack([dst, np.ones(len(dst))]) @ T2.T)[:, :2]
            rows = []
            for (x, y), (u, v) in zip(a, b):
                rows.append([x, y, 1, 0, 0, 0, -u * x, -u * y, -u])
                rows.append([0, 0, 0, x, y, 1, -v * x, -v * y, -v])
            Hn = np.linalg.svd(np.array(rows))[2][-1].reshape(3, 3)
            s, tx, ty = T2[0, 0], T2[0, 2], T2[1, 2]
            T2_inverse = np.array([[1.0 / s, 0.0, -tx], [0.0, 1.0 / s, -ty], [0.0, 0.0, 1.0]])
            return T2_inverse @ Hn @ T1
        """, ["its translation not divided by the scale"]),
    # the blind set 1204b's 08/01: an own inverse map keeping only the pixels whose source has w > 0
    # the blind set 1204e's 08/01: each plane warped, the planes put back with np.array (channels first)
    "apply_homography stacking the warped planes channel-first": ("lab08.ex1", """
        def apply_homography(image, H, dsize=None):
            height, width = image.shape[:2]
            size = dsize or (width, height)
            if image.ndim == 2:
                return cv2.warpPerspective(image, np.asarray(H, float), size)
            warped = []
            for k in range(image.shape[2]):
                warped.append(cv2.warpPerspective(image[:, :, k], np.asarray(H, float), size))
            return np.asarray(warped)
        """, ["the channels come first"]),
    "apply_homography keeping only w > 0": ("lab08.ex1", """
        def apply_homography(image, H, dsize=None):
            width, height = dsize if dsize is not None else (image.shape[1], image.shape[0])
            xs, ys = np.meshgrid(np.arange(width, dtype=np.float64), np.arange(height, dtype=np.float64))
            q = np.stack([xs.ravel(), ys.ravel(), np.ones(xs.size)]) 
            src = np.linalg.inv(np.asarray(H, np.float64)) @ q
            w = src[2]
            valid = w > 0
            safe = np.where(valid, w, 1.0)
            map_x = np.where(valid, src[0] / safe, -1e6).reshape(height, width).astype(np.float32)
            map_y = np.where(valid, src[1] / safe, -1e6).reshape(height, width).astype(np.float32)
            return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """, ["right for h and wrong for -h", "w > 0"]),
    # the blind set 1204b's 08/06: the minimal set refused by a guard one too strict
    "homography_ransac refusing exactly 4 pairs": ("lab08.ex4", """
        _ransac_right = homography_ransac
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            if len(src) <= 4:
                raise ValueError("need at least 4 correspondences")
            return _ransac_right(src, dst, threshold, seed)
        """, ["minimal set", "refuses them"]),
    "apply_homography refusing a determinant np.isclose takes for 0": ("lab08.ex1", """
        def apply_homography(image, H, dsize=None):
            if np.isclose(np.linalg.det(H), 0.0):
                raise ValueError("H is singular")
            height, width = image.shape[:2]
            return cv2.warpPerspective(image, np.asarray(H, dtype=np.float64), dsize or (width, height))
        """, ["right for H and not for 0.001 H", "(raised on apply_homography(image, 0.001 * H))"]),
    "apply_homography with H transposed": ("lab08.ex1", """
        def apply_homography(image, H, dsize=None):
            h, w = image.shape[:2]
            return cv2.warpPerspective(image, np.asarray(H, float).T, dsize or (w, h))
        """, ["h is transposed"]),
    # the blind set 1202i's 08/01: each source pixel sent through H and copied to the nearest output pixel
    "apply_homography mapping the source pixels forward": ("lab08.ex1", """
        def apply_homography(image, H, dsize=None):
            height, width = image.shape[:2]
            out_w, out_h = dsize or (width, height)
            ys, xs = np.mgrid[0:height, 0:width]
            with np.errstate(divide="ignore", invalid="ignore"):
                target = transform_points(H, np.column_stack([xs.ravel(), ys.ravel()]).astype(np.float64))
            target[~np.isfinite(target)] = -1e6
            u, v = np.round(target[:, 0]).astype(np.int64), np.round(target[:, 1]).astype(np.int64)
            keep = (u >= 0) & (u < out_w) & (v >= 0) & (v < out_h)
            out = np.zeros((out_h, out_w) + image.shape[2:], dtype=image.dtype)
            out[v[keep], u[keep]] = image[ys.ravel()[keep], xs.ravel()[keep]]
            return out
        """, ["the image is mapped forward", "holes"]),
    # ---------------------------------------------------------------- ex1
    "no perspective division": ("lab08.ex1", """
        def transform_points(H, pts):
            pts = np.asarray(pts, float)
            return (np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(H).T)[:, :2]
        """, ["perspective division is missing"]),
    "an affine H applied without the division by w": ("lab08.ex1", """
        _transform = transform_points
        def transform_points(H, pts):
            H = np.asarray(H, float)
            if H[2, 0] == 0 and H[2, 1] == 0:   # affine: w is constant
                return np.asarray(pts, float) @ H[:2, :2].T + H[:2, 2]
            return _transform(H, pts)
        """, ["an affine h", "divided by w for an affine h too"]),
    "only x divided by w (a typo in the y column)": ("lab08.ex1", """
        def transform_points(H, pts):
            pts = np.asarray(pts, float)
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(H).T
            return np.column_stack([q[:, 0] / q[:, 2], q[:, 1] / q[:, 0]])
        """, ["in y only", "changing `q[:, 1] / q[:, 0]` to `q[:, 1] / q[:, 2]`"]),
    "w computed as if H[2, 2] were 1": ("lab08.ex1", """
        def transform_points(H, pts):
            H, pts = np.asarray(H, float), np.asarray(pts, float)
            w = H[2, 0] * pts[:, 0] + H[2, 1] * pts[:, 1] + 1.0
            return np.column_stack([(H[0, 0] * pts[:, 0] + H[0, 1] * pts[:, 1] + H[0, 2]) / w,
                                    (H[1, 0] * pts[:, 0] + H[1, 1] * pts[:, 1] + H[1, 2]) / w])
        """, ["is wrong for every point"]),
    "points times H": ("lab08.ex1", """
        def transform_points(H, pts):
            pts = np.asarray(pts, float)
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(H)
            return q[:, :2] / q[:, 2:]
        """, ["transposed"]),
    "homogeneous points returned": ("lab08.ex1", """
        def transform_points(H, pts):
            pts = np.asarray(pts, float)
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(H).T
            return q / q[:, 2:]
        """, ["homogeneous", "w is kept"]),
    "warp with the inverse map": ("lab08.ex1", """
        def apply_homography(image, H, dsize=None):
            h, w = image.shape[:2]
            return cv2.warpPerspective(image, H, dsize or (w, h),
                                       flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP)
        """, ["inverted"]),
    "divided by x instead of w": ("lab08.ex1", """
        def transform_points(H, pts):
            pts = np.asarray(pts, float).reshape(-1, 2)
            q = np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(H, float).T
            return q[:, :2] / q[:, 0:1]
        """, ["divided by x, the wrong coordinate"]),
    "warpAffine for a homography": ("lab08.ex1", """
        def apply_homography(image, H, dsize=None):
            h, w = image.shape[:2]
            H = np.asarray(H, float) / H[2, 2]
            return cv2.warpAffine(image, H[:2], dsize or (w, h))
        """, ["perspective row", "warpPerspective"]),
    # ---------------------------------------------------------------- ex2
    "DLT whose rows leave out the last pair": ("lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            rows = []
            for (x, y), (u, v) in zip(src[:-1], dst[:-1]):
                rows.append([-x, -y, -1, 0, 0, 0, u * x, u * y, u])
                rows.append([0, 0, 0, -x, -y, -1, v * x, v * y, v])
            H = np.linalg.svd(np.array(rows))[2][-1].reshape(3, 3)
            return H / H[2, 2]
        """, ["misses the last one", "left out of the system solved"]),
    "DLT src and dst swapped": ("lab08.ex2", """
        _reference_dlt = homography_dlt
        def homography_dlt(src, dst):
            return _reference_dlt(dst, src)
        """, ["inverse homography"]),
    "DLT h reshaped column-major": ("lab08.ex2", """
        _reference_dlt = homography_dlt
        def homography_dlt(src, dst):
            return _reference_dlt(src, dst).T
        """, ["transposed"]),
    "DLT normalisation not undone": ("lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            T1, T2 = _normalisation(src), _normalisation(dst)
            s = src @ T1[:2, :2].T + T1[:2, 2]
            d = dst @ T2[:2, :2].T + T2[:2, 2]
            _, _, Vt = np.linalg.svd(_dlt_rows(s, d))
            return Vt[-1].reshape(3, 3)
        """, ["without undoing the normalisation"]),
    "DLT with a reduced SVD": ("lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            T1, T2 = _normalisation(src), _normalisation(dst)
            s = src @ T1[:2, :2].T + T1[:2, 2]
            d = dst @ T2[:2, :2].T + T2[:2, 2]
            _, _, Vt = np.linalg.svd(_dlt_rows(s, d), full_matrices=False)
            H = np.linalg.inv(T2) @ Vt[-1].reshape(3, 3) @ T1
            return H / H[2, 2]
        """, ["full_matrices=false", "null vector"]),
    "DLT with OpenCV": ("lab08.ex2", """
        def homography_dlt(src, dst):
            H, _ = cv2.findHomography(np.float64(src), np.float64(dst), 0)
            return H
        """, ["cv2.findHomography", "yourself"]),
    "DLT with a sign error in the u rows": ("lab08.ex2", """
        _reference_rows = _dlt_rows
        def _dlt_rows(src, dst):
            A = _reference_rows(src, dst)
            A[0::2, 6:9] *= -1
            return A
        """, ["sign error in the u rows"]),
    "DLT v rows built with u": ("lab08.ex2", """
        _reference_rows = _dlt_rows
        def _dlt_rows(src, dst):
            A = _reference_rows(src, dst)
            A[1::2, 6:9] = A[0::2, 6:9]
            return A
        """, ["the v rows use u"]),
    "DLT with u and v swapped in the rows": ("lab08.ex2", """
        _reference_rows = _dlt_rows
        def _dlt_rows(src, dst):
            return _reference_rows(src, np.asarray(dst)[:, ::-1])
        """, ["u and v are swapped"]),
    "DLT normalisation undone the wrong way round": ("lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            T1, T2 = _normalisation(src), _normalisation(dst)
            _, _, Vt = np.linalg.svd(_dlt_rows(transform_points(T1, src), transform_points(T2, dst)))
            H = T2 @ Vt[-1].reshape(3, 3) @ np.linalg.inv(T1)
            return H / H[2, 2]
        """, ["undone the wrong way round"]),
    "DLT takes the largest singular vector": ("lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            T1, T2 = _normalisation(src), _normalisation(dst)
            _, _, Vt = np.linalg.svd(_dlt_rows(transform_points(T1, src), transform_points(T2, dst)))
            H = np.linalg.inv(T2) @ Vt[0].reshape(3, 3) @ T1
            return H / H[2, 2]
        """, ["largest singular value"]),
    "warp_to_reference keeps the moving size": ("lab08.ex2", """
        def warp_to_reference(reference, moving, H):
            return apply_homography(moving, H)
        """, ["reference's size"]),
    "warp_to_reference cropping the moving-size warp": ("lab08.ex2", """
        def warp_to_reference(reference, moving, H):
            rows, cols = reference.shape[:2]
            out = np.zeros_like(reference if reference.ndim == moving.ndim else moving[:1, :1].repeat(rows, 0).repeat(cols, 1))
            warped = apply_homography(moving, H)
            keep_r, keep_c = min(rows, warped.shape[0]), min(cols, warped.shape[1])
            out[:keep_r, :keep_c] = warped[:keep_r, :keep_c]
            return out
        """, ["changing `apply_homography(moving, H)` to `apply_homography(moving, H, dsize=(cols, rows))`"]),
    "every point divided by the first point's w": ("lab08.ex1", """
        def transform_points(H, pts):
            q = np.hstack([np.asarray(pts, float), np.ones((len(pts), 1))]) @ np.asarray(H, float).T
            return q[:, :2] / q[0, 2]
        """, ["first point's w"]),
    "DLT with a sign error in the second row": ("lab08.ex2", """
        def _dlt_rows(src, dst):
            n = len(src)
            A = np.zeros((2 * n, 9))
            sh = np.hstack([src, np.ones((n, 1))])
            A[0::2, 0:3] = sh; A[0::2, 6:9] = -dst[:, :1] * sh
            A[1::2, 3:6] = sh; A[1::2, 6:9] = dst[:, 1:] * sh        # sign error
            return A
        """, ["sign error in the v rows"]),
    "DLT with the largest singular vector": ("lab08.ex2", """
        def homography_dlt(src, dst):
            A = _dlt_rows(np.asarray(src, float), np.asarray(dst, float))
            H = np.linalg.svd(A)[2][0].reshape(3, 3)
            return H / H[2, 2]
        """, ["largest singular value"]),
    "homography_dlt centring the caller's points in place": ("lab08.ex2", """
        _reference_dlt = homography_dlt
        def homography_dlt(src, dst):
            src = np.asarray(src, dtype=float)       # no copy for a float array
            dst = np.asarray(dst, dtype=float)
            ms, md = src.mean(axis=0), dst.mean(axis=0)
            src -= ms
            dst -= md
            H = _reference_dlt(src, dst)
            T_src = np.array([[1, 0, -ms[0]], [0, 1, -ms[1]], [0, 0, 1.0]])
            T_dst_inv = np.array([[1, 0, md[0]], [0, 1, md[1]], [0, 0, 1.0]])
            return T_dst_inv @ H @ T_src
        """, ["the caller's `src` in place", "called a second time on that same array"]),
    # ---------------------------------------------------------------- ex3
    # the blind set 1202d's 08/07: each image's contrast stretched before it is placed
    # the tutorial's list comprehension made an array without its shape: (0,) when nothing passes the test
    "match_features answering (0,) arrays when no match passes": ("lab08.ex3", """
        def match_features(img1, img2, ratio=0.75, method="sift"):
            grey = lambda im: cv2.cvtColor(im, cv2.COLOR_BGR2GRAY) if im.ndim == 3 else im
            sift = cv2.SIFT_create() if method == "sift" else cv2.ORB_create(1000)
            k1, d1 = sift.detectAndCompute(grey(img1), None)
            k2, d2 = sift.detectAndCompute(grey(img2), None)
            if d1 is None or d2 is None or len(k2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            norm = cv2.NORM_L2 if method == "sift" else cv2.NORM_HAMMING
            good = [m for m, n in cv2.BFMatcher(norm).knnMatch(d1, d2, k=2) if m.distance < ratio * n.distance]
            return np.float64([k1[m.queryIdx].pt for m in good]), np.float64([k2[m.trainIdx].pt for m in good])
        """, ["pts1 has shape (0,); expected (0, 2)"]),
    "draw_matches stretching each image's contrast": ("lab08.ex3", """
        _right_draw = draw_matches
        def draw_matches(img1, img2, pts1, pts2):
            stretch = lambda im: cv2.normalize(im, None, 0, 255, cv2.NORM_MINMAX)
            return _right_draw(stretch(img1), stretch(img2), pts1, pts2)
        """, ["the images themselves are changed"]),
    "Lowe's test on squared distances (the test at sqrt(ratio))": ("lab08.ex3", """
        def match_features(img1, img2, ratio=0.75, method="sift"):
            sift = cv2.SIFT_create()
            grey = [cv2.cvtColor(i, cv2.COLOR_BGR2GRAY) if i.ndim == 3 else i for i in (img1, img2)]
            (kp1, d1), (kp2, d2) = (sift.detectAndCompute(g, None) for g in grey)
            pts1, pts2 = [], []
            for m, n in cv2.BFMatcher(cv2.NORM_L2).knnMatch(d1, d2, k=2):
                if m.distance ** 2 < ratio * n.distance ** 2:
                    pts1.append(kp1[m.queryIdx].pt)
                    pts2.append(kp2[m.trainIdx].pt)
            return np.array(pts1).reshape(-1, 2), np.array(pts2).reshape(-1, 2)
        """, ["squared distances compared with the ratio", "squares the distances it compares"]),
    "draw_matches placing img2 on the canvas after the lines": ("lab08.ex3", """
        def draw_matches(img1, img2, pts1, pts2):
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
            canvas[:h1, :w1] = _bgr(img1)
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                cv2.line(canvas, (int(round(x1)), int(round(y1))), (int(round(x2 + w1)), int(round(y2))),
                         (0, 255, 0), 1, cv2.LINE_AA)
            canvas[:h2, w1:] = _bgr(img2)
            return canvas
        """, ["img2 is placed on the canvas after the drawing"]),
    # the blind set 1201c's 08/04: the matched positions kept as int32 (as for drawing)
    # the blind set 1201d's 08/03: the best 50 matches kept whatever the ratio
    # the blind set 1201e's 08/06: Lowe's paper's 0.8 as the default
    # the blind set 1201f's 08/04: the keypoints circled in the caller's own images
    "draw_matches circling the points in the caller's images": ("lab08.ex3", """
        _draw_matches = draw_matches
        def draw_matches(img1, img2, pts1, pts2):
            for image, pts in ((img1, pts1), (img2, pts2)):
                for x, y in np.asarray(pts, np.float64).reshape(-1, 2):
                    cv2.circle(image, (int(round(x)), int(round(y))), 3, (0, 255, 255), 1)
            return _draw_matches(img1, img2, pts1, pts2)
        """, ["writes into the caller's `img1` in place"]),
    "match_features with the default ratio 0.8": ("lab08.ex3", """
        _match_features = match_features
        def match_features(img1, img2, ratio=0.8, method="sift"):
            return _match_features(img1, img2, ratio, method)
        """, ["gives `ratio` the default 0.8, where the api's default is ratio=0.75"]),
    # the blind set 1202e's 08/08: an ORB tutorial's absolute cut-off beside Lowe's test
    "match_features with a fixed distance cut-off beside the ratio test": ("lab08.ex3", """
        def _match(features1, features2, ratio, method="sift"):
            (points1, descriptors1), (points2, descriptors2) = features1, features2
            norm = cv2.NORM_HAMMING if method == "orb" else cv2.NORM_L2
            pairs = cv2.BFMatcher(norm).knnMatch(descriptors1, descriptors2, k=2)
            good = [m for m, n in (p for p in pairs if len(p) == 2) if m.distance < ratio * n.distance and m.distance < 64]
            query = np.array([m.queryIdx for m in good], dtype=int)
            train = np.array([m.trainIdx for m in good], dtype=int)
            return points1[query].reshape(-1, 2), points2[train].reshape(-1, 2)
        """, ["a fixed cut-off", "m.distance < 64"]),
    "match_features keeping the first 50 matches": ("lab08.ex3", """
        _match_features = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            pts1, pts2 = _match_features(img1, img2, ratio, method)
            return pts1[:50], pts2[:50]
        """, ["your code keeps the first 50 (`pts1[:50]`)"]),
    "match_features with the keypoint positions cast to int32": ("lab08.ex3", """
        _match_features = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            pts1, pts2 = _match_features(img1, img2, ratio, method)
            return np.array(pts1, dtype=np.int32), np.array(pts2, dtype=np.int32)
        """, ["are whole numbers (an array of int32)", "your code makes them integers"]),
    "no ratio test": ("lab08.ex3", """
        _reference_match = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            return _reference_match(img1, img2, ratio=0.8, method=method)
        """, ["no effect"]),
    "ratio test reversed": ("lab08.ex3", """
        _reference_match = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            return _reference_match(img1, img2, ratio=1.5 - ratio, method=method)
        """, ["reversed"]),
    "pts1 and pts2 swapped": ("lab08.ex3", """
        _reference_match = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            pts1, pts2 = _reference_match(img1, img2, ratio, method)
            return pts2, pts1
        """, ["swapped"]),
    "matches as (row, column)": ("lab08.ex3", """
        _reference_match = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            pts1, pts2 = _reference_match(img1, img2, ratio, method)
            return pts1[:, ::-1], pts2[:, ::-1]
        """, ["x and y are swapped"]),
    "matcher fed the same image twice": ("lab08.ex3", """
        def match_features(img1, img2, ratio=0.75, method="sift"):
            return _match(_detect(img1, method), _detect(img1, method), ratio, method)
        """, ["same image twice"]),
    "draw_matches converting a grey img2 only": ("lab08.ex3", """
        def draw_matches(img1, img2, pts1, pts2):
            if img2.ndim == 2:
                img2 = cv2.cvtColor(img2, cv2.COLOR_GRAY2BGR)
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
            canvas[:h1, :w1] = img1
            canvas[:h2, w1:] = img2
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                cv2.line(canvas, (int(round(x1)), int(round(y1))), (int(round(x2 + w1)), int(round(y2))),
                         (0, 255, 0), 1, cv2.LINE_AA)
            return canvas
        """, ["`canvas[:h1, :w1] = img1` to `canvas[:h1, :w1] = _bgr(img1)`"]),   # (img1 made colour as img2 is)
    "lines not shifted by W1": ("lab08.ex3", """
        _reference_draw = draw_matches
        def draw_matches(img1, img2, pts1, pts2):
            return _reference_draw(img1, img2, pts1, np.asarray(pts2) - [img1.shape[1], 0])
        """, ["x2 + w1"]),
    "lines shifted by W2 instead of W1": ("lab08.ex3", _SIDE_BY_SIDE + """            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                cv2.line(canvas, (int(round(x1)), int(round(y1))), (int(round(x2 + w2)), int(round(y2))),
                         (0, 255, 0), 1, cv2.LINE_AA)
            return canvas
        """, ["shifted by img2's width", "x2 + w1"]),
    "lines ending at y2 + W1 (the offset on the wrong coordinate)": ("lab08.ex3", _SIDE_BY_SIDE + """            for p, q in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                end = (int(round(q[0])), int(round(q[1] + w1)))
                cv2.line(canvas, (int(round(p[0])), int(round(p[1]))), end, (0, 255, 0), 1, cv2.LINE_AA)
            return canvas
        """, ["(x2, y2 + W1)", "added to y2"]),
    "points drawn as (row, column)": ("lab08.ex3", _SIDE_BY_SIDE + """            for (r1, c1), (r2, c2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                cv2.line(canvas, (int(c1), int(r1)), (int(c2) + w1, int(r2)), (0, 255, 0), 1)
            return canvas
        """, ["other order", "(y1, x1)"]),
    "images stacked vertically": ("lab08.ex3", """
        def draw_matches(img1, img2, pts1, pts2):
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((h1 + h2, max(w1, w2), 3), np.uint8)
            canvas[:h1, :w1] = _bgr(img1)
            canvas[h1:, :w2] = _bgr(img2)
            return canvas
        """, ["side by side"]),
    "a canvas as high as img1 only (raises for a taller img2)": ("lab08.ex3", """
        def draw_matches(img1, img2, pts1, pts2):
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((h1, w1 + w2, 3), np.uint8)
            canvas[:h1, :w1] = _bgr(img1)
            canvas[:h2, w1:] = _bgr(img2)
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                cv2.line(canvas, (int(round(x1)), int(round(y1))), (int(round(x2 + w1)), int(round(y2))),
                         (0, 255, 0), 1, cv2.LINE_AA)
            return canvas
        """, ["`(max(h1, h2), w1 + w2, 3)`"]),
    # ---------------------------------------------------------------- ex4
    "draw_matches with the two point sets exchanged": ("lab08.ex3", """
        _reference_draw_matches = draw_matches
        def draw_matches(img1, img2, pts1, pts2):
            return _reference_draw_matches(img1, img2, pts2, pts1)
        """, ["point sets are exchanged"]),
    # samples drawn by shuffling the correspondences themselves: the best mask is in some earlier turn's order
    "RANSAC shuffling its correspondences in place": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None, confidence=0.999, max_iterations=5000):
            rng = np.random.default_rng(seed)
            both = np.hstack([np.asarray(src, np.float64).reshape(-1, 2), np.asarray(dst, np.float64).reshape(-1, 2)])
            keep = np.zeros(len(both), bool)
            for _ in range(500):
                rng.shuffle(both)
                H = homography_dlt(both[:4, :2], both[:4, 2:])
                near = np.linalg.norm(transform_points(H, both[:, :2]) - both[:, 2:], axis=1) < threshold
                if near.sum() > keep.sum():
                    keep = near
            return homography_dlt(both[keep, :2], both[keep, 2:]), keep
        """, ["shuffles `both` itself at every turn"]),
    "RANSAC without the final refit": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)
            best, best_count = None, -1
            for _ in range(500):
                idx = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[idx], dst[idx])
                count = (np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold).sum()
                if count > best_count:
                    best, best_count = H, count
            return best, np.linalg.norm(transform_points(best, src) - dst, axis=1) < threshold
        """, ["refit h on all the inliers"]),
    # the blind set 1204d's 08/05: the inliers taken as np.where's tuple, counted by len (always 1)
    # the blind set 1204d's 08/03: the warp brightened or darkened to the reference's mean (a gain step the
    # sheet does not ask for): taken out whole, not steered round (its mask made empty, its gain floored to 1)
    # the blind set 1204e's 08/03: the moving image cut (or padded) to the reference's size before it is warped
    "warp_to_reference cutting the moving image to the reference's size first": ("lab08.ex2", reference_def_with(
        "lab08_homographies", "warp_to_reference", "return apply_homography(moving, H, (width, height))",
        "canvas = np.zeros((height, width) + moving.shape[2:], dtype=moving.dtype)\n"
        "rows, cols = min(height, moving.shape[0]), min(width, moving.shape[1])\n"
        "canvas[:rows, :cols] = moving[:rows, :cols]\n"
        "return apply_homography(canvas, H, (width, height))"), ["`apply_homography(moving, H, (width, height))`"]),
    # the blind set 1205g's 08/01: an affine H's top rows handed to cv2.warpAffine without dividing by H[2, 2]
    "apply_homography warping an affine H by its top rows, H[2, 2] left out": ("lab08.ex1", reference_def_with(
        "lab08_homographies", "apply_homography", "height, width = image.shape[:2]",
        "height, width = image.shape[:2]\n"
        "H = np.asarray(H, dtype=np.float64)\n"
        "if H[2, 0] == 0 and H[2, 1] == 0:\n"
        "    return cv2.warpAffine(image, H[:2], dsize or (width, height), flags=cv2.INTER_LINEAR)"),
        ["and not for 2.5 A, the same map"]),
    # the blind set 1205g's 08/03: a degeneracy test of one rank (`!= 8`) where a bound belongs, refusing every
    # noisy system (rank 9); its negation, which refuses the exact pairs the code fitted, is no repair
    "homography_dlt refusing every system whose rank is not exactly 8": ("lab08.ex2", reference_def_with(
        "lab08_homographies", "homography_dlt", "A = _dlt_rows(src_n, dst_n)",
        "A = _dlt_rows(src_n, dst_n)\n"
        "if np.linalg.matrix_rank(A) != 8:\n"
        "    raise ValueError('degenerate point configuration')"),
        ["to `np.linalg.matrix_rank(A) < 8`"]),
    "warp_to_reference matching the reference's brightness": ("lab08.ex2", reference_def_with(
        "lab08_homographies", "warp_to_reference", "return apply_homography(moving, H, (width, height))",
        "warped = apply_homography(moving, H, (width, height))\n"
        "covered = apply_homography(np.ones(moving.shape[:2], np.uint8), H, (width, height)) > 0\n"
        "if covered.any():\n"
        "    gain = reference[covered].mean() / max(warped[covered].mean(), 1e-6)\n"
        "    warped = np.clip(np.round(warped * gain), 0, 255).astype(np.uint8)\n"
        "return warped"), ["removing `if covered.any(): ...`"]),
    "RANSAC counting np.where's tuple": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)
            best, best_count = None, 0
            for _ in range(500):
                idx = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[idx], dst[idx])
                inliers = np.where(np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold)
                if len(inliers) > best_count:
                    best, best_count = inliers, len(inliers)
            if best_count < 4:
                return homography_dlt(src, dst), np.ones(len(src), dtype=bool)
            H = homography_dlt(src[best], dst[best])
            return H, np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
        """, ["counts with `len(inliers)`", "`np.where(...)[0]`"]),
    "RANSAC comparing distances with the threshold squared": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)
            best, best_count = None, -1
            for _ in range(500):
                idx = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[idx], dst[idx])
                count = (np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold ** 2).sum()
                if count > best_count:
                    best, best_count = H, count
            inliers = np.linalg.norm(transform_points(best, src) - dst, axis=1) < threshold ** 2
            H = homography_dlt(src[inliers], dst[inliers])
            return H, np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold ** 2
        """, ["the mask acts as if the threshold were larger than 3 px"]),
    "RANSAC taking the norm of every pair at once": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)

            def inliers_of(H):
                errors = np.linalg.norm(transform_points(H, src) - dst)
                return errors < threshold

            best = np.ones(len(src), dtype=bool)
            for _ in range(300):
                mask = inliers_of(homography_dlt(*(p[rng.choice(len(src), 4, replace=False)] for p in (src, dst))))
                if np.sum(mask) > np.sum(best):
                    best = mask
            H = homography_dlt(src[best], dst[best]) if np.ndim(best) else homography_dlt(src, dst)
            return H, inliers_of(H)
        """, ["without an axis", "one true or false for all the pairs"]),
    "RANSAC with too few samples": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)
            best, best_count = None, -1
            for _ in range(6):
                idx = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[idx], dst[idx])
                count = (np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold).sum()
                if count > best_count:
                    best, best_count = H, count
            inliers = np.linalg.norm(transform_points(best, src) - dst, axis=1) < threshold
            H = homography_dlt(src[inliers], dst[inliers]) if inliers.sum() >= 4 else best
            return H, np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
        """, ["draws too few samples"]),
    "RANSAC with squared distances, H refit once more after the mask": ("lab08.ex4", """
        _ransac = homography_ransac
        def homography_ransac(src, dst, threshold=3.0, seed=None, confidence=0.999, max_iterations=5000):
            H, mask = _ransac(src, dst, np.sqrt(threshold), seed, confidence, max_iterations)
            keep = np.asarray(mask).ravel().astype(bool)
            return homography_dlt(np.asarray(src, float)[keep], np.asarray(dst, float)[keep]), mask
        """, ["*squared* error"]),
    "RANSAC with squared distances": ("lab08.ex4", """
        _reference_ransac = homography_ransac
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            H, _ = _reference_ransac(src, dst, threshold, seed)
            err = np.linalg.norm(transform_points(H, src) - np.asarray(dst), axis=1)
            return H, err ** 2 < threshold
        """, ["squared"]),
    "RANSAC inlier test by the L1 distance |du| + |dv|": ("lab08.ex4", """
        def _transfer_errors(Hs, src, dst):
            homogeneous = np.hstack([src, np.ones((len(src), 1))])
            mapped = np.einsum("kij,nj->kni", Hs, homogeneous)
            with np.errstate(divide="ignore", invalid="ignore"):
                xy = mapped[..., :2] / mapped[..., 2:3]
            errors = np.abs(xy - dst).sum(axis=2)
            return np.where(np.isfinite(errors), errors, np.inf)
        """, ["|du| + |dv| (the L1 distance)"]),
    "RANSAC mask inverted": ("lab08.ex4", """
        _reference_ransac = homography_ransac
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            H, inliers = _reference_ransac(src, dst, threshold, seed)
            return H, ~inliers
        """, ["mask is inverted"]),
    "RANSAC keeps the last sample's model": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)
            for _ in range(200):
                idx = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[idx], dst[idx])
                inliers = np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
            return H, inliers
        """, ["does not keep the model with the most inliers"]),
    "RANSAC fits all points": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            H = homography_dlt(src, dst)
            return H, np.linalg.norm(transform_points(H, src) - np.asarray(dst), axis=1) < threshold
        """, ["outliers included"]),
    "RANSAC returning its best 4-point H (many samples, no refit)": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)
            samples = np.array([rng.choice(len(src), 4, replace=False) for _ in range(1500)])
            best, best_count, best_spread = None, -1, np.inf
            for idx in samples:
                H = homography_dlt(src[idx], dst[idx])
                err = np.linalg.norm(transform_points(H, src) - dst, axis=1)
                count, spread = (err < threshold).sum(), err[err < threshold].sum()
                if (count, -spread) > (best_count, -best_spread):
                    best, best_count, best_spread = H, count, spread
            return best, np.linalg.norm(transform_points(best, src) - dst, axis=1) < threshold
        """, ["not the fit to its own inliers", "refit h on all the inliers"]),
    "RANSAC returning the last sample's mask": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float)
            dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)
            best_count, best_inliers = -1, None
            for _ in range(500):
                idx = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[idx], dst[idx])
                inliers = np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
                if inliers.sum() > best_count:
                    best_count, best_inliers = inliers.sum(), inliers
            H = homography_dlt(src[best_inliers], dst[best_inliers])
            return H, inliers
        """, ["reads `inliers` after the loop: that is the value of the loop's last turn"]),
    "RANSAC with a fixed threshold (the argument ignored)": ("lab08.ex4", """
        _reference_ransac = homography_ransac
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            return _reference_ransac(src, dst, 1.0, seed)
        """, ["threshold=1.0 and threshold=20.0 give the same h and inlier mask: threshold is ignored"]),
    "RANSAC at OpenCV's default threshold (the argument not passed on)": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            H, mask = cv2.findHomography(np.asarray(src, np.float64), np.asarray(dst, np.float64), cv2.RANSAC)
            return H / H[2, 2], mask.ravel().astype(bool)
        """, ["not H's inliers at the threshold given"]),
    "RANSAC keeping the last model drawn": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            rng = np.random.default_rng(seed)
            for _ in range(200):
                idx = rng.choice(len(src), 4, replace=False)
                H = homography_dlt(src[idx], dst[idx])
                inliers = np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
            if inliers.sum() >= 4:
                H = homography_dlt(src[inliers], dst[inliers])
            return H, np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
        """, ["returns the last model drawn rather than the best one."]),   # (500 samples: not "too few")
    # ---------------------------------------------------------------- ex5
    # the blind set 1203c's 08/06: OpenCV's stitching pipeline, which warps img1 too
    "stitch through cv2.Stitcher": ("lab08.ex5", """
        def stitch(img1, img2):
            status, panorama = cv2.Stitcher_create(cv2.Stitcher_PANORAMA).stitch([img1, img2])
            if status != cv2.Stitcher_OK:
                raise RuntimeError(f"stitching failed (status {status})")
            return panorama
        """, ["your code stitches with `cv2.Stitcher_create`"]),
    "stitch composing the grey copies made for the matching": ("lab08.ex5", """
        def stitch(img1, img2):
            img1, img2 = _grey(img1), _grey(img2)
            H21 = _pairwise_homography(img2, img1)
            return _compose([cv2.cvtColor(img1, cv2.COLOR_GRAY2BGR), cv2.cvtColor(img2, cv2.COLOR_GRAY2BGR)],
                            [np.eye(3), H21])
        """, ["colours are lost"]),
    "stitch averaging the two warps in uint8 (the sum wraps past 255)": ("lab08.ex5", _STITCH_CANVAS + """
            warped1 = apply_homography(_bgr(img1), shift, size)
            warped2 = apply_homography(_bgr(img2), shift @ H21, size)
            both = (warped1 > 0).any(axis=2) & (warped2 > 0).any(axis=2)
            panorama = np.maximum(warped1, warped2)
            panorama[both] = (warped1[both] + warped2[both]) // 2
            return panorama
        """, ["uint8 images gives when it wraps round"]),
    # the blind set 1201d's 08/06: the feathered sum never divided by the summed weights
    "panorama as the weighted sum, never divided by the weights": ("lab08.ex5", _COMPOSE_FEATHERED.format(
        panorama="total"), ["never divided by the sum of its weights", "adds the weights up in `weights`"]),
    # the blind set 1204e's 08/07: the feathered sum divided by one number for the whole canvas
    "panorama as the weighted sum divided by the largest summed weight": ("lab08.ex5", _COMPOSE_FEATHERED.format(
        panorama="total / np.max(weights)"),
        ["img1 is in place, only shifted, but its levels are scaled", "`weights[..., None]`"]),
    # the blind set 1203b's 08/07: img2 warped onto the canvas, img1 pasted over it (nothing blended)
    "stitch pasting img1 over the warped img2": ("lab08.ex5", _STITCH_CANVAS + """
            panorama = apply_homography(_bgr(img2), shift @ H21, size)
            x, y = int(-x_min), int(-y_min)
            panorama[y:y + img1.shape[0], x:x + img1.shape[1]] = _bgr(img1)
            return panorama
        """, ["the overlap is img1 alone", "nothing of img2 is blended into it"]),
    "img2 as the reference": ("lab08.ex5", """
        def stitch(img1, img2):
            return _compose([img2, img1], [np.eye(3), _pairwise_homography(img1, img2)])
        """, ["img1 is the reference frame"]),
    "no shift for negative coordinates": ("lab08.ex5", """
        def stitch(img1, img2):
            H = _pairwise_homography(img2, img1)
            corners = transform_points(H, _corners(img2))
            w = int(max(corners[:, 0].max(), img1.shape[1] - 1)) + 1
            h = int(max(corners[:, 1].max(), img1.shape[0] - 1)) + 1
            warped = apply_homography(img2, H, (w, h))
            first = np.zeros_like(warped)
            first[: img1.shape[0], : img1.shape[1]] = img1
            both = (warped > 0).any(axis=2) & (first > 0).any(axis=2)
            panorama = np.maximum(warped, first)
            panorama[both] = ((warped[both].astype(np.float64) + first[both]) / 2).astype(np.uint8)
            return panorama
        """, ["not shifted for negative coordinates"]),
    # the shift made with the wrong sign: everything moved further out, the reference itself cut
    "canvas shifted the wrong way": ("lab08.ex5", """
        _translation_right = _translation
        def _translation(tx, ty):
            return _translation_right(-tx, -ty)
        """, ["shifted the wrong way", "outside the canvas"]),
    "canvas of img1's size": ("lab08.ex5", """
        def stitch(img1, img2):
            H = _pairwise_homography(img2, img1)
            warped = apply_homography(img2, H, (img1.shape[1], img1.shape[0]))
            return np.where(img1 > 0, img1, warped)
        """, ["cut off", "bounding box"]),
    "img2 warped with the inverse": ("lab08.ex5", """
        def stitch(img1, img2):
            return _compose([img1, img2], [np.eye(3), np.linalg.inv(_pairwise_homography(img2, img1))])
        """, ["inverse homography"]),
    "canvas shift on the wrong side of H": ("lab08.ex5", _STITCH_CANVAS + """
            first, second = apply_homography(img1, shift, size), apply_homography(img2, H21 @ shift, size)
            both = (first > 0) & (second > 0)
            return np.where(both, first // 2 + second // 2, np.maximum(first, second))
        """, ["shift is on the wrong side"]),
    "canvas shift not applied to img2": ("lab08.ex5", _STITCH_CANVAS + """
            first, second = apply_homography(img1, shift, size), apply_homography(img2, H21, size)
            return np.where(first > 0, first, second)
        """, ["shift is not applied to img2"]),
    "img2 as the reference (img1 warped onto img2)": ("lab08.ex5", """
        def stitch(img1, img2):
            H12 = _pairwise_homography(img1, img2)
            return _compose([img1, img2], [H12, np.eye(3)])
        """, ["img2 is used as the reference frame"]),
    # ---------------------------------------------------------------- ext1
    "ORB matcher fed img1 twice": ("lab08.ext1", """
        _reference_match = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            if method == "orb":
                return _match(_detect(img1, method), _detect(img1, method), ratio, method)
            return _reference_match(img1, img2, ratio, method)
        """, ["same image"]),
    "ORB pts1 and pts2 exchanged": ("lab08.ext1", """
        _reference_match = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            pts1, pts2 = _reference_match(img1, img2, ratio, method)
            return (pts2, pts1) if method == "orb" else (pts1, pts2)
        """, ["pts1 and pts2 are swapped"]),
    "ORB points as (row, column)": ("lab08.ext1", """
        _reference_match = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            pts1, pts2 = _reference_match(img1, img2, ratio, method)
            return (pts1[:, ::-1], pts2[:, ::-1]) if method == "orb" else (pts1, pts2)
        """, ["x and y are swapped"]),
    "method ignored": ("lab08.ext1", """
        _reference_match = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            return _reference_match(img1, img2, ratio)
        """, ["the method argument is not followed"]),
    # ---------------------------------------------------------------- ext2
    # the blind set 1204f's 08/05: the list of images made one array (images of one size only)
    "stitch_many stacking the images into one array": ("lab08.ext2", """
        _reference_many = stitch_many
        def stitch_many(images):
            images = np.asarray(images)
            return _reference_many(list(images))
        """, ["`np.asarray(images)` to `list(images)`"]),
    "homographies chained in the wrong order": ("lab08.ext2", """
        def stitch_many(images):
            images = list(images)
            step = [_pairwise_homography(images[k + 1], images[k]) for k in range(len(images) - 1)]
            homographies = [np.eye(3)]
            for k in range(1, len(images)):
                H = np.eye(3)
                for j in range(k):
                    H = H @ step[j] if j == 0 else step[j] @ H   # wrong order
                homographies.append(H / H[2, 2])
            return _compose(images, homographies)
        """, ["chain"]),
    # the reference in the middle, the chain right of it multiplied the other way round: right with 3 or 4
    # images (one step on that side), wrong from 5 (the hidden five-view check's views do not commute)
    "homographies right of the middle reference chained in the reverse order": ("lab08.ext2", """
        def stitch_many(images):
            images = list(images)
            features = [_detect(image) for image in images]
            step = [_pairwise_homography(features[k + 1], features[k]) for k in range(len(images) - 1)]
            r = len(images) // 2
            homographies = []
            for k in range(len(images)):
                H = np.eye(3)
                if k > r:
                    for j in range(k - 1, r - 1, -1):
                        H = H @ step[j]
                elif k < r:
                    for j in range(k, r):
                        H = np.linalg.inv(step[j]) @ H
                homographies.append(H / H[2, 2])
            return _compose(images, homographies)
        """, ["chained in the reverse order"]),
    "last image skipped (loop stops one short)": ("lab08.ext2", """
        def stitch_many(images):
            images = list(images)
            step = [_pairwise_homography(images[k + 1], images[k]) for k in range(len(images) - 1)]
            r = len(images) // 2
            homographies = []
            for k in range(len(images) - 1):                      # one short
                H = np.eye(3)
                for j in range(k - 1, r - 1, -1):
                    H = step[j] @ H
                for j in range(k, r):
                    H = np.linalg.inv(step[j]) @ H
                homographies.append(H / H[2, 2])
            return _compose(images[:-1], homographies)
        """, ["the last one, is left out"]),
    "first image skipped (loop starts at 1)": ("lab08.ext2", """
        def stitch_many(images):
            images = list(images)
            step = [_pairwise_homography(images[k + 1], images[k]) for k in range(len(images) - 1)]
            r = len(images) // 2
            homographies = []
            for k in range(1, len(images)):                       # starts one late
                H = np.eye(3)
                for j in range(k - 1, r - 1, -1):
                    H = step[j] @ H
                for j in range(k, r):
                    H = np.linalg.inv(step[j]) @ H
                homographies.append(H / H[2, 2])
            return _compose(images[1:], homographies)
        """, ["image 1", "left out"]),
    "many images without the canvas shift": ("lab08.ext2", """
        def _compose(images, homographies):          # no shift: the canvas starts at (0, 0)
            corners = np.vstack([transform_points(H, _corners(im)) for im, H in zip(images, homographies)])
            w, h = (np.ceil(corners.max(axis=0)) + 1).astype(int)
            out = np.zeros((h, w, 3), np.uint8)
            for image, H in zip(images, homographies):
                warped = apply_homography(_bgr(image), H, (int(w), int(h)))
                out = np.where(warped > 0, warped, out)
            return out
        """, ["cut off at the left", "translation"]),
    "only the first two images": ("lab08.ext2", """
        def stitch_many(images):
            return stitch(images[0], images[1])
        """, ["image 3, the last one, is left out"]),
    "the last image left out (range(len(images) - 1))": ("lab08.ext2", """
        _reference_many = stitch_many
        def stitch_many(images):
            images = list(images)
            return _reference_many([images[k] for k in range(len(images) - 1)])
        """, ["the last one, is left out"]),
    "the first image left out (range(1, len(images)))": ("lab08.ext2", """
        _reference_many = stitch_many
        def stitch_many(images):
            images = list(images)
            return _reference_many([images[k] for k in range(1, len(images))])
        """, ["the first one, is left out"]),
    "canvas of the middle image's size": ("lab08.ext2", """
        def stitch_many(images):
            images = list(images)
            step = [_pairwise_homography(images[k + 1], images[k]) for k in range(len(images) - 1)]
            r = len(images) // 2
            h, w = images[r].shape[:2]
            canvas = np.zeros((h, w, 3), np.uint8)
            for k, image in enumerate(images):
                H = np.eye(3)
                for j in range(k - 1, r - 1, -1):
                    H = step[j] @ H
                for j in range(k, r):
                    H = np.linalg.inv(step[j]) @ H
                warped = apply_homography(_bgr(image), H, (w, h))
                canvas = np.where(warped > 0, warped, canvas)
            return canvas
        """, ["the canvas is only one image's size"]),
    "pairwise H not inverted before the reference": ("lab08.ext2", """
        def stitch_many(images):
            images = list(images)
            step = [_pairwise_homography(images[k + 1], images[k]) for k in range(len(images) - 1)]
            r = len(images) // 2
            homographies = []
            for k in range(len(images)):
                H = np.eye(3)
                for j in range(k - 1, r - 1, -1):
                    H = step[j] @ H
                for j in range(k, r):
                    H = step[j] @ H          # np.linalg.inv(step[j]) forgotten
                homographies.append(H / H[2, 2])
            return _compose(images, homographies)
        """, ["image 1 was warped with the inverse homography"]),
    # ---------------------------------------------------------------- ext3
    # the blind set 1202f's 08/08: a leftover line overwrites the argument
    "blend_multiband with levels overwritten by a leftover levels = 4": ("lab08.ext3", """
        _blend_multiband = blend_multiband
        def blend_multiband(img1, img2, mask, levels=4):
            levels = 4
            return _blend_multiband(img1, img2, mask, levels)
        """, ["levels is ignored", "sets `levels = 4`"]),
    # the blind set 1202i's 08/08: the image pyramids built with the default's 4 levels, the mask's with levels
    "blend_multiband building the image pyramids with 4 levels whatever levels says": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            a = np.asarray(img1, dtype=np.float32)
            b = np.asarray(img2, dtype=np.float32)
            weights = _gaussian_pyramid(np.clip(np.asarray(mask, dtype=np.float32), 0, 1), levels)
            bands = []
            for band_a, band_b, w in zip(_laplacian_pyramid(a, 4), _laplacian_pyramid(b, 4), weights):
                if band_a.ndim == 3:
                    w = w[..., None]
                bands.append(w * band_a + (1 - w) * band_b)
            result = bands[-1]
            for band in reversed(bands[:-1]):
                result = cv2.pyrUp(result, dstsize=(band.shape[1], band.shape[0])) + band
            return np.clip(np.round(result), 0, 255).astype(np.uint8)
        """, ["with the default levels=4 it gives the image back"]),
    "plain alpha blend": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            m = np.asarray(mask, np.float64)
            if img1.ndim == 3:
                m = m[..., None]
            return np.clip(np.round(m * img1 + (1 - m) * img2), 0, 255).astype(np.uint8)
        """, ["plain cut"]),
    "pyramids in uint8": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            def lap(img):
                g = [img]
                for _ in range(levels - 1):
                    g.append(cv2.pyrDown(g[-1]))
                return [cv2.subtract(f, cv2.pyrUp(c, dstsize=(f.shape[1], f.shape[0])))
                        for f, c in zip(g[:-1], g[1:])] + [g[-1]]
            w = _gaussian_pyramid(np.asarray(mask, np.float32), levels)
            bands = []
            for a, b, m in zip(lap(img1), lap(img2), w):
                m = m[..., None] if a.ndim == 3 else m
                bands.append((m * a + (1 - m) * b).astype(np.uint8))
            out = bands[-1]
            for band in reversed(bands[:-1]):
                out = cv2.add(cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0])), band)
            return out
        """, ["float"]),
    "wide feather instead of a pyramid": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            m = cv2.GaussianBlur(np.asarray(mask, np.float64), (0, 0), 8.0)
            if img1.ndim == 3:
                m = m[..., None]
            return np.clip(np.round(m * img1 + (1 - m) * img2), 0, 255).astype(np.uint8)
        """, ["ghosting"]),
    "narrow feather instead of a pyramid": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            m = cv2.GaussianBlur(np.asarray(mask, np.float64), (0, 0), 2.5)
            if img1.ndim == 3:
                m = m[..., None]
            return np.clip(np.round(m * img1 + (1 - m) * img2), 0, 255).astype(np.uint8)
        """, ["narrow feather"]),
    "multi-band blend with the mask divided by its maximum": ("lab08.ext3", """
        _reference_blend = blend_multiband
        def blend_multiband(img1, img2, mask, levels=4):
            weights = np.asarray(mask, dtype=np.float64)
            weights = weights / weights.max()
            return _reference_blend(img1, img2, weights, levels)
        """, ["gives the same image as a mask of 1 everywhere", "`weights / weights.max()` (line"]),
    "multi-band blend with a fixed 2-level pyramid (levels ignored)": ("lab08.ext3", """
        _reference_blend = blend_multiband
        def blend_multiband(img1, img2, mask, levels=4):
            return _reference_blend(img1, img2, mask, 2)
        """, ["levels=1 and levels=6 give the same image: levels is ignored"]),
    "one smoothed mask for the whole image (no Laplacian pyramid)": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            weights = _gaussian_pyramid(np.asarray(mask, np.float32), levels)
            m = cv2.resize(weights[-1], (img1.shape[1], img1.shape[0]))
            m = m[..., None] if img1.ndim == 3 else m
            return np.clip(np.round(m * img1 + (1 - m) * img2), 0, 255).astype(np.uint8)
        """, ["not band by band in a laplacian pyramid"]),
    "collapse without adding the bands": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            weights = _gaussian_pyramid(np.asarray(mask, np.float32), levels)
            bands = []
            for a, b, w in zip(_laplacian_pyramid(np.float32(img1), levels),
                               _laplacian_pyramid(np.float32(img2), levels), weights):
                w = w[..., None] if a.ndim == 3 else w
                bands.append(w * a + (1 - w) * b)
            out = bands[-1]
            for band in reversed(bands[:-1]):
                out = cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0]))   # + band forgotten
            return np.clip(np.round(out), 0, 255).astype(np.uint8)
        """, ["does not add the bands back"]),
    # ---- inputs the usual set-up leaves out (issue 35): a single point, images of two sizes
    "transform_points squeezing its result": ("lab08.ex1", """
        def transform_points(H, pts):
            pts = np.asarray(pts, np.float64).reshape(-1, 1, 2)
            return cv2.perspectiveTransform(pts, np.asarray(H, np.float64)).squeeze()
        """, ["returned shape (2,); expected (1, 2)"]),
    "canvas from img1's size for both images": ("lab08.ex5", """
        def stitch(img1, img2):
            H = _pairwise_homography(img2, img1)
            h, w = img1.shape[:2]
            corners = np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], float)
            box = np.vstack([corners, transform_points(H, corners)])    # img2's corners at img1's size
            x_min, y_min = np.floor(box.min(axis=0))
            x_max, y_max = np.ceil(box.max(axis=0))
            T = _translation(-x_min, -y_min)
            size = (int(x_max - x_min) + 1, int(y_max - y_min) + 1)
            a = apply_homography(img1, T, size).astype(float)
            b = apply_homography(img2, T @ H, size).astype(float)
            ma = apply_homography(np.full(img1.shape[:2], 255, np.uint8), T, size) > 127
            mb = apply_homography(np.full(img2.shape[:2], 255, np.uint8), T @ H, size) > 127
            count = np.maximum(ma.astype(float) + mb, 1)[..., None]
            return np.clip((a * ma[..., None] + b * mb[..., None]) / count, 0, 255).astype(np.uint8)
        """, ["cut off at the right", "sized as if every image had one image's size", "at img1's size"]),
    "collapsed pyramid cast to uint8 without a clip": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            weights = _gaussian_pyramid(np.asarray(mask, np.float32), levels)
            bands = []
            for a, b, w in zip(_laplacian_pyramid(np.float32(img1), levels),
                               _laplacian_pyramid(np.float32(img2), levels), weights):
                w = w[..., None] if a.ndim == 3 else w
                bands.append(w * a + (1 - w) * b)
            out = bands[-1]
            for band in reversed(bands[:-1]):
                out = cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0])) + band
            return out.astype(np.uint8)      # values past 0..255 beside strong edges wrap around
        """, ["wrap around to the other end of the range instead of being clipped", "np.clip"]),
    "mask weights img2": ("lab08.ext3", """
        _reference_blend = blend_multiband
        def blend_multiband(img1, img2, mask, levels=4):
            return _reference_blend(img2, img1, mask, levels)
        """, ["weights img2"]),
    "mask pyramid by slicing (mask[::2, ::2], no smoothing)": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            weights = [np.float32(mask)]
            for _ in range(levels - 1):
                weights.append(weights[-1][::2, ::2])          # plain subsampling
            la, lb = _laplacian_pyramid(np.float32(img1), levels), _laplacian_pyramid(np.float32(img2), levels)
            blended = [(w[..., None] if a.ndim == 3 else w) * (a - b) + b for a, b, w in zip(la, lb, weights)]
            out = blended.pop()
            while blended:
                band = blended.pop()
                out = cv2.pyrUp(out, dstsize=band.shape[1::-1]) + band
            return np.clip(np.round(out), 0, 255).astype(np.uint8)
        """, ["subsampled without smoothing", "subsamples or resizes the mask"]),
    "the same mask resized (nearest) to every level": ("lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            la, lb = _laplacian_pyramid(np.float32(img1), levels), _laplacian_pyramid(np.float32(img2), levels)
            out = None
            for a, b in reversed(list(zip(la, lb))):      # blend and collapse, coarsest level first
                w = cv2.resize(np.float32(mask), (a.shape[1], a.shape[0]), interpolation=cv2.INTER_NEAREST)
                w = w[..., None] if a.ndim == 3 else w
                band = w * a + (1 - w) * b
                out = band if out is None else cv2.pyrUp(out, dstsize=(a.shape[1], a.shape[0])) + band
            return np.clip(np.round(out), 0, 255).astype(np.uint8)
        """, ["subsampled without smoothing"]),
    "mask pyramid by cv2.resize of the full mask (linear) to each level": ("lab08.ext3", """
        def _mask_levels(mask, shapes):
            return [cv2.resize(mask, (w, h)) for h, w in shapes]
        def blend_multiband(img1, img2, mask, levels=4):
            la = _laplacian_pyramid(np.float32(img1), levels)
            lb = _laplacian_pyramid(np.float32(img2), levels)
            weights = _mask_levels(np.float32(mask), [x.shape[:2] for x in la])
            bands = [(w[..., None] if a.ndim == 3 else w) * a + (1 - (w[..., None] if a.ndim == 3 else w)) * b
                     for a, b, w in zip(la, lb, weights)]
            out = bands[-1]
            for band in reversed(bands[:-1]):
                out = cv2.pyrUp(out, dstsize=(band.shape[1], band.shape[0])) + band
            return np.clip(np.round(out), 0, 255).astype(np.uint8)
        """, ["subsampled without smoothing"]),
    "ORB only on colour images": ("lab08.ext1", """
        _detect_right = _detect
        def _detect(image, method):
            if method == "orb":
                image = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)   # assumes a colour image
            return _detect_right(image, method)
        """, ['raised']),
    # ---------------------------------------------------------------- the API's conventions
    # k points of k coordinates taken for one point, or for points given as columns
    **columns_by_first_axis("transform_points", "lab08.ex1", "H, pts", ("pts",), "pts.shape[0] == 2"),
    "warp_to_reference makes a grey moving image BGR": ("lab08.ex2", """
        def warp_to_reference(reference, moving, H):
            if moving.ndim == 2:
                moving = cv2.cvtColor(moving, cv2.COLOR_GRAY2BGR)
            h, w = reference.shape[:2]
            return cv2.warpPerspective(moving, np.asarray(H, dtype=np.float64), (w, h))
        """, ["grey images", "channels are not kept"]),
    # ---- whole numbers given as integers; an H whose last entry is 0
    "transform_points answers integer points in integers": ("lab08.ex1", """
        _reference_transform = transform_points
        def transform_points(H, pts):
            moved = np.zeros_like(np.asarray(pts))
            moved[...] = _reference_transform(H, pts)
            return moved
        """, ["your answer is an integer array", "`moved = np.zeros_like(np.asarray(pts))`", "then writes into it"]),
    "apply_homography divides H by H[2, 2]": ("lab08.ex1", """
        _reference_apply = apply_homography
        def apply_homography(image, H, dsize=None):
            H = np.asarray(H, np.float64)
            return _reference_apply(image, H / H[2, 2], dsize)
        """, ["it divides by H[2, 2], which is 0 here"]),
    # ---- the distance the inlier mask is drawn with
    "RANSAC inliers by the x offset alone": ("lab08.ex4", """
        _reference_ransac = homography_ransac
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            H, _ = _reference_ransac(src, dst, threshold, seed)
            moved = transform_points(H, np.asarray(src, np.float64))
            return H, np.abs(moved[:, 0] - np.asarray(dst, np.float64)[:, 0]) < threshold
        """, ["the mask is exactly the pairs whose |du| alone"]),
    "match_features on a copy halved for speed, points never scaled back": ("lab08.ex3", """
        _match_right = match_features
        def match_features(img1, img2, ratio=0.75, method="sift"):
            small = [cv2.pyrDown(i) if max(i.shape[:2]) > 800 else i for i in (img1, img2)]
            return _match_right(small[0], small[1], ratio, method)
        """, ["scaled by 1/2", "scaled back"]),
    "draw_matches centring the shorter image vertically": ("lab08.ex3", """
        def draw_matches(img1, img2, pts1, pts2):
            a, b = _bgr(img1), _bgr(img2)
            height = max(a.shape[0], b.shape[0])
            canvas = np.zeros((height, a.shape[1] + b.shape[1], 3), dtype=np.uint8)
            top1, top2 = (height - a.shape[0]) // 2, (height - b.shape[0]) // 2
            canvas[top1:top1 + a.shape[0], :a.shape[1]] = a
            canvas[top2:top2 + b.shape[0], a.shape[1]:] = b
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                cv2.line(canvas, (int(round(x1)), int(round(y1)) + top1),
                         (int(round(x2)) + a.shape[1], int(round(y2)) + top2), (0, 255, 0), 1)
            return canvas
        """, ["centred vertically"]),
    "draw_matches colouring with NumPy integers": ("lab08.ex3", _SIDE_BY_SIDE + """            for p, q in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                colour = tuple(np.random.randint(0, 256, 3))
                start = (int(round(p[0])), int(round(p[1])))
                end = (int(round(q[0] + w1)), int(round(q[1])))
                cv2.line(canvas, start, end, colour, 1)
            return canvas
        """, ["changing `tuple(np.random.randint(0, 256, 3))` to `tuple(map(int, np.random.randint(0, 256, 3)))`"]),
    # the blind set 1205d's 08/06: each band the level less its own blur (a difference of Gaussians at one scale)
    "blend_multiband's bands made as a level less its own Gaussian blur": ("lab08.ext3", """
        def _laplacian_pyramid(image, levels):
            gaussian = _gaussian_pyramid(image, levels)
            bands = []
            for level in gaussian[:-1]:
                blurred = cv2.GaussianBlur(level, (5, 5), 0)
                bands.append(level - blurred)
            return bands + [gaussian[-1]]
        """, ["`level - blurred`, a level less its own blur"]),

    # (blind set 2026-12-06c)
    "matches kept wrapped in one-item lists (drawMatchesKnn's form), then read as matches": ("lab08.ex3", """
        def match_features(img1, img2, ratio=0.75, method="sift"):
            detector, norm = (cv2.SIFT_create(), cv2.NORM_L2) if method == "sift" else \\
                (cv2.ORB_create(nfeatures=1000), cv2.NORM_HAMMING)
            grey1 = img1 if img1.ndim == 2 else cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY)
            grey2 = img2 if img2.ndim == 2 else cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY)
            kp1, des1 = detector.detectAndCompute(grey1, None)
            kp2, des2 = detector.detectAndCompute(grey2, None)
            if des1 is None or des2 is None or len(kp2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            good = []
            for pair in cv2.BFMatcher(norm).knnMatch(des1, des2, k=2):
                if len(pair) == 2 and pair[0].distance < ratio * pair[1].distance:
                    good.append([pair[0]])
            pts1 = np.array([kp1[m.queryIdx].pt for m in good], dtype=np.float64).reshape(-1, 2)
            pts2 = np.array([kp2[m.trainIdx].pt for m in good], dtype=np.float64).reshape(-1, 2)
            return pts1, pts2
        """, ["is appended wrapped in one (`good.append([pair[0]])`", "`m[0].queryidx`"]),
    "pyramid bands blended by cv2.addWeighted with the mask level as its alpha": ("lab08.ext3", reference_def_with(
        "lab08_homographies", "blend_multiband", "bands.append(w * band_a + (1 - w) * band_b)",
        "bands.append(cv2.addWeighted(band_a, w, band_b, 1 - w, 0))"),
        ["cv2.addweighted needs one number for alpha", "multiply the arrays by it"]),

    "a RANSAC drawing each sample's source and destination points by two draws": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None, confidence=0.999, max_iterations=5000):
            src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            n = len(src)
            rng = np.random.default_rng(seed)
            best = np.zeros(n, dtype=bool)
            for _ in range(300):
                H = homography_dlt(src[rng.choice(n, 4, replace=False)], dst[rng.choice(n, 4, replace=False)])
                with np.errstate(all="ignore"):
                    inliers = np.linalg.norm(transform_points(H, src) - dst, axis=1) < threshold
                if inliers.sum() > best.sum():
                    best = inliers
            if best.sum() < 4:
                return homography_dlt(src, dst), np.ones(n, dtype=bool)
            return homography_dlt(src[best], dst[best]), best
        """, ["two separate random draws", "draw the indices once and take both with them"]),
    # (the blind sets 2026-12-06f's and 06g's 08/05: cv2.findHomography's mask flattened, never made bool)
    "RANSAC inlier mask returned as cv2.findHomography's uint8 0/1": ("lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            H, mask = cv2.findHomography(np.float32(src), np.float32(dst), cv2.RANSAC, threshold)
            return H / H[2, 2], mask.ravel()
        """, ["uint8 0s and 1s", "bool"]),
}


# Conventions the lab sheet leaves open: advice (0 points), never a lost point.
ADVICE = {
    "DLT without normalisation (the lab sheet's DLT on raw pixels)": ("lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            _, _, Vt = np.linalg.svd(_dlt_rows(src, dst))
            H = Vt[-1].reshape(3, 3)
            return H / H[2, 2]
        """, ["normalised dlt", "raw pixel coordinates", "no points"]),
    # The outputs cannot tell it (benchmarks/spread_lab08_extensions.py): a tip read from the code.
    "ORB descriptors matched with NORM_L2": ("lab08.ext1", """
        def _match(features1, features2, ratio, method="sift"):
            (points1, descriptors1), (points2, descriptors2) = features1, features2
            if descriptors1 is None or descriptors2 is None or len(points2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            pairs = cv2.BFMatcher(cv2.NORM_L2).knnMatch(descriptors1, descriptors2, k=2)
            good = [m for m, n in (p for p in pairs if len(p) == 2) if m.distance < ratio * n.distance]
            return (points1[[m.queryIdx for m in good]].reshape(-1, 2),
                    points2[[m.trainIdx for m in good]].reshape(-1, 2))
        """, ["cv2.NORM_L2", "hamming", "no points"]),
    "ORB descriptors (WTA_K = 2) matched with NORM_HAMMING2": ("lab08.ext1", """
        def _match(features1, features2, ratio, method="sift"):
            (points1, descriptors1), (points2, descriptors2) = features1, features2
            if descriptors1 is None or descriptors2 is None or len(points2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            norm = cv2.NORM_HAMMING2 if method == "orb" else cv2.NORM_L2
            pairs = cv2.BFMatcher(norm).knnMatch(descriptors1, descriptors2, k=2)
            good = [m for m, n in (p for p in pairs if len(p) == 2) if m.distance < ratio * n.distance]
            return (points1[[m.queryIdx for m in good]].reshape(-1, 2),
                    points2[[m.trainIdx for m in good]].reshape(-1, 2))
        """, ["cv2.NORM_HAMMING2", "WTA_K = 3 or 4", "no points"]),
    "ORB descriptors matched with BFMatcher()'s default norm": ("lab08.ext1", """
        def _match(features1, features2, ratio, method="sift"):
            (points1, descriptors1), (points2, descriptors2) = features1, features2
            if descriptors1 is None or descriptors2 is None or len(points2) < 2:
                return np.zeros((0, 2)), np.zeros((0, 2))
            pairs = cv2.BFMatcher().knnMatch(descriptors1, descriptors2, k=2)
            good = [m for m, n in (p for p in pairs if len(p) == 2) if m.distance < ratio * n.distance]
            return (points1[[m.queryIdx for m in good]].reshape(-1, 2),
                    points2[[m.trainIdx for m in good]].reshape(-1, 2))
        """, ["NORM_L2 by default", "hamming"]),
}
