"""Lab 11: single-bug submissions written apart from the tables (see the package docstring)."""

from . import Case

MODULE = "lab11_two_view"

CASES = [
    Case("triangulation reads view 1's y in view 2's rows", "lab11.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1, P2 = np.asarray(P1, float), np.asarray(P2, float)
            pts1 = np.asarray(pts1, float).reshape(-1, 2)
            pts2 = np.asarray(pts2, float).reshape(-1, 2)
            out = []
            for i in range(len(pts1)):
                x1, y1 = pts1[i]
                x2, y2 = pts2[i]
                A = np.array([x1 * P1[2] - P1[0],
                              y1 * P1[2] - P1[1],
                              x2 * P2[2] - P2[0],
                              y1 * P2[2] - P2[1]])
                X = np.linalg.svd(A)[2][-1]
                out.append(X[:3] / X[3])
            return np.array(out)
        """, "the fourth row uses y1 where y2 belongs (a wrong operand)",
         ("y1", "view 1", "first view's", "wrong point", "pts1")),

    Case("epipolar lines divided by the norm of (a, b, c)", "lab11.ex2", """
        def epipolar_lines(F, pts1):
            pts1 = np.asarray(pts1, float).reshape(-1, 2)
            x = np.hstack([pts1, np.ones((len(pts1), 1))])
            lines = (np.asarray(F, float) @ x.T).T
            return lines / np.linalg.norm(lines, axis=1, keepdims=True)
        """, "the lines are scaled to |(a, b, c)| = 1, not a^2 + b^2 = 1",
         ("a^2 + b^2", "(a, b, c)", "all three", "wrong norm")),

    Case("essential matrix with K2 not transposed", "lab11.ex3", """
        def essential_from_fundamental(F, K1, K2):
            return np.asarray(K2, float) @ np.asarray(F, float) @ np.asarray(K1, float)
        """, "E = K2^T F K1: K2 is not transposed",
         ("transpose", "k2^t", "k2.t", "not transposed")),

    Case("fundamental 8-point with the lab sheet's row copied literally", "lab11.ex4", """
        def fundamental_8point(pts1, pts2):
            pts1 = np.asarray(pts1, float)
            pts2 = np.asarray(pts2, float)
            A = []
            for (x, y), (xp, yp) in zip(pts1, pts2):
                A.append([x * xp, x * yp, x, y * xp, y, xp, yp, yp, 1])
            _, _, Vt = np.linalg.svd(np.array(A))
            F = Vt[-1].reshape(3, 3)
            U, s, Vt = np.linalg.svd(F)
            return U @ np.diag([s[0], s[1], 0]) @ Vt
        """, "the design row's entries are in the wrong order (y' twice, y y' missing)",
         ("design row", "rows of a", "row of a", "the sheet's row")),

    Case("epipoles from np.linalg.eig, last column", "lab11.ex5", """
        def epipoles(F):
            F = np.asarray(F, float)
            _, v1 = np.linalg.eig(F)
            _, v2 = np.linalg.eig(F.T)
            return np.real(v1[:, -1]), np.real(v2[:, -1])
        """, "np.linalg.eig does not sort its eigenvalues: the last column is not the null vector",
         ("eig", "not sorted", "unsorted", "smallest")),

    Case("reconstruction indexes the points with the 0/1 RANSAC mask", "lab11.ex6", """
        def two_view_reconstruction(img1, img2, K):
            g1 = cv2.cvtColor(img1, cv2.COLOR_BGR2GRAY)
            g2 = cv2.cvtColor(img2, cv2.COLOR_BGR2GRAY)
            sift = cv2.SIFT_create()
            kp1, d1 = sift.detectAndCompute(g1, None)
            kp2, d2 = sift.detectAndCompute(g2, None)
            good = []
            for m, n in cv2.BFMatcher().knnMatch(d1, d2, k=2):
                if m.distance < 0.75 * n.distance:
                    good.append(m)
            pts1 = np.float64([kp1[m.queryIdx].pt for m in good])
            pts2 = np.float64([kp2[m.trainIdx].pt for m in good])
            F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, 1.0, 0.999)
            pts1, pts2 = pts1[mask.ravel()], pts2[mask.ravel()]
            K = np.asarray(K, float)
            E = K.T @ F @ K
            _, R, t, _ = cv2.recoverPose(E, pts1, pts2, K)
            P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
            P2 = K @ np.hstack([R, t.reshape(3, 1)])
            X = triangulate(P1, P2, pts1, pts2)
            keep = (X[:, 2] > 0) & ((X @ R.T + t.reshape(3))[:, 2] > 0)
            return F, pts1[keep], pts2[keep], X[keep]
        """, "the uint8 mask of 0 and 1 indexes rows 0 and 1, not the inliers (astype(bool) missing)",
         ("mask", "bool", "index")),

    Case("essential 8-point normalising with K instead of K^-1", "lab11.ex3", """
        def essential_8point(pts1, pts2, K1, K2):
            h1 = np.hstack([np.asarray(pts1, float), np.ones((len(pts1), 1))])
            h2 = np.hstack([np.asarray(pts2, float), np.ones((len(pts2), 1))])
            x1 = h1 @ np.asarray(K1, float).T
            x2 = h2 @ np.asarray(K2, float).T
            A = np.array([np.outer(b, a).ravel() for a, b in zip(x1, x2)])
            E = np.linalg.svd(A)[2][-1].reshape(3, 3)
            U, _, Vt = np.linalg.svd(E)
            return U @ np.diag([1, 1, 0]) @ Vt
        """, "the points are multiplied by K, not by K^-1",
         ("k^-1", "inverse", "k instead", "inv(k")),
]
