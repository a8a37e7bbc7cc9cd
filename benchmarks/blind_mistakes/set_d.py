"""A fourth blind set (set d), written without reading how the grader names mistakes: its
author read only the lab sheet, the assignment API, the reference solutions, ``Case``, set c
(for its format and its case names, so as not to repeat them) and the runner, never the
grader, its fixtures, its tests or the other sets' cases. Four single-bug submissions per lab,
mostly on exercises set c left out, spread over kinds of mistake (sign of an angle, scaling
about the wrong point, transposed matrix, swapped arguments of OpenCV or of a helper, a
copy-pasted operand, a misplaced ratio, a missing flag, dehomogenising by the wrong
coordinate, radius taken as diameter, (x, y) order, an ignored argument, the wrong singular
vector, a sheet formula misapplied, denormalisation, a missing rotation, fixed-point units, a
falsy zero, half a stripe). Each truth was written with its case, before any measurement;
each case was checked in plain Python to change the reference's result on a small input.

Each entry is ``(module, Case)``; ``python benchmarks/blind_naming.py --set d`` grades them.
"""

from . import Case

CASES = [
    # ------------------------------------------------------------------ lab07
    ("lab07_transformations", Case("rotation uses the lecture's R(theta) as written", "lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = np.deg2rad(angle_deg)
            c, s = np.cos(theta), np.sin(theta)
            R = np.array([[c, -s], [s, c]])
            center = np.asarray(center, dtype=np.float64)
            M = np.eye(3)
            M[:2, :2] = R
            M[:2, 2] = center - R @ center
            return M
        """, "the lab sheet's R(theta) is copied as is; with y pointing down it turns the image "
        "clockwise on screen, so the angle's sign is reversed (the API wants R(-theta), as "
        "cv2.getRotationMatrix2D)",
        ("clockwise", "sign", "direction", "-θ", "-theta", "−θ", "negative angle", "negated",
         "opposite", "r(θ)", "r(-θ)", "r(theta)", "transpos", "inverse rotation"))),
    ("lab07_transformations", Case("scaling about the image centre", "lab07.ex3", """
        def scale(image, sx=1.5, sy=1.5):
            height, width = image.shape[:2]
            cx, cy = (width - 1) / 2.0, (height - 1) / 2.0
            M = np.array([[sx, 0.0, (1 - sx) * cx],
                          [0.0, sy, (1 - sy) * cy]])
            return cv2.warpAffine(image, M, (width, height))
        """, "the image is scaled about its centre; the API scales about the origin (the top-left "
        "pixel), so the result is shifted by (1 - s) times the centre",
        ("centre", "center", "origin", "top-left", "top left", "corner", "shifted", "translation",
         "offset"))),
    ("lab07_transformations", Case("shear factor below the diagonal", "lab07.ex4", """
        def shear_matrix(s):
            return np.array([[1.0, 0.0, 0.0],
                             [s, 1.0, 0.0],
                             [0.0, 0.0, 1.0]])
        """, "s is put in row 2, column 1: y' = y + s x, a vertical shear, instead of the sheet's "
        "x' = x + s y (the shear matrix is transposed)",
        ("vertical", "along y", "y-axis", "y axis", "y direction", "transpos", "wrong axis",
         "y' = y + s", "y + s x", "y + s*x", "y + sx", "[1, 0]", "row 2", "second row",
         "lower-left", "lower left", "below the diagonal", "x and y"))),
    ("lab07_transformations", Case("getAffineTransform(dst, src)", "lab07.ex5", """
        def affine_from_points(src, dst):
            src = np.asarray(src, dtype=np.float32)
            dst = np.asarray(dst, dtype=np.float32)
            return cv2.getAffineTransform(dst, src).astype(np.float64)
        """, "cv2.getAffineTransform is given the point sets in the wrong order: it returns the "
        "inverse map, from dst to src",
        ("inverse", "invert", "swapped", "exchanged", "reversed", "src and dst", "dst and src",
         "argument order", "order of the arguments", "wrong direction", "opposite direction",
         "backward", "dst to src", "a^-1", "a⁻¹"))),

    # ------------------------------------------------------------------ lab08
    ("lab08_homographies", Case("DLT second row copied with x' instead of y'", "lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            T1, T2 = _normalisation(src), _normalisation(dst)
            s = src @ T1[:2, :2].T + T1[:2, 2]
            d = dst @ T2[:2, :2].T + T2[:2, 2]
            rows = []
            for (x, y), (u, v) in zip(s, d):
                rows.append([-x, -y, -1.0, 0.0, 0.0, 0.0, x * u, y * u, u])
                rows.append([0.0, 0.0, 0.0, -x, -y, -1.0, x * u, y * u, u])
            _, _, Vt = np.linalg.svd(np.array(rows))
            H = np.linalg.inv(T2) @ Vt[-1].reshape(3, 3) @ T1
            return H / H[2, 2]
        """, "copy-paste: the second row of each pair ends in x x', y x', x' where the lab sheet has "
        "x y', y y', y' (the y' equation uses x')",
        ("y'", "x' instead of y'", "x' where", "u instead of v", "v instead", "second row",
         "second equation", "copy", "wrong coordinate", "rows_v"))),
    ("lab08_homographies", Case("ratio test multiplies the best distance", "lab08.ex3", """
        def match_features(img1, img2, ratio=0.75, method="sift"):
            (p1, d1), (p2, d2) = _detect(img1, method), _detect(img2, method)
            norm = cv2.NORM_HAMMING if method == "orb" else cv2.NORM_L2
            pts1, pts2 = [], []
            for pair in cv2.BFMatcher(norm).knnMatch(d1, d2, k=2):
                if len(pair) == 2 and ratio * pair[0].distance < pair[1].distance:
                    pts1.append(p1[pair[0].queryIdx])
                    pts2.append(p2[pair[0].trainIdx])
            return np.array(pts1).reshape(-1, 2), np.array(pts2).reshape(-1, 2)
        """, "the ratio is applied to the wrong distance: ratio * best < second keeps every match "
        "whose best is below 1/ratio (1.33) times the second best, so ambiguous matches pass (Lowe's "
        "test is best < ratio * second)",
        ("ratio", "lowe", "ambiguous", "second-best", "second best", "second nearest"))),
    ("lab08_homographies", Case("findHomography without cv2.RANSAC", "lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            H, mask = cv2.findHomography(src, dst)
            return H, mask.ravel().astype(bool)
        """, "cv2.findHomography is called without the cv2.RANSAC method: a plain least-squares fit "
        "over every pair, outliers included, with every pair marked as an inlier",
        ("ransac", "outlier", "least squares", "least-squares", "all points", "every point",
         "every pair", "all pairs", "robust"))),
    ("lab08_homographies", Case("panorama homography helper called (img1, img2)", "lab08.ex5", """
        def stitch(img1, img2):
            H = _pairwise_homography(img1, img2)
            return _compose([img1, img2], [np.eye(3), H])
        """, "_pairwise_homography(moving, reference) is called with the images in the wrong order: "
        "H maps img1 onto img2, and img2 is warped by it, i.e. by the inverse of the homography "
        "that takes img2 into img1's frame",
        ("inverse", "invert", "direction", "wrong way", "swapped", "exchanged", "reversed",
         "argument order", "order of the arguments", "img1 onto img2", "h^-1", "h⁻¹", "backward",
         "opposite"))),

    # ------------------------------------------------------------------ lab09
    ("lab09_camera", Case("intrinsics applied as X @ K", "lab09.ex2", """
        def project_with_intrinsics(K, points):
            X, single = _points(points)
            return _divide(X @ np.asarray(K, dtype=np.float64), single)
        """, "the points are rows, so X @ K applies K^T; x = K X needs X @ K.T (K is transposed)",
        ("transpos", "k.t", "k^t", "kᵀ", "x @ k", "row vector", "column vector",
         "order of multiplication", "multiplication order"))),
    ("lab09_camera", Case("projection divided by the world Z", "lab09.ex3", """
        def project(P, points):
            X, single = _points(points)
            h = np.column_stack([X, np.ones(len(X))]) @ np.asarray(P, dtype=np.float64).T
            pts = h[:, :2] / X[:, 2:3]
            return pts[0] if single else pts
        """, "the homogeneous image point P X is divided by the world point's Z instead of its own "
        "third coordinate w (they agree only for a camera at the world origin, unrotated)",
        ("world z", "world depth", "world coordinate", "third coordinate", "w coordinate",
         "dehomogen", "de-homogen", "homogeneous", "perspective division", "divided by z",
         "divides by z", "instead of w", "by w"))),
    ("lab09_camera", Case("aperture taken as the pinhole's diameter", "lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X, _ = _points(points)
            rng = np.random.default_rng(seed)
            r = aperture / 2.0
            radius = r * np.sqrt(rng.uniform(0.0, 1.0, size=(len(X), n_rays)))
            angle = rng.uniform(0.0, 2 * np.pi, size=(len(X), n_rays))
            A = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)
            ideal = pinhole_project(X, f)
            spread = 1.0 + f / X[:, 2]
            return ideal[:, None, :] - A * spread[:, None, None]
        """, "aperture is read as the pinhole's diameter (radius = aperture / 2); the API's aperture "
        "is the radius, so every blur disc is half as wide",
        ("diameter", "radius", "half", "/ 2", "factor 2", "factor of 2", "twice"))),
    ("lab09_camera", Case("cv2.circle centre given as (y, x)", "lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            color = tuple(int(c) for c in color)
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(y)), int(round(x))), int(radius), color, thickness=-1)
            return out
        """, "cv2.circle takes the centre as (x, y) = (column, row); the student passes (y, x), so "
        "each dot is drawn at the point mirrored in the diagonal",
        ("(y, x)", "y, x", "(row, col", "row, col", "row/col", "rows and columns", "x and y",
         "y and x", "swapped", "exchanged", "transpos", "diagonal"))),

    # ------------------------------------------------------------------ lab10
    ("lab10_camera2", Case("weak perspective ignores the z_avg argument", "lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            z = X[:, 2].mean()
            x = (f / z) * X[:, :2]
            return x[0] if single else x
        """, "the z_avg argument is ignored: the points' own mean depth is always used",
        ("z_avg", "ignor", "argument", "parameter", "given depth", "supplied", "passed"))),
    ("lab10_camera2", Case("camera DLT takes the first row of Vt", "lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.asarray(points3d, dtype=np.float64)
            x = np.asarray(points2d, dtype=np.float64)
            T = _normalising_transform(x)
            U = _normalising_transform(X)
            xn = (np.column_stack([x, np.ones(len(x))]) @ T.T)[:, :2]
            Xn = np.column_stack([X, np.ones(len(X))]) @ U.T
            zeros = np.zeros_like(Xn)
            rows_u = np.hstack([Xn, zeros, -xn[:, :1] * Xn])
            rows_v = np.hstack([zeros, Xn, -xn[:, 1:] * Xn])
            A = np.vstack([rows_u, rows_v])
            p = np.linalg.svd(A)[2][0]
            P = np.linalg.inv(T) @ p.reshape(3, 4) @ U
            return P / np.linalg.norm(P)
        """, "Vt[0] is the right singular vector of the LARGEST singular value; the solution of "
        "A p = 0 is the one of the smallest, Vt[-1]",
        ("largest", "smallest", "vt[0]", "vt[-1]", "first row", "first singular",
         "singular vector", "singular value", "null vector", "null space"))),
    ("lab10_camera2", Case("decomposition returns the camera centre as t", "lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            flip = np.eye(3)[::-1]
            Q, U = np.linalg.qr((flip @ P[:, :3]).T)
            K = flip @ U.T @ flip
            R = flip @ Q.T
            signs = np.diag(np.sign(np.diag(K)))
            K, R = K @ signs, signs @ R
            t = -np.linalg.inv(P[:, :3]) @ P[:, 3]
            return K / K[2, 2], R, t
        """, "t is computed as -M^-1 P[:, 3], which the lab sheet itself calls the camera centre C; "
        "the translation of P = K [R | t] is K^-1 P[:, 3] = -R C",
        ("centre", "center", "-r c", "-rc", "-r @ c", "camera position", "-m^-1", "-m⁻¹",
         "inv(m)"))),
    ("lab10_camera2", Case("chessboard object points with rows and columns exchanged",
                           "lab10.ex6", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size))
            if not found:
                return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))
            criteria = (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3)
            corners = cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1), criteria)
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float64)
            objp[:, :2] = np.mgrid[0:rows, 0:cols].T.reshape(-1, 2) * square_size
            K = np.asarray(K, dtype=np.float64)
            dist = None if dist is None else np.asarray(dist, dtype=np.float64)
            _, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
            reprojected, _ = cv2.projectPoints(objp, rvec, tvec, K, dist)
            return rvec.ravel(), tvec.ravel(), reprojected.reshape(-1, 2)
        """, "the object points are built with rows and columns exchanged (mgrid[0:rows, 0:cols]): "
        "on a non-square board they are not in OpenCV's corner order, so the 3D-2D pairs do not "
        "correspond",
        ("corner order", "order of the corners", "rows and columns", "columns and rows",
         "rows and cols", "cols and rows", "pattern_size", "pattern size", "object point",
         "mgrid", "transpos", "swapped", "exchanged", "correspondence"))),

    # ------------------------------------------------------------------ lab11
    ("lab11_two_view", Case("triangulated points left homogeneous", "lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, np.float64), np.asarray(P2, np.float64)
            pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
            pts2 = np.asarray(pts2, np.float64).reshape(-1, 2)
            A = np.stack([pts1[:, 0:1] * P1[2] - P1[0],
                          pts1[:, 1:2] * P1[2] - P1[1],
                          pts2[:, 0:1] * P2[2] - P2[0],
                          pts2[:, 1:2] * P2[2] - P2[1]], axis=1)
            X = np.linalg.svd(A)[2][:, -1, :]
            return X[:, :3]
        """, "the SVD null vector is a unit-norm homogeneous point: its first three entries must be "
        "divided by the fourth, w",
        ("dehomogen", "de-homogen", "homogeneous", "divide", "division", "divided",
         "w coordinate", "fourth coordinate", "last coordinate", "x[3]", "unit norm",
         "unit-norm", "unit vector"))),
    ("lab11_two_view", Case("epipolar lines as x @ F", "lab11.ex2", """
        def epipolar_lines(F, pts1):
            lines = _homogeneous(pts1) @ np.asarray(F, np.float64)
            return lines / np.linalg.norm(lines[:, :2], axis=1, keepdims=True)
        """, "with points as rows, x @ F computes F^T x (lines in image 1 for points of image 2); "
        "l' = F x needs x @ F.T",
        ("transpos", "f^t", "fᵀ", "f.t", "x @ f", "image 1", "first image", "other image",
         "wrong image", "row vector"))),
    ("lab11_two_view", Case("E = K1^T F K2", "lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            return np.asarray(K1, np.float64).T @ np.asarray(F, np.float64) @ np.asarray(K2, np.float64)
        """, "the two intrinsic matrices are exchanged: E = K2^T F K1 (the second camera's K "
        "transposed on the left)",
        ("k1 and k2", "k2 and k1", "swapped", "exchanged", "k1^t", "k1ᵀ", "k1.t", "wrong side",
         "reversed"))),
    ("lab11_two_view", Case("8-point F denormalised like a homography", "lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
            pts2 = np.asarray(pts2, np.float64).reshape(-1, 2)
            T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
            Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T)
            U, s, Vt = np.linalg.svd(Fn)
            Fn = U @ np.diag([s[0], s[1], 0.0]) @ Vt
            F = np.linalg.inv(T2) @ Fn @ T1
            return F / np.linalg.norm(F)
        """, "the normalisation is undone as for a homography, T2^-1 Fn T1; for F (x2^T F x1 = 0) "
        "it is T2^T Fn T1",
        ("normalis", "normaliz", "denormal", "de-normal", "t2", "hartley"))),

    # ------------------------------------------------------------------ lab12
    ("lab12_stereo", Case("rectifying homography of camera 2 without R^T", "lab12.ex3", """
        def rectify(img_l, img_r, K1, K2, R, T):
            K1 = np.asarray(K1, dtype=np.float64)
            K2 = np.asarray(K2, dtype=np.float64)
            R = np.asarray(R, dtype=np.float64)
            T = np.asarray(T, dtype=np.float64).reshape(3)
            height, width = np.asarray(img_l).shape[:2]
            C2 = -R.T @ T
            e1 = C2 / np.linalg.norm(C2)
            mean_axis = np.array([0.0, 0.0, 1.0]) + R.T @ np.array([0.0, 0.0, 1.0])
            e2 = np.cross(mean_axis, e1)
            e2 /= np.linalg.norm(e2)
            e3 = np.cross(e1, e2)
            R_rect = np.vstack([e1, e2, e3])
            f = (K1[0, 0] + K1[1, 1] + K2[0, 0] + K2[1, 1]) / 4.0
            rot1 = R_rect @ np.linalg.inv(K1)
            rot2 = R_rect @ np.linalg.inv(K2)
            centre = np.array([(width - 1) / 2.0, (height - 1) / 2.0, 1.0])
            mapped = []
            for rot in (rot1, rot2):
                ray = rot @ centre
                mapped.append(f * ray[:2] / ray[2])
            cx, cy = centre[:2] - np.mean(mapped, axis=0)
            K_new = np.array([[f, 0.0, cx], [0.0, f, cy], [0.0, 0.0, 1.0]])
            H1 = K_new @ rot1
            H2 = K_new @ rot2
            rect_l = cv2.warpPerspective(np.asarray(img_l), H1, (width, height), flags=cv2.INTER_LINEAR)
            rect_r = cv2.warpPerspective(np.asarray(img_r), H2, (width, height), flags=cv2.INTER_LINEAR)
            return rect_l, rect_r, H1, H2
        """, "camera 2's own rotation is not undone: H2 = K_new R_rect K2^-1 lacks R^T "
        "(K_new R_rect R^T K2^-1), so the right image is rectified as if its camera were oriented "
        "like the left one",
        ("r^t", "rᵀ", "r.t", "relative rotation", "camera 2's rotation", "second camera's rotation",
         "right camera's rotation", "rotation of camera 2", "rotation of the second",
         "rotation of the right", "ignores r", "without r"))),
    ("lab12_stereo", Case("StereoBM output not divided by 16", "lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost == "ncc":
                volume = _ncc_volume(_grey_float(left), _grey_float(right), int(max_disparity),
                                     int(block_size))
                return np.argmin(volume, axis=0).astype(np.float64)
            if cost != "ssd":
                raise ValueError(cost)
            def grey(image):
                return image if image.ndim == 2 else cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
            n = 16 * ((int(max_disparity) + 16) // 16)
            matcher = cv2.StereoBM_create(numDisparities=n, blockSize=int(block_size))
            return matcher.compute(grey(left), grey(right)).astype(np.float64)
        """, "cv2.StereoBM returns fixed-point disparities with 4 fractional bits: the output is 16 "
        "times the disparity and must be divided by 16",
        ("16", "fixed-point", "fixed point", "sixteen", "fractional bit"))),
    ("lab12_stereo", Case("smoothness=0 replaced by the default", "lab12.ex5", """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            s = float(smoothness or DEFAULT_SMOOTHNESS)
            left, right = _grey_float(left), _grey_float(right)
            D = int(max_disparity) + 1
            costs = _sad_volume(left, right, D - 1, int(block_size))
            if s == 0:
                return np.argmin(costs, axis=2).T.astype(np.float64)
            width = costs.shape[0]
            ramp = (s * np.arange(D)).astype(np.float32)
            energy = np.empty_like(costs)
            energy[0] = costs[0]
            for x in range(1, width):
                previous = energy[x - 1]
                from_below = np.minimum.accumulate(previous - ramp, axis=1) + ramp
                from_above = np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1)[:, ::-1] - ramp
                best = np.minimum(from_below, from_above)
                energy[x] = costs[x] + best - best.min(axis=1, keepdims=True)
            disparity = np.empty((width, costs.shape[1]), dtype=np.int64)
            disparity[-1] = np.argmin(energy[-1], axis=1)
            candidates = np.arange(D)
            for x in range(width - 1, 0, -1):
                jump = ramp[np.abs(candidates[None, :] - disparity[x][:, None])]
                disparity[x - 1] = np.argmin(energy[x - 1] + jump, axis=1)
            return disparity.T.astype(np.float64)
        """, "`smoothness or DEFAULT_SMOOTHNESS` treats smoothness=0 as missing (0 is falsy): the "
        "default penalty is used, so the smoothness term cannot be switched off",
        ("smoothness=0", "smoothness = 0", "smoothness 0", "smoothness of 0", "zero smoothness",
         "smoothness is 0", "falsy", "switched off", "switch off", "turned off",
         "winner-take-all", "winner takes all", "default smoothness", "ignor"))),
    ("lab12_stereo", Case("structured light decodes the stripe's left edge", "lab12.ex6", """
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n_bits, height, width = images.shape
            bits = images > 127
            binary = np.zeros((height, width), dtype=np.int64)
            bit = np.zeros((height, width), dtype=bool)
            for i in range(n_bits):
                bit = bit ^ bits[i]
                binary = (binary << 1) | bit
            column = binary * width / (1 << n_bits)
            disparity = np.arange(width)[None, :] - column
            decodable = bits.any(axis=0)
            return np.where(decodable, depth_from_disparity(disparity, f, baseline), 0.0)
        """, "the projector column is taken as the stripe's first column k W / 2^n instead of its "
        "centre (k + 0.5) W / 2^n - 0.5: every disparity is off by about half a stripe",
        ("centre", "center", "edge", "half a stripe", "half stripe", "half-stripe", "+ 0.5",
         "+0.5", "k + 0.5", "left border", "first column", "start of the stripe"))),
]
