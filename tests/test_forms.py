"""Wrong forms named from what was measured: a result's shape, NumPy's own error (issue 26)."""

from __future__ import annotations

import numpy as np
import pytest

from autograder.engine.forms import exception_form, scale_form, shape_form
from conftest import assert_mistake_named, graded_case, named_mistakes


def numpy_error(operation) -> str:
    """The message NumPy gives for ``operation`` (this NumPy's own wording, not a copy of it)."""
    with pytest.raises((ValueError, IndexError)) as raised:
        operation()
    return f"project() raised {type(raised.value).__name__}: {raised.value}"


# ------------------------------------------------------------------ shapes
@pytest.mark.parametrize("got, expected, words", [
    ((2, 3), (3, 3), "2x3 affine form"),
    ((3, 3), (2, 3), "3x3 homogeneous matrix; its top 2 rows"),
    ((3, 3), (3, 4), "last column is missing"),
    ((2, 2), (3, 3), "2x2 linear part alone"),
    ((3, 3), (4, 4), "3x3 linear part alone"),
    ((4, 2), (2, 4), "transposed"),
    ((12, 1, 2), (None, 2), "(N, 1, 2) point layout"),
    ((12, 3), (None, 2), "still homogeneous"),
    ((12, 4), (None, 3), "still homogeneous"),
    ((9,), (3, 3), "flattened"),
    ((5, 1), (5,), "column of shape (5, 1)"),
    ((1, 5), (None,), "row of shape (1, 5)"),
    ((120, 160, 3), (120, 160), "grey in, grey out"),
    ((120, 160), (120, 160, 3), "BGR in, BGR out"),
    ((120, 160, 1), (120, 160), "channel axis of length 1"),
    ((120,), (120, 160), "indexed on its last axis"),
    ((16, 20, 2), (4, 20, 2), "16 = 4 x 4"),
    ((9, 2), (3, 2), "9 = 3 x 3"),
    ((3, 120, 160), (120, 160, 3), "channels come first"),
])
def test_a_recognised_form_is_named_from_the_shape(got, expected, words):
    form = shape_form(got, expected)
    assert form is not None and words in form.sentence and form.sentence.startswith("it looks")
    assert form.mistake


@pytest.mark.parametrize("got, expected", [
    ((1, 2), (2, 2)), ((2, 2), (1, 2)),                    # no affine form of that size
    ((4, 4), (3, 3)), ((2, 2), (4, 4)), ((3, 3, 3), (3, 3)), ((12, 5), (None, 2)), ((7,), (3, 3)), ((2, 2), (2,)),
    ((12, 1, 3), (None, 2)),
    ((3, 3, 3), (3, 3)), ((120, 160, 2), (120, 160)), ((120, 160, 3), (None, 160)),   # no image of a known size
    ((16, 20, 3), (4, 20, 2)), ((9,), (3,)),   # a square count with other items; a flat 9 (a 3 x 3 flattened?)
])
def test_a_form_no_rule_knows_is_left_to_the_description(got, expected):
    assert shape_form(got, expected) is None


# ------------------------------------------------------------------ NumPy's errors
def test_a_per_row_value_kept_flat_is_named_from_the_broadcast_error():
    x = np.ones((15, 3))
    message = numpy_error(lambda: x[:, :2] / x[:, 2])
    form = exception_form(message)
    assert form is not None and "shape (15, 1)" in form.sentence and "x[:, 2:3]" in form.sentence


def test_points_not_made_homogeneous_are_named_from_the_product_error():
    H, points = np.eye(3), np.ones((10, 2))
    for operation in (lambda: points @ H.T, lambda: H @ points.T, lambda: np.dot(H, points.T)):
        form = exception_form(numpy_error(operation))
        assert form is not None and "homogeneous" in form.sentence, numpy_error(operation)


def test_points_stored_as_rows_multiplied_as_columns_are_named():
    H, points = np.eye(3), np.ones((10, 3))
    form = exception_form(numpy_error(lambda: np.dot(H, points)))
    assert form is not None and "pts @ M.T" in form.sentence


@pytest.mark.parametrize("operation", [
    lambda: np.ones(3) + np.ones(4),                       # two flat arrays: nothing to name
    lambda: np.ones((5, 7)) @ np.ones((3, 2)),             # sizes far apart: not the homogeneous 1
    lambda: np.ones((4, 2)) + np.ones((3, 2)),
    lambda: np.ones(3)[5],
])
def test_other_numpy_errors_are_left_as_they_are(operation):
    assert exception_form(numpy_error(operation)) is None


