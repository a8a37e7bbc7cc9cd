"""Lists of things to check, each item held to the student's code (autograder.engine.claims.checklist).

"Check that A, and that B" tells a student whose code does A to look at A: wrong about them (issue 35:
no hint contradicts the code). Each item carries the predicate of the code that does it; an item the
code does is left out, and a list with nothing left says ``none_left``.
"""

from __future__ import annotations

import ast
import textwrap

import pytest

from autograder.engine import claims
from autograder.engine.hints import calls, expr, read_code

LINES = claims.checklist(
    "your code divides the lines: ",
    ("each line is divided by sqrt(a^2 + b^2) of its own first two entries", calls("np.hypot")
     | expr("np.sqrt(_[:, 0] ** 2 + _[:, 1] ** 2)")),
    ("the divided lines are returned", expr("_ / _[:, None]")),
    none_left="the error is elsewhere")


def said(source: str) -> str:
    return claims.GUARDED[LINES].told(read_code(textwrap.dedent(source)), ["lines_of"])


def test_an_item_the_code_does_is_not_said():
    text = said("""
        def lines_of(F, pts):
            lines = pts @ F.T
            return lines / np.abs(lines[:, :2]).sum(axis=1)[:, None]
        """)
    assert text == "your code divides the lines: check that each line is divided by sqrt(a^2 + b^2) of its own " \
                   "first two entries"


def test_every_item_is_said_to_code_doing_none_of_them():
    text = said("""
        def lines_of(F, pts):
            return pts @ F.T
        """)
    assert text == LINES
    assert "and that the divided lines are returned" in text


def test_code_doing_every_item_is_told_the_error_is_elsewhere():
    text = said("""
        def lines_of(F, pts):
            lines = pts @ F.T
            return lines / np.hypot(lines[:, 0], lines[:, 1])[:, None]
        """)
    assert text == "your code divides the lines: the error is elsewhere"


def test_an_item_in_a_helper_the_function_calls_counts():
    text = said("""
        def _norm(l):
            return np.hypot(l[:, 0], l[:, 1])

        def lines_of(F, pts):
            lines = pts @ F.T
            return lines * _norm(lines)[:, None]
        """)
    assert text == "your code divides the lines: check that the divided lines are returned"


def test_without_code_to_read_the_whole_list_is_said():
    assert claims.GUARDED[LINES].told(read_code(""), ["lines_of"]) == LINES


def test_an_item_without_the_code_that_does_it_is_refused():
    with pytest.raises(ValueError):
        claims.checklist("lead: ", ("the lines are returned", None))
    with pytest.raises(ValueError):
        claims.checklist("lead: ")


def test_a_checklist_inside_a_longer_message_is_replaced_there():
    class Trial:   # a check's trial without a submission to read: the text as it is
        sandbox, check = None, None
    assert claims.said(Trial(), f"The lines are off. {LINES}.") == f"The lines are off. {LINES}."


POINTED = claims.checklist(
    "your code divides the lines: ",
    ("the divided lines are returned", expr("_ / _[:, None]")),
    none_left=claims.look_at(("which lines the norm is taken of", calls("np.hypot")),
                             ("the order of the rows", calls("np.argsort")), otherwise="nothing else is read"))


def pointed(source: str) -> str:
    return claims.GUARDED[POINTED].told(read_code(textwrap.dedent(source)), ["lines_of"])


def test_a_pointer_to_a_step_the_code_does_is_not_said():
    text = pointed("""
        def lines_of(F, pts):
            lines = pts @ F.T
            return lines / np.hypot(lines[:, 0], lines[:, 1])[:, None]
        """)
    assert text == "your code divides the lines: look at the order of the rows"
    text = pointed("""
        def lines_of(F, pts):
            lines = (pts @ F.T)[np.argsort(pts[:, 0])]
            return lines / np.hypot(lines[:, 0], lines[:, 1])[:, None]
        """)
    assert text == "your code divides the lines: nothing else is read"


def test_pointers_are_said_only_when_no_item_is_left():
    text = pointed("""
        def lines_of(F, pts):
            return pts @ F.T
        """)
    assert text == "your code divides the lines: check that the divided lines are returned"


def test_a_pointer_without_the_code_that_does_its_step_is_refused():
    with pytest.raises(ValueError):
        claims.look_at(("the rows", None))


def test_nothing_left_drops_the_separator_written_before_it():
    assert claims._replaced("your code calls X; S", "S", "") == "your code calls X."
    assert claims._replaced(" (your code calls X: S).", "S", "") == " (your code calls X)."
    assert claims._replaced("Message. S", "S", "") == "Message."
    assert claims._replaced("a: S and more", "S", "x") == "a: x and more"


def test_wherever_written_leans_towards_done_where_nothing_is_written():
    def reversed_order(function):
        calls_ = [n for n in ast.walk(function) if isinstance(n, ast.Call) and getattr(n.func, "attr", "") == "cross"]
        return None if not calls_ else not any(
            isinstance(c.args[0], ast.Name) and c.args[0].id == "e1" for c in calls_)
    done = claims.wherever_written("crosses in order", reversed_order)
    code = read_code(textwrap.dedent("""
        def helper(x):
            return x

        def axes(e1, z):
            return np.cross(e1, z)
        """))
    assert not done.holds(code.reachable(["axes", "helper"]))   # a helper without the step does not hide it
    assert done.holds(code.reachable(["helper"]))
