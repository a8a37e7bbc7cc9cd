"""A warp whose content is right but whose uncovered pixels are not black is told what they hold
(issue 35: a location without a cause is only described): wrapped round (np.roll, BORDER_WRAP),
the nearest edge repeated, the image mirrored, the input left in place, one constant level."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from autograder.engine.judges import FILLS, KEPT_INPUT, ROLL_HINT, fill_held
from autograder.engine.runner import grade
from conftest import check_results, mutant
from fixtures.images import as_homography, coverage, photo, warp

SOURCE = photo("astronaut", (240, 180))
SHIFT = np.array([[1.0, 0, 37], [0, 1, 21]])
ROTATION = cv2.getRotationMatrix2D((90.0, 70.0), 25.0, 0.9)


def filled(M, border, value=0):
    return cv2.warpPerspective(SOURCE, as_homography(M), SOURCE.shape[1::-1], borderMode=border, borderValue=value)


@pytest.mark.parametrize("M", [SHIFT, ROTATION], ids=["shift", "rotation"])
@pytest.mark.parametrize("border", sorted(FILLS))
def test_a_border_rules_fill_is_told_by_that_rule(M, border):
    _, outside = coverage(M, SOURCE.shape)
    assert fill_held(filled(M, border), SOURCE, M, None, outside) == FILLS[border]


def test_the_input_left_in_place_and_a_constant_fill_are_told():
    _, outside = coverage(SHIFT, SOURCE.shape)
    kept = np.where(warp(np.ones_like(SOURCE), SHIFT) > 0, warp(SOURCE, SHIFT), SOURCE)
    assert fill_held(kept, SOURCE, SHIFT, None, outside) == KEPT_INPUT
    white = filled(SHIFT, cv2.BORDER_CONSTANT, (255, 255, 255))
    assert fill_held(white, SOURCE, SHIFT, None, outside).startswith("are all 255")


def test_black_noise_and_a_fill_nothing_explains_are_not_named():
    _, outside = coverage(SHIFT, SOURCE.shape)
    noisy = warp(SOURCE, SHIFT).copy()
    noisy[outside] = np.random.default_rng(0).integers(0, 256, (int(outside.sum()), 3), dtype=np.uint8)
    assert fill_held(noisy, SOURCE, SHIFT, None, outside) == ""
    assert fill_held(warp(SOURCE, SHIFT), SOURCE, SHIFT, None, np.zeros(outside.shape, bool)) == ""


def test_a_translation_by_np_roll_is_told_it_wraps_round_and_why(tmp_path):
    source = """
        def translate(image, tx=100, ty=50):
            return np.roll(np.roll(image, int(ty), axis=0), int(tx), axis=1)
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex1"], pictures="none")
    partial = [c for c in check_results(result, "lab07.ex1") if not c.passed and c.name.startswith("translate(")]
    assert partial, "np.roll's wrapped fill loses the fill's points"
    assert all(FILLS[cv2.BORDER_WRAP] in c.message for c in partial), [c.message for c in partial]
    assert all(c.hint == ROLL_HINT for c in partial)


def test_a_replicated_border_is_told_so_and_not_told_about_np_roll(tmp_path):
    source = """
        def translate(image, tx=100, ty=50):
            M = np.float32([[1, 0, tx], [0, 1, ty]])
            h, w = image.shape[:2]
            return cv2.warpAffine(image, M, (w, h), borderMode=cv2.BORDER_REPLICATE)
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex1"], pictures="none")
    partial = [c for c in check_results(result, "lab07.ex1") if not c.passed and c.name.startswith("translate(")]
    assert partial and all(FILLS[cv2.BORDER_REPLICATE] in c.message for c in partial)
    assert not any("np.roll" in c.hint for c in partial)
    # a border mode passed is not "already black": the one it passes is named, the constant one asked for
    assert all("Your code uses cv2.BORDER_REPLICATE, which fills them so." in c.message for c in partial)
    assert all("your code already" not in c.hint and "cv2.BORDER_CONSTANT" in c.hint for c in partial)


def test_a_constant_border_of_another_value_is_told_to_look_elsewhere(tmp_path):
    source = """
        def translate(image, tx=100, ty=50):
            M = np.float32([[1, 0, tx], [0, 1, ty]])
            h, w = image.shape[:2]
            return cv2.warpAffine(image, M, (w, h), borderMode=cv2.BORDER_CONSTANT, borderValue=(255, 255, 255))
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex1"], pictures="none")
    partial = [c for c in check_results(result, "lab07.ex1") if not c.passed and c.name.startswith("translate(")]
    assert partial and all("your code already uses cv2.BORDER_CONSTANT" in c.hint and "borderValue" in c.hint
                           for c in partial), [c.hint for c in partial]
