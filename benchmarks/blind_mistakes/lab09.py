"""Lab 9: single-bug submissions written apart from the tables (see the package docstring)."""

from . import Case

MODULE = "lab09_camera"

CASES = [
    Case("pinhole projection with floor division", "lab09.ex1", """
        def pinhole_project(points, f):
            X = np.atleast_2d(np.asarray(points, dtype=float))
            xy = f * X[:, :2] // X[:, 2:3]
            return xy[0] if np.ndim(points) == 1 else xy
        """, "// floors the projected coordinates to whole numbers",
         ("//", "floor", "whole", "integer", "rounded")),

    Case("project appends a column of zeros", "lab09.ex3", """
        def project(P, points):
            X = np.atleast_2d(np.asarray(points, dtype=float))
            Xh = np.hstack([X, np.zeros((len(X), 1))])
            x = Xh @ np.asarray(P, dtype=float).T
            out = x[:, :2] / x[:, 2:3]
            return out[0] if np.ndim(points) == 1 else out
        """, "the homogeneous world points end in 0, not 1: P's last column (the translation) is lost",
         ("0 instead of 1", "zeros", "homogeneous", "translation", "last column")),

    Case("aperture sampled over a square", "lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X = np.atleast_2d(np.asarray(points, dtype=float))
            rng = np.random.default_rng(seed)
            A = rng.uniform(-aperture, aperture, size=(len(X), n_rays, 2))
            ideal = pinhole_project(X, f)
            spread = 1 + f / X[:, 2]
            return ideal[:, None, :] - A * spread[:, None, None]
        """, "the aperture points are uniform over a square, not over the disc's area",
         ("square",)),

    Case("blur spread with Z / f for f / Z", "lab09.ex4", """
        def simulate_aperture(points, f, aperture, n_rays=100, seed=None):
            X = np.atleast_2d(np.asarray(points, dtype=float))
            rng = np.random.default_rng(seed)
            r = aperture * np.sqrt(rng.uniform(0, 1, (len(X), n_rays)))
            a = rng.uniform(0, 2 * np.pi, (len(X), n_rays))
            A = np.stack([r * np.cos(a), r * np.sin(a)], axis=-1)
            ideal = pinhole_project(X, f)
            spread = 1 + X[:, 2] / f
            return ideal[:, None, :] - A * spread[:, None, None]
        """, "the spread factor is 1 + Z / f instead of 1 + f / Z (a wrong operand)",
         ("z / f", "1 + f / z", "spread factor")),

    Case("distortion coefficients unpacked as (k1, k2, k3, p1, p2)", "lab09.ext2", """
        def distort_points(points, dist):
            pts = np.atleast_2d(np.asarray(points, dtype=float))
            k1, k2, k3, p1, p2 = np.asarray(dist, dtype=float).ravel()[:5]
            x, y = pts[:, 0], pts[:, 1]
            r2 = x ** 2 + y ** 2
            radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
            xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x ** 2)
            yd = y * radial + p1 * (r2 + 2 * y ** 2) + 2 * p2 * x * y
            out = np.column_stack([xd, yd])
            return out[0] if np.ndim(points) == 1 else out
        """, "OpenCV's order is (k1, k2, p1, p2, k3): k3, p1, p2 are read from the wrong places",
         ("order", "coefficients are read", "(k1, k2, p1, p2, k3)")),

    Case("distortion with r for r squared", "lab09.ext2", """
        def distort_points(points, dist):
            pts = np.atleast_2d(np.asarray(points, dtype=float))
            k1, k2, p1, p2, k3 = np.asarray(dist, dtype=float).ravel()[:5]
            x, y = pts[:, 0], pts[:, 1]
            r2 = np.sqrt(x ** 2 + y ** 2)
            radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
            xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x ** 2)
            yd = y * radial + p1 * (r2 + 2 * y ** 2) + 2 * p2 * x * y
            out = np.column_stack([xd, yd])
            return out[0] if np.ndim(points) == 1 else out
        """, "r^2 is computed as r (the square root taken): every power of r is halved",
         ("r^2", "r instead", "square root", "sqrt")),

    Case("intrinsic projection as X @ K", "lab09.ex2", """
        def project_with_intrinsics(K, points):
            X = np.atleast_2d(np.asarray(points, dtype=float))
            x = X @ np.asarray(K, dtype=float)
            out = x[:, :2] / x[:, 2:3]
            return out[0] if np.ndim(points) == 1 else out
        """, "points as rows need X @ K.T: X @ K applies K transposed",
         ("transposed", "k.t", "k^t")),

    Case("draw_points draws on the caller's image", "lab09.ex5", """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            for x, y in np.asarray(pts, dtype=float).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(image, (int(round(x)), int(round(y))), int(radius),
                               tuple(int(c) for c in color), -1)
            return image
        """, "the input image is modified in place (no copy)",
         ("in place", "copy", "modified"), moves=False),
]
