"""A failure explained from what the student's own expressions held on the failing input (issue 35:
"relayed exceptions that do not say which input or why", shapes measured without a cause).

:mod:`autograder.engine.traced` rewrites the student's functions so that every expression records
its shape (or number) and runs them once more on the failing input; the sentence quotes the
student's expression and the shapes it had. Here the rewrite runs in this process on the tests' own
small functions (never a student's: grading runs it in the companion sandbox), and the end-to-end
tests grade submissions through the sandbox.
"""

from __future__ import annotations

import textwrap
import traceback

import cv2
import numpy as np
import pytest

from autograder.engine import traced
from autograder.engine.hints import read_code
from autograder.engine.raised import without_comprehensions
from autograder.engine.runner import grade
from conftest import check_results, edited_reference, failing_messages, mutant


def recorded(source: str, function: str, *args, **kwargs):
    """``(code, recording, original namespace)`` of ``function`` of ``source`` run on ``args``."""
    source = textwrap.dedent(source)
    code = read_code(source)
    original = {"np": np, "cv2": cv2, "__name__": "student"}
    exec(compile(source, "student.py", "exec"), original)
    rewritten = dict(original)
    exec(compile(traced.recording_source(code, function), "student.py", "exec"), rewritten)
    return code, traced.recording_of(rewritten[traced.RECORDED](*args, **kwargs)), original


def raised_sentence(source: str, function: str, *args) -> str | None:
    code, recording, original = recorded(source, function, *args)
    assert recording.raised
    try:
        original[function](*args)
    except Exception as exc:   # noqa: BLE001 - the tests' own code, raising on purpose
        frames = without_comprehensions([(f"{f.filename}", f.lineno, f.name, f.line or "")
                                         for f in traceback.extract_tb(exc.__traceback__) if f.filename == "student.py"])
        form = traced.explain_raised(code, recording, code.functions[frames[-1][2]], frames[-1][1], str(exc), frames)
        return None if form is None else form.sentence
    raise AssertionError("it did not raise")


def shape_sentence(source: str, function: str, expected: tuple, *args) -> str | None:
    code, recording, _ = recorded(source, function, *args)
    form = traced.explain_shape(code, recording, function, recording.returned[1], expected)
    return None if form is None else form.sentence


# ------------------------------------------------------------------ the rewrite changes no answer
SOURCES = {
    "loops, slices and in-place updates": ("""
        def f(image, k=2):
            out = np.zeros_like(image)
            for y in range(image.shape[0]):
                out[y, k:] = image[y, :image.shape[1] - k]
            out[out > 100] += 1
            return out
        """, (np.arange(48, dtype=np.uint8).reshape(4, 12) * 5,)),
    "comprehensions, lambdas, nested defs and unpacking": ("""
        def f(points, scale=2.0):
            def shifted(p, by=1.0):
                return p + by
            rows = [shifted(p) * scale for p in points if p.sum() > -100]
            first, *rest = rows
            key = lambda r: float(r[0])
            best = max(rows, key=key)
            return np.stack([first, best] + rest), (total := len(rows)), f"{total}"
        """, (np.arange(6.0).reshape(3, 2),)),
    "try, with, while and a walrus": ("""
        def f(values):
            total, i = 0.0, 0
            while (n := len(values)) > i:
                try:
                    total += 1.0 / values[i]
                except ZeroDivisionError:
                    total += 0
                i += 1
            return total, n, values.T.shape, -values[::-1]
        """, (np.array([1.0, 0.5, 4.0]),)),
}


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_the_recording_rewrite_gives_the_same_answers(name):
    source, args = SOURCES[name]
    code, recording, original = recorded(source, "f", *args)
    expected = original["f"](*args)
    rewritten = dict(original)
    exec(compile(traced.recording_source(code, "f"), "student.py", "exec"), rewritten)
    got = rewritten["f"](*args)
    for a, b in zip(expected if isinstance(expected, tuple) else (expected,), got if isinstance(got, tuple) else (got,)):
        np.testing.assert_array_equal(np.asarray(a), np.asarray(b))
    assert recording.values and not recording.raised


def test_a_recording_that_is_not_one_is_refused():
    found = traced.recording_of({"record": {"1:0:1:5": ["array", [2, -1], "float64"], "x": ["number", 1]}})
    assert found.values == {"1:0:1:5": ("other",)}   # (a negative size is no shape; "x" is no place)
    assert traced.recording_of({"record": "nothing"}) is None
    assert traced.recording_of(["record"]) is None


# ------------------------------------------------------------------ exceptions
def test_operands_that_do_not_broadcast_are_named_with_their_shapes():
    sentence = raised_sentence("""
        def blend(a, b, mask):
            weight = mask.astype(float)
            return weight * a + (1 - weight) * b
        """, "blend", np.ones((4, 5, 3)), np.zeros((4, 5, 3)), np.ones((4, 5)))
    assert sentence.startswith("in `weight * a` (line 4), `weight` has shape (4, 5) and `a` (4, 5, 3)")
    assert "`weight[..., None]` gives it one" in sentence


