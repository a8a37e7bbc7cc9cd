"""Lab 11's mistakes table (two-view geometry): realistic wrong implementations, each the
reference solution with one function redefined, the exercise it must lose points in, and
the words its diagnosis must contain (read by ``autograder verify``; see
:mod:`autograder.labs.mistakes`)."""

from . import columns_by_first_axis, reference_def_with

# the start of the lab sheet's two-view pipeline, written out: SIFT, Lowe's test, F by RANSAC
_MATCHED = """
        def two_view_reconstruction(img1, img2, K):
            grey1 = cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY) if img1.ndim == 3 else img1
            grey2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY) if img2.ndim == 3 else img2
            sift = cv2.SIFT_create()
            kp1, des1 = sift.detectAndCompute(grey1, None)
            kp2, des2 = sift.detectAndCompute(grey2, None)
            pairs = cv2.BFMatcher(cv2.NORM_L2).knnMatch(des1, des2, k=2)
            good = [m for m, n in (p for p in pairs if len(p) == 2) if m.distance < 0.75 * n.distance]
            pts1 = np.float64([kp1[m.queryIdx].pt for m in good])
            pts2 = np.float64([kp2[m.trainIdx].pt for m in good])
            F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
"""

# the lab sheet's pipeline, written out (SIFT, Lowe's test, F by RANSAC, pose, triangulation), with the points
# given to cv2.recoverPose (POSE_POINTS) and to triangulate (TRIANGULATED) left to each case
_PIPELINE = _MATCHED + """            pts1, pts2 = pts1[mask.ravel() == 1], pts2[mask.ravel() == 1]
            K = np.asarray(K, np.float64)
            _, R, t, _ = cv2.recoverPose(K.T @ F @ K, POSE_POINTS, K)
            P1, P2 = K @ np.eye(3, 4), K @ np.hstack([R, t.reshape(3, 1)])
            points3d = triangulate(P1, P2, TRIANGULATED)
            in_front = (points3d[:, 2] > 0) & ((points3d @ R.T + t.reshape(3))[:, 2] > 0)
            return F, pts1[in_front], pts2[in_front], points3d[in_front]
        """

# a two-view pipeline whose cameras lack K ([R | t] on pixel coordinates); IN_FRONT: what it keeps
_WITHOUT_K = _MATCHED + """            inliers = mask.ravel().astype(bool)
            pts1, pts2 = pts1[inliers], pts2[inliers]
            K = np.asarray(K, np.float64)
            E = K.T @ F @ K
            _, R, t, pose_mask = cv2.recoverPose(E, pts1, pts2, K)
            P1 = np.hstack([np.eye(3), np.zeros((3, 1))])
            P2 = np.hstack([R, t])
            points3d = triangulate(P1, P2, pts1, pts2)
            in_front = IN_FRONT
            return F, pts1[in_front], pts2[in_front], points3d[in_front]
"""

