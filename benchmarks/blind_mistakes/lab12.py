"""Lab 12: single-bug submissions written apart from the tables (see the package docstring)."""

from . import Case

MODULE = "lab12_stereo"

CASES = [
    Case("block matching SAD on uint8 images (the difference wraps)", "lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            h, w = left.shape
            costs = np.full((max_disparity + 1, h, w), np.inf)
            for d in range(max_disparity + 1):
                shifted = np.zeros_like(right)
                shifted[:, d:] = right[:, :w - d]
                diff = np.abs(left - shifted)
                costs[d] = cv2.blur(diff.astype(np.float64), (block_size, block_size))
                costs[d, :, :d] = np.inf
            return np.argmin(costs, axis=0).astype(float)
        """, "left - shifted is computed in uint8: negative differences wrap around to 255, ...",
         ("uint8", "wrap", "overflow")),

    Case("depth with floor division", "lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=float)
            out = np.zeros_like(d)
            ok = np.isfinite(d) & (d > 0)
            out[ok] = f * baseline // d[ok]
            return out
        """, "// floors the depths to whole numbers",
         ("//", "floor", "whole", "integer", "rounded")),

    Case("disparity_from_matches only for (N, 2) points", "lab12.ex2", """
        def disparity_from_matches(xl, xr):
            xl = np.asarray(xl, dtype=float)
            xr = np.asarray(xr, dtype=float)
            return xl[:, 0] - xr[:, 0]
        """, "(N,) x coordinates are indexed as if they were (N, 2) points",
         ("(n,)", "1-d", "one-dimensional", "x coordinates", "index")),

    Case("dynamic programming along the columns", "lab12.ex5", """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            s = 6.0 if smoothness is None else float(smoothness)
            L = left.astype(np.float64)
            R = right.astype(np.float64)
            h, w = L.shape
            D = max_disparity + 1
            C = np.full((D, h, w), 255.0)
            for d in range(min(D, w)):
                sh = np.empty_like(R)
                sh[:, d:] = R[:, :w - d]
                sh[:, :d] = R[:, :1]
                C[d, :, d:] = cv2.blur(np.abs(L - sh), (block_size, block_size))[:, d:]
            # scan every column from top to bottom
            M = np.empty_like(C)
            M[:, 0, :] = C[:, 0, :]
            dd = np.arange(D)
            jump = s * np.abs(dd[:, None] - dd[None, :])
            for y in range(1, h):
                prev = M[:, y - 1, :]
                M[:, y, :] = C[:, y, :] + (prev[None, :, :] + jump[:, :, None]).min(axis=1)
            disp = np.empty((h, w))
            disp[-1] = np.argmin(M[:, -1, :], axis=0)
            for y in range(h - 1, 0, -1):
                cur = disp[y].astype(int)
                disp[y - 1] = np.argmin(M[:, y - 1, :] + jump[cur, :].T, axis=0)
            return disp
        """, "the scanline DP runs along the columns (over y), not along the rows (over x)",
         ("along the columns", "over y", "scanline", "transposed", "rows and columns")),

    Case("rectification with e2 = e1 x (mean axis)", "lab12.ex3", """
        def rectify(img_l, img_r, K1, K2, R, T):
            K1, K2, R = (np.asarray(a, float) for a in (K1, K2, R))
            T = np.asarray(T, float).reshape(3)
            h, w = np.asarray(img_l).shape[:2]
            C2 = -R.T @ T
            e1 = C2 / np.linalg.norm(C2)
            axis = np.array([0.0, 0.0, 1.0]) + R.T @ np.array([0.0, 0.0, 1.0])
            e2 = np.cross(e1, axis)
            e2 /= np.linalg.norm(e2)
            e3 = np.cross(e1, e2)
            Rr = np.vstack([e1, e2, e3])
            f = (K1[0, 0] + K1[1, 1] + K2[0, 0] + K2[1, 1]) / 4
            r1 = Rr @ np.linalg.inv(K1)
            r2 = Rr @ R.T @ np.linalg.inv(K2)
            c = np.array([(w - 1) / 2, (h - 1) / 2, 1.0])
            m = [f * (r @ c)[:2] / (r @ c)[2] for r in (r1, r2)]
            cx, cy = c[:2] - np.mean(m, axis=0)
            Kn = np.array([[f, 0, cx], [0, f, cy], [0, 0, 1]])
            H1, H2 = Kn @ r1, Kn @ r2
            return (cv2.warpPerspective(img_l, H1, (w, h)), cv2.warpPerspective(img_r, H2, (w, h)), H1, H2)
        """, "the cross product's order is reversed: e2 (and e3) point the opposite way, the images turn upside down",
         ("cross", "upside", "flipped vertically", "e2")),

    Case("Gray code with k << 1", "lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            u = np.arange(width)
            k = (u * 2 ** n_bits) // width
            g = k ^ (k << 1)
            rows = []
            for i in range(n_bits - 1, -1, -1):
                rows.append(((g >> i) & 1) * 255)
            return np.array(rows, dtype=np.uint8)
        """, "the Gray code is k ^ (k >> 1); k << 1 shifts the wrong way",
         ("<<", ">>", "shift", "gray code")),

    Case("structured-light disparity as column - u", "lab12.ex6", """
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n, h, w = images.shape
            bits = images > 127
            k = np.zeros((h, w), dtype=np.int64)
            b = np.zeros((h, w), dtype=bool)
            for i in range(n):
                b = b ^ bits[i]
                k = k * 2 + b
            column = (k + 0.5) * w / 2 ** n - 0.5
            disparity = column - np.arange(w)[None, :]
            depth = np.zeros((h, w))
            ok = bits.any(axis=0) & (disparity > 0)
            depth[ok] = f * baseline / disparity[ok]
            return depth
        """, "the disparity is u - column; column - u is its negative",
         ("sign", "u - column", "negative", "reversed", "wrong side")),

    Case("triangulation divides by the third entry", "lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            a = np.asarray(pts1, float)
            single = a.ndim == 1
            a = a.reshape(-1, 2)
            b = np.asarray(pts2, float).reshape(-1, 2)
            out = []
            for (x1, y1), (x2, y2) in zip(a, b):
                A = np.array([x1 * P1[2] - P1[0], y1 * P1[2] - P1[1],
                              x2 * P2[2] - P2[0], y2 * P2[2] - P2[1]])
                X = np.linalg.svd(A)[2][-1]
                out.append(X[:3] / X[2])
            out = np.array(out)
            return out[0] if single else out
        """, "the homogeneous point is divided by its third entry Z, not by w (the fourth)",
         ("third entry", "by w", "fourth", "last entry")),
]
