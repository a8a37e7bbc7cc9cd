"""A NumPy error is explained from the student's line that raised it (issue 35: "relayed
exceptions that do not say which input or why").

``np.hstack([R, t])`` raises "all the input arrays must have same number of dimensions" for a
translation given as a (3,) vector: the message alone names neither ``t`` nor the caller's
shape. :mod:`autograder.engine.raised` reads the raising line and binds the call's arguments
to the student's own parameters; it names the cause only when the array the error points at
is a parameter, unchanged before that line, given 1-D.
"""

from __future__ import annotations

import ast
import textwrap

import numpy as np
import pytest

from autograder.engine.hints import read_code
from autograder.engine.raised import MISTAKE, explained
from autograder.engine.runner import grade
from conftest import check_results, mutant

NDIM = ("all the input arrays must have same number of dimensions, but the array at index 0 has 2 "
        "dimension(s) and the array at index 1 has 1 dimension(s)")
R, t = np.eye(3), np.array([1.0, 2.0, 3.0])


def traceback_at(line: int, function: str = "f") -> str:
    return f'Traceback (your code):\n  File "lab.py", line {line}, in {function}\n    ...\nValueError: {NDIM}'


def explain(source: str, line: int, args=(R, t), raised_in: str = "f"):
    """What is said of ``f(*args)`` raising NDIM at ``line`` of ``raised_in``."""
    return explained(read_code(textwrap.dedent(source)), traceback_at(line, raised_in), NDIM, "f", args, {})


NAMED = {
    "hstack of the parameters": ("""
        def f(R, t):
            return np.hstack([R, t])
        """, 3),
    "concatenate of converted parameters": ("""
        def f(rotation, translation):
            Rt = np.concatenate((np.asarray(rotation, float), translation.astype(np.float64)), axis=1)
            return Rt
        """, 3),
}
NAMED["the vector converted in place first"] = ("""
        def f(R, t):
            t = np.asarray(t, dtype=np.float64)
            return np.hstack([R, t])
        """, 4)
NOT_NAMED = {
    "the vector was reshaped before": ("""
        def f(R, t):
            t = t.reshape(1, 3)
            return np.hstack([R, t])
        """, 4),
    "the 1-D array is not a parameter": ("""
        def f(R, t):
            c = -R.T @ t
            return np.hstack([R, c])
        """, 4),
    "the line is in a helper": ("""
        def join(a, b):
            return np.hstack([a, b])

        def f(R, t):
            return join(R, t)
        """, 3),
}


@pytest.mark.parametrize("name", sorted(NAMED))
def test_a_vector_given_1d_and_joined_to_a_matrix_is_named(name):
    source, line = NAMED[name]
    form = explain(source, line)
    assert form is not None and form.mistake == MISTAKE
    assert "shape (3,)" in form.sentence and f"(line {line})" in form.sentence


@pytest.mark.parametrize("name", sorted(NOT_NAMED))
def test_what_the_line_does_not_show_is_not_named(name):
    source, line = NOT_NAMED[name]
    assert explain(source, line, raised_in="join" if "helper" in name else "f") is None


def test_a_column_given_is_not_named():
    source, line = NAMED["hstack of the parameters"]
    assert explain(source, line, args=(R, t.reshape(3, 1))) is None   # not 1-D as given: another cause


def test_a_camera_matrix_joining_a_flat_translation_is_told_in_grading(tmp_path):
    source = """
        def camera_matrix(K, R, t):
            return np.asarray(K, float) @ np.hstack([np.asarray(R, float), np.asarray(t, float)])
        """
    result = grade(mutant(tmp_path, "lab09_camera", source), ["lab09.ex3"], pictures="none")
    failed = [c for c in check_results(result, "lab09.ex3") if not c.passed]
    assert failed and any(c.mistake == MISTAKE and "joins `t` as it was given, shape (3,)" in c.message
                          for c in failed), [c.message for c in failed]


def test_a_fractional_parameter_in_a_slice_is_named():
    source = """
        def f(image, tx, ty):
            out = np.zeros_like(image)
            out[ty:, tx:] = image[:-ty or None, :-tx or None]
            return out
        """
    message = "slice indices must be integers or None or have an __index__ method"
    form = explained(read_code(textwrap.dedent(source)), traceback_at(4), message, "f", (R, 12.5, 3), {})
    assert form is not None and "`tx`, given 12.5 here, in a slice" in form.sentence
    assert explained(read_code(textwrap.dedent(source)), traceback_at(4), message, "f", (R, 12.0, 3), {}) is None