def test_an_unrelated_message_names_nothing():
    assert exception_form("project() raised KeyError: 'f'") is None
    assert exception_form("shapes (3,3) and (3,3) not aligned") is None


# ------------------------------------------------------------------ through a grading
def test_the_2x3_form_of_a_translation_is_named_in_the_feedback():
    source = '''
def translation_matrix(tx, ty):
    return np.float32([[1, 0, tx], [0, 1, ty]])
'''
    result = assert_mistake_named("lab07_transformations", "lab07.ex1", source, ["2x3 affine form"])
    assert any("affine form" in mistake for mistake, _ in named_mistakes(result, "lab07.ex1"))


def test_a_flat_w_is_named_when_numpy_refuses_the_division():
    source = '''
def transform_points(H, pts):
    pts = np.asarray(pts, dtype=float)
    x = np.hstack([pts, np.ones((len(pts), 1))]) @ np.asarray(H, dtype=float).T
    return x[:, :2] / x[:, 2]
'''
    result = graded_case("lab08_homographies", "lab08.ex1", source)
    named = named_mistakes(result, "lab08.ex1")
    # (the forms' name, or -- first where it is confirmed -- the change of their code that keeps the column 2-D)
    assert named and all("per-row value kept flat" in name or (name == "repair:keep_axis" and "`x[:, :2] / x[:, 2:3]`" in message)
                         for name, message in named), named


# ------------------------------------------------------------------ a single factor
def test_a_vector_divided_by_its_own_entry_or_negated_is_named():
    C = np.array([0.5319, -0.231, 3.3973])
    divided = scale_form(C / C[2], C)
    assert divided is not None and "its own third entry" in divided.sentence
    assert "sign" in scale_form(-C, C).sentence


@pytest.mark.parametrize("got", [np.array([1.4, -0.4, 6.4]), np.array([0.7, -0.2, 3.0]),
                                 np.array([0.7, -0.2, 3.2])])
def test_another_factor_or_a_different_vector_names_nothing(got):
    """Twice the truth (no entry is 1/2), a vector not proportional to it, and the truth itself."""
    assert scale_form(got, np.array([0.7, -0.2, 3.2])) is None


def test_a_result_of_the_wrong_shape_is_told_its_wrong_type_too():
    """OpenCV's (N, 1) uint8 inlier mask where a flat boolean one is asked: mending the shape alone would
    be a second failed submission, so the type is told with it (and what 0/1 integers do as an index)."""
    import numpy as np

    from autograder.engine.checks import _kind_too

    mask = np.array([[1], [0], [1]], np.uint8)
    told = _kind_too(mask, None, "b")
    assert "uint8 where bool is asked" in told and "astype(bool)" in told, told
    assert _kind_too(mask.astype(bool), None, "b") == ""
    assert "float64 where uint8 is asked" in _kind_too(np.zeros((2, 2)), np.uint8, None)
    assert "astype(bool)" not in _kind_too(np.array([[2], [3]]), None, "b")


def test_a_colour_image_turned_grey_in_bgr_form_is_named_only_where_the_input_has_colour():
    from autograder.engine.forms import colours_lost

    rng = np.random.default_rng(0)
    colour = rng.integers(0, 256, (20, 30, 3), dtype=np.uint8)
    grey = np.repeat(colour[..., :1], 3, axis=2)   # three equal channels
    assert "colours are lost" in colours_lost(grey, [colour])
    assert colours_lost(colour, [colour]) == ""             # its colours kept
    assert colours_lost(grey, [grey]) == ""                 # a grey picture in BGR form stays grey
    assert colours_lost(grey[..., 0], [colour]) == ""       # (another shape: the channel forms' to name)
    black = (colour / 255.0).astype(np.uint8)               # a [0, 1] float cast to uint8: 0 nearly everywhere
    assert colours_lost(black, [colour]) == ""              # (equal channels, but no grey copy of anything)


def test_an_image_in_the_unit_range_cast_to_uint8_is_named_only_where_it_holds_nothing_but_0_and_1():
    from autograder.engine.forms import UNIT_RANGE_CAST, unit_range_cast

    rng = np.random.default_rng(1)
    expected = rng.integers(0, 256, (20, 30), dtype=np.uint8)
    cast = (expected / 255.0).astype(np.uint8)             # 0 everywhere but where expected is 255
    assert UNIT_RANGE_CAST in unit_range_cast(cast, expected)
    assert unit_range_cast(expected, expected) == ""         # the right image
    assert unit_range_cast(np.zeros_like(expected), np.full_like(expected, 7)) == ""   # (a dark expected image)
    assert unit_range_cast(cast.astype(float), expected) == ""                         # (not uint8: another form)
