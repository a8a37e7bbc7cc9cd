"""A function that returns None where an array is asked for is told where its code does it
(issue 35: "returned None; expected a numpy array" located the failure without its cause)."""

from __future__ import annotations

import textwrap

import pytest

from autograder.engine.hints import none_returned, read_code
from autograder.engine.runner import grade
from conftest import check_results, mutant

CASES = {
    "no return": ("""
        def f(image):
            image[0, 0] = 255
        """, "has no `return` of a value"),
    "return None under a condition": ("""
        def f(images):
            found, corners = detect(images)
            if not found:
                return None
            return corners
        """, "returns None where `not found`"),
    "bare return in an else": ("""
        def f(x):
            if x.ndim == 2:
                return x * 2
            else:
                return
        """, "returns None where `not (x.ndim == 2)`"),
    "an end reached": ("""
        def f(x):
            if x.ndim == 2:
                return x * 2
        """, "can reach its end without a `return`"),
    "a loop that may finish": ("""
        def f(xs):
            for x in xs:
                if x > 0:
                    return x
        """, "can reach its end without a `return`"),
}
SILENT = {
    "always returns": """
        def f(x):
            if x.ndim == 2:
                return x * 2
            return x
        """,
    "both branches return": """
        def f(x):
            if x.ndim == 2:
                return x * 2
            else:
                raise ValueError("3-D")
        """,
    "a None from a call": """
        def f(x):
            return helper(x)
        """,
    "a nested function's bare return": """
        def f(x):
            def g():
                return
            return x
        """,
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_where_none_is_returned_is_read(name):
    source, words = CASES[name]
    assert words in none_returned(read_code(textwrap.dedent(source)), "f")


@pytest.mark.parametrize("name", sorted(SILENT))
def test_code_that_does_not_return_none_itself_is_told_nothing(name):
    assert none_returned(read_code(textwrap.dedent(SILENT[name])), "f") == ""
    assert none_returned(read_code(textwrap.dedent(SILENT[name])), "missing") == ""


def test_a_drawing_that_forgets_to_return_is_told_in_grading(tmp_path):
    source = """
        def draw_points(image, pts, radius=3, color=(0, 0, 255)):
            out = image.copy()
            for x, y in np.asarray(pts, float).reshape(-1, 2):
                if np.isfinite(x) and np.isfinite(y):
                    cv2.circle(out, (int(round(x)), int(round(y))), int(radius), tuple(color), -1)
        """
    result = grade(mutant(tmp_path, "lab09_camera", source), ["lab09.ex5"], pictures="none")
    messages = [c.message for c in check_results(result, "lab09.ex5") if not c.passed]
    assert any("returned None; expected a numpy array" in m and "your `draw_points` has no `return` of a value"
               in m for m in messages), messages


TUPLES = {
    "a tuple of Nones under a condition": ("""
        def f(image):
            found, corners = detect(image)
            if not found:
                return None, None, None
            return corners, corners, corners
        """, "returns `(None, None, None)` where `not found`"),
    "a None beside an array": ("""
        def f(x):
            if x.size == 0:
                return x, None
            return x, x
        """, "returns `(x, None)` where `x.size == 0`"),
}


@pytest.mark.parametrize("name", sorted(TUPLES))
def test_where_a_part_of_the_answer_is_none_is_read(name):
    source, words = TUPLES[name]
    assert words in none_returned(read_code(textwrap.dedent(source)), "f", in_tuple=True)
    assert none_returned(read_code(textwrap.dedent(SILENT["always returns"])), "f", in_tuple=True) == ""


def test_a_pose_of_nones_without_a_board_is_told_where_in_grading(tmp_path):
    source = """
        def estimate_pose(image, pattern_size, square_size, K, dist=None):
            grey = cv2.cvtColor(image, cv2.COLOR_BGR2GRAY) if image.ndim == 3 else image
            found, corners = cv2.findChessboardCorners(grey, tuple(pattern_size))
            if not found:
                return None, None, None
            objp = _object_points(pattern_size, square_size)
            _, rvec, tvec = cv2.solvePnP(objp, corners, np.asarray(K, float), dist)
            reprojected, _ = cv2.projectPoints(objp, rvec, tvec, np.asarray(K, float), dist)
            return rvec.ravel(), tvec.ravel(), reprojected.reshape(-1, 2)
        """
    result = grade(mutant(tmp_path, "lab10_camera2", source), ["lab10.ex6"], pictures="none")
    messages = [c.message for c in check_results(result, "lab10.ex6") if not c.passed]
    assert any("returned None" in m and "your `estimate_pose` returns `(None, None, None)` where `not found`"
               in m for m in messages), messages
