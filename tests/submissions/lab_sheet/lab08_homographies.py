"""Lab 8 written the way the lab sheet says (a test submission): full marks.

cv2.warpPerspective to apply H; the sheet's A_i rows solved by SVD on raw pixels; SIFT with
cv2.BFMatcher and the ratio test, cv2.drawMatches; cv2.findHomography with
cv2.RANSAC, then cv2.warpPerspective; a panorama from SIFT + RANSAC + warp +
blend. Extensions: ORB, a chain of images, Laplacian pyramids.
"""

import cv2
import matplotlib.pyplot as plt
import numpy as np


# Exercise 1: "Apply using cv2.warpPerspective."
def apply_homography(image, H, dsize=None):
    h, w = image.shape[:2]
    return cv2.warpPerspective(image, np.float64(H), dsize or (w, h))


def transform_points(H, pts):
    pts = np.float64(pts).reshape(-1, 1, 2)
    return cv2.perspectiveTransform(pts, np.float64(H)).reshape(-1, 2)


# Exercise 2: "Solve Ah = 0 ... Use SVD, reshape h to H" (the sheet's rows, raw pixels)
def homography_dlt(src, dst):
    A = []
    for (x, y), (xp, yp) in zip(np.float64(src), np.float64(dst)):
        A.append([-x, -y, -1, 0, 0, 0, x * xp, y * xp, xp])
        A.append([0, 0, 0, -x, -y, -1, x * yp, y * yp, yp])
    _, _, Vt = np.linalg.svd(np.array(A))
    H = Vt[-1].reshape(3, 3)
    return H / H[2, 2]


def warp_to_reference(reference, moving, H):
    h, w = reference.shape[:2]
    warped = cv2.warpPerspective(moving, H, (w, h))
    plt.imshow(warped)
    plt.show()
    return warped


# Exercise 3: "Use cv2.SIFT_create(), cv2.BFMatcher, and cv2.drawMatches with a ratio test."
def _features(image, method):
    grey = image if image.ndim == 2 else cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)
    detector = cv2.SIFT_create() if method == "sift" else cv2.ORB_create(nfeatures=1000)
    return detector.detectAndCompute(grey, None)


def match_features(img1, img2, ratio=0.75, method="sift"):
    kp1, des1 = _features(img1, method)
    kp2, des2 = _features(img2, method)
    pts1, pts2 = [], []
    if des1 is not None and des2 is not None and len(kp2) >= 2:
        bf = cv2.BFMatcher(cv2.NORM_L2 if method == "sift" else cv2.NORM_HAMMING)
        for pair in bf.knnMatch(des1, des2, k=2):
            if len(pair) == 2 and pair[0].distance < ratio * pair[1].distance:
                pts1.append(kp1[pair[0].queryIdx].pt)
                pts2.append(kp2[pair[0].trainIdx].pt)
    return np.float64(pts1).reshape(-1, 2), np.float64(pts2).reshape(-1, 2)


def draw_matches(img1, img2, pts1, pts2):
    kp1 = [cv2.KeyPoint(float(x), float(y), 1) for x, y in pts1]
    kp2 = [cv2.KeyPoint(float(x), float(y), 1) for x, y in pts2]
    matches = [cv2.DMatch(i, i, 0) for i in range(len(kp1))]
    colour = lambda im: cv2.cvtColor(im, cv2.COLOR_GRAY2BGR) if im.ndim == 2 else im  # noqa: E731
    return cv2.drawMatches(colour(img1), kp1, colour(img2), kp2, matches, None)


# Exercise 4: "Use cv2.findHomography with cv2.RANSAC, then apply with cv2.warpPerspective."
def homography_ransac(src, dst, threshold=3.0, seed=None):
    H, mask = cv2.findHomography(np.float32(src), np.float32(dst), cv2.RANSAC, threshold)
    return H, mask.ravel().astype(bool)


# Exercise 5: "Detect features (SIFT), estimate H (RANSAC), warp with cv2.warpPerspective, and blend."
def _homography(moving, reference):
    pts_ref, pts_mov = match_features(reference, moving)
    H, _ = cv2.findHomography(pts_mov, pts_ref, cv2.RANSAC, 3.0)
    return H


def _panorama(images, homographies):
    corners = []
    for image, H in zip(images, homographies):
        h, w = image.shape[:2]
        box = np.float64([[0, 0], [w - 1, 0], [w - 1, h - 1], [0, h - 1]]).reshape(-1, 1, 2)
        corners.append(cv2.perspectiveTransform(box, H).reshape(-1, 2))
    corners = np.vstack(corners)
    x0, y0 = np.floor(corners.min(axis=0))
    x1, y1 = np.ceil(corners.max(axis=0))
    T = np.array([[1, 0, -x0], [0, 1, -y0], [0, 0, 1]])
    size = (int(x1 - x0) + 1, int(y1 - y0) + 1)
    total = np.zeros((size[1], size[0], 3))
    count = np.zeros((size[1], size[0], 1))
    for image, H in zip(images, homographies):
        colour = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR) if image.ndim == 2 else image
        total += cv2.warpPerspective(colour, T @ H, size)
        count += cv2.warpPerspective(np.ones(image.shape[:2]), T @ H, size)[..., None] > 0.999
    return (total / np.maximum(count, 1)).astype(np.uint8)


def stitch(img1, img2):
    return _panorama([img1, img2], [np.eye(3), _homography(img2, img1)])


# Extensions
def stitch_many(images):
    r = len(images) // 2
    homographies = []
    for k in range(len(images)):
        H = np.eye(3)
        for j in range(k, r):          # left of the middle: k -> k+1 -> ... -> r
            H = _homography(images[j], images[j + 1]) @ H
        for j in range(k, r, -1):      # right of the middle: k -> k-1 -> ... -> r
            H = _homography(images[j], images[j - 1]) @ H
        homographies.append(H)
    return _panorama(list(images), homographies)


def blend_multiband(img1, img2, mask, levels=4):
    a, b, m = np.float32(img1), np.float32(img2), np.float32(mask)
    ga, gb, gm = [a], [b], [m]
    for _ in range(levels - 1):
        ga.append(cv2.pyrDown(ga[-1]))
        gb.append(cv2.pyrDown(gb[-1]))
        gm.append(cv2.pyrDown(gm[-1]))
    blended = []
    for i in range(levels):
        if i < levels - 1:
            size = (ga[i].shape[1], ga[i].shape[0])
            la = ga[i] - cv2.pyrUp(ga[i + 1], dstsize=size)
            lb = gb[i] - cv2.pyrUp(gb[i + 1], dstsize=size)
        else:
            la, lb = ga[i], gb[i]
        w = gm[i][..., None] if la.ndim == 3 else gm[i]
        blended.append(w * la + (1 - w) * lb)
    result = blended[-1]
    for band in reversed(blended[:-1]):
        result = cv2.pyrUp(result, dstsize=(band.shape[1], band.shape[0])) + band
    return np.clip(np.round(result), 0, 255).astype(np.uint8)