@pytest.mark.parametrize("message, mistake", [
    ("could not broadcast input array from shape (150,200) into shape (150,200,3)", "grey image written into a colour"),
    ("could not broadcast input array from shape (150,200,3) into shape (150,200)", "colour image written into a grey"),
])
def test_a_grey_and_a_colour_image_written_into_each_other_are_named(message, mistake):
    from autograder.engine.forms import exception_form

    form = exception_form(f"draw_matches() raised ValueError: {message}")
    assert form is not None and mistake in form.mistake
    assert exception_form("could not broadcast input array from shape (15,20) into shape (150,200,3)") is None


def test_an_axis_the_given_array_lacks_is_named_at_its_line():
    """`image.shape[2]` raising "tuple index out of range" for a grey image the check gave: the line,
    the name and the shape given are said; not when the array was reshaped before, nor for an axis it has."""
    raised = "tuple index out of range"
    grey = np.zeros((4, 5), np.uint8)

    def told(source: str, line: int):
        text = f'Traceback (your code):\n  File "lab.py", line {line}, in f\n    ...\nIndexError: {raised}'
        return explained(read_code(textwrap.dedent(source)), text, raised, "f", (grey,), {})

    form = told("""
        def f(image):
            out = np.zeros_like(image)
            for c in range(image.shape[2]):
                out[..., c] = image[..., c]
            return out
        """, 4)
    assert form is not None and "`image.shape[2]` (line 4)" in form.sentence and "(4, 5)" in form.sentence, form
    assert "grey image" in form.sentence
    assert told("""
        def f(image):
            image = image.reshape(4, 5, 1)
            return image.shape[2]
        """, 4) is None
    assert told("""
        def f(image):
            return [image.shape[1]][3]
        """, 3) is None


def test_an_index_beyond_the_given_array_is_named_at_its_line():
    """`pts[:, 2]` raising "index 2 is out of bounds for axis 1 with size 2" for (N, 2) points: the line,
    the name and the shape given are said; not when the index is computed, nor for another array."""
    raised = "index 2 is out of bounds for axis 1 with size 2"
    pts = np.zeros((5, 2))

    def told(source: str, line: int):
        text = f'Traceback (your code):\n  File "lab.py", line {line}, in f\n    ...\nIndexError: {raised}'
        return explained(read_code(textwrap.dedent(source)), text, raised, "f", (pts,), {})

    form = told("""
        def f(pts):
            w = pts[:, 2]
            return pts[:, :2] / w[:, None]
        """, 3)
    assert form is not None and "`pts[:, 2]` (line 3)" in form.sentence and "(5, 2)" in form.sentence, form
    assert told("""
        def f(pts):
            k = 2
            return pts[:, k]
        """, 4) is None
    assert told("""
        def f(pts):
            other = np.zeros((5, 2))
            return other[:, 2]
        """, 4) is None


def test_a_singular_solve_of_a_vector_fixed_to_1_is_named():
    """`np.append(np.linalg.solve(F[:2, :2], -F[:2, 2]), 1.0)` raising "Singular matrix" (an epipole at
    infinity): the solve, its matrix, and the last entry fixed to 1 are said; a solve whose answer gets no
    1 appended is only located."""
    raised = "Singular matrix"
    F = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])

    def told(source: str, line: int):
        text = f'Traceback (your code):\n  File "lab.py", line {line}, in f\n    ...\nLinAlgError: {raised}'
        return explained(read_code(textwrap.dedent(source)), text, raised, "f", (F,), {})

    form = told("""
        def f(F):
            e = np.append(np.linalg.solve(F[:2, :2], -F[:2, 2]), 1.0)
            return e / np.linalg.norm(e)
        """, 3)
    assert form is not None and "`F[:2, :2]` is singular" in form.sentence and "fixed to 1" in form.sentence, form
    plain = told("""
        def f(F):
            return np.linalg.solve(F[:2, :2], -F[:2, 2])
        """, 3)
    assert plain is not None and "is singular" in plain.sentence and "fixed to 1" not in plain.sentence, plain


