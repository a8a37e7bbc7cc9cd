"""Lab 7: the reference passes, the skeleton scores 0, usual mistakes are named."""

import textwrap

import pytest

from autograder.engine.runner import grade
from autograder.labs.mistakes.lab07 import MISTAKES
from conftest import assert_all_not_implemented, assert_full_marks, assert_mistake_named, check_results, mutant

MODULE = "lab07_transformations"


def test_reference_scores_full_marks(reference_result):
    assert_full_marks(reference_result, "lab07")


def test_skeleton_scores_zero_with_not_implemented(skeleton_result):
    assert_all_not_implemented(skeleton_result, "lab07")


@pytest.mark.parametrize("case", sorted(MISTAKES))
@pytest.mark.xdist_group("lab07")
def test_mistake_is_caught_and_named(case):
    assert_mistake_named(MODULE, *MISTAKES[case])


def test_other_exercises_unaffected_by_a_mistake(tmp_path):
    result = grade(mutant(tmp_path, MODULE, """
        def shear_matrix(s):
            raise ValueError("oops")
        """), ["lab07"])
    for exercise in result.exercises:
        assert (exercise.score == exercise.max_score) == (exercise.id != "lab07.ex4"), exercise.id
    failing = [c for c in check_results(result, "lab07.ex4") if not c.passed]
    assert any("ValueError: oops" in c.message for c in failing)
    assert any('File "lab07_transformations.py"' in c.traceback for c in failing)


# Textbook variants of the estimators: each scores full marks on its exercise.
VARIANTS = {
    "ex2 about (w / 2, h / 2), OpenCV's tutorial centre": ("lab07.ex2", """
        def rotate(image, angle_deg=45):
            h, w = image.shape[:2]
            return cv2.warpAffine(image, cv2.getRotationMatrix2D((w / 2, h / 2), angle_deg, 1.0), (w, h))
        """),
    "ex2 with np.rot90 for quarter turns of a square image": ("lab07.ex2", """
        def rotate(image, angle_deg=45):
            h, w = image.shape[:2]
            turns = float(angle_deg) % 360
            if h == w and turns in (90.0, 180.0, 270.0):
                return np.ascontiguousarray(np.rot90(image, int(turns // 90)))
            M = cv2.getRotationMatrix2D(((w - 1) / 2, (h - 1) / 2), angle_deg, 1.0)
            return cv2.warpAffine(image, M, (w, h))
        """),
    "ex5 by the 6x6 system": ("lab07.ex5", """
        def affine_from_points(src, dst):
            M = np.zeros((6, 6))
            M[0::2, 0:2] = src; M[0::2, 2] = 1; M[1::2, 3:5] = src; M[1::2, 5] = 1
            return np.linalg.solve(M, np.asarray(dst, float).reshape(-1)).reshape(2, 3)
        """),
    "ex5 by the inverse of [src 1]": ("lab07.ex5", """
        def affine_from_points(src, dst):
            S = np.hstack([np.asarray(src, float), np.ones((3, 1))])
            return (np.linalg.inv(S) @ np.asarray(dst, float)).T
        """),
    "ex5 by cv2.getAffineTransform, float32 (the lab sheet)": ("lab07.ex5", """
        def affine_from_points(src, dst):
            return cv2.getAffineTransform(np.float32(src), np.float32(dst))
        """),
    "ex6 by the normal equations": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            n = len(src)
            M = np.zeros((2 * n, 6))
            M[0::2, 0:2] = src; M[0::2, 2] = 1; M[1::2, 3:5] = src; M[1::2, 5] = 1
            b = np.asarray(dst, float).reshape(-1)
            return (np.linalg.inv(M.T @ M) @ M.T @ b).reshape(2, 3)
        """),
    "ex6 on centred points": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            src = np.asarray(src, float); dst = np.asarray(dst, float)
            ms, md = src.mean(0), dst.mean(0)
            L = np.linalg.lstsq(src - ms, dst - md, rcond=None)[0].T
            return np.hstack([L, (md - L @ ms)[:, None]])
        """),
    "ex6 by pinv of a float32 system": ("lab07.ex6", """
        def affine_lstsq(src, dst):
            n = len(src)
            M = np.zeros((2 * n, 6), np.float32)
            M[0::2, 0:2] = src; M[0::2, 2] = 1; M[1::2, 3:5] = src; M[1::2, 5] = 1
            return (np.linalg.pinv(M) @ np.float32(dst).reshape(-1)).reshape(2, 3)
        """),
}


@pytest.mark.parametrize("case", sorted(VARIANTS))
def test_textbook_variant_scores_full_marks(tmp_path, case):
    exercise, source = VARIANTS[case]
    result = grade(mutant(tmp_path, MODULE, source), [exercise])
    for check in check_results(result, exercise):
        assert check.passed or check.max_score == 0, f"{check.name}: {check.message}"


def test_a_scale_made_with_cv2_resize_is_told_it_resizes(tmp_path):
    """An output of the input's size times the scale, from code calling cv2.resize: named."""
    from autograder.engine.judges import RESIZED

    source = """
        def scale(image, sx=1.5, sy=1.5):
            return cv2.resize(image, None, fx=sx, fy=sy)
        """
    result = grade(mutant(tmp_path, "lab07_transformations", source), ["lab07.ex3"], pictures="none")
    failed = [c for c in check_results(result, "lab07.ex3") if not c.passed and c.max_score]
    assert failed and all(c.mistake == RESIZED and "your code calls cv2.resize" in c.message for c in failed
                          if "returned shape" in c.message), [c.message for c in failed]


