"""Lab 10: single-bug submissions written apart from the tables (see the package docstring)."""

from . import Case

MODULE = "lab10_camera2"

CASES = [
    Case("orthographic projection with a column of zeros", "lab10.ex3", """
        def orthographic_project(points):
            X = np.atleast_2d(np.asarray(points, dtype=float))
            M = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
            Xh = np.hstack([X, np.zeros((len(X), 1))])
            x = Xh @ M.T
            out = x[:, :2] / x[:, 2:3]
            return out[0] if np.ndim(points) == 1 else out
        """, "the homogeneous points end in 0, so w = 0 and the division gives NaN/inf",
         ("0 instead of 1", "zeros", "homogeneous", "w = 0", "divided by zero", "division by zero")),

    Case("camera DLT with X_i = (X, Y, Z, 0)", "lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            rows = []
            for (X, Y, Z), (u, v) in zip(np.asarray(points3d, float), np.asarray(points2d, float)):
                Xi = np.array([X, Y, Z, 0.0])
                rows.append(np.concatenate([Xi, np.zeros(4), -u * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -v * Xi]))
            _, _, Vt = np.linalg.svd(np.array(rows))
            return Vt[-1].reshape(3, 4)
        """, "the homogeneous 3D points end in 0 instead of 1: P's last column is not constrained",
         ("0 instead of 1", "zeros", "homogeneous", "last column", "fourth")),

    Case("camera DLT by np.linalg.eig of A^T A, last column", "lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.asarray(points3d, float)
            x = np.asarray(points2d, float)
            A = []
            for (Xw, Yw, Zw), (u, v) in zip(X, x):
                Xi = [Xw, Yw, Zw, 1.0]
                A.append(Xi + [0, 0, 0, 0] + [-u * c for c in Xi])
                A.append([0, 0, 0, 0] + Xi + [-v * c for c in Xi])
            A = np.array(A)
            w, V = np.linalg.eig(A.T @ A)
            p = np.real(V[:, -1])
            return p.reshape(3, 4)
        """, "np.linalg.eig does not sort its eigenvalues: the last column is not the smallest's",
         ("eig", "not sorted", "unsorted", "smallest")),

    Case("decomposition computes t after scaling K to K[2, 2] = 1", "lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, float)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            M = P[:, :3]
            flip = np.eye(3)[::-1]
            Q, U = np.linalg.qr((flip @ M).T)
            K = flip @ U.T @ flip
            R = flip @ Q.T
            S = np.diag(np.sign(np.diag(K)))
            K, R = K @ S, S @ R
            K = K / K[2, 2]
            t = np.linalg.inv(K) @ P[:, 3]
            return K, R, t
        """, "t = K^-1 p4 with K already divided by K[2, 2]: t carries P's scale",
         ("t carries", "scale of t", "t is scaled", "before t", "k[2, 2] before")),

    Case("camera centre without its minus sign", "lab10.ex5", """
        def camera_center(P):
            P = np.asarray(P, float)
            return np.linalg.solve(P[:, :3], P[:, 3])
        """, "C = -M^-1 p4: the sign is missing",
         ("sign", "minus", "-m^-1", "negat", "mirrored")),

    Case("dolly zoom focal lengths with floor division", "lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X = np.atleast_2d(np.asarray(points, float))
            distances = np.asarray(distances, float).ravel()
            fs = f0 * distances // z0
            out = []
            for f, d in zip(fs, distances):
                moved = X + np.array([0.0, 0.0, d - z0])
                out.append(perspective_project(moved, f))
            return fs, np.stack(out)
        """, "// floors the focal lengths to whole numbers",
         ("//", "floor", "whole", "integer", "rounded")),

    Case("weak perspective mean depth of X[2] (the third point)", "lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X = np.atleast_2d(np.asarray(points, float))
            if z_avg is None:
                z_avg = X[2].mean()
            out = f * X[:, :2] / z_avg
            return out[0] if np.ndim(points) == 1 else out
        """, "X[2] is the third point (a row), not the Z column X[:, 2]",
         ("x[2]", "third point", "row instead", "z column")),
]