def test_what_is_said_of_a_missing_axis_or_a_singular_solve_holds_for_the_code_it_reads():
    """Points (N, 2) read with `.shape[2]` are not called a grey image; a 1 written before the solve's
    answer (or inside its arguments) is not the last entry fixed to 1."""
    def told(source: str, line: int, raised: str, args):
        text = f'Traceback (your code):\n  File "lab.py", line {line}, in f\n    ...\nError: {raised}'
        return explained(read_code(textwrap.dedent(source)), text, raised, "f", args, {})

    form = told("""
        def f(pts):
            return pts.shape[2]
        """, 3, "tuple index out of range", (np.zeros((10, 2)),))
    assert form is not None and "has no axis 2" in form.sentence and "grey" not in form.sentence, form
    F = np.zeros((3, 3))
    before = told("""
        def f(F):
            return np.append(1.0, np.linalg.solve(F[:2, :2], F[:2, 2] - 1))
        """, 3, "Singular matrix", (F,))
    assert before is not None and "is singular" in before.sentence and "fixed to 1" not in before.sentence, before


@pytest.mark.parametrize("second, message, told", [
    (np.zeros((150, 200), np.uint8),
     "all the input arrays must have same number of dimensions, but the array at index 0 has 3 dimension(s) and "
     "the array at index 1 has 2 dimension(s)", "convert `img2` to BGR first"),
    (np.zeros((200, 90, 3), np.uint8),
     "all the input array dimensions except for the concatenation axis must match exactly, but along dimension 0, "
     "the array at index 0 has size 180 and the array at index 1 has size 200", "as high as the taller one"),
])
def test_two_images_joined_as_they_came_are_named(second, message, told):
    """A matcher's canvas made by np.hstack([img1, img2]) of the images as given: a grey and a colour one,
    or two of different heights (both allowed by the API), raise; the line and the shapes say why."""
    source = """
        def f(img1, img2):
            canvas = np.hstack([img1, img2])
            return canvas
        """
    first = np.zeros((180, 240, 3), np.uint8)
    text = f'Traceback (your code):\n  File "lab.py", line 3, in f\n    ...\nValueError: {message}'
    form = explained(read_code(textwrap.dedent(source)), text, message, "f", (first, second), {})
    assert form is not None and told in form.sentence, form
    # (converted first, the images are no longer as they came: nothing is said of them)
    converted = source.replace("canvas = np.hstack", "img2 = img2[:180]\n            canvas = np.hstack")
    text = text.replace("line 3", "line 4")
    assert explained(read_code(textwrap.dedent(converted)), text, message, "f", (first, second), {}) is None


def test_a_single_point_joined_as_given_is_told_to_become_a_row_of_one_point():
    # `X = np.asarray(points)` keeps a (3,) point 1-D: hstack with a column of ones refuses it; a point is a row
    ndim = NDIM.replace("index 0 has 2", "index 0 has 1").replace("index 1 has 1", "index 1 has 2")
    source = textwrap.dedent("""
        def f(P, points):
            X = np.asarray(points, dtype=np.float64)
            Xh = np.hstack([X, np.ones((X.shape[0], 1))])
            return Xh @ P.T
        """)
    tb = f'Traceback (your code):\n  File "lab.py", line 4, in f\n    ...\nValueError: {ndim}'
    form = explained(read_code(source), tb, ndim, "f", (np.eye(3, 4), np.array([1.0, 2.0, 4.0])), {})
    assert form is not None and "a single point" in form.sentence and "np.atleast_2d(X)" in form.sentence, form


ZERO = "integer division or modulo by zero"
STRIPES = """
    def f(width, n_bits):
        width, n_bits = int(width), int(n_bits)
        stripe = width // 2 ** n_bits
        out = np.zeros(width, dtype=int)
        for u in range(width):
            out[u] = u // stripe
        return out
    """


def test_a_floor_division_rounding_a_divisor_to_zero_is_named_with_the_numbers_given():
    from autograder.engine.raised import ROUNDED_TO_ZERO

    form = explained(read_code(textwrap.dedent(STRIPES)), traceback_at(7), ZERO, "f", (5, 3), {})
    assert form is not None and form.mistake == ROUNDED_TO_ZERO, form
    assert "divides by `stripe` (line 7), which is 0 here (width=5, n_bits=3): `stripe = width // 2 ** n_bits` " \
           "(line 4) is a floor division of a smaller number by a larger one" in form.sentence


