"""A third blind set (set c), written without reading how the grader names mistakes: its
author read only the lab sheet, the assignment API, the reference solutions, ``Case`` and the
runner, never the grader, its fixtures, its tests or the other sets' remaining cases. Four
single-bug submissions per lab, spread over exercises and kinds of mistake (operand or index,
transpose, degrees, row/column order, off-by-one, OpenCV flag, normalisation,
dehomogenisation, dtype, sign, order of returned values, mutated input). Each truth was
written with its case, before any measurement.

Each entry is ``(module, Case)``; ``python benchmarks/blind_naming.py --set c`` grades them.
"""

from . import Case

CASES = [
    # ------------------------------------------------------------------ lab07
    ("lab07_transformations", Case("translate passes dsize as (height, width)", "lab07.ex1", """
        def translate(image, tx=100, ty=50):
            M = translation_matrix(tx, ty)[:2]
            return cv2.warpAffine(image, M, image.shape[:2])
        """, "cv2.warpAffine's dsize is (width, height); image.shape[:2] is (height, width), so a "
        "non-square output has its sides exchanged",
        ("(height, width)", "height, width", "width and height", "height and width", "dsize",
         "(h, w)", "transposed size", "output size", "image size"))),
    ("lab07_transformations", Case("rotation angle used as radians", "lab07.ex2", """
        def rotation_matrix(angle_deg, center=(0.0, 0.0)):
            theta = angle_deg
            c, s = np.cos(theta), np.sin(theta)
            R = np.array([[c, s], [-s, c]])
            center = np.asarray(center, dtype=np.float64)
            M = np.eye(3)
            M[:2, :2] = R
            M[:2, 2] = center - R @ center
            return M
        """, "the angle in degrees goes straight into cos/sin, which take radians (np.deg2rad missing)",
        ("radian", "degree", "deg2rad"))),
    ("lab07_transformations", Case("affine from 3 points not transposed", "lab07.ex5", """
        def affine_from_points(src, dst):
            src = np.asarray(src, dtype=np.float64)
            dst = np.asarray(dst, dtype=np.float64)
            S = np.hstack([src, np.ones((3, 1))])
            return np.linalg.solve(S, dst)
        """, "solve(S, dst) gives A^T (3x2); the transpose back to the 2x3 A is missing",
        ("transpos", "3x2", "(3, 2)", "3 x 2", "a.t", "a^t"))),
    ("lab07_transformations", Case("least squares right-hand side stacked, not interleaved",
                                   "lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, dtype=np.float64)
            dst = np.asarray(dst, dtype=np.float64)
            n = len(src)
            M = np.zeros((2 * n, 6))
            M[0::2, 0:2] = src
            M[0::2, 2] = 1.0
            M[1::2, 3:5] = src
            M[1::2, 5] = 1.0
            b = np.concatenate([dst[:, 0], dst[:, 1]])
            params, *_ = np.linalg.lstsq(M, b, rcond=None)
            return params.reshape(2, 3)
        """, "the rows of M alternate x', y' per point but b lists every x' then every y': the "
        "equations and the right-hand side are out of step",
        ("interleav", "order of b", "right-hand side", "rhs", "stacked", "out of step",
         "rows of b", "b vector", "x' then", "ordering"))),

    # ------------------------------------------------------------------ lab08
    ("lab08_homographies", Case("warpPerspective told H is already inverse", "lab08.ex1", """
        def apply_homography(image, H, dsize=None):
            height, width = image.shape[:2]
            return cv2.warpPerspective(image, np.asarray(H, dtype=np.float64), dsize or (width, height),
                                       flags=cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP,
                                       borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """, "cv2.WARP_INVERSE_MAP makes OpenCV use H as the output-to-source map: the image is "
        "warped by H^-1",
        ("inverse", "inverted", "h^-1", "h⁻¹", "inv(h)", "warp_inverse_map", "wrong direction",
         "opposite direction"))),
    ("lab08_homographies", Case("DLT takes the last column of Vt", "lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            T1, T2 = _normalisation(src), _normalisation(dst)
            src_n = src @ T1[:2, :2].T + T1[:2, 2]
            dst_n = dst @ T2[:2, :2].T + T2[:2, 2]
            _, _, Vt = np.linalg.svd(_dlt_rows(src_n, dst_n))
            H = np.linalg.inv(T2) @ Vt[:, -1].reshape(3, 3) @ T1
            return H / H[2, 2]
        """, "the null vector is the last ROW of Vt (last column of V); Vt[:, -1] is a column of Vt",
        ("vt[-1]", "vt[:, -1]", "last row", "column of vt", "row of vt", "column of v",
         "singular vector", "null vector", "null space"))),
    ("lab08_homographies", Case("RANSAC returns OpenCV's uint8 (N, 1) mask", "lab08.ex4", """
        def homography_ransac(src, dst, threshold=3.0, seed=None):
            src = np.asarray(src, dtype=np.float64).reshape(-1, 2)
            dst = np.asarray(dst, dtype=np.float64).reshape(-1, 2)
            H, mask = cv2.findHomography(src, dst, cv2.RANSAC, threshold)
            return H, mask
        """, "cv2.findHomography's mask is uint8 of shape (N, 1); the API asks for a bool (N,) "
        "array (mask.ravel().astype(bool))",
        ("bool", "uint8", "(n, 1)", "n x 1", "nx1", "ravel", "flatten", "dtype", "0/1"))),
    ("lab08_homographies", Case("panorama overlap averaged in uint8", "lab08.ex5", """
        def stitch(img1, img2):
            H = _pairwise_homography(img2, img1)
            corners = np.vstack([_corners(img1), transform_points(H, _corners(img2))])
            x_min, y_min = np.floor(corners.min(axis=0))
            x_max, y_max = np.ceil(corners.max(axis=0))
            T = _translation(-x_min, -y_min)
            size = (int(x_max - x_min) + 1, int(y_max - y_min) + 1)
            a = apply_homography(_bgr(img1), T, size)
            b = apply_homography(_bgr(img2), T @ H, size)
            in_a, in_b = a.any(axis=2), b.any(axis=2)
            panorama = np.where(in_a[..., None], a, b)
            both = in_a & in_b
            panorama[both] = (a[both] + b[both]) // 2
            return panorama
        """, "the two uint8 images are added before halving: the sum wraps around 255 in the "
        "overlap (convert to float or int first)",
        ("uint8", "overflow", "wrap", "dtype", "255", "modulo", "integer"))),

    # ------------------------------------------------------------------ lab09
    ("lab09_camera", Case("pinhole output array inherits an integer dtype", "lab09.ex1", """
        def pinhole_project(points, f):
            points = np.asarray(points)
            X = np.atleast_2d(points)
            out = np.zeros_like(X[:, :2])
            out[:, 0] = f * X[:, 0] / X[:, 2]
            out[:, 1] = f * X[:, 1] / X[:, 2]
            return out[0] if points.ndim == 1 else out
        """, "np.zeros_like copies the input's dtype: with integer points (the lab sheet's (1, 1, 2)) "
        "the projections are truncated to integers",
        ("integer", "truncat", "dtype", "zeros_like", "rounded down", "floor"))),
    ("lab09_camera", Case("intrinsic matrix transposed", "lab09.ex2", """
        def intrinsic_matrix(f, px, py):
            return np.array([[f, 0.0, 0.0],
                             [0.0, f, 0.0],
                             [px, py, 1.0]], dtype=np.float64)
        """, "the principal point is written in the bottom row: K is transposed (it belongs in the "
        "third column)",
        ("transpos", "bottom row", "third row", "last row", "k.t", "k^t", "third column",
         "last column"))),
    ("lab09_camera", Case("P = [K R | t]: translation not multiplied by K", "lab09.ex3", """
        def camera_matrix(K, R, t):
            K = np.asarray(K, dtype=np.float64)
            R = np.asarray(R, dtype=np.float64)
            t = np.asarray(t, dtype=np.float64).reshape(3)
            return np.column_stack([K @ R, t])
        """, "K multiplies only R: the fourth column must be K t, not t",
        ("k t", "k @ t", "kt", "k*t", "k [r | t]", "k[r|t]", "k [r|t]", "[kr | t]", "[kr|t]",
         "fourth column", "last column", "translation"))),
    ("lab09_camera", Case("draw_points draws on the caller's image", "lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            color = tuple(int(c) for c in color)
            for x, y in np.asarray(pts, dtype=np.float64).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(image, (int(round(x)), int(round(y))), int(radius), color, thickness=-1)
            return image
        """, "cv2.circle draws in place: without image.copy() the input image is modified",
        ("copy", "mutat", "in place", "in-place", "modif", "input image", "overwr", "caller"),
        moves=False)),

    # ------------------------------------------------------------------ lab10
    ("lab10_camera2", Case("weak perspective default depth averages every coordinate",
                           "lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            points = np.asarray(points, dtype=np.float64)
            X = np.atleast_2d(points)
            z = X.mean() if z_avg is None else float(z_avg)
            x = (f / z) * X[:, :2]
            return x[0] if points.ndim == 1 else x
        """, "X.mean() averages X, Y and Z together; the default z_avg is the mean of the depths "
        "X[:, 2].mean()",
        ("z_avg", "mean depth", "average depth", "mean of the depth", "all coordinates",
         "every coordinate", "whole array", "x[:, 2]"))),
    ("lab10_camera2", Case("orthographic matrix third row copied as [0, 0, 1, 0]", "lab10.ex3", """
        def orthographic_project(points):
            points = np.asarray(points, dtype=np.float64)
            X = np.atleast_2d(points)
            M = np.array([[1.0, 0.0, 0.0, 0.0],
                          [0.0, 1.0, 0.0, 0.0],
                          [0.0, 0.0, 1.0, 0.0]])
            h = np.column_stack([X, np.ones(len(X))]) @ M.T
            x = h[:, :2] / h[:, 2:3]
            return x[0] if points.ndim == 1 else x
        """, "the third row should be [0, 0, 0, 1]; with [0, 0, 1, 0] w = Z and the division makes "
        "it a perspective projection (f = 1)",
        ("perspective", "divid", "division", "third row", "by z", "/ z", "/z", "[0, 0, 0, 1]",
         "[0,0,0,1]"))),
    ("lab10_camera2", Case("camera DLT: +u X in the u rows", "lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.asarray(points3d, dtype=np.float64)
            x = np.asarray(points2d, dtype=np.float64)
            T = _normalising_transform(x)
            U = _normalising_transform(X)
            xn = (np.column_stack([x, np.ones(len(x))]) @ T.T)[:, :2]
            Xn = np.column_stack([X, np.ones(len(X))]) @ U.T
            zeros = np.zeros_like(Xn)
            rows_u = np.hstack([Xn, zeros, xn[:, :1] * Xn])
            rows_v = np.hstack([zeros, Xn, -xn[:, 1:] * Xn])
            A = np.vstack([rows_u, rows_v])
            p = np.linalg.svd(A)[2][-1]
            P = np.linalg.inv(T) @ p.reshape(3, 4) @ U
            return P / np.linalg.norm(P)
        """, "the first row of each pair has +x_i X_i^T where the lab sheet has -x_i X_i^T (sign "
        "error in the u equations)",
        ("sign", "+u x", "+x_i", "minus", "negat"))),
    ("lab10_camera2", Case("camera centre not dehomogenised", "lab10.ex5", """
        def camera_center(P):
            C = np.linalg.svd(np.asarray(P, dtype=np.float64))[2][-1]
            return C[:3]
        """, "the null vector is homogeneous (unit norm): C[:3] must be divided by C[3]",
        ("dehomogen", "homogeneous", "c[3]", "fourth coordinate", "last coordinate", "divide",
         "division", "w coordinate", "unit norm", "unit vector"))),

    # ------------------------------------------------------------------ lab11
    ("lab11_two_view", Case("triangulation: x where y belongs in view 2", "lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, np.float64), np.asarray(P2, np.float64)
            pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
            pts2 = np.asarray(pts2, np.float64).reshape(-1, 2)
            A = np.stack([pts1[:, 0:1] * P1[2] - P1[0],
                          pts1[:, 1:2] * P1[2] - P1[1],
                          pts2[:, 0:1] * P2[2] - P2[0],
                          pts2[:, 0:1] * P2[2] - P2[1]], axis=1)
            X = np.linalg.svd(A)[2][:, -1, :]
            return X[:, :3] / X[:, 3:4]
        """, "copy-paste: the second equation of view 2 uses x' instead of y' (x' p3 - p2)",
        ("y'", "y coordinate", "x instead of y", "x' instead of y'", "second equation",
         "x p3 - p2", "y p3 - p2"))),
    ("lab11_two_view", Case("epipolar lines scaled to a unit 3-vector", "lab11.ex2", """
        def epipolar_lines(F, pts1):
            lines = _homogeneous(pts1) @ np.asarray(F, np.float64).T
            return lines / np.linalg.norm(lines, axis=1, keepdims=True)
        """, "each line is divided by sqrt(a^2 + b^2 + c^2) instead of sqrt(a^2 + b^2)",
        ("a^2 + b^2", "a² + b²", "a2 + b2", "a²+b²", "a^2+b^2", "normalis", "normaliz", "unit",
         "c^2", "c²"))),
    ("lab11_two_view", Case("8-point F without rank 2", "lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1 = np.asarray(pts1, np.float64).reshape(-1, 2)
            pts2 = np.asarray(pts2, np.float64).reshape(-1, 2)
            T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
            Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T)
            F = T2.T @ Fn @ T1
            return F / np.linalg.norm(F)
        """, "the rank-2 constraint is not enforced (the smallest singular value is not zeroed)",
        ("rank", "singular"))),
    ("lab11_two_view", Case("epipoles returned as (e2, e1)", "lab11.ex5", """
        def epipoles(F):
            U, _, Vt = np.linalg.svd(np.asarray(F, np.float64))
            return U[:, -1], Vt[-1]
        """, "the two epipoles are returned in the wrong order: the left null vector first "
        "(F e1 = 0 is Vt[-1], F^T e2 = 0 is U[:, -1])",
        ("swapped", "exchanged", "order", "e1 and e2", "e2 and e1", "reversed", "other epipole",
         "left and right", "right and left", "transpos", "f^t", "fᵀ"))),

    # ------------------------------------------------------------------ lab12
    ("lab12_stereo", Case("disparity computed as xr - xl", "lab12.ex2", """
        def disparity_from_matches(xl, xr):
            xl = np.asarray(xl, dtype=np.float64)
            xr = np.asarray(xr, dtype=np.float64)
            if xl.ndim == 2:
                xl = xl[:, 0]
            if xr.ndim == 2:
                xr = xr[:, 0]
            return xr - xl
        """, "wrong sign: d = x_l - x_r, the student subtracts the other way",
        ("sign", "xr - xl", "x_r - x_l", "negat", "reversed", "swapped", "exchanged",
         "opposite"))),
    ("lab12_stereo", Case("block matching never tries d = max_disparity", "lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost not in ("ssd", "ncc"):
                raise ValueError(cost)
            left, right = _grey_float(left), _grey_float(right)
            if cost == "ncc":
                volume = _ncc_volume(left, right, int(max_disparity), int(block_size))
                return np.argmin(volume, axis=0).astype(np.float64)
            height, width = left.shape
            costs = np.full((max_disparity, height, width), np.inf)
            for d in range(min(max_disparity, width)):
                squared = (left - _shift_right(right, d)) ** 2
                costs[d] = _box_mean(squared, block_size)
                costs[d, :, :d] = np.inf
            return np.argmin(costs, axis=0).astype(np.float64)
        """, "off by one at the end of the range: disparities 0..max_disparity-1 are searched, "
        "max_disparity itself never (range(max_disparity + 1) is needed)",
        ("off-by-one", "off by one", "max_disparity", "last disparity", "inclusive",
         "exclusive", "largest disparity", "maximum disparity"))),
    ("lab12_stereo", Case("DP backtracking ignores the jump cost", "lab12.ex5", """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)
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
            for x in range(width - 1, 0, -1):
                disparity[x - 1] = np.argmin(energy[x - 1], axis=1)
            return disparity.T.astype(np.float64)
        """, "the backtracking picks each column's own best accumulated energy without adding the "
        "smoothness cost of the jump to the disparity already chosen on its right, so the path is "
        "not the optimal one",
        ("backtrack", "back-track", "traceback", "trace back", "jump", "transition", "path"))),
    ("lab12_stereo", Case("Gray-code bits least significant first", "lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            u = np.arange(int(width))
            k = (u * (1 << int(n_bits))) // int(width)
            gray = k ^ (k >> 1)
            shifts = np.arange(int(n_bits))[:, None]
            return (((gray[None, :] >> shifts) & 1) * 255).astype(np.uint8)
        """, "the rows carry the bits least significant first; the API wants the most significant "
        "bit in row 0 (the rows are in reverse order)",
        ("least significant", "most significant", "lsb", "msb", "bit order", "order of the bits",
         "reversed", "reverse order"))),
]
