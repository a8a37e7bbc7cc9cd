"""A second blind set, written after the naming mechanism was finished and committed before it
was measured: nothing in the mechanism was changed for it (the first set, labNN.py, was written
before the mechanism, but by the same hand as the reading's rules). Two single-bug submissions
per lab, written the same way: apart from the mistake tables and from the first set.

Each entry is ``(module, Case)``.
"""

from . import Case

CASES = [
    ("lab07_transformations", Case("scaling matrix returned as OpenCV's 2x3", "lab07.ex3", """
        def scaling_matrix(sx, sy):
            return np.float32([[sx, 0, 0], [0, sy, 0]])
        """, "the API asks for the 3x3 homogeneous matrix; the 2x3 is what cv2.warpAffine takes",
        ("2x3", "(2, 3)", "3x3", "homogeneous"))),
    ("lab07_transformations", Case("least squares built from (y, x) source points", "lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, float)
            dst = np.asarray(dst, float)
            n = len(src)
            M = np.zeros((2 * n, 6))
            M[0::2, 0:2] = src[:, ::-1]
            M[0::2, 2] = 1
            M[1::2, 3:5] = src[:, ::-1]
            M[1::2, 5] = 1
            params = np.linalg.pinv(M) @ dst.reshape(-1)
            return params.reshape(2, 3)
        """, "the source points are read as (row, column): x and y of src are exchanged",
        ("x and y", "(row, column)", "swapped", "exchanged"))),

    ("lab08_homographies", Case("transform_points applies only the affine part of H", "lab08.ex1", """
        def transform_points(H, pts):
            pts = np.asarray(pts, float)
            H = np.asarray(H, float)
            return pts @ H[:2, :2].T + H[:2, 2]
        """, "the perspective row (and the division by w) is left out: only H's affine part is applied",
        ("perspective", "division", "affine", "third row", "w"))),
    ("lab08_homographies", Case("DLT undoes only the source normalisation", "lab08.ex2", """
        def homography_dlt(src, dst):
            src = np.asarray(src, float)
            dst = np.asarray(dst, float)
            T1, T2 = _normalisation(src), _normalisation(dst)
            s = src @ T1[:2, :2].T + T1[:2, 2]
            d = dst @ T2[:2, :2].T + T2[:2, 2]
            _, _, Vt = np.linalg.svd(_dlt_rows(s, d))
            H = Vt[-1].reshape(3, 3) @ T1
            return H / H[2, 2]
        """, "T_dst^-1 is missing: H = T_dst^-1 Hn T_src", ("t_dst", "normalisation", "denormalis", "undo"))),

    ("lab09_camera", Case("project divides by a 1-D third coordinate", "lab09.ex3", """
        def project(P, points):
            X = np.atleast_2d(np.asarray(points, float))
            x = np.hstack([X, np.ones((len(X), 1))]) @ np.asarray(P, float).T
            out = x[:, :2] / x[:, 2]
            return out[0] if np.ndim(points) == 1 else out
        """, "x[:, 2] has shape (N,): it broadcasts against the columns, not the rows (x[:, 2:3])",
        ("broadcast", "x[:, 2:3]", "(n,)", "shape"))),
    ("lab09_camera", Case("aperture angles over half a turn", "lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X = np.atleast_2d(np.asarray(points, float))
            rng = np.random.default_rng(seed)
            r = aperture * np.sqrt(rng.uniform(0, 1, (len(X), n_rays)))
            a = rng.uniform(0, np.pi, (len(X), n_rays))
            A = np.stack([r * np.cos(a), r * np.sin(a)], axis=-1)
            ideal = pinhole_project(X, f)
            return ideal[:, None, :] - A * (1 + f / X[:, 2])[:, None, None]
        """, "the angle is drawn in [0, pi): half the disc", ("half", "angle", "pi"))),

    ("lab10_camera2", Case("perspective y divided by X", "lab10.ex1", """
        def perspective_project(points, f):
            X = np.atleast_2d(np.asarray(points, float))
            x = np.column_stack([f * X[:, 0] / X[:, 2], f * X[:, 1] / X[:, 0]])
            return x[0] if np.ndim(points) == 1 else x
        """, "y = f Y / X: the wrong operand (Z belongs there)", ("y is computed as", "y divided", "/ x"))),
    ("lab10_camera2", Case("camera centre divided by its third entry", "lab10.ex5", """
        def camera_center(P):
            C = np.linalg.svd(np.asarray(P, float))[2][-1]
            return C[:3] / C[2]
        """, "the null vector is divided by its third entry, not by the fourth (w)",
        ("third", "fourth", "by w", "de-homogenis"))),

    ("lab11_two_view", Case("rank 2 rebuilt with Vt transposed", "lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1 = np.asarray(pts1, float)
            pts2 = np.asarray(pts2, float)
            T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
            Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T)
            U, s, Vt = np.linalg.svd(Fn)
            s[2] = 0
            Fn = U @ np.diag(s) @ Vt.T
            F = T2.T @ Fn @ T1
            return F / np.linalg.norm(F)
        """, "U diag(s) Vt is rebuilt with Vt transposed", ("transposed", "vt.t", "v^t", "v transposed"))),
    ("lab11_two_view", Case("epipolar lines drawn with y = -(a x + c) / b always", "lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            out = image.copy()
            h, w = out.shape[:2]
            colour = (0, 255, 0) if out.ndim == 3 else 255
            for a, b, c in np.asarray(lines, float):
                y0 = -c / b
                y1 = -(c + a * (w - 1)) / b
                if np.isfinite(y0) and np.isfinite(y1):
                    cv2.line(out, (0, int(round(y0))), (w - 1, int(round(y1))), colour, 1)
            return out
        """, "vertical lines (b = 0) are not drawn: they need x = -(b y + c) / a",
        ("vertical", "b = 0", "steep"))),

    ("lab12_stereo", Case("stereoRectify's homography for the right image built with K1", "lab12.ex3", """
        def rectify(img_l, img_r, K1, K2, R, T):
            K1, K2 = np.float64(K1), np.float64(K2)
            h, w = np.asarray(img_l).shape[:2]
            R1, R2, P1, P2, *_ = cv2.stereoRectify(K1, None, K2, None, (w, h), np.float64(R),
                                                   np.float64(T).reshape(3, 1), flags=cv2.CALIB_ZERO_DISPARITY,
                                                   alpha=0)
            H1 = P1[:, :3] @ R1 @ np.linalg.inv(K1)
            H2 = P2[:, :3] @ R2 @ np.linalg.inv(K1)
            return (cv2.warpPerspective(img_l, H1, (w, h)), cv2.warpPerspective(img_r, H2, (w, h)), H1, H2)
        """, "H2 uses K1^-1 where K2^-1 belongs", ("k1", "k2"))),
    ("lab12_stereo", Case("Gray code stripes over width - 1", "lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            u = np.arange(width)
            k = (u * 2 ** n_bits) // max(width - 1, 1)
            k = np.minimum(k, 2 ** n_bits - 1)
            g = k ^ (k >> 1)
            shifts = np.arange(n_bits - 1, -1, -1)[:, None]
            return (((g[None, :] >> shifts) & 1) * 255).astype(np.uint8)
        """, "the stripe index divides by width - 1, not width", ("width - 1", "stripe index", "stripe"))),
]