def test_a_floor_division_written_in_the_divisor_is_named_and_a_plain_zero_only_described():
    from autograder.engine.raised import ROUNDED_TO_ZERO, ZERO_DIVISOR

    written = STRIPES.replace("u // stripe", "u // (width // 2 ** n_bits)")
    form = explained(read_code(textwrap.dedent(written)), traceback_at(7), ZERO, "f", (5, 3), {})
    assert form is not None and form.mistake == ROUNDED_TO_ZERO
    assert "(width=5, n_bits=3): `width // 2 ** n_bits` is a floor division" in form.sentence
    plain = """
        def f(x1, x2):
            return 1.0 / (x2 - x1)
        """
    form = explained(read_code(textwrap.dedent(plain)), traceback_at(3), "float division by zero", "f", (2.0, 2.0), {})
    assert form is not None and form.mistake == ZERO_DIVISOR and "(x2=2.0, x1=2.0)" in form.sentence


def test_a_zero_divisor_the_code_does_not_show_is_not_named():
    looped = """
        def f(width, n_bits):
            stripe = 1
            for i in range(n_bits):
                stripe = width // 2 ** n_bits
            return width // stripe
        """
    assert explained(read_code(textwrap.dedent(looped)), traceback_at(6), ZERO, "f", (5, 3), {}) is None \
        or "stripe" not in explained(read_code(textwrap.dedent(looped)), traceback_at(6), ZERO, "f", (5, 3), {}).sentence
    from_an_array = """
        def f(points, n):
            return n // points.shape[0]
        """
    assert explained(read_code(textwrap.dedent(from_an_array)), traceback_at(3), ZERO, "f", (np.zeros((0, 2)), 4), {}) is None


def test_a_negative_shift_count_is_named_with_the_numbers_given():
    """`u >> (int(np.log2(width)) - n_bits)` with n_bits > log2(width): the count is worked out; a shift
    whose count cannot be, the only one on the line, is still the one; two such shifts name neither."""
    from autograder.engine.raised import NEGATIVE_SHIFT

    shifted = """
        def f(width, n_bits):
            width, n_bits = int(width), int(n_bits)
            out = np.zeros(width, dtype=int)
            for u in range(width):
                out[u] = u >> (int(np.log2(width)) - n_bits)
            return out
        """
    negative = "negative shift count"
    form = explained(read_code(textwrap.dedent(shifted)), traceback_at(6), negative, "f", (905, 10), {})
    assert form is not None and form.mistake == NEGATIVE_SHIFT, form
    assert "shifts by `int(np.log2(width)) - n_bits` (line 6), which is -1 here (n_bits=10, width=905)" in form.sentence
    unknown = shifted.replace("(int(np.log2(width)) - n_bits)", "(u - n_bits)")
    form = explained(read_code(textwrap.dedent(unknown)), traceback_at(6), negative, "f", (905, 10), {})
    assert form is not None and "shifts by `u - n_bits` (line 6), which is negative here" in form.sentence
    two = shifted.replace("u >> (int(np.log2(width)) - n_bits)", "(u >> (u - n_bits)) + (u << (n_bits - u))")
    assert explained(read_code(textwrap.dedent(two)), traceback_at(6), negative, "f", (905, 10), {}) is None


def test_one_value_per_axis_given_for_another_number_of_axes_is_named():
    """`ndimage.shift(image, (ty, tx))` on a colour image: two values for three axes, from the shape given; an
    array whose shape is not known (made in the function) names nothing."""
    from autograder.engine.raised import SEQUENCE_PER_AXIS

    shifted = """
        def f(image, tx, ty):
            from scipy import ndimage
            return ndimage.shift(image, (ty, tx), order=1)
        """
    rank = "sequence argument must have length equal to input rank"
    form = explained(read_code(textwrap.dedent(shifted)), traceback_at(4), rank, "f", (np.zeros((5, 6, 3)), 1, 2), {})
    assert form is not None and form.mistake == SEQUENCE_PER_AXIS, form
    assert "gives `ndimage.shift` `(ty, tx)`, 2 values, for `image` of shape (5, 6, 3), which has 3 axes (a colour " \
           "image" in form.sentence
    made = shifted.replace("ndimage.shift(image,", "ndimage.shift(image[..., None] * 1,")
    assert explained(read_code(textwrap.dedent(made)), traceback_at(4), rank, "f", (np.zeros((5, 6, 3)), 1, 2), {}) is None


NONE_SUBSCRIPT = "'NoneType' object is not subscriptable"