def test_operands_meant_axis_by_axis_from_the_first_are_told_the_axes_to_add():
    """`fs[:, None] * xy[None]`, (3, 1) against (1, 9, 2): one axis of 1 more at the end of the shorter
    lines the two up as meant."""
    sentence = raised_sentence("""
        def scaled(fs, xy):
            return fs[:, None] * xy[None, :, :]
        """, "scaled", np.array([1.0, 2.0, 3.0]), np.ones((9, 2)))
    assert "shape (3, 1, 1), `fs[:, None]` would line up with `xy[None, :, :]`" in sentence, sentence
    assert "`fs[:, None][..., None]`" in sentence, sentence


def test_an_axis_given_before_an_opencv_call_that_drops_it_is_told_there_not_at_the_use():
    """`m = m[..., None]`, then a pyramid of m by cv2.pyrDown (blind set 2026-12-06d): OpenCV returns the
    one-channel levels as (rows, cols), so the axis is gone at the use; adding it there would break the
    first level, which kept it. Told at the line that gives the axis and the call that drops it."""
    source = """
        def blend(a, b, m, levels):
            m = m[..., None]
            ga, gm = [a], [m]
            for _ in range(levels - 1):
                ga.append(cv2.pyrDown(ga[-1]))
                gm.append(cv2.pyrDown(gm[-1]))
            out = []
            for i in range(levels):
                w = gm[i]
                out.append(w * ga[i] + (1 - w) * 0.5)
            return out
        """
    sentence = raised_sentence(source, "blend", np.ones((16, 20, 3), np.float32), None,
                               np.ones((16, 20), np.float32), 3)
    assert "in `w * ga[i]` (line 11), `w` has shape (8, 10) and `ga[i]` (8, 10, 3)" in sentence, sentence
    assert "Line 3 gives an array an axis of size 1 (`m[..., None]`), but `cv2.pyrDown` (line 7)" in sentence, sentence
    assert "[..., None]` gives it one" not in sentence
    # (an axis never given: the advice to give it at the use stands)
    plain = raised_sentence(source.replace("m = m[..., None]", "m = m * 1.0"), "blend",
                            np.ones((16, 20, 3), np.float32), None, np.ones((16, 20), np.float32), 3)
    assert "`w[..., None]` gives it one" in plain and "OpenCV drops it" not in plain, plain


def test_a_pyramid_level_brought_up_without_its_size_is_told_dstsize():
    """`cv2.pyrUp(result) + band` with an odd side below: pyrUp doubles it, one pixel too many."""
    sentence = raised_sentence("""
        def collapse(result, band):
            return cv2.pyrUp(result) + band
        """, "collapse", np.zeros((22, 32, 3), np.float32), np.zeros((43, 63, 3), np.float32))
    assert "they differ on axis 0 (44 and 43)" in sentence, sentence
    assert "`dstsize=(band.shape[1], band.shape[0])`" in sentence, sentence


def test_a_crop_of_an_array_smaller_than_asked_is_told_that_a_slice_never_pads():
    """`resized[:h, :w]` of a shrunk image: the slice keeps the smaller shape; it is told to copy it into
    an array of the size asked."""
    sentence = shape_sentence("""
        def framed(image, resized):
            h, w = image.shape[:2]
            return resized[:h, :w]
        """, "framed", (6, 8), np.ones((6, 8)), np.ones((3, 12)))
    assert "`resized[:h, :w]` (line 4) makes the shape (3, 8)" in sentence, sentence
    assert "a slice crops but never pads" in sentence, sentence
    shrunk = shape_sentence("""
        def halved(image):
            return image[::2, ::2]
        """, "halved", (6, 8), np.ones((6, 8)))
    assert shrunk is None or "never pads" not in shrunk, shrunk   # (a step shrinks what has the size asked)


def test_an_axis_wrong_before_a_slice_is_followed_back_to_where_it_went_wrong():
    """`X[:, :3] / X[:, 3:]` of null vectors taken from `svd(A)[2].T` of a stack (blind set 2026-12-06e's 11/01):
    the slice keeps axis 0 whole, so it crops nothing there and no 'copy into a larger array' is told; the
    wrong axis came with X, made by `V[..., -1]` of a stack `.T` reversed."""
    sentence = shape_sentence("""
        def solve(A):
            V = np.linalg.svd(A)[2].T
            X = V[..., -1]
            return X[:, :3] / X[:, 3:4]
        """, "solve", (6, 3), np.random.default_rng(0).normal(size=(6, 4, 4)))
    assert "never pads" not in sentence, sentence
    assert "`V[..., -1]` (line 4) makes the shape (4, 4) from `V` of shape (4, 4, 6)" in sentence, sentence
    assert "`V` comes from `np.linalg.svd(A)[2].T` (line 3), and on a stack of matrices .T reverses every axis" \
        in sentence, sentence


