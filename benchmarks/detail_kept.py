"""How much of a warp's fine detail legitimate interpolations keep, and how much a blur after the warp leaves.

Prints, for four photographs and four affine maps, the mean squared Laplacian of the warped image (over the
covered area, its border left out) as a share of bilinear's: nearest, cubic and Lanczos warps, cv2.resize with
INTER_AREA where the map shrinks, and a 3x3 Gaussian blur after the bilinear warp. compare.DETAIL_KEPT sits
between the smallest legitimate share of the maps that do not shrink and the largest blurred one; maps that shrink
(INTER_AREA keeps as little as 0.38 at a quarter) are not measured by the judges.

    python benchmarks/detail_kept.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from autograder.engine.compare import DETAIL_KEPT, detail_kept  # noqa: E402
from fixtures.images import photo  # noqa: E402

MAPS = {"shear 0.5": [[1, 0.5, 0], [0, 1, 0]], "affine": [[0.8, 0.3, 10], [-0.2, 0.9, 40]],
        "scale 1.5": [[1.5, 0, 0], [0, 1.5, 0]], "scale 0.6": [[0.6, 0, 0], [0, 0.6, 0]],
        "scale 0.5": [[0.5, 0, 0], [0, 0.5, 0]], "scale 0.25": [[0.25, 0, 0], [0, 0.25, 0]]}


def main() -> int:
    legit, shrinking, blurred = [], [], []
    for name in ("astronaut", "coffee", "rocket", "chelsea"):
        source = photo(name, (240, 180))
        for label, M in MAPS.items():
            M = np.float64(M)
            expected = cv2.warpAffine(source, M, (240, 180), flags=cv2.INTER_LINEAR)
            inside = cv2.warpAffine(np.ones(source.shape[:2], np.uint8), M, (240, 180), flags=cv2.INTER_NEAREST) > 0
            shares = {flag: detail_kept(cv2.warpAffine(source, M, (240, 180), flags=code), expected, inside)
                      for flag, code in (("nearest", cv2.INTER_NEAREST), ("cubic", cv2.INTER_CUBIC),
                                         ("lanczos", cv2.INTER_LANCZOS4))}
            if M[0, 0] < 1 and M[0, 1] == 0:
                shrunk = cv2.resize(source, None, fx=M[0, 0], fy=M[1, 1], interpolation=cv2.INTER_AREA)
                canvas = np.zeros_like(source)
                canvas[:shrunk.shape[0], :shrunk.shape[1]] = shrunk
                shares["resize area"] = detail_kept(canvas, expected, inside)
            blur = detail_kept(cv2.GaussianBlur(expected, (3, 3), 0), expected, inside)
            (shrinking if abs(np.linalg.det(M[:, :2])) < 0.75 else legit).extend(shares.values())
            blurred.append(blur)
            print(f"{name:10} {label:10} " + " ".join(f"{k} {v:.2f}" for k, v in shares.items()) + f" | blur {blur:.2f}")
    print(f"legitimate, maps that do not shrink (measured): at least {min(legit):.2f}; maps that shrink (not "
          f"measured): at least {min(shrinking):.2f}; blurred: at most {max(blurred):.2f}; threshold {DETAIL_KEPT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