def test_a_helper_without_a_return_is_named_where_its_none_is_used():
    from autograder.engine.raised import NONE_RETURNED

    source = """
        def _normalise(points):
            T = np.eye(3)
            points = points @ T

        def f(R, t):
            moved = _normalise(R)
            return moved[:, :2]
        """
    form = explained(read_code(textwrap.dedent(source)), traceback_at(8), NONE_SUBSCRIPT, "f", (R, t), {})
    assert form is not None and form.mistake == NONE_RETURNED, form
    assert form.sentence.startswith("`_normalise(R)` (line 7) gives None: your `_normalise` has no `return` of a value"), form
    unpacked = """
        def _split(points):
            if len(points):
                return points[:, 0], points[:, 1]

        def f(R, t):
            x, y = _split(R)
            return x + y
        """
    form = explained(read_code(textwrap.dedent(unpacked)), traceback_at(7), "cannot unpack non-iterable NoneType object",
                     "f", (R, t), {})
    assert form is not None and "your `_split` can reach its end without a `return`" in form.sentence, form


def test_a_method_that_works_in_place_is_named_and_a_none_the_code_does_not_show_is_not():
    source = """
        def f(R, t):
            order = list(t).sort()
            return order[0]
        """
    form = explained(read_code(textwrap.dedent(source)), traceback_at(4), NONE_SUBSCRIPT, "f", (R, t), {})
    assert form is not None and "`.sort()` changes its object in place and returns None" in form.sentence, form
    returning = """
        def _helper(points):
            return points if len(points) else None

        def f(R, t):
            moved = _helper(R)
            return moved[:, :2]
        """
    assert explained(read_code(textwrap.dedent(returning)), traceback_at(7), NONE_SUBSCRIPT, "f", (R, t), {}) is None


def test_a_helper_without_a_return_is_told_in_grading(tmp_path):
    source = """
        def _diagonal(sx, sy):
            M = np.eye(3)
            M[0, 0], M[1, 1] = sx, sy

        def scaling_matrix(sx, sy):
            M = _diagonal(float(sx), float(sy))
            M[2, 2] = 1.0
            return M
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex3"], pictures="none",
                   include_hidden=False)
    failed = [c for c in check_results(result, "lab07.ex3") if not c.passed]
    assert failed and any("your `_diagonal` has no `return` of a value" in c.message for c in failed), \
        [c.message for c in failed]


def test_numbers_worked_out_from_the_code_stay_small():
    from autograder.engine.raised import _number

    assert _number(ast.parse("2 ** 40 ** 2", mode="eval").body, {}) is None
    assert _number(ast.parse("(2 ** 40) ** 64", mode="eval").body, {}) is None
    assert _number(ast.parse("width // 2 ** n", mode="eval").body, {"width": 5, "n": 3}) == 0


def test_a_write_into_a_read_only_view_or_into_the_callers_array_is_named():
    """"assignment destination is read-only": the view NumPy made (`S.diagonal()`, a name holding one)
    or the caller's array (the grader's inputs are read-only) is named on the raising line; a write into
    the function's own array says nothing of either."""
    from autograder.engine.raised import INPUT_WRITTEN, READ_ONLY_VIEW

    message = "assignment destination is read-only"
    view = """
        def f(sx, sy):
            S = np.eye(3)
            S.diagonal()[:2] = sx, sy
            return S
        """
    named = """
        def f(sx, sy):
            S = np.eye(3)
            d = np.diagonal(S)
            d[:2] = sx, sy
            return S
        """
    given = """
        def f(points, s):
            points /= s
            return points
        """
    own = """
        def f(points, s):
            out = np.zeros(3)
            out[0] = s
            return out
        """
    form = explained(read_code(textwrap.dedent(view)), traceback_at(4), message, "f", (2.0, 3.0), {})
    assert form.mistake == READ_ONLY_VIEW and "`S.diagonal()` (line 4)" in form.sentence
    form = explained(read_code(textwrap.dedent(named)), traceback_at(5), message, "f", (2.0, 3.0), {})
    assert form.mistake == READ_ONLY_VIEW and "`np.diagonal(S)`" in form.sentence
    form = explained(read_code(textwrap.dedent(given)), traceback_at(3), message, "f", (np.ones((4, 2)), 2.0), {})
    assert form.mistake == INPUT_WRITTEN and "`points` (line 3)" in form.sentence
    assert explained(read_code(textwrap.dedent(own)), traceback_at(4), message, "f", (np.ones(3), 2.0), {}) is None