def test_a_row_of_an_array_with_its_axes_exchanged_is_followed_back_to_where_it_was_made():
    """`result[0]` of `np.array([x, y])` for one point (the blind set 2026-12-06f's 09/01): (2, 1) where (1, 2) gives
    the (2,) asked -- the index is right, the array it reads was stacked the other way round."""
    sentence = shape_sentence("""
        def project(p):
            p = np.atleast_2d(p)
            x, y = p[:, 0] / p[:, 2], p[:, 1] / p[:, 2]
            result = np.array([x, y])
            return result[0]
        """, "project", (2,), np.array([1.0, 2.0, 4.0]))
    assert "`np.array([x, y])` (line 5) makes the shape (2, 1)" in sentence, sentence
    assert "its two axes are exchanged (the transpose of the (1, 2) asked)" in sentence, sentence
    assert "`result[0]`" not in sentence, sentence


def test_an_array_made_without_the_values_last_axis_is_named_where_it_was_made():
    sentence = raised_sentence("""
        def paste(image):
            h, w = image.shape[:2]
            out = np.zeros(image.shape[:2], dtype=image.dtype)
            out[:h, :w] = image
            return out
        """, "paste", np.zeros((4, 5, 3), np.uint8))
    assert sentence.endswith("`out` comes from `np.zeros(image.shape[:2], dtype=image.dtype)` (line 4), of 2 axes "
                             "where the value has 3"), sentence


def test_a_negative_slice_bound_is_named_with_its_value():
    sentence = raised_sentence("""
        def shift_rows(image, s):
            out = np.zeros_like(image)
            for y in range(image.shape[0]):
                shift = int(round(s * y))
                out[y, shift:] = image[y, :image.shape[1] - shift]
            return out
        """, "shift_rows", np.ones((6, 10)), -0.5)
    assert sentence.startswith("`shift` is -1 here (line 6), and a negative slice bound counts from the end")
    assert "`out[y, shift:]` is then (1,)" in sentence


def test_a_product_of_other_inner_sizes_is_named():
    sentence = raised_sentence("""
        def apply(H, pts):
            return (H @ pts)[:2]
        """, "apply", np.eye(3), np.ones((5, 3)))
    assert "in `H @ pts` (line 3), `H` has shape (3, 3) and `pts` (5, 3)" in sentence
    assert "(3) to equal the next-to-last of the second (5)" in sentence


def test_an_index_past_its_axis_is_named_with_its_value():
    sentence = raised_sentence("""
        def last_pairs(values):
            out = []
            for i in range(len(values)):
                out.append(values[i + 1] - values[i])
            return out
        """, "last_pairs", np.arange(4.0))
    assert sentence.startswith("`i + 1` is 4 in `values[i + 1]` (line 5): axis 0 of `values` (shape (4,)) has 4 entries")


def test_a_fixed_index_past_an_axis_the_input_made_empty_is_named_with_the_array_s_shape():
    """`null_space(A)[:, 0]` on a full-rank (noisy) system: SciPy answers (4, 0) -- the 05d blind set's 11/01, told
    only as the relayed IndexError before."""
    sentence = raised_sentence("""
        from scipy.linalg import null_space
        def solve(A):
            return null_space(A)[:, 0]
        """, "solve", np.arange(16.0).reshape(4, 4) ** 2 + np.eye(4))
    assert sentence.startswith("`null_space(A)` has shape (4, 0) in `null_space(A)[:, 0]` (line 4): its axis 1 "
                               "has no entries at all"), sentence
    assert "the last row of Vt from np.linalg.svd" in sentence


def test_a_list_indexed_past_its_end_is_named_with_the_index_and_its_length():
    # Python's error says neither: the module's palette and a local list alike
    sentence = raised_sentence("""
        PALETTE = [(255, 0, 0), (0, 255, 0), (0, 0, 255)]

        def colours(n):
            return [PALETTE[i] for i in range(n)]
        """, "colours", 5)
    assert sentence == "`i` is 3 in `PALETTE[i]` (line 5): `PALETTE` holds 3 items, numbered 0 to 2"
    sentence = raised_sentence("""
        def pairs(values):
            items = list(values)
            return [items[k + 1] - items[k] for k in range(len(items))]
        """, "pairs", (1.0, 2.0))
    assert sentence == "`k + 1` is 2 in `items[k + 1]` (line 4): `items` holds 2 items, numbered 0 to 1"


def test_a_matrix_that_is_not_square_given_to_a_solve_is_named_with_its_shape():
    sentence = raised_sentence("""
        def fit(A, b):
            M = np.asarray(A, float)
            return np.linalg.solve(M, b)
        """, "fit", np.ones((8, 6)), np.ones(8))
    assert sentence == ("in `np.linalg.solve(M, b)` (line 4), `M` has shape (8, 6): `solve` needs a square matrix -- "
                        "8 equations in 6 unknowns are solved in the least-squares sense, by np.linalg.lstsq")


