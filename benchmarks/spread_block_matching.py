"""How far legitimate block matchers spread on lab 12's scenes (the margins' evidence).

Lab 12's block-matching checks accept a bad-pixel rate up to the worst
legitimate matcher's on the same scene plus a small slack, never "reference + k"
on one scene. This script measures the legitimate matchers on every scene the
checks use (public and hidden) and prints, per scene, each matcher's bad-pixel
rate and the spread above the reference:

- the reference ``block_matching`` (mean SSD over the block, argmin);
- SSD after a Gaussian prefilter of both views (sigma 1, a common textbook step);
- SAD (sum of absolute differences) instead of SSD;
- the lab sheet's own recipe, ``cv2.StereoBM`` with its defaults, as the
  skeleton tells a careful student to use it (``numDisparities`` rounded up to a
  multiple of 16, output divided by 16, invalid pixels and disparities above
  ``max_disparity`` set to 0).

Then, for comparison, a known mistake on the same scenes: the SSD computed on the uint8
images themselves (the squares wrap around), which the random-dot scene of black and
white dots must fail.

Pixels left of the search band (``x < numDisparities + block_size // 2``), where
no matcher can search the whole range, are not judged (``fixtures.lab12.band``).
The ends of the range are judged apart: pixels at infinity (the fraction given
d >= 1) and pixels at d = max_disparity (the fraction given it: ``cv2.StereoBM``'s
recipe sets its sub-pixel estimates above max_disparity invalid, half of them).

    python benchmarks/spread_block_matching.py

The figures it prints are the ones ``fixtures/make_lab12_figures.py`` stores as
``legitimate`` (the worst of these matchers) and the checks use.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from fixtures import lab12  # noqa: E402
from fixtures.make_lab12_figures import (BLOCK_MATCHING_SCENES, block_matching_figures,  # noqa: E402
                                         legitimate_matchers)


def scenes() -> dict:
    """The checks' scenes (public, then hidden if this copy has them) and a few more."""
    chosen = dict(BLOCK_MATCHING_SCENES)
    try:
        from autograder.labs.hidden import lab12 as hidden
        for draw in range(3):   # its sensor noise is drawn per submission
            chosen[f"hidden: noisy random dots (draw {draw})"] = (
                lambda draw=draw: hidden.block_matching_scene(np.random.default_rng(draw)), 9)
    except ImportError:
        pass
    for seed in (13, 14, 15):
        chosen[f"random dots (seed {seed}, noise 2)"] = (
            lambda seed=seed: lab12.random_dot_scene(seed, n_boxes=3, noise=2.0), 9)
    chosen["motorcycle, block 5"] = (lambda: lab12.scene("motorcycle"), 5)
    return chosen


def known_mistakes() -> dict:
    """Matchers that are wrong, for comparison: they must land above the accepted rate."""
    import cv2
    import numpy as np

    def uint8_ssd(left, right, max_disparity, block_size):
        # the squared differences computed on the uint8 images themselves: they wrap around
        height, width = left.shape
        costs = np.full((max_disparity + 1, height, width), np.inf)
        for d in range(max_disparity + 1):
            shifted = np.zeros_like(right)
            shifted[:, d:] = right[:, :width - d]
            costs[d] = cv2.boxFilter(((left - shifted) ** 2).astype(np.float64), -1, (block_size, block_size))
            costs[d, :, :d] = np.inf
        return np.argmin(costs, axis=0).astype(np.float64)

    return {"uint8 SSD (wrong)": uint8_ssd}


def main() -> None:
    matchers = legitimate_matchers()
    names = list(matchers)
    print("bad-pixel rates right of the search band (error > 1 px or invalid, truth known)")
    print(f"{'scene':<36}{'block':>6}" + "".join(f"{n:>20}" for n in names) + f"{'spread':>9}")
    worst = 0.0
    for key, (build, block_size) in scenes().items():
        figures = block_matching_figures(build(), block_size, matchers)
        spread = figures["legitimate"] - figures["reference"]
        worst = max(worst, spread)
        print(f"{key:<36}{block_size:>6}" + "".join(f"{figures['bad'][n]:>20.1%}" for n in names)
              + f"{spread:>+9.1%}")
        if figures["far_legitimate"] or key == "zero_disparity":
            print(f"{'  pixels at infinity given d >= 1':<42}"
                  + "".join(f"{figures['far_wrong'][n]:>20.1%}" for n in names))
        if figures["top_legitimate"] < 1:
            print(f"{'  pixels at d = max_disparity given it':<42}"
                  + "".join(f"{figures['top_found'][n]:>20.1%}" for n in names))
    print(f"largest spread above the reference: {worst:+.1%}")
    print()
    print("known mistakes (the check accepts the worst legitimate rate + 3 points):")
    for key, (build, block_size) in scenes().items():
        legitimate = block_matching_figures(build(), block_size, matchers)["legitimate"]
        wrong = block_matching_figures(build(), block_size, {**matchers, **known_mistakes()})["bad"]
        print(f"{key:<36}{block_size:>6}  " + "".join(f"{name}: {wrong[name]:.1%} (accepted up to "
                                                      f"{legitimate + 0.03:.1%})" for name in known_mistakes()))


if __name__ == "__main__":
    main()
