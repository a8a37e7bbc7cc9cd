"""Lab 7 tolerances, measured: how far legitimate affine estimates fall from the exact ones.

Prints, for ex5 (three point pairs) and ex6 (least squares), the largest point
error in pixels between each legitimate variant and the exact answer, over the
grader's own problem distributions (fixtures.lab07). The checks' tolerances
(autograder/labs/lab07.py: AFFINE_POINT_TOLERANCE, LSTSQ_POINT_TOLERANCE) sit
well above the worst legitimate figure and well below the smallest mistake.

    python benchmarks/fairness_lab07.py
"""

from __future__ import annotations

import cv2
import numpy as np

from fixtures import lab07 as truth


def point_error(A, B, pts) -> float:
    """Largest distance (px) between where two affine maps send the points."""
    return float(np.linalg.norm(truth.apply_affine(A, pts) - truth.apply_affine(B, pts), axis=1).max())


def region(pts):
    """The points and the corners of their bounding box: the data's extent."""
    lo, hi = pts.min(0), pts.max(0)
    return np.vstack([pts, [[lo[0], lo[1]], [hi[0], lo[1]], [lo[0], hi[1]], [hi[0], hi[1]]]])


# ------------------------------------------------------------------ ex5 variants
def ex5_variants(src, dst):
    S = np.hstack([src, np.ones((3, 1))])
    return {
        "cv2.getAffineTransform, float32 points (the lab sheet)":
            cv2.getAffineTransform(src.astype(np.float32), dst.astype(np.float32)),
        "np.linalg.solve, 3x3": np.linalg.solve(S, dst).T,
        "np.linalg.inv": (np.linalg.inv(S) @ dst).T,
        "6x6 system, lstsq": _six_by_six(src, dst),
    }


def _six_by_six(src, dst):
    M = np.zeros((6, 6))
    M[0::2, 0:2], M[0::2, 2], M[1::2, 3:5], M[1::2, 5] = src, 1, src, 1
    p, *_ = np.linalg.lstsq(M, dst.reshape(-1), rcond=None)
    return p.reshape(2, 3)


# ------------------------------------------------------------------ ex6 variants
def ex6_variants(src, dst):
    n = len(src)
    M = np.zeros((2 * n, 6))
    M[0::2, 0:2], M[0::2, 2], M[1::2, 3:5], M[1::2, 5] = src, 1, src, 1
    b = dst.reshape(-1)
    mean_s, mean_d = src.mean(0), dst.mean(0)
    centred = np.linalg.lstsq(src - mean_s, dst - mean_d, rcond=None)[0].T  # normalised: centre first
    A_c = np.hstack([centred, (mean_d - centred @ mean_s)[:, None]])
    variants = {
        "np.linalg.lstsq on the 2N x 6 system (the lab sheet)": np.linalg.lstsq(M, b, rcond=None)[0].reshape(2, 3),
        "normal equations, np.linalg.inv(M.T M) M.T b": (np.linalg.inv(M.T @ M) @ M.T @ b).reshape(2, 3),
        "np.linalg.pinv": (np.linalg.pinv(M) @ b).reshape(2, 3),
        "cv2.solve(DECOMP_SVD)": cv2.solve(M, b[:, None], flags=cv2.DECOMP_SVD)[1].reshape(2, 3),
        "centred (normalised) points": A_c,
        "float32 system (np.linalg.lstsq)": np.linalg.lstsq(M.astype(np.float32), b.astype(np.float32),
                                                            rcond=None)[0].reshape(2, 3),
    }
    return variants


def ex6_mistakes(src, dst, best):
    return {"first three points only": truth.least_squares_affine(src[:3], dst[:3]),
            **{name: wrong for name, wrong in truth.affine_mistakes(best).items()}}


def main():
    worst: dict[str, float] = {}
    for seed in range(500):
        rng = np.random.default_rng(seed)
        A, src = truth.random_affine(rng), truth.triangle(rng)
        dst = truth.apply_affine(A, src)
        for name, got in ex5_variants(src, dst).items():
            worst[name] = max(worst.get(name, 0.0), point_error(got, A, region(src)))
    print("ex5: largest point error (px) over the triangle's bounding box, 500 problems")
    for name, value in worst.items():
        print(f"  {value:10.2e}  {name}")
    smallest_mistake = min(point_error(wrong, A, region(src))
                           for seed in range(100)
                           for rng in [np.random.default_rng(seed)]
                           for A, src in [(truth.random_affine(rng), truth.triangle(rng))]
                           for wrong in truth.affine_mistakes(A).values())
    print(f"  {smallest_mistake:10.2e}  smallest named mistake (100 problems)")

    worst, smallest = {}, np.inf
    for seed in range(300):
        n = 4 + seed % 57
        src, dst, _, best = truth.noisy_correspondences(seed, n, noise=1.5)
        for name, got in ex6_variants(src, dst).items():
            worst[name] = max(worst.get(name, 0.0), point_error(got, best, src))
        smallest = min(smallest, min(point_error(wrong, best, src) for wrong in ex6_mistakes(src, dst, best).values()))
    print("ex6: largest point error (px) from the exact least-squares fit, over the source points, "
          "300 noisy problems (N = 4..60)")
    for name, value in worst.items():
        print(f"  {value:10.2e}  {name}")
    print(f"  {smallest:10.2e}  smallest named mistake")


if __name__ == "__main__":
    main()