def test_a_change_that_only_passes_the_check_gives_way_to_what_the_raise_shows(tmp_path):
    # a colour per line taken past the palette's end: `lines[i]` as the colour mends the exception and
    # passes the check (colours are not compared exactly), but it is no fix; the index is the cause
    folder = edited_reference(tmp_path, "lab11_two_view", (
        "colour = _PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255",
        "colour = _PALETTE[i] if canvas.ndim == 3 else 255"))
    messages = failing_messages(folder, "lab11.ex2")
    # (or the line made the reference's again: the index wrapped round the palette, the fix itself)
    assert messages and any(("in `_PALETTE[i]` (line " in m and "`_PALETTE` holds" in m)
                            or "to `_PALETTE[i % len(_PALETTE)] if canvas.ndim == 3 else 255`" in m for m in messages), messages
    assert not any("lines[i]" in m for m in messages), messages


def test_arrays_of_different_types_given_to_opencv_are_named_with_where_they_came_from():
    sentence = raised_sentence("""
        def describe(image, kind="sift"):
            detector = cv2.ORB_create() if kind == "orb" else cv2.SIFT_create()
            return detector.detectAndCompute(image, None)[1]

        def match(img1, img2, kind="orb"):
            d1, d2 = describe(img1, kind), describe(img2)
            return cv2.BFMatcher(cv2.NORM_HAMMING).knnMatch(d1, d2, k=2)
        """, "match", *_textured_pair())
    assert "was given `d1` uint8 of shape" in sentence and "`d2` float32 of shape" in sentence
    assert "`d1` comes from `describe(img1, kind)` (line 7)" in sentence
    assert "`d2` comes from `describe(img2)` (line 7)" in sentence


def _textured_pair():
    rng = np.random.default_rng(0)
    image = cv2.GaussianBlur(rng.integers(0, 255, (200, 200), dtype=np.uint8), (5, 5), 0)
    return image, np.roll(image, 7, axis=1)


def test_an_opencv_error_of_another_kind_is_not_explained_by_types():
    """A warp given a uint8 image and a float64 matrix is right: an OpenCV error that is not a type
    assertion says nothing of the arrays' kinds."""
    code, recording, _ = recorded("""
        def warp(image, M):
            return cv2.warpAffine(image, M, (0, 0))
        """, "warp", np.ones((4, 4), np.uint8), np.eye(2, 3))
    message = "OpenCV(4.10) error: (-215:Assertion failed) dsize.area() > 0 in function 'warpAffine'"
    assert traced.explain_raised(code, recording, code.functions["warp"], 3, message) is None


# ------------------------------------------------------------------ answers of the wrong shape
def test_an_outer_broadcast_is_named_where_it_makes_the_answer():
    sentence = shape_sentence("""
        def spread(points, n=4):
            scale = 1.0 + points[:, 2:3]
            offsets = np.ones((len(points), n, 2))
            rays = points[:, None, :2] + offsets * scale[:, None, None]
            return rays
        """, "spread", (3, 4, 2), np.ones((3, 3)))
    assert sentence.startswith("`offsets * scale[:, None, None]` (line 5) makes the shape (3, 3, 4, 2) from "
                               "`offsets` of shape (3, 4, 2) and `scale[:, None, None]` of shape (3, 1, 1, 1) "
                               "(`scale` is (3, 1))")
    assert "every entry of one with every entry of the other" in sentence


def test_an_axis_lost_in_a_nested_helper_is_followed_there():
    sentence = shape_sentence("""
        def difference(xl, xr):
            def xs(values):
                values = np.asarray(values, dtype=float)
                return np.atleast_2d(values)[:, 0]
            return xs(xl) - xs(xr)
        """, "difference", (5,), np.arange(5.0), np.zeros(5))
    assert sentence == ("`np.atleast_2d(values)[:, 0]` (line 5) makes the shape (1,) from "
                        "`np.atleast_2d(values)` of shape (1, 5) (`values` is (5,))")


def test_a_branch_that_flattens_is_named_with_its_condition():
    sentence = shape_sentence("""
        def project(pts, f=1.0):
            pts = np.asarray(pts, dtype=float)
            single = pts.size == 3
            out = f * pts.reshape(-1, 3)[:, :2] / pts.reshape(-1, 3)[:, 2:]
            if single:
                return out[0]
            return out
        """, "project", (1, 2), np.array([[1.0, 2.0, 4.0]]))
    assert sentence == ("`out[0]` (line 7) makes the shape (2,) from `out` of shape (1, 2) (`out` has the shape "
                        "asked, (1, 2)), on the branch `if single:` (line 6), where `single` is `pts.size == 3` (line 4)")


def test_a_shape_the_recording_does_not_show_made_is_not_named():
    """An answer built from a list (no array on its way) names nothing."""
    assert shape_sentence("""
        def f(values):
            rows = []
            for v in values:
                rows.append([v, v])
            return np.array(rows)
        """, "f", (3,), [1.0, 2.0, 3.0]) is None


