"""Lab 9: the reference passes, the skeleton scores 0, usual mistakes are named."""

import pytest

from autograder.labs.mistakes.lab09 import ADVICE, MISTAKES
from conftest import assert_advice_case, assert_all_not_implemented, assert_full_marks, assert_mistake_named

MODULE = "lab09_camera"


def test_reference_scores_full_marks(reference_result):
    assert_full_marks(reference_result, "lab09")


def test_skeleton_scores_zero_with_not_implemented(skeleton_result):
    assert_all_not_implemented(skeleton_result, "lab09")


@pytest.mark.parametrize("name", sorted(MISTAKES))
@pytest.mark.xdist_group("lab09")
def test_mistake_is_diagnosed(name):
    assert_mistake_named(MODULE, *MISTAKES[name])


@pytest.mark.parametrize("name", sorted(ADVICE))
@pytest.mark.xdist_group("lab09")
def test_convention_is_advice_not_points(name):
    assert_advice_case(MODULE, *ADVICE[name])