def test_a_name_assigned_under_a_test_and_read_first_is_told_local():
    """`_rng` assigned only where a seed is given, and read on every call (the blind set 1205g's 09/03): Python
    takes it as the function's own name; the assignment and its test are told."""
    source = textwrap.dedent("""
        import numpy as np

        _rng = np.random.default_rng()

        def f(n, seed=None):
            if seed is not None:
                _rng = np.random.default_rng(seed)
            return _rng.random(n)
        """)
    message = "cannot access local variable '_rng' where it is not associated with a value"
    traceback = f'Traceback (your code):\n  File "lab.py", line 9, in f\n    ...\nUnboundLocalError: {message}'
    form = explained(read_code(source), traceback, message, "f", (3,), {})
    assert form is not None and "assigns `_rng` (line 8, under `seed is not None`)" in form.sentence, form
    old = "local variable '_rng' referenced before assignment"
    assert explained(read_code(source), traceback.replace(message, old), old, "f", (3,), {}) is not None


def test_a_list_of_none_beside_pairs_made_an_array_is_told_its_appends():
    """`projected.append(None)` for a point behind the camera beside `(x, y)` for the others, then np.array (the
    blind set 1205g's 10/01): the two appends are told; a list of pairs only is not."""
    source = textwrap.dedent("""
        import numpy as np

        def f(points):
            projected = []
            for X, Y, Z in points:
                if Z <= 0:
                    projected.append(None)
                else:
                    projected.append((X / Z, Y / Z))
            return np.array(projected, dtype=np.float64)
        """)
    message = ("setting an array element with a sequence. The requested array has an inhomogeneous shape after 1 "
               "dimensions. The detected shape was (3,) + inhomogeneous part.")
    traceback = f'Traceback (your code):\n  File "lab.py", line 11, in f\n    ...\nValueError: {message}'
    points = np.array([[1.0, 2.0, 3.0], [1.0, 1.0, -1.0], [2.0, 2.0, 2.0]])
    form = explained(read_code(source), traceback, message, "f", (points,), {})
    assert form is not None and "appends None to `projected` (line 8) and a sequence of 2 (line 10)" in form.sentence, form
    alone = source.replace("projected.append(None)", "projected.append((np.nan, np.nan))")
    assert explained(read_code(alone), traceback, message, "f", (points,), {}) is None


def _raised_at(source: str, line: int, message: str, args=(None,)):
    traceback = f'Traceback (your code):\n  File "lab.py", line {line}, in f\n    ...\n{message}'
    return explained(read_code(textwrap.dedent(source)), traceback, message, "f", args, {})


def test_pad_widths_for_fewer_axes_than_a_colour_image_has_are_told_with_numpys_counts():
    """`np.pad(img, ((0, k), (0, 0)))` of a BGR image (the blind set 1205h's 08/02): NumPy's message counts two
    pairs and three axes; the call on the line is told with them. Another error on the line is not."""
    source = """
        import numpy as np

        def f(img):
            k = 3
            out = np.pad(img, ((0, k), (0, 0)))
            return out
        """
    message = ("operands could not be broadcast together with remapped shapes [original->remapped]: (2,2)  and "
               "requested shape (3,2)")
    form = _raised_at(source, 6, message)
    assert form is not None and "`np.pad` the widths `((0, k), (0, 0))`, 2 (before, after) pairs, for an array of 3 " \
        "axes (a colour image" in form.sentence, form
    assert _raised_at(source.replace("np.pad", "np.add"), 6, message) is None


def test_a_size_computed_from_a_float_is_told_with_the_line_that_made_it_one():
    """`np.zeros((height, width, 3))` with `width, height = right - left + 1, ...` and `right = np.ceil(...)` (the
    blind set 1205h's 08/04): followed back to the float; sizes made whole are not told."""
    source = """
        import numpy as np

        def f(pts):
            left, top = np.floor(pts.min(axis=0))
            right, bottom = np.ceil(pts.max(axis=0))
            width, height = right - left + 1, bottom - top + 1
            return np.zeros((height, width, 3))
        """
    message = "'numpy.float64' object cannot be interpreted as an integer"
    form = _raised_at(source, 8, message)
    assert form is not None and "`height`, a float: it is computed from a float (line 6" in form.sentence, form
    whole = source.replace("width, height = right - left + 1, bottom - top + 1",
                           "width, height = int(right - left) + 1, int(bottom - top) + 1")
    assert _raised_at(whole, 8, message) is None