# ------------------------------------------------------------------ through the sandbox
def test_grading_names_a_wrong_shape_where_the_student_made_it(tmp_path):
    folder = mutant(tmp_path, "lab12_stereo", '''
def disparity_from_matches(xl, xr):
    def x_coordinates(values):
        values = np.asarray(values, dtype=np.float64)
        return np.atleast_2d(values)[:, 0]
    return x_coordinates(xl) - x_coordinates(xr)
''')
    result = grade(str(folder), ["lab12.ex2"])
    messages = [c.message for c in check_results(result, "lab12.ex2") if c.score < c.max_score]
    assert any("`np.atleast_2d(values)[:, 0]`" in m and "(`values` is (" in m for m in messages), messages


def test_grading_names_operands_that_do_not_broadcast(tmp_path):
    folder = mutant(tmp_path, "lab07_transformations", '''
def shear(image, s):
    h, w = image.shape[:2]
    out = np.zeros_like(image)
    for y in range(h):
        shift = int(round(s * y))
        out[y, shift:] = image[y, :w - shift]
    return out
''')
    result = grade(str(folder), ["lab07.ex4"])
    messages = [c.message for c in check_results(result, "lab07.ex4") if c.score < c.max_score]
    assert any("a negative slice bound counts from the end of the axis" in m for m in messages), messages


def test_an_array_asked_for_one_truth_value_is_named():
    sentence = raised_sentence("""
        def keep_front(points):
            z = points[:, 2]
            if z > 0:
                return points
            return points[:0]
        """, "keep_front", np.ones((4, 3)))
    assert sentence.startswith("`z > 0` (line 4) is an array of shape (4,) where one truth value is asked")


def test_an_array_indexed_on_more_axes_than_it_has_is_named():
    sentence = raised_sentence("""
        def xs(point):
            p = np.asarray(point, float)
            return p[:, 0]
        """, "xs", np.array([1.0, 2.0, 3.0]))
    assert sentence == "in `p[:, 0]` (line 4), `p` has shape (3,): 1 axis, indexed with 2"


def test_a_test_of_the_last_size_that_let_a_one_axis_array_in_is_named_with_its_line():
    """`if x.shape[-1] == 2: x = x[:, 0]`: two x coordinates pass the test made for (N, 2) points."""
    sentence = raised_sentence("""
        def xs(x):
            x = np.asarray(x, float)
            if x.shape[-1] == 2:
                x = x[:, 0]
            return x
        """, "xs", np.array([3.0, 4.0]))
    assert sentence == ("in `x[:, 0]` (line 5), `x` has shape (2,): 1 axis, indexed with 2; it got there because "
                        "`x.shape[-1] == 2` (line 4) holds for it: an array of shape (2,) passes that test too -- "
                        "test its number of axes, `x.ndim`")


def test_a_test_of_an_array_set_again_before_the_failing_line_is_not_said_to_have_let_it_in():
    sentence = raised_sentence("""
        def xs(x):
            x = np.asarray(x, float)
            if x.shape[-1] == 2:
                x = x.ravel()
                x = x[:, 0]
            return x
        """, "xs", np.array([[3.0, 4.0]]))
    assert sentence == "in `x[:, 0]` (line 6), `x` has shape (2,): 1 axis, indexed with 2"


@pytest.mark.parametrize("d", [np.array([[2.0, 0.0], [4.0, 1.0]]), np.array([2.0, -1.0, 4.0])])
def test_a_masked_assignment_of_the_whole_array_is_named_with_the_selection_it_needs(d):
    """`depth[good] = f / d` assigns one value per entry of `d` where one per selected entry belongs: NumPy
    raises a TypeError (2-D) or a ValueError (1-D, some entries not selected)."""
    sentence = raised_sentence("""
        def depth(d, f):
            out = np.zeros_like(d)
            good = d > 0
            out[good] = f / d
            return out
        """, "depth", d, 2.0)
    assert sentence == (f"in `out[good] = f / d` (line 5), the right side has shape {tuple(d.shape)}"
                        + ", a value for every entry of the array, where `out[good]` takes one value per entry `good` "
                        "selects: select the same entries on the right too, `d[good]`")


def test_a_reshape_of_another_size_is_named_with_the_shape_reshaped():
    sentence = raised_sentence("""
        def as_rows(H, pts):
            moved = pts @ H.T
            return np.reshape(moved, (len(pts), 2))
        """, "as_rows", np.eye(3), np.ones((5, 3)))
    assert sentence == "in `np.reshape(moved, (len(pts), 2))` (line 4), `moved` has shape (5, 3) (15 values)"


# ------------------------------------------------------------------ a value departing from the reference's
CAMERA = np.array([[500.0, 0, 320], [0, 500, 240], [0, 0, 1]]), cv2.Rodrigues(np.array([0.1, 0.2, 0.3]))[0], \
    np.array([0.1, 0.2, 2.0])
REFERENCE_CAMERA = """
def camera(K, R, t):
    P = K @ np.hstack([R, t.reshape(3, 1)])
    return P / P[2, 3]
"""


def departures(student: str, reference: str = REFERENCE_CAMERA, args=CAMERA):
    code, mine, _ = recorded(student, "camera", *args)
    _, theirs, _ = recorded(reference, "camera", *args)
    return list(traced.explain_values(code, mine, theirs, "camera"))


