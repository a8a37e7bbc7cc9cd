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