def test_the_column_of_ones_is_read_in_the_code_not_in_a_shape():
    """`M[0::2, 2] = 1`, a row `[x, y, 1, 0, 0, 0]` or np.ones build the column of ones; a shape holding a 1
    (`reshape(-1, 2, 1)`, `np.zeros((n, 3, 1))`) does not, and the missing column is still told there."""
    import ast

    from autograder.labs import lab07

    def builds(body: str) -> bool:
        return bool(lab07.ONES_COLUMN.found([ast.parse("def f(src, dst, n):\n" + body).body[0]]))

    assert builds("    M = np.zeros((2 * n, 6))\n    M[0::2, 2] = 1\n")
    assert builds("    rows = [[x, y, 1, 0, 0, 0] for x, y in src]\n")
    assert builds("    A = np.hstack([src, np.ones((n, 1))])\n")
    assert not builds("    A = src.reshape(-1, 2, 1)\n    B = np.zeros((n, 3, 1))\n")


@pytest.mark.parametrize("sampling, said", [
    # coordinates clipped into the image: every output pixel finds the edge pixel
    ("""
        xs = np.clip(np.arange(w) - s * y, 0, w - 1)
        out[y] = image[y, np.round(xs).astype(int)]
     """, "a coordinate clipped into the image samples the edge pixel"),
    # np.interp's default outside the samples: the first and the last sample
    ("""
        for c in range(image.shape[2] if image.ndim == 3 else 1):
            row = image[y, :, c] if image.ndim == 3 else image[y]
            got = np.clip(np.interp(np.arange(w) - s * y, np.arange(w), row), 0, 255)
            if image.ndim == 3:
                out[y, :, c] = got
            else:
                out[y] = got
     """, "np.interp without left= and right="),
])
def test_a_replicated_fill_is_told_from_the_code_that_makes_it(tmp_path, sampling, said):
    """The edge pixel repeated where black belongs: a clip of coordinates, or np.interp's default; a
    clip of pixel values (0 to 255) is never told as the cause."""
    source = """
        def shear(image, s=0.5):
            out = np.zeros_like(image)
            h, w = image.shape[:2]
            for y in range(h):
    """ + textwrap.indent(textwrap.dedent(sampling), " " * 16) + """
            return out
    """
    result = grade(mutant(tmp_path, MODULE, source), ["lab07.ex4"], pictures="none", include_hidden=False)
    messages = [c.message for c in check_results(result, "lab07.ex4") if not c.passed]
    assert messages and all(said in m for m in messages if "not black" in m), messages
    assert any("not black" in m for m in messages), messages


def test_a_matrix_of_the_right_numbers_in_other_places_is_told_where_each_belongs():
    """Entries that are the expected ones, each once, some moved: each moved one is told with the place it
    belongs in; a matrix with an entry not among the expected, or with repeated values, tells nothing."""
    import numpy as np

    from autograder.engine.judges import entries_misplaced

    expected = np.array([[0.9, -0.2, 30.0], [0.3, 1.1, 20.0]])
    reshaped = np.array([[0.9, -0.2, 0.3], [1.1, 30.0, 20.0]])
    assert entries_misplaced(reshaped, expected) == ("[0, 2] holds the value that belongs in [1, 0], [1, 0] holds the "
                                                     "value that belongs in [1, 1], [1, 1] holds the value that "
                                                     "belongs in [0, 2]")
    assert entries_misplaced(expected, expected) == ""
    assert entries_misplaced(reshaped + np.array([[0, 0, 0], [0, 0, 1e-3]]), expected) == ""
    assert entries_misplaced(np.ones((2, 3)), np.ones((2, 3))) == ""


def test_a_library_fit_of_another_family_is_told_only_where_it_is_what_affine_lstsq_answers():
    """`cv2.findHomography` answered (directly, or through names made from it) is the fit told; one called only
    to compare with beside the student's own least squares is not (the sentence would be false there)."""
    import ast

    from autograder.labs.lab07 import _feeds_the_return

    def told(source):
        function = ast.parse(textwrap.dedent(source)).body[0]
        call = next(n for n in ast.walk(function) if isinstance(n, ast.Call) and ast.unparse(n.func).endswith(
            "findHomography"))
        return _feeds_the_return(function, call)

    assert told("""
        def affine_lstsq(src, dst):
            H, _ = cv2.findHomography(src, dst, 0)
            A = H[:2] / H[2, 2]
            return A
        """)
    assert told("""
        def affine_lstsq(src, dst):
            return cv2.findHomography(src, dst, 0)[0][:2]
        """)
    assert not told("""
        def affine_lstsq(src, dst):
            H, _ = cv2.findHomography(src, dst, 0)
            A = np.linalg.lstsq(design(src), dst.ravel(), rcond=None)[0].reshape(2, 3)
            if np.abs(H[2, :2]).max() > 1e-3:
                warnings.warn("not affine")
            return A
        """)


def test_a_solution_read_back_row_by_row_is_told_without_the_six_wide_rows_the_code_never_writes(tmp_path):
    """A (3, 2) solution of [x, y, 1] rows reshaped (2, 3) gives the same A as six-wide rows paired with the unknowns
    in another order; the code writes no six-wide rows, so that cause is not said (07d lab07/06), the label kept."""
    from conftest import edited_reference
    from fixtures.lab07 import TRANSPOSED_READ_BY_ROWS

    folder = edited_reference(tmp_path, "lab07_transformations",
                              ("return np.linalg.solve(S, dst).T", "return np.linalg.solve(S, dst).reshape(2, 3)"))
    failed = [c for c in check_results(grade(str(folder), ["lab07.ex5"]), "lab07.ex5") if c.score < c.max_score]
    assert failed and all(c.mistake == TRANSPOSED_READ_BY_ROWS for c in failed), [c.mistake for c in failed]
    assert all("reshaped where it is transposed" in c.message and "[x, y, 1, 0, 0, 0]" not in c.message
               for c in failed), [c.message for c in failed]