def test_an_entry_written_into_arithmetic_of_a_single_value_is_told():
    """`depth = f * b / d` then `depth[~valid] = 0` for a 0-d d (the blind set 1205h's 12/05): a NumPy scalar has no
    entries; a name made as an array is not told."""
    source = """
        import numpy as np

        def f(d):
            valid = d > 0
            depth = 2.0 * 3.0 / d
            depth[~valid] = 0.0
            return depth
        """
    message = "'numpy.float64' object does not support item assignment"
    form = _raised_at(source, 7, message)
    assert form is not None and "writes into `depth` (line 7), which it computes by arithmetic (line 6)" in form.sentence
    assert _raised_at(source.replace("depth = 2.0 * 3.0 / d", "depth = np.zeros(3)"), 7, message) is None


def test_a_name_numpy_2_removed_is_told_at_its_line_with_its_replacement():
    """`np.array(..., dtype=np.float_)` under NumPy 2 (the blind set 1205h's 07/03): the use is told with the name
    NumPy's message gives instead; a message about another name is not."""
    source = """
        import numpy as np

        def f(tx):
            return np.array([[1, 0, tx], [0, 1, 0]], dtype=np.float_)
        """
    message = "`np.float_` was removed in the NumPy 2.0 release. Use `np.float64` instead."
    form = _raised_at(source, 5, message)
    assert form is not None and "uses `np.float_` (line 5)" in form.sentence and "write `np.float64`" in form.sentence
    other = "`np.int0` was removed in the NumPy 2.0 release. Use `np.intp` instead."
    assert _raised_at(source, 5, other) is None


def test_an_alias_of_a_builtin_numpy_removed_is_told_with_the_builtin():
    """`.astype(np.int)` (the blind set 1206b's 12/03): NumPy 1.24 removed the aliases of Python's types; the use
    is told with the builtin its message names."""
    source = """
        import numpy as np

        def f(u):
            return np.floor(u).astype(np.int)
        """
    message = ("module 'numpy' has no attribute 'int'.\n`np.int` was a deprecated alias for the builtin `int`. To avoid "
               "this error in existing code, use `int` by itself.")
    form = _raised_at(source, 5, message)
    assert form is not None and "uses `np.int` (line 5)" in form.sentence and "NumPy 1.24" in form.sentence \
        and "write `int`" in form.sentence, form


def test_a_float_that_is_no_size_is_not_told_as_one():
    """`np.full((h, w), mean / 2)`: the fill value may be a float; only the shape's names are followed."""
    source = """
        import numpy as np

        def f(img, h, w):
            mean = img.sum() / img.size
            return np.full((h, w), mean / 2)
        """
    assert _raised_at(source, 6, "'numpy.float64' object cannot be interpreted as an integer", (None, 1, 2)) is None


def _domain(source: str, line: int, args, message: str = "math domain error"):
    tb = f'Traceback (your code):\n  File "lab.py", line {line}, in f\n    ...\nValueError: {message}'
    return explained(read_code(textwrap.dedent(source)), tb, f"f() raised ValueError: {message}", "f", args, {})


def test_a_math_function_given_a_number_outside_what_it_takes_is_told_at_its_call():
    """`math.log(1 - w ** 4)` beside `math.log(1 - confidence)` (the blind set 1206a's 08/02: every pair an inlier,
    w = 1): the call whose argument is not worked out from the numbers given -- the default confidence is one of
    them -- is told; Python 3.14's wording of the error too."""
    source = """
        import math
        def f(n, confidence=0.99):
            w = n / n
            return math.log(1 - confidence) / math.log(1 - w ** 4)
        """
    for message in ("math domain error", "expected a positive input, got 0.0"):
        form = _domain(source, 5, (4,), message)
        assert form is not None and "math.log(1 - w ** 4)" in form.sentence and "positive" in form.sentence, form
        assert "1 - confidence" not in form.sentence.split("math.log takes")[0].replace("math.log(1 - w ** 4)", "")


def test_a_math_domain_error_is_not_told_where_which_call_raised_is_not_known():
    """Two calls whose arguments are both unknown: either may have raised, so neither is told; a square root
    told with its own domain where it is the only one."""
    assert _domain("""
        import math
        def f(a, b):
            return math.sqrt(a - b) + math.acos(b)
        """, 4, (np.float64(1.0), np.float64(2.0))) is None
    form = _domain("""
        import math
        def f(c):
            return math.acos(c / 2) + 1
        """, 4, (np.array([3.0]),))
    assert form is not None and "from -1 to 1" in form.sentence, form


