"""The whole-pixel-shift rule of image warps, measured (autograder.engine.compare.whole_pixel_shift).

For maps and images like the lab 7 and 8 checks' (a general affine map, a grey one with and without
dsize, translations whole and fractional, a rotation, a zoom, a shear, two homographies), prints for
each legitimate warp (bilinear, nearest, cubic, Lanczos, a float32 map, either half-pixel convention)
and each warp a whole pixel off (a border added and not taken back, the output or the input moved by
one pixel) the best fit within half a pixel, the best fit moved by a whole pixel and their ratio.
Legitimate warps must stay above WHOLE_PIXEL_RATIO, warps a pixel off below it where they can be told.

    python benchmarks/whole_pixel_shift.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from autograder.engine.compare import (HALF_PIXEL_OFFSETS, WHOLE_PIXEL_OFFSETS, WHOLE_PIXEL_RATIO,  # noqa: E402
                                       blurred_difference, warp_error)
from autograder.labs.lab07 import photo  # noqa: E402
from fixtures.images import as_homography, coverage, warp  # noqa: E402


def moved(dx, dy) -> np.ndarray:
    return np.array([[1.0, 0, dx], [0, 1, dy], [0, 0, 1]])


def warped(source, H, dsize, flags=cv2.INTER_LINEAR, float32=False):
    h, w = source.shape[:2]
    return cv2.warpPerspective(source, H.astype(np.float32) if float32 else H, dsize or (w, h), flags=flags,
                               borderMode=cv2.BORDER_CONSTANT, borderValue=0)


CASES = [
    ("rocket", False, [[0.8, 0.3, 10.0], [-0.2, 0.9, 40.0]], None),
    ("chelsea", True, [[0.9, -0.2, 20.0], [0.15, 1.05, -5.0]], None),
    ("chelsea", True, [[1.2, 0.1, 5.0], [0.0, 1.1, -10.0]], (220, 100)),
    ("rocket", False, [[1, 0, -20.4], [0, 1, -10.6]], None),
    ("rocket", False, [[1, 0, 100], [0, 1, 50]], None),
    ("rocket", False, cv2.getRotationMatrix2D((99.5, 74.5), 45, 1.0).tolist(), None),
    ("camera", True, cv2.getRotationMatrix2D((99.5, 74.5), 90, 1.0).tolist(), None),
    ("camera", True, cv2.getRotationMatrix2D((99.5, 74.5), 180, 1.0).tolist(), None),
    ("rocket", False, [[1.5, 0, 0], [0, 1.5, 0]], None),
    ("rocket", False, [[1, 0.5, 0], [0, 1, 0]], None),
    ("astronaut", False, [[0.9, 0.05, 12.0], [-0.04, 0.95, 8.0], [1e-4, -2e-4, 1.0]], None),
    ("coffee", False, [[1.1, -0.1, -15.0], [0.08, 1.0, 5.0], [3e-4, 1e-4, 1.0]], None),
]


def main() -> int:
    worst_legitimate, worst_off = np.inf, 0.0
    print(f"{'image':<10}{'map':<34}{'warp':<16}{'within':>8}{'moved':>8}{'ratio':>8}")
    for name, grey, M, dsize in CASES:
        source = photo(name, (200, 150), grey=grey)
        H = as_homography(np.asarray(M, float))
        inside, _ = coverage(H, source.shape, dsize)
        warps = {
            "bilinear": warped(source, H, dsize), "nearest": warped(source, H, dsize, cv2.INTER_NEAREST),
            "cubic": warped(source, H, dsize, cv2.INTER_CUBIC), "lanczos": warped(source, H, dsize, cv2.INTER_LANCZOS4),
            "float32 map": warped(source, H, dsize, float32=True),
            "centre +0.5": warped(source, moved(.5, .5) @ H @ moved(-.5, -.5), dsize),
            "centre -0.5": warped(source, moved(-.5, -.5) @ H @ moved(.5, .5), dsize),
            "centre +0.5 x": warped(source, moved(.5, 0) @ H @ moved(-.5, 0), dsize),
            "OFF border": warped(source, H @ moved(1, 1), dsize), "OFF out +x": warped(source, moved(1, 0) @ H, dsize),
            "OFF out -y": warped(source, moved(0, -1) @ H, dsize), "OFF in +x": warped(source, H @ moved(1, 0), dsize),
        }
        for kind, got in warps.items():
            within = min([warp_error(got, source, H, dsize, inside=inside)] + [
                blurred_difference(got, warp(source, moved(cx, cy) @ H @ moved(-cx, -cy), dsize), inside)
                for cx, cy in HALF_PIXEL_OFFSETS])   # (as the rule: a centre half a pixel off in both images)
            best = min(blurred_difference(got, warp(source, moved(dx, dy) @ H, dsize), inside)
                       for dx, dy in WHOLE_PIXEL_OFFSETS)
            ratio = best / within if within > 0 else np.inf
            if kind.startswith("OFF"):
                worst_off = max(worst_off, ratio if ratio < 1 else 0.0)   # (those it can tell at all)
            else:
                worst_legitimate = min(worst_legitimate, ratio)
            print(f"{name:<10}{str(np.round(H[:2], 2).tolist())[:32]:<34}{kind:<16}{within:>8.2f}{best:>8.2f}{ratio:>8.2f}")
    print(f"\nlegitimate warps: smallest ratio {worst_legitimate:.2f}; warps a pixel off, told: largest ratio "
          f"{worst_off:.2f}; the rule's ratio {WHOLE_PIXEL_RATIO}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
