"""Lab 10 ext1 tolerance, measured: undistortion on cameras whose principal point is off centre.

The check "undistort_image keeps K's principal point off the image centre"
(autograder/labs/lab10.py, UNDISTORT_TOLERANCE) compares the student's undistortion with the
distortion-free view rendered through fixtures/lab10.OFF_CENTRE_K (fx != fy, principal point
(175, 110) where the centre is (159.5, 119.5)), and its probe through OFF_CENTRE_PROBE_K. This
prints the mean blurred difference (grey levels, on the pixels the lens keeps) of the legitimate
recipes -- cv2.undistort (the lab sheet's), float32 K and dist, cv2.initUndistortRectifyMap with K
as the new camera matrix (CV_32FC1 or CV_16SC2 maps, linear, cubic or nearest remap), an own map
of OpenCV's model -- and of the mistakes: initUndistortRectifyMap given no new camera matrix
(OpenCV then centres the principal point), the usual undistortion mistakes.

    python benchmarks/spread_undistort_off_centre.py
"""

from __future__ import annotations

import cv2
import numpy as np

from autograder.engine.compare import blurred_difference
from fixtures import lab09
from fixtures import lab10 as truth


def remapped(newK, map_type=cv2.CV_32FC1, interpolation=cv2.INTER_LINEAR):
    def undistort(image, K, dist):
        h, w = image.shape[:2]
        maps = cv2.initUndistortRectifyMap(K, dist, None, newK(K), (w, h), map_type)
        return cv2.remap(image, *maps, interpolation, borderMode=cv2.BORDER_CONSTANT)
    return undistort


def own_map(image, K, dist):
    """Each output pixel samples the distorted image where OpenCV's model sends it."""
    h, w = image.shape[:2]
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float64)
    normalised = np.column_stack([(xs.ravel() - K[0, 2]) / K[0, 0], (ys.ravel() - K[1, 2]) / K[1, 1]])
    d = lab09.distort_truth(normalised, dist)
    map_x = (d[:, 0] * K[0, 0] + K[0, 2]).reshape(h, w).astype(np.float32)
    map_y = (d[:, 1] * K[1, 1] + K[1, 2]).reshape(h, w).astype(np.float32)
    return cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT)


LEGITIMATE = {
    "cv2.undistort": lambda image, K, dist: cv2.undistort(image, K, dist),
    "cv2.undistort, float32 K and dist": lambda image, K, dist: cv2.undistort(image, np.float32(K), np.float32(dist)),
    "initUndistortRectifyMap(newCameraMatrix=K) + remap": remapped(lambda K: K),
    "the same, CV_16SC2 maps": remapped(lambda K: K, cv2.CV_16SC2),
    "the same, cubic remap": remapped(lambda K: K, interpolation=cv2.INTER_CUBIC),
    "the same, nearest remap": remapped(lambda K: K, interpolation=cv2.INTER_NEAREST),
    "own map of OpenCV's model": own_map,
}
MISTAKES = {
    "initUndistortRectifyMap given no new camera matrix (principal point centred)": remapped(lambda K: None),
    "cv2.getDefaultNewCameraMatrix(K, size, True) as the new matrix": remapped(
        lambda K: cv2.getDefaultNewCameraMatrix(K, truth.POSE_SIZE, True)),
    "fx used for both focal lengths": lambda image, K, dist: cv2.undistort(
        image, np.diag([K[0, 0], K[0, 0], 1.0]) + np.pad(K[:2, 2:], ((0, 1), (2, 0))), dist),
}


def main():
    for label, K in (("check", truth.OFF_CENTRE_K), ("probe", truth.OFF_CENTRE_PROBE_K)):
        for lens in (truth.DIST, truth.FULL_DIST):
            distorted, clean, *_ = truth.distorted_view(tuple(lens), tuple(K.ravel()))
            valid = truth.undistortion_valid(K, np.asarray(lens), truth.POSE_SIZE)
            print(f"== {label} camera, cx = {K[0, 2]:g}, cy = {K[1, 2]:g}, lens {tuple(lens)}")
            spread = {name: blurred_difference(f(distorted, K, np.asarray(lens)), clean, valid)
                      for name, f in LEGITIMATE.items()}
            worst = max(spread, key=spread.get)
            print(f"  legitimate: {min(spread.values()):.2f}-{spread[worst]:.2f} ({worst})")
            for name, f in MISTAKES.items():
                print(f"  mistake {name}: {blurred_difference(f(distorted, K, np.asarray(lens)), clean, valid):.1f}")


if __name__ == "__main__":
    main()
