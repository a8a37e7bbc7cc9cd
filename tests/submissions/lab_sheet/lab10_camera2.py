"""Lab 10 written the way the lab sheet says, line by line (a test submission).

The formulas as printed (no NaN for points behind the camera: the API leaves
that to the formula), the DLT on raw coordinates solved by SVD, the
decomposition by QR of M^-1 with t = -M^-1 P[:, 3] as the camera centre, and
cv2.findChessboardCorners + cv2.solvePnP + cv2.projectPoints for the pose (no
sub-pixel refinement: the sheet does not mention it), cv2.undistort, and
Matplotlib to look at the results. It must score full marks.
"""

import cv2
import matplotlib.pyplot as plt
import numpy as np


def plot_points(title, points):
    """What a student does to look at a projection: a Matplotlib scatter plot."""
    plt.figure()
    plt.title(title)
    plt.scatter(points[..., 0], points[..., 1], s=4)
    plt.gca().invert_yaxis()
    plt.show()


def _as_rows(points):
    points = np.asarray(points, dtype=np.float64)
    return np.atleast_2d(points), points.ndim == 1


# Exercise 1: x = f X / Z, y = f Y / Z
def perspective_project(points, f):
    X, single = _as_rows(points)
    x = f * X[:, 0] / X[:, 2]
    y = f * X[:, 1] / X[:, 2]
    projected = np.column_stack([x, y])
    return projected[0] if single else projected


def show_focal_lengths(points):
    for f in [100, 500, 1000]:
        plot_points(f"f = {f}", perspective_project(points, f))


# Exercise 2: one depth Z_avg for every point
def weak_perspective_project(points, f, z_avg=None):
    X, single = _as_rows(points)
    Z_avg = np.mean(X[:, 2]) if z_avg is None else z_avg
    projected = np.column_stack([f * X[:, 0] / Z_avg, f * X[:, 1] / Z_avg])
    return projected[0] if single else projected


# Exercise 3: x = P [X, Y, Z, 1]^T with the sheet's matrix
def orthographic_project(points):
    X, single = _as_rows(points)
    P = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=np.float64)
    x = (P @ np.column_stack([X, np.ones(len(X))]).T).T
    projected = x[:, :2] / x[:, 2:]
    return projected[0] if single else projected


# Exercise 4: A p = 0 by SVD, smallest singular vector reshaped into P
def camera_matrix_dlt(points3d, points2d):
    A = []
    for (X, Y, Z), (x, y) in zip(np.asarray(points3d, float), np.asarray(points2d, float)):
        Xi = np.array([X, Y, Z, 1.0])
        A.append(np.concatenate([Xi, np.zeros(4), -x * Xi]))
        A.append(np.concatenate([np.zeros(4), Xi, -y * Xi]))
    _, _, Vt = np.linalg.svd(np.array(A))
    return Vt[-1].reshape(3, 4)


# Exercise 5: M = P[:, :3], C = -M^-1 P[:, 3], QR of M^-1
def camera_center(P):
    P = np.asarray(P, dtype=np.float64)
    M = P[:, 0:3]
    return -np.linalg.inv(M) @ P[:, 3]


def decompose_camera_matrix(P):
    P = np.asarray(P, dtype=np.float64)
    if np.linalg.det(P[:, 0:3]) < 0:      # P is known up to sign: make det(M) > 0
        P = -P
    M = P[:, 0:3]
    C = camera_center(P)
    Q, U = np.linalg.qr(np.linalg.inv(M))   # M^-1 = Q U, so M = U^-1 Q^T
    K = np.linalg.inv(U)
    R = Q.T
    D = np.diag(np.sign(np.diag(K)))      # make K's diagonal positive
    K, R = K @ D, D @ R
    K = K / K[2, 2]
    t = -R @ C                            # the API's t, from the centre
    return K, R, t


# Exercise 6: cv2.findChessboardCorners, cv2.solvePnP, cv2.projectPoints
def estimate_pose(image, pattern_size, square_size, K, dist=None):
    gray = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
    ret, corners = cv2.findChessboardCorners(gray, pattern_size, None)
    if not ret:
        return np.full(3, np.nan), np.full(3, np.nan), np.zeros((0, 2))
    objp = np.zeros((pattern_size[0] * pattern_size[1], 3), np.float32)
    objp[:, :2] = np.mgrid[0:pattern_size[0], 0:pattern_size[1]].T.reshape(-1, 2) * square_size
    ret, rvec, tvec = cv2.solvePnP(objp, corners, K, dist)
    imgpts, _ = cv2.projectPoints(objp, rvec, tvec, K, dist)
    plt.figure()
    plt.imshow(gray, cmap="gray")
    plt.plot(imgpts[:, 0, 0], imgpts[:, 0, 1], "r.")
    plt.show()
    return rvec.ravel(), tvec.ravel(), imgpts.reshape(-1, 2)


# Extension: cv2.undistort
def undistort_image(image, K, dist):
    return cv2.undistort(image, K, dist)


# Extension: dolly zoom
def dolly_zoom(points, f0, z0, distances):
    X, _ = _as_rows(points)
    focal_lengths = np.array([f0 * d / z0 for d in distances])
    projections = np.array([perspective_project(X + np.array([0, 0, d - z0]), f)
                            for f, d in zip(focal_lengths, distances)])
    return focal_lengths, projections


# Extension: pose over several frames
def track_pose(frames, pattern_size, square_size, K, dist=None):
    poses = []
    for frame in frames:
        rvec, tvec, _ = estimate_pose(frame, pattern_size, square_size, K, dist)
        poses.append(np.concatenate([rvec, tvec]))
    return np.array(poses)
