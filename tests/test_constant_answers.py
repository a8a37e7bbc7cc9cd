"""A function that answers the same whatever it is given earns no points (autograder.engine.constant)."""

from __future__ import annotations

import numpy as np

from autograder.engine.constant import MISTAKE, _differ
from autograder.engine.runner import grade
from conftest import REFERENCE, mutant


def test_a_constant_earns_nothing_from_checks_that_compare_its_answers_with_each_other(tmp_path):
    """`return np.full(1, 0.5)` passed every check comparing the function's answers among themselves (a point alone
    and among many, integers and floats): 43 of the 464 public points in the hostile round of 2026-12-07."""
    constant = mutant(tmp_path, "lab09_camera", """
        def pinhole_project(*args, **kwargs):
            return np.full(1, 0.5)
        """)
    result = grade(constant, ["lab09.ex1"], pictures="none", include_hidden=False)
    graded = [c for e in result.exercises for c in e.checks if c.max_score > 0]
    assert graded and all(c.score == 0 for c in graded)
    zeroed = [c for c in graded if c.mistake == MISTAKE]
    assert zeroed and all("gave one same answer to each of the" in c.message for c in zeroed)
    # (the reference, whose answers to a point given as integers and as floats are one answer, loses nothing)
    reference = grade(REFERENCE, ["lab09.ex1"], pictures="none", include_hidden=False)
    assert all(c.score == c.max_score for e in reference.exercises for c in e.checks)


def test_answers_alike_up_to_scale_and_sign_are_one_answer():
    """Two inputs whose right answers differ only by a scale or a sign (F and 2F give E and 2E) do not show
    that an answer equal for both ignores its input: the labs ask for such matrices up to scale and sign."""
    E = np.array([[0.0, -1, 2], [1, 0, -3], [-2, 3, 0]])
    assert not _differ(E, -2.5 * E)
    assert not _differ((E, np.array([1.0, 2.0])), (3 * E, np.array([1.0, 2.0])))
    F = E + np.diag([1.0, 2.0, 3.0])
    assert _differ(F, F.T) and _differ(E, E[:2]) and _differ([E], [E, E])
    assert not _differ(np.array([np.nan, 1.0]), np.array([np.nan, 2.0]))


def test_a_large_answer_is_compared_by_a_sample_of_its_entries():
    """The gate holds a sample of a large answer, never the whole (an image per function, a stack of patterns): alike
    answers are alike in it, answers that differ anywhere much differ in it, and another shape is another answer."""
    from autograder.engine.constant import ALIKE, SAMPLE, _sampled
    from autograder.engine.inplace import same_answer

    image = np.random.default_rng(0).uniform(0, 255, (480, 640))
    kept = _sampled(image)
    assert kept[0] == image.shape and kept[1].size <= SAMPLE
    assert same_answer(_sampled(image + 1e-9), kept, ALIKE)
    assert not same_answer(_sampled(image[::-1]), kept, ALIKE)
    assert not same_answer(_sampled(image.reshape(640, 480)), kept, ALIKE)
    small = (np.eye(3), np.ones(5))
    assert _sampled(small) == small or all(a is b for a, b in zip(_sampled(small), small))
