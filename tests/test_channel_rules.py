"""The API's rule for functions that take an image (the input's dtype and channel count come
back) and the conventions a function's docstring pins (undistortion keeps K): an answer that
breaks them is judged, and loses the points the contract implies, with its cause named."""

import numpy as np

from autograder.engine.checks import Trial
from autograder.engine.registry import select


def test_compare_images_with_another_channel_count_attaches_no_difference_map():
    """A BGR answer for a grey truth (or grey for BGR) is the check's to judge: attaching the
    pictures must not raise (it did: every warp check of labs 7-10 ended in a grader error)."""
    trial = Trial(None, select(["lab07.ex1"])[0].checks[0])
    grey = np.zeros((12, 16), np.uint8)
    bgr = np.zeros((12, 16, 3), np.uint8)
    trial.compare_images("grey in, BGR out", grey, grey, bgr)
    trial.compare_images("BGR in, grey out", bgr, bgr, grey)
    trial.compare_images("same shape", bgr, bgr, bgr)
    [mismatched, swapped, same] = trial.artifacts()
    assert "difference" not in [item["label"] for item in mismatched.items]
    assert "difference" not in [item["label"] for item in swapped.items]
    assert "difference" in [item["label"] for item in same.items]