def test_the_first_value_departing_by_a_transpose_is_found_and_undone():
    [(form, fn, node, relation)] = departures("""
        def camera(K, R, t):
            Rt = np.column_stack([R.T, t])
            return (K @ Rt) / (K @ Rt)[2, 3]
        """)
    assert relation == "the transpose of" and form.sentence.startswith("`R.T` (line 3) gives the transpose of a value")
    assert traced.undo_text(node, relation) == "R"
    assert "np.column_stack([R, t])" in traced.undone(fn, node, relation)


def test_a_value_scaled_by_a_slip_factor_is_found_and_a_homogeneous_rescaling_is_not():
    [(form, _, node, relation)] = departures("""
        def camera(K, R, t):
            half = K / 2
            P = half @ np.hstack([R, t.reshape(3, 1)])
            return P / P[2, 3]
        """)
    assert relation == "0.5 times" and traced.undo_text(node, relation) == "2 * (K / 2)"
    assert departures("""
        def camera(K, R, t):
            P = (K * 3.7) @ np.hstack([R, t.reshape(3, 1)])
            return P / P[2, 3]
        """) == []   # (3.7 is no slip's factor: a homogeneous matrix is right at any scale)


def test_a_departure_made_from_a_departed_value_is_not_the_first():
    """`K @ Rt` departs too, but from `Rt`, which departed before: only `R.T` is told."""
    found = departures("""
        def camera(K, R, t):
            Rt = np.column_stack([R.T, t])
            P = K @ Rt
            return P / P[2, 3]
        """)
    assert [ast_text(f[2]) for f in found] == ["R.T"]


def ast_text(node) -> str:
    import ast

    return ast.unparse(node)


def test_an_opencv_type_assertion_against_a_type_it_takes_is_not_explained_by_the_arrays_kinds():
    """`cv2.warpAffine(image, M)` with an integer M asserts `M0.type() == CV_32F`: the image and M differ in
    kind by design, so nothing is said of their kinds (the beginner's sentence names M's dtype)."""
    code, recording, _ = recorded("""
        def scale(image, sx=2, sy=1):
            return cv2.warpAffine(image, np.array([[sx, 0, 0], [0, sy, 0]]), (4, 4))
        """, "scale", np.ones((4, 4), np.uint8))
    message = ("OpenCV(4.10) error: (-215:Assertion failed) (M0.type() == CV_32F || M0.type() == CV_64F) && "
               "M0.rows == 2 && M0.cols == 3 in function 'warpAffine'")
    assert traced.explain_raised(code, recording, code.functions["scale"], 3, message) is None


def test_grading_names_a_value_half_what_it_should_be_and_confirms_it(tmp_path):
    """The first tangential term written `p1 x y` for `2 p1 x y`: `p1 * x` is half the reference's value
    there, and doubling it gives the expected answers (the departure told, the fix shown)."""
    folder = edited_reference(tmp_path, "lab09_camera", ("xd = x * radial + 2 * p1 * x * y", "xd = x * radial + p1 * x * y"))
    result = grade(str(folder), ["lab09.ext2"])
    messages = [c.message for c in check_results(result, "lab09.ext2") if c.score < c.max_score]
    assert any(("`p1 * x` (line" in m and "gives 0.5 times a value" in m and "with `2 * (p1 * x)` there" in m)
               or "`x * radial + p1 * x * y` to `x * radial + 2 * p1 * x * y`" in m   # (the line made the reference's)
               for m in messages), messages


def test_a_change_after_the_first_value_to_go_wrong_gives_way_to_that_value(tmp_path):
    """A DLT whose null vector is reshaped column by column: transposing the result a line later mends it
    (a repair), but the reshape is where the values first go wrong -- that is told."""
    folder = edited_reference(tmp_path, "lab08_homographies", (
        "    H = np.linalg.inv(T2) @ Vt[-1].reshape(3, 3) @ T1\n",
        "    H_norm = Vt[-1].reshape(3, 3, order='F')\n    H = np.linalg.inv(T2) @ H_norm @ T1\n"))
    result = grade(str(folder), ["lab08.ex2"])
    messages = [c.message for c in check_results(result, "lab08.ex2") if c.score < c.max_score]
    assert messages and any("reshape(3, 3, order='F')` (line" in m and "gives the transpose of a value" in m
                            for m in messages), messages
    assert not any("H_norm.T`" in m for m in messages)   # (the change a line later, undoing it)