def test_a_math_domain_error_beside_a_power_is_not_told():
    """`math.log(a) + math.pow(b, 0.5)`: math.pow raises the same error for a negative base, so which call raised is
    not known and neither is told."""
    assert _domain("""
        import math
        def f(a, b):
            return math.log(a) + math.pow(b, 0.5)
        """, 4, (np.float64(1.0), np.float64(-2.0))) is None


def test_a_removed_name_whose_message_advises_in_words_is_told_with_that_advice():
    """`np.asfarray(src)` (the blind set 1206c's 07/04): NumPy's message says "Use `np.asarray` with a proper
    dtype instead" -- a sentence, not a name alone: told as it says."""
    source = """
        import numpy as np

        def f(src):
            return np.asfarray(src) * 2
        """
    message = "`np.asfarray` was removed in the NumPy 2.0 release. Use `np.asarray` with a proper dtype instead."
    form = _raised_at(source, 5, message)
    assert form is not None and "uses `np.asfarray` (line 5)" in form.sentence \
        and "use `np.asarray` with a proper dtype" in form.sentence, form


@pytest.mark.parametrize("written, said", [("np.product(a)", "write `np.prod`"),
                                            ("np.linalg.svg(a)", "`np.linalg.svd` is the nearest it has")])
def test_a_name_numpy_does_not_have_is_told_removed_or_misspelt(written, said):
    """Python's own "module 'numpy' has no attribute ..." for a name NumPy 2 removed without a message of its
    own (`np.product`) or a misspelling of one it has (`np.linalg.svg`); a name nothing near is not told."""
    source = f"""
        import numpy as np

        def f(a):
            return {written}
        """
    module, name = written.split("(")[0].rsplit(".", 1)
    message = f"module '{module.replace('np', 'numpy', 1)}' has no attribute '{name}'"
    form = _raised_at(source, 5, message)
    assert form is not None and said in form.sentence, form
    assert _raised_at(source.replace(written, "np.zzqqxx(a)"), 5, "module 'numpy' has no attribute 'zzqqxx'") is None


def test_an_attribute_read_through_the_list_holding_the_item_is_told_where_it_was_wrapped():
    """`good.append([m])` then `k[m.queryIdx]` in a loop over `good` (the blind set 1206c's 08/04), and a loop over
    knnMatch's answer read as matches: each item is a list or tuple, told with where it became one; a loop over
    something else is not told."""
    source = """
        import numpy as np

        def f(matcher, d1, d2, kp):
            good = []
            for m, n in matcher.knnMatch(d1, d2, k=2):
                good.append([m])
            return [kp[g.queryIdx].pt for g in good]
        """
    form = _raised_at(source, 8, "'list' object has no attribute 'queryIdx'", args=(None,) * 4)
    assert form is not None and "`good.append([m])`, line 7" in form.sentence and "`g[0].queryIdx`" in form.sentence
    pairs = """
        import numpy as np

        def f(matcher, d1, d2):
            matches = matcher.knnMatch(d1, d2, k=2)
            return [m.distance for m in matches]
        """
    form = _raised_at(pairs, 6, "'tuple' object has no attribute 'distance'", args=(None,) * 3)
    assert form is not None and "`knnMatch` (line 5) answers each query with a sequence" in form.sentence
    other = pairs.replace("matcher.knnMatch(d1, d2, k=2)", "list(d1)")
    assert _raised_at(other, 6, "'tuple' object has no attribute 'distance'", args=(None,) * 3) is None


def test_a_keyword_a_numpy_function_does_not_take_is_told_with_its_parameters():
    """`np.diag([sx, sy, 1], dtype=np.float64)` (the blind set 1206d's 07/06): np.diag has no dtype; its own
    parameters are told. A keyword of a function of the module's own is not."""
    source = """
        import numpy as np

        def f(sx, sy):
            return np.diag([sx, sy, 1.0], dtype=np.float64)
        """
    form = _raised_at(source, 5, "diag() got an unexpected keyword argument 'dtype'", args=(1.0, 2.0))
    assert form is not None and "calls `np.diag` with `dtype=` (line 5)" in form.sentence \
        and "(its parameters: v, k)" in form.sentence, form
    own = source.replace("np.diag(", "helper(")
    assert _raised_at(own, 5, "helper() got an unexpected keyword argument 'dtype'", args=(1.0, 2.0)) is None
