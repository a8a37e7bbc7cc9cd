"""compare.wrapped_around: a blend computed in uint8 arithmetic that wrapped round is told from
other wrong images (a sum of k images taken modulo 256 before the division by k)."""

import numpy as np
import pytest

from autograder.engine.compare import wrapped_around


def _images(seed=0):
    rng = np.random.default_rng(seed)
    a = rng.integers(0, 256, (60, 80, 3)).astype(np.uint8)
    b = np.clip(a.astype(int) + rng.integers(-20, 21, a.shape), 0, 255).astype(np.uint8)
    return a, b


@pytest.mark.parametrize("k", [2, 3])
def test_a_sum_wrapped_before_its_division_is_found_with_its_count(k):
    a, b = _images()
    images = [a, b, a][:k]
    expected = np.mean([i.astype(np.float64) for i in images], axis=0)
    total = np.zeros_like(a)
    for image in images:
        total = total + image            # uint8 + uint8 stays uint8: wraps modulo 256
    got = total // k
    assert wrapped_around(got, expected, np.ones(a.shape[:2], bool)) == k


def test_right_and_otherwise_wrong_images_are_not_called_wrapped():
    a, b = _images(1)
    expected = (a.astype(np.float64) + b) / 2
    valid = np.ones(a.shape[:2], bool)
    assert wrapped_around(np.round(expected).astype(np.uint8), expected, valid) == 0       # right
    assert wrapped_around((expected / 2).astype(np.uint8), expected, valid) == 0           # half as bright
    assert wrapped_around(255 - np.round(expected).astype(np.uint8), expected, valid) == 0  # inverted
    assert wrapped_around(np.random.default_rng(2).integers(0, 256, a.shape), expected, valid) == 0


def test_pixels_no_sum_made_are_left_out_of_the_judgement():
    a, b = _images(3)
    expected = (a.astype(np.float64) + b) / 2
    got = np.round(expected).astype(np.uint8)
    got[:, :40] = (a[:, :40] + b[:, :40]) // 2   # the overlap only, as a two-image panorama's
    assert wrapped_around(got, expected, np.ones(a.shape[:2], bool)) == 2