def test_a_guess_from_the_answer_gives_way_to_a_confirmed_departure_before_its_repair(tmp_path):
    """E reshaped column by column inside essential_8point: the answer is E^T, which a check's guess reads
    as "pts1 and pts2 are swapped"; the repair beside it transposes E a line later. The reshape is where
    the values first go wrong: that is told (or, where a check reads the reshape in the code, that), and neither
    the guess nor the later change."""
    folder = mutant(tmp_path, "lab11_two_view", '''
def essential_8point(pts1, pts2, K1, K2):
    x1 = _homogeneous(pts1) @ np.linalg.inv(K1).T
    x2 = _homogeneous(pts2) @ np.linalg.inv(K2).T
    A = (x2[:, :, None] * x1[:, None, :]).reshape(len(x1), 9)
    _, _, Vt = np.linalg.svd(A)
    E = Vt[-1].reshape(3, 3, order='F')
    U, _, Vt = np.linalg.svd(E)
    return U @ np.diag([1.0, 1.0, 0.0]) @ Vt
''')
    result = grade(str(folder), ["lab11.ex3"])
    messages = [c.message for c in check_results(result, "lab11.ex3") if c.score < c.max_score]
    # (told by the departure's line, or by the check's reading of the reshape in the code: never as the guess)
    assert messages and all("reshape(3, 3, order='F')` (line" in m or "reshaped column by column (order='F')" in m
                            for m in messages), messages
    assert any("reshape(3, 3, order='F')` (line" in m for m in messages), messages
    assert not any("swapped" in m for m in messages)


def test_an_axis_of_one_added_to_the_wrong_operand_is_not_asked_of_the_other():
    """A grey band (h, w) against a mask given an axis (h, w, 1) for colour: adding one to the band too
    would make a grey answer (h, w, 1); the sentence asks which operand needs it."""
    sentence = raised_sentence("""
        def blend(a, mask):
            w = mask[..., None]
            return w * a
        """, "blend", np.ones((4, 5)), np.ones((4, 5)))
    assert "`w` has an axis of size 1 at the end that `a` has not" in sentence
    assert "gives it one" not in sentence


def test_an_index_array_holding_a_value_past_its_axis_is_named_with_its_range():
    sentence = raised_sentence("""
        def pick(points, rng_values):
            order = np.argsort(rng_values, axis=0)[:, :4]
            return points[order]
        """, "pick", np.ones((10, 2)), np.random.default_rng(0).random((300, 10)))
    assert "`order` holds" in sentence and "(its values go from 0 to 299)" in sentence
    assert "axis 0 of `points` (shape (10, 2)) has 10 entries" in sentence


def test_a_form_read_from_numpys_message_is_told_where_it_happened_too(tmp_path, monkeypatch):
    """A per-row depth kept flat against (N, 2) points: the form NumPy's message shows is named, and the
    recording says which of the student's expressions had which shape, on which line (without the repair
    that mends it, `X[:, 2].mean()`, which would be told first)."""
    from autograder.engine.mutants import repair

    monkeypatch.setattr(repair, "name_by_repair", lambda trial, seconds=0: None)
    folder = edited_reference(tmp_path, "lab10_camera2", ("z = X[:, 2].mean() if z_avg is None", "z = X[:, 2] if z_avg is None"))
    result = grade(folder, ["lab10.ex2"], pictures="none")
    [check] = [c for c in check_results(result, "lab10.ex2") if c.name.startswith("weak_perspective_project with the default")]
    assert check.mistake == "a per-row value kept flat (N,) against an (N, k) array", check.message
    assert "in `f / z * X[:, :2]` (line" in check.message and "`f / z` has shape (" in check.message, check.message


def test_an_item_of_a_returned_tuple_of_the_wrong_shape_is_followed_to_where_it_was_made(tmp_path):
    folder = mutant(tmp_path, "lab11_two_view", """
        def epipoles(F):
            F = np.asarray(F, dtype=np.float64)
            _, _, Vt = np.linalg.svd(F)
            first = Vt[-1:].T
            _, _, Vt2 = np.linalg.svd(F.T)
            second = Vt2[-1]
            return first, second
        """)
    result = grade(folder, ["lab11.ex5"], pictures="none", include_hidden=False)
    messages = [c.message for c in check_results(result, "lab11.ex5") if not c.passed]
    assert messages and any("e1 has shape (3, 1); expected (3,). On this input, `Vt[-1:].T` (line" in m
                            for m in messages), messages


def test_a_value_computed_per_item_agrees_with_an_item_of_the_references_stack():
    """A loop over the points (`A` of one point, 4 x 4) where the reference stacks them all ((N, 4, 4)):
    the student's value is one item of the reference's, so it agrees; another matrix does not."""
    rng = np.random.default_rng(0)
    stack = rng.normal(size=(5, 4, 4))
    assert traced._agrees(stack[3].copy(), [stack])
    assert not traced._agrees(stack[3].T.copy(), [stack])
    assert not traced._agrees(rng.normal(size=(4, 4)), [stack])
    assert not traced._agrees(stack[3, :3].copy(), [stack])   # (a part of an item is no item)
    points = rng.normal(size=(6, 2))
    assert not traced._agrees(points[2].copy(), [points])     # (a point is no matrix: a row of an input)


def test_a_loop_over_the_channels_given_a_grey_image_says_the_last_axis_is_the_width():
    """`for c in range(image.shape[-1]): out[..., c] = f(image[..., c])` on a grey (H, W) image: the
    assignment is told as a column where a channel was meant (1202e 07/05)."""
    said = raised_sentence("""
        def scale(image, s=2.0):
            out = np.zeros_like(image)
            for c in range(image.shape[-1]):
                out[..., c] = image * s
            return out
        """, "scale", np.zeros((15, 20), np.uint8))
    assert said is not None and "a grey image's (H, W)" in said and "is a column, not a channel" in said, said


