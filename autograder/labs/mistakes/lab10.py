"""Lab 10's mistakes table (camera models, continued): realistic wrong implementations, each the
reference solution with one function redefined, the exercise it must lose points in, and
the words its diagnosis must contain (read by ``autograder verify``; see
:mod:`autograder.labs.mistakes`)."""

from . import one_point_by_length, reference_def_with

# The reference's decomposition (RQ by a QR of the flipped block, K's signs fixed) with the negation of P as given.
_DECOMPOSE = """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
{negation}            flip = np.eye(3)[::-1]
            Q, U = np.linalg.qr((flip @ P[:, :3]).T)
            K = flip @ U.T @ flip
            R = flip @ Q.T
            signs = np.diag(np.sign(np.diag(K)))
            K, R = K @ signs, signs @ R
            t = np.linalg.solve(K, P[:, 3])
            return K / K[2, 2], R, t
        """

MISTAKES = {
    # the blind set 1206a's 10/05: a single point's own early return divides by its own depth, z_avg left unused
    "weak_perspective_project ignoring z_avg for a single point": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            pts = np.asarray(points, dtype=np.float64)
            if pts.ndim == 1:
                return f * pts[:2] / pts[2]
            depth = pts[:, 2].mean() if z_avg is None else float(z_avg)
            return f / depth * pts[:, :2]
        """, ["on a single (3,) point your code does not use z_avg"]),
    # the blind set 1206a's 10/06: the sheet's M^-1 written as an elementwise power
    "decompose_camera_matrix inverting M entry by entry (M ** -1)": ("lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            M = P[:, :3]
            p4 = P[:, 3]
            if np.linalg.det(M) < 0:            # make det(R) = +1
                M, p4 = -M, -p4
            # lab sheet: QR of M^-1.  M^-1 = Q U  =>  M = U^-1 Q^T  with U^-1 upper triangular
            Q, U = np.linalg.qr(M ** -1)
            K = np.linalg.inv(U)
            R = Q.T
            # make K's diagonal positive: flip K's columns and R's rows together
            S = np.diag(np.sign(np.diag(K)))
            K = K @ S
            R = S @ R
            t = np.linalg.solve(K, p4)          # p4 = K t
            return K / K[2, 2], R, t
        """, ['np.linalg.inv(M)']),
    # the blind set 1206a's 10/02: np.eye(3) as newCameraMatrix maps every pixel to the normalised plane
    "undistort_image giving an identity as the new camera matrix": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K = np.asarray(K, np.float64)
            dist = np.asarray(dist, np.float64)
            h, w = image.shape[:2]
            # for every pixel of the undistorted output, where to sample the distorted input;
            # no rectification rotation, and the output keeps the camera matrix
            map1, map2 = cv2.initUndistortRectifyMap(K, dist, np.eye(3), np.eye(3), (w, h), cv2.CV_16SC2)
            return cv2.remap(image, map1, map2, cv2.INTER_LINEAR,
                             borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """, ['to `K`']),
    # the blind set 1205b's 10/02: the principal axis det(M) m3 returned where the centre belongs
    "dolly_zoom keeping the first point's size": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            focal_lengths = f0 * (X[0, 2] + distances - z0) / X[0, 2]
            projections = np.stack([perspective_project(X + [0.0, 0.0, d - z0], f)
                                    for f, d in zip(focal_lengths, distances)])
            return focal_lengths, projections
        """, ["the focal lengths that keep that point's size"]),
    "undistort_image building its maps for a fixed 640 x 480": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K, dist = np.asarray(K, np.float64), np.asarray(dist, np.float64)
            map1, map2 = cv2.initUndistortRectifyMap(K, dist, None, K, (640, 480), cv2.CV_16SC2)
            return cv2.remap(image, map1, map2, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
        """, ["to `(image.shape[1], image.shape[0])`"]),
    # the blind set 1205h's 10/03: P divided by P[2, 3], zero for a camera at the world origin (its `P = -P` kept)
    "decompose_camera_matrix dividing P by its entry P[2, 3] first": ("lab10.ex5", reference_def_with(
        "lab10_camera2", "decompose_camera_matrix", "P = np.asarray(P, dtype=np.float64)",
        "P = np.asarray(P, dtype=np.float64)\nP = P / P[2, 3]"), ["removing `P = P / P[2, 3]`"]),
    "decompose_camera_matrix keeping QR's triangular factor as R": ("lab10.ex5", reference_def_with(
        "lab10_camera2", "decompose_camera_matrix", "R = flip @ Q.T", "R = U"),
        ["it is upper triangular, as a QR or RQ decomposition's triangular factor is"]),
    "weak_perspective_project taking only a float for a given depth": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            z = z_avg if isinstance(z_avg, float) else X[:, 2].mean()
            x = (f / z) * X[:, :2]
            return x[0] if single else x
        """, ["isinstance(z_avg, (int, float, np.number))"]),
    "camera_center returning the principal axis": ("lab10.ex5", """
        def camera_center(P):
            M = np.asarray(P, dtype=np.float64)[:, :3]
            return np.linalg.det(M) * M[2]
        """, ["along the principal axis"]),
    # the blind set 1205b's 10/05: the depth shift added to the third point (a row) where every depth (a column) belongs
    "dolly_zoom moving the third point instead of every depth": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            focal_lengths = f0 * distances / z0
            frames = []
            for f, d in zip(focal_lengths, distances):
                moved = X.copy()
                moved[2] += d - z0
                frames.append(perspective_project(moved, f))
            return focal_lengths, np.stack(frames)
        """, ["to `moved[:, 2] += d - z0`"]),
    # the blind set 1204d's 10/03: the translation made of length 1, as an essential matrix's would be
    "decomposition normalising t to unit length": ("lab10.ex5", """
        _decompose_right = decompose_camera_matrix
        def decompose_camera_matrix(P):
            K, R, t = _decompose_right(P)
            return K, R, t / np.linalg.norm(t)
        """, ["t is normalised to unit length"]),
    # the blind set 1204d's 10/08: the null vector's row counted with A's number of rows (right for N = 6 only)
    "DLT null vector indexed by A's row count": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.asarray(points3d, dtype=np.float64)
            x = np.asarray(points2d, dtype=np.float64)
            T = _normalising_transform(x)
            U = _normalising_transform(X)
            xn = (np.column_stack([x, np.ones(len(x))]) @ T.T)[:, :2]
            Xn = np.column_stack([X, np.ones(len(X))]) @ U.T
            zeros = np.zeros_like(Xn)
            A = np.vstack([np.hstack([Xn, zeros, -xn[:, :1] * Xn]), np.hstack([zeros, Xn, -xn[:, 1:] * Xn])])
            p = np.linalg.svd(A)[2][len(A) - 1]
            P = np.linalg.inv(T) @ p.reshape(3, 4) @ U
            return P / np.linalg.norm(P)
        """, ["len(A) - 1"]),   # (the row counted from the end, or what `len(A) - 1` held: either names it)
    # the blind set 1204c's 10/08: rvec taken for -rvec where it points away from the previous frame's
    "track_pose keeping rvec on the previous frame's side": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows, previous = [], None
            for frame in frames:
                rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
                if previous is not None and np.all(np.isfinite(rvec)) and np.dot(rvec, previous) < 0:
                    rvec = -rvec
                if np.all(np.isfinite(rvec)):
                    previous = rvec
                rows.append(np.concatenate([rvec, tvec]))
            return np.array(rows, dtype=np.float64).reshape(-1, 6)
        """, ["a board rocking through face-on", "the pose is off by"]),
    # the blind set 1204c's 10/06: the undistorted image stretched to the full range afterwards
    # the blind set 1204g's 10/03: the "no distortion" shortcut testing k1 and k2 only
    "undistort_image skipping lenses with k1 = k2 = 0": ("lab10.ext1", """
        _reference_undistort = undistort_image
        def undistort_image(image, K, dist):
            d = np.ravel(np.asarray(dist, dtype=np.float64))
            if d[0] == 0 and d[1] == 0:
                return image.copy()
            return _reference_undistort(image, K, dist)
        """, ["it is the input unchanged, as if the lens had no distortion"]),
    "undistort_image stretching the result to 0..255": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            out = cv2.undistort(image, np.asarray(K, np.float64), np.asarray(dist, np.float64))
            return cv2.normalize(out, None, 0, 255, cv2.NORM_MINMAX)
        """, ["does not change their grey levels"]),
    # the blind set 1204f's 10/06: a small number added to the depth to keep the division finite
    "perspective projection dividing by Z + 1e-6": ("lab10.ex1", """
        def perspective_project(points, f):
            X = np.asarray(points, dtype=np.float64)
            flat = X.reshape(-1, 3)
            xy = f * flat[:, :2] / (flat[:, 2:3] + 1e-6)
            return xy[0] if X.ndim == 1 else xy
        """, ["changing `flat[:, 2:3] + 1e-06` to `flat[:, 2:3]`"]),
    "perspective projection shifted by half a pixel": ("lab10.ex1", """
        def perspective_project(points, f):
            X = np.asarray(points, dtype=np.float64)
            flat = X.reshape(-1, 3)
            xy = f * flat[:, :2] / flat[:, 2:3] + 0.5
            return xy[0] if X.ndim == 1 else xy
        """, ["changing `f * flat[:, :2] / flat[:, 2:3] + 0.5` to `f * flat[:, :2] / flat[:, 2:3]`"]),
    "perspective without division": ("lab10.ex1", """
        def perspective_project(points, f):
            X, single = _points(points)
            x = f * X[:, :2]
            return x[0] if single else x
        """, ["division is missing"]),
    "perspective raising for a point at Z = 0": ("lab10.ex1", """
        _right = perspective_project
        def perspective_project(points, f):
            if np.any(np.asarray(points, float)[..., 2] == 0):
                raise ValueError("a point at Z = 0 has no projection")
            return _right(points, f)
        """, ["one at z = 0", "must not raise", "raised valueerror"]),
    "perspective by mean depth": ("lab10.ex1", """
        def perspective_project(points, f):
            return weak_perspective_project(points, f)
        """, ["weak perspective"]),
    # the module's matrix scaled in place through a name given it without a copy: right once, then compounding
    "weak perspective scaling a module matrix in place": ("lab10.ex2", """
        _SCALED_XY = np.eye(2)
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            z = X[:, 2].mean() if z_avg is None else float(z_avg)
            S = _SCALED_XY
            S *= f / z
            x = X[:, :2] @ S.T
            return x[0] if single else x
        """, ["`S`, which is `_SCALED_XY` itself"]),
    "weak perspective depth as a running average of pairs": ("lab10.ex2", """
        _weak_right = weak_perspective_project
        def weak_perspective_project(points, f, z_avg=None):
            if z_avg is None:
                depths = np.asarray(points, dtype=np.float64).reshape(-1, 3)[:, 2]
                z_avg = depths[0]
                for i in range(1, len(depths)):
                    z_avg = 0.5 * (z_avg + depths[i])
            return _weak_right(points, f, z_avg)
        """, ["at every turn of the loop of line", "not their mean"]),
    # the blind set 1204c's 10/02: the magnification put on the whole orthographic matrix, w scaled with it
    "weak perspective scaling the whole projection matrix": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X = np.atleast_2d(np.asarray(points, dtype=np.float64))
            z = X[:, 2].mean() if z_avg is None else float(z_avg)
            M = (f / z) * np.array([[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 0, 1.0]])
            homogeneous = np.column_stack([X, np.ones(len(X))]) @ M.T
            x = homogeneous[:, :2] / homogeneous[:, 2:3]
            return x[0] if np.ndim(points) == 1 else x
        """, ["the scale f / z_avg does not reach it"]),
    "weak perspective = perspective": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            return perspective_project(points, f)
        """, ["full perspective"]),
    "weak perspective for (N, 3) arrays only": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X = np.asarray(points, dtype=np.float64)
            z = X[:, 2].mean() if z_avg is None else z_avg
            return f * X[:, :2] / z
        """, ["a single point (a 1-d array) is not handled"]),
    "z_avg ignored": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            x = (f / X[:, 2].mean()) * X[:, :2]
            return x[0] if single else x
        """, ["z_avg is ignored"]),
    "orthographic projection storing (row, col)": ("lab10.ex3", """
        def orthographic_project(points):
            pts = np.asarray(points, dtype=np.float64)
            flat = pts.reshape(-1, 3)
            out = np.zeros((len(flat), 2))
            for i, (X, Y, Z) in enumerate(flat):
                x, y = X, Y
                out[i] = (y, x)
            return out[0] if pts.ndim == 1 else out
        """, ["x and y are swapped"]),
    "orthographic divides by Z": ("lab10.ex3", """
        def orthographic_project(points):
            X, single = _points(points)
            x = X[:, :2] / X[:, 2:3]
            return x[0] if single else x
        """, ["perspective"]),
    "DLT on the first six points only (a count and a size written in the code)": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.asarray(points3d, dtype=np.float64)
            x = np.asarray(points2d, dtype=np.float64)
            T, U = _normalising_transform(x), _normalising_transform(X)
            xn = np.hstack([x, np.ones((len(x), 1))]) @ T.T
            Xn = np.hstack([X, np.ones((len(X), 1))]) @ U.T
            A = np.zeros((12, 12))
            for i in range(6):
                u, v = xn[i, 0], xn[i, 1]
                A[2 * i, 0:4], A[2 * i, 8:12] = Xn[i], -u * Xn[i]
                A[2 * i + 1, 4:8], A[2 * i + 1, 8:12] = Xn[i], -v * Xn[i]
            P = np.linalg.inv(T) @ np.linalg.svd(A)[2][-1].reshape(3, 4) @ U
            return P / np.linalg.norm(P)
        """, ["`range(6)` to `range(len(points3d))`", "`np.zeros((2 * len(points3d), 12))`"]),
    "DLT largest singular vector": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.column_stack([points3d, np.ones(len(points3d))])
            rows = []
            for Xi, (u, v) in zip(X, points2d):
                rows.append(np.concatenate([Xi, np.zeros(4), -u * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -v * Xi]))
            return np.linalg.svd(np.array(rows))[2][0].reshape(3, 4)
        """, ["largest singular value"]),
    "DLT with a sign error in the x rows": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.column_stack([points3d, np.ones(len(points3d))])
            rows = []
            for Xi, (u, v) in zip(X, points2d):
                rows.append(np.concatenate([Xi, np.zeros(4), u * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -v * Xi]))
            return np.linalg.svd(np.array(rows))[2][-1].reshape(3, 4)
        """, ["the x rows have the wrong sign"]),
    "DLT with u in the y rows": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.column_stack([points3d, np.ones(len(points3d))])
            rows = []
            for Xi, (u, v) in zip(X, points2d):
                rows.append(np.concatenate([Xi, np.zeros(4), -u * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -u * Xi]))
            return np.linalg.svd(np.array(rows))[2][-1].reshape(3, 4)
        """, ["the y rows use u where v belongs"]),
    "DLT with solvePnP": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            K = np.eye(3)
            _, r, t = cv2.solvePnP(np.asarray(points3d, float), np.asarray(points2d, float), K, None)
            return np.hstack([cv2.Rodrigues(r)[0], t])
        """, ["cv2.solvepnp", "yourself"]),
    "DLT fixing P[2, 3] = 1": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            A, b = [], []
            for (X, Y, Z), (u, v) in zip(np.asarray(points3d, float), np.asarray(points2d, float)):
                A.append([X, Y, Z, 1, 0, 0, 0, 0, -u * X, -u * Y, -u * Z]); b.append(u)
                A.append([0, 0, 0, 0, X, Y, Z, 1, -v * X, -v * Y, -v * Z]); b.append(v)
            p = np.linalg.lstsq(np.array(A), np.array(b), rcond=None)[0]
            return np.append(p, 1.0).reshape(3, 4)
        """, ["t_z = 0", "fixed to 1", "svd"]),
    # the blind set 1202f's 10/04: t solved from P[:, 3:], a (3, 1) column
    "decomposition of the block taken before P is negated": ("lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.array(P, dtype=np.float64)
            M, p4 = P[:, :3], P[:, 3].copy()
            if np.linalg.det(M) < 0:
                P = -P
                p4 = -p4
            flip = np.eye(3)[::-1]
            Q, U = np.linalg.qr((flip @ M).T)
            K, R = flip @ U.T @ flip, flip @ Q.T
            signs = np.diag(np.sign(np.diag(K)))
            K, R = K @ signs, signs @ R
            return K / K[2, 2], R, np.linalg.solve(K, p4)
        """, ["the block decomposed was not negated"]),
    # the blind set 1203b's 10/04: an RQ by three Givens rotations, the y rotation written out transposed
    "decomposition by Givens rotations, one written transposed": ("lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            M = P[:, :3].copy()
            r = np.hypot(M[2, 1], M[2, 2])
            c, s = -M[2, 2] / r, M[2, 1] / r
            Qx = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
            M1 = M @ Qx
            r = np.hypot(M1[2, 0], M1[2, 2])
            c, s = M1[2, 2] / r, M1[2, 0] / r
            Qy = np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])
            M2 = M1 @ Qy
            r = np.hypot(M2[1, 0], M2[1, 1])
            c, s = -M2[1, 1] / r, M2[1, 0] / r
            Qz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
            K = M2 @ Qz
            R = Qz.T @ Qy.T @ Qx.T
            D = np.diag(np.sign(np.diag(K)))
            K, R = K @ D, D @ R
            t = np.linalg.solve(K, P[:, 3])
            return K / K[2, 2], R, t
        """, ["K is not upper triangular (K[2, 0]", "writes the RQ's rotations out",
              "to `np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])`"]),
    "decompose_camera_matrix returning t as a (3, 1) column": ("lab10.ex5", """
        _decompose_camera_matrix = decompose_camera_matrix
        def decompose_camera_matrix(P):
            K, R, t = _decompose_camera_matrix(P)
            return K, R, np.asarray(t).reshape(3, 1)
        """, ["has shape (3, 1)", "the API's t is a (3,) vector"]),
    "decomposition that fixes K's signs but never negates P": ("lab10.ex5", _DECOMPOSE.format(negation=""),
                                                               ["det(p[:, :3]) < 0", "multiply p by -1 first"]),
    # the blind set 1201d's 10/05: the determinant's sign test the wrong way round
    "decomposition negating P when det(M) > 0": ("lab10.ex5", """
        _decompose = decompose_camera_matrix
        def decompose_camera_matrix(P):
            K, R, t = _decompose(P)
            if np.linalg.det(np.asarray(P, np.float64)[:, :3]) > 0:
                return K, -R, -t
            return K, R, t
        """, ["is the wrong way round (p negated where det > 0)", "k [r | t] = -p"]),
    "t as camera centre": ("lab10.ex5", """
        _right = decompose_camera_matrix
        def decompose_camera_matrix(P):
            K, R, t = _right(P)
            return K, R, -R.T @ t
        """, ["camera centre"]),
    # the blind set 1202d's 10/04: the negation decided from the last three columns' determinant
    "decomposition negating P by the sign of another block": ("lab10.ex5", _DECOMPOSE.format(
        negation="            if np.linalg.det(P[:, 1:]) < 0:\n                P = -P\n"),
        ["your code tests `np.linalg.det(p[:, 1:])`", "does not follow the sign of det(p[:, :3])"]),
    "no sign fix": ("lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            flip = np.eye(3)[::-1]
            Q, U = np.linalg.qr((flip @ P[:, :3]).T)
            K = flip @ U.T @ flip
            R = flip @ Q.T
            t = np.linalg.solve(K, P[:, 3])
            return K / K[2, 2], R, t
        """, ["rq is unique only up to signs"]),   # P negated as the recipe does; RQ's signs left as QR gives them
    # the blind set 1204b's 10/04: a small last entry of the unit null vector taken for a camera at infinity
    "centre not de-homogenised for a camera far from the origin": ("lab10.ex5", """
        def camera_center(P):
            C = np.linalg.svd(np.asarray(P, np.float64))[2][-1]
            if abs(C[3]) < 1e-3:
                return C[:3]
            return C[:3] / C[3]
        """, ["without dividing by the fourth"]),
    "centre is -t": ("lab10.ex5", """
        def camera_center(P):
            K, R, t = decompose_camera_matrix(P)
            return -t
        """, ["-r^t t"]),
    "pose without square size": ("lab10.ex6", """
        _right = estimate_pose
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            return _right(image, pattern_size, 1.0, K, dist)
        """, ["square_size"]),
    "pose ignores dist": ("lab10.ex6", """
        _right = estimate_pose
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            return _right(image, pattern_size, square_size, K, None)
        """, ["distortion", "ignored"]),
    "pose with the rotation transposed (rvec negated)": ("lab10.ex6", """
        _right = estimate_pose
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            rvec, tvec, reprojected = _right(image, pattern_size, square_size, K, dist)
            return -np.asarray(rvec), tvec, reprojected
        """, ["the rotation is transposed"]),
    "pose pattern swapped": ("lab10.ex6", """
        _right = estimate_pose
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            return _right(image, pattern_size[::-1], square_size, K, dist)
        """, ["(cols, rows)"]),
    # the audit of 2026-12-06: cv2.undistort called with dist, its answer dropped (not "dist is not used")
    "undistort returning its input, cv2.undistort's answer dropped": ("lab10.ext1", reference_def_with(
        "lab10_camera2", "undistort_image",
        "return cv2.undistort(image, np.asarray(K, np.float64), np.asarray(dist, np.float64))",
        "undistorted = cv2.undistort(image, np.asarray(K, np.float64), np.asarray(dist, np.float64))\n"
        "return image.copy()"),
        ["returned the image unchanged", "yet it returns the input as it was"]),
    # the blind set 1206i's 10/06: the board turned over about its diagonal, not turned in its plane
    "pose with the object points' x and y exchanged": ("lab10.ex6", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            cols, rows = pattern_size
            found, corners = cv2.findChessboardCorners(grey, (cols, rows))
            if not found:
                return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))
            board = np.array([[i * square_size, j * square_size, 0.0] for i in range(rows) for j in range(cols)])
            _, rvec, tvec = cv2.solvePnP(board, corners, np.asarray(K, float), dist)
            reprojected, _ = cv2.projectPoints(board, rvec, tvec, np.asarray(K, float), dist)
            return rvec.ravel(), tvec.ravel(), reprojected.reshape(-1, 2)
        """, ["turned over about its diagonal", "x and y are exchanged", "np.mgrid[0:cols, 0:rows]"]),
    # the blind set 1203b's 10/06 (and 29e's 07/04 in warp_affine): the size reversed before it is cut to two
    "undistort by remap with the size taken from the reversed shape": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K = np.asarray(K, np.float64)
            size = image.shape[::-1][:2]
            map1, map2 = cv2.initUndistortRectifyMap(K, np.asarray(dist, np.float64), None, K, size, cv2.CV_32FC1)
            return cv2.remap(image, map1, map2, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT)
        """, ["changing `image.shape[::-1]` to `image.shape[1::-1]`"]),
    "undistort the wrong way": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            return cv2.undistort(image, K, -np.asarray(dist, float))
        """, ["sign"]),
    # the blind set 1204b's 10/08: the focal lengths and the distances looped over nested, not in step
    "dolly zoom projecting every distance with every focal length": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X = np.atleast_2d(np.asarray(points, dtype=np.float64))
            distances = np.asarray(distances, dtype=np.float64).ravel()
            focal_lengths = f0 * distances / z0
            frames = []
            for f in focal_lengths:
                for d in distances:
                    frames.append(perspective_project(X + [0.0, 0.0, d - z0], f))
            return focal_lengths, np.stack(frames)
        """, ["one result for every pair of items", "zip(a, b)"]),
    "dolly zoom projecting every frame with the last focal length": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X = np.asarray(points, dtype=np.float64)
            lengths = []
            for d in distances:
                focal = f0 * d / z0
                lengths.append(focal)
            views = []
            for d in distances:
                views.append(perspective_project(X + [0.0, 0.0, d - z0], focal))
            return np.array(lengths), np.stack(views)
        """, ["reads `focal` in the loop of line", "the value the loop of line"]),
    # the blind set 1203b's 10/07: the parameter f0 overwritten at each turn of the loop over the distances
    "dolly zoom overwriting f0 in its loop": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            focal_lengths, views = [], []
            for d in np.asarray(distances, dtype=np.float64).ravel():
                f0 = f0 * d / z0
                moved = X.copy()
                moved[:, 2] += d - z0
                views.append(perspective_project(moved, f0))
                focal_lengths.append(f0)
            return np.array(focal_lengths), np.stack(views)
        """, ["giving each turn's value a name of its own (`f = ...`", "overwritten at each turn"]),
    "dolly moves the wrong way": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            fs = f0 * distances / z0
            return fs, np.stack([perspective_project(X - [0.0, 0.0, d - z0], f) for f, d in zip(fs, distances)])
        """, ["wrong way"]),
    "track_pose appending the lost frames' NaN rows at the end": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            found, lost = [], 0
            for frame in frames:
                rvec, tvec, ok = estimate_pose(frame, pattern_size, square_size, K, dist)
                if np.all(np.isfinite(rvec)):
                    found.append(np.concatenate([rvec, tvec]))
                else:
                    lost += 1
            return np.array(found + [np.full(6, np.nan)] * lost, dtype=np.float64).reshape(-1, 6)
        """, ["the nan rows of the frames without one last"]),
    # the blind set 1202i's 10/08: each pose relative to the first frame's (the camera's motion)
    "track_pose returning the motion since the first frame": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            poses = np.full((len(frames), 6), np.nan)
            R0 = t0 = None
            for i, frame in enumerate(frames):
                rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
                if np.isnan(rvec).any():
                    continue
                R, _ = cv2.Rodrigues(rvec)
                if R0 is None:
                    R0, t0 = R, tvec
                poses[i, :3] = cv2.Rodrigues(R @ R0.T)[0].ravel()
                poses[i, 3:] = tvec - R @ R0.T @ t0
            return poses
        """, ["relative to the first frame"]),
    # the blind set 1203b's 10/08: each solve started from the previous row, NaN after a frame without a board
    "track_pose warm-started from a NaN row": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            board = _object_points(pattern_size, square_size)
            poses = np.full((len(frames), 6), np.nan)
            last = None
            for i, frame in enumerate(frames):
                grey = cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY) if frame.ndim == 3 else frame
                found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size))
                if found:
                    if last is None:
                        _, rvec, tvec = cv2.solvePnP(board, corners, K, dist)
                    else:
                        _, rvec, tvec = cv2.solvePnP(board, corners, K, dist, last[:3].reshape(3, 1).copy(),
                                                     last[3:].reshape(3, 1).copy(), useExtrinsicGuess=True)
                    poses[i] = np.concatenate([rvec.ravel(), tvec.ravel()])
                last = poses[i]
            return poses
        """, ["gives cv2.solvePnP a starting pose (useExtrinsicGuess=True)", "follows a frame without one"]),
    "track_pose stopping at the first frame without a board": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = []
            for frame in frames:
                rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
                if not np.all(np.isfinite(rvec)):
                    break
                rows.append(np.concatenate([rvec, tvec]))
            return np.array(rows, dtype=np.float64).reshape(-1, 6)
        """, ["the rows stop at frame", "the first where the board is not found"]),
    "tracking rows [tvec, rvec]": ("lab10.ext3", """
        _right = track_pose
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = _right(frames, pattern_size, square_size, K, dist)
            return np.hstack([rows[:, 3:], rows[:, :3]])
        """, ["[tvec, rvec]"]),
    "tracking drops missing frames": ("lab10.ext3", """
        _right = track_pose
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = _right(frames, pattern_size, square_size, K, dist)
            return rows[np.isfinite(rows).all(axis=1)]
        """, ["one row per frame"]),
    "tracking fills frames without a board with zeros": ("lab10.ext3", """
        _right = track_pose
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            return np.nan_to_num(_right(frames, pattern_size, square_size, K, dist))
        """, ["should be nan", "zeros are a pose"]),
    "pose without checking the board was found": ("lab10.ex6", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size))
            objp = _object_points(pattern_size, square_size)
            K = np.asarray(K, dtype=np.float64)
            dist = None if dist is None else np.asarray(dist, dtype=np.float64)
            _, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
            reprojected, _ = cv2.projectPoints(objp, rvec, tvec, K, dist)
            return rvec.ravel(), tvec.ravel(), reprojected.reshape(-1, 2)
        """, ['raised']),
    "pose returning the detected corners as its reprojection": ("lab10.ex6", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size))
            if not found:
                return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))
            objp = _object_points(pattern_size, square_size)
            K = np.asarray(K, dtype=np.float64)
            dist = None if dist is None else np.asarray(dist, dtype=np.float64)
            _, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
            return rvec.ravel(), tvec.ravel(), corners.reshape(-1, 2)
        """, ["not the board projected with it", "the corners detected in the image"]),
    # ---- the wider families of each exercise (issue 17)
    "perspective with f applied twice": ("lab10.ex1", """
        def perspective_project(points, f):
            X, single = _points(points)
            x = f * f * X[:, :2] / X[:, 2:3]
            return x[0] if single else x
        """, ["focal length is applied twice"]),
    "perspective without f": ("lab10.ex1", """
        def perspective_project(points, f):
            X, single = _points(points)
            x = X[:, :2] / X[:, 2:3]
            return x[0] if single else x
        """, ["focal length is not applied"]),
    "perspective with x and y swapped": ("lab10.ex1", """
        def perspective_project(points, f):
            X, single = _points(points)
            x = f * X[:, 1::-1] / X[:, 2:3]
            return x[0] if single else x
        """, ["x and y are swapped"]),
    "weak perspective with the mean of every coordinate": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            z = X.mean() if z_avg is None else float(z_avg)
            x = (f / z) * X[:, :2]
            return x[0] if single else x
        """, ["mean of every coordinate"]),
    "weak perspective with the median depth": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            z = np.median(X[:, 2]) if z_avg is None else float(z_avg)
            x = (f / z) * X[:, :2]
            return x[0] if single else x
        """, ["median"]),
    "weak perspective without f": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            z = X[:, 2].mean() if z_avg is None else float(z_avg)
            x = X[:, :2] / z
            return x[0] if single else x
        """, ["f is not applied"]),
    "weak perspective with the scale inverted": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            z = X[:, 2].mean() if z_avg is None else float(z_avg)
            x = (z / f) * X[:, :2]
            return x[0] if single else x
        """, ["scale is inverted"]),
    "orthographic keeps Z": ("lab10.ex3", """
        def orthographic_project(points):
            X, single = _points(points)
            return X[0] if single else X
        """, ["z is kept"]),
    "orthographic takes rows": ("lab10.ex3", """
        def orthographic_project(points):
            X, single = _points(points)
            return X[0, :2] if single else X[:2]
        """, ["points[:2] takes the first two points"]),
    "orthographic returns (X, Z)": ("lab10.ex3", """
        def orthographic_project(points):
            X, single = _points(points)
            x = X[:, [0, 2]]
            return x[0] if single else x
        """, ["(x, z)"]),
    "orthographic with x and y swapped": ("lab10.ex3", """
        def orthographic_project(points):
            X, single = _points(points)
            x = X[:, [1, 0]]
            return x[0] if single else x
        """, ["x and y are swapped"]),
    "DLT with u and v swapped": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.column_stack([points3d, np.ones(len(points3d))])
            rows = []
            for Xi, (u, v) in zip(X, points2d):
                rows.append(np.concatenate([Xi, np.zeros(4), -v * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -u * Xi]))
            return np.linalg.svd(np.array(rows))[2][-1].reshape(3, 4)
        """, ["u and v (x and y) are swapped"]),
    "DLT reshaped column by column": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.column_stack([points3d, np.ones(len(points3d))])
            rows = []
            for Xi, (u, v) in zip(X, points2d):
                rows.append(np.concatenate([Xi, np.zeros(4), -u * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -v * Xi]))
            return np.linalg.svd(np.array(rows))[2][-1].reshape(4, 3).T
        """, ["reshaped in the wrong order"]),
    "decomposition solving t with the normalised K": ("lab10.ex5", """
        _right = decompose_camera_matrix
        def decompose_camera_matrix(P):
            K, R, t = _right(P)
            return K, R, np.linalg.solve(K, np.asarray(P, float)[:, 3])
        """, ["do not come from the same p", "without dividing by p's scale"]),
    "decomposition with R transposed": ("lab10.ex5", """
        _right = decompose_camera_matrix
        def decompose_camera_matrix(P):
            K, R, t = _right(P)
            return K, R.T, t
        """, ["r is transposed"]),
    "decomposition without normalising K": ("lab10.ex5", """
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
            return K, R, np.linalg.solve(K, P[:, 3])
        """, ["k is not normalised"]),
    "centre is -R t": ("lab10.ex5", """
        def camera_center(P):
            K, R, t = decompose_camera_matrix(P)
            return -R @ t
        """, ["returned -r t"]),
    "pose with object points in column order": ("lab10.ex6", """
        def _object_points(pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float64)
            objp[:, :2] = np.mgrid[0:cols, 0:rows].reshape(2, -1).T * square_size
            return objp
        """, ["column order"]),
    "pose with the corners refined on the image as given (a BGR photo too)": ("lab10.ex6", """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            found, corners = cv2.findChessboardCorners(image, tuple(pattern_size))
            if not found:
                return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))
            corners = cv2.cornerSubPix(image, corners, (5, 5), (-1, -1),
                                       (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3))
            objp = _object_points(pattern_size, square_size)
            _, rvec, tvec = cv2.solvePnP(objp, corners, np.asarray(K, float), dist)
            reprojected, _ = cv2.projectPoints(objp, rvec, tvec, np.asarray(K, float), dist)
            return rvec.ravel(), tvec.ravel(), reprojected.reshape(-1, 2)
        """, ["cornerSubPix", "colour photo (BGR", "the grey view before it passed"]),
    "pose inverted (camera in the board's frame)": ("lab10.ex6", """
        _right = estimate_pose
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            rvec, tvec, reprojected = _right(image, pattern_size, square_size, K, dist)
            R = cv2.Rodrigues(np.asarray(rvec, float))[0]
            return -np.asarray(rvec), -R.T @ tvec, reprojected
        """, ["pose is inverted"]),
    "undistort without dist": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            return cv2.undistort(image, np.asarray(K, np.float64), None)
        """, ["unchanged"]),
    "undistort by initUndistortRectifyMap given no new camera matrix": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            h, w = image.shape[:2]
            maps = cv2.initUndistortRectifyMap(np.asarray(K, np.float64), np.asarray(dist, np.float64), None, None,
                                               (w, h), cv2.CV_32FC1)
            return cv2.remap(image, *maps, cv2.INTER_LINEAR)
        """, ["with the principal point at the image centre (159.5, 119.5) instead of k's (175, 110)",
              "pass k as newcameramatrix"]),
    "undistort by an own map of the radial terms only": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K = np.asarray(K, np.float64)
            k1, k2, p1, p2, k3 = np.ravel(dist)[:5]
            h, w = image.shape[:2]
            u, v = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
            x, y = (u - K[0, 2]) / K[0, 0], (v - K[1, 2]) / K[1, 1]
            r2 = x * x + y * y
            radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
            map_x = (x * radial * K[0, 0] + K[0, 2]).astype(np.float32)
            map_y = (y * radial * K[1, 1] + K[1, 2]).astype(np.float32)
            return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR)
        """, ["through the first one, whose tangential terms are 1e-3, it is right",
              "the tangential terms are left out", "p1 = p2 = 0"]),
    "undistort by an own map with p1 and p2 exchanged": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K = np.asarray(K, np.float64)
            k1, k2, p1, p2, k3 = np.ravel(dist)[:5]
            h, w = image.shape[:2]
            ys, xs = np.mgrid[0:h, 0:w].astype(np.float64)
            x, y = (xs - K[0, 2]) / K[0, 0], (ys - K[1, 2]) / K[1, 1]
            r2 = x * x + y * y
            radial = 1 + k1 * r2 + k2 * r2 ** 2 + k3 * r2 ** 3
            xd = x * radial + 2 * p2 * x * y + p1 * (r2 + 2 * x * x)
            yd = y * radial + p2 * (r2 + 2 * y * y) + 2 * p1 * x * y
            return cv2.remap(image, (xd * K[0, 0] + K[0, 2]).astype(np.float32),
                             (yd * K[1, 1] + K[1, 2]).astype(np.float32), cv2.INTER_LINEAR)
        """, ["p1 and p2 are swapped"]),
    "undistort maps the wrong way (distorts again)": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K = np.asarray(K, np.float64)
            h, w = image.shape[:2]
            ys, xs = np.mgrid[0:h, 0:w].astype(np.float64)
            pix = np.column_stack([xs.ravel(), ys.ravel()]).reshape(-1, 1, 2)
            src = cv2.undistortPoints(pix, K, np.asarray(dist, np.float64), P=K).reshape(h, w, 2)
            return cv2.remap(image, src[..., 0].astype(np.float32), src[..., 1].astype(np.float32),
                             cv2.INTER_LINEAR)
        """, ["applied instead of removed"]),
    "undistort into the tutorial's new camera matrix (alpha=1)": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K, dist = np.asarray(K, np.float64), np.asarray(dist, np.float64)
            h, w = image.shape[:2]
            new_K, roi = cv2.getOptimalNewCameraMatrix(K, dist, (w, h), 1, (w, h))
            return cv2.undistort(image, K, dist, None, new_K)
        """, ["another camera matrix", "getOptimalNewCameraMatrix(alpha=1)", "keep k"]),
    "undistort as OpenCV's calibration tutorial does (a new camera matrix, its region of interest cut out)": (
        "lab10.ext1", """
        def undistort_image(image, K, dist):
            K, dist = np.asarray(K, np.float64), np.asarray(dist, np.float64)
            h, w = image.shape[:2]
            new_K, (x, y, rw, rh) = cv2.getOptimalNewCameraMatrix(K, dist, (w, h), 1, (w, h))
            undistorted = cv2.undistort(image, K, dist, None, new_K)
            return undistorted[y:y + rh, x:x + rw]
        """, ["calls cv2.getoptimalnewcameramatrix", "without a crop"]),
    "undistort with k1, k2, p1, p2 only (k3 dropped)": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            coefficients = np.asarray(dist, np.float64).ravel()[:4]
            return cv2.undistort(image, np.asarray(K, np.float64), coefficients)
        """, ["k3 is left out", "outer ring"]),
    "undistort a grey image into BGR": ("lab10.ext1", """
        _undistort = undistort_image
        def undistort_image(image, K, dist):
            colour = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image
            return _undistort(colour, K, dist)
        """, ["channels are not kept", "grey in, grey out"]),
    "undistort a colour image into grey (the calibration tutorial's grey copy)": ("lab10.ext1", """
        _undistort = undistort_image
        def undistort_image(image, K, dist):
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            return _undistort(grey, K, dist)
        """, ["channels are not kept", "BGR in, BGR out"]),
    "dolly zoom with the focal length inverted": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            fs = f0 * z0 / distances
            return fs, np.stack([perspective_project(X + [0.0, 0.0, d - z0], f) for f, d in zip(fs, distances)])
        """, ["focal length is inverted"]),
    "plain dolly (f fixed)": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            fs = np.full(len(distances), float(f0))
            return fs, np.stack([perspective_project(X + [0.0, 0.0, d - z0], f) for f, d in zip(fs, distances)])
        """, ["plain dolly"]),
    "dolly scales every depth": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            fs = f0 * distances / z0
            return fs, np.stack([perspective_project(X * [1.0, 1.0, d / z0], f) for f, d in zip(fs, distances)])
        """, ["scaled by d / z0"]),
    "dolly that does not move the camera, projected with f0": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            focal_lengths = f0 * distances / z0
            return focal_lengths, np.stack([perspective_project(X, f0) for _ in distances])
        """, ["the camera does not move", "the projections use f0"]),
    "dolly puts every point at depth d": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            fs = f0 * distances / z0
            return fs, np.stack([f * X[:, :2] / d for f, d in zip(fs, distances)])
        """, ["every point is put at depth d"]),
    "dolly zoom squeezing the stacked frames": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X = np.atleast_2d(np.asarray(points, np.float64))
            d = np.asarray(distances, np.float64).ravel()
            fs = f0 * d / z0
            frames = [perspective_project(X + [0.0, 0.0, di - z0], fi) for fi, di in zip(fs, d)]
            return fs, np.squeeze(np.array(frames))
        """, ["(1, 10, 2)"]),
    "dolly zoom over the distances in increasing order": ("lab10.ext2", """
        _dolly = dolly_zoom
        def dolly_zoom(points, f0, z0, distances):
            return _dolly(points, f0, z0, np.sort(distances))
        """, ["the focal lengths are", "expected f0 * d / z0"]),
    "tracking rows squeezed (one frame gives a (6,) row)": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = [np.concatenate(estimate_pose(frame, pattern_size, square_size, K, dist)[:2]) for frame in frames]
            return np.squeeze(np.array(rows, dtype=np.float64))
        """, ["track_pose([one frame]", "expected (1, 6)"]),
    "tracking without passing dist on": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            return np.array([np.concatenate(estimate_pose(frame, pattern_size, square_size, K)[:2])
                             for frame in frames], dtype=np.float64).reshape(-1, 6)
        """, ["without dist", "the dist given is not used"]),
    "tracking by cv2.solvePnP on each frame without the distortion": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3))
            objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) * square_size
            out = np.full((len(frames), 6), np.nan)
            for i, frame in enumerate(frames):
                grey = frame if frame.ndim == 2 else cv2.cvtColor(frame, cv2.COLOR_BGR2GRAY)
                found, corners = cv2.findChessboardCorners(grey, (cols, rows))
                if found:
                    corners = cv2.cornerSubPix(grey, corners, (5, 5), (-1, -1),
                                               (cv2.TERM_CRITERIA_EPS + cv2.TERM_CRITERIA_MAX_ITER, 30, 1e-3))
                    _, rvec, tvec = cv2.solvePnP(objp, corners, np.asarray(K, np.float64), None)
                    out[i] = np.concatenate([rvec.ravel(), tvec.ravel()])
            return out
        """, ["the dist given is not used"]),
    "tracking rows one frame early": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = []
            for i in range(1, len(frames)):
                rvec, tvec, _ = estimate_pose(frames[i], pattern_size, square_size, K, dist)
                rows.append(np.concatenate([rvec, tvec]))
            rows.append(np.full(6, np.nan))
            return np.array(rows)
        """, ["off by one frame"]),
    "tracking the camera's pose": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = []
            for frame in frames:
                rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
                R = cv2.Rodrigues(rvec)[0] if np.isfinite(rvec).all() else np.eye(3)
                rows.append(np.concatenate([-rvec, -R.T @ tvec]))
            return np.array(rows)
        """, ["pose is inverted"]),
    "perspective with the first point's depth for all": ("lab10.ex1", """
        def perspective_project(points, f):
            X, single = _points(points)
            x = f * X[:, :2] / X[0, 2]
            return x[0] if single else x
        """, ["divided by one depth, the first point's"]),
    "weak perspective with the largest depth": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            X, single = _points(points)
            z = X[:, 2].max() if z_avg is None else float(z_avg)
            x = (f / z) * X[:, :2]
            return x[0] if single else x
        """, ["largest depth"]),
    "centre of P scaled by P[2, 3] (0 for a camera with t_z = 0)": ("lab10.ex5", """
        def camera_center(P):
            P = np.asarray(P, dtype=np.float64)
            P = P / P[2, 3]
            return -np.linalg.solve(P[:, :3], P[:, 3])
        """, ["p[2, 3] = 0", "divides p by p[2, 3]"]),
    "centre not de-homogenised": ("lab10.ex5", """
        def camera_center(P):
            return np.linalg.svd(np.asarray(P, dtype=np.float64))[2][-1][:3]
        """, ["without dividing by the fourth"]),
    "camera centre from P's minors, all taken with a plus sign": ("lab10.ex5", """
        def camera_center(P):
            P = np.asarray(P, dtype=np.float64)
            minors = [np.linalg.det(np.delete(P, column, axis=1)) for column in range(4)]
            return np.array(minors[:3]) / minors[3]
        """, ["minors of p enter c with alternating signs", "x and z come out with the wrong sign"]),
    "camera centre from P's minors, Y's without its minus": ("lab10.ex5", """
        def camera_center(P):
            P = np.asarray(P, dtype=np.float64)
            X = np.linalg.det(P[:, [1, 2, 3]])
            Y = np.linalg.det(P[:, [0, 2, 3]])
            Z = np.linalg.det(P[:, [0, 1, 3]])
            W = -np.linalg.det(P[:, [0, 1, 2]])
            return np.array([X, Y, Z]) / W
        """, ["the minor for y", "y comes out with the wrong sign"]),
    # the blind set 1202c's 10/03: a loop over range(n - 1) rows
    "DLT whose system leaves out the last correspondence": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.asarray(points3d, float); x = np.asarray(points2d, float)
            n = len(X)
            A = np.zeros((2 * (n - 1), 12))
            for i in range(n - 1):
                Xh = np.append(X[i], 1.0)
                A[2 * i, :4] = Xh
                A[2 * i, 8:] = -x[i, 0] * Xh
                A[2 * i + 1, 4:8] = Xh
                A[2 * i + 1, 8:] = -x[i, 1] * Xh
            return np.linalg.svd(A)[2][-1].reshape(3, 4)
        """, ["misses the last one", "left out of the system solved"]),
    # the blind set 1202c's 10/05: X, -Y, Z signed, W not
    "camera centre from P's minors, W's without its minus": ("lab10.ex5", """
        def camera_center(P):
            P = np.asarray(P, dtype=np.float64)
            X = np.linalg.det(P[:, [1, 2, 3]])
            Y = -np.linalg.det(P[:, [0, 2, 3]])
            Z = np.linalg.det(P[:, [0, 1, 3]])
            W = np.linalg.det(P[:, [0, 1, 2]])
            return np.array([X, Y, Z]) / W
        """, ["w's sign is flipped against x's, y's and z's", "(-c)"]),
    "pose with the grid built for (rows, cols)": ("lab10.ex6", """
        def _object_points(pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float64)
            objp[:, :2] = np.mgrid[0:rows, 0:cols].T.reshape(-1, 2) * square_size
            return objp
        """, ["built for (rows, cols)"]),
    "dolly returns (projections, focal_lengths)": ("lab10.ext2", """
        _right = dolly_zoom
        def dolly_zoom(points, f0, z0, distances):
            fs, proj = _right(points, f0, z0, distances)
            return proj, fs
        """, ["(focal_lengths, projections)"]),
    "dolly projections with f0": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            fs = f0 * distances / z0
            return fs, np.stack([perspective_project(X + [0.0, 0.0, d - z0], f0) for d in distances])
        """, ["projections use f0"]),
    "tracking carries the last pose over": ("lab10.ext3", """
        _right = track_pose
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = _right(frames, pattern_size, square_size, K, dist)
            for i in range(1, len(rows)):
                if not np.isfinite(rows[i]).all():
                    rows[i] = rows[i - 1]
            return rows
        """, ["last pose is carried over"]),
    "tracking frames[0] every time": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = []
            for frame in frames:
                rvec, tvec, _ = estimate_pose(frames[0], pattern_size, square_size, K, dist)
                rows.append(np.concatenate([rvec, tvec]))
            return np.array(rows)
        """, ["same frame is used for every row"]),
    "pose reprojected without dist": ("lab10.ex6", """
        _right = estimate_pose
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            rvec, tvec, _ = _right(image, pattern_size, square_size, K, dist)
            if not np.isfinite(rvec).all():
                return rvec, tvec, np.zeros((0, 2))
            reprojected, _ = cv2.projectPoints(_object_points(pattern_size, square_size), rvec, tvec,
                                               np.asarray(K, float), None)
            return rvec, tvec, reprojected.reshape(-1, 2)
        """, ["projected without dist"]),
    "DLT normalised but not denormalised": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.asarray(points3d, float); x = np.asarray(points2d, float)
            T3, T2 = _normalising_transform(X), _normalising_transform(x)
            Xn = np.column_stack([X, np.ones(len(X))]) @ T3.T
            xn = (np.column_stack([x, np.ones(len(x))]) @ T2.T)[:, :2]
            rows = []
            for Xi, (u, v) in zip(Xn, xn):
                rows.append(np.concatenate([Xi, np.zeros(4), -u * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -v * Xi]))
            return np.linalg.svd(np.array(rows))[2][-1].reshape(3, 4)
        """, ["normalisation is not undone"]),
    "decomposition by QR instead of RQ": ("lab10.ex5", """
        def decompose_camera_matrix(P):
            P = np.asarray(P, dtype=np.float64)
            if np.linalg.det(P[:, :3]) < 0:
                P = -P
            R, K = np.linalg.qr(P[:, :3])
            D = np.diag(np.sign(np.diag(K)))
            K, R = D @ K, R @ D
            return K / K[2, 2], R, np.linalg.solve(K, P[:, 3])
        """, ["qr decomposition"]),
    "undistort with K transposed": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            return cv2.undistort(image, np.asarray(K, np.float64).T, np.asarray(dist, np.float64))
        """, ["k is transposed"]),
    "dolly moves X and Y too": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            fs = f0 * distances / z0
            return fs, np.stack([perspective_project(X + (d - z0), f) for f, d in zip(fs, distances)])
        """, ["added to x and y too"]),
    "tracking rows not flattened": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            return np.array([np.array(estimate_pose(f, pattern_size, square_size, K, dist)[:2]) for f in frames])
        """, ["not flattened"]),
    "perspective divided by the distance": ("lab10.ex1", """
        def perspective_project(points, f):
            X, single = _points(points)
            x = f * X[:, :2] / np.linalg.norm(X, axis=1, keepdims=True)
            return x[0] if single else x
        """, ["distance |x|"]),
    "DLT takes a column of Vt": ("lab10.ex4", """
        def camera_matrix_dlt(points3d, points2d):
            X = np.column_stack([points3d, np.ones(len(points3d))])
            rows = []
            for Xi, (u, v) in zip(X, points2d):
                rows.append(np.concatenate([Xi, np.zeros(4), -u * Xi]))
                rows.append(np.concatenate([np.zeros(4), Xi, -v * Xi]))
            return np.linalg.svd(np.array(rows))[2][:, -1].reshape(3, 4)
        """, ["last column of vt"]),
    "tracking marks missing frames with -1": ("lab10.ext3", """
        _right = track_pose
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            rows = _right(frames, pattern_size, square_size, K, dist)
            rows[~np.isfinite(rows)] = -1
            return rows
        """, ["should be nan"]),
    "decomposition with t of the wrong sign": ("lab10.ex5", """
        _right = decompose_camera_matrix
        def decompose_camera_matrix(P):
            K, R, t = _right(P)
            return K, R, -t
        """, ["t has the wrong sign"]),
    "pose grid divided by square_size": ("lab10.ex6", """
        def _object_points(pattern_size, square_size):
            cols, rows = pattern_size
            objp = np.zeros((cols * rows, 3), np.float64)
            objp[:, :2] = np.mgrid[0:cols, 0:rows].T.reshape(-1, 2) / square_size
            return objp
        """, ["not in the units of square_size"]),
    # ---------------------------------------------------------------- the API's conventions
    # k points of k coordinates taken for one point, or for points given as columns
    **one_point_by_length("perspective_project", "lab10.ex1", "points, f", "points", "len(points) == 3"),
    **one_point_by_length("weak_perspective_project", "lab10.ex2", "points, f, z_avg=None", "points", "points.shape[0] == 3"),
    **one_point_by_length("orthographic_project", "lab10.ex3", "points", "points", "len(points) == 3"),
    "perspective_project squeezes its answer": ("lab10.ex1", """
        _reference_perspective = perspective_project
        def perspective_project(points, f):
            return np.squeeze(_reference_perspective(points, f))
        """, ["one-row array", "(1, 2)"]),
    "weak_perspective_project squeezes its answer": ("lab10.ex2", """
        _reference_weak = weak_perspective_project
        def weak_perspective_project(points, f, z_avg=None):
            return np.squeeze(_reference_weak(points, f, z_avg))
        """, ["one-row array", "(1, 2)"]),
    "orthographic_project squeezes its answer": ("lab10.ex3", """
        _reference_orthographic = orthographic_project
        def orthographic_project(points):
            return np.squeeze(_reference_orthographic(points))
        """, ["one-row array", "(1, 2)"]),
    # ---- whole numbers given as integers
    "perspective_project answers integer points in integers": ("lab10.ex1", """
        _reference_perspective_int = perspective_project
        def perspective_project(points, f):
            projected = np.zeros_like(np.asarray(points)[..., :2])
            projected[...] = _reference_perspective_int(points, f)
            return projected
        """, ["your answer is an integer array", "`projected = np.zeros_like(np.asarray(points)[..., :2])`"]),
    "weak_perspective_project answers integer points in integers": ("lab10.ex2", """
        _reference_weak_int = weak_perspective_project
        def weak_perspective_project(points, f, z_avg=None):
            pts = np.asarray(points)
            projected = pts[..., :2].copy()
            projected[...] = _reference_weak_int(points, f, z_avg)
            return projected
        """, ["your answer is an integer array", "`projected = pts[..., :2].copy()`"]),
    "dolly_zoom answers integer points in integers": ("lab10.ext2", """
        _reference_dolly = dolly_zoom
        def dolly_zoom(points, f0, z0, distances):
            focal_lengths, projections = _reference_dolly(points, f0, z0, distances)
            views = np.zeros(projections.shape, dtype=np.asarray(points).dtype)
            views[...] = projections
            return focal_lengths, views
        """, ["your answer is an integer array", "dtype=np.asarray(points).dtype"]),
    # ---- black fill where the source lies outside the image
    "undistort_image fills with the edge pixels": ("lab10.ext1", """
        def undistort_image(image, K, dist):
            K = np.asarray(K, np.float64)
            h, w = image.shape[:2]
            map_x, map_y = cv2.initUndistortRectifyMap(K, np.asarray(dist, np.float64), None, K, (w, h), cv2.CV_32FC1)
            return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
        """, ["are not black", "your code uses cv2.BORDER_REPLICATE"]),
    # the blind set 1205e's 10/10: P negated by the sign of one entry, where det(P[:, :3]) decides
    "decompose_camera_matrix negating P by the sign of P[2, 2]": ("lab10.ex5", reference_def_with(
        "lab10_camera2", "decompose_camera_matrix", "if np.linalg.det(P[:, :3]) < 0:", "if P[2, 2] < 0:"),
        ["your code tests `P[2, 2] < 0`"]),

    # (blind set 2026-12-06c)
    "weak perspective dividing y by the points' mean depth, not the z_avg given": ("lab10.ex2", """
        def weak_perspective_project(points, f, z_avg=None):
            pts = np.asarray(points, dtype=np.float64)
            single = pts.ndim == 1
            pts = np.atleast_2d(pts)
            X, Y, Z = pts[:, 0], pts[:, 1], pts[:, 2]
            z_mean = Z.mean()
            if z_avg is None:
                z_avg = z_mean
            z_avg = float(z_avg)
            x = f * X / z_avg
            y = f * Y / z_mean
            out = np.column_stack([x, y])
            return out[0] if single else out
        """, ["changing `f * y / z_mean` to `f * y / z_avg`"]),

    "frames numbered from 1 where their row index belongs (enumerate(frames, start=1))": ("lab10.ext3", """
        def track_pose(frames, pattern_size, square_size, K, dist=None):
            poses = np.full((len(frames), 6), np.nan)
            for i, frame in enumerate(frames, start=1):
                rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
                poses[i] = np.concatenate([rvec, tvec])
            return poses
        """, ["changing `enumerate(frames, start=1)` to `enumerate(frames)`"]),
    # (blind set 2026-12-06e: the pose from corners cut to whole pixels, its own projection returned)
    "estimate_pose giving solvePnP the refined corners cut to whole pixels": ("lab10.ex6", reference_def_with(
        "lab10_camera2", "estimate_pose", "_, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)",
        "_, rvec, tvec = cv2.solvePnP(objp, corners.astype(np.int32).astype(np.float64), K, dist)"),
        ["the corners returned are your pose's own projection", "look at what cv2.solvepnp is given"]),
}


# every exercise has at least five cases (ext1's undistortion since its new camera matrix and channels)
FEWER_MISTAKES: dict = {}


# Conventions the API leaves open: advice (0 points), never a lost point.
ADVICE = {
    # the dolly's formula written inline, with no NaN where the move puts a point behind the camera
    "dolly_zoom projecting points moved behind the camera": ("lab10.ext2", """
        def dolly_zoom(points, f0, z0, distances):
            X, _ = _points(points)
            distances = np.asarray(distances, dtype=np.float64).ravel()
            fs = f0 * distances / z0
            frames = []
            for f, d in zip(fs, distances):
                Z = X[:, 2] + (d - z0)
                with np.errstate(divide="ignore", invalid="ignore"):
                    frames.append(f * X[:, :2] / Z[:, None])
            return fs, np.stack(frames)
        """, ["frame at d = 2", "nan", "no points"]),
}
