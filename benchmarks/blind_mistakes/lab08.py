"""Lab 8: single-bug submissions written apart from the tables (see the package docstring)."""

from . import Case

MODULE = "lab08_homographies"

CASES = [
    Case("transform_points builds the homogeneous points with a column of zeros", "lab08.ex1", """
        def transform_points(H, pts):
            pts = np.asarray(pts, dtype=float)
            ones = np.zeros((pts.shape[0], 1))
            p = np.hstack([pts, ones])
            q = (H @ p.T).T
            return q[:, :2] / q[:, 2:3]
        """, "the homogeneous coordinate is 0 instead of 1 (the translation column is lost)",
         ("0 instead of 1", "zeros", "homogeneous", "translation", "third coordinate")),

    Case("DLT design matrix allocated as integers", "lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, dtype=float)
            dst = np.asarray(dst, dtype=float)
            n = len(src)
            A = np.zeros((2 * n, 9), dtype=int)
            for i in range(n):
                x, y = src[i]
                u, v = dst[i]
                A[2 * i] = [-x, -y, -1, 0, 0, 0, x * u, y * u, u]
                A[2 * i + 1] = [0, 0, 0, -x, -y, -1, x * v, y * v, v]
            _, _, Vt = np.linalg.svd(A)
            H = Vt[-1].reshape(3, 3)
            return H / H[2, 2]
        """, "A is an integer array: every coordinate product is truncated",
         ("integer", "int", "truncat", "fractions")),

    Case("match_features takes queryIdx and trainIdx the other way round", "lab08.ex3", """
        def match_features(img1, img2, ratio=0.75, method="sift"):
            g1 = cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY) if img1.ndim == 3 else img1
            g2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY) if img2.ndim == 3 else img2
            if method == "orb":
                det, norm = cv2.ORB_create(nfeatures=1000), cv2.NORM_HAMMING
            else:
                det, norm = cv2.SIFT_create(), cv2.NORM_L2
            kp1, des1 = det.detectAndCompute(g1, None)
            kp2, des2 = det.detectAndCompute(g2, None)
            matches = cv2.BFMatcher(norm).knnMatch(des1, des2, k=2)
            pts1, pts2 = [], []
            for pair in matches:
                if len(pair) < 2:
                    continue
                m, n = pair
                if m.distance < ratio * n.distance:
                    pts1.append(kp1[m.trainIdx].pt)
                    pts2.append(kp2[m.queryIdx].pt)
            return np.array(pts1, dtype=float).reshape(-1, 2), np.array(pts2, dtype=float).reshape(-1, 2)
        """, "queryIdx and trainIdx are exchanged (query indexes img1's keypoints)",
         ("queryidx", "trainidx", "query", "exchanged")),

    Case("RANSAC with findHomography(dst, src)", "lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, dtype=np.float64)
            dst = np.asarray(dst, dtype=np.float64)
            H, mask = cv2.findHomography(dst, src, cv2.RANSAC, threshold)
            return H, mask.ravel().astype(bool)
        """, "src and dst exchanged: the H returned maps dst onto src (the inverse)",
         ("inverse", "src and dst", "dst and src", "h is inverted")),

    Case("stitch adds the two warped images in uint8", "lab08.ex5", """
        def stitch(img1, img2):
            pts1, pts2 = match_features(img1, img2)
            H, _ = homography_ransac(pts2, pts1, 3.0, seed=0)
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            c1 = np.array([[0, 0], [w1, 0], [w1, h1], [0, h1]], dtype=float)
            c2 = transform_points(H, np.array([[0, 0], [w2, 0], [w2, h2], [0, h2]], dtype=float))
            allc = np.vstack([c1, c2])
            xmin, ymin = np.floor(allc.min(axis=0)).astype(int)
            xmax, ymax = np.ceil(allc.max(axis=0)).astype(int)
            T = np.array([[1, 0, -xmin], [0, 1, -ymin], [0, 0, 1]], dtype=float)
            size = (xmax - xmin, ymax - ymin)
            a = cv2.warpPerspective(img1, T, size)
            b = cv2.warpPerspective(img2, T @ H, size)
            both = (a.max(axis=2) > 0) & (b.max(axis=2) > 0)
            pano = np.where(both[..., None], (a + b) // 2, a + b)
            return pano.astype(np.uint8)
        """, "uint8 arithmetic: a + b wraps around in the overlap before it is halved",
         ("uint8", "wrap", "overflow")),

    Case("multi-band weights not broadcast over the colour channels", "lab08.ext3", """
        def blend_multiband(img1, img2, mask, levels=4):
            a = img1.astype(np.float32)
            b = img2.astype(np.float32)
            m = mask.astype(np.float32)
            ga, gb, gm = [a], [b], [m]
            for i in range(levels - 1):
                ga.append(cv2.pyrDown(ga[-1]))
                gb.append(cv2.pyrDown(gb[-1]))
                gm.append(cv2.pyrDown(gm[-1]))
            la, lb = [], []
            for i in range(levels - 1):
                size = (ga[i].shape[1], ga[i].shape[0])
                la.append(ga[i] - cv2.pyrUp(ga[i + 1], dstsize=size))
                lb.append(gb[i] - cv2.pyrUp(gb[i + 1], dstsize=size))
            la.append(ga[-1])
            lb.append(gb[-1])
            blended = [gm[i] * la[i] + (1 - gm[i]) * lb[i] for i in range(levels)]
            out = blended[-1]
            for i in range(levels - 2, -1, -1):
                out = cv2.pyrUp(out, dstsize=(blended[i].shape[1], blended[i].shape[0])) + blended[i]
            return np.clip(out, 0, 255).astype(np.uint8)
        """, "the (H, W) weights are not given a channel axis (w[..., None]) for colour images",
         ("channel", "broadcast", "[..., none]")),

    Case("draw_matches copies a grey img2 into the colour canvas as it is", "lab08.ex3", """
        def draw_matches(img1, img2, pts1, pts2):
            h1, w1 = img1.shape[:2]
            h2, w2 = img2.shape[:2]
            canvas = np.zeros((max(h1, h2), w1 + w2, 3), dtype=np.uint8)
            canvas[:h1, :w1] = img1 if img1.ndim == 3 else cv2.cvtColor(img1, cv2.COLOR_GRAY2BGR)
            canvas[:h2, w1:] = img2
            for (x1, y1), (x2, y2) in zip(pts1, pts2):
                cv2.line(canvas, (int(x1), int(y1)), (int(x2) + w1, int(y2)), (0, 255, 0), 1)
            return canvas
        """, "a grey img2 is not converted to BGR before it is copied into the 3-channel canvas",
         ("grey", "gray", "channel", "cvtcolor", "gray2bgr")),

    Case("warp_to_reference passes reference.shape[:2] as dsize", "lab08.ex2", """
        def warp_to_reference(reference, moving, H):
            return cv2.warpPerspective(moving, H, reference.shape[:2])
        """, "dsize is (width, height); shape[:2] is (height, width)",
         ("width and height", "(width, height)", "swapped")),

    Case("stitch_many sizes the canvas from the first and last images only", "lab08.ext2", """
        def stitch_many(images):
            images = list(images)
            n = len(images)
            r = n // 2
            step = []
            for k in range(n - 1):
                p_k, p_next = match_features(images[k], images[k + 1])
                H, _ = homography_ransac(p_next, p_k, 3.0, seed=0)
                step.append(H)
            Hs = []
            for k in range(n):
                H = np.eye(3)
                if k > r:
                    for j in range(k - 1, r - 1, -1):
                        H = step[j] @ H
                elif k < r:
                    for j in range(k, r):
                        H = np.linalg.inv(step[j]) @ H
                Hs.append(H / H[2, 2])
            corners = []
            for k in (0, n - 1):
                h, w = images[k].shape[:2]
                c = np.array([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]], dtype=float)
                corners.append(transform_points(Hs[k], c))
            corners = np.vstack(corners)
            xmin, ymin = np.floor(corners.min(axis=0))
            xmax, ymax = np.ceil(corners.max(axis=0))
            T = np.array([[1, 0, -xmin], [0, 1, -ymin], [0, 0, 1]])
            size = (int(xmax - xmin) + 1, int(ymax - ymin) + 1)
            pano = np.zeros((size[1], size[0], 3), np.float64)
            weight = np.zeros((size[1], size[0]), np.float64)
            for image, H in zip(images, Hs):
                warped = cv2.warpPerspective(image, T @ H, size).astype(np.float64)
                covered = cv2.warpPerspective(np.ones(image.shape[:2], np.float32), T @ H, size)
                pano += warped * covered[..., None]
                weight += covered
            return np.clip(pano / np.maximum(weight, 1e-9)[..., None], 0, 255).astype(np.uint8)
        """, "the bounding box leaves out the middle image's corners, so its part outside is cut off",
         ("bounding box", "middle image's corners", "not all the corners", "corners of every image")),
]