MISTAKES = {
    # the blind set 1206a's 11/01: a (4, N, 4) stack reshaped to (N, 4, 4) mixes the points' equations
    "triangulate regrouping the equations by reshape where a transpose belongs": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1 = np.asarray(P1, dtype=np.float64)
            P2 = np.asarray(P2, dtype=np.float64)
            x1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
            x2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
            n = len(x1)
            # the four equations for all points at once, one (N, 4) block per equation
            rows = np.array([np.outer(x1[:, 0], P1[2]) - P1[0],
                             np.outer(x1[:, 1], P1[2]) - P1[1],
                             np.outer(x2[:, 0], P2[2]) - P2[0],
                             np.outer(x2[:, 1], P2[2]) - P2[1]])        # (4, N, 4)
            # one 4x4 system per point
            A = rows.reshape(n, 4, 4)                                        # (N, 4, 4)
            _, _, Vt = np.linalg.svd(A)
            X = Vt[:, -1, :]                                          # smallest singular value
            return X[:, :3] / X[:, 3:]
        """, ['transpose(1, 0, 2)']),
    # the blind set 1206a's 11/02: np.unique sorts the points and drops repeated ones
    "epipolar_lines looping over the unique points (sorted, repeats dropped)": ("lab11.ex2", """
        def epipolar_lines(F, pts1):
            F = np.asarray(F, dtype=np.float64)
            points = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
            lines = []
            for x, y in np.unique(points, axis=0):
                a, b, c = F @ np.array([x, y, 1.0])        # l' = F x
                norm = np.hypot(a, b)
                lines.append([a / norm, b / norm, c / norm])
            return np.array(lines, dtype=np.float64).reshape(-1, 3)
        """, ['to `points`']),
    # the blind set 1206a's 11/03: a 44-degree line crossing only the top and bottom of a wide image is never drawn
    "draw_epipolar_lines skipping a line whose ends on its own borders are both outside": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            out = np.array(image, dtype=np.uint8, copy=True)
            h, w = out.shape[:2]
            for i, (a, b, c) in enumerate(np.asarray(lines, dtype=np.float64).reshape(-1, 3)):
                if abs(b) >= abs(a):
                    # closer to horizontal: end points on the left and right borders
                    y_left = -c / b
                    y_right = -(c + a * (w - 1)) / b
                    start, end = (0.0, y_left), (w - 1.0, y_right)
                    if not (0 <= y_left <= h - 1 or 0 <= y_right <= h - 1):
                        continue
                else:
                    # closer to vertical: end points on the top and bottom borders
                    x_top = -c / a
                    x_bottom = -(c + b * (h - 1)) / a
                    start, end = (x_top, 0.0), (x_bottom, h - 1.0)
                    if not (0 <= x_top <= w - 1 or 0 <= x_bottom <= w - 1):
                        continue
                ok, p, q = cv2.clipLine((0, 0, w, h), _to_int(start, w, h), _to_int(end, w, h))
                if not ok:
                    continue                         # the line does not cross the image
                colour = _PALETTE[i % len(_PALETTE)] if out.ndim == 3 else 255
                cv2.line(out, p, q, colour, 1, cv2.LINE_8)
            return out
        """, ['leave the image through its top or bottom border']),
    # the blind set 1205h's 11/01: np.kron of the two whole point arrays: a row for every pair of points (N^2 rows)
    "fundamental_8point building A with np.kron of the whole point arrays": ("lab11.ex4", reference_def_with(
        "lab11_two_view", "_eight_point_core", "A = (x2[:, :, None] * x1[:, None, :]).reshape(len(x1), 9)",
        "A = np.kron(x2, x1)"), ["changing `np.kron(x2, x1)` to `(x2[:, :, None] * x1[:, None, :]).reshape(len(x2), -1)`"]),
    # the blind set 1205h's 11/03: a line drawn between the first two border crossings found -- a line through a
    # corner meets two borders there, and is drawn as one pixel
    "draw_epipolar_lines joining the first two border crossings": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            out = np.array(image, dtype=np.uint8, copy=True)
            h, w = out.shape[:2]
            for i, (a, b, c) in enumerate(np.asarray(lines, dtype=np.float64).reshape(-1, 3)):
                ends = []
                if b != 0:
                    for x in (0.0, w - 1.0):
                        y = -(a * x + c) / b
                        if 0.0 <= y <= h - 1.0:
                            ends.append((x, y))
                if a != 0:
                    for y in (0.0, h - 1.0):
                        x = -(b * y + c) / a
                        if 0.0 <= x <= w - 1.0:
                            ends.append((x, y))
                if len(ends) < 2:
                    continue
                (x0, y0), (x1, y1) = ends[0], ends[1]
                colour = _PALETTE[i % len(_PALETTE)] if out.ndim == 3 else 255
                cv2.line(out, (int(round(x0)), int(round(y0))), (int(round(x1)), int(round(y1))), colour, 1, cv2.LINE_8)
            return out
        """, ["changing `ends[0], ends[1]` to `ends[0], ends[-1]`"]),
    # the blind set 1205b's 11/06: image 2's conversion tested on image 1's channels (the line above copied)
    "epipoles from a basis of the range (scipy.linalg.orth) where the null space belongs": ("lab11.ex5", """
        def epipoles(F):
            import scipy.linalg
            F = np.asarray(F, dtype=np.float64)
            return scipy.linalg.orth(F)[:, -1], scipy.linalg.orth(F.T)[:, -1]
        """, ["it lies in the column space of F", "a vector of the range was taken"]),
    "two_view_reconstruction converting img2 by img1's number of channels": ("lab11.ex6", reference_def_with(
        "lab11_two_view", "two_view_reconstruction",
        "grey2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY) if img2.ndim == 3 else img2",
        "grey2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY) if img1.ndim == 3 else img2"),
        ["BGR img1, grey img2", "img2.ndim == 3"]),
    # the blind set 1206i's 11/06: F's mask never applied, the matches returned whole (RANSAC's outliers kept)
    "two_view_reconstruction keeping the outliers of F": ("lab11.ex6", reference_def_with(
        "lab11_two_view", "two_view_reconstruction", "pts1, pts2 = pts1[inliers], pts2[inliers]", "pass"),
        ["lie more than 5 px from the epipolar lines of the F returned", "outliers"]),
    # the blind set 1205b's 11/02: a steep line's end points each given the other border's row
    "draw_epipolar_lines pairing a steep line's end points with the wrong rows": ("lab11.ex2", reference_def_with(
        "lab11_two_view", "draw_epipolar_lines", "p, q = (-c / a, 0.0), (-(c + b * (height - 1)) / a, height - 1.0)",
        "p, q = (-c / a, height - 1.0), (-(c + b * (height - 1)) / a, 0.0)"),
        ["changing `((-c / a, height - 1.0), (-(c + b * (height - 1)) / a, 0.0))`"]),
    # the blind set 1204d's 11/05: V made a proper rotation by negating a column of Vt, not its last row (and
    # not told as the 8-point core's F negated: a rank-2 matrix is the same up to sign)
    "essential_8point negating a column of Vt for a proper V": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
            E = _eight_point_core(x1, x2)
            U, _, Vt = np.linalg.svd(E)
            if np.linalg.det(U) < 0:
                U[:, -1] *= -1
            if np.linalg.det(Vt) < 0:
                Vt[:, -1] *= -1
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["`Vt[-1, :] *= -1`"]),
    # the blind set 1204d's 11/02: the line's normal angle from arctan of a ratio, its quadrant lost
    "epipolar lines rebuilt from arctan(b / a)": ("lab11.ex2", """
        def epipolar_lines(F, pts1):
            F = np.asarray(F, dtype=np.float64)
            pts = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
            raw = (F @ np.column_stack([pts, np.ones(len(pts))]).T).T
            a, b, c = raw[:, 0], raw[:, 1], raw[:, 2]
            theta = np.arctan(b / a)
            return np.column_stack([np.cos(theta), np.sin(theta), c / np.hypot(a, b)])
        """, ["`np.arctan2(b, a)`"]),
    # the blind set 1204d's 11/07: the null vectors' third entries replaced by 1
    "epipoles made homogeneous by replacing the third entry": ("lab11.ex5", """
        def epipoles(F):
            U, _, Vt = np.linalg.svd(np.asarray(F, np.float64))
            e1, e2 = Vt[-1], U[:, -1]
            return np.append(e1[:2], 1.0), np.append(e2[:2], 1.0)
        """, ["`np.append(e1[:2], 1.0)` to `e1`"]),
    # ---------------------------------------------------------------- ex1
    "triangulation with x where y belongs in the second row": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            pts1 = np.asarray(pts1, float).reshape(-1, 2); pts2 = np.asarray(pts2, float).reshape(-1, 2)
            A = np.stack([pts1[:, 0:1] * P1[2] - P1[0], pts1[:, 0:1] * P1[2] - P1[1],
                          pts2[:, 0:1] * P2[2] - P2[0], pts2[:, 0:1] * P2[2] - P2[1]], axis=1)
            X = np.linalg.svd(A)[2][:, -1, :]
            return X[:, :3] / X[:, 3:4]
        """, ["x is used where y belongs in each view's second row"]),
    "triangulation with x where y belongs in the second view's row (a loop, copy-pasted)": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            out = []
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float).reshape(-1, 2), np.asarray(pts2, float).reshape(-1, 2)):
                A = np.array([x1 * P1[2] - P1[0], y1 * P1[2] - P1[1], x2 * P2[2] - P2[0], x2 * P2[2] - P2[1]])
                X = np.linalg.svd(A)[2][-1]
                out.append(X[:3] / X[3])
            return np.array(out)
        """, ["x is used where y belongs in the second view's second row"]),
    "triangulation without dividing by w": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            return np.linalg.svd(A)[2][:, -1, :3]
        """, ["not divided by w"]),
    "triangulation with each P scaled so that P[2, 3] = 1": ("lab11.ex1", """
        _triangulate = triangulate
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            return _triangulate(P1 / P1[2, 3], P2 / P2[2, 3], pts1, pts2)
        """, ["camera 1 = k1 [i | 0]"]),
    "triangulation from one view only": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1 = np.asarray(P1, float)
            pts1 = np.asarray(pts1, float)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1]], axis=1)
            X = np.linalg.svd(A)[2][:, -1, :]
            return X[:, :3] / X[:, 3:]
        """, ["only the first view"]),
    "triangulation writing image 1's rows for the camera [I | 0]": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            P1 = np.asarray(P1, float)
            out = []
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                A = np.array([[-1.0, 0.0, x1, 0.0], [0.0, -1.0, y1, 0.0], x2 * P2[2] - P2[0], y2 * P2[2] - P2[1]])
                X = np.linalg.svd(A)[2][-1]
                out.append(X[:3] / X[3])
            return np.array(out).reshape(-1, 3)
        """, ["never uses its parameter `P1`"]),
    "triangulation with the cameras swapped": ("lab11.ex1", """
        _triangulate = triangulate
        def triangulate(P1, P2, pts1, pts2):
            return _triangulate(P2, P1, pts1, pts2)
        """, ["swapped"]),
    "triangulation with OpenCV": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            X = cv2.triangulatePoints(np.float64(P1), np.float64(P2), np.float64(pts1).T, np.float64(pts2).T)
            return (X[:3] / X[3]).T
        """, ["cv2.triangulatePoints", "yourself"]),
    "triangulation with x and y swapped in the rows": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            A = np.stack([pts1[:, 1:] * P1[2] - P1[0], pts1[:, :1] * P1[2] - P1[1],
                          pts2[:, 1:] * P2[2] - P2[0], pts2[:, :1] * P2[2] - P2[1]], axis=1)
            X = np.linalg.svd(A)[2][:, -1]
            return X[:, :3] / X[:, 3:]
        """, ["x and y are swapped"]),
    "triangulation with a sign error in the rows (x p3 + p1)": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            A = np.stack([pts1[:, :1] * P1[2] + P1[0], pts1[:, 1:] * P1[2] + P1[1],
                          pts2[:, :1] * P2[2] + P2[0], pts2[:, 1:] * P2[2] + P2[1]], axis=1)
            X = np.linalg.svd(A)[2][:, -1]
            return X[:, :3] / X[:, 3:]
        """, ["a sign error in the rows"]),
    "triangulation with P1 used for both views": ("lab11.ex1", """
        _triangulate = triangulate
        def triangulate(P1, P2, pts1, pts2):
            return _triangulate(P1, P1, pts1, pts2)
        """, ["p1 is used for both views"]),
    "triangulation whose second row uses p1 again": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[0],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[0]], axis=1)
            X = np.linalg.svd(A)[2][:, -1]
            return X[:, :3] / X[:, 3:]
        """, ["second row of each view uses p1 again"]),
    "triangulation with the largest singular vector": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            X = np.linalg.svd(A)[2][:, 0]
            return X[:, :3] / X[:, 3:]
        """, ["largest singular value"]),
    "inhomogeneous triangulation with the right-hand side's sign flipped": ("lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            out = np.empty((len(pts1), 3))
            for i, ((x1, y1), (x2, y2)) in enumerate(zip(np.asarray(pts1, float), np.asarray(pts2, float))):
                A = np.array([x1 * P1[2] - P1[0], y1 * P1[2] - P1[1], x2 * P2[2] - P2[0], y2 * P2[2] - P2[1]])
                out[i] = np.linalg.lstsq(A[:, :3], A[:, 3], rcond=None)[0]
            return out
        """, ["every point is the true one negated"]),
    # the blind set 1203b's 11/04: K2^T F K1 made rank 2 on the way out, where the API asks for K2^T F K1 itself
    # the blind set 1204d's 11/06: the singular values sorted (ascending) before the first is zeroed, their
    # vectors left in numpy's order: mended only by taking the sort out and zeroing the last together
    "rank 2 by the singular values sorted without their vectors": ("lab11.ex4", reference_def_with(
        "lab11_two_view", "fundamental_8point", "Fn = U @ np.diag([s[0], s[1], 0.0]) @ Vt",
        "s = np.sort(s)\ns[0] = 0.0\nFn = U @ np.diag(s) @ Vt"),
        ["removing `s = np.sort(s)`", "changing `s[0] = 0.0` to `s[2] = 0.0`"]),
    # the blind set 1204e's 11/06: the conditioning matrix made from a literal of whole numbers, its scale cut to 0
    "fundamental_8point conditioning into an integer matrix": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1 = np.asarray(pts1, dtype=np.float64).reshape(-1, 2)
            pts2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
            def conditioning(pts):
                centre = pts.mean(axis=0)
                s = np.sqrt(2.0) / np.mean(np.linalg.norm(pts - centre, axis=1))
                T = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1]])
                T[0, 0] = T[1, 1] = s
                T[:2, 2] = -s * centre
                return T
            T1, T2 = conditioning(pts1), conditioning(pts2)
            x1 = np.column_stack([pts1, np.ones(len(pts1))]) @ T1.T
            x2 = np.column_stack([pts2, np.ones(len(pts2))]) @ T2.T
            A = np.einsum("ni,nj->nij", x2, x1).reshape(-1, 9)
            U, s, Vt = np.linalg.svd(np.linalg.svd(A)[2][-1].reshape(3, 3))
            F = T2.T @ U @ np.diag([s[0], s[1], 0.0]) @ Vt @ T1
            return F / np.linalg.norm(F)
        """, ["makes T an integer array (from a literal of whole numbers, no dtype)"]),
    # the blind set 1204e's 11/03: a grey image's lines drawn with 1.0 (a [0, 1] image's white), nearly black
    "epipolar lines drawn on a grey image with the colour 1.0": ("lab11.ex2", reference_def_with(
        "lab11_two_view", "draw_epipolar_lines", "colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255",
        "colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 1.0"), ["else 1.0` to `", "else 255`"]),
    # the blind set 1204e's 11/05: normalised coordinates with y pointing up (a lecture's camera frame)
    "essential_8point with y pointing up in both views": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            flip = np.diag([1.0, -1.0, 1.0])
            x1 = _homogeneous(pts1) @ (flip @ np.linalg.inv(K1)).T
            x2 = _homogeneous(pts2) @ (flip @ np.linalg.inv(K2)).T
            U, _, Vt = np.linalg.svd(_eight_point_core(x1, x2))
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["`flip @ np.linalg.inv(K1)` to `np.linalg.inv(K1)`", "`flip @ np.linalg.inv(K2)` to `np.linalg.inv(K2)`"]),
    # the blind set 1204e's 11/02: the F given made rank 2 before its lines are taken (the API's lines are F x)
    "epipolar lines of F made rank 2 first": ("lab11.ex2", reference_def_with(
        "lab11_two_view", "epipolar_lines", "lines = _homogeneous(pts1) @ np.asarray(F, np.float64).T",
        "U, s, Vt = np.linalg.svd(np.asarray(F, np.float64))\nF = U @ np.diag([s[0], s[1], 0.0]) @ Vt\n"
        "lines = _homogeneous(pts1) @ F.T"), ["removing `F = U @ np.diag([s[0], s[1], 0.0]) @ Vt`"]),
    "essential_from_fundamental making E rank 2": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            E = np.asarray(K2, np.float64).T @ np.asarray(F, np.float64) @ np.asarray(K1, np.float64)
            U, s, Vt = np.linalg.svd(E)
            return U @ np.diag([s[0], s[1], 0.0]) @ Vt
        """, ["changing `U @ np.diag([s[0], s[1], 0.0]) @ Vt` to `E`"]),
    "essential_from_fundamental refusing an F whose rank is not 2": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            F = np.asarray(F, np.float64)
            if np.linalg.matrix_rank(F) != 2:
                raise ValueError("F must have rank 2")
            return np.asarray(K2, np.float64).T @ F @ np.asarray(K1, np.float64)
        """, ["to `np.linalg.matrix_rank(F) < 2`"]),   # (the test of one rank made the bound it meant: 1205g's 08/03)
    # K read as its four usual numbers: right for the synthetic K's of fx = fy and no skew only
    "essential_from_fundamental with K rebuilt from fx, fy, cx, cy": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            def pinhole(K):
                fx, fy, cx, cy = K[0, 0], K[1, 1], K[0, 2], K[1, 2]
                return np.array([[fx, 0.0, cx], [0.0, fy, cy], [0.0, 0.0, 1.0]])
            return pinhole(K2).T @ np.asarray(F, np.float64) @ pinhole(K1)
        """, ["without its skew entry K[0, 1]"]),
    "essential_from_fundamental with square pixels assumed": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            K1, K2 = np.array(K1, np.float64), np.array(K2, np.float64)
            K1[1, 1], K2[1, 1] = K1[0, 0], K2[0, 0]
            return K2.T @ np.asarray(F, np.float64) @ K1
        """, ["fx is used for fy"]),
    "essential_8point rebuilt without U": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
            U, S, Vt = np.linalg.svd(_eight_point_core(x1, x2))
            return np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["unpacks `u` from", "and never uses it"]),
    "essential_8point handing homogeneous points to fundamental_8point": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            n1 = np.column_stack([np.asarray(pts1, np.float64), np.ones(len(pts1))]) @ np.linalg.inv(K1).T
            n2 = np.column_stack([np.asarray(pts2, np.float64), np.ones(len(pts2))]) @ np.linalg.inv(K2).T
            U, _, Vt = np.linalg.svd(fundamental_8point(n1, n2))
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["to `fundamental_8point(n1[:, :2], n2[:, :2])`"]),
    "E given (1, 1, 0) before its conditioning is undone": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
            T1, T2 = np.diag([2.0, 2.0, 1.0]), np.diag([3.0, 3.0, 1.0])
            U, _, Vt = np.linalg.svd(_eight_point_core(x1 @ T1.T, x2 @ T2.T))
            En = U @ np.diag([1.0, 1.0, 0.0]) @ Vt
            return T2.T @ En @ T1
        """, ["a step after it changes the singular values again"]),
    # ---------------------------------------------------------------- ex2
    # the blind set 1204b's 11/07: the epipoles scaled as epipolar lines are, by the length of (x, y)
    "epipoles scaled by the length of their first two entries": ("lab11.ex5", """
        def epipoles(F):
            U, _, Vt = np.linalg.svd(np.asarray(F, np.float64))
            e1, e2 = Vt[-1], U[:, -1]
            return e1 / np.linalg.norm(e1[:2]), e2 / np.linalg.norm(e2[:2])
        """, ["is not finite", "changing `e1 / np.linalg.norm(e1[:2])` to `e1`"]),
    # the blind set 1204b's 11/03: an own rasteriser whose negative rows and columns wrap round
    "epipolar lines rasterised with negative indices wrapping round": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            out = image.copy()
            height, width = out.shape[:2]
            for k, (a, b, c) in enumerate(np.asarray(lines, np.float64)):
                colour = 255 if out.ndim == 2 else (0, 0, 255) if k % 2 == 0 else (0, 255, 0)
                if abs(b) >= abs(a):
                    xs = np.arange(width)
                    ys = np.round(-(a * xs + c) / b).astype(int)
                    keep = ys <= height - 1
                else:
                    ys = np.arange(height)
                    xs = np.round(-(b * ys + c) / a).astype(int)
                    keep = xs <= width - 1
                out[ys[keep], xs[keep]] = colour
            return out
        """, ["negative row or column index counts from the end"]),
    "epipolar lines drawn on a grey copy of a colour image": ("lab11.ex2", """
        _draw_lines_right = draw_epipolar_lines
        def draw_epipolar_lines(image, lines):
            if image.ndim == 3:
                backdrop = cv2.cvtColor(cv2.cvtColor(image, cv2.COLOR_BGR2GRAY), cv2.COLOR_GRAY2BGR)
                return _draw_lines_right(backdrop, lines)
            return _draw_lines_right(image, lines)
        """, ["the image converted to grey", "drawn on a grey copy"]),
    "epipolar lines from OpenCV's (N, 1, 3) homogeneous points": ("lab11.ex2", """
        def epipolar_lines(F, pts1):
            x1 = cv2.convertPointsToHomogeneous(np.float64(pts1))
            lines = x1 @ np.asarray(F, np.float64).T
            scale = np.sqrt((lines[:, :2] ** 2).sum(axis=1, keepdims=True))
            return (lines / scale).reshape(-1, 3)
        """, ["changing `cv2.convertPointsToHomogeneous(np.float64(pts1))` to "
              "`cv2.convertPointsToHomogeneous(np.float64(pts1))[:, 0]`"]),
    # the blind set 1201d's 11/03: a vertical line (b = 0) skipped to avoid the division
    "epipolar lines skipping the vertical ones": ("lab11.ex2", """
        _draw_epipolar_lines = draw_epipolar_lines
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, dtype=np.uint8, copy=True)
            for a, b, c in np.asarray(lines, np.float64).reshape(-1, 3):
                if abs(b) < 1e-12:
                    continue
                canvas = _draw_epipolar_lines(canvas, np.array([[a, b, c]]))
            return canvas
        """, ["the lines missing are the vertical ones (b = 0)", "skips every line with b = 0"]),
    "epipolar lines with F transposed": ("lab11.ex2", """
        def epipolar_lines(F, pts1):
            lines = _homogeneous(pts1) @ np.asarray(F, float)
            return lines / np.linalg.norm(lines[:, :2], axis=1, keepdims=True)
        """, ["transposed"]),
    "epipolar lines joining the epipole e2 and the point x1": ("lab11.ex2", """
        def epipolar_lines(F, pts1):
            e2 = np.linalg.svd(np.asarray(F, np.float64).T)[2][-1]
            lines = np.cross(e2, _homogeneous(pts1))
            return lines / np.linalg.norm(lines[:, :2], axis=1, keepdims=True)
        """, ["passes through image 2's epipole and through the point x1 itself"]),
    "epipolar lines with c = 1 (the third coordinate dropped)": ("lab11.ex2", """
        _right_lines = epipolar_lines
        def epipolar_lines(F, pts1):
            lines = np.array(_right_lines(F, pts1), float)
            lines[:, 2] = 1.0
            return lines
        """, ["is wrong for every line, in c only.", "\nit returned"]),
    "epipolar lines squeezed (one point gives a (3,) line)": ("lab11.ex2", """
        def epipolar_lines(F, pts1):
            x = np.column_stack([np.asarray(pts1, float), np.ones(len(pts1))])
            lines = np.squeeze(np.asarray(F, float) @ x.T).T
            return lines / np.linalg.norm(lines[..., :2], axis=-1, keepdims=True)
        """, ["n=1", "shape (3,)"]),
    "epipolar lines not normalised": ("lab11.ex2", """
        def epipolar_lines(F, pts1):
            return _homogeneous(pts1) @ np.asarray(F, float).T
        """, ["a^2 + b^2 = 1"]),
    "epipolar lines scaled to unit length over a, b and c": ("lab11.ex2", """
        def epipolar_lines(F, pts1):
            lines = _homogeneous(pts1) @ np.asarray(F, float).T
            return lines / np.linalg.norm(lines, axis=1, keepdims=True)
        """, ["over all three entries"]),
    "draw_epipolar_lines drawing the palette's colours on a grey image too": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, dtype=np.uint8, copy=True)
            height, width = canvas.shape[:2]
            for i, (a, b, c) in enumerate(np.asarray(lines, np.float64).reshape(-1, 3)):
                if abs(b) >= abs(a):
                    p, q = (0.0, -c / b), (width - 1.0, -(c + a * (width - 1)) / b)
                else:
                    p, q = (-c / a, 0.0), (-(c + b * (height - 1)) / a, height - 1.0)
                inside, p, q = cv2.clipLine((0, 0, width, height), _to_int(p, width, height), _to_int(q, width, height))
                if inside:
                    cv2.line(canvas, p, q, _PALETTE[i % len(_PALETTE)], 1, cv2.LINE_8)
            return canvas
        """, ["draws them in black", "first value of a colour"]),
    "draw short segments": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image.copy()
            w = canvas.shape[1]
            for a, b, c in np.asarray(lines, float):
                if abs(b) < 1e-9:
                    continue
                x0, x1 = w // 3, 2 * w // 3
                cv2.line(canvas, (x0, int(round(-(c + a * x0) / b))), (x1, int(round(-(c + a * x1) / b))),
                         (0, 0, 255), 1)
            return canvas
        """, ["stop short"]),
    "draw_epipolar_lines drawing on a new black image (np.zeros_like)": ("lab11.ex2", """
        _draw = draw_epipolar_lines
        def draw_epipolar_lines(image, lines):
            return _draw(np.zeros_like(image), lines)
        """, ["new blank image"]),
    "draw_epipolar_lines returning BGR for a grey input (the tutorial's way)": ("lab11.ex2", """
        _draw = draw_epipolar_lines
        def draw_epipolar_lines(image, lines):
            if image.ndim == 2:
                image = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
            return _draw(image, lines)
        """, ["channels are not kept", "grey in, grey out"]),
    "draw each line between the left and right borders, y clipped into the image": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, dtype=np.uint8, copy=True)
            height, width = canvas.shape[:2]
            for i, (a, b, c) in enumerate(np.asarray(lines, np.float64).reshape(-1, 3)):
                b = b if abs(b) > 1e-9 else 1e-9
                y0 = int(np.clip(-c / b, 0, height - 1))
                y1 = int(np.clip(-(c + a * (width - 1)) / b, 0, height - 1))
                colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255
                cv2.line(canvas, (0, y0), (width - 1, y1), colour, 1)
            return canvas
        """, ["leave the image through its top or bottom border",
              "computed from its x only, never its x from y"]),
    "draw each line between the left and right borders, vertical lines skipped": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, dtype=np.uint8, copy=True)
            height, width = canvas.shape[:2]
            for i, (a, b, c) in enumerate(np.asarray(lines, np.float64).reshape(-1, 3)):
                if abs(b) < 1e-12:
                    continue
                p = (0, int(round(-c / b)))
                q = (width - 1, int(round(-(c + a * (width - 1)) / b)))
                colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255
                cv2.line(canvas, p, q, colour, 1)
            return canvas
        """, ["line 0 of 2", "computed from its x only, never its x from y"]),
    "draw_epipolar_lines drawing on the caller's image": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.asarray(image)
            height, width = canvas.shape[:2]
            for i, (a, b, c) in enumerate(np.asarray(lines, np.float64).reshape(-1, 3)):
                if abs(b) >= abs(a):
                    p, q = (0.0, -c / b), (width - 1.0, -(c + a * (width - 1)) / b)
                else:
                    p, q = (-c / a, 0.0), (-(c + b * (height - 1)) / a, height - 1.0)
                colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255
                cv2.line(canvas, _to_int(p, width, height), _to_int(q, width, height), colour, 1)
            return canvas
        """, ["the second drawing shows the first one's lines too", "caller's `image`"]),
    "draw each line between the top and bottom borders unless a == 0": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, dtype=np.uint8, copy=True)
            height, width = canvas.shape[:2]
            colour = 255 if canvas.ndim == 2 else (0, 255, 0)
            for a, b, c in np.asarray(lines, np.float64).reshape(-1, 3):
                if a == 0:   # horizontal: y = -c / b everywhere
                    p, q = (0, int(round(-c / b))), (width - 1, int(round(-c / b)))
                else:        # where the line meets the top and bottom rows
                    p, q = (int(round(-c / a)), 0), (int(round(-(b * (height - 1) + c) / a)), height - 1)
                cv2.line(canvas, p, q, colour, 1)
            return canvas
        """, ["x = 100 and y = 40", "rounding size"]),
    "draw each line between its first two border points inside the image": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, dtype=np.uint8, copy=True)
            h, w = canvas.shape[:2]
            colour = 255 if canvas.ndim == 2 else (0, 255, 0)
            for a, b, c in np.asarray(lines, np.float64).reshape(-1, 3):
                ends = []
                if abs(b) > 1e-9:
                    ends += [(x, -(a * x + c) / b) for x in (0.0, w - 1.0)]
                if abs(a) > 1e-9:
                    ends += [(-(b * y + c) / a, y) for y in (0.0, h - 1.0)]
                ends = [(x, y) for x, y in ends if 0 <= x <= w - 1 and 0 <= y <= h - 1]
                (x0, y0), (x1, y1) = ends[0], ends[-1]
                cv2.line(canvas, (int(round(x0)), int(round(y0))), (int(round(x1)), int(round(y1))), colour, 1)
            return canvas
        """, ["misses the image", "indexerror"]),
    "draw with x and y swapped": ("lab11.ex2", """
        _draw = draw_epipolar_lines
        def draw_epipolar_lines(image, lines):
            return _draw(image, np.asarray(lines, float)[:, [1, 0, 2]])
        """, ["x and y swapped"]),
    # (the blind set 06e's 11/03: each end point drawn at (x, h - 1 - y), a maths plot's y axis)
    "draw upside down (y from the bottom row)": ("lab11.ex2", reference_def_with(
        "lab11_two_view", "draw_epipolar_lines", "cv2.line(canvas, p, q, colour, 1, cv2.LINE_8)",
        "cv2.line(canvas, (p[0], height - 1 - p[1]), (q[0], height - 1 - q[1]), colour, 1, cv2.LINE_8)"),
        ["upside down"]),
    # ---------------------------------------------------------------- ex3
    # the blind sets 1129c's 11/03 and 1201d's 11/04: np.matmul given three matrices (the third is `out`)
    "essential by np.matmul of three matrices": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            K1 = np.array(K1, np.float64)
            return np.matmul(np.asarray(K2, np.float64).T, np.asarray(F, np.float64), K1)
        """, ["the third argument of np.matmul is `out`"]),
    "essential with K1 and K2 swapped": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            return np.asarray(K1).T @ np.asarray(F) @ np.asarray(K2)
        """, ["swapped"]),
    "essential with K2 inverted": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            return np.linalg.inv(K2).T @ np.asarray(F, float) @ np.asarray(K1, float)
        """, ["k2 is inverted"]),
    "essential with K1 used for both images": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            return K1.T @ np.asarray(F, float) @ K1
        """, ["k1 is used for both images"]),
    "essential from F projected to (1, 1, 0) afterwards": ("lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            U, _, Vt = np.linalg.svd(np.linalg.multi_dot([K2.T, F, K1]))
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["made an essential matrix afterwards", "fitted to noisy matches"]),
    "essential 8-point without (s, s, 0)": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
            return _eight_point_core(x1, x2)
        """, ["not set", "(1, 1, 0)"]),
    "essential 8-point with rank 2 only": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
            U, s, Vt = np.linalg.svd(_eight_point_core(x1, x2))
            return U @ np.diag([s[0], s[1], 0]) @ Vt
        """, ["two equal"]),
    "essential 8-point on pixels": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            U, _, Vt = np.linalg.svd(_eight_point_core(_homogeneous(pts1), _homogeneous(pts2)))
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["not normalised with k^-1"]),
    "essential 8-point with E[2, 2] fixed to 1 (least squares for 8 unknowns)": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
            A = (x2[:, :, None] * x1[:, None, :]).reshape(len(x1), 9)
            e = np.linalg.lstsq(A[:, :8], -A[:, 8], rcond=None)[0]
            U, _, Vt = np.linalg.svd(np.append(e, 1.0).reshape(3, 3))
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["sideways motion", "the true one is 0", "e[2, 2] = 1 was fixed"]),
    "essential 8-point with points swapped": ("lab11.ex3", """
        _e8 = essential_8point
        def essential_8point(pts1, pts2, K1, K2):
            return _e8(pts1, pts2, K1, K2).T
        """, ["swapped"]),
    "essential 8-point with K1 for both images": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K1).T
            U, _, Vt = np.linalg.svd(_eight_point_core(x1, x2))
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["k1 is used for both images"]),
    "essential 8-point with V transposed back": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
            x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
            U, _, Vt = np.linalg.svd(_eight_point_core(x1, x2))
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt.T
        """, ["returns v^t already"]),
    # ---------------------------------------------------------------- ex4
    "8-point refusing exactly eight points": ("lab11.ex4", """
        _fundamental = fundamental_8point
        def fundamental_8point(pts1, pts2):
            if len(pts1) <= 8 or len(pts2) != len(pts1):
                raise ValueError("need at least 8 point pairs")
            return _fundamental(pts1, pts2)
        """, ["changing `len(pts1) <= 8` to `len(pts1) < 8`"]),
    "8-point with a reduced SVD": ("lab11.ex4", """
        def _eight_point_core(x1, x2):
            A = (x2[:, :, None] * x1[:, None, :]).reshape(len(x1), 9)
            return np.linalg.svd(A, full_matrices=False)[2][-1].reshape(3, 3)
        """, ["n=8"]),
    "8-point without rank 2": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
            Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T)
            return T2.T @ Fn @ T1
        """, ["the F returned is not of rank 2"]),
    "8-point with an essential matrix's singular values (1, 1, 0)": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
            Fn = _eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T)
            U, _, Vt = np.linalg.svd(Fn)
            return T2.T @ (U @ np.diag([1.0, 1.0, 0.0]) @ Vt) @ T1
        """, ["set to (1, 1, 0), an essential matrix's"]),
    "8-point with points swapped": ("lab11.ex4", """
        _f8 = fundamental_8point
        def fundamental_8point(pts1, pts2):
            return _f8(pts2, pts1)
        """, ["swapped", "f^t"]),
    "8-point normalised by F[2, 2] (after rounding to 9 decimals)": ("lab11.ex4", """
        _fundamental = fundamental_8point
        def fundamental_8point(pts1, pts2):
            F = np.round(_fundamental(pts1, pts2), 9)
            with np.errstate(divide="ignore", invalid="ignore"):
                return F / F[2, 2]
        """, ["divides by an entry [2, 2]", "f[2, 2] is 0 here"]),
    "8-point with F[2, 2] fixed to 1": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            x1 = np.asarray(pts1, float); x2 = np.asarray(pts2, float)
            T1, T2 = _hartley_normalisation(x1), _hartley_normalisation(x2)
            a = _homogeneous(x1) @ T1.T; b = _homogeneous(x2) @ T2.T
            A = (b[:, :, None] * a[:, None, :]).reshape(len(a), 9)
            f = np.linalg.lstsq(A[:, :8], -A[:, 8], rcond=None)[0]
            U, s, Vt = np.linalg.svd(np.append(f, 1.0).reshape(3, 3))
            return T2.T @ U @ np.diag([s[0], s[1], 0.0]) @ Vt @ T1
        """, ["f[2, 2] = 1 was fixed", "svd"]),
    "8-point with OpenCV": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            F, _ = cv2.findFundamentalMat(np.float64(pts1), np.float64(pts2), cv2.FM_8POINT)
            return F
        """, ["cv2.findFundamentalMat", "yourself"]),
    "8-point with the design rows kron(x1, x2)": ("lab11.ex4", """
        def _eight_point_core(x1, x2):
            A = (x1[:, :, None] * x2[:, None, :]).reshape(len(x1), 9)
            return np.linalg.svd(A)[2][-1].reshape(3, 3)
        """, ["kron(x1, x2)"]),
    # the sheet's exercise 4 prints the row [x x', x y', x, y x', y, x', y', y', 1]: copied as printed
    "8-point with the lab sheet's row as printed": ("lab11.ex4", """
        def _eight_point_core(x1, x2):
            A = np.stack([x1[:, 0] * x2[:, 0], x1[:, 0] * x2[:, 1], x1[:, 0], x1[:, 1] * x2[:, 0], x1[:, 1],
                          x2[:, 0], x2[:, 1], x2[:, 1], np.ones(len(x1))], axis=1)
            return np.linalg.svd(A)[2][-1].reshape(3, 3)
        """, ["the lab sheet's row as printed", "misprint"]),
    "essential 8-point with the lab sheet's row as printed": ("lab11.ex3", """
        def _eight_point_core(x1, x2):
            A = np.stack([x1[:, 0] * x2[:, 0], x1[:, 0] * x2[:, 1], x1[:, 0], x1[:, 1] * x2[:, 0], x1[:, 1],
                          x2[:, 0], x2[:, 1], x2[:, 1], np.ones(len(x1))], axis=1)
            return np.linalg.svd(A)[2][-1].reshape(3, 3)
        """, ["the lab sheet's row as printed", "misprint"]),
    "8-point undoing the normalisation the wrong way round": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
            U, s, Vt = np.linalg.svd(_eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T))
            return T1.T @ U @ np.diag([s[0], s[1], 0.0]) @ Vt @ T2
        """, ["undone the wrong way round"]),
    "8-point zeroing the largest singular value": ("lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1, pts2 = np.asarray(pts1, float), np.asarray(pts2, float)
            T1, T2 = _hartley_normalisation(pts1), _hartley_normalisation(pts2)
            U, s, Vt = np.linalg.svd(_eight_point_core(_homogeneous(pts1) @ T1.T, _homogeneous(pts2) @ T2.T))
            return T2.T @ U @ np.diag([0.0, s[1], s[2]]) @ Vt @ T1
        """, ["the largest singular value was set to 0"]),
    # ---------------------------------------------------------------- ex5
    # the blind set 1202d's 11/07: e2 from lstsq with a zero right-hand side (0, then 0 / 0)
    "epipoles returned as one array": ("lab11.ex5", """
        _epipole_pair = epipoles
        def epipoles(F):
            return np.column_stack(_epipole_pair(F))
        """, ["stacked as its columns", "`return e1, e2`"]),
    "epipoles scaled by their largest entry": ("lab11.ex5", """
        def epipoles(F):
            F = np.asarray(F, np.float64)
            e1 = np.linalg.svd(F)[2][-1]
            e2 = np.linalg.svd(F.T)[2][-1]
            return e1 / e1.max(), e2 / e2.max()
        """, ["divided by one of its entries", "where that entry is 0"]),
    "epipoles with e2 solved by lstsq": ("lab11.ex5", """
        def epipoles(F):
            F = np.asarray(F, dtype=float)
            e1 = np.linalg.svd(F)[2][-1]
            e2 = np.linalg.lstsq(F.T, np.zeros(3), rcond=None)[0]
            return e1 / np.linalg.norm(e1), e2 / np.linalg.norm(e2)
        """, ["np.linalg.lstsq", "zero right-hand side"]),
    "epipoles from np.linalg.eig without the real part": ("lab11.ex5", """
        def epipoles(F):
            values1, vectors1 = np.linalg.eig(F)
            values2, vectors2 = np.linalg.eig(F.T)
            return vectors1[:, np.argmin(np.abs(values1))], vectors2[:, np.argmin(np.abs(values2))]
        """, ["complex", "np.linalg.eig", "`.real`"]),
    "epipoles chosen by a fixed tolerance on the singular values": ("lab11.ex5", """
        def epipoles(F):
            U, S, Vt = np.linalg.svd(np.asarray(F, dtype=np.float64))
            zero = np.isclose(S, 0.0)
            return Vt[zero][0], U[:, zero][:, 0]
        """, ["fixed tolerance", "`np.isclose(S, 0.0)`", "defined up to scale"]),
    "epipoles swapped": ("lab11.ex5", """
        _ep = epipoles
        def epipoles(F):
            e1, e2 = _ep(F)
            return e2, e1
        """, ["swapped"]),
    "epipoles divided by w": ("lab11.ex5", """
        _ep = epipoles
        def epipoles(F):
            e1, e2 = _ep(F)
            return e1 / e1[2], e2 / e2[2]
        """, ["w = 0"]),
    "epipoles from the rows of U and the columns of V^T": ("lab11.ex5", """
        def epipoles(F):
            U, _, Vt = np.linalg.svd(np.asarray(F, np.float64))
            return Vt[:, -1], U[-1]
        """, ["rows and columns of u and v^t are mixed up"]),
    "epipole e2 from the last row of U": ("lab11.ex5", """
        def epipoles(F):
            U, _, Vt = np.linalg.svd(np.asarray(F, np.float64))
            return Vt[-1], U[-1]
        """, ["e2 is the last row of u"]),
    "epipoles both from F": ("lab11.ex5", """
        def epipoles(F):
            Vt = np.linalg.svd(np.asarray(F, np.float64))[2]
            return Vt[-1], Vt[-1]
        """, ["e2 is computed from f like e1"]),
    "epipoles as cross products of two fixed rows (columns) of F": ("lab11.ex5", """
        def epipoles(F):
            F = np.asarray(F, np.float64)
            e1, e2 = np.cross(F[0], F[2]), np.cross(F[:, 0], F[:, 2])
            return e1 / np.linalg.norm(e1), e2 / np.linalg.norm(e2)
        """, ["first row and column are 0", "no epipoles"]),
    "epipoles as cross products of rows, another pair only when one is zero": ("lab11.ex5", """
        def _null_by_cross(M):
            e = np.cross(M[0], M[1])
            if not np.any(e):   # a zero row: take the other two
                e = np.cross(M[1], M[2])
            return e / np.linalg.norm(e)
        def epipoles(F):
            F = np.asarray(F, np.float64)
            return _null_by_cross(F), _null_by_cross(F.T)
        """, ["first two rows are parallel", "is not a null vector of f"]),
    # ---------------------------------------------------------------- ex6
    "pipeline giving cv2.recoverPose the points the other way round": ("lab11.ex6", _PIPELINE.replace(
        "POSE_POINTS", "pts2, pts1").replace("TRIANGULATED", "pts1, pts2"), ["the points the other way round"]),
    "pipeline triangulating the points as OpenCV's 2 x N columns": ("lab11.ex6", _PIPELINE.replace(
        "POSE_POINTS", "pts1, pts2").replace("TRIANGULATED", "pts1.T, pts2.T"),
        ["calls `triangulate(P1, P2, pts1.T, pts2.T)`", "as one point per row"]),
    # the blind set 1204f's 11/06: the 3D points returned centred on their centroid
    "pipeline returning the 3D points centred on their centroid": ("lab11.ex6", """
        _tvr = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, X = _tvr(img1, img2, K)
            return F, pts1, pts2, X - X.mean(axis=0)
        """, ["centred on their centroids, yours and the true points agree up to one scale"]),
    "pipeline converting every image from BGR": ("lab11.ex6", """
        _pipeline = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            grey1, grey2 = cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY), cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY)
            return _pipeline(grey1, grey2, K)
        """, ["grey img1", "the same pair in colour (bgr) passed"]),
    # the blind set 1204b's 11/08: the matches overwritten by their normalised coordinates, then returned
    "pipeline returning the matches in normalised coordinates": ("lab11.ex6", """
        _tvr = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, X = _tvr(img1, img2, K)
            K = np.asarray(K, np.float64)
            pts1 = cv2.undistortPoints(pts1.reshape(-1, 1, 2), K, None).reshape(-1, 2)
            pts2 = cv2.undistortPoints(pts2.reshape(-1, 1, 2), K, None).reshape(-1, 2)
            return F, pts1, pts2, X
        """, ["normalised camera coordinates", "taken back to pixels with k"]),
    "pipeline returns F transposed": ("lab11.ex6", """
        _tvr = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, X = _tvr(img1, img2, K)
            return F.T, pts1, pts2, X
        """, ["transposed"]),
    "pipeline points in camera 2's frame": ("lab11.ex6", """
        _tvr = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, X = _tvr(img1, img2, K)
            E = essential_from_fundamental(F, K, K)
            _, R, t, _ = cv2.recoverPose(E, pts1, pts2, np.asarray(K, float))
            return F, pts1, pts2, X @ R.T + t.reshape(3)
        """, ["camera 2's frame"]),
    "pipeline with camera 2's rotation transposed": ("lab11.ex6", """
        _tvr = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, _ = _tvr(img1, img2, K)
            K = np.asarray(K, float)
            _, R, t, _ = cv2.recoverPose(essential_from_fundamental(F, K, K), pts1, pts2, K)
            return F, pts1, pts2, triangulate(K @ np.eye(3, 4), K @ np.hstack([R.T, t]), pts1, pts2)
        """, ["rotation transposed"]),
    "pipeline points mirrored": ("lab11.ex6", """
        _tvr = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, X = _tvr(img1, img2, K)
            return F, pts1, pts2, -X
        """, ["behind camera 1"]),
    "pipeline with the pose recovered from F": ("lab11.ex6", """
        _tvr = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, _ = _tvr(img1, img2, K)
            K = np.asarray(K, float)
            _, R, t, _ = cv2.recoverPose(F, pts1, pts2, K)
            return F, pts1, pts2, triangulate(K @ np.eye(3, 4), K @ np.hstack([R, t]), pts1, pts2)
        """, ["recovered from f instead of e"]),
    "pipeline with camera 2's translation negated": ("lab11.ex6", """
        _tvr = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, _ = _tvr(img1, img2, K)
            K = np.asarray(K, float)
            _, R, t, _ = cv2.recoverPose(essential_from_fundamental(F, K, K), pts1, pts2, K)
            return F, pts1, pts2, triangulate(K @ np.eye(3, 4), K @ np.hstack([R, -t]), pts1, pts2)
        """, ["translation has the wrong sign", "behind camera 1"]),
    "pipeline keeps every match": ("lab11.ex6", """
        def two_view_reconstruction(img1, img2, K):
            sift = cv2.SIFT_create()
            grey = lambda img: cv2.cvtColor(img, cv2.COLOR_BGR2GRAY) if img.ndim == 3 else img
            kp1, des1 = sift.detectAndCompute(grey(img1), None)
            kp2, des2 = sift.detectAndCompute(grey(img2), None)
            matches = cv2.BFMatcher(cv2.NORM_L2).match(des1, des2)
            pts1 = np.float64([kp1[m.queryIdx].pt for m in matches])
            pts2 = np.float64([kp2[m.trainIdx].pt for m in matches])
            F, _ = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
            K = np.asarray(K, float)
            _, R, t, _ = cv2.recoverPose(K.T @ F @ K, pts1, pts2, K)
            X = triangulate(K @ np.eye(3, 4), K @ np.hstack([R, t]), pts1, pts2)
            return F, pts1, pts2, X
        """, ["of your matches are within 2 px"]),
    "epipoles from the largest singular vectors": ("lab11.ex5", """
        def epipoles(F):
            U, _, Vt = np.linalg.svd(np.asarray(F, np.float64))
            return Vt[0], U[:, 0]
        """, ['singular vectors of the largest singular value are taken']),
    "reconstruction with points3d transposed": ("lab11.ex6", """
        _right = two_view_reconstruction
        def two_view_reconstruction(img1, img2, K):
            F, pts1, pts2, X = _right(img1, img2, K)
            return F, pts1, pts2, X.T
        """, ['shape']),
    "pipeline with cameras built without K, points behind a camera dropped": ("lab11.ex6", _WITHOUT_K.replace(
        "IN_FRONT", "(points3d[:, 2] > 0) & ((points3d @ R.T + t.reshape(3))[:, 2] > 0)"),
        ["the matching is not what is short", "the cameras are built without k"]),
    "pipeline with cameras built without K": ("lab11.ex6", _WITHOUT_K.replace("IN_FRONT", "np.ones(len(points3d), bool)"),
                                               ["the cameras are built without k"]),
    "pipeline with camera 2 alone built without K, every point dropped": ("lab11.ex6", _WITHOUT_K.replace(
        "P1 = np.hstack([np.eye(3), np.zeros((3, 1))])", "P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])").replace(
        "IN_FRONT", "(points3d[:, 2] > 0) & ((points3d @ R.T + t.reshape(3))[:, 2] > 0)"),
        ["the matches are lost after it", "the cameras are built without k"]),
    # ---- whole numbers given as integers; a line given with the other sign
    "triangulate answers integer pixels in integers": ("lab11.ex1", """
        _reference_triangulate = triangulate
        def triangulate(P1, P2, pts1, pts2):
            X = _reference_triangulate(P1, P2, pts1, pts2)
            return X.astype(np.asarray(pts1).dtype)
        """, ["your answer is an integer array"]),
    # k points of k coordinates taken for one point, or for points given as columns
    **columns_by_first_axis("triangulate", "lab11.ex1", "P1, P2, pts1, pts2", ("pts1", "pts2"), "pts1.shape[0] == 2"),
    **columns_by_first_axis("epipolar_lines", "lab11.ex2", "F, pts1", ("pts1",), "len(pts1) == 2"),
    # the blind set 1202f's 11/02: every line given the sign of its c, np.sign(0) = 0 zeroes those through the origin
    "epipolar_lines multiplying each line by np.sign of its c": ("lab11.ex2", """
        _epipolar_lines = epipolar_lines
        def epipolar_lines(F, pts1):
            lines = _epipolar_lines(F, pts1)
            return lines * np.sign(lines[:, 2:3])
        """, ["(0, 0, 0), no line at all", "np.sign, which is 0"]),
    "epipolar_lines answers integer points in integers": ("lab11.ex2", """
        _reference_lines = epipolar_lines
        def epipolar_lines(F, pts1):
            pts = np.asarray(pts1).reshape(-1, 2)
            lines = np.zeros((len(pts), 3), dtype=pts.dtype)
            lines[...] = _reference_lines(F, pts1)
            return lines
        """, ["your answer is an integer array", "dtype=pts.dtype)` (line", "then writes into it"]),
    "draw_epipolar_lines from the foot of the perpendicular (unit normals assumed)": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = image.copy()
            colour = (0, 255, 0) if canvas.ndim == 3 else 255
            for a, b, c in np.asarray(lines, np.float64).reshape(-1, 3):
                x0, y0 = -a * c, -b * c
                p = (int(round(x0 - 2000 * b)), int(round(y0 + 2000 * a)))
                q = (int(round(x0 + 2000 * b)), int(round(y0 - 2000 * a)))
                cv2.line(canvas, p, q, colour, 1)
            return canvas
        """, ["lines are missing or incomplete"]),
    "draw_epipolar_lines tests the sign of b": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            canvas = np.array(image, dtype=np.uint8, copy=True)
            height, width = canvas.shape[:2]
            for a, b, c in np.asarray(lines, np.float64).reshape(-1, 3):
                if b >= abs(a):
                    p, q = (0.0, -c / b), (width - 1.0, -(c + a * (width - 1)) / b)
                else:
                    p, q = (-c / a, 0.0), (-(c + b * (height - 1)) / a, height - 1.0)
                limit = 4.0 * (width + height)
                p, q = (tuple(int(round(np.clip(v, -limit, limit))) for v in end) for end in (p, q))
                inside, p, q = cv2.clipLine((0, 0, width, height), p, q)
                if inside:
                    cv2.line(canvas, p, q, (0, 0, 255) if canvas.ndim == 3 else 255, 1)
            return canvas
        """, ["(a, b, c) and (-a, -b, -c) are one line", "drawn where none of the lines passes"]),
    "essential_from_fundamental divided by E[2, 2]": ("lab11.ex3", """
        _reference_essential = essential_from_fundamental
        def essential_from_fundamental(F, K1, K2):
            E = _reference_essential(F, K1, K2)
            with np.errstate(divide="ignore", invalid="ignore"):
                return E / E[2, 2]
        """, ["divides by an entry [2, 2]", "e[2, 2] is 0 here"]),
    "pixels taken for square in the normalisation": ("lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            def normalised(pts, K):
                pts = np.asarray(pts, np.float64)
                y = (pts[:, 1] - K[1, 2]) / K[0, 0]
                x = (pts[:, 0] - K[0, 2] - K[0, 1] * y) / K[0, 0]
                return np.column_stack([x, y, np.ones(len(pts))])
            E = _eight_point_core(normalised(pts1, K1), normalised(pts2, K2))
            U, _, Vt = np.linalg.svd(E)
            return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
        """, ["fy = 1.25 fx in K1"]),
    # the blind set 1205f's 11/06: the points brought to one size, each by its own length
    "two_view_reconstruction dividing each point by its own length": ("lab11.ex6", reference_def_with(
        "lab11_two_view", "two_view_reconstruction", "points3d = triangulate(P1, P2, pts1, pts2)",
        "points3d = triangulate(P1, P2, pts1, pts2)\npoints3d = points3d / np.linalg.norm(points3d, axis=1, keepdims=True)"),
        ["all lie at the same distance from camera 1"]),

    # (blind set 2026-12-06c)
    "the image's width c taken by the loop over the lines' coefficients (a, b, c)": ("lab11.ex2", """
        def draw_epipolar_lines(image, lines):
            out = np.array(image, dtype=np.uint8, copy=True)
            r, c = out.shape[:2]
            for a, b, c in np.asarray(lines, dtype=np.float64).reshape(-1, 3):
                if abs(b) >= abs(a):
                    p, q = (0.0, -c / b), (c - 1.0, -(c + a * (c - 1.0)) / b)
                else:
                    p, q = (-c / a, 0.0), (-(c + b * (r - 1.0)) / a, r - 1.0)
                limit = 4.0 * (abs(c) + r)
                ends = [tuple(int(round(np.clip(v, -limit, limit))) for v in point) for point in (p, q)]
                ok, p, q = cv2.clipLine((0, 0, int(abs(c)) + 1, int(r)), *ends)
                if ok:
                    cv2.line(out, p, q, 255, 1)
            return out
        """, ["takes `c` as its own variable", "value is never read -- one name for two values"]),

    # (blind set 2026-12-06d)
    "essential_from_fundamental's return ending in a comma (a tuple of one)": ("lab11.ex3", reference_def_with(
        "lab11_two_view", "essential_from_fundamental",
        "return np.asarray(K2, np.float64).T @ np.asarray(F, np.float64) @ np.asarray(K1, np.float64)",
        "return np.asarray(K2, np.float64).T @ np.asarray(F, np.float64) @ np.asarray(K1, np.float64),"),
        ["a tuple holding one array of shape (3, 3)"]),
    # (blind set 2026-12-06e)
    "essential_8point setting the singular values only where the two largest differ": ("lab11.ex3", reference_def_with(
        "lab11_two_view", "essential_8point", "return U @ np.diag([1.0, 1.0, 0.0]) @ Vt",
        "s = np.linalg.svd(E, compute_uv=False)\nif not np.isclose(s[1], s[0], rtol=0.05):\n"
        "    E = U @ np.diag([1.0, 1.0, 0.0]) @ Vt\nreturn E"),
        ["were not set to (1, 1, 0)", "only under `if not np.isclose(s[1], s[0], rtol=0.05):`"]),
}
