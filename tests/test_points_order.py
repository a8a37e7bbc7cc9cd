"""Points returned in another order than the input's are told so (a permutation of the expected rows), not only
as points far off."""

import numpy as np

from autograder.engine.judges import where_points_differ


def test_rows_in_another_order_are_told_as_a_permutation():
    expected = np.arange(20, dtype=float).reshape(10, 2) * [3.0, 7.0]
    got = expected[np.argsort(-expected[:, 0], kind="stable")]     # sorted far to near, say
    said = where_points_differ(got, expected, 1e-6)
    assert "in another order (your row 0 is the expected row 9)" in said


def test_points_off_or_repeated_are_no_permutation():
    expected = np.arange(20, dtype=float).reshape(10, 2)
    shifted = expected[::-1] + 0.5
    repeated = np.repeat(expected[:5], 2, axis=0)
    for got in (shifted, repeated):
        said = where_points_differ(got, expected, 1e-6)
        assert "another order" not in said and said.startswith("for ")
