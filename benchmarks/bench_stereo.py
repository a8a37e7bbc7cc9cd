"""Stereo benchmark: the reference matchers of lab 12 against OpenCV's, on real data.

The Middlebury "motorcycle" pair shipped with scikit-image
(``skimage.data.stereo_motorcycle()``: 741 x 500 pixels, ground-truth disparities
up to 60 px), at FULL resolution, ``max_disparity = 64``. For each method it
prints the bad-pixel rate (absolute error > 2 px, invalid pixels counted bad,
measured where the ground truth is known) and the wall time of one call, in
the same run:

- the reference ``block_matching`` (SSD and NCC, block 9) and ``dp_stereo``
  (block 5, its default smoothness), loaded by file path from
  ``reference_solutions/lab12_stereo.py``;
- OpenCV's ``StereoBM`` (block 9 and 15) and ``StereoSGBM`` (block 5,
  P1 = 8 b^2, P2 = 32 b^2), whose fixed-point output is divided by 16.

It is a script that prints figures, not a timed test::

    python benchmarks/bench_stereo.py [--half]

``--half`` runs at half resolution (370 x 250, ``max_disparity = 32``,
ground truth halved). The script exits with status 1 if the reference DP does
not beat StereoBM's bad-pixel rate.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
import time
from pathlib import Path

import cv2
import numpy as np
import skimage.data

ROOT = Path(__file__).resolve().parents[1]
THRESHOLD = 2.0


def load_reference():
    path = ROOT / "reference_solutions" / "lab12_stereo.py"
    spec = importlib.util.spec_from_file_location("lab12_stereo_reference", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def motorcycle(half: bool):
    left, right, disparity = skimage.data.stereo_motorcycle()
    left = cv2.cvtColor(left, cv2.COLOR_RGB2GRAY)
    right = cv2.cvtColor(right, cv2.COLOR_RGB2GRAY)
    truth = np.where(np.isfinite(disparity) & (disparity > 0), disparity, 0.0).astype(np.float64)
    if half:
        h, w = truth.shape
        H, W = h // 2, w // 2
        left = cv2.resize(left[:2 * H, :2 * W], (W, H), interpolation=cv2.INTER_AREA)
        right = cv2.resize(right[:2 * H, :2 * W], (W, H), interpolation=cv2.INTER_AREA)
        blocks = truth[:2 * H, :2 * W].reshape(H, 2, W, 2)
        truth = np.where((blocks > 0).all(axis=(1, 3)), blocks.mean(axis=(1, 3)) / 2, 0.0)
    return left, right, truth


def bad_pixel_rate(got, truth, threshold=THRESHOLD) -> float:
    known = truth > 0
    with np.errstate(invalid="ignore"):
        good = np.isfinite(got) & (got > 0) & (np.abs(got - truth) <= threshold)
    return float(1.0 - good[known].mean())


def timed(function, repeat: int = 1):
    best, result = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return result, best


def measure(half: bool = False) -> dict:
    """Bad-pixel rate and best-of-2 wall time of each method, in one run."""
    reference = load_reference()
    left, right, truth = motorcycle(half)
    max_disparity = 32 if half else 64
    num_disparities = 16 * ((max_disparity + 15) // 16)

    def opencv(matcher):
        return lambda: matcher.compute(left, right).astype(np.float64) / 16.0

    methods = {
        "reference block_matching SSD (block 9)":
            lambda: reference.block_matching(left, right, max_disparity, 9, "ssd"),
        "reference block_matching NCC (block 9)":
            lambda: reference.block_matching(left, right, max_disparity, 9, "ncc"),
        "reference dp_stereo (block 5, default smoothness)":
            lambda: reference.dp_stereo(left, right, max_disparity, 5),
        "OpenCV StereoBM (block 9)":
            opencv(cv2.StereoBM_create(numDisparities=num_disparities, blockSize=9)),
        "OpenCV StereoBM (block 15)":
            opencv(cv2.StereoBM_create(numDisparities=num_disparities, blockSize=15)),
        "OpenCV StereoSGBM (block 5)":
            opencv(cv2.StereoSGBM_create(minDisparity=0, numDisparities=num_disparities, blockSize=5,
                                         P1=8 * 25, P2=32 * 25, mode=cv2.StereoSGBM_MODE_SGBM)),
    }
    height, width = left.shape
    results = {}
    for name, run in methods.items():
        disparity, seconds = timed(run, repeat=2)
        results[name] = {"bad_pixels": bad_pixel_rate(disparity, truth), "seconds": seconds}
    return {"resolution": f"{width} x {height}", "half": half, "max_disparity": max_disparity,
            "threshold_px": THRESHOLD, "ground_truth_share": float(np.mean(truth > 0)),
            "methods": results}


def report(f: dict) -> None:
    print(f"Middlebury motorcycle (skimage), {'half' if f['half'] else 'full'} resolution "
          f"{f['resolution']}, max_disparity {f['max_disparity']}; bad pixel = error > "
          f"{f['threshold_px']:g} px or invalid, over the {f['ground_truth_share']:.0%} of pixels "
          f"with ground truth")
    print(f"{'method':52s} {'bad pixels':>10s} {'seconds':>9s}")
    for name, method in f["methods"].items():
        print(f"{name:52s} {method['bad_pixels']:10.1%} {method['seconds']:9.3f}")
    dp, best_bm = dp_against_block_matching(f)
    verdict = "beats" if dp < best_bm else "does NOT beat"
    print(f"reference dp_stereo {verdict} OpenCV StereoBM: {dp:.1%} vs {best_bm:.1%} bad pixels")


def dp_against_block_matching(f: dict) -> tuple[float, float]:
    """The reference DP's bad-pixel rate, and the best of OpenCV's StereoBM."""
    rates = {name: method["bad_pixels"] for name, method in f["methods"].items()}
    return (rates["reference dp_stereo (block 5, default smoothness)"],
            min(rate for name, rate in rates.items() if "StereoBM" in name))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--half", action="store_true", help="half resolution (370 x 250)")
    args = parser.parse_args(argv)
    figures = measure(args.half)
    report(figures)
    dp, best_bm = dp_against_block_matching(figures)
    return 0 if dp < best_bm else 1


if __name__ == "__main__":
    sys.exit(main())
