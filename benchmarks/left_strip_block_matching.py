"""Lab 12's left strip: how many pixels each block matcher sends left of the right image.

A left pixel ``x`` has its match at ``x - d`` in the right image, whose first column is 0, so a
disparity above ``x`` (+ half a pixel) points where the right image has no pixel. The checks
(``left_strip_tip`` in ``autograder/labs/lab12.py``, a tip worth no points: the API leaves the band open) allow up
to ``LEFT_STRIP_ALLOWED`` of the strip ``x < max_disparity`` so; this script prints the evidence, per scene the
checks use:

- the legitimate matchers (``fixtures.make_lab12_figures.legitimate_matchers``: the reference,
  a Gaussian prefilter, SAD, the lab sheet's ``cv2.StereoBM``), ``cv2.StereoBM`` with nothing
  clipped, a loop over the columns ``x >= d``, and the reference's NCC;
- searches against a right image padded or wrapped round, the ``x < d`` cost left finite
  (``np.roll``, ``np.pad`` with zeros, edge or reflection), for SSD and NCC: the slips.

    python benchmarks/left_strip_block_matching.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from autograder.labs.lab12 import LEFT_STRIP_ALLOWED, PAST_THE_EDGE  # noqa: E402
from fixtures import lab12  # noqa: E402
from fixtures.make_lab12_figures import legitimate_matchers, load_reference  # noqa: E402

# (scene, max_disparity or None for the scene's, block_size, cost): the checks' calls
CASES = (("random_dots", 16, 9, "ssd"), ("random_dots", None, 9, "ssd"), ("slanted", None, 7, "ssd"),
         ("motorcycle", None, 9, "ssd"), ("motorcycle", None, 9, "ncc"), ("zero_disparity", None, 9, "ssd"))


def padded(reference, mode: str, cost: str):
    """A matcher comparing every d at every column against the right image padded by ``mode``
    (``"roll"``: wrapped round)."""
    def match(left, right, max_disparity, block_size):
        left, right = reference._grey_float(left), reference._grey_float(right)
        width = left.shape[1]
        if mode == "roll":
            shifts = [np.roll(right, d, axis=1) for d in range(max_disparity + 1)]
        else:
            wide = np.pad(right, ((0, 0), (max_disparity, 0)), **({"mode": mode} if mode != "zeros" else {}))
            shifts = [wide[:, max_disparity - d:max_disparity - d + width] for d in range(max_disparity + 1)]
        mean = lambda image: reference._box_mean(image, block_size)  # noqa: E731
        if cost == "ssd":
            volume = [mean((left - shifted) ** 2) for shifted in shifts]
        else:
            mean_l = mean(left)
            std_l = np.sqrt(np.maximum(mean(left * left) - mean_l ** 2, 0.0))
            volume = []
            for shifted in shifts:
                mean_r = mean(shifted)
                std_r = np.sqrt(np.maximum(mean(shifted * shifted) - mean_r ** 2, 0.0))
                below = std_l * std_r
                ncc = np.divide(mean(left * shifted) - mean_l * mean_r, below, out=np.zeros_like(below),
                                where=below > 1e-6)
                volume.append(-ncc)
        return np.argmin(np.stack(volume), axis=0).astype(np.float64)
    return match


def matchers(cost: str) -> tuple[dict, dict]:
    """(legitimate, slips) for ``cost``."""
    reference = load_reference()
    slips = {f"{mode}, x < d not excluded": padded(reference, mode, cost)
             for mode in ("roll", "zeros", "edge", "reflect")}
    if cost == "ncc":
        return {"reference NCC": lambda l, r, m, b: reference.block_matching(l, r, m, b, "ncc")}, slips

    def stereo_bm_unclipped(left, right, max_disparity, block_size):
        n = 16 * -(-(max_disparity + 1) // 16)
        return cv2.StereoBM_create(numDisparities=n, blockSize=block_size).compute(left, right) / 16.0

    def columns_from_d(left, right, max_disparity, block_size):
        left, right = reference._grey_float(left), reference._grey_float(right)
        height, width = left.shape
        best, out = np.full((height, width), np.inf), np.zeros((height, width))
        for d in range(max_disparity + 1):
            squared = np.zeros((height, width))
            squared[:, d:] = (left[:, d:] - right[:, :width - d]) ** 2
            cost = np.full((height, width), np.inf)
            cost[:, d:] = cv2.boxFilter(squared, -1, (block_size, block_size), normalize=False)[:, d:]
            better = cost < best
            best[better], out[better] = cost[better], d
        return out

    legitimate = dict(legitimate_matchers(), **{"cv2.StereoBM, nothing clipped": stereo_bm_unclipped,
                                                "a loop over d, columns x >= d": columns_from_d})
    return legitimate, slips


def past_the_edge(got, max_disparity: int) -> float:
    """The share of the strip x < max_disparity given a disparity above x + PAST_THE_EDGE."""
    strip = np.asarray(got, np.float64)[:, :max_disparity]
    with np.errstate(invalid="ignore"):
        past = np.isfinite(strip) & (strip > np.arange(strip.shape[1])[None, :] + PAST_THE_EDGE)
    return float(past.mean())


def main():
    print(f"accepted: {LEFT_STRIP_ALLOWED:.0%} of the strip")
    for name, max_disparity, block_size, cost in CASES:
        scene = lab12.scene(name)
        max_disparity = max_disparity or scene.max_disparity
        print(f"\n{name}, max_disparity {max_disparity}, block {block_size}, {cost}")
        legitimate, slips = matchers(cost)
        for group, found in (("legitimate", legitimate), ("slip", slips)):
            for label, match in found.items():
                share = past_the_edge(match(np.array(scene.left), np.array(scene.right), max_disparity, block_size),
                                      max_disparity)
                print(f"  {group:10s} {label:32s} {share:6.1%}")


if __name__ == "__main__":
    main()