def test_a_colour_canvas_too_small_for_its_value_is_not_told_as_a_grey_loop():
    said = raised_sentence("""
        def paste(image):
            out = np.zeros((10, 12, 3), np.uint8)
            out[..., 0] = image
            return out
        """, "paste", np.zeros((15, 20), np.uint8))
    assert said is None or "not a channel" not in said, said


def test_an_unpacking_of_a_grey_image_shape_says_what_the_shape_holds():
    said = raised_sentence("""
        def translate(image, tx=1.0):
            h, w = image.shape[:-1]
            return image[:h, :w]
        """, "translate", np.zeros((12, 16), np.uint8))
    assert said is not None and "unpacks into 2 names a value of 1 item" in said and "(12,)" in said, said
    assert "a grey image's (H, W)" in said, said


def test_the_students_own_assert_is_quoted_with_the_values_it_compared():
    said = raised_sentence("""
        def essential(pts1):
            assert len(pts1) > 8, "needs 8"
            return pts1
        """, "essential", np.zeros((8, 2)))
    assert said is not None and "`assert len(pts1) > 8`" in said and "`len(pts1)` is 8" in said, said


def test_an_index_after_an_ellipsis_on_a_one_axis_array_is_told_as_a_single_number():
    """`xl[..., 0]` meant for (N, 2) points, given (N,) x coordinates: one number (1202f 12/04)."""
    code, recording, _ = recorded("""
        def disparity_from_matches(xl, xr):
            left = np.asarray(xl, dtype=np.float64)
            right = np.asarray(xr, dtype=np.float64)
            return left[..., 0] - right[..., 0]
        """, "disparity_from_matches", np.arange(5.0) + 10, np.arange(5.0))
    form = traced.explain_scalar(code, recording, "disparity_from_matches")
    assert form is not None and "`left[..., 0]`" in form.sentence and "is a single number" in form.sentence, form
    code, recording, _ = recorded("""
        def disparity_from_matches(xl, xr):
            return np.asarray(xl)[..., 0] - np.asarray(xr)[..., 0]
        """, "disparity_from_matches", np.ones((5, 2)), np.zeros((5, 2)))
    assert traced.explain_scalar(code, recording, "disparity_from_matches") is None


def test_two_columns_joined_end_to_end_are_told_where_and_how():
    said = shape_sentence("""
        def pinhole_project(points, f):
            pts = np.asarray(points, dtype=np.float64).reshape(-1, 3)
            x = f * pts[:, 0] / pts[:, 2]
            y = f * pts[:, 1] / pts[:, 2]
            return np.hstack([x, y])
        """, "pinhole_project", (4, 2), np.array([[1.0, 2, 4], [2, 1, 5], [0, 1, 3], [1, 1, 2]]), 500.0)
    assert said is not None and "`np.hstack([x, y])`" in said and "np.column_stack" in said, said


def test_an_in_place_operation_on_an_integer_array_names_where_the_array_was_made():
    """`offset -= R @ centre` on a centre given as whole numbers: NumPy refuses the float result in an int64
    array; the sentence says so from the error's dtypes and follows the copy back to where it was made."""
    source = """
        def rotated(angle, center=(0.0, 0.0)):
            R = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
            centre = np.array(center)
            offset = centre.copy()
            offset -= R @ centre
            return offset
        """
    said = raised_sentence(source, "rotated", 0.5, (10, 20))
    assert said is not None and "`offset -= R @ centre` (line 6) writes a float64 result into `offset`, an array of " \
        "int64" in said, said
    assert "`centre.copy()` (line 5), a copy of `np.array(center)` (line 4)" in said, said
    floats = raised_sentence(source.replace("offset -= R @ centre", "offset -= R @ centre + 'x'"), "rotated", 0.5,
                             (10.0, 20.0))
    assert floats is None or "in-place" not in floats   # (another error on the line: no dtype told)


def test_a_mask_of_another_length_is_told_the_arrays_as_long_as_it():
    """`matched1[front]` where `front` was made for the inliers (the blind set 1205g's 11/06): the arrays of the
    mask's length and the indexed array's other axes are told; none where no array has them."""
    source = """
        def keep(matched1, inliers):
            in1 = matched1[inliers]
            front = in1[:, 0] > 0
            return matched1[front]
        """
    matched = np.arange(12.0).reshape(6, 2) - 3
    sentence = raised_sentence(source, "keep", matched, np.array([True, True, False, True, False, True]))
    assert "`matched1` has shape (6, 2) and the mask `front` (4,); `in1` is of shape (4, 2), as long as the mask" \
        in sentence, sentence
    alone = raised_sentence(source.replace("front = in1[:, 0] > 0", "front = matched1[:4, 0] > 0"), "keep", matched,
                            np.array([True, True, False, True, False, True]))
    assert "as long as the mask" not in alone, alone
